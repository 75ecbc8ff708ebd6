/* The `refray` command as a user runs it: output, exit codes, messages. */
#define _XOPEN_SOURCE 700 /* realpath, mkdtemp, PATH_MAX */
#include <stdio.h>
#include <limits.h>
#include <stdlib.h>
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
    /* exit codes (src/cli/exit_codes.h): 2 cannot be computed, 5 usage */
    const char *out = run("formula no-such-id 2>&1", &rc);
    RF_CHECK_EQ_INT(rc, 5);
    RF_CHECK(strstr(out, "unknown id 'no-such-id'") != NULL);
    out = run("formula crosss a=1,0,0 b=0,1,0 2>&1", &rc);
    RF_CHECK_EQ_INT(rc, 5);
    RF_CHECK(strstr(out, "did you mean 'cross'?") != NULL);
    out = run("formula crosss --help 2>&1", &rc);
    RF_CHECK_EQ_INT(rc, 5);
    RF_CHECK(strcmp(out, "refray formula: unknown id 'crosss'; did you mean 'cross'? (see: refray formula list)\n") == 0);
    out = run("formula inverse matrix=1,2,2,4 2>&1", &rc);
    RF_CHECK_EQ_INT(rc, 2);
    RF_CHECK(strcmp(out, "refray formula inverse: the matrix is singular (det = 0)\n") == 0);
    out = run("formula length a=1,nan 2>&1", &rc);
    RF_CHECK_EQ_INT(rc, 5);
    RF_CHECK(strstr(out, "cannot read") != NULL);
    out = run("formula length 2>&1", &rc);
    RF_CHECK_EQ_INT(rc, 5);
    RF_CHECK(strstr(out, "missing input 'a'") != NULL);
    out = run("formula length a=3,4 b=1 2>&1", &rc);
    RF_CHECK_EQ_INT(rc, 5);
    RF_CHECK(strstr(out, "unknown input 'b' (inputs: a)") != NULL);
    out = run("formula length a=3,4 a=1,2 2>&1", &rc);
    RF_CHECK_EQ_INT(rc, 5);
    out = run("formula length a=x 2>&1", &rc);
    RF_CHECK_EQ_INT(rc, 5);
    RF_CHECK(strstr(out, "input 'a': cannot read 'x' as numbers") != NULL);
    out = run("formula reflect n=0,1 dir=1,-1,0 2>&1", &rc);
    RF_CHECK_EQ_INT(rc, 5);
    RF_CHECK(strcmp(out, "refray formula reflect: input 'n' has 2 components; it takes 3\n") == 0);
    out = run("formula dot a=1,2 b=3,4 --digits 3 2>&1", &rc);
    RF_CHECK_EQ_INT(rc, 5);
    out = run("formula dot a=1,2 b=3,4 --format xml 2>&1", &rc);
    RF_CHECK_EQ_INT(rc, 5);
    RF_CHECK(strstr(out, "bad value 'xml' for --format") != NULL);
    out = run("nonsense 2>&1", &rc);
    RF_CHECK_EQ_INT(rc, 5); /* README: Exit codes */
    out = run("formula 2>&1", &rc);
    RF_CHECK_EQ_INT(rc, 5);
    RF_CHECK(strstr(out, "missing the formula id") != NULL);
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
    const char *out = run("formula --batch - 2>/dev/null <<'EOF'\n"
                          "{\"id\":\"dot\",\"in\":{\"a\":[1,2,3],\"b\":[4,5,6]}}\n"
                          "{\"id\":\"dot\",\"in\":{\"a\":[1,2,3]}}\n"
                          "{\"id\":\"length\",\"in\":{\"a\":[6,8]}}\n"
                          "EOF",
                          &rc);
    RF_CHECK_EQ_INT(rc, 5); /* one case lacks an input */
    RF_CHECK(strstr(out, "{\"id\":\"dot\",\"out\":{\"dot\":32,") == out);
    RF_CHECK(strstr(out, "{\"line\":2,\"id\":\"dot\",\"error\":\"missing input 'b'\"}\n") != NULL);
    RF_CHECK(strstr(out, "{\"id\":\"length\",\"out\":{\"length\":10,\"unit\":[0.6,0.8]}}\n") != NULL);
}

/* --batch FILE and --batch=FILE read the file (not stdin); a bad line is named FILE:N on stderr;
 * an empty or missing file is an error; the exit code is the highest of the lines'. */
