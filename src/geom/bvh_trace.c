/* The BVH's traversal (refray/bvh.h): the ray's conservative float set-up, the 8-wide node
 * test (AVX or scalar), the triangle filter (SSE or scalar), the double-precision decision and
 * the ordered stack walk shared by nearest-hit and occlusion queries. */
#include <float.h>
#include <math.h>
#include <stdint.h>
#include <string.h>

#include "bvh_layout.h"

#if defined(__AVX__)
#include <immintrin.h>
#define RF_BVH_AVX 1
#endif
#if defined(__SSE2__)
#include <emmintrin.h>
#define RF_BVH_SSE 1
#endif

#define STACK (WIDTH * 64) /* (children - 1) per level, depth < 64 */

static inline float fmaxf_(float a, float b) { return b > a ? b : a; }

/* float unit roundoff */
#define U32 0x1p-24

/* The node test's rows (RfBvhRay.rows) by the direction's sign bits (bit a: dir[a] < 0, the
 * near plane is then the box's hi side): axis a's near plane is row 2a or 2a + 1, its far plane
 * the other, as byte offsets in RfBvhNode.b. A table the ray points into: no arithmetic and no
 * copy per query. */
#define ROW(i) ((i) * sizeof(((const RfBvhNode *)0)->b[0]))
static const size_t row_table[8][6] = {
    {ROW(0), ROW(2), ROW(4), ROW(1), ROW(3), ROW(5)}, {ROW(1), ROW(2), ROW(4), ROW(0), ROW(3), ROW(5)},
    {ROW(0), ROW(3), ROW(4), ROW(1), ROW(2), ROW(5)}, {ROW(1), ROW(3), ROW(4), ROW(0), ROW(2), ROW(5)},
    {ROW(0), ROW(2), ROW(5), ROW(1), ROW(3), ROW(4)}, {ROW(1), ROW(2), ROW(5), ROW(0), ROW(3), ROW(4)},
    {ROW(0), ROW(3), ROW(5), ROW(1), ROW(2), ROW(4)}, {ROW(1), ROW(3), ROW(5), ROW(0), ROW(2), ROW(4)}};
#undef ROW

void rf_bvh_ray_init(const RfBvh *bvh, const RfRay *rp, RfBvhRay *r)
{
    (void)bvh;
    /* the ray read in 8-byte pieces (rf_ray_read): its caller has just stored it, and a wider
     * load across two of its stores would wait for them to retire (this load was a quarter of
     * the set-up's time) */
    const RfRay ray = rf_ray_read(rp);
    r->ray = ray;
    r->tri_ready = 0;
    /* Slab distances (plane - origin) * inv, rounded toward "hit" (docs/performance.md): the
     * near plane's origin moved so the difference can only shrink, the far plane's so it can
     * only grow (rf__widen_up/down: past the rounding of o to float), and 1/dir shrunk / grown by
     * 8 ulps, which covers the roundings of the conversion, the difference and the product. A
     * zero component has inv = inf: the near factor is clamped to 2^127 (still a lower bound) so
     * that a finite difference stays finite; the far factor may be inf. No branches: they would
     * be guesses per ray. The AVX path does the three axes in lanes, each lane the scalar
     * path's operations in its order (the same floats). */
#if RF_BVH_AVX
    const __m128 sign = _mm_set1_ps(-0.0f);
    __m256d dd = _mm256_set_pd(1.0, ray.dir.z, ray.dir.y, ray.dir.x);
    __m128 f = _mm256_cvtpd_ps(_mm256_set_pd(0.0, ray.origin.z, ray.origin.y, ray.origin.x));
    __m128 fi = _mm256_cvtpd_ps(_mm256_div_pd(_mm256_set1_pd(1.0), dd)); /* 1/d: +-inf for +-0 */
    __m128 neg = _mm_castsi128_ps(_mm_srai_epi32(_mm_castps_si128(_mm256_cvtpd_ps(dd)), 31)); /* signbit(d) */
    __m128 w = _mm_add_ps(_mm_mul_ps(_mm_andnot_ps(sign, f), _mm_set1_ps(0x1p-23f)), _mm_set1_ps(0x1p-126f));
    __m128 up = _mm_add_ps(f, w), down = _mm_sub_ps(f, w);
    _mm_storeu_ps(r->org[0], _mm_blendv_ps(up, down, neg));
    _mm_storeu_ps(r->org[1], _mm_blendv_ps(down, up, neg));
    __m128 near = _mm_mul_ps(fi, _mm_set1_ps(1.0f - 0x1p-21f)), far = _mm_mul_ps(fi, _mm_set1_ps(1.0f + 0x1p-21f));
    __m128 clamp = _mm_or_ps(_mm_set1_ps(0x1p127f), _mm_and_ps(neg, sign));
    _mm_storeu_ps(r->inv[0], _mm_blendv_ps(clamp, near, _mm_cmple_ps(_mm_andnot_ps(sign, near), _mm_set1_ps(0x1p127f))));
    _mm_storeu_ps(r->inv[1], far);
    r->rows = row_table[_mm_movemask_ps(neg) & 7];
#else
    const double o[3] = {ray.origin.x, ray.origin.y, ray.origin.z};
    const double d[3] = {ray.dir.x, ray.dir.y, ray.dir.z};
    int signs = 0;
    for (int a = 0; a < 3; a++) {
        int neg = signbit(d[a]) != 0; /* the sign of 1/d, without waiting for the division */
        float up = rf__widen_up(o[a]), down = rf__widen_down(o[a]);
        signs |= neg << a;
        r->org[0][a] = neg ? down : up;
        r->org[1][a] = neg ? up : down;
        float fi = (float)(1.0 / d[a]);
        float near = fi * (1.0f - 0x1p-21f), far = fi * (1.0f + 0x1p-21f);
        r->inv[0][a] = fabsf(near) <= 0x1p127f ? near : neg ? -0x1p127f : 0x1p127f;
        r->inv[1][a] = far;
    }
    r->rows = row_table[signs];
#endif
}

