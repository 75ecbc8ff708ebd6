/* Grading a class (issue 16): the image formats students write (read through netpbm, stb_image
 * and libtiff, values checked exactly), corrupt files of each format, the heat map scaled to the
 * thresholds, the edge-tolerant mode, the transfer-function and shift hints, and `refray grade`
 * on a generated class of 200 submissions whose every verdict is known (the class generator is
 * make_class below; RF_GRADE_CLASS_KEEP=DIR keeps the class and its report in DIR). */
#define _XOPEN_SOURCE 700
#include "rf_test.h"

#include <stdlib.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include <ppm.h>
#include <stb_image_write.h>
#include <tiffio.h>
#include <zlib.h>

#include "refray/diff.h"
#include "refray/grade.h"
#include "refray/image.h"
#include "refray/transfer.h"

/* ---- writers of the test images, through the same libraries ---- */

static int write_ppm(const char *path, const unsigned char *rgb, int w, int h, int plain)
{
    FILE *f = fopen(path, "wb");
    if (!f)
        return 0;
    pixel *row = ppm_allocrow((unsigned)w);
    ppm_writeppminit(f, w, h, 255, plain);
    for (int y = 0; y < h; y++) {
        for (int x = 0; x < w; x++) {
            const unsigned char *p = rgb + 3 * ((size_t)y * w + x);
            PPM_ASSIGN(row[x], p[0], p[1], p[2]);
        }
        ppm_writeppmrow(f, row, w, 255, plain);
    }
    ppm_freerow(row);
    return fclose(f) == 0;
}

/* 8-bit (codes), 16-bit (codes16) or 32-bit float (floats) RGB TIFF, one of the three given. */
static int write_tiff(const char *path, int w, int h, const unsigned char *codes, const unsigned short *codes16,
                      const float *floats)
{
    TIFF *t = TIFFOpen(path, "w");
    if (!t)
        return 0;
    int bits = codes ? 8 : codes16 ? 16 : 32;
    TIFFSetField(t, TIFFTAG_IMAGEWIDTH, (uint32_t)w);
    TIFFSetField(t, TIFFTAG_IMAGELENGTH, (uint32_t)h);
    TIFFSetField(t, TIFFTAG_SAMPLESPERPIXEL, 3);
    TIFFSetField(t, TIFFTAG_BITSPERSAMPLE, bits);
    TIFFSetField(t, TIFFTAG_SAMPLEFORMAT, floats ? SAMPLEFORMAT_IEEEFP : SAMPLEFORMAT_UINT);
    TIFFSetField(t, TIFFTAG_PHOTOMETRIC, PHOTOMETRIC_RGB);
    TIFFSetField(t, TIFFTAG_PLANARCONFIG, PLANARCONFIG_CONTIG);
    TIFFSetField(t, TIFFTAG_ROWSPERSTRIP, 16);
    TIFFSetField(t, TIFFTAG_COMPRESSION, COMPRESSION_ADOBE_DEFLATE);
    int ok = 1;
    for (int y = 0; y < h && ok; y++) {
        size_t at = 3 * (size_t)y * w;
        void *row = codes ? (void *)(codes + at) : codes16 ? (void *)(codes16 + at) : (void *)(floats + at);
        ok = TIFFWriteScanline(t, row, (uint32_t)y, 0) >= 0;
    }
    TIFFClose(t);
    return ok;
}

static int write_png8(const char *path, const unsigned char *rgb, int w, int h)
{
    RfImage img;
    char err[256];
    if (rf_image_alloc(&img, w, h, 3) != RF_OK)
        return 0;
    for (size_t i = 0; i < (size_t)w * h * 3; i++)
        img.data[i] = rgb[i] / 255.0f;
    RfPngOptions p = {RF_PNG_AS_IS, 1.0, 8, NULL};
    int ok = rf_png_write(path, &img, p, err, sizeof err) == RF_OK;
    rf_image_free(&img);
    return ok;
}

/* ---- reading every format: the values as written ---- */

static const unsigned char codes[6][3] = {{0, 0, 0}, {255, 255, 255}, {200, 100, 50}, {1, 128, 254},
                                          {17, 34, 51}, {99, 0, 180}};

static void check_codes(const char *path, int lossy, const char *format)
{
    char err[512];
    RfImage img;
    RfImageSource src;
    RfPngOptions as_is = {RF_PNG_AS_IS, 1.0, 8, NULL}, gamma = {RF_PNG_GAMMA, 2.2, 8, NULL};
    if (rf_image_read_source(path, as_is, &img, &src, err, sizeof err) != RF_OK) {
        rf_test_fail(__FILE__, __LINE__, "%s: %s", path, err);
        return;
    }
    RF_CHECK_STR(rf_image_file_name(src.format), format);
    RF_CHECK_EQ_INT(src.encoded, 1);
    RF_CHECK_EQ_INT(img.width, 3);
    RF_CHECK_EQ_INT(img.height, 2);
    RF_CHECK_EQ_INT(img.channels, 3);
    for (int i = 0; i < 6 && img.data; i++)
        for (int c = 0; c < 3; c++)
            if (lossy) /* JPEG at quality 100: within two codes */
                RF_CHECK_NEAR(img.data[3 * i + c], codes[i][c] / 255.0, 0, 2.0 / 255.0);
            else
                RF_CHECK(img.data[3 * i + c] == (float)(codes[i][c] / 255.0));
    rf_image_free(&img);
    /* the same codes through the PNG curve: (code / 255)^2.2 */
    RF_CHECK_EQ_INT(rf_image_read(path, gamma, &img, err, sizeof err), RF_OK);
    if (img.data && !lossy)
        RF_CHECK(img.data[3 * 2 + 0] == (float)rf_gamma_decode(200 / 255.0, 2.2));
    rf_image_free(&img);
}

