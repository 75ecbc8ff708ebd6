/* The scene exporters' entry points (refray/scene_export.h): the options, rf_scene_export,
 * which sets up the context and picks the writer (export_mitsuba.c, export_pbrt.c,
 * export_pov.c), and rf_export_free. What the writers share is export_common.c, below them. */
#include <stdlib.h>
#include <string.h>

#include "export_internal.h"

RfExportOptions rf_export_options_default(void)
{
    RfExportOptions o;
    memset(&o, 0, sizeof o);
    o.format = RF_EXPORT_MITSUBA;
    o.shadows = -1;
    return o;
}

/* The §3.4 basis: w = normalise(eye - target), u = normalise(up x w), v = w x u. */
static void camera_basis(RfExCtx *c)
{
    const RfSceneCamera *cam = &c->s->camera;
    c->w = rf_vec3_normalize(rf_vec3_sub(cam->eye, cam->target));
    c->u = rf_vec3_normalize(rf_vec3_cross(cam->up, c->w));
    c->v = rf_vec3_cross(c->w, c->u);
}

RfStatus rf_scene_export(const RfScene *scene, const RfExportOptions *opt, RfExport *ex)
{
    memset(ex, 0, sizeof *ex);
    RfExCtx *c = calloc(1, sizeof *c);
    if (!c)
        return RF_ERR_NOMEM;
    RfScene flat;
    int flattened = 0;
    c->o = opt;
    c->ex = ex;
    c->s = scene;
    if (scene->instance_count > 0) {
        char msg[256];
        RfStatus st = rf_scene_flatten(scene, RF_FLATTEN_PLACED_QUADRICS, &flat, msg, sizeof msg);
        if (st != RF_OK) {
            RfSrcLoc none = {0, 0};
            rf__ex_note(c, none, 2, "the scene graph cannot be written as plain primitives: %s (not even with "
                        "--lossy)", msg);
            free(c);
            return st == RF_ERR_NOMEM ? RF_ERR_NOMEM : RF_ERR_DOMAIN;
        }
        flattened = 1;
        c->s = &flat;
    }
    c->width = opt->width > 0 ? opt->width : scene->render.width;
    c->height = opt->height > 0 ? opt->height : scene->render.height;
    c->depth = opt->depth > 0 ? opt->depth : scene->render.max_depth;
    c->samples = opt->samples > 0 ? opt->samples : scene->render.samples;
    c->filtered = (opt->shadows >= 0 ? opt->shadows : (int)scene->render.shadows) == RF_SHADOWS_FILTERED;
    c->win = rf_scene_camera_window(&scene->camera, c->width, c->height);
    camera_basis(c);
    if (scene->motion_count > 0) {
        RfSrcLoc none = {0, 0};
        rf__ex_note(c, none, 1, "motion blur: %zu moving instances (written at the shutter's opening)",
                    scene->motion_count);
    }
    if (rf__ex_file(c, opt->output ? opt->output : "scene")) {
        if (opt->format == RF_EXPORT_MITSUBA)
            rf__export_mitsuba(c);
        else if (opt->format == RF_EXPORT_PBRT)
            rf__export_pbrt(c);
        else
            rf__export_pov(c);
    }
    RfStatus st = ex->failed ? RF_ERR_NOMEM : ex->problems && !opt->lossy ? RF_ERR_DOMAIN : RF_OK;
    if (st != RF_OK) { /* nothing to write */
        for (size_t i = 0; i < ex->file_count; i++) {
            free(ex->files[i].path);
            free(ex->files[i].text);
        }
        free(ex->files);
        ex->files = NULL;
        ex->file_count = 0;
    }
    if (flattened)
        rf_scene_free(&flat);
    free(c);
    return st;
}

void rf_export_free(RfExport *ex)
{
    for (size_t i = 0; i < ex->file_count; i++) {
        free(ex->files[i].path);
        free(ex->files[i].text);
    }
    free(ex->files);
    free(ex->notes);
    memset(ex, 0, sizeof *ex);
}
