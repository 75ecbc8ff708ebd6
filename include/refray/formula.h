/* refray: the formula registry behind `refray formula` (contract: FORMULAS.md).
 *
 * Each formula is one table entry: its id, script section, a one-line summary, the input and
 * output specifications, the erratum (if the script has one) and the function. Input specs are
 * "name:kind[=default]" or "name:kind?" (optional, no default), separated by ';'. Kinds:
 *   num  a finite number        int   an integer          bool  true/false
 *   vec  2..4 numbers           vec3  3 numbers            nums  a list of numbers
 *   mat  a square matrix 2x2..4x4 (rows, or a flat row-major list)
 *   vecs a list of vectors (of one dimension)              tris  a list of triangles (3 vec3 each)
 *   str  a word (the allowed words are listed in the summary or help)
 * Defaults are written as on the command line ("step:num=0.02", "white:vec=0.33333333333333331,
 * 0.33333333333333331"). Outputs are documented the same way ("name:kind; ..."). */
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
} RfFormula;

/* Registry. */
size_t rf_formula_count(void);
const RfFormula *rf_formula_at(size_t index);
const RfFormula *rf_formula_find(const char *id);

/* Runs a formula on a JSON object of inputs (text). On success returns 0 and *out_json holds
 * the outputs as one JSON object (malloc'ed). On failure returns non-zero and *out_json holds
 * the error message (malloc'ed, plain text). */
int rf_formula_run_json(const RfFormula *f, const char *in_json, char **out_json);

/* Converts command-line arguments key=value into a JSON object text (malloc'ed). Values:
 * true/false, comma-separated numbers (one number, or a list; ';' separates the rows of a
 * matrix or a list of vectors), JSON text starting with '[' or '{', otherwise a string. On a
 * malformed argument returns NULL and writes a message into err. */
char *rf_formula_args_to_json(int argc, char **argv, char *err, size_t err_size);

/* Batch mode: JSON lines {"id": ..., "in": {...}} in, one JSON line out per case.
 * Returns the number of cases that failed. */
int rf_formula_batch(FILE *in, FILE *out);

/* JSON text of a cJSON tree (malloc'ed) with numbers that round-trip exactly (cJSON's own
 * printer rounds to 15 digits when it deems that close enough). NULL when out of memory. */
struct cJSON;
char *rf_formula_json_text(const struct cJSON *j);

/* Writes the help of one formula (inputs, outputs, section, erratum). */
void rf_formula_help(const RfFormula *f, FILE *out);

/* ---- for the implementations of formulas ---- */

/* Error: printf-style message; always returns 1 so that "return rf_call_error(...)" works. */
int rf_call_error(RfFormulaCall *call, const char *fmt, ...);
/* Inputs: each returns 0 on success, 1 with an error set (missing, malformed). Missing
 * optional inputs without a default return 0 and set *present = 0 (where present is asked). */
int rf_in_num(RfFormulaCall *call, const char *name, double *v);
int rf_in_int(RfFormulaCall *call, const char *name, long *v);
int rf_in_bool(RfFormulaCall *call, const char *name, int *v);
int rf_in_has(RfFormulaCall *call, const char *name);
/* A vector of dim components (dim 0: any of 2..4; the actual count goes to *dim_out). */
int rf_in_vec(RfFormulaCall *call, const char *name, int dim, double *v, int *dim_out);
int rf_in_vec3(RfFormulaCall *call, const char *name, RfVec3 *v); /* 2D vectors get z = 0 */
/* A square matrix of size n (n 0: any of 2..4; the size goes to *n_out), row-major. */
int rf_in_mat(RfFormulaCall *call, const char *name, int n, double *m, int *n_out);
/* A list of numbers (malloc'ed into *v, count in *count). */
int rf_in_nums(RfFormulaCall *call, const char *name, double **v, int *count);
/* A list of up to max vectors of one dimension dim (0: any of 2..4), row-major into v. */
int rf_in_vecs(RfFormulaCall *call, const char *name, int dim, int max, double *v, int *count, int *dim_out);
/* A list of up to max triangles [[a,b,c], ...] of 3D points: 9 numbers per triangle into
 * corners (a.x a.y a.z b.x ...). */
int rf_in_tris(RfFormulaCall *call, const char *name, int max, double *corners, int *count);
/* A word out of a '|'-separated list of choices; *index gets its position. */
int rf_in_choice(RfFormulaCall *call, const char *name, const char *choices, int *index);
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
