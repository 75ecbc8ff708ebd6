/* refray: float images and their files — OpenEXR (linear, OpenEXRCore C API) and PNG (libpng).
 * Writers write to a temporary file in the target's folder and rename it into place, so a
 * failed write never leaves a corrupt file under the target name. */
#ifndef REFRAY_IMAGE_H
#define REFRAY_IMAGE_H

#include <stddef.h>

#include "refray/status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Interleaved float pixels, row 0 at the top: data[(y * width + x) * channels + c].
 * channels is 1 (Y), 3 (RGB) or 4 (RGBA). */
typedef struct {
    int width, height, channels;
    float *data;
} RfImage;

/* The largest image accepted, in pixels (16384 x 16384; 4 GiB as RGBA floats): sizes read from
 * a corrupt header are refused before anything is allocated. */
#define RF_IMAGE_MAX_PIXELS ((size_t)1 << 28)

/* Zeroed pixels. RF_ERR_DOMAIN for a size <= 0, above RF_IMAGE_MAX_PIXELS, or channels not
 * 1, 3 or 4; RF_ERR_NOMEM when the allocation fails. On failure *img is empty (data NULL). */
RfStatus rf_image_alloc(RfImage *img, int width, int height, int channels);
void rf_image_free(RfImage *img); /* safe on an empty or already freed image */

/* How PNG maps values to 8- or 16-bit codes: as they are (already display-encoded),
 * with the power curve v^(1/gamma) (the script's §1.1.2), or with the sRGB curve. Values are
 * clamped to [0,1] after encoding and quantised by round(v * (2^bits - 1)). */
typedef enum { RF_PNG_AS_IS, RF_PNG_GAMMA, RF_PNG_SRGB } RfPngEncoding;

/* Several output files committed together: each writer given the batch writes its temporary
 * file and closes it; rf_write_batch_commit renames them all into place, rf_write_batch_abort
 * (or a failed write, after which the caller aborts) removes them all, so a command never leaves
 * one output written and another not. */
typedef struct RfWriteBatch RfWriteBatch;
RfWriteBatch *rf_write_batch_new(void);
RfStatus rf_write_batch_commit(RfWriteBatch *batch, char *err, size_t err_size); /* frees the batch */
void rf_write_batch_abort(RfWriteBatch *batch);                                   /* frees the batch */
/* A text file (len bytes) written under a temporary name and renamed into place, or with a
 * batch renamed at rf_write_batch_commit (src/io/textfile.c). */
RfStatus rf_write_text(const char *path, const char *text, size_t len, RfWriteBatch *batch, char *err,
                       size_t err_size);

typedef struct {
    RfPngEncoding encoding;
    double gamma;  /* for RF_PNG_GAMMA, e.g. 2.2 */
    int bits;      /* 8 or 16 */
    RfWriteBatch *batch; /* writing: NULL renames the file into place at once */
} RfPngOptions;

/* A text attribute of an EXR header (name, value). */
typedef struct {
    const char *name, *value;
} RfImageAttr;

/* How an EXR is stored. ZIP (zlib over 16 scanlines) is the default: lossless, so floats read back
 * bit-exact, and read by every OpenEXR reader. PIZ is lossless too; NONE is the fastest. */
typedef enum { RF_EXR_ZIP, RF_EXR_NONE, RF_EXR_PIZ } RfExrCompression;

typedef struct {
    RfExrCompression compression;
    int half; /* 0: 32-bit FLOAT channels (the default, exact); 1: 16-bit HALF (rounded) */
    RfWriteBatch *batch; /* NULL renames the file into place at once */
    /* A crop of a larger image: the pixels' place in it (the data window starts at x0, y0) and
     * its size (the display window); display 0 x 0: the image is the whole picture. */
    int x0, y0, display_width, display_height;
} RfExrOptions;

/* A window of an EXR in pixels: [x0, x1) x [y0, y1). */
typedef struct {
    int x0, y0, x1, y1;
} RfExrWindow;

/* Output paths. A writer writes through a symbolic link (to the file it names) and refuses a
 * target that exists and is not a regular file (a device such as /dev/full, a directory, a
 * pipe). rf_output_check says so before any work: it also creates and removes a temporary file
 * next to the target, so an unwritable folder is found before a render, not after it.
 * rf_output_same: do two paths name the same file (after links; for files that do not exist yet,
 * the same resolved path)? A command refuses an output that is one of its inputs or another of
 * its outputs. */
RfStatus rf_output_check(const char *path, char *err, size_t err_size);
int rf_output_same(const char *a, const char *b);
/* A command's outputs before it works: each one checked (rf_output_check; NULL entries are
 * skipped), none the same as another or as one of the inputs. */
