/* SAH-binned BVH: build and traversal (see include/refray/bvh.h). */
#include "refray/bvh.h"

#include <float.h>
#include <stdlib.h>
#include <string.h>

#define BINS 16          /* centroid bins per split (Wald 2007 uses 16 or 32) */
#define MAX_LEAF 8       /* a leaf never holds more (unless all centroids coincide: see split) */
#define STACK 128        /* traversal stack; the depth is bounded by the build (MAX_DEPTH) */
#define MAX_DEPTH 100
#define COST_TRAVERSE 1.0 /* SAH cost of visiting a node, relative to one primitive test */

typedef struct {
    const RfAabb *boxes;
    RfVec3 *centers;
    int *prims;
    RfBvhNode *nodes;
    int node_count, node_cap, depth;
} Builder;

static double axis_of(RfVec3 v, int axis) { return axis == 0 ? v.x : axis == 1 ? v.y : v.z; }

/* The bin of a centroid coordinate c, for bins of width 1/scale from lo. */
static int bin_of(double c, double lo, double scale)
{
    int k = (int)((c - lo) * scale);
    return k < 0 ? 0 : k >= BINS ? BINS - 1 : k;
}

static int new_node(Builder *b)
{
    if (b->node_count == b->node_cap) {
        int cap = b->node_cap ? 2 * b->node_cap : 64;
        RfBvhNode *n = realloc(b->nodes, sizeof *n * (size_t)cap);
        if (!n)
            return -1;
        b->nodes = n;
        b->node_cap = cap;
    }
    return b->node_count++;
}

/* Chooses the split of prims[first .. first+count) with the lowest SAH cost; returns the number
 * that go left (0: make a leaf). Each axis is binned over the centroid bounds, and the best
 * split of the three axes wins. */
static int partition(Builder *b, int first, int count, RfAabb bounds, int *axis_out)
{
    RfAabb cb = rf_aabb_empty();
    for (int i = first; i < first + count; i++)
        cb = rf_aabb_add_point(cb, b->centers[b->prims[i]]);
    double best_cost = HUGE_VAL;
    int best_axis = -1, best_bin = -1;
    for (int axis = 0; axis < 3; axis++) {
        double lo = axis_of(cb.lo, axis), hi = axis_of(cb.hi, axis);
        if (!(hi > lo))
            continue;
        RfAabb bin_box[BINS];
        int bin_count[BINS] = {0};
        double scale = BINS / (hi - lo);
        for (int k = 0; k < BINS; k++)
            bin_box[k] = rf_aabb_empty();
        for (int i = first; i < first + count; i++) {
            int p = b->prims[i];
            int k = bin_of(axis_of(b->centers[p], axis), lo, scale);
            bin_count[k]++;
            bin_box[k] = rf_aabb_union(bin_box[k], b->boxes[p]);
        }
        /* sweep: cost of splitting after bin k = A_left N_left + A_right N_right */
        double right_area[BINS];
        int right_n[BINS];
        RfAabb acc = rf_aabb_empty();
        int n = 0;
        for (int k = BINS - 1; k > 0; k--) {
            acc = rf_aabb_union(acc, bin_box[k]);
            n += bin_count[k];
            right_area[k] = rf_aabb_area(acc);
            right_n[k] = n;
        }
        acc = rf_aabb_empty();
        n = 0;
        for (int k = 0; k < BINS - 1; k++) {
            acc = rf_aabb_union(acc, bin_box[k]);
            n += bin_count[k];
            if (n == 0 || right_n[k + 1] == 0)
                continue;
            double cost = rf_aabb_area(acc) * n + right_area[k + 1] * right_n[k + 1];
            if (cost < best_cost) {
                best_cost = cost;
                best_axis = axis;
                best_bin = k;
            }
        }
    }
    double area = rf_aabb_area(bounds);
    if (best_axis < 0) {
        /* all centroids coincide: halve by position so that leaves stay small */
        *axis_out = 0;
        return count > MAX_LEAF ? count / 2 : 0;
    }
    double split_cost = COST_TRAVERSE + (area > 0.0 ? best_cost / area : 0.0);
    if (count <= MAX_LEAF && split_cost >= count)
        return 0;
    /* partition in place by bin */
    double lo = axis_of(cb.lo, best_axis), scale = BINS / (axis_of(cb.hi, best_axis) - lo);
    int i = first, j = first + count - 1;
    while (i <= j) {
        if (bin_of(axis_of(b->centers[b->prims[i]], best_axis), lo, scale) <= best_bin) {
            i++;
        } else {
            int t = b->prims[i];
            b->prims[i] = b->prims[j];
            b->prims[j--] = t;
        }
    }
    *axis_out = best_axis;
    return i - first;
}

