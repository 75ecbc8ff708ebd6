/* The BVH's build (refray/bvh.h): references in float boxes rounded outward, binned SAH with
 * the top levels binned on every thread and the subtrees built on every thread, the binary
 * tree collapsed to 8-wide nodes, triangle blocks filled on every thread. */
#include <float.h>
#include <limits.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "bvh_layout.h"
#include "refray/parallel.h"

#if defined(__SSE2__)
#include <emmintrin.h>
#define RF_BVH_SSE 1
#endif

#define BINS 32          /* centroid bins per split (Wald 2007 uses 16 or 32) */
#define MAX_LEAF 8       /* items in a leaf (two triangle blocks) */
#define SAH_DEPTH 32     /* deeper, splits halve the range: depth stays below 64 */
#define COST_NODE 1.5f   /* SAH cost of a node visit, in triangle blocks */
#define COST_OTHER 2.0f  /* SAH cost of an item tested by the caller, in triangle blocks */
#define PAR_BIN 65536    /* ranges at least this long are binned on every thread */
#define SHORT_RANGE 64   /* shorter ranges are binned into one set of bins (bin_range) */
#define TASK_MIN 4096    /* the top levels are split until subtrees are this small ... */
#define TASKS_PER_THREAD 8 /* ... or there are about this many per thread */
/* In a BVH of at least LARGE_BVH items, a range of at least ONE_AXIS_FROM is binned along the
 * longest axis of its centroids' box alone: a third of the binning, and on the 1.2 M-triangle
 * bunny the same trace cost within 0.1 % (callgrind; below 512 items the other axes start to
 * pay). Smaller BVHs, whose build takes milliseconds, keep all three axes: there the trace is
 * what counts (+0.8 to +1.9 % on the SPD scenes with one axis). docs/performance.md. */
#define LARGE_BVH 65536
#define ONE_AXIS_FROM 512


/* ---- references, boxes, bins ---------------------------------------------------------- */

typedef struct { float lo[4], hi[4]; } Ref; /* lane 3 is 0; the item lives in ids[] */
typedef struct { float lo[4], hi[4]; } Box4;
typedef struct { Box4 box; int32_t a, b; } BNode; /* inner: children a, b; leaf: a = -1 - first, b = count */

/* What the split of a range needs to know of it: its box, its centroids' box (centroid = lo + hi,
 * twice the centre) and how many of its items are triangles. */
typedef struct {
    Box4 bounds, cbounds;
    int nt;
} Info;

static Box4 box4_empty(void)
{
    Box4 b;
    for (int k = 0; k < 4; k++) {
        b.lo[k] = INFINITY;
        b.hi[k] = -INFINITY;
    }
    b.lo[3] = b.hi[3] = 0.0f;
    return b;
}
static inline void box4_grow(Box4 *b, const float lo[4], const float hi[4])
{
#if RF_BVH_SSE
    _mm_storeu_ps(b->lo, _mm_min_ps(_mm_loadu_ps(b->lo), _mm_loadu_ps(lo)));
    _mm_storeu_ps(b->hi, _mm_max_ps(_mm_loadu_ps(b->hi), _mm_loadu_ps(hi)));
#else
    for (int k = 0; k < 3; k++) {
        b->lo[k] = lo[k] < b->lo[k] ? lo[k] : b->lo[k];
        b->hi[k] = hi[k] > b->hi[k] ? hi[k] : b->hi[k];
    }
#endif
}
static inline void centroid(const Ref *r, float c[4])
{
    for (int k = 0; k < 4; k++)
        c[k] = r->lo[k] + r->hi[k];
}
static float box4_area(const Box4 *b)
{
    float dx = b->hi[0] - b->lo[0], dy = b->hi[1] - b->lo[1], dz = b->hi[2] - b->lo[2];
    if (!(dx >= 0.0f && dy >= 0.0f && dz >= 0.0f))
        return 0.0f;
    return dx * dy + dy * dz + dz * dx; /* half the area: only ratios matter */
}

static void info_of(const Ref *refs, const int32_t *ids, int first, int count, Info *in)
{
    in->bounds = box4_empty();
    in->cbounds = box4_empty();
    in->nt = 0;
    for (int i = first; i < first + count; i++) {
        float c[4];
        centroid(&refs[i], c);
        box4_grow(&in->bounds, refs[i].lo, refs[i].hi);
        box4_grow(&in->cbounds, c, c);
        in->nt += ids[i] >= 0;
    }
}

typedef struct {
    Box4 box[3][BINS];
    int n[3][BINS], nt[3][BINS]; /* items and triangles per bin */
} Bins;

/* The bin of a centroid along each axis; binning and partitioning call the same routine, so
 * they agree bit for bit. */
typedef struct {
    float cmin[4], scale[4]; /* scale 0: no extent, the axis cannot be split */
    int bins;
    int axis0, axis1;        /* the axes binned: [axis0, axis1) */
} Binner;

static inline void bin_of(const Binner *bn, const Ref *r, int k[4])
{
#if RF_BVH_SSE
    __m128 c = _mm_add_ps(_mm_loadu_ps(r->lo), _mm_loadu_ps(r->hi));
    __m128 f = _mm_mul_ps(_mm_sub_ps(c, _mm_loadu_ps(bn->cmin)), _mm_loadu_ps(bn->scale));
    f = _mm_min_ps(_mm_max_ps(f, _mm_setzero_ps()), _mm_set1_ps((float)(bn->bins - 1)));
    _mm_storeu_si128((__m128i *)k, _mm_cvttps_epi32(f));
#else
    const float top = (float)(bn->bins - 1);
    for (int a = 0; a < 3; a++) {
        float f = (r->lo[a] + r->hi[a] - bn->cmin[a]) * bn->scale[a];
        f = f > 0.0f ? f : 0.0f; /* max, then min: as the vector code */
        f = f < top ? f : top;
        k[a] = (int)f;
    }
    k[3] = 0;
#endif
}

