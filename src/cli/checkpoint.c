/* Checkpoints of a render and the signals that interrupt it (checkpoint.h). */
#include "checkpoint.h"

#include <pthread.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "farm.h"
#include "refray/render.h"

struct RfCheckpoint {
    pthread_mutex_t lock;
    char *path, *hint;
    double every, last;
    struct timespec start;
    RfImage pixels;      /* the crop: the done tiles' pixels, zero elsewhere */
    unsigned char *done; /* per render tile (RF_RENDER_TILE) of the crop */
    int tiles, ndone;
    RfExrOptions windows;
    RfImageAttr *attrs; /* the identity, then refray:partial and refray:tilesDone */
    int nattrs;
    char error[512];
};

static double now_seconds(const RfCheckpoint *c)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)(t.tv_sec - c->start.tv_sec) + 1e-9 * (double)(t.tv_nsec - c->start.tv_nsec);
}

RfCheckpoint *rf_checkpoint_new(const char *path, double every, int w, int h, RfExrOptions windows,
                                const RfImageAttr *attrs, int nattrs, const char *hint)
{
    RfCheckpoint *c = calloc(1, sizeof *c);
    if (!c)
        return NULL;
    pthread_mutex_init(&c->lock, NULL);
    clock_gettime(CLOCK_MONOTONIC, &c->start);
    c->path = strdup(path);
    c->hint = strdup(hint);
    c->every = every;
    c->tiles = rf_render_tile_count(w, h);
    c->done = calloc((size_t)c->tiles, 1);
    c->windows = windows;
    c->windows.batch = NULL;
    c->attrs = calloc((size_t)nattrs + 2, sizeof *c->attrs);
    c->nattrs = nattrs;
    if (!c->path || !c->hint || !c->done || !c->attrs || rf_image_alloc(&c->pixels, w, h, 3) != RF_OK) {
        rf_checkpoint_free(c);
        return NULL;
    }
    for (int i = 0; i < nattrs; i++)
        c->attrs[i] = attrs[i];
    return c;
}

void rf_checkpoint_free(RfCheckpoint *c)
{
    if (!c)
        return;
    pthread_mutex_destroy(&c->lock);
    rf_image_free(&c->pixels);
    free(c->done);
    free(c->attrs);
    free(c->path);
    free(c->hint);
    free(c);
}

/* The file, with c->lock held. */
static int write_locked(RfCheckpoint *c, char *err, size_t errsz)
{
    char partial[1024];
    char *ranges = rf_farm_ranges_format(c->done, c->tiles);
    if (!ranges) {
        snprintf(err, errsz, "%s: out of memory", c->path);
        return 0;
    }
    snprintf(partial, sizeof partial,
             "PARTIAL RENDER, NOT AN IMAGE: %d of %d tiles of %dx%d pixels done (black elsewhere); finish it with: %s",
             c->ndone, c->tiles, RF_RENDER_TILE, RF_RENDER_TILE, c->hint);
    c->attrs[c->nattrs] = (RfImageAttr){"refray:partial", partial};
    c->attrs[c->nattrs + 1] = (RfImageAttr){"refray:tilesDone", ranges};
    RfStatus st = rf_exr_write_opts(c->path, &c->pixels, c->attrs, c->nattrs + 2, c->windows, err, errsz);
    free(ranges);
    c->last = now_seconds(c);
    return st == RF_OK;
}

void rf_checkpoint_tile_done(void *ctx, const RfImage *img, RfTile tile)
{
    RfCheckpoint *c = ctx;
    pthread_mutex_lock(&c->lock);
    for (int y = tile.y0; y < tile.y1; y++)
        memcpy(c->pixels.data + ((size_t)y * (size_t)img->width + (size_t)tile.x0) * 3,
               img->data + ((size_t)y * (size_t)img->width + (size_t)tile.x0) * 3,
               sizeof(float) * 3 * (size_t)(tile.x1 - tile.x0));
    if (!c->done[tile.index]) {
        c->done[tile.index] = 1;
        c->ndone++;
    }
    if (now_seconds(c) - c->last >= c->every && c->ndone < c->tiles) {
        char err[512];
        if (!write_locked(c, err, sizeof err) && !c->error[0])
            snprintf(c->error, sizeof c->error, "%s", err);
    }
    pthread_mutex_unlock(&c->lock);
}

