/* refray export --mitsuba: the scene as a Mitsuba 3 XML file (scene version 3.0.0), its
 * triangles and polygons in OBJ files beside it (Mitsuba's XML has no inline meshes), for the
 * `path` integrator in an RGB variant. docs/crosscheck.md derives the conversions. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "export_internal.h"
#include "refray/geometry.h"

/* refray's kd I cos(theta) / d^2 is Mitsuba's (rho / pi) I' cos(theta) / d^2 with rho = kd and
 * I' = pi I: every light is scaled by pi (the background, seen only, is not) */
#define MI_LIGHT_SCALE 3.14159265358979323846

static int positive(RfRgb c) { return c.r > 0.0 || c.g > 0.0 || c.b > 0.0; }

/* The BSDF of material `index`, with id "m<index>" (two-sided: "m<index>t"); what it cannot
 * represent is noted and the nearest BSDF written. */
static void write_bsdf(RfExCtx *c, size_t index, int two_sided)
{
    const RfMaterial *m = &c->s->materials[index];
    RfExMat x = rf__ex_classify(c->s, m);
    if (x.highlight)
        rf__ex_note(c, m->loc, 1, "material '%s': Phong highlight ks (%s) shininess %s: Mitsuba 3 has no Phong "
                    "lobe (dropped)", m->name, rf__ex_rgb(c, m->ks, " "), rf__ex_num(c, m->shininess));
    if (x.transmits && !x.fresnel)
        rf__ex_note(c, m->loc, 1, "material '%s': kt without `fresnel`: Mitsuba's dielectric always weights by "
                    "the Fresnel term (written with it)", m->name);
    if (x.transmits && x.diffuse)
        rf__ex_note(c, m->loc, 1, "material '%s': diffuse and transmitting at once: no Mitsuba BSDF adds a "
                    "dielectric to a diffuse one (the diffuse part dropped)", m->name);
    int dielectric = x.transmits || x.fresnel;
    int blend = x.diffuse && (x.mirror || dielectric) && !x.transmits;
    int wrap = two_sided && !dielectric;
    char id[64];
    snprintf(id, sizeof id, " id=\"m%zu%s\"", index, two_sided ? "t" : "");
    rf__ex_printf(c, "  <!-- material '%s' -->\n", m->name);
    if (wrap)
        rf__ex_printf(c, "  <bsdf type=\"twosided\"%s>\n", id);
    const char *inner_id = wrap ? "" : id;
    /* a blend is (1 - w) A + w B: w = 1/2 with doubled coefficients adds kd-diffuse and kr-mirror */
    double k = blend ? 2.0 : 1.0;
    if (blend)
        rf__ex_printf(c, "  <bsdf type=\"blendbsdf\"%s><float name=\"weight\" value=\"0.5\"/>\n", inner_id);
    const char *part_id = blend ? "" : inner_id;
    if (blend || (!dielectric && !x.mirror))
        rf__ex_printf(c, "    <bsdf type=\"diffuse\"%s><rgb name=\"reflectance\" value=\"%s\"/></bsdf>\n", part_id,
                      rf__ex_rgb(c, rf_rgb_scale(m->kd, k), ", "));
    if (dielectric)
        rf__ex_printf(c, "    <bsdf type=\"dielectric\"%s><float name=\"int_ior\" value=\"%s\"/> <float name=\"ext_ior\" "
                      "value=\"1\"/>\n      <rgb name=\"specular_reflectance\" value=\"%s\"/> <rgb "
                      "name=\"specular_transmittance\" value=\"%s\"/></bsdf>\n", part_id, rf__ex_num(c, m->ior),
                      rf__ex_rgb(c, rf_rgb_scale(m->kr, k), ", "), rf__ex_rgb(c, m->kt, ", "));
    else if (x.mirror)
        rf__ex_printf(c, "    <bsdf type=\"conductor\"%s><string name=\"material\" value=\"none\"/> <rgb "
                      "name=\"specular_reflectance\" value=\"%s\"/></bsdf>\n", part_id,
                      rf__ex_rgb(c, rf_rgb_scale(m->kr, k), ", "));
    if (blend)
        rf__ex_printf(c, "  </bsdf>\n");
    if (wrap)
        rf__ex_printf(c, "  </bsdf>\n");
}

