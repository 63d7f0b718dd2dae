/* wc_classify.c -- classify: WRENCH arguments (and '-', JSON wrenches from
 * stdin), and the verdicts as a table with the blocking transitions in
 * words. */
#include "wc_call.h"
#include "wc_commands.h"
#include "wc_print.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* JSON wrenches from stdin, appended to `wrenches`: every value on every
 * line (white space between them), so that none is dropped; anything else
 * on a line is an error naming it, and so is a stdin without a wrench. */
static int read_wrenches(cJSON *wrenches)
{
    size_t length = 0;
    char *text = wc_read_all(stdin, &length);
    if (!text)
        return wc_usage_error("stdin: out of memory");
    int line_number = 0, read = 0;
    for (size_t start = 0; start < length;) {
        line_number++;
        const char *line = text + start;
        const char *newline = memchr(line, '\n', length - start);
        size_t line_length = newline ? (size_t)(newline - line) : length - start;
        start += line_length + 1;
        size_t at = 0;
        for (;;) {
            at += strspn(line + at, " \t\r"); /* stops at the NUL read_all ends with */
            if (at >= line_length)
                break;
            const char *end = NULL;
            cJSON *w = cJSON_ParseWithLengthOpts(line + at, line_length - at, &end, false);
            if (!w) {
                int shown = (int)(line_length - at > 24 ? 24 : line_length - at);
                int status = wc_usage_error("stdin line %d, column %zu: not a JSON wrench: '%.*s'",
                                         line_number, at + 1, shown, line + at);
                free(text);
                return status;
            }
            cJSON_AddItemToArray(wrenches, w);
            read++;
            at = (size_t)(end - line);
        }
    }
    free(text);
    if (read == 0)
        return wc_usage_error("stdin: no wrenches given (one JSON wrench or more per line)");
    return -1;
}

int wc_classify_request(wc_run *run, cJSON *params)
{
    run->wrenches = cJSON_CreateArray();
    for (int i = 1; i < run->count; i++) {
        int status = -1;
        if (strcmp(run->items[i], "-") == 0) {
            status = read_wrenches(run->wrenches);
        } else {
            cJSON *w = wc_wrench_argument(run->items[i]);
            if (!w)
                status = wc_usage_error("'%s' is not a wrench: fx,fy,tau or fx,fy@x,y",
                                        run->items[i]);
            else
                cJSON_AddItemToArray(run->wrenches, w);
        }
        if (status >= 0)
            return status;
    }
    cJSON_AddItemToObject(params, "wrenches", cJSON_Duplicate(run->wrenches, true));
    if (run->sets) {
        cJSON_AddItemToObject(params, "sets", run->sets);
        run->sets = NULL;
    }
    if (run->method)
        cJSON_AddStringToObject(params, "method", run->method);
    if (run->tolerance_given)
        cJSON_AddNumberToObject(params, "tolerance", run->tolerance);
    return -1;
}

/* The blocking transition of verdict `v` (for the set v->string) in words;
 * "" when there is none. */
static void explain(const cJSON *v, char *why, size_t size)
{
    const char *blocking = cJSON_GetStringValue(cJSON_GetObjectItem(v, "blocking"));
    const cJSON *states = cJSON_GetObjectItem(v, "states");
    why[0] = 0;
    if (blocking && strcmp(v->string, "strong") == 0)
        wc_explain_strong(blocking, why, size);
    else if (blocking && strcmp(v->string, "goal") == 0)
        wc_explain_goal(blocking, states, why, size);
    else if (blocking && cJSON_GetArraySize(states) > 0)
        wc_explain_goal(blocking, states, why, size);
    else if (blocking) /* both, blocked by a strong-set mode */
        wc_explain_strong(blocking, why, size);
}

/* A robust outside's witness: the contact points of the fixture of the
 * tolerance's set on which the wrench is outside. */
static void print_perturbation(const cJSON *points)
{
    if (!cJSON_IsArray(points))
        return;
    printf("      outside on the fixture with contacts at");
    const cJSON *p;
    cJSON_ArrayForEach(p, points)
    printf(" (%g, %g)", cJSON_GetArrayItem(p, 0)->valuedouble,
           cJSON_GetArrayItem(p, 1)->valuedouble);
    printf("\n");
}

