/* refray export --pov: the scene as POV-Ray 3.7 SDL with refray's conventions (it replaces
 * tools/nff2pov.py, whose conventions were checked: POV-Ray agrees with refray to its half-float
 * EXR rounding on whitted and the SPD balls, rings, tetra and tree). docs/crosscheck.md. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "export_internal.h"

static int grey(RfRgb c) { return c.r == c.g && c.g == c.b; }
static int positive_kt(const RfMaterial *m) { return m->kt.r > 0.0 || m->kt.g > 0.0 || m->kt.b > 0.0; }
static RfVec3 vmin(RfVec3 a, RfVec3 b) { return rf_vec3(fmin(a.x, b.x), fmin(a.y, b.y), fmin(a.z, b.z)); }
static RfVec3 vmax(RfVec3 a, RfVec3 b) { return rf_vec3(fmax(a.x, b.x), fmax(a.y, b.y), fmax(a.z, b.z)); }

/* The size of the scene: its bounds, the eye and the lights (for the fade distance of inverse-
 * square lights and where a directional light is placed). */
static double scene_extent(const RfScene *s, RfVec3 *centre)
{
    RfVec3 lo, hi;
    if (!rf_scene_bounds(s, &lo, &hi))
        lo = hi = s->camera.eye;
    for (size_t i = 0; i < s->light_count; i++)
        if (s->lights[i].kind != RF_LIGHT_DIRECTIONAL) {
            lo = vmin(lo, s->lights[i].position);
            hi = vmax(hi, s->lights[i].position);
        }
    lo = vmin(lo, s->camera.eye);
    hi = vmax(hi, s->camera.eye);
    *centre = rf_vec3_scale(rf_vec3_add(lo, hi), 0.5);
    double e = rf_vec3_length(rf_vec3_sub(hi, lo));
    return e > 0.0 && isfinite(e) ? e : 1.0;
}

/* #declare M<index> = material { texture { ... } interior { ... } } */
static void write_material(RfExCtx *c, const RfMaterial *m, size_t index)
{
    RfExMat x = rf__ex_classify(c->s, m);
    const char *to = "POV-Ray";
    if (x.transmits && (x.diffuse || x.highlight))
        rf__ex_note(c, m->loc, 1, "material '%s': transmission with a diffuse or highlight term: POV-Ray's filter "
                    "takes its share from the surface colour, refray's kt does not (%s)", m->name,
                    c->o->lossy ? "written with the filter" : "refused");
    if (x.highlight && !grey(m->ks))
        rf__ex_note(c, m->loc, 1, "material '%s': coloured highlight ks (%s): %s's phong is grey (written with "
                    "their mean)", m->name, rf__ex_rgb(c, m->ks, " "), to);
    if (x.fresnel && x.transmits && !(m->kr.r == 1.0 && m->kr.g == 1.0 && m->kr.b == 1.0))
        rf__ex_note(c, m->loc, 1, "material '%s': Fresnel glass with kr (%s) other than 1: POV-Ray's "
                    "conserve_energy takes kr F from the transmitted light, refray kt (1 - F)", m->name,
                    rf__ex_rgb(c, m->kr, " "));
    rf__ex_printf(c, "#declare M%zu = material {  // '%s'\n", index, m->name);
    if (x.transmits)
        rf__ex_printf(c, "  texture { pigment { rgbf <%s, 1> }\n", rf__ex_rgb(c, m->kt, ", "));
    else
        rf__ex_printf(c, "  texture { pigment { rgb <%s> }\n", rf__ex_rgb(c, m->kd, ", "));
    rf__ex_printf(c, "    finish { ambient 0 diffuse %s specular 0", x.transmits ? "0" : "1");
    if (x.highlight)
        rf__ex_printf(c, " phong %s phong_size %s", rf__ex_num(c, (m->ks.r + m->ks.g + m->ks.b) / 3.0),
                      rf__ex_num(c, m->shininess));
    else
        rf__ex_printf(c, " phong 0");
    if (x.fresnel)
        rf__ex_printf(c, " reflection { 0, rgb <%s> fresnel on }%s", rf__ex_rgb(c, m->kr, ", "),
                      x.transmits ? " conserve_energy" : "");
    else if (x.mirror)
        rf__ex_printf(c, " reflection { rgb <%s> }", rf__ex_rgb(c, m->kr, ", "));
    rf__ex_printf(c, " }\n  }\n");
    if (x.transmits || x.fresnel)
        rf__ex_printf(c, "  interior { ior %s }\n", rf__ex_num(c, m->ior));
    rf__ex_printf(c, "}\n");
}

