/* The formula registry: independent cases for every §2 and §4 id, error handling, help, batch. */
#include <cJSON.h>
#include <stdlib.h>
#include <string.h>

#include "refray/formula.h"
#include "rf_test.h"

/* The §2 and §4 ids of FORMULAS.md. */
static const char *const core_ids[] = {
    "length", "dot", "cross", "triangle-normal", "line-point", "plane-point", "basis-coordinates",
    "barycentric", "scale2", "shear2", "reflect2", "rotate2", "rotate3", "euler", "rotation-basis",
    "axis-angle", "inverse", "homogeneous", "affine", "rotate-about-point", "scale3h", "shear3z",
    "rotate3h", "translate3h", "change-of-basis", "camera-transform", "transform-point",
    "transform-direction", "transform-normal",
};

static void t_registry_complete(void)
{
    for (size_t i = 0; i < sizeof core_ids / sizeof core_ids[0]; i++) {
        const RfFormula *f = rf_formula_find(core_ids[i]);
        rf_test_checks++;
        if (!f || !f->fn || !f->section || !f->summary || !f->outputs)
            rf_test_fail(__FILE__, __LINE__, "id %s missing or incomplete", core_ids[i]);
    }
    /* ids are unique */
    for (size_t i = 0; i < rf_formula_count(); i++)
        for (size_t j = i + 1; j < rf_formula_count(); j++)
            RF_CHECK(strcmp(rf_formula_at(i)->id, rf_formula_at(j)->id) != 0);
    RF_CHECK(rf_formula_find("no-such-id") == NULL);
}

/* Every case of tests/data/formula_cases_core.jsonl (tools/oracle/gen_core_cases.py, numpy):
 * 1e-12 relative; 1e-14 absolute for values that are zero in exact arithmetic (e.g. cos 90°). */
static void t_oracle_core(void)
{
    int n = rf_test_formula_cases("formula_cases_core.jsonl", 1e-12, 1e-14);
    RF_CHECK(n >= 150);
}

/* Runs one formula on JSON text; returns the exit status, output or error in *out. */
static int run(const char *id, const char *json, char **out)
{
    return rf_formula_run_json(rf_formula_find(id), json, out);
}

static void expect_error(const char *id, const char *json, const char *fragment)
{
    char *out = NULL;
    int rc = run(id, json, &out);
    rf_test_checks++;
    if (!rc || !out || !strstr(out, fragment))
        rf_test_fail(__FILE__, __LINE__, "%s %s: expected an error containing '%s', got rc %d: %s", id, json,
                     fragment, rc, out ? out : "(null)");
    free(out);
}

static void t_errors(void)
{
    expect_error("length", "{}", "missing input 'a'");
    expect_error("length", "{\"a\":[1,2],\"b\":3}", "unknown input 'b'");
    expect_error("length", "{\"a\":\"x\"}", "input 'a' must be a vector");
    expect_error("length", "{\"a\":[1,2,3,4,5]}", "input 'a' must be a vector");
    expect_error("dot", "{\"a\":[1,2],\"b\":[1,2,3]}", "same dimension");
    expect_error("inverse", "{\"matrix\":[[1,2],[2,4]]}", "singular");
    expect_error("inverse", "{\"matrix\":[[1,2,3],[4,5,6],[5,7,9]]}", "singular");
    expect_error("inverse", "{\"matrix\":[[1,2,3],[4,5,6]]}", "square matrix");
    expect_error("inverse", "{\"matrix\":[[1,2],[3,4]],\"kind\":\"scale\"}", "diagonal");
    expect_error("inverse", "{\"matrix\":[[2,0],[0,2]],\"kind\":\"rotation\"}", "orthogonal");
    expect_error("inverse", "{\"matrix\":[[1,0],[0,1]],\"kind\":\"magic\"}", "must be one of");
    expect_error("axis-angle", "{\"d\":[0,0,0],\"phi_deg\":10}", "zero vector");
    expect_error("euler", "{\"psi_deg\":1,\"theta_deg\":2,\"phi_deg\":3,\"order\":\"yxy\"}", "must be one of");
    expect_error("camera-transform", "{\"eye\":[0,0,0],\"target\":[0,1,0],\"up\":[0,1,0]}", "parallel");
    expect_error("triangle-normal", "{\"a\":[0,0,0],\"b\":[1,1,1],\"c\":[2,2,2]}", "collinear");
    expect_error("basis-coordinates", "{\"basis\":[[1,2],[2,4]],\"v\":[1,1]}", "dependent");
    expect_error("basis-coordinates", "{\"basis\":[[1,0,0],[0,1,0]],\"v\":[1,1,1]}", "needs 3 vectors");
    expect_error("line-point", "{\"p\":[1,1],\"q\":[1,1],\"t\":0.5}", "must differ");
    expect_error("homogeneous", "{\"point\":[1,2],\"direction\":[1,2]}", "exactly one");
    expect_error("homogeneous", "{\"point\":[1,2],\"w\":0}", "w != 0");
    expect_error("transform-normal", "{\"matrix\":[[1,0,0],[0,0,0],[0,0,1]],\"n\":[0,1,0]}", "singular");
    expect_error("transform-point", "{\"matrix\":[[1,0,0,0],[0,1,0,0],[0,0,1,0],[0,0,1,0]],\"x\":[1,1,0]}",
                 "infinity");
    expect_error("length", "{\"a\":[1e308,1e308]}", "not finite"); /* the length overflows */
    expect_error("length", "[1,2]", "JSON object");
    expect_error("length", "not json", "not valid JSON");
}

