/* refray fuzzing: what every harness (fuzz/fuzz_*.c) and the regression test
 * (tests/test_fuzz_regress.c) do with an input, so that a reproducer kept under
 * tests/data/fuzz/<target>/ runs exactly the code that the fuzzer ran.
 *
 *   rf_fuzz_run(target, bytes, size, dir)   one input through the reader of target ("nff",
 *                                           "rf", "obj", "mtl", "exr", "png", "formula") and,
 *                                           when it parses, through validation, the analysis,
 *                                           the tracer and a tiny render (bounded work)
 *   rf_fuzz_sandbox(dir, size, scenes)      a fresh folder under /tmp holding copies of the
 *                                           files that scenes may name (gem.obj, gem.mtl,
 *                                           torus.obj): OBJ and .rf inputs are read as
 *                                           "<dir>/fuzz.obj" etc., so relative mtllib/mesh
 *                                           paths resolve there
 *
 * Header-only (static functions) so that the test build needs no extra object; C99, clean
 * under the project's -Wall -Wextra -Wpedantic -Werror. */
#ifndef RF_FUZZ_COMMON_H
#define RF_FUZZ_COMMON_H

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "refray/diff.h"
#include "refray/formula.h"
#include "refray/hash.h"
#include "refray/image.h"
#include "refray/render.h"
#include "refray/scene.h"
#include "refray/scene_export.h"
#include "refray/scene_io.h"

/* Work bounds: a parsed scene larger than this is checked but not traced (the BVH build and
 * the rays would take too long per input); images larger than this are read but not diffed. */
#define RF_FUZZ_MAX_ITEMS 20000
#define RF_FUZZ_MAX_DIFF_PIXELS 4096
/* the tiny render */
#define RF_FUZZ_RENDER_W 4
#define RF_FUZZ_RENDER_H 3
/* the exports: the flattened scene's size (an instance of a quadric under a non-similarity
 * transform becomes a mesh of ~9,000 triangles for Mitsuba) */
#define RF_FUZZ_MAX_EXPORT_TRIANGLES 5000
#define RF_FUZZ_MAX_EXPORT_PLACEMENTS 32

/* dir/name into out; 0 on success, -1 when it does not fit. */
static inline int rf_fuzz_path(char *out, size_t size, const char *dir, const char *name)
{
    int n = snprintf(out, size, "%s/%s", dir, name);
    return n >= 0 && (size_t)n < size ? 0 : -1;
}

/* Copies src to dir/name; 0 on success. */
static inline int rf_fuzz_copy(const char *src, const char *dir, const char *name)
{
    char dst[4096];
    char buf[1 << 14];
    size_t k;
    int ok = 1;
    if (rf_fuzz_path(dst, sizeof dst, dir, name))
        return -1;
    FILE *in = fopen(src, "rb");
    if (!in)
        return -1;
    FILE *out = fopen(dst, "wb");
    if (!out) {
        fclose(in);
        return -1;
    }
    while ((k = fread(buf, 1, sizeof buf, in)) > 0)
        if (fwrite(buf, 1, k, out) != k)
            ok = 0;
    fclose(in);
    if (fclose(out) != 0)
        ok = 0;
    return ok ? 0 : -1;
}

/* The files that a fuzzed scene may refer to by a relative name. */
static const char *const rf_fuzz_sandbox_files[] = {"gem.obj", "gem.mtl", "torus.obj"};

/* Makes a fresh folder /tmp/refray-fuzz-XXXXXX (or under $TMPDIR) with copies of the files
 * above from the folder `scenes` (a missing one is skipped). dir gets the folder's name;
 * 0 on success. */
static inline int rf_fuzz_sandbox(char *dir, size_t size, const char *scenes)
{
    const char *tmp = getenv("TMPDIR");
    char src[4096];
    if (rf_fuzz_path(dir, size, tmp && *tmp ? tmp : "/tmp", "refray-fuzz-XXXXXX") || !mkdtemp(dir))
        return -1;
    for (size_t i = 0; i < sizeof rf_fuzz_sandbox_files / sizeof rf_fuzz_sandbox_files[0]; i++)
        if (rf_fuzz_path(src, sizeof src, scenes, rf_fuzz_sandbox_files[i]) == 0)
            (void)rf_fuzz_copy(src, dir, rf_fuzz_sandbox_files[i]);
    return 0;
}

