/* refray fuzzing: the libFuzzer entry point, included by each target fuzz_<target>.c after
 * #define RF_FUZZ_TARGET "nff" (or rf, obj, mtl, exr, png, formula); the work is rf_fuzz_run of
 * fuzz_common.h, the same function tests/test_fuzz_regress.c runs on the kept reproducers.
 *
 * At start-up the harness makes its sandbox, a folder under /tmp holding the files that scenes
 * may name (removed at exit); while an input runs, the library may open only files inside it
 * (sandbox.c). */
#include <stdint.h>
#include <stdlib.h>

#include "fuzz_common.h"

#ifndef RF_FUZZ_TARGET
#error "define RF_FUZZ_TARGET (\"nff\", \"rf\", ...) before including fuzz_main.h"
#endif

extern char rf_fuzz_sandbox_dir[1024]; /* sandbox.c */
extern int rf_fuzz_sandbox_active;

static void cleanup(void)
{
    if (rf_fuzz_sandbox_dir[0])
        rf_fuzz_sandbox_remove(rf_fuzz_sandbox_dir);
}

int LLVMFuzzerInitialize(int *argc, char ***argv);
int LLVMFuzzerInitialize(int *argc, char ***argv)
{
    (void)argc;
    (void)argv;
    const char *scenes = getenv("RF_FUZZ_SCENES");
    if (rf_fuzz_sandbox(rf_fuzz_sandbox_dir, sizeof rf_fuzz_sandbox_dir, scenes && *scenes ? scenes : "scenes")) {
        fprintf(stderr, "refray fuzz: cannot make a folder under /tmp\n");
        exit(1);
    }
    atexit(cleanup);
    return 0;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    rf_fuzz_sandbox_active = 1;
    (void)rf_fuzz_run(RF_FUZZ_TARGET, data, size, rf_fuzz_sandbox_dir);
    rf_fuzz_sandbox_active = 0;
    return 0;
}
