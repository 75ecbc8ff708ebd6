/* Bad input as a hostile user gives it (issue 13): every case gets one clear message, a non-zero
 * exit code and no damaged or half-written file, and nothing crashes or hangs. One table, run
 * through the commands as a user runs them, in a scratch folder; every command is bounded by
 * `timeout`, so a hang fails the test instead of stopping the suite. */
#define _XOPEN_SOURCE 700
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "refray/camera.h"
#include "refray/render.h"
#include "refray/scene_io.h"
#include "rf_test.h"

#define CAM "camera eye 0 0 5 target 0 0 0 up 0 1 0 fov 40\nresolution 16 16\n"

static char dir[] = "/tmp/refray-robust-XXXXXX";
static char bin[PATH_MAX], raster[PATH_MAX], verify[PATH_MAX], data[PATH_MAX];

static void put(const char *name, const char *text)
{
    char path[PATH_MAX + 64];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    FILE *f = fopen(path, "wb");
    if (f) {
        fputs(text, f);
        fclose(f);
    }
}

/* A chain of `levels` groups, each placing the one below (twice with `dag`: 2^levels paths). */
static void put_graph(const char *name, int levels, int dag)
{
    size_t cap = (size_t)levels * 80 + 256, n = 0;
    char *t = malloc(cap);
    n += (size_t)snprintf(t + n, cap - n, CAM "object o0\nsphere 0 0 0 1\nend\n");
    for (int i = 1; i <= levels; i++) {
        n += (size_t)snprintf(t + n, cap - n, "group o%d\ninstance o%d translate 0.1 0 0\n", i, i - 1);
        if (dag)
            n += (size_t)snprintf(t + n, cap - n, "instance o%d translate -0.1 0 0\n", i - 1);
        n += (size_t)snprintf(t + n, cap - n, "end\n");
    }
    snprintf(t + n, cap - n, "instance o%d scale 0.3\n", levels);
    put(name, t);
    free(t);
}

static int exists(const char *name)
{
    char path[PATH_MAX + 64];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    return access(path, F_OK) == 0;
}

typedef struct {
    const char *what, *cmd; /* $R: refray, $X: refray-raster, $V: refray-verify, $D: tests/data/robust */
    int exit_code;          /* expected; -1: any non-zero */
    const char *message;    /* in the output (stdout and stderr) */
} Case;

static void run_case(const Case *c)
{
    static char cmd[4 * PATH_MAX + 8192], expanded[3 * PATH_MAX + 4096];
    size_t n = 0;
    for (const char *p = c->cmd; *p && n + PATH_MAX + 1 < sizeof expanded; p++) {
        if (p[0] == '$' && (p[1] == 'R' || p[1] == 'X' || p[1] == 'V' || p[1] == 'D')) {
            const char *r = p[1] == 'R' ? bin : p[1] == 'X' ? raster : p[1] == 'V' ? verify : data;
            n += (size_t)snprintf(expanded + n, sizeof expanded - n, "%s", r);
            p++;
        } else {
            expanded[n++] = *p;
        }
    }
    expanded[n] = 0;
    snprintf(cmd, sizeof cmd, "cd '%s' && timeout 60 sh -c '%s' 2>&1", dir, expanded);
    int rc;
    const char *out = rf_test_run(cmd, &rc);
    rf_test_checks++;
    int code_ok = c->exit_code < 0 ? rc != 0 && rc != 124 : rc == c->exit_code;
    if (!code_ok || (c->message && !strstr(out, c->message)))
        rf_test_fail(__FILE__, __LINE__, "%s: exit %d (expected %d), output:\n%s\n  expected to contain: %s", c->what,
                     rc, c->exit_code, out, c->message ? c->message : "(anything)");
}

