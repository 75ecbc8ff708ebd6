/* The comparator (issue 5): diff metrics against hand-computed values, the silhouette mask,
 * `refray diff` exit codes, the OpenGL rasterizer against the tracer (--local) on a scene with
 * every primitive and light kind, a known-answer projection test, and planted errors (a flipped
 * normal, a wrong Phong exponent, a camera off by half a pixel) that the comparison must catch.
 * The rasterizer runs through OSMesa: no display needed. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "../compare/gl_context.h"
#include "../compare/raster.h"
#include "refray/camera.h"
#include "refray/diff.h"
#include "refray/render.h"
#include "refray/scene_io.h"
#include "rf_test.h"

/* ---- diff metrics ---- */


/* The GL back end of these tests: RF_GL=osmesa|egl|auto (default auto); CI runs them with each. */
static RfGlBackend test_gl(void)
{
    const char *e = getenv("RF_GL");
    int b = e ? rf_gl_backend_parse(e) : RF_GL_AUTO;
    return b < 0 ? RF_GL_AUTO : (RfGlBackend)b;
}

static RfImage tiny(int w, int h, int ch, const float *v)
{
    RfImage img;
    rf_image_alloc(&img, w, h, ch);
    memcpy(img.data, v, sizeof *v * (size_t)(w * h * ch));
    return img;
}

static void test_diff_metrics_by_hand(void)
{
    const float va[] = {0, 0, 0, 1, 1, 1}, vb[] = {0, 0, 0, 0.5f, 1, 1};
    RfImage a = tiny(2, 1, 3, va), b = tiny(2, 1, 3, vb);
    RfDiffResult r;
    char err[256];
    RF_CHECK(rf_diff_images(&a, &b, NULL, NULL, NULL, &r, NULL, err, sizeof err) == RF_OK);
    /* channel errors 0 0 0 0.5 0 0 */
    RF_CHECK_NEAR(r.all.max_abs, 0.5, 0, 0);
    RF_CHECK_EQ_INT(r.all.max_x, 1);
    RF_CHECK_EQ_INT(r.all.max_y, 0);
    RF_CHECK_NEAR(r.all.mean_abs, 0.5 / 6.0, 1e-15, 0);
    RF_CHECK_NEAR(r.all.rmse, sqrt(0.25 / 6.0), 1e-15, 0);
    RF_CHECK_NEAR(r.all.psnr, 20.0 * log10(1.0 / sqrt(0.25 / 6.0)), 1e-12, 0); /* 13.80 dB */
    RF_CHECK_NEAR(r.all.rel_mse, 0.25 / (0.25 + 0.01) / 6.0, 1e-12, 0);
    RF_CHECK_EQ_INT(r.all.above_255, 1);
    RF_CHECK_NEAR(rf_diff_percent(r.all.above_255, &r.all), 50.0, 0, 0);
    RF_CHECK_EQ_INT(r.verdict, RF_DIFF_FAIL);
    RF_CHECK_EQ_INT(r.has_depth, 0);
    RF_CHECK_EQ_INT(r.interior.pixels, 2);
    /* identical: PASS, PSNR infinite */
    RF_CHECK(rf_diff_images(&a, &a, NULL, NULL, NULL, &r, NULL, err, sizeof err) == RF_OK);
    RF_CHECK(r.verdict == RF_DIFF_PASS && r.all.max_abs == 0.0 && isinf(r.all.psnr));
    /* sizes differ: refused with a message */
    RfImage c = tiny(1, 2, 3, va);
    RF_CHECK(rf_diff_images(&a, &c, NULL, NULL, NULL, &r, NULL, err, sizeof err) == RF_ERR_DOMAIN);
    RF_CHECK(strstr(err, "sizes differ") != NULL);
    /* NaN on one side fails whatever the thresholds */
    b.data[0] = NAN;
    RfDiffOptions o = rf_diff_options_default();
    o.fail = o.warn = INFINITY;
    o.fail_mean = INFINITY;
    b.data[3] = 1;
    RF_CHECK(rf_diff_images(&a, &b, NULL, NULL, &o, &r, NULL, err, sizeof err) == RF_OK);
    RF_CHECK_EQ_INT(r.all.nonfinite, 1);
    RF_CHECK_EQ_INT(r.verdict, RF_DIFF_FAIL);
    rf_image_free(&a), rf_image_free(&b), rf_image_free(&c);
}

