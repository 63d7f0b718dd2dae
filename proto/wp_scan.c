/* wp_scan.c -- a JSON text read without a tree: checked before it is
 * parsed (UTF-8, depth, control characters, escapes, numbers), numeric ids
 * kept as the client wrote them, spans of members, and long arrays of
 * triples of numbers read straight from the text. */
#include "wp_json.h"

#include <ctype.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

bool wp_utf8_valid(const char *text, size_t length)
{
    const unsigned char *p = (const unsigned char *)text, *end = p + length;
    while (p < end) {
        unsigned char c = *p;
        if (c < 0x80) {
            p++;
            continue;
        }
        int more;
        unsigned min;
        unsigned code;
        if (c >= 0xc2 && c <= 0xdf) {
            more = 1, min = 0x80, code = c & 0x1f;
        } else if (c >= 0xe0 && c <= 0xef) {
            more = 2, min = 0x800, code = c & 0x0f;
        } else if (c >= 0xf0 && c <= 0xf4) {
            more = 3, min = 0x10000, code = c & 0x07;
        } else {
            return false; /* a continuation byte, an overlong lead, or beyond */
        }
        if (end - p <= more)
            return false;
        for (int i = 1; i <= more; i++) {
            if ((p[i] & 0xc0) != 0x80)
                return false;
            code = code << 6 | (p[i] & 0x3f);
        }
        if (code < min || code > 0x10ffff || (code >= 0xd800 && code <= 0xdfff))
            return false;
        p += more + 1;
    }
    return true;
}

/* A byte a number token may hold (JSON's, and what strtod would take). */
static bool number_char(char c)
{
    return (c >= '0' && c <= '9') || c == '-' || c == '+' || c == '.' || c == 'e' || c == 'E';
}

/* The end of the number token starting at text[i] ('-' or a digit), and
 * what RFC 8259's grammar finds wrong with it (NULL: nothing):
 *   number = [ "-" ] int [ "." 1*DIGIT ] [ ("e" / "E") [ "+" / "-" ] 1*DIGIT ]
 *   int    = "0" / ( digit1-9 *DIGIT )
 * The token runs on over every character a number could hold, so that a
 * message shows all of "012" or "1.e5", not just where it went wrong. */
static size_t number_token(const char *text, size_t i, size_t length, const char **problem)
{
#define DIGIT_AT(k) ((k) < length && text[k] >= '0' && text[k] <= '9')
    *problem = NULL;
    size_t k = i;
    if (text[k] == '-')
        k++;
    if (DIGIT_AT(k) && text[k] == '0') {
        k++;
        if (DIGIT_AT(k))
            *problem = "has a leading zero";
    } else if (DIGIT_AT(k)) {
        while (DIGIT_AT(k))
            k++;
    } else {
        *problem = "has no digit before its fraction"; /* "-", "-.5" */
    }
    if (!*problem && k < length && text[k] == '.') {
        k++;
        if (!DIGIT_AT(k))
            *problem = "has no digit after its decimal point";
        while (DIGIT_AT(k))
            k++;
    }
    if (!*problem && k < length && (text[k] == 'e' || text[k] == 'E')) {
        k++;
        if (k < length && (text[k] == '+' || text[k] == '-'))
            k++;
        if (!DIGIT_AT(k))
            *problem = "has no digit in its exponent";
        while (DIGIT_AT(k))
            k++;
    }
#undef DIGIT_AT
    while (k < length && number_char(text[k]))
        k++;
    return k;
}

