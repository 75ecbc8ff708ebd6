/* §4 transformations. */
#include "refray/transform.h"

#include <math.h>
#include <stddef.h>

RfMat2 rf_mat2_scale(double sx, double sy)
{
    RfMat2 m = {{{sx, 0.0}, {0.0, sy}}};
    return m;
}

RfMat2 rf_mat2_shear(RfAxis axis, double s)
{
    RfMat2 m = rf_mat2_identity();
    if (axis == RF_AXIS_X)
        m.m[0][1] = s;
    else
        m.m[1][0] = s;
    return m;
}

RfMat2 rf_mat2_reflect(RfAxis axis)
{
    return axis == RF_AXIS_X ? rf_mat2_scale(-1.0, 1.0) : rf_mat2_scale(1.0, -1.0);
}

RfMat2 rf_mat2_rotate(double phi)
{
    double c = cos(phi), s = sin(phi);
    RfMat2 m = {{{c, -s}, {s, c}}};
    return m;
}

RfMat3 rf_mat3_rotate(RfAxis axis, double phi)
{
    /* the 2D rotation placed in the plane of the two other axes, in cyclic order
     * (y,z) for x, (z,x) for y, (x,y) for z: this gives the script's three matrices */
    RfMat3 m = rf_mat3_identity();
    int i = ((int)axis + 1) % 3, j = ((int)axis + 2) % 3;
    double c = cos(phi), s = sin(phi);
    m.m[i][i] = c;
    m.m[i][j] = -s;
    m.m[j][i] = s;
    m.m[j][j] = c;
    return m;
}

RfMat3 rf_mat3_euler(RfEulerOrder order, double psi, double theta, double phi)
{
    static const RfAxis axes[4][3] = {
        {RF_AXIS_Z, RF_AXIS_Y, RF_AXIS_X}, /* ZYX: R_z(phi) R_y(theta) R_x(psi) */
        {RF_AXIS_X, RF_AXIS_Y, RF_AXIS_Z}, /* XYZ: R_x(psi) R_y(theta) R_z(phi) */
        {RF_AXIS_Z, RF_AXIS_X, RF_AXIS_Z}, /* ZXZ: R_z(phi) R_x(theta) R_z(psi) */
        {RF_AXIS_Z, RF_AXIS_Y, RF_AXIS_Z}, /* ZYZ: R_z(phi) R_y(theta) R_z(psi) */
    };
    /* the angle of each factor: XYZ uses (psi, theta, phi) left to right, the others
     * (phi, theta, psi) */
    double first = order == RF_EULER_XYZ ? psi : phi;
    double last = order == RF_EULER_XYZ ? phi : psi;
    const RfAxis *a = axes[order];
    return rf_mat3_mul(rf_mat3_mul(rf_mat3_rotate(a[0], first), rf_mat3_rotate(a[1], theta)),
                       rf_mat3_rotate(a[2], last));
}

RfMat3 rf_mat3_rotation_basis(RfVec3 u, RfVec3 v, RfVec3 w)
{
    return rf_mat3_rows(u, v, w);
}

RfStatus rf_mat3_axis_angle(RfVec3 d, double phi, RfMat3 *r, RfVec3 *e_out, RfVec3 *f_out)
{
    double len = rf_vec3_length(d);
    if (!(len > 0.0) || !isfinite(len))
        return RF_ERR_DEGENERATE;
    d = rf_vec3_scale(d, 1.0 / len);
    RfVec3 e;
    if (d.y == 0.0 && d.z == 0.0)
        e = rf_vec3(0.0, 0.0, d.x > 0.0 ? -1.0 : 1.0); /* y-axis x d, normalised */
    else
        e = rf_vec3_scale(rf_vec3(0.0, -d.z, d.y), 1.0 / sqrt(d.y * d.y + d.z * d.z));
    RfVec3 f = rf_vec3_cross(d, e);
    RfMat3 m = rf_mat3_rows(d, e, f);
    *r = rf_mat3_mul(rf_mat3_mul(rf_mat3_transpose(m), rf_mat3_rotate(RF_AXIS_X, phi)), m);
    if (e_out)
        *e_out = e;
    if (f_out)
        *f_out = f;
    return RF_OK;
}

RfStatus rf_mat3_rodrigues(RfVec3 d, double phi, RfMat3 *r)
{
    double len = rf_vec3_length(d);
    if (!(len > 0.0) || !isfinite(len))
        return RF_ERR_DEGENERATE;
    d = rf_vec3_scale(d, 1.0 / len);
    /* R = cos(phi) I + sin(phi) [d]x + (1 - cos(phi)) d d^T */
    double c = cos(phi), s = sin(phi), k = 1.0 - c;
    RfMat3 m = {{{c + k * d.x * d.x, k * d.x * d.y - s * d.z, k * d.x * d.z + s * d.y},
                 {k * d.y * d.x + s * d.z, c + k * d.y * d.y, k * d.y * d.z - s * d.x},
                 {k * d.z * d.x - s * d.y, k * d.z * d.y + s * d.x, c + k * d.z * d.z}}};
    *r = m;
    return RF_OK;
}

