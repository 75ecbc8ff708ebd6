/* Square matrices: one generic implementation per algorithm, fixed-size wrappers around it. */
#include "refray/mat.h"
#include "refray/numeric.h"

#include <math.h>
#include <string.h>

#define AT(a, n, r, c) ((a)[(r) * (n) + (c)])

void rf_matn_identity(int n, double *out)
{
    for (int r = 0; r < n; r++)
        for (int c = 0; c < n; c++)
            AT(out, n, r, c) = r == c ? 1.0 : 0.0;
}

void rf_matn_mul(int n, const double *a, const double *b, double *out)
{
    double t[RF_MATN_MAX * RF_MATN_MAX];
    for (int r = 0; r < n; r++)
        for (int c = 0; c < n; c++) {
            double s = 0.0;
            for (int k = 0; k < n; k++)
                s += AT(a, n, r, k) * AT(b, n, k, c);
            AT(t, n, r, c) = s;
        }
    memcpy(out, t, sizeof(double) * (size_t)(n * n));
}

void rf_matn_transpose(int n, const double *a, double *out)
{
    double t[RF_MATN_MAX * RF_MATN_MAX];
    for (int r = 0; r < n; r++)
        for (int c = 0; c < n; c++)
            AT(t, n, c, r) = AT(a, n, r, c);
    memcpy(out, t, sizeof(double) * (size_t)(n * n));
}

void rf_matn_mul_vec(int n, const double *a, const double *x, double *out)
{
    double t[RF_MATN_MAX];
    for (int r = 0; r < n; r++) {
        double s = 0.0;
        for (int k = 0; k < n; k++)
            s += AT(a, n, r, k) * x[k];
        t[r] = s;
    }
    memcpy(out, t, sizeof(double) * (size_t)n);
}

static double max_abs(int n, const double *a)
{
    double m = 0.0;
    for (int i = 0; i < n * n; i++)
        m = fmax(m, fabs(a[i]));
    return m;
}

/* Gauss-Jordan elimination with partial pivoting on [A | B], B with nb columns.
 * On success B holds A^-1 B. Returns RF_ERR_SINGULAR when a pivot is under RF_SINGULAR_REL
 * times the largest entry of A, RF_ERR_DOMAIN when an entry is not finite. */
static RfStatus gauss_jordan(int n, const double *a_in, int nb, double *b)
{
    double a[RF_MATN_MAX * RF_MATN_MAX];
    double scale = max_abs(n, a_in);
    memcpy(a, a_in, sizeof(double) * (size_t)(n * n));
    for (int i = 0; i < n * n; i++)
        if (!isfinite(a[i]))
            return RF_ERR_DOMAIN;
    if (!(scale > 0.0))
        return RF_ERR_SINGULAR;
    for (int col = 0; col < n; col++) {
        int piv = col;
        for (int r = col + 1; r < n; r++)
            if (fabs(AT(a, n, r, col)) > fabs(AT(a, n, piv, col)))
                piv = r;
        if (fabs(AT(a, n, piv, col)) <= RF_SINGULAR_REL * scale)
            return RF_ERR_SINGULAR;
        if (piv != col) {
            for (int c = 0; c < n; c++) {
                double t = AT(a, n, col, c); AT(a, n, col, c) = AT(a, n, piv, c); AT(a, n, piv, c) = t;
            }
            for (int c = 0; c < nb; c++) {
                double t = AT(b, nb, col, c); AT(b, nb, col, c) = AT(b, nb, piv, c); AT(b, nb, piv, c) = t;
            }
        }
        double p = AT(a, n, col, col);
        for (int r = 0; r < n; r++) {
            if (r == col)
                continue;
            double f = AT(a, n, r, col) / p;
            if (f == 0.0)
                continue;
            for (int c = col; c < n; c++)
                AT(a, n, r, c) -= f * AT(a, n, col, c);
            for (int c = 0; c < nb; c++)
                AT(b, nb, r, c) -= f * AT(b, nb, col, c);
        }
    }
    for (int r = 0; r < n; r++) {
        double p = AT(a, n, r, r);
        for (int c = 0; c < nb; c++)
            AT(b, nb, r, c) /= p;
    }
    return RF_OK;
}

/* Determinant as the product of the pivots of forward elimination (partial pivoting, no cut-off:
 * an exactly singular matrix gives exactly 0). */
double rf_matn_det(int n, const double *a)
{
    double t[RF_MATN_MAX * RF_MATN_MAX];
    double d = 1.0;
    memcpy(t, a, sizeof(double) * (size_t)(n * n));
    for (int col = 0; col < n; col++) {
        int piv = col;
        for (int r = col + 1; r < n; r++)
            if (fabs(AT(t, n, r, col)) > fabs(AT(t, n, piv, col)))
                piv = r;
        if (AT(t, n, piv, col) == 0.0)
            return 0.0;
        if (piv != col) {
            d = -d;
            for (int c = 0; c < n; c++) {
                double s = AT(t, n, col, c); AT(t, n, col, c) = AT(t, n, piv, c); AT(t, n, piv, c) = s;
            }
        }
        d *= AT(t, n, col, col);
        for (int r = col + 1; r < n; r++) {
            double f = AT(t, n, r, col) / AT(t, n, col, col);
            for (int c = col; c < n; c++)
                AT(t, n, r, c) -= f * AT(t, n, col, c);
        }
    }
    return d;
}

RfStatus rf_matn_inverse(int n, const double *a, double *out)
{
    double b[RF_MATN_MAX * RF_MATN_MAX];
    rf_matn_identity(n, b);
    RfStatus st = gauss_jordan(n, a, n, b);
    if (st == RF_OK)
        memcpy(out, b, sizeof(double) * (size_t)(n * n));
    return st;
}

