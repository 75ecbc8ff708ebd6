/* refray-raster: the comparator's OpenGL rendering of a scene (raster.h) to a linear EXR, the
 * counterpart of `refray render --local`. Its own binary so that refray itself needs no GL. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "../src/cli/args.h"
#include "gl_context.h"
#include "raster.h"
#include "refray/scene_io.h"
#include "refray/version.h"

static void usage(FILE *out)
{
    fprintf(out,
            "usage: refray-raster SCENE -o OUT.exr [--depth-out DEPTH.exr] [--png OUT.png]\n"
            "                     [--mode phong|gouraud|flat] [--width W] [--height H]\n"
            "                     [--gamma G | --srgb] [--nff-fov centres|edges] [--gl auto|osmesa|egl]\n"
            "  OpenGL 4.5 core (offscreen) rasterization of the scene with the tracer's --local\n"
            "  shading: the image `refray render --local` must reproduce (docs/compare.md).\n"
            "  -o           linear RGB OpenEXR (32-bit float)\n"
            "  --depth-out  linear eye-space depth (distance along the view axis), +inf = background\n"
            "  --mode       phong (per pixel, default); gouraud and flat shade polygons per vertex /\n"
            "               per face (teaching); spheres, cones and planes are always per pixel\n"
            "  --gl         the headless GL: osmesa (Mesa's off-screen library), egl (Mesa's\n"
            "               surfaceless EGL, OSMesa's successor) or auto (default: osmesa, else egl);\n"
            "               both give the same image\n"
            "exit: 0 ok, 1 error, 2 usage\n");
}


int main(int argc, char **argv)
{
    const char *scene_path = NULL, *exr = NULL, *depth_out = NULL, *png = NULL;
    RfRasterOptions opt = {0, 0, RF_SHADE_PHONG};
    RfLoadOptions lopt = rf_load_options_default();
    RfPngOptions popt = {RF_PNG_GAMMA, 2.2, 8, NULL};
    int gl = RF_GL_AUTO;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
        int ok = 1, shared, used;
        if (strcmp(a, "--help") == 0 || strcmp(a, "-h") == 0) {
            usage(stdout);
            return 0;
        } else if (strcmp(a, "-o") == 0 && v) {
            exr = v, i++;
        } else if (strcmp(a, "--depth-out") == 0 && v) {
            depth_out = v, i++;
        } else if (strcmp(a, "--png") == 0 && v) {
            png = v, i++;
        } else if (strcmp(a, "--width") == 0 && v) {
            ok = rf_arg_int(v, 1, 65536, &opt.width), i++;
        } else if (strcmp(a, "--height") == 0 && v) {
            ok = rf_arg_int(v, 1, 65536, &opt.height), i++;
        } else if (strcmp(a, "--mode") == 0 && v) {
            i++;
            if (strcmp(v, "phong") == 0)
                opt.mode = RF_SHADE_PHONG;
            else if (strcmp(v, "gouraud") == 0)
                opt.mode = RF_SHADE_GOURAUD;
            else if (strcmp(v, "flat") == 0)
                opt.mode = RF_SHADE_FLAT;
            else
                ok = 0;
        } else if (strcmp(a, "--gl") == 0 && v) {
            ok = (gl = rf_gl_backend_parse(v)) >= 0, i++;
        } else if ((shared = rf_arg_shared(a, v, &lopt, &popt, &used)) != 0) {
            ok = shared > 0, i += used - 1;
        } else if (a[0] != '-' && !scene_path) {
            scene_path = a;
        } else {
            fprintf(stderr, "refray-raster: unknown or incomplete option '%s' (see: refray-raster --help)\n", a);
            return 2;
        }
        if (!ok) {
            fprintf(stderr, "refray-raster: bad value for %s\n", a);
            return 2;
        }
    }
    if (!scene_path || (!exr && !png && !depth_out)) {
        usage(stderr);
        return 2;
    }
    char err[1024];
    RfScene scene;
    const char *outs[3] = {exr, png, depth_out}, *ins[1] = {scene_path};
    if (rf_outputs_check(outs, 3, ins, 1, err, sizeof err) != RF_OK) { /* before any work */
        fprintf(stderr, "refray-raster: %s\n", err);
        return 2;
    }
    rf_scene_init(&scene);
    if (rf_scene_load(scene_path, &lopt, &scene, err, sizeof err) != RF_OK) {
        fprintf(stderr, "%s\n", err);
        return 1;
    }
    RfGlContext *ctx = NULL;
    RfImage img, depth;
    if (rf_gl_context_create((RfGlBackend)gl, &ctx, err, sizeof err) != RF_OK) {
        fprintf(stderr, "refray-raster: %s\n", err);
        rf_scene_free(&scene);
        return 1;
    }
    RfStatus st = rf_raster_render(&scene, &opt, rf_gl_context_proc, ctx, &img, depth_out ? &depth : NULL,
                                   err, sizeof err);
    const char *backend = rf_gl_context_backend(ctx);
    rf_gl_context_destroy(ctx);
    rf_scene_free(&scene);
    if (st != RF_OK) {
        fprintf(stderr, "refray-raster: %s: %s\n", scene_path, err);
        return 1;
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
        rc = 1;
    }
    if (!rc && exr && rf_exr_write_opts(exr, &img, attrs, 4, eopt, err, sizeof err) != RF_OK)
        rc = 1;
    if (!rc && png && rf_png_write(png, &img, popt, err, sizeof err) != RF_OK)
        rc = 1;
    if (!rc && depth_out && rf_exr_write_opts(depth_out, &depth, attrs, 4, eopt, err, sizeof err) != RF_OK)
        rc = 1;
    if (rc)
        rf_write_batch_abort(batch);
    else if (rf_write_batch_commit(batch, err, sizeof err) != RF_OK)
        rc = 1;
    if (rc)
        fprintf(stderr, "refray-raster: %s\n", err);
    rf_image_free(&img);
    if (depth_out)
        rf_image_free(&depth);
    return rc;
}
