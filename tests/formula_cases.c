/* Runs a file of independently computed formula cases through the registry: one JSON line per
 * case, {"id", "in", "expect", "source"[, "rel", "abs"]}. Every expected field must be in the
 * output and match: numbers to rel * max(|a|,|b|) + abs, booleans, nulls and strings exactly,
 * arrays element by element. A case with "error": true must fail. Extra output fields are fine
 * (the contract allows more fields). */
#include <cJSON.h>
#include <stdlib.h>
#include <string.h>

#include "refray/formula.h"
#include "rf_test.h"

static int match(const cJSON *want, const cJSON *got, double rel, double abs_tol, char *path, size_t cap)
{
    if (cJSON_IsNumber(want))
        return cJSON_IsNumber(got) && rf_test_near(got->valuedouble, want->valuedouble, rel, abs_tol);
    if (cJSON_IsBool(want))
        return cJSON_IsBool(got) && cJSON_IsTrue(want) == cJSON_IsTrue(got);
    if (cJSON_IsNull(want))
        return got && cJSON_IsNull(got);
    if (cJSON_IsString(want))
        return cJSON_IsString(got) && strcmp(want->valuestring, got->valuestring) == 0;
    if (cJSON_IsArray(want)) {
        if (!cJSON_IsArray(got) || cJSON_GetArraySize(want) != cJSON_GetArraySize(got))
            return 0;
        for (int i = 0; i < cJSON_GetArraySize(want); i++) {
            size_t len = strlen(path);
            snprintf(path + len, cap - len, "[%d]", i);
            if (!match(cJSON_GetArrayItem(want, i), cJSON_GetArrayItem(got, i), rel, abs_tol, path, cap))
                return 0;
            path[len] = 0;
        }
        return 1;
    }
    if (cJSON_IsObject(want)) {
        const cJSON *e;
        cJSON_ArrayForEach(e, want) {
            size_t len = strlen(path);
            snprintf(path + len, cap - len, ".%s", e->string);
            if (!match(e, cJSON_GetObjectItemCaseSensitive(got, e->string), rel, abs_tol, path, cap))
                return 0;
            path[len] = 0;
        }
        return 1;
    }
    return 0;
}

int rf_test_formula_cases(const char *file, double rel, double abs_tol)
{
    FILE *f = fopen(rf_test_data(file), "r");
    static char line[1 << 20];
    int count = 0, lineno = 0;
    rf_test_checks++;
    if (!f) {
        rf_test_fail(__FILE__, __LINE__, "cannot open %s", rf_test_data(file));
        return 0;
    }
    while (fgets(line, sizeof line, f)) {
        lineno++;
        cJSON *c = cJSON_Parse(line);
        if (!c) {
            rf_test_fail(file, lineno, "not valid JSON");
            continue;
        }
        const cJSON *id = cJSON_GetObjectItemCaseSensitive(c, "id");
        const cJSON *in = cJSON_GetObjectItemCaseSensitive(c, "in");
        const cJSON *want = cJSON_GetObjectItemCaseSensitive(c, "expect");
        const cJSON *r = cJSON_GetObjectItemCaseSensitive(c, "rel");
        const cJSON *a = cJSON_GetObjectItemCaseSensitive(c, "abs");
        int want_error = cJSON_IsTrue(cJSON_GetObjectItemCaseSensitive(c, "error"));
        const RfFormula *fm = cJSON_IsString(id) ? rf_formula_find(id->valuestring) : NULL;
        rf_test_checks++;
        count++;
        if (!fm) {
            rf_test_fail(file, lineno, "unknown id %s", cJSON_IsString(id) ? id->valuestring : "?");
            cJSON_Delete(c);
            continue;
        }
        char *in_text = rf_formula_json_text(in);
        char *out = NULL;
        int rc = rf_formula_run_json(fm, in_text, &out);
        if (want_error) {
            if (!rc)
                rf_test_fail(file, lineno, "%s %s: expected an error, got %s", id->valuestring, in_text, out);
        } else if (rc) {
            rf_test_fail(file, lineno, "%s %s: error: %s", id->valuestring, in_text, out);
        } else {
            cJSON *got = cJSON_Parse(out);
            char path[256] = "";
            if (!match(want, got, cJSON_IsNumber(r) ? r->valuedouble : rel,
                       cJSON_IsNumber(a) ? a->valuedouble : abs_tol, path, sizeof path))
                rf_test_fail(file, lineno, "%s %s: field %s differs: got %s", id->valuestring, in_text,
                             path, out);
            cJSON_Delete(got);
        }
        free(in_text);
        free(out);
        cJSON_Delete(c);
    }
    fclose(f);
    return count;
}
