/* refray: the scene model. Every renderer (tracer, OSMesa rasterizer, viewer) reads this one
 * in-memory scene, so a difference between their images is never a difference in parsing
 * (DESIGN.md "One scene loader feeds every renderer"). The readers live in scene_io.h.
 *
 * Conventions: right-handed coordinates; colours are linear RGB (RfRgb); angles are stored in degrees as written in the file; every array is count + pointer
 * and owned by the scene (rf_scene_free releases all of it). docs/scene-format.md describes
 * the file formats and how NFF maps onto this model. */
#ifndef REFRAY_SCENE_H
#define REFRAY_SCENE_H

#include <stddef.h>

#include "refray/intersect.h" /* RfSphere, RfPlane, RfCone: primitives pass straight to §3.5 */
#include "refray/rgb.h"
#include "refray/shading.h"   /* RfFalloff */
#include "refray/status.h"
#include "refray/vec.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Where a statement starts in its file (1-based line and byte column), for later messages. */
typedef struct { int line, col; } RfSrcLoc;

/* ---- camera (§3.4) ---------------------------------------------------------------------- */

/* How a field of view is measured (NFF.md: NFF's `angle` has two readings).
 * EDGES: the angle spans the outer edges of the image, half-height = d tan(fov/2)
 *   (refray's format, SCENES.md, the SPD's own POV-Ray converter).
 * PIXEL_CENTRES: the angle spans the centres of the outermost pixel rows, so
 *   half-height = d tan(fov/2) * H / (H - 1) (the NFF text; refray's default for NFF). */
typedef enum { RF_FOV_EDGES, RF_FOV_PIXEL_CENTRES } RfFovReading;

typedef struct {
    RfVec3 eye, target, up; /* up need not be unit or perpendicular to target - eye */
    double d;               /* distance from the eye to the image plane (§3.4) */
    int has_window;         /* 1: l, r, b, t below give the image window on the plane at d;
                               0: fov and fov_reading give it */
    double l, r, b, t;
    double fov;             /* full vertical field of view in degrees, 0 < fov < 180 */
    RfFovReading fov_reading;
    double hither;          /* near distance along the ray: nothing closer is visible */
    RfSrcLoc loc, target_loc, up_loc;
} RfSceneCamera;

/* The image window l < r, b < t on the plane at distance d for a W x H image, whichever way
 * the camera was given: the one place that applies the field-of-view reading. Square pixels:
 * with a field of view, r = -l = t * W / H. */
typedef struct { double l, r, b, t, d; } RfWindow;
RfWindow rf_scene_camera_window(const RfSceneCamera *cam, int width, int height);

/* ---- render settings -------------------------------------------------------------------- */

typedef struct {
    int width, height;
    int max_depth;           /* the primary ray is depth 1; no ray deeper than this is traced */
    double min_contribution; /* a secondary ray whose weight falls below this is not traced */
    int samples;             /* samples per pixel */
    RfRgb background;        /* radiance of rays that miss everything */
    RfRgb ambient;           /* ambient light: the ambient term is ka * ambient */
} RfRenderSettings;

/* ---- materials -------------------------------------------------------------------------- */

enum {
    RF_MAT_FRESNEL = 1u << 0, /* kr, kt are scaled by F and 1 - F of the exact unpolarised
                                 dielectric Fresnel term with ior (TIR: F = 1) */
    RF_MAT_SMOOTH = 1u << 1   /* interpolate vertex normals where a primitive has them;
                                 without this flag every primitive is shaded flat */
};

#define RF_NAME_MAX 48

typedef struct {
    char name[RF_NAME_MAX];
    RfRgb ka, kd, ks;   /* Phong ambient, diffuse, specular coefficients per channel */
    double shininess;   /* Phong exponent n */
    RfRgb kr, kt;       /* weights of the mirror and the refracted ray */
    double ior;         /* index of refraction inside the object (outside: 1) */
    RfRgb emission;     /* radiance emitted by the surface itself */
    unsigned flags;     /* RF_MAT_* */
    RfSrcLoc loc;
} RfMaterial;