/* The triangle tests' set-up, made when the first triangle block is reached (a ray that meets
 * only boxes, spheres or nothing does not pay for it): the watertight shear and the filter.
 * The filter (docs/performance.md): every ray-space coordinate computed in float lies within
 * delta = 9 u (vmax + |o|max) of the double test's, so each edge function lies within
 * B = 4.2 m delta + 4.2 u m^2 + 2.1 delta^2 of the exact one whose sign the double test takes
 * (m: the largest float coordinate of the triangle). The slack over 4, 4, 2 covers the rounding
 * of B itself; 2^-140 and 2^-120 cover underflow. */
static void tri_setup(const RfBvh *bvh, RfBvhRay *r)
{
    const double o[3] = {r->ray.origin.x, r->ray.origin.y, r->ray.origin.z};
    rf_watertight_ray(&r->ray, &r->wr);
    r->wr.scalar = bvh->scalar; /* the scalar kernels throughout: the tests compare the two */
    r->fo[0] = (float)o[r->wr.kx];
    r->fo[1] = (float)o[r->wr.ky];
    r->fo[2] = (float)o[r->wr.kz];
    r->fsx = (float)r->wr.sx;
    r->fsy = (float)r->wr.sy;
    double omax = fabs(o[0]);
    omax = fabs(o[1]) > omax ? fabs(o[1]) : omax;
    omax = fabs(o[2]) > omax ? fabs(o[2]) : omax;
    double R = bvh->vmax + omax;
    r->filter = R <= 0x1p60;
    double delta = (9.0 * U32 * R + 0x1p-140) * (1.0 + 0x1p-20);
    r->k1 = rf__widen_up(4.2 * delta);
    r->k2 = rf__widen_up(4.2 * U32);
    r->k3 = rf__widen_up(2.1 * delta * delta + 0x1p-120);
    r->tri_ready = 1;
}

/* ---- traversal: node and triangle kernels ------------------------------------------------ */

/* Row `off` (a byte offset, RfBvhRay.rows) of a node's boxes. */
static inline const float *row_scalar(const RfBvhNode *n, size_t off)
{
    return (const float *)(const void *)((const char *)n->b + off);
}

/* The children a ray enters within [tmin, tmax]: bit k of the result; tn[k] their entry
 * distances. NaN (0 * inf: a parallel ray with its origin on a slab plane) is the first
 * operand of max/min and drops out, which keeps the box (conservative). */
static inline unsigned node_test_scalar(const RfBvhNode *n, const RfBvhRay *r, float tmin, float tmax, float *tn)
{
    unsigned mask = 0;
    for (int k = 0; k < WIDTH; k++) {
        float t0 = tmin, t1 = tmax;
        for (int a = 0; a < 3; a++) {
            float e = (row_scalar(n, r->rows[a])[k] - r->org[0][a]) * r->inv[0][a];
            float x = (row_scalar(n, r->rows[3 + a])[k] - r->org[1][a]) * r->inv[1][a];
            t0 = e > t0 ? e : t0;
            t1 = x < t1 ? x : t1;
        }
        tn[k] = t0;
        mask |= (unsigned)(t0 <= t1) << k;
    }
    return mask;
}

