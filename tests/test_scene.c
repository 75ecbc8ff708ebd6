/* Tests of the scene model, the NFF and refray-format readers, the analysis and `refray info`.
 * Paths are relative to the repository root (make test runs there). */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "refray/scene.h"
#include "refray/scene_io.h"
#include "rf_test.h"

#define CHECK_VEC(v, X, Y, Z)                                                                \
    do {                                                                                     \
        RF_CHECK_NEAR((v).x, X, 0, 0);                                                       \
        RF_CHECK_NEAR((v).y, Y, 0, 0);                                                       \
        RF_CHECK_NEAR((v).z, Z, 0, 0);                                                       \
    } while (0)

#define CHECK_RGB(c, R, G, B)                                                                \
    do {                                                                                     \
        RF_CHECK_NEAR((c).r, R, 0, 0);                                                       \
        RF_CHECK_NEAR((c).g, G, 0, 0);                                                       \
        RF_CHECK_NEAR((c).b, B, 0, 0);                                                       \
    } while (0)

static size_t count_type(const RfScene *s, RfPrimType t)
{
    size_t n = 0;
    for (size_t i = 0; i < s->prim_count; i++)
        n += s->prims[i].type == t;
    return n;
}

static size_t count_flag(const RfScene *s, unsigned flag)
{
    size_t n = 0;
    for (size_t i = 0; i < s->prim_count; i++)
        n += (s->prims[i].flags & flag) != 0;
    return n;
}

/* ---- the SPD scenes ------------------------------------------------------------------------ */

/* Counts made independently of the reader, from the shared originals:
 *   awk '$1=="s"{s++} $1=="p"{if($2==3)t++; else p++} $1=="pp"{pp++; if($2==3)t++; else p++}
 *        $1=="c"{c++} $1=="l"{l++}' FILE.nff
 * (every SPD `pp` has 3 vertices; no SPD light has a colour; `p 144` occurs 128 times in
 * gears, its concave gear faces). Cameras: sed -n 3,8p FILE.nff. */
typedef struct {
    const char *path;
    size_t spheres, triangles, polygons, cones, vertex_normal_prims, nonconvex;
    size_t lights;
    double from[3], at[3], up[3], hither;
} SpdCase;

static const SpdCase spd_cases[] = {
    {"scenes/spd/balls-2.nff", 91, 0, 1, 0, 0, 0, 3, {2.1, 1.3, 1.7}, {0, 0, 0}, {0, 0, 1}, 0.01},
    {"scenes/spd/balls.nff", 7381, 0, 1, 0, 0, 0, 3, {2.1, 1.3, 1.7}, {0, 0, 0}, {0, 0, 1}, 0.01},
    {"scenes/spd/gears.nff.gz", 0, 0, 9345, 0, 0, 128, 5, {-1.1, -2.1, 2.6}, {0, 0, 0}, {0, 0, 1}, 1},
    {"scenes/spd/mount.nff", 4, 8192, 0, 0, 0, 0, 1, {-1.6, 1.6, 1.7}, {0, 0, 0}, {0, 0, 1}, 0.01},
    {"scenes/spd/rings.nff", 4200, 0, 1, 4200, 0, 0, 3, {-1, -2.61313, 0.5}, {-1, -1.61313, 0.5},
     {0, 0, 1}, 1},
    {"scenes/spd/teapot-2.nff", 0, 240, 4, 0, 240, 0, 2, {4.86, 7.2, 5.4}, {0, 0, 0}, {0, 0, 1}, 1},
    {"scenes/spd/teapot.nff", 0, 2256, 36, 0, 2256, 0, 2, {4.86, 7.2, 5.4}, {0, 0, 0}, {0, 0, 1}, 1},
    {"scenes/spd/tetra.nff", 0, 4096, 0, 0, 0, 0, 1, {1.02285, -3.17715, -2.17451},
     {-0.004103, -0.004103, 0.216539}, {-0.816497, -0.816497, 0.816497}, 1},
    {"scenes/spd/tree.nff", 4095, 0, 1, 4095, 0, 0, 7, {4.5, 0.4, 2}, {0, 0, 1.5}, {0, 0, 1}, 1},
};

