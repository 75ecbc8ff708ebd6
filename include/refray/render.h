/* refray: the Whitted-style ray tracer of §3.3-3.8 — primary rays through the §3.4 camera,
 * nearest hits through a BVH, Phong illumination per light with shadow rays, mirror reflection
 * and Snell refraction (with Fresnel where the material asks), to a depth limit and a
 * contribution threshold. Threads over tiles; the image does not depend on the thread count. */
#ifndef REFRAY_RENDER_H
#define REFRAY_RENDER_H

#include <stdint.h>

#include "refray/image.h"
#include "refray/numeric.h"
#include "refray/parallel.h"
#include "refray/scene.h"
#include "refray/status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* How the tracer finds hits. Every choice gives the same answers, bit for bit: these exist to
 * prove that (tests, `refray render --accel`) and to measure. */
typedef struct {
    int threads;     /* for building the BVH; 0: every core */
    int scalar;      /* 1: the scalar BVH kernels instead of AVX/SSE */
    int brute_force; /* 1: no BVH, every item tested against every ray (the reference) */
    /* Not a speed choice but a convention (RfRenderOptions.two_sided): 1 makes every primitive
     * visible from both sides, its RF_PRIM_TWO_SIDED and RF_PRIM_INSIDE flags aside. */
    int two_sided;
} RfTracerOptions;

RfTracerOptions rf_tracer_options_default(void);

/* `refray trace`: every step of one pixel's rays (RfTraceEvent, below RfSurfaceHit). */
typedef struct RfTraceEvent RfTraceEvent;
typedef void (*RfTraceFn)(void *ctx, const RfTraceEvent *e);

typedef struct {
    int width, height;   /* 0: the scene's */
    int max_depth;       /* 0: the scene's; the primary ray is depth 1 */
    double threshold;    /* < 0: the scene's (RfRenderSettings.min_contribution); a secondary ray
                            whose weight falls below it is not traced (POV-Ray's adc_bailout);
                            NaN or above 1: RF_ERR_DOMAIN */
    int samples;         /* per pixel, 0: the scene's. 1: the pixel centre; more: placed by the
                            sampler, weighted by the filter */
    int sampler;         /* RfSampler, -1: the scene's (default stratified) */
    int adaptive;        /* §3.9 adaptive supersampling: 1 on, 0 off, -1: the scene's */
    double adaptive_threshold; /* < 0: the scene's */
    int adaptive_depth;  /* < 0: the scene's */
    int filter;          /* RfFilterKind, -1: the scene's (default box) */
    double filter_radius; /* pixels; 0: the filter's default (or the scene's radius for its filter) */
    double aperture, focus; /* §3.10 thin lens; NaN: the scene camera's */
    int light_samples;   /* > 0: shadow rays per area light instead of each light's own */
    int preview;         /* 0 (a reference render): a sample whose radiance is NaN, Inf or negative,
                            or a pixel that overflows float, fails the render (RF_ERR_NUMERIC, the
                            first one described in RfRenderStats.invalid); 1: such samples become
                            black and are counted */
    int threads;         /* 0: every core */
    int local_only;      /* 1: primary rays and local Phong only (no shadows, reflection,
                            refraction): the comparator's matching mode */
    /* Conventions other renderers differ in, so that a cross-render can be exact. */
    int two_sided;       /* 1: every primitive is seen from both sides, as in POV-Ray and Mitsuba
                            (one-sided and inside-only primitives too; a back face is shaded with
                            the normal turned to the ray, as every hit is); 0: as the scene says */
    int shadows;         /* RfShadowMode; -1: the scene's (default RF_SHADOWS_OPAQUE) */
    uint64_t seed;       /* of the counter-based random numbers (jitter) */
    double fixed_offset; /* 0: the self-intersection policy (rf_hit_offset_origin); > 0 replaces it
                            by this absolute offset: a planted bug for the verifier only */
    RfTracerOptions accel; /* threads 0 there: the render's thread count */
    unsigned kernel;     /* 0: the kernel the scene needs; else the parts of a compiled kernel
                            (rf_kernel_parse: "general" has them all), which must include the
                            needed ones (RF_ERR_DOMAIN otherwise): the same image either way */
    RfProgressFn progress; /* called after each tile (may be NULL) */
    void *progress_ctx;

    /* Beyond one machine (issue 14). crop: the window rendered, [x0, x1) x [y0, y1) of the
     * image; all 0: the whole image. img is then the window's size, and each of its pixels is
     * the one of the whole image's render, bit for bit (the random numbers are keyed by the
     * pixel's place in the whole image; adaptive supersampling also takes the centres one pixel
     * around the window). */
    RfTile crop;
    /* Checkpoints: the (final) pass runs over tiles of RF_RENDER_TILE^2 pixels of the window,
     * row by row (rf_render_tile_count). tile_done (may be NULL) is called after each, from the
     * thread that rendered it (several at once: lock in it), with the image being rendered, whose
     * tile pixels are final. skip (may be NULL): per tile, 1 = done before: its pixels are copied
     * from resume_from (the window's size) instead of rendered. cancel (may be NULL): when it
     * becomes non-zero (a signal handler's flag), no new tile starts and rf_render returns
     * RF_ERR_INTERRUPTED with img freed; the tiles reported done stay valid. */
    void (*tile_done)(void *ctx, const RfImage *img, RfTile tile);
    void *tile_done_ctx;
    const unsigned char *skip;
    const RfImage *resume_from;
    const volatile int *cancel;
    /* refray trace: with a 1 x 1 crop, every step of that pixel's rays goes to trace (on one
     * thread); the image is the same as without (RF_ERR_DOMAIN for a larger window) */
    RfTraceFn trace;
    void *trace_ctx;
    /* Statistical image tests (refray diff --stat): when set, filled (allocated here, the
     * window's size, RGB) with each pixel's variance of its mean: the samples' variance over
     * their number, s^2 / n. Needs 2 or more samples, the box filter and no adaptive
     * supersampling (RF_ERR_DOMAIN otherwise). Stratified and Sobol samples vary less than
     * independent ones, so s^2 / n overstates their variance: a test with it errs on the side of
     * accepting. */
    RfImage *variance;
} RfRenderOptions;

