/* `refray formula` entries of §3 (ray tracing). Each runs the library routine the tracer uses
 * (intersect.h, camera.h, shading.h, optics.h); the formula only reads, checks and prints. */
#include "refray/camera.h"
#include "refray/formula.h"
#include "formula_internal.h"
#include "refray/intersect.h"
#include "refray/optics.h"
#include "refray/shading.h"

#include <math.h>

#define DEG (180.0 / RF_PI)

static void out_rgb(RfFormulaCall *c, const char *name, RfRgb v)
{
    double a[3] = {v.r, v.g, v.b};
    rf_out_vec(c, name, a, 3);
}

static int in_rgb(RfFormulaCall *c, const char *name, RfRgb *v)
{
    double a[3];
    if (rf_in_vec(c, name, 0, a, NULL))
        return 1;
    *v = rf_rgb(a[0], a[1], a[2]);
    return 0;
}

/* A 3D vector normalised here; a zero vector is an error. */
static int in_unit(RfFormulaCall *c, const char *name, RfVec3 *v)
{
    if (rf_in_vec3(c, name, v))
        return 1;
    double len = rf_vec3_length(*v);
    if (!(len > 0.0) || !isfinite(len))
        return rf_call_error(c, "input '%s' must not be the zero vector", name);
    *v = rf_vec3_scale(*v, 1.0 / len);
    return 0;
}

static int in_positive(RfFormulaCall *c, const char *name, double *v)
{
    if (rf_in_num(c, name, v))
        return 1;
    if (!(*v > 0.0))
        return rf_call_error(c, "input '%s' must be > 0", name);
    return 0;
}

/* origin and dir of a ray; dir is used as given (t in units of |dir|) but must not be zero */
static int in_ray(RfFormulaCall *c, RfRay *ray)
{
    if (rf_in_vec3(c, "origin", &ray->origin) || rf_in_vec3(c, "dir", &ray->dir))
        return 1;
    if (!(rf_vec3_length(ray->dir) > 0.0))
        return rf_call_error(c, "dir must not be the zero vector");
    return 0;
}

/* The outputs shared by the intersections: hit, t (null without a hit), point, normal. */
static void out_hit(RfFormulaCall *c, RfRay ray, int found, const RfHit *hit)
{
    rf_out_bool(c, "hit", found);
    if (found) {
        rf_out_num(c, "t", hit->t);
        rf_out_vec3(c, "point", rf_ray_at(ray, hit->t));
        rf_out_vec3(c, "normal", hit->normal);
    } else {
        rf_out_null(c, "t");
        rf_out_null(c, "point");
        rf_out_null(c, "normal");
    }
}

static int f_nyquist(RfFormulaCall *c)
{
    double fmax, fs;
    if (rf_in_num(c, "f_max", &fmax) || in_positive(c, "f_sample", &fs))
        return 1;
    if (!(fmax >= 0.0))
        return rf_call_error(c, "f_max must be >= 0");
    rf_out_num(c, "min_rate", 2.0 * fmax);
    rf_out_bool(c, "aliasing", !(fs > 2.0 * fmax)); /* Satz 3.1: strictly greater */
    rf_out_num(c, "nyquist_frequency", 0.5 * fs);
    return 0;
}

static int f_camera_basis(RfFormulaCall *c) { return rf_formula_camera(c, 0); }

