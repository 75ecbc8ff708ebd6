/* refray: sample patterns, warps and reconstruction filters for §3.9 (anti-aliasing) and §3.10
 * (distributed ray tracing). Every number is a pure function of (pixel, sample index, sample
 * count, dimension, seed) through the counter-based generator (rng.h), so an image is the same
 * for any thread count and tile order.
 *
 * A "dimension" names one use of random numbers within a sample path: the pixel position, the
 * lens, the time, the k-th light's area, a glossy bounce at depth d. Each dimension gets its own
 * scrambling, so the strata of one are not correlated with the strata of another. Dimension d
 * draws its jitter from the generator's dimensions 2d and 2d + 1 (rf_rng_uniform), so d < 2^31;
 * the 1D and 2D functions share this numbering (use a dimension for one of them only). */
#ifndef REFRAY_SAMPLING_H
#define REFRAY_SAMPLING_H

#include <stdint.h>

#include "refray/vec.h"

#ifdef __cplusplus
extern "C" {
#endif

/* How the n samples of a pixel (or of one dimension) are spread over [0,1)^2. */
typedef enum {
    RF_SAMPLER_UNIFORM,    /* §3.9 uniform supersampling: the centres of a regular grid of a x b
                              = n cells (a the largest divisor of n up to sqrt n: a prime n gives
                              one row), the same positions in every pixel: no noise, aliasing */
    RF_SAMPLER_RANDOM,     /* §3.9 stochastic: independent uniform points */
    RF_SAMPLER_STRATIFIED, /* §3.9 stratified (jittered): one uniform point per cell of a k x k grid
                              when n = k^2; otherwise n x n Latin-hypercube strata (one point per
                              row and per column); the cell order is shuffled per pixel and
                              dimension, except in dimension 0 (the pixel position), where sample
                              i of k^2 is in column i mod k, row i div k: the renderer's pattern,
                              bit for bit (but never 1.0) */
    RF_SAMPLER_SOBOL,      /* low discrepancy: the 2D Sobol (0,2)-sequence, Owen-scrambled by
                              hashing (Burley 2020) per pixel and dimension, index shuffled (the
                              shuffled sequence is again a (0,2)-sequence); sample k does not
                              depend on n, so any n is a valid prefix and n = 2^m a (0,m,2)-net */
    RF_SAMPLER_COUNT
} RfSampler;

/* "uniform", "random", "stratified", "sobol"; rf_sampler_parse returns -1 for an unknown name. */
const char *rf_sampler_name(RfSampler s);
int rf_sampler_parse(const char *name);

/* Sample k (0 <= k < n) of n in [0,1)^2 for one pixel and dimension. n = 0 counts as 1; the
 * uniform and stratified patterns take k modulo n. */
void rf_sample_2d(RfSampler s, uint32_t k, uint32_t n, uint64_t pixel, uint32_t dimension, uint64_t seed,
                  double out[2]);
/* What rf_sample_2d hashes out of (pixel, dimension, seed) before it looks at the sample: a
 * caller that draws several samples of one pixel and dimension (the shadow rays of an area
 * light) computes it once with rf_sample_keys and draws with rf_sample_2d_keyed, the same values
 * as rf_sample_2d's. */
typedef struct {
    uint32_t xor_key[4], mul_key[4]; /* the round keys of a keyed shuffle of [0, n) */
} RfPermuteKeys;
typedef struct {
    RfSampler sampler;
    uint32_t dimension;
    uint64_t pixel, seed;
    uint64_t stream;     /* rf_rng_stream(pixel, seed): random and stratified draw from it */
    uint64_t base;       /* the pixel's key (every pattern but random) */
    RfPermuteKeys order; /* uniform, stratified: the strata's shuffle */
    uint64_t sobol_index, sobol_x, sobol_y;
} RfSampleKeys;
RfSampleKeys rf_sample_keys(RfSampler s, uint64_t pixel, uint32_t dimension, uint64_t seed);
void rf_sample_2d_keyed(const RfSampleKeys *keys, uint32_t k, uint32_t n, double out[2]);
/* Samples k0 .. k0 + count - 1 of n into out[0 .. count - 1]: rf_sample_2d_keyed's values (the
 * Sobol pattern four at a time in SIMD lanes where the build has SSE4.1). */
void rf_sample_2d_keyed_run(const RfSampleKeys *keys, uint32_t k0, uint32_t count, uint32_t n, double (*out)[2]);

/* Sample k of n in [0,1): uniform (k + 0.5) / n, random, stratified (one per stratum
 * [j/n, (j+1)/n), strata shuffled except in dimension 0), sobol (the scrambled van der Corput
 * sequence: the first coordinate of rf_sample_2d's point). */
double rf_sample_1d(RfSampler s, uint32_t k, uint32_t n, uint64_t pixel, uint32_t dimension, uint64_t seed);

/* ---- warps: [0,1)^2 onto a domain, with their densities -------------------------------- */

/* The unit disk by Shirley and Chiu's concentric map (keeps strata compact); density 1/pi. */
void rf_warp_disk(double u, double v, double *x, double *y);
/* The unit sphere, uniform by area; density 1/(4 pi). */
RfVec3 rf_warp_sphere(double u, double v);
/* Directions in the cone around +z with cos(theta) >= cos_max, uniform by solid angle;
 * density 1/(2 pi (1 - cos_max)). cos_max = -1 gives the sphere. */
RfVec3 rf_warp_cone(double u, double v, double cos_max);
double rf_warp_cone_pdf(double cos_max);
/* The Phong lobe around +z: density (n + 1)/(2 pi) cos(theta)^n on the hemisphere z > 0
 * (cos(theta) = u^(1/(n+1)), phi = 2 pi v); the pdf is 0 for dir.z <= 0. */
RfVec3 rf_warp_cos_power(double u, double v, double n);
double rf_warp_cos_power_pdf(RfVec3 dir, double n);

/* An orthonormal basis (s, t, n) around the unit vector n (Duff et al. 2017, no branch on a
 * threshold): a local direction (x, y, z) maps to x s + y t + z n. */
typedef struct { RfVec3 s, t, n; } RfFrame;
RfFrame rf_frame(RfVec3 n);
RfVec3 rf_frame_to_world(const RfFrame *f, RfVec3 local);

/* ---- reconstruction filters (§3.9) ------------------------------------------------------ */

typedef enum {
    RF_FILTER_BOX,      /* 1 inside the pixel (radius 0.5), the script's average */
    RF_FILTER_GAUSSIAN, /* exp(-x^2 / (2 sigma^2)) - exp(-r^2 / (2 sigma^2)), separable;
                           sigma = 0.5, radius r = 1.5 pixels by default */
    RF_FILTER_MITCHELL, /* Mitchell-Netravali (1988), B = C = 1/3, radius 2 pixels, separable;
                           negative lobes */
    RF_FILTER_COUNT
} RfFilterKind;

typedef struct {
    RfFilterKind kind;
    double radius; /* pixels: samples are drawn in [-radius, radius]^2 around the pixel centre */
    double sigma;  /* Gaussian only */
} RfFilter;

/* The defaults above; rf_filter_parse reads "box", "gaussian", "mitchell" (-1: unknown). */
RfFilter rf_filter_default(RfFilterKind kind);
const char *rf_filter_name(RfFilterKind kind);
int rf_filter_parse(const char *name);
/* The filter's weight at offset (dx, dy) from the pixel centre, in pixels (0 outside
 * [-radius, radius]^2). Not normalised: the pixel divides by the sum of its weights. Mitchell's
 * kernel (support [-2, 2]) is stretched to the radius, k(2 dx / r) k(2 dy / r), so at the
 * default radius 2 its 1D kernel integrates to 1. */
double rf_filter_eval(const RfFilter *f, double dx, double dy);

#ifdef __cplusplus
}
#endif

#endif
