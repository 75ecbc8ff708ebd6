/* `refray bench`: run time against error. Renders a scene with each sampling strategy at several
 * sample counts, measures the median wall time of the whole render call (tracer build included)
 * and the error against a converged reference (RMSE and relMSE over all W x H x 3 values), and
 * reports the time each strategy needs to reach relMSE 1e-3 (log-log interpolation between the
 * two rows that bracket it, as tools/anchor_soft.py does for the anchor renderers). */
#include "cli.h"
#include "args.h"
#include "exit_codes.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "refray/diff.h"
#include "refray/image.h"
#include "refray/render.h"
#include "refray/sampling.h"
#include "refray/scene_io.h"

#define TARGET 1e-3          /* the relMSE every strategy is timed to */
#define TARGET_TEXT "1e-3"
#define REF_SEED_OFFSET 1000003u
#define MAX_STRATEGIES 8
#define MAX_SPP 16
#define MAX_RUNS 100
#define MAX_ANCHOR_ROWS 1024
#define ADAPTIVE (-2)        /* a strategy that is §3.9 adaptive supersampling, not an RfSampler */
#define ADAPTIVE_DEPTHS 3    /* its rows: adaptive_depth 1, 2, 3 */

/* One measurement: a row of the table and of the CSV. */
typedef struct {
    char renderer[32], strategy[32];
    double spp, seconds, rmse, relmse;
} Row;

typedef struct {
    const char *scene, *ref, *csv, *plot, *anchors;
    int ref_samples, runs, threads, width, height, light_samples, seed, quiet, process;
    int strategy[MAX_STRATEGIES], nstrategies; /* RfSampler or ADAPTIVE */
    int light[MAX_STRATEGIES];                  /* NAME/L: L shadow rays per area light; 0: default */
    char name[MAX_STRATEGIES][32];              /* as written */
    int spp[MAX_SPP], nspp;                     /* ascending */
} Args;

enum {
    OPT_REF = RF_OPT_ID, OPT_REF_SAMPLES, OPT_SAMPLERS, OPT_SPP, OPT_RUNS, OPT_THREADS, OPT_WIDTH, OPT_HEIGHT, OPT_SEED,
    OPT_LIGHT_SAMPLES, OPT_CSV, OPT_PLOT, OPT_ANCHORS, OPT_QUIET, OPT_PROCESS
};

static const RfOpt bench_opts[] = {
    {"ref", OPT_REF, "REF.exr", "the reference (linear EXR of the same size); default: rendered, see below", NULL},
    {"ref-samples", OPT_REF_SAMPLES, "N", "sobol samples of the rendered reference (default 1024)",
     "an integer in [1, 1048576]"},
    {"samplers", OPT_SAMPLERS, "LIST", "default random,stratified,sobol,uniform,adaptive; NAME/L: L shadow rays",
     "a comma-separated list of uniform, random, stratified, sobol, adaptive, each NAME or NAME/L"},
    {"spp", OPT_SPP, "LIST", "sample counts per pixel (default 1,4,16,64,256)",
     "a comma-separated list of integers in [1, 1048576]"},
    {"runs", OPT_RUNS, "R", "renders per row; the median time counts (default 3)", "an integer in [1, 100]"},
    {"threads", OPT_THREADS, "T", "worker threads (default: one per processor)", "an integer in [1, 1024]"},
    {"width", OPT_WIDTH, "W", "image width (default: the scene's)", "an integer in [1, 65536]"},
    {"height", OPT_HEIGHT, "H", "image height (default: the scene's)", "an integer in [1, 65536]"},
    {"seed", OPT_SEED, "S", "seed of the random samplers (default 1)", "an integer in [0, 2147483647]"},
    {"light-samples", OPT_LIGHT_SAMPLES, "N", "shadow rays per area light and camera sample",
     "an integer in [1, 65536]"},
    {"csv", OPT_CSV, "OUT.csv", "rows renderer,strategy,spp,seconds,rmse,relmse (renderer \"refray\")", NULL},
    {"plot", OPT_PLOT, "OUT.png|OUT.svg", "log-log relMSE against seconds with gnuplot (OUT.gp, OUT.dat beside)",
     "a file name ending in .png or .svg"},
    {"anchors", OPT_ANCHORS, "ANCHORS.csv", "other renderers' rows (tools/anchor_soft.py): time to relMSE 1e-3",
     NULL},
    {"process", OPT_PROCESS, NULL, "time whole `refray render` processes writing the EXR, as the anchors are timed",
     NULL},
    {"quiet", OPT_QUIET, NULL, "no progress lines on stderr", NULL},
    RF_OPT_TABLE_END,
};

static const RfOpt *const bench_tables[] = {bench_opts, NULL};

