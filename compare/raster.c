/* The OpenGL rasterizer of the comparator (raster.h). GL 4.5 core, every entry point loaded
 * through the context back end (gl_context.h), so this file knows nothing of OSMesa. */
#include "raster.h"

/* what the rasterizer expands at most (it has no GPU instancing) */
#define RF_RASTER_MAX_TRIANGLES 50000000
#define RF_RASTER_MAX_PLACEMENTS 5000000

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <GL/glcorearb.h>

#include "refray/geometry.h"
#include "refray/transform.h"
#include "shaders.h"

#define RF_GL_FUNCS(X)                                                                          \
    X(PFNGLGETERRORPROC, GetError) X(PFNGLGETSTRINGPROC, GetString)                             \
    X(PFNGLGENFRAMEBUFFERSPROC, GenFramebuffers) X(PFNGLBINDFRAMEBUFFERPROC, BindFramebuffer)   \
    X(PFNGLDELETEFRAMEBUFFERSPROC, DeleteFramebuffers)                                          \
    X(PFNGLGENRENDERBUFFERSPROC, GenRenderbuffers) X(PFNGLBINDRENDERBUFFERPROC, BindRenderbuffer) \
    X(PFNGLDELETERENDERBUFFERSPROC, DeleteRenderbuffers)                                        \
    X(PFNGLRENDERBUFFERSTORAGEPROC, RenderbufferStorage)                                        \
    X(PFNGLFRAMEBUFFERRENDERBUFFERPROC, FramebufferRenderbuffer)                                \
    X(PFNGLCHECKFRAMEBUFFERSTATUSPROC, CheckFramebufferStatus) X(PFNGLDRAWBUFFERSPROC, DrawBuffers) \
    X(PFNGLVIEWPORTPROC, Viewport) X(PFNGLCLIPCONTROLPROC, ClipControl)                         \
    X(PFNGLCLEARBUFFERFVPROC, ClearBufferfv) X(PFNGLENABLEPROC, Enable) X(PFNGLDISABLEPROC, Disable) \
    X(PFNGLDEPTHFUNCPROC, DepthFunc) X(PFNGLCREATESHADERPROC, CreateShader)                     \
    X(PFNGLSHADERSOURCEPROC, ShaderSource) X(PFNGLCOMPILESHADERPROC, CompileShader)             \
    X(PFNGLGETSHADERIVPROC, GetShaderiv) X(PFNGLGETSHADERINFOLOGPROC, GetShaderInfoLog)         \
    X(PFNGLDELETESHADERPROC, DeleteShader) X(PFNGLCREATEPROGRAMPROC, CreateProgram)             \
    X(PFNGLATTACHSHADERPROC, AttachShader) X(PFNGLLINKPROGRAMPROC, LinkProgram)                 \
    X(PFNGLGETPROGRAMIVPROC, GetProgramiv) X(PFNGLGETPROGRAMINFOLOGPROC, GetProgramInfoLog)     \
    X(PFNGLDELETEPROGRAMPROC, DeleteProgram) X(PFNGLUSEPROGRAMPROC, UseProgram)                 \
    X(PFNGLGENBUFFERSPROC, GenBuffers) X(PFNGLBINDBUFFERPROC, BindBuffer)                       \
    X(PFNGLBUFFERDATAPROC, BufferData) X(PFNGLBINDBUFFERBASEPROC, BindBufferBase)               \
    X(PFNGLDELETEBUFFERSPROC, DeleteBuffers) X(PFNGLGENVERTEXARRAYSPROC, GenVertexArrays)       \
    X(PFNGLBINDVERTEXARRAYPROC, BindVertexArray) X(PFNGLDELETEVERTEXARRAYSPROC, DeleteVertexArrays) \
    X(PFNGLDRAWARRAYSPROC, DrawArrays) X(PFNGLDRAWARRAYSINSTANCEDPROC, DrawArraysInstanced)     \
    X(PFNGLGETUNIFORMLOCATIONPROC, GetUniformLocation) X(PFNGLUNIFORM1IPROC, Uniform1i)         \
    X(PFNGLUNIFORM2FPROC, Uniform2f) X(PFNGLUNIFORM3FPROC, Uniform3f)                           \
    X(PFNGLUNIFORM1DPROC, Uniform1d) X(PFNGLUNIFORM3DPROC, Uniform3d) X(PFNGLUNIFORM4DPROC, Uniform4d) \
    X(PFNGLREADBUFFERPROC, ReadBuffer) X(PFNGLREADPIXELSPROC, ReadPixels)                       \
    X(PFNGLPIXELSTOREIPROC, PixelStorei) X(PFNGLFINISHPROC, Finish)

