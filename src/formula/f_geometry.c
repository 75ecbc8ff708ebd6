/* `refray formula` entries of §2 (analytic geometry). */
#include "refray/formula.h"
#include "refray/geometry.h"

#include <math.h>
#include <string.h>

static double norm_n(const double *a, int n)
{
    double s = 0.0;
    for (int i = 0; i < n; i++)
        s += a[i] * a[i];
    return sqrt(s);
}

static int read_pair(RfFormulaCall *c, double *a, double *b, int *n)
{
    int na = 0, nb = 0;
    if (rf_in_vec(c, "a", 0, a, &na) || rf_in_vec(c, "b", 0, b, &nb))
        return 1;
    if (na != nb)
        return rf_call_error(c, "a and b must have the same dimension");
    *n = na;
    return 0;
}

static int f_length(RfFormulaCall *c)
{
    double a[4], unit[4];
    int n = 0;
    if (rf_in_vec(c, "a", 0, a, &n))
        return 1;
    double len = norm_n(a, n);
    rf_out_num(c, "length", len);
    if (len > 0.0) {
        for (int i = 0; i < n; i++)
            unit[i] = a[i] / len;
        rf_out_vec(c, "unit", unit, n);
    } else {
        rf_out_null(c, "unit");
    }
    return 0;
}

/* The angle between a and b by 2 atan2(|a^ - b^|, |a^ + b^|) (Kahan): accurate at every angle
 * and in every dimension, unlike acos of the normalised dot product. */
static double angle_n(const double *a, const double *b, int n)
{
    double la = norm_n(a, n), lb = norm_n(b, n), d[4], s[4];
    for (int i = 0; i < n; i++) {
        d[i] = a[i] / la - b[i] / lb;
        s[i] = a[i] / la + b[i] / lb;
    }
    return 2.0 * atan2(norm_n(d, n), norm_n(s, n));
}

static int f_dot(RfFormulaCall *c)
{
    double a[4], b[4], dot = 0.0;
    int n = 0;
    if (read_pair(c, a, b, &n))
        return 1;
    for (int i = 0; i < n; i++)
        dot += a[i] * b[i];
    rf_out_num(c, "dot", dot);
    if (norm_n(a, n) > 0.0 && norm_n(b, n) > 0.0)
        rf_out_num(c, "angle_deg", angle_n(a, b, n) * (180.0 / RF_PI));
    else
        rf_out_null(c, "angle_deg"); /* no angle with a zero vector */
    return 0;
}

static int f_cross(RfFormulaCall *c)
{
    RfVec3 a, b;
    if (rf_in_vec3(c, "a", &a) || rf_in_vec3(c, "b", &b))
        return 1;
    RfVec3 x = rf_vec3_cross(a, b);
    rf_out_vec3(c, "cross", x);
    double la = rf_vec3_length(a), lb = rf_vec3_length(b);
    if (la > 0.0 && lb > 0.0)
        rf_out_num(c, "sin_phi", rf_vec3_length(x) / (la * lb));
    else
        rf_out_null(c, "sin_phi");
    return 0;
}

static int f_triangle_normal(RfFormulaCall *c)
{
    RfVec3 a, b, p;
    RfTriangleNormal t;
    if (rf_in_vec3(c, "a", &a) || rf_in_vec3(c, "b", &b) || rf_in_vec3(c, "c", &p))
        return 1;
    if (rf_triangle_normal(a, b, p, &t) != RF_OK)
        return rf_call_error(c, "the points are collinear: the triangle has no normal");
    rf_out_vec3(c, "n_raw", t.n_raw);
    rf_out_vec3(c, "n", t.n);
    rf_out_num(c, "area", t.area);
    return 0;
}

/* p, q (and r) of one dimension n; the differences q-p, r-p */
static int read_points(RfFormulaCall *c, const char *names, double pts[][4], int count, int *n)
{
    const char *name = names;
    for (int i = 0; i < count; i++, name += strlen(name) + 1) {
        int d;
        if (rf_in_vec(c, name, 0, pts[i], &d))
            return 1;
        if (d == 4)
            return rf_call_error(c, "input '%s' must be a 2D or 3D point", name);
        if (i == 0)
            *n = d;
        else if (d != *n)
            return rf_call_error(c, "all points must have the same dimension");
    }
    return 0;
}

static int f_line_point(RfFormulaCall *c)
{
    double pt[2][4], t, out[4];
    int n = 0;
    if (read_points(c, "p\0q", pt, 2, &n) || rf_in_num(c, "t", &t))
        return 1;
    int same = 1;
    for (int i = 0; i < n; i++)
        same &= pt[0][i] == pt[1][i];
    if (same)
        return rf_call_error(c, "p and q must differ (§2.2: a line needs two points)");
    for (int i = 0; i < n; i++)
        out[i] = pt[0][i] + t * (pt[1][i] - pt[0][i]);
    rf_out_vec(c, "point", out, n);
    rf_out_bool(c, "on_ray", t >= 0.0);
    rf_out_bool(c, "on_segment", t >= 0.0 && t <= 1.0);
    return 0;
}

