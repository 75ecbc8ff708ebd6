/* The tracer (render.h): scene preparation, nearest-hit and occlusion queries, the
 * self-intersection policy. The shading lives in the kernels (kernel_body.h). */
#include "refray/render.h"
#include "refray/geometry.h"

#include <float.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "refray/bvh.h"
#include "refray/camera.h"
#include "refray/intersect.h"
#include "refray/numeric.h"
#include "refray/optics.h"
#include "refray/rng.h"
#include "refray/shading.h"
#include "refray/transform.h"

/* One item of a level: a primitive, or one triangle (sub >= 0) of a polygon (a convex one's fan
 * triangle v0, v(sub+1), v(sub+2); a non-convex one's ear-clipped triangle sub); a triangle has
 * sub = 0. Its key orders (prim, sub): of two
 * hits at the same t the lower key wins, so the image does not depend on the BVH (DESIGN.md). */
typedef struct {
    int prim, sub;
} Item;

static uint64_t item_key(Item it) { return ((uint64_t)(uint32_t)it.prim << 32) | (uint32_t)(it.sub + 2); }
static Item key_item(uint64_t key)
{
    Item it = {(int)(key >> 32), (int)(uint32_t)key - 2};
    return it;
}

/* The items of the world, or of one object in its own space (§4.8). */
typedef struct {
    RfBvh bvh;
    Item *items;         /* every item of the level, in key order (kept only by brute force) */
    int item_count;
    int *bvh_items;      /* the BVH's items: items[bvh_items[j]] */
    int bvh_count;
    RfAabb box;          /* an object's: of its bounded items, for its instances' boxes (the
                            world's is not needed, nor made) */
    uint64_t *unbounded; /* keys of the items tested for every ray: planes, instances of
                            unbounded objects */
    int unbounded_count;
    int state;           /* objects: 0 not built, 1 building, 2 built */
} Level;

struct RfTracer {
    const RfScene *scene;
    RfTracerOptions opt;
    Level world;
    Level *objects;    /* per RfScene.objects: one BVH each, shared by all its instances */
    /* Non-convex polygons are cut into triangles by ear clipping (rf_triangulate_polygon), so
     * that they are watertight against their neighbours and inside themselves like every other
     * triangle (the crossing-number test they had leaked rays at edges: docs/verify.md,
     * star-prisms). Polygon prim's triangle k has the corners cut[cut_first[prim] + 3 k + j]. */
    int *cut;
    size_t *cut_first;
    RfConeFrame *cone_frames; /* the cones' frames, once: primitive i's at i - cone_first (the */
    size_t cone_first;        /* primitives from the first cone to the last; NULL: no cones) */
};

/* ---- preparation ---- */

static RfVec3 vertex(const RfScene *s, const RfPrimitive *p, int k)
{
    return s->vertices[p->u.poly.first + (size_t)k];
}

/* Items the BVH intersects itself: triangles and the fan triangles of convex polygons. */
static int item_is_triangle(const RfScene *s, Item it)
{
    RfPrimType ty = s->prims[it.prim].type;
    return it.sub >= 0 && (ty == RF_PRIM_TRIANGLE || ty == RF_PRIM_POLYGON);
}

/* The corners of a triangle item within its primitive: a triangle's 0, 1, 2; a convex polygon's
 * fan triangle 0, sub + 1, sub + 2; a non-convex polygon's ear-clipped triangle. */
static void item_corners(const RfTracer *t, Item it, int c[3])
{
    const RfPrimitive *p = &t->scene->prims[it.prim];
    if (p->type == RF_PRIM_POLYGON && (p->flags & RF_PRIM_NONCONVEX)) {
        const int *k = t->cut + t->cut_first[it.prim] + 3 * (size_t)it.sub;
        c[0] = k[0], c[1] = k[1], c[2] = k[2];
    } else {
        c[0] = 0, c[1] = it.sub + 1, c[2] = it.sub + 2;
    }
}

static RfTriangle item_triangle(const RfTracer *t, Item it)
{
    const RfScene *s = t->scene;
    const RfPrimitive *p = &s->prims[it.prim];
    int c[3];
    item_corners(t, it, c);
    RfTriangle tri = {vertex(s, p, c[0]), vertex(s, p, c[1]), vertex(s, p, c[2])};
    return tri;
}

/* sqrt(1 - a^2), padded by a few ulps against the rounding of a and of the root, so the box
 * stays conservative */
static double disc_reach(double a) { return fmin(1.0, sqrt(fmax(0.0, 1.0 - a * a)) + 4.0 * DBL_EPSILON); }

static RfAabb item_box(const RfScene *s, Item it)
{
    const RfPrimitive *p = &s->prims[it.prim];
    RfAabb b = rf_aabb_empty();
    switch (p->type) {
    case RF_PRIM_SPHERE: {
        RfVec3 r = rf_vec3(p->u.sphere.radius, p->u.sphere.radius, p->u.sphere.radius);
        b.lo = rf_vec3_sub(p->u.sphere.center, r);
        b.hi = rf_vec3_add(p->u.sphere.center, r);
        break;
    }
    case RF_PRIM_TRIANGLE:
    case RF_PRIM_POLYGON:
        for (int k = 0; k < p->u.poly.count; k++)
            b = rf_aabb_add_point(b, vertex(s, p, k));
        break;
    case RF_PRIM_CONE: {
        /* the box of the two end discs: a disc of radius r around c with unit axis a reaches
         * r sqrt(1 - a_i^2) along coordinate i */
        const RfCone *c = &p->u.cone;
        RfVec3 a = rf_vec3_normalize(rf_vec3_sub(c->apex, c->base));
        RfVec3 e = rf_vec3(disc_reach(a.x), disc_reach(a.y), disc_reach(a.z));
        RfVec3 eb = rf_vec3_scale(e, c->base_radius), ea = rf_vec3_scale(e, c->apex_radius);
        b = rf_aabb_add_point(b, rf_vec3_sub(c->base, eb));
        b = rf_aabb_add_point(b, rf_vec3_add(c->base, eb));
        b = rf_aabb_add_point(b, rf_vec3_sub(c->apex, ea));
        b = rf_aabb_add_point(b, rf_vec3_add(c->apex, ea));
        break;
    }
    default:
        break;
    }
    return b;
}