/* Removes the sandbox folder and what the harnesses put in it. */
static inline void rf_fuzz_sandbox_remove(const char *dir)
{
    static const char *const extra[] = {"input.exr", "input.png", "out.png", "out.exr"};
    char p[4096];
    for (size_t i = 0; i < sizeof rf_fuzz_sandbox_files / sizeof rf_fuzz_sandbox_files[0]; i++)
        if (rf_fuzz_path(p, sizeof p, dir, rf_fuzz_sandbox_files[i]) == 0)
            (void)unlink(p);
    for (size_t i = 0; i < sizeof extra / sizeof extra[0]; i++)
        if (rf_fuzz_path(p, sizeof p, dir, extra[i]) == 0)
            (void)unlink(p);
    (void)rmdir(dir);
}

/* A few rays through the tracer: from the centre of the bounds and from the camera, along the
 * axes and the diagonals, as nearest-hit and occlusion queries. */
static inline void rf_fuzz_rays(const RfScene *s, const RfTracer *tr)
{
    RfVec3 lo, hi, origins[3];
    int n = 0;
    if (rf_scene_bounds(s, &lo, &hi)) {
        origins[n++] = rf_vec3(0.5 * (lo.x + hi.x), 0.5 * (lo.y + hi.y), 0.5 * (lo.z + hi.z));
        origins[n++] = rf_vec3(lo.x - 1.0, hi.y + 1.0, lo.z - 1.0);
    }
    if (s->has_camera)
        origins[n++] = s->camera.eye;
    static const double dirs[][3] = {{1, 0, 0},  {-1, 0, 0}, {0, 1, 0},   {0, -1, 0},
                                     {0, 0, 1},  {0, 0, -1}, {1, 1, 1},   {-1, -1, -1},
                                     {1, -2, 3}, {0.3, 0.4, -1}};
    for (int o = 0; o < n; o++)
        for (size_t d = 0; d < sizeof dirs / sizeof dirs[0]; d++) {
            RfVec3 dir = rf_vec3(dirs[d][0], dirs[d][1], dirs[d][2]);
            double len = sqrt(dir.x * dir.x + dir.y * dir.y + dir.z * dir.z);
            RfRay ray = rf_ray(origins[o], rf_vec3(dir.x / len, dir.y / len, dir.z / len));
            RfSurfaceHit hit;
            uint64_t last = 0;
            (void)rf_tracer_intersect(tr, &ray, 0.0, INFINITY, &hit);
            (void)rf_tracer_occluded(tr, &ray, 1e-9, 1e30);
            (void)rf_tracer_occluded_cached(tr, &ray, 0.0, INFINITY, &last);
        }
}

/* refray export to each target, in memory, with --lossy (the most code) and without. */
static inline void rf_fuzz_export(const RfScene *s)
{
    RfTriangleCount tc = rf_scene_triangle_count(s);
    if (tc.rendered > RF_FUZZ_MAX_EXPORT_TRIANGLES || tc.instances_rendered > RF_FUZZ_MAX_EXPORT_PLACEMENTS)
        return;
    static const RfExportFormat formats[] = {RF_EXPORT_MITSUBA, RF_EXPORT_PBRT, RF_EXPORT_POV};
    for (size_t f = 0; f < sizeof formats / sizeof formats[0]; f++)
        for (int lossy = 0; lossy < 2; lossy++) {
            RfExportOptions o = rf_export_options_default();
            RfExport ex;
            o.format = formats[f];
            o.source = "fuzz";
            o.output = formats[f] == RF_EXPORT_MITSUBA ? "fuzz.xml" : formats[f] == RF_EXPORT_PBRT ? "fuzz.pbrt" : "fuzz.pov";
            o.lossy = lossy;
            o.two_sided = lossy; /* the other sides' rule on the second pass */
            (void)rf_scene_export(s, &o, &ex);
            rf_export_free(&ex);
        }
}

