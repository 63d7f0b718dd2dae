/* store.c -- the fixture store and the server's state: fixture.put,
 * fixture.get, fixture.delete, fixture.list, server.status. */
#include "common.h"
#include "methods.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* params.id: a well-formed fixture id. */
static const char *read_id(const cJSON *params, wp_error *error)
{
    const char *id;
    if (!wp_member_string(params, "params", "id", true, &id, error))
        return NULL;
    if (!wp_fixture_id_valid(id)) {
        wp_error_set(error, WP_INVALID_PARAMS, "params.id",
                     "not a fixture id: 32 hexadecimal digits, as fixture.put returns");
        return NULL;
    }
    return id;
}

cJSON *wp_handle_fixture_put(wp_call *call)
{
    const wp_host *host = call->host;
    const cJSON *params = call->params;
    wp_error *error = call->error;
    wp_fixture_doc doc;
    if (!wp_fixture_read(cJSON_GetObjectItemCaseSensitive(params, "fixture"), "params.fixture",
                         &doc, error))
        return NULL;
    wp_fixture_use use;
    wp_host_failure failure;
    if (!host->fixture_adopt(host->self, &doc, true, &use, &failure)) {
        wp_error_host(error, &failure, "");
        return NULL;
    }
    cJSON *result = cJSON_CreateObject();
    if (result) {
        cJSON_AddStringToObject(result, "id", use.id);
        cJSON_AddStringToObject(result, "name", use.name);
        cJSON_AddNumberToObject(result, "fixels", use.fixture->fixel_count);
        cJSON_AddNumberToObject(result, "goal_cones",
                                wr_analysis_cone_count(use.analysis, WR_SET_GOAL));
        cJSON_AddNumberToObject(result, "strong_cones",
                                wr_analysis_cone_count(use.analysis, WR_SET_STRONG));
        cJSON_AddBoolToObject(result, "pinned", wr_analysis_pinned(use.analysis));
        /* The mass properties in use, given or derived from the shape, for
         * a client to check against its own CAD. */
        const wr_fixture *f = use.fixture;
        if (f->shape != WR_SHAPE_NONE)
            cJSON_AddNumberToObject(result, "area", f->area);
        cJSON_AddItemToObject(result, "com", cJSON_CreateDoubleArray(f->com, 2));
        cJSON_AddNumberToObject(result, "inertia", f->inertia);
    }
    host->fixture_release(host->self, &use);
    return result ? result : wp_out_of_memory(NULL, error);
}

cJSON *wp_handle_fixture_get(wp_call *call)
{
    const wp_host *host = call->host;
    const cJSON *params = call->params;
    wp_error *error = call->error;
    const char *id = read_id(params, error);
    wp_fixture_use use;
    wp_host_failure failure;
    if (!id)
        return NULL;
    if (!host->fixture_use(host->self, id, &use, &failure)) {
        wp_error_host(error, &failure, "params.id");
        return NULL;
    }
    cJSON *result = cJSON_CreateRaw(use.canonical);
    host->fixture_release(host->self, &use);
    return result ? result : wp_out_of_memory(NULL, error);
}

cJSON *wp_handle_fixture_delete(wp_call *call)
{
    const wp_host *host = call->host;
    const cJSON *params = call->params;
    wp_error *error = call->error;
    const char *id = read_id(params, error);
    wp_host_failure failure;
    if (!id)
        return NULL;
    if (!host->fixture_delete(host->self, id, &failure)) {
        wp_error_host(error, &failure, "params.id");
        return NULL;
    }
    cJSON *result = cJSON_CreateObject();
    if (!result || !cJSON_AddTrueToObject(result, "deleted"))
        return wp_out_of_memory(result, error);
    return result;
}

/* A page of fixture.list: at most this many fixtures (the default), each
 * name at most WP_NAME_MAX bytes, so that a page is about a megabyte. */
#define LIST_PAGE 1000

/* The stored fixtures, sorted by id, a page at a time: those after
 * params.after (an id; none: from the first), at most params.limit;
 * "more" says whether any follow the page's last. */
cJSON *wp_handle_fixture_list(wp_call *call)
{
    const char *after = NULL;
    double limit = LIST_PAGE;
    bool given = false;
    if (!wp_member_string(call->params, "params", "after", false, &after, call->error) ||
        !wp_member_number(call->params, "params", "limit", false, &limit, &given, call->error))
        return NULL;
    if (after && !wp_fixture_id_valid(after)) {
        wp_error_set(call->error, WP_INVALID_PARAMS, "params.after",
                     "not a fixture id (32 hexadecimal digits)");
        return NULL;
    }
    if (given && !(limit >= 1 && limit <= LIST_PAGE && limit == floor(limit))) {
        wp_error_set(call->error, WP_INVALID_PARAMS, "params.limit",
                     "must be a whole number from 1 to %d", LIST_PAGE);
        return NULL;
    }
    wp_fixture_listing listing = {0, NULL};
    wp_host_failure failure;
    if (!call->host->fixture_list(call->host->self, &listing, &failure)) {
        wp_error_host(call->error, &failure, "");
        return NULL;
    }
    cJSON *result = cJSON_CreateObject();
    cJSON *list = cJSON_AddArrayToObject(result, "fixtures");
    bool ok = list != NULL;
    size_t first = 0;
    while (after && first < listing.count && strcmp(listing.entries[first].id, after) <= 0)
        first++;
    size_t end = first + (size_t)limit < listing.count ? first + (size_t)limit : listing.count;
    for (size_t i = first; ok && i < end; i++) {
        const wp_fixture_entry *e = &listing.entries[i];
        cJSON *item = cJSON_CreateObject();
        ok = item && cJSON_AddStringToObject(item, "id", e->id) &&
             cJSON_AddStringToObject(item, "name", e->name) &&
             cJSON_AddNumberToObject(item, "fixels", e->fixels);
        if (item)
            cJSON_AddItemToArray(list, item);
    }
    ok = ok && cJSON_AddBoolToObject(result, "more", end < listing.count);
    wp_fixture_listing_release(&listing);
    return ok ? result : wp_out_of_memory(result, call->error);
}

cJSON *wp_handle_server_status(wp_call *call)
{
    wp_server_state state;
    wp_host_failure failure;
    if (!call->host->state(call->host->self, &state, &failure)) {
        wp_error_host(call->error, &failure, "");
        return NULL;
    }
    cJSON *result = cJSON_CreateObject();
    if (!result)
        return wp_out_of_memory(NULL, call->error);
    cJSON_AddStringToObject(result, "version", WR_VERSION);
    cJSON_AddNumberToObject(result, "uptime_s", state.uptime_s);
    cJSON_AddNumberToObject(result, "fixtures", (double)state.fixtures);
    cJSON_AddNumberToObject(result, "cached", (double)state.cached);
    cJSON_AddNumberToObject(result, "cache_bytes", (double)state.cache_bytes);
    cJSON_AddNumberToObject(result, "cache_limit_bytes", (double)state.cache_limit_bytes);
    cJSON_AddNumberToObject(result, "threads", state.threads);
    cJSON_AddNumberToObject(result, "clients", (double)state.clients);
    cJSON_AddNumberToObject(result, "refused", (double)state.refused);
    cJSON_AddNumberToObject(result, "denied", (double)state.denied);
    cJSON_AddNumberToObject(result, "requests", (double)state.requests);
    if (!cJSON_AddNumberToObject(result, "errors", (double)state.errors))
        return wp_out_of_memory(result, call->error);
    return result;
}
