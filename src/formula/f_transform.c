/* `refray formula` entries of §4 (transformations and homogeneous coordinates). */
#include "refray/formula.h"
#include "formula_internal.h"
#include "refray/mat.h"
#include "refray/numeric.h"
#include "refray/transform.h"

#include <math.h>
#include <string.h>

/* Applies the n x n matrix m to the optional input "point". A point of dimension n is
 * multiplied directly; one of dimension n-1 is taken as homogeneous (w = 1) and
 * dehomogenised. */
static int apply_to_point(RfFormulaCall *c, const double *m, int n)
{
    double p[4] = {0, 0, 0, 0}, y[4];
    int d;
    if (!rf_in_has(c, "point"))
        return 0;
    if (rf_in_vec(c, "point", RF_DIM(n - 1) | RF_DIM(n), p, &d))
        return 1;
    if (d == n) {
        rf_matn_mul_vec(n, m, p, y);
        rf_out_vec(c, "point", y, n);
    } else if (d == n - 1) {
        p[d] = 1.0;
        rf_matn_mul_vec(n, m, p, y);
        if (y[d] == 0.0)
            return rf_call_error(c, "the point maps to infinity (w = 0)");
        for (int i = 0; i < d; i++)
            y[i] /= y[d];
        rf_out_vec(c, "point", y, d);
    }
    return 0;
}

static int out_matrix_and_point(RfFormulaCall *c, const double *m, int n)
{
    rf_out_mat(c, "matrix", m, n);
    return apply_to_point(c, m, n);
}

static int read_axis(RfFormulaCall *c, RfAxis *axis)
{
    int i;
    if (rf_in_choice(c, "axis", &i))
        return 1;
    *axis = (RfAxis)i;
    return 0;
}

static int f_scale2(RfFormulaCall *c)
{
    double sx, sy;
    if (rf_in_num(c, "sx", &sx) || rf_in_num(c, "sy", &sy))
        return 1;
    RfMat2 m = rf_mat2_scale(sx, sy);
    return out_matrix_and_point(c, &m.m[0][0], 2);
}

static int f_shear2(RfFormulaCall *c)
{
    RfAxis axis;
    double s;
    if (read_axis(c, &axis) || rf_in_num(c, "s", &s))
        return 1;
    RfMat2 m = rf_mat2_shear(axis, s);
    return out_matrix_and_point(c, &m.m[0][0], 2);
}

static int f_reflect2(RfFormulaCall *c)
{
    RfAxis axis;
    if (read_axis(c, &axis))
        return 1;
    RfMat2 m = rf_mat2_reflect(axis);
    return out_matrix_and_point(c, &m.m[0][0], 2);
}

static int f_rotate2(RfFormulaCall *c)
{
    double phi;
    if (rf_in_angle(c, "phi_deg", &phi))
        return 1;
    RfMat2 m = rf_mat2_rotate(phi);
    return out_matrix_and_point(c, &m.m[0][0], 2);
}

static int f_rotate3(RfFormulaCall *c)
{
    RfAxis axis;
    double phi;
    if (read_axis(c, &axis) || rf_in_angle(c, "phi_deg", &phi))
        return 1;
    RfMat3 m = rf_mat3_rotate(axis, phi);
    return out_matrix_and_point(c, &m.m[0][0], 3);
}

static int f_euler(RfFormulaCall *c)
{
    double psi, theta, phi;
    int order;
    if (rf_in_angle(c, "psi_deg", &psi) || rf_in_angle(c, "theta_deg", &theta) ||
        rf_in_angle(c, "phi_deg", &phi) || rf_in_choice(c, "order", &order))
        return 1;
    RfMat3 m = rf_mat3_euler((RfEulerOrder)order, psi, theta, phi);
    return out_matrix_and_point(c, &m.m[0][0], 3);
}

static int f_rotation_basis(RfFormulaCall *c)
{
    RfVec3 u, v, w;
    if (rf_in_vec3(c, "u", &u) || rf_in_vec3(c, "v", &v) || rf_in_vec3(c, "w", &w))
        return 1;
    RfMat3 m = rf_mat3_rotation_basis(u, v, w);
    rf_out_mat(c, "matrix", &m.m[0][0], 3);
    rf_out_bool(c, "orthonormal", rf_matn_is_orthogonal(3, &m.m[0][0]) && rf_mat3_det(m) > 0.0);
    return 0;
}

