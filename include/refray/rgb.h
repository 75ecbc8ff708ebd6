/* refray: linear RGB triples as value types (§3.6.2: the Phong coefficients and light
 * intensities are given per channel red, green, blue). */
#ifndef REFRAY_RGB_H
#define REFRAY_RGB_H

#ifdef __cplusplus
extern "C" {
#endif

typedef struct { double r, g, b; } RfRgb;

static inline RfRgb rf_rgb(double r, double g, double b)
{
    RfRgb c; c.r = r; c.g = g; c.b = b; return c;
}
static inline RfRgb rf_rgb_add(RfRgb a, RfRgb b) { return rf_rgb(a.r + b.r, a.g + b.g, a.b + b.b); }
static inline RfRgb rf_rgb_mul(RfRgb a, RfRgb b) { return rf_rgb(a.r * b.r, a.g * b.g, a.b * b.b); }
static inline RfRgb rf_rgb_scale(RfRgb a, double s) { return rf_rgb(a.r * s, a.g * s, a.b * s); }

#ifdef __cplusplus
}
#endif

#endif
