/* The formula registry: input parsing and validation against each entry's spec, JSON output,
 * the command-line and batch front ends. The formulas themselves live in the f_*.c files. */
#include "refray/formula.h"

#include <cJSON.h>
#include <ctype.h>
#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "refray/mat.h"

struct RfFormulaCall {
    const RfFormula *formula;
    cJSON *in;
    cJSON *out;
    cJSON *defaults; /* parsed defaults of the spec, built on demand */
    char error[512];
    int failed;
};

/* ---- registry ---- */

static const RfFormula *const tables[] = {
    rf_formulas_color, rf_formulas_geometry, rf_formulas_raytrace, rf_formulas_transform,
};

size_t rf_formula_count(void)
{
    size_t n = 0;
    for (size_t t = 0; t < sizeof tables / sizeof tables[0]; t++)
        for (const RfFormula *f = tables[t]; f->id; f++)
            n++;
    return n;
}

const RfFormula *rf_formula_at(size_t index)
{
    for (size_t t = 0; t < sizeof tables / sizeof tables[0]; t++)
        for (const RfFormula *f = tables[t]; f->id; f++)
            if (index-- == 0)
                return f;
    return NULL;
}

const RfFormula *rf_formula_find(const char *id)
{
    for (size_t t = 0; t < sizeof tables / sizeof tables[0]; t++)
        for (const RfFormula *f = tables[t]; f->id; f++)
            if (strcmp(f->id, id) == 0)
                return f;
    return NULL;
}

/* ---- specs ---- */

/* One parsed item of a spec: "name:kind=default", "name:kind?" or "name:kind", optionally
 * followed by a note after a space ("unit:vec (null for the zero vector)"). */
typedef struct {
    char name[48], kind[16], def[160], note[200];
    int has_def, optional;
} SpecItem;

static void copy_trimmed(char *dst, size_t cap, const char *s, const char *end)
{
    while (s < end && *s == ' ')
        s++;
    while (end > s && end[-1] == ' ')
        end--;
    size_t n = (size_t)(end - s);
    if (n >= cap)
        n = cap - 1;
    memcpy(dst, s, n);
    dst[n] = 0;
}

/* Parses the item that starts at *p and advances *p past it; returns 0 at the end. */
static int spec_next(const char **p, SpecItem *it)
{
    const char *s = *p;
    while (*s == ' ' || *s == ';')
        s++;
    if (!*s)
        return 0;
    const char *end = strchr(s, ';');
    if (!end)
        end = s + strlen(s);
    *p = end;
    memset(it, 0, sizeof *it);
    const char *colon = memchr(s, ':', (size_t)(end - s));
    const char *name_end = colon ? colon : end;
    copy_trimmed(it->name, sizeof it->name, s, name_end);
    if (!colon)
        return 1;
    /* the kind is one word; '?' or '=default' may follow it directly; the rest is a note */
    const char *k = colon + 1, *q = k;
    while (q < end && *q != ' ' && *q != '?' && *q != '=')
        q++;
    copy_trimmed(it->kind, sizeof it->kind, k, q);
    if (q < end && *q == '?') {
        it->optional = 1;
        q++;
    } else if (q < end && *q == '=') {
        const char *d = ++q;
        while (q < end && *q != ' ')
            q++;
        copy_trimmed(it->def, sizeof it->def, d, q);
        it->has_def = 1;
        it->optional = 1;
    }
    copy_trimmed(it->note, sizeof it->note, q, end);
    return 1;
}

static int spec_find(const char *spec, const char *name, SpecItem *it)
{
    const char *p = spec ? spec : "";
    while (spec_next(&p, it))
        if (strcmp(it->name, name) == 0)
            return 1;
    return 0;
}

/* ---- JSON output ----
 * cJSON's own printer decides that a number "round-trips" when the reparsed value is within
 * DBL_EPSILON relative (cJSON 1.7.15), so 0.30000000000000004 would print as 0.3. The contract
 * needs exact round trips: this printer writes the shortest of %.15g, %.16g, %.17g that reads
 * back as the same double. */

typedef struct {
    char *data;
    size_t len, cap;
    int oom;
} TextBuf;