wp_json_shape wp_json_scan(const char *text, size_t length, int limit)
{
    wp_json_shape shape = {0, false, false, false, NULL, 0, 0};
    int depth = 0;
    bool in_string = false;
    for (size_t i = 0; i < length; i++) {
        char c = text[i];
        if ((unsigned char)c < 0x20 && (in_string || (c != '\t' && c != '\r' && c != '\n')))
            shape.control = true;
        if (in_string) {
            if (c == '\\') {
                /* An escape RFC 8259 allows, \uXXXX with four hex digits:
                 * cJSON reads "\udu" as U+0000 and cuts the string there,
                 * and would skip the byte after a lone backslash unchecked. */
                char next = i + 1 < length ? text[i + 1] : '\0';
                if (next == 'u') {
                    bool hex = i + 5 < length;
                    for (size_t k = i + 2; hex && k < i + 6; k++)
                        hex = isxdigit((unsigned char)text[k]) != 0;
                    if (!hex)
                        shape.bad_escape = true;
                    else if (memcmp(text + i + 2, "0000", 4) == 0)
                        shape.nul_escape = true;
                } else if (!next || !strchr("\"\\/bfnrt", next)) {
                    shape.bad_escape = true;
                }
                i++;
            } else if (c == '"') {
                in_string = false;
            }
        } else if (c == '"') {
            in_string = true;
        } else if (c == '[' || c == '{') {
            if (++depth > shape.depth) {
                shape.depth = depth;
                if (shape.depth > limit)
                    return shape;
            }
        } else if (c == ']' || c == '}') {
            depth--;
        } else if (c == '-' || (c >= '0' && c <= '9')) {
            /* cJSON reads numbers with strtod, which takes more than JSON
             * allows ("012", "1.", "-.5", "1.e5"): check each by the RFC. */
            const char *problem;
            size_t end = number_token(text, i, length, &problem);
            if (problem && !shape.number_problem) {
                shape.number_problem = problem;
                shape.number_at = i;
                shape.number_length = end - i;
            }
            i = end - 1;
        }
    }
    return shape;
}

/* ---- numeric ids as the client wrote them ---------------------------------- */

/* JSON white space (RFC 8259); the scan has refused any other control
 * character before a line is parsed. */
static size_t skip_space(const char *text, size_t i, size_t length)
{
    while (i < length && (text[i] == ' ' || text[i] == '\t' || text[i] == '\r' || text[i] == '\n'))
        i++;
    return i;
}

/* The end of the JSON value starting at text[i], in a text cJSON has
 * already accepted (so no validation here, only its extent). */
static size_t skip_value(const char *text, size_t i, size_t length);

size_t wp_json_skip_value(const char *text, size_t i, size_t length)
{
    return skip_value(text, i, length);
}

size_t wp_json_skip_space(const char *text, size_t i, size_t length)
{
    return skip_space(text, i, length);
}

static size_t skip_value(const char *text, size_t i, size_t length)
{
    if (i >= length)
        return length;
    if (text[i] == '"' || text[i] == '[' || text[i] == '{') {
        int depth = 0;
        bool in_string = false;
        for (; i < length; i++) {
            char c = text[i];
            if (in_string) {
                if (c == '\\')
                    i++;
                else if (c == '"')
                    in_string = false;
                else
                    continue;
            } else if (c == '"') {
                in_string = true;
                continue;
            } else if (c == '[' || c == '{') {
                depth++;
                continue;
            } else if (c == ']' || c == '}') {
                depth--;
            } else {
                continue;
            }
            if (depth == 0 && !in_string)
                return i + 1; /* the closing quote or bracket of the value */
        }
        return length;
    }
    /* A number or a literal: up to the next delimiter. */
    while (i < length && text[i] != ',' && text[i] != '}' && text[i] != ']' && text[i] != ' ' &&
           text[i] != '\t' && text[i] != '\r' && text[i] != '\n')
        i++;
    return i;
}

/* Is the text a JSON number by RFC 8259, and all of it? */
static bool number_exactly(const char *text, size_t length)
{
    const char *problem;
    return length > 0 && (text[0] == '-' || (text[0] >= '0' && text[0] <= '9')) &&
           number_token(text, 0, length, &problem) == length && !problem;
}

/* The object at text[i] ('{'), parsed as `object`: give its first member
 * named "id" (the one cJSON_GetObjectItemCaseSensitive finds), when that is
 * a number, the text it was written with.  cJSON keeps members in the
 * order written, duplicates included, so the k-th member of the text is
 * the k-th child; names are compared decoded, so "\u0069d" is "id" too. */
static bool keep_object_id(cJSON *object, const char *text, size_t i, size_t length)
{
    i = skip_space(text, i + 1, length);
    for (cJSON *member = object->child; member && i < length && text[i] == '"';
         member = member->next) {
        i = skip_space(text, skip_value(text, i, length), length); /* the name */
        if (i >= length || text[i] != ':')
            return true; /* not the text cJSON read: leave the id as parsed */
        size_t start = skip_space(text, i + 1, length);
        size_t end = skip_value(text, start, length);
        if (member->string && strcmp(member->string, "id") == 0) {
            if (!cJSON_IsNumber(member) || member->valuestring ||
                !number_exactly(text + start, end - start))
                return true;
            char *written = cJSON_malloc(end - start + 1);
            if (!written)
                return false;
            memcpy(written, text + start, end - start);
            written[end - start] = 0;
            member->valuestring = written;
            return true;
        }
        i = skip_space(text, end, length);
        if (i < length && text[i] == ',')
            i = skip_space(text, i + 1, length);
    }
    return true;
}

