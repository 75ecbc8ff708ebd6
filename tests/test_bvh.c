/* The BVH against brute force, ray by ray: the same nearest hit (same key, same t bit for bit)
 * and the same occlusion answer, for triangles and cones (tested by the BVH) mixed with spheres
 * (tested by the BVH or by the caller), with the vector and the scalar kernels, on random
 * scenes, degenerate ones and rays through shared edges. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "refray/bvh.h"
#include "rf_test.h"

typedef struct {
    int n_tris, n_balls;
    RfTriangle *tris;
    int *sides;
    RfSphere *balls;
    long tests; /* caller's item tests */
    int n_cones; /* after the spheres, with their sides */
    RfCone *cones;
    int *cone_sides;
} Scene;

static int item_total(const Scene *s) { return s->n_tris + s->n_balls + s->n_cones; }

/* The first hit of cone i at t >= t_min whose side a nearest query sees (a hidden side passes
 * the ray on), or, sided = 0, any hit. */
static int cone_first(const Scene *s, int i, const RfRay *ray, double t_min, double t_max, int sided, RfHit *h)
{
    RfConeFrame f = rf_cone_frame(s->cones[i]);
    while (rf_intersect_cone_framed(ray, &s->cones[i], &f, t_min, t_max, 1, h)) {
        int side = s->cone_sides[i];
        if (!sided || side == RF_BVH_SEE_BOTH || (rf_vec3_dot(ray->dir, h->normal) < 0.0) == (side == RF_BVH_SEE_FRONT))
            return 1;
        t_min = nextafter(h->t, HUGE_VAL);
    }
    return 0;
}

static uint64_t key_of(int item) { return (uint64_t)item + 1; }

/* Triangles, then spheres: every other sphere the BVH tests itself (two-sided), the rest through
 * the callback. */
static void describe(void *ctx, int item, RfBvhItem *out)
{
    const Scene *s = ctx;
    out->key = key_of(item);
    out->user = (uint32_t)item;
    if (item < s->n_tris) {
        out->kind = RF_BVH_TRIANGLE;
        out->tri = s->tris[item];
        out->sides = s->sides[item];
        return;
    }
    if (item >= s->n_tris + s->n_balls) {
        int i = item - s->n_tris - s->n_balls;
        const RfCone *c = &s->cones[i];
        out->kind = RF_BVH_CONE;
        out->cone = *c;
        out->frame = rf_cone_frame(*c);
        out->sides = s->cone_sides[i];
        double r = fmax(c->base_radius, c->apex_radius); /* a loose box is still a box */
        out->box.lo = rf_vec3(fmin(c->base.x, c->apex.x) - r, fmin(c->base.y, c->apex.y) - r, fmin(c->base.z, c->apex.z) - r);
        out->box.hi = rf_vec3(fmax(c->base.x, c->apex.x) + r, fmax(c->base.y, c->apex.y) + r, fmax(c->base.z, c->apex.z) + r);
        return;
    }
    const RfSphere *b = &s->balls[item - s->n_tris];
    out->sides = RF_BVH_SEE_BOTH;
    if (item % 2) {
        out->kind = RF_BVH_SPHERE;
        out->sphere = *b;
        return;
    }
    RfVec3 e = rf_vec3(b->radius, b->radius, b->radius);
    out->kind = RF_BVH_OTHER;
    out->box.lo = rf_vec3_sub(b->center, e);
    out->box.hi = rf_vec3_add(b->center, e);
}

static int ball_hit(void *ctx, uint64_t key, const RfBvhRay *r, double t_min, double t_max, int inclusive, double *t)
{
    Scene *s = ctx;
    RfHit h;
    s->tests++;
    int i = (int)(key - 1) - s->n_tris;
    if (inclusive)
        t_max = nextafter(t_max, HUGE_VAL);
    if (!rf_intersect_sphere(r->ray, s->balls[i], RF_SPHERE_STABLE, t_min, t_max, &h))
        return 0;
    *t = h.t;
    return 1;
}

