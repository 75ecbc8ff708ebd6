/* refray: helpers shared by the image writers and readers (not part of the public API). */
#ifndef REFRAY_IO_INTERNAL_H
#define REFRAY_IO_INTERNAL_H

#include <stdio.h>

#include "refray/image.h"

/* printf-style "path: message" into err (if err and err_size allow); returns status. */
RfStatus rf_io_fail(RfStatus status, char *err, size_t err_size, const char *path, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 5, 6)))
#endif
    ;

/* "path: what: strerror(errnum)"; thread-safe (strerror_r). */
RfStatus rf_io_fail_errno(RfStatus status, char *err, size_t err_size, const char *path, const char *what,
                          int errnum);

/* The start of every reader: img must exist (it is emptied) and path must be given. */
RfStatus rf_io_read_start(RfImage *img, const char *path, char *err, size_t err_size);

/* A header's image size checked against its file before anything is allocated for it (fuzzing
 * found files of 58 to 263 bytes that asked for 2 GiB and more): a format that packs at most
 * per_byte decoded bytes into one byte of the file cannot hold decoded_bytes in fewer than
 * decoded_bytes / per_byte of them; slack_bytes covers headers and tiny images. RF_ERR_PARSE
 * with "FORMAT claims W x H pixels, far more than its N bytes can hold", else RF_OK (also when
 * the file cannot be stat'ed: the reader reports that). */
RfStatus rf_io_check_claim(const char *path, const char *format, long long width, long long height,
                           double decoded_bytes, double per_byte, double slack_bytes, char *err, size_t err_size);

/* Validates width/height/channels/data of an image to be written. */
RfStatus rf_io_check_image(const RfImage *img, const char *path, char *err, size_t err_size);

/* A file being written under a temporary name in the target's folder. Either fd is written
 * directly, or the caller wraps it in fp (rf_atomic_stdio) and writes through stdio. */
typedef struct {
    const char *path; /* the target as given (for messages) */
    char *target;     /* the file written: path with symbolic links followed (malloc'd) */
    char *tmp;        /* the temporary file's name (malloc'd) */
    int fd;
    FILE *fp;
} RfAtomicFile;

/* Creates the temporary file (mkstemp) next to path. */
RfStatus rf_atomic_open(RfAtomicFile *f, const char *path, char *err, size_t err_size);
/* Wraps the descriptor in a stdio stream (f->fp). */
RfStatus rf_atomic_stdio(RfAtomicFile *f, char *err, size_t err_size);
/* Flushes and closes the temporary file, then renames it over the target. On failure the
 * temporary file is removed and the target is untouched. Always releases f. */
RfStatus rf_atomic_commit(RfAtomicFile *f, char *err, size_t err_size);
/* Closes and removes the temporary file; the target is untouched. Safe to call twice. */
void rf_atomic_abort(RfAtomicFile *f);
/* rf_atomic_commit, or with a batch: closes the temporary file and hands it to the batch,
 * which renames it at rf_write_batch_commit. Always releases f. */
RfStatus rf_atomic_finish(RfAtomicFile *f, RfWriteBatch *batch, char *err, size_t err_size);

/* The PNG options' curve, shared by every reader of integer codes (PNG, PNM, JPEG, BMP, TIFF):
 * rf_io_check_decode refuses an unknown encoding or a bad gamma, rf_io_decode_value maps a code
 * in [0, 1] to a linear value, rf_io_encode_value a linear value to a code's (unclamped; png.c). */
RfStatus rf_io_check_decode(RfPngOptions opt, const char *path, char *err, size_t err_size);
double rf_io_decode_value(double v, RfPngOptions opt);
double rf_io_encode_value(double v, RfPngOptions opt);

/* The readers of the formats students write besides EXR and PNG (foreign.c), through Debian's
 * libraries: netpbm (PBM/PGM/PPM, plain and raw), stb_image (JPEG, BMP, TGA, Radiance HDR),
 * libtiff. *encoded (may be NULL) is set to 1 for integer codes decoded with the curve, 0 for
 * linear floats (HDR, float TIFF). rf_stb_read's format is the one the dispatcher sniffed (for
 * messages; stb_image finds it again by itself). */
RfStatus rf_pnm_read(const char *path, RfPngOptions decode, RfImage *img, int *encoded, char *err, size_t err_size);
RfStatus rf_stb_read(const char *path, RfImageFile format, RfPngOptions decode, RfImage *img, int *encoded, char *err,
                     size_t err_size);
RfStatus rf_tiff_read(const char *path, RfPngOptions decode, RfImage *img, int *encoded, char *err, size_t err_size);

#endif
