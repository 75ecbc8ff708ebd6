/* What the scene exporters share (export_internal.h): buffers, notes, numbers, the material
 * classes, the checks every target shares. Below the writers and export.c, which use it. */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "export_internal.h"

const char *rf_export_format_name(RfExportFormat f)
{
    return f == RF_EXPORT_MITSUBA ? "Mitsuba 3" : f == RF_EXPORT_PBRT ? "pbrt-v4" : "POV-Ray 3.7";
}

/* Makes room for n more bytes and a NUL in a growing buffer; -1 when out of memory. */
static int reserve(char **buf, size_t len, size_t *cap, size_t n)
{
    if (len + n + 1 <= *cap)
        return 0;
    size_t cap2 = *cap ? *cap : 1024;
    while (len + n + 1 > cap2)
        cap2 *= 2;
    char *b = realloc(*buf, cap2);
    if (!b)
        return -1;
    *buf = b;
    *cap = cap2;
    return 0;
}

/* Appends a formatted text to a growing NUL-terminated buffer. */
static int append_v(char **buf, size_t *len, size_t *cap, const char *fmt, va_list ap)
{
    va_list aq;
    va_copy(aq, ap);
    int n = vsnprintf(NULL, 0, fmt, aq);
    va_end(aq);
    if (n < 0 || reserve(buf, *len, cap, (size_t)n))
        return -1;
    vsnprintf(*buf + *len, *cap - *len, fmt, ap);
    *len += (size_t)n;
    return 0;
}

void rf__ex_printf(RfExCtx *c, const char *fmt, ...)
{
    if (!c->out || c->ex->failed)
        return;
    va_list ap;
    va_start(ap, fmt);
    if (append_v(&c->out->text, &c->out->len, &c->out->cap, fmt, ap))
        c->ex->failed = 1;
    va_end(ap);
}

RfExportFile *rf__ex_file(RfExCtx *c, const char *path)
{
    RfExport *ex = c->ex;
    RfExportFile *f = realloc(ex->files, sizeof *f * (ex->file_count + 1));
    char *p = strdup(path);
    if (!f || !p) {
        if (f)
            ex->files = f;
        free(p);
        ex->failed = 1;
        c->out = NULL;
        return NULL;
    }
    ex->files = f;
    f += ex->file_count++;
    memset(f, 0, sizeof *f);
    f->path = p;
    c->out = f;
    return f;
}

void rf__ex_note(RfExCtx *c, RfSrcLoc loc, int problem, const char *fmt, ...)
{
    RfExport *ex = c->ex;
    char head[512];
    const char *src = c->o->source ? c->o->source : "scene";
    if (loc.line > 0)
        snprintf(head, sizeof head, "%s:%d:%d: ", src, loc.line, loc.col);
    else
        snprintf(head, sizeof head, "%s: ", src);
    va_list ap;
    va_start(ap, fmt);
    char body[1024];
    vsnprintf(body, sizeof body, fmt, ap);
    va_end(ap);
    char line[1600];
    snprintf(line, sizeof line, "%s%s%s\n", head, body,
             problem == 1 && c->o->lossy ? " (written approximately: --lossy)" : "");
    if (problem)
        ex->problems++;
    size_t n = strlen(line);
    if (reserve(&ex->notes, ex->notes_len, &ex->notes_cap, n)) {
        ex->failed = 1;
        return;
    }
    memcpy(ex->notes + ex->notes_len, line, n + 1);
    ex->notes_len += n;
}

/* The shortest of %.15g, %.16g, %.17g that reads back as x, into b. */
static void shortest(char *b, size_t size, double x)
{
    if (x == 0.0) /* no "-0" in another renderer's file */
        x = 0.0;
    for (int p = 15; p <= 17; p++) {
        snprintf(b, size, "%.*g", p, x);
        if (strtod(b, NULL) == x)
            break;
    }
}

static char *ring_slot(RfExCtx *c)
{
    char *b = c->ring[c->ring_next];
    c->ring_next = (c->ring_next + 1) % RF_EX_RING;
    return b;
}

const char *rf__ex_num(RfExCtx *c, double x)
{
    char *b = ring_slot(c);
    shortest(b, RF_EX_SLOT, x);
    return b;
}

const char *rf__ex_vec(RfExCtx *c, RfVec3 v, const char *sep)
{
    char a[3][32];
    double x[3] = {v.x, v.y, v.z};
    for (int i = 0; i < 3; i++)
        shortest(a[i], sizeof a[i], x[i]);
    char *b = ring_slot(c);
    snprintf(b, RF_EX_SLOT, "%s%s%s%s%s", a[0], sep, a[1], sep, a[2]);
    return b;
}

const char *rf__ex_rgb(RfExCtx *c, RfRgb v, const char *sep)
{
    return rf__ex_vec(c, rf_vec3(v.r, v.g, v.b), sep);
}

