/* Vectors and matrices: hand-derived values and identities over many random inputs. */
#include <float.h>
#include <string.h>

#include "refray/mat.h"
#include "refray/vec.h"
#include "rf_test.h"

static RfVec3 rand_vec(RfTestRng *r, double s)
{
    return rf_vec3(rf_test_uniform(r, -s, s), rf_test_uniform(r, -s, s), rf_test_uniform(r, -s, s));
}

static void check_vec(RfVec3 a, RfVec3 b, double tol, const char *what)
{
    double scale = fmax(1.0, fmax(rf_vec3_length(a), rf_vec3_length(b)));
    rf_test_checks++;
    if (!(fabs(a.x - b.x) <= tol * scale && fabs(a.y - b.y) <= tol * scale && fabs(a.z - b.z) <= tol * scale))
        rf_test_fail(__FILE__, __LINE__, "%s: (%.17g %.17g %.17g) vs (%.17g %.17g %.17g)", what, a.x, a.y,
                     a.z, b.x, b.y, b.z);
}

static void t_vec_basics(void)
{
    /* by hand: |(1,2,2)| = 3; <(1,2,3),(4,-5,6)> = 4 - 10 + 18 = 12;
     * (1,2,3) x (4,5,6) = (2*6-3*5, 3*4-1*6, 1*5-2*4) = (-3, 6, -3) */
    RF_CHECK_NEAR(rf_vec3_length(rf_vec3(1, 2, 2)), 3.0, 0, 0);
    RF_CHECK_NEAR(rf_vec3_dot(rf_vec3(1, 2, 3), rf_vec3(4, -5, 6)), 12.0, 0, 0);
    RfVec3 c = rf_vec3_cross(rf_vec3(1, 2, 3), rf_vec3(4, 5, 6));
    RF_CHECK(c.x == -3.0 && c.y == 6.0 && c.z == -3.0);
    RF_CHECK_NEAR(rf_vec3_angle(rf_vec3(1, 0, 0), rf_vec3(1, 1, 0)), RF_PI / 4, 1e-15, 0);
    RF_CHECK_NEAR(rf_vec3_angle(rf_vec3(1, 0, 0), rf_vec3(-1, 1e-9, 0)), RF_PI - 1e-9, 1e-15, 0);
    RfVec3 z = rf_vec3_normalize(rf_vec3(0, 0, 0));
    RF_CHECK(z.x == 0.0 && z.y == 0.0 && z.z == 0.0);
}

static void t_cross_precision(void)
{
    /* nearly parallel vectors: the plain a.y*b.z - a.z*b.y cancels; the fma form keeps every
     * digit. a = (1, 1+2^-30, 1), b = (1, 1, 1): exact cross = (2^-30, 0, -2^-30). */
    double e = ldexp(1.0, -30);
    RfVec3 c = rf_vec3_cross(rf_vec3(1, 1 + e, 1), rf_vec3(1, 1, 1));
    RF_CHECK(c.x == e && c.y == 0.0 && c.z == -e);
    /* a = (1+2^-27, 1, 0), b = (1, 1-2^-27, 0): z = (1+h)(1-h) - 1 = -h^2 exactly, h = 2^-27;
     * the plain product rounds (1+h)(1-h) = 1 - 2^-54 to 1 and gives 0 */
    double h = ldexp(1.0, -27);
    RfVec3 d = rf_vec3_cross(rf_vec3(1 + h, 1, 0), rf_vec3(1, 1 - h, 0));
    RF_CHECK(d.z == -h * h);
}

