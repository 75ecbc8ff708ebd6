/* refray: the reader of refray's own scene format (docs/scene-format.md has every keyword
 * with an example).
 *
 * One statement per line: a keyword, its positional numbers, then named attributes. A line
 * that starts with a number continues the statement above (long polygons). Colours take one
 * number (grey) or three. Point and spot lights fall off with the squared distance (§3.7)
 * unless `falloff none` is given. Primitives are two-sided unless marked otherwise. */
#include "refray/hash.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "reader.h"
#include "refray/scene_io.h"
#include "refray/transform.h"

#define RF_MAX_POLY_VERTICES 1000000
#define RF_PATH_MAX 4096

/* An `instance` whose object is looked up at the end of the file (forward references). */
typedef struct {
    size_t instance;
    RfToken name;
} PendingRef;

typedef struct {
    RfLexer lx;
    RfScene *scene;
    int material;      /* current material, -1 before the first */
    int object;        /* the object block being read (§4.8), -1 in the world */
    RfToken object_kw; /* its keyword, for "no 'end'" */
    RfVec3 *vbuf, *nbuf; /* scratch for polygon vertices and normals */
    size_t vcap;
    PendingRef *refs;
    size_t ref_count, ref_cap;
    int threads; /* RfLoadOptions.threads, for `mesh` */
} RfReader;

/* A colour: one number (grey) or three, each >= 0. */
static RfStatus read_colour(RfLexer *lx, const char *what, RfRgb *c)
{
    RfStatus st = rf_lex_number_ge(lx, what, 0.0, &c->r);
    if (st)
        return st;
    if (lx->tok.kind != RF_TOK_NUMBER) {
        c->g = c->b = c->r;
        return RF_OK;
    }
    if ((st = rf_lex_number_ge(lx, what, 0.0, &c->g)) || (st = rf_lex_number_ge(lx, what, 0.0, &c->b)))
        return st;
    return RF_OK;
}

/* Takes the next attribute token into *attr; 0 at the end of the statement. */
static int next_attr(RfLexer *lx, RfToken *attr)
{
    if (rf_lex_at_statement_start(lx))
        return 0;
    *attr = lx->tok;
    rf_lex_advance(lx);
    return 1;
}

static RfStatus bad_attr(RfLexer *lx, const RfToken *kw, const RfToken *attr)
{
    char q[96], k[96];
    if (attr->kind == RF_TOK_NUMBER)
        return rf_lex_error(lx, attr->line, attr->col, "too many numbers for %s: %s",
                            rf_lex_quote(kw, k, sizeof k), rf_lex_quote(attr, q, sizeof q));
    return rf_lex_error(lx, attr->line, attr->col, "unknown attribute %s for %s",
                        rf_lex_quote(attr, q, sizeof q), rf_lex_quote(kw, k, sizeof k));
}

/* The end of a statement without attributes. */
static RfStatus no_attrs(RfLexer *lx, const RfToken *kw)
{
    RfToken a;
    return next_attr(lx, &a) ? bad_attr(lx, kw, &a) : RF_OK;
}

static RfStatus read_camera(RfReader *r, const RfToken *kw)
{
    RfLexer *lx = &r->lx;
    RfSceneCamera *c = &r->scene->camera;
    RfToken a;
    RfStatus st = RF_OK;
    int have_eye = 0, have_target = 0, have_up = 0, have_fov = 0;
    if (r->scene->has_camera)
        return rf_lex_error(lx, kw->line, kw->col, "second camera: the scene has one camera");
    memset(c, 0, sizeof *c);
    c->d = 1.0;
    c->fov_reading = RF_FOV_EDGES;
    c->loc = c->target_loc = c->up_loc = rf__token_loc(kw);
    while (!st && next_attr(lx, &a)) {
        if (rf_lex_is(&a, "eye")) {
            st = rf_lex_vec3(lx, "eye", &c->eye);
            have_eye = 1;
        } else if (rf_lex_is(&a, "target")) {
            st = rf_lex_vec3(lx, "target", &c->target);
            c->target_loc = rf__token_loc(&a);
            have_target = 1;
        } else if (rf_lex_is(&a, "up")) {
            st = rf_lex_vec3(lx, "up", &c->up);
            c->up_loc = rf__token_loc(&a);
            have_up = 1;
        } else if (rf_lex_is(&a, "fov")) {
            if (!(st = rf_lex_number(lx, "fov", &c->fov)))
                st = rf_lex_check(lx, c->fov > 0.0 && c->fov < 180.0,
                                  "fov must be in (0, 180) degrees, found %g", c->fov);
            have_fov = 1;
        } else if (rf_lex_is(&a, "window")) {
            if (!(st = rf_lex_number(lx, "window l", &c->l)) &&
                !(st = rf_lex_number(lx, "window r", &c->r)) &&
                !(st = rf_lex_check(lx, c->l < c->r, "window needs l < r")) &&
                !(st = rf_lex_number(lx, "window b", &c->b)) &&
                !(st = rf_lex_number(lx, "window t", &c->t)))
                st = rf_lex_check(lx, c->b < c->t, "window needs b < t");
            c->has_window = 1;
        } else if (rf_lex_is(&a, "d")) {
            if (!(st = rf_lex_number(lx, "d", &c->d)))
                st = rf_lex_check(lx, c->d > 0.0, "d must be > 0, found %g", c->d);
        } else if (rf_lex_is(&a, "hither")) {
            st = rf_lex_number_ge(lx, "hither", 0.0, &c->hither);
        } else if (rf_lex_is(&a, "aperture")) { /* §3.10 thin lens: its radius */
            st = rf_lex_number_ge(lx, "aperture radius", 0.0, &c->aperture);
        } else if (rf_lex_is(&a, "focus")) {
            if (!(st = rf_lex_number(lx, "focus distance", &c->focus)))
                st = rf_lex_check(lx, c->focus > 0.0, "focus distance must be > 0, found %g", c->focus);
        } else {
            return bad_attr(lx, kw, &a);
        }
    }
    if (st)
        return st;
    const char *missing = !have_eye ? "eye" : !have_target ? "target" : !have_up ? "up" : NULL;
    if (missing)
        return rf_lex_error(lx, kw->line, kw->col, "camera needs '%s'", missing);
    if (c->aperture > 0.0 && !(c->focus > 0.0))
        return rf_lex_error(lx, kw->line, kw->col, "camera with an aperture needs 'focus'");
    if (have_fov == c->has_window)
        return rf_lex_error(lx, kw->line, kw->col, "camera needs exactly one of 'fov' and 'window'");
    r->scene->has_camera = 1;
    return rf__reader_check_camera(lx, c);
}

