/* `refray grade REF SUBMISSION...`: a whole class against one reference (issue 16). Each
 * submission (a file, every image of a folder, or the rows "student,file" of a CSV) gets a
 * verdict, a reason, a score (grade.h) and an HTML page; the folder --out gets grades.csv,
 * grades.json and index.html. One unreadable submission never stops the others. */
#include "cli.h"
#include "args.h"
#include "diff_args.h"
#include "exit_codes.h"
#include "grade_report.h"

#include <ctype.h>
#include <dirent.h>
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>

#include "refray/grade.h"
#include "refray/image.h"

enum { OPT_OUT = 'o', OPT_QUIET = 'q' };

static const RfOpt grade_opts[] = {
    {"out", OPT_OUT, "DIR", "the report's folder (default grade-report): grades.csv, grades.json, index.html", NULL},
    {"quiet", OPT_QUIET, NULL, "no line per submission on stdout, only the summary", NULL},
    RF_OPT_TABLE_END,
};

static const RfOpt *const grade_tables[] = {grade_opts, rf_opts_diff, rf_opts_png, NULL};

static const RfCommand grade_cmd = {
    "refray grade",
    "refray grade [options] REFERENCE SUBMISSION...\n",
    "Grades each SUBMISSION against REFERENCE (EXR, linear). A SUBMISSION is an image file, a folder\n"
    "(every image in it), or a CSV file of rows student,file (a header row is skipped; paths are\n"
    "relative to the CSV). Images: PNG, PPM/PGM/PBM (P1-P6), JPEG, TIFF, BMP, TGA (display-\n"
    "encoded codes), HDR, EXR, float TIFF (linear, encoded with --gamma G, default 2.2, or --srgb).\n"
    "Compared in display values with the thresholds of refray diff (display defaults: --fail 1/255,\n"
    "--failpercent 0.1, --fail-mean 1/255, --warn 0.5/255, --warnpercent 0.1).\n",
    grade_tables,
    "Verdicts: pass, warn, fail, unreadable, wrong size; the reason names the criterion, by how\n"
    "much and where, and a gamma/sRGB mix-up or a whole-image shift when it finds one.\n"
    "Score: 100 pass, 90 warn, fail 80 x (1 - share of pixels above --fail), 0 unreadable or\n"
    "wrong size.\n"
    "exit: 0 all passed, 1 some warned (none worse), 2 some failed, 3 some had the wrong size\n"
    "(none failed), 4 some were unreadable (none failed) or the reference or an output could not\n"
    "be read or written, 5 usage\n",
};

typedef struct {
    RfSubmission *v;
    int n, cap;
} List;

static int add(List *l, const char *student, const char *path)
{
    if (l->n == l->cap) {
        int cap = l->cap ? 2 * l->cap : 64;
        RfSubmission *v = realloc(l->v, (size_t)cap * sizeof *v);
        if (!v)
            return 0;
        l->v = v, l->cap = cap;
    }
    RfSubmission *s = &l->v[l->n];
    memset(s, 0, sizeof *s);
    s->student = strdup(student);
    s->path = strdup(path);
    s->format = "";
    if (!s->student || !s->path) {
        free(s->student), free(s->path);
        return 0;
    }
    l->n++;
    return 1;
}

static int has_suffix(const char *s, const char *suffix)
{
    size_t n = strlen(s), k = strlen(suffix);
    return n >= k && strcasecmp(s + n - k, suffix) == 0;
}

static int is_image_name(const char *name)
{
    static const char *const ext[] = {".png", ".ppm", ".pgm", ".pbm", ".pnm", ".jpg", ".jpeg", ".tif", ".tiff",
                                      ".bmp", ".hdr", ".exr", ".tga"};
    for (size_t i = 0; i < sizeof ext / sizeof ext[0]; i++)
        if (has_suffix(name, ext[i]))
            return 1;
    return 0;
}

/* The student's name from a path: the file name without its extension. */
static void stem(const char *path, char *out, size_t n)
{
    const char *base = strrchr(path, '/');
    base = base ? base + 1 : path;
    snprintf(out, n, "%s", base);
    char *dot = strrchr(out, '.');
    if (dot && dot != out)
        *dot = 0;
}

static int cmp_names(const void *a, const void *b)
{
    return strcmp(*(char *const *)a, *(char *const *)b);
}

