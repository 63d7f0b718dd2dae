/* wp_rpc.c -- the JSON-RPC 2.0 envelope: one line in, one line out. */
#include "wp_method.h"

#include <assert.h>
#include <ctype.h>
#include <math.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const char *message_of(int code)
{
    switch (code) {
    case WP_PARSE_ERROR: return "Parse error";
    case WP_INVALID_REQUEST: return "Invalid Request";
    case WP_NO_METHOD: return "Method not found";
    case WP_INVALID_PARAMS: return "Invalid params";
    case WP_NO_FIXTURE: return "No such fixture";
    case WP_STORAGE: return "Storage failure";
    case WP_LIMIT: return "Limit exceeded";
    case WP_SOLVER: return "Solver failure";
    case WP_ACCESS: return "Access denied";
    default: return "Internal error";
    }
}

/* {"jsonrpc":"2.0","error":{...},"id":<id>} with id text (e.g. "null"). */
static void write_error(wp_buffer *b, const wp_error *error, const char *id)
{
    wp_writer w = wp_writer_on(b);
    wp_write_object(&w);
    wp_write_key(&w, "jsonrpc");
    wp_write_string(&w, "2.0");
    wp_write_key(&w, "error");
    wp_write_object(&w);
    wp_write_key(&w, "code");
    wp_write_number(&w, error->code);
    wp_write_key(&w, "message");
    wp_write_string(&w, message_of(error->code));
    wp_write_key(&w, "data");
    wp_write_object(&w);
    wp_write_key(&w, "field");
    wp_write_string(&w, error->field);
    wp_write_key(&w, "reason");
    wp_write_string(&w, error->reason);
    wp_write_object_end(&w);
    wp_write_object_end(&w);
    wp_write_key(&w, "id");
    wp_write_raw(&w, id, strlen(id));
    wp_write_object_end(&w);
}

/* A response's opening, {"jsonrpc":"2.0","result": -- its result follows. */
/* A response's closing, after its result (opened by wp_call_open_result):
 * its id, text such as "null". */
static void write_response_close(wp_writer *w, const char *id_text)
{
    const char *id = id_text ? id_text : "null";
    wp_write_key(w, "id");
    wp_write_raw(w, id, strlen(id));
    wp_write_object_end(w);
}

char *wp_error_line(int code, const char *field, const char *reason)
{
    wp_error error;
    wp_error_set(&error, code, field, "%s", reason);
    wp_buffer b = {0};
    write_error(&b, &error, "null");
    wp_buffer_puts(&b, "\n");
    return wp_buffer_take(&b);
}

static const char *const ENVELOPE_FIELDS[] = {"jsonrpc", "method", "params", "id", NULL};


struct wp_answer {
    wp_limits limits;
    cJSON *json;             /* the parsed line; NULL when refused */
    char *refusal;           /* the whole answer of a refused line */
    bool batch;
    bool whole;              /* no pieces: one step writes all (wp_answer_line) */
    unsigned long budget;    /* work units per piece (WP_PIECE_BUDGET) */
    size_t piece_bytes;      /* bytes after which a piece ends (WP_PIECE_BYTES) */
    cJSON *next;             /* the next request to start, or NULL */
    bool opened;             /* a batch's "[" is written */
    size_t stream_written;   /* bytes the current stream's steps have written */
    wp_writer response;      /* the current stream's response, across its pieces */
    bool done;
    wp_prepared prepared;    /* params' member read from the text (wp_method.h) */
    wp_fixture_hold hold;    /* the request in hand's fixture (wp_method.h) */
    /* The request in progress, when its result is written in pieces. */
    const wp_streamer *streamer;
    void *stream;            /* the streamer's own state */
    cJSON *params;           /* its params (in `json`, or `empty`) */
    cJSON *empty;            /* {} for a request without params */
    char *id_text;           /* its id as answered (malloc'd) */
    size_t bytes;            /* wp_answer_bytes */
    /* A long batch is read a request at a time (after the whole line was
     * parsed once, to refuse it whole if it is not JSON, and the tree
     * freed): its text, the spans of the requests not yet begun, and the
     * tree of the one in hand.  So a batch whose answer waits on a slow
     * reader holds its text and one request's tree, not the tree of every
     * request in it (forty times the text). */
    char *text;
    size_t (*spans)[2];
    size_t span_count, span_next;
    cJSON *member;
};

static void release_fixture(wp_answer *answer, const wp_host *host)
{
    if (answer->hold.holding)
        host->fixture_release(host->self, &answer->hold.use);
    answer->hold.holding = false;
    free(answer->hold.text);
    answer->hold.text = NULL;
    answer->hold.text_length = 0;
}

/* What the envelope of one request says: an error found in it, its id as
 * the answer echoes it, and whether it is a notification.  Returns whether
 * it is valid. */
