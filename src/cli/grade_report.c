/* `refray grade`'s CSV, JSON and HTML (grade_report.h). */
#include "grade_report.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cJSON.h>

int rf_grade_hist_bin(double e)
{
    if (!(e < 1.0))
        return RF_HIST_BINS - 1;
    if (e < 1e-5)
        return 0;
    int b = 1 + (int)floor((log10(e) + 5.0) * 8.0);
    return b < 1 ? 1 : b > RF_HIST_BINS - 2 ? RF_HIST_BINS - 2 : b;
}

/* A text file written under "NAME.tmp" and renamed into place when complete. */
typedef struct {
    FILE *f;
    char path[4096], tmp[4200];
} Out;

static int out_open(Out *o, const RfGradeRun *run, const char *name, char *err, size_t errsz)
{
    snprintf(o->path, sizeof o->path, "%s/%s", run->dir, name);
    snprintf(o->tmp, sizeof o->tmp, "%s.tmp", o->path);
    o->f = fopen(o->tmp, "w");
    if (!o->f)
        snprintf(err, errsz, "%s: cannot write: %s", o->tmp, strerror(errno));
    return o->f != NULL;
}

static int out_close(Out *o, char *err, size_t errsz)
{
    int bad = ferror(o->f);
    bad |= fclose(o->f) != 0;
    if (bad || rename(o->tmp, o->path) != 0) {
        snprintf(err, errsz, "%s: cannot write: %s", o->path, strerror(errno));
        remove(o->tmp);
        return 0;
    }
    return 1;
}

/* Text for HTML: & < > " escaped. */
static void html(FILE *f, const char *s)
{
    for (; *s; s++)
        switch (*s) {
        case '&': fputs("&amp;", f); break;
        case '<': fputs("&lt;", f); break;
        case '>': fputs("&gt;", f); break;
        case '"': fputs("&quot;", f); break;
        default: fputc(*s, f);
        }
}

/* One CSV field (RFC 4180): quoted when it holds a comma, quote or line break. */
static void csv(FILE *f, const char *s, const char *after)
{
    if (strpbrk(s, ",\"\r\n")) {
        fputc('"', f);
        for (; *s; s++) {
            if (*s == '"')
                fputc('"', f);
            fputc(*s, f);
        }
        fputc('"', f);
    } else {
        fputs(s, f);
    }
    fputs(after, f);
}

static const RfDiffStats *stats(const RfSubmission *s)
{
    return &s->g.diff.interior;
}

static int compared(const RfSubmission *s)
{
    return s->g.verdict <= RF_GRADE_FAIL;
}

static const char *style =
    "<style>body{font:14px sans-serif;margin:1.5em;color:#222}table{border-collapse:collapse}"
    "td,th{border:1px solid #ccc;padding:3px 8px;text-align:left;vertical-align:top}"
    "th{background:#eee;cursor:pointer}.pass{color:#070}.warn{color:#a60}.fail,.unreadable,.wrong{color:#c00}"
    "img.px{image-rendering:pixelated;image-rendering:crisp-edges}"
    "button{margin:2px}button.on{background:#333;color:#fff}.frame{overflow:auto;max-width:100%;"
    "max-height:80vh;border:1px solid #999;display:inline-block;background:#444}</style>\n";

static const char *verdict_class(RfGradeVerdict v)
{
    return v == RF_GRADE_SIZE ? "wrong" : rf_grade_verdict_name(v);
}

