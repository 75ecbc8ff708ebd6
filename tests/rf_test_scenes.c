/* Helpers of the tests that go through every shipped scene, load scenes or collect refray
 * trace's events (rf_test.h, rf_test_render.h). */
#include "rf_test.h"
#include "rf_test_render.h"

int rf_test_load_scene(const char *path, RfScene *s)
{
    char err[512];
    if (rf_scene_load(path, NULL, s, err, sizeof err) == RF_OK)
        return 1;
    rf_test_fail(__FILE__, __LINE__, "%s", err);
    return 0;
}

void rf_test_shipped_scenes(glob_t *g, int with_obj)
{
    const char *pats[] = {"scenes/*.rf", "scenes/*.obj", "scenes/spd/*.nff", "scenes/spd/*.nff.gz"};
    int flags = 0;
    for (size_t i = 0; i < sizeof pats / sizeof pats[0]; i++) {
        if (i == 1 && !with_obj)
            continue;
        glob(pats[i], flags, NULL, g);
        flags = GLOB_APPEND;
    }
}

void rf_test_trace_collect(void *ctx, const RfTraceEvent *e)
{
    RfTestTraceLog *l = ctx;
    if (l->n < RF_TEST_TRACE_MAX) {
        l->ev[l->n] = *e;
        l->ev[l->n].hit = NULL; /* valid only during the call */
        l->n++;
    }
}
