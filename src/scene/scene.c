/* refray: the scene model — allocation, the checks of every entity, and the feature analysis
 * (scene.h). */
#include "refray/scene.h"
#include "refray/hash.h"
#include "scene_internal.h"
#include "refray/numeric.h"
#include "refray/transform.h"

#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>


RfStatus rf__msgf(char *msg, size_t msgsz, RfStatus st, const char *fmt, ...)
{
    if (msg && msgsz) {
        va_list ap;
        va_start(ap, fmt);
        vsnprintf(msg, msgsz, fmt, ap);
        va_end(ap);
    }
    return st;
}

static int positive(RfRgb c) { return c.r > 0.0 || c.g > 0.0 || c.b > 0.0; }

const char *rf_shadow_mode_name(RfShadowMode m) { return m == RF_SHADOWS_FILTERED ? "filtered" : "opaque"; }

int rf_shadow_mode_parse(const char *name)
{
    return strcmp(name, "opaque") == 0 ? RF_SHADOWS_OPAQUE : strcmp(name, "filtered") == 0 ? RF_SHADOWS_FILTERED : -1;
}

/* ---- allocation --------------------------------------------------------------------------- */

void rf_scene_init(RfScene *scene)
{
    memset(scene, 0, sizeof *scene);
    scene->source_hash = RF_HASH_INIT;
    scene->render.width = 512;
    scene->render.height = 512;
    scene->render.max_depth = 8;
    scene->render.min_contribution = 0.0;
    scene->render.samples = 1;
    scene->render.sampler = RF_SAMPLER_STRATIFIED;
    scene->render.filter = rf_filter_default(RF_FILTER_BOX);
    scene->render.adaptive_threshold = 0.1;
    scene->render.adaptive_depth = 2;
    scene->render.shutter_open = 0.0;
    scene->render.shutter_close = 1.0;
    scene->camera.d = 1.0;
    scene->camera.fov = 45.0;
    scene->camera.up = rf_vec3(0, 1, 0);
    scene->camera.target = rf_vec3(0, 0, -1);
}

void rf_scene_free(RfScene *scene)
{
    free(scene->materials);
    free(scene->lights);
    free(scene->prims);
    free(scene->vertices);
    free(scene->normals);
    free(scene->objects);
    free(scene->instances);
    free(scene->motions);
    for (size_t i = 0; i < scene->file_count; i++)
        free(scene->files[i]);
    free(scene->files);
    rf_scene_init(scene);
}

/* Makes room for `extra` more elements of size elem (doubling), with overflow checks. */
static RfStatus reserve(void **arr, size_t *cap, size_t count, size_t extra, size_t elem)
{
    if (extra > SIZE_MAX / elem - count)
        return RF_ERR_NOMEM;
    size_t need = count + extra;
    if (need <= *cap)
        return RF_OK;
    size_t cap2 = *cap ? *cap : 16;
    while (cap2 < need)
        cap2 = cap2 > SIZE_MAX / 2 / elem ? need : cap2 * 2;
    void *p = realloc(*arr, cap2 * elem);
    if (!p)
        return RF_ERR_NOMEM;
    *arr = p;
    *cap = cap2;
    return RF_OK;
}

RfMaterial rf_material_default(void)
{
    RfMaterial m;
    memset(&m, 0, sizeof m);
    m.ior = 1.0;
    m.flags = RF_MAT_SMOOTH;
    return m;
}

RfStatus rf_scene_add_material(RfScene *scene, const RfMaterial *m, int *index)
{
    if (scene->material_count >= INT32_MAX)
        return RF_ERR_NOMEM;
    RfStatus st = reserve((void **)&scene->materials, &scene->material_cap, scene->material_count,
                          1, sizeof *m);
    if (st)
        return st;
    scene->materials[scene->material_count] = *m;
    if (index)
        *index = (int)scene->material_count;
    scene->material_count++;
    return RF_OK;
}

