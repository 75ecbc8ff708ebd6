/* refray fuzzing: the file sandbox. In the fuzz build the library's calls of fopen and gzopen are
 * renamed to rf_fuzz_fopen and rf_fuzz_gzopen (objcopy --redefine-sym on its archive, fuzz.mk),
 * so that only the library's opens come here, never libFuzzer's own (its corpus, its crash
 * files). While an input runs (rf_fuzz_sandbox_active), a path is opened only when it lies inside
 * the sandbox folder and has no "..": an input naming /dev/zero, /etc/passwd or a file of the
 * machine gets "cannot open" instead, and a reproducer never depends on the machine's files. */
#include <errno.h>
#include <stdio.h>
#include <string.h>
#include <zlib.h>

char rf_fuzz_sandbox_dir[1024];
int rf_fuzz_sandbox_active;

FILE *rf_fuzz_fopen(const char *path, const char *mode);
gzFile rf_fuzz_gzopen(const char *path, const char *mode);

static int allowed(const char *path)
{
    size_t n = strlen(rf_fuzz_sandbox_dir);
    if (!rf_fuzz_sandbox_active)
        return 1;
    return n > 0 && strncmp(path, rf_fuzz_sandbox_dir, n) == 0 && path[n] == '/' && !strstr(path, "..");
}

FILE *rf_fuzz_fopen(const char *path, const char *mode)
{
    if (!allowed(path)) {
        errno = ENOENT;
        return NULL;
    }
    return fopen(path, mode);
}

gzFile rf_fuzz_gzopen(const char *path, const char *mode)
{
    if (!allowed(path)) {
        errno = ENOENT;
        return NULL;
    }
    return gzopen(path, mode);
}
