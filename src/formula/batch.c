/* `refray formula --batch`: JSON lines in, one result per case out, and --check: each case's
 * outputs against its "expect" with a tolerance, reported line by line for a tutor. */
#include "formula_internal.h"

#include <ctype.h>
#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

/* Reads one line of any length; returns NULL at the end of the input. */
static char *read_line(FILE *in)
{
    size_t cap = 256, n = 0;
    char *buf = malloc(cap);
    int c;
    if (!buf)
        return NULL;
    while ((c = fgetc(in)) != EOF && c != '\n') {
        if (n + 1 >= cap) {
            char *nb = realloc(buf, cap *= 2);
            if (!nb) {
                free(buf);
                return NULL;
            }
            buf = nb;
        }
        buf[n++] = (char)c;
    }
    if (c == EOF && n == 0) {
        free(buf);
        return NULL;
    }
    buf[n] = 0;
    return buf;
}

/* ---- --check ---- */

typedef struct {
    char text[1024]; /* the mismatches of one case, "; "-separated */
    int count;
    double rtol, atol;
} Mismatches;

static void mismatch(Mismatches *m, const char *path, const cJSON *want, const cJSON *got, double diff)
{
    char *w = rf_formula_json_text(want), *g = got ? rf_formula_json_text(got) : NULL;
    size_t len = strlen(m->text);
    if (m->count < 4) {
        if (isnan(diff))
            snprintf(m->text + len, sizeof m->text - len, "%s%s: expected %s, got %s", m->count ? "; " : "",
                     path, w ? w : "?", got ? (g ? g : "?") : "nothing (no such output)");
        else
            snprintf(m->text + len, sizeof m->text - len, "%s%s: expected %s, got %s, difference %.3g > %.3g",
                     m->count ? "; " : "", path, w ? w : "?", g ? g : "?", diff,
                     m->atol + m->rtol * fabs(want->valuedouble));
    } else if (m->count == 4) {
        snprintf(m->text + len, sizeof m->text - len, "; ...");
    }
    m->count++;
    free(w);
    free(g);
}

/* Compares an expected value with an output, recording every mismatching number, word or
 * shape under its path ("matrix[1][0]"). Expected vectors and matrices may also be written in
 * the command-line form "1,2;3,4". */
static void compare(const cJSON *want, const cJSON *got, const char *path, Mismatches *m)
{
    cJSON *parsed = NULL;
    if (cJSON_IsString(want) && got && !cJSON_IsString(got) && (parsed = rf_formula_value_json(want->valuestring)))
        want = parsed;
    if (cJSON_IsNumber(want)) {
        if (!cJSON_IsNumber(got)) {
            mismatch(m, path, want, got, NAN);
        } else {
            double diff = fabs(got->valuedouble - want->valuedouble);
            if (!(diff <= m->atol + m->rtol * fabs(want->valuedouble)))
                mismatch(m, path, want, got, diff);
        }
    } else if (cJSON_IsArray(want)) {
        if (!cJSON_IsArray(got) || cJSON_GetArraySize(want) != cJSON_GetArraySize(got)) {
            mismatch(m, path, want, got, NAN);
        } else {
            for (int i = 0; i < cJSON_GetArraySize(want); i++) {
                char sub[256];
                snprintf(sub, sizeof sub, "%s[%d]", path, i);
                compare(cJSON_GetArrayItem(want, i), cJSON_GetArrayItem(got, i), sub, m);
            }
        }
    } else if (cJSON_IsBool(want)) {
        if (!cJSON_IsBool(got) || cJSON_IsTrue(want) != cJSON_IsTrue(got))
            mismatch(m, path, want, got, NAN);
    } else if (cJSON_IsNull(want)) {
        if (!cJSON_IsNull(got))
            mismatch(m, path, want, got, NAN);
    } else if (cJSON_IsString(want)) {
        if (!cJSON_IsString(got) || strcmp(want->valuestring, got->valuestring) != 0)
            mismatch(m, path, want, got, NAN);
    } else {
        mismatch(m, path, want, got, NAN);
    }
    cJSON_Delete(parsed);
}