static void t_grade_formats_read(void)
{
    char dir[] = "/tmp/refray-grade-fmt-XXXXXX", path[256];
    if (!mkdtemp(dir)) {
        rf_test_fail(__FILE__, __LINE__, "mkdtemp");
        return;
    }
    unsigned char rgb[18];
    memcpy(rgb, codes, sizeof rgb);
    struct {
        const char *name, *format;
        int lossy;
    } files[] = {{"a.ppm", "PNM", 0}, {"plain.ppm", "PNM", 0}, {"a.png", "PNG", 0}, {"a.bmp", "BMP", 0},
                 {"a.tga", "TGA", 0}, {"a.tif", "TIFF", 0}, {"a.jpg", "JPEG", 1}};
    for (size_t k = 0; k < sizeof files / sizeof files[0]; k++) {
        snprintf(path, sizeof path, "%s/%s", dir, files[k].name);
        int ok = k == 0   ? write_ppm(path, rgb, 3, 2, 0)
                 : k == 1 ? write_ppm(path, rgb, 3, 2, 1)
                 : k == 2 ? write_png8(path, rgb, 3, 2)
                 : k == 3 ? stbi_write_bmp(path, 3, 2, 3, rgb)
                 : k == 4 ? stbi_write_tga(path, 3, 2, 3, rgb)
                 : k == 5 ? write_tiff(path, 3, 2, rgb, NULL, NULL)
                          : stbi_write_jpg(path, 3, 2, 3, rgb, 100);
        RF_CHECK(ok);
        check_codes(path, files[k].lossy, files[k].format);
    }
    /* 16-bit TIFF: code / 65535; float TIFF and HDR: linear, as stored (HDR values that RGBE
     * holds exactly: a shared power of two with 8-bit mantissas) */
    unsigned short c16[18];
    float lin[18];
    for (int i = 0; i < 18; i++)
        c16[i] = (unsigned short)(rgb[i] * 257 + (i == 5 ? 1 : 0)), lin[i] = (float)(rgb[i] / 256.0);
    snprintf(path, sizeof path, "%s/a16.tif", dir);
    RF_CHECK(write_tiff(path, 3, 2, NULL, c16, NULL));
    char err[512];
    RfImage img;
    RfImageSource src;
    RfPngOptions as_is = {RF_PNG_AS_IS, 1.0, 8, NULL};
    RF_CHECK_EQ_INT(rf_image_read_source(path, as_is, &img, &src, err, sizeof err), RF_OK);
    for (int i = 0; i < 18 && img.data; i++)
        RF_CHECK(img.data[i] == (float)(c16[i] / 65535.0));
    rf_image_free(&img);
    const char *linear[2] = {"f.tif", "a.hdr"};
    for (int k = 0; k < 2; k++) {
        snprintf(path, sizeof path, "%s/%s", dir, linear[k]);
        RF_CHECK(k == 0 ? write_tiff(path, 3, 2, NULL, NULL, lin) : stbi_write_hdr(path, 3, 2, 3, lin));
        RF_CHECK_EQ_INT(rf_image_read_source(path, as_is, &img, &src, err, sizeof err), RF_OK);
        RF_CHECK_EQ_INT(src.encoded, 0);
        RF_CHECK_STR(rf_image_file_name(src.format), k == 0 ? "TIFF" : "HDR");
        /* RGBE shares the exponent of the pixel's largest channel: exact for channels that are
         * multiples of that power of two's 1/256 (here all but the darkest ones of a pixel) */
        for (int i = 0; i < 18 && img.data; i++)
            if (k == 0 || i / 3 != 4)
                RF_CHECK(img.data[i] == lin[i] || (k == 1 && lin[i] < 0.5f * lin[i - i % 3]));
        rf_image_free(&img);
    }
    /* `refray diff` takes them too (it gave exit 4 for a .ppm before) */
    char cmd[1024];
    int code;
    snprintf(cmd, sizeof cmd, "%s diff %s/a.ppm %s/plain.ppm --kv", rf_test_bin(), dir, dir);
    const char *out = rf_test_run(cmd, &code);
    RF_CHECK_EQ_INT(code, 0);
    RF_CHECK_NEAR(rf_test_diff_kv(out, "max_abs"), 0.0, 0, 0);
    snprintf(cmd, sizeof cmd, "rm -rf %s", dir);
    RF_CHECK(system(cmd) == 0);
}

/* One corrupt (truncated or garbage) file per format: a clear error naming the file, exit 4. */
static void t_grade_formats_corrupt(void)
{
    const char *files[] = {"corrupt/truncated.ppm", "corrupt/garbage_plain.ppm", "corrupt/truncated.jpg",
                           "corrupt/truncated.tif", "corrupt/truncated.bmp", "corrupt/truncated.hdr",
                           "corrupt/truncated.png", "corrupt/truncated.exr", "corrupt/garbage.tga", "corrupt/zero_count.hdr"};
    for (size_t k = 0; k < sizeof files / sizeof files[0]; k++) {
        char path[512], err[512], cmd[1200];
        RfImage img;
        int code;
        snprintf(path, sizeof path, "%s", rf_test_data(files[k]));
        RfPngOptions g = {RF_PNG_GAMMA, 2.2, 8, NULL};
        RfStatus st = rf_image_read(path, g, &img, err, sizeof err);
        RF_CHECK(st == RF_ERR_PARSE);
        RF_CHECK(img.data == NULL);
        if (!strstr(err, path))
            rf_test_fail(__FILE__, __LINE__, "%s: the message does not name the file: %s", files[k], err);
        snprintf(cmd, sizeof cmd, "%s diff %s %s 2>&1", rf_test_bin(), path, path);
        const char *out = rf_test_run(cmd, &code);
        if (code != 4 || !strstr(out, files[k]))
            rf_test_fail(__FILE__, __LINE__, "%s: exit %d: %s", files[k], code, out);
        rf_test_checks++;
    }
}

