/* force.c -- force.range (docs/PROTOCOL.md): the maximal intervals of a
 * push's magnitude that do goal's, strong's or both's job under each load
 * case (wr_force_range), and their intersection over the cases;
 * push.force, the least push force along the outline; and push.regions'
 * force and cases, read for analysis.c. */
#include "common.h"
#include "loads.h"
#include "methods.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define SET_NAMES wp_set_names

/* push.force's samples of F* per segment: the default and the most. */
#define WP_FORCE_SAMPLES 64
#define WP_FORCE_MAX_SAMPLES 4096
static const char *const PUSH_FIELDS[] = {"at", "direction", NULL};

/* params.sets: names of sets, each once; all three when left out. */
static bool read_sets(const cJSON *params, bool sets[3], wp_error *error)
{
    const cJSON *list = cJSON_GetObjectItemCaseSensitive(params, "sets");
    sets[0] = sets[1] = sets[2] = list == NULL;
    if (!list)
        return true;
    if (!cJSON_IsArray(list) || cJSON_GetArraySize(list) == 0) {
        wp_error_set(error, WP_INVALID_PARAMS, "params.sets",
                     "must be a non-empty array of \"goal\", \"strong\", \"both\"");
        return false;
    }
    size_t i = 0;
    for (const cJSON *item = list->child; item; item = item->next, i++) {
        char field[WP_FIELD_MAX];
        wp_path_index(field, "params.sets", i);
        int s = 0;
        while (s < 3 && !(cJSON_IsString(item) && strcmp(item->valuestring, SET_NAMES[s]) == 0))
            s++;
        if (s == 3 || sets[s]) {
            wp_error_set(error, WP_INVALID_PARAMS, field,
                         s == 3 ? "must be \"goal\", \"strong\" or \"both\"" : "given twice");
            return false;
        }
        sets[s] = true;
    }
    return true;
}

/* The unit push, a physical wrench of the model system: params.push (a
 * unit force at a point, along the inward normal there or a direction) or
 * params.wrench (a direction of wrench, of unit length in the scaled metric
 * of docs/MODEL.md section 5). */
static bool read_push(const cJSON *params, const wr_fixture *f, double push[3], wp_error *error)
{
    const cJSON *at_push = cJSON_GetObjectItemCaseSensitive(params, "push");
    const cJSON *wrench = cJSON_GetObjectItemCaseSensitive(params, "wrench");
    if ((at_push != NULL) == (wrench != NULL)) {
        wp_error_set(error, WP_INVALID_PARAMS, at_push ? "params.wrench" : "params.push",
                     at_push ? "give \"push\" or \"wrench\", not both"
                             : "required: a push {\"at\", \"direction\"?} or a \"wrench\"");
        return false;
    }
    if (wrench) {
        double w[3], unit[3];
        if (!cJSON_IsArray(wrench) || cJSON_GetArraySize(wrench) != 3) {
            wp_error_set(error, WP_INVALID_PARAMS, "params.wrench",
                         "a wrench is [f_x, f_y, tau]: 3 numbers");
            return false;
        }
        const cJSON *item = wrench->child;
        for (int k = 0; k < 3; k++, item = item->next) {
            char field[WP_FIELD_MAX];
            wp_path_index(field, "params.wrench", (size_t)k);
            if (!wp_number(item, field, &w[k], error))
                return false;
        }
        /* Its direction is the same in the fixture's units and the model
         * system (forces and torques convert by one factor). */
        if (!(wr_fixture_unit_wrench(f, w, unit) > 0)) {
            wp_error_set(error, WP_INVALID_PARAMS, "params.wrench",
                         "must not be zero: it is the push's direction");
            return false;
        }
        wr_fixture_unscale_wrench(f, unit, push);
        return true;
    }
    double at[2], direction[2];
    bool directed = false;
    if (!wp_check_object(at_push, "params.push", PUSH_FIELDS, error) ||
        !wp_member_vector2(at_push, "params.push", "at", true, at, NULL, error) ||
        !wp_member_vector2(at_push, "params.push", "direction", false, direction, &directed,
                           error))
        return false;
    if (directed) {
        double length = hypot(direction[0], direction[1]);
        if (!(length > 0) || !isfinite(length)) {
            wp_error_set(error, WP_INVALID_PARAMS, "params.push.direction",
                         "must be a non-zero finite vector");
            return false;
        }
        if (!wp_point_near_part(f, at, "params.push.at", error))
            return false;
        direction[0] /= length;
        direction[1] /= length;
    } else {
        if (f->shape == WR_SHAPE_NONE) {
            wp_error_set(error, WP_INVALID_PARAMS, "params.push.direction",
                         "required: the fixture has no shape, so no inward normal");
            return false;
        }
        /* The inward normal there, by the rule a fixel's is found by: at
         * must be on the boundary, off its corners. */
        wr_fixel_spec fixel;
        memset(&fixel, 0, sizeof fixel);
        fixel.at[0] = at[0];
        fixel.at[1] = at[1];
        wr_friction_spec frictionless;
        memset(&frictionless, 0, sizeof frictionless);
        frictionless.given = true;
        wr_fixture placed;
        wr_error invalid;
        if (wr_fixture_place(f, &fixel, 1, &frictionless, &placed, &invalid) != WR_OK) {
            wp_error_set(error, WP_INVALID_PARAMS, "params.push.at",
                         "%s (or give \"direction\")", invalid.reason);
            return false;
        }
        direction[0] = placed.fixels[0].normal[0];
        direction[1] = placed.fixels[0].normal[1];
    }
    wr_fixture_force_wrench(f, direction, at, push);
    return true;
}

