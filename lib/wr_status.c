/* wr_status.c -- the phrases of wr_status, and the filling of a wr_error. */
#include "wr_status.h"
#include "wr_internal.h"

#include <stdarg.h>
#include <stdio.h>

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

void wr_error_set(wr_error *error, const char *field, const char *format, ...)
{
    if (!error)
        return;
    snprintf(error->field, sizeof error->field, "%s", field ? field : "");
    va_list args;
    va_start(args, format);
    vsnprintf(error->reason, sizeof error->reason, format, args);
    va_end(args);
}
