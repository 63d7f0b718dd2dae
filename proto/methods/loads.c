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

bool wp_point_near_part(const wr_fixture *f, const double at[2], const char *path,
                        wp_error *error)
{
    double d = hypot(at[0] - f->com[0], at[1] - f->com[1]);
    if (d <= f->size)
        return true;
    wp_error_set(error, WP_INVALID_PARAMS, path,
                 "(%g, %g) is %.6g from the part's centre of mass, %.6g beyond its size (%.6g): "
                 "a load acts on the part",
                 at[0], at[1], d, d - f->size, f->size);
    return false;
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
        /* m G in kg * length / s^2: the model system's force already.
         * The tilt convention of gravity.sweep: phi is where it pulls. */
        w[0] = f->mass * g * cos(phi * DEGREES);
        w[1] = f->mass * g * sin(phi * DEGREES);
    } else if (cJSON_GetObjectItemCaseSensitive(json, "force")) {
        double force[2], at[2];
        wp_path_key(field, path, "at");
        if (!wp_check_object(json, path, FORCE_LOAD_FIELDS, error) ||
            !wp_member_string(json, path, "name", false, &name, error) ||
            !wp_member_vector2(json, path, "force", true, force, NULL, error) ||
            !wp_member_vector2(json, path, "at", true, at, NULL, error) ||
            !wp_point_near_part(f, at, field, error))
            return false;
        const double model[2] = {force[0] * factor, force[1] * factor};
        wr_fixture_force_wrench(f, model, at, w);
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
    for (int k = 0; k < 3; k++)
        sum[k] += w[k];
    if (!(isfinite(sum[0]) && isfinite(sum[1]) && isfinite(sum[2]))) {
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