static bool read_envelope(const cJSON *request, wp_error *error, char **id_text,
                          bool *notification)
{
    *id_text = NULL;
    *notification = false;
    const cJSON *id = cJSON_IsObject(request) ? cJSON_GetObjectItemCaseSensitive(request, "id")
                                             : NULL;
    if (!cJSON_IsObject(request)) {
        wp_error_set(error, WP_INVALID_REQUEST, "", "a request is an object, not %s",
                     wp_type_name(request));
        return false;
    }
    if (id && !cJSON_IsString(id) && !cJSON_IsNumber(id) && !cJSON_IsNull(id)) {
        wp_error_set(error, WP_INVALID_REQUEST, "id", "must be a string, a number or null");
        return false;
    }
    if (cJSON_IsNumber(id) && !isfinite(id->valuedouble)) {
        /* It could not be echoed: JSON has no infinities. */
        wp_error_set(error, WP_INVALID_REQUEST, "id", "must be a finite number");
        return false;
    }
    if (id && !cJSON_IsNull(id)) {
        /* The id is echoed as the client wrote it: a number's own text
         * (kept by wp_json_keep_id_text), a string's canonical text; out of
         * memory: answered under id null. */
        *id_text = wp_json_id_text(id);
        if (!*id_text) {
            wp_error_set(error, WP_INTERNAL, "", "out of memory");
            return false;
        }
    }
    const cJSON *version = cJSON_GetObjectItemCaseSensitive(request, "jsonrpc");
    const cJSON *method = cJSON_GetObjectItemCaseSensitive(request, "method");
    wp_error envelope;
    bool valid = false;
    if (!wp_check_object(request, "", ENVELOPE_FIELDS, &envelope))
        wp_error_set(error, WP_INVALID_REQUEST, envelope.field, "%s", envelope.reason);
    else if (!cJSON_IsString(version) || strcmp(version->valuestring, "2.0") != 0)
        wp_error_set(error, WP_INVALID_REQUEST, "jsonrpc", "must be \"2.0\"");
    else if (!cJSON_IsString(method))
        wp_error_set(error, WP_INVALID_REQUEST, "method", "must be a string, not %s",
                     wp_type_name(method));
    else
        valid = true;
    /* Only a valid request without an id is a notification: an invalid one
     * is answered (with id null if it has none). */
    *notification = valid && id == NULL;
    return valid;
}

/* The method a valid request names, its params checked against the table:
 * NULL with `error` set when there is none or the params do not fit. */
static const wp_method *find_method(const cJSON *request, const cJSON *params, wp_error *error)
{
    const cJSON *method = cJSON_GetObjectItemCaseSensitive(request, "method");
    const wp_method *m = wp_method_find(method->valuestring);
    if (!m) {
        wp_error_set(error, WP_NO_METHOD, "method", "no method named \"%.64s\"",
                     method->valuestring);
        return NULL;
    }
    if (!wp_check_object(params, "params", m->fields, error))
        return NULL;
    for (const char *const *name = m->required; *name; name++)
        if (!cJSON_GetObjectItemCaseSensitive(params, *name)) {
            char field[WP_FIELD_MAX];
            wp_path_key(field, "params", *name);
            wp_error_set(error, WP_INVALID_PARAMS, field, "required");
            return NULL;
        }
    return m;
}

/* Before a request's answer in a batch: "[" or ",". */
static void separate(wp_answer *answer, wp_buffer *out)
{
    if (!answer->batch)
        return;
    wp_buffer_puts(out, answer->opened ? "," : "[");
    answer->opened = true;
}

static void write_error_answer(wp_answer *answer, wp_buffer *out, const wp_error *error,
                               const char *id_text)
{
    separate(answer, out);
    write_error(out, error, id_text ? id_text : "null");
}

/* The call of the request in hand, for its handler or stream. */
static wp_call call_of(wp_answer *answer, const wp_host *host, cJSON *params, wp_error *error,
                       const char *id_text)
{
    return (wp_call){host, &answer->limits, params, error, &answer->hold,
                     id_text ? id_text : "null", !answer->batch && !answer->whole,
                     answer->batch || !answer->prepared.text ? NULL : &answer->prepared};
}

static void end_stream(wp_answer *answer, const wp_host *host)
{
    if (answer->stream)
        answer->streamer->free(answer->stream);
    answer->stream = NULL;
    answer->streamer = NULL;
    answer->params = NULL;
    cJSON_Delete(answer->empty);
    answer->empty = NULL;
    free(answer->id_text);
    answer->id_text = NULL;
    release_fixture(answer, host);
}

/* Go on with the request whose result is written in pieces.  `mine` says
 * whether its text began in this piece (so that a failure can still take
 * it back and answer the error in its place). */
