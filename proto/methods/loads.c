/* loads.c -- loads and cases from JSON into the model system. */
#include "loads.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static const char *const CASE_FIELDS[] = {"name", "loads", NULL};
static const char *const GRAVITY_LOAD_FIELDS[] = {"gravity", "name", NULL};
static const char *const GRAVITY_FIELDS[] = {"g", "direction_deg", NULL};
static const char *const FORCE_LOAD_FIELDS[] = {"force", "at", "name", NULL};
static const char *const WRENCH_LOAD_FIELDS[] = {"wrench", "name", NULL};

#define DEGREES (3.14159265358979323846 / 180)

static bool near_part(const wr_fixture *f, const double at[2])
{
    return hypot(at[0] - f->com[0], at[1] - f->com[1]) <= f->size;
}

bool wp_point_near_part(const wr_fixture *f, const double at[2], const char *path,
                        wp_error *error)
{
    double d = hypot(at[0] - f->com[0], at[1] - f->com[1]);
    if (near_part(f, at))
        return true;
    wp_error_set(error, WP_INVALID_PARAMS, path,
                 "(%g, %g) is %.6g from the part's centre of mass, %.6g beyond its size (%.6g): "
                 "a load acts on the part",
                 at[0], at[1], d, d - f->size, f->size);
    return false;
}

/* A load's wrench in the model system, from the numbers as given (in the
 * fixture's units): the one conversion of each kind, for the tree's reader
 * and the text's. */
static void gravity_load(const wr_fixture *f, double g, double phi, double w[3])
{
    /* m G in kg * length / s^2: the model system's force already.  The
     * tilt convention of gravity.sweep: phi is where it pulls. */
    w[0] = f->mass * g * cos(phi * DEGREES);
    w[1] = f->mass * g * sin(phi * DEGREES);
    w[2] = 0;
}

static void force_load(const wr_fixture *f, const double force[2], const double at[2],
                       double w[3])
{
    double factor = wr_fixture_force_factor(f);
    const double model[2] = {force[0] * factor, force[1] * factor};
    wr_fixture_force_wrench(f, model, at, w);
}

/* Add w to sum; false when the sum overflows. */
static bool add_load(double sum[3], const double w[3])
{
    for (int k = 0; k < 3; k++)
        sum[k] += w[k];
    return isfinite(sum[0]) && isfinite(sum[1]) && isfinite(sum[2]);
}

/* One load at `path`, added to `sum` (model system). */
static bool read_load(const cJSON *json, const char *path, const wr_fixture *f, double sum[3],
                      wp_error *error)
{
    if (!cJSON_IsObject(json)) {
        wp_error_set(error, WP_INVALID_PARAMS, path,
                     "a load is {\"gravity\": {...}}, {\"force\", \"at\"} or {\"wrench\"}, not %s",
                     wp_type_name(json));
        return false;
    }
    const char *name;
    double w[3] = {0, 0, 0}, factor = wr_fixture_force_factor(f);
    char field[WP_FIELD_MAX];
    if (cJSON_GetObjectItemCaseSensitive(json, "gravity")) {
        const cJSON *gravity = cJSON_GetObjectItemCaseSensitive(json, "gravity");
        double g, phi;
        wp_path_key(field, path, "gravity");
        if (!wp_check_object(json, path, GRAVITY_LOAD_FIELDS, error) ||
            !wp_member_string(json, path, "name", false, &name, error) ||
            !wp_check_object(gravity, field, GRAVITY_FIELDS, error) ||
            !wp_member_number(gravity, field, "g", true, &g, NULL, error) ||
            !wp_member_number(gravity, field, "direction_deg", true, &phi, NULL, error))
            return false;
        if (g < 0) {
            char g_field[WP_FIELD_MAX];
            wp_path_key(g_field, field, "g");
            wp_error_set(error, WP_INVALID_PARAMS, g_field,
                         "must not be negative (it is a magnitude; direction_deg says where it "
                         "pulls), got %g",
                         g);
            return false;
        }
        gravity_load(f, g, phi, w);
    } else if (cJSON_GetObjectItemCaseSensitive(json, "force")) {
        double force[2], at[2];
        wp_path_key(field, path, "at");
        if (!wp_check_object(json, path, FORCE_LOAD_FIELDS, error) ||
            !wp_member_string(json, path, "name", false, &name, error) ||
            !wp_member_vector2(json, path, "force", true, force, NULL, error) ||
            !wp_member_vector2(json, path, "at", true, at, NULL, error) ||
            !wp_point_near_part(f, at, field, error))
            return false;
        force_load(f, force, at, w);
    } else if (cJSON_GetObjectItemCaseSensitive(json, "wrench")) {
        const cJSON *list = cJSON_GetObjectItemCaseSensitive(json, "wrench");
        wp_path_key(field, path, "wrench");
        if (!wp_check_object(json, path, WRENCH_LOAD_FIELDS, error) ||
            !wp_member_string(json, path, "name", false, &name, error))
            return false;
        if (!cJSON_IsArray(list) || cJSON_GetArraySize(list) != 3) {
            wp_error_set(error, WP_INVALID_PARAMS, field,
                         "a wrench is [f_x, f_y, tau]: 3 numbers");
            return false;
        }
        const cJSON *item = list->child;
        for (int k = 0; k < 3; k++, item = item->next) {
            char at[WP_FIELD_MAX];
            wp_path_index(at, field, (size_t)k);
            if (!wp_number(item, at, &w[k], error))
                return false;
            w[k] *= factor;
        }
    } else {
        wp_error_set(error, WP_INVALID_PARAMS, path,
                     "a load has \"gravity\", \"force\" (with \"at\") or \"wrench\"");
        return false;
    }
    if (!add_load(sum, w)) {
        wp_error_set(error, WP_INVALID_PARAMS, path, "too large: the case's load overflows");
        return false;
    }
    return true;
}

