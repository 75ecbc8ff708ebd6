/* The specialised render kernels (issue 11): every compiled kernel that has the parts a scene
 * needs renders it bit for bit as the general kernel does, for every shipped scene and the SPD
 * scenes, at 1, 4 and 6 samples, with adaptive supersampling and in --local mode (the
 * specialised kernels trace camera rays in groups of four, the general one ray by ray); the choice leaves out what a scene does not
 * need, and refuses a kernel that lacks what it needs. */
#include <glob.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "refray/render.h"
#include "refray/scene_io.h"
#include "rf_test.h"
#include "rf_test_render.h"

/* samples < 0: §3.9 adaptive supersampling (its centres and its quadrants go in groups too) */
static int render(const RfScene *s, unsigned kernel, int samples, int local, RfImage *img, RfRenderStats *st)
{
    RfRenderOptions o = rf_render_options_default();
    if (samples < 0) {
        o.adaptive = 1;
        o.adaptive_threshold = 0.02;
        o.adaptive_depth = 2;
        samples = 1;
    }
    o.width = 41; /* odd: the last group of camera rays in a row is short */
    o.height = 30;
    o.threads = 2;
    o.samples = samples;
    o.local_only = local;
    o.kernel = kernel;
    return rf_render(s, &o, img, st) == RF_OK;
}

static void t_kernels_identical(void)
{
    glob_t g;
    int compared = 0, specialised = 0;
    rf_test_shipped_scenes(&g, 1);
    for (size_t i = 0; i < g.gl_pathc; i++) {
        RfScene s;
        if (!rf_test_load_scene(g.gl_pathv[i], &s))
            continue;
        /* samples, local; 6 samples: a group of four camera rays and one of two; -1: adaptive */
        const int modes[5][2] = {{1, 0}, {4, 0}, {6, 0}, {1, 1}, {-1, 0}};
        for (int m = 0; m < 5; m++) {
            RfImage ref;
            RfRenderStats st;
            if (!render(&s, rf_kernel_all_parts(), modes[m][0], modes[m][1], &ref, &st)) {
                rf_test_fail(__FILE__, __LINE__, "%s: general kernel", g.gl_pathv[i]);
                continue;
            }
            RF_CHECK_EQ_INT(st.kernel, rf_kernel_all_parts());
            /* every other compiled kernel; those that lack a needed part must refuse */
            RfRenderOptions o = rf_render_options_default();
            o.samples = modes[m][0] < 0 ? 1 : modes[m][0];
            o.adaptive = modes[m][0] < 0 ? 1 : o.adaptive;
            o.local_only = modes[m][1];
            unsigned chosen = rf_render_kernel(&s, &o);
            for (int k = 0; k < rf_kernel_count_compiled(); k++) {
                unsigned parts = rf_kernel_compiled(k);
                RfImage img;
                int ok = render(&s, parts, modes[m][0], modes[m][1], &img, &st);
                /* every kernel with the chosen one's parts renders; one that refuses lacks some */
                RF_CHECK(ok || (parts & chosen) != chosen);
                if (!ok)
                    continue;
                RF_CHECK(memcmp(ref.data, img.data, sizeof(float) * 3 * 41 * 30) == 0);
                compared++;
                rf_image_free(&img);
            }
            specialised += chosen != rf_kernel_all_parts();
            rf_image_free(&ref);
        }
        rf_scene_free(&s);
    }
    globfree(&g);
    RF_CHECK(compared >= 100); /* 20 scenes, five modes, and the specialised ones again */
    RF_CHECK(specialised >= 15); /* tree, tetra, torus.obj: no highlights, five modes each */
}

