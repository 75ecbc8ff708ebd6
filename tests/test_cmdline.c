/* The command-line conventions of every command (issue 17): the one table of exit codes (README
 * "Exit codes", src/cli/exit_codes.h) for an unknown option, a missing file, a malformed file and
 * success; --opt=value and --; -h/--help and -V/--version; "did you mean"; messages naming what
 * is missing; --help listing every option the parser takes; output formats that follow the
 * file name; diff's threshold/count lines; the progress bar's rate. */
#define _XOPEN_SOURCE 700
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "refray/image.h"
#include "rf_test.h"

/* A scratch folder with a good scene, a broken one and a file that is no image. */
typedef struct {
    char dir[64];
    char bin[PATH_MAX], raster[PATH_MAX], verify[PATH_MAX], view[PATH_MAX];
} Scratch;

static int put(const Scratch *s, const char *name, const char *text)
{
    char path[256];
    snprintf(path, sizeof path, "%s/%s", s->dir, name);
    FILE *f = fopen(path, "w");
    if (!f)
        return 0;
    fputs(text, f);
    return fclose(f) == 0;
}

#define CAM "camera eye 0 0 5 target 0 0 0 up 0 1 0 fov 40\nresolution 8 6\n"

static int scratch_open(Scratch *s)
{
    snprintf(s->dir, sizeof s->dir, "/tmp/rf-cmdline-XXXXXX");
    if (!mkdtemp(s->dir) || !realpath(rf_test_bin(), s->bin) || !rf_test_tool("refray-raster", s->raster, sizeof s->raster) ||
        !rf_test_tool("refray-verify", s->verify, sizeof s->verify) ||
        !rf_test_tool("refray-view", s->view, sizeof s->view)) {
        RF_CHECK(!"scratch folder");
        return 0;
    }
    return put(s, "ok.rf", CAM "light point 0 0 5 intensity 1\nsphere 0 0 0 1\n") &&
           put(s, "bad.rf", CAM "sphere 0 0 0 -1\n") && put(s, "bad.exr", "not an image\n");
}

static void scratch_close(Scratch *s)
{
    char cmd[128];
    int code;
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", s->dir);
    rf_test_run(cmd, &code);
}

/* Runs `cd DIR && CMD 2>&1`: the output; *code the exit code. */
static const char *run_in(const Scratch *s, const char *cmd, int *code)
{
    char full[1 << 15];
    snprintf(full, sizeof full, "cd '%s' && %s 2>&1", s->dir, cmd);
    return rf_test_run(full, code);
}

/* Each command's exit code (README: Exit codes) for an unknown option, a missing file, a
 * malformed file and success; where a command reads no file, a bad option value stands in. */
