/* §4: rotations, Euler angles, axis-angle vs Rodrigues, inverses, normals, camera. */
#include "refray/transform.h"
#include "rf_test.h"

static void check_mat3(RfMat3 a, RfMat3 b, double tol, const char *what)
{
    for (int r = 0; r < 3; r++)
        for (int c = 0; c < 3; c++) {
            rf_test_checks++;
            if (!(fabs(a.m[r][c] - b.m[r][c]) <= tol)) {
                rf_test_fail(__FILE__, __LINE__, "%s: entry (%d,%d) %.17g vs %.17g", what, r, c, a.m[r][c], b.m[r][c]);
                return;
            }
        }
}

static void t_elementary_rotations(void)
{
    /* 90 degrees: R_z maps x to y, R_x maps y to z, R_y maps z to x (right-handed) */
    RfVec3 v = rf_mat3_mul_vec(rf_mat3_rotate(RF_AXIS_Z, RF_PI / 2), rf_vec3(1, 0, 0));
    RF_CHECK_NEAR(v.x, 0, 0, 1e-16); RF_CHECK_NEAR(v.y, 1, 0, 0);
    v = rf_mat3_mul_vec(rf_mat3_rotate(RF_AXIS_X, RF_PI / 2), rf_vec3(0, 1, 0));
    RF_CHECK_NEAR(v.z, 1, 0, 0); RF_CHECK_NEAR(v.y, 0, 0, 1e-16);
    v = rf_mat3_mul_vec(rf_mat3_rotate(RF_AXIS_Y, RF_PI / 2), rf_vec3(0, 0, 1));
    RF_CHECK_NEAR(v.x, 1, 0, 0); RF_CHECK_NEAR(v.z, 0, 0, 1e-16);
    /* R^-1(phi) = R(-phi) = R^T */
    RfMat3 r = rf_mat3_rotate(RF_AXIS_Y, 0.7);
    check_mat3(rf_mat3_rotate(RF_AXIS_Y, -0.7), rf_mat3_transpose(r), 0, "R(-phi) = R^T");
}

/* The script's explicit matrix of R = R_z(phi) R_y(theta) R_x(psi), §4.3.1, transcribed. */
static RfMat3 script_euler(double psi, double th, double phi)
{
    double cps = cos(psi), sps = sin(psi), ct = cos(th), st = sin(th), cph = cos(phi), sph = sin(phi);
    RfMat3 m = {{{ct * cph, sps * st * cph - cps * sph, cps * st * cph + sps * sph},
                 {ct * sph, sps * st * sph + cps * cph, cps * st * sph - sps * cph},
                 {-st, sps * ct, cps * ct}}};
    return m;
}

static void t_euler(void)
{
    RfTestRng r = {4};
    for (int i = 0; i < 1000; i++) {
        double a = rf_test_uniform(&r, -4, 4), b = rf_test_uniform(&r, -4, 4), c = rf_test_uniform(&r, -4, 4);
        check_mat3(rf_mat3_euler(RF_EULER_ZYX, a, b, c), script_euler(a, b, c), 1e-15, "explicit Euler = product");
        for (int o = 0; o < 4; o++) {
            RfMat3 m = rf_mat3_euler((RfEulerOrder)o, a, b, c);
            RF_CHECK(rf_matn_is_orthogonal(3, &m.m[0][0]));
            RF_CHECK_NEAR(rf_mat3_det(m), 1.0, 1e-14, 0);
        }
    }
    /* xyz is the product in the other order: R_x(psi) R_y(theta) R_z(phi) */
    RfMat3 xyz = rf_mat3_euler(RF_EULER_XYZ, 0.1, 0.2, 0.3);
    RfMat3 want = rf_mat3_mul(rf_mat3_mul(rf_mat3_rotate(RF_AXIS_X, 0.1), rf_mat3_rotate(RF_AXIS_Y, 0.2)),
                              rf_mat3_rotate(RF_AXIS_Z, 0.3));
    check_mat3(xyz, want, 0, "xyz order");
}

