/* refray: local illumination — the Phong model (§3.6.2), reflection (§3.6.2, §3.8), vertex
 * normals and their interpolation (§3.6.3) and the light sources of §3.7. Vectors called unit
 * must have length 1 (the caller normalises; these run per shading point). */
#ifndef REFRAY_SHADING_H
#define REFRAY_SHADING_H

#include <stddef.h>

#include "refray/intersect.h"
#include "refray/rgb.h"
#include "refray/status.h"
#include "refray/vec.h"

#ifdef __cplusplus
extern "C" {
#endif

/* §3.6.2 per RGB channel, for one light of intensity I_L:
 *   ambient  = ka I_L
 *   diffuse  = kd I_L max(0, <N,L>)
 *   specular = ks I_L max(0, <R_L,V>)^n, and 0 when <N,L> <= 0 (light behind the surface)
 *   total    = ambient + diffuse + specular
 *   r_l      = 2N<N,L> - L (erratum: the script writes 2N<N,L>L)
 * N, L, V unit; L and V point away from the surface (to the light, to the viewer). A zero
 * <R_L,V> gives no highlight even for n = 0 (0^0 is not taken as 1). */
typedef struct { RfRgb ambient, diffuse, specular, total; RfVec3 r_l; } RfPhong;
RfPhong rf_phong(RfVec3 n, RfVec3 l, RfVec3 v, RfRgb ka, RfRgb kd, RfRgb ks, double shininess,
                 RfRgb light);

/* §3.6.2 R = 2N<N,L> - L (N unit; L any length, R has its length). */
RfVec3 rf_reflect(RfVec3 n, RfVec3 l);
/* §3.8 a travelling ray D is mirrored to D - 2<D,N>N (= rf_reflect(N, -D), the same numbers). */
RfVec3 rf_reflect_dir(RfVec3 d, RfVec3 n);

/* §3.6.3 the vertex normal: normalise(sum over the adjacent faces of (b-a) x (c-a)), each face
 * given as three corners a, b, c (faces[3k], faces[3k+1], faces[3k+2]); the cross products are
 * area-weighted, and the sum is normalised, not divided by the count. RF_ERR_DEGENERATE when
 * the sum is zero (no faces, or they cancel). */
RfStatus rf_vertex_normal(const RfVec3 *corners, size_t faces, RfVec3 *n);
/* §3.6.3 Phong shading: normalise(l1 n1 + l2 n2 + l3 n3). RF_ERR_DEGENERATE for a zero sum. */
RfStatus rf_interpolate_normal(RfVec3 n1, RfVec3 n2, RfVec3 n3, double l1, double l2, double l3,
                               RfVec3 *n);

/* §3.7 lights, seen from a surface point: the arriving intensity i (per channel), the unit
 * direction l to the light, the distance to it (INFINITY for a directional light, for shadow
 * rays) and, for a spot light, the angle theta (radians) between its axis and the point. */
typedef enum {
    RF_FALLOFF_INVERSE_SQUARE, /* §3.7: the intensity falls with the squared distance */
    RF_FALLOFF_NONE            /* NFF/SPD lights: no falloff (DESIGN.md) */
} RfFalloff;
typedef struct { RfRgb i; RfVec3 l; double distance, theta; } RfLightSample;

/* Point light: i = I/d^2 (or I). RF_ERR_DEGENERATE when the point is at the light. */
RfStatus rf_light_point(RfRgb intensity, RfVec3 light_pos, RfFalloff falloff, RfVec3 point,
                        RfLightSample *out);
/* Directional light: direction = where the light travels (unit); l = -direction, i = E. */
RfLightSample rf_light_directional(RfRgb irradiance, RfVec3 direction);
/* Spot light: i = I cos^n(theta) / d^2 for theta <= cutoff (radians, in [0, pi/2]), else 0;
 * theta = angle(axis, point - light_pos), axis unit. RF_ERR_DEGENERATE at the light. */
RfStatus rf_light_spot(RfRgb intensity, RfVec3 light_pos, RfVec3 axis, double exponent,
                       double cutoff, RfFalloff falloff, RfVec3 point, RfLightSample *out);

#ifdef __cplusplus
}
#endif

#endif
