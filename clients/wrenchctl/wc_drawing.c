/* wc_drawing.c -- coordinates to the drawing's precision (wc_print.h). */
#include "wc_print.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>


/* The decimals of v's shortest exact form, WC_MAX_DECIMALS at most. */
static int decimals_of(double v)
{
    for (int p = 0; p < WC_MAX_DECIMALS; p++) {
        char text[64];
        snprintf(text, sizeof text, "%.*f", p, v);
        if (strtod(text, NULL) == v)
            return p;
    }
    return WC_MAX_DECIMALS;
}

/* A number of the drawing into its decimals and, along axis k (-1: none),
 * its box. */
static void take(double x, int k, int *decimals, double lo[2], double hi[2])
{
    int d = decimals_of(x);
    *decimals = *decimals > d ? *decimals : d;
    if (k >= 0) {
        lo[k] = fmin(lo[k], x);
        hi[k] = fmax(hi[k], x);
    }
}

/* Every coordinate of the shape (a vertex's x and y, not its bulge; a
 * circle's centre and radius) into decimals and the box. */
static void shape_numbers(const cJSON *shape, int *decimals, double lo[2], double hi[2])
{
    const cJSON *c = cJSON_GetObjectItem(shape, "center");
    const cJSON *r = cJSON_GetObjectItem(shape, "radius");
    if (cJSON_GetArraySize(c) == 2 && cJSON_IsNumber(r)) {
        for (int k = 0; k < 2; k++) {
            double x = cJSON_GetArrayItem(c, k)->valuedouble;
            take(x - r->valuedouble, k, decimals, lo, hi);
            take(x + r->valuedouble, k, decimals, lo, hi);
            take(x, -1, decimals, lo, hi);
        }
        take(r->valuedouble, -1, decimals, lo, hi);
        return;
    }
    const cJSON *v, *loop;
    cJSON_ArrayForEach(v, cJSON_GetObjectItem(shape, "vertices"))
    for (int k = 0; k < 2 && cJSON_GetArraySize(v) >= 2; k++)
        take(cJSON_GetArrayItem(v, k)->valuedouble, k, decimals, lo, hi);
    cJSON_ArrayForEach(loop, cJSON_GetObjectItem(shape, "loops"))
    cJSON_ArrayForEach(v, loop) for (int k = 0; k < 2 && cJSON_GetArraySize(v) >= 2; k++)
        take(cJSON_GetArrayItem(v, k)->valuedouble, k, decimals, lo, hi);
}

int wc_drawing_decimals(const cJSON *shape)
{
    if (!cJSON_IsObject(shape))
        return -1;
    int decimals = 0;
    double lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY};
    shape_numbers(shape, &decimals, lo, hi);
    double size = hypot(hi[0] - lo[0], hi[1] - lo[1]);
    if (!(size > 0) || !isfinite(size))
        return -1;
    int floor_decimals = (int)ceil(-log10(1e-4 * size));
    if (floor_decimals > decimals)
        decimals = floor_decimals;
    return decimals < 0 ? 0 : decimals > WC_MAX_DECIMALS ? WC_MAX_DECIMALS : decimals;
}

void wc_point_text(const cJSON *point, int decimals, char *out, size_t size)
{
    double x = cJSON_GetNumberValue(cJSON_GetArrayItem(point, 0)) + 0.0;
    double y = cJSON_GetNumberValue(cJSON_GetArrayItem(point, 1)) + 0.0;
    if (decimals < 0)
        snprintf(out, size, "(%.6g, %.6g)", x, y);
    else
        snprintf(out, size, "(%.*f, %.*f)", decimals, x, decimals, y);
}
