/* Tile scheduling and counter-based random numbers: every pixel once, any thread count. */
#include <stdlib.h>
#include <string.h>

#include "refray/parallel.h"
#include "refray/rng.h"
#include "rf_test.h"

typedef struct {
    int width;
    unsigned char *hits;
    double *value;
    int fail_at;
} Ctx;

static int fill(void *vctx, RfTile t, int thread)
{
    Ctx *c = vctx;
    (void)thread;
    if (t.index == c->fail_at)
        return 1;
    for (int y = t.y0; y < t.y1; y++)
        for (int x = t.x0; x < t.x1; x++) {
            c->hits[y * c->width + x]++;
            c->value[y * c->width + x] = rf_rng_uniform((uint64_t)(y * c->width + x), 3, 1, 42);
        }
    return 0;
}

static void t_tiles_cover_once(void)
{
    enum { W = 157, H = 93 };
    double *first = malloc(sizeof(double) * W * H);
    for (int threads = 1; threads <= 5; threads += 2)
        for (int tile = 1; tile <= 64; tile *= 4) {
            Ctx c = {W, calloc(W * H, 1), malloc(sizeof(double) * W * H), -1};
            RF_CHECK_EQ_INT(rf_parallel_tiles(W, H, tile, threads, fill, NULL, &c), RF_OK);
            int once = 1;
            for (int i = 0; i < W * H; i++)
                once &= c.hits[i] == 1;
            RF_CHECK(once);
            if (threads == 1 && tile == 1)
                memcpy(first, c.value, sizeof(double) * W * H);
            else
                RF_CHECK(memcmp(first, c.value, sizeof(double) * W * H) == 0);
            free(c.hits);
            free(c.value);
        }
    free(first);
}

static void t_tiles_errors(void)
{
    Ctx c = {8, calloc(64, 1), malloc(sizeof(double) * 64), 2};
    RF_CHECK_EQ_INT(rf_parallel_tiles(8, 8, 2, 2, fill, NULL, &c), RF_ERR_IO);
    RF_CHECK_EQ_INT(rf_parallel_tiles(0, 8, 2, 2, fill, NULL, &c), RF_ERR_DOMAIN);
    RF_CHECK_EQ_INT(rf_parallel_tiles(8, 8, 0, 2, fill, NULL, &c), RF_ERR_DOMAIN);
    free(c.hits);
    free(c.value);
    RF_CHECK(rf_cpu_count() >= 1);
}

static void t_rng(void)
{
    /* uniform in [0,1): mean 1/2 and variance 1/12 within 5 standard errors over 1e6 draws,
     * and different counters give different streams */
    double sum = 0, sum2 = 0;
    enum { N = 1000000 };
    for (int i = 0; i < N; i++) {
        double u = rf_rng_uniform((uint64_t)i, 0, 0, 7);
        RF_CHECK(u >= 0.0 && u < 1.0);
        sum += u;
        sum2 += u * u;
    }
    double mean = sum / N, var = sum2 / N - mean * mean;
    RF_CHECK_NEAR(mean, 0.5, 0, 5 * sqrt(1.0 / 12 / N));
    RF_CHECK_NEAR(var, 1.0 / 12, 0, 5 * sqrt(1.0 / 180 / N));
    RF_CHECK(rf_rng_uniform(1, 0, 0, 7) != rf_rng_uniform(1, 1, 0, 7));
    RF_CHECK(rf_rng_uniform(1, 0, 0, 7) != rf_rng_uniform(1, 0, 1, 7));
    RF_CHECK(rf_rng_uniform(1, 0, 0, 7) != rf_rng_uniform(1, 0, 0, 8));
    RF_CHECK(rf_rng_uniform(1, 0, 0, 7) == rf_rng_uniform(1, 0, 0, 7));
}

const RfTest rf_tests_parallel[] = {
    {"parallel_tiles_cover_once", t_tiles_cover_once},
    {"parallel_tiles_errors", t_tiles_errors},
    {"rng_counter_based", t_rng},
    RF_TEST_END,
};