/* A black, non-reflecting, non-transmitting material with ior 1, smooth: the base every
 * reader fills in. */
RfMaterial rf_material_default(void);

/* ---- lights (§3.7) ---------------------------------------------------------------------- */

typedef enum { RF_LIGHT_POINT, RF_LIGHT_DIRECTIONAL, RF_LIGHT_SPOT, RF_LIGHT_KIND_COUNT } RfLightKind;

typedef struct {
    RfLightKind kind;
    RfFalloff falloff;   /* point and spot lights; a directional light has none */
    RfVec3 position;     /* point, spot */
    RfVec3 direction;    /* unit; directional: the direction the light travels;
                            spot: the axis, pointing away from the light */
    RfRgb intensity;
    double spot_exponent; /* spot: intensity * cos(angle to the axis)^exponent ... */
    double spot_cutoff;   /* ... inside this half-angle in degrees, 0 outside (0 < cutoff <= 90) */
    RfSrcLoc loc;
} RfLight;

/* ---- primitives ------------------------------------------------------------------------- */

typedef enum {
    RF_PRIM_SPHERE,
    RF_PRIM_PLANE,    /* infinite plane through point with normal */
    RF_PRIM_TRIANGLE, /* 3 vertices in the shared vertex array */
    RF_PRIM_POLYGON,  /* n >= 3 coplanar vertices in the shared vertex array */
    RF_PRIM_CONE,     /* open cone frustum or cylinder (no end caps) */
    RF_PRIM_TYPE_COUNT
} RfPrimType;

enum {
    RF_PRIM_TWO_SIDED = 1u << 0,      /* visible from both sides; otherwise only from the front:
                                         the counter-clockwise side of a polygon, the outside
                                         of a sphere or cone (the inside with RF_PRIM_INSIDE) */
    RF_PRIM_INSIDE = 1u << 1,         /* NFF negative radii: only the inside is visible */
    RF_PRIM_VERTEX_NORMALS = 1u << 2, /* triangle/polygon: normals[nfirst ..] per vertex */
    RF_PRIM_NONCONVEX = 1u << 3       /* polygon that is not convex (set by the scene, e.g. the
                                         SPD gears): intersect it with a general point test */
};

typedef struct {
    RfPrimType type;
    unsigned flags; /* RF_PRIM_* */
    int material;   /* index into RfScene.materials */
    RfSrcLoc loc;
    union {
        RfSphere sphere;                                  /* radius > 0 */
        RfPlane plane;                                    /* <x, normal> = offset, normal unit */
        struct { size_t first, nfirst; int count; } poly; /* triangle, polygon */
        RfCone cone;                                      /* radii >= 0 */
    } u;
} RfPrimitive;

/* ---- the scene -------------------------------------------------------------------------- */

typedef enum { RF_FORMAT_NONE, RF_FORMAT_NFF, RF_FORMAT_RF } RfSceneFormat;

typedef struct {
    RfSceneFormat format;
    int has_camera;
    RfSceneCamera camera;
    RfRenderSettings render;

    RfMaterial *materials;
    size_t material_count;
    RfLight *lights;
    size_t light_count;
    RfPrimitive *prims;
    size_t prim_count;
    RfVec3 *vertices; /* shared by every triangle and polygon (offset + count) */
    size_t vertex_count;
    RfVec3 *normals;  /* per-vertex normals (unit) of primitives with RF_PRIM_VERTEX_NORMALS */
    size_t normal_count;

    /* capacities of the arrays above: private to the rf_scene_add_* functions */
    size_t material_cap, light_cap, prim_cap, vertex_cap, normal_cap;
} RfScene;

/* An empty scene with default render settings (512 x 512, depth 8, threshold 0, 1 sample,
 * black background, no ambient light) and no camera. */
void rf_scene_init(RfScene *scene);
void rf_scene_free(RfScene *scene);

/* Builders shared by every reader. Each copies its argument and reports through a plain
 * message (no file position: the reader prefixes it). */
