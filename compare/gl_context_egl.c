/* The EGL back end (gl_backend.h): Mesa's surfaceless platform (EGL_MESA_platform_surfaceless),
 * which needs no display or window system and, without a GPU, renders with llvmpipe like
 * OSMesa; the context is made current without a surface (EGL_KHR_surfaceless_context), and the
 * comparator draws into framebuffer objects. The successor of OSMesa, which Mesa 25.1 removed. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <EGL/egl.h>
#include <EGL/eglext.h>

#include "gl_backend.h"

typedef struct {
    EGLDisplay dpy;
    EGLContext ctx;
} Egl;

static int has_extension(const char *list, const char *name)
{
    size_t n = strlen(name);
    for (const char *p = list; p && (p = strstr(p, name)) != NULL; p += n)
        if ((p == list || p[-1] == ' ') && (p[n] == ' ' || p[n] == 0))
            return 1;
    return 0;
}

static void *egl_create(char *err, size_t errsz)
{
    const char *client = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    if (!has_extension(client, "EGL_MESA_platform_surfaceless")) {
        snprintf(err, errsz, "EGL: no EGL_MESA_platform_surfaceless (Mesa's EGL is needed: libegl-mesa0)");
        return NULL;
    }
    PFNEGLGETPLATFORMDISPLAYEXTPROC get_display =
        (PFNEGLGETPLATFORMDISPLAYEXTPROC)eglGetProcAddress("eglGetPlatformDisplayEXT");
    Egl *c = calloc(1, sizeof *c);
    EGLint major = 0, minor = 0, n = 0;
    EGLConfig cfg;
    static const EGLint cfg_attribs[] = {EGL_SURFACE_TYPE, EGL_PBUFFER_BIT, EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT,
                                         EGL_NONE};
    static const EGLint ctx_attribs[] = {EGL_CONTEXT_MAJOR_VERSION, 4, EGL_CONTEXT_MINOR_VERSION, 5,
                                         EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                         EGL_NONE};
    if (!c || !get_display) {
        snprintf(err, errsz, c ? "EGL: no eglGetPlatformDisplayEXT" : "EGL: out of memory");
        free(c);
        return NULL;
    }
    c->dpy = get_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, NULL);
    const char *step = NULL;
    if (c->dpy == EGL_NO_DISPLAY || !eglInitialize(c->dpy, &major, &minor))
        step = "cannot open the surfaceless display";
    else if (!has_extension(eglQueryString(c->dpy, EGL_EXTENSIONS), "EGL_KHR_surfaceless_context"))
        step = "no EGL_KHR_surfaceless_context";
    else if (!eglBindAPI(EGL_OPENGL_API))
        step = "no desktop OpenGL";
    else if (!eglChooseConfig(c->dpy, cfg_attribs, &cfg, 1, &n) || n < 1)
        step = "no OpenGL config";
    else if ((c->ctx = eglCreateContext(c->dpy, cfg, EGL_NO_CONTEXT, ctx_attribs)) == EGL_NO_CONTEXT)
        step = "cannot create an OpenGL 4.5 core context";
    else if (!eglMakeCurrent(c->dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, c->ctx))
        step = "cannot make the context current";
    if (step) {
        snprintf(err, errsz, "EGL (surfaceless): %s (error 0x%x)", step, (unsigned)eglGetError());
        if (c->ctx)
            eglDestroyContext(c->dpy, c->ctx);
        if (c->dpy != EGL_NO_DISPLAY)
            eglTerminate(c->dpy);
        free(c);
        return NULL;
    }
    return c;
}

static RfGlProc egl_proc(void *impl, const char *name)
{
    (void)impl;
    return (RfGlProc)eglGetProcAddress(name);
}

static void egl_destroy(void *impl)
{
    Egl *c = impl;
    eglMakeCurrent(c->dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    eglDestroyContext(c->dpy, c->ctx);
    eglTerminate(c->dpy);
    free(c);
}

const RfGlBackendOps rf_gl_egl_ops = {"egl", egl_create, egl_proc, egl_destroy};