/* The side of a render's tiles, and their number in a w x h window. */
#define RF_RENDER_TILE 16
int rf_render_tile_count(int width, int height);

RfRenderOptions rf_render_options_default(void);

typedef struct {
    uint64_t primary_rays, shadow_rays, secondary_rays;
    uint64_t invalid_samples; /* samples whose radiance was NaN or Inf: counted, replaced by 0 */
    uint64_t adaptive_pixels; /* §3.9 adaptive supersampling: the pixels subdivided */
    uint64_t background_tiles; /* tiles no camera ray of which can hit anything (a pinhole camera,
                                  rf_tracer_cone_empty): the background, no ray traced */
    /* the first invalid sample (lowest pixel index, then sample): its pixel, sample index (-1:
     * the pixel's mean overflows float), value, and path ("camera -> sphere #3 (material 'red')
     * -> mirror ray -> ..."), re-traced after the render */
    struct {
        int found, x, y, sample;
        double value[3];
        char path[512];
    } invalid;
    int width, height, samples, max_depth, threads;
    int sampler, adaptive;    /* what ran: RfSampler, adaptive supersampling on */
    RfFilter filter;
    unsigned features;   /* rf_scene_features of the scene */
    double build_seconds; /* preparing the tracer: items, BVH */
    double trace_seconds; /* the rays */
    size_t accel_bytes;  /* held by the tracer (rf_tracer_bytes) */
    unsigned kernel;     /* the parts of the kernel that ran (rf_kernel_name) */
    double busy_seconds; /* the threads' time in tiles, summed */
    double idle_share;   /* 1 - busy / (threads x trace time): the threads' waiting at the end */
} RfRenderStats;

/* The kernel a render of this scene with these options would run: the compiled one with the
 * fewest parts (shadow rays, secondary rays, Fresnel, highlights, ambient, emission, spot,
 * directional and falling-off lights, jittered samples) that has every part the scene needs. */
unsigned rf_render_kernel(const RfScene *scene, const RfRenderOptions *opt);
/* "general" followed by the parts left out, each after a '-' ("general-secondary-fresnel");
 * buf returned. Parts: shadow, secondary, fresnel, specular, ambient, emission, spot,
 * directional, falloff, jitter, area, lens, motion, glossy. */
const char *rf_kernel_name(unsigned parts, char *buf, size_t size);
/* The parts of a kernel name (rf_kernel_name's form); 0 for an unknown name or a set that no
 * compiled kernel has. */
unsigned rf_kernel_parse(const char *name);
/* Every part a kernel can have; the number of compiled kernels and the parts of kernel i. */
unsigned rf_kernel_all_parts(void);
int rf_kernel_count_compiled(void);
unsigned rf_kernel_compiled(int i);

/* The prepared scene: acceleration structure and per-primitive data. Immutable once built, so
 * any number of threads trace through it at once. */
