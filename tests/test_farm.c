/* Beyond one machine (issue 14): crops equal the whole render bit for bit, tiles merge into it,
 * a missing, overlapping or foreign tile is refused, an interrupted render resumes to the
 * identical image, and the GNU parallel and Slurm examples run. */
#define _XOPEN_SOURCE 700
#include "rf_test.h"

#include <signal.h>
#include <stdlib.h>
#include <time.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include "../src/cli/farm.h"
#include "refray/render.h"
#include "refray/scene_io.h"

static int load(const char *path, RfScene *s)
{
    char err[512];
    if (rf_scene_load(path, NULL, s, err, sizeof err) != RF_OK) {
        rf_test_fail(__FILE__, __LINE__, "%s", err);
        return 0;
    }
    return 1;
}

/* The crop's pixels, bit for bit, against the same window of the whole image. */
static int same_window(const RfImage *whole, const RfImage *crop, RfTile c)
{
    for (int y = c.y0; y < c.y1; y++)
        if (memcmp(whole->data + ((size_t)y * (size_t)whole->width + (size_t)c.x0) * 3,
                   crop->data + (size_t)(y - c.y0) * (size_t)crop->width * 3, sizeof(float) * 3 * (size_t)(c.x1 - c.x0)))
            return 0;
    return 1;
}

/* Crops (at the borders, inside, one pixel, odd sizes) of renders that use every kind of
 * sampling: 1 spp, a filter wider than the pixel, adaptive supersampling (whose neighbours lie
 * outside the crop), area lights and a lens, motion blur; 1 and 2 threads. */
static void t_farm_crop_identical(void)
{
    static const struct {
        const char *scene;
        int samples, adaptive, filter;
    } cases[] = {
        {"scenes/whitted.rf", 1, 0, -1},
        {"scenes/whitted.rf", 4, 0, RF_FILTER_GAUSSIAN},
        {"scenes/whitted.rf", 1, 1, -1},
        {"scenes/soft.rf", 4, 0, -1},
        {"scenes/motion.rf", 3, 0, -1},
    };
    static const RfTile crops[] = {{0, 0, 40, 30, 0}, {13, 7, 29, 23, 0}, {39, 29, 40, 30, 0}, {0, 11, 40, 12, 0},
                                   {5, 0, 6, 30, 0}, {17, 3, 35, 28, 0}};
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        RfScene s;
        if (!load(cases[i].scene, &s))
            continue;
        RfRenderOptions o = rf_render_options_default();
        o.width = 40, o.height = 30, o.samples = cases[i].samples, o.threads = 2;
        o.adaptive = cases[i].adaptive;
        o.filter = cases[i].filter;
        RfImage whole, part;
        RfRenderStats st;
        RF_CHECK_EQ_INT(rf_render(&s, &o, &whole, &st), RF_OK);
        for (size_t k = 0; k < sizeof crops / sizeof crops[0]; k++) {
            o.crop = crops[k];
            o.threads = 1 + (int)(k % 2);
            if (rf_render(&s, &o, &part, &st) != RF_OK) {
                rf_test_fail(__FILE__, __LINE__, "%s crop %zu failed", cases[i].scene, k);
                continue;
            }
            RF_CHECK_EQ_INT(part.width, crops[k].x1 - crops[k].x0);
            RF_CHECK_EQ_INT(part.height, crops[k].y1 - crops[k].y0);
            if (!same_window(&whole, &part, crops[k]))
                rf_test_fail(__FILE__, __LINE__, "%s (%d spp%s): crop %d,%d,%d,%d differs from the whole render",
                             cases[i].scene, cases[i].samples, cases[i].adaptive ? ", adaptive" : "", crops[k].x0,
                             crops[k].y0, crops[k].x1, crops[k].y1);
            rf_image_free(&part);
        }
        /* windows outside the image are refused */
        RfTile bad[] = {{0, 0, 41, 30, 0}, {5, 5, 5, 9, 0}, {-1, 0, 3, 3, 0}};
        for (size_t k = 0; k < 3; k++) {
            o.crop = bad[k];
            RF_CHECK_EQ_INT(rf_render(&s, &o, &part, &st), RF_ERR_DOMAIN);
        }
        rf_image_free(&whole);
        rf_scene_free(&s);
    }
}