/* The reference: every item, in key order, with the double kernels and the same rules. */
static RfBvhHit brute_nearest(const Scene *s, RfRay ray, double t_min, double t_max, int *occluded)
{
    RfBvhHit best;
    memset(&best, 0, sizeof best);
    best.t = t_max;
    RfWatertightRay wr;
    rf_watertight_ray(&ray, &wr);
    *occluded = 0;
    for (int i = 0; i < item_total(s); i++) {
        double t;
        RfHit h;
        if (i >= s->n_tris + s->n_balls) {
            int c = i - s->n_tris - s->n_balls;
            *occluded |= cone_first(s, c, &ray, t_min, t_max, 0, &h);
            if (!cone_first(s, c, &ray, t_min, HUGE_VAL, 1, &h))
                continue;
            t = h.t;
            if (t < best.t)
                best.normal = h.normal;
        } else if (i < s->n_tris) {
            if (!rf_intersect_triangle_watertight(&wr, s->tris[i], t_min, HUGE_VAL, &h))
                continue;
            t = h.t;
            *occluded |= t < t_max;
            if (s->sides[i] != RF_BVH_SEE_BOTH &&
                (rf_vec3_dot(ray.dir, h.normal) < 0.0) != (s->sides[i] == RF_BVH_SEE_FRONT))
                continue;
        } else {
            if (!rf_intersect_sphere(ray, s->balls[i - s->n_tris], RF_SPHERE_STABLE, t_min, HUGE_VAL, &h))
                continue;
            t = h.t;
            *occluded |= t < t_max;
        }
        if (t < best.t) { /* key order: an equal t later never wins */
            best.t = t;
            best.key = key_of(i);
        }
    }
    return best;
}

static RfRay random_ray(RfTestRng *r, double spread)
{
    RfRay ray = rf_ray(rf_vec3(rf_test_uniform(r, -spread, spread), rf_test_uniform(r, -spread, spread),
                               rf_test_uniform(r, -spread, spread)),
                       rf_vec3(rf_test_uniform(r, -1, 1), rf_test_uniform(r, -1, 1), rf_test_uniform(r, -1, 1)));
    return ray;
}

/* Checks rays against brute force with both kernels; returns the caller's tests made. */
static void check_rays(Scene *s, const RfRay *rays, int n, double t_max, const char *what)
{
    for (int scalar = 0; scalar < 2; scalar++) {
        RfBvh bvh;
        RfBvhDesc d = {item_total(s), describe, s, 2, scalar};
        RF_CHECK_EQ_INT(rf_bvh_build(&bvh, &d), RF_OK);
        RF_CHECK(bvh.depth < 64);
        int bad = 0;
        for (int i = 0; i < n && !bad; i++) {
            int occ;
            RfBvhHit want = brute_nearest(s, rays[i], 0.0, t_max, &occ);
            RfBvhRay br;
            rf_bvh_ray_init(&bvh, &rays[i], &br);
            RfBvhHit got;
            memset(&got, 0, sizeof got);
            got.t = t_max;
            rf_bvh_nearest(&bvh, &br, 0.0, &got, ball_hit, s);
            uint64_t occ_key = 0;
            int gocc = rf_bvh_occluded(&bvh, &br, 0.0, t_max, ball_hit, s, &occ_key);
            /* the item reported occludes: it is hit in range */
            if (gocc) {
                int item = (int)(occ_key - 1), occ1 = 0;
                RfHit hh;
                if (item >= s->n_tris + s->n_balls) {
                    occ1 = cone_first(s, item - s->n_tris - s->n_balls, &rays[i], 0.0, t_max, 0, &hh);
                } else if (item < s->n_tris) {
                    RfWatertightRay wr1;
                    rf_watertight_ray(&rays[i], &wr1);
                    occ1 = rf_intersect_triangle_watertight(&wr1, s->tris[item], 0.0, t_max, &hh);
                } else {
                    occ1 = rf_intersect_sphere(rays[i], s->balls[item - s->n_tris], RF_SPHERE_STABLE, 0.0, t_max, &hh);
                }
                RF_CHECK(occ1);
            }
            rf_test_checks++;
            if (got.key != want.key || (want.key && got.t != want.t) || gocc != occ) {
                rf_test_fail(__FILE__, __LINE__, "%s (%s) ray %d: bvh key %llu t %.17g occluded %d, brute force key %llu t %.17g occluded %d",
                             what, scalar ? "scalar" : "vector", i, (unsigned long long)got.key, got.t, gocc,
                             (unsigned long long)want.key, want.t, occ);
                bad = 1;
            }
            /* a triangle's, sphere's or cone's user bits come back with it, a cone's normal too */
            if ((got.tri || got.sphere || got.cone) && got.user != (uint32_t)(got.key - 1))
                rf_test_fail(__FILE__, __LINE__, "%s: user bits %u for key %llu", what, got.user, (unsigned long long)got.key);
            if (got.cone && got.key == want.key &&
                (got.normal.x != want.normal.x || got.normal.y != want.normal.y || got.normal.z != want.normal.z))
                rf_test_fail(__FILE__, __LINE__, "%s: cone normal of key %llu differs", what, (unsigned long long)got.key);
            rf_test_checks += got.cone != NULL;
            /* a triangle's normal, kept by a small BVH (RfBvh.normals) or computed by the side
             * test: rf_triangle_unit_normal's bits; a BVH that keeps them always passes one on */
            if (got.tri) {
                RfVec3 n = rf_triangle_unit_normal(got.tri);
                if (got.has_normal && (got.normal.x != n.x || got.normal.y != n.y || got.normal.z != n.z))
                    rf_test_fail(__FILE__, __LINE__, "%s: triangle normal of key %llu differs", what,
                                 (unsigned long long)got.key);
                if (bvh.normals && !got.has_normal)
                    rf_test_fail(__FILE__, __LINE__, "%s: no kept normal for key %llu", what, (unsigned long long)got.key);
                rf_test_checks++;
            }
        }
        rf_bvh_free(&bvh);
    }
}