static void t_spd_load(void)
{
    /* NFF.md totals: balls 7382, gears 9345, mount 8196, rings 8401, teapot 2292, tetra 4096,
     * tree 8191 */
    static const size_t totals[] = {92, 7382, 9345, 8196, 8401, 244, 2292, 4096, 8191};
    for (size_t k = 0; k < sizeof spd_cases / sizeof spd_cases[0]; k++) {
        const SpdCase *c = &spd_cases[k];
        RfScene s;
        char err[512];
        RfStatus st = rf_scene_load(c->path, NULL, &s, err, sizeof err);
        RF_CHECK_EQ_INT(st, RF_OK);
        if (st) {
            fprintf(stderr, "  %s\n", err);
            continue;
        }
        RF_CHECK_EQ_INT(s.format, RF_FORMAT_NFF);
        RF_CHECK_EQ_INT(s.prim_count, totals[k]);
        RF_CHECK_EQ_INT(count_type(&s, RF_PRIM_SPHERE), c->spheres);
        RF_CHECK_EQ_INT(count_type(&s, RF_PRIM_TRIANGLE), c->triangles);
        RF_CHECK_EQ_INT(count_type(&s, RF_PRIM_POLYGON), c->polygons);
        RF_CHECK_EQ_INT(count_type(&s, RF_PRIM_CONE), c->cones);
        RF_CHECK_EQ_INT(count_type(&s, RF_PRIM_PLANE), 0);
        RF_CHECK_EQ_INT(count_flag(&s, RF_PRIM_VERTEX_NORMALS), c->vertex_normal_prims);
        RF_CHECK_EQ_INT(count_flag(&s, RF_PRIM_NONCONVEX), c->nonconvex);
        RF_CHECK(s.has_camera);
        CHECK_VEC(s.camera.eye, c->from[0], c->from[1], c->from[2]);
        CHECK_VEC(s.camera.target, c->at[0], c->at[1], c->at[2]);
        CHECK_VEC(s.camera.up, c->up[0], c->up[1], c->up[2]);
        RF_CHECK_NEAR(s.camera.fov, 45, 0, 0);
        RF_CHECK_NEAR(s.camera.hither, c->hither, 0, 0);
        RF_CHECK_EQ_INT(s.camera.fov_reading, RF_FOV_PIXEL_CENTRES);
        RF_CHECK_EQ_INT(s.render.width, 512);
        RF_CHECK_EQ_INT(s.render.height, 512);
        CHECK_RGB(s.render.background, 0.078, 0.361, 0.753);
        RF_CHECK_EQ_INT(s.light_count, c->lights);
        for (size_t i = 0; i < s.light_count; i++) {
            double share = 1.0 / sqrt((double)c->lights);
            RF_CHECK_EQ_INT(s.lights[i].kind, RF_LIGHT_POINT);
            RF_CHECK_EQ_INT(s.lights[i].falloff, RF_FALLOFF_NONE);
            CHECK_RGB(s.lights[i].intensity, share, share, share);
        }
        RF_CHECK_EQ_INT(rf_scene_validate(&s, c->path, err, sizeof err), RF_OK);
        rf_scene_free(&s);
    }
}

/* The NFF `f` mapping on the first material of balls.nff: f 1 0.75 0.33 0.8 0 100000 0 1, and
 * mount's glass: f 1 1 1 0.1 0.1 101.148 0.9 1.5; rings' `ior 0` with T = 0 becomes 1. */
static void t_spd_materials(void)
{
    RfScene s;
    char err[512];
    RF_CHECK_EQ_INT(rf_scene_load("scenes/spd/balls.nff", NULL, &s, err, sizeof err), RF_OK);
    if (s.material_count > 1) {
        const RfMaterial *m = &s.materials[0];
        CHECK_RGB(m->kd, 0.8, 0.75 * 0.8, 0.33 * 0.8);
        CHECK_RGB(m->ks, 0, 0, 0);
        RF_CHECK_NEAR(m->shininess, 100000, 0, 0);
        CHECK_RGB(m->ka, 0, 0, 0);
        m = &s.materials[1]; /* f 1 0.9 0.7 0.5 0.5 3.0827 0 1 */
        CHECK_RGB(m->ks, 0.5, 0.5, 0.5);
        CHECK_RGB(m->kr, 0.5, 0.5, 0.5);
        CHECK_RGB(m->kt, 0, 0, 0);
    }
    rf_scene_free(&s);
    RF_CHECK_EQ_INT(rf_scene_load("scenes/spd/mount.nff", NULL, &s, err, sizeof err), RF_OK);
    if (s.material_count > 0) {
        const RfMaterial *m = &s.materials[0];
        CHECK_RGB(m->kd, 0.1, 0.1, 0.1);
        CHECK_RGB(m->kt, 0.9, 0.9, 0.9);
        RF_CHECK_NEAR(m->ior, 1.5, 0, 0);
        RF_CHECK(!(m->flags & RF_MAT_FRESNEL));
        /* the four glass spheres follow this material: transmitting, so two-sided */
        RF_CHECK_EQ_INT(count_flag(&s, RF_PRIM_TWO_SIDED), 4);
    }
    rf_scene_free(&s);
    RF_CHECK_EQ_INT(rf_scene_load("scenes/spd/rings.nff", NULL, &s, err, sizeof err), RF_OK);
    if (s.material_count > 0)
        RF_CHECK_NEAR(s.materials[0].ior, 1.0, 0, 0);
    rf_scene_free(&s);
}

/* ---- small files with every keyword ------------------------------------------------------- */

/* Writes text to a fresh temporary folder as `name`; the path goes to path. */
static int write_temp(const char *name, const char *text, char *path, size_t n)
{
    char dir[] = "/tmp/rf-scene-test-XXXXXX";
    if (!mkdtemp(dir))
        return 0;
    snprintf(path, n, "%s/%s", dir, name);
    FILE *f = fopen(path, "wb");
    if (!f)
        return 0;
    fputs(text, f);
    fclose(f);
    return 1;
}

static void remove_temp(const char *path)
{
    char dir[1024];
    snprintf(dir, sizeof dir, "%s", path);
    char *slash = strrchr(dir, '/');
    remove(path);
    if (slash) {
        *slash = 0;
        rmdir(dir);
    }
}