static void level_free(Level *lv)
{
    rf_bvh_free(&lv->bvh);
    free(lv->items);
    free(lv->bvh_items);
    free(lv->unbounded);
}

void rf_tracer_free(RfTracer *t)
{
    if (!t)
        return;
    level_free(&t->world);
    for (size_t o = 0; t->objects && o < t->scene->object_count; o++)
        level_free(&t->objects[o]);
    free(t->objects);
    free(t->cut);
    free(t->cut_first);
    free(t->cone_frames);
    free(t);
}

static RfStatus build_object(RfTracer *t, int o);
static RfAabb transformed_box(RfAabb ob, RfMat4 m, int *ok);

/* An instance's box: the 8 corners of its object's box taken to world space, padded by a few
 * ulps so that the rounding of the corners never culls a ray (§4.8). Returns 0 for an object
 * with unbounded parts (the instance is then tested for every ray) and -1 for an empty one. */
static int instance_box(const RfTracer *t, const RfPrimitive *p, RfAabb *b)
{
    const RfInstance *in = &t->scene->instances[p->u.instance];
    const Level *lv = &t->objects[in->object];
    if (lv->unbounded_count > 0)
        return 0;
    if (lv->bvh_count == 0)
        return -1;
    int ok;
    *b = transformed_box(lv->box, in->to_world, &ok);
    return ok;
}

typedef struct {
    const RfTracer *tracer;
    const Level *level;
} Describe;

/* The BVH's 30 user bits of a triangle: its material, and whether it interpolates vertex
 * normals (§3.6.3), so that a hit needs no look-up in the scene's primitives. */
#define USER_SMOOTH (1u << 29)
#define USER_MATERIAL (USER_SMOOTH - 1)

static int prim_smooth(const RfScene *s, const RfPrimitive *p)
{
    return (p->flags & RF_PRIM_VERTEX_NORMALS) && (s->materials[p->material].flags & RF_MAT_SMOOTH);
}

static int prim_sides(const RfTracer *t, const RfPrimitive *p)
{
    return (p->flags & RF_PRIM_TWO_SIDED) || t->opt.two_sided ? RF_BVH_SEE_BOTH
           : (p->flags & RF_PRIM_INSIDE)  ? RF_BVH_SEE_BACK
                                          : RF_BVH_SEE_FRONT;
}

/* What the BVH takes itself (triangles, spheres) and what it asks the tracer about (boxes). */
static void describe_item(void *ctx, int j, RfBvhItem *out)
{
    const Describe *d = ctx;
    const RfScene *s = d->tracer->scene;
    Item it = d->level->items[d->level->bvh_items[j]];
    const RfPrimitive *p = &s->prims[it.prim];
    out->key = item_key(it);
    out->sides = prim_sides(d->tracer, p);
    out->user = (uint32_t)p->material;
    if (item_is_triangle(s, it)) {
        out->kind = RF_BVH_TRIANGLE;
        out->tri = item_triangle(d->tracer, it);
        out->user |= prim_smooth(s, p) ? USER_SMOOTH : 0u;
    } else if (p->type == RF_PRIM_SPHERE) {
        out->kind = RF_BVH_SPHERE;
        out->sphere = p->u.sphere;
    } else if (p->type == RF_PRIM_CONE) { /* the frame the tracer's own test uses (cone_frames) */
        out->kind = RF_BVH_CONE;
        out->cone = p->u.cone;
        out->frame = d->tracer->cone_frames[(size_t)it.prim - d->tracer->cone_first];
        out->box = item_box(s, it);
    } else {
        out->kind = RF_BVH_OTHER;
        if (p->type == RF_PRIM_INSTANCE)
            instance_box(d->tracer, p, &out->box);
        else
            out->box = item_box(s, it);
    }
}

/* Items and BVH of prims[first, end): the world (objects' parts skipped) or one object. The
 * objects placed by instances here are built first. */
