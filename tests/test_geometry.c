/* §2: triangle normal, parameter forms, bases, barycentric coordinates. */
#include "refray/geometry.h"
#include "rf_test.h"

#include <stdlib.h>

static void t_triangle_normal(void)
{
    /* by hand: a=(0,0,0), b=(2,0,0), c=(0,2,0): n' = (2,0,0) x (0,2,0) = (0,0,4), area 2 */
    RfTriangleNormal t;
    RF_CHECK_EQ_INT(rf_triangle_normal(rf_vec3(0, 0, 0), rf_vec3(2, 0, 0), rf_vec3(0, 2, 0), &t), RF_OK);
    RF_CHECK(t.n_raw.z == 4.0 && t.n.z == 1.0 && t.area == 2.0);
    /* reversed orientation flips the normal */
    rf_triangle_normal(rf_vec3(0, 0, 0), rf_vec3(0, 2, 0), rf_vec3(2, 0, 0), &t);
    RF_CHECK(t.n.z == -1.0);
    RF_CHECK_EQ_INT(rf_triangle_normal(rf_vec3(0, 0, 0), rf_vec3(1, 1, 1), rf_vec3(2, 2, 2), &t),
                    RF_ERR_DEGENERATE);
}

static void t_param_forms(void)
{
    RfVec3 p = rf_line_point(rf_vec3(1, 2, 3), rf_vec3(3, 2, 1), 0.25);
    RF_CHECK(p.x == 1.5 && p.y == 2.0 && p.z == 2.5);
    RfVec3 q = rf_plane_point(rf_vec3(0, 0, 0), rf_vec3(2, 0, 0), rf_vec3(0, 4, 0), 0.5, 0.25);
    RF_CHECK(q.x == 1.0 && q.y == 1.0 && q.z == 0.0);
}

static void t_basis(void)
{
    /* v = 2 b1 + 3 b2 with b1 = (1,1), b2 = (1,-1): v = (5, -1) */
    double b1[2] = {1, 1}, b2[2] = {1, -1}, v[2] = {5, -1}, c[2];
    const double *basis[2] = {b1, b2};
    RF_CHECK_EQ_INT(rf_basis_coordinates(2, basis, v, c), RF_OK);
    RF_CHECK_NEAR(c[0], 2.0, 1e-15, 0);
    RF_CHECK_NEAR(c[1], 3.0, 1e-15, 0);
    RF_CHECK(rf_basis_is_orthogonal(2, basis, 0));
    RF_CHECK(!rf_basis_is_orthogonal(2, basis, 1));
    double d1[3] = {1, 2, 3}, d2[3] = {2, 4, 6}, d3[3] = {0, 0, 1}, w[3] = {1, 1, 1}, cc[3];
    const double *dep[3] = {d1, d2, d3};
    RF_CHECK_EQ_INT(rf_basis_coordinates(3, dep, w, cc), RF_ERR_SINGULAR);
}

static void t_barycentric(void)
{
    double l[3];
    /* by hand: triangle (0,0),(4,0),(0,4), q = (1,1): areas 4, 2, 2 of 8 -> (0.5, 0.25, 0.25) */
    RF_CHECK_EQ_INT(rf_barycentric(rf_vec3(0, 0, 0), rf_vec3(4, 0, 0), rf_vec3(0, 4, 0), rf_vec3(1, 1, 0), l), RF_OK);
    RF_CHECK(l[0] == 0.5 && l[1] == 0.25 && l[2] == 0.25);
    /* the vertices and the edge midpoints */
    rf_barycentric(rf_vec3(0, 0, 0), rf_vec3(4, 0, 0), rf_vec3(0, 4, 0), rf_vec3(4, 0, 0), l);
    RF_CHECK(l[0] == 0.0 && l[1] == 1.0 && l[2] == 0.0);
    rf_barycentric(rf_vec3(0, 0, 0), rf_vec3(4, 0, 0), rf_vec3(0, 4, 0), rf_vec3(2, 2, 0), l);
    RF_CHECK(l[0] == 0.0 && l[1] == 0.5 && l[2] == 0.5);
    /* a point off the plane gets the coordinates of its projection */
    rf_barycentric(rf_vec3(0, 0, 0), rf_vec3(4, 0, 0), rf_vec3(0, 4, 0), rf_vec3(1, 1, 7), l);
    RF_CHECK(l[0] == 0.5 && l[1] == 0.25 && l[2] == 0.25);
    /* property: Q = sum l_i P_i and sum l_i = 1 over random triangles */
    RfTestRng r = {3};
    for (int i = 0; i < 1000; i++) {
        RfVec3 p[3], q;
        for (int k = 0; k < 3; k++)
            p[k] = rf_vec3(rf_test_uniform(&r, -9, 9), rf_test_uniform(&r, -9, 9), rf_test_uniform(&r, -9, 9));
        double w0 = rf_test_uniform(&r, -1, 2), w1 = rf_test_uniform(&r, -1, 2), w2 = 1.0 - w0 - w1;
        q = rf_vec3_add(rf_vec3_add(rf_vec3_scale(p[0], w0), rf_vec3_scale(p[1], w1)), rf_vec3_scale(p[2], w2));
        if (rf_barycentric(p[0], p[1], p[2], q, l) != RF_OK)
            continue;
        RF_CHECK_NEAR(l[0] + l[1] + l[2], 1.0, 0, 1e-9);
        RF_CHECK_NEAR(l[0], w0, 0, 1e-7);
        RF_CHECK_NEAR(l[1], w1, 0, 1e-7);
    }
    RF_CHECK_EQ_INT(rf_barycentric(rf_vec3(0, 0, 0), rf_vec3(1, 0, 0), rf_vec3(2, 0, 0), rf_vec3(1, 1, 0), l),
                    RF_ERR_DEGENERATE);
}

