/* Grading one submission (grade.h): verdict, reason, transfer-function and shift hints, score. */
#include "refray/grade.h"

#include "io_internal.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

const char *rf_grade_verdict_name(RfGradeVerdict v)
{
    static const char *const names[] = {"pass", "warn", "fail", "unreadable", "wrong size"};
    return (unsigned)v < 5 ? names[v] : "unknown";
}

double rf_grade_score(RfGradeVerdict v, double fail_share)
{
    double q = fail_share < 0.0 ? 0.0 : fail_share > 1.0 ? 1.0 : fail_share;
    switch (v) {
    case RF_GRADE_PASS: return 100.0;
    case RF_GRADE_WARN: return 90.0;
    case RF_GRADE_FAIL: return 80.0 * (1.0 - q);
    default: return 0.0;
    }
}

static double clamp01(double v)
{
    return isfinite(v) ? (v < 0.0 ? 0.0 : v > 1.0 ? 1.0 : v) : v; /* NaN/Inf stay, so that they fail */
}

/* out = three channels of src (grey copied to RGB, alpha dropped) mapped by f and clamped. */
typedef double (*Map)(double v, const void *ctx);
static RfStatus map_rgb(const RfImage *src, Map f, const void *ctx, RfImage *out)
{
    RfStatus st = rf_image_alloc(out, src->width, src->height, 3);
    if (st != RF_OK)
        return st;
    size_t n = (size_t)src->width * (size_t)src->height;
    for (size_t i = 0; i < n; i++)
        for (int c = 0; c < 3; c++) {
            double v = src->data[i * (size_t)src->channels + (size_t)(src->channels == 1 ? 0 : c)];
            out->data[3 * i + (size_t)c] = (float)clamp01(f(v, ctx));
        }
    return RF_OK;
}

static double as_stored(double v, const void *ctx)
{
    (void)ctx;
    return v;
}

static double encoded_with(double v, const void *ctx)
{
    return rf_io_encode_value(v, *(const RfPngOptions *)ctx);
}

RfStatus rf_grade_display(const RfImage *stored, int encoded, RfPngOptions enc, RfImage *out)
{
    return map_rgb(stored, encoded ? as_stored : encoded_with, &enc, out);
}

/* Appends printf text to the reason, "; " between parts. */
static void say(RfGrade *g, const char *fmt, ...)
{
    size_t n = strlen(g->reason);
    if (n > 0 && n + 2 < sizeof g->reason)
        memcpy(g->reason + n, "; ", 3), n += 2;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(g->reason + n, sizeof g->reason - n, fmt, ap);
    va_end(ap);
}

/* Which criterion, by how much, where. */
static void explain(RfGrade *g, const RfDiffStats *s, const RfDiffOptions *o)
{
    double pf = rf_diff_percent(s->above_fail, s), pw = rf_diff_percent(s->above_warn, s);
    if (s->nonfinite > 0)
        say(g, "%ld pixel%s NaN or Inf (e.g. at (%d, %d))", s->nonfinite, s->nonfinite == 1 ? "" : "s", s->max_x,
            s->max_y);
    int hard = s->nonfinite == 0 && s->max_abs > o->hardfail;
    if (hard)
        say(g, "worst pixel error %.3g at (%d, %d) above hardfail %.3g", s->max_abs, s->max_x, s->max_y, o->hardfail);
    if (pf > o->fail_percent && hard)
        say(g, "%.3g %% of pixels above fail %.3g (allowed %g %%)", pf, o->fail, o->fail_percent);
    else if (pf > o->fail_percent)
        say(g, "%.3g %% of pixels above fail %.3g (allowed %g %%), worst %.3g at (%d, %d)", pf, o->fail,
            o->fail_percent, s->max_abs, s->max_x, s->max_y);
    if (s->mean_abs > o->fail_mean)
        say(g, "mean error %.3g above fail-mean %.3g", s->mean_abs, o->fail_mean);
    if (g->reason[0] == '\0' && pw > o->warn_percent)
        say(g, "%.3g %% of pixels above warn %.3g (allowed %g %%), worst %.3g at (%d, %d)", pw, o->warn,
            o->warn_percent, s->max_abs, s->max_x, s->max_y);
}

/* A cause explains the submission when the submission under it passes or warns, or (lossy files)
 * its mean error drops below a fifth of the one it was graded with. */
static int explains(const RfDiffResult *cause, const RfDiffResult *as_graded)
{
    return cause->verdict != RF_DIFF_FAIL || cause->interior.mean_abs < 0.2 * as_graded->interior.mean_abs;
}

