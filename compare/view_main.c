/* refray-view: a GLFW window on a scene (issue 15). The tracer's image refines on a worker
 * thread (a 1-sample pass, then the full sample count, tile by tile through rf_render's
 * tile_done), and the window stays responsive; the last pass is `refray render` with the same
 * settings, so the converged image is the same bit for bit. Keys flip to the comparator's OpenGL
 * rasterization (raster.c, drawn on the window's own context) and to a difference heat map; the
 * mouse moves the camera and restarts the render; the scene file is reloaded when it changes.
 * Its own binary (GLFW, like refray-raster's GL) so that refray itself needs no display. */
#define _XOPEN_SOURCE 700
#define GLFW_INCLUDE_NONE
#include <GL/glcorearb.h>
#include <GLFW/glfw3.h>

#include <math.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>

#include "../src/cli/args.h"
#include "../src/cli/exit_codes.h"
#include "raster.h"
#include "refray/camera.h"
#include "refray/render.h"
#include "refray/scene_io.h"

static const char *const keys_help =
    "keys:\n"
    "  T / G / D   show the tracer's image / the OpenGL rasterization (the comparator's GLSL, on\n"
    "              this window's context) / their difference as a heat map (scale in the title)\n"
    "  L           local-only mode on/off (primary rays and local Phong: what the rasterization\n"
    "              reproduces)\n"
    "  [ ]         recursion depth - / +          - =   samples per pixel / 2, x 2\n"
    "  left drag   orbit around the target         right drag (or shift + left)  pan\n"
    "  arrows      orbit (left/right, up/down)     wheel, PgUp / PgDn   dolly\n"
    "  R           reset the camera\n"
    "  C           print the camera in refray's scene syntax, ready to paste into the file\n"
    "  click       pixel inspector: linear RGB and the primitive hit (printed)\n"
    "  S           save what is shown: view-N.exr (linear) and view-N.png\n"
    "  Q, Esc      quit\n"
    "The title bar is the status line: view, samples, time, Mrays/s, the kernel in use. The scene\n"
    "file is reloaded when it changes on disk; a broken edit shows its file:line:col error there\n"
    "(and on stderr) and the last good scene stays.\n";

enum {
    OPT_WIDTH = RF_OPT_ID, OPT_HEIGHT, OPT_SAMPLES, OPT_DEPTH, OPT_THREADS, OPT_LOCAL, OPT_TWO_SIDED, OPT_SHOW,
    OPT_SCREENSHOT, OPT_SAVE, OPT_TIMEOUT
};

static const RfOpt view_opts[] = {
    {"width", OPT_WIDTH, "W", "window and image width (default: the scene's)", "an integer in [1, 16384]"},
    {"height", OPT_HEIGHT, "H", "window and image height (default: the scene's)", "an integer in [1, 16384]"},
    {"samples", OPT_SAMPLES, "N", "samples per pixel of the full pass (default: the scene's)",
     "an integer in [1, 4096]"},
    {"depth", OPT_DEPTH, "D", "the deepest ray tree (default: the scene's)", "an integer in [1, 64]"},
    {"threads", OPT_THREADS, "N", "worker threads (default: one per processor)", "an integer in [1, 1024]"},
    {"local", OPT_LOCAL, NULL, "primary rays and local Phong only, as refray render --local", NULL},
    {"two-sided", OPT_TWO_SIDED, NULL, "every surface seen from both sides, tracer and raster alike", NULL},
    {"show", OPT_SHOW, "tracer|raster|diff", "the view to start with (keys T, G, D)", "tracer, raster or diff"},
    {"screenshot", OPT_SCREENSHOT, "OUT.png", "once converged, save the window's pixels (8-bit) and exit", NULL},
    {"save", OPT_SAVE, "OUT.exr", "with --screenshot: the linear image shown too (.exr, or .png encoded)", NULL},
    {"timeout", OPT_TIMEOUT, "S", "with --screenshot: give up after S seconds (default 60)", "a number >= 0"},
    RF_OPT_TABLE_END,
};

static const RfOpt *const view_tables[] = {view_opts, rf_opts_png, rf_opts_load, NULL};

static const RfCommand view_cmd = {
    "refray-view",
    "refray-view [options] SCENE\n",
    "A window on SCENE: the tracer's image refining (refray render's, bit for bit once\n"
    "converged), the comparator's OpenGL rasterization and their difference.\n",
    view_tables,
    NULL, /* the keys: set at run time (keys_help) */
};

