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
#include "refray/mat.h"       /* RfMat4: instance transforms (§4.8) */
#include "refray/rgb.h"
#include "refray/sampling.h" /* RfSampler, RfFilter */
#include "refray/shading.h"   /* RfFalloff */
#include "refray/status.h"
#include "refray/transform.h" /* RfTransformStep: keyframes of motion */
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
    double aperture;        /* §3.10 thin lens: aperture radius (0: pinhole) ... */
    double focus;           /* ... and the distance of the plane in focus along the view axis */
    double hither;          /* near plane at this distance along the view axis -w: nothing
                               nearer is seen by primary rays (OpenGL's near plane) */
    RfSrcLoc loc, target_loc, up_loc;
} RfSceneCamera;

/* The image window l < r, b < t on the plane at distance d for a W x H image, whichever way
 * the camera was given: the one place that applies the field-of-view reading. Square pixels:
 * with a field of view, r = -l = t * W / H. */
typedef struct { double l, r, b, t, d; } RfWindow;
RfWindow rf_scene_camera_window(const RfSceneCamera *cam, int width, int height);

/* ---- render settings -------------------------------------------------------------------- */

/* Shadow rays and transmitting surfaces (`shadows` in .rf, refray render --shadows). OPAQUE:
 * every surface between a point and a light blocks it. FILTERED: as POV-Ray's shadow rays, the
 * light goes straight on through every surface it crosses (no refraction, no Fresnel),
 * multiplied per channel by that surface's kt at each crossing (a sphere: twice); a surface
 * with kt = 0 blocks it. */
typedef enum { RF_SHADOWS_OPAQUE = 0, RF_SHADOWS_FILTERED = 1 } RfShadowMode;
/* "opaque", "filtered"; rf_shadow_mode_parse returns -1 for an unknown name. */
const char *rf_shadow_mode_name(RfShadowMode m);
int rf_shadow_mode_parse(const char *name);

typedef struct {
    int width, height;
    int max_depth;           /* the primary ray is depth 1; no ray deeper than this is traced */
    double min_contribution; /* a secondary ray whose weight falls below this is not traced */
    int samples;             /* samples per pixel (1: the pixel centre) */
    RfRgb background;        /* radiance of rays that miss everything */
    RfRgb ambient;           /* ambient light: the ambient term is ka * ambient */
    /* §3.9/§3.10 sampling: the pattern of every sampled dimension (pixel position, lens, time,
     * area lights, glossy rays), the reconstruction filter, adaptive supersampling */
    RfSampler sampler;
    RfFilter filter;
    int adaptive;              /* 1: §3.9 adaptive supersampling instead of `samples` */
    double adaptive_threshold; /* subdivide where neighbouring values differ by more (max channel) */
    int adaptive_depth;        /* at most this many subdivisions (4^depth samples a pixel) */
    double shutter_open, shutter_close; /* §3.10 the time interval of every sample path */
    RfShadowMode shadows;      /* what a shadow ray does at a transmitting surface */
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
    double gloss;       /* §3.10 glossy reflection and transmission: mirror and refracted rays
                           are perturbed within the lobe cos^gloss around the ideal direction
                           (0: ideal, no perturbation) */
    unsigned flags;     /* RF_MAT_* */
    RfSrcLoc loc;
} RfMaterial;

/* Whether the §3.6.2 highlight ks (r.v)^n of m can add anything: some ks > 0 (or an exponent
 * beyond 1e15, where (r.v)^n may overflow). Renderers skip the power where it cannot. */
int rf_material_has_highlight(const RfMaterial *m);

/* A black, non-reflecting, non-transmitting material with ior 1, smooth: the base every
 * reader fills in. */
RfMaterial rf_material_default(void);

/* ---- lights (§3.7) ---------------------------------------------------------------------- */

