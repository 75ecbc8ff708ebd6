/* OpenEXR through OpenEXRCore's C API. Files are written through our own pwrite callback into
 * the temporary file of rf_atomic_open and read through our own pread callback, so the context's
 * user data is ours and the error handler can keep the library's message for err. */
#include "io_internal.h"

#include "refray/parallel.h"

#include <errno.h>
#include <fcntl.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

/* Included as <OpenEXR/...> rather than through pkg-config's -I/usr/include/OpenEXR: the headers
 * then count as system headers, whose C11 anonymous unions -Wpedantic would reject in C99. */
#include <OpenEXR/openexr.h>

typedef struct {
    int fd;
    char msg[256]; /* the library's first error message */
} ExrIo;

static void exr_on_error(exr_const_context_t ctxt, exr_result_t code, const char *msg)
{
    void *ud = NULL;
    if (exr_get_user_data(ctxt, &ud) == EXR_ERR_SUCCESS && ud) {
        ExrIo *io = ud;
        if (io->msg[0] == '\0')
            snprintf(io->msg, sizeof io->msg, "%s", msg ? msg : exr_get_default_error_message(code));
    }
}

/* A write context's handler may not ask for the user data: the library calls it with the
 * context's lock held, and exr_get_user_data takes that lock again (a deadlock when a write
 * fails). The writer keeps its own message (exr_pwrite) and falls back to the code's. */
static void exr_on_write_error(exr_const_context_t ctxt, exr_result_t code, const char *msg)
{
    (void)ctxt;
    (void)code;
    (void)msg;
}

static int64_t exr_pwrite(exr_const_context_t ctxt, void *ud, const void *buffer, uint64_t sz, uint64_t offset,
                          exr_stream_error_func_ptr_t error_cb)
{
    ExrIo *io = ud;
    const char *p = buffer;
    uint64_t done = 0;
    while (done < sz) {
        size_t part = sz - done > (uint64_t)1 << 30 ? (size_t)1 << 30 : (size_t)(sz - done);
        ssize_t n = pwrite(io->fd, p + done, part, (off_t)(offset + done));
        if (n < 0 && errno == EINTR)
            continue;
        if (n <= 0) {
            char msg[128];
            int e = n < 0 ? errno : ENOSPC; /* a write of 0 bytes: the device is full */
            if (strerror_r(e, msg, sizeof msg) != 0)
                snprintf(msg, sizeof msg, "error %d", e);
            if (!io->msg[0])
                snprintf(io->msg, sizeof io->msg, "write failed: %s", msg);
            error_cb(ctxt, EXR_ERR_WRITE_IO, "write failed: %s", msg);
            return -1;
        }
        done += (uint64_t)n;
    }
    return (int64_t)done;
}

/* A short count at the end of the file is not an error here: the library reports the missing bytes. */
static int64_t exr_pread(exr_const_context_t ctxt, void *ud, void *buffer, uint64_t sz, uint64_t offset,
                         exr_stream_error_func_ptr_t error_cb)
{
    ExrIo *io = ud;
    char *p = buffer;
    uint64_t done = 0;
    while (done < sz) {
        size_t part = sz - done > (uint64_t)1 << 30 ? (size_t)1 << 30 : (size_t)(sz - done);
        ssize_t n = pread(io->fd, p + done, part, (off_t)(offset + done));
        if (n < 0 && errno == EINTR)
            continue;
        if (n < 0) {
            char msg[128];
            if (strerror_r(errno, msg, sizeof msg) == 0)
                error_cb(ctxt, EXR_ERR_READ_IO, "read failed: %s", msg);
            else
                error_cb(ctxt, EXR_ERR_READ_IO, "read failed");
            return -1;
        }
        if (n == 0)
            break;
        done += (uint64_t)n;
    }
    return (int64_t)done;
}

static int64_t exr_size(exr_const_context_t ctxt, void *ud)
{
    ExrIo *io = ud;
    struct stat st;
    (void)ctxt;
    return fstat(io->fd, &st) == 0 ? (int64_t)st.st_size : -1;
}

/* The library's message for a failed call, or the generic one for its code. */
static const char *exr_msg(const ExrIo *io, exr_result_t rv)
{
    return io->msg[0] ? io->msg : exr_get_default_error_message(rv);
}