RfStatus rf_scene_add_light(RfScene *scene, const RfLight *light)
{
    RfStatus st = reserve((void **)&scene->lights, &scene->light_cap, scene->light_count, 1,
                          sizeof *light);
    if (st)
        return st;
    RfLight *l = &scene->lights[scene->light_count++];
    *l = *light;
    l->direction = rf_vec3_normalize(l->direction);
    return RF_OK;
}

RfStatus rf_scene_add_vertices(RfScene *scene, const RfVec3 *v, const RfVec3 *normals, int n,
                               size_t *first, size_t *nfirst)
{
    size_t k = n > 0 ? (size_t)n : 0;
    RfStatus st = reserve((void **)&scene->vertices, &scene->vertex_cap, scene->vertex_count, k,
                          sizeof *v);
    if (!st && normals)
        st = reserve((void **)&scene->normals, &scene->normal_cap, scene->normal_count, k,
                     sizeof *normals);
    if (st)
        return st;
    *first = scene->vertex_count;
    memcpy(scene->vertices + scene->vertex_count, v, k * sizeof *v);
    scene->vertex_count += k;
    *nfirst = scene->normal_count;
    if (normals) {
        for (size_t i = 0; i < k; i++)
            scene->normals[scene->normal_count + i] = rf_vec3_normalize(normals[i]);
        scene->normal_count += k;
    }
    return RF_OK;
}

RfStatus rf_scene_add_object(RfScene *scene, const char *name, RfSrcLoc loc, int *index)
{
    if (scene->object_count >= INT32_MAX)
        return RF_ERR_NOMEM;
    RfStatus st = reserve((void **)&scene->objects, &scene->object_cap, scene->object_count, 1,
                          sizeof *scene->objects);
    if (st)
        return st;
    RfSceneObject *o = &scene->objects[scene->object_count];
    memset(o, 0, sizeof *o);
    snprintf(o->name, sizeof o->name, "%s", name);
    o->first = scene->prim_count;
    o->loc = loc;
    if (index)
        *index = (int)scene->object_count;
    scene->object_count++;
    return RF_OK;
}

RfStatus rf_scene_add_instance(RfScene *scene, int object, RfMat4 m, size_t *index)
{
    RfInstance in;
    RfMat3 lin_inv;
    in.object = object;
    in.to_world = m;
    if (rf_mat4_inverse(m, &in.to_object) || rf_mat3_inverse(rf_mat4_linear(m), &lin_inv))
        return RF_ERR_SINGULAR;
    in.normal_to_world = rf_mat3_transpose(lin_inv); /* §4.9 n' = (M^-1)^T n */
    in.motion = -1;
    RfStatus st = reserve((void **)&scene->instances, &scene->instance_cap, scene->instance_count,
                          1, sizeof in);
    if (st)
        return st;
    scene->instances[scene->instance_count] = in;
    *index = scene->instance_count++;
    return RF_OK;
}

/* The matrices at one time: M, M^-1, (M^-1)^T of the linear part. */
static RfStatus instance_matrices(RfMat4 m, RfMat4 *to_world, RfMat4 *to_object, RfMat3 *normal)
{
    RfMat3 lin_inv;
    *to_world = m;
    if (rf_mat4_inverse(m, to_object) || rf_mat3_inverse(rf_mat4_linear(m), &lin_inv))
        return RF_ERR_SINGULAR;
    *normal = rf_mat3_transpose(lin_inv);
    return RF_OK;
}

RfStatus rf_motion_at(const RfMotion *mo, double time, RfMat4 *to_world, RfMat4 *to_object, RfMat3 *normal)
{
    RfTransformStep steps[RF_MOTION_MAX_STEPS];
    int k = 0;
    while (k + 1 < mo->key_count && !(time < mo->time[k + 1]))
        k++;
    /* between keyframes k and k+1 (or holding the first or the last one) */
    double s = k + 1 < mo->key_count && time > mo->time[k]
                   ? (time - mo->time[k]) / (mo->time[k + 1] - mo->time[k])
                   : 0.0;
    for (int i = 0; i < mo->step_count; i++) {
        steps[i] = mo->steps[k][i];
        if (s > 0.0)
            for (int j = 0; j < 12; j++)
                steps[i].v[j] = (1.0 - s) * mo->steps[k][i].v[j] + s * mo->steps[k + 1][i].v[j];
    }
    RfMat4 m;
    RfStatus st = rf_transform_steps_matrix(steps, mo->step_count, &m);
    return st != RF_OK ? RF_ERR_SINGULAR : instance_matrices(m, to_world, to_object, normal);
}