/* Random triangles (unit size, every side in turn) and spheres (radii in [rmin, rmax]) in the
 * cube [-extent, extent]^3. */
static void random_tris_balls(Scene *s, RfTestRng *r, double extent, double rmin, double rmax)
{
    for (int i = 0; i < s->n_tris; i++) {
        RfVec3 c = rf_vec3(rf_test_uniform(r, -extent, extent), rf_test_uniform(r, -extent, extent),
                           rf_test_uniform(r, -extent, extent));
        RfVec3 *p[3] = {&s->tris[i].p1, &s->tris[i].p2, &s->tris[i].p3};
        for (int k = 0; k < 3; k++)
            *p[k] = rf_vec3_add(c, rf_vec3(rf_test_uniform(r, -1, 1), rf_test_uniform(r, -1, 1), rf_test_uniform(r, -1, 1)));
        s->sides[i] = i % 3;
    }
    for (int i = 0; i < s->n_balls; i++) {
        s->balls[i].center = rf_vec3(rf_test_uniform(r, -extent, extent), rf_test_uniform(r, -extent, extent),
                                     rf_test_uniform(r, -extent, extent));
        s->balls[i].radius = rf_test_uniform(r, rmin, rmax);
    }
}

/* A scene of nt random triangles and nb random spheres (random_tris_balls); scene_free frees it. */
static Scene random_scene(RfTestRng *r, int nt, int nb, double extent, double rmin, double rmax)
{
    Scene s = {nt, nb, malloc(sizeof(RfTriangle) * (size_t)nt), malloc(sizeof(int) * (size_t)nt),
               malloc(sizeof(RfSphere) * (size_t)nb), 0, 0, NULL, NULL};
    random_tris_balls(&s, r, extent, rmin, rmax);
    return s;
}

static void scene_free(Scene *s)
{
    free(s->tris);
    free(s->sides);
    free(s->balls);
}

static void t_bvh_random(void)
{
    RfTestRng r = {11};
    enum { NT = 3000, NB = 800, RAYS = 6000 };
    Scene s = random_scene(&r, NT, NB, 10, 0.01, 0.5);
    RfRay *rays = malloc(sizeof *rays * RAYS);
    for (int i = 0; i < RAYS; i++) {
        rays[i] = random_ray(&r, 12);
        if (i % 7 == 0) /* axis-parallel rays: two direction components exactly 0 */
            rays[i].dir = rf_vec3(0, 0, i % 2 ? 1 : -1);
    }
    check_rays(&s, rays, RAYS, HUGE_VAL, "random");
    check_rays(&s, rays, RAYS, 6.0, "random, t_max 6");
    /* the tree must pay off: far fewer sphere tests than brute force would make (half the
     * spheres go through the callback) */
    RF_CHECK(s.tests < 2L * 2 * 3 * RAYS * (NB / 2) / 10);
    free(rays);
    scene_free(&s);
}

/* A scene large enough (more than 65,536 items) that the build bins and partitions its top
 * ranges on every thread (bvh_build.c, PAR_BIN): the answers as brute force gives them. */
