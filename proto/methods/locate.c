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

static bool add(cJSON *object, const char *key, cJSON *item)
{
    if (!item)
        return false;
    cJSON_AddItemToObject(object, key, item);
    return true;
}

static cJSON *numbers(const double *v, int n)
{
    double w[8];
    for (int i = 0; i < n; i++)
        w[i] = v[i] + 0.0; /* no -0 */
    return cJSON_CreateDoubleArray(w, n);
}

static cJSON *feature_json(const wr_locate_feature *ft, const char *name)
{
    cJSON *o = cJSON_CreateObject(), *linear = cJSON_CreateObject(), *exact = cJSON_CreateObject(),
          *ellipse = cJSON_CreateObject(), *cov = cJSON_CreateArray();
    bool ok = o && linear && exact && ellipse && cov;
    ok = ok && add(o, "name", name ? cJSON_CreateString(name) : cJSON_CreateNull()) &&
         add(o, "at", numbers(ft->at, 2));
    ok = ok && add(linear, "vector", numbers(ft->linear, 2)) &&
         add(linear, "length", cJSON_CreateNumber(ft->linear_length));
    ok = ok && add(exact, "vector", numbers(ft->exact, 2)) &&
         add(exact, "length", cJSON_CreateNumber(ft->exact_length));
    double rows[2][2] = {{ft->covariance[0], ft->covariance[1]},
                         {ft->covariance[1], ft->covariance[2]}};
    for (int r = 0; r < 2 && ok; r++)
        ok = cJSON_AddItemToArray(cov, numbers(rows[r], 2));
    ok = ok && add(ellipse, "axes", numbers(ft->axes, 2)) &&
         add(ellipse, "angle_deg", cJSON_CreateNumber(ft->angle_deg + 0.0));
    if (!ok) {
        cJSON_Delete(linear);
        cJSON_Delete(exact);
        cJSON_Delete(ellipse);
        cJSON_Delete(cov);
        cJSON_Delete(o);
        return NULL;
    }
    cJSON_AddItemToObject(o, "linear", linear);
    cJSON_AddItemToObject(o, "exact", exact);
    cJSON_AddItemToObject(o, "covariance", cov);
    cJSON_AddItemToObject(o, "ellipse", ellipse);
    return o;
}

static cJSON *result_json(const wr_locating *m, const wr_locate_feature *features,
                          const char **names, size_t count)
{
    cJSON *r = cJSON_CreateObject();
    bool ok = r && add(r, "deterministic", cJSON_CreateBool(m->deterministic));
    if (ok && m->deterministic)
        ok = add(r, "free_motion", cJSON_CreateNull());
    else if (ok) {
        cJSON *motion = cJSON_CreateObject();
        ok = add(r, "free_motion", motion) && add(motion, "twist", numbers(m->twist, 3)) &&
             add(motion, "kind", cJSON_CreateString(m->rotation ? "rotation" : "translation")) &&
             add(motion, "about", m->rotation ? numbers(m->about, 2) : cJSON_CreateNull());
    }
    if (ok && !m->deterministic) {
        /* Nothing is determined: the rest is null. */
        ok = add(r, "sensitivity", cJSON_CreateNull()) && add(r, "condition", cJSON_CreateNull()) &&
             add(r, "pose_error", cJSON_CreateNull()) && add(r, "features", cJSON_CreateNull());
        return ok ? r : (cJSON_Delete(r), NULL);
    }
    cJSON *sensitivity = cJSON_CreateArray(), *pose = cJSON_CreateObject(),
          *list = cJSON_CreateArray();
    ok = ok && add(r, "sensitivity", sensitivity);
    for (int j = 0; j < 3 && ok; j++)
        ok = cJSON_AddItemToArray(sensitivity, numbers(m->sensitivity[j], m->fixel_count));
    ok = ok && add(r, "condition", cJSON_CreateNumber(m->condition)) &&
         add(r, "pose_error", pose) && add(pose, "linear", numbers(m->pose_linear, 3)) &&
         add(pose, "exact", numbers(m->pose_exact, 3)) && add(r, "features", list);
    for (size_t i = 0; i < count && ok; i++)
        ok = cJSON_AddItemToArray(list, feature_json(&features[i], names[i]));
    if (!ok) {
        if (!cJSON_GetObjectItem(r, "sensitivity"))
            cJSON_Delete(sensitivity);
        if (!cJSON_GetObjectItem(r, "pose_error"))
            cJSON_Delete(pose);
        if (!cJSON_GetObjectItem(r, "features"))
            cJSON_Delete(list);
        cJSON_Delete(r);
        return NULL;
    }
    return r;
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
cJSON *wp_handle_fixture_locating(wp_call *call)
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
        return NULL;
    if (present && !(sigma_ratio > 0)) {
        wp_error_set(error, WP_INVALID_PARAMS, "params.sigma_ratio",
                     "must be above 0 (sigma = tolerance / sigma_ratio), not %g", sigma_ratio);
        return NULL;
    }
    wr_locate_feature *features;
    const char **names;
    size_t count;
    cJSON *result = NULL;
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
        char field[WP_FIELD_MAX];
        wp_path_key(field, "params", why.field);
        wp_error_status(error, status, field, "%s", why.reason);
        goto done;
    }
    result = result_json(&m, features, names, count);
    if (!result)
        result = wp_out_of_memory(NULL, error);
done:
    free(features);
    free(names);
    return result;
}
