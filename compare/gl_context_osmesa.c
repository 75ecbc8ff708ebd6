/* The OSMesa back end (gl_backend.h): Mesa's software context (llvmpipe on Debian 12), no
 * display needed. */
#include <stdio.h>
#include <stdlib.h>

#include <GL/osmesa.h>

#include "gl_backend.h"

typedef struct {
    OSMesaContext ctx;
    unsigned char surface[4]; /* 1 x 1 RGBA: OSMesa needs a buffer; we draw into FBOs */
} Osmesa;

static void *osmesa_create(char *err, size_t errsz)
{
    const int attribs[] = {OSMESA_FORMAT, OSMESA_RGBA, OSMESA_DEPTH_BITS, 0,
                           OSMESA_PROFILE, OSMESA_CORE_PROFILE,
                           OSMESA_CONTEXT_MAJOR_VERSION, 4, OSMESA_CONTEXT_MINOR_VERSION, 5, 0};
    Osmesa *c = calloc(1, sizeof *c);
    if (!c) {
        snprintf(err, errsz, "OSMesa: out of memory");
        return NULL;
    }
    c->ctx = OSMesaCreateContextAttribs(attribs, NULL);
    if (!c->ctx) {
        snprintf(err, errsz, "OSMesa: cannot create an OpenGL 4.5 core context");
        free(c);
        return NULL;
    }
    if (!OSMesaMakeCurrent(c->ctx, c->surface, GL_UNSIGNED_BYTE, 1, 1)) {
        snprintf(err, errsz, "OSMesa: cannot make the context current");
        OSMesaDestroyContext(c->ctx);
        free(c);
        return NULL;
    }
    return c;
}

static RfGlProc osmesa_proc(void *impl, const char *name)
{
    (void)impl;
    return (RfGlProc)OSMesaGetProcAddress(name);
}

static void osmesa_destroy(void *impl)
{
    Osmesa *c = impl;
    OSMesaMakeCurrent(NULL, NULL, 0, 0, 0);
    OSMesaDestroyContext(c->ctx);
    free(c);
}

const RfGlBackendOps rf_gl_osmesa_ops = {"osmesa", osmesa_create, osmesa_proc, osmesa_destroy};