static int f_axis_angle(RfFormulaCall *c)
{
    RfVec3 d, e, f;
    RfMat3 r;
    double phi;
    if (rf_in_vec3(c, "d", &d) || rf_in_angle(c, "phi_deg", &phi))
        return 1;
    if (rf_mat3_axis_angle(d, phi, &r, &e, &f) != RF_OK)
        return rf_call_error(c, "the axis d must not be the zero vector");
    rf_out_mat(c, "matrix", &r.m[0][0], 3);
    rf_out_vec3(c, "e", e);
    rf_out_vec3(c, "f", f);
    return apply_to_point(c, &r.m[0][0], 3);
}

/* §4.4: the special inverses, each checked to apply, and the general numerical one. */
static int f_inverse(RfFormulaCall *c)
{
    double m[16], inv[16];
    int n = 0, kind;
    if (rf_in_mat(c, "matrix", 0, m, &n) ||
        rf_in_choice(c, "kind", &kind))
        return 1;
    int homogeneous = 1; /* the last row is (0,...,0,1) */
    for (int k = 0; k < n; k++)
        homogeneous &= m[(n - 1) * n + k] == (k == n - 1 ? 1.0 : 0.0);
    switch (kind) {
    case 0:
        if (rf_matn_inverse(n, m, inv) != RF_OK)
            return rf_call_error(c, "the matrix is singular (det = %.17g)", rf_matn_det(n, m));
        break;
    case 1: /* S^-1(x,y,z) = S(1/x,1/y,1/z) */
        for (int r = 0; r < n; r++)
            for (int k = 0; k < n; k++) {
                if (r != k && m[r * n + k] != 0.0)
                    return rf_call_error(c, "kind=scale needs a diagonal matrix");
                if (r == k && m[r * n + k] == 0.0)
                    return rf_call_error(c, "the matrix is singular: scale factor %d is 0", r + 1);
                inv[r * n + k] = r == k ? 1.0 / m[r * n + k] : 0.0;
            }
        break;
    case 2: { /* R^-1 = R^T, for a rotation (or its homogeneous form without translation) */
        int lin = homogeneous && n == 4 ? 3 : n;
        double a[9];
        for (int r = 0; r < lin; r++)
            for (int k = 0; k < lin; k++)
                a[r * lin + k] = m[r * n + k];
        int pure = 1;
        for (int r = 0; r < n; r++)
            for (int k = 0; k < n; k++)
                if ((r >= lin || k >= lin) && m[r * n + k] != (r == k ? 1.0 : 0.0))
                    pure = 0;
        if (!pure || !rf_matn_is_orthogonal(lin, a) || rf_matn_det(lin, a) < 0.0)
            return rf_call_error(c, "kind=rotation needs an orthogonal matrix with det +1");
        rf_matn_transpose(n, m, inv);
        break;
    }
    case 3: /* T^-1(x,y,z) = T(-x,-y,-z) */
        if (!homogeneous)
            return rf_call_error(c, "kind=translation needs a homogeneous matrix");
        for (int r = 0; r < n - 1; r++)
            for (int k = 0; k < n - 1; k++)
                if (m[r * n + k] != (r == k ? 1.0 : 0.0))
                    return rf_call_error(c, "kind=translation needs the identity as linear part");
        memcpy(inv, m, sizeof(double) * (size_t)(n * n));
        for (int r = 0; r < n - 1; r++)
            inv[r * n + n - 1] = -m[r * n + n - 1];
        break;
    }
    rf_out_mat(c, "inverse", inv, n);
    rf_out_bool(c, "singular", 0);
    rf_out_num(c, "det", rf_matn_det(n, m));
    return 0;
}

