/* refray export --pbrt: the scene as a pbrt-v4 scene file for its `path` integrator.
 * docs/crosscheck.md derives the conversions; pbrt-v4 is not packaged for Debian, so this
 * writer is checked by content only (tests/test_export.c), not by renders. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "export_internal.h"
#include "refray/geometry.h"

#define PBRT_LIGHT_SCALE 3.14159265358979323846 /* as Mitsuba's: rho = kd, I' = pi I */

/* The material of a shape; what pbrt-v4 cannot represent is noted at its first use only
 * (notes 1), not once per shape of a mesh. */
static void material(RfExCtx *c, const RfMaterial *m, int notes)
{
    RfExMat x = rf__ex_classify(c->s, m);
    if (notes && x.highlight)
        rf__ex_note(c, m->loc, 1, "material '%s': Phong highlight ks (%s): pbrt-v4 has no Phong lobe (dropped)",
                    m->name, rf__ex_rgb(c, m->ks, " "));
    if (x.transmits || x.fresnel) {
        if (notes && (!x.fresnel || m->kr.r != 1.0 || m->kr.g != 1.0 || m->kr.b != 1.0 || m->kt.r != 1.0 ||
                      m->kt.g != 1.0 || m->kt.b != 1.0 || x.diffuse))
            rf__ex_note(c, m->loc, 1, "material '%s': pbrt-v4's dielectric is exactly kr = kt = 1 with `fresnel` and "
                        "no diffuse term (written as that)", m->name);
        rf__ex_printf(c, "  Material \"dielectric\" \"float eta\" [ %s ]  # '%s'\n", rf__ex_num(c, m->ior), m->name);
    } else if (x.mirror) {
        if (notes)
            rf__ex_note(c, m->loc, 1, "material '%s': mirror kr (%s): pbrt-v4's conductor made from a reflectance "
                        "follows a metal's Fresnel curve, refray's mirror weight is constant%s", m->name,
                        rf__ex_rgb(c, m->kr, " "), x.diffuse ? "; its diffuse part dropped" : "");
        rf__ex_printf(c, "  Material \"conductor\" \"rgb reflectance\" [ %s ] \"float roughness\" [ 0 ]  # '%s'\n",
                      rf__ex_rgb(c, m->kr, " "), m->name);
    } else {
        rf__ex_printf(c, "  Material \"diffuse\" \"rgb reflectance\" [ %s ]  # '%s'\n", rf__ex_rgb(c, m->kd, " "), m->name);
    }
}

/* x, y, z axes and the origin as pbrt's ConcatTransform (column-major). */
static void frame(RfExCtx *c, RfVec3 x, RfVec3 y, RfVec3 z, RfVec3 t)
{
    rf__ex_printf(c, "  ConcatTransform [ %s 0  %s 0  %s 0  %s 1 ]\n", rf__ex_vec(c, x, " "), rf__ex_vec(c, y, " "),
                  rf__ex_vec(c, z, " "), rf__ex_vec(c, t, " "));
}