bool wp_cases_read(const cJSON *json, const char *path, const wr_fixture *f, int most,
                   wp_cases *out, wp_error *error)
{
    memset(out, 0, sizeof *out);
    if (!json) {
        wp_error_set(error, WP_INVALID_PARAMS, path, "required");
        return false;
    }
    if (!cJSON_IsArray(json)) {
        wp_error_set(error, WP_INVALID_PARAMS, path, "must be an array of cases, not %s",
                     wp_type_name(json));
        return false;
    }
    int count = cJSON_GetArraySize(json);
    if (count == 0) {
        wp_error_set(error, WP_INVALID_PARAMS, path,
                     "empty: give at least one case {\"loads\": [...]}");
        return false;
    }
    if (count > most) {
        wp_error_set(error, WP_INVALID_PARAMS, path,
                     "at most %d cases (the daemon's --max-cases), %d given", most, count);
        return false;
    }
    out->items = calloc((size_t)count, sizeof *out->items);
    if (!out->items) {
        wp_error_set(error, WP_INTERNAL, "", "out of memory");
        return false;
    }
    int i = 0;
    for (const cJSON *item = json->child; item; item = item->next, i++) {
        char field[WP_FIELD_MAX], loads_path[WP_FIELD_MAX];
        wp_path_index(field, path, (size_t)i);
        wp_case *c = &out->items[i];
        if (!wp_check_object(item, field, CASE_FIELDS, error) ||
            !wp_member_string(item, field, "name", false, &c->name, error))
            break;
        const cJSON *loads = cJSON_GetObjectItemCaseSensitive(item, "loads");
        wp_path_key(loads_path, field, "loads");
        if (!cJSON_IsArray(loads)) {
            wp_error_set(error, WP_INVALID_PARAMS, loads_path,
                         loads ? "must be an array of loads" : "required");
            break;
        }
        int n = cJSON_GetArraySize(loads);
        if (n == 0 || n > WP_MAX_LOADS) {
            if (n == 0)
                wp_error_set(error, WP_INVALID_PARAMS, loads_path, "empty: a case has a load");
            else
                wp_error_set(error, WP_INVALID_PARAMS, loads_path,
                             "at most %d loads in a case, %d given", WP_MAX_LOADS, n);
            break;
        }
        int j = 0;
        const cJSON *load = loads->child;
        for (; load; load = load->next, j++) {
            char at[WP_FIELD_MAX];
            wp_path_index(at, loads_path, (size_t)j);
            if (!read_load(load, at, f, c->load, error))
                break;
        }
        if (load)
            break;
        out->count++;
    }
    if (out->count != count) {
        wp_cases_release(out);
        return false;
    }
    return true;
}

void wp_cases_release(wp_cases *cases)
{
    free(cases->items);
    memset(cases, 0, sizeof *cases);
}

/* ---- cases read from their text ------------------------------------------
 * The common shape only, checked as the tree's reader checks it; anything
 * else (an escape in a key or a name, a member twice or unknown, a value of
 * another type, a load the tree's reader would refuse) makes the text
 * reader give up, and the caller reads the tree, which says what is wrong. */

typedef struct text_reader {
    char *text;
    size_t length, i;
} text_reader;

static void skip_space(text_reader *r)
{
    r->i = wp_json_skip_space(r->text, r->i, r->length);
}

/* The byte c next (after white space), consumed. */
static bool take(text_reader *r, char c)
{
    skip_space(r);
    if (r->i >= r->length || r->text[r->i] != c)
        return false;
    r->i++;
    return true;
}

/* A string without escapes: its text, which ends at the next '"' (the
 * text is not written until all of it is read). */
static const char *plain_string(text_reader *r, size_t *length)
{
    skip_space(r);
    size_t start = r->i;
    if (start >= r->length || r->text[start] != '"')
        return NULL;
    size_t end = wp_json_string_end(r->text, r->length, start);
    if (!end || memchr(r->text + start, '\\', end - start))
        return NULL;
    r->i = end;
    *length = end - start - 2;
    return r->text + start + 1;
}

/* A key and its colon: the key's index in `keys`, or -1. */
static int key(text_reader *r, const char *const *keys)
{
    size_t length;
    const char *name = plain_string(r, &length);
    if (!name || !take(r, ':'))
        return -1;
    for (int k = 0; keys[k]; k++)
        if (strlen(keys[k]) == length && memcmp(name, keys[k], length) == 0)
            return k;
    return -1;
}