/* Area lights (§3.10) are seen only through their light: camera and secondary rays pass them
 * (add an emitting surface to see one). Units: a point light of intensity I gives I / d^2 at
 * distance d; an area light has radiance Le, and an element dA of it seen under the angle
 * theta_l from its normal acts as a point light of intensity Le cos(theta_l) dA (so a sphere
 * light of radius r acts from afar as a point light of intensity Le pi r^2). */
typedef enum {
    RF_LIGHT_POINT,
    RF_LIGHT_DIRECTIONAL,
    RF_LIGHT_SPOT,
    RF_LIGHT_RECT,   /* parallelogram position + a edge1 + b edge2, a, b in [0,1] */
    RF_LIGHT_DISC,   /* disc around position with normal direction and radius */
    RF_LIGHT_SPHERE, /* sphere around position with radius, emitting outward */
    RF_LIGHT_KIND_COUNT
} RfLightKind;

typedef struct {
    RfLightKind kind;
    RfFalloff falloff;   /* point and spot lights; a directional light has none */
    RfVec3 position;     /* point, spot; rect: a corner; disc, sphere: the centre */
    RfVec3 direction;    /* unit; directional: the direction the light travels;
                            spot: the axis, pointing away from the light; disc: the normal of
                            its emitting side; rect: edge1 x edge2 normalised */
    RfRgb intensity;     /* point, spot, directional; area lights: the radiance Le */
    double spot_exponent; /* spot: intensity * cos(angle to the axis)^exponent ... */
    double spot_cutoff;   /* ... inside this half-angle in degrees, 0 outside (0 < cutoff <= 90) */
    RfVec3 edge1, edge2;  /* rect: the sides from the corner; the front is edge1 x edge2 */
    double radius;        /* disc, sphere */
    int two_sided;        /* rect, disc: emits from both sides */
    int samples;          /* area lights: shadow rays per shading point and camera sample */
    RfSrcLoc loc;
} RfLight;

/* An area light's kind (rect, disc, sphere)? */
int rf_light_is_area(RfLightKind kind);
/* Its area (the whole sphere for a sphere light). */
double rf_light_area(const RfLight *l);

/* ---- primitives ------------------------------------------------------------------------- */

typedef enum {
    RF_PRIM_SPHERE,
    RF_PRIM_PLANE,    /* infinite plane through point with normal */
    RF_PRIM_TRIANGLE, /* 3 vertices in the shared vertex array */
    RF_PRIM_POLYGON,  /* n >= 3 coplanar vertices in the shared vertex array */
    RF_PRIM_CONE,     /* open cone frustum or cylinder (no end caps) */
    RF_PRIM_INSTANCE, /* an object placed by a transform: RfScene.instances[u.instance] (§4.8) */
    RF_PRIM_TYPE_COUNT
} RfPrimType;

enum {
    RF_PRIM_TWO_SIDED = 1u << 0,      /* visible from both sides; otherwise only from the front:
                                         the counter-clockwise side of a polygon, the outside
                                         of a sphere or cone (the inside with RF_PRIM_INSIDE) */
    RF_PRIM_INSIDE = 1u << 1,         /* NFF negative radii: only the inside is visible */
    RF_PRIM_VERTEX_NORMALS = 1u << 2, /* triangle/polygon: normals[nfirst ..] per vertex */
    RF_PRIM_NONCONVEX = 1u << 3,      /* polygon that is not convex (set by the scene, e.g. the
                                         SPD gears): intersect it with a general point test */
    RF_PRIM_IN_OBJECT = 1u << 4       /* part of an object (RfSceneObject), not of the world:
                                         seen only through the instances of that object */
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
        size_t instance;                                  /* index into RfScene.instances */
    } u;
} RfPrimitive;

/* ---- the scene graph (§4.8) ------------------------------------------------------------- */

/* A named object (a mesh, or a group of primitives and instances): the primitives
 * prims[first .. first + count), each flagged RF_PRIM_IN_OBJECT. Objects are placed only by
 * instances; instances inside objects make the graph a DAG (one object in several groups). */
typedef struct {
    char name[RF_NAME_MAX];
    size_t first, count;
    RfSrcLoc loc;
} RfSceneObject;

