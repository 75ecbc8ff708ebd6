/* Float images: allocation, the formats' names, the write-then-rename helper and the error
 * helpers that the readers and writers share (reading by signature is read.c, above them). */
#include "io_internal.h"

#include <errno.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

RfStatus rf_io_fail(RfStatus status, char *err, size_t err_size, const char *path, const char *fmt, ...)
{
    if (err && err_size > 0) {
        int n = snprintf(err, err_size, "%s: ", path ? path : "(null)");
        if (n >= 0 && (size_t)n < err_size) {
            va_list ap;
            va_start(ap, fmt);
            vsnprintf(err + n, err_size - (size_t)n, fmt, ap);
            va_end(ap);
        }
    }
    return status;
}

RfStatus rf_io_fail_errno(RfStatus status, char *err, size_t err_size, const char *path, const char *what,
                          int errnum)
{
    char msg[256];
    if (strerror_r(errnum, msg, sizeof msg) != 0) /* XSI strerror_r: strerror() is not thread-safe */
        snprintf(msg, sizeof msg, "error %d", errnum);
    return rf_io_fail(status, err, err_size, path, "%s: %s", what, msg);
}

/* The formats' names, here below the readers: read.c's dispatcher and foreign.c's claims use them. */
const char *rf_image_file_name(RfImageFile f)
{
    static const char *const names[] = {"unknown", "EXR", "PNG", "PNM", "JPEG", "TIFF", "BMP", "HDR", "TGA"};
    return (unsigned)f < sizeof names / sizeof names[0] ? names[f] : "unknown";
}

/* Pixel count of a width x height image, or 0 when the size is not acceptable. */
static size_t checked_pixels(int width, int height)
{
    if (width <= 0 || height <= 0)
        return 0;
    if ((size_t)width > RF_IMAGE_MAX_PIXELS / (size_t)height)
        return 0;
    return (size_t)width * (size_t)height;
}

RfStatus rf_image_alloc(RfImage *img, int width, int height, int channels)
{
    size_t pixels = checked_pixels(width, height);
    if (!img)
        return RF_ERR_DOMAIN;
    img->width = img->height = img->channels = 0;
    img->data = NULL;
    if (pixels == 0 || (channels != 1 && channels != 3 && channels != 4))
        return RF_ERR_DOMAIN;
    /* RF_IMAGE_MAX_PIXELS * 4 * sizeof(float) fits any 64-bit size_t; check anyway for 32-bit. */
    if (pixels > SIZE_MAX / sizeof(float) / (size_t)channels)
        return RF_ERR_NOMEM;
    img->data = calloc(pixels * (size_t)channels, sizeof(float));
    if (!img->data)
        return RF_ERR_NOMEM;
    img->width = width;
    img->height = height;
    img->channels = channels;
    return RF_OK;
}

void rf_image_free(RfImage *img)
{
    if (!img)
        return;
    free(img->data);
    img->data = NULL;
    img->width = img->height = img->channels = 0;
}

RfStatus rf_io_read_start(RfImage *img, const char *path, char *err, size_t err_size)
{
    if (!img)
        return rf_io_fail(RF_ERR_DOMAIN, err, err_size, path, "no image to read into");
    img->width = img->height = img->channels = 0;
    img->data = NULL;
    if (!path)
        return rf_io_fail(RF_ERR_DOMAIN, err, err_size, path, "no input path");
    struct stat sb; /* a device would be read without end, a FIFO would block */
    if (stat(path, &sb) == 0 && !S_ISREG(sb.st_mode))
        return rf_io_fail(RF_ERR_IO, err, err_size, path, "not a regular file (a directory, device or pipe)");
    return RF_OK;
}

RfStatus rf_io_check_claim(const char *path, const char *format, long long width, long long height,
                           double decoded_bytes, double per_byte, double slack_bytes, char *err, size_t err_size)
{
    struct stat sb;
    if (stat(path, &sb) != 0 || decoded_bytes <= per_byte * (double)sb.st_size + slack_bytes)
        return RF_OK;
    return rf_io_fail(RF_ERR_PARSE, err, err_size, path, "%s claims %lld x %lld pixels, far more than its %lld bytes can hold",
                      format, width, height, (long long)sb.st_size);
}

RfStatus rf_io_check_image(const RfImage *img, const char *path, char *err, size_t err_size)
{
    if (!path)
        return rf_io_fail(RF_ERR_DOMAIN, err, err_size, path, "no output path");
    if (!img || !img->data)
        return rf_io_fail(RF_ERR_DOMAIN, err, err_size, path, "no image data to write");
    if (img->channels != 1 && img->channels != 3 && img->channels != 4)
        return rf_io_fail(RF_ERR_DOMAIN, err, err_size, path, "unsupported channel count %d (1, 3 or 4)",
                          img->channels);
    if (checked_pixels(img->width, img->height) == 0)
        return rf_io_fail(RF_ERR_DOMAIN, err, err_size, path, "unsupported image size %dx%d", img->width,
                          img->height);
    return RF_OK;
}