static void buf_put(TextBuf *b, const char *s, size_t n)
{
    if (b->oom)
        return;
    if (b->len + n + 1 > b->cap) {
        size_t cap = b->cap ? b->cap : 256;
        while (cap < b->len + n + 1)
            cap *= 2;
        char *d = realloc(b->data, cap);
        if (!d) {
            b->oom = 1;
            return;
        }
        b->data = d;
        b->cap = cap;
    }
    memcpy(b->data + b->len, s, n);
    b->len += n;
    b->data[b->len] = 0;
}

static void buf_str(TextBuf *b, const char *s) { buf_put(b, s, strlen(s)); }

static void print_number(TextBuf *b, double v)
{
    char text[40];
    for (int digits = 15; digits <= 17; digits++) {
        snprintf(text, sizeof text, "%.*g", digits, v);
        if (strtod(text, NULL) == v)
            break;
    }
    buf_str(b, text);
}

static void print_json(TextBuf *b, const cJSON *j)
{
    const cJSON *e;
    if (cJSON_IsNumber(j)) {
        print_number(b, j->valuedouble);
    } else if (cJSON_IsBool(j)) {
        buf_str(b, cJSON_IsTrue(j) ? "true" : "false");
    } else if (cJSON_IsString(j)) {
        char *quoted = cJSON_PrintUnformatted(j); /* cJSON escapes strings correctly */
        buf_str(b, quoted ? quoted : "\"\"");
        free(quoted);
    } else if (cJSON_IsArray(j) || cJSON_IsObject(j)) {
        int first = 1, obj = cJSON_IsObject(j);
        buf_str(b, obj ? "{" : "[");
        cJSON_ArrayForEach(e, j) {
            if (!first)
                buf_str(b, ",");
            first = 0;
            if (obj) {
                cJSON key;
                memset(&key, 0, sizeof key);
                key.type = cJSON_String;
                key.valuestring = e->string;
                print_json(b, &key);
                buf_str(b, ":");
            }
            print_json(b, e);
        }
        buf_str(b, obj ? "}" : "]");
    } else {
        buf_str(b, "null");
    }
}

char *rf_formula_json_text(const struct cJSON *j)
{
    TextBuf b = {NULL, 0, 0, 0};
    print_json(&b, j);
    if (b.oom) {
        free(b.data);
        return NULL;
    }
    return b.data;
}

/* ---- command-line values -> JSON ---- */

/* Parses s (length n) as one finite number; returns 1 on success. */
static int parse_number(const char *s, size_t n, double *v)
{
    char buf[128];
    char *end;
    while (n > 0 && isspace((unsigned char)*s))
        s++, n--;
    while (n > 0 && isspace((unsigned char)s[n - 1]))
        n--;
    if (n == 0 || n >= sizeof buf)
        return 0;
    memcpy(buf, s, n);
    buf[n] = 0;
    /* strtod also takes "nan", "inf" and hex floats: accept plain decimal numbers only */
    for (size_t i = 0; i < n; i++)
        if (!strchr("0123456789+-.eE", buf[i]))
            return 0;
    *v = strtod(buf, &end);
    return *end == 0 && isfinite(*v);
}

/* "1,2,3" -> [1,2,3]; "1,2;3,4" -> [[1,2],[3,4]]; "5" -> 5. NULL if not numbers. */
static cJSON *numbers_to_json(const char *s)
{
    int rows = strchr(s, ';') != NULL;
    int list = rows || strchr(s, ',') != NULL;
    double v;
    if (!list)
        return parse_number(s, strlen(s), &v) ? cJSON_CreateNumber(v) : NULL;
    cJSON *outer = cJSON_CreateArray();
    const char *row = s;
    for (;;) {
        const char *row_end = strchr(row, ';');
        if (!row_end)
            row_end = row + strlen(row);
        cJSON *arr = rows ? cJSON_CreateArray() : outer;
        const char *p = row;
        for (;;) {
            const char *q = memchr(p, ',', (size_t)(row_end - p));
            const char *e = q ? q : row_end;
            if (!parse_number(p, (size_t)(e - p), &v)) {
                if (rows)
                    cJSON_Delete(arr);
                cJSON_Delete(outer);
                return NULL;
            }
            cJSON_AddItemToArray(arr, cJSON_CreateNumber(v));
            if (!q)
                break;
            p = q + 1;
        }
        if (rows)
            cJSON_AddItemToArray(outer, arr);
        if (!*row_end)
            break;
        row = row_end + 1;
    }
    return outer;
}

