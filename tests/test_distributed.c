/* §3.9 and §3.10 in the renderer: soft shadows against the closed-form irradiance of a
 * rectangle light, stratified against random sampling, motion blur against static renders at
 * the sampled times, the thin lens at aperture 0, area lights shrunk to point lights, glossy rays
 * against the mirror, adaptive supersampling against uniform, filters, determinism, and the
 * scene format's errors. Fixed seeds: every statistical check is deterministic. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "refray/camera.h"
#include "refray/render.h"
#include "refray/scene_io.h"
#include "refray/transform.h"
#include "rf_test.h"

static int load(const char *text, RfScene *s)
{
    char err[512];
    if (rf_scene_read_rf("t.rf", text, strlen(text), s, err, sizeof err) != RF_OK) {
        rf_test_fail(__FILE__, __LINE__, "%s", err);
        return 0;
    }
    return 1;
}

static int render(const RfScene *s, RfRenderOptions o, RfImage *img)
{
    RfRenderStats st;
    if (o.threads == 0)
        o.threads = 2;
    RfStatus r = rf_render(s, &o, img, &st);
    if (r != RF_OK)
        rf_test_fail(__FILE__, __LINE__, "render: %s", rf_status_str(r));
    return r == RF_OK;
}

static double mean_abs_diff(const RfImage *a, const RfImage *b)
{
    size_t n = (size_t)a->width * (size_t)a->height * 3;
    double sum = 0.0;
    for (size_t i = 0; i < n; i++)
        sum += fabs((double)a->data[i] - (double)b->data[i]);
    return sum / (double)n;
}

/* ---- soft shadows against the closed form ------------------------------------------------ */

/* A floor (kd 1, so a pixel is the irradiance E) under a 1 x 0.6 rectangle light of radiance 1
 * at height 1, seen from straight above. */
#define RECT_SCENE                                                                                   \
    "camera eye 0 3 0  target 0 0 0  up 0 0 -1  fov 70\n"                                            \
    "resolution 16 16\ndepth 1\n"                                                                    \
    "light rect -0.5 1 -0.3  1 0 0  0 0 0.6  radiance 1\n"                                           \
    "material floor kd 1\n"                                                                          \
    "polygon 4  -5 0 -5  -5 0 5  5 0 5  5 0 -5\n"

static RfVec3 v3(double x, double y, double z) { return rf_vec3(x, y, z); }

/* Irradiance at x (normal +y) from a Lambertian polygon of radiance 1 (Lambert's formula):
 * E = 1/2 |sum_i angle(r_i, r_i+1) n . unit(r_i x r_i+1)|, r_i the unit vectors to the corners. */
static double polygon_irradiance(RfVec3 x, const RfVec3 *corner, int n)
{
    double sum = 0.0;
    for (int i = 0; i < n; i++) {
        RfVec3 a = rf_vec3_normalize(rf_vec3_sub(corner[i], x));
        RfVec3 b = rf_vec3_normalize(rf_vec3_sub(corner[(i + 1) % n], x));
        RfVec3 c = rf_vec3_cross(a, b);
        double angle = atan2(rf_vec3_length(c), rf_vec3_dot(a, b));
        sum += angle * rf_vec3_normalize(c).y;
    }
    return 0.5 * fabs(sum);
}

/* The exact irradiance at each pixel centre's floor point, as the renderer's camera sees it. */
static void exact_rect(const RfScene *s, double *e)
{
    RfCamera cam;
    RfWindow w = rf_scene_camera_window(&s->camera, 16, 16);
    rf_camera_init(&cam, s->camera.eye, s->camera.target, s->camera.up, w.d, w.l, w.r, w.b, w.t, 16, 16);
    RfVec3 corner[4] = {v3(-0.5, 1, -0.3), v3(0.5, 1, -0.3), v3(0.5, 1, 0.3), v3(-0.5, 1, 0.3)};
    for (int y = 0; y < 16; y++)
        for (int x = 0; x < 16; x++) {
            RfRay r = rf_camera_ray(&cam, x + 0.5, y + 0.5, 0, 0);
            RfVec3 p = rf_ray_at(r, -r.origin.y / r.dir.y);
            e[y * 16 + x] = polygon_irradiance(p, corner, 4);
        }
}

