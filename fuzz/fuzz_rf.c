/* libFuzzer target "rf": refray's scene format (rf_scene_read_rf; `mesh` reads the sandbox's OBJ and
 * MTL files); a scene that parses goes on through validation, the tracer and a tiny render. (fuzz_common.h) */
#define RF_FUZZ_TARGET "rf"
#include "fuzz_main.h"