static int f_primary_ray(RfFormulaCall *c)
{
    RfVec3 eye, target, up;
    double d, sx, sy, e[4];
    long nx, ny, i, j;
    RfCamera cam;
    RfStatus st;
    static const char *const edge[4] = {"l", "r", "b", "t"};
    if (rf_in_vec3(c, "eye", &eye) || rf_in_vec3(c, "target", &target) || rf_in_vec3(c, "up", &up) ||
        in_positive(c, "d", &d) || rf_in_int(c, "nx", &nx) || rf_in_int(c, "ny", &ny) ||
        rf_in_int(c, "i", &i) || rf_in_int(c, "j", &j) || rf_in_num(c, "sx", &sx) ||
        rf_in_num(c, "sy", &sy))
        return 1;
    if (nx < 1 || ny < 1 || nx > 1000000000L || ny > 1000000000L)
        return rf_call_error(c, "nx and ny must be between 1 and 1e9");
    if (i < 0 || i >= nx || j < 0 || j >= ny)
        return rf_call_error(c, "pixel (i, j) must lie in [0, nx) x [0, ny)");
    if (!(sx >= 0.0 && sx <= 1.0 && sy >= 0.0 && sy <= 1.0))
        return rf_call_error(c, "sx and sy must lie in [0, 1] (0.5 = the pixel centre)");
    int edges = 0;
    for (int k = 0; k < 4; k++)
        edges += rf_in_has(c, edge[k]);
    if (rf_in_has(c, "fov_deg")) {
        double fov;
        if (edges)
            return rf_call_bad_input(c, "give either fov_deg or l, r, b, t, not both");
        if (rf_in_angle(c, "fov_deg", &fov))
            return 1;
        if (!(fov > 0.0 && fov < RF_PI))
            return rf_call_error(c, "fov_deg must lie in (0, 180)");
        st = rf_camera_init_fov(&cam, eye, target, up, d, fov, (int)nx, (int)ny);
    } else {
        if (edges != 4)
            return rf_call_bad_input(c, "give fov_deg (vertical) or all of l, r, b, t");
        for (int k = 0; k < 4; k++)
            if (rf_in_num(c, edge[k], &e[k]))
                return 1;
        if (e[0] == e[1] || e[2] == e[3])
            return rf_call_error(c, "the image plane needs l != r and b != t");
        st = rf_camera_init(&cam, eye, target, up, d, e[0], e[1], e[2], e[3], (int)nx, (int)ny);
    }
    if (st == RF_ERR_DEGENERATE)
        return rf_call_error(c, "eye equals target, or up is zero or parallel to the view direction");
    if (st != RF_OK)
        return rf_call_error(c, "invalid camera: %s", rf_status_str(st));
    double px = (double)i + sx, py = (double)j + sy;
    RfRay ray = rf_camera_ray(&cam, px, py, 0.0, 0.0);
    rf_out_vec3(c, "origin", ray.origin);
    rf_out_vec3(c, "s", rf_camera_to_world(&cam, rf_camera_plane_point(&cam, px, py)));
    rf_out_vec3(c, "direction", ray.dir);
    rf_out_num(c, "l", cam.l);
    rf_out_num(c, "r", cam.r);
    rf_out_num(c, "b", cam.b);
    rf_out_num(c, "t", cam.t);
    return 0;
}

static int f_intersect_sphere(RfFormulaCall *c)
{
    RfRay ray;
    RfSphere s;
    RfHit hit;
    int variant;
    if (in_ray(c, &ray) || rf_in_vec3(c, "center", &s.center) || in_positive(c, "radius", &s.radius) ||
        rf_in_choice(c, "variant", &variant))
        return 1;
    RfSphereMethod m = variant ? RF_SPHERE_STABLE : RF_SPHERE_SCRIPT;
    RfSphereQuadratic q = rf_sphere_quadratic(ray, s, m);
    rf_out_num(c, "a", q.a);
    rf_out_num(c, "b", q.b);
    rf_out_num(c, "c", q.c);
    rf_out_num(c, "disc", q.disc);
    if (q.roots) {
        rf_out_num(c, "t1", q.t1);
        rf_out_num(c, "t2", q.t2);
    } else {
        rf_out_null(c, "t1");
        rf_out_null(c, "t2");
    }
    out_hit(c, ray, rf_intersect_sphere(ray, s, m, 0.0, INFINITY, &hit), &hit);
    return 0;
}

static int f_intersect_plane(RfFormulaCall *c)
{
    RfRay ray;
    RfPlane p;
    RfHit hit;
    double t;
    if (in_ray(c, &ray) || rf_in_vec3(c, "normal", &p.normal) || rf_in_num(c, "offset", &p.offset))
        return 1;
    if (!(rf_vec3_length(p.normal) > 0.0))
        return rf_call_error(c, "the plane normal must not be the zero vector (erratum 3.5.2)");
    int crosses = rf_plane_line_t(ray, p, &t);
    rf_out_bool(c, "parallel", !crosses);
    if (crosses)
        rf_out_num(c, "t_line", t);
    else
        rf_out_null(c, "t_line");
    out_hit(c, ray, rf_intersect_plane(ray, p, 0.0, INFINITY, &hit), &hit);
    return 0;
}

static int f_intersect_triangle(RfFormulaCall *c)
{
    RfRay ray;
    RfTriangle tri;
    RfHit hit;
    int variant;
    if (in_ray(c, &ray) || rf_in_vec3(c, "p1", &tri.p1) || rf_in_vec3(c, "p2", &tri.p2) ||
        rf_in_vec3(c, "p3", &tri.p3) || rf_in_choice(c, "variant", &variant))
        return 1;
    RfVec3 n = rf_vec3_cross(rf_vec3_sub(tri.p2, tri.p1), rf_vec3_sub(tri.p3, tri.p1));
    if (!(rf_vec3_length(n) > 0.0))
        return rf_call_error(c, "the triangle is degenerate (collinear corners)");
    static const RfTriangleMethod methods[3] = {RF_TRIANGLE_SCRIPT, RF_TRIANGLE_MOLLER,
                                                RF_TRIANGLE_WATERTIGHT};
    int found = rf_intersect_triangle(ray, tri, methods[variant], 0.0, INFINITY, &hit);
    out_hit(c, ray, found, &hit);
    static const char *const names[3] = {"l1", "l2", "l3"};
    for (int k = 0; k < 3; k++) {
        if (found)
            rf_out_num(c, names[k], hit.l[k]);
        else
            rf_out_null(c, names[k]);
    }
    return 0;
}