/* Two sets of bins (sets = 2), items alternating between them: consecutive items often fall
 * into the same bin, and one set would make each update wait for the previous one. A short
 * range takes one set (sets = 1): there the second set's clearing and merging cost more. */
static void bin_range(const Ref *refs, const int32_t *ids, int first, int end, const Binner *bn, int sets, Bins *b)
{
    Bins *two = b + sets - 1;
    for (int s = 0; s < sets; s++)
        for (int a = bn->axis0; a < bn->axis1; a++)
            for (int k = 0; k < bn->bins; k++) {
                b[s].box[a][k] = box4_empty();
                b[s].n[a][k] = b[s].nt[a][k] = 0;
            }
    for (int i = first; i < end; i++) {
        const Ref *r = &refs[i];
        Bins *bs = (i & 1) ? two : b;
        int k[4], tri = ids[i] >= 0;
        bin_of(bn, r, k);
        for (int a = bn->axis0; a < bn->axis1; a++) {
            box4_grow(&bs->box[a][k[a]], r->lo, r->hi);
            bs->n[a][k[a]]++;
            bs->nt[a][k[a]] += tri;
        }
    }
}

static void bins_merge(Bins *into, const Bins *b, const Binner *bn)
{
    int bins = bn->bins;
    for (int a = bn->axis0; a < bn->axis1; a++)
        for (int k = 0; k < bins; k++) {
            box4_grow(&into->box[a][k], b->box[a][k].lo, b->box[a][k].hi);
            into->n[a][k] += b->n[a][k];
            into->nt[a][k] += b->nt[a][k];
        }
}

/* SAH cost of a leaf with n items of which nt are triangles (4 to a block). */
static float leaf_cost(int n, int nt) { return (float)((nt + LANES - 1) / LANES) + COST_OTHER * (float)(n - nt); }

/* ---- the binary tree ------------------------------------------------------------------------ */

typedef struct {
    BNode *nodes;
    int count, cap;
} NodeBuf;

typedef struct {
    Ref *refs;
    int32_t *ids;  /* item >= 0 for triangles, -1 - item for the caller's items */
    int threads;
    int one_axis_from; /* ranges this long or longer are binned along one axis (ONE_AXIS_FROM) */
} Builder;

typedef struct {
    int first, count, depth;
    Info info;
    int parent; /* the top-level node whose child this subtree is, and which side */
    int side;
    NodeBuf buf;
} Task;

typedef struct {
    Task *tasks;
    int count, cap;
    int task_size; /* ranges up to this long become tasks in the top phase */
} TaskList;

/* Room for one more element in a growing array (the capacity doubles); 0: out of memory. */
static int room_for_one(void **arr, int *cap, int count, size_t elem)
{
    if (count < *cap)
        return 1;
    if (*cap > INT_MAX / 2)
        return 0;
    int c = *cap ? 2 * *cap : 64;
    void *p = realloc(*arr, elem * (size_t)c);
    if (!p)
        return 0;
    *arr = p;
    *cap = c;
    return 1;
}

static int nb_new(NodeBuf *nb)
{
    return room_for_one((void **)&nb->nodes, &nb->cap, nb->count, sizeof *nb->nodes) ? nb->count++ : -1;
}

typedef struct {
    const Builder *b;
    const Binner *bn;
    int first, count, chunks;
    Bins *bins;
} BinJob;

static int bin_chunk(void *ctx, int i, int thread)
{
    const BinJob *j = ctx;
    int lo = j->first + (int)((long long)j->count * i / j->chunks);
    int hi = j->first + (int)((long long)j->count * (i + 1) / j->chunks);
    (void)thread;
    bin_range(j->b->refs, j->b->ids, lo, hi, j->bn, 2, &j->bins[2 * i]);
    return 0;
}

static void swap_refs(Builder *b, int i, int j)
{
    Ref r = b->refs[i];
    int32_t id = b->ids[i];
    b->refs[i] = b->refs[j];
    b->ids[i] = b->ids[j];
    b->refs[j] = r;
    b->ids[j] = id;
}

static inline int goes_right(const Binner *bn, const Ref *r, int axis, int bin)
{
    int k[4];
    bin_of(bn, r, k);
    return k[axis] > bin;
}

/* Partitions refs[first, first + count) in place by the split (left: the bins up to bin) and
 * returns where the right side starts. Blocks of PBLOCK items at both ends are classified
 * without branches into lists of misplaced items, which are then swapped in pairs (Edelkamp and
 * Weiss, BlockQuicksort, 2016): a plain partition's branch per item mispredicts half the time
 * (the build 0.74 -> 0.65 s on the 1.2 M-triangle mesh; a branch-free copy into scratch memory
 * was slower, its copy back costing more than the mispredictions). */
#define PBLOCK 64
static int partition(Builder *b, int first, int count, const Binner *bn, int axis, int bin)
{
    int i = first, j = first + count - 1; /* [first, i) is left, (j, first + count) right */
    uint8_t offl[PBLOCK], offr[PBLOCK];   /* the misplaced items of the two blocks */
    int nl = 0, nr = 0, sl = 0, sr = 0;
    while (j - i + 1 >= 2 * PBLOCK) {
        if (nl == 0) {
            sl = 0;
            for (int k = 0; k < PBLOCK; k++) {
                offl[nl] = (uint8_t)k;
                nl += goes_right(bn, &b->refs[i + k], axis, bin);
            }
        }
        if (nr == 0) {
            sr = 0;
            for (int k = 0; k < PBLOCK; k++) {
                offr[nr] = (uint8_t)k;
                nr += !goes_right(bn, &b->refs[j - k], axis, bin);
            }
        }
        int m = nl < nr ? nl : nr;
        for (int k = 0; k < m; k++)
            swap_refs(b, i + offl[sl + k], j - offr[sr + k]);
        nl -= m;
        nr -= m;
        sl += m;
        sr += m;
        if (nl == 0)
            i += PBLOCK;
        if (nr == 0)
            j -= PBLOCK;
    }
    while (i <= j) { /* the rest, and a block's items not yet swapped, one by one */
        if (!goes_right(bn, &b->refs[i], axis, bin))
            i++;
        else
            swap_refs(b, i, j--);
    }
    return i;
}

