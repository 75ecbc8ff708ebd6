/* Reading an image by its signature: the dispatcher above the EXR and PNG readers. */
#include "io_internal.h"

#include <errno.h>
#include <string.h>

RfStatus rf_image_read(const char *path, RfPngOptions png_decode, RfImage *img, char *err, size_t err_size)
{
    static const unsigned char exr_magic[4] = {0x76, 0x2f, 0x31, 0x01};
    static const unsigned char png_magic[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    unsigned char sig[8];
    size_t n;
    FILE *fp;

    RfStatus started = rf_io_read_start(img, path, err, err_size);
    if (started != RF_OK)
        return started;
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
    if (n >= sizeof exr_magic && memcmp(sig, exr_magic, sizeof exr_magic) == 0)
        return rf_exr_read(path, img, err, err_size);
    if (n == sizeof png_magic && memcmp(sig, png_magic, sizeof png_magic) == 0)
        return rf_png_read(path, png_decode, img, err, err_size);
    return rf_io_fail(RF_ERR_PARSE, err, err_size, path, "not an OpenEXR or PNG file (unknown signature)");
}

