/* refray: the Wavefront OBJ reader (docs/scene-format.md "OBJ and MTL").
 *
 * Statements: v (x y z, an optional w or r g b is ignored), vt (counted, for index checks),
 * vn, f / fo with every index form (v, v/vt, v//vn, v/vt/vn; negative indices count back from
 * the last one defined), o and g (names, accepted), s (smoothing group; `s off` / `s 0` shade
 * flat), usemtl, mtllib (paths relative to the OBJ file). Free-form geometry and display
 * statements (l, p, curv, surf, ...) are skipped; any other keyword is an error.
 *
 * Faces: a triangle becomes RF_PRIM_TRIANGLE, a larger face RF_PRIM_POLYGON (a convex one is
 * fanned by the tracer; a concave planar one is marked non-convex by the model and
 * intersected with the point-in-polygon test, shaded flat). Faces of zero area are dropped.
 * Indices must refer to vertices defined earlier in the file.
 *
 * Normals (§3.6.3): `vn` where the face gives them; otherwise, in a smoothing group, per
 * corner the normalised sum of the area vectors (cross products, area-weighted, not divided by
 * a count) of the faces of that group around the vertex whose normals lie within the crease
 * angle of this face's normal. A face with `s off` gets no vertex normals (flat). Files
 * without `s` are smoothed (group 1): the crease angle keeps their hard edges. */
#include <limits.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "reader.h"
#include "refray/hash.h"
#include "refray/numeric.h"
#include "refray/parallel.h"
#include "refray/scene_io.h"

#define RF_OBJ_PATH_MAX 4096

typedef struct { long v, vn; } Corner; /* 0-based; vn = -1 without a normal */

typedef struct {
    size_t first; /* into corners */
    int n;
    int material; /* -1: the placement's */
    long group;   /* smoothing group, 0 = off (flat) */
    int has_vn;
    RfSrcLoc loc;
} Face;

typedef struct {
    RfLexer lx;
    RfScene *scene;
    const RfObjPlacement *pl;
    RfVec3 *pos, *nrm;
    size_t npos, nnrm, ntex, cap_pos, cap_nrm;
    Corner *corners;
    size_t ncorners, cap_corners;
    Face *faces;
    size_t nfaces, cap_faces;
    int material; /* current material, -1: the placement's */
    long group;
    int fixed;    /* the arrays are sized already (one chunk of a parallel parse): never grown */
    int threads;  /* the placement's thread count, 0 resolved to one per processor */
} ObjReader;

static int grow(void **arr, size_t *cap, size_t count, size_t elem)
{
    if (count < *cap)
        return 1;
    size_t c = *cap ? *cap * 2 : 256;
    if (c > SIZE_MAX / elem)
        return 0;
    void *p = realloc(*arr, c * elem);
    if (!p)
        return 0;
    *arr = p;
    *cap = c;
    return 1;
}

/* Room for one more element: grown, or, in a chunk of a parallel parse, within the chunk's
 * share (counted before; a line that does not fit is read line by line). */
static int room(const ObjReader *r, void **arr, size_t *cap, size_t count, size_t elem)
{
    return r->fixed ? count < *cap : grow(arr, cap, count, elem);
}

static int eol(const RfLexer *lx) { return lx->tok.kind == RF_TOK_EOF || lx->tok.bol; }

static void skip_line(RfLexer *lx)
{
    while (!eol(lx))
        rf_lex_advance(lx);
}

static RfStatus oom(ObjReader *r) { return rf_lex_error(&r->lx, r->lx.last.line, r->lx.last.col, "out of memory"); }

/* v x y z [w | r g b]: the optional values are read (they must be numbers) and ignored. */
static RfStatus read_vertex(ObjReader *r, const RfToken *kw)
{
    RfVec3 v;
    double extra;
    int n = 0;
    RfStatus st = rf_lex_vec3(&r->lx, "vertex coordinate", &v);
    while (!st && !eol(&r->lx) && n < 4) {
        st = rf_lex_number(&r->lx, "vertex w or colour", &extra);
        n++;
    }
    if (!st && (n == 2 || n > 3))
        st = rf_lex_error(&r->lx, r->lx.last.line, r->lx.last.col,
                          "'v' takes x y z and an optional w or r g b, found %d extra numbers", n);
    if (st)
        return st;
    if (!room(r, (void **)&r->pos, &r->cap_pos, r->npos, sizeof *r->pos))
        return oom(r);
    r->pos[r->npos++] = v;
    (void)kw;
    return RF_OK;
}

static RfStatus read_normal(ObjReader *r)
{
    RfVec3 n;
    RfStatus st = rf_lex_vec3(&r->lx, "normal component", &n);
    if (st)
        return st;
    if (!room(r, (void **)&r->nrm, &r->cap_nrm, r->nnrm, sizeof *r->nrm))
        return oom(r);
    r->nrm[r->nnrm++] = n;
    return RF_OK;
}

/* vt u [v [w]] */
static RfStatus read_texcoord(ObjReader *r)
{
    double t;
    int n = 0;
    RfStatus st = rf_lex_number(&r->lx, "texture coordinate", &t);
    while (!st && !eol(&r->lx) && n < 2) {
        st = rf_lex_number(&r->lx, "texture coordinate", &t);
        n++;
    }
    r->ntex++;
    return st;
}

