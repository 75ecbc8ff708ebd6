/* gl_context.h: the run-time choice between the back ends (gl_backend.h). */
#include "gl_context.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "gl_backend.h"

struct RfGlContext {
    const RfGlBackendOps *ops;
    void *impl;
};

int rf_gl_backend_parse(const char *name)
{
    return strcmp(name, "auto") == 0 ? RF_GL_AUTO : strcmp(name, "osmesa") == 0 ? RF_GL_OSMESA
                                                  : strcmp(name, "egl") == 0    ? RF_GL_EGL
                                                                                : -1;
}

RfStatus rf_gl_context_create(RfGlBackend backend, RfGlContext **out, char *err, size_t errsz)
{
    const RfGlBackendOps *order[2] = {&rf_gl_osmesa_ops, &rf_gl_egl_ops};
    int first = backend == RF_GL_EGL ? 1 : 0, last = backend == RF_GL_OSMESA ? 0 : 1;
    char why[2][256] = {"", ""};
    *out = NULL;
    for (int i = first; i <= last; i++) {
        void *impl = order[i]->create(why[i], sizeof why[i]);
        if (!impl)
            continue;
        RfGlContext *c = malloc(sizeof *c);
        if (!c) {
            order[i]->destroy(impl);
            snprintf(err, errsz, "out of memory");
            return RF_ERR_NOMEM;
        }
        c->ops = order[i];
        c->impl = impl;
        *out = c;
        return RF_OK;
    }
    if (backend == RF_GL_AUTO)
        snprintf(err, errsz, "no OpenGL 4.5 core context: %s; %s", why[0], why[1]);
    else
        snprintf(err, errsz, "%s", why[first]);
    return RF_ERR_DOMAIN;
}

RfGlProc rf_gl_context_proc(void *ctx, const char *name)
{
    RfGlContext *c = ctx;
    return c->ops->proc(c->impl, name);
}

void rf_gl_context_destroy(RfGlContext *c)
{
    if (!c)
        return;
    c->ops->destroy(c->impl);
    free(c);
}

const char *rf_gl_context_backend(const RfGlContext *c) { return c->ops->name; }