static void t_exit_codes(void)
{
    Scratch s;
    if (!scratch_open(&s))
        return;
    char r[PATH_MAX + 8], cmd[4 * PATH_MAX];
    int code;
    const char *out = run_in(&s, "true", &code);
    snprintf(r, sizeof r, "'%s'", s.bin);
    /* the tiles and renders the other commands read */
    snprintf(cmd, sizeof cmd, "%s render ok.rf -o a.exr --quiet && %s render ok.rf -o b.exr --quiet --samples 4 --variance va.exr "
             "&& cp a.exr c.exr && %s render ok.rf --samples 4 --seed 2 -o c.exr --variance vc.exr --quiet", r, r, r);
    out = run_in(&s, cmd, &code);
    RF_CHECK_EQ_INT(code, 0);
    static const struct {
        const char *name, *unknown, *missing, *malformed, *ok;
    } cases[] = {
        {"render", "$R render ok.rf -o x.exr --bogus", "$R render nosuch.rf -o x.exr", "$R render bad.rf -o x.exr",
         "$R render ok.rf -o x.exr --quiet"},
        {"merge", "$R merge a.exr -o x.exr --bogus", "$R merge nosuch.exr -o x.exr", "$R merge bad.exr -o x.exr",
         "$R merge a.exr -o x.exr --quiet"},
        {"trace", "$R trace ok.rf 1 1 --bogus", "$R trace nosuch.rf 1 1", "$R trace bad.rf 1 1", "$R trace ok.rf 1 1"},
        {"diff", "$R diff a.exr a.exr --bogus", "$R diff a.exr nosuch.exr", "$R diff a.exr bad.exr", "$R diff a.exr a.exr"},
        {"info", "$R info ok.rf --bogus", "$R info nosuch.rf", "$R info bad.rf", "$R info ok.rf"},
        {"formula", "$R formula --bogus", "$R formula --batch nosuch.jsonl", "$R formula --batch bad.exr",
         "$R formula dot a=1,2,3 b=4,5,6"},
        {"chromaticity", "$R chromaticity -o x.png --bogus", NULL, "$R chromaticity -o x.png --white 1",
         "$R chromaticity -o x.svg --size 200"},
        {"metamers", "$R metamers --bogus", NULL, "$R metamers --size x", "$R metamers"},
        {"bench", "$R bench ok.rf --bogus", "$R bench nosuch.rf", "$R bench bad.rf",
         "$R bench ok.rf --spp 1 --samplers random --runs 1 --ref-samples 4 --quiet"},
        {"refray-raster", "$X ok.rf -o x.exr --bogus", "$X nosuch.rf -o x.exr", "$X bad.rf -o x.exr", "$X ok.rf -o x.exr"},
        {"refray-verify", "$V ok.rf --bogus", "$V nosuch.rf --rays 10", "$V bad.rf --rays 10", "$V ok.rf --rays 100"},
        {"refray-view", "$W ok.rf --bogus", "$W nosuch.rf", "$W bad.rf", NULL}, /* success: test_view (a display) */
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        const char *cmds[4] = {cases[i].unknown, cases[i].missing, cases[i].malformed, cases[i].ok};
        const int want[4] = {5, 4, cases[i].missing ? 4 : 5, 0};
        for (int k = 0; k < 4; k++) {
            if (!cmds[k])
                continue;
            /* $R refray, $X refray-raster, $V refray-verify, $W refray-view */
            size_t n = 0;
            for (const char *c = cmds[k]; *c && n + PATH_MAX + 4 < sizeof cmd; c++) {
                if (c[0] == '$' && (c[1] == 'R' || c[1] == 'X' || c[1] == 'V' || c[1] == 'W')) {
                    const char *tool = c[1] == 'R' ? s.bin : c[1] == 'X' ? s.raster : c[1] == 'V' ? s.verify : s.view;
                    n += (size_t)snprintf(cmd + n, sizeof cmd - n, "'%s'", tool);
                    c++;
                } else {
                    cmd[n++] = *c;
                }
            }
            cmd[n] = 0;
            out = run_in(&s, cmd, &code);
            rf_test_checks++;
            if (code != want[k])
                rf_test_fail(__FILE__, __LINE__, "%s: `%s`: exit %d, expected %d; said: %s", cases[i].name, cmds[k], code,
                             want[k], out);
        }
    }
    /* diff's own verdicts keep idiff's numbers: FAIL 2, size mismatch 3 */
    snprintf(cmd, sizeof cmd, "%s render ok.rf -o big.exr --width 16 --quiet && %s diff a.exr big.exr", r, r);
    out = run_in(&s, cmd, &code);
    RF_CHECK_EQ_INT(code, 3);
    snprintf(cmd, sizeof cmd, "%s diff a.exr c.exr --fail 1e-9 --failpercent 0", r);
    out = run_in(&s, cmd, &code);
    RF_CHECK_EQ_INT(code, 2);
    scratch_close(&s);
}

