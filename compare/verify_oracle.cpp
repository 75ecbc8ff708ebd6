// refray-verify: the exact oracle. CGAL's Exact_predicates_exact_constructions_kernel (Epeck:
// interval-filtered, exact rational fall-back) decides every hit; distances are compared
// exactly, sphere roots included (see cmp_roots). The candidate search is a plain BVH over
// padded boxes, written here so that the oracle shares no code with the tracer's BVH.
#include "verify.hpp"

// GCC 12 reports boost::tuple members inside CGAL's Sphere_3 as maybe-uninitialized after
// inlining (a known false positive of CGAL + GCC >= 11); the code is CGAL's, not ours.
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"

#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/intersections.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace rv {

typedef CGAL::Exact_predicates_exact_constructions_kernel K;
typedef K::FT FT;
typedef K::Point_3 Point;
typedef K::Vector_3 Vector;

namespace {

// a t = x + s sqrt(D) with a = <d,d> > 0 the same for every root of one ray, s in {-1, 0, 1}:
// triangles and planes have s = 0 (t rational), sphere roots s = -1 (near) or +1 (far).
struct Root {
    FT x;
    int s;
    FT D;
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

// The exact sign of A - B for two roots of the same ray: P = (xA - xB) + sA sqrt(DA) against
// Q = sB sqrt(DB); when P and Q share a sign, compare P^2 with Q^2, which is again of the form
// x + y sqrt(DA).
int cmp_roots(const Root &A, const Root &B)
{
    FT u = A.x - B.x;
    int sP = sign_root(u, FT(A.s), A.D);
    int sQ = (B.s == 0 || sgn(B.D) == 0) ? 0 : B.s;
    if (sP != sQ)
        return sP > sQ ? 1 : -1;
    if (sP == 0)
        return 0;
    FT x = u * u + (A.s != 0 ? A.D : FT(0)) - B.D;
    return sP * sign_root(x, FT(2 * A.s) * u, A.D);
}

Point pt(RfVec3 v) { return Point(v.x, v.y, v.z); }
Vector vc(RfVec3 v) { return Vector(v.x, v.y, v.z); }

struct Node {
    RfAabb box;
    int left, right; // children, or -1 for a leaf
    int first, count;
};

} // namespace

struct Oracle::Impl {
    struct ExactItem {
        K::Triangle_3 tri;
        Vector n;
        bool degenerate = false;
        Point c;
        FT r2;
        FT off;
    };
    std::vector<ExactItem> ex;
    std::vector<int> planes; // unbounded items (planes, instances): always candidates
    std::vector<int> order;  // bounded items in BVH order
    std::vector<Node> nodes;

