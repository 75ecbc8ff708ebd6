/* Results as a text table, Markdown or LaTeX (rounded with --digits; JSON stays exact), and
 * the help of a formula: its inputs, outputs and an example run live, so it cannot drift. */
#include "formula_internal.h"

#include <stdlib.h>
#include <string.h>

/* ---- values as text ---- */

/* A number: exact (digits < 0) or rounded to digits decimals with trailing zeros dropped. */
static void number_text(double v, int digits, RfFormulaFormat fmt, FILE *out)
{
    char t[400];
    if (digits < 0) {
        rf_formula_number_text(v, t, sizeof t);
    } else {
        snprintf(t, sizeof t, "%.*f", digits, v);
        if (strchr(t, '.')) {
            size_t n = strlen(t);
            while (t[n - 1] == '0')
                t[--n] = 0;
            if (t[n - 1] == '.')
                t[--n] = 0;
        }
        if (strcmp(t, "-0") == 0)
            strcpy(t, "0");
    }
    char *e = strchr(t, 'e');
    if (e && fmt == RF_FORMULA_LATEX) { /* 1e-17 -> 1 \cdot 10^{-17} */
        *e = 0;
        fprintf(out, "%s \\cdot 10^{%d}", t, atoi(e + 1));
        return;
    }
    fputs(t, out);
}

static void latex_text(const char *s, FILE *out)
{
    for (; *s; s++) {
        if (strchr("&%$#_{}", *s))
            fprintf(out, "\\%c", *s);
        else if (*s == '\\')
            fputs("\\textbackslash{}", out);
        else if (*s == '^' || *s == '~')
            fprintf(out, "\\%c{}", *s);
        else
            fputc(*s, out);
    }
}

static void word_text(const char *s, RfFormulaFormat fmt, FILE *out)
{
    if (fmt != RF_FORMULA_LATEX) {
        fputs(s, out);
        return;
    }
    fputs("\\text{", out);
    latex_text(s, out);
    fputc('}', out);
}

/* A value of an input or output. Vectors read (1, 2, 3), matrices [[1, 2], [3, 4]]; in LaTeX
 * (math mode) outputs are column vectors and matrices in pmatrix, inputs stay on one line. */
static void value_text(const cJSON *v, RfFormulaFormat fmt, int digits, int one_line, FILE *out)
{
    const cJSON *e;
    if (cJSON_IsNumber(v)) {
        number_text(v->valuedouble, digits, fmt, out);
    } else if (cJSON_IsBool(v)) {
        word_text(cJSON_IsTrue(v) ? "true" : "false", fmt, out);
    } else if (cJSON_IsString(v)) {
        word_text(v->valuestring, fmt, out);
    } else if (cJSON_IsArray(v)) {
        int matrix = cJSON_IsArray(cJSON_GetArrayItem(v, 0)), first = 1;
        int pm = fmt == RF_FORMULA_LATEX && !one_line;
        fputs(pm ? "\\begin{pmatrix}" : matrix ? "[" : "(", out);
        cJSON_ArrayForEach(e, v) {
            if (!first)
                fputs(pm ? " \\\\ " : ", ", out);
            first = 0;
            if (matrix) { /* a row: [1, 2], or in pmatrix 1 & 2 */
                const cJSON *x;
                int k = 0;
                fputs(pm ? "" : "[", out);
                cJSON_ArrayForEach(x, e) {
                    fputs(k++ ? (pm ? " & " : ", ") : "", out);
                    value_text(x, fmt, digits, one_line, out);
                }
                fputs(pm ? "" : "]", out);
            } else {
                value_text(e, fmt, digits, one_line, out);
            }
        }
        fputs(pm ? "\\end{pmatrix}" : matrix ? "]" : ")", out);
    } else {
        word_text("none", fmt, out); /* null: the value does not exist */
    }
}

/* ---- tables ---- */

struct RfFormulaTable {
    int batch;     /* columns line, id, inputs, output, value; else output, value */
    char **cells;
    size_t n, cap;
};

RfFormulaTable *rf_formula_table_new(int batch)
{
    RfFormulaTable *t = calloc(1, sizeof *t);
    if (t)
        t->batch = batch;
    return t;
}

void rf_formula_table_free(RfFormulaTable *t)
{
    if (!t)
        return;
    for (size_t i = 0; i < t->n; i++)
        free(t->cells[i]);
    free(t->cells);
    free(t);
}

