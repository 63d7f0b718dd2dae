/* wp_methods.c -- the methods of docs/PROTOCOL.md: one table of names,
 * handlers and parameters, and the handlers, which read params, call
 * libwrench and write results. */
#include "wp_design.h"
#include "wp_rpc.h"

#include <assert.h>
#include <math.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ---- shared readers ------------------------------------------------------ */

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

static cJSON *out_of_memory(cJSON *partial, wp_error *error)
{
    cJSON_Delete(partial);
    wp_error_set(error, WP_INTERNAL, "", "out of memory");
    return NULL;
}

static cJSON *vector3(const double v[3])
{
    /* + 0.0 turns -0 into 0, which cJSON would print as "-0". */
    const double w[3] = {v[0] + 0.0, v[1] + 0.0, v[2] + 0.0};
    return cJSON_CreateDoubleArray(w, 3);
}

/* ---- fixtures ------------------------------------------------------------ */

static cJSON *fixture_put(wp_call *call)
{
    const wp_host *host = call->host;
    const cJSON *params = call->params;
    wp_error *error = call->error;
    wp_fixture_doc doc;
    if (!wp_fixture_read(cJSON_GetObjectItemCaseSensitive(params, "fixture"), "params.fixture",
                         &doc, error))
        return NULL;
    wp_fixture_use use;
    if (!host->fixture_adopt(host->self, &doc, true, &use, error))
        return NULL;
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
    return result ? result : out_of_memory(NULL, error);
}

static cJSON *fixture_get(wp_call *call)
{
    const wp_host *host = call->host;
    const cJSON *params = call->params;
    wp_error *error = call->error;
    const char *id = read_id(params, error);
    wp_fixture_use use;
    if (!id || !host->fixture_use(host->self, id, &use, error)) {
        if (id && !error->field[0])
            snprintf(error->field, sizeof error->field, "params.id");
        return NULL;
    }
    cJSON *result = cJSON_CreateRaw(use.canonical);
    host->fixture_release(host->self, &use);
    return result ? result : out_of_memory(NULL, error);
}

static cJSON *fixture_delete(wp_call *call)
{
    const wp_host *host = call->host;
    const cJSON *params = call->params;
    wp_error *error = call->error;
    const char *id = read_id(params, error);
    if (!id || !host->fixture_delete(host->self, id, error)) {
        if (id && !error->field[0])
            snprintf(error->field, sizeof error->field, "params.id");
        return NULL;
    }
    cJSON *result = cJSON_CreateObject();
    if (!result || !cJSON_AddTrueToObject(result, "deleted"))
        return out_of_memory(result, error);
    return result;
}

/* A page of fixture.list: at most this many fixtures (the default), each
 * name at most WP_NAME_MAX bytes, so that a page is about a megabyte. */
#define LIST_PAGE 1000

/* The stored fixtures, sorted by id, a page at a time: those after
 * params.after (an id; none: from the first), at most params.limit;
 * "more" says whether any follow the page's last. */
static cJSON *fixture_list(wp_call *call)
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
    if (!call->host->fixture_list(call->host->self, &listing, call->error))
        return NULL;
    size_t first = 0;
    while (after && first < listing.count && strcmp(listing.entries[first].id, after) <= 0)
        first++;
    size_t end = first + (size_t)limit < listing.count ? first + (size_t)limit : listing.count;
    cJSON *result = cJSON_CreateObject();
    cJSON *list = cJSON_AddArrayToObject(result, "fixtures");
    bool ok = list != NULL;
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
    return ok ? result : out_of_memory(result, call->error);
}

static cJSON *server_status(wp_call *call)
{
    wp_server_state state;
    if (!call->host->state(call->host->self, &state, call->error))
        return NULL;
    cJSON *result = cJSON_CreateObject();
    if (!result)
        return out_of_memory(NULL, call->error);
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
        return out_of_memory(result, call->error);
    return result;
}

void wp_fixture_listing_release(wp_fixture_listing *listing)
{
    for (size_t i = 0; i < listing->count; i++)
        free(listing->entries[i].name);
    free(listing->entries);
    listing->entries = NULL;
    listing->count = 0;
}

/* ---- wrench.classify ------------------------------------------------------ */

static const char *const SET_NAMES[] = {"goal", "strong", "both"};
static const char *const VERDICT_NAMES[] = {"inside", "boundary", "outside"};

/* wrench.classify's "fields": which parts of each verdict to return. */
enum { FIELD_VERDICT, FIELD_MARGIN, FIELD_BLOCKING, FIELD_STATES, FIELD_WITNESS, FIELD_COUNT };
static const char *const FIELD_NAMES[] = {"verdict", "margin", "blocking", "states", "witness"};
/* Their columns in the lean answer, in this order. */
static const char *const COLUMN_NAMES[] = {"verdicts", "margins", "blocking", "states", "witness"};

typedef struct classify_request {
    wr_set sets[3];
    int set_count;
    bool lp;
    double tolerance;
    size_t wrench_count;
    double (*wrenches)[3];
    unsigned fields;   /* 1 << FIELD_*; 0: not given, every field in rows */
} classify_request;

/* params.fields: a non-empty array of distinct names of FIELD_NAMES. */
static bool read_fields(const cJSON *params, classify_request *r, wp_error *error)
{
    const cJSON *fields = cJSON_GetObjectItemCaseSensitive(params, "fields");
    if (!fields)
        return true;
    if (!cJSON_IsArray(fields) || cJSON_GetArraySize(fields) == 0) {
        wp_error_set(error, WP_INVALID_PARAMS, "params.fields",
                     "must be a non-empty array of \"verdict\", \"margin\", \"blocking\", "
                     "\"states\", \"witness\"");
        return false;
    }
    size_t i = 0;
    for (const cJSON *item = fields->child; item; item = item->next, i++) {
        char field[WP_FIELD_MAX];
        wp_path_index(field, "params.fields", i);
        int found = -1;
        for (int f = 0; f < FIELD_COUNT && cJSON_IsString(item); f++)
            if (strcmp(item->valuestring, FIELD_NAMES[f]) == 0)
                found = f;
        if (found < 0) {
            wp_error_set(error, WP_INVALID_PARAMS, field,
                         "must be \"verdict\", \"margin\", \"blocking\", \"states\" or "
                         "\"witness\"");
            return false;
        }
        if (r->fields & (1u << found)) {
            wp_error_set(error, WP_INVALID_PARAMS, field, "\"%s\" is given twice",
                         FIELD_NAMES[found]);
            return false;
        }
        r->fields |= 1u << found;
    }
    return true;
}

static bool read_sets(const cJSON *params, classify_request *r, wp_error *error)
{
    const cJSON *sets = cJSON_GetObjectItemCaseSensitive(params, "sets");
    if (!sets) {
        r->sets[0] = WR_SET_GOAL;
        r->sets[1] = WR_SET_STRONG;
        r->set_count = 2;
        return true;
    }
    if (!cJSON_IsArray(sets) || !sets->child) {
        wp_error_set(error, WP_INVALID_PARAMS, "params.sets",
                     "must be a non-empty array of \"goal\", \"strong\", \"both\"");
        return false;
    }
    size_t index = 0;
    for (const cJSON *item = sets->child; item; item = item->next, index++) {
        char field[WP_FIELD_MAX];
        wp_path_index(field, "params.sets", index);
        int set = -1;
        for (int s = 0; s < 3 && cJSON_IsString(item); s++)
            if (strcmp(item->valuestring, SET_NAMES[s]) == 0)
                set = s;
        if (set < 0) {
            wp_error_set(error, WP_INVALID_PARAMS, field, "must be \"goal\", \"strong\" or \"both\"");
            return false;
        }
        for (int s = 0; s < r->set_count; s++)
            if (r->sets[s] == (wr_set)set) {
                wp_error_set(error, WP_INVALID_PARAMS, field, "\"%s\" is asked twice",
                             SET_NAMES[set]);
                return false;
            }
        r->sets[r->set_count++] = (wr_set)set;
    }
    return true;
}

/* params.wrenches: each read into r->wrenches (or taken from `prepared`,
 * which may be NULL), no more than --max-wrenches of them. */
