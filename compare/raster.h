/* refray comparator: the OpenGL rasterization of a scene (issue 5). The same in-memory scene the
 * tracer reads, the same camera window and pixel centres, the tracer's --local shading (local
 * Phong, no shadows, reflection or refraction), into 32-bit float colour and depth buffers.
 * docs/compare.md describes the method and its accuracy. */
#ifndef RF_RASTER_H
#define RF_RASTER_H

#include <stddef.h>

#include "gl_context.h"
#include "refray/image.h"
#include "refray/scene.h"
#include "refray/status.h"

typedef enum {
    RF_SHADE_PHONG,   /* per pixel: the tracer's --local image */
    RF_SHADE_GOURAUD, /* polygons lit at their vertices, colours interpolated (teaching) */
    RF_SHADE_FLAT     /* polygons lit once, at the centroid with the face normal (teaching) */
} RfShadeMode;        /* spheres, cones and planes are always shaded per pixel (impostors) */

typedef struct {
    int width, height; /* 0: the scene's */
    RfShadeMode mode;
    int two_sided;     /* 1: every surface seen from both sides, its one-sided and inside-only flags
                          aside (the tracer's RfRenderOptions.two_sided, `--two-sided`) */
} RfRasterOptions;

/* Draws the scene with the current GL context, whose entry points come from proc(proc_ctx,
 * name). color gets RGB linear floats, depth (may be NULL) one channel of linear eye-space
 * depth: the distance of the visible point from the eye along the view axis (-w), +inf where
 * nothing is hit; row 0 at the top. err gets one line on failure. */
RfStatus rf_raster_render(const RfScene *scene, const RfRasterOptions *opt,
                          RfGlProc (*proc)(void *ctx, const char *name), void *proc_ctx,
                          RfImage *color, RfImage *depth, char *err, size_t errsz);

/* Triangulates polygon prim as the tracer does (a non-convex one by ear clipping,
 * rf_triangulate_polygon; a convex one as a fan) into out[3 k], the vertex indices within the
 * polygon; returns the triangle count (count - 2) or -1 when out of memory. Exposed for the
 * tests. */
int rf_raster_triangulate(const RfScene *scene, const RfPrimitive *prim, int *out);

#endif
