/* Shared by tiles, checkpoints and merging (farm.h). */
#include "farm.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

const char *const rf_farm_identity[3] = {"refray:version", "refray:sceneHash", "refray:settings"};

int rf_farm_tile_rect(int n, int k, int w, int h, RfTile *out, char *err, size_t errsz)
{
    if (n < 1 || k < 0 || k >= n) {
        snprintf(err, errsz, "--tile %d is not in [0, %d) (tiles are numbered from 0)", k, n);
        return 0;
    }
    int c = 1;
    for (int d = 1; (long)d * d <= n; d++)
        if (n % d == 0)
            c = d;
    int r = n / c;
    if (r > h || c > w) {
        snprintf(err, errsz, "%d tiles make a grid of %d rows x %d columns, more than the %dx%d image has", n, r, c,
                 w, h);
        return 0;
    }
    int i = k / c, j = k % c;
    out->x0 = (int)((long long)j * w / c);
    out->x1 = (int)((long long)(j + 1) * w / c);
    out->y0 = (int)((long long)i * h / r);
    out->y1 = (int)((long long)(i + 1) * h / r);
    out->index = k;
    return 1;
}

char *rf_farm_ranges_format(const unsigned char *done, int n)
{
    size_t cap = 64, len = 0;
    char *s = malloc(cap);
    if (!s)
        return NULL;
    s[0] = 0;
    for (int i = 0; i < n;) {
        if (!done[i]) {
            i++;
            continue;
        }
        int j = i;
        while (j + 1 < n && done[j + 1])
            j++;
        if (len + 32 > cap) {
            char *t = realloc(s, cap *= 2);
            if (!t) {
                free(s);
                return NULL;
            }
            s = t;
        }
        len += (size_t)snprintf(s + len, cap - len, j > i ? "%s%d-%d" : "%s%d", len ? "," : "", i, j);
        i = j + 1;
    }
    return s;
}

int rf_farm_ranges_parse(const char *s, unsigned char *done, int n)
{
    memset(done, 0, (size_t)n);
    while (*s) {
        char *end;
        long a = strtol(s, &end, 10), b = a;
        if (end == s || a < 0)
            return 0;
        s = end;
        if (*s == '-') {
            b = strtol(s + 1, &end, 10);
            if (end == s + 1 || b < a)
                return 0;
            s = end;
        }
        if (b >= n)
            return 0;
        for (long i = a; i <= b; i++)
            done[i] = 1;
        if (*s == ',')
            s++;
        else if (*s)
            return 0;
    }
    return 1;
}

char *rf_farm_attr(const char *path, const char *name)
{
    char *v = NULL, err[256];
    return rf_exr_read_attr(path, name, &v, err, sizeof err) == RF_OK ? v : NULL;
}

int rf_farm_same_render(const char *path, const char *const expect[3], int w, int h, char *err, size_t errsz)
{
    RfExrWindow disp;
    if (rf_exr_read_windows(path, NULL, &disp, err, errsz) != RF_OK)
        return 0;
    if (disp.x0 != 0 || disp.y0 != 0 || disp.x1 != w || disp.y1 != h) {
        snprintf(err, errsz, "%s: the whole image is %dx%d there, not %dx%d: another render", path, disp.x1 - disp.x0,
                 disp.y1 - disp.y0, w, h);
        return 0;
    }
    for (int i = 0; i < 3; i++) {
        char *v = rf_farm_attr(path, rf_farm_identity[i]);
        int same = v && strcmp(v, expect[i]) == 0;
        if (!same)
            snprintf(err, errsz, "%s: %s is \"%s\", not \"%s\": another render", path, rf_farm_identity[i],
                     v ? v : "(missing)", expect[i]);
        free(v);
        if (!same)
            return 0;
    }
    return 1;
}