/* Every image of a folder, by name. */
static int add_dir(List *l, const char *dir)
{
    DIR *d = opendir(dir);
    if (!d) {
        fprintf(stderr, "refray grade: %s: cannot read the folder: %s\n", dir, strerror(errno));
        return RF_EXIT_FILE;
    }
    char **names = NULL;
    size_t n = 0, cap = 0;
    int rc = 0;
    struct dirent *e;
    while ((e = readdir(d)) != NULL && rc == 0) {
        if (e->d_name[0] == '.' || !is_image_name(e->d_name))
            continue;
        if (n == cap) {
            char **v = realloc(names, (cap = cap ? 2 * cap : 64) * sizeof *v);
            if (!v) {
                rc = RF_EXIT_FILE;
                break;
            }
            names = v;
        }
        if (!(names[n] = strdup(e->d_name)))
            rc = RF_EXIT_FILE;
        else
            n++;
    }
    closedir(d);
    qsort(names, n, sizeof *names, cmp_names);
    for (size_t i = 0; i < n; i++) {
        char path[4096], who[256];
        snprintf(path, sizeof path, "%s/%s", dir, names[i]);
        stem(names[i], who, sizeof who);
        if (rc == 0 && !add(l, who, path))
            rc = RF_EXIT_FILE;
        free(names[i]);
    }
    free(names);
    if (rc)
        fprintf(stderr, "refray grade: out of memory\n");
    return rc;
}

static char *trim(char *s)
{
    while (isspace((unsigned char)*s))
        s++;
    size_t n = strlen(s);
    while (n > 0 && isspace((unsigned char)s[n - 1]))
        s[--n] = 0;
    if (n >= 2 && s[0] == '"' && s[n - 1] == '"') /* a quoted field (without inner quotes) */
        s[n - 1] = 0, s++;
    return s;
}

/* The rows "student,file" of a CSV; file paths relative to the CSV's folder. */
static int add_csv(List *l, const char *csv)
{
    FILE *f = fopen(csv, "r");
    if (!f) {
        fprintf(stderr, "refray grade: %s: cannot open: %s\n", csv, strerror(errno));
        return RF_EXIT_FILE;
    }
    char line[4096], dir[4096];
    snprintf(dir, sizeof dir, "%s", csv);
    char *slash = strrchr(dir, '/');
    if (slash)
        slash[1] = 0;
    else
        dir[0] = 0;
    int rc = 0;
    for (int no = 1; rc == 0 && fgets(line, sizeof line, f); no++) {
        char *comma = strchr(line, ',');
        if (!comma) {
            if (*trim(line) == 0)
                continue;
            fprintf(stderr, "refray grade: %s:%d: expected student,file\n", csv, no);
            rc = RF_EXIT_FILE;
            break;
        }
        *comma = 0;
        char *who = trim(line), *file = trim(comma + 1), path[8192];
        if (no == 1 && strcasecmp(who, "student") == 0)
            continue;
        if (!*who || !*file) {
            fprintf(stderr, "refray grade: %s:%d: expected student,file\n", csv, no);
            rc = RF_EXIT_FILE;
            break;
        }
        snprintf(path, sizeof path, "%s%s", file[0] == '/' ? "" : dir, file);
        if (!add(l, who, path))
            rc = RF_EXIT_FILE;
    }
    fclose(f);
    return rc;
}

static int collect(List *l, char **args, int n)
{
    for (int i = 0; i < n; i++) {
        struct stat sb;
        int rc = 0;
        if (stat(args[i], &sb) == 0 && S_ISDIR(sb.st_mode))
            rc = add_dir(l, args[i]);
        else if (has_suffix(args[i], ".csv"))
            rc = add_csv(l, args[i]);
        else {
            char who[256];
            stem(args[i], who, sizeof who);
            rc = add(l, who, args[i]) ? 0 : RF_EXIT_FILE;
        }
        if (rc)
            return rc;
    }
    return 0;
}

/* "007-alice": the number keeps names unique, the rest is the student's name made safe for a file. */
static void make_id(RfSubmission *s, int index)
{
    int n = snprintf(s->id, sizeof s->id, "%03d-", index + 1);
    for (const char *c = s->student; *c && n < (int)sizeof s->id - 1; c++)
        s->id[n++] = isalnum((unsigned char)*c) || *c == '-' || *c == '_' ? *c : '_';
    s->id[n] = 0;
}

