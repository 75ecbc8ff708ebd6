#include "refray/status.h"

const char *rf_status_str(RfStatus status)
{
    switch (status) {
    case RF_OK: return "ok";
    case RF_ERR_SINGULAR: return "matrix is singular";
    case RF_ERR_DEGENERATE: return "degenerate input";
    case RF_ERR_DOMAIN: return "a value is outside its allowed range";
    case RF_ERR_PARSE: return "malformed input";
    case RF_ERR_IO: return "input/output error";
    case RF_ERR_NOMEM: return "out of memory";
    case RF_ERR_NUMERIC: return "a computation gave NaN, Inf or a negative value";
    case RF_ERR_INTERRUPTED: return "interrupted";
    }
    return "unknown status";
}