RfStatus rf_scene_set_motion(RfScene *scene, size_t index, const RfMotion *mo, char *msg, size_t msgsz)
{
    RfMat4 w, o;
    RfMat3 n;
    if (mo->key_count < 1 || mo->key_count > RF_MOTION_MAX_KEYS || mo->step_count < 0 ||
        mo->step_count > RF_MOTION_MAX_STEPS)
        return rf__msgf(msg, msgsz, RF_ERR_DOMAIN, "motion: 1 to %d keyframes of at most %d steps",
                        RF_MOTION_MAX_KEYS, RF_MOTION_MAX_STEPS);
    for (int k = 0; k < mo->key_count; k++) {
        if (!isfinite(mo->time[k]) || (k > 0 && !(mo->time[k] > mo->time[k - 1])))
            return rf__msgf(msg, msgsz, RF_ERR_DOMAIN, "motion: keyframe times must be finite and increase");
        for (int i = 0; i < mo->step_count; i++) {
            if (mo->steps[k][i].kind != mo->steps[0][i].kind || mo->steps[k][i].axis != mo->steps[0][i].axis)
                return rf__msgf(msg, msgsz, RF_ERR_DOMAIN,
                                "motion: keyframe at %g differs in its steps from the first: keyframes list the same steps",
                                mo->time[k]);
            for (int j = 0; j < 12; j++)
                if (!isfinite(mo->steps[k][i].v[j]))
                    return rf__msgf(msg, msgsz, RF_ERR_DOMAIN, "motion: values must be finite");
        }
        if (rf_motion_at(mo, mo->time[k], &w, &o, &n) != RF_OK)
            return rf__msgf(msg, msgsz, RF_ERR_SINGULAR, "motion: the transform at time %g is singular", mo->time[k]);
    }
    RfStatus st = reserve((void **)&scene->motions, &scene->motion_cap, scene->motion_count, 1, sizeof *mo);
    if (st)
        return rf__msgf(msg, msgsz, st, "out of memory");
    scene->motions[scene->motion_count] = *mo;
    RfInstance *in = &scene->instances[index];
    rf_motion_at(mo, mo->time[0], &in->to_world, &in->to_object, &in->normal_to_world);
    in->motion = (int)scene->motion_count++;
    return RF_OK;
}

int rf_light_is_area(RfLightKind kind)
{
    return kind == RF_LIGHT_RECT || kind == RF_LIGHT_DISC || kind == RF_LIGHT_SPHERE;
}

double rf_light_area(const RfLight *l)
{
    switch (l->kind) {
    case RF_LIGHT_RECT: return rf_vec3_length(rf_vec3_cross(l->edge1, l->edge2));
    case RF_LIGHT_DISC: return RF_PI * l->radius * l->radius;
    case RF_LIGHT_SPHERE: return 4.0 * RF_PI * l->radius * l->radius;
    default: return 0.0;
    }
}

/* ---- checks ------------------------------------------------------------------------------ */

RfVec3 rf__polygon_area_vector(const RfVec3 *v, int n, double *ext2)
{
    RfVec3 sum = rf_vec3(0, 0, 0);
    *ext2 = 0.0;
    for (int i = 1; i < n; i++) {
        RfVec3 a = rf_vec3_sub(v[i], v[0]);
        double d = rf_vec3_dot(a, a); /* finite (checked): no NaN for fmax to guard against */
        *ext2 = d > *ext2 ? d : *ext2;
        if (i + 1 < n)
            sum = rf_vec3_add(sum, rf_vec3_cross(a, rf_vec3_sub(v[i + 1], v[0])));
    }
    return sum;
}

