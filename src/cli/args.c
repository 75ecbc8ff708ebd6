/* Shared command-line values (args.h). */
#include "args.h"
#include "exit_codes.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

int rf_arg_int(const char *s, int lo, int hi, int *out)
{
    char *end;
    long v = strtol(s, &end, 10);
    if (*s == 0 || *end != 0 || v < lo || v > hi)
        return 0;
    *out = (int)v;
    return 1;
}

int rf_arg_nonneg(const char *s, double *out)
{
    char *end;
    double v = strtod(s, &end);
    if (*s == 0 || *end != 0 || !(v >= 0.0) || !isfinite(v))
        return 0;
    *out = v;
    return 1;
}

const RfOpt rf_opts_png[] = {
    {"gamma", RF_ARG_GAMMA, "G", "PNG values encoded as v^(1/G) (default 2.2, the script's §1.1.2)",
     "a number in (0, 10)"},
    {"srgb", RF_ARG_SRGB, NULL, "PNG values encoded with the sRGB curve instead", NULL},
    RF_OPT_TABLE_END,
};

const RfOpt rf_opts_load[] = {
    {"nff-fov", RF_ARG_NFF_FOV, "centres|edges", "an NFF angle spans the outer pixels' centres (default) or edges",
     "centres or edges"},
    RF_OPT_TABLE_END,
};

int rf_arg_shared(int key, const char *v, RfLoadOptions *lopt, RfPngOptions *popt)
{
    switch (key) {
    case RF_ARG_SRGB:
        popt->encoding = RF_PNG_SRGB;
        return 1;
    case RF_ARG_GAMMA: {
        double g;
        if (!rf_arg_nonneg(v, &g) || !(g > 0.0 && g < 10.0))
            return -1;
        popt->encoding = RF_PNG_GAMMA;
        popt->gamma = g;
        return 1;
    }
    case RF_ARG_NFF_FOV:
        if (!lopt)
            return 0;
        if (strcmp(v, "centres") == 0 || strcmp(v, "centers") == 0)
            lopt->nff_fov = RF_FOV_PIXEL_CENTRES;
        else if (strcmp(v, "edges") == 0)
            lopt->nff_fov = RF_FOV_EDGES;
        else
            return -1;
        return 1;
    }
    return 0;
}

const RfOpt rf_opts_render[] = {
    {"width", RF_ARG_WIDTH, "W", "image width in pixels (default: the scene's)", "an integer in [1, 65536]"},
    {"height", RF_ARG_HEIGHT, "H", "image height in pixels (default: the scene's)", "an integer in [1, 65536]"},
    {"samples", RF_ARG_SAMPLES, "N", "samples per pixel (1: the pixel centre)", "an integer in [1, 1048576]"},
    {"depth", RF_ARG_DEPTH, "D", "the deepest ray tree (default: the scene's)", "an integer in [1, 1000]"},
    {"threshold", RF_ARG_THRESHOLD, "T",
     "leave out a secondary ray whose weight falls below T (default: the scene's, 0 in NFF; POV-Ray's "
     "adc_bailout is 1/255 = 0.0039215686)", "a number in [0, 1]"},
    {"threads", RF_ARG_THREADS, "N", "worker threads (default: one per processor)", "an integer in [1, 1024]"},
    {"seed", RF_ARG_SEED, "S", "seed of the random samplers (default 0)", "an integer in [0, 2147483647]"},
    {"sampler", RF_ARG_SAMPLER, "NAME", "uniform, random, stratified, sobol or adaptive (default: the scene's)",
     "uniform, random, stratified, sobol or adaptive"},
    {"adaptive-threshold", RF_ARG_ADAPTIVE_THRESHOLD, "T",
     "adaptive: split a pixel that differs from a neighbour by more (default 0.1)", "a number >= 0"},
    {"adaptive-depth", RF_ARG_ADAPTIVE_DEPTH, "D", "adaptive: how often a pixel may be split (default 2)",
     "an integer in [0, 8]"},
    {"filter", RF_ARG_FILTER, "NAME", "pixel filter: box, gaussian or mitchell (default box)",
     "box, gaussian or mitchell"},
    {"filter-radius", RF_ARG_FILTER_RADIUS, "R", "the filter's radius in pixels", "a number in (0, 16]"},
    {"aperture", RF_ARG_APERTURE, "A", "thin lens (§3.10): the lens radius (needs a focus)", "a number >= 0"},
    {"focus", RF_ARG_FOCUS, "F", "thin lens: the distance in focus", "a number > 0"},
    {"light-samples", RF_ARG_LIGHT_SAMPLES, "N", "shadow rays per area light and camera sample",
     "an integer in [1, 65536]"},
    {"kernel", RF_ARG_KERNEL, "NAME", "render kernel: auto, general or one refray info names (the same image)",
     "auto, general or a name refray info prints"},
    {"preview", RF_ARG_PREVIEW, NULL, "render a NaN, Inf or negative sample black (and count it) instead of failing",
     NULL},
    {"local", RF_ARG_LOCAL, NULL, "primary rays and local Phong only (no shadows, reflection, refraction)", NULL},
    {"two-sided", RF_ARG_TWO_SIDED, NULL, "every surface visible from both sides, as in POV-Ray and Mitsuba", NULL},
    {"shadows", RF_ARG_SHADOWS, "MODE", "opaque, or filtered by the kt of each surface crossed, as POV-Ray "
     "(default: the scene's, opaque)", "opaque or filtered"},
    RF_OPT_TABLE_END,
};

