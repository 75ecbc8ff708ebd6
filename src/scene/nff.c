/* refray: the NFF reader (shared/NFF.md). Takes the Standard Procedural Databases unchanged.
 *
 * Line breaks carry no meaning (the SPD writes a cone's 8 numbers on one line, the NFF text on
 * three), so the file is read as a stream of tokens: a keyword, then its numbers.
 *
 * Mapping onto the model (docs/scene-format.md has the table):
 *   v            camera: eye = from, target = at, up, fov = angle read as options->nff_fov
 *                (default RF_FOV_PIXEL_CENTRES, the NFF text), d = 1, hither, resolution;
 *                `hither` and `resolution` may be left out (0 and 512 x 512)
 *   b r g b      background
 *   l x y z [rgb] point light without falloff; intensity rgb, or 1/sqrt(number of lights) in
 *                each channel when no colour is given (the SPD convention, DESIGN.md)
 *   f r g b Kd Ks Shine T ior
 *                kd = Kd * (r,g,b); ks = Ks * (1,1,1): a white highlight, as the SPD's own POV-Ray
 *                output writes `phong Ks` (the highlight has the light's colour, as on a
 *                dielectric); shininess = Shine; kr = Ks * (1,1,1) (NFF.md: Ks is also the mirror
 *                weight); kt = T * (1,1,1); ior (0 with T = 0 in some SPD files: stored as 1,
 *                nothing refracts); ka = 0 (NFF has no ambient term); smooth; no Fresnel
 *   c            cone: base, base radius, apex, apex radius; both radii negative -> inside only
 *   s x y z r    sphere; r < 0 -> inside only
 *   p n / pp n   n = 3 -> triangle, n > 3 -> polygon; pp adds a unit normal per vertex
 * Objects are one-sided unless the current material has T > 0. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "reader.h"
#include "refray/scene_io.h"

/* Upper bound on the vertices of one polygon: far above any SPD polygon (144), low enough
 * that a corrupt count fails at once instead of after reading the rest of the file. */
#define NFF_MAX_POLY_VERTICES 1000000

typedef struct {
    RfLexer lx;
    RfScene *scene;
    const RfLoadOptions *opt;
    int material;   /* current material, -1 before the first `f` */
    int two_sided;  /* the current material transmits */
    unsigned char *coloured; /* per light: 1 when the file gave its colour */
    size_t coloured_cap;
} NffReader;

/* One line of the viewpoint block: the word `key` followed by its values. */
static RfStatus view_key(NffReader *r, const char *key, RfToken *kw)
{
    char q[96];
    RfLexer *lx = &r->lx;
    if (!rf_lex_is(&lx->tok, key))
        return rf_lex_error(lx, lx->tok.line, lx->tok.col,
                            "expected '%s' in the viewpoint (v), found %s", key,
                            rf_lex_quote(&lx->tok, q, sizeof q));
    *kw = lx->tok;
    rf_lex_advance(lx);
    return RF_OK;
}

static RfStatus read_view(NffReader *r, const RfToken *v)
{
    RfLexer *lx = &r->lx;
    RfScene *s = r->scene;
    RfSceneCamera *c = &s->camera;
    RfToken kw;
    RfStatus st;
    memset(&kw, 0, sizeof kw); /* set by view_key on success; -O3 cannot see that */
    if (s->has_camera)
        return rf_lex_error(lx, v->line, v->col, "second viewpoint (v): the scene has one camera");
    memset(c, 0, sizeof *c);
    c->loc = rf__token_loc(v);
    c->d = 1.0;
    c->fov_reading = r->opt->nff_fov;
    if ((st = view_key(r, "from", &kw)) || (st = rf_lex_vec3(lx, "from", &c->eye)) ||
        (st = view_key(r, "at", &kw)) || (st = rf_lex_vec3(lx, "at", &c->target)))
        return st;
    c->target_loc = rf__token_loc(&kw);
    if ((st = view_key(r, "up", &kw)) || (st = rf_lex_vec3(lx, "up", &c->up)))
        return st;
    c->up_loc = rf__token_loc(&kw);
    if ((st = view_key(r, "angle", &kw)) || (st = rf_lex_number(lx, "angle", &c->fov)) ||
        (st = rf_lex_check(lx, c->fov > 0.0 && c->fov < 180.0,
                           "angle must be in (0, 180) degrees, found %g", c->fov)))
        return st;
    if (rf_lex_is(&lx->tok, "hither")) {
        rf_lex_advance(lx);
        if ((st = rf_lex_number_ge(lx, "hither", 0.0, &c->hither)))
            return st;
    }
    if (rf_lex_is(&lx->tok, "resolution")) {
        rf_lex_advance(lx);
        if ((st = rf_lex_int(lx, "resolution width", 1, 65536, &s->render.width)) ||
            (st = rf_lex_int(lx, "resolution height", 1, 65536, &s->render.height)))
            return st;
    }
    s->has_camera = 1;
    return rf__reader_check_camera(lx, c);
}