RfStatus rf_scene_check_primitive(const RfScene *scene, const RfPrimitive *p, char *msg,
                                  size_t msgsz)
{
    const char *name = rf_prim_type_name(p->type);
    if (p->type == RF_PRIM_INSTANCE) /* takes its materials from the object's primitives */
        return p->u.instance < scene->instance_count
                   ? RF_OK
                   : rf__msgf(msg, msgsz, RF_ERR_DOMAIN, "instance: index out of bounds");
    if (p->material < 0 || (size_t)p->material >= scene->material_count)
        return rf__msgf(msg, msgsz, RF_ERR_DOMAIN, "%s has no valid material", name);
    switch (p->type) {
    case RF_PRIM_SPHERE:
        if (!rf__finite3(p->u.sphere.center) || !isfinite(p->u.sphere.radius))
            return rf__msgf(msg, msgsz, RF_ERR_DOMAIN, "sphere: values must be finite");
        if (!(p->u.sphere.radius > 0.0))
            return rf__msgf(msg, msgsz, RF_ERR_DEGENERATE,
                        "degenerate sphere: radius must be > 0, found %g",
                        p->u.sphere.radius);
        return RF_OK;
    case RF_PRIM_PLANE:
        if (!rf__finite3(p->u.plane.normal) || !isfinite(p->u.plane.offset))
            return rf__msgf(msg, msgsz, RF_ERR_DOMAIN, "plane: values must be finite");
        if (!(rf_vec3_length(p->u.plane.normal) > 0.0))
            return rf__msgf(msg, msgsz, RF_ERR_DEGENERATE, "degenerate plane: zero normal vector");
        return RF_OK;
    case RF_PRIM_TRIANGLE:
    case RF_PRIM_POLYGON: {
        int n = p->u.poly.count;
        if (n < 3 || (p->type == RF_PRIM_TRIANGLE && n != 3))
            return rf__msgf(msg, msgsz, RF_ERR_DEGENERATE, "%s needs %s3 vertices, found %d", name,
                        p->type == RF_PRIM_TRIANGLE ? "" : "at least ", n);
        if (p->u.poly.first > scene->vertex_count || (size_t)n > scene->vertex_count - p->u.poly.first)
            return rf__msgf(msg, msgsz, RF_ERR_DOMAIN, "%s: vertex range out of bounds", name);
        const RfVec3 *v = scene->vertices + p->u.poly.first;
        for (int i = 0; i < n; i++)
            if (!rf__finite3(v[i]))
                return rf__msgf(msg, msgsz, RF_ERR_DOMAIN, "%s: vertex %d is not finite", name, i + 1);
        double ext2;
        RfVec3 nv = rf__polygon_area_vector(v, n, &ext2);
        if (!(rf_vec3_length(nv) > RF_SCENE_DEGENERATE_REL * ext2))
            return rf__msgf(msg, msgsz, RF_ERR_DEGENERATE,
                        "degenerate %s: its vertices are collinear (zero area)", name);
        if (p->flags & RF_PRIM_VERTEX_NORMALS) {
            if (p->u.poly.nfirst > scene->normal_count ||
                (size_t)n > scene->normal_count - p->u.poly.nfirst)
                return rf__msgf(msg, msgsz, RF_ERR_DOMAIN, "%s: normal range out of bounds", name);
            const RfVec3 *vn = scene->normals + p->u.poly.nfirst;
            for (int i = 0; i < n; i++)
                if (!rf__finite3(vn[i]) || !(rf_vec3_length(vn[i]) > 0.0))
                    return rf__msgf(msg, msgsz, RF_ERR_DEGENERATE,
                                "%s: normal of vertex %d has zero length", name, i + 1);
        }
        return RF_OK;
    }
    case RF_PRIM_CONE: {
        double rb = p->u.cone.base_radius, ra = p->u.cone.apex_radius;
        if (!rf__finite3(p->u.cone.base) || !rf__finite3(p->u.cone.apex) || !isfinite(rb) || !isfinite(ra))
            return rf__msgf(msg, msgsz, RF_ERR_DOMAIN, "cone: values must be finite");
        if (rb < 0.0 || ra < 0.0)
            return rf__msgf(msg, msgsz, RF_ERR_DOMAIN, "cone radii must be >= 0");
        if (!(rf_vec3_length(rf_vec3_sub(p->u.cone.apex, p->u.cone.base)) > 0.0))
            return rf__msgf(msg, msgsz, RF_ERR_DEGENERATE, "degenerate cone: base and apex coincide");
        if (!(rb > 0.0 || ra > 0.0))
            return rf__msgf(msg, msgsz, RF_ERR_DEGENERATE, "degenerate cone: both radii are zero");
        return RF_OK;
    }
    case RF_PRIM_INSTANCE:
    case RF_PRIM_TYPE_COUNT:
        break;
    }
    return rf__msgf(msg, msgsz, RF_ERR_DOMAIN, "unknown primitive type %d", (int)p->type);
}

