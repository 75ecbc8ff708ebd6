/* Image comparison (diff.h): metrics, silhouette mask, verdict, the statistical test (the heat
 * maps are heatmap.c). */
#include "refray/diff.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

RfDiffOptions rf_diff_options_default(void)
{
    RfDiffOptions o;
    o.warn = 1e-4;
    o.warn_percent = 0.1;
    o.fail = 1.0 / 255.0;
    o.fail_percent = 0.1;
    o.fail_mean = 1e-4;
    o.hardfail = INFINITY;
    o.depth_edge = 0.01;
    o.edge_tolerant = 0;
    return o;
}

double rf_diff_percent(long count, const RfDiffStats *s)
{
    return s->pixels > 0 ? 100.0 * (double)count / (double)s->pixels : 0.0;
}

const char *rf_diff_verdict_name(RfDiffVerdict v)
{
    return v == RF_DIFF_PASS ? "PASS" : v == RF_DIFF_WARN ? "WARN" : "FAIL";
}

static double inv_depth(float z)
{
    return isfinite(z) && z > 0.0f ? 1.0 / (double)z : 0.0;
}

void rf_diff_silhouettes(const RfImage *d, double edge, unsigned char *mask)
{
    int w = d->width, h = d->height, ch = d->channels;
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++)
            for (int dir = 0; dir < 2; dir++) {
                int dx = dir == 0, dy = dir == 1;
                if (x + 2 * dx >= w || y + 2 * dy >= h)
                    continue;
                size_t i0 = (size_t)y * w + x, i1 = i0 + (size_t)(dx + dy * w), i2 = i1 + (size_t)(dx + dy * w);
                float z0 = d->data[i0 * ch], z1 = d->data[i1 * ch], z2 = d->data[i2 * ch];
                double a = inv_depth(z0), b = inv_depth(z1), c = inv_depth(z2);
                double top = fmax(a, fmax(b, c));
                /* NaN depth counts as an edge too: nothing trustworthy there */
                if (fabs(a - 2.0 * b + c) > edge * top || isnan(z0) || isnan(z1) || isnan(z2))
                    mask[i0] = mask[i1] = mask[i2] = 1;
            }
}

/* The largest channel error of two pixels, INFINITY when a value is not finite. */
static double pixel_error(const float *pa, const float *pb, int nc)
{
    double e = 0.0;
    for (int c = 0; c < nc; c++) {
        double a = pa[c], b = pb[c];
        if (!isfinite(a) || !isfinite(b))
            return INFINITY;
        e = fmax(e, fabs(a - b));
    }
    return e;
}

double rf_diff_pixel_error(const RfImage *a, const RfImage *b, int x, int y, int edge_tolerant, int *bx, int *by)
{
    int nc = a->channels == 1 || b->channels == 1 ? 1 : 3, r = edge_tolerant ? 1 : 0, best_x = x, best_y = y;
    const float *pa = a->data + ((size_t)y * (size_t)a->width + (size_t)x) * (size_t)a->channels;
    double best = pixel_error(pa, b->data + ((size_t)y * (size_t)b->width + (size_t)x) * (size_t)b->channels, nc);
    for (int j = y - r; j <= y + r; j++)
        for (int i = x - r; i <= x + r; i++) {
            if (i < 0 || j < 0 || i >= b->width || j >= b->height)
                continue;
            double e = pixel_error(pa, b->data + ((size_t)j * (size_t)b->width + (size_t)i) * (size_t)b->channels, nc);
            if (e < best)
                best = e, best_x = i, best_y = j;
        }
    if (bx)
        *bx = best_x, *by = best_y;
    return best;
}

typedef struct {
    double sum, sum2, sumrel;
    long n3;
} Acc;