static const RfCommand bench_cmd = {
    "refray bench",
    "refray bench [options] SCENE\n",
    "Run time against error: each strategy at each sample count is rendered R times\n"
    "(default 3); seconds = the median wall time of the render call (tracer build\n"
    "included, scene loading not; with --process: of the whole `refray render` process,\n"
    "from its start to the written EXR, as tools/anchor_soft.py times other renderers),\n"
    "errors against the reference over all W x H x 3 values:\n"
    "RMSE = sqrt(mean (x-r)^2), relMSE = mean (x-r)^2 / (r^2 + 0.01).\n",
    bench_tables,
    "Without --ref the reference is rendered with --ref-samples sobol samples and seed\n"
    "S + 1000003 (REF_SEED_OFFSET), and written to <OUT>_ref.exr when --csv OUT.csv is given. adaptive is §3.9\n"
    "adaptive supersampling at depths 1..3 (its spp: the mean samples taken). --anchors:\n"
    "their time to relMSE 1e-3 and its ratio to refray's best.\n"
    "exit: 0 ok, 2 a render failed, 4 a file cannot be read or written, 5 usage (README: Exit codes)\n",
};

static double now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

/* ---- options ------------------------------------------------------------------------------ */

/* A comma-separated list into items of < 32 characters; the count, or -1 when it is empty, has
 * an empty or too long item, or more than max items. */
static int split_list(const char *s, char items[][32], int max)
{
    int n = 0;
    for (;;) {
        size_t len = strcspn(s, ",");
        if (len == 0 || len >= 32 || n == max)
            return -1;
        memcpy(items[n], s, len);
        items[n++][len] = 0;
        if (!s[len])
            return n;
        s += len + 1;
    }
}

static int parse_strategies(const char *v, Args *a)
{
    char items[MAX_STRATEGIES][32];
    a->nstrategies = split_list(v, items, MAX_STRATEGIES);
    for (int i = 0; i < a->nstrategies; i++) {
        /* NAME or NAME/L: the sampler, and L shadow rays per area light and camera sample */
        char *slash = strchr(items[i], '/');
        memcpy(a->name[i], items[i], sizeof a->name[i]);
        a->light[i] = 0;
        if (slash) {
            *slash = 0;
            if (!rf_arg_int(slash + 1, 1, 1 << 16, &a->light[i]))
                return 0;
        }
        a->strategy[i] = strcmp(items[i], "adaptive") == 0 ? ADAPTIVE : rf_sampler_parse(items[i]);
        if (a->strategy[i] == -1)
            return 0;
    }
    return a->nstrategies > 0;
}

static int parse_spp(const char *v, Args *a)
{
    char items[MAX_SPP][32];
    a->nspp = split_list(v, items, MAX_SPP);
    for (int i = 0; i < a->nspp; i++) {
        int s;
        if (!rf_arg_int(items[i], 1, 1 << 20, &s))
            return 0;
        int j = i; /* insertion sort: the rows of a strategy must come by spp */
        for (; j > 0 && a->spp[j - 1] > s; j--)
            a->spp[j] = a->spp[j - 1];
        a->spp[j] = s;
    }
    return a->nspp > 0;
}

/* -1: run; else the exit code (--help, --version or a usage error, reported). */
static int parse_args(int argc, char **argv, Args *a)
{
    memset(a, 0, sizeof *a);
    a->ref_samples = 1024, a->runs = 3, a->seed = 1;
    parse_strategies("random,stratified,sobol,uniform,adaptive", a);
    parse_spp("1,4,16,64,256", a);
    RfOptParser p;
    int key;
    rf_opt_init(&p, &bench_cmd, argc, argv);
    while ((key = rf_opt_next(&p)) != RF_OPT_DONE) {
        const char *v = p.value;
        int ok = 1;
        switch (key) {
        case RF_OPT_EXIT: return p.exit_code;
        case OPT_QUIET: a->quiet = 1; break;
        case OPT_PROCESS: a->process = 1; break;
        case OPT_REF: a->ref = v; break;
        case OPT_CSV: a->csv = v; break;
        case OPT_ANCHORS: a->anchors = v; break;
        case OPT_PLOT: {
            const char *dot = strrchr(v, '.');
            a->plot = v;
            ok = dot && (strcmp(dot, ".png") == 0 || strcmp(dot, ".svg") == 0);
            break;
        }
        case OPT_REF_SAMPLES: ok = rf_arg_int(v, 1, 1 << 20, &a->ref_samples); break;
        case OPT_SAMPLERS: ok = parse_strategies(v, a); break;
        case OPT_SPP: ok = parse_spp(v, a); break;
        case OPT_RUNS: ok = rf_arg_int(v, 1, MAX_RUNS, &a->runs); break;
        case OPT_THREADS: ok = rf_arg_int(v, 1, 1024, &a->threads); break;
        case OPT_WIDTH: ok = rf_arg_int(v, 1, 65536, &a->width); break;
        case OPT_HEIGHT: ok = rf_arg_int(v, 1, 65536, &a->height); break;
        case OPT_SEED: ok = rf_arg_int(v, 0, 2147483647, &a->seed); break;
        case OPT_LIGHT_SAMPLES: ok = rf_arg_int(v, 1, 1 << 16, &a->light_samples); break;
        }
        if (!ok)
            return rf_opt_bad_value(&p);
    }
    int bad = rf_opt_operand(&p, "the scene file", &a->scene);
    return bad ? bad : -1;
}