    int build(const std::vector<Item> &items, int first, int count)
    {
        Node nd;
        nd.box = rf_aabb_empty();
        for (int i = first; i < first + count; i++)
            nd.box = rf_aabb_union(nd.box, items[(size_t)order[(size_t)i]].box);
        nd.left = nd.right = -1;
        nd.first = first;
        nd.count = count;
        int idx = (int)nodes.size();
        nodes.push_back(nd);
        if (count <= 4)
            return idx;
        RfVec3 ext = rf_vec3_sub(nd.box.hi, nd.box.lo);
        int axis = ext.x >= ext.y ? (ext.x >= ext.z ? 0 : 2) : (ext.y >= ext.z ? 1 : 2);
        auto key = [&](int i) {
            RfVec3 c = rf_aabb_center(items[(size_t)i].box);
            return axis == 0 ? c.x : axis == 1 ? c.y : c.z;
        };
        int mid = first + count / 2;
        std::nth_element(order.begin() + first, order.begin() + mid, order.begin() + first + count,
                         [&](int a, int b) { return key(a) < key(b); });
        int l = build(items, first, mid - first);
        int r = build(items, mid, first + count - mid);
        nodes[(size_t)idx].left = l;
        nodes[(size_t)idx].right = r;
        return idx;
    }
};

Oracle::Oracle(const RfScene *s) : prim_items_(s->prim_count), impl_(new Impl)
{
    for (size_t i = 0; i < s->prim_count; i++) {
        const RfPrimitive *p = &s->prims[i];
        if (p->flags & RF_PRIM_IN_OBJECT) // reached only through its instances
            continue;
        Item it{};
        it.prim = (int)i;
        it.flags = p->flags;
        it.box = rf_aabb_empty();
        auto vert = [&](int k) { return s->vertices[p->u.poly.first + (size_t)k]; };
        auto push = [&](const Item &x) {
            prim_items_[i].push_back((int)items_.size());
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
        case RF_PRIM_POLYGON:
            if (p->type == RF_PRIM_POLYGON && (p->flags & RF_PRIM_NONCONVEX)) {
                it.kind = ITEM_UNSUPPORTED;
                for (int k = 0; k < p->u.poly.count; k++)
                    it.box = rf_aabb_add_point(it.box, vert(k));
                push(it);
                break;
            }
            for (int k = 0; k + 2 < p->u.poly.count; k++) {
                it.kind = ITEM_TRI;
                it.p[0] = vert(0);
                it.p[1] = vert(k + 1);
                it.p[2] = vert(k + 2);
                it.box = rf_aabb_empty();
                for (int j = 0; j < 3; j++)
                    it.box = rf_aabb_add_point(it.box, it.p[j]);
                push(it);
            }
            break;
        case RF_PRIM_CONE: {
            it.kind = ITEM_UNSUPPORTED;
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
        default: // instances (and any later kind): not modelled, a candidate of every ray
            it.kind = ITEM_UNSUPPORTED;
            push(it);
            break;
        }
    }
    impl_->ex.resize(items_.size());
    for (size_t i = 0; i < items_.size(); i++) {
        const Item &it = items_[i];
        Impl::ExactItem &e = impl_->ex[i];
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
        }
        if (it.kind == ITEM_PLANE || it.box.lo.x > it.box.hi.x) // unbounded: always a candidate
            impl_->planes.push_back((int)i);
        else
            impl_->order.push_back((int)i);
    }
    if (!impl_->order.empty())
        impl_->build(items_, 0, (int)impl_->order.size());
}

Oracle::~Oracle() = default;

// The slab test on a box padded by 1e-9 of the magnitudes involved: the rounding of the
// double computation is ~1e-16 of them, so no box the exact ray meets is ever culled.
static bool slab_hit(const RfAabb &b, RfRay r)
{
    const double o[3] = {r.origin.x, r.origin.y, r.origin.z}, d[3] = {r.dir.x, r.dir.y, r.dir.z};
    const double lo[3] = {b.lo.x, b.lo.y, b.lo.z}, hi[3] = {b.hi.x, b.hi.y, b.hi.z};
    double mag = 0;
    for (int k = 0; k < 3; k++)
        mag = std::max({mag, std::fabs(o[k]), std::fabs(lo[k]), std::fabs(hi[k])});
    double pad = 1e-9 * mag + 1e-300;
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

void Oracle::candidates(RfRay ray, std::vector<int> &out) const
{
    out.assign(impl_->planes.begin(), impl_->planes.end());
    if (impl_->nodes.empty())
        return;
    int stack[256], sp = 0;
    stack[sp++] = 0;
    while (sp > 0) {
        const Node &n = impl_->nodes[(size_t)stack[--sp]];
        if (!slab_hit(n.box, ray))
            continue;
        if (n.left < 0) {
            for (int i = n.first; i < n.first + n.count; i++)
                out.push_back(impl_->order[(size_t)i]);
        } else {
            stack[sp++] = n.left;
            stack[sp++] = n.right;
        }
    }
}

ExactHit Oracle::nearest(RfRay ray, double tracer_t, double tol) const
{
    ExactHit res;
    std::vector<int> cand;
    candidates(ray, cand);
    Point O = pt(ray.origin);
    Vector D = vc(ray.dir);
    K::Ray_3 R(O, D);
    FT a = D * D;
    Root best{FT(0), 0, FT(0)};
    for (int i : cand) {
        const Item &it = items_[(size_t)i];
        const Impl::ExactItem &e = impl_->ex[(size_t)i];
        Root r{FT(0), 0, FT(0)};
        bool front = false;
        switch (it.kind) {
        case ITEM_UNSUPPORTED:
            res.skipped = true;
            continue;
        case ITEM_TRI: {
            if (e.degenerate)
                continue;
            FT den = e.n * D;
            if (sgn(den) == 0) { // the ray is parallel: in the plane it is the tracer's "no hit"
                if (CGAL::do_intersect(R, e.tri))
                    res.coplanar = true;
                continue;
            }
            if (!CGAL::do_intersect(R, e.tri))
                continue;
            r.x = a * (e.n * (e.tri[0] - O)) / den;
            front = sgn(den) < 0;
            break;
        }
        case ITEM_SPHERE: {
            Vector f = O - e.c;
            FT bh = D * f, cc = f * f - e.r2, dq = bh * bh - a * cc;
            bool cgal_hit = CGAL::do_intersect(R, K::Sphere_3(e.c, e.r2));
            bool hit = false;
            // an inside-only sphere skips a near root that faces outward: its far wall is what a
            // ray from outside sees (the tracer's rule, tracer.c hit_item)
            bool inside_only = !(it.flags & RF_PRIM_TWO_SIDED) && (it.flags & RF_PRIM_INSIDE);
            if (sgn(dq) >= 0) {
                if (sign_root(-bh, FT(-1), dq) >= 0 && !(inside_only && sgn(dq) > 0)) {
                    r = Root{-bh, -1, dq};
                    front = sgn(dq) > 0;
                    hit = true;
                } else if (sign_root(-bh, FT(1), dq) >= 0) {
                    r = Root{-bh, 1, dq};
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
            FT den = e.n * D, num = e.off - e.n * (O - CGAL::ORIGIN);
            if (sgn(den) == 0) {
                if (sgn(num) == 0)
                    res.coplanar = true;
                continue;
            }
            r.x = a * num / den;
            if (sgn(r.x) < 0)
                continue;
            front = sgn(den) < 0;
            break;
        }
        }
        if (!(it.flags & RF_PRIM_TWO_SIDED) && front == !!(it.flags & RF_PRIM_INSIDE))
            continue; // one-sided, seen from its invisible side (the tracer's rule)
        int c = res.hit ? cmp_roots(r, best) : -1;
        if (c < 0) {
            res.hit = true;
            res.items.assign(1, i);
            best = r;
        } else if (c == 0) {
            res.items.push_back(i);
        }
    }
    if (!res.hit)
        return res;
    long double x = CGAL::to_double(best.x), dd = CGAL::to_double(best.D), aa = CGAL::to_double(a);
    res.t = (x + best.s * std::sqrt(std::max(dd, 0.0L))) / aa;
    if (tol >= 0 && std::isfinite(tracer_t)) {
        Root lo{a * (FT(tracer_t) - FT(tol)), 0, FT(0)}, hi{a * (FT(tracer_t) + FT(tol)), 0, FT(0)};
        res.t_ok = cmp_roots(lo, best) <= 0 && cmp_roots(best, hi) <= 0;
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
    default:
        return 0;
    }
}

bool Oracle::segment_hits(int item, RfVec3 a, RfVec3 b) const
{
    const Impl::ExactItem &e = impl_->ex[(size_t)item];
    if (items_[(size_t)item].kind != ITEM_TRI || e.degenerate)
        return false;
    return CGAL::do_intersect(K::Segment_3(pt(a), pt(b)), e.tri);
}

} // namespace rv
