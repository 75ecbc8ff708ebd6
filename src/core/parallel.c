/* Task and tile scheduling on POSIX threads (see include/refray/parallel.h). */
#include "refray/parallel.h"

#include <pthread.h>
#include <stdlib.h>
#include <unistd.h>

typedef struct {
    int total;
    RfTaskFn fn;
    RfProgressFn progress;
    void *ctx;
    pthread_mutex_t lock;
    int next, done, failed;
} Pool;

typedef struct {
    Pool *pool;
    int thread;
} Worker;

int rf_cpu_count(void)
{
    long n = sysconf(_SC_NPROCESSORS_ONLN);
    return n > 0 ? (int)n : 1;
}

static void *work(void *arg)
{
    Worker *w = arg;
    Pool *p = w->pool;
    for (;;) {
        pthread_mutex_lock(&p->lock);
        int i = p->failed ? p->total : p->next++;
        pthread_mutex_unlock(&p->lock);
        if (i >= p->total)
            break;
        int rc = p->fn(p->ctx, i, w->thread);
        pthread_mutex_lock(&p->lock);
        if (rc)
            p->failed = 1;
        else if (p->progress)
            p->progress(p->ctx, ++p->done, p->total);
        pthread_mutex_unlock(&p->lock);
    }
    return NULL;
}

RfStatus rf_parallel_for(int n, int threads, RfTaskFn fn, RfProgressFn progress, void *ctx)
{
    if (n < 0 || threads < 0)
        return RF_ERR_DOMAIN;
    Pool p;
    p.total = n;
    p.fn = fn;
    p.progress = progress;
    p.ctx = ctx;
    p.next = p.done = p.failed = 0;
    if (threads == 0)
        threads = rf_cpu_count();
    if (threads > n)
        threads = n;
    if (pthread_mutex_init(&p.lock, NULL) != 0)
        return RF_ERR_NOMEM;
    if (threads <= 1) { /* no pool: the caller runs every task */
        Worker self = {&p, 0};
        work(&self);
        pthread_mutex_destroy(&p.lock);
        return p.failed ? RF_ERR_IO : RF_OK;
    }
    Worker *workers = malloc(sizeof *workers * (size_t)threads);
    pthread_t *ids = malloc(sizeof *ids * (size_t)threads);
    RfStatus st = RF_OK;
    int started = 0;
    if (!workers || !ids) {
        st = RF_ERR_NOMEM;
    } else {
        /* thread 0 is the caller itself; the others are started */
        for (int t = 0; t < threads; t++) {
            workers[t].pool = &p;
            workers[t].thread = t;
        }
        for (int t = 1; t < threads; t++, started++)
            if (pthread_create(&ids[t], NULL, work, &workers[t]) != 0)
                break;
        work(&workers[0]);
        for (int t = 1; t <= started; t++)
            pthread_join(ids[t], NULL);
        if (p.failed)
            st = RF_ERR_IO;
    }
    pthread_mutex_destroy(&p.lock);
    free(workers);
    free(ids);
    return st;
}

typedef struct {
    int width, height, tile, tiles_x;
    RfTileFn fn;
    RfProgressFn progress;
    void *ctx;
} TileJob;

static void tile_progress(void *ctx, int done, int total)
{
    const TileJob *j = ctx;
    j->progress(j->ctx, done, total);
}

static int tile_task(void *ctx, int i, int thread)
{
    const TileJob *j = ctx;
    RfTile t;
    t.index = i;
    t.x0 = (i % j->tiles_x) * j->tile;
    t.y0 = (i / j->tiles_x) * j->tile;
    t.x1 = t.x0 + j->tile < j->width ? t.x0 + j->tile : j->width;
    t.y1 = t.y0 + j->tile < j->height ? t.y0 + j->tile : j->height;
    return j->fn(j->ctx, t, thread);
}

RfStatus rf_parallel_tiles(int width, int height, int tile_size, int threads, RfTileFn fn,
                           RfProgressFn progress, void *ctx)
{
    if (width <= 0 || height <= 0 || tile_size <= 0 || threads < 0)
        return RF_ERR_DOMAIN;
    TileJob j = {width, height, tile_size, (width + tile_size - 1) / tile_size, fn, progress, ctx};
    int total = j.tiles_x * ((height + tile_size - 1) / tile_size);
    return rf_parallel_for(total, threads, tile_task, progress ? tile_progress : NULL, &j);
}
