/* The image formats students write besides EXR and PNG, read through Debian's libraries rather
 * than decoders of refray's own: netpbm (PBM/PGM/PPM, plain P1-P3 and raw P4-P6; stb_image reads
 * no plain PPM), stb_image (JPEG, BMP, TGA, Radiance HDR) and libtiff. Integer codes are
 * decoded with the PNG options' curve, exactly as a PNG is (rf_io_decode_value); HDR and float
 * TIFF hold linear values and are taken as they are. Alpha is never curved. */
#include "io_internal.h"

#include <errno.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

#include <pnm.h>
#include <stb_image.h>
#include <tiffio.h>

/* The channels of refray's image for a file's samples per pixel: grey+alpha becomes RGBA. */
static int channels_for(int samples)
{
    return samples == 2 ? 4 : samples;
}

/* Stores one pixel of `samples` values (codes scaled to [0, 1], or linear floats) at pixel i. */
static void store(RfImage *img, size_t i, const double *v, int samples, int linear, RfPngOptions decode)
{
    float *px = img->data + i * (size_t)img->channels;
    int has_alpha = samples == 2 || samples == 4, colours = has_alpha ? samples - 1 : samples;
    for (int c = 0; c < img->channels; c++) {
        int alpha = has_alpha && c == img->channels - 1;
        double s = alpha ? v[samples - 1] : v[colours == 1 ? 0 : c];
        px[c] = (float)(alpha || linear ? s : rf_io_decode_value(s, decode));
    }
}

static RfStatus open_checked(const char *path, RfPngOptions decode, RfImage *img, FILE **fp, char *err,
                             size_t err_size)
{
    RfStatus st = rf_io_read_start(img, path, err, err_size);
    if (st == RF_OK)
        st = rf_io_check_decode(decode, path, err, err_size);
    if (st != RF_OK)
        return st;
    *fp = fopen(path, "rb");
    if (!*fp)
        return rf_io_fail_errno(RF_ERR_IO, err, err_size, path, "cannot open", errno);
    return RF_OK;
}

static RfStatus alloc_failed(RfStatus st, const char *path, int w, int h, char *err, size_t err_size)
{
    return st == RF_ERR_NOMEM ? rf_io_fail(st, err, err_size, path, "out of memory")
                              : rf_io_fail(RF_ERR_PARSE, err, err_size, path, "unsupported image size %d x %d", w, h);
}

/* netpbm reports an error by calling the user's message function, then longjmp to the buffer set
 * with pm_setjmpbuf (else it exits). Both are the library's globals: this reader is not for
 * concurrent use. The message is dropped (its function gets no context to put it anywhere). */
static void pnm_quiet(const char *msg)
{
    (void)msg;
}

RfStatus rf_pnm_read(const char *path, RfPngOptions decode, RfImage *img, int *encoded, char *err, size_t err_size)
{
    FILE *fp = NULL;
    RfStatus st = open_checked(path, decode, img, &fp, err, err_size);
    if (st != RF_OK)
        return st;
    xel *volatile row = NULL;
    volatile RfStatus failed = RF_ERR_PARSE;
    volatile int reported = 0; /* err already says why */
    jmp_buf jb, *old = NULL;
    pm_init("refray", 0);
    pm_setusererrormsgfn(pnm_quiet);
    pm_setusermessagefn(pnm_quiet);
    pm_setjmpbufsave(&jb, &old);
    if (setjmp(jb)) {
        pm_setjmpbuf(old);
        pm_setusererrormsgfn(NULL);
        pm_setusermessagefn(NULL);
        if (row)
            pnm_freerow(row);
        rf_image_free(img);
        fclose(fp);
        if (reported)
            return failed;
        return failed == RF_ERR_PARSE ? rf_io_fail(RF_ERR_PARSE, err, err_size, path, "corrupt or truncated PNM (PPM/PGM/PBM) file")
                                      : alloc_failed(failed, path, 0, 0, err, err_size);
    }
    int cols, rows, format;
    xelval maxval;
    pnm_readpnminit(fp, &cols, &rows, &maxval, &format);
    int samples = PNM_FORMAT_TYPE(format) == PPM_TYPE ? 3 : 1;
    /* at least a bit a pixel (P4); refused here, the message kept for the jump below */
    st = rf_io_check_claim(path, "PNM", cols, rows, (double)cols * rows / 8.0, 1.0, 4096.0, err, err_size);
    if (st != RF_OK) {
        failed = st, reported = 1;
        pm_error("claim");
    }
    st = rf_image_alloc(img, cols, rows, samples);
    if (st != RF_OK) {
        failed = st;
        pm_error("size");
    }
    row = pnm_allocrow((unsigned)cols);
    for (int y = 0; y < rows; y++) {
        pnm_readpnmrow(fp, row, cols, maxval, format);
        for (int x = 0; x < cols; x++) {
            double v[3];
            if (samples == 3)
                v[0] = PPM_GETR(row[x]), v[1] = PPM_GETG(row[x]), v[2] = PPM_GETB(row[x]);
            else
                v[0] = PNM_GET1(row[x]);
            for (int c = 0; c < samples; c++)
                v[c] /= (double)maxval;
            store(img, (size_t)y * (size_t)cols + (size_t)x, v, samples, 0, decode);
        }
    }
    pnm_freerow(row);
    pm_setjmpbuf(old);
    pm_setusererrormsgfn(NULL);
    pm_setusermessagefn(NULL);
    fclose(fp);
    if (encoded)
        *encoded = 1;
    return RF_OK;
}

