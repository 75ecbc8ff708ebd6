/* `refray diff`: compares two images (EXR or PNG) with the metrics of diff.h, optionally away from
 * silhouettes given depth images, writes heatmaps, and exits like OpenImageIO's idiff. */
#include "cli.h"
#include "args.h"
#include "diff_args.h"
#include "exit_codes.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "refray/diff.h"
#include "refray/image.h"
#include "refray/transfer.h"

enum {
    OPT_HEATMAP = RF_OPT_ID, OPT_DEPTH_HEATMAP, OPT_DEPTH_A, OPT_DEPTH_B, OPT_DEPTH_EDGE, OPT_AS_IS, OPT_SPACE, OPT_KV, OPT_STAT, OPT_VAR_A,
    OPT_VAR_B, OPT_ALPHA, OPT_ACCEPT
};

static const RfOpt diff_opts[] = {
    {"heatmap", OPT_HEATMAP, "FILE", "the per-pixel error as a heat map (.png or .exr); with --stat -log10 p", NULL},
    {"depth-a", OPT_DEPTH_A, "DA.exr", "A's depth image (refray render --depth-out): silhouettes are masked", NULL},
    {"depth-b", OPT_DEPTH_B, "DB.exr", "B's depth image (with --depth-a)", NULL},
    {"depth-heatmap", OPT_DEPTH_HEATMAP, "FILE", "the relative depth error as a heat map (.png or .exr)", NULL},
    {"depth-edge", OPT_DEPTH_EDGE, "E", "relative depth jump that makes a silhouette pixel", "a number >= 0"},
    {"as-is", OPT_AS_IS, NULL, "PNG values as stored (no decoding curve)", NULL},
    {"space", OPT_SPACE, "linear|display", "compare linear or display (encoded) values (default: display for a PNG)",
     "linear or display"},
    {"kv", OPT_KV, NULL, "key=value lines (for scripts)", NULL},
    {"stat", OPT_STAT, NULL, "per-pixel z-test of two noisy renders with their variances", NULL},
    {"var-a", OPT_VAR_A, "VA.exr", "with --stat: A's variance (refray render --variance)", NULL},
    {"var-b", OPT_VAR_B, "VB.exr", "with --stat: B's variance", NULL},
    {"alpha", OPT_ALPHA, "A", "with --stat: the significance level over all pixels (default 0.01)",
     "a number in (0, 1)"},
    {"accept", OPT_ACCEPT, "S", "with --stat: PASS when this share of the pixels accepts (default 0.9975)",
     "a number in [0, 1]"},
    RF_OPT_TABLE_END,
};

static const RfOpt *const diff_tables[] = {diff_opts, rf_opts_diff, rf_opts_png, NULL};

static const RfCommand diff_cmd = {
    "refray diff",
    "refray diff [options] A B\n"
    "       refray diff --stat --var-a VA.exr --var-b VB.exr [options] A B\n",
    "A is the image under test, B the reference: EXR or HDR (linear), or PNG, PPM/PGM (P1-P6),\n"
    "JPEG, TIFF, BMP, TGA (codes, decoded with --gamma G, default 2.2, or --srgb; a float\n"
    "TIFF is linear). --space display compares the gamma/sRGB-encoded values, so that one\n"
    "8-bit code is 1/255 (the default when A or B holds codes: grading a student's image);\n"
    "linear compares linear values (the default for two EXRs). --edge-tolerant forgives\n"
    "aliasing at silhouettes and half-pixel offsets (the best match in B's 3x3 neighbourhood).\n"
    "With depth images, pixels at depth discontinuities (silhouettes) of either are\n"
    "reported separately and the verdict uses the others.\n",
    diff_tables,
    "FAIL: more than --failpercent % (0.1) of pixels differ by more than --fail (1/255),\n"
    "      the mean difference exceeds --fail-mean (1e-4), a pixel exceeds --hardfail\n"
    "      (off), or a value is NaN/Inf on one side; WARN: more than --warnpercent % (0.1)\n"
    "      differ by more than --warn (1e-4); otherwise PASS. In display values the defaults\n"
    "      allow 8-bit rounding: --fail-mean 1/255, --warn 0.5/255.\n"
    "--stat: two noisy renders (EXR) with their variances (refray render --variance) by a\n"
    "      per-pixel z-test: |a - b| / sqrt(va + vb) per channel, the pixel's p the smallest\n"
    "      channel's times 3; a pixel accepts when p > 1 - (1 - A)^(1/pixels) (A = --alpha,\n"
    "      0.01: Sidak over the pixels); PASS when at least --accept (0.9975) of the pixels\n"
    "      accept (Mitsuba 3's test), else FAIL\n"
    "exit (idiff's): 0 pass, 1 warn, 2 fail, 3 size or channel mismatch, 4 file error,\n"
    "5 usage (README: Exit codes)\n",
};

