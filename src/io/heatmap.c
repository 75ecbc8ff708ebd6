/* The heat maps of diff.h: the error map scaled to the verdict's thresholds, with its legend drawn
 * by cairo (shared by `refray diff --heatmap` and `refray grade`), and the depth comparison. */
#include "refray/diff.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cairo.h>
#include <fontconfig/fontconfig.h>

/* black -> purple -> red -> yellow -> white for t in [0, 1] */
static void heat(double t, float *rgb)
{
    static const float stops[5][3] = {{0, 0, 0}, {0.45f, 0.05f, 0.55f}, {0.9f, 0.15f, 0.1f},
                                      {1.0f, 0.85f, 0.1f}, {1, 1, 1}};
    t = t < 0.0 ? 0.0 : t > 1.0 ? 1.0 : t;
    double s = t * 4.0;
    int k = s >= 4.0 ? 3 : (int)s;
    double f = s - k;
    for (int c = 0; c < 3; c++)
        rgb[c] = (float)((1.0 - f) * stops[k][c] + f * stops[k + 1][c]);
}

static void log_heat(double e, double lo, double hi, float *rgb)
{
    if (e <= 0.0) {
        rgb[0] = rgb[1] = rgb[2] = 0.0f;
        return;
    }
    heat(isfinite(e) ? (log10(e) - log10(lo)) / (log10(hi) - log10(lo)) : 1.0, rgb);
    if (e < lo) /* faintly visible, so that tiny differences are not mistaken for none */
        rgb[0] = rgb[2] = 0.08f, rgb[1] = 0.0f;
}

static void grey_out(float *rgb)
{
    for (int c = 0; c < 3; c++)
        rgb[c] = 0.5f * rgb[c] + 0.25f;
}

void rf_diff_heat_colour(double e, const RfDiffOptions *opt, float *rgb)
{
    RfDiffOptions def = rf_diff_options_default();
    const RfDiffOptions *o = opt ? opt : &def;
    double t;
    if (!isfinite(e)) { /* NaN/Inf: never a valid radiance */
        rgb[0] = 1.0f, rgb[1] = 0.0f, rgb[2] = 1.0f;
    } else if (e > o->fail) { /* dark red just above fail, full red at 100 x fail */
        t = o->fail > 0.0 ? fmin(1.0, log10(e / o->fail) / 2.0) : 1.0;
        rgb[0] = (float)(0.55 + 0.45 * t), rgb[1] = rgb[2] = 0.0f;
    } else if (e > o->warn) { /* yellow, brighter toward fail */
        t = (e - o->warn) / (o->fail - o->warn);
        rgb[0] = (float)(0.55 + 0.45 * t), rgb[1] = (float)(0.5 + 0.4 * t), rgb[2] = 0.05f;
    } else if (e > 0.0) { /* quiet grey-blue on a log scale 1e-6 .. warn: rounding noise */
        t = o->warn > 1e-6 ? (log10(fmax(e, 1e-6)) + 6.0) / (log10(o->warn) + 6.0) : 1.0;
        rgb[0] = (float)(0.1 + 0.06 * t), rgb[1] = (float)(0.12 + 0.08 * t), rgb[2] = (float)(0.2 + 0.14 * t);
    } else {
        rgb[0] = rgb[1] = rgb[2] = 0.0f;
    }
}

enum { MIN_WIDTH = 384, MAX_SCALE = 8, BAND = 44, MAX_RINGS = 64 };

typedef struct {
    long fails;
    double worst;
    int worst_x, worst_y, scale;
} MapInfo;

static void text(cairo_t *cr, double x, double y, const char *s)
{
    cairo_move_to(cr, x, y);
    cairo_show_text(cr, s);
}

/* A swatch of the colours from error e0 to e1 (log steps), w x 12 at (x, y). */
static void swatch(cairo_t *cr, double x, double y, double w, double e0, double e1, const RfDiffOptions *o)
{
    for (int i = 0; i < (int)w; i++) {
        float c[3];
        double t = (i + 0.5) / w;
        rf_diff_heat_colour(e0 * pow(e1 / e0, t), o, c);
        cairo_set_source_rgb(cr, c[0], c[1], c[2]);
        cairo_rectangle(cr, x + i, y, 1, 12);
        cairo_fill(cr);
    }
}