/* params.range [lo, hi] in the fixture's force unit, into the model
 * system; [0, inf) when left out. */
static bool read_range(const cJSON *params, const wr_fixture *f, double range[2],
                       wp_error *error)
{
    bool given = false;
    range[0] = 0;
    range[1] = INFINITY;
    if (!wp_member_vector2(params, "params", "range", false, range, &given, error))
        return false;
    if (!given) {
        range[1] = INFINITY;
        return true;
    }
    if (range[0] < 0) {
        wp_error_set(error, WP_INVALID_PARAMS, "params.range[0]",
                     "must not be negative (a push's magnitude), got %g", range[0]);
        return false;
    }
    if (range[1] < range[0]) {
        wp_error_set(error, WP_INVALID_PARAMS, "params.range",
                     "upside down: [%g, %g] (give [lo, hi] with lo <= hi)", range[0], range[1]);
        return false;
    }
    double factor = wr_fixture_force_factor(f);
    range[0] *= factor;
    range[1] *= factor;
    return true;
}

/* S = {"intervals": [[a, b], ...], "least": a0}, b null without an upper
 * end, least null without an interval; in the fixture's force unit. */
static void write_force_set(wp_writer *out, const wr_fixture *f, const wr_forces *good)
{
    wp_write_object(out);
    wp_write_key(out, "intervals");
    wp_write_array(out);
    for (int i = 0; i < good->count; i++) {
        wp_write_array(out);
        wp_write_number(out, wp_force_out(f, good->items[i].lo));
        if (isfinite(good->items[i].hi))
            wp_write_number(out, wp_force_out(f, good->items[i].hi));
        else
            wp_write_null(out);
        wp_write_array_end(out);
    }
    wp_write_array_end(out);
    wp_write_key(out, "least");
    if (good->count)
        wp_write_number(out, wp_force_out(f, good->items[0].lo));
    else
        wp_write_null(out);
    wp_write_object_end(out);
}

/* params.cases: from their text when the envelope cut it out of the line
 * (wp_method.raw_text), without a tree node per number; from the tree
 * otherwise, and when the text is not the common shape (the tree's reader
 * says what is wrong). */
static bool read_cases(wp_call *call, const wr_fixture *f, wp_cases *cases)
{
    int most = wp_case_limit(call->limits);
    const wp_prepared *text = call->prepared;
    if (!text)
        return wp_cases_read(cJSON_GetObjectItemCaseSensitive(call->params, "cases"),
                             "params.cases", f, most, cases, call->error);
    if (wp_cases_read_text(text->text, text->length, f, most, cases))
        return true;
    /* The tree of the text, in params in place of the [] left there, so
     * that it lives as long as the names borrowed from it. */
    cJSON *tree = cJSON_ParseWithLength(text->text, text->length);
    if (!tree || !cJSON_ReplaceItemInObjectCaseSensitive(call->params, "cases", tree)) {
        cJSON_Delete(tree);
        wp_error_set(call->error, WP_INTERNAL, "", "out of memory");
        return false;
    }
    return wp_cases_read(tree, "params.cases", f, most, cases, call->error);
}

