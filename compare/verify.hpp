// refray-verify: shared declarations of the CGAL verifier (docs/verify.md). Only
// verify_oracle.cpp includes CGAL; the rest sees the oracle through this interface.
#ifndef REFRAY_VERIFY_HPP
#define REFRAY_VERIFY_HPP

#include <memory>
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

enum ItemKind { ITEM_TRI, ITEM_SPHERE, ITEM_PLANE, ITEM_UNSUPPORTED };

// One thing the oracle intersects, made from the tracer's own doubles (a convex polygon becomes
// the tracer's fan triangles v0, v(k+1), v(k+2)).
struct Item {
    ItemKind kind;
    int prim;
    unsigned flags; // RF_PRIM_*
    RfVec3 p[3];    // triangle
    RfSphere s;
    RfPlane pl;
    RfAabb box;     // not for planes
};

struct ExactHit {
    bool hit = false;
    std::vector<int> items; // the nearest items (several when exactly tied)
    long double t = 0;      // the exact nearest t, rounded (for reports and tie bands)
    bool t_ok = false;      // exact |t - tracer_t| <= tol (when asked)
    bool coplanar = false;  // the ray lies in the plane of a candidate triangle/plane
    bool skipped = false;   // a candidate the oracle does not model (cone, non-convex polygon)
    bool inconsistent = false; // CGAL's do_intersect(Ray_3, Sphere_3) disagreed with the root test
};

class Oracle {
public:
    explicit Oracle(const RfScene *scene);
    ~Oracle();
    Oracle(const Oracle &) = delete;
    Oracle &operator=(const Oracle &) = delete;

    const std::vector<Item> &items() const { return items_; }
    const std::vector<int> &items_of(int prim) const { return prim_items_[(size_t)prim]; }
    // Every item the ray can possibly meet at t >= 0 (padded boxes: never a false miss).
    void candidates(RfRay ray, std::vector<int> &out) const;
    // The exact nearest hit at t >= 0 with the tracer's rules (the first root of a sphere in
    // range, then one-sidedness; a ray in a triangle's plane does not hit it). When tol >= 0,
    // t_ok says whether the exact t lies within tol of tracer_t.
    ExactHit nearest(RfRay ray, double tracer_t, double tol) const;
    // Exact side of q: triangle/plane: sign of <q - p1, N>; sphere: sign(|q - c|^2 - r^2).
    int side(int item, RfVec3 q) const;
    // Exact: does the closed segment [a, b] meet the triangle item?
    bool segment_hits(int item, RfVec3 a, RfVec3 b) const;

private:
    struct Impl;
    std::vector<Item> items_;
    std::vector<std::vector<int>> prim_items_;
    std::unique_ptr<Impl> impl_;
};

} // namespace rv

#endif