static int columns(const RfFormulaTable *t) { return t->batch ? 5 : 2; }

/* Appends one cell; text is taken over (NULL: out of memory, the cell stays empty). */
static void add_cell(RfFormulaTable *t, char *text)
{
    if (!text && !(text = calloc(1, 1)))
        return;
    if (t->n == t->cap) {
        size_t cap = t->cap ? 2 * t->cap : 64;
        char **c = realloc(t->cells, cap * sizeof *c);
        if (!c) {
            free(text);
            return;
        }
        t->cells = c;
        t->cap = cap;
    }
    t->cells[t->n++] = text;
}

/* A cell written with stdio: open, write, close (the text becomes the cell). */
typedef struct {
    char *text;
    size_t len;
    FILE *f;
} Cell;

/* NULL when out of memory: the caller adds an empty cell instead */
static FILE *cell_open(Cell *c)
{
    c->text = NULL;
    c->f = open_memstream(&c->text, &c->len);
    return c->f;
}

static void cell_close(RfFormulaTable *t, Cell *c)
{
    if (c->f)
        fclose(c->f);
    add_cell(t, c->text);
}

static void cell_str(RfFormulaTable *t, const char *s, RfFormulaFormat fmt, int code)
{
    Cell c;
    FILE *f = cell_open(&c);
    if (!f) {
        add_cell(t, NULL);
        return;
    }
    if (fmt == RF_FORMULA_LATEX && code && *s) {
        fputs("\\texttt{", f);
        latex_text(s, f);
        fputc('}', f);
    } else if (fmt == RF_FORMULA_LATEX) {
        latex_text(s, f);
    } else {
        fputs(s, f);
    }
    cell_close(t, &c);
}

static void cell_value(RfFormulaTable *t, const cJSON *v, RfFormulaFormat fmt, int digits, int one_line)
{
    Cell c;
    FILE *f = cell_open(&c);
    if (!f) {
        add_cell(t, NULL);
        return;
    }
    if (fmt == RF_FORMULA_LATEX)
        fputc('$', f);
    value_text(v, fmt, digits, one_line, f);
    if (fmt == RF_FORMULA_LATEX)
        fputc('$', f);
    cell_close(t, &c);
}

/* The inputs of a case on one line: "a=(1, 2), kind=scale" (exact, as given). */
static void cell_inputs(RfFormulaTable *t, const cJSON *in, RfFormulaFormat fmt)
{
    Cell c;
    FILE *f = cell_open(&c);
    if (!f) {
        add_cell(t, NULL);
        return;
    }
    const cJSON *e;
    int first = 1;
    cJSON_ArrayForEach(e, in) {
        /* an input written as on the command line ("1,2;3,4") is shown as the numbers it is */
        cJSON *parsed = cJSON_IsString(e) ? rf_formula_value_json(e->valuestring) : NULL;
        const cJSON *v = parsed && !cJSON_IsString(parsed) ? parsed : e;
        if (!first)
            fputs(", ", f);
        first = 0;
        if (fmt == RF_FORMULA_LATEX) {
            fputs("\\texttt{", f);
            latex_text(e->string, f);
            fputs("} = $", f);
            value_text(v, fmt, -1, 1, f);
            fputc('$', f);
        } else {
            fprintf(f, "%s=", e->string);
            value_text(v, fmt, -1, 1, f);
        }
        cJSON_Delete(parsed);
    }
    cell_close(t, &c);
}

void rf_formula_table_case(RfFormulaTable *t, int line, const RfFormula *f, const cJSON *in,
                           const cJSON *out, const char *error, RfFormulaFormat fmt, int digits)
{
    const cJSON *e;
    int first = 1;
    char num[32];
    if (!t)
        return;
    /* one row per output (or one for the error); line, id and inputs on the first only */
    for (e = out ? out->child : NULL;; e = e->next) {
        if (t->batch) {
            snprintf(num, sizeof num, "%d", line);
            cell_str(t, first ? num : "", fmt, 0);
            cell_str(t, first && f ? f->id : "", fmt, 1);
            if (first && cJSON_IsObject(in))
                cell_inputs(t, in, fmt);
            else
                cell_str(t, "", fmt, 0);
        }
        first = 0;
        if (!out) {
            cell_str(t, "error", fmt, 0);
            cell_str(t, error ? error : "", fmt, 0);
            break;
        }
        if (!e)
            break;
        cell_str(t, e->string, fmt, 1);
        cell_value(t, e, fmt, digits, 0);
        if (!e->next)
            break;
    }
}