/* Boxes per excluded cone for one piece of a robust interval: a piece
 * that so few do not prove is split instead (wr_robust_forces). */
#define ROBUST_FORCE_BUDGET 64

/* One case's good magnitudes for the sets asked: by the cones, or for a
 * part on supports by the discs of wr_support.h (G_goal's; the others are
 * refused before, by supports_sets). */
static wr_status set_ranges(const wp_call *call, const wr_analysis *a, const bool sets[3],
                            const double load[3], const double push[3], double lo, double hi,
                            wr_forces good[3])
{
    const wr_supports *supports = wr_analysis_fixture(a)->supports;
    if (!supports)
        return wr_force_ranges(a, sets, load, push, lo, hi, good);
    wr_lp_env *env = call->host->lp_env ? call->host->lp_env(call->host->self) : NULL;
    if (!env)
        return WR_LP_FAILED;
    return wr_supports_force_range(a, supports, env, load, push, lo, hi, &good[WR_SET_GOAL]);
}
/* On supports force.range answers G_goal's magnitudes: false, with the
 * error at params.sets, when strong or both is asked. */
static bool supports_sets(wp_call *call, const wr_fixture *f, const bool sets[3])
{
    if (!f->supports || (!sets[WR_SET_STRONG] && !sets[WR_SET_BOTH]))
        return true;
    wp_error_set(call->error, WP_INVALID_PARAMS, "params.sets",
                 "the fixture rests on supports: force.range gives the magnitudes that seat it "
                 "(\"goal\"); whether the seated part is held under a load is wrench.classify's "
                 "\"strong\" with that load");
    return false;
}

bool wp_handle_force_range(wp_call *call, wp_writer *out)
{
    const cJSON *params = call->params;
    wp_error *error = call->error;
    bool sets[3];
    if (!read_sets(params, sets, error))
        return false;
    wp_fixture_use *use = wp_call_fixture(call);
    if (!use)
        return false;
    const wr_fixture *f = use->fixture;
    double push[3], range[2];
    wp_cases cases;
    if (!supports_sets(call, f, sets) || !read_push(params, f, push, error) ||
        !read_range(params, f, range, error) || !read_cases(call, f, &cases))
        return false;
    wp_write_object(out);
    wp_write_key(out, "cases");
    wp_write_array(out);
    wr_forces every[3] = {{0}}, good[3] = {{0}}, meet = {0};
    /* A fixture with a tolerance: each good interval's robust part. */
    wr_robust *robust = NULL;
    wr_status status = f->tolerance.given ? wr_robust_new(use->analysis, ROBUST_FORCE_BUDGET,
                                                          &robust)
                                          : WR_OK;
    for (int c = 0; status == WR_OK && c < cases.count; c++) {
        wp_write_object(out);
        wp_write_key(out, "name");
        if (cases.items[c].name)
            wp_write_string(out, cases.items[c].name);
        else
            wp_write_null(out);
        status = set_ranges(call, use->analysis, sets, cases.items[c].load, push, range[0],
                            range[1], good);
        for (int s = 0; status == WR_OK && s < 3; s++) {
            if (!sets[s])
                continue;
            if (robust) {
                wr_forces nominal = good[s];
                good[s] = (wr_forces){0};
                status = wr_robust_forces(robust, (wr_set)s, cases.items[c].load, push,
                                          &nominal, call->host->stop, &good[s]);
                wr_forces_release(&nominal);
                if (status != WR_OK)
                    break;
            }
            wp_write_key(out, SET_NAMES[s]);
            write_force_set(out, f, &good[s]);
            /* One magnitude for every case: the intersection. */
            if (c == 0) {
                wr_forces swap = every[s];
                every[s] = good[s];
                good[s] = swap;
            } else {
                status = wr_forces_intersect(&every[s], &good[s], &meet);
                wr_forces swap = every[s];
                every[s] = meet;
                meet = swap;
            }
        }
        if (status == WR_OK)
            wp_write_object_end(out);
    }
    if (status == WR_OK) {
        wp_write_array_end(out);
        wp_write_key(out, "all");
        wp_write_object(out);
        for (int s = 0; s < 3; s++)
            if (sets[s]) {
                wp_write_key(out, SET_NAMES[s]);
                write_force_set(out, f, &every[s]);
            }
        wp_write_object_end(out);
        wp_write_object_end(out);
    }
    for (int s = 0; s < 3; s++) {
        wr_forces_release(&every[s]);
        wr_forces_release(&good[s]);
    }
    wr_forces_release(&meet);
    wr_robust_free(robust);
    wp_cases_release(&cases);
    if (status != WR_OK) {
        /* The inputs were checked: what is left is a push too large for
         * doubles, or memory.  (What was written is taken back.) */
        wp_error_status(error, status, status == WR_INVALID ? "params" : "", "%s",
                        status == WR_INVALID ? "the push or a load is too large to compute with"
                                             : wr_strerror(status));
        return false;
    }
    return true;
}