static void test_diff_verdict_ladder(void)
{
    /* 1000 pixels; one pixel off by e in one channel */
    float *v = calloc(3000, sizeof *v);
    RfImage a = tiny(1000, 1, 3, v), b = tiny(1000, 1, 3, v);
    RfDiffResult r;
    char err[64];
    b.data[0] = 5e-4f; /* above warn (1e-4) on 0.1 % of pixels: not more than 0.1 %: PASS */
    rf_diff_images(&a, &b, NULL, NULL, NULL, &r, NULL, err, sizeof err);
    RF_CHECK_EQ_INT(r.verdict, RF_DIFF_PASS);
    b.data[3] = 5e-4f; /* 0.2 % above warn, mean 1/3000 of 1e-3: WARN */
    rf_diff_images(&a, &b, NULL, NULL, NULL, &r, NULL, err, sizeof err);
    RF_CHECK_EQ_INT(r.verdict, RF_DIFF_WARN);
    b.data[0] = b.data[3] = 0.01f; /* 0.2 % above 1/255: FAIL */
    rf_diff_images(&a, &b, NULL, NULL, NULL, &r, NULL, err, sizeof err);
    RF_CHECK_EQ_INT(r.verdict, RF_DIFF_FAIL);
    b.data[3] = 0.0f; /* 0.1 % above 1/255 (allowed), mean 0.01/3000 < 1e-4: PASS? warn share 0.1 %: PASS */
    rf_diff_images(&a, &b, NULL, NULL, NULL, &r, NULL, err, sizeof err);
    RF_CHECK_EQ_INT(r.verdict, RF_DIFF_PASS);
    b.data[0] = 0.9f; /* mean 0.9 / 3000 = 3e-4 > 1e-4: FAIL by the mean */
    rf_diff_images(&a, &b, NULL, NULL, NULL, &r, NULL, err, sizeof err);
    RF_CHECK_EQ_INT(r.verdict, RF_DIFF_FAIL);
    free(v), rf_image_free(&a), rf_image_free(&b);
}

static void test_diff_silhouettes(void)
{
    /* 1/z linear across a plane: never an edge; a step: the pixels around it */
    const float plane[5] = {1.0f / 1.0f, 1.0f / 0.9f, 1.0f / 0.8f, 1.0f / 0.7f, 1.0f / 0.6f};
    const float step[5] = {1, 1, 1, 2, 2}, bg[5] = {3, 3, INFINITY, INFINITY, INFINITY};
    unsigned char m[5];
    RfImage d = tiny(5, 1, 1, plane);
    memset(m, 0, sizeof m);
    rf_diff_silhouettes(&d, 0.01, m);
    RF_CHECK(m[0] + m[1] + m[2] + m[3] + m[4] == 0);
    memcpy(d.data, step, sizeof step);
    rf_diff_silhouettes(&d, 0.01, m);
    RF_CHECK(m[0] == 0 && m[1] && m[2] && m[3] && m[4]);
    memset(m, 0, sizeof m);
    memcpy(d.data, bg, sizeof bg);
    rf_diff_silhouettes(&d, 0.01, m);
    RF_CHECK(m[0] && m[1] && m[2] && m[3] && !m[4]); /* background next to background: no edge */
    rf_image_free(&d);
}

/* ---- exit codes of `refray diff` ---- */

static void write_exr(const char *path, int w, int h, float v0)
{
    RfImage img;
    char err[256];
    rf_image_alloc(&img, w, h, 3);
    img.data[0] = v0;
    rf_exr_write(path, &img, NULL, 0, err, sizeof err);
    rf_image_free(&img);
}