static void t_rect_light_closed_form(void)
{
    RfScene s;
    if (!load(RECT_SCENE, &s))
        return;
    double exact[256], sum[256] = {0}, sum2[256] = {0};
    exact_rect(&s, exact);
    enum { R = 32 };
    for (int run = 0; run < R; run++) {
        RfRenderOptions o = rf_render_options_default();
        RfImage img;
        o.sampler = RF_SAMPLER_RANDOM;
        o.light_samples = 64;
        o.seed = 1000 + (uint64_t)run;
        if (!render(&s, o, &img))
            break;
        for (int i = 0; i < 256; i++) {
            sum[i] += img.data[3 * i];
            sum2[i] += (double)img.data[3 * i] * img.data[3 * i];
        }
        rf_image_free(&img);
    }
    /* each pixel's mean over 32 independent estimates within 6 standard errors (t with 31
     * degrees of freedom: p < 1e-6 per pixel), and the whole image's mean within 0.5 % */
    int outside = 0;
    double tot = 0.0, tot_exact = 0.0;
    for (int i = 0; i < 256; i++) {
        double m = sum[i] / R, var = (sum2[i] - R * m * m) / (R - 1), se = sqrt(var > 0 ? var / R : 0);
        outside += fabs(m - exact[i]) > 6.0 * se + 1e-6 * exact[i];
        tot += m;
        tot_exact += exact[i];
    }
    RF_CHECK_EQ_INT(outside, 0);
    RF_CHECK_NEAR(tot, tot_exact, 5e-3, 0);
    /* Lambert's polygon formula against the rectangle's own closed form under its centre
     * (4 corner rectangles: E = 2 [X/sqrt(1+X^2) atan(Y/sqrt(1+X^2)) + Y/sqrt(1+Y^2) atan(X/sqrt(1+Y^2))],
     * X = 0.5, Y = 0.3 at height 1) */
    RfVec3 corner[4] = {v3(-0.5, 1, -0.3), v3(0.5, 1, -0.3), v3(0.5, 1, 0.3), v3(-0.5, 1, 0.3)};
    double X = 0.5, Y = 0.3, ax = sqrt(1 + X * X), ay = sqrt(1 + Y * Y);
    RF_CHECK_NEAR(polygon_irradiance(v3(0, 0, 0), corner, 4), 2 * (X / ax * atan(Y / ax) + Y / ay * atan(X / ay)), 1e-13, 0);
    RF_CHECK(exact[8 * 16 + 8] > 0.45 && exact[0] < 0.01); /* under the light, and far off to the side */
    rf_scene_free(&s);
}

/* Stratified and Sobol light samples have a lower error than random ones at the same count. */
static void t_stratified_beats_random(void)
{
    RfScene s;
    if (!load(RECT_SCENE, &s))
        return;
    double exact[256], rmse[RF_SAMPLER_COUNT] = {0};
    exact_rect(&s, exact);
    for (int k = RF_SAMPLER_RANDOM; k <= RF_SAMPLER_SOBOL; k++) {
        RfRenderOptions o = rf_render_options_default();
        RfImage img;
        o.sampler = k;
        o.light_samples = 16;
        if (!render(&s, o, &img))
            continue;
        for (int i = 0; i < 256; i++)
            rmse[k] += (img.data[3 * i] - exact[i]) * (img.data[3 * i] - exact[i]) / 256.0;
        rmse[k] = sqrt(rmse[k]);
        rf_image_free(&img);
    }
    RF_CHECK(rmse[RF_SAMPLER_STRATIFIED] < 0.5 * rmse[RF_SAMPLER_RANDOM]);
    RF_CHECK(rmse[RF_SAMPLER_SOBOL] < 0.5 * rmse[RF_SAMPLER_RANDOM]);
    RF_CHECK(rmse[RF_SAMPLER_RANDOM] > 0.0);
    rf_scene_free(&s);
}

/* ---- area lights shrunk to points ------------------------------------------------------- */

/* A sphere light of radius r and radiance I / (pi r^2) acts as a point light of intensity I
 * (scene.h); as r shrinks, the soft image tends to the hard one. */
