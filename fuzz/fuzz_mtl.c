/* libFuzzer target "mtl": the MTL reader (rf_scene_read_mtl); its materials are rendered on a sphere and
 * a triangle each. (fuzz_common.h) */
#define RF_FUZZ_TARGET "mtl"
#include "fuzz_main.h"