#if RF_BVH_AVX
static inline __m256 row(const RfBvhNode *n, size_t off)
{
    return _mm256_load_ps(row_scalar(n, off));
}

/* (row - org[s][a]) * inv[s][a] for the near (s = 0) or far (s = 1) plane of axis a. The ray's
 * slab constants are broadcast from the RfBvhRay at each test: twelve ymm registers of them do
 * not stay in registers beside the test's own, and copies made once per query were spilled, a
 * broadcast and a store per constant per query on top of the same load per test. */
static inline __m256 slab(const RfBvhNode *n, const RfBvhRay *r, int s, int a)
{
    return _mm256_mul_ps(_mm256_sub_ps(row(n, r->rows[3 * s + a]), _mm256_broadcast_ss(&r->org[s][a])),
                         _mm256_broadcast_ss(&r->inv[s][a]));
}

static inline unsigned node_test_avx(const RfBvhNode *n, const RfBvhRay *r, __m256 tmin, __m256 tmax, float *tn)
{
    /* e > t0 ? e : t0 with e first: a NaN e (0 * inf) drops out */
    __m256 e0 = slab(n, r, 0, 0), x0 = slab(n, r, 1, 0);
    __m256 e1 = slab(n, r, 0, 1), x1 = slab(n, r, 1, 1);
    __m256 e2 = slab(n, r, 0, 2), x2 = slab(n, r, 1, 2);
    __m256 t0 = _mm256_max_ps(e2, _mm256_max_ps(e1, _mm256_max_ps(e0, tmin)));
    __m256 t1 = _mm256_min_ps(x2, _mm256_min_ps(x1, _mm256_min_ps(x0, tmax)));
    _mm256_storeu_ps(tn, t0);
    return (unsigned)_mm256_movemask_ps(_mm256_cmp_ps(t0, t1, _CMP_LE_OQ));
}
#endif

/* node_test_avx or, with the scalar kernels, node_test_scalar */
static RF_INLINE_ALWAYS unsigned node_test(const RfBvh *bvh, const RfBvhNode *n, const RfBvhRay *r, float tmin,
                                           float tmax, float *tn)
{
#if RF_BVH_AVX
    if (!bvh->scalar)
        return node_test_avx(n, r, _mm256_set1_ps(tmin), _mm256_set1_ps(tmax), tn);
#else
    (void)bvh;
#endif
    return node_test_scalar(n, r, tmin, tmax, tn);
}

/* The lanes of a triangle block that the float edge test cannot rule out (bit k: lane k). */
static inline unsigned filter_scalar(const RfBvhTriBlock *blk, const RfBvhRay *r)
{
    const int kx = r->wr.kx, ky = r->wr.ky, kz = r->wr.kz;
    unsigned keep = 0;
    for (int k = 0; k < LANES; k++) {
        float x[3], y[3];
        for (int v = 0; v < 3; v++) {
            float z = blk->v[v][kz][k] - r->fo[2];
            x[v] = (blk->v[v][kx][k] - r->fo[0]) - r->fsx * z;
            y[v] = (blk->v[v][ky][k] - r->fo[1]) - r->fsy * z;
        }
        float u = x[2] * y[1] - y[2] * x[1];
        float v = x[0] * y[2] - y[0] * x[2];
        float w = x[1] * y[0] - y[1] * x[0];
        float m = 0.0f;
        for (int q = 0; q < 3; q++) {
            m = fmaxf_(m, fabsf(x[q]));
            m = fmaxf_(m, fabsf(y[q]));
        }
        float bnd = m * (r->k1 + r->k2 * m) + r->k3, nb = -bnd;
        int neg = u < nb || v < nb || w < nb, pos = u > bnd || v > bnd || w > bnd;
        keep |= (unsigned)!(neg && pos) << k;
    }
    return keep;
}