static cJSON *value_to_json(const char *s)
{
    if (strcmp(s, "true") == 0)
        return cJSON_CreateTrue();
    if (strcmp(s, "false") == 0)
        return cJSON_CreateFalse();
    if (strcmp(s, "null") == 0)
        return cJSON_CreateNull();
    if (*s == '[' || *s == '{')
        return cJSON_ParseWithOpts(s, NULL, 1); /* 1: nothing may follow the value */
    cJSON *num = numbers_to_json(s);
    if (num)
        return num;
    /* non-finite numbers are refused, whatever their spelling */
    if (strpbrk(s, ",;") || strncasecmp(s, "nan", 3) == 0 || strncasecmp(s, "inf", 3) == 0 ||
        strncasecmp(s, "-inf", 4) == 0 || strncasecmp(s, "+inf", 4) == 0)
        return NULL;
    /* a word; something that starts like a number but did not parse is an error */
    if (*s == 0 || strchr("0123456789+-.", *s))
        return NULL;
    return cJSON_CreateString(s);
}

char *rf_formula_args_to_json(int argc, char **argv, char *err, size_t err_size)
{
    cJSON *obj = cJSON_CreateObject();
    for (int i = 0; i < argc; i++) {
        const char *eq = strchr(argv[i], '=');
        if (!eq || eq == argv[i]) {
            snprintf(err, err_size, "argument '%s' is not of the form key=value", argv[i]);
            cJSON_Delete(obj);
            return NULL;
        }
        char key[64];
        size_t kn = (size_t)(eq - argv[i]);
        if (kn >= sizeof key)
            kn = sizeof key - 1;
        memcpy(key, argv[i], kn);
        key[kn] = 0;
        if (cJSON_GetObjectItemCaseSensitive(obj, key)) {
            snprintf(err, err_size, "input '%s' is given twice", key);
            cJSON_Delete(obj);
            return NULL;
        }
        cJSON *v = value_to_json(eq + 1);
        if (!v) {
            snprintf(err, err_size, "input '%s': cannot read '%s' (numbers must be finite decimals)",
                     key, eq + 1);
            cJSON_Delete(obj);
            return NULL;
        }
        cJSON_AddItemToObject(obj, key, v);
    }
    char *text = rf_formula_json_text(obj);
    cJSON_Delete(obj);
    return text;
}

/* ---- calls ---- */

int rf_call_error(RfFormulaCall *call, const char *fmt, ...)
{
    if (!call->failed) { /* keep the first error: it is the cause */
        va_list ap;
        va_start(ap, fmt);
        vsnprintf(call->error, sizeof call->error, fmt, ap);
        va_end(ap);
        call->failed = 1;
    }
    return 1;
}

/* The JSON item of an input, its default when absent, or NULL (optional without default).
 * Sets an error for a missing required input or an input the formula does not take. */
static const cJSON *input_item(RfFormulaCall *call, const char *name, int *err)
{
    SpecItem it;
    *err = 0;
    if (!spec_find(call->formula->inputs, name, &it)) {
        *err = rf_call_error(call, "internal: input '%s' is not in the spec of %s", name,
                             call->formula->id);
        return NULL;
    }
    const cJSON *v = cJSON_GetObjectItemCaseSensitive(call->in, name);
    if (v && !cJSON_IsNull(v))
        return v;
    if (it.has_def) {
        if (!call->defaults)
            call->defaults = cJSON_CreateObject();
        cJSON *d = cJSON_GetObjectItemCaseSensitive(call->defaults, name);
        if (!d) {
            d = value_to_json(it.def);
            if (!d) {
                *err = rf_call_error(call, "internal: bad default '%s' for %s", it.def, name);
                return NULL;
            }
            cJSON_AddItemToObject(call->defaults, name, d);
        }
        return d;
    }
    if (!it.optional)
        *err = rf_call_error(call, "missing input '%s'", name);
    return NULL;
}

