/* Image I/O: EXR and PNG round trips, attributes, decode curves, and every error path
 * (missing, truncated and corrupt files, bad folders, absurd sizes). Files live in a mkdtemp
 * folder per test; each test checks that the folder holds exactly the files it expects, so a
 * stray temporary file from a failed write is caught, then removes it. */
#include <dirent.h>
#include <float.h>
#include <limits.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

/* As in src/io/exr.c: via <OpenEXR/...> the headers count as system headers (C11 unions). */
#include <OpenEXR/openexr.h>

#include "refray/image.h"
#include "rf_test.h"

/* ---- helpers ---- */

typedef struct {
    char dir[64];
    char path[512];
} TmpDir;

static int tmp_open(TmpDir *t)
{
    strcpy(t->dir, "/tmp/refray-io-XXXXXX");
    return mkdtemp(t->dir) != NULL;
}

/* t->path = dir/name (one buffer per TmpDir: copy it when two paths are needed at once). */
static const char *tmp_path(TmpDir *t, const char *name)
{
    snprintf(t->path, sizeof t->path, "%s/%s", t->dir, name);
    return t->path;
}

static int tmp_count(const TmpDir *t)
{
    int n = 0;
    struct dirent *e;
    DIR *d = opendir(t->dir);
    if (!d)
        return -1;
    while ((e = readdir(d)) != NULL)
        if (strcmp(e->d_name, ".") != 0 && strcmp(e->d_name, "..") != 0)
            n++;
    closedir(d);
    return n;
}

/* Removes the folder and its files (and sub-folders one level down). */
static void tmp_close(TmpDir *t)
{
    struct dirent *e;
    DIR *d = opendir(t->dir);
    char p[512];
    if (d) {
        while ((e = readdir(d)) != NULL) {
            if (strcmp(e->d_name, ".") == 0 || strcmp(e->d_name, "..") == 0)
                continue;
            snprintf(p, sizeof p, "%s/%s", t->dir, e->d_name);
            if (unlink(p) != 0)
                rmdir(p);
        }
        closedir(d);
    }
    RF_CHECK(rmdir(t->dir) == 0);
}

static int write_bytes(const char *path, const void *data, size_t n)
{
    FILE *f = fopen(path, "wb");
    int ok;
    if (!f)
        return 0;
    ok = fwrite(data, 1, n, f) == n;
    return fclose(f) == 0 && ok;
}

/* The whole file (malloc'd), or NULL. */
static unsigned char *read_bytes(const char *path, size_t *n)
{
    FILE *f = fopen(path, "rb");
    unsigned char *buf = NULL;
    long len;
    if (!f)
        return NULL;
    if (fseek(f, 0, SEEK_END) == 0 && (len = ftell(f)) >= 0 && fseek(f, 0, SEEK_SET) == 0) {
        buf = malloc((size_t)len + 1);
        if (buf && fread(buf, 1, (size_t)len, f) != (size_t)len) {
            free(buf);
            buf = NULL;
        }
        *n = (size_t)len;
    }
    fclose(f);
    return buf;
}

static long file_size(const char *path)
{
    struct stat st;
    return stat(path, &st) == 0 ? (long)st.st_size : -1;
}

static int same_bits(float a, float b)
{
    return memcmp(&a, &b, sizeof a) == 0;
}

static int starts_with(const char *s, const char *prefix)
{
    return strncmp(s, prefix, strlen(prefix)) == 0;
}

static const RfPngOptions as_is8 = {RF_PNG_AS_IS, 0.0, 8, NULL};

/* Floats that stress an exact round trip: signed zeros, denormals, extremes, infinities, NaN. */
static float special_value(size_t i)
{
    const float v[] = {0.0f,     -0.0f,           1.0f,      -1.0f,    0.5f,       1.0f / 3.0f,
                       FLT_MIN,  FLT_MIN / 8.0f,  ldexpf(1.0f, -149),  FLT_MAX,    -FLT_MAX,
                       1e30f,    -1e-30f,         123456.789f,         -7.25e-20f, 0.18f,
                       INFINITY, -INFINITY,       NAN};
    return v[i % (sizeof v / sizeof v[0])];
}

/* ---- image allocation ---- */

static void test_image_alloc(void)
{
    RfImage img;
    size_t i;
    RF_CHECK_EQ_INT(rf_image_alloc(&img, 3, 2, 4), RF_OK);
    RF_CHECK(img.data != NULL && img.width == 3 && img.height == 2 && img.channels == 4);
    for (i = 0; img.data && i < 3 * 2 * 4; i++)
        RF_CHECK(img.data[i] == 0.0f);
    rf_image_free(&img);
    RF_CHECK(img.data == NULL);
    rf_image_free(&img); /* twice is harmless */
    rf_image_free(NULL);

    RF_CHECK_EQ_INT(rf_image_alloc(&img, 0, 5, 3), RF_ERR_DOMAIN);
    RF_CHECK(img.data == NULL);
    RF_CHECK_EQ_INT(rf_image_alloc(&img, 5, -1, 3), RF_ERR_DOMAIN);
    RF_CHECK_EQ_INT(rf_image_alloc(&img, 5, 5, 2), RF_ERR_DOMAIN);
    RF_CHECK_EQ_INT(rf_image_alloc(&img, 5, 5, 0), RF_ERR_DOMAIN);
    RF_CHECK_EQ_INT(rf_image_alloc(&img, INT_MAX, INT_MAX, 4), RF_ERR_DOMAIN);
    RF_CHECK_EQ_INT(rf_image_alloc(&img, 100000, 100000, 3), RF_ERR_DOMAIN);
    RF_CHECK(img.data == NULL);
    /* The limit itself is accepted in principle; one pixel more is not. */
    RF_CHECK_EQ_INT(rf_image_alloc(&img, 16385, 16384, 1), RF_ERR_DOMAIN);
}

