/* libFuzzer target "png": the PNG readers (rf_image_read as `refray diff` calls it, rf_png_read); an image
 * that reads is diffed, heat-mapped and written back. (fuzz_common.h) */
#define RF_FUZZ_TARGET "png"
#include "fuzz_main.h"