static int find_material(const RfScene *s, const RfToken *name)
{
    for (size_t i = 0; i < s->material_count; i++)
        if (strlen(s->materials[i].name) == name->len &&
            memcmp(s->materials[i].name, name->s, name->len) == 0)
            return (int)i;
    return -1;
}

/* A material name token: a word shorter than RF_NAME_MAX. */
static RfStatus read_name(RfLexer *lx, RfToken *name)
{
    char q[96];
    RfStatus st = rf_lex_word(lx, "a material name", name);
    if (!st && name->len >= RF_NAME_MAX)
        st = rf_lex_error(lx, name->line, name->col, "material name %s is longer than %d bytes",
                          rf_lex_quote(name, q, sizeof q), RF_NAME_MAX - 1);
    return st;
}

/* A reference to a defined material. */
static RfStatus read_material_ref(RfReader *r, int *index)
{
    RfToken name;
    char q[96];
    RfStatus st = read_name(&r->lx, &name);
    if (st)
        return st;
    *index = find_material(r->scene, &name);
    if (*index < 0)
        return rf_lex_error(&r->lx, name.line, name.col, "unknown material %s",
                            rf_lex_quote(&name, q, sizeof q));
    return RF_OK;
}

static RfStatus read_material(RfReader *r, const RfToken *kw)
{
    RfLexer *lx = &r->lx;
    RfMaterial m = rf_material_default();
    RfToken name, a;
    char q[96];
    RfStatus st = read_name(lx, &name);
    if (st)
        return st;
    if (find_material(r->scene, &name) >= 0)
        return rf_lex_error(lx, name.line, name.col, "material %s is defined twice",
                            rf_lex_quote(&name, q, sizeof q));
    memcpy(m.name, name.s, name.len);
    m.name[name.len] = 0;
    m.loc = rf__token_loc(kw);
    while (!st && next_attr(lx, &a)) {
        if (rf_lex_is(&a, "ka"))
            st = read_colour(lx, "ka", &m.ka);
        else if (rf_lex_is(&a, "kd"))
            st = read_colour(lx, "kd", &m.kd);
        else if (rf_lex_is(&a, "ks"))
            st = read_colour(lx, "ks", &m.ks);
        else if (rf_lex_is(&a, "kr"))
            st = read_colour(lx, "kr", &m.kr);
        else if (rf_lex_is(&a, "kt"))
            st = read_colour(lx, "kt", &m.kt);
        else if (rf_lex_is(&a, "emission"))
            st = read_colour(lx, "emission", &m.emission);
        else if (rf_lex_is(&a, "shininess"))
            st = rf_lex_number_ge(lx, "shininess", 0.0, &m.shininess);
        else if (rf_lex_is(&a, "glossy"))
            st = rf_lex_number_ge(lx, "glossy exponent", 0.0, &m.gloss);
        else if (rf_lex_is(&a, "ior")) {
            if (!(st = rf_lex_number(lx, "ior", &m.ior)))
                st = rf_lex_check(lx, m.ior > 0.0, "ior must be > 0, found %g", m.ior);
        } else if (rf_lex_is(&a, "fresnel"))
            m.flags |= RF_MAT_FRESNEL;
        else if (rf_lex_is(&a, "flat"))
            m.flags &= ~(unsigned)RF_MAT_SMOOTH;
        else if (rf_lex_is(&a, "smooth"))
            m.flags |= RF_MAT_SMOOTH;
        else
            return bad_attr(lx, kw, &a);
    }
    if (st)
        return st;
    if (rf_scene_add_material(r->scene, &m, &r->material))
        return rf_lex_error(lx, kw->line, kw->col, "out of memory");
    return RF_OK;
}