static void test_write_bad_images(void)
{
    TmpDir t;
    RfImage img = {0, 0, 3, NULL};
    float px[12] = {0};
    RfPngOptions o = {RF_PNG_GAMMA, 2.2, 8, NULL};
    char err[512];
    if (!tmp_open(&t)) {
        RF_CHECK(0);
        return;
    }
    RF_CHECK_EQ_INT(rf_png_write(tmp_path(&t, "a.png"), &img, o, err, sizeof err), RF_ERR_DOMAIN);
    RF_CHECK_EQ_INT(rf_exr_write(tmp_path(&t, "a.exr"), &img, NULL, 0, err, sizeof err), RF_ERR_DOMAIN);
    img.width = 0;
    img.height = 2;
    img.data = px;
    RF_CHECK_EQ_INT(rf_png_write(tmp_path(&t, "a.png"), &img, o, err, sizeof err), RF_ERR_DOMAIN);
    RF_CHECK(strstr(err, "a.png: ") != NULL);
    img.width = 100000;
    img.height = 100000; /* absurd: refused before any pixel is touched */
    RF_CHECK_EQ_INT(rf_exr_write(tmp_path(&t, "a.exr"), &img, NULL, 0, err, sizeof err), RF_ERR_DOMAIN);
    RF_CHECK_EQ_INT(rf_png_write(tmp_path(&t, "a.png"), &img, o, err, sizeof err), RF_ERR_DOMAIN);
    img.width = 2;
    img.height = 2;
    img.channels = 2;
    RF_CHECK_EQ_INT(rf_exr_write(tmp_path(&t, "a.exr"), &img, NULL, 0, err, sizeof err), RF_ERR_DOMAIN);
    img.channels = 3;
    o.bits = 12;
    RF_CHECK_EQ_INT(rf_png_write(tmp_path(&t, "a.png"), &img, o, err, sizeof err), RF_ERR_DOMAIN);
    o.bits = 8;
    o.gamma = 0.0;
    RF_CHECK_EQ_INT(rf_png_write(tmp_path(&t, "a.png"), &img, o, err, sizeof err), RF_ERR_DOMAIN);
    o.gamma = NAN;
    RF_CHECK_EQ_INT(rf_png_write(tmp_path(&t, "a.png"), &img, o, err, sizeof err), RF_ERR_DOMAIN);
    RF_CHECK_EQ_INT(tmp_count(&t), 0);
    tmp_close(&t);
}

/* ---- EXR ---- */

/* Writes a w x h image of special values with the options, reads it back, compares bits. */
static void exr_roundtrip(TmpDir *t, int w, int h, int channels, RfExrOptions opt)
{
    RfImage img, back = {0, 0, 0, NULL};
    char err[512], path[512];
    size_t i, n = (size_t)w * (size_t)h * (size_t)channels;
    int same = 1;
    snprintf(path, sizeof path, "%s", tmp_path(t, "rt.exr"));
    RF_CHECK_EQ_INT(rf_image_alloc(&img, w, h, channels), RF_OK);
    if (!img.data)
        return;
    for (i = 0; i < n; i++)
        img.data[i] = special_value(i * 7 + 3);
    RF_CHECK_EQ_INT(rf_exr_write_opts(path, &img, NULL, 0, opt, err, sizeof err), RF_OK);
    RF_CHECK_EQ_INT(rf_image_read(path, as_is8, &back, err, sizeof err), RF_OK);
    RF_CHECK_EQ_INT(back.width, w);
    RF_CHECK_EQ_INT(back.height, h);
    RF_CHECK_EQ_INT(back.channels, channels);
    if (back.data && back.width == w && back.height == h && back.channels == channels)
        for (i = 0; i < n; i++)
            if (!same_bits(img.data[i], back.data[i])) {
                if (same)
                    rf_test_fail(__FILE__, __LINE__, "sample %zu: wrote %.9g, read %.9g (%dx%dx%d, comp %d)", i,
                                 img.data[i], back.data[i], w, h, channels, (int)opt.compression);
                same = 0;
            }
    RF_CHECK(same);
    rf_image_free(&img);
    rf_image_free(&back);
    RF_CHECK_EQ_INT(tmp_count(t), 1); /* only rt.exr: no temporary file left */
    unlink(path);
}

static void test_exr_roundtrip_exact(void)
{
    TmpDir t;
    RfExrOptions zip = {RF_EXR_ZIP, 0, NULL, 0, 0, 0, 0}, none = {RF_EXR_NONE, 0, NULL, 0, 0, 0, 0}, piz = {RF_EXR_PIZ, 0, NULL, 0, 0, 0, 0};
    int c;
    if (!tmp_open(&t)) {
        RF_CHECK(0);
        return;
    }
    for (c = 1; c <= 4; c++) {
        if (c == 2)
            continue;
        exr_roundtrip(&t, 7, 37, c, zip); /* 37 lines: two full 16-line ZIP chunks and a short one */
        exr_roundtrip(&t, 7, 5, c, none);
        exr_roundtrip(&t, 5, 33, c, piz);
    }
    exr_roundtrip(&t, 1, 1, 3, zip);
    exr_roundtrip(&t, 300, 2, 4, zip);
    tmp_close(&t);
}

static void test_exr_default_write(void)
{
    TmpDir t;
    RfImage img, back = {0, 0, 0, NULL};
    char err[512];
    const char *path;
    int i;
    if (!tmp_open(&t)) {
        RF_CHECK(0);
        return;
    }
    path = tmp_path(&t, "d.exr");
    RF_CHECK_EQ_INT(rf_image_alloc(&img, 4, 3, 3), RF_OK);
    if (!img.data)
        return;
    for (i = 0; i < 36; i++)
        img.data[i] = (float)i * 0.25f - 3.0f;
    RF_CHECK_EQ_INT(rf_exr_write(path, &img, NULL, 0, err, sizeof err), RF_OK);
    RF_CHECK_EQ_INT(rf_exr_read(path, &back, err, sizeof err), RF_OK);
    RF_CHECK(back.data && memcmp(back.data, img.data, 36 * sizeof(float)) == 0);
    /* The written file is readable by others: 0644, not mkstemp's 0600. */
    {
        struct stat st;
        RF_CHECK(stat(path, &st) == 0 && (st.st_mode & 0777) == 0644);
    }
    rf_image_free(&img);
    rf_image_free(&back);
    tmp_close(&t);
}