bool wp_push_load_read(const cJSON *params, const wr_fixture *f, double finger_friction,
                       int most_cases, wp_push_load *out, wp_error *error)
{
    return wp_push_load_read_at(params, "params", f, finger_friction, most_cases, out, error);
}

bool wp_push_load_read_at(const cJSON *params, const char *path, const wr_fixture *f,
                          double finger_friction, int most_cases, wp_push_load *out,
                          wp_error *error)
{
    memset(out, 0, sizeof *out);
    char field_force[WP_FIELD_MAX], field_cases[WP_FIELD_MAX];
    wp_path_key(field_force, path, "force");
    wp_path_key(field_cases, path, "cases");
    const cJSON *cases_json = cJSON_GetObjectItemCaseSensitive(params, "cases");
    double force;
    if (!wp_member_number(params, path, "force", false, &force, &out->given, error))
        return false;
    if (!out->given) {
        if (cases_json) {
            wp_error_set(error, WP_INVALID_PARAMS, field_force,
                         "required with \"cases\": the push's magnitude");
            return false;
        }
        return true;
    }
    if (!(force > 0)) {
        wp_error_set(error, WP_INVALID_PARAMS, field_force,
                     "must be positive (a push's magnitude), got %g", force);
        return false;
    }
    if (finger_friction > 0) {
        char field[WP_FIELD_MAX];
        wp_path_key(field, path, "finger_friction");
        wp_error_set(error, WP_INVALID_PARAMS, field,
                     "not with \"force\": regions under a force are exact, for a frictionless "
                     "finger");
        return false;
    }
    out->force = force * wr_fixture_force_factor(f);
    if (!isfinite(out->force)) {
        wp_error_set(error, WP_INVALID_PARAMS, field_force, "too large to compute with");
        return false;
    }
    wp_cases cases = {0};
    if (cases_json && !wp_cases_read(cases_json, field_cases, f, most_cases, &cases, error))
        return false;
    out->count = cases_json ? cases.count : 1;
    out->loads = calloc((size_t)out->count, sizeof *out->loads);
    if (!out->loads) {
        wp_cases_release(&cases);
        wp_error_set(error, WP_INTERNAL, "", "out of memory");
        return false;
    }
    for (int c = 0; c < cases.count; c++)
        memcpy(out->loads[c], cases.items[c].load, sizeof out->loads[c]);
    wp_cases_release(&cases);
    return true;
}

void wp_push_load_release(wp_push_load *load)
{
    free(load->loads);
    memset(load, 0, sizeof *load);
}

/* params.set: one name (default "both": what a user pushes with). */
static bool read_one_set(const cJSON *params, wr_set *set, wp_error *error)
{
    const char *name = NULL;
    if (!wp_member_string(params, "params", "set", false, &name, error))
        return false;
    *set = WR_SET_BOTH;
    if (!name)
        return true;
    for (int s = 0; s < 3; s++)
        if (strcmp(name, SET_NAMES[s]) == 0) {
            *set = (wr_set)s;
            return true;
        }
    wp_error_set(error, WP_INVALID_PARAMS, "params.set", "must be \"goal\", \"strong\" or \"both\"");
    return false;
}

static void write_force_or_null(wp_writer *out, const wr_fixture *f, double force)
{
    if (isfinite(force))
        wp_write_number(out, wp_force_out(f, force));
    else
        wp_write_null(out);
}