static wp_step continue_stream(wp_answer *answer, const wp_host *host, wp_buffer *out,
                               size_t start, bool mine, unsigned long *used, wp_counts *counts)
{
    wp_error error = {0};
    wp_call call = call_of(answer, host, answer->params, &error, answer->id_text);
    unsigned long budget = answer->whole ? (unsigned long)-1 : answer->budget;
    size_t before = out->length;
    answer->response.out = out;
    wp_step step = answer->streamer->step(answer->stream, &call, &answer->response, budget, used);
    while (step == WP_STEP_MORE && answer->whole) {
        *used = 0;
        step = answer->streamer->step(answer->stream, &call, &answer->response, budget, used);
    }
    /* A stream that opens its own response and has written nothing in
     * earlier pieces (no notification either) can still be answered an
     * error, outside a batch (whose separator went out before). */
    bool untouched = answer->streamer->opens_result && !answer->batch &&
                     answer->stream_written == 0;
    answer->stream_written += out->length - before;
    if (step == WP_STEP_MORE)
        return WP_STEP_MORE;
    if (step == WP_STEP_DONE) {
        write_response_close(&answer->response, answer->id_text);
        end_stream(answer, host);
        return WP_STEP_DONE;
    }
    counts->errors++;
    if (!mine && untouched)
        start = before; /* nothing of it went out: answer the error instead */
    else if (!mine) {
        end_stream(answer, host);
        return WP_STEP_FAILED;
    }
    /* Its text is all in this piece: answer the error in its place.  In a
     * batch `start` is before the member's separator; when that was the
     * batch's "[", it goes with the rest and the error's separator opens
     * the batch again. */
    bool took_open = answer->batch && out->length > start && out->data[start] == '[';
    out->length = start;
    if (took_open)
        answer->opened = false;
    write_error_answer(answer, out, &error, answer->id_text);
    end_stream(answer, host);
    return WP_STEP_DONE;
}

/* Start the next request of the line and answer it, or begin writing its
 * result in pieces.  Returns whether it was cheap. */
static bool start_request(wp_answer *answer, const wp_host *host, wp_buffer *out,
                          unsigned long *used, wp_counts *counts, wp_step *stream_step)
{
    cJSON *request = answer->next;
    answer->next = answer->batch ? request->next : NULL;
    counts->requests++;
    *stream_step = WP_STEP_DONE;
    wp_error error = {0};
    char *id_text = NULL;
    bool notification = false;
    const wp_method *m = NULL;
    cJSON *params = NULL, *empty = NULL;
    if (read_envelope(request, &error, &id_text, &notification)) {
        params = cJSON_GetObjectItemCaseSensitive(request, "params");
        if (!params)
            params = empty = cJSON_CreateObject();
        if (!params)
            wp_error_set(&error, WP_INTERNAL, "", "out of memory");
        else
            m = find_method(request, params, &error);
    }
    bool cheap = !m || (m->flags & WP_CHEAP);
    wp_call call = call_of(answer, host, params, &error, id_text);
    if (m && m->stream) {
        void *stream = m->stream->begin(&call, answer->batch ? NULL : &answer->prepared);
        if (stream && notification) {
            /* Nobody will read it: nothing to compute. */
            m->stream->free(stream);
        } else if (stream) {
            size_t start = out->length;
            separate(answer, out);
            answer->streamer = m->stream;
            answer->stream = stream;
            answer->stream_written = 0;
            answer->params = params;
            answer->empty = empty;
            empty = NULL;
            answer->id_text = id_text;
            id_text = NULL;
            answer->bytes = 4096 + (m->stream->bytes ? m->stream->bytes(stream) : 0);
            answer->response = wp_writer_on(out);
            if (!m->stream->opens_result)
                wp_call_open_result(&call, &answer->response);
            /* `start` is before the "," or "[": a failure takes it all back. */
            *stream_step = continue_stream(answer, host, out, start, true, used, counts);
        } else {
            counts->errors++;
            if (!notification)
                write_error_answer(answer, out, &error, id_text);
        }
    } else {
        /* The result is written in its place; a handler that fails takes
         * back what it wrote, and the error is answered instead. */
        if (!notification)
            separate(answer, out);
        size_t opened = out->length;
        wp_writer w = wp_writer_on(out);
        wp_call_open_result(&call, &w);
        bool ok = m && m->handler(&call, &w);
        if (ok)
            write_response_close(&w, id_text);
        if (!ok || notification) {
            out->length = opened; /* (a notification wrote no separator) */
            if (out->data)
                out->data[out->length] = 0;
        }
        if (!ok) {
            counts->errors++;
            if (!notification)
                write_error(out, &error, id_text ? id_text : "null");
        }
    }
    /* The flags, acted on here and only here: the fixture wp_call_fixture
     * acquired for the call is released after it (after its last piece). */
    if (!answer->stream)
        release_fixture(answer, host);
    cJSON_Delete(empty);
    free(id_text);
    return cheap;
}

/* A parse that fails for want of memory is not a line that is not JSON:
 * cJSON says neither, so its allocations go through this, which notes a
 * failure for the thread that parses (cJSON's hooks are process-wide,
 * installed once). */
static _Thread_local bool parse_out_of_memory;

static void *noting_malloc(size_t size)
{
    void *p = malloc(size);
    if (!p)
        parse_out_of_memory = true;
    return p;
}