/* ---- measuring ---------------------------------------------------------------------------- */

static int cmp_double(const void *x, const void *y)
{
    double a = *(const double *)x, b = *(const double *)y;
    return (a > b) - (a < b);
}

/* The median of t[0..n). */
static double median(double *t, int n)
{
    qsort(t, (size_t)n, sizeof t[0], cmp_double);
    return n % 2 ? t[n / 2] : 0.5 * (t[n / 2 - 1] + t[n / 2]);
}

/* Renders runs times: *seconds = the median time of the rf_render call, *img and *st those of the
 * first run (the same seed gives the same image every run; a difference is reported). */
static RfStatus render_measured(const RfScene *scene, const RfRenderOptions *opt, int runs, double *seconds,
                                RfImage *img, RfRenderStats *st)
{
    double t[MAX_RUNS];
    for (int r = 0; r < runs; r++) {
        RfImage again;
        RfRenderStats st2;
        double t0 = now();
        RfStatus s = rf_render(scene, opt, r == 0 ? img : &again, r == 0 ? st : &st2);
        t[r] = now() - t0;
        if (s != RF_OK) {
            if (r > 0)
                rf_image_free(img);
            return s;
        }
        if (r > 0) {
            if (memcmp(img->data, again.data, sizeof(float) * 3 * (size_t)img->width * img->height) != 0)
                fprintf(stderr, "refray bench: warning: run %d gave a different image than run 1\n", r + 1);
            rf_image_free(&again);
        }
    }
    *seconds = median(t, runs);
    return RF_OK;
}

/* --process: runs `refray render` (this executable) with the row's settings runs times, each
 * writing out_exr; *seconds = the median wall time from fork to exit. The image is the
 * in-process render's (the same settings and seed give the same image; measure_all compares
 * the first process's EXR with it). Returns 0, or -1 when a process could not run or failed. */
static int time_processes(const Args *a, const RfRenderOptions *opt, const char *sampler, const char *out_exr,
                          double *seconds)
{
    char w[16], h[16], n[16], seed[24], threads[16], light[16], depth[16];
    snprintf(w, sizeof w, "%d", opt->width);
    snprintf(h, sizeof h, "%d", opt->height);
    snprintf(n, sizeof n, "%d", opt->samples);
    snprintf(seed, sizeof seed, "%llu", (unsigned long long)opt->seed);
    snprintf(threads, sizeof threads, "%d", opt->threads);
    snprintf(light, sizeof light, "%d", opt->light_samples);
    snprintf(depth, sizeof depth, "%d", opt->adaptive_depth);
    char *argv[32];
    int k = 0;
    const char *fixed[] = {"refray", "render", a->scene, "-o", out_exr, "--quiet", "--width", w, "--height", h,
                           "--samples", n, "--seed", seed, "--sampler", sampler};
    for (size_t i = 0; i < sizeof fixed / sizeof fixed[0]; i++)
        argv[k++] = (char *)fixed[i];
    if (opt->threads > 0)
        argv[k++] = "--threads", argv[k++] = threads;
    if (opt->light_samples > 0)
        argv[k++] = "--light-samples", argv[k++] = light;
    if (opt->adaptive)
        argv[k++] = "--adaptive-depth", argv[k++] = depth;
    argv[k] = NULL;
    double t[MAX_RUNS];
    for (int r = 0; r < a->runs; r++) {
        fflush(NULL);
        double t0 = now();
        pid_t pid = fork();
        if (pid == 0) {
            execv("/proc/self/exe", argv);
            _exit(127);
        }
        int status = 0;
        if (pid < 0 || waitpid(pid, &status, 0) != pid || !WIFEXITED(status) || WEXITSTATUS(status) != 0) {
            fprintf(stderr, "refray bench: `refray render %s ... --sampler %s` failed\n", a->scene, sampler);
            return -1;
        }
        t[r] = now() - t0;
    }
    *seconds = median(t, a->runs);
    return 0;
}

/* RMSE and relMSE of img against ref (rf_diff_images: the same definitions); 0 on a mismatch. */
static int image_errors(const RfImage *img, const RfImage *ref, double *rmse, double *relmse)
{
    RfDiffOptions dopt = rf_diff_options_default();
    RfDiffResult res;
    char err[256];
    if (rf_diff_images(img, ref, NULL, NULL, &dopt, &res, NULL, err, sizeof err) != RF_OK)
        return 0;
    *rmse = res.all.rmse;
    *relmse = res.all.rel_mse;
    return 1;
}

