/* refray-raster: the comparator's OpenGL rendering of a scene (raster.h) to a linear EXR, the
 * counterpart of `refray render --local`. Its own binary so that refray itself needs no GL. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "../src/cli/args.h"
#include "../src/cli/exit_codes.h"
#include "gl_context.h"
#include "raster.h"
#include "refray/scene_io.h"
#include "refray/version.h"

enum { OPT_DEPTH_OUT = RF_OPT_ID, OPT_PNG, OPT_MODE, OPT_WIDTH, OPT_HEIGHT, OPT_GL, OPT_TWO_SIDED };

static const RfOpt raster_opts[] = {
    {"output", 'o', "FILE", "the image: .exr linear RGB (32-bit float) or .png (display-encoded)", NULL},
    {"depth-out", OPT_DEPTH_OUT, "DEPTH.exr", "linear eye-space depth (distance along the view axis), +inf = background",
     NULL},
    {"png", OPT_PNG, "OUT.png", "a display PNG besides", NULL},
    {"mode", OPT_MODE, "phong|gouraud|flat", "shading: phong per pixel (default); gouraud, flat per vertex / face",
     "phong, gouraud or flat"},
    {"width", OPT_WIDTH, "W", "image width (default: the scene's)", "an integer in [1, 65536]"},
    {"height", OPT_HEIGHT, "H", "image height (default: the scene's)", "an integer in [1, 65536]"},
    {"gl", OPT_GL, "auto|osmesa|egl", "the headless GL (default auto: osmesa, else egl); the same image",
     "auto, osmesa or egl"},
    {"two-sided", OPT_TWO_SIDED, NULL, "every surface visible from both sides (as refray render --two-sided)", NULL},
    RF_OPT_TABLE_END,
};

static const RfOpt *const raster_tables[] = {raster_opts, rf_opts_png, rf_opts_load, NULL};

static const RfCommand raster_cmd = {
    "refray-raster",
    "refray-raster [options] SCENE -o OUT.exr [--depth-out DEPTH.exr] [--png OUT.png]\n",
    "OpenGL 4.5 core (offscreen) rasterization of the scene with the tracer's --local\n"
    "shading: the image `refray render --local` must reproduce (docs/compare.md).\n",
    raster_tables,
    "--mode gouraud and flat shade polygons per vertex / per face (teaching); spheres, cones\n"
    "and planes are always per pixel. --gl osmesa is Mesa's off-screen library, egl Mesa's\n"
    "surfaceless EGL (OSMesa's successor).\n"
    "exit: 0 ok, 2 no GL context or the rasterization failed, 4 a file cannot be read or\n"
    "written, 5 usage (README: Exit codes)\n",
};

int main(int argc, char **argv)
{
    const char *scene_path = NULL, *exr = NULL, *depth_out = NULL, *png = NULL;
    RfRasterOptions opt = {0, 0, RF_SHADE_PHONG, 0};
    RfLoadOptions lopt = rf_load_options_default();
    RfPngOptions popt = {RF_PNG_GAMMA, 2.2, 8, NULL};
    int gl = RF_GL_AUTO;
    RfOptParser p;
    int key;
    rf_opt_init(&p, &raster_cmd, argc, argv);
    while ((key = rf_opt_next(&p)) != RF_OPT_DONE) {
        const char *v = p.value;
        int ok = 1;
        switch (key) {
        case RF_OPT_EXIT: return p.exit_code;
        case 'o': exr = v; break;
        case OPT_DEPTH_OUT: depth_out = v; break;
        case OPT_PNG: png = v; break;
        case OPT_WIDTH: ok = rf_arg_int(v, 1, 65536, &opt.width); break;
        case OPT_HEIGHT: ok = rf_arg_int(v, 1, 65536, &opt.height); break;
        case OPT_MODE:
            ok = strcmp(v, "phong") == 0 || strcmp(v, "gouraud") == 0 || strcmp(v, "flat") == 0;
            opt.mode = v[0] == 'g' ? RF_SHADE_GOURAUD : v[0] == 'f' ? RF_SHADE_FLAT : RF_SHADE_PHONG;
            break;
        case OPT_GL: ok = (gl = rf_gl_backend_parse(v)) >= 0; break;
        case OPT_TWO_SIDED: opt.two_sided = 1; break;
        default: ok = rf_arg_shared(key, v, &lopt, &popt) > 0;
        }
        if (!ok)
            return rf_opt_bad_value(&p);
    }
    int bad = rf_opt_operand(&p, "the scene file", &scene_path);
    if (bad)
        return bad;
    if (!exr && !png && !depth_out)
        return rf_opt_usage_error(&raster_cmd, "missing the output: -o OUT.exr, -o OUT.png, --png or --depth-out");
    if ((exr && !rf_arg_image_format("refray-raster", "-o", exr, RF_IMAGE_EXR | RF_IMAGE_PNG)) ||
        (png && !rf_arg_image_format("refray-raster", "--png", png, RF_IMAGE_PNG)) ||
        (depth_out && !rf_arg_image_format("refray-raster", "--depth-out", depth_out, RF_IMAGE_EXR)))
        return RF_EXIT_USAGE;
    char err[1024];
    RfScene scene;
    const char *outs[3] = {exr, png, depth_out}, *ins[1] = {scene_path};
    bad = rf_arg_outputs_check("refray-raster", outs, 3, ins, 1); /* before any work */
    if (bad)
        return bad;
    rf_scene_init(&scene);
    if (rf_scene_load(scene_path, &lopt, &scene, err, sizeof err) != RF_OK) {
        rf_arg_report("refray-raster", err);
        return RF_EXIT_FILE;
    }
    RfGlContext *ctx = NULL;
    RfImage img, depth;
    if (rf_gl_context_create((RfGlBackend)gl, &ctx, err, sizeof err) != RF_OK) {
        fprintf(stderr, "refray-raster: %s\n", err);
        rf_scene_free(&scene);
        return RF_EXIT_FAIL;
    }
    RfStatus st = rf_raster_render(&scene, &opt, rf_gl_context_proc, ctx, &img, depth_out ? &depth : NULL,
                                   err, sizeof err);
    const char *backend = rf_gl_context_backend(ctx);
    rf_gl_context_destroy(ctx);
    rf_scene_free(&scene);
    if (st != RF_OK) {
        fprintf(stderr, "refray-raster: %s: %s\n", scene_path, err);
        return RF_EXIT_FAIL;
    }
    static const char *modes[] = {"phong", "gouraud", "flat"};
    char settings[128];
    snprintf(settings, sizeof settings, "%dx%d, OpenGL 4.5 core (%s), %s shading", img.width, img.height,
             backend, modes[opt.mode]);
    RfImageAttr attrs[] = {{"refray:version", RF_VERSION}, {"refray:scene", scene_path},
                           {"refray:renderer", "refray-raster"}, {"refray:settings", settings}};
    int rc = 0;
    RfWriteBatch *batch = rf_write_batch_new(); /* the outputs together, or none */
    RfExrOptions eopt = {RF_EXR_ZIP, 0, batch, 0, 0, 0, 0};
    popt.batch = batch;
    if (!batch) {
        snprintf(err, sizeof err, "out of memory");
        rc = RF_EXIT_FAIL;
    }
    if (!rc && exr && rf_arg_write_image(exr, &img, attrs, 4, eopt, popt, err, sizeof err) != RF_OK)
        rc = RF_EXIT_FILE;
    if (!rc && png && rf_png_write(png, &img, popt, err, sizeof err) != RF_OK)
        rc = RF_EXIT_FILE;
    if (!rc && depth_out && rf_exr_write_opts(depth_out, &depth, attrs, 4, eopt, err, sizeof err) != RF_OK)
        rc = RF_EXIT_FILE;
    if (rc)
        rf_write_batch_abort(batch);
    else if (rf_write_batch_commit(batch, err, sizeof err) != RF_OK)
        rc = RF_EXIT_FILE;
    if (rc)
        fprintf(stderr, "refray-raster: %s\n", err);
    rf_image_free(&img);
    if (depth_out)
        rf_image_free(&depth);
    return rc;
}