/* One index of a face corner: 1-based or negative (relative to the last `count` defined). */
static RfStatus resolve(ObjReader *r, const RfToken *t, const char *s, size_t len, size_t count,
                        const char *what, long *out)
{
    char buf[32], q[96];
    char *end = NULL;
    if (len == 0 || len >= sizeof buf)
        return rf_lex_error(&r->lx, t->line, t->col, "malformed face corner %s (v, v/vt, v//vn or v/vt/vn)",
                            rf_lex_quote(t, q, sizeof q));
    memcpy(buf, s, len);
    buf[len] = 0;
    long v = strtol(buf, &end, 10);
    if (*end)
        return rf_lex_error(&r->lx, t->line, t->col, "malformed face corner %s (v, v/vt, v//vn or v/vt/vn)",
                            rf_lex_quote(t, q, sizeof q));
    if (v == 0)
        return rf_lex_error(&r->lx, t->line, t->col, "%s index 0 in %s: OBJ indices start at 1",
                            what, rf_lex_quote(t, q, sizeof q));
    long idx = v > 0 ? v - 1 : (long)count + v;
    if (idx < 0 || (size_t)idx >= count)
        return rf_lex_error(&r->lx, t->line, t->col, "%s index %ld out of range in %s (%zu defined so far)",
                            what, v, rf_lex_quote(t, q, sizeof q), count);
    *out = idx;
    return RF_OK;
}

/* A corner token; *form gets 0 (v), 1 (v/vt), 2 (v//vn) or 3 (v/vt/vn). */
static RfStatus read_corner(ObjReader *r, const RfToken *t, Corner *c, int *form)
{
    const char *s = t->s, *end = t->s + t->len;
    const char *s1 = memchr(s, '/', t->len);
    const char *s2 = s1 ? memchr(s1 + 1, '/', (size_t)(end - s1 - 1)) : NULL;
    long vt;
    RfStatus st = resolve(r, t, s, (size_t)((s1 ? s1 : end) - s), r->npos, "vertex", &c->v);
    c->vn = -1;
    *form = 0;
    if (st || !s1)
        return st;
    const char *tex = s1 + 1, *tex_end = s2 ? s2 : end;
    if (tex_end > tex && (st = resolve(r, t, tex, (size_t)(tex_end - tex), r->ntex, "texture", &vt)))
        return st;
    *form = tex_end > tex ? 1 : 2;
    if (!s2) {
        if (*form == 2) /* "v/" */
            return resolve(r, t, tex, 0, 0, "texture", &vt);
        return RF_OK;
    }
    *form = tex_end > tex ? 3 : 2;
    return resolve(r, t, s2 + 1, (size_t)(end - s2 - 1), r->nnrm, "normal", &c->vn);
}

static RfStatus read_face(ObjReader *r, const RfToken *kw)
{
    static const char *const forms[] = {"v", "v/vt", "v//vn", "v/vt/vn"};
    Face f;
    char q[96];
    int form0 = -1;
    memset(&f, 0, sizeof f);
    f.first = r->ncorners;
    f.material = r->material;
    f.group = r->group;
    f.loc = rf__token_loc(kw);
    while (!eol(&r->lx)) {
        RfToken t = r->lx.tok;
        Corner c;
        int form;
        RfStatus st = read_corner(r, &t, &c, &form);
        if (st)
            return st;
        if (form0 >= 0 && form != form0)
            return rf_lex_error(&r->lx, t.line, t.col, "face corner %s is %s, the first corner was %s: one form per face",
                                rf_lex_quote(&t, q, sizeof q), forms[form], forms[form0]);
        form0 = form;
        if (f.n == INT32_MAX || !room(r, (void **)&r->corners, &r->cap_corners, r->ncorners, sizeof c))
            return oom(r);
        r->corners[r->ncorners++] = c;
        f.n++;
        rf_lex_advance(&r->lx);
    }
    if (f.n < 3)
        return rf_lex_error(&r->lx, kw->line, kw->col, "a face needs at least 3 vertices, found %d", f.n);
    f.has_vn = form0 >= 2;
    if (!room(r, (void **)&r->faces, &r->cap_faces, r->nfaces, sizeof f))
        return oom(r);
    r->faces[r->nfaces++] = f;
    return RF_OK;
}

/* s off | s 0 | s on | s N */
static RfStatus read_smoothing(ObjReader *r, const RfToken *kw)
{
    char q[96];
    if (eol(&r->lx))
        return rf_lex_error(&r->lx, r->lx.last_end_line, r->lx.last_end_col,
                            "'s' needs a group number or 'off'");
    RfToken t = r->lx.tok;
    if (rf_lex_is(&t, "off")) {
        r->group = 0;
    } else if (rf_lex_is(&t, "on")) {
        r->group = 1;
    } else {
        int g;
        RfStatus st = rf_lex_int(&r->lx, "smoothing group", 0, INT32_MAX, &g);
        if (st)
            return st;
        r->group = g;
        return RF_OK;
    }
    rf_lex_advance(&r->lx);
    (void)kw;
    (void)q;
    return RF_OK;
}

static RfStatus read_usemtl(ObjReader *r, const RfToken *kw)
{
    char q[96];
    if (eol(&r->lx))
        return rf_lex_error(&r->lx, kw->line, kw->col, "usemtl needs a material name");
    RfToken t = r->lx.tok;
    rf_lex_advance(&r->lx);
    for (size_t i = 0; i < r->scene->material_count; i++)
        if (strlen(r->scene->materials[i].name) == t.len &&
            memcmp(r->scene->materials[i].name, t.s, t.len) == 0) {
            r->material = (int)i;
            return RF_OK;
        }
    return rf_lex_error(&r->lx, t.line, t.col, "unknown material %s (not in any mtllib read so far)",
                        rf_lex_quote(&t, q, sizeof q));
}

static RfStatus read_mtllib(ObjReader *r, const RfToken *kw)
{
    char path[RF_OBJ_PATH_MAX], q[96], why[512];
    if (eol(&r->lx))
        return rf_lex_error(&r->lx, kw->line, kw->col, "mtllib needs a file name");
    while (!eol(&r->lx)) {
        RfToken t = r->lx.tok;
        char *text = NULL;
        size_t len = 0;
        rf_lex_advance(&r->lx);
        if (!rf__reader_relative_path(r->lx.name, t.s, t.len, path, sizeof path))
            return rf_lex_error(&r->lx, t.line, t.col, "path %s is too long", rf_lex_quote(&t, q, sizeof q));
        if (rf__reader_read_file(r->scene, path, &text, &len, why, sizeof why)) {
            const char *msg = strstr(why, ": ") ? strstr(why, ": ") + 2 : why; /* drop "[cannot open] path: " */
            return rf_lex_error(&r->lx, t.line, t.col, "material library %s: %s",
                                rf_lex_quote(&t, q, sizeof q), msg);
        }
        RfStatus st = rf_scene_read_mtl(path, text, len, r->scene, r->lx.err, r->lx.errsz);
        r->scene->source_hash = rf_hash_bytes(r->scene->source_hash, text, len);
        free(text);
        if (st)
            return st;
    }
    return RF_OK;
}