static void t_rotation_basis(void)
{
    /* R_uvw R_uvw^T = I and R_uvw maps u, v, w to the axes, for camera bases of random views */
    RfTestRng r = {5};
    for (int i = 0; i < 500; i++) {
        RfVec3 eye = rf_vec3(rf_test_uniform(&r, -5, 5), rf_test_uniform(&r, -5, 5), rf_test_uniform(&r, -5, 5));
        RfVec3 tgt = rf_vec3(rf_test_uniform(&r, -5, 5), rf_test_uniform(&r, -5, 5), rf_test_uniform(&r, -5, 5));
        RfCameraBasis b;
        if (rf_camera_basis(eye, tgt, rf_vec3(0, 1, 0), &b) != RF_OK)
            continue;
        RfMat3 m = rf_mat3_rotation_basis(b.u, b.v, b.w);
        check_mat3(rf_mat3_mul(m, rf_mat3_transpose(m)), rf_mat3_identity(), 1e-15, "R R^T = I");
        RfVec3 x = rf_mat3_mul_vec(m, b.v);
        RF_CHECK_NEAR(x.y, 1.0, 1e-15, 0);
        /* the view matrix takes the eye to the origin and the target onto the -w axis */
        RfMat4 view = rf_camera_view(eye, b);
        RfVec3 e0, t0;
        rf_transform_point(view, eye, &e0);
        rf_transform_point(view, tgt, &t0);
        RF_CHECK_NEAR(rf_vec3_length(e0), 0.0, 0, 1e-14);
        RF_CHECK_NEAR(t0.z, -rf_vec3_length(rf_vec3_sub(tgt, eye)), 1e-13, 0);
        RF_CHECK_NEAR(t0.x, 0.0, 0, 1e-13);
        RF_CHECK_NEAR(t0.y, 0.0, 0, 1e-13);
    }
    RfCameraBasis b;
    RF_CHECK_EQ_INT(rf_camera_basis(rf_vec3(0, 0, 0), rf_vec3(0, 5, 0), rf_vec3(0, 1, 0), &b), RF_ERR_DEGENERATE);
    RF_CHECK_EQ_INT(rf_camera_basis(rf_vec3(0, 0, 0), rf_vec3(0, 0, 0), rf_vec3(0, 1, 0), &b), RF_ERR_DEGENERATE);
    RF_CHECK_EQ_INT(rf_camera_basis(rf_vec3(0, 0, 0), rf_vec3(0, 0, -1), rf_vec3(0, 0, 0), &b), RF_ERR_DEGENERATE);
    /* up not perpendicular to w: u is still unit length (erratum of §3.4) */
    RF_CHECK_EQ_INT(rf_camera_basis(rf_vec3(0, 0, 0), rf_vec3(0, 0, -1), rf_vec3(0, 3, 1), &b), RF_OK);
    RF_CHECK_NEAR(rf_vec3_length(b.u), 1.0, 1e-15, 0);
    RF_CHECK(b.u.x == 1.0 && b.v.y == 1.0 && b.w.z == 1.0);
}

