/* refray trace's events (RfRenderOptions.trace) collected in memory by the tests. */
#ifndef RF_TEST_TRACE_H
#define RF_TEST_TRACE_H

#include "refray/render.h"

#define RF_TEST_TRACE_MAX 4096

typedef struct {
    RfTraceEvent ev[RF_TEST_TRACE_MAX];
    int n;
} RfTestTraceLog;

/* An RfTraceFn: appends the event to the RfTestTraceLog ctx (its hit pointer cleared). */
void rf_test_trace_collect(void *ctx, const RfTraceEvent *e);

#endif