static void light(RfExCtx *c, const RfLight *l)
{
    RfRgb i = rf_rgb_scale(l->intensity, PBRT_LIGHT_SCALE);
    switch (l->kind) {
    case RF_LIGHT_POINT:
        rf__ex_printf(c, "LightSource \"point\" \"point3 from\" [ %s ] \"rgb I\" [ %s ]\n", rf__ex_vec(c, l->position, " "),
                      rf__ex_rgb(c, i, " "));
        return;
    case RF_LIGHT_SPOT:
        rf__ex_printf(c, "LightSource \"spot\" \"point3 from\" [ %s ] \"point3 to\" [ %s ] \"float coneangle\" [ %s ] "
                      "\"float conedelta\" [ 0 ] \"rgb I\" [ %s ]\n", rf__ex_vec(c, l->position, " "),
                      rf__ex_vec(c, rf_vec3_add(l->position, l->direction), " "), rf__ex_num(c, l->spot_cutoff),
                      rf__ex_rgb(c, i, " "));
        return;
    case RF_LIGHT_DIRECTIONAL:
        rf__ex_printf(c, "LightSource \"distant\" \"point3 from\" [ 0 0 0 ] \"point3 to\" [ %s ] \"rgb L\" [ %s ]\n",
                      rf__ex_vec(c, l->direction, " "), rf__ex_rgb(c, i, " "));
        return;
    case RF_LIGHT_RECT: case RF_LIGHT_DISC: case RF_LIGHT_SPHERE:
        rf__ex_printf(c, "AttributeBegin\n  AreaLightSource \"diffuse\" \"rgb L\" [ %s ] \"bool twosided\" %s\n"
                      "  Material \"diffuse\" \"rgb reflectance\" [ 0 0 0 ]\n", rf__ex_rgb(c, i, " "),
                      l->two_sided ? "true" : "false");
        if (l->kind == RF_LIGHT_SPHERE) {
            rf__ex_printf(c, "  Translate %s\n  Shape \"sphere\" \"float radius\" [ %s ]\n", rf__ex_vec(c, l->position, " "),
                          rf__ex_num(c, l->radius));
        } else if (l->kind == RF_LIGHT_RECT) {
            RfVec3 p = l->position, a = rf_vec3_add(p, l->edge1), b = rf_vec3_add(a, l->edge2), d = rf_vec3_add(p, l->edge2);
            rf__ex_printf(c, "  Shape \"trianglemesh\" \"integer indices\" [ 0 1 2 0 2 3 ] \"point3 P\" [ %s  %s  %s  %s ]\n",
                          rf__ex_vec(c, p, " "), rf__ex_vec(c, a, " "), rf__ex_vec(c, b, " "), rf__ex_vec(c, d, " "));
        } else {
            RfVec3 a = rf__ex_perpendicular(l->direction);
            frame(c, a, rf_vec3_cross(l->direction, a), l->direction, l->position);
            rf__ex_printf(c, "  Shape \"disk\" \"float radius\" [ %s ]\n", rf__ex_num(c, l->radius));
        }
        rf__ex_printf(c, "AttributeEnd\n");
        rf__ex_note(c, l->loc, 0, "%s area light: pbrt-v4's is a shape, seen by every ray and blocking shadow rays; "
                    "refray's is seen by none", rf_light_kind_name(l->kind));
        return;
    case RF_LIGHT_KIND_COUNT:
        return;
    }
}

