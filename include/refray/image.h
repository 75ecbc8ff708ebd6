/* refray: float images and their files — OpenEXR (linear, OpenEXRCore C API) and PNG (libpng).
 * Writers write to a temporary file in the target's folder and rename it into place, so a
 * failed write never leaves a corrupt file under the target name. */
#ifndef REFRAY_IMAGE_H
#define REFRAY_IMAGE_H

#include <stddef.h>

#include "refray/status.h"

/* Interleaved float pixels, row 0 at the top: data[(y * width + x) * channels + c].
 * channels is 1 (Y), 3 (RGB) or 4 (RGBA). */
typedef struct {
    int width, height, channels;
    float *data;
} RfImage;

RfStatus rf_image_alloc(RfImage *img, int width, int height, int channels); /* zeroed */
void rf_image_free(RfImage *img);

/* How PNG maps values to 8- or 16-bit codes: as they are (already display-encoded),
 * with the power curve v^(1/gamma) (the script's §1.1.2), or with the sRGB curve. Values are
 * clamped to [0,1] after encoding and quantised by round(v * (2^bits - 1)). */
typedef enum { RF_PNG_AS_IS, RF_PNG_GAMMA, RF_PNG_SRGB } RfPngEncoding;

typedef struct {
    RfPngEncoding encoding;
    double gamma;  /* for RF_PNG_GAMMA, e.g. 2.2 */
    int bits;      /* 8 or 16 */
} RfPngOptions;

/* A text attribute of an EXR header (name, value). */
typedef struct {
    const char *name, *value;
} RfImageAttr;

/* err gets one line "path: message" on failure. */
RfStatus rf_png_write(const char *path, const RfImage *img, RfPngOptions opt, char *err, size_t err_size);
RfStatus rf_exr_write(const char *path, const RfImage *img, const RfImageAttr *attrs, int nattrs,
                      char *err, size_t err_size);
/* Reads an EXR (as float, linear) or a PNG (decoded with the given options' inverse curve into
 * linear floats), chosen by the file's signature. */
RfStatus rf_image_read(const char *path, RfPngOptions png_decode, RfImage *img, char *err, size_t err_size);

#endif