static int positive(RfRgb c) { return c.r > 0.0 || c.g > 0.0 || c.b > 0.0; }

RfExMat rf__ex_classify(const RfScene *s, const RfMaterial *m)
{
    RfExMat x;
    x.diffuse = positive(m->kd);
    x.highlight = rf_material_has_highlight(m);
    x.mirror = positive(m->kr);
    x.transmits = positive(m->kt);
    x.fresnel = (m->flags & RF_MAT_FRESNEL) && (x.mirror || x.transmits);
    x.ambient = positive(rf_rgb_mul(m->ka, s->render.ambient));
    x.emits = positive(m->emission);
    x.glossy = m->gloss > 0.0 && (x.mirror || x.transmits);
    return x;
}

RfVec3 rf__ex_perpendicular(RfVec3 n)
{
    RfVec3 a = fabs(n.x) < 0.6 ? rf_vec3(1, 0, 0) : rf_vec3(0, 1, 0);
    return rf_vec3_normalize(rf_vec3_cross(n, a));
}

void rf__ex_common_header(RfExCtx *c, const char *lead)
{
    const RfScene *s = c->s;
    rf__ex_printf(c, "%swritten by `refray export` from %s for %s (docs/crosscheck.md derives every conversion)\n",
                  lead, c->o->source ? c->o->source : "a scene", rf_export_format_name(c->o->format));
    rf__ex_printf(c, "%simage %d x %d; refray's recursion depth %d (the primary ray is depth 1)\n", lead, c->width,
                  c->height, c->depth);
    if (!s->camera.has_window)
        rf__ex_printf(c, "%scamera: refray's field of view %s deg measured %s gives the window\n", lead,
                      rf__ex_num(c, s->camera.fov),
                      s->camera.fov_reading == RF_FOV_EDGES ? "between the image edges"
                                                            : "between the centres of the outermost pixels (NFF; "
                                                              "refray --nff-fov centres): half-height d tan(fov/2) H/(H-1)");
    rf__ex_printf(c, "%s  l %s r %s b %s t %s at d %s; right-handed: image right = view direction x up\n", lead,
                  rf__ex_num(c, c->win.l), rf__ex_num(c, c->win.r), rf__ex_num(c, c->win.b), rf__ex_num(c, c->win.t),
                  rf__ex_num(c, c->win.d));
    rf__ex_printf(c, "%ssurfaces: %s\n", lead,
                  c->o->two_sided ? "every one visible from both sides (refray --two-sided)"
                                  : "as the scene says (one-sided ones are noted where the target differs)");
    rf__ex_printf(c, "%sshadows of transmitting objects: %s\n", lead,
                  c->filtered ? "filtered by kt, straight through (refray --shadows filtered, POV-Ray's rule)"
                              : "opaque (refray's default)");
}

void rf__ex_common_checks(RfExCtx *c, int area_ok, int lens_ok)
{
    const RfScene *s = c->s;
    const char *to = rf_export_format_name(c->o->format);
    /* only materials a primitive uses, each noted once */
    unsigned char *used = rf__ex_used_materials(c);
    if (!used)
        return;
    for (size_t i = 0; i < s->material_count; i++) {
        if (!used[i])
            continue;
        const RfMaterial *m = &s->materials[i];
        RfExMat x = rf__ex_classify(s, m);
        if (x.ambient)
            rf__ex_note(c, m->loc, 1, "material '%s': ambient term ka * ambient light: %s has no ambient term "
                        "(dropped)", m->name, to);
        if (x.emits)
            rf__ex_note(c, m->loc, 1, "material '%s': emission: refray adds it to the surface's radiance only, "
                        "an emitter in %s would light other surfaces (dropped)", m->name, to);
        if (x.transmits && c->filtered && c->o->format != RF_EXPORT_POV)
            rf__ex_note(c, m->loc, 1, "material '%s' transmits and shadows are filtered: %s's shadow rays stop "
                        "at every surface (written opaque; render refray with --shadows opaque)", m->name, to);
        if (x.glossy)
            rf__ex_note(c, m->loc, 1, "material '%s': glossy %s: refray's cos^N lobe around the ideal ray has no "
                        "counterpart in %s (written as ideal)", m->name, rf__ex_num(c, m->gloss), to);
    }
    free(used);
    for (size_t i = 0; c->o->format != RF_EXPORT_POV && i < s->light_count; i++) {
        const RfLight *l = &s->lights[i];
        if (l->kind != RF_LIGHT_DIRECTIONAL && !rf_light_is_area(l->kind) && l->falloff == RF_FALLOFF_NONE)
            rf__ex_note(c, l->loc, 1, "%s light without falloff (NFF's convention): %s's lights fall off with the "
                        "squared distance (written with it)", rf_light_kind_name(l->kind), to);
        if (l->kind == RF_LIGHT_SPOT && l->spot_exponent != 0.0)
            rf__ex_note(c, l->loc, 1, "spot light with exponent %s: %s's spot has no cos^n term, only a fade to "
                        "its edge (written without it)", rf__ex_num(c, l->spot_exponent), to);
    }
    if (!area_ok)
        for (size_t i = 0; i < s->light_count; i++)
            if (rf_light_is_area(s->lights[i].kind))
                rf__ex_note(c, s->lights[i].loc, 1, "light %zu: %s area light: %s has no area light with refray's "
                            "sampling (written as a point light at its centre)", i,
                            rf_light_kind_name(s->lights[i].kind), to);
    if (!lens_ok && s->camera.aperture > 0.0)
        rf__ex_note(c, s->camera.loc, 1, "camera: thin lens (aperture %s): %s's focal blur is another lens model "
                    "(written as a pinhole)", rf__ex_num(c, s->camera.aperture), to);
    if (s->render.samples > 1 && c->o->format == RF_EXPORT_POV)
        rf__ex_note(c, s->camera.loc, 0,
                    "%d samples per pixel: POV-Ray's anti-aliasing is its own (render refray with 1 sample and "
                    "POV-Ray with -A to compare)", s->render.samples);
}

