/* `refray info SCENE`: what a scene holds (primitive counts by type, materials, lights, camera,
 * settings, bounds) and the features its renderer needs (rf_scene_features). */
#include <stdio.h>
#include <string.h>

#include "cli.h"
#include "args.h"
#include "exit_codes.h"
#include "refray/render.h"
#include "refray/scene.h"
#include "refray/scene_io.h"

/* Materials and lights listed one per line before "... and N more" (unless --all). */
#define INFO_LIST_MAX 10

enum { OPT_ALL = RF_OPT_ID };

static const RfOpt info_opts[] = {
    {"all", OPT_ALL, NULL, "list every material and light (default: the first 10)", NULL},
    RF_OPT_TABLE_END,
};

static const RfOpt *const info_tables[] = {info_opts, rf_opts_load, NULL};

static const RfCommand info_cmd = {
    "refray info",
    "refray info [options] SCENE\n",
    "Loads SCENE (.nff, .rf, .obj, optionally .gz) and prints its camera, render\n"
    "settings, primitive counts, the scene graph (objects, groups, instances,\n"
    "triangles before and after instancing), materials, lights, bounding box and\n"
    "the features it uses.\n",
    info_tables,
    "exit: 0 ok, 4 the scene cannot be read, 5 usage (README: Exit codes)\n",
};

static void rgb(const char *label, RfRgb c)
{
    printf(" %s (%g, %g, %g)", label, c.r, c.g, c.b);
}

static void vec(const char *label, RfVec3 v)
{
    printf(" %s (%g, %g, %g)", label, v.x, v.y, v.z);
}

static void print_camera(const RfScene *s)
{
    const RfSceneCamera *c = &s->camera;
    RfWindow w = rf_scene_camera_window(c, s->render.width, s->render.height);
    printf("camera   ");
    vec("eye", c->eye);
    vec("target", c->target);
    vec("up", c->up);
    printf("\n         ");
    if (c->has_window)
        printf(" window given");
    else
        printf(" fov %g deg (%s)", c->fov,
               c->fov_reading == RF_FOV_EDGES ? "edge to edge" : "between outer pixel centres");
    printf(", d %g, hither %g\n          window l %.9g r %.9g b %.9g t %.9g\n", c->d, c->hither,
           w.l, w.r, w.b, w.t);
    if (c->aperture > 0.0)
        printf("          thin lens: aperture radius %g, focus %g\n", c->aperture, c->focus);
}

/* Returns the number of planes (unbounded, so left out of the bounds). */
static size_t print_prims(const RfScene *s)
{
    size_t by_type[RF_PRIM_TYPE_COUNT] = {0};
    size_t two_sided = 0, inside = 0, normals = 0, nonconvex = 0;
    for (size_t i = 0; i < s->prim_count; i++) {
        const RfPrimitive *p = &s->prims[i];
        if ((unsigned)p->type < RF_PRIM_TYPE_COUNT)
            by_type[p->type]++;
        two_sided += (p->flags & RF_PRIM_TWO_SIDED) != 0;
        inside += (p->flags & RF_PRIM_INSIDE) != 0;
        normals += (p->flags & RF_PRIM_VERTEX_NORMALS) != 0;
        nonconvex += (p->flags & RF_PRIM_NONCONVEX) != 0;
    }
    printf("primitives %zu:", s->prim_count);
    for (int t = 0; t < RF_PRIM_TYPE_COUNT; t++)
        if (by_type[t])
            printf(" %s %zu", rf_prim_type_name((RfPrimType)t), by_type[t]);
    printf("\n           two-sided %zu, inside-only %zu, with vertex normals %zu, non-convex %zu\n",
           two_sided, inside, normals, nonconvex);
    printf("vertices  %zu (vertex normals %zu)\n", s->vertex_count, s->normal_count);
    return by_type[RF_PRIM_PLANE];
}

/* The scene graph (§4.8): each object with its parts and the objects it places, the world's
 * instances, and the triangles before and after instancing. */