static RfStatus exr_status(exr_result_t rv)
{
    switch (rv) {
    case EXR_ERR_OUT_OF_MEMORY: return RF_ERR_NOMEM;
    case EXR_ERR_FILE_ACCESS:
    case EXR_ERR_READ_IO:
    case EXR_ERR_WRITE_IO: return RF_ERR_IO;
    case EXR_ERR_INVALID_ARGUMENT:
    case EXR_ERR_ARGUMENT_OUT_OF_RANGE:
    case EXR_ERR_NAME_TOO_LONG:
    case EXR_ERR_ATTR_TYPE_MISMATCH: return RF_ERR_DOMAIN;
    default: return RF_ERR_PARSE;
    }
}

/* ---- writing ---- */

static const char *const rgba_names[4] = {"R", "G", "B", "A"};

/* Index of an EXR channel name in our interleaved pixel, or -1. */
static int channel_slot(const char *name, int channels)
{
    int c;
    if (channels == 1)
        return strcmp(name, "Y") == 0 ? 0 : -1;
    for (c = 0; c < channels; c++)
        if (strcmp(name, rgba_names[c]) == 0)
            return c;
    return -1;
}

/* The chunks are compressed on every core, each thread with an encode pipeline of its own (the
 * library's design: a pipeline per thread, the context shared read-only), and written in order
 * afterwards (a part with increasing y takes its chunks in order). zlib is most of a write:
 * 512 x 512 RGB floats take 30 ms on one core. */
typedef struct {
    exr_const_context_t ctx;
    int part, y0;
    const RfImage *img;
    const exr_chunk_info_t *ci;  /* per chunk */
    uint8_t **data;              /* per chunk: its bytes as they go into the file */
    size_t *size;
    struct EncodeThread *thread; /* per thread */
} EncodeJob;

typedef struct EncodeThread {
    EncodeJob *job;
    exr_encode_pipeline_t enc;
    int inited, chosen, chunk;
    exr_result_t rv;
} EncodeThread;

/* The pipeline's write step: keeps a copy of the chunk's bytes (compressed, or packed when
 * compression would not shrink them) for the ordered write. */
static exr_result_t stash_chunk(exr_encode_pipeline_t *enc)
{
    EncodeThread *t = enc->encoding_user_data;
    EncodeJob *j = t->job;
    uint8_t *copy = malloc(enc->compressed_bytes ? enc->compressed_bytes : 1);
    if (!copy)
        return EXR_ERR_OUT_OF_MEMORY;
    memcpy(copy, enc->compressed_buffer, enc->compressed_bytes);
    j->data[t->chunk] = copy;
    j->size[t->chunk] = enc->compressed_bytes;
    return EXR_ERR_SUCCESS;
}

static int encode_chunk(void *ctx, int k, int thread)
{
    EncodeJob *j = ctx;
    EncodeThread *t = &j->thread[thread];
    const exr_chunk_info_t *ci = &j->ci[k];
    const RfImage *img = j->img;
    const int nc = img->channels;
    exr_result_t rv;
    if (t->inited) {
        rv = exr_encoding_update(j->ctx, j->part, ci, &t->enc);
    } else {
        t->inited = 1; /* destroy even a half-initialised pipeline: it frees what is there */
        rv = exr_encoding_initialize(j->ctx, j->part, ci, &t->enc);
    }
    for (int i = 0; rv == EXR_ERR_SUCCESS && i < t->enc.channel_count; i++) {
        exr_coding_channel_info_t *ch = &t->enc.channels[i];
        int c = channel_slot(ch->channel_name, nc);
        if (c < 0) { /* cannot happen: we declared the channels */
            rv = EXR_ERR_INVALID_ARGUMENT;
            break;
        }
        ch->user_bytes_per_element = (int16_t)sizeof(float);
        ch->user_data_type = EXR_PIXEL_FLOAT;
        ch->user_pixel_stride = (int32_t)(nc * sizeof(float));
        ch->user_line_stride = (int32_t)((size_t)img->width * (size_t)nc * sizeof(float));
        ch->encode_from_ptr =
            (const uint8_t *)(img->data + ((size_t)(ci->start_y - j->y0) * (size_t)img->width) * (size_t)nc + (size_t)c);
    }
    if (rv == EXR_ERR_SUCCESS && !t->chosen) {
        t->chosen = 1;
        rv = exr_encoding_choose_default_routines(j->ctx, j->part, &t->enc);
        t->enc.write_fn = stash_chunk;
        t->enc.yield_until_ready_fn = NULL; /* the library's checks that this chunk is next to be
                                               written: the ordered write makes them */
        t->enc.encoding_user_data = t;
    }
    t->chunk = k;
    if (rv == EXR_ERR_SUCCESS)
        rv = exr_encoding_run(j->ctx, j->part, &t->enc);
    if (rv != EXR_ERR_SUCCESS && t->rv == EXR_ERR_SUCCESS)
        t->rv = rv;
    return rv != EXR_ERR_SUCCESS;
}