static void test_diff_exit_codes(void)
{
    char dir[] = "/tmp/rf_cmpXXXXXX", a[64], b[64], c[64], d[64], e[64], cmd[512];
    int rc;
    if (!mkdtemp(dir)) {
        RF_CHECK(!"mkdtemp");
        return;
    }
    snprintf(a, sizeof a, "%s/a.exr", dir), snprintf(b, sizeof b, "%s/b.exr", dir);
    snprintf(c, sizeof c, "%s/c.exr", dir), snprintf(d, sizeof d, "%s/d.exr", dir);
    snprintf(e, sizeof e, "%s/small.exr", dir);
    write_exr(a, 10, 10, 0.0f);
    write_exr(b, 10, 10, 5e-4f);  /* 1 % of the pixels above warn: WARN */
    write_exr(c, 10, 10, 0.5f);   /* 1 % above 1/255: FAIL */
    write_exr(d, 10, 10, 0.0f);
    write_exr(e, 5, 10, 0.0f);
    const char *cases[][2] = {{d, "0"}, {b, "1"}, {c, "2"}, {e, "3"}, {"/nonexistent.exr", "4"}};
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        snprintf(cmd, sizeof cmd, "%s diff %s %s --heatmap %s/heat.png 2>&1", rf_test_bin(), cases[i][0], a, dir);
        const char *out = rf_test_run(cmd, &rc);
        if (rc != atoi(cases[i][1]))
            fprintf(stderr, "refray diff %s: exit %d, expected %s\n%s", cases[i][0], rc, cases[i][1], out);
        RF_CHECK_EQ_INT(rc, atoi(cases[i][1]));
    }
    snprintf(cmd, sizeof cmd, "%s diff %s 2>/dev/null", rf_test_bin(), a);
    rf_test_run(cmd, &rc);
    RF_CHECK_EQ_INT(rc, 5); /* usage */
    snprintf(cmd, sizeof cmd, "%s diff %s %s --bogus 2>/dev/null", rf_test_bin(), a, a);
    rf_test_run(cmd, &rc);
    RF_CHECK_EQ_INT(rc, 5);
    /* two EXRs are compared in linear values; a student's PNG against the reference EXR in
     * display values, so that a perfect 8-bit PNG of the EXR passes (in linear values its bright
     * pixels would be up to 2.2/255 off) */
    snprintf(cmd, sizeof cmd, "%s diff %s %s --kv", rf_test_bin(), c, a);
    const char *out = rf_test_run(cmd, &rc);
    RF_CHECK(strstr(out, "space=linear") != NULL);
    RfImage g;
    char png[64], exr[64], err[256];
    RfPngOptions po = {RF_PNG_GAMMA, 2.2, 8, NULL};
    rf_image_alloc(&g, 64, 4, 3);
    for (int i = 0; i < 64 * 4 * 3; i++)
        g.data[i] = (float)(i % 192) / 191.0f;
    snprintf(png, sizeof png, "%s/student.png", dir), snprintf(exr, sizeof exr, "%s/ref.exr", dir);
    RF_CHECK(rf_png_write(png, &g, po, err, sizeof err) == RF_OK);
    RF_CHECK(rf_exr_write(exr, &g, NULL, 0, err, sizeof err) == RF_OK);
    rf_image_free(&g);
    snprintf(cmd, sizeof cmd, "%s diff %s %s --kv", rf_test_bin(), png, exr);
    out = rf_test_run(cmd, &rc);
    RF_CHECK(strstr(out, "space=display") != NULL);
    RF_CHECK_EQ_INT(rc, 0);
    snprintf(cmd, sizeof cmd, "%s diff %s %s --space linear >/dev/null", rf_test_bin(), png, exr);
    rf_test_run(cmd, &rc);
    RF_CHECK_EQ_INT(rc, 2);
    snprintf(cmd, sizeof cmd, "rm -rf %s", dir);
    rf_test_run(cmd, &rc);
}

/* ---- rasterizer against tracer ---- */

