/* PNG through libpng. libpng reports errors by longjmp to the setjmp point of the calling function;
 * locals of that function changed after setjmp are volatile, and the error message lives in the
 * caller's frame (PngErr), so the error path sees determinate values (C99 7.13.2.1). */
#include "io_internal.h"

#include <errno.h>
#include <math.h>
#include <setjmp.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <png.h>

#include "refray/transfer.h"

typedef struct {
    char msg[200];   /* libpng's error message */
    RfStatus status; /* what a longjmp means: RF_ERR_PARSE / RF_ERR_IO, or RF_ERR_NOMEM */
} PngErr;

static void png_on_error(png_structp png, png_const_charp msg)
{
    PngErr *pe = png_get_error_ptr(png);
    if (pe)
        snprintf(pe->msg, sizeof pe->msg, "%s", msg ? msg : "unknown libpng error");
    png_longjmp(png, 1);
}

static void png_on_warning(png_structp png, png_const_charp msg)
{
    (void)png; /* warnings (e.g. a bad ancillary chunk) do not stop reading; the library stays quiet */
    (void)msg;
}

RfStatus rf_io_check_decode(RfPngOptions opt, const char *path, char *err, size_t err_size)
{
    if (opt.encoding != RF_PNG_AS_IS && opt.encoding != RF_PNG_GAMMA && opt.encoding != RF_PNG_SRGB)
        return rf_io_fail(RF_ERR_DOMAIN, err, err_size, path, "unknown PNG encoding %d", (int)opt.encoding);
    if (opt.encoding == RF_PNG_GAMMA && !(opt.gamma > 0.0 && isfinite(opt.gamma)))
        return rf_io_fail(RF_ERR_DOMAIN, err, err_size, path, "PNG gamma must be positive (got %g)", opt.gamma);
    return RF_OK;
}

double rf_io_encode_value(double v, RfPngOptions opt)
{
    switch (opt.encoding) {
    case RF_PNG_GAMMA: return rf_gamma_encode(v, opt.gamma);
    case RF_PNG_SRGB: return rf_srgb_encode(v);
    default: return v;
    }
}

double rf_io_decode_value(double v, RfPngOptions opt)
{
    switch (opt.encoding) {
    case RF_PNG_GAMMA: return rf_gamma_decode(v, opt.gamma);
    case RF_PNG_SRGB: return rf_srgb_decode(v);
    default: return v;
    }
}

/* One row of img as PNG codes (16-bit ones big-endian, as PNG stores them). */
static void encode_row(const RfImage *img, int y, RfPngOptions opt, unsigned char *row)
{
    const float *src = img->data + (size_t)y * (size_t)img->width * (size_t)img->channels;
    size_t i, n = (size_t)img->width * (size_t)img->channels;
    uint32_t last_bits = 0;
    long last_q = -1; /* the code of the last value encoded with the curve (-1: none yet) */
    for (i = 0; i < n; i++) {
        int alpha = img->channels == 4 && i % 4 == 3; /* PNG alpha is linear: no curve */
        uint32_t bits;
        memcpy(&bits, &src[i], sizeof bits);
        long q;
        if (!alpha && last_q >= 0 && bits == last_bits) {
            q = last_q; /* the same value as the last: its code again, without the curve's pow */
        } else {
            double v = alpha ? src[i] : rf_io_encode_value(src[i], opt);
            q = rf_quantize(v, opt.bits); /* clamps to [0,1] and rounds */
            if (!alpha)
                last_bits = bits, last_q = q;
        }
        if (opt.bits == 16) {
            row[2 * i] = (unsigned char)(q >> 8);
            row[2 * i + 1] = (unsigned char)(q & 0xff);
        } else
            row[i] = (unsigned char)q;
    }
}

