/* The test runner: runs every test of every table (or those whose name contains argv[1]). */
#define _XOPEN_SOURCE 700
#include <limits.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

#include "rf_test.h"

extern const RfTest rf_tests_vecmat[];
extern const RfTest rf_tests_geometry[];
extern const RfTest rf_tests_transform[];
extern const RfTest rf_tests_formula[];
extern const RfTest rf_tests_cli[];
extern const RfTest rf_tests_color[];
extern const RfTest rf_tests_raytrace[];
extern const RfTest rf_tests_io[];
extern const RfTest rf_tests_bvh[];
extern const RfTest rf_tests_accel[];
extern const RfTest rf_tests_kernels[];
extern const RfTest rf_tests_parallel[];
extern const RfTest rf_tests_scene[];
extern const RfTest rf_tests_render[];
extern const RfTest rf_tests_stress[];
extern const RfTest rf_tests_compare[];
extern const RfTest rf_tests_mesh[];
extern const RfTest rf_tests_docs[];
extern const RfTest rf_tests_distributed[];
extern const RfTest rf_tests_robust[];
extern const RfTest rf_tests_sampling[];
extern const RfTest rf_tests_bench[];
extern const RfTest rf_tests_fuzz_regress[];
extern const RfTest rf_tests_povray[];
extern const RfTest rf_tests_export[];
extern const RfTest rf_tests_farm[];
extern const RfTest rf_tests_view[];
extern const RfTest rf_tests_trace[];
extern const RfTest rf_tests_stat[];
extern const RfTest rf_tests_grade[];
extern const RfTest rf_tests_cmdline[];
extern const RfTest rf_tests_install[];
extern const RfTest rf_tests_sides[];

static const RfTest *const suites[] = {
    rf_tests_vecmat, rf_tests_geometry, rf_tests_transform, rf_tests_formula, rf_tests_cli,
    rf_tests_color, rf_tests_raytrace, rf_tests_io, rf_tests_bvh, rf_tests_accel, rf_tests_kernels, rf_tests_parallel,
    rf_tests_scene, rf_tests_render,
    rf_tests_stress,
    rf_tests_compare,
    rf_tests_mesh,
    rf_tests_docs,
    rf_tests_sampling,
    rf_tests_bench,
    rf_tests_distributed,
    rf_tests_robust,
    rf_tests_fuzz_regress,
    rf_tests_povray,
    rf_tests_export,
    rf_tests_farm,
    rf_tests_view,
    rf_tests_trace,
    rf_tests_stat,
    rf_tests_grade,
    rf_tests_install,
    rf_tests_sides,
    rf_tests_cmdline,
};

int rf_test_failed_checks;
long rf_test_checks;
static const char *current_test;

void rf_test_fail(const char *file, int line, const char *fmt, ...)
{
    va_list ap;
    rf_test_failed_checks++;
    fprintf(stderr, "FAIL %s (%s:%d): ", current_test, file, line);
    va_start(ap, fmt);
    vfprintf(stderr, fmt, ap);
    va_end(ap);
    fputc('\n', stderr);
}

int rf_test_near(double a, double b, double rel, double abs_tol)
{
    if (isnan(a) || isnan(b))
        return 0;
    if (a == b)
        return 1;
    return fabs(a - b) <= rel * fmax(fabs(a), fabs(b)) + abs_tol;
}

const char *rf_test_bin(void)
{
    const char *b = getenv("RF_BIN");
    return b ? b : "build/refray";
}

const char *rf_test_data(const char *name)
{
    static char path[1024];
    const char *d = getenv("RF_TEST_DATA");
    snprintf(path, sizeof path, "%s/%s", d ? d : "tests/data", name);
    return path;
}

const char *rf_test_run(const char *cmd, int *exit_code)
{
    static char out[1 << 16];
    size_t n = 0;
    FILE *p = popen(cmd, "r");
    out[0] = 0;
    if (!p) {
        *exit_code = -1;
        return out;
    }
    while (n + 1 < sizeof out) {
        size_t k = fread(out + n, 1, sizeof out - 1 - n, p);
        if (k == 0)
            break;
        n += k;
    }
    out[n] = 0;
    int st = pclose(p);
    *exit_code = st >= 0 && (st & 0x7f) == 0 ? (st >> 8) & 0xff : -1;
    return out;
}

int rf_test_have(const char *program)
{
    char cmd[512];
    int code;
    snprintf(cmd, sizeof cmd, "command -v '%s' >/dev/null 2>&1", program);
    rf_test_run(cmd, &code);
    return code == 0;
}

int rf_test_tool(const char *name, char *out, size_t size)
{
    char bin[PATH_MAX];
    if (!realpath(rf_test_bin(), bin))
        return 0;
    snprintf(out, size, "%.*s/%s", (int)(strrchr(bin, '/') - bin), bin, name);
    return 1;
}

double rf_test_diff_kv(const char *out, const char *name)
{
    char key[64];
    snprintf(key, sizeof key, "all.%s=", name);
    const char *p = strstr(out, key);
    return p ? strtod(p + strlen(key), NULL) : NAN;
}

int main(int argc, char **argv)
{
    const char *filter = argc > 1 ? argv[1] : NULL;
    int passed = 0, failed = 0;
    for (size_t s = 0; s < sizeof suites / sizeof suites[0]; s++)
        for (const RfTest *t = suites[s]; t->name; t++) {
            if (filter && !strstr(t->name, filter))
                continue;
            current_test = t->name;
            int before = rf_test_failed_checks;
            t->fn();
            if (rf_test_failed_checks == before)
                passed++;
            else
                failed++;
        }
    fprintf(stderr, "(%ld checks)\n", rf_test_checks);
    printf("%d passed, %d failed\n", passed, failed);
    return failed ? 1 : 0;
}