/* The parser's conventions, with the exact messages. */
static void t_conventions(void)
{
    Scratch s;
    if (!scratch_open(&s))
        return;
    char cmd[3 * PATH_MAX], want[512];
    int code;
    const char *out;
#define RUN(...) (snprintf(cmd, sizeof cmd, __VA_ARGS__), out = run_in(&s, cmd, &code))
    /* --opt=value, and -- before an operand that begins with '-' */
    RUN("cp ok.rf ./-x.rf && '%s' render --width=4 --height=3 --output=w.exr --quiet -- -x.rf && '%s' info -- -x.rf", s.bin, s.bin);
    RF_CHECK_EQ_INT(code, 0);
    RF_CHECK(strstr(out, "scene     -x.rf (refray format)") != NULL);
    RfImage img = {0, 0, 0, NULL};
    char path[256], err[256];
    snprintf(path, sizeof path, "%s/w.exr", s.dir);
    RF_CHECK(rf_exr_read(path, &img, err, sizeof err) == RF_OK && img.width == 4 && img.height == 3);
    rf_image_free(&img);
    /* the exact messages: no invented position for a file that cannot be opened; what is
     * missing, by name; did you mean (edit distance, a swap counts once); an ambiguous prefix
     * (a unique one is taken, as GNU tools do) */
    static const struct {
        int raster, code;
        const char *args, *says;
    } msgs[] = {
        {0, 4, "render nosuch.rf -o x.exr", "refray render: cannot open nosuch.rf: No such file or directory\n"},
        {0, 5, "render", "refray render: missing the scene file (see: refray render --help)\n"},
        {0, 5, "render ok.rf more.rf -o x.exr",
         "refray render: unexpected 'more.rf' after the scene file 'ok.rf' (see: refray render --help)\n"},
        {0, 5, "metamers extra", "refray metamers: unexpected 'extra': it takes options only (see: refray metamers --help)\n"},
        {0, 5, "trace ok.rf 3", "refray trace: missing the pixel's Y (see: refray trace --help)\n"},
        {0, 5, "diff a.exr", "refray diff: missing the reference image B (see: refray diff --help)\n"},
        {0, 5, "render ok.rf --width",
         "refray render: --width needs a value (an integer in [1, 65536]) (see: refray render --help)\n"},
        {0, 5, "render ok.rf -o", "refray render: -o needs a value (FILE) (see: refray render --help)\n"},
        {0, 5, "render ok.rf -o x.exr --quiet=yes", "refray render: --quiet takes no value (see: refray render --help)\n"},
        {0, 5, "render ok.rf -o x.exr --width 0", "refray render: bad value '0' for --width: an integer in [1, 65536]\n"},
        {0, 5, "render ok.rf -o x.exr --threshold 1.5",
         "refray render: bad value '1.5' for --threshold: a number in [0, 1]\n"},
        {0, 5, "render ok.rf -o x.exr --threshold nan",
         "refray render: bad value 'nan' for --threshold: a number in [0, 1]\n"},
        {0, 5, "rendre", "refray: unknown command 'rendre'; did you mean 'render'? (see: refray --help)\n"},
        {0, 5, "frobnicate", "refray: unknown command 'frobnicate' (see: refray --help)\n"},
        {0, 5, "render ok.rf -o x.exr --smaples 4",
         "refray render: unknown option '--smaples'; did you mean '--samples'? (see: refray render --help)\n"},
        {0, 5, "diff a.exr b.exr --heatmpa=h.png",
         "refray diff: unknown option '--heatmpa'; did you mean '--heatmap'? (see: refray diff --help)\n"},
        {1, 5, "ok.rf -o x.exr --mdoe flat",
         "refray-raster: unknown option '--mdoe'; did you mean '--mode'? (see: refray-raster --help)\n"},
        {0, 5, "render ok.rf -o x.exr --sa 1",
         "refray render: option '--sa' is ambiguous; possibilities: --samples --sampler (see: refray render --help)\n"},
    };
    for (size_t i = 0; i < sizeof msgs / sizeof msgs[0]; i++) {
        RUN("'%s' %s", msgs[i].raster ? s.raster : s.bin, msgs[i].args);
        rf_test_checks++;
        if (code != msgs[i].code || strcmp(out, msgs[i].says) != 0)
            rf_test_fail(__FILE__, __LINE__, "`%s`: exit %d (expected %d), said:\n%s  expected:\n%s", msgs[i].args, code,
                         msgs[i].code, out, msgs[i].says);
    }
    RUN("'%s'", s.bin); /* no command: the list of commands, then what is missing */
    RF_CHECK_EQ_INT(code, 5);
    RF_CHECK(strstr(out, "commands:\n  render ") != NULL && strstr(out, "\nrefray: missing the command\n") != NULL);
    RUN("'%s' render ok.rf -o x.exr --qui", s.bin);
    RF_CHECK_EQ_INT(code, 0);
    /* -V / --version and -h / --help everywhere, subcommands too */
    static const char *const tools[] = {"refray", "refray render", "refray merge", "refray trace", "refray diff",
                                        "refray info", "refray formula", "refray chromaticity", "refray metamers",
                                        "refray bench", "refray-raster", "refray-verify", "refray-view"};
    for (size_t i = 0; i < sizeof tools / sizeof tools[0]; i++) {
        const char *sub = strchr(tools[i], ' ');
        const char *bin = strncmp(tools[i], "refray-raster", 13) == 0   ? s.raster
                          : strncmp(tools[i], "refray-verify", 13) == 0 ? s.verify
                          : strncmp(tools[i], "refray-view", 11) == 0   ? s.view
                                                                          : s.bin;
        for (int v = 0; v < 2; v++) {
            RUN("'%s'%s %s", bin, sub ? sub : "", v ? "-V" : "--version");
            snprintf(want, sizeof want, "%s%s 0.2.0\n", strchr(tools[i], '-') ? tools[i] : "refray",
                     strchr(tools[i], '-') ? " (refray)" : "");
            rf_test_checks++;
            if (code != 0 || strcmp(out, want) != 0)
                rf_test_fail(__FILE__, __LINE__, "%s %s: exit %d, printed %s", tools[i], v ? "-V" : "--version", code, out);
            RUN("'%s'%s %s 2>/dev/null", bin, sub ? sub : "", v ? "-h" : "--help");
            snprintf(want, sizeof want, "usage: %s", tools[i]);
            rf_test_checks++; /* `refray --help` names itself on a line before */
            if (code != 0 || !(strncmp(out, want, strlen(want)) == 0 || (!sub && bin == s.bin && strstr(out, want))))
                rf_test_fail(__FILE__, __LINE__, "%s %s: exit %d, printed %.80s", tools[i], v ? "-h" : "--help", code, out);
        }
    }
#undef RUN
    scratch_close(&s);
}

