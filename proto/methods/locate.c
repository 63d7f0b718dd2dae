/* locate.c -- fixture.locating: where locator errors put the part
 * (docs/PROTOCOL.md, lib/wr_locate.h). */
#include "methods.h"

#include "common.h"
#include "wr_locate.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* At most this many features in one request: each costs a few
 * microseconds, and a person names a handful. */
#define LOCATE_MAX_FEATURES 4096

static const char *const FEATURE_FIELDS[] = {"name", "at", NULL};

/* params.tolerance: a number for every fixel, or one per fixel.  Its
 * values are checked here (before the fixture is looked up); the list's
 * length once the fixture is known. */
static bool read_tolerance(const cJSON *value, double *out, int *count, wp_error *error)
{
    if (cJSON_IsNumber(value)) {
        *count = -1;
        if (!wp_number(value, "params.tolerance", &out[0], error))
            return false;
        if (!(out[0] >= 0)) {
            wp_error_set(error, WP_INVALID_PARAMS, "params.tolerance",
                         "must not be negative (each locator is off by at most +-tolerance "
                         "along its normal), not %g", out[0]);
            return false;
        }
        return true;
    }
    if (!cJSON_IsArray(value)) {
        wp_error_set(error, WP_INVALID_PARAMS, "params.tolerance",
                     "must be a number or an array of one number per fixel, not %s",
                     wp_type_name(value));
        return false;
    }
    int n = cJSON_GetArraySize(value);
    if (n > WR_MAX_FIXELS) {
        wp_error_set(error, WP_INVALID_PARAMS, "params.tolerance",
                     "has %d numbers; a fixture has at most %d fixels", n, WR_MAX_FIXELS);
        return false;
    }
    int i = 0;
    for (const cJSON *t = value->child; t; t = t->next, i++) {
        char path[WP_FIELD_MAX];
        wp_path_index(path, "params.tolerance", (size_t)i);
        if (!wp_number(t, path, &out[i], error))
            return false;
        if (!(out[i] >= 0)) {
            wp_error_set(error, WP_INVALID_PARAMS, path,
                         "must not be negative (locator %d is off by at most +-this along its "
                         "normal), not %g", i + 1, out[i]);
            return false;
        }
    }
    *count = n;
    return true;
}

/* params.features: [{"name"?, "at": [x, y]}, ...] into a new array. */
static bool read_features(const cJSON *value, wr_locate_feature **out, const char ***names,
                          size_t *count, wp_error *error)
{
    *out = NULL;
    *names = NULL;
    *count = 0;
    if (!value)
        return true;
    if (!cJSON_IsArray(value)) {
        wp_error_set(error, WP_INVALID_PARAMS, "params.features",
                     "must be an array of {\"name\", \"at\": [x, y]}, not %s", wp_type_name(value));
        return false;
    }
    int n = cJSON_GetArraySize(value);
    if (n > LOCATE_MAX_FEATURES) {
        wp_error_set(error, WP_INVALID_PARAMS, "params.features",
                     "has %d features; at most %d are answered in one request", n,
                     LOCATE_MAX_FEATURES);
        return false;
    }
    if (n == 0)
        return true;
    *out = calloc((size_t)n, sizeof **out);
    *names = calloc((size_t)n, sizeof **names);
    if (!*out || !*names) {
        wp_error_status(error, WR_NO_MEMORY, "", "out of memory");
        return false;
    }
    size_t i = 0;
    for (const cJSON *ft = value->child; ft; ft = ft->next, i++) {
        char path[WP_FIELD_MAX];
        wp_path_index(path, "params.features", i);
        if (!cJSON_IsObject(ft)) {
            wp_error_set(error, WP_INVALID_PARAMS, path,
                         "must be an object {\"name\", \"at\": [x, y]}, not %s", wp_type_name(ft));
            return false;
        }
        if (!wp_check_object(ft, path, FEATURE_FIELDS, error) ||
            !wp_member_vector2(ft, path, "at", true, (*out)[i].at, NULL, error))
            return false;
        if (cJSON_GetObjectItemCaseSensitive(ft, "name") &&
            !wp_member_string(ft, path, "name", false, &(*names)[i], error))
            return false;
    }
    *count = i;
    return true;
}

/* [v0, ...]: n numbers, no -0. */
static void write_numbers(wp_writer *out, const double *v, int n)
{
    wp_write_array(out);
    for (int i = 0; i < n; i++)
        wp_write_number(out, v[i] + 0.0);
    wp_write_array_end(out);
}

/* {"vector": [x, y], "length": l} */
static void write_displacement(wp_writer *out, const double v[2], double length)
{
    wp_write_object(out);
    wp_write_key(out, "vector");
    write_numbers(out, v, 2);
    wp_write_member_number(out, "length", length);
    wp_write_object_end(out);
}