/* stb_image reads through these callbacks from the file in memory, so that a read past its end
 * is seen: stb_image itself goes on with zeros, and a truncated BMP or JPEG would read "fine". */
typedef struct {
    const unsigned char *data;
    size_t size, at;
    int overrun;
} StbSource;

static int stb_read(void *user, char *out, int n)
{
    StbSource *s = user;
    size_t k = s->size - s->at < (size_t)n ? s->size - s->at : (size_t)n;
    if (n > 0 && k == 0)
        s->overrun = 1;
    memcpy(out, s->data + s->at, k);
    s->at += k;
    return (int)k;
}

static void stb_skip(void *user, int n)
{
    StbSource *s = user;
    if (n < 0)
        s->at = (size_t)-n > s->at ? 0 : s->at - (size_t)-n;
    else if ((size_t)n > s->size - s->at)
        s->at = s->size, s->overrun = 1;
    else
        s->at += (size_t)n;
}

static int stb_eof(void *user)
{
    StbSource *s = user;
    return s->at >= s->size;
}

static const stbi_io_callbacks stb_io = {stb_read, stb_skip, stb_eof};

/* stb_image (2022) loops forever on a run-length count of 0 in a Radiance scanline (later fixed
 * upstream; a read past the end gives 0 too): the counts of every RLE scanline are walked first,
 * and a file with a zero count, a run past the scanline's end, or that ends inside a scanline is
 * refused before stb_image sees it. Only the layout is checked;
 * stb_image decodes the values. */
static const char *hdr_layout(const unsigned char *d, size_t n)
{
    size_t at = 0;
    int w = 0, h = 0, blank = 0;
    while (at < n && !blank) { /* header lines up to the empty one */
        const unsigned char *nl = memchr(d + at, '\n', n - at);
        if (!nl)
            return "truncated header";
        /* stb_image reads each line as a C string: one that starts with a 0 byte is "empty" and
         * ends the header there too (a walk that went on looked for the resolution in the wrong
         * line and let a hanging file through; found by fuzzing) */
        blank = nl == d + at || d[at] == 0;
        at = (size_t)(nl - d) + 1;
    }
    /* the resolution line as stb_image reads it: up to 1023 characters, the rest of the line
     * skipped (a longer line read only in part put the walk below off stb_image's place) */
    char line[1024];
    size_t k = 0;
    for (; at < n && d[at] != '\n'; at++)
        if (k + 1 < sizeof line)
            line[k++] = (char)d[at];
    line[k] = 0;
    at++;
    if (sscanf(line, "-Y %d +X %d", &h, &w) != 2 || w <= 0 || h <= 0)
        return NULL; /* another layout: stb_image refuses it */
    for (int y = 0; y < h; y++) {
        if (at + 4 > n)
            return "truncated pixels";
        if (w < 8 || w >= 32768 || d[at] != 2 || d[at + 1] != 2 || (d[at + 2] & 0x80))
            return NULL; /* flat pixels from here on: fixed size, read with zeros past the end */
        at += 4;
        for (int c = 0; c < 4; c++)
            for (int x = 0; x < w;) {
                if (at >= n)
                    return "truncated pixels";
                int count = d[at++];
                if (count > 128)
                    count -= 128, at++;
                else
                    at += (size_t)count;
                if (count == 0)
                    return "a run-length count of 0";
                if (count > w - x) /* stb_image (2022) would write past its scanline */
                    return "a run longer than the scanline";
                x += count;
            }
    }
    return at > n ? "truncated pixels" : NULL;
}