/* The box of the centroids of refs[first, end). */
static void centroid_bounds(const Ref *refs, int first, int end, Box4 *box)
{
    *box = box4_empty();
    for (int i = first; i < end; i++) {
        float c[4];
        centroid(&refs[i], c);
        box4_grow(box, c, c);
    }
}

/* Halves a range without looking at positions (no useful split exists, or the depth limit). */
static int halve(const Builder *b, int first, int count, Info *left, Info *right)
{
    int l = count / 2;
    info_of(b->refs, b->ids, first, l, left);
    info_of(b->refs, b->ids, first + l, count - l, right);
    return l;
}

/* Chooses how to split refs[first, first + count) and partitions it in place; returns the
 * number that go left (0: make a leaf) and the two sides' Info. SAH over up to BINS bins per
 * axis (fewer for short ranges; one axis for long ranges of big BVHs, ONE_AXIS_FROM); halves the
 * range when no bin split exists or the depth limit is reached. */
static int split(Builder *b, int first, int count, int depth, const Info *in, Info *left, Info *right)
{
    int leaf_ok = count <= MAX_LEAF;
    if (count == 1 || (count <= LANES && in->nt == count))
        return 0; /* one block: its cost 1 is below a node's (COST_NODE) alone */
    if (depth > SAH_DEPTH)
        return leaf_ok ? 0 : halve(b, first, count, left, right);
    Binner bn;
    int any_axis = 0;
    bn.bins = count < 4 * BINS ? 4 + count / 8 : BINS;
    for (int a = 0; a < 3; a++) {
        float ext = in->cbounds.hi[a] - in->cbounds.lo[a];
        bn.cmin[a] = in->cbounds.lo[a];
        /* (1 - 2^-10): the largest centroid stays in the last bin despite rounding */
        bn.scale[a] = ext > 0.0f ? (float)bn.bins * (1.0f - 0x1p-10f) / ext : 0.0f;
        any_axis |= ext > 0.0f;
    }
    bn.cmin[3] = bn.scale[3] = 0.0f;
    bn.axis0 = 0, bn.axis1 = 3;
    if (count >= b->one_axis_from) { /* the longest axis of the centroids' box alone */
        int w = 0;
        for (int a = 1; a < 3; a++)
            if (in->cbounds.hi[a] - in->cbounds.lo[a] > in->cbounds.hi[w] - in->cbounds.lo[w])
                w = a;
        bn.axis0 = w, bn.axis1 = w + 1;
    }
    if (!any_axis) /* every centroid coincides */
        return leaf_ok ? 0 : halve(b, first, count, left, right);
    Bins bins2[2], *bins = bins2, *part = NULL; /* merged in place: a Bins is 3.8 KB */
    if (count >= PAR_BIN && b->threads > 1 && (part = malloc(sizeof *part * 2 * (size_t)b->threads))) {
        BinJob j = {b, &bn, first, count, b->threads, part};
        if (rf_parallel_for(b->threads, b->threads, bin_chunk, NULL, &j) == RF_OK) {
            bins = part;
            for (int t = 1; t < 2 * b->threads; t++)
                bins_merge(bins, &part[t], &bn);
        }
    }
    if (bins == bins2) {
        int sets = count >= SHORT_RANGE ? 2 : 1;
        bin_range(b->refs, b->ids, first, first + count, &bn, sets, bins2);
        if (sets == 2)
            bins_merge(bins, &bins2[1], &bn);
    }
    /* sweep each axis: the cost of splitting after bin k */
    float best = INFINITY;
    int best_axis = -1, best_bin = -1;
    Box4 best_l, best_r;
    int best_nt = 0;
    for (int a = bn.axis0; a < bn.axis1; a++) {
        if (!(bn.scale[a] > 0.0f))
            continue;
        float right_cost[BINS];
        Box4 right_box[BINS];
        Box4 acc = box4_empty();
        int n = 0, t = 0;
        for (int k = bn.bins - 1; k > 0; k--) {
            box4_grow(&acc, bins->box[a][k].lo, bins->box[a][k].hi);
            n += bins->n[a][k];
            t += bins->nt[a][k];
            right_cost[k] = n ? box4_area(&acc) * leaf_cost(n, t) : -1.0f;
            right_box[k] = acc;
        }
        acc = box4_empty();
        n = t = 0;
        for (int k = 0; k < bn.bins - 1; k++) {
            box4_grow(&acc, bins->box[a][k].lo, bins->box[a][k].hi);
            n += bins->n[a][k];
            t += bins->nt[a][k];
            if (n == 0 || right_cost[k + 1] < 0.0f)
                continue;
            float c = box4_area(&acc) * leaf_cost(n, t) + right_cost[k + 1];
            if (c < best) {
                best = c;
                best_axis = a;
                best_bin = k;
                best_l = acc;
                best_r = right_box[k + 1];
                best_nt = t;
            }
        }
    }
    free(part);
    if (best_axis < 0)
        return leaf_ok ? 0 : halve(b, first, count, left, right);
    float area = box4_area(&in->bounds);
    float split_cost = COST_NODE + (area > 0.0f ? best / area : 0.0f);
    if (leaf_ok && leaf_cost(count, in->nt) <= split_cost)
        return 0;
    int i = partition(b, first, count, &bn, best_axis, best_bin);
    Box4 lc, rc;
    centroid_bounds(b->refs, first, i, &lc);
    centroid_bounds(b->refs, i, first + count, &rc);
    left->bounds = best_l;
    left->cbounds = lc;
    left->nt = best_nt;
    right->bounds = best_r;
    right->cbounds = rc;
    right->nt = in->nt - best_nt;
    return i - first;
}

