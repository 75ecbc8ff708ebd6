/* `refray formula`: list, one case from key=value arguments, --batch, ID --help. */
#include "cli.h"

#include <stdlib.h>
#include <string.h>

#include "refray/formula.h"

static void usage(FILE *out)
{
    fprintf(out,
            "usage: refray formula list\n"
            "       refray formula ID key=value ...   (prints one JSON object)\n"
            "       refray formula ID --help\n"
            "       refray formula --batch < cases.jsonl   (one JSON line per case)\n");
}

int rf_cmd_formula(int argc, char **argv)
{
    if (argc < 2) {
        usage(stderr);
        return 2;
    }
    const char *what = argv[1];
    if (strcmp(what, "--help") == 0 || strcmp(what, "-h") == 0) {
        usage(stdout);
        return 0;
    }
    if (strcmp(what, "list") == 0) {
        for (size_t i = 0; i < rf_formula_count(); i++) {
            const RfFormula *f = rf_formula_at(i);
            printf("%-22s §%-7s %s\n", f->id, f->section, f->summary);
        }
        return 0;
    }
    if (strcmp(what, "--batch") == 0) {
        int failed = rf_formula_batch(stdin, stdout);
        if (failed)
            fprintf(stderr, "refray formula: %d case%s failed (see their \"error\" lines)\n", failed,
                    failed == 1 ? "" : "s");
        return failed ? 1 : 0;
    }
    const RfFormula *f = rf_formula_find(what);
    if (!f) {
        fprintf(stderr, "refray formula: unknown id '%s' (see: refray formula list)\n", what);
        return 2;
    }
    for (int i = 2; i < argc; i++)
        if (strcmp(argv[i], "--help") == 0 || strcmp(argv[i], "-h") == 0) {
            rf_formula_help(f, stdout);
            return 0;
        }
    char err[512];
    char *in = rf_formula_args_to_json(argc - 2, argv + 2, err, sizeof err);
    if (!in) {
        fprintf(stderr, "refray formula %s: %s\n", f->id, err);
        return 2;
    }
    char *out = NULL;
    int rc = rf_formula_run_json(f, in, &out);
    if (rc)
        fprintf(stderr, "refray formula %s: %s\n", f->id, out ? out : "out of memory");
    else
        printf("%s\n", out);
    free(in);
    free(out);
    return rc ? 1 : 0;
}
