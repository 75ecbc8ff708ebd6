/* rf_render (render.h): the job of a render, the choice of its kernel (kernel.h), threads over
 * tiles, and the statistics. */
#include "refray/render.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "kernel.h"
#include "refray/numeric.h"

RfRenderOptions rf_render_options_default(void)
{
    RfRenderOptions o;
    memset(&o, 0, sizeof o);
    o.seed = 1;
    o.sampler = -1;
    o.adaptive = -1;
    o.adaptive_threshold = -1.0;
    o.adaptive_depth = -1;
    o.threshold = -1.0;
    o.filter = -1;
    o.aperture = NAN;
    o.focus = NAN;
    o.shadows = -1;
    return o;
}

/* ---- which kernel ---- */

static const char *const part_names[RF_K_COUNT] = {"shadow", "secondary", "fresnel", "specular", "ambient",
                                                   "emission", "spot", "directional", "falloff", "jitter",
                                                   "area", "lens", "motion", "glossy"};

/* The scene's settings with the options' overrides. */
typedef struct {
    int samples, max_depth;
    double threshold;
    RfSampler sampler;
    int adaptive, adaptive_depth;
    double adaptive_threshold;
    RfFilter filter;
    double aperture, focus;
    RfShadowMode shadows;
} Resolved;

static int resolve(const RfScene *scene, const RfRenderOptions *opt, Resolved *r)
{
    const RfRenderSettings *rs = &scene->render;
    r->samples = opt->samples > 0 ? opt->samples : (rs->samples > 0 ? rs->samples : 1);
    r->max_depth = opt->max_depth > 0 ? opt->max_depth : rs->max_depth;
    r->threshold = opt->threshold < 0.0 ? rs->min_contribution : opt->threshold; /* NaN stays, and is refused */
    r->sampler = opt->sampler >= 0 ? (RfSampler)opt->sampler : rs->sampler;
    r->adaptive = opt->adaptive >= 0 ? opt->adaptive : rs->adaptive;
    r->adaptive_threshold = opt->adaptive_threshold >= 0.0 ? opt->adaptive_threshold : rs->adaptive_threshold;
    r->adaptive_depth = opt->adaptive_depth >= 0 ? opt->adaptive_depth : rs->adaptive_depth;
    r->filter = rs->filter;
    if (opt->filter >= 0 && opt->filter != (int)rs->filter.kind)
        r->filter = rf_filter_default((RfFilterKind)opt->filter);
    if (opt->filter_radius > 0.0)
        r->filter.radius = opt->filter_radius;
    r->aperture = isnan(opt->aperture) ? scene->camera.aperture : opt->aperture;
    r->focus = isnan(opt->focus) ? scene->camera.focus : opt->focus;
    r->shadows = opt->shadows >= 0 ? (RfShadowMode)opt->shadows : rs->shadows;
    return (r->shadows == RF_SHADOWS_OPAQUE || r->shadows == RF_SHADOWS_FILTERED) && r->max_depth > 0 && r->threshold >= 0.0 && r->threshold <= 1.0 && (unsigned)r->sampler < RF_SAMPLER_COUNT && (unsigned)r->filter.kind < RF_FILTER_COUNT &&
           r->filter.radius > 0.0 && r->adaptive_depth <= 8 && r->aperture >= 0.0 && isfinite(r->aperture) &&
           (r->aperture == 0.0 || (r->focus > 0.0 && isfinite(r->focus)));
}

/* The parts a render of this scene with these options needs (kernel.h); f: its
 * rf_scene_features (a pass over every primitive, made once per render). */
