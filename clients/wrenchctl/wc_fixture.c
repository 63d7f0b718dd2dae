/* wc_fixture.c -- the store's commands: put, get, delete, list; and status. */
#include "wc_call.h"
#include "wc_commands.h"
#include "wc_print.h"

#include <stdbool.h>
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

/* fixture.list answers a page at a time: every page is asked (each after
 * the last id of the one before) and the whole list printed as one. */
int wc_list_request(wc_run *run, cJSON *params)
{
    (void)params; /* each page has its own */
    cJSON *all = cJSON_CreateObject();
    cJSON *fixtures = all ? cJSON_AddArrayToObject(all, "fixtures") : NULL;
    if (!fixtures) {
        cJSON_Delete(all);
        fputs("wrenchctl: out of memory\n", stderr);
        return EXIT_SERVER;
    }
    char after[64] = "";
    int status = EXIT_INSIDE;
    for (;;) {
        cJSON *page_params = cJSON_CreateObject();
        if (page_params && after[0])
            cJSON_AddStringToObject(page_params, "after", after);
        cJSON *page = wc_call(run->o, "fixture.list", page_params, &status);
        if (!page) {
            cJSON_Delete(all);
            return status;
        }
        cJSON *items = cJSON_DetachItemFromObject(page, "fixtures");
        bool more = cJSON_IsTrue(cJSON_GetObjectItem(page, "more"));
        cJSON_Delete(page);
        cJSON *item = items ? items->child : NULL;
        const char *last = NULL;
        while (item) {
            cJSON *next = item->next;
            cJSON_AddItemToArray(fixtures, cJSON_DetachItemViaPointer(items, item));
            last = cJSON_GetStringValue(cJSON_GetObjectItem(item, "id"));
            item = next;
        }
        if (last)
            snprintf(after, sizeof after, "%s", last);
        cJSON_Delete(items);
        if (!more || !last)
            break;
    }
    if (run->o->json)
        wc_print_json(all);
    status = wc_list_answer(run, all);
    cJSON_Delete(all);
    return status;
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