/* ---- atomic writes ---- */

/* path with its symbolic links followed (at most 40, as the kernel), malloc'd; NULL when the
 * links loop or memory runs out. A link's relative target is taken from the link's folder. */
static char *resolve_links(const char *path)
{
    char *p = strdup(path);
    for (int hops = 0; p && hops < 40; hops++) {
        struct stat ls;
        if (lstat(p, &ls) != 0 || !S_ISLNK(ls.st_mode))
            return p;
        char link[4096];
        ssize_t n = readlink(p, link, sizeof link - 1);
        if (n < 0) {
            free(p);
            return NULL;
        }
        link[n] = 0;
        const char *slash = strrchr(p, '/');
        size_t dir = link[0] == '/' || !slash ? 0 : (size_t)(slash - p) + 1;
        char *q = malloc(dir + (size_t)n + 1);
        if (q) {
            memcpy(q, p, dir);
            memcpy(q + dir, link, (size_t)n + 1);
        }
        free(p);
        p = q;
    }
    free(p);
    return NULL;
}

RfStatus rf_atomic_open(RfAtomicFile *f, const char *path, char *err, size_t err_size)
{
    static const char suffix[] = ".XXXXXX";
    struct stat st;
    mode_t mode = 0644;

    f->path = path;
    f->fd = -1;
    f->fp = NULL;
    f->tmp = NULL;
    if (!path || !path[0])
        return rf_io_fail(RF_ERR_DOMAIN, err, err_size, "\"\"", "empty output path");
    f->target = resolve_links(path);
    if (!f->target)
        return rf_io_fail(RF_ERR_IO, err, err_size, path, "cannot follow its symbolic links (a loop?)");
    if (stat(f->target, &st) == 0 && !S_ISREG(st.st_mode)) {
        rf_atomic_abort(f);
        return rf_io_fail(RF_ERR_IO, err, err_size, path,
                          "not a regular file (a device, directory or pipe): it is not replaced");
    }
    size_t len = strlen(f->target);
    f->tmp = malloc(len + sizeof suffix);
    if (!f->tmp) {
        rf_atomic_abort(f);
        return rf_io_fail(RF_ERR_NOMEM, err, err_size, path, "out of memory");
    }
    /* "<target>.XXXXXX" lies in the target's folder, so the final rename() stays on one file system. */
    memcpy(f->tmp, f->target, len);
    memcpy(f->tmp + len, suffix, sizeof suffix);
    f->fd = mkstemp(f->tmp);
    if (f->fd < 0) {
        int e = errno;
        free(f->tmp);
        f->tmp = NULL;
        rf_atomic_abort(f);
        return rf_io_fail_errno(RF_ERR_IO, err, err_size, path, "cannot create a temporary file next to it", e);
    }
    /* mkstemp creates 0600. Keep a replaced file's permissions; a new file gets 0644 (reading
     * the umask would need umask(), which changes process state and is not thread-safe). */
    if (stat(f->target, &st) == 0 && S_ISREG(st.st_mode))
        mode = st.st_mode & 07777;
    if (fchmod(f->fd, mode) != 0) {
        int e = errno;
        rf_atomic_abort(f);
        return rf_io_fail_errno(RF_ERR_IO, err, err_size, path, "cannot set the permissions", e);
    }
    return RF_OK;
}

RfStatus rf_atomic_stdio(RfAtomicFile *f, char *err, size_t err_size)
{
    f->fp = fdopen(f->fd, "wb");
    if (!f->fp)
        return rf_io_fail_errno(RF_ERR_IO, err, err_size, f->path, "cannot open a stream", errno);
    return RF_OK;
}

void rf_atomic_abort(RfAtomicFile *f)
{
    if (f->fp)
        fclose(f->fp);
    else if (f->fd >= 0)
        close(f->fd);
    f->fp = NULL;
    f->fd = -1;
    if (f->tmp) {
        unlink(f->tmp);
        free(f->tmp);
        f->tmp = NULL;
    }
    free(f->target);
    f->target = NULL;
}

/* Flushes and closes the temporary file; on failure removes it (f released) and says why. */
static RfStatus atomic_close(RfAtomicFile *f, char *err, size_t err_size)
{
    int failed, e = 0;
    if (f->fp) {
        failed = fflush(f->fp) != 0 || ferror(f->fp);
        e = errno;
        if (fclose(f->fp) != 0 && !failed) {
            failed = 1;
            e = errno;
        }
    } else {
        failed = close(f->fd) != 0;
        e = errno;
    }
    f->fp = NULL;
    f->fd = -1;
    if (failed) {
        rf_atomic_abort(f);
        return rf_io_fail_errno(RF_ERR_IO, err, err_size, f->path, "cannot write", e ? e : EIO);
    }
    return RF_OK;
}