typedef struct RfTracer RfTracer;

RfStatus rf_tracer_create(const RfScene *scene, RfTracer **out);
RfStatus rf_tracer_create_opts(const RfScene *scene, const RfTracerOptions *opt, RfTracer **out);
void rf_tracer_free(RfTracer *tracer);
/* Bytes held by the tracer: BVH nodes, triangle blocks, item tables. */
size_t rf_tracer_bytes(const RfTracer *tracer);
/* 1 when no ray from apex inside the cone {x : <n_k, x - apex> >= 0, k < count} can hit
 * anything (rf_bvh_cone_empty on the world's BVH); 0 when it may, or when some item is tested
 * for every ray (planes, moving instances, instances of unbounded objects) or every item is
 * (brute force). */
int rf_tracer_cone_empty(const RfTracer *tracer, RfVec3 apex, const RfVec3 *normals, int count);

/* The nearest hit along a ray (t in [t_min, t_max)); returns the primitive index or -1. Of
 * several primitives hit at the same t, the lowest primitive index wins (a convex polygon's fan
 * triangles in order), whatever the BVH. */
typedef struct {
    double t;
    int prim, material;
    RfVec3 point, normal;   /* geometric normal, unit, facing the side the ray came from */
    RfVec3 shading_normal;  /* interpolated (smooth materials) or = normal, same side */
    int front;              /* 1 when the ray hit the outward / counter-clockwise side */
    double scale;           /* the size of the numbers the point is made of: its rounding error is a
                               few ulps of it (numeric.h, rf_hit_offset_origin). Spheres, triangles
                               and planes: the point is put back on the surface, and this is the
                               largest |coordinate| of the sphere (centre + radius), the triangle's
                               vertices or the plane's point; cones and hits in instances: of the
                               hit point and the ray's origin, times RF_RAY_OFFSET_CONE/_INSTANCE */
} RfSurfaceHit;
int rf_tracer_intersect(const RfTracer *tracer, const RfRay *ray, double t_min, double t_max, RfSurfaceHit *hit);
/* rf_tracer_intersect for the rays of the lanes in active (bit l: rays[l] from t_min[l], to
 * infinity) in one query, the tree walked once for them all (rf_bvh_nearest4): bit l of the
 * result is set when ray l hits, with hit[l] bit for bit what rf_tracer_intersect gives it.
 * Rays without motion (the scene's first keyframe). */
unsigned rf_tracer_intersect4(const RfTracer *tracer, const RfRay rays[4], unsigned active, const double t_min[4],
                              RfSurfaceHit hit[4]);

/* `refray trace`: every step of one pixel's rays, reported by the render kernels themselves as
 * they render it (RfRenderOptions.trace), so the trace is the renderer's own arithmetic. */
typedef enum {
    RF_TRACE_SAMPLE,    /* a camera sample: its image position and primary ray */
    RF_TRACE_HIT,       /* the nearest hit of a ray (hit) */
    RF_TRACE_MISS,      /* a ray that meets nothing: color = the background */
    RF_TRACE_LIGHT,     /* one light (sample) at a hit: L, its intensity there, the shadow ray, the terms */
    RF_TRACE_SECONDARY, /* a mirror or refracted ray leaving a hit: Snell and Fresnel numbers, weight */
    RF_TRACE_RESULT,    /* the colour a ray returns: local = emission + ambient + the light terms */
    RF_TRACE_PIXEL      /* the pixel's value, as stored in the image */
} RfTraceKind;

struct RfTraceEvent {
    RfTraceKind kind;
    int depth;                /* the ray's depth (1: primary) */
    int sample, samples;      /* the camera sample k of n */
    double px, py;            /* SAMPLE: image position in pixel units (y down) */
    RfRay ray;                /* SAMPLE: the primary ray; SECONDARY: the new ray */
    const RfSurfaceHit *hit;  /* HIT (valid during the call) */
    int light, light_sample;  /* LIGHT: the light's index, the area light's sample (-1: none) */
    RfVec3 l;                 /* LIGHT: unit direction to the light */
    double distance, n_dot_l; /* LIGHT */
    int visible;              /* LIGHT: 1 lit; 0 in shadow; -1 the light is behind the surface */
    RfRgb transmittance;      /* LIGHT, filtered shadows: the factor the shadow ray's crossings
                                 put on I (1, 1, 1 when it crossed nothing) */
    RfRgb intensity, diffuse, specular; /* LIGHT: I at the point, kd I max(0, N.L), ks I max(0, R.V)^n */
    int refracted, tir, fresnel; /* SECONDARY: refracted (else mirror); total internal reflection; exact Fresnel */
    double eta_i, eta_t, cos_i, fr, ft; /* SECONDARY: §3.8.1 */
    RfRgb weight;             /* SECONDARY: the weight of the new ray's colour */
    RfRgb color, local;       /* RESULT, MISS, PIXEL: the colour; RESULT: its local part */
};
/* §3.10 motion blur: the moving instances' transforms at one time, made once per sample path
 * (one state per thread). The _at queries see moving instances where they are at the state's
 * time; without a state (NULL, and the functions without _at) at their first keyframe. */