static RfStatus read_light(RfReader *r, const RfToken *kw)
{
    RfLexer *lx = &r->lx;
    RfLight l;
    RfToken kind, a;
    char q[96];
    RfStatus st = rf_lex_word(lx, "a light kind (point, directional, spot, rect, disc, sphere)", &kind);
    if (st)
        return st;
    memset(&l, 0, sizeof l);
    l.loc = rf__token_loc(kw);
    l.intensity = rf_rgb(1, 1, 1);
    l.falloff = RF_FALLOFF_INVERSE_SQUARE;
    l.samples = 1;
    int have_axis = 0, have_cutoff = 0;
    if (rf_lex_is(&kind, "rect") || rf_lex_is(&kind, "disc") || rf_lex_is(&kind, "sphere")) {
        /* §3.10 area lights: geometry, then radiance, sides and shadow samples */
        l.falloff = RF_FALLOFF_NONE; /* the 1/d^2 is in the geometry term */
        st = rf_lex_vec3(lx, kind.s[0] == 'r' ? "rect corner" : "light centre", &l.position);
        if (kind.s[0] == 'r') {
            l.kind = RF_LIGHT_RECT;
            if (!st && !(st = rf_lex_vec3(lx, "rect edge 1", &l.edge1)))
                st = rf_lex_vec3(lx, "rect edge 2", &l.edge2);
            if (!st)
                st = rf_lex_check(lx, rf_vec3_length(rf_vec3_cross(l.edge1, l.edge2)) > 0.0,
                                  "rect light: its edges are parallel or zero (no area)");
            if (!st)
                l.direction = rf_vec3_normalize(rf_vec3_cross(l.edge1, l.edge2));
        } else if (kind.s[0] == 'd') {
            l.kind = RF_LIGHT_DISC;
            if (!st && !(st = rf_lex_vec3(lx, "disc normal", &l.direction)))
                st = rf_lex_check(lx, rf_vec3_length(l.direction) > 0.0, "disc normal has zero length");
            if (!st && !(st = rf_lex_number(lx, "disc radius", &l.radius)))
                st = rf_lex_check(lx, l.radius > 0.0, "disc radius must be > 0, found %g", l.radius);
            if (!st)
                l.direction = rf_vec3_normalize(l.direction);
        } else {
            l.kind = RF_LIGHT_SPHERE;
            if (!st && !(st = rf_lex_number(lx, "sphere radius", &l.radius)))
                st = rf_lex_check(lx, l.radius > 0.0, "sphere light radius must be > 0, found %g", l.radius);
        }
        while (!st && next_attr(lx, &a)) {
            if (rf_lex_is(&a, "radiance"))
                st = read_colour(lx, "radiance", &l.intensity);
            else if (rf_lex_is(&a, "two-sided") && l.kind != RF_LIGHT_SPHERE)
                l.two_sided = 1;
            else if (rf_lex_is(&a, "samples"))
                st = rf_lex_int(lx, "light samples", 1, 1 << 16, &l.samples);
            else
                return bad_attr(lx, &kind, &a);
        }
        if (st)
            return st;
        if (rf_scene_add_light(r->scene, &l))
            return rf_lex_error(lx, kw->line, kw->col, "out of memory");
        return RF_OK;
    }
    if (rf_lex_is(&kind, "point") || rf_lex_is(&kind, "spot")) {
        l.kind = kind.s[0] == 'p' ? RF_LIGHT_POINT : RF_LIGHT_SPOT;
        st = rf_lex_vec3(lx, "light position", &l.position);
    } else if (rf_lex_is(&kind, "directional")) {
        l.kind = RF_LIGHT_DIRECTIONAL;
        l.falloff = RF_FALLOFF_NONE;
        if (!(st = rf_lex_vec3(lx, "light direction", &l.direction)))
            st = rf_lex_check(lx, rf_vec3_length(l.direction) > 0.0,
                              "light direction has zero length");
    } else {
        return rf_lex_error(lx, kind.line, kind.col,
                            "unknown light kind %s (point, directional, spot, rect, disc, sphere)",
                            rf_lex_quote(&kind, q, sizeof q));
    }
    while (!st && next_attr(lx, &a)) {
        if (rf_lex_is(&a, "intensity")) {
            st = read_colour(lx, "intensity", &l.intensity);
        } else if (rf_lex_is(&a, "falloff") && l.kind != RF_LIGHT_DIRECTIONAL) {
            RfToken v;
            if (!(st = rf_lex_word(lx, "'none' or 'inverse-square'", &v))) {
                if (rf_lex_is(&v, "none"))
                    l.falloff = RF_FALLOFF_NONE;
                else if (rf_lex_is(&v, "inverse-square"))
                    l.falloff = RF_FALLOFF_INVERSE_SQUARE;
                else
                    st = rf_lex_error(lx, v.line, v.col,
                                      "falloff must be 'none' or 'inverse-square', found %s",
                                      rf_lex_quote(&v, q, sizeof q));
            }
        } else if (rf_lex_is(&a, "axis") && l.kind == RF_LIGHT_SPOT) {
            if (!(st = rf_lex_vec3(lx, "spot axis", &l.direction)))
                st = rf_lex_check(lx, rf_vec3_length(l.direction) > 0.0,
                                  "spot axis has zero length");
            have_axis = 1;
        } else if (rf_lex_is(&a, "exponent") && l.kind == RF_LIGHT_SPOT) {
            st = rf_lex_number_ge(lx, "spot exponent", 0.0, &l.spot_exponent);
        } else if (rf_lex_is(&a, "cutoff") && l.kind == RF_LIGHT_SPOT) {
            if (!(st = rf_lex_number(lx, "spot cutoff", &l.spot_cutoff)))
                st = rf_lex_check(lx, l.spot_cutoff > 0.0 && l.spot_cutoff <= 90.0,
                                  "spot cutoff must be in (0, 90] degrees, found %g",
                                  l.spot_cutoff);
            have_cutoff = 1;
        } else {
            return bad_attr(lx, &kind, &a);
        }
    }
    if (st)
        return st;
    if (l.kind == RF_LIGHT_SPOT && (!have_axis || !have_cutoff))
        return rf_lex_error(lx, kw->line, kw->col, "spot light needs 'axis' and 'cutoff'");
    if (rf_scene_add_light(r->scene, &l))
        return rf_lex_error(lx, kw->line, kw->col, "out of memory");
    return RF_OK;
}

