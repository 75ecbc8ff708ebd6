/* `refray trace SCENE X Y`: every ray of one pixel, as the renderer computes it (issue 16): the
 * render kernels report each step while they render that one pixel (RfRenderOptions.trace), so
 * the trace is the renderer's own arithmetic and ends with the value `refray render` writes for
 * the pixel, bit for bit. A readable tree, or JSON (--json). */
#include "cli.h"
#include "args.h"
#include "exit_codes.h"

#include <stdlib.h>
#include <string.h>

#include "refray/render.h"
#include "refray/scene_io.h"

enum { OPT_JSON = RF_OPT_ID, OPT_SAMPLE };

static const RfOpt trace_opts[] = {
    {"json", OPT_JSON, NULL, "the same as one JSON object: {\"scene\", \"settings\", \"pixel\", \"events\": [...]}",
     NULL},
    {"sample", OPT_SAMPLE, "S", "only camera sample S of the pixel (0 .. samples - 1), and the pixel's value",
     "an integer >= 0"},
    RF_OPT_TABLE_END,
};

static const RfOpt *const trace_tables[] = {trace_opts, rf_opts_render, rf_opts_png, rf_opts_load, NULL};

static const RfCommand trace_cmd = {
    "refray trace",
    "refray trace [options] SCENE X Y\n",
    "Every ray of pixel (X, Y) (0, 0 at the top left), as the renderer computes it with the\n"
    "same options as refray render: each camera sample's primary ray (§3.4), each hit\n"
    "(primitive, t, point, geometric and shading normal), each light's L, its intensity\n"
    "at the point, the shadow ray's verdict and the Phong terms per channel (§3.6.2),\n"
    "each mirror or refracted ray with its Snell and Fresnel numbers and weight (§3.8),\n"
    "the colour every ray returns, and the pixel's value as refray render writes it.\n",
    trace_tables,
    "exit: 0 ok, 2 the render failed, 4 the scene cannot be read, 5 usage (README: Exit codes)\n",
};

typedef struct {
    const RfScene *scene;
    int json, first;
    int only_sample; /* --sample S, or -1 for every sample */
    int samples;     /* the pixel's camera samples, as the kernel numbers them */
} Printer;

static void v3(FILE *f, RfVec3 v, int json)
{
    fprintf(f, json ? "[%.17g, %.17g, %.17g]" : "(%.9g, %.9g, %.9g)", v.x, v.y, v.z);
}

static void rgb(FILE *f, RfRgb c, int json)
{
    fprintf(f, json ? "[%.9g, %.9g, %.9g]" : "(%.9g, %.9g, %.9g)", c.r, c.g, c.b);
}

/* A name for JSON and the tree: quotes and control characters escaped. */
static void str(FILE *f, const char *s)
{
    fputc('"', f);
    for (; *s; s++)
        if (*s == '"' || *s == '\\')
            fprintf(f, "\\%c", *s);
        else if ((unsigned char)*s < 0x20)
            fprintf(f, "\\u%04x", (unsigned char)*s);
        else
            fputc(*s, f);
    fputc('"', f);
}

