// refray-verify: the tracer's geometric decisions against exact arithmetic (issue 7,
// docs/verify.md). For each ray of a class: the tracer's answer (rf_tracer_intersect: hit or
// miss, nearest primitive, t) against the exact one (verify_oracle.cpp, CGAL Epeck); every
// disagreement is ambiguous (within kDelta * S of a boundary) or real. Also measured: shadow
// acne and light leaks over scene scales 1e-4 .. 1e6, the optics edge cases, and the
// invalid-sample count of stress renders. Exit status 1 on any real disagreement, 2 when a
// scene cannot be loaded or is outside the verifier's range (or on bad usage).
#include "verify.hpp"

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cstdarg>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <deque>
#include <exception>
#include <map>
#include <new>
#include <string>
#include <utility>
#include <vector>

#include "../src/cli/exit_codes.h"
#include "../src/cli/opt.h"
#include "refray/numeric.h"
#include "refray/optics.h"
#include "refray/scene_io.h"
#include "refray/transform.h"

namespace rv {
namespace {

// ---- options, statistics ----------------------------------------------------------------

struct Opts {
    long rays = 100000;
    uint64_t seed = 1;
    bool kernel = false; // the tracer under test is the kernel loop below (planted methods)
    RfTriangleMethod tri = RF_TRIANGLE_WATERTIGHT;
    RfSphereMethod sph = RF_SPHERE_STABLE;
    double fixed_offset = 0; // > 0: planted fixed epsilon instead of the offset policy
    const char *scene = nullptr; // one scene file: the classes over it, one row each
    long scene_rays = 0;         // rays per class in the aggregated rows of --stress scenes
};

// Plain data: children of --jobs send it back through a pipe.
struct Stats {
    char name[16];
    long rays, agree, amb, real, edge_miss, skipped; // skipped: rays not representable
    long acne_n, acne_d; // falsely occluded (or leaking) samples / samples
    double secs;
    int n_examples;
    char examples[3][480];
    char skip_note[480]; // the first ray skipped as not representable, and why
    int error;           // the row could not run (a scene not loaded or refused): error_msg
    char error_msg[480];
};

void example(Stats &st, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
void example(Stats &st, const char *fmt, ...)
{
    if (st.n_examples >= 3)
        return;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(st.examples[st.n_examples++], sizeof st.examples[0], fmt, ap);
    va_end(ap);
}

// A ray whose exact evaluation is impossible (an exception from CGAL or the allocator, a
// non-finite ray): counted as skipped, the first one kept for the report.
void not_representable(Stats &st, RfRay r, const char *why)
{
    st.rays++;
    st.skipped++;
    if (!st.skip_note[0])
        snprintf(st.skip_note, sizeof st.skip_note, "o=(%a,%a,%a) d=(%a,%a,%a): %s", r.origin.x, r.origin.y,
                 r.origin.z, r.dir.x, r.dir.y, r.dir.z, why);
}

void row_error(Stats &st, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
void row_error(Stats &st, const char *fmt, ...)
{
    st.error = 1;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(st.error_msg, sizeof st.error_msg, fmt, ap);
    va_end(ap);
}

bool finite_ray(RfRay r)
{
    return std::isfinite(r.origin.x) && std::isfinite(r.origin.y) && std::isfinite(r.origin.z) &&
           std::isfinite(r.dir.x) && std::isfinite(r.dir.y) && std::isfinite(r.dir.z);
}

// ---- random numbers (splitmix64: reproducible per seed and class) ------------------------

struct Rng {
    uint64_t s;
    explicit Rng(uint64_t seed) : s(seed * 0x9E3779B97F4A7C15ULL + 0x1234567ULL) {}
    uint64_t next()
    {
        uint64_t z = (s += 0x9E3779B97F4A7C15ULL);
        z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
        z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
        return z ^ (z >> 31);
    }
    double u() { return (double)(next() >> 11) * 0x1p-53; }
    double range(double lo, double hi) { return lo + (hi - lo) * u(); }
    double pow10(double lo, double hi) { return std::pow(10.0, range(lo, hi)); }
    int below(int n) { return (int)(next() % (uint64_t)n); }
    RfVec3 unit()
    {
        for (;;) {
            RfVec3 v = rf_vec3(range(-1, 1), range(-1, 1), range(-1, 1));
            double l = rf_vec3_length(v);
            if (l > 0.05 && l <= 1)
                return rf_vec3_scale(v, 1 / l);
        }
    }
    RfVec3 ball()
    {
        for (;;) {
            RfVec3 v = rf_vec3(range(-1, 1), range(-1, 1), range(-1, 1));
            if (rf_vec3_dot(v, v) <= 1)
                return v;
        }
    }
};

// Two unit vectors perpendicular to the unit vector k and to each other.
void frame(RfVec3 k, RfVec3 *u, RfVec3 *v)
{
    RfVec3 h = std::fabs(k.x) < 0.6 ? rf_vec3(1, 0, 0) : rf_vec3(0, 1, 0);
    *u = rf_vec3_normalize(rf_vec3_cross(k, h));
    *v = rf_vec3_cross(k, *u);
}

// ---- scenes built in code -------------------------------------------------------------------

// A closed mesh and a region certainly inside it: a ray from there must hit the mesh. A mesh
// of an object (object >= 0) is closed in each of the object's placements: the region is the
// ball (c, r_in) in object space.
struct Mesh {
    bool is_box;
    RfVec3 c;
    double r_in;
    RfVec3 lo, hi;
    int object;
};

struct World {
    RfScene sc;
    int mat = 0;
    unsigned in_obj = 0; // RF_PRIM_IN_OBJECT while an object is being built
    int cur_object = -1;
    std::vector<int> prim_mesh; // per primitive: closed mesh index or -1
    std::vector<Mesh> meshes;
    std::unique_ptr<Oracle> orc;
    RfTracer *tr = nullptr;
    RfAabb bounds;
    std::vector<int> mesh_paths; // paths placing an object that holds a closed mesh
    // the generators' pick lists, per kind mask and level (made on first use)
    mutable std::map<unsigned, std::vector<std::vector<int>>> picks;

    World()
    {
        rf_scene_init(&sc);
        RfMaterial m = rf_material_default();
        m.kd = rf_rgb(0.8, 0.8, 0.8);
        rf_scene_add_material(&sc, &m, &mat);
        bounds = rf_aabb_empty();
    }
    ~World()
    {
        rf_tracer_free(tr);
        rf_scene_free(&sc);
    }
    World(const World &) = delete;
    World &operator=(const World &) = delete;

    void grow(RfVec3 p)
    {
        if (!in_obj)
            bounds = rf_aabb_add_point(bounds, p);
    }
    void add(RfPrimitive p, int mesh)
    {
        char msg[256];
        p.material = mat;
        p.flags |= in_obj;
        if (rf_scene_add_primitive(&sc, &p, msg, sizeof msg) == RF_OK)
            prim_mesh.push_back(mesh);
    }
    void sphere(RfVec3 c, double r, unsigned flags)
    {
        RfPrimitive p{};
        p.type = RF_PRIM_SPHERE;
        p.flags = flags;
        p.u.sphere.center = c;
        p.u.sphere.radius = r;
        add(p, -1);
        RfVec3 rr = rf_vec3(r, r, r);
        grow(rf_vec3_sub(c, rr));
        grow(rf_vec3_add(c, rr));
    }
    void poly(const RfVec3 *v, int n, unsigned flags, int mesh)
    {
        RfPrimitive p{};
        size_t first, nfirst;
        if (rf_scene_add_vertices(&sc, v, nullptr, n, &first, &nfirst) != RF_OK)
            return;
        p.type = n == 3 ? RF_PRIM_TRIANGLE : RF_PRIM_POLYGON;
        p.flags = flags;
        p.u.poly.first = first;
        p.u.poly.nfirst = nfirst;
        p.u.poly.count = n;
        add(p, mesh);
        for (int i = 0; i < n; i++)
            grow(v[i]);
    }
    void plane(RfVec3 n, double offset)
    {
        RfPrimitive p{};
        p.type = RF_PRIM_PLANE;
        p.flags = RF_PRIM_TWO_SIDED;
        p.u.plane.normal = n;
        p.u.plane.offset = offset;
        add(p, -1);
    }
    void cone(RfVec3 base, double rb, RfVec3 apex, double ra, unsigned flags)
    {
        RfPrimitive p{};
        p.type = RF_PRIM_CONE;
        p.flags = flags;
        p.u.cone.base = base;
        p.u.cone.base_radius = rb;
        p.u.cone.apex = apex;
        p.u.cone.apex_radius = ra;
        add(p, -1);
        double m = std::max(rb, ra);
        for (RfVec3 c : {base, apex}) {
            grow(rf_vec3_sub(c, rf_vec3(m, m, m)));
            grow(rf_vec3_add(c, rf_vec3(m, m, m)));
        }
    }
    // object NAME ... end (§4.8): the primitives added in between belong to the object
    int begin_object(const char *name)
    {
        int o = -1;
        rf_scene_add_object(&sc, name, RfSrcLoc{0, 0}, &o);
        in_obj = RF_PRIM_IN_OBJECT;
        cur_object = o;
        return o;
    }
    void end_object(int o)
    {
        sc.objects[o].count = sc.prim_count - sc.objects[o].first;
        in_obj = 0;
        cur_object = -1;
    }
    void instance(int object, RfMat4 m)
    {
        size_t idx;
        if (rf_scene_add_instance(&sc, object, m, &idx) != RF_OK)
            return;
        RfPrimitive p{};
        p.type = RF_PRIM_INSTANCE;
        p.flags = RF_PRIM_TWO_SIDED;
        p.u.instance = idx;
        add(p, -1);
    }
    // The icosahedron subdivided `level` times, vertices on radius r (times 1 + jitter*U(-1,1)):
    // closed, two-sided triangles sharing their vertices' doubles exactly.
    void icosphere(RfVec3 c, double r, int level, double jitter, Rng &rng)
    {
        const double g = (1 + std::sqrt(5.0)) / 2;
        std::vector<RfVec3> v = {{-1, g, 0}, {1, g, 0}, {-1, -g, 0}, {1, -g, 0}, {0, -1, g}, {0, 1, g},
                                 {0, -1, -g}, {0, 1, -g}, {g, 0, -1}, {g, 0, 1}, {-g, 0, -1}, {-g, 0, 1}};
        std::vector<std::array<int, 3>> f = {{0, 11, 5}, {0, 5, 1}, {0, 1, 7}, {0, 7, 10}, {0, 10, 11},
                                             {1, 5, 9}, {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                                             {3, 9, 4}, {3, 4, 2}, {3, 2, 6}, {3, 6, 8}, {3, 8, 9},
                                             {4, 9, 5}, {2, 4, 11}, {6, 2, 10}, {8, 6, 7}, {9, 8, 1}};
        for (int l = 0; l < level; l++) {
            std::map<std::pair<int, int>, int> mid;
            auto midpoint = [&](int a, int b) {
                auto key = std::make_pair(std::min(a, b), std::max(a, b));
                auto it = mid.find(key);
                if (it != mid.end())
                    return it->second;
                v.push_back(rf_vec3_scale(rf_vec3_add(v[(size_t)a], v[(size_t)b]), 0.5));
                return mid[key] = (int)v.size() - 1;
            };
            std::vector<std::array<int, 3>> nf;
            for (auto &t : f) {
                int a = midpoint(t[0], t[1]), b = midpoint(t[1], t[2]), cc = midpoint(t[2], t[0]);
                nf.push_back({t[0], a, cc});
                nf.push_back({t[1], b, a});
                nf.push_back({t[2], cc, b});
                nf.push_back({a, b, cc});
            }
            f.swap(nf);
        }
        for (auto &p : v)
            p = rf_vec3_add(c, rf_vec3_scale(rf_vec3_normalize(p), r * (1 + jitter * rng.range(-1, 1))));
        int id = (int)meshes.size();
        meshes.push_back(Mesh{false, c, 0.3 * r, {}, {}, cur_object});
        for (auto &t : f) {
            RfVec3 tri[3] = {v[(size_t)t[0]], v[(size_t)t[1]], v[(size_t)t[2]]};
            poly(tri, 3, RF_PRIM_TWO_SIDED, id);
        }
    }
    // The box [0, n h]^3 + corner, each face an n x n grid of squares split into two triangles
    // along alternating diagonals. With h a power of two and a dyadic corner every vertex and
    // every edge point k/2^10 of the way is exact, so rays can pass exactly through them.
    void grid_cube(RfVec3 corner, int n, double h)
    {
        int id = (int)meshes.size();
        RfVec3 hi = rf_vec3_add(corner, rf_vec3(n * h, n * h, n * h));
        RfVec3 m = rf_vec3(n * h * 0.2, n * h * 0.2, n * h * 0.2);
        meshes.push_back(Mesh{true, {}, 0, rf_vec3_add(corner, m), rf_vec3_sub(hi, m), -1});
        for (int a = 0; a < 3; a++)
            for (int side = 0; side < 2; side++)
                for (int i = 0; i < n; i++)
                    for (int j = 0; j < n; j++) {
                        auto P = [&](int ii, int jj) {
                            double c[3];
                            c[a] = side * n * h;
                            c[(a + 1) % 3] = ii * h;
                            c[(a + 2) % 3] = jj * h;
                            return rf_vec3_add(corner, rf_vec3(c[0], c[1], c[2]));
                        };
                        RfVec3 p00 = P(i, j), p10 = P(i + 1, j), p11 = P(i + 1, j + 1), p01 = P(i, j + 1);
                        if ((i + j) % 2) {
                            RfVec3 t1[3] = {p00, p10, p11}, t2[3] = {p00, p11, p01};
                            poly(t1, 3, RF_PRIM_TWO_SIDED, id);
                            poly(t2, 3, RF_PRIM_TWO_SIDED, id);
                        } else {
                            RfVec3 t1[3] = {p00, p10, p01}, t2[3] = {p10, p11, p01};
                            poly(t1, 3, RF_PRIM_TWO_SIDED, id);
                            poly(t2, 3, RF_PRIM_TWO_SIDED, id);
                        }
                    }
    }
    // An exactly planar quad p0, p0+u, p0+u+v, p0+v: u, v small integers times 2^e, p0 a
    // multiple of 2^(e-20), so every sum is exact.
    void quad(RfVec3 p0, double s, Rng &rng, unsigned flags)
    {
        double q = std::ldexp(1.0, (int)std::floor(std::log2(s)) - 20);
        p0 = rf_vec3(std::round(p0.x / q) * q, std::round(p0.y / q) * q, std::round(p0.z / q) * q);
        double e = std::ldexp(1.0, (int)std::floor(std::log2(s)) - 3);
        RfVec3 u, v;
        do {
            u = rf_vec3(rng.below(9) - 4, rng.below(9) - 4, rng.below(9) - 4);
            v = rf_vec3(rng.below(9) - 4, rng.below(9) - 4, rng.below(9) - 4);
        } while (rf_vec3_length(rf_vec3_cross(u, v)) < 4);
        u = rf_vec3_scale(u, e);
        v = rf_vec3_scale(v, e);
        RfVec3 pts[4] = {p0, rf_vec3_add(p0, u), rf_vec3_add(rf_vec3_add(p0, u), v), rf_vec3_add(p0, v)};
        poly(pts, 4, flags, -1);
    }
    // A star or gear outline of 2 k vertices (k = 4 .. 20, radii alternating between s and
    // s * U(0.2, 0.7), gear teeth or spikes): non-convex. exact: in the plane p0 + i u + j v
    // with small integer vectors u, v times a power of two and integer (i, j), so the vertices
    // are exactly coplanar and every edge point k/2^10 of the way is exact; otherwise in a
    // random plane with coordinates rounded to 7 significant digits (as in the SPD's gears).
    void star(RfVec3 c, double s, bool exact, unsigned flags, Rng &rng)
    {
        int k = 4 + rng.below(17);
        double rin = rng.range(0.2, 0.7), tw = rng.range(0, 1);
        std::vector<RfVec3> pts;
        if (exact) {
            double q = std::ldexp(1.0, (int)std::floor(std::log2(s)) - 26);
            RfVec3 p0 = rf_vec3(std::round(c.x / q) * q, std::round(c.y / q) * q, std::round(c.z / q) * q);
            double e = std::ldexp(1.0, (int)std::floor(std::log2(s)) - 8);
            RfVec3 u, v;
            do {
                u = rf_vec3(rng.below(5) - 2, rng.below(5) - 2, rng.below(5) - 2);
                v = rf_vec3(rng.below(5) - 2, rng.below(5) - 2, rng.below(5) - 2);
            } while (rf_vec3_length(rf_vec3_cross(u, v)) < 2);
            for (int i = 0; i < 2 * k; i++) {
                double a = RF_PI * (i + (i % 2 ? tw : 0)) / k, r = (i % 2 ? rin : 1.0) * 64;
                double ii = std::round(r * std::cos(a)), jj = std::round(r * std::sin(a));
                pts.push_back(rf_vec3_add(p0, rf_vec3_add(rf_vec3_scale(u, ii * e), rf_vec3_scale(v, jj * e))));
            }
        } else {
            RfVec3 n = rng.unit(), u, v;
            frame(n, &u, &v);
            for (int i = 0; i < 2 * k; i++) {
                double a = RF_PI * (i + (i % 2 ? tw : 0)) / k, r = (i % 2 ? rin : 1.0) * s;
                RfVec3 p = rf_vec3_add(c, rf_vec3_add(rf_vec3_scale(u, r * std::cos(a)), rf_vec3_scale(v, r * std::sin(a))));
                char b[3][40];
                snprintf(b[0], sizeof b[0], "%.7g", p.x);
                snprintf(b[1], sizeof b[1], "%.7g", p.y);
                snprintf(b[2], sizeof b[2], "%.7g", p.z);
                pts.push_back(rf_vec3(std::atof(b[0]), std::atof(b[1]), std::atof(b[2])));
            }
        }
        poly(pts.data(), (int)pts.size(), flags, -1);
    }
    // Spheres, a closed jittered icosphere, quads, loose triangles and a plane, all scaled by s
    // around `at` (the uniform, far and surface classes).
    void mixed(RfVec3 at, double s, Rng &rng)
    {
        icosphere(at, 0.6 * s, 2, 1e-3, rng);
        for (int i = 0; i < 8; i++)
            sphere(rf_vec3_add(at, rf_vec3_scale(rng.ball(), 1.5 * s)), s * rng.range(0.05, 0.4),
                   i % 2 ? RF_PRIM_TWO_SIDED : 0);
        for (int i = 0; i < 4; i++)
            quad(rf_vec3_add(at, rf_vec3_scale(rng.ball(), 1.5 * s)), s, rng, RF_PRIM_TWO_SIDED);
        for (int i = 0; i < 4; i++) {
            RfVec3 c = rf_vec3_add(at, rf_vec3_scale(rng.ball(), 1.5 * s));
            RfVec3 t[3];
            for (auto &p : t)
                p = rf_vec3_add(c, rf_vec3_scale(rng.ball(), 0.5 * s));
            poly(t, 3, i % 2 ? RF_PRIM_TWO_SIDED : 0, -1);
        }
        RfVec3 n = rng.unit();
        plane(n, rf_vec3_dot(n, at) - 1.8 * s);
    }
    // Throws SceneError (the oracle's range and model checks).
    void finish()
    {
        if (sc.instance_count > 0) { // objects placed by instances: the scene's own bounds
            RfVec3 lo, hi;
            if (rf_scene_bounds(&sc, &lo, &hi)) {
                bounds.lo = lo;
                bounds.hi = hi;
            }
        }
        orc.reset(new Oracle(&sc));
        if (!(bounds.lo.x <= bounds.hi.x)) {
            // every placement reaches a plane (rf_scene_bounds skips those): the bounded items
            // of every path, placed
            for (int p = 0; p < orc->path_count(); p++)
                for (int i : orc->level_items(orc->path(p).level)) {
                    const Item &it = orc->items()[(size_t)i];
                    if (it.kind == ITEM_INSTANCE || !(it.box.lo.x <= it.box.hi.x))
                        continue;
                    for (int k = 0; k < 8; k++) {
                        RfVec3 c = rf_vec3(k & 1 ? it.box.hi.x : it.box.lo.x, k & 2 ? it.box.hi.y : it.box.lo.y,
                                           k & 4 ? it.box.hi.z : it.box.lo.z);
                        LV q = orc->path(p).to_world.point(lv(c));
                        bounds = rf_aabb_add_point(bounds, rf_vec3((double)q.x, (double)q.y, (double)q.z));
                    }
                }
            if (!(bounds.lo.x <= bounds.hi.x)) // planes only
                bounds = RfAabb{rf_vec3(-1, -1, -1), rf_vec3(1, 1, 1)};
        }
        if (rf_tracer_create(&sc, &tr) != RF_OK) {
            fprintf(stderr, "refray-verify: rf_tracer_create failed\n");
            exit(2);
        }
        for (int p = 1; p < orc->path_count(); p++)
            for (const Mesh &m : meshes)
                if (m.object >= 0 && orc->path(p).level == m.object + 1) {
                    mesh_paths.push_back(p);
                    break;
                }
    }
    int interior_mesh(RfVec3 o) const
    {
        for (size_t i = 0; i < meshes.size(); i++) {
            const Mesh &m = meshes[i];
            if (m.object >= 0) {
                for (int p : mesh_paths) {
                    const Path &P = orc->path(p);
                    if (P.level == m.object + 1 && len(sub(P.to_obj.point(lv(o)), lv(m.c))) < (L)m.r_in)
                        return (int)i;
                }
                continue;
            }
            if (m.is_box ? (o.x > m.lo.x && o.y > m.lo.y && o.z > m.lo.z && o.x < m.hi.x && o.y < m.hi.y && o.z < m.hi.z)
                         : rf_vec3_length(rf_vec3_sub(o, m.c)) < m.r_in)
                return (int)i;
        }
        return -1;
    }
};

// ---- the tracer under test ----------------------------------------------------------------

struct TraceAns {
    int prim;
    double t;
};

// The library's tracer (rf_tracer_intersect), or with --triangle/--sphere the same nearest-hit
// loop over the §3.5 kernels with the chosen methods (the planted-bug mode: the world's
// triangles, polygons' included, spheres, planes and cones; instances are not in this loop).
TraceAns tracer_query(const World &w, const Opts &o, RfRay r, double t_max)
{
    if (!o.kernel) {
        RfSurfaceHit h;
        int p = rf_tracer_intersect(w.tr, &r, 0.0, t_max, &h);
        return {p, p >= 0 ? h.t : NAN};
    }
    std::vector<Cand> cand;
    w.orc->candidates(r, cand);
    TraceAns best{-1, NAN};
    for (const Cand &cd : cand) {
        if (cd.path != 0)
            continue;
        const Item &it = w.orc->items()[(size_t)cd.item];
        RfHit h;
        int ok = 0;
        double t_min = 0.0;
    again:
        if (it.kind == ITEM_TRI)
            ok = rf_intersect_triangle(r, RfTriangle{it.p[0], it.p[1], it.p[2]}, o.tri, t_min, t_max, &h);
        else if (it.kind == ITEM_SPHERE)
            ok = rf_intersect_sphere(r, it.s, o.sph, t_min, t_max, &h);
        else if (it.kind == ITEM_PLANE)
            ok = rf_intersect_plane(r, it.pl, t_min, t_max, &h);
        else if (it.kind == ITEM_CONE)
            ok = rf_intersect_cone(r, it.cone, t_min, t_max, &h);
        else
            ok = 0;
        if (!ok)
            continue;
        if (!(it.flags & RF_PRIM_TWO_SIDED)) {
            int front = rf_vec3_dot(r.dir, h.normal) < 0.0;
            if (front == !!(it.flags & RF_PRIM_INSIDE)) {
                // the hidden side of a sphere or cone: its far root may face the ray (tracer.c)
                if (it.kind == ITEM_SPHERE || it.kind == ITEM_CONE) {
                    t_min = std::nextafter(h.t, HUGE_VAL);
                    goto again;
                }
                continue;
            }
        }
        t_max = h.t;
        best = {it.prim, h.t};
    }
    return best;
}

// ---- margins to the boundaries (long double, for the classification only) -----------------

// The local rays of one world ray, per path (made once per check).
struct LocalRays {
    const Oracle &orc;
    RfRay ray;
    std::deque<std::pair<int, LocalRay>> v;
    LocalRays(const Oracle &o, RfRay r) : orc(o), ray(r) {}
    const LocalRay &get(int path)
    {
        for (const auto &x : v)
            if (x.first == path)
                return x.second;
        v.emplace_back(path, orc.local_ray(path, ray));
        return v.back().second;
    }
};

struct Margin {
    L m, S; // the configuration is ambiguous when m <= kDelta * S
    bool near() const { return !(m > (L)kDelta * S); }
};
// A margin given as the smallest ratio distance / bound over several boundaries.
Margin ratio_margin(L r) { return {r, (L)(1 / kDelta)}; }

// The ray's deviation in an object's space (the tracer's rounded object-space ray against the
// exact one), as a distance near parameter t: dev_o + dev_d t.
L dev_at(const LocalRay &lr, L t) { return lr.dev_o + (lr.dev_d > 0 ? lr.dev_d * std::fabs(t) : 0); }

// A cone in the tracer's own terms (rf_intersect_cone): unit axis k, slope m, the quadratic
// a t^2 + 2 bh t + c of the ray with coefficients computed as the tracer does (here in long
// double), and the sizes of the terms each coefficient subtracts (Am, Bm, Cm): the tracer
// evaluates them, and the discriminant bh^2 - a c, without any stabilisation, so its
// decisions are exact only for coefficients perturbed by ~eps times those sizes.
// --cone-bound geometric: the sphere's kind of bound instead (kDelta times the sizes |o - base|,
// the length and the radius, as distances from tangency and from the surface), which the
// kernel does not meet (docs/verify.md, "Cones").
bool g_cone_geometric = false;

struct ConeGeom {
    L H, m, oz, dz, a, bh, c, disc, dl, ol, Am, Bm, Cm, Sabs;
    L rb, S, opl, r0; // geometric bound: the size, |o_perp|, the radius at the origin's position
    L da, dbh, dc; // the coefficients' change under the object-space ray's deviation (instances)
};

ConeGeom cone_geom(const Item &it, const LocalRay &lr)
{
    ConeGeom g;
    const RfCone &cn = it.cone;
    LV B = lv(cn.base), A = sub(lv(cn.apex), B);
    g.H = len(A);
    LV k = scale(A, 1 / g.H);
    L rb = cn.base_radius;
    g.m = ((L)cn.apex_radius - rb) / g.H;
    LV orel = sub(lr.o, B), d = lr.d;
    g.dz = dot(d, k);
    g.oz = dot(orel, k);
    LV dp = sub(d, scale(k, g.dz)), op = sub(orel, scale(k, g.oz));
    L r0 = rb + g.m * g.oz;
    g.a = dot(dp, dp) - g.m * g.m * g.dz * g.dz;
    g.bh = dot(op, dp) - g.m * g.dz * r0;
    g.c = dot(op, op) - r0 * r0;
    g.disc = g.bh * g.bh - g.a * g.c;
    g.dl = len(d);
    g.ol = len(orel);
    L am = std::fabs(g.m), R0m = rb + am * g.ol, m2 = 1 + g.m * g.m;
    g.Am = g.dl * g.dl * m2;
    g.Bm = g.dl * (g.ol + am * R0m);
    g.Cm = g.ol * g.ol + R0m * R0m;
    g.Sabs = len(lr.o) + len(B) + g.H;
    g.da = 2 * m2 * g.dl * lr.dev_d;
    g.dbh = m2 * (g.ol * lr.dev_d + g.dl * lr.dev_o) + am * R0m * lr.dev_d + am * am * g.dl * lr.dev_o;
    g.dc = 2 * (g.ol + am * R0m) * lr.dev_o;
    g.rb = rb;
    g.S = g.ol + g.H + std::max(rb, (L)cn.apex_radius);
    g.opl = len(op);
    g.r0 = r0;
    return g;
}

// The tolerance on a cone root t: the root's change under coefficient errors of kDelta times
// their sizes (implicit differentiation: |da t^2 + 2 dbh t + dc| / |2 sqrt(disc)|) and under
// the discriminant's own rounding (|t| eps_D / (2 disc)), plus the instance deviation.
L cone_band(const ConeGeom &g, L t)
{
    L sd = std::sqrt(std::fabs(g.disc)), at = std::fabs(t);
    if (!(sd > 0))
        return HUGE_VALL;
    if (g_cone_geometric) { // as for spheres: kDelta max(S, t |d|) / (cos |d|)
        L rho = std::fabs(g.rb + g.m * (g.oz + t * g.dz));
        L cosv = std::min((L)1, sd / (std::max(rho, (L)kDelta * g.S) * std::sqrt(1 + g.m * g.m) * g.dl));
        return (L)kDelta * std::max(g.S, at * g.dl) / (cosv * g.dl) + 4 * (g.da * t * t + 2 * g.dbh * at + g.dc) / (2 * sd);
    }
    return (L)kDelta * ((g.Am * t * t + 2 * g.Bm * at + g.Cm) / (2 * sd) + at * (g.Bm * g.Bm + g.Am * g.Cm) / (sd * sd)) +
           4 * (g.da * t * t + 2 * g.dbh * at + g.dc) / (2 * sd);
}

// The cone's boundaries: tangency (disc = 0), the origin on the surface (c = 0), and each root
// at a rim (axial position 0 or H, with the root's tolerance). Returned as a ratio.
Margin cone_margin(const ConeGeom &g, const LocalRay &lr)
{
    L r;
    if (g_cone_geometric) {
        // the distance from tangency |rho - l| = |disc| / (|a| (rho + l)) (a cylinder: l the
        // line's distance from the axis), rho at the parabola's vertex; from the surface
        // | |o_perp| - r0 | = |c| / (|o_perp| + r0)
        r = HUGE_VALL;
        if (g.a != 0) {
            L tv = -g.bh / g.a, rho = std::max(std::fabs(g.rb + g.m * (g.oz + tv * g.dz)), (L)kDelta * g.S);
            r = std::fabs(g.disc) / (std::fabs(g.a) * 2 * rho) / ((L)kDelta * g.S + 4 * dev_at(lr, tv));
        }
        r = std::min(r, std::fabs(g.c) / (g.opl + std::fabs(g.r0)) / ((L)kDelta * g.S + 4 * lr.dev_o));
    } else {
        r = std::fabs(g.disc) / ((L)kDelta * 2 * (g.Bm * g.Bm + g.Am * g.Cm) + 4 * (2 * g.Bm * g.dbh + g.Am * g.dc + g.Cm * g.da));
        r = std::min(r, std::fabs(g.c) / ((L)kDelta * 2 * g.Cm + 4 * g.dc));
    }
    if (g.disc >= 0) {
        L ts[2];
        int n = 0;
        L sq = std::sqrt(g.disc), q = -(g.bh + (g.bh < 0 ? -sq : sq));
        if (g.a != 0 && q != 0) {
            ts[n++] = q / g.a;
            ts[n++] = g.c / q;
        } else if (q != 0) {
            ts[n++] = g.c / q;
        }
        for (int i = 0; i < n; i++) {
            L t = ts[i];
            if (!std::isfinite(t))
                continue;
            L z = g.oz + t * g.dz, mr = std::min(std::fabs(z), std::fabs(z - g.H));
            L bound = (L)kDelta * (g.Sabs + std::fabs(t) * g.dl) + std::fabs(g.dz) * cone_band(g, t) + 4 * dev_at(lr, t);
            r = std::min(r, mr / bound);
        }
    }
    return ratio_margin(r);
}

// How far the ray is from changing its answer for this item: triangles: the distance from the
// ray's line to each edge line (the perpendicular shift that puts the ray on the edge) and from
// the origin to the plane (t = 0); spheres: | |v| - r | (tangency) and | |f| - r | (origin on
// the sphere); planes: the origin's distance and the ray's tilt out of the plane; cones: see
// cone_margin. In an object's space the object-space ray's deviation (the tracer's rounded
// inverse and transform) is added: 4 (dev_o + dev_d R / |d|) at the item's distance R.
Margin margin(const Item &it, const LocalRay &lr)
{
    LV o = lr.o, d = lr.d;
    L dl = len(d);
    switch (it.kind) {
    case ITEM_TRI: {
        LV p[3] = {lv(it.p[0]), lv(it.p[1]), lv(it.p[2])};
        L S = 0, m = HUGE_VALL;
        for (int k = 0; k < 3; k++) {
            S = std::max(S, len(sub(p[k], o)));
            LV a = p[k], e = sub(p[(k + 1) % 3], p[k]), w = sub(a, o), c = cross(d, e);
            L cl = len(c);
            m = std::min(m, cl > 0 ? std::fabs(dot(w, c)) / cl : len(cross(w, d)) / dl);
        }
        LV n = cross(sub(p[1], p[0]), sub(p[2], p[0]));
        L nl = len(n);
        if (nl > 0)
            m = std::min(m, std::fabs(dot(n, sub(p[0], o))) / nl);
        if (lr.dev_o > 0 || lr.dev_d > 0)
            S += 4 * dev_at(lr, S / dl) / (L)kDelta;
        return {m, S};
    }
    case ITEM_SPHERE: {
        LV f = sub(o, lv(it.s.center));
        L r = it.s.radius, fl = len(f), vl = len(cross(f, d)) / dl;
        L S = fl + r;
        if (lr.dev_o > 0 || lr.dev_d > 0)
            S += 4 * dev_at(lr, S / dl) / (L)kDelta;
        return {std::min(std::fabs(vl - r), std::fabs(fl - r)), S};
    }
    case ITEM_PLANE: {
        LV n = lv(it.pl.normal);
        L nl = len(n), S = std::max(len(o), std::fabs((L)it.pl.offset)) + 1e-300L;
        L m = std::fabs(dot(n, o) - it.pl.offset) / nl, cosv = std::fabs(dot(n, d)) / (nl * dl);
        if (lr.dev_o > 0 || lr.dev_d > 0) {
            L den = dot(n, d), tp = den != 0 ? ((L)it.pl.offset - dot(n, o)) / den : HUGE_VALL;
            S += 4 * dev_at(lr, tp) / (L)kDelta;
            cosv = std::max((L)0, cosv - 4 * lr.dev_d / dl);
        }
        return {std::min(m, cosv * S), S};
    }
    case ITEM_CONE:
        return cone_margin(cone_geom(it, lr), lr);
    default:
        return {0, 1};
    }
}

// |cos| of the angle between the ray and the surface normal at parameter t.
L cos_at(const Item &it, const LocalRay &lr, L t)
{
    LV d = lr.d;
    L dl = len(d);
    if (it.kind == ITEM_TRI) {
        LV n = cross(sub(lv(it.p[1]), lv(it.p[0])), sub(lv(it.p[2]), lv(it.p[0])));
        return std::fabs(dot(n, d)) / (len(n) * dl);
    }
    if (it.kind == ITEM_SPHERE) {
        LV q = sub(lr.o, lv(it.s.center));
        q = {q.x + t * d.x, q.y + t * d.y, q.z + t * d.z};
        return std::fabs(dot(q, d)) / (it.s.radius * dl);
    }
    if (it.kind == ITEM_PLANE) {
        LV n = lv(it.pl.normal);
        return std::fabs(dot(n, d)) / (len(n) * dl);
    }
    return 1;
}

// The tolerance on t (units of |dir|) for an item hit near t: kDelta S / cos, with S grown to
// the hit's distance t |dir| (a plane's t = num / <d,n> has the relative error eps / cos of
// its denominator, i.e. an error in position of eps t |d| / cos). Cones: their own band
// (cone_band).
L t_band(const Item &it, const LocalRay &lr, L t)
{
    if (it.kind == ITEM_CONE)
        return cone_band(cone_geom(it, lr), t);
    Margin m = margin(it, lr);
    L dl = len(lr.d), c = std::max(cos_at(it, lr, t), (L)1e-300);
    return (L)kDelta * std::max(m.S, std::fabs(t) * dl) / (c * dl);
}

// ---- one ray: tracer against the exact answer ----------------------------------------------

enum Verdict { AGREE, AMBIG, REAL };

struct Check {
    Verdict v;
    bool edge_miss;
    TraceAns t;
    ExactHit e;
};

// Testing hook (tests/test_stress.c): REFRAY_VERIFY_FAULT=N makes every N-th exact evaluation
// throw, as CGAL does on a value it cannot represent.
long g_fault_every = 0, g_fault_count = 0;

// May throw (the oracle's exact arithmetic): check_and_tally counts such rays as skipped.
Check check_ray(const World &w, const Opts &o, RfRay r, int interior)
{
    Check c{AGREE, false, tracer_query(w, o, r, HUGE_VAL), {}};
    const Oracle &orc = *w.orc;
    const auto &items = orc.items();
    std::vector<Cand> cands;
    orc.candidates(r, cands);
    LocalRays lrs(orc, r);
    // the tracer's primitive: its items in the world, or (an object's primitive: the tracer
    // does not say through which instance) every placement of it among the candidates
    std::vector<Cand> tc;
    if (c.t.prim >= 0) {
        for (int i : orc.items_of(c.t.prim))
            if (items[(size_t)i].level == 0)
                tc.push_back(Cand{i, 0});
        for (const Cand &cd : cands)
            if (cd.path != 0 && items[(size_t)cd.item].prim == c.t.prim)
                tc.push_back(cd);
    }
    // the tolerance for the tracer's t on its own primitive
    L tol = -1;
    for (const Cand &cd : tc)
        tol = std::max(tol, t_band(items[(size_t)cd.item], lrs.get(cd.path), c.t.t));
    if (std::isnan(tol))
        tol = HUGE_VALL;
    if (g_fault_every > 0 && ++g_fault_count % g_fault_every == 0)
        throw std::range_error("injected fault (REFRAY_VERIFY_FAULT)");
    c.e = orc.nearest(r, cands, c.t.t, (double)tol);
    const ExactHit &e = c.e;
    if (e.inconsistent) {
        c.v = REAL;
        return c;
    }
    bool t_hit = c.t.prim >= 0;
    if (!t_hit && !e.hit)
        return c;
    bool same = false;
    for (const Cand &cd : e.items)
        same |= t_hit && items[(size_t)cd.item].prim == c.t.prim;
    bool amb = e.coplanar;
    for (const Cand &cd : e.items)
        amb |= margin(items[(size_t)cd.item], lrs.get(cd.path)).near();
    for (const Cand &cd : tc)
        amb |= margin(items[(size_t)cd.item], lrs.get(cd.path)).near();
    if (same) {
        if (e.t_ok)
            return c;
        c.v = amb ? AMBIG : REAL; // right primitive, t outside the bound (or the other root)
        return c;
    }
    bool tie = false;
    if (t_hit && e.hit) {
        L band = 0;
        for (const Cand &cd : e.items)
            band = std::max(band, t_band(items[(size_t)cd.item], lrs.get(cd.path), e.t));
        band = std::max(band, tol);
        tie = !(std::fabs((L)c.t.t - e.t) > band);
        amb |= tie;
    }
    // A ray from inside a closed mesh whose exact first hit is on the mesh must not get out:
    // a tracer miss, or a hit beyond the mesh, is real whatever the margins (watertightness).
    // Unless the first contact only grazes the surface, within rounding of a silhouette edge:
    // a ridge of a non-convex mesh seen from inside (star prisms), whose two faces the ray sees
    // from opposite sides. The exact ray touches the ridge, or passes an ulp inside it, and stays
    // in the solid; a tracer that passes an ulp beside it has not let it out. Such a ray (near
    // an edge: amb) whose exact contact has faces of both sides, or which the tracer next sees
    // leave the same mesh (from inside, seeing a world triangle's back: outward windings), is
    // ambiguous. A ray that got out would meet the mesh again from outside, if at all.
    int em = e.hit ? w.prim_mesh[(size_t)items[(size_t)e.items[0].item].prim] : -1;
    bool grazes = false;
    if (amb && interior >= 0 && em == interior) {
        int pos = 0, neg = 0;
        for (const Cand &cd : e.items) {
            int f = cd.path == 0 ? orc.facing(cd.item, r.dir) : 0;
            pos += f > 0, neg += f < 0;
        }
        grazes = pos > 0 && neg > 0;
        if (t_hit && w.prim_mesh[(size_t)c.t.prim] == interior)
            for (int i : orc.items_of(c.t.prim))
                grazes |= items[(size_t)i].level == 0 && orc.facing(i, r.dir) > 0;
    }
    if (interior >= 0 && em == interior && !grazes && (!t_hit || (!tie && c.t.t > e.t))) {
        c.v = REAL;
        c.edge_miss = amb;
        return c;
    }
    c.v = amb ? AMBIG : REAL;
    return c;
}

void tally(Stats &st, const World &w, RfRay r, const Check &c)
{
    st.rays++;
    switch (c.v) {
    case AGREE: st.agree++; break;
    case AMBIG: st.amb++; break;
    case REAL:
        st.real++;
        if (c.edge_miss)
            st.edge_miss++;
        example(st, "o=(%a,%a,%a) d=(%a,%a,%a): tracer prim %d t=%.17g, exact prim %d t=%.17Lg%s%s",
                r.origin.x, r.origin.y, r.origin.z, r.dir.x, r.dir.y, r.dir.z, c.t.prim, c.t.t,
                c.e.hit ? w.orc->items()[(size_t)c.e.items[0].item].prim : -1, c.e.t,
                c.edge_miss ? " (through an edge of a closed mesh)" : "",
                c.e.inconsistent ? " (CGAL sphere test disagrees with the exact roots)" : "");
        break;
    }
}

// One ray checked and counted; a ray the oracle cannot evaluate exactly (an exception: CGAL's
// conversions, the allocator) or that is not finite is counted as skipped (not representable).
void check_and_tally(Stats &st, const World &w, const Opts &o, RfRay r, int interior)
{
    if (!finite_ray(r)) {
        not_representable(st, r, "the ray is not finite");
        return;
    }
    try {
        Check c = check_ray(w, o, r, interior);
        tally(st, w, r, c);
    } catch (const std::bad_alloc &) {
        not_representable(st, r, "out of memory in the exact evaluation");
    } catch (const std::exception &ex) {
        not_representable(st, r, ex.what());
    }
}

// ---- ray generators on a world -----------------------------------------------------------

RfVec3 box_point(const RfAabb &b, double grow, Rng &rng)
{
    RfVec3 c = rf_aabb_center(b), h = rf_vec3_scale(rf_vec3_sub(b.hi, b.lo), 0.5 * grow);
    return rf_vec3(c.x + h.x * rng.range(-1, 1), c.y + h.y * rng.range(-1, 1), c.z + h.z * rng.range(-1, 1));
}

RfRay gen_uniform(const World &w, Rng &rng) { return rf_ray(box_point(w.bounds, 1.4, rng), rng.unit()); }

// A primitive placed in the world: an item and the composed to_world of its path (none in the
// world itself: its doubles are used as they are).
struct Placed {
    int item = -1, path = 0;
    const Affine *M = nullptr;
    RfVec3 map(RfVec3 p) const
    {
        if (!M)
            return p;
        LV q = M->point(lv(p));
        return rf_vec3((double)q.x, (double)q.y, (double)q.z);
    }
};

// A random item of the kinds in `mask` (bits 1 << ItemKind) reachable from the world: uniform
// among the level's eligible items (instances whose object holds such items count as one
// entry), descending into instances. The lists are those of the old generators when the world
// holds no instance.
bool pick(const World &w, Rng &rng, unsigned mask, Placed &out)
{
    const Oracle &orc = *w.orc;
    const auto &items = orc.items();
    auto f = w.picks.find(mask);
    if (f == w.picks.end()) {
        size_t nl = w.sc.object_count + 1;
        std::vector<std::vector<int>> lists(nl);
        std::vector<int> state(nl, 0); // 0 unknown, 1 visiting, 2 done
        std::function<bool(int)> fill = [&](int level) -> bool {
            if (state[(size_t)level] == 2)
                return !lists[(size_t)level].empty();
            if (state[(size_t)level] == 1)
                return false;
            state[(size_t)level] = 1;
            for (int i : orc.level_items(level)) {
                const Item &it = items[(size_t)i];
                if (it.kind == ITEM_INSTANCE) {
                    if (fill(w.sc.instances[it.inst].object + 1))
                        lists[(size_t)level].push_back(i);
                } else if (mask & (1u << it.kind)) {
                    lists[(size_t)level].push_back(i);
                }
            }
            state[(size_t)level] = 2;
            return !lists[(size_t)level].empty();
        };
        for (size_t l = 0; l < nl; l++)
            fill((int)l);
        f = w.picks.emplace(mask, std::move(lists)).first;
    }
    int level = 0, path = 0;
    for (int depth = 0; depth < 64; depth++) {
        const std::vector<int> &l = f->second[(size_t)level];
        if (l.empty())
            return false;
        int i = l[(size_t)rng.below((int)l.size())];
        const Item &it = items[(size_t)i];
        if (it.kind != ITEM_INSTANCE) {
            out.item = i;
            out.path = path;
            out.M = path ? &orc.path(path).to_world : nullptr;
            return true;
        }
        path = orc.child_path(path, it.inst);
        level = orc.path(path).level;
    }
    return false;
}

// A point on a cone's rim (base: end 0, apex: end 1) at angle phi, and its frame.
struct ConeFrame {
    RfVec3 k, u, v;
    double H;
};
ConeFrame cone_frame(const RfCone &c)
{
    ConeFrame f;
    RfVec3 a = rf_vec3_sub(c.apex, c.base);
    f.H = rf_vec3_length(a);
    f.k = rf_vec3_scale(a, 1 / f.H);
    frame(f.k, &f.u, &f.v);
    return f;
}
RfVec3 cone_point(const RfCone &c, const ConeFrame &f, double w, double phi, double *rho, RfVec3 *radial)
{
    *rho = c.base_radius + (c.apex_radius - c.base_radius) * w;
    *radial = rf_vec3_add(rf_vec3_scale(f.u, std::cos(phi)), rf_vec3_scale(f.v, std::sin(phi)));
    return rf_vec3_add(rf_vec3_add(c.base, rf_vec3_scale(f.k, w * f.H)), rf_vec3_scale(*radial, *rho));
}

const unsigned kEdgeKinds = 1u << ITEM_TRI | 1u << ITEM_CONE;

// Aimed at a vertex (exactly) or an edge point of a random triangle (a polygon's too), or at a
// point of a cone's rim; from inside a closed mesh when there is one (a dyadic origin in a grid
// cube: the direction is then exact and the ray passes exactly through the edge or vertex),
// else from anywhere around. Items of objects: the target (and an origin inside the object's
// mesh) in object space, then placed by the composed to_world.
RfRay gen_edges(const World &w, Rng &rng, int *interior)
{
    const auto &items = w.orc->items();
    Placed pl;
    *interior = -1;
    if (!pick(w, rng, kEdgeKinds, pl))
        return gen_uniform(w, rng);
    const Item &t = items[(size_t)pl.item];
    if (t.kind == ITEM_CONE) {
        ConeFrame f = cone_frame(t.cone);
        double rho;
        RfVec3 radial;
        RfVec3 p = cone_point(t.cone, f, rng.below(2), rng.range(0, 2 * RF_PI), &rho, &radial);
        RfVec3 o = box_point(w.bounds, 1.4, rng);
        return rf_ray(o, rf_vec3_sub(pl.map(p), o));
    }
    int k = rng.below(3);
    RfVec3 a = t.p[k], b = t.p[(k + 1) % 3];
    RfVec3 target = a;
    int kind = rng.below(3);
    RfVec3 o;
    int mi = w.prim_mesh[(size_t)t.prim];
    if (mi >= 0 && w.meshes[(size_t)mi].is_box) {
        const Mesh &m = w.meshes[(size_t)mi];
        double q = std::ldexp(1.0, (int)std::floor(std::log2(m.hi.x - m.lo.x)) - 24); // dyadic grid
        RfVec3 p = rf_vec3(rng.range(m.lo.x, m.hi.x), rng.range(m.lo.y, m.hi.y), rng.range(m.lo.z, m.hi.z));
        o = rf_vec3(std::round(p.x / q) * q, std::round(p.y / q) * q, std::round(p.z / q) * q);
        if (kind > 0) // a dyadic point of the edge: exact
            target = rf_vec3_add(a, rf_vec3_scale(rf_vec3_sub(b, a), (double)rng.below(1024) / 1024));
    } else {
        if (mi >= 0)
            o = pl.map(rf_vec3_add(w.meshes[(size_t)mi].c, rf_vec3_scale(rng.ball(), 0.99 * w.meshes[(size_t)mi].r_in)));
        else
            o = box_point(w.bounds, 1.4, rng);
        if (kind == 1)
            target = rf_vec3_scale(rf_vec3_add(a, b), 0.5);
        else if (kind == 2)
            target = rf_vec3_lerp(a, b, rng.u());
    }
    *interior = w.interior_mesh(o);
    return rf_ray(o, rf_vec3_sub(pl.map(target), o));
}

// Tangent to a random sphere or cone, the line's distance from the surface r e with eps 0 or
// +-10^U(-16, -2) (r the radius there), from 1.1 .. 1000 r away. A cone's tangent line lies in
// the tangent plane at a random surface point, in a random direction of that plane. Items of
// objects: made in object space, then placed (an affine map keeps tangency).
bool gen_grazing(const World &w, Rng &rng, RfRay *out)
{
    const auto &items = w.orc->items();
    Placed pl;
    if (!pick(w, rng, 1u << ITEM_SPHERE | 1u << ITEM_CONE, pl))
        return false;
    const Item &it = items[(size_t)pl.item];
    double eps = rng.below(4) == 0 ? 0 : (rng.below(2) ? 1 : -1) * rng.pow10(-16, -2);
    RfVec3 o, target;
    if (it.kind == ITEM_SPHERE) {
        const RfSphere &s = it.s;
        double rho = s.radius * (1 + eps), L0 = s.radius * rng.pow10(0.05, 3);
        RfVec3 wdir = rng.unit();
        o = rf_vec3_sub(s.center, rf_vec3_scale(wdir, L0));
        RfVec3 u = rf_vec3_normalize(rf_vec3_cross(wdir, rng.unit()));
        // the line from o through c + u q has distance rho from c when q = rho L0 / sqrt(L0^2 - rho^2)
        double q = rho * L0 / std::sqrt(std::max(L0 * L0 - rho * rho, 1e-300));
        target = rf_vec3_add(s.center, rf_vec3_scale(u, q));
    } else {
        const RfCone &c = it.cone;
        ConeFrame f = cone_frame(c);
        double rho, w01 = rng.u();
        RfVec3 radial;
        RfVec3 p = cone_point(c, f, w01, rng.range(0, 2 * RF_PI), &rho, &radial);
        double dr = c.apex_radius - c.base_radius;
        RfVec3 g = rf_vec3_normalize(rf_vec3_add(rf_vec3_scale(f.k, f.H), rf_vec3_scale(radial, dr)));
        RfVec3 tau = rf_vec3_cross(f.k, radial);
        RfVec3 n = rf_vec3_normalize(rf_vec3_sub(radial, rf_vec3_scale(f.k, dr / f.H)));
        double psi = rng.range(0.02, RF_PI - 0.02), rr = std::max(rho, 1e-3 * std::max(c.base_radius, c.apex_radius));
        RfVec3 e = rf_vec3_add(rf_vec3_scale(g, std::cos(psi)), rf_vec3_scale(tau, std::sin(psi)));
        target = rf_vec3_add(p, rf_vec3_scale(n, eps * rr));
        o = rf_vec3_sub(target, rf_vec3_scale(e, rr * rng.pow10(0.05, 3)));
    }
    RfVec3 wo = pl.map(o);
    *out = rf_ray(wo, rf_vec3_sub(pl.map(target), wo));
    return true;
}

// Nearly parallel to a random triangle (a polygon's too) or plane: an in-plane direction tilted
// by 0 or +-10^U(-17, -2), from a point at height 0 or +-10^U(-16, -1) of the size above it; or
// nearly parallel to a generator of a cone (the quadratic's linear case), from near its surface.
bool gen_parallel(const World &w, Rng &rng, RfRay *out)
{
    const auto &items = w.orc->items();
    Placed pl;
    if (!pick(w, rng, 1u << ITEM_TRI | 1u << ITEM_PLANE | 1u << ITEM_CONE, pl))
        return false;
    const Item &it = items[(size_t)pl.item];
    RfVec3 n, q;
    double size;
    if (it.kind == ITEM_TRI) {
        RfVec3 p[3] = {pl.map(it.p[0]), pl.map(it.p[1]), pl.map(it.p[2])};
        n = rf_vec3_normalize(rf_vec3_cross(rf_vec3_sub(p[1], p[0]), rf_vec3_sub(p[2], p[0])));
        double l1 = rng.u(), l2 = rng.u();
        if (l1 + l2 > 1)
            l1 = 1 - l1, l2 = 1 - l2;
        q = rf_vec3_add(p[0], rf_vec3_add(rf_vec3_scale(rf_vec3_sub(p[1], p[0]), l1),
                                          rf_vec3_scale(rf_vec3_sub(p[2], p[0]), l2)));
        size = pl.M ? rf_vec3_length(rf_vec3_sub(rf_vec3_add(rf_vec3_sub(p[1], p[0]), p[2]), p[0]))
                    : rf_vec3_length(rf_vec3_sub(it.box.hi, it.box.lo));
    } else if (it.kind == ITEM_CONE) {
        const RfCone &c = it.cone;
        ConeFrame f = cone_frame(c);
        double rho, dr = c.apex_radius - c.base_radius;
        RfVec3 radial;
        RfVec3 p = cone_point(c, f, rng.u(), rng.range(0, 2 * RF_PI), &rho, &radial);
        RfVec3 g = rf_vec3_normalize(rf_vec3_add(rf_vec3_scale(f.k, f.H), rf_vec3_scale(radial, dr)));
        RfVec3 nn = rf_vec3_normalize(rf_vec3_sub(radial, rf_vec3_scale(f.k, dr / f.H)));
        double sz = std::max({f.H, c.base_radius, c.apex_radius});
        double tilt = rng.below(4) == 0 ? 0 : (rng.below(2) ? 1 : -1) * rng.pow10(-17, -2);
        double h = rng.below(4) == 0 ? 0 : (rng.below(2) ? 1 : -1) * rng.pow10(-16, -1) * sz;
        RfVec3 d = rf_vec3_add(g, rf_vec3_scale(nn, tilt));
        RfVec3 o = rf_vec3_add(rf_vec3_sub(p, rf_vec3_scale(d, sz * rng.range(0.3, 2))), rf_vec3_scale(nn, h));
        RfVec3 wo = pl.map(o);
        *out = rf_ray(wo, rf_vec3_sub(pl.map(rf_vec3_add(o, d)), wo));
        return true;
    } else {
        n = rf_vec3_normalize(it.pl.normal);
        size = rf_vec3_length(rf_vec3_sub(w.bounds.hi, w.bounds.lo));
        q = rf_vec3_add(rf_vec3_scale(n, it.pl.offset), rf_vec3_scale(rf_vec3_normalize(rf_vec3_cross(n, rng.unit())), size * rng.u()));
        if (pl.M) { // a plane of an object: the plane through the placed point, placed normal
            RfVec3 a = pl.map(q), t1, t2;
            frame(n, &t1, &t2);
            RfVec3 b = pl.map(rf_vec3_add(q, t1)), c = pl.map(rf_vec3_add(q, t2));
            n = rf_vec3_normalize(rf_vec3_cross(rf_vec3_sub(b, a), rf_vec3_sub(c, a)));
            q = a;
        }
    }
    RfVec3 u = rf_vec3_normalize(rf_vec3_cross(n, rng.unit()));
    double tilt = rng.below(4) == 0 ? 0 : (rng.below(2) ? 1 : -1) * rng.pow10(-17, -2);
    double h = rng.below(4) == 0 ? 0 : (rng.below(2) ? 1 : -1) * rng.pow10(-16, -1) * size;
    RfVec3 d = rf_vec3_add(u, rf_vec3_scale(n, tilt));
    RfVec3 o = rf_vec3_add(rf_vec3_sub(q, rf_vec3_scale(d, size * rng.range(0.3, 2))), rf_vec3_scale(n, h));
    *out = rf_ray(o, d);
    return true;
}

// ---- the ray classes -----------------------------------------------------------------------

const char *const kAllClasses[] = {"uniform",   "edges",  "grazing",  "parallel", "far",       "radii",
                                   "surface",   "acne",   "leak",     "optics",   "invalid",   "cones",
                                   "polygons",  "instances", "star-prisms"};

// The distance from p to a triangle item (long double).
L tri_dist(const Item &it, LV p)
{
    LV a = lv(it.p[0]), b = lv(it.p[1]), c = lv(it.p[2]);
    LV ab = sub(b, a), ac = sub(c, a), n = cross(ab, ac);
    L nn = dot(n, n);
    if (!(nn > 0))
        return HUGE_VALL;
    LV ap = sub(p, a);
    // barycentric coordinates of p's projection; inside: the distance to the plane
    L u = dot(cross(ap, ac), n) / nn, v = dot(cross(ab, ap), n) / nn;
    if (u >= 0 && v >= 0 && u + v <= 1)
        return std::fabs(dot(ap, n)) / std::sqrt(nn);
    auto seg = [&](LV s0, LV s1) {
        LV e = sub(s1, s0), w = sub(p, s0);
        L ee = dot(e, e), t = ee > 0 ? std::min((L)1, std::max((L)0, dot(w, e) / ee)) : 0;
        return len(sub(w, scale(e, t)));
    };
    return std::min({seg(a, b), seg(b, c), seg(c, a)});
}

// Rays starting on surfaces: a primary ray's tracer hit p, then a secondary ray from
// rf_hit_offset_origin(h, dir) (mirror, random outgoing or random transmitted direction),
// checked like any other ray; in addition its origin must lie exactly on the side of its own
// surface it leaves to (else it re-hits that surface: self-intersection, counted as acne).
void surface_ray(const World &w, const Opts &o, Rng &rng, Stats &st)
{
    RfRay pr = rf_ray(box_point(w.bounds, 3.0, rng), rf_vec3(0, 0, 0));
    pr.dir = rf_vec3_sub(box_point(w.bounds, 0.8, rng), pr.origin);
    RfSurfaceHit h;
    int prim = rf_tracer_intersect(w.tr, &pr, 0.0, HUGE_VAL, &h);
    if (prim < 0)
        return;
    RfVec3 n = h.normal, d;
    int kind = rng.below(3);
    RfVec3 in = rf_vec3_normalize(pr.dir);
    if (kind == 0)
        d = rf_vec3_sub(in, rf_vec3_scale(n, 2 * rf_vec3_dot(in, n)));
    else {
        d = rng.unit();
        if ((rf_vec3_dot(d, n) > 0) != (kind == 1))
            d = rf_vec3_neg(d);
    }
    if (rf_vec3_dot(d, n) == 0)
        return;
    RfSurfaceHit hn = h; // the renderer's policy, with the normal the new ray leaves by
    hn.normal = n;
    RfRay r = rf_ray(rf_hit_offset_origin(&hn, d, o.fixed_offset), d);
    check_and_tally(st, w, o, r, w.interior_mesh(r.origin));
    // the exact side of the new origin against the primitive it leaves (its fan triangles are
    // coplanar for the quads built here; a sphere's and a cone's side are exact too)
    const auto &its = w.orc->items_of(prim);
    if (its.empty() || w.orc->items()[(size_t)its[0]].level != 0) // a primitive of an instanced object
        return;
    // a polygon's fan triangle holding p (the one nearest to it: a non-planar polygon's fan
    // triangles lie in different planes)
    int side_item = its[0];
    if (its.size() > 1) {
        L best = HUGE_VALL;
        for (int i : its) {
            L dist = tri_dist(w.orc->items()[(size_t)i], lv(h.point));
            if (dist < best)
                best = dist, side_item = i;
        }
    }
    const Item &it = w.orc->items()[(size_t)side_item];
    int want;
    if (it.kind == ITEM_SPHERE)
        want = rf_vec3_dot(d, rf_vec3_sub(h.point, it.s.center)) > 0 ? 1 : -1;
    else if (it.kind == ITEM_CONE) { // the outward normal at p: radial minus the slope along k
        ConeFrame f = cone_frame(it.cone);
        RfVec3 q = rf_vec3_sub(h.point, it.cone.base);
        RfVec3 radial = rf_vec3_sub(q, rf_vec3_scale(f.k, rf_vec3_dot(q, f.k)));
        double rl = rf_vec3_length(radial);
        if (!(rl > 0))
            return;
        RfVec3 nn = rf_vec3_sub(rf_vec3_scale(radial, 1 / rl), rf_vec3_scale(f.k, (it.cone.apex_radius - it.cone.base_radius) / f.H));
        want = rf_vec3_dot(d, nn) > 0 ? 1 : -1;
    } else {
        RfVec3 nn;
        if (it.kind == ITEM_PLANE)
            nn = it.pl.normal;
        else
            nn = rf_vec3_cross(rf_vec3_sub(it.p[1], it.p[0]), rf_vec3_sub(it.p[2], it.p[0]));
        want = rf_vec3_dot(d, nn) > 0 ? 1 : -1;
    }
    int side;
    try {
        side = w.orc->side(side_item, r.origin);
    } catch (const std::exception &) {
        return; // the ray itself was checked (and counted) above; only this side test is lost
    }
    st.acne_d++;
    if (side != want) {
        st.acne_n++;
        st.real++; // a self-intersection is a real error whatever the ray check said
        example(st, "self-intersection: origin (%a,%a,%a) on the wrong side of primitive %d", r.origin.x,
                r.origin.y, r.origin.z, prim);
    }
}

// A random affine placement for the instances class: a rotation about a random axis, a
// non-uniform scale s (1, U(0.3, 3), U(0.3, 3)) (s = 10^U(-2, 2)), sometimes a shear or a
// mirror, then a translation to `at`.
RfMat4 random_placement(Rng &rng, RfVec3 at, double s)
{
    RfMat4 m = rf_mat4_scale(s, s * rng.range(0.3, 3), s * rng.range(0.3, 3));
    if (rng.below(3) == 0)
        m = rf_mat4_mul(rf_mat4_shear_z(rng.range(-0.8, 0.8), rng.range(-0.8, 0.8)), m);
    if (rng.below(4) == 0)
        m = rf_mat4_mul(rf_mat4_scale(-1, 1, 1), m);
    RfMat3 r;
    if (rf_mat3_axis_angle(rng.unit(), rng.range(0, 2 * RF_PI), &r, nullptr, nullptr) == RF_OK)
        m = rf_mat4_mul(rf_mat4_affine(r, rf_vec3(0, 0, 0)), m);
    return rf_mat4_mul(rf_mat4_translate(at), m);
}

void run_rays(const char *cls, const Opts &o, Stats &st)
{
    Rng rng(o.seed * 1000003ULL + (uint64_t)std::hash<std::string>()(cls));
    const int subs = 16;
    for (int sub = 0; sub < subs; sub++) {
        long n = o.rays / subs + (sub < o.rays % subs ? 1 : 0);
        World w;
        std::string c = cls;
        double s = 1;
        RfVec3 at = rf_vec3(0, 0, 0);
        if (c == "uniform") {
            w.mixed(at, 1, rng);
        } else if (c == "edges") {
            if (sub % 2)
                w.icosphere(rng.ball(), rng.pow10(-1, 1), 3, 1e-2, rng);
            else
                w.grid_cube(rf_vec3(std::ldexp((double)rng.below(1 << 20), -16), 0.25, -3), 4 + rng.below(4),
                            std::ldexp(1.0, rng.below(6) - 3));
        } else if (c == "grazing") {
            for (int i = 0; i < 6; i++) {
                double r = rng.pow10(-3, 3);
                w.sphere(rf_vec3_scale(rng.unit(), r * rng.range(0, 40)), r, i % 2 ? RF_PRIM_TWO_SIDED : 0);
            }
        } else if (c == "parallel") {
            for (int i = 0; i < 3; i++)
                w.quad(rf_vec3_scale(rng.ball(), 2), 1, rng, RF_PRIM_TWO_SIDED);
            for (int i = 0; i < 3; i++) {
                RfVec3 cc = rf_vec3_scale(rng.ball(), 2), t[3];
                for (auto &p : t)
                    p = rf_vec3_add(cc, rng.ball());
                w.poly(t, 3, RF_PRIM_TWO_SIDED, -1);
            }
            RfVec3 nn = rng.unit();
            w.plane(nn, -3);
        } else if (c == "far") {
            at = rf_vec3_scale(rng.unit(), std::pow(10.0, 7.0 * sub / (subs - 1)));
            w.mixed(at, 1, rng);
        } else if (c == "radii") {
            s = std::pow(10.0, -6 + 12.0 * sub / (subs - 1));
            at = rf_vec3_scale(rng.unit(), std::max(rng.pow10(0, 7), 2 * s * rng.u()));
            if (sub % 2)
                w.sphere(at, s, sub % 4 == 1 ? RF_PRIM_TWO_SIDED : 0);
            else
                w.icosphere(at, s, 1, 1e-3, rng);
        } else if (c == "surface") {
            s = std::pow(10.0, -4 + 10.0 * sub / (subs - 1));
            at = rf_vec3_scale(rng.unit(), 3 * s * rng.u());
            w.mixed(at, s, rng);
        } else if (c == "cones") {
            // cylinders, frusta and cones with a tip (at either end), radii 1e-3 .. 1e3, lengths
            // 0.3 .. 30 radii, axes random or along a coordinate axis; one-sided (outside),
            // two-sided and inside-only (NFF's negative radii)
            for (int i = 0; i < 6; i++) {
                double r = rng.pow10(-3, 3), len = r * rng.pow10(-0.5, 1.5);
                double rb = r, ra = i % 3 == 0 ? r : i % 3 == 1 ? r * rng.range(0.2, 2) : 0;
                if (rng.below(2))
                    std::swap(rb, ra);
                RfVec3 ax = sub % 4 == 3 ? rf_vec3(0, 0, 1) : rng.unit();
                RfVec3 base = rf_vec3_scale(rng.unit(), r * rng.range(0, 40));
                unsigned fl = i % 2 ? (unsigned)RF_PRIM_TWO_SIDED : (sub % 3 == 2 ? (unsigned)RF_PRIM_INSIDE : 0u);
                w.cone(base, rb, rf_vec3_add(base, rf_vec3_scale(ax, len)), ra, fl);
            }
        } else if (c == "star-prisms") {
            // a closed star prism: non-convex star polygons as top and bottom (exactly planar,
            // dyadic), convex side quads; rays from inside at points of the boundary edges
            // must not get out (they did, 6.6 %, while the tracer tested non-convex polygons by
            // their plane and a crossing number; now it cuts them into triangles: docs/verify.md)
            int k = 4 + rng.below(9);
            double e = 1.0 / 64, rin = rng.range(0.3, 0.6);
            std::vector<RfVec3> top, bot;
            for (int i = 0; i < 2 * k; i++) {
                double a = RF_PI * i / k, r = (i % 2 ? rin : 1.0) * 64;
                double x = std::round(r * std::cos(a)) * e, y = std::round(r * std::sin(a)) * e;
                bot.push_back(rf_vec3(x, y, 0));
                top.push_back(rf_vec3(x, y, 1));
            }
            int id = (int)w.meshes.size();
            w.meshes.push_back(Mesh{false, rf_vec3(0, 0, 0.5), 0.25, {}, {}, -1});
            std::vector<RfVec3> rbot(bot.rbegin(), bot.rend());
            w.poly(top.data(), (int)top.size(), RF_PRIM_TWO_SIDED, id);
            w.poly(rbot.data(), (int)rbot.size(), RF_PRIM_TWO_SIDED, id);
            for (int i = 0; i < 2 * k; i++) {
                int j = (i + 1) % (2 * k);
                RfVec3 q[4] = {bot[(size_t)i], bot[(size_t)j], top[(size_t)j], top[(size_t)i]};
                w.poly(q, 4, RF_PRIM_TWO_SIDED, id);
            }
        } else if (c == "polygons") {
            // stars and gears: exactly planar with dyadic vertices, or in random planes with
            // decimal coordinates; one- and two-sided
            for (int i = 0; i < 4; i++)
                w.star(rf_vec3_scale(rng.ball(), 3), rng.range(0.5, 2), (sub + i) % 2 == 0, i % 2 ? RF_PRIM_TWO_SIDED : 0, rng);
        } else if (c == "instances") {
            // one object (a closed icosphere, a sphere, a cone, a star polygon, a triangle, a
            // plane in every fourth sub-scene) placed 3 times directly and twice through a
            // group (a chain of two instances), far from the origin in later sub-scenes
            int obj = w.begin_object("thing");
            w.icosphere(rf_vec3(0, 0, 0), 1, 1 + sub % 2, 1e-3, rng);
            w.sphere(rf_vec3(2.2, 0, 0), 0.6, sub % 2 ? RF_PRIM_TWO_SIDED : 0);
            w.cone(rf_vec3(0, 2, 0), 0.5, rf_vec3(0.3, 3.5, 0.2), sub % 3 ? 0.2 : 0.0, sub % 2 ? 0 : RF_PRIM_TWO_SIDED);
            w.star(rf_vec3(0, 0, -2.5), 1.2, sub % 2 == 0, RF_PRIM_TWO_SIDED, rng);
            RfVec3 tri[3] = {{-2, -2, 0}, {-3, -2.5, 0.5}, {-2.2, -3.4, -0.3}};
            w.poly(tri, 3, 0, -1);
            if (sub % 4 == 3)
                w.plane(rf_vec3(0, 0, 1), -6);
            w.end_object(obj);
            double sc = rng.pow10(-2, 2);
            int grp = w.begin_object("group");
            // apart: the object reaches 4.1 from its origin, 20 once placed (scale <= 3, shear
            // <= 1.6), the group 45 + 20, 312 once placed: no two placements overlap, so a ray
            // from inside one icosphere meets that one first
            w.instance(obj, random_placement(rng, rf_vec3(0, 0, 0), 1));
            w.instance(obj, random_placement(rng, rf_vec3(45, 0, 0), 1));
            w.end_object(grp);
            RfVec3 far = rf_vec3_scale(rng.unit(), sub < 4 ? 0 : std::pow(10.0, 6.0 * (sub - 4) / (subs - 5)));
            for (int i = 0; i < 4; i++)
                w.instance(i < 3 ? obj : grp,
                           random_placement(rng, rf_vec3_add(far, rf_vec3(700 * sc * i, 0, 0)), sc));
        }
        w.finish();
        if (c == "surface") { // until n secondary rays (a primary ray may miss)
            long before = st.rays;
            for (long a = 0; st.rays - before < n && a < 50 * n + 100; a++)
                surface_ray(w, o, rng, st);
            continue;
        }
        for (long k = 0; k < n; k++) {
            RfRay r = rf_ray(rf_vec3(0, 0, 0), rf_vec3(0, 0, 0));
            int interior = -1;
            int mode = c == "cones" || c == "polygons" || c == "instances" ? rng.below(4) : c == "star-prisms" ? 1 : -1;
            try {
                if (c == "uniform" || c == "far" || mode == 0) {
                    r = gen_uniform(w, rng);
                    interior = w.interior_mesh(r.origin);
                } else if (c == "edges" || mode == 1) {
                    r = gen_edges(w, rng, &interior);
                } else if (c == "grazing" || (mode == 2 && c != "polygons")) {
                    if (!gen_grazing(w, rng, &r))
                        continue;
                } else if (c == "parallel" || mode >= 2) {
                    if (!gen_parallel(w, rng, &r))
                        continue;
                } else if (c == "radii") {
                    r.origin = rng.ball();
                    r.dir = rf_vec3_sub(rf_vec3_add(at, rf_vec3_scale(rng.ball(), 1.3 * s)), r.origin);
                    interior = w.interior_mesh(r.origin);
                }
            } catch (const std::exception &ex) {
                not_representable(st, r, ex.what());
                continue;
            }
            if (rf_vec3_dot(r.dir, r.dir) == 0)
                continue;
            check_and_tally(st, w, o, r, interior);
        }
    }
}

// The classes on a scene file: the same generators over its primitives.
void run_file(const char *cls, const Opts &o, World &w, Stats &st)
{
    Rng rng(o.seed * 1000003ULL + (uint64_t)std::hash<std::string>()(cls));
    std::string c = cls;
    for (long k = 0; k < o.rays; k++) {
        RfRay r = rf_ray(rf_vec3(0, 0, 0), rf_vec3(0, 0, 0));
        int interior = -1;
        try {
            if (c == "uniform" || c == "far" || c == "radii") {
                r = gen_uniform(w, rng);
            } else if (c == "edges") {
                r = gen_edges(w, rng, &interior);
            } else if (c == "grazing") {
                if (!gen_grazing(w, rng, &r))
                    return;
            } else if (c == "parallel") {
                if (!gen_parallel(w, rng, &r))
                    return;
            } else {
                surface_ray(w, o, rng, st);
                continue;
            }
        } catch (const std::exception &ex) {
            not_representable(st, r, ex.what());
            continue;
        }
        if (!finite_ray(r) || rf_vec3_dot(r.dir, r.dir) > 0)
            check_and_tally(st, w, o, r, interior);
    }
}

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


// ---- driver ------------------------------------------------------------------------------------

const char *const kFileClasses[] = {"uniform", "edges", "grazing", "parallel", "surface"};

// Loads a scene and prepares the oracle and the tracer. On failure *err says why: the loader's
// message (file:line:col), or the verifier's refusal of a scene outside its range with the
// primitive's position (RfPrimitive.loc: its statement in the scene or in the mesh file it
// includes).
// *code (may be null): RF_EXIT_FILE when the scene cannot be read, RF_EXIT_FAIL when the oracle
// cannot take it
bool load_world(const char *path, World &w, std::string *err, int *code = nullptr)
{
    char msg[1024];
    rf_scene_free(&w.sc);
    rf_scene_init(&w.sc);
    if (code)
        *code = RF_EXIT_FILE;
    if (rf_scene_load(path, nullptr, &w.sc, msg, sizeof msg) != RF_OK) {
        *err = msg;
        return false;
    }
    if (code)
        *code = RF_EXIT_FAIL;
    // the exact oracle expands every placement: a graph with more paths than it can hold (a DAG
    // of groups placing their child twice has 2^levels) is refused before the expansion
    RfTriangleCount tc = rf_scene_triangle_count(&w.sc);
    if (tc.instances_rendered > 1000000) {
        snprintf(msg, sizeof msg,
                 "%s: the scene graph expands to %zu placements, more than the exact oracle holds (1000000); scene refused",
                 path, tc.instances_rendered);
        *err = msg;
        return false;
    }
    w.prim_mesh.assign(w.sc.prim_count, -1);
    rf_scene_bounds(&w.sc, &w.bounds.lo, &w.bounds.hi);
    try {
        w.finish();
    } catch (const SceneError &e) {
        if (e.loc.line > 0)
            snprintf(msg, sizeof msg, "%s:%d:%d: %s; scene refused", path, e.loc.line, e.loc.col, e.what());
        else
            snprintf(msg, sizeof msg, "%s: %s; scene refused", path, e.what());
        *err = msg;
        return false;
    } catch (const std::exception &e) {
        snprintf(msg, sizeof msg, "%s: the exact oracle cannot represent this scene (%s); scene refused", path, e.what());
        *err = msg;
        return false;
    }
    return true;
}

void run_class_body(const char *cls, const Opts &o, World *file_world, Stats &st)
{
    std::string c = cls;
    if (c.compare(0, 6, "scene:") == 0) { // a scene file: every file class, one row
        const char *path = cls + 6;
        World w;
        Opts so = o;
        so.rays = o.scene_rays;
        std::string err;
        if (!load_world(path, w, &err))
            row_error(st, "%s", err.c_str());
        else
            for (const char *fc : kFileClasses)
                run_file(fc, so, w, st);
    } else if (file_world)
        run_file(cls, o, *file_world, st);
    else if (c == "acne")
        run_acne(o, st);
    else if (c == "leak")
        run_leak(o, st);
    else if (c == "optics")
        run_optics(o, st);
    else if (c == "invalid")
        run_invalid(o, st);
    else
        run_rays(cls, o, st);
}

Stats run_class(const char *cls, const Opts &o, World *file_world)
{
    Stats st;
    memset(&st, 0, sizeof st);
    snprintf(st.name, sizeof st.name, "%s", cls);
    if (strncmp(cls, "scene:", 6) == 0) {
        const char *base = strrchr(cls + 6, '/');
        snprintf(st.name, sizeof st.name, "%s", base ? base + 1 : cls + 6);
    }
    auto t0 = std::chrono::steady_clock::now();
    // anything the oracle throws outside a ray (a built-in scene it refuses, the allocator)
    // ends the row with a message instead of the process
    try {
        run_class_body(cls, o, file_world, st);
    } catch (const SceneError &e) {
        row_error(st, "%s: %s", cls, e.what());
    } catch (const std::exception &e) {
        row_error(st, "%s: %s", cls, e.what());
    }
    st.secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return st;
}

void print_table(const std::vector<Stats> &rows, FILE *f)
{
    fprintf(f, "%-13s %10s %10s %10s %6s %11s %8s %12s %8s\n", "class", "rays", "agree", "ambiguous", "real",
            "edge misses", "skipped", "acne share", "seconds");
    Stats tot;
    memset(&tot, 0, sizeof tot);
    for (const Stats &s : rows) {
        char acne[32] = "-";
        if (s.acne_d)
            snprintf(acne, sizeof acne, "%ld/%ld", s.acne_n, s.acne_d);
        if (s.error)
            fprintf(f, "%-13s %10s\n", s.name, "error");
        else
            fprintf(f, "%-13s %10ld %10ld %10ld %6ld %11ld %8ld %12s %8.1f\n", s.name, s.rays, s.agree, s.amb,
                    s.real, s.edge_miss, s.skipped, acne, s.secs);
        tot.rays += s.rays, tot.agree += s.agree, tot.amb += s.amb, tot.real += s.real;
        tot.edge_miss += s.edge_miss, tot.skipped += s.skipped, tot.acne_n += s.acne_n, tot.acne_d += s.acne_d;
        tot.secs += s.secs;
    }
    char acne[32] = "-";
    if (tot.acne_d)
        snprintf(acne, sizeof acne, "%ld/%ld", tot.acne_n, tot.acne_d);
    fprintf(f, "%-13s %10ld %10ld %10ld %6ld %11ld %8ld %12s %8.1f\n", "total", tot.rays, tot.agree, tot.amb, tot.real,
            tot.edge_miss, tot.skipped, acne, tot.secs);
    for (const Stats &s : rows)
        for (int i = 0; i < s.n_examples; i++)
            fprintf(f, "real (%s): %s\n", s.name, s.examples[i]);
    for (const Stats &s : rows)
        if (s.skipped)
            fprintf(f, "skipped (not representable) (%s): %ld rays; the first: %s\n", s.name, s.skipped, s.skip_note);
}

// Runs the classes, up to `jobs` at once in child processes (no shared state: each child
// builds its own scenes and sends its Stats back through a pipe).
std::vector<Stats> run_all(const std::vector<std::string> &classes, const Opts &o, int jobs, World *fw)
{
    std::vector<Stats> rows(classes.size());
    if (jobs <= 1 || fw) {
        for (size_t i = 0; i < classes.size(); i++)
            rows[i] = run_class(classes[i].c_str(), o, fw);
        return rows;
    }
    // the longest rows first (measured at CI size), so that no long row starts last; the table
    // keeps the given order
    auto cost = [](const std::string &c) {
        return c == "instances" ? 5 : c == "edges" ? 4 : c == "cones" ? 3 : c == "grazing" || c == "parallel" || c == "radii" || c == "polygons" ? 1 : 0;
    };
    std::vector<size_t> order(classes.size());
    for (size_t i = 0; i < order.size(); i++)
        order[i] = i;
    std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return cost(classes[a]) > cost(classes[b]); });
    size_t next = 0, done = 0;
    std::map<pid_t, std::pair<size_t, int>> running;
    while (done < classes.size()) {
        while ((int)running.size() < jobs && next < classes.size()) {
            size_t row = order[next];
            int fd[2];
            if (pipe(fd) != 0) {
                perror("pipe");
                exit(2);
            }
            fflush(nullptr);
            pid_t pid = fork();
            if (pid == 0) {
                close(fd[0]);
                Stats st = run_class(classes[row].c_str(), o, nullptr);
                ssize_t wr = write(fd[1], &st, sizeof st);
                _exit(wr == (ssize_t)sizeof st ? 0 : 3);
            }
            close(fd[1]);
            running[pid] = {row, fd[0]};
            next++;
        }
        int status;
        pid_t pid = wait(&status);
        auto it = running.find(pid);
        if (it == running.end())
            continue;
        Stats st;
        size_t got = 0;
        while (got < sizeof st) {
            ssize_t k = read(it->second.second, (char *)&st + got, sizeof st - got);
            if (k <= 0)
                break;
            got += (size_t)k;
        }
        close(it->second.second);
        if (got != sizeof st || !WIFEXITED(status) || WEXITSTATUS(status) != 0) {
            memset(&st, 0, sizeof st);
            snprintf(st.name, sizeof st.name, "%s", classes[it->second.first].c_str());
            row_error(st, "class %s crashed (%s %d)", classes[it->second.first].c_str(),
                      WIFSIGNALED(status) ? "signal" : "exit status",
                      WIFSIGNALED(status) ? WTERMSIG(status) : WEXITSTATUS(status));
        }
        rows[it->second.first] = st;
        running.erase(it);
        done++;
    }
    return rows;
}

enum { OPT_RAYS = RF_OPT_ID, OPT_SEED, OPT_JOBS, OPT_CLASS, OPT_STRESS, OPT_SCENE_RAYS, OPT_TRIANGLE, OPT_SPHERE,
       OPT_CONE_BOUND, OPT_FIXED_OFFSET };

const RfOpt verify_opts[] = {
    {"rays", OPT_RAYS, "N", "rays per class (default 100000)", "an integer >= 0"},
    {"class", OPT_CLASS, "CLASS", "one class of rays (repeatable; default: all); see below", nullptr},
    {"seed", OPT_SEED, "S", "the rays' random seed (default 1)", "an integer >= 0"},
    {"jobs", OPT_JOBS, "J", "classes run in J processes at once (default 1)", "an integer >= 1"},
    {"stress", OPT_STRESS, nullptr, "every class, the table of make stress", nullptr},
    {"scene-rays", OPT_SCENE_RAYS, "N", "rays per class in a scene's row (default rays/50)", "an integer >= 1"},
    {"triangle", OPT_TRIANGLE, "watertight|moller|script", "test the §3.5 triangle kernel with this method",
     "watertight, moller or script"},
    {"sphere", OPT_SPHERE, "stable|script", "test the §3.5 sphere kernel with this method", "stable or script"},
    {"fixed-offset", OPT_FIXED_OFFSET, "EPS", "replace the self-intersection policy by a fixed absolute offset",
     "a number >= 0"},
    {"cone-bound", OPT_CONE_BOUND, "kernel|geometric", "cones judged by the cone kernel's bound (default) or the geometric one",
     "kernel or geometric"},
    {nullptr, 0, nullptr, nullptr, nullptr},
};

const RfOpt *const verify_tables[] = {verify_opts, nullptr};

const RfCommand verify_cmd = {
    "refray-verify",
    "refray-verify [options] [SCENE...]\n",
    "The tracer's intersection decisions against CGAL's exact arithmetic. SCENE: an .nff/.rf/.obj\n"
    "scene: rays of the classes uniform, edges, grazing, parallel, surface over its primitives, a\n"
    "row per class (default: every class on scenes built in code); several scenes or --stress:\n"
    "one row per scene with --scene-rays rays per class.\n",
    verify_tables,
    "classes: uniform edges grazing parallel far radii surface acne leak optics invalid cones\n"
    "polygons instances star-prisms. The spheres' geometric cone bound is one the unstabilised\n"
    "cone kernel does not meet.\n"
    "exit: 0 no real disagreement, 2 a real disagreement (a planted bug found) or a row that could\n"
    "not run (a scene outside the verifier's range), 4 a scene cannot be read, 5 usage\n"
    "(README: Exit codes). docs/verify.md\n",
};

int verify_main(int argc, char **argv)
{
    if (const char *f = getenv("REFRAY_VERIFY_FAULT"))
        g_fault_every = std::atol(f);
    Opts o;
    std::vector<std::string> classes;
    std::vector<const char *> scenes;
    bool stress = false;
    int jobs = 1;
    RfOptParser p;
    int key;
    rf_opt_init(&p, &verify_cmd, argc, argv);
    while ((key = rf_opt_next(&p)) != RF_OPT_DONE) {
        const char *v = p.value;
        char *end = nullptr;
        bool ok = true;
        switch (key) {
        case RF_OPT_EXIT: return p.exit_code;
        case OPT_RAYS: o.rays = std::strtol(v, &end, 10), ok = *end == 0 && *v && o.rays >= 0; break;
        case OPT_SEED: o.seed = std::strtoull(v, &end, 10), ok = *end == 0 && *v && *v != '-'; break;
        case OPT_JOBS: jobs = (int)std::strtol(v, &end, 10), ok = *end == 0 && *v && jobs >= 1; break;
        case OPT_CLASS: classes.push_back(v); break;
        case OPT_STRESS: stress = true; break;
        case OPT_SCENE_RAYS: o.scene_rays = std::strtol(v, &end, 10), ok = *end == 0 && *v && o.scene_rays >= 1; break;
        case OPT_TRIANGLE: {
            std::string m = v;
            o.kernel = true;
            o.tri = m == "moller" ? RF_TRIANGLE_MOLLER : m == "script" ? RF_TRIANGLE_SCRIPT : RF_TRIANGLE_WATERTIGHT;
            ok = m == "moller" || m == "script" || m == "watertight";
            break;
        }
        case OPT_SPHERE:
            o.kernel = true;
            o.sph = std::string(v) == "script" ? RF_SPHERE_SCRIPT : RF_SPHERE_STABLE;
            ok = std::string(v) == "script" || std::string(v) == "stable";
            break;
        case OPT_CONE_BOUND:
            g_cone_geometric = std::string(v) == "geometric";
            ok = g_cone_geometric || std::string(v) == "kernel";
            break;
        case OPT_FIXED_OFFSET: o.fixed_offset = std::strtod(v, &end), ok = *end == 0 && *v && o.fixed_offset >= 0; break;
        }
        if (!ok)
            return rf_opt_bad_value(&p);
    }
    char **ops;
    int nops = rf_opt_operands(&p, &ops);
    for (int i = 0; i < nops; i++)
        scenes.push_back(ops[i]);
    for (const std::string &c : classes)
        if (std::find(std::begin(kAllClasses), std::end(kAllClasses), c) == std::end(kAllClasses) &&
            c.compare(0, 6, "scene:") != 0) {
            return rf_opt_usage_error(&verify_cmd, "unknown class '%s'", c.c_str());
        }
    if (o.scene_rays <= 0)
        o.scene_rays = std::max(1L, o.rays / 50);
    std::unique_ptr<World> fw;
    if (scenes.size() == 1 && !stress) { // one scene: a row per class over it
        o.scene = scenes[0];
        fw.reset(new World);
        std::string err;
        int code = RF_EXIT_FILE;
        if (!load_world(o.scene, *fw, &err, &code)) {
            fprintf(stderr, "refray-verify: %s\n", err.c_str());
            return code;
        }
        if (classes.empty())
            classes.assign(std::begin(kFileClasses), std::end(kFileClasses));
        for (const std::string &c : classes)
            if (std::find(std::begin(kFileClasses), std::end(kFileClasses), c) == std::end(kFileClasses)) {
                return rf_opt_usage_error(&verify_cmd, "class '%s' runs on built-in scenes only", c.c_str());
            }
    } else {
        if (stress || (classes.empty() && scenes.empty()))
            classes.assign(std::begin(kAllClasses), std::end(kAllClasses));
        for (const char *sc : scenes) // several scenes, or --stress: one aggregated row each
            classes.push_back(std::string("scene:") + sc);
    }
    std::vector<Stats> rows = run_all(classes, o, jobs, fw.get());
    printf("refray-verify: %s, %ld rays per class (%ld per class in scene rows), seed %llu%s\n",
           o.scene ? o.scene : "built-in scenes", o.rays, o.scene_rays, (unsigned long long)o.seed,
           o.kernel ? " (kernel mode: planted methods)" : "");
    if (o.fixed_offset > 0)
        printf("planted: fixed self-intersection offset %g\n", o.fixed_offset);
    if (g_cone_geometric)
        printf("cones judged by the geometric bound (--cone-bound geometric)\n");
    print_table(rows, stdout);
    long real = 0;
    int errors = 0;
    for (const Stats &s : rows) {
        real += s.real;
        if (s.error) {
            errors++;
            fprintf(stderr, "refray-verify: %s\n", s.error_msg);
        }
    }
    if (real)
        printf("FAIL: real disagreements\n");
    else if (errors)
        printf("ERROR: %d row%s could not run (see above)\n", errors, errors > 1 ? "s" : "");
    else
        printf("OK: no real disagreement\n");
    return real || errors ? RF_EXIT_FAIL : RF_EXIT_OK;
}

} // namespace
} // namespace rv

int main(int argc, char **argv)
{
    // the last line of defence: no exception ends the process with an abort
    try {
        return rv::verify_main(argc, argv);
    } catch (const std::bad_alloc &) {
        fprintf(stderr, "refray-verify: out of memory\n");
    } catch (const std::exception &e) {
        fprintf(stderr, "refray-verify: internal error: %s\n", e.what());
    }
    return 2;
}
