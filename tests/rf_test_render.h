/* Helpers of the tests that load scenes and render them (rf_test_scenes.c). */
#ifndef RF_TEST_RENDER_H
#define RF_TEST_RENDER_H

#include "refray/render.h"
#include "refray/scene_io.h"

/* rf_scene_load with the default options; on failure the test fails with the reader's message
 * and 0 is returned. */
int rf_test_load_scene(const char *path, RfScene *s);

/* refray trace's events (RfRenderOptions.trace) collected in memory. */
#define RF_TEST_TRACE_MAX 4096

typedef struct {
    RfTraceEvent ev[RF_TEST_TRACE_MAX];
    int n;
} RfTestTraceLog;

/* An RfTraceFn: appends the event to the RfTestTraceLog ctx (its hit pointer cleared). */
void rf_test_trace_collect(void *ctx, const RfTraceEvent *e);

#endif