static void shape(RfExCtx *c, const RfPrimitive *world, double plane_size, unsigned char *noted)
{
    const RfScene *s = c->s;
    const RfInstance *placement;
    const RfPrimitive *p = rf__ex_world_prim(s, world, &placement);
    if (!p)
        return;
    rf__ex_printf(c, "AttributeBegin  # line %d\n", p->loc.line);
    material(c, &s->materials[p->material], !noted[p->material]);
    noted[p->material] = 1;
    if (placement) { /* an ellipsoid or a sheared cone: the quadric in its object's space, placed */
        const RfMat4 *m = &placement->to_world;
        frame(c, rf_vec3(m->m[0][0], m->m[1][0], m->m[2][0]), rf_vec3(m->m[0][1], m->m[1][1], m->m[2][1]),
              rf_vec3(m->m[0][2], m->m[1][2], m->m[2][2]), rf_vec3(m->m[0][3], m->m[1][3], m->m[2][3]));
    }
    switch (p->type) {
    case RF_PRIM_SPHERE:
        if ((p->flags & RF_PRIM_INSIDE) && !c->o->two_sided)
            rf__ex_note(c, p->loc, 1, "inside-only sphere: pbrt-v4's sphere is seen from both sides");
        rf__ex_printf(c, "  Translate %s\n  Shape \"sphere\" \"float radius\" [ %s ]\n",
                      rf__ex_vec(c, p->u.sphere.center, " "), rf__ex_num(c, p->u.sphere.radius));
        break;
    case RF_PRIM_PLANE: {
        RfVec3 n = p->u.plane.normal, a = rf_vec3_scale(rf__ex_perpendicular(n), plane_size),
               b = rf_vec3_scale(rf_vec3_cross(n, rf__ex_perpendicular(n)), plane_size), o = rf_vec3_scale(n, p->u.plane.offset);
        rf__ex_note(c, p->loc, 0, "infinite plane written as a square of side %s: its horizon differs",
                    rf__ex_num(c, 2.0 * plane_size));
        rf__ex_printf(c, "  Shape \"trianglemesh\" \"integer indices\" [ 0 1 2 0 2 3 ] \"point3 P\" [ %s  %s  %s  %s ]\n",
                      rf__ex_vec(c, rf_vec3_sub(rf_vec3_sub(o, a), b), " "), rf__ex_vec(c, rf_vec3_sub(rf_vec3_add(o, a), b), " "),
                      rf__ex_vec(c, rf_vec3_add(rf_vec3_add(o, a), b), " "), rf__ex_vec(c, rf_vec3_add(rf_vec3_sub(o, a), b), " "));
        break;
    }
    case RF_PRIM_CONE: {
        const RfCone *k = &p->u.cone;
        if (k->base_radius != k->apex_radius)
            rf__ex_note(c, p->loc, 1, "cone with radii %s and %s: pbrt-v4 has only cylinders (written with their "
                        "mean radius)", rf__ex_num(c, k->base_radius), rf__ex_num(c, k->apex_radius));
        RfVec3 ax = rf_vec3_sub(k->apex, k->base);
        double len = rf_vec3_length(ax);
        RfVec3 z = rf_vec3_scale(ax, 1.0 / len), x = rf__ex_perpendicular(z);
        frame(c, x, rf_vec3_cross(z, x), z, k->base);
        rf__ex_printf(c, "  Shape \"cylinder\" \"float radius\" [ %s ] \"float zmin\" [ 0 ] \"float zmax\" [ %s ]\n",
                      rf__ex_num(c, 0.5 * (k->base_radius + k->apex_radius)), rf__ex_num(c, len));
        break;
    }
    case RF_PRIM_TRIANGLE:
    case RF_PRIM_POLYGON: {
        const RfVec3 *v = s->vertices + p->u.poly.first;
        int n = p->u.poly.count;
        int tri_buf[3 * 64], *tri = NULL, nt = n - 2;
        if ((p->flags & RF_PRIM_NONCONVEX) && n <= 66) {
            tri = tri_buf;
            nt = rf_triangulate_polygon(v, n, tri);
        } else if (p->flags & RF_PRIM_NONCONVEX) {
            rf__ex_note(c, p->loc, 1, "non-convex polygon of %d vertices: fanned (more than 66 are not cut into "
                        "ears here)", n);
        }
        rf__ex_printf(c, "  Shape \"trianglemesh\" \"integer indices\" [");
        for (int t = 0; t < nt; t++)
            rf__ex_printf(c, " %d %d %d", tri ? tri[3 * t] : 0, tri ? tri[3 * t + 1] : t + 1, tri ? tri[3 * t + 2] : t + 2);
        rf__ex_printf(c, " ]\n    \"point3 P\" [");
        for (int k = 0; k < n; k++)
            rf__ex_printf(c, "  %s", rf__ex_vec(c, v[k], " "));
        rf__ex_printf(c, " ]\n");
        if ((p->flags & RF_PRIM_VERTEX_NORMALS) && (s->materials[p->material].flags & RF_MAT_SMOOTH)) {
            rf__ex_printf(c, "    \"normal N\" [");
            for (int k = 0; k < n; k++)
                rf__ex_printf(c, "  %s", rf__ex_vec(c, s->normals[p->u.poly.nfirst + k], " "));
            rf__ex_printf(c, " ]\n");
        }
        break;
    }
    case RF_PRIM_INSTANCE:
    case RF_PRIM_TYPE_COUNT:
        break;
    }
    rf__ex_printf(c, "AttributeEnd\n");
}