/* A line's own tolerance ("rtol"/"atol"), or the default. */
static int line_tolerance(const cJSON *c, const char *key, double def, double *v, char *error, size_t cap)
{
    const cJSON *t = cJSON_GetObjectItemCaseSensitive(c, key);
    *v = def;
    if (!t)
        return 0;
    if (!cJSON_IsNumber(t) || !(t->valuedouble >= 0.0) || !isfinite(t->valuedouble)) {
        snprintf(error, cap, "\"%s\" must be a number >= 0", key);
        return 1;
    }
    *v = t->valuedouble;
    return 0;
}

/* ---- the batch ---- */

static void message(const RfFormulaBatchOptions *opt, int line, const char *fmt, ...)
{
    if (!opt || !opt->err)
        return;
    va_list ap;
    va_start(ap, fmt);
    fprintf(opt->err, "%s:%d: ", opt->name ? opt->name : "-", line);
    vfprintf(opt->err, fmt, ap);
    fputc('\n', opt->err);
    va_end(ap);
}

int rf_formula_batch(FILE *in, FILE *out, const RfFormulaBatchOptions *opt, RfFormulaBatchSummary *sum)
{
    RfFormulaBatchOptions def = {RF_FORMULA_JSON, -1, 0, RF_FORMULA_RTOL, RF_FORMULA_ATOL, NULL, NULL};
    RfFormulaBatchSummary local;
    if (!opt)
        opt = &def;
    if (!sum)
        sum = &local;
    memset(sum, 0, sizeof *sum);
    RfFormulaTable *table = opt->check || opt->format == RF_FORMULA_JSON ? NULL : rf_formula_table_new(1);
    char *line;
    for (int lineno = 1; (line = read_line(in)) != NULL; lineno++, free(line)) {
        const char *p = line;
        while (isspace((unsigned char)*p))
            p++;
        if (!*p)
            continue;
        sum->cases++;
        cJSON *c = cJSON_ParseWithOpts(p, NULL, 1); /* trailing text makes the line invalid */
        const cJSON *id = c ? cJSON_GetObjectItemCaseSensitive(c, "id") : NULL;
        const cJSON *inputs = c ? cJSON_GetObjectItemCaseSensitive(c, "in") : NULL;
        const cJSON *expect = c ? cJSON_GetObjectItemCaseSensitive(c, "expect") : NULL;
        const RfFormula *f = NULL;
        char error[512] = "";
        RfFormulaResult result = RF_FORMULA_BAD_LINE;
        cJSON *o = NULL;
        double rtol = opt->rtol, atol = opt->atol;
        if (!c)
            snprintf(error, sizeof error, "the line is not valid JSON");
        else if (!cJSON_IsObject(c))
            snprintf(error, sizeof error, "the line is not a JSON object {\"id\":..., \"in\":{...}}");
        else if (!cJSON_IsString(id))
            snprintf(error, sizeof error, "the case has no string \"id\"");
        else if (expect && !cJSON_IsObject(expect))
            snprintf(error, sizeof error, "\"expect\" must be an object {\"output\": value, ...}");
        else if (line_tolerance(c, "rtol", opt->rtol, &rtol, error, sizeof error) ||
                 line_tolerance(c, "atol", opt->atol, &atol, error, sizeof error))
            ;
        else if ((result = RF_FORMULA_BAD_INPUT, !(f = rf_formula_find(id->valuestring))))
            snprintf(error, sizeof error, "unknown formula id '%s' (see: refray formula list)", id->valuestring);
        else {
            cJSON *empty = inputs ? NULL : cJSON_CreateObject();
            o = rf_formula_run(f, inputs ? inputs : empty, error, sizeof error, &result);
            cJSON_Delete(empty);
        }
        const char *name = cJSON_IsString(id) ? id->valuestring : NULL;
        /* --check: "expect":{"error":true} or {"error":"words of the message"} asks for a failure */
        const cJSON *want_error = opt->check && cJSON_IsObject(expect) && f
                                ? cJSON_GetObjectItemCaseSensitive(expect, "error") : NULL;
        if (!cJSON_IsTrue(want_error) && !cJSON_IsString(want_error))
            want_error = NULL;
        int error_wanted = want_error && !o &&
                           (cJSON_IsTrue(want_error) ||
                            (cJSON_IsString(want_error) && strstr(error, want_error->valuestring)));
        if (!o && !error_wanted) {
            sum->errors++;
            if (result > sum->worst)
                sum->worst = result;
            message(opt, lineno, "%s%s%s", name ? name : "", name ? ": " : "", error);
        }
        if (opt->check) {
            Mismatches m;
            memset(&m, 0, sizeof m);
            m.rtol = rtol;
            m.atol = atol;
            if (error_wanted) {
                sum->passed++;
                fprintf(out, "line %d (%s): pass (error: %s)\n", lineno, name, error);
            } else if (!o || want_error) {
                char *got = o ? rf_formula_json_text(o) : NULL;
                sum->failed++;
                if (sum->worst < RF_FORMULA_FAILED)
                    sum->worst = RF_FORMULA_FAILED;
                if (want_error && o)
                    fprintf(out, "line %d (%s): FAIL expected an error, got %s\n", lineno, name, got ? got : "?");
                else
                    fprintf(out, "line %d (%s): %s %s\n", lineno, name ? name : "no id",
                            want_error ? "FAIL expected another error, got" : "ERROR", error);
                free(got);
            } else if (!expect) {
                sum->unchecked++;
                fprintf(out, "line %d (%s): not checked (no \"expect\")\n", lineno, name);
            } else {
                const cJSON *e;
                cJSON_ArrayForEach(e, expect)
                    compare(e, cJSON_GetObjectItemCaseSensitive(o, e->string), e->string, &m);
                if (m.count) {
                    sum->failed++;
                    if (sum->worst < RF_FORMULA_FAILED)
                        sum->worst = RF_FORMULA_FAILED;
                    fprintf(out, "line %d (%s): FAIL %s\n", lineno, name, m.text);
                } else {
                    sum->passed++;
                    fprintf(out, "line %d (%s): pass\n", lineno, name);
                }
            }
        } else if (table) {
            rf_formula_table_case(table, lineno, f, inputs, o, o ? NULL : error, opt->format, opt->digits);
        } else {
            cJSON *reply = cJSON_CreateObject();
            if (!o)
                cJSON_AddNumberToObject(reply, "line", lineno);
            if (name)
                cJSON_AddStringToObject(reply, "id", name);
            else
                cJSON_AddNullToObject(reply, "id");
            if (o)
                cJSON_AddItemToObject(reply, "out", o);
            else
                cJSON_AddStringToObject(reply, "error", error);
            o = NULL;
            char *text = rf_formula_json_text(reply);
            fprintf(out, "%s\n", text ? text : "{\"id\":null,\"error\":\"out of memory\"}");
            free(text);
            cJSON_Delete(reply);
        }
        fflush(out);
        cJSON_Delete(o);
        cJSON_Delete(c);
    }
    if (table) {
        rf_formula_table_print(table, opt->format, out);
        rf_formula_table_free(table);
    }
    if (sum->cases == 0) {
        if (opt->err)
            fprintf(opt->err, "%s: no cases (the batch is empty; one JSON line {\"id\":..., \"in\":{...}} per case)\n",
                    opt->name ? opt->name : "-");
        sum->worst = RF_FORMULA_BAD_LINE;
    }
    if (opt->check && sum->cases) {
        fprintf(out, "%d passed, %d failed", sum->passed, sum->failed);
        if (sum->unchecked)
            fprintf(out, ", %d not checked", sum->unchecked);
        fputc('\n', out);
    }
    return opt->check ? sum->failed : sum->errors;
}
