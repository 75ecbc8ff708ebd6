/* The tracer's acceleration structure against brute force on every shipped scene (issue 10):
 * the BVH with its vector kernels, the same with the scalar kernels, and no BVH at all (every
 * item tested with the double-precision kernels alone) must give the same answers bit for bit:
 * the same primitive, t, point and normals for nearest hits and the same occlusion answers,
 * ray by ray, and the same images. */
#include <glob.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "refray/camera.h"
#include "refray/render.h"
#include "refray/scene_io.h"
#include "rf_test.h"
#include "rf_test_render.h"

/* the tracers compared; TWO_SIDED (every side seen) only where a test asks for it */
enum { VECTOR, SCALAR, BRUTE, KINDS, TWO_SIDED = KINDS };

/* count tracers of the kinds above, from VECTOR on */
static RfStatus make_tracers(const RfScene *s, RfTracer **t, int count)
{
    for (int k = 0; k < count; k++) {
        RfTracerOptions o = rf_tracer_options_default();
        o.threads = 2;
        o.scalar = k == SCALAR;
        o.brute_force = k == BRUTE;
        o.two_sided = k == TWO_SIDED;
        RfStatus st = rf_tracer_create_opts(s, &o, &t[k]);
        if (st != RF_OK)
            return st;
    }
    return RF_OK;
}

static int same_hit(int pa, const RfSurfaceHit *a, int pb, const RfSurfaceHit *b)
{
    if (pa != pb)
        return 0;
    if (pa < 0)
        return 1;
    return a->t == b->t && a->material == b->material && a->front == b->front &&
           memcmp(&a->point, &b->point, sizeof a->point) == 0 &&
           memcmp(&a->normal, &b->normal, sizeof a->normal) == 0 &&
           memcmp(&a->shading_normal, &b->shading_normal, sizeof a->shading_normal) == 0;
}

/* How many test rays a scene gets: brute force costs (rendered triangles) tests per ray, so
 * each scene's rays stay under `work` tests in all (at most cap rays, at least 16). */
static int ray_budget(const RfScene *s, long work, int cap)
{
    RfTriangleCount tc = rf_scene_triangle_count(s);
    long per_ray = (long)(tc.rendered + s->prim_count) + 1;
    long max = work / per_ray;
    return max > cap ? cap : max < 16 ? 16 : (int)max;
}

/* Rays of three kinds: camera rays on a grid, random rays through the scene's box, and rays
 * leaving the surfaces the camera rays hit (reflection-like, from the offset origin). */
static int scene_rays(const RfScene *s, const RfTracer *t, RfTestRng *rng, RfRay *rays, int max)
{
    int n = 0;
    RfCamera cam;
    RfWindow w = rf_scene_camera_window(&s->camera, 40, 30);
    rf_camera_init(&cam, s->camera.eye, s->camera.target, s->camera.up, w.d, w.l, w.r, w.b, w.t, 40, 30);
    RfVec3 lo, hi;
    int bounded = rf_scene_bounds(s, &lo, &hi);
    for (int y = 0; y < 30 && n < max; y++)
        for (int x = 0; x < 40 && n < max; x++) {
            RfRay r = rf_camera_ray(&cam, x + 0.5, y + 0.5, 0, 0);
            rays[n++] = r;
            RfSurfaceHit h;
            if (n < max && rf_tracer_intersect(t, &r, 0, HUGE_VAL, &h) >= 0) {
                RfVec3 d = rf_vec3(rf_test_uniform(rng, -1, 1), rf_test_uniform(rng, -1, 1), rf_test_uniform(rng, -1, 1));
                if (rf_vec3_dot(d, h.normal) < 0)
                    d = rf_vec3_neg(d);
                rays[n++] = rf_ray(rf_hit_offset_origin(&h, d, 0), d);
            }
        }
    while (bounded && n < max) {
        RfVec3 o = rf_vec3(rf_test_uniform(rng, lo.x, hi.x), rf_test_uniform(rng, lo.y, hi.y), rf_test_uniform(rng, lo.z, hi.z));
        RfVec3 d = rf_vec3(rf_test_uniform(rng, -1, 1), rf_test_uniform(rng, -1, 1), rf_test_uniform(rng, -1, 1));
        if (n % 5 == 0) /* axis-parallel */
            d = rf_vec3(0, n % 2 ? 1 : -1, 0);
        rays[n++] = rf_ray(o, d);
    }
    return n;
}

