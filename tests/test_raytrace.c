/* §3 kernels: intersections, camera, Phong, lights, reflection, refraction, Fresnel; and the
 * independently computed cases of tests/data/formula_cases_raytrace.jsonl
 * (tools/oracle/gen_raytrace_cases.py, mpmath at 50 digits). */
#include <math.h>
#include <string.h>

#include "refray/camera.h"
#include "refray/intersect.h"
#include "refray/optics.h"
#include "refray/shading.h"
#include "rf_test.h"

static const double INF = INFINITY;

static RfVec3 v3(double x, double y, double z) { return rf_vec3(x, y, z); }

static RfVec3 rand_vec(RfTestRng *r, double s)
{
    return v3(rf_test_uniform(r, -s, s), rf_test_uniform(r, -s, s), rf_test_uniform(r, -s, s));
}

static RfVec3 rand_unit(RfTestRng *r)
{
    for (;;) {
        RfVec3 v = rand_vec(r, 1.0);
        double l = rf_vec3_length(v);
        if (l > 0.1 && l <= 1.0)
            return rf_vec3_scale(v, 1.0 / l);
    }
}

#define CHECK_VEC_NEAR(a, b, tol)                                                            \
    do {                                                                                     \
        RfVec3 a_ = (a), b_ = (b);                                                           \
        RF_CHECK_NEAR(a_.x, b_.x, (tol), (tol));                                             \
        RF_CHECK_NEAR(a_.y, b_.y, (tol), (tol));                                             \
        RF_CHECK_NEAR(a_.z, b_.z, (tol), (tol));                                             \
    } while (0)

/* ---- §3.5.1 spheres ---- */

/* The Ray Tracer Challenge table (reliability.md §3): unit sphere at the origin, d = +z. */
static void test_sphere_cases(void)
{
    RfSphere s = {v3(0, 0, 0), 1.0};
    for (int m = 0; m < 2; m++) {
        RfSphereMethod method = m ? RF_SPHERE_STABLE : RF_SPHERE_SCRIPT;
        RfHit h;
        RfSphereQuadratic q;
        /* hit from outside: t = 4, 6 */
        RfRay r = rf_ray(v3(0, 0, -5), v3(0, 0, 1));
        q = rf_sphere_quadratic(r, s, method);
        RF_CHECK_EQ_INT(q.roots, 2);
        RF_CHECK(q.t1 == 4.0 && q.t2 == 6.0 && q.a == 1.0 && q.b == -10.0 && q.c == 24.0 && q.disc == 4.0);
        RF_CHECK(rf_intersect_sphere(r, s, method, 0.0, INF, &h) && h.t == 4.0);
        CHECK_VEC_NEAR(h.normal, v3(0, 0, -1), 0.0);
        /* tangent: D = 0, t = 5 twice, counts as a hit */
        r.origin = v3(0, 1, -5);
        q = rf_sphere_quadratic(r, s, method);
        RF_CHECK(q.roots == 1 && q.disc == 0.0 && q.t1 == 5.0 && q.t2 == 5.0);
        RF_CHECK(rf_intersect_sphere(r, s, method, 0.0, INF, &h) && h.t == 5.0);
        /* miss: D < 0 */
        r.origin = v3(0, 2, -5);
        q = rf_sphere_quadratic(r, s, method);
        RF_CHECK(q.roots == 0 && q.disc < 0.0);
        h.t = -7.0;
        RF_CHECK(!rf_intersect_sphere(r, s, method, 0.0, INF, &h));
        RF_CHECK(h.t == -7.0); /* untouched on a miss */
        /* origin inside: t1 = -1 behind, the hit is t2 = 1 with the outward normal */
        r.origin = v3(0, 0, 0);
        q = rf_sphere_quadratic(r, s, method);
        RF_CHECK(q.t1 == -1.0 && q.t2 == 1.0);
        RF_CHECK(rf_intersect_sphere(r, s, method, 0.0, INF, &h) && h.t == 1.0);
        CHECK_VEC_NEAR(h.normal, v3(0, 0, 1), 0.0);
        /* sphere behind the origin: -6, -4, no hit */
        r.origin = v3(0, 0, 5);
        q = rf_sphere_quadratic(r, s, method);
        RF_CHECK(q.t1 == -6.0 && q.t2 == -4.0);
        RF_CHECK(!rf_intersect_sphere(r, s, method, 0.0, INF, &h));
        /* the interval [t_min, t_max): t_max excluded, t_min included, t_min past t1 gives t2 */
        r.origin = v3(0, 0, -5);
        RF_CHECK(!rf_intersect_sphere(r, s, method, 0.0, 4.0, &h));
        RF_CHECK(rf_intersect_sphere(r, s, method, 4.0, 4.5, &h) && h.t == 4.0);
        RF_CHECK(rf_intersect_sphere(r, s, method, 4.5, INF, &h) && h.t == 6.0);
        /* a non-unit direction: t in units of |d| */
        r.dir = v3(0, 0, 2);
        RF_CHECK(rf_intersect_sphere(r, s, method, 0.0, INF, &h) && h.t == 2.0);
    }
}

/* A small sphere far away (reliability.md S1): origin 0, d = -z, centre (x0, 0, -1e8), r = 1.
 * b^2 and 4ac are both 4e16, where one ulp is 8: the script's D loses every digit, while the
 * stable form gets D/4 = r^2 - x0^2 from the perpendicular distance |v| = x0 exactly.
 * x0 = 0.5: exact roots 1e8 -+ sqrt(0.75). The script's c = 1e16 - 0.75 rounds to 1e16, so
 * D = 0 and it reports a tangent at t = 1e8 (relative error 8.7e-9); the stable form is right
 * to 1e-16. x0 = 1.5: the ray passes 0.5 outside the sphere, yet the script's c = 1e16 + 1.25
 * rounds to 1e16 again and it reports a (false) tangent hit; the stable form misses. */
static void test_sphere_stable_vs_script(void)
{
    RfRay r = rf_ray(v3(0, 0, 0), v3(0, 0, -1));
    RfSphere s = {v3(0.5, 0, -1e8), 1.0};
    RfSphereQuadratic a = rf_sphere_quadratic(r, s, RF_SPHERE_SCRIPT);
    RfSphereQuadratic b = rf_sphere_quadratic(r, s, RF_SPHERE_STABLE);
    double t1 = 1e8 - sqrt(0.75), t2 = 1e8 + sqrt(0.75); /* each within half an ulp (7.5e-9) */
    RF_CHECK(a.roots == 1 && a.disc == 0.0);
    RF_CHECK(fabs(a.t1 - t1) > 0.8);                       /* the script is off by sqrt(0.75) */
    RF_CHECK_EQ_INT(b.roots, 2);
    RF_CHECK_NEAR(b.disc, 3.0, 1e-15, 0.0);
    RF_CHECK_NEAR(b.t1, t1, 2e-16, 0.0);
    RF_CHECK_NEAR(b.t2, t2, 2e-16, 0.0);
    RfHit h;
    s.center.x = 1.5;
    RF_CHECK(rf_intersect_sphere(r, s, RF_SPHERE_SCRIPT, 0.0, INF, &h)); /* the script's false hit */
    RF_CHECK(!rf_intersect_sphere(r, s, RF_SPHERE_STABLE, 0.0, INF, &h));

    /* the origin 2^-30 outside a unit sphere, d towards it: the near root is 2^-30 exactly; the
     * stable form gets it from c/q with c compensated, to the last bit */
    r = rf_ray(v3(-1.0 - ldexp(1.0, -30), 0, 0), v3(1, 0, 0));
    s.center = v3(0, 0, 0);
    b = rf_sphere_quadratic(r, s, RF_SPHERE_STABLE);
    RF_CHECK(b.t1 == ldexp(1.0, -30) && b.t2 == 2.0 + ldexp(1.0, -30));

    /* random rays: both variants agree on well-conditioned cases */
    RfTestRng rng = {7};
    for (int k = 0; k < 2000; k++) {
        RfSphere sp = {rand_vec(&rng, 5.0), rf_test_uniform(&rng, 0.5, 3.0)};
        RfRay ry = rf_ray(rand_vec(&rng, 10.0), rand_unit(&rng));
        RfSphereQuadratic x = rf_sphere_quadratic(ry, sp, RF_SPHERE_SCRIPT);
        RfSphereQuadratic y = rf_sphere_quadratic(ry, sp, RF_SPHERE_STABLE);
        if (fabs(x.disc) < 1e-3)
            continue; /* near-tangent: the variants may legitimately differ */
        RF_CHECK_EQ_INT(x.roots, y.roots);
        if (x.roots && y.roots) {
            RF_CHECK_NEAR(x.t1, y.t1, 1e-9, 1e-9);
            RF_CHECK_NEAR(x.t2, y.t2, 1e-9, 1e-9);
        }
    }
}

