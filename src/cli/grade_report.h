/* `refray grade`'s outputs: grades.csv, grades.json, index.html and one HTML page per submission
 * (self-contained: the images are PNG files in img/ beside the pages, script and style inline). */
#ifndef REFRAY_CLI_GRADE_REPORT_H
#define REFRAY_CLI_GRADE_REPORT_H

#include <stddef.h>

#include "refray/grade.h"

/* The error histogram: bin 0 below 1e-5 (0 included), bins 1..40 eight per decade from 1e-5 to
 * 1, the last 1 and above (or NaN/Inf). */
enum { RF_HIST_BINS = 42 };
int rf_grade_hist_bin(double e);

typedef struct {
    char *student, *path;   /* as given or read from the CSV (malloc'd) */
    char id[96];            /* "007-alice": the names of its page and images */
    const char *format;     /* "PNG", "JPEG", ...; "" when unreadable */
    RfGrade g;              /* unreadable: the reader's message is the reason */
    int width, height;
    int images;             /* 1 when img/ID.png was written, 2 with the difference and heat map */
    long hist[RF_HIST_BINS];
} RfSubmission;

typedef struct {
    const char *dir;        /* the output folder */
    const char *reference;  /* the reference's path */
    int width, height;      /* the reference's size */
    RfDiffOptions opt;
    const char *curve;      /* "gamma 2.2" or "sRGB" */
} RfGradeRun;

/* Each writes its file through a temporary name; 0 and a message in err on failure. */
int rf_grade_write_page(const RfGradeRun *run, const RfSubmission *s, char *err, size_t errsz);
int rf_grade_write_index(const RfGradeRun *run, const RfSubmission *subs, int n, char *err, size_t errsz);
int rf_grade_write_csv(const RfGradeRun *run, const RfSubmission *subs, int n, char *err, size_t errsz);
int rf_grade_write_json(const RfGradeRun *run, const RfSubmission *subs, int n, char *err, size_t errsz);

#endif
