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

#ifdef __cplusplus
}
#endif

#endif
