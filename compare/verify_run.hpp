// refray-verify: what the verifier's parts share besides the oracle (verify.hpp): the options,
// a row's statistics, the random numbers, the worlds built in code, and the entries of the
// parts (verify_check.cpp: one ray against the exact answer; verify_rays.cpp: the ray classes;
// verify_edges.cpp: acne, leaks, optics and stress renders; verify.cpp: the driver).
#ifndef REFRAY_VERIFY_RUN_HPP
#define REFRAY_VERIFY_RUN_HPP

#include <cmath>
#include <cstdint>
#include <map>
#include <memory>
#include <vector>

#include "verify.hpp"
#include "refray/numeric.h"
#include "refray/optics.h"
#include "refray/scene_io.h"
#include "refray/transform.h"

namespace rv {

// ---- options, statistics ----------------------------------------------------------------

struct Opts {
    long rays = 100000;
    uint64_t seed = 1;
    bool kernel = false; // the tracer under test is verify_check.cpp's kernel loop (planted methods)
    RfTriangleMethod tri = RF_TRIANGLE_WATERTIGHT;
    RfSphereMethod sph = RF_SPHERE_STABLE;
    double fixed_offset = 0; // > 0: planted fixed epsilon instead of the offset policy
    const char *scene = nullptr; // one scene file: the classes over it, one row each
    long scene_rays = 0;         // rays per class in the aggregated rows of --stress scenes
    bool cone_geometric = false; // --cone-bound geometric: cones judged by the sphere's kind of bound
    long fault_every = 0;        // testing hook (tests/test_stress.c): REFRAY_VERIFY_FAULT=N makes every
                                 // N-th exact evaluation of a row throw, as CGAL does on a value it
                                 // cannot represent
};

// Plain data: children of --jobs send it back through a pipe.
struct Stats {
    char name[16];
    long rays, agree, amb, real, edge_miss, skipped; // skipped: rays not representable
    long acne_n, acne_d; // falsely occluded (or leaking) samples / samples
    long evaluations;    // exact evaluations begun (Opts::fault_every counts them)
    double secs;
    int n_examples;
    char examples[3][480];
    char skip_note[480]; // the first ray skipped as not representable, and why
    int error;           // the row could not run (a scene not loaded or refused): error_msg
    char error_msg[480];
};

// An example line for the report (at most three per row).
void example(Stats &st, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
// A ray whose exact evaluation is impossible (an exception from CGAL or the allocator, a
// non-finite ray): counted as skipped, the first one kept for the report.
void not_representable(Stats &st, RfRay r, const char *why);
// The row could not run (a scene not loaded or refused): its message.
void row_error(Stats &st, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
bool finite_ray(RfRay r);

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
void frame(RfVec3 k, RfVec3 *u, RfVec3 *v);

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

// ---- the parts' entries ----------------------------------------------------------------------

// One ray checked and counted; a ray the oracle cannot evaluate exactly (an exception: CGAL's
// conversions, the allocator) or that is not finite is counted as skipped (not representable).
void check_and_tally(Stats &st, const World &w, const Opts &o, RfRay r, int interior);
// The rows of the ray classes on worlds built in code (verify_rays.cpp).
void run_rays(const char *cls, const Opts &o, Stats &st);
// The classes on a scene file: the same generators over its primitives.
void run_file(const char *cls, const Opts &o, World &w, Stats &st);
// Shadow acne, light leaks, the optics' edge cases and stress renders (verify_edges.cpp).
void run_acne(const Opts &o, Stats &st);
void run_leak(const Opts &o, Stats &st);
void run_optics(const Opts &o, Stats &st);
void run_invalid(const Opts &o, Stats &st);

} // namespace rv

#endif