/* n points into the scratch buffer: the vertices, or their normals when `normals` is set. */
static RfStatus read_points(RfReader *r, int normals, int n, const char *what)
{
    if ((size_t)n > r->vcap) {
        RfVec3 *v = realloc(r->vbuf, (size_t)n * sizeof *v);
        if (v)
            r->vbuf = v;
        RfVec3 *vn = v ? realloc(r->nbuf, (size_t)n * sizeof *vn) : NULL;
        if (vn)
            r->nbuf = vn;
        if (!v || !vn)
            return rf_lex_error(&r->lx, r->lx.tok.line, r->lx.tok.col, "out of memory");
        r->vcap = (size_t)n;
    }
    RfVec3 *dst = normals ? r->nbuf : r->vbuf;
    for (int i = 0; i < n; i++) {
        RfStatus st = rf_lex_vec3(&r->lx, what, &dst[i]);
        if (st)
            return st;
    }
    return RF_OK;
}

static RfStatus read_primitive(RfReader *r, const RfToken *kw)
{
    RfLexer *lx = &r->lx;
    RfPrimitive p;
    RfToken a;
    int n = 0, normals = 0;
    RfStatus st = rf__reader_default_material(lx, r->scene, kw, &r->material);
    if (st)
        return st;
    memset(&p, 0, sizeof p);
    p.material = r->material;
    p.flags = RF_PRIM_TWO_SIDED;
    p.loc = rf__token_loc(kw);
    unsigned in_object = r->object >= 0 ? RF_PRIM_IN_OBJECT : 0u;
    if (rf_lex_is(kw, "sphere")) {
        p.type = RF_PRIM_SPHERE;
        if (!(st = rf_lex_vec3(lx, "sphere centre", &p.u.sphere.center)))
            st = rf_lex_number(lx, "sphere radius", &p.u.sphere.radius);
    } else if (rf_lex_is(kw, "plane")) {
        RfVec3 point;
        p.type = RF_PRIM_PLANE;
        if (!(st = rf_lex_vec3(lx, "plane point", &point)) &&
            !(st = rf_lex_vec3(lx, "plane normal", &p.u.plane.normal)))
            p.u.plane.offset = rf_vec3_dot(p.u.plane.normal, point);
    } else if (rf_lex_is(kw, "cone")) {
        p.type = RF_PRIM_CONE;
        if (!(st = rf_lex_vec3(lx, "cone base", &p.u.cone.base)) &&
            !(st = rf_lex_number_ge(lx, "cone base radius", 0.0, &p.u.cone.base_radius)) &&
            !(st = rf_lex_vec3(lx, "cone apex", &p.u.cone.apex)))
            st = rf_lex_number_ge(lx, "cone apex radius", 0.0, &p.u.cone.apex_radius);
    } else if (rf_lex_is(kw, "cylinder")) {
        p.type = RF_PRIM_CONE;
        if (!(st = rf_lex_vec3(lx, "cylinder base", &p.u.cone.base)) &&
            !(st = rf_lex_vec3(lx, "cylinder apex", &p.u.cone.apex)) &&
            !(st = rf_lex_number_ge(lx, "cylinder radius", 0.0, &p.u.cone.base_radius)))
            p.u.cone.apex_radius = p.u.cone.base_radius;
    } else if (rf_lex_is(kw, "triangle")) {
        p.type = RF_PRIM_TRIANGLE;
        n = 3;
        st = read_points(r, 0, n, "triangle vertex");
    } else {
        p.type = RF_PRIM_POLYGON;
        if (!(st = rf_lex_int(lx, "polygon vertex count", 3, RF_MAX_POLY_VERTICES, &n)))
            st = read_points(r, 0, n, "polygon vertex");
    }
    while (!st && next_attr(lx, &a)) {
        if (rf_lex_is(&a, "material")) {
            st = read_material_ref(r, &p.material);
        } else if (rf_lex_is(&a, "two-sided")) {
            p.flags = (p.flags & ~(unsigned)RF_PRIM_INSIDE) | RF_PRIM_TWO_SIDED;
        } else if (rf_lex_is(&a, "one-sided")) {
            p.flags &= ~(unsigned)(RF_PRIM_TWO_SIDED | RF_PRIM_INSIDE);
        } else if (rf_lex_is(&a, "inside") && (p.type == RF_PRIM_SPHERE || p.type == RF_PRIM_CONE)) {
            p.flags = (p.flags & ~(unsigned)RF_PRIM_TWO_SIDED) | RF_PRIM_INSIDE;
        } else if (rf_lex_is(&a, "normals") && n > 0) {
            st = read_points(r, 1, n, "vertex normal");
            normals = 1;
        } else {
            return bad_attr(lx, kw, &a);
        }
    }
    if (st)
        return st;
    p.flags |= in_object;
    if (n > 0) {
        p.u.poly.count = n;
        if (normals)
            p.flags |= RF_PRIM_VERTEX_NORMALS;
        if (rf_scene_add_vertices(r->scene, r->vbuf, normals ? r->nbuf : NULL, n, &p.u.poly.first,
                                  &p.u.poly.nfirst))
            return rf_lex_error(lx, kw->line, kw->col, "out of memory");
    }
    return rf__reader_add_prim(lx, r->scene, &p);
}

/* ---- the scene graph (§4.8) ---------------------------------------------------------------- */

static int find_object(const RfScene *s, const char *name, size_t len)
{
    for (size_t i = 0; i < s->object_count; i++)
        if (strlen(s->objects[i].name) == len && memcmp(s->objects[i].name, name, len) == 0)
            return (int)i;
    return -1;
}