static const char nff_small[] =
    "# every NFF keyword\n"
    "b 0.1 0.2 0.3\n"
    "v\n"
    "from 0 -10 1\n"
    "at 0 0 1\n"
    "up 0 0 2\n"
    "angle 30\n"
    "hither 0.5\n"
    "resolution 64 48\n"
    "l 1 2 3\n"
    "l 4 5 6 0.5 0.25 1   # with a colour\n"
    "l 7 8 9\n"
    "f 1 0.5 0.25 0.8 0.2 20 0 1\n"
    "s 1 2 3 0.5\n"
    "s 0 0 0 -4\n"
    "f 0.5 0.5 0.5 0.6 0.3 10 0.7 1.33\n"
    "c 0 0 0 1 0 0 2 0.5\n"
    "c\n0 0 3 -1\n0 0 4 -0.5\n"
    "p 3\n0 0 0\n1 0 0\n0 1 0\n"
    "p 4\n0 0 0\n2 0 0\n2 2 0\n0 2 0\n"
    "pp 3\n0 0 0 0 0 1\n1 0 0 0 0 2\n0 1 0 0 1 1\n";

static void t_nff_small(void)
{
    char path[1024], err[512];
    RfScene s;
    RF_CHECK(write_temp("small.nff", nff_small, path, sizeof path));
    RfStatus st = rf_scene_load(path, NULL, &s, err, sizeof err);
    remove_temp(path);
    RF_CHECK_EQ_INT(st, RF_OK);
    if (st) {
        fprintf(stderr, "  %s\n", err);
        return;
    }
    CHECK_RGB(s.render.background, 0.1, 0.2, 0.3);
    CHECK_VEC(s.camera.eye, 0, -10, 1);
    CHECK_VEC(s.camera.target, 0, 0, 1);
    CHECK_VEC(s.camera.up, 0, 0, 2);
    RF_CHECK_NEAR(s.camera.fov, 30, 0, 0);
    RF_CHECK_NEAR(s.camera.hither, 0.5, 0, 0);
    RF_CHECK_NEAR(s.camera.d, 1, 0, 0);
    RF_CHECK_EQ_INT(s.render.width, 64);
    RF_CHECK_EQ_INT(s.render.height, 48);
    RF_CHECK_EQ_INT(s.light_count, 3);
    if (s.light_count == 3) {
        double share = 1.0 / sqrt(3.0);
        CHECK_VEC(s.lights[0].position, 1, 2, 3);
        CHECK_RGB(s.lights[0].intensity, share, share, share);
        CHECK_RGB(s.lights[1].intensity, 0.5, 0.25, 1);
        CHECK_RGB(s.lights[2].intensity, share, share, share);
        RF_CHECK_EQ_INT(s.lights[2].falloff, RF_FALLOFF_NONE);
    }
    RF_CHECK_EQ_INT(s.material_count, 2);
    if (s.material_count == 2) {
        const RfMaterial *m = &s.materials[0];
        CHECK_RGB(m->kd, 0.8, 0.4, 0.2);
        CHECK_RGB(m->ks, 0.2, 0.2, 0.2);
        CHECK_RGB(m->kr, 0.2, 0.2, 0.2);
        RF_CHECK_NEAR(m->shininess, 20, 0, 0);
        CHECK_RGB(m->kt, 0, 0, 0);
        m = &s.materials[1];
        CHECK_RGB(m->kt, 0.7, 0.7, 0.7);
        RF_CHECK_NEAR(m->ior, 1.33, 0, 0);
    }
    RF_CHECK_EQ_INT(s.prim_count, 7);
    if (s.prim_count == 7) {
        const RfPrimitive *p = s.prims;
        RF_CHECK_EQ_INT(p[0].type, RF_PRIM_SPHERE);
        CHECK_VEC(p[0].u.sphere.center, 1, 2, 3);
        RF_CHECK_NEAR(p[0].u.sphere.radius, 0.5, 0, 0);
        RF_CHECK_EQ_INT(p[0].flags, 0);
        RF_CHECK_EQ_INT(p[0].material, 0);
        RF_CHECK_EQ_INT(p[0].loc.line, 14);
        RF_CHECK_NEAR(p[1].u.sphere.radius, 4, 0, 0);
        RF_CHECK_EQ_INT(p[1].flags, RF_PRIM_INSIDE);
        RF_CHECK_EQ_INT(p[2].type, RF_PRIM_CONE);
        CHECK_VEC(p[2].u.cone.apex, 0, 0, 2);
        RF_CHECK_NEAR(p[2].u.cone.base_radius, 1, 0, 0);
        RF_CHECK_NEAR(p[2].u.cone.apex_radius, 0.5, 0, 0);
        RF_CHECK_EQ_INT(p[2].flags, RF_PRIM_TWO_SIDED); /* T > 0 */
        RF_CHECK_EQ_INT(p[2].material, 1);
        RF_CHECK_EQ_INT(p[3].flags, RF_PRIM_TWO_SIDED | RF_PRIM_INSIDE);
        RF_CHECK_NEAR(p[3].u.cone.base_radius, 1, 0, 0);
        RF_CHECK_EQ_INT(p[4].type, RF_PRIM_TRIANGLE);
        RF_CHECK_EQ_INT(p[5].type, RF_PRIM_POLYGON);
        RF_CHECK_EQ_INT(p[5].u.poly.count, 4);
        CHECK_VEC(s.vertices[p[5].u.poly.first + 2], 2, 2, 0);
        RF_CHECK_EQ_INT(p[6].type, RF_PRIM_TRIANGLE);
        RF_CHECK(p[6].flags & RF_PRIM_VERTEX_NORMALS);
        CHECK_VEC(s.normals[p[6].u.poly.nfirst + 1], 0, 0, 1); /* (0 0 2) normalised */
        RF_CHECK_NEAR(s.normals[p[6].u.poly.nfirst + 2].y, sqrt(0.5), 1e-15, 0);
    }
    /* the two readings of `angle` */
    RfWindow w = rf_scene_camera_window(&s.camera, 64, 48);
    double t = tan(15.0 * RF_PI / 180.0);
    RF_CHECK_NEAR(w.t, t * 48.0 / 47.0, 1e-15, 0);
    RF_CHECK_NEAR(w.r, t * 48.0 / 47.0 * 64.0 / 48.0, 1e-15, 0);
    rf_scene_free(&s);
    RfLoadOptions opt = rf_load_options_default();
    opt.nff_fov = RF_FOV_EDGES;
    RF_CHECK_EQ_INT(rf_scene_read_nff("t.nff", nff_small, strlen(nff_small), &opt, &s, err,
                                      sizeof err), RF_OK);
    w = rf_scene_camera_window(&s.camera, 64, 48);
    RF_CHECK_NEAR(w.t, t, 1e-15, 0);
    RF_CHECK_NEAR(w.b, -t, 1e-15, 0);
    rf_scene_free(&s);
}