static int load_feature(RfScene *s)
{
    char err[512];
    /* compare/features.rf: every primitive and light kind (the report renders it too) */
    if (rf_scene_load("compare/features.rf", NULL, s, err, sizeof err) != RF_OK) {
        fprintf(stderr, "%s\n", err);
        return 0;
    }
    return 1;
}

/* renders `raster` with GL and `traced` with the tracer (--local, with depth) and diffs them; the
 * two_sided flags are each side's --two-sided */
static int compare_sides(const RfScene *raster, int raster_two_sided, const RfScene *traced, int tracer_two_sided,
                         RfDiffResult *res)
{
    RfGlContext *ctx = NULL;
    RfImage ci, di, ct, dt;
    RfRasterOptions ro = {0, 0, RF_SHADE_PHONG, raster_two_sided};
    RfRenderOptions to = rf_render_options_default();
    RfTracerOptions tro = rf_tracer_options_default();
    RfRenderStats st;
    char err[512];
    to.local_only = 1;
    to.threads = 2;
    to.two_sided = tro.two_sided = tracer_two_sided;
    if (rf_gl_context_create(test_gl(), &ctx, err, sizeof err) != RF_OK) {
        fprintf(stderr, "%s\n", err);
        return 0;
    }
    RfStatus s = rf_raster_render(raster, &ro, rf_gl_context_proc, ctx, &ci, &di, err, sizeof err);
    rf_gl_context_destroy(ctx);
    if (s != RF_OK) {
        fprintf(stderr, "raster: %s\n", err);
        return 0;
    }
    if (rf_render(traced, &to, &ct, &st) != RF_OK) {
        rf_image_free(&ci), rf_image_free(&di);
        return 0;
    }
    /* the tracer's depth, as `refray render --depth-out` computes it */
    RfCamera cam;
    RfTracer *tr = NULL;
    const RfSceneCamera *sc = &traced->camera;
    RfWindow w = rf_scene_camera_window(sc, ct.width, ct.height);
    rf_camera_init(&cam, sc->eye, sc->target, sc->up, w.d, w.l, w.r, w.b, w.t, ct.width, ct.height);
    rf_tracer_create_opts(traced, &tro, &tr);
    rf_image_alloc(&dt, ct.width, ct.height, 1);
    for (int y = 0; y < ct.height; y++)
        for (int x = 0; x < ct.width; x++) {
            RfRay ray = rf_camera_ray(&cam, x + 0.5, y + 0.5, 0, 0);
            RfSurfaceHit h;
            double c = -rf_vec3_dot(ray.dir, cam.basis.w);
            dt.data[y * ct.width + x] = rf_tracer_intersect(tr, &ray, sc->hither / c, HUGE_VAL, &h) >= 0
                                            ? (float)(h.t * c) : INFINITY;
        }
    rf_tracer_free(tr);
    s = rf_diff_images(&ci, &ct, &di, &dt, NULL, res, NULL, err, sizeof err);
    rf_image_free(&ci), rf_image_free(&di), rf_image_free(&ct), rf_image_free(&dt);
    return s == RF_OK;
}

/* the comparator's bar for a match (docs/compare.md): the verdict, the interior's mean and share
 * above 1/255, the depth, and silhouettes a small part of the image */
static void check_match(const char *what, const RfDiffResult *r)
{
    if (r->verdict != RF_DIFF_PASS)
        fprintf(stderr, "%s: interior mean %g max %g at (%d, %d), %ld above 1/255\n", what, r->interior.mean_abs,
                r->interior.max_abs, r->interior.max_x, r->interior.max_y, r->interior.above_255);
    RF_CHECK_EQ_INT(r->verdict, RF_DIFF_PASS);
    RF_CHECK(r->interior.mean_abs <= 1e-4);
    RF_CHECK(rf_diff_percent(r->interior.above_255, &r->interior) <= 0.1);
    RF_CHECK(r->depth_max_rel < 1e-5);
    RF_CHECK(r->silhouette < r->all.pixels / 5);
}

