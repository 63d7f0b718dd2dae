/* wp_rpc.c -- the JSON-RPC 2.0 envelope: one line in, one line out. */
#include "wp_rpc.h"

#include <ctype.h>
#include <math.h>
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
    wp_buffer_puts(b, "{\"jsonrpc\":\"2.0\",\"error\":{\"code\":");
    wp_buffer_number(b, error->code);
    wp_buffer_puts(b, ",\"message\":");
    wp_buffer_string(b, message_of(error->code));
    wp_buffer_puts(b, ",\"data\":{\"field\":");
    wp_buffer_string(b, error->field);
    wp_buffer_puts(b, ",\"reason\":");
    wp_buffer_string(b, error->reason);
    wp_buffer_puts(b, "}},\"id\":");
    wp_buffer_puts(b, id);
    wp_buffer_puts(b, "}");
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

/* Check the params against the method's table entry, then run it. */
static cJSON *call(const wp_host *host, const wp_limits *limits, const cJSON *request,
                   wp_error *error)
{
    const cJSON *method = cJSON_GetObjectItemCaseSensitive(request, "method");
    const wp_method *m = wp_method_find(method->valuestring);
    if (!m) {
        wp_error_set(error, WP_NO_METHOD, "method", "no method named \"%.64s\"",
                     method->valuestring);
        return NULL;
    }
    if (!m->handler) {
        wp_error_set(error, WP_NO_METHOD, "method", "%s is not served yet", m->name);
        return NULL;
    }
    const cJSON *params = cJSON_GetObjectItemCaseSensitive(request, "params");
    cJSON *empty = NULL;
    if (!params) {
        params = empty = cJSON_CreateObject();
        if (!empty) {
            wp_error_set(error, WP_INTERNAL, "", "out of memory");
            return NULL;
        }
    }
    cJSON *result = NULL;
    if (wp_check_object(params, "params", m->fields, error)) {
        bool complete = true;
        for (const char *const *name = m->required; *name && complete; name++)
            if (!cJSON_GetObjectItemCaseSensitive(params, *name)) {
                char field[WP_FIELD_MAX];
                wp_path_key(field, "params", *name);
                wp_error_set(error, WP_INVALID_PARAMS, field, "required");
                complete = false;
            }
        if (complete)
            result = m->handler(host, limits, params, error);
    }
    cJSON_Delete(empty);
    return result;
}

/* Answer one request object into `b`; nothing for a notification.  The id
 * is echoed as the client wrote it: a number's own text (kept by
 * wp_json_keep_id_text), a string's canonical text. */