static RfStatus build_level(RfTracer *t, size_t first, size_t end, int world, Level *lv)
{
    const RfScene *scene = t->scene;
    size_t n_items = 0;
    RfStatus st;
    for (size_t i = first; i < end; i++) {
        const RfPrimitive *p = &scene->prims[i];
        if (world && (p->flags & RF_PRIM_IN_OBJECT))
            continue;
        if (p->type == RF_PRIM_INSTANCE &&
            (st = build_object(t, scene->instances[p->u.instance].object)) != RF_OK)
            return st;
        n_items += p->type == RF_PRIM_POLYGON ? (size_t)p->u.poly.count - 2 : 1;
    }
    if (n_items > (size_t)INT32_MAX / 2 || scene->material_count > USER_MATERIAL)
        return RF_ERR_NOMEM;
    size_t cap = n_items ? n_items : 1;
    lv->items = malloc(sizeof *lv->items * cap);
    lv->bvh_items = malloc(sizeof *lv->bvh_items * cap);
    lv->unbounded = malloc(sizeof *lv->unbounded * cap);
    if (!lv->items || !lv->bvh_items || !lv->unbounded)
        return RF_ERR_NOMEM;
    int bvh_count = 0;
    lv->box = rf_aabb_empty();
    for (size_t i = first; i < end; i++) {
        const RfPrimitive *p = &scene->prims[i];
        Item it = {(int)i, -1};
        if (world && (p->flags & RF_PRIM_IN_OBJECT))
            continue;
        int key = lv->item_count;
        if (p->type == RF_PRIM_INSTANCE) {
            RfAabb b;
            /* a moving instance is tested for every ray: its box depends on the time */
            int bounded = scene->instances[p->u.instance].motion >= 0 ? 0 : instance_box(t, p, &b);
            if (bounded < 0) /* an empty object: nothing to hit */
                continue;
            lv->items[lv->item_count++] = it;
            if (bounded > 0) {
                lv->bvh_items[bvh_count++] = key;
                if (!world)
                    lv->box = rf_aabb_union(lv->box, b);
            } else
                lv->unbounded[lv->unbounded_count++] = item_key(it);
        } else if (p->type == RF_PRIM_PLANE) {
            lv->items[lv->item_count++] = it;
            lv->unbounded[lv->unbounded_count++] = item_key(it);
        } else {
            if (!world) /* the whole primitive's box, whatever its items */
                lv->box = rf_aabb_union(lv->box, item_box(scene, it));
            if (p->type == RF_PRIM_POLYGON) { /* fan or ear-clipped triangles */
                for (int k = 0; k + 2 < p->u.poly.count; k++) {
                    it.sub = k;
                    lv->bvh_items[bvh_count++] = lv->item_count;
                    lv->items[lv->item_count++] = it;
                }
            } else {
                if (p->type == RF_PRIM_TRIANGLE)
                    it.sub = 0;
                lv->bvh_items[bvh_count++] = key;
                lv->items[lv->item_count++] = it;
            }
        }
    }
    lv->bvh_count = bvh_count;
    if (t->opt.brute_force)
        return RF_OK;
    Describe d = {t, lv};
    RfBvhDesc desc = {bvh_count, describe_item, &d, t->opt.threads, t->opt.scalar};
    st = rf_bvh_build(&lv->bvh, &desc);
    /* the BVH holds the keys: the item tables were for building it */
    free(lv->items);
    free(lv->bvh_items);
    lv->items = NULL;
    lv->bvh_items = NULL;
    return st;
}

/* One object's level, built once however many instances place it (§4.8). */
static RfStatus build_object(RfTracer *t, int o)
{
    if (o < 0 || (size_t)o >= t->scene->object_count)
        return RF_ERR_DOMAIN;
    Level *lv = &t->objects[o];
    if (lv->state == 2)
        return RF_OK;
    if (lv->state == 1) /* a cycle: rf_scene_validate reports it with its position */
        return RF_ERR_DOMAIN;
    lv->state = 1;
    const RfSceneObject *ob = &t->scene->objects[o];
    RfStatus st = build_level(t, ob->first, ob->first + ob->count, 0, lv);
    lv->state = 2;
    return st;
}

/* What the set-up needs of the scene's primitives, found in one pass over them (a mesh's 1.2 M
 * primitives are 106 MB to read): the first and last cone, and the corners of the triangles the
 * non-convex polygons are cut into. */
typedef struct {
    size_t cone_first, cone_end; /* equal: no cone */
    size_t cut_total;
} PrimScan;

static PrimScan scan_prims(const RfScene *s)
{
    PrimScan ps = {0, 0, 0};
    int cones = 0;
    for (size_t i = 0; i < s->prim_count; i++) {
        const RfPrimitive *p = &s->prims[i];
        if (p->type == RF_PRIM_CONE) {
            if (!cones)
                ps.cone_first = i;
            cones = 1;
            ps.cone_end = i + 1;
        } else if (p->type == RF_PRIM_POLYGON && (p->flags & RF_PRIM_NONCONVEX)) {
            ps.cut_total += 3 * (size_t)(p->u.poly.count - 2);
        }
    }
    return ps;
}

/* The frames of the scene's cones (struct RfTracer), when it has any: an array over the
 * primitives from the first cone to the last, so that a mesh with one cone does not pay for
 * every triangle. */
static RfStatus cone_frames(RfTracer *t, const PrimScan *ps)
{
    const RfScene *s = t->scene;
    if (ps->cone_first == ps->cone_end)
        return RF_OK;
    t->cone_first = ps->cone_first;
    t->cone_frames = malloc(sizeof *t->cone_frames * (ps->cone_end - ps->cone_first));
    if (!t->cone_frames)
        return RF_ERR_NOMEM;
    for (size_t i = ps->cone_first; i < ps->cone_end; i++)
        if (s->prims[i].type == RF_PRIM_CONE)
            t->cone_frames[i - ps->cone_first] = rf_cone_frame(s->prims[i].u.cone);
    return RF_OK;
}

/* The triangles of every non-convex polygon (struct RfTracer). */
static RfStatus cut_nonconvex(RfTracer *t, const PrimScan *ps)
{
    const RfScene *s = t->scene;
    if (ps->cut_total == 0)
        return RF_OK;
    t->cut = malloc(sizeof *t->cut * ps->cut_total);
    t->cut_first = calloc(s->prim_count, sizeof *t->cut_first);
    if (!t->cut || !t->cut_first)
        return RF_ERR_NOMEM;
    size_t at = 0;
    for (size_t i = 0; i < s->prim_count; i++) {
        const RfPrimitive *p = &s->prims[i];
        if (p->type != RF_PRIM_POLYGON || !(p->flags & RF_PRIM_NONCONVEX))
            continue;
        t->cut_first[i] = at;
        if (rf_triangulate_polygon(s->vertices + p->u.poly.first, p->u.poly.count, t->cut + at) < 0)
            return RF_ERR_NOMEM;
        at += 3 * (size_t)(p->u.poly.count - 2);
    }
    return RF_OK;
}

RfTracerOptions rf_tracer_options_default(void)
{
    RfTracerOptions o;
    memset(&o, 0, sizeof o);
    return o;
}

