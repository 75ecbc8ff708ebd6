/* refray: what the scene exporters share (internal; scene_export.h is the interface): the text
 * buffers, the notes, numbers that read back as the same double, the camera window and basis,
 * and the classification of a material into what the targets know. */
#ifndef RF_SCENE_EXPORT_INTERNAL_H
#define RF_SCENE_EXPORT_INTERNAL_H

#include "refray/scene.h"
#include "refray/scene_export.h"

#define RF_EX_RING 32
#define RF_EX_SLOT 160

typedef struct {
    const RfScene *s; /* the scene with its instances expanded */
    const RfExportOptions *o;
    RfExport *ex;
    RfExportFile *out; /* the file being written */
    int width, height, depth, samples;
    int filtered;     /* shadows of transmitting objects filtered (RF_SHADOWS_FILTERED), else opaque */
    RfWindow win;     /* the image window at distance win.d for width x height */
    RfVec3 u, v, w;   /* the §3.4 camera basis: right, up, backward (w = normalise(eye - target)) */
    char ring[RF_EX_RING][RF_EX_SLOT];
    int ring_next;
} RfExCtx;

/* What a material does, in the terms the targets know. */
typedef struct {
    int diffuse;   /* kd > 0 */
    int highlight; /* rf_material_has_highlight */
    int mirror;    /* kr > 0 */
    int transmits; /* kt > 0 */
    int fresnel;   /* RF_MAT_FRESNEL with kr or kt */
    int ambient;   /* ka * the scene's ambient light > 0 */
    int emits;     /* emission > 0 */
    int glossy;    /* gloss > 0 with kr or kt */
} RfExMat;

RfExMat rf__ex_classify(const RfScene *s, const RfMaterial *m);

/* Appends to the current file (a failed allocation sets ex->failed). */
void rf__ex_printf(RfExCtx *c, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;
/* Starts another file; path is copied. The current file becomes it. */
RfExportFile *rf__ex_file(RfExCtx *c, const char *path);
/* A note "source:line:col: fmt" (the line and column left out when loc has none); problem 0: for
 * information; 1: something the target cannot represent exactly (--lossy writes the nearest
 * thing); 2: something that cannot be written at all. */
void rf__ex_note(RfExCtx *c, RfSrcLoc loc, int problem, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 4, 5)))
#endif
    ;

/* The shortest of %.15g, %.16g, %.17g that reads back as x, in a slot of the context's ring:
 * valid for the next RF_EX_RING - 1 calls of rf__ex_num, rf__ex_vec, rf__ex_rgb (one slot each),
 * so one printf may take up to RF_EX_RING of them. */
const char *rf__ex_num(RfExCtx *c, double x);
/* Three numbers joined by sep ("x, y, z" with ", "). */
const char *rf__ex_vec(RfExCtx *c, RfVec3 v, const char *sep);
const char *rf__ex_rgb(RfExCtx *c, RfRgb v, const char *sep);

/* The header comment's lines that every target shares (the source, the conventions of refray
 * it is read with), each line prefixed with lead ("# ", "// "). */
void rf__ex_common_header(RfExCtx *c, const char *lead);
/* The notes every target shares: ambient light, emission, glossy rays, filtered shadows and
 * lights without falloff or with a spot exponent (but for POV-Ray), area lights where the target
 * has none (area_ok 0), a thin lens where it has none (lens_ok 0). */
void rf__ex_common_checks(RfExCtx *c, int area_ok, int lens_ok);

/* A note when the camera's near plane (hither) may cut the scene: POV-Ray and pbrt have none. */
void rf__ex_check_hither(RfExCtx *c);

/* What primitive p of the flattened scene writes: p itself (*placement NULL), or for a quadric
 * under a non-similarity transform (rf_scene_flatten's RF_FLATTEN_PLACED_QUADRICS: an instance
 * of a one-primitive object) that primitive in its object's space, with *placement the instance
 * that places it (to_world, normal_to_world). NULL for nothing to write on its own: a primitive
 * inside an object (its instance writes it), an instance of anything else. */
const RfPrimitive *rf__ex_world_prim(const RfScene *s, const RfPrimitive *p, const RfInstance **placement);

/* Which materials the world's primitives use, per material: bit 1 by a one-sided primitive, bit 2
 * by a two-sided one (every one with --two-sided); malloc'd, NULL (ex->failed set) without
 * memory. */
unsigned char *rf__ex_used_materials(RfExCtx *c);

/* One note for the world's one-sided primitives but spheres (none with --two-sided): how the
 * target shows their back (`back`, e.g. "shows it black"). */
void rf__ex_note_one_sided(RfExCtx *c, const char *back);

/* A unit vector perpendicular to n (unit). */
RfVec3 rf__ex_perpendicular(RfVec3 n);

/* The writers: each writes c->ex->files[0] (and the files beside it). */
void rf__export_mitsuba(RfExCtx *c);
void rf__export_pbrt(RfExCtx *c);
void rf__export_pov(RfExCtx *c);

#endif
