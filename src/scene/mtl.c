/* refray: the Wavefront MTL reader. Each `newmtl` becomes one RfMaterial; the illumination
 * model (`illum` 0-9) decides which of refray's rays and terms the material turns on — the
 * table in docs/scene-format.md "MTL", after the Alias|Wavefront "File Formats 4.2" ch. 5
 * formulas (shared/research/ecosystem.md §4):
 *
 *   0  colour = Kd, no lighting            -> emission Kd (+ Ke), ka = kd = ks = 0
 *   1  Ka Ia + Kd sum(N.L) I               -> ka, kd; ks = 0
 *   2  + Ks sum((R.V)^Ns) I (Phong, §3.6.2) -> ka, kd, ks, Ns
 *   3  + Ks Ir: reflection ray on          -> + kr = Ks
 *   4  glass: as 3, dissolve d             -> + kt = 1 - d, ior 1 (no bending)
 *   5  Fresnel reflection                  -> kr = Ks, fresnel, ior Ni
 *   6  refraction, Fresnel off             -> kr = Ks, kt = (1 - Ks) Tf, ior Ni
 *   7  refraction + Fresnel                -> kr = Ks, kt = (1 - Ks) Tf, fresnel, ior Ni
 *   8, 9  as 3, 4 with ray tracing off     -> as 2 (refray has no reflection maps)
 *
 * Texture maps, `bump`, `disp`, `decal`, `refl`, `sharpness` and vendor keywords are ignored;
 * `Tr` is ignored as well (tools disagree whether it is d or 1 - d). Errors are
 * "file:line:col: message" as in the other readers. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "reader.h"
#include "refray/scene_io.h"

typedef struct {
    RfRgb ka, kd, ks, ke, tf;
    double ns, ni, d;
    int illum, has_ni;
    char name[RF_NAME_MAX];
    RfSrcLoc loc;
} MtlParams;

static void mtl_defaults(MtlParams *p)
{
    memset(p, 0, sizeof *p);
    p->kd = rf_rgb(0.8, 0.8, 0.8);
    p->tf = rf_rgb(1, 1, 1);
    p->ni = 1.0;
    p->d = 1.0;
    p->illum = 2;
}

static RfRgb one_minus(RfRgb c)
{
    return rf_rgb(c.r < 1.0 ? 1.0 - c.r : 0.0, c.g < 1.0 ? 1.0 - c.g : 0.0,
                  c.b < 1.0 ? 1.0 - c.b : 0.0);
}

/* The illumination model onto refray's material (the table at the top). A Fresnel model
 * without Ni gets 1.5: with the MTL default 1.0 the dielectric F would be 0 everywhere. */
static RfMaterial mtl_to_material(const MtlParams *p)
{
    RfMaterial m = rf_material_default();
    memcpy(m.name, p->name, sizeof m.name);
    m.loc = p->loc;
    m.ka = p->ka;
    m.kd = p->kd;
    m.ks = p->ks;
    m.shininess = p->ns;
    m.emission = p->ke;
    m.ior = p->ni;
    switch (p->illum) {
    case 0:
        m.emission = rf_rgb_add(p->kd, p->ke);
        m.ka = m.kd = m.ks = rf_rgb(0, 0, 0);
        break;
    case 1:
        m.ks = rf_rgb(0, 0, 0);
        break;
    case 3:
        m.kr = p->ks;
        break;
    case 4:
        m.kr = p->ks;
        m.kt = rf_rgb(1.0 - p->d, 1.0 - p->d, 1.0 - p->d);
        m.ior = 1.0;
        break;
    case 5:
    case 7:
        m.kr = p->ks;
        m.flags |= RF_MAT_FRESNEL;
        if (!p->has_ni)
            m.ior = 1.5;
        if (p->illum == 7)
            m.kt = rf_rgb_mul(one_minus(p->ks), p->tf);
        break;
    case 6:
        m.kr = p->ks;
        m.kt = rf_rgb_mul(one_minus(p->ks), p->tf);
        break;
    default: /* 2, 8, 9 */
        break;
    }
    return m;
}

static int eol(const RfLexer *lx) { return lx->tok.kind == RF_TOK_EOF || lx->tok.bol; }

static void skip_line(RfLexer *lx)
{
    while (!eol(lx))
        rf_lex_advance(lx);
}

/* `K? r [g b]`; the spectral and xyz forms are refused. */
static RfStatus read_colour(RfLexer *lx, const char *what, RfRgb *c)
{
    char q[96];
    if (lx->tok.kind == RF_TOK_WORD && !eol(lx))
        return rf_lex_error(lx, lx->tok.line, lx->tok.col,
                            "%s: the %s form is not supported (give r g b)", what,
                            rf_lex_quote(&lx->tok, q, sizeof q));
    RfStatus st = rf_lex_number_ge(lx, what, 0.0, &c->r);
    if (st)
        return st;
    if (eol(lx)) {
        c->g = c->b = c->r;
        return RF_OK;
    }
    if ((st = rf_lex_number_ge(lx, what, 0.0, &c->g)) || (st = rf_lex_number_ge(lx, what, 0.0, &c->b)))
        return st;
    return RF_OK;
}

