/* refray: the scene graph of §4.8 — objects placed by instances, a DAG (one object may sit in
 * several groups) — its checks, counts and bounds, and the flattening into plain primitives
 * (scene.h). */
#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "refray/scene.h"
#include "scene_internal.h"
#include "refray/bvh.h" /* RfAabb */
#include "refray/transform.h"


/* ---- checks: names resolved, no cycle ------------------------------------------------------ */

typedef struct {
    const RfScene *scene;
    unsigned char *state; /* per object: 0 unvisited, 1 on the DFS stack, 2 done */
    int *height;          /* per object (done): the longest chain of objects it contains, itself included */
    int *stack;           /* the objects on the DFS path, for the message */
    int depth;
    RfSrcLoc *loc;
    char *msg;
    size_t msgsz;
} CycleSearch;

static RfStatus too_deep(CycleSearch *cs, const RfPrimitive *p, int o)
{
    *cs->loc = p->loc;
    return rf__msgf(cs->msg, cs->msgsz, RF_ERR_DOMAIN,
                    "instances nested deeper than %d levels (through object '%s'): the limit keeps every "
                    "tool's recursion bounded",
                    RF_SCENE_MAX_NESTING, cs->scene->objects[o].name);
}

/* Depth-first search from object o; a back edge (an object still on the stack) is a cycle. The
 * heights are memoised, so a DAG costs one visit per object, and the recursion stops at the
 * nesting limit. */
static RfStatus visit(CycleSearch *cs, int o)
{
    const RfScene *s = cs->scene;
    const RfSceneObject *ob = &s->objects[o];
    int h = 1;
    cs->state[o] = 1;
    cs->stack[cs->depth++] = o;
    for (size_t i = ob->first; i < ob->first + ob->count; i++) {
        const RfPrimitive *p = &s->prims[i];
        if (p->type != RF_PRIM_INSTANCE)
            continue;
        int c = s->instances[p->u.instance].object;
        if (cs->state[c] == 1) {
            /* the path from c to here, then c again */
            size_t n = 0;
            int k = cs->depth - 1;
            while (k > 0 && cs->stack[k] != c)
                k--;
            n += (size_t)snprintf(cs->msg, cs->msgsz, "cycle in the scene graph: ");
            for (; k < cs->depth && n < cs->msgsz; k++)
                n += (size_t)snprintf(cs->msg + n, cs->msgsz - n, "'%s' -> ",
                                      s->objects[cs->stack[k]].name);
            if (n < cs->msgsz)
                snprintf(cs->msg + n, cs->msgsz - n, "'%s' (an object cannot contain itself)",
                         s->objects[c].name);
            *cs->loc = p->loc;
            return RF_ERR_DOMAIN;
        }
        if (cs->state[c] == 0) {
            if (cs->depth >= RF_SCENE_MAX_NESTING)
                return too_deep(cs, p, c);
            RfStatus st = visit(cs, c);
            if (st)
                return st;
        }
        if (1 + cs->height[c] > h)
            h = 1 + cs->height[c];
        if (h > RF_SCENE_MAX_NESTING)
            return too_deep(cs, p, c);
    }
    cs->depth--;
    cs->state[o] = 2;
    cs->height[o] = h;
    return RF_OK;
}

RfStatus rf_scene_graph_check(const RfScene *scene, RfSrcLoc *loc, char *msg, size_t msgsz)
{
    for (size_t o = 0; o < scene->object_count; o++) {
        const RfSceneObject *ob = &scene->objects[o];
        if (ob->first > scene->prim_count || ob->count > scene->prim_count - ob->first) {
            *loc = ob->loc;
            return rf__msgf(msg, msgsz, RF_ERR_DOMAIN, "object '%s': primitive range out of bounds",
                        ob->name);
        }
    }
    for (size_t i = 0; scene->instance_count > 0 && i < scene->prim_count; i++) { /* a mesh has none */
        const RfPrimitive *p = &scene->prims[i];
        if (p->type != RF_PRIM_INSTANCE)
            continue;
        int o = scene->instances[p->u.instance].object;
        if (o < 0 || (size_t)o >= scene->object_count) {
            *loc = p->loc;
            return rf__msgf(msg, msgsz, RF_ERR_DOMAIN, "instance of an unknown object");
        }
    }
    if (scene->object_count == 0)
        return RF_OK;
    CycleSearch cs;
    memset(&cs, 0, sizeof cs);
    cs.scene = scene;
    cs.state = calloc(scene->object_count, 1);
    cs.height = calloc(scene->object_count, sizeof *cs.height);
    cs.stack = malloc(scene->object_count * sizeof *cs.stack);
    cs.loc = loc;
    cs.msg = msg;
    cs.msgsz = msgsz;
    RfStatus st = cs.state && cs.height && cs.stack ? RF_OK : RF_ERR_NOMEM;
    for (size_t o = 0; !st && o < scene->object_count; o++)
        if (!cs.state[o])
            st = visit(&cs, (int)o);
    if (st == RF_ERR_NOMEM)
        rf__msgf(msg, msgsz, st, "out of memory");
    free(cs.state);
    free(cs.height);
    free(cs.stack);
    return st;
}