void rf__export_pbrt(RfExCtx *c)
{
    const RfScene *s = c->s;
    RfWindow w = c->win;
    rf__ex_common_checks(c, 1, 1);
    rf__ex_check_hither(c);
    RfVec3 lo, hi;
    double extent = rf_scene_bounds(s, &lo, &hi) ? rf_vec3_length(rf_vec3_sub(hi, lo)) : 1.0;
    extent = fmax(extent, rf_vec3_length(rf_vec3_sub(s->camera.eye, s->camera.target)));
    rf__ex_common_header(c, "# ");
    rf__ex_printf(c, "# pbrt-v4, `path` integrator:\n"
                     "# - diffuse: refray's kd I cos(theta) / d^2 (no 1/pi) is pbrt's (rho/pi) I' cos(theta) / d^2 with\n"
                     "#   reflectance rho = kd and every light's I, L scaled by pi; glass: dielectric eta = ior (exactly\n"
                     "#   refray's kr = kt = 1 with `fresnel`)\n"
                     "# - pbrt's camera space is left-handed: `Scale -1 1 1` before LookAt keeps refray's image right =\n"
                     "#   view direction x up; fov 90 with screenwindow = refray's window / d (any window, off-centre too)\n"
                     "# - maxdepth = refray's depth: pbrt samples the lights at the hits 1 .. maxdepth; its path tracer\n"
                     "#   also carries diffuse-to-diffuse light, which a Whitted tracer does not\n"
                     "# - not checked by a render here: pbrt-v4 is not packaged for Debian\n");
    char stem[4096];
    const char *out = c->o->output ? c->o->output : "scene.pbrt";
    snprintf(stem, sizeof stem, "%s", out);
    char *dot = strrchr(stem, '.'), *slash = strrchr(stem, '/');
    if (dot && (!slash || dot > slash))
        *dot = '\0';
    const char *base = strrchr(stem, '/') ? strrchr(stem, '/') + 1 : stem;
    rf__ex_printf(c, "Scale -1 1 1\nLookAt %s  %s  %s\n", rf__ex_vec(c, s->camera.eye, " "),
                  rf__ex_vec(c, s->camera.target, " "), rf__ex_vec(c, s->camera.up, " "));
    rf__ex_printf(c, "Camera \"perspective\" \"float fov\" [ 90 ] \"float screenwindow\" [ %s %s %s %s ]",
                  rf__ex_num(c, w.l / w.d), rf__ex_num(c, w.r / w.d), rf__ex_num(c, w.b / w.d), rf__ex_num(c, w.t / w.d));
    if (s->camera.aperture > 0.0)
        rf__ex_printf(c, " \"float lensradius\" [ %s ] \"float focaldistance\" [ %s ]", rf__ex_num(c, s->camera.aperture),
                      rf__ex_num(c, s->camera.focus));
    rf__ex_printf(c, "\nSampler \"independent\" \"integer pixelsamples\" [ %d ]\n"
                     "PixelFilter \"box\" \"float xradius\" [ 0.5 ] \"float yradius\" [ 0.5 ]\n"
                     "Film \"rgb\" \"integer xresolution\" [ %d ] \"integer yresolution\" [ %d ] \"string filename\" [ \"%s.exr\" ]\n"
                     "Integrator \"path\" \"integer maxdepth\" [ %d ]\nWorldBegin\n",
                  c->samples, c->width, c->height, base, c->depth);
    if (s->render.background.r > 0.0 || s->render.background.g > 0.0 || s->render.background.b > 0.0)
        rf__ex_printf(c, "LightSource \"infinite\" \"rgb L\" [ %s ]  # lights diffuse surfaces too, unlike refray's background\n",
                      rf__ex_rgb(c, s->render.background, " "));
    for (size_t i = 0; i < s->light_count; i++)
        light(c, &s->lights[i]);
    unsigned char *noted = calloc(s->material_count ? s->material_count : 1, 1);
    if (!noted) {
        c->ex->failed = 1;
        return;
    }
    for (size_t i = 0; i < s->prim_count; i++)
        shape(c, &s->prims[i], 1e3 * extent, noted);
    free(noted);
    rf__ex_note_one_sided(c, "shades it");
}