/* The display width of UTF-8 text (code points). */
static size_t width(const char *s)
{
    size_t w = 0;
    for (; *s; s++)
        w += ((unsigned char)*s & 0xC0) != 0x80;
    return w;
}

void rf_formula_table_print(const RfFormulaTable *t, RfFormulaFormat fmt, FILE *out)
{
    static const char *const head_batch[] = {"line", "id", "inputs", "output", "value"};
    static const char *const head_one[] = {"output", "value"};
    const char *const *head = t->batch ? head_batch : head_one;
    int nc = columns(t);
    size_t rows = t->n / (size_t)nc, w[5] = {0};
    for (int k = 0; k < nc; k++)
        w[k] = width(head[k]);
    for (size_t i = 0; i < t->n; i++)
        if (width(t->cells[i]) > w[i % (size_t)nc])
            w[i % (size_t)nc] = width(t->cells[i]);
    if (fmt == RF_FORMULA_LATEX) {
        fprintf(out, "\\begin{tabular}{%s}\n\\hline\n", t->batch ? "rllll" : "ll");
        for (int k = 0; k < nc; k++)
            fprintf(out, "%s%s", head[k], k + 1 < nc ? " & " : " \\\\\n\\hline\n");
        for (size_t r = 0; r < rows; r++)
            for (int k = 0; k < nc; k++)
                fprintf(out, "%s%s", t->cells[r * (size_t)nc + (size_t)k], k + 1 < nc ? " & " : " \\\\\n");
        fputs("\\hline\n\\end{tabular}\n", out);
        return;
    }
    int md = fmt == RF_FORMULA_MARKDOWN;
    for (size_t r = 0; r < rows + 2; r++) {
        for (int k = 0; k < nc; k++) {
            const char *s = r == 0 ? head[k] : r == 1 ? NULL : t->cells[(r - 2) * (size_t)nc + (size_t)k];
            int last = k + 1 == nc;
            if (md)
                fputs(k ? " | " : "| ", out);
            else if (k)
                fputs("  ", out);
            if (!s) { /* the rule under the header */
                for (size_t i = 0; i < w[k]; i++)
                    fputc('-', out);
            } else {
                for (const char *c = s; *c; c++) /* '|' would end a Markdown cell */
                    fputs(md && *c == '|' ? "\\|" : (char[]){*c, 0}, out);
                if (!last || md)
                    for (size_t i = width(s); i < w[k]; i++)
                        fputc(' ', out);
            }
        }
        fputs(md ? " |\n" : "\n", out);
    }
}

void rf_formula_print(const RfFormula *f, const char *out_json, RfFormulaFormat format, int digits, FILE *out)
{
    cJSON *o = format == RF_FORMULA_JSON ? NULL : cJSON_Parse(out_json);
    RfFormulaTable *t = o ? rf_formula_table_new(0) : NULL;
    if (!t) {
        fprintf(out, "%s\n", out_json);
        cJSON_Delete(o);
        return;
    }
    rf_formula_table_case(t, 0, f, NULL, o, NULL, format, digits);
    rf_formula_table_print(t, format, out);
    rf_formula_table_free(t);
    cJSON_Delete(o);
}

/* ---- help ---- */