/* object NAME / group NAME: the statements up to `end` make one object. Blocks do not nest;
 * an object goes into another through `instance`. */
static RfStatus read_object(RfReader *r, const RfToken *kw)
{
    RfLexer *lx = &r->lx;
    RfToken name;
    char q[96], k[96], nm[RF_NAME_MAX];
    if (r->object >= 0)
        return rf_lex_error(lx, kw->line, kw->col,
                            "%s inside object '%s': blocks do not nest (close it with 'end'; "
                            "place objects in objects with 'instance')",
                            rf_lex_quote(kw, k, sizeof k), r->scene->objects[r->object].name);
    RfStatus st = rf_lex_word(lx, "an object name", &name);
    if (st)
        return st;
    if (name.len >= RF_NAME_MAX)
        return rf_lex_error(lx, name.line, name.col, "object name %s is longer than %d bytes",
                            rf_lex_quote(&name, q, sizeof q), RF_NAME_MAX - 1);
    if (find_object(r->scene, name.s, name.len) >= 0)
        return rf_lex_error(lx, name.line, name.col, "object %s is defined twice",
                            rf_lex_quote(&name, q, sizeof q));
    memcpy(nm, name.s, name.len);
    nm[name.len] = 0;
    if (rf_scene_add_object(r->scene, nm, rf__token_loc(kw), &r->object))
        return rf_lex_error(lx, kw->line, kw->col, "out of memory");
    r->object_kw = *kw;
    return no_attrs(lx, kw);
}

static RfStatus read_end(RfReader *r, const RfToken *kw)
{
    if (r->object < 0)
        return rf_lex_error(&r->lx, kw->line, kw->col, "'end' without an 'object' or 'group'");
    RfSceneObject *o = &r->scene->objects[r->object];
    o->count = r->scene->prim_count - o->first;
    r->object = -1;
    return no_attrs(&r->lx, kw);
}

/* One transform step of an instance (angles in degrees). *known = 0 when a is not a transform
 * keyword. */
static RfStatus read_transform(RfReader *r, const RfToken *a, RfTransformStep *step, int *known)
{
    RfLexer *lx = &r->lx;
    RfStatus st = RF_OK;
    char q[96];
    double *v = step->v;
    *known = 1;
    memset(step, 0, sizeof *step);
    if (rf_lex_is(a, "translate")) {
        step->kind = RF_STEP_TRANSLATE;
        st = rf_lex_number(lx, "translation", &v[0]);
        if (!st && !(st = rf_lex_number(lx, "translation", &v[1])))
            st = rf_lex_number(lx, "translation", &v[2]);
    } else if (rf_lex_is(a, "scale")) {
        step->kind = RF_STEP_SCALE;
        if (!(st = rf_lex_number(lx, "scale factor", &v[0]))) {
            v[1] = v[2] = v[0];
            if (lx->tok.kind == RF_TOK_NUMBER && !rf_lex_at_statement_start(lx) &&
                !(st = rf_lex_number(lx, "scale factor", &v[1])))
                st = rf_lex_number(lx, "scale factor", &v[2]);
        }
        if (!st && !(v[0] != 0.0 && v[1] != 0.0 && v[2] != 0.0))
            st = rf_lex_error(lx, a->line, a->col, "scale factors must be non-zero");
    } else if (rf_lex_is(a, "rotate")) {
        RfToken ax;
        step->kind = RF_STEP_ROTATE;
        if ((st = rf_lex_word(lx, "an axis (x, y, z)", &ax)))
            return st;
        if (!rf_lex_is(&ax, "x") && !rf_lex_is(&ax, "y") && !rf_lex_is(&ax, "z"))
            return rf_lex_error(lx, ax.line, ax.col, "rotate needs an axis x, y or z, found %s",
                                rf_lex_quote(&ax, q, sizeof q));
        step->axis = ax.s[0] - 'x';
        st = rf_lex_number(lx, "rotation angle", &v[0]);
    } else if (rf_lex_is(a, "axis-angle")) {
        step->kind = RF_STEP_AXIS_ANGLE;
        for (int k = 0; !st && k < 3; k++)
            st = rf_lex_number(lx, "rotation axis", &v[k]);
        if (!st && !(st = rf_lex_number(lx, "rotation angle", &v[3])) &&
            !(rf_vec3_length(rf_vec3(v[0], v[1], v[2])) > 0.0))
            return rf_lex_error(lx, a->line, a->col, "axis-angle: the axis has zero length");
    } else if (rf_lex_is(a, "euler")) {
        static const char *const orders[] = {"zyx", "xyz", "zxz", "zyz"};
        RfToken o;
        int k = -1;
        step->kind = RF_STEP_EULER;
        if ((st = rf_lex_word(lx, "an Euler order (zyx, xyz, zxz, zyz)", &o)))
            return st;
        for (int i = 0; i < 4; i++)
            if (rf_lex_is(&o, orders[i]))
                k = i;
        if (k < 0)
            return rf_lex_error(lx, o.line, o.col, "unknown Euler order %s (zyx, xyz, zxz, zyz)",
                                rf_lex_quote(&o, q, sizeof q));
        step->axis = k;
        if (!(st = rf_lex_number(lx, "Euler angle psi", &v[0])) &&
            !(st = rf_lex_number(lx, "Euler angle theta", &v[1])))
            st = rf_lex_number(lx, "Euler angle phi", &v[2]);
    } else if (rf_lex_is(a, "matrix")) {
        step->kind = RF_STEP_MATRIX;
        for (int k = 0; !st && k < 12; k++)
            st = rf_lex_number(lx, "matrix entry (3 rows of 4)", &v[k]);
    } else {
        *known = 0;
    }
    return st;
}

