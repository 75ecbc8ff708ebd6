/* refray: small vectors (§2.1) as value types. All functions take and return by value. */
#ifndef REFRAY_VEC_H
#define REFRAY_VEC_H

#include <math.h>

#ifdef __cplusplus
extern "C" {
#endif

#define RF_PI 3.14159265358979323846

typedef struct { double x, y; } RfVec2;
typedef struct { double x, y, z; } RfVec3;
typedef struct { double x, y, z, w; } RfVec4;

static inline RfVec2 rf_vec2(double x, double y) { RfVec2 v; v.x = x; v.y = y; return v; }
static inline RfVec3 rf_vec3(double x, double y, double z)
{
    RfVec3 v; v.x = x; v.y = y; v.z = z; return v;
}
static inline RfVec4 rf_vec4(double x, double y, double z, double w)
{
    RfVec4 v; v.x = x; v.y = y; v.z = z; v.w = w; return v;
}

/* fmin and fmax with the results of the C library's (glibc on x86-64: minsd/maxsd, so the
 * second operand on a tie, which decides the sign of a zero; a NaN gives the other operand),
 * inline: GCC calls the library for fmin/fmax unless told that no NaN or signed zero occurs. */
static inline double rf_min_num(double x, double y)
{
    if (isnan(x))
        return y;
    if (isnan(y))
        return x;
    return x < y ? x : y;
}
static inline double rf_max_num(double x, double y)
{
    if (isnan(x))
        return y;
    if (isnan(y))
        return x;
    return x > y ? x : y;
}

/* nextafter(x, +inf) without the library call: the next double above x (+0 and -0 give the
 * smallest subnormal, +inf and NaN stay). Test vec_next_up. */
static inline double rf_next_up(double x)
{
    if (x != x || x == HUGE_VAL)
        return x;
    if (x == 0.0)
        return 0x1p-1074;
    union { double d; unsigned long long u; } b;
    b.d = x;
    b.u += x > 0.0 ? 1 : -1ll; /* the magnitude up for x > 0, down (towards 0) for x < 0 */
    return b.d;
}

/* a*b - c*d with one rounding error (Kahan's algorithm via fma): used where the plain form
 * cancels catastrophically, e.g. the cross product of nearly parallel vectors. */
static inline double rf_diff_of_products(double a, double b, double c, double d)
{
    double cd = c * d;
    double err = fma(-c, d, cd);
    double dop = fma(a, b, -cd);
    return dop + err;
}

static inline RfVec3 rf_vec3_add(RfVec3 a, RfVec3 b) { return rf_vec3(a.x + b.x, a.y + b.y, a.z + b.z); }
static inline RfVec3 rf_vec3_sub(RfVec3 a, RfVec3 b) { return rf_vec3(a.x - b.x, a.y - b.y, a.z - b.z); }
static inline RfVec3 rf_vec3_scale(RfVec3 a, double s) { return rf_vec3(a.x * s, a.y * s, a.z * s); }
static inline RfVec3 rf_vec3_neg(RfVec3 a) { return rf_vec3(-a.x, -a.y, -a.z); }
static inline RfVec3 rf_vec3_mul(RfVec3 a, RfVec3 b) { return rf_vec3(a.x * b.x, a.y * b.y, a.z * b.z); }
static inline double rf_vec3_dot(RfVec3 a, RfVec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }

/* §2.1 Definition 2.2, each component as a difference of products with one rounding. */
static inline RfVec3 rf_vec3_cross(RfVec3 a, RfVec3 b)
{
    return rf_vec3(rf_diff_of_products(a.y, b.z, a.z, b.y),
                   rf_diff_of_products(a.z, b.x, a.x, b.z),
                   rf_diff_of_products(a.x, b.y, a.y, b.x));
}

/* §2.1 |a| = sqrt(sum a_i^2) (erratum: the script drops the square). */
static inline double rf_vec3_length(RfVec3 a) { return sqrt(rf_vec3_dot(a, a)); }
/* The largest |coordinate| (the infinity norm); a NaN coordinate is passed over. */
static inline double rf_vec3_max_abs(RfVec3 v)
{
    double m = fabs(v.x) > 0.0 ? fabs(v.x) : 0.0;
    m = fabs(v.y) > m ? fabs(v.y) : m;
    return fabs(v.z) > m ? fabs(v.z) : m;
}

/* a/|a|; the zero vector stays zero (callers that need a direction check the length first). */
static inline RfVec3 rf_vec3_normalize(RfVec3 a)
{
    double len = rf_vec3_length(a);
    return len > 0.0 ? rf_vec3_scale(a, 1.0 / len) : a;
}

static inline RfVec3 rf_vec3_lerp(RfVec3 a, RfVec3 b, double t)
{
    return rf_vec3_add(a, rf_vec3_scale(rf_vec3_sub(b, a), t));
}

/* Homogeneous coordinates (§4.5.1): points get w = 1, directions w = 0. */
static inline RfVec4 rf_vec4_point(RfVec3 p) { return rf_vec4(p.x, p.y, p.z, 1.0); }
static inline RfVec4 rf_vec4_direction(RfVec3 d) { return rf_vec4(d.x, d.y, d.z, 0.0); }

/* The angle between a and b in radians, by atan2(|a x b|, <a,b>): accurate near 0 and pi,
 * where acos(<a,b>/(|a||b|)) loses half the digits. */
double rf_vec3_angle(RfVec3 a, RfVec3 b);

#ifdef __cplusplus
}
#endif

#endif