/* intersect-cylinder (cylinder = 1: apex_radius optional, equal to base_radius) and
 * intersect-cone */
static int intersect_cone(RfFormulaCall *c, int cylinder)
{
    RfRay ray;
    RfCone k;
    RfHit hit;
    if (in_ray(c, &ray) || rf_in_vec3(c, "base", &k.base) || rf_in_num(c, "base_radius", &k.base_radius) ||
        rf_in_vec3(c, "apex", &k.apex))
        return 1;
    if (cylinder && !rf_in_has(c, "apex_radius"))
        k.apex_radius = k.base_radius;
    else if (rf_in_num(c, "apex_radius", &k.apex_radius))
        return 1;
    if (cylinder && k.apex_radius != k.base_radius)
        return rf_call_bad_input(c, "a cylinder has apex_radius = base_radius (use intersect-cone)");
    if (!(k.base_radius >= 0.0 && k.apex_radius >= 0.0) || (k.base_radius == 0.0 && k.apex_radius == 0.0))
        return rf_call_error(c, "the radii must be >= 0 and not both 0 (NFF's negative pair means "
                                "inside-only visibility: give the absolute values)");
    if (!(rf_vec3_length(rf_vec3_sub(k.apex, k.base)) > 0.0))
        return rf_call_error(c, "base and apex must differ");
    out_hit(c, ray, rf_intersect_cone(ray, k, 0.0, INFINITY, &hit), &hit);
    return 0;
}
static int f_intersect_cylinder(RfFormulaCall *c) { return intersect_cone(c, 1); }
static int f_intersect_cone(RfFormulaCall *c) { return intersect_cone(c, 0); }

static int f_phong(RfFormulaCall *c)
{
    RfVec3 n, l, v;
    RfRgb ka, kd, ks, light;
    double shin;
    if (in_unit(c, "n", &n) || in_unit(c, "l", &l) || in_unit(c, "v", &v) || in_rgb(c, "ka", &ka) ||
        in_rgb(c, "kd", &kd) || in_rgb(c, "ks", &ks) || rf_in_num(c, "shininess", &shin) ||
        in_rgb(c, "light", &light))
        return 1;
    if (!(shin >= 0.0))
        return rf_call_error(c, "shininess must be >= 0");
    RfPhong p = rf_phong(n, l, v, ka, kd, ks, shin, light);
    out_rgb(c, "ambient", p.ambient);
    out_rgb(c, "diffuse", p.diffuse);
    out_rgb(c, "specular", p.specular);
    out_rgb(c, "total", p.total);
    rf_out_vec3(c, "r_l", p.r_l);
    rf_out_num(c, "n_dot_l", rf_vec3_dot(n, l));
    rf_out_num(c, "r_dot_v", rf_vec3_dot(p.r_l, v));
    return 0;
}

static int f_reflect(RfFormulaCall *c)
{
    RfVec3 n, x;
    int has_l = rf_in_has(c, "l"), has_d = rf_in_has(c, "dir");
    if (has_l == has_d)
        return rf_call_bad_input(c, "give exactly one of l (towards the light) and dir (a travelling ray)");
    if (in_unit(c, "n", &n) || rf_in_vec3(c, has_l ? "l" : "dir", &x))
        return 1;
    rf_out_vec3(c, "r", has_l ? rf_reflect(n, x) : rf_reflect_dir(x, n));
    return 0;
}

#define MAX_FACES 64
static int f_vertex_normal(RfFormulaCall *c)
{
    double v[9 * MAX_FACES];
    RfVec3 corners[3 * MAX_FACES], n;
    int count = 0;
    if (rf_in_tris(c, "faces", MAX_FACES, v, &count))
        return 1;
    for (int k = 0; k < 3 * count; k++)
        corners[k] = rf_vec3(v[3 * k], v[3 * k + 1], v[3 * k + 2]);
    if (rf_vertex_normal(corners, (size_t)count, &n) != RF_OK)
        return rf_call_error(c, "the face normals sum to zero: no vertex normal");
    rf_out_vec3(c, "n", n);
    return 0;
}

