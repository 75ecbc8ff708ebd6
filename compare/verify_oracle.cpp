// refray-verify: the exact oracle. CGAL's Exact_predicates_exact_constructions_kernel (Epeck:
// interval-filtered, exact rational fall-back) decides every hit; distances are compared
// exactly, sphere and cone roots included (see cmp_roots). The candidate search is a plain BVH
// over padded boxes per level (the world, each object), written here so that the oracle shares
// no code with the tracer's BVH. Instances: the world ray is taken into the object's space by
// the exact inverse of the composed to_world matrices (as stored in doubles), so the reference
// is the exact intersection with the object placed by those matrices; t is the same in both
// spaces (the direction is not normalised, as in the tracer, §4.8). The inverse is applied
// without a division: adj(L) (x - T) = det(L) L^-1 (x - T), i.e. the object's space scaled by
// sigma = det (composed along the path), where the object's items are scaled by sigma too.
// Every number stays a dyadic rational (a sum of products of doubles), which keeps the exact
// fall-backs cheap.
#include "verify.hpp"

// GCC 12 reports boost::tuple members inside CGAL's Sphere_3 as maybe-uninitialized after
// inlining (a known false positive of CGAL + GCC >= 11); the code is CGAL's, not ours.
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"

// One thread per process (--jobs forks): CGAL's lazy kernel need not guard its exact values
// with std::call_once (a futex per exact evaluation).
#define CGAL_HAS_NO_THREADS 1
#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/intersections.h>

#include <algorithm>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <functional>

#include "refray/geometry.h"
#include "refray/transform.h"

namespace rv {

typedef CGAL::Exact_predicates_exact_constructions_kernel K;
typedef K::FT FT;
typedef K::Point_3 Point;
typedef K::Vector_3 Vector;

namespace {

// den t = x + s sqrt(D) with den > 0, s in {-1, 0, 1}: triangles and planes have s = 0
// (t rational), sphere and cone roots s = -1 (near) or +1 (far). Roots of one ray in one
// space share den = <d,d> (den_id: the path), so they compare without any division; a cone's
// roots carry their own denominator (den_id -1).
struct Root {
    FT x;
    int s;
    FT D;
    FT den;
    int den_id;
};

int sgn(const FT &v) { return (int)CGAL::sign(v); }

// The exact sign of x + y sqrt(D), D >= 0.
int sign_root(const FT &x, const FT &y, const FT &D)
{
    int sx = sgn(x), sy = sgn(D) == 0 ? 0 : sgn(y);
    if (sy == 0)
        return sx;
    if (sx == 0 || sx == sy)
        return sy;
    return sx * sgn(x * x - y * y * D); // opposite signs: the larger magnitude wins
}

// The exact sign of A - B for two roots of the same denominator: P = (xA - xB) + sA sqrt(DA)
// against Q = sB sqrt(DB); when P and Q share a sign, compare P^2 with Q^2, which is again of
// the form x + y sqrt(DA).
int cmp_same(const FT &xA, int sA, const FT &DA, const FT &xB, int sB, const FT &DB)
{
    FT u = xA - xB;
    int sP = sign_root(u, FT(sA), DA);
    int sQ = (sB == 0 || sgn(DB) == 0) ? 0 : sB;
    if (sP != sQ)
        return sP > sQ ? 1 : -1;
    if (sP == 0)
        return 0;
    FT x = u * u + (sA != 0 ? DA : FT(0)) - (sB != 0 ? DB : FT(0));
    return sP * sign_root(x, FT(2 * sA) * u, DA);
}

// The exact sign of A - B: over a common denominator (denB A against denA B) when they differ.
int cmp_roots(const Root &A, const Root &B)
{
    if (A.den_id >= 0 && A.den_id == B.den_id)
        return cmp_same(A.x, A.s, A.D, B.x, B.s, B.D);
    return cmp_same(B.den * A.x, A.s, A.s ? B.den * B.den * A.D : FT(0), A.den * B.x, B.s,
                    B.s ? A.den * A.den * B.D : FT(0));
}

Point pt(RfVec3 v) { return Point(v.x, v.y, v.z); }
Vector vc(RfVec3 v) { return Vector(v.x, v.y, v.z); }
double coord(RfVec3 v, int k) { return k == 0 ? v.x : k == 1 ? v.y : v.z; }

// A long double close to the exact value: a double within an ulp of it plus one within an ulp
// of the rest (~2^-105 relative). The exact values are forced first: CGAL's to_double alone
// accepts a relative error of 1e-5.
L approx(const FT &v)
{
    CGAL::exact(v);
    double hi = CGAL::to_double(v);
    if (!std::isfinite(hi))
        return (L)hi;
    FT rest = v - FT(hi);
    CGAL::exact(rest);
    return (L)hi + (L)CGAL::to_double(rest);
}

// The world -> object map of a path, scaled: x -> m[.][0..2] x + m[.][3] = sigma (the exact
// object-space point), sigma != 0 (the product of the path's determinants). Dyadic entries.
struct XMat {
    FT m[3][4];
    FT sigma;
};

// The path through instance b below a: b's lin (a's map) + a's sigma b's translation.
XMat compose(const XMat &b, const XMat &a)
{
    XMat r;
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 4; j++) {
            FT s = j == 3 ? a.sigma * b.m[i][3] : FT(0);
            for (int k = 0; k < 3; k++)
                s = s + b.m[i][k] * a.m[k][j];
            CGAL::exact(s); // a leaf from here on: later rays build short expression DAGs
            r.m[i][j] = s;
        }
    r.sigma = a.sigma * b.sigma;
    CGAL::exact(r.sigma);
    return r;
}

struct Node {
    RfAabb box;
    int left, right; // children, or -1 for a leaf
    int first, count;
};

// The slab test on a box padded by 1e-9 of the magnitudes involved (plus `extra`, the error of
// an object-space ray): the rounding of the double computation is ~1e-16 of them, so no box the
// exact ray meets is ever culled.
bool slab_hit(const RfAabb &b, RfRay r, double extra)
{
    const double o[3] = {r.origin.x, r.origin.y, r.origin.z}, d[3] = {r.dir.x, r.dir.y, r.dir.z};
    const double lo[3] = {b.lo.x, b.lo.y, b.lo.z}, hi[3] = {b.hi.x, b.hi.y, b.hi.z};
    double mag = 0;
    for (int k = 0; k < 3; k++)
        mag = std::max({mag, std::fabs(o[k]), std::fabs(lo[k]), std::fabs(hi[k])});
    double pad = 1e-9 * mag + extra + 1e-300;
    double tmin = 0, tmax = HUGE_VAL;
    for (int k = 0; k < 3; k++) {
        double l = lo[k] - pad, h = hi[k] + pad;
        if (d[k] == 0) {
            if (o[k] < l || o[k] > h)
                return false;
            continue;
        }
        double t0 = (l - o[k]) / d[k], t1 = (h - o[k]) / d[k];
        if (t0 > t1)
            std::swap(t0, t1);
        tmin = std::max(tmin, t0);
        tmax = std::min(tmax, t1);
    }
    return tmin <= tmax * (1 + 1e-9) + 1e-300;
}

} // namespace