/* POV-Ray lets shadow rays through filtering objects; refray's shadows of transmitting objects
 * are opaque (unless --shadows filtered). For a sphere and a point or spot light a black disc
 * that fills the cone from the light to the sphere, halfway between them, invisible to camera
 * and reflected rays, casts exactly the sphere's shadow beyond it (scenes/bench/whitted.pov). */
static void opaque_shadow_discs(RfExCtx *c, const RfPrimitive *p)
{
    for (size_t i = 0; i < c->s->light_count; i++) {
        const RfLight *l = &c->s->lights[i];
        if (l->kind != RF_LIGHT_POINT && l->kind != RF_LIGHT_SPOT)
            continue;
        RfVec3 to = rf_vec3_sub(p->u.sphere.center, l->position);
        double dist = rf_vec3_length(to), r = p->u.sphere.radius;
        if (!(dist > r))
            continue;
        RfVec3 ax = rf_vec3_scale(to, 1.0 / dist);
        double sin_a = r / dist, tan_a = sin_a / sqrt(1.0 - sin_a * sin_a), td = 0.5 * (dist - r);
        rf__ex_printf(c, "disc { <%s>, <%s>, %s  // the opaque shadow of line %d for light %zu\n"
                      "  texture { pigment { rgb 0 } finish { ambient 0 diffuse 0 phong 0 } } no_image no_reflection }\n",
                      rf__ex_vec(c, rf_vec3_add(l->position, rf_vec3_scale(ax, td)), ", "), rf__ex_vec(c, ax, ", "),
                      rf__ex_num(c, td * tan_a), p->loc.line, i);
    }
}

/* "  material { M<index> } }\n": the end of an object */
static const char *material_ref(RfExCtx *c, int index)
{
    char *b = c->ring[c->ring_next]; /* a slot of the ring, as the numbers beside it */
    c->ring_next = (c->ring_next + 1) % RF_EX_RING;
    snprintf(b, RF_EX_SLOT, "  material { M%d } }\n", index);
    return b;
}

static void write_light(RfExCtx *c, const RfLight *l, double fade, RfVec3 centre, double extent)
{
    int inv_sq = l->kind != RF_LIGHT_DIRECTIONAL && l->falloff == RF_FALLOFF_INVERSE_SQUARE;
    RfRgb i = l->intensity;
    RfVec3 pos = l->position;
    if (rf_light_is_area(l->kind)) { /* noted: a point light of the same power from afar */
        double a = rf_light_area(l);
        if (l->kind == RF_LIGHT_SPHERE)
            a *= 0.25;
        else if (l->kind == RF_LIGHT_RECT)
            pos = rf_vec3_add(pos, rf_vec3_scale(rf_vec3_add(l->edge1, l->edge2), 0.5));
        i = rf_rgb_scale(i, a);
        inv_sq = 1;
    }
    if (l->kind == RF_LIGHT_DIRECTIONAL) /* far upstream of everything: POV-Ray's shadow rays end there */
        pos = rf_vec3_sub(centre, rf_vec3_scale(l->direction, 1e3 * extent));
    if (inv_sq)
        i = rf_rgb_scale(i, 1.0 / (2.0 * fade * fade));
    rf__ex_printf(c, "light_source { <%s> color rgb <%s>", rf__ex_vec(c, pos, ", "), rf__ex_rgb(c, i, ", "));
    if (inv_sq)
        rf__ex_printf(c, " fade_distance %s fade_power 2", rf__ex_num(c, fade));
    if (l->kind == RF_LIGHT_DIRECTIONAL)
        rf__ex_printf(c, " parallel point_at <%s>", rf__ex_vec(c, centre, ", "));
    if (l->kind == RF_LIGHT_SPOT)
        rf__ex_printf(c, "\n  spotlight point_at <%s> radius %s falloff %s tightness %s",
                      rf__ex_vec(c, rf_vec3_add(pos, l->direction), ", "), rf__ex_num(c, l->spot_cutoff),
                      rf__ex_num(c, l->spot_cutoff), rf__ex_num(c, l->spot_exponent));
    rf__ex_printf(c, " }\n");
}

/* What the primitives share in their notes: each is noted once with a count and the first place. */
typedef struct {
    size_t glass; /* transmitting non-spheres under opaque shadows */
    RfSrcLoc first_glass;
    int smooth_noted;
} PovTally;

