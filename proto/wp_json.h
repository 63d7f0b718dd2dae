/* wp_json.h -- JSON helpers of the protocol layer, one header for a file
 * per topic:
 *   wp_error.c      errors that name a field; lib statuses as JSON-RPC codes
 *   wp_read.c       strict typed access to request members
 *   wp_buffer.c     the text buffer answers are written into
 *   wp_writer.c     the JSON writer every answer is written with
 *   wp_canonical.c  canonical text of a tree (fixture ids, request lines)
 *   wp_scan.c       a text read without a tree: checked before parsing, ids
 *                   as written, spans of members, long arrays of triples */
#ifndef WP_JSON_H
#define WP_JSON_H

#include "wp_number.h" /* wp_format_number */
#include "wr_status.h"

#include <cjson/cJSON.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#ifdef __cplusplus
extern "C" {
#endif

/* JSON-RPC error codes (docs/PROTOCOL.md). */
#define WP_PARSE_ERROR (-32700)
#define WP_INVALID_REQUEST (-32600)
#define WP_NO_METHOD (-32601)
#define WP_INVALID_PARAMS (-32602)
#define WP_INTERNAL (-32603)
#define WP_NO_FIXTURE (-32001)
#define WP_STORAGE (-32002)
#define WP_LIMIT (-32003)
#define WP_SOLVER (-32004)
#define WP_ACCESS (-32005)

/* Longest field path kept; longer ones are cut. */
#define WP_FIELD_MAX 192

typedef struct wp_error {
    int code;                   /* one of the codes above */
    char field[WP_FIELD_MAX];   /* path from the request's root, "" if none */
    char reason[256];
} wp_error;

void wp_error_set(wp_error *error, int code, const char *field, const char *format, ...)
    __attribute__((format(printf, 4, 5)));

/* The error of a libwrench call that did not return WR_OK, the one place
 * lib statuses become JSON-RPC codes.  WR_NO_MEMORY and WR_STOPPED are
 * said in their own words ("out of memory", "stopped: the client is
 * gone"), WP_INTERNAL at no field; WR_LP_FAILED is WP_SOLVER and the rest
 * (the request's input: WR_INVALID, WR_NO_SHAPE) WP_INVALID_PARAMS, both at
 * `field` with the caller's reason, which says what of the request failed. */
void wp_error_status(wp_error *error, wr_status status, const char *field, const char *format,
                     ...) __attribute__((format(printf, 4, 5)));

/* wp_error_status for a lib call that refused at `why` (wr_error) what it
 * was given from `path`: the field is path.why->field, or `path` when the
 * lib names none. */
void wp_error_refusal(wp_error *error, wr_status status, const char *path, const wr_error *why);

/* "prefix.key" and "prefix[index]" into a WP_FIELD_MAX buffer. */
void wp_path_key(char out[WP_FIELD_MAX], const char *prefix, const char *key);
void wp_path_index(char out[WP_FIELD_MAX], const char *prefix, size_t index);

/* The type of a JSON value in words, for error reasons ("a string"). */
const char *wp_type_name(const cJSON *value);

/* `value` must be an object whose members are all in `allowed` (NULL-ended)
 * and appear once.  Errors are -32602 at `path` or `path.member`. */
bool wp_check_object(const cJSON *value, const char *path, const char *const *allowed,
                     wp_error *error);

/* Typed members of an object already checked with wp_check_object.  Each
 * returns false with an error at `path.key` when the member is of the wrong
 * type, or is missing and `required`; *present (may be NULL) says whether it
 * was there. */
bool wp_member_number(const cJSON *object, const char *path, const char *key, bool required,
                      double *out, bool *present, wp_error *error);
bool wp_member_vector2(const cJSON *object, const char *path, const char *key, bool required,
                       double out[2], bool *present, wp_error *error);
bool wp_member_string(const cJSON *object, const char *path, const char *key, bool required,
                      const char **out, wp_error *error);
/* A finite number, or an array of exactly two finite numbers, at `path`. */
bool wp_number(const cJSON *value, const char *path, double *out, wp_error *error);
bool wp_vector2(const cJSON *value, const char *path, double out[2], wp_error *error);

/* A growable string.  Out of memory is sticky: `failed` is set, appends stop
 * and wp_buffer_take returns NULL. */
typedef struct wp_buffer {
    char *data;
    size_t length, capacity;
    bool failed;
} wp_buffer;

/* Appends the text; out of room, wp_buffer_grow_append grows the buffer
 * first.  Inline: an answer is written a few bytes at a time. */
void wp_buffer_grow_append(wp_buffer *buffer, const char *text, size_t length);
static inline void wp_buffer_append(wp_buffer *buffer, const char *text, size_t length)
{
    if (buffer->length + length < buffer->capacity) { /* room for the NUL too */
        char *at = buffer->data + buffer->length;
        if (length <= 16)
            for (size_t i = 0; i < length; i++) /* a few bytes: no call */
                at[i] = text[i];
        else
            memcpy(at, text, length);
        buffer->length += length;
        buffer->data[buffer->length] = 0;
    } else {
        wp_buffer_grow_append(buffer, text, length);
    }
}
void wp_buffer_puts(wp_buffer *buffer, const char *text);
/* Room for `n` more bytes (and the NUL) at the end of the text, grown if
 * need be: where to write them, or NULL when out of memory.  The bytes
 * written count once wp_buffer_commit says how many. */
char *wp_buffer_grow_room(wp_buffer *buffer, size_t n);
static inline char *wp_buffer_room(wp_buffer *buffer, size_t n)
{
    if (buffer->length + n < buffer->capacity)
        return buffer->data + buffer->length;
    return wp_buffer_grow_room(buffer, n);
}
static inline void wp_buffer_commit(wp_buffer *buffer, size_t written)
{
    buffer->length += written;
    buffer->data[buffer->length] = 0;
}
/* Capacity for `bytes` bytes of text in all, at once: a large answer whose
 * size is known roughly is not regrown (and recopied) a dozen times.  A
 * hint: on failure nothing changes. */
void wp_buffer_reserve(wp_buffer *buffer, size_t bytes);
void wp_buffer_number(wp_buffer *buffer, double value);
void wp_buffer_string(wp_buffer *buffer, const char *text); /* quoted, escaped */

/* The NUL-terminated text (malloc'd, the caller frees), or NULL. */
char *wp_buffer_take(wp_buffer *buffer);

/* The writer of every answer's JSON (wp_writer.c), on a buffer: values,
 * objects and arrays, with the commas and the nesting kept by the writer,
 * so that a caller says only what comes next.  Numbers are written by
 * wp_format_number, strings escaped.  A writer may span steps: it holds no
 * text, and its buffer may be a different one at each step (set `out`).
 * At depth 0 values are separate texts (lines), never joined by commas.
 * Nesting deeper than WP_WRITER_DEPTH is a programming error (asserted). */
#define WP_WRITER_DEPTH 64
typedef struct wp_writer {
    wp_buffer *out;
    unsigned depth;    /* containers open */
    uint64_t filled;   /* bit d - 1: the container at depth d has a member */
    bool keyed;        /* a key is written, its value not yet */
} wp_writer;

/* A writer on `out` at depth 0. */
static inline wp_writer wp_writer_on(wp_buffer *out) { return (wp_writer){out, 0, 0, false}; }
/* A writer on `out` inside an array whose "[" is written elsewhere: its
 * values are joined by commas, the first without one -- a sequence of
 * values that wp_write_raw puts into that array later (a chunk's text). */
static inline wp_writer wp_writer_in_array(wp_buffer *out)
{
    return (wp_writer){out, 1, 0, false};
}

/* What comes before a value: true when a comma is due (after the
 * container's last member); nothing after a key, first in a container, at
 * depth 0.  The caller writes the comma with its own text, in one append. */
static inline bool wp_write_comma_due(wp_writer *w)
{
    if (w->keyed) {
        w->keyed = false;
        return false;
    }
    if (!w->depth)
        return false;
    uint64_t bit = (uint64_t)1 << (w->depth - 1);
    bool due = (w->filled & bit) != 0;
    w->filled |= bit;
    return due;
}
static inline void wp_write_separate(wp_writer *w)
{
    if (wp_write_comma_due(w))
        wp_buffer_append(w->out, ",", 1);
}

void wp_write_object(wp_writer *w);     /* { */
void wp_write_object_end(wp_writer *w); /* } */
void wp_write_array(wp_writer *w);      /* [ */
void wp_write_array_end(wp_writer *w);  /* ] */
/* A member's key, in an object: a name of the protocol, written as it is
 * (no character in it needs escaping). */
void wp_write_key(wp_writer *w, const char *key);
void wp_write_number(wp_writer *w, double value);
void wp_write_string(wp_writer *w, const char *text); /* quoted, escaped */
void wp_write_bool(wp_writer *w, bool value);
void wp_write_null(wp_writer *w);
/* Text that is JSON already (`length` bytes): a value, or a sequence of
 * values joined by commas (a wp_writer_in_array's text), which join the
 * container's members as values written one by one would.  Nothing when
 * `length` is 0. */
void wp_write_raw(wp_writer *w, const char *text, size_t length);
/* [v0, v1, ...]: n numbers. */
void wp_write_numbers(wp_writer *w, const double *v, size_t n);
/* A member: its key and its value, in one call. */
static inline void wp_write_member_number(wp_writer *w, const char *key, double value)
{
    wp_write_key(w, key);
    wp_write_number(w, value);
}
static inline void wp_write_member_string(wp_writer *w, const char *key, const char *text)
{
    wp_write_key(w, key);
    wp_write_string(w, text);
}
static inline void wp_write_member_bool(wp_writer *w, const char *key, bool value)
{
    wp_write_key(w, key);
    wp_write_bool(w, value);
}
/* A string value of exactly n characters that the caller writes at the
 * place returned, at once, before anything else is written: characters
 * that need no escaping (a column of verdict letters).  NULL when out of
 * memory (the buffer says so). */
char *wp_write_string_room(wp_writer *w, size_t n);

/* Canonical JSON: object members sorted by key, numbers as
 * wp_format_number, no white space; a top-level member named `skip` (may be
 * NULL) is left out.  Malloc'd, or NULL when out of memory. */
char *wp_canonical(const cJSON *value, const char *skip);
/* A digest of the value's canonical form without writing its text: SHA-256
 * of its members sorted by key, strings by length and bytes, numbers as
 * their doubles' bits.  Two values with one digest have one canonical text
 * (numbers that differ only as -0 and 0 have two digests and one text);
 * the digest costs a small part of the text's, whose numbers are written
 * in decimal.  False out of memory. */
bool wp_canonical_digest(const cJSON *value, unsigned char digest[32]);

/* Is the text well-formed UTF-8 (RFC 3629: no overlong forms, no
 * surrogates, nothing above U+10FFFF)?  JSON text must be. */
bool wp_utf8_valid(const char *text, size_t length);

/* What a scan of a JSON text finds without parsing it: the deepest nesting
 * of arrays and objects (stopping once past `limit`); whether a string
 * holds the escape \u0000, which cJSON would silently cut the string at;
 * and whether a control character stands where JSON allows none -- raw in
 * a string (RFC 8259 wants it escaped; a raw NUL would cut the string too),
 * or outside strings other than tab, CR and LF (cJSON takes any byte up to
 * space for white space). */
typedef struct wp_json_shape {
    int depth;
    bool nul_escape;
    bool control;
    bool bad_escape; /* an escape RFC 8259 does not allow ("\x", "\udu") */
    /* The first number outside strings that RFC 8259 does not allow
     * ("012", "-00", "1.", "-.5", "1.e5", "1e"), which cJSON may read
     * anyway: what is wrong with it ("has a leading zero"), or NULL; and
     * where it stands in the text. */
    const char *number_problem;
    size_t number_at, number_length;
} wp_json_shape;
wp_json_shape wp_json_scan(const char *text, size_t length, int limit);

/* Spans of a JSON text read without building a tree (a hundred thousand
 * wrenches make millions of tree nodes).  The text must have passed
 * wp_json_scan.  The value of member `key` of the object at `object`
 * (white space may precede it): true with its byte span [*start, *end);
 * false when it is not there as written (a key spelt with escapes is not
 * found) or the text is not such an object. */
bool wp_json_member(const char *text, size_t length, size_t object, const char *key,
                    size_t *start, size_t *end);
/* Where the JSON value at i (white space before it skipped by the caller)
 * ends, and where white space from i ends; for a text wp_json_scan passed
 * and cJSON read. */
size_t wp_json_skip_value(const char *text, size_t i, size_t length);
/* Is the text one JSON value by RFC 8259 (white space around it allowed),
 * nested at most 64 deep?  Strict and without a tree: a member cut out of
 * a line before the line is parsed is checked so, since the parse never
 * sees it.  False for anything it doubts (the caller then parses the line
 * as it was written). */
bool wp_json_valid(const char *text, size_t length);
size_t wp_json_skip_space(const char *text, size_t i, size_t length);
/* The same, with only where the value starts: its end is not looked for
 * (a member holding megabytes is not read twice). */
bool wp_json_member_start(const char *text, size_t length, size_t object, const char *key,
                          size_t *start);
/* An array of arrays of three finite numbers at the start of `text` (white
 * space may precede it), each read as cJSON reads a number: their count and
 * *out (malloc'd), or -1 when the text is anything else (the caller then
 * reads it the ordinary way, and says what is wrong).  With `end` NULL
 * only white space may follow the array; else *end is where it ends. */
long wp_json_triples(const char *text, size_t length, double (**out)[3], size_t *end);
/* The finite number at text[*i], of a text wp_json_scan passed, read as
 * cJSON reads it: true with *i past it, false when it is not a number there
 * (or not finite as a double). */
bool wp_json_read_number(const char *text, size_t length, size_t *i, double *out);
/* Past the closing quote of the string whose opening quote is at text[i];
 * 0 when it does not end. */
size_t wp_json_string_end(const char *text, size_t length, size_t i);
/* A hint that the `bytes` at p, about to be written front to back, be
 * backed by huge pages: a few page faults for megabytes, not thousands. */
void wp_advise_huge(void *p, size_t bytes);

/* Numeric ids echoed as written: JSON-RPC wants the id back as the client
 * sent it, and a double cannot hold 9007199254740993 or a 30-digit id.
 * For the request object `json` was parsed from `text` (or each request of
 * a batch), the text of its first "id" member, when that is a number, is
 * kept in the id item's `valuestring` (unused by cJSON for numbers, freed
 * by cJSON_Delete).  False only when out of memory. */
bool wp_json_keep_id_text(cJSON *json, const char *text, size_t length);
/* The text to echo for an id: a number as it was written (when kept),
 * else the canonical text.  Malloc'd, or NULL when out of memory. */
char *wp_json_id_text(const cJSON *id);

#ifdef __cplusplus
}
#endif

#endif