int rf_in_has(RfFormulaCall *call, const char *name)
{
    const cJSON *v = cJSON_GetObjectItemCaseSensitive(call->in, name);
    return v && !cJSON_IsNull(v);
}

static int json_num(RfFormulaCall *call, const char *name, const cJSON *v, double *out)
{
    if (!cJSON_IsNumber(v))
        return rf_call_error(call, "input '%s' must be a number", name);
    if (!isfinite(v->valuedouble))
        return rf_call_error(call, "input '%s' is not finite", name);
    *out = v->valuedouble;
    return 0;
}

int rf_in_num(RfFormulaCall *call, const char *name, double *v)
{
    int err;
    const cJSON *it = input_item(call, name, &err);
    if (err)
        return 1;
    if (!it)
        return rf_call_error(call, "internal: optional number '%s' needs a default", name);
    return json_num(call, name, it, v);
}

int rf_in_angle(RfFormulaCall *call, const char *name, double *radians)
{
    double deg;
    if (rf_in_num(call, name, &deg))
        return 1;
    *radians = deg * (RF_PI / 180.0);
    return 0;
}

int rf_in_int(RfFormulaCall *call, const char *name, long *v)
{
    double d;
    if (rf_in_num(call, name, &d))
        return 1;
    if (d != floor(d) || fabs(d) > 9.0e15)
        return rf_call_error(call, "input '%s' must be an integer", name);
    *v = (long)d;
    return 0;
}

int rf_in_bool(RfFormulaCall *call, const char *name, int *v)
{
    int err;
    const cJSON *it = input_item(call, name, &err);
    if (err)
        return 1;
    if (!it || !cJSON_IsBool(it))
        return rf_call_error(call, "input '%s' must be true or false", name);
    *v = cJSON_IsTrue(it);
    return 0;
}

/* Reads a JSON array of numbers into v (at most max); returns the count or -1. */
static int json_numbers(const cJSON *arr, double *v, int max)
{
    int n = 0;
    const cJSON *e;
    if (!cJSON_IsArray(arr))
        return -1;
    cJSON_ArrayForEach(e, arr) {
        if (!cJSON_IsNumber(e) || !isfinite(e->valuedouble) || n >= max)
            return -1;
        v[n++] = e->valuedouble;
    }
    return n;
}

int rf_in_vec(RfFormulaCall *call, const char *name, int dim, double *v, int *dim_out)
{
    int err;
    const cJSON *it = input_item(call, name, &err);
    if (err)
        return 1;
    if (!it)
        return rf_call_error(call, "internal: optional vector '%s' needs a default", name);
    /* into a buffer of the largest size first: v holds only dim numbers when dim is given */
    double buf[4];
    int n = json_numbers(it, buf, 4);
    if (dim ? n != dim : (n < 2 || n > 4)) {
        if (dim)
            return rf_call_error(call, "input '%s' must be a vector of %d finite numbers", name, dim);
        return rf_call_error(call, "input '%s' must be a vector of 2 to 4 finite numbers", name);
    }
    memcpy(v, buf, sizeof(double) * (size_t)n);
    if (dim_out)
        *dim_out = n;
    return 0;
}

int rf_in_vec3(RfFormulaCall *call, const char *name, RfVec3 *v)
{
    double a[4] = {0, 0, 0, 0};
    int n = 0;
    if (rf_in_vec(call, name, 0, a, &n))
        return 1;
    if (n == 4)
        return rf_call_error(call, "input '%s' must be a 2D or 3D vector", name);
    *v = rf_vec3(a[0], a[1], a[2]);
    return 0;
}

