// refray-verify: shared declarations of the CGAL verifier (docs/verify.md). Only
// verify_oracle.cpp includes CGAL; the rest sees the oracle through this interface.
#ifndef REFRAY_VERIFY_HPP
#define REFRAY_VERIFY_HPP

#include <cmath>
#include <deque>
#include <functional>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "refray/bvh.h"
#include "refray/intersect.h"
#include "refray/render.h"
#include "refray/scene.h"

namespace rv {

// The ambiguity bound: a disagreement is "ambiguous" when the exact configuration is within
// kDelta * S of a boundary (an edge line, a tangent, the ray origin on the surface, two equal
// distances), S being the size of the numbers the tracer's decision subtracts and multiplies
// (docs/verify.md derives the tracer's own bound, <= 16 eps S, and keeps a factor 4 of room).
constexpr double kEps = 0x1p-53;
constexpr double kDelta = 64 * kEps;

// The verifier's range (docs/verify.md, "Range"): every coordinate, radius, plane offset and
// instance matrix entry (composed along the scene graph, and of the inverse) at most kMaxMag
// in magnitude, every primitive at least kMinSize across. Beyond it the tracer's squares
// overflow or underflow and the verifier's own double arithmetic (ray generators, boxes) stops
// being meaningful; such a scene is refused with its position.
constexpr double kMaxMag = 0x1p100;
constexpr double kMinSize = 0x1p-100;

// A scene outside that range (or one the oracle cannot model): what and where.
struct SceneError : std::runtime_error {
    int prim;    // the primitive to blame, -1 when none
    RfSrcLoc loc; // its position (line 0: unknown)
    SceneError(const std::string &what, int p, RfSrcLoc l) : std::runtime_error(what), prim(p), loc(l) {}
};

// ---- long double vectors (margins, local rays) -----------------------------------------------

typedef long double L;
struct LV {
    L x, y, z;
};
inline LV lv(RfVec3 v) { return {v.x, v.y, v.z}; }
inline LV sub(LV a, LV b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline LV add(LV a, LV b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
inline LV scale(LV a, L s) { return {a.x * s, a.y * s, a.z * s}; }
inline L dot(LV a, LV b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline LV cross(LV a, LV b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
inline L len(LV a) { return std::sqrt(dot(a, a)); }
inline L comp(LV a, int k) { return k == 0 ? a.x : k == 1 ? a.y : a.z; }

// An affine map x -> m[.][0..2] x + m[.][3] in long double.
struct Affine {
    L m[3][4];
    LV point(LV p) const
    {
        return {m[0][0] * p.x + m[0][1] * p.y + m[0][2] * p.z + m[0][3],
                m[1][0] * p.x + m[1][1] * p.y + m[1][2] * p.z + m[1][3],
                m[2][0] * p.x + m[2][1] * p.y + m[2][2] * p.z + m[2][3]};
    }
    LV dir(LV p) const
    {
        return {m[0][0] * p.x + m[0][1] * p.y + m[0][2] * p.z, m[1][0] * p.x + m[1][1] * p.y + m[1][2] * p.z,
                m[2][0] * p.x + m[2][1] * p.y + m[2][2] * p.z};
    }
    static Affine identity()
    {
        Affine a{};
        a.m[0][0] = a.m[1][1] = a.m[2][2] = 1;
        return a;
    }
};

// ---- the oracle ------------------------------------------------------------------------------

enum ItemKind { ITEM_TRI, ITEM_SPHERE, ITEM_PLANE, ITEM_CONE, ITEM_INSTANCE };

// One thing the oracle intersects, made from the tracer's own doubles (a polygon becomes the
// tracer's triangles: a convex one's fan v0, v(k+1), v(k+2), a non-convex one's ear clipping).
// Items of an object (level o + 1) live in that object's space and are reached through instances.
struct Item {
    ItemKind kind;
    int prim;       // the scene primitive (the tracer reports an object's primitive by its own index)
    int level;      // 0: the world; o + 1: object o
    unsigned flags; // RF_PRIM_*
    RfVec3 p[3];    // triangle
    RfSphere s;
    RfPlane pl;
    RfCone cone;
    int inst;       // ITEM_INSTANCE: index into RfScene.instances
    RfAabb box;     // in its level's space; empty: unbounded (planes, instances of unbounded objects)
};

// An item met through an instance path: path 0 is the world itself, any other a chain of
// instances from the world down (Oracle::path).
struct Cand {
    int item, path;
};

// A world ray in a path's object space.
struct LocalRay {
    LV o, d;     // the exact object-space ray (the world ray under the exact inverse of the composed
                 // to_world matrices), rounded to long double
    L dev_o, dev_d; // bounds on |tracer's object-space origin / direction - exact| (0 in the world;
                    // infinite when the tracer cannot take the ray there)
};

struct Path {
    int parent, inst, level; // the instance taking parent's space to `level`'s (path 0: -1, -1, 0)
    std::vector<int> chain;  // instances from the world down
    Affine to_obj;           // the exact composed inverse, rounded to long double (~2^-106)
    Affine to_world;         // the composed to_world matrices (products in long double)
};

struct ExactHit {
    bool hit = false;
    std::vector<Cand> items; // the nearest items (several when exactly tied)
    long double t = 0;       // the exact nearest t, rounded (for reports and tie bands)
    bool t_ok = false;       // exact |t - tracer_t| <= tol (when asked)
    bool coplanar = false;   // the ray lies in the plane of a candidate triangle or plane, or in
                             // a cone's surface (the tracer's "no hit" by contract)
    bool inconsistent = false; // CGAL's do_intersect(Ray_3, Sphere_3) disagreed with the root test
};

class Oracle {
public:
    // Throws SceneError for a scene outside the verifier's range (kMaxMag, kMinSize) or with a
    // transform the oracle does not model (a projective or exactly singular instance matrix).
    explicit Oracle(const RfScene *scene);
    ~Oracle();
    Oracle(const Oracle &) = delete;
    Oracle &operator=(const Oracle &) = delete;

    const RfScene *scene() const { return scene_; }
    const std::vector<Item> &items() const { return items_; }
    // Every item of a primitive (a polygon's triangles), of any level.
    const std::vector<int> &items_of(int prim) const { return prim_items_[(size_t)prim]; }
    // The items of a level (0: world, o + 1: object o).
    const std::vector<int> &level_items(int level) const;
    // The path below `parent` through scene instance `inst` (made on demand; throws
    // SceneError when the composed matrices leave the verifier's range).
    int child_path(int parent, int inst) const;
    const Path &path(int p) const { return (*paths_)[(size_t)p]; }
    int path_count() const { return (int)paths_->size(); }
    LocalRay local_ray(int path, RfRay world) const;

    // Every (item, path) the ray can possibly meet at t >= 0 (padded boxes: never a false miss),
    // instances entered.
    void candidates(RfRay ray, std::vector<Cand> &out) const;
    // The exact nearest hit at t >= 0 among cands with the tracer's rules (the first root of a
    // sphere or cone in range that faces the visible side, one-sidedness; a ray in a triangle's
    // plane does not hit it). When tol >= 0, t_ok says whether the exact t lies within tol of
    // tracer_t. May throw (CGAL, std::bad_alloc): the caller counts the ray as not representable.
    ExactHit nearest(RfRay ray, const std::vector<Cand> &cands, double tracer_t, double tol) const;
    // Exact side of q (world items): triangle/plane: sign of <q - p1, N>; sphere:
    // sign(|q - c|^2 - r^2); cone: sign of (distance from the axis)^2 - radius^2 (0 elsewhere).
    int side(int item, RfVec3 q) const;
    // Exact sign of <d, N> for a world triangle (its winding's normal), 0 for other items.
    int facing(int item, RfVec3 d) const;
    // Exact: does the closed segment [a, b] meet the triangle item?
    bool segment_hits(int item, RfVec3 a, RfVec3 b) const;

private:
    struct Impl;
    const RfScene *scene_;
    std::vector<Item> items_;
    std::vector<std::vector<int>> prim_items_;
    std::unique_ptr<std::deque<Path>> paths_; // grows on demand; references stay valid
    std::unique_ptr<Impl> impl_;
};

} // namespace rv

#endif