static int build(Builder *b, int first, int count, int depth)
{
    int idx = new_node(b);
    if (idx < 0)
        return -1;
    RfAabb bounds = rf_aabb_empty();
    for (int i = first; i < first + count; i++)
        bounds = rf_aabb_union(bounds, b->boxes[b->prims[i]]);
    if (depth > b->depth)
        b->depth = depth;
    int axis = 0;
    int left = depth >= MAX_DEPTH ? 0 : partition(b, first, count, bounds, &axis);
    b->nodes[idx].box = bounds;
    b->nodes[idx].axis = axis;
    if (left == 0) {
        b->nodes[idx].first = first;
        b->nodes[idx].count = count;
        return idx;
    }
    b->nodes[idx].count = 0;
    if (build(b, first, left, depth + 1) < 0)
        return -1;
    int right = build(b, first + left, count - left, depth + 1);
    if (right < 0)
        return -1;
    b->nodes[idx].first = right; /* b->nodes may have moved: index, not pointer */
    return idx;
}

RfStatus rf_bvh_build(RfBvh *bvh, const RfAabb *boxes, int n)
{
    Builder b;
    memset(bvh, 0, sizeof *bvh);
    memset(&b, 0, sizeof b);
    if (n < 0)
        return RF_ERR_DOMAIN;
    for (int i = 0; i < n; i++) {
        RfAabb x = boxes[i];
        if (!isfinite(x.lo.x) || !isfinite(x.lo.y) || !isfinite(x.lo.z) || !isfinite(x.hi.x) ||
            !isfinite(x.hi.y) || !isfinite(x.hi.z) || x.lo.x > x.hi.x || x.lo.y > x.hi.y || x.lo.z > x.hi.z)
            return RF_ERR_DOMAIN;
    }
    if (n == 0)
        return RF_OK;
    b.boxes = boxes;
    b.centers = malloc(sizeof *b.centers * (size_t)n);
    b.prims = malloc(sizeof *b.prims * (size_t)n);
    if (!b.centers || !b.prims) {
        free(b.centers);
        free(b.prims);
        return RF_ERR_NOMEM;
    }
    for (int i = 0; i < n; i++) {
        b.centers[i] = rf_aabb_center(boxes[i]);
        b.prims[i] = i;
    }
    int root = build(&b, 0, n, 1);
    free(b.centers);
    if (root < 0) {
        free(b.prims);
        free(b.nodes);
        return RF_ERR_NOMEM;
    }
    bvh->nodes = b.nodes;
    bvh->node_count = b.node_count;
    bvh->prims = b.prims;
    bvh->prim_count = n;
    bvh->depth = b.depth;
    return RF_OK;
}

void rf_bvh_free(RfBvh *bvh)
{
    free(bvh->nodes);
    free(bvh->prims);
    memset(bvh, 0, sizeof *bvh);
}

/* 1 + 2 gamma(3), gamma(n) = n eps / (1 - n eps) with eps = DBL_EPSILON / 2 (PBR 4th ed.) */
#define SLAB_WIDEN (1.0 + 2.0 * (3.0 * (DBL_EPSILON / 2)) / (1.0 - 3.0 * (DBL_EPSILON / 2)))

/* A ray prepared for slab tests: origin, reciprocal direction and the sign of each component
 * (which picks the near and the far plane of every slab without a swap). */
typedef struct {
    RfVec3 o, inv;
    int nx, ny, nz;
} SlabRay;