static int f_homogeneous(RfFormulaCall *c)
{
    double v[4] = {0, 0, 0, 0}, h[4], w;
    int n = 0, point = rf_in_has(c, "point"), dir = rf_in_has(c, "direction"), hom = rf_in_has(c, "h");
    if (point + dir + hom != 1)
        return rf_call_bad_input(c, "give exactly one of point, direction or h");
    if (hom) { /* dehomogenise a given homogeneous vector */
        if (rf_in_vec(c, "h", 0, h, &n))
            return 1;
        rf_out_vec(c, "h", h, n);
        rf_out_bool(c, "at_infinity", h[n - 1] == 0.0);
        if (h[n - 1] == 0.0) {
            rf_out_null(c, "dehomogenised");
        } else {
            for (int i = 0; i < n - 1; i++)
                v[i] = h[i] / h[n - 1];
            rf_out_vec(c, "dehomogenised", v, n - 1);
        }
        return 0;
    }
    if (rf_in_vec(c, point ? "point" : "direction", 0, v, &n) || rf_in_num(c, "w", &w))
        return 1;
    if (point && w == 0.0)
        return rf_call_error(c, "a point needs w != 0 (w = 0 is a direction)");
    /* a point: the representative (w x, w y, w) of its class; a direction: (x, y, 0) */
    for (int i = 0; i < n; i++)
        h[i] = point ? v[i] * w : v[i];
    h[n] = point ? w : 0.0;
    rf_out_vec(c, "h", h, n + 1);
    rf_out_bool(c, "at_infinity", !point);
    if (point)
        rf_out_vec(c, "dehomogenised", v, n);
    else
        rf_out_null(c, "dehomogenised");
    return 0;
}

static int f_affine(RfFormulaCall *c)
{
    double a[16], b[4], x[4], y[4], h[25];
    int n = 0, nb, nx;
    if (rf_in_mat(c, "a", 0, a, &n) || rf_in_vec(c, "b", RF_DIM(n), b, &nb) ||
        rf_in_vec(c, "x", RF_DIM(n), x, &nx))
        return 1;
    rf_matn_mul_vec(n, a, x, y);
    for (int i = 0; i < n; i++)
        y[i] += b[i];
    rf_matn_affine(n, a, b, h);
    rf_out_vec(c, "y", y, n);
    rf_out_mat(c, "matrix_h", h, n + 1);
    return 0;
}

static int f_rotate_about_point(RfFormulaCall *c)
{
    double cp[4], phi;
    int n = 0;
    if (rf_in_vec(c, "c", 0, cp, &n) || rf_in_angle(c, "phi_deg", &phi))
        return 1;
    /* T(c) R(phi) T(-c) (Example 4.1) */
    RfMat2 r = rf_mat2_rotate(phi);
    double t[9], rh[9], tn[9], m[9], zero[2] = {0, 0}, neg[2] = {-cp[0], -cp[1]};
    double id[4] = {1, 0, 0, 1};
    rf_matn_affine(2, id, cp, t);
    rf_matn_affine(2, &r.m[0][0], zero, rh);
    rf_matn_affine(2, id, neg, tn);
    rf_matn_mul(3, t, rh, m);
    rf_matn_mul(3, m, tn, m);
    return out_matrix_and_point(c, m, 3);
}

static int f_scale3h(RfFormulaCall *c)
{
    double sx, sy, sz;
    if (rf_in_num(c, "sx", &sx) || rf_in_num(c, "sy", &sy) || rf_in_num(c, "sz", &sz))
        return 1;
    RfMat4 m = rf_mat4_scale(sx, sy, sz);
    return out_matrix_and_point(c, &m.m[0][0], 4);
}

static int f_shear3z(RfFormulaCall *c)
{
    double dx, dy;
    if (rf_in_num(c, "dx", &dx) || rf_in_num(c, "dy", &dy))
        return 1;
    RfMat4 m = rf_mat4_shear_z(dx, dy);
    return out_matrix_and_point(c, &m.m[0][0], 4);
}

static int f_rotate3h(RfFormulaCall *c)
{
    RfAxis axis;
    double phi;
    if (read_axis(c, &axis) || rf_in_angle(c, "phi_deg", &phi))
        return 1;
    RfMat4 m = rf_mat4_rotate(axis, phi);
    return out_matrix_and_point(c, &m.m[0][0], 4);
}

static int f_translate3h(RfFormulaCall *c)
{
    double dx, dy, dz;
    if (rf_in_num(c, "dx", &dx) || rf_in_num(c, "dy", &dy) || rf_in_num(c, "dz", &dz))
        return 1;
    RfMat4 m = rf_mat4_translate(rf_vec3(dx, dy, dz));
    return out_matrix_and_point(c, &m.m[0][0], 4);
}