#if RF_BVH_SSE
static inline unsigned filter_sse(const RfBvhTriBlock *blk, const RfBvhRay *r)
{
    const int kx = r->wr.kx, ky = r->wr.ky, kz = r->wr.kz;
    const __m128 ox = _mm_set1_ps(r->fo[0]), oy = _mm_set1_ps(r->fo[1]), oz = _mm_set1_ps(r->fo[2]);
    const __m128 sx = _mm_set1_ps(r->fsx), sy = _mm_set1_ps(r->fsy);
    const __m128 sign = _mm_set1_ps(-0.0f);
#define RF_SHEAR(vi, X, Y)                                                                      \
    __m128 X, Y;                                                                               \
    {                                                                                          \
        __m128 z_ = _mm_sub_ps(_mm_load_ps(blk->v[vi][kz]), oz);                                \
        X = _mm_sub_ps(_mm_sub_ps(_mm_load_ps(blk->v[vi][kx]), ox), _mm_mul_ps(sx, z_));       \
        Y = _mm_sub_ps(_mm_sub_ps(_mm_load_ps(blk->v[vi][ky]), oy), _mm_mul_ps(sy, z_));       \
    }
    RF_SHEAR(0, ax, ay)
    RF_SHEAR(1, bx, by)
    RF_SHEAR(2, cx, cy)
#undef RF_SHEAR
    /* the same operations, in the same order, as filter_scalar */
    __m128 m = _mm_max_ps(_mm_andnot_ps(sign, ax), _mm_setzero_ps());
    m = _mm_max_ps(_mm_andnot_ps(sign, ay), m);
    m = _mm_max_ps(_mm_andnot_ps(sign, bx), m);
    m = _mm_max_ps(_mm_andnot_ps(sign, by), m);
    m = _mm_max_ps(_mm_andnot_ps(sign, cx), m);
    m = _mm_max_ps(_mm_andnot_ps(sign, cy), m);
    __m128 u = _mm_sub_ps(_mm_mul_ps(cx, by), _mm_mul_ps(cy, bx));
    __m128 v = _mm_sub_ps(_mm_mul_ps(ax, cy), _mm_mul_ps(ay, cx));
    __m128 w = _mm_sub_ps(_mm_mul_ps(bx, ay), _mm_mul_ps(by, ax));
    __m128 bnd = _mm_add_ps(_mm_mul_ps(m, _mm_add_ps(_mm_set1_ps(r->k1), _mm_mul_ps(_mm_set1_ps(r->k2), m))),
                            _mm_set1_ps(r->k3));
    __m128 nb = _mm_xor_ps(bnd, sign);
    __m128 neg = _mm_or_ps(_mm_or_ps(_mm_cmplt_ps(u, nb), _mm_cmplt_ps(v, nb)), _mm_cmplt_ps(w, nb));
    __m128 pos = _mm_or_ps(_mm_or_ps(_mm_cmpgt_ps(u, bnd), _mm_cmpgt_ps(v, bnd)), _mm_cmpgt_ps(w, bnd));
    return ~(unsigned)_mm_movemask_ps(_mm_and_ps(neg, pos)) & 0xFu;
}
#endif

static inline unsigned block_filter(const RfBvh *bvh, const RfBvhTriBlock *blk, const RfBvhRay *r)
{
    if (!r->filter)
        return 0xFu;
#if RF_BVH_SSE
    if (!bvh->scalar)
        return filter_sse(blk, r);
#endif
    (void)bvh;
    return filter_scalar(blk, r);
}

/* ---- traversal ------------------------------------------------------------------------------ */

typedef struct {
    float t;      /* entry distance (a lower bound) */
    uint32_t ref;
} Entry;

/* What a traversal looks for: the nearest hit by the (t, key) rule and the items' sides, any
 * hit (occlusion), or the nearest hit with every side seen. One mode argument, not two flags:
 * the traversal keeps no more live values than it did with one. */
enum { NEAREST = 0, ANY = 1, ANY_SIDE = 2 };

/* The leaf's triangles: the float filter, then the double watertight test for what is left.
 * ANY: returns 1 at the first hit in [t_min, best->t). Otherwise improves *best by the
 * (t, key) rule and the triangles' sides (ANY_SIDE: either side counts); returns 1 when it did. */