static void t_bvh_large(void)
{
    RfTestRng r = {29};
    enum { NT = 140000, NB = 2000, RAYS = 160 };
    Scene s = random_scene(&r, NT, NB, 60, 0.05, 0.8);
    RfRay *rays = malloc(sizeof *rays * RAYS);
    for (int i = 0; i < RAYS; i++)
        rays[i] = random_ray(&r, 70);
    check_rays(&s, rays, RAYS, HUGE_VAL, "large");
    free(rays);
    scene_free(&s);
}

/* A grid of squares split into triangles, vertices on a dyadic grid (exact), rays aimed exactly
 * at edges and vertices: both triangles of an edge are hit at the same t and the lower key wins,
 * with the BVH as with brute force; far from the origin as well (the float filter's bound). */
static void t_bvh_shared_edges(void)
{
    enum { N = 24 };
    const double offsets[] = {0.0, 1e5, 3e7};
    for (size_t o = 0; o < sizeof offsets / sizeof offsets[0]; o++) {
        Scene s = {2 * N * N, 0, malloc(sizeof(RfTriangle) * 2 * N * N), malloc(sizeof(int) * 2 * N * N), NULL, 0, 0, NULL, NULL};
        double h = 0.125, off = offsets[o];
        int t = 0;
        for (int i = 0; i < N; i++)
            for (int j = 0; j < N; j++) {
                RfVec3 p00 = rf_vec3(off + i * h, off + j * h, off), p10 = rf_vec3(off + (i + 1) * h, off + j * h, off);
                RfVec3 p01 = rf_vec3(off + i * h, off + (j + 1) * h, off), p11 = rf_vec3(off + (i + 1) * h, off + (j + 1) * h, off);
                RfTriangle a = {p00, p10, p11}, b = {p00, p11, p01};
                s.tris[t] = a;
                s.sides[t++] = RF_BVH_SEE_BOTH;
                s.tris[t] = b;
                s.sides[t++] = RF_BVH_SEE_FRONT;
            }
        RfTestRng r = {13};
        enum { RAYS = 3000 };
        RfRay *rays = malloc(sizeof *rays * RAYS);
        for (int i = 0; i < RAYS; i++) {
            /* a grid point (a vertex) or an edge midpoint, from a random origin above or below */
            int gi = (int)rf_test_uniform(&r, 1, N - 1), gj = (int)rf_test_uniform(&r, 1, N - 1);
            RfVec3 aim = rf_vec3(off + gi * h + (i % 3 == 1 ? h / 2 : 0), off + gj * h + (i % 3 == 2 ? h / 2 : 0), off);
            if (i % 3 == 0 && i % 2)
                aim = rf_vec3(off + (gi + 0.5) * h, off + (gj + 0.5) * h, off); /* the diagonal */
            RfVec3 from = rf_vec3(aim.x + rf_test_uniform(&r, -2, 2), aim.y + rf_test_uniform(&r, -2, 2),
                                  off + (i % 4 == 0 ? -1.0 : 1.0) * rf_test_uniform(&r, 0.5, 3));
            rays[i] = rf_ray(from, rf_vec3_sub(aim, from));
        }
        check_rays(&s, rays, RAYS, HUGE_VAL, offsets[o] == 0 ? "shared edges" : "shared edges far away");
        free(rays);
        free(s.tris);
        free(s.sides);
    }
}

/* The ray's slab constants (rf_bvh_ray_init, lanes of AVX where built with it) against their
 * definition written out per axis here: the origin rounded to float and moved outward by
 * |f| 2^-23 + 2^-126, 1/d in float shrunk and grown by 2^-21, the near factor clamped to 2^127,
 * on rays with zero (+0 and -0), tiny, huge and infinite direction components. */