static bool read_wrench_list(const wp_limits *limits, const cJSON *params,
                             const wr_fixture *fixture, wp_prepared *prepared,
                             classify_request *r, wp_error *error)
{
    const cJSON *wrenches = cJSON_GetObjectItemCaseSensitive(params, "wrenches");
    if (!cJSON_IsArray(wrenches)) {
        wp_error_set(error, WP_INVALID_PARAMS, "params.wrenches",
                     "must be an array of wrenches, not %s", wp_type_name(wrenches));
        return false;
    }
    size_t count = prepared && prepared->wrenches ? prepared->count
                                                  : (size_t)cJSON_GetArraySize(wrenches);
    if (count > limits->max_wrenches) {
        wp_error_set(error, WP_LIMIT, "params.wrenches",
                     "%zu wrenches in one request, the limit is %zu (--max-wrenches)", count,
                     limits->max_wrenches);
        return false;
    }
    if (prepared && prepared->wrenches) {
        /* Read already, each three finite numbers: what wp_wrench_read
         * would have made of them. */
        r->wrenches = prepared->wrenches;
        prepared->wrenches = NULL;
        r->wrench_count = count;
        return true;
    }
    r->wrenches = malloc((count ? count : 1) * sizeof *r->wrenches);
    if (!r->wrenches) {
        wp_error_set(error, WP_INTERNAL, "", "out of memory");
        return false;
    }
    size_t i = 0;
    for (const cJSON *w = wrenches->child; w; w = w->next, i++) {
        char field[WP_FIELD_MAX];
        wp_path_index(field, "params.wrenches", i);
        if (!wp_wrench_read(w, field, fixture, r->wrenches[i], error))
            return false;
    }
    r->wrench_count = count;
    return true;
}

static bool read_classify(const wp_limits *limits, const cJSON *params,
                          const wr_fixture *fixture, wp_prepared *prepared, classify_request *r,
                          wp_error *error)
{
    memset(r, 0, sizeof *r);
    r->tolerance = WR_DEFAULT_TOLERANCE;
    const char *method;
    bool tolerance_given;
    if (!read_sets(params, r, error) || !read_fields(params, r, error) ||
        !wp_member_string(params, "params", "method", false, &method, error) ||
        !wp_member_number(params, "params", "tolerance", false, &r->tolerance, &tolerance_given,
                          error))
        return false;
    if (method && strcmp(method, "auto") != 0 && strcmp(method, "lp") != 0) {
        wp_error_set(error, WP_INVALID_PARAMS, "params.method", "must be \"auto\" or \"lp\"");
        return false;
    }
    r->lp = method && strcmp(method, "lp") == 0;
    /* A margin is in [-1, 1]: a band of 1 or more would call every wrench
     * a boundary case. */
    if (!(r->tolerance >= 0 && r->tolerance < 1)) {
        wp_error_set(error, WP_INVALID_PARAMS, "params.tolerance", "must be in [0, 1)");
        return false;
    }
    if (r->lp && tolerance_given) {
        /* The LP method finds no margin, so it has no band to widen. */
        wp_error_set(error, WP_INVALID_PARAMS, "params.tolerance",
                     "the \"lp\" method computes no margin, so it takes no tolerance");
        return false;
    }
    return read_wrench_list(limits, params, fixture, prepared, r, error);
}

static void write_vector(wp_buffer *b, const double *v, int n)
{
    WP_BUFFER_LITERAL(b, "[");
    for (int i = 0; i < n; i++) {
        if (i)
            WP_BUFFER_LITERAL(b, ",");
        wp_buffer_number(b, v[i]);
    }
    WP_BUFFER_LITERAL(b, "]");
}

static void write_blocking(wp_buffer *b, const wr_analysis *a, const wr_answer *answer);
static void write_states(wp_buffer *b, const wr_analysis *a, const wr_answer *answer);
static void write_witness(wp_buffer *b, const wr_analysis *a, const wr_answer *answer);

/* One set's answer V (docs/PROTOCOL.md). */
static void write_answer(wp_buffer *b, const wr_analysis *a, const wr_answer *answer)
{
    WP_BUFFER_LITERAL(b, "{\"verdict\":\"");
    wp_buffer_puts(b, VERDICT_NAMES[answer->verdict]);
    wp_buffer_puts(b, answer->verdict == WR_VERDICT_INSIDE ? "\",\"inside\":true,\"margin\":"
                                                           : "\",\"inside\":false,\"margin\":");
    if (answer->has_margin)
        wp_buffer_number(b, answer->margin);
    else
        WP_BUFFER_LITERAL(b, "null");
    WP_BUFFER_LITERAL(b, ",\"blocking\":");
    write_blocking(b, a, answer);
    WP_BUFFER_LITERAL(b, ",\"states\":");
    write_states(b, a, answer);
    WP_BUFFER_LITERAL(b, ",\"witness\":");
    write_witness(b, a, answer);
    WP_BUFFER_LITERAL(b, "}");
}

/* The blocking string, or null. */
static void write_blocking(wp_buffer *b, const wr_analysis *a, const wr_answer *answer)
{
    if (answer->blocking < 0) {
        WP_BUFFER_LITERAL(b, "null");
        return;
    }
    const wr_cone *cone = wr_analysis_cone(a, answer->blocking_set, answer->blocking);
    char text[WR_CONSTRAINT_TEXT];
    wr_constraint_format(&cone->constraint, text);
    WP_BUFFER_LITERAL(b, "\"");
    wp_buffer_puts(b, text);
    WP_BUFFER_LITERAL(b, "\"");
}

/* The contact states a blocking goal string comes from: [] otherwise. */
static void write_states(wp_buffer *b, const wr_analysis *a, const wr_answer *answer)
{
    WP_BUFFER_LITERAL(b, "[");
    if (answer->blocking >= 0 && answer->blocking_set == WR_SET_GOAL) {
        const wr_fixture *f = wr_analysis_fixture(a);
        const wr_plan_origins *origins = &wr_analysis_plan(a)->origins[answer->blocking];
        for (int i = 0; i < origins->count; i++) {
            char state[WR_STATE_TEXT];
            wr_state_format(origins->states[i], f->fixel_count, state);
            wp_buffer_puts(b, i ? ",\"" : "\"");
            wp_buffer_puts(b, state);
            WP_BUFFER_LITERAL(b, "\"");
        }
    }
    WP_BUFFER_LITERAL(b, "]");
}

/* The witness, or null when inside. */
static void write_witness(wp_buffer *b, const wr_analysis *a, const wr_answer *answer)
{
    if (answer->blocking < 0) {
        WP_BUFFER_LITERAL(b, "null");
        return;
    }
    const wr_fixture *f = wr_analysis_fixture(a);
    const wr_witness *w = &answer->witness;
    WP_BUFFER_LITERAL(b, "{\"acceleration\":");
    write_vector(b, w->acceleration, 3);
    WP_BUFFER_LITERAL(b, ",\"forces\":[");
    for (int i = 0; i < f->fixel_count; i++) {
        if (i)
            WP_BUFFER_LITERAL(b, ",");
        write_vector(b, w->force[i], 2);
    }
    WP_BUFFER_LITERAL(b, "],\"wrench\":");
    write_vector(b, w->wrench, 3);
    WP_BUFFER_LITERAL(b, ",\"friction\":[");
    for (int i = 0; i < f->fixel_count; i++) {
        if (i)
            WP_BUFFER_LITERAL(b, ",");
        if (isnan(w->friction[i]))
            WP_BUFFER_LITERAL(b, "null");
        else
            wp_buffer_number(b, w->friction[i]);
    }
    WP_BUFFER_LITERAL(b, "]}");
}

/* wrench.classify, written in pieces (wp_stream, wp_rpc.h): the wrenches
 * are read once, up front, so that a bad one is refused before any answer
 * is written; then the answer is made in chunks of consecutive wrenches.
 *
 * A chunk's text is made by whichever thread claims it -- the step, or a
 * helper on another worker (wp_streamer.work) -- into its own buffer, and
 * the steps write the chunks into the answer in order as they are done.
 * Chunk i lives in chunks[i % CLASSIFY_WINDOW]: at most that many are made
 * ahead of the one being written, which bounds what waits in memory.  How
 * many wrenches a chunk has depends on the request alone (the fields and
 * the method), never on the threads, so the same request is answered the
 * same bytes however many workers share it. */
#define CLASSIFY_WINDOW 16
/* A step ends after this much text (or its budget): a piece is where its
 * helpers are forked and joined, and a few chunks a piece keep that cost
 * small.  Still a sixteenth of the default --max-output. */
#define CLASSIFY_PIECE_BYTES (4 * WP_PIECE_BYTES)
/* Verdicts by the map (wr_verdict_map) from this many on: building it costs
 * as much as about that many verdicts measured. */
#define CLASSIFY_MAP_VERDICTS 100000

typedef struct classify_chunk {
    wp_buffer text;
    wr_answer *answers;   /* room for a chunk's answers (columns other than the
                             verdicts), kept for the slot's next chunk */
    bool done;
    wr_status status;     /* not WR_OK: it failed at wrench `failed` */
    size_t failed;
} classify_chunk;

