/* refray fuzzing: tiny seed images for the exr and png targets.
 *   mkseeds EXR_DIR PNG_DIR
 * EXR: refray's writer with every compression (ZIP, NONE, PIZ), FLOAT and HALF, Y/RGB/RGBA,
 * sizes that fill one and several scanline blocks, plus NaN/Inf values and header attributes.
 * PNG: refray's writer (8/16 bits, grey/RGB/RGBA, each encoding) and libpng directly for what
 * refray never writes: palette (with tRNS), grey+alpha, 1/2/4-bit grey, Adam7 interlacing. */
#include <math.h>
#include <png.h>
#include <stdio.h>
#include <stdlib.h>

#include "refray/image.h"

static void fill(RfImage *img, int seed)
{
    size_t n = (size_t)img->width * (size_t)img->height * (size_t)img->channels;
    for (size_t i = 0; i < n; i++)
        img->data[i] = (float)((i * 37u + (unsigned)seed * 11u) % 101u) / 50.0f;
    if (seed == 3 && n > 4) {
        img->data[1] = NAN;
        img->data[2] = INFINITY;
        img->data[3] = -1.0f;
    }
}

/* A PNG straight through libpng: colour type, bit depth, interlacing; palette with tRNS. */
static int raw_png(const char *path, int w, int h, int color, int depth, int interlace)
{
    FILE *f = fopen(path, "wb");
    if (!f)
        return 1;
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, NULL, NULL, NULL);
    png_infop info = png ? png_create_info_struct(png) : NULL;
    int channels = color == PNG_COLOR_TYPE_GRAY_ALPHA ? 2 : color == PNG_COLOR_TYPE_RGB ? 3
                   : color == PNG_COLOR_TYPE_RGBA ? 4 : 1;
    size_t rowbytes = ((size_t)w * (size_t)channels * (size_t)depth + 7) / 8;
    unsigned char *row = malloc(rowbytes);
    if (!png || !info || !row || setjmp(png_jmpbuf(png))) {
        png_destroy_write_struct(&png, &info);
        free(row);
        fclose(f);
        return 1;
    }
    png_init_io(png, f);
    png_set_IHDR(png, info, (png_uint_32)w, (png_uint_32)h, depth, color,
                 interlace ? PNG_INTERLACE_ADAM7 : PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT,
                 PNG_FILTER_TYPE_DEFAULT);
    if (color == PNG_COLOR_TYPE_PALETTE) {
        png_color pal[4] = {{0, 0, 0}, {255, 0, 0}, {0, 255, 0}, {40, 80, 255}};
        png_byte trns[2] = {0, 128};
        png_set_PLTE(png, info, pal, 4);
        png_set_tRNS(png, info, trns, 2, NULL);
    }
    if (color == PNG_COLOR_TYPE_GRAY)
        png_set_gAMA(png, info, 1.0 / 2.2);
    png_write_info(png, info);
    int passes = interlace ? png_set_interlace_handling(png) : 1;
    for (int p = 0; p < passes; p++)
        for (int y = 0; y < h; y++) {
            for (size_t i = 0; i < rowbytes; i++)
                row[i] = (unsigned char)(color == PNG_COLOR_TYPE_PALETTE && depth == 8 ? (i + (size_t)y) % 4
                                                                                       : i * 29u + (size_t)y * 7u);
            png_write_row(png, row);
        }
    png_write_end(png, NULL);
    png_destroy_write_struct(&png, &info);
    free(row);
    return fclose(f) != 0;
}

int main(int argc, char **argv)
{
    char path[4096], err[512];
    int bad = 0;
    if (argc != 3) {
        fprintf(stderr, "usage: mkseeds EXR_DIR PNG_DIR\n");
        return 2;
    }
    static const int sizes[][2] = {{1, 1}, {3, 2}, {5, 17}, {2, 40}};
    static const int chans[] = {1, 3, 4};
    static const char *const comp_name[] = {"zip", "none", "piz"};
    RfImageAttr attrs[] = {{"refray:version", "fuzz"}, {"refray:note", "seed"}};
    int k = 0;
    for (int c = 0; c < 3; c++)
        for (int comp = 0; comp < 3; comp++)
            for (int half = 0; half < 2; half++) {
                const int *sz = sizes[(c + comp + half) % 4];
                RfImage img = {0, 0, 0, NULL};
                if (rf_image_alloc(&img, sz[0], sz[1], chans[c]))
                    return 1;
                fill(&img, k % 4);
                RfExrOptions o = {(RfExrCompression)comp, half, NULL, 0, 0, 0, 0};
                snprintf(path, sizeof path, "%s/seed_%s_%s_c%d_%dx%d.exr", argv[1], comp_name[comp],
                         half ? "half" : "float", chans[c], sz[0], sz[1]);
                if (rf_exr_write_opts(path, &img, attrs, k % 3, o, err, sizeof err)) {
                    fprintf(stderr, "%s\n", err);
                    bad = 1;
                }
                rf_image_free(&img);
                k++;
            }
    static const char *const enc_name[] = {"asis", "gamma", "srgb"};
    k = 0;
    for (int c = 0; c < 3; c++)
        for (int enc = 0; enc < 3; enc++)
            for (int bits = 8; bits <= 16; bits += 8) {
                const int *sz = sizes[(c + enc + bits / 8) % 4];
                RfImage img = {0, 0, 0, NULL};
                if (rf_image_alloc(&img, sz[0], sz[1], chans[c]))
                    return 1;
                fill(&img, k % 4);
                RfPngOptions o = {(RfPngEncoding)enc, 2.2, bits, NULL};
                snprintf(path, sizeof path, "%s/seed_%s_%d_c%d_%dx%d.png", argv[2], enc_name[enc], bits,
                         chans[c], sz[0], sz[1]);
                if (rf_png_write(path, &img, o, err, sizeof err)) {
                    fprintf(stderr, "%s\n", err);
                    bad = 1;
                }
                rf_image_free(&img);
                k++;
            }
    static const struct { int color, depth, interlace; const char *name; } raw[] = {
        {PNG_COLOR_TYPE_PALETTE, 8, 0, "palette8"},  {PNG_COLOR_TYPE_PALETTE, 2, 1, "palette2_adam7"},
        {PNG_COLOR_TYPE_GRAY_ALPHA, 8, 0, "greyalpha8"}, {PNG_COLOR_TYPE_GRAY_ALPHA, 16, 1, "greyalpha16_adam7"},
        {PNG_COLOR_TYPE_GRAY, 1, 0, "grey1"},        {PNG_COLOR_TYPE_GRAY, 2, 0, "grey2"},
        {PNG_COLOR_TYPE_GRAY, 4, 1, "grey4_adam7"},  {PNG_COLOR_TYPE_RGB, 8, 1, "rgb8_adam7"},
        {PNG_COLOR_TYPE_RGBA, 16, 0, "rgba16"},
    };
    for (size_t i = 0; i < sizeof raw / sizeof raw[0]; i++) {
        snprintf(path, sizeof path, "%s/seed_raw_%s.png", argv[2], raw[i].name);
        if (raw_png(path, 5 + (int)i, 3 + (int)i % 4, raw[i].color, raw[i].depth, raw[i].interlace)) {
            fprintf(stderr, "mkseeds: cannot write %s\n", path);
            bad = 1;
        }
    }
    return bad;
}
