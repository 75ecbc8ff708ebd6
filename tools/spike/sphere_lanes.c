/* Spike (issue 11): what SIMD across rays buys the exact sphere test. rf_sphere_roots (the
 * tracer's scalar kernel, one ray at a time) against the same operations in the four double
 * lanes of AVX2, one ray per lane, on rays from whitted's eye into its mirror sphere's box; every
 * output (roots, sqrt(D/4), v) is compared bit for bit. Not part of the build:
 *
 *   make && cc -std=c99 -O2 -march=native -mno-avx512f -ffp-contract=off -Iinclude \
 *      tools/spike/sphere_lanes.c build/librefray.a -lm -o /tmp/sphere_lanes && /tmp/sphere_lanes
 */
#define _POSIX_C_SOURCE 200809L
#include <immintrin.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "refray/intersect.h"
#include "refray/vec.h"

typedef struct { double ox[4], oy[4], oz[4], dx[4], dy[4], dz[4]; } Ray4;
typedef struct { double t0[4], t1[4], sq[4], vx[4], vy[4], vz[4]; int ok[4]; } Roots4;

/* one TwoSum step of dot_minus_square (intersect.c) per lane */
static inline void add_square4(__m256d h, double sgn, __m256d *s, __m256d *e)
{
    __m256d g = _mm256_set1_pd(sgn), hh = _mm256_mul_pd(h, h);
    __m256d p = _mm256_mul_pd(g, hh);
    __m256d pe = _mm256_mul_pd(g, _mm256_fmsub_pd(h, h, hh));
    __m256d q = _mm256_add_pd(*s, p), z = _mm256_sub_pd(q, *s);
    *e = _mm256_add_pd(*e, _mm256_add_pd(_mm256_add_pd(_mm256_sub_pd(*s, _mm256_sub_pd(q, z)), _mm256_sub_pd(p, z)), pe));
    *s = q;
}

/* rf_sphere_roots on four rays: the same operations in the same order per lane. Lanes with a
 * rare case (q = 0, a = 0, dq = 0, a NaN root) are handed to the scalar kernel. */
static void sphere_roots4(const Ray4 *R, RfSphere s, const RfRay *rays, Roots4 *out)
{
    __m256d dx = _mm256_loadu_pd(R->dx), dy = _mm256_loadu_pd(R->dy), dz = _mm256_loadu_pd(R->dz);
    __m256d fx = _mm256_sub_pd(_mm256_loadu_pd(R->ox), _mm256_set1_pd(s.center.x));
    __m256d fy = _mm256_sub_pd(_mm256_loadu_pd(R->oy), _mm256_set1_pd(s.center.y));
    __m256d fz = _mm256_sub_pd(_mm256_loadu_pd(R->oz), _mm256_set1_pd(s.center.z));
    __m256d a = _mm256_add_pd(_mm256_add_pd(_mm256_mul_pd(dx, dx), _mm256_mul_pd(dy, dy)), _mm256_mul_pd(dz, dz));
    __m256d bh = _mm256_add_pd(_mm256_add_pd(_mm256_mul_pd(dx, fx), _mm256_mul_pd(dy, fy)), _mm256_mul_pd(dz, fz));
    __m256d k = _mm256_div_pd(bh, a);
    __m256d vx = _mm256_sub_pd(fx, _mm256_mul_pd(dx, k)), vy = _mm256_sub_pd(fy, _mm256_mul_pd(dy, k)),
            vz = _mm256_sub_pd(fz, _mm256_mul_pd(dz, k));
    __m256d lv = _mm256_sqrt_pd(_mm256_add_pd(_mm256_add_pd(_mm256_mul_pd(vx, vx), _mm256_mul_pd(vy, vy)),
                                              _mm256_mul_pd(vz, vz)));
    __m256d r = _mm256_set1_pd(s.radius);
    __m256d dq = _mm256_mul_pd(a, _mm256_mul_pd(_mm256_sub_pd(r, lv), _mm256_add_pd(r, lv)));
    int real = _mm256_movemask_pd(_mm256_cmp_pd(dq, _mm256_setzero_pd(), _CMP_GE_OQ));
    for (int l = 0; l < 4; l++)
        out->ok[l] = (real >> l) & 1;
    if (!real)
        return;
    __m256d se = _mm256_setzero_pd(), ee = _mm256_setzero_pd();
    add_square4(fx, 1.0, &se, &ee);
    add_square4(fy, 1.0, &se, &ee);
    add_square4(fz, 1.0, &se, &ee);
    add_square4(r, -1.0, &se, &ee);
    __m256d c = _mm256_add_pd(se, ee);
    __m256d sq = _mm256_sqrt_pd(dq);
    __m256d sign = _mm256_set1_pd(-0.0);
    __m256d q = _mm256_xor_pd(_mm256_add_pd(bh, _mm256_or_pd(_mm256_andnot_pd(sign, sq), _mm256_and_pd(sign, bh))), sign);
    __m256d r1 = _mm256_div_pd(q, a), r2 = _mm256_div_pd(c, q);
    __m256d lo = _mm256_blendv_pd(r2, r1, _mm256_cmp_pd(r1, r2, _CMP_LT_OQ));
    __m256d hi = _mm256_blendv_pd(r2, r1, _mm256_cmp_pd(r1, r2, _CMP_GT_OQ));
    int rare = _mm256_movemask_pd(_mm256_or_pd(_mm256_or_pd(_mm256_cmp_pd(q, _mm256_setzero_pd(), _CMP_EQ_OQ),
                                                            _mm256_cmp_pd(a, _mm256_setzero_pd(), _CMP_EQ_OQ)),
                                               _mm256_or_pd(_mm256_cmp_pd(dq, _mm256_setzero_pd(), _CMP_EQ_OQ),
                                                            _mm256_cmp_pd(r1, r2, _CMP_UNORD_Q)))) & real;
    _mm256_storeu_pd(out->t0, lo);
    _mm256_storeu_pd(out->t1, hi);
    _mm256_storeu_pd(out->sq, sq);
    _mm256_storeu_pd(out->vx, vx);
    _mm256_storeu_pd(out->vy, vy);
    _mm256_storeu_pd(out->vz, vz);
    while (rare) {
        int l = __builtin_ctz((unsigned)rare);
        rare &= rare - 1;
        RfSphereRoots one;
        out->ok[l] = rf_sphere_roots(&rays[l], &s, &one);
        out->t0[l] = one.t[0], out->t1[l] = one.t[1], out->sq[l] = one.sq;
        out->vx[l] = one.v.x, out->vy[l] = one.v.y, out->vz[l] = one.v.z;
    }
}