RfStatus rf_tracer_create_opts(const RfScene *scene, const RfTracerOptions *opt, RfTracer **out)
{
    RfTracer *t = calloc(1, sizeof *t);
    *out = NULL;
    if (!t)
        return RF_ERR_NOMEM;
    t->scene = scene;
    t->opt = opt ? *opt : rf_tracer_options_default();
    t->objects = calloc(scene->object_count ? scene->object_count : 1, sizeof *t->objects);
    PrimScan ps = scan_prims(scene);
    RfStatus st = t->objects ? cut_nonconvex(t, &ps) : RF_ERR_NOMEM;
    if (st == RF_OK)
        st = cone_frames(t, &ps);
    if (st == RF_OK)
        st = build_level(t, 0, scene->prim_count, 1, &t->world);
    if (st != RF_OK) {
        rf_tracer_free(t);
        return st;
    }
    *out = t;
    return RF_OK;
}

RfStatus rf_tracer_create(const RfScene *scene, RfTracer **out)
{
    return rf_tracer_create_opts(scene, NULL, out);
}

int rf_tracer_cone_empty(const RfTracer *t, RfVec3 apex, const RfVec3 *normals, int count)
{
    if (t->opt.brute_force || t->world.unbounded_count > 0)
        return 0;
    return t->world.bvh_count == 0 || rf_bvh_cone_empty(&t->world.bvh, apex, normals, count);
}

size_t rf_tracer_bytes(const RfTracer *t)
{
    const Level *lv[2] = {&t->world, NULL};
    size_t bytes = sizeof *t;
    if (t->cut) {
        for (size_t i = 0; i < t->scene->prim_count; i++)
            if (t->scene->prims[i].type == RF_PRIM_POLYGON && (t->scene->prims[i].flags & RF_PRIM_NONCONVEX))
                bytes += sizeof *t->cut * 3 * (size_t)(t->scene->prims[i].u.poly.count - 2);
        bytes += sizeof *t->cut_first * t->scene->prim_count;
    }
    for (size_t o = 0; o <= t->scene->object_count; o++) {
        const Level *l = o == 0 ? lv[0] : &t->objects[o - 1];
        bytes += rf_bvh_bytes(&l->bvh) + sizeof *l + sizeof *l->unbounded * (size_t)l->unbounded_count;
        if (l->items) /* brute force keeps them */
            bytes += (size_t)l->item_count * (sizeof *l->items + sizeof *l->bvh_items);
    }
    return bytes;
}

/* ---- intersection ---- */

/* A nearest-hit (or, shadow = 1, any-hit) query through the levels. The details of the nearest
 * hit so far that is not a BVH triangle (spheres, cones, planes, instances) are kept here as
 * they are found; a triangle's are computed once, for the winner (trace_level). */
typedef struct {
    const RfTracer *tracer;
    int shadow;         /* any-hit: every surface blocks, whichever side */
    int both;           /* nearest-hit: every surface counts, whichever side (RfTracerOptions.two_sided,
                           filtered shadow rays) */
    Item item;          /* the item hit (inside instances: the object's primitive) */
    int material;       /* its material */
    int smooth;         /* it interpolates vertex normals */
    RfHit hit;          /* hit.normal in the space of the query's ray */
    const RfTriangle *tri; /* a BVH triangle's double vertices when it is the hit (else NULL) */
    int instanced;      /* the hit is inside an instance: nmat takes its normals to this space */
    RfMat3 nmat;
    uint64_t occluder;  /* shadow: the key of the world item found */
    const RfMotionState *motion; /* §3.10 moving instances at the ray's time; NULL: their first keyframe */
} Query;

/* The moving instances' matrices at one time (RfScene.motions order): one set per path, made
 * once per camera sample instead of once per ray and instance. */
typedef struct {
    int ok;      /* 0: singular at this time (the instance is not hit) */
    int bounded; /* box holds the instance at this time */
    RfAabb box;
    RfMat4 to_object;
    RfMat3 normal_to_world;
} MotionFrame;

struct RfMotionState {
    const RfTracer *tracer;
    double time;
    MotionFrame *frames;
};

/* The world box of an object's box under m: its 8 corners, padded by a few ulps so that the
 * corners' rounding never culls a ray (as instance_box). */
static RfAabb transformed_box(RfAabb ob, RfMat4 m, int *ok)
{
    RfAabb b = rf_aabb_empty();
    *ok = 1;
    for (int c = 0; c < 8; c++) {
        RfVec3 k = rf_vec3(c & 1 ? ob.hi.x : ob.lo.x, c & 2 ? ob.hi.y : ob.lo.y, c & 4 ? ob.hi.z : ob.lo.z);
        if (rf_transform_point(m, k, &k) != RF_OK)
            *ok = 0;
        b = rf_aabb_add_point(b, k);
    }
    double mx = fmax(fmax(fmax(fabs(b.lo.x), fabs(b.hi.x)), fmax(fabs(b.lo.y), fabs(b.hi.y))),
                     fmax(fabs(b.lo.z), fabs(b.hi.z)));
    RfVec3 pad = rf_vec3(16.0 * DBL_EPSILON * mx, 16.0 * DBL_EPSILON * mx, 16.0 * DBL_EPSILON * mx);
    b.lo = rf_vec3_sub(b.lo, pad);
    b.hi = rf_vec3_add(b.hi, pad);
    return b;
}

/* Can the ray meet the (padded) box within [t_min, t_max]? Slab distances in double, the
 * comparison with a relative slack far above their rounding; NaN never culls. */