/* A motion's witness on supports: each support's friction force on the
 * part and its normal force in the witness's distribution. */
static void print_support_witness(const cJSON *witness)
{
    const cJSON *forces = cJSON_GetObjectItem(witness, "support_forces");
    const cJSON *normals = cJSON_GetObjectItem(witness, "support_normals");
    if (!cJSON_IsArray(forces) || !cJSON_IsArray(normals))
        return;
    const cJSON *a = cJSON_GetObjectItem(witness, "acceleration");
    printf("      moves with acceleration (%g, %g, %g); the supports' friction:",
           cJSON_GetArrayItem(a, 0)->valuedouble, cJSON_GetArrayItem(a, 1)->valuedouble,
           cJSON_GetArrayItem(a, 2)->valuedouble);
    int i = 0;
    const cJSON *f;
    cJSON_ArrayForEach(f, forces)
    {
        printf(" (%g, %g) of N = %g", cJSON_GetArrayItem(f, 0)->valuedouble,
               cJSON_GetArrayItem(f, 1)->valuedouble,
               cJSON_GetArrayItem(normals, i)->valuedouble);
        i++;
    }
    printf("\n");
}

static void print_verdicts(const cJSON *wrenches, const cJSON *results)
{
    int width = 6;
    const cJSON *w, *r, *v;
    cJSON_ArrayForEach(w, wrenches)
    {
        char text[96];
        wc_describe_wrench(w, text, sizeof text);
        width = (int)strlen(text) > width ? (int)strlen(text) : width;
    }
    printf("%4s  %-*s  %-6s  %-8s  %10s  %-8s  %s\n", "#", width, "wrench", "set", "verdict",
           "margin", "blocking", "why");
    int index = 0;
    cJSON_ArrayForEach(r, results)
    {
        char wrench[96];
        wc_describe_wrench(cJSON_GetArrayItem(wrenches, index), wrench, sizeof wrench);
        bool first = true;
        cJSON_ArrayForEach(v, r)
        {
            const char *blocking = cJSON_GetStringValue(cJSON_GetObjectItem(v, "blocking"));
            const cJSON *margin = cJSON_GetObjectItem(v, "margin");
            char margin_text[32] = "-", why[1024];
            if (cJSON_IsNumber(margin))
                snprintf(margin_text, sizeof margin_text, "%+.6f", margin->valuedouble);
            explain(v, why, sizeof why);
            char number[16] = "";
            if (first)
                snprintf(number, sizeof number, "%d", index + 1);
            printf("%4s  %-*s  %-6s  %-8s  %10s  %-8s  %s\n", number, width,
                   first ? wrench : "", v->string,
                   cJSON_GetStringValue(cJSON_GetObjectItem(v, "verdict")), margin_text,
                   blocking ? blocking : "", why);
            print_perturbation(cJSON_GetObjectItem(v, "perturbation"));
            const char *verdict = cJSON_GetStringValue(cJSON_GetObjectItem(v, "verdict"));
            if (verdict && strcmp(verdict, "outside") == 0) /* a motion found */
                print_support_witness(cJSON_GetObjectItem(v, "witness"));
            first = false;
        }
        index++;
    }
}

int wc_classify_answer(wc_run *run, const cJSON *result)
{
    const cJSON *results = cJSON_GetObjectItem(result, "results");
    bool all_inside = true;
    const cJSON *r, *v;
    cJSON_ArrayForEach(r, results)
    cJSON_ArrayForEach(v, r) all_inside &= cJSON_IsTrue(cJSON_GetObjectItem(v, "inside"));
    if (!run->o->json && run->friction_interval_given)
        wc_print_friction(run->friction_low, run->friction_high);
    if (!run->o->json && run->geometric_given)
        printf("robust over the fixture's tolerance: contacts within %g along the outline, "
               "normals within %g degrees\n",
               run->geometric[0], run->geometric[1]);
    if (!run->o->json)
        print_verdicts(run->wrenches, results);
    return all_inside ? EXIT_INSIDE : EXIT_NOT_INSIDE;
}
