/* refray fuzzing: the libFuzzer entry point, included by each target fuzz_<target>.c after
 * #define RF_FUZZ_TARGET "nff" (or rf, obj, mtl, exr, png, formula); the work is rf_fuzz_run of
 * fuzz_common.h, the same function tests/test_fuzz_regress.c runs on the kept reproducers.
 *
 * The sandbox: a folder under /tmp made at start-up (removed at exit) holds the files that
 * scenes may name; while an input runs, the readers may open only files inside it (fopen and
 * gzopen are wrapped at link time, -Wl,--wrap=fopen,--wrap=gzopen): an input naming
 * /dev/zero, /dev/stdin or any other file of the machine gets "cannot open" instead. */
#include <errno.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <zlib.h>

#include "fuzz_common.h"

#ifndef RF_FUZZ_TARGET
#error "define RF_FUZZ_TARGET (\"nff\", \"rf\", ...) before including fuzz_main.h"
#endif

static char sandbox[4096];
static int sandbox_active;

/* The real functions (the linker's --wrap names). */
FILE *__real_fopen(const char *path, const char *mode);
gzFile __real_gzopen(const char *path, const char *mode);

/* While an input runs: only paths inside the sandbox, without "..", and /dev/null (the batch's
 * output). Outside an input (libFuzzer reading its corpus): everything. */
static int allowed(const char *path)
{
    size_t n = strlen(sandbox);
    if (!sandbox_active || strcmp(path, "/dev/null") == 0)
        return 1;
    return strncmp(path, sandbox, n) == 0 && path[n] == '/' && !strstr(path, "..");
}

FILE *__wrap_fopen(const char *path, const char *mode);
FILE *__wrap_fopen(const char *path, const char *mode)
{
    if (!allowed(path)) {
        errno = ENOENT;
        return NULL;
    }
    return __real_fopen(path, mode);
}

gzFile __wrap_gzopen(const char *path, const char *mode);
gzFile __wrap_gzopen(const char *path, const char *mode)
{
    if (!allowed(path)) {
        errno = ENOENT;
        return NULL;
    }
    return __real_gzopen(path, mode);
}

static void cleanup(void)
{
    if (sandbox[0])
        rf_fuzz_sandbox_remove(sandbox);
}

int LLVMFuzzerInitialize(int *argc, char ***argv);
int LLVMFuzzerInitialize(int *argc, char ***argv)
{
    (void)argc;
    (void)argv;
    const char *scenes = getenv("RF_FUZZ_SCENES");
    if (rf_fuzz_sandbox(sandbox, sizeof sandbox, scenes && *scenes ? scenes : "scenes")) {
        fprintf(stderr, "refray fuzz: cannot make a folder under /tmp\n");
        exit(1);
    }
    atexit(cleanup);
    return 0;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    sandbox_active = 1;
    (void)rf_fuzz_run(RF_FUZZ_TARGET, data, size, sandbox);
    sandbox_active = 0;
    return 0;
}