static void t_accel_scenes_vs_brute_force(void)
{
    glob_t g;
    int scenes = 0;
    rf_test_shipped_scenes(&g, 1);
    for (size_t i = 0; i < g.gl_pathc; i++) {
        const char *path = g.gl_pathv[i];
        RfScene s;
        char err[512];
        RfTracer *t[KINDS] = {NULL, NULL, NULL};
        RF_CHECK_EQ_INT(rf_scene_load(path, NULL, &s, err, sizeof err), RF_OK);
        if (make_tracers(&s, t, KINDS) != RF_OK) {
            rf_test_fail(__FILE__, __LINE__, "%s: tracers", path);
            continue;
        }
        int max = ray_budget(&s, 3000000L, 2400);
        RfRay *rays = malloc(sizeof *rays * (size_t)max);
        RfTestRng rng = {77 + i};
        int n = scene_rays(&s, t[VECTOR], &rng, rays, max), bad = 0;
        for (int k = 0; k < n && bad < 3; k++) {
            RfSurfaceHit h[KINDS];
            int p[KINDS];
            double dist = rf_test_uniform(&rng, 0.1, 20);
            for (int m = 0; m < KINDS; m++)
                p[m] = rf_tracer_intersect(t[m], &rays[k], 0, HUGE_VAL, &h[m]);
            int occ[KINDS];
            for (int m = 0; m < KINDS; m++)
                occ[m] = rf_tracer_occluded(t[m], &rays[k], 0, dist);
            rf_test_checks++;
            for (int m = 1; m < KINDS; m++)
                if (!same_hit(p[0], &h[0], p[m], &h[m]) || occ[0] != occ[m]) {
                    rf_test_fail(__FILE__, __LINE__, "%s ray %d: BVH prim %d t %.17g occluded %d, %s prim %d t %.17g occluded %d",
                                 path, k, p[0], p[0] >= 0 ? h[0].t : 0.0, occ[0], m == SCALAR ? "scalar" : "brute force",
                                 p[m], p[m] >= 0 ? h[m].t : 0.0, occ[m]);
                    bad++;
                    break;
                }
        }
        free(rays);
        for (int m = 0; m < KINDS; m++)
            rf_tracer_free(t[m]);
        rf_scene_free(&s);
        scenes++;
    }
    globfree(&g);
    RF_CHECK(scenes >= 18);
}

/* rf_tracer_intersect4 (camera rays in groups, issue 11) gives each lane what
 * rf_tracer_intersect gives its ray, bit for bit: on every shipped scene, with the vector and
 * scalar kernels, brute force and every side seen (two_sided), for groups of four of the rays
 * above with every pattern of idle lanes and start distances of 0 or beyond the first hit. */