RfStatus rf_outputs_check(const char *const *outs, int n_out, const char *const *ins, int n_in, char *err,
                          size_t err_size);

/* err gets one line "path: message" on failure. Status: RF_ERR_DOMAIN for bad arguments,
 * RF_ERR_IO for a file that cannot be opened, read or written, RF_ERR_PARSE for a corrupt or
 * unsupported file, RF_ERR_NOMEM. A writer never leaves a partial file under the target name
 * (it writes "<target>.XXXXXX" in the same folder, then renames, at once or with its batch); a
 * new file gets mode 0644, a replaced one keeps its mode. */
/* 1, 3 or 4 channels give grey, RGB or RGBA. Alpha is quantised without the curve (PNG alpha is
 * linear). The file says how it is encoded: gAMA 1/gamma for RF_PNG_GAMMA, sRGB (with gAMA and
 * cHRM) for RF_PNG_SRGB, nothing for RF_PNG_AS_IS. */
RfStatus rf_png_write(const char *path, const RfImage *img, RfPngOptions opt, char *err, size_t err_size);
/* Channels R,G,B(,A), or Y for a one-channel image, as 32-bit FLOAT with ZIP compression; each
 * attribute is stored as a string attribute of the header (names must not be EXR's own, such as
 * "channels" or "compression"). */
RfStatus rf_exr_write(const char *path, const RfImage *img, const RfImageAttr *attrs, int nattrs,
                      char *err, size_t err_size);
RfStatus rf_exr_write_opts(const char *path, const RfImage *img, const RfImageAttr *attrs, int nattrs,
                           RfExrOptions opt, char *err, size_t err_size);
/* Reads an image, its format chosen by the file's signature (TGA, which has none, by the extension
 * .tga): EXR and Radiance HDR (linear floats, taken as they are), PNG, PPM/PGM/PBM (plain P1-P3 and
 * raw P4-P6), JPEG, BMP, TGA and TIFF (8- or 16-bit codes, display-encoded: decoded with the
 * given options' inverse curve into linear floats, like a PNG; a float TIFF is linear). PNG and EXR
 * through refray's readers below, the others through netpbm, stb_image and libtiff. On failure
 * *img is empty (data NULL). */
RfStatus rf_image_read(const char *path, RfPngOptions png_decode, RfImage *img, char *err, size_t err_size);

typedef enum {
    RF_FILE_UNKNOWN, RF_FILE_EXR, RF_FILE_PNG, RF_FILE_PNM, RF_FILE_JPEG, RF_FILE_TIFF, RF_FILE_BMP, RF_FILE_HDR,
    RF_FILE_TGA
} RfImageFile;
const char *rf_image_file_name(RfImageFile f); /* "EXR", "PNG", "PNM", "JPEG", ... */

/* What was read: the format, and whether the file held display-encoded integer codes (decoded
 * with the curve: PNG, PNM, JPEG, BMP, TGA, integer TIFF) or linear floats (EXR, HDR,
 * float TIFF). */
typedef struct {
    RfImageFile format;
    int encoded;
} RfImageSource;
/* rf_image_read, and src (may be NULL) says what the file was. */
RfStatus rf_image_read_source(const char *path, RfPngOptions decode, RfImage *img, RfImageSource *src, char *err,
                              size_t err_size);

/* The readers behind rf_image_read. EXR: the first part, scanline storage (tiled and deep files
 * are refused), every standard compression, HALF/FLOAT/UINT channels converted to float; R,G,B(,A) give 3
 * (4) channels, Y alone 1, Y with A 4 (Y copied to R, G, B). The data window becomes the image.
 * PNG: any colour type and depth; palette and grey+alpha become RGB(A); alpha is never curved
 * (PNG alpha is linear). */
RfStatus rf_exr_read(const char *path, RfImage *img, char *err, size_t err_size);
RfStatus rf_png_read(const char *path, RfPngOptions decode, RfImage *img, char *err, size_t err_size);

/* An EXR's data window (where its pixels sit) and display window (the whole picture), either
 * may be NULL. A crop written with RfExrOptions x0, y0 and a display size reads back as those. */
RfStatus rf_exr_read_windows(const char *path, RfExrWindow *data, RfExrWindow *display, char *err, size_t err_size);

/* A string attribute of an EXR's header: *value is malloc'd (free it). RF_ERR_DOMAIN with a
 * message when the attribute is missing or not a string. */
RfStatus rf_exr_read_attr(const char *path, const char *name, char **value, char *err, size_t err_size);

#ifdef __cplusplus
}
#endif

#endif