static void print_graph(const RfScene *s, int all)
{
    size_t world_instances = 0;
    for (size_t i = 0; i < s->prim_count; i++)
        world_instances += s->prims[i].type == RF_PRIM_INSTANCE &&
                           !(s->prims[i].flags & RF_PRIM_IN_OBJECT);
    RfTriangleCount tc = rf_scene_triangle_count(s);
    if (s->object_count || s->instance_count) {
        printf("objects   %zu, instances %zu (%zu placed in the world; %zu after expanding groups)",
               s->object_count, s->instance_count, world_instances, tc.instances_rendered);
        if (s->motion_count)
            printf(", %zu moving", s->motion_count);
        printf("\n");
        for (size_t o = 0; o < s->object_count; o++) {
            if (!all && o == INFO_LIST_MAX) {
                printf("          ... and %zu more (--all lists them)\n", s->object_count - o);
                break;
            }
            const RfSceneObject *ob = &s->objects[o];
            size_t inst = 0, tris = 0;
            for (size_t i = ob->first; i < ob->first + ob->count; i++) {
                const RfPrimitive *p = &s->prims[i];
                inst += p->type == RF_PRIM_INSTANCE;
                tris += p->type == RF_PRIM_TRIANGLE ? 1
                        : p->type == RF_PRIM_POLYGON && !(p->flags & RF_PRIM_NONCONVEX)
                            ? (size_t)p->u.poly.count - 2
                            : p->type == RF_PRIM_POLYGON;
            }
            printf("  %-12s %s: %zu primitives (%zu triangles), %zu instances",
                   ob->name, inst ? "group" : "object", ob->count - inst, tris, inst);
            const char *sep = " of";
            for (size_t i = ob->first; i < ob->first + ob->count; i++)
                if (s->prims[i].type == RF_PRIM_INSTANCE) {
                    int c = s->instances[s->prims[i].u.instance].object;
                    printf("%s %s", sep, c >= 0 ? s->objects[c].name : "?");
                    sep = ",";
                }
            printf("\n");
        }
    }
    printf("triangles %zu stored, %zu rendered after instancing\n", tc.stored, tc.rendered);
}

static void print_materials(const RfScene *s, int all)
{
    printf("materials %zu\n", s->material_count);
    for (size_t i = 0; i < s->material_count; i++) {
        if (!all && i == INFO_LIST_MAX) {
            printf("          ... and %zu more (--all lists them)\n", s->material_count - i);
            break;
        }
        const RfMaterial *m = &s->materials[i];
        printf("  %-8s", m->name);
        rgb("ka", m->ka);
        rgb("kd", m->kd);
        rgb("ks", m->ks);
        printf(" n %g", m->shininess);
        rgb("kr", m->kr);
        rgb("kt", m->kt);
        printf(" ior %g", m->ior);
        if (m->emission.r > 0 || m->emission.g > 0 || m->emission.b > 0)
            rgb("emission", m->emission);
        if (m->gloss > 0.0)
            printf(" glossy %g", m->gloss);
        printf("%s%s\n", m->flags & RF_MAT_FRESNEL ? " fresnel" : "",
               m->flags & RF_MAT_SMOOTH ? " smooth" : " flat");
    }
}

static void print_lights(const RfScene *s, int all)
{
    size_t by_kind[RF_LIGHT_KIND_COUNT] = {0};
    for (size_t i = 0; i < s->light_count; i++)
        if ((unsigned)s->lights[i].kind < RF_LIGHT_KIND_COUNT)
            by_kind[s->lights[i].kind]++;
    printf("lights    %zu:", s->light_count);
    for (int k = 0; k < RF_LIGHT_KIND_COUNT; k++)
        if (by_kind[k])
            printf(" %s %zu", rf_light_kind_name((RfLightKind)k), by_kind[k]);
    printf("\n");
    for (size_t i = 0; i < s->light_count; i++) {
        if (!all && i == INFO_LIST_MAX) {
            printf("          ... and %zu more (--all lists them)\n", s->light_count - i);
            break;
        }
        const RfLight *l = &s->lights[i];
        printf("  %-11s", rf_light_kind_name(l->kind));
        if (l->kind != RF_LIGHT_DIRECTIONAL)
            vec("at", l->position);
        if (l->kind != RF_LIGHT_POINT)
            vec(l->kind == RF_LIGHT_SPOT ? "axis" : "direction", l->direction);
        if (l->kind == RF_LIGHT_SPOT)
            printf(" exponent %g cutoff %g deg", l->spot_exponent, l->spot_cutoff);
        if (rf_light_is_area(l->kind)) {
            if (l->kind == RF_LIGHT_RECT) {
                vec("edge1", l->edge1);
                vec("edge2", l->edge2);
            } else {
                printf(" radius %g", l->radius);
            }
            rgb("radiance", l->intensity);
            printf(" area %g, %s, %d sample%s\n", rf_light_area(l),
                   l->kind == RF_LIGHT_SPHERE ? "outward" : l->two_sided ? "two-sided" : "one-sided", l->samples,
                   l->samples == 1 ? "" : "s");
            continue;
        }
        rgb("intensity", l->intensity);
        if (l->kind != RF_LIGHT_DIRECTIONAL)
            printf(" %s", l->falloff == RF_FALLOFF_NONE ? "no falloff" : "inverse-square");
        printf("\n");
    }
}