static bool number(text_reader *r, double *out)
{
    skip_space(r);
    return wp_json_read_number(r->text, r->length, &r->i, out);
}

/* [n_0, ..., n_{count-1}] */
static bool numbers(text_reader *r, double *out, int count)
{
    if (!take(r, '['))
        return false;
    for (int k = 0; k < count; k++)
        if (!number(r, &out[k]) || !take(r, k + 1 < count ? ',' : ']'))
            return false;
    return true;
}

/* After an object's member: true with *more when a ',' follows, false
 * when neither ',' nor `close` does. */
static bool next_member(text_reader *r, char close, bool *more)
{
    skip_space(r);
    if (r->i < r->length && r->text[r->i] == ',') {
        r->i++;
        *more = true;
        return true;
    }
    *more = false;
    return take(r, close);
}

static const char *const LOAD_KEYS[] = {"name", "gravity", "force", "at", "wrench", NULL};
enum { LOAD_NAME, LOAD_GRAVITY, LOAD_FORCE, LOAD_AT, LOAD_WRENCH };

static bool text_load(text_reader *r, const wr_fixture *f, double sum[3])
{
    double g = 0, phi = 0, force[2] = {0, 0}, at[2] = {0, 0}, w[3] = {0, 0, 0};
    unsigned seen = 0;
    if (!take(r, '{'))
        return false;
    for (bool more = true; more;) {
        int k = key(r, LOAD_KEYS);
        if (k < 0 || (seen & 1u << k))
            return false;
        seen |= 1u << k;
        bool read = false;
        switch (k) {
        case LOAD_NAME:
            read = plain_string(r, &(size_t){0}) != NULL;
            break;
        case LOAD_GRAVITY: {
            static const char *const keys[] = {"g", "direction_deg", NULL};
            unsigned got = 0;
            read = take(r, '{');
            for (bool again = read; again;) {
                int j = key(r, keys);
                read = j >= 0 && !(got & 1u << j) && number(r, j ? &phi : &g) &&
                       next_member(r, '}', &again);
                got |= j >= 0 ? 1u << j : 0;
                if (!read)
                    break;
            }
            read = read && got == 3;
            break;
        }
        case LOAD_FORCE:
            read = numbers(r, force, 2);
            break;
        case LOAD_AT:
            read = numbers(r, at, 2);
            break;
        case LOAD_WRENCH:
            read = numbers(r, w, 3);
            break;
        }
        if (!read || !next_member(r, '}', &more))
            return false;
    }
    unsigned kind = seen & ~(1u << LOAD_NAME);
    if (kind == 1u << LOAD_GRAVITY) {
        if (g < 0)
            return false;
        gravity_load(f, g, phi, w);
    } else if (kind == (1u << LOAD_FORCE | 1u << LOAD_AT)) {
        if (!near_part(f, at))
            return false;
        force_load(f, force, at, w);
    } else if (kind == 1u << LOAD_WRENCH) {
        for (int k = 0; k < 3; k++)
            w[k] *= wr_fixture_force_factor(f);
    } else {
        return false;
    }
    return add_load(sum, w);
}

static const char *const CASE_KEYS[] = {"name", "loads", NULL};

static bool text_case(text_reader *r, const wr_fixture *f, wp_case *c)
{
    unsigned seen = 0;
    if (!take(r, '{'))
        return false;
    for (bool more = true; more;) {
        int k = key(r, CASE_KEYS);
        if (k < 0 || (seen & 1u << k))
            return false;
        seen |= 1u << k;
        if (k == 0) {
            if (!(c->name = plain_string(r, &(size_t){0})))
                return false;
        } else {
            if (!take(r, '['))
                return false;
            int n = 0;
            for (bool again = true; again; n++)
                if (n == WP_MAX_LOADS || !text_load(r, f, c->load) ||
                    !next_member(r, ']', &again))
                    return false;
        }
        if (!next_member(r, '}', &more))
            return false;
    }
    return seen & 2u;
}

bool wp_cases_read_text(char *text, size_t length, const wr_fixture *f, int most,
                        wp_cases *out)
{
    memset(out, 0, sizeof *out);
    text_reader r = {text, length, 0};
    if (!take(&r, '['))
        return false;
    /* Room for as many cases as the text could hold ("{"loads":[{"wrench":
     * [0,0,0]}]}," is 28 bytes), given back when counted. */
    size_t capacity = length / 28 + 1;
    if (capacity > (size_t)most)
        capacity = (size_t)most;
    out->items = calloc(capacity, sizeof *out->items);
    if (!out->items)
        return false;
    for (bool more = true; more; out->count++)
        if ((size_t)out->count == capacity || !text_case(&r, f, &out->items[out->count]) ||
            !next_member(&r, ']', &more))
            goto refuse;
    skip_space(&r);
    if (r.i != length)
        goto refuse;
    /* Read whole: the names are ended in place. */
    for (int c = 0; c < out->count; c++)
        if (out->items[c].name)
            *strchr(out->items[c].name, '"') = 0;
    return true;
refuse:
    wp_cases_release(out);
    return false;
}