static RF_INLINE_ALWAYS int leaf_tris(const RfBvh *bvh, uint32_t ref, RfBvhRay *r, double t_min, RfBvhHit *best,
                                      int mode)
{
    int improved = 0;
    if (!r->tri_ready)
        tri_setup(bvh, r);
    const RfBvhTriBlock *blk = &bvh->blocks[REF_FIRST(ref)], *end = blk + REF_COUNT(ref);
    for (; blk < end; blk++) {
        for (int l = 3; l < 8; l++)
            __builtin_prefetch((const char *)blk + 64 * l);
        unsigned keep = block_filter(bvh, blk, r);
        while (keep) {
            int k = __builtin_ctz(keep);
            keep &= keep - 1;
            uint64_t key = blk->key[k];
            double t, e[4];
            if (key == 0 || !rf_watertight_edges(&r->wr, &blk->tri[k], &t, e) || !(t >= t_min))
                continue;
            if (mode == ANY) {
                if (t < best->t) {
                    best->key = key;
                    return 1;
                }
                continue;
            }
            if (!(t < best->t || (t == best->t && key < best->key)))
                continue;
            unsigned sides = blk->user[k] >> 30;
            int sided = mode == NEAREST && sides != RF_BVH_SEE_BOTH;
            const RfVec3 *kept = bvh->normals ? &bvh->normals[(size_t)(blk - bvh->blocks) * LANES + (size_t)k] : NULL;
            RfVec3 nrm = kept ? *kept : rf_vec3(0, 0, 0);
            if (sided) {
                if (!kept)
                    nrm = rf_triangle_unit_normal(&blk->tri[k]);
                int front = rf_vec3_dot(r->ray.dir, nrm) < 0.0;
                if (front != (sides == RF_BVH_SEE_FRONT))
                    continue;
            }
            best->t = t;
            best->key = key;
            best->tri = &blk->tri[k];
            best->sphere = NULL;
            best->cone = NULL;
            memcpy(best->edges, e, sizeof e);
            best->has_normal = sided || kept;
            best->normal = nrm;
            best->user = blk->user[k] & USER_BITS;
            improved = 1;
        }
    }
    return improved;
}

/* A sphere of an "others" leaf, by the rules the tracer applies to every item, from its roots r
 * (rf_sphere_roots): the first root at t >= t_min within the limit (t < lim, or t <= lim for a
 * key below lim_key) whose side the sphere shows (a hidden side passes the ray on to the far
 * root; modes other than NEAREST: either side). Returns the root + 1 (1 near, 2 far) or 0, and
 * its t. */
static inline int sphere_pick(const RfBvhOther *o, const RfSphereRoots *r, const RfRay *ray, double t_min,
                              double lim, uint64_t lim_key, int mode, double *t)
{
    unsigned sides = o->user >> 30;
    double lo = t_min;
    for (int c = 0; c < 2; c++) {
        double tc = r->t[c];
        if (!(tc >= lo && (tc < lim || (tc == lim && o->key < lim_key))))
            continue;
        if (mode == NEAREST && sides != RF_BVH_SEE_BOTH) {
            int front = rf_vec3_dot(ray->dir, rf_sphere_root_normal(r, ray, &o->u.sphere, c)) < 0.0;
            if (front == (sides == RF_BVH_SEE_BACK)) { /* the hidden side: look beyond it */
                lo = rf_next_up(tc);
                continue;
            }
        }
        *t = tc;
        return c + 1;
    }
    return 0;
}

/* A cone of an "others" leaf, by the same rules: the first hit at t >= t_min below lim
 * (inclusive: t <= lim) whose side the cone shows to a NEAREST query (a hidden side passes the
 * ray on). Returns 1 with *h (its normal only when mode is not ANY). */
static inline int cone_hit(const RfBvh *bvh, const RfBvhOther *o, const RfRay *ray, double t_min, double lim,
                           int inclusive, int mode, RfHit *h)
{
    const RfBvhCone *c = &bvh->cones[o->u.cone];
    unsigned sides = o->user >> 30;
    double t_max = inclusive ? rf_next_up(lim) : lim;
    while (rf_intersect_cone_framed(ray, &c->cone, &c->frame, t_min, t_max, mode != ANY, h)) {
        if (mode != NEAREST || sides == RF_BVH_SEE_BOTH ||
            (rf_vec3_dot(ray->dir, h->normal) < 0.0) != (sides == RF_BVH_SEE_BACK))
            return 1;
        t_min = rf_next_up(h->t); /* the hidden side: look beyond it */
    }
    return 0;
}

/* One item of an "others" leaf: its test by its kind, then one rule for a hit: 1 at any hit
 * (ANY: best->key is set), or when it is the new nearest (best takes its details). roots: a
 * sphere's roots when the caller has them (rf_sphere_roots4), NULL to compute them here. */