RfStatus rf_atomic_commit(RfAtomicFile *f, char *err, size_t err_size)
{
    RfStatus st = atomic_close(f, err, err_size);
    if (st != RF_OK)
        return st;
    if (rename(f->tmp, f->target) != 0) {
        int e = errno;
        rf_atomic_abort(f);
        return rf_io_fail_errno(RF_ERR_IO, err, err_size, f->path, "cannot rename the temporary file to it", e);
    }
    free(f->tmp);
    f->tmp = NULL;
    rf_atomic_abort(f); /* only frees the names now */
    return RF_OK;
}

/* ---- several outputs together ---- */

struct RfWriteBatch {
    int count, cap;
    char **tmp, **target, **path; /* malloc'd names */
};

RfWriteBatch *rf_write_batch_new(void) { return calloc(1, sizeof(RfWriteBatch)); }

RfStatus rf_atomic_finish(RfAtomicFile *f, RfWriteBatch *b, char *err, size_t err_size)
{
    if (!b)
        return rf_atomic_commit(f, err, err_size);
    RfStatus st = atomic_close(f, err, err_size);
    if (st != RF_OK)
        return st;
    if (b->count == b->cap) {
        int cap = b->cap ? 2 * b->cap : 4;
        char **t = realloc(b->tmp, sizeof *t * (size_t)cap), **g = t ? realloc(b->target, sizeof *g * (size_t)cap) : NULL,
             **p = g ? realloc(b->path, sizeof *p * (size_t)cap) : NULL;
        if (t)
            b->tmp = t;
        if (g)
            b->target = g;
        if (p)
            b->path = p;
        if (!t || !g || !p) {
            rf_atomic_abort(f);
            return rf_io_fail(RF_ERR_NOMEM, err, err_size, f->path, "out of memory");
        }
        b->cap = cap;
    }
    char *path = strdup(f->path);
    if (!path) {
        rf_atomic_abort(f);
        return rf_io_fail(RF_ERR_NOMEM, err, err_size, f->path, "out of memory");
    }
    b->tmp[b->count] = f->tmp;
    b->target[b->count] = f->target;
    b->path[b->count++] = path;
    f->tmp = f->target = NULL; /* the batch owns them now */
    return RF_OK;
}

static void batch_free(RfWriteBatch *b, int unlink_from)
{
    for (int i = 0; i < b->count; i++) {
        if (i >= unlink_from)
            unlink(b->tmp[i]);
        free(b->tmp[i]);
        free(b->target[i]);
        free(b->path[i]);
    }
    free(b->tmp);
    free(b->target);
    free(b->path);
    free(b);
}

void rf_write_batch_abort(RfWriteBatch *b)
{
    if (b)
        batch_free(b, 0);
}

RfStatus rf_write_batch_commit(RfWriteBatch *b, char *err, size_t err_size)
{
    if (!b)
        return RF_OK;
    for (int i = 0; i < b->count; i++)
        if (rename(b->tmp[i], b->target[i]) != 0) {
            RfStatus st = rf_io_fail_errno(RF_ERR_IO, err, err_size, b->path[i],
                                           "cannot rename the temporary file to it", errno);
            batch_free(b, i); /* the ones not yet renamed are removed */
            return st;
        }
    batch_free(b, b->count);
    return RF_OK;
}

/* ---- output paths ---- */

RfStatus rf_output_check(const char *path, char *err, size_t err_size)
{
    RfAtomicFile f;
    RfStatus st = rf_atomic_open(&f, path, err, err_size);
    if (st == RF_OK)
        rf_atomic_abort(&f); /* it could be created: removed again */
    return st;
}

int rf_output_same(const char *a, const char *b)
{
    struct stat sa, sb;
    if (stat(a, &sa) == 0 && stat(b, &sb) == 0)
        return sa.st_dev == sb.st_dev && sa.st_ino == sb.st_ino;
    char *ra = resolve_links(a), *rb = resolve_links(b);
    int same = ra && rb && strcmp(ra, rb) == 0;
    free(ra);
    free(rb);
    return same;
}

RfStatus rf_outputs_check(const char *const *outs, int n_out, const char *const *ins, int n_in, char *err,
                          size_t err_size)
{
    for (int i = 0; i < n_out; i++) {
        if (!outs[i])
            continue;
        for (int j = 0; j < n_in; j++)
            if (ins[j] && rf_output_same(outs[i], ins[j]))
                return rf_io_fail(RF_ERR_DOMAIN, err, err_size, outs[i], "is an input (%s): it is not overwritten",
                                  ins[j]);
        for (int j = 0; j < i; j++)
            if (outs[j] && rf_output_same(outs[i], outs[j]))
                return rf_io_fail(RF_ERR_DOMAIN, err, err_size, outs[i], "is given as two outputs (also %s)", outs[j]);
        RfStatus st = rf_output_check(outs[i], err, err_size);
        if (st != RF_OK)
            return st;
    }
    return RF_OK;
}