typedef struct {
    int calls, twice;
    unsigned char seen[64];
} DoneLog;

static void log_done(void *ctx, const RfImage *img, RfTile t)
{
    DoneLog *d = ctx;
    (void)img;
    __atomic_add_fetch(&d->calls, 1, __ATOMIC_RELAXED);
    if (t.index >= 0 && t.index < 64 && __atomic_exchange_n(&d->seen[t.index], 1, __ATOMIC_RELAXED))
        __atomic_add_fetch(&d->twice, 1, __ATOMIC_RELAXED);
}

/* Resuming: tiles marked done are copied from the earlier pixels, the others rendered; with the
 * earlier pixels those of the whole render, the result is the whole render bit for bit (also
 * when the earlier pixels are garbage where the tiles were not done: those are re-rendered).
 * tile_done sees every tile once; cancel stops the render with RF_ERR_INTERRUPTED. */
static void t_farm_resume_skip(void)
{
    RfScene s;
    if (!load("scenes/whitted.rf", &s))
        return;
    RfRenderOptions o = rf_render_options_default();
    o.width = 70, o.height = 50, o.samples = 2, o.threads = 2; /* 5 x 4 tiles, the last ones partial */
    RF_CHECK_EQ_INT(rf_render_tile_count(70, 50), 20);
    RfImage whole, earlier, again;
    RfRenderStats st, st2;
    RF_CHECK_EQ_INT(rf_render(&s, &o, &whole, &st), RF_OK);
    RF_CHECK_EQ_INT(rf_image_alloc(&earlier, 70, 50, 3), RF_OK);
    unsigned char skip[20];
    for (int t = 0; t < 20; t++)
        skip[t] = t % 3 != 1;
    for (size_t i = 0; i < (size_t)70 * 50 * 3; i++)
        earlier.data[i] = -1.0f; /* not a render's value */
    for (int ty = 0; ty < 4; ty++)
        for (int tx = 0; tx < 5; tx++)
            if (skip[ty * 5 + tx])
                for (int y = ty * 16; y < ty * 16 + 16 && y < 50; y++)
                    for (int x = tx * 16; x < tx * 16 + 16 && x < 70; x++)
                        memcpy(earlier.data + ((size_t)y * 70 + x) * 3, whole.data + ((size_t)y * 70 + x) * 3,
                               sizeof(float) * 3);
    DoneLog log;
    memset(&log, 0, sizeof log);
    o.skip = skip;
    o.resume_from = &earlier;
    o.tile_done = log_done;
    o.tile_done_ctx = &log;
    RF_CHECK_EQ_INT(rf_render(&s, &o, &again, &st2), RF_OK);
    RF_CHECK(memcmp(again.data, whole.data, sizeof(float) * 3 * 70 * 50) == 0);
    RF_CHECK_EQ_INT(log.calls, 20);
    RF_CHECK_EQ_INT(log.twice, 0);
    RF_CHECK(st2.primary_rays < st.primary_rays / 2); /* 7 of 20 tiles traced */
    rf_image_free(&again);
    /* a resume image of the wrong size is refused */
    o.width = 71;
    RF_CHECK_EQ_INT(rf_render(&s, &o, &again, &st2), RF_ERR_DOMAIN);
    /* cancelled before it starts: nothing rendered, the image freed */
    o.width = 70;
    o.skip = NULL, o.resume_from = NULL, o.tile_done = NULL;
    volatile int cancel = 1;
    o.cancel = &cancel;
    RF_CHECK_EQ_INT(rf_render(&s, &o, &again, &st2), RF_ERR_INTERRUPTED);
    RF_CHECK(again.data == NULL);
    rf_image_free(&earlier);
    rf_image_free(&whole);
    rf_scene_free(&s);
}

/* Tile K of N: the tiles partition the image (every pixel in exactly one), their sizes differ by
 * at most a row and a column, and grids bigger than the image are refused. */
