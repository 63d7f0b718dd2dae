/* wc_design.c -- wrenchctl design: fixture.design's request from a body
 * file and options, a progress bar on a terminal, the ranked table. */
#include "wc_call.h"
#include "wc_commands.h"
#include "wc_print.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

/* design.progress on stderr, redrawn in place: a bar, the count, the best
 * score so far. */
static void progress_bar(const char *line, void *context)
{
    (void)context;
    cJSON *json = cJSON_Parse(line);
    const cJSON *params = cJSON_GetObjectItem(json, "params");
    double done = cJSON_GetNumberValue(cJSON_GetObjectItem(params, "done"));
    double total = cJSON_GetNumberValue(cJSON_GetObjectItem(params, "total"));
    const cJSON *best = cJSON_GetObjectItem(params, "best");
    if (json && total > 0 && done >= 0) {
        enum { WIDTH = 30 };
        int filled = (int)(WIDTH * done / total);
        char bar[WIDTH + 1];
        for (int i = 0; i < WIDTH; i++)
            bar[i] = i < filled ? '#' : '.';
        bar[WIDTH] = 0;
        fprintf(stderr, "\r[%s] %3.0f%% %.0f/%.0f candidates", bar, 100 * done / total, done,
                total);
        if (cJSON_IsNumber(best))
            fprintf(stderr, ", best %.6g", best->valuedouble);
        fputs(done >= total ? "\n" : "  ", stderr);
        fflush(stderr);
    }
    cJSON_Delete(json);
}

int wc_design_request(wc_run *run, cJSON *params)
{
    FILE *file = fopen(run->items[0], "r");
    if (!file)
        return wc_usage_error("design: cannot open '%s'", run->items[0]);
    char *text = wc_read_all(file, NULL);
    fclose(file);
    cJSON *json = text ? cJSON_Parse(text) : NULL;
    free(text);
    if (!cJSON_IsObject(json)) {
        cJSON_Delete(json);
        return wc_usage_error("design: '%s' is not a JSON object (a fixture or a body)",
                              run->items[0]);
    }
    cJSON *body = cJSON_GetObjectItem(json, "body");
    cJSON_AddItemToObject(params, "body", cJSON_Duplicate(body ? body : json, true));
    if (run->friction_interval_given) {
        if (run->friction_low == run->friction_high)
            cJSON_AddNumberToObject(params, "friction", run->friction_low);
        else
            cJSON_AddItemToObject(params, "friction",
                                  cJSON_CreateDoubleArray((double[2]){run->friction_low,
                                                                      run->friction_high},
                                                          2));
    } else if (body && cJSON_GetObjectItem(json, "friction")) {
        cJSON_AddItemToObject(params, "friction",
                              cJSON_Duplicate(cJSON_GetObjectItem(json, "friction"), true));
    } else {
        cJSON_Delete(json);
        return wc_usage_error("design: no friction: give --friction or a fixture with one");
    }
    if (run->spacing > 0) {
        cJSON_AddNumberToObject(params, "spacing", run->spacing);
    } else if (body && cJSON_IsArray(cJSON_GetObjectItem(json, "fixels"))) {
        /* The fixture's fixels are the candidate sites. */
        cJSON *sites = cJSON_AddArrayToObject(params, "sites");
        const cJSON *fixel;
        cJSON_ArrayForEach(fixel, cJSON_GetObjectItem(json, "fixels"))
        {
            cJSON *site = cJSON_CreateObject();
            const cJSON *at = cJSON_GetObjectItem(fixel, "at");
            const cJSON *normal = cJSON_GetObjectItem(fixel, "normal");
            if (at)
                cJSON_AddItemToObject(site, "at", cJSON_Duplicate(at, true));
            if (normal)
                cJSON_AddItemToObject(site, "normal", cJSON_Duplicate(normal, true));
            cJSON_AddItemToArray(sites, site);
        }
    } else {
        cJSON_Delete(json);
        return wc_usage_error("design: no candidate sites: give --spacing H, or a fixture whose "
                              "fixels are the sites");
    }
    cJSON_Delete(json);
    if (run->fixels)
        cJSON_AddNumberToObject(params, "fixels", run->fixels);
    if (run->top)
        cJSON_AddNumberToObject(params, "top", run->top);
    if (run->objective)
        cJSON_AddStringToObject(params, "objective", run->objective);
    if (run->radius_given)
        cJSON_AddNumberToObject(params, "finger_radius", run->finger_radius);
    if (run->friction_given)
        cJSON_AddNumberToObject(params, "finger_friction", run->finger_friction);
    if (run->shard_given)
        cJSON_AddItemToObject(params, "shard", cJSON_CreateIntArray(run->shard, 2));
    if (!run->o->local && isatty(STDERR_FILENO)) {
        cJSON_AddBoolToObject(params, "progress", true);
        run->o->notify = progress_bar;
    }
    return -1;
}

