/* Command-line values shared by refray's subcommands, refray-raster and refray-view: numbers with
 * ranges, the option table fragments every scene/image command merges into its own table (opt.h)
 * with one handler each, and output images whose format follows their name. One parser, so the
 * commands cannot drift apart. */
#ifndef REFRAY_CLI_ARGS_H
#define REFRAY_CLI_ARGS_H

#include "opt.h"
#include "refray/image.h"
#include "refray/render.h"
#include "refray/scene_io.h"

/* A whole-string decimal integer in [lo, hi]; 1 on success. */
int rf_arg_int(const char *s, int lo, int hi, int *out);
/* A whole-string finite number >= 0; 1 on success. */
int rf_arg_nonneg(const char *s, double *out);

/* The keys of the shared options (opt.h: ids from 0x1000, clear of each command's own). */
enum {
    RF_ARG_GAMMA = 0x1000, RF_ARG_SRGB, RF_ARG_NFF_FOV,
    RF_ARG_WIDTH = 0x1100, RF_ARG_HEIGHT, RF_ARG_SAMPLES, RF_ARG_DEPTH, RF_ARG_THREADS, RF_ARG_SEED,
    RF_ARG_SAMPLER, RF_ARG_ADAPTIVE_THRESHOLD, RF_ARG_ADAPTIVE_DEPTH, RF_ARG_FILTER, RF_ARG_FILTER_RADIUS,
    RF_ARG_APERTURE, RF_ARG_FOCUS, RF_ARG_LIGHT_SAMPLES, RF_ARG_KERNEL, RF_ARG_PREVIEW, RF_ARG_LOCAL,
    RF_ARG_TWO_SIDED, RF_ARG_SHADOWS, RF_ARG_THRESHOLD
};

/* --gamma G and --srgb: how a PNG is encoded or decoded. */
extern const RfOpt rf_opts_png[];
/* --nff-fov centres|edges: how an NFF scene's angle is read. */
extern const RfOpt rf_opts_load[];
/* Handles the keys of rf_opts_png and rf_opts_load (lopt may be NULL for commands that load no
 * scene). 0 when key is none of them, 1 when handled, -1 for a bad value. */
int rf_arg_shared(int key, const char *v, RfLoadOptions *lopt, RfPngOptions *popt);

/* The options that decide a render (`refray render` and `refray trace`): --width, --height,
 * --samples, --depth, --threads, --seed, --sampler, --adaptive-threshold, --adaptive-depth,
 * --filter, --filter-radius, --aperture, --focus, --light-samples, --kernel, --preview, --local,
 * --two-sided, --shadows. */
extern const RfOpt rf_opts_render[];
/* 0 when key is not one of rf_opts_render, 1 when handled, -1 for a bad value. */
int rf_arg_render(int key, const char *v, RfRenderOptions *opt);

/* Output images: the format follows the name's extension (case-insensitive). */
typedef enum { RF_IMAGE_EXR = 1, RF_IMAGE_PNG = 2, RF_IMAGE_SVG = 4 } RfImageFormat;
/* The format path names among the allowed ones (an OR of RfImageFormat), or 0 after the message
 * "PROG: OPTION FILE: the name must end in .exr or .png (the format follows it)" on stderr. */
int rf_arg_image_format(const char *prog, const char *option, const char *path, unsigned allowed);
/* Writes img as the EXR (attrs, eopt) or the PNG (popt) its name asks for. */
RfStatus rf_arg_write_image(const char *path, const RfImage *img, const RfImageAttr *attrs, int nattrs,
                            RfExrOptions eopt, RfPngOptions popt, char *err, size_t errsz);

/* rf_outputs_check with the message "PROG: ..." on stderr: 0 when the outputs are good, else the
 * exit code: RF_EXIT_USAGE for an output that is an input or given twice, RF_EXIT_FILE for one
 * that cannot be written. */
int rf_arg_outputs_check(const char *prog, const char *const *outs, int n_out, const char *const *ins, int n_in);

/* A loader's message on stderr: "file:line:col: ..." as it is (the form editors jump to), any
 * other (a file that cannot be opened has no line) after "PROG: ". */
void rf_arg_report(const char *prog, const char *err);

#endif