/* A header that claims far more pixels than its file can hold is refused before anything is
 * allocated for it, with the claim in the message (fuzzing found a 58-byte BMP that asked for
 * 2.4 GB): a BMP, a raw PPM, a PNG and a JPEG whose headers say 16000 x 16000 (256 M pixels, under
 * refray's limit of 2^28), each a few hundred bytes. */
static void t_grade_formats_claims(void)
{
    char dir[] = "/tmp/refray-claims-XXXXXX", path[600], err[512];
    unsigned char rgb[3 * 8 * 8] = {0};
    if (!mkdtemp(dir)) {
        rf_test_fail(__FILE__, __LINE__, "mkdtemp");
        return;
    }
    for (int k = 0; k < 4; k++) {
        static const char *const names[] = {"big.bmp", "big.ppm", "big.png", "big.jpg"};
        snprintf(path, sizeof path, "%s/%s", dir, names[k]);
        if (k == 1) {
            FILE *f = fopen(path, "wb");
            RF_CHECK(f != NULL);
            if (!f)
                continue;
            fprintf(f, "P6\n16000 16000\n255\n");
            fwrite(rgb, 1, sizeof rgb, f);
            fclose(f);
        } else {
            /* an 8 x 8 image, then its size fields patched: BMP's at bytes 18 and 22 (32-bit
             * little-endian), PNG's at 16 and 20 (big-endian, with the IHDR's CRC made anew),
             * JPEG's in the SOF0 segment */
            RfImage small;
            RF_CHECK(rf_image_alloc(&small, 8, 8, 3) == RF_OK);
            RfPngOptions po = {RF_PNG_SRGB, 2.2, 8, NULL};
            int ok = k == 0 ? stbi_write_bmp(path, 8, 8, 3, rgb)
                     : k == 3 ? stbi_write_jpg(path, 8, 8, 3, rgb, 90)
                              : rf_png_write(path, &small, po, err, sizeof err) == RF_OK;
            rf_image_free(&small);
            RF_CHECK(ok);
            FILE *f = fopen(path, "r+b");
            unsigned char b[4096];
            size_t n = f ? fread(b, 1, sizeof b, f) : 0;
            RF_CHECK(n > 40);
            if (!f || n <= 40)
                continue;
            if (k == 0) {
                for (int i = 0; i < 4; i++)
                    b[18 + i] = (unsigned char)(16000 >> (8 * i)), b[22 + i] = (unsigned char)(16000 >> (8 * i));
            } else if (k == 2) {
                b[16] = b[20] = 0, b[17] = b[21] = 0, b[18] = b[22] = 16000 >> 8, b[19] = b[23] = 16000 & 255;
                uint32_t crc = (uint32_t)crc32(0, b + 12, 17); /* the IHDR's type and data */
                for (int i = 0; i < 4; i++)
                    b[29 + i] = (unsigned char)(crc >> (24 - 8 * i));
            } else {
                for (size_t i = 2; i + 8 < n; i++)
                    if (b[i] == 0xff && b[i + 1] == 0xc0) { /* SOF0: length, precision, height, width */
                        b[i + 5] = b[i + 7] = 16000 >> 8, b[i + 6] = b[i + 8] = 16000 & 255;
                        break;
                    }
            }
            rewind(f);
            fwrite(b, 1, n, f);
            fclose(f);
        }
        RfImage img;
        RfPngOptions g = {RF_PNG_GAMMA, 2.2, 8, NULL};
        RfStatus st = rf_image_read(path, g, &img, err, sizeof err);
        if (st != RF_ERR_PARSE || img.data || !strstr(err, "claims 16000 x 16000 pixels, far more than its"))
            rf_test_fail(__FILE__, __LINE__, "%s: status %d: %s", names[k], (int)st, err);
        rf_test_checks++;
        remove(path);
    }
    rmdir(dir);
}

/* ---- the heat map, the edge-tolerant mode and the hints, on a small synthetic scene ---- */

/* A linear test picture: a bright disc on a gradient, with a dark band (edges everywhere). */
static void scene(RfImage *img, int w, int h)
{
    rf_image_alloc(img, w, h, 3);
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            float *p = img->data + 3 * ((size_t)y * w + x);
            double d = hypot(x - 0.4 * w, y - 0.5 * h), g = 0.05 + 0.6 * x / w;
            p[0] = (float)(d < 0.25 * h ? 0.9 : g);
            p[1] = (float)(d < 0.25 * h ? 0.3 : 0.5 * g);
            p[2] = (float)(y > 0.7 * h && y < 0.8 * h ? 0.01 : 0.2 + 0.3 * y / h);
        }
}

/* The display values as 8-bit codes of the linear picture with a curve, then back to [0, 1]. */
static void quantised(const RfImage *lin, RfPngEncoding e, RfImage *out)
{
    rf_image_alloc(out, lin->width, lin->height, 3);
    for (size_t i = 0; i < (size_t)lin->width * lin->height * 3; i++) {
        double v = e == RF_PNG_GAMMA ? rf_gamma_encode(lin->data[i], 2.2)
                   : e == RF_PNG_SRGB ? rf_srgb_encode(lin->data[i])
                                      : lin->data[i];
        out->data[i] = (float)(rf_quantize(v, 8) / 255.0);
    }
}

static long count_colour(const RfImage *m, int rows, float r, float g, float b)
{
    long n = 0;
    for (size_t i = 0; i < (size_t)m->width * rows; i++)
        n += fabsf(m->data[3 * i] - r) < 0.02f && fabsf(m->data[3 * i + 1] - g) < 0.02f &&
             fabsf(m->data[3 * i + 2] - b) < 0.02f;
    return n;
}