static int ignored_keyword(const RfToken *kw)
{
    static const char *const skip[] = {"l", "p", "vp", "cstype", "deg", "bmat", "step", "curv",
                                       "curv2", "surf", "parm", "trim", "hole", "scrv", "sp",
                                       "end", "con", "mg", "bevel", "c_interp", "d_interp", "lod",
                                       "usemap", "maplib", "shadow_obj", "trace_obj", "ctech",
                                       "stech", "call", "csh"};
    for (size_t i = 0; i < sizeof skip / sizeof skip[0]; i++)
        if (rf_lex_is(kw, skip[i]))
            return 1;
    return 0;
}

static RfStatus read_statement(ObjReader *r, const RfToken *kw)
{
    char q[96];
    if (rf_lex_is(kw, "v"))
        return read_vertex(r, kw);
    if (rf_lex_is(kw, "vn"))
        return read_normal(r);
    if (rf_lex_is(kw, "vt"))
        return read_texcoord(r);
    if (rf_lex_is(kw, "f") || rf_lex_is(kw, "fo"))
        return read_face(r, kw);
    if (rf_lex_is(kw, "s"))
        return read_smoothing(r, kw);
    if (rf_lex_is(kw, "usemtl"))
        return read_usemtl(r, kw);
    if (rf_lex_is(kw, "mtllib"))
        return read_mtllib(r, kw);
    if (rf_lex_is(kw, "o") || rf_lex_is(kw, "g") || ignored_keyword(kw)) {
        skip_line(&r->lx);
        return RF_OK;
    }
    return rf_lex_error(&r->lx, kw->line, kw->col, "unknown OBJ keyword %s", rf_lex_quote(kw, q, sizeof q));
}

/* ---- the fast path: plain `v x y z` and `f` lines ------------------------------------------- */

/* Most of a large OBJ file is `v x y z` and `f a b c` lines. These are read here directly: the
 * same values as the statement readers above (numbers by rf_lex_decimal, which is correctly
 * rounded, integers exactly), and anything unusual — another keyword, a fourth number, a
 * negative or out-of-range index, an exotic number — returns 0 so that the line goes through
 * the statement readers, which also write every error message. */
static const char *skip_blanks(const char *s, const char *end)
{
    while (s < end && (*s == ' ' || *s == '\t' || *s == '\r'))
        s++;
    return s;
}

static int token_end(const char *s, const char *end)
{
    return s == end || *s == ' ' || *s == '\t' || *s == '\r' || *s == '#';
}

/* Between `least` and `most` plain decimals up to the line's end or comment, as the statement
 * readers would read them: their count, or -1 for anything else. */
static inline int fast_decimals(const char *s, const char *end, double *c, int least, int most)
{
    int n = 0;
    for (; n < most; n++) {
        s = skip_blanks(s, end);
        if (n >= least && (s == end || *s == '#'))
            return n;
        const char *e = rf_lex_decimal(s, end, &c[n]);
        if (!e || e - s >= 80 || !token_end(e, end))
            return -1;
        s = e;
    }
    s = skip_blanks(s, end);
    return s == end || *s == '#' ? n : -1;
}

/* v x y z or vn x y z: three plain decimals into arr (a position or a normal) */
static int fast_vec3(ObjReader *r, const char *s, const char *end, RfVec3 **arr, size_t *count, size_t *cap)
{
    double c[3];
    if (fast_decimals(s, end, c, 3, 3) < 0 || !room(r, (void **)arr, cap, *count, sizeof **arr))
        return 0;
    (*arr)[(*count)++] = rf_vec3(c[0], c[1], c[2]);
    return 1;
}

static int fast_texcoord(ObjReader *r, const char *s, const char *end)
{
    double c[3];
    if (fast_decimals(s, end, c, 1, 3) < 0)
        return 0;
    r->ntex++; /* counted, for the faces' index checks */
    return 1;
}

/* A positive index up to count, or 0. */
static long fast_index(const char **s, const char *end, size_t count)
{
    long v = 0;
    const char *p = *s;
    uint64_t eight;
    int zeros, n = rf_lex_digits8(p, end, &eight, &zeros); /* most indices: 8 digits or fewer at once */
    if (n >= 0) {
        v = (long)eight;
        p += n;
        if (n < 8)
            end = p; /* the run ended: the loop below has nothing left to read */
    }
    for (; p < end && *p >= '0' && *p <= '9' && v <= 100000000000L; p++)
        v = v * 10 + (*p - '0');
    if (p == *s || v < 1 || (size_t)v > count)
        return 0;
    *s = p;
    return v;
}

static int fast_face(ObjReader *r, const char *s, const char *end, int line)
{
    Face f;
    memset(&f, 0, sizeof f);
    f.first = r->ncorners;
    f.material = r->material;
    f.group = r->group;
    f.loc.line = line;
    f.loc.col = 1;
    int form0 = -1;
    for (;;) {
        s = skip_blanks(s, end);
        if (s == end || *s == '#')
            break;
        Corner c = {0, -1};
        int form = 0;
        long v = fast_index(&s, end, r->npos);
        if (!v)
            goto slow;
        c.v = v - 1;
        if (s < end && *s == '/') {
            s++;
            form = 2;
            if (s < end && *s != '/') {
                if (!fast_index(&s, end, r->ntex))
                    goto slow;
                form = 1;
            }
            if (s < end && *s == '/') {
                s++;
                long n = fast_index(&s, end, r->nnrm);
                if (!n)
                    goto slow;
                c.vn = n - 1;
                form = form == 1 ? 3 : 2;
            } else if (form == 2) {
                goto slow; /* "v/" */
            }
        }
        if (!token_end(s, end) || (form0 >= 0 && form != form0) || f.n == INT32_MAX ||
            !room(r, (void **)&r->corners, &r->cap_corners, r->ncorners, sizeof c))
            goto slow;
        form0 = form;
        r->corners[r->ncorners++] = c;
        f.n++;
    }
    if (f.n < 3 || !room(r, (void **)&r->faces, &r->cap_faces, r->nfaces, sizeof f))
        goto slow;
    f.has_vn = form0 >= 2;
    r->faces[r->nfaces++] = f;
    return 1;
slow:
    r->ncorners = f.first;
    return 0;
}

