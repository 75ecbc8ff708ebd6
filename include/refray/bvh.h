/* refray: a bounding volume hierarchy over primitives given by their bounding boxes.
 * Built top-down with the surface area heuristic over binned centroids (Wald 2007, "On fast
 * Construction of SAH-based Bounding Volume Hierarchies"), flattened depth-first (the left
 * child follows its parent), traversed front to back by the children's entry distances. Double precision throughout; the slab
 * test widens the far distance by 1 + 2 gamma(3) (Pharr, Jakob, Humphreys, PBR 4th ed., 6.8)
 * so that rounding never culls a box the ray really crosses. Deterministic: the same boxes give
 * the same tree. Boxes must be finite (unbounded primitives such as planes are the caller's). */
#ifndef REFRAY_BVH_H
#define REFRAY_BVH_H

#include "refray/ray.h"
#include "refray/status.h"
#include "refray/vec.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct { RfVec3 lo, hi; } RfAabb;

static inline RfAabb rf_aabb_empty(void)
{
    RfAabb b;
    b.lo = rf_vec3(HUGE_VAL, HUGE_VAL, HUGE_VAL);
    b.hi = rf_vec3(-HUGE_VAL, -HUGE_VAL, -HUGE_VAL);
    return b;
}
static inline RfAabb rf_aabb_union(RfAabb a, RfAabb b)
{
    a.lo = rf_vec3(fmin(a.lo.x, b.lo.x), fmin(a.lo.y, b.lo.y), fmin(a.lo.z, b.lo.z));
    a.hi = rf_vec3(fmax(a.hi.x, b.hi.x), fmax(a.hi.y, b.hi.y), fmax(a.hi.z, b.hi.z));
    return a;
}
static inline RfAabb rf_aabb_add_point(RfAabb a, RfVec3 p)
{
    RfAabb b;
    b.lo = b.hi = p;
    return rf_aabb_union(a, b);
}
static inline RfVec3 rf_aabb_center(RfAabb a) { return rf_vec3_scale(rf_vec3_add(a.lo, a.hi), 0.5); }
/* Surface area; 0 for an empty box. */
static inline double rf_aabb_area(RfAabb a)
{
    RfVec3 d = rf_vec3_sub(a.hi, a.lo);
    if (d.x < 0.0 || d.y < 0.0 || d.z < 0.0)
        return 0.0;
    return 2.0 * (d.x * d.y + d.y * d.z + d.z * d.x);
}

typedef struct {
    RfAabb box;
    int first; /* leaf: first position in RfBvh.prims; inner node: index of the right child */
    int count; /* leaf: number of primitives (> 0); inner node: 0 */
    int axis;  /* inner node: the split axis, for front-to-back order */
} RfBvhNode;

typedef struct {
    RfBvhNode *nodes;
    int node_count;
    int *prims; /* primitive indices, leaves refer to ranges of this array */
    int prim_count;
    int depth;  /* the deepest leaf's depth (root = 1) */
} RfBvh;

/* Builds the tree over n boxes (n >= 0). RF_ERR_DOMAIN for a box that is not finite,
 * RF_ERR_NOMEM. The bvh is zeroed on failure. */
RfStatus rf_bvh_build(RfBvh *bvh, const RfAabb *boxes, int n);
void rf_bvh_free(RfBvh *bvh);

/* Tests primitive prim against the ray; returns 1 and lowers *t_max to the hit distance when
 * it is hit at a t in (t_min, *t_max). ctx is the caller's. */
typedef int (*RfBvhPrimFn)(void *ctx, int prim, RfRay ray, double t_min, double *t_max);

/* The nearest hit in (t_min, *t_max) (any_hit = 0), or any hit (any_hit = 1, for shadow rays:
 * stops at the first). Returns the primitive index hit last (the nearest when any_hit = 0), or
 * -1; *t_max holds its distance. Of several primitives hit at exactly the same distance, the one
 * the traversal meets first wins (deterministic for a given tree). */
int rf_bvh_intersect(const RfBvh *bvh, RfRay ray, double t_min, double *t_max, RfBvhPrimFn fn,
                     void *ctx, int any_hit);

/* Whether the ray meets the box at some t in [t_min, t_max] (conservatively: never a false
 * miss). inv_dir = 1/dir per component. */
int rf_aabb_hit(RfAabb box, RfVec3 origin, RfVec3 inv_dir, double t_min, double t_max);

#ifdef __cplusplus
}
#endif

#endif
