/* libFuzzer target "obj": the Wavefront OBJ reader (rf_scene_read_obj; `mtllib gem.mtl` reads the sandbox
 * copy); a scene that parses goes on through validation, the tracer and a tiny render. (fuzz_common.h) */
#define RF_FUZZ_TARGET "obj"
#include "fuzz_main.h"
