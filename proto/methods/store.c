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
        return false;
    if (!wp_fixture_id_valid(id)) {
        wp_error_set(error, WP_INVALID_PARAMS, "params.id",
                     "not a fixture id: 32 hexadecimal digits, as fixture.put returns");
        return false;
    }
    return id;
}

bool wp_handle_fixture_put(wp_call *call, wp_writer *out)
{
    const wp_host *host = call->host;
    const cJSON *params = call->params;
    wp_error *error = call->error;
    wp_fixture_doc doc;
    if (!wp_fixture_read(cJSON_GetObjectItemCaseSensitive(params, "fixture"), "params.fixture",
                         &doc, error))
        return false;
    wp_fixture_use use;
    wp_host_failure failure;
    if (!host->fixture_adopt(host->self, &doc, true, &use, &failure)) {
        wp_error_host(error, &failure, "");
        return false;
    }
    wp_write_object(out);
    wp_write_member_string(out, "id", use.id);
    wp_write_member_string(out, "name", use.name);
    wp_write_member_number(out, "fixels", use.fixture->fixel_count);
    wp_write_member_number(out, "goal_cones", wr_analysis_cone_count(use.analysis, WR_SET_GOAL));
    wp_write_member_number(out, "strong_cones",
                           wr_analysis_cone_count(use.analysis, WR_SET_STRONG));
    wp_write_member_bool(out, "pinned", wr_analysis_pinned(use.analysis));
    /* The mass properties in use, given or derived from the shape, for a
     * client to check against its own CAD. */
    const wr_fixture *f = use.fixture;
    if (f->shape != WR_SHAPE_NONE)
        wp_write_member_number(out, "area", f->area);
    wp_write_key(out, "com");
    wp_write_numbers(out, f->com, 2);
    wp_write_member_number(out, "inertia", f->inertia);
    wp_write_object_end(out);
    host->fixture_release(host->self, &use);
    return true;
}

bool wp_handle_fixture_get(wp_call *call, wp_writer *out)
{
    const wp_host *host = call->host;
    const cJSON *params = call->params;
    wp_error *error = call->error;
    const char *id = read_id(params, error);
    wp_fixture_use use;
    wp_host_failure failure;
    if (!id)
        return false;
    if (!host->fixture_use(host->self, id, &use, &failure)) {
        wp_error_host(error, &failure, "params.id");
        return false;
    }
    wp_write_raw(out, use.canonical, strlen(use.canonical));
    host->fixture_release(host->self, &use);
    return true;
}

bool wp_handle_fixture_delete(wp_call *call, wp_writer *out)
{
    const wp_host *host = call->host;
    const cJSON *params = call->params;
    wp_error *error = call->error;
    const char *id = read_id(params, error);
    wp_host_failure failure;
    if (!id)
        return false;
    if (!host->fixture_delete(host->self, id, &failure)) {
        wp_error_host(error, &failure, "params.id");
        return false;
    }
    wp_write_object(out);
    wp_write_member_bool(out, "deleted", true);
    wp_write_object_end(out);
    return true;
}

/* A page of fixture.list: at most this many fixtures (the default), each
 * name at most WP_NAME_MAX bytes, so that a page is about a megabyte. */
#define LIST_PAGE 1000

/* The stored fixtures, sorted by id, a page at a time: those after
 * params.after (an id; none: from the first), at most params.limit;
 * "more" says whether any follow the page's last. */
bool wp_handle_fixture_list(wp_call *call, wp_writer *out)
{
    const char *after = NULL;
    double limit = LIST_PAGE;
    bool given = false;
    if (!wp_member_string(call->params, "params", "after", false, &after, call->error) ||
        !wp_member_number(call->params, "params", "limit", false, &limit, &given, call->error))
        return false;
    if (after && !wp_fixture_id_valid(after)) {
        wp_error_set(call->error, WP_INVALID_PARAMS, "params.after",
                     "not a fixture id (32 hexadecimal digits)");
        return false;
    }
    if (given && !(limit >= 1 && limit <= LIST_PAGE && limit == floor(limit))) {
        wp_error_set(call->error, WP_INVALID_PARAMS, "params.limit",
                     "must be a whole number from 1 to %d", LIST_PAGE);
        return false;
    }
    wp_fixture_listing listing = {0, NULL};
    wp_host_failure failure;
    if (!call->host->fixture_list(call->host->self, &listing, &failure)) {
        wp_error_host(call->error, &failure, "");
        return false;
    }
    wp_write_object(out);
    wp_write_key(out, "fixtures");
    wp_write_array(out);
    size_t first = 0;
    while (after && first < listing.count && strcmp(listing.entries[first].id, after) <= 0)
        first++;
    size_t end = first + (size_t)limit < listing.count ? first + (size_t)limit : listing.count;
    for (size_t i = first; i < end; i++) {
        const wp_fixture_entry *e = &listing.entries[i];
        wp_write_object(out);
        wp_write_member_string(out, "id", e->id);
        wp_write_member_string(out, "name", e->name);
        wp_write_member_number(out, "fixels", e->fixels);
        wp_write_object_end(out);
    }
    wp_write_array_end(out);
    wp_write_member_bool(out, "more", end < listing.count);
    wp_write_object_end(out);
    wp_fixture_listing_release(&listing);
    return true;
}

bool wp_handle_server_status(wp_call *call, wp_writer *out)
{
    wp_server_state state;
    wp_host_failure failure;
    if (!call->host->state(call->host->self, &state, &failure)) {
        wp_error_host(call->error, &failure, "");
        return false;
    }
    wp_write_object(out);
    wp_write_member_string(out, "version", WR_VERSION);
    wp_write_member_number(out, "uptime_s", state.uptime_s);
    wp_write_member_number(out, "fixtures", (double)state.fixtures);
    wp_write_member_number(out, "cached", (double)state.cached);
    wp_write_member_number(out, "cache_bytes", (double)state.cache_bytes);
    wp_write_member_number(out, "cache_limit_bytes", (double)state.cache_limit_bytes);
    wp_write_member_number(out, "threads", state.threads);
    wp_write_member_number(out, "clients", (double)state.clients);
    wp_write_member_number(out, "refused", (double)state.refused);
    wp_write_member_number(out, "denied", (double)state.denied);
    wp_write_member_number(out, "requests", (double)state.requests);
    wp_write_member_number(out, "errors", (double)state.errors);
    wp_write_object_end(out);
    return true;
}
