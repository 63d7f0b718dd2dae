/* wc_reach.c -- where the finger may push: --push-on, or the clients'
 * default (docs/PROTOCOL.md, push_on): the outer boundary and every hole
 * wider than the finger; a point finger, whose size is not known, the
 * outer boundary only. */
#include "wc_call.h"
#include "wc_commands.h"

#include "wp_fixture.h"

#include <stdlib.h>
#include <string.h>

int wc_take_push_on(wc_run *run, const char *value)
{
    if (strcmp(value, "outer") == 0 || strcmp(value, "all") == 0) {
        run->push_on = cJSON_CreateString(value);
        return 0;
    }
    cJSON *list = cJSON_CreateArray();
    const char *p = value;
    while (*p) {
        char *end;
        long loop = strtol(p, &end, 10);
        if (end == p || loop < 0 || (*end && *end != ',')) {
            cJSON_Delete(list);
            return wc_usage_error("--push-on wants outer, all or loop numbers (0,2,5), not '%s'",
                                  value);
        }
        cJSON_AddItemToArray(list, cJSON_CreateNumber((double)loop));
        p = *end ? end + 1 : end;
    }
    if (cJSON_GetArraySize(list) == 0) {
        cJSON_Delete(list);
        return wc_usage_error("--push-on wants outer, all or loop numbers (0,2,5), not '%s'",
                              value);
    }
    run->push_on = list;
    return 0;
}

/* The default for `body` (a body's JSON): NULL when every loop is taken
 * anyway (no holes, or a body this cannot read: the daemon then says what
 * is wrong with it), else "outer" or [0, the wider holes...]. */
static cJSON *default_push_on(const cJSON *body, double finger_radius)
{
    cJSON *params = cJSON_CreateObject();
    cJSON_AddItemToObject(params, "body", cJSON_Duplicate(body, true));
    wr_fixture *fixture = NULL;
    wp_error error;
    bool read = wp_body_read(params, "params", &fixture, &error);
    cJSON_Delete(params);
    if (!read)
        return NULL;
    const wr_outline *o = fixture->shape == WR_SHAPE_OUTLINE ? fixture->outline : NULL;
    cJSON *result = NULL;
    if (o && o->loop_count > 1) {
        result = cJSON_CreateArray();
        cJSON_AddItemToArray(result, cJSON_CreateNumber(0));
        for (size_t l = 1; finger_radius > 0 && l < o->loop_count; l++)
            if (wr_outline_loop_width(o, l) > 2 * finger_radius)
                cJSON_AddItemToArray(result, cJSON_CreateNumber((double)l));
        if (cJSON_GetArraySize(result) == 1) {
            cJSON_Delete(result);
            result = cJSON_CreateString("outer");
        }
    }
    wr_fixture_free(fixture);
    return result;
}

int wc_push_on(wc_run *run, const cJSON *body, cJSON *params)
{
    if (run->push_on) {
        cJSON_AddItemToObject(params, "push_on", cJSON_Duplicate(run->push_on, true));
        return -1;
    }
    cJSON *stored = NULL;
    if (cJSON_IsString(body)) {
        /* A stored fixture: its body, from the daemon. */
        int status;
        cJSON *get = cJSON_CreateObject();
        cJSON_AddStringToObject(get, "id", body->valuestring);
        stored = wc_call(run->o, "fixture.get", get, &status);
        if (!stored)
            return status;
        body = cJSON_GetObjectItem(stored, "body");
    }
    cJSON *chosen = body ? default_push_on(body, run->radius_given ? run->finger_radius : 0)
                         : NULL;
    cJSON_Delete(stored);
    if (chosen)
        cJSON_AddItemToObject(params, "push_on", chosen);
    return -1;
}
