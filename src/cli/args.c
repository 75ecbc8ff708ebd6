/* Shared command-line values (args.h). */
#include "args.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

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

int rf_arg_shared(const char *a, const char *v, RfLoadOptions *lopt, RfPngOptions *popt, int *used)
{
    *used = 1;
    if (strcmp(a, "--srgb") == 0) {
        popt->encoding = RF_PNG_SRGB;
        return 1;
    }
    if (strcmp(a, "--gamma") == 0) {
        double g;
        if (!v || !rf_arg_nonneg(v, &g) || !(g > 0.0 && g < 10.0))
            return -1;
        popt->encoding = RF_PNG_GAMMA;
        popt->gamma = g;
        *used = 2;
        return 1;
    }
    if (lopt && strcmp(a, "--nff-fov") == 0) {
        if (!v)
            return -1;
        if (strcmp(v, "centres") == 0 || strcmp(v, "centers") == 0)
            lopt->nff_fov = RF_FOV_PIXEL_CENTRES;
        else if (strcmp(v, "edges") == 0)
            lopt->nff_fov = RF_FOV_EDGES;
        else
            return -1;
        *used = 2;
        return 1;
    }
    return 0;
}

int rf_arg_render(const char *a, const char *v, RfRenderOptions *opt, int *used)
{
    int ok = 1;
    *used = 2;
    if (strcmp(a, "--preview") == 0 || strcmp(a, "--local") == 0) {
        *used = 1;
        if (a[2] == 'p')
            opt->preview = 1;
        else
            opt->local_only = 1;
        return 1;
    }
    if (!v)
        return strcmp(a, "--width") == 0 || strcmp(a, "--height") == 0 || strcmp(a, "--samples") == 0 ||
                       strcmp(a, "--depth") == 0 || strcmp(a, "--threads") == 0 || strcmp(a, "--seed") == 0 ||
                       strcmp(a, "--sampler") == 0 || strcmp(a, "--adaptive-threshold") == 0 ||
                       strcmp(a, "--adaptive-depth") == 0 || strcmp(a, "--filter") == 0 ||
                       strcmp(a, "--filter-radius") == 0 || strcmp(a, "--aperture") == 0 ||
                       strcmp(a, "--focus") == 0 || strcmp(a, "--light-samples") == 0 || strcmp(a, "--kernel") == 0
                   ? -1
                   : 0;
    if (strcmp(a, "--width") == 0)
        ok = rf_arg_int(v, 1, 65536, &opt->width);
    else if (strcmp(a, "--height") == 0)
        ok = rf_arg_int(v, 1, 65536, &opt->height);
    else if (strcmp(a, "--samples") == 0)
        ok = rf_arg_int(v, 1, 1 << 20, &opt->samples);
    else if (strcmp(a, "--depth") == 0)
        ok = rf_arg_int(v, 1, 1000, &opt->max_depth);
    else if (strcmp(a, "--threads") == 0)
        ok = rf_arg_int(v, 1, 1024, &opt->threads);
    else if (strcmp(a, "--seed") == 0) {
        int s = 0;
        ok = rf_arg_int(v, 0, 2147483647, &s);
        opt->seed = (uint64_t)s;
    } else if (strcmp(a, "--sampler") == 0) {
        if (strcmp(v, "adaptive") == 0)
            opt->adaptive = 1;
        else
            ok = (opt->sampler = rf_sampler_parse(v)) >= 0, opt->adaptive = 0;
    } else if (strcmp(a, "--adaptive-threshold") == 0)
        ok = rf_arg_nonneg(v, &opt->adaptive_threshold);
    else if (strcmp(a, "--adaptive-depth") == 0)
        ok = rf_arg_int(v, 0, 8, &opt->adaptive_depth);
    else if (strcmp(a, "--filter") == 0)
        ok = (opt->filter = rf_filter_parse(v)) >= 0;
    else if (strcmp(a, "--filter-radius") == 0)
        ok = rf_arg_nonneg(v, &opt->filter_radius) && opt->filter_radius > 0.0 && opt->filter_radius <= 16.0;
    else if (strcmp(a, "--aperture") == 0)
        ok = rf_arg_nonneg(v, &opt->aperture);
    else if (strcmp(a, "--focus") == 0)
        ok = rf_arg_nonneg(v, &opt->focus) && opt->focus > 0.0;
    else if (strcmp(a, "--light-samples") == 0)
        ok = rf_arg_int(v, 1, 1 << 16, &opt->light_samples);
    else if (strcmp(a, "--kernel") == 0)
        ok = strcmp(v, "auto") == 0 || (opt->kernel = rf_kernel_parse(v)) != 0;
    else
        return 0;
    return ok ? 1 : -1;
}
