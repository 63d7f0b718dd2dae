/* wc_print.c -- JSON, rows of tables, and verdicts in words. */
#include "wc_print.h"

#include "wc_explain.h" /* generated from clients/python/wrenchd.py */

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

void wc_print_json(const cJSON *value)
{
    char *text = cJSON_Print(value);
    if (text)
        puts(text);
    free(text);
}

void wc_print_rows(const char *label, const cJSON *rows, const cJSON *flags,
                   const char *flag_text)
{
    int i = 0;
    const cJSON *row;
    cJSON_ArrayForEach(row, rows)
    {
        printf("  %-11s [%+.6f, %+.6f, %+.6f]%s\n", i ? "" : label,
               cJSON_GetArrayItem(row, 0)->valuedouble, cJSON_GetArrayItem(row, 1)->valuedouble,
               cJSON_GetArrayItem(row, 2)->valuedouble,
               flags && cJSON_IsTrue(cJSON_GetArrayItem(flags, i)) ? flag_text : "");
        i++;
    }
    if (i == 0)
        printf("  %-11s none\n", label);
}

void wc_print_strings(const cJSON *list)
{
    const cJSON *item;
    cJSON_ArrayForEach(item, list) printf(" %s", item->valuestring);
    printf("\n");
}

void wc_print_friction(double low, double high)
{
    if (low == high)
        printf("friction %g at every fixel, static and kinetic (--friction)\n", low);
    else
        printf("friction [%g, %g] at every fixel, static and kinetic: robust answers, each holds "
               "for every friction in the interval\n",
               low, high);
}

/* "(fx, fy, tau)" or "(fx, fy) at (x, y)". */
void wc_describe_wrench(const cJSON *w, char *out, size_t size)
{
    const cJSON *force = cJSON_GetObjectItem(w, "force"), *at = cJSON_GetObjectItem(w, "at");
    if (cJSON_IsArray(w) && cJSON_GetArraySize(w) == 3)
        snprintf(out, size, "(%g, %g, %g)", cJSON_GetArrayItem(w, 0)->valuedouble,
                 cJSON_GetArrayItem(w, 1)->valuedouble, cJSON_GetArrayItem(w, 2)->valuedouble);
    else if (cJSON_GetArraySize(force) == 2 && cJSON_GetArraySize(at) == 2)
        snprintf(out, size, "(%g, %g) at (%g, %g)", cJSON_GetArrayItem(force, 0)->valuedouble,
                 cJSON_GetArrayItem(force, 1)->valuedouble, cJSON_GetArrayItem(at, 0)->valuedouble,
                 cJSON_GetArrayItem(at, 1)->valuedouble);
    else {
        char *text = cJSON_PrintUnformatted(w);
        snprintf(out, size, "%s", text ? text : "?");
        free(text);
    }
}

/* ---- explanations: the words are WC_EXPLAIN_*, wc_explain.h ---------------- */

/* snprintf at out + *n; *n counts what it would have written. */
static void append(char *out, size_t size, size_t *n, const char *format, ...)
    __attribute__((format(printf, 4, 5)));
static void append(char *out, size_t size, size_t *n, const char *format, ...)
{
    va_list args;
    va_start(args, format);
    int written = *n < size ? vsnprintf(out + *n, size - *n, format, args)
                            : vsnprintf(NULL, 0, format, args);
    va_end(args);
    *n += written > 0 ? (size_t)written : 0;
}

/* "fixel 1", "fixel 1 and fixel 2", "fixel 1, fixel 2 and fixel 3". */
static void fixels_named(const int *fixels, int count, char *out, size_t size)
{
    size_t n = 0;
    out[0] = 0;
    for (int i = 0; i < count && n < size; i++) {
        append(out, size, &n, "%s",
               i == 0 ? "" : i == count - 1 ? WC_EXPLAIN_LIST_AND : WC_EXPLAIN_LIST_COMMA);
        append(out, size, &n, WC_EXPLAIN_FIXEL, fixels[i] + 1);
    }
}

void wc_explain_goal(const char *blocking, const cJSON *states, char *out, size_t size)
{
    size_t n = 0;
    out[0] = 0;
    const cJSON *state;
    cJSON_ArrayForEach(state, states)
    {
        const char *s = state->valuestring;
        int separating[16], holding[16], apart[16], ns = 0, nh = 0, na = 0;
        for (int i = 0; s[i] && i < 16; i++) {
            if (s[i] == '1' && blocking[i] == 's')
                separating[ns++] = i;
            else if (s[i] == '1')
                holding[nh++] = i;
            else
                apart[na++] = i;
        }
        char a[160], b[160];
        if (n > 0)
            append(out, size, &n, "%s", WC_EXPLAIN_STATES_JOIN);
        if (ns == 0) {
            /* Nothing breaks: the self transition.  From the no-contact
             * state nothing holds either. */
            fixels_named(holding, nh, a, sizeof a);
            fixels_named(apart, na, b, sizeof b);
            append(out, size, &n, WC_EXPLAIN_STAY, s);
            if (nh > 0)
                append(out, size, &n, nh == 1 ? WC_EXPLAIN_HOLDS_ONE : WC_EXPLAIN_HOLDS_MANY, a);
            if (nh > 0 && na > 0)
                append(out, size, &n, "%s", WC_EXPLAIN_STAY_AND);
            if (na > 0)
                append(out, size, &n, na == 1 ? WC_EXPLAIN_APART_ONE : WC_EXPLAIN_APART_MANY, b);
        } else {
            fixels_named(separating, ns, a, sizeof a);
            append(out, size, &n, WC_EXPLAIN_BREAK_AWAY, s, a);
            if (nh > 0) {
                fixels_named(holding, nh, b, sizeof b);
                append(out, size, &n, nh == 1 ? WC_EXPLAIN_WHILE_ONE : WC_EXPLAIN_WHILE_MANY, b);
            }
        }
    }
}

void wc_explain_strong(const char *blocking, char *out, size_t size)
{
    size_t length = strlen(blocking);
    if (length && (blocking[length - 1] == '+' || blocking[length - 1] == '-')) {
        snprintf(out, size, WC_EXPLAIN_PIVOT,
                 blocking[length - 1] == '+' ? WC_EXPLAIN_PIVOT_PLUS : WC_EXPLAIN_PIVOT_MINUS);
        return;
    }
    size_t n = 0;
    append(out, size, &n, "%s", WC_EXPLAIN_MOVE);
    for (size_t i = 0; i < length && n < size; i++) {
        const char *motion = blocking[i] == 's'   ? WC_EXPLAIN_MOTION_S
                             : blocking[i] == 'l' ? WC_EXPLAIN_MOTION_L
                             : blocking[i] == 'r' ? WC_EXPLAIN_MOTION_R
                                                  : WC_EXPLAIN_MOTION_N;
        append(out, size, &n, "%s", i ? WC_EXPLAIN_MOVE_JOIN : "");
        append(out, size, &n, WC_EXPLAIN_MOVE_FIXEL, (int)i + 1, motion);
    }
}

/* ---- coordinates to the drawing's precision ---------------------------------- */

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