static void outcome(RfGrade *g, const char *fix, const RfDiffResult *r, const RfDiffResult *as_graded)
{
    if (r->verdict == RF_DIFF_PASS)
        say(g, "%s it would pass", fix);
    else if (r->verdict == RF_DIFF_WARN)
        say(g, "%s it would only warn", fix);
    else
        say(g, "%s it would match far better (mean error %.3g instead of %.3g)", fix, r->interior.mean_abs,
            as_graded->interior.mean_abs);
}

typedef struct {
    RfPngOptions curve; /* the curve the student may have used instead */
    int twice;          /* the expected curve applied twice */
    char what[96], fix[64];
} Cause;

/* The reference as the student would have written it with the cause's curve, in display values. */
typedef struct {
    const Cause *cause;
    int encoded;
    RfPngOptions enc;
} Prediction;

static double predicted(double v, const void *ctx)
{
    const Prediction *p = ctx;
    v = p->cause->twice ? rf_io_encode_value(rf_io_encode_value(v, p->enc), p->enc)
                        : rf_io_encode_value(v, p->cause->curve);
    return p->encoded ? v : rf_io_encode_value(v, p->enc); /* a linear file: shown with the expected curve */
}

static RfStatus predict(const RfImage *ref, const Cause *c, int encoded, RfPngOptions enc, RfImage *out)
{
    Prediction p = {c, encoded, enc};
    return map_rgb(ref, predicted, &p, out);
}

static void curve_name(RfPngOptions p, char *buf, size_t n)
{
    if (p.encoding == RF_PNG_SRGB)
        snprintf(buf, n, "sRGB");
    else if (p.encoding == RF_PNG_GAMMA)
        snprintf(buf, n, "gamma %g", p.gamma);
    else
        snprintf(buf, n, "no");
}

/* The transfer-function causes worth trying for this submission (at most 4). */
static int causes(int encoded, RfPngOptions enc, Cause *c)
{
    char want[32];
    int n = 0;
    curve_name(enc, want, sizeof want);
    memset(c, 0, 4 * sizeof *c);
    if (!encoded) {
        if (enc.encoding != RF_PNG_AS_IS) {
            c[n].curve = enc;
            snprintf(c[n].what, sizeof c[n].what, "looks like display-encoded (%s) values written to a linear file", want);
            snprintf(c[n].fix, sizeof c[n].fix, "with linear values");
            n++;
        }
        return n;
    }
    c[n].curve = (RfPngOptions){RF_PNG_AS_IS, 1.0, 8, NULL};
    snprintf(c[n].what, sizeof c[n].what, "looks like linear values written without %s encoding", want);
    snprintf(c[n].fix, sizeof c[n].fix, "with %s", want);
    n++;
    if (!(enc.encoding == RF_PNG_GAMMA && enc.gamma == 2.2)) {
        c[n].curve = (RfPngOptions){RF_PNG_GAMMA, 2.2, 8, NULL};
        snprintf(c[n].what, sizeof c[n].what, "looks like gamma 2.2 encoding instead of %s", want);
        snprintf(c[n].fix, sizeof c[n].fix, "with %s", want);
        n++;
    }
    if (enc.encoding != RF_PNG_SRGB) {
        c[n].curve = (RfPngOptions){RF_PNG_SRGB, 2.2, 8, NULL};
        snprintf(c[n].what, sizeof c[n].what, "looks like sRGB encoding instead of %s", want);
        snprintf(c[n].fix, sizeof c[n].fix, "with %s", want);
        n++;
    }
    if (enc.encoding != RF_PNG_AS_IS) {
        c[n].twice = 1;
        snprintf(c[n].what, sizeof c[n].what, "looks like the %s encoding applied twice", want);
        snprintf(c[n].fix, sizeof c[n].fix, "encoded once");
        n++;
    }
    return n;
}

static RfStatus transfer_hint(RfGrade *g, const RfImage *ref, const RfImage *sub_display, int encoded,
                              RfPngOptions enc, const RfDiffOptions *o)
{
    Cause c[4];
    int n = causes(encoded, enc, c), best = -1;
    RfDiffResult r, best_r;
    memset(&best_r, 0, sizeof best_r);
    char err[256];
    for (int k = 0; k < n; k++) {
        RfImage p;
        RfStatus st = predict(ref, &c[k], encoded, enc, &p);
        if (st != RF_OK)
            return st;
        st = rf_diff_images(sub_display, &p, NULL, NULL, o, &r, NULL, err, sizeof err);
        rf_image_free(&p);
        if (st != RF_OK)
            return st;
        if (explains(&r, &g->diff) && (best < 0 || r.verdict < best_r.verdict ||
                                       (r.verdict == best_r.verdict && r.interior.mean_abs < best_r.interior.mean_abs)))
            best = k, best_r = r;
    }
    if (best >= 0) {
        say(g, "%s", c[best].what);
        outcome(g, c[best].fix, &best_r, &g->diff);
        g->transfer_hint = 1;
    }
    return RF_OK;
}

