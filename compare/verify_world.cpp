// refray-verify: the worlds built in code (docs/verify.md, "Classes"): primitives, closed meshes
// with a region certainly inside them, objects and their instances, and the finished world's
// oracle and tracer. World (verify_run.hpp) declares what each builder makes.
#include "verify_run.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <map>
#include <utility>
#include <vector>

namespace rv {

World::World()
{
    rf_scene_init(&sc);
    RfMaterial m = rf_material_default();
    m.kd = rf_rgb(0.8, 0.8, 0.8);
    rf_scene_add_material(&sc, &m, &mat);
    bounds = rf_aabb_empty();
}

World::~World()
{
    rf_tracer_free(tr);
    rf_scene_free(&sc);
}

void World::grow(RfVec3 p)
{
    if (!in_obj)
        bounds = rf_aabb_add_point(bounds, p);
}

void World::add(RfPrimitive p, int mesh)
{
    char msg[256];
    p.material = mat;
    p.flags |= in_obj;
    if (rf_scene_add_primitive(&sc, &p, msg, sizeof msg) == RF_OK)
        prim_mesh.push_back(mesh);
}

void World::sphere(RfVec3 c, double r, unsigned flags)
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

void World::poly(const RfVec3 *v, int n, unsigned flags, int mesh)
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

void World::plane(RfVec3 n, double offset)
{
    RfPrimitive p{};
    p.type = RF_PRIM_PLANE;
    p.flags = RF_PRIM_TWO_SIDED;
    p.u.plane.normal = n;
    p.u.plane.offset = offset;
    add(p, -1);
}

void World::cone(RfVec3 base, double rb, RfVec3 apex, double ra, unsigned flags)
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

int World::begin_object(const char *name)
{
    int o = -1;
    rf_scene_add_object(&sc, name, RfSrcLoc{0, 0}, &o);
    in_obj = RF_PRIM_IN_OBJECT;
    cur_object = o;
    return o;
}

void World::end_object(int o)
{
    sc.objects[o].count = sc.prim_count - sc.objects[o].first;
    in_obj = 0;
    cur_object = -1;
}

void World::instance(int object, RfMat4 m)
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

void World::icosphere(RfVec3 c, double r, int level, double jitter, Rng &rng)
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

void World::grid_cube(RfVec3 corner, int n, double h)
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

void World::quad(RfVec3 p0, double s, Rng &rng, unsigned flags)
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

void World::star(RfVec3 c, double s, bool exact, unsigned flags, Rng &rng)
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

void World::mixed(RfVec3 at, double s, Rng &rng)
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

void World::finish()
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

int World::interior_mesh(RfVec3 o) const
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

} // namespace rv
