/* refray: ray/primitive intersection (§3.5) for the tracer's hot path.
 *
 * Every rf_intersect_* takes the ray and the primitive by value and an interval [t_min, t_max)
 * (t in units of |dir|; t_min inclusive so that t_min = 0 accepts a hit at the origin, t_max
 * exclusive so that a shadow ray to a light at t_max does not hit the light's own point). It
 * returns 1 and fills *hit when the nearest hit in the interval exists, otherwise returns 0 and
 * leaves *hit untouched, so the tracer can keep its closest hit and pass t_max = closest.t.
 * Directions must be non-zero (rf_intersect_* never divide by |dir|; a zero direction gives no
 * hit). No tolerances: parallel means an exactly zero denominator; the self-intersection offset
 * is the caller's business (numeric.h). NaN inputs give no hit. */
#ifndef REFRAY_INTERSECT_H
#define REFRAY_INTERSECT_H

#include "refray/ray.h"
#include "refray/vec.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct {
    double t;
    double l[3];   /* triangles: barycentric coordinates of the hit for p1, p2, p3; else 0 */
    RfVec3 normal; /* unit geometric normal at the hit, see each primitive for its side */
} RfHit;

/* ---- §3.5.1 sphere ---- */

typedef struct { RfVec3 center; double radius; } RfSphere; /* radius > 0 */

typedef enum {
    RF_SPHERE_SCRIPT, /* the script's quadratic a t^2 + b t + c, D = b^2 - 4ac, midnight formula */
    RF_SPHERE_STABLE  /* same roots, precise: D = 4a (r - |v|)(r + |v|), v = f - (<f,d>/a) d
                       * (the perpendicular distance, Ray Tracing Gems ch. 7 / pbrt-v4); c by a
                       * compensated dot product; q = -(b + sign(b) sqrt(D))/2, roots q/a, c/q */
} RfSphereMethod;

/* The quadratic of §3.5.1 with f = e - center: a = <d,d>, b = 2<d,f>, c = <f,f> - r^2, its
 * discriminant and roots t1 <= t2 (D = 0: t1 = t2, the tangent). roots = 0 when D < 0. */
typedef struct { double a, b, c, disc, t1, t2; int roots; } RfSphereQuadratic;
RfSphereQuadratic rf_sphere_quadratic(RfRay ray, RfSphere s, RfSphereMethod method);

/* The smallest root in [t_min, t_max): t1 when the origin is outside, t2 when inside (t1 < 0
 * is behind); a tangent (D = 0) counts as a hit. normal = (p - center)/radius, outward; the
 * stable method computes p - center as v -+ (sqrt(D/4)/a) d, exact to a few ulps even where
 * t is large and e + t d - center would cancel. */
int rf_intersect_sphere(RfRay ray, RfSphere s, RfSphereMethod method, double t_min, double t_max,
                        RfHit *hit);
/* The stable method's two roots t[0] <= t[1] (1), or none (0), with what a root's normal needs:
 * rf_intersect_sphere is these two routines, and the tracer's own loops use them directly. */
typedef struct { double t[2]; RfVec3 v; double sq, a; } RfSphereRoots; /* sq = sqrt(D/4), a = <d,d> */
int rf_sphere_roots(const RfRay *ray, const RfSphere *s, RfSphereRoots *out);
/* Four rays side by side (a structure of arrays) for the tests that take one ray per SIMD lane. */
typedef struct { double ox[4], oy[4], oz[4], dx[4], dy[4], dz[4]; } RfRay4;
static inline void rf_ray4_set(RfRay4 *r4, int lane, const RfRay *ray)
{
    r4->ox[lane] = ray->origin.x, r4->oy[lane] = ray->origin.y, r4->oz[lane] = ray->origin.z;
    r4->dx[lane] = ray->dir.x, r4->dy[lane] = ray->dir.y, r4->dz[lane] = ray->dir.z;
}
static inline RfRay rf_ray4_get(const RfRay4 *r4, int lane)
{
    return rf_ray(rf_vec3(r4->ox[lane], r4->oy[lane], r4->oz[lane]), rf_vec3(r4->dx[lane], r4->dy[lane], r4->dz[lane]));
}
/* rf_sphere_roots for the four rays of r4: bit l of the result is its return for ray l, out[l]
 * the roots when the bit is set. In four double lanes of AVX2 where the build has them, each
 * lane the scalar routine's operations in its order (the same bits); the rare cases (a tangent,
 * a = 0, a NaN root) go to rf_sphere_roots. */
unsigned rf_sphere_roots4(const RfRay4 *r4, const RfSphere *s, RfSphereRoots out[4]);
/* The smallest root of t[0] <= t[1] in [t_min, t_max): 0 (none), 1 (near) or 2 (far); NaN is
 * in no range. rf_intersect_sphere's choice, for callers that need the root alone. */
static inline int rf_sphere_pick_root(const double t[2], double t_min, double t_max)
{
    return t[0] >= t_min && t[0] < t_max ? 1 : t[1] >= t_min && t[1] < t_max ? 2 : 0;
}
/* The outward unit normal at root t[far]. */
static inline RfVec3 rf_sphere_root_normal(const RfSphereRoots *r, const RfRay *ray, const RfSphere *s, int far)
{
    /* p - center = f + t d = v -+ (sqrt(D/4)/a) d: no cancellation between a large t and the
     * centre, so the normal of a far sphere keeps its digits (|v + x d| = r exactly). Inline:
     * a returned copy read back across its stores stalled. */
    double off = (r->sq > 0.0 ? r->sq : 0.0) / r->a; /* sqrt(D/4)/a; +0 for dq = -0 */
    return rf_vec3_scale(rf_vec3_add(r->v, rf_vec3_scale(ray->dir, far ? off : -off)), 1.0 / s->radius);
}