/* On supports (wr_support.h) push.force finds the least push that seats
 * the part (set "goal") along a polygon's straight edges, for a point
 * finger: false with the error set otherwise. */
static bool supports_least_ok(wp_call *call, const wr_fixture *f, wr_set set, double radius)
{
    if (!f->supports)
        return true;
    const char *why = wp_supports_push_unanswered(f, set, radius);
    if (!why)
        return true;
    wp_error_set(call->error, WP_INVALID_PARAMS, why,
                 "the fixture rests on supports: push.force finds the least push that seats it "
                 "(set \"goal\"), along a polygon's straight edges, for a point finger; whether "
                 "the seated part is held is wrench.classify's \"strong\" with that push");
    return false;
}

/* F* at one point of the outline: the floating part's, or on supports
 * the least from outside (a push just above it seats). */
static wr_status least_at(const wp_call *call, const wr_analysis *a, wr_set set,
                          const double (*loads)[3], int case_count, const double push[3],
                          double *force)
{
    const wr_supports *supports = wr_analysis_fixture(a)->supports;
    if (!supports)
        return wr_least_force_at(a, set, loads, case_count, push, force);
    wr_lp_env *env = call->host->lp_env ? call->host->lp_env(call->host->self) : NULL;
    double lower;
    return env ? wr_supports_least_force(a, supports, env, loads, case_count, push, force, &lower)
               : WR_LP_FAILED;
}

/* A stop that the caller's stop or a deadline asks for. */
typedef struct deadline_stop {
    const wr_stop *caller;
    double deadline; /* wp_now_s's second; 0: none */
} deadline_stop;

static bool deadline_or_caller(void *context)
{
    const deadline_stop *d = context;
    return wr_stop_requested(d->caller) || (d->deadline > 0 && wp_now_s() >= d->deadline);
}

/* F* at `samples` evenly spaced points of edge e (off its ends) into
 * values (INFINITY where no push is made: a loop push_on leaves out, where
 * the finger does not fit), exact (least_at: on supports too), or with
 * `robust` robust (wr_robust_least_force_at).  *made: the samples made;
 * past the deadline fewer, and *partial set.  WR_OK; WR_STOPPED (the
 * call's stop); WR_NO_MEMORY; WR_INVALID; WR_LP_FAILED. */
static wr_status sample_edge(const wp_call *call, const wr_analysis *a, const wr_robust *robust,
                             wr_set set, const double (*loads)[3], int case_count,
                             const wr_finger *finger, int e, int samples, double deadline,
                             const wr_stop *stop, double *values, int *made, bool *partial)
{
    const wr_stop *caller = call->host->stop;
    const wr_fixture *f = wr_analysis_fixture(a);
    double top = f->shape == WR_SHAPE_CIRCLE ? 360 : 1;
    bool pushed = wr_finger_pushes_on(f, finger, e);
    wr_span *blocked = NULL;
    int blocked_count = 0;
    wr_status status = WR_OK;
    *made = 0;
    if (pushed && finger->radius > 0 && f->shape != WR_SHAPE_CIRCLE) {
        size_t loop, piece;
        wr_push_edge_place(f, e, &loop, &piece);
        status = wr_finger_blocked(f->outline, loop, piece, finger->radius, caller, &blocked,
                                   &blocked_count);
    }
    for (int j = 0; status == WR_OK && j < samples; j++) {
        if (deadline > 0 && wp_now_s() >= deadline) {
            *partial = true;
            break;
        }
        double t = top * (j + 0.5) / samples, push[3];
        bool reached = pushed;
        for (int b = 0; reached && b < blocked_count; b++)
            reached = !(t >= blocked[b].lo && t <= blocked[b].hi);
        wr_push_wrench(f, e, t, push);
        values[j] = INFINITY;
        if (reached && robust)
            status = wr_robust_least_force_at(robust, set, loads, case_count, push, stop,
                                              &values[j]);
        else if (reached)
            status = least_at(call, a, set, loads, case_count, push, &values[j]);
        if (status == WR_STOPPED && !wr_stop_requested(caller)) {
            status = WR_OK; /* the deadline, inside a robust sample */
            *partial = true;
            break;
        }
        if (status == WR_OK)
            (*made)++;
    }
    free(blocked);
    if (wr_stop_requested(caller))
        status = WR_STOPPED;
    return status;
}