/* §4.7.1: local -> world is T(e) B (B has the basis vectors as columns); world -> local is
 * B^-1 T(-e). The script writes B^T for the second, which equals B^-1 only for an orthonormal
 * basis; B^-1 is right for every basis. */
static int f_change_of_basis(RfFormulaCall *c)
{
    double e[4], basis[16], p[4] = {0}, bm[16], bh[25], t[25], m[25], neg[4];
    double id[16];
    int n = 0, count, dim, np, dir;
    if (rf_in_vec(c, "origin", 0, e, &n) || rf_in_vecs(c, "basis", RF_DIM(n), 4, basis, &count, &dim) ||
        rf_in_vec(c, "point", RF_DIM(n), p, &np) || rf_in_choice(c, "direction", &dir))
        return 1;
    if (count != n)
        return rf_call_bad_input(c, "basis: a basis of R^%d needs %d vectors, not %d", n, n, count);
    for (int r = 0; r < n; r++)
        for (int k = 0; k < n; k++)
            bm[r * n + k] = basis[k * n + r]; /* columns are the basis vectors */
    rf_matn_identity(n, id);
    if (dir == 0) {
        double zero[3] = {0, 0, 0};
        rf_matn_affine(n, id, e, t);
        rf_matn_affine(n, bm, zero, bh);
        rf_matn_mul(n + 1, t, bh, m);
    } else {
        double binv[9], zero[3] = {0, 0, 0};
        if (rf_matn_inverse(n, bm, binv) != RF_OK)
            return rf_call_error(c, "the basis vectors are linearly dependent");
        for (int i = 0; i < n; i++)
            neg[i] = -e[i];
        rf_matn_affine(n, binv, zero, bh);
        rf_matn_affine(n, id, neg, t);
        rf_matn_mul(n + 1, bh, t, m);
    }
    p[n] = 1.0;
    rf_out_mat(c, "matrix", m, n + 1);
    rf_matn_mul_vec(n + 1, m, p, p);
    rf_out_vec(c, "point", p, n);
    return 0;
}

int rf_formula_camera(RfFormulaCall *c, int with_view)
{
    RfVec3 eye, target, up;
    RfCameraBasis b;
    if (rf_in_vec3(c, "eye", &eye) || rf_in_vec3(c, "target", &target) || rf_in_vec3(c, "up", &up))
        return 1;
    if (rf_camera_basis(eye, target, up, &b) != RF_OK)
        return rf_call_error(c, "eye equals target, or up is zero or parallel to the view direction");
    rf_out_vec3(c, "u", b.u);
    rf_out_vec3(c, "v", b.v);
    rf_out_vec3(c, "w", b.w);
    if (with_view) {
        RfMat4 v = rf_camera_view(eye, b);
        rf_out_mat(c, "view", &v.m[0][0], 4);
    }
    return 0;
}

static int f_camera_transform(RfFormulaCall *c) { return rf_formula_camera(c, 1); }

/* transform-point (w = 1) and transform-direction (w = 0): an x of dimension n - 1 is made
 * homogeneous; an x of dimension n is multiplied as it is (a linear map). */
static int transform_vector(RfFormulaCall *c, double w)
{
    double m[16], x[4] = {0, 0, 0, 0}, y[4];
    int n = 0, d;
    if (rf_in_mat(c, "matrix", 0, m, &n) || rf_in_vec(c, "x", RF_DIM(n - 1) | RF_DIM(n), x, &d))
        return 1;
    if (d == n) {
        rf_matn_mul_vec(n, m, x, y);
        rf_out_vec(c, "y", y, n);
        return 0;
    }
    x[d] = w;
    rf_matn_mul_vec(n, m, x, y);
    if (w != 0.0) {
        if (y[d] == 0.0)
            return rf_call_error(c, "the point maps to infinity (w' = 0)");
        for (int i = 0; i < d; i++)
            y[i] /= y[d];
    }
    rf_out_vec(c, "y", y, d);
    rf_out_num(c, "w", y[d]);
    return 0;
}

static int f_transform_point(RfFormulaCall *c) { return transform_vector(c, 1.0); }
static int f_transform_direction(RfFormulaCall *c) { return transform_vector(c, 0.0); }