/* linear -> display values with the PNG curve, clamped to [0, 1] like a PNG writer would */
static void encode_display(RfImage *img, RfPngOptions p)
{
    size_t n = (size_t)img->width * img->height * img->channels;
    for (size_t i = 0; i < n; i++) {
        double v = img->data[i];
        if (img->channels == 4 && i % 4 == 3)
            continue;
        if (p.encoding == RF_PNG_GAMMA)
            v = rf_gamma_encode(v, p.gamma);
        else if (p.encoding == RF_PNG_SRGB)
            v = rf_srgb_encode(v);
        if (!isnan(v))
            v = v < 0.0 ? 0.0 : v > 1.0 ? 1.0 : v;
        img->data[i] = (float)v;
    }
}

static void print_stats(const char *title, const char *key, const RfDiffStats *s, const RfDiffOptions *o, int kv)
{
    if (kv) {
        printf("%s.pixels=%ld\n%s.nonfinite=%ld\n%s.max_abs=%.9g\n%s.max_x=%d\n%s.max_y=%d\n"
               "%s.mean_abs=%.9g\n%s.rmse=%.9g\n%s.psnr=%.6g\n%s.rel_mse=%.9g\n"
               "%s.pct_above_255=%.6g\n%s.pct_above_warn=%.6g\n%s.pct_above_fail=%.6g\n",
               key, s->pixels, key, s->nonfinite, key, s->max_abs, key, s->max_x, key, s->max_y, key,
               s->mean_abs, key, s->rmse, key, s->psnr, key, s->rel_mse, key,
               rf_diff_percent(s->above_255, s), key, rf_diff_percent(s->above_warn, s), key,
               rf_diff_percent(s->above_fail, s));
        return;
    }
    printf("%s (%ld pixels):\n", title, s->pixels);
    printf("  max abs error   %.6g at (%d, %d)\n", s->max_abs, s->max_x, s->max_y);
    printf("  mean abs error  %.6g\n  RMSE            %.6g\n  PSNR            %.2f dB\n", s->mean_abs, s->rmse,
           s->psnr);
    printf("  relMSE          %.6g   (mean (A-B)^2 / (B^2 + 0.01))\n", s->rel_mse);
    printf("  above 1/255     %ld (%.4f %%)\n", s->above_255, rf_diff_percent(s->above_255, s));
    /* the threshold, then the count: a blank between them always (%-9g alone may fill its field) */
    printf("  above warn %-9g %ld (%.4f %%)\n", o->warn, s->above_warn, rf_diff_percent(s->above_warn, s));
    printf("  above fail %-9g %ld (%.4f %%)\n", o->fail, s->above_fail, rf_diff_percent(s->above_fail, s));
    if (s->nonfinite)
        printf("  NaN/Inf         %ld pixels\n", s->nonfinite);
}

/* A heat map: a PNG of its values as they are, or an EXR of the same values. */
static int write_heatmap(const char *path, const RfImage *img, char *err, size_t errsz)
{
    RfPngOptions p = {RF_PNG_AS_IS, 1.0, 8, NULL};
    RfExrOptions e = {RF_EXR_ZIP, 0, NULL, 0, 0, 0, 0};
    return rf_arg_write_image(path, img, NULL, 0, e, p, err, errsz) == RF_OK;
}

