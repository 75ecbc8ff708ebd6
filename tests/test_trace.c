/* refray trace (issue 16): the trace of a pixel is the renderer's own arithmetic. Its last event
 * is the value the whole render writes for that pixel, bit for bit (1 and 4 samples, every kind
 * of surface of whitted: ground, Phong sphere, mirror, glass, background), and the colours it
 * reports add up, in the kernel's order, to what each ray returns: local + sum of weight x the
 * child ray's colour. The command's JSON parses and says the same. */
#include "rf_test.h"
#include "rf_test_render.h"

#include <cJSON.h>
#include <stdlib.h>

#include "refray/render.h"
#include "refray/scene_io.h"

/* Replays the events of one ray starting at index *i (its HIT or MISS at `depth`): returns the
 * colour the kernel's arithmetic gives from the reported numbers, checks it against the RESULT. */
static RfRgb replay(const RfTestTraceLog *l, int *i, int depth, int *bad)
{
    const RfTraceEvent *e = &l->ev[*i];
    if (e->kind == RF_TRACE_MISS) {
        (*i)++;
        return e->color;
    }
    (*i)++; /* the HIT */
    RfRgb local = {0, 0, 0}, color = {0, 0, 0};
    int have_local = 0;
    while (*i < l->n) {
        e = &l->ev[*i];
        if (e->kind == RF_TRACE_LIGHT && e->depth == depth) {
            (*i)++;
        } else if (e->kind == RF_TRACE_SECONDARY && e->depth == depth) {
            RfRgb w = e->weight;
            if (!have_local) { /* the local part is reported with the result; take it there */
                int j = *i;
                while (j < l->n && !(l->ev[j].kind == RF_TRACE_RESULT && l->ev[j].depth == depth))
                    j++;
                if (j < l->n)
                    local = l->ev[j].local, color = local, have_local = 1;
            }
            (*i)++;
            RfRgb child = replay(l, i, depth + 1, bad);
            color = rf_rgb_add(color, rf_rgb_mul(w, child));
        } else if (e->kind == RF_TRACE_RESULT && e->depth == depth) {
            if (!have_local)
                color = e->local;
            *bad += memcmp(&color, &e->color, sizeof color) != 0;
            (*i)++;
            return e->color;
        } else {
            (*bad)++;
            (*i)++;
        }
    }
    (*bad)++;
    return color;
}

static void t_trace_reproduces_pixels(void)
{
    RfScene s;
    if (!rf_test_load_scene("scenes/whitted.rf", &s))
        return;
    /* (x, y) of a 160 x 120 whitted: ground, red sphere, mirror, glass, sky */
    static const int px[][2] = {{75, 75}, {35, 60}, {82, 50}, {112, 70}, {80, 5}};
    static const int spp[] = {1, 4};
    RfTestTraceLog *log = malloc(sizeof *log);
    for (int si = 0; si < 2; si++) {
        RfRenderOptions o = rf_render_options_default();
        RfRenderStats st;
        RfImage whole;
        o.width = 160, o.height = 120, o.samples = spp[si], o.threads = 2;
        RF_CHECK_EQ_INT(rf_render(&s, &o, &whole, &st), RF_OK);
        int kinds[RF_TRACE_PIXEL + 1] = {0};
        for (size_t k = 0; k < sizeof px / sizeof px[0]; k++) {
            RfImage one;
            log->n = 0;
            o.crop = (RfTile){px[k][0], px[k][1], px[k][0] + 1, px[k][1] + 1, 0};
            o.trace = rf_test_trace_collect, o.trace_ctx = log;
            RF_CHECK_EQ_INT(rf_render(&s, &o, &one, &st), RF_OK);
            RF_CHECK(log->n > 0 && log->n < RF_TEST_TRACE_MAX && log->ev[log->n - 1].kind == RF_TRACE_PIXEL);
            const float *w = whole.data + ((size_t)px[k][1] * 160 + (size_t)px[k][0]) * 3;
            float got[3] = {(float)log->ev[log->n - 1].color.r, (float)log->ev[log->n - 1].color.g,
                            (float)log->ev[log->n - 1].color.b};
            if (memcmp(got, w, sizeof got) != 0 || memcmp(one.data, w, sizeof got) != 0)
                rf_test_fail(__FILE__, __LINE__, "%d spp pixel (%d, %d): trace %.9g, render %.9g", spp[si], px[k][0],
                             px[k][1], got[0], w[0]);
            rf_test_checks++;
            /* each sample: SAMPLE, then the primary ray's events, which add up */
            int bad = 0, samples = 0;
            for (int i = 0; i < log->n;) {
                kinds[log->ev[i].kind]++;
                if (log->ev[i].kind == RF_TRACE_SAMPLE) {
                    samples++;
                    i++;
                    for (int j = i; j < log->n && log->ev[j].kind != RF_TRACE_SAMPLE; j++)
                        kinds[log->ev[j].kind]++;
                    replay(log, &i, 1, &bad);
                } else {
                    i++;
                }
            }
            RF_CHECK_EQ_INT(samples, spp[si]);
            if (bad)
                rf_test_fail(__FILE__, __LINE__, "pixel (%d, %d): %d reported colours do not add up", px[k][0], px[k][1],
                             bad);
            rf_test_checks++;
            rf_image_free(&one);
        }
        /* the mirror and the glass send secondary rays; the sky is missed; lights are traced */
        RF_CHECK(kinds[RF_TRACE_SECONDARY] > 0 && kinds[RF_TRACE_MISS] > 0 && kinds[RF_TRACE_LIGHT] > 0);
        rf_image_free(&whole);
        o.trace = NULL;
    }
    /* a trace wants one pixel */
    RfRenderOptions o = rf_render_options_default();
    RfRenderStats st;
    RfImage img;
    o.width = 16, o.height = 12, o.trace = rf_test_trace_collect, o.trace_ctx = log;
    RF_CHECK_EQ_INT(rf_render(&s, &o, &img, &st), RF_ERR_DOMAIN);
    free(log);
    rf_scene_free(&s);
}

