/* refray comparator: the headless GL context, apart from the drawing code (DESIGN.md "Headless
 * GL"). raster.c only sees this interface and loads every GL function through
 * rf_gl_context_proc. Two back ends, chosen at run time: OSMesa (Mesa's off-screen library;
 * Mesa 25.1 removed it) and EGL on Mesa's surfaceless platform (no display, no window system).
 * On Debian 12 both run llvmpipe and draw the same images bit for bit (tests/test_compare.c). */
#ifndef RF_GL_CONTEXT_H
#define RF_GL_CONTEXT_H

#include <stddef.h>

#include "refray/status.h"

typedef void (*RfGlProc)(void);
typedef struct RfGlContext RfGlContext;

/* RF_GL_AUTO: OSMesa when it gives a context, else EGL. */
typedef enum { RF_GL_AUTO, RF_GL_OSMESA, RF_GL_EGL } RfGlBackend;

/* "auto", "osmesa", "egl" -> the back end, or -1. */
int rf_gl_backend_parse(const char *name);

/* An OpenGL 4.5 core context of that back end made current on the calling thread; drawing goes
 * into framebuffer objects the caller creates (there is no window surface). err: one line on
 * failure (with AUTO: both back ends' reasons). */
RfStatus rf_gl_context_create(RfGlBackend backend, RfGlContext **out, char *err, size_t errsz);
/* A GL entry point by name ("glDrawArrays"), NULL when missing; ctx is the RfGlContext. */
RfGlProc rf_gl_context_proc(void *ctx, const char *name);
void rf_gl_context_destroy(RfGlContext *ctx);
/* "osmesa" or "egl" (for reports and EXR headers). */
const char *rf_gl_context_backend(const RfGlContext *ctx);

#endif
