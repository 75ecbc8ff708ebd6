/* refray: the acceleration structure of the tracer — a wide bounding volume hierarchy over
 * triangles (intersected here, watertight) and other items (boxes, intersected by the caller).
 *
 * Build: binned surface area heuristic (Wald 2007, "On fast Construction of SAH-based Bounding
 * Volume Hierarchies") over float boxes, top levels with parallel binning, then the subtrees on
 * every core; the binary tree is collapsed into nodes of 8 children (the child of the largest
 * area is opened first). The tree depends only on the items, never on the thread count.
 *
 * Exactness: speed comes from layout and from skipping work, never from a less exact decision.
 *  - Node boxes are floats rounded outward from the items' double boxes, and the ray's float
 *    slab test rounds every quantity toward "hit" (rf_bvh_ray_init), so no ray that touches a
 *    box in exact arithmetic is culled.
 *  - A leaf's triangles first pass a single-precision edge test, 4 at a time, that rejects a
 *    triangle only when error bounds prove that the double-precision watertight test
 *    (rf_watertight_t, §3.5.3) would reject it; the double test decides every candidate.
 *  - Of two hits at the same t the lower item index wins, so the answer does not depend on the
 *    tree, on the traversal order or on the code path (SIMD or scalar).
 * docs/performance.md has the layout, the error bounds and the measurements. */
#ifndef REFRAY_BVH_H
#define REFRAY_BVH_H

#include <stddef.h>
#include <stdint.h>

#include "refray/intersect.h"
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
static inline double rf_min_(double a, double b) { return b < a ? b : a; } /* NaN-free inputs */
static inline double rf_max_(double a, double b) { return b > a ? b : a; }
static inline RfAabb rf_aabb_union(RfAabb a, RfAabb b)
{
    a.lo = rf_vec3(rf_min_(a.lo.x, b.lo.x), rf_min_(a.lo.y, b.lo.y), rf_min_(a.lo.z, b.lo.z));
    a.hi = rf_vec3(rf_max_(a.hi.x, b.hi.x), rf_max_(a.hi.y, b.hi.y), rf_max_(a.hi.z, b.hi.z));
    return a;
}
static inline RfAabb rf_aabb_add_point(RfAabb a, RfVec3 p)
{
    RfAabb b;
    b.lo = b.hi = p;
    return rf_aabb_union(a, b);
}

static inline RfVec3 rf_aabb_center(RfAabb a) { return rf_vec3_scale(rf_vec3_add(a.lo, a.hi), 0.5); }

/* Which side of a triangle nearest-hit queries see (occlusion queries see both):
 * the counter-clockwise side (p2 - p1) x (p3 - p1) is the front. */
enum { RF_BVH_SEE_BOTH = 0, RF_BVH_SEE_FRONT = 1, RF_BVH_SEE_BACK = 2 };

/* What the BVH is told of an item. Triangles, spheres and cones it intersects itself
 * (watertight, §3.5.3; the stable quadratic, §3.5.1; rf_intersect_cone_framed), with the sides
 * they show to nearest-hit queries; any other item is given by its box and tested by the
 * caller's RfBvhItemFn. */
enum { RF_BVH_OTHER = 0, RF_BVH_TRIANGLE = 1, RF_BVH_SPHERE = 2, RF_BVH_CONE = 3 };

typedef struct {
    int kind;        /* RF_BVH_* */
    uint64_t key;    /* >= 1, distinct: of two hits at the same t the lower key wins */
    int sides;       /* triangles, spheres, cones: RF_BVH_SEE_* (the front is the outside) */
    uint32_t user;   /* triangles, spheres, cones: 30 bits the caller gets back with a hit */
    RfTriangle tri;  /* RF_BVH_TRIANGLE */
    RfSphere sphere; /* RF_BVH_SPHERE */
    RfCone cone;     /* RF_BVH_CONE, with its frame (rf_cone_frame) */
    RfConeFrame frame;
    RfAabb box;      /* RF_BVH_OTHER, RF_BVH_CONE */
} RfBvhItem;