int rf_arg_render(int key, const char *v, RfRenderOptions *opt)
{
    int ok = 1;
    switch (key) {
    case RF_ARG_PREVIEW:
        opt->preview = 1;
        break;
    case RF_ARG_LOCAL:
        opt->local_only = 1;
        break;
    case RF_ARG_TWO_SIDED:
        opt->two_sided = 1;
        break;
    case RF_ARG_SHADOWS:
        ok = (opt->shadows = rf_shadow_mode_parse(v)) >= 0;
        break;
    case RF_ARG_WIDTH:
        ok = rf_arg_int(v, 1, 65536, &opt->width);
        break;
    case RF_ARG_HEIGHT:
        ok = rf_arg_int(v, 1, 65536, &opt->height);
        break;
    case RF_ARG_SAMPLES:
        ok = rf_arg_int(v, 1, 1 << 20, &opt->samples);
        break;
    case RF_ARG_DEPTH:
        ok = rf_arg_int(v, 1, 1000, &opt->max_depth);
        break;
    case RF_ARG_THRESHOLD:
        ok = rf_arg_nonneg(v, &opt->threshold) && opt->threshold <= 1.0;
        break;
    case RF_ARG_THREADS:
        ok = rf_arg_int(v, 1, 1024, &opt->threads);
        break;
    case RF_ARG_SEED: {
        int s = 0;
        ok = rf_arg_int(v, 0, 2147483647, &s);
        opt->seed = (uint64_t)s;
        break;
    }
    case RF_ARG_SAMPLER:
        if (strcmp(v, "adaptive") == 0)
            opt->adaptive = 1;
        else
            ok = (opt->sampler = rf_sampler_parse(v)) >= 0, opt->adaptive = 0;
        break;
    case RF_ARG_ADAPTIVE_THRESHOLD:
        ok = rf_arg_nonneg(v, &opt->adaptive_threshold);
        break;
    case RF_ARG_ADAPTIVE_DEPTH:
        ok = rf_arg_int(v, 0, 8, &opt->adaptive_depth);
        break;
    case RF_ARG_FILTER:
        ok = (opt->filter = rf_filter_parse(v)) >= 0;
        break;
    case RF_ARG_FILTER_RADIUS:
        ok = rf_arg_nonneg(v, &opt->filter_radius) && opt->filter_radius > 0.0 && opt->filter_radius <= 16.0;
        break;
    case RF_ARG_APERTURE:
        ok = rf_arg_nonneg(v, &opt->aperture);
        break;
    case RF_ARG_FOCUS:
        ok = rf_arg_nonneg(v, &opt->focus) && opt->focus > 0.0;
        break;
    case RF_ARG_LIGHT_SAMPLES:
        ok = rf_arg_int(v, 1, 1 << 16, &opt->light_samples);
        break;
    case RF_ARG_KERNEL:
        ok = strcmp(v, "auto") == 0 || (opt->kernel = rf_kernel_parse(v)) != 0;
        break;
    default:
        return 0;
    }
    return ok ? 1 : -1;
}

static const struct {
    RfImageFormat format;
    const char *ext;
} formats[] = {{RF_IMAGE_EXR, ".exr"}, {RF_IMAGE_PNG, ".png"}, {RF_IMAGE_SVG, ".svg"}};

static int format_of(const char *path)
{
    size_t n = strlen(path);
    for (size_t i = 0; i < sizeof formats / sizeof formats[0]; i++)
        if (n > 4 && strcasecmp(path + n - 4, formats[i].ext) == 0)
            return formats[i].format;
    return 0;
}

int rf_arg_image_format(const char *prog, const char *option, const char *path, unsigned allowed)
{
    int f = format_of(path);
    if (f && (allowed & (unsigned)f))
        return f;
    fprintf(stderr, "%s: %s %s: the name must end in", prog, option, path);
    int count = 0, total = 0;
    for (size_t i = 0; i < sizeof formats / sizeof formats[0]; i++)
        total += (allowed & formats[i].format) != 0;
    for (size_t i = 0; i < sizeof formats / sizeof formats[0]; i++)
        if (allowed & formats[i].format)
            fprintf(stderr, "%s%s", count++ == 0 ? " " : count == total ? " or " : ", ", formats[i].ext);
    fprintf(stderr, " (the format follows it)\n");
    return 0;
}

RfStatus rf_arg_write_image(const char *path, const RfImage *img, const RfImageAttr *attrs, int nattrs,
                            RfExrOptions eopt, RfPngOptions popt, char *err, size_t errsz)
{
    if (format_of(path) == RF_IMAGE_PNG)
        return rf_png_write(path, img, popt, err, errsz);
    return rf_exr_write_opts(path, img, attrs, nattrs, eopt, err, errsz);
}

void rf_arg_report(const char *prog, const char *err)
{
    /* a position: the first "name:LINE:COL: " before any blank */
    const char *c = err + strcspn(err, ": ");
    int positioned = 0;
    if (*c == ':') {
        size_t line = strspn(c + 1, "0123456789"), col = line ? strspn(c + 2 + line, "0123456789") : 0;
        positioned = line && c[1 + line] == ':' && col && c[2 + line + col] == ':';
    }
    if (positioned)
        fprintf(stderr, "%s\n", err);
    else
        fprintf(stderr, "%s: %s\n", prog, err);
}

int rf_arg_outputs_check(const char *prog, const char *const *outs, int n_out, const char *const *ins, int n_in)
{
    char err[1024];
    RfStatus st = rf_outputs_check(outs, n_out, ins, n_in, err, sizeof err);
    if (st == RF_OK)
        return 0;
    fprintf(stderr, "%s: %s\n", prog, err);
    return st == RF_ERR_DOMAIN ? RF_EXIT_USAGE : RF_EXIT_FILE;
}