static void write_matrix(RfExCtx *c, RfVec3 x, RfVec3 y, RfVec3 z, RfVec3 t)
{
    rf__ex_printf(c, "    <transform name=\"to_world\"><matrix value=\"%s %s %s %s  %s %s %s %s  %s %s %s %s  0 0 0 1\"/>"
                  "</transform>\n", rf__ex_num(c, x.x), rf__ex_num(c, y.x), rf__ex_num(c, z.x), rf__ex_num(c, t.x),
                  rf__ex_num(c, x.y), rf__ex_num(c, y.y), rf__ex_num(c, z.y), rf__ex_num(c, t.y), rf__ex_num(c, x.z),
                  rf__ex_num(c, y.z), rf__ex_num(c, z.z), rf__ex_num(c, t.z));
}

static void write_light(RfExCtx *c, const RfLight *l)
{
    RfRgb i = rf_rgb_scale(l->intensity, MI_LIGHT_SCALE);
    switch (l->kind) {
    case RF_LIGHT_POINT:
        rf__ex_printf(c, "  <emitter type=\"point\"><point name=\"position\" value=\"%s\"/> <rgb name=\"intensity\" "
                      "value=\"%s\"/></emitter>\n", rf__ex_vec(c, l->position, ", "), rf__ex_rgb(c, i, ", "));
        return;
    case RF_LIGHT_DIRECTIONAL:
        rf__ex_printf(c, "  <emitter type=\"directional\"><vector name=\"direction\" value=\"%s\"/> <rgb "
                      "name=\"irradiance\" value=\"%s\"/></emitter>\n", rf__ex_vec(c, l->direction, ", "),
                      rf__ex_rgb(c, i, ", "));
        return;
    case RF_LIGHT_SPOT:
        rf__ex_printf(c, "  <emitter type=\"spot\">\n");
        write_matrix(c, rf_vec3_cross(rf__ex_perpendicular(l->direction), l->direction),
                     rf__ex_perpendicular(l->direction), l->direction, l->position);
        /* beam_width = cutoff_angle: no fade, a hard edge as refray's */
        rf__ex_printf(c, "    <rgb name=\"intensity\" value=\"%s\"/> <float name=\"cutoff_angle\" value=\"%s\"/> "
                      "<float name=\"beam_width\" value=\"%s\"/>\n  </emitter>\n", rf__ex_rgb(c, i, ", "),
                      rf__ex_num(c, l->spot_cutoff), rf__ex_num(c, l->spot_cutoff));
        return;
    case RF_LIGHT_RECT: case RF_LIGHT_DISC: case RF_LIGHT_SPHERE: {
        /* depth 1 is written for the `direct` integrator, which hides the emitter from the camera */
        rf__ex_note(c, l->loc, c->depth > 1, "%s area light: Mitsuba's area emitter is a shape that blocks shadow "
                    "rays%s; refray's is seen by no ray and blocks nothing", rf_light_kind_name(l->kind),
                    c->depth > 1 ? " and is seen by camera and mirror rays (the path integrator of Mitsuba 3.5.2 "
                                   "ignores hide_emitters)" : "");
        if (l->two_sided)
            rf__ex_note(c, l->loc, 1, "two-sided %s light: Mitsuba's area emitters emit from the front only",
                        rf_light_kind_name(l->kind));
        RfVec3 n = l->direction;
        if (l->kind == RF_LIGHT_SPHERE) {
            rf__ex_printf(c, "  <shape type=\"sphere\"><point name=\"center\" value=\"%s\"/> <float name=\"radius\" "
                          "value=\"%s\"/>\n", rf__ex_vec(c, l->position, ", "), rf__ex_num(c, l->radius));
        } else if (l->kind == RF_LIGHT_RECT) {
            rf__ex_printf(c, "  <shape type=\"rectangle\">\n");
            write_matrix(c, rf_vec3_scale(l->edge1, 0.5), rf_vec3_scale(l->edge2, 0.5), n,
                         rf_vec3_add(l->position, rf_vec3_scale(rf_vec3_add(l->edge1, l->edge2), 0.5)));
        } else {
            RfVec3 a = rf__ex_perpendicular(n), b = rf_vec3_cross(n, a);
            rf__ex_printf(c, "  <shape type=\"disk\">\n");
            write_matrix(c, rf_vec3_scale(a, l->radius), rf_vec3_scale(b, l->radius), n, l->position);
        }
        rf__ex_printf(c, "    <bsdf type=\"diffuse\"><rgb name=\"reflectance\" value=\"0\"/></bsdf>\n"
                      "    <emitter type=\"area\"><rgb name=\"radiance\" value=\"%s\"/></emitter>\n  </shape>\n",
                      rf__ex_rgb(c, i, ", "));
        return;
    }
    case RF_LIGHT_KIND_COUNT:
        return;
    }
}