static void install_hooks(void)
{
    cJSON_Hooks hooks = {noting_malloc, free};
    cJSON_InitHooks(&hooks);
}

/* The refusal of a line that ran out of memory while it was parsed: -32603
 * (documented for it), under the request's id when the line is one request
 * whose id can be read from the text (a string or a number, echoed as
 * written), else under null. */
static cJSON *refuse_out_of_memory(char **refusal, const char *text, size_t length)
{
    size_t start, end;
    const char *id = "null";
    char *written = NULL;
    if (wp_json_member(text, length, 0, "id", &start, &end) && end > start &&
        (text[start] == '"' || text[start] == '-' || isdigit((unsigned char)text[start]))) {
        written = malloc(end - start + 1);
        if (written) {
            memcpy(written, text + start, end - start);
            written[end - start] = 0;
            id = written;
        }
    }
    wp_error error;
    wp_error_set(&error, WP_INTERNAL, "", "out of memory while reading the request");
    wp_buffer b = {0};
    write_error(&b, &error, id);
    wp_buffer_puts(&b, "\n");
    free(written);
    *refusal = wp_buffer_take(&b);
    return NULL;
}

/* parse_line's refusal: the answer in *refusal, no JSON. */
static cJSON *refuse(char **refusal, int code, const char *reason)
{
    *refusal = wp_error_line(code, "", reason);
    return NULL;
}

/* The JSON of a request line, or NULL with *refusal set to the answer
 * (malloc'd) when the line is refused before any request in it is read. */
static cJSON *parse_line(const wp_limits *limits, const char *line, size_t length,
                         wp_counts *counts, char **refusal)
{
    while (length > 0 && isspace((unsigned char)line[length - 1]))
        length--;
    size_t start = 0;
    while (start < length && isspace((unsigned char)line[start]))
        start++;
    if (start == length) {
        counts->requests++;
        counts->errors++;
        return refuse(refusal, WP_PARSE_ERROR, "an empty line is not a JSON text");
    }
    if (!wp_utf8_valid(line, length)) {
        counts->requests++;
        counts->errors++;
        return refuse(refusal, WP_PARSE_ERROR, "the line is not valid UTF-8");
    }
    wp_json_shape shape = wp_json_scan(line, length, limits->max_depth);
    if (shape.depth > limits->max_depth) {
        counts->requests++;
        counts->errors++;
        char reason[96];
        snprintf(reason, sizeof reason, "JSON nested deeper than %d levels", limits->max_depth);
        return refuse(refusal, WP_INVALID_REQUEST, reason);
    }
    if (shape.control) {
        counts->requests++;
        counts->errors++;
        return refuse(refusal, WP_PARSE_ERROR,
                      "a control character where JSON allows none (raw in a string, or "
                             "as white space)");
    }
    if (shape.bad_escape) {
        counts->requests++;
        counts->errors++;
        return refuse(refusal, WP_PARSE_ERROR,
                      "an escape JSON does not allow in a string (\\u takes four hex digits)");
    }
    if (shape.nul_escape) {
        /* cJSON would cut the string at the NUL and answer for another
         * request ("fixture.list\u0000x" as "fixture.list"): refuse it. */
        counts->requests++;
        counts->errors++;
        return refuse(refusal, WP_INVALID_REQUEST,
                      "a string holds \\u0000 (U+0000), which wrenchd does not accept");
    }
    static pthread_once_t hooks_installed = PTHREAD_ONCE_INIT;
    pthread_once(&hooks_installed, install_hooks);
    parse_out_of_memory = false;
    const char *end = NULL;
    cJSON *json = cJSON_ParseWithLengthOpts(line + start, length - start, &end, false);
    if (!json && parse_out_of_memory) {
        counts->requests++;
        counts->errors++;
        return refuse_out_of_memory(refusal, line + start, length - start);
    }
    if (json && end == line + length && shape.number_problem) {
        /* cJSON read it, but RFC 8259 does not allow it (a leading zero
         * would be octal to some readers): not JSON. */
        cJSON_Delete(json);
        counts->requests++;
        counts->errors++;
        char reason[160];
        snprintf(reason, sizeof reason, "the number %.*s%s %s, which JSON (RFC 8259) does not allow",
                 (int)(shape.number_length > 40 ? 40 : shape.number_length),
                 line + shape.number_at, shape.number_length > 40 ? "..." : "",
                 shape.number_problem);
        return refuse(refusal, WP_PARSE_ERROR, reason);
    }
    if (!json || end != line + length) {
        cJSON_Delete(json);
        counts->requests++;
        counts->errors++;
        return refuse(refusal, WP_PARSE_ERROR, json ? "text after the JSON value"
                                                      : "the line is not valid JSON");
    }
    if (!wp_json_keep_id_text(json, line + start, length - start)) {
        cJSON_Delete(json);
        counts->requests++;
        counts->errors++;
        return refuse(refusal, WP_INTERNAL, "out of memory");
    }
    return json;
}

