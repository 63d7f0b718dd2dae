/* wc_fixture.c -- the store's commands: put, get, delete, list; and status. */
#include "wc_call.h"
#include "wc_commands.h"
#include "wc_print.h"

#include <stdio.h>

int wc_put_request(wc_run *run, cJSON *params)
{
    (void)params; /* the fixture is in it already */
    if (!cJSON_IsObject(run->fixture)) /* an id: no such file */
        return wc_usage_error("%s: a fixture file holds one JSON object", run->items[0]);
    return -1;
}

int wc_put_answer(wc_run *run, const cJSON *result)
{
    if (!run->o->json)
        printf("%s  stored \"%s\": %d fixels; G_goal excludes %d cones, G_strong %d%s\n",
               cJSON_GetStringValue(cJSON_GetObjectItem(result, "id")),
               cJSON_GetStringValue(cJSON_GetObjectItem(result, "name")),
               (int)cJSON_GetNumberValue(cJSON_GetObjectItem(result, "fixels")),
               (int)cJSON_GetNumberValue(cJSON_GetObjectItem(result, "goal_cones")),
               (int)cJSON_GetNumberValue(cJSON_GetObjectItem(result, "strong_cones")),
               cJSON_IsTrue(cJSON_GetObjectItem(result, "pinned")) ? ""
                                                                   : "; the fixels do not pin it");
    return EXIT_INSIDE;
}

int wc_id_request(wc_run *run, cJSON *params)
{
    cJSON_AddStringToObject(params, "id", run->items[0]);
    return -1;
}

int wc_delete_answer(wc_run *run, const cJSON *result)
{
    (void)result;
    if (!run->o->json)
        printf("deleted %s\n", run->items[0]);
    return EXIT_INSIDE;
}

int wc_list_answer(wc_run *run, const cJSON *result)
{
    if (run->o->json)
        return EXIT_INSIDE;
    cJSON *fixtures = cJSON_GetObjectItem(result, "fixtures");
    printf("%-32s  %6s  %s\n", "id", "fixels", "name");
    const cJSON *f;
    cJSON_ArrayForEach(f, fixtures)
    printf("%-32s  %6d  %s\n", cJSON_GetStringValue(cJSON_GetObjectItem(f, "id")),
           (int)cJSON_GetNumberValue(cJSON_GetObjectItem(f, "fixels")),
           cJSON_GetStringValue(cJSON_GetObjectItem(f, "name")));
    printf("(%d stored)\n", cJSON_GetArraySize(fixtures));
    return EXIT_INSIDE;
}

int wc_status_answer(wc_run *run, const cJSON *result)
{
    if (run->o->json)
        return EXIT_INSIDE;
    const cJSON *item;
    cJSON_ArrayForEach(item, result)
    {
        if (cJSON_IsString(item))
            printf("%-18s %s\n", item->string, item->valuestring);
        else
            printf("%-18s %.0f\n", item->string, item->valuedouble);
    }
    return EXIT_INSIDE;
}