typedef struct classify_state {
    classify_request request;
    wp_fixture_use *use;        /* held by the envelope until the stream's free */
    pthread_mutex_t lock;       /* claims and completions; the text is the claimer's */
    pthread_cond_t made;        /* a chunk is done */
    size_t chunk_wrenches;      /* wrenches per chunk (the last may have fewer) */
    size_t chunk_count;
    size_t claimed;             /* chunks [0, claimed) are claimed, in order */
    size_t written;             /* chunks [0, written) are in the answer */
    classify_chunk chunks[CLASSIFY_WINDOW];
    wr_verdict_map *map;        /* a long batch's verdicts, or NULL */
    bool failing;               /* a chunk failed: nothing more is claimed */
    bool forked;                /* classify_parallel said yes since the last
                                   step began: helpers may be in classify_work
                                   until the next step returns */
    bool opened;                /* the answer's opening text is written */
} classify_state;

/* push.regions, written an edge at a time (a finger with friction samples
 * every edge: a long outline is seconds of work). */
typedef struct push_state {
    wr_set set;
    wr_finger finger;    /* its friction and radius */
    int edges, next;     /* the outline's edges; the next to answer */
    unsigned long edge_cost;
    bool opened, any;    /* "{"regions":[" written; a region written */
    double total, resolution;
} push_state;

/* friction.sweep, a job's budget at a time (wr_sweep.h). */
enum { SWEEP_WRENCHES, SWEEP_PUSH, SWEEP_GRAVITY };
typedef struct sweep_state {
    int what;                   /* SWEEP_* */
    wr_sweep_range range;
    classify_request request;   /* the sets (one for push and gravity), the wrenches */
    wr_finger finger;
    wr_sweeper *sweepers[3];    /* one per set */
    wr_sweep_job *job;          /* the current one */
    size_t next;                /* wrenches: the next to answer, */
    int set;                    /* and its next set */
    bool opened;                /* "{"results":[" written */
} sweep_state;

struct wp_stream {
    union {
        classify_state classify;
        push_state push;
        sweep_state sweep;
        wp_design_stream *design;
    } u;
};

static void classify_free(wp_stream *stream)
{
    if (!stream)
        return;
    classify_state *state = &stream->u.classify;
    for (int i = 0; i < CLASSIFY_WINDOW; i++) {
        free(state->chunks[i].text.data);
        free(state->chunks[i].answers);
    }
    wr_verdict_map_free(state->map);
    free(state->request.wrenches);
    pthread_mutex_destroy(&state->lock);
    pthread_cond_destroy(&state->made);
    free(stream);
}

/* The call's fixture (held until the stream's free) and a zeroed stream;
 * NULL with the error set when either fails. */
static wp_stream *stream_with_fixture(wp_call *call, wp_fixture_use **use)
{
    *use = wp_call_fixture(call);
    if (!*use)
        return NULL;
    wp_stream *stream = calloc(1, sizeof *stream);
    if (!stream)
        wp_error_set(call->error, WP_INTERNAL, "", "out of memory");
    return stream;
}

/* The verdicts alone, by the explicit cones: no margin, no answer kept. */
static bool verdicts_alone(const classify_request *r)
{
    return r->fields == (1u << FIELD_VERDICT) && !r->lp;
}

/* Wrenches per chunk: about half a millisecond of work and some tens of
 * kilobytes of text, whatever is asked. */
static size_t chunk_wrenches(const classify_request *r)
{
    if (r->lp)
        return 16;
    if (r->fields == (1u << FIELD_VERDICT))
        return 16384;
    if (!(r->fields & ~((1u << FIELD_VERDICT) | (1u << FIELD_MARGIN))) && r->fields)
        return 1024;
    return 256;
}

static wp_stream *classify_begin(wp_call *call, wp_prepared *prepared)
{
    wp_fixture_use *use;
    wp_stream *stream = stream_with_fixture(call, &use);
    if (!stream)
        return NULL;
    classify_state *state = &stream->u.classify;
    pthread_mutex_init(&state->lock, NULL);
    pthread_cond_init(&state->made, NULL);
    state->use = use;
    if (!read_classify(call->limits, call->params, use->fixture, prepared, &state->request,
                       call->error)) {
        classify_free(stream);
        return NULL;
    }
    /* Read: the tree of a hundred thousand wrenches (tens of megabytes of
     * nodes) need not live as long as the answer does. */
    cJSON_DeleteItemFromObjectCaseSensitive(call->params, "wrenches");
    const classify_request *r = &state->request;
    state->chunk_wrenches = chunk_wrenches(r);
    state->chunk_count = (r->wrench_count + state->chunk_wrenches - 1) / state->chunk_wrenches;
    /* Verdicts without margins, many of them: by the map.  Built here,
     * before any helper can be reading it. */
    size_t verdicts = verdicts_alone(r) ? r->wrench_count * (size_t)r->set_count : 0;
    if (verdicts >= CLASSIFY_MAP_VERDICTS) {
        wr_status status = wr_verdict_map_new(use->analysis, r->tolerance, &state->map);
        if (status == WR_NO_MEMORY) {
            wp_error_set(call->error, WP_INTERNAL, "", "out of memory");
            classify_free(stream);
            return NULL;
        }
        /* Otherwise (it cannot be made for this tolerance) each verdict is
         * measured. */
    }
    return stream;
}

/* One wrench's answer for one set, as much of it as the chunk writes. */
static wr_status answer_one(const classify_state *state, const wr_analysis *a, wr_lp_set *goal,
                            wr_lp_set *strong, size_t i, wr_set set, bool verdict_only,
                            bool witness, wr_answer *answer)
{
    const classify_request *r = &state->request;
    if (r->lp)
        return wr_classify_lp(a, goal, strong, r->wrenches[i], set, answer);
    if (verdict_only) {
        answer->has_margin = false;
        return state->map ? wr_verdict_map_classify(state->map, r->wrenches[i], set, &answer->verdict)
                          : wr_classify_verdict(a, r->wrenches[i], set, r->tolerance,
                                                &answer->verdict);
    }
    return witness ? wr_classify(a, r->wrenches[i], set, r->tolerance, answer)
                   : wr_classify_margin(a, r->wrenches[i], set, r->tolerance, answer);
}

/* Wrenches between polls of the stop (a call through a pointer each). */
#define STOP_POLL 64

/* One set's columns of a lean chunk: {"verdicts": "...", "margins": [...],
 * ...}, each column a pass over the chunk's answers, computed once. */
static wr_status write_set_columns(const classify_state *state, const wr_analysis *a,
                                   wr_lp_set *goal, wr_lp_set *strong, const wr_stop *stop,
                                   wr_set set, size_t from, size_t to, wr_answer *answers,
                                   wp_buffer *out, size_t *failed)
{
    const classify_request *r = &state->request;
    bool witness = r->fields & (1u << FIELD_WITNESS);
    static const char LETTERS[] = {'i', 'b', 'o'};
    if (verdicts_alone(r)) {
        /* The letters straight into the text: nothing else is kept. */
        WP_BUFFER_LITERAL(out, "\"verdicts\":\"");
        size_t at = out->length;
        wp_buffer_reserve(out, at + (to - from) + 64);
        if (out->failed)
            return WR_OK; /* the buffer says so */
        for (size_t i = from; i < to; i++) {
            if ((i - from) % STOP_POLL == 0 && wr_stop_requested(stop)) {
                *failed = i;
                return WR_STOPPED;
            }
            wr_answer answer;
            wr_status status = answer_one(state, a, goal, strong, i, set, true, false, &answer);
            if (status != WR_OK) {
                *failed = i;
                return status;
            }
            out->data[at + (i - from)] = LETTERS[answer.verdict];
        }
        out->length = at + (to - from);
        out->data[out->length] = 0;
        WP_BUFFER_LITERAL(out, "\"");
        return WR_OK;
    }
    for (size_t i = from; i < to; i++) {
        if ((i - from) % STOP_POLL == 0 && wr_stop_requested(stop)) {
            *failed = i;
            return WR_STOPPED;
        }
        wr_status status =
            answer_one(state, a, goal, strong, i, set, false, witness, &answers[i - from]);
        if (status != WR_OK) {
            *failed = i;
            return status;
        }
    }
    bool first = true;
    for (int column = 0; column < FIELD_COUNT; column++) {
        if (!(r->fields & (1u << column)))
            continue;
        wp_buffer_puts(out, first ? "\"" : ",\"");
        first = false;
        wp_buffer_puts(out, COLUMN_NAMES[column]);
        if (column == FIELD_VERDICT) {
            WP_BUFFER_LITERAL(out, "\":\"");
            size_t at = out->length;
            wp_buffer_reserve(out, at + (to - from) + 64);
            if (out->failed)
                return WR_OK; /* the buffer says so */
            for (size_t i = from; i < to; i++)
                out->data[at + (i - from)] = LETTERS[answers[i - from].verdict];
            out->length = at + (to - from);
            out->data[out->length] = 0;
            WP_BUFFER_LITERAL(out, "\"");
            continue;
        }
        WP_BUFFER_LITERAL(out, "\":[");
        for (size_t i = from; i < to; i++) {
            const wr_answer *answer = &answers[i - from];
            if (i > from)
                WP_BUFFER_LITERAL(out, ",");
            if (column == FIELD_MARGIN) {
                if (answer->has_margin)
                    wp_buffer_number(out, answer->margin);
                else
                    WP_BUFFER_LITERAL(out, "null");
            } else if (column == FIELD_BLOCKING) {
                write_blocking(out, a, answer);
            } else if (column == FIELD_STATES) {
                write_states(out, a, answer);
            } else {
                write_witness(out, a, answer);
            }
        }
        WP_BUFFER_LITERAL(out, "]");
    }
    return WR_OK;
}

