/* classify.c -- wrench.classify: its params read and checked, its answer
 * written in chunks of wrenches that helpers may make in parallel. */
#include "common.h"
#include "wp_chunks.h"
#include "methods.h"

#include <assert.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const char *const VERDICT_NAMES[] = {"inside", "boundary", "outside"};

/* wrench.classify's "fields": which parts of each verdict to return. */
enum { FIELD_VERDICT, FIELD_MARGIN, FIELD_BLOCKING, FIELD_STATES, FIELD_WITNESS, FIELD_COUNT };
static const char *const FIELD_NAMES[] = {"verdict", "margin", "blocking", "states", "witness"};
/* Their columns in the lean answer, in this order. */
static const char *const COLUMN_NAMES[] = {"verdicts", "margins", "blocking", "states", "witness"};

/* params.fields: a non-empty array of distinct names of FIELD_NAMES. */
static bool read_fields(const cJSON *params, wp_classify_request *r, wp_error *error)
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

static bool read_classify(const wp_limits *limits, const cJSON *params,
                          const wr_fixture *fixture, wp_prepared *prepared, wp_classify_request *r,
                          wp_error *error)
{
    memset(r, 0, sizeof *r);
    r->tolerance = WR_DEFAULT_TOLERANCE;
    const char *method;
    bool tolerance_given;
    if (!wp_read_sets(params, r, error) || !read_fields(params, r, error) ||
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
    if (r->lp && fixture->tolerance.given) {
        /* The LPs decide the nominal fixture alone. */
        wp_error_set(error, WP_INVALID_PARAMS, "params.method",
                     "the \"lp\" method answers the nominal fixture only; a fixture with a "
                     "tolerance is answered by its cones (\"auto\")");
        return false;
    }
    if (r->lp && tolerance_given) {
        /* The LP method finds no margin, so it has no band to widen. */
        wp_error_set(error, WP_INVALID_PARAMS, "params.tolerance",
                     "the \"lp\" method computes no margin, so it takes no tolerance");
        return false;
    }
    return wp_read_wrenches(limits, params, fixture, prepared, r, error);
}

static void write_blocking(wp_writer *w, const wr_analysis *a, const wr_answer *answer);
static void write_states(wp_writer *w, const wr_analysis *a, const wr_answer *answer);
static void write_witness(wp_writer *w, const wr_analysis *a, const wr_answer *answer);

/* One set's answer V (docs/PROTOCOL.md); with `robust` (may be NULL) an
 * outside's perturbation when it has one. */
static void write_answer(wp_writer *w, const wr_analysis *a, const wr_answer *answer,
                         const wr_robust_answer *robust)
{
    wp_write_object(w);
    wp_write_member_string(w, "verdict", VERDICT_NAMES[answer->verdict]);
    wp_write_member_bool(w, "inside", answer->verdict == WR_VERDICT_INSIDE);
    wp_write_key(w, "margin");
    if (answer->has_margin)
        wp_write_number(w, answer->margin);
    else
        wp_write_null(w);
    wp_write_key(w, "blocking");
    write_blocking(w, a, answer);
    wp_write_key(w, "states");
    write_states(w, a, answer);
    wp_write_key(w, "witness");
    write_witness(w, a, answer);
    if (robust)
        wp_write_perturbation(w, wr_analysis_fixture(a), robust);
    wp_write_object_end(w);
}

/* The blocking string, or null. */
static void write_blocking(wp_writer *w, const wr_analysis *a, const wr_answer *answer)
{
    if (answer->blocking < 0) {
        wp_write_null(w);
        return;
    }
    const wr_cone *cone = wr_analysis_cone(a, answer->blocking_set, answer->blocking);
    char text[WR_CONSTRAINT_TEXT];
    wr_constraint_format(&cone->constraint, text);
    wp_write_string(w, text);
}

/* The contact states a blocking goal string comes from: [] otherwise. */
static void write_states(wp_writer *w, const wr_analysis *a, const wr_answer *answer)
{
    wp_write_array(w);
    if (answer->blocking >= 0 && answer->blocking_set == WR_SET_GOAL) {
        const wr_fixture *f = wr_analysis_fixture(a);
        const wr_plan_origins *origins = &wr_analysis_plan(a)->origins[answer->blocking];
        for (int i = 0; i < origins->count; i++) {
            char state[WR_STATE_TEXT];
            wr_state_format(origins->states[i], f->fixel_count, state);
            wp_write_string(w, state);
        }
    }
    wp_write_array_end(w);
}

/* The witness, or null when inside. */
static void write_witness(wp_writer *w, const wr_analysis *a, const wr_answer *answer)
{
    if (answer->blocking < 0) {
        wp_write_null(w);
        return;
    }
    const wr_fixture *f = wr_analysis_fixture(a);
    const wr_witness *witness = &answer->witness;
    /* Wrenches are classified as given, in the fixture's force unit (a cone
     * is a cone: verdicts and margins do not depend on the scale), so the
     * witness's forces and wrench are in it too; its acceleration, in
     * length / s^2 and rad / s^2, is what those forces give in the model
     * system: times the force factor (1 without units). */
    const double k = wr_fixture_force_factor(f);
    const double acceleration[3] = {witness->acceleration[0] * k, witness->acceleration[1] * k,
                                    witness->acceleration[2] * k};
    wp_write_object(w);
    wp_write_key(w, "acceleration");
    wp_write_numbers(w, acceleration, 3);
    wp_write_key(w, "forces");
    wp_write_array(w);
    for (int i = 0; i < f->fixel_count; i++)
        wp_write_numbers(w, witness->force[i], 2);
    wp_write_array_end(w);
    wp_write_key(w, "wrench");
    wp_write_numbers(w, witness->wrench, 3);
    wp_write_key(w, "friction");
    wp_write_array(w);
    for (int i = 0; i < f->fixel_count; i++) {
        if (isnan(witness->friction[i]))
            wp_write_null(w);
        else
            wp_write_number(w, witness->friction[i]);
    }
    wp_write_array_end(w);
    if (f->supports) {
        wp_write_key(w, "support_forces");
        wp_write_array(w);
        for (int i = 0; i < witness->support_count; i++)
            wp_write_numbers(w, witness->support_force[i], 2);
        wp_write_array_end(w);
        wp_write_key(w, "support_normals");
        wp_write_numbers(w, witness->support_normal, (size_t)witness->support_count);
    }
    wp_write_object_end(w);
}

/* wrench.classify, written in pieces (wp_streamer, wp_method.h): the wrenches
 * are read once, up front, so that a bad one is refused before any answer
 * is written; then the answer is made in chunks of consecutive wrenches by
 * the engine (wp_chunks.h): a chunk's text is made by whichever thread
 * claims it into its record's buffer (or, next in order and made by a step,
 * straight into the answer with the response's writer), and merged into
 * the answer in order.  At most
 * CLASSIFY_WINDOW are made ahead of the one being merged, which bounds what
 * waits in memory.  How many wrenches a chunk has depends on the request
 * alone (the fields and the method), never on the threads, so the same
 * request is answered the same bytes however many workers share it. */
#define CLASSIFY_WINDOW 16
/* A step ends after this much text (or its budget): a piece is where its
 * helpers are forked and joined, and a few chunks a piece keep that cost
 * small.  Still a sixteenth of the default --max-output. */
#define CLASSIFY_PIECE_BYTES (4 * WP_PIECE_BYTES)
/* Verdicts by the map (wr_verdict_map) from this many on: building it costs
 * as much as about that many verdicts measured. */
#define CLASSIFY_MAP_VERDICTS 100000

/* A chunk's record in the engine. */
typedef struct classify_chunk {
    wp_buffer text;
    wr_answer *answers;   /* room for a chunk's answers (columns other than the
                             verdicts), kept for the record's next chunk */
    size_t answers_bytes;
} classify_chunk;

typedef struct classify_state {
    wp_classify_request request;
    wp_fixture_use *use;        /* held by the envelope until the stream's free */
    size_t chunk_wrenches;      /* wrenches per chunk (the last may have fewer) */
    size_t chunk_count;
    wp_chunks *chunks;
    wr_verdict_map *map;        /* a long batch's verdicts, or NULL */
    bool opened;                /* the answer's opening text is written */
    wr_robust *robust;          /* the fixture has a tolerance: robust answers */
    wp_writer *out;             /* the response's writer, set by each step
                                   for its merges and its direct chunks */
} classify_state;

static const wp_chunk_ops CLASSIFY_CHUNKS;

static void classify_free(void *stream)
{
    if (!stream)
        return;
    classify_state *state = stream;
    wp_chunks_free(state->chunks);
    wr_verdict_map_free(state->map);
    wr_robust_free(state->robust);
    free(state->request.wrenches);
    free(stream);
}


static bool verdicts_alone(const wp_classify_request *r)
{
    return r->fields == (1u << FIELD_VERDICT) && !r->lp;
}

/* Wrenches per chunk: about half a millisecond of work and some tens of
 * kilobytes of text, whatever is asked. */
static size_t chunk_wrenches(const wp_classify_request *r)
{
    if (r->lp)
        return 16;
    if (r->fields == (1u << FIELD_VERDICT))
        return 16384;
    if (!(r->fields & ~((1u << FIELD_VERDICT) | (1u << FIELD_MARGIN))) && r->fields)
        return 1024;
    return 256;
}

static void *classify_begin(wp_call *call, wp_prepared *prepared)
{
    wp_fixture_use *use;
    classify_state *state = wp_stream_with_fixture(call, sizeof *state, &use);
    if (!state)
        return NULL;
    state->use = use;
    if (!read_classify(call->limits, call->params, use->fixture, prepared, &state->request,
                       call->error)) {
        classify_free(state);
        return NULL;
    }
    /* Read: the tree of a hundred thousand wrenches (tens of megabytes of
     * nodes) need not live as long as the answer does. */
    cJSON_DeleteItemFromObjectCaseSensitive(call->params, "wrenches");
    const wp_classify_request *r = &state->request;
    state->chunk_wrenches = chunk_wrenches(r);
    state->chunk_count = (r->wrench_count + state->chunk_wrenches - 1) / state->chunk_wrenches;
    /* Verdicts without margins, many of them: by the map.  Built here,
     * before any helper can be reading it. */
    size_t verdicts = verdicts_alone(r) ? r->wrench_count * (size_t)r->set_count : 0;
    if (use->fixture->tolerance.given) {
        if (wr_robust_new(use->analysis, 0, &state->robust) != WR_OK) {
            wp_error_set(call->error, WP_INTERNAL, "", "out of memory");
            classify_free(state);
            return NULL;
        }
        verdicts = 0; /* the map knows the nominal fixture only */
    }
    if (verdicts >= CLASSIFY_MAP_VERDICTS && !wr_analysis_fixture(use->analysis)->supports) {
        wr_status status = wr_verdict_map_new(use->analysis, r->tolerance, &state->map);
        if (status == WR_NO_MEMORY) {
            wp_error_set(call->error, WP_INTERNAL, "", "out of memory");
            classify_free(state);
            return NULL;
        }
        /* Otherwise (it cannot be made for this tolerance) each verdict is
         * measured. */
    }
    state->chunks = wp_chunks_new(&CLASSIFY_CHUNKS, state, state->chunk_count);
    if (!state->chunks) {
        wp_error_set(call->error, WP_INTERNAL, "", "out of memory");
        classify_free(state);
        return NULL;
    }
    return state;
}

/* One wrench's answer for one set, as much of it as the chunk writes. */
static wr_status answer_one(const classify_state *state, const wr_analysis *a, wr_lp_set *goal,
                            wr_lp_set *strong, size_t i, wr_set set, bool verdict_only,
                            bool witness, const wp_host *host, wr_answer *answer)
{
    const wp_classify_request *r = &state->request;
    if (wr_analysis_fixture(a)->supports)
        return wp_supports_answer(a, host, r->wrenches[i], set, r->tolerance, answer);
    if (r->lp)
        return wr_classify_lp(a, goal, strong, r->wrenches[i], set, answer);
    if (state->robust) {
        wr_robust_answer robust;
        wr_status status = wr_robust_classify(state->robust, r->wrenches[i], set, r->tolerance,
                                              &robust);
        *answer = robust.answer;
        return status;
    }
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
                                   wr_lp_set *goal, wr_lp_set *strong, const wp_host *host,
                                   wr_set set, size_t from, size_t to, wr_answer *answers,
                                   wp_writer *out, size_t *failed)
{
    const wr_stop *stop = host->stop;
    const wp_classify_request *r = &state->request;
    bool witness = r->fields & (1u << FIELD_WITNESS);
    static const char LETTERS[] = {'i', 'b', 'o'};
    if (verdicts_alone(r)) {
        /* The letters straight into the text: nothing else is kept. */
        wp_write_key(out, "verdicts");
        char *room = wp_write_string_room(out, to - from);
        if (!room)
            return WR_OK; /* the buffer says so */
        for (size_t i = from; i < to; i++) {
            wr_answer answer;
            wr_status status = (i - from) % STOP_POLL == 0 && wr_stop_requested(stop)
                                   ? WR_STOPPED
                                   : answer_one(state, a, goal, strong, i, set, true, false,
                                                host, &answer);
            if (status != WR_OK) {
                /* The answer ends here: the room not filled is taken back. */
                out->out->length = (size_t)(room - out->out->data) - 1;
                out->out->data[out->out->length] = 0;
                *failed = i;
                return status;
            }
            room[i - from] = LETTERS[answer.verdict];
        }
        return WR_OK;
    }
    for (size_t i = from; i < to; i++) {
        if ((i - from) % STOP_POLL == 0 && wr_stop_requested(stop)) {
            *failed = i;
            return WR_STOPPED;
        }
        wr_status status =
            answer_one(state, a, goal, strong, i, set, false, witness, host, &answers[i - from]);
        if (status != WR_OK) {
            *failed = i;
            return status;
        }
    }
    for (int column = 0; column < FIELD_COUNT; column++) {
        if (!(r->fields & (1u << column)))
            continue;
        wp_write_key(out, COLUMN_NAMES[column]);
        if (column == FIELD_VERDICT) {
            char *room = wp_write_string_room(out, to - from);
            if (!room)
                return WR_OK; /* the buffer says so */
            for (size_t i = from; i < to; i++)
                room[i - from] = LETTERS[answers[i - from].verdict];
            continue;
        }
        wp_write_array(out);
        for (size_t i = from; i < to; i++) {
            const wr_answer *answer = &answers[i - from];
            if (column == FIELD_MARGIN) {
                if (answer->has_margin)
                    wp_write_number(out, answer->margin);
                else
                    wp_write_null(out);
            } else if (column == FIELD_BLOCKING) {
                write_blocking(out, a, answer);
            } else if (column == FIELD_STATES) {
                write_states(out, a, answer);
            } else {
                write_witness(out, a, answer);
            }
        }
        wp_write_array_end(out);
    }
    return WR_OK;
}

/* Chunk `index`'s values with `out`, with the thread's own LP sets: rows,
 * or a lean piece {"count": n, "goal": {...}, ...}.  Not WR_OK: it failed
 * at wrench *failed (WR_STOPPED: the client is gone). */
static wr_status make_chunk(const classify_state *state, size_t index, wr_answer **answers,
                            const wp_host *host,
                            wp_error *error, wp_writer *out, size_t *failed)
{
    const wp_classify_request *r = &state->request;
    const wr_analysis *a = state->use->analysis;
    wr_lp_set *goal = NULL, *strong = NULL;
    *failed = 0;
    wr_status sets = r->lp ? host->lp_sets(host->self, state->use, &goal, &strong) : WR_OK;
    if (sets != WR_OK) {
        wp_error_status(error, sets, "", "%s", wr_strerror(sets));
        return WR_NO_MEMORY;
    }
    size_t from = index * state->chunk_wrenches;
    size_t to = from + state->chunk_wrenches < r->wrench_count ? from + state->chunk_wrenches
                                                               : r->wrench_count;
    if (r->fields) {
        if (!verdicts_alone(r) && !*answers &&
            !(*answers = malloc(state->chunk_wrenches * sizeof **answers)))
            return WR_NO_MEMORY;
        wp_write_object(out);
        wp_write_member_number(out, "count", (double)(to - from));
        wr_status status = WR_OK;
        for (int s = 0; s < r->set_count && status == WR_OK; s++) {
            wp_write_key(out, wp_set_names[r->sets[s]]);
            wp_write_object(out);
            status = write_set_columns(state, a, goal, strong, host, r->sets[s], from, to,
                                       *answers, out, failed);
            if (status == WR_OK)
                wp_write_object_end(out);
        }
        if (status == WR_OK)
            wp_write_object_end(out);
        return status;
    }
    for (size_t i = from; i < to; i++) {
        if ((i - from) % STOP_POLL == 0 && wr_stop_requested(host->stop)) {
            *failed = i;
            return WR_STOPPED;
        }
        wp_write_object(out);
        for (int s = 0; s < r->set_count; s++) {
            wr_robust_answer robust = {.has_perturbation = false};
            wr_status status =
                state->robust ? wr_robust_classify(state->robust, r->wrenches[i], r->sets[s],
                                                   r->tolerance, &robust)
                              : answer_one(state, a, goal, strong, i, r->sets[s], false, true,
                                           host, &robust.answer);
            if (status != WR_OK) {
                *failed = i;
                return status;
            }
            wp_write_key(out, wp_set_names[r->sets[s]]);
            write_answer(out, a, &robust.answer, &robust);
        }
        wp_write_object_end(out);
    }
    return WR_OK;
}

/* Work units per wrench, for the budget: a wrench against a cone is one,
 * a verdict by the map about one, an LP sixty-four. */
static unsigned long wrench_cost(const classify_state *state)
{
    const wp_classify_request *r = &state->request;
    const wr_analysis *a = state->use->analysis;
    unsigned long cones = 0;
    for (int s = 0; s < r->set_count; s++)
        cones += (unsigned long)(r->sets[s] == WR_SET_BOTH
                                     ? wr_analysis_cone_count(a, WR_SET_GOAL) +
                                           wr_analysis_cone_count(a, WR_SET_STRONG)
                                     : wr_analysis_cone_count(a, r->sets[s]));
    return state->map ? (unsigned long)r->set_count : r->lp ? 64 * (cones + 1) : cones + 1;
}

/* The engine's make: chunk `index` into its record's text, or straight into
 * the answer (`direct`).  A failure is said as the chunk's turn comes. */
static wr_status classify_make(void *method, size_t index, void *record, wp_buffer *direct,
                               const wp_host *host, unsigned long *used, wp_error *error)
{
    const classify_state *state = method;
    classify_chunk *chunk = record;
    assert(chunk->text.length == 0);
    size_t failed;
    /* Made by a step, next in order: with the response's writer, which
     * knows whether a comma is due; else a sequence of values that the
     * merge puts into the answer. */
    assert(!direct || direct == state->out->out);
    wp_writer alone = wp_writer_in_array(&chunk->text);
    wr_status status = make_chunk(state, index, &chunk->answers, host, error,
                                  direct ? state->out : &alone, &failed);
    if (status == WR_OK && !direct && chunk->text.failed)
        status = WR_NO_MEMORY;
    chunk->answers_bytes = chunk->answers ? state->chunk_wrenches * sizeof *chunk->answers : 0;
    *used += wrench_cost(state) * state->chunk_wrenches;
    if (status == WR_LP_FAILED)
        wp_error_status(error, status, "params.wrenches",
                        "GLPK failed on wrench %zu; nothing was answered", failed);
    else if (status != WR_OK)
        wp_error_status(error, status, "params.wrenches", "%s", wr_strerror(status));
    return status;
}

/* The engine's merge: the record's text into the answer. */
static wr_status classify_merge(void *method, size_t index, void *record, wp_buffer *out,
                                wp_error *error)
{
    (void)index;
    (void)error;
    const classify_state *state = method;
    classify_chunk *chunk = record;
    assert(out == state->out->out);
    wp_write_raw(state->out, chunk->text.data, chunk->text.length);
    chunk->text.length = 0;
    /* A long batch's records keep their capacity; a short one's go. */
    if (state->chunk_count <= CLASSIFY_WINDOW) {
        free(chunk->text.data);
        memset(&chunk->text, 0, sizeof chunk->text);
    }
    return WR_OK;
}

static void classify_chunk_release(void *record)
{
    classify_chunk *chunk = record;
    free(chunk->text.data);
    free(chunk->answers);
}

/* The text's room and the answers' (state->chunk_wrenches of them). */
static size_t classify_chunk_bytes(const void *record)
{
    const classify_chunk *chunk = record;
    return chunk->text.capacity + chunk->answers_bytes;
}

static const wp_chunk_ops CLASSIFY_CHUNKS = {
    .record_size = sizeof(classify_chunk),
    .make = classify_make,
    .merge = classify_merge,
    .release = classify_chunk_release,
    .bytes = classify_chunk_bytes,
    .direct = true,
    .window = CLASSIFY_WINDOW,
};

static bool classify_parallel(void *stream)
{
    return wp_chunks_parallel(((classify_state *)stream)->chunks);
}

static bool classify_work(void *stream, const wp_host *host)
{
    return wp_chunks_work(((classify_state *)stream)->chunks, host);
}

static wp_step classify_step(void *stream, wp_call *call, wp_writer *out,
                             unsigned long budget, unsigned long *used)
{
    classify_state *state = stream;
    const wp_classify_request *r = &state->request;
    bool shared = wp_chunks_shared(state->chunks);
    state->out = out;
    if (!state->opened) {
        state->opened = true;
        wp_write_object(out);
        if (r->fields) {
            wp_write_member_number(out, "count", (double)r->wrench_count);
            wp_write_key(out, "pieces");
        } else {
            wp_write_key(out, "results");
        }
        wp_write_array(out);
    }
    /* A request's first chunk fails, if it does, in the first step, while
     * its text can still be taken back. */
    wp_step step = wp_chunks_run(state->chunks, shared, call->host, out->out, budget, used,
                                 CLASSIFY_PIECE_BYTES, call->error);
    if (step != WP_STEP_DONE)
        return step;
    wp_write_array_end(out);
    wp_write_object_end(out);
    return out->out->failed ? WP_STEP_FAILED : WP_STEP_DONE;
}

static size_t classify_bytes(const void *stream)
{
    const classify_state *state = stream;
    size_t bytes = sizeof *state + state->request.wrench_count * sizeof *state->request.wrenches;
    return bytes + wp_chunks_bytes(state->chunks) +
           (state->map ? wr_verdict_map_bytes(state->map) : 0);
}

const wp_streamer wp_classify_stream = {classify_begin,   classify_step, classify_free,
                                            classify_bytes,   false,         classify_parallel,
                                            classify_work};

/* Light enough for an event loop: the explicit cones (no GLPK), and few
 * wrenches against few cones. */
bool wp_classify_light(const cJSON *params, int cones)
{
    const cJSON *how = cJSON_GetObjectItemCaseSensitive(params, "method");
    const cJSON *wrenches = cJSON_GetObjectItemCaseSensitive(params, "wrenches");
    if ((how && !(cJSON_IsString(how) && strcmp(how->valuestring, "auto") == 0)) ||
        !cJSON_IsArray(wrenches))
        return false;
    long count = cJSON_GetArraySize(wrenches);
    return count <= WP_LIGHT_CONE_CHECKS && count * (cones > 0 ? cones : 1) <= WP_LIGHT_CONE_CHECKS;
}