void rf__ex_check_hither(RfExCtx *c)
{
    const RfScene *s = c->s;
    if (!(s->camera.hither > 0.0))
        return;
    /* nothing nearer than hither along the view axis: the near plane cuts nothing */
    RfVec3 lo, hi;
    int planes = 0;
    for (size_t i = 0; i < s->prim_count; i++)
        planes |= s->prims[i].type == RF_PRIM_PLANE && !(s->prims[i].flags & RF_PRIM_IN_OBJECT);
    if (!planes && rf_scene_bounds(s, &lo, &hi)) {
        double near = INFINITY;
        for (int k = 0; k < 8; k++) {
            RfVec3 p = rf_vec3(k & 1 ? hi.x : lo.x, k & 2 ? hi.y : lo.y, k & 4 ? hi.z : lo.z);
            near = fmin(near, -rf_vec3_dot(rf_vec3_sub(p, s->camera.eye), c->w));
        }
        if (near >= s->camera.hither)
            return;
    }
    /* only a note: whether a primary ray meets something nearer is the render's question */
    rf__ex_note(c, s->camera.loc, 0, "camera: hither %s: %s's camera has no near plane; the scene's bounds reach "
                "nearer, so compare the images there with care", rf__ex_num(c, s->camera.hither),
                rf_export_format_name(c->o->format));
}

const RfPrimitive *rf__ex_world_prim(const RfScene *s, const RfPrimitive *p, const RfInstance **placement)
{
    *placement = NULL;
    if (p->flags & RF_PRIM_IN_OBJECT) /* written with its placement, if at all */
        return NULL;
    if (p->type != RF_PRIM_INSTANCE)
        return p;
    const RfInstance *in = &s->instances[p->u.instance];
    const RfSceneObject *ob = &s->objects[in->object];
    const RfPrimitive *q = &s->prims[ob->first];
    if (ob->count != 1 || (q->type != RF_PRIM_SPHERE && q->type != RF_PRIM_CONE))
        return NULL;
    *placement = in;
    return q;
}

unsigned char *rf__ex_used_materials(RfExCtx *c)
{
    const RfScene *s = c->s;
    unsigned char *used = calloc(s->material_count ? s->material_count : 1, 1);
    if (!used) {
        c->ex->failed = 1;
        return NULL;
    }
    for (size_t i = 0; i < s->prim_count; i++) {
        const RfInstance *placement;
        const RfPrimitive *p = rf__ex_world_prim(s, &s->prims[i], &placement);
        if (p && p->material >= 0 && (size_t)p->material < s->material_count)
            used[p->material] |= (p->flags & RF_PRIM_TWO_SIDED) || c->o->two_sided ? 2 : 1;
    }
    return used;
}

void rf__ex_note_one_sided(RfExCtx *c, const char *back)
{
    const RfScene *s = c->s;
    size_t n = 0;
    RfSrcLoc first = {0, 0};
    if (c->o->two_sided)
        return;
    for (size_t i = 0; i < s->prim_count; i++) {
        const RfInstance *placement;
        const RfPrimitive *p = rf__ex_world_prim(s, &s->prims[i], &placement);
        /* a sphere's back is seen only from inside it */
        if (p && !(p->flags & RF_PRIM_TWO_SIDED) && p->type != RF_PRIM_SPHERE && !n++)
            first = p->loc;
    }
    if (n)
        rf__ex_note(c, first, 0, "%zu one-sided primitives (the first here): refray lets rays through their back, "
                    "%s %s (render refray with --two-sided to compare where a back is seen)", n,
                    rf_export_format_name(c->o->format), back);
}