/* The histogram as inline SVG: bar heights on a log scale of the counts, the thresholds marked. */
static void histogram(FILE *f, const RfSubmission *s, const RfDiffOptions *o)
{
    const double W = 640, H = 180, left = 40, bottom = 30, bw = (W - left - 10) / RF_HIST_BINS;
    long top = 1;
    for (int b = 0; b < RF_HIST_BINS; b++)
        top = s->hist[b] > top ? s->hist[b] : top;
    fprintf(f, "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%g\" height=\"%g\" font-size=\"10\">\n", W, H);
    fprintf(f, "<rect x=\"0\" y=\"0\" width=\"%g\" height=\"%g\" fill=\"#fafafa\"/>\n", W, H);
    for (int b = 0; b < RF_HIST_BINS; b++) {
        double h = s->hist[b] ? (H - bottom - 10) * log10(1.0 + (double)s->hist[b]) / log10(1.0 + (double)top) : 0.0;
        fprintf(f, "<rect x=\"%.1f\" y=\"%.1f\" width=\"%.1f\" height=\"%.1f\" fill=\"#557\"><title>%ld pixels</title></rect>\n",
                left + b * bw, H - bottom - h, bw - 1, h, s->hist[b]);
    }
    /* x axis: bin 1 starts at 1e-5, 8 bins a decade */
    for (int d = -5; d <= 0; d++) {
        double x = left + (1 + (d + 5) * 8) * bw;
        fprintf(f, "<text x=\"%.1f\" y=\"%g\" text-anchor=\"middle\">1e%d</text>\n", x, H - bottom + 14, d);
    }
    fprintf(f, "<text x=\"%.1f\" y=\"%g\" text-anchor=\"middle\">0</text>\n", left + 0.5 * bw, H - bottom + 14);
    fprintf(f, "<text x=\"%g\" y=\"%g\">pixel error (largest channel |submission - reference|, display values); "
               "bar height: log of the count</text>\n", left, H - 2);
    const char *names[2] = {"warn", "fail"}, *colours[2] = {"#c90", "#c00"};
    double at[2] = {o->warn, o->fail};
    for (int k = 0; k < 2; k++) {
        if (!(at[k] > 1e-5 && at[k] < 1.0))
            continue;
        double x = left + (1 + (log10(at[k]) + 5.0) * 8.0) * bw;
        fprintf(f, "<line x1=\"%.1f\" y1=\"4\" x2=\"%.1f\" y2=\"%g\" stroke=\"%s\" stroke-dasharray=\"4 2\"/>"
                   "<text x=\"%.1f\" y=\"%d\" fill=\"%s\">%s %.3g</text>\n",
                x, x, H - bottom, colours[k], x + 3, 12 + 12 * k, colours[k], names[k], at[k]);
    }
    fprintf(f, "</svg>\n");
}

static const char *page_script =
    "<script>\n"
    "var views={r:'img/reference.png',s:'img/%s.png'%s%s%s},cur='s',zoom=%d;\n"
    "var im=document.getElementById('im');\n"
    "function show(v){if(!views[v])return;cur=v;im.src=views[v];for(var k in views){var b=document.getElementById('b'+k);"
    "if(b)b.className=k==v?'on':'';}}\n"
    "function setzoom(z){zoom=Math.max(1,Math.min(32,z));im.style.width=(%d*zoom)+'px';"
    "document.getElementById('z').textContent=zoom+'x';}\n"
    "document.addEventListener('keydown',function(e){if(e.key=='r'||e.key=='s'||e.key=='d')show(e.key);"
    "else if(e.key==' '){show(cur=='r'?'s':'r');e.preventDefault();}else if(e.key=='+'||e.key=='=')setzoom(zoom*2);"
    "else if(e.key=='-')setzoom(Math.floor(zoom/2));});\n"
    "show('s');setzoom(zoom);\n"
    "</script>\n";

