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
    if (rf_in_vec(c, "a", 0, a, &na) || rf_in_vec(c, "b", RF_DIM(na), b, &nb))
        return 1;
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
    double pa[4] = {0, 0, 0, 0}, pb[4] = {0, 0, 0, 0};
    int n;
    if (read_pair(c, pa, pb, &n))
        return 1;
    RfVec3 a = rf_vec3(pa[0], pa[1], pa[2]), b = rf_vec3(pb[0], pb[1], pb[2]); /* 2D: z = 0 */
    RfVec3 x = rf_vec3_cross(a, b);
    rf_out_vec3(c, "cross", x);
    double la = rf_vec3_length(a), lb = rf_vec3_length(b);
    if (la > 0.0 && lb > 0.0)
        rf_out_num(c, "sin_phi", rf_vec3_length(x) / (la * lb));
    else
        rf_out_null(c, "sin_phi");
    return 0;
}

/* Points of one length n (2D or 3D, as the spec says): the parser refuses any other. */
static int read_points(RfFormulaCall *c, const char *names, double pts[][4], int count, int *n)
{
    const char *name = names;
    for (int i = 0; i < count; i++, name += strlen(name) + 1)
        if (rf_in_vec(c, name, i ? RF_DIM(*n) : 0, pts[i], i ? NULL : n))
            return 1;
    return 0;
}

static int f_triangle_normal(RfFormulaCall *c)
{
    double pt[3][4] = {{0}};
    int n;
    RfTriangleNormal t;
    if (read_points(c, "a\0b\0c", pt, 3, &n))
        return 1;
    RfVec3 a = rf_vec3(pt[0][0], pt[0][1], pt[0][2]), b = rf_vec3(pt[1][0], pt[1][1], pt[1][2]),
           p = rf_vec3(pt[2][0], pt[2][1], pt[2][2]); /* 2D corners lie in the plane z = 0 */
    if (rf_triangle_normal(a, b, p, &t) != RF_OK)
        return rf_call_error(c, "the points are collinear: the triangle has no normal");
    rf_out_vec3(c, "n_raw", t.n_raw);
    rf_out_vec3(c, "n", t.n);
    rf_out_num(c, "area", t.area);
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
    if (rf_in_vecs(c, "basis", 0, 4, basis, &count, &dim) || rf_in_vec(c, "v", RF_DIM(dim), v, &nv))
        return 1;
    if (count != dim)
        return rf_call_bad_input(c, "a basis of R^%d needs %d vectors, not %d", dim, dim, count);
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

#define PT23 "(2D points lie in the plane z = 0)"

const RfFormula rf_formulas_geometry[] = {
    {"length", "2.1", "length of a vector, |a| = sqrt(sum a_i^2), and the unit vector a/|a|",
     "a:vec234 the vector",
     "length:num |a|; unit:vec a/|a| (null for the zero vector)",
     "the script writes |a| = sqrt(sum a_i); correct: sqrt(sum a_i^2)", f_length, "a=3,4"},
    {"dot", "2.1", "scalar product <a,b> = sum a_i b_i = |a||b| cos(phi), and the angle phi",
     "a:vec234 the first vector; b:vec234 the second vector, as long as a",
     "dot:num <a,b>; angle_deg:num the angle phi between a and b, 0..180 (null with a zero vector)",
     NULL, f_dot, "a=1,2,3 b=4,5,6"},
    {"cross", "2.1", "cross product a x b (2D vectors get z = 0); |a x b| = |a||b| sin(phi)",
     "a:vec23 the first vector " PT23 "; b:vec23 the second vector, as long as a",
     "cross:vec a x b (3 components); sin_phi:num |a x b|/(|a||b|) = sin(phi) (null with a zero vector)",
     "identities (iv), (v) lost their minus signs: a x (b x c) = b<a,c> - c<a,b>; "
     "<a x b, c x d> = <a,c><b,d> - <a,d><b,c>", f_cross, "a=1,0,0 b=1,1,0"},
    {"triangle-normal", "2.1", "n' = (b-a) x (c-a), n = n'/|n'|, oriented area |n'|/2",
     "a:vec23 the first corner " PT23 "; b:vec23 the second corner; c:vec23 the third corner",
     "n_raw:vec n' = (b-a) x (c-a), not normalised; n:vec the unit normal n'/|n'|; "
     "area:num the triangle's area |n'|/2", NULL, f_triangle_normal, "a=0,0,0 b=2,0,0 c=0,1,0"},
    {"line-point", "2.2", "g(t) = P + t (Q - P); on the ray for t >= 0, on the segment for t in [0,1]",
     "p:vec23 the point P (t = 0); q:vec23 the point Q (t = 1), as long as p; t:num the line parameter",
     "point:vec g(t); on_ray:bool t >= 0; on_segment:bool 0 <= t <= 1", NULL, f_line_point,
     "p=1,1 q=3,2 t=0.5"},
    {"plane-point", "2.2", "g(s,t) = P + s (Q - P) + t (R - P); in the parallelogram for s,t in [0,1]",
     "p:vec23 the point P " PT23 "; q:vec23 the point Q; r:vec23 the point R; "
     "s:num the parameter along Q - P; t:num the parameter along R - P",
     "point:vec g(s,t), as long as p; in_parallelogram:bool s and t in [0,1]", NULL, f_plane_point,
     "p=0,0,0 q=1,0,0 r=0,1,0 s=0.5 t=2"},
    {"basis-coordinates", "2.3", "coordinates c of v in a basis: v = sum c_i b_i (n vectors of R^n)",
     "basis:vecs234 the basis vectors b_1 ... b_n, n of them, each of n numbers; "
     "v:vec234 the vector, as long as the basis vectors",
     "coords:vec the coordinates c_i; orthogonal:bool the basis vectors are pairwise orthogonal; "
     "orthonormal:bool orthogonal and of length 1", NULL, f_basis_coordinates, "basis=1,1;1,-1 v=3,1"},
    {"barycentric", "2.4", "barycentric coordinates as ratios of oriented areas (measured along the "
     "triangle normal); inside iff all >= 0",
     "p1:vec23 the first corner " PT23 "; p2:vec23 the second corner; p3:vec23 the third corner; "
     "q:vec23 the point",
     "l1:num the weight of p1; l2:num the weight of p2; l3:num the weight of p3; "
     "inside:bool all weights >= 0 (q in the triangle, edges included)", NULL, f_barycentric,
     "p1=0,0 p2=4,0 p3=0,4 q=1,1"},
    {NULL, NULL, NULL, NULL, NULL, NULL, NULL, NULL},
};