static int box_may_hit(RfAabb b, RfRay r, double t_min, double t_max)
{
    const double o[3] = {r.origin.x, r.origin.y, r.origin.z}, d[3] = {r.dir.x, r.dir.y, r.dir.z};
    const double lo[3] = {b.lo.x, b.lo.y, b.lo.z}, hi[3] = {b.hi.x, b.hi.y, b.hi.z};
    double t0 = t_min, t1 = t_max;
    for (int a = 0; a < 3; a++) {
        if (d[a] == 0.0) {
            if (o[a] < lo[a] || o[a] > hi[a])
                return 0;
            continue;
        }
        double inv = 1.0 / d[a], ta = (lo[a] - o[a]) * inv, tb = (hi[a] - o[a]) * inv;
        if (ta > tb) {
            double x = ta;
            ta = tb;
            tb = x;
        }
        t0 = ta > t0 ? ta : t0;
        t1 = tb < t1 ? tb : t1;
    }
    return !(t0 > t1 + 1e-9 * (fabs(t0) + fabs(t1)));
}

RfMotionState *rf_motion_state_new(const RfTracer *t)
{
    RfMotionState *ms = calloc(1, sizeof *ms);
    if (!ms)
        return NULL;
    ms->tracer = t;
    ms->time = NAN;
    ms->frames = calloc(t->scene->motion_count ? t->scene->motion_count : 1, sizeof *ms->frames);
    if (!ms->frames) {
        free(ms);
        return NULL;
    }
    return ms;
}

void rf_motion_state_free(RfMotionState *ms)
{
    if (ms)
        free(ms->frames);
    free(ms);
}

void rf_motion_state_set(RfMotionState *ms, double time)
{
    if (time == ms->time)
        return;
    ms->time = time;
    const RfScene *s = ms->tracer->scene;
    for (size_t i = 0; i < s->instance_count; i++) {
        const RfInstance *in = &s->instances[i];
        if (in->motion < 0)
            continue;
        RfMat4 to_world;
        MotionFrame *f = &ms->frames[in->motion];
        f->ok = rf_motion_at(&s->motions[in->motion], time, &to_world, &f->to_object, &f->normal_to_world) == RF_OK;
        const Level *lv = in->object >= 0 ? &ms->tracer->objects[in->object] : NULL;
        f->bounded = 0;
        if (f->ok && lv && lv->unbounded_count == 0 && lv->bvh_count > 0)
            f->box = transformed_box(lv->box, to_world, &f->bounded);
    }
}

static int trace_level(const Level *lv, Query *q, const RfRay *rp, double t_min, double *t_lim, uint64_t *key_lim);

/* §4.8/§4.9: the ray goes into object space by M^-1 without normalising its direction, so t
 * is the same in both spaces; the normal comes back by the inverse transpose (M^-1)^T. */
static int hit_instance(Query *q, const RfPrimitive *p, RfRay ray, double t_min, double t_max, double *t)
{
    const RfTracer *tr = q->tracer;
    const RfInstance *in = &tr->scene->instances[p->u.instance];
    RfMat4 to_object = in->to_object;
    RfMat3 normal_to_world = in->normal_to_world;
    RfRay r;
    if (in->motion >= 0 && q->motion) { /* §3.10: where the instance is at the ray's time */
        const MotionFrame *f = &q->motion->frames[in->motion];
        if (!f->ok || (f->bounded && !box_may_hit(f->box, ray, t_min, t_max)))
            return 0;
        to_object = f->to_object;
        normal_to_world = f->normal_to_world;
    }
    if (rf_transform_point(to_object, ray.origin, &r.origin) != RF_OK)
        return 0;
    r.dir = rf_transform_direction(to_object, ray.dir);
    Query sub;
    sub.tracer = tr;
    sub.shadow = q->shadow;
    sub.both = q->both;
    sub.instanced = 0;
    sub.motion = q->motion;
    double tm = t_max;
    uint64_t key = 0;
    if (!trace_level(&tr->objects[in->object], &sub, &r, t_min, &tm, &key))
        return 0;
    if (q->shadow)
        return *t = tm, 1;
    q->hit = sub.hit;
    q->tri = NULL;
    q->hit.normal = rf_vec3_normalize(rf_mat3_mul_vec(normal_to_world, sub.hit.normal));
    q->item = sub.item;
    q->material = sub.material;
    q->smooth = sub.smooth;
    q->nmat = sub.instanced ? rf_mat3_mul(normal_to_world, sub.nmat) : normal_to_world;
    q->instanced = 1;
    *t = tm;
    return 1;
}

/* Intersects one item with the double-precision kernels of §3.5 at t in [t_min, t_max); on a
 * hit keeps its details in q and returns 1 with *t. */
