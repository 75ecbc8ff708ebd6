/* refray: refraction (§3.8.1) — index of refraction, Snell's law, the transmitted direction,
 * the Fresnel reflectance and Cauchy dispersion. Angles in radians.
 *
 * One classification of total internal reflection (TIR) serves all of them: with
 * sin^2 theta_t = (eta_i/eta_t)^2 sin^2 theta_i, TIR iff sin^2 theta_t > 1 + RF_TIR_SLACK
 * (numeric.h); at the critical angle the ray grazes (theta_t = 90 deg, cos theta_t = 0). */
#ifndef REFRAY_OPTICS_H
#define REFRAY_OPTICS_H

#include "refray/vec.h"

#ifdef __cplusplus
extern "C" {
#endif

#define RF_C0 299792458.0 /* speed of light in vacuum, m/s (exact by definition of the metre) */

/* §3.8.1 eta = c0 / c_medium. */
double rf_ior(double c_medium);

/* §3.8.1 eta_i sin theta_i = eta_t sin theta_t, theta_i in [0, pi/2]. theta_t is NAN under
 * TIR; critical = asin(eta_t/eta_i), NAN when eta_i <= eta_t (no TIR possible). */
typedef struct { double theta_t, critical; int tir; } RfSnell;
RfSnell rf_snell(double eta_i, double eta_t, double theta_i);

/* §3.8.1 the script's transmission vector
 *   T = -(eta_i/eta_t) I + ((eta_i/eta_t) cos_i - sqrt(1 - (eta_i/eta_t)^2 (1 - cos_i^2))) N,
 * cos_i = <I,N>, with I and N unit and I on the side of N (pointing back to where the ray came
 * from; <I,N> >= 0); the tracer flips N and swaps the indices when leaving a medium. Returns 1
 * and writes *t (unit), or 0 under TIR (*t untouched). */
int rf_refract(RfVec3 i, RfVec3 n, double eta_i, double eta_t, RfVec3 *t);

/* The Fresnel reflectance for unpolarised light at a dielectric interface, cos_i in [0, 1].
 * exact: rs = ((eta_i cos_i - eta_t cos_t)/(eta_i cos_i + eta_t cos_t))^2,
 *        rp = ((eta_t cos_i - eta_i cos_t)/(eta_t cos_i + eta_i cos_t))^2, r = (rs + rp)/2;
 * schlick: r = R0 + (1 - R0)(1 - cos)^5, R0 = ((eta_i - eta_t)/(eta_i + eta_t))^2, with cos the
 * cosine on the optically thinner side (cos_t when eta_i > eta_t), rs = rp = NAN.
 * Under TIR r = rs = rp = 1 (schlick: r = 1); t = 1 - r. eta_i = eta_t: no interface, r = 0. */
typedef enum { RF_FRESNEL_EXACT, RF_FRESNEL_SCHLICK } RfFresnelMethod;
typedef struct { double r, t, rs, rp; int tir; } RfFresnel;
RfFresnel rf_fresnel(double eta_i, double eta_t, double cos_i, RfFresnelMethod method);

/* Cauchy's dispersion formula eta = A + B / lambda^2 with lambda in micrometres. */
double rf_cauchy(double lambda_nm, double a, double b);

#ifdef __cplusplus
}
#endif

#endif