static void t_bvh_ray_constants(void)
{
    static const double vals[] = {0.0, -0.0, 1.0, -1.0, 0.3, -7.25, 1e-30, -1e-300, 1e30, -3e38, 5e-324, 1e300};
    const size_t nv = sizeof vals / sizeof vals[0];
    RfBvh bvh;
    memset(&bvh, 0, sizeof bvh);
    uint64_t st = 12345;
    for (int i = 0; i < 4000; i++) {
        double o[3], d[3];
        for (int a = 0; a < 3; a++) {
            st = st * 6364136223846793005ULL + 1442695040888963407ULL;
            o[a] = vals[(st >> 33) % nv] * (i % 3 ? 1.0 : 3.7);
            d[a] = vals[(st >> 41) % nv] * (i % 5 ? 1.0 : 0.61);
        }
        RfBvhRay r;
        rf_bvh_ray_init(&bvh, &(RfRay){rf_vec3(o[0], o[1], o[2]), rf_vec3(d[0], d[1], d[2])}, &r);
        for (int a = 0; a < 3; a++) {
            int neg = signbit(d[a]) != 0;
            float f = (float)o[a], w = fabsf(f) * 0x1p-23f + 0x1p-126f, up = f + w, down = f - w;
            float fi = (float)(1.0 / d[a]), near = fi * (1.0f - 0x1p-21f), far = fi * (1.0f + 0x1p-21f);
            float inv0 = fabsf(near) <= 0x1p127f ? near : neg ? -0x1p127f : 0x1p127f;
            float org0 = neg ? down : up, org1 = neg ? up : down; /* bit for bit: NaN too (inf - inf) */
            size_t rb = 8 * sizeof(float); /* a row: the 8 children's planes */
            int ok = r.rows[a] == (size_t)(2 * a + neg) * rb && r.rows[3 + a] == (size_t)(2 * a + 1 - neg) * rb && memcmp(&r.org[0][a], &org0, sizeof org0) == 0 &&
                     memcmp(&r.org[1][a], &org1, sizeof org1) == 0 && memcmp(&r.inv[0][a], &inv0, sizeof inv0) == 0 &&
                     memcmp(&r.inv[1][a], &far, sizeof far) == 0;
            if (!ok)
                rf_test_fail(__FILE__, __LINE__, "axis %d of o = %g, d = %g: org %a %a, inv %a %a", a, o[a], d[a],
                             r.org[0][a], r.org[1][a], r.inv[0][a], r.inv[1][a]);
            rf_test_checks++;
        }
    }
}

static void t_bvh_degenerate(void)
{
    RfTestRng r = {12};
    RfBvh bvh;
    /* empty */
    Scene e = {0, 0, NULL, NULL, NULL, 0, 0, NULL, NULL};
    RfBvhDesc d = {0, describe, &e, 1, 0};
    RF_CHECK_EQ_INT(rf_bvh_build(&bvh, &d), RF_OK);
    RfBvhRay br;
    RfBvhHit best;
    memset(&best, 0, sizeof best);
    best.t = HUGE_VAL;
    rf_bvh_ray_init(&bvh, &(RfRay){rf_vec3(0, 0, 0), rf_vec3(1, 0, 0)}, &br);
    RF_CHECK_EQ_INT(rf_bvh_nearest(&bvh, &br, 0, &best, ball_hit, &e), 0);
    RF_CHECK_EQ_INT(rf_bvh_occluded(&bvh, &br, 0, HUGE_VAL, ball_hit, &e, NULL), 0);
    rf_bvh_free(&bvh);
    /* 300 identical spheres and 300 identical triangles: no SAH split exists */
    enum { N = 300 };
    Scene s = {N, N, malloc(sizeof(RfTriangle) * N), malloc(sizeof(int) * N), malloc(sizeof(RfSphere) * N), 0, 0, NULL, NULL};
    for (int i = 0; i < N; i++) {
        s.balls[i].center = rf_vec3(1, 2, 3);
        s.balls[i].radius = 0.5;
        RfTriangle t = {rf_vec3(0, 0, 0), rf_vec3(1, 0, 0), rf_vec3(0, 1, 0)};
        s.tris[i] = t;
        s.sides[i] = RF_BVH_SEE_BOTH;
    }
    RfRay rays[500];
    for (int i = 0; i < 500; i++)
        rays[i] = random_ray(&r, 4);
    check_rays(&s, rays, 500, HUGE_VAL, "coincident items");
    /* non-finite boxes and vertices are refused */
    s.balls[7].radius = NAN;
    RfBvhDesc bad = {2 * N, describe, &s, 1, 0};
    RF_CHECK_EQ_INT(rf_bvh_build(&bvh, &bad), RF_ERR_DOMAIN);
    RF_CHECK(bvh.nodes == NULL);
    s.balls[7].radius = 0.5;
    s.tris[5].p2.y = INFINITY;
    RF_CHECK_EQ_INT(rf_bvh_build(&bvh, &bad), RF_ERR_DOMAIN);
    free(s.tris);
    free(s.sides);
    free(s.balls);
}

