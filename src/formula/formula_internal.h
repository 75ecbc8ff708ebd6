/* Formula functions shared between the modules of src/formula (registry, batch, printing). */
#ifndef REFRAY_FORMULA_INTERNAL_H
#define REFRAY_FORMULA_INTERNAL_H

#include <cJSON.h>
#include <stddef.h>

#include "refray/formula.h"

/* eye, target, up -> u, v, w (§3.4), and with_view: the world-to-camera matrix (§4.7.2). */
int rf_formula_camera(RfFormulaCall *c, int with_view);

/* Runs f on parsed inputs: the output object, or NULL with the message in error and the kind
 * of failure in *result. */
cJSON *rf_formula_run(const RfFormula *f, const cJSON *in, char *error, size_t error_size,
                      RfFormulaResult *result);

/* A command-line value as JSON: true/false/null, numbers "1,2;3,4", JSON text, or a word;
 * NULL when it is malformed (a non-finite number, say). */
cJSON *rf_formula_value_json(const char *s);

/* The shortest of %.15g, %.16g, %.17g that reads back as v. */
void rf_formula_number_text(double v, char *text, size_t cap);

/* The rows of a table of results (print.c): one case's outputs, or a batch's cases with their
 * line, id and inputs; printed as text, Markdown or LaTeX. */
typedef struct RfFormulaTable RfFormulaTable;
RfFormulaTable *rf_formula_table_new(int batch);
/* One case: its outputs (out), or the error when out is NULL. */
void rf_formula_table_case(RfFormulaTable *t, int line, const RfFormula *f, const cJSON *in,
                           const cJSON *out, const char *error, RfFormulaFormat fmt, int digits);
void rf_formula_table_print(const RfFormulaTable *t, RfFormulaFormat fmt, FILE *out);
void rf_formula_table_free(RfFormulaTable *t);

#endif