static void t_grade_heatmap_scaled(void)
{
    RfImage lin, ref, sub, map;
    RfPngOptions enc = {RF_PNG_GAMMA, 2.2, 8, NULL};
    RfDiffOptions o = rf_diff_options_default();
    o.warn = 0.5 / 255 + 1e-6, o.fail_mean = 1.0 / 255;
    scene(&lin, 64, 48);
    RF_CHECK_EQ_INT(rf_grade_display(&lin, 0, enc, &ref), RF_OK);
    quantised(&lin, RF_PNG_GAMMA, &sub);
    /* a correctly rounded PNG: no yellow, no red, and the legend band below (64 x 6 = 384 wide) */
    RF_CHECK_EQ_INT(rf_diff_heatmap(&sub, &ref, NULL, &o, &map), RF_OK);
    RF_CHECK_EQ_INT(map.width, 384);
    RF_CHECK_EQ_INT(map.height, 48 * 6 + 44);
    long hot = 0;
    for (size_t i = 0; i < (size_t)map.width * 48 * 6; i++)
        hot += map.data[3 * i] > 0.5f; /* yellow and red both have a bright red channel */
    RF_CHECK_EQ_INT(hot, 0);
    rf_image_free(&map);
    /* one wrong pixel: red, and ringed in cyan */
    sub.data[3 * (10 * 64 + 20)] = 1.0f - sub.data[3 * (10 * 64 + 20)];
    RF_CHECK_EQ_INT(rf_diff_heatmap(&sub, &ref, NULL, &o, &map), RF_OK);
    float red[3];
    rf_diff_heat_colour(fabs(sub.data[3 * (10 * 64 + 20)] - ref.data[3 * (10 * 64 + 20)]), &o, red);
    RF_CHECK(red[0] > 0.5f && red[1] == 0.0f);
    RF_CHECK_EQ_INT(count_colour(&map, map.height - 44, red[0], red[1], red[2]), 36); /* its 6 x 6 block */
    RF_CHECK(count_colour(&map, map.height - 44, 0.0f, 1.0f, 1.0f) > 50);             /* the ring */
    rf_image_free(&map);
    rf_diff_heatmap_done();
    rf_image_free(&lin), rf_image_free(&ref), rf_image_free(&sub);
}

static void t_grade_edge_tolerant_and_hints(void)
{
    RfImage lin, ref, sub, shifted;
    RfPngOptions enc = {RF_PNG_GAMMA, 2.2, 8, NULL};
    RfDiffOptions o = rf_diff_options_default();
    RfGrade g;
    o.warn = 0.5 / 255 + 1e-6, o.fail_mean = 1.0 / 255;
    scene(&lin, 64, 48);
    rf_grade_display(&lin, 0, enc, &ref);
    /* right: pass, score 100 */
    quantised(&lin, RF_PNG_GAMMA, &sub);
    RF_CHECK_EQ_INT(rf_grade_image(&lin, &ref, 1, &sub, enc, &o, &g), RF_OK);
    RF_CHECK_EQ_INT(g.verdict, RF_GRADE_PASS);
    RF_CHECK_NEAR(g.score, 100.0, 0, 0);
    RF_CHECK_STR(g.reason, "");
    /* shifted one pixel right: fails, the reason says so; edge-tolerant it passes */
    rf_image_alloc(&shifted, 64, 48, 3);
    for (int y = 0; y < 48; y++)
        for (int x = 0; x < 64; x++)
            memcpy(shifted.data + 3 * (y * 64 + x), sub.data + 3 * (y * 64 + (x > 0 ? x - 1 : 0)), 3 * sizeof(float));
    RF_CHECK_EQ_INT(rf_grade_image(&lin, &ref, 1, &shifted, enc, &o, &g), RF_OK);
    RF_CHECK_EQ_INT(g.verdict, RF_GRADE_FAIL);
    RF_CHECK(strstr(g.reason, "the whole image is shifted by 1 pixel right; moved back it would pass") != NULL);
    RF_CHECK_EQ_INT(g.shift_x, 1);
    RF_CHECK_EQ_INT(g.shift_y, 0);
    RF_CHECK(g.score < 80.0 && g.score > 0.0);
    RF_CHECK_NEAR(g.score, 80.0 * (1.0 - (double)g.diff.all.above_fail / g.diff.all.pixels), 1e-12, 0);
    o.edge_tolerant = 1;
    RF_CHECK_EQ_INT(rf_grade_image(&lin, &ref, 1, &shifted, enc, &o, &g), RF_OK);
    RF_CHECK_EQ_INT(g.verdict, RF_GRADE_PASS);
    o.edge_tolerant = 0;
    /* linear values written as codes, and sRGB instead of gamma 2.2: named */
    rf_image_free(&sub);
    quantised(&lin, RF_PNG_AS_IS, &sub);
    RF_CHECK_EQ_INT(rf_grade_image(&lin, &ref, 1, &sub, enc, &o, &g), RF_OK);
    RF_CHECK_EQ_INT(g.verdict, RF_GRADE_FAIL);
    RF_CHECK(strstr(g.reason, "looks like linear values written without gamma 2.2 encoding; with gamma 2.2 it would "
                              "pass") != NULL);
    rf_image_free(&sub);
    quantised(&lin, RF_PNG_SRGB, &sub);
    RF_CHECK_EQ_INT(rf_grade_image(&lin, &ref, 1, &sub, enc, &o, &g), RF_OK);
    RF_CHECK_EQ_INT(g.verdict, RF_GRADE_FAIL);
    RF_CHECK(strstr(g.reason, "looks like sRGB encoding instead of gamma 2.2; with gamma 2.2 it would pass") != NULL);
    /* the reason names the criterion, by how much and where */
    char want[160];
    snprintf(want, sizeof want, "%.3g %% of pixels above fail 0.00392 (allowed 0.1 %%), worst %.3g at (%d, %d)",
             rf_diff_percent(g.diff.all.above_fail, &g.diff.all), g.diff.all.max_abs, g.diff.all.max_x,
             g.diff.all.max_y);
    RF_CHECK(strncmp(g.reason, want, strlen(want)) == 0);
    /* a wrong size */
    RfImage small;
    rf_image_alloc(&small, 32, 24, 3);
    RF_CHECK_EQ_INT(rf_grade_image(&lin, &ref, 1, &small, enc, &o, &g), RF_OK);
    RF_CHECK_EQ_INT(g.verdict, RF_GRADE_SIZE);
    RF_CHECK_STR(g.reason, "32 x 24, the reference is 64 x 48");
    RF_CHECK_NEAR(g.score, 0.0, 0, 0);
    rf_image_free(&small), rf_image_free(&shifted), rf_image_free(&sub), rf_image_free(&ref), rf_image_free(&lin);
}