struct Oracle::Impl {
    struct ExactItem {
        K::Triangle_3 tri;
        Vector n;
        bool degenerate = false;
        Point c;
        FT r2;
        FT off;
        Point base;      // cone
        Vector A;        // apex - base
        FT AA, rb, dr;   // <A,A>, base radius, apex radius - base radius
    };
    struct Level {
        std::vector<int> items, unbounded, order;
        std::vector<Node> nodes;
        RfAabb box = rf_aabb_empty();
        int state = 0; // 0 not built, 1 building, 2 built
    };
    std::vector<ExactItem> ex;
    std::vector<Level> levels;
    std::vector<XMat> inst_inv;         // per scene instance: adj(L), -adj(L) T, det(L) of to_world
    std::vector<int> inst_prim;         // per scene instance: its primitive (for messages)
    std::deque<XMat> path_inv;          // per path: the scaled composed inverse
    std::map<std::pair<int, int>, int> path_ix;

    int build(const std::vector<Item> &items, Level &lv, int first, int count)
    {
        Node nd;
        nd.box = rf_aabb_empty();
        for (int i = first; i < first + count; i++)
            nd.box = rf_aabb_union(nd.box, items[(size_t)lv.order[(size_t)i]].box);
        nd.left = nd.right = -1;
        nd.first = first;
        nd.count = count;
        int idx = (int)lv.nodes.size();
        lv.nodes.push_back(nd);
        if (count <= 4)
            return idx;
        RfVec3 ext = rf_vec3_sub(nd.box.hi, nd.box.lo);
        int axis = ext.x >= ext.y ? (ext.x >= ext.z ? 0 : 2) : (ext.y >= ext.z ? 1 : 2);
        auto key = [&](int i) {
            RfVec3 c = rf_aabb_center(items[(size_t)i].box);
            return axis == 0 ? c.x : axis == 1 ? c.y : c.z;
        };
        int mid = first + count / 2;
        std::nth_element(lv.order.begin() + first, lv.order.begin() + mid, lv.order.begin() + first + count,
                         [&](int a, int b) { return key(a) < key(b); });
        int l = build(items, lv, first, mid - first);
        int r = build(items, lv, mid, first + count - mid);
        lv.nodes[(size_t)idx].left = l;
        lv.nodes[(size_t)idx].right = r;
        return idx;
    }
};

namespace {

[[noreturn]] void refuse(const RfScene *s, int prim, const char *fmt, ...) __attribute__((format(printf, 3, 4)));
[[noreturn]] void refuse(const RfScene *s, int prim, const char *fmt, ...)
{
    char msg[512];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    RfSrcLoc loc{0, 0};
    std::string what;
    if (prim >= 0) {
        loc = s->prims[prim].loc;
        what = std::string(rf_prim_type_name(s->prims[prim].type)) + " (primitive " + std::to_string(prim) + "): ";
    }
    throw SceneError(what + msg, prim, loc);
}

const char kRange[] = "outside the verifier's range (|x| <= 2^100 ~ 1.3e30, sizes >= 2^-100 ~ 7.9e-31)";

void check_mag(const RfScene *s, int prim, const char *what, double v)
{
    if (!(std::fabs(v) <= kMaxMag))
        refuse(s, prim, "%s %.17g is %s", what, v, kRange);
}

void check_vec(const RfScene *s, int prim, const char *what, RfVec3 v)
{
    check_mag(s, prim, what, v.x);
    check_mag(s, prim, what, v.y);
    check_mag(s, prim, what, v.z);
}

void check_size(const RfScene *s, int prim, const char *what, double v)
{
    if (!(v >= kMinSize))
        refuse(s, prim, "%s %.17g is %s", what, v, kRange);
}

// Every number of a primitive within the verifier's range (kMaxMag, kMinSize).
void check_prim(const RfScene *s, int i)
{
    const RfPrimitive *p = &s->prims[i];
    switch (p->type) {
    case RF_PRIM_SPHERE:
        check_vec(s, i, "centre coordinate", p->u.sphere.center);
        check_mag(s, i, "radius", p->u.sphere.radius);
        check_size(s, i, "radius", p->u.sphere.radius);
        break;
    case RF_PRIM_PLANE:
        check_mag(s, i, "offset", p->u.plane.offset);
        break;
    case RF_PRIM_TRIANGLE:
    case RF_PRIM_POLYGON: {
        RfAabb b = rf_aabb_empty();
        for (int k = 0; k < p->u.poly.count; k++) {
            RfVec3 v = s->vertices[p->u.poly.first + (size_t)k];
            check_vec(s, i, "vertex coordinate", v);
            b = rf_aabb_add_point(b, v);
        }
        RfVec3 e = rf_vec3_sub(b.hi, b.lo);
        check_size(s, i, "extent", std::max({e.x, e.y, e.z}));
        break;
    }
    case RF_PRIM_CONE: {
        const RfCone &c = p->u.cone;
        check_vec(s, i, "base coordinate", c.base);
        check_vec(s, i, "apex coordinate", c.apex);
        check_mag(s, i, "base radius", c.base_radius);
        check_mag(s, i, "apex radius", c.apex_radius);
        check_size(s, i, "largest radius", std::max(c.base_radius, c.apex_radius));
        RfVec3 a = rf_vec3_sub(c.apex, c.base);
        check_size(s, i, "length", std::max({std::fabs(a.x), std::fabs(a.y), std::fabs(a.z)}));
        break;
    }
    default:
        break;
    }
}

} // namespace