static int write_png(const char *dir, const char *id, const char *suffix, const RfImage *img, char *err, size_t errsz)
{
    char path[4096];
    RfPngOptions p = {RF_PNG_AS_IS, 1.0, 8, NULL};
    snprintf(path, sizeof path, "%s/img/%s%s.png", dir, id, suffix);
    return rf_png_write(path, img, p, err, errsz) == RF_OK;
}

/* |submission - reference| x 10 in display values: where they differ, at a glance. */
static RfStatus difference(const RfImage *a, const RfImage *b, RfImage *out)
{
    RfStatus st = rf_image_alloc(out, a->width, a->height, 3);
    if (st != RF_OK)
        return st;
    for (size_t i = 0; i < (size_t)a->width * (size_t)a->height * 3; i++) {
        double d = 10.0 * fabs((double)a->data[i] - (double)b->data[i]);
        out->data[i] = (float)(d < 1.0 ? d : 1.0); /* NaN becomes 1: visible */
    }
    return RF_OK;
}

/* One submission: read, grade, its images. 0, or RF_EXIT_FILE when an output cannot be written. */
static int grade_one(const RfGradeRun *run, const RfImage *ref, const RfImage *ref_disp, RfPngOptions enc,
                     RfSubmission *s)
{
    char err[1024];
    RfImage stored, disp, other = {0, 0, 0, NULL};
    RfImageSource src;
    RfPngOptions as_is = {RF_PNG_AS_IS, 1.0, 8, NULL};
    memset(&disp, 0, sizeof disp);
    if (rf_image_read_source(s->path, as_is, &stored, &src, err, sizeof err) != RF_OK) {
        s->g.verdict = RF_GRADE_UNREADABLE;
        snprintf(s->g.reason, sizeof s->g.reason, "%.600s", err);
        return 0;
    }
    s->format = rf_image_file_name(src.format);
    s->width = stored.width, s->height = stored.height;
    RfStatus st = rf_grade_display(&stored, src.encoded, enc, &disp);
    rf_image_free(&stored);
    if (st == RF_OK)
        st = rf_grade_image(ref, ref_disp, src.encoded, &disp, enc, &run->opt, &s->g);
    if (st != RF_OK) {
        rf_image_free(&disp);
        s->g.verdict = RF_GRADE_UNREADABLE;
        snprintf(s->g.reason, sizeof s->g.reason, "%.600s: out of memory", s->path);
        return 0;
    }
    int ok = write_png(run->dir, s->id, "", &disp, err, sizeof err);
    s->images = ok;
    if (ok && s->g.verdict <= RF_GRADE_FAIL) {
        for (int y = 0; y < disp.height; y++)
            for (int x = 0; x < disp.width; x++)
                s->hist[rf_grade_hist_bin(rf_diff_pixel_error(&disp, ref_disp, x, y, run->opt.edge_tolerant, NULL,
                                                              NULL))]++;
        ok = difference(&disp, ref_disp, &other) == RF_OK && write_png(run->dir, s->id, "-diff", &other, err, sizeof err);
        rf_image_free(&other);
        ok = ok && rf_diff_heatmap(&disp, ref_disp, NULL, &run->opt, &other) == RF_OK &&
             write_png(run->dir, s->id, "-heat", &other, err, sizeof err);
        rf_image_free(&other);
        s->images = ok ? 2 : 1;
    }
    rf_image_free(&disp);
    if (!ok) {
        fprintf(stderr, "refray grade: %s\n", err);
        return RF_EXIT_FILE;
    }
    return 0;
}

static int make_dir(const char *path)
{
    if (mkdir(path, 0755) == 0 || errno == EEXIST) {
        struct stat sb;
        if (stat(path, &sb) == 0 && S_ISDIR(sb.st_mode))
            return 1;
        errno = ENOTDIR;
    }
    fprintf(stderr, "refray grade: %s: cannot make the folder: %s\n", path, strerror(errno));
    return 0;
}

/* 0 all passed; else the worst: fail, then unreadable, wrong size, warn. */
static int exit_code(const RfSubmission *v, int n)
{
    int seen[5] = {0};
    for (int i = 0; i < n; i++)
        seen[v[i].g.verdict] = 1;
    return seen[RF_GRADE_FAIL]         ? RF_EXIT_FAIL
           : seen[RF_GRADE_UNREADABLE] ? RF_EXIT_FILE
           : seen[RF_GRADE_SIZE]       ? RF_EXIT_SIZE
           : seen[RF_GRADE_WARN]       ? RF_EXIT_WARN
                                       : RF_EXIT_OK;
}

