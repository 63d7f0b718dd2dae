/* wr_status.c -- the phrases of wr_status. */
#include "wr_status.h"

const char *wr_strerror(wr_status status)
{
    switch (status) {
    case WR_OK:
        return "ok";
    case WR_INVALID:
        return "invalid argument";
    case WR_NO_MEMORY:
        return "out of memory";
    case WR_LP_FAILED:
        return "the LP solver failed";
    case WR_STOPPED:
        return "stopped by the caller";
    case WR_NO_SHAPE:
        return "the fixture has no shape";
    }
    return "unknown status";
}
