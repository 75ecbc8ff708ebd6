/* The render kernels (internal to src/render): one source, kernel_body.h, compiled once per
 * feature set by kernels.c, so that a render runs code with exactly the parts its scene needs
 * (DESIGN.md "Skip what a scene does not need"). Every kernel gives the image of the general
 * one bit for bit: a part a kernel leaves out would have added nothing. */
#ifndef RF_RENDER_KERNEL_H
#define RF_RENDER_KERNEL_H

#include <float.h>
#include <stdint.h>

#include "refray/camera.h"
#include "refray/image.h"
#include "refray/parallel.h"
#include "refray/render.h"
#include "refray/sampling.h"

/* The parts of a kernel (RfRenderStats.kernel holds a set of these). */
enum {
    RF_K_SHADOW = 1u << 0,      /* shadow rays (lights that can be occluded, not --local) */
    RF_K_SECONDARY = 1u << 1,   /* mirror and refracted rays */
    RF_K_FRESNEL = 1u << 2,     /* Fresnel weights (with RF_K_SECONDARY) */
    RF_K_SPECULAR = 1u << 3,    /* Phong highlights (some ks > 0) */
    RF_K_AMBIENT = 1u << 4,     /* ka * ambient */
    RF_K_EMISSION = 1u << 5,    /* emitting materials */
    RF_K_SPOT = 1u << 6,        /* spot lights */
    RF_K_DIRECTIONAL = 1u << 7, /* directional lights */
    RF_K_FALLOFF = 1u << 8,     /* lights that fall off with the squared distance */
    RF_K_JITTER = 1u << 9,      /* more than one sample per pixel, or adaptive */
    RF_K_AREA = 1u << 10,       /* §3.10 area lights (soft shadows) */
    RF_K_LENS = 1u << 11,       /* §3.10 a thin lens (depth of field) */
    RF_K_MOTION = 1u << 12,     /* §3.10 moving instances (motion blur) */
    RF_K_GLOSSY = 1u << 13,     /* §3.10 glossy reflection and transmission */
    RF_K_ALL = (1u << 14) - 1,  /* the general kernel */
    RF_K_COUNT = 14
};

/* A radiance the film takes: finite and not negative in every channel (-0 is fine). */
static inline int rf_kernel_rgb_valid(RfRgb c)
{
    return c.r >= 0.0 && c.r <= DBL_MAX && c.g >= 0.0 && c.g <= DBL_MAX && c.b >= 0.0 && c.b <= DBL_MAX;
}

/* Sampled dimensions (sampling.h): the pixel position, the lens, the time, then per path vertex
 * (depth) 64 slots: 0 the glossy mirror ray, 1 the glossy refracted ray, 2 + i light i. */
enum { RF_DIM_PIXEL = 0, RF_DIM_LENS = 1, RF_DIM_TIME = 2 };
static inline uint32_t rf_kernel_dim(int depth, int slot)
{
    return 8u + (uint32_t)(depth - 1) * 64u + (uint32_t)(slot & 63);
}

/* The vertices of one path, written only when a failed sample is traced again to explain it. */
typedef struct {
    char text[512];
    size_t len;
    RfTraceFn trace; /* refray trace: every step as an event (NULL: the text only) */
    void *trace_ctx;
} RfPathLog;

/* Samples of one dimension drawn together (rf_sample_2d_keyed_run): an area light's, a pixel's
 * positions and lens points, into buffers of this many. */
#define RF_SAMPLE_RUN 16

/* Where a sample path is: its pixel, camera sample k of n, the pattern, its time. */
typedef struct {
    uint64_t pixel;
    uint32_t k, n;
    RfSampler sampler;
    double time;
    RfMotionState *motion; /* the thread's, set to time */
    RfPathLog *log;        /* NULL, except when explaining an invalid sample */
    const double *lens_uv;    /* this sample's lens point in [0,1)^2, drawn with the pixel's others
                                 (NULL: drawn per sample) */
} RfPathSample;


