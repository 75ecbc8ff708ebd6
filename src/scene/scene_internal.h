/* refray: the scene model's internal helpers (scene.c defines them, scene_check.c the readers'
 * check), shared below the readers by scene_graph.c and scene_check.c and above them by reader.h. */
#ifndef RF_SCENE_INTERNAL_H
#define RF_SCENE_INTERNAL_H

#include <math.h>

#include "refray/scene.h"

/* printf into msg (when msg and msgsz) and return st: the plain messages of scene.c and
 * scene_graph.c, which the readers prefix with a file position. */
RfStatus rf__msgf(char *msg, size_t msgsz, RfStatus st, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 4, 5)))
#endif
    ;

/* Finite coordinates; finite and non-negative channels. */
static inline int rf__finite3(RfVec3 v) { return isfinite(v.x) && isfinite(v.y) && isfinite(v.z); }
static inline int rf__nonneg_rgb(RfRgb c)
{
    return isfinite(c.r) && isfinite(c.g) && isfinite(c.b) && c.r >= 0.0 && c.g >= 0.0 && c.b >= 0.0;
}

/* Twice the vector area of a polygon (the sum of the fan's cross products about v[0]; equal to
 * Newell's normal) and the largest squared distance of a vertex from v[0]: what the model's
 * degeneracy test measures (scene.c). */
RfVec3 rf__polygon_area_vector(const RfVec3 *v, int n, double *ext2);

/* For readers that add many primitives at once, on several threads: room for this many more
 * primitives, vertices and normals (rf__scene_reserve; the counts stay), and a primitive checked
 * and stored into prims[index] as rf_scene_add_primitive would append it (rf__scene_put_primitive;
 * the caller has counted it in). */
RfStatus rf__scene_reserve(RfScene *scene, size_t prims, size_t vertices, size_t normals);
RfStatus rf__scene_put_primitive(RfScene *scene, size_t index, const RfPrimitive *p, char *msg, size_t msgsz);

/* rf_scene_validate for a scene a reader made: every primitive was checked when it was added
 * (rf_scene_add_primitive, rf__scene_put_primitive), against counts that only grow, and no
 * reader changes one afterwards, so the primitives are not checked a second time (on the
 * 1.2 M-triangle bunny that was 19 ms on one thread). scene_check.c. */
RfStatus rf__scene_validate_read(const RfScene *scene, const char *source, char *err, size_t errsz);

#endif