static double number(const cJSON *object, const char *key)
{
    return cJSON_GetNumberValue(cJSON_GetObjectItem(object, key));
}

int wc_design_answer(wc_run *run, const cJSON *result)
{
    const cJSON *designs = cJSON_GetObjectItem(result, "designs");
    const cJSON *counts = cJSON_GetObjectItem(result, "counts");
    bool any_push = false;
    const cJSON *d;
    cJSON_ArrayForEach(d, designs)
    {
        any_push = any_push || cJSON_IsObject(cJSON_GetObjectItem(d, "best_push"));
    }
    if (run->o->json)
        return any_push ? EXIT_INSIDE : EXIT_NOT_INSIDE;
    const char *objective = cJSON_GetStringValue(cJSON_GetObjectItem(result, "objective"));
    printf("design: %.0f fixels from %.0f sites, %.0f candidates", run->fixels ? run->fixels : 3.0,
           number(result, "sites"), number(counts, "candidates"));
    const cJSON *shard = cJSON_GetObjectItem(result, "shard");
    if (cJSON_GetArraySize(shard) == 2 && cJSON_GetArrayItem(shard, 1)->valuedouble > 1)
        printf(" (shard %.0f of %.0f: %.0f of them)", cJSON_GetArrayItem(shard, 0)->valuedouble,
               cJSON_GetArrayItem(shard, 1)->valuedouble, number(counts, "examined"));
    printf("; %.0f without a seating push, %.0f unpinned, %.0f degenerate; ranked by %s\n",
           number(counts, "no_seating_push"), number(counts, "unpinned"),
           number(counts, "degenerate"), objective ? objective : "margin");
    printf("%-4s  %-10s  %-34s  %-30s  %-9s  %-9s  %-7s  %s\n", "rank", "score", "fixels at",
           "best push at -> direction", "goal len", "both len", "gravity", "critical mu");
    cJSON_ArrayForEach(d, designs)
    {
        char fixels[256] = "", push[128] = "none", cell[64];
        const cJSON *f;
        cJSON_ArrayForEach(f, cJSON_GetObjectItem(d, "fixels"))
        {
            const cJSON *at = cJSON_GetObjectItem(f, "at");
            snprintf(cell, sizeof cell, "%s(%.4g, %.4g)", fixels[0] ? " " : "",
                     cJSON_GetArrayItem(at, 0)->valuedouble, cJSON_GetArrayItem(at, 1)->valuedouble);
            strncat(fixels, cell, sizeof fixels - strlen(fixels) - 1);
        }
        const cJSON *best = cJSON_GetObjectItem(d, "best_push");
        if (cJSON_IsObject(best)) {
            const cJSON *at = cJSON_GetObjectItem(best, "at");
            const cJSON *direction = cJSON_GetObjectItem(best, "direction");
            snprintf(push, sizeof push, "(%.4g, %.4g) -> (%.3g, %.3g)",
                     cJSON_GetArrayItem(at, 0)->valuedouble, cJSON_GetArrayItem(at, 1)->valuedouble,
                     cJSON_GetArrayItem(direction, 0)->valuedouble + 0.0,
                     cJSON_GetArrayItem(direction, 1)->valuedouble + 0.0);
        }
        const cJSON *critical = cJSON_GetObjectItem(d, "critical_mu");
        char critical_text[32] = "none below 2";
        if (cJSON_IsNumber(critical))
            snprintf(critical_text, sizeof critical_text, "%.6g", critical->valuedouble);
        printf("%-4.0f  %-10.6g  %-34s  %-30s  %-9.4g  %-9.4g  %-7.3g  %s\n", number(d, "rank"),
               number(d, "score"), fixels, push, number(d, "goal_length"),
               number(d, "both_length"), number(d, "gravity_goal_deg"), critical_text);
    }
    if (cJSON_GetArraySize(designs) == 0)
        printf("no design: no candidate has a push that seats the part\n");
    else
        printf("Push at the best push and let go: it is in the both region (goal seats the part,\n"
               "strong then holds it); a goal push alone may leave it sliding along its fixels.\n");
    return any_push ? EXIT_INSIDE : EXIT_NOT_INSIDE;
}
