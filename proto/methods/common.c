/* common.c -- readers and writers that several families of methods share
 * (common.h). */
#include "common.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

const char *const wp_set_names[3] = {"goal", "strong", "both"};

void wp_write_edge_place(wp_writer *out, const wr_fixture *f, int edge)
{
    if (f->shape == WR_SHAPE_OUTLINE) {
        size_t loop, segment;
        wr_push_edge_place(f, edge, &loop, &segment);
        wp_write_member_number(out, "loop", (double)loop);
        wp_write_member_number(out, "segment", (double)segment);
    } else {
        wp_write_member_number(out, "edge", edge);
    }
}

void wp_write_perturbation(wp_writer *out, const wr_fixture *f, const wr_robust_answer *r)
{
    if (!r->has_perturbation)
        return;
    wp_write_key(out, "perturbation");
    wp_write_array(out);
    for (int i = 0; i < f->fixel_count; i++)
        wp_write_numbers(out, r->points[i], 2);
    wp_write_array_end(out);
    wp_write_key(out, "perturbation_normals");
    wp_write_array(out);
    for (int i = 0; i < f->fixel_count; i++)
        wp_write_numbers(out, r->normals[i], 2);
    wp_write_array_end(out);
}

bool wp_read_sets(const cJSON *params, wp_classify_request *r, wp_error *error)
{
    const cJSON *sets = cJSON_GetObjectItemCaseSensitive(params, "sets");
    if (!sets) {
        r->sets[0] = WR_SET_GOAL;
        r->sets[1] = WR_SET_STRONG;
        r->set_count = 2;
        return true;
    }
    if (!cJSON_IsArray(sets) || !sets->child) {
        wp_error_set(error, WP_INVALID_PARAMS, "params.sets",
                     "must be a non-empty array of \"goal\", \"strong\", \"both\"");
        return false;
    }
    size_t index = 0;
    for (const cJSON *item = sets->child; item; item = item->next, index++) {
        char field[WP_FIELD_MAX];
        wp_path_index(field, "params.sets", index);
        int set = -1;
        for (int s = 0; s < 3 && cJSON_IsString(item); s++)
            if (strcmp(item->valuestring, wp_set_names[s]) == 0)
                set = s;
        if (set < 0) {
            wp_error_set(error, WP_INVALID_PARAMS, field, "must be \"goal\", \"strong\" or \"both\"");
            return false;
        }
        for (int s = 0; s < r->set_count; s++)
            if (r->sets[s] == (wr_set)set) {
                wp_error_set(error, WP_INVALID_PARAMS, field, "\"%s\" is asked twice",
                             wp_set_names[set]);
                return false;
            }
        r->sets[r->set_count++] = (wr_set)set;
    }
    return true;
}

/* params.wrenches: each read into r->wrenches (or taken from `prepared`,
 * which may be NULL), no more than --max-wrenches of them. */
bool wp_read_wrenches(const wp_limits *limits, const cJSON *params,
                             const wr_fixture *fixture, wp_prepared *prepared,
                             wp_classify_request *r, wp_error *error)
{
    const cJSON *wrenches = cJSON_GetObjectItemCaseSensitive(params, "wrenches");
    if (!cJSON_IsArray(wrenches)) {
        wp_error_set(error, WP_INVALID_PARAMS, "params.wrenches",
                     "must be an array of wrenches, not %s", wp_type_name(wrenches));
        return false;
    }
    size_t count = prepared && prepared->wrenches ? prepared->count
                                                  : (size_t)cJSON_GetArraySize(wrenches);
    if (count > limits->max_wrenches) {
        wp_error_set(error, WP_LIMIT, "params.wrenches",
                     "%zu wrenches in one request, the limit is %zu (--max-wrenches)", count,
                     limits->max_wrenches);
        return false;
    }
    if (prepared && prepared->wrenches) {
        /* Read already, each three finite numbers: what wp_wrench_read
         * would have made of them. */
        r->wrenches = prepared->wrenches;
        prepared->wrenches = NULL;
        r->wrench_count = count;
        return true;
    }
    r->wrenches = malloc((count ? count : 1) * sizeof *r->wrenches);
    if (!r->wrenches) {
        wp_error_set(error, WP_INTERNAL, "", "out of memory");
        return false;
    }
    size_t i = 0;
    for (const cJSON *w = wrenches->child; w; w = w->next, i++) {
        char field[WP_FIELD_MAX];
        wp_path_index(field, "params.wrenches", i);
        if (!wp_wrench_read(w, field, fixture, r->wrenches[i], error))
            return false;
    }
    r->wrench_count = count;
    return true;
}