/* Light work, by the method table's flags (the policy in wp_rpc.h). */
bool wp_answer_light(wp_answer *answer, const wp_host *host)
{
    if (answer->refusal)
        return true; /* refusing a line is light */
    const cJSON *json = answer->json;
    if (answer->batch)
        return false; /* a batch may be work */
    const cJSON *method = cJSON_GetObjectItemCaseSensitive(json, "method");
    const cJSON *params = cJSON_GetObjectItemCaseSensitive(json, "params");
    if (!cJSON_IsObject(json) || !cJSON_IsString(method))
        return true; /* an invalid request */
    const wp_method *m = wp_method_find(method->valuestring);
    if (!m || (m->flags & WP_CHEAP))
        return true; /* no such method: an error answer */
    if (!(m->flags & WP_READY) || !cJSON_IsObject(params) || !host->fixture_use_ready)
        return false;
    const cJSON *id = cJSON_GetObjectItemCaseSensitive(params, "fixture");
    if (!cJSON_IsString(id) || !wp_fixture_id_valid(id->valuestring))
        return false;
    if (answer->hold.holding)
        return false; /* held since begin: a long line, never light */
    int cones = host->fixture_use_ready(host->self, id->valuestring, &answer->hold.use);
    answer->hold.holding = cones >= 0;
    if (cones < 0)
        return false;
    /* On supports every answer solves LPs, disc by disc; with a tolerance
     * it searches boxes of the perturbation set: whatever the method,
     * never light (the hold is the worker's). */
    const wr_fixture *f = answer->hold.use.fixture;
    if (f->supports || f->tolerance.given)
        return false;
    return !m->light || m->light(params, cones);
}


/* Lines from this long on are worth reading without a tree node per number. */
#define PREPARE_BYTES 65536

/* The method a line names, found from the text, the name quoted as
 * written (an escaped name takes the ordinary way); NULL when its row
 * reads nothing from the text. */
static const wp_method *raw_method(const char *line, size_t length)
{
    size_t start, end;
    if (!wp_json_member(line, length, 0, "method", &start, &end))
        return NULL;
    const char *quoted = line + start;
    size_t n = end - start;
    for (const wp_method *m = wp_methods; m->name; m++)
        if ((m->raw_array || m->raw_text) && n == strlen(m->name) + 2 && quoted[0] == '"' &&
            quoted[n - 1] == '"' && memcmp(quoted + 1, m->name, n - 2) == 0)
            return m;
    return NULL;
}

/* A copy of the line with [] in place of text[start, end). */
static char *cut(const char *line, size_t length, size_t start, size_t end, size_t *copy_length)
{
    char *copy = malloc(length - (end - start) + 3);
    if (!copy)
        return NULL;
    memcpy(copy, line, start);
    memcpy(copy + start, "[]", 2);
    memcpy(copy + start + 2, line + end, length - end);
    *copy_length = length - (end - start) + 2;
    copy[*copy_length] = 0;
    return copy;
}

/* A line of a method with a raw_array or raw_text (wp_method.h), which the
 * scan has passed: read that member of params straight from the text (a
 * raw_array when the line is long and the member is the common shape,
 * arrays of three numbers; a raw_text as it is written), and return a copy
 * of the line with [] in its place for the tree; NULL for the ordinary
 * way. */
static char *prepare(const wp_method *m, const char *line, size_t length,
                     wp_prepared *prepared, size_t *copy_length)
{
    size_t params_start, start, end;
    if (!wp_json_member_start(line, length, 0, "params", &params_start))
        return NULL;
    if (m->raw_text) {
        /* The parse of the line never sees the member: its syntax is
         * checked here, or the line is read the ordinary way. */
        if (!wp_json_member(line, length, params_start, m->raw_text, &start, &end) ||
            !wp_json_valid(line + start, end - start))
            return NULL;
        char *text = malloc(end - start + 1);
        char *copy = text ? cut(line, length, start, end, copy_length) : NULL;
        if (!copy) {
            free(text);
            return NULL;
        }
        memcpy(text, line + start, end - start);
        text[end - start] = 0;
        prepared->text = text;
        prepared->length = end - start;
        return copy;
    }
    /* Neither params nor its array is spanned before it is read: a
     * million wrenches are 30 MB of text. */
    if (length < PREPARE_BYTES ||
        !wp_json_member_start(line, length, params_start, m->raw_array, &start))
        return NULL;
    double (*wrenches)[3];
    size_t read;
    long count = wp_json_triples(line + start, length - start, &wrenches, &read);
    if (count < 0)
        return NULL;
    char *copy = cut(line, length, start, start + read, copy_length);
    if (!copy) {
        free(wrenches);
        return NULL;
    }
    prepared->wrenches = wrenches;
    prepared->count = (size_t)count;
    return copy;
}

/* Keep a long batch as text and spans (wp_answer's `text`), its tree
 * freed; left as a tree when out of memory. */