/* ---- §3.5.2 planes ---- */

static void test_plane_cases(void)
{
    RfPlane p = {v3(0, 0, 1), 2.0}; /* z = 2 */
    RfHit h;
    double t;
    RfRay r = rf_ray(v3(1, 1, 0), v3(0, 0, 1));
    RF_CHECK(rf_intersect_plane(r, p, 0.0, INF, &h) && h.t == 2.0);
    CHECK_VEC_NEAR(h.normal, v3(0, 0, 1), 0.0);
    /* a non-unit normal with the offset scaled alike: the same plane, the same t */
    RfPlane p3 = {v3(0, 0, 3), 6.0};
    RF_CHECK(rf_intersect_plane(r, p3, 0.0, INF, &h) && h.t == 2.0);
    CHECK_VEC_NEAR(h.normal, v3(0, 0, 1), 0.0);
    /* oblique: from (0,0,0) along (1,0,1), t = 2 */
    r.dir = v3(1, 0, 1);
    RF_CHECK(rf_intersect_plane(r, p, 0.0, INF, &h) && h.t == 2.0);
    /* parallel: <d,n> = 0, also for a ray inside the plane */
    r.dir = v3(1, 0, 0);
    RF_CHECK(!rf_plane_line_t(r, p, &t));
    RF_CHECK(!rf_intersect_plane(r, p, 0.0, INF, &h));
    r.origin = v3(0, 0, 2);
    RF_CHECK(!rf_intersect_plane(r, p, 0.0, INF, &h));
    /* behind the origin: the line meets the plane at t = -3 */
    r = rf_ray(v3(0, 0, 5), v3(0, 0, 1));
    RF_CHECK(rf_plane_line_t(r, p, &t) && t == -3.0);
    RF_CHECK(!rf_intersect_plane(r, p, 0.0, INF, &h));
    /* from the back side it is hit as well (planes are two-sided here) */
    r.dir = v3(0, 0, -1);
    RF_CHECK(rf_intersect_plane(r, p, 0.0, INF, &h) && h.t == 3.0);
}

/* ---- §3.5.3 triangles ---- */

static const RfTriangleMethod TRI_METHODS[3] = {RF_TRIANGLE_SCRIPT, RF_TRIANGLE_MOLLER,
                                                RF_TRIANGLE_WATERTIGHT};

static void test_triangle_cases(void)
{
    RfTriangle tri = {v3(0, 0, 0), v3(1, 0, 0), v3(0, 1, 0)};
    for (int m = 0; m < 3; m++) {
        RfTriangleMethod method = TRI_METHODS[m];
        RfHit h;
        /* interior, from the front: t = 1, l = (0.5, 0.25, 0.25) */
        RfRay r = rf_ray(v3(0.25, 0.25, 1), v3(0, 0, -1));
        RF_CHECK(rf_intersect_triangle(r, tri, method, 0.0, INF, &h));
        RF_CHECK_NEAR(h.t, 1.0, 1e-15, 0.0);
        RF_CHECK_NEAR(h.l[0], 0.5, 1e-15, 0.0);
        RF_CHECK_NEAR(h.l[1], 0.25, 1e-15, 0.0);
        RF_CHECK_NEAR(h.l[2], 0.25, 1e-15, 0.0);
        CHECK_VEC_NEAR(h.normal, v3(0, 0, 1), 0.0);
        /* two-sided: from the back */
        r = rf_ray(v3(0.25, 0.25, -2), v3(0, 0, 1));
        RF_CHECK(rf_intersect_triangle(r, tri, method, 0.0, INF, &h));
        RF_CHECK_NEAR(h.t, 2.0, 1e-15, 0.0);
        /* outside the triangle (l1 < 0) */
        r = rf_ray(v3(0.75, 0.75, 1), v3(0, 0, -1));
        RF_CHECK(!rf_intersect_triangle(r, tri, method, 0.0, INF, &h));
        /* behind the origin */
        r = rf_ray(v3(0.25, 0.25, 1), v3(0, 0, 1));
        RF_CHECK(!rf_intersect_triangle(r, tri, method, 0.0, INF, &h));
        /* parallel to the plane, above it and inside it */
        r = rf_ray(v3(-1, 0.25, 1), v3(1, 0, 0));
        RF_CHECK(!rf_intersect_triangle(r, tri, method, 0.0, INF, &h));
        r.origin.z = 0.0;
        RF_CHECK(!rf_intersect_triangle(r, tri, method, 0.0, INF, &h));
        /* exactly on an edge (l3 = 0) and exactly on a vertex (l1 = 1): hits */
        r = rf_ray(v3(0.5, 0, 1), v3(0, 0, -1));
        RF_CHECK(rf_intersect_triangle(r, tri, method, 0.0, INF, &h));
        RF_CHECK(h.l[2] == 0.0);
        r = rf_ray(v3(0.5, 0.5, 1), v3(0, 0, -1)); /* the hypotenuse, l1 = 0 */
        RF_CHECK(rf_intersect_triangle(r, tri, method, 0.0, INF, &h));
        RF_CHECK_NEAR(h.l[0], 0.0, 0.0, 1e-16);
        r = rf_ray(v3(0, 0, 1), v3(0, 0, -1));
        RF_CHECK(rf_intersect_triangle(r, tri, method, 0.0, INF, &h));
        RF_CHECK(h.l[0] == 1.0);
        r = rf_ray(v3(0, 1, 1), v3(0, 0, -1));
        RF_CHECK(rf_intersect_triangle(r, tri, method, 0.0, INF, &h));
        RF_CHECK(h.l[2] == 1.0);
        /* just outside the edge by one ulp-sized step */
        r = rf_ray(v3(0.5, -1e-12, 1), v3(0, 0, -1));
        RF_CHECK(!rf_intersect_triangle(r, tri, method, 0.0, INF, &h));
        /* the interval: t_max = 1 excludes the hit at t = 1 */
        r = rf_ray(v3(0.25, 0.25, 1), v3(0, 0, -1));
        RF_CHECK(!rf_intersect_triangle(r, tri, method, 0.0, 1.0, &h));
        /* a degenerate triangle never hits */
        RfTriangle deg = {v3(0, 0, 0), v3(1, 1, 0), v3(2, 2, 0)};
        r = rf_ray(v3(1, 1, 1), v3(0, 0, -1));
        RF_CHECK(!rf_intersect_triangle(r, deg, method, 0.0, INF, &h));
    }
}