int rf_cmd_info(int argc, char **argv)
{
    const char *path = NULL;
    int all = 0;
    RfLoadOptions opt = rf_load_options_default();
    RfOptParser p;
    int key;
    rf_opt_init(&p, &info_cmd, argc, argv);
    while ((key = rf_opt_next(&p)) != RF_OPT_DONE) {
        if (key == RF_OPT_EXIT)
            return p.exit_code;
        if (key == OPT_ALL)
            all = 1;
        else if (rf_arg_shared(key, p.value, &opt, NULL) < 0)
            return rf_opt_bad_value(&p);
    }
    int bad = rf_opt_operand(&p, "the scene file", &path);
    if (bad)
        return bad;
    RfScene s;
    char err[512];
    if (rf_scene_load(path, &opt, &s, err, sizeof err) != RF_OK) {
        rf_arg_report("refray info", err);
        return RF_EXIT_FILE;
    }
    const RfRenderSettings *r = &s.render;
    printf("scene     %s (%s)\n", path,
           s.format == RF_FORMAT_NFF ? "NFF" : s.format == RF_FORMAT_OBJ ? "Wavefront OBJ" : "refray format");
    print_camera(&s);
    printf("image     %d x %d, depth %d, threshold %g, %d sample%s per pixel\n", r->width,
           r->height, r->max_depth, r->min_contribution, r->samples, r->samples == 1 ? "" : "s");
    if (r->adaptive)
        printf("          sampler adaptive (threshold %g, depth %d)", r->adaptive_threshold, r->adaptive_depth);
    else
        printf("          sampler %s", rf_sampler_name(r->sampler));
    printf(", filter %s radius %g, shutter %g .. %g\n", rf_filter_name(r->filter.kind), r->filter.radius,
           r->shutter_open, r->shutter_close);
    if (r->shadows == RF_SHADOWS_FILTERED)
        printf("          shadows filtered (by the kt of every surface a shadow ray crosses)\n");
    printf("         ");
    rgb("background", r->background);
    rgb("ambient", r->ambient);
    printf("\n");
    size_t planes = print_prims(&s);
    print_graph(&s, all);
    print_materials(&s, all);
    print_lights(&s, all);
    RfVec3 lo, hi;
    if (rf_scene_bounds(&s, &lo, &hi))
        printf("bounds    (%g, %g, %g) .. (%g, %g, %g)%s\n", lo.x, lo.y, lo.z, hi.x, hi.y, hi.z,
               planes ? " (planes are unbounded, left out)" : "");
    else
        printf("bounds    none (no bounded primitive)\n");
    unsigned f = rf_scene_features(&s);
    printf("features ");
    if (!f)
        printf(" none");
    for (int b = 0; b < RF_FEAT_COUNT; b++)
        if (f & (1u << b))
            printf(" %s", rf_feature_name(1u << b));
    printf("\n");
    /* the render kernel `refray render` would run with its defaults (--kernel general: all parts) */
    RfRenderOptions ro = rf_render_options_default();
    char kname[256];
    printf("kernel    %s\n", rf_kernel_name(rf_render_kernel(&s, &ro), kname, sizeof kname));
    rf_scene_free(&s);
    return 0;
}