/* Ear clipping on polygons that are hard for it: random star-shaped polygons (sorted angles,
 * random radii: simple by construction, about half the corners reflex), a comb with deep teeth and
 * a spiral strip, both orientations. A valid triangulation of a simple polygon has n - 2
 * triangles, each of positive area in the polygon's orientation (no zero-area ear: it would
 * leave a T-junction), no vertex strictly inside any of them, and areas that sum to the
 * polygon's (shoelace formula). */
static double tri_area2(const double *u, const double *v, const int *t)
{
    return (u[t[1]] - u[t[0]]) * (v[t[2]] - v[t[0]]) - (v[t[1]] - v[t[0]]) * (u[t[2]] - u[t[0]]);
}

static void check_triangulation(const double *u, const double *v, int n, const char *what)
{
    int *t = malloc(sizeof *t * 3 * (size_t)n);
    int nt = rf_triangulate_polygon_2d(u, v, n, t);
    double area2 = 0.0, sum = 0.0;
    for (int k = 0; k < n; k++)
        area2 += u[k] * v[(k + 1) % n] - u[(k + 1) % n] * v[k];
    int bad_orientation = 0, inside = 0;
    for (int k = 0; k < nt; k++) {
        double a = tri_area2(u, v, t + 3 * k) * (area2 > 0 ? 1 : -1);
        bad_orientation += !(a > 0.0); /* no ear of three collinear corners: the comb's spine has them */
        sum += a;
        for (int q = 0; q < n && n <= 400; q++) {
            if (q == t[3 * k] || q == t[3 * k + 1] || q == t[3 * k + 2])
                continue;
            int e[3] = {t[3 * k], t[3 * k + 1], t[3 * k + 2]}, in = 1;
            for (int j = 0; j < 3; j++) {
                int w[3] = {e[j], e[(j + 1) % 3], q};
                in &= tri_area2(u, v, w) * (area2 > 0 ? 1 : -1) > 0.0;
            }
            inside += in;
        }
    }
    if (nt != n - 2 || bad_orientation || inside || !rf_test_near(sum, fabs(area2), 1e-9, 0))
        rf_test_fail(__FILE__, __LINE__, "%s: %d triangles (expected %d), %d not in the polygon's orientation, "
                     "%d vertices inside a triangle, area %.17g vs %.17g", what, nt, n - 2, bad_orientation, inside,
                     sum, fabs(area2));
    rf_test_checks++;
    free(t);
}

static void test_triangulate_hard_polygons(void)
{
    RfTestRng rng = {2024};
    enum { MAX = 100000 };
    double *u = malloc(sizeof *u * MAX), *v = malloc(sizeof *v * MAX);
    char what[64];
    for (int trial = 0; trial < 40; trial++) {
        int n = trial < 38 ? 5 + trial * 5 : (trial == 38 ? 20000 : MAX);
        double *ang = malloc(sizeof *ang * (size_t)n);
        for (int k = 0; k < n; k++)
            ang[k] = 2 * 3.14159265358979323846 * (k + rf_test_uniform(&rng, 0.0, 0.9)) / n;
        for (int k = 0; k < n; k++) {
            double r = rf_test_uniform(&rng, 0.2, 1.0);
            int kk = trial % 2 ? k : n - 1 - k; /* odd trials counter-clockwise, even clockwise */
            u[kk] = r * cos(ang[k]);
            v[kk] = r * sin(ang[k]);
        }
        free(ang);
        snprintf(what, sizeof what, "random star %d (n = %d)", trial, n);
        check_triangulation(u, v, n, what);
    }
    /* a comb: a spine along the bottom and 60 teeth 10 high, 0.5 wide, 0.5 apart */
    int n = 0;
    for (int k = 0; k < 60; k++) {
        double x = k;
        u[n] = x, v[n++] = 10, u[n] = x + 0.5, v[n++] = 10, u[n] = x + 0.5, v[n++] = 1, u[n] = x + 1, v[n++] = 1;
    }
    u[n] = 60, v[n++] = 0, u[n] = 0, v[n++] = 0;
    check_triangulation(u, v, n, "comb (clockwise)");
    for (int k = 0; k < n / 2; k++) { /* reversed: counter-clockwise */
        double tu = u[k], tv = v[k];
        u[k] = u[n - 1 - k], v[k] = v[n - 1 - k], u[n - 1 - k] = tu, v[n - 1 - k] = tv;
    }
    check_triangulation(u, v, n, "comb (counter-clockwise)");
    /* a spiral strip: out along r = 1 + a, back along r = 1.5 + a, 3 turns */
    n = 0;
    for (int k = 0; k <= 150; k++) {
        double a = 6 * 3.14159265358979323846 * k / 150;
        u[n] = (1 + a) * cos(a), v[n++] = (1 + a) * sin(a);
    }
    for (int k = 150; k >= 0; k--) {
        double a = 6 * 3.14159265358979323846 * k / 150;
        u[n] = (1.5 + a) * cos(a), v[n++] = (1.5 + a) * sin(a);
    }
    check_triangulation(u, v, n, "spiral strip");
    free(u), free(v);
}

const RfTest rf_tests_geometry[] = {
    {"geometry_triangulate_hard_polygons", test_triangulate_hard_polygons},
    {"geom_triangle_normal", t_triangle_normal},
    {"geom_param_forms", t_param_forms},
    {"geom_basis", t_basis},
    {"geom_barycentric", t_barycentric},
    RF_TEST_END,
};
