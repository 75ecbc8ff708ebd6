/* refray: the whole-scene check (rf_scene_validate): camera, settings, every material, light
 * and primitive, and the scene graph. Above scene.c (the model's own checks) and scene_graph.c
 * (the graph's), which it calls. */
#include <math.h>
#include <stdio.h>

#include "scene_internal.h"

static RfStatus check_light(const RfLight *l, char *msg, size_t msgsz)
{
    if (!rf__finite3(l->position) || !rf__finite3(l->direction) || !rf__nonneg_rgb(l->intensity))
        return rf__msgf(msg, msgsz, RF_ERR_DOMAIN, "light: values must be finite, intensity >= 0");
    if (l->kind != RF_LIGHT_POINT && l->kind != RF_LIGHT_SPHERE && !(rf_vec3_length(l->direction) > 0.0))
        return rf__msgf(msg, msgsz, RF_ERR_DEGENERATE, "light: direction has zero length");
    if (rf_light_is_area(l->kind)) {
        if (!rf__finite3(l->edge1) || !rf__finite3(l->edge2) || !isfinite(l->radius))
            return rf__msgf(msg, msgsz, RF_ERR_DOMAIN, "area light: values must be finite");
        if (l->samples < 1 || l->samples > 1 << 16)
            return rf__msgf(msg, msgsz, RF_ERR_DOMAIN, "area light: samples must be in [1, 65536]");
        if (!(rf_light_area(l) > 0.0) || !isfinite(rf_light_area(l)))
            return rf__msgf(msg, msgsz, RF_ERR_DEGENERATE, "area light: its area must be > 0");
    }
    if (l->kind == RF_LIGHT_SPOT && (!(l->spot_cutoff > 0.0 && l->spot_cutoff <= 90.0) ||
                                     !(l->spot_exponent >= 0.0) || !isfinite(l->spot_exponent)))
        return rf__msgf(msg, msgsz, RF_ERR_DOMAIN,
                    "spot light: cutoff must be in (0, 90] degrees, exponent >= 0");
    return RF_OK;
}

static RfStatus check_material(const RfMaterial *m, char *msg, size_t msgsz)
{
    const RfRgb *c[] = {&m->ka, &m->kd, &m->ks, &m->kr, &m->kt, &m->emission};
    for (size_t i = 0; i < sizeof c / sizeof c[0]; i++)
        if (!rf__nonneg_rgb(*c[i]))
            return rf__msgf(msg, msgsz, RF_ERR_DOMAIN, "material: coefficients must be finite, >= 0");
    if (!(m->shininess >= 0.0) || !isfinite(m->shininess) || !(m->ior > 0.0) || !isfinite(m->ior))
        return rf__msgf(msg, msgsz, RF_ERR_DOMAIN, "material: needs shininess >= 0 and ior > 0");
    if (!(m->gloss >= 0.0) || !isfinite(m->gloss))
        return rf__msgf(msg, msgsz, RF_ERR_DOMAIN, "material: needs gloss >= 0");
    return RF_OK;
}

static RfStatus located(char *err, size_t errsz, const char *source, RfSrcLoc loc,
                        const char *msg, RfStatus st)
{
    snprintf(err, errsz, "%s:%d:%d: %s", source ? source : "<scene>", loc.line, loc.col, msg);
    return st;
}

/* rf_scene_validate; prims = 0 leaves out the primitives' checks */
static RfStatus validate(const RfScene *scene, const char *source, char *err, size_t errsz, int prims)
{
    char msg[256];
    RfSrcLoc loc = {1, 1};
    RfStatus st;
    const RfRenderSettings *r = &scene->render;
    if (!scene->has_camera)
        return located(err, errsz, source, loc, "the scene has no camera", RF_ERR_DOMAIN);
    if ((st = rf_scene_camera_check(&scene->camera, &loc, msg, sizeof msg)))
        return located(err, errsz, source, loc, msg, st);
    if (r->width < 1 || r->height < 1 || r->max_depth < 1 || r->samples < 1 ||
        !(r->min_contribution >= 0.0 && r->min_contribution <= 1.0) || !rf__nonneg_rgb(r->background) ||
        !rf__nonneg_rgb(r->ambient) || (unsigned)r->sampler >= RF_SAMPLER_COUNT ||
        (unsigned)r->filter.kind >= RF_FILTER_COUNT || !(r->filter.radius > 0.0 && r->filter.radius <= 16.0) ||
        !(r->filter.sigma > 0.0 || r->filter.kind != RF_FILTER_GAUSSIAN) || !(r->adaptive_threshold >= 0.0) ||
        r->adaptive_depth < 0 || r->adaptive_depth > 8 || !isfinite(r->shutter_open) ||
        !isfinite(r->shutter_close) || !(r->shutter_open <= r->shutter_close) ||
        (r->shadows != RF_SHADOWS_OPAQUE && r->shadows != RF_SHADOWS_FILTERED))
        return located(err, errsz, source, loc, "render settings out of range", RF_ERR_DOMAIN);
    for (size_t i = 0; i < scene->material_count; i++)
        if ((st = check_material(&scene->materials[i], msg, sizeof msg)))
            return located(err, errsz, source, scene->materials[i].loc, msg, st);
    for (size_t i = 0; i < scene->light_count; i++)
        if ((st = check_light(&scene->lights[i], msg, sizeof msg)))
            return located(err, errsz, source, scene->lights[i].loc, msg, st);
    for (size_t i = 0; prims && i < scene->prim_count; i++)
        if ((st = rf_scene_check_primitive(scene, &scene->prims[i], msg, sizeof msg)))
            return located(err, errsz, source, scene->prims[i].loc, msg, st);
    if ((st = rf_scene_graph_check(scene, &loc, msg, sizeof msg)))
        return located(err, errsz, source, loc, msg, st);
    return RF_OK;
}

RfStatus rf_scene_validate(const RfScene *scene, const char *source, char *err, size_t errsz)
{
    return validate(scene, source, err, errsz, 1);
}

RfStatus rf__scene_validate_read(const RfScene *scene, const char *source, char *err, size_t errsz)
{
    return validate(scene, source, err, errsz, 0);
}