/* "  matrix <...>": POV-Ray's form of the affine placement m (it multiplies a point as a row vector,
 * so its rows are m's columns, the translation last) */
static void pov_matrix(RfExCtx *c, const RfMat4 *m)
{
    RfVec3 col[4];
    for (int k = 0; k < 4; k++)
        col[k] = rf_vec3(m->m[0][k], m->m[1][k], m->m[2][k]);
    rf__ex_printf(c, "  matrix <%s,  %s,  %s,  %s>\n", rf__ex_vec(c, col[0], ", "), rf__ex_vec(c, col[1], ", "),
                  rf__ex_vec(c, col[2], ", "), rf__ex_vec(c, col[3], ", "));
}

static void write_prim(RfExCtx *c, const RfPrimitive *world, PovTally *t)
{
    const RfScene *s = c->s;
    const RfInstance *placement;
    const RfPrimitive *p = rf__ex_world_prim(s, world, &placement);
    if (!p)
        return;
    const RfMaterial *m = &s->materials[p->material];
    int smooth = (p->flags & RF_PRIM_VERTEX_NORMALS) && (m->flags & RF_MAT_SMOOTH);
    switch (p->type) {
    case RF_PRIM_SPHERE:
        if ((p->flags & RF_PRIM_INSIDE) && !c->o->two_sided)
            rf__ex_note(c, p->loc, 1, "inside-only sphere: POV-Ray's sphere is seen from outside too");
        rf__ex_printf(c, "sphere { <%s>, %s\n", rf__ex_vec(c, p->u.sphere.center, ", "),
                      rf__ex_num(c, p->u.sphere.radius));
        break;
    case RF_PRIM_PLANE:
        rf__ex_printf(c, "plane { <%s>, %s\n", rf__ex_vec(c, p->u.plane.normal, ", "),
                      rf__ex_num(c, p->u.plane.offset));
        break;
    case RF_PRIM_CONE:
        rf__ex_printf(c, "cone { <%s>, %s, <%s>, %s open\n", rf__ex_vec(c, p->u.cone.base, ", "),
                      rf__ex_num(c, p->u.cone.base_radius), rf__ex_vec(c, p->u.cone.apex, ", "),
                      rf__ex_num(c, p->u.cone.apex_radius));
        break;
    case RF_PRIM_TRIANGLE:
    case RF_PRIM_POLYGON: {
        const RfVec3 *v = s->vertices + p->u.poly.first;
        int n = p->u.poly.count;
        if (smooth) {
            if (!t->smooth_noted) /* once: the SPD teapot has thousands */
                rf__ex_note(c, p->loc, 0, "%s with vertex normals (the first here), written as smooth_triangle: "
                            "where a shadow or mirror ray leaves a smoothed surface on the wrong side of its "
                            "geometric one, each renderer has its own rule (docs/crosscheck.md)",
                            rf_prim_type_name(p->type));
            t->smooth_noted = 1;
            /* standalone triangles: POV-Ray drops a degenerate one with a warning, where an empty
             * mesh would be a parse error */
            const RfVec3 *nv = s->normals + p->u.poly.nfirst;
            for (int k = 1; k + 1 < n; k++) /* the last one is closed below, as every object */
                rf__ex_printf(c, "smooth_triangle { <%s>, <%s>, <%s>, <%s>, <%s>, <%s>\n%s", rf__ex_vec(c, v[0], ", "),
                              rf__ex_vec(c, nv[0], ", "), rf__ex_vec(c, v[k], ", "), rf__ex_vec(c, nv[k], ", "),
                              rf__ex_vec(c, v[k + 1], ", "), rf__ex_vec(c, nv[k + 1], ", "),
                              k + 2 < n ? material_ref(c, p->material) : "");
        } else if (n == 3) {
            rf__ex_printf(c, "triangle { <%s>, <%s>, <%s>\n", rf__ex_vec(c, v[0], ", "), rf__ex_vec(c, v[1], ", "),
                          rf__ex_vec(c, v[2], ", "));
        } else { /* POV-Ray closes a polygon by repeating its first vertex */
            rf__ex_printf(c, "polygon { %d", n + 1);
            for (int k = 0; k <= n; k++)
                rf__ex_printf(c, ",%s<%s>", k % 3 == 2 ? "\n  " : " ", rf__ex_vec(c, v[k % n], ", "));
            rf__ex_printf(c, "\n");
        }
        break;
    }
    case RF_PRIM_INSTANCE: /* flattened away */
    case RF_PRIM_TYPE_COUNT:
        return;
    }
    if (placement) /* an ellipsoid or a sheared cone: the quadric in its object's space, placed */
        pov_matrix(c, &placement->to_world);
    rf__ex_printf(c, "%s", material_ref(c, p->material));
    if (p->type == RF_PRIM_SPHERE && positive_kt(m) && !c->filtered && !placement)
        opaque_shadow_discs(c, p);
    else if (positive_kt(m) && !c->filtered && !t->glass++)
        t->first_glass = p->loc;
}