static void t_farm_tile_rect_partition(void)
{
    char err[256];
    static const int sizes[][2] = {{640, 480}, {7, 5}, {1, 1}, {33, 1000}};
    for (size_t s = 0; s < 4; s++) {
        int w = sizes[s][0], h = sizes[s][1];
        unsigned char *cover = calloc((size_t)w * (size_t)h, 1);
        for (int n = 1; n <= 40; n++) {
            memset(cover, 0, (size_t)w * (size_t)h);
            int ok = 1, bad = 0, minw = 1 << 30, maxw = 0, minh = 1 << 30, maxh = 0;
            for (int k = 0; k < n && ok; k++) {
                RfTile t;
                ok = rf_farm_tile_rect(n, k, w, h, &t, err, sizeof err);
                if (!ok)
                    break;
                minw = t.x1 - t.x0 < minw ? t.x1 - t.x0 : minw, maxw = t.x1 - t.x0 > maxw ? t.x1 - t.x0 : maxw;
                minh = t.y1 - t.y0 < minh ? t.y1 - t.y0 : minh, maxh = t.y1 - t.y0 > maxh ? t.y1 - t.y0 : maxh;
                for (int y = t.y0; y < t.y1; y++)
                    for (int x = t.x0; x < t.x1; x++)
                        bad += cover[(size_t)y * w + x]++ != 0;
            }
            if (!ok) { /* only when the grid has more rows or columns than the image */
                RF_CHECK(strstr(err, "more than the") != NULL);
                continue;
            }
            for (size_t i = 0; i < (size_t)w * (size_t)h; i++)
                bad += cover[i] != 1;
            if (bad || maxw - minw > 1 || maxh - minh > 1)
                rf_test_fail(__FILE__, __LINE__, "%d tiles of %dx%d: %d pixels not covered once, widths %d..%d, "
                             "heights %d..%d", n, w, h, bad, minw, maxw, minh, maxh);
            rf_test_checks++;
        }
        free(cover);
    }
    RfTile t;
    RF_CHECK(rf_farm_tile_rect(16, 5, 640, 480, &t, err, sizeof err) && t.x0 == 160 && t.x1 == 320 && t.y0 == 120 &&
             t.y1 == 240);
    RF_CHECK(!rf_farm_tile_rect(4, 4, 640, 480, &t, err, sizeof err) && strstr(err, "not in [0, 4)"));
    /* the done-tile lists of checkpoints */
    unsigned char d[12] = {1, 1, 1, 0, 1, 0, 0, 1, 1, 0, 0, 1}, e[12];
    char *r = rf_farm_ranges_format(d, 12);
    RF_CHECK_STR(r, "0-2,4,7-8,11");
    RF_CHECK(rf_farm_ranges_parse(r, e, 12) && memcmp(d, e, 12) == 0);
    free(r);
    RF_CHECK(!rf_farm_ranges_parse("0-2,12", e, 12));
    RF_CHECK(!rf_farm_ranges_parse("3-1", e, 12));
    RF_CHECK(!rf_farm_ranges_parse("1,,2", e, 12));
    RF_CHECK(rf_farm_ranges_parse("", e, 12) && memchr(e, 1, 12) == NULL);
}

/* Decoded pixels of two EXRs, bit for bit. */
static int same_pixels(const char *a, const char *b)
{
    RfImage x, y;
    char err[512];
    if (rf_exr_read(a, &x, err, sizeof err) != RF_OK) {
        fprintf(stderr, "  %s\n", err);
        return 0;
    }
    if (rf_exr_read(b, &y, err, sizeof err) != RF_OK) {
        fprintf(stderr, "  %s\n", err);
        rf_image_free(&x);
        return 0;
    }
    int same = x.width == y.width && x.height == y.height && x.channels == y.channels &&
               memcmp(x.data, y.data, sizeof(float) * (size_t)x.width * (size_t)x.height * (size_t)x.channels) == 0;
    rf_image_free(&x);
    rf_image_free(&y);
    return same;
}

static void sleep_ms(long ms)
{
    struct timespec t = {ms / 1000, (ms % 1000) * 1000000L};
    nanosleep(&t, NULL);
}

static int exists(const char *path)
{
    struct stat sb;
    return stat(path, &sb) == 0;
}

#define RENDER_OPTS "--width 96 --height 72 --samples 2 --quiet"