/* The kinds of line the fast path reads (v, vn, vt, f followed by a blank), the lines that are
 * nothing (empty, a comment, a lone carriage return), the statements that set the state of the
 * faces after them or name things (s, usemtl, mtllib, o, g), and every other line. */
typedef enum { LINE_NONE, LINE_V, LINE_VN, LINE_VT, LINE_F, LINE_STATE, LINE_OTHER } LineKind;

/* Does the line start with the keyword kw, then a blank or its end? */
static int starts_with_keyword(const char *s, const char *end, const char *kw)
{
    size_t n = strlen(kw);
    if ((size_t)(end - s) < n || memcmp(s, kw, n) != 0)
        return 0;
    return s + n == end || s[n] == ' ' || s[n] == '\t' || s[n] == '\r';
}

static inline LineKind line_kind(const char *s, const char *end)
{
    static const char *const state[] = {"s", "usemtl", "mtllib", "o", "g"};
    size_t n = (size_t)(end - s);
    if (n == 0 || *s == '#' || (n == 1 && *s == '\r'))
        return LINE_NONE;
    if (n >= 2 && (s[1] == ' ' || s[1] == '\t')) /* the common lines first, without a call */
        return s[0] == 'v' ? LINE_V : s[0] == 'f' ? LINE_F : s[0] == 's' || s[0] == 'o' || s[0] == 'g' ? LINE_STATE : LINE_OTHER;
    if (n >= 3 && s[0] == 'v' && (s[2] == ' ' || s[2] == '\t'))
        return s[1] == 'n' ? LINE_VN : s[1] == 't' ? LINE_VT : LINE_OTHER;
    for (size_t i = 0; i < sizeof state / sizeof state[0]; i++)
        if (starts_with_keyword(s, end, state[i]))
            return LINE_STATE;
    return LINE_OTHER;
}

/* A line of kind v, vn, vt or f read by the fast path: 1, or 0 when the statement readers must
 * read it. */
static inline int fast_line(ObjReader *r, LineKind kind, const char *s, const char *end, int line)
{
    switch (kind) {
    case LINE_V: return fast_vec3(r, s + 2, end, &r->pos, &r->npos, &r->cap_pos);
    case LINE_VN: return fast_vec3(r, s + 3, end, &r->nrm, &r->nnrm, &r->cap_nrm);
    case LINE_VT: return fast_texcoord(r, s + 3, end);
    case LINE_F: return fast_face(r, s + 2, end, line);
    default: return 0;
    }
}

/* ---- normals and faces into the scene ------------------------------------------------------ */

static RfVec3 corner_pos(const ObjReader *r, const Face *f, int k)
{
    return r->pos[r->corners[f->first + (size_t)k].v];
}

/* The face's area vector and extent as the model's degeneracy test measures them. */
static RfVec3 face_area(const ObjReader *r, const Face *f, RfVec3 *buf, double *ext2)
{
    for (int k = 0; k < f->n; k++)
        buf[k] = corner_pos(r, f, k);
    return rf__polygon_area_vector(buf, f->n, ext2);
}

typedef struct {
    RfVec3 *area, *unit; /* per face */
    size_t *start, *list; /* per position: the faces around it, list[start[v] .. start[v+1]) */
    double cos_crease;
} Smoothing;

static void smoothing_free(Smoothing *sm)
{
    free(sm->area);
    free(sm->unit);
    free(sm->start);
    free(sm->list);
}

/* most: the corners of the largest face */
static RfStatus smoothing_init(const ObjReader *r, int most, Smoothing *sm)
{
    memset(sm, 0, sizeof *sm);
    size_t nf = r->nfaces ? r->nfaces : 1, np = r->npos + 1;
    sm->area = malloc(nf * sizeof *sm->area);
    sm->unit = malloc(nf * sizeof *sm->unit);
    sm->start = calloc(np + 1, sizeof *sm->start);
    size_t corners = 1; /* the faces' (r->corners may have room between them: parse_chunks) */
    for (size_t i = 0; i < r->nfaces; i++)
        corners += (size_t)r->faces[i].n;
    sm->list = malloc(corners * sizeof *sm->list);
    if (!sm->area || !sm->unit || !sm->start || !sm->list)
        return RF_ERR_NOMEM;
    sm->cos_crease = cos(r->pl->crease_deg * (RF_PI / 180.0));
    RfVec3 *buf = malloc(sizeof *buf * (size_t)most);
    if (!buf)
        return RF_ERR_NOMEM;
    for (size_t i = 0; i < r->nfaces; i++) {
        double ext2;
        sm->area[i] = face_area(r, &r->faces[i], buf, &ext2);
        double len = rf_vec3_length(sm->area[i]);
        sm->unit[i] = len > 0.0 ? rf_vec3_scale(sm->area[i], 1.0 / len) : rf_vec3(0, 0, 0);
    }
    free(buf);
    for (size_t i = 0; i < r->nfaces; i++)
        for (int k = 0; k < r->faces[i].n; k++)
            sm->start[r->corners[r->faces[i].first + (size_t)k].v + 1]++;
    for (size_t v = 0; v < np; v++)
        sm->start[v + 1] += sm->start[v];
    size_t *fill = calloc(np, sizeof *fill);
    if (!fill)
        return RF_ERR_NOMEM;
    for (size_t i = 0; i < r->nfaces; i++)
        for (int k = 0; k < r->faces[i].n; k++) {
            long v = r->corners[r->faces[i].first + (size_t)k].v;
            sm->list[sm->start[v] + fill[v]++] = i;
        }
    free(fill);
    return RF_OK;
}