/* Every option line of every --help ("  -o, --output FILE   text" or "  --opt VALUE   text") is an
 * option the parser takes (not "unknown"), and the parser takes no option the help leaves out
 * (each table entry is one line: the help is made from the table, counted here). */
static void t_help_lists_every_option(void)
{
    Scratch s;
    if (!scratch_open(&s))
        return;
    static const char *const tools[] = {"render", "merge", "trace", "diff", "info", "formula", "chromaticity", "metamers",
                                        "bench", "refray-raster", "refray-verify", "refray-view"};
    for (size_t i = 0; i < sizeof tools / sizeof tools[0]; i++) {
        char cmd[3 * PATH_MAX], help[1 << 14];
        int code, options = 0;
        const char *bin = strcmp(tools[i], "refray-raster") == 0   ? s.raster
                          : strcmp(tools[i], "refray-verify") == 0 ? s.verify
                          : strcmp(tools[i], "refray-view") == 0   ? s.view
                                                                    : s.bin;
        int sub = strncmp(tools[i], "refray-", 7) != 0;
        snprintf(cmd, sizeof cmd, "'%s' %s --help", bin, sub ? tools[i] : "");
        snprintf(help, sizeof help, "%s", run_in(&s, cmd, &code));
        RF_CHECK_EQ_INT(code, 0);
        for (char *line = strtok(help, "\n"); line; line = strtok(NULL, "\n")) {
            char name[64], value[64] = "";
            if (strncmp(line, "  -", 3) != 0)
                continue;
            const char *l = line + 2;
            if (l[1] != '-') /* "-o, --output FILE" */
                l += 4;
            if (sscanf(l, "--%63[a-z-]", name) != 1)
                continue;
            const char *after = l + 2 + strlen(name);
            int takes = after[0] == ' ' && after[1] != ' ';
            if (takes)
                sscanf(after + 1, "%63s", value);
            options++;
            /* the option, with a value where it takes one, then an unknown one that stops the
             * command before it works: the option itself is never unknown or short of a value */
            snprintf(cmd, sizeof cmd, "'%s' %s --%s%s%s --bogus-end", bin, sub ? tools[i] : "", name, takes ? "=" : "",
                     takes ? "1" : "");
            const char *out = run_in(&s, cmd, &code);
            char said[3][128];
            snprintf(said[0], sizeof said[0], "unknown option '--%s'", name);
            snprintf(said[1], sizeof said[1], "--%s needs a value", name);
            snprintf(said[2], sizeof said[2], "--%s takes no value", name);
            rf_test_checks++;
            if (strstr(out, said[0]) || strstr(out, said[1]) || strstr(out, said[2]) ||
                (strcmp(name, "help") != 0 && strcmp(name, "version") != 0 && !strstr(out, "'--bogus-end'") &&
                 !strstr(out, "bad value")))
                rf_test_fail(__FILE__, __LINE__, "%s --help lists --%s %s, which the parser does not take so: %s", tools[i],
                             name, value, out);
        }
        rf_test_checks++;
        if (options < 3)
            rf_test_fail(__FILE__, __LINE__, "%s --help lists %d options", tools[i], options);
    }
    scratch_close(&s);
}

