/* The back ends behind gl_context.h (gl_context.c dispatches): each makes a current OpenGL 4.5
 * core context, finds entry points, and tears it down. Internal to compare/. */
#ifndef RF_GL_BACKEND_H
#define RF_GL_BACKEND_H

#include "gl_context.h"

typedef struct {
    const char *name;
    void *(*create)(char *err, size_t errsz); /* NULL on failure, err set */
    RfGlProc (*proc)(void *impl, const char *name);
    void (*destroy)(void *impl);
} RfGlBackendOps;

extern const RfGlBackendOps rf_gl_osmesa_ops, rf_gl_egl_ops;

#endif