bool wp_handle_push_force(wp_call *call, wp_writer *out)
{
    const cJSON *params = call->params;
    wp_error *error = call->error;
    wr_set set;
    double radius = 0, samples_given = WP_FORCE_SAMPLES;
    bool have_samples = false;
    if (!read_one_set(params, &set, error) ||
        !wp_member_number(params, "params", "finger_radius", false, &radius, NULL, error) ||
        !wp_member_number(params, "params", "samples", false, &samples_given, &have_samples,
                          error))
        return false;
    if (radius < 0) {
        wp_error_set(error, WP_INVALID_PARAMS, "params.finger_radius", "must not be negative");
        return false;
    }
    if (have_samples && !(samples_given >= 1 && samples_given <= WP_FORCE_MAX_SAMPLES &&
                          samples_given == floor(samples_given))) {
        wp_error_set(error, WP_INVALID_PARAMS, "params.samples",
                     "must be a whole number from 1 to %d", WP_FORCE_MAX_SAMPLES);
        return false;
    }
    int samples = (int)samples_given;
    double deadline;
    if (!wp_read_deadline(params, &deadline, error))
        return false;
    wp_fixture_use *use = wp_call_fixture(call);
    if (!use)
        return false;
    const wr_fixture *f = use->fixture;
    if (!supports_least_ok(call, f, set, radius))
        return false;
    if (f->shape == WR_SHAPE_NONE) {
        wp_error_set(error, WP_INVALID_PARAMS, "params.fixture.body.shape",
                     "a push force needs the part's outline: the fixture has no shape");
        return false;
    }
    bool *push_on;
    wr_finger finger = {.radius = radius};
    if (!wp_read_push_on(params, "params", f, &push_on, &finger.push_on_count, error))
        return false;
    finger.push_on = push_on;
    wp_cases cases;
    if (!wp_cases_read(cJSON_GetObjectItemCaseSensitive(params, "cases"), "params.cases", f,
                       wp_case_limit(call->limits), &cases, error)) {
        free(push_on);
        return false;
    }
    double (*loads)[3] = malloc((size_t)cases.count * sizeof *loads);
    double *values = malloc((size_t)samples * sizeof *values);
    wr_status status = loads && values ? WR_OK : WR_NO_MEMORY;
    /* A fixture with a tolerance: every F* robust (wr_robust_least_force_at),
     * the least's point the nominal search's. */
    wr_robust *robust = NULL;
    if (status == WR_OK && f->tolerance.given)
        status = wr_robust_new(use->analysis, ROBUST_FORCE_BUDGET, &robust);
    for (int c = 0; loads && c < cases.count; c++)
        memcpy(loads[c], cases.items[c].load, sizeof loads[c]);
    /* Past params.deadline_s the search for the least stops: "least" is
     * then null, no segment is sampled, and the answer is "partial". */
    deadline_stop by = {call->host->stop, deadline};
    const wr_stop stop = {deadline_or_caller, &by};
    wr_least_force least = {0};
    bool partial = false;
    wr_lp_env *env = call->host->lp_env ? call->host->lp_env(call->host->self) : NULL;
    if (status == WR_OK)
        status = f->supports
                     ? (env ? wr_supports_least_force_find(use->analysis, f->supports, env,
                                                           (const double (*)[3])loads, cases.count,
                                                           &finger, &stop, &least)
                            : WR_LP_FAILED)
                     : wr_least_force_find(use->analysis, set, (const double (*)[3])loads,
                                           cases.count, &finger, &stop, &least);
    /* With a tolerance the samples come first (grid, made[e] per edge),
     * and the least is the least robust F* of the samples and of the
     * nominal search's point. */
    int edges = wr_push_edge_count(f);
    double top = f->shape == WR_SHAPE_CIRCLE ? 360 : 1;
    double *grid = NULL;
    int *made_on = NULL;
    if (status == WR_OK && robust) {
        grid = malloc(sizeof *grid * (size_t)edges * (size_t)samples);
        made_on = calloc((size_t)edges, sizeof *made_on);
        status = grid && made_on ? WR_OK : WR_NO_MEMORY;
    }
    int robust_edges = 0; /* edges sampled (the last one cut short by a deadline) */
    for (int e = 0; status == WR_OK && robust && !partial && e < edges; e++, robust_edges++)
        status = sample_edge(call, use->analysis, robust, set, loads, cases.count, &finger, e,
                             samples, deadline, &stop, grid + (size_t)e * samples, &made_on[e],
                             &partial);
    if (status == WR_OK && robust && least.found) {
        /* No fixture of the set needs less than the nominal one, so the
         * nominal lower bound stays one. */
        double push[3];
        wr_push_wrench(f, least.edge, least.t, push);
        status = wr_robust_least_force_at(robust, set, (const double (*)[3])loads, cases.count,
                                          push, &stop, &least.force);
        if (status == WR_STOPPED && !wr_stop_requested(call->host->stop)) {
            status = WR_OK;
            partial = true;
            least.force = INFINITY;
        }
        for (int e = 0; status == WR_OK && e < edges; e++)
            for (int j = 0; j < made_on[e]; j++)
                if (grid[(size_t)e * samples + j] < least.force) {
                    least.force = grid[(size_t)e * samples + j];
                    least.edge = e;
                    least.t = top * (j + 0.5) / samples;
                    wr_boundary_point(f, e, least.t, least.at, least.direction);
                }
        least.found = isfinite(least.force);
        least.converged = least.force <= least.lower * (1 + 1e-9);
    }
    if (status == WR_STOPPED && !wr_stop_requested(call->host->stop)) {
        status = WR_OK;
        partial = true;
        least.found = false;
    }
    if (status == WR_OK) {
        wp_write_object(out);
        wp_write_key(out, "least");
        if (least.found) {
            wp_write_object(out);
            wp_write_edge_place(out, f, least.edge);
            wp_write_member_number(out, "t", least.t + 0.0);
            const double at[2] = {least.at[0] + 0.0, least.at[1] + 0.0};
            const double direction[2] = {least.direction[0] + 0.0, least.direction[1] + 0.0};
            wp_write_key(out, "at");
            wp_write_numbers(out, at, 2);
            wp_write_key(out, "direction");
            wp_write_numbers(out, direction, 2);
            wp_write_key(out, "force");
            write_force_or_null(out, f, least.force);
            wp_write_key(out, "lower_bound");
            write_force_or_null(out, f, least.lower);
            wp_write_member_bool(out, "converged", least.converged);
            wp_write_object_end(out);
        } else {
            wp_write_null(out);
        }
        wp_write_member_number(out, "evaluations", (double)least.evaluations);
        wp_write_member_number(out, "samples", samples);
        /* F* at evenly spaced points of every edge (off its ends), each
         * exact. */
        wp_write_key(out, "segments");
        wp_write_array(out);
    }
    /* Past params.deadline_s, only the samples made so far (the last
     * edge's cut short, none after a search that stopped), and "partial". */
    for (int e = 0; status == WR_OK && (robust ? e < robust_edges : !partial && e < edges);
         e++) {
        int made = 0;
        if (robust) {
            made = made_on[e];
            memcpy(values, grid + (size_t)e * samples, sizeof *values * (size_t)made);
        } else {
            status = sample_edge(call, use->analysis, NULL, set, loads, cases.count, &finger, e,
                                 samples, deadline, &stop, values, &made, &partial);
        }
        if (status != WR_OK)
            break;
        wp_write_object(out);
        wp_write_edge_place(out, f, e);
        wp_write_key(out, "t");
        wp_write_array(out);
        for (int j = 0; j < made; j++)
            wp_write_number(out, top * (j + 0.5) / samples);
        wp_write_array_end(out);
        wp_write_key(out, "force");
        wp_write_array(out);
        for (int j = 0; j < made; j++)
            write_force_or_null(out, f, values[j]);
        wp_write_array_end(out);
        wp_write_object_end(out);
    }
    free(loads);
    free(push_on);
    free(values);
    wr_robust_free(robust);
    free(grid);
    free(made_on);
    wp_cases_release(&cases);
    if (status != WR_OK) {
        wp_error_status(error, status, "", "%s", wr_strerror(status));
        return false;
    }
    wp_write_array_end(out);
    if (partial)
        wp_write_member_bool(out, "partial", true);
    wp_write_object_end(out);
    return true;
}