/* ---- time to the target ------------------------------------------------------------------- */

/* The rows of one strategy, by spp: the time to reach relMSE target, interpolated log-log between
 * the first two consecutive rows that bracket it (e0 > target >= e1); the first row's time when
 * that row is already at or below it; NAN when no row reaches it. text gets it in words. */
static double time_to_target(const Row *rows, int n, double target, char *text, size_t size)
{
    if (n == 0) {
        snprintf(text, size, "no data");
        return NAN;
    }
    if (rows[0].relmse <= target) {
        snprintf(text, size, "%.4g s (below at the first row, %.4g spp)", rows[0].seconds, rows[0].spp);
        return rows[0].seconds;
    }
    for (int i = 0; i + 1 < n; i++) {
        const Row *a = &rows[i], *b = &rows[i + 1];
        if (a->relmse > target && target >= b->relmse) {
            double t = b->seconds;
            if (b->relmse > 0.0 && a->seconds > 0.0 && b->seconds > 0.0) {
                double f = (log(target) - log(a->relmse)) / (log(b->relmse) - log(a->relmse));
                t = exp(log(a->seconds) + f * (log(b->seconds) - log(a->seconds)));
            }
            snprintf(text, size, "%.4g s (between %.4g and %.4g spp)", t, a->spp, b->spp);
            return t;
        }
    }
    snprintf(text, size, "not reached (relMSE %.3g at %.4g spp)", rows[n - 1].relmse, rows[n - 1].spp);
    return NAN;
}

/* The number of rows from rows[0] on with its renderer and strategy. */
static int group_len(const Row *rows, int n)
{
    int k = 1;
    while (k < n && strcmp(rows[k].renderer, rows[0].renderer) == 0 && strcmp(rows[k].strategy, rows[0].strategy) == 0)
        k++;
    return k;
}

/* ---- files -------------------------------------------------------------------------------- */

/* path with its extension (after the last '.' of the last component) replaced by suffix. */
static void with_suffix(const char *path, const char *suffix, char *out, size_t size)
{
    const char *slash = strrchr(path, '/'), *dot = strrchr(path, '.');
    int len = dot && (!slash || dot > slash + 1) ? (int)(dot - path) : (int)strlen(path);
    snprintf(out, size, "%.*s%s", len, path, suffix);
}

static void write_csv(FILE *f, const Row *rows, int n)
{
    fprintf(f, "renderer,strategy,spp,seconds,rmse,relmse\n");
    for (int i = 0; i < n; i++)
        fprintf(f, "%s,%s,%.6g,%.9g,%.6e,%.6e\n", rows[i].renderer, rows[i].strategy, rows[i].spp,
                rows[i].seconds, rows[i].rmse, rows[i].relmse);
}

/* Splits a CSV line (no quoting) in place into at most max fields; the count. */
static int csv_fields(char *line, char **field, int max)
{
    int n = 0;
    line[strcspn(line, "\r\n")] = 0;
    for (char *p = line; n < max;) {
        field[n++] = p;
        p = strchr(p, ',');
        if (!p)
            break;
        *p++ = 0;
    }
    return n;
}

static int cmp_group_then_spp(const void *x, const void *y)
{
    const Row *a = x, *b = y;
    int c = strcmp(a->renderer, b->renderer);
    c = c ? c : strcmp(a->strategy, b->strategy);
    return c ? c : (a->spp > b->spp) - (a->spp < b->spp);
}

/* The anchors' rows (renderer,strategy,spp,seconds,rmse,relmse, columns by the header's names),
 * each renderer/strategy contiguous and by spp. 0 with a message in err on failure. */