/* What a kind takes, in words, with the unit its name implies. */
static void kind_text(const RfFormulaItem *it, int input, FILE *out)
{
    char dims[64] = "", sizes[64] = ""; /* "2 or 3", "2x2 or 3x3" */
    int k = 0, count = 0;
    for (int d = 2; d <= 4; d++)
        count += (it->dims >> d) & 1u;
    for (int d = 2; d <= 4; d++)
        if ((it->dims >> d) & 1u) {
            const char *sep = k == 0 ? "" : k == count - 1 ? " or " : ", ";
            size_t len = strlen(dims), ls = strlen(sizes);
            snprintf(dims + len, sizeof dims - len, "%s%d", sep, d);
            snprintf(sizes + ls, sizeof sizes - ls, "%s%dx%d", sep, d, d);
            k++;
        }
    const char *unit = strstr(it->name, "_deg") ? " (degrees)" : strstr(it->name, "_nm") ? " (nm)"
                     : strstr(it->name, "_hz") ? " (Hz)" : "";
    if (strchr(it->kind, '|')) {
        fputs("one of: ", out);
        for (const char *c = it->kind; *c; c++)
            fputs(*c == '|' ? ", " : (char[]){*c, 0}, out);
    } else if (strcmp(it->kind, "rgb") == 0)
        fputs(input ? "colour r,g,b (one number v: the grey v,v,v)" : "colour r,g,b", out);
    else if (strncmp(it->kind, "vecs", 4) == 0)
        fprintf(out, "list of vectors of %s numbers", dims);
    else if (strncmp(it->kind, "vec", 3) == 0)
        fprintf(out, input ? "vector of %s numbers" : "vector", dims);
    else if (strncmp(it->kind, "mat", 3) == 0)
        fprintf(out, input ? "matrix %s" : "matrix", sizes);
    else if (strcmp(it->kind, "num") == 0)
        fprintf(out, "number%s", unit);
    else if (strcmp(it->kind, "int") == 0)
        fputs("integer", out);
    else if (strcmp(it->kind, "bool") == 0)
        fputs("true or false", out);
    else if (strcmp(it->kind, "nums") == 0)
        fprintf(out, "list of numbers%s", unit);
    else if (strcmp(it->kind, "tris") == 0)
        fputs("list of triangles [[a,b,c], ...] of 3D points", out);
    else
        fputs(it->kind, out);
}

static void help_spec(const char *title, const char *spec, int input, FILE *out)
{
    RfFormulaItem it;
    fprintf(out, "%s:\n", title);
    for (int i = 0; rf_formula_item(spec, i, &it); i++) {
        fprintf(out, "  %-15s ", it.name);
        kind_text(&it, input, out);
        if (it.has_def)
            fprintf(out, "; default %s", it.def);
        else if (it.optional)
            fputs("; optional", out);
        fprintf(out, "\n  %15s %s\n", "", it.note);
    }
}

/* The example's arguments (split at blanks) run through the command-line front end. */
static void help_example(const RfFormula *f, FILE *out)
{
    char buf[1024], *argv[32], err[512];
    int argc = 0;
    snprintf(buf, sizeof buf, "%s", f->example ? f->example : "");
    for (char *tok = strtok(buf, " "); tok && argc < 32; tok = strtok(NULL, " "))
        argv[argc++] = tok;
    fprintf(out, "example:\n  $ refray formula %s", f->id);
    for (int i = 0; i < argc; i++) /* quoted as a shell needs it */
        fprintf(out, strpbrk(argv[i], ";[]{}\" ") ? " '%s'" : " %s", argv[i]);
    fputc('\n', out);
    char *in = rf_formula_args_to_json(argc, argv, err, sizeof err), *res = NULL;
    int rc = in ? rf_formula_run_json(f, in, &res) : RF_FORMULA_BAD_INPUT;
    fprintf(out, "  %s%s\n", rc ? "(the example fails) " : "", in ? (res ? res : "out of memory") : err);
    free(in);
    free(res);
}

void rf_formula_help(const RfFormula *f, FILE *out)
{
    fprintf(out, "%s (script section %s)\n  %s\n", f->id, f->section, f->summary);
    help_spec("inputs", f->inputs, 1, out);
    help_spec("outputs", f->outputs, 0, out);
    if (f->erratum)
        fprintf(out, "erratum of the script:\n  %s\n", f->erratum);
    help_example(f, out);
}

void rf_formula_reference(FILE *out)
{
    fputs("# `refray formula`: every formula\n\n"
          "Made by `refray formula --reference` from the formula table (src/formula/f_*.c); the test\n"
          "`formula_reference_current` keeps this file equal to it. The same text for one id:\n"
          "`refray formula ID --help`. Every example's output was computed by running it.\n\n"
          "Conventions: vectors `1,2,3`, matrices `1,2;3,4` (rows) or nested JSON arrays; angles in\n"
          "degrees (names ending in `_deg`), wavelengths in nm (`_nm`); a number where a colour is\n"
          "expected is the grey (v,v,v); a vector or matrix of a length (size) the input does not take\n"
          "is an error, never padded or cut. `null` in an output: the value does not exist.\n",
          out);
    for (size_t i = 0; i < rf_formula_count(); i++) {
        const RfFormula *f = rf_formula_at(i);
        fprintf(out, "\n## %s\n\n```\n", f->id);
        rf_formula_help(f, out);
        fputs("```\n", out);
    }
}