static RfStatus png_write_impl(const char *path, const RfImage *img, RfPngOptions opt, PngErr *pe, char *err,
                               size_t err_size)
{
    png_structp png;
    png_infop info;
    RfAtomicFile f;
    RfStatus st;
    unsigned char *volatile row = NULL;
    int y, color_type;

    st = rf_io_check_image(img, path, err, err_size);
    if (st == RF_OK)
        st = rf_io_check_decode(opt, path, err, err_size);
    if (st != RF_OK)
        return st;
    if (opt.bits != 8 && opt.bits != 16)
        return rf_io_fail(RF_ERR_DOMAIN, err, err_size, path, "PNG bits must be 8 or 16 (got %d)", opt.bits);
    if ((size_t)img->width > PNG_UINT_31_MAX / 8)
        return rf_io_fail(RF_ERR_DOMAIN, err, err_size, path, "image too wide for PNG (%d pixels)", img->width);
    color_type = img->channels == 1 ? PNG_COLOR_TYPE_GRAY
               : img->channels == 3 ? PNG_COLOR_TYPE_RGB
                                    : PNG_COLOR_TYPE_RGB_ALPHA;

    png = png_create_write_struct(PNG_LIBPNG_VER_STRING, pe, png_on_error, png_on_warning);
    info = png ? png_create_info_struct(png) : NULL;
    if (!info) {
        png_destroy_write_struct(&png, NULL);
        return rf_io_fail(RF_ERR_NOMEM, err, err_size, path, "out of memory");
    }
    st = rf_atomic_open(&f, path, err, err_size);
    if (st == RF_OK)
        st = rf_atomic_stdio(&f, err, err_size);
    if (st != RF_OK) {
        rf_atomic_abort(&f);
        png_destroy_write_struct(&png, &info);
        return st;
    }
    row = malloc((size_t)img->width * (size_t)img->channels * (size_t)(opt.bits / 8));
    if (!row) {
        rf_atomic_abort(&f);
        png_destroy_write_struct(&png, &info);
        return rf_io_fail(RF_ERR_NOMEM, err, err_size, path, "out of memory");
    }
    if (setjmp(png_jmpbuf(png))) {
        free(row);
        png_destroy_write_struct(&png, &info);
        rf_atomic_abort(&f);
        return rf_io_fail(pe->status, err, err_size, path, "cannot write PNG: %s", pe->msg);
    }
    png_init_io(png, f.fp);
    png_set_IHDR(png, info, (png_uint_32)img->width, (png_uint_32)img->height, opt.bits, color_type,
                 PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    /* Tell viewers how the codes are encoded; as-is values carry no claim. */
    if (opt.encoding == RF_PNG_SRGB)
        png_set_sRGB_gAMA_and_cHRM(png, info, PNG_sRGB_INTENT_PERCEPTUAL);
    else if (opt.encoding == RF_PNG_GAMMA)
        png_set_gAMA(png, info, 1.0 / opt.gamma);
    png_write_info(png, info);
    for (y = 0; y < img->height; y++) {
        encode_row(img, y, opt, row);
        png_write_row(png, row);
    }
    png_write_end(png, info);
    free(row);
    png_destroy_write_struct(&png, &info);
    return rf_atomic_finish(&f, opt.batch, err, err_size);
}

RfStatus rf_png_write(const char *path, const RfImage *img, RfPngOptions opt, char *err, size_t err_size)
{
    PngErr pe;
    pe.msg[0] = '\0';
    pe.status = RF_ERR_IO;
    return png_write_impl(path, img, opt, &pe, err, err_size);
}

static RfStatus png_read_impl(const char *path, RfPngOptions decode, RfImage *img, PngErr *pe, char *err,
                              size_t err_size)
{
    png_structp png;
    png_infop info;
    FILE *fp;
    RfStatus st;
    png_bytep *volatile rows = NULL;
    unsigned char *volatile pixels = NULL;
    png_uint_32 w, h, y;
    int depth, color_type, nc;
    size_t rowbytes, i, n;

    RfStatus started = rf_io_read_start(img, path, err, err_size);
    if (started != RF_OK)
        return started;
    st = rf_io_check_decode(decode, path, err, err_size);
    if (st != RF_OK)
        return st;
    fp = fopen(path, "rb");
    if (!fp)
        return rf_io_fail_errno(RF_ERR_IO, err, err_size, path, "cannot open", errno);
    png = png_create_read_struct(PNG_LIBPNG_VER_STRING, pe, png_on_error, png_on_warning);
    info = png ? png_create_info_struct(png) : NULL;
    if (!info) {
        png_destroy_read_struct(&png, NULL, NULL);
        fclose(fp);
        return rf_io_fail(RF_ERR_NOMEM, err, err_size, path, "out of memory");
    }
    if (setjmp(png_jmpbuf(png))) {
        free(rows);
        free(pixels);
        rf_image_free(img);
        png_destroy_read_struct(&png, &info, NULL);
        fclose(fp);
        return rf_io_fail(pe->status, err, err_size, path, "%s: %s",
                          pe->status == RF_ERR_NOMEM ? "cannot read PNG" : "corrupt or truncated PNG", pe->msg);
    }
    png_init_io(png, fp);
    /* No chunk may make libpng allocate more than 16 MiB, and every ancillary chunk refray does
     * not read (text, palettes, profiles, times, ...; only tRNS gives pixels) is skipped unread:
     * 119 bytes asked libpng for 2 GiB through a malformed sPLT, 71 bytes took 1.8 GB through an
     * iTXt that claimed 1.8 GB (both found by fuzzing, tests/data/fuzz/png/). */
    static const png_byte skipped[] = "cHRM\0gAMA\0iCCP\0sBIT\0sRGB\0bKGD\0hIST\0pHYs\0sPLT\0tIME\0iTXt\0"
                                      "tEXt\0zTXt\0eXIf\0oFFs\0pCAL\0sCAL\0sTER\0";
    png_set_chunk_malloc_max(png, (png_alloc_size_t)16 << 20);
    png_set_keep_unknown_chunks(png, PNG_HANDLE_CHUNK_NEVER, NULL, 0); /* unknown ones too */
    png_set_keep_unknown_chunks(png, PNG_HANDLE_CHUNK_NEVER, skipped, (int)(sizeof skipped / 5));
    png_read_info(png, info);
    color_type = png_get_color_type(png, info);
    depth = png_get_bit_depth(png, info);
    w = png_get_image_width(png, info);
    h = png_get_image_height(png, info);
    /* the filtered rows come out of zlib, at most ~1032 bytes from one */
    st = rf_io_check_claim(path, "PNG", w, h, (double)w * h * png_get_channels(png, info) * depth / 8.0, 1032.0,
                           65536.0, err, err_size);
    if (st != RF_OK) {
        png_destroy_read_struct(&png, &info, NULL);
        fclose(fp);
        return st;
    }
    /* Raw codes in 8 or 16 bits as grey, RGB or RGBA; no gamma handling by libpng: the curve
     * is the caller's choice. */
    if (color_type == PNG_COLOR_TYPE_PALETTE)
        png_set_palette_to_rgb(png);
    if (color_type == PNG_COLOR_TYPE_GRAY && depth < 8)
        png_set_expand_gray_1_2_4_to_8(png);
    if (png_get_valid(png, info, PNG_INFO_tRNS))
        png_set_tRNS_to_alpha(png);
    if (color_type == PNG_COLOR_TYPE_GRAY_ALPHA ||
        (color_type == PNG_COLOR_TYPE_GRAY && png_get_valid(png, info, PNG_INFO_tRNS)))
        png_set_gray_to_rgb(png);
    png_set_interlace_handling(png);
    png_read_update_info(png, info); /* the transforms change depth and channels, not the size */
    depth = png_get_bit_depth(png, info);
    nc = png_get_channels(png, info);
    rowbytes = png_get_rowbytes(png, info);
    if (w > 0x7fffffffu || h > 0x7fffffffu || (nc != 1 && nc != 3 && nc != 4) || (depth != 8 && depth != 16))
        png_error(png, "unsupported PNG layout");
    st = rf_image_alloc(img, (int)w, (int)h, nc);
    if (st == RF_ERR_DOMAIN)
        png_error(png, "unsupported image size");
    if (st != RF_OK) {
        pe->status = RF_ERR_NOMEM;
        png_error(png, "out of memory");
    }
    if (rowbytes != (size_t)w * (size_t)nc * (size_t)(depth / 8))
        png_error(png, "unexpected row size");
    pixels = malloc(rowbytes * h);
    rows = malloc(sizeof(png_bytep) * h);
    if (!pixels || !rows) {
        pe->status = RF_ERR_NOMEM;
        png_error(png, "out of memory");
    }
    for (y = 0; y < h; y++)
        rows[y] = pixels + (size_t)y * rowbytes;
    png_read_image(png, rows);
    png_read_end(png, NULL);

    n = (size_t)w * (size_t)h * (size_t)nc;
    for (i = 0; i < n; i++) {
        double v = depth == 16 ? (pixels[2 * i] << 8 | pixels[2 * i + 1]) / 65535.0 : pixels[i] / 255.0;
        img->data[i] = (float)(nc == 4 && i % 4 == 3 ? v : rf_io_decode_value(v, decode));
    }
    free(rows);
    free(pixels);
    png_destroy_read_struct(&png, &info, NULL);
    fclose(fp);
    return RF_OK;
}

RfStatus rf_png_read(const char *path, RfPngOptions decode, RfImage *img, char *err, size_t err_size)
{
    PngErr pe;
    pe.msg[0] = '\0';
    pe.status = RF_ERR_PARSE;
    return png_read_impl(path, decode, img, &pe, err, err_size);
}
