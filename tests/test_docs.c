/* The documentation's examples are what the commands print (issue 17: they must not drift):
 * every `$ refray...` line (refray-raster, refray-view and the others too) in a fenced block of
 * README.md and of every .md file in docs/ is run from a scratch folder holding scenes/, docs/, out/ and
 * the files the examples name (tests/data/docs/), and the lines below it, up to the next `$ `
 * line or the fence, must be its whole output (stdout and stderr), line for line; a command
 * continued with a trailing backslash is one command. The normalisation, and nothing else:
 *  - a line `...` stands for any number of lines (an example that shows only the start of a
 *    long output ends with it);
 *  - `…` within a line stands for any text (a value that depends on the machine or the date);
 *  - run times, rays per second, the idle share and the thread count (numbers before " s",
 *    " Mrays/s", " % idle", " thread(s)") are compared as "#";
 *  - trailing blanks of a line and blank lines at the end of an example do not count.
 * Every other character must match. `$ ` lines of other programs (make, cc) end an example and
 * are not run. */
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

/* Does one masked actual line match one masked expected line, where `…` stands for any text? */
static int line_matches(const char *e, const char *a)
{
    static const char ell[] = "\xe2\x80\xa6"; /* … */
    const char *star = strstr(e, ell);
    if (!star)
        return strcmp(e, a) == 0;
    size_t head = (size_t)(star - e);
    if (strncmp(e, a, head) != 0)
        return 0;
    const char *rest = star + 3;
    for (const char *t = a + head;; t++) { /* the shortest text that lets the rest match */
        if (line_matches(rest, t))
            return 1;
        if (!*t)
            return 0;
    }
}

/* Is `actual` (the command's output) `expected` (the example's lines, '\n'-separated) under the
 * normalisation above? */
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
            if (line_matches(me, ma))
                break;
            if (!skipping) {
                snprintf(why, cap, "expected: %s\n    printed:  %s", el, al);
                return 0;
            }
        }
        skipping = 0;
    }
    if (!skipping && a[strspn(a, "\n")]) { /* more output than the example shows */
        size_t j = strcspn(a + strspn(a, "\n"), "\n");
        snprintf(why, cap, "printed more than the example shows (end it with a line '...'), from: %.*s", (int)j,
                 a + strspn(a, "\n"));
        return 0;
    }
    return 1;
}

/* Runs one example (its command line from "$ refray" on, its expected lines) from dir. */
static void run_example(const char *md, int line, const char *cmd, char *expected, const char *bin, const char *dir)
{
    size_t n = strlen(expected);
    while (n > 0 && expected[n - 1] == '\n' && (n == 1 || expected[n - 2] == '\n'))
        expected[--n] = 0; /* blank lines at the end do not count */
    static char full[1 << 15];
    char why[9000];
    int rc;
    snprintf(full, sizeof full, "cd '%s' && %s%s 2>&1", dir, bin, cmd + 8);
    const char *out = rf_test_run(full, &rc);
    rf_test_checks++;
    if (!output_matches(expected, out, why, sizeof why))
        rf_test_fail(md, line, "`%s`:\n    %s", cmd + 2, why);
}

/* Runs the examples of one markdown file; returns how many ran. */
static int check_file(const char *md, const char *bin, const char *dir)
{
    FILE *f = fopen(md, "r");
    if (!f) {
        rf_test_fail(__FILE__, __LINE__, "cannot open %s", md);
        return 0;
    }
    static char line[8192], cmd[1 << 14], expected[1 << 16];
    int in_block = 0, have = 0, count = 0, lineno = 0, cmd_line = 0, continued = 0;
    for (;;) {
        char *got = fgets(line, sizeof line, f);
        if (got)
            lineno++;
        int fence = got && strncmp(line, "```", 3) == 0;
        int dollar = got && in_block && strncmp(line, "$ ", 2) == 0 && !continued;
        if (have && !continued && (!got || fence || dollar)) {
            run_example(md, cmd_line, cmd, expected, bin, dir);
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
        size_t len = strlen(line);
        if (continued) { /* the command goes on */
            continued = len > 0 && line[len - 1] == '\\';
            if (have) {
                size_t n = strlen(cmd);
                snprintf(cmd + n, sizeof cmd - n, "%.*s", (int)(len - (size_t)continued), line);
            }
        } else if (dollar) {
            continued = len > 0 && line[len - 1] == '\\';
            have = strncmp(line, "$ refray", 8) == 0;
            snprintf(cmd, sizeof cmd, "%.*s", (int)(len - (size_t)continued), line);
            expected[0] = 0;
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

/* The matcher itself: masking, "...", "…", a changed number, a missing line, a line too many. */
static void t_doc_matcher(void)
{
    char why[512];
    RF_CHECK(output_matches("a 1.5 s, 3 Mrays/s, 2 threads (0.1 % idle)\n",
                            "a 0.25 s, 12.5 Mrays/s, 8 threads (3.0 % idle)\n", why, sizeof why));
    RF_CHECK(!output_matches("trace 0.1 s, 7 spp\n", "trace 0.1 s, 8 spp\n", why, sizeof why));
    RF_CHECK(!output_matches("x 0.1\n", "x 0.2\n", why, sizeof why));
    RF_CHECK(output_matches("one\n...\nfour\n...\n", "one\ntwo\nthree\nfour\nfive\n", why, sizeof why));
    RF_CHECK(!output_matches("one\n...\nfour\n", "one\ntwo\nthree\nfour\nfive\n", why, sizeof why));
    RF_CHECK(!output_matches("one\nfour\n", "one\ntwo\nfour\n", why, sizeof why));
    RF_CHECK(!output_matches("one\n...\nsix\n", "one\ntwo\n", why, sizeof why));
    /* strict: the whole output, unless the example ends with "..." */
    RF_CHECK(!output_matches("one\n", "one\ntwo\n", why, sizeof why));
    RF_CHECK(output_matches("one\n...\n", "one\ntwo\n", why, sizeof why));
    RF_CHECK(output_matches("one\n\ntwo\n", "one\n\ntwo\n\n", why, sizeof why));
    RF_CHECK(!output_matches("one\ntwo\n", "one\n\ntwo\n", why, sizeof why));
    /* "…" within a line: any text, the rest exact */
    RF_CHECK(output_matches("written /tmp/\xe2\x80\xa6/a.exr at \xe2\x80\xa6\n", "written /tmp/x1y/a.exr at 12:00\n", why,
                            sizeof why));
    RF_CHECK(!output_matches("written /tmp/\xe2\x80\xa6/a.exr\n", "written /tmp/x1y/b.exr\n", why, sizeof why));
}

/* The README, the docs users read (all but the generated docs/api.md, whose header comments cite
 * the design notes for developers) and the comparator's report (compare/report.sh and its notes)
 * point only to files in the repository: no "../" path, and every NAME.md they name exists (as given, or in docs/). */
static void t_doc_no_outside_refs(void)
{
    static const char *const files[] = {"README.md",          "compare/report.sh",   "compare/report-notes.txt",
                                        "scenes/README.md",   "docs/color.md",       "docs/compare.md",
                                        "docs/crosscheck.md", "docs/formulas.md",    "docs/performance.md",
                                        "docs/scene-format.md", "docs/verify.md"};
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