static bool has_number_id(const cJSON *request)
{
    return cJSON_IsObject(request) &&
           cJSON_IsNumber(cJSON_GetObjectItemCaseSensitive(request, "id"));
}

bool wp_json_keep_id_text(cJSON *json, const char *text, size_t length)
{
    size_t i = skip_space(text, 0, length);
    if (i >= length)
        return true;
    if (cJSON_IsObject(json) && text[i] == '{')
        return has_number_id(json) ? keep_object_id(json, text, i, length) : true;
    if (!cJSON_IsArray(json) || text[i] != '[')
        return true;
    bool any = false;
    for (const cJSON *request = json->child; request && !any; request = request->next)
        any = has_number_id(request);
    if (!any) /* no walk over a batch without numeric ids */
        return true;
    i = skip_space(text, i + 1, length);
    for (cJSON *request = json->child; request && i < length; request = request->next) {
        if (has_number_id(request) && text[i] == '{' &&
            !keep_object_id(request, text, i, length))
            return false;
        i = skip_space(text, skip_value(text, i, length), length);
        if (i < length && text[i] == ',')
            i = skip_space(text, i + 1, length);
    }
    return true;
}

char *wp_json_id_text(const cJSON *id)
{
    if (cJSON_IsNumber(id) && id->valuestring) {
        char *copy = malloc(strlen(id->valuestring) + 1);
        return copy ? strcpy(copy, id->valuestring) : NULL;
    }
    return wp_canonical(id, NULL);
}

/* ---- a value's syntax, checked without a tree ---------------------------- */

static bool hex_digit(char c)
{
    return (c >= '0' && c <= '9') || (c >= 'a' && c <= 'f') || (c >= 'A' && c <= 'F');
}

/* The end of the valid value at text[i] (white space skipped before it),
 * or 0 when it is not one. */
static size_t valid_value(const char *text, size_t length, size_t i, int depth)
{
    i = skip_space(text, i, length);
    if (i >= length || depth > 64)
        return 0;
    char c = text[i];
    if (c == '"') {
        for (i++; i < length; i++) {
            unsigned char u = (unsigned char)text[i];
            if (u < 0x20)
                return 0;
            if (u == '"')
                return i + 1;
            if (u != '\\')
                continue;
            if (++i >= length || !strchr("\"\\/bfnrtu", text[i]) || !text[i])
                return 0;
            if (text[i] == 'u') {
                for (int k = 0; k < 4; k++)
                    if (++i >= length || !hex_digit(text[i]))
                        return 0;
            }
        }
        return 0;
    }
    if (c == '[' || c == '{') {
        char close = c == '[' ? ']' : '}';
        i = skip_space(text, i + 1, length);
        if (i < length && text[i] == close)
            return i + 1;
        for (;;) {
            if (close == '}') {
                if (i >= length || text[i] != '"')
                    return 0;
                i = valid_value(text, length, i, depth + 1); /* the key */
                if (!i)
                    return 0;
                i = skip_space(text, i, length);
                if (i >= length || text[i] != ':')
                    return 0;
                i++;
            }
            i = valid_value(text, length, i, depth + 1);
            if (!i)
                return 0;
            i = skip_space(text, i, length);
            if (i >= length)
                return 0;
            if (text[i] == close)
                return i + 1;
            if (text[i] != ',')
                return 0;
            i = skip_space(text, i + 1, length);
        }
    }
    static const char *const LITERALS[] = {"true", "false", "null"};
    for (int k = 0; k < 3; k++) {
        size_t n = strlen(LITERALS[k]);
        if (length - i >= n && memcmp(text + i, LITERALS[k], n) == 0)
            return i + n;
    }
    /* A number: -?(0|[1-9][0-9]*)(.[0-9]+)?([eE][+-]?[0-9]+)? */
    if (text[i] == '-')
        i++;
    if (i >= length || text[i] < '0' || text[i] > '9')
        return 0;
    if (text[i] == '0')
        i++;
    else
        while (i < length && text[i] >= '0' && text[i] <= '9')
            i++;
    if (i < length && text[i] == '.') {
        size_t digits = ++i;
        while (i < length && text[i] >= '0' && text[i] <= '9')
            i++;
        if (i == digits)
            return 0;
    }
    if (i < length && (text[i] == 'e' || text[i] == 'E')) {
        i++;
        if (i < length && (text[i] == '+' || text[i] == '-'))
            i++;
        size_t digits = i;
        while (i < length && text[i] >= '0' && text[i] <= '9')
            i++;
        if (i == digits)
            return 0;
    }
    return i;
}