static RF_INLINE_ALWAYS int other_item(const RfBvh *bvh, const RfBvhOther *o, const RfBvhRay *r, double t_min,
                                       RfBvhHit *best, RfBvhItemFn fn, void *ctx, int mode, const RfSphereRoots *roots)
{
    double t;
    RfSphereRoots own;
    RfHit h;
    int root = 0, hit;
    if (o->kind == RF_BVH_SPHERE) {
        if (!roots) {
            if (!rf_sphere_roots(&r->ray, &o->u.sphere, &own))
                return 0;
            roots = &own;
        }
        root = sphere_pick(o, roots, &r->ray, t_min, best->t, mode == ANY ? 0 : best->key, mode, &t);
        hit = root != 0;
    } else if (o->kind == RF_BVH_CONE) {
        if ((hit = cone_hit(bvh, o, &r->ray, t_min, best->t, mode != ANY && o->key < best->key, mode, &h)))
            t = h.t;
    } else {
        hit = fn(ctx, o->key, r, t_min, best->t, mode != ANY && o->key < best->key, &t);
    }
    if (!hit)
        return 0;
    best->key = o->key;
    if (mode == ANY)
        return 1;
    best->t = t;
    best->tri = NULL;
    best->sphere = o->kind == RF_BVH_SPHERE ? &o->u.sphere : NULL;
    best->cone = o->kind == RF_BVH_CONE ? &bvh->cones[o->u.cone].cone : NULL;
    if (o->kind == RF_BVH_SPHERE) {
        best->far = root == 2;
        best->roots = *roots;
    } else if (o->kind == RF_BVH_CONE) {
        best->normal = h.normal;
    }
    if (o->kind != RF_BVH_OTHER) /* the caller's items keep their details themselves */
        best->user = o->user & USER_BITS;
    return 1;
}

static inline int leaf_others(const RfBvh *bvh, uint32_t ref, const RfBvhRay *r, double t_min,
                              RfBvhHit *best, RfBvhItemFn fn, void *ctx, int mode)
{
    int improved = 0;
    const RfBvhOther *o = &bvh->others[REF_FIRST(ref)], *end = o + REF_COUNT(ref);
    for (; o < end; o++)
        if (other_item(bvh, o, r, t_min, best, fn, ctx, mode, NULL)) {
            if (mode == ANY)
                return 1;
            improved = 1;
        }
    return improved;
}

static inline int traverse(const RfBvh *bvh, RfBvhRay *r, double t_min, RfBvhHit *best,
                           RfBvhItemFn fn, void *ctx, int mode)
{
    if (bvh->node_count == 0)
        return 0;
    Entry stack[STACK];
    int top = 0, found = 0;
    const float tmin = rf__widen_down(t_min);
    float tmax = rf__widen_up(best->t);
    uint32_t cur = REF_INNER(0);
    for (;;) {
        if (REF_KIND(cur) == KIND_INNER) {
            const RfBvhNode *n = &bvh->nodes[REF_INDEX(cur)];
            float tn[WIDTH];
            unsigned mask = node_test(bvh, n, r, tmin, tmax, tn);
            if (mask) {
                int k = __builtin_ctz(mask);
                mask &= mask - 1;
                if (!mask) { /* one child: no order to keep */
                    cur = n->ref[k];
                    continue;
                }
                /* several: onto the stack, sorted there so that the nearest is on top (an
                 * empty slot, entered only through NaN, is a leaf of nothing). An occlusion
                 * query takes them unsorted: any hit ends it wherever it lies, and most shadow
                 * rays find none and visit every entered child anyway (rings -3 % instructions,
                 * mount +0.3 %, docs/performance.md) */
                int base = top;
                for (;;) {
                    Entry e = {tn[k], n->ref[k]};
                    int q = top++;
                    for (; mode != ANY && q > base && stack[q - 1].t < e.t; q--)
                        stack[q] = stack[q - 1];
                    stack[q] = e;
                    if (!mask)
                        break;
                    k = __builtin_ctz(mask);
                    mask &= mask - 1;
                }
                cur = stack[--top].ref;
                continue;
            }
        } else if (REF_KIND(cur) != KIND_EMPTY) {
            int hit = REF_KIND(cur) == KIND_TRIS ? leaf_tris(bvh, cur, r, t_min, best, mode)
                                                 : leaf_others(bvh, cur, r, t_min, best, fn, ctx, mode);
            if (hit) {
                if (mode == ANY)
                    return 1;
                found = 1;
                tmax = rf__widen_up(best->t);
            }
        }
        /* the next subtree that can still hold a hit as near as the best (ties count) */
        for (;;) {
            if (top == 0)
                return found;
            --top;
            if (stack[top].t <= tmax)
                break;
        }
        cur = stack[top].ref;
    }
}

/* ---- four rays in one walk (rf_bvh_nearest4) ------------------------------------------------ */