static void t_axis_angle(void)
{
    RfTestRng r = {6};
    for (int i = 0; i < 2000; i++) {
        RfVec3 d = rf_vec3(rf_test_uniform(&r, -2, 2), rf_test_uniform(&r, -2, 2), rf_test_uniform(&r, -2, 2));
        if (i % 10 == 0) /* the degenerate helper case of the script: d along x */
            d = rf_vec3(i % 20 ? 3.0 : -0.5, 0, 0);
        double phi = rf_test_uniform(&r, -7, 7);
        RfMat3 a, b;
        RfVec3 e, f;
        RF_CHECK_EQ_INT(rf_mat3_axis_angle(d, phi, &a, &e, &f), RF_OK);
        RF_CHECK_EQ_INT(rf_mat3_rodrigues(d, phi, &b), RF_OK);
        check_mat3(a, b, 1e-14, "script construction = Rodrigues");
        /* (d, e, f) is a right-handed orthonormal frame and R d = d */
        RfVec3 dn = rf_vec3_normalize(d), rd = rf_mat3_mul_vec(a, dn);
        RF_CHECK_NEAR(rf_vec3_dot(dn, e), 0.0, 0, 1e-15);
        RF_CHECK_NEAR(rf_vec3_length(e), 1.0, 1e-15, 0);
        RF_CHECK_NEAR(rf_vec3_dot(rf_vec3_cross(dn, e), f), 1.0, 1e-15, 0);
        RF_CHECK_NEAR(rf_vec3_length(rf_vec3_sub(rd, dn)), 0.0, 0, 1e-15);
    }
    /* by hand: 120 degrees about (1,1,1) permutes the axes x -> y -> z */
    RfMat3 m;
    rf_mat3_axis_angle(rf_vec3(1, 1, 1), 2 * RF_PI / 3, &m, NULL, NULL);
    RfMat3 perm = {{{0, 0, 1}, {1, 0, 0}, {0, 1, 0}}};
    check_mat3(m, perm, 1e-15, "120 deg about (1,1,1)");
    RF_CHECK_EQ_INT(rf_mat3_axis_angle(rf_vec3(0, 0, 0), 1.0, &m, NULL, NULL), RF_ERR_DEGENERATE);
}

static void t_homogeneous(void)
{
    /* §4.6: translation moves points, not directions; composition (AB)^-1 = B^-1 A^-1 */
    RfMat4 t = rf_mat4_translate(rf_vec3(1, 2, 3)), s = rf_mat4_scale(2, 4, 8), ts = rf_mat4_mul(t, s);
    RfVec3 p;
    RF_CHECK_EQ_INT(rf_transform_point(ts, rf_vec3(1, 1, 1), &p), RF_OK);
    RF_CHECK(p.x == 3 && p.y == 6 && p.z == 11);
    RfVec3 d = rf_transform_direction(ts, rf_vec3(1, 1, 1));
    RF_CHECK(d.x == 2 && d.y == 4 && d.z == 8);
    RfMat4 inv, tinv, sinv;
    RF_CHECK_EQ_INT(rf_mat4_inverse(ts, &inv), RF_OK);
    rf_mat4_inverse(t, &tinv);
    rf_mat4_inverse(s, &sinv);
    RfMat4 want = rf_mat4_mul(sinv, tinv);
    for (int k = 0; k < 16; k++)
        RF_CHECK_NEAR(inv.m[k / 4][k % 4], want.m[k / 4][k % 4], 1e-15, 1e-16);
    /* shear_z: x += dx z */
    rf_transform_point(rf_mat4_shear_z(0.5, -1), rf_vec3(1, 1, 2), &p);
    RF_CHECK(p.x == 2 && p.y == -1 && p.z == 2);
    /* a projective matrix sending the point to infinity */
    RfMat4 proj = rf_mat4_identity();
    proj.m[3][2] = 1;
    proj.m[3][3] = 0;
    RF_CHECK_EQ_INT(rf_transform_point(proj, rf_vec3(1, 1, 0), &p), RF_ERR_DEGENERATE);
}

/* §4.9: the inverse transpose keeps normals perpendicular to tangents for every invertible M;
 * the shortcut n' = M n does so only for rotation x uniform scale. */
