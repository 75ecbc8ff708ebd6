/* refray: status codes returned by every library function that can fail. */
#ifndef REFRAY_STATUS_H
#define REFRAY_STATUS_H

#ifdef __cplusplus
extern "C" {
#endif

typedef enum {
    RF_OK = 0,
    RF_ERR_SINGULAR,   /* a matrix or linear system has no unique solution */
    RF_ERR_DEGENERATE, /* a zero vector, collinear points, parallel axes, ... */
    RF_ERR_DOMAIN,     /* an input outside the domain of the formula */
    RF_ERR_PARSE,      /* malformed input text */
    RF_ERR_IO,         /* a file could not be read or written */
    RF_ERR_NOMEM,      /* out of memory */
    RF_ERR_NUMERIC,    /* a computation gave NaN, Inf or a negative radiance */
    RF_ERR_INTERRUPTED /* stopped on request (a signal) before the work was done */
} RfStatus;

/* A short English description of a status, e.g. "matrix is singular". */
const char *rf_status_str(RfStatus status);

#ifdef __cplusplus
}
#endif

#endif