static void t_batch_file(void)
{
    char dir[] = "/tmp/refray-batch-XXXXXX", cmd[3 * PATH_MAX], bin[PATH_MAX];
    int rc;
    if (!realpath(rf_test_bin(), bin) || !mkdtemp(dir)) {
        rf_test_fail(__FILE__, __LINE__, "mkdtemp");
        return;
    }
    snprintf(cmd, sizeof cmd,
             "cd %s && printf '%%s\\n' '{\"id\":\"length\",\"in\":{\"a\":[6,8]}}' '' 'oops' "
             "'{\"id\":\"inverse\",\"in\":{\"matrix\":\"1,2;2,4\"}}' > c.jsonl && : > empty.jsonl", dir);
    rf_test_run(cmd, &rc);
    RF_CHECK_EQ_INT(rc, 0);
    snprintf(cmd, sizeof cmd, "cd %s && %s formula --batch c.jsonl < /dev/null 2>err.txt; echo rc=$?; cat err.txt",
             dir, bin);
    const char *out = rf_test_run(cmd, &rc);
    const char *want = "{\"id\":\"length\",\"out\":{\"length\":10,\"unit\":[0.6,0.8]}}\n"
                       "{\"line\":3,\"id\":null,\"error\":\"the line is not valid JSON\"}\n"
                       "{\"line\":4,\"id\":\"inverse\",\"error\":\"the matrix is singular (det = 0)\"}\n"
                       "rc=4\n"
                       "c.jsonl:3: the line is not valid JSON\n"
                       "c.jsonl:4: inverse: the matrix is singular (det = 0)\n"
                       "refray formula: 2 of 3 cases failed (see their \"error\" lines)\n";
    rf_test_checks++;
    if (strcmp(out, want) != 0)
        rf_test_fail(__FILE__, __LINE__, "--batch c.jsonl:\n%s\nexpected:\n%s", out, want);
    snprintf(cmd, sizeof cmd, "cd %s && %s formula --batch=c.jsonl --format table 2>/dev/null", dir, bin);
    out = rf_test_run(cmd, &rc);
    RF_CHECK_EQ_INT(rc, 4);
    RF_CHECK(strstr(out, "line  id       inputs                   output  value\n") == out);
    RF_CHECK(strstr(out, "1     length   a=(6, 8)                 length  10\n") != NULL);
    RF_CHECK(strstr(out, "4     inverse  matrix=[[1, 2], [2, 4]]  error   the matrix is singular (det = 0)\n") != NULL);
    snprintf(cmd, sizeof cmd, "cd %s && %s formula --batch empty.jsonl 2>&1", dir, bin);
    out = rf_test_run(cmd, &rc);
    RF_CHECK_EQ_INT(rc, 4);
    RF_CHECK(strstr(out, "empty.jsonl: no cases (the batch is empty") == out);
    snprintf(cmd, sizeof cmd, "cd %s && %s formula --batch nothere.jsonl 2>&1", dir, bin);
    out = rf_test_run(cmd, &rc);
    RF_CHECK_EQ_INT(rc, 4);
    RF_CHECK(strcmp(out, "refray formula: nothere.jsonl: No such file or directory\n") == 0);
    snprintf(cmd, sizeof cmd, "cd %s && %s formula --batch - < /dev/null 2>&1", dir, bin);
    out = rf_test_run(cmd, &rc);
    RF_CHECK_EQ_INT(rc, 4);
    RF_CHECK(strstr(out, "<stdin>: no cases") == out);
    snprintf(cmd, sizeof cmd, "rm -rf %s", dir);
    rf_test_run(cmd, &rc);
}

/* The solution sheet docs/exercises.jsonl (answers computed with numpy and colorsys by
 * tools/oracle/gen_exercises.py) passes --check line by line; a copy with one wrong answer
 * fails on exactly that line, with exit code 2. */
static void t_exercise_sheet(void)
{
    char cmd[2048], sheet[1024];
    int rc;
    snprintf(sheet, sizeof sheet, "%s", rf_test_data("../../docs/exercises.jsonl"));
    snprintf(cmd, sizeof cmd, "%s formula --batch %s --check", rf_test_bin(), sheet);
    const char *out = rf_test_run(cmd, &rc);
    RF_CHECK_EQ_INT(rc, 0);
    int lines = 0, pass = 0;
    for (const char *p = out; *p; p++)
        if (*p == '\n')
            lines++;
    for (const char *p = out; (p = strstr(p, "): pass")) != NULL; p++) /* "pass" or "pass (error: ...)" */
        pass++;
    RF_CHECK(pass >= 25 && pass == lines - 1);
    RF_CHECK(strstr(out, "0 failed\n") != NULL);
    /* line 2 expects cross (1,2,3) x (4,5,6) = (-3,6,-3): plant 7 for 6 */
    snprintf(cmd, sizeof cmd,
             "sed '2s/\"cross\":\\[-3.0,6.0,-3.0\\]/\"cross\":[-3.0,7.0,-3.0]/' %s > /tmp/refray-planted.jsonl && "
             "%s formula --batch /tmp/refray-planted.jsonl --check | grep -v ': pass'; echo rc=$?; "
             "%s formula --batch /tmp/refray-planted.jsonl --check > /dev/null; echo rc=$?; rm -f /tmp/refray-planted.jsonl",
             sheet, rf_test_bin(), rf_test_bin());
    out = rf_test_run(cmd, &rc);
    char want[256];
    snprintf(want, sizeof want, "line 2 (cross): FAIL cross[1]: expected 7, got 6, difference 1 > 7e-09\n%d passed, 1 failed\nrc=0\nrc=2\n",
             pass - 1);
    rf_test_checks++;
    if (strcmp(out, want) != 0)
        rf_test_fail(__FILE__, __LINE__, "planted wrong answer:\n%s\nexpected:\n%s", out, want);
}

static void t_formula_formats_cli(void)
{
    int rc;
    const char *out = run("formula inverse 'matrix=1,2;3,4' --format markdown --digits 2", &rc);
    RF_CHECK_EQ_INT(rc, 0);
    RF_CHECK(strcmp(out, "| output   | value                  |\n| -------- | ---------------------- |\n"
                         "| inverse  | [[-2, 1], [1.5, -0.5]] |\n| singular | false                  |\n"
                         "| det      | -2                     |\n") == 0);
    out = run("formula dot a=1,2,3 b=4,5,6 --format=table --digits=4", &rc);
    RF_CHECK_EQ_INT(rc, 0);
    RF_CHECK(strcmp(out, "output     value\n---------  -------\ndot        32\nangle_deg  12.9332\n") == 0);
}

const RfTest rf_tests_cli[] = {
    {"cli_formula_list", t_list},
    {"cli_formula_one_case", t_one_case},
    {"cli_formula_errors", t_errors},
    {"cli_help", t_help},
    {"cli_formula_batch", t_batch},
    {"cli_formula_batch_file", t_batch_file},
    {"cli_formula_exercise_sheet", t_exercise_sheet},
    {"cli_formula_formats", t_formula_formats_cli},
    RF_TEST_END,
};
