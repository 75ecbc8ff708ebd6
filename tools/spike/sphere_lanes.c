/* Spike (issue 11, sixth round): what SIMD across rays buys the exact sphere test.
 * rf_sphere_roots (the tracer's scalar kernel, one ray at a time) against rf_sphere_roots4 (the
 * same operations in the four double lanes of AVX2, one ray per lane; the library's since the
 * twelfth round, when camera rays went into groups) on rays from whitted's eye into its mirror
 * sphere's box; every output (roots, sqrt(D/4), v, a) is compared bit for bit. Not part of the
 * build:
 *
 *   make && cc -std=c99 -O2 -march=native -mno-avx512f -ffp-contract=off -Iinclude \
 *      tools/spike/sphere_lanes.c build/librefray.a -lm -o /tmp/sphere_lanes && /tmp/sphere_lanes
 */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "refray/intersect.h"
#include "refray/vec.h"

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
    RfRay4 *r4 = malloc((size_t)N / 4 * sizeof *r4);
    unsigned long long x = 88172645463325252ULL;
    for (int i = 0; i < N; i++) {
        double c[3];
        for (int k = 0; k < 3; k++) {
            x ^= x << 13, x ^= x >> 7, x ^= x << 17;
            c[k] = 2.0 * (double)(x >> 11) * 0x1p-53 - 1.0;
        }
        RfVec3 d = rf_vec3_normalize(rf_vec3_sub(rf_vec3(0.1 + c[0], 1 + c[1], -1.3 + c[2]), eye));
        rays[i] = rf_ray(eye, d);
        rf_ray4_set(&r4[i / 4], i % 4, &rays[i]);
    }
    RfSphere sph = {rf_vec3(0.1, 1, -1.3), 1.0};
    RfSphereRoots *ref = malloc((size_t)N * sizeof *ref);
    int *ok = malloc((size_t)N * sizeof *ok);
    RfSphereRoots *got = malloc((size_t)N * sizeof *got);
    unsigned *got_ok = malloc((size_t)N / 4 * sizeof *got_ok);
    double best1 = 1e9, best4 = 1e9;
    for (int rep = 0; rep < 7; rep++) {
        double t0 = now();
        for (int i = 0; i < N; i++)
            ok[i] = rf_sphere_roots(&rays[i], &sph, &ref[i]);
        double t1 = now();
        for (int i = 0; i < N / 4; i++)
            got_ok[i] = rf_sphere_roots4(&r4[i], &sph, &got[4 * i]);
        double t2 = now();
        best1 = t1 - t0 < best1 ? t1 - t0 : best1;
        best4 = t2 - t1 < best4 ? t2 - t1 : best4;
    }
    long hits = 0, bad = 0;
    for (int i = 0; i < N; i++) {
        const RfSphereRoots *g = &got[i];
        hits += ok[i];
        if ((int)((got_ok[i / 4] >> (i % 4)) & 1) != ok[i])
            bad++;
        else if (ok[i] && !(same(g->t[0], ref[i].t[0]) && same(g->t[1], ref[i].t[1]) && same(g->sq, ref[i].sq) &&
                            same(g->a, ref[i].a) && same(g->v.x, ref[i].v.x) && same(g->v.y, ref[i].v.y) &&
                            same(g->v.z, ref[i].v.z)))
            bad++;
    }
    printf("%d rays, %ld with real roots; scalar %.2f ns/ray, 4 lanes %.2f ns/ray: %.2fx; %ld differ\n", N, hits,
           1e9 * best1 / N, 1e9 * best4 / N, best1 / best4, bad);
    return bad != 0;
}