int rf_in_mat(RfFormulaCall *call, const char *name, int n, double *m, int *n_out)
{
    int err;
    const cJSON *it = input_item(call, name, &err);
    if (err)
        return 1;
    if (!it || !cJSON_IsArray(it))
        return rf_call_error(call, "input '%s' must be a matrix (rows, or a flat row-major list)", name);
    int size = cJSON_GetArraySize(it), got = -1;
    if (size > 0 && cJSON_IsArray(cJSON_GetArrayItem(it, 0))) {
        /* a list of rows, each as long as there are rows */
        got = size;
        int r = 0;
        const cJSON *row;
        cJSON_ArrayForEach(row, it) {
            if (r >= RF_MATN_MAX || json_numbers(row, m + r * size, RF_MATN_MAX) != size) {
                got = -1;
                break;
            }
            r++;
        }
    } else {
        double flat[RF_MATN_MAX * RF_MATN_MAX];
        int k = json_numbers(it, flat, RF_MATN_MAX * RF_MATN_MAX);
        for (int s = 2; s <= RF_MATN_MAX; s++)
            if (k == s * s) {
                got = s;
                memcpy(m, flat, sizeof(double) * (size_t)k);
            }
    }
    if (got < 2 || got > RF_MATN_MAX || (n && got != n)) {
        if (n)
            return rf_call_error(call, "input '%s' must be a %dx%d matrix of finite numbers", name, n, n);
        return rf_call_error(call, "input '%s' must be a square matrix of finite numbers, 2x2 to 4x4", name);
    }
    if (n_out)
        *n_out = got;
    return 0;
}

int rf_in_nums(RfFormulaCall *call, const char *name, double **v, int *count)
{
    int err;
    const cJSON *it = input_item(call, name, &err);
    if (err)
        return 1;
    if (!it)
        return rf_call_error(call, "missing input '%s'", name);
    if (cJSON_IsNumber(it)) { /* a single number is a list of one */
        *v = malloc(sizeof(double));
        if (!*v)
            return rf_call_error(call, "out of memory");
        *count = 1;
        return json_num(call, name, it, *v);
    }
    int size = cJSON_IsArray(it) ? cJSON_GetArraySize(it) : -1;
    if (size < 1)
        return rf_call_error(call, "input '%s' must be a non-empty list of numbers", name);
    *v = malloc(sizeof(double) * (size_t)size);
    if (!*v)
        return rf_call_error(call, "out of memory");
    if (json_numbers(it, *v, size) != size) {
        free(*v);
        *v = NULL;
        return rf_call_error(call, "input '%s' must be a list of finite numbers", name);
    }
    *count = size;
    return 0;
}

int rf_in_vecs(RfFormulaCall *call, const char *name, int dim, int max, double *v, int *count,
               int *dim_out)
{
    int err;
    const cJSON *it = input_item(call, name, &err);
    if (err)
        return 1;
    if (!it || !cJSON_IsArray(it) || cJSON_GetArraySize(it) < 1)
        return rf_call_error(call, "input '%s' must be a list of vectors", name);
    if (cJSON_GetArraySize(it) > max)
        return rf_call_error(call, "input '%s' has more than %d vectors", name, max);
    int n = 0, d = dim;
    const cJSON *e;
    cJSON_ArrayForEach(e, it) {
        double tmp[4];
        int k = json_numbers(e, tmp, 4);
        if (d == 0 && k >= 2)
            d = k;
        if (k != d || k < 2)
            return rf_call_error(call, "input '%s': every vector must have %s components", name,
                                 dim ? (dim == 2 ? "2" : dim == 3 ? "3" : "4") : "the same number of (2 to 4)");
        memcpy(v + n * d, tmp, sizeof(double) * (size_t)d);
        n++;
    }
    *count = n;
    if (dim_out)
        *dim_out = d;
    return 0;
}

