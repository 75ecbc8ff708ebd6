/* The `refray` command as a user runs it: output, exit codes, messages. */
#include <stdio.h>
#include <string.h>

#include "refray/formula.h"
#include "rf_test.h"

static const char *run(const char *args, int *rc)
{
    char cmd[2048];
    snprintf(cmd, sizeof cmd, "%s %s", rf_test_bin(), args);
    return rf_test_run(cmd, rc);
}

static void t_list(void)
{
    int rc;
    const char *out = run("formula list", &rc);
    RF_CHECK_EQ_INT(rc, 0);
    /* one line per registered id, each starting with the id */
    int lines = 0;
    for (const char *p = out; *p; p++)
        lines += *p == '\n';
    RF_CHECK_EQ_INT(lines, (long)rf_formula_count());
    RF_CHECK(strstr(out, "transform-normal") && strstr(out, "§4.9"));
    RF_CHECK(strstr(out, "barycentric") && strstr(out, "§2.4"));
}

static void t_one_case(void)
{
    int rc;
    const char *out = run("formula barycentric p1=0,0 p2=4,0 p3=0,4 q=1,1", &rc);
    RF_CHECK_EQ_INT(rc, 0);
    RF_CHECK(strcmp(out, "{\"l1\":0.5,\"l2\":0.25,\"l3\":0.25,\"inside\":true}\n") == 0);
    out = run("formula inverse 'matrix=2,0;0,4' kind=scale", &rc);
    RF_CHECK_EQ_INT(rc, 0);
    RF_CHECK(strcmp(out, "{\"inverse\":[[0.5,0],[0,0.25]],\"singular\":false,\"det\":8}\n") == 0);
}

static void t_errors(void)
{
    int rc;
    const char *out = run("formula no-such-id 2>&1", &rc);
    RF_CHECK_EQ_INT(rc, 2);
    RF_CHECK(strstr(out, "unknown id 'no-such-id'") != NULL);
    out = run("formula inverse matrix=1,2,2,4 2>&1", &rc);
    RF_CHECK_EQ_INT(rc, 1);
    RF_CHECK(strcmp(out, "refray formula inverse: the matrix is singular (det = 0)\n") == 0);
    out = run("formula length a=1,nan 2>&1", &rc);
    RF_CHECK_EQ_INT(rc, 2);
    RF_CHECK(strstr(out, "cannot read") != NULL);
    out = run("formula length 2>&1", &rc);
    RF_CHECK_EQ_INT(rc, 1);
    RF_CHECK(strstr(out, "missing input 'a'") != NULL);
    out = run("nonsense 2>&1", &rc);
    RF_CHECK_EQ_INT(rc, 5); /* README: Exit codes */
    out = run("formula 2>&1", &rc);
    RF_CHECK_EQ_INT(rc, 2);
    RF_CHECK(strstr(out, "usage") != NULL);
}

static void t_help(void)
{
    int rc;
    const char *out = run("formula axis-angle --help", &rc);
    RF_CHECK_EQ_INT(rc, 0);
    RF_CHECK(strstr(out, "section 4.3.1") && strstr(out, "phi_deg") && strstr(out, "erratum"));
    out = run("--help", &rc);
    RF_CHECK_EQ_INT(rc, 0);
    RF_CHECK(strstr(out, "formula") != NULL);
}

static void t_batch(void)
{
    int rc;
    const char *out = run("formula --batch 2>/dev/null <<'EOF'\n"
                          "{\"id\":\"dot\",\"in\":{\"a\":[1,2,3],\"b\":[4,5,6]}}\n"
                          "{\"id\":\"dot\",\"in\":{\"a\":[1,2,3]}}\n"
                          "{\"id\":\"length\",\"in\":{\"a\":[6,8]}}\n"
                          "EOF",
                          &rc);
    RF_CHECK_EQ_INT(rc, 1); /* one case failed */
    RF_CHECK(strstr(out, "{\"id\":\"dot\",\"out\":{\"dot\":32,") == out);
    RF_CHECK(strstr(out, "{\"id\":\"dot\",\"error\":\"missing input 'b'\"}\n") != NULL);
    RF_CHECK(strstr(out, "{\"id\":\"length\",\"out\":{\"length\":10,\"unit\":[0.6,0.8]}}\n") != NULL);
}

const RfTest rf_tests_cli[] = {
    {"cli_formula_list", t_list},
    {"cli_formula_one_case", t_one_case},
    {"cli_formula_errors", t_errors},
    {"cli_help", t_help},
    {"cli_formula_batch", t_batch},
    RF_TEST_END,
};
