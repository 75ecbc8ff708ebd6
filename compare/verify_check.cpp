// refray-verify: one ray, the tracer's answer against the exact one (docs/verify.md): the
// tracer under test, the margins of a disagreement to the decisions' boundaries (long double,
// for the classification only), and the verdict counted in a row.
#include "verify_run.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <exception>
#include <new>
#include <stdexcept>
#include <utility>
#include <vector>

namespace rv {

namespace {

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
struct ConeGeom {
    L H, m, oz, dz, a, bh, c, disc, dl, ol, Am, Bm, Cm, Sabs;
    L rb, S, opl, r0; // geometric bound: the size, |o_perp|, the radius at the origin's position
    L da, dbh, dc; // the coefficients' change under the object-space ray's deviation (instances)
    bool geometric; // --cone-bound geometric (Opts::cone_geometric)
};

ConeGeom cone_geom(const Item &it, const LocalRay &lr, bool geometric)
{
    ConeGeom g;
    g.geometric = geometric;
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
    if (g.geometric) { // as for spheres: kDelta max(S, t |d|) / (cos |d|)
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
    if (g.geometric) {
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
Margin margin(const Item &it, const LocalRay &lr, bool cone_geometric)
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
        return cone_margin(cone_geom(it, lr, cone_geometric), lr);
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
L t_band(const Item &it, const LocalRay &lr, L t, bool cone_geometric)
{
    if (it.kind == ITEM_CONE)
        return cone_band(cone_geom(it, lr, cone_geometric), t);
    Margin m = margin(it, lr, cone_geometric);
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
        tol = std::max(tol, t_band(items[(size_t)cd.item], lrs.get(cd.path), c.t.t, o.cone_geometric));
    if (std::isnan(tol))
        tol = HUGE_VALL;
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
        amb |= margin(items[(size_t)cd.item], lrs.get(cd.path), o.cone_geometric).near();
    for (const Cand &cd : tc)
        amb |= margin(items[(size_t)cd.item], lrs.get(cd.path), o.cone_geometric).near();
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
            band = std::max(band, t_band(items[(size_t)cd.item], lrs.get(cd.path), e.t, o.cone_geometric));
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

} // namespace

// One ray checked and counted; a ray the oracle cannot evaluate exactly (an exception: CGAL's
// conversions, the allocator) or that is not finite is counted as skipped (not representable).
void check_and_tally(Stats &st, const World &w, const Opts &o, RfRay r, int interior)
{
    if (!finite_ray(r)) {
        not_representable(st, r, "the ray is not finite");
        return;
    }
    try {
        if (o.fault_every > 0 && ++st.evaluations % o.fault_every == 0) // the testing hook (Opts::fault_every)
            throw std::range_error("injected fault (REFRAY_VERIFY_FAULT)");
        Check c = check_ray(w, o, r, interior);
        tally(st, w, r, c);
    } catch (const std::bad_alloc &) {
        not_representable(st, r, "out of memory in the exact evaluation");
    } catch (const std::exception &ex) {
        not_representable(st, r, ex.what());
    }
}

} // namespace rv