/* What the commands do with a parsed scene (refray info, refray render, refray export), bounded. */
static inline void rf_fuzz_scene(const RfScene *s)
{
    char err[512];
    RfVec3 lo, hi;
    (void)rf_scene_features(s);
    (void)rf_scene_triangle_count(s);
    (void)rf_scene_bounds(s, &lo, &hi);
    if (rf_scene_validate(s, "fuzz", err, sizeof err) != RF_OK)
        return;
    if (s->has_camera)
        (void)rf_scene_camera_window(&s->camera, RF_FUZZ_RENDER_W, RF_FUZZ_RENDER_H);
    size_t items = s->prim_count + s->vertex_count / 3 + s->instance_count + s->light_count;
    if (items > RF_FUZZ_MAX_ITEMS)
        return;
    for (size_t i = 0; i < s->object_count; i++)
        (void)rf_scene_object_bounds(s, (int)i, &lo, &hi);
    if (s->has_camera)
        rf_fuzz_export(s);

    RfTracerOptions topt = rf_tracer_options_default();
    topt.threads = 1;
    RfTracer *tr = NULL;
    if (rf_tracer_create_opts(s, &topt, &tr) == RF_OK && tr) {
        (void)rf_tracer_bytes(tr);
        rf_fuzz_rays(s, tr);
        rf_tracer_free(tr);
    }

    /* the render: the scene's sampling and kernel choice, at a tiny size and with the sample
     * counts capped (a scene may ask for thousands per pixel or per light) */
    RfRenderOptions ro = rf_render_options_default();
    ro.width = RF_FUZZ_RENDER_W;
    ro.height = RF_FUZZ_RENDER_H;
    ro.threads = 1;
    ro.accel.threads = 1;
    ro.max_depth = s->render.max_depth > 4 || s->render.max_depth < 1 ? 4 : s->render.max_depth;
    ro.samples = s->render.samples > 4 || s->render.samples < 1 ? 4 : s->render.samples;
    ro.adaptive_depth = s->render.adaptive_depth > 2 || s->render.adaptive_depth < 0 ? 2 : s->render.adaptive_depth;
    for (size_t i = 0; i < s->light_count; i++)
        if (s->lights[i].samples > 4)
            ro.light_samples = 4;
    RfImage img = {0, 0, 0, NULL};
    RfRenderStats st;
    if (rf_render(s, &ro, &img, &st) == RF_OK) {
        (void)rf_kernel_name(st.kernel, err, sizeof err);
        /* the rule of the specialised kernels (issue 11): the general kernel's image, bit for
         * bit, whatever the scene; a difference is a finding */
        RfRenderOptions go = ro;
        RfImage ref = {0, 0, 0, NULL};
        go.kernel = rf_kernel_parse("general");
        if (go.kernel && st.kernel != go.kernel && rf_render(s, &go, &ref, &st) == RF_OK &&
            (ref.width != img.width || ref.height != img.height || ref.channels != img.channels ||
             memcmp(ref.data, img.data, sizeof(float) * (size_t)img.channels * (size_t)img.width * (size_t)img.height) != 0)) {
            fprintf(stderr, "fuzz: the specialised kernel's image differs from the general kernel's\n");
            abort();
        }
        rf_image_free(&ref);
    }
    rf_image_free(&img);
    /* the general kernel, one sample, no adaptive sampling, as a preview (non-finite samples
     * counted, not an error): the same image, another code path */
    ro.kernel = rf_kernel_parse("general");
    ro.preview = 1;
    ro.samples = 1;
    ro.adaptive = 0;
    ro.width = 2;
    ro.height = 2;
    if (ro.kernel && rf_render(s, &ro, &img, &st) == RF_OK)
        rf_image_free(&img);
    rf_image_free(&img);
}

/* The MTL harness: the materials read into a scene with a camera, a light and a sphere and a
 * triangle for each (of the first 16) materials, so that the renderer shades with them. */