/* A subtree on the packet's stack: the lanes that entered it and each one's entry distance;
 * near, the least of them, orders the stack. */
typedef struct {
    float t[4];
    float near;
    uint32_t ref;
    unsigned lanes;
} Entry4;

/* An "others" leaf for the lanes of a packet: a sphere's roots for the four rays at once
 * (rf_sphere_roots4), then each lane's rule with its own limit; other items lane by lane. */
static inline unsigned leaf_others4(const RfBvh *bvh, uint32_t ref, const RfBvhRay *r, const RfRay4 *r4,
                                    unsigned lanes, const double *t_min, RfBvhHit *best, RfBvhItemFn fn,
                                    void *const *ctx, int mode)
{
    unsigned improved = 0;
    const RfBvhOther *o = &bvh->others[REF_FIRST(ref)], *end = o + REF_COUNT(ref);
    for (; o < end; o++) {
        RfSphereRoots roots[4];
        unsigned todo = lanes;
        if (o->kind == RF_BVH_SPHERE)
            todo &= rf_sphere_roots4(r4, &o->u.sphere, roots);
        for (; todo; todo &= todo - 1) {
            int l = __builtin_ctz(todo);
            if (other_item(bvh, o, &r[l], t_min[l], &best[l], fn, ctx[l], mode,
                           o->kind == RF_BVH_SPHERE ? &roots[l] : NULL))
                improved |= 1u << l;
        }
    }
    return improved;
}

/* traverse's nearest-hit walk (mode NEAREST or ANY_SIDE) for the lanes in active at once: each
 * node is tested for the lanes that entered it, each lane pruned by its own best; the order of
 * the walk is the packet's, which does not change a lane's result (the (t, key) rule picks one
 * hit whatever the order, and every pruned subtree is one that lane could not have improved). */
static unsigned traverse4(const RfBvh *bvh, RfBvhRay *r, unsigned active, const double *t_min, RfBvhHit *best,
                          RfBvhItemFn fn, void *const *ctx, int mode)
{
    if (bvh->node_count == 0 || !active)
        return 0;
    RfRay4 r4;
    float tmin[4], tmax[4];
    for (int l = 0; l < 4; l++) { /* an idle lane holds a copy of a working one: real numbers */
        int from = (active >> l) & 1 ? l : __builtin_ctz(active);
        rf_ray4_set(&r4, l, &r[from].ray);
        tmin[l] = rf__widen_down(t_min[from]);
        tmax[l] = rf__widen_up(best[from].t);
    }
    Entry4 stack[STACK];
    int top = 0;
    unsigned found = 0, lanes = active;
    uint32_t cur = REF_INNER(0);
    for (;;) {
        if (REF_KIND(cur) == KIND_INNER) {
            const RfBvhNode *n = &bvh->nodes[REF_INDEX(cur)];
            float tn[4][WIDTH];
            unsigned m[4] = {0, 0, 0, 0}, any = 0;
            for (unsigned s = lanes; s; s &= s - 1) {
                int l = __builtin_ctz(s);
                m[l] = node_test(bvh, n, &r[l], tmin[l], tmax[l], tn[l]);
                any |= m[l];
            }
            if (any) {
                /* the entered children onto the stack, the nearest (by its nearest lane) on top */
                int base = top;
                for (; any; any &= any - 1) {
                    int k = __builtin_ctz(any);
                    Entry4 e = {{INFINITY, INFINITY, INFINITY, INFINITY}, INFINITY, n->ref[k], 0};
                    for (unsigned s = lanes; s; s &= s - 1) {
                        int l = __builtin_ctz(s);
                        if ((m[l] >> k) & 1) {
                            e.lanes |= 1u << l;
                            e.t[l] = tn[l][k];
                            e.near = tn[l][k] < e.near ? tn[l][k] : e.near;
                        }
                    }
                    int q = top++;
                    for (; q > base && stack[q - 1].near < e.near; q--)
                        stack[q] = stack[q - 1];
                    stack[q] = e;
                }
                --top;
                cur = stack[top].ref;
                lanes = stack[top].lanes;
                continue;
            }
        } else if (REF_KIND(cur) != KIND_EMPTY) {
            unsigned hit = 0;
            if (REF_KIND(cur) == KIND_TRIS) {
                for (unsigned s = lanes; s; s &= s - 1) {
                    int l = __builtin_ctz(s);
                    hit |= (unsigned)leaf_tris(bvh, cur, &r[l], t_min[l], &best[l], mode) << l;
                }
            } else {
                hit = leaf_others4(bvh, cur, r, &r4, lanes, t_min, best, fn, ctx, mode);
            }
            found |= hit;
            for (; hit; hit &= hit - 1) {
                int l = __builtin_ctz(hit);
                tmax[l] = rf__widen_up(best[l].t);
            }
        }
        /* the next subtree that can still hold a hit as near as some lane's best (ties count) */
        for (;;) {
            if (top == 0)
                return found;
            const Entry4 *e = &stack[--top];
            lanes = 0;
            for (unsigned s = e->lanes; s; s &= s - 1) {
                int l = __builtin_ctz(s);
                lanes |= (unsigned)(e->t[l] <= tmax[l]) << l;
            }
            if (lanes)
                break;
        }
        cur = stack[top].ref;
    }
}