static void read_lazily(wp_answer *answer, const char *line, size_t length, size_t members)
{
    char *text = malloc(length + 1);
    size_t (*spans)[2] = malloc(members * sizeof *spans);
    if (!text || !spans) {
        free(text);
        free(spans);
        return;
    }
    memcpy(text, line, length);
    text[length] = 0;
    size_t i = wp_json_skip_space(text, 0, length);
    assert(text[i] == '[');
    i = wp_json_skip_space(text, i + 1, length);
    size_t n = 0;
    while (i < length && text[i] != ']' && n < members) {
        spans[n][0] = i;
        i = wp_json_skip_value(text, i, length);
        spans[n++][1] = i;
        i = wp_json_skip_space(text, i, length);
        if (i < length && text[i] == ',')
            i = wp_json_skip_space(text, i + 1, length);
    }
    assert(n == members);
    cJSON_Delete(answer->json);
    answer->json = NULL;
    answer->next = NULL;
    answer->text = text;
    answer->spans = spans;
    answer->span_count = n;
    answer->bytes = length + (members * sizeof *spans);
}

/* A lazily read batch: the next request's tree in answer->next (the one
 * before it freed: its stream is over), or its error answer written when
 * it cannot be read for want of memory.  False when none is left. */
static bool next_member(wp_answer *answer, wp_buffer *out, wp_counts *counts)
{
    while (!answer->next && answer->text && answer->span_next < answer->span_count) {
        cJSON_Delete(answer->member);
        answer->member = NULL;
        size_t start = answer->spans[answer->span_next][0];
        size_t end = answer->spans[answer->span_next][1];
        answer->span_next++;
        cJSON *member = cJSON_ParseWithLengthOpts(answer->text + start, end - start, NULL, false);
        if (member && !wp_json_keep_id_text(member, answer->text + start, end - start)) {
            cJSON_Delete(member);
            member = NULL;
        }
        if (!member) {
            counts->requests++;
            counts->errors++;
            wp_error error;
            wp_error_set(&error, WP_INTERNAL, "", "out of memory while reading the request");
            write_error_answer(answer, out, &error, NULL);
            continue;
        }
        answer->member = answer->next = member;
    }
    return answer->next != NULL;
}

/* A line the loop may parse (WP_LIGHT_LINE) is never one whose fixture is
 * recognised from its text (recognise_fixture, which may derive cones). */
_Static_assert(WP_LIGHT_LINE < WP_INLINE_TEXT_MIN, "recognition stays off the event loop");

/* The tree of a line: a member of a raw_array or raw_text row read from
 * the text (prepare), the rest parsed; NULL with answer->refusal set (or
 * not, out of memory) when the line is refused. */
static cJSON *read_tree(wp_answer *answer, const wp_limits *limits, const char *line,
                        size_t length)
{
    wp_counts counted = {0, 0}; /* a refusal counts when its step writes it */
    size_t short_length = 0;
    char *short_line = NULL;
    /* Only a text the scan passes (UTF-8, depth, controls, numbers) is
     * read so; the copy is scanned again, short as it is. */
    const wp_method *raw = raw_method(line, length);
    if (raw && (raw->raw_text || length >= PREPARE_BYTES) && wp_utf8_valid(line, length)) {
        wp_json_shape shape = wp_json_scan(line, length, limits->max_depth);
        if (shape.depth <= limits->max_depth && !shape.control && !shape.nul_escape &&
            !shape.bad_escape && !shape.number_problem)
            short_line = prepare(raw, line, length, &answer->prepared, &short_length);
    }
    cJSON *json = NULL;
    if (short_line) {
        wp_counts scratch = {0, 0};
        json = parse_line(limits, short_line, short_length, &scratch, &answer->refusal);
        free(short_line);
        if (!json) {
            /* Refused as the line was written, not as cut. */
            free(answer->refusal);
            answer->refusal = NULL;
            free(answer->prepared.text);
            free(answer->prepared.wrenches);
            memset(&answer->prepared, 0, sizeof answer->prepared);
        }
    }
    if (!json)
        json = parse_line(limits, line, length, &counted, &answer->refusal);
    return json;
}

/* The row of the method a line names as written (a name spelt with
 * escapes is not found: the line is then read the ordinary way). */
static const wp_method *method_as_written(const char *line, size_t length)
{
    size_t start, end;
    if (!wp_json_member(line, length, 0, "method", &start, &end) || end - start < 2 ||
        line[start] != '"' || line[end - 1] != '"')
        return NULL;
    for (const wp_method *m = wp_methods; m->name; m++)
        if (strlen(m->name) == end - start - 2 && memcmp(line + start + 1, m->name, end - start - 2) == 0)
            return m;
    return NULL;
}

/* Does the tree read a single request of method `m`? */
static bool reads_method(const cJSON *json, const wp_method *m)
{
    const cJSON *method = cJSON_IsObject(json) ? cJSON_GetObjectItemCaseSensitive(json, "method")
                                               : NULL;
    return cJSON_IsString(method) && strcmp(method->valuestring, m->name) == 0;
}