static RfStatus read_light(NffReader *r, const RfToken *kw)
{
    RfLight l;
    RfStatus st;
    memset(&l, 0, sizeof l);
    l.kind = RF_LIGHT_POINT;
    l.falloff = RF_FALLOFF_NONE;
    l.loc = rf__token_loc(kw);
    if ((st = rf_lex_vec3(&r->lx, "light position", &l.position)))
        return st;
    int coloured = r->lx.tok.kind == RF_TOK_NUMBER && !r->lx.tok.bol;
    if (coloured && (st = rf_lex_rgb(&r->lx, "light colour", &l.intensity)))
        return st;
    size_t n = r->scene->light_count;
    if (n >= r->coloured_cap) {
        size_t cap = r->coloured_cap ? 2 * r->coloured_cap : 16;
        unsigned char *p = realloc(r->coloured, cap);
        if (!p)
            return rf_lex_error(&r->lx, kw->line, kw->col, "out of memory");
        r->coloured = p;
        r->coloured_cap = cap;
    }
    r->coloured[n] = (unsigned char)coloured;
    if (rf_scene_add_light(r->scene, &l))
        return rf_lex_error(&r->lx, kw->line, kw->col, "out of memory");
    return RF_OK;
}

static RfStatus read_material(NffReader *r, const RfToken *kw)
{
    RfLexer *lx = &r->lx;
    RfMaterial m = rf_material_default();
    RfRgb colour;
    double kd, ks, shine, t, ior;
    RfStatus st;
    if ((st = rf_lex_rgb(lx, "material colour", &colour)) ||
        (st = rf_lex_number_ge(lx, "Kd", 0.0, &kd)) || (st = rf_lex_number_ge(lx, "Ks", 0.0, &ks)) ||
        (st = rf_lex_number_ge(lx, "Shine", 0.0, &shine)) ||
        (st = rf_lex_number_ge(lx, "T", 0.0, &t)) || (st = rf_lex_number_ge(lx, "ior", 0.0, &ior)) ||
        (st = rf_lex_check(lx, ior > 0.0 || t == 0.0,
                           "ior must be > 0 for a transmitting material (T = %g)", t)))
        return st;
    snprintf(m.name, sizeof m.name, "f@%d", kw->line);
    m.kd = rf_rgb_scale(colour, kd);
    m.ks = rf_rgb(ks, ks, ks);
    m.shininess = shine;
    m.kr = m.ks;
    m.kt = rf_rgb(t, t, t);
    m.ior = ior > 0.0 ? ior : 1.0;
    m.loc = rf__token_loc(kw);
    if (rf_scene_add_material(r->scene, &m, &r->material))
        return rf_lex_error(lx, kw->line, kw->col, "out of memory");
    r->two_sided = t > 0.0;
    return RF_OK;
}

static RfPrimitive new_prim(NffReader *r, RfPrimType type, const RfToken *kw)
{
    RfPrimitive p;
    memset(&p, 0, sizeof p);
    p.type = type;
    p.material = r->material;
    p.flags = r->two_sided ? RF_PRIM_TWO_SIDED : 0;
    p.loc = rf__token_loc(kw);
    return p;
}

static RfStatus read_sphere(NffReader *r, const RfToken *kw)
{
    RfPrimitive p = new_prim(r, RF_PRIM_SPHERE, kw);
    RfStatus st;
    if ((st = rf_lex_vec3(&r->lx, "sphere centre", &p.u.sphere.center)) ||
        (st = rf_lex_number(&r->lx, "sphere radius", &p.u.sphere.radius)))
        return st;
    if (p.u.sphere.radius < 0.0) {
        p.u.sphere.radius = -p.u.sphere.radius;
        p.flags |= RF_PRIM_INSIDE;
    }
    return rf__reader_add_prim(&r->lx, r->scene, &p);
}