/* 0 when some corner turns against the polygon's normal: the SPD gears' faces are not convex
 * although NFF promises convex polygons, so the intersector needs this hint. */
static int polygon_is_convex(const RfVec3 *v, int n)
{
    double ext2;
    RfVec3 nv = rf__polygon_area_vector(v, n, &ext2);
    double tol = RF_SCENE_DEGENERATE_REL * rf_vec3_length(nv) * ext2;
    for (int i = 0; i < n; i++) {
        RfVec3 e0 = rf_vec3_sub(v[(i + 1) % n], v[i]);
        RfVec3 e1 = rf_vec3_sub(v[(i + 2) % n], v[(i + 1) % n]);
        if (rf_vec3_dot(rf_vec3_cross(e0, e1), nv) < -tol)
            return 0;
    }
    return 1;
}

/* A checked primitive into its slot q: planes normalised, polygons marked non-convex. */
static void store_primitive(const RfScene *scene, RfPrimitive *q, const RfPrimitive *p)
{
    *q = *p;
    q->flags &= ~(unsigned)RF_PRIM_NONCONVEX;
    if (q->type == RF_PRIM_PLANE) {
        double len = rf_vec3_length(q->u.plane.normal);
        q->u.plane.normal = rf_vec3_scale(q->u.plane.normal, 1.0 / len);
        q->u.plane.offset /= len;
    }
    if (q->type == RF_PRIM_POLYGON &&
        !polygon_is_convex(scene->vertices + q->u.poly.first, q->u.poly.count))
        q->flags |= RF_PRIM_NONCONVEX;
}

RfStatus rf_scene_add_primitive(RfScene *scene, const RfPrimitive *p, char *msg, size_t msgsz)
{
    RfStatus st = rf_scene_check_primitive(scene, p, msg, msgsz);
    if (st)
        return st;
    st = reserve((void **)&scene->prims, &scene->prim_cap, scene->prim_count, 1, sizeof *p);
    if (st)
        return rf__msgf(msg, msgsz, st, "out of memory");
    store_primitive(scene, &scene->prims[scene->prim_count++], p);
    return RF_OK;
}

RfStatus rf__scene_put_primitive(RfScene *scene, size_t index, const RfPrimitive *p, char *msg, size_t msgsz)
{
    RfStatus st = rf_scene_check_primitive(scene, p, msg, msgsz);
    if (!st)
        store_primitive(scene, &scene->prims[index], p);
    return st;
}

RfStatus rf__scene_reserve(RfScene *scene, size_t prims, size_t vertices, size_t normals)
{
    RfStatus st = reserve((void **)&scene->prims, &scene->prim_cap, scene->prim_count, prims, sizeof *scene->prims);
    if (!st)
        st = reserve((void **)&scene->vertices, &scene->vertex_cap, scene->vertex_count, vertices,
                      sizeof *scene->vertices);
    if (!st)
        st = reserve((void **)&scene->normals, &scene->normal_cap, scene->normal_count, normals,
                      sizeof *scene->normals);
    return st;
}

