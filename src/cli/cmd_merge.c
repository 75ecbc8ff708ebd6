/* `refray merge`: the tiles of one render (refray render --crop / --tiles, farm.h) into the whole
 * image. Every tile must come from the same render (version, scene hash, settings, image size)
 * and together they must cover the image exactly once; a foreign, overlapping or missing tile is
 * one message naming it. The output is written atomically, with the tiles' identity. */
#include "cli.h"
#include "args.h"
#include "exit_codes.h"
#include "farm.h"

#include <stdlib.h>
#include <string.h>

#include "refray/image.h"

enum { OPT_PNG = RF_OPT_ID, OPT_QUIET };

static const RfOpt merge_opts[] = {
    {"output", 'o', "FILE", "the whole image, bit for bit the pixels of the tiles: .exr (linear) or .png", NULL},
    {"png", OPT_PNG, "FILE.png", "a display PNG besides, as refray render writes it", NULL},
    {"quiet", OPT_QUIET, NULL, "no summary line", NULL},
    RF_OPT_TABLE_END,
};

static const RfOpt *const merge_tables[] = {merge_opts, rf_opts_png, NULL};

static const RfCommand merge_cmd = {
    "refray merge",
    "refray merge [options] TILE.exr... -o OUT.exr\n",
    "Puts the tiles of one render (refray render --crop, or --tiles N --tile K; any order)\n"
    "together. Every tile must come from the same render and together they must cover the\n"
    "image exactly once.\n",
    merge_tables,
    "exit: 0 ok, 4 a tile is missing, unreadable, foreign or overlapping, or the output cannot be\n"
    "written, 5 usage (README: Exit codes)\n",
};

typedef struct {
    const char *path;
    RfExrWindow data;
} Tile;

static int by_x0(const void *a, const void *b)
{
    const Tile *const *p = a, *const *q = b;
    return (*p)->data.x0 - (*q)->data.x0;
}

/* Row by row, the tiles that cross the row, left to right, must abut. 0 and a message naming
 * the first pixel that no tile or two tiles cover. */
static int check_cover(const Tile *t, int n, int w, int h, char *err, size_t errsz)
{
    const Tile **row = malloc(sizeof *row * (size_t)n);
    if (!row) {
        snprintf(err, errsz, "out of memory");
        return 0;
    }
    int ok = 1;
    for (int y = 0; y < h && ok; y++) {
        int m = 0;
        for (int i = 0; i < n; i++)
            if (t[i].data.y0 <= y && y < t[i].data.y1)
                row[m++] = &t[i];
        qsort(row, (size_t)m, sizeof *row, by_x0);
        int x = 0;
        for (int i = 0; i < m && ok; i++) {
            if (row[i]->data.x0 > x) {
                snprintf(err, errsz, "no tile covers pixels (%d..%d, %d): a tile is missing", x, row[i]->data.x0 - 1, y);
                ok = 0;
            } else if (row[i]->data.x0 < x) {
                snprintf(err, errsz, "%s and %s both cover pixel (%d, %d): tiles overlap", row[i - 1]->path, row[i]->path,
                         row[i]->data.x0, y);
                ok = 0;
            }
            x = row[i]->data.x1;
        }
        if (ok && x < w) {
            snprintf(err, errsz, "no tile covers pixels (%d..%d, %d): a tile is missing", x, w - 1, y);
            ok = 0;
        }
    }
    free(row);
    return ok;
}