/* A single request of a WP_FIXTURE method whose params.fixture is an
 * object the host kept the text of (wp_host.h, fixture_use_text): that
 * fixture held for the request (answer->hold) and a copy of the line with
 * [] in the object's place returned, so that neither the scan nor the
 * parse reads it again; NULL for the ordinary way.
 *
 * Why the line need not be read where the kept text stands: the text is a
 * whole JSON object that a line this daemon parsed held at this same place
 * (params.fixture of a single request, so at the same depth; the text is
 * kept by record_fixture_text below).  A value's text ends where its
 * brackets close, so when the bytes here equal it they are that object,
 * and a JSON text with one value put for another at a value's place is
 * valid exactly when it was: the copy is read as the line would have been.
 * The place is found by spanning the members before it without a scan;
 * on a line that is not JSON the copy, whose text before the place is the
 * same, is refused too, and the line is then read and refused as written. */
static char *recognise_fixture(wp_answer *answer, const wp_host *host, const char *line,
                               size_t length, const wp_method **m, size_t *copy_length)
{
    size_t params_start, fixture_start;
    size_t i = wp_json_skip_space(line, 0, length);
    if (i >= length || line[i] != '{')
        return NULL; /* a batch, or not a request */
    *m = method_as_written(line, length);
    if (!*m || !((*m)->flags & WP_FIXTURE) ||
        !wp_json_member_start(line, length, 0, "params", &params_start) ||
        !wp_json_member_start(line, length, params_start, "fixture", &fixture_start) ||
        line[fixture_start] != '{')
        return NULL;
    size_t span = host->fixture_use_text(host->self, line + fixture_start,
                                         length - fixture_start, &answer->hold.use);
    if (!span)
        return NULL;
    answer->hold.holding = true;
    char *copy = cut(line, length, fixture_start, fixture_start + span, copy_length);
    if (!copy)
        release_fixture(answer, host);
    return copy;
}

/* For a single request of a WP_FIXTURE method read the ordinary way, with
 * an inline fixture object of WP_INLINE_TEXT_MIN bytes on: its text as the
 * line wrote it, for the host to keep at the adoption (wp_call_fixture).
 * The line has passed the scan and the parse, so its spans are sound. */
static void record_fixture_text(wp_answer *answer, const cJSON *json, const char *line,
                                size_t length)
{
    const cJSON *method = cJSON_GetObjectItemCaseSensitive(json, "method");
    const wp_method *m = cJSON_IsString(method) ? wp_method_find(method->valuestring) : NULL;
    size_t params_start, start, end;
    if (!m || !(m->flags & WP_FIXTURE) ||
        !wp_json_member_start(line, length, 0, "params", &params_start) ||
        !wp_json_member(line, length, params_start, "fixture", &start, &end) ||
        line[start] != '{' || end - start < WP_INLINE_TEXT_MIN)
        return;
    answer->hold.text = malloc(end - start);
    if (!answer->hold.text)
        return; /* not kept: nothing else changes */
    memcpy(answer->hold.text, line + start, end - start);
    answer->hold.text_length = end - start;
}

wp_answer *wp_answer_begin(const wp_limits *limits, const wp_host *host, const char *line,
                           size_t length)
{
    wp_answer *answer = calloc(1, sizeof *answer);
    if (!answer)
        return NULL;
    answer->limits = *limits;
    answer->budget = WP_PIECE_BUDGET;
    answer->piece_bytes = WP_PIECE_BYTES;
    cJSON *json = NULL;
    bool keeps_texts = host && host->fixture_use_text && length >= WP_INLINE_TEXT_MIN;
    if (keeps_texts) {
        const wp_method *m = NULL;
        size_t cut_length = 0;
        char *cut_line = recognise_fixture(answer, host, line, length, &m, &cut_length);
        if (cut_line) {
            json = read_tree(answer, limits, cut_line, cut_length);
            free(cut_line);
            if (!reads_method(json, m)) {
                /* Refused, or not the request found from the text: read as written. */
                cJSON_Delete(json);
                json = NULL;
                free(answer->refusal);
                answer->refusal = NULL;
                free(answer->prepared.text);
                free(answer->prepared.wrenches);
                memset(&answer->prepared, 0, sizeof answer->prepared);
                release_fixture(answer, host);
            }
            keeps_texts = false; /* kept already */
        }
    }
    if (!json)
        json = read_tree(answer, limits, line, length);
    if (!json) {
        if (!answer->refusal) {
            free(answer);
            return NULL;
        }
        answer->bytes = strlen(answer->refusal);
        return answer;
    }
    if (keeps_texts && cJSON_IsObject(json))
        record_fixture_text(answer, json, line, length);
    answer->json = json;
    answer->bytes = length * 4; /* a rough figure for the tree */
    if (cJSON_IsArray(json)) {
        size_t members = (size_t)cJSON_GetArraySize(json);
        char reason[128];
        if (!json->child || members > limits->max_batch) {
            if (!json->child)
                snprintf(reason, sizeof reason, "an empty batch");
            else
                snprintf(reason, sizeof reason,
                         "a batch of %zu requests; the limit is %zu (--max-batch)", members,
                         limits->max_batch);
            cJSON_Delete(json);
            answer->json = NULL;
            answer->refusal = wp_error_line(WP_INVALID_REQUEST, "", reason);
            if (!answer->refusal) {
                free(answer);
                return NULL;
            }
            answer->bytes = strlen(answer->refusal);
            return answer;
        }
        answer->batch = true;
        answer->next = json->child;
        if (length >= PREPARE_BYTES)
            read_lazily(answer, line, length, members);
    } else {
        answer->next = json;
    }
    return answer;
}