/* Builds the subtree of refs[first, first + count) into nb; returns its root index or -1
 * (out of memory). In the top phase (tasks != NULL) ranges up to task_size become tasks. A
 * leaf holds one kind of item: a range of both kinds is split by kind. */
static int build_node(Builder *b, NodeBuf *nb, TaskList *tasks, int first, int count, int depth, const Info *in)
{
    int idx = nb_new(nb);
    if (idx < 0)
        return -1;
    nb->nodes[idx].box = in->bounds;
    Info info[2];
    int left = split(b, first, count, depth, in, &info[0], &info[1]);
    if (left == 0 && in->nt > 0 && in->nt < count) {
        int i = first, j = first + count - 1;
        while (i <= j) { /* triangles first */
            if (b->ids[i] >= 0)
                i++;
            else
                swap_refs(b, i, j--);
        }
        left = in->nt;
        info_of(b->refs, b->ids, first, left, &info[0]);
        info_of(b->refs, b->ids, first + left, count - left, &info[1]);
    }
    if (left == 0) {
        nb->nodes[idx].a = -1 - first;
        nb->nodes[idx].b = count;
        return idx;
    }
    int ranges[2][2] = {{first, left}, {first + left, count - left}};
    int child[2];
    for (int s = 0; s < 2; s++) {
        if (tasks && ranges[s][1] <= tasks->task_size) {
            if (!room_for_one((void **)&tasks->tasks, &tasks->cap, tasks->count, sizeof *tasks->tasks))
                return -1;
            Task *t = &tasks->tasks[tasks->count];
            memset(t, 0, sizeof *t);
            t->first = ranges[s][0];
            t->count = ranges[s][1];
            t->depth = depth + 1;
            t->info = info[s];
            t->parent = idx;
            t->side = s;
            child[s] = -2 - tasks->count++; /* linked after the parallel phase */
        } else {
            child[s] = build_node(b, nb, tasks, ranges[s][0], ranges[s][1], depth + 1, &info[s]);
            if (child[s] < 0)
                return -1;
        }
    }
    nb->nodes[idx].a = child[0];
    nb->nodes[idx].b = child[1];
    return idx;
}

typedef struct {
    Builder *b;
    TaskList *tl;
    const int *order; /* tasks by decreasing size */
} TaskJob;

static int run_task(void *ctx, int i, int thread)
{
    TaskJob *j = ctx;
    Task *t = &j->tl->tasks[j->order[i]];
    (void)thread;
    return build_node(j->b, &t->buf, NULL, t->first, t->count, t->depth, &t->info) < 0;
}

static int cmp_task_size(const void *a, const void *b, void *ctx);

/* ---- build: collapse to 8-wide nodes ------------------------------------------------------- */

typedef struct {
    BNode *bn;            /* the whole binary tree, room for ROOT_EXTRA more nodes at bn_count */
    int bn_count;
    Ref *refs;            /* the items' boxes and ids, in leaf order (the root's refinement */
    int32_t *ids;         /* reorders a leaf's range) */
    RfBvhNode *nodes;     /* wide nodes, growing */
    int count, cap;
    int depth;
} Collapse;

static int wide_new(Collapse *c)
{
    if (!room_for_one((void **)&c->nodes, &c->cap, c->count, sizeof *c->nodes))
        return -1;
    RfBvhNode *n = &c->nodes[c->count];
    for (int k = 0; k < WIDTH; k++) {
        for (int a = 0; a < 3; a++) {
            n->b[2 * a][k] = INFINITY;
            n->b[2 * a + 1][k] = -INFINITY;
        }
        n->ref[k] = 0;
        n->pad[k] = 0;
    }
    return c->count++;
}

static int is_leaf(const BNode *n) { return n->a < 0; }

/* ---- the root's free slots ------------------------------------------------------------------
 * Every ray tests all 8 slots of the root, used or not, so a small scene whose binary tree has
 * fewer than 8 leaves gets its leaves cut into more slots for free. The binary SAH cannot see
 * such cuts: a leaf of four wall quads of a room has a box as large as the room, and so does
 * every two-way split of it, while four leaves of one flat quad each have a quarter of the
 * cost. So the root tries every partition of a leaf (at most MAX_LEAF items: Bell(8) = 4140
 * partitions) into as many groups as there are free slots plus one, and takes the one of least
 * SAH cost (area times leaf_cost) when it is below the leaf's. The traversal's answers do not
 * depend on the tree (docs/performance.md, "Ties"). */
#define ROOT_EXTRA (2 * WIDTH) /* nodes the refinement may add: 2 (groups - 1) per leaf */

typedef struct {
    const Ref *refs;
    int m, tris, max_groups;
    int cur[MAX_LEAF], best[MAX_LEAF];
    Box4 box[MAX_LEAF]; /* the groups of cur[0..i) so far: box, items and SAH cost */
    int n[MAX_LEAF];
    float cost[MAX_LEAF];
    float best_cost;
} Partition;

/* The SAH cost of a group of n items of one kind (triangles or not) within box. */
static float group_cost(const Box4 *box, int n, int tris) { return box4_area(box) * leaf_cost(n, tris ? n : 0); }

/* Every partition of items i.. given cur[0..i) in g groups (restricted growth strings), best
 * first found kept. A group's cost only grows as items join it, so a partial partition that
 * costs as much as the best already found is cut off (branch and bound). */
static void partition_search(Partition *p, int i, int g)
{
    float partial = 0.0f;
    for (int q = 0; q < g; q++)
        partial += p->cost[q];
    if (!(partial < p->best_cost))
        return;
    if (i == p->m) {
        p->best_cost = partial;
        memcpy(p->best, p->cur, sizeof p->best);
        return;
    }
    for (int q = 0; q <= g && q < p->max_groups; q++) {
        Box4 box = p->box[q];
        int n = p->n[q];
        float cost = p->cost[q];
        if (q == g) {
            p->box[q] = box4_empty();
            p->n[q] = 0;
        }
        box4_grow(&p->box[q], p->refs[i].lo, p->refs[i].hi);
        p->n[q]++;
        p->cost[q] = group_cost(&p->box[q], p->n[q], p->tris);
        p->cur[i] = q;
        partition_search(p, i + 1, q == g ? g + 1 : g);
        p->box[q] = box, p->n[q] = n, p->cost[q] = cost;
    }
}