/* The image's format follows its name: -o x.png writes a PNG (not EXR bytes), -o x.exr an EXR; an
 * unknown extension is refused (exit 5) and nothing is written. */
static void t_output_formats(void)
{
    Scratch s;
    if (!scratch_open(&s))
        return;
    static const struct {
        const char *cmd, *file;
        int code;
        const char *magic; /* "" for none written */
    } cases[] = {
        {"$R render ok.rf -o r.png --quiet", "r.png", 0, "\x89PNG"},
        {"$R render ok.rf -o r.exr --quiet", "r.exr", 0, "\x76\x2f\x31\x01"},
        {"$R render ok.rf -o R.EXR --quiet", "R.EXR", 0, "\x76\x2f\x31\x01"},
        {"$R render ok.rf -o r.tif --quiet", "r.tif", 5, ""},
        {"$R render ok.rf -o x.exr --png p.exr --quiet", "p.exr", 5, ""},
        {"$R render ok.rf -o x.exr --depth-out d.png --quiet", "d.png", 5, ""},
        {"$R render ok.rf --tiles 1 --tile 0 -o t.exr --quiet && $R merge t.exr -o m.png --quiet", "m.png", 0, "\x89PNG"},
        {"$R merge t.exr -o m.jpg", "m.jpg", 5, ""},
        {"$R diff r.exr r.exr --heatmap h.exr", "h.exr", 0, "\x76\x2f\x31\x01"},
        {"$R diff r.exr r.exr --heatmap h.png", "h.png", 0, "\x89PNG"},
        {"$R diff r.exr r.exr --heatmap h.ppm", "h.ppm", 5, ""},
        {"$R chromaticity -o c.pdf", "c.pdf", 5, ""},
        {"$R metamers -o m.svg --size 200", "m.svg", 0, "<?xml"},
        {"$X ok.rf -o g.png", "g.png", 0, "\x89PNG"},
        {"$X ok.rf -o g.bmp", "g.bmp", 5, ""},
        {"$W ok.rf --screenshot v.exr", "v.exr", 5, ""},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        char cmd[4 * PATH_MAX], path[256];
        size_t n = 0;
        for (const char *c = cases[i].cmd; *c && n + PATH_MAX + 4 < sizeof cmd; c++)
            if (c[0] == '$' && (c[1] == 'R' || c[1] == 'X' || c[1] == 'W')) {
                n += (size_t)snprintf(cmd + n, sizeof cmd - n, "'%s'", c[1] == 'R' ? s.bin : c[1] == 'X' ? s.raster : s.view);
                c++;
            } else {
                cmd[n++] = *c;
            }
        cmd[n] = 0;
        int code;
        const char *out = run_in(&s, cmd, &code);
        rf_test_checks++;
        if (code != cases[i].code)
            rf_test_fail(__FILE__, __LINE__, "`%s`: exit %d, expected %d: %s", cases[i].cmd, code, cases[i].code, out);
        if (cases[i].code == 5) {
            rf_test_checks++;
            if (!strstr(out, "the name must end in"))
                rf_test_fail(__FILE__, __LINE__, "`%s` said: %s", cases[i].cmd, out);
        }
        snprintf(path, sizeof path, "%s/%s", s.dir, cases[i].file);
        FILE *f = fopen(path, "rb");
        char head[8] = {0};
        size_t got = f ? fread(head, 1, sizeof head, f) : 0;
        if (f)
            fclose(f);
        size_t k = strlen(cases[i].magic);
        rf_test_checks++;
        if (k ? !(got >= k && memcmp(head, cases[i].magic, k) == 0) : f != NULL)
            rf_test_fail(__FILE__, __LINE__, "`%s`: %s %s", cases[i].cmd, cases[i].file,
                         k ? "does not start with its format's signature" : "was written");
    }
    /* -o x.png is the same image as --png x.png */
    char cmd[3 * PATH_MAX];
    int code;
    snprintf(cmd, sizeof cmd, "'%s' render ok.rf -o a.png --quiet && '%s' render ok.rf -o b.exr --png b.png --quiet && cmp a.png b.png",
             s.bin, s.bin);
    run_in(&s, cmd, &code);
    RF_CHECK_EQ_INT(code, 0);
    scratch_close(&s);
}

