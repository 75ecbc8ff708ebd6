/* refray: rays r(t) = e + t d (§3.5.1). The direction need not be unit length unless a
 * function says so; t is measured in units of |d|. */
#ifndef REFRAY_RAY_H
#define REFRAY_RAY_H

#include "refray/vec.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct { RfVec3 origin, dir; } RfRay;

static inline RfRay rf_ray(RfVec3 origin, RfVec3 dir)
{
    RfRay r; r.origin = origin; r.dir = dir; return r;
}
static inline RfVec3 rf_ray_at(RfRay r, double t) { return rf_vec3_add(r.origin, rf_vec3_scale(r.dir, t)); }

/* A hot-path helper the compiler must inline wherever it is used: GCC puts a routine that two
 * callers share out of line (the BVH's leaf tests, shared by the one-ray and the group walk, cost
 * a render 4 % that way). */
#if defined(__GNUC__)
#define RF_INLINE_ALWAYS inline __attribute__((always_inline))
#else
#define RF_INLINE_ALWAYS inline
#endif

/* *r read one double at a time. A ray its caller has just built is often stored in pieces (a
 * returned point, a direction); a wider load across two of those stores cannot be forwarded
 * from them and waits until they reach the cache. The empty asm keeps the compiler from merging
 * the six loads into wider ones. */
#if defined(__GNUC__) && defined(__SSE2__)
static inline double rf__ray_piece(const double *p)
{
    double v = *p;
    __asm__("" : "+x"(v));
    return v;
}
#else
static inline double rf__ray_piece(const double *p) { return *p; }
#endif
static inline RfRay rf_ray_read(const RfRay *r)
{
    RfRay o;
    o.origin.x = rf__ray_piece(&r->origin.x);
    o.origin.y = rf__ray_piece(&r->origin.y);
    o.origin.z = rf__ray_piece(&r->origin.z);
    o.dir.x = rf__ray_piece(&r->dir.x);
    o.dir.y = rf__ray_piece(&r->dir.y);
    o.dir.z = rf__ray_piece(&r->dir.z);
    return o;
}

#ifdef __cplusplus
}
#endif

#endif