static int read_anchors(const char *path, Row *rows, int max, int *n, char *err, size_t size)
{
    static const char *const names[6] = {"renderer", "strategy", "spp", "seconds", "rmse", "relmse"};
    int col[6], line_no = 0;
    char line[1024], *f[16];
    FILE *in = fopen(path, "r");
    *n = 0;
    if (!in) {
        snprintf(err, size, "%s: cannot open the anchors file", path);
        return 0;
    }
    if (!fgets(line, sizeof line, in)) {
        snprintf(err, size, "%s: empty file (want the header renderer,strategy,spp,seconds,rmse,relmse)", path);
        fclose(in);
        return 0;
    }
    line_no = 1;
    int nf = csv_fields(line, f, 16);
    for (int c = 0; c < 6; c++) {
        col[c] = -1;
        for (int k = 0; k < nf; k++)
            if (strcmp(f[k], names[c]) == 0)
                col[c] = k;
        if (col[c] < 0) {
            snprintf(err, size, "%s:1: no column '%s' in the header", path, names[c]);
            fclose(in);
            return 0;
        }
    }
    while (fgets(line, sizeof line, in)) {
        line_no++;
        if (line[0] == '#' || line[strspn(line, " \t\r\n")] == 0)
            continue;
        Row *r = &rows[*n];
        double *num[4] = {&r->spp, &r->seconds, &r->rmse, &r->relmse};
        int ok = *n < max && csv_fields(line, f, 16) == nf;
        for (int c = 2; ok && c < 6; c++) {
            char *end;
            *num[c - 2] = strtod(f[col[c]], &end);
            ok = end != f[col[c]] && *end == 0 && isfinite(*num[c - 2]) && *num[c - 2] >= 0.0;
        }
        ok = ok && strlen(f[col[0]]) < sizeof r->renderer && strlen(f[col[1]]) < sizeof r->strategy;
        if (!ok) {
            snprintf(err, size, "%s:%d: not a row renderer,strategy,spp,seconds,rmse,relmse of numbers >= 0%s", path,
                     line_no, *n < max ? "" : " (too many rows)");
            fclose(in);
            return 0;
        }
        strcpy(r->renderer, f[col[0]]);
        strcpy(r->strategy, f[col[1]]);
        (*n)++;
    }
    fclose(in);
    qsort(rows, (size_t)*n, sizeof *rows, cmp_group_then_spp);
    return 1;
}

/* ---- the plot ------------------------------------------------------------------------------ */

/* s in a gnuplot single-quoted string (' doubled). */
static void gp_quoted(FILE *f, const char *s)
{
    fputc('\'', f);
    for (; *s; s++)
        fputs(*s == '\'' ? "''" : (char[2]){*s, 0}, f);
    fputc('\'', f);
}

/* One data block per renderer/strategy (points with seconds and relMSE > 0, which a log scale
 * can show) and one plot clause for it; dashed for anchors. */
static void plot_groups(FILE *dat, FILE *gp, const char *dat_path, const Row *rows, int n, int dashed,
                        int *block)
{
    for (int i = 0; i < n; i += group_len(rows + i, n - i)) {
        int k = group_len(rows + i, n - i), points = 0;
        char title[80];
        for (int j = i; j < i + k; j++)
            points += rows[j].seconds > 0.0 && rows[j].relmse > 0.0;
        if (points == 0)
            continue;
        fprintf(dat, "# %s %s\n", rows[i].renderer, rows[i].strategy);
        for (int j = i; j < i + k; j++)
            if (rows[j].seconds > 0.0 && rows[j].relmse > 0.0)
                fprintf(dat, "%.9g %.9g %g\n", rows[j].seconds, rows[j].relmse, rows[j].spp);
        fprintf(dat, "\n\n");
        if (dashed)
            snprintf(title, sizeof title, "%s %s", rows[i].renderer, rows[i].strategy);
        else
            snprintf(title, sizeof title, "%s", rows[i].strategy);
        fputs(*block ? ", \\\n     " : "plot ", gp);
        gp_quoted(gp, dat_path);
        fprintf(gp, " index %d with linespoints %s title ", (*block)++, dashed ? "dt 2 lw 1.5 pt 6" : "lw 2 pt 7");
        gp_quoted(gp, title);
    }
}

