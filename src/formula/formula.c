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

#include "formula_internal.h"
#include "refray/mat.h"

struct RfFormulaCall {
    const RfFormula *formula;
    cJSON *in;
    cJSON *out;
    cJSON *cache; /* parsed defaults, and string inputs read as numbers, built on demand */
    char error[512];
    int failed;
    RfFormulaResult result; /* RF_FORMULA_FAILED or RF_FORMULA_BAD_INPUT once failed */
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

/* The lengths of a kind: "vec23" -> {2,3}; "rgb" -> {3}; "vec", "mat", "vecs" -> {2,3,4}. */
static void kind_dims(RfFormulaItem *it)
{
    static const char *const bases[] = {"vecs", "vec", "mat"};
    if (strcmp(it->kind, "rgb") == 0) {
        it->dims = RF_DIM(3);
        it->grey = 1;
        return;
    }
    for (size_t b = 0; b < sizeof bases / sizeof bases[0]; b++) {
        size_t n = strlen(bases[b]);
        if (strncmp(it->kind, bases[b], n) != 0 || strspn(it->kind + n, "234") != strlen(it->kind + n))
            continue;
        for (const char *d = it->kind + n; *d; d++)
            it->dims |= RF_DIM(*d - '0');
        if (!it->dims)
            it->dims = RF_DIM(2) | RF_DIM(3) | RF_DIM(4);
        return;
    }
}

/* Parses the item that starts at *p and advances *p past it; returns 0 at the end. */
static int spec_next(const char **p, RfFormulaItem *it)
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
    kind_dims(it);
    return 1;
}

int rf_formula_item(const char *spec, int index, RfFormulaItem *item)
{
    const char *p = spec ? spec : "";
    for (int i = 0; spec_next(&p, item); i++)
        if (i == index)
            return 1;
    return 0;
}

static int spec_find(const char *spec, const char *name, RfFormulaItem *it)
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

void rf_formula_number_text(double v, char *text, size_t cap)
{
    for (int digits = 15; digits <= 17; digits++) {
        snprintf(text, cap, "%.*g", digits, v);
        if (strtod(text, NULL) == v)
            break;
    }
}