/* `refray diff`: the warn and fail lines give the threshold, a blank, then the count. Two 10 x 10
 * images: 13 pixels differ by 0.01 (above warn 1e-4 and fail 1/255), 4 more by 0.001 (above
 * warn only). */
static void t_diff_threshold_lines(void)
{
    Scratch s;
    if (!scratch_open(&s))
        return;
    RfImage a, b;
    char pa[256], pb[256], err[256];
    RF_CHECK(rf_image_alloc(&a, 10, 10, 3) == RF_OK && rf_image_alloc(&b, 10, 10, 3) == RF_OK);
    for (int i = 0; i < 300; i++)
        a.data[i] = b.data[i] = 0.5f;
    for (int p = 0; p < 17; p++)
        a.data[3 * p + 1] = 0.5f + (p < 13 ? 0.01f : 0.001f);
    snprintf(pa, sizeof pa, "%s/da.exr", s.dir);
    snprintf(pb, sizeof pb, "%s/db.exr", s.dir);
    RF_CHECK(rf_exr_write(pa, &a, NULL, 0, err, sizeof err) == RF_OK && rf_exr_write(pb, &b, NULL, 0, err, sizeof err) == RF_OK);
    rf_image_free(&a);
    rf_image_free(&b);
    char cmd[PATH_MAX + 64];
    int code;
    snprintf(cmd, sizeof cmd, "'%s' diff da.exr db.exr", s.bin);
    const char *out = run_in(&s, cmd, &code);
    RF_CHECK_EQ_INT(code, 2);
    RF_CHECK(strstr(out, "\n  above warn 0.0001    17 (17.0000 %)\n") != NULL);
    RF_CHECK(strstr(out, "\n  above fail 0.00392157 13 (13.0000 %)\n") != NULL);
    snprintf(cmd, sizeof cmd, "'%s' diff da.exr db.exr --warn 0.0039213 --fail 0.5", s.bin);
    out = run_in(&s, cmd, &code); /* a 9-digit threshold fills its field: the blank is still there */
    RF_CHECK(strstr(out, "\n  above warn 0.0039213 13 (13.0000 %)\n") != NULL);
    RF_CHECK(strstr(out, "\n  above fail 0.5       0 (0.0000 %)\n") != NULL);
    if (!strstr(out, "above warn 0.0039213 13"))
        fprintf(stderr, "%s", out);
    scratch_close(&s);
}

