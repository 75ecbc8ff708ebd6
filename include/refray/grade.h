/* refray: grading one student image against a reference (issue 16), `refray grade`'s core.
 *
 * The submission is judged in display values, as `refray diff` judges a PNG: its stored integer
 * codes scaled to [0, 1] (PNG, PPM, JPEG, BMP, TIFF, ...), or for a linear file (EXR, HDR, float
 * TIFF) its values encoded with the chosen curve and clamped; the reference (linear) is encoded
 * the same way. Then rf_diff_images with the diff thresholds gives pass, warn or fail.
 *
 * When it does not pass, the reason names the criterion, by how much and where, and looks for
 * two common causes:
 *  - a transfer-function mix-up: the reference encoded with another curve (none: linear values
 *    written as codes; gamma 2.2 instead of sRGB or back; the curve applied twice; for a linear
 *    file, display-encoded values written into it) matches the submission;
 *  - a whole-image shift by up to two pixels: the submission matches the reference moved by
 *    (dx, dy) away from the border.
 * A cause is named when the submission under it passes or warns, or when its mean error drops
 * below a fifth (lossy formats such as JPEG never pass outright).
 *
 * Score (monotone in the verdict, then in the share of failing pixels): 100 pass, 90 warn,
 * fail 80 x (1 - q) with q the fraction of pixels above --fail, 0 unreadable or wrong size. */
#ifndef REFRAY_GRADE_H
#define REFRAY_GRADE_H

#include "refray/diff.h"
#include "refray/image.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum {
    RF_GRADE_PASS, RF_GRADE_WARN, RF_GRADE_FAIL, RF_GRADE_UNREADABLE, RF_GRADE_SIZE
} RfGradeVerdict;

/* "pass", "warn", "fail", "unreadable", "wrong size" */
const char *rf_grade_verdict_name(RfGradeVerdict v);

/* The score of a verdict with `fail_share` (0..1) of the pixels above --fail. */
double rf_grade_score(RfGradeVerdict v, double fail_share);

typedef struct {
    RfGradeVerdict verdict;
    double score;
    char reason[640];   /* empty on pass */
    RfDiffResult diff;  /* the comparison in display values */
    int shift_x, shift_y;     /* the shift found (content moved right/down), 0 0 when none */
    int transfer_hint;        /* 1 when the reason names a transfer-function mix-up */
} RfGrade;

/* Display values (three channels, clamped to [0, 1]) of an image read with RF_PNG_AS_IS: stored
 * codes as they are when `encoded`, else the values encoded with enc's curve. Grey becomes RGB,
 * alpha is dropped. */
RfStatus rf_grade_display(const RfImage *stored, int encoded, RfPngOptions enc, RfImage *out);

/* Grades a submission: ref_linear the reference (linear), ref_display its display values
 * (rf_grade_display(ref_linear, 0, enc)), sub_display the submission's display values
 * (rf_grade_display of the file read with RF_PNG_AS_IS, `encoded` from its RfImageSource). A different size gives
 * RF_GRADE_SIZE with the reason; RF_ERR_NOMEM when memory runs out. */
RfStatus rf_grade_image(const RfImage *ref_linear, const RfImage *ref_display, int encoded, const RfImage *sub_display,
                        RfPngOptions enc, const RfDiffOptions *opt, RfGrade *g);

#ifdef __cplusplus
}
#endif

#endif