static void print_number(TextBuf *b, double v)
{
    char text[40];
    rf_formula_number_text(v, text, sizeof text);
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

cJSON *rf_formula_value_json(const char *s)
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
        cJSON *v = rf_formula_value_json(eq + 1);
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

static int call_error(RfFormulaCall *call, RfFormulaResult result, const char *fmt, va_list ap)
{
    if (!call->failed) { /* keep the first error: it is the cause */
        vsnprintf(call->error, sizeof call->error, fmt, ap);
        call->failed = 1;
        call->result = result;
    }
    return 1;
}

int rf_call_error(RfFormulaCall *call, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    call_error(call, RF_FORMULA_FAILED, fmt, ap);
    va_end(ap);
    return 1;
}

int rf_call_bad_input(RfFormulaCall *call, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    call_error(call, RF_FORMULA_BAD_INPUT, fmt, ap);
    va_end(ap);
    return 1;
}

/* Kinds made of numbers: their values may also be written as on the command line, as a
 * string ("1,2;3,4"), in a batch file. */
static int numeric_kind(const RfFormulaItem *it)
{
    return it->dims || strcmp(it->kind, "num") == 0 || strcmp(it->kind, "int") == 0 ||
           strcmp(it->kind, "nums") == 0 || strcmp(it->kind, "tris") == 0;
}

/* A value kept for the call's lifetime under name (a default, or a string read as numbers). */
static const cJSON *cached(RfFormulaCall *call, const char *name, const char *text)
{
    if (!call->cache)
        call->cache = cJSON_CreateObject();
    cJSON *d = cJSON_GetObjectItemCaseSensitive(call->cache, name);
    if (!d && (d = rf_formula_value_json(text)) != NULL)
        cJSON_AddItemToObject(call->cache, name, d);
    return d;
}

/* The JSON item of an input, its default when absent, or NULL (optional without default, or
 * an error: *err set). it receives the input's spec item. */
static const cJSON *input_item(RfFormulaCall *call, const char *name, RfFormulaItem *it, int *err)
{
    *err = 0;
    if (!spec_find(call->formula->inputs, name, it)) {
        *err = rf_call_error(call, "internal: input '%s' is not in the spec of %s", name,
                             call->formula->id);
        return NULL;
    }
    const cJSON *v = cJSON_GetObjectItemCaseSensitive(call->in, name);
    if (v && !cJSON_IsNull(v)) {
        if (cJSON_IsString(v) && numeric_kind(it)) {
            const cJSON *n = cached(call, name, v->valuestring);
            if (!n || cJSON_IsString(n)) {
                *err = rf_call_bad_input(call, "input '%s': cannot read '%s' as numbers", name, v->valuestring);
                return NULL;
            }
            return n;
        }
        return v;
    }
    if (it->has_def) {
        const cJSON *d = cached(call, name, it->def);
        if (!d)
            *err = rf_call_error(call, "internal: bad default '%s' for %s", it->def, name);
        return d;
    }
    if (!it->optional)
        *err = rf_call_bad_input(call, "missing input '%s'", name);
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
        return rf_call_bad_input(call, "input '%s' must be a number", name);
    if (!isfinite(v->valuedouble))
        return rf_call_bad_input(call, "input '%s' is not finite", name);
    *out = v->valuedouble;
    return 0;
}

int rf_in_num(RfFormulaCall *call, const char *name, double *v)
{
    int err;
    RfFormulaItem it;
    const cJSON *j = input_item(call, name, &it, &err);
    if (err)
        return 1;
    if (!j)
        return rf_call_error(call, "internal: optional number '%s' needs a default", name);
    return json_num(call, name, j, v);
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
        return rf_call_bad_input(call, "input '%s' must be an integer", name);
    *v = (long)d;
    return 0;
}

int rf_in_bool(RfFormulaCall *call, const char *name, int *v)
{
    int err;
    RfFormulaItem it;
    const cJSON *j = input_item(call, name, &it, &err);
    if (err)
        return 1;
    if (!j || !cJSON_IsBool(j))
        return rf_call_bad_input(call, "input '%s' must be true or false", name);
    *v = cJSON_IsTrue(j);
    return 0;
}

/* Reads a JSON array of numbers, the first max of them into v; returns how many there are, or
 * -1 when it is not an array of finite numbers. */
static int json_numbers(const cJSON *arr, double *v, int max)
{
    int n = 0;
    const cJSON *e;
    if (!cJSON_IsArray(arr))
        return -1;
    cJSON_ArrayForEach(e, arr) {
        if (!cJSON_IsNumber(e) || !isfinite(e->valuedouble))
            return -1;
        if (n < max)
            v[n] = e->valuedouble;
        n++;
    }
    return n;
}

/* "3", "2 or 3", "2, 3 or 4": the lengths of a mask, for messages and help. */
static const char *dims_text(unsigned dims, char *buf, size_t cap)
{
    int k = 0, count = 0;
    for (int d = 0; d < 32; d++)
        count += (dims >> d) & 1u;
    buf[0] = 0;
    for (int d = 0; d < 32; d++)
        if ((dims >> d) & 1u) {
            size_t len = strlen(buf);
            snprintf(buf + len, cap - len, "%s%d", k == 0 ? "" : k == count - 1 ? " or " : ", ", d);
            k++;
        }
    return buf;
}

/* The message for a vector or matrix of a length (size) n the input does not take; what is
 * the thing counted, singular and plural ("component\0components"). */
static int wrong_length(RfFormulaCall *call, const char *name, const RfFormulaItem *it, unsigned allowed,
                        int n, const char *what)
{
    char want[64];
    dims_text(allowed, want, sizeof want);
    const char *counted = n == 1 ? what : what + strlen(what) + 1;
    if (it->dims & RF_DIM(n)) /* the spec takes it, the other inputs decide otherwise */
        return rf_call_bad_input(call, "input '%s' has %d %s; it takes %s here (to match the other inputs)",
                                 name, n, counted, want);
    return rf_call_bad_input(call, "input '%s' has %d %s; it takes %s", name, n, counted, want);
}

int rf_in_vec(RfFormulaCall *call, const char *name, unsigned dims, double *v, int *dim_out)
{
    int err;
    RfFormulaItem it;
    const cJSON *j = input_item(call, name, &it, &err);
    if (err)
        return 1;
    if (!j)
        return rf_call_error(call, "internal: optional vector '%s' needs a default", name);
    unsigned allowed = it.dims & (dims ? dims : ~0u);
    char want[64];
    double buf[4] = {0, 0, 0, 0};
    int n;
    if (it.grey && cJSON_IsNumber(j)) { /* one number where a colour is expected: grey */
        if (json_num(call, name, j, &buf[0]))
            return 1;
        buf[1] = buf[2] = buf[0];
        n = 3;
    } else {
        n = json_numbers(j, buf, 4);
    }
    if (n < 0)
        return rf_call_bad_input(call, "input '%s' must be a vector of %s finite numbers%s", name,
                                 dims_text(allowed, want, sizeof want), it.grey ? " (or one number: grey)" : "");
    if (!(allowed & RF_DIM(n)))
        return wrong_length(call, name, &it, allowed, n, "component\0components");
    memcpy(v, buf, sizeof(double) * (size_t)n);
    if (dim_out)
        *dim_out = n;
    return 0;
}

int rf_in_vec3(RfFormulaCall *call, const char *name, RfVec3 *v)
{
    double a[4] = {0, 0, 0, 0};
    if (rf_in_vec(call, name, RF_DIM(2) | RF_DIM(3), a, NULL))
        return 1;
    *v = rf_vec3(a[0], a[1], a[2]); /* a 2D vector (the spec takes it) lies in the plane z = 0 */
    return 0;
}

int rf_in_mat(RfFormulaCall *call, const char *name, unsigned dims, double *m, int *n_out)
{
    int err;
    RfFormulaItem it;
    const cJSON *j = input_item(call, name, &it, &err);
    if (err)
        return 1;
    unsigned allowed = it.dims & (dims ? dims : ~0u);
    int size = cJSON_IsArray(j) ? cJSON_GetArraySize(j) : 0, got = -1;
    double flat[RF_MATN_MAX * RF_MATN_MAX];
    if (size > 0 && cJSON_IsArray(cJSON_GetArrayItem(j, 0))) {
        /* a list of rows, each as long as there are rows */
        got = size;
        int r = 0;
        const cJSON *row;
        cJSON_ArrayForEach(row, j) {
            if (size > RF_MATN_MAX || json_numbers(row, m + r * size, RF_MATN_MAX) != size) {
                got = size > RF_MATN_MAX ? size : -1;
                break;
            }
            r++;
        }
    } else if (size > 0) {
        int k = json_numbers(j, flat, RF_MATN_MAX * RF_MATN_MAX);
        got = -1;
        for (int s = 1; s * s <= k; s++)
            if (k == s * s)
                got = s;
        if (got >= 2 && got <= RF_MATN_MAX)
            memcpy(m, flat, sizeof(double) * (size_t)k);
    }
    if (got < 1)
        return rf_call_bad_input(call, "input '%s' must be a square matrix of finite numbers (rows, or a "
                                 "flat row-major list)", name);
    if (!(allowed & RF_DIM(got))) {
        char what[64];
        int k = snprintf(what, sizeof what, "row (%dx%d)", got, got);
        snprintf(what + k + 1, sizeof what - (size_t)k - 1, "rows (%dx%d)", got, got);
        return wrong_length(call, name, &it, allowed, got, what);
    }
    if (n_out)
        *n_out = got;
    return 0;
}

int rf_in_nums(RfFormulaCall *call, const char *name, double **v, int *count)
{
    int err;
    RfFormulaItem it;
    const cJSON *j = input_item(call, name, &it, &err);
    if (err)
        return 1;
    if (!j)
        return rf_call_bad_input(call, "missing input '%s'", name);
    if (cJSON_IsNumber(j)) { /* a single number is a list of one */
        *v = malloc(sizeof(double));
        if (!*v)
            return rf_call_error(call, "out of memory");
        *count = 1;
        return json_num(call, name, j, *v);
    }
    int size = cJSON_IsArray(j) ? cJSON_GetArraySize(j) : -1;
    if (size < 1)
        return rf_call_bad_input(call, "input '%s' must be a non-empty list of numbers", name);
    *v = malloc(sizeof(double) * (size_t)size);
    if (!*v)
        return rf_call_error(call, "out of memory");
    if (json_numbers(j, *v, size) != size) {
        free(*v);
        *v = NULL;
        return rf_call_bad_input(call, "input '%s' must be a list of finite numbers", name);
    }
    *count = size;
    return 0;
}

int rf_in_vecs(RfFormulaCall *call, const char *name, unsigned dims, int max, double *v, int *count,
               int *dim_out)
{
    int err;
    RfFormulaItem it;
    const cJSON *j = input_item(call, name, &it, &err);
    if (err)
        return 1;
    if (!j || !cJSON_IsArray(j) || cJSON_GetArraySize(j) < 1)
        return rf_call_bad_input(call, "input '%s' must be a list of vectors", name);
    if (cJSON_GetArraySize(j) > max)
        return rf_call_bad_input(call, "input '%s' has more than %d vectors", name, max);
    int n = 0, d = 0;
    unsigned allowed = it.dims & (dims ? dims : ~0u);
    const cJSON *e;
    cJSON_ArrayForEach(e, j) {
        double tmp[4];
        int k = json_numbers(e, tmp, 4);
        if (k < 0)
            return rf_call_bad_input(call, "input '%s': vector %d is not a list of finite numbers", name, n + 1);
        if (!(allowed & RF_DIM(k)) || (d && k != d))
            return wrong_length(call, name, &it, d ? RF_DIM(d) : allowed, k, "component in a vector\0components in a vector");
        d = k;
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
    RfFormulaItem it;
    const cJSON *j = input_item(call, name, &it, &err);
    if (err)
        return 1;
    if (!j || !cJSON_IsArray(j) || cJSON_GetArraySize(j) < 1)
        return rf_call_bad_input(call, "input '%s' must be a list of triangles [[a,b,c], ...]", name);
    if (cJSON_GetArraySize(j) > max)
        return rf_call_bad_input(call, "input '%s' has more than %d triangles", name, max);
    int n = 0;
    const cJSON *tri, *corner;
    cJSON_ArrayForEach(tri, j) {
        int k = 0;
        if (!cJSON_IsArray(tri) || cJSON_GetArraySize(tri) != 3)
            return rf_call_bad_input(call, "input '%s': each triangle is three 3D points [a,b,c]", name);
        cJSON_ArrayForEach(corner, tri) {
            double p[4];
            int len = json_numbers(corner, p, 4);
            if (len != 3)
                return rf_call_bad_input(call, "input '%s': each corner must be 3 finite numbers, not %d",
                                         name, len);
            memcpy(corners + 9 * n + 3 * k, p, sizeof(double) * 3);
            k++;
        }
        n++;
    }
    *count = n;
    return 0;
}

int rf_in_choice(RfFormulaCall *call, const char *name, int *index)
{
    int err;
    RfFormulaItem it;
    const cJSON *j = input_item(call, name, &it, &err);
    if (err)
        return 1;
    const char *choices = it.kind;
    if (!strchr(choices, '|'))
        return rf_call_error(call, "internal: input '%s' has no choices in its spec", name);
    if (!j || !cJSON_IsString(j))
        return rf_call_bad_input(call, "input '%s' must be one of %s", name, choices);
    const char *w = j->valuestring, *p = choices;
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
    return rf_call_bad_input(call, "input '%s' must be one of %s, not '%s'", name, choices, w);
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

cJSON *rf_formula_run(const RfFormula *f, const cJSON *in, char *error, size_t error_size,
                      RfFormulaResult *result)
{
    RfFormulaCall call;
    memset(&call, 0, sizeof call);
    call.formula = f;
    call.in = (cJSON *)in;
    call.out = cJSON_CreateObject();
    if (!cJSON_IsObject(in)) {
        rf_call_bad_input(&call, "the inputs must be a JSON object");
    } else {
        /* every given input must be one the formula takes */
        const cJSON *e;
        RfFormulaItem it;
        cJSON_ArrayForEach(e, in) {
            if (!spec_find(f->inputs, e->string, &it)) {
                char names[400] = "";
                for (int i = 0; rf_formula_item(f->inputs, i, &it); i++) {
                    size_t len = strlen(names);
                    snprintf(names + len, sizeof names - len, "%s%s", i ? ", " : "", it.name);
                }
                rf_call_bad_input(&call, "unknown input '%s' (inputs: %s)", e->string, names);
                break;
            }
        }
        if (!call.failed && f->fn(&call) && !call.failed)
            rf_call_error(&call, "failed without a message");
    }
    cJSON_Delete(call.cache);
    *result = call.failed ? call.result : RF_FORMULA_OK;
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
    RfFormulaResult result;
    cJSON *in = cJSON_Parse(in_json);
    if (!in) {
        *out_json = strdup("the inputs are not valid JSON");
        return RF_FORMULA_BAD_INPUT;
    }
    cJSON *out = rf_formula_run(f, in, error, sizeof error, &result);
    cJSON_Delete(in);
    if (!out) {
        *out_json = strdup(error);
        return result;
    }
    *out_json = rf_formula_json_text(out);
    cJSON_Delete(out);
    return *out_json ? RF_FORMULA_OK : RF_FORMULA_FAILED;
}