/* One placement of an object. The tracer takes rays into object space with to_object and
 * normals back with normal_to_world = ((M^-1)^T of the linear part, §4.9). */
typedef struct {
    int object;             /* index into RfScene.objects */
    RfMat4 to_world;        /* M: object -> world (or -> the enclosing object); a moving
                               instance: M at its first keyframe */
    RfMat4 to_object;       /* M^-1 */
    RfMat3 normal_to_world; /* (M^-1)^T, linear part only */
    int motion;             /* index into RfScene.motions; -1: it does not move */
} RfInstance;

/* §3.10 motion blur: an instance whose transform changes over the shutter. Each keyframe lists
 * the same transform steps with other numbers; between two keyframes every number is
 * interpolated linearly and the steps composed again (so a rotation turns, it does not shrink);
 * before the first and after the last keyframe the transform holds. */
#define RF_MOTION_MAX_KEYS 16
#define RF_MOTION_MAX_STEPS 8
typedef struct {
    int key_count, step_count;
    double time[RF_MOTION_MAX_KEYS]; /* increasing */
    RfTransformStep steps[RF_MOTION_MAX_KEYS][RF_MOTION_MAX_STEPS];
} RfMotion;

/* The transform of a motion at a time (object -> world), M^-1 and (M^-1)^T;
 * RF_ERR_SINGULAR when it cannot be inverted there. */
RfStatus rf_motion_at(const RfMotion *m, double time, RfMat4 *to_world, RfMat4 *to_object, RfMat3 *normal);

/* ---- the scene -------------------------------------------------------------------------- */

typedef enum { RF_FORMAT_NONE, RF_FORMAT_NFF, RF_FORMAT_RF, RF_FORMAT_OBJ } RfSceneFormat;

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
    RfSceneObject *objects; /* the scene graph (§4.8): objects and their placements */
    size_t object_count;
    RfInstance *instances;
    size_t instance_count;
    RfMotion *motions;      /* the keyframes of moving instances */
    size_t motion_count;

    /* rf_hash_bytes (hash.h) over the bytes of every file rf_scene_load read (the scene, its
     * meshes and material libraries, decompressed, in the order read), from RF_HASH_INIT; it
     * names the scene in a render's EXR header, so tiles of different scenes are not merged */
    uint64_t source_hash;
    /* the path of every file rf_scene_load read for it, as the scene names them, in the order of
     * source_hash (meshes and material libraries as opened, the scene file last): what refray
     * render --deps lists for make */
    char **files;
    size_t file_count;

    /* capacities of the arrays above: private to the rf_scene_add_* functions */
    size_t material_cap, light_cap, prim_cap, vertex_cap, normal_cap, object_cap, instance_cap, motion_cap;
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
/* Appends an object with an empty primitive range starting at prim_count. */
RfStatus rf_scene_add_object(RfScene *scene, const char *name, RfSrcLoc loc, int *index);
/* Appends a placement of `object` by m and computes its inverse and normal matrix (§4.9).
 * RF_ERR_SINGULAR when m (or its linear part) cannot be inverted. object may be set later
 * (forward references); rf_scene_validate checks it. */
RfStatus rf_scene_add_instance(RfScene *scene, int object, RfMat4 m, size_t *index);
/* Makes instance `index` move by the keyframes of m (checked: 1 <= keys, increasing times,
 * the same steps in every keyframe, invertible at every keyframe); its to_world becomes the
 * first keyframe's. msg says what is wrong. */
RfStatus rf_scene_set_motion(RfScene *scene, size_t index, const RfMotion *m, char *msg, size_t msgsz);

/* The deepest nesting of instances (a chain of objects, each placing the next) a scene may
 * have: every tool that walks the graph recursively stays far from its stack's end. */
#define RF_SCENE_MAX_NESTING 64