int rf_checkpoint_write_now(RfCheckpoint *c, int *done, int *total, char *err, size_t errsz)
{
    pthread_mutex_lock(&c->lock);
    int ok = write_locked(c, err, errsz);
    *done = c->ndone;
    *total = c->tiles;
    pthread_mutex_unlock(&c->lock);
    return ok;
}

const char *rf_checkpoint_error(const RfCheckpoint *c) { return c->error; }

int rf_checkpoint_resume(RfCheckpoint *c, const char *path, const unsigned char **skip, const RfImage **pixels,
                         char *err, size_t errsz)
{
    char *partial = rf_farm_attr(path, "refray:partial"), *ranges = rf_farm_attr(path, "refray:tilesDone");
    const char *expect[3];
    RfExrWindow data, disp;
    RfImage img = {0, 0, 0, NULL};
    int ok = 0;
    for (int i = 0; i < 3; i++) { /* the identity is the first three attributes (cmd_render.c) */
        expect[i] = "";
        for (int k = 0; k < c->nattrs; k++)
            if (strcmp(c->attrs[k].name, rf_farm_identity[i]) == 0)
                expect[i] = c->attrs[k].value;
    }
    if (rf_exr_read_windows(path, &data, &disp, err, errsz) != RF_OK)
        goto done;
    if (!partial || !ranges) {
        snprintf(err, errsz, "%s: not a refray checkpoint (no refray:partial / refray:tilesDone in its header)", path);
        goto done;
    }
    if (!rf_farm_same_render(path, expect, c->windows.display_width ? c->windows.display_width : c->pixels.width,
                             c->windows.display_height ? c->windows.display_height : c->pixels.height, err, errsz))
        goto done;
    if (data.x0 != c->windows.x0 || data.y0 != c->windows.y0 || data.x1 - data.x0 != c->pixels.width ||
        data.y1 - data.y0 != c->pixels.height) {
        snprintf(err, errsz, "%s: a checkpoint of the window %d,%d,%d,%d, not of %d,%d,%d,%d: another crop", path,
                 data.x0, data.y0, data.x1, data.y1, c->windows.x0, c->windows.y0, c->windows.x0 + c->pixels.width,
                 c->windows.y0 + c->pixels.height);
        goto done;
    }
    if (!rf_farm_ranges_parse(ranges, c->done, c->tiles)) {
        snprintf(err, errsz, "%s: refray:tilesDone \"%.60s\" is not a list of tiles below %d", path, ranges, c->tiles);
        goto done;
    }
    if (rf_exr_read(path, &img, err, errsz) != RF_OK)
        goto done;
    if (img.channels != 3) {
        snprintf(err, errsz, "%s: a checkpoint has R, G and B", path);
        goto done;
    }
    memcpy(c->pixels.data, img.data, sizeof(float) * 3 * (size_t)img.width * (size_t)img.height);
    c->ndone = 0;
    for (int i = 0; i < c->tiles; i++)
        c->ndone += c->done[i];
    *skip = c->done;
    *pixels = &c->pixels;
    ok = 1;
done:
    rf_image_free(&img);
    free(partial);
    free(ranges);
    return ok;
}

/* ---- signals ---- */

struct RfSignalWatch {
    pthread_t thread;
    sigset_t set;
    volatile int *flag;
    int signal; /* the one caught, written before the flag */
};

static void *watch(void *arg)
{
    RfSignalWatch *w = arg;
    int sig = 0;
    if (sigwait(&w->set, &sig) == 0) {
        w->signal = sig;
        __atomic_store_n(w->flag, 1, __ATOMIC_RELEASE);
    }
    return NULL;
}

RfSignalWatch *rf_signal_watch_start(volatile int *flag)
{
    RfSignalWatch *w = calloc(1, sizeof *w);
    if (!w)
        return NULL;
    w->flag = flag;
    sigemptyset(&w->set);
    sigaddset(&w->set, SIGINT);
    sigaddset(&w->set, SIGTERM);
    if (pthread_sigmask(SIG_BLOCK, &w->set, NULL) != 0 || pthread_create(&w->thread, NULL, watch, w) != 0) {
        free(w);
        return NULL;
    }
    return w;
}

int rf_signal_watch_stop(RfSignalWatch *w)
{
    if (!w)
        return 0;
    if (!__atomic_load_n(w->flag, __ATOMIC_ACQUIRE))
        pthread_cancel(w->thread); /* sigwait is a cancellation point */
    pthread_join(w->thread, NULL);
    int sig = __atomic_load_n(w->flag, __ATOMIC_ACQUIRE) ? w->signal : 0;
    free(w);
    return sig;
}