/* Away from the edges the three methods agree: random triangles, rays aimed at points with
 * barycentric coordinates >= 0.01 (all hit, same t and l) or with one <= -0.01 (all miss). */
static void test_triangle_methods_agree(void)
{
    RfTestRng rng = {11};
    for (int k = 0; k < 20000; k++) {
        RfTriangle tri = {rand_vec(&rng, 5.0), rand_vec(&rng, 5.0), rand_vec(&rng, 5.0)};
        RfVec3 n = rf_vec3_cross(rf_vec3_sub(tri.p2, tri.p1), rf_vec3_sub(tri.p3, tri.p1));
        if (rf_vec3_length(n) < 1.0)
            continue; /* skip slivers: their conditioning is not the point here */
        double a = rf_test_uniform(&rng, -0.5, 1.0), b = rf_test_uniform(&rng, -0.5, 1.0);
        double l[3] = {1.0 - a - b, a, b};
        int inside = l[0] >= 0.01 && l[1] >= 0.01 && l[2] >= 0.01;
        int outside = l[0] <= -0.01 || l[1] <= -0.01 || l[2] <= -0.01;
        if (!inside && !outside)
            continue;
        RfVec3 target = rf_vec3_add(rf_vec3_add(rf_vec3_scale(tri.p1, l[0]), rf_vec3_scale(tri.p2, l[1])),
                                    rf_vec3_scale(tri.p3, l[2]));
        RfVec3 o = rand_vec(&rng, 20.0);
        RfRay r = rf_ray(o, rf_vec3_sub(target, o)); /* t = 1 at the target */
        if (fabs(rf_vec3_dot(rf_vec3_normalize(r.dir), rf_vec3_normalize(n))) < 0.05)
            continue; /* grazing */
        RfHit h[3];
        int hit[3];
        for (int m = 0; m < 3; m++)
            hit[m] = rf_intersect_triangle(r, tri, TRI_METHODS[m], 0.0, INF, &h[m]);
        for (int m = 0; m < 3; m++) {
            RF_CHECK_EQ_INT(hit[m], inside);
            if (hit[m] && inside) {
                RF_CHECK_NEAR(h[m].t, 1.0, 1e-10, 0.0);
                for (int i = 0; i < 3; i++)
                    RF_CHECK_NEAR(h[m].l[i], l[i], 0.0, 1e-10);
            }
        }
    }
}

/* Two triangles sharing the edge P-Q (in opposite orders, as in a consistently wound mesh):
 * every ray aimed at a point of the edge must hit at least one of them with the watertight
 * test. Rays aimed exactly at the rounded edge point are the hard case; the shared-vertex
 * coordinates are random doubles, and origins are spread around. Moller-Trumbore and the
 * script are counted, not required (they can lose such rays). */
static void test_watertight_shared_edge(void)
{
    RfTestRng rng = {2013};
    long misses[3] = {0, 0, 0}, rays = 0;
    for (int k = 0; k < 2000; k++) {
        RfVec3 p = rand_vec(&rng, 3.0), q = rand_vec(&rng, 3.0);
        RfVec3 a = rand_vec(&rng, 3.0), b = rand_vec(&rng, 3.0);
        RfTriangle t1 = {p, q, a}, t2 = {q, p, b};
        for (int j = 0; j < 100; j++) {
            RfVec3 target = rf_vec3_lerp(p, q, rf_test_uniform(&rng, 0.0, 1.0));
            RfVec3 o = rand_vec(&rng, 30.0);
            RfRay r = rf_ray(o, rf_vec3_sub(target, o));
            RfWatertightRay w;
            rf_watertight_ray(&r, &w);
            RfHit h;
            /* only rays that cross the surface (a and b on opposite sides of the ray's plane
             * through the edge) must hit; others pass the folded pair on one side */
            RfVec3 pn = rf_vec3_cross(rf_vec3_sub(q, p), r.dir);
            double sa = rf_vec3_dot(rf_vec3_sub(a, p), pn), sb = rf_vec3_dot(rf_vec3_sub(b, p), pn);
            if (!(sa * sb < 0.0))
                continue;
            rays++;
            int hw = rf_intersect_triangle_watertight(&w, t1, 0.0, INF, &h) |
                     rf_intersect_triangle_watertight(&w, t2, 0.0, INF, &h);
            if (!hw)
                misses[2]++;
            for (int m = 0; m < 2; m++)
                if (!(rf_intersect_triangle(r, t1, TRI_METHODS[m], 0.0, INF, &h) |
                      rf_intersect_triangle(r, t2, TRI_METHODS[m], 0.0, INF, &h)))
                    misses[m]++;
        }
    }
    RF_CHECK(rays > 50000);
    RF_CHECK_EQ_INT(misses[2], 0);
    /* the seam regression of reliability.md W3 (Oblikovati #2146): a quad split along y = x,
     * the ray from (0,0,10) along (0.30458447, 0.30458447, -0.9024725) meets the diagonal */
    {
        RfTriangle qa = {v3(0, 0, 0), v3(10, 0, 0), v3(10, 10, 0)}, qb = {v3(0, 0, 0), v3(10, 10, 0), v3(0, 10, 0)};
        RfRay r = rf_ray(v3(0, 0, 10), v3(0.30458447, 0.30458447, -0.9024725));
        RfWatertightRay w;
        rf_watertight_ray(&r, &w);
        RfHit h;
        RF_CHECK(rf_intersect_triangle_watertight(&w, qa, 0.0, INF, &h) |
                 rf_intersect_triangle_watertight(&w, qb, 0.0, INF, &h));
        RF_CHECK_NEAR(h.t * r.dir.z, -10.0, 1e-15, 0.0);
    }
    fprintf(stderr, "  shared edge: %ld rays, misses script %ld, moller %ld, watertight %ld\n", rays,
            misses[0], misses[1], misses[2]);
}

/* A closed mesh: an octahedron with jittered vertices. Rays from points near its centre in
 * random directions, and aimed exactly at its vertices and at points of its edges, must leave
 * through at least one face (reliability.md W1, scaled down). */
/* The edge test's exact fallback: with P = (1+e, 1+2e), Q = (-1, -1-e) (e = 2^-52, sheared
 * ray along +z from the origin, so these are the values the test sees) both products of
 * Px Qy - Py Qx round to -(1+2e), yet the exact value is -e^2 < 0: the origin lies just to one
 * side of PQ. Of the triangles PQR and PQR' with R = (-1, 1) and R' = (1, -1) on either side, the
 * line therefore meets exactly the first (all three exact edge values negative; worked out in
 * exact rationals). Taking the rounded 0 as "on the edge" would report both. */
static void test_watertight_exact_edge_sign(void)
{
    const double e = 0x1p-52;
    RfVec3 p = rf_vec3(1 + e, 1 + 2 * e, 1), q = rf_vec3(-1, -(1 + e), 1);
    RfTriangle inside = {p, q, rf_vec3(-1, 1, 1)}, outside = {p, q, rf_vec3(1, -1, 1)};
    RfWatertightRay w;
    rf_watertight_ray(&(RfRay){rf_vec3(0, 0, 0), rf_vec3(0, 0, 1)}, &w);
    RfHit h;
    double t;
    RF_CHECK(rf_intersect_triangle_watertight(&w, inside, 0.0, INF, &h));
    RF_CHECK(h.t == 1.0);
    RF_CHECK(!rf_intersect_triangle_watertight(&w, outside, 0.0, INF, &h));
    RF_CHECK(rf_watertight_t(&w, &inside, &t) && t == 1.0);
    RF_CHECK(!rf_watertight_t(&w, &outside, &t));
    /* the same decisions with the vertices in the other orders (each order swaps signs exactly) */
    RfTriangle in2 = {q, inside.p3, p}, out2 = {outside.p3, p, q};
    RF_CHECK(rf_intersect_triangle_watertight(&w, in2, 0.0, INF, &h));
    RF_CHECK(!rf_intersect_triangle_watertight(&w, out2, 0.0, INF, &h));
}