static void t_accel_groups_vs_one_ray(void)
{
    glob_t g;
    int scenes = 0;
    long lanes = 0;
    rf_test_shipped_scenes(&g, 1);
    for (size_t i = 0; i < g.gl_pathc; i++) {
        const char *path = g.gl_pathv[i];
        RfScene s;
        char err[512];
        RfTracer *t[TWO_SIDED + 1] = {NULL, NULL, NULL, NULL};
        RF_CHECK_EQ_INT(rf_scene_load(path, NULL, &s, err, sizeof err), RF_OK);
        if (make_tracers(&s, t, TWO_SIDED + 1) != RF_OK) {
            rf_test_fail(__FILE__, __LINE__, "%s: tracers", path);
            continue;
        }
        int max = ray_budget(&s, 1500000L, 1200);
        RfRay *rays = malloc(sizeof *rays * (size_t)max);
        RfTestRng rng = {99 + i};
        int n = scene_rays(&s, t[VECTOR], &rng, rays, max - 8) & ~3, bad = 0; /* whole groups */
        /* and rays no one should send, two groups of them with ordinary rays between: NaN and
         * infinite components, a zero direction */
        const RfRay odd[4] = {{{NAN, 0, 0}, {0, 0, -1}}, {{0, 0, 0}, {0, NAN, 1}},
                              {{0, 1, 0}, {0, 0, 0}}, {{0, 1, 0}, {INFINITY, 1, 0}}};
        for (int k = 0; k < 8; k++)
            rays[n + k] = k % 2 ? odd[k / 2] : rays[(k * 7) % (n > 0 ? n : 1)];
        n += 8;
        for (int m = 0; m <= TWO_SIDED && !bad; m++)
            for (int k0 = 0; k0 + 4 <= n && !bad; k0 += 4) {
                unsigned active = (unsigned)(k0 / 4) % 15u + 1u; /* 1 .. 15 in turn */
                double t_min[4];
                RfSurfaceHit one[4], four[4];
                int p[4];
                for (int l = 0; l < 4; l++) {
                    t_min[l] = 0.0;
                    if ((k0 / 4 + l) % 3 == 0) { /* from just beyond the first hit: the far side */
                        RfSurfaceHit h;
                        if (rf_tracer_intersect(t[m], &rays[k0 + l], 0, HUGE_VAL, &h) >= 0)
                            t_min[l] = h.t * (1.0 + 1e-9);
                    }
                    p[l] = rf_tracer_intersect(t[m], &rays[k0 + l], t_min[l], HUGE_VAL, &one[l]);
                }
                unsigned hit = rf_tracer_intersect4(t[m], &rays[k0], active, t_min, four);
                for (int l = 0; l < 4; l++) {
                    int on = (active >> l) & 1, got = on && ((hit >> l) & 1) ? four[l].prim : -1;
                    if (!on)
                        continue;
                    lanes++;
                    rf_test_checks++;
                    if (((hit >> l) & 1) != (p[l] >= 0) || !same_hit(p[l], &one[l], got, &four[l]) ||
                        (p[l] >= 0 && four[l].scale != one[l].scale)) {
                        rf_test_fail(__FILE__, __LINE__, "%s tracer %d ray %d lane %d: one ray prim %d t %.17g, group prim %d t %.17g",
                                     path, m, k0 + l, l, p[l], p[l] >= 0 ? one[l].t : 0.0, got, got >= 0 ? four[l].t : 0.0);
                        bad++;
                    }
                }
                if (hit & ~active) {
                    rf_test_fail(__FILE__, __LINE__, "%s: idle lanes reported hit (%x of %x)", path, hit, active);
                    bad++;
                }
            }
        free(rays);
        for (int m = 0; m <= TWO_SIDED; m++)
            rf_tracer_free(t[m]);
        rf_scene_free(&s);
        scenes++;
    }
    globfree(&g);
    RF_CHECK(scenes >= 18);
    RF_CHECK(lanes > 25000);
}

/* rf_sphere_roots4 against rf_sphere_roots, every output bit for bit: random rays at spheres
 * near and far, and the rare cases the lanes hand back (a tangent, q = 0 at an origin on the
 * sphere, a zero direction, NaN and infinite inputs) mixed into groups with ordinary rays. */
static void t_accel_sphere_lanes(void)
{
    RfTestRng rng = {4242};
    const RfSphere spheres[3] = {{{0.1, 1, -1.3}, 1.0}, {{0, 0, 0}, 1.0}, {{1e6, -3e5, 2e5}, 0.5}};
    const RfRay odd[6] = {
        {{1, 0, -5}, {0, 0, 1}},          /* tangent: D/4 = 0 */
        {{1, 0, 0}, {0, 0, 1}},           /* on the sphere, tangent: q = 0 */
        {{0, 0, -5}, {0, 0, 0}},          /* a = 0 */
        {{NAN, 0, -5}, {0, 0, 1}},        /* NaN */
        {{0, 0, -5}, {0, INFINITY, 1}},   /* an infinite direction */
        {{0.5, 0.5, 0}, {0, 0, 1}},       /* inside */
    };
    long same = 0, real = 0;
    for (int trial = 0; trial < 20000; trial++) {
        const RfSphere *sp = &spheres[trial % 3];
        RfRay rays[4];
        RfRay4 r4;
        for (int l = 0; l < 4; l++) {
            if (trial % 7 == 0 && l == trial % 4) {
                rays[l] = odd[(trial / 7) % 6];
            } else {
                RfVec3 o = rf_vec3(rf_test_uniform(&rng, -8, 8), rf_test_uniform(&rng, -8, 8), rf_test_uniform(&rng, 4, 9));
                RfVec3 aim = rf_vec3_add(sp->center, rf_vec3(rf_test_uniform(&rng, -1.2, 1.2) * sp->radius,
                                                             rf_test_uniform(&rng, -1.2, 1.2) * sp->radius,
                                                             rf_test_uniform(&rng, -1.2, 1.2) * sp->radius));
                RfVec3 d = rf_vec3_sub(aim, o);
                rays[l] = rf_ray(o, trial % 2 ? rf_vec3_normalize(d) : d);
            }
            rf_ray4_set(&r4, l, &rays[l]);
        }
        RfSphereRoots got[4];
        unsigned ok = rf_sphere_roots4(&r4, sp, got);
        for (int l = 0; l < 4; l++) {
            RfSphereRoots want;
            int w = rf_sphere_roots(&rays[l], sp, &want);
            rf_test_checks++;
            if (w != (int)((ok >> l) & 1) ||
                (w && (memcmp(want.t, got[l].t, sizeof want.t) != 0 || memcmp(&want.v, &got[l].v, sizeof want.v) != 0 ||
                       memcmp(&want.sq, &got[l].sq, sizeof want.sq) != 0 || memcmp(&want.a, &got[l].a, sizeof want.a) != 0))) {
                rf_test_fail(__FILE__, __LINE__, "trial %d lane %d: one ray %d t %.17g %.17g, lanes %d t %.17g %.17g", trial, l,
                             w, w ? want.t[0] : 0.0, w ? want.t[1] : 0.0, (int)((ok >> l) & 1), got[l].t[0], got[l].t[1]);
                return;
            }
            same++;
            real += w;
        }
    }
    RF_CHECK_EQ_INT(same, 80000);
    RF_CHECK(real > 30000 && real < 79000); /* hits and misses both */
}