int rf_grade_write_page(const RfGradeRun *run, const RfSubmission *s, char *err, size_t errsz)
{
    Out o;
    char name[128];
    snprintf(name, sizeof name, "%s.html", s->id);
    if (!out_open(&o, run, name, err, errsz))
        return 0;
    FILE *f = o.f;
    const RfDiffStats *st = stats(s);
    fprintf(f, "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>refray grade: ");
    html(f, s->student);
    fprintf(f, "</title>\n%s</head><body>\n<p><a href=\"index.html\">&larr; all submissions</a></p>\n<h1>", style);
    html(f, s->student);
    fprintf(f, ": <span class=\"%s\">%s</span>, score %.1f</h1>\n<p>", verdict_class(s->g.verdict),
            rf_grade_verdict_name(s->g.verdict), s->g.score);
    html(f, s->path);
    fprintf(f, " (%s", s->format[0] ? s->format : "unreadable");
    if (s->width > 0)
        fprintf(f, ", %d x %d", s->width, s->height);
    fprintf(f, ") against ");
    html(f, run->reference);
    fprintf(f, " (%d x %d, shown with %s)</p>\n", run->width, run->height, run->curve);
    if (s->g.reason[0]) {
        fprintf(f, "<p><b>Reason:</b> ");
        html(f, s->g.reason);
        fprintf(f, "</p>\n");
    }
    if (compared(s))
        fprintf(f, "<table><tr><td>worst pixel error</td><td>%.4g at (%d, %d)</td></tr>"
                   "<tr><td>mean error</td><td>%.4g</td></tr><tr><td>RMSE / PSNR</td><td>%.4g / %.2f dB</td></tr>"
                   "<tr><td>above warn %.3g</td><td>%ld pixels (%.3g %%, allowed %g %%)</td></tr>"
                   "<tr><td>above fail %.3g</td><td>%ld pixels (%.3g %%, allowed %g %%)</td></tr>"
                   "<tr><td>thresholds</td><td>fail-mean %.3g, hardfail %g%s</td></tr></table>\n",
                st->max_abs, st->max_x, st->max_y, st->mean_abs, st->rmse, st->psnr, run->opt.warn, st->above_warn,
                rf_diff_percent(st->above_warn, st), run->opt.warn_percent, run->opt.fail, st->above_fail,
                rf_diff_percent(st->above_fail, st), run->opt.fail_percent, run->opt.fail_mean, run->opt.hardfail,
                run->opt.edge_tolerant ? "; edge-tolerant (3x3)" : "");
    if (s->images) {
        int zoom = run->width > 0 && run->width < 480 ? 480 / run->width : 1;
        fprintf(f, "<h2>Reference / submission / difference</h2>\n<p>"
                   "<button id=\"br\" onclick=\"show('r')\">reference (r)</button>"
                   "<button id=\"bs\" onclick=\"show('s')\">submission (s)</button>%s"
                   " &nbsp; space flips reference and submission &nbsp; zoom "
                   "<button onclick=\"setzoom(Math.floor(zoom/2))\">&minus;</button><span id=\"z\"></span>"
                   "<button onclick=\"setzoom(zoom*2)\">+</button> (keys + and &minus;)</p>\n"
                   "<div class=\"frame\"><img id=\"im\" class=\"px\" alt=\"image\"></div>\n",
                s->images > 1 ? "<button id=\"bd\" onclick=\"show('d')\">difference &times;10 (d)</button>" : "");
        if (s->images > 1) {
            fprintf(f, "<h2>Heat map</h2>\n<p><img class=\"px\" src=\"img/%s-heat.png\" alt=\"heat map\"></p>\n", s->id);
            fprintf(f, "<h2>Histogram of the pixel errors</h2>\n");
            histogram(f, s, &run->opt);
        }
        int diff = s->images > 1; /* the difference view only where there is one */
        fprintf(f, page_script, s->id, diff ? ",d:'img/" : "", diff ? s->id : "", diff ? "-diff.png'" : "", zoom,
                s->width > 0 ? s->width : run->width);
    }
    fprintf(f, "</body></html>\n");
    return out_close(&o, err, errsz);
}

static const char *index_script =
    "<script>\n"
    "function sortby(c,num){var t=document.getElementById('t'),rows=Array.prototype.slice.call(t.rows,1);"
    "var dir=t.getAttribute('data-c')==c&&t.getAttribute('data-d')=='1'?-1:1;"
    "rows.sort(function(a,b){var x=a.cells[c].getAttribute('data-v')||a.cells[c].textContent,"
    "y=b.cells[c].getAttribute('data-v')||b.cells[c].textContent;"
    "if(num){x=parseFloat(x);y=parseFloat(y);}return (x<y?-1:x>y?1:0)*dir;});"
    "rows.forEach(function(r){t.tBodies[0].appendChild(r);});t.setAttribute('data-c',c);"
    "t.setAttribute('data-d',dir==1?'1':'0');}\n"
    "</script>\n";