static void add_pixel(RfDiffStats *s, Acc *acc, const RfDiffOptions *o, const float *pa, const float *pb,
                      int nc, int x, int y)
{
    double worst = 0.0;
    int bad = 0;
    for (int c = 0; c < nc; c++) {
        double a = pa[c], b = pb[c];
        if (!isfinite(a) || !isfinite(b)) {
            /* a NaN or Inf is never a valid radiance: even the same infinity on both sides fails */
            bad = 1;
            continue;
        }
        double e = fabs(a - b);
        acc->sum += e;
        acc->sum2 += e * e;
        acc->sumrel += e * e / (b * b + 0.01);
        acc->n3++;
        worst = fmax(worst, e);
    }
    s->pixels++;
    if (bad) {
        s->nonfinite++;
        worst = INFINITY;
    }
    if (s->max_x < 0 || worst > s->max_abs) {
        s->max_abs = worst;
        s->max_x = x, s->max_y = y;
    }
    s->above_255 += worst > 1.0 / 255.0;
    s->above_warn += worst > o->warn;
    s->above_fail += worst > o->fail;
}

static void finish(RfDiffStats *s, const Acc *acc)
{
    double n = acc->n3 > 0 ? (double)acc->n3 : 1.0;
    s->mean_abs = acc->sum / n;
    s->rmse = sqrt(acc->sum2 / n);
    s->rel_mse = acc->sumrel / n;
    s->psnr = s->rmse > 0.0 ? 20.0 * log10(1.0 / s->rmse) : INFINITY;
}

static void stats_init(RfDiffStats *s)
{
    memset(s, 0, sizeof *s);
    s->max_x = s->max_y = -1;
}

static RfDiffVerdict verdict(const RfDiffStats *s, const RfDiffOptions *o)
{
    if (s->nonfinite > 0 || s->max_abs > o->hardfail || rf_diff_percent(s->above_fail, s) > o->fail_percent ||
        s->mean_abs > o->fail_mean)
        return RF_DIFF_FAIL;
    if (rf_diff_percent(s->above_warn, s) > o->warn_percent)
        return RF_DIFF_WARN;
    return RF_DIFF_PASS;
}

RfStatus rf_diff_images(const RfImage *a, const RfImage *b, const RfImage *da, const RfImage *db,
                        const RfDiffOptions *opt, RfDiffResult *res, unsigned char *mask_out,
                        char *err, size_t errsz)
{
    RfDiffOptions def = rf_diff_options_default();
    const RfDiffOptions *o = opt ? opt : &def;
    memset(res, 0, sizeof *res);
    stats_init(&res->all);
    stats_init(&res->interior);
    if (a->width != b->width || a->height != b->height) {
        snprintf(err, errsz, "image sizes differ: %dx%d and %dx%d", a->width, a->height, b->width, b->height);
        return RF_ERR_DOMAIN;
    }
    if ((a->channels == 1) != (b->channels == 1)) {
        snprintf(err, errsz, "channel counts differ: %d and %d", a->channels, b->channels);
        return RF_ERR_DOMAIN;
    }
    if ((da == NULL) != (db == NULL)) {
        snprintf(err, errsz, "give both depth images or neither");
        return RF_ERR_DOMAIN;
    }
    const RfImage *ds[2] = {da, db};
    for (int k = 0; k < 2 && da; k++)
        if (ds[k]->width != a->width || ds[k]->height != a->height) {
            snprintf(err, errsz, "depth image %c is %dx%d, the images %dx%d", 'A' + k, ds[k]->width,
                     ds[k]->height, a->width, a->height);
            return RF_ERR_DOMAIN;
        }
    size_t n = (size_t)a->width * (size_t)a->height;
    unsigned char *mask = calloc(n ? n : 1, 1);
    if (!mask) {
        snprintf(err, errsz, "out of memory");
        return RF_ERR_NOMEM;
    }
    if (da) {
        res->has_depth = 1;
        rf_diff_silhouettes(da, o->depth_edge, mask);
        rf_diff_silhouettes(db, o->depth_edge, mask);
    }
    int nc = a->channels == 1 ? 1 : 3;
    Acc all = {0, 0, 0, 0}, in = {0, 0, 0, 0};
    double rel_sum = 0.0;
    long rel_n = 0;
    for (int y = 0; y < a->height; y++)
        for (int x = 0; x < a->width; x++) {
            size_t i = (size_t)y * a->width + x;
            int bx = x, by = y; /* edge-tolerant: A's pixel against its best match among B's neighbours */
            if (o->edge_tolerant)
                rf_diff_pixel_error(a, b, x, y, 1, &bx, &by);
            const float *pa = a->data + i * a->channels,
                        *pb = b->data + ((size_t)by * b->width + (size_t)bx) * b->channels;
            add_pixel(&res->all, &all, o, pa, pb, nc, x, y);
            if (mask[i]) {
                res->silhouette++;
            } else {
                add_pixel(&res->interior, &in, o, pa, pb, nc, x, y);
            }
            if (da) {
                float za = da->data[i * da->channels], zb = db->data[i * db->channels];
                if (isfinite(za) != isfinite(zb)) {
                    res->coverage_mismatch++;
                } else if (!mask[i] && isfinite(za) && zb > 0.0f) {
                    double r = fabs((double)za - (double)zb) / (double)zb;
                    res->depth_max_rel = fmax(res->depth_max_rel, r);
                    rel_sum += r;
                    rel_n++;
                }
            }
        }
    finish(&res->all, &all);
    finish(&res->interior, &in);
    res->depth_mean_rel = rel_n ? rel_sum / (double)rel_n : 0.0;
    res->verdict = verdict(&res->interior, o);
    if (mask_out)
        memcpy(mask_out, mask, n);
    free(mask);
    return RF_OK;
}

