/* The BVH's memory layout and float rounding, shared by its build (bvh_build.c) and its
 * traversal (bvh_trace.c); internal to src/geom. docs/performance.md draws it. */
#ifndef RF_GEOM_BVH_LAYOUT_H
#define RF_GEOM_BVH_LAYOUT_H

#include <math.h>
#include <stdint.h>
#include <string.h>

#include "refray/bvh.h"

/* A child reference: the kind in the top 2 bits; an inner node's index below; a leaf's count - 1
 * (triangle blocks or items, at most 16) in the next 4 bits and its first block or item in the
 * low 26. 0 is an empty slot. */
enum { KIND_EMPTY = 0, KIND_INNER = 1, KIND_TRIS = 2, KIND_OTHERS = 3 };
#define REF_INNER(index) ((1u << 30) | (uint32_t)(index))
#define REF_LEAF(kind, first, count) (((uint32_t)(kind) << 30) | ((uint32_t)((count) - 1) << 26) | (uint32_t)(first))
#define REF_KIND(r) ((r) >> 30)
#define REF_INDEX(r) ((int)((r) & 0x3fffffffu))
#define REF_FIRST(r) ((int)((r) & 0x3ffffffu))
#define REF_COUNT(r) ((int)(((r) >> 26) & 15u) + 1)
#define MAX_NODES (1 << 30)
#define MAX_FIRST (1 << 26)

#define LANES 4 /* triangles per block */
#define USER_BITS 0x3fffffffu
#define WIDTH 8 /* children per node */

struct RfBvhNode {
    float b[6][8];     /* [2 axis]: lo, [2 axis + 1]: hi of each child box; empty: +inf, -inf */
    uint32_t ref[8];   /* REF_* */
    uint32_t pad[8];   /* 256 bytes: a node is 4 whole cache lines */
};

/* Four triangles: the float copy the filter reads, then the double vertices the watertight test
 * reads for the lanes the filter keeps, in the same 512 bytes. */
struct RfBvhTriBlock {
    float v[3][3][4];  /* [vertex][axis][lane], each coordinate rounded to nearest */
    uint64_t key[4];   /* the caller's key; 0: an empty lane */
    uint32_t user[4];  /* RF_BVH_SEE_* in the top 2 bits, the caller's 30 below */
    RfTriangle tri[4];
    uint32_t pad2[8];
};

/* An item of an "others" leaf: a sphere or a cone (tested inline) or an item of the caller (its
 * callback). */
struct RfBvhOther {
    uint64_t key;
    uint32_t user; /* RF_BVH_SEE_* in the top 2 bits, the caller's 30 below */
    int kind;      /* RF_BVH_SPHERE, RF_BVH_CONE or RF_BVH_OTHER */
    union {
        RfSphere sphere;
        int cone; /* its index in RfBvh.cones */
    } u;
};

/* A float at least (at most) x, without branches: x rounded to nearest and moved by
 * |f| 2^-23 + 2^-126 (FLT_MIN, not a subnormal: those cost microcode assists on some CPUs),
 * more than that rounding can have moved it (for |x| up to FLT_MAX;
 * beyond, +-inf): the outward rounding of boxes and of the ray's slab constants. */
static inline float rf__widen_up(double x)
{
    float f = (float)x;
    return f + (fabsf(f) * 0x1p-23f + 0x1p-126f);
}
static inline float rf__widen_down(double x)
{
    float f = (float)x;
    return f - (fabsf(f) * 0x1p-23f + 0x1p-126f);
}

#endif