static const char rf_small[] =
    "# every keyword of refray's format\n"
    "camera eye 0 1 5  target 0 1 0  up 0 1 0  window -2 2 -1 1  d 2  hither 0.1\n"
    "resolution 200 100\n"
    "depth 5\n"
    "threshold 0.01\n"
    "samples 16\n"
    "background 0.1 0.2 0.3\n"
    "ambient 0.05\n"
    "material base  ka 0.1  kd 0.5 0.6 0.7  ks 0.3  shininess 40  kr 0.2  kt 0.4 0.5 0.6\n"
    "  ior 1.5  emission 1 2 3  fresnel  flat\n" /* a line starting with a word is a statement: */
    "material glow  emission 2  smooth\n"
    "light point 1 2 3  intensity 10 20 30\n"
    "light directional 0 -2 0  intensity 0.5\n"
    "light spot 0 5 0  axis 0 -1 0  exponent 8  cutoff 30  intensity 5  falloff none\n"
    "use base\n"
    "sphere 0 1 0 0.5\n"
    "sphere 0 0 0 10  inside  material glow\n"
    "plane 0 -1 0  0 2 0  one-sided\n"
    "triangle 0 0 0  1 0 0  0 1 0  normals 0 0 1  0 0 1  0 1 1\n"
    "polygon 5\n"
    "  0 0 0   2 0 0\n"
    "  2 2 0   1 3 0   0 2 0\n"
    "cone 0 0 0 1  0 2 0 0\n"
    "cylinder 1 0 0  1 3 0  0.25  two-sided\n";