/* Runs gnuplot on the script: 0 done, 127 gnuplot not found, else its failure. */
static int run_gnuplot(const char *script)
{
    fflush(stdout);
    fflush(stderr);
    pid_t pid = fork();
    if (pid < 0)
        return -1;
    if (pid == 0) {
        execlp("gnuplot", "gnuplot", script, (char *)NULL);
        _exit(127);
    }
    int status;
    if (waitpid(pid, &status, 0) < 0)
        return -1;
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

/* The log-log plot of relMSE against seconds: OUT.gp and OUT.dat, then gnuplot. Exit code. */
static int write_plot(const Args *a, const char *title, const Row *rows, int n, const Row *anchors, int na)
{
    char gp_path[4096], dat_path[4096];
    with_suffix(a->plot, ".gp", gp_path, sizeof gp_path);
    with_suffix(a->plot, ".dat", dat_path, sizeof dat_path);
    FILE *gp = fopen(gp_path, "w"), *dat = fopen(dat_path, "w");
    if (!gp || !dat) {
        fprintf(stderr, "refray bench: cannot write %s\n", gp ? dat_path : gp_path);
        if (gp)
            fclose(gp);
        if (dat)
            fclose(dat);
        return RF_EXIT_FILE;
    }
    int svg = strcmp(strrchr(a->plot, '.'), ".svg") == 0, block = 0;
    fprintf(gp, "# refray bench: relMSE against run time; run: gnuplot %s\n", gp_path);
    fprintf(gp, "set terminal %s noenhanced size 900,600\nset output ", svg ? "svg" : "pngcairo");
    gp_quoted(gp, a->plot);
    fprintf(gp, "\nset title ");
    gp_quoted(gp, title);
    fprintf(gp, "\nset xlabel 'seconds (median wall time of the %s)'\nset ylabel 'relMSE'\n"
                "set logscale xy\nset grid\nset key outside right top\nset format x '%%g'\n"
                "set yrange [*<%g:*]\n"
                "set format y '%%.0e'\n",
            a->process ? "whole process; the anchors also" : "render; the anchors: whole process", TARGET / 3);
    plot_groups(dat, gp, dat_path, rows, n, 0, &block);
    plot_groups(dat, gp, dat_path, anchors, na, 1, &block);
    fprintf(gp, "%s%g with lines dt 3 lw 1.5 lc rgb '#808080' title 'relMSE " TARGET_TEXT "'\n",
            block ? ", \\\n     " : "plot ", TARGET);
    int werr = ferror(gp) | ferror(dat);
    werr |= fclose(gp) != 0;
    werr |= fclose(dat) != 0;
    if (werr) {
        fprintf(stderr, "refray bench: cannot write %s or %s\n", gp_path, dat_path);
        return RF_EXIT_FILE;
    }
    int rc = run_gnuplot(gp_path);
    if (rc == 127) {
        printf("refray bench: gnuplot not found (apt-get install gnuplot-nox): wrote %s and %s, no plot\n", gp_path,
               dat_path);
        return 0;
    }
    if (rc != 0) {
        fprintf(stderr, "refray bench: gnuplot failed on %s (exit %d)\n", gp_path, rc);
        return RF_EXIT_FAIL;
    }
    printf("plot: %s (gnuplot script %s)\n", a->plot, gp_path);
    return 0;
}

/* ---- the report ---------------------------------------------------------------------------- */

static void print_table(const Row *rows, int n)
{
    printf("\n%-12s %8s %10s %10s %10s\n", "strategy", "spp", "seconds", "rmse", "relmse");
    for (int i = 0; i < n; i++)
        printf("%-12s %8.4g %10.4g %10.4g %10.4g\n", rows[i].strategy, rows[i].spp, rows[i].seconds, rows[i].rmse,
               rows[i].relmse);
}

/* Time to the target per strategy, the winner and the anchors' ratios to it. */
static void print_targets(const Row *rows, int n, const Row *anchors, int na)
{
    char text[160];
    double best = NAN;
    const char *winner = NULL;
    printf("\ntime to relMSE " TARGET_TEXT " (log-log interpolated):\n");
    for (int i = 0; i < n; i += group_len(rows + i, n - i)) {
        double t = time_to_target(rows + i, group_len(rows + i, n - i), TARGET, text, sizeof text);
        printf("  %-12s %s\n", rows[i].strategy, text);
        if (!isnan(t) && (isnan(best) || t < best))
            best = t, winner = rows[i].strategy;
    }
    if (winner)
        printf("winner: %s (%.4g s to relMSE " TARGET_TEXT ")\n", winner, best);
    else
        printf("winner: none (no strategy reached relMSE " TARGET_TEXT ")\n");
    if (na == 0)
        return;
    printf("\nanchors, time to relMSE " TARGET_TEXT " and anchor time / refray best:\n");
    for (int i = 0; i < na; i += group_len(anchors + i, na - i)) {
        char label[80];
        double t = time_to_target(anchors + i, group_len(anchors + i, na - i), TARGET, text, sizeof text);
        snprintf(label, sizeof label, "%s %s", anchors[i].renderer, anchors[i].strategy);
        if (!isnan(t) && !isnan(best) && best > 0.0)
            printf("  %-28s %-44s %.3gx\n", label, text, t / best);
        else
            printf("  %-28s %-44s -\n", label, text);
    }
}

/* ---- the command --------------------------------------------------------------------------- */

/* The reference: read (it must have the render's size) or rendered with ref_samples sobol samples
 * and another seed, written beside the CSV. Exit code. */
static int get_reference(const Args *a, const RfScene *scene, RfRenderOptions opt, int w, int h, RfImage *ref)
{
    char err[1024];
    if (a->ref) {
        if (rf_exr_read(a->ref, ref, err, sizeof err) != RF_OK) {
            fprintf(stderr, "refray bench: %s\n", err);
            return RF_EXIT_FILE;
        }
        if (ref->width != w || ref->height != h || ref->channels < 3) {
            fprintf(stderr, "refray bench: the reference %s is %dx%d with %d channel%s; the renders are %dx%d RGB\n",
                    a->ref, ref->width, ref->height, ref->channels, ref->channels == 1 ? "" : "s", w, h);
            rf_image_free(ref);
            return RF_EXIT_SIZE;
        }
        printf("reference: %s\n", a->ref);
        return 0;
    }
    RfRenderStats st;
    opt.sampler = RF_SAMPLER_SOBOL, opt.adaptive = 0, opt.samples = a->ref_samples;
    opt.seed = (uint64_t)a->seed + REF_SEED_OFFSET;
    double t0 = now();
    RfStatus s = rf_render(scene, &opt, ref, &st);
    if (s != RF_OK) {
        fprintf(stderr, "refray bench: %s: reference render: %s\n", a->scene, rf_status_str(s));
        return RF_EXIT_FAIL;
    }
    printf("reference: %d spp sobol, seed %llu, rendered in %.3f s", a->ref_samples, (unsigned long long)opt.seed,
           now() - t0);
    if (a->csv) {
        char path[4096], settings[128];
        snprintf(settings, sizeof settings, "%dx%d, %d spp sobol, seed %llu (refray bench reference)", w, h,
                 a->ref_samples, (unsigned long long)opt.seed);
        RfImageAttr attr = {"refray:settings", settings};
        with_suffix(a->csv, "_ref.exr", path, sizeof path);
        if (rf_exr_write(path, ref, &attr, 1, err, sizeof err) != RF_OK) {
            fprintf(stderr, "\nrefray bench: %s\n", err);
            rf_image_free(ref);
            return RF_EXIT_FILE;
        }
        printf(", written to %s", path);
    }
    printf("\n");
    return 0;
}

/* --process: a row's time from whole processes writing tmp_exr, whose first image must be img
 * bit for bit. Exit code. */
static int process_row(const Args *a, const RfRenderOptions *opt, const char *sampler, const char *tmp_exr,
                       const RfImage *img, double *seconds)
{
    char err[1024];
    RfImage back;
    if (time_processes(a, opt, sampler, tmp_exr, seconds) != 0)
        return RF_EXIT_FAIL;
    if (rf_exr_read(tmp_exr, &back, err, sizeof err) != RF_OK) {
        fprintf(stderr, "refray bench: %s\n", err);
        return RF_EXIT_FILE;
    }
    int same = back.width == img->width && back.height == img->height && back.channels >= 3;
    for (size_t i = 0; same && i < (size_t)img->width * img->height; i++)
        same = memcmp(&back.data[i * back.channels], &img->data[3 * i], 3 * sizeof(float)) == 0;
    rf_image_free(&back);
    remove(tmp_exr);
    if (!same)
        fprintf(stderr, "refray bench: warning: `refray render --sampler %s` wrote another image than the bench's "
                        "render with the same settings\n", sampler);
    return 0;
}

/* Every strategy at every sample count (adaptive: at depths 1..3): rows[], their count in *n;
 * --process: each row's processes write tmp_exr. Exit code. */
static int measure_rows(const Args *a, const RfScene *scene, RfRenderOptions opt, const RfImage *ref, Row *rows,
                        int *n, const char *tmp_exr)
{
    int total = 0;
    for (int s = 0; s < a->nstrategies; s++)
        total += a->strategy[s] == ADAPTIVE ? ADAPTIVE_DEPTHS : a->nspp;
    *n = 0;
    for (int s = 0; s < a->nstrategies; s++) {
        int adaptive = a->strategy[s] == ADAPTIVE, count = adaptive ? ADAPTIVE_DEPTHS : a->nspp;
        for (int k = 0; k < count; k++) {
            Row *r = &rows[(*n)++];
            RfImage img;
            RfRenderStats st;
            opt.adaptive = adaptive;
            opt.light_samples = a->light[s] ? a->light[s] : a->light_samples;
            if (adaptive)
                opt.adaptive_depth = k + 1, opt.samples = 1;
            else
                opt.sampler = a->strategy[s], opt.samples = a->spp[k];
            /* --process: the image once here, the times from whole processes */
            RfStatus rs = render_measured(scene, &opt, a->process ? 1 : a->runs, &r->seconds, &img, &st);
            if (rs != RF_OK) {
                fprintf(stderr, "refray bench: %s: %s: %s\n", a->scene, a->name[s],
                        rf_status_str(rs));
                return RF_EXIT_FAIL;
            }
            if (a->process) {
                int rc = process_row(a, &opt, adaptive ? "adaptive" : rf_sampler_name(opt.sampler), tmp_exr, &img,
                                     &r->seconds);
                if (rc) {
                    rf_image_free(&img);
                    return rc;
                }
            }
            snprintf(r->renderer, sizeof r->renderer, "refray");
            snprintf(r->strategy, sizeof r->strategy, "%s", a->name[s]);
            r->spp = adaptive ? (double)st.primary_rays / ((double)st.width * st.height) : opt.samples;
            int ok = image_errors(&img, ref, &r->rmse, &r->relmse);
            rf_image_free(&img);
            if (!ok) {
                fprintf(stderr, "refray bench: the image and the reference differ in size\n");
                return RF_EXIT_SIZE;
            }
            if (!a->quiet) {
                fprintf(stderr, "refray bench: [%d/%d] %s", *n, total, r->strategy);
                if (adaptive)
                    fprintf(stderr, " depth %d", k + 1);
                fprintf(stderr, " %.4g spp: %.4g s, relMSE %.4g\n", r->spp, r->seconds, r->relmse);
            }
        }
    }
    return 0;
}

/* measure_rows, with --process in a temporary folder of its own. Exit code. */
static int measure_all(const Args *a, const RfScene *scene, RfRenderOptions opt, const RfImage *ref, Row *rows,
                       int *n)
{
    char tmp_dir[64] = "", tmp_exr[96] = "";
    if (a->process) { /* the processes' images, each removed after its row */
        const char *base = getenv("TMPDIR");
        snprintf(tmp_dir, sizeof tmp_dir, "%s/refray-bench-XXXXXX", base && strlen(base) < 40 ? base : "/tmp");
        if (!mkdtemp(tmp_dir)) {
            fprintf(stderr, "refray bench: cannot make a temporary folder %s\n", tmp_dir);
            return RF_EXIT_FILE;
        }
        snprintf(tmp_exr, sizeof tmp_exr, "%s/render.exr", tmp_dir);
    }
    int rc = measure_rows(a, scene, opt, ref, rows, n, tmp_exr);
    if (a->process)
        rmdir(tmp_dir);
    return rc;
}

int rf_cmd_bench(int argc, char **argv)
{
    Args a;
    int rc = parse_args(argc, argv, &a);
    if (rc >= 0)
        return rc;

    static Row rows[MAX_STRATEGIES * MAX_SPP], anchors[MAX_ANCHOR_ROWS];
    int n = 0, na = 0;
    char err[1024];
    if (a.anchors && !read_anchors(a.anchors, anchors, MAX_ANCHOR_ROWS, &na, err, sizeof err)) {
        fprintf(stderr, "refray bench: %s\n", err);
        return RF_EXIT_FILE;
    }
    RfScene scene;
    RfLoadOptions lopt = rf_load_options_default();
    lopt.threads = a.threads;
    rf_scene_init(&scene);
    if (rf_scene_load(a.scene, &lopt, &scene, err, sizeof err) != RF_OK) {
        rf_arg_report("refray bench", err);
        return RF_EXIT_FILE;
    }
    int w = a.width > 0 ? a.width : scene.render.width, h = a.height > 0 ? a.height : scene.render.height;
    if ((double)w * (double)h > (double)RF_IMAGE_MAX_PIXELS) {
        fprintf(stderr, "refray bench: %d x %d pixels is more than the %zu an image may have\n", w, h,
                (size_t)RF_IMAGE_MAX_PIXELS);
        rf_scene_free(&scene);
        return RF_EXIT_USAGE;
    }
    FILE *csv = a.csv ? fopen(a.csv, "w") : NULL; /* opened first: a bad path fails before the renders */
    if (a.csv && !csv) {
        fprintf(stderr, "refray bench: cannot write %s\n", a.csv);
        rf_scene_free(&scene);
        return RF_EXIT_FILE;
    }
    RfRenderOptions opt = rf_render_options_default();
    opt.width = w, opt.height = h, opt.threads = a.threads, opt.light_samples = a.light_samples;
    opt.seed = (uint64_t)a.seed;
    printf("refray bench: %s %dx%d, median of %d run%s, seed %d; seconds: %s\n", a.scene, w, h, a.runs,
           a.runs == 1 ? "" : "s", a.seed,
           a.process ? "whole `refray render` processes, EXR written" : "the render call");
    RfImage ref = {0, 0, 0, NULL};
    rc = get_reference(&a, &scene, opt, w, h, &ref);
    if (rc == 0)
        rc = measure_all(&a, &scene, opt, &ref, rows, &n);
    rf_image_free(&ref);
    rf_scene_free(&scene);
    if (rc == 0) {
        print_table(rows, n);
        print_targets(rows, n, anchors, na);
    }
    if (csv) {
        if (rc == 0)
            write_csv(csv, rows, n);
        if ((ferror(csv) | fclose(csv)) != 0 && rc == 0) {
            fprintf(stderr, "refray bench: cannot write %s\n", a.csv);
            rc = RF_EXIT_FILE;
        }
        if (rc == 0)
            printf("csv: %s\n", a.csv);
        else
            remove(a.csv); /* no partial table */
    }
    if (rc == 0 && a.plot) {
        char title[512];
        const char *base = strrchr(a.scene, '/');
        snprintf(title, sizeof title, "refray bench: %s, %dx%d", base ? base + 1 : a.scene, w, h);
        rc = write_plot(&a, title, rows, n, anchors, na);
    }
    return rc;
}
