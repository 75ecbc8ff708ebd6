/* refray: the formula registry behind `refray formula` (reference: docs/formulas.md, made from
 * these tables by `refray formula --reference`).
 *
 * Each formula is one table entry: its id, script section, a one-line summary, the input and
 * output specifications, the erratum (if the script has one), the function and an example.
 * Input specs are "name:kind[=default] description" or "name:kind? description" (optional, no
 * default), separated by ';'. Kinds:
 *   num   a finite number       int   an integer          bool  true/false
 *   vecD  a vector whose length is one of the digits D: vec3 (3 numbers), vec23 (2 or 3), ...
 *   rgb   a colour r,g,b; one number v means the grey (v,v,v)
 *   matD  a square matrix of a size in D (mat34: 3x3 or 4x4), as rows or a flat row-major list
 *   vecsD a list of vectors of one length in D      tris  a list of triangles (3 vec3 each)
 *   nums  a list of numbers     a|b|c  one of the words a, b, c
 * The input parser enforces the kind: a vector of another length is a bad input (usage error),
 * never padded or cut. Defaults are written as on the command line ("step:num=0.02"). Outputs
 * are documented the same way ("name:kind description; ..."). Angles are in degrees wherever
 * they occur (their names end in _deg). */
#ifndef REFRAY_FORMULA_H
#define REFRAY_FORMULA_H

#include <stdio.h>

#include "refray/status.h"
#include "refray/vec.h"

/* The call context: the inputs of one case and the outputs it produces. Opaque. */
typedef struct RfFormulaCall RfFormulaCall;

/* A formula: returns 0 on success; on failure it has set an error with rf_call_error. */
typedef int (*RfFormulaFn)(RfFormulaCall *call);

typedef struct {
    const char *id;
    const char *section;  /* script section, e.g. "2.1", or "beyond" */
    const char *summary;  /* one line: what it computes */
    const char *inputs;   /* input spec, see above */
    const char *outputs;  /* output spec */
    const char *erratum;  /* the script's error and the corrected form, or NULL */
    RfFormulaFn fn;
    const char *example;  /* key=value arguments of a real case, shown (and run) by --help */
} RfFormula;

/* One parsed item of an input or output spec. */
typedef struct {
    char name[48], kind[64], def[160], note[400];
    int has_def, optional;
    unsigned dims; /* vector/matrix kinds: bit k set = length (size) k allowed; 0 otherwise */
    int grey;      /* rgb: a single number is accepted as the grey (v,v,v) */
} RfFormulaItem;

/* The index-th item of a spec (inputs or outputs); 0 when there is none. */
int rf_formula_item(const char *spec, int index, RfFormulaItem *item);

/* How a case ended. */
typedef enum {
    RF_FORMULA_OK = 0,
    RF_FORMULA_FAILED = 1,    /* the answer cannot be computed (singular, degenerate, domain) or,
                                 in a --check batch, it differs from the expected one */
    RF_FORMULA_BAD_INPUT = 2, /* unknown id or input, missing/duplicate input, not a number, a
                                 vector of the wrong length, a word not among the choices */
    RF_FORMULA_BAD_LINE = 3   /* a batch line that is not a JSON case {"id":..., "in":{...}} */
} RfFormulaResult;

/* Registry. */
size_t rf_formula_count(void);
const RfFormula *rf_formula_at(size_t index);
const RfFormula *rf_formula_find(const char *id);

/* Runs a formula on a JSON object of inputs (text). On success returns RF_FORMULA_OK and
 * *out_json holds the outputs as one JSON object (malloc'ed). On failure returns
 * RF_FORMULA_FAILED or RF_FORMULA_BAD_INPUT and *out_json holds the error message (malloc'ed,
 * plain text). */
int rf_formula_run_json(const RfFormula *f, const char *in_json, char **out_json);

/* Converts command-line arguments key=value into a JSON object text (malloc'ed). Values:
 * true/false, comma-separated numbers (one number, or a list; ';' separates the rows of a
 * matrix or a list of vectors), JSON text starting with '[' or '{', otherwise a string. On a
 * malformed argument returns NULL and writes a message into err. */
char *rf_formula_args_to_json(int argc, char **argv, char *err, size_t err_size);

/* How results are printed: JSON (exact, shortest round-trip digits), an aligned text table,
 * a Markdown table or a LaTeX tabular. digits >= 0 rounds the numbers of the last three to
 * that many decimals (trailing zeros dropped); -1 prints them exactly, as JSON does. */
typedef enum { RF_FORMULA_JSON, RF_FORMULA_TABLE, RF_FORMULA_MARKDOWN, RF_FORMULA_LATEX } RfFormulaFormat;

typedef struct {
    RfFormulaFormat format;
    int digits;
    int check;          /* compare each line's "expect" and print a pass/fail report instead */
    double rtol, atol;  /* --check: |got - expected| <= atol + rtol |expected| (lines may override) */
    const char *name;   /* the input's name for messages ("cases.jsonl:3: ..."), or NULL */
    FILE *err;          /* where those messages go, or NULL */
} RfFormulaBatchOptions;

#define RF_FORMULA_RTOL 1e-9
#define RF_FORMULA_ATOL 1e-12

typedef struct {
    int cases;                 /* non-blank lines */
    int errors;                /* cases without a result (bad line, bad input, failed formula) */
    int passed, failed, unchecked; /* --check */
    RfFormulaResult worst;     /* the highest result of any line (BAD_LINE > BAD_INPUT > FAILED) */
} RfFormulaBatchSummary;