static void print_json(Printer *p, const RfTraceEvent *e)
{
    static const char *const kinds[] = {"sample", "hit", "miss", "light", "secondary", "result", "pixel"};
    FILE *f = stdout;
    fprintf(f, "%s\n  {\"event\": \"%s\", \"depth\": %d, \"sample\": %d", p->first ? "" : ",", kinds[e->kind], e->depth,
            e->sample);
    p->first = 0;
    switch (e->kind) {
    case RF_TRACE_SAMPLE:
        fprintf(f, ", \"samples\": %d, \"image_position\": [%.17g, %.17g], \"origin\": ", e->samples, e->px, e->py);
        v3(f, e->ray.origin, 1);
        fprintf(f, ", \"direction\": ");
        v3(f, e->ray.dir, 1);
        break;
    case RF_TRACE_HIT: {
        const RfSurfaceHit *h = e->hit;
        const RfPrimitive *pr = &p->scene->prims[h->prim];
        fprintf(f, ", \"primitive\": %d, \"type\": \"%s\", \"line\": %d, \"material\": ", h->prim,
                rf_prim_type_name(pr->type), pr->loc.line);
        str(f, p->scene->materials[h->material].name);
        fprintf(f, ", \"t\": %.17g, \"point\": ", h->t);
        v3(f, h->point, 1);
        fprintf(f, ", \"normal\": ");
        v3(f, h->normal, 1);
        fprintf(f, ", \"shading_normal\": ");
        v3(f, h->shading_normal, 1);
        fprintf(f, ", \"front\": %s", h->front ? "true" : "false");
        break;
    }
    case RF_TRACE_LIGHT:
        fprintf(f, ", \"light\": %d, \"kind\": \"%s\", \"light_sample\": %d, \"L\": ", e->light,
                rf_light_kind_name(p->scene->lights[e->light].kind), e->light_sample);
        v3(f, e->l, 1);
        fprintf(f, ", \"distance\": %.17g, \"N_dot_L\": %.17g, \"intensity\": ", e->distance, e->n_dot_l);
        rgb(f, e->intensity, 1);
        fprintf(f, ", \"visible\": %s", e->visible > 0 ? "true" : e->visible == 0 ? "false" : "\"behind\"");
        fprintf(f, ", \"transmittance\": ");
        rgb(f, e->transmittance, 1);
        fprintf(f, ", \"diffuse\": ");
        rgb(f, e->diffuse, 1);
        fprintf(f, ", \"specular\": ");
        rgb(f, e->specular, 1);
        break;
    case RF_TRACE_SECONDARY:
        fprintf(f, ", \"ray\": \"%s\", \"total_internal_reflection\": %s, \"fresnel\": %s, \"eta_i\": %.17g, "
                   "\"eta_t\": %.17g, \"cos_i\": %.17g, \"F_r\": %.17g, \"F_t\": %.17g, \"weight\": ",
                e->refracted ? "refracted" : "mirror", e->tir ? "true" : "false", e->fresnel ? "true" : "false",
                e->eta_i, e->eta_t, e->cos_i, e->fr, e->ft);
        rgb(f, e->weight, 1);
        fprintf(f, ", \"origin\": ");
        v3(f, e->ray.origin, 1);
        fprintf(f, ", \"direction\": ");
        v3(f, e->ray.dir, 1);
        break;
    case RF_TRACE_MISS:
    case RF_TRACE_PIXEL:
        fprintf(f, ", \"color\": ");
        rgb(f, e->color, 1);
        break;
    case RF_TRACE_RESULT:
        fprintf(f, ", \"local\": ");
        rgb(f, e->local, 1);
        fprintf(f, ", \"color\": ");
        rgb(f, e->color, 1);
        break;
    }
    fputc('}', f);
}

