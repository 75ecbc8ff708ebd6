/* The render kernels: kernel_body.h compiled once per feature set (kernel.h). The sets are
 * those that measurably pay (docs/performance.md "Specialised kernels"): every combination of the
 * parts whose absence saves work, the others always compiled in. */
#include "kernel.h"

#include <float.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

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

/* Counts an invalid sample and keeps the thread's first (lowest pixel, then sample). */
static void rf_kernel_note_invalid(RfRenderStats *st, int width, uint64_t pixel, int sample, RfRgb c)
{
    uint64_t first = (uint64_t)st->invalid.y * (uint64_t)width + (uint64_t)st->invalid.x;
    st->invalid_samples++;
    if (!st->invalid.found || pixel < first || (pixel == first && sample < st->invalid.sample)) {
        st->invalid.found = 1;
        st->invalid.x = (int)(pixel % (uint64_t)width);
        st->invalid.y = (int)(pixel / (uint64_t)width);
        st->invalid.sample = sample;
        st->invalid.value[0] = c.r;
        st->invalid.value[1] = c.g;
        st->invalid.value[2] = c.b;
    }
}

/* Pixel (x, y)'s value into the float image (the crop); one that overflows float is invalid too
 * (black). */
static void rf_kernel_store(const RfKernelJob *job, RfRenderStats *st, int x, int y, RfRgb c)
{
    uint64_t pixel = (uint64_t)y * (uint64_t)job->width + (uint64_t)x;
    float *px = job->img->data + ((size_t)(y - job->img_y0) * (size_t)job->img->width + (size_t)(x - job->img_x0)) * 3;
    px[0] = (float)c.r;
    px[1] = (float)c.g;
    px[2] = (float)c.b;
    if (!isfinite(px[0]) || !isfinite(px[1]) || !isfinite(px[2])) {
        rf_kernel_note_invalid(st, job->width, pixel, -1, c);
        px[0] = px[1] = px[2] = 0.0f;
    }
}

/* 1 when no camera ray of the tile can hit anything (a pinhole camera): the pyramid from the
 * eye through the tile's pixels, widened by `margin` pixels on each side, reaches no leaf of the
 * BVH (rf_tracer_cone_empty). A margin of 1 holds every ray through the tile's pixels as rounded,
 * by a wide margin; a filter of radius r draws its samples up to r from the pixel's centre, so
 * r + 1 holds them. */
static int rf_kernel_tile_misses(const RfKernelJob *job, RfTile tile, double margin)
{
    const RfCamera *cam = &job->camera;
    const double xs[4] = {tile.x0 - margin, tile.x1 + margin, tile.x1 + margin, tile.x0 - margin};
    const double ys[4] = {tile.y0 - margin, tile.y0 - margin, tile.y1 + margin, tile.y1 + margin};
    RfVec3 d[4], mid = rf_vec3(0.0, 0.0, 0.0), side[4];
    for (int i = 0; i < 4; i++) {
        d[i] = rf_camera_to_world(cam, rf_camera_plane_point(cam, xs[i], ys[i]));
        mid = rf_vec3_add(mid, d[i]);
    }
    for (int i = 0; i < 4; i++) { /* the side planes through the eye, normals inward */
        side[i] = rf_vec3_cross(d[i], d[(i + 1) % 4]);
        double s = rf_vec3_dot(side[i], mid);
        if (!(s != 0.0))
            return 0;
        if (s < 0.0)
            side[i] = rf_vec3_neg(side[i]);
    }
    return rf_tracer_cone_empty(job->tracer, cam->eye, side, 4);
}

/* Where pixel (x, y)'s centre value is kept (adaptive supersampling, kernel.h). */
static inline size_t rf_kernel_centre(const RfKernelJob *job, int x, int y)
{
    return (size_t)(y - job->centres_y0) * (size_t)job->centres_w + (size_t)(x - job->centres_x0);
}