/* The BSDF reference of a primitive. */
static void bsdf_ref(RfExCtx *c, const RfPrimitive *p)
{
    rf__ex_printf(c, "    <ref id=\"m%d%s\"/>\n", p->material, (p->flags & RF_PRIM_TWO_SIDED) || c->o->two_sided ? "t" : "");
}

static int is_mesh(const RfPrimitive *p) { return p->type == RF_PRIM_TRIANGLE || p->type == RF_PRIM_POLYGON; }
static int smooth_of(const RfScene *s, const RfPrimitive *p)
{
    return (p->flags & RF_PRIM_VERTEX_NORMALS) && (s->materials[p->material].flags & RF_MAT_SMOOTH);
}
static int sided_of(const RfExCtx *c, const RfPrimitive *p)
{
    return (p->flags & RF_PRIM_TWO_SIDED) || c->o->two_sided;
}

/* The path of an OBJ beside the XML, OUT-<kind><index>.obj, and its name as the XML refers to it
 * (without the folder). */
static void obj_path(RfExCtx *c, const char *kind, int index, char *path, size_t pathsz, char *base, size_t basesz)
{
    const char *out = c->o->output ? c->o->output : "scene.xml";
    const char *dot = strrchr(out, '.'), *slash = strrchr(out, '/');
    int stem = dot && (!slash || dot > slash) ? (int)(dot - out) : (int)strlen(out);
    snprintf(path, pathsz, "%.*s-%s%d.obj", stem, out, kind, index);
    snprintf(base, basesz, "%s", slash ? strrchr(path, '/') + 1 : path);
}

/* The triangles and polygons of one (material, sidedness, smoothness) as an OBJ file; its
 * <shape> goes into the XML (file 0). */