/* ---- §3.5.2 plane in Hesse form <x, normal> = offset (normal need not be unit) ---- */

typedef struct { RfVec3 normal; double offset; } RfPlane;

/* t = (offset - <e,n>) / <d,n> of the whole line; returns 0 (t untouched) when <d,n> = 0
 * exactly: the ray is parallel (a ray inside the plane counts as parallel, no hit). */
int rf_plane_line_t(RfRay ray, RfPlane p, double *t);
/* normal = normal/|normal| (the given side, not flipped towards the ray). */
int rf_intersect_plane(RfRay ray, RfPlane p, double t_min, double t_max, RfHit *hit);

/* ---- §3.5.3 triangles, two-sided ---- */

typedef struct { RfVec3 p1, p2, p3; } RfTriangle;

typedef enum {
    RF_TRIANGLE_SCRIPT,    /* §3.5.3: plane through the triangle, then barycentric >= 0 */
    RF_TRIANGLE_MOLLER,    /* Moller-Trumbore 1997 */
    RF_TRIANGLE_WATERTIGHT /* Woop, Benthin, Wald 2013 (JCGT 2(1)), with exact edge signs */
} RfTriangleMethod;

/* The watertight test's per-ray set-up (axis permutation and shear), computed once per ray.
 * lanes: the permutation as 32-bit lane indices of (x, y, z) doubles for the vector kernel;
 * scalar: 1 makes the test use its scalar kernel (the same answers; the tests compare them). */
typedef struct {
    RfRay ray;
    int kx, ky, kz;
    double sx, sy, sz;
    int lanes[8];
    int scalar;
} RfWatertightRay;
/* Sets *w up for ray (in place: the set-up is read soon after, field by field). */
void rf_watertight_ray(const RfRay *ray, RfWatertightRay *w);

/* All three: a hit has l1, l2, l3 >= 0 (edges and vertices included) and t in [t_min, t_max);
 * normal = normalise((p2 - p1) x (p3 - p1)) (counter-clockwise side), not flipped to the ray.
 * A degenerate (zero-area) triangle and a ray parallel to the triangle's plane never hit.
 * Only the watertight method guarantees that a ray through a shared edge or vertex of a
 * closed mesh hits at least one of the triangles (it may report both, with equal t). */
int rf_intersect_triangle(RfRay ray, RfTriangle tri, RfTriangleMethod method, double t_min,
                          double t_max, RfHit *hit);
int rf_intersect_triangle_watertight(const RfWatertightRay *wr, RfTriangle tri, double t_min,
                                     double t_max, RfHit *hit);
/* The watertight test's decision and distance alone (no range, no barycentrics, no normal):
 * 1 and *t when the ray's line meets the triangle. rf_intersect_triangle_watertight gives the
 * same t, bit for bit. */
int rf_watertight_t(const RfWatertightRay *wr, const RfTriangle *tri, double *t);
/* rf_watertight_t keeping the edge functions U, V, W and det = U + V + W in e: the hit's
 * barycentric coordinates are e[0..2] / e[3], rf_intersect_triangle_watertight's bit for bit
 * (the BVH keeps them for its winner instead of testing it again). */
int rf_watertight_edges(const RfWatertightRay *wr, const RfTriangle *tri, double *t, double e[4]);
/* The hit at t of the triangle whose edge functions rf_watertight_edges gave: barycentric
 * coordinates e[0..2] / e[3] and the unit normal (rf_triangle_unit_normal, or *normal when the
 * caller has it already) — rf_intersect_triangle_watertight's hit, which is made by this too. */
void rf_watertight_hit(const RfTriangle *tri, double t, const double e[4], const RfVec3 *normal, RfHit *hit);
/* normalise((p2 - p1) x (p3 - p1)): the normal every triangle hit reports. */
RfVec3 rf_triangle_unit_normal(const RfTriangle *tri);

/* ---- NFF `c`: open cone or cylinder (no caps) between base and apex ---- */

/* Radii >= 0, not both 0; base != apex. Equal radii: a cylinder. NFF's negative pair (visible
 * from inside only) is passed as absolute values; the caller decides visibility with the
 * outward normal. */
typedef struct { RfVec3 base; double base_radius; RfVec3 apex; double apex_radius; } RfCone;

/* The nearest hit of the lateral surface with axial position in [0, |apex - base|], from outside
 * or inside (the far wall). A tangent ray counts (double root). A ray along a cylinder's axis or
 * a cone's generator has no quadratic term: the single root of the linear equation is used; a
 * ray running inside the surface does not hit. normal: outward (away from the axis, tilted by
 * the slope); at a radius-0 tip it is taken along the axis. */
int rf_intersect_cone(RfRay ray, RfCone cone, double t_min, double t_max, RfHit *hit);
/* The numbers rf_intersect_cone derives from the cone alone on every call (unit axis k, height h,
 * slope m; degenerate: no surface), for a caller that tests one cone many times. */
typedef struct { RfVec3 k; double h, m; int degenerate; } RfConeFrame;
RfConeFrame rf_cone_frame(RfCone cone);
/* rf_intersect_cone with the cone's frame given: the same answer and t, bit for bit; with
 * want_normal 0 the normal is left zero (an occlusion test needs none). */
int rf_intersect_cone_framed(const RfRay *ray, const RfCone *cone, const RfConeFrame *frame, double t_min,
                             double t_max, int want_normal, RfHit *hit);

#ifdef __cplusplus
}
#endif

#endif
