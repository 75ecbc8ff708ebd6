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
    expect_error("length", "{\"a\":\"x\"}", "input 'a': cannot read 'x' as numbers");
    expect_error("length", "{\"a\":true}", "input 'a' must be a vector");
    expect_error("length", "{\"a\":[1,2,3,4,5]}", "input 'a' has 5 components; it takes 2, 3 or 4");
    expect_error("dot", "{\"a\":[1,2],\"b\":[1,2,3]}", "input 'b' has 3 components; it takes 2 here");
    expect_error("inverse", "{\"matrix\":[[1,2],[2,4]]}", "singular");
    expect_error("inverse", "{\"matrix\":[[1,2,3],[4,5,6],[5,7,9]]}", "singular");
    expect_error("inverse", "{\"matrix\":[[1,2,3],[4,5,6]]}", "square matrix");
    expect_error("inverse", "{\"matrix\":[1,2,3,4,5,6,7,8,9,10,11,12,13,14,15,16,17,18,19,20,21,22,23,24,25]}",
                 "has 5 rows (5x5); it takes 2, 3 or 4");
    expect_error("transform-normal", "{\"matrix\":\"1,0;0,1\",\"n\":[0,1,0]}", "has 2 rows (2x2); it takes 3 or 4");
    expect_error("reflect", "{\"n\":[0,1],\"dir\":[1,-1,0]}", "input 'n' has 2 components; it takes 3");
    expect_error("intersect-plane", "{\"origin\":[0,1,0],\"dir\":[0,-1,0],\"normal\":[0,1],\"offset\":0}",
                 "input 'normal' has 2 components; it takes 3");
    expect_error("cross", "{\"a\":[1,0],\"b\":[0,1,0]}", "input 'b' has 3 components; it takes 2 here");
    expect_error("transform-point", "{\"matrix\":\"1,0,0;0,1,0;0,0,1\",\"x\":[1,2,3,4]}",
                 "input 'x' has 4 components; it takes 2 or 3");
    expect_error("phong", "{\"n\":[0,0,1],\"l\":[0,1,1],\"v\":[0,0,1],\"ka\":[0.1,0.1],\"kd\":0.6,"
                 "\"ks\":0.3,\"shininess\":10}", "input 'ka' has 2 components; it takes 3");
    expect_error("xyz-to-xyy", "{\"xyz\":0.5}", "input 'xyz' must be a vector of 3 finite numbers");
    expect_error("inverse", "{\"matrix\":\"1,2;x,4\"}", "cannot read '1,2;x,4' as numbers");
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
    RfFormulaBatchSummary sum;
    RF_CHECK_EQ_INT(rf_formula_batch(in, out, NULL, &sum), 4);
    RF_CHECK_EQ_INT(sum.cases, 6);
    RF_CHECK_EQ_INT(sum.worst, RF_FORMULA_BAD_LINE);
    rewind(out);
    const char *want[] = {
        "{\"id\":\"cross\",\"out\":{\"cross\":[0,0,1],\"sin_phi\":1}}",
        "{\"line\":2,\"id\":null,\"error\":\"the line is not valid JSON\"}",
        "{\"line\":4,\"id\":\"nope\",\"error\":\"unknown formula id 'nope' (see: refray formula list)\"}",
        "{\"line\":5,\"id\":\"inverse\",\"error\":\"the matrix is singular (det = 0)\"}",
        "{\"line\":6,\"id\":null,\"error\":\"the case has no string \\\"id\\\"\"}",
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


/* The inputs of an id's example (its key=value arguments) as a cJSON object. */
static cJSON *example_inputs(const RfFormula *f)
{
    char buf[1024], *argv[32], err[256];
    int argc = 0;
    snprintf(buf, sizeof buf, "%s", f->example ? f->example : "");
    for (char *t = strtok(buf, " "); t && argc < 32; t = strtok(NULL, " "))
        argv[argc++] = t;
    char *json = rf_formula_args_to_json(argc, argv, err, sizeof err);
    cJSON *in = json ? cJSON_Parse(json) : NULL;
    free(json);
    return in;
}

static int run_obj(const RfFormula *f, const cJSON *in, char **out)
{
    char *text = rf_formula_json_text(in);
    int rc = rf_formula_run_json(f, text, out);
    free(text);
    return rc;
}

/* A value of the shape of kind with len where the length goes: a vector of len numbers, a
 * len x len matrix, a list of vectors of len numbers, triangles with corners of len numbers. */
static cJSON *shaped(const RfFormulaItem *it, int len)
{
    double v[8] = {0.3, 0.7, 1.1, 0.2, 0.9, 0.4, 0.6, 0.8};
    if (strncmp(it->kind, "mat", 3) == 0) {
        cJSON *m = cJSON_CreateArray();
        for (int r = 0; r < len; r++) {
            double row[8];
            for (int k = 0; k < len; k++)
                row[k] = r == k ? 2.0 : 0.25;
            cJSON_AddItemToArray(m, cJSON_CreateDoubleArray(row, len));
        }
        return m;
    }
    if (strncmp(it->kind, "vecs", 4) == 0 || strcmp(it->kind, "tris") == 0) {
        cJSON *l = cJSON_CreateArray(), *tri = cJSON_CreateArray();
        for (int i = 0; i < 3; i++)
            cJSON_AddItemToArray(tri, cJSON_CreateDoubleArray(v + i, len));
        if (strcmp(it->kind, "tris") == 0) {
            cJSON_AddItemToArray(l, tri);
            return l;
        }
        cJSON_Delete(tri);
        for (int i = 0; i < len; i++)
            cJSON_AddItemToArray(l, cJSON_CreateDoubleArray(v + i, len));
        return l;
    }
    return cJSON_CreateDoubleArray(v, len);
}

/* Every id, every vector, matrix, colour or triangle input: each length (size) 1..5 the spec
 * does not take is refused as a bad input (usage), never padded or cut; a bare number too,
 * except for colours (grey). The rest of the inputs are the id's example. */
static void t_wrong_length_every_id(void)
{
    int tried = 0;
    for (size_t i = 0; i < rf_formula_count(); i++) {
        const RfFormula *f = rf_formula_at(i);
        RfFormulaItem it;
        for (int k = 0; rf_formula_item(f->inputs, k, &it); k++) {
            int tris = strcmp(it.kind, "tris") == 0;
            if (!it.dims && !tris)
                continue;
            for (int len = 0; len <= 5; len++) {
                if (len == 0 ? it.grey : tris ? len == 3 : len >= 1 && ((it.dims >> len) & 1u))
                    continue; /* a length the input takes (0: a bare number) */
                cJSON *in = example_inputs(f);
                cJSON *v = len == 0 ? cJSON_CreateNumber(0.5) : shaped(&it, len);
                if (cJSON_GetObjectItemCaseSensitive(in, it.name))
                    cJSON_ReplaceItemInObjectCaseSensitive(in, it.name, v);
                else
                    cJSON_AddItemToObject(in, it.name, v);
                char *out = NULL;
                int rc = run_obj(f, in, &out);
                rf_test_checks++;
                tried++;
                if (rc != RF_FORMULA_BAD_INPUT || !out || !strstr(out, it.name))
                    rf_test_fail(__FILE__, __LINE__, "%s %s of length %d: rc %d (want %d, a bad input naming it): %s",
                                 f->id, it.name, len, rc, RF_FORMULA_BAD_INPUT, out ? out : "(null)");
                free(out);
                cJSON_Delete(in);
            }
        }
    }
    RF_CHECK(tried >= 550); /* 81 ids at the time of writing: 566 cases */
}

/* Every colour input: one number v is the grey (v,v,v), with the same outputs bit for bit. */
static void t_grey_every_colour(void)
{
    int tried = 0;
    for (size_t i = 0; i < rf_formula_count(); i++) {
        const RfFormula *f = rf_formula_at(i);
        RfFormulaItem it;
        for (int k = 0; rf_formula_item(f->inputs, k, &it); k++) {
            if (!it.grey)
                continue;
            double g[3] = {0.375, 0.375, 0.375};
            cJSON *a = example_inputs(f), *b = example_inputs(f);
            cJSON_DeleteItemFromObjectCaseSensitive(a, it.name);
            cJSON_DeleteItemFromObjectCaseSensitive(b, it.name);
            cJSON_AddItemToObject(a, it.name, cJSON_CreateNumber(0.375));
            cJSON_AddItemToObject(b, it.name, cJSON_CreateDoubleArray(g, 3));
            char *oa = NULL, *ob = NULL;
            int ra = run_obj(f, a, &oa), rb = run_obj(f, b, &ob);
            rf_test_checks++;
            tried++;
            if (ra || rb || strcmp(oa, ob) != 0)
                rf_test_fail(__FILE__, __LINE__, "%s %s=0.375: %s; %s=0.375,0.375,0.375: %s", f->id, it.name, oa,
                             it.name, ob);
            free(oa);
            free(ob);
            cJSON_Delete(a);
            cJSON_Delete(b);
        }
    }
    RF_CHECK(tried >= 19); /* 19 colour inputs at the time of writing */
    /* light-point intensity=100 at distance 10: 100/10^2 = 1 per channel */
    char *out = NULL;
    RF_CHECK_EQ_INT(run("light-point", "{\"intensity\":100,\"light_pos\":[0,10,0],\"point\":[0,0,0]}", &out), 0);
    RF_CHECK(out && strcmp(out, "{\"i\":[1,1,1],\"l\":[0,1,0],\"distance\":10}") == 0);
    free(out);
}

/* Missing, unknown, malformed inputs are bad inputs; a case that cannot be computed failed. */
static void t_result_classes(void)
{
    static const struct {
        const char *id, *json;
        int want;
    } cases[] = {
        {"length", "{}", RF_FORMULA_BAD_INPUT},
        {"length", "{\"a\":[3,4],\"b\":1}", RF_FORMULA_BAD_INPUT},
        {"length", "{\"a\":\"x\"}", RF_FORMULA_BAD_INPUT},
        {"quantize", "{\"value\":0.5,\"bits\":2.5}", RF_FORMULA_BAD_INPUT},
        {"inverse", "{\"matrix\":[[1,0],[0,1]],\"kind\":\"magic\"}", RF_FORMULA_BAD_INPUT},
        {"homogeneous", "{\"point\":[1,2],\"direction\":[1,2]}", RF_FORMULA_BAD_INPUT},
        {"reflect", "{\"n\":[0,1,0]}", RF_FORMULA_BAD_INPUT},
        {"length", "not json", RF_FORMULA_BAD_INPUT},
        {"inverse", "{\"matrix\":[[1,2],[2,4]]}", RF_FORMULA_FAILED},
        {"triangle-normal", "{\"a\":[0,0,0],\"b\":[1,1,1],\"c\":[2,2,2]}", RF_FORMULA_FAILED},
        {"intersect-sphere", "{\"origin\":[0,0,5],\"dir\":[0,0,-1],\"center\":[0,0,0],\"radius\":-1}",
         RF_FORMULA_FAILED},
        {"length", "{\"a\":\"3,4\"}", RF_FORMULA_OK}, /* the command-line form in JSON */
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        char *out = NULL;
        int rc = run(cases[i].id, cases[i].json, &out);
        rf_test_checks++;
        if (rc != cases[i].want)
            rf_test_fail(__FILE__, __LINE__, "%s %s: result %d, expected %d (%s)", cases[i].id, cases[i].json, rc,
                         cases[i].want, out ? out : "");
        free(out);
    }
}

static char *help_text(const RfFormula *f)
{
    static char text[16384];
    FILE *t = tmpfile();
    if (!t)
        return strcpy(text, "");
    rf_formula_help(f, t);
    rewind(t);
    size_t n = fread(text, 1, sizeof text - 1, t);
    text[n] = 0;
    fclose(t);
    return text;
}

/* Every id: a description for every input and output, an example that runs, and --help shows
 * the example's real output and the words of every enumerated input. */
static void t_help_every_id(void)
{
    for (size_t i = 0; i < rf_formula_count(); i++) {
        const RfFormula *f = rf_formula_at(i);
        RfFormulaItem it;
        const char *specs[2] = {f->inputs, f->outputs};
        for (int s = 0; s < 2; s++)
            for (int k = 0; rf_formula_item(specs[s], k, &it); k++) {
                rf_test_checks++;
                if (strlen(it.note) < 3 || !it.kind[0])
                    rf_test_fail(__FILE__, __LINE__, "%s: %s '%s' has no kind or description", f->id,
                                 s ? "output" : "input", it.name);
            }
        cJSON *in = example_inputs(f);
        char *out = NULL;
        int rc = in ? run_obj(f, in, &out) : -1;
        rf_test_checks++;
        if (rc != 0) {
            rf_test_fail(__FILE__, __LINE__, "%s: the example '%s' fails: %s", f->id, f->example ? f->example : "(none)",
                         out ? out : "");
        } else {
            const char *h = help_text(f);
            RF_CHECK(strstr(h, out) != NULL && strstr(h, "example fails") == NULL);
            for (int k = 0; rf_formula_item(f->inputs, k, &it); k++)
                if (strchr(it.kind, '|')) { /* "a|b|c" is listed as "one of: a, b, c" */
                    char words[128];
                    snprintf(words, sizeof words, "one of: %s", it.kind);
                    for (char *c = words; *c; c++)
                        if (*c == '|')
                            memmove(c + 2, c + 1, strlen(c + 1) + 1), c[0] = ',', c[1] = ' ';
                    rf_test_checks++;
                    if (!strstr(h, words))
                        rf_test_fail(__FILE__, __LINE__, "%s --help does not list '%s'", f->id, words);
                }
        }
        free(out);
        cJSON_Delete(in);
    }
}

/* Runs a batch text through rf_formula_batch with opt; returns its output (static). */
static const char *batch_text(const char *lines, const RfFormulaBatchOptions *opt, RfFormulaBatchSummary *sum)
{
    static char text[16384];
    FILE *in = tmpfile(), *out = tmpfile();
    if (!in || !out)
        return "";
    fputs(lines, in);
    rewind(in);
    rf_formula_batch(in, out, opt, sum);
    rewind(out);
    size_t n = fread(text, 1, sizeof text - 1, out);
    text[n] = 0;
    fclose(in);
    fclose(out);
    return text;
}

/* --check: pass, a wrong number (path, expected, got, difference), a missing output, a line's
 * own tolerance, the command-line form of an expected matrix, no expect, an error; an expected
 * error (any, or with words of its message) that comes, does not come, or is another. */
static void t_check(void)
{
    RfFormulaBatchOptions opt = {RF_FORMULA_JSON, -1, 1, RF_FORMULA_RTOL, RF_FORMULA_ATOL, "t.jsonl", NULL};
    RfFormulaBatchSummary sum;
    const char *out = batch_text(
        "{\"id\":\"dot\",\"in\":{\"a\":[1,2,3],\"b\":[4,5,6]},\"expect\":{\"dot\":32}}\n"
        "{\"id\":\"cross\",\"in\":{\"a\":[1,0,0],\"b\":[0,1,0]},\"expect\":{\"cross\":[0,0,-1]}}\n"
        "\n"
        "{\"id\":\"length\",\"in\":{\"a\":[3,4]},\"expect\":{\"len\":5}}\n"
        "{\"id\":\"length\",\"in\":{\"a\":[3,4]},\"expect\":{\"length\":5.001},\"rtol\":1e-3}\n"
        "{\"id\":\"length\",\"in\":{\"a\":[3,4]},\"expect\":{\"length\":5.001}}\n"
        "{\"id\":\"inverse\",\"in\":{\"matrix\":\"2,0;0,4\"},\"expect\":{\"inverse\":\"0.5,0;0,0.25\",\"singular\":false}}\n"
        "{\"id\":\"length\",\"in\":{\"a\":[3,4]}}\n"
        "{\"id\":\"inverse\",\"in\":{\"matrix\":[[1,2],[2,4]]},\"expect\":{\"det\":0}}\n"
        "{\"id\":\"inverse\",\"in\":{\"matrix\":[[1,2],[2,4]]},\"expect\":{\"error\":\"singular\"}}\n"
        "{\"id\":\"inverse\",\"in\":{\"matrix\":[[1,2],[2,5]]},\"expect\":{\"error\":true}}\n"
        "{\"id\":\"inverse\",\"in\":{\"matrix\":[[1,2],[2,4]]},\"expect\":{\"error\":\"diagonal\"}}\n",
        &opt, &sum);
    const char *want =
        "line 1 (dot): pass\n"
        "line 2 (cross): FAIL cross[2]: expected -1, got 1, difference 2 > 1e-09\n"
        "line 4 (length): FAIL len: expected 5, got nothing (no such output)\n"
        "line 5 (length): pass\n"
        "line 6 (length): FAIL length: expected 5.001, got 5, difference 0.001 > 5e-09\n"
        "line 7 (inverse): pass\n"
        "line 8 (length): not checked (no \"expect\")\n"
        "line 9 (inverse): ERROR the matrix is singular (det = 0)\n"
        "line 10 (inverse): pass (error: the matrix is singular (det = 0))\n"
        "line 11 (inverse): FAIL expected an error, got {\"inverse\":[[5,-2],[-2,1]],\"singular\":false,\"det\":1}\n"
        "line 12 (inverse): FAIL expected another error, got the matrix is singular (det = 0)\n"
        "4 passed, 6 failed, 1 not checked\n";
    rf_test_checks++;
    if (strcmp(out, want) != 0)
        rf_test_fail(__FILE__, __LINE__, "check report:\n%s\nexpected:\n%s", out, want);
    RF_CHECK_EQ_INT(sum.passed, 4);
    RF_CHECK_EQ_INT(sum.failed, 6);
    RF_CHECK_EQ_INT(sum.worst, RF_FORMULA_FAILED);
}

/* The output formats, exact text: a vector and a number, a matrix, rounding, null, LaTeX. */
static void t_formats(void)
{
    static const struct {
        const char *id, *out;
        RfFormulaFormat fmt;
        int digits;
        const char *want;
    } cases[] = {
        {"dot", "{\"dot\":32,\"angle_deg\":12.93315449189912}", RF_FORMULA_TABLE, -1,
         "output     value\n---------  -----------------\ndot        32\nangle_deg  12.93315449189912\n"},
        {"dot", "{\"dot\":32,\"angle_deg\":12.93315449189912}", RF_FORMULA_TABLE, 3,
         "output     value\n---------  ------\ndot        32\nangle_deg  12.933\n"},
        {"length", "{\"length\":0,\"unit\":null}", RF_FORMULA_MARKDOWN, 2,
         "| output | value |\n| ------ | ----- |\n| length | 0     |\n| unit   | none  |\n"},
        {"inverse", "{\"inverse\":[[-2,1],[1.5,-0.5]],\"singular\":false,\"det\":-2.0000000000000004}",
         RF_FORMULA_MARKDOWN, 4,
         "| output   | value                  |\n| -------- | ---------------------- |\n"
         "| inverse  | [[-2, 1], [1.5, -0.5]] |\n| singular | false                  |\n| det      | -2                     |\n"},
        {"inverse", "{\"inverse\":[[-2,1],[1.5,-0.5]],\"singular\":false,\"det\":-2.0000000000000004}",
         RF_FORMULA_LATEX, 4,
         "\\begin{tabular}{ll}\n\\hline\noutput & value \\\\\n\\hline\n"
         "\\texttt{inverse} & $\\begin{pmatrix}-2 & 1 \\\\ 1.5 & -0.5\\end{pmatrix}$ \\\\\n"
         "\\texttt{singular} & $\\text{false}$ \\\\\n\\texttt{det} & $-2$ \\\\\n\\hline\n\\end{tabular}\n"},
        {"length", "{\"length\":5,\"unit\":[0.6,0.8]}", RF_FORMULA_LATEX, -1,
         "\\begin{tabular}{ll}\n\\hline\noutput & value \\\\\n\\hline\n\\texttt{length} & $5$ \\\\\n"
         "\\texttt{unit} & $\\begin{pmatrix}0.6 \\\\ 0.8\\end{pmatrix}$ \\\\\n\\hline\n\\end{tabular}\n"},
        {"frequency", "{\"nu_hz\":1.234e-17}", RF_FORMULA_LATEX, -1,
         "\\begin{tabular}{ll}\n\\hline\noutput & value \\\\\n\\hline\n\\texttt{nu\\_hz} & $1.234 \\cdot 10^{-17}$ \\\\\n"
         "\\hline\n\\end{tabular}\n"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        static char text[4096];
        FILE *t = tmpfile();
        rf_formula_print(rf_formula_find(cases[i].id), cases[i].out, cases[i].fmt, cases[i].digits, t);
        rewind(t);
        size_t n = fread(text, 1, sizeof text - 1, t);
        text[n] = 0;
        fclose(t);
        rf_test_checks++;
        if (strcmp(text, cases[i].want) != 0)
            rf_test_fail(__FILE__, __LINE__, "%s format %d digits %d:\n%s\nexpected:\n%s", cases[i].id, cases[i].fmt,
                         cases[i].digits, text, cases[i].want);
    }
    /* a batch as a Markdown table: line, id, inputs, then one row per output */
    RfFormulaBatchOptions opt = {RF_FORMULA_MARKDOWN, 3, 0, RF_FORMULA_RTOL, RF_FORMULA_ATOL, NULL, NULL};
    const char *out = batch_text("{\"id\":\"length\",\"in\":{\"a\":[3,4]}}\n{\"id\":\"dot\",\"in\":{\"a\":[1,0],\"b\":[1]}}\n",
                                 &opt, NULL);
    const char *want =
        "| line | id     | inputs          | output | value                                 |\n"
        "| ---- | ------ | --------------- | ------ | ------------------------------------- |\n"
        "| 1    | length | a=(3, 4)        | length | 5                                     |\n"
        "|      |        |                 | unit   | (0.6, 0.8)                            |\n"
        "| 2    | dot    | a=(1, 0), b=(1) | error  | input 'b' has 1 component; it takes 2 |\n";
    rf_test_checks++;
    if (strcmp(out, want) != 0)
        rf_test_fail(__FILE__, __LINE__, "markdown batch:\n%s\nexpected:\n%s", out, want);
}

/* docs/formulas.md is what `refray formula --reference` prints: the table, not a copy. */
static void t_reference_current(void)
{
    static char want[1 << 20], have[1 << 20];
    FILE *t = tmpfile(), *f = fopen(rf_test_data("../../docs/formulas.md"), "r");
    RF_CHECK(t && f);
    if (!t || !f) {
        if (t)
            fclose(t);
        if (f)
            fclose(f);
        return;
    }
    rf_formula_reference(t);
    rewind(t);
    size_t nw = fread(want, 1, sizeof want - 1, t), nh = fread(have, 1, sizeof have - 1, f);
    want[nw] = have[nh] = 0;
    fclose(t);
    fclose(f);
    rf_test_checks++;
    if (strcmp(want, have) != 0)
        rf_test_fail(__FILE__, __LINE__, "docs/formulas.md is out of date: refray formula --reference > docs/formulas.md");
}

const RfTest rf_tests_formula[] = {
    {"formula_registry_complete", t_registry_complete},
    {"formula_oracle_core", t_oracle_core},
    {"formula_errors", t_errors},
    {"formula_args_to_json", t_args_to_json},
    {"formula_batch", t_batch},
    {"formula_round_trip_digits", t_round_trip_digits},
    {"formula_help", t_help},
    {"formula_wrong_length_every_id", t_wrong_length_every_id},
    {"formula_grey_every_colour", t_grey_every_colour},
    {"formula_result_classes", t_result_classes},
    {"formula_help_every_id", t_help_every_id},
    {"formula_check", t_check},
    {"formula_formats", t_formats},
    {"formula_reference_current", t_reference_current},
    RF_TEST_END,
};
