/* refray: the transformations of §4 — 2D matrices, 3D rotations, Euler angles, rotation about
 * an axis, inverses, homogeneous coordinates, affine maps, change of basis, the camera
 * transformation and the transformation of normals. Angles are in radians. */
#ifndef REFRAY_TRANSFORM_H
#define REFRAY_TRANSFORM_H

#include "refray/mat.h"
#include "refray/status.h"
#include "refray/vec.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum { RF_AXIS_X = 0, RF_AXIS_Y = 1, RF_AXIS_Z = 2 } RfAxis;

/* §4.2 2D matrices. */
RfMat2 rf_mat2_scale(double sx, double sy);
RfMat2 rf_mat2_shear(RfAxis axis, double s);   /* shear_x: [[1,s],[0,1]], shear_y: [[1,0],[s,1]] */
RfMat2 rf_mat2_reflect(RfAxis axis);           /* reflect_x: diag(-1,1), reflect_y: diag(1,-1) */
RfMat2 rf_mat2_rotate(double phi);

/* §4.3 R_x, R_y, R_z. */
RfMat3 rf_mat3_rotate(RfAxis axis, double phi);

/* §4.3 Euler angles psi, theta, phi (about x, y, z for the orders xyz/zyx). The order names the
 * factors of the product left to right: ZYX = R_z(phi) R_y(theta) R_x(psi) (the script's
 * explicit matrix), XYZ = R_x(psi) R_y(theta) R_z(phi), ZXZ = R_z(phi) R_x(theta) R_z(psi),
 * ZYZ = R_z(phi) R_y(theta) R_z(psi). */
typedef enum { RF_EULER_ZYX, RF_EULER_XYZ, RF_EULER_ZXZ, RF_EULER_ZYZ } RfEulerOrder;
RfMat3 rf_mat3_euler(RfEulerOrder order, double psi, double theta, double phi);

/* §4.3 R_uvw: the rows are u, v, w; it maps u, v, w onto the axes. */
RfMat3 rf_mat3_rotation_basis(RfVec3 u, RfVec3 v, RfVec3 w);

/* §4.3 rotation by phi about the axis d, by the script's construction: d normalised,
 * e = (0, -d_z, d_y)/sqrt(d_y^2 + d_z^2) (= x-axis x d, normalised), f = d x e,
 * M = rows (d, e, f), R = M^-1 R_x(phi) M with M^-1 = M^T (M is orthonormal).
 * The script's helper is undefined for d parallel to the x axis (d_y = d_z = 0); there the
 * y axis is the helper: e = normalise(y-axis x d) = (0, 0, -sign(d_x)).
 * e and f may be NULL. RF_ERR_DEGENERATE for d = 0. */
RfStatus rf_mat3_axis_angle(RfVec3 d, double phi, RfMat3 *r, RfVec3 *e, RfVec3 *f);

/* Rodrigues' formula, the independent cross-check of rf_mat3_axis_angle (d normalised here). */
RfStatus rf_mat3_rodrigues(RfVec3 d, double phi, RfMat3 *r);

/* §4.6 homogeneous 4x4 matrices. */
RfMat4 rf_mat4_scale(double sx, double sy, double sz);
RfMat4 rf_mat4_shear_z(double dx, double dy);
RfMat4 rf_mat4_rotate(RfAxis axis, double phi);
RfMat4 rf_mat4_translate(RfVec3 d);

/* One step of a composed transform (a scene's `translate 1 2 3`, `rotate y 30`, ...), kept as
 * numbers so that keyframes of motion can be interpolated number by number. v holds:
 * TRANSLATE x y z; SCALE sx sy sz; ROTATE the angle in degrees about axis (RfAxis);
 * AXIS_ANGLE the axis x y z and the angle in degrees; EULER psi theta phi in degrees with
 * axis = RfEulerOrder; MATRIX the 3 x 4 rows of an affine matrix. */
typedef enum {
    RF_STEP_TRANSLATE, RF_STEP_SCALE, RF_STEP_ROTATE, RF_STEP_AXIS_ANGLE, RF_STEP_EULER, RF_STEP_MATRIX
} RfStepKind;
typedef struct {
    RfStepKind kind;
    int axis;
    double v[12];
} RfTransformStep;

/* The step's matrix; RF_ERR_DEGENERATE for a zero axis or scale factor. */
RfStatus rf_transform_step_matrix(const RfTransformStep *step, RfMat4 *m);
/* Steps composed in order, each acting after the ones before it: M = S_n ... S_2 S_1. */
RfStatus rf_transform_steps_matrix(const RfTransformStep *steps, int n, RfMat4 *m);

/* §4.5: y = M (x, 1) dehomogenised (a point), and y = M (x, 0) (a direction).
 * rf_transform_point fails with RF_ERR_DEGENERATE when the result has w = 0 (a point at
 * infinity, only possible for projective M). */
RfStatus rf_transform_point(RfMat4 m, RfVec3 x, RfVec3 *y);
RfVec3 rf_transform_direction(RfMat4 m, RfVec3 x);

/* §4.9 n' = normalise((M^-1)^T n), M the linear part. RF_ERR_SINGULAR for a singular M,
 * RF_ERR_DEGENERATE for n = 0. */
RfStatus rf_transform_normal(RfMat3 m, RfVec3 n, RfVec3 *out);

/* §3.4 / §4.7.2: the camera basis w = (e - target)/|e - target|, u = normalise(up x w)
 * (erratum: the script does not normalise), v = w x u. RF_ERR_DEGENERATE when eye = target,
 * up = 0 or up is parallel to the view direction. */
typedef struct { RfVec3 u, v, w; } RfCameraBasis;
RfStatus rf_camera_basis(RfVec3 eye, RfVec3 target, RfVec3 up, RfCameraBasis *out);
/* §4.7.2 world -> camera: R_uvw (as 4x4) times T(-eye). */
RfMat4 rf_camera_view(RfVec3 eye, RfCameraBasis basis);

#ifdef __cplusplus
}
#endif

#endif