/* The best partition of leaf node li into at most max_groups groups; its cost saving (0: none)
 * and, in p->best, each item's group. */
static float leaf_partition(const Collapse *c, int li, int max_groups, Partition *p)
{
    const BNode *leaf = &c->bn[li];
    int first = -1 - leaf->a;
    p->refs = &c->refs[first];
    p->m = leaf->b;
    p->tris = c->ids[first] >= 0;
    p->max_groups = max_groups;
    if (p->m < 2 || p->m > MAX_LEAF)
        return 0.0f;
    float whole = group_cost(&leaf->box, p->m, p->tris);
    p->best_cost = whole;
    partition_search(p, 0, 0);
    return whole - p->best_cost;
}

/* Cuts leaf node li by p->best: its items reordered group by group, the node turned into a
 * chain of inner nodes (group 0 | rest, group 1 | rest, ...) that the root's collapse opens. */
static void leaf_cut(Collapse *c, int li, const Partition *p)
{
    int first = -1 - c->bn[li].a, m = p->m, groups = 0;
    Ref refs[MAX_LEAF];
    int32_t ids[MAX_LEAF];
    int start[MAX_LEAF + 1];
    for (int i = 0; i < m; i++)
        groups = p->best[i] + 1 > groups ? p->best[i] + 1 : groups;
    int at = 0;
    for (int q = 0; q < groups; q++) {
        start[q] = at;
        for (int i = 0; i < m; i++)
            if (p->best[i] == q) {
                refs[at] = c->refs[first + i];
                ids[at++] = c->ids[first + i];
            }
    }
    start[groups] = m;
    memcpy(&c->refs[first], refs, sizeof *refs * (size_t)m);
    memcpy(&c->ids[first], ids, sizeof *ids * (size_t)m);
    /* from the last group back: each chain node holds group q and the rest */
    int rest = -1;
    for (int q = groups - 1; q >= 0; q--) {
        BNode leaf;
        leaf.box = box4_empty();
        for (int i = start[q]; i < start[q + 1]; i++)
            box4_grow(&leaf.box, c->refs[first + i].lo, c->refs[first + i].hi);
        leaf.a = -1 - (first + start[q]);
        leaf.b = start[q + 1] - start[q];
        int li_q = c->bn_count++;
        c->bn[li_q] = leaf;
        if (rest < 0) {
            rest = li_q;
            continue;
        }
        BNode inner;
        inner.box = leaf.box;
        box4_grow(&inner.box, c->bn[rest].box.lo, c->bn[rest].box.hi);
        inner.a = li_q;
        inner.b = rest;
        int in_q = q == 0 ? li : c->bn_count++;
        c->bn[in_q] = inner;
        rest = in_q;
    }
}

/* With only leaves in the root's n slots: cuts the leaf whose best partition saves the most;
 * 0 when none saves anything. */
static int root_refine(Collapse *c, const int *slot, int n)
{
    Partition p, best_p;
    float best_gain = 0.0f;
    int best_leaf = -1;
    for (int k = 0; k < n; k++) {
        float gain = leaf_partition(c, slot[k], WIDTH - n + 1, &p);
        if (gain > best_gain) {
            best_gain = gain;
            best_leaf = slot[k];
            best_p = p;
        }
    }
    if (best_leaf < 0)
        return 0;
    leaf_cut(c, best_leaf, &best_p);
    return 1;
}

/* Fills wide node w with the (up to 8) descendants of binary node bi: the child with the
 * largest area is opened until 8 slots are used or only leaves are left. A leaf slot gets its
 * kind and count in ref and, until the blocks are laid out, its range start in pad. */
static int collapse(Collapse *c, int bi, int w, int depth)
{
    int slot[WIDTH], n = 0;
    if (depth > c->depth)
        c->depth = depth;
    if (depth == 1 && is_leaf(&c->bn[bi]))
        root_refine(c, &bi, 1); /* a root that is one leaf: into up to 8 slots */
    if (is_leaf(&c->bn[bi])) {
        slot[n++] = bi;
    } else {
        slot[n++] = c->bn[bi].a;
        slot[n++] = c->bn[bi].b;
        while (n < WIDTH) {
            int best = -1;
            float best_area = -1.0f;
            for (int k = 0; k < n; k++) {
                const BNode *s = &c->bn[slot[k]];
                float a = box4_area(&s->box);
                if (!is_leaf(s) && a > best_area) {
                    best_area = a;
                    best = k;
                }
            }
            if (best < 0) { /* only leaves: the root may cut one into a chain of inner nodes */
                if (depth == 1 && root_refine(c, slot, n))
                    continue;
                break;
            }
            int open = slot[best];
            slot[best] = c->bn[open].a;
            slot[n++] = c->bn[open].b;
        }
    }
    int inner[WIDTH];
    for (int k = 0; k < n; k++) {
        const BNode *s = &c->bn[slot[k]];
        RfBvhNode *wn = &c->nodes[w];
        for (int a = 0; a < 3; a++) {
            wn->b[2 * a][k] = s->box.lo[a];
            wn->b[2 * a + 1][k] = s->box.hi[a];
        }
        inner[k] = -1;
        if (is_leaf(s)) {
            int first = -1 - s->a;
            wn->ref[k] = REF_LEAF(c->ids[first] >= 0 ? KIND_TRIS : KIND_OTHERS, 0, s->b);
            wn->pad[k] = (uint32_t)first;
        } else {
            int id = c->count < MAX_NODES ? wide_new(c) : -1;
            if (id < 0)
                return -1;
            wn = &c->nodes[w]; /* may have moved */
            wn->ref[k] = REF_INNER(id);
            inner[k] = id;
        }
    }
    for (int k = 0; k < n; k++)
        if (inner[k] >= 0 && collapse(c, slot[k], inner[k], depth + 1) < 0)
            return -1;
    return 0;
}

