/* Refraction (§3.8.1): Snell, the transmission vector, Fresnel, dispersion. */
#include "refray/optics.h"

#include <math.h>

#include "refray/numeric.h"

double rf_ior(double c_medium) { return RF_C0 / c_medium; }

/* The one TIR decision (optics.h): 1 under TIR; otherwise 0 and cos theta_t. */
static int transmitted_cos(double sin2_t, double *cos_t)
{
    if (!(sin2_t <= 1.0 + RF_TIR_SLACK))
        return 1;
    *cos_t = sqrt(rf_max_num(0.0, 1.0 - sin2_t)); /* glibc fmax's result, inline (vec.h) */
    return 0;
}

/* sin^2 theta from cos theta as (1 - c)(1 + c): exact-ish near c = 1, unlike 1 - c^2 */
static double sin2_from_cos(double c) { return rf_max_num(0.0, (1.0 - c) * (1.0 + c)); }

RfSnell rf_snell(double eta_i, double eta_t, double theta_i)
{
    RfSnell s;
    double sin_t = eta_i / eta_t * sin(theta_i), cos_t;
    s.critical = eta_i > eta_t ? asin(eta_t / eta_i) : NAN;
    s.tir = transmitted_cos(sin_t * sin_t, &cos_t);
    s.theta_t = s.tir ? NAN : atan2(fmin(sin_t, 1.0), cos_t);
    return s;
}

int rf_refract(RfVec3 i, RfVec3 n, double eta_i, double eta_t, RfVec3 *t)
{
    double eta = eta_i / eta_t, c = rf_vec3_dot(i, n), cos_t;
    if (transmitted_cos(eta * eta * sin2_from_cos(c), &cos_t))
        return 0;
    *t = rf_vec3_add(rf_vec3_scale(i, -eta), rf_vec3_scale(n, eta * c - cos_t));
    return 1;
}

/* (x - y)/(x + y) squared; a 0/0 (grazing on both sides) reflects everything */
static double ratio2(double x, double y)
{
    double den = x + y;
    if (den == 0.0)
        return 1.0;
    double q = (x - y) / den;
    return q * q;
}

RfFresnel rf_fresnel(double eta_i, double eta_t, double cos_i, RfFresnelMethod method)
{
    RfFresnel f;
    double eta = eta_i / eta_t, cos_t = 1.0;
    f.rs = f.rp = method == RF_FRESNEL_EXACT ? 0.0 : NAN;
    f.tir = 0;
    if (eta_i == eta_t) { /* no interface */
        f.r = 0.0;
        f.t = 1.0;
        return f;
    }
    f.tir = transmitted_cos(eta * eta * sin2_from_cos(cos_i), &cos_t);
    if (f.tir) {
        f.r = 1.0;
        if (method == RF_FRESNEL_EXACT)
            f.rs = f.rp = 1.0;
    } else if (method == RF_FRESNEL_EXACT) {
        f.rs = ratio2(eta_i * cos_i, eta_t * cos_t);
        f.rp = ratio2(eta_t * cos_i, eta_i * cos_t);
        f.r = 0.5 * (f.rs + f.rp);
    } else {
        double r0 = ratio2(eta_i, eta_t), x = 1.0 - (eta_i > eta_t ? cos_t : cos_i);
        f.r = r0 + (1.0 - r0) * (x * x * x * x * x);
    }
    f.t = 1.0 - f.r;
    return f;
}

double rf_cauchy(double lambda_nm, double a, double b)
{
    double um = lambda_nm / 1000.0;
    return a + b / (um * um);
}