/* Chunk `index`'s text into `out` (empty), with the thread's own LP sets:
 * rows joined by commas, or a lean piece {"count": n, "goal": {...}, ...};
 * either preceded by a comma but for the first.  Not WR_OK: it failed at
 * wrench *failed (WR_STOPPED: the client is gone). */
static wr_status make_chunk(const classify_state *state, size_t index, wr_answer **answers,
                            const wp_host *host,
                            wp_error *error, wp_buffer *out, size_t *failed)
{
    const classify_request *r = &state->request;
    const wr_analysis *a = state->use->analysis;
    wr_lp_set *goal = NULL, *strong = NULL;
    *failed = 0;
    if (r->lp && !host->lp_sets(host->self, state->use, &goal, &strong, error))
        return WR_NO_MEMORY;
    size_t from = index * state->chunk_wrenches;
    size_t to = from + state->chunk_wrenches < r->wrench_count ? from + state->chunk_wrenches
                                                               : r->wrench_count;
    if (index)
        WP_BUFFER_LITERAL(out, ",");
    if (r->fields) {
        if (!verdicts_alone(r) && !*answers &&
            !(*answers = malloc(state->chunk_wrenches * sizeof **answers)))
            return WR_NO_MEMORY;
        char count[32];
        snprintf(count, sizeof count, "{\"count\":%zu", to - from);
        wp_buffer_puts(out, count);
        wr_status status = WR_OK;
        for (int s = 0; s < r->set_count && status == WR_OK; s++) {
            WP_BUFFER_LITERAL(out, ",\"");
            wp_buffer_puts(out, SET_NAMES[r->sets[s]]);
            WP_BUFFER_LITERAL(out, "\":{");
            status = write_set_columns(state, a, goal, strong, host->stop, r->sets[s], from, to,
                                       *answers, out, failed);
            WP_BUFFER_LITERAL(out, "}");
        }
        WP_BUFFER_LITERAL(out, "}");
        return status;
    }
    for (size_t i = from; i < to; i++) {
        if ((i - from) % STOP_POLL == 0 && wr_stop_requested(host->stop)) {
            *failed = i;
            return WR_STOPPED;
        }
        wp_buffer_puts(out, i > from ? ",{" : "{");
        for (int s = 0; s < r->set_count; s++) {
            wr_answer answer;
            wr_status status = answer_one(state, a, goal, strong, i, r->sets[s], false, true,
                                          &answer);
            if (status != WR_OK) {
                *failed = i;
                return status;
            }
            wp_buffer_puts(out, s ? ",\"" : "\"");
            wp_buffer_puts(out, SET_NAMES[r->sets[s]]);
            WP_BUFFER_LITERAL(out, "\":");
            write_answer(out, a, &answer);
        }
        WP_BUFFER_LITERAL(out, "}");
    }
    return WR_OK;
}

/* Claim the next chunk and make it; false when none can be claimed now
 * (all are, the window is full, or one failed).  Any thread.  A step
 * passes its answer as `out`: the chunk next to be written is then made
 * straight into it (nothing to copy, for a short batch nothing else).
 * `error` only for an LP set that cannot be made. */
static bool claim_and_make(classify_state *state, const wp_host *host, wp_error *error,
                           wp_buffer *out)
{
    pthread_mutex_lock(&state->lock);
    bool claimable = !state->failing && state->claimed < state->chunk_count &&
                     state->claimed < state->written + CLASSIFY_WINDOW;
    size_t index = state->claimed;
    if (claimable)
        state->claimed++;
    bool direct = claimable && out && index == state->written;
    pthread_mutex_unlock(&state->lock);
    if (!claimable)
        return false;
    /* The slot is this thread's alone until done: the writer reads it only
     * then, and it was emptied when its last chunk was written. */
    classify_chunk *chunk = &state->chunks[index % CLASSIFY_WINDOW];
    assert(!chunk->done && chunk->text.length == 0);
    size_t failed;
    wr_status status = make_chunk(state, index, &chunk->answers, host, error,
                                  direct ? out : &chunk->text, &failed);
    if (status == WR_OK && !direct && chunk->text.failed)
        status = WR_NO_MEMORY;
    pthread_mutex_lock(&state->lock);
    chunk->status = status;
    chunk->failed = failed;
    if (status != WR_OK)
        state->failing = true; /* no more claims: the answer ends at this chunk */
    if (direct && status == WR_OK)
        state->written++; /* in the answer already */
    else
        chunk->done = true;
    pthread_cond_broadcast(&state->made);
    pthread_mutex_unlock(&state->lock);
    return true;
}

static bool classify_parallel(wp_stream *stream)
{
    classify_state *state = &stream->u.classify;
    pthread_mutex_lock(&state->lock);
    bool more = !state->failing && state->claimed < state->chunk_count;
    /* The host opens a fork on a yes and runs the step after it: its
     * helpers may claim every chunk left before that step begins, so the
     * step cannot tell from the claims alone that it shares. */
    state->forked = state->forked || more;
    pthread_mutex_unlock(&state->lock);
    return more;
}

static bool classify_work(wp_stream *stream, const wp_host *host)
{
    wp_error ignored = {0}; /* a helper's failure is the chunk's status, said by a step */
    return claim_and_make(&stream->u.classify, host, &ignored, NULL);
}

/* Write the chunks that are done, in order, into the answer.  A failed
 * chunk ends it: false with the error set. */
static bool write_done(classify_state *state, wp_buffer *out, wp_error *error)
{
    pthread_mutex_lock(&state->lock);
    for (;;) {
        classify_chunk *chunk = &state->chunks[state->written % CLASSIFY_WINDOW];
        if (state->written == state->claimed || !chunk->done)
            break;
        pthread_mutex_unlock(&state->lock);
        if (chunk->status != WR_OK) {
            if (chunk->status == WR_LP_FAILED)
                wp_error_status(error, chunk->status, "params.wrenches",
                                "GLPK failed on wrench %zu; nothing was answered", chunk->failed);
            else
                wp_error_status(error, chunk->status, "params.wrenches", "%s",
                                wr_strerror(chunk->status));
            return false;
        }
        wp_buffer_append(out, chunk->text.data, chunk->text.length);
        chunk->text.length = 0;
        /* A long batch's slots keep their capacity; a short one's go. */
        if (state->chunk_count <= CLASSIFY_WINDOW) {
            free(chunk->text.data);
            memset(&chunk->text, 0, sizeof chunk->text);
        }
        pthread_mutex_lock(&state->lock);
        chunk->done = false;
        state->written++;
    }
    pthread_mutex_unlock(&state->lock);
    return true;
}