/* The command line: 4 tiles merged equal the whole render; the tiles know their place; a
 * missing, overlapping, foreign or partial tile is refused with one message naming it, and no
 * output is written. */
static void t_farm_cli_tiles_merge(void)
{
    char dir[] = "/tmp/rf_farm_XXXXXX", cmd[4096];
    int code;
    if (!mkdtemp(dir)) {
        rf_test_fail(__FILE__, __LINE__, "mkdtemp");
        return;
    }
    const char *bin = rf_test_bin();
    snprintf(cmd, sizeof cmd,
             "set -e; %s render scenes/whitted.rf -o %s/full.exr " RENDER_OPTS "; for k in 0 1 2 3; do %s render "
             "scenes/whitted.rf -o %s/t$k.exr --tiles 4 --tile $k " RENDER_OPTS "; done; %s merge %s/t3.exr %s/t1.exr "
             "%s/t0.exr %s/t2.exr -o %s/merged.exr --png %s/merged.png 2>&1",
             bin, dir, bin, dir, bin, dir, dir, dir, dir, dir, dir);
    const char *out = rf_test_run(cmd, &code);
    RF_CHECK_EQ_INT(code, 0);
    RF_CHECK(strstr(out, "refray merge: 4 tiles") != NULL);
    char a[600], b[600];
    snprintf(a, sizeof a, "%s/full.exr", dir);
    snprintf(b, sizeof b, "%s/merged.exr", dir);
    RF_CHECK(same_pixels(a, b));
    /* tile 3 of 4 is the bottom right quarter, in place in a 96 x 72 picture */
    RfExrWindow data, disp;
    char err[512];
    snprintf(a, sizeof a, "%s/t3.exr", dir);
    RF_CHECK_EQ_INT(rf_exr_read_windows(a, &data, &disp, err, sizeof err), RF_OK);
    RF_CHECK(data.x0 == 48 && data.y0 == 36 && data.x1 == 96 && data.y1 == 72);
    RF_CHECK(disp.x0 == 0 && disp.y0 == 0 && disp.x1 == 96 && disp.y1 == 72);
    char *crop = rf_farm_attr(a, "refray:crop"), *hash = rf_farm_attr(a, "refray:sceneHash");
    RF_CHECK(crop && strcmp(crop, "48,36,96,72") == 0);
    RF_CHECK(hash && strlen(hash) == 16);
    free(crop);
    free(hash);
    /* refused sets: (files, what the message must say) */
    snprintf(cmd, sizeof cmd,
             "set -e; %s render scenes/whitted.rf -o %s/foreign.exr --tiles 4 --tile 2 --width 96 --height 72 "
             "--samples 3 --quiet; %s render scenes/whitted.rf -o %s/crop.exr --crop 40,30,60,50 " RENDER_OPTS "; "
             "sed 's/depth 8/depth 7/' scenes/whitted.rf > %s/other.rf; %s render %s/other.rf -o %s/otherscene.exr "
             "--tiles 4 --tile 2 " RENDER_OPTS,
             bin, dir, bin, dir, dir, bin, dir, dir);
    rf_test_run(cmd, &code);
    RF_CHECK_EQ_INT(code, 0);
    static const struct {
        const char *files, *says;
        int exit_code; /* README: Exit codes */
    } refused[] = {
        {"t0 t1 t3", "no tile covers pixels (0..47, 36): a tile is missing", 4},
        {"t0 t1 t2 t3 crop", "both cover pixel", 4},
        {"t0 t1 foreign t3", "foreign.exr: refray:settings is", 4},
        {"t0 t1 otherscene t3", "otherscene.exr: refray:sceneHash is", 4},
        {"t0 t1 t2 t3 t2", "is given twice", 5},
    };
    for (size_t i = 0; i < sizeof refused / sizeof refused[0]; i++) {
        char files[1024] = "";
        char list[128];
        snprintf(list, sizeof list, "%s", refused[i].files);
        for (char *f = strtok(list, " "); f; f = strtok(NULL, " ")) {
            size_t n = strlen(files);
            snprintf(files + n, sizeof files - n, " %s/%s.exr", dir, f);
        }
        snprintf(cmd, sizeof cmd, "%s merge%s -o %s/bad.exr 2>&1", bin, files, dir);
        out = rf_test_run(cmd, &code);
        if (code != refused[i].exit_code || !strstr(out, refused[i].says))
            rf_test_fail(__FILE__, __LINE__, "merge %s: exit %d, said: %s (expected: %s)", refused[i].files, code, out,
                         refused[i].says);
        rf_test_checks++;
        snprintf(a, sizeof a, "%s/bad.exr", dir);
        RF_CHECK(!exists(a));
    }
    /* --crop and --tiles checks */
    snprintf(cmd, sizeof cmd, "%s render scenes/whitted.rf -o %s/x.exr --crop 0,0,97,10 " RENDER_OPTS " 2>&1", bin, dir);
    out = rf_test_run(cmd, &code);
    RF_CHECK(code == 5 && strstr(out, "is not inside the 96x72 image"));
    snprintf(cmd, sizeof cmd, "%s render scenes/whitted.rf -o %s/x.exr --tiles 4 " RENDER_OPTS " 2>&1", bin, dir);
    out = rf_test_run(cmd, &code);
    RF_CHECK(code == 5 && strstr(out, "--tiles N and --tile K come together"));
    snprintf(cmd, sizeof cmd, "%s render scenes/whitted.rf -o %s/x.exr --crop 5,5,5,9 " RENDER_OPTS " 2>&1", bin, dir);
    out = rf_test_run(cmd, &code);
    RF_CHECK(code == 5 && strstr(out, "X0,Y0,X1,Y1"));
    snprintf(cmd, sizeof cmd, "rm -rf %s", dir);
    rf_test_run(cmd, &code);
}