static void test_exr_half(void)
{
    TmpDir t;
    RfImage img, back = {0, 0, 0, NULL};
    RfExrOptions half = {RF_EXR_ZIP, 1, NULL, 0, 0, 0, 0};
    const float exact[] = {0.0f, 0.5f, 1.0f, -2.0f, 65504.0f, 0.25f, 1024.0f, -0.125f, 3.0f};
    char err[512];
    const char *path;
    int i;
    if (!tmp_open(&t)) {
        RF_CHECK(0);
        return;
    }
    path = tmp_path(&t, "h.exr");
    RF_CHECK_EQ_INT(rf_image_alloc(&img, 3, 3, 4), RF_OK);
    if (!img.data)
        return;
    for (i = 0; i < 9; i++) {
        img.data[i * 4 + 0] = exact[i];
        img.data[i * 4 + 1] = 0.1f * (float)(i + 1); /* not representable: rounded to 11 bits */
        img.data[i * 4 + 2] = -3.14159f * (float)i;
        img.data[i * 4 + 3] = 1.0f;
    }
    RF_CHECK_EQ_INT(rf_exr_write_opts(path, &img, NULL, 0, half, err, sizeof err), RF_OK);
    RF_CHECK_EQ_INT(rf_image_read(path, as_is8, &back, err, sizeof err), RF_OK);
    RF_CHECK_EQ_INT(back.channels, 4);
    if (back.data && back.channels == 4 && back.width == 3 && back.height == 3) {
        for (i = 0; i < 9; i++) {
            RF_CHECK(back.data[i * 4] == exact[i]);
            RF_CHECK_NEAR(back.data[i * 4 + 1], img.data[i * 4 + 1], 1.0 / 2048, 0.0);
            RF_CHECK_NEAR(back.data[i * 4 + 2], img.data[i * 4 + 2], 1.0 / 2048, 0.0);
            RF_CHECK(back.data[i * 4 + 3] == 1.0f);
        }
    }
    /* The stored type really is HALF: the file is smaller than the FLOAT one. */
    {
        long hs = file_size(path), fs;
        RfExrOptions full = {RF_EXR_ZIP, 0, NULL, 0, 0, 0, 0};
        RF_CHECK_EQ_INT(rf_exr_write_opts(path, &img, NULL, 0, full, err, sizeof err), RF_OK);
        fs = file_size(path);
        RF_CHECK(hs > 0 && fs > hs);
    }
    rf_image_free(&img);
    rf_image_free(&back);
    tmp_close(&t);
}

static void test_exr_attributes(void)
{
    TmpDir t;
    RfImage img;
    char err[512], path[512];
    char *v = NULL;
    const char *long_name = "refray.a.name.longer.than.thirty.one.chars";
    const RfImageAttr attrs[] = {
        {"refray.version", "0.2.0"},
        {"refray.settings", "spp=16\nmaxdepth=5\nscene=\"scenes/whitted.rf\""},
        {"refray.renderTime", "12.345 s"},
        {"refray.cflags", "-std=c99 -O2 -ffp-contract=off"},
        {"refray.cpu", "Intel(R) Xeon(R) CPU @ 2.20GHz"},
        {"empty", ""},
        {long_name, "long names work"},
    };
    if (!tmp_open(&t)) {
        RF_CHECK(0);
        return;
    }
    snprintf(path, sizeof path, "%s", tmp_path(&t, "a.exr"));
    RF_CHECK_EQ_INT(rf_image_alloc(&img, 2, 2, 3), RF_OK);
    if (!img.data)
        return;
    RF_CHECK_EQ_INT(rf_exr_write(path, &img, attrs, (int)(sizeof attrs / sizeof attrs[0]), err, sizeof err), RF_OK);
    {
        size_t i;
        for (i = 0; i < sizeof attrs / sizeof attrs[0]; i++) {
            RF_CHECK_EQ_INT(rf_exr_read_attr(path, attrs[i].name, &v, err, sizeof err), RF_OK);
            RF_CHECK(v && strcmp(v, attrs[i].value) == 0);
            free(v);
            v = NULL;
        }
    }
    RF_CHECK_EQ_INT(rf_exr_read_attr(path, "refray.missing", &v, err, sizeof err), RF_ERR_DOMAIN);
    RF_CHECK(v == NULL);
    RF_CHECK(starts_with(err, path) && strstr(err, "refray.missing") != NULL);
    /* A required attribute of another type is not a string. */
    RF_CHECK_EQ_INT(rf_exr_read_attr(path, "dataWindow", &v, err, sizeof err), RF_ERR_DOMAIN);
    RF_CHECK(v == NULL);

    /* A name that clashes with EXR's own attribute fails after the temporary file was created:
     * no stray file, and the good file written above is untouched. */
    {
        const RfImageAttr bad[] = {{"compression", "none"}};
        size_t n0 = 0, n1 = 0;
        unsigned char *before = read_bytes(path, &n0), *after;
        img.data[0] = 42.0f;
        RF_CHECK(rf_exr_write(path, &img, bad, 1, err, sizeof err) != RF_OK);
        RF_CHECK(starts_with(err, path));
        after = read_bytes(path, &n1);
        RF_CHECK(before && after && n0 == n1 && memcmp(before, after, n0) == 0);
        free(before);
        free(after);
        RF_CHECK_EQ_INT(tmp_count(&t), 1);
    }
    {
        const RfImageAttr noname[] = {{"", "x"}};
        RF_CHECK_EQ_INT(rf_exr_write(path, &img, noname, 1, err, sizeof err), RF_ERR_DOMAIN);
        RF_CHECK_EQ_INT(rf_exr_write(path, &img, NULL, 2, err, sizeof err), RF_ERR_DOMAIN);
    }
    rf_image_free(&img);
    tmp_close(&t);
}