static SlabRay slab_ray(RfVec3 o, RfVec3 inv)
{
    SlabRay r;
    r.o = o;
    r.inv = inv;
    r.nx = inv.x < 0.0;
    r.ny = inv.y < 0.0;
    r.nz = inv.z < 0.0;
    return r;
}

/* The distance where the ray enters the box within [t0, t1], or HUGE_VAL for a miss. The far
 * distances are widened by SLAB_WIDEN so that rounding never culls a box the ray crosses; a NaN
 * (0 * inf: the origin on a slab plane of a parallel ray) fails the comparisons and leaves the
 * interval as it was, which is conservative too. */
static inline double slab_entry(const RfAabb *b, const SlabRay *r, double t0, double t1)
{
    double tn, tf;
    tn = ((r->nx ? b->hi.x : b->lo.x) - r->o.x) * r->inv.x;
    tf = ((r->nx ? b->lo.x : b->hi.x) - r->o.x) * r->inv.x * SLAB_WIDEN;
    t0 = tn > t0 ? tn : t0;
    t1 = tf < t1 ? tf : t1;
    tn = ((r->ny ? b->hi.y : b->lo.y) - r->o.y) * r->inv.y;
    tf = ((r->ny ? b->lo.y : b->hi.y) - r->o.y) * r->inv.y * SLAB_WIDEN;
    t0 = tn > t0 ? tn : t0;
    t1 = tf < t1 ? tf : t1;
    tn = ((r->nz ? b->hi.z : b->lo.z) - r->o.z) * r->inv.z;
    tf = ((r->nz ? b->lo.z : b->hi.z) - r->o.z) * r->inv.z * SLAB_WIDEN;
    t0 = tn > t0 ? tn : t0;
    t1 = tf < t1 ? tf : t1;
    return t0 <= t1 ? t0 : HUGE_VAL;
}

int rf_aabb_hit(RfAabb box, RfVec3 origin, RfVec3 inv_dir, double t_min, double t_max)
{
    SlabRay r = slab_ray(origin, inv_dir);
    return slab_entry(&box, &r, t_min, t_max) != HUGE_VAL;
}

int rf_bvh_intersect(const RfBvh *bvh, RfRay ray, double t_min, double *t_max, RfBvhPrimFn fn,
                     void *ctx, int any_hit)
{
    if (bvh->node_count == 0)
        return -1;
    SlabRay r = slab_ray(ray.origin, rf_vec3(1.0 / ray.dir.x, 1.0 / ray.dir.y, 1.0 / ray.dir.z));
    struct {
        int node;
        double entry;
    } stack[STACK];
    int top = 0, hit = -1, node = 0;
    if (slab_entry(&bvh->nodes[0].box, &r, t_min, *t_max) == HUGE_VAL)
        return -1;
    for (;;) {
        const RfBvhNode *n = &bvh->nodes[node];
        if (n->count == 0) {
            /* test both children here and go to the nearer one first; the farther one waits on
             * the stack with its entry distance, and is skipped if a closer hit appears */
            int a = node + 1, b = n->first;
            double ta = slab_entry(&bvh->nodes[a].box, &r, t_min, *t_max);
            double tb = slab_entry(&bvh->nodes[b].box, &r, t_min, *t_max);
            if (tb < ta) {
                int ti = a;
                double tt = ta;
                a = b, ta = tb, b = ti, tb = tt;
            }
            if (ta != HUGE_VAL) {
                if (tb != HUGE_VAL) {
                    stack[top].node = b;
                    stack[top++].entry = tb;
                }
                node = a;
                continue;
            }
        } else {
            for (int i = n->first; i < n->first + n->count; i++) {
                int p = bvh->prims[i];
                if (fn(ctx, p, ray, t_min, t_max)) {
                    hit = p;
                    if (any_hit)
                        return hit;
                }
            }
        }
        /* pop the next subtree that can still hold a closer hit */
        for (node = -1; top > 0;) {
            top--;
            if (stack[top].entry <= *t_max) {
                node = stack[top].node;
                break;
            }
        }
        if (node < 0)
            break;
    }
    return hit;
}