static void write_mesh(RfExCtx *c, size_t first, int index)
{
    const RfScene *s = c->s;
    const RfPrimitive *p0 = &s->prims[first];
    int smooth = smooth_of(s, p0), sided = sided_of(c, p0);
    char path[4096], base[4096];
    obj_path(c, "mesh", index, path, sizeof path, base, sizeof base);
    rf__ex_printf(c, "  <shape type=\"obj\"><string name=\"filename\" value=\"%s\"/> <boolean name=\"face_normals\" "
                  "value=\"%s\"/>\n", base, smooth ? "false" : "true");
    bsdf_ref(c, p0);
    rf__ex_printf(c, "  </shape>\n");
    RfExportFile *xml_index = c->out;
    size_t xml_at = (size_t)(xml_index - c->ex->files);
    if (!rf__ex_file(c, path))
        return;
    rf__ex_printf(c, "# %s: the %s triangles of material '%s' (refray export --mitsuba)\n", base,
                  smooth ? "smooth" : "flat", s->materials[p0->material].name);
    size_t nv = 0;
    int *tri = NULL;
    int tri_cap = 0;
    for (size_t i = first; i < s->prim_count; i++) {
        const RfPrimitive *p = &s->prims[i];
        if ((p->flags & RF_PRIM_IN_OBJECT) || !is_mesh(p) || p->material != p0->material ||
            smooth_of(s, p) != smooth || sided_of(c, p) != sided)
            continue;
        int n = p->u.poly.count;
        const RfVec3 *v = s->vertices + p->u.poly.first;
        for (int k = 0; k < n; k++)
            rf__ex_printf(c, "v %s\n", rf__ex_vec(c, v[k], " "));
        if (smooth)
            for (int k = 0; k < n; k++)
                rf__ex_printf(c, "vn %s\n", rf__ex_vec(c, s->normals[p->u.poly.nfirst + k], " "));
        if (3 * (n - 2) > tri_cap) {
            int *t = realloc(tri, sizeof *t * (size_t)(3 * (n - 2)));
            if (!t) {
                c->ex->failed = 1;
                break;
            }
            tri = t;
            tri_cap = 3 * (n - 2);
        }
        /* refray fans convex polygons and ear-clips the others: the same surface */
        int nt = (p->flags & RF_PRIM_NONCONVEX) ? rf_triangulate_polygon(v, n, tri) : n - 2;
        if (nt < 0) {
            c->ex->failed = 1;
            break;
        }
        for (int t = 0; t < nt; t++) {
            int a = (p->flags & RF_PRIM_NONCONVEX) ? tri[3 * t] : 0, b = (p->flags & RF_PRIM_NONCONVEX) ? tri[3 * t + 1] : t + 1,
                d = (p->flags & RF_PRIM_NONCONVEX) ? tri[3 * t + 2] : t + 2;
            size_t ia = nv + (size_t)a + 1, ib = nv + (size_t)b + 1, id = nv + (size_t)d + 1;
            if (smooth)
                rf__ex_printf(c, "f %zu//%zu %zu//%zu %zu//%zu\n", ia, ia, ib, ib, id, id);
            else
                rf__ex_printf(c, "f %zu %zu %zu\n", ia, ib, id);
        }
        nv += (size_t)n;
    }
    free(tri);
    c->out = c->ex->files + xml_at;
}

/* A point of a sphere's or cone's surface at (u, v) in [0, 1]^2 (around, along), in its object's
 * space, and the outward normal there (not unit). */
static void quadric_at(const RfPrimitive *p, double u, double v, RfVec3 *x, RfVec3 *n)
{
    double phi = 2.0 * RF_PI * u;
    if (p->type == RF_PRIM_SPHERE) { /* the poles exact, so that their triangles are exactly degenerate */
        double theta = RF_PI * v, st = v == 0.0 || v == 1.0 ? 0.0 : sin(theta), ct = v == 0.0 ? 1.0 : v == 1.0 ? -1.0 : cos(theta);
        *n = rf_vec3(st * cos(phi), ct, st * sin(phi));
        *x = rf_vec3_add(p->u.sphere.center, rf_vec3_scale(*n, p->u.sphere.radius));
        return;
    }
    const RfCone *k = &p->u.cone;
    RfVec3 ax = rf_vec3_sub(k->apex, k->base);
    double len = rf_vec3_length(ax), r = k->base_radius + v * (k->apex_radius - k->base_radius);
    RfVec3 z = rf_vec3_scale(ax, 1.0 / len), xa = rf__ex_perpendicular(z), ya = rf_vec3_cross(z, xa);
    RfVec3 radial = rf_vec3_add(rf_vec3_scale(xa, cos(phi)), rf_vec3_scale(ya, sin(phi)));
    *x = rf_vec3_add(rf_vec3_add(k->base, rf_vec3_scale(ax, v)), rf_vec3_scale(radial, r));
    *n = rf_vec3_sub(rf_vec3_scale(radial, len), rf_vec3_scale(z, k->apex_radius - k->base_radius));
}