/* `refray diff --edge-tolerant` and the heat map through the command */
/* A scratch folder with ref.exr, the test picture (w x h), and q its gamma-2.2 8-bit codes. */
static int scratch(char *dir, int w, int h, RfImage *lin, RfImage *q)
{
    char path[512], err[256];
    if (!mkdtemp(dir))
        return 0;
    scene(lin, w, h);
    quantised(lin, RF_PNG_GAMMA, q);
    snprintf(path, sizeof path, "%s/ref.exr", dir);
    RF_CHECK_EQ_INT(rf_exr_write(path, lin, NULL, 0, err, sizeof err), RF_OK);
    return 1;
}

static void t_grade_diff_edge_tolerant_cli(void)
{
    char dir[] = "/tmp/refray-grade-et-XXXXXX", cmd[2048], err[256];
    RfImage lin, q;
    if (!scratch(dir, 64, 48, &lin, &q))
        return;
    unsigned char rgb[64 * 48 * 3];
    for (int y = 0; y < 48; y++) /* shifted one pixel down */
        for (int x = 0; x < 64; x++)
            for (int c = 0; c < 3; c++)
                rgb[3 * (y * 64 + x) + c] = (unsigned char)lrintf(255.0f * q.data[3 * ((y > 0 ? y - 1 : 0) * 64 + x) + c]);
    snprintf(cmd, sizeof cmd, "%s/sub.ppm", dir);
    RF_CHECK(write_ppm(cmd, rgb, 64, 48, 0));
    int code;
    snprintf(cmd, sizeof cmd, "%s diff %s/sub.ppm %s/ref.exr --heatmap %s/heat.png >/dev/null 2>&1", rf_test_bin(), dir,
             dir, dir);
    rf_test_run(cmd, &code);
    RF_CHECK_EQ_INT(code, 2);
    snprintf(cmd, sizeof cmd, "%s diff %s/sub.ppm %s/ref.exr --edge-tolerant --kv 2>&1", rf_test_bin(), dir, dir);
    const char *out = rf_test_run(cmd, &code);
    RF_CHECK_EQ_INT(code, 0);
    RF_CHECK(strstr(out, "verdict=PASS") != NULL);
    snprintf(cmd, sizeof cmd, "%s/heat.png", dir);
    RfImage heat;
    RfPngOptions as_is = {RF_PNG_AS_IS, 1.0, 8, NULL};
    RF_CHECK_EQ_INT(rf_image_read(cmd, as_is, &heat, err, sizeof err), RF_OK);
    RF_CHECK_EQ_INT(heat.width, 384);
    rf_image_free(&heat), rf_image_free(&lin), rf_image_free(&q);
    snprintf(cmd, sizeof cmd, "rm -rf %s", dir);
    RF_CHECK(system(cmd) == 0);
}

/* ---- the class: 200 submissions with known verdicts ---- */

enum { KINDS = 5, FORMATS = 8, CLASS = 200 };
static const char *const kind_names[KINDS] = {"right", "gamma", "pixel", "shift", "noisy"};
static const char *const format_ext[FORMATS] = {"p3.ppm", "p6.ppm", "png", "jpg", "tif", "bmp", "hdr", "t16.tif"};

/* The verdict grade must give, and a word its reason must hold ("" when none). JPEG at quality 95
 * does not pass the default thresholds (its errors reach tens of codes at edges: lossy), so every
 * JPEG fails at them; its gamma and shift mistakes are still named. HDR keeps 8 mantissa bits for
 * a pixel's largest channel, so the dim channels of bright pixels are off by more than a code once
 * gamma-encoded; HDR fails too. */
static void truth(int kind, int format, int variant, const char **verdict, const char **word)
{
    int lossy = format == 3 || format == 6;
    static const char *const words[KINDS] = {"", "", "hardfail", "shifted", ""};
    *verdict = kind == 0 ? (lossy ? "fail" : "pass") : kind == 4 ? (lossy ? "fail" : "warn") : "fail";
    *word = words[kind];
    if (kind == 1) /* JPEG's own errors hide the small step from sRGB to gamma 2.2 */
        *word = format == 6 ? "written to a linear file" : variant % 2 == 0 ? "linear values written without gamma 2.2"
              : format == 3 ? "" : "sRGB encoding instead of gamma 2.2";
    if (kind == 2 && format == 3) /* JPEG spreads the pixel over its block: below --hardfail 0.25 */
        *word = "";
}