static void t_normals(void)
{
    RfVec3 n = rf_vec3_normalize(rf_vec3(1, 1, 0)), tangent = rf_vec3(1, -1, 0), out;
    RfMat3 nonuniform = rf_mat4_linear(rf_mat4_scale(2, 1, 1));
    RF_CHECK_EQ_INT(rf_transform_normal(nonuniform, n, &out), RF_OK);
    RfVec3 t2 = rf_mat3_mul_vec(nonuniform, tangent);
    RF_CHECK_NEAR(rf_vec3_dot(out, t2), 0.0, 0, 1e-15);
    /* by hand: (M^-1)^T n ~ (1/2, 1, 0) -> (1, 2, 0)/sqrt(5) */
    RF_CHECK_NEAR(out.x, 1 / sqrt(5.0), 1e-15, 0);
    RF_CHECK_NEAR(out.y, 2 / sqrt(5.0), 1e-15, 0);
    RfVec3 shortcut = rf_vec3_normalize(rf_mat3_mul_vec(nonuniform, n));
    RF_CHECK(fabs(rf_vec3_dot(shortcut, t2)) > 0.5); /* the shortcut is wrong here */
    RF_CHECK(!rf_matn_is_similarity(3, &nonuniform.m[0][0], NULL));
    RfTestRng r = {7};
    for (int i = 0; i < 500; i++) {
        double s = rf_test_uniform(&r, 0.1, 10);
        RfMat3 sim = rf_mat3_euler(RF_EULER_ZYX, rf_test_uniform(&r, -3, 3), rf_test_uniform(&r, -3, 3),
                                   rf_test_uniform(&r, -3, 3));
        for (int k = 0; k < 9; k++)
            sim.m[k / 3][k % 3] *= s;
        RfVec3 nn = rf_vec3_normalize(rf_vec3(rf_test_uniform(&r, -1, 1), rf_test_uniform(&r, -1, 1), 0.3));
        double lambda;
        RF_CHECK(rf_matn_is_similarity(3, &sim.m[0][0], &lambda));
        RF_CHECK_NEAR(lambda, s * s, 1e-13, 0);
        RF_CHECK_EQ_INT(rf_transform_normal(sim, nn, &out), RF_OK);
        RfVec3 sc = rf_vec3_normalize(rf_mat3_mul_vec(sim, nn));
        RF_CHECK_NEAR(rf_vec3_length(rf_vec3_sub(out, sc)), 0.0, 0, 1e-14); /* shortcut = exact */
    }
    RfMat3 sing = rf_mat4_linear(rf_mat4_scale(1, 0, 1));
    RF_CHECK_EQ_INT(rf_transform_normal(sing, n, &out), RF_ERR_SINGULAR);
    RF_CHECK_EQ_INT(rf_transform_normal(nonuniform, rf_vec3(0, 0, 0), &out), RF_ERR_DEGENERATE);
}

static void t_2d(void)
{
    RfVec2 p = rf_mat2_mul_vec(rf_mat2_rotate(RF_PI / 2), rf_vec2(1, 0));
    RF_CHECK_NEAR(p.x, 0, 0, 1e-16); RF_CHECK_NEAR(p.y, 1, 0, 0);
    p = rf_mat2_mul_vec(rf_mat2_shear(RF_AXIS_X, 2), rf_vec2(1, 1));
    RF_CHECK(p.x == 3 && p.y == 1);
    p = rf_mat2_mul_vec(rf_mat2_reflect(RF_AXIS_Y), rf_vec2(1, 1));
    RF_CHECK(p.x == 1 && p.y == -1);
    /* a shear keeps the area: det = 1 */
    RfMat2 sh = rf_mat2_shear(RF_AXIS_Y, 5);
    RF_CHECK(rf_matn_det(2, &sh.m[0][0]) == 1.0);
}

const RfTest rf_tests_transform[] = {
    {"tf_elementary_rotations", t_elementary_rotations},
    {"tf_euler", t_euler},
    {"tf_rotation_basis_camera", t_rotation_basis},
    {"tf_axis_angle_rodrigues", t_axis_angle},
    {"tf_homogeneous", t_homogeneous},
    {"tf_normals", t_normals},
    {"tf_2d", t_2d},
    RF_TEST_END,
};
