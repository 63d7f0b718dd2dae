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
 * name at most WP_NAME_MAX bytes, so that a page holds about a megabyte. */
#define LIST_PAGE 1000

/* fixture.list's page: its entries, taken from the store's listing when
 * the request begins (the rest released at once), written a piece at a
 * time. */
typedef struct list_state {
    wp_fixture_listing page;
    size_t next;  /* the next entry to write */
    bool more;    /* entries follow the page's last */
    size_t bytes; /* what it holds: the entries and their names */
} list_state;

static void list_free(void *stream)
{
    list_state *state = stream;
    if (!state)
        return;
    wp_fixture_listing_release(&state->page);
    free(state);
}

/* The stored fixtures, sorted by id, a page at a time: those after
 * params.after (an id; none: from the first), at most params.limit;
 * "more" says whether any follow the page's last. */
static void *list_begin(wp_call *call, wp_prepared *prepared)
{
    (void)prepared;
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
    list_state *state = calloc(1, sizeof *state);
    if (!state) {
        wp_error_set(call->error, WP_INTERNAL, "", "out of memory");
        return NULL;
    }
    wp_fixture_listing all = {0, NULL};
    wp_host_failure failure;
    if (!call->host->fixture_list(call->host->self, &all, &failure)) {
        wp_error_host(call->error, &failure, "");
        free(state);
        return NULL;
    }
    /* The page is entries [first, end) of the sorted listing: kept, the
     * rest's names freed now, so that the stream holds one page. */
    size_t first = 0;
    while (after && first < all.count && strcmp(all.entries[first].id, after) <= 0)
        first++;
    size_t end = first + (size_t)limit < all.count ? first + (size_t)limit : all.count;
    for (size_t i = 0; i < all.count; i++)
        if (i < first || i >= end) {
            free(all.entries[i].name);
            all.entries[i].name = NULL;
        }
    memmove(all.entries, all.entries + first, (end - first) * sizeof *all.entries);
    state->page = (wp_fixture_listing){end - first, all.entries};
    state->more = end < all.count;
    state->bytes = sizeof *state + all.count * sizeof *all.entries;
    for (size_t i = 0; i < state->page.count; i++)
        state->bytes += strlen(state->page.entries[i].name) + 1;
    return state;
}

/* {"fixtures": [{"id", "name", "fixels"}, ...], "more"}: entries until a
 * piece's bytes (WP_PIECE_BYTES), so that the daemon checks its bound on
 * the client's unsent output between them (--max-output). */
static wp_step list_step(void *stream, wp_call *call, wp_writer *out, unsigned long budget,
                         unsigned long *used)
{
    (void)call;
    (void)budget;
    list_state *state = stream;
    size_t start = out->out->length;
    if (state->next == 0) {
        wp_write_object(out);
        wp_write_key(out, "fixtures");
        wp_write_array(out);
    }
    for (; state->next < state->page.count && !out->out->failed; state->next++) {
        if (out->out->length - start >= WP_PIECE_BYTES) {
            *used += 1;
            return WP_STEP_MORE;
        }
        const wp_fixture_entry *e = &state->page.entries[state->next];
        wp_write_object(out);
        wp_write_member_string(out, "id", e->id);
        wp_write_member_string(out, "name", e->name);
        wp_write_member_number(out, "fixels", e->fixels);
        wp_write_object_end(out);
    }
    wp_write_array_end(out);
    wp_write_member_bool(out, "more", state->more);
    wp_write_object_end(out);
    *used += 1;
    return out->out->failed ? WP_STEP_FAILED : WP_STEP_DONE;
}

static size_t list_bytes(const void *stream) { return ((const list_state *)stream)->bytes; }

const wp_streamer wp_list_stream = {list_begin, list_step, list_free, list_bytes, false, NULL, NULL};

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
