/* The render kernels: kernel_body.h compiled once per feature set (kernel.h). The sets are
 * those that measurably pay (docs/performance.md "Specialised kernels"): every combination of the
 * parts whose absence saves work, the others always compiled in. */
#include "kernel.h"

#include <math.h>

#include "refray/optics.h"
#include "refray/rng.h"
#include "refray/shading.h"

/* max over the channels, as fmax(r, fmax(g, b)) (NaN ignored) without a library call. */
static inline double rf_kernel_rgb_max(RfRgb c)
{
    double m = c.r;
    if (c.g > m || m != m)
        m = c.g;
    if (c.b > m || m != m)
        m = c.b;
    return m;
}

/* The sub-pixel position of sample k of n > 1: stratified jitter on a k x k grid when n is a
 * perfect square, otherwise uniform jitter (counter-based random numbers: rng.h). */
static void rf_kernel_sample(int n, int k, uint64_t pixel, uint64_t seed, double *sx, double *sy)
{
    double u = rf_rng_uniform(pixel, (uint32_t)k, 0, seed), v = rf_rng_uniform(pixel, (uint32_t)k, 1, seed);
    int side = (int)floor(sqrt((double)n) + 0.5);
    if (side * side == n) {
        *sx = ((k % side) + u) / side;
        *sy = ((k / side) + v) / side;
    } else {
        *sx = u;
        *sy = v;
    }
}

#define RF_CAT_(a, b) a##_##b
#define RF_CAT(a, b) RF_CAT_(a, b)
#define RF_KNAME(name) RF_CAT(name, RF_KPARTS)

#include "kernels_list.h"

#undef RF_KNAME