static int hit_item(Query *q, Item it, const RfRay *rp, const RfWatertightRay *wr, double t_min, double t_max,
                    double *t)
{
    /* the ray is read where a kernel needs it by value (rf_ray_read, ray.h): a copy for all
     * would be made, and waited for, on the cones' path too */
    const RfScene *s = q->tracer->scene;
    const RfPrimitive *p = &s->prims[it.prim];
    RfHit h;
    int ok = 0;
    if (p->type == RF_PRIM_INSTANCE)
        return hit_instance(q, p, rf_ray_read(rp), t_min, t_max, t);
again:
    switch (p->type) {
    case RF_PRIM_SPHERE: {
        if (q->shadow) { /* rf_intersect_sphere's root, without the normal a shadow query never reads */
            RfSphereRoots r;
            int root = rf_sphere_roots(rp, &p->u.sphere, &r) ? rf_sphere_pick_root(r.t, t_min, t_max) : 0;
            if (root)
                *t = r.t[root - 1];
            return root != 0;
        }
        ok = rf_intersect_sphere(rf_ray_read(rp), p->u.sphere, RF_SPHERE_STABLE, t_min, t_max, &h);
        break;
    }
    case RF_PRIM_PLANE: {
        ok = rf_intersect_plane(rf_ray_read(rp), p->u.plane, t_min, t_max, &h);
        break;
    }
    case RF_PRIM_TRIANGLE:
    case RF_PRIM_POLYGON:
        if (it.sub >= 0) {
            RfWatertightRay own;
            if (!wr) {
                rf_watertight_ray(rp, &own);
                wr = &own;
            }
            ok = rf_intersect_triangle_watertight(wr, item_triangle(q->tracer, it), t_min, t_max, &h);
        }
        break;
    case RF_PRIM_CONE: {
        /* a shadow query needs no normal: the hidden side is a matter of the nearest hit */
        const RfConeFrame *frame = &q->tracer->cone_frames[(size_t)it.prim - q->tracer->cone_first];
        ok = rf_intersect_cone_framed(rp, &p->u.cone, frame, t_min, t_max, !q->shadow, &h);
        break;
    }
    default:
        break;
    }
    if (!ok)
        return 0;
    if (!q->shadow && !q->both && !(p->flags & RF_PRIM_TWO_SIDED)) {
        /* one-sided: visible only from the front (outside, counter-clockwise side), or only
         * from the inside for RF_PRIM_INSIDE */
        int front = rf_vec3_dot(rp->dir, h.normal) < 0.0;
        if (front == !!(p->flags & RF_PRIM_INSIDE)) {
            /* the hidden side of a sphere or cone: its far root may face the ray (an inside-only
             * sphere seen from outside shows its far wall) */
            if (p->type == RF_PRIM_SPHERE || p->type == RF_PRIM_CONE) {
                t_min = rf_next_up(h.t);
                goto again;
            }
            return 0;
        }
    }
    q->hit = h;
    q->tri = NULL;
    q->item = it;
    q->material = p->material;
    q->smooth = it.sub >= 0 && prim_smooth(s, p);
    q->instanced = 0;
    *t = h.t;
    return 1;
}

/* Tests an item against the limit (t_lim, key_lim): a hit counts when it is nearer, or as near
 * with a lower key (the tie rule; key_lim = 0: t < t_lim). */
static int hit_key(Query *q, uint64_t key, const RfRay *ray, const RfWatertightRay *wr, double t_min, double t_lim,
                   uint64_t key_lim, double *t)
{
    double t_max = !q->shadow && key < key_lim ? rf_next_up(t_lim) : t_lim;
    return hit_item(q, key_item(key), ray, wr, t_min, t_max, t);
}

/* The BVH's callback for the items it does not intersect itself. */
static int bvh_item(void *ctx, uint64_t key, const RfBvhRay *r, double t_min, double t_max, int inclusive, double *t)
{
    return hit_item(ctx, key_item(key), &r->ray, NULL, t_min, inclusive ? rf_next_up(t_max) : t_max, t);
}

/* A level's unbounded items (planes), in key order, before its BVH: 1 when one is hit within
 * the limit (*t_lim, *key_lim), which it then becomes (a shadow query: q->occluder). */
static inline int level_unbounded(const Level *lv, Query *q, const RfRay *rp, double t_min, double *t_lim,
                                  uint64_t *key_lim)
{
    int found = 0;
    for (int u = 0; u < lv->unbounded_count; u++) {
        uint64_t key = lv->unbounded[u];
        double t;
        if (hit_key(q, key, rp, NULL, t_min, *t_lim, *key_lim, &t)) {
            if (q->shadow)
                return q->occluder = key, 1;
            *t_lim = t, *key_lim = key, found = 1;
        }
    }
    return found;
}

static inline void bvh_hit_init(RfBvhHit *best, double t, uint64_t key)
{
    best->t = t;
    best->key = key;
    best->tri = NULL;
    best->sphere = NULL;
    best->cone = NULL;
}

/* The details of the BVH's winner (a triangle, sphere or cone it tested itself) into q: the same
 * bits as the BVH's t. The caller's items have put theirs there already. */
static RF_INLINE_ALWAYS void level_winner(Query *q, const RfBvhHit *best, const RfRay *rp)
{
    if (!(best->tri || best->sphere || best->cone))
        return;
    q->tri = best->tri;
    if (best->tri) { /* rf_intersect_triangle_watertight's hit from the BVH's own test */
        rf_watertight_hit(best->tri, best->t, best->edges, best->has_normal ? &best->normal : NULL, &q->hit);
    } else {
        q->hit.t = best->t;
        q->hit.l[0] = q->hit.l[1] = q->hit.l[2] = 0.0;
        q->hit.normal = best->cone ? best->normal : rf_sphere_root_normal(&best->roots, rp, best->sphere, best->far);
    }
    q->item = key_item(best->key);
    q->material = (int)(best->user & USER_MATERIAL);
    q->smooth = (best->user & USER_SMOOTH) != 0;
    q->instanced = 0;
}

/* The nearest (or, shadow = 1, any) hit in one level at t >= t_min within the limit
 * (*t_lim, *key_lim) (hit_key's rule). Returns 1 with q->hit, q->item and the new limit. */