/* refray diff --stat (rf_diff_stat): exit 0 pass, 2 fail, 3 mismatch, 4 file error */
static int stat_test(const char *pa, const char *pb, const char *pva, const char *pvb, double alpha, double accept,
                     const char *heatmap, int kv)
{
    char err[1024];
    const char *outs[1] = {heatmap}, *ins[4] = {pa, pb, pva, pvb};
    int bad = rf_arg_outputs_check("refray diff", outs, 1, ins, 4);
    if (bad)
        return bad;
    RfImage im[4], pv = {0, 0, 0, NULL};
    const char *paths[4] = {pa, pb, pva, pvb};
    int rc = RF_EXIT_FILE, n = 0;
    for (; n < 4; n++)
        if (rf_exr_read(paths[n], &im[n], err, sizeof err) != RF_OK) {
            fprintf(stderr, "refray diff: %s\n", err);
            goto done;
        }
    RfStatResult r;
    RfStatus st = rf_diff_stat(&im[0], &im[1], &im[2], &im[3], alpha, accept, &r, heatmap ? &pv : NULL, err, sizeof err);
    if (st != RF_OK) {
        fprintf(stderr, "refray diff: %s\n", err);
        rc = st == RF_ERR_DOMAIN ? RF_EXIT_SIZE : RF_EXIT_FILE;
        goto done;
    }
    if (kv)
        printf("pixels=%ld\naccepted=%ld\naccepted_share=%.9g\nalpha=%.9g\nalpha_pixel=%.9g\nmin_p=%.9g\n"
               "min_p_x=%d\nmin_p_y=%d\nverdict=%s\n",
               r.pixels, r.accepted, (double)r.accepted / (double)r.pixels, alpha, r.alpha_pixel, r.min_p, r.min_x,
               r.min_y, r.pass ? "PASS" : "FAIL");
    else
        printf("A: %s (variance %s)\nB: %s (variance %s)\nper-pixel z-test: %ld of %ld pixels accept (%.4f %%, "
               "needed %.4f %%) at the Sidak level %.3g (alpha %g); smallest p %.3g at (%d, %d)\nverdict: %s\n",
               pa, pva, pb, pvb, r.accepted, r.pixels, 100.0 * (double)r.accepted / (double)r.pixels, 100.0 * accept,
               r.alpha_pixel, alpha, r.min_p, r.min_x, r.min_y, r.pass ? "PASS" : "FAIL");
    rc = r.pass ? RF_EXIT_OK : RF_EXIT_FAIL;
    if (heatmap) { /* -log10 p, white at p = 1e-6 */
        RfImage h;
        if (rf_image_alloc(&h, pv.width, pv.height, 3) == RF_OK) {
            for (size_t i = 0; i < (size_t)pv.width * (size_t)pv.height; i++) {
                double t = fmin(1.0, -log10(fmax((double)pv.data[i], 1e-300)) / 6.0);
                h.data[3 * i] = (float)fmin(1.0, 3.0 * t);
                h.data[3 * i + 1] = (float)fmin(1.0, fmax(0.0, 3.0 * t - 1.0));
                h.data[3 * i + 2] = (float)fmin(1.0, fmax(0.0, 3.0 * t - 2.0));
            }
            if (!write_heatmap(heatmap, &h, err, sizeof err)) {
                fprintf(stderr, "refray diff: %s\n", err);
                rc = RF_EXIT_FILE;
            }
            rf_image_free(&h);
        }
    }
done:
    for (int k = 0; k < n; k++)
        rf_image_free(&im[k]);
    rf_image_free(&pv);
    return rc;
}