/* ---- counts and bounds --------------------------------------------------------------------- */

static size_t sat_add(size_t a, size_t b) { return a > SIZE_MAX - b ? SIZE_MAX : a + b; }

/* Triangles of one stored primitive (0 for spheres, cones, planes, instances). */
static size_t prim_triangles(const RfPrimitive *p)
{
    if (p->type == RF_PRIM_TRIANGLE)
        return 1;
    if (p->type == RF_PRIM_POLYGON)
        return (p->flags & RF_PRIM_NONCONVEX) ? 1 : (size_t)p->u.poly.count - 2;
    return 0;
}

/* Triangles rendered for prims[first, end) (skipping object parts when world is set), with
 * every instance expanded; memo[o] caches object o (SIZE_MAX: not yet known). The graph is
 * checked to be acyclic before this runs. */
static size_t expanded(const RfScene *s, size_t first, size_t end, int world, size_t *memo,
                       size_t *instances)
{
    size_t n = 0;
    for (size_t i = first; i < end; i++) {
        const RfPrimitive *p = &s->prims[i];
        if (world && (p->flags & RF_PRIM_IN_OBJECT))
            continue;
        if (p->type != RF_PRIM_INSTANCE) {
            n = sat_add(n, prim_triangles(p));
            continue;
        }
        int o = s->instances[p->u.instance].object;
        if (o < 0 || (size_t)o >= s->object_count)
            continue;
        *instances = sat_add(*instances, 1);
        if (memo[o] == SIZE_MAX) {
            size_t sub = 0;
            memo[o] = expanded(s, s->objects[o].first, s->objects[o].first + s->objects[o].count,
                               0, memo, &sub);
            /* instances below this one are counted once per placement of it: keep the
             * per-object count in the upper memo slot */
            memo[s->object_count + (size_t)o] = sub;
        }
        n = sat_add(n, memo[o]);
        *instances = sat_add(*instances, memo[s->object_count + (size_t)o]);
    }
    return n;
}

RfTriangleCount rf_scene_triangle_count(const RfScene *scene)
{
    RfTriangleCount c = {0, 0, 0};
    for (size_t i = 0; i < scene->prim_count; i++)
        c.stored = sat_add(c.stored, prim_triangles(&scene->prims[i]));
    size_t *memo = malloc((2 * scene->object_count + 1) * sizeof *memo);
    if (!memo)
        return c;
    for (size_t o = 0; o < 2 * scene->object_count; o++)
        memo[o] = SIZE_MAX;
    c.rendered = expanded(scene, 0, scene->prim_count, 1, memo, &c.instances_rendered);
    free(memo);
    return c;
}

static RfVec3 vmin(RfVec3 a, RfVec3 b) { return rf_vec3(fmin(a.x, b.x), fmin(a.y, b.y), fmin(a.z, b.z)); }
static RfVec3 vmax(RfVec3 a, RfVec3 b) { return rf_vec3(fmax(a.x, b.x), fmax(a.y, b.y), fmax(a.z, b.z)); }

/* An object's box, memoised per object (a DAG is one visit per object, not per path): state 0
 * not yet known, 1 bounded, 2 unbounded or empty. Recursion stops at the nesting limit. */
typedef struct {
    unsigned char state;
    RfVec3 lo, hi;
} BoxMemo;