/* A few deterministic "random" bytes. */
static void garbage(unsigned char *buf, size_t n, unsigned seed)
{
    size_t i;
    for (i = 0; i < n; i++) {
        seed = seed * 1103515245u + 12345u;
        buf[i] = (unsigned char)(seed >> 16);
    }
}

static void quiet_exr(exr_const_context_t ctxt, exr_result_t code, const char *msg)
{
    (void)ctxt;
    (void)code;
    (void)msg;
}

/* A tiled 8x8 one-channel HALF EXR made with OpenEXRCore directly (one uncompressed tile of zeros). */
static int write_tiled_exr(const char *path)
{
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    exr_context_t ctx = NULL;
    unsigned char tile[8 * 8 * 2] = {0};
    int part = 0;
    exr_result_t rv;
    init.error_handler_fn = quiet_exr;
    rv = exr_start_write(&ctx, path, EXR_WRITE_FILE_DIRECTLY, &init);
    if (rv == EXR_ERR_SUCCESS)
        rv = exr_add_part(ctx, NULL, EXR_STORAGE_TILED, &part);
    if (rv == EXR_ERR_SUCCESS)
        rv = exr_initialize_required_attr_simple(ctx, part, 8, 8, EXR_COMPRESSION_NONE);
    if (rv == EXR_ERR_SUCCESS)
        rv = exr_add_channel(ctx, part, "Y", EXR_PIXEL_HALF, EXR_PERCEPTUALLY_LOGARITHMIC, 1, 1);
    if (rv == EXR_ERR_SUCCESS)
        rv = exr_set_tile_descriptor(ctx, part, 8, 8, EXR_TILE_ONE_LEVEL, EXR_TILE_ROUND_DOWN);
    if (rv == EXR_ERR_SUCCESS)
        rv = exr_write_header(ctx);
    if (rv == EXR_ERR_SUCCESS)
        rv = exr_write_tile_chunk(ctx, part, 0, 0, 0, 0, tile, sizeof tile);
    if (ctx) {
        exr_result_t f = exr_finish(&ctx);
        if (rv == EXR_ERR_SUCCESS)
            rv = f;
    }
    return rv == EXR_ERR_SUCCESS;
}

static void test_exr_errors(void)
{
    TmpDir t;
    RfImage img, back = {0, 0, 0, NULL};
    unsigned char junk[300];
    unsigned char *good;
    size_t good_n = 0;
    char err[512], path[512];
    const long cuts[] = {3, 8, 40, 200, -60, -8, -1};
    size_t i;
    if (!tmp_open(&t)) {
        RF_CHECK(0);
        return;
    }
    /* A missing file. */
    snprintf(path, sizeof path, "%s", tmp_path(&t, "missing.exr"));
    RF_CHECK_EQ_INT(rf_image_read(path, as_is8, &back, err, sizeof err), RF_ERR_IO);
    RF_CHECK(starts_with(err, path));
    RF_CHECK(back.data == NULL);
    RF_CHECK_EQ_INT(rf_exr_read(path, &back, err, sizeof err), RF_ERR_IO);
    RF_CHECK(back.data == NULL);

    /* The EXR magic followed by garbage. */
    snprintf(path, sizeof path, "%s", tmp_path(&t, "junk.exr"));
    garbage(junk, sizeof junk, 7);
    junk[0] = 0x76;
    junk[1] = 0x2f;
    junk[2] = 0x31;
    junk[3] = 0x01;
    RF_CHECK(write_bytes(path, junk, sizeof junk));
    RF_CHECK_EQ_INT(rf_image_read(path, as_is8, &back, err, sizeof err), RF_ERR_PARSE);
    RF_CHECK(starts_with(err, path));
    RF_CHECK(back.data == NULL);
    /* ... and a correct version field before the garbage. */
    junk[4] = 2;
    junk[5] = junk[6] = junk[7] = 0;
    RF_CHECK(write_bytes(path, junk, sizeof junk));
    RF_CHECK_EQ_INT(rf_image_read(path, as_is8, &back, err, sizeof err), RF_ERR_PARSE);
    RF_CHECK(back.data == NULL);

    /* A good file cut short at several places: header, offset table, pixel data. */
    snprintf(path, sizeof path, "%s", tmp_path(&t, "cut.exr"));
    RF_CHECK_EQ_INT(rf_image_alloc(&img, 16, 40, 3), RF_OK);
    if (!img.data)
        return;
    for (i = 0; i < 16 * 40 * 3; i++)
        img.data[i] = (float)i;
    RF_CHECK_EQ_INT(rf_exr_write(path, &img, NULL, 0, err, sizeof err), RF_OK);
    good = read_bytes(path, &good_n);
    RF_CHECK(good != NULL);
    for (i = 0; good && i < sizeof cuts / sizeof cuts[0]; i++) {
        size_t len = cuts[i] > 0 ? (size_t)cuts[i] : good_n - (size_t)-cuts[i];
        RfStatus st;
        RF_CHECK(write_bytes(path, good, len));
        st = rf_image_read(path, as_is8, &back, err, sizeof err);
        if (st == RF_OK)
            rf_test_fail(__FILE__, __LINE__, "EXR cut to %zu of %zu bytes was read without error", len, good_n);
        RF_CHECK(st == RF_ERR_PARSE || st == RF_ERR_IO);
        RF_CHECK(starts_with(err, path));
        RF_CHECK(back.data == NULL);
        rf_image_free(&back);
    }
    /* Garbage inside the compressed pixel data. */
    if (good && good_n > 400) {
        garbage(good + good_n - 300, 250, 99);
        RF_CHECK(write_bytes(path, good, good_n));
        RF_CHECK(rf_image_read(path, as_is8, &back, err, sizeof err) != RF_OK);
        RF_CHECK(back.data == NULL);
    }
    free(good);
    rf_image_free(&img);

    /* Tiled files: a clear refusal. */
    snprintf(path, sizeof path, "%s", tmp_path(&t, "tiled.exr"));
    RF_CHECK(write_tiled_exr(path));
    RF_CHECK_EQ_INT(rf_image_read(path, as_is8, &back, err, sizeof err), RF_ERR_PARSE);
    RF_CHECK(strstr(err, "tiled") != NULL);
    RF_CHECK(back.data == NULL);
    tmp_close(&t);
}