/* §3.6.3 the normal of face fi at its corner k: the normalised area-weighted sum over the faces
 * of its smoothing group around that vertex within the crease angle (the face itself always). */
static RfVec3 corner_normal(const ObjReader *r, const Smoothing *sm, size_t fi, int k)
{
    const Face *f = &r->faces[fi];
    long v = r->corners[f->first + (size_t)k].v;
    RfVec3 sum = rf_vec3(0, 0, 0);
    for (size_t j = sm->start[v]; j < sm->start[v + 1]; j++) {
        size_t g = sm->list[j];
        if (j > sm->start[v] && sm->list[j - 1] == g)
            continue; /* a face that repeats this vertex counts once */
        if (g == fi || (r->faces[g].group == f->group &&
                        rf_vec3_dot(sm->unit[fi], sm->unit[g]) >= sm->cos_crease))
            sum = rf_vec3_add(sum, sm->area[g]);
    }
    double len = rf_vec3_length(sum);
    return len > 0.0 ? rf_vec3_scale(sum, 1.0 / len) : sm->unit[fi];
}

/* ---- the faces into the scene, in chunks on every thread ----------------------------------
 * Two passes over chunks of faces: the first finds the faces with an area and counts their
 * corners, so that every face's vertices, normals and primitive get their place in the scene
 * (the order of the file, as one face after another would append them); the second writes them
 * there and checks each primitive. Any number of threads gives the same scene. */
enum { EMIT_CHUNK = 16384 }; /* faces per chunk */

typedef struct {
    size_t faces, verts, norms;    /* the chunk's faces with an area, their corners and normals */
    size_t pfirst, vfirst, nfirst; /* where they go in the scene */
    RfStatus st;                   /* RF_OK, or why the chunk stopped (at face bad, saying msg) */
    size_t bad;
    char msg[256];
} EmitChunk;

typedef struct {
    ObjReader *r;
    const Smoothing *sm;
    unsigned char *keep; /* per face: it has an area */
    EmitChunk *chunks;
    int most;            /* corners of the largest face */
    int def;             /* the material of faces before any usemtl */
} EmitJob;

static int face_normals(const Face *f) { return f->has_vn || f->group != 0; }

/* The faces of chunk ci: [*lo, *hi). */
static void chunk_faces(const ObjReader *r, int ci, size_t *lo, size_t *hi)
{
    *lo = (size_t)ci * EMIT_CHUNK;
    *hi = *lo + EMIT_CHUNK < r->nfaces ? *lo + EMIT_CHUNK : r->nfaces;
}

/* Pass one: which faces have an area (the model's degeneracy test), and the counts. */
static int emit_count(void *ctx, int ci, int thread)
{
    EmitJob *j = ctx;
    const ObjReader *r = j->r;
    EmitChunk *c = &j->chunks[ci];
    size_t lo, hi;
    RfVec3 *v = malloc(sizeof *v * (size_t)j->most);
    (void)thread;
    if (!v) {
        c->st = RF_ERR_NOMEM;
        return 0;
    }
    chunk_faces(r, ci, &lo, &hi);
    for (size_t i = lo; i < hi; i++) {
        const Face *f = &r->faces[i];
        double ext2;
        RfVec3 a = face_area(r, f, v, &ext2);
        j->keep[i] = rf_vec3_length(a) > RF_SCENE_DEGENERATE_REL * ext2; /* else: nothing to see */
        if (j->keep[i]) {
            c->faces++;
            c->verts += (size_t)f->n;
            c->norms += face_normals(f) ? (size_t)f->n : 0;
        }
    }
    free(v);
    return 0;
}

/* Pass two: the faces' vertices, normals and primitives into their places. */
static int emit_write(void *ctx, int ci, int thread)
{
    EmitJob *j = ctx;
    const ObjReader *r = j->r;
    RfScene *scene = r->scene;
    EmitChunk *c = &j->chunks[ci];
    size_t lo, hi, pi = c->pfirst, vi = c->vfirst, ni = c->nfirst;
    (void)thread;
    chunk_faces(r, ci, &lo, &hi);
    for (size_t i = lo; i < hi; i++) {
        const Face *f = &r->faces[i];
        if (!j->keep[i])
            continue;
        int normals = face_normals(f);
        RfPrimitive p;
        memset(&p, 0, sizeof p);
        p.type = f->n == 3 ? RF_PRIM_TRIANGLE : RF_PRIM_POLYGON;
        p.flags = RF_PRIM_TWO_SIDED | r->pl->prim_flags | (normals ? RF_PRIM_VERTEX_NORMALS : 0u);
        p.loc = f->loc;
        p.u.poly.count = f->n;
        p.u.poly.first = vi;
        p.u.poly.nfirst = ni;
        p.material = f->material >= 0 ? f->material : j->def;
        for (int k = 0; k < f->n; k++) {
            const Corner *cn = &r->corners[f->first + (size_t)k];
            scene->vertices[vi++] = r->pos[cn->v];
            if (normals) /* normalised as rf_scene_add_vertices does */
                scene->normals[ni++] = rf_vec3_normalize(f->has_vn ? r->nrm[cn->vn] : corner_normal(r, j->sm, i, k));
        }
        if ((c->st = rf__scene_put_primitive(scene, pi++, &p, c->msg, sizeof c->msg)) != RF_OK) {
            c->bad = i;
            return 0;
        }
    }
    return 0;
}

/* The material of faces before any usemtl: the placement's, else one named "default", found or
 * made where the first face with an area that needs it stands (as appending face by face made
 * it). */
