/* The camera of §3.4 and the thin lens of §3.10. */
#include "refray/camera.h"

#include <math.h>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

RfStatus rf_camera_init(RfCamera *cam, RfVec3 eye, RfVec3 target, RfVec3 up, double d, double l,
                        double r, double b, double t, int nx, int ny)
{
    RfCameraBasis basis;
    RfStatus st = rf_camera_basis(eye, target, up, &basis);
    if (st != RF_OK)
        return st;
    if (!(d > 0.0) || !(l != r) || !(b != t) || nx < 1 || ny < 1 || !isfinite(d) ||
        !isfinite(l) || !isfinite(r) || !isfinite(b) || !isfinite(t))
        return RF_ERR_DOMAIN;
    cam->eye = eye;
    cam->basis = basis;
    cam->d = d;
    cam->l = l;
    cam->r = r;
    cam->b = b;
    cam->t = t;
    cam->nx = nx;
    cam->ny = ny;
    cam->aperture_radius = 0.0;
    cam->focal_distance = 1.0;
    return RF_OK;
}

RfStatus rf_camera_init_fov(RfCamera *cam, RfVec3 eye, RfVec3 target, RfVec3 up, double d,
                            double fov_y, int nx, int ny)
{
    if (!(fov_y > 0.0 && fov_y < RF_PI) || nx < 1 || ny < 1)
        return RF_ERR_DOMAIN;
    double t = d * tan(0.5 * fov_y), r = t * (double)nx / (double)ny;
    return rf_camera_init(cam, eye, target, up, d, -r, r, -t, t, nx, ny);
}

RfStatus rf_camera_set_lens(RfCamera *cam, double aperture_radius, double focal_distance)
{
    if (!(aperture_radius >= 0.0) || !(focal_distance > 0.0) || !isfinite(aperture_radius) ||
        !isfinite(focal_distance))
        return RF_ERR_DOMAIN;
    cam->aperture_radius = aperture_radius;
    cam->focal_distance = focal_distance;
    return RF_OK;
}

/* §3.4: lambda1 runs from l (left edge) to r, lambda2 from t (top row) down to b. */
RfVec3 rf_camera_plane_point(const RfCamera *cam, double px, double py)
{
#if defined(__SSE2__)
    /* the two divisions as one instruction: the same quotients */
    double q[2];
    _mm_storeu_pd(q, _mm_div_pd(_mm_set_pd((cam->t - cam->b) * py, (cam->r - cam->l) * px),
                                _mm_set_pd((double)cam->ny, (double)cam->nx)));
    return rf_vec3(cam->l + q[0], cam->t - q[1], -cam->d);
#else
    double l1 = cam->l + (cam->r - cam->l) * px / (double)cam->nx;
    double l2 = cam->t - (cam->t - cam->b) * py / (double)cam->ny;
    return rf_vec3(l1, l2, -cam->d);
#endif
}

RfStatus rf_thin_lens_ray(RfVec3 pixel_dir, double lens_u, double lens_v, double aperture_radius,
                          double focal_distance, RfRay *out)
{
    if (!(pixel_dir.z < 0.0) || !(focal_distance > 0.0))
        return RF_ERR_DOMAIN;
    /* the pinhole ray t pixel_dir reaches z = -focal_distance at t = -focal_distance / z */
    RfVec3 focus = rf_vec3_scale(pixel_dir, -focal_distance / pixel_dir.z);
    RfVec3 lens = rf_vec3(aperture_radius * lens_u, aperture_radius * lens_v, 0.0);
    out->origin = lens;
    out->dir = rf_vec3_normalize(rf_vec3_sub(focus, lens));
    return RF_OK;
}

RfRay rf_camera_ray(const RfCamera *cam, double px, double py, double lens_u, double lens_v)
{
    RfVec3 c = rf_camera_plane_point(cam, px, py);
    RfRay cr;
    if (cam->aperture_radius > 0.0 &&
        rf_thin_lens_ray(c, lens_u, lens_v, cam->aperture_radius, cam->focal_distance, &cr) == RF_OK)
        return rf_ray(rf_vec3_add(cam->eye, rf_camera_to_world(cam, cr.origin)),
                      rf_vec3_normalize(rf_camera_to_world(cam, cr.dir)));
    return rf_ray(cam->eye, rf_vec3_normalize(rf_camera_to_world(cam, c)));
}
