/* Fuzzing regressions (fuzz/README.md): every file under tests/data/fuzz/<target>/ goes through
 * the same code the fuzz target ran on it (rf_fuzz_run of fuzz/fuzz_common.h: the reader, then
 * validation, the tracer and a tiny render, or the image diff, or the formula front ends). The
 * reader must return a status (an error or RF_OK) and nothing may crash, hang or (under
 * AddressSanitizer, as in CI) touch memory it does not own. Leaks are the fuzz targets' to find
 * (libFuzzer checks every input): the child ends with _exit, without LeakSanitizer's check.
 *
 * Each file runs in a child process, so that a crash fails this test with the file's name and
 * the signal instead of ending the whole test run. The fuzz targets aim at 0.1 s an input: a file
 * that takes more than 5 s or grows its process by more than 1 GiB fails too (a header that claims
 * a huge image must not be believed before the data is there), and one still running after
 * 30 s is killed as a hang. */
#include <dirent.h>
#include <signal.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/types.h>
#include <time.h>
#include <sys/wait.h>
#include <unistd.h>

#include "../fuzz/fuzz_common.h"
#include "rf_test.h"

#define RF_REGRESS_MAX_SECONDS 5
#define RF_REGRESS_MAX_RSS_KB (1024 * 1024)

static const char *const fuzz_targets[] = {"nff", "rf", "obj", "mtl", "exr", "png", "formula"};

static int cmp_names(const void *a, const void *b)
{
    return strcmp(*(char *const *)a, *(char *const *)b);
}

/* The regular files of a folder, sorted; *n gets the count (0 for a missing folder). */
static char **list_files(const char *dir, size_t *n)
{
    DIR *d = opendir(dir);
    char **names = NULL;
    size_t cap = 0;
    struct dirent *e;
    *n = 0;
    if (!d)
        return NULL;
    while ((e = readdir(d)) != NULL) {
        if (e->d_name[0] == '.')
            continue;
        if (*n == cap) {
            char **nn = realloc(names, (cap = cap ? 2 * cap : 16) * sizeof *names);
            if (!nn)
                break;
            names = nn;
        }
        size_t len = strlen(e->d_name);
        if (!(names[*n] = malloc(len + 1)))
            break;
        memcpy(names[*n], e->d_name, len + 1);
        (*n)++;
    }
    closedir(d);
    if (*n)
        qsort(names, *n, sizeof *names, cmp_names);
    return names;
}

static unsigned char *read_all(const char *path, size_t *len)
{
    FILE *f = fopen(path, "rb");
    unsigned char *buf = NULL;
    size_t cap = 0, k;
    *len = 0;
    if (!f)
        return NULL;
    do {
        if (*len == cap) {
            unsigned char *nb = realloc(buf, cap = cap ? 2 * cap : 4096);
            if (!nb) {
                free(buf);
                fclose(f);
                return NULL;
            }
            buf = nb;
        }
        k = fread(buf + *len, 1, cap - *len, f);
        *len += k;
    } while (k > 0);
    fclose(f);
    return buf ? buf : malloc(1);
}

/* Runs one input in a child; 0 when the child returned a valid status and exited normally,
 * else describes what happened in why. */