/* The progress bar on a terminal (script(1) gives the render a pseudo-terminal): a few redraws a
 * second, not one per finished tile (a 3 s render wrote 108 KB), and its 100 % state last. */
static void t_progress_rate(void)
{
    if (!rf_test_have("script")) {
        fprintf(stderr, "  (skipped: script(1) from bsdutils is not installed)\n");
        return;
    }
    Scratch s;
    if (!scratch_open(&s))
        return;
    char cmd[3 * PATH_MAX + 256], log[256], scene[PATH_MAX];
    int code;
    snprintf(log, sizeof log, "%s/tty.log", s.dir);
    if (!realpath("scenes/whitted.rf", scene)) {
        RF_CHECK(!"scenes/whitted.rf");
        return;
    }
    snprintf(cmd, sizeof cmd, "script -qfec \"'%s' render '%s' -o w.exr --samples 9 --threads 2\" '%s' >/dev/null", s.bin, scene,
             log);
    run_in(&s, cmd, &code);
    RF_CHECK_EQ_INT(code, 0);
    FILE *f = fopen(log, "rb");
    static char text[1 << 20];
    size_t n = f ? fread(text, 1, sizeof text - 1, f) : 0;
    if (f)
        fclose(f);
    text[n] = 0;
    int draws = 0;
    for (const char *p = text; (p = strstr(p, "\r[")); p++)
        draws++;
    const char *trace = strstr(text, "trace ");
    double secs = trace ? strtod(trace + 6, NULL) : 0.0;
    /* 4 a second, the first and the last: at most 4 s + 3 over the whole render (load and build
     * included, which the trace time leaves out: 1 more) */
    RF_CHECK(secs > 0.2);
    RF_CHECK(draws >= 2);
    RF_CHECK(draws <= (int)(4.0 * secs) + 4);
    /* the bar's bytes: from its first draw to the summary line (script(1) writes a header first) */
    const char *bar = strstr(text, "\r["), *summary = strstr(text, "refray render: ");
    RF_CHECK(bar && summary && summary > bar && (size_t)(summary - bar) < 80 * (size_t)draws);
    RF_CHECK(strstr(text, "] 100%") != NULL);
    if (rf_test_failed_checks)
        fprintf(stderr, "  %zu bytes, %d redraws in %.2f s\n", n, draws, secs);
    scratch_close(&s);
}

const RfTest rf_tests_cmdline[] = {
    {"cmdline_exit_codes", t_exit_codes},
    {"cmdline_conventions", t_conventions},
    {"cmdline_help_lists_every_option", t_help_lists_every_option},
    {"cmdline_output_formats", t_output_formats},
    {"cmdline_diff_threshold_lines", t_diff_threshold_lines},
    {"cmdline_progress_rate", t_progress_rate},
    RF_TEST_END,
};