static int f_transform_normal(RfFormulaCall *c)
{
    double m[16];
    int n = 0;
    RfVec3 nrm, out;
    if (rf_in_mat(c, "matrix", 0, m, &n) || rf_in_vec3(c, "n", &nrm))
        return 1;
    RfMat3 a;
    for (int r = 0; r < 3; r++)
        for (int k = 0; k < 3; k++)
            a.m[r][k] = m[r * n + k];
    if (n == 4 && (m[12] != 0.0 || m[13] != 0.0 || m[14] != 0.0 || m[15] != 1.0))
        return rf_call_error(c, "a projective 4x4 matrix (last row not 0,0,0,1) also moves the "
                                "tangent plane's offset; give an affine matrix");
    RfStatus st = rf_transform_normal(a, nrm, &out);
    if (st == RF_ERR_DEGENERATE)
        return rf_call_error(c, "the normal n must not be the zero vector");
    if (st != RF_OK)
        return rf_call_error(c, "the matrix is singular: normals cannot be transformed");
    double lambda;
    int similarity = rf_matn_is_similarity(3, &a.m[0][0], &lambda);
    rf_out_vec3(c, "n", out);
    rf_out_bool(c, "similarity", similarity);
    rf_out_bool(c, "orthogonal", rf_matn_is_orthogonal(3, &a.m[0][0]));
    /* the shortcut n' = M n of §4.9, which is right only for similarity maps */
    rf_out_vec3(c, "n_shortcut", rf_vec3_normalize(rf_mat3_mul_vec(a, nrm)));
    return 0;
}

#define POINT(kind, how) "; point:" kind "? a point to transform (optional): " how
#define POINT2 POINT("vec2", "2 numbers")
#define POINT3 POINT("vec3", "3 numbers")
#define POINT_H2 POINT("vec23", "x,y (homogeneous, w = 1, dehomogenised after) or x,y,w")
#define POINT_H3 POINT("vec34", "x,y,z (homogeneous, w = 1, dehomogenised after) or x,y,z,w")
#define MAT_OUT "matrix:mat the matrix; point:vec the transformed point (only when point is given)"
#define AXIS_IN "axis:x|y|z the axis of rotation"
#define PHI_IN "phi_deg:num the rotation angle, counter-clockwise looking down the axis (degrees)"

