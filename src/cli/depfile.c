/* refray render --deps: the make dependency file of a render (depfile.h). */
#include "depfile.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Appends s escaped for a make rule to buf (NULL: only counts); returns the length. */
static size_t put_name(char *buf, const char *s)
{
    size_t n = 0;
    for (; *s; s++) {
        if (*s == ' ' || *s == '#') {
            if (buf)
                buf[n] = '\\';
            n++;
        } else if (*s == '$') {
            if (buf)
                buf[n] = '$';
            n++;
        }
        if (buf)
            buf[n] = *s;
        n++;
    }
    return n;
}

/* The whole text into buf (NULL: only counts); returns its length. */
static size_t layout(char *buf, const char *const *targets, int n_targets, char *const *prereqs, size_t n_prereqs)
{
    size_t n = 0;
    int first = 1;
    for (int i = 0; i < n_targets; i++)
        if (targets[i]) {
            if (!first && buf)
                buf[n] = ' ';
            n += !first;
            n += put_name(buf ? buf + n : NULL, targets[i]);
            first = 0;
        }
    if (buf)
        buf[n] = ':';
    n++;
    for (size_t i = 0; i < n_prereqs; i++) {
        if (buf)
            buf[n] = ' ';
        n++;
        n += put_name(buf ? buf + n : NULL, prereqs[i]);
    }
    if (buf)
        buf[n] = '\n';
    n++;
    for (size_t i = 0; i < n_prereqs; i++) { /* after a blank line each, as gcc -MP writes them */
        if (buf)
            buf[n] = '\n';
        n++;
        n += put_name(buf ? buf + n : NULL, prereqs[i]);
        if (buf)
            memcpy(buf + n, ":\n", 2);
        n += 2;
    }
    return n;
}

char *rf_depfile_text(const char *const *targets, int n_targets, char *const *prereqs, size_t n_prereqs)
{
    size_t n = layout(NULL, targets, n_targets, prereqs, n_prereqs);
    char *buf = malloc(n + 1);
    if (!buf)
        return NULL;
    layout(buf, targets, n_targets, prereqs, n_prereqs);
    buf[n] = 0;
    return buf;
}

int rf_depfile_write(const char *path, const char *text, char *err, size_t errsz)
{
    size_t n = strlen(path);
    char *tmp = malloc(n + 16);
    if (!tmp) {
        snprintf(err, errsz, "%s: out of memory", path);
        return 0;
    }
    snprintf(tmp, n + 16, "%s.tmp", path);
    FILE *f = fopen(tmp, "wb");
    int ok = f && fputs(text, f) >= 0;
    if (f && fclose(f) != 0)
        ok = 0;
    if (ok && rename(tmp, path) != 0)
        ok = 0;
    if (!ok) {
        snprintf(err, errsz, "cannot write %s: %s", path, strerror(errno ? errno : EIO));
        remove(tmp);
    }
    free(tmp);
    return ok;
}
