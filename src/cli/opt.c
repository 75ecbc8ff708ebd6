/* The shared command-line parser (opt.h). getopt_long keeps its position in libc's optind; a
 * command parses its arguments once, and rf_opt_init starts getopt_long afresh (optind = 0). */
#include "opt.h"
#include "exit_codes.h"

#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

#include "refray/version.h"

enum { KEY_HELP = 'h', KEY_VERSION = 'V' };

static const RfOpt common[] = {
    {"help", KEY_HELP, NULL, "print this help and exit", NULL},
    {"version", KEY_VERSION, NULL, "print the version and exit", NULL},
    RF_OPT_TABLE_END,
};

void rf_opt_init(RfOptParser *p, const RfCommand *cmd, int argc, char **argv)
{
    memset(p, 0, sizeof *p);
    p->cmd = cmd, p->argc = argc, p->argv = argv;
    char *s = p->shorts;
    *s++ = ':'; /* a missing value returns ':', told apart from an unknown option */
    for (int t = 0; t == 0 || cmd->tables[t - 1]; t++) /* the tables, then (at their NULL) common */
        for (const RfOpt *o = cmd->tables[t] ? cmd->tables[t] : common; o->name && p->n < RF_OPT_MAX; o++) {
            p->entries[p->n] = o;
            p->longs[p->n] = (struct option){o->name, o->value ? required_argument : no_argument, NULL, o->key};
            p->n++;
            if (o->key < RF_OPT_ID) {
                *s++ = (char)o->key;
                if (o->value)
                    *s++ = ':';
            }
        }
    *s = 0;
    p->longs[p->n] = (struct option){NULL, 0, NULL, 0};
    optind = 0; /* glibc: start afresh */
    opterr = 0; /* the messages are ours */
}

static const RfOpt *find_key(const RfOptParser *p, int key)
{
    for (int i = 0; i < p->n; i++)
        if (p->entries[i]->key == key)
            return p->entries[i];
    return NULL;
}

/* Optimal string alignment distance (Damerau-Levenshtein without repeated edits of a substring). */
static int distance(const char *a, const char *b)
{
    size_t m = strlen(a), n = strlen(b);
    if (m > 64 || n > 64)
        return 1 << 20;
    int d[65][65];
    for (size_t i = 0; i <= m; i++)
        d[i][0] = (int)i;
    for (size_t j = 0; j <= n; j++)
        d[0][j] = (int)j;
    for (size_t i = 1; i <= m; i++)
        for (size_t j = 1; j <= n; j++) {
            int cost = a[i - 1] != b[j - 1];
            int v = d[i - 1][j] + 1;
            if (d[i][j - 1] + 1 < v)
                v = d[i][j - 1] + 1;
            if (d[i - 1][j - 1] + cost < v)
                v = d[i - 1][j - 1] + cost;
            if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1] && d[i - 2][j - 2] + 1 < v)
                v = d[i - 2][j - 2] + 1;
            d[i][j] = v;
        }
    return d[m][n];
}

int rf_suggest(const char *word, const char *const *candidates, int n)
{
    size_t len = strlen(word);
    int limit = len <= 4 ? 1 : len <= 8 ? 2 : 3, best = -1, best_d = limit + 1;
    for (int i = 0; i < n; i++) {
        int d = distance(word, candidates[i]);
        if (d < best_d)
            best = i, best_d = d;
    }
    return best;
}

/* The message for getopt_long's '?' or ':' (the offending word is argv[optind - 1]). */
static void report(const RfOptParser *p, int c)
{
    const char *prog = p->cmd->prog;
    const char *word = optind > 0 && optind <= p->argc ? p->argv[optind - 1] : "";
    int is_long = strncmp(word, "--", 2) == 0;
    if (c == ':') {
        const RfOpt *o = find_key(p, optopt);
        if (o)
            fprintf(stderr, "%s: %s%s needs a value (%s)", prog, o->key < RF_OPT_ID && !is_long ? "-" : "--",
                    o->key < RF_OPT_ID && !is_long ? (char[2]){(char)o->key, 0} : o->name,
                    o->expect ? o->expect : o->value);
        else
            fprintf(stderr, "%s: %s needs a value", prog, word);
    } else if (!is_long) {
        fprintf(stderr, "%s: unknown option '-%c'", prog, optopt ? optopt : '?');
    } else {
        const char *name = word + 2;
        size_t len = strcspn(name, "=");
        const char *names[RF_OPT_MAX];
        int matches = 0, exact = -1;
        for (int i = 0; i < p->n; i++) {
            names[i] = p->entries[i]->name;
            if (strncmp(names[i], name, len) == 0) {
                matches++;
                if (names[i][len] == 0)
                    exact = i;
            }
        }
        if ((exact >= 0 || matches == 1) && name[len] == '=') {
            fprintf(stderr, "%s: --%.*s takes no value", prog, (int)len, name);
        } else if (matches > 1) {
            fprintf(stderr, "%s: option '--%.*s' is ambiguous; possibilities:", prog, (int)len, name);
            for (int i = 0; i < p->n; i++)
                if (strncmp(names[i], name, len) == 0)
                    fprintf(stderr, " --%s", names[i]);
        } else {
            char buf[128];
            snprintf(buf, sizeof buf, "%.*s", (int)len, name);
            int s = rf_suggest(buf, names, p->n);
            fprintf(stderr, "%s: unknown option '--%s'", prog, buf);
            if (s >= 0)
                fprintf(stderr, "; did you mean '--%s'?", names[s]);
        }
    }
    fprintf(stderr, " (see: %s --help)\n", prog);
}