const RfFormula rf_formulas_transform[] = {
    {"scale2", "4.2.1", "2D scale [[sx,0],[0,sy]], optionally applied to a point",
     "sx:num the factor along x; sy:num the factor along y" POINT2, MAT_OUT, NULL, f_scale2,
     "sx=2 sy=3 point=1,1"},
    {"shear2", "4.2.2", "2D shear along axis x ([[1,s],[0,1]]) or y ([[1,0],[s,1]])",
     "axis:x|y x: x += s y, y: y += s x; s:num the shear factor" POINT2, MAT_OUT, NULL, f_shear2,
     "axis=x s=0.5 point=1,2"},
    {"reflect2", "4.2.3", "2D reflection: axis x negates x ([[-1,0],[0,1]]), axis y negates y",
     "axis:x|y the coordinate that is negated" POINT2, MAT_OUT, NULL, f_reflect2, "axis=x point=1,2"},
    {"rotate2", "4.2.4", "2D rotation [[cos,-sin],[sin,cos]] by phi",
     "phi_deg:num the angle, counter-clockwise (degrees)" POINT2, MAT_OUT, NULL, f_rotate2,
     "phi_deg=90 point=1,0"},
    {"rotate3", "4.3.1", "R_x, R_y or R_z (axis=x|y|z) by phi", AXIS_IN "; " PHI_IN POINT3, MAT_OUT, NULL,
     f_rotate3, "axis=z phi_deg=90 point=1,0,0"},
    {"euler", "4.3.1", "Euler rotation; order names the factors left to right: zyx = R_z(phi) "
     "R_y(theta) R_x(psi) (the script's matrix), xyz = R_x(psi) R_y(theta) R_z(phi), zxz = R_z(phi) "
     "R_x(theta) R_z(psi), zyz = R_z(phi) R_y(theta) R_z(psi)",
     "psi_deg:num the first angle psi (degrees); theta_deg:num the second angle theta (degrees); "
     "phi_deg:num the third angle phi (degrees); order:zyx|xyz|zxz|zyz=zyx the axes of the factors, "
     "left to right" POINT3, MAT_OUT, NULL, f_euler, "psi_deg=90 theta_deg=0 phi_deg=90"},
    {"rotation-basis", "4.3.1", "R_uvw with rows u, v, w: maps u, v, w onto the axes; R_uvw^T maps back",
     "u:vec3 the first basis vector (row 1); v:vec3 the second (row 2); w:vec3 the third (row 3)",
     "matrix:mat R_uvw; orthonormal:bool u, v, w are orthonormal and right-handed (a rotation)",
     "the script's last entry w_u is w_z", f_rotation_basis, "u=0,1,0 v=0,0,1 w=1,0,0"},
    {"axis-angle", "4.3.1", "rotation about axis d by phi: e = (0,-d_z,d_y)/sqrt(d_y^2+d_z^2), f = d x e, "
     "M = rows(d,e,f), R = M^-1 R_x(phi) M; d is normalised; for d_y = d_z = 0 the helper axis is y "
     "(e = normalise(y x d))",
     "d:vec3 the axis (not zero, normalised here); " PHI_IN POINT3,
     "matrix:mat the rotation R; e:vec the helper axis e; f:vec the helper axis f = d x e; "
     "point:vec the rotated point (only when point is given)",
     "the script writes e = (0, -d_z, dy) without the normalisation's condition: e is undefined for "
     "d_y = d_z = 0; refray then uses the y axis as helper", f_axis_angle, "d=1,1,1 phi_deg=120 point=1,0,0"},
    {"inverse", "4.4", "inverse matrix: kind=scale (reciprocal factors), rotation (transpose), "
     "translation (negated offset), general (Gauss-Jordan with partial pivoting; singular is an error)",
     "matrix:mat234 the matrix M; kind:general|scale|rotation|translation=general which inverse: "
     "Gauss-Jordan, 1/factors of a diagonal M, the transpose of a rotation, or the negated offset of a translation",
     "inverse:mat M^-1; singular:bool always false (a singular matrix is an error); det:num det M", NULL,
     f_inverse, "matrix=1,2;3,4"},
    {"homogeneous", "4.5.1", "homogeneous coordinates: a point (x,y[,z]) -> (w x, w y[, w z], w), a "
     "direction -> (x,y[,z],0); or give h to dehomogenise",
     "point:vec23? a point (give one of point, direction, h); direction:vec23? a direction; "
     "h:vec234? a homogeneous vector to dehomogenise; w:num=1 the weight w of the point's representative (not 0)",
     "h:vec the homogeneous vector; dehomogenised:vec the Cartesian point (null at infinity); "
     "at_infinity:bool the last component is 0 (a direction)", NULL, f_homogeneous, "point=1,2 w=2"},
    {"affine", "4.5.2", "affine map y = A x + b and its homogeneous matrix [[A, b], [0, 1]]",
     "a:mat23 the linear part A (2x2 or 3x3); b:vec23 the offset b, as long as A is wide; "
     "x:vec23 the point x, as long as b",
     "y:vec A x + b; matrix_h:mat the homogeneous matrix [[A, b], [0, 1]]",
     "the script's first row reads a11 x1 + a21 x2 + b1 and \"b1 != 0 or 2 != 0\"; correct: "
     "a11 x1 + a12 x2 + b1, and b2", f_affine, "a=1,2;3,4 b=5,6 x=1,1"},
    {"rotate-about-point", "4.5.2", "2D rotation by phi about the point c: T(c) R(phi) T(-c) (Example 4.1)",
     "c:vec2 the centre of rotation; phi_deg:num the angle, counter-clockwise (degrees)" POINT_H2,
     MAT_OUT " (3x3, homogeneous)", NULL, f_rotate_about_point, "c=1,1 phi_deg=90 point=2,1"},
    {"scale3h", "4.6", "homogeneous 3D scale", "sx:num the factor along x; sy:num along y; sz:num along z" POINT_H3,
     MAT_OUT, NULL, f_scale3h, "sx=2 sy=3 sz=4 point=1,1,1"},
    {"shear3z", "4.6", "homogeneous 3D shear along z: x += dx z, y += dy z",
     "dx:num the shear of x per unit z; dy:num the shear of y per unit z" POINT_H3, MAT_OUT, NULL,
     f_shear3z, "dx=0.5 dy=0 point=0,0,2"},
    {"rotate3h", "4.6", "homogeneous 3D rotation about axis x, y or z", AXIS_IN "; " PHI_IN POINT_H3,
     MAT_OUT, NULL, f_rotate3h, "axis=x phi_deg=90 point=0,1,0"},
    {"translate3h", "4.6", "homogeneous 3D translation",
     "dx:num the offset along x; dy:num along y; dz:num along z" POINT_H3, MAT_OUT, NULL, f_translate3h,
     "dx=1 dy=2 dz=3 point=1,1,1"},
    {"change-of-basis", "4.7.1", "to-world: p = T(e) B p_local (B's columns the basis vectors); "
     "to-local: p_local = B^-1 T(-e) p (B^-1 = B^T for an orthonormal basis, as the script writes)",
     "origin:vec23 the local frame's origin e (2D or 3D); basis:vecs23 the local basis vectors, n of "
     "them, each as long as origin; point:vec23 the point to convert, as long as origin; "
     "direction:to-world|to-local=to-world local -> world, or world -> local",
     "matrix:mat the homogeneous matrix; point:vec the converted point", 
     "the script writes (p_u, p_u, 1); correct: (p_u, p_v, 1)", f_change_of_basis,
     "origin=1,1 basis=0,1;-1,0 point=1,0"},
    {"camera-transform", "4.7.2", "camera basis w = (e-target)/|e-target|, u = normalise(up x w), v = w x u "
     "and the world-to-camera matrix R_uvw T(-e)",
     "eye:vec3 the eye position e; target:vec3 the point looked at; up:vec3 the up direction "
     "(not parallel to the view direction)",
     "u:vec the camera's right axis; v:vec its up axis; w:vec its backward axis; "
     "view:mat the world-to-camera matrix R_uvw T(-e) (4x4)",
     "the script's u = up x w must be normalised when up is not perpendicular to w", f_camera_transform,
     "eye=0,0,5 target=0,0,0 up=0,1,0"},
    {"transform-point", "4.5", "y = M (x, 1) dehomogenised (x of dimension n-1 for an n x n M), or y = M x "
     "(x of dimension n)",
     "matrix:mat234 the matrix M (n x n); x:vec234 the point: n-1 numbers (homogeneous, w = 1) or n",
     "y:vec the transformed point; w:num the w before dehomogenising (only for n-1 numbers)", NULL,
     f_transform_point, "matrix=1,0,0,1;0,1,0,2;0,0,1,3;0,0,0,1 x=1,1,1"},
    {"transform-direction", "4.5", "y = M (x, 0): translations do not move directions",
     "matrix:mat234 the matrix M (n x n); x:vec234 the direction: n-1 numbers (homogeneous, w = 0) or n",
     "y:vec the transformed direction; w:num the w of M (x, 0) (only for n-1 numbers)", NULL,
     f_transform_direction, "matrix=1,0,0,1;0,1,0,2;0,0,1,3;0,0,0,1 x=1,1,1"},
    {"transform-normal", "4.9", "n' = normalise((M^-1)^T n) for the linear part of M; also the shortcut "
     "normalise(M n), right only for similarity maps (rotation x uniform scale)",
     "matrix:mat34 the matrix M: 3x3 linear, or 4x4 affine (last row 0,0,0,1); n:vec3 the normal (not zero)",
     "n:vec the unit transformed normal; similarity:bool M's linear part is rotation x uniform scale; "
     "orthogonal:bool M's linear part is orthogonal; n_shortcut:vec normalise(M n), right only for similarity maps",
     "the script says (M^-1)^T = lambda M for all similarity maps including \"scalings\": that holds "
     "only for rotation x uniform scale (lambda = 1/s^2); a non-uniform scale needs the inverse transpose",
     f_transform_normal, "matrix=2,0,0;0,1,0;0,0,1 n=1,1,0"},
    {NULL, NULL, NULL, NULL, NULL, NULL, NULL, NULL},
};