static inline void rf_fuzz_mtl_scene(RfScene *s)
{
    char msg[256];
    size_t nm = s->material_count < 16 ? s->material_count : 16;
    s->has_camera = 1;
    s->camera.eye = rf_vec3(0, 0, 5);
    s->camera.target = rf_vec3(0, 0, 0);
    s->camera.up = rf_vec3(0, 1, 0);
    s->camera.d = 1.0;
    s->camera.has_window = 0;
    s->camera.fov = 60.0;
    s->render.ambient = rf_rgb(0.1, 0.1, 0.1);
    RfLight l;
    memset(&l, 0, sizeof l);
    l.kind = RF_LIGHT_POINT;
    l.position = rf_vec3(2, 3, 4);
    l.intensity = rf_rgb(10, 10, 10);
    l.direction = rf_vec3(0, -1, 0);
    l.samples = 1;
    (void)rf_scene_add_light(s, &l);
    for (size_t i = 0; i < nm; i++) {
        double x = -1.5 + 3.0 * (double)i / 16.0;
        RfPrimitive p;
        memset(&p, 0, sizeof p);
        p.type = RF_PRIM_SPHERE;
        p.material = (int)i;
        p.u.sphere.center = rf_vec3(x, 0.5, 0);
        p.u.sphere.radius = 0.3;
        (void)rf_scene_add_primitive(s, &p, msg, sizeof msg);
        RfVec3 v[3] = {rf_vec3(x - 0.3, -1, 0.2), rf_vec3(x + 0.3, -1, 0.2), rf_vec3(x, -0.4, 0.2)};
        size_t first = 0, nfirst = 0;
        if (rf_scene_add_vertices(s, v, NULL, 3, &first, &nfirst) == RF_OK) {
            memset(&p, 0, sizeof p);
            p.type = RF_PRIM_TRIANGLE;
            p.material = (int)i;
            p.flags = RF_PRIM_TWO_SIDED;
            p.u.poly.first = first;
            p.u.poly.nfirst = nfirst;
            p.u.poly.count = 3;
            (void)rf_scene_add_primitive(s, &p, msg, sizeof msg);
        }
    }
    rf_fuzz_scene(s);
}

/* A scene a reader accepted: rf_scene_validate, which checks every primitive again (the readers
 * check each as they add it and leave the whole-scene pass out), must pass too; then as
 * rf_fuzz_scene. */
static inline void rf_fuzz_read_scene(const RfScene *s)
{
    char err[512];
    if (rf_scene_validate(s, "fuzz", err, sizeof err) != RF_OK) {
        fprintf(stderr, "a scene the reader accepted fails rf_scene_validate: %s\n", err);
        abort();
    }
    rf_fuzz_scene(s);
}

/* An image as `refray diff` uses it: compared with itself and with a copy shifted by one
 * channel value, heatmaps, a silhouette mask for one-channel (depth) images, and written back
 * as PNG and EXR into dir. */
static inline void rf_fuzz_image(const RfImage *img, const char *dir)
{
    char err[512], path[4096];
    if (!img->data || (size_t)img->width * (size_t)img->height > RF_FUZZ_MAX_DIFF_PIXELS)
        return;
    RfDiffOptions o = rf_diff_options_default();
    RfDiffResult res;
    size_t px = (size_t)img->width * (size_t)img->height;
    unsigned char *mask = calloc(px, 1);
    RfImage heat = {0, 0, 0, NULL}, b = {0, 0, 0, NULL};
    if (!mask)
        return;
    if (rf_image_alloc(&b, img->width, img->height, img->channels) == RF_OK) {
        for (size_t i = 0; i < px * (size_t)img->channels; i++)
            b.data[i] = img->data[i] * 0.5f + 0.25f;
        if (img->channels == 1) {
            rf_diff_silhouettes(img, o.depth_edge, mask);
            (void)rf_diff_images(img, &b, img, &b, &o, &res, mask, err, sizeof err);
            if (rf_diff_depth_heatmap(img, &b, mask, &heat) == RF_OK)
                rf_image_free(&heat);
        } else {
            (void)rf_diff_images(img, &b, NULL, NULL, &o, &res, mask, err, sizeof err);
            (void)rf_diff_images(img, img, NULL, NULL, &o, &res, NULL, err, sizeof err);
            (void)rf_diff_percent(res.all.above_fail, &res.all);
            if (rf_diff_heatmap(img, &b, mask, &o, &heat) == RF_OK)
                rf_image_free(&heat);
            rf_diff_heatmap_done(); /* the legend's font caches: no leak per input */
        }
        rf_image_free(&b);
    }
    free(mask);
    RfPngOptions po = {RF_PNG_SRGB, 2.2, 8, NULL};
    if (rf_fuzz_path(path, sizeof path, dir, "out.png") == 0)
        (void)rf_png_write(path, img, po, err, sizeof err);
    if (rf_fuzz_path(path, sizeof path, dir, "out.exr") == 0)
        (void)rf_exr_write(path, img, NULL, 0, err, sizeof err);
}

