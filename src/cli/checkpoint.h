/* `refray render --checkpoint FILE` and `--resume FILE` (issue 14): the finished tiles of a long
 * render, written every few seconds to a partial EXR that is clearly marked as such (farm.h:
 * refray:partial, refray:tilesDone), never over the output; and the signals that stop a render
 * with its checkpoint written. */
#ifndef REFRAY_CLI_CHECKPOINT_H
#define REFRAY_CLI_CHECKPOINT_H

#include <stddef.h>

#include "refray/image.h"
#include "refray/parallel.h"

typedef struct RfCheckpoint RfCheckpoint;

/* A checkpoint of the w x h crop written to path at most every `every` seconds, as an EXR with
 * the windows of `windows` (RfExrOptions x0, y0, display size) and the header attrs (the
 * render's identity, farm.h) plus its own. hint: the command that resumes, for the header. */
RfCheckpoint *rf_checkpoint_new(const char *path, double every, int w, int h, RfExrOptions windows,
                                const RfImageAttr *attrs, int nattrs, const char *hint);
void rf_checkpoint_free(RfCheckpoint *c);

/* Loads a checkpoint of this render (the same identity, crop and windows; else 0 and err says
 * what differs): its done tiles become *skip (owned by c) and its pixels *pixels (owned by c),
 * and c starts from them. */
int rf_checkpoint_resume(RfCheckpoint *c, const char *path, const unsigned char **skip, const RfImage **pixels,
                         char *err, size_t errsz);

/* rf_render's tile_done (RfRenderOptions): copies the tile, writes the file when due. */
void rf_checkpoint_tile_done(void *ctx, const RfImage *img, RfTile tile);

/* Writes the file now (after an interruption); the tiles done and the total. */
int rf_checkpoint_write_now(RfCheckpoint *c, int *done, int *total, char *err, size_t errsz);
/* The first write error of a periodic write (or ""): the render goes on, the message is kept. */
const char *rf_checkpoint_error(const RfCheckpoint *c);

/* SIGINT and SIGTERM, while a watch runs, set *flag (read by rf_render through
 * RfRenderOptions.cancel) instead of ending the process: a thread waits for them (sigwait), so
 * no handler and no global state. Start before any other thread exists (they inherit the
 * blocked signals). rf_signal_watch_stop returns the signal caught, or 0; the signals stay
 * blocked until the command ends (it then finishes and exits by itself). */
typedef struct RfSignalWatch RfSignalWatch;
RfSignalWatch *rf_signal_watch_start(volatile int *flag);
int rf_signal_watch_stop(RfSignalWatch *w);

#endif