/* Small scenes: the root's free slots. A room of five quads (ten triangles, as scenes/soft.rf)
 * and two spheres: the binary SAH keeps four of the quads in one leaf (every two-way cut of them
 * has a box as large as the room), the root's refinement gives each quad its own leaf, so the
 * tree is one node with five one-block triangle leaves (three blocks without it). Then random
 * scenes of 1 to 12 items, where leaves are cut into chains of every shape, against brute force. */
static void t_bvh_small_root(void)
{
    static const double quads[5][4][3] = {
        {{-1, 0, -1}, {-1, 0, 1}, {1, 0, 1}, {1, 0, -1}},  {{-1, 2, -1}, {1, 2, -1}, {1, 2, 1}, {-1, 2, 1}},
        {{-1, 0, -1}, {1, 0, -1}, {1, 2, -1}, {-1, 2, -1}}, {{-1, 0, -1}, {-1, 2, -1}, {-1, 2, 1}, {-1, 0, 1}},
        {{1, 0, -1}, {1, 0, 1}, {1, 2, 1}, {1, 2, -1}}};
    RfTriangle tris[10];
    int sides[10];
    RfSphere balls[2] = {{{-0.4, 0.4, -0.35}, 0.4}, {{0.45, 0.3, 0.45}, 0.3}};
    for (int q = 0; q < 5; q++)
        for (int h = 0; h < 2; h++) {
            const double *a = quads[q][0], *b = quads[q][1 + h], *c = quads[q][2 + h];
            RfTriangle t = {rf_vec3(a[0], a[1], a[2]), rf_vec3(b[0], b[1], b[2]), rf_vec3(c[0], c[1], c[2])};
            tris[2 * q + h] = t;
            sides[2 * q + h] = RF_BVH_SEE_BOTH;
        }
    Scene room = {10, 2, tris, sides, balls, 0, 0, NULL, NULL};
    RfBvh bvh;
    RfBvhDesc d = {12, describe, &room, 1, 0};
    RF_CHECK_EQ_INT(rf_bvh_build(&bvh, &d), RF_OK);
    RF_CHECK_EQ_INT(bvh.node_count, 1);
    RF_CHECK_EQ_INT(bvh.block_count, 5);
    rf_bvh_free(&bvh);
    RfTestRng r = {13};
    RfRay rays[400];
    for (int i = 0; i < 400; i++) /* from inside the room, as shadow and camera rays are */
        rays[i] = rf_ray(rf_vec3(rf_test_uniform(&r, -1, 1), rf_test_uniform(&r, 0, 2), rf_test_uniform(&r, -1, 1)),
                         rf_vec3(rf_test_uniform(&r, -1, 1), rf_test_uniform(&r, -1, 1), rf_test_uniform(&r, -1, 1)));
    check_rays(&room, rays, 400, HUGE_VAL, "room");
    check_rays(&room, rays, 400, 1.0, "room, t_max 1");
    for (int n = 1; n <= 12; n++)
        for (int rep = 0; rep < 4; rep++) {
            RfSphere few[12];
            Scene s = {0, 0, NULL, NULL, few, 0, 0, NULL, NULL};
            s.n_tris = n > 10 ? 10 : (int)rf_test_uniform(&r, 0, n + 0.999);
            s.n_balls = n - s.n_tris;
            RfTriangle mine[10];
            int mine_sides[10];
            for (int i = 0; i < s.n_tris; i++) { /* the room's triangles, moved apart and scaled */
                RfVec3 off = rf_vec3(rf_test_uniform(&r, -3, 3), rf_test_uniform(&r, -1, 1), rf_test_uniform(&r, -3, 3));
                double sc = rf_test_uniform(&r, 0.1, 2);
                mine[i].p1 = rf_vec3_add(rf_vec3_scale(tris[i].p1, sc), off);
                mine[i].p2 = rf_vec3_add(rf_vec3_scale(tris[i].p2, sc), off);
                mine[i].p3 = rf_vec3_add(rf_vec3_scale(tris[i].p3, sc), off);
                mine_sides[i] = i % 3;
            }
            for (int i = 0; i < s.n_balls; i++) {
                few[i].center = rf_vec3(rf_test_uniform(&r, -3, 3), rf_test_uniform(&r, 0, 2), rf_test_uniform(&r, -3, 3));
                few[i].radius = rf_test_uniform(&r, 0.05, 1);
            }
            s.tris = mine;
            s.sides = mine_sides;
            RfRay sr[200];
            for (int i = 0; i < 200; i++)
                sr[i] = random_ray(&r, 4);
            check_rays(&s, sr, 200, HUGE_VAL, "small scene");
            check_rays(&s, sr, 200, 2.0, "small scene, t_max 2");
        }
}

