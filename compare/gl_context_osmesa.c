/* The OSMesa back end of gl_context.h: Mesa's software context (llvmpipe on Debian 12), no
 * display needed. */
#include "gl_context.h"

#include <stdio.h>
#include <stdlib.h>

#include <GL/osmesa.h>

struct RfGlContext {
    OSMesaContext ctx;
    unsigned char surface[4]; /* 1 x 1 RGBA: OSMesa needs a buffer; we draw into FBOs */
};

RfStatus rf_gl_context_create(RfGlContext **out, char *err, size_t errsz)
{
    const int attribs[] = {OSMESA_FORMAT, OSMESA_RGBA, OSMESA_DEPTH_BITS, 0,
                           OSMESA_PROFILE, OSMESA_CORE_PROFILE,
                           OSMESA_CONTEXT_MAJOR_VERSION, 4, OSMESA_CONTEXT_MINOR_VERSION, 5, 0};
    RfGlContext *c = calloc(1, sizeof *c);
    *out = NULL;
    if (!c) {
        snprintf(err, errsz, "out of memory");
        return RF_ERR_NOMEM;
    }
    c->ctx = OSMesaCreateContextAttribs(attribs, NULL);
    if (!c->ctx) {
        snprintf(err, errsz, "OSMesa: cannot create an OpenGL 4.5 core context");
        free(c);
        return RF_ERR_DOMAIN;
    }
    if (!OSMesaMakeCurrent(c->ctx, c->surface, GL_UNSIGNED_BYTE, 1, 1)) {
        snprintf(err, errsz, "OSMesa: cannot make the context current");
        OSMesaDestroyContext(c->ctx);
        free(c);
        return RF_ERR_DOMAIN;
    }
    *out = c;
    return RF_OK;
}

RfGlProc rf_gl_context_proc(void *ctx, const char *name)
{
    (void)ctx;
    return (RfGlProc)OSMesaGetProcAddress(name);
}

void rf_gl_context_destroy(RfGlContext *c)
{
    if (!c)
        return;
    OSMesaMakeCurrent(NULL, NULL, 0, 0, 0);
    OSMesaDestroyContext(c->ctx);
    free(c);
}

const char *rf_gl_context_backend(void)
{
    return "osmesa";
}