static int run_isolated(const char *target, const unsigned char *data, size_t len, const char *sandbox,
                        char *why, size_t whysz)
{
    fflush(stdout);
    fflush(stderr);
    pid_t pid = fork();
    if (pid < 0) {
        snprintf(why, whysz, "fork failed");
        return -1;
    }
    if (pid == 0) {
        struct timespec t0, t1;
        struct rusage ru0, ru;
        alarm(30);
        /* the child starts with the parent's resident pages: count its growth */
        if (getrusage(RUSAGE_SELF, &ru0) != 0)
            ru0.ru_maxrss = 0;
        clock_gettime(CLOCK_MONOTONIC, &t0);
        RfStatus st = rf_fuzz_run(target, data, len, sandbox);
        clock_gettime(CLOCK_MONOTONIC, &t1);
        /* _exit: the parent's atexit handlers and library destructors (OSMesa's, after the
         * comparator tests) are not the child's to run */
        if (strcmp(rf_status_str(st), "unknown status") == 0)
            _exit(3);
        if ((double)(t1.tv_sec - t0.tv_sec) + 1e-9 * (double)(t1.tv_nsec - t0.tv_nsec) > RF_REGRESS_MAX_SECONDS)
            _exit(4);
        if (getrusage(RUSAGE_SELF, &ru) == 0 && ru.ru_maxrss - ru0.ru_maxrss > RF_REGRESS_MAX_RSS_KB)
            _exit(5);
        _exit(0);
    }
    int status = 0;
    if (waitpid(pid, &status, 0) != pid) {
        snprintf(why, whysz, "waitpid failed");
        return -1;
    }
    if (WIFEXITED(status) && WEXITSTATUS(status) == 0)
        return 0;
    if (WIFEXITED(status) && WEXITSTATUS(status) == 3)
        snprintf(why, whysz, "the reader returned an unknown status");
    else if (WIFEXITED(status) && WEXITSTATUS(status) == 4)
        snprintf(why, whysz, "too slow: more than %d s", RF_REGRESS_MAX_SECONDS);
    else if (WIFEXITED(status) && WEXITSTATUS(status) == 5)
        snprintf(why, whysz, "too much memory: the process grew by more than %d MiB", RF_REGRESS_MAX_RSS_KB / 1024);
    else if (WIFEXITED(status))
        snprintf(why, whysz, "exit code %d (a sanitizer report above?)", WEXITSTATUS(status));
    else if (WIFSIGNALED(status))
        snprintf(why, whysz, "%s (signal %d)", WTERMSIG(status) == SIGALRM ? "hang: still running after 30 s"
                                                                         : "crashed",
                 WTERMSIG(status));
    else
        snprintf(why, whysz, "stopped (status 0x%x)", (unsigned)status);
    return -1;
}

static void test_fuzz_regressions(void)
{
    char sandbox[4096], dir[4096], path[8192], why[256];
    size_t total = 0;
    RF_CHECK(rf_fuzz_sandbox(sandbox, sizeof sandbox, "scenes") == 0);
    for (size_t t = 0; t < sizeof fuzz_targets / sizeof fuzz_targets[0]; t++) {
        size_t n = 0;
        snprintf(dir, sizeof dir, "%s", rf_test_data("fuzz"));
        snprintf(dir + strlen(dir), sizeof dir - strlen(dir), "/%s", fuzz_targets[t]);
        char **names = list_files(dir, &n);
        for (size_t i = 0; i < n; i++) {
            size_t len = 0;
            snprintf(path, sizeof path, "%s/%s", dir, names[i]);
            unsigned char *data = read_all(path, &len);
            rf_test_checks++;
            if (!data)
                rf_test_fail(__FILE__, __LINE__, "%s: cannot read", path);
            else if (run_isolated(fuzz_targets[t], data, len, sandbox, why, sizeof why) != 0)
                rf_test_fail(__FILE__, __LINE__, "%s (fuzz target %s): %s", path, fuzz_targets[t], why);
            free(data);
            free(names[i]);
            total++;
        }
        free(names);
    }
    rf_fuzz_sandbox_remove(sandbox);
    (void)total;
}

/* The harness itself on inputs that every reader must refuse or accept quietly: nothing, a
 * NUL byte, an unterminated line, a lone keyword, a binary header cut short. */
static void test_fuzz_harness_smoke(void)
{
    static const char *const inputs[] = {"", "\0", "v", "sphere", "camera", "f 1 2 3", "newmtl",
                                         "\x89PNG\r\n\x1a\n", "v/1\x01\x00\x00", "{\"id\":\"length\"}\n"};
    static const size_t lens[] = {0, 1, 1, 6, 6, 7, 6, 8, 7, 16};
    char sandbox[4096], why[256];
    RF_CHECK(rf_fuzz_sandbox(sandbox, sizeof sandbox, "scenes") == 0);
    for (size_t t = 0; t < sizeof fuzz_targets / sizeof fuzz_targets[0]; t++)
        for (size_t i = 0; i < sizeof inputs / sizeof inputs[0]; i++) {
            rf_test_checks++;
            if (run_isolated(fuzz_targets[t], (const unsigned char *)inputs[i], lens[i], sandbox, why,
                             sizeof why) != 0)
                rf_test_fail(__FILE__, __LINE__, "smoke input %zu (fuzz target %s): %s", i, fuzz_targets[t], why);
        }
    rf_fuzz_sandbox_remove(sandbox);
}

const RfTest rf_tests_fuzz_regress[] = {
    {"fuzz_regressions", test_fuzz_regressions},
    {"fuzz_harness_smoke", test_fuzz_harness_smoke},
    RF_TEST_END,
};