/* ---- PNG ---- */

/* Writes one row of values (3 channels, each pixel grey) and returns the codes read back as-is. */
static void png_codes(TmpDir *t, const double *v, int n, RfPngOptions opt, long *codes)
{
    RfImage img, back = {0, 0, 0, NULL};
    char err[512], path[512];
    double max = opt.bits == 16 ? 65535.0 : 255.0;
    RfPngOptions raw = {RF_PNG_AS_IS, 0.0, opt.bits, NULL};
    int i;
    snprintf(path, sizeof path, "%s", tmp_path(t, "codes.png"));
    for (i = 0; i < n; i++)
        codes[i] = -1;
    if (rf_image_alloc(&img, n, 1, 3) != RF_OK)
        return;
    for (i = 0; i < n * 3; i++)
        img.data[i] = (float)v[i / 3];
    RF_CHECK_EQ_INT(rf_png_write(path, &img, opt, err, sizeof err), RF_OK);
    RF_CHECK_EQ_INT(rf_image_read(path, raw, &back, err, sizeof err), RF_OK);
    if (back.data && back.width == n && back.channels == 3)
        for (i = 0; i < n; i++) {
            codes[i] = lround(back.data[i * 3] * max);
            RF_CHECK(back.data[i * 3 + 1] == back.data[i * 3] && back.data[i * 3 + 2] == back.data[i * 3]);
        }
    rf_image_free(&img);
    rf_image_free(&back);
    unlink(path);
}

static void test_png_codes_8bit(void)
{
    TmpDir t;
    const double v[] = {0.5, 0.0, 1.0, 0.0031308, 0.00313081, 0.18, -1.0, 2.0, NAN, INFINITY, 0.25, 0.02};
    long c[sizeof v / sizeof v[0]];
    RfPngOptions gamma = {RF_PNG_GAMMA, 2.2, 8, NULL}, srgb = {RF_PNG_SRGB, 0.0, 8, NULL}, asis = {RF_PNG_AS_IS, 0.0, 8, NULL};
    size_t i;
    if (!tmp_open(&t)) {
        RF_CHECK(0);
        return;
    }
    png_codes(&t, v, (int)(sizeof v / sizeof v[0]), gamma, c);
    RF_CHECK_EQ_INT(c[0], 186); /* round(0.5^(1/2.2) * 255) = round(186.08) */
    RF_CHECK_EQ_INT(c[1], 0);
    RF_CHECK_EQ_INT(c[2], 255);
    RF_CHECK_EQ_INT(c[5], (long)floor(pow(0.18, 1 / 2.2) * 255 + 0.5));
    RF_CHECK_EQ_INT(c[6], 0);   /* clamped */
    RF_CHECK_EQ_INT(c[7], 255); /* clamped */
    RF_CHECK_EQ_INT(c[8], 0);   /* NaN */
    RF_CHECK_EQ_INT(c[9], 255);
    png_codes(&t, v, (int)(sizeof v / sizeof v[0]), srgb, c);
    RF_CHECK_EQ_INT(c[0], 188); /* round((1.055 * 0.5^(1/2.4) - 0.055) * 255) = round(187.52) */
    RF_CHECK_EQ_INT(c[3], 10);  /* the linear segment's end: 12.92 * 0.0031308 * 255 = 10.31 */
    RF_CHECK_EQ_INT(c[4], 10);  /* just past it, on the power segment: continuous */
    RF_CHECK_EQ_INT(c[5], (long)floor((1.055 * pow(0.18, 1 / 2.4) - 0.055) * 255 + 0.5));
    /* between the linear segment's end and ten times it, by hand: 0.02^(1/2.4) = e^(ln 0.02 / 2.4)
     * = e^-1.63001 = 0.195914; 1.055 * 0.195914 - 0.055 = 0.151689; * 255 = 38.68 -> 39 (the
     * linear segment would give 12.92 * 0.02 * 255 = 65.9 -> 66) */
    RF_CHECK_EQ_INT(c[11], 39);
    RF_CHECK_EQ_INT(c[7], 255);
    png_codes(&t, v, (int)(sizeof v / sizeof v[0]), asis, c);
    RF_CHECK_EQ_INT(c[0], 128); /* 127.5 rounds up */
    RF_CHECK_EQ_INT(c[10], 64); /* 63.75 */
    for (i = 0; i < sizeof v / sizeof v[0]; i++)
        RF_CHECK(c[i] >= 0 && c[i] <= 255);
    RF_CHECK_EQ_INT(tmp_count(&t), 0);
    tmp_close(&t);
}

