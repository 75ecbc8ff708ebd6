/* The render kernels: kernel_body.h compiled once per feature set (kernel.h). The sets are
 * those that measurably pay (docs/performance.md "Specialised kernels"): every combination of the
 * parts whose absence saves work, the others always compiled in. */
#include "kernel.h"

#include <math.h>

#include "refray/optics.h"
#include "refray/intersect.h"
#include "refray/sampling.h"
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

/* The largest channel difference |a - b| (NaN counts as a difference). */
static inline double rf_kernel_rgb_diff(RfRgb a, RfRgb b)
{
    double d[3] = {fabs(a.r - b.r), fabs(a.g - b.g), fabs(a.b - b.b)}, m = 0.0;
    for (int i = 0; i < 3; i++)
        m = d[i] > m || d[i] != d[i] ? d[i] : m;
    return m;
}

#define RF_CAT_(a, b) a##_##b
#define RF_CAT(a, b) RF_CAT_(a, b)
#define RF_KNAME(name) RF_CAT(name, RF_KPARTS)

#include "kernels_list.h"

#undef RF_KNAME