/* Small renders of every shipped scene: the scalar kernels and brute force give the image of
 * the vector kernels, bit for bit (brute force where it stays cheap). */
static void t_accel_images(void)
{
    glob_t g;
    rf_test_shipped_scenes(&g, 0);
    for (size_t i = 0; i < g.gl_pathc; i++) {
        RfScene s;
        if (!rf_test_load_scene(g.gl_pathv[i], &s))
            continue;
        RfTriangleCount tc = rf_scene_triangle_count(&s);
        RfImage img[KINDS];
        for (int m = 0; m < KINDS; m++) {
            RfRenderOptions o = rf_render_options_default();
            RfRenderStats st;
            o.width = 40;
            o.height = 30;
            o.threads = 2;
            o.samples = 1;
            o.accel.scalar = m == SCALAR;
            o.accel.brute_force = m == BRUTE;
            img[m].data = NULL;
            if (m == BRUTE && tc.rendered + s.prim_count > 12000)
                continue;
            RF_CHECK_EQ_INT(rf_render(&s, &o, &img[m], &st), RF_OK);
            if (m > 0 && img[m].data && img[0].data)
                RF_CHECK(memcmp(img[0].data, img[m].data, sizeof(float) * 3 * 40 * 30) == 0);
        }
        for (int m = 0; m < KINDS; m++)
            if (img[m].data)
                rf_image_free(&img[m]);
        rf_scene_free(&s);
    }
    globfree(&g);
}

/* The tie rule on a shared edge: a unit square in z = 0 cut along its diagonal into two
 * triangles of different materials; rays straight down through dyadic points of the diagonal
 * meet both at t = 1 exactly, and the lower primitive index wins, whichever triangle comes first
 * in the file, with the BVH as with brute force. */
static void t_accel_tie_rule(void)
{
    for (int order = 0; order < 2; order++) {
        char text[512];
        const char *a = "polygon 3  0 0 0  1 0 0  1 1 0", *b = "polygon 3  0 0 0  1 1 0  0 1 0";
        snprintf(text, sizeof text,
                 "camera eye 0.5 0.5 3  target 0.5 0.5 0  up 0 1 0  fov 40\n"
                 "material first kd 1 0 0\n%s\nmaterial second kd 0 1 0\n%s\n",
                 order ? b : a, order ? a : b);
        RfScene s;
        char err[512];
        RF_CHECK_EQ_INT(rf_scene_read_rf("tie.rf", text, strlen(text), &s, err, sizeof err), RF_OK);
        RfTracer *t[KINDS];
        RF_CHECK_EQ_INT(make_tracers(&s, t, KINDS), RF_OK);
        int ties = 0, ok = 1;
        for (int k = 1; k < 64; k++) {
            double x = k / 64.0;
            RfRay r = rf_ray(rf_vec3(x, x, 1), rf_vec3(0, 0, -1));
            for (int m = 0; m < KINDS; m++) {
                RfSurfaceHit h;
                int p = rf_tracer_intersect(t[m], &r, 0, HUGE_VAL, &h);
                ok &= p == 0 && h.t == 1.0 && h.material == 0;
                ties += m == 0 && p == 0;
            }
        }
        RF_CHECK(ok);
        RF_CHECK_EQ_INT(ties, 63);
        for (int m = 0; m < KINDS; m++)
            rf_tracer_free(t[m]);
        rf_scene_free(&s);
    }
}


