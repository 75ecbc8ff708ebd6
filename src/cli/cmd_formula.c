/* `refray formula`: list, one case from key=value arguments, --batch FILE [--check], ID --help,
 * --reference; results as JSON (exact) or a table, Markdown or LaTeX (--digits). */
#include "cli.h"

#include <errno.h>
#include <stdlib.h>
#include <string.h>

#include "args.h"
#include "exit_codes.h"
#include "opt.h"
#include "refray/formula.h"

enum { OPT_BATCH = 'b', OPT_CHECK = 'c', OPT_FORMAT = 'f', OPT_DIGITS = RF_OPT_ID, OPT_RTOL, OPT_ATOL, OPT_REFERENCE };

static const RfOpt formula_opts[] = {
    {"batch", OPT_BATCH, "FILE", "read cases from FILE, one JSON line {\"id\":..., \"in\":{...}} each ('-': stdin)",
     NULL},
    {"check", OPT_CHECK, NULL, "with --batch: compare each line's \"expect\" and report pass/fail per line", NULL},
    {"format", OPT_FORMAT, "F", "json (default, exact digits), table, markdown or latex",
     "json, table, markdown or latex"},
    {"digits", OPT_DIGITS, "N", "table/markdown/latex: round numbers to N decimals (JSON stays exact)",
     "an integer in [0, 17]"},
    {"rtol", OPT_RTOL, "X", "--check: relative tolerance (default 1e-9; a line's \"rtol\" wins)", "a number >= 0"},
    {"atol", OPT_ATOL, "X", "--check: absolute tolerance (default 1e-12; a line's \"atol\" wins)", "a number >= 0"},
    {"reference", OPT_REFERENCE, NULL, "print every formula's help as Markdown (docs/formulas.md)", NULL},
    RF_OPT_TABLE_END,
};

static const RfOpt *const formula_tables[] = {formula_opts, NULL};

static const RfCommand formula_cmd = {
    "refray formula",
    "refray formula list\n"
    "       refray formula [options] ID key=value ...\n"
    "       refray formula ID --help\n"
    "       refray formula [options] --batch FILE\n",
    "Computes a formula of the lecture script. Inputs are key=value: vectors 1,2,3,\n"
    "matrices 1,2;3,4 (rows; quote them for the shell) or JSON, words plain; angles are\n"
    "in degrees (names ending in _deg). A number where a colour is expected is the grey\n"
    "(v,v,v); a vector of a length the input does not take is an error. 'refray formula\n"
    "list' names every id, 'refray formula ID --help' its inputs, outputs and an example.\n"
    "\n"
    "--batch FILE reads one case per line, {\"id\":\"dot\",\"in\":{\"a\":[1,2],\"b\":\"3,4\"}},\n"
    "and prints one result per case; a bad line answers {\"line\":N,\"id\":...,\"error\":...}\n"
    "and FILE:N: on stderr. --check compares each line's \"expect\":{\"dot\":11} with\n"
    "|got - expected| <= atol + rtol |expected| (per number; words, booleans and null\n"
    "exactly; \"expect\":{\"error\":\"singular\"} asks for a failure whose message has\n"
    "those words) and prints 'line N (id): pass' or 'FAIL output: expected, got,\n"
    "difference' per line and 'N passed, N failed'.\n",
    formula_tables,
    "exit: 0 ok; 2 a formula failed (singular, degenerate, out of its domain) or a --check\n"
    "line differs; 4 the batch file is missing, unreadable or empty, or a line is not a\n"
    "JSON case; 5 usage: unknown id, option or input, a missing or duplicate input, not a\n"
    "number, a vector of the wrong length, a word not among the choices. A batch exits\n"
    "with the highest code of its lines. (README: Exit codes)\n",
};

static int exit_code(RfFormulaResult r)
{
    return r == RF_FORMULA_OK ? RF_EXIT_OK : r == RF_FORMULA_FAILED ? RF_EXIT_FAIL
         : r == RF_FORMULA_BAD_LINE ? RF_EXIT_FILE : RF_EXIT_USAGE;
}

static int run_batch(const char *path, const RfFormulaBatchOptions *opt_in)
{
    RfFormulaBatchOptions opt = *opt_in;
    RfFormulaBatchSummary sum;
    int stdin_ = strcmp(path, "-") == 0;
    FILE *in = stdin_ ? stdin : fopen(path, "r");
    if (!in) {
        fprintf(stderr, "refray formula: %s: %s\n", path, strerror(errno));
        return RF_EXIT_FILE;
    }
    opt.name = stdin_ ? "<stdin>" : path;
    opt.err = stderr;
    rf_formula_batch(in, stdout, &opt, &sum);
    int unreadable = ferror(in);
    if (!stdin_)
        fclose(in);
    if (unreadable) {
        fprintf(stderr, "refray formula: %s: cannot be read\n", opt.name);
        return RF_EXIT_FILE;
    }
    if (sum.errors && !opt.check)
        fprintf(stderr, "refray formula: %d of %d case%s failed (see their \"error\" lines)\n", sum.errors,
                sum.cases, sum.cases == 1 ? "" : "s");
    return exit_code(sum.worst);
}

/* "unknown id 'crosss'; did you mean 'cross'?" */
static int unknown_id(const char *word)
{
    const char *ids[256];
    int count = 0;
    for (size_t i = 0; i < rf_formula_count() && count < 256; i++)
        ids[count++] = rf_formula_at(i)->id;
    int s = rf_suggest(word, ids, count);
    fprintf(stderr, "refray formula: unknown id '%s'", word);
    if (s >= 0)
        fprintf(stderr, "; did you mean '%s'?", ids[s]);
    fprintf(stderr, " (see: refray formula list)\n");
    return RF_EXIT_USAGE;
}