/* Batch mode: JSON lines {"id": ..., "in": {...}[, "expect": {...}, "rtol": r, "atol": a]} in,
 * one result per case out (an invalid line: {"line":N,"id":null,"error":"line N: ..."}).
 * opt and sum may be NULL (JSON, no check). Returns the number of cases in error or, with
 * check, failed. */
int rf_formula_batch(FILE *in, FILE *out, const RfFormulaBatchOptions *opt, RfFormulaBatchSummary *sum);

/* Prints one case's outputs (JSON object text) in a format. */
void rf_formula_print(const RfFormula *f, const char *out_json, RfFormulaFormat format, int digits, FILE *out);

/* JSON text of a cJSON tree (malloc'ed) with numbers that round-trip exactly (cJSON's own
 * printer rounds to 15 digits when it deems that close enough). NULL when out of memory. */
struct cJSON;
char *rf_formula_json_text(const struct cJSON *j);

/* Writes the help of one formula: summary, every input (meaning, kind, unit, default, allowed
 * words), every output, the erratum, and the example with the output it really gives. */
void rf_formula_help(const RfFormula *f, FILE *out);
/* The reference of every formula in Markdown (docs/formulas.md). */
void rf_formula_reference(FILE *out);

/* ---- for the implementations of formulas ---- */

/* Error: printf-style message; always returns 1 so that "return rf_call_error(...)" works.
 * rf_call_error: the answer cannot be computed (RF_FORMULA_FAILED); rf_call_bad_input: the
 * inputs are not what the formula takes (RF_FORMULA_BAD_INPUT). */
int rf_call_error(RfFormulaCall *call, const char *fmt, ...)
#ifdef __GNUC__
    __attribute__((format(printf, 2, 3)))
#endif
    ;
int rf_call_bad_input(RfFormulaCall *call, const char *fmt, ...)
#ifdef __GNUC__
    __attribute__((format(printf, 2, 3)))
#endif
    ;
/* Inputs: each returns 0 on success, 1 with an error set (missing, malformed). Missing
 * optional inputs without a default return 0 and set *present = 0 (where present is asked). */
int rf_in_num(RfFormulaCall *call, const char *name, double *v);
int rf_in_int(RfFormulaCall *call, const char *name, long *v);
int rf_in_bool(RfFormulaCall *call, const char *name, int *v);
int rf_in_has(RfFormulaCall *call, const char *name);
/* A caller's further limit on lengths (sizes): RF_DIM(3) | RF_DIM(4); 0: as the spec says. A
 * length outside 0..31 (a list of 35 numbers) is in no set: RF_DIM gives 0, not a shift past the
 * word (undefined behaviour). */
#define RF_DIM(n) ((n) >= 0 && (n) < 32 ? 1u << (n) : 0u)
/* A vector of a length the spec's kind allows and, when dims != 0, one of dims (the length of
 * another input, say); at most 4 components; the length goes to *dim_out. An rgb input also
 * takes one number as grey. */
int rf_in_vec(RfFormulaCall *call, const char *name, unsigned dims, double *v, int *dim_out);
/* A vec3 input; a vec23 input of 2 components lies in the plane z = 0 (the spec says so). */
int rf_in_vec3(RfFormulaCall *call, const char *name, RfVec3 *v);
/* A square matrix of a size the spec allows (and dims), row-major; the size goes to *n_out. */
int rf_in_mat(RfFormulaCall *call, const char *name, unsigned dims, double *m, int *n_out);
/* A list of numbers (malloc'ed into *v, count in *count). */
int rf_in_nums(RfFormulaCall *call, const char *name, double **v, int *count);
/* A list of up to max vectors of one length the spec (and dims) allows, row-major into v. */
int rf_in_vecs(RfFormulaCall *call, const char *name, unsigned dims, int max, double *v, int *count,
               int *dim_out);
/* A list of up to max triangles [[a,b,c], ...] of 3D points: 9 numbers per triangle into
 * corners (a.x a.y a.z b.x ...). */
int rf_in_tris(RfFormulaCall *call, const char *name, int max, double *corners, int *count);
/* A word out of the spec's choices (kind "a|b|c"); *index gets its position. */
int rf_in_choice(RfFormulaCall *call, const char *name, int *index);
/* Angle in degrees (name ends in _deg) -> radians. */
int rf_in_angle(RfFormulaCall *call, const char *name, double *radians);

/* Outputs. A non-finite number is an error (never silently printed). */
void rf_out_num(RfFormulaCall *call, const char *name, double v);
void rf_out_bool(RfFormulaCall *call, const char *name, int v);
void rf_out_null(RfFormulaCall *call, const char *name);
void rf_out_str(RfFormulaCall *call, const char *name, const char *v);
void rf_out_vec(RfFormulaCall *call, const char *name, const double *v, int dim);
void rf_out_vec3(RfFormulaCall *call, const char *name, RfVec3 v);
void rf_out_mat(RfFormulaCall *call, const char *name, const double *m, int n);

/* The tables of the modules, each ended by an entry with id NULL. */
extern const RfFormula rf_formulas_geometry[];  /* §2 */
extern const RfFormula rf_formulas_transform[]; /* §4 */
extern const RfFormula rf_formulas_color[];     /* §1 */
extern const RfFormula rf_formulas_raytrace[];  /* §3 */

#endif
