// refray-verify: the rows beyond one ray's decision (docs/verify.md): shadow acne and light
// leaks over scene scales 1e-4 .. 1e6, Snell, refraction and Fresnel at their edge cases, and
// stress renders in which no NaN or Inf may reach the film.
#include "verify_run.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <vector>

#include "refray/optics.h"

namespace rv {

// ---- acne and leaks over scene scales 1e-4 .. 1e6 ------------------------------------------

// Acne: one convex object (a sphere of radius s, or an exactly convex grid cube of size ~s) at
// 10 s from the origin; a sample is the tracer's hit point p of a camera ray, a point light L
// is placed at elevation 10^U(-4, 0.18) rad above the surface there, and the sample counts
// when the light is exactly visible from the true surface point (cube: L strictly on the
// outer side of the hit triangle's plane, CGAL orientation; sphere: <L-c, p-c> > r^2 (1 +
// 1e-6), far beyond p's rounding). The tracer's shadow ray from rf_hit_offset_origin(h, l)
// must then reach the light: any hit is a false self-shadow.
void run_acne(const Opts &o, Stats &st)
{
    Rng rng(o.seed * 7919 + 11);
    for (int k = -4; k <= 6; k++)
        for (int obj = 0; obj < 2; obj++) {
            double s = std::pow(10.0, k);
            int idx = 2 * (k + 4) + obj;
            long n = o.rays / 22 + (idx < o.rays % 22 ? 1 : 0), before = st.rays;
            World w;
            RfVec3 c = rf_vec3_scale(rng.unit(), 10 * s);
            if (obj == 0) {
                w.sphere(c, s, RF_PRIM_TWO_SIDED);
            } else {
                double h = std::ldexp(1.0, (int)std::floor(std::log2(s)) - 1);
                RfVec3 corner = rf_vec3(std::round(c.x / h) * h, std::round(c.y / h) * h, std::round(c.z / h) * h);
                w.grid_cube(corner, 3, h);
                c = rf_vec3_add(corner, rf_vec3(1.5 * h, 1.5 * h, 1.5 * h));
            }
            w.finish();
            double size = obj == 0 ? s : 3 * std::ldexp(1.0, (int)std::floor(std::log2(s)) - 1);
            for (long a = 0; st.rays - before < n && a < 50 * n + 100; a++) { // n counted samples
                RfVec3 eye = rf_vec3_add(c, rf_vec3_scale(rng.unit(), 4 * size));
                RfRay pr = rf_ray(eye, rf_vec3_sub(rf_vec3_add(c, rf_vec3_scale(rng.ball(), size)), eye));
                RfSurfaceHit h;
                int prim = rf_tracer_intersect(w.tr, &pr, 0.0, HUGE_VAL, &h);
                if (prim < 0)
                    continue;
                RfVec3 n = h.normal;
                RfVec3 t1 = rf_vec3_normalize(rf_vec3_cross(n, rng.unit())), t2 = rf_vec3_cross(n, t1);
                double el = rng.pow10(-4, 0.18), az = rng.range(0, 2 * RF_PI);
                RfVec3 dir = rf_vec3_add(rf_vec3_scale(n, std::sin(el)),
                                         rf_vec3_scale(rf_vec3_add(rf_vec3_scale(t1, std::cos(az)), rf_vec3_scale(t2, std::sin(az))), std::cos(el)));
                RfVec3 Lp = rf_vec3_add(h.point, rf_vec3_scale(dir, size * rng.pow10(0, 2)));
                bool visible;
                if (obj == 0) {
                    LV lc = sub(lv(Lp), lv(c)), pc = sub(lv(h.point), lv(c));
                    visible = dot(lc, pc) > (L)s * s * (1 + 1e-6L);
                } else {
                    int item = w.orc->items_of(prim)[0];
                    int se = w.orc->side(item, eye), sl = w.orc->side(item, Lp);
                    visible = se != 0 && se == sl;
                }
                RfVec3 l = rf_vec3_normalize(rf_vec3_sub(Lp, h.point));
                if (!visible || rf_vec3_dot(n, l) <= 0)
                    continue;
                RfSurfaceHit hn = h;
                hn.normal = n;
                RfRay sr = rf_ray(rf_hit_offset_origin(&hn, l, o.fixed_offset), l);
                double dist = rf_vec3_length(rf_vec3_sub(Lp, sr.origin));
                RfSurfaceHit sh;
                st.rays++;
                st.acne_d++;
                if (rf_tracer_intersect(w.tr, &sr, 0.0, dist, &sh) >= 0) {
                    st.acne_n++;
                    st.real++;
                    example(st, "scale 1e%d %s: shadow ray from (%a,%a,%a) dir (%a,%a,%a) hits prim %d at t=%g",
                            k, obj ? "cube" : "sphere", sr.origin.x, sr.origin.y, sr.origin.z, l.x, l.y, l.z,
                            sh.prim, sh.t);
                } else {
                    st.agree++;
                }
            }
        }
}

// Leaks: a floor square and a plate 1e-3 s above it (both exactly planar, translated to 10 s);
// exact floor points under the plate, a light above such that the segment to it crosses the
// plate (CGAL: exactly occluded); the tracer's shadow ray from the offset origin must be
// blocked. An offset larger than the gap starts above the plate: a light leak.
void run_leak(const Opts &o, Stats &st)
{
    Rng rng(o.seed * 104729 + 5);
    for (int k = -4; k <= 6; k++) {
        double s = std::pow(10.0, k), z0 = 10 * s, hgt = 1e-3 * s;
        World w;
        RfVec3 fl[4] = {{-s, -s, z0}, {s, -s, z0}, {s, s, z0}, {-s, s, z0}};
        RfVec3 pl[4] = {{-s / 2, -s / 2, z0 + hgt}, {s / 2, -s / 2, z0 + hgt}, {s / 2, s / 2, z0 + hgt}, {-s / 2, s / 2, z0 + hgt}};
        w.poly(fl, 4, RF_PRIM_TWO_SIDED, -1);
        w.poly(pl, 4, RF_PRIM_TWO_SIDED, -1);
        w.finish();
        long n = o.rays / 11 + (k + 4 < o.rays % 11 ? 1 : 0), before = st.rays;
        for (long a = 0; st.rays - before < n && a < 50 * n + 100; a++) {
            RfVec3 p = rf_vec3(s * rng.range(-0.3, 0.3), s * rng.range(-0.3, 0.3), z0);
            RfVec3 Lp = rf_vec3(p.x + s * rng.range(-0.1, 0.1), p.y + s * rng.range(-0.1, 0.1), z0 + s * rng.range(0.5, 2));
            bool occluded = false;
            for (int item : w.orc->items_of(1))
                occluded |= w.orc->segment_hits(item, p, Lp);
            if (!occluded)
                continue;
            RfVec3 l = rf_vec3_normalize(rf_vec3_sub(Lp, p));
            RfSurfaceHit hp; // a hit at p on the plane z = z0, seen from nearby
            std::memset(&hp, 0, sizeof hp);
            hp.point = p;
            hp.normal = rf_vec3(0, 0, 1);
            hp.scale = std::max(std::fabs(p.x), std::max(std::fabs(p.y), std::fabs(p.z)));
            RfRay sr = rf_ray(rf_hit_offset_origin(&hp, l, o.fixed_offset), l);
            RfSurfaceHit sh;
            st.rays++;
            st.acne_d++;
            if (rf_tracer_intersect(w.tr, &sr, 0.0, rf_vec3_length(rf_vec3_sub(Lp, sr.origin)), &sh) < 0) {
                st.acne_n++;
                st.real++;
                example(st, "scale 1e%d: light leaks past the plate from (%a,%a,%a)", k, sr.origin.x, sr.origin.y,
                        sr.origin.z);
            } else {
                st.agree++;
            }
        }
    }
}

// ---- optics: Snell, refraction and Fresnel at the edge cases --------------------------------

void run_optics(const Opts &, Stats &st)
{
    struct Pair {
        double ei, et;
    } pairs[] = {{1.5, 1.0}, {1.0, 1.5}, {1.33, 1.0}, {2.4, 1.0}, {1.5, 1.33}};
    for (const Pair &pp : pairs) {
        std::vector<double> th;
        double crit = pp.ei > pp.et ? std::asin(pp.et / pp.ei) : NAN;
        for (int i = 0; i <= 2000; i++)
            th.push_back(RF_PI / 2 * i / 2000);
        th.push_back(std::nextafter(RF_PI / 2, 0));
        if (!std::isnan(crit)) {
            for (double dlt : {0.0, 1e-15, 1e-12, 1e-9, 1e-6, 1e-3})
                for (double sg : {-1.0, 1.0})
                    th.push_back(crit + sg * dlt);
            for (int i = -50; i <= 50; i++)
                th.push_back(crit + i * 2e-11);
            double lo = crit, hi = crit; // the neighbouring doubles
            for (int i = 0; i < 5; i++) {
                lo = std::nextafter(lo, 0.0);
                hi = std::nextafter(hi, 2.0);
                th.push_back(lo);
                th.push_back(hi);
            }
        }
        std::sort(th.begin(), th.end());
        double prev_r = -1, prev_th = -1;
        for (double t : th) {
            st.rays++;
            bool bad = false;
            const char *why = "";
            double ci = std::cos(t), si = std::sin(t);
            RfVec3 i = rf_vec3(si, 0, ci), n = rf_vec3(0, 0, 1);
            RfFresnel fe = rf_fresnel(pp.ei, pp.et, ci, RF_FRESNEL_EXACT);
            RfFresnel fs = rf_fresnel(pp.ei, pp.et, ci, RF_FRESNEL_SCHLICK);
            RfSnell sn = rf_snell(pp.ei, pp.et, t);
            RfVec3 tv = rf_vec3(NAN, NAN, NAN);
            int refr = rf_refract(i, n, pp.ei, pp.et, &tv);
            L s2 = (L)pp.ei / pp.et * ((L)pp.ei / pp.et) * (L)si * si; // sin^2 theta_t
            if (!std::isfinite(fe.r) || !std::isfinite(fe.t) || !std::isfinite(fs.r) || !std::isfinite(fs.t) ||
                fe.r < 0 || fe.r > 1 || fs.r < 0 || fs.r > 1)
                bad = true, why = "Fresnel not finite or outside [0, 1]";
            else if (std::fabs(fe.r + fe.t - 1) > 1e-12 || std::fabs(fs.r + fs.t - 1) > 1e-12)
                bad = true, why = "R + T != 1";
            else if (s2 > 1 + 2e-14L && (refr || fe.r != 1 || !fe.tir || !sn.tir || fs.r != 1))
                bad = true, why = "beyond the critical angle without total internal reflection";
            else if (s2 < 1 - 2e-14L) {
                if (!refr || fe.tir || sn.tir || fe.r >= 1)
                    bad = true, why = "total internal reflection below the critical angle";
                else {
                    L tl = len(lv(tv)), st_ = len(cross(lv(tv), lv(n))) / tl;
                    if (std::fabs(tl - 1) > 1e-12L || std::fabs(pp.ei * si - pp.et * st_) > 1e-12L || tv.z > 0 ||
                        !std::isfinite(sn.theta_t))
                        bad = true, why = "refracted direction not unit or not satisfying Snell";
                }
            }
            if (refr && !(std::isfinite(tv.x) && std::isfinite(tv.y) && std::isfinite(tv.z)))
                bad = true, why = "refracted direction not finite";
            // F rises monotonically through the critical angle
            if (!std::isnan(crit) && std::fabs(t - crit) < 1e-3 && prev_th >= 0 && std::fabs(prev_th - crit) < 1e-3 &&
                fe.r < prev_r - 1e-15)
                bad = true, why = "Fresnel reflectance not monotone at the critical angle";
            if (t == 0 && pp.ei == 1.0 && pp.et == 1.5 && std::fabs(fe.r - 0.04) > 1e-12)
                bad = true, why = "F(normal incidence, 1 -> 1.5) != 0.04";
            prev_r = fe.r;
            prev_th = t;
            if (bad) {
                st.real++;
                example(st, "eta %g -> %g, theta %.17g: %s (r = %.17g)", pp.ei, pp.et, t, why, fe.r);
            } else {
                st.agree++;
            }
        }
        // grazing incidence exactly: cos_i = 0 reflects everything
        st.rays++;
        RfFresnel g = rf_fresnel(pp.ei, pp.et, 0.0, RF_FRESNEL_EXACT);
        if (!(g.r == 1 || std::fabs(g.r - 1) < 1e-15)) {
            st.real++;
            example(st, "eta %g -> %g: F(cos 0) = %.17g, expected 1", pp.ei, pp.et, g.r);
        } else {
            st.agree++;
        }
    }
}

// ---- stress renders: no NaN or Inf may reach the film ---------------------------------------

void run_invalid(const Opts &o, Stats &st)
{
    Rng rng(o.seed * 31337 + 3);
    for (int variant = 0; variant < 6; variant++) {
        double s = std::pow(10.0, variant < 3 ? -4 + 5 * variant : -2 + 4 * (variant - 3)); // 1e-4,1e1,1e6 / 1e-2,1e2,1e6
        World w;
        RfMaterial glass = rf_material_default();
        glass.kd = rf_rgb(0.05, 0.05, 0.05);
        glass.ks = rf_rgb(0.5, 0.5, 0.5);
        glass.shininess = 50;
        glass.kr = rf_rgb(1, 1, 1);
        glass.kt = rf_rgb(1, 1, 1);
        glass.ior = 1.5;
        glass.flags |= RF_MAT_FRESNEL;
        int gi;
        rf_scene_add_material(&w.sc, &glass, &gi);
        RfVec3 at = rf_vec3(10 * s, -3 * s, 7 * s);
        if (variant < 3) { // a glass sphere on a floor, seen at grazing angles from just above it
            w.mat = gi;
            w.sphere(at, s, 0);
            w.icosphere(rf_vec3_add(at, rf_vec3(2.2 * s, 0, 0)), s, 2, 0, rng);
            w.mat = 0;
            w.plane(rf_vec3(0, 0, 1), at.z - s);
            w.sc.camera.eye = rf_vec3_add(at, rf_vec3(-6 * s, -1e-3 * s, -s + 1e-6 * s));
        } else { // tiny far spheres of glass
            w.mat = gi;
            for (int i = 0; i < 40; i++)
                w.sphere(rf_vec3_add(at, rf_vec3_scale(rng.ball(), 1e6 * s)), 1e-6 * s * rng.pow10(0, 4), 0);
            w.mat = 0;
            w.sc.camera.eye = rf_vec3_add(at, rf_vec3(0, 0, -2e6 * s));
        }
        RfLight li{};
        li.kind = RF_LIGHT_POINT;
        li.falloff = RF_FALLOFF_NONE;
        li.position = rf_vec3_add(at, rf_vec3(-s, 2 * s, 5 * s));
        li.intensity = rf_rgb(1, 1, 1);
        rf_scene_add_light(&w.sc, &li);
        w.sc.has_camera = 1;
        w.sc.camera.target = at;
        w.sc.camera.up = rf_vec3(0, 0, 1);
        if (variant >= 3)
            w.sc.camera.up = rf_vec3(0, 1, 0);
        w.sc.camera.d = 1;
        w.sc.camera.fov = variant < 3 ? 40 : 60;
        w.sc.camera.fov_reading = RF_FOV_EDGES;
        w.sc.render.max_depth = 12;
        w.sc.render.background = rf_rgb(0.2, 0.3, 0.4);
        RfRenderOptions ro = rf_render_options_default();
        int side = std::max(8, (int)std::ceil(std::sqrt((double)o.rays / 6 / 4)));
        ro.width = ro.height = std::min(side, 2048);
        ro.samples = 4;
        ro.threads = 1;
        ro.seed = o.seed;
        ro.fixed_offset = o.fixed_offset;
        RfImage img;
        RfRenderStats rs;
        if (rf_render(&w.sc, &ro, &img, &rs) != RF_OK) {
            st.real++;
            example(st, "stress render %d failed", variant);
            continue;
        }
        st.rays += (long)rs.primary_rays;
        st.real += (long)rs.invalid_samples;
        st.agree += (long)(rs.primary_rays - rs.invalid_samples);
        if (rs.invalid_samples)
            example(st, "stress render %d (scale %g): %llu invalid samples", variant, s,
                    (unsigned long long)rs.invalid_samples);
        for (size_t i = 0; i < (size_t)img.width * img.height * 3; i++)
            if (!std::isfinite(img.data[i])) {
                st.real++;
                example(st, "stress render %d: a non-finite pixel reached the film", variant);
                break;
            }
        rf_image_free(&img);
    }
}

} // namespace rv
