/* refray's test runner: each test file defines test functions and a table of them; main.c
 * lists the tables. A test fails when any check in it fails; the run ends with the line
 * "N passed, N failed" (tests, not checks). */
#ifndef RF_TEST_H
#define RF_TEST_H

#include <glob.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

typedef struct {
    const char *name;
    void (*fn)(void);
} RfTest;

/* Set by the checks; read by the runner. */
extern int rf_test_failed_checks;
extern long rf_test_checks;

void rf_test_fail(const char *file, int line, const char *fmt, ...);
/* |a - b| <= rel * max(|a|, |b|) + abs_tol */
int rf_test_near(double a, double b, double rel, double abs_tol);
/* Environment helpers: the built binary and the test data folder. */
const char *rf_test_bin(void);
const char *rf_test_data(const char *name); /* static buffer: tests/data/<name> */
/* Runs every case of tests/data/<file> (JSON lines of independently computed formula cases,
 * see tests/formula_cases.c) through the registry; numbers must agree to
 * rel * max(|a|,|b|) + abs_tol (a case may override both). Returns the number of cases. */
int rf_test_formula_cases(const char *file, double rel, double abs_tol);
/* Runs a shell command, captures stdout (static buffer) and the exit code. */
const char *rf_test_run(const char *cmd, int *exit_code);
/* 1 when program is on the PATH (tests that need an optional tool skip without it). */
int rf_test_have(const char *program);
/* The absolute path of one of the built binaries ("refray-raster"), the one beside rf_test_bin();
 * 0 when rf_test_bin() does not resolve. */
int rf_test_tool(const char *name, char *out, size_t size);
/* The value of all.NAME in `refray diff --kv` output, NAN when absent. */
double rf_test_diff_kv(const char *out, const char *name);
/* Every shipped scene into g (globfree it): the .rf files of scenes/, its .obj files when
 * with_obj, and the NFF files of scenes/spd/ (.nff, .nff.gz). */
void rf_test_shipped_scenes(glob_t *g, int with_obj);

#define RF_CHECK(cond)                                                                       \
    do {                                                                                     \
        rf_test_checks++;                                                                    \
        if (!(cond))                                                                         \
            rf_test_fail(__FILE__, __LINE__, "check failed: %s", #cond);                    \
    } while (0)

#define RF_CHECK_NEAR(a, b, rel, abs_tol)                                                    \
    do {                                                                                     \
        double rf_a_ = (a), rf_b_ = (b);                                                     \
        rf_test_checks++;                                                                    \
        if (!rf_test_near(rf_a_, rf_b_, (rel), (abs_tol)))                                   \
            rf_test_fail(__FILE__, __LINE__, "%s = %.17g, expected %s = %.17g (rel %g, abs %g)", \
                         #a, rf_a_, #b, rf_b_, (double)(rel), (double)(abs_tol));            \
    } while (0)

#define RF_CHECK_EQ_INT(a, b)                                                                \
    do {                                                                                     \
        long rf_a_ = (long)(a), rf_b_ = (long)(b);                                           \
        rf_test_checks++;                                                                    \
        if (rf_a_ != rf_b_)                                                                  \
            rf_test_fail(__FILE__, __LINE__, "%s = %ld, expected %ld", #a, rf_a_, rf_b_);    \
    } while (0)

#define RF_CHECK_STR(a, b)                                                                   \
    do {                                                                                     \
        const char *rf_sa_ = (a), *rf_sb_ = (b);                                             \
        rf_test_checks++;                                                                    \
        if (strcmp(rf_sa_, rf_sb_) != 0)                                                     \
            rf_test_fail(__FILE__, __LINE__, "%s = \"%s\", expected \"%s\"", #a, rf_sa_,     \
                         rf_sb_);                                                            \
    } while (0)

#define RF_TEST_END {NULL, NULL}

/* A reproducible random stream for property tests (splitmix64), uniform in [lo, hi). */
typedef struct { unsigned long long state; } RfTestRng;
static inline double rf_test_uniform(RfTestRng *r, double lo, double hi)
{
    unsigned long long z = (r->state += 0x9E3779B97F4A7C15ULL);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
    z ^= z >> 31;
    return lo + (hi - lo) * (double)(z >> 11) * (1.0 / 9007199254740992.0);
}

#endif