/* A sphere or cone under a non-similarity transform: Mitsuba's sphere and cylinder take neither
 * a non-uniform scale nor a shear, so the nearest thing (--lossy) is a mesh of the placed
 * surface, OUT-placedK.obj, with its exact normals at the vertices. */
static void write_placed(RfExCtx *c, const RfPrimitive *p, const RfInstance *in, int index)
{
    enum { AROUND = 96, ALONG = 48 };
    int along = p->type == RF_PRIM_SPHERE ? ALONG : 1; /* a cone is straight along its axis */
    rf__ex_note(c, p->loc, 1, "%s under a non-similarity transform: Mitsuba's %s takes no non-uniform scale or "
                "shear (%s)", rf_prim_type_name(p->type), p->type == RF_PRIM_SPHERE ? "sphere" : "cylinder",
                c->o->lossy ? "written as a mesh of its surface" : "refused");
    if (!c->o->lossy)
        return;
    int nv = (AROUND + 1) * (along + 1);
    RfVec3 *x = malloc(2 * sizeof *x * (size_t)nv), *n = x + nv;
    if (!x) {
        c->ex->failed = 1;
        return;
    }
    for (int j = 0; j <= along; j++)
        for (int i = 0; i <= AROUND; i++) {
            int k = j * (AROUND + 1) + i;
            quadric_at(p, (double)i / AROUND, (double)j / along, &x[k], &n[k]);
            rf_transform_point(in->to_world, x[k], &x[k]);
            n[k] = rf_vec3_normalize(rf_mat3_mul_vec(in->normal_to_world, n[k])); /* §4.9 */
        }
    char path[4096], base[4096];
    obj_path(c, "placed", index, path, sizeof path, base, sizeof base);
    rf__ex_printf(c, "  <shape type=\"obj\"><string name=\"filename\" value=\"%s\"/> <boolean name=\"face_normals\" "
                  "value=\"false\"/>\n", base);
    bsdf_ref(c, p);
    rf__ex_printf(c, "  </shape>\n");
    size_t xml_at = (size_t)(c->out - c->ex->files);
    if (rf__ex_file(c, path)) {
        rf__ex_printf(c, "# %s: the %s of line %d under its placement, %d x %d quads (refray export --mitsuba --lossy)\n",
                      base, rf_prim_type_name(p->type), p->loc.line, AROUND, along);
        for (int k = 0; k < nv; k++)
            rf__ex_printf(c, "v %s\nvn %s\n", rf__ex_vec(c, x[k], " "), rf__ex_vec(c, n[k], " "));
        /* each triangle wound around the surface's outward normal (a mirroring placement reverses
         * the grid's order); the degenerate ones at a sphere's poles are left out */
        for (int j = 0; j < along; j++)
            for (int i = 0; i < AROUND; i++)
                for (int h = 0; h < 2; h++) {
                    int a = j * (AROUND + 1) + i;
                    int q[3] = {a, h ? a + AROUND + 2 : a + 1, h ? a + AROUND + 1 : a + AROUND + 2};
                    RfVec3 g = rf_vec3_cross(rf_vec3_sub(x[q[1]], x[q[0]]), rf_vec3_sub(x[q[2]], x[q[0]]));
                    if (!(rf_vec3_dot(g, g) > 0.0))
                        continue;
                    if (rf_vec3_dot(g, rf_vec3_add(n[q[0]], rf_vec3_add(n[q[1]], n[q[2]]))) < 0.0) {
                        int t = q[1];
                        q[1] = q[2];
                        q[2] = t;
                    }
                    rf__ex_printf(c, "f %d//%d %d//%d %d//%d\n", q[0] + 1, q[0] + 1, q[1] + 1, q[1] + 1, q[2] + 1,
                                  q[2] + 1);
                }
        c->out = c->ex->files + xml_at;
    }
    free(x);
}