RfStatus rf_scene_add_material(RfScene *scene, const RfMaterial *m, int *index);
RfStatus rf_scene_add_light(RfScene *scene, const RfLight *light);
/* Appends n vertices (and n normals when normals != NULL, normalised here) and returns the
 * offsets for RfPrimitive.u.poly. */
RfStatus rf_scene_add_vertices(RfScene *scene, const RfVec3 *v, const RfVec3 *normals, int n,
                               size_t *first, size_t *nfirst);
/* Checks the primitive (rf_scene_check_primitive), normalises plane normals, sets
 * RF_PRIM_NONCONVEX, and appends it. A plane may come with any non-zero normal and the
 * matching offset: both are divided by |normal| here. On RF_ERR_DEGENERATE/DOMAIN msg says why. */
RfStatus rf_scene_add_primitive(RfScene *scene, const RfPrimitive *p, char *msg, size_t msgsz);

/* The checks of the model, one routine each, used by the readers and by rf_scene_validate:
 * finite values, sphere radius > 0, plane normal != 0, polygons with >= 3 vertices and a
 * non-zero area (not collinear), non-zero vertex normals, cones with base != apex and not
 * both radii 0, a valid material index. msg gets a plain message. */
RfStatus rf_scene_check_primitive(const RfScene *scene, const RfPrimitive *p, char *msg,
                                  size_t msgsz);
/* eye != target, up != 0 and not parallel to the view direction, 0 < fov < 180 or l < r,
 * b < t, d > 0, hither >= 0. *loc gets the statement to blame. */
RfStatus rf_scene_camera_check(const RfSceneCamera *cam, RfSrcLoc *loc, char *msg, size_t msgsz);
/* Whole-scene check for scenes built in code: camera, settings, every primitive and light.
 * err gets "source:line:col: message" (source may be NULL). */
RfStatus rf_scene_validate(const RfScene *scene, const char *source, char *err, size_t errsz);

/* ---- analysis (DESIGN.md "Skip what a scene does not need") ----------------------------- */

enum {
    RF_FEAT_REFLECTION = 1u << 0,     /* some material has kr > 0 */
    RF_FEAT_TRANSMISSION = 1u << 1,   /* some material has kt > 0 */
    RF_FEAT_FRESNEL = 1u << 2,        /* some reflecting/transmitting material uses Fresnel */
    RF_FEAT_SPECULAR = 1u << 3,       /* some material has a Phong highlight (ks > 0) */
    RF_FEAT_AMBIENT = 1u << 4,        /* ka * ambient is non-zero for some material */
    RF_FEAT_EMISSION = 1u << 5,       /* some material emits */
    RF_FEAT_VERTEX_NORMALS = 1u << 6, /* some primitive interpolates vertex normals */
    RF_FEAT_LIGHT_FALLOFF = 1u << 7,  /* some light falls off with distance */
    RF_FEAT_SPOT_LIGHTS = 1u << 8,
    RF_FEAT_AREA_LIGHTS = 1u << 9,    /* reserved: the model has no area lights yet */
    RF_FEAT_MOTION = 1u << 10,        /* reserved: the model has no motion yet */
    RF_FEAT_APERTURE = 1u << 11,      /* reserved: the model has no thin lens yet */
    RF_FEAT_COUNT = 12
};

/* Only materials used by some primitive count. */
unsigned rf_scene_features(const RfScene *scene);
/* "reflection", "transmission", ... for one RF_FEAT_* bit; NULL for others. */
const char *rf_feature_name(unsigned bit);
const char *rf_prim_type_name(RfPrimType type);
const char *rf_light_kind_name(RfLightKind kind);

/* Axis-aligned box of every bounded primitive (planes are unbounded and left out).
 * 0 when there is none. Cones get the box of their two end discs' bounding cubes. */
int rf_scene_bounds(const RfScene *scene, RfVec3 *lo, RfVec3 *hi);

#ifdef __cplusplus
}
#endif

#endif