/* Cones tested by the BVH itself (RF_BVH_CONE), among triangles and spheres: open cylinders and
 * cones of every side (front, back, both), random axes, rays from inside and outside. */
static void t_bvh_cones(void)
{
    RfTestRng r = {17};
    enum { NT = 300, NB = 100, NC = 600, RAYS = 5000 };
    Scene s = {NT, NB, malloc(sizeof(RfTriangle) * NT), malloc(sizeof(int) * NT), malloc(sizeof(RfSphere) * NB), 0,
               NC, malloc(sizeof(RfCone) * NC), malloc(sizeof(int) * NC)};
    random_tris_balls(&s, &r, 6, 0.05, 0.6);
    for (int i = 0; i < NC; i++) {
        RfCone *c = &s.cones[i];
        c->base = rf_vec3(rf_test_uniform(&r, -6, 6), rf_test_uniform(&r, -6, 6), rf_test_uniform(&r, -6, 6));
        c->apex = rf_vec3_add(c->base, rf_vec3(rf_test_uniform(&r, -2, 2), rf_test_uniform(&r, -2, 2), rf_test_uniform(&r, -2, 2)));
        c->base_radius = rf_test_uniform(&r, 0.05, 0.8);
        c->apex_radius = i % 4 == 0 ? 0.0 : i % 4 == 1 ? c->base_radius : rf_test_uniform(&r, 0.0, 0.8);
        s.cone_sides[i] = i % 3;
    }
    RfRay *rays = malloc(sizeof *rays * RAYS);
    for (int i = 0; i < RAYS; i++) {
        rays[i] = random_ray(&r, 7);
        if (i % 5 == 0) /* from a cone's axis: inside it */
            rays[i].origin = rf_vec3_scale(rf_vec3_add(s.cones[i % NC].base, s.cones[i % NC].apex), 0.5);
    }
    long before = rf_test_checks;
    check_rays(&s, rays, RAYS, HUGE_VAL, "cones");
    check_rays(&s, rays, RAYS, 3.0, "cones, t_max 3");
    RF_CHECK(rf_test_checks - before > 2 * 2 * RAYS + 500); /* many nearest hits were cones */
    free(rays);
    free(s.tris);
    free(s.sides);
    free(s.balls);
    free(s.cones);
    free(s.cone_sides);
}

/* rf_bvh_cone_empty against brute force: square pyramids of random apex, axis and width among
 * sparse triangles and spheres; where it answers "empty", rays spread over the pyramid (its
 * edges and corners too) hit nothing, by brute force and by the BVH. Both answers must occur,
 * and the degenerate inputs answer "maybe" (0) or, for an empty BVH, "empty". */