static void t_rf_small(void)
{
    char path[1024], err[512];
    RfScene s;
    /* "  ior 1.5 ..." starts with a word: it is not a continuation, so the reader must refuse
     * it; the file below joins it to the material line instead. */
    RF_CHECK_EQ_INT(rf_scene_read_rf("t.rf", rf_small, strlen(rf_small), &s, err, sizeof err),
                    RF_ERR_PARSE);
    RF_CHECK_STR(err, "t.rf:10:3: unknown keyword 'ior'");
    char text[sizeof rf_small];
    snprintf(text, sizeof text, "%s", rf_small);
    char *nl = strstr(text, "0.6\n  ior");
    if (nl)
        nl[3] = ' ';
    RF_CHECK(write_temp("small.rf", text, path, sizeof path));
    RfStatus st = rf_scene_load(path, NULL, &s, err, sizeof err);
    remove_temp(path);
    RF_CHECK_EQ_INT(st, RF_OK);
    if (st) {
        fprintf(stderr, "  %s\n", err);
        return;
    }
    RF_CHECK_EQ_INT(s.format, RF_FORMAT_RF);
    const RfSceneCamera *c = &s.camera;
    CHECK_VEC(c->eye, 0, 1, 5);
    CHECK_VEC(c->target, 0, 1, 0);
    CHECK_VEC(c->up, 0, 1, 0);
    RF_CHECK(c->has_window);
    RF_CHECK_NEAR(c->l, -2, 0, 0);
    RF_CHECK_NEAR(c->r, 2, 0, 0);
    RF_CHECK_NEAR(c->b, -1, 0, 0);
    RF_CHECK_NEAR(c->t, 1, 0, 0);
    RF_CHECK_NEAR(c->d, 2, 0, 0);
    RF_CHECK_NEAR(c->hither, 0.1, 0, 0);
    RF_CHECK_EQ_INT(s.render.width, 200);
    RF_CHECK_EQ_INT(s.render.height, 100);
    RF_CHECK_EQ_INT(s.render.max_depth, 5);
    RF_CHECK_NEAR(s.render.min_contribution, 0.01, 0, 0);
    RF_CHECK_EQ_INT(s.render.samples, 16);
    CHECK_RGB(s.render.background, 0.1, 0.2, 0.3);
    CHECK_RGB(s.render.ambient, 0.05, 0.05, 0.05);
    RF_CHECK_EQ_INT(s.material_count, 2);
    if (s.material_count == 2) {
        const RfMaterial *m = &s.materials[0];
        RF_CHECK_STR(m->name, "base");
        CHECK_RGB(m->ka, 0.1, 0.1, 0.1);
        CHECK_RGB(m->kd, 0.5, 0.6, 0.7);
        CHECK_RGB(m->ks, 0.3, 0.3, 0.3);
        RF_CHECK_NEAR(m->shininess, 40, 0, 0);
        CHECK_RGB(m->kr, 0.2, 0.2, 0.2);
        CHECK_RGB(m->kt, 0.4, 0.5, 0.6);
        RF_CHECK_NEAR(m->ior, 1.5, 0, 0);
        CHECK_RGB(m->emission, 1, 2, 3);
        RF_CHECK_EQ_INT(m->flags, RF_MAT_FRESNEL);
        RF_CHECK_EQ_INT(s.materials[1].flags, RF_MAT_SMOOTH);
        CHECK_RGB(s.materials[1].emission, 2, 2, 2);
    }
    RF_CHECK_EQ_INT(s.light_count, 3);
    if (s.light_count == 3) {
        const RfLight *l = s.lights;
        RF_CHECK_EQ_INT(l[0].kind, RF_LIGHT_POINT);
        RF_CHECK_EQ_INT(l[0].falloff, RF_FALLOFF_INVERSE_SQUARE);
        CHECK_VEC(l[0].position, 1, 2, 3);
        CHECK_RGB(l[0].intensity, 10, 20, 30);
        RF_CHECK_EQ_INT(l[1].kind, RF_LIGHT_DIRECTIONAL);
        CHECK_VEC(l[1].direction, 0, -1, 0);
        CHECK_RGB(l[1].intensity, 0.5, 0.5, 0.5);
        RF_CHECK_EQ_INT(l[2].kind, RF_LIGHT_SPOT);
        RF_CHECK_EQ_INT(l[2].falloff, RF_FALLOFF_NONE);
        CHECK_VEC(l[2].direction, 0, -1, 0);
        RF_CHECK_NEAR(l[2].spot_exponent, 8, 0, 0);
        RF_CHECK_NEAR(l[2].spot_cutoff, 30, 0, 0);
    }
    RF_CHECK_EQ_INT(s.prim_count, 7);
    if (s.prim_count == 7) {
        const RfPrimitive *p = s.prims;
        RF_CHECK_EQ_INT(p[0].material, 0);
        RF_CHECK_EQ_INT(p[0].flags, RF_PRIM_TWO_SIDED);
        RF_CHECK_EQ_INT(p[1].material, 1);
        RF_CHECK_EQ_INT(p[1].flags, RF_PRIM_INSIDE);
        RF_CHECK_EQ_INT(p[2].type, RF_PRIM_PLANE);
        CHECK_VEC(p[2].u.plane.normal, 0, 1, 0);
        RF_CHECK_NEAR(p[2].u.plane.offset, -1, 0, 0);
        RF_CHECK_EQ_INT(p[2].flags, 0);
        RF_CHECK_EQ_INT(p[3].type, RF_PRIM_TRIANGLE);
        RF_CHECK_EQ_INT(p[3].flags, RF_PRIM_TWO_SIDED | RF_PRIM_VERTEX_NORMALS);
        RF_CHECK_NEAR(s.normals[p[3].u.poly.nfirst + 2].z, sqrt(0.5), 1e-15, 0);
        RF_CHECK_EQ_INT(p[4].type, RF_PRIM_POLYGON);
        RF_CHECK_EQ_INT(p[4].u.poly.count, 5);
        CHECK_VEC(s.vertices[p[4].u.poly.first + 3], 1, 3, 0);
        RF_CHECK_EQ_INT(p[4].loc.line, 19);
        RF_CHECK_EQ_INT(p[5].type, RF_PRIM_CONE);
        RF_CHECK_NEAR(p[5].u.cone.apex_radius, 0, 0, 0);
        RF_CHECK_NEAR(p[6].u.cone.base_radius, 0.25, 0, 0);
        RF_CHECK_NEAR(p[6].u.cone.apex_radius, 0.25, 0, 0);
        CHECK_VEC(p[6].u.cone.apex, 1, 3, 0);
    }
    RfWindow w = rf_scene_camera_window(&s.camera, 200, 100);
    RF_CHECK_NEAR(w.l, -2, 0, 0);
    RF_CHECK_NEAR(w.d, 2, 0, 0);
    RfVec3 lo, hi;
    RF_CHECK(rf_scene_bounds(&s, &lo, &hi));
    CHECK_VEC(lo, -10, -10, -10);
    CHECK_VEC(hi, 10, 10, 10);
    rf_scene_free(&s);
}

/* ---- errors ------------------------------------------------------------------------------- */

#define NFF_VIEW "v\nfrom 0 0 5\nat 0 0 0\nup 0 1 0\nangle 45\nhither 1\nresolution 8 8\n"
#define RF_CAM "camera eye 0 0 5  target 0 0 0  up 0 1 0  fov 45\n"

typedef struct {
    int nff;
    const char *text, *expected;
} ErrCase;