/* Whether the box of child k of node n lies outside one of the cone's planes by more than
 * margin: its corner farthest to the inside of each plane decides. */
static int box_outside_cone(const RfBvhNode *n, int k, RfVec3 apex, const RfVec3 *normals, int count,
                            double margin)
{
    for (int i = 0; i < count; i++) {
        RfVec3 v = normals[i];
        RfVec3 c = rf_vec3(v.x > 0.0 ? n->b[1][k] : n->b[0][k], v.y > 0.0 ? n->b[3][k] : n->b[2][k],
                           v.z > 0.0 ? n->b[5][k] : n->b[4][k]);
        if (rf_vec3_dot(v, rf_vec3_sub(c, apex)) < -margin * rf_vec3_length(v))
            return 1;
    }
    return 0;
}

int rf_bvh_cone_empty(const RfBvh *bvh, RfVec3 apex, const RfVec3 *normals, int count)
{
    if (bvh->node_count == 0)
        return 1;
    for (int i = 0; i < count; i++)
        if (!(rf_vec3_dot(normals[i], normals[i]) > 0.0))
            return 0;
    const RfBvhNode *root = &bvh->nodes[0];
    double s = rf_vec3_max_abs(apex); /* S */
    for (int k = 0; k < WIDTH; k++)
        if (REF_KIND(root->ref[k]) != KIND_EMPTY)
            for (int r = 0; r < 6; r++)
                s = fabsf(root->b[r][k]) > s ? fabsf(root->b[r][k]) : s;
    double margin = 0x1p-13 * s; /* inf for an unbounded box: then nothing is outside */
    uint32_t stack[STACK];
    int top = 0;
    stack[top++] = REF_INNER(0);
    while (top > 0) {
        const RfBvhNode *n = &bvh->nodes[REF_INDEX(stack[--top])];
        for (int k = 0; k < WIDTH; k++) {
            uint32_t ref = n->ref[k];
            if (REF_KIND(ref) == KIND_EMPTY || box_outside_cone(n, k, apex, normals, count, margin))
                continue;
            if (REF_KIND(ref) != KIND_INNER)
                return 0; /* a leaf the cone may reach */
            stack[top++] = ref;
        }
    }
    return 1;
}

int rf_bvh_nearest(const RfBvh *bvh, RfBvhRay *ray, double t_min, RfBvhHit *best,
                   RfBvhItemFn fn, void *ctx)
{
    return traverse(bvh, ray, t_min, best, fn, ctx, NEAREST);
}

int rf_bvh_nearest_any_side(const RfBvh *bvh, RfBvhRay *ray, double t_min, RfBvhHit *best,
                            RfBvhItemFn fn, void *ctx)
{
    return traverse(bvh, ray, t_min, best, fn, ctx, ANY_SIDE);
}

int rf_bvh_occluded(const RfBvh *bvh, RfBvhRay *ray, double t_min, double t_max,
                    RfBvhItemFn fn, void *ctx, uint64_t *key)
{
    RfBvhHit lim; /* an any-hit walk reads t and writes key alone */
    lim.t = t_max;
    lim.key = 0;
    lim.tri = NULL;
    lim.sphere = NULL;
    lim.cone = NULL;
    int hit = traverse(bvh, ray, t_min, &lim, fn, ctx, ANY);
    if (hit && key)
        *key = lim.key;
    return hit;
}

unsigned rf_bvh_nearest4(const RfBvh *bvh, RfBvhRay ray[4], unsigned active, const double t_min[4], RfBvhHit best[4],
                         RfBvhItemFn fn, void *const ctx[4], int any_side)
{
    return traverse4(bvh, ray, active & 0xFu, t_min, best, fn, ctx, any_side ? ANY_SIDE : NEAREST);
}