typedef struct {
    int count; /* items 0 .. count-1 */
    /* Fills *out for item i. Boxes, vertices, centres and radii must be finite. Called once or
     * twice per item, from several threads at once. */
    void (*describe)(void *ctx, int item, RfBvhItem *out);
    void *ctx;
    int threads; /* build threads, 0: every core */
    int scalar;  /* 1: traverse with the scalar code (the vector code is the default where the
                    compiler targets AVX/SSE2; both give the same answers) */
} RfBvhDesc;

typedef struct RfBvhNode RfBvhNode;         /* 8 children: float boxes, child references */
typedef struct RfBvhTriBlock RfBvhTriBlock; /* 4 triangles: float and double vertices, keys */
typedef struct RfBvhOther RfBvhOther;       /* a sphere, a cone or a caller's item */
typedef struct { RfCone cone; RfConeFrame frame; } RfBvhCone;

typedef struct {
    RfBvhNode *nodes;
    int node_count;
    RfBvhTriBlock *blocks;
    int block_count;
    RfBvhOther *others; /* spheres, cones and the caller's items, in leaf order */
    int other_count;
    RfBvhCone *cones;   /* the cones of others, in leaf order */
    int cone_count;
    int item_count, tri_count;
    int depth;         /* levels of 8-wide nodes, root = 1 */
    double vmax;       /* max |coordinate| of any triangle vertex (the filter's error scale) */
    RfVec3 *normals;   /* a small BVH's: each triangle lane's rf_triangle_unit_normal (blocks' order),
                          read by the side test and passed on with the nearest hit; NULL in a
                          large one */
    int scalar;
} RfBvh;

/* Builds the structure. RF_ERR_DOMAIN for a non-finite or inverted box or vertex,
 * RF_ERR_NOMEM (also beyond 2^26 triangle blocks). The bvh is zeroed on failure. */
RfStatus rf_bvh_build(RfBvh *bvh, const RfBvhDesc *desc);
void rf_bvh_free(RfBvh *bvh);
/* Bytes held by the built structure (nodes, triangle blocks, item keys). */
size_t rf_bvh_bytes(const RfBvh *bvh);

/* A ray prepared for one BVH: the float slab constants, rounded so that the test stays
 * conservative, and — made by the traversal when it first reaches a triangle — the watertight
 * set-up (§3.5.3) and the filter's constants. */
typedef struct {
    RfRay ray;
    int tri_ready;     /* wr and the filter's fields are set (always when a triangle won) */
    RfWatertightRay wr;
    float org[2][4];   /* [0]: origin rounded for the near planes, [1]: for the far planes (x, y, z, -) */
    float inv[2][4];   /* 1/dir shrunk ([0], near) and grown ([1], far) by a few ulps (x, y, z, -) */
    const size_t *rows; /* byte offsets in RfBvhNode.b (rows of 8 floats) of axis a's near plane (rows[a]) and far
                          plane (rows[3 + a]): rows 2a and 2a + 1, swapped where dir < 0 (the near
                          plane is then the box's hi side); a static table's, not the ray's */
    float fo[3];       /* filter: the origin in float (nearest), permuted to kx, ky, kz */
    float fsx, fsy;    /* filter: the shear in float */
    float k1, k2, k3;  /* filter bound B = m (k1 + k2 m) + k3, m = max |ray-space coordinate| */
    int filter;        /* 0: every triangle goes to the double test (coordinates out of range) */
} RfBvhRay;

void rf_bvh_ray_init(const RfBvh *bvh, const RfRay *ray, RfBvhRay *out);

/* The caller's test of a non-triangle item: 1 and *t when the item is hit at t >= t_min with
 * t < t_max, or t <= t_max when inclusive. The caller keeps what else it needs of the hit: a
 * hit it reports is always the new nearest one. */
