/* refray: the steps every scene reader shares (reader.h): appending checked primitives and
 * vertices, the default material, the end of a read, reading a (gzipped) file, relative paths,
 * the load options. Below the readers (nff.c, obj.c, mtl.c, rfscene.c), which load.c picks. */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <zlib.h>

#include "reader.h"
#include "refray/scene_io.h"

RfLoadOptions rf_load_options_default(void)
{
    RfLoadOptions o;
    o.nff_fov = RF_FOV_PIXEL_CENTRES;
    o.crease_angle = 60.0;
    o.threads = 0;
    return o;
}

RfStatus rf__reader_add_prim(RfLexer *lx, RfScene *scene, const RfPrimitive *p)
{
    char msg[256];
    RfStatus st = rf_scene_add_primitive(scene, p, msg, sizeof msg);
    return st ? rf_lex_error(lx, p->loc.line, p->loc.col, "%s", msg) : RF_OK;
}

RfStatus rf__reader_add_vertex(RfLexer *lx, RfScene *scene, RfVec3 v, const RfVec3 *n,
                               size_t *first, size_t *nfirst)
{
    size_t f, nf;
    if (rf_scene_add_vertices(scene, &v, n, 1, &f, &nf))
        return rf_lex_error(lx, lx->last.line, lx->last.col, "out of memory");
    if (first)
        *first = f;
    if (nfirst)
        *nfirst = nf;
    return RF_OK;
}

RfStatus rf__reader_check_camera(RfLexer *lx, const RfSceneCamera *cam)
{
    char msg[256];
    RfSrcLoc loc;
    RfStatus st = rf_scene_camera_check(cam, &loc, msg, sizeof msg);
    return st ? rf_lex_error(lx, loc.line, loc.col, "%s", msg) : RF_OK;
}

RfStatus rf__reader_default_material(RfLexer *lx, RfScene *scene, const RfToken *kw,
                                     int *current)
{
    if (*current >= 0)
        return RF_OK;
    RfMaterial m = rf_material_default();
    snprintf(m.name, sizeof m.name, "default");
    m.kd = rf_rgb(1, 1, 1);
    m.loc = rf__token_loc(kw);
    if (rf_scene_add_material(scene, &m, current))
        return rf_lex_error(lx, kw->line, kw->col, "out of memory");
    return RF_OK;
}

RfStatus rf__reader_finish(RfLexer *lx, RfScene *scene, RfStatus st)
{
    if (!st && !scene->has_camera)
        st = rf_lex_error(lx, lx->tok.line, lx->tok.col, "the scene has no camera (%s)",
                          scene->format == RF_FORMAT_NFF ? "NFF needs a viewpoint 'v'"
                                                         : "add a 'camera' statement");
    if (!st)
        st = rf__scene_validate_read(scene, lx->name, lx->err, lx->errsz);
    if (st)
        rf_scene_free(scene);
    return st;
}

int rf__ends_with(const char *s, size_t n, const char *suffix)
{
    size_t k = strlen(suffix);
    return n >= k && strncmp(s + n - k, suffix, k) == 0;
}

/* Reads a whole file (decompressing .gz) into a malloc'd buffer. Only regular files: a device
 * (/dev/zero) would never end and a FIFO would block; and at most RF_SCENE_MAX_FILE_BYTES,
 * decompressed, so that a gzip bomb ends with a message too. */
static RfStatus read_file(const char *path, int gz, char **text, size_t *len, char *err,
                          size_t errsz)
{
    struct stat sb;
    if (stat(path, &sb) == 0 && !S_ISREG(sb.st_mode)) {
        snprintf(err, errsz, "%s: not a regular file (a directory, device or pipe)", path);
        return RF_ERR_IO;
    }
    gzFile f = gz ? gzopen(path, "rb") : NULL;
    FILE *pf = gz ? NULL : fopen(path, "rb");
    if (!f && !pf) {
        snprintf(err, errsz, "cannot open %s: %s", path, strerror(errno ? errno : ENOENT));
        return RF_ERR_IO;
    }
    size_t cap = 1 << 16, n = 0;
    int read_errno = 0;
    char *buf = malloc(cap);
    int bad = !buf;
    while (!bad) {
        if (n >= RF_SCENE_MAX_FILE_BYTES) {
            bad = 3;
            break;
        }
        if (n == cap) {
            char *b2 = cap > ((size_t)-1) / 2 ? NULL : realloc(buf, cap * 2);
            if (!b2) {
                bad = 1;
                break;
            }
            buf = b2;
            cap *= 2;
        }
        size_t want = cap - n > (1u << 30) ? (1u << 30) : cap - n;
        size_t k;
        if (gz) {
            int r = gzread(f, buf + n, (unsigned)want);
            if (r < 0) {
                bad = 2;
                break;
            }
            k = (size_t)r;
        } else {
            k = fread(buf + n, 1, want, pf);
            if (k == 0 && ferror(pf)) {
                bad = 2;
                read_errno = errno;
            }
        }
        if (k == 0)
            break;
        n += k;
    }
    if (gz) {
        int zerr = Z_OK;
        gzerror(f, &zerr);
        if (!bad && zerr != Z_OK && zerr != Z_STREAM_END)
            bad = 2; /* e.g. Z_BUF_ERROR: the compressed stream is truncated */
        gzclose(f);
    }
    else
        fclose(pf);
    if (bad) {
        free(buf);
        if (bad == 3)
            snprintf(err, errsz, "%s: larger than %d MiB%s: refused", path, RF_SCENE_MAX_FILE_BYTES >> 20,
                     gz ? " decompressed" : "");
        else
            snprintf(err, errsz, "%s: %s%s", path,
                     bad == 1 ? "out of memory" : gz ? "cannot decompress (corrupt gzip data)" : "cannot read: ",
                     bad == 2 && !gz ? strerror(read_errno ? read_errno : EIO) : "");
        return bad == 1 ? RF_ERR_NOMEM : RF_ERR_IO;
    }
    *text = buf;
    *len = n;
    return RF_OK;
}

RfStatus rf__reader_add_file(RfScene *scene, const char *path, char *err, size_t errsz)
{
    size_t n = strlen(path);
    char **files = realloc(scene->files, (scene->file_count + 1) * sizeof *files);
    char *copy = malloc(n + 1);
    if (files)
        scene->files = files;
    if (!files || !copy) {
        free(copy);
        snprintf(err, errsz, "%s: out of memory", path);
        return RF_ERR_NOMEM;
    }
    scene->files[scene->file_count++] = memcpy(copy, path, n + 1);
    return RF_OK;
}

RfStatus rf__reader_read_file(RfScene *scene, const char *path, char **text, size_t *len, char *err,
                              size_t errsz)
{
    size_t n = strlen(path);
    RfStatus st = read_file(path, rf__ends_with(path, n, ".gz"), text, len, err, errsz);
    if (!st && scene && (st = rf__reader_add_file(scene, path, err, errsz))) {
        free(*text);
        *text = NULL;
    }
    return st;
}

int rf__reader_relative_path(const char *base, const char *rel, size_t rel_len, char *out, size_t n)
{
    const char *slash = strrchr(base, '/');
    size_t dir = rel_len > 0 && rel[0] == '/' ? 0 : slash ? (size_t)(slash - base) + 1 : 0;
    if (dir + rel_len + 1 > n)
        return 0;
    memcpy(out, base, dir);
    memcpy(out + dir, rel, rel_len);
    out[dir + rel_len] = 0;
    return 1;
}