static void test_png_codes_16bit(void)
{
    TmpDir t;
    const double v[] = {0.5, 0.0031308, 1.0, 0.0, 0.75};
    long c[5];
    RfPngOptions gamma = {RF_PNG_GAMMA, 2.2, 16, NULL}, srgb = {RF_PNG_SRGB, 0.0, 16, NULL}, asis = {RF_PNG_AS_IS, 0.0, 16, NULL};
    if (!tmp_open(&t)) {
        RF_CHECK(0);
        return;
    }
    png_codes(&t, v, 5, gamma, c);
    RF_CHECK_EQ_INT(c[0], 47824); /* 0.5^(1/2.2) * 65535 = 47823.51 */
    RF_CHECK_EQ_INT(c[2], 65535);
    RF_CHECK_EQ_INT(c[3], 0);
    png_codes(&t, v, 5, srgb, c);
    RF_CHECK_EQ_INT(c[0], 48192); /* 48191.62 */
    RF_CHECK_EQ_INT(c[1], 2651);  /* 12.92 * 0.0031308 * 65535 = 2650.89 */
    png_codes(&t, v, 5, asis, c);
    RF_CHECK_EQ_INT(c[0], 32768); /* 32767.5 rounds up */
    RF_CHECK_EQ_INT(c[4], 49151); /* 49151.25 */
    tmp_close(&t);
}

/* Round trip through the curve: the linear value comes back within half a code step of the
 * encoded value, mapped back through the curve's slope. */
static void png_roundtrip(TmpDir *t, int channels, RfPngOptions opt)
{
    RfImage img, back = {0, 0, 0, NULL};
    char err[512], path[512];
    int w = 9, h = 4, i, n = w * h * channels;
    double step = 0.5 / (opt.bits == 16 ? 65535.0 : 255.0);
    snprintf(path, sizeof path, "%s", tmp_path(t, "rt.png"));
    if (rf_image_alloc(&img, w, h, channels) != RF_OK) {
        RF_CHECK(0);
        return;
    }
    for (i = 0; i < n; i++)
        img.data[i] = (float)((i % 17) / 16.0);
    RF_CHECK_EQ_INT(rf_png_write(path, &img, opt, err, sizeof err), RF_OK);
    RF_CHECK_EQ_INT(rf_image_read(path, opt, &back, err, sizeof err), RF_OK);
    RF_CHECK_EQ_INT(back.channels, channels);
    RF_CHECK_EQ_INT(back.width, w);
    RF_CHECK_EQ_INT(back.height, h);
    if (back.data && back.channels == channels && back.width == w && back.height == h) {
        for (i = 0; i < n; i++) {
            double v = img.data[i], r = back.data[i], tol;
            if (channels == 4 && i % 4 == 3)
                tol = step; /* alpha: linear codes */
            else if (opt.encoding == RF_PNG_GAMMA) /* dv = gamma * e^(gamma-1) de */
                tol = opt.gamma * pow(pow(v, 1 / opt.gamma) + step, opt.gamma - 1) * step;
            else if (opt.encoding == RF_PNG_SRGB)
                tol = 2.4 / 1.055 * pow((1.055 * pow(v, 1 / 2.4) - 0.055 + step + 0.055) / 1.055, 1.4) * step + step / 12.92;
            else
                tol = step;
            if (!(fabs(v - r) <= tol * 1.0001 + 1e-7))
                rf_test_fail(__FILE__, __LINE__, "sample %d: %.9g read back as %.9g (tol %.3g, %d ch, enc %d, %d bits)",
                             i, v, r, tol, channels, (int)opt.encoding, opt.bits);
            rf_test_checks++;
        }
        RF_CHECK(back.data[0] == 0.0f);      /* 0 -> code 0 -> 0 */
        RF_CHECK(back.data[16] == 1.0f);     /* 1 -> full code -> 1 */
    }
    rf_image_free(&img);
    rf_image_free(&back);
    RF_CHECK_EQ_INT(tmp_count(t), 1);
    unlink(path);
}

static void test_png_roundtrip(void)
{
    TmpDir t;
    const RfPngEncoding enc[] = {RF_PNG_GAMMA, RF_PNG_SRGB, RF_PNG_AS_IS};
    const int chans[] = {1, 3, 4};
    int e, c, b;
    if (!tmp_open(&t)) {
        RF_CHECK(0);
        return;
    }
    for (e = 0; e < 3; e++)
        for (c = 0; c < 3; c++)
            for (b = 8; b <= 16; b += 8) {
                RfPngOptions o = {enc[e], 2.2, b, NULL};
                png_roundtrip(&t, chans[c], o);
            }
    {
        RfPngOptions o = {RF_PNG_GAMMA, 1.8, 8, NULL};
        png_roundtrip(&t, 3, o);
    }
    tmp_close(&t);
}

/* Alpha is stored linearly (PNG's rule) while colour is curved; grey stays one channel. */
static void test_png_alpha_and_grey(void)
{
    TmpDir t;
    RfImage img, back = {0, 0, 0, NULL};
    RfPngOptions gamma = {RF_PNG_GAMMA, 2.2, 8, NULL};
    char err[512], path[512];
    if (!tmp_open(&t)) {
        RF_CHECK(0);
        return;
    }
    snprintf(path, sizeof path, "%s", tmp_path(&t, "a.png"));
    RF_CHECK_EQ_INT(rf_image_alloc(&img, 1, 1, 4), RF_OK);
    if (!img.data)
        return;
    img.data[0] = img.data[1] = img.data[2] = img.data[3] = 0.5f;
    RF_CHECK_EQ_INT(rf_png_write(path, &img, gamma, err, sizeof err), RF_OK);
    RF_CHECK_EQ_INT(rf_image_read(path, as_is8, &back, err, sizeof err), RF_OK);
    RF_CHECK_EQ_INT(back.channels, 4);
    if (back.data && back.channels == 4) {
        RF_CHECK_EQ_INT(lround(back.data[0] * 255), 186);
        RF_CHECK_EQ_INT(lround(back.data[3] * 255), 128);
    }
    rf_image_free(&back);
    rf_image_free(&img);

    RF_CHECK_EQ_INT(rf_image_alloc(&img, 2, 1, 1), RF_OK);
    if (!img.data)
        return;
    img.data[0] = 0.5f;
    img.data[1] = 1.0f;
    RF_CHECK_EQ_INT(rf_png_write(path, &img, gamma, err, sizeof err), RF_OK);
    RF_CHECK_EQ_INT(rf_image_read(path, as_is8, &back, err, sizeof err), RF_OK);
    RF_CHECK_EQ_INT(back.channels, 1);
    if (back.data && back.channels == 1) {
        RF_CHECK_EQ_INT(lround(back.data[0] * 255), 186);
        RF_CHECK(back.data[1] == 1.0f);
    }
    rf_image_free(&back);
    rf_image_free(&img);
    tmp_close(&t);
}