static unsigned needed_parts(const RfScene *scene, unsigned f, const RfRenderOptions *opt, const Resolved *r)
{
    unsigned k = 0;
    if (!opt->local_only && scene->light_count > 0)
        k |= RF_K_SHADOW;
    if (!opt->local_only && r->max_depth > 1 && (f & (RF_FEAT_REFLECTION | RF_FEAT_TRANSMISSION))) {
        k |= RF_K_SECONDARY;
        if (f & RF_FEAT_FRESNEL)
            k |= RF_K_FRESNEL;
        if (f & RF_FEAT_GLOSSY)
            k |= RF_K_GLOSSY;
    }
    if (f & RF_FEAT_SPECULAR)
        k |= RF_K_SPECULAR;
    if (f & RF_FEAT_AMBIENT)
        k |= RF_K_AMBIENT;
    if (f & RF_FEAT_EMISSION)
        k |= RF_K_EMISSION;
    if (f & RF_FEAT_LIGHT_FALLOFF)
        k |= RF_K_FALLOFF;
    if (f & RF_FEAT_AREA_LIGHTS)
        k |= RF_K_AREA;
    if (f & RF_FEAT_MOTION)
        k |= RF_K_MOTION;
    if (r->aperture > 0.0)
        k |= RF_K_LENS;
    for (size_t i = 0; i < scene->light_count; i++) {
        if (scene->lights[i].kind == RF_LIGHT_SPOT)
            k |= RF_K_SPOT;
        if (scene->lights[i].kind == RF_LIGHT_DIRECTIONAL)
            k |= RF_K_DIRECTIONAL;
    }
    if (r->samples > 1 || r->adaptive)
        k |= RF_K_JITTER;
    return k;
}

static int popcount(unsigned x)
{
    int n = 0;
    for (; x; x &= x - 1)
        n++;
    return n;
}

/* The compiled kernel with the fewest parts that has all the needed ones (the general kernel
 * has them all), or the one asked for when it has them; NULL otherwise. */
static const RfKernel *choose_kernel(unsigned needed, unsigned asked)
{
    const RfKernel *best = NULL;
    for (int i = 0; i < rf_kernel_count; i++) {
        const RfKernel *k = &rf_kernels[i];
        if ((k->parts & needed) != needed || (asked && k->parts != asked))
            continue;
        if (!best || popcount(k->parts) < popcount(best->parts))
            best = k;
    }
    return best;
}

unsigned rf_kernel_all_parts(void) { return RF_K_ALL; }

int rf_kernel_count_compiled(void) { return rf_kernel_count; }

unsigned rf_kernel_compiled(int i) { return i >= 0 && i < rf_kernel_count ? rf_kernels[i].parts : 0; }

unsigned rf_render_kernel(const RfScene *scene, const RfRenderOptions *opt)
{
    Resolved r;
    resolve(scene, opt, &r);
    const RfKernel *k = choose_kernel(needed_parts(scene, rf_scene_features(scene), opt, &r), opt->kernel);
    return k ? k->parts : 0;
}

const char *rf_kernel_name(unsigned parts, char *buf, size_t size)
{
    size_t n = (size_t)snprintf(buf, size, "general");
    for (int b = 0; b < RF_K_COUNT; b++)
        if (!(parts & (1u << b)))
            n += (size_t)snprintf(buf + n, n < size ? size - n : 0, "-%s", part_names[b]);
    return buf;
}

unsigned rf_kernel_parse(const char *name)
{
    unsigned parts = RF_K_ALL;
    if (strncmp(name, "general", 7) != 0)
        return 0;
    for (const char *s = name + 7; *s;) {
        if (*s++ != '-')
            return 0;
        size_t len = strcspn(s, "-");
        int b = 0;
        while (b < RF_K_COUNT && !(strlen(part_names[b]) == len && strncmp(s, part_names[b], len) == 0))
            b++;
        if (b == RF_K_COUNT)
            return 0;
        parts &= ~(1u << b);
        s += len;
    }
    for (int i = 0; i < rf_kernel_count; i++)
        if (rf_kernels[i].parts == parts)
            return parts;
    return 0;
}