static exr_result_t write_pixels(exr_context_t ctx, int part, const RfImage *img, int y0)
{
    int32_t lines;
    exr_result_t rv = exr_get_scanlines_per_chunk(ctx, part, &lines);
    if (rv != EXR_ERR_SUCCESS)
        return rv;
    int chunks = (int)(((int64_t)img->height + lines - 1) / lines);
    int threads = rf_cpu_count();
    threads = threads < chunks ? threads : chunks;
    EncodeJob j = {ctx, part, y0, img, NULL, NULL, NULL, NULL};
    exr_chunk_info_t *ci = calloc((size_t)chunks, sizeof *ci);
    j.data = calloc((size_t)chunks, sizeof *j.data);
    j.size = calloc((size_t)chunks, sizeof *j.size);
    j.thread = calloc((size_t)threads, sizeof *j.thread);
    j.ci = ci;
    if (!ci || !j.data || !j.size || !j.thread)
        rv = EXR_ERR_OUT_OF_MEMORY;
    /* The library hands out a chunk's info only when the chunk is next to be written: the first
     * one from it, the others the same with their rows (the last one may be shorter); each is
     * checked against the library's when it is written. Chunks start at the data window. */
    if (rv == EXR_ERR_SUCCESS)
        rv = exr_write_scanline_chunk_info(ctx, part, y0, &ci[0]);
    for (int k = 1; rv == EXR_ERR_SUCCESS && k < chunks; k++) {
        ci[k] = ci[0];
        ci[k].idx = ci[0].idx + k;
        ci[k].start_y = y0 + k * lines;
        ci[k].height = img->height - k * lines < lines ? img->height - k * lines : lines;
        ci[k].unpacked_size = ci[0].unpacked_size / (uint64_t)ci[0].height * (uint64_t)ci[k].height;
    }
    if (rv == EXR_ERR_SUCCESS) {
        for (int t = 0; t < threads; t++) {
            exr_encode_pipeline_t init = EXR_ENCODE_PIPELINE_INITIALIZER;
            j.thread[t].job = &j;
            j.thread[t].enc = init;
        }
        if (rf_parallel_for(chunks, threads, encode_chunk, NULL, &j) != RF_OK) {
            rv = EXR_ERR_OUT_OF_MEMORY; /* a thread could not start, unless a chunk failed: */
            for (int t = 0; t < threads; t++)
                if (j.thread[t].rv != EXR_ERR_SUCCESS)
                    rv = j.thread[t].rv;
        }
    }
    for (int k = 0; rv == EXR_ERR_SUCCESS && k < chunks; k++)
    {
        exr_chunk_info_t lib;
        if (k > 0) {
            rv = exr_write_scanline_chunk_info(ctx, part, ci[k].start_y, &lib);
            if (rv == EXR_ERR_SUCCESS && (lib.idx != ci[k].idx || lib.height != ci[k].height ||
                                          lib.unpacked_size != ci[k].unpacked_size))
                rv = EXR_ERR_INVALID_ARGUMENT;
        }
        if (rv == EXR_ERR_SUCCESS)
            rv = exr_write_scanline_chunk(ctx, part, ci[k].start_y, j.data[k], j.size[k]);
    }
    for (int t = 0; j.thread && t < threads; t++)
        if (j.thread[t].inited) {
            exr_result_t drv = exr_encoding_destroy(ctx, &j.thread[t].enc);
            if (rv == EXR_ERR_SUCCESS)
                rv = drv;
        }
    for (int k = 0; j.data && k < chunks; k++)
        free(j.data[k]);
    free(ci);
    free(j.data);
    free(j.size);
    free(j.thread);
    return rv;
}