int rf_cmd_grade(int argc, char **argv)
{
    RfDiffOptions o = rf_diff_options_default();
    RfPngOptions enc = {RF_PNG_GAMMA, 2.2, 8, NULL};
    const char *out = "grade-report";
    unsigned set = 0;
    int quiet = 0, key, r;
    RfOptParser p;
    rf_opt_init(&p, &grade_cmd, argc, argv);
    while ((key = rf_opt_next(&p)) != RF_OPT_DONE) {
        if (key == RF_OPT_EXIT)
            return p.exit_code;
        r = 1;
        if (key == OPT_OUT)
            out = p.value;
        else if (key == OPT_QUIET)
            quiet = 1;
        else if ((r = rf_arg_diff(key, p.value, &o, &set)) == 0)
            r = rf_arg_shared(key, p.value, NULL, &enc);
        if (r < 0)
            return rf_opt_bad_value(&p);
    }
    char **args;
    int nargs = rf_opt_operands(&p, &args);
    if (nargs < 2)
        return rf_opt_usage_error(&grade_cmd, "give the reference and at least one submission");
    rf_arg_diff_display(&o, set);

    char err[1024], curve[32];
    RfImage ref, ref_disp;
    if (rf_image_read(args[0], enc, &ref, err, sizeof err) != RF_OK) {
        fprintf(stderr, "refray grade: %s\n", err);
        return RF_EXIT_FILE;
    }
    if (enc.encoding == RF_PNG_SRGB)
        snprintf(curve, sizeof curve, "sRGB");
    else
        snprintf(curve, sizeof curve, "gamma %g", enc.gamma);
    List l = {NULL, 0, 0};
    int rc = collect(&l, args + 1, nargs - 1);
    char img_dir[4096];
    snprintf(img_dir, sizeof img_dir, "%s/img", out);
    if (rc == 0 && l.n == 0) {
        fprintf(stderr, "refray grade: no submissions found\n");
        rc = RF_EXIT_USAGE;
    }
    if (rc == 0 && (!make_dir(out) || !make_dir(img_dir)))
        rc = RF_EXIT_FILE;
    if (rc == 0 && rf_grade_display(&ref, 0, enc, &ref_disp) != RF_OK) {
        fprintf(stderr, "refray grade: out of memory\n");
        rc = RF_EXIT_FILE;
    }
    RfGradeRun run = {out, args[0], ref.width, ref.height, o, curve};
    if (rc == 0) {
        rc = write_png(out, "reference", "", &ref_disp, err, sizeof err) ? 0 : RF_EXIT_FILE;
        if (rc)
            fprintf(stderr, "refray grade: %s\n", err);
        for (int i = 0; i < l.n && rc == 0; i++) {
            RfSubmission *s = &l.v[i];
            make_id(s, i);
            rc = grade_one(&run, &ref, &ref_disp, enc, s);
            if (rc == 0 && !rf_grade_write_page(&run, s, err, sizeof err)) {
                fprintf(stderr, "refray grade: %s\n", err);
                rc = RF_EXIT_FILE;
            }
            if (!quiet)
                printf("%-20s %-10s %5.1f  %s\n", s->student, rf_grade_verdict_name(s->g.verdict), s->g.score,
                       s->g.reason);
        }
        rf_image_free(&ref_disp);
    }
    if (rc == 0 && (!rf_grade_write_csv(&run, l.v, l.n, err, sizeof err) ||
                    !rf_grade_write_json(&run, l.v, l.n, err, sizeof err) ||
                    !rf_grade_write_index(&run, l.v, l.n, err, sizeof err))) {
        fprintf(stderr, "refray grade: %s\n", err);
        rc = RF_EXIT_FILE;
    }
    if (rc == 0) {
        int count[5] = {0};
        for (int i = 0; i < l.n; i++)
            count[l.v[i].g.verdict]++;
        printf("%d submissions: %d pass, %d warn, %d fail, %d unreadable, %d wrong size; report: %s/index.html\n", l.n,
               count[0], count[1], count[2], count[3], count[4], out);
        rc = exit_code(l.v, l.n);
    }
    for (int i = 0; i < l.n; i++)
        free(l.v[i].student), free(l.v[i].path);
    free(l.v);
    rf_image_free(&ref);
    rf_diff_heatmap_done();
    return rc;
}