static int object_bounds(const RfScene *scene, int object, BoxMemo *memo, int depth)
{
    BoxMemo *m = &memo[object];
    if (m->state)
        return m->state == 1;
    m->state = 2; /* until known; a cycle (unvalidated scenes) ends here as unbounded */
    if (depth > RF_SCENE_MAX_NESTING)
        return 0;
    RfVec3 lo = rf_vec3(INFINITY, INFINITY, INFINITY), hi = rf_vec3(-INFINITY, -INFINITY, -INFINITY);
    const RfSceneObject *ob = &scene->objects[object];
    int any = 0;
    for (size_t i = ob->first; i < ob->first + ob->count && i < scene->prim_count; i++) {
        const RfPrimitive *p = &scene->prims[i];
        switch (p->type) {
        case RF_PRIM_SPHERE: {
            RfVec3 r = rf_vec3(p->u.sphere.radius, p->u.sphere.radius, p->u.sphere.radius);
            lo = vmin(lo, rf_vec3_sub(p->u.sphere.center, r));
            hi = vmax(hi, rf_vec3_add(p->u.sphere.center, r));
            break;
        }
        case RF_PRIM_TRIANGLE:
        case RF_PRIM_POLYGON:
            for (int k = 0; k < p->u.poly.count; k++) {
                lo = vmin(lo, scene->vertices[p->u.poly.first + (size_t)k]);
                hi = vmax(hi, scene->vertices[p->u.poly.first + (size_t)k]);
            }
            break;
        case RF_PRIM_CONE: {
            double r = fmax(p->u.cone.base_radius, p->u.cone.apex_radius);
            RfVec3 e = rf_vec3(r, r, r);
            lo = vmin(lo, vmin(rf_vec3_sub(p->u.cone.base, e), rf_vec3_sub(p->u.cone.apex, e)));
            hi = vmax(hi, vmax(rf_vec3_add(p->u.cone.base, e), rf_vec3_add(p->u.cone.apex, e)));
            break;
        }
        case RF_PRIM_INSTANCE: {
            const RfInstance *in = &scene->instances[p->u.instance];
            if (in->object < 0 || (size_t)in->object >= scene->object_count ||
                !object_bounds(scene, in->object, memo, depth + 1))
                return 0;
            RfVec3 ol = memo[in->object].lo, oh = memo[in->object].hi;
            for (int c = 0; c < 8; c++) { /* the 8 corners of the child's box */
                RfVec3 k = rf_vec3(c & 1 ? oh.x : ol.x, c & 2 ? oh.y : ol.y, c & 4 ? oh.z : ol.z);
                if (rf_transform_point(in->to_world, k, &k) != RF_OK)
                    return 0;
                lo = vmin(lo, k);
                hi = vmax(hi, k);
            }
            break;
        }
        case RF_PRIM_PLANE:
        case RF_PRIM_TYPE_COUNT:
            return 0;
        }
        any = 1;
    }
    if (any) {
        m->state = 1;
        m->lo = lo;
        m->hi = hi;
    }
    return any;
}

int rf_scene_object_bounds(const RfScene *scene, int object, RfVec3 *lo, RfVec3 *hi)
{
    *lo = rf_vec3(INFINITY, INFINITY, INFINITY);
    *hi = rf_vec3(-INFINITY, -INFINITY, -INFINITY);
    if (object < 0 || (size_t)object >= scene->object_count)
        return 0;
    BoxMemo *memo = calloc(scene->object_count, sizeof *memo);
    int ok = memo && object_bounds(scene, object, memo, 1);
    if (ok) {
        *lo = memo[object].lo;
        *hi = memo[object].hi;
    }
    free(memo);
    return ok;
}

/* ---- flattening ---------------------------------------------------------------------------- */

typedef struct {
    RfMat4 m;    /* object -> world */
    RfMat3 n;    /* (M^-1)^T of the linear part (§4.9) */
    int mirror;  /* det M < 0: the winding flips, so vertex order is reversed */
    int similar; /* a similarity (rotation x uniform scale): spheres stay spheres */
    double scale;
    unsigned flags; /* rf_scene_flatten's */
} Xf;

static RfStatus emit(const RfScene *s, const RfPrimitive *p, const Xf *x, RfScene *out, char *msg,
                     size_t msgsz);

static RfStatus emit_range(const RfScene *s, size_t first, size_t end, int world, const Xf *x,
                           RfScene *out, char *msg, size_t msgsz)
{
    for (size_t i = first; i < end; i++) {
        const RfPrimitive *p = &s->prims[i];
        if (world && (p->flags & RF_PRIM_IN_OBJECT))
            continue;
        RfStatus st = emit(s, p, x, out, msg, msgsz);
        if (st)
            return st;
    }
    return RF_OK;
}

/* RF_FLATTEN_PLACED_QUADRICS: the quadric p as it is, the one primitive of a new object, and a
 * world instance placing it by x's matrix. */