/* What the choice leaves out, and what it must not. */
static void t_kernels_choice(void)
{
    RfScene s;
    char err[512], name[256];
    RfRenderOptions o = rf_render_options_default();
    RF_CHECK_EQ_INT(rf_scene_load("scenes/spd/tree.nff", NULL, &s, err, sizeof err), RF_OK);
    /* the tree has no highlights (ks = 0 everywhere) and no §3.10 parts: the kernel without
     * them, at any sample count */
    RF_CHECK_STR(rf_kernel_name(rf_render_kernel(&s, &o), name, sizeof name), "general-specular-area-lens-motion-glossy");
    o.samples = 4;
    RF_CHECK_STR(rf_kernel_name(rf_render_kernel(&s, &o), name, sizeof name), "general-specular-area-lens-motion-glossy");
    /* an exponent beyond 1e15 counts as a highlight even with ks = 0: (r.v)^n may overflow */
    RF_CHECK(!rf_material_has_highlight(&s.materials[0]));
    s.materials[0].shininess = 1e16;
    RF_CHECK(rf_material_has_highlight(&s.materials[0]));
    RF_CHECK_STR(rf_kernel_name(rf_render_kernel(&s, &o), name, sizeof name), "general-area-lens-motion-glossy");
    /* a lens from the options needs the lens part */
    o.aperture = 0.05;
    o.focus = 3.0;
    RF_CHECK_STR(rf_kernel_name(rf_render_kernel(&s, &o), name, sizeof name), "general");
    o.aperture = NAN;
    o.focus = NAN;
    rf_scene_free(&s);
    RF_CHECK_EQ_INT(rf_scene_load("scenes/soft.rf", NULL, &s, err, sizeof err), RF_OK);
    RF_CHECK_STR(rf_kernel_name(rf_render_kernel(&s, &o), name, sizeof name), "general-specular");
    rf_scene_free(&s);
    RF_CHECK_EQ_INT(rf_scene_load("scenes/whitted.rf", NULL, &s, err, sizeof err), RF_OK);
    o.samples = 1;
    RF_CHECK_STR(rf_kernel_name(rf_render_kernel(&s, &o), name, sizeof name), "general-area-lens-motion-glossy");
    /* a kernel without highlights cannot render the red sphere's */
    RfImage img;
    RfRenderStats st;
    o.width = 16;
    o.height = 12;
    o.kernel = rf_kernel_parse("general-specular-area-lens-motion-glossy");
    RF_CHECK(o.kernel != 0);
    RF_CHECK_EQ_INT(rf_render(&s, &o, &img, &st), RF_ERR_DOMAIN);
    rf_scene_free(&s);
    /* names: the general kernel, round trips, unknown parts and sets nobody compiled */
    RF_CHECK_EQ_INT(rf_kernel_parse("general"), rf_kernel_all_parts());
    RF_CHECK_EQ_INT(rf_kernel_parse("general-bogus"), 0);
    RF_CHECK_EQ_INT(rf_kernel_parse("general-ambient"), 0);
    RF_CHECK_EQ_INT(rf_kernel_parse("general-specular-bogus"), 0);
    RF_CHECK_EQ_INT(rf_kernel_parse("shadow"), 0);
    for (int k = 0; k < rf_kernel_count_compiled(); k++)
        RF_CHECK_EQ_INT(rf_kernel_parse(rf_kernel_name(rf_kernel_compiled(k), name, sizeof name)),
                        rf_kernel_compiled(k));
}

/* Background tiles: where no camera ray of a tile can hit anything, the specialised kernels fill
 * it without tracing; tetra (mostly sky) and whitted (sky above the ground) at 1 and 4 samples,
 * the 4-sample run with its variance image, and at 4 samples through a Gaussian (radius 1.5)
 * and a Mitchell filter (radius 2), whose weights the skipped tiles still sum: the same image,
 * variance and ray counts as the general kernel, which skips no tile. A lens skips none, nor
 * does a scene with a plane. */