static const ErrCase err_cases[] = {
    /* unknown keywords */
    {1, NFF_VIEW "q 1 2\n", "t.nff:8:1: unknown NFF keyword 'q'"},
    {0, RF_CAM "sphre 0 0 0 1\n", "t.rf:2:1: unknown keyword 'sphre'"},
    {0, RF_CAM "sphere 0 0 0 1 shiny\n", "t.rf:2:16: unknown attribute 'shiny' for 'sphere'"},
    {0, RF_CAM "light area 0 0 0\n", "t.rf:2:7: unknown light kind 'area' (point, directional, spot, rect, disc, sphere)"},
    /* a missing number: reported just after the statement's last token */
    {1, NFF_VIEW "s 0 0 0\ns 1 1 1 1\n", "t.nff:8:8: missing number: expected sphere radius"},
    {0, RF_CAM "sphere 0 0 0\n", "t.rf:2:13: missing number: expected sphere radius"},
    {0, RF_CAM "material m kd 0.5 0.5 ks 1\n", "t.rf:2:23: expected kd (a number), found 'ks'"},
    {1, NFF_VIEW "p 3\n0 0 0\n1 0 0\n", "t.nff:10:6: missing number: expected polygon vertex"},
    /* NaN, Inf, overflow */
    {1, NFF_VIEW "s 0 0 nan 1\n", "t.nff:8:7: sphere centre must be a finite number, found 'nan'"},
    {0, "camera eye 0 0 -inf  target 0 0 0  up 0 1 0  fov 45\n",
     "t.rf:1:16: eye must be a finite number, found '-inf'"},
    {0, RF_CAM "sphere 0 0 0 1e999\n", "t.rf:2:14: sphere radius must be a finite number, found '1e999'"},
    {0, RF_CAM "background 0.5 0.1x 0\n", "t.rf:2:16: expected background (a number), found '0.1x'"},
    /* camera */
    {1, "v\nfrom 0 0 5\nat 0 0 0\nup 0 0 0\nangle 45\n", "t.nff:4:1: camera: up vector has zero length"},
    {1, "v\nfrom 1 2 3\nat 1 2 3\nup 0 1 0\nangle 45\n", "t.nff:3:1: camera: eye and target coincide"},
    {0, "camera eye 0 0 5  target 0 0 0  up 0 0 -3  fov 45\n",
     "t.rf:1:33: camera: up vector is parallel to the view direction"},
    {1, "v\nfrom 0 0 5\nat 0 0 0\nup 0 1 0\nangle 180\n",
     "t.nff:5:7: angle must be in (0, 180) degrees, found 180"},
    {0, "camera eye 0 0 5  target 0 0 0  up 0 1 0\n",
     "t.rf:1:1: camera needs exactly one of 'fov' and 'window'"},
    {1, "s 0 0 0 1\n", "t.nff:2:1: the scene has no camera (NFF needs a viewpoint 'v')"},
    {0, "sphere 0 0 0 1\n", "t.rf:2:1: the scene has no camera (add a 'camera' statement)"},
    {1, NFF_VIEW NFF_VIEW, "t.nff:8:1: second viewpoint (v): the scene has one camera"},
    /* degenerate primitives */
    {1, NFF_VIEW "s 0 0 0 0\n", "t.nff:8:1: degenerate sphere: radius must be > 0, found 0"},
    {1, NFF_VIEW "p 3\n0 0 0\n1 1 1\n2 2 2\n",
     "t.nff:8:1: degenerate triangle: its vertices are collinear (zero area)"},
    {0, RF_CAM "polygon 4  0 0 0  1 0 0  2 0 0  3 0 0\n",
     "t.rf:2:1: degenerate polygon: its vertices are collinear (zero area)"},
    {1, NFF_VIEW "p 2\n0 0 0\n1 0 0\n",
     "t.nff:8:3: polygon vertex count must be an integer in [3, 1000000], found '2'"},
    {0, RF_CAM "cone 0 0 0 1  0 0 0 0.5\n", "t.rf:2:1: degenerate cone: base and apex coincide"},
    {1, NFF_VIEW "c 0 0 0 -1 0 0 1 1\n",
     "t.nff:8:18: cone radii must both be >= 0, or both < 0 (inside only)"},
    {0, RF_CAM "plane 0 0 0  0 0 0\n", "t.rf:2:1: degenerate plane: zero normal vector"},
    {1, NFF_VIEW "pp 3\n0 0 0 0 0 1\n1 0 0 0 0 0\n0 1 0 0 0 1\n",
     "t.nff:8:1: triangle: normal of vertex 2 has zero length"},
    /* out-of-range values */
    {0, RF_CAM "resolution -640 480\n",
     "t.rf:2:12: resolution width must be an integer in [1, 65536], found '-640'"},
    {1, "v\nfrom 0 0 5\nat 0 0 0\nup 0 1 0\nangle 45\nhither 1\nresolution 8 0\n",
     "t.nff:7:14: resolution height must be an integer in [1, 65536], found '0'"},
    {1, NFF_VIEW "f 1 1 1 0.5 0.5 10 0.5 0\n",
     "t.nff:8:24: ior must be > 0 for a transmitting material (T = 0.5)"},
    {1, NFF_VIEW "b 0.1 -0.2 0.3\n", "t.nff:8:7: background colour must be >= 0, found -0.2"},
    {0, RF_CAM "depth 2.5\n", "t.rf:2:7: depth must be an integer in [1, 1000], found '2.5'"},
    {0, RF_CAM "light spot 0 0 0  axis 0 -1 0  cutoff 120\n",
     "t.rf:2:39: spot cutoff must be in (0, 90] degrees, found 120"},
    {0, RF_CAM "light spot 0 0 0  axis 0 0 0  cutoff 20\n", "t.rf:2:28: spot axis has zero length"},
    /* names and structure */
    {0, RF_CAM "use nothing\n", "t.rf:2:5: unknown material 'nothing'"},
    {0, RF_CAM "material m\nmaterial m\n", "t.rf:3:10: material 'm' is defined twice"},
    {0, RF_CAM "sphere 0 0 0 1 2\n", "t.rf:2:16: too many numbers for 'sphere': '2'"},
    {0, RF_CAM "depth 3 4\n", "t.rf:2:9: too many numbers for 'depth': '4'"},
    {0, RF_CAM RF_CAM, "t.rf:2:1: second camera: the scene has one camera"},
    {1, "1 2 3\n", "t.nff:1:1: expected a keyword, found '1'"},
    {1, NFF_VIEW "s 0 0 0 1 \x01\n", "t.nff:8:11: unknown NFF keyword '\\x01'"},
};