int rf_opt_next(RfOptParser *p)
{
    int c = getopt_long(p->argc, p->argv, p->shorts, p->longs, NULL);
    p->value = optarg;
    p->current = NULL;
    if (c == -1) {
        p->first_operand = optind;
        return RF_OPT_DONE;
    }
    if (c == '?' || c == ':') {
        report(p, c);
        p->exit_code = RF_EXIT_USAGE;
        return RF_OPT_EXIT;
    }
    p->current = find_key(p, c);
    if (c == KEY_HELP || c == KEY_VERSION) {
        if (c == KEY_HELP)
            rf_opt_help(p->cmd, stdout);
        else if (strncmp(p->cmd->prog, "refray", 6) == 0 && (p->cmd->prog[6] == 0 || p->cmd->prog[6] == ' '))
            printf("refray %s\n", RF_VERSION);
        else
            printf("%s (refray) %s\n", p->cmd->prog, RF_VERSION);
        p->exit_code = RF_EXIT_OK;
        return RF_OPT_EXIT;
    }
    return c;
}

int rf_opt_operands(const RfOptParser *p, char ***operands)
{
    *operands = p->argv + p->first_operand;
    return p->argc - p->first_operand;
}

int rf_opt_operand(const RfOptParser *p, const char *what, const char **operand)
{
    char **ops;
    int n = rf_opt_operands(p, &ops), want = what != NULL;
    if (n < want)
        return rf_opt_usage_error(p->cmd, "missing %s", what);
    if (n > want)
        return what ? rf_opt_usage_error(p->cmd, "unexpected '%s' after %s '%s'", ops[1], what, ops[0])
                    : rf_opt_usage_error(p->cmd, "unexpected '%s': it takes options only", ops[0]);
    if (operand)
        *operand = want ? ops[0] : NULL;
    return 0;
}

int rf_opt_bad_value(const RfOptParser *p)
{
    const RfOpt *o = p->current;
    fprintf(stderr, "%s: bad value '%s' for --%s: %s\n", p->cmd->prog, p->value ? p->value : "", o ? o->name : "?",
            o && o->expect ? o->expect : "see --help");
    return RF_EXIT_USAGE;
}

int rf_opt_usage_error(const RfCommand *cmd, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    fprintf(stderr, "%s: ", cmd->prog);
    vfprintf(stderr, fmt, ap);
    va_end(ap);
    fprintf(stderr, " (see: %s --help)\n", cmd->prog);
    return RF_EXIT_USAGE;
}

/* One option's line: "  -o, --output FILE" padded to the description's column. */
static void help_line(FILE *out, const RfOpt *o)
{
    char head[128];
    int n = snprintf(head, sizeof head, "  %s%c%s--%s%s%s", o->key < RF_OPT_ID ? "-" : "",
                     o->key < RF_OPT_ID ? o->key : ' ', o->key < RF_OPT_ID ? ", " : "", o->name,
                     o->value ? " " : "", o->value ? o->value : "");
    if (o->key >= RF_OPT_ID) /* no short form: no gap where it would be */
        n = snprintf(head, sizeof head, "  --%s%s%s", o->name, o->value ? " " : "", o->value ? o->value : "");
    fprintf(out, "%s%*s%s\n", head, n < 28 ? 28 - n : 2, "", o->help);
}

void rf_opt_help(const RfCommand *cmd, FILE *out)
{
    fprintf(out, "usage: %s\n", cmd->synopsis);
    if (cmd->about)
        fprintf(out, "%s", cmd->about);
    fprintf(out, "\noptions:\n");
    for (int t = 0; cmd->tables[t]; t++)
        for (const RfOpt *o = cmd->tables[t]; o->name; o++)
            help_line(out, o);
    for (const RfOpt *o = common; o->name; o++)
        help_line(out, o);
    if (cmd->notes)
        fprintf(out, "\n%s", cmd->notes);
}
