/* Shared command-line values (args.h). */
#include "args.h"

#include <math.h>
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