/* ---- build: the whole -------------------------------------------------------------------- */

/* What a block's lane needs of an item, kept from the first (sequential) pass over the items so
 * that filling the blocks in leaf order reads one small record per item instead of calling
 * describe() on the caller's scene in random order. */
typedef struct {
    union {
        RfTriangle tri;
        RfSphere sphere;
    } u;
    uint64_t key;
    uint32_t user; /* sides << 30 | the caller's bits */
    int kind;      /* RF_BVH_* */
} Payload;

enum { CHUNKS = 64 };

typedef struct {
    const RfBvhDesc *desc;
    Ref *refs;
    int32_t *ids;
    Payload *payload;
    double vmax[CHUNKS]; /* per chunk: max |coordinate| of a triangle vertex */
    int cones[CHUNKS];   /* per chunk: its cones */
    int bad;
} RefJob;

static int make_refs(void *ctx, int chunk, int thread)
{
    RefJob *j = ctx;
    int n = j->desc->count;
    int lo = (int)((long long)n * chunk / CHUNKS), hi = (int)((long long)n * (chunk + 1) / CHUNKS);
    double vmax = 0.0;
    int cones = 0;
    (void)thread;
    for (int i = lo; i < hi; i++) {
        Payload *pl = &j->payload[i];
        RfBvhItem it;
        memset(&it, 0, sizeof it);
        j->desc->describe(j->desc->ctx, i, &it);
        RfAabb box = it.box;
        pl->key = it.key;
        pl->kind = it.kind;
        pl->user = ((uint32_t)it.sides << 30) | (it.user & USER_BITS);
        if (it.kind == RF_BVH_TRIANGLE) {
            pl->u.tri = it.tri;
            const RfVec3 *p[3] = {&it.tri.p1, &it.tri.p2, &it.tri.p3};
            box = rf_aabb_add_point(rf_aabb_add_point(rf_aabb_add_point(rf_aabb_empty(), *p[0]), *p[1]), *p[2]);
            for (int v = 0; v < 3; v++) {
                double m = rf_max_num(fabs(p[v]->x), rf_max_num(fabs(p[v]->y), fabs(p[v]->z))); /* fmax, inline */
                vmax = m > vmax ? m : vmax;
            }
            j->ids[i] = i;
        } else {
            if (it.kind == RF_BVH_SPHERE) {
                pl->u.sphere = it.sphere;
                RfVec3 r = rf_vec3(it.sphere.radius, it.sphere.radius, it.sphere.radius);
                box.lo = rf_vec3_sub(it.sphere.center, r);
                box.hi = rf_vec3_add(it.sphere.center, r);
                if (!isfinite(it.sphere.radius) || !(it.sphere.radius > 0.0))
                    return j->bad = 1;
            }
            j->ids[i] = -1 - i;
        }
        const double lo3[3] = {box.lo.x, box.lo.y, box.lo.z}, hi3[3] = {box.hi.x, box.hi.y, box.hi.z};
        for (int a = 0; a < 3; a++) {
            if (!isfinite(lo3[a]) || !isfinite(hi3[a]) || !(lo3[a] <= hi3[a]))
                return j->bad = 1;
            j->refs[i].lo[a] = rf__widen_down(lo3[a]);
            j->refs[i].hi[a] = rf__widen_up(hi3[a]);
        }
        j->refs[i].lo[3] = j->refs[i].hi[3] = 0.0f;
        cones += it.kind == RF_BVH_CONE;
    }
    j->vmax[chunk] = vmax;
    j->cones[chunk] = cones;
    return 0;
}

typedef struct {
    RfBvh *bvh;
    const int32_t *ids;
    const Payload *payload;
    const int *leaf_node, *leaf_slot; /* triangle leaves: where they sit */
    const int *leaf_start;            /* and their range in ids[] */
    int leaves;
} FillJob;

/* Writes every lane of the blocks of a chunk of triangle leaves (empty lanes: key 0). */
static int fill_blocks(void *ctx, int chunk, int thread)
{
    const FillJob *j = ctx;
    int lo = (int)((long long)j->leaves * chunk / CHUNKS);
    int hi = (int)((long long)j->leaves * (chunk + 1) / CHUNKS);
    (void)thread;
    for (int l = lo; l < hi; l++) {
        const RfBvhNode *n = &j->bvh->nodes[j->leaf_node[l]];
        uint32_t ref = n->ref[j->leaf_slot[l]];
        int first = j->leaf_start[l], count = (int)n->pad[j->leaf_slot[l]];
        if (l + 4 < hi) { /* the records of a leaf a little ahead */
            int ahead = (int)j->bvh->nodes[j->leaf_node[l + 4]].pad[j->leaf_slot[l + 4]];
            for (int i = 0; i < ahead; i++)
                __builtin_prefetch(&j->payload[j->ids[j->leaf_start[l + 4] + i]]);
        }
        RfBvhTriBlock *blk = &j->bvh->blocks[REF_FIRST(ref)];
        for (int i = 0; i < REF_COUNT(ref) * LANES; i++) {
            RfBvhTriBlock *b = &blk[i / LANES];
            int lane = i % LANES;
            if (i >= count) {
                for (int v = 0; v < 3; v++)
                    for (int a = 0; a < 3; a++)
                        b->v[v][a][lane] = 0.0f;
                b->key[lane] = 0;
                b->user[lane] = 0;
                memset(&b->tri[lane], 0, sizeof b->tri[lane]);
                continue;
            }
            const Payload *pl = &j->payload[j->ids[first + i]];
            const RfVec3 *p[3] = {&pl->u.tri.p1, &pl->u.tri.p2, &pl->u.tri.p3};
            for (int v = 0; v < 3; v++) {
                b->v[v][0][lane] = (float)p[v]->x;
                b->v[v][1][lane] = (float)p[v]->y;
                b->v[v][2][lane] = (float)p[v]->z;
            }
            b->key[lane] = pl->key;
            b->user[lane] = pl->user;
            b->tri[lane] = pl->u.tri;
        }
    }
    return 0;
}