typedef struct RfMotionState RfMotionState;
RfMotionState *rf_motion_state_new(const RfTracer *tracer);
void rf_motion_state_free(RfMotionState *ms);
void rf_motion_state_set(RfMotionState *ms, double time);
int rf_tracer_intersect_at(const RfTracer *tracer, const RfRay *ray, const RfMotionState *ms, double t_min, double t_max,
                           RfSurfaceHit *hit);
/* 1 when anything is hit at t in [t_min, t_max), seen from either side: a shadow ray's
 * occlusion query (it stops at the first hit). */
int rf_tracer_occluded(const RfTracer *tracer, const RfRay *ray, double t_min, double t_max);
/* The same answer, with a cache (POV-Ray's "shadow cache"): *last holds the primitive that
 * occluded the previous query (0: none; keep one per light and thread), which is tested first;
 * *last then becomes the occluder found, or 0 when nothing occludes. */
int rf_tracer_occluded_cached(const RfTracer *tracer, const RfRay *ray, double t_min, double t_max, uint64_t *last);
int rf_tracer_occluded_cached_at(const RfTracer *tracer, const RfRay *ray, const RfMotionState *ms, double t_min,
                                 double t_max, uint64_t *last);
/* Filtered shadows (RF_SHADOWS_FILTERED): the product, per channel, of the kt of every surface
 * the ray crosses at t in [t_min, t_max), each seen from either side, in the order met (a
 * sphere counts twice; two surfaces at exactly the same t once); (0, 0, 0) once the product is
 * 0 in every channel (a surface with kt = 0 blocks). *last as rf_tracer_occluded_cached, for
 * the primitives that block alone (kt = 0, outside instances). */
RfRgb rf_tracer_transmittance_at(const RfTracer *tracer, const RfRay *ray, const RfMotionState *ms, double t_min,
                                 double t_max, uint64_t *last);


/* The self-intersection policy (numeric.h RF_RAY_OFFSET_REL): the hit point moved off the
 * surface along the unit geometric normal to the side dir leaves by, by RF_RAY_OFFSET_REL times
 * h->scale, so that it scales with the numbers the point was computed from, whatever the
 * scene's size or place (no floor). fixed_offset > 0 moves it by that absolute distance instead
 * (RfRenderOptions.fixed_offset, the verifier's planted bug: a scale-blind epsilon must be caught
 * by the acne measurement). */
static inline RfVec3 rf_hit_offset_origin(const RfSurfaceHit *h, RfVec3 dir, double fixed_offset)
{
    /* inline: the kernel builds its shadow ray in registers (a returned copy read back across
     * its stores stalled). A floor far below any coordinate a scene has keeps a hit at the
     * origin off its surface. */
    double eps = fixed_offset > 0.0 ? fixed_offset : RF_RAY_OFFSET_REL * (h->scale > 0x1p-900 ? h->scale : 0x1p-900);
    return rf_vec3_add(h->point, rf_vec3_scale(h->normal, rf_vec3_dot(dir, h->normal) >= 0.0 ? eps : -eps));
}

/* Everything besides the scene that decides a render's pixels, as one line for an image header
 * ("640x480, 16 spp stratified, filter box 0.5, depth 8, seed 1[, local only][, adaptive ...]
 * [, lens ...][, light samples N][, two-sided][, shadows filtered][, preview]"), the scene's
 * settings resolved with the options.
 * Two renders of one scene with equal lines give the same pixels. 0 for options rf_render
 * would refuse. */
int rf_render_describe(const RfScene *scene, const RfRenderOptions *opt, char *buf, size_t size);

/* Renders the scene into img (allocated here, RGB float, linear). */
RfStatus rf_render(const RfScene *scene, const RfRenderOptions *opt, RfImage *img, RfRenderStats *stats);

#ifdef __cplusplus
}
#endif

#endif