RfMat4 rf_mat4_scale(double sx, double sy, double sz)
{
    RfMat4 m = rf_mat4_identity();
    m.m[0][0] = sx;
    m.m[1][1] = sy;
    m.m[2][2] = sz;
    return m;
}

RfMat4 rf_mat4_shear_z(double dx, double dy)
{
    RfMat4 m = rf_mat4_identity();
    m.m[0][2] = dx;
    m.m[1][2] = dy;
    return m;
}

RfMat4 rf_mat4_rotate(RfAxis axis, double phi)
{
    return rf_mat4_affine(rf_mat3_rotate(axis, phi), rf_vec3(0.0, 0.0, 0.0));
}

RfMat4 rf_mat4_translate(RfVec3 d)
{
    return rf_mat4_affine(rf_mat3_identity(), d);
}

RfStatus rf_transform_step_matrix(const RfTransformStep *st, RfMat4 *m)
{
    const double *v = st->v, deg = RF_PI / 180.0;
    RfMat3 rot;
    switch (st->kind) {
    case RF_STEP_TRANSLATE:
        *m = rf_mat4_translate(rf_vec3(v[0], v[1], v[2]));
        return RF_OK;
    case RF_STEP_SCALE:
        *m = rf_mat4_scale(v[0], v[1], v[2]);
        return v[0] != 0.0 && v[1] != 0.0 && v[2] != 0.0 ? RF_OK : RF_ERR_DEGENERATE;
    case RF_STEP_ROTATE:
        *m = rf_mat4_rotate((RfAxis)st->axis, v[0] * deg);
        return RF_OK;
    case RF_STEP_AXIS_ANGLE: {
        RfStatus s = rf_mat3_axis_angle(rf_vec3(v[0], v[1], v[2]), v[3] * deg, &rot, NULL, NULL);
        *m = rf_mat4_affine(s == RF_OK ? rot : rf_mat3_identity(), rf_vec3(0, 0, 0));
        return s;
    }
    case RF_STEP_EULER:
        *m = rf_mat4_affine(rf_mat3_euler((RfEulerOrder)st->axis, v[0] * deg, v[1] * deg, v[2] * deg),
                            rf_vec3(0, 0, 0));
        return RF_OK;
    case RF_STEP_MATRIX:
        *m = rf_mat4_identity();
        for (int i = 0; i < 3; i++)
            for (int j = 0; j < 4; j++)
                m->m[i][j] = v[4 * i + j];
        return RF_OK;
    }
    return RF_ERR_DOMAIN;
}

RfStatus rf_transform_steps_matrix(const RfTransformStep *steps, int n, RfMat4 *m)
{
    *m = rf_mat4_identity();
    for (int i = 0; i < n; i++) {
        RfMat4 s;
        RfStatus st = rf_transform_step_matrix(&steps[i], &s);
        if (st != RF_OK)
            return st;
        *m = rf_mat4_mul(s, *m);
    }
    return RF_OK;
}

RfStatus rf_transform_point(RfMat4 m, RfVec3 x, RfVec3 *y)
{
    RfVec4 h = rf_mat4_mul_vec(m, rf_vec4_point(x));
    if (h.w == 0.0)
        return RF_ERR_DEGENERATE;
    *y = h.w == 1.0 ? rf_vec3(h.x, h.y, h.z) : rf_vec3(h.x / h.w, h.y / h.w, h.z / h.w);
    return RF_OK;
}

RfVec3 rf_transform_direction(RfMat4 m, RfVec3 x)
{
    RfVec4 h = rf_mat4_mul_vec(m, rf_vec4_direction(x));
    return rf_vec3(h.x, h.y, h.z);
}

RfStatus rf_transform_normal(RfMat3 m, RfVec3 n, RfVec3 *out)
{
    RfMat3 inv;
    if (!(rf_vec3_length(n) > 0.0))
        return RF_ERR_DEGENERATE;
    RfStatus st = rf_mat3_inverse(m, &inv);
    if (st != RF_OK)
        return st;
    RfVec3 t = rf_mat3_mul_vec(rf_mat3_transpose(inv), n);
    *out = rf_vec3_normalize(t);
    return RF_OK;
}

RfStatus rf_camera_basis(RfVec3 eye, RfVec3 target, RfVec3 up, RfCameraBasis *out)
{
    RfVec3 back = rf_vec3_sub(eye, target);
    double len = rf_vec3_length(back);
    if (!(len > 0.0) || !isfinite(len))
        return RF_ERR_DEGENERATE;
    RfVec3 w = rf_vec3_scale(back, 1.0 / len);
    RfVec3 u = rf_vec3_cross(up, w);
    double ulen = rf_vec3_length(u);
    if (!(ulen > 0.0) || !isfinite(ulen))
        return RF_ERR_DEGENERATE;
    out->w = w;
    out->u = rf_vec3_scale(u, 1.0 / ulen);
    out->v = rf_vec3_cross(w, out->u);
    return RF_OK;
}

RfMat4 rf_camera_view(RfVec3 eye, RfCameraBasis b)
{
    RfMat4 r = rf_mat4_affine(rf_mat3_rotation_basis(b.u, b.v, b.w), rf_vec3(0.0, 0.0, 0.0));
    return rf_mat4_mul(r, rf_mat4_translate(rf_vec3_neg(eye)));
}