/* The watertight test's exact edge sign through the whole tracer (a second guard besides
 * tests/test_raytrace.c): two triangles share the edge P = (1+e, 1+2e, 1), Q = (-1, -1-e, 1)
 * (e = 2^-52), the ray from the origin along +z passes 2^-104-ish to one side of it (the rounded
 * edge products agree, the exact ones do not). The one on the far side comes first in the file:
 * were the edge taken as hit, both would be met at t = 1 and the tie rule would pick it. With
 * the BVH (vector and scalar kernels) and brute force the ray meets the near-side triangle only. */
static void t_accel_exact_edge_sign(void)
{
    const double e = 0x1p-52;
    char text[1024], err[256];
    snprintf(text, sizeof text,
             "camera eye 0 0 -5 target 0 0 0 up 0 1 0 fov 40\n"
             "material outside kd 1 0 0\ntriangle %.17g %.17g 1  %.17g %.17g 1  1 -1 1\n"
             "material inside kd 0 1 0\ntriangle %.17g %.17g 1  %.17g %.17g 1  -1 1 1\n",
             1 + e, 1 + 2 * e, -1.0, -(1 + e), 1 + e, 1 + 2 * e, -1.0, -(1 + e));
    RfScene s;
    RfTracer *t[KINDS];
    if (rf_scene_read_rf("edge.rf", text, strlen(text), &s, err, sizeof err) != RF_OK || make_tracers(&s, t, KINDS) != RF_OK) {
        rf_test_fail(__FILE__, __LINE__, "%s", err);
        return;
    }
    RfRay ray = rf_ray(rf_vec3(0, 0, 0), rf_vec3(0, 0, 1));
    for (int m = 0; m < KINDS; m++) {
        RfSurfaceHit h;
        int p = rf_tracer_intersect(t[m], &ray, 0.0, HUGE_VAL, &h);
        RF_CHECK_EQ_INT(p, 1);
        RF_CHECK(h.t == 1.0 && h.material == 1);
        rf_tracer_free(t[m]);
    }
    rf_scene_free(&s);
}

/* Non-convex polygons are watertight against their neighbours (docs/verify.md): the closed
 * star prism of tests/data/verify/star_prism.nff (star top and bottom, quad sides, faces turned
 * inward), rays from a point inside it through 64 points of every edge of every face, and the
 * documented ray that leaked (o, d in hex). Every ray must hit the prism, seen from inside
 * (front: the faces are turned inward), with the BVH's kernels and brute force. The tracer's
 * old plane + crossing-number test let 24.9 % of such edge rays out. */
static void t_accel_nonconvex_watertight(void)
{
    RfScene s;
    if (!rf_test_load_scene(rf_test_data("verify/star_prism.nff"), &s))
        return;
    RfTracer *t[KINDS];
    if (make_tracers(&s, t, KINDS) != RF_OK) {
        rf_test_fail(__FILE__, __LINE__, "tracers");
        rf_scene_free(&s);
        return;
    }
    RfVec3 o = rf_vec3(0x1.0b03b41333333p-4, 0x1.4d866fb333333p-5, 0x1.553c9ba333334p-1);
    int rays = 0, leaks = 0, nonconvex = 0;
    for (size_t i = 0; i < s.prim_count; i++) {
        const RfPrimitive *p = &s.prims[i];
        nonconvex += (p->flags & RF_PRIM_NONCONVEX) != 0;
        for (int k = 0; k < p->u.poly.count; k++) {
            RfVec3 a = s.vertices[p->u.poly.first + (size_t)k],
                   b = s.vertices[p->u.poly.first + (size_t)((k + 1) % p->u.poly.count)];
            for (int j = 0; j < 64; j++) {
                RfVec3 q = rf_vec3_add(a, rf_vec3_scale(rf_vec3_sub(b, a), (j + 0.5) / 64.0));
                RfRay ray = rf_ray(o, rf_vec3_sub(q, o));
                for (int m = 0; m < KINDS; m++) {
                    RfSurfaceHit h;
                    leaks += rf_tracer_intersect(t[m], &ray, 0.0, HUGE_VAL, &h) < 0;
                }
                rays++;
            }
        }
    }
    RfRay doc = rf_ray(o, rf_vec3(0x1.041beab7f999ap-1, -0x1.8448e4a14cccdp-3, 0x1.5586c8b999998p-2));
    for (int m = 0; m < KINDS; m++) {
        RfSurfaceHit h;
        leaks += rf_tracer_intersect(t[m], &doc, 0.0, HUGE_VAL, &h) < 0;
        rf_tracer_free(t[m]);
    }
    RF_CHECK_EQ_INT(nonconvex, 2);
    RF_CHECK(rays > 2000);
    RF_CHECK_EQ_INT(leaks, 0);
    rf_scene_free(&s);
}