static void t_sphere_light_to_point(void)
{
    static const char *base = "camera eye 0 2 4  target 0 0.3 0  up 0 1 0  fov 45\nresolution 32 24\n"
                              "material m kd 0.5\nsphere 0 0.5 0 0.5\npolygon 4 -3 0 -3 -3 0 3 3 0 3 3 0 -3\n";
    char text[1024];
    RfScene s;
    RfImage point, soft;
    RfRenderOptions o = rf_render_options_default();
    o.light_samples = 16;
    snprintf(text, sizeof text, "%slight point 1 3 1 intensity 10\n", base);
    if (!load(text, &s) || !render(&s, o, &point))
        return;
    rf_scene_free(&s);
    double prev = INFINITY, radii[3] = {0.2, 0.05, 0.0125};
    for (int k = 0; k < 3; k++) {
        snprintf(text, sizeof text, "%slight sphere 1 3 1 %.17g radiance %.17g\n", base, radii[k],
                 10.0 / (RF_PI * radii[k] * radii[k]));
        if (!load(text, &s) || !render(&s, o, &soft))
            return;
        double d = mean_abs_diff(&point, &soft);
        RF_CHECK(d < prev);
        prev = d;
        rf_image_free(&soft);
        rf_scene_free(&s);
    }
    RF_CHECK(prev < 2e-3); /* the image's values are ~0.2 */
    rf_image_free(&point);
}

/* ---- the thin lens ---------------------------------------------------------------------- */

static void t_aperture_zero_is_pinhole(void)
{
    RfScene lens, pinhole;
    RfImage a, b;
    RfRenderOptions o = rf_render_options_default();
    o.samples = 4;
    o.width = 48;
    o.height = 48;
    char err[512];
    if (rf_scene_load("scenes/soft.rf", NULL, &lens, err, sizeof err) != RF_OK) {
        rf_test_fail(__FILE__, __LINE__, "%s", err);
        return;
    }
    rf_scene_load("scenes/soft.rf", NULL, &pinhole, err, sizeof err);
    pinhole.camera.aperture = 0.0; /* the same scene without its lens */
    o.aperture = 0.0;              /* the lens closed from the options */
    if (render(&lens, o, &a) && render(&pinhole, rf_render_options_default(), &b)) {
        RfImage c;
        RfRenderOptions p = rf_render_options_default();
        p.samples = 4;
        p.width = 48;
        p.height = 48;
        render(&pinhole, p, &c);
        RF_CHECK(memcmp(a.data, c.data, sizeof(float) * 3 * 48 * 48) == 0);
        /* and the open lens blurs: the image differs */
        RfImage d;
        o.aperture = NAN;
        render(&lens, o, &d);
        RF_CHECK(mean_abs_diff(&a, &d) > 1e-3);
        rf_image_free(&c);
        rf_image_free(&d);
        rf_image_free(&b);
        rf_image_free(&a);
    }
    rf_scene_free(&lens);
    rf_scene_free(&pinhole);
}

/* ---- motion blur ------------------------------------------------------------------------ */

#define MOTION_SCENE(shutter)                                                                       \
    "camera eye 0 1.5 5  target 0 0.5 0  up 0 1 0  fov 40\nresolution 40 24\nsamples 64\n"         \
    "shutter " shutter "\nlight point 2 4 3 intensity 20\nmaterial m kd 0.6 ks 0.3 shininess 20\n"   \
    "polygon 4 -4 0 -4 -4 0 4 4 0 4 4 0 -4\nobject ball\nsphere 0 0 0 0.5\nend\n"                  \
    "object bar\npolygon 4 -0.8 -0.1 0  0.8 -0.1 0  0.8 0.1 0  -0.8 0.1 0\nend\n"                  \
    "instance ball translate -1 0.5 0 at 1 translate 1 0.5 0\n"                                     \
    "instance bar rotate z 0 translate 0 1.5 0 at 1 rotate z 90 translate 0 1.5 0\n"

/* The tracer at a time sees a moving instance exactly where a static one placed by the
 * interpolated transform is: same primitive, same t, same normal, bit for bit. */