RfStatus rf_scene_camera_check(const RfSceneCamera *cam, RfSrcLoc *loc, char *msg, size_t msgsz)
{
    *loc = cam->loc;
    if (!rf__finite3(cam->eye) || !rf__finite3(cam->target) || !rf__finite3(cam->up))
        return rf__msgf(msg, msgsz, RF_ERR_DOMAIN, "camera: values must be finite");
    RfVec3 dir = rf_vec3_sub(cam->target, cam->eye);
    double ld = rf_vec3_length(dir), lu = rf_vec3_length(cam->up);
    if (!(ld > 0.0)) {
        *loc = cam->target_loc;
        return rf__msgf(msg, msgsz, RF_ERR_DEGENERATE, "camera: eye and target coincide");
    }
    if (!(lu > 0.0)) {
        *loc = cam->up_loc;
        return rf__msgf(msg, msgsz, RF_ERR_DEGENERATE, "camera: up vector has zero length");
    }
    if (!(rf_vec3_length(rf_vec3_cross(dir, cam->up)) > RF_SCENE_DEGENERATE_REL * ld * lu)) {
        *loc = cam->up_loc;
        return rf__msgf(msg, msgsz, RF_ERR_DEGENERATE,
                    "camera: up vector is parallel to the view direction");
    }
    if (!(cam->d > 0.0) || !isfinite(cam->d))
        return rf__msgf(msg, msgsz, RF_ERR_DOMAIN, "camera: image-plane distance d must be > 0");
    if (!(cam->hither >= 0.0) || !isfinite(cam->hither))
        return rf__msgf(msg, msgsz, RF_ERR_DOMAIN, "camera: hither must be >= 0");
    if (cam->has_window) {
        if (!isfinite(cam->l) || !isfinite(cam->r) || !isfinite(cam->b) || !isfinite(cam->t) ||
            !(cam->l < cam->r) || !(cam->b < cam->t))
            return rf__msgf(msg, msgsz, RF_ERR_DOMAIN, "camera: window needs l < r and b < t");
    } else if (!(cam->fov > 0.0 && cam->fov < 180.0)) {
        return rf__msgf(msg, msgsz, RF_ERR_DOMAIN, "camera: field of view must be in (0, 180) degrees");
    }
    if (!(cam->aperture >= 0.0) || !isfinite(cam->aperture) ||
        (cam->aperture > 0.0 && (!(cam->focus > 0.0) || !isfinite(cam->focus))))
        return rf__msgf(msg, msgsz, RF_ERR_DOMAIN, "camera: needs aperture >= 0 and, with a lens, focus > 0");
    return RF_OK;
}

RfWindow rf_scene_camera_window(const RfSceneCamera *cam, int width, int height)
{
    RfWindow w;
    w.d = cam->d;
    if (cam->has_window) {
        w.l = cam->l;
        w.r = cam->r;
        w.b = cam->b;
        w.t = cam->t;
        return w;
    }
    double t = cam->d * tan(cam->fov * (RF_PI / 360.0));
    if (cam->fov_reading == RF_FOV_PIXEL_CENTRES && height > 1)
        t *= (double)height / (double)(height - 1); /* centre-to-centre span is H - 1 pixels */
    w.t = t;
    w.b = -t;
    w.r = t * (double)width / (double)height;
    w.l = -w.r;
    return w;
}

int rf_material_has_highlight(const RfMaterial *m)
{
    /* r.v <= 1 + 10u for unit n, l, v, so pow(r.v, n) <= e^1.1 for n <= 1e15: with ks = 0 the
     * term is then (0 * I) * finite, a zero of the same sign as with pow replaced by 0 */
    return positive(m->ks) || m->shininess > 1e15;
}

/* ---- analysis ---------------------------------------------------------------------------- */