int rf_grade_write_index(const RfGradeRun *run, const RfSubmission *subs, int n, char *err, size_t errsz)
{
    Out o;
    if (!out_open(&o, run, "index.html", err, errsz))
        return 0;
    FILE *f = o.f;
    int count[5] = {0};
    for (int i = 0; i < n; i++)
        count[subs[i].g.verdict]++;
    fprintf(f, "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>refray grade</title>\n%s%s</head><body>\n"
               "<h1>refray grade: %d submission%s</h1>\n<p>reference ",
            style, index_script, n, n == 1 ? "" : "s");
    html(f, run->reference);
    fprintf(f, " (%d x %d), compared in display values (%s); fail %.3g (allowed %g %%), warn %.3g (allowed %g %%), "
               "fail-mean %.3g, hardfail %g%s</p>\n<p>",
            run->width, run->height, run->curve, run->opt.fail, run->opt.fail_percent, run->opt.warn,
            run->opt.warn_percent, run->opt.fail_mean, run->opt.hardfail, run->opt.edge_tolerant ? ", edge-tolerant" : "");
    for (int v = 0; v < 5; v++)
        fprintf(f, "%s<span class=\"%s\">%s</span> %d", v ? ", " : "", verdict_class((RfGradeVerdict)v),
                rf_grade_verdict_name((RfGradeVerdict)v), count[v]);
    fprintf(f, " (click a column's head to sort)</p>\n<table id=\"t\"><thead><tr><th onclick=\"sortby(0,1)\">#</th>"
               "<th onclick=\"sortby(1)\">student</th><th onclick=\"sortby(2)\">file</th>"
               "<th onclick=\"sortby(3)\">format</th><th onclick=\"sortby(4)\">verdict</th>"
               "<th onclick=\"sortby(5,1)\">score</th><th onclick=\"sortby(6,1)\">worst error</th>"
               "<th onclick=\"sortby(7)\">reason</th></tr></thead><tbody>\n");
    for (int i = 0; i < n; i++) {
        const RfSubmission *s = &subs[i];
        fprintf(f, "<tr><td>%d</td><td><a href=\"%s.html\">", i + 1, s->id);
        html(f, s->student);
        fprintf(f, "</a></td><td>");
        html(f, s->path);
        fprintf(f, "</td><td>%s</td><td class=\"%s\" data-v=\"%d\">%s</td><td>%.1f</td>", s->format,
                verdict_class(s->g.verdict), (int)s->g.verdict, rf_grade_verdict_name(s->g.verdict), s->g.score);
        if (compared(s))
            fprintf(f, "<td data-v=\"%.9g\">%.3g</td><td>", stats(s)->max_abs, stats(s)->max_abs);
        else
            fprintf(f, "<td data-v=\"-1\"></td><td>");
        html(f, s->g.reason);
        fprintf(f, "</td></tr>\n");
    }
    fprintf(f, "</tbody></table>\n</body></html>\n");
    return out_close(&o, err, errsz);
}

int rf_grade_write_csv(const RfGradeRun *run, const RfSubmission *subs, int n, char *err, size_t errsz)
{
    Out o;
    if (!out_open(&o, run, "grades.csv", err, errsz))
        return 0;
    FILE *f = o.f;
    fprintf(f, "student,file,format,verdict,score,reason,max_error,max_x,max_y,mean_error,pct_above_warn,"
               "pct_above_fail,shift_x,shift_y,page\n");
    for (int i = 0; i < n; i++) {
        const RfSubmission *s = &subs[i];
        char page[128];
        csv(f, s->student, ",");
        csv(f, s->path, ",");
        fprintf(f, "%s,%s,%.1f,", s->format, rf_grade_verdict_name(s->g.verdict), s->g.score);
        csv(f, s->g.reason, ",");
        if (compared(s))
            fprintf(f, "%.6g,%d,%d,%.6g,%.6g,%.6g,%d,%d,", stats(s)->max_abs, stats(s)->max_x, stats(s)->max_y,
                    stats(s)->mean_abs, rf_diff_percent(stats(s)->above_warn, stats(s)),
                    rf_diff_percent(stats(s)->above_fail, stats(s)), s->g.shift_x, s->g.shift_y);
        else
            fprintf(f, ",,,,,,,,");
        snprintf(page, sizeof page, "%s.html", s->id);
        csv(f, page, "\n");
    }
    return out_close(&o, err, errsz);
}