/* Writes submission i (kind i % 5, format i / 5 % 8) from the reference's display codes. */
static int make_submission(const char *path, int i, const RfImage *lin, const unsigned char *right)
{
    int w = lin->width, h = lin->height, kind = i % KINDS, format = i / KINDS % FORMATS, variant = i / (KINDS * FORMATS);
    size_t n = (size_t)w * h * 3;
    unsigned char *c = malloc(n);
    float *f = malloc(n * sizeof *f);
    unsigned short *c16 = malloc(n * sizeof *c16);
    RfTestRng rng = {(unsigned long long)i * 7919u + 1u};
    for (size_t k = 0; k < n; k++) {
        double v = lin->data[k / 3 * (size_t)lin->channels + k % 3];
        if (kind == 1) /* linear values written as they are, or the sRGB curve instead of gamma 2.2; in
                          the HDR file gamma-encoded values, where linear ones belong */
            v = format == 6 ? rf_gamma_encode(v, 2.2) : variant % 2 == 0 ? v : rf_srgb_encode(v);
        else
            v = rf_gamma_encode(v, 2.2);
        if (kind == 4) /* noisy but acceptable: up to 0.45 of a code before rounding */
            v += rf_test_uniform(&rng, -0.45, 0.45) / 255.0;
        c[k] = (unsigned char)rf_quantize(v, 8);
        c16[k] = (unsigned short)(c[k] * 257);
        f[k] = (float)(kind == 1 ? v : lin->data[k / 3 * (size_t)lin->channels + k % 3]);
    }
    if (kind == 3) { /* the whole image moved by one pixel: right, left, down, up, diagonal */
        static const int sh[5][2] = {{1, 0}, {-1, 0}, {0, 1}, {0, -1}, {1, 1}};
        int dx = sh[variant][0], dy = sh[variant][1];
        for (int y = 0; y < h; y++)
            for (int x = 0; x < w; x++) {
                int sx = x - dx < 0 ? 0 : x - dx >= w ? w - 1 : x - dx, sy = y - dy < 0 ? 0 : y - dy >= h ? h - 1 : y - dy;
                for (int k = 0; k < 3; k++) {
                    size_t to = 3 * ((size_t)y * w + x) + k, from = 3 * ((size_t)sy * w + sx) + k;
                    c[to] = right[from];
                    c16[to] = (unsigned short)(right[from] * 257);
                    f[to] = lin->data[((size_t)sy * w + sx) * lin->channels + k];
                }
            }
    }
    if (kind == 2) { /* one pixel very wrong: each channel to the far end (dark to 255, bright to 0) */
        size_t at = 3 * ((size_t)(10 + 11 * variant) * w + (size_t)(13 + 15 * variant));
        for (int k = 0; k < 3; k++) {
            c[at + k] = c[at + k] > 127 ? 0 : 255;
            c16[at + k] = (unsigned short)(c[at + k] * 257);
            f[at + k] = f[at + k] > 0.5f ? 0.0f : 1.0f;
        }
    }
    int ok;
    switch (format) {
    case 0: ok = write_ppm(path, c, w, h, 1); break;
    case 1: ok = write_ppm(path, c, w, h, 0); break;
    case 2: ok = write_png8(path, c, w, h); break;
    case 3: ok = stbi_write_jpg(path, w, h, 3, c, 95); break;
    case 4: ok = write_tiff(path, w, h, c, NULL, NULL); break;
    case 5: ok = stbi_write_bmp(path, w, h, 3, c); break;
    case 6: ok = stbi_write_hdr(path, w, h, 3, f); break;
    default: ok = write_tiff(path, w, h, NULL, c16, NULL); break;
    }
    free(c), free(f), free(c16);
    return ok;
}

/* The class folder: ref.exr (refray render scenes/whitted.rf at 96 x 72), the 200 submissions
 * named like "s007-pixel.png", class.csv (student,file) and truth.csv (student,verdict,word). */
static int make_class(const char *dir, RfImage *lin)
{
    char path[1024], err[512];
    int code;
    snprintf(path, sizeof path, "%s render scenes/whitted.rf --width 96 --height 72 -o %s/ref.exr --quiet 2>&1",
             rf_test_bin(), dir);
    rf_test_run(path, &code);
    snprintf(path, sizeof path, "%s/ref.exr", dir);
    if (code != 0 || rf_exr_read(path, lin, err, sizeof err) != RF_OK) {
        rf_test_fail(__FILE__, __LINE__, "the reference: exit %d, %s", code, err);
        return 0;
    }
    size_t n = (size_t)lin->width * lin->height * 3;
    unsigned char *right = malloc(n);
    for (size_t k = 0; k < n; k++)
        right[k] = (unsigned char)rf_quantize(rf_gamma_encode(lin->data[k / 3 * (size_t)lin->channels + k % 3], 2.2), 8);
    snprintf(path, sizeof path, "%s/class.csv", dir);
    FILE *csv = fopen(path, "w");
    snprintf(path, sizeof path, "%s/truth.csv", dir);
    FILE *tr = fopen(path, "w");
    int ok = csv && tr;
    if (ok)
        fprintf(csv, "student,file\n"), fprintf(tr, "student,verdict,word\n");
    for (int i = 0; i < CLASS && ok; i++) {
        const char *verdict, *word;
        int kind = i % KINDS, format = i / KINDS % FORMATS;
        snprintf(path, sizeof path, "%s/s%03d-%s.%s", dir, i, kind_names[kind], format_ext[format]);
        ok = make_submission(path, i, lin, right);
        truth(kind, format, i / (KINDS * FORMATS), &verdict, &word);
        fprintf(csv, "student%03d,s%03d-%s.%s\n", i, i, kind_names[kind], format_ext[format]);
        fprintf(tr, "student%03d,%s,%s\n", i, verdict, word);
    }
    if (csv)
        fclose(csv);
    if (tr)
        fclose(tr);
    free(right);
    return ok;
}

static int exists(const char *dir, const char *name)
{
    char path[1024];
    struct stat sb;
    snprintf(path, sizeof path, "%s/%s", dir, name);
    return stat(path, &sb) == 0 && S_ISREG(sb.st_mode);
}