static void print_tree(Printer *p, const RfTraceEvent *e)
{
    FILE *f = stdout;
    int ind = 2 * e->depth;
    switch (e->kind) {
    case RF_TRACE_SAMPLE:
        fprintf(f, "sample %d of %d at image position (%.9g, %.9g): primary ray from ", e->sample, e->samples, e->px,
                e->py);
        v3(f, e->ray.origin, 0);
        fprintf(f, " along ");
        v3(f, e->ray.dir, 0);
        fprintf(f, "\n");
        break;
    case RF_TRACE_HIT: {
        const RfSurfaceHit *h = e->hit;
        const RfPrimitive *pr = &p->scene->prims[h->prim];
        fprintf(f, "%*sdepth %d: hits %s #%d (line %d, material '%s') at t = %.9g, point ", ind, "", e->depth,
                rf_prim_type_name(pr->type), h->prim, pr->loc.line, p->scene->materials[h->material].name, h->t);
        v3(f, h->point, 0);
        fprintf(f, ", %s side\n%*s  normal ", h->front ? "front" : "back", ind, "");
        v3(f, h->normal, 0);
        fprintf(f, ", shading normal ");
        v3(f, h->shading_normal, 0);
        fprintf(f, "\n");
        break;
    }
    case RF_TRACE_MISS:
        fprintf(f, "%*sdepth %d: meets nothing: background ", ind, "", e->depth);
        rgb(f, e->color, 0);
        fprintf(f, "\n");
        break;
    case RF_TRACE_LIGHT:
        fprintf(f, "%*s  light %d (%s", ind, "", e->light, rf_light_kind_name(p->scene->lights[e->light].kind));
        if (e->light_sample >= 0)
            fprintf(f, ", sample %d", e->light_sample);
        fprintf(f, "): L = ");
        v3(f, e->l, 0);
        fprintf(f, ", distance %.9g, N.L = %.9g, I = ", e->distance, e->n_dot_l);
        rgb(f, e->intensity, 0);
        if (e->visible < 0)
            fprintf(f, ": behind the surface\n");
        else if (e->visible == 0)
            fprintf(f, ": the shadow ray is blocked\n");
        else {
            RfRgb tr = e->transmittance;
            if (tr.r != 1.0 || tr.g != 1.0 || tr.b != 1.0) { /* filtered shadows: through transmitting surfaces */
                fprintf(f, ": lit through transmitting surfaces, I times ");
                rgb(f, tr, 0);
            } else {
                fprintf(f, ": lit");
            }
            fprintf(f, "\n%*s    diffuse ", ind, "");
            rgb(f, e->diffuse, 0);
            fprintf(f, " + specular ");
            rgb(f, e->specular, 0);
            fprintf(f, "\n");
        }
        break;
    case RF_TRACE_SECONDARY:
        fprintf(f, "%*s  %s ray, weight ", ind, "", e->refracted ? "refracted" : "mirror");
        rgb(f, e->weight, 0);
        fprintf(f, " (eta %.9g -> %.9g, cos_i %.9g", e->eta_i, e->eta_t, e->cos_i);
        if (e->fresnel)
            fprintf(f, ", Fresnel R %.9g T %.9g", e->fr, e->ft);
        if (e->tir)
            fprintf(f, ", total internal reflection: the transmitted share joins the mirror ray");
        fprintf(f, "), from ");
        v3(f, e->ray.origin, 0);
        fprintf(f, " along ");
        v3(f, e->ray.dir, 0);
        fprintf(f, "\n");
        break;
    case RF_TRACE_RESULT:
        fprintf(f, "%*sdepth %d returns ", ind, "", e->depth);
        rgb(f, e->color, 0);
        fprintf(f, " (emission + ambient + lights: ");
        rgb(f, e->local, 0);
        fprintf(f, ")\n");
        break;
    case RF_TRACE_PIXEL:
        fprintf(f, "pixel value ");
        rgb(f, e->color, 0);
        fprintf(f, " (as float, the value refray render writes; %d sample%s)\n", e->samples, e->samples == 1 ? "" : "s");
        break;
    }
}

static void on_event(void *ctx, const RfTraceEvent *e)
{
    Printer *p = ctx;
    if (e->kind == RF_TRACE_SAMPLE && e->sample + 1 > p->samples)
        p->samples = e->sample + 1;
    /* --sample S: the other samples' rays are left out; the pixel's value (their mean) stays */
    if (p->only_sample >= 0 && e->kind != RF_TRACE_PIXEL && e->sample != p->only_sample)
        return;
    if (p->json)
        print_json(p, e);
    else
        print_tree(p, e);
}

