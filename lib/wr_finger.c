/* wr_finger.c -- placeholder until the finger's clearance lands: radius 0
 * only (issue 16). */
#include "wr_finger.h"

#include <math.h>

wr_status wr_finger_blocked(const wr_outline *outline, size_t loop, size_t segment, double radius,
                            const wr_stop *stop, wr_span **spans, int *count)
{
    (void)outline, (void)loop, (void)segment, (void)stop, (void)spans, (void)count;
    return radius == 0 ? WR_OK : WR_INVALID;
}