/* Writes the bytes to dir/name; 0 on success. */
static inline int rf_fuzz_write(const char *dir, const char *name, const uint8_t *data, size_t size, char *path,
                         size_t pathsz)
{
    if (rf_fuzz_path(path, pathsz, dir, name))
        return -1;
    FILE *f = fopen(path, "wb");
    if (!f)
        return -1;
    int ok = fwrite(data, 1, size, f) == size;
    return fclose(f) == 0 && ok ? 0 : -1;
}

/* The formula front ends: the batch on the bytes as JSON lines, and the bytes split at blanks
 * as the command line `refray formula ID key=value ...`. */
static inline void rf_fuzz_formula(const uint8_t *data, size_t size)
{
    static FILE *devnull;
    if (!devnull)
        devnull = fopen("/dev/null", "w");
    if (size > 0 && devnull) {
        FILE *in = fmemopen((void *)data, size, "r");
        if (in) {
            (void)rf_formula_batch(in, devnull, NULL, NULL);
            fclose(in);
        }
    }
    /* the command line */
    char *text = malloc(size + 1);
    char **argv = malloc((size / 2 + 2) * sizeof *argv);
    if (text && argv) {
        int argc = 0;
        memcpy(text, data, size);
        text[size] = 0;
        for (char *p = text; *p;) {
            while (*p == ' ' || *p == '\n' || *p == '\t')
                *p++ = 0;
            if (!*p)
                break;
            argv[argc++] = p;
            while (*p && *p != ' ' && *p != '\n' && *p != '\t')
                p++;
        }
        const RfFormula *f = argc > 0 ? rf_formula_find(argv[0]) : NULL;
        if (f) {
            char err[512];
            char *in = rf_formula_args_to_json(argc - 1, argv + 1, err, sizeof err);
            if (in) {
                char *out = NULL;
                (void)rf_formula_run_json(f, in, &out);
                free(out);
                free(in);
            }
        }
    }
    free(argv);
    free(text);
}

/* Two scenes the same, field by field (counts, vertices, normals, material names, primitives). */
static inline int rf_fuzz_same_scene(const RfScene *a, const RfScene *b)
{
    if (a->prim_count != b->prim_count || a->vertex_count != b->vertex_count || a->normal_count != b->normal_count ||
        a->material_count != b->material_count || a->file_count != b->file_count)
        return 0;
    int same = (a->vertex_count == 0 || memcmp(a->vertices, b->vertices, sizeof *a->vertices * a->vertex_count) == 0) &&
               (a->normal_count == 0 || memcmp(a->normals, b->normals, sizeof *a->normals * a->normal_count) == 0);
    for (size_t m = 0; m < a->material_count; m++)
        same &= strcmp(a->materials[m].name, b->materials[m].name) == 0;
    for (size_t p = 0; p < a->prim_count; p++) {
        const RfPrimitive *x = &a->prims[p], *y = &b->prims[p];
        same &= x->type == y->type && x->flags == y->flags && x->material == y->material &&
                x->loc.line == y->loc.line && x->loc.col == y->loc.col;
        if (x->type == RF_PRIM_TRIANGLE || x->type == RF_PRIM_POLYGON)
            same &= x->u.poly.first == y->u.poly.first && x->u.poly.count == y->u.poly.count &&
                    x->u.poly.nfirst == y->u.poly.nfirst;
    }
    return same;
}

/* The OBJ input again, each of its lines followed by a comment line long enough that the text
 * passes 2 x 16 KB: the reader takes it in chunks on two threads (obj.c, parse_chunks) and line
 * by line on one; both must give the same scene or the same error (else abort: a finding).
 * Run for a quarter of the inputs (by their hash), so that the other paths keep their pace. */