RfStatus rf_stb_read(const char *path, RfImageFile format, RfPngOptions decode, RfImage *img, int *encoded, char *err,
                     size_t err_size)
{
    FILE *fp = NULL;
    RfStatus st = open_checked(path, decode, img, &fp, err, err_size);
    if (st != RF_OK)
        return st;
    unsigned char *bytes = NULL;
    size_t size = 0, cap = 0;
    for (;;) { /* the whole file: students' images are small */
        if (size == cap) {
            unsigned char *b = cap < ((size_t)1 << 31) ? realloc(bytes, cap = cap ? 2 * cap : 1 << 16) : NULL;
            if (!b) {
                free(bytes);
                fclose(fp);
                return rf_io_fail(RF_ERR_NOMEM, err, err_size, path, "out of memory");
            }
            bytes = b;
        }
        size_t k = fread(bytes + size, 1, cap - size, fp);
        size += k;
        if (k == 0)
            break;
    }
    int read_error = ferror(fp);
    fclose(fp);
    if (read_error) {
        free(bytes);
        return rf_io_fail(RF_ERR_IO, err, err_size, path, "cannot read");
    }
    StbSource src = {bytes, size, 0, 0};
    int w, h, comp;
    const char *bad = NULL;
    if (!stbi_info_from_callbacks(&stb_io, &src, &w, &h, &comp))
        bad = stbi_failure_reason();
    src.at = 0;
    int hdr = !bad && stbi_is_hdr_from_callbacks(&stb_io, &src);
    src.at = 0;
    int wide = !bad && !hdr && stbi_is_16_bit_from_callbacks(&stb_io, &src);
    src.at = 0, src.overrun = 0;
    if (!bad && hdr)
        bad = hdr_layout(bytes, size);
    int want = comp == 2 ? 4 : 0, samples = want ? want : comp;
    /* refused before stb_image allocates anything for a size from a corrupt header; no format
     * stb_image reads here packs more than 512 pixels into a byte (a grey progressive JPEG whose
     * blocks have only their DC code, 1 bit for 64 pixels) */
    if (!bad && rf_io_check_claim(path, rf_image_file_name(format), w, h, (double)w * h, 512.0, 4096.0, err, err_size) != RF_OK) {
        free(bytes);
        return RF_ERR_PARSE;
    }
    st = bad ? RF_ERR_PARSE : rf_image_alloc(img, w, h, channels_for(samples));
    if (st != RF_OK) {
        free(bytes);
        return bad ? rf_io_fail(RF_ERR_PARSE, err, err_size, path, "corrupt or unsupported image (stb_image: %s)", bad)
                   : alloc_failed(st, path, w, h, err, err_size);
    }
    void *data = hdr    ? (void *)stbi_loadf_from_callbacks(&stb_io, &src, &w, &h, &comp, want)
               : wide ? (void *)stbi_load_16_from_callbacks(&stb_io, &src, &w, &h, &comp, want)
                      : (void *)stbi_load_from_callbacks(&stb_io, &src, &w, &h, &comp, want);
    free(bytes);
    if (!data || src.overrun || w != img->width || h != img->height || (!want && comp != samples)) {
        stbi_image_free(data);
        rf_image_free(img);
        return rf_io_fail(RF_ERR_PARSE, err, err_size, path, "corrupt or truncated image (stb_image: %s)",
                          !data ? stbi_failure_reason() : src.overrun ? "the file ends early" : "inconsistent header");
    }
    size_t n = (size_t)w * (size_t)h;
    for (size_t i = 0; i < n; i++) {
        double v[4];
        for (int c = 0; c < samples; c++) {
            size_t k = i * (size_t)samples + (size_t)c;
            v[c] = hdr ? ((const float *)data)[k] : wide ? ((const stbi_us *)data)[k] / 65535.0
                                                         : ((const stbi_uc *)data)[k] / 255.0;
        }
        store(img, i, v, samples, hdr, decode);
    }
    stbi_image_free(data);
    if (encoded)
        *encoded = !hdr;
    return RF_OK;
}