static RfStatus default_material(ObjReader *r, const unsigned char *keep, int *def)
{
    *def = r->pl->material;
    for (size_t i = 0; *def < 0 && i < r->nfaces; i++) {
        const Face *f = &r->faces[i];
        if (!keep[i] || f->material >= 0)
            continue;
        RfToken kw;
        memset(&kw, 0, sizeof kw);
        kw.line = f->loc.line;
        kw.col = f->loc.col;
        for (size_t m = 0; m < r->scene->material_count && *def < 0; m++)
            if (strcmp(r->scene->materials[m].name, "default") == 0)
                *def = (int)m;
        return rf__reader_default_material(&r->lx, r->scene, &kw, def);
    }
    return RF_OK;
}

static RfStatus emit_faces(ObjReader *r)
{
    RfScene *scene = r->scene;
    Smoothing sm;
    EmitJob j;
    int smooth = 0; /* some face gets its normals from its neighbours */
    memset(&sm, 0, sizeof sm);
    memset(&j, 0, sizeof j);
    size_t nchunks = (r->nfaces + EMIT_CHUNK - 1) / EMIT_CHUNK;
    if (nchunks > INT_MAX)
        return oom(r);
    j.r = r;
    j.sm = &sm;
    j.most = 3;
    for (size_t i = 0; i < r->nfaces; i++) {
        j.most = r->faces[i].n > j.most ? r->faces[i].n : j.most;
        smooth |= !r->faces[i].has_vn && r->faces[i].group != 0;
    }
    j.keep = malloc(r->nfaces + 1);
    j.chunks = calloc(nchunks + 1, sizeof *j.chunks);
    RfStatus st = !j.keep || !j.chunks ? RF_ERR_NOMEM : smooth ? smoothing_init(r, j.most, &sm) : RF_OK;
    if (!st && rf_parallel_for((int)nchunks, r->threads, emit_count, NULL, &j) != RF_OK)
        st = RF_ERR_NOMEM;
    size_t faces = 0, verts = 0, norms = 0;
    for (size_t c = 0; !st && c < nchunks; c++) {
        EmitChunk *ch = &j.chunks[c];
        st = ch->st; /* out of memory */
        ch->pfirst = scene->prim_count + faces;
        ch->vfirst = scene->vertex_count + verts;
        ch->nfirst = scene->normal_count + norms;
        faces += ch->faces;
        verts += ch->verts;
        norms += ch->norms;
    }
    if (!st)
        st = rf__scene_reserve(scene, faces, verts, norms);
    if (!st)
        st = default_material(r, j.keep, &j.def);
    if (!st) {
        size_t prims0 = scene->prim_count, verts0 = scene->vertex_count, norms0 = scene->normal_count;
        scene->prim_count += faces; /* counted in: each face's check sees its own range */
        scene->vertex_count += verts;
        scene->normal_count += norms;
        if (rf_parallel_for((int)nchunks, r->threads, emit_write, NULL, &j) != RF_OK)
            st = RF_ERR_NOMEM;
        for (size_t c = 0; !st && c < nchunks; c++) /* the file's first failing face */
            if (j.chunks[c].st)
                st = rf_lex_error(&r->lx, r->faces[j.chunks[c].bad].loc.line, r->faces[j.chunks[c].bad].loc.col,
                                  "%s", j.chunks[c].msg);
        if (st) { /* the scene is freed by the caller: its counts only need to stay honest */
            scene->prim_count = prims0;
            scene->vertex_count = verts0;
            scene->normal_count = norms0;
        }
    }
    smoothing_free(&sm);
    free(j.keep);
    free(j.chunks);
    return st == RF_ERR_NOMEM ? oom(r) : st;
}

/* One line through the statement readers, on a lexer over that line alone (line: its number). */
static RfStatus slow_line(ObjReader *r, const char *s, const char *end, int line)
{
    char q[96];
    RfStatus st = RF_OK;
    rf_lex_init_at(&r->lx, r->lx.name, s, (size_t)(end - s), line, r->lx.err, r->lx.errsz);
    while (!st && r->lx.tok.kind != RF_TOK_EOF) {
        RfToken kw = r->lx.tok;
        if (kw.kind != RF_TOK_WORD || !kw.bol)
            return rf_lex_error(&r->lx, kw.line, kw.col, "expected an OBJ keyword at the start of a line, found %s",
                                rf_lex_quote(&kw, q, sizeof q));
        rf_lex_advance(&r->lx);
        st = read_statement(r, &kw);
        if (!st && !eol(&r->lx))
            st = rf_lex_error(&r->lx, r->lx.tok.line, r->lx.tok.col, "too many values for %s",
                              rf_lex_quote(&kw, q, sizeof q));
    }
    return st;
}

/* The end of the line that starts at s: its newline, or end. */
static const char *line_end(const char *s, const char *end)
{
    const char *nl = memchr(s, '\n', (size_t)(end - s));
    return nl ? nl : end;
}

/* Line by line, one after another: OBJ statements end with their line (the fast path, or the
 * statement readers). */
static RfStatus parse_lines(ObjReader *r, const char *text, size_t len)
{
    RfStatus st = RF_OK;
    const char *p = text, *end = text + len;
    for (int line = 1; !st && p < end; line++) {
        const char *le = line_end(p, end);
        if (!fast_line(r, line_kind(p, le), p, le, line))
            st = slow_line(r, p, le, line);
        p = le < end ? le + 1 : end;
    }
    return st;
}

/* ---- the parse on several threads ----------------------------------------------------------
 * A file whose lines are all v, vn, vt, f, nothing or state statements (s, usemtl, mtllib, o,
 * g) is read in chunks of whole lines on every thread. A scan counts each chunk's lines,
 * vertices, normals, texture coordinates and faces (and room for its corners: as many as its f
 * lines could hold, each face pointing at its own), so that every chunk writes straight into
 * the places reading the file in order would give; a chunk reads its lines by the fast path or,
 * when that declines, by the statement readers, counting from what the chunks before it hold.
 * Then the state statements run in the file's order through the statement readers (their
 * material files are read there, and their errors are the file's first: every other line has
 * been read by then), and the faces after each get its material and smoothing group. A line of
 * any other kind, or one that fails, and the file is read one line after another instead
 * (parse_lines), before anything reached the scene: the same arrays, the same scene and the
 * same errors for any number of threads. */