typedef int (*RfBvhItemFn)(void *ctx, uint64_t key, const RfBvhRay *ray, double t_min, double t_max,
                           int inclusive, double *t);

/* The nearest hit so far: t and key. Start with key 0 for "none" (t is then an exclusive limit)
 * or with a hit's key (a later hit at the same t must have a lower key). When a triangle, a
 * sphere or a cone of the BVH is the nearest: tri, sphere or cone (the others NULL), for a
 * triangle its edge functions (rf_watertight_edges: the barycentric coordinates are
 * edges[0..2] / edges[3]) and, when its side was checked or the BVH keeps its triangles'
 * normals (RfBvh.normals), its unit normal (has_normal), for a
 * sphere its roots and far (the far root: rf_sphere_root_normal), for a cone its normal, and the
 * user bits; all three NULL for the caller's items. */
typedef struct {
    double t;
    uint64_t key;
    const RfTriangle *tri;
    const RfSphere *sphere;
    const RfCone *cone;  /* a cone: its unit outward normal at t in normal */
    int far;
    RfSphereRoots roots; /* the sphere's, for rf_sphere_root_normal */
    double edges[4];     /* the triangle's U, V, W, det */
    int has_normal;
    RfVec3 normal;       /* rf_triangle_unit_normal of tri, when has_normal; a cone's normal */
    uint32_t user;
} RfBvhHit;

/* Improves *best with the nearest hit at t >= t_min: a hit (t, key) wins when t < best->t or
 * t == best->t and key < best->key. Triangles hidden by their `sides` do not count. Returns 1
 * when best changed. */
int rf_bvh_nearest(const RfBvh *bvh, RfBvhRay *ray, double t_min, RfBvhHit *best,
                   RfBvhItemFn fn, void *ctx);
/* The same with every triangle and sphere seen from either side, their `sides` aside (filtered
 * shadow rays, which cross every surface in turn). */
int rf_bvh_nearest_any_side(const RfBvh *bvh, RfBvhRay *ray, double t_min, RfBvhHit *best,
                            RfBvhItemFn fn, void *ctx);
/* rf_bvh_nearest (any_side = 0) or rf_bvh_nearest_any_side (1) for the rays of the lanes in
 * active (bit l: ray[l], t_min[l], best[l], ctx[l]) in one walk: a node is visited once for the
 * lanes that enter it, a sphere tested for all of them at once (rf_sphere_roots4). Each lane
 * ends with what its one-ray query gives (the (t, key) rule does not depend on the order of the
 * walk). Returns the lanes whose best changed. */
unsigned rf_bvh_nearest4(const RfBvh *bvh, RfBvhRay ray[4], unsigned active, const double t_min[4],
                         RfBvhHit best[4], RfBvhItemFn fn, void *const ctx[4], int any_side);
/* 1 when anything is hit at t_min <= t < t_max, seen from either side (shadow rays); *key (may
 * be NULL) gets the key of the item found. */
int rf_bvh_occluded(const RfBvh *bvh, RfBvhRay *ray, double t_min, double t_max,
                    RfBvhItemFn fn, void *ctx, uint64_t *key);

/* 1 when no ray from apex inside the cone {x : <n_k, x - apex> >= 0 for k < count} can reach a
 * leaf: the walk of every such ray stops at boxes that lie outside one of the planes by more
 * than 2^-13 S, S the largest magnitude among apex's and the root boxes' coordinates. The node
 * test reads the float boxes (rounded outward when built) and is conservative to about 2^-19 S
 * in the distances it compares, so such a ray enters none of them (docs/performance.md): a
 * frustum of camera rays that this holds for hits nothing in the BVH. 0 when in doubt (a NaN
 * or zero normal). */
int rf_bvh_cone_empty(const RfBvh *bvh, RfVec3 apex, const RfVec3 *normals, int count);

#ifdef __cplusplus
}
#endif

#endif
