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

/* A number of the drawing into the count of numbers by decimals and,
 * along axis k (-1: none), its box. */
static void take(double x, int k, int *decimals, double lo[2], double hi[2])
{
    decimals[decimals_of(x)]++;
    if (k >= 0) {
        lo[k] = fmin(lo[k], x);
        hi[k] = fmax(hi[k], x);
    }
}

/* Every coordinate of the shape (a vertex's x and y, not its bulge; a
 * circle's centre and radius) into decimals and the box. */
static void shape_numbers(const cJSON *shape, int decimals[], double lo[2], double hi[2])
{
    const cJSON *c = cJSON_GetObjectItem(shape, "center");
    const cJSON *r = cJSON_GetObjectItem(shape, "radius");
    if (cJSON_GetArraySize(c) == 2 && cJSON_IsNumber(r)) {
        for (int k = 0; k < 2; k++) {
            double x = cJSON_GetArrayItem(c, k)->valuedouble;
            take(x, -1, decimals, lo, hi);
            lo[k] = fmin(lo[k], x - r->valuedouble);
            hi[k] = fmax(hi[k], x + r->valuedouble);
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
    int counts[WC_MAX_DECIMALS + 1] = {0};
    double lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY};
    shape_numbers(shape, counts, lo, hi);
    /* The median: a drawing's own numbers, not the many digits of curves
     * a reader approximated with arcs. */
    int total = 0, seen = 0, decimals = 0;
    for (int d = 0; d <= WC_MAX_DECIMALS; d++)
        total += counts[d];
    while (decimals < WC_MAX_DECIMALS && (seen += counts[decimals]) <= total / 2)
        decimals++;
    double size = hypot(hi[0] - lo[0], hi[1] - lo[1]);
    if (!(size > 0) || !isfinite(size))
        return -1;
    int floor_decimals = (int)ceil(-log10(1e-4 * size));
    if (floor_decimals > decimals)
        decimals = floor_decimals;
    return decimals < 0 ? 0 : decimals > WC_MAX_DECIMALS ? WC_MAX_DECIMALS : decimals;
}

/* v rounded to `decimals` places, its trailing zeros (and point) dropped,
 * "-0" as "0". */
static void number_text(double v, int decimals, char *out, size_t size)
{
    snprintf(out, size, "%.*f", decimals, v);
    if (strchr(out, '.')) {
        size_t n = strlen(out);
        while (n > 0 && out[n - 1] == '0')
            out[--n] = 0;
        if (n > 0 && out[n - 1] == '.')
            out[--n] = 0;
    }
    if (strcmp(out, "-0") == 0)
        snprintf(out, size, "0");
}

void wc_point_text(const cJSON *point, int decimals, char *out, size_t size)
{
    double x = cJSON_GetNumberValue(cJSON_GetArrayItem(point, 0)) + 0.0;
    double y = cJSON_GetNumberValue(cJSON_GetArrayItem(point, 1)) + 0.0;
    if (decimals < 0) {
        snprintf(out, size, "(%.6g, %.6g)", x, y);
        return;
    }
    char a[64], b[64];
    number_text(x, decimals, a, sizeof a);
    number_text(y, decimals, b, sizeof b);
    snprintf(out, size, "(%s, %s)", a, b);
}