static void t_args_to_json(void)
{
    char err[256];
    char *argv1[] = {"a=1,2,3", "m=1,0;0,1", "axis=x", "flag=true", "s=-2.5e3", "l=[[1,2],[3,4]]"};
    char *j = rf_formula_args_to_json(6, argv1, err, sizeof err);
    RF_CHECK(j && strcmp(j, "{\"a\":[1,2,3],\"m\":[[1,0],[0,1]],\"axis\":\"x\",\"flag\":true,"
                            "\"s\":-2500,\"l\":[[1,2],[3,4]]}") == 0);
    free(j);
    char *bad[][1] = {{"a=nan"}, {"a=1,inf"}, {"a=1,,2"}, {"noequals"}, {"a=1e999"}, {"=3"}, {"a=0x10"}};
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        j = rf_formula_args_to_json(1, bad[i], err, sizeof err);
        rf_test_checks++;
        if (j)
            rf_test_fail(__FILE__, __LINE__, "'%s' was accepted as %s", bad[i][0], j);
        free(j);
    }
    char *twice[] = {"a=1", "a=2"};
    RF_CHECK(rf_formula_args_to_json(2, twice, err, sizeof err) == NULL && strstr(err, "twice"));
}

static void t_batch(void)
{
    FILE *in = tmpfile(), *out = tmpfile();
    char line[4096];
    fputs("{\"id\":\"cross\",\"in\":{\"a\":[1,0,0],\"b\":[0,1,0]}}\n"
          "this is not json\n"
          "\n"
          "{\"id\":\"nope\",\"in\":{}}\n"
          "{\"id\":\"inverse\",\"in\":{\"matrix\":[[1,2],[2,4]]}}\n"
          "{\"in\":{}}\n"
          "{\"id\":\"length\",\"in\":{\"a\":[3,4]}}",
          in);
    rewind(in);
    RF_CHECK_EQ_INT(rf_formula_batch(in, out), 4);
    rewind(out);
    const char *want[] = {
        "{\"id\":\"cross\",\"out\":{\"cross\":[0,0,1],\"sin_phi\":1}}",
        "{\"id\":null,\"error\":\"the line is not valid JSON\"}",
        "{\"id\":\"nope\",\"error\":\"unknown formula id 'nope' (see: refray formula list)\"}",
        "{\"id\":\"inverse\",\"error\":\"the matrix is singular (det = 0)\"}",
        "{\"id\":null,\"error\":\"the case has no string \\\"id\\\"\"}",
        "{\"id\":\"length\",\"out\":{\"length\":5,\"unit\":[0.6,0.8]}}",
    };
    for (size_t i = 0; i < sizeof want / sizeof want[0]; i++) {
        rf_test_checks++;
        if (!fgets(line, sizeof line, out)) {
            rf_test_fail(__FILE__, __LINE__, "batch output ended after %zu lines", i);
            break;
        }
        line[strcspn(line, "\n")] = 0;
        if (strcmp(line, want[i]) != 0)
            rf_test_fail(__FILE__, __LINE__, "batch line %zu: %s, expected %s", i + 1, line, want[i]);
    }
    RF_CHECK(!fgets(line, sizeof line, out));
    fclose(in);
    fclose(out);
}

static void t_round_trip_digits(void)
{
    /* outputs round-trip to the same double: 1/3 and 0.1 + 0.2 survive printing */
    char *out = NULL;
    RF_CHECK_EQ_INT(run("scale2", "{\"sx\":0.30000000000000004,\"sy\":0.33333333333333331}", &out), 0);
    cJSON *j = cJSON_Parse(out);
    cJSON *m = cJSON_GetObjectItem(j, "matrix");
    RF_CHECK(cJSON_GetArrayItem(cJSON_GetArrayItem(m, 0), 0)->valuedouble == 0.1 + 0.2);
    RF_CHECK(cJSON_GetArrayItem(cJSON_GetArrayItem(m, 1), 1)->valuedouble == 1.0 / 3.0);
    cJSON_Delete(j);
    free(out);
}

static void t_help(void)
{
    FILE *f = tmpfile();
    char text[4096];
    rf_formula_help(rf_formula_find("transform-normal"), f);
    rewind(f);
    size_t n = fread(text, 1, sizeof text - 1, f);
    text[n] = 0;
    fclose(f);
    RF_CHECK(strstr(text, "script section 4.9") != NULL);
    RF_CHECK(strstr(text, "erratum") != NULL && strstr(text, "inverse transpose") != NULL);
    RF_CHECK(strstr(text, "matrix") != NULL && strstr(text, "similarity") != NULL);
    /* every erratum of §2/§4 in FORMULAS.md is shown by its id's help */
    const char *with_erratum[] = {"length", "cross", "rotation-basis", "axis-angle", "affine",
                                  "change-of-basis", "camera-transform", "transform-normal"};
    for (size_t i = 0; i < sizeof with_erratum / sizeof with_erratum[0]; i++)
        RF_CHECK(rf_formula_find(with_erratum[i])->erratum != NULL);
}

const RfTest rf_tests_formula[] = {
    {"formula_registry_complete", t_registry_complete},
    {"formula_oracle_core", t_oracle_core},
    {"formula_errors", t_errors},
    {"formula_args_to_json", t_args_to_json},
    {"formula_batch", t_batch},
    {"formula_round_trip_digits", t_round_trip_digits},
    {"formula_help", t_help},
    RF_TEST_END,
};
