/* refray: the virtual camera of §3.4 (pinhole, primary rays) and the thin lens of §3.10.
 *
 * Camera space: the eye at the origin, x along u, y along v, looking along -z (-w). The image
 * plane lies at distance d with edges l, r (along u) and b, t (along v). Pixel (i, j) with
 * i in [0, nx), j in [0, ny) and row j = 0 at the top; a sample at offset (sx, sy) in [0,1]^2
 * of the pixel ((0.5, 0.5) = the centre) has the continuous pixel coordinates
 * (px, py) = (i + sx, j + sy) and lies at
 *   s = lambda1 u + lambda2 v - d w,  lambda1 = l + (r - l) px / nx,  lambda2 = t - (t - b) py / ny. */
#ifndef REFRAY_CAMERA_H
#define REFRAY_CAMERA_H

#include "refray/ray.h"
#include "refray/status.h"
#include "refray/transform.h"
#include "refray/vec.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct {
    RfVec3 eye;
    RfCameraBasis basis;          /* u, v, w of §3.4 (rf_camera_basis) */
    double d, l, r, b, t;         /* image plane distance and edges */
    int nx, ny;                   /* pixels */
    double aperture_radius;       /* §3.10 thin lens; 0: pinhole */
    double focal_distance;        /* distance of the plane in focus (> 0 when aperture > 0) */
} RfCamera;

/* §3.4 with explicit edges. RF_ERR_DEGENERATE for eye = target or up parallel to the view
 * direction (rf_camera_basis); RF_ERR_DOMAIN for d <= 0, l = r, b = t, nx or ny < 1.
 * The lens starts closed (pinhole). */
RfStatus rf_camera_init(RfCamera *cam, RfVec3 eye, RfVec3 target, RfVec3 up, double d, double l,
                        double r, double b, double t, int nx, int ny);
/* The symmetric frustum from the vertical field of view fov_y (radians, edge to edge):
 * t = d tan(fov_y/2), b = -t, r = t nx/ny, l = -r. RF_ERR_DOMAIN unless 0 < fov_y < pi. */
RfStatus rf_camera_init_fov(RfCamera *cam, RfVec3 eye, RfVec3 target, RfVec3 up, double d,
                            double fov_y, int nx, int ny);
/* §3.10: opens the lens. RF_ERR_DOMAIN unless aperture_radius >= 0 and focal_distance > 0. */
RfStatus rf_camera_set_lens(RfCamera *cam, double aperture_radius, double focal_distance);

/* The image-plane point (lambda1, lambda2, -d) in camera space for pixel coordinates (px, py). */
RfVec3 rf_camera_plane_point(const RfCamera *cam, double px, double py);
/* Camera space to world: x u + y v + z w (a direction; add the eye for a point). Inline: every
 * primary ray needs it, and a returned copy read back across its stores stalled. */
static inline RfVec3 rf_camera_to_world(const RfCamera *cam, RfVec3 c)
{
    return rf_vec3_add(rf_vec3_add(rf_vec3_scale(cam->basis.u, c.x), rf_vec3_scale(cam->basis.v, c.y)),
                       rf_vec3_scale(cam->basis.w, c.z));
}

/* The primary ray through (px, py). Pinhole (aperture 0): origin = eye, dir = s/|s| with s the
 * world image-plane vector. Lens open: the thin-lens ray through the lens point
 * aperture (lens_u, lens_v) (a point of the unit disk, already mapped from the sampler)
 * mapped to world space, dir unit. */
RfRay rf_camera_ray(const RfCamera *cam, double px, double py, double lens_u, double lens_v);

/* §3.10 in camera space: the ray from the lens point aperture_radius (lens_u, lens_v, 0) to the
 * point where the pinhole ray along pixel_dir meets the focal plane z = -focal_distance; dir
 * unit. RF_ERR_DOMAIN when pixel_dir does not point into the scene (z >= 0) or
 * focal_distance <= 0. */
RfStatus rf_thin_lens_ray(RfVec3 pixel_dir, double lens_u, double lens_v, double aperture_radius,
                          double focal_distance, RfRay *out);

#ifdef __cplusplus
}
#endif

#endif