static int f_interpolate_normal(RfFormulaCall *c)
{
    RfVec3 n1, n2, n3, n;
    double l1, l2, l3;
    if (rf_in_vec3(c, "n1", &n1) || rf_in_vec3(c, "n2", &n2) || rf_in_vec3(c, "n3", &n3) ||
        rf_in_num(c, "l1", &l1) || rf_in_num(c, "l2", &l2) || rf_in_num(c, "l3", &l3))
        return 1;
    if (rf_interpolate_normal(n1, n2, n3, l1, l2, l3, &n) != RF_OK)
        return rf_call_error(c, "l1 n1 + l2 n2 + l3 n3 is the zero vector");
    rf_out_vec3(c, "n", n);
    return 0;
}

static void out_light(RfFormulaCall *c, const RfLightSample *s)
{
    out_rgb(c, "i", s->i);
    rf_out_vec3(c, "l", s->l);
    if (isfinite(s->distance))
        rf_out_num(c, "distance", s->distance);
    else
        rf_out_null(c, "distance");
}

static int in_falloff(RfFormulaCall *c, RfFalloff *f)
{
    int k;
    if (rf_in_choice(c, "falloff", &k))
        return 1;
    *f = k ? RF_FALLOFF_NONE : RF_FALLOFF_INVERSE_SQUARE;
    return 0;
}

static int f_light_point(RfFormulaCall *c)
{
    RfRgb in;
    RfVec3 pos, p;
    RfFalloff f;
    RfLightSample s;
    if (in_rgb(c, "intensity", &in) || rf_in_vec3(c, "light_pos", &pos) || rf_in_vec3(c, "point", &p) ||
        in_falloff(c, &f))
        return 1;
    if (rf_light_point(in, pos, f, p, &s) != RF_OK)
        return rf_call_error(c, "the point is at the light: no direction, infinite intensity");
    out_light(c, &s);
    return 0;
}

static int f_light_directional(RfFormulaCall *c)
{
    RfRgb e;
    RfVec3 dir;
    if (in_rgb(c, "irradiance", &e) || in_unit(c, "direction", &dir))
        return 1;
    RfLightSample s = rf_light_directional(e, dir);
    out_light(c, &s);
    return 0;
}

static int f_light_spot(RfFormulaCall *c)
{
    RfRgb in;
    RfVec3 pos, axis, p;
    double ex, cut;
    RfFalloff f;
    RfLightSample s;
    if (in_rgb(c, "intensity", &in) || rf_in_vec3(c, "light_pos", &pos) || in_unit(c, "axis", &axis) ||
        rf_in_num(c, "exponent", &ex) || rf_in_num(c, "cutoff_deg", &cut) || rf_in_vec3(c, "point", &p) ||
        in_falloff(c, &f))
        return 1;
    if (!(ex >= 0.0))
        return rf_call_error(c, "exponent must be >= 0");
    if (!(cut >= 0.0 && cut <= 90.0))
        return rf_call_error(c, "cutoff_deg must lie in [0, 90]");
    if (rf_light_spot(in, pos, axis, ex, cut / DEG, f, p, &s) != RF_OK)
        return rf_call_error(c, "the point is at the light: no direction, infinite intensity");
    out_light(c, &s);
    rf_out_num(c, "theta_deg", s.theta * DEG);
    return 0;
}

static int f_ior(RfFormulaCall *c)
{
    double cm;
    if (in_positive(c, "c_medium", &cm))
        return 1;
    rf_out_num(c, "eta", rf_ior(cm));
    return 0;
}

static int in_etas(RfFormulaCall *c, double *ei, double *et)
{
    return in_positive(c, "eta_i", ei) || in_positive(c, "eta_t", et);
}

static int f_snell(RfFormulaCall *c)
{
    double ei, et, th;
    if (in_etas(c, &ei, &et) || rf_in_num(c, "theta_i_deg", &th))
        return 1;
    if (!(th >= 0.0 && th <= 90.0))
        return rf_call_error(c, "theta_i_deg must lie in [0, 90]");
    RfSnell s = rf_snell(ei, et, th / DEG);
    if (s.tir)
        rf_out_null(c, "theta_t_deg");
    else
        rf_out_num(c, "theta_t_deg", s.theta_t * DEG);
    rf_out_bool(c, "tir", s.tir);
    if (isnan(s.critical))
        rf_out_null(c, "critical_deg");
    else
        rf_out_num(c, "critical_deg", s.critical * DEG);
    return 0;
}

static int f_refract(RfFormulaCall *c)
{
    RfVec3 i, n, t;
    double ei, et;
    if (in_unit(c, "i", &i) || in_unit(c, "n", &n) || in_etas(c, &ei, &et))
        return 1;
    double cos_i = rf_vec3_dot(i, n);
    if (!(cos_i >= 0.0))
        return rf_call_error(c, "i must lie on the side of n (<i,n> >= 0): flip n and swap eta_i, eta_t");
    int ok = rf_refract(i, n, ei, et, &t);
    if (ok)
        rf_out_vec3(c, "t", t);
    else
        rf_out_null(c, "t");
    rf_out_bool(c, "tir", !ok);
    rf_out_num(c, "cos_i", cos_i);
    return 0;
}