static int compare(const RfScene *raster, const RfScene *traced, RfDiffResult *res)
{
    return compare_sides(raster, 0, traced, 0, res);
}

static void test_raster_matches_tracer(void)
{
    RfScene s;
    RfDiffResult r;
    if (!load_feature(&s)) {
        RF_CHECK(!"feature scene");
        return;
    }
    RF_CHECK(compare(&s, &s, &r));
    check_match("feature scene", &r);
    rf_scene_free(&s);
}

/* refray-raster --two-sided against refray render --two-sided: the feature scene with its
 * one-sided ground plane turned over (seen from below, so culled by both renderers unless
 * two-sided) matches when both draw every surface from both sides, and fails when only the
 * rasterizer does. */
static void test_raster_two_sided(void)
{
    RfScene s;
    RfDiffResult r;
    if (!load_feature(&s)) {
        RF_CHECK(!"feature scene");
        return;
    }
    int planes = 0;
    for (size_t i = 0; i < s.prim_count; i++)
        if (s.prims[i].type == RF_PRIM_PLANE) {
            s.prims[i].u.plane.normal = rf_vec3_neg(s.prims[i].u.plane.normal);
            s.prims[i].u.plane.offset = -s.prims[i].u.plane.offset;
            planes++;
        }
    RF_CHECK_EQ_INT(planes, 1);
    RF_CHECK(compare_sides(&s, 1, &s, 1, &r));
    check_match("feature scene, ground turned over, both two-sided", &r);
    RF_CHECK(compare_sides(&s, 1, &s, 0, &r));
    RF_CHECK_EQ_INT(r.verdict, RF_DIFF_FAIL);
    rf_scene_free(&s);
}

static void test_planted_errors(void)
{
    RfScene good, bad;
    RfDiffResult r;
    if (!load_feature(&good) || !load_feature(&bad)) {
        RF_CHECK(!"feature scene");
        return;
    }
    /* 1. a flipped normal: the smooth triangle's first vertex normal points backwards */
    for (size_t i = 0; i < bad.prim_count; i++)
        if (bad.prims[i].type == RF_PRIM_TRIANGLE)
            bad.normals[bad.prims[i].u.poly.nfirst] = rf_vec3_neg(bad.normals[bad.prims[i].u.poly.nfirst]);
    RF_CHECK(compare(&good, &bad, &r));
    RF_CHECK_EQ_INT(r.verdict, RF_DIFF_FAIL);
    rf_scene_free(&bad);
    /* 1b. a flipped plane normal: the one-sided ground is seen from behind (culled) */
    load_feature(&bad);
    for (size_t i = 0; i < bad.prim_count; i++)
        if (bad.prims[i].type == RF_PRIM_PLANE) {
            bad.prims[i].u.plane.normal = rf_vec3_neg(bad.prims[i].u.plane.normal);
            bad.prims[i].u.plane.offset = -bad.prims[i].u.plane.offset;
        }
    RF_CHECK(compare(&good, &bad, &r));
    RF_CHECK_EQ_INT(r.verdict, RF_DIFF_FAIL);
    rf_scene_free(&bad);
    /* 2. a wrong Phong exponent: 40 -> 32 on the red sphere */
    load_feature(&bad);
    for (size_t i = 0; i < bad.material_count; i++)
        if (strcmp(bad.materials[i].name, "red") == 0)
            bad.materials[i].shininess = 32;
    RF_CHECK(compare(&good, &bad, &r));
    RF_CHECK_EQ_INT(r.verdict, RF_DIFF_FAIL);
    rf_scene_free(&bad);
    /* 3. the camera off by half a pixel: the window shifted right by (r - l) / (2 W) */
    load_feature(&bad);
    RfWindow w = rf_scene_camera_window(&bad.camera, bad.render.width, bad.render.height);
    double half = 0.5 * (w.r - w.l) / bad.render.width;
    bad.camera.has_window = 1;
    bad.camera.l = w.l + half, bad.camera.r = w.r + half, bad.camera.b = w.b, bad.camera.t = w.t;
    RF_CHECK(compare(&good, &bad, &r));
    RF_CHECK_EQ_INT(r.verdict, RF_DIFF_FAIL);
    rf_scene_free(&bad);
    rf_scene_free(&good);
}