typedef struct {
#define RF_GL_FIELD(type, name) type name;
    RF_GL_FUNCS(RF_GL_FIELD)
#undef RF_GL_FIELD
} Gl;

static int gl_load(Gl *gl, RfGlProc (*proc)(void *, const char *), void *ctx, char *err, size_t errsz)
{
#define RF_GL_LOAD(type, name)                                                                  \
    if (!(gl->name = (type)proc(ctx, "gl" #name))) {                                            \
        snprintf(err, errsz, "GL entry point gl%s is missing", #name);                          \
        return 0;                                                                               \
    }
    RF_GL_FUNCS(RF_GL_LOAD)
#undef RF_GL_LOAD
    return 1;
}

/* ---- scene -> GPU arrays ---- */

typedef struct {
    double *trid;  /* 12 per triangle */
    float *trin;   /* 9 per triangle */
    int *trii;     /* 4 per triangle */
    size_t ntri, tri_cap;
    double *quad;  /* 8 per quadric */
    int *quai;     /* 4 per quadric */
    size_t nquad;
} Geometry;

static RfVec3 pvert(const RfScene *s, const RfPrimitive *p, int k)
{
    return s->vertices[p->u.poly.first + (size_t)k];
}

int rf_raster_triangulate(const RfScene *s, const RfPrimitive *p, int *out)
{
    int n = p->u.poly.count;
    if (p->type != RF_PRIM_POLYGON || !(p->flags & RF_PRIM_NONCONVEX)) {
        for (int k = 0; k + 2 < n; k++) { /* the tracer's fan: v0, v(k+1), v(k+2) */
            out[3 * k] = 0;
            out[3 * k + 1] = k + 1;
            out[3 * k + 2] = k + 2;
        }
        return n - 2;
    }
    return rf_triangulate_polygon(s->vertices + p->u.poly.first, n, out);
}

/* Where the primitives being emitted sit: the world (identity), or an instance with M (object ->
 * world), M^-1 and the normal matrix (M^-1)^T, composed through nested instances (§4.8, §4.9). */
typedef struct {
    int instanced;
    RfMat4 to_world, to_object;
    RfMat3 nmat;
} Place;

static RfVec3 place_point(const Place *pl, RfVec3 p)
{
    RfVec3 q = p;
    if (pl->instanced && rf_transform_point(pl->to_world, p, &q) != RF_OK)
        q = p;
    return q;
}

/* a normal from the primitive's space to the world, not normalised (vertex normals are
 * interpolated before normalising, as the tracer does in object space) */
static RfVec3 place_normal(const Place *pl, RfVec3 n)
{
    return pl->instanced ? rf_mat3_mul_vec(pl->nmat, n) : n;
}

static int add_triangle(Geometry *g, const RfScene *s, const RfPrimitive *p, const int *k, RfVec3 n,
                        const Place *pl, int sides)
{
    if (g->ntri == g->tri_cap) {
        size_t cap = g->tri_cap ? 2 * g->tri_cap : 1024;
        double *d = realloc(g->trid, sizeof *d * 12 * cap);
        if (d)
            g->trid = d;
        float *f = realloc(g->trin, sizeof *f * 9 * cap);
        if (f)
            g->trin = f;
        int *i = realloc(g->trii, sizeof *i * 4 * cap);
        if (i)
            g->trii = i;
        if (!d || !f || !i)
            return 0;
        g->tri_cap = cap;
    }
    double *d = g->trid + 12 * g->ntri;
    float *f = g->trin + 9 * g->ntri;
    int *ii = g->trii + 4 * g->ntri;
    const RfMaterial *m = &s->materials[p->material];
    int smooth = (p->flags & RF_PRIM_VERTEX_NORMALS) && (m->flags & RF_MAT_SMOOTH) &&
                 !(p->type == RF_PRIM_POLYGON && (p->flags & RF_PRIM_NONCONVEX));
    for (int j = 0; j < 3; j++) {
        RfVec3 q = place_point(pl, pvert(s, p, k[j]));
        RfVec3 vn = (p->flags & RF_PRIM_VERTEX_NORMALS) ? place_normal(pl, s->normals[p->u.poly.nfirst + (size_t)k[j]]) : n;
        d[3 * j] = q.x, d[3 * j + 1] = q.y, d[3 * j + 2] = q.z;
        f[3 * j] = (float)vn.x, f[3 * j + 1] = (float)vn.y, f[3 * j + 2] = (float)vn.z;
    }
    d[9] = n.x, d[10] = n.y, d[11] = n.z;
    ii[0] = p->material;
    ii[1] = sides;
    ii[2] = smooth;
    ii[3] = 0;
    g->ntri++;
    return 1;
}

typedef struct {
    const RfScene *s;
    Geometry *g;
    RfVec3 eye;
    double near;
    int *tris, cap;
    size_t quad_cap;
    int two_sided; /* RfRasterOptions.two_sided */
} Builder;

/* The shaders' flags word of p (1: seen from both sides, 2: only from inside): the scene's, or
 * both sides for every surface with RfRasterOptions.two_sided, as the tracer's option does. */
static int side_flags(const Builder *b, const RfPrimitive *p)
{
    return b->two_sided ? (int)RF_PRIM_TWO_SIDED : (int)(p->flags & (RF_PRIM_TWO_SIDED | RF_PRIM_INSIDE));
}

static RfStatus add_polygon(Builder *b, const RfPrimitive *p, const Place *pl)
{
    int n = p->u.poly.count;
    if (3 * (n - 2) > b->cap) {
        int *t = realloc(b->tris, sizeof *t * 3 * (size_t)(n - 2));
        if (!t)
            return RF_ERR_NOMEM;
        b->tris = t, b->cap = 3 * (n - 2);
    }
    int nt = rf_raster_triangulate(b->s, p, b->tris);
    if (nt < 0)
        return RF_ERR_NOMEM;
    for (int k = 0; k < nt; k++) {
        const int *t = b->tris + 3 * k;
        /* the tracer's geometric normal: its triangle's (a fan's or an ear-clipped one's), in the
         * primitive's space, taken to the world by the normal matrix */
        RfVec3 v0 = pvert(b->s, p, t[0]), v1 = pvert(b->s, p, t[1]), v2 = pvert(b->s, p, t[2]);
        RfVec3 n = rf_vec3_normalize(rf_vec3_cross(rf_vec3_sub(v1, v0), rf_vec3_sub(v2, v0)));
        if (pl->instanced)
            n = rf_vec3_normalize(place_normal(pl, n));
        if (!add_triangle(b->g, b->s, p, t, n, pl, side_flags(b, p)))
            return RF_ERR_NOMEM;
    }
    return RF_OK;
}

static RfStatus add_quadric(Builder *b, const RfPrimitive *p, const Place *pl)
{
    Geometry *g = b->g;
    if (g->nquad == b->quad_cap) {
        size_t cap = b->quad_cap ? 2 * b->quad_cap : 256;
        double *d = realloc(g->quad, sizeof *d * 40 * cap);
        if (d)
            g->quad = d;
        int *i = realloc(g->quai, sizeof *i * 4 * cap);
        if (i)
            g->quai = i;
        if (!d || !i)
            return RF_ERR_NOMEM;
        b->quad_cap = cap;
    }
    double *d = g->quad + 40 * g->nquad;
    int *q = g->quai + 4 * g->nquad;
    RfVec3 lo, hi;
    memset(d, 0, sizeof *d * 40);
    if (p->type == RF_PRIM_SPHERE) {
        RfSphere sp = p->u.sphere;
        d[0] = sp.center.x, d[1] = sp.center.y, d[2] = sp.center.z, d[3] = sp.radius;
        lo = rf_vec3_sub(sp.center, rf_vec3(sp.radius, sp.radius, sp.radius));
        hi = rf_vec3_add(sp.center, rf_vec3(sp.radius, sp.radius, sp.radius));
        q[0] = 0;
    } else if (p->type == RF_PRIM_CONE) {
        RfCone c = p->u.cone;
        double r = fmax(c.base_radius, c.apex_radius);
        d[0] = c.base.x, d[1] = c.base.y, d[2] = c.base.z, d[3] = c.base_radius;
        d[4] = c.apex.x, d[5] = c.apex.y, d[6] = c.apex.z, d[7] = c.apex_radius;
        lo = rf_vec3(fmin(c.base.x, c.apex.x) - r, fmin(c.base.y, c.apex.y) - r, fmin(c.base.z, c.apex.z) - r);
        hi = rf_vec3(fmax(c.base.x, c.apex.x) + r, fmax(c.base.y, c.apex.y) + r, fmax(c.base.z, c.apex.z) + r);
        q[0] = 1;
    } else {
        d[0] = p->u.plane.normal.x, d[1] = p->u.plane.normal.y, d[2] = p->u.plane.normal.z;
        d[3] = p->u.plane.offset;
        q[0] = 2;
        lo = hi = b->eye;
    }
    if (pl->instanced && p->type != RF_PRIM_PLANE) { /* the world box of the 8 corners */
        RfVec3 wl = rf_vec3(INFINITY, INFINITY, INFINITY), wh = rf_vec3(-INFINITY, -INFINITY, -INFINITY);
        for (int c = 0; c < 8; c++) {
            RfVec3 w = place_point(pl, rf_vec3(c & 1 ? hi.x : lo.x, c & 2 ? hi.y : lo.y, c & 4 ? hi.z : lo.z));
            wl = rf_vec3(fmin(wl.x, w.x), fmin(wl.y, w.y), fmin(wl.z, w.z));
            wh = rf_vec3(fmax(wh.x, w.x), fmax(wh.y, w.y), fmax(wh.z, w.z));
        }
        lo = wl, hi = wh;
    }
    d[8] = lo.x, d[9] = lo.y, d[10] = lo.z, d[11] = hi.x, d[12] = hi.y, d[13] = hi.z;
    if (pl->instanced) {
        for (int r = 0; r < 3; r++)
            for (int c = 0; c < 4; c++)
                d[14 + 4 * r + c] = pl->to_object.m[r][c];
        for (int r = 0; r < 3; r++)
            for (int c = 0; c < 3; c++)
                d[26 + 3 * r + c] = pl->nmat.m[r][c];
    }
    q[1] = side_flags(b, p);
    q[2] = p->material;
    /* full screen for planes, and when the near plane could cut the (padded) box: the box would
     * lose the fragments in front of the eye */
    double pad = 2.0 * b->near + 0.01 * rf_vec3_length(rf_vec3_sub(hi, lo));
    RfVec3 e = b->eye;
    q[3] = (p->type == RF_PRIM_PLANE || (e.x > lo.x - pad && e.x < hi.x + pad && e.y > lo.y - pad &&
                                         e.y < hi.y + pad && e.z > lo.z - pad && e.z < hi.z + pad)) |
           (pl->instanced ? 2 : 0);
    g->nquad++;
    return RF_OK;
}

/* Emits prims[first, first + count) placed by pl; instances recurse into their objects (the
 * graph is a DAG, rf_scene_graph_check; the depth guard only stops a corrupt one). */
static RfStatus emit(Builder *b, size_t first, size_t count, int world, const Place *pl, int depth)
{
    const RfScene *s = b->s;
    RfStatus st = RF_OK;
    for (size_t i = first; i < first + count && st == RF_OK; i++) {
        const RfPrimitive *p = &s->prims[i];
        if (world && (p->flags & RF_PRIM_IN_OBJECT))
            continue;
        switch (p->type) {
        case RF_PRIM_TRIANGLE:
        case RF_PRIM_POLYGON:
            st = add_polygon(b, p, pl);
            break;
        case RF_PRIM_SPHERE:
        case RF_PRIM_CONE:
        case RF_PRIM_PLANE:
            st = add_quadric(b, p, pl);
            break;
        case RF_PRIM_INSTANCE: {
            const RfInstance *in = &s->instances[p->u.instance];
            if (depth > 64 || in->object < 0 || (size_t)in->object >= s->object_count)
                return RF_ERR_DOMAIN;
            Place inner;
            inner.instanced = 1;
            inner.to_world = pl->instanced ? rf_mat4_mul(pl->to_world, in->to_world) : in->to_world;
            inner.to_object = pl->instanced ? rf_mat4_mul(in->to_object, pl->to_object) : in->to_object;
            inner.nmat = pl->instanced ? rf_mat3_mul(pl->nmat, in->normal_to_world) : in->normal_to_world;
            const RfSceneObject *ob = &s->objects[in->object];
            st = emit(b, ob->first, ob->count, 0, &inner, depth + 1);
            break;
        }
        default:
            break;
        }
    }
    return st;
}

static RfStatus build_geometry(const RfScene *s, Geometry *g, RfVec3 eye, double near, int two_sided)
{
    Builder b;
    Place world;
    memset(g, 0, sizeof *g);
    memset(&b, 0, sizeof b);
    memset(&world, 0, sizeof world);
    b.s = s, b.g = g, b.eye = eye, b.near = near, b.two_sided = two_sided;
    RfStatus st = emit(&b, 0, s->prim_count, 1, &world, 0);
    free(b.tris);
    return st;
}

static void free_geometry(Geometry *g)
{
    free(g->trid), free(g->trin), free(g->trii), free(g->quad), free(g->quai);
}

/* ---- GL objects ---- */

static GLuint compile(const Gl *gl, const char *vs, const char *fs, char *err, size_t errsz)
{
    GLenum kinds[2] = {GL_VERTEX_SHADER, GL_FRAGMENT_SHADER};
    const char *srcs[2] = {vs, fs};
    GLuint prog = gl->CreateProgram();
    char log[2048];
    for (int i = 0; i < 2; i++) {
        GLuint sh = gl->CreateShader(kinds[i]);
        const GLchar *parts[2] = {rf_glsl_common, srcs[i]};
        GLint ok = 0;
        gl->ShaderSource(sh, 2, parts, NULL);
        gl->CompileShader(sh);
        gl->GetShaderiv(sh, GL_COMPILE_STATUS, &ok);
        if (!ok) {
            gl->GetShaderInfoLog(sh, sizeof log, NULL, log);
            log[strcspn(log, "\n")] = 0;
            snprintf(err, errsz, "GLSL %s shader: %s", i ? "fragment" : "vertex", log);
            gl->DeleteShader(sh);
            gl->DeleteProgram(prog);
            return 0;
        }
        gl->AttachShader(prog, sh);
        gl->DeleteShader(sh);
    }
    GLint ok = 0;
    gl->LinkProgram(prog);
    gl->GetProgramiv(prog, GL_LINK_STATUS, &ok);
    if (!ok) {
        gl->GetProgramInfoLog(prog, sizeof log, NULL, log);
        log[strcspn(log, "\n")] = 0;
        snprintf(err, errsz, "GLSL link: %s", log);
        gl->DeleteProgram(prog);
        return 0;
    }
    return prog;
}

typedef struct {
    RfVec3 eye;
    RfCameraBasis basis;
    RfWindow win;
    double near, hither;
    int width, height, mode;
    RfRgb ambient;
    int lights;
} View;

static void set_uniforms(const Gl *gl, GLuint prog, const View *vw)
{
    gl->UseProgram(prog);
#define LOC(name) gl->GetUniformLocation(prog, name)
    gl->Uniform3d(LOC("u_eye"), vw->eye.x, vw->eye.y, vw->eye.z);
    gl->Uniform3d(LOC("u_u"), vw->basis.u.x, vw->basis.u.y, vw->basis.u.z);
    gl->Uniform3d(LOC("u_v"), vw->basis.v.x, vw->basis.v.y, vw->basis.v.z);
    gl->Uniform3d(LOC("u_w"), vw->basis.w.x, vw->basis.w.y, vw->basis.w.z);
    gl->Uniform4d(LOC("u_win"), vw->win.l, vw->win.r, vw->win.b, vw->win.t);
    gl->Uniform1d(LOC("u_d"), vw->win.d);
    gl->Uniform1d(LOC("u_near"), vw->near);
    gl->Uniform1d(LOC("u_hither"), vw->hither);
    gl->Uniform2f(LOC("u_size"), (float)vw->width, (float)vw->height);
    gl->Uniform1i(LOC("u_light_count"), vw->lights);
    gl->Uniform1i(LOC("u_mode"), vw->mode);
    gl->Uniform3f(LOC("u_ambient"), (float)vw->ambient.r, (float)vw->ambient.g, (float)vw->ambient.b);
#undef LOC
}

static GLuint ssbo(const Gl *gl, GLuint index, const void *data, size_t bytes)
{
    GLuint b;
    static const float dummy[8] = {0}; /* an empty array still needs a bound buffer */
    gl->GenBuffers(1, &b);
    gl->BindBuffer(GL_SHADER_STORAGE_BUFFER, b);
    gl->BufferData(GL_SHADER_STORAGE_BUFFER, (GLsizeiptr)(bytes ? bytes : sizeof dummy),
                   bytes ? data : dummy, GL_STATIC_DRAW);
    gl->BindBufferBase(GL_SHADER_STORAGE_BUFFER, index, b);
    return b;
}

/* the near plane: the tracer's hither plane (a distance along the view axis, tracer.c: primary
 * rays start there), which is exactly GL's near plane; the fragment shaders apply it to the
 * impostors' roots too. Without hither: 1e-6 of the scene's size (reversed float Z keeps its
 * relative precision at any near distance). */
static double near_plane(const RfScene *s, const View *vw)
{
    RfVec3 lo, hi;
    double size = rf_scene_bounds(s, &lo, &hi) ? rf_vec3_length(rf_vec3_sub(hi, lo)) +
                                                     rf_vec3_length(rf_vec3_sub(vw->eye, lo))
                                               : 1.0;
    double tiny = 1e-6 * (size > 0.0 ? size : 1.0);
    return vw->hither > 0.0 ? vw->hither : tiny;
}

RfStatus rf_raster_render(const RfScene *s, const RfRasterOptions *opt,
                          RfGlProc (*proc)(void *ctx, const char *name), void *proc_ctx,
                          RfImage *color, RfImage *depth, char *err, size_t errsz)
{
    Gl gl;
    View vw;
    Geometry g;
    RfStatus st = RF_OK;
    memset(color, 0, sizeof *color);
    if (depth)
        memset(depth, 0, sizeof *depth);
    if (!s->has_camera) {
        snprintf(err, errsz, "the scene has no camera");
        return RF_ERR_DOMAIN;
    }
    /* the rasterizer draws every placement (no instancing on the GPU side): refuse a graph that
     * expands beyond what it could draw, before expanding it */
    RfTriangleCount tc = rf_scene_triangle_count(s);
    if (tc.rendered > RF_RASTER_MAX_TRIANGLES || tc.instances_rendered > RF_RASTER_MAX_PLACEMENTS) {
        snprintf(err, errsz,
                 "the scene graph expands to %zu triangles in %zu placements: more than the rasterizer draws "
                 "(%d triangles, %d placements)",
                 tc.rendered, tc.instances_rendered, RF_RASTER_MAX_TRIANGLES, RF_RASTER_MAX_PLACEMENTS);
        return RF_ERR_DOMAIN;
    }
    for (size_t i = 0; i < s->light_count; i++)
        if (rf_light_is_area(s->lights[i].kind)) { /* §3.10: no OpenGL counterpart to compare with */
            snprintf(err, errsz, "%s light (line %d): the rasterizer has point, directional and spot lights only",
                     rf_light_kind_name(s->lights[i].kind), s->lights[i].loc.line);
            return RF_ERR_DOMAIN;
        }
    memset(&vw, 0, sizeof vw);
    vw.width = opt->width > 0 ? opt->width : s->render.width;
    vw.height = opt->height > 0 ? opt->height : s->render.height;
    vw.mode = (int)opt->mode;
    vw.eye = s->camera.eye;
    vw.win = rf_scene_camera_window(&s->camera, vw.width, vw.height);
    vw.hither = s->camera.hither;
    vw.ambient = s->render.ambient;
    vw.lights = (int)s->light_count;
    if (vw.width <= 0 || vw.height <= 0 || rf_camera_basis(s->camera.eye, s->camera.target, s->camera.up, &vw.basis) != RF_OK) {
        snprintf(err, errsz, "bad camera or image size");
        return RF_ERR_DOMAIN;
    }
    vw.near = near_plane(s, &vw);
    if (!gl_load(&gl, proc, proc_ctx, err, errsz))
        return RF_ERR_DOMAIN;
    if ((st = build_geometry(s, &g, vw.eye, vw.near, opt->two_sided)) != RF_OK) {
        free_geometry(&g);
        snprintf(err, errsz, st == RF_ERR_NOMEM ? "out of memory" : "bad instance in the scene graph");
        return st;
    }
    if ((st = rf_image_alloc(color, vw.width, vw.height, 3)) != RF_OK ||
        (depth && (st = rf_image_alloc(depth, vw.width, vw.height, 1)) != RF_OK)) {
        free_geometry(&g);
        rf_image_free(color);
        snprintf(err, errsz, "cannot allocate a %d x %d image", vw.width, vw.height);
        return st;
    }
    float *mats = calloc(s->material_count ? 20 * s->material_count : 1, sizeof *mats);
    double *lights = calloc(s->light_count ? 16 * s->light_count : 1, sizeof *lights);
    float *pix = malloc(sizeof *pix * 4 * (size_t)vw.width * (size_t)vw.height);
    if (!mats || !lights || !pix) {
        free(mats), free(lights), free(pix), free_geometry(&g);
        rf_image_free(color), rf_image_free(depth);
        snprintf(err, errsz, "out of memory");
        return RF_ERR_NOMEM;
    }
    for (size_t i = 0; i < s->material_count; i++) {
        const RfMaterial *m = &s->materials[i];
        const RfRgb *c[4] = {&m->ka, &m->kd, &m->ks, &m->emission};
        for (int k = 0; k < 4; k++)
            mats[20 * i + 4 * k] = (float)c[k]->r, mats[20 * i + 4 * k + 1] = (float)c[k]->g,
            mats[20 * i + 4 * k + 2] = (float)c[k]->b;
        mats[20 * i + 16] = (float)m->shininess;
    }
    for (size_t i = 0; i < s->light_count; i++) {
        const RfLight *l = &s->lights[i];
        double *o = lights + 16 * i;
        o[0] = l->position.x, o[1] = l->position.y, o[2] = l->position.z;
        o[3] = l->kind == RF_LIGHT_DIRECTIONAL ? 1.0 : l->kind == RF_LIGHT_SPOT ? 2.0 : 0.0;
        o[4] = l->direction.x, o[5] = l->direction.y, o[6] = l->direction.z;
        o[7] = l->falloff == RF_FALLOFF_NONE ? 1.0 : 0.0;
        o[8] = l->intensity.r, o[9] = l->intensity.g, o[10] = l->intensity.b;
        o[12] = l->spot_exponent, o[13] = cos(l->spot_cutoff * (RF_PI / 180.0));
    }

    GLuint fbo, rb[3], bufs[7], vao, prog_tri = 0, prog_quad = 0;
    gl.GenFramebuffers(1, &fbo);
    gl.BindFramebuffer(GL_FRAMEBUFFER, fbo);
    gl.GenRenderbuffers(3, rb);
    const GLenum fmt[3] = {GL_RGBA32F, GL_R32F, GL_DEPTH_COMPONENT32F};
    const GLenum att[3] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1, GL_DEPTH_ATTACHMENT};
    for (int i = 0; i < 3; i++) {
        gl.BindRenderbuffer(GL_RENDERBUFFER, rb[i]);
        gl.RenderbufferStorage(GL_RENDERBUFFER, fmt[i], vw.width, vw.height);
        gl.FramebufferRenderbuffer(GL_FRAMEBUFFER, att[i], GL_RENDERBUFFER, rb[i]);
    }
    gl.DrawBuffers(2, att);
    gl.GenVertexArrays(1, &vao);
    gl.BindVertexArray(vao);
    bufs[0] = ssbo(&gl, 0, mats, sizeof *mats * 20 * s->material_count);
    bufs[1] = ssbo(&gl, 1, lights, sizeof *lights * 16 * s->light_count);
    bufs[2] = ssbo(&gl, 2, g.trid, sizeof *g.trid * 12 * g.ntri);
    bufs[3] = ssbo(&gl, 3, g.trin, sizeof *g.trin * 9 * g.ntri);
    bufs[4] = ssbo(&gl, 4, g.trii, sizeof *g.trii * 4 * g.ntri);
    bufs[5] = ssbo(&gl, 5, g.quad, sizeof *g.quad * 40 * g.nquad);
    bufs[6] = ssbo(&gl, 6, g.quai, sizeof *g.quai * 4 * g.nquad);
    if (gl.CheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
        snprintf(err, errsz, "GL: the float framebuffer is incomplete");
        st = RF_ERR_DOMAIN;
    } else if (!(prog_tri = compile(&gl, rf_glsl_tri_vs, rf_glsl_tri_fs, err, errsz)) ||
               !(prog_quad = compile(&gl, rf_glsl_quad_vs, rf_glsl_quad_fs, err, errsz))) {
        st = RF_ERR_DOMAIN;
    } else {
        const float bg[4] = {(float)s->render.background.r, (float)s->render.background.g,
                             (float)s->render.background.b, 0.0f};
        const float far_depth[4] = {INFINITY, 0, 0, 0}, zero = 0.0f;
        gl.Viewport(0, 0, vw.width, vw.height);
        gl.ClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE);
        gl.ClearBufferfv(GL_COLOR, 0, bg);
        gl.ClearBufferfv(GL_COLOR, 1, far_depth);
        gl.ClearBufferfv(GL_DEPTH, 0, &zero);
        gl.Enable(GL_DEPTH_TEST);
        gl.DepthFunc(GL_GREATER); /* reversed Z: larger is nearer */
        gl.Disable(GL_CULL_FACE); /* one-sided primitives are culled per fragment, as the tracer */
        if (g.ntri) {
            set_uniforms(&gl, prog_tri, &vw);
            gl.DrawArrays(GL_TRIANGLES, 0, (GLsizei)(3 * g.ntri));
        }
        if (g.nquad) {
            set_uniforms(&gl, prog_quad, &vw);
            gl.DrawArraysInstanced(GL_TRIANGLES, 0, 36, (GLsizei)g.nquad);
        }
        gl.PixelStorei(GL_PACK_ALIGNMENT, 1);
        gl.ReadBuffer(GL_COLOR_ATTACHMENT0);
        gl.ReadPixels(0, 0, vw.width, vw.height, GL_RGBA, GL_FLOAT, pix);
        /* GL's row 0 is the bottom; the image's is the top */
        for (int y = 0; y < vw.height; y++)
            for (int x = 0; x < vw.width; x++)
                for (int c = 0; c < 3; c++)
                    color->data[((size_t)(vw.height - 1 - y) * vw.width + x) * 3 + c] =
                        pix[((size_t)y * vw.width + x) * 4 + c];
        if (depth) {
            gl.ReadBuffer(GL_COLOR_ATTACHMENT1);
            gl.ReadPixels(0, 0, vw.width, vw.height, GL_RED, GL_FLOAT, pix);
            for (int y = 0; y < vw.height; y++)
                memcpy(depth->data + (size_t)(vw.height - 1 - y) * vw.width, pix + (size_t)y * vw.width,
                       sizeof *pix * (size_t)vw.width);
        }
        GLenum e = gl.GetError();
        if (e != GL_NO_ERROR) {
            snprintf(err, errsz, "GL error 0x%04x while drawing", (unsigned)e);
            st = RF_ERR_DOMAIN;
        }
    }
    if (prog_tri)
        gl.DeleteProgram(prog_tri);
    if (prog_quad)
        gl.DeleteProgram(prog_quad);
    gl.DeleteBuffers(7, bufs);
    gl.DeleteVertexArrays(1, &vao);
    gl.DeleteRenderbuffers(3, rb);
    gl.BindFramebuffer(GL_FRAMEBUFFER, 0);
    gl.DeleteFramebuffers(1, &fbo);
    free(mats), free(lights), free(pix), free_geometry(&g);
    if (st != RF_OK) {
        rf_image_free(color);
        rf_image_free(depth);
    }
    return st;
}
