/* Reading an image by its signature: the dispatcher above the EXR, PNG, PNM, JPEG, BMP, HDR, TIFF
 * and TGA readers. GIF is not read: stb_image's GIF decoder has had memory errors, and students
 * do not write GIF renders. */
#include "io_internal.h"

#include <errno.h>
#include <string.h>
#include <strings.h>

static int has_suffix(const char *path, const char *suffix)
{
    size_t n = strlen(path), k = strlen(suffix);
    return n >= k && strcasecmp(path + n - k, suffix) == 0;
}

/* The format by the first bytes; TGA has no signature and goes by its extension. */
static RfImageFile sniff(const unsigned char *s, size_t n, const char *path)
{
    if (n >= 4 && memcmp(s, "\x76\x2f\x31\x01", 4) == 0)
        return RF_FILE_EXR;
    if (n >= 8 && memcmp(s, "\x89PNG\r\n\x1a\n", 8) == 0)
        return RF_FILE_PNG;
    if (n >= 2 && s[0] == 'P' && s[1] >= '1' && s[1] <= '6')
        return RF_FILE_PNM;
    if (n >= 3 && memcmp(s, "\xff\xd8\xff", 3) == 0)
        return RF_FILE_JPEG;
    if (n >= 4 && (memcmp(s, "II*\0", 4) == 0 || memcmp(s, "MM\0*", 4) == 0))
        return RF_FILE_TIFF;
    if (n >= 2 && memcmp(s, "BM", 2) == 0)
        return RF_FILE_BMP;
    if (n >= 2 && memcmp(s, "#?", 2) == 0) /* "#?RADIANCE" or "#?RGBE" */
        return RF_FILE_HDR;
    /* stb_image would take a GIF, PSD or Softimage PIC named .tga for what it is */
    if (n >= 4 && (memcmp(s, "GIF8", 4) == 0 || memcmp(s, "8BPS", 4) == 0 || memcmp(s, "\x53\x80\xf6\x34", 4) == 0))
        return RF_FILE_UNKNOWN;
    return has_suffix(path, ".tga") ? RF_FILE_TGA : RF_FILE_UNKNOWN;
}

RfStatus rf_image_read_source(const char *path, RfPngOptions decode, RfImage *img, RfImageSource *src, char *err,
                              size_t err_size)
{
    unsigned char sig[16];
    size_t n;
    FILE *fp;
    int encoded = 1;
    RfStatus st;

    if (src)
        src->format = RF_FILE_UNKNOWN, src->encoded = 0;
    st = rf_io_read_start(img, path, err, err_size);
    if (st != RF_OK)
        return st;
    fp = fopen(path, "rb");
    if (!fp)
        return rf_io_fail_errno(RF_ERR_IO, err, err_size, path, "cannot open", errno);
    n = fread(sig, 1, sizeof sig, fp);
    if (n < sizeof sig && ferror(fp)) {
        int e = errno;
        fclose(fp);
        return rf_io_fail_errno(RF_ERR_IO, err, err_size, path, "cannot read", e);
    }
    fclose(fp);
    RfImageFile f = sniff(sig, n, path);
    switch (f) {
    case RF_FILE_EXR: st = rf_exr_read(path, img, err, err_size), encoded = 0; break;
    case RF_FILE_PNG: st = rf_png_read(path, decode, img, err, err_size); break;
    case RF_FILE_PNM: st = rf_pnm_read(path, decode, img, &encoded, err, err_size); break;
    case RF_FILE_TIFF: st = rf_tiff_read(path, decode, img, &encoded, err, err_size); break;
    case RF_FILE_JPEG: case RF_FILE_BMP: case RF_FILE_HDR: case RF_FILE_TGA:
        st = rf_stb_read(path, f, decode, img, &encoded, err, err_size);
        break;
    default:
        return rf_io_fail(RF_ERR_PARSE, err, err_size, path,
                          "not an image refray reads (unknown signature; EXR, PNG, PPM/PGM/PBM, JPEG, TIFF, BMP, "
                          "HDR, TGA)");
    }
    if (st == RF_OK && src)
        src->format = f, src->encoded = encoded;
    return st;
}

RfStatus rf_image_read(const char *path, RfPngOptions png_decode, RfImage *img, char *err, size_t err_size)
{
    return rf_image_read_source(path, png_decode, img, NULL, err, err_size);
}