void rf__export_pov(RfExCtx *c)
{
    const RfScene *s = c->s;
    RfVec3 centre;
    double extent = scene_extent(s, &centre);
    /* POV-Ray's fade is 2 / (1 + (d/fd)^2): with the colour I / (2 fd^2) a light gives
     * I / (d^2 + fd^2), which is I / d^2 to a relative fd^2/d^2 */
    double fade = 1e-5 * extent;
    rf__ex_common_checks(c, 0, 0);
    rf__ex_check_hither(c);
    rf__ex_common_header(c, "// ");
    rf__ex_printf(c, "// POV-Ray: right-handed by explicit vectors: direction = the view axis times d plus the window's\n"
                     "//   centre, right = (r - l) u, up = (t - b) v (u = up x w, v = w x u, w = eye - target, unit);\n"
                     "//   POV-Ray shoots through pixel centres like refray at 1 sample (render it with -A)\n"
                     "// materials: pigment kd with diffuse 1 (refray's kd I cos(theta)); phong ks phong_size n (the same\n"
                     "//   (r.v)^n); reflection kr, with Fresnel `reflection { 0, kr fresnel on }`; glass: filter kt with\n"
                     "//   conserve_energy (transmitted kt (1 - F)) and interior ior\n"
                     "// lights: no falloff as they are; inverse-square by POV-Ray's fade: colour I / (2 fd^2) with\n"
                     "//   fade_distance fd = %s fade_power 2 gives I / (d^2 + fd^2); spot: radius = falloff = cutoff,\n"
                     "//   tightness = exponent (cos^n inside the cone, 0 outside); directional: parallel\n"
                     "// linear light (assumed_gamma 1; write EXR: +FE), adc_bailout = refray's threshold (0 unless the\n"
                     "//   scene sets one: POV-Ray's default 1/255 cuts rays refray traces), max_trace_level = refray's depth\n",
                  rf__ex_num(c, fade));
    rf__ex_printf(c, "// resolution %d %d\n#version 3.7;\n", c->width, c->height);
    rf__ex_printf(c, "global_settings { assumed_gamma 1.0 max_trace_level %d adc_bailout %s ambient_light 0 }\n",
                  c->depth, rf__ex_num(c, s->render.min_contribution));
    rf__ex_printf(c, "background { rgb <%s> }\n", rf__ex_rgb(c, s->render.background, ", "));
    RfWindow w = c->win;
    RfVec3 dir = rf_vec3_add(rf_vec3_scale(c->w, -w.d),
                             rf_vec3_add(rf_vec3_scale(c->u, 0.5 * (w.l + w.r)), rf_vec3_scale(c->v, 0.5 * (w.b + w.t))));
    rf__ex_printf(c, "camera { perspective location <%s>\n  direction <%s>\n  right <%s>\n  up <%s> }\n",
                  rf__ex_vec(c, s->camera.eye, ", "), rf__ex_vec(c, dir, ", "),
                  rf__ex_vec(c, rf_vec3_scale(c->u, w.r - w.l), ", "), rf__ex_vec(c, rf_vec3_scale(c->v, w.t - w.b), ", "));
    for (size_t i = 0; i < s->light_count; i++)
        write_light(c, &s->lights[i], fade, centre, extent);
    unsigned char *used = rf__ex_used_materials(c);
    if (!used)
        return;
    for (size_t i = 0; i < s->material_count; i++)
        if (used[i])
            write_material(c, &s->materials[i], i);
    free(used);
    PovTally t;
    memset(&t, 0, sizeof t);
    for (size_t i = 0; i < s->prim_count; i++)
        write_prim(c, &s->prims[i], &t);
    rf__ex_note_one_sided(c, "shades it");
    if (t.glass)
        rf__ex_note(c, t.first_glass, 1, "%zu transmitting primitives other than spheres (the first here): POV-Ray "
                    "lets shadow rays through them, refray's shadows of transmitting objects are opaque (only "
                    "spheres get a shadow disc; compare with refray --shadows filtered)", t.glass);
}