Oracle::Oracle(const RfScene *s)
    : scene_(s), prim_items_(s->prim_count), paths_(new std::deque<Path>), impl_(new Impl)
{
    Impl &im = *impl_;
    im.levels.resize(s->object_count + 1);
    im.inst_prim.assign(s->instance_count, -1);
    // ---- items, per level
    for (size_t i = 0; i < s->prim_count; i++) {
        const RfPrimitive *p = &s->prims[i];
        check_prim(s, (int)i);
        int level = 0;
        if (p->flags & RF_PRIM_IN_OBJECT) { // the object whose range holds it
            level = -1;
            for (size_t o = 0; o < s->object_count; o++)
                if (i >= s->objects[o].first && i < s->objects[o].first + s->objects[o].count)
                    level = (int)o + 1;
            if (level < 0) // in no object: never rendered
                continue;
        }
        Item it{};
        it.prim = (int)i;
        it.level = level;
        it.flags = p->flags;
        it.inst = -1;
        it.box = rf_aabb_empty();
        auto vert = [&](int k) { return s->vertices[p->u.poly.first + (size_t)k]; };
        auto push = [&](const Item &x) {
            prim_items_[i].push_back((int)items_.size());
            im.levels[(size_t)level].items.push_back((int)items_.size());
            items_.push_back(x);
        };
        switch (p->type) {
        case RF_PRIM_SPHERE: {
            it.kind = ITEM_SPHERE;
            it.s = p->u.sphere;
            RfVec3 r = rf_vec3(it.s.radius, it.s.radius, it.s.radius);
            it.box.lo = rf_vec3_sub(it.s.center, r);
            it.box.hi = rf_vec3_add(it.s.center, r);
            push(it);
            break;
        }
        case RF_PRIM_PLANE:
            it.kind = ITEM_PLANE;
            it.pl = p->u.plane;
            push(it);
            break;
        case RF_PRIM_TRIANGLE:
        case RF_PRIM_POLYGON: {
            // the tracer's triangles: a convex polygon's fan, a non-convex one's ear clipping
            // (the same rf_triangulate_polygon, tracer.c), each decided exactly
            std::vector<int> corner(3 * (size_t)std::max(1, p->u.poly.count - 2));
            bool cut = p->type == RF_PRIM_POLYGON && (p->flags & RF_PRIM_NONCONVEX);
            if (cut && rf_triangulate_polygon(s->vertices + p->u.poly.first, p->u.poly.count, corner.data()) < 0)
                refuse(s, (int)i, "could not be triangulated (out of memory)");
            for (int k = 0; k + 2 < p->u.poly.count; k++) {
                it.kind = ITEM_TRI;
                it.p[0] = vert(cut ? corner[3 * (size_t)k] : 0);
                it.p[1] = vert(cut ? corner[3 * (size_t)k + 1] : k + 1);
                it.p[2] = vert(cut ? corner[3 * (size_t)k + 2] : k + 2);
                it.box = rf_aabb_empty();
                for (int j = 0; j < 3; j++)
                    it.box = rf_aabb_add_point(it.box, it.p[j]);
                push(it);
            }
            break;
        }
        case RF_PRIM_CONE: {
            it.kind = ITEM_CONE;
            it.cone = p->u.cone;
            const RfCone &c = p->u.cone;
            double m = std::max(c.base_radius, c.apex_radius);
            RfVec3 r = rf_vec3(m, m, m);
            it.box = rf_aabb_add_point(it.box, rf_vec3_sub(c.base, r));
            it.box = rf_aabb_add_point(it.box, rf_vec3_add(c.base, r));
            it.box = rf_aabb_add_point(it.box, rf_vec3_sub(c.apex, r));
            it.box = rf_aabb_add_point(it.box, rf_vec3_add(c.apex, r));
            push(it);
            break;
        }
        case RF_PRIM_INSTANCE: {
            it.kind = ITEM_INSTANCE;
            it.inst = (int)p->u.instance;
            if (it.inst < 0 || (size_t)it.inst >= s->instance_count || s->instances[it.inst].object < 0 ||
                (size_t)s->instances[it.inst].object >= s->object_count)
                refuse(s, (int)i, "names no object");
            im.inst_prim[(size_t)it.inst] = (int)i;
            push(it); // its box once the object's level is built
            break;
        }
        default:
            refuse(s, (int)i, "a primitive type the oracle does not know");
        }
    }
    // ---- the exact inverse of every instance's to_world (affine, as stored in doubles)
    im.inst_inv.resize(s->instance_count);
    for (size_t n = 0; n < s->instance_count; n++) {
        const RfMat4 &M = s->instances[n].to_world;
        int prim = im.inst_prim[n];
        if (prim < 0)
            continue;
        if (!(M.m[3][0] == 0 && M.m[3][1] == 0 && M.m[3][2] == 0 && M.m[3][3] == 1))
            refuse(s, prim, "a projective transform (last row not 0 0 0 1) is not modelled");
        for (int i = 0; i < 3; i++)
            for (int j = 0; j < 4; j++)
                check_mag(s, prim, "transform entry", M.m[i][j]);
        FT a[3][3];
        for (int i = 0; i < 3; i++)
            for (int j = 0; j < 3; j++)
                a[i][j] = FT(M.m[i][j]);
        FT cof[3][3];
        for (int i = 0; i < 3; i++)
            for (int j = 0; j < 3; j++) {
                int i1 = (i + 1) % 3, i2 = (i + 2) % 3, j1 = (j + 1) % 3, j2 = (j + 2) % 3;
                cof[i][j] = a[i1][j1] * a[i2][j2] - a[i1][j2] * a[i2][j1];
            }
        FT det = a[0][0] * cof[0][0] + a[0][1] * cof[0][1] + a[0][2] * cof[0][2];
        if (sgn(det) == 0)
            refuse(s, prim, "the transform is exactly singular");
        XMat &X = im.inst_inv[n];
        for (int i = 0; i < 3; i++)
            for (int j = 0; j < 3; j++) {
                X.m[i][j] = cof[j][i]; // adj(L)
                CGAL::exact(X.m[i][j]);
            }
        for (int i = 0; i < 3; i++) {
            FT t = FT(0);
            for (int k = 0; k < 3; k++)
                t = t - X.m[i][k] * FT(M.m[k][3]);
            CGAL::exact(t);
            X.m[i][3] = t;
        }
        X.sigma = det;
        CGAL::exact(X.sigma);
        for (int i = 0; i < 3; i++)
            for (int j = 0; j < 4; j++)
                check_mag(s, prim, "inverse transform entry", CGAL::to_double(X.m[i][j] / det));
    }
    // ---- exact data per item
    im.ex.resize(items_.size());
    for (size_t i = 0; i < items_.size(); i++) {
        const Item &it = items_[i];
        Impl::ExactItem &e = im.ex[i];
        if (it.kind == ITEM_TRI) {
            e.tri = K::Triangle_3(pt(it.p[0]), pt(it.p[1]), pt(it.p[2]));
            e.degenerate = CGAL::collinear(e.tri[0], e.tri[1], e.tri[2]);
            e.n = CGAL::cross_product(e.tri[1] - e.tri[0], e.tri[2] - e.tri[0]);
        } else if (it.kind == ITEM_SPHERE) {
            e.c = pt(it.s.center);
            e.r2 = FT(it.s.radius) * FT(it.s.radius);
        } else if (it.kind == ITEM_PLANE) {
            e.n = vc(it.pl.normal);
            e.off = FT(it.pl.offset);
        } else if (it.kind == ITEM_CONE) {
            e.base = pt(it.cone.base);
            e.A = pt(it.cone.apex) - e.base;
            e.AA = e.A * e.A;
            e.rb = FT(it.cone.base_radius);
            e.dr = FT(it.cone.apex_radius) - e.rb;
            e.degenerate = sgn(e.AA) == 0;
        }
    }
    // ---- levels: BVHs, instance boxes (objects first, as the tracer builds them)
    std::function<void(int)> build_level = [&](int level) {
        Impl::Level &lv = im.levels[(size_t)level];
        if (lv.state == 2)
            return;
        if (lv.state == 1)
            throw SceneError("the scene graph has a cycle", -1, RfSrcLoc{0, 0});
        lv.state = 1;
        std::vector<int> keep;
        for (int i : lv.items) {
            Item &it = items_[(size_t)i];
            if (it.kind == ITEM_INSTANCE) {
                int child = s->instances[it.inst].object + 1;
                build_level(child);
                const Impl::Level &cl = im.levels[(size_t)child];
                if (cl.items.empty())
                    continue; // an empty object: nothing to hit (the tracer skips it too)
                if (cl.unbounded.empty()) {
                    // the 8 corners of the object's box under to_world, in long double, padded
                    // far beyond their rounding, then rounded outward
                    const RfMat4 &M = s->instances[it.inst].to_world;
                    L lo[3] = {HUGE_VALL, HUGE_VALL, HUGE_VALL}, hi[3] = {-HUGE_VALL, -HUGE_VALL, -HUGE_VALL};
                    for (int c = 0; c < 8; c++) {
                        L k[3] = {c & 1 ? cl.box.hi.x : cl.box.lo.x, c & 2 ? cl.box.hi.y : cl.box.lo.y,
                                  c & 4 ? cl.box.hi.z : cl.box.lo.z};
                        for (int r = 0; r < 3; r++) {
                            L v = M.m[r][3], mag = std::fabs((L)M.m[r][3]);
                            for (int j = 0; j < 3; j++) {
                                v += (L)M.m[r][j] * k[j];
                                mag += std::fabs((L)M.m[r][j] * k[j]);
                            }
                            L pad = mag * 0x1p-50L;
                            lo[r] = std::min(lo[r], v - pad);
                            hi[r] = std::max(hi[r], v + pad);
                        }
                    }
                    it.box.lo = rf_vec3(std::nextafter((double)lo[0], -HUGE_VAL), std::nextafter((double)lo[1], -HUGE_VAL),
                                        std::nextafter((double)lo[2], -HUGE_VAL));
                    it.box.hi = rf_vec3(std::nextafter((double)hi[0], HUGE_VAL), std::nextafter((double)hi[1], HUGE_VAL),
                                        std::nextafter((double)hi[2], HUGE_VAL));
                    for (int r = 0; r < 3; r++)
                        if (!(std::fabs((double)lo[r]) <= kMaxMag && std::fabs((double)hi[r]) <= kMaxMag))
                            refuse(s, it.prim, "the placed object's box reaches %.17g, %s",
                                   (double)std::max(std::fabs(lo[r]), std::fabs(hi[r])), kRange);
                }
            }
            keep.push_back(i);
            if (it.kind == ITEM_PLANE || it.box.lo.x > it.box.hi.x) // unbounded: always a candidate
                lv.unbounded.push_back(i);
            else {
                lv.order.push_back(i);
                lv.box = rf_aabb_union(lv.box, it.box);
            }
        }
        lv.items.swap(keep);
        if (!lv.order.empty())
            im.build(items_, lv, 0, (int)lv.order.size());
        lv.state = 2;
    };
    for (size_t l = 0; l < im.levels.size(); l++)
        build_level((int)l);
    // ---- paths: the world, then every chain of instances (up to a cap; more on demand), which
    // checks the composed matrices against the range up front
    Path world;
    world.parent = world.inst = -1;
    world.level = 0;
    world.to_obj = world.to_world = Affine::identity();
    paths_->push_back(world);
    XMat id;
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 4; j++)
            id.m[i][j] = FT(i == j ? 1 : 0);
    id.sigma = FT(1);
    im.path_inv.push_back(id);
    size_t budget = 100000;
    std::function<void(int)> walk = [&](int path) {
        for (int i : im.levels[(size_t)(*paths_)[(size_t)path].level].items) {
            if (items_[(size_t)i].kind != ITEM_INSTANCE || paths_->size() >= budget)
                continue;
            walk(child_path(path, items_[(size_t)i].inst));
        }
    };
    walk(0);
}