static RfStatus emit_placed(const RfPrimitive *p, const Xf *x, RfScene *out, char *msg, size_t msgsz)
{
    int object;
    RfPrimitive q = *p, in;
    RfStatus st = rf_scene_add_object(out, "placed", p->loc, &object);
    if (st)
        return rf__msgf(msg, msgsz, st, "out of memory");
    q.flags |= RF_PRIM_IN_OBJECT;
    if ((st = rf_scene_add_primitive(out, &q, msg, msgsz)) != RF_OK)
        return st;
    out->objects[object].count = 1;
    memset(&in, 0, sizeof in);
    in.type = RF_PRIM_INSTANCE;
    in.flags = RF_PRIM_TWO_SIDED; /* an instance has no sides: its object's primitive has */
    in.material = p->material;    /* unused, as a reader's instance's */
    in.loc = p->loc;
    st = rf_scene_add_instance(out, object, x->m, &in.u.instance);
    if (st == RF_ERR_SINGULAR)
        return rf__msgf(msg, msgsz, st, "the placement of the %s of line %d is singular", rf_prim_type_name(p->type),
                        p->loc.line);
    if (st)
        return rf__msgf(msg, msgsz, st, "out of memory");
    return rf_scene_add_primitive(out, &in, msg, msgsz);
}

static RfStatus emit(const RfScene *s, const RfPrimitive *p, const Xf *x, RfScene *out, char *msg,
                     size_t msgsz)
{
    RfPrimitive q = *p;
    q.flags &= ~(unsigned)RF_PRIM_IN_OBJECT;
    switch (p->type) {
    case RF_PRIM_INSTANCE: {
        const RfInstance *in = &s->instances[p->u.instance];
        const RfSceneObject *ob = &s->objects[in->object];
        Xf y;
        y.m = rf_mat4_mul(x->m, in->to_world);
        y.n = rf_mat3_mul(x->n, in->normal_to_world);
        RfMat3 lin = rf_mat4_linear(y.m);
        y.mirror = rf_mat3_det(lin) < 0.0;
        double lambda = 1.0;
        y.similar = rf_matn_is_similarity(3, &lin.m[0][0], &lambda);
        y.scale = sqrt(lambda);
        y.flags = x->flags;
        return emit_range(s, ob->first, ob->first + ob->count, 0, &y, out, msg, msgsz);
    }
    case RF_PRIM_SPHERE:
    case RF_PRIM_CONE:
        if (!x->similar && (x->flags & RF_FLATTEN_PLACED_QUADRICS))
            return emit_placed(p, x, out, msg, msgsz);
        if (!x->similar)
            return rf__msgf(msg, msgsz, RF_ERR_DOMAIN,
                        "%s under a non-similarity transform (line %d) has no flat form",
                        rf_prim_type_name(p->type), p->loc.line);
        if (p->type == RF_PRIM_SPHERE) {
            rf_transform_point(x->m, p->u.sphere.center, &q.u.sphere.center);
            q.u.sphere.radius *= x->scale;
        } else {
            rf_transform_point(x->m, p->u.cone.base, &q.u.cone.base);
            rf_transform_point(x->m, p->u.cone.apex, &q.u.cone.apex);
            q.u.cone.base_radius *= x->scale;
            q.u.cone.apex_radius *= x->scale;
        }
        break;
    case RF_PRIM_PLANE: {
        RfVec3 point = rf_vec3_scale(p->u.plane.normal, p->u.plane.offset);
        rf_transform_point(x->m, point, &point);
        q.u.plane.normal = rf_vec3_normalize(rf_mat3_mul_vec(x->n, p->u.plane.normal));
        q.u.plane.offset = rf_vec3_dot(q.u.plane.normal, point);
        break;
    }
    case RF_PRIM_TRIANGLE:
    case RF_PRIM_POLYGON: {
        int n = p->u.poly.count, vn = (p->flags & RF_PRIM_VERTEX_NORMALS) != 0;
        RfVec3 *v = malloc(2 * (size_t)n * sizeof *v);
        if (!v)
            return rf__msgf(msg, msgsz, RF_ERR_NOMEM, "out of memory");
        for (int k = 0; k < n; k++) {
            int src = x->mirror && k > 0 ? n - k : k; /* v0 first, then reversed */
            rf_transform_point(x->m, s->vertices[p->u.poly.first + (size_t)src], &v[k]);
            if (vn)
                v[n + k] = rf_mat3_mul_vec(x->n, s->normals[p->u.poly.nfirst + (size_t)src]);
        }
        RfStatus st = rf_scene_add_vertices(out, v, vn ? v + n : NULL, n, &q.u.poly.first,
                                            &q.u.poly.nfirst);
        free(v);
        if (st)
            return rf__msgf(msg, msgsz, st, "out of memory");
        break;
    }
    case RF_PRIM_TYPE_COUNT:
        return rf__msgf(msg, msgsz, RF_ERR_DOMAIN, "unknown primitive type");
    }
    return rf_scene_add_primitive(out, &q, msg, msgsz);
}