RfStatus rf_exr_write(const char *path, const RfImage *img, const RfImageAttr *attrs, int nattrs, char *err,
                      size_t err_size)
{
    RfExrOptions opt = {RF_EXR_ZIP, 0, NULL, 0, 0, 0, 0};
    return rf_exr_write_opts(path, img, attrs, nattrs, opt, err, err_size);
}

RfStatus rf_exr_write_opts(const char *path, const RfImage *img, const RfImageAttr *attrs, int nattrs,
                           RfExrOptions opt, char *err, size_t err_size)
{
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    exr_context_t ctx = NULL;
    exr_compression_t comp;
    exr_result_t rv;
    RfAtomicFile f;
    ExrIo io;
    RfStatus st;
    int part = 0, c, i, long_names = 0;

    st = rf_io_check_image(img, path, err, err_size);
    if (st != RF_OK)
        return st;
    switch (opt.compression) {
    case RF_EXR_ZIP: comp = EXR_COMPRESSION_ZIP; break;
    case RF_EXR_NONE: comp = EXR_COMPRESSION_NONE; break;
    case RF_EXR_PIZ: comp = EXR_COMPRESSION_PIZ; break;
    default: return rf_io_fail(RF_ERR_DOMAIN, err, err_size, path, "unknown EXR compression %d", (int)opt.compression);
    }
    /* The coding pipeline's line stride is an int32_t. */
    if ((size_t)img->width * (size_t)img->channels * sizeof(float) > INT32_MAX)
        return rf_io_fail(RF_ERR_DOMAIN, err, err_size, path, "image too wide for EXR (%d pixels)", img->width);
    if (nattrs < 0 || (nattrs > 0 && !attrs))
        return rf_io_fail(RF_ERR_DOMAIN, err, err_size, path, "bad attribute list");
    int cropped = opt.x0 != 0 || opt.y0 != 0 || opt.display_width != 0 || opt.display_height != 0;
    if (cropped && (opt.x0 < 0 || opt.y0 < 0 || opt.display_width <= 0 || opt.display_height <= 0 ||
                    (int64_t)opt.x0 + img->width > opt.display_width ||
                    (int64_t)opt.y0 + img->height > opt.display_height))
        return rf_io_fail(RF_ERR_DOMAIN, err, err_size, path, "crop %dx%d at (%d, %d) is not inside %dx%d", img->width,
                          img->height, opt.x0, opt.y0, opt.display_width, opt.display_height);
    for (i = 0; i < nattrs; i++) {
        if (!attrs[i].name || !attrs[i].name[0] || !attrs[i].value)
            return rf_io_fail(RF_ERR_DOMAIN, err, err_size, path, "attribute %d has no name or no value", i);
        if (strlen(attrs[i].name) > 31) /* EXR's short-name limit; longer names set a version flag */
            long_names = 1;
    }

    st = rf_atomic_open(&f, path, err, err_size);
    if (st != RF_OK)
        return st;
    memset(&io, 0, sizeof io);
    io.fd = f.fd;
    init.error_handler_fn = exr_on_write_error;
    init.user_data = &io;
    init.write_fn = exr_pwrite;

    rv = exr_start_write(&ctx, path, EXR_WRITE_FILE_DIRECTLY, &init);
    if (rv == EXR_ERR_SUCCESS)
        rv = exr_add_part(ctx, NULL, EXR_STORAGE_SCANLINE, &part);
    if (rv == EXR_ERR_SUCCESS)
        rv = exr_initialize_required_attr_simple(ctx, part, img->width, img->height, comp);
    if (rv == EXR_ERR_SUCCESS && cropped) {
        exr_attr_box2i_t dw, disp;
        dw.min.x = opt.x0, dw.min.y = opt.y0, dw.max.x = opt.x0 + img->width - 1, dw.max.y = opt.y0 + img->height - 1;
        disp.min.x = 0, disp.min.y = 0, disp.max.x = opt.display_width - 1, disp.max.y = opt.display_height - 1;
        rv = exr_set_data_window(ctx, part, &dw);
        if (rv == EXR_ERR_SUCCESS)
            rv = exr_set_display_window(ctx, part, &disp);
    }
    /* Linear-light data is "perceptually logarithmic" in EXR's terms (pLinear = 0, as the C++
     * library's default); it only matters to B44. */
    for (c = 0; rv == EXR_ERR_SUCCESS && c < img->channels; c++)
        rv = exr_add_channel(ctx, part, img->channels == 1 ? "Y" : rgba_names[c],
                             opt.half ? EXR_PIXEL_HALF : EXR_PIXEL_FLOAT, EXR_PERCEPTUALLY_LOGARITHMIC, 1, 1);
    /* zlib's fastest level: the write takes 22 instead of 30 ms for 640 x 480 RGB floats, for
     * files 2 % larger (the same pixels: the compression is lossless) */
    if (rv == EXR_ERR_SUCCESS && comp == EXR_COMPRESSION_ZIP)
        rv = exr_set_zip_compression_level(ctx, part, 1);
    if (rv == EXR_ERR_SUCCESS && long_names)
        rv = exr_set_longname_support(ctx, 1);
    for (i = 0; rv == EXR_ERR_SUCCESS && i < nattrs; i++) {
        rv = exr_attr_set_string(ctx, part, attrs[i].name, attrs[i].value);
        if (rv != EXR_ERR_SUCCESS && !io.msg[0])
            snprintf(io.msg, sizeof io.msg, "attribute \"%s\": %s", attrs[i].name,
                     exr_get_default_error_message(rv));
    }
    if (rv == EXR_ERR_SUCCESS)
        rv = exr_write_header(ctx);
    if (rv == EXR_ERR_SUCCESS)
        rv = write_pixels(ctx, part, img, cropped ? opt.y0 : 0);
    if (ctx) {
        exr_result_t frv = exr_finish(&ctx); /* writes the chunk offset table */
        if (rv == EXR_ERR_SUCCESS)
            rv = frv;
    }
    if (rv != EXR_ERR_SUCCESS) {
        rf_atomic_abort(&f);
        return rf_io_fail(exr_status(rv), err, err_size, path, "cannot write EXR: %s", exr_msg(&io, rv));
    }
    return rf_atomic_finish(&f, opt.batch, err, err_size);
}