Oracle::~Oracle() = default;

const std::vector<int> &Oracle::level_items(int level) const { return impl_->levels[(size_t)level].items; }

int Oracle::child_path(int parent, int inst) const
{
    Impl &im = *impl_;
    auto key = std::make_pair(parent, inst);
    auto f = im.path_ix.find(key);
    if (f != im.path_ix.end())
        return f->second;
    const Path &pp = (*paths_)[(size_t)parent];
    const RfInstance &in = scene_->instances[inst];
    Path P;
    P.parent = parent;
    P.inst = inst;
    P.level = in.object + 1;
    P.chain = pp.chain;
    P.chain.push_back(inst);
    XMat X = parent == 0 ? im.inst_inv[(size_t)inst] : compose(im.inst_inv[(size_t)inst], im.path_inv[(size_t)parent]);
    L sig = approx(X.sigma);
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 4; j++) {
            P.to_obj.m[i][j] = approx(X.m[i][j]) / sig;
            L w = j == 3 ? pp.to_world.m[i][3] : 0; // the parent's to_world after this instance's M
            for (int k = 0; k < 3; k++)
                w += pp.to_world.m[i][k] * (L)in.to_world.m[k][j];
            P.to_world.m[i][j] = w;
            if (!(std::fabs(P.to_obj.m[i][j]) <= kMaxMag && std::fabs(P.to_world.m[i][j]) <= kMaxMag))
                refuse(scene_, im.inst_prim[(size_t)inst],
                       "the transform composed through the scene graph has an entry of %.17g, %s",
                       (double)std::max(std::fabs(P.to_obj.m[i][j]), std::fabs(P.to_world.m[i][j])), kRange);
        }
    int id = (int)paths_->size();
    paths_->push_back(P);
    im.path_inv.push_back(X);
    im.path_ix[key] = id;
    return id;
}