int rf_render_describe(const RfScene *scene, const RfRenderOptions *opt, char *buf, size_t size)
{
    Resolved r;
    if (!resolve(scene, opt, &r) || size == 0)
        return 0;
    int w = opt->width > 0 ? opt->width : scene->render.width, h = opt->height > 0 ? opt->height : scene->render.height;
    size_t n = (size_t)snprintf(buf, size, "%dx%d, %d spp %s, filter %s %.17g, depth %d%s, seed %llu", w, h, r.samples,
                                r.adaptive ? "adaptive" : rf_sampler_name(r.sampler), rf_filter_name(r.filter.kind),
                                r.filter.radius, r.max_depth, opt->local_only ? ", local only" : "",
                                (unsigned long long)opt->seed);
    if (r.adaptive && n < size)
        n += (size_t)snprintf(buf + n, size - n, ", adaptive threshold %.17g depth %d", r.adaptive_threshold,
                              r.adaptive_depth);
    if (r.aperture > 0.0 && n < size)
        n += (size_t)snprintf(buf + n, size - n, ", lens aperture %.17g focus %.17g", r.aperture, r.focus);
    if (opt->light_samples > 0 && n < size)
        n += (size_t)snprintf(buf + n, size - n, ", light samples %d", opt->light_samples);
    if (r.threshold != scene->render.min_contribution && n < size) /* the scene's is in its hash */
        n += (size_t)snprintf(buf + n, size - n, ", threshold %.17g", r.threshold);
    if (opt->two_sided && n < size)
        n += (size_t)snprintf(buf + n, size - n, ", two-sided");
    if (r.shadows == RF_SHADOWS_FILTERED && n < size)
        n += (size_t)snprintf(buf + n, size - n, ", shadows filtered");
    if (opt->preview && n < size)
        n += (size_t)snprintf(buf + n, size - n, ", preview");
    return n < size;
}

/* ---- the render ---- */

static double seconds_between(struct timespec a, struct timespec b)
{
    return (double)(b.tv_sec - a.tv_sec) + 1e-9 * (double)(b.tv_nsec - a.tv_nsec);
}

typedef struct {
    RfKernelJob job;
    RfTileFn tile;
    const RfRenderOptions *opt;
    int ox, oy;     /* the pass's window in the image: its tiles are numbered from here */
    int final_pass; /* the pass that writes the image: skip, tile_done */
} Run;

int rf_render_tile_count(int width, int height)
{
    return ((width + RF_RENDER_TILE - 1) / RF_RENDER_TILE) * ((height + RF_RENDER_TILE - 1) / RF_RENDER_TILE);
}

static int cancelled(const RfRenderOptions *opt)
{
    return opt->cancel && __atomic_load_n(opt->cancel, __ATOMIC_RELAXED) != 0;
}

/* One tile of the pass's window, moved to its place in the image; its time added to its
 * thread's busy time (for the idle share). A tile done before (opt->skip) is copied from
 * opt->resume_from instead. */
static int run_tile(void *ctx, RfTile tile, int thread)
{
    Run *r = ctx;
    const RfRenderOptions *opt = r->opt;
    if (cancelled(opt))
        return 1;
    RfTile local = tile;
    tile.x0 += r->ox, tile.x1 += r->ox, tile.y0 += r->oy, tile.y1 += r->oy;
    int rc = 0;
    if (r->final_pass && opt->skip && opt->skip[tile.index]) {
        const RfImage *from = opt->resume_from;
        RfImage *img = r->job.img;
        for (int y = local.y0; y < local.y1; y++)
            memcpy(img->data + ((size_t)y * (size_t)img->width + (size_t)local.x0) * 3,
                   from->data + ((size_t)y * (size_t)from->width + (size_t)local.x0) * 3,
                   sizeof(float) * 3 * (size_t)(local.x1 - local.x0));
    } else {
        struct timespec a, b;
        clock_gettime(CLOCK_MONOTONIC, &a);
        rc = r->tile(&r->job, tile, thread);
        clock_gettime(CLOCK_MONOTONIC, &b);
        r->job.per_thread[thread].busy_seconds += seconds_between(a, b);
    }
    if (rc == 0 && r->final_pass && opt->tile_done)
        opt->tile_done(opt->tile_done_ctx, r->job.img, local);
    return rc;
}

static void run_progress(void *ctx, int done, int total)
{
    Run *r = ctx;
    r->opt->progress(r->opt->progress_ctx, done, total);
}