static inline void rf_fuzz_obj_chunks(const char *name, const uint8_t *data, size_t size)
{
    enum { LEAST = 40000 };
    size_t lines = 1;
    for (size_t i = 0; i < size; i++)
        lines += data[i] == '\n';
    size_t pad = LEAST / lines + 2, cap = size + lines * (pad + 1) + 1, len = 0;
    char *text = malloc(cap);
    if (!text)
        return;
    for (size_t i = 0; i <= size; i++) {
        if (i < size)
            text[len++] = (char)data[i];
        if (i == size || data[i] == '\n') {
            if (i == size)
                text[len++] = '\n';
            text[len++] = '#';
            memset(text + len, '-', pad - 2);
            len += pad - 2;
            text[len++] = '\n';
        }
    }
    RfScene s[2];
    RfStatus st[2];
    char err[2][1024];
    for (int k = 0; k < 2; k++) {
        RfLoadOptions lo = rf_load_options_default();
        lo.threads = k + 1;
        st[k] = rf_scene_read_obj(name, text, len, &lo, &s[k], err[k], sizeof err[k]);
    }
    if (st[0] != st[1] || (st[0] != RF_OK && strcmp(err[0], err[1]) != 0) ||
        (st[0] == RF_OK && !rf_fuzz_same_scene(&s[0], &s[1]))) {
        fprintf(stderr, "obj: chunks and lines differ: %d '%s' / %d '%s'\n", (int)st[0], err[0], (int)st[1], err[1]);
        abort();
    }
    for (int k = 0; k < 2; k++)
        if (st[k] == RF_OK)
            rf_scene_free(&s[k]);
    free(text);
}

/* One input of one target; returns the reader's status (RF_OK for the formula target). */
static inline RfStatus rf_fuzz_run(const char *target, const uint8_t *data, size_t size, const char *dir)
{
    char err[1024], name[4096];
    RfStatus st = RF_OK;
    if (strcmp(target, "formula") == 0) {
        rf_fuzz_formula(data, size);
        return RF_OK;
    }
    if (strcmp(target, "exr") == 0 || strcmp(target, "png") == 0) {
        int exr = target[0] == 'e';
        RfImage img = {0, 0, 0, NULL};
        RfPngOptions dec = {RF_PNG_GAMMA, 2.2, 8, NULL};
        if (rf_fuzz_write(dir, exr ? "input.exr" : "input.png", data, size, name, sizeof name))
            return RF_ERR_IO;
        /* as `refray diff` reads it (by signature), then by the reader itself */
        if (rf_image_read(name, dec, &img, err, sizeof err) == RF_OK)
            rf_fuzz_image(&img, dir);
        rf_image_free(&img);
        if (exr) {
            char *v = NULL;
            st = rf_exr_read(name, &img, err, sizeof err);
            if (rf_exr_read_attr(name, "refray:version", &v, err, sizeof err) == RF_OK)
                free(v);
        } else {
            dec.encoding = RF_PNG_SRGB;
            dec.bits = 16;
            st = rf_png_read(name, dec, &img, err, sizeof err);
        }
        rf_image_free(&img);
        return st;
    }
    RfScene scene;
    RfLoadOptions lo = rf_load_options_default();
    rf_scene_init(&scene);
    char base[16];
    snprintf(base, sizeof base, "fuzz.%.8s", target);
    if (rf_fuzz_path(name, sizeof name, dir, base))
        return RF_ERR_IO;
    if (strcmp(target, "nff") == 0) {
        st = rf_scene_read_nff(name, (const char *)data, size, &lo, &scene, err, sizeof err);
        if (st == RF_OK)
            rf_fuzz_read_scene(&scene);
        rf_scene_free(&scene);
        /* the other field-of-view reading: another camera window */
        rf_scene_init(&scene);
        lo.nff_fov = RF_FOV_EDGES;
        if (rf_scene_read_nff(name, (const char *)data, size, &lo, &scene, err, sizeof err) == RF_OK &&
            scene.has_camera)
            (void)rf_scene_camera_window(&scene.camera, 3, 2);
    } else if (strcmp(target, "rf") == 0) {
        st = rf_scene_read_rf(name, (const char *)data, size, &scene, err, sizeof err);
        if (st == RF_OK)
            rf_fuzz_read_scene(&scene);
    } else if (strcmp(target, "obj") == 0) {
        st = rf_scene_read_obj(name, (const char *)data, size, &lo, &scene, err, sizeof err);
        if (st == RF_OK)
            rf_fuzz_read_scene(&scene);
        if (rf_hash_bytes(0, data, size) % 4 == 0) /* a quarter of the inputs: it costs 4 reads */
            rf_fuzz_obj_chunks(name, data, size);
    } else if (strcmp(target, "mtl") == 0) {
        st = rf_scene_read_mtl(name, (const char *)data, size, &scene, err, sizeof err);
        if (st == RF_OK)
            rf_fuzz_mtl_scene(&scene);
    } else {
        st = RF_ERR_DOMAIN;
    }
    rf_scene_free(&scene);
    return st;
}

#endif