int rf_grade_write_json(const RfGradeRun *run, const RfSubmission *subs, int n, char *err, size_t errsz)
{
    cJSON *root = cJSON_CreateObject(), *th = cJSON_CreateObject(), *arr = cJSON_CreateArray();
    cJSON_AddStringToObject(root, "reference", run->reference);
    cJSON_AddNumberToObject(root, "width", run->width);
    cJSON_AddNumberToObject(root, "height", run->height);
    cJSON_AddStringToObject(root, "curve", run->curve);
    cJSON_AddNumberToObject(th, "warn", run->opt.warn);
    cJSON_AddNumberToObject(th, "warnpercent", run->opt.warn_percent);
    cJSON_AddNumberToObject(th, "fail", run->opt.fail);
    cJSON_AddNumberToObject(th, "failpercent", run->opt.fail_percent);
    cJSON_AddNumberToObject(th, "fail_mean", run->opt.fail_mean);
    if (isfinite(run->opt.hardfail))
        cJSON_AddNumberToObject(th, "hardfail", run->opt.hardfail);
    else
        cJSON_AddNullToObject(th, "hardfail");
    cJSON_AddBoolToObject(th, "edge_tolerant", run->opt.edge_tolerant);
    cJSON_AddItemToObject(root, "thresholds", th);
    for (int i = 0; i < n; i++) {
        const RfSubmission *s = &subs[i];
        cJSON *j = cJSON_CreateObject();
        char page[128];
        cJSON_AddStringToObject(j, "student", s->student);
        cJSON_AddStringToObject(j, "file", s->path);
        cJSON_AddStringToObject(j, "format", s->format);
        cJSON_AddStringToObject(j, "verdict", rf_grade_verdict_name(s->g.verdict));
        cJSON_AddNumberToObject(j, "score", s->g.score);
        cJSON_AddStringToObject(j, "reason", s->g.reason);
        if (compared(s)) {
            const RfDiffStats *st = stats(s);
            cJSON_AddNumberToObject(j, "max_error", isfinite(st->max_abs) ? st->max_abs : 1e308);
            cJSON_AddNumberToObject(j, "max_x", st->max_x);
            cJSON_AddNumberToObject(j, "max_y", st->max_y);
            cJSON_AddNumberToObject(j, "mean_error", isfinite(st->mean_abs) ? st->mean_abs : 1e308);
            cJSON_AddNumberToObject(j, "pct_above_warn", rf_diff_percent(st->above_warn, st));
            cJSON_AddNumberToObject(j, "pct_above_fail", rf_diff_percent(st->above_fail, st));
            cJSON_AddNumberToObject(j, "shift_x", s->g.shift_x);
            cJSON_AddNumberToObject(j, "shift_y", s->g.shift_y);
        }
        snprintf(page, sizeof page, "%s.html", s->id);
        cJSON_AddStringToObject(j, "page", page);
        cJSON_AddItemToArray(arr, j);
    }
    cJSON_AddItemToObject(root, "submissions", arr);
    char *text = cJSON_Print(root);
    cJSON_Delete(root);
    Out o;
    int ok = text && out_open(&o, run, "grades.json", err, errsz);
    if (ok) {
        fputs(text, o.f);
        fputc('\n', o.f);
        ok = out_close(&o, err, errsz);
    } else if (!text) {
        snprintf(err, errsz, "out of memory");
    }
    free(text);
    return ok;
}