static void t_motion_equals_static_at_time(void)
{
    RfScene mo, st;
    if (!load(MOTION_SCENE("0 1"), &mo) || !load(MOTION_SCENE("0 1"), &st))
        return;
    RfTracer *tm = NULL;
    rf_tracer_create(&mo, &tm);
    RfMotionState *ms = rf_motion_state_new(tm);
    int compared = 0, hits = 0;
    for (int j = 0; j < 8; j++) {
        double time = (j + 0.5) / 8.0;
        /* the static copy: each moving instance fixed at its transform at `time` */
        for (size_t i = 0; i < st.instance_count; i++) {
            RfInstance *in = &st.instances[i];
            if (in->motion < 0)
                continue;
            RfMat4 w;
            rf_motion_at(&st.motions[in->motion], time, &w, &in->to_object, &in->normal_to_world);
            in->to_world = w;
            in->motion = -1;
        }
        RfTracer *ts = NULL;
        rf_tracer_create(&st, &ts);
        rf_motion_state_set(ms, time);
        for (int k = 0; k < 400; k++) {
            double u = (k % 20) / 19.0, v = (k / 20) / 19.0;
            RfRay r = rf_ray(v3(0, 1.5, 5), rf_vec3_normalize(v3(-1.6 + 3.2 * u, 0.6 - 1.4 * v, -5)));
            RfSurfaceHit a, b;
            int ha = rf_tracer_intersect_at(tm, &r, ms, 0.0, HUGE_VAL, &a), hb = rf_tracer_intersect(ts, &r, 0.0, HUGE_VAL, &b);
            RF_CHECK_EQ_INT(ha, hb);
            if (ha >= 0 && hb >= 0) {
                RF_CHECK(memcmp(&a.t, &b.t, sizeof a.t) == 0);
                RF_CHECK(memcmp(&a.normal, &b.normal, sizeof a.normal) == 0);
                hits += a.prim != 0;
            }
            compared++;
        }
        rf_tracer_free(ts);
        rf_scene_free(&st);
        load(MOTION_SCENE("0 1"), &st);
    }
    RF_CHECK_EQ_INT(compared, 3200);
    RF_CHECK(hits > 100); /* rays that meet the moving ball or bar */
    rf_motion_state_free(ms);
    rf_tracer_free(tm);
    rf_scene_free(&mo);
    rf_scene_free(&st);
}

/* Keyframes in their order, by a render that does not call rf_motion_at on both sides: with
 * the shutter open and closed at t = 0.25, the moving scene is the static one written by hand
 * with the transforms a quarter of the way: the ball at x = -1 + 0.25 * 2 = -0.5, the bar turned
 * 0.25 * 90 = 22.5 deg. (Keyframes interpolated backwards would put them at x = 0.5 and
 * 67.5 deg.) */
static void t_motion_quarter_shutter_is_static(void)
{
    RfScene mo, st;
    static const char *still =
        "camera eye 0 1.5 5  target 0 0.5 0  up 0 1 0  fov 40\nresolution 40 24\n"
        "light point 2 4 3 intensity 20\nmaterial m kd 0.6 ks 0.3 shininess 20\n"
        "polygon 4 -4 0 -4 -4 0 4 4 0 4 4 0 -4\nobject ball\nsphere 0 0 0 0.5\nend\n"
        "object bar\npolygon 4 -0.8 -0.1 0  0.8 -0.1 0  0.8 0.1 0  -0.8 0.1 0\nend\n"
        "instance ball translate -0.5 0.5 0\ninstance bar rotate z 22.5 translate 0 1.5 0\n";
    if (!load(MOTION_SCENE("0.25 0.25"), &mo) || !load(still, &st))
        return;
    RfImage a, b;
    RfRenderOptions o = rf_render_options_default();
    o.samples = 1;
    if (render(&mo, o, &a) && render(&st, o, &b)) {
        RF_CHECK(a.width == b.width && a.height == b.height);
        double d = mean_abs_diff(&a, &b);
        if (!(d < 1e-9))
            rf_test_fail(__FILE__, __LINE__, "mean |moving at 0.25 - static| = %g", d);
        rf_test_checks++;
        rf_image_free(&a);
        rf_image_free(&b);
    }
    rf_scene_free(&mo);
    rf_scene_free(&st);
}

/* The blurred image is the mean over the shutter: against the mean of 16 static renders at the
 * times (j + 1/2)/16 (shutter closed at that time), within the noise of 64 samples. */