/* Every src="..." and href="..." of a page names a file that exists. */
static int links_resolve(const char *dir, const char *page)
{
    char path[1024];
    snprintf(path, sizeof path, "%s/%s", dir, page);
    FILE *f = fopen(path, "r");
    if (!f)
        return 0;
    static char text[1 << 20];
    size_t n = fread(text, 1, sizeof text - 1, f);
    fclose(f);
    text[n] = 0;
    int ok = 1;
    for (const char *p = text; ok && (p = strpbrk(p, "sh")) != NULL; p++) {
        const char *q = strncmp(p, "src=\"", 5) == 0 ? p + 5 : strncmp(p, "href=\"", 6) == 0 ? p + 6 : NULL;
        if (!q)
            continue;
        char name[512];
        size_t k = strcspn(q, "\"");
        snprintf(name, sizeof name, "%.*s", (int)k, q);
        ok = exists(dir, name);
        if (!ok)
            rf_test_fail(__FILE__, __LINE__, "%s: %s does not exist", page, name);
    }
    /* the views of the A/B flip, named in the script */
    for (const char *p = text; ok && (p = strstr(p, "'img/")) != NULL; p++) {
        char name[512];
        size_t k = strcspn(p + 1, "'");
        snprintf(name, sizeof name, "%.*s", (int)k, p + 1);
        ok = exists(dir, name);
        if (!ok)
            rf_test_fail(__FILE__, __LINE__, "%s: %s does not exist", page, name);
    }
    return ok;
}

/* One CSV field (quoted fields have no inner quotes here) into out; the rest of the line. */
static const char *field(const char *s, char *out, size_t n)
{
    size_t k = 0;
    if (*s == '"') {
        s++;
        while (*s && !(*s == '"' && s[1] != '"')) {
            if (*s == '"')
                s++;
            if (k + 1 < n)
                out[k++] = *s;
            s++;
        }
        if (*s == '"')
            s++;
    } else {
        while (*s && *s != ',' && *s != '\n')
            if (k + 1 < n)
                out[k++] = *s++;
            else
                s++;
    }
    out[k] = 0;
    return *s == ',' ? s + 1 : s;
}

static void t_grade_class_of_200(void)
{
    const char *keep = getenv("RF_GRADE_CLASS_KEEP");
    char tmp[] = "/tmp/refray-grade-class-XXXXXX", dir[512], cmd[2048];
    if (keep) {
        snprintf(dir, sizeof dir, "%s", keep);
        mkdir(dir, 0755);
    } else {
        if (!mkdtemp(tmp))
            return;
        snprintf(dir, sizeof dir, "%s", tmp);
    }
    RfImage lin;
    char report[600];
    snprintf(report, sizeof report, "%s/report", dir);
    if (!make_class(dir, &lin))
        return;
    rf_image_free(&lin);
    struct timespec t0, t1;
    struct rusage u0, u1;
    int code;
    getrusage(RUSAGE_CHILDREN, &u0);
    clock_gettime(CLOCK_MONOTONIC, &t0);
    snprintf(cmd, sizeof cmd, "%s grade %s/ref.exr %s/class.csv --hardfail 0.25 --out %s/report --quiet 2>&1",
             rf_test_bin(), dir, dir, dir);
    const char *out = rf_test_run(cmd, &code);
    clock_gettime(CLOCK_MONOTONIC, &t1);
    getrusage(RUSAGE_CHILDREN, &u1);
    double secs = (double)(t1.tv_sec - t0.tv_sec) + 1e-9 * (double)(t1.tv_nsec - t0.tv_nsec);
    double cpu = (double)(u1.ru_utime.tv_sec - u0.ru_utime.tv_sec + u1.ru_stime.tv_sec - u0.ru_stime.tv_sec) +
                 1e-6 * (double)(u1.ru_utime.tv_usec - u0.ru_utime.tv_usec + u1.ru_stime.tv_usec - u0.ru_stime.tv_usec);
    printf("    refray grade: 200 submissions in %.2f s (%.2f s of CPU)\n", secs, cpu);
    RF_CHECK_EQ_INT(code, 2); /* some failed */
    RF_CHECK(strstr(out, "200 submissions:") != NULL);
    /* every row against the truth */
    char path[1024], line[2048], tline[512];
    snprintf(path, sizeof path, "%s/report/grades.csv", dir);
    FILE *g = fopen(path, "r");
    snprintf(path, sizeof path, "%s/truth.csv", dir);
    FILE *t = fopen(path, "r");
    int rows = 0, wrong = 0;
    if (g && t && fgets(line, sizeof line, g) && fgets(tline, sizeof tline, t)) {
        RF_CHECK(strncmp(line, "student,file,format,verdict,score,reason,", 41) == 0);
        while (fgets(line, sizeof line, g) && fgets(tline, sizeof tline, t)) {
            char student[64], file[256], format[16], verdict[16], score[16], reason[700], page[128], tmp2[64];
            char tstudent[64], tverdict[16], tword[64];
            const char *p = field(line, student, sizeof student);
            p = field(p, file, sizeof file);
            p = field(p, format, sizeof format);
            p = field(p, verdict, sizeof verdict);
            p = field(p, score, sizeof score);
            p = field(p, reason, sizeof reason);
            for (int k = 0; k < 8; k++)
                p = field(p, tmp2, sizeof tmp2);
            field(p, page, sizeof page);
            const char *q = field(tline, tstudent, sizeof tstudent);
            q = field(q, tverdict, sizeof tverdict);
            field(q, tword, sizeof tword);
            rows++;
            int ok = strcmp(student, tstudent) == 0 && strcmp(verdict, tverdict) == 0 &&
                     (tword[0] == 0 || strstr(reason, tword) != NULL) && exists(report, "img/reference.png");
            double sc = atof(score);
            ok = ok && (strcmp(verdict, "pass") == 0 ? sc == 100.0 : strcmp(verdict, "warn") == 0 ? sc == 90.0
                                                                                                  : sc < 80.0 + 1e-9);
            ok = ok && links_resolve(report, page);
            if (!ok && wrong++ < 10)
                rf_test_fail(__FILE__, __LINE__, "%s (%s): %s, score %s, '%s'; expected %s with '%s'", student, file,
                             verdict, score, reason, tverdict, tword);
        }
    }
    if (g)
        fclose(g);
    if (t)
        fclose(t);
    RF_CHECK_EQ_INT(rows, CLASS);
    RF_CHECK_EQ_INT(wrong, 0);
    RF_CHECK(links_resolve(report, "index.html"));
    RF_CHECK(exists(report, "grades.json"));
    /* the CPU time, not the wall time: a loaded machine must not fail the test */
    if (cpu > 15.0)
        rf_test_fail(__FILE__, __LINE__, "grading took %.1f s of CPU (more than 15)", cpu);
    if (!keep) {
        snprintf(cmd, sizeof cmd, "rm -rf %s", dir);
        RF_CHECK(system(cmd) == 0);
    }
}