static int f_fresnel(RfFormulaCall *c)
{
    double ei, et, ci;
    int variant;
    if (in_etas(c, &ei, &et) || rf_in_num(c, "cos_i", &ci) ||
        rf_in_choice(c, "variant", &variant))
        return 1;
    if (!(ci >= 0.0 && ci <= 1.0))
        return rf_call_error(c, "cos_i must lie in [0, 1]");
    RfFresnel f = rf_fresnel(ei, et, ci, variant ? RF_FRESNEL_SCHLICK : RF_FRESNEL_EXACT);
    rf_out_num(c, "r", f.r);
    rf_out_num(c, "t", f.t);
    if (isnan(f.rs)) {
        rf_out_null(c, "rs");
        rf_out_null(c, "rp");
    } else {
        rf_out_num(c, "rs", f.rs);
        rf_out_num(c, "rp", f.rp);
    }
    rf_out_bool(c, "tir", f.tir);
    return 0;
}

static int f_dispersion(RfFormulaCall *c)
{
    double lam, a, b;
    if (in_positive(c, "lambda_nm", &lam) || rf_in_num(c, "a", &a) || rf_in_num(c, "b", &b))
        return 1;
    rf_out_num(c, "eta", rf_cauchy(lam, a, b));
    return 0;
}

static int f_thin_lens(RfFormulaCall *c)
{
    double lu, lv, ap, fd;
    RfVec3 pd;
    RfRay ray;
    if (rf_in_num(c, "lens_u", &lu) || rf_in_num(c, "lens_v", &lv) || rf_in_num(c, "aperture_radius", &ap) ||
        in_positive(c, "focal_distance", &fd) || rf_in_vec3(c, "pixel_direction", &pd))
        return 1;
    if (!(ap >= 0.0))
        return rf_call_error(c, "aperture_radius must be >= 0");
    if (!(lu * lu + lv * lv <= 1.0))
        return rf_call_error(c, "(lens_u, lens_v) must lie in the unit disk");
    if (rf_thin_lens_ray(pd, lu, lv, ap, fd, &ray) != RF_OK)
        return rf_call_error(c, "pixel_direction must point into the scene (z < 0, camera space)");
    rf_out_vec3(c, "origin", ray.origin);
    rf_out_vec3(c, "direction", ray.dir);
    return 0;
}

#define ERR_34 "the script's u = up x w must be normalised when up is not perpendicular to w"
#define RAY_IN "origin:vec3 the ray's origin e; dir:vec3 the ray's direction d (not normalised: t " \
               "counts in units of |d|), not zero; "
#define CONE_IN RAY_IN "base:vec3 the centre of the base circle; base_radius:num the radius at the base (>= 0); " \
                "apex:vec3 the centre of the apex circle (not the base); "
#define HIT_OUT "t:num the ray parameter of the nearest hit with t >= 0 (null without a hit); " \
                "hit:bool the ray hits; point:vec the hit point e + t d (null without a hit); " \
                "normal:vec the unit normal at the hit (null without a hit)"
#define CAMERA_IN "eye:vec3 the eye position e; target:vec3 the point looked at; up:vec3 the up " \
                  "direction (not parallel to the view direction)"
#define LIGHT_OUT "i:rgb the light's intensity arriving at the point; l:vec the unit vector from " \
                  "the point towards the light; distance:num the distance to the light (null: infinitely far)"
#define FALLOFF_IN "falloff:inverse-square|none=inverse-square inverse-square: I/d^2, none: I (NFF)"
#define ETA_IN "eta_i:num the index of refraction on the incident side (> 0); eta_t:num the index " \
               "on the transmitted side (> 0)"