/* ---- reading ---- */

/* Opens path for reading with our callbacks; on failure fills err and leaves *ctx NULL. */
static RfStatus exr_open(const char *path, ExrIo *io, exr_context_t *ctx, char *err, size_t err_size)
{
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    exr_result_t rv;

    *ctx = NULL;
    memset(io, 0, sizeof *io);
    if (!path)
        return rf_io_fail(RF_ERR_DOMAIN, err, err_size, path, "no input path");
    io->fd = open(path, O_RDONLY);
    if (io->fd < 0)
        return rf_io_fail_errno(RF_ERR_IO, err, err_size, path, "cannot open", errno);
    init.error_handler_fn = exr_on_error;
    init.user_data = io;
    init.read_fn = exr_pread;
    init.size_fn = exr_size;
    rv = exr_start_read(ctx, path, &init);
    if (rv != EXR_ERR_SUCCESS) {
        if (*ctx)
            exr_finish(ctx);
        *ctx = NULL;
        close(io->fd);
        io->fd = -1;
        return rf_io_fail(exr_status(rv) == RF_ERR_IO ? RF_ERR_IO : RF_ERR_PARSE, err, err_size, path,
                          "not a readable EXR: %s", exr_msg(io, rv));
    }
    return RF_OK;
}

static void exr_close(ExrIo *io, exr_context_t *ctx)
{
    if (*ctx)
        exr_finish(ctx);
    *ctx = NULL;
    if (io->fd >= 0)
        close(io->fd);
    io->fd = -1;
}

/* Where a file's channel goes in our interleaved pixel, or -1 to skip it. */
static int read_slot(const char *name, int y_only, int nc)
{
    if (!name)
        return -1;
    if (strcmp(name, "A") == 0)
        return nc == 4 ? 3 : -1;
    if (y_only)
        return strcmp(name, "Y") == 0 ? 0 : -1;
    return channel_slot(name, 3);
}

/* Decodes part 0 (scanline) into img, whose size matches the data window dw.
 * Each channel is decoded into its own plane of a scratch buffer, then interleaved here: with
 * interleaved output pointers, OpenEXRCore 3.1's HALF-to-FLOAT fast path for four channels
 * (chosen when the pointers run opposite to the file's alphabetical A,B,G,R order) puts the
 * channels in reverse order. Planes take the generic, order-independent unpacker. */
