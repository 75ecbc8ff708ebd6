/* The comparison thresholds shared by `refray diff` and `refray grade` (diff_args.h). */
#include "diff_args.h"
#include "args.h"

const RfOpt rf_opts_diff[] = {
    {"warn", RF_ARG_WARN, "X", "a pixel differing by more than X counts for WARN (default 1e-4)", "a number >= 0"},
    {"warnpercent", RF_ARG_WARNPERCENT, "P", "WARN when more than P % of the pixels do (default 0.1)",
     "a number >= 0"},
    {"fail", RF_ARG_FAIL, "Y", "a pixel differing by more than Y counts for FAIL (default 1/255)", "a number >= 0"},
    {"failpercent", RF_ARG_FAILPERCENT, "P", "FAIL when more than P % of the pixels do (default 0.1)",
     "a number >= 0"},
    {"fail-mean", RF_ARG_FAIL_MEAN, "M", "FAIL when the mean difference exceeds M (default 1e-4)", "a number >= 0"},
    {"hardfail", RF_ARG_HARDFAIL, "H", "FAIL when any pixel differs by more than H (default off)", "a number >= 0"},
    {"edge-tolerant", RF_ARG_EDGE_TOLERANT, NULL,
     "a pixel's error is the smallest over the reference's 3x3 neighbourhood (aliasing, half-pixel offsets)", NULL},
    RF_OPT_TABLE_END,
};

int rf_arg_diff(int key, const char *v, RfDiffOptions *o, unsigned *set)
{
    double *target;
    switch (key) {
    case RF_ARG_WARN: target = &o->warn, *set |= RF_SET_WARN; break;
    case RF_ARG_WARNPERCENT: target = &o->warn_percent; break;
    case RF_ARG_FAIL: target = &o->fail; break;
    case RF_ARG_FAILPERCENT: target = &o->fail_percent; break;
    case RF_ARG_FAIL_MEAN: target = &o->fail_mean, *set |= RF_SET_FAIL_MEAN; break;
    case RF_ARG_HARDFAIL: target = &o->hardfail; break;
    case RF_ARG_EDGE_TOLERANT: o->edge_tolerant = 1; return 1;
    default: return 0;
    }
    return rf_arg_nonneg(v, target) ? 1 : -1;
}

void rf_arg_diff_display(RfDiffOptions *o, unsigned set)
{
    if (!(set & RF_SET_FAIL_MEAN))
        o->fail_mean = 1.0 / 255.0;
    if (!(set & RF_SET_WARN))
        o->warn = 0.5 / 255.0 + 1e-6;
}