static wp_step classify_step(wp_stream *stream, wp_call *call, wp_buffer *out,
                             unsigned long budget, unsigned long *used)
{
    classify_state *state = &stream->u.classify;
    const classify_request *r = &state->request;
    const wr_analysis *a = state->use->analysis;
    /* Helpers may be making chunks until this step returns: it ends the
     * answer only if the host was told of none before it began
     * (wp_streamer.parallel; helpers come only after a yes) -- never in the
     * first step, which began before the stream existed. */
    pthread_mutex_lock(&state->lock);
    bool shared = state->opened && state->forked;
    state->forked = false;
    pthread_mutex_unlock(&state->lock);
    if (!state->opened) {
        state->opened = true;
        if (r->fields) {
            char count[48];
            snprintf(count, sizeof count, "{\"count\":%zu,\"pieces\":[", r->wrench_count);
            wp_buffer_puts(out, count);
        } else {
            WP_BUFFER_LITERAL(out, "{\"results\":[");
        }
    }
    /* At least one chunk a step, whatever the piece spent before it: every
     * step makes progress (and a request's first chunk fails, if it does,
     * while its text can still be taken back). */
    size_t start = out->length;
    /* Work units per chunk, for the budget: a wrench against a cone is one,
     * a verdict by the map about one, an LP sixty-four. */
    unsigned long cones = 0;
    for (int s = 0; s < r->set_count; s++)
        cones += (unsigned long)(r->sets[s] == WR_SET_BOTH
                                     ? wr_analysis_cone_count(a, WR_SET_GOAL) +
                                           wr_analysis_cone_count(a, WR_SET_STRONG)
                                     : wr_analysis_cone_count(a, r->sets[s]));
    unsigned long per_wrench = state->map ? (unsigned long)r->set_count
                               : r->lp    ? 64 * (cones + 1)
                                          : cones + 1;
    unsigned long chunk_cost = per_wrench * state->chunk_wrenches;
    for (;;) {
        if (!write_done(state, out, call->error))
            return shared ? WP_STEP_MORE : WP_STEP_FAILED;
        if (out->failed)
            return shared ? WP_STEP_MORE : WP_STEP_FAILED;
        if (state->written == state->chunk_count) {
            if (shared)
                return WP_STEP_MORE; /* the next step, alone, ends it */
            WP_BUFFER_LITERAL(out, "]}");
            return out->failed ? WP_STEP_FAILED : WP_STEP_DONE;
        }
        if (out->length > start &&
            (*used >= budget || out->length - start >= CLASSIFY_PIECE_BYTES ||
             wr_stop_requested(call->host->stop)))
            return WP_STEP_MORE;
        if (claim_and_make(state, call->host, call->error, out)) {
            *used += chunk_cost;
            continue;
        }
        /* Nothing to claim: the next chunk to write is a helper's, being
         * made; wait for it (helpers never wait for a step). */
        pthread_mutex_lock(&state->lock);
        while (state->written < state->claimed &&
               !state->chunks[state->written % CLASSIFY_WINDOW].done)
            pthread_cond_wait(&state->made, &state->lock);
        pthread_mutex_unlock(&state->lock);
    }
}

static size_t classify_bytes(const wp_stream *stream)
{
    const classify_state *state = &stream->u.classify;
    size_t bytes = sizeof *stream + state->request.wrench_count * sizeof *state->request.wrenches;
    for (int i = 0; i < CLASSIFY_WINDOW; i++)
        bytes += state->chunks[i].text.capacity +
                 (state->chunks[i].answers ? state->chunk_wrenches * sizeof(wr_answer) : 0);
    return bytes + (state->map ? wr_verdict_map_bytes(state->map) : 0);
}

static const wp_streamer CLASSIFY_STREAM = {classify_begin,   classify_step, classify_free,
                                            classify_bytes,   false,         classify_parallel,
                                            classify_work};

/* Light enough for an event loop: the explicit cones (no GLPK), and few
 * wrenches against few cones. */
static bool classify_light(const cJSON *params, int cones)
{
    const cJSON *how = cJSON_GetObjectItemCaseSensitive(params, "method");
    const cJSON *wrenches = cJSON_GetObjectItemCaseSensitive(params, "wrenches");
    if ((how && !(cJSON_IsString(how) && strcmp(how->valuestring, "auto") == 0)) ||
        !cJSON_IsArray(wrenches))
        return false;
    long count = cJSON_GetArraySize(wrenches);
    return count <= WP_LIGHT_CONE_CHECKS && count * (cones > 0 ? cones : 1) <= WP_LIGHT_CONE_CHECKS;
}

/* ---- cone.get, plan.get, modes.get --------------------------------------- */

static cJSON *cone_get(wp_call *call)
{
    const cJSON *params = call->params;
    wp_error *error = call->error;
    const char *text;
    if (!wp_member_string(params, "params", "constraints", true, &text, error))
        return NULL;
    wp_fixture_use *use = wp_call_fixture(call);
    if (!use)
        return NULL;
    const wr_fixture *f = use->fixture;
    wr_constraint constraint;
    wr_error invalid;
    wr_cone cone;
    cJSON *result = NULL;
    wr_status status = wr_constraint_parse(text, f->fixel_count, &constraint, &invalid);
    if (status != WR_OK) {
        wp_error_status(error, status, "params.constraints", "%s", invalid.reason);
        goto done;
    }
    status = wr_cone_build(&cone, f, &constraint);
    if (status != WR_OK) {
        wr_cone_release(&cone);
        wp_error_status(error, status, "params.constraints", "%s", wr_strerror(status));
        goto done;
    }
    result = cJSON_CreateObject();
    cJSON_AddStringToObject(result, "constraints", text);
    cJSON_AddBoolToObject(result, "empty", cone.empty);
    cJSON_AddNumberToObject(result, "dimension", cone.dimension);
    cJSON *halfspaces = cJSON_AddArrayToObject(result, "halfspaces");
    cJSON *strict = cJSON_AddArrayToObject(result, "strict");
    cJSON *equalities = cJSON_AddArrayToObject(result, "equalities");
    cJSON *generators = cJSON_AddArrayToObject(result, "generators");
    if (!result || !halfspaces || !strict || !equalities || !generators) {
        wr_cone_release(&cone);
        result = out_of_memory(result, error);
        goto done;
    }
    double row[3];
    for (int i = 0; i < cone.facet_count; i++) {
        wr_fixture_unscale_row(f, cone.facets[i], row);
        cJSON_AddItemToArray(halfspaces, vector3(row));
        cJSON_AddItemToArray(strict, cJSON_CreateBool(cone.facet_open[i]));
    }
    for (int i = 0; i < cone.equality_count && !cone.empty; i++) {
        wr_fixture_unscale_row(f, cone.equalities[i], row);
        cJSON_AddItemToArray(equalities, vector3(row));
    }
    for (int i = 0; i < cone.ray_count; i++) {
        wr_fixture_unscale_wrench(f, cone.rays[i], row);
        wr_fixture_unit_direction(row);
        cJSON_AddItemToArray(generators, vector3(row));
    }
    wr_cone_release(&cone);
done:
    return result;
}

static cJSON *plan_get(wp_call *call)
{
    wp_error *error = call->error;
    wp_fixture_use *use = wp_call_fixture(call);
    if (!use)
        return NULL;
    const wr_plan *plan = wr_analysis_plan(use->analysis);
    int k = plan->fixel_count;
    cJSON *result = cJSON_CreateObject();
    cJSON *states = cJSON_AddArrayToObject(result, "states");
    cJSON *cones = cJSON_AddArrayToObject(result, "cones");
    for (int s = 0; states && s < plan->state_count; s++) {
        const wr_plan_state *ps = &plan->states[s];
        char text[WR_STATE_TEXT];
        wr_state_format(ps->state, k, text);
        cJSON *state = cJSON_CreateObject();
        cJSON_AddStringToObject(state, "state", text);
        cJSON *excluded = cJSON_AddArrayToObject(state, "excluded");
        for (int e = 0; excluded && e < ps->excluded_count; e++)
            cJSON_AddItemToArray(excluded,
                                 cJSON_CreateString(plan->excluded[ps->excluded_first + e].letters));
        cJSON_AddItemToArray(states, state);
    }
    for (int i = 0; cones && i < plan->kept_count; i++)
        cJSON_AddItemToArray(cones, cJSON_CreateString(plan->kept[i].letters));
    if (!states || !cones)
        return out_of_memory(result, error);
    return result;
}

static cJSON *modes_get(wp_call *call)
{
    wp_error *error = call->error;
    wp_fixture_use *use = wp_call_fixture(call);
    if (!use)
        return NULL;
    const wr_analysis *a = use->analysis;
    cJSON *result = cJSON_CreateObject();
    cJSON *feasible = cJSON_AddArrayToObject(result, "feasible");
    const wr_constraint *modes = wr_analysis_constraints(a, WR_SET_STRONG);
    for (int i = 0; feasible && i < wr_analysis_cone_count(a, WR_SET_STRONG); i++) {
        char text[WR_CONSTRAINT_TEXT];
        wr_constraint_format(&modes[i], text);
        cJSON_AddItemToArray(feasible, cJSON_CreateString(text));
    }
    cJSON_AddBoolToObject(result, "pinned", wr_analysis_pinned(a));
    if (!feasible)
        return out_of_memory(result, error);
    return result;
}

/* ---- push.regions, gravity.sweep, stability.margin ----------------------- */

/* path.set: one of goal, strong, both (default goal). */
static bool read_set_at(const cJSON *object, const char *path, wr_set *set, wp_error *error)
{
    const char *name;
    if (!wp_member_string(object, path, "set", false, &name, error))
        return false;
    *set = WR_SET_GOAL;
    if (!name)
        return true;
    for (int s = 0; s < 3; s++)
        if (strcmp(name, SET_NAMES[s]) == 0) {
            *set = (wr_set)s;
            return true;
        }
    char field[WP_FIELD_MAX];
    wp_path_key(field, path, "set");
    wp_error_set(error, WP_INVALID_PARAMS, field, "must be \"goal\", \"strong\" or \"both\"");
    return false;
}

