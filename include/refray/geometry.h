/* refray: analytic geometry of §2 — triangles, parameter forms, bases, barycentric coordinates. */
#ifndef REFRAY_GEOMETRY_H
#define REFRAY_GEOMETRY_H

#include "refray/status.h"
#include "refray/vec.h"

#ifdef __cplusplus
extern "C" {
#endif

/* §2.1 Example 2.3: n' = (b-a) x (c-a), n = n'/|n'|, area = |n'|/2.
 * RF_ERR_DEGENERATE (n and area still written, n = 0) when the points are collinear. */
typedef struct { RfVec3 n_raw, n; double area; } RfTriangleNormal;
RfStatus rf_triangle_normal(RfVec3 a, RfVec3 b, RfVec3 c, RfTriangleNormal *out);

/* §2.2 g(t) = P + t (Q - P) and g(s,t) = P + s (Q - P) + t (R - P). */
RfVec3 rf_line_point(RfVec3 p, RfVec3 q, double t);
RfVec3 rf_plane_point(RfVec3 p, RfVec3 q, RfVec3 r, double s, double t);

/* §2.3: the coordinates c of v in the basis b[0..n-1] of R^n (v = sum c_i b_i), for n = 1..4.
 * Vectors are arrays of n doubles. RF_ERR_SINGULAR when the vectors are dependent. */
RfStatus rf_basis_coordinates(int n, const double *const *basis, const double *v, double *coords);
/* 1 when the n vectors of dimension n are pairwise orthogonal (resp. also of unit length),
 * within RF_STRUCTURE_TOL. */
int rf_basis_is_orthogonal(int n, const double *const *basis, int unit);

/* §2.4 Example 2.5: barycentric coordinates as ratios of oriented areas, the orientation
 * measured along the triangle's normal (so a point off the plane gets the coordinates of its
 * orthogonal projection). RF_ERR_DEGENERATE for a triangle of zero area. */
RfStatus rf_barycentric(RfVec3 p1, RfVec3 p2, RfVec3 p3, RfVec3 q, double l[3]);

/* Ear clipping (src/geom/triangulate.c) of a simple polygon: n - 2 triangles as vertex indices
 * out[3 k .. 3 k + 2], each in the polygon's orientation (three collinear corners may give a
 * triangle of zero area), so that together they cover the polygon exactly once; -1 when out of
 * memory. A polygon that is not simple still gets n - 2 triangles (the part without ears is
 * fanned). The 2D form takes the vertices (u[k], v[k]); the 3D form works in the coordinate
 * plane that drops the largest component of the polygon's Newell normal. */
int rf_triangulate_polygon_2d(const double *u, const double *v, int n, int *out);
int rf_triangulate_polygon(const RfVec3 *v, int n, int *out);

#ifdef __cplusplus
}
#endif

#endif