/* The unit normals of a small BVH's triangles (RfBvh.normals), made by the routine the side
 * test called per candidate (the same bits): whitted's ground computed one for most camera rays.
 * A large BVH computes them: there the array would be one more cache miss per candidate, and
 * 24 bytes a triangle. Returns 0 when out of memory. */
#define NORMALS_UP_TO 16384 /* triangle lanes: 384 KB of normals */
static int unit_normals(RfBvh *bvh)
{
    size_t lanes = (size_t)bvh->block_count * LANES;
    if (lanes == 0 || lanes > NORMALS_UP_TO)
        return 1;
    if (!(bvh->normals = malloc(sizeof *bvh->normals * lanes)))
        return 0;
    for (size_t i = 0; i < lanes; i++) {
        const RfBvhTriBlock *blk = &bvh->blocks[i / LANES];
        int k = (int)(i % LANES);
        bvh->normals[i] = blk->key[k] ? rf_triangle_unit_normal(&blk->tri[k]) : rf_vec3(0, 0, 0);
    }
    return 1;
}

static int cmp_task_size(const void *a, const void *b, void *ctx)
{
    const TaskList *tl = ctx;
    int ca = tl->tasks[*(const int *)a].count, cb = tl->tasks[*(const int *)b].count;
    if (ca != cb)
        return ca > cb ? -1 : 1;
    return *(const int *)a - *(const int *)b;
}

/* qsort with a context (C99 has none): an insertion sort, for the few dozen tasks. */
static void sort_tasks(int *order, int n, TaskList *tl)
{
    for (int i = 1; i < n; i++)
        for (int k = i; k > 0 && cmp_task_size(&order[k], &order[k - 1], tl) < 0; k--) {
            int t = order[k];
            order[k] = order[k - 1];
            order[k - 1] = t;
        }
}

static void *aligned(size_t bytes)
{
    void *p = NULL;
    return posix_memalign(&p, 64, bytes ? bytes : 64) == 0 ? p : NULL;
}