static double now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static int same(double a, double b) { return memcmp(&a, &b, sizeof a) == 0; }

int main(void)
{
    /* whitted.rf's eye (0 2.6 7) and mirror sphere (centre 0.1 1 -1.3, radius 1); the rays aim at
     * random points of the sphere's box, as the rays the BVH hands to the sphere test do (those
     * that enter its box: ~80 % of whitted's have real roots, docs/performance.md) */
    const int N = 1 << 21;
    RfVec3 eye = rf_vec3(0, 2.6, 7);
    RfRay *rays = malloc((size_t)N * sizeof *rays);
    Ray4 *r4 = malloc((size_t)N / 4 * sizeof *r4);
    unsigned long long x = 88172645463325252ULL;
    for (int i = 0; i < N; i++) {
        double c[3];
        for (int k = 0; k < 3; k++) {
            x ^= x << 13, x ^= x >> 7, x ^= x << 17;
            c[k] = 2.0 * (double)(x >> 11) * 0x1p-53 - 1.0;
        }
        RfVec3 d = rf_vec3_normalize(rf_vec3_sub(rf_vec3(0.1 + c[0], 1 + c[1], -1.3 + c[2]), eye));
        rays[i] = rf_ray(eye, d);
        Ray4 *q = &r4[i / 4];
        int l = i % 4;
        q->ox[l] = eye.x, q->oy[l] = eye.y, q->oz[l] = eye.z, q->dx[l] = d.x, q->dy[l] = d.y, q->dz[l] = d.z;
    }
    RfSphere sph = {rf_vec3(0.1, 1, -1.3), 1.0};
    RfSphereRoots *ref = malloc((size_t)N * sizeof *ref);
    int *ok = malloc((size_t)N * sizeof *ok);
    Roots4 *got = malloc((size_t)N / 4 * sizeof *got);
    double best1 = 1e9, best4 = 1e9;
    for (int rep = 0; rep < 7; rep++) {
        double t0 = now();
        for (int i = 0; i < N; i++)
            ok[i] = rf_sphere_roots(&rays[i], &sph, &ref[i]);
        double t1 = now();
        for (int i = 0; i < N / 4; i++)
            sphere_roots4(&r4[i], sph, &rays[4 * i], &got[i]);
        double t2 = now();
        best1 = t1 - t0 < best1 ? t1 - t0 : best1;
        best4 = t2 - t1 < best4 ? t2 - t1 : best4;
    }
    long hits = 0, bad = 0;
    for (int i = 0; i < N; i++) {
        const Roots4 *g = &got[i / 4];
        int l = i % 4;
        hits += ok[i];
        if (g->ok[l] != ok[i])
            bad++;
        else if (ok[i] && !(same(g->t0[l], ref[i].t[0]) && same(g->t1[l], ref[i].t[1]) && same(g->sq[l], ref[i].sq) &&
                            same(g->vx[l], ref[i].v.x) && same(g->vy[l], ref[i].v.y) && same(g->vz[l], ref[i].v.z)))
            bad++;
    }
    printf("%d rays, %ld with real roots; scalar %.2f ns/ray, 4 lanes %.2f ns/ray: %.2fx; %ld differ\n", N, hits,
           1e9 * best1 / N, 1e9 * best4 / N, best1 / best4, bad);
    return bad != 0;
}
