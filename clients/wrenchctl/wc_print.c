/* wc_print.c -- JSON, rows of tables, and verdicts in words. */
#include "wc_print.h"

#include "wc_explain.h" /* generated from clients/python/wrenchd.py */

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

void wc_print_units(const cJSON *fixture)
{
    const cJSON *units = cJSON_GetObjectItem(fixture, "units");
    const char *length = cJSON_GetStringValue(cJSON_GetObjectItem(units, "length"));
    const char *force = cJSON_GetStringValue(cJSON_GetObjectItem(units, "force"));
    if (length && force)
        printf("units: lengths in %s, forces in %s (the fixture's)\n", length, force);
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