static int trace_level(const Level *lv, Query *q, const RfRay *rp, double t_min, double *t_lim, uint64_t *key_lim)
{
    double bt = *t_lim;
    uint64_t bk = *key_lim;
    int found = level_unbounded(lv, q, rp, t_min, &bt, &bk);
    if (found && q->shadow)
        return 1;
    RfBvhHit best;
    bvh_hit_init(&best, bt, bk);
    RfBvhRay br;
    if (q->tracer->opt.brute_force) {
        /* every item, in key order, with the double kernels alone: the reference for the BVH */
        RfWatertightRay wr;
        rf_watertight_ray(rp, &wr);
        for (int j = 0; j < lv->bvh_count; j++) {
            uint64_t key = item_key(lv->items[lv->bvh_items[j]]);
            double t;
            if (hit_key(q, key, rp, &wr, t_min, bt, bk, &t)) {
                if (q->shadow)
                    return q->occluder = key, 1;
                bt = t, bk = key, found = 1;
            }
        }
    } else if (lv->bvh_count > 0) {
        rf_bvh_ray_init(&lv->bvh, rp, &br);
        if (q->shadow) {
            uint64_t key = 0;
            int hit = rf_bvh_occluded(&lv->bvh, &br, t_min, bt, bvh_item, q, &key);
            q->occluder = key;
            return hit;
        }
        if (q->both ? rf_bvh_nearest_any_side(&lv->bvh, &br, t_min, &best, bvh_item, q)
                    : rf_bvh_nearest(&lv->bvh, &br, t_min, &best, bvh_item, q)) {
            bt = best.t;
            bk = best.key;
            found = 1;
        }
    }
    if (!found)
        return 0;
    level_winner(q, &best, rp);
    *t_lim = bt;
    *key_lim = bk;
    return 1;
}

/* A query of one kind (Query.shadow, Query.both) at the time of the motion state ms. */
static inline void query_init(Query *q, const RfTracer *t, int shadow, int both, const RfMotionState *ms)
{
    q->tracer = t;
    q->shadow = shadow;
    q->both = both;
    q->instanced = 0;
    q->motion = ms;
}

/* The nearest (or, shadow = 1, any) hit in [t_min, t_max); returns 1 with q->hit/q->item. */
static int trace_query(const RfTracer *t, Query *q, const RfRay *ray, double t_min, double t_max)
{
    uint64_t key = 0;
    q->tracer = t;
    q->instanced = 0;
    return trace_level(&t->world, q, ray, t_min, &t_max, &key);
}

int rf_tracer_occluded(const RfTracer *t, const RfRay *rp, double t_min, double t_max)
{
    Query q;
    const RfRay ray = rf_ray_read(rp);
    query_init(&q, t, 1, 0, NULL);
    return trace_query(t, &q, &ray, t_min, t_max);
}

int rf_tracer_occluded_cached(const RfTracer *t, const RfRay *ray, double t_min, double t_max, uint64_t *last)
{
    return rf_tracer_occluded_cached_at(t, ray, NULL, t_min, t_max, last);
}

int rf_tracer_occluded_cached_at(const RfTracer *t, const RfRay *rp, const RfMotionState *ms, double t_min,
                                 double t_max, uint64_t *last)
{
    Query q;
    const RfRay ray = rf_ray_read(rp);
    query_init(&q, t, 1, 0, ms);
    if (*last) { /* the occluder of the last query first: neighbouring shadow rays share it */
        double tt;
        if (hit_item(&q, key_item(*last), &ray, NULL, t_min, t_max, &tt))
            return 1;
    }
    if (!trace_query(t, &q, &ray, t_min, t_max)) {
        *last = 0; /* in the light: the next ray likely is too, and would test the cache in vain */
        return 0;
    }
    *last = q.occluder;
    return 1;
}

RfRgb rf_tracer_transmittance_at(const RfTracer *t, const RfRay *rp, const RfMotionState *ms, double t_min,
                                 double t_max, uint64_t *last)
{
    const RfRgb zero = rf_rgb(0, 0, 0);
    const RfRay ray = rf_ray_read(rp);
    Query q;
    query_init(&q, t, 1, 0, ms);
    /* the last primitive that blocked alone: any hit on it gives 0, as the walk would */
    if (*last && hit_item(&q, key_item(*last), &ray, NULL, t_min, t_max, &(double){0}))
        return zero;
    RfRgb tr = rf_rgb(1, 1, 1);
    q.shadow = 0;
    q.both = 1;
    /* POV-Ray's walk: the nearest crossing, its kt, on from just beyond it */
    while (t_min < t_max && trace_query(t, &q, &ray, t_min, t_max)) {
        RfRgb kt = t->scene->materials[q.material].kt;
        tr = rf_rgb_mul(tr, kt);
        if (!(tr.r > 0.0 || tr.g > 0.0 || tr.b > 0.0)) {
            const RfPrimitive *p = &t->scene->prims[q.item.prim];
            int alone = !(kt.r > 0.0 || kt.g > 0.0 || kt.b > 0.0) && !q.instanced && p->type != RF_PRIM_INSTANCE;
            *last = alone ? item_key(q.item) : 0;
            return zero;
        }
        t_min = rf_next_up(q.hit.t);
    }
    *last = 0;
    return tr;
}

int rf_tracer_intersect(const RfTracer *t, const RfRay *ray, double t_min, double t_max, RfSurfaceHit *out)
{
    return rf_tracer_intersect_at(t, ray, NULL, t_min, t_max, out);
}

/* The surface hit of a nearest-hit query q of ray (§3.5, the normals of §3.6.3 and §4.9, the
 * point's error bound); returns its primitive. */