unsigned rf_scene_features(const RfScene *scene)
{
    unsigned f = 0;
    unsigned char *used = calloc(scene->material_count ? scene->material_count : 1, 1);
    for (size_t i = 0; i < scene->prim_count; i++) {
        const RfPrimitive *p = &scene->prims[i];
        if (p->material < 0 || (size_t)p->material >= scene->material_count)
            continue;
        if (used)
            used[p->material] = 1;
        if ((p->flags & RF_PRIM_VERTEX_NORMALS) &&
            (scene->materials[p->material].flags & RF_MAT_SMOOTH))
            f |= RF_FEAT_VERTEX_NORMALS;
    }
    for (size_t i = 0; i < scene->material_count; i++) {
        const RfMaterial *m = &scene->materials[i];
        if (used && !used[i])
            continue;
        if (positive(m->kr))
            f |= RF_FEAT_REFLECTION;
        if (positive(m->kt))
            f |= RF_FEAT_TRANSMISSION;
        if ((m->flags & RF_MAT_FRESNEL) && (positive(m->kr) || positive(m->kt)))
            f |= RF_FEAT_FRESNEL;
        if (rf_material_has_highlight(m))
            f |= RF_FEAT_SPECULAR;
        if (positive(rf_rgb_mul(m->ka, scene->render.ambient)))
            f |= RF_FEAT_AMBIENT;
        if (positive(m->emission))
            f |= RF_FEAT_EMISSION;
        if (m->gloss > 0.0 && (positive(m->kr) || positive(m->kt)))
            f |= RF_FEAT_GLOSSY;
    }
    free(used);
    for (size_t i = 0; i < scene->instance_count; i++)
        if (scene->instances[i].motion >= 0)
            f |= RF_FEAT_MOTION;
    if (scene->camera.aperture > 0.0)
        f |= RF_FEAT_APERTURE;
    for (size_t i = 0; i < scene->light_count; i++) {
        const RfLight *l = &scene->lights[i];
        if (l->kind != RF_LIGHT_DIRECTIONAL && l->falloff == RF_FALLOFF_INVERSE_SQUARE)
            f |= RF_FEAT_LIGHT_FALLOFF;
        if (l->kind == RF_LIGHT_SPOT)
            f |= RF_FEAT_SPOT_LIGHTS;
        if (rf_light_is_area(l->kind))
            f |= RF_FEAT_AREA_LIGHTS;
    }
    return f;
}

const char *rf_feature_name(unsigned bit)
{
    switch (bit) {
    case RF_FEAT_REFLECTION: return "reflection";
    case RF_FEAT_TRANSMISSION: return "transmission";
    case RF_FEAT_FRESNEL: return "fresnel";
    case RF_FEAT_SPECULAR: return "specular";
    case RF_FEAT_AMBIENT: return "ambient";
    case RF_FEAT_EMISSION: return "emission";
    case RF_FEAT_VERTEX_NORMALS: return "vertex-normals";
    case RF_FEAT_LIGHT_FALLOFF: return "light-falloff";
    case RF_FEAT_SPOT_LIGHTS: return "spot-lights";
    case RF_FEAT_AREA_LIGHTS: return "area-lights";
    case RF_FEAT_MOTION: return "motion";
    case RF_FEAT_APERTURE: return "aperture";
    case RF_FEAT_GLOSSY: return "glossy";
    }
    return NULL;
}

const char *rf_prim_type_name(RfPrimType type)
{
    switch (type) {
    case RF_PRIM_SPHERE: return "sphere";
    case RF_PRIM_PLANE: return "plane";
    case RF_PRIM_TRIANGLE: return "triangle";
    case RF_PRIM_POLYGON: return "polygon";
    case RF_PRIM_CONE: return "cone";
    case RF_PRIM_INSTANCE: return "instance";
    case RF_PRIM_TYPE_COUNT: break;
    }
    return "primitive";
}

const char *rf_light_kind_name(RfLightKind kind)
{
    switch (kind) {
    case RF_LIGHT_POINT: return "point";
    case RF_LIGHT_DIRECTIONAL: return "directional";
    case RF_LIGHT_SPOT: return "spot";
    case RF_LIGHT_RECT: return "rect";
    case RF_LIGHT_DISC: return "disc";
    case RF_LIGHT_SPHERE: return "sphere";
    case RF_LIGHT_KIND_COUNT: break;
    }
    return "light";
}
