/* §2: triangle normal, parameter forms, bases, barycentric coordinates. */
#include "refray/geometry.h"
#include "rf_test.h"

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

const RfTest rf_tests_geometry[] = {
    {"geom_triangle_normal", t_triangle_normal},
    {"geom_param_forms", t_param_forms},
    {"geom_basis", t_basis},
    {"geom_barycentric", t_barycentric},
    RF_TEST_END,
};