RfStatus rf_render(const RfScene *scene, const RfRenderOptions *opt, RfImage *img, RfRenderStats *stats)
{
    Run run;
    RfKernelJob *job = &run.job;
    RfStatus st;
    memset(&run, 0, sizeof run);
    memset(stats, 0, sizeof *stats);
    if (opt->variance) /* empty until filled: freed safely on any failure */
        memset(opt->variance, 0, sizeof *opt->variance);
    run.opt = opt;
    Resolved res;
    job->width = opt->width > 0 ? opt->width : scene->render.width;
    job->height = opt->height > 0 ? opt->height : scene->render.height;
    if (!resolve(scene, opt, &res) || job->width <= 0 || job->height <= 0 || !scene->has_camera ||
        opt->light_samples < 0 || opt->light_samples > 1 << 16)
        return RF_ERR_DOMAIN;
    RfTile crop = opt->crop;
    if (crop.x0 == 0 && crop.y0 == 0 && crop.x1 == 0 && crop.y1 == 0)
        crop.x1 = job->width, crop.y1 = job->height;
    if (crop.x0 < 0 || crop.y0 < 0 || crop.x1 > job->width || crop.y1 > job->height || crop.x0 >= crop.x1 ||
        crop.y0 >= crop.y1)
        return RF_ERR_DOMAIN;
    const int crop_w = crop.x1 - crop.x0, crop_h = crop.y1 - crop.y0;
    if (opt->skip && (!opt->resume_from || !opt->resume_from->data || opt->resume_from->width != crop_w ||
                      opt->resume_from->height != crop_h || opt->resume_from->channels != 3))
        return RF_ERR_DOMAIN;
    job->img_x0 = crop.x0;
    job->img_y0 = crop.y0;
    RfPathLog trace_log; /* refray trace: one pixel, one thread */
    if (opt->trace) {
        if (crop_w != 1 || crop_h != 1)
            return RF_ERR_DOMAIN;
        memset(&trace_log, 0, sizeof trace_log);
        trace_log.trace = opt->trace;
        trace_log.trace_ctx = opt->trace_ctx;
        job->trace_log = &trace_log;
    }
    /* adaptive supersampling compares each pixel's centre with its 4 neighbours' */
    RfTile around = {crop.x0 > 0 ? crop.x0 - 1 : 0, crop.y0 > 0 ? crop.y0 - 1 : 0,
                     crop.x1 < job->width ? crop.x1 + 1 : crop.x1, crop.y1 < job->height ? crop.y1 + 1 : crop.y1, 0};
    job->centres_x0 = around.x0;
    job->centres_y0 = around.y0;
    job->centres_w = around.x1 - around.x0;
    job->samples = res.samples;
    job->max_depth = res.max_depth;
    job->sampler = res.sampler;
    job->filter = res.filter;
    /* the box of radius 1/2 places samples in the pixel square and takes their mean */
    job->filter_box = res.filter.kind == RF_FILTER_BOX && res.filter.radius == 0.5;
    job->adaptive_depth = res.adaptive_depth;
    job->adaptive_threshold = res.adaptive_threshold;
    job->shutter_open = scene->render.shutter_open;
    job->shutter_close = scene->render.shutter_close;
    const unsigned features = rf_scene_features(scene); /* a pass over every primitive: once */
    job->moving = (features & RF_FEAT_MOTION) != 0;
    job->local_only = opt->local_only;
    /* filtered shadows differ from opaque ones only where some surface transmits: elsewhere
     * every crossing has kt = 0 and blocks, so the opaque query (one any-hit, cached) gives the
     * same image */
    job->filtered_shadows = res.shadows == RF_SHADOWS_FILTERED && (features & RF_FEAT_TRANSMISSION);
    job->fixed_offset = opt->fixed_offset;
    job->seed = opt->seed;
    job->min_contribution = res.threshold;
    job->background = scene->render.background;
    job->ambient = scene->render.ambient;
    job->materials = scene->materials;
    job->scene = scene;
    const RfSceneCamera *sc = &scene->camera;
    RfWindow w = rf_scene_camera_window(sc, job->width, job->height);
    st = rf_camera_init(&job->camera, sc->eye, sc->target, sc->up, w.d, w.l, w.r, w.b, w.t, job->width, job->height);
    if (st == RF_OK && res.aperture > 0.0)
        st = rf_camera_set_lens(&job->camera, res.aperture, res.focus);
    if (st != RF_OK)
        return st;
    job->hither = sc->hither;
    unsigned needed = needed_parts(scene, features, opt, &res);
    /* a trace runs the general kernel, the only one with the trace's events (the same image) */
    const RfKernel *kernel = choose_kernel(needed, opt->trace ? RF_K_ALL : opt->kernel);
    if (!kernel) /* a kernel asked for that lacks a part the scene needs */
        return RF_ERR_DOMAIN;
    run.tile = res.adaptive ? kernel->adaptive_centres : kernel->tile;
    int threads = opt->trace ? 1 : opt->threads > 0 ? opt->threads : rf_cpu_count();
    job->per_thread = calloc((size_t)threads, sizeof *job->per_thread);
    RfKernelLight *lights = malloc(sizeof *lights * (scene->light_count + 1));
    double *column_x = malloc(sizeof *column_x * (size_t)job->width);
    double *row_y = malloc(sizeof *row_y * (size_t)job->height);
    job->shadow_cache = calloc((size_t)threads * rf_kernel_shadow_stride(scene->light_count), sizeof *job->shadow_cache);
    unsigned char *highlight = malloc(scene->material_count + 1);
    job->centres = res.adaptive ? malloc(sizeof *job->centres * (size_t)job->centres_w * (size_t)(around.y1 - around.y0))
                                : NULL;
    if (!job->per_thread || !lights || !column_x || !row_y || !job->shadow_cache || !highlight ||
        (res.adaptive && !job->centres)) {
        free(job->centres);
        free(highlight);
        free(job->shadow_cache);
        free(job->per_thread);
        free(lights);
        free(column_x);
        free(row_y);
        return RF_ERR_NOMEM;
    }
    for (size_t i = 0; i < scene->light_count; i++) {
        const RfLight *l = &scene->lights[i];
        lights[i].kind = l->kind;
        lights[i].falloff = l->falloff;
        lights[i].position = l->position;
        lights[i].direction = l->direction;
        lights[i].intensity = l->intensity;
        lights[i].spot_exponent = l->spot_exponent;
        lights[i].spot_cutoff_rad = l->spot_cutoff * (RF_PI / 180.0);
        lights[i].edge1 = l->edge1;
        lights[i].edge2 = l->edge2;
        lights[i].radius = l->radius;
        lights[i].area = rf_light_area(l);
        lights[i].two_sided = l->two_sided;
        lights[i].samples = !rf_light_is_area(l->kind) ? 0 : opt->light_samples > 0 ? opt->light_samples : l->samples;
    }
    for (size_t i = 0; i < scene->material_count; i++)
        highlight[i] = (unsigned char)rf_material_has_highlight(&scene->materials[i]);
    job->highlight = highlight;
    job->lights = lights;
    job->light_count = (int)scene->light_count;
    /* the pixel centres' image-plane coordinates (§3.4, as rf_camera_plane_point) */
    const RfCamera *cam = &job->camera;
    for (int x = 0; x < job->width; x++)
        column_x[x] = cam->l + (cam->r - cam->l) * ((double)x + 0.5) / (double)cam->nx;
    for (int y = 0; y < job->height; y++)
        row_y[y] = cam->t - (cam->t - cam->b) * ((double)y + 0.5) / (double)cam->ny;
    job->column_x = column_x;
    job->row_y = row_y;
    RfTracer *tracer = NULL;
    RfTracerOptions topt = opt->accel;
    if (topt.threads <= 0)
        topt.threads = threads;
    topt.two_sided = opt->two_sided;
    struct timespec t0, t1, t2;
    clock_gettime(CLOCK_MONOTONIC, &t0);
    st = rf_tracer_create_opts(scene, &topt, &tracer);
    clock_gettime(CLOCK_MONOTONIC, &t1);
    if (st == RF_OK)
        st = rf_image_alloc(img, crop_w, crop_h, 3);
    if (st == RF_OK && opt->variance) { /* the samples' variance: 2 or more plain (box) samples */
        st = res.samples >= 2 && job->filter_box && !res.adaptive ? rf_image_alloc(opt->variance, crop_w, crop_h, 3)
                                                                  : RF_ERR_DOMAIN;
        job->variance = st == RF_OK ? opt->variance : NULL;
    }
    if (st == RF_OK && job->moving) { /* §3.10 one motion state per thread */
        job->motion = calloc((size_t)threads, sizeof *job->motion);
        for (int i = 0; job->motion && i < threads && st == RF_OK; i++)
            st = (job->motion[i] = rf_motion_state_new(tracer)) ? RF_OK : RF_ERR_NOMEM;
        if (!job->motion)
            st = RF_ERR_NOMEM;
    }
    job->cull = !(cam->aperture_radius > 0.0) && !job->moving && !opt->trace && rf_kernel_rgb_valid(job->background);
    if (st == RF_OK) {
        stats->accel_bytes = rf_tracer_bytes(tracer);
        job->tracer = tracer;
        job->img = img;
        if (res.adaptive) { /* §3.9 pass 1: the centres, of the window and one pixel around it */
            run.ox = around.x0, run.oy = around.y0;
            st = rf_parallel_tiles(around.x1 - around.x0, around.y1 - around.y0, RF_RENDER_TILE, threads, run_tile,
                                   opt->progress ? run_progress : NULL, &run);
            run.tile = kernel->adaptive_refine; /* pass 2: every centre is known */
        }
        run.ox = crop.x0, run.oy = crop.y0, run.final_pass = 1;
        if (st == RF_OK)
            st = rf_parallel_tiles(crop_w, crop_h, RF_RENDER_TILE, threads, run_tile,
                                   opt->progress ? run_progress : NULL, &run);
        if (st != RF_OK && cancelled(opt))
            st = RF_ERR_INTERRUPTED;
    }
    clock_gettime(CLOCK_MONOTONIC, &t2);
    stats->build_seconds = seconds_between(t0, t1);
    stats->trace_seconds = seconds_between(t1, t2);
    double busy = 0.0;
    for (int i = 0; i < threads; i++) {
        busy += job->per_thread[i].busy_seconds;
        stats->primary_rays += job->per_thread[i].primary_rays;
        stats->shadow_rays += job->per_thread[i].shadow_rays;
        stats->secondary_rays += job->per_thread[i].secondary_rays;
        stats->invalid_samples += job->per_thread[i].invalid_samples;
        stats->adaptive_pixels += job->per_thread[i].adaptive_pixels;
        stats->background_tiles += job->per_thread[i].background_tiles;
        const RfRenderStats *t = &job->per_thread[i];
        if (t->invalid.found &&
            (!stats->invalid.found || t->invalid.y < stats->invalid.y ||
             (t->invalid.y == stats->invalid.y &&
              (t->invalid.x < stats->invalid.x ||
               (t->invalid.x == stats->invalid.x && t->invalid.sample < stats->invalid.sample)))))
            stats->invalid = t->invalid;
    }
    if (st == RF_OK && stats->invalid.found) {
        /* the first invalid sample, traced again to name its path; a reference render fails */
        RfPathLog log;
        memset(&log, 0, sizeof log);
        uint64_t pixel = (uint64_t)stats->invalid.y * (uint64_t)job->width + (uint64_t)stats->invalid.x;
        kernel->explain(job, pixel, stats->invalid.sample, &log);
        snprintf(stats->invalid.path, sizeof stats->invalid.path, "%s", log.text);
        if (!opt->preview)
            st = RF_ERR_NUMERIC;
    }
    stats->sampler = (int)res.sampler;
    stats->adaptive = res.adaptive;
    stats->filter = res.filter;
    stats->width = job->width;
    stats->height = job->height;
    stats->samples = job->samples;
    stats->max_depth = job->max_depth;
    stats->threads = threads;
    stats->features = features;
    stats->kernel = kernel->parts;
    /* the share of the threads' time in the tile phase spent waiting (the last tiles) */
    int used = threads < rf_render_tile_count(crop_w, crop_h) ? threads : rf_render_tile_count(crop_w, crop_h);
    stats->idle_share = stats->trace_seconds > 0.0 ? 1.0 - busy / (used * stats->trace_seconds) : 0.0;
    if (stats->idle_share < 0.0)
        stats->idle_share = 0.0;
    for (int i = 0; job->motion && i < threads; i++)
        rf_motion_state_free(job->motion[i]);
    free(job->motion);
    free(job->per_thread);
    free(job->shadow_cache);
    free(job->centres);
    free(highlight);
    free(lights);
    free(column_x);
    free(row_y);
    rf_tracer_free(tracer);
    if (st != RF_OK) {
        rf_image_free(img);
        if (opt->variance)
            rf_image_free(opt->variance);
    }
    return st;
}