/* A light as the kernel walks it: the scene's light with its cut-off in radians. */
typedef struct {
    RfLightKind kind;
    RfFalloff falloff;
    RfVec3 position, direction;
    RfRgb intensity;      /* area lights: the radiance */
    double spot_exponent, spot_cutoff_rad;
    RfVec3 edge1, edge2;  /* rect */
    double radius, area;  /* disc, sphere; every area light */
    int two_sided;
    int samples;          /* area lights: shadow rays per shading point; 0: not an area light */
} RfKernelLight;

typedef struct {
    const RfTracer *tracer;
    const RfMaterial *materials;
    const unsigned char *highlight; /* per material: rf_material_has_highlight */
    const RfKernelLight *lights;
    int light_count;
    int max_depth, local_only;
    int filtered_shadows;           /* RF_SHADOWS_FILTERED, and some surface transmits */
    double min_contribution, fixed_offset;
    RfRgb background, ambient;
    RfCamera camera;
    const double *column_x, *row_y; /* 1 spp: the image-plane coordinates of the pixel centres */
    double hither;                  /* near plane distance along the view axis (NFF `hither`) */
    int width, height, samples;
    uint64_t seed;
    RfSampler sampler;              /* §3.9/§3.10 the pattern of every sampled dimension */
    RfFilter filter;
    int filter_box;                 /* the box of radius 1/2: the plain mean of the pixel's samples */
    double shutter_open, shutter_close;
    int moving;                     /* some instance moves (motion blur) */
    int adaptive_depth;             /* §3.9 adaptive supersampling */
    double adaptive_threshold;
    RfRgb *centres;                 /* adaptive: the pixel centres' values (pass 1), of the window
                                       centres_x0, centres_y0, centres_w wide: the crop and one
                                       pixel around it */
    int centres_x0, centres_y0, centres_w;
    RfPathLog *trace_log;           /* refray trace (a 1 x 1 crop): every sample logs here */
    RfImage *variance;              /* NULL, or each pixel's variance of its mean (the crop's size) */
    RfImage *img;                   /* the crop, whose top left pixel is (img_x0, img_y0) */
    int img_x0, img_y0;
    RfRenderStats *per_thread;      /* one per thread: no sharing on the hot path */
    uint64_t *shadow_cache;         /* per thread and light: the last occluder (rf_tracer_occluded_cached);
                                       thread t's at rf_kernel_shadow_cache */
    RfMotionState **motion;         /* per thread: moving instances at the sample's time (or NULL) */
    const RfScene *scene;           /* for the names in an explained path */
    /* 1: a tile whose camera rays provably meet nothing (rf_kernel_tile_misses) gets the
     * background without a ray traced; 0 where a tile is always traced (a lens, motion, refray
     * trace, an invalid background). Never in the general kernel. */
    int cull;
} RfKernelJob;

/* Thread t's shadow cache: light_count slots, then a cache line of 8 unused ones before the
 * next thread's. Unoccluded shadow rays write their slot (rf_tracer_occluded_cached), so two
 * threads' slots on one line would pass it between the cores at every such ray. */
static inline size_t rf_kernel_shadow_stride(size_t light_count) { return light_count + 8; }

static inline uint64_t *rf_kernel_shadow_cache(const RfKernelJob *job, int thread)
{
    return job->shadow_cache + (size_t)thread * rf_kernel_shadow_stride((size_t)job->light_count);
}

typedef struct {
    unsigned parts;   /* RF_K_* compiled in */
    RfTileFn tile;    /* renders one tile of an RfKernelJob */
    RfTileFn adaptive_centres, adaptive_refine; /* §3.9 adaptive supersampling's two passes */
    /* traces sample k of a pixel again, as the tile did, writing its path into log */
    RfRgb (*explain)(const RfKernelJob *job, uint64_t pixel, int k, RfPathLog *log);
} RfKernel;

extern const RfKernel rf_kernels[];
extern const int rf_kernel_count;

#endif
