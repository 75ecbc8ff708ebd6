/* libFuzzer target "exr": the OpenEXR readers (rf_image_read as `refray diff` calls it, rf_exr_read,
 * rf_exr_read_attr); an image that reads is diffed, heat-mapped and written back. (fuzz_common.h) */
#define RF_FUZZ_TARGET "exr"
#include "fuzz_main.h"