/* ---- GL entry points the window's own drawing needs ---- */
#define VIEW_GL(X)                                                                                  \
    X(PFNGLGENTEXTURESPROC, GenTextures) X(PFNGLBINDTEXTUREPROC, BindTexture)                     \
    X(PFNGLTEXIMAGE2DPROC, TexImage2D) X(PFNGLTEXPARAMETERIPROC, TexParameteri)                   \
    X(PFNGLCREATESHADERPROC, CreateShader) X(PFNGLSHADERSOURCEPROC, ShaderSource)                 \
    X(PFNGLCOMPILESHADERPROC, CompileShader) X(PFNGLGETSHADERIVPROC, GetShaderiv)                 \
    X(PFNGLCREATEPROGRAMPROC, CreateProgram) X(PFNGLATTACHSHADERPROC, AttachShader)               \
    X(PFNGLLINKPROGRAMPROC, LinkProgram) X(PFNGLUSEPROGRAMPROC, UseProgram)                       \
    X(PFNGLGENVERTEXARRAYSPROC, GenVertexArrays) X(PFNGLBINDVERTEXARRAYPROC, BindVertexArray)     \
    X(PFNGLDRAWARRAYSPROC, DrawArrays) X(PFNGLVIEWPORTPROC, Viewport)                             \
    X(PFNGLCLEARPROC, Clear) X(PFNGLDISABLEPROC, Disable) X(PFNGLREADPIXELSPROC, ReadPixels)      \
    X(PFNGLPIXELSTOREIPROC, PixelStorei) X(PFNGLACTIVETEXTUREPROC, ActiveTexture)                 \
    X(PFNGLGETUNIFORMLOCATIONPROC, GetUniformLocation) X(PFNGLUNIFORM1IPROC, Uniform1i)           \
    X(PFNGLBINDFRAMEBUFFERPROC, BindFramebuffer) X(PFNGLREADBUFFERPROC, ReadBuffer)
typedef struct {
#define X(type, name) type name;
    VIEW_GL(X)
#undef X
} Gl;

static RfGlProc glfw_proc(void *ctx, const char *name)
{
    (void)ctx;
    return (RfGlProc)glfwGetProcAddress(name);
}

/* A full-window triangle showing the texture, display-encoded as refray's PNG (v^(1/2.2)). */
static const char *const vs_src = "#version 330 core\n"
                                  "out vec2 uv;\n"
                                  "void main() {\n"
                                  "  vec2 p = vec2((gl_VertexID << 1) & 2, gl_VertexID & 2);\n"
                                  "  uv = vec2(p.x, 1.0 - p.y);\n" /* image row 0 at the top */
                                  "  gl_Position = vec4(2.0 * p - 1.0, 0.0, 1.0);\n"
                                  "}\n";
static const char *const fs_src = "#version 330 core\n"
                                  "in vec2 uv;\n"
                                  "out vec4 color;\n"
                                  "uniform sampler2D image;\n"
                                  "uniform int encode;\n"
                                  "void main() {\n"
                                  "  vec3 v = clamp(texture(image, uv).rgb, 0.0, 1.0);\n"
                                  "  color = vec4(encode == 1 ? pow(v, vec3(1.0 / 2.2)) : v, 1.0);\n"
                                  "}\n";

/* ---- what the worker and the window share, under lock ---- */
typedef struct {
    pthread_mutex_t lock;
    pthread_cond_t wake;
    RfImage shown;       /* the tracer's image as it refines */
    int dirty;           /* new pixels since the last upload */
    unsigned generation; /* bumped by every change: the worker restarts */
    unsigned done_gen;   /* the generation whose last pass finished (none yet: generation - 1) */
    volatile int cancel;
    int quit;
    /* the settings of the next render */
    RfScene *next_scene; /* a freshly loaded scene for the worker (owned here until taken) */
    RfSceneCamera cam;
    int local, two_sided, depth, samples, threads, width, height;
    /* status */
    int pass_samples;
    double seconds, mrays;
    char kernel[160];
} Shared;

static void on_tile(void *ctx, const RfImage *img, RfTile t)
{
    Shared *sh = ctx;
    pthread_mutex_lock(&sh->lock);
    if (sh->shown.width == img->width && sh->shown.height == img->height)
        for (int y = t.y0; y < t.y1; y++)
            memcpy(sh->shown.data + ((size_t)y * (size_t)img->width + (size_t)t.x0) * 3,
                   img->data + ((size_t)y * (size_t)img->width + (size_t)t.x0) * 3,
                   sizeof(float) * 3 * (size_t)(t.x1 - t.x0));
    sh->dirty = 1;
    pthread_mutex_unlock(&sh->lock);
}

