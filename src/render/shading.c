/* Local illumination: Phong (§3.6.2), reflection, vertex normals (§3.6.3), lights (§3.7). */
#include "refray/shading.h"

#include <math.h>

RfVec3 rf_reflect(RfVec3 n, RfVec3 l)
{
    return rf_vec3_sub(rf_vec3_scale(n, 2.0 * rf_vec3_dot(n, l)), l);
}

RfVec3 rf_reflect_dir(RfVec3 d, RfVec3 n)
{
    return rf_reflect(n, rf_vec3_neg(d));
}

RfPhong rf_phong(RfVec3 n, RfVec3 l, RfVec3 v, RfRgb ka, RfRgb kd, RfRgb ks, double shininess,
                 RfRgb light)
{
    RfPhong p;
    double nl = rf_vec3_dot(n, l);
    p.r_l = rf_reflect(n, l);
    double rv = rf_vec3_dot(p.r_l, v);
    /* §3.6.2: only directions with positive scalar products contribute */
    double diff = nl > 0.0 ? nl : 0.0;
    double spec = nl > 0.0 && rv > 0.0 ? pow(rv, shininess) : 0.0;
    p.ambient = rf_rgb_mul(ka, light);
    p.diffuse = rf_rgb_scale(rf_rgb_mul(kd, light), diff);
    p.specular = rf_rgb_scale(rf_rgb_mul(ks, light), spec);
    p.total = rf_rgb_add(rf_rgb_add(p.ambient, p.diffuse), p.specular);
    return p;
}

static RfStatus unit_or_degenerate(RfVec3 s, RfVec3 *n)
{
    double len = rf_vec3_length(s);
    if (!(len > 0.0) || !isfinite(len))
        return RF_ERR_DEGENERATE;
    *n = rf_vec3_scale(s, 1.0 / len);
    return RF_OK;
}

RfStatus rf_vertex_normal(const RfVec3 *corners, size_t faces, RfVec3 *n)
{
    RfVec3 s = rf_vec3(0.0, 0.0, 0.0);
    for (size_t f = 0; f < faces; f++) {
        const RfVec3 *c = corners + 3 * f;
        s = rf_vec3_add(s, rf_vec3_cross(rf_vec3_sub(c[1], c[0]), rf_vec3_sub(c[2], c[0])));
    }
    return unit_or_degenerate(s, n);
}

RfStatus rf_interpolate_normal(RfVec3 n1, RfVec3 n2, RfVec3 n3, double l1, double l2, double l3,
                               RfVec3 *n)
{
    RfVec3 s = rf_vec3_add(rf_vec3_add(rf_vec3_scale(n1, l1), rf_vec3_scale(n2, l2)),
                           rf_vec3_scale(n3, l3));
    return unit_or_degenerate(s, n);
}

RfStatus rf_light_point(RfRgb intensity, RfVec3 light_pos, RfFalloff falloff, RfVec3 point,
                        RfLightSample *out)
{
    RfVec3 to = rf_vec3_sub(light_pos, point);
    double d = rf_vec3_length(to);
    if (!(d > 0.0) || !isfinite(d))
        return RF_ERR_DEGENERATE;
    out->l = rf_vec3_scale(to, 1.0 / d);
    out->distance = d;
    out->theta = 0.0;
    out->i = falloff == RF_FALLOFF_INVERSE_SQUARE ? rf_rgb_scale(intensity, 1.0 / (d * d)) : intensity;
    return RF_OK;
}

RfLightSample rf_light_directional(RfRgb irradiance, RfVec3 direction)
{
    RfLightSample s;
    s.i = irradiance;
    s.l = rf_vec3_neg(direction);
    s.distance = INFINITY;
    s.theta = 0.0;
    return s;
}

/* A point light weighted by cos^n of the angle off the axis (§3.7). The angle comes from
 * rf_vec3_angle (atan2 form), accurate near the axis where acos would lose digits. */
RfStatus rf_light_spot(RfRgb intensity, RfVec3 light_pos, RfVec3 axis, double exponent,
                       double cutoff, RfFalloff falloff, RfVec3 point, RfLightSample *out)
{
    RfStatus st = rf_light_point(intensity, light_pos, falloff, point, out);
    if (st != RF_OK)
        return st;
    out->theta = rf_vec3_angle(axis, rf_vec3_neg(out->l));
    double w = out->theta <= cutoff ? pow(cos(out->theta), exponent) : 0.0;
    out->i = rf_rgb_scale(out->i, w);
    return RF_OK;
}
