/* refray: image comparison (issue 5), shared by `refray diff`, the tests and the HTML report.
 *
 * Metrics over RGB channel values (A = the image under test, B = the reference):
 *   max_abs  = max |A - B|, mean_abs = mean |A - B|, rmse = sqrt(mean (A - B)^2),
 *   psnr     = 20 log10(1 / rmse) dB (peak 1; +inf for identical images),
 *   rel_mse  = mean (A - B)^2 / (B^2 + 0.01) (eps 0.01 as adobe/sbmc; no factor 0.5).
 * A pixel's error is its largest channel error; the shares count pixels above a threshold.
 * Silhouettes: pixels where either depth image is discontinuous (rf_diff_silhouettes); the same
 * metrics over the remaining pixels are the "interior" ones, and the verdict uses them.
 *
 * Verdict (OpenImageIO idiff's ladder, refray's defaults tuned to the comparator's accuracy
 * goal): FAIL when a value is NaN or Inf on either side, a pixel error exceeds hardfail, more than
 * fail_percent % of the pixels exceed fail, or mean_abs exceeds fail_mean; otherwise WARN when
 * more than warn_percent % exceed warn; otherwise PASS. */
#ifndef REFRAY_DIFF_H
#define REFRAY_DIFF_H

#include <stddef.h>

#include "refray/image.h"
#include "refray/status.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct {
    double warn, warn_percent;  /* defaults 1e-4, 0.1 % */
    double fail, fail_percent;  /* defaults 1/255 (0.00392), 0.1 % */
    double fail_mean;           /* default 1e-4; INFINITY: off */
    double hardfail;            /* default INFINITY (off) */
    double depth_edge;          /* silhouette threshold, rf_diff_silhouettes; default 0.01 */
    int edge_tolerant;          /* default 0; 1: a pixel's error is the smallest over B's 3x3
                                   neighbourhood (rf_diff_pixel_error): aliasing at silhouettes
                                   and half-pixel offsets are forgiven */
} RfDiffOptions;

RfDiffOptions rf_diff_options_default(void);

typedef struct {
    long pixels;                /* pixels compared */
    long nonfinite;             /* pixels with NaN or Inf in either image (never a valid radiance) */
    double max_abs, mean_abs, rmse, psnr, rel_mse;
    int max_x, max_y;           /* where max_abs is (row 0 at the top); -1 when no pixel */
    long above_255, above_warn, above_fail; /* pixels whose error exceeds 1/255, warn, fail */
} RfDiffStats;

typedef enum { RF_DIFF_PASS = 0, RF_DIFF_WARN = 1, RF_DIFF_FAIL = 2 } RfDiffVerdict;

typedef struct {
    RfDiffStats all, interior;  /* interior = all when no depth is given */
    int has_depth;
    long silhouette;            /* pixels masked as silhouettes */
    long coverage_mismatch;     /* depth finite in one image, background (inf) in the other */
    double depth_max_rel, depth_mean_rel; /* |zA - zB| / zB over interior pixels both hit */
    RfDiffVerdict verdict;
} RfDiffResult;

/* A pixel's error: the largest |A - B| over its channels (the first three, or one), INFINITY when
 * a value is NaN or Inf. edge_tolerant: the smallest such error between A's pixel (x, y) and the
 * pixels of B's 3x3 neighbourhood of (x, y) that lie inside the image. *bx, *by (may be NULL) get
 * the B pixel that gave it. A and B have the same size. */
double rf_diff_pixel_error(const RfImage *a, const RfImage *b, int x, int y, int edge_tolerant, int *bx, int *by);

/* Share of s.pixels in percent (0 for no pixels). */
double rf_diff_percent(long count, const RfDiffStats *s);
const char *rf_diff_verdict_name(RfDiffVerdict v); /* "PASS", "WARN", "FAIL" */