int rf_cmd_diff(int argc, char **argv)
{
    const char *pa = NULL, *pb = NULL, *heatmap = NULL, *depth_heatmap = NULL, *pda = NULL, *pdb = NULL;
    RfDiffOptions o = rf_diff_options_default();
    RfPngOptions popt = {RF_PNG_GAMMA, 2.2, 8, NULL};
    int kv = 0, space = -1; /* -1 auto, 0 linear, 1 display */
    int stat = 0;
    unsigned set = 0; /* the thresholds given (diff_args.h) */
    const char *pva = NULL, *pvb = NULL;
    double alpha = 0.01, accept = 0.9975;
    RfOptParser p;
    int key;
    rf_opt_init(&p, &diff_cmd, argc, argv);
    while ((key = rf_opt_next(&p)) != RF_OPT_DONE) {
        const char *v = p.value;
        int ok = 1;
        switch (key) {
        case RF_OPT_EXIT:
            return p.exit_code;
        case OPT_HEATMAP: heatmap = v; break;
        case OPT_DEPTH_HEATMAP: depth_heatmap = v; break;
        case OPT_DEPTH_A: pda = v; break;
        case OPT_DEPTH_B: pdb = v; break;
        case OPT_DEPTH_EDGE: ok = rf_arg_nonneg(v, &o.depth_edge); break;
        case OPT_AS_IS: popt.encoding = RF_PNG_AS_IS; break;
        case OPT_SPACE:
            space = strcmp(v, "linear") == 0 ? 0 : strcmp(v, "display") == 0 ? 1 : -2;
            ok = space >= 0;
            break;
        case OPT_KV: kv = 1; break;
        case OPT_STAT: stat = 1; break;
        case OPT_VAR_A: pva = v; break;
        case OPT_VAR_B: pvb = v; break;
        case OPT_ALPHA: ok = rf_arg_nonneg(v, &alpha) && alpha > 0.0 && alpha < 1.0; break;
        case OPT_ACCEPT: ok = rf_arg_nonneg(v, &accept) && accept <= 1.0; break;
        default: {
            int r = rf_arg_diff(key, v, &o, &set);
            ok = r != 0 ? r > 0 : rf_arg_shared(key, v, NULL, &popt) > 0;
        }
        }
        if (!ok)
            return rf_opt_bad_value(&p);
    }
    char **ops;
    int n = rf_opt_operands(&p, &ops);
    if (n < 2)
        return rf_opt_usage_error(&diff_cmd, "%s", n == 0 ? "missing the images A and B" : "missing the reference image B");
    if (n > 2)
        return rf_opt_usage_error(&diff_cmd, "two images only: '%s' is a third", ops[2]);
    pa = ops[0], pb = ops[1];
    if ((heatmap && !rf_arg_image_format("refray diff", "--heatmap", heatmap, RF_IMAGE_PNG | RF_IMAGE_EXR)) ||
        (depth_heatmap &&
         !rf_arg_image_format("refray diff", "--depth-heatmap", depth_heatmap, RF_IMAGE_PNG | RF_IMAGE_EXR)))
        return RF_EXIT_USAGE;
    if (stat || pva || pvb) {
        if (!stat || !pva || !pvb)
            return rf_opt_usage_error(&diff_cmd, "--stat takes A, B, --var-a and --var-b");
        return stat_test(pa, pb, pva, pvb, alpha, accept, heatmap, kv);
    }
    if ((!pda) != (!pdb) || (depth_heatmap && !pda))
        return rf_opt_usage_error(&diff_cmd, "--depth-a and --depth-b go together (and --depth-heatmap needs them)");
    { /* heatmaps: writable, and never one of the images compared */
        const char *outs[2] = {heatmap, depth_heatmap}, *ins[4] = {pa, pb, pda, pdb};
        int bad = rf_arg_outputs_check("refray diff", outs, 2, ins, 4);
        if (bad)
            return bad;
    }
    char err[1024];
    RfImage ia, ib, da, db, heat;
    memset(&heat, 0, sizeof heat), memset(&ia, 0, sizeof ia), memset(&ib, 0, sizeof ib), memset(&da, 0, sizeof da), memset(&db, 0, sizeof db);
    int rc = 0;
    RfImageSource sa, sb;
    if (rf_image_read_source(pa, popt, &ia, &sa, err, sizeof err) != RF_OK ||
        rf_image_read_source(pb, popt, &ib, &sb, err, sizeof err) != RF_OK ||
        (pda && (rf_image_read(pda, popt, &da, err, sizeof err) != RF_OK ||
                 rf_image_read(pdb, popt, &db, err, sizeof err) != RF_OK))) {
        fprintf(stderr, "refray diff: %s\n", err);
        rc = RF_EXIT_FILE;
        goto done;
    }
    if (space < 0) /* a PNG, PPM, JPEG, ... (integer codes) on either side: a student's image */
        space = sa.encoded || sb.encoded;
    if (space == 1) {
        rf_arg_diff_display(&o, set);
        encode_display(&ia, popt);
        encode_display(&ib, popt);
    }
    RfDiffResult res;
    unsigned char *mask = malloc((size_t)ia.width * ia.height + 1);
    if (!mask) {
        fprintf(stderr, "refray diff: out of memory\n");
        rc = RF_EXIT_FILE;
        goto done;
    }
    RfStatus st = rf_diff_images(&ia, &ib, pda ? &da : NULL, pdb ? &db : NULL, &o, &res, mask, err, sizeof err);
    if (st != RF_OK) {
        fprintf(stderr, "refray diff: %s\n", err);
        free(mask);
        rc = st == RF_ERR_DOMAIN ? RF_EXIT_SIZE : RF_EXIT_FILE;
        goto done;
    }
    if (kv) {
        printf("a=%s\nb=%s\nwidth=%d\nheight=%d\nspace=%s\n", pa, pb, ia.width, ia.height, space ? "display" : "linear");
    } else {
        printf("A: %s\nB: %s (reference)\n%d x %d, compared in %s values\n", pa, pb, ia.width, ia.height,
               space ? "display (encoded)" : "linear");
    }
    print_stats("all pixels", "all", &res.all, &o, kv);
    if (res.has_depth) {
        print_stats("away from silhouettes", "interior", &res.interior, &o, kv);
        if (kv)
            printf("silhouette=%ld\ncoverage_mismatch=%ld\ndepth_max_rel=%.9g\ndepth_mean_rel=%.9g\n", res.silhouette,
                   res.coverage_mismatch, res.depth_max_rel, res.depth_mean_rel);
        else
            printf("silhouettes: %ld pixels masked (%.3f %%); coverage differs at %ld pixels\n"
                   "depth away from silhouettes: max rel error %.3g, mean %.3g\n",
                   res.silhouette, 100.0 * res.silhouette / ((double)ia.width * ia.height), res.coverage_mismatch,
                   res.depth_max_rel, res.depth_mean_rel);
    }
    printf(kv ? "verdict=%s\n" : "verdict: %s\n", rf_diff_verdict_name(res.verdict));
    rc = (int)res.verdict;
    if (heatmap) {
        if (rf_diff_heatmap(&ia, &ib, res.has_depth ? mask : NULL, &o, &heat) != RF_OK || !write_heatmap(heatmap, &heat, err, sizeof err)) {
            fprintf(stderr, "refray diff: %s\n", heat.data ? err : "cannot make the heatmap");
            rc = RF_EXIT_FILE;
        }
        rf_image_free(&heat);
        rf_diff_heatmap_done();
    }
    if (depth_heatmap && rc != RF_EXIT_FILE) {
        if (rf_diff_depth_heatmap(&da, &db, mask, &heat) != RF_OK || !write_heatmap(depth_heatmap, &heat, err, sizeof err)) {
            fprintf(stderr, "refray diff: %s\n", heat.data ? err : "cannot make the depth heatmap");
            rc = RF_EXIT_FILE;
        }
        rf_image_free(&heat);
    }
    free(mask);
done:
    rf_image_free(&ia), rf_image_free(&ib), rf_image_free(&da), rf_image_free(&db);
    return rc;
}