/* instance NAME transforms...: places an object (defined before or after) by the composed
 * transform; inside an object block it makes that object a group containing NAME. */
static RfStatus read_instance(RfReader *r, const RfToken *kw)
{
    RfLexer *lx = &r->lx;
    RfToken name, a;
    RfMat4 m = rf_mat4_identity();
    RfPrimitive p;
    /* keyframes: the steps before the first `at TIME` are the transform (at time 0 when `at`
     * follows); each `at TIME` starts a keyframe with the same steps, other numbers */
    RfMotion *mo = calloc(1, sizeof *mo);
    int nsteps[RF_MOTION_MAX_KEYS] = {0}, timed0 = 0;
    RfToken key_tok[RF_MOTION_MAX_KEYS];
    char msg[256];
    if (!mo)
        return rf_lex_error(lx, kw->line, kw->col, "out of memory");
    mo->key_count = 1;
    key_tok[0] = *kw;
    RfStatus st = rf_lex_word(lx, "an object name", &name);
    while (!st && next_attr(lx, &a)) {
        int known, k = mo->key_count - 1;
        if (rf_lex_is(&a, "at") && k == 0 && nsteps[0] == 0 && !timed0) { /* the first keyframe's time */
            st = rf_lex_number(lx, "keyframe time", &mo->time[0]);
            timed0 = 1;
            key_tok[0] = a;
            continue;
        }
        if (rf_lex_is(&a, "at")) {
            if (k + 1 >= RF_MOTION_MAX_KEYS) {
                st = rf_lex_error(lx, a.line, a.col, "more than %d keyframes", RF_MOTION_MAX_KEYS);
            } else if (!(st = rf_lex_number(lx, "keyframe time", &mo->time[k + 1]))) {
                if ((k > 0 || timed0) && !(mo->time[k + 1] > mo->time[k]))
                    st = rf_lex_error(lx, a.line, a.col, "keyframe times must increase");
                key_tok[k + 1] = a;
                mo->key_count++;
            }
            continue;
        }
        RfTransformStep step;
        st = read_transform(r, &a, &step, &known);
        if (!known) {
            free(mo);
            return bad_attr(lx, kw, &a);
        }
        if (!st && nsteps[k] >= RF_MOTION_MAX_STEPS)
            st = rf_lex_error(lx, a.line, a.col, "more than %d transform steps", RF_MOTION_MAX_STEPS);
        if (!st)
            mo->steps[k][nsteps[k]++] = step;
    }
    if (!st && mo->key_count > 1 && !timed0 && !(mo->time[1] > 0.0)) /* the first keyframe: time 0 */
        st = rf_lex_error(lx, key_tok[1].line, key_tok[1].col,
                          "keyframe times must increase (the first keyframe is at time 0)");
    mo->step_count = nsteps[0];
    for (int k = 1; !st && k < mo->key_count; k++) {
        int same = nsteps[k] == nsteps[0];
        for (int i = 0; same && i < nsteps[0]; i++)
            same = mo->steps[k][i].kind == mo->steps[0][i].kind && mo->steps[k][i].axis == mo->steps[0][i].axis;
        if (!same)
            st = rf_lex_error(lx, key_tok[k].line, key_tok[k].col,
                              "keyframe at %g lists other transform steps than the first: each keyframe "
                              "lists the same steps (kinds, axes, order) with other numbers",
                              mo->time[k]);
    }
    if (!st)
        st = rf_transform_steps_matrix(mo->steps[0], mo->step_count, &m) == RF_OK
                 ? RF_OK
                 : rf_lex_error(lx, kw->line, kw->col, "instance transform is degenerate");
    if (!st)
        st = rf__reader_default_material(lx, r->scene, kw, &r->material);
    if (st) {
        free(mo);
        return st;
    }
    memset(&p, 0, sizeof p);
    p.type = RF_PRIM_INSTANCE;
    p.flags = RF_PRIM_TWO_SIDED | (r->object >= 0 ? RF_PRIM_IN_OBJECT : 0u);
    p.material = r->material; /* unused: the object's primitives have their own */
    p.loc = rf__token_loc(kw);
    st = rf_scene_add_instance(r->scene, -1, m, &p.u.instance);
    if (st == RF_ERR_SINGULAR) {
        free(mo);
        return rf_lex_error(lx, kw->line, kw->col, "instance transform is singular (a zero scale?)");
    }
    if (!st && mo->key_count > 1) {
        st = rf_scene_set_motion(r->scene, p.u.instance, mo, msg, sizeof msg);
        if (st && st != RF_ERR_NOMEM) {
            free(mo);
            return rf_lex_error(lx, kw->line, kw->col, "%s", msg);
        }
    }
    free(mo);
    if (!st && r->ref_count == r->ref_cap) {
        size_t cap = r->ref_cap ? 2 * r->ref_cap : 16;
        PendingRef *refs = realloc(r->refs, cap * sizeof *refs);
        if (refs) {
            r->refs = refs;
            r->ref_cap = cap;
        } else {
            st = RF_ERR_NOMEM;
        }
    }
    if (st)
        return rf_lex_error(lx, kw->line, kw->col, "out of memory");
    r->refs[r->ref_count].instance = p.u.instance;
    r->refs[r->ref_count].name = name;
    r->ref_count++;
    return rf__reader_add_prim(lx, r->scene, &p);
}

/* The end of the file: every block closed, every instance's object known. Cycles are found
 * by rf_scene_validate (rf_scene_graph_check) at the instance that closes them. */
