/* wc_analysis.c -- what a fixture's analysis holds: cone (the explicit
 * cone of a constraint string), plan (contact states, excluded
 * transitions, G_goal's cones) and modes (the feasible moving modes). */
#include "wc_commands.h"
#include "wc_print.h"

#include <stdio.h>

int wc_cone_request(wc_run *run, cJSON *params)
{
    cJSON_AddStringToObject(params, "constraints", run->items[1]);
    return -1;
}

int wc_cone_answer(wc_run *run, const cJSON *result)
{
    if (run->o->json)
        return EXIT_INSIDE;
    const char *constraints = cJSON_GetStringValue(cJSON_GetObjectItem(result, "constraints"));
    if (cJSON_IsTrue(cJSON_GetObjectItem(result, "empty"))) {
        printf("G_%s is empty: no wrench satisfies %s\n", constraints, constraints);
        return EXIT_INSIDE;
    }
    cJSON *halfspaces = cJSON_GetObjectItem(result, "halfspaces");
    int dimension = (int)cJSON_GetNumberValue(cJSON_GetObjectItem(result, "dimension"));
    printf("G_%s: dimension %d, %d half-space%s (F g <= 0, physical units)%s\n", constraints,
           dimension, cJSON_GetArraySize(halfspaces),
           cJSON_GetArraySize(halfspaces) == 1 ? "" : "s",
           dimension == 3 && cJSON_GetArraySize(halfspaces) == 0 ? ": every wrench" : "");
    wc_print_rows("half-spaces", halfspaces, cJSON_GetObjectItem(result, "strict"), "  open");
    wc_print_rows("equalities", cJSON_GetObjectItem(result, "equalities"), NULL, "");
    wc_print_rows("generators", cJSON_GetObjectItem(result, "generators"), NULL, "");
    return EXIT_INSIDE;
}

int wc_plan_answer(wc_run *run, const cJSON *result)
{
    if (run->o->json)
        return EXIT_INSIDE;
    printf("%-10s  %s\n", "state", "excluded transitions");
    const cJSON *state;
    cJSON_ArrayForEach(state, cJSON_GetObjectItem(result, "states"))
    {
        printf("%-10s ", cJSON_GetStringValue(cJSON_GetObjectItem(state, "state")));
        wc_print_strings(cJSON_GetObjectItem(state, "excluded"));
    }
    cJSON *cones = cJSON_GetObjectItem(result, "cones");
    printf("G_goal excludes %d cones:", cJSON_GetArraySize(cones));
    wc_print_strings(cones);
    return EXIT_INSIDE;
}

int wc_modes_answer(wc_run *run, const cJSON *result)
{
    if (run->o->json)
        return EXIT_INSIDE;
    cJSON *feasible = cJSON_GetObjectItem(result, "feasible");
    printf("%d feasible moving modes:", cJSON_GetArraySize(feasible));
    wc_print_strings(feasible);
    printf("%s\n", cJSON_IsTrue(cJSON_GetObjectItem(result, "pinned"))
                       ? "pinned: rolling at every fixel holds the part still"
                       : "not pinned: the part can pivot about its contact point");
    return EXIT_INSIDE;
}