/* An interrupted render resumes to the identical image: a render with a checkpoint gets SIGINT
 * (and another SIGTERM) once its checkpoint holds some tiles; it exits 130 (143) leaving the
 * checkpoint and no output; --resume finishes it, equal bit for bit to an uninterrupted render,
 * and removes the checkpoint. A checkpoint of other settings is refused. */
static void t_farm_cli_interrupt_resume(void)
{
    char dir[] = "/tmp/rf_farm_XXXXXX", cmd[4096], ck[600], outp[600], ref[600];
    int code;
    if (!mkdtemp(dir)) {
        rf_test_fail(__FILE__, __LINE__, "mkdtemp");
        return;
    }
    const char *bin = rf_test_bin();
    snprintf(ck, sizeof ck, "%s/ck.exr", dir);
    snprintf(outp, sizeof outp, "%s/out.exr", dir);
    snprintf(ref, sizeof ref, "%s/ref.exr", dir);
#define LONG_OPTS "--width 480 --height 360 --samples 24 --threads 2 --quiet"
    snprintf(cmd, sizeof cmd, "%s render scenes/whitted.rf -o %s " LONG_OPTS, bin, ref);
    rf_test_run(cmd, &code);
    RF_CHECK_EQ_INT(code, 0);
    static const int sigs[2] = {SIGINT, SIGTERM};
    for (int round = 0; round < 2; round++) {
        pid_t pid = fork();
        if (pid == 0) {
            execl(bin, bin, "render", "scenes/whitted.rf", "-o", outp, "--width", "480", "--height", "360", "--samples",
                  "24", "--threads", "2", "--quiet", "--checkpoint", ck, "--checkpoint-every", "0.05", (char *)NULL);
            _exit(127);
        }
        /* wait for the first checkpoint (at most 20 s), then interrupt */
        for (int i = 0; i < 2000 && !exists(ck); i++)
            sleep_ms(10);
        sleep_ms(50);
        kill(pid, sigs[round]);
        int status = 0;
        waitpid(pid, &status, 0);
        int rc = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
        if (rc == 0) { /* the render finished before the signal: nothing to resume this round */
            fprintf(stderr, "  the render finished before the signal (a fast machine): round %d not tested\n", round);
            rf_test_fail(__FILE__, __LINE__, "the render was not interrupted; make it longer");
            continue;
        }
        RF_CHECK_EQ_INT(rc, 128 + sigs[round]);
        RF_CHECK(exists(ck));
        RF_CHECK(!exists(outp));
        char *partial = rf_farm_attr(ck, "refray:partial"), *done = rf_farm_attr(ck, "refray:tilesDone");
        RF_CHECK(partial && strstr(partial, "PARTIAL RENDER") && strstr(partial, "tiles of 16x16 pixels done"));
        RF_CHECK(done && done[0]);
        free(partial);
        free(done);
        if (round == 1) { /* other settings cannot resume it */
            snprintf(cmd, sizeof cmd, "%s render scenes/whitted.rf -o %s --width 480 --height 360 --samples 23 "
                     "--threads 2 --quiet --resume %s 2>&1", bin, outp, ck);
            const char *out = rf_test_run(cmd, &code);
            RF_CHECK(code == 4 && strstr(out, "refray:settings is") && strstr(out, "another render"));
            RF_CHECK(exists(ck));
        }
        snprintf(cmd, sizeof cmd, "%s render scenes/whitted.rf -o %s " LONG_OPTS " --resume %s 2>&1", bin, outp, ck);
        rf_test_run(cmd, &code);
        RF_CHECK_EQ_INT(code, 0);
        RF_CHECK(same_pixels(outp, ref));
        RF_CHECK(!exists(ck)); /* done: the checkpoint is gone */
        unlink(outp);
    }
#undef LONG_OPTS
    snprintf(cmd, sizeof cmd, "rm -rf %s", dir);
    rf_test_run(cmd, &code);
}