static void test_watertight_closed_mesh(void)
{
    RfTestRng rng = {42};
    long rays = 0, misses = 0;
    static const int faces[8][3] = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4},
                                    {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
    for (int k = 0; k < 200; k++) {
        RfVec3 v[6] = {v3(1, 0, 0), v3(-1, 0, 0), v3(0, 1, 0), v3(0, -1, 0), v3(0, 0, 1), v3(0, 0, -1)};
        double scale = pow(10.0, rf_test_uniform(&rng, -6.0, 6.0));
        RfVec3 shift = rand_vec(&rng, 100.0 * scale);
        for (int i = 0; i < 6; i++)
            v[i] = rf_vec3_add(rf_vec3_scale(rf_vec3_add(v[i], rand_vec(&rng, 0.2)), scale), shift);
        RfTriangle tri[8];
        for (int f = 0; f < 8; f++)
            tri[f] = (RfTriangle){v[faces[f][0]], v[faces[f][1]], v[faces[f][2]]};
        for (int j = 0; j < 500; j++) {
            RfVec3 o = rf_vec3_add(shift, rand_vec(&rng, 0.1 * scale));
            RfVec3 d;
            int kind = j % 3;
            if (kind == 0) {
                d = rand_unit(&rng);
            } else if (kind == 1) {
                d = rf_vec3_sub(v[j % 6], o); /* exactly at a vertex */
            } else {
                const int *f = faces[j % 8];
                d = rf_vec3_sub(rf_vec3_lerp(v[f[0]], v[f[1]], rf_test_uniform(&rng, 0, 1)), o);
            }
            RfWatertightRay w;
            rf_watertight_ray(&(RfRay){o, d}, &w);
            int any = 0;
            RfHit h;
            for (int f = 0; f < 8; f++)
                any |= rf_intersect_triangle_watertight(&w, tri[f], 0.0, INF, &h);
            rays++;
            misses += !any;
        }
    }
    RF_CHECK_EQ_INT(rays, 100000);
    RF_CHECK_EQ_INT(misses, 0);
}

/* ---- NFF cone / cylinder ---- */

/* The tracer tests each cone with its frame computed once (rf_cone_frame) and without the
 * normal for shadow rays: the same answers and t as rf_intersect_cone, bit for bit, and with
 * the normal the same normal, on random cones, cylinders and rays (many near the surface). */
static void test_cone_framed(void)
{
    RfTestRng rng = {31};
    int hits = 0;
    for (int i = 0; i < 20000; i++) {
        RfVec3 base = v3(rf_test_uniform(&rng, -2, 2), rf_test_uniform(&rng, -2, 2), rf_test_uniform(&rng, -2, 2));
        RfVec3 apex = rf_vec3_add(base, v3(rf_test_uniform(&rng, -2, 2), rf_test_uniform(&rng, -2, 2),
                                           rf_test_uniform(&rng, -2, 2)));
        double r0 = rf_test_uniform(&rng, 0, 1), r1 = i % 3 == 0 ? r0 : i % 3 == 1 ? 0.0 : rf_test_uniform(&rng, 0, 1);
        RfCone c = {base, r0, apex, r1};
        RfVec3 o = v3(rf_test_uniform(&rng, -4, 4), rf_test_uniform(&rng, -4, 4), rf_test_uniform(&rng, -4, 4));
        RfVec3 on_axis = rf_vec3_add(base, rf_vec3_scale(rf_vec3_sub(apex, base), rf_test_uniform(&rng, 0, 1)));
        RfRay r = rf_ray(o, rf_vec3_sub(on_axis, o)); /* towards a point of the axis */
        RfConeFrame f = rf_cone_frame(c);
        RfHit a, b, n;
        int ha = rf_intersect_cone(r, c, 0.0, INF, &a);
        int hb = rf_intersect_cone_framed(&r, &c, &f, 0.0, INF, 0, &b);
        int hn = rf_intersect_cone_framed(&r, &c, &f, 0.0, INF, 1, &n);
        rf_test_checks++;
        if (ha != hb || ha != hn || (ha && (memcmp(&a.t, &b.t, sizeof a.t) != 0 || memcmp(&a.t, &n.t, sizeof a.t) != 0 ||
                                            memcmp(&a.normal, &n.normal, sizeof a.normal) != 0))) {
            rf_test_fail(__FILE__, __LINE__, "cone %d: rf_intersect_cone %d t %a, framed %d t %a / %d t %a", i, ha,
                         a.t, hb, b.t, hn, n.t);
            break;
        }
        hits += ha;
    }
    RF_CHECK(hits > 5000); /* the rays aim at the axis: most hit */
}