static RfStatus resolve_refs(RfReader *r)
{
    char q[96];
    if (r->object >= 0)
        return rf_lex_error(&r->lx, r->object_kw.line, r->object_kw.col,
                            "object '%s' has no 'end'", r->scene->objects[r->object].name);
    for (size_t i = 0; i < r->ref_count; i++) {
        const RfToken *n = &r->refs[i].name;
        int o = find_object(r->scene, n->s, n->len);
        if (o < 0)
            return rf_lex_error(&r->lx, n->line, n->col, "unknown object %s",
                                rf_lex_quote(n, q, sizeof q));
        r->scene->instances[r->refs[i].instance].object = o;
    }
    return RF_OK;
}

/* mesh PATH [crease DEG]: the faces of an OBJ file (path relative to this file) in the world
 * or in the object being read; faces before the OBJ's first usemtl take the current material. */
static RfStatus read_mesh(RfReader *r, const RfToken *kw)
{
    RfLexer *lx = &r->lx;
    RfToken file, a;
    char path[RF_PATH_MAX], q[96];
    RfObjPlacement pl;
    RfStatus st = RF_OK;
    pl.crease_deg = 60.0;
    pl.material = r->material;
    pl.prim_flags = r->object >= 0 ? RF_PRIM_IN_OBJECT : 0u;
    pl.threads = r->threads;
    pl.chunked = NULL;
    if (rf_lex_at_statement_start(lx))
        return rf_lex_error(lx, lx->last_end_line, lx->last_end_col, "mesh needs an OBJ file name");
    file = lx->tok; /* any token: "./a.obj" reads as a number */
    rf_lex_advance(lx);
    while (!st && next_attr(lx, &a)) {
        if (rf_lex_is(&a, "crease")) {
            if (!(st = rf_lex_number(lx, "crease angle", &pl.crease_deg)))
                st = rf_lex_check(lx, pl.crease_deg >= 0.0 && pl.crease_deg <= 180.0,
                                  "crease angle must be in [0, 180] degrees");
        } else {
            return bad_attr(lx, kw, &a);
        }
    }
    if (st)
        return st;
    if (!rf__reader_relative_path(lx->name, file.s, file.len, path, sizeof path))
        return rf_lex_error(lx, file.line, file.col, "path %s is too long",
                            rf_lex_quote(&file, q, sizeof q));
    char why[512];
    char *text = NULL;
    size_t len = 0;
    if (rf__reader_read_file(r->scene, path, &text, &len, why, sizeof why)) {
        const char *msg = strstr(why, ": ") ? strstr(why, ": ") + 2 : why; /* drop "[cannot open] path: " */
        return rf_lex_error(lx, file.line, file.col, "mesh %s: %s", rf_lex_quote(&file, q, sizeof q),
                            msg);
    }
    st = rf__obj_read(path, text, len, &pl, r->scene, lx->err, lx->errsz);
    r->scene->source_hash = rf_hash_bytes(r->scene->source_hash, text, len);
    free(text);
    return st;
}

/* One word of a closed set (its parser returns -1 for others) into *k; `what` and the names
 * make the message. */
static RfStatus read_choice(RfLexer *lx, const char *what, const char *names, int (*parse)(const char *),
                            int *k)
{
    RfToken w;
    char q[96], name[32], want[128];
    snprintf(want, sizeof want, "a %s (%s)", what, names);
    RfStatus st = rf_lex_word(lx, want, &w);
    if (st)
        return st;
    snprintf(name, sizeof name, "%.*s", (int)(w.len < 31 ? w.len : 31), w.s);
    if ((*k = parse(name)) < 0)
        return rf_lex_error(lx, w.line, w.col, "unknown %s %s (%s)", what, rf_lex_quote(&w, q, sizeof q), names);
    return RF_OK;
}

/* A sampler's name, or RF_SAMPLER_COUNT for "adaptive" (§3.9 adaptive supersampling). */
static int parse_sampler(const char *name)
{
    return strcmp(name, "adaptive") == 0 ? RF_SAMPLER_COUNT : rf_sampler_parse(name);
}

/* sampler uniform|random|stratified|sobol, or sampler adaptive [threshold T] [depth D] (§3.9) */
static RfStatus read_sampler(RfReader *r, const RfToken *kw)
{
    RfLexer *lx = &r->lx;
    RfRenderSettings *rs = &r->scene->render;
    RfToken a;
    int s;
    RfStatus st = read_choice(lx, "sampler", "uniform, random, stratified, sobol, adaptive", parse_sampler, &s);
    if (st)
        return st;
    rs->adaptive = s == RF_SAMPLER_COUNT;
    if (!rs->adaptive) {
        rs->sampler = (RfSampler)s;
        return no_attrs(lx, kw);
    }
    while (!st && next_attr(lx, &a)) {
        if (rf_lex_is(&a, "threshold"))
            st = rf_lex_number_ge(lx, "adaptive threshold", 0.0, &rs->adaptive_threshold);
        else if (rf_lex_is(&a, "depth"))
            st = rf_lex_int(lx, "adaptive depth", 0, 8, &rs->adaptive_depth);
        else
            return bad_attr(lx, kw, &a);
    }
    return st;
}