int rf_cmd_merge(int argc, char **argv)
{
    const char *out = NULL, *png = NULL;
    RfPngOptions popt = {RF_PNG_GAMMA, 2.2, 8, NULL};
    int quiet = 0, n = 0, key;
    RfOptParser p;
    rf_opt_init(&p, &merge_cmd, argc, argv);
    while ((key = rf_opt_next(&p)) != RF_OPT_DONE) {
        if (key == RF_OPT_EXIT)
            return p.exit_code;
        if (key == 'o')
            out = p.value;
        else if (key == OPT_PNG)
            png = p.value;
        else if (key == OPT_QUIET)
            quiet = 1;
        else if (rf_arg_shared(key, p.value, NULL, &popt) < 0)
            return rf_opt_bad_value(&p);
    }
    char **paths;
    n = rf_opt_operands(&p, &paths);
    if (n <= 0)
        return rf_opt_usage_error(&merge_cmd, "missing the tiles");
    if (!out)
        return rf_opt_usage_error(&merge_cmd, "missing the output: -o OUT.exr");
    if (!rf_arg_image_format("refray merge", "-o", out, RF_IMAGE_EXR | RF_IMAGE_PNG) ||
        (png && !rf_arg_image_format("refray merge", "--png", png, RF_IMAGE_PNG)))
        return RF_EXIT_USAGE;
    char err[1024];
    const char *outs[2] = {out, png};
    int bad = rf_arg_outputs_check("refray merge", outs, 2, (const char *const *)paths, n);
    if (bad)
        return bad;
    Tile *tiles = calloc((size_t)n, sizeof *tiles);
    char *expect[3] = {NULL, NULL, NULL};
    RfImage full = {0, 0, 0, NULL};
    int rc = RF_EXIT_FILE, w = 0, h = 0; /* a tile missing, unreadable or foreign, or a failed write */
    if (!tiles) {
        rc = RF_EXIT_FAIL;
        goto done;
    }
    for (int i = 0; i < n; i++) { /* headers first: nothing is decoded before the set is known good */
        RfExrWindow disp;
        tiles[i].path = paths[i];
        for (int j = 0; j < i; j++)
            if (rf_output_same(paths[i], paths[j])) {
                fprintf(stderr, "refray merge: %s is given twice\n", paths[i]);
                rc = RF_EXIT_USAGE;
                goto done;
            }
        if (rf_exr_read_windows(paths[i], &tiles[i].data, &disp, err, sizeof err) != RF_OK) {
            fprintf(stderr, "refray merge: %s\n", err);
            goto done;
        }
        char *partial = rf_farm_attr(paths[i], "refray:partial");
        if (partial) {
            fprintf(stderr, "refray merge: %s is a checkpoint of an unfinished render (refray:partial), not a tile\n",
                    paths[i]);
            free(partial);
            goto done;
        }
        if (i == 0) {
            w = disp.x1, h = disp.y1;
            for (int k = 0; k < 3; k++)
                if (!(expect[k] = rf_farm_attr(paths[0], rf_farm_identity[k]))) {
                    fprintf(stderr, "refray merge: %s: no %s in its header: not a tile of refray render\n", paths[0],
                            rf_farm_identity[k]);
                    goto done;
                }
        }
        if (disp.x0 != 0 || disp.y0 != 0 || tiles[i].data.x0 < 0 || tiles[i].data.y0 < 0 ||
            tiles[i].data.x1 > disp.x1 || tiles[i].data.y1 > disp.y1) {
            fprintf(stderr, "refray merge: %s: its pixels (%d,%d,%d,%d) are not inside its image (%d,%d,%d,%d)\n",
                    paths[i], tiles[i].data.x0, tiles[i].data.y0, tiles[i].data.x1, tiles[i].data.y1, disp.x0, disp.y0,
                    disp.x1, disp.y1);
            goto done;
        }
        if (i > 0 && !rf_farm_same_render(paths[i], (const char *const *)expect, w, h, err, sizeof err)) {
            fprintf(stderr, "refray merge: %s (the first tile, %s, sets the render)\n", err, paths[0]);
            goto done;
        }
    }
    if (!check_cover(tiles, n, w, h, err, sizeof err)) {
        fprintf(stderr, "refray merge: %s\n", err);
        goto done;
    }
    if (rf_image_alloc(&full, w, h, 3) != RF_OK) {
        fprintf(stderr, "refray merge: %dx%d: out of memory\n", w, h);
        rc = RF_EXIT_FAIL;
        goto done;
    }
    for (int i = 0; i < n; i++) {
        RfImage t;
        if (rf_exr_read(paths[i], &t, err, sizeof err) != RF_OK) {
            fprintf(stderr, "refray merge: %s\n", err);
            goto done;
        }
        if (t.channels != 3) {
            fprintf(stderr, "refray merge: %s has %d channels, a tile of refray render 3 (R, G, B)\n", paths[i],
                    t.channels);
            rf_image_free(&t);
            goto done;
        }
        for (int y = 0; y < t.height; y++)
            memcpy(full.data + ((size_t)(tiles[i].data.y0 + y) * (size_t)w + (size_t)tiles[i].data.x0) * 3,
                   t.data + (size_t)y * (size_t)t.width * 3, sizeof(float) * 3 * (size_t)t.width);
        rf_image_free(&t);
    }
    {
        char crop[64], count[32];
        snprintf(crop, sizeof crop, "0,0,%d,%d", w, h);
        snprintf(count, sizeof count, "%d", n);
        RfImageAttr attrs[5] = {{rf_farm_identity[0], expect[0]}, {rf_farm_identity[1], expect[1]},
                                {rf_farm_identity[2], expect[2]}, {"refray:crop", crop}, {"refray:mergedTiles", count}};
        RfWriteBatch *batch = rf_write_batch_new();
        RfExrOptions eopt = {RF_EXR_ZIP, 0, batch, 0, 0, 0, 0};
        popt.batch = batch;
        if (!batch) {
            fprintf(stderr, "refray merge: out of memory\n");
            goto done;
        }
        if (rf_arg_write_image(out, &full, attrs, 5, eopt, popt, err, sizeof err) != RF_OK ||
            (png && rf_png_write(png, &full, popt, err, sizeof err) != RF_OK)) {
            fprintf(stderr, "refray merge: %s; nothing written\n", err);
            rf_write_batch_abort(batch);
            goto done;
        }
        if (rf_write_batch_commit(batch, err, sizeof err) != RF_OK) {
            fprintf(stderr, "refray merge: %s\n", err);
            goto done;
        }
    }
    if (!quiet)
        fprintf(stderr, "refray merge: %d tiles -> %s (%dx%d)\n", n, out, w, h);
    rc = 0;
done:
    for (int k = 0; k < 3; k++)
        free(expect[k]);
    rf_image_free(&full);
    free(tiles);
    return rc;
}