RfStatus rf_matn_solve(int n, const double *a, const double *rhs, double *x)
{
    double b[RF_MATN_MAX];
    memcpy(b, rhs, sizeof(double) * (size_t)n);
    RfStatus st = gauss_jordan(n, a, 1, b);
    if (st == RF_OK)
        memcpy(x, b, sizeof(double) * (size_t)n);
    return st;
}

int rf_matn_is_similarity(int n, const double *a, double *lambda)
{
    double ata[RF_MATN_MAX * RF_MATN_MAX], at[RF_MATN_MAX * RF_MATN_MAX];
    double lam = 0.0;
    rf_matn_transpose(n, a, at);
    rf_matn_mul(n, at, a, ata);
    for (int i = 0; i < n; i++)
        lam += AT(ata, n, i, i);
    lam /= n;
    if (lambda)
        *lambda = lam;
    if (!(lam > 0.0) || !isfinite(lam))
        return 0;
    for (int r = 0; r < n; r++)
        for (int c = 0; c < n; c++)
            if (fabs(AT(ata, n, r, c) - (r == c ? lam : 0.0)) > RF_STRUCTURE_TOL * lam)
                return 0;
    return 1;
}

int rf_matn_is_orthogonal(int n, const double *a)
{
    double lam;
    return rf_matn_is_similarity(n, a, &lam) && fabs(lam - 1.0) <= RF_STRUCTURE_TOL;
}

void rf_matn_affine(int n, const double *a, const double *b, double *out)
{
    int m = n + 1;
    for (int r = 0; r < m; r++)
        for (int c = 0; c < m; c++) {
            double v;
            if (r == n)
                v = c == n ? 1.0 : 0.0;
            else if (c == n)
                v = b[r];
            else
                v = AT(a, n, r, c);
            AT(out, m, r, c) = v;
        }
}

/* ---- fixed sizes ---- */

RfMat2 rf_mat2_identity(void) { RfMat2 o; rf_matn_identity(2, &o.m[0][0]); return o; }
RfMat2 rf_mat2_mul(RfMat2 a, RfMat2 b) { RfMat2 o; rf_matn_mul(2, &a.m[0][0], &b.m[0][0], &o.m[0][0]); return o; }
RfVec2 rf_mat2_mul_vec(RfMat2 a, RfVec2 x)
{
    return rf_vec2(a.m[0][0] * x.x + a.m[0][1] * x.y, a.m[1][0] * x.x + a.m[1][1] * x.y);
}

RfMat3 rf_mat3_identity(void) { RfMat3 o; rf_matn_identity(3, &o.m[0][0]); return o; }
RfMat3 rf_mat3_rows(RfVec3 r0, RfVec3 r1, RfVec3 r2)
{
    RfMat3 o = {{{r0.x, r0.y, r0.z}, {r1.x, r1.y, r1.z}, {r2.x, r2.y, r2.z}}};
    return o;
}
RfMat3 rf_mat3_mul(RfMat3 a, RfMat3 b) { RfMat3 o; rf_matn_mul(3, &a.m[0][0], &b.m[0][0], &o.m[0][0]); return o; }
RfMat3 rf_mat3_transpose(RfMat3 a) { RfMat3 o; rf_matn_transpose(3, &a.m[0][0], &o.m[0][0]); return o; }
RfVec3 rf_mat3_mul_vec(RfMat3 a, RfVec3 x)
{
    double v[3] = {x.x, x.y, x.z};
    rf_matn_mul_vec(3, &a.m[0][0], v, v);
    return rf_vec3(v[0], v[1], v[2]);
}
double rf_mat3_det(RfMat3 a) { return rf_matn_det(3, &a.m[0][0]); }
RfStatus rf_mat3_inverse(RfMat3 a, RfMat3 *out) { return rf_matn_inverse(3, &a.m[0][0], &out->m[0][0]); }

RfMat4 rf_mat4_identity(void) { RfMat4 o; rf_matn_identity(4, &o.m[0][0]); return o; }
RfMat4 rf_mat4_mul(RfMat4 a, RfMat4 b) { RfMat4 o; rf_matn_mul(4, &a.m[0][0], &b.m[0][0], &o.m[0][0]); return o; }
RfMat4 rf_mat4_transpose(RfMat4 a) { RfMat4 o; rf_matn_transpose(4, &a.m[0][0], &o.m[0][0]); return o; }
RfVec4 rf_mat4_mul_vec(RfMat4 a, RfVec4 x)
{
    double v[4] = {x.x, x.y, x.z, x.w};
    rf_matn_mul_vec(4, &a.m[0][0], v, v);
    return rf_vec4(v[0], v[1], v[2], v[3]);
}
double rf_mat4_det(RfMat4 a) { return rf_matn_det(4, &a.m[0][0]); }
RfStatus rf_mat4_inverse(RfMat4 a, RfMat4 *out) { return rf_matn_inverse(4, &a.m[0][0], &out->m[0][0]); }

RfMat3 rf_mat4_linear(RfMat4 a)
{
    RfMat3 o;
    for (int r = 0; r < 3; r++)
        for (int c = 0; c < 3; c++)
            o.m[r][c] = a.m[r][c];
    return o;
}

RfMat4 rf_mat4_affine(RfMat3 a, RfVec3 b)
{
    RfMat4 o;
    double t[3] = {b.x, b.y, b.z};
    rf_matn_affine(3, &a.m[0][0], t, &o.m[0][0]);
    return o;
}