enum { PARSE_CHUNK = 1 << 14 }; /* bytes per chunk (then to the end of its last line) */

typedef struct {
    const char *at; /* the line */
    int line;       /* its number within the chunk (0: the first) */
    size_t faces;   /* faces of the chunk before it */
} StateLine;

typedef struct {
    const char *lo, *hi;                              /* whole lines, each with its newline */
    size_t lines, pos, nrm, tex, faces;               /* counted by the scan */
    size_t corners;                                   /* room for the faces' corners */
    size_t line0, pos0, nrm0, tex0, faces0, corners0; /* before the chunk */
    StateLine *state;
    size_t nstate, cap_state;
    int other; /* the scan met a line of another kind (or ran out of memory) */
    int taken; /* every v, vn, vt and f line read, and the counts came out as the scan's */
} ParseChunk;

typedef struct {
    ObjReader *r;
    ParseChunk *chunks;
} ParseJob;

/* At most this many corners on an f line of len bytes after "f ": each takes a character and
 * a blank before the next. */
static size_t most_corners(size_t len) { return (len + 1) / 2; }

static int scan_chunk(void *ctx, int ci, int thread)
{
    ParseChunk *c = &((ParseJob *)ctx)->chunks[ci];
    (void)thread;
    for (const char *p = c->lo; p < c->hi && !c->other; c->lines++) {
        const char *le = line_end(p, c->hi);
        switch (line_kind(p, le)) {
        case LINE_NONE: break;
        case LINE_V: c->pos++; break;
        case LINE_VN: c->nrm++; break;
        case LINE_VT: c->tex++; break;
        case LINE_F:
            c->faces++;
            c->corners += most_corners((size_t)(le - p - 2));
            break;
        case LINE_STATE:
            if (!grow((void **)&c->state, &c->cap_state, c->nstate, sizeof *c->state)) {
                c->other = 1;
                break;
            }
            c->state[c->nstate].at = p;
            c->state[c->nstate].line = (int)c->lines;
            c->state[c->nstate++].faces = c->faces;
            break;
        default: c->other = 1;
        }
        p = le < c->hi ? le + 1 : c->hi;
    }
    return 0;
}

static int read_chunk(void *ctx, int ci, int thread)
{
    ParseJob *j = ctx;
    ParseChunk *c = &j->chunks[ci];
    ObjReader r = *j->r; /* this chunk's share of the arrays, from the counts before it */
    (void)thread;
    r.npos = c->pos0, r.cap_pos = c->pos0 + c->pos;
    r.nnrm = c->nrm0, r.cap_nrm = c->nrm0 + c->nrm;
    r.ntex = c->tex0;
    r.nfaces = c->faces0, r.cap_faces = c->faces0 + c->faces;
    r.ncorners = c->corners0, r.cap_corners = c->corners0 + c->corners;
    r.fixed = 1;
    r.lx.err = NULL; /* a failing line is read again line by line, which writes the message */
    r.lx.errsz = 0;
    int line = (int)c->line0 + 1;
    for (const char *p = c->lo; p < c->hi; line++) {
        const char *le = line_end(p, c->hi);
        LineKind kind = line_kind(p, le);
        if (kind != LINE_NONE && kind != LINE_STATE && !fast_line(&r, kind, p, le, line) &&
            slow_line(&r, p, le, line) != RF_OK)
            return 0; /* not taken */
        p = le < c->hi ? le + 1 : c->hi;
    }
    c->taken = r.npos == r.cap_pos && r.nnrm == r.cap_nrm && r.ntex == c->tex0 + c->tex && r.nfaces == r.cap_faces;
    return 0;
}

/* The faces [from, to) get the current material and smoothing group (the fast path gave them
 * the first: no usemtl, smooth). */
static void set_state(ObjReader *r, size_t from, size_t to)
{
    if (r->material == -1 && r->group == 1)
        return;
    for (size_t i = from; i < to; i++) {
        r->faces[i].material = r->material;
        r->faces[i].group = r->group;
    }
}

/* The state statements in the file's order, and the material and smoothing group of the faces
 * after each. */
static RfStatus run_state_lines(ObjReader *r, const ParseChunk *chunks, size_t nchunks)
{
    size_t from = 0; /* the faces before it have their state */
    for (size_t ci = 0; ci < nchunks; ci++)
        for (size_t k = 0; k < chunks[ci].nstate; k++) {
            const StateLine *sl = &chunks[ci].state[k];
            set_state(r, from, chunks[ci].faces0 + sl->faces);
            from = chunks[ci].faces0 + sl->faces;
            RfStatus st = slow_line(r, sl->at, line_end(sl->at, chunks[ci].hi),
                                    (int)(chunks[ci].line0 + (size_t)sl->line) + 1);
            if (st)
                return st;
        }
    set_state(r, from, r->nfaces);
    return RF_OK;
}

