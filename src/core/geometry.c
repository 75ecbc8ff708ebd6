/* §2 analytic geometry. */
#include "refray/geometry.h"
#include "refray/mat.h"
#include "refray/numeric.h"

#include <math.h>

double rf_vec3_angle(RfVec3 a, RfVec3 b)
{
    return atan2(rf_vec3_length(rf_vec3_cross(a, b)), rf_vec3_dot(a, b));
}

RfStatus rf_triangle_normal(RfVec3 a, RfVec3 b, RfVec3 c, RfTriangleNormal *out)
{
    out->n_raw = rf_vec3_cross(rf_vec3_sub(b, a), rf_vec3_sub(c, a));
    double len = rf_vec3_length(out->n_raw);
    out->area = 0.5 * len;
    if (!(len > 0.0)) {
        out->n = rf_vec3(0.0, 0.0, 0.0);
        return RF_ERR_DEGENERATE;
    }
    out->n = rf_vec3_scale(out->n_raw, 1.0 / len);
    return RF_OK;
}

RfVec3 rf_line_point(RfVec3 p, RfVec3 q, double t)
{
    return rf_vec3_add(p, rf_vec3_scale(rf_vec3_sub(q, p), t));
}

RfVec3 rf_plane_point(RfVec3 p, RfVec3 q, RfVec3 r, double s, double t)
{
    return rf_vec3_add(p, rf_vec3_add(rf_vec3_scale(rf_vec3_sub(q, p), s),
                                      rf_vec3_scale(rf_vec3_sub(r, p), t)));
}

RfStatus rf_basis_coordinates(int n, const double *const *basis, const double *v, double *coords)
{
    double m[RF_MATN_MAX * RF_MATN_MAX];
    if (n < 1 || n > RF_MATN_MAX)
        return RF_ERR_DOMAIN;
    /* the basis vectors are the columns of the system matrix */
    for (int r = 0; r < n; r++)
        for (int c = 0; c < n; c++)
            m[r * n + c] = basis[c][r];
    return rf_matn_solve(n, m, v, coords);
}

int rf_basis_is_orthogonal(int n, const double *const *basis, int unit)
{
    for (int i = 0; i < n; i++) {
        double lii = 0.0;
        for (int k = 0; k < n; k++)
            lii += basis[i][k] * basis[i][k];
        if (unit && fabs(lii - 1.0) > RF_STRUCTURE_TOL)
            return 0;
        for (int j = i + 1; j < n; j++) {
            double dij = 0.0, ljj = 0.0;
            for (int k = 0; k < n; k++) {
                dij += basis[i][k] * basis[j][k];
                ljj += basis[j][k] * basis[j][k];
            }
            /* cosine of the angle, so the test does not depend on the lengths */
            if (fabs(dij) > RF_STRUCTURE_TOL * sqrt(lii * ljj))
                return 0;
        }
    }
    return 1;
}

RfStatus rf_barycentric(RfVec3 p1, RfVec3 p2, RfVec3 p3, RfVec3 q, double l[3])
{
    RfVec3 n = rf_vec3_cross(rf_vec3_sub(p2, p1), rf_vec3_sub(p3, p1));
    double whole = rf_vec3_dot(n, n); /* 2 * area * |n|: the oriented area measured along n */
    if (!(whole > 0.0))
        return RF_ERR_DEGENERATE;
    /* Delta(Q,P2,P3), Delta(P1,Q,P3), Delta(P1,P2,Q), each as <(B-A) x (C-A), n> */
    l[0] = rf_vec3_dot(rf_vec3_cross(rf_vec3_sub(p2, q), rf_vec3_sub(p3, q)), n) / whole;
    l[1] = rf_vec3_dot(rf_vec3_cross(rf_vec3_sub(q, p1), rf_vec3_sub(p3, p1)), n) / whole;
    l[2] = rf_vec3_dot(rf_vec3_cross(rf_vec3_sub(p2, p1), rf_vec3_sub(q, p1)), n) / whole;
    return RF_OK;
}