/* examples/farm: GNU parallel renders 4 tiles on two local job slots ("-S 2/:") and a batch of
 * scenes; the Slurm job scripts run as Slurm would run them (one process per array index, then
 * the merge), and sbatch --test-only parses them where Slurm is installed. */
static void t_farm_examples(void)
{
    if (!rf_test_have("parallel")) {
        fprintf(stderr, "  skipped: GNU parallel is not installed (apt-get install parallel)\n");
        return;
    }
    char dir[] = "/tmp/rf_farm_XXXXXX", cmd[4096], a[600], b[600];
    int code;
    if (!mkdtemp(dir)) {
        rf_test_fail(__FILE__, __LINE__, "mkdtemp");
        return;
    }
    char bin[1100];
    if (!rf_test_tool("refray", bin, sizeof bin)) {
        rf_test_fail(__FILE__, __LINE__, "no %s", rf_test_bin());
        return;
    }
    snprintf(cmd, sizeof cmd, "sh tests/farm_examples.sh %s %s 2>&1", bin, dir);
    const char *out = rf_test_run(cmd, &code);
    if (code != 0)
        rf_test_fail(__FILE__, __LINE__, "tests/farm_examples.sh failed (exit %d):\n%s", code, out);
    rf_test_checks++;
    static const char *const pairs[][2] = {{"ref.exr", "parallel.exr"}, {"ref.exr", "slurm.exr"},
                                           {"ref_whitted.exr", "pbatch/whitted.exr"}, {"ref_tetra.exr", "pbatch/tetra.exr"},
                                           {"ref_whitted.exr", "sbatch/whitted.exr"}, {"ref_tetra.exr", "sbatch/tetra.exr"}};
    for (size_t i = 0; code == 0 && i < sizeof pairs / sizeof pairs[0]; i++) {
        snprintf(a, sizeof a, "%s/%s", dir, pairs[i][0]);
        snprintf(b, sizeof b, "%s/%s", dir, pairs[i][1]);
        if (!same_pixels(a, b))
            rf_test_fail(__FILE__, __LINE__, "%s differs from %s", b, a);
        rf_test_checks++;
    }
    snprintf(cmd, sizeof cmd, "rm -rf %s", dir);
    rf_test_run(cmd, &code);
}

const RfTest rf_tests_farm[] = {
    {"farm_crop_identical", t_farm_crop_identical},
    {"farm_resume_skip", t_farm_resume_skip},
    {"farm_tile_rect_partition", t_farm_tile_rect_partition},
    {"farm_cli_tiles_merge", t_farm_cli_tiles_merge},
    {"farm_cli_interrupt_resume", t_farm_cli_interrupt_resume},
    {"farm_examples", t_farm_examples},
    RF_TEST_END,
};
