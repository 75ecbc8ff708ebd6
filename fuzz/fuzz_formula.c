/* libFuzzer target "formula": the formula front ends: rf_formula_batch on the bytes as JSON lines, and
 * rf_formula_args_to_json + rf_formula_run_json on them as a command line. (fuzz_common.h) */
#define RF_FUZZ_TARGET "formula"
#include "fuzz_main.h"