/* The call's fixture (held until the stream's free) and a zeroed state of
 * `size` bytes; NULL with the error set when either fails. */
void *wp_stream_with_fixture(wp_call *call, size_t size, wp_fixture_use **use)
{
    *use = wp_call_fixture(call);
    if (!*use)
        return NULL;
    void *stream = calloc(1, size);
    if (!stream)
        wp_error_set(call->error, WP_INTERNAL, "", "out of memory");
    return stream;
}


/* path.set: one of goal, strong, both (default goal). */
bool wp_read_set_at(const cJSON *object, const char *path, wr_set *set, wp_error *error)
{
    const char *name;
    if (!wp_member_string(object, path, "set", false, &name, error))
        return false;
    *set = WR_SET_GOAL;
    if (!name)
        return true;
    for (int s = 0; s < 3; s++)
        if (strcmp(name, wp_set_names[s]) == 0) {
            *set = (wr_set)s;
            return true;
        }
    char field[WP_FIELD_MAX];
    wp_path_key(field, path, "set");
    wp_error_set(error, WP_INVALID_PARAMS, field, "must be \"goal\", \"strong\" or \"both\"");
    return false;
}

/* path.finger_friction and path.finger_radius: not negative (default 0). */
bool wp_read_finger(const cJSON *object, const char *path, wr_finger *finger,
                        wp_error *error)
{
    *finger = (wr_finger){.friction = 0};
    if (!wp_member_number(object, path, "finger_friction", false, &finger->friction, NULL,
                          error) ||
        !wp_member_number(object, path, "finger_radius", false, &finger->radius, NULL, error))
        return false;
    char field[WP_FIELD_MAX];
    if (finger->friction < 0 || finger->radius < 0) {
        wp_path_key(field, path, finger->friction < 0 ? "finger_friction" : "finger_radius");
        wp_error_set(error, WP_INVALID_PARAMS, field, "must not be negative");
        return false;
    }
    return true;
}

bool wp_read_push_on(const cJSON *object, const char *path, const wr_fixture *shape, bool **mask,
                     size_t *count, wp_error *error)
{
    *mask = NULL;
    *count = 0;
    const cJSON *value = cJSON_GetObjectItemCaseSensitive(object, "push_on");
    if (!value)
        return true;
    char field[WP_FIELD_MAX];
    wp_path_key(field, path, "push_on");
    size_t loops = shape->shape == WR_SHAPE_OUTLINE && shape->outline ? shape->outline->loop_count : 1;
    if (cJSON_IsString(value) && strcmp(value->valuestring, "all") == 0)
        return true;
    bool *chosen = calloc(loops, sizeof *chosen);
    if (!chosen) {
        wp_error_set(error, WP_INTERNAL, "", "out of memory");
        return false;
    }
    if (cJSON_IsString(value) && strcmp(value->valuestring, "outer") == 0) {
        chosen[0] = true;
    } else if (cJSON_IsArray(value) && cJSON_GetArraySize(value) > 0) {
        size_t i = 0;
        const cJSON *item;
        cJSON_ArrayForEach(item, value)
        {
            char at[WP_FIELD_MAX];
            wp_path_index(at, field, i++);
            double loop = cJSON_IsNumber(item) ? item->valuedouble : NAN;
            if (!(loop >= 0) || loop != floor(loop) || loop >= (double)loops) {
                wp_error_set(error, WP_INVALID_PARAMS, at,
                             "must be a loop of the part's boundary, a whole number from 0 "
                             "(the outer boundary) to %zu", loops - 1);
                free(chosen);
                return false;
            }
            chosen[(size_t)loop] = true;
        }
    } else {
        wp_error_set(error, WP_INVALID_PARAMS, field,
                     "must be \"outer\", \"all\" or a non-empty list of loop numbers");
        free(chosen);
        return false;
    }
    *mask = chosen;
    *count = loops;
    return true;
}

double wp_now_s(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + t.tv_nsec * 1e-9;
}

bool wp_read_deadline(const cJSON *params, double *deadline, wp_error *error)
{
    double seconds = 0;
    bool present = false;
    *deadline = 0;
    if (!wp_member_number(params, "params", "deadline_s", false, &seconds, &present, error))
        return false;
    if (present && !(seconds > 0 && seconds <= 1e9)) {
        wp_error_set(error, WP_INVALID_PARAMS, "params.deadline_s",
                     "must be a number of seconds above 0 (at most 1e9), got %g", seconds);
        return false;
    }
    *deadline = present ? wp_now_s() + seconds : 0;
    return true;
}