/* PNG CRC-32 (for hand-made chunks). */
static unsigned long crc32_png(const unsigned char *p, size_t n)
{
    unsigned long c = 0xffffffffUL;
    size_t i;
    int k;
    for (i = 0; i < n; i++) {
        c ^= p[i];
        for (k = 0; k < 8; k++)
            c = c & 1 ? 0xedb88320UL ^ (c >> 1) : c >> 1;
    }
    return c ^ 0xffffffffUL;
}

static void put32(unsigned char *p, unsigned long v)
{
    p[0] = (unsigned char)(v >> 24);
    p[1] = (unsigned char)(v >> 16);
    p[2] = (unsigned char)(v >> 8);
    p[3] = (unsigned char)v;
}

static void test_png_errors(void)
{
    TmpDir t;
    RfImage img, back = {0, 0, 0, NULL};
    RfPngOptions gamma = {RF_PNG_GAMMA, 2.2, 8, NULL};
    unsigned char *good;
    size_t good_n = 0, i;
    char err[512], path[512];
    const long cuts[] = {4, 8, 12, 20, 33, 45, -40, -13, -1};
    if (!tmp_open(&t)) {
        RF_CHECK(0);
        return;
    }
    snprintf(path, sizeof path, "%s", tmp_path(&t, "missing.png"));
    RF_CHECK_EQ_INT(rf_image_read(path, gamma, &back, err, sizeof err), RF_ERR_IO);
    RF_CHECK(starts_with(err, path));
    RF_CHECK_EQ_INT(rf_png_read(path, gamma, &back, err, sizeof err), RF_ERR_IO);
    RF_CHECK(back.data == NULL);

    /* A good 32x32 PNG, then cut, then corrupted. */
    snprintf(path, sizeof path, "%s", tmp_path(&t, "p.png"));
    RF_CHECK_EQ_INT(rf_image_alloc(&img, 32, 32, 3), RF_OK);
    if (!img.data)
        return;
    for (i = 0; i < 32 * 32 * 3; i++)
        img.data[i] = (float)((i * 37 % 101) / 100.0);
    RF_CHECK_EQ_INT(rf_png_write(path, &img, gamma, err, sizeof err), RF_OK);
    rf_image_free(&img);
    good = read_bytes(path, &good_n);
    RF_CHECK(good != NULL && good_n > 100);
    if (!good || good_n <= 100) {
        free(good);
        tmp_close(&t);
        return;
    }
    for (i = 0; i < sizeof cuts / sizeof cuts[0]; i++) {
        size_t len = cuts[i] > 0 ? (size_t)cuts[i] : good_n - (size_t)-cuts[i];
        RfStatus st;
        RF_CHECK(write_bytes(path, good, len));
        st = rf_image_read(path, gamma, &back, err, sizeof err);
        if (st == RF_OK)
            rf_test_fail(__FILE__, __LINE__, "PNG cut to %zu of %zu bytes was read without error", len, good_n);
        RF_CHECK(st == RF_ERR_PARSE);
        RF_CHECK(starts_with(err, path));
        RF_CHECK(back.data == NULL);
        rf_image_free(&back);
    }
    /* Bytes flipped inside IDAT: a CRC error (or a zlib error), never a crash. */
    {
        unsigned char *bad = malloc(good_n);
        if (bad) {
            memcpy(bad, good, good_n);
            for (i = 60; i < 70; i++)
                bad[i] ^= 0x5a;
            RF_CHECK(write_bytes(path, bad, good_n));
            RF_CHECK_EQ_INT(rf_image_read(path, gamma, &back, err, sizeof err), RF_ERR_PARSE);
            RF_CHECK(strstr(err, "corrupt") != NULL);
            RF_CHECK(back.data == NULL);
            /* The PNG signature followed by garbage. */
            garbage(bad + 8, good_n - 8, 3);
            RF_CHECK(write_bytes(path, bad, good_n));
            RF_CHECK_EQ_INT(rf_image_read(path, gamma, &back, err, sizeof err), RF_ERR_PARSE);
            RF_CHECK(back.data == NULL);
            free(bad);
        }
    }
    /* An absurd size in a valid header: refused before the pixels are allocated. */
    {
        unsigned char hdr[8 + 25 + 12]; /* signature, IHDR, an empty IDAT (where libpng stops) */
        memcpy(hdr, good, 8);
        put32(hdr + 8, 13);
        memcpy(hdr + 12, "IHDR", 4);
        put32(hdr + 16, 1000000); /* within libpng's own limit of 1e6 x 1e6 */
        put32(hdr + 20, 1000000);
        hdr[24] = 8; /* depth */
        hdr[25] = 2; /* RGB */
        hdr[26] = hdr[27] = hdr[28] = 0;
        put32(hdr + 29, crc32_png(hdr + 12, 17));
        put32(hdr + 33, 0);
        memcpy(hdr + 37, "IDAT", 4);
        put32(hdr + 41, crc32_png(hdr + 37, 4));
        RF_CHECK(write_bytes(path, hdr, sizeof hdr));
        RF_CHECK_EQ_INT(rf_image_read(path, gamma, &back, err, sizeof err), RF_ERR_PARSE);
        if (!strstr(err, "PNG claims 1000000 x 1000000 pixels, far more than its 45 bytes can hold"))
            rf_test_fail(__FILE__, __LINE__, "unexpected message: %s", err);
        RF_CHECK(back.data == NULL);
    }
    free(good);
    /* No known signature (a PPM is read now: tests/test_grade.c); an empty file. */
    RF_CHECK(write_bytes(path, "Q3\n1 1\n255\n0 0 0\n", 17));
    RF_CHECK_EQ_INT(rf_image_read(path, gamma, &back, err, sizeof err), RF_ERR_PARSE);
    RF_CHECK(starts_with(err, path) && strstr(err, "signature") != NULL);
    RF_CHECK(write_bytes(path, "", 0));
    RF_CHECK_EQ_INT(rf_image_read(path, gamma, &back, err, sizeof err), RF_ERR_PARSE);
    RF_CHECK(back.data == NULL);
    /* Bad decode options. */
    {
        RfPngOptions bad = {RF_PNG_GAMMA, -1.0, 8, NULL};
        RF_CHECK_EQ_INT(rf_png_read(path, bad, &back, err, sizeof err), RF_ERR_DOMAIN);
    }
    tmp_close(&t);
}