static void write_shape(RfExCtx *c, const RfPrimitive *world, double plane_size, int *placed)
{
    const RfScene *s = c->s;
    const RfInstance *placement;
    const RfPrimitive *p = rf__ex_world_prim(s, world, &placement);
    if (!p)
        return;
    if (placement) {
        write_placed(c, p, placement, (*placed)++);
        return;
    }
    if (p->type == RF_PRIM_SPHERE) {
        rf__ex_printf(c, "  <shape type=\"sphere\"><point name=\"center\" value=\"%s\"/> <float name=\"radius\" "
                      "value=\"%s\"/>%s\n", rf__ex_vec(c, p->u.sphere.center, ", "), rf__ex_num(c, p->u.sphere.radius),
                      (p->flags & RF_PRIM_INSIDE) ? " <boolean name=\"flip_normals\" value=\"true\"/>" : "");
        if ((p->flags & RF_PRIM_INSIDE) && !c->o->two_sided)
            rf__ex_note(c, p->loc, 1, "inside-only sphere: Mitsuba's sphere blocks rays from outside too");
    } else if (p->type == RF_PRIM_PLANE) {
        RfVec3 n = p->u.plane.normal, a = rf__ex_perpendicular(n), b = rf_vec3_cross(n, a);
        rf__ex_printf(c, "  <shape type=\"rectangle\">  <!-- the plane of line %d as a square of side %s -->\n",
                      p->loc.line, rf__ex_num(c, 2.0 * plane_size));
        write_matrix(c, rf_vec3_scale(a, plane_size), rf_vec3_scale(b, plane_size), n,
                     rf_vec3_scale(n, p->u.plane.offset));
        rf__ex_note(c, p->loc, 0, "infinite plane written as a square of side %s (Mitsuba has no infinite plane): "
                    "its horizon differs", rf__ex_num(c, 2.0 * plane_size));
    } else if (p->type == RF_PRIM_CONE) {
        const RfCone *k = &p->u.cone;
        if (k->base_radius != k->apex_radius) {
            rf__ex_note(c, p->loc, 1, "cone with radii %s and %s: Mitsuba has only cylinders (%s)",
                        rf__ex_num(c, k->base_radius), rf__ex_num(c, k->apex_radius),
                        c->o->lossy ? "written with their mean radius" : "refused");
        }
        rf__ex_printf(c, "  <shape type=\"cylinder\"><point name=\"p0\" value=\"%s\"/> <point name=\"p1\" value=\"%s\"/> "
                      "<float name=\"radius\" value=\"%s\"/>%s\n", rf__ex_vec(c, k->base, ", "), rf__ex_vec(c, k->apex, ", "),
                      rf__ex_num(c, 0.5 * (k->base_radius + k->apex_radius)),
                      (p->flags & RF_PRIM_INSIDE) ? " <boolean name=\"flip_normals\" value=\"true\"/>" : "");
    } else {
        return;
    }
    bsdf_ref(c, p);
    rf__ex_printf(c, "  </shape>\n");
    (void)s;
}