static exr_result_t read_pixels(exr_context_t ctx, const exr_attr_box2i_t *dw, int y_only, RfImage *img)
{
    exr_decode_pipeline_t dec = EXR_DECODE_PIPELINE_INITIALIZER;
    exr_result_t rv;
    int32_t lines;
    int64_t y;
    int inited = 0, chosen = 0;
    const int nc = img->channels;
    const size_t w = (size_t)img->width;
    float *planes = NULL;
    size_t plane_size = 0;

    rv = exr_get_scanlines_per_chunk(ctx, 0, &lines);
    if (rv == EXR_ERR_SUCCESS && (lines < 1 || (size_t)lines > RF_IMAGE_MAX_PIXELS / w))
        rv = EXR_ERR_FILE_BAD_HEADER;
    if (rv == EXR_ERR_SUCCESS) {
        /* one plane per channel we keep, and one more that the channels we skip decode into: a
         * NULL destination crashes OpenEXRCore's unpackers on chunks whose header and data
         * disagree (found by fuzzing, tests/data/fuzz/exr/) */
        plane_size = w * (size_t)lines;
        planes = malloc(plane_size * ((size_t)nc + 1) * sizeof(float));
        if (!planes)
            rv = EXR_ERR_OUT_OF_MEMORY;
    }
    for (y = dw->min.y; rv == EXR_ERR_SUCCESS && y <= dw->max.y; y += lines) {
        exr_chunk_info_t ci;
        size_t row0, r, x;
        int i, c;
        rv = exr_read_scanline_chunk_info(ctx, 0, (int)y, &ci);
        if (rv != EXR_ERR_SUCCESS)
            break;
        if (ci.start_y < dw->min.y || ci.height < 1 || ci.height > lines || ci.width != img->width ||
            (int64_t)ci.start_y + ci.height - 1 > dw->max.y ||
            /* an uncompressed chunk holds exactly its pixels */
            (ci.compression == EXR_COMPRESSION_NONE && ci.packed_size != ci.unpacked_size)) {
            rv = EXR_ERR_CORRUPT_CHUNK;
            break;
        }
        if (inited)
            rv = exr_decoding_update(ctx, 0, &ci, &dec);
        else {
            inited = 1;
            rv = exr_decoding_initialize(ctx, 0, &ci, &dec);
        }
        if (rv != EXR_ERR_SUCCESS)
            break;
        for (i = 0; i < dec.channel_count; i++) {
            exr_coding_channel_info_t *ch = &dec.channels[i];
            c = read_slot(ch->channel_name, y_only, nc);
            if (c < 0)
                c = nc; /* the scratch plane */
            ch->user_bytes_per_element = (int16_t)sizeof(float);
            ch->user_data_type = EXR_PIXEL_FLOAT;
            ch->user_pixel_stride = (int32_t)sizeof(float);
            ch->user_line_stride = (int32_t)(w * sizeof(float));
            ch->decode_to_ptr = (uint8_t *)(planes + (size_t)c * plane_size);
        }
        if (!chosen) {
            chosen = 1;
            rv = exr_decoding_choose_default_routines(ctx, 0, &dec);
            if (rv != EXR_ERR_SUCCESS)
                break;
        }
        rv = exr_decoding_run(ctx, 0, &dec);
        if (rv != EXR_ERR_SUCCESS)
            break;
        row0 = (size_t)(ci.start_y - dw->min.y);
        for (c = 0; c < nc; c++) {
            const float *src = planes + (size_t)c * plane_size;
            if (y_only && (c == 1 || c == 2))
                src = planes; /* grey with alpha: Y to R, G, B */
            for (r = 0; r < (size_t)ci.height; r++) {
                float *dst = img->data + (row0 + r) * w * (size_t)nc + (size_t)c;
                for (x = 0; x < w; x++)
                    dst[x * (size_t)nc] = src[r * w + x];
            }
        }
    }
    if (inited) {
        exr_result_t drv = exr_decoding_destroy(ctx, &dec);
        if (rv == EXR_ERR_SUCCESS)
            rv = drv;
    }
    free(planes);
    return rv;
}