/* eye (0,0,5) looking at -z, window [-1,1]^2 at d = 1, 8 x 8 pixels: at z = 0 a pixel is 1.25
 * wide and pixel (i, j) has its centre at x = -5 + 1.25 (i + 0.5), y = 5 - 1.25 (j + 0.5). The
 * emitting square [0, 2.5] x [0, 1.25] at z = 0 covers exactly the centres of pixels (4, 3) and
 * (5, 3), at depth 5; a sphere of radius 0.3 around (-3.125, -1.875, 0) those of pixel (1, 5). */
static void test_projection_known_answer(void)
{
    static const char text[] =
        "camera eye 0 0 5  target 0 0 0  up 0 1 0  window -1 1 -1 1  d 1\n"
        "resolution 8 8\n"
        "material glow  emission 1\n"
        "polygon 4  0 0 0  2.5 0 0  2.5 1.25 0  0 1.25 0\n"
        "material dot  emission 0.5\n"
        "sphere -3.125 -1.875 0  0.3\n";
    RfScene s;
    char err[256];
    RfImage ci, di, ct;
    RfRenderStats st;
    RfGlContext *ctx = NULL;
    RfRasterOptions ro = {0, 0, RF_SHADE_PHONG, 0};
    RfRenderOptions to = rf_render_options_default();
    to.local_only = 1;
    if (rf_scene_read_rf("known.rf", text, sizeof text - 1, &s, err, sizeof err) != RF_OK ||
        rf_gl_context_create(test_gl(), &ctx, err, sizeof err) != RF_OK) {
        fprintf(stderr, "%s\n", err);
        RF_CHECK(0);
        return;
    }
    RF_CHECK(rf_raster_render(&s, &ro, rf_gl_context_proc, ctx, &ci, &di, err, sizeof err) == RF_OK);
    rf_gl_context_destroy(ctx);
    RF_CHECK(rf_render(&s, &to, &ct, &st) == RF_OK);
    int bad_r = 0, bad_t = 0;
    for (int j = 0; j < 8; j++)
        for (int i = 0; i < 8; i++) {
            float want = (j == 3 && (i == 4 || i == 5)) ? 1.0f : (j == 5 && i == 1) ? 0.5f : 0.0f;
            bad_r += ci.data[(j * 8 + i) * 3] != want;
            bad_t += ct.data[(j * 8 + i) * 3] != want;
            float z = di.data[j * 8 + i];
            if (want == 1.0f)
                RF_CHECK_NEAR(z, 5.0, 1e-6, 0);
            else if (want == 0.0f)
                RF_CHECK(isinf(z));
            else /* the pixel ray passes the sphere's centre at distance L: hit at L - 0.3 */
                RF_CHECK_NEAR(z, (sqrt(38.28125) - 0.3) * 5.0 / sqrt(38.28125), 1e-6, 0);
        }
    RF_CHECK_EQ_INT(bad_r, 0);
    RF_CHECK_EQ_INT(bad_t, 0);
    rf_image_free(&ci), rf_image_free(&di), rf_image_free(&ct);
    rf_scene_free(&s);
}