int rf_cmd_trace(int argc, char **argv)
{
    const char *scene_path = NULL;
    int xy[2] = {-1, -1}, json = 0, only_sample = -1;
    RfRenderOptions opt = rf_render_options_default();
    RfLoadOptions lopt = rf_load_options_default();
    RfPngOptions popt = {RF_PNG_GAMMA, 2.2, 8, NULL};
    RfOptParser op;
    int key;
    rf_opt_init(&op, &trace_cmd, argc, argv);
    while ((key = rf_opt_next(&op)) != RF_OPT_DONE) {
        int r = 1;
        if (key == RF_OPT_EXIT)
            return op.exit_code;
        if (key == OPT_JSON)
            json = 1;
        else if (key == OPT_SAMPLE)
            r = rf_arg_int(op.value, 0, 1 << 30, &only_sample) ? 1 : -1;
        else if ((r = rf_arg_render(key, op.value, &opt)) == 0)
            r = rf_arg_shared(key, op.value, &lopt, &popt);
        if (r < 0)
            return rf_opt_bad_value(&op);
    }
    char **ops;
    int n = rf_opt_operands(&op, &ops);
    if (n == 0)
        return rf_opt_usage_error(&trace_cmd, "missing the scene file and the pixel X Y");
    if (n < 3)
        return rf_opt_usage_error(&trace_cmd, "missing the pixel's %s", n == 1 ? "X and Y" : "Y");
    if (n > 3)
        return rf_opt_usage_error(&trace_cmd, "one pixel only: '%s' is one word too many", ops[3]);
    scene_path = ops[0];
    for (int k = 0; k < 2; k++)
        if (!rf_arg_int(ops[1 + k], 0, 65535, &xy[k])) {
            fprintf(stderr, "refray trace: bad pixel coordinate '%s': an integer in [0, 65535]\n", ops[1 + k]);
            return RF_EXIT_USAGE;
        }
    char err[1024];
    RfScene scene;
    if (rf_scene_load(scene_path, &lopt, &scene, err, sizeof err) != RF_OK) {
        rf_arg_report("refray trace", err);
        return RF_EXIT_FILE;
    }
    int w = opt.width > 0 ? opt.width : scene.render.width, h = opt.height > 0 ? opt.height : scene.render.height;
    if (xy[0] >= w || xy[1] >= h) {
        fprintf(stderr, "refray trace: pixel (%d, %d) is not in the %dx%d image\n", xy[0], xy[1], w, h);
        rf_scene_free(&scene);
        return RF_EXIT_USAGE;
    }
    Printer p = {&scene, json, 1, only_sample, 0};
    char settings[512];
    if (!rf_render_describe(&scene, &opt, settings, sizeof settings))
        settings[0] = 0;
    if (json) {
        printf("{\"scene\": ");
        str(stdout, scene_path);
        printf(", \"settings\": ");
        str(stdout, settings);
        printf(", \"pixel\": [%d, %d], \"events\": [", xy[0], xy[1]);
    } else {
        printf("refray trace: %s pixel (%d, %d); %s\n", scene_path, xy[0], xy[1], settings);
    }
    opt.crop = (RfTile){xy[0], xy[1], xy[0] + 1, xy[1] + 1, 0};
    opt.trace = on_event;
    opt.trace_ctx = &p;
    opt.preview = 1; /* a NaN is traced and shown, not refused */
    RfImage img;
    RfRenderStats st;
    RfStatus rs = rf_render(&scene, &opt, &img, &st);
    if (json)
        printf("\n]}\n");
    rf_scene_free(&scene);
    if (rs != RF_OK) {
        fprintf(stderr, "refray trace: %s: %s\n", scene_path, rf_status_str(rs));
        return rs == RF_ERR_DOMAIN ? RF_EXIT_USAGE : RF_EXIT_FAIL;
    }
    rf_image_free(&img);
    if (only_sample >= p.samples) {
        fprintf(stderr, "refray trace: the pixel has %d camera sample%s (0 .. %d): no sample %d\n", p.samples,
                p.samples == 1 ? "" : "s", p.samples - 1, only_sample);
        return RF_EXIT_USAGE;
    }
    return 0;
}