/* Marks (sets to 1, never clears) the silhouette pixels of a one-channel depth image (linear
 * eye-space depth, +inf = background) in mask[width * height]: every pixel of a horizontal or
 * vertical run of three whose inverse depths 1/z (0 for background) have a second difference
 * above edge * the run's largest 1/z. 1/z is linear across a plane in screen space, so planes
 * never trip it; a jump between objects or onto the background always does. */
void rf_diff_silhouettes(const RfImage *depth, double edge, unsigned char *mask);

/* Compares a with b (same size; the first three channels, or one channel each). da, db: depth
 * images of the same size or NULL (both or neither). mask_out (may be NULL) gets the silhouette
 * mask (width * height bytes). RF_ERR_DOMAIN with a message for mismatched sizes/channels. */
RfStatus rf_diff_images(const RfImage *a, const RfImage *b, const RfImage *da, const RfImage *db,
                        const RfDiffOptions *opt, RfDiffResult *res, unsigned char *mask_out,
                        char *err, size_t errsz);

/* The error heat map, scaled to the verdict's thresholds (opt: warn, fail, edge_tolerant; NULL:
 * the defaults), per pixel the error of rf_diff_pixel_error: 0 black; up to warn dark grey-blue,
 * brighter on a log scale from 1e-6 to warn (so that rounding noise of a passing image stays
 * quiet); warn..fail yellow, brighter toward fail; above fail red, dark just above fail and full
 * at 100 x fail; NaN/Inf magenta. Silhouette pixels (mask != NULL) are greyed. The pixels are
 * enlarged (nearest neighbour) by the integer factor that makes the map at least 384 wide (at
 * most 8); when at most 64 pixels fail each gets a cyan ring, so that a single one is seen; a
 * legend band below names the colours, the thresholds, the failing count and the worst pixel.
 * Display-ready 8-bit RGB values (write with RF_PNG_AS_IS). */
RfStatus rf_diff_heatmap(const RfImage *a, const RfImage *b, const unsigned char *mask, const RfDiffOptions *opt,
                         RfImage *out);
/* Frees the font caches that the legends' text left in cairo and fontconfig (they would be seen
 * as leaks at exit); call it once when no more heat maps are drawn, never while one is. */
void rf_diff_heatmap_done(void);
/* The heat map's colour for one error (three floats), without the enlargement and the legend. */
void rf_diff_heat_colour(double e, const RfDiffOptions *opt, float *rgb);
/* The depth comparison: |zA - zB| / zB on a log scale 1e-7 .. 0.1, magenta where only one image
 * hits something, black where neither does, grey for silhouettes. */
RfStatus rf_diff_depth_heatmap(const RfImage *da, const RfImage *db, const unsigned char *mask,
                               RfImage *out);

/* A statistical test of two noisy renders (Mitsuba 3's recipe, shared/research/ecosystem.md):
 * per pixel and channel z = (a - b) / sqrt(va + vb), va and vb the variances of the two pixel
 * means (refray render --variance), and the two-sided p-value erfc(|z| / sqrt 2); a pixel's p is
 * the smallest of its channels' times 3 (Bonferroni over the channels, at most 1). A pixel
 * accepts when p > alpha_pixel = 1 - (1 - alpha)^(1 / pixels) (Sidak over the pixels); the test
 * passes when at least `accept` of the pixels do (0.9975). A pixel with va + vb = 0 accepts when
 * a = b exactly. pvalues (may be NULL) gets each pixel's p (one channel). */
typedef struct {
    long pixels, accepted;
    double alpha_pixel;  /* the Sidak-corrected level */
    double min_p;        /* the smallest pixel p, at (min_x, min_y) */
    int min_x, min_y;
    int pass;
} RfStatResult;
RfStatus rf_diff_stat(const RfImage *a, const RfImage *b, const RfImage *va, const RfImage *vb, double alpha,
                      double accept, RfStatResult *out, RfImage *pvalues, char *err, size_t errsz);

#ifdef __cplusplus
}
#endif

#endif
