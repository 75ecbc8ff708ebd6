/* refray comparator: the headless GL context, apart from the drawing code (DESIGN.md "Headless
 * GL"). raster.c only sees this interface and loads every GL function through
 * rf_gl_context_proc, so an EGL surfaceless back end (Mesa >= 25.1 has no OSMesa) is a second
 * implementation of these three functions, with no change to shaders or draw code. */
#ifndef RF_GL_CONTEXT_H
#define RF_GL_CONTEXT_H

#include <stddef.h>

#include "refray/status.h"

typedef void (*RfGlProc)(void);
typedef struct RfGlContext RfGlContext;

/* An OpenGL 4.5 core context made current on the calling thread; drawing goes into framebuffer
 * objects the caller creates (the context's own surface is 1 x 1). err: one line on failure. */
RfStatus rf_gl_context_create(RfGlContext **out, char *err, size_t errsz);
/* A GL entry point by name ("glDrawArrays"), NULL when missing. */
RfGlProc rf_gl_context_proc(void *ctx, const char *name);
void rf_gl_context_destroy(RfGlContext *ctx);
/* "osmesa" (for reports and EXR headers). */
const char *rf_gl_context_backend(void);

#endif