/* refray trace: the pixel's value as stored in the image */
static void rf_kernel_trace_pixel(const RfKernelJob *job, const RfPathSample *ps, int x, int y)
{
    const float *px = job->img->data + ((size_t)(y - job->img_y0) * (size_t)job->img->width + (size_t)(x - job->img_x0)) * 3;
    RfTraceEvent ev;
    memset(&ev, 0, sizeof ev);
    ev.kind = RF_TRACE_PIXEL, ev.samples = (int)ps->n;
    ev.color = rf_rgb(px[0], px[1], px[2]);
    ps->log->trace(ps->log->trace_ctx, &ev);
}

/* Pixel (x, y)'s variance of its mean from the sum and the sum of squares of its n samples:
 * s^2 / n with s^2 = (sq - sum^2 / n) / (n - 1), per channel, never below 0 (rounding). */
static void rf_kernel_store_variance(const RfKernelJob *job, int x, int y, RfRgb sum, RfRgb sq, int n)
{
    float *v = job->variance->data + ((size_t)(y - job->img_y0) * (size_t)job->variance->width + (size_t)(x - job->img_x0)) * 3;
    const double s[3] = {sum.r, sum.g, sum.b}, q[3] = {sq.r, sq.g, sq.b};
    for (int c = 0; c < 3; c++) {
        double var = (q[c] - s[c] * s[c] / n) / ((double)n - 1.0) / n;
        v[c] = (float)(var > 0.0 ? var : 0.0);
    }
}

/* A region of n background samples per pixel (rf_kernel_tile_misses): the pixel sums as the
 * tile's loop makes them (one sample: the sample itself; more: added to +0 in turn), stored as
 * rf_kernel_store stores them, once for every pixel; the same primary ray count. */
static void rf_kernel_background(const RfKernelJob *job, RfRenderStats *st, RfTile r, int n)
{
    RfRgb bg = job->background, sum = bg, sq = rf_rgb(0, 0, 0);
    if (n > 1) {
        sum = rf_rgb(0, 0, 0); /* the loop's sums start at +0 */
        for (int k = 0; k < n; k++) {
            sum = rf_rgb_add(sum, bg);
            sq = rf_rgb_add(sq, rf_rgb_mul(bg, bg));
        }
    }
    RfRgb mean = rf_rgb(sum.r / n, sum.g / n, sum.b / n);
    const float v[3] = {(float)mean.r, (float)mean.g, (float)mean.b};
    int finite = isfinite(v[0]) && isfinite(v[1]) && isfinite(v[2]);
    st->primary_rays += (uint64_t)n * (uint64_t)(r.x1 - r.x0) * (uint64_t)(r.y1 - r.y0);
    for (int y = r.y0; y < r.y1; y++) {
        float *px = job->img->data + ((size_t)(y - job->img_y0) * (size_t)job->img->width + (size_t)(r.x0 - job->img_x0)) * 3;
        for (int x = r.x0; x < r.x1; x++, px += 3) {
            if (n > 1 && job->variance)
                rf_kernel_store_variance(job, x, y, sum, sq, n);
            if (finite)
                memcpy(px, v, sizeof v);
            else /* a background beyond float: each pixel noted as the loop would */
                rf_kernel_store(job, st, x, y, mean);
        }
    }
}

/* Appends to an explained path (kernel.h RfPathLog). */
static void rf_kernel_log(RfPathLog *log, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    if (log->len < sizeof log->text) {
        int n = vsnprintf(log->text + log->len, sizeof log->text - log->len, fmt, ap);
        log->len += n > 0 ? (size_t)n : 0;
    }
    va_end(ap);
}

static void rf_kernel_log_hit(RfPathLog *log, const RfScene *s, const RfSurfaceHit *h)
{
    const RfPrimitive *p = &s->prims[h->prim];
    rf_kernel_log(log, " -> %s #%d (line %d, material '%s')", rf_prim_type_name(p->type), h->prim, p->loc.line,
                  s->materials[h->material].name);
}

#define RF_CAT_(a, b) a##_##b
#define RF_CAT(a, b) RF_CAT_(a, b)
#define RF_KNAME(name) RF_CAT(name, RF_KPARTS)

#include "kernels_list.h"

#undef RF_KNAME