RfStatus rf_bvh_build(RfBvh *bvh, const RfBvhDesc *desc)
{
    memset(bvh, 0, sizeof *bvh);
    bvh->scalar = desc->scalar;
    int n = desc->count;
    if (n < 0)
        return RF_ERR_DOMAIN;
    bvh->item_count = n;
    if (n == 0)
        return RF_OK;
    RfStatus st = RF_ERR_NOMEM;
    int threads = desc->threads > 0 ? desc->threads : rf_cpu_count();
    Builder b = {malloc(sizeof(Ref) * (size_t)n), malloc(sizeof(int32_t) * (size_t)n), threads,
                 n >= LARGE_BVH ? ONE_AXIS_FROM : INT_MAX};
    NodeBuf top = {NULL, 0, 0};
    TaskList tl = {NULL, 0, 0, 0};
    int *order = NULL, *leaf_node = NULL, *leaf_slot = NULL, *leaf_start = NULL;
    Payload *payload = NULL;
    BNode *all = NULL;
    Collapse c;
    memset(&c, 0, sizeof c);
    if (!b.refs || !b.ids)
        goto done;
    RefJob *rj = calloc(1, sizeof *rj);
    payload = malloc(sizeof *payload * (size_t)n);
    if (!rj || !payload)
        goto done;
    rj->desc = desc;
    rj->refs = b.refs;
    rj->ids = b.ids;
    rj->payload = payload;
    if (rf_parallel_for(CHUNKS, threads, make_refs, NULL, rj) != RF_OK || rj->bad) {
        st = rj->bad ? RF_ERR_DOMAIN : RF_ERR_NOMEM;
        free(rj);
        goto done;
    }
    bvh->vmax = 0.0;
    int cones = 0;
    for (int i = 0; i < CHUNKS; i++) {
        bvh->vmax = rj->vmax[i] > bvh->vmax ? rj->vmax[i] : bvh->vmax;
        cones += rj->cones[i];
    }
    free(rj);
    /* the top levels here, their subtrees on every thread */
    tl.task_size = n / (TASKS_PER_THREAD * threads);
    if (tl.task_size < TASK_MIN)
        tl.task_size = TASK_MIN;
    Info root;
    info_of(b.refs, b.ids, 0, n, &root);
    if (build_node(&b, &top, threads > 1 ? &tl : NULL, 0, n, 1, &root) < 0)
        goto done;
    order = malloc(sizeof *order * (size_t)(tl.count + 1));
    if (!order)
        goto done;
    for (int i = 0; i < tl.count; i++)
        order[i] = i;
    sort_tasks(order, tl.count, &tl);
    TaskJob tj = {&b, &tl, order};
    if (rf_parallel_for(tl.count, threads, run_task, NULL, &tj) != RF_OK)
        goto done;
    /* one array: the top nodes, then each task's nodes (its indices shifted) */
    size_t total = (size_t)top.count;
    for (int i = 0; i < tl.count; i++)
        total += (size_t)tl.tasks[i].buf.count;
    all = malloc(sizeof *all * (total + ROOT_EXTRA));
    if (!all)
        goto done;
    memcpy(all, top.nodes, sizeof *all * (size_t)top.count);
    size_t at = (size_t)top.count;
    for (int i = 0; i < tl.count; i++) {
        Task *t = &tl.tasks[i];
        for (int k = 0; k < t->buf.count; k++) {
            BNode nd = t->buf.nodes[k];
            if (nd.a >= 0) {
                nd.a += (int32_t)at;
                nd.b += (int32_t)at;
            }
            all[at + (size_t)k] = nd;
        }
        if (t->side == 0)
            all[t->parent].a = (int32_t)at;
        else
            all[t->parent].b = (int32_t)at;
        at += (size_t)t->buf.count;
    }
    /* 8-wide nodes, leaves still as ranges of ids[] */
    c.bn = all;
    c.bn_count = (int)total;
    c.refs = b.refs;
    c.ids = b.ids;
    if (wide_new(&c) < 0 || collapse(&c, 0, 0, 1) < 0)
        goto done;
    free(b.refs); /* not needed any more: make room for the blocks */
    b.refs = NULL;
    free(all);
    all = NULL;
    /* leaves: triangle blocks (filled on every thread) and the caller's items */
    int leaves = 0, blocks = 0, others = 0;
    for (int i = 0; i < c.count; i++)
        for (int k = 0; k < WIDTH; k++) {
            uint32_t r = c.nodes[i].ref[k];
            if (REF_KIND(r) == KIND_TRIS) {
                leaves++;
                blocks += (REF_COUNT(r) + LANES - 1) / LANES;
            } else if (REF_KIND(r) == KIND_OTHERS) {
                others += REF_COUNT(r);
            }
        }
    if (blocks >= MAX_FIRST || others >= MAX_FIRST)
        goto done;
    bvh->nodes = aligned(sizeof *bvh->nodes * (size_t)c.count);
    bvh->blocks = aligned(sizeof *bvh->blocks * (size_t)blocks);
    bvh->others = malloc(sizeof *bvh->others * (size_t)others + 1);
    bvh->cones = malloc(sizeof *bvh->cones * (size_t)cones + 1);
    leaf_node = malloc(sizeof *leaf_node * (size_t)leaves + 1);
    leaf_slot = malloc(sizeof *leaf_slot * (size_t)leaves + 1);
    leaf_start = malloc(sizeof *leaf_start * (size_t)leaves + 1);
    if (!bvh->nodes || !bvh->blocks || !bvh->others || !bvh->cones || !leaf_node || !leaf_slot || !leaf_start)
        goto done;
    memcpy(bvh->nodes, c.nodes, sizeof *bvh->nodes * (size_t)c.count);
    bvh->node_count = c.count;
    bvh->block_count = blocks;
    bvh->depth = c.depth;
    /* references to their blocks and keys; pad keeps a triangle leaf's item count until filled */
    int l = 0, blk = 0, oth = 0;
    for (int i = 0; i < c.count; i++)
        for (int k = 0; k < WIDTH; k++) {
            RfBvhNode *nd = &bvh->nodes[i];
            uint32_t r = nd->ref[k];
            int start = (int)nd->pad[k], count = REF_COUNT(r);
            nd->pad[k] = 0;
            if (REF_KIND(r) == KIND_TRIS) {
                int nb = (count + LANES - 1) / LANES;
                leaf_node[l] = i;
                leaf_slot[l] = k;
                leaf_start[l++] = start;
                nd->ref[k] = REF_LEAF(KIND_TRIS, blk, nb);
                nd->pad[k] = (uint32_t)count;
                blk += nb;
            } else if (REF_KIND(r) == KIND_OTHERS) {
                for (int q = 0; q < count; q++) {
                    const Payload *pl = &payload[-1 - b.ids[start + q]];
                    RfBvhOther *o = &bvh->others[oth + q];
                    memset(o, 0, sizeof *o);
                    o->key = pl->key;
                    o->user = pl->user;
                    o->kind = pl->kind;
                    if (pl->kind == RF_BVH_SPHERE) {
                        o->u.sphere = pl->u.sphere;
                    } else if (pl->kind == RF_BVH_CONE) { /* its cone and frame: asked again */
                        RfBvhItem it;
                        desc->describe(desc->ctx, -1 - b.ids[start + q], &it);
                        o->u.cone = bvh->cone_count;
                        bvh->cones[bvh->cone_count].cone = it.cone;
                        bvh->cones[bvh->cone_count++].frame = it.frame;
                    }
                }
                nd->ref[k] = REF_LEAF(KIND_OTHERS, oth, count);
                oth += count;
            }
        }
    bvh->other_count = others;
    FillJob fj = {bvh, b.ids, payload, leaf_node, leaf_slot, leaf_start, leaves};
    if (rf_parallel_for(CHUNKS, threads, fill_blocks, NULL, &fj) != RF_OK || !unit_normals(bvh))
        goto done;
    for (int i = 0; i < leaves; i++)
        bvh->nodes[leaf_node[i]].pad[leaf_slot[i]] = 0;
    bvh->tri_count = 0;
    for (int i = 0; i < n; i++)
        bvh->tri_count += b.ids[i] >= 0;
    st = RF_OK;
done:
    free(b.refs);
    free(b.ids);
    free(top.nodes);
    for (int i = 0; i < tl.count; i++)
        free(tl.tasks[i].buf.nodes);
    free(tl.tasks);
    free(order);
    free(all);
    free(c.nodes);
    free(leaf_node);
    free(leaf_slot);
    free(leaf_start);
    free(payload);
    if (st != RF_OK) {
        rf_bvh_free(bvh);
        bvh->scalar = desc->scalar;
    }
    return st;
}

void rf_bvh_free(RfBvh *bvh)
{
    free(bvh->nodes);
    free(bvh->blocks);
    free(bvh->others);
    free(bvh->cones);
    free(bvh->normals);
    memset(bvh, 0, sizeof *bvh);
}

size_t rf_bvh_bytes(const RfBvh *bvh)
{
    return sizeof *bvh->nodes * (size_t)bvh->node_count + sizeof *bvh->blocks * (size_t)bvh->block_count +
           sizeof *bvh->others * (size_t)bvh->other_count + sizeof *bvh->cones * (size_t)bvh->cone_count +
           (bvh->normals ? sizeof *bvh->normals * (size_t)bvh->block_count * LANES : 0);
}