RfStatus rf_exr_read(const char *path, RfImage *img, char *err, size_t err_size)
{
    const exr_attr_chlist_t *chl = NULL;
    exr_attr_box2i_t dw;
    exr_storage_t storage;
    exr_context_t ctx;
    exr_result_t rv;
    ExrIo io;
    RfStatus st;
    int64_t w, h;
    int idx_r = -1, idx_g = -1, idx_b = -1, idx_a = -1, idx_y = -1, nc, i, y_only;

    st = rf_io_read_start(img, path, err, err_size);
    if (st != RF_OK)
        return st;
    st = exr_open(path, &io, &ctx, err, err_size);
    if (st != RF_OK)
        return st;

    rv = exr_get_storage(ctx, 0, &storage);
    if (rv != EXR_ERR_SUCCESS) {
        st = rf_io_fail(RF_ERR_PARSE, err, err_size, path, "bad EXR header: %s", exr_msg(&io, rv));
        goto done;
    }
    if (storage != EXR_STORAGE_SCANLINE) {
        st = rf_io_fail(RF_ERR_PARSE, err, err_size, path, "%s EXR files are not supported (only scanline images)",
                        storage == EXR_STORAGE_TILED ? "tiled" : "deep");
        goto done;
    }
    rv = exr_get_channels(ctx, 0, &chl);
    if (rv == EXR_ERR_SUCCESS)
        rv = exr_get_data_window(ctx, 0, &dw);
    if (rv != EXR_ERR_SUCCESS || !chl) {
        st = rf_io_fail(RF_ERR_PARSE, err, err_size, path, "bad EXR header: %s", exr_msg(&io, rv));
        goto done;
    }
    for (i = 0; i < chl->num_channels; i++) {
        const exr_attr_chlist_entry_t *e = &chl->entries[i];
        const char *n = e->name.str;
        int *dst = NULL;
        if (!n)
            continue;
        if (strcmp(n, "R") == 0)
            dst = &idx_r;
        else if (strcmp(n, "G") == 0)
            dst = &idx_g;
        else if (strcmp(n, "B") == 0)
            dst = &idx_b;
        else if (strcmp(n, "A") == 0)
            dst = &idx_a;
        else if (strcmp(n, "Y") == 0)
            dst = &idx_y;
        if (!dst)
            continue;
        if (e->x_sampling != 1 || e->y_sampling != 1) {
            st = rf_io_fail(RF_ERR_PARSE, err, err_size, path, "subsampled EXR channel %s is not supported", n);
            goto done;
        }
        *dst = i;
    }
    y_only = !(idx_r >= 0 && idx_g >= 0 && idx_b >= 0);
    if (y_only && idx_y < 0) {
        char names[128] = "";
        size_t len = 0;
        for (i = 0; i < chl->num_channels && len < sizeof names; i++)
            len += (size_t)snprintf(names + len, sizeof names - len, "%s%s", i ? ", " : "",
                                    chl->entries[i].name.str ? chl->entries[i].name.str : "?");
        st = rf_io_fail(RF_ERR_PARSE, err, err_size, path,
                        "EXR channels %s: refray reads R, G and B (all three, A optional) or Y", names);
        goto done;
    }
    nc = y_only ? (idx_a >= 0 ? 4 : 1) : (idx_a >= 0 ? 4 : 3);

    w = (int64_t)dw.max.x - dw.min.x + 1;
    h = (int64_t)dw.max.y - dw.min.y + 1;
    /* no compression EXR has packs more than ~1000 floats into a byte (zlib's limit is about
     * 1032:1): a header that claims far more pixels than the file can hold is refused before its
     * image is allocated (a 263-byte file asked for 2 GiB; found by fuzzing) */
    st = rf_io_check_claim(path, "EXR", (long long)w, (long long)h,
                           (double)(w > 0 ? w : 0) * (double)(h > 0 ? h : 0) * (double)nc * sizeof(float), 4096.0,
                           64.0 * 1048576.0, err, err_size);
    if (st != RF_OK)
        goto done;
    if (w <= 0 || h <= 0 || w > INT32_MAX || h > INT32_MAX ||
        rf_image_alloc(img, (int)w, (int)h, nc) == RF_ERR_DOMAIN) {
        st = rf_io_fail(RF_ERR_PARSE, err, err_size, path, "unsupported EXR data window %lldx%lld", (long long)w,
                        (long long)h);
        goto done;
    }
    if (!img->data) {
        st = rf_io_fail(RF_ERR_NOMEM, err, err_size, path, "out of memory for %lldx%lld pixels", (long long)w,
                        (long long)h);
        goto done;
    }
    if ((size_t)img->width * sizeof(float) > INT32_MAX) { /* the pipeline's line stride is an int32_t */
        st = rf_io_fail(RF_ERR_PARSE, err, err_size, path, "EXR too wide (%d pixels)", img->width);
        goto done;
    }
    rv = read_pixels(ctx, &dw, y_only, img);
    if (rv != EXR_ERR_SUCCESS) {
        st = rf_io_fail(exr_status(rv) == RF_ERR_NOMEM ? RF_ERR_NOMEM : RF_ERR_PARSE, err, err_size, path,
                        "cannot decode EXR pixels: %s", exr_msg(&io, rv));
        goto done;
    }
    st = RF_OK;
done:
    if (st != RF_OK)
        rf_image_free(img);
    exr_close(&io, &ctx);
    return st;
}

