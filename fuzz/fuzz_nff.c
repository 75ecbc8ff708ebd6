/* libFuzzer target "nff": the NFF reader (rf_scene_read_nff, with both readings of the field of view);
 * a scene that parses goes on through validation, the tracer and a tiny render. (fuzz_common.h) */
#define RF_FUZZ_TARGET "nff"
#include "fuzz_main.h"