static void test_cone_cylinder(void)
{
    RfCone cyl = {v3(0, 0, 0), 1.0, v3(0, 0, 2), 1.0};
    RfHit h;
    /* from outside, perpendicular to the axis: t = 4 at x = -1, normal -x */
    RfRay r = rf_ray(v3(-5, 0, 1), v3(1, 0, 0));
    RF_CHECK(rf_intersect_cone(r, cyl, 0.0, INF, &h) && h.t == 4.0);
    CHECK_VEC_NEAR(h.normal, v3(-1, 0, 0), 0.0);
    /* from inside (open surface): the far wall, outward normal +x */
    r.origin = v3(0, 0, 1);
    RF_CHECK(rf_intersect_cone(r, cyl, 0.0, INF, &h) && h.t == 1.0);
    CHECK_VEC_NEAR(h.normal, v3(1, 0, 0), 0.0);
    /* above the apex end and below the base: miss (no caps, finite length) */
    r.origin = v3(-5, 0, 2.5);
    RF_CHECK(!rf_intersect_cone(r, cyl, 0.0, INF, &h));
    r.origin = v3(-5, 0, -0.5);
    RF_CHECK(!rf_intersect_cone(r, cyl, 0.0, INF, &h));
    /* along the axis: no quadratic term, no hit (no caps); on the surface line: no hit */
    r = rf_ray(v3(0, 0, -5), v3(0, 0, 1));
    RF_CHECK(!rf_intersect_cone(r, cyl, 0.0, INF, &h));
    r.origin = v3(1, 0, -5);
    RF_CHECK(!rf_intersect_cone(r, cyl, 0.0, INF, &h));
    /* tangent: y = 1 grazes at x = 0 */
    r = rf_ray(v3(-5, 1, 1), v3(1, 0, 0));
    RF_CHECK(rf_intersect_cone(r, cyl, 0.0, INF, &h) && h.t == 5.0);
    /* slanted through the open end: enters the inside, hits the far wall */
    r = rf_ray(v3(0, 0, 3), v3(1, 0, -1));
    RF_CHECK(rf_intersect_cone(r, cyl, 0.0, INF, &h) && h.t == 1.0);
    CHECK_VEC_NEAR(rf_ray_at(r, h.t), v3(1, 0, 2), 0.0);
    /* behind the origin */
    r = rf_ray(v3(5, 0, 1), v3(1, 0, 0));
    RF_CHECK(!rf_intersect_cone(r, cyl, 0.0, INF, &h));

    /* a cone: radius 1 at z = 0 to 0 at z = 1 (slope -1); at z = 0.5 the radius is 0.5 and the
     * outward normal is (-1, 0, 1)/sqrt(2) on the -x side */
    RfCone cone = {v3(0, 0, 0), 1.0, v3(0, 0, 1), 0.0};
    r = rf_ray(v3(-5, 0, 0.5), v3(1, 0, 0));
    RF_CHECK(rf_intersect_cone(r, cone, 0.0, INF, &h) && h.t == 4.5);
    CHECK_VEC_NEAR(h.normal, rf_vec3_scale(v3(-1, 0, 1), 1.0 / sqrt(2.0)), 1e-15);
    /* past the tip the squared equation has a mirrored nappe: at z = 1.5 it must not be hit */
    r.origin.z = 1.5;
    RF_CHECK(!rf_intersect_cone(r, cone, 0.0, INF, &h));
    /* a ray parallel to a generator (a = 0, the linear case): from (-1, 0, -1) along (1, 0, 1),
     * parallel to the -x generator x = -(1 - z). It enters through the open base at t = 1 and
     * meets the +x wall x = 1 - z at -1 + t = 2 - t, t = 1.5, the point (0.5, 0, 0.5), from
     * inside; outward normal (1, 0, 1)/sqrt2 */
    r = rf_ray(v3(-1, 0, -1), v3(1, 0, 1));
    RF_CHECK(rf_intersect_cone(r, cone, 0.0, INF, &h) && h.t == 1.5);
    CHECK_VEC_NEAR(h.normal, rf_vec3_scale(v3(1, 0, 1), 1.0 / sqrt(2.0)), 1e-15);
    /* the tip: the normal is taken along the axis */
    r = rf_ray(v3(-1, 0, 1), v3(1, 0, 0));
    RF_CHECK(rf_intersect_cone(r, cone, 0.0, INF, &h) && h.t == 1.0);
    CHECK_VEC_NEAR(h.normal, v3(0, 0, 1), 0.0);
    /* a frustum, apex radius larger than the base radius, seen from the inside */
    RfCone fr = {v3(0, 0, 0), 1.0, v3(0, 0, 2), 3.0};
    r = rf_ray(v3(0, 0, 1), v3(0, 1, 0)); /* radius 2 at z = 1 */
    RF_CHECK(rf_intersect_cone(r, fr, 0.0, INF, &h) && h.t == 2.0);
    CHECK_VEC_NEAR(h.normal, rf_vec3_scale(v3(0, 1, -1), 1.0 / sqrt(2.0)), 1e-15);

    /* random rays: a reported hit lies on the surface (radius = interpolated radius) */
    RfTestRng rng = {5};
    RfCone c2 = {v3(1, 2, 3), 0.7, v3(-1, 0, 5), 1.9};
    RfVec3 axis = rf_vec3_normalize(rf_vec3_sub(c2.apex, c2.base));
    double hh = rf_vec3_length(rf_vec3_sub(c2.apex, c2.base));
    int hits = 0;
    for (int k = 0; k < 5000; k++) {
        /* aimed at points near the axis segment, so that most rays hit */
        RfVec3 o = rand_vec(&rng, 6.0);
        RfVec3 aim = rf_vec3_add(rf_vec3_lerp(c2.base, c2.apex, rf_test_uniform(&rng, 0, 1)), rand_vec(&rng, 0.5));
        RfRay ry = rf_ray(o, rf_vec3_sub(aim, o));
        if (!rf_intersect_cone(ry, c2, 0.0, INF, &h))
            continue;
        hits++;
        RfVec3 q = rf_vec3_sub(rf_ray_at(ry, h.t), c2.base);
        double z = rf_vec3_dot(q, axis);
        double rad = rf_vec3_length(rf_vec3_sub(q, rf_vec3_scale(axis, z)));
        RF_CHECK(z >= -1e-12 && z <= hh + 1e-12);
        RF_CHECK_NEAR(rad, c2.base_radius + (c2.apex_radius - c2.base_radius) * z / hh, 1e-10, 1e-10);
        RF_CHECK_NEAR(rf_vec3_length(h.normal), 1.0, 1e-15, 0.0);
    }
    RF_CHECK(hits > 2500);
}

/* ---- §3.4 camera, §3.10 thin lens ---- */

static void test_camera(void)
{
    RfCamera cam;
    /* looking down -z from (0,0,5), up +y: u = x, v = y, w = z */
    RF_CHECK(rf_camera_init_fov(&cam, v3(0, 0, 5), v3(0, 0, 0), v3(0, 1, 0), 1.0, RF_PI / 2, 3, 3) == RF_OK);
    RF_CHECK_NEAR(cam.t, 1.0, 1e-15, 0.0);
    RF_CHECK(cam.l == -cam.r && cam.b == -cam.t && cam.r == cam.t);
    /* the centre pixel of a 3x3 image looks straight along -w */
    RfRay r = rf_camera_ray(&cam, 1.5, 1.5, 0, 0);
    CHECK_VEC_NEAR(r.origin, v3(0, 0, 5), 0.0);
    CHECK_VEC_NEAR(r.dir, v3(0, 0, -1), 1e-16);
    /* pixel (0, 0) is top-left: -u, +v; its top-left corner is (l, t) */
    r = rf_camera_ray(&cam, 0.5, 0.5, 0, 0);
    RF_CHECK(r.dir.x < 0 && r.dir.y > 0);
    RfVec3 s = rf_camera_plane_point(&cam, 0.0, 0.0);
    RF_CHECK(s.x == cam.l && s.y == cam.t && s.z == -1.0);
    s = rf_camera_plane_point(&cam, 3.0, 3.0);
    RF_CHECK(s.x == cam.r && s.y == cam.b);
    /* aspect: 4x2 pixels with fov 90: t = d, r = 2d */
    RF_CHECK(rf_camera_init_fov(&cam, v3(0, 0, 0), v3(1, 0, 0), v3(0, 0, 1), 2.0, RF_PI / 2, 4, 2) == RF_OK);
    RF_CHECK_NEAR(cam.r, 4.0, 1e-15, 0.0);
    /* world mapping: looking along +x with up +z: w = -x, u = up x w = -y, v = z */
    CHECK_VEC_NEAR(cam.basis.w, v3(-1, 0, 0), 0.0);
    CHECK_VEC_NEAR(cam.basis.u, v3(0, -1, 0), 0.0);
    CHECK_VEC_NEAR(cam.basis.v, v3(0, 0, 1), 0.0);
    /* errors */
    RF_CHECK(rf_camera_init_fov(&cam, v3(0, 0, 0), v3(0, 0, 0), v3(0, 1, 0), 1, 1, 2, 2) == RF_ERR_DEGENERATE);
    RF_CHECK(rf_camera_init_fov(&cam, v3(0, 0, 0), v3(0, 1, 0), v3(0, 1, 0), 1, 1, 2, 2) == RF_ERR_DEGENERATE);
    RF_CHECK(rf_camera_init_fov(&cam, v3(0, 0, 0), v3(0, 0, 1), v3(0, 1, 0), 1, RF_PI, 2, 2) == RF_ERR_DOMAIN);
    RF_CHECK(rf_camera_init(&cam, v3(0, 0, 0), v3(0, 0, 1), v3(0, 1, 0), 1, 1, 1, -1, 1, 2, 2) == RF_ERR_DOMAIN);

    /* thin lens: every lens sample of one pixel meets the pinhole ray on the focal plane */
    RfTestRng rng = {3};
    for (int k = 0; k < 200; k++) {
        RfVec3 pd = v3(rf_test_uniform(&rng, -1, 1), rf_test_uniform(&rng, -1, 1), -1.0);
        double f = rf_test_uniform(&rng, 0.5, 20.0), lu, lv;
        do {
            lu = rf_test_uniform(&rng, -1, 1);
            lv = rf_test_uniform(&rng, -1, 1);
        } while (lu * lu + lv * lv > 1.0);
        RfRay lr;
        RF_CHECK(rf_thin_lens_ray(pd, lu, lv, 0.3, f, &lr) == RF_OK);
        RF_CHECK_NEAR(rf_vec3_length(lr.dir), 1.0, 1e-15, 0.0);
        double t = (-f - lr.origin.z) / lr.dir.z;
        RfVec3 hitp = rf_ray_at(lr, t), pin = rf_vec3_scale(pd, f);
        CHECK_VEC_NEAR(hitp, pin, 1e-12);
    }
    RfRay lr;
    RF_CHECK(rf_thin_lens_ray(v3(0, 0, 1), 0, 0, 0.1, 1, &lr) == RF_ERR_DOMAIN);
    /* an open lens through the camera: the lens point lies in the u-v plane around the eye */
    RF_CHECK(rf_camera_init_fov(&cam, v3(1, 2, 3), v3(0, 0, 0), v3(0, 1, 0), 1.0, 1.0, 8, 8) == RF_OK);
    RfRay pin = rf_camera_ray(&cam, 2.5, 3.5, 0.5, 0.5);
    RF_CHECK(rf_camera_set_lens(&cam, 0.2, 4.0) == RF_OK);
    RfRay lens = rf_camera_ray(&cam, 2.5, 3.5, 0.5, 0.5);
    RfVec3 off = rf_vec3_sub(lens.origin, cam.eye);
    RF_CHECK_NEAR(rf_vec3_dot(off, cam.basis.w), 0.0, 0.0, 1e-15);
    RF_CHECK_NEAR(rf_vec3_length(off), 0.2 * sqrt(0.5), 1e-14, 0.0);
    /* both rays pass through the same point of the focal plane (distance 4 along -w) */
    double tp = 4.0 / -rf_vec3_dot(pin.dir, cam.basis.w);
    double tl = (4.0 + rf_vec3_dot(off, cam.basis.w)) / -rf_vec3_dot(lens.dir, cam.basis.w);
    CHECK_VEC_NEAR(rf_ray_at(pin, tp), rf_ray_at(lens, tl), 1e-13);
}