static void test_triangulate_nonconvex(void)
{
    /* an L: (0,0) (2,0) (2,1) (1,1) (1,2) (0,2), area 3; ear clipping gives 4 triangles with the
     * polygon's orientation and the same total area */
    static const char text[] = "camera eye 0 0 5  target 0 0 0  up 0 1 0  fov 40\n"
                               "polygon 6  0 0 0  2 0 0  2 1 0  1 1 0  1 2 0  0 2 0\n";
    RfScene s;
    char err[256];
    int tris[12];
    RF_CHECK(rf_scene_read_rf("l.rf", text, sizeof text - 1, &s, err, sizeof err) == RF_OK);
    RF_CHECK(s.prims[0].flags & RF_PRIM_NONCONVEX);
    RF_CHECK_EQ_INT(rf_raster_triangulate(&s, &s.prims[0], tris), 4);
    double area = 0.0;
    for (int k = 0; k < 4; k++) {
        RfVec3 a = s.vertices[tris[3 * k]], b = s.vertices[tris[3 * k + 1]], c = s.vertices[tris[3 * k + 2]];
        double z = rf_vec3_cross(rf_vec3_sub(b, a), rf_vec3_sub(c, a)).z * 0.5;
        RF_CHECK(z >= 0.0); /* counter-clockwise, as the polygon */
        area += z;
    }
    RF_CHECK_NEAR(area, 3.0, 1e-15, 0);
    rf_scene_free(&s);
}

/* the teaching modes: flat lights a polygon once (one colour), Gouraud at its vertices
 * (colours vary, but differ from per-pixel Phong); under a directional light without a highlight
 * all three agree, since the lighting is then constant across a flat face */
static void test_raster_modes(void)
{
    static const char point[] =
        "camera eye 0 0 4  target 0 0 0  up 0 1 0  fov 50\nresolution 32 32\n"
        "light point 0.5 0.3 1  intensity 1\nmaterial m  kd 0.8  ks 0.5  shininess 10\n"
        "triangle -2 -2 0  2 -2 0  0 2 0\n";
    static const char dir[] =
        "camera eye 0 0 4  target 0 0 0  up 0 1 0  fov 50\nresolution 32 32\n"
        "light directional 0.2 -0.1 -1  intensity 1\nmaterial m  kd 0.8\n"
        "triangle -2 -2 0  2 -2 0  0 2 0\n";
    const char *texts[2] = {point, dir};
    RfGlContext *ctx = NULL;
    char err[256];
    if (rf_gl_context_create(test_gl(), &ctx, err, sizeof err) != RF_OK) {
        fprintf(stderr, "%s\n", err);
        RF_CHECK(0);
        return;
    }
    for (int k = 0; k < 2; k++) {
        RfScene s;
        RfImage img[3], depth;
        RF_CHECK(rf_scene_read_rf("modes.rf", texts[k], strlen(texts[k]), &s, err, sizeof err) == RF_OK);
        for (int m = 0; m < 3; m++) {
            RfRasterOptions ro = {0, 0, (RfShadeMode)m, 0};
            RF_CHECK(rf_raster_render(&s, &ro, rf_gl_context_proc, ctx, &img[m], &depth, err, sizeof err) == RF_OK);
            if (m == RF_SHADE_FLAT) { /* every covered pixel has one colour */
                float first = -1.0f;
                int varies = 0;
                for (int i = 0; i < 32 * 32; i++)
                    if (isfinite(depth.data[i])) {
                        if (first < 0.0f)
                            first = img[m].data[3 * i];
                        varies |= img[m].data[3 * i] != first;
                    }
                RF_CHECK(first > 0.0f && !varies);
            }
            rf_image_free(&depth);
        }
        double d_pg = 0.0, d_pf = 0.0;
        for (int i = 0; i < 32 * 32 * 3; i++) {
            d_pg = fmax(d_pg, fabs(img[0].data[i] - img[1].data[i]));
            d_pf = fmax(d_pf, fabs(img[0].data[i] - img[2].data[i]));
        }
        if (k == 0)
            RF_CHECK(d_pg > 0.01 && d_pf > 0.01); /* a point light and a highlight: they differ */
        else
            RF_CHECK(d_pg < 1e-5 && d_pf < 1e-5);
        for (int m = 0; m < 3; m++)
            rf_image_free(&img[m]);
        rf_scene_free(&s);
    }
    rf_gl_context_destroy(ctx);
}

/* LeakSanitizer off (1) and on again (0) in the sanitizer build; nothing otherwise. */
#if defined(__SANITIZE_ADDRESS__)
#include <sanitizer/lsan_interface.h>
static void lsan_pause(int off)
{
    if (off)
        __lsan_disable();
    else
        __lsan_enable();
}
#else
static void lsan_pause(int off) { (void)off; }
#endif