/* §2.1 identities, with the corrected signs of (iv) and (v). */
static void t_cross_identities(void)
{
    RfTestRng r = {1};
    for (int i = 0; i < 2000; i++) {
        RfVec3 a = rand_vec(&r, 10), b = rand_vec(&r, 10), c = rand_vec(&r, 10), d = rand_vec(&r, 10);
        double s = rf_test_uniform(&r, -5, 5);
        RfVec3 axb = rf_vec3_cross(a, b);
        double scale = rf_vec3_length(a) * rf_vec3_length(b);
        /* (i) <a, a x b> = <b, a x b> = 0 */
        RF_CHECK_NEAR(rf_vec3_dot(a, axb) / (scale * rf_vec3_length(a)), 0.0, 0, 1e-14);
        RF_CHECK_NEAR(rf_vec3_dot(b, axb) / (scale * rf_vec3_length(b)), 0.0, 0, 1e-14);
        /* (ii) <a, b x c> = <a x b, c> */
        double lhs = rf_vec3_dot(a, rf_vec3_cross(b, c)), rhs = rf_vec3_dot(axb, c);
        RF_CHECK_NEAR(lhs, rhs, 0, 1e-13 * scale * rf_vec3_length(c));
        /* (iii) a x (s b + c) = s (a x b) + a x c */
        check_vec(rf_vec3_cross(a, rf_vec3_add(rf_vec3_scale(b, s), c)),
                  rf_vec3_add(rf_vec3_scale(axb, s), rf_vec3_cross(a, c)), 1e-12 * 100, "(iii)");
        /* (iv) a x (b x c) = b<a,c> - c<a,b> */
        check_vec(rf_vec3_cross(a, rf_vec3_cross(b, c)),
                  rf_vec3_sub(rf_vec3_scale(b, rf_vec3_dot(a, c)), rf_vec3_scale(c, rf_vec3_dot(a, b))),
                  1e-12 * 1000, "(iv)");
        /* (v) <a x b, c x d> = <a,c><b,d> - <a,d><b,c> */
        double v1 = rf_vec3_dot(axb, rf_vec3_cross(c, d));
        double v2 = rf_vec3_dot(a, c) * rf_vec3_dot(b, d) - rf_vec3_dot(a, d) * rf_vec3_dot(b, c);
        RF_CHECK_NEAR(v1, v2, 0, 1e-12 * 1e4);
        /* |a x b| = |a||b| sin(phi) */
        RF_CHECK_NEAR(rf_vec3_length(axb), scale * sin(rf_vec3_angle(a, b)), 1e-12, 1e-12 * scale);
    }
}

static void t_mat_inverse_identities(void)
{
    RfTestRng r = {2};
    for (int i = 0; i < 1000; i++) {
        RfMat4 a, b, ai, bi, abi;
        for (int k = 0; k < 16; k++) {
            a.m[k / 4][k % 4] = rf_test_uniform(&r, -3, 3);
            b.m[k / 4][k % 4] = rf_test_uniform(&r, -3, 3);
        }
        if (rf_mat4_inverse(a, &ai) || rf_mat4_inverse(b, &bi) ||
            rf_mat4_inverse(rf_mat4_mul(a, b), &abi)) {
            continue; /* a random matrix is singular with probability 0; rounding could still trip */
        }
        /* A A^-1 = I, and (AB)^-1 = B^-1 A^-1, relative to the condition of the product */
        RfMat4 id = rf_mat4_mul(a, ai), bia = rf_mat4_mul(bi, ai);
        double norm = 0;
        for (int k = 0; k < 16; k++)
            norm = fmax(norm, fabs(abi.m[k / 4][k % 4]));
        for (int k = 0; k < 16; k++) {
            RF_CHECK_NEAR(id.m[k / 4][k % 4], k % 5 == 0 ? 1.0 : 0.0, 0, 1e-9);
            RF_CHECK_NEAR(abi.m[k / 4][k % 4], bia.m[k / 4][k % 4], 0, 1e-9 * norm);
        }
        /* det(AB) = det(A) det(B), det(A^-1) = 1/det(A) */
        RF_CHECK_NEAR(rf_mat4_det(rf_mat4_mul(a, b)), rf_mat4_det(a) * rf_mat4_det(b), 1e-9, 1e-12);
        RF_CHECK_NEAR(rf_mat4_det(ai) * rf_mat4_det(a), 1.0, 1e-9, 0);
    }
}

static void t_mat_singular(void)
{
    /* rank 2: row 3 = row 1 + row 2 */
    RfMat3 s = {{{1, 2, 3}, {4, 5, 6}, {5, 7, 9}}}, out = rf_mat3_identity();
    RF_CHECK_EQ_INT(rf_mat3_inverse(s, &out), RF_ERR_SINGULAR);
    RF_CHECK(out.m[0][0] == 1.0); /* untouched */
    RF_CHECK(rf_mat3_det(s) == 0.0 || fabs(rf_mat3_det(s)) < 1e-14);
    RfMat3 z = {{{0, 0, 0}, {0, 0, 0}, {0, 0, 0}}};
    RF_CHECK_EQ_INT(rf_mat3_inverse(z, &out), RF_ERR_SINGULAR);
    RfMat3 nan = rf_mat3_identity();
    nan.m[1][1] = NAN;
    RF_CHECK_EQ_INT(rf_mat3_inverse(nan, &out), RF_ERR_DOMAIN);
    /* the policy of numeric.h: a pivot under 1e-13 times the largest entry is singular.
     * diag(1e-5, 1e5, 1): pivot 1e-5 > 1e-8, regular, inverse exact; diag(1e-9, 1e5, 1):
     * condition 1e14, called singular */
    RfMat3 d = {{{1e-5, 0, 0}, {0, 1e5, 0}, {0, 0, 1}}};
    RF_CHECK_EQ_INT(rf_mat3_inverse(d, &out), RF_OK);
    RF_CHECK_NEAR(out.m[0][0], 1e5, 1e-15, 0);
    RF_CHECK_NEAR(out.m[1][1], 1e-5, 1e-15, 0);
    d.m[0][0] = 1e-9;
    RF_CHECK_EQ_INT(rf_mat3_inverse(d, &out), RF_ERR_SINGULAR);
}