/* ---- §3.6.2 Phong ---- */

/* By hand: N = (0,0,1), L = (0,1,1)/sqrt2, V = (0,0,1).
 *   <N,L> = 1/sqrt2; R_L = 2N<N,L> - L = (0, -1, 1)/sqrt2; <R_L,V> = 1/sqrt2;
 *   <R_L,V>^10 = 2^-5 = 1/32.
 * ka = (0.1, 0.2, 0.3), kd = (0.5, 0.6, 0.7), ks = (0.8, 0.4, 0.2), I_L = (1, 0.5, 2):
 *   ambient  = ka I_L           = (0.1, 0.1, 0.6)
 *   diffuse  = kd I_L / sqrt2   = (0.5, 0.3, 1.4)/sqrt2 = (0.35355339059327373, 0.21213203435596424, 0.98994949366116653)
 *   specular = ks I_L / 32      = (0.8, 0.2, 0.4)/32    = (0.025, 0.00625, 0.0125)
 *   total    = the sum          = (0.47855339059327373, 0.31838203435596424, 1.60244949366116653) */
static void test_phong(void)
{
    double s2 = sqrt(0.5);
    RfRgb ka = rf_rgb(0.1, 0.2, 0.3), kd = rf_rgb(0.5, 0.6, 0.7), ks = rf_rgb(0.8, 0.4, 0.2);
    RfRgb il = rf_rgb(1, 0.5, 2);
    RfPhong p = rf_phong(v3(0, 0, 1), v3(0, s2, s2), v3(0, 0, 1), ka, kd, ks, 10.0, il);
    CHECK_VEC_NEAR(p.r_l, v3(0, -s2, s2), 1e-16);
    RF_CHECK_NEAR(p.ambient.r, 0.1, 1e-15, 0);
    RF_CHECK_NEAR(p.ambient.g, 0.1, 1e-15, 0);
    RF_CHECK_NEAR(p.ambient.b, 0.6, 1e-15, 0);
    RF_CHECK_NEAR(p.diffuse.r, 0.35355339059327373, 1e-15, 0);
    RF_CHECK_NEAR(p.diffuse.g, 0.21213203435596424, 1e-15, 0);
    RF_CHECK_NEAR(p.diffuse.b, 0.98994949366116653, 1e-15, 0);
    RF_CHECK_NEAR(p.specular.r, 0.025, 1e-14, 0);
    RF_CHECK_NEAR(p.specular.g, 0.00625, 1e-14, 0);
    RF_CHECK_NEAR(p.specular.b, 0.0125, 1e-14, 0);
    RF_CHECK_NEAR(p.total.r, 0.47855339059327373, 1e-15, 0);
    RF_CHECK_NEAR(p.total.g, 0.31838203435596424, 1e-15, 0);
    RF_CHECK_NEAR(p.total.b, 1.60244949366116653, 1e-15, 0);
    /* light below the surface: only the ambient term, no highlight even if <R_L,V> > 0 */
    p = rf_phong(v3(0, 0, 1), v3(0, s2, -s2), v3(0, -s2, -s2), ka, kd, ks, 10.0, il);
    RF_CHECK(p.diffuse.r == 0 && p.diffuse.g == 0 && p.diffuse.b == 0);
    RF_CHECK(p.specular.r == 0 && p.specular.g == 0 && p.specular.b == 0);
    RF_CHECK(p.total.r == p.ambient.r && p.total.b == p.ambient.b);
    /* viewer opposite the mirror direction: <R_L,V> < 0 counts as 0 (also for n = 0) */
    p = rf_phong(v3(0, 0, 1), v3(0, s2, s2), v3(0, s2, -s2), ka, kd, ks, 0.0, il);
    RF_CHECK(p.specular.r == 0 && p.diffuse.r > 0);
    /* the mirror direction itself: <R_L,V> = 1 - 2^-52 after rounding, so with n = 1000
     * specular = ks I_L (1 - 2.2e-13) */
    p = rf_phong(v3(0, 0, 1), v3(0, s2, s2), v3(0, -s2, s2), ka, kd, ks, 1000.0, il);
    RF_CHECK_NEAR(p.specular.r, 0.8, 1e-12, 0);
}

/* ---- reflection identities ---- */