bool wp_json_valid(const char *text, size_t length)
{
    size_t end = valid_value(text, length, 0, 0);
    return end && skip_space(text, end, length) == length;
}

/* ---- reading spans of a text without a tree ------------------------------ */

static size_t span_space(const char *text, size_t length, size_t i)
{
    while (i < length && (text[i] == ' ' || text[i] == '\t' || text[i] == '\n' || text[i] == '\r'))
        i++;
    return i;
}

/* The end of the string whose opening quote is at i, past its closing
 * quote; 0 when it does not end. */
static size_t span_string(const char *text, size_t length, size_t i)
{
    for (i++; i < length; i++) {
        if (text[i] == '\\')
            i++;
        else if (text[i] == '"')
            return i + 1;
    }
    return 0;
}

/* The end of the value that starts at i; 0 when the text is cut short. */
static size_t span_value(const char *text, size_t length, size_t i)
{
    if (i >= length)
        return 0;
    if (text[i] == '"')
        return span_string(text, length, i);
    if (text[i] != '[' && text[i] != '{') {
        while (i < length && strchr("+-.0123456789eEtruefalsn", text[i]) && text[i])
            i++;
        return i;
    }
    int depth = 0;
    for (; i < length; i++) {
        char c = text[i];
        if (c == '"') {
            i = span_string(text, length, i);
            if (!i)
                return 0;
            i--;
        } else if (c == '[' || c == '{') {
            depth++;
        } else if ((c == ']' || c == '}') && --depth == 0) {
            return i + 1;
        }
    }
    return 0;
}

/* The member `key` of the object at `object`: true with where its value
 * starts, and with `end` not NULL, where it ends. */
static bool find_member(const char *text, size_t length, size_t object, const char *key,
                        size_t *start, size_t *end)
{
    size_t i = span_space(text, length, object);
    if (i >= length || text[i] != '{')
        return false;
    size_t key_length = strlen(key);
    i = span_space(text, length, i + 1);
    while (i < length && text[i] == '"') {
        size_t after = span_string(text, length, i);
        if (!after)
            return false;
        /* Compared as written: a key spelt with escapes is not found, and
         * the caller falls back to the full parse. */
        bool match = after - i - 2 == key_length && memcmp(text + i + 1, key, key_length) == 0;
        i = span_space(text, length, after);
        if (i >= length || text[i] != ':')
            return false;
        i = span_space(text, length, i + 1);
        if (match && !end) {
            *start = i;
            return i < length;
        }
        size_t value_end = span_value(text, length, i);
        if (!value_end)
            return false;
        if (match) {
            *start = i;
            *end = value_end;
            return true;
        }
        i = span_space(text, length, value_end);
        if (i >= length || text[i] != ',')
            return false;
        i = span_space(text, length, i + 1);
    }
    return false;
}

bool wp_json_member(const char *text, size_t length, size_t object, const char *key,
                    size_t *start, size_t *end)
{
    return find_member(text, length, object, key, start, end);
}

bool wp_json_member_start(const char *text, size_t length, size_t object, const char *key,
                          size_t *start)
{
    return find_member(text, length, object, key, start, NULL);
}

/* Exact powers of ten: every one up to 10^22 is a double. */
static const double POWERS_OF_TEN[] = {1e0,  1e1,  1e2,  1e3,  1e4,  1e5,  1e6,  1e7,
                                       1e8,  1e9,  1e10, 1e11, 1e12, 1e13, 1e14, 1e15,
                                       1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22};

/* A JSON number at text[*i] (the scan has checked its form), as strtod
 * reads it.  Most numbers written by programs have at most 15 significant
 * digits and a small exponent: their digits m are then an exact double, as
 * is 10^|e| for |e| <= 22, and m * 10^e or m / 10^-e is one correctly
 * rounded operation -- the double nearest the decimal, which is what strtod
 * returns (Clinger's fast path).  Anything else is left to strtod. */