RfStatus rf_diff_stat(const RfImage *a, const RfImage *b, const RfImage *va, const RfImage *vb, double alpha,
                      double accept, RfStatResult *out, RfImage *pvalues, char *err, size_t errsz)
{
    const RfImage *im[4] = {a, b, va, vb};
    memset(out, 0, sizeof *out);
    for (int k = 0; k < 4; k++)
        if (!im[k] || !im[k]->data || im[k]->channels < 3 || im[k]->width != a->width || im[k]->height != a->height) {
            snprintf(err, errsz, "the images and their variances must all be %dx%d RGB", a ? a->width : 0,
                     a ? a->height : 0);
            return RF_ERR_DOMAIN;
        }
    if (!(alpha > 0.0 && alpha < 1.0) || !(accept >= 0.0 && accept <= 1.0)) {
        snprintf(err, errsz, "alpha must lie in (0, 1) and the accepted share in [0, 1]");
        return RF_ERR_DOMAIN;
    }
    if (pvalues && rf_image_alloc(pvalues, a->width, a->height, 1) != RF_OK) {
        snprintf(err, errsz, "out of memory");
        return RF_ERR_NOMEM;
    }
    long n = (long)a->width * a->height;
    out->pixels = n;
    out->alpha_pixel = -expm1(log1p(-alpha) / (double)n); /* 1 - (1 - alpha)^(1/n), without cancellation */
    out->min_p = 2.0;
    for (long i = 0; i < n; i++) {
        double p = 1.0;
        for (int c = 0; c < 3; c++) {
            size_t at = (size_t)i * (size_t)a->channels + (size_t)c;
            double d = (double)a->data[at] - (double)b->data[(size_t)i * (size_t)b->channels + (size_t)c];
            double v = (double)va->data[(size_t)i * (size_t)va->channels + (size_t)c] +
                       (double)vb->data[(size_t)i * (size_t)vb->channels + (size_t)c];
            double pc = v > 0.0 ? erfc(fabs(d) / sqrt(2.0 * v)) : d == 0.0 ? 1.0 : 0.0;
            if (!(pc == pc)) /* NaN in an image: it fails */
                pc = 0.0;
            p = fmin(p, pc);
        }
        p = fmin(1.0, 3.0 * p);
        out->accepted += p > out->alpha_pixel;
        if (p < out->min_p) {
            out->min_p = p;
            out->min_x = (int)(i % a->width);
            out->min_y = (int)(i / a->width);
        }
        if (pvalues)
            pvalues->data[i] = (float)p;
    }
    out->pass = (double)out->accepted >= accept * (double)n;
    return RF_OK;
}