static RF_INLINE_ALWAYS int surface_hit(const RfTracer *t, const Query *q, const RfRay *rp, RfSurfaceHit *out)
{
    const RfRay ray = *rp;
    const RfScene *s = t->scene;
    out->t = q->hit.t;
    out->prim = q->item.prim;
    out->material = q->material;
    out->point = rf_ray_at(ray, q->hit.t);
    /* the hit point's error bound, in units of RF_RAY_OFFSET_REL (numeric.h). o + t d carries the
     * rounding of t, which grows with the distance travelled; a point put back on its surface
     * does not (pbrt-v4's reprojection): a sphere's along its radius, a triangle's from its
     * barycentric coordinates, a plane's along its normal. Their errors are a few ulps of the
     * coordinates they are made of. A cone's quadratic and an instance's matrices lose more. */
    const RfPrimitive *pr = &s->prims[q->item.prim];
    int reprojected = 0; /* else the scale of the point and the origin */
    if (!q->instanced && pr->type == RF_PRIM_SPHERE) {
        RfVec3 v = rf_vec3_sub(out->point, pr->u.sphere.center);
        double len = rf_vec3_length(v);
        if (len > 0.0) {
            out->point = rf_vec3_add(pr->u.sphere.center, rf_vec3_scale(v, pr->u.sphere.radius / len));
            double sc = rf_vec3_max_abs(pr->u.sphere.center) + pr->u.sphere.radius;
            out->scale = rf_max_num(rf_vec3_max_abs(out->point), sc);
            reprojected = 1;
        }
    } else if (!q->instanced && q->item.sub >= 0 && (pr->type == RF_PRIM_TRIANGLE || pr->type == RF_PRIM_POLYGON)) {
        RfTriangle tri = q->tri ? *q->tri : item_triangle(t, q->item); /* the BVH block's copy: the same doubles */
        out->point = rf_vec3_add(rf_vec3_add(rf_vec3_scale(tri.p1, q->hit.l[0]), rf_vec3_scale(tri.p2, q->hit.l[1])),
                                 rf_vec3_scale(tri.p3, q->hit.l[2]));
        out->scale = rf_max_num(rf_vec3_max_abs(tri.p1), rf_max_num(rf_vec3_max_abs(tri.p2), rf_vec3_max_abs(tri.p3)));
        reprojected = 1;
    } else if (!q->instanced && pr->type == RF_PRIM_PLANE) {
        RfVec3 n = pr->u.plane.normal; /* any length */
        double nn = rf_vec3_dot(n, n);
        out->point = rf_vec3_sub(out->point, rf_vec3_scale(n, (rf_vec3_dot(n, out->point) - pr->u.plane.offset) / nn));
        out->scale = rf_max_num(rf_vec3_max_abs(out->point), fabs(pr->u.plane.offset) / sqrt(nn));
        reprojected = 1;
    }
    if (!reprojected) {
        double so = rf_vec3_max_abs(ray.origin);
        out->scale = rf_vec3_max_abs(out->point);
        out->scale = so > out->scale ? so : out->scale;
    }
    if (pr->type == RF_PRIM_CONE)
        out->scale *= RF_RAY_OFFSET_CONE;
    if (q->instanced)
        out->scale *= RF_RAY_OFFSET_INSTANCE;
    out->front = rf_vec3_dot(ray.dir, q->hit.normal) < 0.0;
    out->normal = out->front ? q->hit.normal : rf_vec3_neg(q->hit.normal);
    out->shading_normal = out->normal;
    if (q->smooth) {
        /* §3.6.3 Phong shading: interpolate the vertex normals with the barycentric coordinates */
        const RfVec3 *nv = s->normals + s->prims[q->item.prim].u.poly.nfirst;
        RfVec3 n;
        int c[3];
        item_corners(t, q->item, c);
        if (rf_interpolate_normal(nv[c[0]], nv[c[1]], nv[c[2]], q->hit.l[0], q->hit.l[1], q->hit.l[2], &n) == RF_OK) {
            if (q->instanced) /* object space -> world (§4.9) */
                n = rf_vec3_normalize(rf_mat3_mul_vec(q->nmat, n));
            /* keep it on the side of the geometric normal the ray sees */
            out->shading_normal = rf_vec3_dot(n, out->normal) < 0.0 ? rf_vec3_neg(n) : n;
        }
    }
    return out->prim;
}

int rf_tracer_intersect_at(const RfTracer *t, const RfRay *rp, const RfMotionState *ms, double t_min, double t_max,
                           RfSurfaceHit *out)
{
    Query q;
    const RfRay ray = rf_ray_read(rp);
    query_init(&q, t, 0, t->opt.two_sided, ms);
    if (!trace_query(t, &q, &ray, t_min, t_max))
        return -1;
    return surface_hit(t, &q, &ray, out);
}

unsigned rf_tracer_intersect4(const RfTracer *t, const RfRay rays[4], unsigned active, const double t_min[4],
                              RfSurfaceHit out[4])
{
    const Level *lv = &t->world;
    unsigned hit = 0;
    active &= 0xFu;
    if (t->opt.brute_force || lv->bvh_count == 0) { /* nothing to share: one query per ray */
        for (unsigned s = active; s; s &= s - 1) {
            int l = __builtin_ctz(s);
            hit |= (unsigned)(rf_tracer_intersect(t, &rays[l], t_min[l], HUGE_VAL, &out[l]) >= 0) << l;
        }
        return hit;
    }
    /* trace_query's world level, with the BVH walked once for the four rays */
    Query q[4];
    RfRay ray[4];
    RfBvhRay br[4];
    RfBvhHit best[4];
    void *ctx[4];
    for (unsigned s = active; s; s &= s - 1) {
        int l = __builtin_ctz(s);
        query_init(&q[l], t, 0, t->opt.two_sided, NULL);
        ctx[l] = &q[l];
        ray[l] = rf_ray_read(&rays[l]);
        bvh_hit_init(&best[l], HUGE_VAL, 0); /* the planes' nearest hit is where the BVH's walk starts */
        hit |= (unsigned)level_unbounded(lv, &q[l], &ray[l], t_min[l], &best[l].t, &best[l].key) << l;
        rf_bvh_ray_init(&lv->bvh, &ray[l], &br[l]);
    }
    hit |= rf_bvh_nearest4(&lv->bvh, br, active, t_min, best, bvh_item, ctx, t->opt.two_sided);
    for (unsigned s = hit; s; s &= s - 1) {
        int l = __builtin_ctz(s);
        level_winner(&q[l], &best[l], &ray[l]);
        surface_hit(t, &q[l], &ray[l], &out[l]);
    }
    return hit;
}