static void t_bvh_cone_empty(void)
{
    RfTestRng r = {17};
    enum { NT = 300, NB = 60, CONES = 400, RAYS = 64 };
    Scene s = {NT, NB, malloc(sizeof(RfTriangle) * NT), malloc(sizeof(int) * NT), malloc(sizeof(RfSphere) * NB), 0, 0, NULL, NULL};
    random_tris_balls(&s, &r, 10, 0.05, 0.4);
    for (int i = 0; i < NT; i++) { /* small triangles: room between them */
        RfTriangle *t = &s.tris[i];
        t->p2 = rf_vec3_add(t->p1, rf_vec3_scale(rf_vec3_sub(t->p2, t->p1), 0.3));
        t->p3 = rf_vec3_add(t->p1, rf_vec3_scale(rf_vec3_sub(t->p3, t->p1), 0.3));
    }
    RfBvh bvh;
    RfBvhDesc d = {item_total(&s), describe, &s, 2, 0};
    RF_CHECK_EQ_INT(rf_bvh_build(&bvh, &d), RF_OK);
    int empty = 0;
    for (int c = 0; c < CONES; c++) {
        RfVec3 apex = rf_vec3(rf_test_uniform(&r, -14, 14), rf_test_uniform(&r, -14, 14), rf_test_uniform(&r, -14, 14));
        RfVec3 w = rf_vec3_normalize(rf_vec3(rf_test_uniform(&r, -1, 1), rf_test_uniform(&r, -1, 1), rf_test_uniform(&r, -1, 1)));
        RfVec3 u = rf_vec3_normalize(rf_vec3_cross(w, fabs(w.x) < 0.5 ? rf_vec3(1, 0, 0) : rf_vec3(0, 1, 0)));
        RfVec3 v = rf_vec3_cross(w, u);
        double h = rf_test_uniform(&r, 0.005, 0.12); /* half the pyramid's width at distance 1 */
        RfVec3 corner[4], n[4];
        for (int k = 0; k < 4; k++) {
            double a = k == 0 || k == 3 ? -h : h, b = k < 2 ? -h : h;
            corner[k] = rf_vec3_add(w, rf_vec3_add(rf_vec3_scale(u, a), rf_vec3_scale(v, b)));
        }
        for (int k = 0; k < 4; k++) {
            n[k] = rf_vec3_cross(corner[k], corner[(k + 1) % 4]);
            if (rf_vec3_dot(n[k], w) < 0.0)
                n[k] = rf_vec3_neg(n[k]);
        }
        if (!rf_bvh_cone_empty(&bvh, apex, n, 4))
            continue;
        empty++;
        for (int i = 0; i < RAYS; i++) {
            double a = i < 4 ? (i % 2 ? h : -h) : rf_test_uniform(&r, -h, h);
            double b = i < 4 ? (i < 2 ? h : -h) : rf_test_uniform(&r, -h, h);
            RfRay ray = rf_ray(apex, rf_vec3_add(w, rf_vec3_add(rf_vec3_scale(u, a), rf_vec3_scale(v, b))));
            int occluded;
            RfBvhHit ref = brute_nearest(&s, ray, 0.0, HUGE_VAL, &occluded);
            RfBvhRay br;
            rf_bvh_ray_init(&bvh, &ray, &br);
            RfBvhHit best;
            memset(&best, 0, sizeof best);
            best.t = HUGE_VAL;
            int hit = rf_bvh_nearest(&bvh, &br, 0.0, &best, ball_hit, &s) ||
                      rf_bvh_occluded(&bvh, &br, 0.0, HUGE_VAL, ball_hit, &s, NULL);
            if (ref.key != 0 || occluded || hit)
                rf_test_fail(__FILE__, __LINE__, "cone %d called empty, ray %d hits (brute force key %llu, BVH %d)", c,
                             i, (unsigned long long)ref.key, hit);
            rf_test_checks++;
        }
    }
    /* both answers occur (the scene is sparse, the apexes inside and around it) */
    RF_CHECK(empty > CONES / 5 && empty < CONES * 4 / 5);
    RfVec3 zero[4] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}}, nan4[4] = {{NAN, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    RF_CHECK_EQ_INT(rf_bvh_cone_empty(&bvh, rf_vec3(100, 100, 100), zero, 4), 0);
    RF_CHECK_EQ_INT(rf_bvh_cone_empty(&bvh, rf_vec3(100, 100, 100), nan4, 4), 0);
    /* a cone that holds a sphere's centre is not empty */
    RfVec3 at = s.balls[0].center, from = rf_vec3_add(at, rf_vec3(0, 0, 30));
    RfVec3 box4[4] = {{0, 1, -0.01}, {0, -1, -0.01}, {1, 0, -0.01}, {-1, 0, -0.01}}; /* around -z */
    RF_CHECK_EQ_INT(rf_bvh_cone_empty(&bvh, from, box4, 4), 0);
    rf_bvh_free(&bvh);
    RfBvh none;
    RfBvhDesc d0 = {0, describe, &s, 1, 0};
    RF_CHECK_EQ_INT(rf_bvh_build(&none, &d0), RF_OK);
    RF_CHECK_EQ_INT(rf_bvh_cone_empty(&none, from, box4, 4), 1);
    rf_bvh_free(&none);
    free(s.tris);
    free(s.sides);
    free(s.balls);
}

const RfTest rf_tests_bvh[] = {
    {"bvh_cones_vs_brute_force", t_bvh_cones},
    {"bvh_cone_empty_vs_brute_force", t_bvh_cone_empty},
    {"bvh_random_vs_brute_force", t_bvh_random},
    {"bvh_large_parallel_build_vs_brute_force", t_bvh_large},
    {"bvh_shared_edges_vs_brute_force", t_bvh_shared_edges},
    {"bvh_degenerate", t_bvh_degenerate},
    {"bvh_ray_constants", t_bvh_ray_constants},
    {"bvh_small_root_vs_brute_force", t_bvh_small_root},
    RF_TEST_END,
};