/* filter box|gaussian|mitchell [radius R] [sigma S] (§3.9 reconstruction) */
static RfStatus read_filter(RfReader *r, const RfToken *kw)
{
    RfLexer *lx = &r->lx;
    RfRenderSettings *rs = &r->scene->render;
    RfToken a;
    int k;
    RfStatus st = read_choice(lx, "filter", "box, gaussian, mitchell", rf_filter_parse, &k);
    if (st)
        return st;
    rs->filter = rf_filter_default((RfFilterKind)k);
    while (!st && next_attr(lx, &a)) {
        if (rf_lex_is(&a, "radius")) {
            if (!(st = rf_lex_number(lx, "filter radius", &rs->filter.radius)))
                st = rf_lex_check(lx, rs->filter.radius > 0.0 && rs->filter.radius <= 16.0,
                                  "filter radius must be in (0, 16] pixels, found %g", rs->filter.radius);
        } else if (rf_lex_is(&a, "sigma") && k == RF_FILTER_GAUSSIAN) {
            if (!(st = rf_lex_number(lx, "filter sigma", &rs->filter.sigma)))
                st = rf_lex_check(lx, rs->filter.sigma > 0.0, "filter sigma must be > 0, found %g", rs->filter.sigma);
        } else {
            return bad_attr(lx, kw, &a);
        }
    }
    return st;
}

static RfStatus read_statement(RfReader *r, const RfToken *kw)
{
    RfLexer *lx = &r->lx;
    RfRenderSettings *rs = &r->scene->render;
    RfStatus st;
    char q[96];
    if (rf_lex_is(kw, "camera"))
        return read_camera(r, kw);
    if (rf_lex_is(kw, "material"))
        return read_material(r, kw);
    if (rf_lex_is(kw, "light"))
        return read_light(r, kw);
    if (rf_lex_is(kw, "object") || rf_lex_is(kw, "group"))
        return read_object(r, kw);
    if (rf_lex_is(kw, "end"))
        return read_end(r, kw);
    if (rf_lex_is(kw, "instance"))
        return read_instance(r, kw);
    if (rf_lex_is(kw, "mesh"))
        return read_mesh(r, kw);
    if (rf_lex_is(kw, "sphere") || rf_lex_is(kw, "plane") || rf_lex_is(kw, "triangle") ||
        rf_lex_is(kw, "polygon") || rf_lex_is(kw, "cone") || rf_lex_is(kw, "cylinder"))
        return read_primitive(r, kw);
    if (rf_lex_is(kw, "use"))
        st = read_material_ref(r, &r->material);
    else if (rf_lex_is(kw, "resolution")) {
        if (!(st = rf_lex_int(lx, "resolution width", 1, 65536, &rs->width)))
            st = rf_lex_int(lx, "resolution height", 1, 65536, &rs->height);
    } else if (rf_lex_is(kw, "depth"))
        st = rf_lex_int(lx, "depth", 1, 1000, &rs->max_depth);
    else if (rf_lex_is(kw, "threshold")) {
        if (!(st = rf_lex_number_ge(lx, "threshold", 0.0, &rs->min_contribution)))
            st = rf_lex_check(lx, rs->min_contribution <= 1.0, "threshold must be in [0, 1]");
    } else if (rf_lex_is(kw, "samples"))
        st = rf_lex_int(lx, "samples", 1, 1 << 20, &rs->samples);
    else if (rf_lex_is(kw, "sampler"))
        return read_sampler(r, kw);
    else if (rf_lex_is(kw, "filter"))
        return read_filter(r, kw);
    else if (rf_lex_is(kw, "shadows")) {
        int m;
        if (!(st = read_choice(lx, "shadow mode", "opaque, filtered", rf_shadow_mode_parse, &m)))
            rs->shadows = (RfShadowMode)m;
    } else if (rf_lex_is(kw, "shutter")) {
        if (!(st = rf_lex_number(lx, "shutter open", &rs->shutter_open)) &&
            !(st = rf_lex_number(lx, "shutter close", &rs->shutter_close)))
            st = rf_lex_check(lx, rs->shutter_open <= rs->shutter_close, "shutter needs open <= close");
    } else if (rf_lex_is(kw, "background"))
        st = read_colour(lx, "background", &rs->background);
    else if (rf_lex_is(kw, "ambient"))
        st = read_colour(lx, "ambient", &rs->ambient);
    else
        return rf_lex_error(lx, kw->line, kw->col, "unknown keyword %s",
                            rf_lex_quote(kw, q, sizeof q));
    return st ? st : no_attrs(lx, kw);
}

RfStatus rf_scene_read_rf(const char *name, const char *text, size_t len, RfScene *scene,
                          char *err, size_t errsz)
{
    return rf__scene_read_rf(name, text, len, NULL, scene, err, errsz);
}

RfStatus rf__scene_read_rf(const char *name, const char *text, size_t len, const RfLoadOptions *opt,
                           RfScene *scene, char *err, size_t errsz)
{
    RfReader r;
    RfStatus st = RF_OK;
    char q[96];
    memset(&r, 0, sizeof r);
    r.threads = opt ? opt->threads : 0;
    r.scene = scene;
    r.material = -1;
    r.object = -1;
    rf_scene_init(scene);
    scene->format = RF_FORMAT_RF;
    rf_lex_init(&r.lx, name, text, len, err, errsz);
    while (!st && r.lx.tok.kind != RF_TOK_EOF) {
        RfToken kw = r.lx.tok;
        if (kw.kind != RF_TOK_WORD || !kw.bol) {
            st = rf_lex_error(&r.lx, kw.line, kw.col, "expected a keyword at the start of a line, found %s",
                              rf_lex_quote(&kw, q, sizeof q));
            break;
        }
        rf_lex_advance(&r.lx);
        st = read_statement(&r, &kw);
    }
    if (!st)
        st = resolve_refs(&r);
    free(r.vbuf);
    free(r.nbuf);
    free(r.refs);
    return rf__reader_finish(&r.lx, scene, st);
}
