/* Beyond one machine (issue 14): what `refray render --crop/--tiles/--checkpoint/--resume` and
 * `refray merge` share. A render's EXR names what it was made from in its header:
 *   refray:version, refray:sceneHash (scene.h source_hash, 16 hex digits), refray:settings
 *   (everything else that decides the pixels), refray:crop ("x0,y0,x1,y1", the data window)
 * and its display window is the whole picture. Tiles merge only when the first three and the
 * display window agree. A checkpoint adds refray:partial (a sentence for people) and
 * refray:tilesDone (the render tiles done, as ranges "0-17,19,22-40"). */
#ifndef REFRAY_CLI_FARM_H
#define REFRAY_CLI_FARM_H

#include <stddef.h>

#include "refray/image.h"
#include "refray/parallel.h"

/* The attributes that must agree for tiles or a checkpoint to belong to one render. */
extern const char *const rf_farm_identity[3];

/* Tile k of n of a w x h image: a grid of r rows x c columns, c the largest divisor of n with
 * c <= sqrt(n) (4: 2 x 2, 16: 4 x 4, 6: 3 x 2, a prime p: p rows), row and column edges at
 * floor(i h / r), floor(j w / c): areas differ by under a row or column. 0 and a message when
 * n or k is out of range or the image has fewer rows or columns than the grid. */
int rf_farm_tile_rect(int n, int k, int w, int h, RfTile *out, char *err, size_t errsz);

/* The done flags of n tiles as ranges ("0-3,7"; "" for none), malloc'd; NULL when out of memory. */
char *rf_farm_ranges_format(const unsigned char *done, int n);
/* Parses ranges into done[0..n) (zeroed first); 0 for a malformed list or an index >= n. */
int rf_farm_ranges_parse(const char *s, unsigned char *done, int n);

/* An EXR's header value, or NULL (malloc'd). */
char *rf_farm_attr(const char *path, const char *name);

/* 1 when the EXR at path was made by the same render as the header values expect[] (of
 * rf_farm_identity, in order) with the display window w x h; else 0 and err names the first
 * attribute that differs, with both values. */
int rf_farm_same_render(const char *path, const char *const expect[3], int w, int h, char *err, size_t errsz);

#endif