namespace {

// The world ray in a path's space, rounded to long double, with the bound of that rounding.
void approx_local(const Path &P, RfRay w, LV &o, LV &d, L &err_o, L &err_d)
{
    LV wo = lv(w.origin), wd = lv(w.dir);
    o = P.to_obj.point(wo);
    d = P.to_obj.dir(wd);
    err_o = err_d = 0;
    for (int i = 0; i < 3; i++) {
        L mo = std::fabs(P.to_obj.m[i][3]), md = 0;
        for (int j = 0; j < 3; j++) {
            mo += std::fabs(P.to_obj.m[i][j] * comp(wo, j));
            md += std::fabs(P.to_obj.m[i][j] * comp(wd, j));
        }
        err_o += mo;
        err_d += md;
    }
    err_o *= 0x1p-60L;
    err_d *= 0x1p-60L;
}

} // namespace

LocalRay Oracle::local_ray(int path, RfRay world) const
{
    LocalRay lr;
    if (path == 0) {
        lr.o = lv(world.origin);
        lr.d = lv(world.dir);
        lr.dev_o = lr.dev_d = 0;
        return lr;
    }
    const Path &P = (*paths_)[(size_t)path];
    L eo, ed;
    approx_local(P, world, lr.o, lr.d, eo, ed);
    // what the tracer computes: each level's rounded to_object on the previous level's ray
    RfRay r = world;
    bool ok = true;
    for (int inst : P.chain) {
        const RfMat4 &T = scene_->instances[inst].to_object;
        if (rf_transform_point(T, r.origin, &r.origin) != RF_OK)
            ok = false;
        r.dir = rf_transform_direction(T, r.dir);
    }
    lr.dev_o = ok ? len(sub(lv(r.origin), lr.o)) + eo : HUGE_VALL;
    lr.dev_d = ok ? len(sub(lv(r.dir), lr.d)) + ed : HUGE_VALL;
    if (!(lr.dev_o < HUGE_VALL && lr.dev_d < HUGE_VALL)) // every margin then ambiguous
        lr.dev_o = lr.dev_d = HUGE_VALL;
    return lr;
}

void Oracle::candidates(RfRay ray, std::vector<Cand> &out) const
{
    out.clear();
    const Impl &im = *impl_;
    std::function<void(int, RfRay, double)> collect = [&](int path, RfRay r, double extra) {
        const Impl::Level &lv = im.levels[(size_t)(*paths_)[(size_t)path].level];
        auto visit = [&](int i) {
            const Item &it = items_[(size_t)i];
            if (it.kind != ITEM_INSTANCE) {
                out.push_back(Cand{i, path});
                return;
            }
            int cp = child_path(path, it.inst);
            LV o, d;
            L eo, ed;
            approx_local((*paths_)[(size_t)cp], ray, o, d, eo, ed);
            RfRay cr = rf_ray(rf_vec3((double)o.x, (double)o.y, (double)o.z), rf_vec3((double)d.x, (double)d.y, (double)d.z));
            if (!(std::isfinite(cr.origin.x) && std::isfinite(cr.origin.y) && std::isfinite(cr.origin.z)))
                return;
            collect(cp, cr, (double)(4 * eo + 4 * ed * len(o) / std::max(len(d), (L)1e-300)));
        };
        for (int i : lv.unbounded)
            visit(i);
        if (lv.nodes.empty())
            return;
        int stack[256], sp = 0;
        stack[sp++] = 0;
        while (sp > 0) {
            const Node &n = lv.nodes[(size_t)stack[--sp]];
            if (!slab_hit(n.box, r, extra))
                continue;
            if (n.left < 0) {
                for (int i = n.first; i < n.first + n.count; i++)
                    visit(lv.order[(size_t)i]);
            } else {
                stack[sp++] = n.left;
                stack[sp++] = n.right;
            }
        }
    };
    collect(0, ray, 0);
}