static bool read_set(const cJSON *params, wr_set *set, wp_error *error)
{
    return read_set_at(params, "params", set, error);
}

/* path.finger_friction and path.finger_radius: not negative (default 0). */
static bool read_finger(const cJSON *object, const char *path, wr_finger *finger,
                        wp_error *error)
{
    *finger = (wr_finger){0, 0};
    if (!wp_member_number(object, path, "finger_friction", false, &finger->friction, NULL,
                          error) ||
        !wp_member_number(object, path, "finger_radius", false, &finger->radius, NULL, error))
        return false;
    char field[WP_FIELD_MAX];
    if (finger->friction < 0 || finger->radius < 0) {
        wp_path_key(field, path, finger->friction < 0 ? "finger_friction" : "finger_radius");
        wp_error_set(error, WP_INVALID_PARAMS, field, "must not be negative");
        return false;
    }
    return true;
}

static void stream_free(wp_stream *stream) { free(stream); }

static wp_stream *push_begin(wp_call *call, wp_prepared *prepared)
{
    (void)prepared;
    wr_set set;
    wr_finger finger;
    if (!read_set(call->params, &set, call->error) ||
        !read_finger(call->params, "params", &finger, call->error))
        return NULL;
    double friction = finger.friction, radius = finger.radius;
    wp_fixture_use *use = wp_call_fixture(call);
    if (!use)
        return NULL;
    if (use->fixture->shape == WR_SHAPE_NONE) {
        wp_error_set(call->error, WP_INVALID_PARAMS, "params.fixture.body.shape",
                     "push regions need the part's outline: the fixture has no shape");
        return NULL;
    }
    wp_stream *stream = calloc(1, sizeof *stream);
    if (!stream) {
        wp_error_set(call->error, WP_INTERNAL, "", "out of memory");
        return NULL;
    }
    push_state *state = &stream->u.push;
    state->set = set;
    state->finger = (wr_finger){friction, radius};
    state->edges = wr_push_edge_count(use->fixture);
    /* An edge against every cone: a few dot products each, or, with a
     * finger's friction, a segment test at every sample and bisection. */
    const wr_analysis *a = use->analysis;
    unsigned long cones = (unsigned long)(set == WR_SET_GOAL     ? wr_analysis_cone_count(a, WR_SET_GOAL)
                                          : set == WR_SET_STRONG ? wr_analysis_cone_count(a, WR_SET_STRONG)
                                                                 : wr_analysis_cone_count(a, WR_SET_GOAL) +
                                                                       wr_analysis_cone_count(a, WR_SET_STRONG));
    /* A finger with a size is tested against every segment of the outline. */
    state->edge_cost = (cones + 1) * (friction > 0 ? 2200 : 4) +
                       (radius > 0 ? 8 * (unsigned long)state->edges : 0);
    return stream;
}

static void write_region(wp_buffer *out, const wr_fixture *f, const wr_region *r, double length)
{
    double from[2], to[2], normal[2];
    wr_boundary_point(f, r->edge, r->t0, from, normal);
    wr_boundary_point(f, r->edge, r->t1, to, normal);
    /* + 0.0: a -0 is written 0. */
    const double ends[2][2] = {{from[0] + 0.0, from[1] + 0.0}, {to[0] + 0.0, to[1] + 0.0}};
    if (f->shape == WR_SHAPE_OUTLINE) {
        size_t loop, segment;
        wr_push_edge_place(f, r->edge, &loop, &segment);
        WP_BUFFER_LITERAL(out, "{\"loop\":");
        wp_buffer_number(out, (double)loop);
        WP_BUFFER_LITERAL(out, ",\"segment\":");
        wp_buffer_number(out, (double)segment);
    } else {
        WP_BUFFER_LITERAL(out, "{\"edge\":");
        wp_buffer_number(out, r->edge);
    }
    WP_BUFFER_LITERAL(out, ",\"from\":");
    write_vector(out, ends[0], 2);
    WP_BUFFER_LITERAL(out, ",\"to\":");
    write_vector(out, ends[1], 2);
    WP_BUFFER_LITERAL(out, ",\"t0\":");
    wp_buffer_number(out, r->t0);
    WP_BUFFER_LITERAL(out, ",\"t1\":");
    wp_buffer_number(out, r->t1);
    WP_BUFFER_LITERAL(out, ",\"length\":");
    wp_buffer_number(out, length);
    WP_BUFFER_LITERAL(out, "}");
}

static wp_step push_step(wp_stream *stream, wp_call *call, wp_buffer *out, unsigned long budget,
                         unsigned long *used)
{
    push_state *state = &stream->u.push;
    wp_fixture_use *use = wp_call_fixture(call); /* held since begin */
    if (!use)
        return WP_STEP_FAILED;
    const wr_fixture *f = use->fixture;
    size_t start = out->length;
    if (!state->opened) {
        state->opened = true;
        WP_BUFFER_LITERAL(out, "{\"regions\":[");
    }
    /* At least one edge a step: every step makes progress. */
    for (bool first = true; state->next < state->edges && !out->failed; first = false) {
        if (!first && (*used >= budget || out->length - start >= WP_PIECE_BYTES))
            return WP_STEP_MORE;
        wr_regions part = {0};
        wr_status status = wr_push_regions_part(use->analysis, state->set, &state->finger,
                                                state->next, 1, call->host->stop, &part);
        if (status != WR_OK) {
            wr_regions_release(&part);
            wp_error_status(call->error, status, "", "%s", wr_strerror(status));
            return WP_STEP_FAILED;
        }
        for (int i = 0; i < part.count; i++) {
            /* Summed in the order written, as the whole answer always was. */
            double length = wr_region_length(f, &part.items[i]);
            state->total += length;
            if (state->any)
                WP_BUFFER_LITERAL(out, ",");
            state->any = true;
            write_region(out, f, &part.items[i], length);
        }
        state->resolution = part.resolution;
        wr_regions_release(&part);
        state->next++;
        *used += state->edge_cost;
    }
    WP_BUFFER_LITERAL(out, "],\"total_length\":");
    wp_buffer_number(out, state->total);
    WP_BUFFER_LITERAL(out, ",\"fraction\":");
    wp_buffer_number(out, state->total / wr_perimeter(f));
    wp_buffer_puts(out, state->resolution == 0 ? ",\"exact\":true" : ",\"exact\":false");
    WP_BUFFER_LITERAL(out, ",\"resolution\":");
    wp_buffer_number(out, state->resolution);
    WP_BUFFER_LITERAL(out, "}");
    return WP_STEP_DONE;
}

static const wp_streamer PUSH_STREAM = {push_begin, push_step, stream_free, NULL, false, NULL, NULL};

static cJSON *gravity_sweep(wp_call *call)
{
    const cJSON *params = call->params;
    wp_error *error = call->error;
    wr_set set;
    if (!read_set(params, &set, error))
        return NULL;
    wp_fixture_use *use = wp_call_fixture(call);
    if (!use)
        return NULL;
    cJSON *result = NULL;
    wr_regions arcs;
    wr_status status = wr_gravity_sweep(use->analysis, set, &arcs);
    if (status != WR_OK) {
        wp_error_status(error, status, "params.set", "%s", wr_strerror(status));
    } else {
        result = cJSON_CreateObject();
        cJSON *list = cJSON_AddArrayToObject(result, "intervals_deg");
        for (int i = 0; list && i < arcs.count; i++) {
            const double arc[2] = {arcs.items[i].t0 + 0.0, arcs.items[i].t1 + 0.0};
            cJSON_AddItemToArray(list, cJSON_CreateDoubleArray(arc, 2));
        }
        if (!list)
            result = out_of_memory(result, error);
        wr_regions_release(&arcs);
    }
    return result;
}