static void t_errors(void)
{
    for (size_t i = 0; i < sizeof err_cases / sizeof err_cases[0]; i++) {
        const ErrCase *c = &err_cases[i];
        RfScene s;
        char err[512] = "";
        RfStatus st = c->nff ? rf_scene_read_nff("t.nff", c->text, strlen(c->text), NULL, &s, err,
                                                 sizeof err)
                             : rf_scene_read_rf("t.rf", c->text, strlen(c->text), &s, err,
                                                sizeof err);
        RF_CHECK(st != RF_OK);
        RF_CHECK_STR(err, c->expected);
        /* a failed read leaves an empty scene that can be freed again */
        RF_CHECK(s.prim_count == 0 && s.prims == NULL && s.materials == NULL);
        rf_scene_free(&s);
    }
    RfScene s;
    char err[512];
    RF_CHECK_EQ_INT(rf_scene_load("/nonexistent/missing.nff", NULL, &s, err, sizeof err), RF_ERR_IO);
    RF_CHECK_STR(err, "cannot open /nonexistent/missing.nff: No such file or directory"); /* no line to point at */
}

/* `refray info`: the analysis on stdout; a bad scene gives exactly one line on stderr and
 * exit code 4 (README: Exit codes). */
static void t_info_cli(void)
{
    char cmd[2048], path[1024];
    int code;
    snprintf(cmd, sizeof cmd, "%s info scenes/whitted.rf", rf_test_bin());
    const char *out = rf_test_run(cmd, &code);
    RF_CHECK_EQ_INT(code, 0);
    RF_CHECK(strstr(out, "primitives 4: sphere 3 polygon 1") != NULL);
    RF_CHECK(strstr(out, "lights    1: point 1") != NULL);
    RF_CHECK(strstr(out, "features  reflection transmission fresnel specular ambient "
                         "light-falloff\n") != NULL);
    snprintf(cmd, sizeof cmd, "%s info scenes/spd/tree.nff", rf_test_bin());
    out = rf_test_run(cmd, &code);
    RF_CHECK_EQ_INT(code, 0);
    RF_CHECK(strstr(out, "primitives 8191: sphere 4095 polygon 1 cone 4095") != NULL);
    RF_CHECK(write_temp("bad.nff", NFF_VIEW "s 0 0 0 0\n", path, sizeof path));
    snprintf(cmd, sizeof cmd, "%s info %s 2>&1 >/dev/null", rf_test_bin(), path);
    out = rf_test_run(cmd, &code);
    RF_CHECK_EQ_INT(code, 4);
    char expected[1200];
    snprintf(expected, sizeof expected, "%s:8:1: degenerate sphere: radius must be > 0, found 0\n",
             path);
    RF_CHECK_STR(out, expected);
    remove_temp(path);
    snprintf(cmd, sizeof cmd, "%s info 2>/dev/null", rf_test_bin());
    rf_test_run(cmd, &code);
    RF_CHECK_EQ_INT(code, 5);
}

/* ---- analysis ----------------------------------------------------------------------------- */

static void t_features(void)
{
    static const struct {
        const char *path;
        unsigned features;
    } cases[] = {
        {"scenes/whitted.rf", RF_FEAT_REFLECTION | RF_FEAT_TRANSMISSION | RF_FEAT_FRESNEL |
                                  RF_FEAT_SPECULAR | RF_FEAT_AMBIENT | RF_FEAT_LIGHT_FALLOFF},
        {"scenes/spd/tetra.nff", 0},
        {"scenes/spd/teapot.nff", RF_FEAT_REFLECTION | RF_FEAT_SPECULAR | RF_FEAT_VERTEX_NORMALS},
        {"scenes/spd/mount.nff", RF_FEAT_REFLECTION | RF_FEAT_TRANSMISSION | RF_FEAT_SPECULAR},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        RfScene s;
        char err[512];
        RF_CHECK_EQ_INT(rf_scene_load(cases[i].path, NULL, &s, err, sizeof err), RF_OK);
        RF_CHECK_EQ_INT(rf_scene_features(&s), cases[i].features);
        rf_scene_free(&s);
    }
    /* unused materials do not count; emission and spot lights do */
    static const char text[] = RF_CAM "material unused kr 1 kt 1\nmaterial lamp emission 1\n"
                                      "light spot 0 1 0 axis 0 -1 0 cutoff 45\nsphere 0 0 0 1\n";
    RfScene s;
    char err[512];
    RF_CHECK_EQ_INT(rf_scene_read_rf("t.rf", text, strlen(text), &s, err, sizeof err), RF_OK);
    RF_CHECK_EQ_INT(rf_scene_features(&s),
                    RF_FEAT_EMISSION | RF_FEAT_SPOT_LIGHTS | RF_FEAT_LIGHT_FALLOFF);
    for (unsigned b = 0; b < RF_FEAT_COUNT; b++)
        RF_CHECK(rf_feature_name(1u << b) != NULL);
    rf_scene_free(&s);
}