static void test_reflect(void)
{
    RfTestRng rng = {17};
    for (int k = 0; k < 1000; k++) {
        RfVec3 n = rand_unit(&rng), l = rand_vec(&rng, 3.0);
        RfVec3 r = rf_reflect(n, l);
        RF_CHECK_NEAR(rf_vec3_length(r), rf_vec3_length(l), 1e-14, 1e-14); /* length kept */
        RF_CHECK_NEAR(rf_vec3_dot(r, n), rf_vec3_dot(l, n), 1e-13, 1e-13); /* same angle to N */
        /* R + L = 2<N,L> N: the tangential parts cancel */
        CHECK_VEC_NEAR(rf_vec3_add(r, l), rf_vec3_scale(n, 2.0 * rf_vec3_dot(n, l)), 1e-13);
        CHECK_VEC_NEAR(rf_reflect(n, r), l, 1e-13); /* an involution */
        /* a travelling ray: D - 2<D,N>N, the same numbers as -reflect(N, -D)... reversed */
        RfVec3 d = rf_reflect_dir(l, n);
        RfVec3 e = rf_vec3_sub(l, rf_vec3_scale(n, 2.0 * rf_vec3_dot(l, n)));
        RF_CHECK(d.x == e.x && d.y == e.y && d.z == e.z);
    }
    CHECK_VEC_NEAR(rf_reflect(v3(0, 0, 1), v3(1, 0, 1)), v3(-1, 0, 1), 0.0);
    CHECK_VEC_NEAR(rf_reflect_dir(v3(1, 0, -1), v3(0, 0, 1)), v3(1, 0, 1), 0.0);
}

/* ---- §3.6.3 normals ---- */

static void test_normals(void)
{
    /* two faces at the origin: a big one in the xy plane (normal +z, area 2) and a small one
     * in the xz plane (normal -y, area 0.5): area weighting gives (0,-1,4)/sqrt17, while the
     * mean of the unit normals would give (0,-1,1)/sqrt2 */
    RfVec3 c[6] = {v3(0, 0, 0), v3(2, 0, 0), v3(0, 2, 0), v3(0, 0, 0), v3(1, 0, 0), v3(0, 0, 1)};
    RfVec3 n;
    RF_CHECK(rf_vertex_normal(c, 2, &n) == RF_OK);
    CHECK_VEC_NEAR(n, rf_vec3_scale(v3(0, -1, 4), 1.0 / sqrt(17.0)), 1e-15);
    RF_CHECK(rf_vertex_normal(c, 0, &n) == RF_ERR_DEGENERATE);
    /* interpolation: a vertex reproduces its normal; the midpoint of an edge is normalised */
    RfVec3 n1 = v3(1, 0, 0), n2 = v3(0, 1, 0), n3 = v3(0, 0, 1);
    RF_CHECK(rf_interpolate_normal(n1, n2, n3, 1, 0, 0, &n) == RF_OK);
    CHECK_VEC_NEAR(n, n1, 0.0);
    RF_CHECK(rf_interpolate_normal(n1, n2, n3, 0.5, 0.5, 0, &n) == RF_OK);
    CHECK_VEC_NEAR(n, v3(sqrt(0.5), sqrt(0.5), 0), 1e-16);
    RF_CHECK(rf_interpolate_normal(n1, rf_vec3_neg(n1), n3, 0.5, 0.5, 0, &n) == RF_ERR_DEGENERATE);
}

/* ---- §3.7 lights ---- */

static void test_lights(void)
{
    RfLightSample s;
    RfRgb one = rf_rgb(4, 8, 12);
    RF_CHECK(rf_light_point(one, v3(0, 0, 2), RF_FALLOFF_INVERSE_SQUARE, v3(0, 0, 0), &s) == RF_OK);
    RF_CHECK(s.i.r == 1 && s.i.g == 2 && s.i.b == 3 && s.distance == 2.0);
    CHECK_VEC_NEAR(s.l, v3(0, 0, 1), 0.0);
    RF_CHECK(rf_light_point(one, v3(0, 0, 2), RF_FALLOFF_NONE, v3(0, 0, 0), &s) == RF_OK);
    RF_CHECK(s.i.r == 4);
    RF_CHECK(rf_light_point(one, v3(1, 1, 1), RF_FALLOFF_NONE, v3(1, 1, 1), &s) == RF_ERR_DEGENERATE);
    s = rf_light_directional(rf_rgb(1, 1, 1), v3(0, -1, 0));
    CHECK_VEC_NEAR(s.l, v3(0, 1, 0), 0.0);
    RF_CHECK(isinf(s.distance));
    /* spot pointing down from (0,0,1), exponent 2, cutoff 30 deg; the point (0.5,0,0):
     * d^2 = 1.25, cos theta = 1/sqrt(1.25), i = 4 * 0.8 / 1.25 = 2.56 (red) */
    RF_CHECK(rf_light_spot(one, v3(0, 0, 1), v3(0, 0, -1), 2.0, RF_PI / 6, RF_FALLOFF_INVERSE_SQUARE,
                           v3(0.5, 0, 0), &s) == RF_OK);
    RF_CHECK_NEAR(s.i.r, 2.56, 1e-14, 0);
    RF_CHECK_NEAR(s.theta, atan(0.5), 1e-15, 0);
    /* outside the cutoff: 0 */
    RF_CHECK(rf_light_spot(one, v3(0, 0, 1), v3(0, 0, -1), 2.0, RF_PI / 6, RF_FALLOFF_INVERSE_SQUARE,
                           v3(1, 0, 0), &s) == RF_OK);
    RF_CHECK(s.i.r == 0 && s.i.g == 0);
    /* on the axis: the full point-light value */
    RF_CHECK(rf_light_spot(one, v3(0, 0, 1), v3(0, 0, -1), 7.0, 0.0, RF_FALLOFF_INVERSE_SQUARE,
                           v3(0, 0, -1), &s) == RF_OK);
    RF_CHECK(s.i.r == 1.0 && s.theta == 0.0);
}

/* ---- §3.8.1 refraction and Fresnel ---- */

static void test_snell_refract(void)
{
    RfTestRng rng = {99};
    /* symmetry: the way back with the indices swapped returns the incident angle */
    for (int k = 0; k < 1000; k++) {
        double ei = rf_test_uniform(&rng, 1.0, 2.5), et = rf_test_uniform(&rng, 1.0, 2.5);
        double th = rf_test_uniform(&rng, 0.0, RF_PI / 2);
        RfSnell s = rf_snell(ei, et, th);
        if (s.tir) {
            RF_CHECK(ei > et && th > s.critical);
            continue;
        }
        RF_CHECK_NEAR(ei * sin(th), et * sin(s.theta_t), 1e-14, 1e-15);
        if (s.theta_t < 1.5) { /* away from grazing, where asin amplifies rounding */
            RfSnell b = rf_snell(et, ei, s.theta_t);
            RF_CHECK(!b.tir);
            RF_CHECK_NEAR(b.theta_t, th, 1e-13, 1e-15);
        }
    }
    /* TIR only beyond the critical angle: at it theta_t = 90 deg */
    RfSnell s = rf_snell(1.5, 1.0, asin(1.0 / 1.5));
    RF_CHECK(!s.tir);
    RF_CHECK_NEAR(s.theta_t, RF_PI / 2, 1e-7, 0); /* sqrt sensitivity at grazing */
    RF_CHECK_NEAR(s.critical * 180.0 / RF_PI, 41.8103148957786, 1e-13, 0);
    RF_CHECK(rf_snell(1.5, 1.0, asin(1.0 / 1.5) + 1e-9).tir);
    RF_CHECK(isnan(rf_snell(1.0, 1.5, 1.0).critical));

    /* refract: unit result, on the far side, Snell's law holds, TIR agrees with Snell */
    for (int k = 0; k < 2000; k++) {
        RfVec3 n = rand_unit(&rng), i = rand_unit(&rng);
        if (rf_vec3_dot(i, n) < 0.0)
            i = rf_vec3_neg(i);
        double ei = rf_test_uniform(&rng, 1.0, 2.5), et = rf_test_uniform(&rng, 1.0, 2.5);
        RfVec3 t;
        int ok = rf_refract(i, n, ei, et, &t);
        double ci = rf_vec3_dot(i, n), sin_i = rf_vec3_length(rf_vec3_cross(i, n));
        RF_CHECK_EQ_INT(ok, !rf_snell(ei, et, atan2(sin_i, ci)).tir);
        RF_CHECK_EQ_INT(ok, !rf_fresnel(ei, et, ci, RF_FRESNEL_EXACT).tir);
        if (!ok)
            continue;
        RF_CHECK_NEAR(rf_vec3_length(t), 1.0, 1e-14, 0);
        RF_CHECK(rf_vec3_dot(t, n) <= 0.0);
        RF_CHECK_NEAR(ei * sin_i, et * rf_vec3_length(rf_vec3_cross(t, n)), 1e-12, 1e-13);
        /* T lies in the plane of I and N */
        RF_CHECK_NEAR(rf_vec3_dot(t, rf_vec3_cross(i, n)), 0.0, 0, 1e-14);
    }
    /* normal incidence passes straight through; 30 deg into glass by hand */
    RfVec3 t;
    RF_CHECK(rf_refract(v3(0, 0, 1), v3(0, 0, 1), 1.0, 1.5, &t));
    CHECK_VEC_NEAR(t, v3(0, 0, -1), 1e-16);
    RF_CHECK(rf_refract(v3(0, 0.5, sqrt(0.75)), v3(0, 0, 1), 1.0, 1.5, &t));
    /* sin theta_t = 0.5/1.5 = 1/3: T = (0, -1/3, -sqrt(8)/3) */
    CHECK_VEC_NEAR(t, v3(0, -1.0 / 3.0, -sqrt(8.0) / 3.0), 1e-15);
    /* TIR from glass at 60 deg */
    RF_CHECK(!rf_refract(v3(0, sqrt(0.75), 0.5), v3(0, 0, 1), 1.5, 1.0, &t));
}