void rf__export_mitsuba(RfExCtx *c)
{
    const RfScene *s = c->s;
    RfWindow w = c->win;
    rf__ex_common_checks(c, 1, 1);
    RfVec3 lo, hi;
    double extent = rf_scene_bounds(s, &lo, &hi) ? rf_vec3_length(rf_vec3_sub(hi, lo)) : 1.0;
    extent = fmax(extent, rf_vec3_length(rf_vec3_sub(s->camera.eye, s->camera.target)));
    double tol = 1e-12 * (fabs(w.r) + fabs(w.t));
    if (fabs(w.l + w.r) > tol || fabs(w.b + w.t) > tol)
        rf__ex_note(c, s->camera.loc, 1, "camera: off-centre window (l %s r %s b %s t %s): Mitsuba's perspective "
                    "camera is centred (written centred)", rf__ex_num(c, w.l), rf__ex_num(c, w.r), rf__ex_num(c, w.b),
                    rf__ex_num(c, w.t));
    if (fabs((w.r - w.l) * c->height - (w.t - w.b) * c->width) > 1e-9 * (w.r - w.l) * c->height)
        rf__ex_note(c, s->camera.loc, 1, "camera: the window's aspect differs from the image's (pixels not square): "
                    "Mitsuba's pixels are square (written with the vertical field of view)");
    int area = 0;
    for (size_t i = 0; i < s->light_count; i++)
        area |= rf_light_is_area(s->lights[i].kind);
    int diffuse = 0;
    for (size_t i = 0; i < s->material_count; i++)
        diffuse |= rf__ex_classify(s, &s->materials[i]).diffuse;
    if (positive(s->render.background) && diffuse)
        rf__ex_note(c, s->camera.loc, 1, "background %s: Mitsuba's constant emitter also lights the diffuse "
                    "surfaces, refray's background is only seen", rf__ex_rgb(c, s->render.background, " "));
    rf__ex_printf(c, "<?xml version=\"1.0\" encoding=\"utf-8\"?>\n<!--\n");
    size_t head = c->out->len;
    rf__ex_common_header(c, "  ");
    rf__ex_printf(c,
                  "  Mitsuba 3 (an RGB variant, e.g. scalar_rgb) with the `path` integrator:\n"
                  "  - diffuse: refray's kd I cos(theta) / d^2 (no 1/pi) is Mitsuba's (rho/pi) I' cos(theta) / d^2 with\n"
                  "    reflectance rho = kd and every light's intensity, irradiance or radiance I' = pi I\n"
                  "  - mirror (kr, no Fresnel): conductor `none` with specular_reflectance kr; kd and kr together:\n"
                  "    blendbsdf weight 1/2 of diffuse 2 kd and conductor 2 kr (= their sum)\n"
                  "  - glass (kt with `fresnel`; kr alone with `fresnel`): dielectric, int_ior = ior, specular_reflectance\n"
                  "    kr, specular_transmittance kt: F kr and (1 - F) kt as refray; Mitsuba scales the radiance by\n"
                  "    (eta_t/eta_i)^2 at each refraction, which cancels for light that enters and leaves a closed object\n"
                  "  - spot: cutoff_angle = beam_width = refray's cutoff (a hard edge; only exponent 0 is exact)\n"
                  "  - depth 1 (no secondary rays): the `direct` integrator (light and BSDF samples with MIS at the\n"
                  "    first hit: direct light only, emitters hidden from the camera)\n"
                  "  - max_depth = refray's depth + 1: Mitsuba samples the lights at every hit but the last, so the\n"
                  "    light at the hits 1 .. depth is counted, as refray's shadow rays. Mitsuba's path tracer also\n"
                  "    carries light from diffuse surface to diffuse surface (directly or via mirrors and glass),\n"
                  "    which a Whitted tracer does not: the images agree only where no such path fits in max_depth\n"
                  "  - point lights cannot be hit by sampled rays, so they make no caustics; shadow rays are blocked\n"
                  "    by glass in both renderers\n"
                  "  - film: box filter of one pixel (refray's box), independent sampler; sensor's near_clip = hither\n");
    /* "--" may not appear inside an XML comment */
    for (size_t i = head; i + 1 < c->out->len; i++)
        if (c->out->text[i] == '-' && c->out->text[i + 1] == '-')
            c->out->text[i + 1] = ' ', i++;
    rf__ex_printf(c, "-->\n<scene version=\"3.0.0\">\n");
    if (c->depth == 1) /* direct light only; unlike `path`, `direct` hides area emitters from the camera */
        rf__ex_printf(c, "  <integrator type=\"direct\"><boolean name=\"hide_emitters\" value=\"true\"/></integrator>\n");
    else
        rf__ex_printf(c, "  <integrator type=\"path\"><integer name=\"max_depth\" value=\"%d\"/>%s</integrator>\n",
                      c->depth + 1, area ? " <boolean name=\"hide_emitters\" value=\"true\"/>" : "");
    double fov = 2.0 * atan(0.5 * (w.t - w.b) / w.d) * 180.0 / 3.14159265358979323846;
    int lens = s->camera.aperture > 0.0;
    rf__ex_printf(c, "  <sensor type=\"%s\">\n    <string name=\"fov_axis\" value=\"y\"/> <float name=\"fov\" value=\"%s\"/>\n",
                  lens ? "thinlens" : "perspective", rf__ex_num(c, fov));
    if (lens)
        rf__ex_printf(c, "    <float name=\"aperture_radius\" value=\"%s\"/> <float name=\"focus_distance\" value=\"%s\"/>\n",
                      rf__ex_num(c, s->camera.aperture), rf__ex_num(c, s->camera.focus));
    rf__ex_printf(c, "    <float name=\"near_clip\" value=\"%s\"/> <float name=\"far_clip\" value=\"%s\"/>\n",
                  rf__ex_num(c, s->camera.hither > 0.0 ? s->camera.hither : 1e-6 * extent), rf__ex_num(c, 1e4 * extent));
    rf__ex_printf(c, "    <transform name=\"to_world\"><lookat origin=\"%s\" target=\"%s\" up=\"%s\"/></transform>\n",
                  rf__ex_vec(c, s->camera.eye, ", "), rf__ex_vec(c, s->camera.target, ", "),
                  rf__ex_vec(c, s->camera.up, ", "));
    rf__ex_printf(c, "    <sampler type=\"independent\"><integer name=\"sample_count\" value=\"%d\"/></sampler>\n"
                     "    <film type=\"hdrfilm\"><integer name=\"width\" value=\"%d\"/> <integer name=\"height\" value=\"%d\"/>\n"
                     "      <string name=\"pixel_format\" value=\"rgb\"/> <string name=\"component_format\" value=\"float32\"/>\n"
                     "      <rfilter type=\"box\"/></film>\n  </sensor>\n", c->samples, c->width, c->height);
    if (positive(s->render.background))
        rf__ex_printf(c, "  <emitter type=\"constant\"><rgb name=\"radiance\" value=\"%s\"/></emitter>\n",
                      rf__ex_rgb(c, s->render.background, ", "));
    for (size_t i = 0; i < s->light_count; i++)
        write_light(c, &s->lights[i]);
    /* the BSDFs the primitives use, one-sided and two-sided apart */
    unsigned char *used = rf__ex_used_materials(c);
    if (!used)
        return;
    for (size_t i = 0; i < s->material_count; i++)
        for (int t = 0; t < 2; t++)
            if (used[i] & (1 << t))
                write_bsdf(c, i, t);
    free(used);
    rf__ex_note_one_sided(c, "shows it black and stops rays there");
    double plane_size = 1e3 * extent;
    int meshes = 0, placed = 0, *keys = NULL;
    for (size_t i = 0; i < s->prim_count; i++) {
        const RfPrimitive *p = &s->prims[i];
        if (p->flags & RF_PRIM_IN_OBJECT)
            continue;
        if (!is_mesh(p)) {
            write_shape(c, p, plane_size, &placed);
            continue;
        }
        /* the first primitive of its (material, sides, smoothness) group starts a mesh file */
        int key = (p->material * 2 + sided_of(c, p)) * 2 + smooth_of(s, p), seen = 0;
        for (int g = 0; g < meshes && !seen; g++)
            seen = keys[g] == key;
        if (seen)
            continue;
        int *k2 = realloc(keys, sizeof *k2 * (size_t)(meshes + 1));
        if (!k2) {
            c->ex->failed = 1;
            break;
        }
        keys = k2;
        keys[meshes] = key;
        write_mesh(c, i, meshes++);
    }
    free(keys);
    rf__ex_printf(c, "</scene>\n");
}