RfStatus rf_exr_read_windows(const char *path, RfExrWindow *data, RfExrWindow *display, char *err, size_t err_size)
{
    exr_context_t ctx;
    ExrIo io;
    exr_attr_box2i_t dw, disp;
    RfStatus st = exr_open(path, &io, &ctx, err, err_size);
    if (st != RF_OK)
        return st;
    exr_result_t rv = exr_get_data_window(ctx, 0, &dw);
    if (rv == EXR_ERR_SUCCESS)
        rv = exr_get_display_window(ctx, 0, &disp);
    if (rv != EXR_ERR_SUCCESS)
        st = rf_io_fail(RF_ERR_PARSE, err, err_size, path, "bad EXR header: %s", exr_msg(&io, rv));
    else if ((int64_t)dw.max.x + 1 > INT32_MAX || (int64_t)dw.max.y + 1 > INT32_MAX ||
             (int64_t)disp.max.x + 1 > INT32_MAX || (int64_t)disp.max.y + 1 > INT32_MAX)
        st = rf_io_fail(RF_ERR_PARSE, err, err_size, path, "EXR window too large");
    if (st == RF_OK && data)
        *data = (RfExrWindow){dw.min.x, dw.min.y, dw.max.x + 1, dw.max.y + 1};
    if (st == RF_OK && display)
        *display = (RfExrWindow){disp.min.x, disp.min.y, disp.max.x + 1, disp.max.y + 1};
    exr_close(&io, &ctx);
    return st;
}

RfStatus rf_exr_read_attr(const char *path, const char *name, char **value, char *err, size_t err_size)
{
    exr_context_t ctx;
    exr_result_t rv;
    const char *s = NULL;
    int32_t len = 0;
    ExrIo io;
    RfStatus st;

    if (!value || !name)
        return rf_io_fail(RF_ERR_DOMAIN, err, err_size, path, "no attribute name or result");
    *value = NULL;
    st = exr_open(path, &io, &ctx, err, err_size);
    if (st != RF_OK)
        return st;
    rv = exr_attr_get_string(ctx, 0, name, &len, &s);
    if (rv == EXR_ERR_NO_ATTR_BY_NAME)
        st = rf_io_fail(RF_ERR_DOMAIN, err, err_size, path, "no attribute \"%s\"", name);
    else if (rv == EXR_ERR_ATTR_TYPE_MISMATCH)
        st = rf_io_fail(RF_ERR_DOMAIN, err, err_size, path, "attribute \"%s\" is not a string", name);
    else if (rv != EXR_ERR_SUCCESS || len < 0 || (len > 0 && !s))
        st = rf_io_fail(RF_ERR_PARSE, err, err_size, path, "cannot read attribute \"%s\": %s", name,
                        exr_msg(&io, rv));
    else if (!(*value = malloc((size_t)len + 1)))
        st = rf_io_fail(RF_ERR_NOMEM, err, err_size, path, "out of memory");
    else {
        if (len > 0)
            memcpy(*value, s, (size_t)len);
        (*value)[len] = '\0';
    }
    exr_close(&io, &ctx);
    return st;
}
