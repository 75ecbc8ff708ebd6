/* refray: work over image tiles on a pool of threads. Tiles are handed out in a fixed order
 * through one counter (a mutex taken once per tile, never per pixel); each tile writes only its
 * own pixels, so results do not depend on the thread count or on which thread renders a tile. */
#ifndef REFRAY_PARALLEL_H
#define REFRAY_PARALLEL_H

#include "refray/status.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct {
    int x0, y0, x1, y1; /* pixels [x0, x1) x [y0, y1) */
    int index;          /* tile number in row-major tile order */
} RfTile;

/* One task of rf_parallel_for; returns 0 to go on, non-zero to stop every thread (an error). */
typedef int (*RfTaskFn)(void *ctx, int index, int thread);
/* Renders one tile; returns 0 to go on, non-zero to stop every thread (an error). */
typedef int (*RfTileFn)(void *ctx, RfTile tile, int thread);
/* Called after each finished tile with (done, total) from one thread at a time (may be NULL). */
typedef void (*RfProgressFn)(void *ctx, int done, int total);

/* The number of online processors (at least 1). */
int rf_cpu_count(void);

/* Runs fn(ctx, i, thread) for every i in [0, n) on up to `threads` threads (0: every core;
 * thread 0 is the caller). Tasks are handed out in increasing order through one counter (a
 * mutex taken once per task), so tasks should be coarse. progress (may be NULL) is called after
 * each finished task with (done, n), one thread at a time. Returns RF_OK, RF_ERR_DOMAIN for
 * n < 0 or threads < 0, RF_ERR_NOMEM, or RF_ERR_IO when a task failed. */
RfStatus rf_parallel_for(int n, int threads, RfTaskFn fn, RfProgressFn progress, void *ctx);

/* Runs fn over every tile of a width x height image, tile_size square, on threads threads
 * (0: rf_cpu_count()). Returns RF_OK, RF_ERR_DOMAIN for bad sizes, or RF_ERR_NOMEM / the
 * first failing tile's code mapped to RF_ERR_IO when a thread cannot be started or a tile
 * fails. */
RfStatus rf_parallel_tiles(int width, int height, int tile_size, int threads, RfTileFn fn,
                           RfProgressFn progress, void *ctx);

#ifdef __cplusplus
}
#endif

#endif