static void t_bad_input_table(void)
{
    if (!realpath(rf_test_bin(), bin) || !rf_test_tool("refray-raster", raster, sizeof raster) ||
        !rf_test_tool("refray-verify", verify, sizeof verify) || !realpath(rf_test_data("robust"), data) ||
        !mkdtemp(dir)) {
        rf_test_fail(__FILE__, __LINE__, "cannot set up the scratch folder");
        return;
    }
    put("ok.rf", CAM "light point 0 0 5 intensity 1\nsphere 0 0 0 1\n");
    put_graph("chain.rf", 3000, 0);
    put_graph("dag.rf", 30, 1);
    put("inf.rf", CAM "light point 0 0 5 intensity 1\nmaterial m kd 0x1p1023\nsphere 0 0 0 1\n");
    put("zero.rf", CAM "mesh /dev/zero\n");
    put("zero.obj", "mtllib /dev/zero\nv 0 0 0\n");
    put("bom.rf", "\xEF\xBB\xBF" CAM "sphere 0 0 0 1\n");
    put("crlf.rf", "camera eye 0 0 5 target 0 0 0 up 0 1 0 fov 40\r\nsphere 0 0 0 1\r\nsphere 0 0 0 2 bogus\r\n");
    put("garbage.jsonl", "{\"id\":\"dot\",\"in\":{\"a\":[1,2,3],\"b\":[4,5,6]}} garbage\n");
    put("nul.jsonl", "{\"id\":\"dot\",\"in\":{\"a\":[1,2,3],\0\"b\":[4,5,6]}}\n");
    {
        char path[PATH_MAX + 64];
        snprintf(path, sizeof path, "%s/nul.jsonl", dir); /* the NUL above ended the string: write it raw */
        FILE *f = fopen(path, "wb");
        static const char line[] = "{\"id\":\"dot\",\"in\":{\"a\":[1,2,3],\0\"b\":[4,5,6]}}\n";
        if (f) {
            fwrite(line, 1, sizeof line - 1, f);
            fclose(f);
        }
    }
    static const Case cases[] = {
        /* crashes and hangs */
        {"3000 nested instances (render)", "$R render chain.rf -o a.exr", 4, "nested deeper than 64 levels"},
        {"3000 nested instances (info)", "$R info chain.rf", 4, "chain.rf:196:1: instances nested deeper"},
        {"3000 nested instances (raster)", "$X chain.rf -o a.exr", 4, "nested deeper than 64 levels"},
        {"a DAG of 30 doubling levels (info: once per object)", "$R info dag.rf", 0, "objects   31"},
        {"a DAG of 30 doubling levels (raster refuses to expand it)", "$X dag.rf -o a.exr", 2,
         "expands to 0 triangles in 2147483647 placements"},
        {"a DAG of 30 doubling levels (the verifier refuses to expand it)", "$V dag.rf --rays 100", 2,
         "expands to 2147483647 placements"},
        {"3000 nested instances (verifier)", "$V chain.rf --rays 100", -1, "nested deeper than 64 levels"},
        {"a 4-vector for a 3-vector", "$R formula srgb-encode rgb=1,2,3,4", 5, "input 'rgb' has 4 components; it takes 3"},
        {"mesh /dev/zero", "$R info zero.rf", 4, "zero.rf:3:6: mesh '/dev/zero': not a regular file"},
        {"mtllib /dev/zero", "$R info zero.obj", 4, "material library '/dev/zero': not a regular file"},
        {"a FIFO as the scene", "rm -f fifo.rf; mkfifo fifo.rf; $R info fifo.rf", 4,
         "refray info: fifo.rf: not a regular file"},
        {"a device as an image", "$R diff /dev/zero /dev/zero", 4, "not a regular file"},
        {"the EXR write fails (file size limit)", "ulimit -f 0; $R render ok.rf -o big.exr --quiet", 4,
         "cannot write EXR: write failed: File too large"},
        {"an infinite radiance fails a reference render", "$R render inf.rf -o inf.exr", 2,
         "float-overflowing radiance"},
        {"... and is black and counted in a preview", "$R render inf.rf -o inf.exr --preview", 0, "invalid samples"},
        {"a diff of images with Inf never passes", "$R diff $D/inf.exr $D/inf.exr", 2, "verdict: FAIL"},
        /* files */
        {"-o the scene itself", "$R render ok.rf -o ok.rf", 5, "-o ok.rf: the name must end in .exr or .png"},
        {"-o X --png X", "$R render ok.rf -o x.png --png x.png", 5, "is given as two outputs"},
        {"-o a name without .exr or .png", "$R render ok.rf -o x.out", 5,
         "refray render: -o x.out: the name must end in .exr or .png (the format follows it)"},
        {"-o /dev/full", "ln -sf /dev/full full.exr; $R render ok.rf -o full.exr", 4,
         "not a regular file (a device, directory or pipe)"},
        {"an output folder that does not exist", "$R render ok.rf -o a.exr --png nodir/a.png", 4,
         "nodir/a.png: cannot create a temporary file next to it"},
        {"-o \"\"", "$R render ok.rf -o \"\"", 5, "refray render: -o : the name must end in .exr or .png"},
        {"--width 0", "$R render ok.rf -o a.exr --width 0", 5, "bad value '0' for --width: an integer in [1, 65536]"},
        {"an EXR with R only", "$R diff $D/only_r.exr $D/only_r.exr", 4, "EXR channels R: refray reads R, G and B"},
        {"an EXR with G and B only", "$R diff $D/only_gb.exr $D/only_gb.exr", 4, "EXR channels B, G"},
        {"a heatmap over one of the images", "$R diff $D/only_r.exr $D/only_gb.exr --heatmap $D/only_r.exr", 5,
         "is an input"},
        /* bad text */
        {"a UTF-8 byte order mark", "$R info bom.rf", 0, "primitives 1"},
        {"CRLF line ends keep their positions", "$R info crlf.rf", 4, "crlf.rf:3:16: unknown attribute 'bogus'"},
        {"trailing garbage after a JSON line", "$R formula --batch garbage.jsonl", 4, "garbage.jsonl:1: the line is not valid JSON"},
        {"a NUL byte in a batch line", "$R formula --batch nul.jsonl", 4, "nul.jsonl:1: the line is not valid JSON"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++)
        run_case(&cases[i]);
    /* nothing half-written or damaged */
    RF_CHECK(!exists("a.exr") && !exists("inf.exr.tmp") && !exists("big.exr") && !exists("x.out") && !exists("x.png"));
    struct stat sb;
    RF_CHECK(stat("/dev/full", &sb) == 0 && S_ISCHR(sb.st_mode));
    char cmd[PATH_MAX * 2];
    int rc;
    snprintf(cmd, sizeof cmd, "ls -A '%s' | grep -c 'XXXXXX\\|\\.exr\\.\\|\\.png\\.' ", dir);
    RF_CHECK(strcmp(rf_test_run(cmd, &rc), "0\n") == 0); /* no temporary file left */
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
    rf_test_run(cmd, &rc);
}

/* Writing through a symbolic link writes the file it names; the link stays. A failed second
 * output leaves no first one. */
static void t_outputs_links_and_batches(void)
{
    char d[] = "/tmp/refray-out-XXXXXX", cmd[PATH_MAX * 3], b[PATH_MAX];
    int rc;
    if (!mkdtemp(d) || !realpath(rf_test_bin(), b))
        return;
    snprintf(cmd, sizeof cmd,
             "cd '%s' && printf '" CAM "sphere 0 0 0 1\\n' > s.rf && touch real.exr && ln -s real.exr link.exr && "
             "'%s' render s.rf -o link.exr --quiet && test -L link.exr && test -s real.exr && echo through",
             d, b);
    RF_CHECK(strstr(rf_test_run(cmd, &rc), "through") != NULL);
    snprintf(cmd, sizeof cmd,
             "cd '%s' && (ulimit -f 2; '%s' render s.rf -o first.exr --png second.png --width 200 --height 200 "
             "--quiet); ls", d, b);
    const char *out = rf_test_run(cmd, &rc);
    RF_CHECK(!strstr(out, "first.exr") && !strstr(out, "second.png"));
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", d);
    rf_test_run(cmd, &rc);
}


/* Opaque shadows (§3.8): every surface blocks a shadow ray from either side, one-sided or not,
 * inside-only spheres too. Checked with the occlusion query and in a render: a floor point
 * under each blocker is in shadow whichever way the blocker faces. (A bug planted in an earlier
 * review, shadow rays that skip one-sided surfaces, passed every other test.) */
static void t_shadows_from_either_side(void)
{
    static const char *blockers[] = {
        "polygon 4 -1 2 -1  -1 2 1  1 2 1  1 2 -1 one-sided",  /* faces up: the shadow ray meets its back */
        "polygon 4 -1 2 -1  1 2 -1  1 2 1  -1 2 1 one-sided",  /* faces down */
        "triangle -2 2 -2  0 2 3  2 2 -2 one-sided",
        "triangle -2 2 -2  2 2 -2  0 2 3 one-sided",
        "sphere 0 2 0 0.5 one-sided",
        "sphere 0 2 0 0.5 inside",
        "plane 0 2 0  0 1 0 one-sided",
        "plane 0 2 0  0 -1 0 one-sided",
        "cylinder -1 2 0  1 2 0  0.5 one-sided", /* lying: the vertical rays meet its wall twice */
        "cone -1 2 0 0.6  1 2 0 0.2 inside",
    };
    for (size_t i = 0; i < sizeof blockers / sizeof blockers[0]; i++) {
        char text[1024], err[512];
        RfScene s;
        snprintf(text, sizeof text,
                 "camera eye 0 6 0.01 target 0 0 0 up 0 0 -1 fov 20\nresolution 9 9\nlight point 0 5 0 intensity 30\n"
                 "material m kd 1\npolygon 4 -9 0 -9  -9 0 9  9 0 9  9 0 -9\n%s\n", blockers[i]);
        if (rf_scene_read_rf("t.rf", text, strlen(text), &s, err, sizeof err) != RF_OK) {
            rf_test_fail(__FILE__, __LINE__, "%s: %s", blockers[i], err);
            continue;
        }
        RfTracer *t = NULL;
        RF_CHECK_EQ_INT(rf_tracer_create(&s, &t), RF_OK);
        /* up from the floor and down from above the light: both cross the blocker */
        RF_CHECK(rf_tracer_occluded(t, &(RfRay){rf_vec3(0, 1e-6, 0), rf_vec3(0, 1, 0)}, 0.0, 5.0));
        RF_CHECK(rf_tracer_occluded(t, &(RfRay){rf_vec3(0, 4.5, 0), rf_vec3(0, -1, 0)}, 0.0, 4.0));
        rf_tracer_free(t);
        /* and the render: the floor under the blocker is black (no ambient) */
        RfRenderOptions o = rf_render_options_default();
        RfImage img;
        RfRenderStats st;
        o.threads = 1;
        o.local_only = 0;
        if (rf_render(&s, &o, &img, &st) == RF_OK) {
            /* the centre pixel sees the blocker or the floor under it: either way no direct light
             * reaches the floor point, and a blocker seen from above is lit or not by its side */
            RfSurfaceHit h;
            RfTracer *t2 = NULL;
            rf_tracer_create(&s, &t2);
            RfCamera cam;
            RfWindow w = rf_scene_camera_window(&s.camera, 9, 9);
            rf_camera_init(&cam, s.camera.eye, s.camera.target, s.camera.up, w.d, w.l, w.r, w.b, w.t, 9, 9);
            RfRay centre = rf_camera_ray(&cam, 4.5, 4.5, 0, 0);
            int prim = rf_tracer_intersect(t2, &centre, 0.0, HUGE_VAL, &h);
            if (prim == 0 && img.data[3 * (4 * 9 + 4)] != 0.0f) /* the floor itself is seen: in shadow */
                rf_test_fail(__FILE__, __LINE__, "%s: the floor under it is lit (%g)", blockers[i],
                             img.data[3 * (4 * 9 + 4)]);
            rf_tracer_free(t2);
            rf_image_free(&img);
        }
        rf_scene_free(&s);
    }
}


/* Scale-invariant robustness: the whitted scene scaled by powers of ten from 1e-12 to 1e12
 * (light intensities by the square, so the irradiance stays) renders the same image bit for
 * bit, and moved by 1e3 .. 1e8 (a million times the extent of its objects and camera, about
 * 100: the ground is 60 wide) keeps at least 99.9 % of its values within 1e-6 and loses no
 * light (no value that is lit at scale 1 goes black). Measured: moved by 1e7, 6e7 and 1e8, 0,
 * 15 and 18 of 20736 values are off by more than 1e-6 (with the former offset of 1e-13 of |p|
 * and |o|: 86, 270 and 362). */
static int whitted_at(double s, double shift, RfImage *img)
{
    char text[4096], err[512];
    RfScene sc;
#define P(v) ((v) * s + shift)
    snprintf(text, sizeof text,
             "camera eye %.17g %.17g %.17g target %.17g %.17g %.17g up 0 1 0 fov 40\nresolution 96 72\ndepth 8\n"
             "background 0\nambient 0.05\nlight point %.17g %.17g %.17g intensity %.17g\n"
             "material ground kd 0.6 ka 0.6\npolygon 4 %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g\n"
             "material red kd 0.7 0.08 0.08 ka 0.7 0.08 0.08 ks 0.5 shininess 50\nsphere %.17g %.17g %.17g %.17g\n"
             "material mirror kr 0.9\nsphere %.17g %.17g %.17g %.17g\n"
             "material glass kr 1 kt 1 ior 1.5 fresnel\nsphere %.17g %.17g %.17g %.17g\n",
             P(0.0), P(2.6), P(7.0), P(0.0), P(0.6), P(0.0), P(-5.0), P(6.0), P(2.0), 60.0 * s * s, P(-30.0), P(0.0),
             P(-30.0), P(-30.0), P(0.0), P(30.0), P(30.0), P(0.0), P(30.0), P(30.0), P(0.0), P(-30.0), P(-2.0), P(0.8),
             P(-0.3), 0.8 * s, P(0.1), P(1.0), P(-1.3), 1.0 * s, P(1.1), P(0.6), P(1.4), 0.6 * s);
#undef P
    if (rf_scene_read_rf("w.rf", text, strlen(text), &sc, err, sizeof err) != RF_OK) {
        rf_test_fail(__FILE__, __LINE__, "%s", err);
        return 0;
    }
    RfRenderOptions o = rf_render_options_default();
    o.threads = 2;
    RfRenderStats st;
    int ok = rf_render(&sc, &o, img, &st) == RF_OK;
    rf_scene_free(&sc);
    return ok;
}

static void t_scale_invariance(void)
{
    RfImage ref, img;
    if (!whitted_at(1.0, 0.0, &ref))
        return;
    size_t n = (size_t)ref.width * ref.height * 3;
    static const double scales[] = {1e-12, 1e-6, 1e-3, 1e3, 1e6, 1e12};
    for (size_t k = 0; k < sizeof scales / sizeof scales[0]; k++) {
        if (!whitted_at(scales[k], 0.0, &img))
            continue;
        size_t changed = 0;
        for (size_t i = 0; i < n; i++)
            changed += memcmp(&img.data[i], &ref.data[i], sizeof(float)) != 0;
        rf_test_checks++;
        if (changed)
            rf_test_fail(__FILE__, __LINE__, "whitted scaled by %g: %zu of %zu values differ", scales[k], changed, n);
        rf_image_free(&img);
    }
    static const double shifts[] = {1e3, 1e6, 1e7, 6e7, 1e8};
    for (size_t k = 0; k < sizeof shifts / sizeof shifts[0]; k++) {
        if (!whitted_at(1.0, shifts[k], &img))
            continue;
        size_t far = 0, lost = 0;
        for (size_t i = 0; i < n; i++) {
            far += fabs((double)img.data[i] - ref.data[i]) > 1e-6;
            lost += ref.data[i] > 0.05f && img.data[i] == 0.0f;
        }
        rf_test_checks++;
        if (far * 1000 > n || lost)
            rf_test_fail(__FILE__, __LINE__, "whitted moved by %g: %zu of %zu values off by more than 1e-6, %zu lost",
                         shifts[k], far, n, lost);
        rf_image_free(&img);
    }
    rf_image_free(&ref);
}

const RfTest rf_tests_robust[] = {
    {"robust_bad_input_table", t_bad_input_table},
    {"robust_outputs_links_and_batches", t_outputs_links_and_batches},
    {"robust_shadows_from_either_side", t_shadows_from_either_side},
    {"robust_scale_invariance", t_scale_invariance},
    RF_TEST_END,
};