/* The whitted scene says what SCENES.md §2 says. */
static void t_whitted(void)
{
    RfScene s;
    char err[512];
    RF_CHECK_EQ_INT(rf_scene_load("scenes/whitted.rf", NULL, &s, err, sizeof err), RF_OK);
    if (s.prim_count != 4 || s.material_count != 4 || s.light_count != 1) {
        RF_CHECK(0);
        rf_scene_free(&s);
        return;
    }
    CHECK_VEC(s.camera.eye, 0, 2.6, 7);
    CHECK_VEC(s.camera.target, 0, 0.6, 0);
    RF_CHECK_NEAR(s.camera.fov, 40, 0, 0);
    RF_CHECK_EQ_INT(s.camera.fov_reading, RF_FOV_EDGES);
    RF_CHECK_EQ_INT(s.render.width, 640);
    RF_CHECK_EQ_INT(s.render.height, 480);
    RF_CHECK_EQ_INT(s.render.max_depth, 8);
    RfWindow w = rf_scene_camera_window(&s.camera, 640, 480);
    RF_CHECK_NEAR(w.t, tan(20.0 * RF_PI / 180.0), 1e-15, 0);
    RF_CHECK_NEAR(w.r, w.t * 640.0 / 480.0, 1e-15, 0);
    CHECK_RGB(s.lights[0].intensity, 60, 60, 60);
    RF_CHECK_EQ_INT(s.lights[0].falloff, RF_FALLOFF_INVERSE_SQUARE);
    const RfPrimitive *ground = &s.prims[0];
    RF_CHECK_EQ_INT(ground->type, RF_PRIM_POLYGON);
    const RfVec3 *v = s.vertices + ground->u.poly.first;
    RfVec3 n = rf_vec3_cross(rf_vec3_sub(v[1], v[0]), rf_vec3_sub(v[2], v[1]));
    RF_CHECK(n.y > 0 && n.x == 0 && n.z == 0); /* counter-clockwise from +y */
    CHECK_RGB(s.materials[1].kd, 0.7, 0.08, 0.08);
    CHECK_RGB(s.materials[1].ka, 0.7, 0.08, 0.08);
    RF_CHECK_NEAR(s.materials[1].shininess, 50, 0, 0);
    CHECK_RGB(s.materials[2].kr, 0.9, 0.9, 0.9);
    RF_CHECK(s.materials[3].flags & RF_MAT_FRESNEL);
    RF_CHECK_NEAR(s.materials[3].ior, 1.5, 0, 0);
    CHECK_RGB(s.render.ambient, 0.05, 0.05, 0.05);
    rf_scene_free(&s);
}

/* ---- robustness: truncated and corrupted input never crashes ---------------------------- */

static char *slurp(const char *path, size_t *len)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return NULL;
    char *buf = NULL;
    size_t cap = 0, n = 0, k;
    do {
        if (n == cap) {
            cap = cap ? 2 * cap : 1 << 16;
            char *b = realloc(buf, cap);
            if (!b)
                break;
            buf = b;
        }
        k = fread(buf + n, 1, cap - n, f);
        n += k;
    } while (k > 0);
    fclose(f);
    *len = n;
    return buf;
}

static uint64_t lcg(uint64_t *s)
{
    *s = *s * 6364136223846793005u + 1442695040888963407u;
    return *s >> 33;
}

static void fuzz_one(const char *path, int nff, uint64_t seed, int rounds)
{
    size_t len = 0;
    char *orig = slurp(path, &len);
    RF_CHECK(orig != NULL && len > 0);
    if (!orig || !len) {
        free(orig);
        return;
    }
    char *buf = malloc(len);
    static const char bytes[] = "\n \t#-+.0123456789eExnaif\x00\xff";
    int ok = 0, failed = 0;
    for (int r = 0; r < rounds; r++) {
        size_t n = len;
        memcpy(buf, orig, len);
        if (r % 3 == 0) {
            n = (size_t)(lcg(&seed) % len); /* truncate */
        } else {
            int flips = 1 + (int)(lcg(&seed) % 4);
            for (int k = 0; k < flips; k++)
                buf[lcg(&seed) % len] = bytes[lcg(&seed) % (sizeof bytes - 1)];
        }
        RfScene s;
        char err[512] = "";
        RfStatus st = nff ? rf_scene_read_nff("f", buf, n, NULL, &s, err, sizeof err)
                          : rf_scene_read_rf("f", buf, n, &s, err, sizeof err);
        if (st == RF_OK) {
            ok++;
            RF_CHECK_EQ_INT(rf_scene_validate(&s, "f", err, sizeof err), RF_OK);
        } else {
            failed++;
            int line = 0, col = 0;
            RF_CHECK(sscanf(err, "f:%d:%d: ", &line, &col) == 2 && line >= 1 && col >= 1);
        }
        rf_scene_free(&s);
    }
    RF_CHECK(ok > 0 && failed > 0); /* both outcomes were exercised */
    free(buf);
    free(orig);
}

static void t_fuzz(void)
{
    fuzz_one("scenes/spd/teapot-2.nff", 1, 1, 300);
    fuzz_one("scenes/spd/balls-2.nff", 1, 2, 300);
    fuzz_one("scenes/whitted.rf", 0, 3, 600);
}

const RfTest rf_tests_scene[] = {
    {"scene_spd_load", t_spd_load},
    {"scene_spd_materials", t_spd_materials},
    {"scene_nff_small", t_nff_small},
    {"scene_rf_small", t_rf_small},
    {"scene_errors", t_errors},
    {"scene_info_cli", t_info_cli},
    {"scene_features", t_features},
    {"scene_whitted", t_whitted},
    {"scene_fuzz", t_fuzz},
    RF_TEST_END,
};