const RfFormula rf_formulas_raytrace[] = {
    {"nyquist", "3.1", "Nyquist-Shannon: a signal with maximal frequency f_max must be sampled at a rate "
     "strictly greater than min_rate = 2 f_max; aliasing when f_sample <= 2 f_max; nyquist_frequency = f_sample/2",
     "f_max:num the signal's highest frequency (>= 0); f_sample:num the sampling rate (> 0, same unit)",
     "min_rate:num 2 f_max (the rate must exceed it); aliasing:bool f_sample <= 2 f_max; "
     "nyquist_frequency:num f_sample/2, the highest frequency the rate can represent",
     NULL, f_nyquist, "f_max=20 f_sample=44.1"},
    {"camera-basis", "3.4", "w = (e - target)/|e - target|, u = normalise(up x w), v = w x u", CAMERA_IN,
     "u:vec the camera's right axis; v:vec its up axis; w:vec its backward axis (from target to eye)",
     ERR_34, f_camera_basis, "eye=0,0,5 target=0,0,0 up=0,1,0"},
    {"primary-ray", "3.4", "s = l1 u + l2 v - d w with l1 = l + (r-l)(i+sx)/nx, l2 = t - (t-b)(j+sy)/ny "
     "(row j = 0 at the top); fov_deg (vertical, edge to edge) gives t = d tan(fov/2), r = t nx/ny, "
     "l = -r, b = -t; give fov_deg or l, r, b, t. origin is the eye, s is relative to the eye, direction = s/|s|",
     CAMERA_IN "; d:num=1 the distance of the image plane from the eye (> 0); "
     "fov_deg:num? the vertical field of view, edge to edge, in (0,180) (degrees, or give l, r, b, t); "
     "l:num? the image plane's left edge; r:num? its right edge; b:num? its bottom edge; t:num? its top edge; "
     "nx:int the image width in pixels; ny:int the image height in pixels; i:int the pixel column, 0..nx-1; "
     "j:int the pixel row, 0..ny-1, 0 at the top; sx:num=0.5 the sample's position across the pixel, 0..1; "
     "sy:num=0.5 the sample's position down the pixel, 0..1",
     "origin:vec the ray's origin (the eye); s:vec the image-plane point relative to the eye; "
     "direction:vec the unit direction s/|s|; l:num the left edge used; r:num the right edge used; "
     "b:num the bottom edge used; t:num the top edge used",
     ERR_34, f_primary_ray, "eye=0,0,5 target=0,0,0 up=0,1,0 fov_deg=90 nx=4 ny=2 i=0 j=0"},
    {"intersect-sphere", "3.5.1", "a = <d,d>, b = 2<d,e-c>, c = <e-c,e-c> - r^2, D = b^2 - 4ac; D < 0 none, "
     "D = 0 one (tangent), roots < 0 behind the origin; t = the smallest root >= 0. variant=stable: "
     "the same roots computed precisely (D = 4a(r-|v|)(r+|v|), v = f - (<f,d>/a) d; c compensated; "
     "q = -(b + sign(b) sqrt(D))/2, roots q/a and c/q). t1 <= t2 (null when D < 0); t, point and the outward unit normal are null without a hit",
     RAY_IN "center:vec3 the sphere's centre c; radius:num its radius r (> 0); "
     "variant:script|stable=script script: the midnight formula as written, stable: the same roots, rounded less",
     "a:num the quadratic's a = <d,d>; b:num its b; c:num its c; disc:num the discriminant D; "
     "t1:num the smaller root (null when D < 0); t2:num the larger root (null when D < 0); " HIT_OUT, NULL,
     f_intersect_sphere, "origin=0,0,5 dir=0,0,-1 center=0,0,0 radius=1"},
    {"intersect-plane", "3.5.2", "Hesse form <x,n> = offset: t = (offset - <e,n>)/<d,n>; parallel when "
     "<d,n> = 0; t < 0 is behind the origin (no hit). t_line is the t of the whole line (null when parallel); t, point, normal (unit) are null without a hit",
     RAY_IN "normal:vec3 the plane's normal n (not zero, need not be unit); offset:num the plane's offset: <x,n> = offset",
     HIT_OUT "; parallel:bool the ray is parallel to the plane; t_line:num the t where the whole line "
     "meets the plane, also behind the origin (null when parallel)",
     "the script requires a, b, c != 0 (correct: (a,b,c) != 0) and uses d for both the ray direction "
     "and the plane offset; kept apart here", f_intersect_plane, "origin=0,1,0 dir=0,-1,0 normal=0,1,0 offset=-1"},
    {"intersect-triangle", "3.5.3", "two-sided ray/triangle hit with t >= 0 and barycentric l1, l2, l3 >= 0. "
     "variant=script: the plane, then barycentric coordinates; moller: Moller-Trumbore; watertight: "
     "Woop, Benthin, Wald 2013 with exact edge signs (no ray passes between two triangles). normal: the unit (p2-p1) x (p3-p1); t, point, normal, l1..l3 are null without a hit",
     RAY_IN "p1:vec3 the first corner; p2:vec3 the second corner; p3:vec3 the third corner; "
     "variant:script|moller|watertight=script the algorithm",
     HIT_OUT "; l1:num the barycentric weight of p1 (null without a hit); l2:num the weight of p2; "
     "l3:num the weight of p3", NULL, f_intersect_triangle,
     "origin=0.25,0.25,1 dir=0,0,-1 p1=0,0,0 p2=1,0,0 p3=0,1,0"},
    {"intersect-cylinder", "NFF", "open cylinder (NFF c, no caps) between base and apex; the nearest "
     "hit with t >= 0, from outside or inside; apex_radius may be omitted (it equals base_radius); the normal "
     "is the outward unit normal; null without a hit",
     CONE_IN "apex_radius:num? the radius at the apex, equal to base_radius (may be omitted)", HIT_OUT,
     NULL, f_intersect_cylinder, "origin=5,0,0.5 dir=-1,0,0 base=0,0,0 base_radius=1 apex=0,0,1"},
    {"intersect-cone", "NFF", "open cone (NFF c, no caps) between base and apex with radii base_radius, "
     "apex_radius; the nearest hit with t >= 0, from outside or inside; the normal is the outward unit "
     "normal; null without a hit",
     CONE_IN "apex_radius:num the radius at the apex (>= 0, not both radii 0)", HIT_OUT, NULL,
     f_intersect_cone, "origin=5,0,0.5 dir=-1,0,0 base=0,0,0 base_radius=1 apex=0,0,1 apex_radius=0"},
    {"phong", "3.6.2", "I = ka I_L + kd I_L <N,L> + ks I_L <R_L,V>^n per channel; N, L, V normalised here, "
     "L and V point away from the surface; negative scalar products count as 0; no highlight when "
     "<N,L> <= 0",
     "n:vec3 the surface normal N (normalised here); l:vec3 the direction from the surface to the light L; "
     "v:vec3 the direction from the surface to the viewer V; ka:rgb the ambient coefficient; "
     "kd:rgb the diffuse coefficient; ks:rgb the specular coefficient; shininess:num the exponent n (>= 0); "
     "light:rgb=1,1,1 the light's intensity I_L",
     "ambient:rgb ka I_L; diffuse:rgb kd I_L <N,L>; specular:rgb ks I_L <R_L,V>^n; "
     "total:rgb the sum; r_l:vec the reflected light direction R_L = 2N<N,L> - L; "
     "n_dot_l:num <N,L>; r_dot_v:num <R_L,V>",
     "the script writes R_L = 2N<N,L>L; correct: R_L = 2N<N,L> - L", f_phong,
     "n=0,0,1 l=0,1,1 v=0,0,1 ka=0.1 kd=0.6 ks=0.3 shininess=10"},
    {"reflect", "3.6.2, 3.8", "R = 2N<N,L> - L for l (towards the light), or D - 2<D,N>N for a travelling "
     "ray dir; n normalised here",
     "n:vec3 the surface normal N (normalised here); l:vec3? the direction towards the light L "
     "(give l or dir); dir:vec3? the direction D of a ray travelling into the surface",
     "r:vec the reflected direction", "the script writes R_L = 2N<N,L>L; correct: R_L = 2N<N,L> - L",
     f_reflect, "n=0,1,0 dir=1,-1,0"},
    {"vertex-normal", "3.6.3", "n = normalise(sum (b-a) x (c-a)) over the faces around the vertex "
     "(area-weighted; normalised, not divided by the count). faces: the triangles around the "
     "vertex, [[a,b,c], ...] (at most 64)",
     "faces:tris the triangles around the vertex, each [a,b,c] counter-clockwise (at most 64)",
     "n:vec the unit vertex normal", NULL, f_vertex_normal,
     "faces=[[[0,0,0],[1,0,0],[0,1,0]],[[0,0,0],[0,1,0],[0,0,1]]]"},
    {"interpolate-normal", "3.6.3", "Phong shading: n = normalise(l1 n1 + l2 n2 + l3 n3)",
     "n1:vec3 the normal at the first corner; n2:vec3 at the second; n3:vec3 at the third; "
     "l1:num the barycentric weight of corner 1; l2:num of corner 2; l3:num of corner 3",
     "n:vec the unit interpolated normal", NULL, f_interpolate_normal,
     "n1=0,0,1 n2=0,1,0 n3=1,0,0 l1=0.5 l2=0.25 l3=0.25"},
    {"light-point", "3.7", "point light: i = I/d^2 (falloff=none: I, the NFF convention), l towards the light",
     "intensity:rgb the light's intensity I; light_pos:vec3 the light's position; "
     "point:vec3 the lit point; " FALLOFF_IN, LIGHT_OUT, NULL, f_light_point,
     "intensity=100 light_pos=0,10,0 point=0,0,0"},
    {"light-directional", "3.7", "parallel light: i = irradiance everywhere, l = -direction normalised "
     "(direction = where the light travels); distance is null (infinitely far)",
     "irradiance:rgb the light's irradiance; direction:vec3 the direction the light travels (not zero)",
     LIGHT_OUT, NULL, f_light_directional, "irradiance=1 direction=0,-1,-1"},
    {"light-spot", "3.7", "spot light: i = I cos^n(theta)/d^2 for theta <= cutoff, else 0; theta = angle "
     "between the axis and the direction from the light to the point",
     "intensity:rgb the light's intensity I; light_pos:vec3 the light's position; "
     "axis:vec3 the direction the spot points to (not zero); exponent:num the fall-off exponent n (>= 0); "
     "cutoff_deg:num the cone's half angle, 0..90 (degrees); point:vec3 the lit point; " FALLOFF_IN,
     LIGHT_OUT "; theta_deg:num the angle between the axis and the direction to the point (degrees)",
     NULL, f_light_spot, "intensity=100 light_pos=0,10,0 axis=0,-1,0 exponent=2 cutoff_deg=30 point=1,0,0"},
    {"ior", "3.8.1", "index of refraction eta = c0/c_medium, c0 = 299792458 m/s",
     "c_medium:num the speed of light in the medium (m/s, > 0)", "eta:num the index of refraction", NULL,
     f_ior, "c_medium=225000000"},
    {"snell", "3.8.1", "eta_i sin(theta_i) = eta_t sin(theta_t); total internal reflection only beyond the "
     "critical angle (at it theta_t = 90); theta_t_deg is null under TIR, critical_deg null when eta_i <= eta_t",
     ETA_IN "; theta_i_deg:num the angle of incidence to the normal, 0..90 (degrees)",
     "theta_t_deg:num the angle of refraction (degrees, null under total internal reflection); "
     "tir:bool total internal reflection; critical_deg:num the critical angle (degrees, null when eta_i <= eta_t)",
     NULL, f_snell, "eta_i=1 eta_t=1.5 theta_i_deg=30"},
    {"refract", "3.8.1", "T = -(eta_i/eta_t) I + ((eta_i/eta_t) cos_i - sqrt(1 - (eta_i/eta_t)^2 "
     "(1 - cos_i^2))) N, cos_i = <I,N>; I (normalised here) points back to where the ray came from, on "
     "the side of N; t is null under total internal reflection",
     "i:vec3 the direction back to where the ray came from, I (normalised here, <I,N> >= 0); "
     "n:vec3 the surface normal N on the incident side (normalised here); " ETA_IN,
     "t:vec the unit refracted direction T (null under total internal reflection); "
     "tir:bool total internal reflection; cos_i:num cos(theta_i) = <I,N>", NULL, f_refract,
     "i=0,1,1 n=0,1,0 eta_i=1 eta_t=1.5"},
    {"fresnel", "3.8.1", "exact dielectric Fresnel reflectance (unpolarised mean of rs, rp, the squared "
     "amplitude ratios) or variant=schlick; r = 1 under total internal reflection, t = 1 - r; rs and rp are null for schlick",
     ETA_IN "; cos_i:num cos(theta_i) of the angle of incidence, 0..1; "
     "variant:exact|schlick=exact exact: Fresnel's equations, schlick: Schlick's approximation",
     "r:num the reflectance; t:num the transmittance 1 - r; rs:num the s-polarised reflectance (null for schlick); "
     "rp:num the p-polarised reflectance (null for schlick); tir:bool total internal reflection", NULL,
     f_fresnel, "eta_i=1 eta_t=1.5 cos_i=0.5"},
    {"dispersion", "beyond", "Cauchy: eta = A + B/lambda^2 with lambda in micrometres",
     "lambda_nm:num the wavelength (nm, > 0); a:num Cauchy's A; b:num Cauchy's B (micrometres^2)",
     "eta:num the index of refraction", NULL, f_dispersion, "lambda_nm=589.3 a=1.5046 b=0.0042"},
    {"thin-lens", "3.10", "camera space (eye at 0, looking along -z): the ray from the lens point "
     "aperture_radius (lens_u, lens_v, 0) to where the pinhole ray along pixel_direction meets the "
     "focal plane z = -focal_distance",
     "lens_u:num the lens sample's x in the unit disk; lens_v:num its y (lens_u^2 + lens_v^2 <= 1); "
     "aperture_radius:num the lens radius (>= 0); focal_distance:num the distance of the plane in focus (> 0); "
     "pixel_direction:vec3 the pinhole ray's direction in camera space (z < 0)",
     "origin:vec the ray's origin on the lens; direction:vec the ray's unit direction", NULL, f_thin_lens,
     "lens_u=0.5 lens_v=0 aperture_radius=0.1 focal_distance=2 pixel_direction=0,0,-1"},
    {NULL, NULL, NULL, NULL, NULL, NULL, NULL, NULL},
};