/* The graph checks (scene_graph.c): every instance names an existing object, no object
 * contains itself through instances (a cycle), and no chain of objects is longer than
 * RF_SCENE_MAX_NESTING. On failure *loc is the instance statement to blame and msg says which
 * objects form the cycle, or where the chain gets too deep. */
RfStatus rf_scene_graph_check(const RfScene *scene, RfSrcLoc *loc, char *msg, size_t msgsz);
/* Triangles as stored (a convex polygon counts as count - 2, a non-convex one as 1) and as
 * rendered after instancing: the world's primitives with every instance expanded. */
typedef struct { size_t stored, rendered, instances_rendered; } RfTriangleCount;
RfTriangleCount rf_scene_triangle_count(const RfScene *scene);
/* Object-space box of an object's bounded primitives (instances inside it transformed);
 * 0 when it has none or an unbounded one (a plane). */
int rf_scene_object_bounds(const RfScene *scene, int object, RfVec3 *lo, RfVec3 *hi);
/* A copy of the scene without instances: every instance of a mesh replaced by transformed
 * triangles and polygons (vertex normals by the inverse transpose, §4.9; a mirroring transform
 * reverses the vertex order so the front stays the front), spheres and cones transformed when
 * the transform is a similarity. It renders like the instanced scene up to rounding, except
 * smooth shading under a non-uniform scale: the flat copy normalises the transformed vertex
 * normals before the interpolation, the tracer interpolates in object space and transforms
 * after. RF_ERR_DOMAIN (msg says why) for a sphere or cone under a non-similarity transform,
 * which has no primitive of its own (unless flags say RF_FLATTEN_PLACED_QUADRICS). */
RfStatus rf_scene_flatten(const RfScene *scene, unsigned flags, RfScene *out, char *msg, size_t msgsz);
/* rf_scene_flatten's flags. RF_FLATTEN_PLACED_QUADRICS: a sphere or cone under a non-similarity
 * transform (an ellipsoid, a sheared cone) stays in out as the one primitive of an object of its
 * own, placed by one instance with the composed matrix (the world's instances are then these
 * alone): for writers whose targets transform a quadric (POV-Ray's matrix, pbrt's
 * ConcatTransform) instead of an error. */
enum { RF_FLATTEN_PLACED_QUADRICS = 1u };

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
    RF_FEAT_SPECULAR = 1u << 3,       /* some material has a highlight (rf_material_has_highlight) */
    RF_FEAT_AMBIENT = 1u << 4,        /* ka * ambient is non-zero for some material */
    RF_FEAT_EMISSION = 1u << 5,       /* some material emits */
    RF_FEAT_VERTEX_NORMALS = 1u << 6, /* some primitive interpolates vertex normals */
    RF_FEAT_LIGHT_FALLOFF = 1u << 7,  /* some light falls off with distance */
    RF_FEAT_SPOT_LIGHTS = 1u << 8,
    RF_FEAT_AREA_LIGHTS = 1u << 9,    /* some light is a rect, disc or sphere (§3.10) */
    RF_FEAT_MOTION = 1u << 10,        /* some instance moves over the shutter (§3.10) */
    RF_FEAT_APERTURE = 1u << 11,      /* the camera has a thin lens, aperture > 0 (§3.10) */
    RF_FEAT_GLOSSY = 1u << 12,        /* some reflecting or transmitting material is glossy */
    RF_FEAT_COUNT = 13
};

/* Only materials used by some primitive count. */
unsigned rf_scene_features(const RfScene *scene);
/* "reflection", "transmission", ... for one RF_FEAT_* bit; NULL for others. */
const char *rf_feature_name(unsigned bit);
const char *rf_prim_type_name(RfPrimType type);
const char *rf_light_kind_name(RfLightKind kind);

/* Axis-aligned box of every bounded world primitive, instances by their transformed object
 * boxes (planes are unbounded and left out).
 * 0 when there is none. Cones get the box of their two end discs' bounding cubes. */
int rf_scene_bounds(const RfScene *scene, RfVec3 *lo, RfVec3 *hi);

#ifdef __cplusplus
}
#endif

#endif
