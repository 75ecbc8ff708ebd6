/* The comparison thresholds that `refray diff` and `refray grade` both take, one option table
 * fragment (opt.h) and one handler, so that the two commands cannot drift apart. */
#ifndef REFRAY_CLI_DIFF_ARGS_H
#define REFRAY_CLI_DIFF_ARGS_H

#include "opt.h"
#include "refray/diff.h"

enum {
    RF_ARG_WARN = 0x1200, RF_ARG_WARNPERCENT, RF_ARG_FAIL, RF_ARG_FAILPERCENT, RF_ARG_FAIL_MEAN, RF_ARG_HARDFAIL,
    RF_ARG_EDGE_TOLERANT
};

/* --warn, --warnpercent, --fail, --failpercent, --fail-mean, --hardfail, --edge-tolerant */
extern const RfOpt rf_opts_diff[];

/* Which of them were given (bits), for the defaults that depend on the space compared in. */
enum { RF_SET_WARN = 1, RF_SET_FAIL_MEAN = 2 };

/* Handles the keys of rf_opts_diff into o (set: the RF_SET_ bits of those given). 0 when key is
 * none of them, 1 when handled, -1 for a bad value. */
int rf_arg_diff(int key, const char *v, RfDiffOptions *o, unsigned *set);

/* The defaults for display values (8-bit codes): a correctly rounded PNG has errors up to half a
 * code, so the mean may reach one code (--fail-mean 1/255) and anything beyond rounding warns
 * (--warn 0.5/255); thresholds given on the command line stay. */
void rf_arg_diff_display(RfDiffOptions *o, unsigned set);

#endif