static cJSON *stability_margin(wp_call *call)
{
    const cJSON *params = call->params;
    wp_error *error = call->error;
    wp_fixture_use *use = wp_call_fixture(call);
    if (!use)
        return NULL;
    double bias[3];
    cJSON *result = NULL;
    wr_disturbance d;
    bool read = wp_wrench_read(cJSON_GetObjectItemCaseSensitive(params, "bias"), "params.bias",
                               use->fixture, bias, error);
    wr_status status = read ? wr_disturbance_margin(use->analysis, bias, &d) : WR_OK;
    if (status != WR_OK)
        wp_error_status(error, status, "params.bias",
                        "so large that its margin is beyond the largest number");
    else if (read) {
        result = cJSON_CreateObject();
        if (d.bounded) {
            char text[WR_CONSTRAINT_TEXT];
            wr_constraint_format(&wr_analysis_constraints(use->analysis, WR_SET_STRONG)[d.blocking],
                                 text);
            cJSON_AddNumberToObject(result, "margin", d.margin + 0.0);
            cJSON_AddStringToObject(result, "blocking", text);
            cJSON_AddItemToObject(result, "worst_direction", vector3(d.worst_direction));
        } else {
            /* No moving mode at all: no disturbance moves the part. */
            cJSON_AddNullToObject(result, "margin");
            cJSON_AddNullToObject(result, "blocking");
            cJSON_AddNullToObject(result, "worst_direction");
        }
        if (!cJSON_GetObjectItem(result, "worst_direction"))
            result = out_of_memory(result, error);
    }
    return result;
}

/* ---- friction.sweep -------------------------------------------------------- */

static const char *const SWEEP_PUSH_FIELDS[] = {"set", "finger_friction", "finger_radius", NULL};
static const char *const SWEEP_GRAVITY_FIELDS[] = {"set", NULL};

/* params.range: [low, high], 0 <= low < high <= WR_MAX_FRICTION (default
 * [0, 2]); params.kinetic_ratio in (0, 1] (default 1). */
static bool read_sweep_range(const cJSON *params, wr_sweep_range *range, wp_error *error)
{
    *range = (wr_sweep_range){0, 2, 1};
    const cJSON *value = cJSON_GetObjectItemCaseSensitive(params, "range");
    if (value) {
        if (!cJSON_IsArray(value) || cJSON_GetArraySize(value) != 2) {
            wp_error_set(error, WP_INVALID_PARAMS, "params.range",
                         "must be [low, high]: two coefficients of friction");
            return false;
        }
        double ends[2];
        for (int i = 0; i < 2; i++) {
            char field[WP_FIELD_MAX];
            wp_path_index(field, "params.range", (size_t)i);
            const cJSON *end = cJSON_GetArrayItem(value, i);
            if (!cJSON_IsNumber(end) || !isfinite(end->valuedouble)) {
                wp_error_set(error, WP_INVALID_PARAMS, field, "must be a number, not %s",
                             wp_type_name(end));
                return false;
            }
            ends[i] = end->valuedouble;
        }
        if (ends[0] < 0) {
            wp_error_set(error, WP_INVALID_PARAMS, "params.range[0]",
                         "a coefficient of friction is not negative");
            return false;
        }
        if (ends[1] > WR_MAX_FRICTION) {
            wp_error_set(error, WP_INVALID_PARAMS, "params.range[1]",
                         "at most %g: no contact has more friction", WR_MAX_FRICTION);
            return false;
        }
        if (!(ends[0] < ends[1])) {
            wp_error_set(error, WP_INVALID_PARAMS, "params.range",
                         "the low end must be below the high end");
            return false;
        }
        range->low = ends[0] + 0.0;
        range->high = ends[1];
    }
    bool given;
    if (!wp_member_number(params, "params", "kinetic_ratio", false, &range->kinetic_ratio, &given,
                          error))
        return false;
    if (!(range->kinetic_ratio > 0 && range->kinetic_ratio <= 1)) {
        wp_error_set(error, WP_INVALID_PARAMS, "params.kinetic_ratio",
                     "must be in (0, 1]: kinetic friction is positive and not above static");
        return false;
    }
    return true;
}

static void write_intervals(wp_buffer *out, const wr_intervals *list)
{
    WP_BUFFER_LITERAL(out, "[");
    for (int i = 0; i < list->count; i++) {
        if (i)
            WP_BUFFER_LITERAL(out, ",");
        const double pair[2] = {list->items[i][0] + 0.0, list->items[i][1] + 0.0};
        write_vector(out, pair, 2);
    }
    WP_BUFFER_LITERAL(out, "]");
}

/* {"intervals", "critical", "curve", "exact", "resolution"} */
static void write_curve(wp_buffer *out, const wr_sweep_curve *curve)
{
    WP_BUFFER_LITERAL(out, "{\"intervals\":");
    write_intervals(out, &curve->intervals);
    WP_BUFFER_LITERAL(out, ",\"critical\":");
    if (curve->has_critical)
        wp_buffer_number(out, curve->critical + 0.0);
    else
        WP_BUFFER_LITERAL(out, "null");
    WP_BUFFER_LITERAL(out, ",\"curve\":[");
    for (int i = 0; i < curve->point_count; i++) {
        if (i)
            WP_BUFFER_LITERAL(out, ",");
        const double point[2] = {curve->points[i][0] + 0.0, curve->points[i][1] + 0.0};
        write_vector(out, point, 2);
    }
    wp_buffer_puts(out, curve->exact ? "],\"exact\":true" : "],\"exact\":false");
    WP_BUFFER_LITERAL(out, ",\"resolution\":");
    wp_buffer_number(out, curve->resolution);
    WP_BUFFER_LITERAL(out, "}");
}

/* The sweep's reading of params: which question, the range, and the
 * wrenches and sets or the set and finger. */
static bool read_sweep(wp_call *call, const wr_fixture *fixture, sweep_state *state)
{
    const cJSON *params = call->params;
    wp_error *error = call->error;
    const char *names[3] = {"wrenches", "push", "gravity"};
    int given = 0;
    for (int i = 0; i < 3; i++)
        if (cJSON_GetObjectItemCaseSensitive(params, names[i])) {
            given++;
            state->what = i;
        }
    if (given != 1) {
        wp_error_set(error, WP_INVALID_PARAMS, "params",
                     "give exactly one of \"wrenches\", \"push\" and \"gravity\" (%d given)",
                     given);
        return false;
    }
    if (state->what != SWEEP_WRENCHES && cJSON_GetObjectItemCaseSensitive(params, "sets")) {
        wp_error_set(error, WP_INVALID_PARAMS, "params.sets",
                     "only with \"wrenches\": a push or gravity sweep takes its \"set\"");
        return false;
    }
    if (!read_sweep_range(params, &state->range, error))
        return false;
    if (state->what == SWEEP_WRENCHES) {
        classify_request *r = &state->request;
        if (!read_sets(params, r, error))
            return false;
        return read_wrench_list(call->limits, params, fixture, NULL, r, error);
    }
    bool push = state->what == SWEEP_PUSH;
    const char *path = push ? "params.push" : "params.gravity";
    const cJSON *what = cJSON_GetObjectItemCaseSensitive(params, push ? "push" : "gravity");
    state->request.set_count = 1;
    if (!wp_check_object(what, path, push ? SWEEP_PUSH_FIELDS : SWEEP_GRAVITY_FIELDS, error) ||
        !read_set_at(what, path, &state->request.sets[0], error) ||
        (push && !read_finger(what, path, &state->finger, error)))
        return false;
    if (push && fixture->shape == WR_SHAPE_NONE) {
        wp_error_set(error, WP_INVALID_PARAMS, "params.fixture.body.shape",
                     "push regions need the part's outline: the fixture has no shape");
        return false;
    }
    return true;
}

static void sweep_free(wp_stream *stream)
{
    if (!stream)
        return;
    sweep_state *state = &stream->u.sweep;
    wr_sweep_job_free(state->job);
    for (int s = 0; s < 3; s++)
        wr_sweeper_free(state->sweepers[s]);
    free(state->request.wrenches);
    free(stream);
}

/* friction.sweep: one of wrenches, push, gravity, against a common mu.
 * Everything is read and the sweepers made before any answer is written;
 * then each step runs the current job for its budget (wr_sweep.h). */
static wp_stream *sweep_begin(wp_call *call, wp_prepared *prepared)
{
    (void)prepared;
    wp_fixture_use *use;
    wp_stream *stream = stream_with_fixture(call, &use);
    if (!stream)
        return NULL;
    sweep_state *state = &stream->u.sweep;
    if (!read_sweep(call, use->fixture, state)) {
        sweep_free(stream);
        return NULL;
    }
    wr_status status = WR_OK;
    for (int s = 0; status == WR_OK && s < state->request.set_count; s++)
        status = wr_sweeper_new(use->fixture, state->request.sets[s], &state->range,
                                &state->sweepers[s]);
    if (status == WR_OK && state->what == SWEEP_PUSH)
        status = wr_sweep_job_push(state->sweepers[0], &state->finger, &state->job);
    else if (status == WR_OK && state->what == SWEEP_GRAVITY)
        status = wr_sweep_job_gravity(state->sweepers[0], &state->job);
    if (status != WR_OK) {
        wp_error_status(call->error, status, "params", "%s", wr_strerror(status));
        sweep_free(stream);
        return NULL;
    }
    return stream;
}

