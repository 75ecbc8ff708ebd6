/* Command-line values shared by refray's subcommands and refray-raster: numbers with ranges and
 * the options every scene/image command takes (--gamma, --srgb, --nff-fov). One parser, so the
 * commands cannot drift apart. */
#ifndef REFRAY_CLI_ARGS_H
#define REFRAY_CLI_ARGS_H

#include "refray/image.h"
#include "refray/render.h"
#include "refray/scene_io.h"

/* A whole-string decimal integer in [lo, hi]; 1 on success. */
int rf_arg_int(const char *s, int lo, int hi, int *out);
/* A whole-string finite number >= 0; 1 on success. */
int rf_arg_nonneg(const char *s, double *out);

/* Handles a = "--gamma G", "--srgb" or "--nff-fov centres|edges" (lopt may be NULL for commands
 * that load no scene). Returns 0 when a is none of them, 1 when it was handled (*used = the
 * number of arguments it took, value included), -1 for a bad or missing value. */
int rf_arg_shared(const char *a, const char *v, RfLoadOptions *lopt, RfPngOptions *popt, int *used);

/* Handles one of the options that decide a render (`refray render` and `refray trace`): --width,
 * --height, --samples, --depth, --threads, --seed, --sampler, --adaptive-threshold,
 * --adaptive-depth, --filter, --filter-radius, --aperture, --focus, --light-samples, --kernel,
 * --preview, --local. Returns 0 when a is none of them, 1 when handled (*used: the arguments
 * taken), -1 for a bad or missing value. */
int rf_arg_render(const char *a, const char *v, RfRenderOptions *opt, int *used);

#endif