static void test_fresnel(void)
{
    /* normal incidence: ((1.5 - 1)/(1.5 + 1))^2 = 0.04 from either side, both variants */
    RfFresnel f = rf_fresnel(1.0, 1.5, 1.0, RF_FRESNEL_EXACT);
    RF_CHECK_NEAR(f.r, 0.04, 1e-15, 0);
    RF_CHECK_NEAR(f.rs, 0.04, 1e-15, 0);
    RF_CHECK_NEAR(f.rp, 0.04, 1e-15, 0);
    RF_CHECK_NEAR(f.t, 0.96, 1e-15, 0);
    RF_CHECK_NEAR(rf_fresnel(1.5, 1.0, 1.0, RF_FRESNEL_EXACT).r, 0.04, 1e-15, 0);
    RF_CHECK_NEAR(rf_fresnel(1.0, 1.5, 1.0, RF_FRESNEL_SCHLICK).r, 0.04, 1e-15, 0);
    /* grazing: r = 1 */
    RF_CHECK(rf_fresnel(1.0, 1.5, 0.0, RF_FRESNEL_EXACT).r == 1.0);
    RF_CHECK(rf_fresnel(1.0, 1.5, 0.0, RF_FRESNEL_SCHLICK).r == 1.0);
    /* Brewster: tan theta_B = eta_t/eta_i, rp = 0 */
    double tb = atan(1.5);
    f = rf_fresnel(1.0, 1.5, cos(tb), RF_FRESNEL_EXACT);
    RF_CHECK_NEAR(f.rp, 0.0, 0, 1e-30);
    /* no interface */
    RF_CHECK(rf_fresnel(1.3, 1.3, 0.3, RF_FRESNEL_EXACT).r == 0.0);
    /* the critical angle from glass: r = 1 at it (up to the sqrt sensitivity of cos_t), exactly
     * 1 beyond, monotone over a +-1e-9 rad sweep, no NaN (reliability.md F2) */
    double tc = asin(1.0 / 1.5);
    f = rf_fresnel(1.5, 1.0, cos(tc), RF_FRESNEL_EXACT);
    RF_CHECK_NEAR(f.r, 1.0, 1e-6, 0);
    double prev = 0.0;
    for (int k = -100; k <= 100; k++) {
        double th = tc + k * 1e-11;
        RfFresnel g = rf_fresnel(1.5, 1.0, cos(th), RF_FRESNEL_EXACT);
        RF_CHECK(!isnan(g.r) && g.r >= prev && g.r <= 1.0);
        RF_CHECK_NEAR(g.r + g.t, 1.0, 1e-15, 0);
        if (k > 0)
            RF_CHECK(g.r == 1.0 && g.tir);
        prev = g.r;
    }
    RfFresnel s = rf_fresnel(1.5, 1.0, cos(tc + 1e-6), RF_FRESNEL_SCHLICK);
    RF_CHECK(s.r == 1.0 && s.tir && isnan(s.rs));
    /* reciprocity: F(cos_i; eta_i, eta_t) = F(cos_t; eta_t, eta_i) */
    RfTestRng rng = {1};
    for (int k = 0; k < 1000; k++) {
        double ei = rf_test_uniform(&rng, 1.0, 2.5), et = rf_test_uniform(&rng, 1.0, 2.5);
        double ci = rf_test_uniform(&rng, 0.0, 1.0);
        RfFresnel a = rf_fresnel(ei, et, ci, RF_FRESNEL_EXACT);
        if (a.tir)
            continue;
        double st = ei / et * sqrt(1.0 - ci * ci), ct = sqrt(1.0 - st * st);
        if (ct < 1e-3)
            continue;
        RfFresnel b = rf_fresnel(et, ei, ct, RF_FRESNEL_EXACT);
        RF_CHECK_NEAR(a.r, b.r, 1e-12, 1e-14);
        RF_CHECK(a.r >= 0.0 && a.r <= 1.0);
    }
    /* dispersion and ior by hand */
    RF_CHECK_NEAR(rf_cauchy(500.0, 1.5, 0.004), 1.516, 1e-15, 0);
    RF_CHECK_NEAR(rf_ior(RF_C0 / 1.5), 1.5, 1e-15, 0);
}

/* The independently computed cases (mpmath, 50 digits) through the registry: 1e-12 relative,
 * absolute floor 1e-14 for values that are zero in exact arithmetic (residues of order
 * 1e-16 x the inputs' magnitude, inputs <= 10); cases near grazing set their own tolerance. */
static void test_formula_cases(void)
{
    int n = rf_test_formula_cases("formula_cases_raytrace.jsonl", 1e-12, 1e-14);
    RF_CHECK(n >= 150);
}

const RfTest rf_tests_raytrace[] = {
    {"raytrace/sphere_cases", test_sphere_cases},
    {"raytrace/sphere_stable_vs_script", test_sphere_stable_vs_script},
    {"raytrace/plane_cases", test_plane_cases},
    {"raytrace/triangle_cases", test_triangle_cases},
    {"raytrace/triangle_methods_agree", test_triangle_methods_agree},
    {"raytrace/watertight_shared_edge", test_watertight_shared_edge},
    {"raytrace/watertight_closed_mesh", test_watertight_closed_mesh},
    {"raytrace/watertight_exact_edge_sign", test_watertight_exact_edge_sign},
    {"raytrace/cone_cylinder", test_cone_cylinder},
    {"raytrace/cone_framed", test_cone_framed},
    {"raytrace/camera", test_camera},
    {"raytrace/phong", test_phong},
    {"raytrace/reflect", test_reflect},
    {"raytrace/normals", test_normals},
    {"raytrace/lights", test_lights},
    {"raytrace/snell_refract", test_snell_refract},
    {"raytrace/fresnel", test_fresnel},
    {"raytrace/formula_cases", test_formula_cases},
    RF_TEST_END,
};
