/* The BVH against brute force: the same nearest hit and the same any-hit answer. */
#include <stdlib.h>

#include "refray/bvh.h"
#include "rf_test.h"

typedef struct {
    RfVec3 c;
    double r;
} Ball;

typedef struct {
    const Ball *balls;
    long tests;
} Ctx;

/* a plain sphere test (the reference kernel lives in intersect.h; any exact test serves here,
 * since the BVH and brute force call the same one) */
static int hit_ball(void *vctx, int prim, RfRay ray, double t_min, double *t_max)
{
    Ctx *ctx = vctx;
    const Ball *b = &ctx->balls[prim];
    ctx->tests++;
    RfVec3 oc = rf_vec3_sub(ray.origin, b->c);
    double a = rf_vec3_dot(ray.dir, ray.dir), hb = rf_vec3_dot(ray.dir, oc);
    double c = rf_vec3_dot(oc, oc) - b->r * b->r, disc = hb * hb - a * c;
    if (disc < 0.0)
        return 0;
    double s = sqrt(disc), t = (-hb - s) / a;
    if (!(t > t_min))
        t = (-hb + s) / a;
    if (t > t_min && t < *t_max) {
        *t_max = t;
        return 1;
    }
    return 0;
}

static int brute(Ctx *ctx, int n, RfRay ray, double t_min, double *t_max)
{
    int hit = -1;
    for (int i = 0; i < n; i++)
        if (hit_ball(ctx, i, ray, t_min, t_max))
            hit = i;
    return hit;
}

static void make_scene(RfTestRng *r, Ball *balls, RfAabb *boxes, int n, double spread, double rmax)
{
    for (int i = 0; i < n; i++) {
        balls[i].c = rf_vec3(rf_test_uniform(r, -spread, spread), rf_test_uniform(r, -spread, spread),
                             rf_test_uniform(r, -spread, spread));
        balls[i].r = rf_test_uniform(r, 0.01, rmax);
        RfVec3 e = rf_vec3(balls[i].r, balls[i].r, balls[i].r);
        boxes[i].lo = rf_vec3_sub(balls[i].c, e);
        boxes[i].hi = rf_vec3_add(balls[i].c, e);
    }
}

static void check_against_brute(const RfBvh *bvh, const Ball *balls, int n, RfTestRng *r, int rays)
{
    Ctx a = {balls, 0}, b = {balls, 0};
    for (int i = 0; i < rays; i++) {
        RfRay ray = rf_ray(rf_vec3(rf_test_uniform(r, -12, 12), rf_test_uniform(r, -12, 12), rf_test_uniform(r, -12, 12)),
                           rf_vec3(rf_test_uniform(r, -1, 1), rf_test_uniform(r, -1, 1), rf_test_uniform(r, -1, 1)));
        if (i % 7 == 0) /* axis-parallel rays: two direction components exactly 0 */
            ray.dir = rf_vec3(0, 0, i % 2 ? 1 : -1);
        double ta = HUGE_VAL, tb = HUGE_VAL;
        int ha = rf_bvh_intersect(bvh, ray, 1e-9, &ta, hit_ball, &a, 0);
        int hb = brute(&b, n, ray, 1e-9, &tb);
        rf_test_checks++;
        /* equal distances (coincident spheres) may resolve to either primitive */
        if (ta != tb || (ha < 0) != (hb < 0)) {
            rf_test_fail(__FILE__, __LINE__, "ray %d: bvh hit %d at %.17g, brute force %d at %.17g", i, ha, ta, hb, tb);
            return;
        }
        double tc = HUGE_VAL;
        int hc = rf_bvh_intersect(bvh, ray, 1e-9, &tc, hit_ball, &a, 1);
        RF_CHECK((hc >= 0) == (hb >= 0));
    }
    /* the tree must pay off: far fewer primitive tests than brute force on large scenes */
    if (n >= 1000)
        RF_CHECK(a.tests * 10 < b.tests);
}