/* The two headless GL back ends draw the same images bit for bit (both run Mesa's llvmpipe on
 * Debian 12): the whitted scene, the SPD tetra (many small triangles) and a non-convex polygon,
 * colour and depth. */
static void test_gl_backends_agree(void)
{
    static const char *const scenes[] = {"scenes/whitted.rf", "scenes/spd/tetra.nff", "scenes/spd/gears.nff.gz"};
    for (size_t k = 0; k < sizeof scenes / sizeof scenes[0]; k++) {
        RfScene s;
        char err[512];
        if (rf_scene_load(scenes[k], NULL, &s, err, sizeof err) != RF_OK) {
            rf_test_fail(__FILE__, __LINE__, "%s", err);
            continue;
        }
        RfImage img[2], depth[2];
        int ok = 1;
        for (int b = 0; b < 2; b++) {
            RfGlContext *ctx = NULL;
            RfRasterOptions ro = {96, 72, RF_SHADE_PHONG, 0};
            /* Mesa's EGL driver is unloaded by eglTerminate with blocks its JIT never frees: their
             * stacks name no module, so no suppression can match them; LeakSanitizer ignores
             * what is allocated while disabled (refray's own allocations here are the same as in
             * the OSMesa pass, which stays checked) */
            if (b)
                lsan_pause(1);
            if (rf_gl_context_create(b ? RF_GL_EGL : RF_GL_OSMESA, &ctx, err, sizeof err) != RF_OK) {
                rf_test_fail(__FILE__, __LINE__, "%s", err);
                if (b)
                    lsan_pause(0);
                ok = 0;
                break;
            }
            RF_CHECK_STR(rf_gl_context_backend(ctx), b ? "egl" : "osmesa");
            ok &= rf_raster_render(&s, &ro, rf_gl_context_proc, ctx, &img[b], &depth[b], err, sizeof err) == RF_OK;
            rf_gl_context_destroy(ctx);
            if (b)
                lsan_pause(0);
        }
        if (ok) {
            size_t n = (size_t)img[0].width * (size_t)img[0].height;
            RF_CHECK(img[0].width == img[1].width && img[0].height == img[1].height);
            if (memcmp(img[0].data, img[1].data, sizeof(float) * 3 * n) || memcmp(depth[0].data, depth[1].data, sizeof(float) * n))
                rf_test_fail(__FILE__, __LINE__, "%s: OSMesa and EGL images differ", scenes[k]);
            rf_test_checks++;
            for (int b = 0; b < 2; b++) {
                rf_image_free(&img[b]);
                rf_image_free(&depth[b]);
            }
        }
        rf_scene_free(&s);
    }
    char err[256];
    RfGlContext *ctx = NULL;
    RF_CHECK_EQ_INT(rf_gl_backend_parse("vulkan"), -1);
    RF_CHECK(rf_gl_context_create(RF_GL_AUTO, &ctx, err, sizeof err) == RF_OK && ctx);
    rf_gl_context_destroy(ctx);
}

const RfTest rf_tests_compare[] = {
    {"compare_gl_backends_agree", test_gl_backends_agree},
    {"compare_diff_metrics_by_hand", test_diff_metrics_by_hand},
    {"compare_diff_verdict_ladder", test_diff_verdict_ladder},
    {"compare_diff_silhouettes", test_diff_silhouettes},
    {"compare_diff_exit_codes", test_diff_exit_codes},
    {"compare_raster_matches_tracer", test_raster_matches_tracer},
    {"compare_raster_two_sided", test_raster_two_sided},
    {"compare_planted_errors", test_planted_errors},
    {"compare_projection_known_answer", test_projection_known_answer},
    {"compare_triangulate_nonconvex", test_triangulate_nonconvex},
    {"compare_raster_modes", test_raster_modes},
    RF_TEST_END,
};
