/* The render kernels (internal to src/render): one source, kernel_body.h, compiled once per
 * feature set by kernels.c, so that a render runs code with exactly the parts its scene needs
 * (DESIGN.md "Skip what a scene does not need"). Every kernel gives the image of the general
 * one bit for bit: a part a kernel leaves out would have added nothing. */
#ifndef RF_RENDER_KERNEL_H
#define RF_RENDER_KERNEL_H

#include <stdint.h>

#include "refray/camera.h"
#include "refray/image.h"
#include "refray/parallel.h"
#include "refray/render.h"

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
    RF_K_JITTER = 1u << 9,      /* more than one sample per pixel */
    RF_K_ALL = (1u << 10) - 1,  /* the general kernel */
    RF_K_COUNT = 10
};

/* A light as the kernel walks it: the scene's light with its cut-off in radians. */
typedef struct {
    RfLightKind kind;
    RfFalloff falloff;
    RfVec3 position, direction;
    RfRgb intensity;
    double spot_exponent, spot_cutoff_rad;
} RfKernelLight;

typedef struct {
    const RfTracer *tracer;
    const RfMaterial *materials;
    const unsigned char *highlight; /* per material: rf_material_has_highlight */
    const RfKernelLight *lights;
    int light_count;
    int max_depth, local_only;
    double min_contribution, fixed_offset;
    RfRgb background, ambient;
    RfCamera camera;
    const double *column_x, *row_y; /* 1 spp: the image-plane coordinates of the pixel centres */
    double hither;                  /* near plane distance along the view axis (NFF `hither`) */
    int width, height, samples;
    uint64_t seed;
    RfImage *img;
    RfRenderStats *per_thread;      /* one per thread: no sharing on the hot path */
    uint64_t *shadow_cache;         /* per thread and light: the last occluder (rf_tracer_occluded_cached) */
} RfKernelJob;

typedef struct {
    unsigned parts;   /* RF_K_* compiled in */
    RfTileFn tile;    /* renders one tile of an RfKernelJob */
} RfKernel;

extern const RfKernel rf_kernels[];
extern const int rf_kernel_count;

#endif
