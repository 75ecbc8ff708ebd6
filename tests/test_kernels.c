/* The specialised render kernels (issue 11): every compiled kernel that has the parts a scene
 * needs renders it bit for bit as the general kernel does, for every shipped scene and the SPD
 * scenes, at 1 and 4 samples and in --local mode; the choice leaves out what a scene does not
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

static int render(const RfScene *s, unsigned kernel, int samples, int local, RfImage *img, RfRenderStats *st)
{
    RfRenderOptions o = rf_render_options_default();
    o.width = 40;
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
        const int modes[3][2] = {{1, 0}, {4, 0}, {1, 1}}; /* samples, local */
        for (int m = 0; m < 3; m++) {
            RfImage ref;
            RfRenderStats st;
            if (!render(&s, rf_kernel_all_parts(), modes[m][0], modes[m][1], &ref, &st)) {
                rf_test_fail(__FILE__, __LINE__, "%s: general kernel", g.gl_pathv[i]);
                continue;
            }
            RF_CHECK_EQ_INT(st.kernel, rf_kernel_all_parts());
            /* every other compiled kernel; those that lack a needed part must refuse */
            RfRenderOptions o = rf_render_options_default();
            o.samples = modes[m][0];
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
                RF_CHECK(memcmp(ref.data, img.data, sizeof(float) * 3 * 40 * 30) == 0);
                compared++;
                rf_image_free(&img);
            }
            specialised += chosen != rf_kernel_all_parts();
            rf_image_free(&ref);
        }
        rf_scene_free(&s);
    }
    globfree(&g);
    RF_CHECK(compared >= 60); /* 20 scenes, three modes, and the specialised ones again */
    RF_CHECK(specialised >= 9); /* tree, tetra, torus.obj: no highlights, three modes each */
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

const RfTest rf_tests_kernels[] = {
    {"kernels_identical_to_general", t_kernels_identical},
    {"kernels_choice", t_kernels_choice},
    RF_TEST_END,
};