static void t_motion_blur_is_time_average(void)
{
    RfScene blur;
    RfImage b, frame, first;
    if (!load(MOTION_SCENE("0 1"), &blur) || !render(&blur, rf_render_options_default(), &b))
        return;
    size_t n = 40 * 24 * 3;
    double *avg = calloc(n, sizeof *avg);
    for (int j = 0; j < 16; j++) {
        char shutter[64], text[2048];
        snprintf(shutter, sizeof shutter, "%.17g %.17g", (j + 0.5) / 16, (j + 0.5) / 16);
        snprintf(text, sizeof text,
                 "camera eye 0 1.5 5  target 0 0.5 0  up 0 1 0  fov 40\nresolution 40 24\nsamples 64\n"
                 "shutter %s\nlight point 2 4 3 intensity 20\nmaterial m kd 0.6 ks 0.3 shininess 20\n"
                 "polygon 4 -4 0 -4 -4 0 4 4 0 4 4 0 -4\nobject ball\nsphere 0 0 0 0.5\nend\n"
                 "object bar\npolygon 4 -0.8 -0.1 0  0.8 -0.1 0  0.8 0.1 0  -0.8 0.1 0\nend\n"
                 "instance ball translate -1 0.5 0 at 1 translate 1 0.5 0\n"
                 "instance bar rotate z 0 translate 0 1.5 0 at 1 rotate z 90 translate 0 1.5 0\n",
                 shutter);
        RfScene s;
        if (!load(text, &s) || !render(&s, rf_render_options_default(), &frame))
            break;
        for (size_t i = 0; i < n; i++)
            avg[i] += frame.data[i] / 16.0;
        if (j == 0)
            first = frame;
        else
            rf_image_free(&frame);
        rf_scene_free(&s);
    }
    double d = 0.0, d_first = 0.0;
    for (size_t i = 0; i < n; i++) {
        d += fabs(b.data[i] - avg[i]) / (double)n;
        d_first += fabs(first.data[i] - avg[i]) / (double)n;
    }
    RF_CHECK(d < 4e-3);         /* the noise of 64 samples against 16 frames */
    RF_CHECK(d_first > 5.0 * d); /* while one frame alone is far from the average */
    free(avg);
    rf_image_free(&first);
    rf_image_free(&b);
    rf_scene_free(&blur);
}

/* ---- glossy rays, adaptive supersampling, filters --------------------------------------- */

static void t_glossy_tends_to_mirror(void)
{
    static const char *fmt = "camera eye 0 1 4  target 0 0.5 0  up 0 1 0  fov 45\nresolution 32 24\nsamples 4\n"
                             "light point 1 3 2 intensity 10\nmaterial red kd 0.8 0.1 0.1\n"
                             "material mirror kr 0.9 %s\nuse red\nsphere 0.8 0.5 -0.5 0.5\n"
                             "use mirror\npolygon 4 -3 0 -3 -3 0 3 3 0 3 3 0 -3\n";
    char text[1024];
    RfScene s;
    RfImage mirror, glossy;
    snprintf(text, sizeof text, fmt, "");
    if (!load(text, &s) || !render(&s, rf_render_options_default(), &mirror))
        return;
    rf_scene_free(&s);
    double prev = INFINITY;
    const char *gloss[3] = {"glossy 50", "glossy 5000", "glossy 500000"};
    for (int k = 0; k < 3; k++) {
        snprintf(text, sizeof text, fmt, gloss[k]);
        if (!load(text, &s) || !render(&s, rf_render_options_default(), &glossy))
            return;
        double d = mean_abs_diff(&mirror, &glossy);
        RF_CHECK(d < prev);
        prev = d;
        rf_image_free(&glossy);
        rf_scene_free(&s);
    }
    RF_CHECK(prev < 1e-3);
    rf_image_free(&mirror);
}

/* Depth 0 is the centre sample (the 1-spp image, bit for bit); threshold 0 and depth 1 split
 * every pixel that differs from a neighbour into the 2 x 2 quadrant centres, which are the
 * uniform sampler's 4 positions: those pixels equal the uniform 4-spp image bit for bit. */