/* libtiff's messages go to the handlers given at TIFFOpenExt with a pointer of ours: the first
 * error is kept for the message, warnings are dropped. */
typedef struct {
    char msg[200];
} TiffMsg;

static int tiff_on_error(TIFF *t, void *user, const char *module, const char *fmt, va_list ap)
{
    TiffMsg *m = user;
    (void)t, (void)module;
    if (m && !m->msg[0])
        vsnprintf(m->msg, sizeof m->msg, fmt, ap);
    return 1;
}

static int tiff_quiet(TIFF *t, void *user, const char *module, const char *fmt, va_list ap)
{
    (void)t, (void)user, (void)module, (void)fmt, (void)ap;
    return 1;
}

/* The common layouts read row by row at their own depth: strips of interleaved grey(+alpha) or
 * RGB(A), 8/16-bit unsigned or 32-bit float samples. */
static int tiff_plain(TIFF *t, int photo, int samples, int bits, int format, int planar)
{
    int grey = photo == PHOTOMETRIC_MINISBLACK && (samples == 1 || samples == 2);
    int rgb = photo == PHOTOMETRIC_RGB && (samples == 3 || samples == 4);
    int depth = (format == SAMPLEFORMAT_UINT && (bits == 8 || bits == 16)) ||
                (format == SAMPLEFORMAT_IEEEFP && bits == 32);
    return !TIFFIsTiled(t) && planar == PLANARCONFIG_CONTIG && (grey || rgb) && depth;
}

static RfStatus tiff_rows(TIFF *t, RfImage *img, int samples, int bits, int linear, RfPngOptions decode)
{
    size_t row_bytes = (size_t)img->width * (size_t)samples * (size_t)(bits / 8);
    if ((size_t)TIFFScanlineSize64(t) != row_bytes)
        return RF_ERR_PARSE;
    unsigned char *row = malloc(row_bytes);
    if (!row)
        return RF_ERR_NOMEM;
    for (int y = 0; y < img->height; y++) {
        if (TIFFReadScanline(t, row, (uint32_t)y, 0) < 0) {
            free(row);
            return RF_ERR_PARSE;
        }
        for (int x = 0; x < img->width; x++) {
            double v[4];
            for (int c = 0; c < samples; c++) {
                size_t k = (size_t)x * (size_t)samples + (size_t)c;
                if (bits == 32) {
                    float f;
                    memcpy(&f, row + 4 * k, 4);
                    v[c] = f;
                } else if (bits == 16) {
                    uint16_t u;
                    memcpy(&u, row + 2 * k, 2); /* libtiff hands samples over in the machine's order */
                    v[c] = u / 65535.0;
                } else
                    v[c] = row[k] / 255.0;
            }
            store(img, (size_t)y * (size_t)img->width + (size_t)x, v, samples, linear, decode);
        }
    }
    free(row);
    return RF_OK;
}

/* Everything else libtiff can turn into 8-bit RGBA (palettes, YCbCr, JPEG-in-TIFF, tiles, 1-bit,
 * min-is-white, separate planes). */
static RfStatus tiff_rgba(TIFF *t, RfImage *img, int samples, RfPngOptions decode)
{
    size_t n = (size_t)img->width * (size_t)img->height;
    uint32_t *px = malloc(n * sizeof *px);
    if (!px)
        return RF_ERR_NOMEM;
    if (!TIFFReadRGBAImageOriented(t, (uint32_t)img->width, (uint32_t)img->height, px, ORIENTATION_TOPLEFT, 0)) {
        free(px);
        return RF_ERR_PARSE;
    }
    int has_alpha = samples == 2 || samples == 4;
    for (size_t i = 0; i < n; i++) {
        double v[4] = {TIFFGetR(px[i]) / 255.0, TIFFGetG(px[i]) / 255.0, TIFFGetB(px[i]) / 255.0,
                       TIFFGetA(px[i]) / 255.0};
        store(img, i, v, has_alpha ? 4 : 3, 0, decode);
    }
    free(px);
    return RF_OK;
}

