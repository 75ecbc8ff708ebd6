/* The command-line parser of every refray command (getopt_long underneath): GNU conventions
 * (--opt=value, --opt value, unique prefixes, --, options and operands in any order), -h/--help
 * and -V/--version everywhere, "did you mean" for a mistyped option, and the --help text made
 * from the same table, so that the help lists every option in one regular format
 * ("  -o, --output FILE      description"; man pages and bash completion are made from it).
 * A command's table is a list of fragments: its own options plus shared ones (args.h). */
#ifndef REFRAY_CLI_OPT_H
#define REFRAY_CLI_OPT_H

#include <getopt.h>
#include <stdio.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef struct {
    const char *name;   /* the long name, without "--" */
    int key;            /* a short option's letter ('o'), or an id >= RF_OPT_ID (long only) */
    const char *value;  /* the value's name in --help ("N", "FILE"); NULL: takes no value */
    const char *help;   /* one line for --help */
    const char *expect; /* what a good value is, for the message on a bad one (NULL: see --help) */
} RfOpt;

#define RF_OPT_ID 256 /* first id of long-only options; shared fragments use ids from 0x1000 */
#define RF_OPT_TABLE_END {NULL, 0, NULL, NULL, NULL}

typedef struct {
    const char *prog;            /* "refray render": the prefix of every message */
    const char *synopsis;        /* the usage line(s) after "usage: " */
    const char *about;           /* what the command does, printed after the usage (or NULL) */
    const RfOpt *const *tables;  /* the option fragments, NULL-terminated */
    const char *notes;           /* more text after the option list (or NULL) */
} RfCommand;

enum { RF_OPT_MAX = 96 };

typedef struct {
    const RfCommand *cmd;
    int argc;
    char **argv;
    const char *value;     /* the current option's value (NULL for a flag) */
    const RfOpt *current;  /* the current option's entry */
    int exit_code;         /* with RF_OPT_EXIT: what the command returns */
    int n, first_operand;
    const RfOpt *entries[RF_OPT_MAX];
    struct option longs[RF_OPT_MAX + 1];
    char shorts[2 * RF_OPT_MAX + 4];
} RfOptParser;

enum {
    RF_OPT_DONE = -1, /* no more options: rf_opt_operands gives the operands */
    RF_OPT_EXIT = -2  /* --help or --version printed, or a usage error reported: return exit_code */
};

void rf_opt_init(RfOptParser *p, const RfCommand *cmd, int argc, char **argv);
/* The next option's key (RfOpt.key) with p->value set; RF_OPT_DONE or RF_OPT_EXIT. */
int rf_opt_next(RfOptParser *p);
/* After RF_OPT_DONE: the number of operands and *operands (in the order given, options removed). */
int rf_opt_operands(const RfOptParser *p, char ***operands);

/* After RF_OPT_DONE, for the commands that take one operand (what: "the scene file") or none
 * (what NULL): *operand set and 0, or the exit code after "PROG: missing the scene file" or
 * "PROG: unexpected 'X'". */
int rf_opt_operand(const RfOptParser *p, const char *what, const char **operand);

/* "PROG: bad value 'V' for --NAME: EXPECT" for the current option; returns RF_EXIT_USAGE. */
int rf_opt_bad_value(const RfOptParser *p);
/* "PROG: MESSAGE (see: PROG --help)"; returns RF_EXIT_USAGE. */
int rf_opt_usage_error(const RfCommand *cmd, const char *fmt, ...)
#ifdef __GNUC__
    __attribute__((format(printf, 2, 3)))
#endif
    ;
/* The whole --help text. */
void rf_opt_help(const RfCommand *cmd, FILE *out);

/* The candidate closest to word by edit distance (insertions, deletions, substitutions and
 * swaps of neighbours), when it is close enough to be a typo: at most 1 edit for words up to
 * 4 letters, 2 up to 8, 3 beyond; -1 when none is. */
int rf_suggest(const char *word, const char *const *candidates, int n);

#ifdef __cplusplus
}
#endif

#endif