int rf_in_tris(RfFormulaCall *call, const char *name, int max, double *corners, int *count)
{
    int err;
    const cJSON *it = input_item(call, name, &err);
    if (err)
        return 1;
    if (!it || !cJSON_IsArray(it) || cJSON_GetArraySize(it) < 1)
        return rf_call_error(call, "input '%s' must be a list of triangles [[a,b,c], ...]", name);
    if (cJSON_GetArraySize(it) > max)
        return rf_call_error(call, "input '%s' has more than %d triangles", name, max);
    int n = 0;
    const cJSON *tri, *corner;
    cJSON_ArrayForEach(tri, it) {
        int k = 0;
        if (!cJSON_IsArray(tri) || cJSON_GetArraySize(tri) != 3)
            return rf_call_error(call, "input '%s': each triangle is three 3D points [a,b,c]", name);
        cJSON_ArrayForEach(corner, tri) {
            if (json_numbers(corner, corners + 9 * n + 3 * k, 3) != 3)
                return rf_call_error(call, "input '%s': each corner must be 3 finite numbers", name);
            k++;
        }
        n++;
    }
    *count = n;
    return 0;
}

int rf_in_choice(RfFormulaCall *call, const char *name, const char *choices, int *index)
{
    int err;
    const cJSON *it = input_item(call, name, &err);
    if (err)
        return 1;
    if (!it || !cJSON_IsString(it))
        return rf_call_error(call, "input '%s' must be one of %s", name, choices);
    const char *w = it->valuestring, *p = choices;
    size_t wn = strlen(w);
    for (int i = 0;; i++) {
        const char *bar = strchr(p, '|');
        size_t n = bar ? (size_t)(bar - p) : strlen(p);
        if (n == wn && strncmp(p, w, n) == 0) {
            *index = i;
            return 0;
        }
        if (!bar)
            break;
        p = bar + 1;
    }
    return rf_call_error(call, "input '%s' must be one of %s, not '%s'", name, choices, w);
}

void rf_out_num(RfFormulaCall *call, const char *name, double v)
{
    if (!isfinite(v)) {
        rf_call_error(call, "output '%s' is not finite", name);
        return;
    }
    cJSON_AddItemToObject(call->out, name, cJSON_CreateNumber(v == 0.0 ? 0.0 : v));
}

void rf_out_bool(RfFormulaCall *call, const char *name, int v)
{
    cJSON_AddItemToObject(call->out, name, cJSON_CreateBool(v));
}

void rf_out_null(RfFormulaCall *call, const char *name)
{
    cJSON_AddItemToObject(call->out, name, cJSON_CreateNull());
}

void rf_out_str(RfFormulaCall *call, const char *name, const char *v)
{
    cJSON_AddItemToObject(call->out, name, cJSON_CreateString(v));
}

static cJSON *number_array(RfFormulaCall *call, const char *name, const double *v, int n)
{
    cJSON *a = cJSON_CreateArray();
    for (int i = 0; i < n; i++) {
        if (!isfinite(v[i]))
            rf_call_error(call, "output '%s' is not finite", name);
        cJSON_AddItemToArray(a, cJSON_CreateNumber(v[i] == 0.0 ? 0.0 : v[i]));
    }
    return a;
}

void rf_out_vec(RfFormulaCall *call, const char *name, const double *v, int dim)
{
    cJSON_AddItemToObject(call->out, name, number_array(call, name, v, dim));
}

void rf_out_vec3(RfFormulaCall *call, const char *name, RfVec3 v)
{
    double a[3] = {v.x, v.y, v.z};
    rf_out_vec(call, name, a, 3);
}

void rf_out_mat(RfFormulaCall *call, const char *name, const double *m, int n)
{
    cJSON *rows = cJSON_CreateArray();
    for (int r = 0; r < n; r++)
        cJSON_AddItemToArray(rows, number_array(call, name, m + r * n, n));
    cJSON_AddItemToObject(call->out, name, rows);
}

/* Runs f on the parsed inputs; returns the output object or NULL with call.error set. */
static cJSON *run(const RfFormula *f, cJSON *in, char *error, size_t error_size)
{
    RfFormulaCall call;
    memset(&call, 0, sizeof call);
    call.formula = f;
    call.in = in;
    call.out = cJSON_CreateObject();
    if (!cJSON_IsObject(in)) {
        rf_call_error(&call, "the inputs must be a JSON object");
    } else {
        /* every given input must be one the formula takes */
        const cJSON *e;
        SpecItem it;
        cJSON_ArrayForEach(e, in) {
            if (!spec_find(f->inputs, e->string, &it)) {
                rf_call_error(&call, "unknown input '%s' (inputs: %s)", e->string, f->inputs);
                break;
            }
        }
        if (!call.failed && f->fn(&call) && !call.failed)
            rf_call_error(&call, "failed without a message");
    }
    cJSON_Delete(call.defaults);
    if (call.failed) {
        snprintf(error, error_size, "%s", call.error);
        cJSON_Delete(call.out);
        return NULL;
    }
    return call.out;
}