static void t_adaptive_supersampling(void)
{
    RfScene s;
    char err[512];
    if (rf_scene_load("scenes/whitted.rf", NULL, &s, err, sizeof err) != RF_OK)
        return;
    RfRenderOptions o = rf_render_options_default();
    RfImage one, uni, ad0, ad1;
    RfRenderStats st;
    o.width = 64;
    o.height = 48;
    o.threads = 2;
    render(&s, o, &one);
    o.samples = 4;
    o.sampler = RF_SAMPLER_UNIFORM;
    render(&s, o, &uni);
    o.samples = 0;
    o.adaptive = 1;
    o.adaptive_depth = 0;
    render(&s, o, &ad0);
    RF_CHECK(memcmp(one.data, ad0.data, sizeof(float) * 3 * 64 * 48) == 0);
    o.adaptive_depth = 1;
    o.adaptive_threshold = 0.0;
    RF_CHECK_EQ_INT(rf_render(&s, &o, &ad1, &st), RF_OK);
    int either = 0, as_uniform = 0, not_centre = 0;
    for (int i = 0; i < 64 * 48; i++) {
        int u = memcmp(&ad1.data[3 * i], &uni.data[3 * i], 3 * sizeof(float)) == 0;
        int c = memcmp(&ad1.data[3 * i], &one.data[3 * i], 3 * sizeof(float)) == 0;
        either += u || c;
        as_uniform += u;
        not_centre += !c;
    }
    /* every pixel is its centre (not split) or the uniform 2 x 2 value (split) */
    RF_CHECK_EQ_INT(either, 64 * 48);
    RF_CHECK(as_uniform >= (int)st.adaptive_pixels && not_centre <= (int)st.adaptive_pixels);
    RF_CHECK(st.adaptive_pixels > 1000 && st.adaptive_pixels < 64 * 48); /* the flat black sky is not split */
    RF_CHECK_EQ_INT(st.primary_rays, 64 * 48 + 4 * st.adaptive_pixels);
    rf_image_free(&one);
    rf_image_free(&uni);
    rf_image_free(&ad0);
    rf_image_free(&ad1);
    rf_scene_free(&s);
}

/* A filter's weights are normalised: a flat region keeps its value. */
static void t_filters_keep_flat_regions(void)
{
    RfScene s;
    if (!load("camera eye 0 0 1 target 0 0 0 up 0 1 0 fov 40\nresolution 8 8\nbackground 0.25 0.5 0.75\n", &s))
        return;
    for (int f = RF_FILTER_BOX; f < RF_FILTER_COUNT; f++) {
        RfRenderOptions o = rf_render_options_default();
        RfImage img;
        o.samples = 9;
        o.filter = f;
        if (!render(&s, o, &img))
            continue;
        for (int i = 0; i < 64; i++) {
            RF_CHECK_NEAR(img.data[3 * i], 0.25, 1e-7, 0);
            RF_CHECK_NEAR(img.data[3 * i + 2], 0.75, 1e-7, 0);
        }
        rf_image_free(&img);
    }
    rf_scene_free(&s);
}

/* ---- determinism and the scene format --------------------------------------------------- */

static void t_distributed_thread_determinism(void)
{
    static const char *scenes[] = {"scenes/soft.rf", "scenes/motion.rf"};
    for (int k = 0; k < 2; k++) {
        RfScene s;
        char err[512];
        if (rf_scene_load(scenes[k], NULL, &s, err, sizeof err) != RF_OK) {
            rf_test_fail(__FILE__, __LINE__, "%s", err);
            continue;
        }
        RfImage a, b;
        RfRenderOptions o = rf_render_options_default();
        o.width = 40;
        o.height = 30;
        o.samples = 4;
        o.threads = 1;
        render(&s, o, &a);
        o.threads = 3;
        render(&s, o, &b);
        RF_CHECK(memcmp(a.data, b.data, sizeof(float) * 3 * 40 * 30) == 0);
        rf_image_free(&a);
        rf_image_free(&b);
        rf_scene_free(&s);
    }
}