static void answer_request(const wp_host *host, const wp_limits *limits, const cJSON *request,
                           wp_buffer *b, wp_counts *counts)
{
    counts->requests++;
    wp_error error = {0};
    const char *id_text = "null";
    char *id_owned = NULL;
    bool notification = false;
    const cJSON *id = cJSON_IsObject(request) ? cJSON_GetObjectItemCaseSensitive(request, "id")
                                             : NULL;
    bool valid = false;
    if (!cJSON_IsObject(request)) {
        wp_error_set(&error, WP_INVALID_REQUEST, "", "a request is an object, not %s",
                     wp_type_name(request));
    } else if (id && !cJSON_IsString(id) && !cJSON_IsNumber(id) && !cJSON_IsNull(id)) {
        wp_error_set(&error, WP_INVALID_REQUEST, "id", "must be a string, a number or null");
    } else if (cJSON_IsNumber(id) && !isfinite(id->valuedouble)) {
        /* It could not be echoed: JSON has no infinities. */
        wp_error_set(&error, WP_INVALID_REQUEST, "id", "must be a finite number");
    } else {
        if (id && !cJSON_IsNull(id)) {
            id_text = id_owned = wp_json_id_text(id);
            if (!id_owned)
                id_text = "null";
        }
        const cJSON *version = cJSON_GetObjectItemCaseSensitive(request, "jsonrpc");
        const cJSON *method = cJSON_GetObjectItemCaseSensitive(request, "method");
        wp_error envelope;
        if (id && !cJSON_IsNull(id) && !id_owned) /* out of memory: answered under id null */
            wp_error_set(&error, WP_INTERNAL, "", "out of memory");
        else if (!wp_check_object(request, "", ENVELOPE_FIELDS, &envelope))
            wp_error_set(&error, WP_INVALID_REQUEST, envelope.field, "%s", envelope.reason);
        else if (!cJSON_IsString(version) || strcmp(version->valuestring, "2.0") != 0)
            wp_error_set(&error, WP_INVALID_REQUEST, "jsonrpc", "must be \"2.0\"");
        else if (!cJSON_IsString(method))
            wp_error_set(&error, WP_INVALID_REQUEST, "method", "must be a string, not %s",
                         wp_type_name(method));
        else
            valid = true;
        /* Only a valid request without an id is a notification: an
         * invalid one is answered (with id null if it has none). */
        notification = valid && id == NULL;
    }
    cJSON *result = valid ? call(host, limits, request, &error) : NULL;
    if (!result)
        counts->errors++;
    if (!notification) {
        if (b->length > 1) /* after "[" and an earlier answer */
            wp_buffer_puts(b, ",");
        cJSON *raw = result ? result->child : NULL;
        size_t room = sizeof WP_RESULTS_OPENING - 1;
        if (b->length == 0 && !b->failed && raw && !raw->next && cJSON_IsRaw(raw) &&
            strcmp(raw->string, "results") == 0 && strspn(raw->valuestring, " ") == room) {
            /* The results take the envelope's opening in their room and
             * become the answer: tens of megabytes are not copied. */
            memcpy(raw->valuestring, WP_RESULTS_OPENING, room);
            wp_buffer_adopt(b, raw->valuestring);
            raw->valuestring = NULL; /* cJSON_Delete skips it */
            wp_buffer_reserve(b, b->length + 16 + strlen(id_text));
            wp_buffer_puts(b, "},\"id\":");
            wp_buffer_puts(b, id_text);
            wp_buffer_puts(b, "}");
        } else if (result) {
            /* Straight into the answer: a batch of wrenches makes tens of
             * megabytes, not to be copied twice more. */
            wp_buffer_puts(b, "{\"jsonrpc\":\"2.0\",\"result\":");
            wp_buffer_json(b, result);
            wp_buffer_puts(b, ",\"id\":");
            wp_buffer_puts(b, id_text);
            wp_buffer_puts(b, "}");
        } else {
            write_error(b, &error, id_text);
        }
    }
    cJSON_Delete(result);
    free(id_owned);
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
    if (shape.nul_escape) {
        /* cJSON would cut the string at the NUL and answer for another
         * request ("fixture.list\u0000x" as "fixture.list"): refuse it. */
        counts->requests++;
        counts->errors++;
        return refuse(refusal, WP_INVALID_REQUEST,
                      "a string holds \\u0000 (U+0000), which wrenchd does not accept");
    }
    const char *end = NULL;
    cJSON *json = cJSON_ParseWithLengthOpts(line + start, length - start, &end, false);
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

/* Answer the parsed line (takes `json`). */
static char *answer_json(const wp_host *host, const wp_limits *limits, cJSON *json,
                         wp_counts *counts)
{
    wp_buffer b = {0};
    if (cJSON_IsArray(json)) {
        if (!json->child) {
            cJSON_Delete(json);
            counts->requests++;
            counts->errors++;
            return wp_error_line(WP_INVALID_REQUEST, "", "an empty batch");
        }
        size_t members = (size_t)cJSON_GetArraySize(json);
        if (members > limits->max_batch) {
            cJSON_Delete(json);
            counts->requests++;
            counts->errors++;
            char reason[128];
            snprintf(reason, sizeof reason, "a batch of %zu requests; the limit is %zu (--max-batch)",
                     members, limits->max_batch);
            return wp_error_line(WP_INVALID_REQUEST, "", reason);
        }
        wp_buffer_puts(&b, "[");
        for (const cJSON *request = json->child; request; request = request->next)
            answer_request(host, limits, request, &b, counts);
        if (b.length == 1) { /* notifications only */
            free(b.data);
            cJSON_Delete(json);
            return NULL;
        }
        wp_buffer_puts(&b, "]");
    } else {
        answer_request(host, limits, json, &b, counts);
        if (b.length == 0) {
            cJSON_Delete(json);
            return NULL;
        }
    }
    cJSON_Delete(json);
    wp_buffer_puts(&b, "\n");
    char *answer = wp_buffer_take(&b);
    if (!answer) { /* the answer did not fit in memory: say so, lose nothing silently */
        counts->errors++;
        answer = wp_error_line(WP_INTERNAL, "", "out of memory while writing the answer");
    }
    return answer;
}

char *wp_answer_line(const wp_host *host, const wp_limits *limits, const char *line,
                     size_t length, wp_counts *counts)
{
    char *refusal = NULL;
    cJSON *json = parse_line(limits, line, length, counts, &refusal);
    return json ? answer_json(host, limits, json, counts) : refusal;
}

/* Light work (wp_answer_light): server.status, or an auto classify of a
 * few wrenches against a stored fixture whose cones are ready. */
static bool json_is_light(const wp_host *host, const cJSON *json)
{
    const cJSON *method = cJSON_GetObjectItemCaseSensitive(json, "method");
    const cJSON *params = cJSON_GetObjectItemCaseSensitive(json, "params");
    if (!cJSON_IsObject(json) || !cJSON_IsString(method))
        return !cJSON_IsArray(json); /* an invalid request, but a batch may be work */
    if (strcmp(method->valuestring, "server.status") == 0)
        return true;
    if (strcmp(method->valuestring, "wrench.classify") != 0 || !cJSON_IsObject(params))
        return false;
    const cJSON *how = cJSON_GetObjectItemCaseSensitive(params, "method");
    const cJSON *id = cJSON_GetObjectItemCaseSensitive(params, "fixture");
    const cJSON *wrenches = cJSON_GetObjectItemCaseSensitive(params, "wrenches");
    if ((how && !(cJSON_IsString(how) && strcmp(how->valuestring, "auto") == 0)) ||
        !cJSON_IsString(id) || !cJSON_IsArray(wrenches) || !host->fixture_ready ||
        !wp_fixture_id_valid(id->valuestring))
        return false;
    long count = cJSON_GetArraySize(wrenches);
    if (count > WP_LIGHT_CONE_CHECKS)
        return false;
    int cones = host->fixture_ready(host->self, id->valuestring);
    return cones >= 0 && count * (cones > 0 ? cones : 1) <= WP_LIGHT_CONE_CHECKS;
}

bool wp_answer_light(const wp_host *host, const wp_limits *limits, const char *line,
                     size_t length, wp_counts *counts, char **answer)
{
    if (length > WP_LIGHT_LINE)
        return false;
    char *refusal = NULL;
    cJSON *json = parse_line(limits, line, length, counts, &refusal);
    if (!json) {
        *answer = refusal; /* refusing a line is light */
        return true;
    }
    if (!json_is_light(host, json)) {
        cJSON_Delete(json); /* nothing counted yet: the worker will */
        return false;
    }
    *answer = answer_json(host, limits, json, counts);
    return true;
}