/* The parallel parse; *taken = 0 when the file must be read line by line instead (r unchanged). */
static RfStatus parse_chunks(ObjReader *r, const char *text, size_t len, int *taken)
{
    size_t nchunks = len / PARSE_CHUNK + 1;
    ParseJob j;
    RfStatus st = RF_OK;
    *taken = 0;
    if (nchunks > INT_MAX || !(j.chunks = calloc(nchunks, sizeof *j.chunks)))
        return RF_OK; /* line by line, which needs less memory */
    j.r = r;
    const char *p = text, *end = text + len;
    for (size_t ci = 0; ci < nchunks; ci++) { /* whole lines with their newlines, ~PARSE_CHUNK bytes */
        const char *hi = end;
        if ((size_t)(end - p) > PARSE_CHUNK) {
            const char *nl = line_end(p + PARSE_CHUNK, end);
            hi = nl < end ? nl + 1 : end;
        }
        j.chunks[ci].lo = p;
        j.chunks[ci].hi = p = hi;
    }
    int ok = rf_parallel_for((int)nchunks, r->threads, scan_chunk, NULL, &j) == RF_OK;
    size_t lines = 0, pos = 0, nrm = 0, tex = 0, faces = 0, corners = 0;
    for (size_t ci = 0; ok && ci < nchunks; ci++) {
        ParseChunk *c = &j.chunks[ci];
        ok = !c->other;
        c->line0 = lines, c->pos0 = pos, c->nrm0 = nrm, c->tex0 = tex, c->faces0 = faces, c->corners0 = corners;
        lines += c->lines, pos += c->pos, nrm += c->nrm, tex += c->tex, faces += c->faces, corners += c->corners;
    }
    ok = ok && lines < INT_MAX;
    if (ok) {
        r->pos = malloc((pos + 1) * sizeof *r->pos);
        r->nrm = malloc((nrm + 1) * sizeof *r->nrm);
        r->faces = malloc((faces + 1) * sizeof *r->faces);
        r->corners = malloc((corners + 1) * sizeof *r->corners);
        ok = r->pos && r->nrm && r->faces && r->corners &&
             rf_parallel_for((int)nchunks, r->threads, read_chunk, NULL, &j) == RF_OK;
        for (size_t ci = 0; ok && ci < nchunks; ci++)
            ok = j.chunks[ci].taken;
        if (ok) {
            r->npos = r->cap_pos = pos;
            r->nnrm = r->cap_nrm = nrm;
            r->ntex = tex;
            r->nfaces = r->cap_faces = faces;
            r->ncorners = r->cap_corners = corners;
            *taken = 1;
            st = run_state_lines(r, j.chunks, nchunks);
        } else {
            free(r->pos), free(r->nrm), free(r->faces), free(r->corners);
            r->pos = r->nrm = NULL, r->faces = NULL, r->corners = NULL;
        }
    }
    for (size_t ci = 0; ci < nchunks; ci++)
        free(j.chunks[ci].state);
    free(j.chunks);
    return st;
}

RfStatus rf__obj_read(const char *name, const char *text, size_t len, const RfObjPlacement *pl,
                      RfScene *scene, char *err, size_t errsz)
{
    ObjReader r;
    RfStatus st = RF_OK;
    int taken = 0;
    memset(&r, 0, sizeof r);
    r.scene = scene;
    r.pl = pl;
    r.threads = pl->threads > 0 ? pl->threads : rf_cpu_count();
    r.material = -1;
    r.group = 1; /* smooth unless the file says `s off` */
    rf_lex_init(&r.lx, name, text, len, err, errsz);
    if (r.threads > 1 && len >= 2 * PARSE_CHUNK)
        st = parse_chunks(&r, text, len, &taken);
    if (!taken)
        st = parse_lines(&r, text, len);
    if (pl->chunked)
        *pl->chunked = taken;
    if (!st)
        st = emit_faces(&r);
    free(r.pos);
    free(r.nrm);
    free(r.corners);
    free(r.faces);
    return st;
}

/* The default view of a bare OBJ file: the bounding sphere fills the vertical field of view,
 * seen from +z a little above and to the right, with a headlight at the eye. */
static RfStatus default_view(RfScene *scene, const char *name, char *err, size_t errsz)
{
    RfVec3 lo, hi;
    if (!rf_scene_bounds(scene, &lo, &hi)) {
        snprintf(err, errsz, "%s:1:1: the OBJ file has no faces", name);
        return RF_ERR_PARSE;
    }
    RfVec3 c = rf_vec3_scale(rf_vec3_add(lo, hi), 0.5);
    double radius = fmax(0.5 * rf_vec3_length(rf_vec3_sub(hi, lo)), 1e-9);
    double fov = 40.0;
    double dist = 1.05 * radius / sin(fov * (RF_PI / 360.0));
    RfSceneCamera *cam = &scene->camera;
    memset(cam, 0, sizeof *cam);
    cam->eye = rf_vec3_add(c, rf_vec3_scale(rf_vec3_normalize(rf_vec3(0.35, 0.4, 1.0)), dist));
    cam->target = c;
    cam->up = rf_vec3(0, 1, 0);
    cam->d = 1.0;
    cam->fov = fov;
    cam->fov_reading = RF_FOV_EDGES;
    cam->loc.line = cam->loc.col = 1;
    cam->target_loc = cam->up_loc = cam->loc;
    scene->has_camera = 1;
    RfLight l;
    memset(&l, 0, sizeof l);
    l.kind = RF_LIGHT_POINT;
    l.falloff = RF_FALLOFF_NONE;
    l.position = cam->eye;
    l.intensity = rf_rgb(1, 1, 1);
    l.loc = cam->loc;
    if (rf_scene_add_light(scene, &l)) {
        snprintf(err, errsz, "%s:1:1: out of memory", name);
        return RF_ERR_NOMEM;
    }
    return RF_OK;
}

RfStatus rf_scene_read_obj(const char *name, const char *text, size_t len,
                           const RfLoadOptions *opt, RfScene *scene, char *err, size_t errsz)
{
    RfLoadOptions def = rf_load_options_default();
    RfObjPlacement pl;
    if (!opt)
        opt = &def;
    pl.crease_deg = opt->crease_angle;
    pl.material = -1;
    pl.prim_flags = 0;
    pl.threads = opt->threads;
    pl.chunked = NULL;
    rf_scene_init(scene);
    scene->format = RF_FORMAT_OBJ;
    RfStatus st = rf__obj_read(name, text, len, &pl, scene, err, errsz);
    if (!st)
        st = default_view(scene, name, err, errsz);
    if (!st)
        st = rf__scene_validate_read(scene, name, err, errsz);
    if (st)
        rf_scene_free(scene);
    return st;
}