int rf_formula_run_json(const RfFormula *f, const char *in_json, char **out_json)
{
    char error[512];
    cJSON *in = cJSON_Parse(in_json);
    if (!in) {
        *out_json = strdup("the inputs are not valid JSON");
        return 1;
    }
    cJSON *out = run(f, in, error, sizeof error);
    cJSON_Delete(in);
    if (!out) {
        *out_json = strdup(error);
        return 1;
    }
    *out_json = rf_formula_json_text(out);
    cJSON_Delete(out);
    return *out_json ? 0 : 1;
}

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

int rf_formula_batch(FILE *in, FILE *out)
{
    int failures = 0;
    char *line;
    while ((line = read_line(in)) != NULL) {
        const char *p = line;
        while (isspace((unsigned char)*p))
            p++;
        if (!*p) {
            free(line);
            continue;
        }
        cJSON *reply = cJSON_CreateObject();
        cJSON *c = cJSON_ParseWithOpts(p, NULL, 1); /* trailing text makes the line invalid */
        const cJSON *id = c ? cJSON_GetObjectItemCaseSensitive(c, "id") : NULL;
        const cJSON *inputs = c ? cJSON_GetObjectItemCaseSensitive(c, "in") : NULL;
        const RfFormula *f = NULL;
        char error[512] = "";
        if (cJSON_IsString(id))
            cJSON_AddStringToObject(reply, "id", id->valuestring);
        else
            cJSON_AddNullToObject(reply, "id");
        if (!c)
            snprintf(error, sizeof error, "the line is not valid JSON");
        else if (!cJSON_IsString(id))
            snprintf(error, sizeof error, "the case has no string \"id\"");
        else if (!(f = rf_formula_find(id->valuestring)))
            snprintf(error, sizeof error, "unknown formula id '%s' (see: refray formula list)", id->valuestring);
        else {
            cJSON *empty = NULL;
            if (!inputs)
                inputs = empty = cJSON_CreateObject();
            cJSON *o = run(f, (cJSON *)inputs, error, sizeof error);
            cJSON_Delete(empty);
            if (o)
                cJSON_AddItemToObject(reply, "out", o);
        }
        if (error[0]) {
            cJSON_AddStringToObject(reply, "error", error);
            failures++;
        }
        char *text = rf_formula_json_text(reply);
        fprintf(out, "%s\n", text ? text : "{\"id\":null,\"error\":\"out of memory\"}");
        fflush(out);
        free(text);
        cJSON_Delete(reply);
        cJSON_Delete(c);
        free(line);
    }
    return failures;
}

static void help_spec(const char *title, const char *spec, FILE *out)
{
    SpecItem it;
    const char *p = spec ? spec : "";
    fprintf(out, "%s:\n", title);
    while (spec_next(&p, &it)) {
        fprintf(out, "  %-16s %-5s", it.name, it.kind);
        if (it.has_def)
            fprintf(out, " (default %s)", it.def);
        else if (it.optional)
            fprintf(out, " (optional)");
        if (it.note[0])
            fprintf(out, " %s", it.note);
        fputc('\n', out);
    }
}

void rf_formula_help(const RfFormula *f, FILE *out)
{
    fprintf(out, "%s (script section %s)\n  %s\n", f->id, f->section, f->summary);
    help_spec("inputs", f->inputs, out);
    help_spec("outputs", f->outputs, out);
    if (f->erratum)
        fprintf(out, "erratum of the script:\n  %s\n", f->erratum);
    fprintf(out, "example:\n  refray formula %s key=value ...   (vectors 1,2,3; matrices "
                 "1,0;0,1 or a flat row-major list)\n", f->id);
}
