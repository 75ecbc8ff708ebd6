// refray-verify: what the verifier's parts share besides the oracle (verify.hpp): the options,
// a row's statistics, the random numbers, the worlds built in code, and the entries of the
// parts (verify_world.cpp: the worlds' builders; verify_check.cpp: one ray against the exact
// answer; verify_rays.cpp: the ray classes; verify_edges.cpp: acne, leaks, optics and stress
// renders; verify.cpp: the driver).
#ifndef REFRAY_VERIFY_RUN_HPP
#define REFRAY_VERIFY_RUN_HPP

#include <cmath>
#include <cstdint>
#include <map>
#include <memory>
#include <vector>

#include "verify.hpp"
#include "refray/mat.h"

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

    World();
    ~World();
    World(const World &) = delete;
    World &operator=(const World &) = delete;

    void grow(RfVec3 p);
    void add(RfPrimitive p, int mesh);
    void sphere(RfVec3 c, double r, unsigned flags);
    void poly(const RfVec3 *v, int n, unsigned flags, int mesh);
    void plane(RfVec3 n, double offset);
    void cone(RfVec3 base, double rb, RfVec3 apex, double ra, unsigned flags);
    // object NAME ... end (§4.8): the primitives added in between belong to the object
    int begin_object(const char *name);
    void end_object(int o);
    void instance(int object, RfMat4 m);
    // The icosahedron subdivided `level` times, vertices on radius r (times 1 + jitter*U(-1,1)):
    // closed, two-sided triangles sharing their vertices' doubles exactly.
    void icosphere(RfVec3 c, double r, int level, double jitter, Rng &rng);
    // The box [0, n h]^3 + corner, each face an n x n grid of squares split into two triangles
    // along alternating diagonals. With h a power of two and a dyadic corner every vertex and
    // every edge point k/2^10 of the way is exact, so rays can pass exactly through them.
    void grid_cube(RfVec3 corner, int n, double h);
    // An exactly planar quad p0, p0+u, p0+u+v, p0+v: u, v small integers times 2^e, p0 a
    // multiple of 2^(e-20), so every sum is exact.
    void quad(RfVec3 p0, double s, Rng &rng, unsigned flags);
    // A star or gear outline of 2 k vertices (k = 4 .. 20, radii alternating between s and
    // s * U(0.2, 0.7), gear teeth or spikes): non-convex. exact: in the plane p0 + i u + j v
    // with small integer vectors u, v times a power of two and integer (i, j), so the vertices
    // are exactly coplanar and every edge point k/2^10 of the way is exact; otherwise in a
    // random plane with coordinates rounded to 7 significant digits (as in the SPD's gears).
    void star(RfVec3 c, double s, bool exact, unsigned flags, Rng &rng);
    // Spheres, a closed jittered icosphere, quads, loose triangles and a plane, all scaled by s
    // around `at` (the uniform, far and surface classes).
    void mixed(RfVec3 at, double s, Rng &rng);
    // Throws SceneError (the oracle's range and model checks).
    void finish();
    // The closed mesh whose certain interior (its box, or its ball in an object's placement)
    // holds o, or -1: a ray from o must hit that mesh.
    int interior_mesh(RfVec3 o) const;
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