/* ---- atomic writes ---- */

static void test_write_bad_folder(void)
{
    TmpDir t;
    RfImage img;
    RfPngOptions gamma = {RF_PNG_GAMMA, 2.2, 8, NULL};
    char err[512], path[512];
    if (!tmp_open(&t)) {
        RF_CHECK(0);
        return;
    }
    RF_CHECK_EQ_INT(rf_image_alloc(&img, 2, 2, 3), RF_OK);
    if (!img.data)
        return;
    snprintf(path, sizeof path, "%s", tmp_path(&t, "no/such/folder/x.png"));
    RF_CHECK_EQ_INT(rf_png_write(path, &img, gamma, err, sizeof err), RF_ERR_IO);
    RF_CHECK(starts_with(err, path));
    RF_CHECK(strstr(err, "No such file") != NULL);
    snprintf(path, sizeof path, "%s", tmp_path(&t, "no/x.exr"));
    RF_CHECK_EQ_INT(rf_exr_write(path, &img, NULL, 0, err, sizeof err), RF_ERR_IO);
    RF_CHECK(starts_with(err, path));
    RF_CHECK_EQ_INT(tmp_count(&t), 0);

    /* The target is a folder: the rename fails, the temporary file goes, the folder stays. */
    snprintf(path, sizeof path, "%s", tmp_path(&t, "sub"));
    RF_CHECK(mkdir(path, 0755) == 0);
    RF_CHECK_EQ_INT(rf_png_write(path, &img, gamma, err, sizeof err), RF_ERR_IO);
    RF_CHECK(starts_with(err, path));
    RF_CHECK_EQ_INT(rf_exr_write(path, &img, NULL, 0, err, sizeof err), RF_ERR_IO);
    RF_CHECK_EQ_INT(tmp_count(&t), 1);
    {
        struct stat st;
        RF_CHECK(stat(path, &st) == 0 && S_ISDIR(st.st_mode));
    }
    rmdir(path);

    /* Overwriting a good file works, and keeps its permissions. */
    snprintf(path, sizeof path, "%s", tmp_path(&t, "keep.png"));
    RF_CHECK_EQ_INT(rf_png_write(path, &img, gamma, err, sizeof err), RF_OK);
    RF_CHECK(chmod(path, 0640) == 0);
    img.data[0] = 1.0f;
    RF_CHECK_EQ_INT(rf_png_write(path, &img, gamma, err, sizeof err), RF_OK);
    {
        struct stat st;
        RF_CHECK(stat(path, &st) == 0 && (st.st_mode & 0777) == 0640);
    }
    /* A failed write (bad options) leaves it as it was. */
    {
        size_t n0 = 0, n1 = 0;
        unsigned char *before = read_bytes(path, &n0), *after;
        RfPngOptions bad = {RF_PNG_GAMMA, 2.2, 7, NULL};
        RF_CHECK(rf_png_write(path, &img, bad, err, sizeof err) != RF_OK);
        after = read_bytes(path, &n1);
        RF_CHECK(before && after && n0 == n1 && memcmp(before, after, n0) == 0);
        free(before);
        free(after);
    }
    RF_CHECK_EQ_INT(tmp_count(&t), 1);
    rf_image_free(&img);
    tmp_close(&t);
}

/* A NULL or zero-sized err buffer is allowed. */
static void test_no_err_buffer(void)
{
    RfImage back = {0, 0, 0, NULL};
    char small[8];
    RF_CHECK_EQ_INT(rf_image_read("/nonexistent/refray.exr", as_is8, &back, NULL, 0), RF_ERR_IO);
    RF_CHECK_EQ_INT(rf_image_read("/nonexistent/refray.exr", as_is8, &back, small, sizeof small), RF_ERR_IO);
    RF_CHECK(strlen(small) == sizeof small - 1);
    RF_CHECK(back.data == NULL);
}

const RfTest rf_tests_io[] = {
    {"io_image_alloc", test_image_alloc},
    {"io_write_bad_images", test_write_bad_images},
    {"io_exr_roundtrip_exact", test_exr_roundtrip_exact},
    {"io_exr_default_write", test_exr_default_write},
    {"io_exr_half", test_exr_half},
    {"io_exr_attributes", test_exr_attributes},
    {"io_exr_errors", test_exr_errors},
    {"io_png_codes_8bit", test_png_codes_8bit},
    {"io_png_codes_16bit", test_png_codes_16bit},
    {"io_png_roundtrip", test_png_roundtrip},
    {"io_png_alpha_and_grey", test_png_alpha_and_grey},
    {"io_png_errors", test_png_errors},
    {"io_write_bad_folder", test_write_bad_folder},
    {"io_no_err_buffer", test_no_err_buffer},
    RF_TEST_END,
};