/* One unreadable submission does not stop the others; the usage and file errors. */
static void t_grade_cli_errors(void)
{
    char dir[] = "/tmp/refray-grade-cli-XXXXXX", cmd[2048], err[256];
    RfImage lin, q;
    if (!scratch(dir, 40, 30, &lin, &q))
        return;
    snprintf(cmd, sizeof cmd, "%s/good.png", dir);
    RfPngOptions as_is = {RF_PNG_AS_IS, 1.0, 8, NULL};
    RF_CHECK_EQ_INT(rf_png_write(cmd, &q, as_is, err, sizeof err), RF_OK);
    int code;
    snprintf(cmd, sizeof cmd, "%s grade %s/ref.exr %s/good.png %s %s/missing.png --out=%s/r 2>&1", rf_test_bin(), dir,
             dir, rf_test_data("corrupt/truncated.jpg"), dir, dir);
    const char *out = rf_test_run(cmd, &code);
    RF_CHECK_EQ_INT(code, 4); /* unreadable ones, none failed */
    RF_CHECK(strstr(out, "good                 pass       100.0") != NULL);
    RF_CHECK(strstr(out, "truncated            unreadable   0.0") != NULL);
    RF_CHECK(strstr(out, "missing.png: cannot open") != NULL);
    RF_CHECK(strstr(out, "3 submissions: 1 pass, 0 warn, 0 fail, 2 unreadable, 0 wrong size") != NULL);
    snprintf(cmd, sizeof cmd, "%s grade %s/ref.exr %s/good.png --out %s/r2 >/dev/null 2>&1", rf_test_bin(), dir, dir, dir);
    rf_test_run(cmd, &code);
    RF_CHECK_EQ_INT(code, 0);
    /* a folder: every image in it, by name (other files skipped); one of the wrong size */
    RfImage small;
    snprintf(cmd, sizeof cmd, "mkdir %s/class && cp %s/good.png %s/class/a.png && echo x > %s/class/notes.txt", dir, dir,
             dir, dir);
    RF_CHECK(system(cmd) == 0);
    snprintf(cmd, sizeof cmd, "%s/class/b.png", dir);
    RF_CHECK_EQ_INT(rf_image_alloc(&small, 20, 15, 3), RF_OK);
    RF_CHECK_EQ_INT(rf_png_write(cmd, &small, as_is, err, sizeof err), RF_OK);
    rf_image_free(&small);
    snprintf(cmd, sizeof cmd, "%s grade %s/ref.exr %s/class --out %s/r4 2>&1", rf_test_bin(), dir, dir, dir);
    out = rf_test_run(cmd, &code);
    RF_CHECK_EQ_INT(code, 3);
    RF_CHECK(strstr(out, "a                    pass       100.0") != NULL);
    RF_CHECK(strstr(out, "b                    wrong size   0.0  20 x 15, the reference is 40 x 30") != NULL);
    RF_CHECK(strstr(out, "2 submissions: 1 pass, 0 warn, 0 fail, 0 unreadable, 1 wrong size") != NULL);
    struct {
        const char *args;
        int code;
    } bad[] = {{"%s/missing.exr %s/good.png", 4}, {"%s/ref.exr", 5}, {"%s/ref.exr %s/good.png --fial 1", 5},
               {"%s/ref.exr %s/good.png --fail x", 5}, {"%s/ref.exr %s/nothing.csv", 4}};
    for (size_t k = 0; k < sizeof bad / sizeof bad[0]; k++) {
        char args[1024];
        snprintf(args, sizeof args, bad[k].args, dir, dir);
        snprintf(cmd, sizeof cmd, "%s grade %s --out %s/r3 2>&1", rf_test_bin(), args, dir);
        out = rf_test_run(cmd, &code);
        if (code != bad[k].code || !strstr(out, "refray grade"))
            rf_test_fail(__FILE__, __LINE__, "grade %s: exit %d, expected %d: %s", args, code, bad[k].code, out);
        rf_test_checks++;
    }
    rf_image_free(&lin), rf_image_free(&q);
    snprintf(cmd, sizeof cmd, "rm -rf %s", dir);
    RF_CHECK(system(cmd) == 0);
}

const RfTest rf_tests_grade[] = {
    {"grade_formats_read", t_grade_formats_read},
    {"grade_formats_corrupt", t_grade_formats_corrupt},
    {"grade_formats_claims", t_grade_formats_claims},
    {"grade_heatmap_scaled", t_grade_heatmap_scaled},
    {"grade_edge_tolerant_and_hints", t_grade_edge_tolerant_and_hints},
    {"grade_diff_edge_tolerant_cli", t_grade_diff_edge_tolerant_cli},
    {"grade_class_of_200", t_grade_class_of_200},
    {"grade_cli_errors", t_grade_cli_errors},
    RF_TEST_END,
};
