/* wp_error.c -- errors that name the field at fault: setting them, the
 * one mapping of lib statuses and of host statuses to JSON-RPC codes, field
 * paths, type names. */
#include "wp_host.h"
#include "wp_json.h"

#include <stdarg.h>
#include <stdio.h>
#include <string.h>

static void error_vset(wp_error *error, int code, const char *field, const char *format,
                       va_list args) __attribute__((format(printf, 4, 0)));

static void error_vset(wp_error *error, int code, const char *field, const char *format,
                       va_list args)
{
    if (!error)
        return;
    error->code = code;
    snprintf(error->field, sizeof error->field, "%s", field ? field : "");
    vsnprintf(error->reason, sizeof error->reason, format, args);
}

void wp_error_set(wp_error *error, int code, const char *field, const char *format, ...)
{
    va_list args;
    va_start(args, format);
    error_vset(error, code, field, format, args);
    va_end(args);
}

void wp_error_status(wp_error *error, wr_status status, const char *field, const char *format,
                     ...)
{
    if (status == WR_NO_MEMORY || status == WR_STOPPED) {
        wp_error_set(error, WP_INTERNAL, "", "%s",
                     status == WR_NO_MEMORY ? "out of memory" : "stopped: the client is gone");
        return;
    }
    va_list args;
    va_start(args, format);
    error_vset(error, status == WR_LP_FAILED ? WP_SOLVER : WP_INVALID_PARAMS, field, format, args);
    va_end(args);
}

void wp_error_refusal(wp_error *error, wr_status status, const char *path, const wr_error *why)
{
    char field[WP_FIELD_MAX];
    if (why->field[0])
        wp_path_key(field, path, why->field);
    else
        snprintf(field, sizeof field, "%s", path);
    wp_error_status(error, status, field, "%s", why->reason);
}

void wp_error_host(wp_error *error, const wp_host_failure *failure, const char *field)
{
    static const int CODES[] = {
        [WP_HOST_OK] = WP_INTERNAL,           [WP_HOST_NO_MEMORY] = WP_INTERNAL,
        [WP_HOST_NO_FIXTURE] = WP_NO_FIXTURE, [WP_HOST_STORAGE] = WP_STORAGE,
        [WP_HOST_LIMIT] = WP_LIMIT,           [WP_HOST_UNSUPPORTED] = WP_NO_METHOD,
    };
    const char *at = failure->status == WP_HOST_LIMIT         ? "params.fixture"
                     : failure->status == WP_HOST_UNSUPPORTED ? "method"
                                                               : field;
    wp_error_set(error, CODES[failure->status], at, "%s", failure->reason);
}

/* Copies at most `most` bytes of `text` to out + at (not terminated); the
 * new end.  Paths are made for every member read, errors or not: by hand,
 * as snprintf would, at a tenth of its cost. */
static size_t put_text(char *out, size_t at, const char *text, size_t most)
{
    size_t n = strnlen(text, most);
    memcpy(out + at, text, n);
    return at + n;
}

void wp_path_key(char out[WP_FIELD_MAX], const char *prefix, const char *key)
{
    size_t n = 0;
    if (prefix && *prefix) {
        n = put_text(out, n, prefix, WP_FIELD_MAX / 2);
        out[n++] = '.';
    }
    n = put_text(out, n, key, WP_FIELD_MAX - 1 - n);
    out[n] = 0;
}

void wp_path_index(char out[WP_FIELD_MAX], const char *prefix, size_t index)
{
    size_t n = put_text(out, 0, prefix, WP_FIELD_MAX - 24);
    char digits[24];
    int d = 0;
    do {
        digits[d++] = (char)('0' + index % 10);
        index /= 10;
    } while (index > 0);
    out[n++] = '[';
    while (d > 0)
        out[n++] = digits[--d];
    out[n++] = ']';
    out[n] = 0;
}

const char *wp_type_name(const cJSON *value)
{
    if (!value)
        return "nothing";
    if (cJSON_IsNumber(value))
        return "a number";
    if (cJSON_IsString(value))
        return "a string";
    if (cJSON_IsBool(value))
        return "a boolean";
    if (cJSON_IsNull(value))
        return "null";
    if (cJSON_IsArray(value))
        return "an array";
    if (cJSON_IsObject(value))
        return "an object";
    return "an unknown value";
}