/* The rings around failing pixels and the legend band, drawn over the map in place. 0 when cairo
 * cannot (a map wider or taller than cairo's 32767): the map then goes without them. */
static int annotate(RfImage *map, int band, const float *errs, int w, int h, const MapInfo *m, const RfDiffOptions *o)
{
    int W = map->width, H = map->height;
    cairo_surface_t *s = cairo_image_surface_create(CAIRO_FORMAT_RGB24, W, H);
    if (cairo_surface_status(s) != CAIRO_STATUS_SUCCESS) {
        cairo_surface_destroy(s);
        return 0;
    }
    unsigned char *data = cairo_image_surface_get_data(s);
    int stride = cairo_image_surface_get_stride(s);
    cairo_surface_flush(s);
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            const float *p = map->data + 3 * ((size_t)y * W + x);
            uint32_t v = (uint32_t)lrintf(p[0] * 255.0f) << 16 | (uint32_t)lrintf(p[1] * 255.0f) << 8 |
                         (uint32_t)lrintf(p[2] * 255.0f);
            memcpy(data + (size_t)y * stride + 4 * (size_t)x, &v, 4);
        }
    cairo_surface_mark_dirty(s);
    cairo_t *cr = cairo_create(s);
    double k = m->scale;
    if (m->fails > 0 && m->fails <= MAX_RINGS) { /* one failing pixel must not go unseen */
        cairo_set_source_rgb(cr, 0.0, 1.0, 1.0);
        cairo_set_line_width(cr, 2.0);
        for (int y = 0; y < h; y++)
            for (int x = 0; x < w; x++)
                if (!(errs[(size_t)y * w + x] <= o->fail)) {
                    cairo_new_sub_path(cr);
                    cairo_arc(cr, (x + 0.5) * k, (y + 0.5) * k, fmax(6.0, 2.5 * k), 0.0, 6.283185307179586);
                }
        cairo_stroke(cr);
    }
    double y0 = H - band;
    cairo_set_source_rgb(cr, 0.12, 0.12, 0.12);
    cairo_rectangle(cr, 0, y0, W, band);
    cairo_fill(cr);
    cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
    cairo_set_font_size(cr, 10.0);
    char buf[160];
    double col = W / 3.0, sw = 18.0, lo = fmin(1e-6, o->warn);
    swatch(cr, 6, y0 + 6, sw, lo, fmax(o->warn, lo * 1.0001), o);
    swatch(cr, 6 + col, y0 + 6, sw, fmax(o->warn, 1e-12) * 1.0001, fmax(o->fail, o->warn * 1.0002), o);
    swatch(cr, 6 + 2 * col, y0 + 6, sw, fmax(o->fail, 1e-12) * 1.0001, fmax(o->fail, 1e-12) * 100.0, o);
    cairo_set_source_rgb(cr, 0.95, 0.95, 0.95);
    snprintf(buf, sizeof buf, "<= warn %.3g", o->warn);
    text(cr, 10 + sw, y0 + 16, buf);
    snprintf(buf, sizeof buf, "<= fail %.3g", o->fail);
    text(cr, 10 + sw + col, y0 + 16, buf);
    text(cr, 10 + sw + 2 * col, y0 + 16, "> fail (to x100)");
    if (m->fails > 0)
        snprintf(buf, sizeof buf, "%ld pixel%s above fail (%.3g %%)%s; worst %.3g at (%d, %d)%s", m->fails,
                 m->fails == 1 ? "" : "s", 100.0 * (double)m->fails / ((double)w * h),
                 m->fails <= MAX_RINGS ? ", ringed" : "", m->worst, m->worst_x, m->worst_y,
                 o->edge_tolerant ? "; edge-tolerant" : "");
    else
        snprintf(buf, sizeof buf, "no pixel above fail; worst %.3g at (%d, %d)%s", m->worst, m->worst_x, m->worst_y,
                 o->edge_tolerant ? "; edge-tolerant" : "");
    text(cr, 6, y0 + 36, buf);
    cairo_destroy(cr);
    cairo_surface_flush(s);
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            uint32_t v;
            memcpy(&v, data + (size_t)y * stride + 4 * (size_t)x, 4);
            float *p = map->data + 3 * ((size_t)y * W + x);
            p[0] = (float)((v >> 16) & 0xff) / 255.0f, p[1] = (float)((v >> 8) & 0xff) / 255.0f;
            p[2] = (float)(v & 0xff) / 255.0f;
        }
    cairo_surface_destroy(s);
    return 1;
}