static wp_step sweep_step(wp_stream *stream, wp_call *call, wp_buffer *out, unsigned long budget,
                          unsigned long *used)
{
    sweep_state *state = &stream->u.sweep;
    const classify_request *r = &state->request;
    const wr_stop *stop = call->host->stop;
    size_t start = out->length;
    for (bool first = true; !out->failed; first = false) {
        if (!first && (*used >= budget || out->length - start >= WP_PIECE_BYTES))
            return WP_STEP_MORE;
        if (state->what == SWEEP_WRENCHES) {
            if (!state->opened) {
                state->opened = true;
                WP_BUFFER_LITERAL(out, "{\"results\":[");
            }
            if (state->next >= r->wrench_count) {
                WP_BUFFER_LITERAL(out, "]}");
                return WP_STEP_DONE;
            }
            if (!state->job) {
                wr_status status = wr_sweep_job_wrench(state->sweepers[state->set],
                                                       r->wrenches[state->next], &state->job);
                if (status != WR_OK) {
                    wp_error_status(call->error, status, "params.wrenches", "%s",
                                    wr_strerror(status));
                    return WP_STEP_FAILED;
                }
            }
        }
        bool done;
        wr_status status = wr_sweep_job_run(state->job, budget > *used ? budget - *used : 1, used,
                                            stop, &done);
        if (status != WR_OK) {
            wp_error_status(call->error, status, "params", "%s", wr_strerror(status));
            return WP_STEP_FAILED;
        }
        if (!done)
            continue;
        if (state->what != SWEEP_WRENCHES) {
            write_curve(out, wr_sweep_job_curve(state->job));
            return WP_STEP_DONE;
        }
        /* A wrench's set answered: {"goal": [...], ...} as its sets end. */
        if (state->set == 0)
            wp_buffer_puts(out, state->next ? ",{\"" : "{\"");
        else
            WP_BUFFER_LITERAL(out, ",\"");
        wp_buffer_puts(out, SET_NAMES[r->sets[state->set]]);
        WP_BUFFER_LITERAL(out, "\":");
        write_intervals(out, wr_sweep_job_intervals(state->job));
        wr_sweep_job_free(state->job);
        state->job = NULL;
        if (++state->set == r->set_count) {
            WP_BUFFER_LITERAL(out, "}");
            state->set = 0;
            state->next++;
        }
    }
    return WP_STEP_FAILED; /* out of memory: the buffer says so */
}

static size_t sweep_bytes(const wp_stream *stream)
{
    return sizeof *stream + stream->u.sweep.request.wrench_count * sizeof(double[3]);
}

static const wp_streamer SWEEP_STREAM = {sweep_begin, sweep_step, sweep_free, sweep_bytes, false, NULL, NULL};

/* ---- fixture.design (wp_design.c) -------------------------------------------------- */

static void design_free(wp_stream *stream)
{
    if (!stream)
        return;
    wp_design_free(stream->u.design);
    free(stream);
}

static wp_stream *design_begin(wp_call *call, wp_prepared *prepared)
{
    (void)prepared;
    wp_stream *stream = calloc(1, sizeof *stream);
    if (!stream) {
        wp_error_set(call->error, WP_INTERNAL, "", "out of memory");
        return NULL;
    }
    stream->u.design = wp_design_begin(call);
    if (!stream->u.design) {
        free(stream);
        return NULL;
    }
    return stream;
}

static wp_step design_step(wp_stream *stream, wp_call *call, wp_buffer *out, unsigned long budget,
                           unsigned long *used)
{
    return wp_design_step(stream->u.design, call, out, budget, used);
}

static size_t design_bytes(const wp_stream *stream)
{
    return sizeof *stream + wp_design_bytes(stream->u.design);
}

static bool design_parallel(wp_stream *stream) { return wp_design_parallel(stream->u.design); }

static bool design_work(wp_stream *stream, const wp_host *host)
{
    return wp_design_work(stream->u.design, host);
}

static const wp_streamer DESIGN_STREAM = {design_begin,  design_step,     design_free,
                                          design_bytes,  true,            design_parallel,
                                          design_work};

/* ---- the table ------------------------------------------------------------ */

static const char *const NONE[] = {NULL};
static const char *const FIXTURE[] = {"fixture", NULL};
static const char *const ID[] = {"id", NULL};
static const char *const LIST[] = {"after", "limit", NULL};
static const char *const CLASSIFY[] = {"fixture", "wrenches", "sets", "method", "tolerance",
                                       "fields", NULL};
static const char *const CLASSIFY_REQUIRED[] = {"fixture", "wrenches", NULL};
static const char *const CONE[] = {"fixture", "constraints", NULL};
static const char *const PUSH[] = {"fixture", "set", "finger_friction", "finger_radius", NULL};
static const char *const SWEEP[] = {"fixture", "set", NULL};
static const char *const MARGIN[] = {"fixture", "bias", NULL};
static const char *const DESIGN[] = {"body", "friction", "fixels", "sites", "spacing", "lattice",
                                     "objective", "top", "finger_radius", "finger_friction",
                                     "progress", "shard", "deadline_s", NULL};
static const char *const DESIGN_REQUIRED[] = {"body", "friction", NULL};
static const char *const FRICTION_SWEEP[] = {"fixture", "range", "kinetic_ratio", "wrenches", "sets",
                                             "push", "gravity", NULL};

/* WP_CHEAP: no derivation, no solver, no disk: a batch answers several in
 * one piece, and the event loop may answer it.  The rest end their piece
 * (wp_answer_step); WP_READY ones are light on a ready stored fixture
 * (wp_answer_light).  push.regions is not (a finger with friction samples
 * every edge), nor are cone.get (a cone derived) and stability.margin. */
const wp_method wp_methods[] = {
    {.name = "fixture.put", .handler = fixture_put, .fields = FIXTURE, .required = FIXTURE,
     .summary = "store a fixture; its id depends on its content"},
    {.name = "fixture.get", .handler = fixture_get, .fields = ID, .required = ID,
     .flags = WP_CHEAP, .summary = "the stored fixture"},
    {.name = "fixture.delete", .handler = fixture_delete, .fields = ID, .required = ID,
     .summary = "forget a stored fixture"},
    {.name = "fixture.list", .handler = fixture_list, .fields = LIST, .required = NONE,
     .flags = WP_CHEAP, .summary = "the stored fixtures"},
    {.name = "wrench.classify", .stream = &CLASSIFY_STREAM, .fields = CLASSIFY,
     .required = CLASSIFY_REQUIRED, .flags = WP_FIXTURE | WP_READY, .light = classify_light,
     .summary = "verdicts, margins and blocking transitions of wrenches"},
    {.name = "cone.get", .handler = cone_get, .fields = CONE, .required = CONE, .flags = WP_FIXTURE,
     .summary = "the explicit cone of a constraint string"},
    {.name = "plan.get", .handler = plan_get, .fields = FIXTURE, .required = FIXTURE,
     .flags = WP_FIXTURE | WP_READY, .summary = "contact states, their excluded strings, G_goal's cones"},
    {.name = "modes.get", .handler = modes_get, .fields = FIXTURE, .required = FIXTURE,
     .flags = WP_FIXTURE | WP_READY, .summary = "the feasible moving contact modes"},
    {.name = "server.status", .handler = server_status, .fields = NONE, .required = NONE,
     .flags = WP_CHEAP, .summary = "version, uptime, counts"},
    {.name = "push.regions", .stream = &PUSH_STREAM, .fields = PUSH, .required = FIXTURE,
     .flags = WP_FIXTURE,
     .summary = "the boundary intervals where a finger's push is in a set"},
    {.name = "gravity.sweep", .handler = gravity_sweep, .fields = SWEEP, .required = FIXTURE,
     .flags = WP_FIXTURE | WP_READY, .summary = "the tilts under which gravity is in a set"},
    {.name = "stability.margin", .handler = stability_margin, .fields = MARGIN,
     .required = MARGIN, .flags = WP_FIXTURE, .summary = "how large a disturbance a biasing wrench tolerates"},
    {.name = "friction.sweep", .stream = &SWEEP_STREAM, .fields = FRICTION_SWEEP,
     .required = FIXTURE, .flags = WP_FIXTURE,
     .summary = "where wrenches, push regions and gravity arcs hold, against a common friction"},
    {.name = "fixture.design", .stream = &DESIGN_STREAM, .fields = DESIGN,
     .required = DESIGN_REQUIRED,
     .summary = "the best fixel sites and push for a body: ranked designs"},
    {0},
};

const wp_method *wp_method_find(const char *name)
{
    for (const wp_method *m = wp_methods; m->name; m++)
        if (strcmp(m->name, name) == 0)
            return m;
    return NULL;
}