static void write_feature(wp_writer *out, const wr_locate_feature *ft, const char *name)
{
    wp_write_object(out);
    wp_write_key(out, "name");
    if (name)
        wp_write_string(out, name);
    else
        wp_write_null(out);
    wp_write_key(out, "at");
    write_numbers(out, ft->at, 2);
    wp_write_key(out, "linear");
    write_displacement(out, ft->linear, ft->linear_length);
    wp_write_key(out, "exact");
    write_displacement(out, ft->exact, ft->exact_length);
    double rows[2][2] = {{ft->covariance[0], ft->covariance[1]},
                         {ft->covariance[1], ft->covariance[2]}};
    wp_write_key(out, "covariance");
    wp_write_array(out);
    for (int r = 0; r < 2; r++)
        write_numbers(out, rows[r], 2);
    wp_write_array_end(out);
    wp_write_key(out, "ellipse");
    wp_write_object(out);
    wp_write_key(out, "axes");
    write_numbers(out, ft->axes, 2);
    wp_write_member_number(out, "angle_deg", ft->angle_deg + 0.0);
    wp_write_object_end(out);
    wp_write_object_end(out);
}

static void write_result(wp_writer *out, const wr_locating *m, const wr_locate_feature *features,
                         const char **names, size_t count)
{
    wp_write_object(out);
    wp_write_member_bool(out, "deterministic", m->deterministic);
    wp_write_key(out, "free_motion");
    if (m->deterministic) {
        wp_write_null(out);
    } else {
        wp_write_object(out);
        wp_write_key(out, "twist");
        write_numbers(out, m->twist, 3);
        wp_write_member_string(out, "kind", m->rotation ? "rotation" : "translation");
        wp_write_key(out, "about");
        if (m->rotation)
            write_numbers(out, m->about, 2);
        else
            wp_write_null(out);
        wp_write_object_end(out);
        /* Nothing is determined: the rest is null. */
        static const char *const REST[] = {"sensitivity", "condition", "pose_error", "features"};
        for (int i = 0; i < 4; i++) {
            wp_write_key(out, REST[i]);
            wp_write_null(out);
        }
        wp_write_object_end(out);
        return;
    }
    wp_write_key(out, "sensitivity");
    wp_write_array(out);
    for (int j = 0; j < 3; j++)
        write_numbers(out, m->sensitivity[j], m->fixel_count);
    wp_write_array_end(out);
    wp_write_member_number(out, "condition", m->condition);
    wp_write_key(out, "pose_error");
    wp_write_object(out);
    wp_write_key(out, "linear");
    write_numbers(out, m->pose_linear, 3);
    wp_write_key(out, "exact");
    write_numbers(out, m->pose_exact, 3);
    wp_write_object_end(out);
    wp_write_key(out, "features");
    wp_write_array(out);
    for (size_t i = 0; i < count; i++)
        write_feature(out, &features[i], names[i]);
    wp_write_array_end(out);
    wp_write_object_end(out);
}

/* Light on an event loop (a stored, derived fixture) with few features:
 * eight pose solves and a few microseconds a feature. */
#define LOCATE_LIGHT_FEATURES 64

bool wp_locating_light(const cJSON *params, int cones)
{
    (void)cones; /* the cones are not used */
    const cJSON *features = cJSON_GetObjectItemCaseSensitive(params, "features");
    return !cJSON_IsArray(features) || cJSON_GetArraySize(features) <= LOCATE_LIGHT_FEATURES;
}

/* Params: fixture, tolerance (a number or one per fixel), features?,
 * sigma_ratio? (default 3).  Lengths in the fixture's length unit. */
bool wp_handle_fixture_locating(wp_call *call, wp_writer *out)
{
    const cJSON *params = call->params;
    wp_error *error = call->error;
    double tolerance[WR_MAX_FIXELS];
    int listed;
    double sigma_ratio = 3;
    bool present = false;
    if (!read_tolerance(cJSON_GetObjectItemCaseSensitive(params, "tolerance"), tolerance, &listed,
                        error) ||
        !wp_member_number(params, "params", "sigma_ratio", false, &sigma_ratio, &present, error))
        return false;
    if (present && !(sigma_ratio > 0)) {
        wp_error_set(error, WP_INVALID_PARAMS, "params.sigma_ratio",
                     "must be above 0 (sigma = tolerance / sigma_ratio), not %g", sigma_ratio);
        return false;
    }
    wr_locate_feature *features;
    const char **names;
    size_t count;
    bool ok = false;
    if (!read_features(cJSON_GetObjectItemCaseSensitive(params, "features"), &features, &names,
                       &count, error))
        goto done;
    wp_fixture_use *use = wp_call_fixture(call);
    if (!use)
        goto done;
    const wr_fixture *f = use->fixture;
    if (listed >= 0 && listed != f->fixel_count) {
        wp_error_set(error, WP_INVALID_PARAMS, "params.tolerance",
                     "has %d number%s; the fixture has %d fixels (one tolerance each, or one "
                     "number for all)", listed, listed == 1 ? "" : "s", f->fixel_count);
        goto done;
    }
    if (listed < 0)
        for (int i = 1; i < f->fixel_count; i++)
            tolerance[i] = tolerance[0];
    wr_locating m;
    wr_error why = {"", ""};
    wr_status status = wr_locate(f, tolerance, sigma_ratio, features, count, &m, &why);
    if (status != WR_OK) {
        wp_error_refusal(error, status, "params", &why);
        goto done;
    }
    write_result(out, &m, features, names, count);
    ok = true;
done:
    free(features);
    free(names);
    return ok;
}