static void t_mat_det_by_hand(void)
{
    /* det [[2,0,1],[1,3,2],[1,1,1]] = 2(3-2) - 0 + 1(1-3) = 0 -> singular; and
     * det [[2,0,1],[1,3,2],[1,1,2]] = 2(6-2) - 0 + 1(1-3) = 6 */
    RfMat3 a = {{{2, 0, 1}, {1, 3, 2}, {1, 1, 2}}}, inv;
    RF_CHECK_NEAR(rf_mat3_det(a), 6.0, 1e-15, 0);
    RF_CHECK_EQ_INT(rf_mat3_inverse(a, &inv), RF_OK);
    /* adjugate / 6: row 0 = (4, 1, -3)/6 */
    RF_CHECK_NEAR(inv.m[0][0], 4.0 / 6, 1e-15, 0);
    RF_CHECK_NEAR(inv.m[0][1], 1.0 / 6, 1e-15, 0);
    RF_CHECK_NEAR(inv.m[0][2], -3.0 / 6, 1e-15, 0);
}

/* rf_min_num / rf_max_num give the C library's fmin / fmax bit for bit (they replace its calls in
 * the sphere test, whose roots must not change): signed zeros both ways, NaNs, infinities,
 * subnormals and random values. */
static void t_min_max_num(void)
{
    const double special[] = {0.0, -0.0, 1.0, -1.0, 0x1p-1074, -0x1p-1074, 0x1p-1022, DBL_MAX, -DBL_MAX,
                              INFINITY, -INFINITY, NAN, -NAN, 1.5, 1.5 + 0x1p-52};
    enum { NS = sizeof special / sizeof special[0] };
    double vals[NS + 200];
    RfTestRng r = {21};
    for (int i = 0; i < NS; i++)
        vals[i] = special[i];
    for (int i = NS; i < NS + 200; i++)
        vals[i] = i % 3 ? rf_test_uniform(&r, -4, 4) : vals[i - 1]; /* ties too */
    int bad = 0;
    for (int i = 0; i < NS + 200; i++)
        for (int j = 0; j < NS + 200; j++) {
            double x = vals[i], y = vals[j];
            double got[2] = {rf_min_num(x, y), rf_max_num(x, y)}, want[2] = {fmin(x, y), fmax(x, y)};
            for (int k = 0; k < 2; k++) {
                rf_test_checks++;
                if (memcmp(&got[k], &want[k], sizeof got[k]) != 0 && !(isnan(got[k]) && isnan(want[k])) && bad++ < 5)
                    rf_test_fail(__FILE__, __LINE__, "%s(%a, %a) = %a, the library gives %a", k ? "max" : "min", x,
                                 y, got[k], want[k]);
            }
        }
}

/* rf_next_up is nextafter(x, +inf) bit for bit: zeros, subnormals, the largest double, the
 * infinities, NaN and random values of both signs. */
static void t_next_up(void)
{
    const double special[] = {0.0, -0.0, 0x1p-1074, -0x1p-1074, 0x1p-1022, -0x1p-1022, DBL_MAX, -DBL_MAX,
                              INFINITY, -INFINITY, 1.0, -1.0, 0x1.fffffffffffffp-1, -2.0};
    RfTestRng r = {22};
    for (int i = 0; i < (int)(sizeof special / sizeof special[0]) + 2000; i++) {
        double x = i < (int)(sizeof special / sizeof special[0]) ? special[i] : rf_test_uniform(&r, -1e3, 1e3);
        double got = rf_next_up(x), want = nextafter(x, HUGE_VAL);
        rf_test_checks++;
        if (memcmp(&got, &want, sizeof got) != 0)
            rf_test_fail(__FILE__, __LINE__, "rf_next_up(%a) = %a, nextafter gives %a", x, got, want);
    }
    RF_CHECK(isnan(rf_next_up(NAN)));
}

const RfTest rf_tests_vecmat[] = {
    {"vec_basics", t_vec_basics},
    {"vec_cross_precision", t_cross_precision},
    {"vec_cross_identities", t_cross_identities},
    {"mat_inverse_identities", t_mat_inverse_identities},
    {"mat_singular", t_mat_singular},
    {"mat_det_by_hand", t_mat_det_by_hand},
    {"vec_min_max_num", t_min_max_num},
    {"vec_next_up", t_next_up},
    RF_TEST_END,
};