/* Appends the material unless one of that name exists (the first definition wins, so two
 * OBJ files may share one library). */
static RfStatus finish(RfLexer *lx, RfScene *scene, const MtlParams *p)
{
    for (size_t i = 0; i < scene->material_count; i++)
        if (strcmp(scene->materials[i].name, p->name) == 0)
            return RF_OK;
    RfMaterial m = mtl_to_material(p);
    if (rf_scene_add_material(scene, &m, NULL))
        return rf_lex_error(lx, p->loc.line, p->loc.col, "out of memory");
    return RF_OK;
}

static RfStatus read_statement(RfLexer *lx, const RfToken *kw, MtlParams *p, int have)
{
    char q[96];
    if (!have)
        return rf_lex_error(lx, kw->line, kw->col, "%s before the first 'newmtl'",
                            rf_lex_quote(kw, q, sizeof q));
    if (rf_lex_is(kw, "Ka"))
        return read_colour(lx, "Ka", &p->ka);
    if (rf_lex_is(kw, "Kd"))
        return read_colour(lx, "Kd", &p->kd);
    if (rf_lex_is(kw, "Ks"))
        return read_colour(lx, "Ks", &p->ks);
    if (rf_lex_is(kw, "Ke"))
        return read_colour(lx, "Ke", &p->ke);
    if (rf_lex_is(kw, "Tf"))
        return read_colour(lx, "Tf", &p->tf);
    if (rf_lex_is(kw, "Ns"))
        return rf_lex_number_ge(lx, "Ns", 0.0, &p->ns);
    if (rf_lex_is(kw, "Ni")) {
        RfStatus st = rf_lex_number(lx, "Ni", &p->ni);
        p->has_ni = 1;
        return st ? st : rf_lex_check(lx, p->ni > 0.0, "Ni must be > 0, found %g", p->ni);
    }
    if (rf_lex_is(kw, "d")) {
        if (lx->tok.len == 5 && memcmp(lx->tok.s, "-halo", 5) == 0)
            rf_lex_advance(lx); /* the halo form: refray takes the plain dissolve */
        RfStatus st = rf_lex_number(lx, "d", &p->d);
        return st ? st : rf_lex_check(lx, p->d >= 0.0 && p->d <= 1.0, "d must be in [0, 1], found %g", p->d);
    }
    if (rf_lex_is(kw, "illum")) {
        RfStatus st = rf_lex_int(lx, "illum", 0, 10, &p->illum);
        if (!st && p->illum == 10)
            st = rf_lex_check(lx, 0, "illum 10 (shadow matte) is not supported: refray maps 0-9");
        return st;
    }
    skip_line(lx); /* maps, Tr and extensions: ignored */
    return RF_OK;
}

RfStatus rf_scene_read_mtl(const char *name, const char *text, size_t len, RfScene *scene,
                           char *err, size_t errsz)
{
    RfLexer lx;
    MtlParams p;
    int have = 0;
    char q[96], q2[96];
    RfStatus st = RF_OK;
    rf_lex_init(&lx, name, text, len, err, errsz);
    mtl_defaults(&p);
    while (!st && lx.tok.kind != RF_TOK_EOF) {
        RfToken kw = lx.tok;
        if (kw.kind != RF_TOK_WORD || !kw.bol) {
            st = rf_lex_error(&lx, kw.line, kw.col, "expected an MTL keyword, found %s",
                              rf_lex_quote(&kw, q, sizeof q));
            break;
        }
        rf_lex_advance(&lx);
        if (rf_lex_is(&kw, "newmtl")) {
            RfToken nm;
            if (have && (st = finish(&lx, scene, &p)))
                break;
            if (eol(&lx)) {
                st = rf_lex_error(&lx, lx.last_end_line, lx.last_end_col,
                                  "newmtl needs a material name");
                break;
            }
            nm = lx.tok;
            rf_lex_advance(&lx);
            if (nm.len >= RF_NAME_MAX) {
                st = rf_lex_error(&lx, nm.line, nm.col, "material name %s is longer than %d bytes",
                                  rf_lex_quote(&nm, q, sizeof q), RF_NAME_MAX - 1);
                break;
            }
            mtl_defaults(&p);
            memcpy(p.name, nm.s, nm.len);
            p.name[nm.len] = 0;
            p.loc = rf__token_loc(&kw);
            have = 1;
        } else {
            st = read_statement(&lx, &kw, &p, have);
        }
        if (!st && !eol(&lx))
            st = rf_lex_error(&lx, lx.tok.line, lx.tok.col, "too many values for %s: %s",
                              rf_lex_quote(&kw, q, sizeof q), rf_lex_quote(&lx.tok, q2, sizeof q2));
    }
    if (!st && have)
        st = finish(&lx, scene, &p);
    return st;
}
