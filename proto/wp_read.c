/* wp_read.c -- strict typed access to the members of a request. */
#include "wp_json.h"

#include <math.h>
#include <string.h>

bool wp_check_object(const cJSON *value, const char *path, const char *const *allowed,
                     wp_error *error)
{
    if (!cJSON_IsObject(value)) {
        wp_error_set(error, WP_INVALID_PARAMS, path, "must be an object, not %s",
                     wp_type_name(value));
        return false;
    }
    /* Field paths are formatted only for an error: requests of many
     * objects (load cases) are checked member by member. */
    char field[WP_FIELD_MAX];
    for (const cJSON *member = value->child; member; member = member->next) {
        bool known = false;
        for (const char *const *name = allowed; *name && !known; name++)
            known = strcmp(*name, member->string) == 0;
        if (!known) {
            wp_path_key(field, path, member->string);
            wp_error_set(error, WP_INVALID_PARAMS, field, "unknown field");
            return false;
        }
        for (const cJSON *other = member->next; other; other = other->next)
            if (strcmp(other->string, member->string) == 0) {
                wp_path_key(field, path, member->string);
                wp_error_set(error, WP_INVALID_PARAMS, field, "appears more than once");
                return false;
            }
    }
    return true;
}

bool wp_number(const cJSON *value, const char *path, double *out, wp_error *error)
{
    if (!cJSON_IsNumber(value)) {
        wp_error_set(error, WP_INVALID_PARAMS, path, "must be a number, not %s",
                     wp_type_name(value));
        return false;
    }
    if (!isfinite(value->valuedouble)) {
        wp_error_set(error, WP_INVALID_PARAMS, path, "must be a finite number");
        return false;
    }
    *out = value->valuedouble;
    return true;
}

bool wp_vector2(const cJSON *value, const char *path, double out[2], wp_error *error)
{
    if (!cJSON_IsArray(value) || cJSON_GetArraySize(value) != 2) {
        wp_error_set(error, WP_INVALID_PARAMS, path, "must be an array of 2 numbers, not %s",
                     cJSON_IsArray(value) ? "an array of another length" : wp_type_name(value));
        return false;
    }
    char field[WP_FIELD_MAX];
    const cJSON *item = value->child;
    for (int i = 0; i < 2; i++, item = item->next) {
        if (cJSON_IsNumber(item) && isfinite(item->valuedouble)) {
            out[i] = item->valuedouble; /* wp_number's answer, without a path */
            continue;
        }
        wp_path_index(field, path, (size_t)i);
        if (!wp_number(item, field, &out[i], error))
            return false;
    }
    return true;
}

/* The member, or NULL with an error when it is missing and required. */
static const cJSON *member(const cJSON *object, const char *path, const char *key, bool required,
                           bool *present, wp_error *error, bool *ok)
{
    const cJSON *value = cJSON_GetObjectItemCaseSensitive(object, key);
    if (present)
        *present = value != NULL;
    *ok = value != NULL || !required;
    if (!value && required) {
        char field[WP_FIELD_MAX];
        wp_path_key(field, path, key);
        wp_error_set(error, WP_INVALID_PARAMS, field, "required");
    }
    return value;
}

bool wp_member_number(const cJSON *object, const char *path, const char *key, bool required,
                      double *out, bool *present, wp_error *error)
{
    bool ok;
    const cJSON *value = member(object, path, key, required, present, error, &ok);
    if (!value)
        return ok;
    if (cJSON_IsNumber(value) && isfinite(value->valuedouble)) {
        *out = value->valuedouble; /* wp_number's answer, without a path */
        return true;
    }
    char field[WP_FIELD_MAX];
    wp_path_key(field, path, key);
    return wp_number(value, field, out, error);
}

bool wp_member_vector2(const cJSON *object, const char *path, const char *key, bool required,
                       double out[2], bool *present, wp_error *error)
{
    bool ok;
    const cJSON *value = member(object, path, key, required, present, error, &ok);
    if (!value)
        return ok;
    const cJSON *x = cJSON_IsArray(value) ? value->child : NULL, *y = x ? x->next : NULL;
    if (y && !y->next && cJSON_IsNumber(x) && cJSON_IsNumber(y) && isfinite(x->valuedouble) &&
        isfinite(y->valuedouble)) {
        out[0] = x->valuedouble; /* wp_vector2's answer, without a path */
        out[1] = y->valuedouble;
        return true;
    }
    char field[WP_FIELD_MAX];
    wp_path_key(field, path, key);
    return wp_vector2(value, field, out, error);
}

bool wp_member_string(const cJSON *object, const char *path, const char *key, bool required,
                      const char **out, wp_error *error)
{
    bool ok;
    const cJSON *value = member(object, path, key, required, NULL, error, &ok);
    *out = NULL;
    if (!value)
        return ok;
    if (!cJSON_IsString(value)) {
        char field[WP_FIELD_MAX];
        wp_path_key(field, path, key);
        wp_error_set(error, WP_INVALID_PARAMS, field, "must be a string, not %s",
                     wp_type_name(value));
        return false;
    }
    *out = value->valuestring;
    return true;
}