static void t_bvh_random(void)
{
    RfTestRng r = {11};
    enum { N = 5000 };
    Ball *balls = malloc(sizeof *balls * N);
    RfAabb *boxes = malloc(sizeof *boxes * N);
    make_scene(&r, balls, boxes, N, 10, 0.3);
    RfBvh bvh;
    RF_CHECK_EQ_INT(rf_bvh_build(&bvh, boxes, N), RF_OK);
    RF_CHECK(bvh.depth < 64);
    /* every primitive appears exactly once in the leaves */
    int *seen = calloc(N, sizeof *seen);
    for (int i = 0; i < bvh.node_count; i++)
        for (int k = 0; k < bvh.nodes[i].count; k++)
            seen[bvh.prims[bvh.nodes[i].first + k]]++;
    int once = 1;
    for (int i = 0; i < N; i++)
        once &= seen[i] == 1;
    RF_CHECK(once);
    check_against_brute(&bvh, balls, N, &r, 20000);
    rf_bvh_free(&bvh);
    free(seen);
    free(balls);
    free(boxes);
}

static void t_bvh_degenerate(void)
{
    RfTestRng r = {12};
    RfBvh bvh;
    double t = HUGE_VAL;
    /* empty */
    RF_CHECK_EQ_INT(rf_bvh_build(&bvh, NULL, 0), RF_OK);
    RF_CHECK_EQ_INT(rf_bvh_intersect(&bvh, rf_ray(rf_vec3(0, 0, 0), rf_vec3(1, 0, 0)), 0, &t, hit_ball, NULL, 0), -1);
    rf_bvh_free(&bvh);
    /* 300 identical spheres: no SAH split exists; leaves must still stay bounded */
    enum { N = 300 };
    Ball balls[N];
    RfAabb boxes[N];
    for (int i = 0; i < N; i++) {
        balls[i].c = rf_vec3(1, 2, 3);
        balls[i].r = 0.5;
        boxes[i].lo = rf_vec3(0.5, 1.5, 2.5);
        boxes[i].hi = rf_vec3(1.5, 2.5, 3.5);
    }
    RF_CHECK_EQ_INT(rf_bvh_build(&bvh, boxes, N), RF_OK);
    int max_leaf = 0;
    for (int i = 0; i < bvh.node_count; i++)
        max_leaf = bvh.nodes[i].count > max_leaf ? bvh.nodes[i].count : max_leaf;
    RF_CHECK(max_leaf <= 8);
    check_against_brute(&bvh, balls, N, &r, 2000);
    rf_bvh_free(&bvh);
    /* a flat box (zero thickness, like a triangle in the plane z = 0), hit by a ray along z */
    RfAabb flat = {{-1, -1, 0}, {1, 1, 0}};
    RF_CHECK(rf_aabb_hit(flat, rf_vec3(0.5, 0.5, 5), rf_vec3(1.0 / 0.0, 1.0 / 0.0, -1), 0, HUGE_VAL));
    RF_CHECK(!rf_aabb_hit(flat, rf_vec3(1.5, 0.5, 5), rf_vec3(1.0 / 0.0, 1.0 / 0.0, -1), 0, HUGE_VAL));
    /* origin exactly on a slab plane, ray parallel to it: 0 * inf = NaN must not cull */
    RF_CHECK(rf_aabb_hit(flat, rf_vec3(-1, 0, 5), rf_vec3(1.0 / 0.0, 1.0 / 0.0, -1), 0, HUGE_VAL));
    /* non-finite boxes are refused */
    RfAabb bad = {{0, 0, 0}, {NAN, 1, 1}};
    RF_CHECK_EQ_INT(rf_bvh_build(&bvh, &bad, 1), RF_ERR_DOMAIN);
}

const RfTest rf_tests_bvh[] = {
    {"bvh_random_vs_brute_force", t_bvh_random},
    {"bvh_degenerate", t_bvh_degenerate},
    RF_TEST_END,
};