static double now_s(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

/* The worker: for each generation, a 1-sample pass, then the full count (the converged image:
 * `refray render` with these settings). A change cancels the pass in flight. */
static void *worker(void *arg)
{
    Shared *sh = arg;
    RfScene *scene = NULL;
    pthread_mutex_lock(&sh->lock);
    while (!sh->quit) {
        if (sh->done_gen == sh->generation && !sh->next_scene) {
            pthread_cond_wait(&sh->wake, &sh->lock);
            continue;
        }
        unsigned gen = sh->generation;
        if (sh->next_scene) {
            if (scene) {
                rf_scene_free(scene);
                free(scene);
            }
            scene = sh->next_scene;
            sh->next_scene = NULL;
        }
        scene->camera = sh->cam;
        int local = sh->local, two_sided = sh->two_sided, depth = sh->depth, samples = sh->samples,
            threads = sh->threads;
        __atomic_store_n(&sh->cancel, 0, __ATOMIC_RELAXED);
        pthread_mutex_unlock(&sh->lock);
        int finished = 1;
        for (int pass = 0; pass < 2 && finished; pass++) {
            if (pass == 0 && samples == 1)
                continue;
            RfRenderOptions o = rf_render_options_default();
            RfRenderStats st;
            RfImage img;
            o.width = sh->width, o.height = sh->height, o.threads = threads, o.local_only = local;
            o.two_sided = two_sided;
            o.max_depth = depth, o.samples = pass == 0 ? 1 : samples, o.preview = 1;
            o.tile_done = on_tile, o.tile_done_ctx = sh, o.cancel = &sh->cancel;
            double t0 = now_s();
            RfStatus rs = rf_render(scene, &o, &img, &st);
            double secs = now_s() - t0;
            pthread_mutex_lock(&sh->lock);
            if (rs == RF_OK) { /* every tile is in sh->shown already (on_tile) */
                sh->pass_samples = o.samples;
                sh->seconds = secs;
                uint64_t rays = st.primary_rays + st.shadow_rays + st.secondary_rays;
                sh->mrays = st.trace_seconds > 0 ? (double)rays / st.trace_seconds * 1e-6 : 0.0;
                rf_kernel_name(st.kernel, sh->kernel, sizeof sh->kernel);
                rf_image_free(&img);
            } else {
                finished = 0;
            }
            finished &= sh->generation == gen;
            pthread_mutex_unlock(&sh->lock);
        }
        pthread_mutex_lock(&sh->lock);
        if (finished && sh->generation == gen)
            sh->done_gen = gen;
    }
    pthread_mutex_unlock(&sh->lock);
    if (scene) {
        rf_scene_free(scene);
        free(scene);
    }
    return NULL;
}

/* ---- the window ---- */
typedef struct {
    Shared *sh;
    const char *path;
    RfLoadOptions lopt;
    RfScene scene;          /* the window's copy: rasterization, inspector, camera */
    RfSceneCamera home;     /* R resets to it */
    int mode;               /* 0 tracer, 1 raster, 2 difference */
    RfImage raster, diff;
    int raster_stale;
    double diff_max;
    char inspected[200];    /* the pixel inspector's last answer, for the status line */
    double mx, my, press_x, press_y;
    int dragging, button, shift;
    int saved;
    char error[600];        /* the last reload's error, or "" */
    struct timespec mtime; /* of the scene file, to the nanosecond: edits come fast */
    off_t size;
} View;

static void restart(View *v)
{
    Shared *sh = v->sh;
    pthread_mutex_lock(&sh->lock);
    sh->cam = v->scene.camera;
    sh->generation++;
    __atomic_store_n(&sh->cancel, 1, __ATOMIC_RELAXED);
    pthread_cond_signal(&sh->wake);
    pthread_mutex_unlock(&sh->lock);
    v->raster_stale = 1;
}

static RfScene *load_copy(View *v, char *err, size_t errsz)
{
    RfScene *s = malloc(sizeof *s);
    if (!s) {
        snprintf(err, errsz, "out of memory");
        return NULL;
    }
    if (rf_scene_load(v->path, &v->lopt, s, err, errsz) != RF_OK) {
        free(s);
        return NULL;
    }
    return s;
}

/* Reloads the scene when its file changed: both copies, the camera kept if the file's camera
 * did not change. A broken edit keeps the last good scene and shows the error. */
static void maybe_reload(View *v)
{
    struct stat sb;
    if (stat(v->path, &sb) != 0 ||
        (sb.st_mtim.tv_sec == v->mtime.tv_sec && sb.st_mtim.tv_nsec == v->mtime.tv_nsec && sb.st_size == v->size))
        return;
    v->mtime = sb.st_mtim;
    v->size = sb.st_size;
    char err[600];
    RfScene fresh;
    if (rf_scene_load(v->path, &v->lopt, &fresh, err, sizeof err) != RF_OK) {
        snprintf(v->error, sizeof v->error, "%s", err);
        fprintf(stderr, "refray-view: %s (the last good scene stays)\n", err);
        return;
    }
    RfScene *worker_copy = load_copy(v, err, sizeof err);
    if (!worker_copy) {
        rf_scene_free(&fresh);
        snprintf(v->error, sizeof v->error, "%s", err);
        return;
    }
    v->error[0] = 0;
    rf_scene_free(&v->scene);
    v->scene = fresh;
    v->home = fresh.camera;
    pthread_mutex_lock(&v->sh->lock);
    if (v->sh->next_scene) {
        rf_scene_free(v->sh->next_scene);
        free(v->sh->next_scene);
    }
    v->sh->next_scene = worker_copy;
    pthread_mutex_unlock(&v->sh->lock);
    fprintf(stderr, "refray-view: reloaded %s\n", v->path);
    restart(v);
}

static RfVec3 cam_basis_right(const RfSceneCamera *c)
{
    RfVec3 w = rf_vec3_normalize(rf_vec3_sub(c->eye, c->target));
    return rf_vec3_normalize(rf_vec3_cross(c->up, w));
}

static void orbit(View *v, double dx, double dy)
{
    RfSceneCamera *c = &v->scene.camera;
    RfVec3 up = rf_vec3_normalize(c->up), off = rf_vec3_sub(c->eye, c->target);
    /* yaw about up, pitch about the camera's right axis (Rodrigues), kept off the poles */
    RfVec3 axes[2] = {up, cam_basis_right(c)};
    double ang[2] = {-dx * 0.01, -dy * 0.01};
    for (int k = 0; k < 2; k++) {
        RfVec3 a = axes[k];
        double cs = cos(ang[k]), sn = sin(ang[k]);
        RfVec3 r = rf_vec3_add(rf_vec3_add(rf_vec3_scale(off, cs), rf_vec3_scale(rf_vec3_cross(a, off), sn)),
                               rf_vec3_scale(a, rf_vec3_dot(a, off) * (1 - cs)));
        if (k == 1 && fabs(rf_vec3_dot(rf_vec3_normalize(r), up)) > 0.995)
            continue;
        off = r;
    }
    c->eye = rf_vec3_add(c->target, off);
    restart(v);
}

static void pan(View *v, double dx, double dy)
{
    RfSceneCamera *c = &v->scene.camera;
    double dist = rf_vec3_length(rf_vec3_sub(c->eye, c->target)) * 0.002;
    RfVec3 right = cam_basis_right(c);
    RfVec3 up = rf_vec3_cross(rf_vec3_normalize(rf_vec3_sub(c->eye, c->target)), right);
    RfVec3 m = rf_vec3_add(rf_vec3_scale(right, -dx * dist), rf_vec3_scale(up, dy * dist));
    c->eye = rf_vec3_add(c->eye, m);
    c->target = rf_vec3_add(c->target, m);
    restart(v);
}

static void print_camera(const RfSceneCamera *c)
{
    printf("camera eye %.9g %.9g %.9g  target %.9g %.9g %.9g  up %.9g %.9g %.9g", c->eye.x, c->eye.y, c->eye.z,
           c->target.x, c->target.y, c->target.z, c->up.x, c->up.y, c->up.z);
    if (c->has_window)
        printf("  window %.9g %.9g %.9g %.9g", c->l, c->r, c->b, c->t);
    else
        printf("  fov %.9g", c->fov);
    printf("\n");
    fflush(stdout);
}

/* The pixel inspector: the tracer's linear RGB there, and what the primary ray through the
 * pixel centre meets. */
static void inspect(View *v, int x, int y)
{
    Shared *sh = v->sh;
    if (x < 0 || y < 0 || x >= sh->width || y >= sh->height)
        return;
    float px[3];
    pthread_mutex_lock(&sh->lock);
    memcpy(px, sh->shown.data + ((size_t)y * (size_t)sh->width + (size_t)x) * 3, sizeof px);
    pthread_mutex_unlock(&sh->lock);
    RfCamera cam;
    const RfSceneCamera *sc = &v->scene.camera;
    RfWindow w = rf_scene_camera_window(sc, sh->width, sh->height);
    RfTracer *t = NULL;
    printf("pixel (%d, %d): linear RGB %.6g %.6g %.6g", x, y, px[0], px[1], px[2]);
    snprintf(v->inspected, sizeof v->inspected, "(%d, %d) = %.4g %.4g %.4g", x, y, px[0], px[1], px[2]);
    if (rf_camera_init(&cam, sc->eye, sc->target, sc->up, w.d, w.l, w.r, w.b, w.t, sh->width, sh->height) == RF_OK &&
        rf_tracer_create(&v->scene, &t) == RF_OK) {
        RfRay ray = rf_camera_ray(&cam, x + 0.5, y + 0.5, 0.0, 0.0);
        RfSurfaceHit h;
        int p = rf_tracer_intersect(t, &ray, 0.0, HUGE_VAL, &h);
        if (p >= 0) {
            const RfPrimitive *pr = &v->scene.prims[p];
            printf("; hits %s #%d (line %d, material '%s') at t = %.9g, point %.9g %.9g %.9g",
                   rf_prim_type_name(pr->type), p, pr->loc.line, v->scene.materials[h.material].name, h.t,
                   h.point.x, h.point.y, h.point.z);
            size_t n = strlen(v->inspected);
            snprintf(v->inspected + n, sizeof v->inspected - n, " %s #%d", rf_prim_type_name(pr->type), p);
        } else {
            printf("; the primary ray meets nothing");
        }
        rf_tracer_free(t);
    }
    printf("\n");
    fflush(stdout);
}

static void on_scroll(GLFWwindow *win, double sx, double sy);

static void on_key(GLFWwindow *win, int key, int scancode, int action, int mods)
{
    (void)scancode;
    View *v = glfwGetWindowUserPointer(win);
    Shared *sh = v->sh;
    v->shift = (mods & GLFW_MOD_SHIFT) != 0;
    if (action != GLFW_PRESS && action != GLFW_REPEAT)
        return;
    int changed = 0;
    pthread_mutex_lock(&sh->lock);
    switch (key) {
    case GLFW_KEY_T: v->mode = 0; break;
    case GLFW_KEY_G: v->mode = 1; break;
    case GLFW_KEY_D: v->mode = 2; break;
    case GLFW_KEY_L: sh->local = !sh->local, changed = 1; break;
    case GLFW_KEY_LEFT_BRACKET: if (sh->depth > 1) sh->depth--, changed = 1; break;
    case GLFW_KEY_RIGHT_BRACKET: if (sh->depth < 64) sh->depth++, changed = 1; break;
    case GLFW_KEY_MINUS: if (sh->samples > 1) sh->samples /= 2, changed = 1; break;
    case GLFW_KEY_EQUAL: if (sh->samples < 4096) sh->samples *= 2, changed = 1; break;
    case GLFW_KEY_Q:
    case GLFW_KEY_ESCAPE: glfwSetWindowShouldClose(win, 1); break;
    default: break;
    }
    pthread_mutex_unlock(&sh->lock);
    if (key == GLFW_KEY_R) {
        v->scene.camera = v->home;
        changed = 1;
    } else if (key == GLFW_KEY_LEFT || key == GLFW_KEY_RIGHT || key == GLFW_KEY_UP || key == GLFW_KEY_DOWN) {
        orbit(v, key == GLFW_KEY_LEFT ? -10 : key == GLFW_KEY_RIGHT ? 10 : 0,
              key == GLFW_KEY_UP ? -10 : key == GLFW_KEY_DOWN ? 10 : 0);
    } else if (key == GLFW_KEY_PAGE_UP || key == GLFW_KEY_PAGE_DOWN) {
        on_scroll(win, 0.0, key == GLFW_KEY_PAGE_UP ? 1.0 : -1.0);
    } else if (key == GLFW_KEY_C) {
        print_camera(&v->scene.camera);
    } else if (key == GLFW_KEY_S) {
        v->saved = -1; /* saved after the next draw (main loop) */
    }
    if (changed)
        restart(v);
}

static void on_button(GLFWwindow *win, int button, int action, int mods)
{
    View *v = glfwGetWindowUserPointer(win);
    if (action == GLFW_PRESS) {
        v->dragging = 1;
        v->button = (button == GLFW_MOUSE_BUTTON_RIGHT || (mods & GLFW_MOD_SHIFT)) ? 1 : 0;
        v->press_x = v->mx, v->press_y = v->my;
    } else if (action == GLFW_RELEASE) {
        v->dragging = 0;
        if (button == GLFW_MOUSE_BUTTON_LEFT && fabs(v->mx - v->press_x) < 2 && fabs(v->my - v->press_y) < 2) {
            int ww, wh;
            glfwGetWindowSize(win, &ww, &wh);
            inspect(v, (int)(v->mx * v->sh->width / (ww > 0 ? ww : 1)), (int)(v->my * v->sh->height / (wh > 0 ? wh : 1)));
        }
    }
}

static void on_move(GLFWwindow *win, double x, double y)
{
    View *v = glfwGetWindowUserPointer(win);
    double dx = x - v->mx, dy = y - v->my;
    v->mx = x, v->my = y;
    if (!v->dragging || (fabs(x - v->press_x) < 2 && fabs(y - v->press_y) < 2))
        return;
    if (v->button)
        pan(v, dx, dy);
    else
        orbit(v, dx, dy);
}

static void on_scroll(GLFWwindow *win, double sx, double sy)
{
    (void)sx;
    View *v = glfwGetWindowUserPointer(win);
    RfSceneCamera *c = &v->scene.camera;
    c->eye = rf_vec3_add(c->target, rf_vec3_scale(rf_vec3_sub(c->eye, c->target), pow(0.9, sy)));
    restart(v);
}

/* |tracer - raster| per pixel (the largest channel), black -> red -> yellow -> white up to the
 * image's largest difference */
static void make_diff(View *v, const RfImage *tr)
{
    size_t n = (size_t)tr->width * (size_t)tr->height;
    double mx = 0.0;
    for (size_t i = 0; i < n; i++)
        for (int c = 0; c < 3; c++)
            mx = fmax(mx, fabs((double)tr->data[3 * i + c] - v->raster.data[3 * i + c]));
    v->diff_max = mx;
    for (size_t i = 0; i < n; i++) {
        double d = 0.0;
        for (int c = 0; c < 3; c++)
            d = fmax(d, fabs((double)tr->data[3 * i + c] - v->raster.data[3 * i + c]));
        double h = mx > 0 ? d / mx * 3.0 : 0.0;
        v->diff.data[3 * i] = (float)fmin(1.0, h);
        v->diff.data[3 * i + 1] = (float)fmin(1.0, fmax(0.0, h - 1.0));
        v->diff.data[3 * i + 2] = (float)fmin(1.0, fmax(0.0, h - 2.0));
    }
}

int main(int argc, char **argv)
{
    const char *scene_path = NULL, *screenshot = NULL, *save = NULL;
    int width = 0, height = 0, samples = 0, depth = 0, threads = 0, local = 0, two_sided = 0, show = 0;
    double timeout = 60.0;
    RfLoadOptions lopt = rf_load_options_default();
    RfPngOptions popt = {RF_PNG_GAMMA, 2.2, 8, NULL};
    RfCommand cmd = view_cmd;
    char notes[4096];
    snprintf(notes, sizeof notes, "--screenshot exits 0, or 2 after --timeout seconds; the PNG has the display's gamma 2.2.\n"
                                  "%sexit: 0 ok, 2 no converged image or no window, 4 a file cannot be read or written,\n"
                                  "5 usage (README: Exit codes)\n", keys_help);
    cmd.notes = notes;
    RfOptParser p;
    int key;
    rf_opt_init(&p, &cmd, argc, argv);
    while ((key = rf_opt_next(&p)) != RF_OPT_DONE) {
        const char *val = p.value;
        int ok = 1;
        switch (key) {
        case RF_OPT_EXIT: return p.exit_code;
        case OPT_WIDTH: ok = rf_arg_int(val, 1, 16384, &width); break;
        case OPT_HEIGHT: ok = rf_arg_int(val, 1, 16384, &height); break;
        case OPT_SAMPLES: ok = rf_arg_int(val, 1, 4096, &samples); break;
        case OPT_DEPTH: ok = rf_arg_int(val, 1, 64, &depth); break;
        case OPT_THREADS: ok = rf_arg_int(val, 1, 1024, &threads); break;
        case OPT_LOCAL: local = 1; break;
        case OPT_TWO_SIDED: two_sided = 1; break;
        case OPT_SHOW:
            show = strcmp(val, "tracer") == 0 ? 0 : strcmp(val, "raster") == 0 ? 1 : strcmp(val, "diff") == 0 ? 2 : -1;
            ok = show >= 0;
            break;
        case OPT_SCREENSHOT: screenshot = val; break;
        case OPT_SAVE: save = val; break;
        case OPT_TIMEOUT: ok = rf_arg_nonneg(val, &timeout); break;
        default: ok = rf_arg_shared(key, val, &lopt, &popt) > 0;
        }
        if (!ok)
            return rf_opt_bad_value(&p);
    }
    int bad = rf_opt_operand(&p, "the scene file", &scene_path);
    if (bad)
        return bad;
    char err[1024];
    if (save && !screenshot)
        return rf_opt_usage_error(&cmd, "--save comes with --screenshot");
    if (screenshot) {
        const char *outs[2] = {screenshot, save}, *ins[1] = {scene_path};
        if (!rf_arg_image_format("refray-view", "--screenshot", screenshot, RF_IMAGE_PNG) ||
            (save && !rf_arg_image_format("refray-view", "--save", save, RF_IMAGE_EXR | RF_IMAGE_PNG)))
            return RF_EXIT_USAGE;
        bad = rf_arg_outputs_check("refray-view", outs, 2, ins, 1);
        if (bad)
            return bad;
    }
    View v;
    memset(&v, 0, sizeof v);
    v.path = scene_path;
    v.lopt = lopt;
    v.mode = show;
    if (rf_scene_load(scene_path, &lopt, &v.scene, err, sizeof err) != RF_OK) {
        rf_arg_report("refray-view", err);
        return RF_EXIT_FILE;
    }
    struct stat sb;
    if (stat(scene_path, &sb) == 0)
        v.mtime = sb.st_mtim, v.size = sb.st_size;
    v.home = v.scene.camera;
    Shared sh;
    memset(&sh, 0, sizeof sh);
    sh.done_gen = sh.generation - 1; /* nothing rendered yet */
    pthread_mutex_init(&sh.lock, NULL);
    pthread_cond_init(&sh.wake, NULL);
    v.sh = &sh;
    sh.width = width > 0 ? width : v.scene.render.width;
    sh.height = height > 0 ? height : v.scene.render.height;
    sh.samples = samples > 0 ? samples : (v.scene.render.samples > 0 ? v.scene.render.samples : 1);
    sh.depth = depth > 0 ? depth : v.scene.render.max_depth;
    sh.threads = threads;
    sh.local = local;
    sh.two_sided = two_sided;
    sh.cam = v.scene.camera;
    sh.next_scene = load_copy(&v, err, sizeof err);
    if (!sh.next_scene || rf_image_alloc(&sh.shown, sh.width, sh.height, 3) != RF_OK ||
        rf_image_alloc(&v.diff, sh.width, sh.height, 3) != RF_OK) {
        fprintf(stderr, "refray-view: %s\n", sh.next_scene ? "out of memory" : err);
        return RF_EXIT_FAIL;
    }
    if (!glfwInit()) {
        fprintf(stderr, "refray-view: GLFW cannot start (no display? run it under xvfb-run)\n");
        return RF_EXIT_FAIL;
    }
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
    glfwWindowHint(GLFW_RESIZABLE, GLFW_FALSE);
    GLFWwindow *win = glfwCreateWindow(sh.width, sh.height, "refray-view", NULL, NULL);
    if (!win) {
        fprintf(stderr, "refray-view: no OpenGL 4.5 core window\n");
        glfwTerminate();
        return RF_EXIT_FAIL;
    }
    glfwMakeContextCurrent(win);
    glfwSwapInterval(1);
    Gl gl;
#define X(type, name)                                                                               \
    if (!(gl.name = (type)glfwGetProcAddress("gl" #name))) {                                      \
        fprintf(stderr, "refray-view: GL function gl" #name " missing\n");                        \
        return RF_EXIT_FAIL;                                                                                   \
    }
    VIEW_GL(X)
#undef X
    GLuint prog = gl.CreateProgram(), vao, tex;
    const char *srcs[2] = {vs_src, fs_src};
    GLenum kinds[2] = {GL_VERTEX_SHADER, GL_FRAGMENT_SHADER};
    for (int k = 0; k < 2; k++) {
        GLuint s = gl.CreateShader(kinds[k]);
        GLint okc = 0;
        gl.ShaderSource(s, 1, &srcs[k], NULL);
        gl.CompileShader(s);
        gl.GetShaderiv(s, GL_COMPILE_STATUS, &okc);
        if (!okc) {
            fprintf(stderr, "refray-view: display shader does not compile\n");
            return RF_EXIT_FAIL;
        }
        gl.AttachShader(prog, s);
    }
    gl.LinkProgram(prog);
    gl.GenVertexArrays(1, &vao);
    gl.GenTextures(1, &tex);
    glfwSetWindowUserPointer(win, &v);
    glfwSetKeyCallback(win, on_key);
    glfwSetMouseButtonCallback(win, on_button);
    glfwSetCursorPosCallback(win, on_move);
    glfwSetScrollCallback(win, on_scroll);
    v.raster_stale = 1;
    pthread_t th;
    pthread_create(&th, NULL, worker, &sh);
    double start = now_s(), last_poll = 0.0;
    int rc = 0, shown_done_frames = 0, uploaded = 0;
    RfImage frame = {0, 0, 0, NULL};
    rf_image_alloc(&frame, sh.width, sh.height, 3);
    while (!glfwWindowShouldClose(win)) {
        glfwWaitEventsTimeout(0.03);
        if (now_s() - last_poll > 0.5) {
            maybe_reload(&v);
            last_poll = now_s();
        }
        /* the tracer's pixels, copied out under the lock */
        pthread_mutex_lock(&sh.lock);
        int upload = sh.dirty || v.mode != 0;
        memcpy(frame.data, sh.shown.data, sizeof(float) * 3 * (size_t)sh.width * (size_t)sh.height);
        sh.dirty = 0;
        int done = sh.done_gen == sh.generation;
        char status[1600];
        snprintf(status, sizeof status, "refray-view %s | %s%s | %d/%d spp, depth %d | %.2f s, %.1f Mrays/s | %s%s%s%s%s",
                 scene_path, v.mode == 0 ? "tracer" : v.mode == 1 ? "OpenGL raster" : "difference",
                 sh.local ? " (local)" : "", done ? sh.pass_samples : 0, sh.samples, sh.depth, sh.seconds, sh.mrays,
                 sh.kernel, v.inspected[0] ? " | pixel " : "", v.inspected, v.error[0] ? " | ERROR: " : "", v.error);
        pthread_mutex_unlock(&sh.lock);
        if (v.mode != 0 && v.raster_stale) {
            RfRasterOptions ro = {sh.width, sh.height, RF_SHADE_PHONG, sh.two_sided};
            rf_image_free(&v.raster);
            if (rf_raster_render(&v.scene, &ro, glfw_proc, NULL, &v.raster, NULL, err, sizeof err) != RF_OK) {
                fprintf(stderr, "refray-view: raster: %s\n", err);
                v.mode = 0;
            }
            v.raster_stale = 0;
        }
        const RfImage *img = &frame;
        if (v.mode == 1 && v.raster.data)
            img = &v.raster;
        else if (v.mode == 2 && v.raster.data) {
            make_diff(&v, &frame);
            img = &v.diff;
            size_t n = strlen(status);
            snprintf(status + n, sizeof status - n, " | heat scale: white = %.3g", v.diff_max);
        }
        glfwSetWindowTitle(win, status);
        int fw, fh;
        glfwGetFramebufferSize(win, &fw, &fh);
        gl.BindFramebuffer(GL_FRAMEBUFFER, 0);
        gl.Viewport(0, 0, fw, fh);
        gl.Disable(GL_DEPTH_TEST);
        gl.ActiveTexture(GL_TEXTURE0);
        gl.BindTexture(GL_TEXTURE_2D, tex);
        if (upload || !uploaded) {
            gl.PixelStorei(GL_UNPACK_ALIGNMENT, 4);
            gl.TexImage2D(GL_TEXTURE_2D, 0, GL_RGB32F, img->width, img->height, 0, GL_RGB, GL_FLOAT, img->data);
            gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
            gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
            uploaded = 1;
        }
        gl.UseProgram(prog);
        gl.Uniform1i(gl.GetUniformLocation(prog, "image"), 0);
        gl.Uniform1i(gl.GetUniformLocation(prog, "encode"), v.mode == 2 ? 0 : 1);
        gl.BindVertexArray(vao);
        gl.DrawArrays(GL_TRIANGLES, 0, 3);
        if (v.saved == -1) { /* S: what is shown, linear EXR and display PNG */
            static int n = 0;
            char exr[64], png[64];
            snprintf(exr, sizeof exr, "view-%d.exr", ++n);
            snprintf(png, sizeof png, "view-%d.png", n);
            if (rf_exr_write(exr, img, NULL, 0, err, sizeof err) != RF_OK ||
                rf_png_write(png, img, v.mode == 2 ? (RfPngOptions){RF_PNG_AS_IS, 1.0, 8, NULL} : popt, err,
                             sizeof err) != RF_OK)
                fprintf(stderr, "refray-view: %s\n", err);
            else
                fprintf(stderr, "refray-view: saved %s and %s\n", exr, png);
            v.saved = 0;
        }
        if (screenshot) {
            shown_done_frames = done ? shown_done_frames + 1 : 0;
            if (shown_done_frames >= 2) { /* the converged image has been uploaded and drawn */
                unsigned char *rgb = malloc((size_t)fw * (size_t)fh * 3);
                RfImage shot;
                if (rgb && rf_image_alloc(&shot, fw, fh, 3) == RF_OK) {
                    gl.PixelStorei(GL_PACK_ALIGNMENT, 1);
                    gl.ReadBuffer(GL_BACK);
                    gl.ReadPixels(0, 0, fw, fh, GL_RGB, GL_UNSIGNED_BYTE, rgb);
                    for (int y = 0; y < fh; y++) /* GL's rows go up */
                        for (int x = 0; x < fw * 3; x++)
                            shot.data[(size_t)y * (size_t)fw * 3 + (size_t)x] =
                                rgb[(size_t)(fh - 1 - y) * (size_t)fw * 3 + (size_t)x] / 255.0f;
                    RfPngOptions asis = {RF_PNG_AS_IS, 1.0, 8, NULL};
                    RfExrOptions eopt = {RF_EXR_ZIP, 0, NULL, 0, 0, 0, 0};
                    if ((save && rf_arg_write_image(save, img, NULL, 0, eopt, popt, err, sizeof err) != RF_OK) ||
                        rf_png_write(screenshot, &shot, asis, err, sizeof err) != RF_OK) {
                        fprintf(stderr, "refray-view: %s\n", err);
                        rc = RF_EXIT_FILE;
                    } else {
                        fprintf(stderr, "refray-view: %s: the converged %d spp image, %dx%d\n", screenshot,
                                sh.pass_samples, fw, fh);
                    }
                    rf_image_free(&shot);
                }
                free(rgb);
                glfwSetWindowShouldClose(win, 1);
            } else if (now_s() - start > timeout) {
                fprintf(stderr, "refray-view: the render did not converge within %g s; no screenshot\n", timeout);
                rc = RF_EXIT_FAIL;
                glfwSetWindowShouldClose(win, 1);
            }
        }
        glfwSwapBuffers(win);
    }
    pthread_mutex_lock(&sh.lock);
    sh.quit = 1;
    __atomic_store_n(&sh.cancel, 1, __ATOMIC_RELAXED);
    pthread_cond_signal(&sh.wake);
    pthread_mutex_unlock(&sh.lock);
    pthread_join(th, NULL);
    if (sh.next_scene) {
        rf_scene_free(sh.next_scene);
        free(sh.next_scene);
    }
    rf_image_free(&frame);
    rf_image_free(&sh.shown);
    rf_image_free(&v.raster);
    rf_image_free(&v.diff);
    rf_scene_free(&v.scene);
    glfwDestroyWindow(win);
    glfwTerminate();
    return rc;
}