/* The command: JSON that parses, glass with Fresnel numbers, the pixel last; errors. */
static void t_trace_command(void)
{
    char cmd[512];
    int code;
    snprintf(cmd, sizeof cmd, "%s trace scenes/whitted.rf 448 280 --json", rf_test_bin());
    const char *out = rf_test_run(cmd, &code);
    RF_CHECK_EQ_INT(code, 0);
    cJSON *j = cJSON_Parse(out);
    RF_CHECK(j != NULL);
    cJSON *ev = j ? cJSON_GetObjectItem(j, "events") : NULL;
    int n = cJSON_GetArraySize(ev), refracted = 0;
    for (int i = 0; i < n; i++) {
        cJSON *e = cJSON_GetArrayItem(ev, i), *ray = cJSON_GetObjectItem(e, "ray");
        if (ray && cJSON_IsString(ray) && strcmp(ray->valuestring, "refracted") == 0)
            refracted += cJSON_IsTrue(cJSON_GetObjectItem(e, "fresnel"));
    }
    RF_CHECK(n > 5);
    RF_CHECK(refracted > 0); /* the glass sphere: refracted rays with exact Fresnel weights */
    cJSON *last = cJSON_GetArrayItem(ev, n - 1);
    RF_CHECK(last && strcmp(cJSON_GetObjectItem(last, "event")->valuestring, "pixel") == 0);
    cJSON_Delete(j);
    snprintf(cmd, sizeof cmd, "%s trace scenes/whitted.rf 640 0 2>&1", rf_test_bin());
    out = rf_test_run(cmd, &code);
    RF_CHECK(code == 5 && strstr(out, "pixel (640, 0) is not in the 640x480 image"));
}

/* --sample S: exactly the events of sample S in the full trace (same numbers, same order), then
 * the pixel; a sample the pixel does not have is refused. */
static void t_trace_one_sample(void)
{
    char cmd[512];
    int code;
    snprintf(cmd, sizeof cmd, "%s trace scenes/whitted.rf 448 280 --width 640 --samples 4 --json", rf_test_bin());
    cJSON *all = cJSON_Parse(rf_test_run(cmd, &code));
    RF_CHECK_EQ_INT(code, 0);
    snprintf(cmd, sizeof cmd, "%s trace scenes/whitted.rf 448 280 --width 640 --samples 4 --sample=2 --json",
             rf_test_bin());
    cJSON *one = cJSON_Parse(rf_test_run(cmd, &code));
    RF_CHECK_EQ_INT(code, 0);
    RF_CHECK(all && one);
    if (all && one) {
        cJSON *ea = cJSON_GetObjectItem(all, "events"), *eo = cJSON_GetObjectItem(one, "events");
        int na = cJSON_GetArraySize(ea), no = cJSON_GetArraySize(eo), k = 0, samples = 0;
        for (int i = 0; i < na; i++) {
            cJSON *e = cJSON_GetArrayItem(ea, i);
            const char *kind = cJSON_GetObjectItem(e, "event")->valuestring;
            samples += strcmp(kind, "sample") == 0;
            if (strcmp(kind, "pixel") != 0 && cJSON_GetObjectItem(e, "sample")->valueint != 2)
                continue;
            char *a = cJSON_PrintUnformatted(e), *b = k < no ? cJSON_PrintUnformatted(cJSON_GetArrayItem(eo, k)) : NULL;
            RF_CHECK(b && strcmp(a, b) == 0);
            free(a);
            free(b);
            k++;
        }
        RF_CHECK_EQ_INT(samples, 4);
        RF_CHECK_EQ_INT(k, no);
        RF_CHECK(no > 3 && no < na);
    }
    cJSON_Delete(all);
    cJSON_Delete(one);
    snprintf(cmd, sizeof cmd, "%s trace scenes/whitted.rf 448 280 --samples 4 --sample 4 2>&1 >/dev/null",
             rf_test_bin());
    const char *out = rf_test_run(cmd, &code);
    RF_CHECK(code == 5 && strstr(out, "the pixel has 4 camera samples (0 .. 3): no sample 4"));
}

const RfTest rf_tests_trace[] = {
    {"trace_reproduces_pixels", t_trace_reproduces_pixels},
    {"trace_command", t_trace_command},
    {"trace_one_sample", t_trace_one_sample},
    RF_TEST_END,
};
