/* The documentation's examples are what the commands print: every `$ refray ...` line in a
 * fenced block of README.md and docs/ (every .md there) is run (from a scratch folder holding scenes/, docs/ and the
 * files the examples name, tests/data/docs/), and the lines below it must be its output
 * (stdout and stderr), in order. A line `...` stands for any number of lines; the example may
 * stop before the output does. Trailing blanks do not count. Run times, rays per second, the idle share and the thread count
 * (which depend on the machine) are compared as "#"; every other character must match. */
#define _XOPEN_SOURCE 700
#include <dirent.h>
#include <limits.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "rf_test.h"

/* Copies s into out with each machine-dependent number (before " s", " Mrays/s", " % idle",
 * " threads", " thread") replaced by '#'. */
static void mask_line(const char *s, char *out, size_t cap)
{
    static const char *const units[] = {" s", " Mrays/s", " % idle", " threads", " thread"};
    size_t n = 0;
    while (*s && n + 2 < cap) {
        if ((*s >= '0' && *s <= '9') && (n == 0 || out[n - 1] == ' ' || out[n - 1] == '(')) {
            const char *e = s;
            while ((*e >= '0' && *e <= '9') || *e == '.')
                e++;
            int masked = 0;
            for (size_t u = 0; u < sizeof units / sizeof units[0] && !masked; u++) {
                size_t k = strlen(units[u]);
                char after = e[k];
                masked = strncmp(e, units[u], k) == 0 && !(after >= 'a' && after <= 'z') && after != '/';
            }
            if (masked) {
                out[n++] = '#';
                s = e;
                continue;
            }
            while (s < e && n + 2 < cap)
                out[n++] = *s++;
            continue;
        }
        out[n++] = *s++;
    }
    while (n > 0 && out[n - 1] == ' ') /* trailing blanks: invisible in markdown */
        n--;
    out[n] = 0;
}

/* Does `actual` (the command's output) show `expected` (the example's lines, '\n'-separated)? */
static int output_matches(const char *expected, const char *actual, char *why, size_t cap)
{
    char el[4096], al[4096], me[4096], ma[4096];
    const char *e = expected, *a = actual;
    int skipping = 0;
    while (*e) {
        size_t k = strcspn(e, "\n");
        snprintf(el, sizeof el, "%.*s", (int)k, e);
        e += k + (e[k] == '\n');
        if (strspn(el, " ") + 3 == strlen(el) && strcmp(el + strlen(el) - 3, "...") == 0) {
            skipping = 1;
            continue;
        }
        mask_line(el, me, sizeof me);
        for (;;) {
            if (!*a) {
                snprintf(why, cap, "line not printed: %s", el);
                return 0;
            }
            size_t j = strcspn(a, "\n");
            snprintf(al, sizeof al, "%.*s", (int)j, a);
            a += j + (a[j] == '\n');
            mask_line(al, ma, sizeof ma);
            if (strcmp(me, ma) == 0)
                break;
            if (!skipping) {
                snprintf(why, cap, "expected: %s\n    printed:  %s", el, al);
                return 0;
            }
        }
        skipping = 0;
    }
    return 1;
}

/* Runs the examples of one markdown file; returns how many ran. */
static int check_file(const char *md, const char *bin, const char *dir)
{
    FILE *f = fopen(md, "r");
    if (!f) {
        rf_test_fail(__FILE__, __LINE__, "cannot open %s", md);
        return 0;
    }
    char line[8192], cmd[8192] = "", expected[1 << 15] = "";
    int in_block = 0, have = 0, count = 0, lineno = 0, cmd_line = 0;
    for (;;) {
        char *got = fgets(line, sizeof line, f);
        if (got)
            lineno++;
        int fence = got && strncmp(line, "```", 3) == 0;
        int start = got && in_block && strncmp(line, "$ refray", 8) == 0;
        int blank = got && in_block && line[0] == '\n';
        if (have && (!got || fence || start || blank)) {
            char full[10000], why[9000];
            int rc;
            snprintf(full, sizeof full, "cd '%s' && %s%s 2>&1", dir, bin, cmd + 8);
            const char *out = rf_test_run(full, &rc);
            rf_test_checks++;
            if (!output_matches(expected, out, why, sizeof why))
                rf_test_fail(md, cmd_line, "`%s`:\n    %s", cmd + 2, why);
            count++;
            have = 0;
        }
        if (!got)
            break;
        line[strcspn(line, "\n")] = 0;
        if (fence) {
            in_block = !in_block;
            continue;
        }
        if (start) {
            snprintf(cmd, sizeof cmd, "%s", line);
            expected[0] = 0;
            have = 1;
            cmd_line = lineno;
        } else if (have) {
            size_t n = strlen(expected);
            snprintf(expected + n, sizeof expected - n, "%s\n", line);
        }
    }
    fclose(f);
    return count;
}