static void t_kernels_background_tiles(void)
{
    const char *scenes[2] = {"scenes/spd/tetra.nff", "scenes/whitted.rf"};
    static const struct {
        int spp, filter;
        double radius;
    } runs[] = {{1, RF_FILTER_BOX, 0.0}, {4, RF_FILTER_BOX, 0.0}, {4, RF_FILTER_GAUSSIAN, 1.5}, {4, RF_FILTER_MITCHELL, 2.0}};
    char err[512];
    for (int i = 0; i < 2; i++) {
        RfScene s;
        RF_CHECK_EQ_INT(rf_scene_load(scenes[i], NULL, &s, err, sizeof err), RF_OK);
        for (size_t r = 0; r < sizeof runs / sizeof runs[0]; r++) {
            int spp = runs[r].spp, box = runs[r].filter == RF_FILTER_BOX;
            RfImage img[2], var[2];
            RfRenderStats st[2];
            for (int general = 0; general < 2; general++) {
                RfRenderOptions o = rf_render_options_default();
                o.width = 160;
                o.height = 128;
                o.threads = 2;
                o.samples = spp;
                o.filter = runs[r].filter;
                o.filter_radius = runs[r].radius;
                o.variance = spp > 1 && box ? &var[general] : NULL;
                o.kernel = general ? rf_kernel_all_parts() : 0;
                RF_CHECK_EQ_INT(rf_render(&s, &o, &img[general], &st[general]), RF_OK);
            }
            RF_CHECK(st[0].background_tiles >= (box ? 10u : 5u)); /* of 80 */
            RF_CHECK_EQ_INT((int)st[1].background_tiles, 0);
            RF_CHECK(memcmp(img[0].data, img[1].data, sizeof(float) * 3 * 160 * 128) == 0);
            if (spp > 1 && box) {
                RF_CHECK(memcmp(var[0].data, var[1].data, sizeof(float) * 3 * 160 * 128) == 0);
                rf_image_free(&var[0]);
                rf_image_free(&var[1]);
            }
            RF_CHECK(st[0].primary_rays == st[1].primary_rays && st[0].shadow_rays == st[1].shadow_rays &&
                     st[0].secondary_rays == st[1].secondary_rays);
            rf_image_free(&img[0]);
            rf_image_free(&img[1]);
        }
        rf_scene_free(&s);
    }
    /* the tracer's answer: a narrow cone from far out, looking away from everything, is empty
     * for tetra; for a scene with a plane (an item without a box) never */
    RfVec3 away[4] = {{0, 1, 0.01}, {0, -1, 0.01}, {1, 0, 0.01}, {-1, 0, 0.01}}; /* around +z */
    const char *cone_scenes[2] = {"scenes/spd/tetra.nff", "scenes/ellipsoid.rf"};
    for (int i = 0; i < 2; i++) {
        RfScene s;
        RfTracer *t;
        RF_CHECK_EQ_INT(rf_scene_load(cone_scenes[i], NULL, &s, err, sizeof err), RF_OK);
        RF_CHECK_EQ_INT(rf_tracer_create(&s, &t), RF_OK);
        RF_CHECK_EQ_INT(rf_tracer_cone_empty(t, rf_vec3(0, 0, 1000), away, 4), i == 0);
        RF_CHECK_EQ_INT(rf_tracer_cone_empty(t, rf_vec3(0, 0, -1000), away, 4), 0); /* looking at it */
        rf_tracer_free(t);
        rf_scene_free(&s);
    }
    RfScene s;
    RF_CHECK_EQ_INT(rf_scene_load("scenes/spd/tetra.nff", NULL, &s, err, sizeof err), RF_OK);
    RfRenderOptions o = rf_render_options_default();
    o.width = 160;
    o.height = 128;
    o.aperture = 0.02; /* a lens: rays from all over it */
    o.focus = 3.0;
    RfImage img;
    RfRenderStats st;
    RF_CHECK_EQ_INT(rf_render(&s, &o, &img, &st), RF_OK);
    RF_CHECK_EQ_INT((int)st.background_tiles, 0);
    rf_image_free(&img);
    rf_scene_free(&s);
}

const RfTest rf_tests_kernels[] = {
    {"kernels_identical_to_general", t_kernels_identical},
    {"kernels_choice", t_kernels_choice},
    {"kernels_background_tiles", t_kernels_background_tiles},
    RF_TEST_END,
};