wp_step wp_answer_step(wp_answer *answer, const wp_host *host, wp_buffer *out,
                       wp_counts *counts)
{
    assert(!answer->done);
    if (answer->refusal) {
        counts->requests++;
        counts->errors++;
        wp_buffer_puts(out, answer->refusal);
        answer->done = true;
        return WP_STEP_DONE;
    }
    size_t start = out->length;
    unsigned long used = 0;
    if (answer->stream) {
        /* Its text began in an earlier piece, already handed out. */
        wp_step step = continue_stream(answer, host, out, start, false, &used, counts);
        if (step != WP_STEP_DONE) {
            answer->done = step == WP_STEP_FAILED;
            return step;
        }
    }
    while (answer->next || next_member(answer, out, counts)) {
        if (!answer->whole && out->length > start &&
            (used >= answer->budget || out->length - start >= answer->piece_bytes))
            return WP_STEP_MORE;
        wp_step step;
        bool cheap = start_request(answer, host, out, &used, counts, &step);
        if (step == WP_STEP_MORE)
            return WP_STEP_MORE;
        assert(step == WP_STEP_DONE); /* a failure in its first piece is answered */
        if (!cheap)
            used = used > answer->budget ? used : answer->budget;
    }
    if (answer->opened)
        wp_buffer_puts(out, "]");
    if (out->length > start || answer->opened)
        wp_buffer_puts(out, "\n");
    answer->done = true;
    return WP_STEP_DONE;
}

size_t wp_answer_bytes(const wp_answer *answer)
{
    if (!answer)
        return 0;
    /* A stream's holdings change as it goes (a batch's chunks made ahead
     * of their turn): asked anew, between steps, when no helper is in it. */
    size_t text = answer->text ? answer->spans[answer->span_count - 1][1] : 0;
    if (answer->stream && answer->streamer->bytes)
        return 4096 + text + answer->streamer->bytes(answer->stream);
    return answer->bytes;
}

bool wp_answer_parallel(wp_answer *answer)
{
    return answer && answer->stream && answer->streamer->parallel &&
           answer->streamer->parallel(answer->stream);
}

bool wp_answer_work(wp_answer *answer, const wp_host *host)
{
    return answer->stream && answer->streamer->work &&
           answer->streamer->work(answer->stream, host);
}

void wp_answer_pieces(wp_answer *answer, unsigned long budget, size_t bytes)
{
    answer->budget = budget ? budget : 1;
    answer->piece_bytes = bytes ? bytes : 1;
}

void wp_answer_free(wp_answer *answer, const wp_host *host)
{
    if (!answer)
        return;
    end_stream(answer, host); /* and the fixture held, if any */
    cJSON_Delete(answer->json);
    cJSON_Delete(answer->member);
    free(answer->text);
    free(answer->spans);
    free(answer->refusal);
    free(answer->prepared.wrenches);
    free(answer->prepared.text);
    free(answer);
}

/* All of an answer in one buffer: the line, or NULL for none, or the error
 * saying the answer did not fit in memory. */
char *wp_answer_whole(wp_answer *answer, const wp_host *host, wp_counts *counts)
{
    answer->whole = true;
    wp_buffer b = {0};
    while (wp_answer_step(answer, host, &b, counts) == WP_STEP_MORE)
        ;
    wp_answer_free(answer, host);
    if (b.length == 0 && !b.failed) {
        free(b.data);
        return NULL; /* notifications only */
    }
    char *line = wp_buffer_take(&b);
    if (!line) { /* the answer did not fit in memory: say so, lose nothing silently */
        counts->errors++;
        line = wp_error_line(WP_INTERNAL, "", "out of memory while writing the answer");
    }
    return line;
}

char *wp_answer_line(const wp_host *host, const wp_limits *limits, const char *line,
                     size_t length, wp_counts *counts)
{
    wp_answer *answer = wp_answer_begin(limits, host, line, length);
    if (!answer) {
        counts->requests++;
        counts->errors++;
        return wp_error_line(WP_INTERNAL, "", "out of memory");
    }
    return wp_answer_whole(answer, host, counts);
}