static void t_distributed_scene_errors(void)
{
    static const struct { const char *text, *msg; } cases[] = {
        {"instance o translate 0 0 0 at 1 rotate y 10\n", "t.rf:2:28: keyframe at 1 lists other transform steps"},
        {"instance o translate 0 0 0 at 1 translate 1 0 0 at 0.5 translate 2 0 0\n",
         "t.rf:2:49: keyframe times must increase"},
        {"instance o translate 0 0 0 at 0 translate 1 0 0\n", "t.rf:2:28: keyframe times must increase"},
        {"light rect 0 0 0  1 0 0  2 0 0\n", "t.rf:2:30: rect light: its edges are parallel"},
        {"light disc 0 0 0  0 1 0  0\n", "disc radius must be > 0"},
        {"light sphere 0 0 0  1 samples 0\n", "light samples"},
        {"light sphere 0 0 0  1 two-sided\n", "unknown attribute 'two-sided'"},
        {"sampler halton\n", "t.rf:2:9: unknown sampler 'halton'"},
        {"filter gaussian radius 0\n", "filter radius must be in (0, 16]"},
        {"shutter 1 0\n", "shutter needs open <= close"},
        {"material m glossy -1\n", "glossy exponent"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        char text[1024], err[512];
        RfScene s;
        snprintf(text, sizeof text, "camera eye 0 0 1 target 0 0 0 up 0 1 0 fov 40\n%s%s", cases[i].text,
                 strncmp(cases[i].text, "instance", 8) == 0 ? "object o\nsphere 0 0 0 1\nend\n" : "");
        RfStatus st = rf_scene_read_rf("t.rf", text, strlen(text), &s, err, sizeof err);
        RF_CHECK(st != RF_OK);
        if (st == RF_OK)
            rf_scene_free(&s);
        else if (!strstr(err, cases[i].msg))
            rf_test_fail(__FILE__, __LINE__, "case %zu: '%s' does not contain '%s'", i, err, cases[i].msg);
    }
    /* the camera: a lens needs a focus distance */
    char err[512];
    RfScene s;
    const char *t = "camera eye 0 0 1 target 0 0 0 up 0 1 0 fov 40 aperture 0.1\n";
    RF_CHECK(rf_scene_read_rf("t.rf", t, strlen(t), &s, err, sizeof err) != RF_OK);
    RF_CHECK(strstr(err, "t.rf:1:1: camera with an aperture needs 'focus'") != NULL);
}


/* Keyframes interpolate each number linearly between their times: a translation from x = 0 at
 * time 0 to x = 4 at time 2 is at x = 1 at time 0.5 (and holds before and after); a rotation
 * from 0 to 90 degrees is at 45 degrees halfway (it turns: |(1,0,0)| stays 1). */
static void t_motion_interpolation(void)
{
    RfScene s;
    if (!load("camera eye 0 0 5 target 0 0 0 up 0 1 0 fov 40\nobject o\nsphere 0 0 0 1\nend\n"
              "instance o translate 0 0 0 at 2 translate 4 0 0\n"
              "instance o rotate z 0 at 1 rotate z 90\n", &s))
        return;
    RfMat4 w, o;
    RfMat3 n;
    RfVec3 p;
    static const double times[] = {-1.0, 0.0, 0.5, 1.0, 2.0, 3.0}, xs[] = {0.0, 0.0, 1.0, 2.0, 4.0, 4.0};
    for (int k = 0; k < 6; k++) {
        RF_CHECK_EQ_INT(rf_motion_at(&s.motions[0], times[k], &w, &o, &n), RF_OK);
        rf_transform_point(w, rf_vec3(0, 0, 0), &p);
        RF_CHECK_NEAR(p.x, xs[k], 0, 1e-15);
    }
    RF_CHECK_EQ_INT(rf_motion_at(&s.motions[1], 0.5, &w, &o, &n), RF_OK);
    rf_transform_point(w, rf_vec3(1, 0, 0), &p);
    RF_CHECK_NEAR(p.x, sqrt(0.5), 1e-15, 0);
    RF_CHECK_NEAR(p.y, sqrt(0.5), 1e-15, 0);
    rf_scene_free(&s);
}

const RfTest rf_tests_distributed[] = {
    {"distributed_rect_light_closed_form", t_rect_light_closed_form},
    {"distributed_stratified_beats_random", t_stratified_beats_random},
    {"distributed_sphere_light_to_point", t_sphere_light_to_point},
    {"distributed_aperture_zero_is_pinhole", t_aperture_zero_is_pinhole},
    {"distributed_motion_interpolation", t_motion_interpolation},
    {"distributed_motion_equals_static_at_time", t_motion_equals_static_at_time},
    {"distributed_motion_quarter_shutter_is_static", t_motion_quarter_shutter_is_static},
    {"distributed_motion_blur_is_time_average", t_motion_blur_is_time_average},
    {"distributed_glossy_tends_to_mirror", t_glossy_tends_to_mirror},
    {"distributed_adaptive_supersampling", t_adaptive_supersampling},
    {"distributed_filters_keep_flat_regions", t_filters_keep_flat_regions},
    {"distributed_thread_determinism", t_distributed_thread_determinism},
    {"distributed_scene_errors", t_distributed_scene_errors},
    RF_TEST_END,
};