RfStatus rf_tiff_read(const char *path, RfPngOptions decode, RfImage *img, int *encoded, char *err, size_t err_size)
{
    RfStatus st = rf_io_read_start(img, path, err, err_size);
    if (st == RF_OK)
        st = rf_io_check_decode(decode, path, err, err_size);
    if (st != RF_OK)
        return st;
    TiffMsg msg = {{0}};
    TIFFOpenOptions *o = TIFFOpenOptionsAlloc();
    if (!o)
        return rf_io_fail(RF_ERR_NOMEM, err, err_size, path, "out of memory");
    TIFFOpenOptionsSetErrorHandlerExtR(o, tiff_on_error, &msg);
    TIFFOpenOptionsSetWarningHandlerExtR(o, tiff_quiet, NULL);
    TIFFOpenOptionsSetMaxSingleMemAlloc(o, (tmsize_t)1 << 30);
    TIFF *t = TIFFOpenExt(path, "r", o);
    TIFFOpenOptionsFree(o);
    if (!t) {
        FILE *probe = fopen(path, "rb"); /* a missing file is an I/O error, not a corrupt one */
        if (!probe)
            return rf_io_fail_errno(RF_ERR_IO, err, err_size, path, "cannot open", errno);
        fclose(probe);
        return rf_io_fail(RF_ERR_PARSE, err, err_size, path, "corrupt or truncated TIFF (libtiff: %s)",
                          msg.msg[0] ? msg.msg : "cannot read the header");
    }
    uint32_t w = 0, h = 0;
    uint16_t samples = 1, bits = 1, format = SAMPLEFORMAT_UINT, planar = PLANARCONFIG_CONTIG, photo = 0;
    TIFFGetField(t, TIFFTAG_IMAGEWIDTH, &w);
    TIFFGetField(t, TIFFTAG_IMAGELENGTH, &h);
    TIFFGetFieldDefaulted(t, TIFFTAG_SAMPLESPERPIXEL, &samples);
    TIFFGetFieldDefaulted(t, TIFFTAG_BITSPERSAMPLE, &bits);
    TIFFGetFieldDefaulted(t, TIFFTAG_SAMPLEFORMAT, &format);
    TIFFGetFieldDefaulted(t, TIFFTAG_PLANARCONFIG, &planar);
    TIFFGetField(t, TIFFTAG_PHOTOMETRIC, &photo);
    uint16_t compression = COMPRESSION_NONE;
    TIFFGetFieldDefaulted(t, TIFFTAG_COMPRESSION, &compression);
    /* LZW packs at most ~2730 bytes into one, Deflate ~1032; the fax codes are left to libtiff
     * (a blank row takes a bit, whatever its width) */
    int fax = compression == COMPRESSION_CCITTRLE || compression == COMPRESSION_CCITTFAX3 ||
              compression == COMPRESSION_CCITTFAX4 || compression == COMPRESSION_CCITTRLEW;
    if (!fax && rf_io_check_claim(path, "TIFF", w, h, (double)w * h * samples * bits / 8.0, 4096.0, 65536.0, err,
                                  err_size) != RF_OK) {
        TIFFClose(t);
        return RF_ERR_PARSE;
    }
    int plain = tiff_plain(t, photo, samples, bits, format, planar);
    if (!plain && format != SAMPLEFORMAT_UINT) {
        TIFFClose(t);
        return rf_io_fail(RF_ERR_PARSE, err, err_size, path,
                          "unsupported TIFF layout (%u samples of %u bits, sample format %u, photometric %u)",
                          samples, bits, format, photo);
    }
    int nc = plain ? channels_for(samples) : samples == 2 || samples == 4 ? 4 : 3;
    st = w > 0x7fffffffu || h > 0x7fffffffu ? RF_ERR_DOMAIN : rf_image_alloc(img, (int)w, (int)h, nc);
    if (st != RF_OK) {
        TIFFClose(t);
        return alloc_failed(st, path, (int)(w & 0x7fffffff), (int)(h & 0x7fffffff), err, err_size);
    }
    int linear = format == SAMPLEFORMAT_IEEEFP;
    st = plain ? tiff_rows(t, img, samples, bits, linear, decode) : tiff_rgba(t, img, samples, decode);
    TIFFClose(t);
    if (st != RF_OK) {
        rf_image_free(img);
        return st == RF_ERR_NOMEM ? rf_io_fail(st, err, err_size, path, "out of memory")
                                  : rf_io_fail(st, err, err_size, path, "corrupt or truncated TIFF (libtiff: %s)",
                                               msg.msg[0] ? msg.msg : "cannot read the pixels");
    }
    if (encoded)
        *encoded = !linear;
    return RF_OK;
}