/* Rays exactly through the vertices of small triangles (o = v - s d with d of a few binary
 * digits, so o + s d = v exactly): the ray meets the triangle's box at its corner, where the float
 * slab distances from two axes meet. The BVH must still report the vertex hit that brute force
 * finds. From far away (s = 2^12) the slab test's outward rounding of 1/d and of the origin keeps
 * the corner; from near by (s = 2^-10, the triangles near 1000 where a float's ulp is 2^-14)
 * the distances are tiny and only the box's own outward rounding to float keeps it (bvh_build.c:
 * a box rounded to nearest can lose the vertex; a planted bug, tools/mutate.sh). */
static void t_accel_far_vertex_rays(void)
{
    uint64_t r = 12345;
    int hits = 0, wrong = 0;
    for (int tri = 0; tri < 120; tri++) {
        const double dist = tri < 60 ? 4096.0 : 0x1p-10, base = tri < 60 ? 0.0 : 1000.0;
        /* one triangle per scene: its box is the BVH node's, so its vertices are box corners */
        double v[3][3];
        char text[1024], err[256];
        size_t n = (size_t)snprintf(text, sizeof text, "camera eye 0 0 5 target 0 0 0 up 0 1 0 fov 40\ntriangle");
        for (int k = 0; k < 3; k++)
            for (int a = 0; a < 3; a++) {
                r = r * 6364136223846793005ULL + 1442695040888963407ULL;
                v[k][a] = base + (double)((r >> 33) % 1000) / 997.0 + 0.1 * (tri % 60); /* not binary fractions */
                n += (size_t)snprintf(text + n, sizeof text - n, " %.17g", v[k][a]);
            }
        snprintf(text + n, sizeof text - n, "\n");
        RfScene s;
        RfTracer *t[KINDS];
        if (rf_scene_read_rf("t.rf", text, strlen(text), &s, err, sizeof err) != RF_OK || make_tracers(&s, t, KINDS) != RF_OK) {
            rf_test_fail(__FILE__, __LINE__, "%s", err);
            return;
        }
        for (int k = 0; k < 3; k++)
            for (int dir = 0; dir < 64; dir++) {
                /* every sign pattern, so that some rays only touch the box at the vertex */
                RfVec3 d = rf_vec3((dir & 1 ? 1 : -1) * (1 + 0.25 * ((dir >> 3) & 1)),
                                   (dir & 2 ? 1 : -1) * (1 + 0.5 * ((dir >> 4) & 1)),
                                   (dir & 4 ? 1 : -1) * (0.75 + 0.125 * ((dir >> 5) & 1)));
                RfVec3 vv = rf_vec3(v[k][0], v[k][1], v[k][2]);
                RfRay ray = rf_ray(rf_vec3_sub(vv, rf_vec3_scale(d, dist)), d);
                RfSurfaceHit h[KINDS];
                int p[KINDS];
                for (int q = 0; q < KINDS; q++)
                    p[q] = rf_tracer_intersect(t[q], &ray, 0.0, HUGE_VAL, &h[q]);
                hits += p[BRUTE] >= 0;
                wrong += !same_hit(p[VECTOR], &h[VECTOR], p[BRUTE], &h[BRUTE]) ||
                         !same_hit(p[SCALAR], &h[SCALAR], p[BRUTE], &h[BRUTE]);
            }
        for (int q = 0; q < KINDS; q++)
            rf_tracer_free(t[q]);
        rf_scene_free(&s);
    }
    RF_CHECK_EQ_INT(wrong, 0);
    RF_CHECK(hits > 10000); /* the watertight test counts a vertex as a hit */
}

const RfTest rf_tests_accel[] = {
    {"accel_tie_rule", t_accel_tie_rule},
    {"accel_far_vertex_rays", t_accel_far_vertex_rays},
    {"accel_exact_edge_sign", t_accel_exact_edge_sign},
    {"accel_nonconvex_watertight", t_accel_nonconvex_watertight},
    {"accel_scenes_vs_brute_force", t_accel_scenes_vs_brute_force},
    {"accel_images_identical", t_accel_images},
    {"accel_groups_vs_one_ray", t_accel_groups_vs_one_ray},
    {"accel_sphere_lanes", t_accel_sphere_lanes},
    RF_TEST_END,
};