/* A window of an image (three channels), w x h from (x0, y0). */
static RfStatus crop(const RfImage *src, int x0, int y0, int w, int h, RfImage *out)
{
    RfStatus st = rf_image_alloc(out, w, h, 3);
    if (st != RF_OK)
        return st;
    for (int y = 0; y < h; y++)
        memcpy(out->data + 3 * (size_t)y * (size_t)w,
               src->data + 3 * ((size_t)(y + y0) * (size_t)src->width + (size_t)x0), 3 * (size_t)w * sizeof(float));
    return RF_OK;
}

enum { SHIFT = 2 }; /* shifts looked for: up to 2 pixels each way */

static void say_shift(RfGrade *g, int dx, int dy, const RfDiffResult *r, const RfDiffResult *at_zero)
{
    char buf[96] = "";
    size_t n = 0;
    if (dx)
        n += (size_t)snprintf(buf, sizeof buf, "%d pixel%s %s", abs(dx), abs(dx) == 1 ? "" : "s", dx > 0 ? "right" : "left");
    if (dy)
        snprintf(buf + n, sizeof buf - n, "%s%d pixel%s %s", dx ? " and " : "", abs(dy), abs(dy) == 1 ? "" : "s",
                 dy > 0 ? "down" : "up");
    say(g, "the whole image is shifted by %s", buf);
    outcome(g, "moved back", r, at_zero);
}

/* The submission against the reference moved by (dx, dy), away from a border of SHIFT pixels. */
static RfStatus shift_hint(RfGrade *g, const RfImage *ref, const RfImage *sub, const RfDiffOptions *o)
{
    int w = ref->width - 2 * SHIFT, h = ref->height - 2 * SHIFT, best_x = 0, best_y = 0;
    if (w < 4 || h < 4)
        return RF_OK;
    RfImage a, b;
    RfDiffResult r, zero, best;
    memset(&zero, 0, sizeof zero), memset(&best, 0, sizeof best);
    char err[256];
    RfStatus st = crop(sub, SHIFT, SHIFT, w, h, &a);
    if (st != RF_OK)
        return st;
    for (int dy = -SHIFT; dy <= SHIFT && st == RF_OK; dy++)
        for (int dx = -SHIFT; dx <= SHIFT && st == RF_OK; dx++) {
            st = crop(ref, SHIFT - dx, SHIFT - dy, w, h, &b);
            if (st == RF_OK)
                st = rf_diff_images(&a, &b, NULL, NULL, o, &r, NULL, err, sizeof err);
            rf_image_free(&b);
            if (st != RF_OK)
                break;
            if (dx == 0 && dy == 0)
                zero = r;
            else if ((best_x == 0 && best_y == 0) || r.verdict < best.verdict ||
                     (r.verdict == best.verdict && r.interior.mean_abs < best.interior.mean_abs))
                best = r, best_x = dx, best_y = dy;
        }
    rf_image_free(&a);
    if (st == RF_OK && zero.verdict != RF_DIFF_PASS && explains(&best, &zero) && best.verdict <= zero.verdict &&
        best.interior.mean_abs < zero.interior.mean_abs) {
        g->shift_x = best_x, g->shift_y = best_y;
        say_shift(g, best_x, best_y, &best, &zero);
    }
    return st;
}

RfStatus rf_grade_image(const RfImage *ref_linear, const RfImage *ref_display, int encoded, const RfImage *sub_display,
                        RfPngOptions enc, const RfDiffOptions *opt, RfGrade *g)
{
    RfDiffOptions def = rf_diff_options_default();
    const RfDiffOptions *o = opt ? opt : &def;
    char err[256];
    memset(g, 0, sizeof *g);
    if (sub_display->width != ref_display->width || sub_display->height != ref_display->height) {
        g->verdict = RF_GRADE_SIZE;
        say(g, "%d x %d, the reference is %d x %d", sub_display->width, sub_display->height, ref_display->width,
            ref_display->height);
        return RF_OK;
    }
    RfStatus st = rf_diff_images(sub_display, ref_display, NULL, NULL, o, &g->diff, NULL, err, sizeof err);
    if (st != RF_OK)
        return st;
    const RfDiffStats *s = &g->diff.interior;
    g->verdict = (RfGradeVerdict)g->diff.verdict;
    g->score = rf_grade_score(g->verdict, s->pixels ? (double)s->above_fail / (double)s->pixels : 0.0);
    if (g->verdict == RF_GRADE_PASS)
        return RF_OK;
    explain(g, s, o);
    st = transfer_hint(g, ref_linear, sub_display, encoded, enc, o);
    if (st == RF_OK && !g->transfer_hint)
        st = shift_hint(g, ref_display, sub_display, o);
    return st;
}