static RfStatus read_cone(NffReader *r, const RfToken *kw)
{
    RfPrimitive p = new_prim(r, RF_PRIM_CONE, kw);
    RfLexer *lx = &r->lx;
    double *rb = &p.u.cone.base_radius, *ra = &p.u.cone.apex_radius;
    RfStatus st;
    if ((st = rf_lex_vec3(lx, "cone base", &p.u.cone.base)) ||
        (st = rf_lex_number(lx, "cone base radius", rb)) ||
        (st = rf_lex_vec3(lx, "cone apex", &p.u.cone.apex)) ||
        (st = rf_lex_number(lx, "cone apex radius", ra)) ||
        (st = rf_lex_check(lx, (*rb < 0.0) == (*ra < 0.0) || *rb == 0.0 || *ra == 0.0,
                           "cone radii must both be >= 0, or both < 0 (inside only)")))
        return st;
    if (*rb < 0.0 || *ra < 0.0) {
        *rb = fabs(*rb);
        *ra = fabs(*ra);
        p.flags |= RF_PRIM_INSIDE;
    }
    return rf__reader_add_prim(lx, r->scene, &p);
}

static RfStatus read_polygon(NffReader *r, const RfToken *kw, int patch)
{
    RfLexer *lx = &r->lx;
    int n;
    RfStatus st = rf_lex_int(lx, "polygon vertex count", 3, NFF_MAX_POLY_VERTICES, &n);
    if (st)
        return st;
    RfPrimitive p = new_prim(r, n == 3 ? RF_PRIM_TRIANGLE : RF_PRIM_POLYGON, kw);
    p.u.poly.count = n;
    if (patch)
        p.flags |= RF_PRIM_VERTEX_NORMALS;
    for (int i = 0; i < n; i++) {
        RfVec3 v, vn;
        if ((st = rf_lex_vec3(lx, "polygon vertex", &v)) ||
            (patch && (st = rf_lex_vec3(lx, "vertex normal", &vn))) ||
            (st = rf__reader_add_vertex(lx, r->scene, v, patch ? &vn : NULL,
                                        i == 0 ? &p.u.poly.first : NULL,
                                        i == 0 ? &p.u.poly.nfirst : NULL)))
            return st;
    }
    return rf__reader_add_prim(lx, r->scene, &p);
}

static RfStatus read_all(NffReader *r)
{
    RfLexer *lx = &r->lx;
    RfScene *s = r->scene;
    RfStatus st = RF_OK;
    char q[96];
    while (!st && lx->tok.kind != RF_TOK_EOF) {
        RfToken kw = lx->tok;
        if (kw.kind != RF_TOK_WORD)
            return rf_lex_error(lx, kw.line, kw.col, "expected a keyword, found %s",
                                rf_lex_quote(&kw, q, sizeof q));
        rf_lex_advance(lx);
        if (rf_lex_is(&kw, "v"))
            st = read_view(r, &kw);
        else if (rf_lex_is(&kw, "b"))
            st = rf_lex_rgb(lx, "background colour", &s->render.background);
        else if (rf_lex_is(&kw, "l"))
            st = read_light(r, &kw);
        else if (rf_lex_is(&kw, "f"))
            st = read_material(r, &kw);
        else if (rf_lex_is(&kw, "s") || rf_lex_is(&kw, "c") || rf_lex_is(&kw, "p") ||
                 rf_lex_is(&kw, "pp")) {
            st = rf__reader_default_material(lx, s, &kw, &r->material);
            if (!st)
                st = kw.s[0] == 's'   ? read_sphere(r, &kw)
                     : kw.s[0] == 'c' ? read_cone(r, &kw)
                                      : read_polygon(r, &kw, kw.len == 2);
        }
        else
            return rf_lex_error(lx, kw.line, kw.col, "unknown NFF keyword %s",
                                rf_lex_quote(&kw, q, sizeof q));
    }
    if (st)
        return st;
    /* SPD convention: lights without a colour get 1/sqrt(number of lights) each */
    double share = s->light_count ? 1.0 / sqrt((double)s->light_count) : 0.0;
    for (size_t i = 0; i < s->light_count; i++)
        if (!r->coloured[i])
            s->lights[i].intensity = rf_rgb(share, share, share);
    return RF_OK;
}

RfStatus rf_scene_read_nff(const char *name, const char *text, size_t len,
                           const RfLoadOptions *opt, RfScene *scene, char *err, size_t errsz)
{
    NffReader r;
    RfLoadOptions def = rf_load_options_default();
    memset(&r, 0, sizeof r);
    r.scene = scene;
    r.opt = opt ? opt : &def;
    r.material = -1;
    rf_scene_init(scene);
    scene->format = RF_FORMAT_NFF;
    rf_lex_init(&r.lx, name, text, len, err, errsz);
    RfStatus st = read_all(&r);
    free(r.coloured);
    return rf__reader_finish(&r.lx, scene, st);
}