static int f_plane_point(RfFormulaCall *c)
{
    double pt[3][4] = {{0}}, s, t, out[4];
    int n = 0;
    if (read_points(c, "p\0q\0r", pt, 3, &n) || rf_in_num(c, "s", &s) || rf_in_num(c, "t", &t))
        return 1;
    RfVec3 p = rf_vec3(pt[0][0], pt[0][1], pt[0][2]), q = rf_vec3(pt[1][0], pt[1][1], pt[1][2]),
           r = rf_vec3(pt[2][0], pt[2][1], pt[2][2]);
    if (!(rf_vec3_length(rf_vec3_cross(rf_vec3_sub(q, p), rf_vec3_sub(r, p))) > 0.0))
        return rf_call_error(c, "p, q, r are collinear: they span no plane");
    RfVec3 x = rf_plane_point(p, q, r, s, t);
    out[0] = x.x, out[1] = x.y, out[2] = x.z;
    rf_out_vec(c, "point", out, n);
    rf_out_bool(c, "in_parallelogram", s >= 0.0 && s <= 1.0 && t >= 0.0 && t <= 1.0);
    return 0;
}

static int f_basis_coordinates(RfFormulaCall *c)
{
    double basis[4 * 4], v[4], coords[4];
    const double *rows[4];
    int count, dim, nv;
    if (rf_in_vecs(c, "basis", 0, 4, basis, &count, &dim) || rf_in_vec(c, "v", 0, v, &nv))
        return 1;
    if (count != dim)
        return rf_call_error(c, "a basis of R^%d needs %d vectors, not %d", dim, dim, count);
    if (nv != dim)
        return rf_call_error(c, "v must have the dimension of the basis vectors (%d)", dim);
    for (int i = 0; i < count; i++)
        rows[i] = basis + i * dim;
    if (rf_basis_coordinates(dim, rows, v, coords) != RF_OK)
        return rf_call_error(c, "the basis vectors are linearly dependent");
    rf_out_vec(c, "coords", coords, dim);
    rf_out_bool(c, "orthogonal", rf_basis_is_orthogonal(dim, rows, 0));
    rf_out_bool(c, "orthonormal", rf_basis_is_orthogonal(dim, rows, 1));
    return 0;
}

static int f_barycentric(RfFormulaCall *c)
{
    double pt[4][4] = {{0}}, l[3];
    int n = 0;
    if (read_points(c, "p1\0p2\0p3\0q", pt, 4, &n))
        return 1;
    RfVec3 v[4];
    for (int i = 0; i < 4; i++)
        v[i] = rf_vec3(pt[i][0], pt[i][1], pt[i][2]);
    if (rf_barycentric(v[0], v[1], v[2], v[3], l) != RF_OK)
        return rf_call_error(c, "the triangle has zero area");
    rf_out_num(c, "l1", l[0]);
    rf_out_num(c, "l2", l[1]);
    rf_out_num(c, "l3", l[2]);
    rf_out_bool(c, "inside", l[0] >= 0.0 && l[1] >= 0.0 && l[2] >= 0.0);
    return 0;
}

const RfFormula rf_formulas_geometry[] = {
    {"length", "2.1", "length of a vector, |a| = sqrt(sum a_i^2), and the unit vector a/|a|",
     "a:vec", "length:num; unit:vec (null for the zero vector)",
     "the script writes |a| = sqrt(sum a_i); correct: sqrt(sum a_i^2)", f_length},
    {"dot", "2.1", "scalar product <a,b> = sum a_i b_i = |a||b| cos(phi), and the angle phi",
     "a:vec; b:vec", "dot:num; angle_deg:num (null with a zero vector)", NULL, f_dot},
    {"cross", "2.1", "cross product a x b (2D vectors get z = 0); |a x b| = |a||b| sin(phi)",
     "a:vec; b:vec", "cross:vec; sin_phi:num (null with a zero vector)",
     "identities (iv), (v) lost their minus signs: a x (b x c) = b<a,c> - c<a,b>; "
     "<a x b, c x d> = <a,c><b,d> - <a,d><b,c>", f_cross},
    {"triangle-normal", "2.1", "n' = (b-a) x (c-a), n = n'/|n'|, oriented area |n'|/2",
     "a:vec; b:vec; c:vec", "n_raw:vec; n:vec; area:num", NULL, f_triangle_normal},
    {"line-point", "2.2", "g(t) = P + t (Q - P); on the ray for t >= 0, on the segment for t in [0,1]",
     "p:vec; q:vec; t:num", "point:vec; on_ray:bool; on_segment:bool", NULL, f_line_point},
    {"plane-point", "2.2", "g(s,t) = P + s (Q - P) + t (R - P); in the parallelogram for s,t in [0,1]",
     "p:vec; q:vec; r:vec; s:num; t:num", "point:vec; in_parallelogram:bool", NULL, f_plane_point},
    {"basis-coordinates", "2.3", "coordinates c of v in a basis: v = sum c_i b_i (n vectors of R^n)",
     "basis:vecs; v:vec", "coords:vec; orthogonal:bool; orthonormal:bool", NULL, f_basis_coordinates},
    {"barycentric", "2.4", "barycentric coordinates as ratios of oriented areas (measured along the "
     "triangle normal); inside iff all >= 0",
     "p1:vec; p2:vec; p3:vec; q:vec", "l1:num; l2:num; l3:num; inside:bool", NULL, f_barycentric},
    {NULL, NULL, NULL, NULL, NULL, NULL, NULL},
};