RfStatus rf_scene_flatten(const RfScene *scene, unsigned flags, RfScene *out, char *msg, size_t msgsz)
{
    rf_scene_init(out);
    out->format = scene->format;
    out->has_camera = scene->has_camera;
    out->camera = scene->camera;
    out->render = scene->render;
    RfStatus st = RF_OK;
    for (size_t i = 0; !st && i < scene->material_count; i++)
        st = rf_scene_add_material(out, &scene->materials[i], NULL);
    for (size_t i = 0; !st && i < scene->light_count; i++)
        st = rf_scene_add_light(out, &scene->lights[i]);
    if (st) {
        rf_scene_free(out);
        return rf__msgf(msg, msgsz, st, "out of memory");
    }
    Xf id;
    id.m = rf_mat4_identity();
    id.n = rf_mat3_identity();
    id.mirror = 0;
    id.similar = 1;
    id.scale = 1.0;
    id.flags = flags;
    st = emit_range(scene, 0, scene->prim_count, 1, &id, out, msg, msgsz);
    if (st)
        rf_scene_free(out);
    return st;
}

/* ---- world bounds ---- */

static void grow_box(RfVec3 *lo, RfVec3 *hi, RfVec3 c, double r)
{
    RfAabb b = {rf_vec3(c.x - r, c.y - r, c.z - r), rf_vec3(c.x + r, c.y + r, c.z + r)};
    RfAabb a = {*lo, *hi};
    a = rf_aabb_union(a, b);
    *lo = a.lo;
    *hi = a.hi;
}

int rf_scene_bounds(const RfScene *scene, RfVec3 *lo, RfVec3 *hi)
{
    *lo = rf_vec3(INFINITY, INFINITY, INFINITY);
    *hi = rf_vec3(-INFINITY, -INFINITY, -INFINITY);
    int any = 0;
    BoxMemo *memo = scene->object_count ? calloc(scene->object_count, sizeof *memo) : NULL;
    for (size_t i = 0; i < scene->prim_count; i++) {
        const RfPrimitive *p = &scene->prims[i];
        if (p->flags & RF_PRIM_IN_OBJECT) /* seen only through instances */
            continue;
        switch (p->type) {
        case RF_PRIM_INSTANCE: {
            const RfInstance *in = &scene->instances[p->u.instance];
            if (!memo || in->object < 0 || (size_t)in->object >= scene->object_count ||
                !object_bounds(scene, in->object, memo, 1))
                break;
            RfVec3 ol = memo[in->object].lo, oh = memo[in->object].hi;
            for (int c = 0; c < 8; c++) { /* the 8 corners of the object box */
                RfVec3 k = rf_vec3(c & 1 ? oh.x : ol.x, c & 2 ? oh.y : ol.y, c & 4 ? oh.z : ol.z);
                if (rf_transform_point(in->to_world, k, &k) == RF_OK)
                    grow_box(lo, hi, k, 0.0);
            }
            any = 1;
            break;
        }
        case RF_PRIM_SPHERE:
            grow_box(lo, hi, p->u.sphere.center, p->u.sphere.radius);
            any = 1;
            break;
        case RF_PRIM_TRIANGLE:
        case RF_PRIM_POLYGON:
            for (int k = 0; k < p->u.poly.count; k++)
                grow_box(lo, hi, scene->vertices[p->u.poly.first + (size_t)k], 0.0);
            any = 1;
            break;
        case RF_PRIM_CONE:
            grow_box(lo, hi, p->u.cone.base, p->u.cone.base_radius);
            grow_box(lo, hi, p->u.cone.apex, p->u.cone.apex_radius);
            any = 1;
            break;
        case RF_PRIM_PLANE:
        case RF_PRIM_TYPE_COUNT:
            break;
        }
    }
    free(memo);
    return any;
}