static void t_doc_examples(void)
{
    char bin[PATH_MAX], root[PATH_MAX], data[PATH_MAX], dir[] = "/tmp/refray-docs-XXXXXX", sh[3 * PATH_MAX + 200];
    int rc;
    if (!realpath(rf_test_bin(), bin) || !realpath(".", root) || !realpath(rf_test_data("docs"), data) || !mkdtemp(dir)) {
        rf_test_fail(__FILE__, __LINE__, "cannot set up the scratch folder (binary, tests/data/docs)");
        return;
    }
    snprintf(sh, sizeof sh, "ln -s '%s/scenes' '%s/scenes' && ln -s '%s/docs' '%s/docs' && cp '%s'/* '%s'/ && mkdir '%s/out'",
             root, dir, root, dir, data, dir, dir);
    rf_test_run(sh, &rc);
    RF_CHECK_EQ_INT(rc, 0);
    int count = check_file("README.md", bin, dir);
    DIR *d = opendir("docs");
    struct dirent *e;
    while (d && (e = readdir(d))) {
        size_t k = strlen(e->d_name);
        if (k > 3 && strcmp(e->d_name + k - 3, ".md") == 0) {
            char md[PATH_MAX];
            snprintf(md, sizeof md, "docs/%s", e->d_name);
            count += check_file(md, bin, dir);
        }
    }
    if (d)
        closedir(d);
    RF_CHECK(count >= 25); /* the README's and docs/color.md's examples at the time of writing */
    snprintf(sh, sizeof sh, "rm -rf '%s'", dir);
    rf_test_run(sh, &rc);
}

/* The matcher itself: masking, "...", a changed number and a missing line. */
static void t_doc_matcher(void)
{
    char why[512];
    RF_CHECK(output_matches("a 1.5 s, 3 Mrays/s, 2 threads (0.1 % idle)\n",
                            "a 0.25 s, 12.5 Mrays/s, 8 threads (3.0 % idle)\n", why, sizeof why));
    RF_CHECK(!output_matches("trace 0.1 s, 7 spp\n", "trace 0.1 s, 8 spp\n", why, sizeof why));
    RF_CHECK(!output_matches("x 0.1\n", "x 0.2\n", why, sizeof why));
    RF_CHECK(output_matches("one\n...\nfour\n", "one\ntwo\nthree\nfour\nfive\n", why, sizeof why));
    RF_CHECK(!output_matches("one\nfour\n", "one\ntwo\nfour\n", why, sizeof why));
    RF_CHECK(!output_matches("one\n...\nsix\n", "one\ntwo\n", why, sizeof why));
}

/* The README and the comparator's report (compare/report.sh and its notes) point only to files in
 * the repository: no "../" path, and every NAME.md they name exists (as given, or in docs/). */
static void t_doc_no_outside_refs(void)
{
    static const char *const files[] = {"README.md", "compare/report.sh", "compare/report-notes.txt"};
    for (size_t i = 0; i < sizeof files / sizeof files[0]; i++) {
        FILE *f = fopen(files[i], "r");
        char line[8192];
        int lineno = 0;
        RF_CHECK(f != NULL);
        while (f && fgets(line, sizeof line, f)) {
            lineno++;
            rf_test_checks++;
            if (strstr(line, "../"))
                rf_test_fail(files[i], lineno, "a path outside the repository: %s", line);
            for (char *p = line; (p = strstr(p, ".md")) != NULL; p += 3) {
                char *b = p;
                while (b > line && (strchr("_-./", b[-1]) || (b[-1] >= 'a' && b[-1] <= 'z') ||
                                    (b[-1] >= 'A' && b[-1] <= 'Z') || (b[-1] >= '0' && b[-1] <= '9')))
                    b--;
                char name[512], in_docs[600];
                snprintf(name, sizeof name, "%.*s.md", (int)(p - b), b);
                snprintf(in_docs, sizeof in_docs, "docs/%s", name);
                FILE *g = p > b ? fopen(name, "r") : NULL;
                if (!g && p > b)
                    g = fopen(in_docs, "r");
                rf_test_checks++;
                if (p > b && !g)
                    rf_test_fail(files[i], lineno, "%s is not a file of the repository", name);
                if (g)
                    fclose(g);
            }
        }
        if (f)
            fclose(f);
    }
}

const RfTest rf_tests_docs[] = {
    {"docs_example_matcher", t_doc_matcher},
    {"docs_examples_print_what_they_say", t_doc_examples},
    {"docs_no_pointers_outside_the_repository", t_doc_no_outside_refs},
    RF_TEST_END,
};