RfStatus rf_diff_heatmap(const RfImage *a, const RfImage *b, const unsigned char *mask, const RfDiffOptions *opt,
                         RfImage *out)
{
    RfDiffOptions def = rf_diff_options_default();
    const RfDiffOptions *o = opt ? opt : &def;
    out->data = NULL;
    if (a->width != b->width || a->height != b->height)
        return RF_ERR_DOMAIN;
    int w = a->width, h = a->height;
    MapInfo m = {0, 0.0, 0, 0, 1};
    while (w * m.scale < MIN_WIDTH && m.scale < MAX_SCALE)
        m.scale++;
    int band = w * m.scale >= 200 ? BAND : 0; /* too narrow for words: no legend */
    if ((size_t)w * m.scale * ((size_t)h * m.scale + band) > RF_IMAGE_MAX_PIXELS)
        m.scale = 1, band = 0;
    float *errs = malloc((size_t)w * h * sizeof *errs);
    RfStatus st = errs ? rf_image_alloc(out, w * m.scale, h * m.scale + band, 3) : RF_ERR_NOMEM;
    if (st != RF_OK) {
        free(errs);
        return st;
    }
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            double e = rf_diff_pixel_error(a, b, x, y, o->edge_tolerant, NULL, NULL);
            float c[3];
            errs[(size_t)y * w + x] = (float)e;
            if (!(e <= o->fail))
                m.fails++;
            if ((x == 0 && y == 0) || !(e <= m.worst))
                m.worst = e, m.worst_x = x, m.worst_y = y;
            rf_diff_heat_colour(e, o, c);
            if (mask && mask[(size_t)y * w + x])
                grey_out(c);
            for (int j = 0; j < m.scale; j++)
                for (int i = 0; i < m.scale; i++)
                    memcpy(out->data + 3 * (((size_t)y * m.scale + j) * out->width + (size_t)x * m.scale + i), c,
                           sizeof c);
        }
    if (band && !annotate(out, band, errs, w, h, &m, o)) /* no legend possible: the map alone */
        out->height = h * m.scale;
    free(errs);
    return RF_OK;
}

RfStatus rf_diff_depth_heatmap(const RfImage *da, const RfImage *db, const unsigned char *mask, RfImage *out)
{
    if (da->width != db->width || da->height != db->height)
        return RF_ERR_DOMAIN;
    RfStatus st = rf_image_alloc(out, da->width, da->height, 3);
    if (st != RF_OK)
        return st;
    for (size_t i = 0; i < (size_t)da->width * da->height; i++) {
        float za = da->data[i * da->channels], zb = db->data[i * db->channels], *px = out->data + 3 * i;
        if (isfinite(za) != isfinite(zb)) {
            px[0] = 1.0f, px[1] = 0.0f, px[2] = 1.0f;
        } else if (!isfinite(za)) {
            px[0] = px[1] = px[2] = 0.0f;
        } else {
            log_heat(zb > 0.0f ? fabs((double)za - (double)zb) / (double)zb : INFINITY, 1e-7, 0.1, px);
            if (mask && mask[i])
                grey_out(px);
        }
    }
    return RF_OK;
}

void rf_diff_heatmap_done(void)
{
    cairo_debug_reset_static_data();
    FcFini();
}