/* `refray formula ID --help` (before the parser, which would print the command's help):
 * *word is the first operand-like argument when --help is given, else NULL. */
static const RfFormula *id_help(int argc, char **argv, const char **word)
{
    const RfFormula *f = NULL;
    int help = 0;
    *word = NULL;
    for (int i = 1; i < argc && strcmp(argv[i], "--") != 0; i++) {
        if (strcmp(argv[i], "--help") == 0 || strcmp(argv[i], "-h") == 0)
            help = 1;
        else if (argv[i][0] != '-' && !strchr(argv[i], '=') && !*word)
            *word = argv[i];
        if (!f && argv[i][0] != '-')
            f = rf_formula_find(argv[i]);
    }
    if (!help)
        *word = NULL;
    return help ? f : NULL;
}

int rf_cmd_formula(int argc, char **argv)
{
    static const char *const formats[] = {"json", "table", "markdown", "latex"};
    RfFormulaBatchOptions opt = {RF_FORMULA_JSON, -1, 0, RF_FORMULA_RTOL, RF_FORMULA_ATOL, NULL, NULL};
    const char *batch = NULL;
    int reference = 0, tol_given = 0;
    const char *word;
    const RfFormula *help = id_help(argc, argv, &word);
    if (help) {
        rf_formula_help(help, stdout);
        return RF_EXIT_OK;
    }
    if (word && strcmp(word, "list") != 0 && argv[1] == word) /* `refray formula nope --help` */
        return unknown_id(word);
    RfOptParser p;
    int key;
    rf_opt_init(&p, &formula_cmd, argc, argv);
    while ((key = rf_opt_next(&p)) != RF_OPT_DONE) {
        double v;
        int k = -1;
        switch (key) {
        case RF_OPT_EXIT:
            return p.exit_code;
        case OPT_BATCH:
            batch = p.value;
            break;
        case OPT_CHECK:
            opt.check = 1;
            break;
        case OPT_FORMAT:
            for (int i = 0; i < 4; i++)
                if (strcmp(p.value, formats[i]) == 0)
                    k = i;
            if (k < 0)
                return rf_opt_bad_value(&p);
            opt.format = (RfFormulaFormat)k;
            break;
        case OPT_DIGITS:
            if (!rf_arg_int(p.value, 0, 17, &opt.digits))
                return rf_opt_bad_value(&p);
            break;
        case OPT_RTOL:
        case OPT_ATOL:
            if (!rf_arg_nonneg(p.value, &v))
                return rf_opt_bad_value(&p);
            *(key == OPT_RTOL ? &opt.rtol : &opt.atol) = v;
            tol_given = 1;
            break;
        case OPT_REFERENCE:
            reference = 1;
            break;
        default:
            return rf_opt_usage_error(&formula_cmd, "internal: option %d not handled", key);
        }
    }
    char **ops;
    int n = rf_opt_operands(&p, &ops);
    if (opt.digits >= 0 && opt.format == RF_FORMULA_JSON)
        return rf_opt_usage_error(&formula_cmd, "--digits rounds table, markdown and latex only (JSON stays exact): "
                                                "add --format");
    if ((opt.check || tol_given) && !batch)
        return rf_opt_usage_error(&formula_cmd, "--check, --rtol and --atol go with --batch FILE");
    if (opt.check && (opt.format != RF_FORMULA_JSON || opt.digits >= 0))
        return rf_opt_usage_error(&formula_cmd, "--check prints a pass/fail report: no --format or --digits");
    if (reference) {
        if (n || batch)
            return rf_opt_usage_error(&formula_cmd, "--reference takes nothing else");
        rf_formula_reference(stdout);
        return RF_EXIT_OK;
    }
    if (batch) {
        if (n)
            return rf_opt_usage_error(&formula_cmd, "--batch takes no id or key=value ('%s')", ops[0]);
        return run_batch(batch, &opt);
    }
    if (n == 0)
        return rf_opt_usage_error(&formula_cmd, "missing the formula id (see: refray formula list)");
    if (strcmp(ops[0], "list") == 0) {
        if (n > 1)
            return rf_opt_usage_error(&formula_cmd, "list takes nothing more ('%s')", ops[1]);
        for (size_t i = 0; i < rf_formula_count(); i++) {
            const RfFormula *f = rf_formula_at(i);
            printf("%-22s §%-7s %s\n", f->id, f->section, f->summary);
        }
        return RF_EXIT_OK;
    }
    const RfFormula *f = rf_formula_find(ops[0]);
    if (!f)
        return unknown_id(ops[0]);
    char err[512];
    char *in = rf_formula_args_to_json(n - 1, ops + 1, err, sizeof err);
    if (!in) {
        fprintf(stderr, "refray formula %s: %s\n", f->id, err);
        return RF_EXIT_USAGE;
    }
    char *out = NULL;
    RfFormulaResult rc = (RfFormulaResult)rf_formula_run_json(f, in, &out);
    if (rc)
        fprintf(stderr, "refray formula %s: %s\n", f->id, out ? out : "out of memory");
    else
        rf_formula_print(f, out, opt.format, opt.digits, stdout);
    free(in);
    free(out);
    return exit_code(rc);
}