namespace {

// The exact ray in one path's scaled space (built on first use within a query): P + t Q =
// sigma (the object-space point at t); the world itself has sigma = 1 (unit).
struct ExRay {
    int path;
    Point O; // P
    Vector D; // Q
    FT a;     // <Q,Q>
    FT s, as; // sigma, |sigma|
    int sg;   // sign of sigma
    bool unit;
    Point sc(const Point &p) const { return unit ? p : Point(s * p.x(), s * p.y(), s * p.z()); }
    FT sc(const FT &v) const { return unit ? v : s * v; }
};

typedef CGAL::Interval_nt<false> I;

// A filter for the common case of a cone candidate the ray misses: the cone quadratic's
// discriminant (see nearest) in interval arithmetic over the exact object-space ray's
// intervals (P / sigma, Q / sigma); certainly negative means no real root, so no hit.
bool cone_misses(const RfCone &c, const ExRay &xr)
{
    CGAL::Protect_FPU_rounding<true> prot;
    auto Oa = CGAL::approx(xr.O);
    auto Da = CGAL::approx(xr.D);
    I s = xr.unit ? I(1) : I(CGAL::to_interval(xr.s));
    I A[3] = {I(c.apex.x) - I(c.base.x), I(c.apex.y) - I(c.base.y), I(c.apex.z) - I(c.base.z)};
    I f[3] = {Oa.x() / s - I(c.base.x), Oa.y() / s - I(c.base.y), Oa.z() / s - I(c.base.z)};
    I d[3] = {Da.x() / s, Da.y() / s, Da.z() / s};
    I AA = A[0] * A[0] + A[1] * A[1] + A[2] * A[2], AA2 = AA * AA;
    I fA = f[0] * A[0] + f[1] * A[1] + f[2] * A[2], dA = d[0] * A[0] + d[1] * A[1] + d[2] * A[2];
    I dd = d[0] * d[0] + d[1] * d[1] + d[2] * d[2], fd = f[0] * d[0] + f[1] * d[1] + f[2] * d[2];
    I ff = f[0] * f[0] + f[1] * f[1] + f[2] * f[2];
    I rb = I(c.base_radius), dr = I(c.apex_radius) - I(c.base_radius), R0 = rb * AA + dr * fA;
    I qa = AA2 * dd - AA * dA * dA - dr * dr * dA * dA;
    I qb = AA2 * fd - AA * fA * dA - R0 * dr * dA;
    I qc = AA2 * ff - AA * fA * fA - R0 * R0;
    I disc = CGAL::square(qb) - qa * qc;
    return disc.sup() < 0; // then a c > bh^2 >= 0: a != 0, no real root
}

// A filter for triangle candidates (CGAL's own filter works on the absolute coordinates, which
// for a small far triangle leaves most cases to the exact fall-back): the triple products
// <d, (p_i - o) x (p_j - o)> over the edges, in interval arithmetic on the differences
// p_i - o. Two of certainly opposite signs: the line misses (-1). All three certainly of one
// sign: the line crosses the interior; then the sign of t = <n, p_0 - o> / <n, d> decides
// (+1: hit, -1: behind the origin). 0: not certain.
int tri_filter(const Item &it, const ExRay &xr)
{
    CGAL::Protect_FPU_rounding<true> prot;
    auto Oa = CGAL::approx(xr.O);
    auto Da = CGAL::approx(xr.D);
    I s = xr.unit ? I(1) : I(CGAL::to_interval(xr.s));
    I o[3] = {Oa.x(), Oa.y(), Oa.z()}, d[3] = {Da.x(), Da.y(), Da.z()}, v[3][3];
    for (int k = 0; k < 3; k++) {
        v[k][0] = s * I(it.p[k].x) - o[0];
        v[k][1] = s * I(it.p[k].y) - o[1];
        v[k][2] = s * I(it.p[k].z) - o[2];
    }
    // (p_i - o) x (p_j - o) = (p_i - o) x (p_j - p_i): the short edge keeps the products small
    // (a ray aimed at a small far triangle makes the long form cancel)
    int pos = 0, neg = 0;
    for (int k = 0; k < 3; k++) {
        const I *a = v[k];
        I b[3];
        for (int j = 0; j < 3; j++)
            b[j] = s * (I(coord(it.p[(k + 1) % 3], j)) - I(coord(it.p[k], j)));
        I w = d[0] * (a[1] * b[2] - a[2] * b[1]) + d[1] * (a[2] * b[0] - a[0] * b[2]) + d[2] * (a[0] * b[1] - a[1] * b[0]);
        pos += w.inf() > 0;
        neg += w.sup() < 0;
    }
    if (pos && neg)
        return -1;
    if (pos < 3 && neg < 3)
        return 0;
    I e1[3], e2[3];
    for (int j = 0; j < 3; j++) {
        e1[j] = s * (I(coord(it.p[1], j)) - I(coord(it.p[0], j)));
        e2[j] = s * (I(coord(it.p[2], j)) - I(coord(it.p[0], j)));
    }
    I n[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
    I num = n[0] * v[0][0] + n[1] * v[0][1] + n[2] * v[0][2], den = n[0] * d[0] + n[1] * d[1] + n[2] * d[2];
    I t = num * den; // the sign of t
    return t.inf() > 0 ? 1 : t.sup() < 0 ? -1 : 0;
}

// The value of a root for reports and tie bands, to a few ulps: from the intervals of x, D and
// den, refined by their exact values when those are loose (CGAL's to_double would accept a
// relative error of 1e-5; a cone's coefficients cancel).
long double root_value(const Root &r)
{
    auto eval = [&]() {
        CGAL::Protect_FPU_rounding<true> prot;
        I t = I(CGAL::to_interval(r.x));
        if (r.s)
            t = t + I(r.s) * CGAL::sqrt(CGAL::max(I(CGAL::to_interval(r.D)), I(0)));
        return t / I(CGAL::to_interval(r.den));
    };
    I t = eval();
    if (!(t.sup() - t.inf() <= 0x1p-50 * std::max(std::fabs(t.inf()), std::fabs(t.sup())))) {
        CGAL::exact(r.x);
        CGAL::exact(r.D);
        CGAL::exact(r.den);
        t = eval();
    }
    return ((long double)t.inf() + (long double)t.sup()) / 2;
}

} // namespace

ExactHit Oracle::nearest(RfRay ray, const std::vector<Cand> &cand, double tracer_t, double tol) const
{
    ExactHit res;
    std::vector<ExRay> rays;
    auto exray = [&](int path) -> const ExRay & {
        for (const ExRay &x : rays)
            if (x.path == path)
                return x;
        ExRay x;
        x.path = path;
        x.unit = path == 0;
        if (x.unit) {
            x.O = pt(ray.origin);
            x.D = vc(ray.dir);
            x.s = x.as = FT(1);
            x.sg = 1;
        } else {
            const XMat &X = impl_->path_inv[(size_t)path];
            FT o[3] = {ray.origin.x, ray.origin.y, ray.origin.z}, d[3] = {ray.dir.x, ray.dir.y, ray.dir.z};
            FT po[3], pd[3];
            for (int i = 0; i < 3; i++) {
                po[i] = X.m[i][0] * o[0] + X.m[i][1] * o[1] + X.m[i][2] * o[2] + X.m[i][3];
                pd[i] = X.m[i][0] * d[0] + X.m[i][1] * d[1] + X.m[i][2] * d[2];
            }
            x.O = Point(po[0], po[1], po[2]);
            x.D = Vector(pd[0], pd[1], pd[2]);
            x.s = X.sigma;
            x.sg = sgn(X.sigma);
            x.as = x.sg > 0 ? X.sigma : -X.sigma;
        }
        x.a = x.D * x.D;
        rays.push_back(x);
        return rays.back();
    };
    Root best{FT(0), 0, FT(0), FT(1), -1};
    for (const Cand &cd : cand) {
        const Item &it = items_[(size_t)cd.item];
        const Impl::ExactItem &e = impl_->ex[(size_t)cd.item];
        const ExRay &xr = exray(cd.path);
        const Point &O = xr.O;
        const Vector &D = xr.D;
        Root r{FT(0), 0, FT(0), xr.a, cd.path}; // den t = x: den = <D,D> of this space
        bool front = false;
        switch (it.kind) {
        case ITEM_INSTANCE: // candidates() enters instances
            continue;
        case ITEM_TRI: {
            int filt = e.degenerate ? -1 : tri_filter(it, xr);
            if (filt < 0)
                continue;
            K::Ray_3 R(O, D);
            // scaled by sigma (a point reflection too when sigma < 0: the same incidences)
            K::Triangle_3 tri = xr.unit ? e.tri : K::Triangle_3(xr.sc(e.tri[0]), xr.sc(e.tri[1]), xr.sc(e.tri[2]));
            FT den = e.n * D; // sigma <n, d_object>
            if (sgn(den) == 0) { // the ray is parallel: in the plane it is the tracer's "no hit"
                if (CGAL::do_intersect(R, tri))
                    res.coplanar = true;
                continue;
            }
            if (filt == 0 && !CGAL::do_intersect(R, tri))
                continue;
            r.x = xr.a * (e.n * (tri[0] - O)) / den;
            front = xr.sg * sgn(den) < 0;
            break;
        }
        case ITEM_SPHERE: {
            Point c = xr.sc(e.c);
            FT r2 = xr.unit ? e.r2 : xr.s * xr.s * e.r2;
            Vector f = O - c;
            FT bh = D * f, cc = f * f - r2, dq = bh * bh - xr.a * cc;
            bool cgal_hit = CGAL::do_intersect(K::Ray_3(O, D), K::Sphere_3(c, r2));
            bool hit = false;
            // an inside-only sphere skips a near root that faces outward: its far wall is what a
            // ray from outside sees (the tracer's rule, tracer.c hit_item)
            bool inside_only = !(it.flags & RF_PRIM_TWO_SIDED) && (it.flags & RF_PRIM_INSIDE);
            if (sgn(dq) >= 0) {
                if (sign_root(-bh, FT(-1), dq) >= 0 && !(inside_only && sgn(dq) > 0)) {
                    r = Root{-bh, -1, dq, xr.a, cd.path};
                    front = sgn(dq) > 0;
                    hit = true;
                } else if (sign_root(-bh, FT(1), dq) >= 0) {
                    r = Root{-bh, 1, dq, xr.a, cd.path};
                    hit = true;
                }
            }
            if (hit != cgal_hit)
                res.inconsistent = true;
            if (!hit)
                continue;
            break;
        }
        case ITEM_PLANE: {
            FT den = e.n * D, num = xr.sc(e.off) - e.n * (O - CGAL::ORIGIN);
            if (sgn(den) == 0) {
                if (sgn(num) == 0)
                    res.coplanar = true;
                continue;
            }
            r.x = xr.a * num / den;
            if (sgn(r.x) < 0)
                continue;
            front = xr.sg * sgn(den) < 0;
            break;
        }
        case ITEM_CONE: {
            // Q(t) = <A,A>^2 (|q_perp|^2 - rho(q)^2) for q = O + t D - base, rho the radius at
            // q's axial position: a t^2 + 2 bh t + c, positive outside; the axial position
            // w = <q,A> / <A,A> must lie in [0, 1]. Every coefficient is exact. (Scaled space:
            // base, A by sigma, the radii by |sigma|.)
            if (e.degenerate || cone_misses(it.cone, xr))
                continue;
            Vector A = xr.unit ? e.A : e.A * xr.s;
            FT AA = xr.unit ? e.AA : xr.s * xr.s * e.AA, rb = xr.unit ? e.rb : xr.as * e.rb,
               dr = xr.unit ? e.dr : xr.as * e.dr;
            Vector f = O - xr.sc(e.base);
            FT fA = f * A, dA = D * A, AA2 = AA * AA, R0 = rb * AA + dr * fA;
            FT qa = AA2 * xr.a - AA * dA * dA - dr * dr * dA * dA;
            FT qb = AA2 * (f * D) - AA * fA * dA - R0 * dr * dA;
            FT qc = AA2 * (f * f) - AA * fA * fA - R0 * R0;
            Root roots[2];
            int deriv[2], n = 0, sa = sgn(qa);
            if (sa == 0) { // linear (a ray along a generator or a cylinder's axis)
                if (sgn(qb) == 0) {
                    if (sgn(qc) == 0)
                        res.coplanar = true; // the ray runs in the surface: no hit by contract
                    continue;
                }
                int sb = sgn(qb); // t = -c / (2 bh)
                roots[0] = Root{sb > 0 ? -qc : qc, 0, FT(0), sb > 0 ? FT(2) * qb : FT(-2) * qb, -1};
                deriv[0] = sb;
                n = 1;
            } else {
                FT disc = qb * qb - qa * qc;
                int sd = sgn(disc);
                if (sd < 0)
                    continue;
                // t = (x -+ sqrt(disc)) / |a| with x = -+ bh: the smaller root first; the
                // derivative Q' = 2 (a t + bh) is -+ sign(a) sqrt(disc) there
                FT x = sa > 0 ? -qb : qb, den = sa > 0 ? qa : -qa;
                if (sd == 0) {
                    roots[0] = Root{x, 0, FT(0), den, -1};
                    deriv[0] = 0;
                    n = 1;
                } else {
                    roots[0] = Root{x, -1, disc, den, -1};
                    deriv[0] = -sa;
                    roots[1] = Root{x, 1, disc, den, -1};
                    deriv[1] = sa;
                    n = 2;
                }
            }
            bool got = false;
            for (int k = 0; k < n && !got; k++) {
                const Root &q = roots[k];
                if (sign_root(q.x, FT(q.s), q.D) < 0)
                    continue;
                // <q,A> = fA + t dA in [0, <A,A>] (times den > 0)
                if (sign_root(fA * q.den + dA * q.x, dA * q.s, q.D) < 0 ||
                    sign_root((AA - fA) * q.den - dA * q.x, -dA * q.s, q.D) < 0)
                    continue;
                bool fr = deriv[k] < 0; // entering: the outward normal faces the ray
                if (!(it.flags & RF_PRIM_TWO_SIDED) && fr == !!(it.flags & RF_PRIM_INSIDE))
                    continue; // the hidden side: the tracer looks further along the ray
                r = q;
                front = fr;
                got = true;
            }
            if (!got)
                continue;
            break;
        }
        }
        if (it.kind != ITEM_CONE && !(it.flags & RF_PRIM_TWO_SIDED) && front == !!(it.flags & RF_PRIM_INSIDE))
            continue; // one-sided, seen from its invisible side (the tracer's rule)
        int c = res.hit ? cmp_roots(r, best) : -1;
        if (c < 0) {
            res.hit = true;
            res.items.assign(1, cd);
            best = r;
        } else if (c == 0) {
            res.items.push_back(cd);
        }
    }
    if (!res.hit)
        return res;
    res.t = root_value(best);
    if (tol >= 0 && std::isfinite(tracer_t)) {
        if (!std::isfinite(tol))
            res.t_ok = true;
        else {
            Root lo{best.den * (FT(tracer_t) - FT(tol)), 0, FT(0), best.den, best.den_id};
            Root hi{best.den * (FT(tracer_t) + FT(tol)), 0, FT(0), best.den, best.den_id};
            res.t_ok = cmp_roots(lo, best) <= 0 && cmp_roots(best, hi) <= 0;
        }
    }
    return res;
}

int Oracle::side(int item, RfVec3 q) const
{
    const Item &it = items_[(size_t)item];
    const Impl::ExactItem &e = impl_->ex[(size_t)item];
    Point Q = pt(q);
    switch (it.kind) {
    case ITEM_TRI:
        return sgn(e.n * (Q - e.tri[0]));
    case ITEM_SPHERE:
        return sgn(CGAL::squared_distance(Q, e.c) - e.r2);
    case ITEM_PLANE:
        return sgn(e.n * (Q - CGAL::ORIGIN) - e.off);
    case ITEM_CONE: {
        Vector f = Q - e.base;
        FT fA = f * e.A, R0 = e.rb * e.AA + e.dr * fA;
        return sgn(e.AA * e.AA * (f * f) - e.AA * fA * fA - R0 * R0);
    }
    default:
        return 0;
    }
}

int Oracle::facing(int item, RfVec3 d) const
{
    const Item &it = items_[(size_t)item];
    if (it.kind != ITEM_TRI || it.level != 0)
        return 0;
    return sgn(impl_->ex[(size_t)item].n * Vector(FT(d.x), FT(d.y), FT(d.z)));
}

bool Oracle::segment_hits(int item, RfVec3 a, RfVec3 b) const
{
    const Impl::ExactItem &e = impl_->ex[(size_t)item];
    if (items_[(size_t)item].kind != ITEM_TRI || e.degenerate)
        return false;
    return CGAL::do_intersect(K::Segment_3(pt(a), pt(b)), e.tri);
}

} // namespace rv