static bool read_number(const char *text, size_t length, size_t *i, double *out)
{
    size_t k = *i;
    bool negative = k < length && text[k] == '-';
    k += negative;
    uint64_t digits = 0;
    int significant = 0, exponent = 0;
    bool fast = true;
    size_t start_digits = k;
    for (; k < length && text[k] >= '0' && text[k] <= '9'; k++) {
        if (significant || text[k] != '0')
            significant++;
        if (significant <= 19)
            digits = digits * 10 + (uint64_t)(text[k] - '0');
        else
            exponent++;
    }
    if (k == start_digits)
        return false;
    if (k < length && text[k] == '.') {
        size_t fraction = ++k;
        for (; k < length && text[k] >= '0' && text[k] <= '9'; k++) {
            if (significant || text[k] != '0')
                significant++;
            if (significant <= 19) {
                digits = digits * 10 + (uint64_t)(text[k] - '0');
                exponent--;
            }
        }
        if (k == fraction)
            return false;
    }
    if (k < length && (text[k] == 'e' || text[k] == 'E')) {
        k++;
        bool minus = k < length && text[k] == '-';
        if (k < length && (text[k] == '-' || text[k] == '+'))
            k++;
        size_t start = k;
        int value = 0;
        for (; k < length && text[k] >= '0' && text[k] <= '9'; k++) {
            if (value < 100000)
                value = value * 10 + (text[k] - '0');
            else
                fast = false;
        }
        if (k == start)
            return false;
        exponent += minus ? -value : value;
    }
    if (k < length && number_char(text[k]))
        return false; /* more of a token than a number: not ours */
    if (fast && significant <= 15 && exponent >= -22 && exponent <= 22) {
        double value = (double)digits;
        value = exponent < 0 ? value / POWERS_OF_TEN[-exponent] : value * POWERS_OF_TEN[exponent];
        *out = negative ? -value : value;
        *i = k;
        return true;
    }
    char token[64];
    size_t n = k - *i;
    if (n >= sizeof token)
        return false;
    memcpy(token, text + *i, n);
    token[n] = 0;
    char *after;
    *out = strtod(token, &after);
    if (after != token + n || !isfinite(*out))
        return false;
    *i = k;
    return true;
}

bool wp_json_read_number(const char *text, size_t length, size_t *i, double *out)
{
    return read_number(text, length, i, out);
}

size_t wp_json_string_end(const char *text, size_t length, size_t i)
{
    return span_string(text, length, i);
}

long wp_json_triples(const char *text, size_t length, double (**out)[3], size_t *end)
{
    *out = NULL;
    size_t i = span_space(text, length, 0);
    if (i >= length || text[i] != '[')
        return -1;
    /* Room for as many as the text could hold ("[0,0,0]," is 8 bytes):
     * only the pages written are ever touched, and it is not regrown. */
    size_t capacity = (length - i) / 8 + 1;
    double(*items)[3] = malloc(capacity * sizeof *items);
    if (!items)
        return -1;
    wp_advise_huge(items, capacity * sizeof *items);
    size_t count = 0;
    i = span_space(text, length, i + 1);
    if (i < length && text[i] == ']') {
        i++;
    } else {
        for (;;) {
            if (count == capacity || i >= length || text[i] != '[')
                goto refuse;
            for (int k = 0; k < 3; k++) {
                i = span_space(text, length, i + 1);
                if (!read_number(text, length, &i, &items[count][k]))
                    goto refuse;
                i = span_space(text, length, i);
                if (i >= length || text[i] != (k < 2 ? ',' : ']'))
                    goto refuse;
            }
            count++;
            i = span_space(text, length, i + 1);
            if (i < length && text[i] == ']') {
                i++;
                break;
            }
            if (i >= length || text[i] != ',')
                goto refuse;
            i = span_space(text, length, i + 1);
        }
    }
    if (end)
        *end = i;
    else if (span_space(text, length, i) != length)
        goto refuse;
    /* Give back what the estimate took beyond the count. */
    double(*fitted)[3] = realloc(items, (count ? count : 1) * sizeof *items);
    *out = fitted ? fitted : items;
    return (long)count;
refuse:
    free(items);
    return -1;
}
