/* sweep.c -- friction.sweep: wrenches, push regions or gravity arcs
 * against a common coefficient of friction, a job's budget at a time. */
#include "common.h"
#include "loads.h"
#include "methods.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* friction.sweep, a job's budget at a time (wr_sweep.h). */
enum { SWEEP_WRENCHES, SWEEP_PUSH, SWEEP_GRAVITY, SWEEP_FORCE };

/* The least push force against mu, F*(mu), is the minimum over the outline
 * of the lower end of a union of intervals whose cones' faces move with mu
 * (their normals quadratic in mu, wr_sweep.h): its breakpoints are where
 * the minimising point jumps from one place of the outline to another as
 * well as where a face changes, and no closed form in mu is kept.  So it
 * is sampled, each sample exact at its mu (wr_least_force_find on the
 * fixture placed again with that friction, to WR_FORCE_TOLERANCE), at
 * FORCE_SAMPLES coefficients evenly over the range and at every end of the
 * exact intervals of mu where the push alone has a region (wr_sweep_push,
 * a frictionless finger): there a large enough push overcomes any load, so
 * F* is finite on them whatever the cases, and their ends are where it may
 * jump to null. */
#define FORCE_SAMPLES 128
/* Over a tolerance each sample is push.force's robust least at its mu
 * (wr_robust_least_force_at_mu: the nominal least's point and
 * ROBUST_FORCE_EDGE_SAMPLES points of each edge, each a robust F*), at
 * ROBUST_FORCE_SAMPLES coefficients evenly and the ends of the robust push
 * sweep's intervals (where a large enough push is proved to do the set's
 * job on every fixture of the set). */
#define ROBUST_FORCE_SAMPLES 17
#define ROBUST_FORCE_EDGE_SAMPLES 4
/* The work units (a wrench against a cone) charged per case for one robust
 * F* evaluation: a hundred times a nominal one's 40 (force_sample), since
 * it bisects the magnitudes with boxes of the tolerance's set. */
#define ROBUST_EVALUATION_COST 4000
typedef struct sweep_state {
    int what;                   /* SWEEP_* */
    wr_sweep_range range;
    wp_classify_request request;   /* the sets (one for push and gravity), the wrenches */
    wr_finger finger;
    bool *push_on;              /* finger.push_on, owned (force) */
    wr_sweeper *sweepers[3];    /* one per set */
    wr_sweep_job *job;          /* the current one */
    size_t next;                /* wrenches: the next to answer, */
    int set;                    /* and its next set */
    bool opened;                /* "{"results":[" written */
    /* force: the cases' loads (model system), the next sample of mu, and
     * the fixture's fixels as specs, to place them again at each mu */
    wp_cases cases;
    double (*loads)[3];
    double *mus;                /* the coefficients sampled, increasing */
    int mu_count;
    double (*at)[2];            /* the least force's point at each; NAN: none */
    int sample;
    wr_fixel_spec fixels[WR_MAX_FIXELS];
    /* params.deadline_s: the monotonic second after which the sweep stops
     * where it has got to (0: none; sweep_step). */
    double deadline;
    /* params.over "supports": the supports' mu_B swept (wrenches, goal;
     * sweep_supports_step) instead of the fixels' mu */
    bool over_supports;
    /* Over mu_B with holding asked: the wrenches' sets by wr_support_sweep
     * jobs (sweep_fixels_step) rather than seating's limit alone. */
    bool supports_jobs;
    /* A fixture on supports swept over its fixels' mu (wrenches: a
     * wr_support_sweep job per wrench and set, sweep_fixels_step; force:
     * the least push on the plate at each mu, sweep_supports_force_step) */
    bool fixels_on_supports;
    wr_support_sweep *fixels_job;
    /* push and gravity over the fixels' mu (plate_piece): the fixture at
     * fixels_mu and its analysis, made again when mu changes */
    wr_fixture fixels_at;
    wr_analysis *fixels_analysis;
    double fixels_mu;
    /* Over the supports, "push" or "gravity" (sweep_plate_step): the push's
     * force and cases or the pull, and the curve made so far -- the grid's
     * points (PLATE_GRID steps), then the critical mu_B bisected in
     * [lo, hi] (lo's region non-empty, of length lo_length; hi's empty).
     * At the mu under way: the next edge and the length of the edges so far. */
    wp_push_load push_load;
    double pull;
    double (*points)[2];        /* [mu, length], PLATE_GRID + 1 of them */
    int point_count;
    bool bisecting;
    double lo, hi, lo_length;
    int edge;
    double length;
    bool nonempty;
    /* A fixture with a tolerance, "push", "gravity" or "force": the
     * nominal job's intervals made robust (sweep_robust_run), and the mu
     * below which its answer is decided (the range's top when done). */
    wr_robust_sweep *robust;
    double robust_top;
    /* "force" over a tolerance: the robust push sweep's answer (its
     * intervals given, their ends sampled). */
    wr_sweep_curve robust_curve;
} sweep_state;

static const char *const SWEEP_PUSH_FIELDS[] = {"set", "finger_friction", "finger_radius", NULL};
static const char *const SWEEP_GRAVITY_FIELDS[] = {"set", NULL};
static const char *const SWEEP_FORCE_FIELDS[] = {"set", "finger_radius", "push_on", NULL};
/* On supports the push takes push.regions' members there, the tilt its pull. */
static const char *const PLATE_PUSH_FIELDS[] = {"set", "force", "cases", "push_on",
                                                "finger_friction", "finger_radius", NULL};
static const char *const PLATE_GRAVITY_FIELDS[] = {"set", "in_plane_g", NULL};

/* params.range: [low, high], 0 <= low < high <= WR_MAX_FRICTION (default
 * [0, 2]); params.kinetic_ratio in (0, 1] (default 1). */
static bool read_sweep_range(const cJSON *params, wr_sweep_range *range, wp_error *error)
{
    *range = (wr_sweep_range){0, 2, 1};
    const cJSON *value = cJSON_GetObjectItemCaseSensitive(params, "range");
    if (value) {
        if (!cJSON_IsArray(value) || cJSON_GetArraySize(value) != 2) {
            wp_error_set(error, WP_INVALID_PARAMS, "params.range",
                         "must be [low, high]: two coefficients of friction");
            return false;
        }
        double ends[2];
        for (int i = 0; i < 2; i++) {
            char field[WP_FIELD_MAX];
            wp_path_index(field, "params.range", (size_t)i);
            const cJSON *end = cJSON_GetArrayItem(value, i);
            if (!cJSON_IsNumber(end) || !isfinite(end->valuedouble)) {
                wp_error_set(error, WP_INVALID_PARAMS, field, "must be a number, not %s",
                             wp_type_name(end));
                return false;
            }
            ends[i] = end->valuedouble;
        }
        if (ends[0] < 0) {
            wp_error_set(error, WP_INVALID_PARAMS, "params.range[0]",
                         "a coefficient of friction is not negative");
            return false;
        }
        if (ends[1] > WR_MAX_FRICTION) {
            wp_error_set(error, WP_INVALID_PARAMS, "params.range[1]",
                         "at most %g: no contact has more friction", WR_MAX_FRICTION);
            return false;
        }
        if (!(ends[0] < ends[1])) {
            wp_error_set(error, WP_INVALID_PARAMS, "params.range",
                         "the low end must be below the high end");
            return false;
        }
        range->low = ends[0] + 0.0;
        range->high = ends[1];
    }
    bool given;
    if (!wp_member_number(params, "params", "kinetic_ratio", false, &range->kinetic_ratio, &given,
                          error))
        return false;
    if (!(range->kinetic_ratio > 0 && range->kinetic_ratio <= 1)) {
        wp_error_set(error, WP_INVALID_PARAMS, "params.kinetic_ratio",
                     "must be in (0, 1]: kinetic friction is positive and not above static");
        return false;
    }
    return true;
}

/* The intervals of `list` up to `top` (INFINITY: all): a partial answer
 * says nothing above its stopped_at, so an interval reaching past it is cut
 * there and one starting at or past it is left out (docs/PROTOCOL.md,
 * deadline_s; as the push sweep's own cut). */
static void write_intervals_below(wp_writer *out, const wr_intervals *list, double top)
{
    wp_write_array(out);
    for (int i = 0; i < list->count && list->items[i][0] < top; i++) {
        const double pair[2] = {list->items[i][0] + 0.0, fmin(list->items[i][1], top) + 0.0};
        wp_write_numbers(out, pair, 2);
    }
    wp_write_array_end(out);
}

static void write_intervals(wp_writer *out, const wr_intervals *list)
{
    write_intervals_below(out, list, INFINITY);
}

static void write_stopped(wp_writer *out, double reached);
static wp_step sweep_robust_run(sweep_state *state, wp_call *call, unsigned long budget,
                                unsigned long *used, bool stopped);

/* {"intervals", "critical", "curve", "exact", "resolution"}, and when the
 * deadline stopped it, "partial" and "stopped_at": `reached`. */
static void write_curve(wp_writer *out, const wr_sweep_curve *curve, bool stopped, double reached)
{
    wp_write_object(out);
    wp_write_key(out, "intervals");
    write_intervals(out, &curve->intervals);
    wp_write_key(out, "critical");
    if (curve->has_critical)
        wp_write_number(out, curve->critical + 0.0);
    else
        wp_write_null(out);
    wp_write_key(out, "curve");
    wp_write_array(out);
    for (int i = 0; i < curve->point_count; i++) {
        const double point[2] = {curve->points[i][0] + 0.0, curve->points[i][1] + 0.0};
        wp_write_numbers(out, point, 2);
    }
    wp_write_array_end(out);
    wp_write_member_bool(out, "exact", curve->exact);
    wp_write_member_number(out, "resolution", curve->resolution);
    if (stopped)
        write_stopped(out, reached);
    wp_write_object_end(out);
}

/* The sweep's reading of params: which question, the range, and the
 * wrenches and sets or the set and finger. */
static bool read_sweep(wp_call *call, const wr_fixture *fixture, sweep_state *state)
{
    const cJSON *params = call->params;
    wp_error *error = call->error;
    const char *names[4] = {"wrenches", "push", "gravity", "force"};
    int given = 0;
    for (int i = 0; i < 4; i++)
        if (cJSON_GetObjectItemCaseSensitive(params, names[i])) {
            given++;
            state->what = i;
        }
    if (given != 1) {
        wp_error_set(error, WP_INVALID_PARAMS, "params",
                     "give exactly one of \"wrenches\", \"push\", \"gravity\" and \"force\" "
                     "(%d given)",
                     given);
        return false;
    }
    const cJSON *cases = cJSON_GetObjectItemCaseSensitive(params, "cases");
    if ((cases != NULL) != (state->what == SWEEP_FORCE)) {
        wp_error_set(error, WP_INVALID_PARAMS, cases ? "params.cases" : "params.cases",
                     cases ? "only with \"force\": the loads a push works against (a push "
                             "on the plate takes its cases inside \"push\")"
                           : "required with \"force\": the loads a push works against");
        return false;
    }
    if (state->what != SWEEP_WRENCHES && cJSON_GetObjectItemCaseSensitive(params, "sets")) {
        wp_error_set(error, WP_INVALID_PARAMS, "params.sets",
                     "only with \"wrenches\": a push or gravity sweep takes its \"set\"");
        return false;
    }
    if (!read_sweep_range(params, &state->range, error) ||
        !wp_read_deadline(params, &state->deadline, error))
        return false;
    if (state->what == SWEEP_WRENCHES) {
        wp_classify_request *r = &state->request;
        if (!wp_read_sets(params, r, error))
            return false;
        return wp_read_wrenches(call->limits, params, fixture, NULL, r, error);
    }
    if (state->what == SWEEP_FORCE) {
        /* {"set"? (default both), "finger_radius"?, "push_on"?} and the cases. */
        const cJSON *what = cJSON_GetObjectItemCaseSensitive(params, "force");
        state->request.set_count = 1;
        if (!wp_check_object(what, "params.force", SWEEP_FORCE_FIELDS, error) ||
            !wp_read_set_at(what, "params.force", &state->request.sets[0], error) ||
            !wp_read_finger(what, "params.force", &state->finger, error) ||
            !wp_read_push_on(what, "params.force", fixture, &state->push_on,
                             &state->finger.push_on_count, error) ||
            !wp_cases_read(cases, "params.cases", fixture, wp_case_limit(call->limits),
                           &state->cases, error))
            return false;
        state->finger.push_on = state->push_on;
        if (!cJSON_GetObjectItemCaseSensitive(what, "set"))
            state->request.sets[0] = WR_SET_BOTH;
        if (fixture->shape == WR_SHAPE_NONE) {
            wp_error_set(error, WP_INVALID_PARAMS, "params.fixture.body.shape",
                         "a push force needs the part's outline: the fixture has no shape");
            return false;
        }
        state->loads = malloc((size_t)state->cases.count * sizeof *state->loads);
        if (!state->loads) {
            wp_error_set(error, WP_INTERNAL, "", "out of memory");
            return false;
        }
        for (int c = 0; c < state->cases.count; c++)
            memcpy(state->loads[c], state->cases.items[c].load, sizeof state->loads[c]);
        /* The fixels as they are, to be placed again with each mu. */
        for (int i = 0; i < fixture->fixel_count; i++) {
            const wr_fixel *x = &fixture->fixels[i];
            state->fixels[i] = (wr_fixel_spec){.at = {x->at[0], x->at[1]}, .normal_given = true,
                                               .normal = {x->normal[0], x->normal[1]}};
        }
        return true;
    }
    bool push = state->what == SWEEP_PUSH;
    const char *path = push ? "params.push" : "params.gravity";
    const cJSON *what = cJSON_GetObjectItemCaseSensitive(params, push ? "push" : "gravity");
    state->request.set_count = 1;
    const char *const *fields = state->over_supports || state->fixels_on_supports
                                    ? (push ? PLATE_PUSH_FIELDS : PLATE_GRAVITY_FIELDS)
                                    : (push ? SWEEP_PUSH_FIELDS : SWEEP_GRAVITY_FIELDS);
    if (!wp_check_object(what, path, fields, error) ||
        !wp_read_set_at(what, path, &state->request.sets[0], error) ||
        (push && !wp_read_finger(what, path, &state->finger, error)))
        return false;
    if (push && fixture->shape == WR_SHAPE_NONE) {
        wp_error_set(error, WP_INVALID_PARAMS, "params.fixture.body.shape",
                     "push regions need the part's outline: the fixture has no shape");
        return false;
    }
    return true;
}

static void sweep_free(void *stream)
{
    if (!stream)
        return;
    sweep_state *state = stream;
    wr_sweep_job_free(state->job);
    wr_robust_sweep_free(state->robust);
    wr_sweep_curve_release(&state->robust_curve);
    wr_support_sweep_free(state->fixels_job);
    wr_analysis_free(state->fixels_analysis);
    for (int s = 0; s < 3; s++)
        wr_sweeper_free(state->sweepers[s]);
    free(state->request.wrenches);
    free(state->loads);
    free(state->mus);
    free(state->at);
    free(state->push_on);
    wp_cases_release(&state->cases);
    wp_push_load_release(&state->push_load);
    free(state->points);
    free(stream);
}

/* params.over: "fixels" (default: a common mu at every fixel) or
 * "supports" (the supports' mu_B, which a fixture on supports alone has). */
static bool read_over(wp_call *call, const wr_fixture *f, sweep_state *state)
{
    const char *over = NULL;
    if (!wp_member_string(call->params, "params", "over", false, &over, call->error))
        return false;
    if (over && strcmp(over, "supports") != 0 && strcmp(over, "fixels") != 0) {
        wp_error_set(call->error, WP_INVALID_PARAMS, "params.over",
                     "must be \"fixels\" or \"supports\"");
        return false;
    }
    state->over_supports = over && strcmp(over, "supports") == 0;
    state->fixels_on_supports = !state->over_supports && f->supports;
    if (state->over_supports && !f->supports) {
        wp_error_set(call->error, WP_INVALID_PARAMS, "params.over",
                     "the fixture has no supports: sweep its fixels' friction (\"fixels\")");
        return false;
    }
    return true;
}

/* "force" on supports, over `over`: push.force's least push on the plate
 * (set goal, a polygon, a point finger). */
static bool supports_force_question(wp_call *call, sweep_state *state, const char *over)
{
    const cJSON *force = cJSON_GetObjectItemCaseSensitive(call->params, "force");
    const wr_fixture *f = wp_call_fixture(call)->fixture;
    const char *why = cJSON_GetObjectItemCaseSensitive(force, "set") &&
                              state->request.sets[0] != WR_SET_GOAL
                          ? "params.force.set"
                      : f->shape != WR_SHAPE_POLYGON ? "params.fixture.body.shape"
                      : state->finger.radius > 0     ? "params.force.finger_radius"
                                                     : NULL;
    if (why) {
        wp_error_set(call->error, WP_INVALID_PARAMS, why,
                     "over %s the sweep gives the least push that seats the part on its "
                     "supports (set \"goal\"), along a polygon's straight edges, for a point "
                     "finger",
                     over);
        return false;
    }
    state->request.sets[0] = WR_SET_GOAL;
    return true;
}

/* Over the supports' mu_B, "push" or "gravity" on the plate: the push's
 * "force" (with "cases" and "push_on") as push.regions reads them on
 * supports, or the pull "in_plane_g" as gravity.sweep does; set "goal",
 * what seating decides (sweep_plate_step). */
static bool plate_question(wp_call *call, sweep_state *state, const char *over)
{
    const wr_fixture *f = wp_call_fixture(call)->fixture; /* held since begin */
    const bool push = state->what == SWEEP_PUSH;
    const char *path = push ? "params.push" : "params.gravity";
    const cJSON *what = cJSON_GetObjectItemCaseSensitive(call->params, push ? "push" : "gravity");
    char field[WP_FIELD_MAX];
    if (!push) {
        bool given;
        wp_path_key(field, path, "in_plane_g");
        if (!wp_member_number(what, path, "in_plane_g", false, &state->pull, &given, call->error))
            return false;
        if (!given)
            return !wp_supports_refuse(call, f, field,
                                       "\"in_plane_g\", the part of gravity in the plate's plane "
                                       "(g sin(tilt), in the fixture's length / s^2): whether a "
                                       "pull seats the part depends on its size");
        if (!(state->pull > 0) || !isfinite(state->pull)) {
            wp_error_set(call->error, WP_INVALID_PARAMS, field, "must be above 0 and finite");
            return false;
        }
        if (state->request.sets[0] == WR_SET_GOAL)
            return true;
        wp_path_key(field, path, "set");
        wp_error_set(call->error, WP_INVALID_PARAMS, field,
                     "over %s the sweep gives the tilts whose pull seats the part (set "
                     "\"goal\"); whether it is held is wrench.classify's \"strong\" at each "
                     "coefficient",
                     over);
        return false;
    }
    if (!wp_push_load_read_at(what, path, f, state->finger.friction, wp_case_limit(call->limits),
                              &state->push_load, call->error) ||
        !wp_read_push_on(what, path, f, &state->push_on, &state->finger.push_on_count,
                         call->error))
        return false;
    state->finger.push_on = state->push_on;
    if (!state->push_load.given) {
        wp_path_key(field, path, "force");
        return !wp_supports_refuse(call, f, field,
                                   "\"force\", the push's magnitude: the regions where a push "
                                   "that hard seats the part");
    }
    const char *why = wp_supports_push_unanswered(f, state->request.sets[0], state->finger.radius);
    if (!why)
        return true;
    if (strcmp(why, "params.fixture.body.shape") != 0) {
        /* push.regions' own member, here inside "push" */
        wp_path_key(field, path, why + strlen("params."));
        why = field;
    }
    wp_error_set(call->error, WP_INVALID_PARAMS, why,
                 "over %s the sweep gives where a push of the given force seats the part (set "
                 "\"goal\"), along a polygon's straight edges, for a point finger",
                 over);
    return false;
}

/* Over the fixels' mu on supports: the wrenches' sets (wr_support_sweep),
 * and as over the supports' mu_B the least push, the push regions under a
 * force and the tilts under a pull. */
static bool fixels_question(wp_call *call, sweep_state *state)
{
    static const char over[] = "the fixels' mu on a fixture with supports";
    if (state->what == SWEEP_FORCE)
        return supports_force_question(call, state, over);
    return state->what == SWEEP_WRENCHES || plate_question(call, state, over);
}

/* Over the supports' mu_B: the wrenches' seating (goal, the default),
 * which wr_supports_friction_limit decides exactly, or with holding asked
 * every set by wr_support_sweep jobs. */
static bool supports_question(wp_call *call, sweep_state *state)
{
    if (state->what == SWEEP_FORCE)
        return supports_force_question(call, state, "the supports' mu_B");
    if (state->what != SWEEP_WRENCHES)
        return plate_question(call, state, "the supports' mu_B");
    wp_classify_request *r = &state->request;
    if (!cJSON_GetObjectItemCaseSensitive(call->params, "sets")) {
        r->sets[0] = WR_SET_GOAL;
        r->set_count = 1;
    } else {
        /* Holding asked: every set by a wr_support_sweep job, as over the
         * fixels' mu (seating by bisection, exact as the limit below). */
        for (int s = 0; s < r->set_count; s++)
            state->supports_jobs |= r->sets[s] != WR_SET_GOAL;
    }
    return true;
}

/* friction.sweep: one of wrenches, push, gravity, against a common mu.
 * Everything is read and the sweepers made before any answer is written;
 * then each step runs the current job for its budget (wr_sweep.h). */
static void *sweep_begin(wp_call *call, wp_prepared *prepared)
{
    (void)prepared;
    wp_fixture_use *use;
    sweep_state *state = wp_stream_with_fixture(call, sizeof *state, &use);
    if (!state)
        return NULL;
    if (!read_over(call, use->fixture, state) || !read_sweep(call, use->fixture, state) ||
        (state->over_supports && !supports_question(call, state)) ||
        (state->fixels_on_supports && !fixels_question(call, state))) {
        sweep_free(state);
        return NULL;
    }
    if (state->over_supports)
        return state; /* no sweeper: the supports' friction leaves the cones as they are */
    if (state->fixels_on_supports)
        return state; /* no sweeper: each answer is a point answer at its mu */
    if (use->fixture->tolerance.given && state->what == SWEEP_PUSH &&
        state->finger.friction > 0) {
        /* As push.regions over a tolerance (its robust regions are a
         * frictionless finger's). */
        wp_error_set(call->error, WP_INVALID_PARAMS, "params.push.finger_friction",
                     "a fixture with a tolerance has robust regions for a frictionless "
                     "finger only");
        sweep_free(state);
        return NULL;
    }
    if (use->fixture->tolerance.given) {
        /* Robust wrenches: the fixels as they are, placed again with each
         * piece of mu (wr_robust_sweep_wrench). */
        const wr_fixture *f = use->fixture;
        for (int i = 0; i < f->fixel_count; i++)
            state->fixels[i] = (wr_fixel_spec){
                .at = {f->fixels[i].at[0], f->fixels[i].at[1]}, .normal_given = true,
                .normal = {f->fixels[i].normal[0], f->fixels[i].normal[1]}};
    }
    wr_status status = WR_OK;
    /* Force: the push alone's intervals first (the job), then the samples
     * a mu at a time (sweep_force_step). */
    for (int s = 0; status == WR_OK && s < state->request.set_count; s++)
        status = wr_sweeper_new(use->fixture, state->request.sets[s], &state->range,
                                &state->sweepers[s]);
    if (status == WR_OK && (state->what == SWEEP_PUSH || state->what == SWEEP_FORCE))
        status = wr_sweep_job_push(state->sweepers[0], &state->finger, &state->job);
    else if (status == WR_OK && state->what == SWEEP_GRAVITY)
        status = wr_sweep_job_gravity(state->sweepers[0], &state->job);
    if (status != WR_OK) {
        wp_error_status(call->error, status, "params", "%s", wr_strerror(status));
        sweep_free(state);
        return NULL;
    }
    return state;
}

/* The least push force at one mu: the fixture's fixels placed again with
 * mu_s = mu and mu_k = ratio mu, its analysis, wr_least_force_find (over a
 * tolerance the robust least, wr_robust_least_force_at_mu).  Its point
 * [mu, F] (F null when no push does the job) is written. */
static wr_status force_sample(sweep_state *state, const wr_fixture *f, double mu,
                              const wr_stop *stop, unsigned long *used, wp_writer *out,
                              double at[2])
{
    wr_least_force least = {0};
    wr_status status;
    if (f->tolerance.given) {
        /* push.force's least over a tolerance at this mu (wr_robust_sweep.h). */
        status = wr_robust_least_force_at_mu(f, mu, state->range.kinetic_ratio,
                                             state->request.sets[0],
                                             (const double (*)[3])state->loads,
                                             state->cases.count, &state->finger,
                                             ROBUST_FORCE_EDGE_SAMPLES, stop, &least);
        *used += least.evaluations * ROBUST_EVALUATION_COST * (unsigned long)state->cases.count;
    } else {
        wr_friction_spec friction = {.given = true, .static_mu = mu, .kinetic_given = true,
                                     .kinetic_mu = mu * state->range.kinetic_ratio};
        wr_fixture placed;
        wr_error invalid;
        status = wr_fixture_place(f, state->fixels, (size_t)f->fixel_count, &friction, &placed,
                                  &invalid);
        wr_analysis *analysis = NULL;
        if (status == WR_OK)
            status = wr_analysis_new(&placed, &analysis);
        if (status == WR_OK)
            status = wr_least_force_find(analysis, state->request.sets[0],
                                         (const double (*)[3])state->loads, state->cases.count,
                                         &state->finger, NULL, &least);
        wr_analysis_free(analysis);
    }
    if (status != WR_OK)
        return status;
    at[0] = least.found ? least.at[0] + 0.0 : NAN;
    at[1] = least.found ? least.at[1] + 0.0 : NAN;
    *used += 1000 + least.evaluations * 40 * (unsigned long)state->cases.count;
    wp_write_array(out);
    wp_write_number(out, mu + 0.0);
    if (least.found)
        wp_write_number(out, wp_force_out(f, least.force));
    else
        wp_write_null(out);
    wp_write_array_end(out);
    return WR_OK;
}

/* The client has gone (or the daemon stops): true with the error set. */
static bool stop_requested(wp_call *call)
{
    if (!wr_stop_requested(call->host->stop))
        return false;
    wp_error_status(call->error, WR_STOPPED, "", "%s", wr_strerror(WR_STOPPED));
    return true;
}

/* params.deadline_s given and passed. */
static bool deadline_passed(const sweep_state *state)
{
    return state->deadline > 0 && wp_now_s() >= state->deadline;
}

/* "partial": true, "stopped_at": mu -- the members a sweep stopped by its
 * deadline ends its result with (docs/PROTOCOL.md, friction.sweep). */
static void write_stopped(wp_writer *out, double reached)
{
    wp_write_member_bool(out, "partial", true);
    wp_write_member_number(out, "stopped_at", reached + 0.0);
}

static int compare_mus(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* The coefficients to sample (`samples` evenly, ends included, and the
 * ends of the push alone's intervals), increasing, without repeats. */
static bool force_mus(sweep_state *state, const wr_intervals *alone, int samples)
{
    int most = samples + 2 * alone->count;
    state->mus = malloc((size_t)most * sizeof *state->mus);
    state->at = malloc((size_t)most * sizeof *state->at);
    if (!state->mus || !state->at)
        return false;
    const double step = (state->range.high - state->range.low) / (samples - 1);
    int n = 0;
    for (int i = 0; i < samples; i++)
        state->mus[n++] = i + 1 == samples ? state->range.high : state->range.low + i * step;
    for (int i = 0; i < alone->count; i++)
        for (int k = 0; k < 2; k++)
            state->mus[n++] = alone->items[i][k];
    qsort(state->mus, (size_t)n, sizeof *state->mus, compare_mus);
    int kept = 0;
    for (int i = 0; i < n; i++)
        if (kept == 0 || state->mus[i] > state->mus[kept - 1])
            state->mus[kept++] = state->mus[i];
    state->mu_count = kept;
    return true;
}

/* The least push's point at each sample: [x, y], or null (NAN) where no
 * push does the job. */
static void write_points(wp_writer *out, const double (*at)[2], int count)
{
    wp_write_key(out, "at");
    wp_write_array(out);
    for (int i = 0; i < count; i++) {
        if (isnan(at[i][0]))
            wp_write_null(out);
        else
            wp_write_numbers(out, at[i], 2);
    }
    wp_write_array_end(out);
}

/* friction.sweep "force": {"curve": [[mu, F], ...], "at": [[x, y] | null,
 * ...], "intervals": [[lo, hi], ...], "exact": false, "resolution": step}:
 * the push alone's intervals (a job), then a sample of mu at a time. */
static wp_step sweep_force_step(sweep_state *state, wp_call *call, wp_writer *out,
                                unsigned long budget, unsigned long *used)
{
    wp_fixture_use *use = wp_call_fixture(call); /* held since begin */
    if (!use)
        return WP_STEP_FAILED;
    const bool robust = use->fixture->tolerance.given;
    const wr_intervals *alone = robust ? &state->robust_curve.intervals
                                       : &wr_sweep_job_curve(state->job)->intervals;
    if (!state->mus) {
        /* The push alone's intervals: the nominal job's, over a tolerance
         * then made robust (sweep_robust_run) before any sample. */
        bool done = state->robust != NULL;
        wr_status status = WR_OK;
        if (!done)
            status = wr_sweep_job_run(state->job, budget > *used ? budget - *used : 1, used,
                                      call->host->stop, &done);
        if (status == WR_OK && done && robust) {
            wp_step step = sweep_robust_run(state, call, budget, used, false);
            if (step != WP_STEP_DONE)
                return step;
            status = wr_robust_sweep_curve(state->robust, state->robust_top,
                                           &state->robust_curve);
        }
        if (status == WR_OK && done &&
            !force_mus(state, alone, robust ? ROBUST_FORCE_SAMPLES : FORCE_SAMPLES))
            status = WR_NO_MEMORY;
        if (status != WR_OK) {
            wp_error_status(call->error, status, "params", "%s", wr_strerror(status));
            return WP_STEP_FAILED;
        }
        if (!done || *used >= budget)
            return WP_STEP_MORE;
    }
    if (!state->opened) {
        state->opened = true;
        wp_write_object(out);
        wp_write_key(out, "curve");
        wp_write_array(out);
    }
    bool partial = false;
    for (bool first = true; state->sample < state->mu_count && !out->out->failed; first = false) {
        /* Past the deadline: the samples so far (at least one). */
        if (state->sample > 0 && deadline_passed(state)) {
            partial = true;
            break;
        }
        if (!first && *used >= budget)
            return WP_STEP_MORE;
        if (stop_requested(call))
            return WP_STEP_FAILED;
        wr_status status = force_sample(state, use->fixture, state->mus[state->sample],
                                        call->host->stop, used, out, state->at[state->sample]);
        if (status != WR_OK) {
            wp_error_status(call->error, status, "params", "%s", wr_strerror(status));
            return WP_STEP_FAILED;
        }
        state->sample++;
    }
    wp_write_array_end(out);
    write_points(out, state->at, state->sample);
    /* The push alone's intervals are known over the whole range; a partial
     * answer gives them up to where its samples stopped. */
    wp_write_key(out, "intervals");
    write_intervals_below(out, alone, partial ? state->mus[state->sample - 1] : INFINITY);
    wp_write_member_bool(out, "exact", false);
    wp_write_member_number(out, "resolution",
                           (state->range.high - state->range.low) /
                               ((robust ? ROBUST_FORCE_SAMPLES : FORCE_SAMPLES) - 1));
    if (partial)
        write_stopped(out, state->mus[state->sample - 1]);
    wp_write_object_end(out);
    return out->out->failed ? WP_STEP_FAILED : WP_STEP_DONE;
}

/* A step over the supports: the fixture held since begin and the thread's
 * GLPK environment; NULL with the error set when there is none. */
static wr_lp_env *supports_env(wp_call *call, wp_fixture_use **use)
{
    *use = wp_call_fixture(call);
    wr_lp_env *env = call->host->lp_env ? call->host->lp_env(call->host->self) : NULL;
    if (!*use || !env) {
        wp_error_status(call->error, WR_LP_FAILED, "", "%s", wr_strerror(WR_LP_FAILED));
        return NULL;
    }
    return env;
}

/* Over the supports' mu_B: {"results": [{"goal": [[low, mu*]] or []}, ...]},
 * each wrench's interval [low, min(high, mu*)) from
 * wr_supports_friction_limit (its lower bracket: every mu_B in it seats). */
#define SUPPORTS_WRENCH_COST 4000
static wp_step sweep_supports_step(sweep_state *state, wp_call *call, wp_writer *out,
                                   unsigned long budget, unsigned long *used)
{
    wp_fixture_use *use;
    wr_lp_env *env = supports_env(call, &use);
    if (!env)
        return WP_STEP_FAILED;
    if (!state->opened) {
        state->opened = true;
        wp_write_object(out);
        wp_write_key(out, "results");
        wp_write_array(out);
    }
    for (bool first = true; state->next < state->request.wrench_count; first = false) {
        if (deadline_passed(state)) {
            /* Each wrench is answered over the whole range at once: the
             * one under way is decided nowhere yet, cut at the range's
             * bottom (docs/PROTOCOL.md, deadline_s). */
            wp_write_object(out);
            wp_write_key(out, "goal");
            wp_write_array(out);
            wp_write_array_end(out);
            wp_write_object_end(out);
            wp_write_array_end(out);
            write_stopped(out, state->range.low);
            wp_write_object_end(out);
            return out->out->failed ? WP_STEP_FAILED : WP_STEP_DONE;
        }
        if (!first && *used >= budget)
            return WP_STEP_MORE;
        if (stop_requested(call))
            return WP_STEP_FAILED;
        /* In the model system, where the supports' friction is (the
         * wrenches are read in the fixture's force unit). */
        const double k = wr_fixture_force_factor(use->fixture);
        const double *given = state->request.wrenches[state->next];
        const double g[3] = {given[0] * k, given[1] * k, given[2] * k};
        double bracket[2];
        wr_status status =
            wr_supports_friction_limit(use->analysis, use->fixture->supports, env, g, bracket);
        if (status != WR_OK) {
            wp_error_status(call->error, status, "params.wrenches", "%s", wr_strerror(status));
            return WP_STEP_FAILED;
        }
        *used += SUPPORTS_WRENCH_COST;
        wp_write_object(out);
        wp_write_key(out, "goal");
        wp_write_array(out);
        double top = fmin(state->range.high, bracket[0]);
        if (top > state->range.low) {
            const double pair[2] = {state->range.low, top + 0.0};
            wp_write_numbers(out, pair, 2);
        }
        wp_write_array_end(out);
        wp_write_object_end(out);
        state->next++;
    }
    wp_write_array_end(out);
    wp_write_object_end(out);
    return out->out->failed ? WP_STEP_FAILED : WP_STEP_DONE;
}

/* Over the supports' mu_B, "push" and "gravity" (docs/MODEL.md section 11,
 * "Against mu_B"): seating only gets harder as mu_B grows (S(mu) = mu S(1)
 * and C + rho S grows with rho), so the region under the push's force and
 * the arcs under the pull shrink, and each is non-empty exactly on
 * [low, mu_c).  The curve is the point answer (wr_supports_push_regions an
 * edge a piece, or wr_supports_gravity_sweep whole, with the supports at
 * that mu_B) at PLATE_GRID steps over the range; once one is empty every
 * later one is, without solving.  mu_c is then bisected on the point
 * answers between the last non-empty point and the first empty one, to
 * PLATE_CRITICAL_TOLERANCE: nothing can hide between points, the
 * predicate being monotone.  The critical is the bisection's lower end
 * (its region non-empty), which the curve also holds. */
#define PLATE_GRID 64
#define PLATE_CRITICAL_TOLERANCE 1e-9
#define PLATE_EDGE_COST 8000
#define PLATE_TILT_COST WP_PIECE_BUDGET

static double plate_grid_mu(const sweep_state *state, int i)
{
    const wr_sweep_range *r = &state->range;
    return i == PLATE_GRID ? r->high : r->low + (r->high - r->low) * i / PLATE_GRID;
}

/* The mu_B under way: the grid's next point or the bracket's middle. */
static double plate_mu(const sweep_state *state)
{
    return state->bisecting ? 0.5 * (state->lo + state->hi)
                            : plate_grid_mu(state, state->point_count);
}

static bool plate_done(const sweep_state *state)
{
    if (!state->bisecting)
        return state->point_count == PLATE_GRID + 1;
    double mid = plate_mu(state);
    return state->hi - state->lo <= PLATE_CRITICAL_TOLERANCE || mid <= state->lo ||
           mid >= state->hi;
}

/* One piece at mu: an edge's regions (push; *done after the last edge) or
 * the circle of tilts (gravity), added to state->length. */
static wr_status plate_piece(sweep_state *state, wp_call *call, wp_fixture_use *use,
                             wr_lp_env *env, double mu, unsigned long *used, bool *done)
{
    const wr_fixture *f = use->fixture;
    /* The supports at mu_B = mu with the fixture's analysis, or (over the
     * fixels) the fixture placed again with mu on every fixel and its
     * supports as they are. */
    wr_supports at_mu;
    const wr_supports *supports = &at_mu;
    const wr_analysis *analysis = use->analysis;
    wr_status status = WR_OK;
    if (!state->fixels_on_supports) {
        wr_supports_with_friction(f->supports, mu, &at_mu);
    } else {
        if (!state->fixels_analysis || state->fixels_mu != mu) {
            wr_analysis_free(state->fixels_analysis);
            state->fixels_analysis = NULL;
            wr_fixture_at_friction(f, mu, state->range.kinetic_ratio, &state->fixels_at);
            status = wr_analysis_new(&state->fixels_at, &state->fixels_analysis);
            if (status != WR_OK)
                return status;
            state->fixels_mu = mu;
        }
        analysis = state->fixels_analysis;
        supports = f->supports;
    }
    wr_regions found = {0}, undecided = {0};
    if (state->what == SWEEP_GRAVITY) {
        /* The arcs proved to seat; the undecided ones (each under
         * WR_SUPPORT_MIN_ARC degrees) are not counted. */
        status = wr_supports_gravity_sweep(analysis, supports, env, state->pull,
                                           call->host->stop, &found, &undecided);
        *used += PLATE_TILT_COST;
        *done = true;
    } else {
        const wp_push_load *load = &state->push_load;
        if (wr_finger_pushes_on(f, &state->finger, state->edge))
            status = wr_supports_push_regions(analysis, supports, env, load->force,
                                              (const double (*)[3])load->loads, load->count,
                                              state->edge, &found);
        *used += PLATE_EDGE_COST;
        *done = ++state->edge == wr_push_edge_count(f);
    }
    for (int i = 0; status == WR_OK && i < found.count; i++) {
        state->length += state->what == SWEEP_GRAVITY ? found.items[i].t1 - found.items[i].t0
                                                      : wr_region_length(f, &found.items[i]);
        state->nonempty = true;
    }
    wr_regions_release(&found);
    wr_regions_release(&undecided);
    return status;
}

/* The answer at mu is complete: a grid point (and, when it is the first
 * empty one, the rest of the grid, empty too, and the bracket), or the
 * bracket narrowed. */
static void plate_record(sweep_state *state, double mu)
{
    const bool nonempty = state->nonempty;
    const double length = nonempty ? state->length : 0;
    state->edge = 0;
    state->length = 0;
    state->nonempty = false;
    if (state->bisecting) {
        if (nonempty) {
            state->lo = mu;
            state->lo_length = length;
        } else {
            state->hi = mu;
        }
        return;
    }
    int n = state->point_count;
    state->points[n][0] = mu;
    state->points[n][1] = length;
    state->point_count++;
    if (nonempty)
        return;
    if (n > 0) {
        state->bisecting = true;
        state->lo = state->points[n - 1][0];
        state->lo_length = state->points[n - 1][1];
        state->hi = mu;
    }
    for (int i = n + 1; i <= PLATE_GRID; i++) {
        state->points[i][0] = plate_grid_mu(state, i);
        state->points[i][1] = 0;
    }
    state->point_count = PLATE_GRID + 1;
}

/* {"intervals", "critical", "curve", "exact": false, "resolution": the
 * grid's step}, and when the deadline stopped it, "partial" and
 * "stopped_at": the bracket's lower end, or the last grid point made (all
 * non-empty: the grid ends at its first empty point). */
static void plate_write(wp_writer *out, const sweep_state *state, bool partial)
{
    const wr_sweep_range *r = &state->range;
    const double top = !partial           ? r->high
                       : state->bisecting ? state->lo
                       : state->point_count ? state->points[state->point_count - 1][0]
                                            : r->low;
    /* Non-empty from the bottom of the range up to `end`, if at all. */
    const bool empty_at_low = !partial && !state->bisecting && state->points[0][1] == 0;
    const bool any = partial ? state->bisecting || state->point_count > 0 : !empty_at_low;
    const double end = state->bisecting ? state->lo : top;
    wp_write_object(out);
    wp_write_key(out, "intervals");
    wp_write_array(out);
    if (any) {
        const double pair[2] = {r->low, end + 0.0};
        wp_write_numbers(out, pair, 2);
    }
    wp_write_array_end(out);
    wp_write_key(out, "critical");
    if (partial || (!state->bisecting && !empty_at_low))
        wp_write_null(out); /* not known, or non-empty at the top */
    else
        wp_write_number(out, empty_at_low ? r->low : state->lo);
    wp_write_key(out, "curve");
    wp_write_array(out);
    bool placed = !state->bisecting; /* the bracket's lower end, in order */
    for (int i = 0; i < state->point_count && state->points[i][0] <= top; i++) {
        if (!placed && state->lo <= state->points[i][0]) {
            placed = true;
            if (state->lo < state->points[i][0]) {
                const double point[2] = {state->lo, state->lo_length};
                wp_write_numbers(out, point, 2);
            }
        }
        const double point[2] = {state->points[i][0], state->points[i][1] + 0.0};
        wp_write_numbers(out, point, 2);
    }
    if (!placed) {
        const double point[2] = {state->lo, state->lo_length};
        wp_write_numbers(out, point, 2);
    }
    wp_write_array_end(out);
    wp_write_member_bool(out, "exact", false);
    wp_write_member_number(out, "resolution", (r->high - r->low) / PLATE_GRID);
    if (partial)
        write_stopped(out, top);
    wp_write_object_end(out);
}

static wp_step sweep_plate_step(sweep_state *state, wp_call *call, wp_writer *out,
                                unsigned long budget, unsigned long *used)
{
    wp_fixture_use *use;
    wr_lp_env *env = supports_env(call, &use);
    if (!env)
        return WP_STEP_FAILED;
    if (!state->points && !(state->points = malloc((PLATE_GRID + 1) * sizeof *state->points))) {
        wp_error_set(call->error, WP_INTERNAL, "", "out of memory");
        return WP_STEP_FAILED;
    }
    for (bool first = true; !plate_done(state); first = false) {
        if (deadline_passed(state)) {
            plate_write(out, state, true);
            return out->out->failed ? WP_STEP_FAILED : WP_STEP_DONE;
        }
        if (!first && *used >= budget)
            return WP_STEP_MORE;
        if (stop_requested(call))
            return WP_STEP_FAILED;
        const double mu = plate_mu(state);
        bool done;
        wr_status status = plate_piece(state, call, use, env, mu, used, &done);
        if (status != WR_OK) {
            wp_error_status(call->error, status, "params", "%s", wr_strerror(status));
            return WP_STEP_FAILED;
        }
        if (done)
            plate_record(state, mu);
    }
    plate_write(out, state, false);
    return out->out->failed ? WP_STEP_FAILED : WP_STEP_DONE;
}

/* The least push on the plate (wr_supports_least_force_find) at mu: the
 * supports' mu_B = mu (over the supports), or the fixture placed again
 * with mu on every fixel (over the fixels). */
static wr_status supports_least_at(const sweep_state *state, const wp_fixture_use *use,
                                   wr_lp_env *env, double mu, const wr_stop *stop,
                                   wr_least_force *least)
{
    const double (*loads)[3] = (const double (*)[3])state->loads;
    if (!state->fixels_on_supports) {
        wr_supports at_mu;
        wr_supports_with_friction(use->fixture->supports, mu, &at_mu);
        return wr_supports_least_force_find(use->analysis, &at_mu, env, loads,
                                            state->cases.count, &state->finger, stop, least);
    }
    wr_fixture at;
    wr_fixture_at_friction(use->fixture, mu, state->range.kinetic_ratio, &at);
    wr_analysis *analysis;
    wr_status status = wr_analysis_new(&at, &analysis);
    if (status != WR_OK)
        return status;
    status = wr_supports_least_force_find(analysis, at.supports, env, loads, state->cases.count,
                                          &state->finger, stop, least);
    wr_analysis_free(analysis);
    return status;
}

/* Over the supports' mu_B (or the fixels' mu on supports), "force":
 * {"curve": [[mu, F | null], ...], "at":
 * [[x, y] | null, ...], "exact": false, "resolution": step}: the least push
 * on the plate (wr_supports_least_force_find) at SUPPORTS_FORCE_SAMPLES
 * coefficients evenly over the range, ends included, a sample a step. */
#define SUPPORTS_FORCE_SAMPLES 17
static wp_step sweep_supports_force_step(sweep_state *state, wp_call *call, wp_writer *out,
                                         unsigned long budget, unsigned long *used)
{
    wp_fixture_use *use;
    wr_lp_env *env = supports_env(call, &use);
    if (!env)
        return WP_STEP_FAILED;
    const double step = (state->range.high - state->range.low) / (SUPPORTS_FORCE_SAMPLES - 1);
    if (!state->at) {
        state->at = malloc(SUPPORTS_FORCE_SAMPLES * sizeof *state->at);
        if (!state->at) {
            wp_error_set(call->error, WP_INTERNAL, "", "out of memory");
            return WP_STEP_FAILED;
        }
        wp_write_object(out);
        wp_write_key(out, "curve");
        wp_write_array(out);
    }
    bool partial = false;
    for (bool first = true; state->sample < SUPPORTS_FORCE_SAMPLES; first = false) {
        if (state->sample > 0 && deadline_passed(state)) {
            partial = true;
            break;
        }
        if (!first && *used >= budget)
            return WP_STEP_MORE;
        double mu = state->sample + 1 == SUPPORTS_FORCE_SAMPLES
                        ? state->range.high
                        : state->range.low + state->sample * step;
        wr_least_force least;
        wr_status status = supports_least_at(state, use, env, mu, call->host->stop, &least);
        if (status != WR_OK) {
            wp_error_status(call->error, status, "params", "%s", wr_strerror(status));
            return WP_STEP_FAILED;
        }
        *used += 1000 + least.evaluations * 400 * (unsigned long)state->cases.count;
        double *point = state->at[state->sample];
        point[0] = least.found ? least.at[0] + 0.0 : NAN;
        point[1] = least.found ? least.at[1] + 0.0 : NAN;
        wp_write_array(out);
        wp_write_number(out, mu + 0.0);
        if (least.found)
            wp_write_number(out, wp_force_out(use->fixture, least.force));
        else
            wp_write_null(out);
        wp_write_array_end(out);
        state->sample++;
    }
    wp_write_array_end(out);
    write_points(out, state->at, state->sample);
    wp_write_member_bool(out, "exact", false);
    wp_write_member_number(out, "resolution", step);
    if (partial)
        write_stopped(out, state->range.low + (state->sample - 1) * step);
    wp_write_object_end(out);
    return out->out->failed ? WP_STEP_FAILED : WP_STEP_DONE;
}

/* "exact": false and the grid's step when a set asked is sampled (strong,
 * both: wr_support_sweep.h); nothing when only goal is asked. */
static void write_fixels_exactness(const sweep_state *state, wp_writer *out)
{
    const wp_classify_request *r = &state->request;
    for (int s = 0; s < r->set_count; s++)
        if (r->sets[s] != WR_SET_GOAL) {
            wp_write_member_bool(out, "exact", false);
            wp_write_member_number(out, "resolution", (state->range.high - state->range.low) /
                                                          WR_SUPPORT_SWEEP_GRID);
            return;
        }
}

/* Over the fixels' mu on supports, or over mu_B with holding asked,
 * "wrenches": {"results": [{"goal":
 * [...], "strong": [...]}, ...], "exact"?, "resolution"?}, a
 * wr_support_sweep job per wrench and set. */
static wp_step sweep_fixels_step(sweep_state *state, wp_call *call, wp_writer *out,
                                unsigned long budget, unsigned long *used)
{
    wp_fixture_use *use;
    wr_lp_env *env = supports_env(call, &use);
    if (!env)
        return WP_STEP_FAILED;
    const wp_classify_request *r = &state->request;
    if (!state->opened) {
        state->opened = true;
        wp_write_object(out);
        wp_write_key(out, "results");
        wp_write_array(out);
    }
    bool stopped = false;
    double reached = 0;
    for (bool first = true; state->next < r->wrench_count && !out->out->failed && !stopped;
         first = false) {
        if (!first && *used >= budget)
            return WP_STEP_MORE;
        if (!state->fixels_job) {
            /* In the model system, where the supports' friction is. */
            const double k = wr_fixture_force_factor(use->fixture);
            const double *given = r->wrenches[state->next];
            const double g[3] = {given[0] * k, given[1] * k, given[2] * k};
            wr_status status = wr_support_sweep_new(
                use->fixture, g, r->sets[state->set], &state->range,
                state->over_supports ? WR_SUPPORT_SWEEP_SUPPORTS : WR_SUPPORT_SWEEP_FIXELS,
                &state->fixels_job);
            if (status != WR_OK) {
                wp_error_status(call->error, status, "params.wrenches", "%s",
                                wr_strerror(status));
                return WP_STEP_FAILED;
            }
        }
        /* Past the deadline: the job ends where it has got to (as the
         * floating sweep's, below). */
        bool done = false;
        stopped = deadline_passed(state);
        wr_status status =
            stopped ? wr_support_sweep_stop(state->fixels_job, &reached)
                    : wr_support_sweep_run(state->fixels_job, env,
                                           budget > *used ? budget - *used : 1, used,
                                           call->host->stop, &done);
        if (status != WR_OK) {
            wp_error_status(call->error, status, "params", "%s", wr_strerror(status));
            return WP_STEP_FAILED;
        }
        if (!done && !stopped)
            continue;
        if (state->set == 0)
            wp_write_object(out);
        wp_write_key(out, wp_set_names[r->sets[state->set]]);
        write_intervals(out, wr_support_sweep_intervals(state->fixels_job));
        wr_support_sweep_free(state->fixels_job);
        state->fixels_job = NULL;
        if (++state->set == r->set_count || stopped) {
            wp_write_object_end(out);
            state->set = 0;
            state->next++;
        }
    }
    wp_write_array_end(out);
    write_fixels_exactness(state, out);
    if (stopped)
        write_stopped(out, reached);
    wp_write_object_end(out);
    return out->out->failed ? WP_STEP_FAILED : WP_STEP_DONE;
}

/* Over a tolerance, "push" or "gravity" (and "force"'s intervals): the
 * nominal job's intervals made robust (wr_robust_sweep.h) a unit at a
 * time, from the nominal job done (or stopped: then nothing robust is
 * decided).  WP_STEP_MORE while the budget is spent; WP_STEP_DONE with
 * state->robust_top the mu below which its answer holds (below the range's
 * top when the deadline stopped it). */
static wp_step sweep_robust_run(sweep_state *state, wp_call *call, unsigned long budget,
                                unsigned long *used, bool stopped)
{
    const wr_fixture *f = wp_call_fixture(call)->fixture; /* held since begin */
    wr_status status = WR_OK;
    if (!state->robust)
        status = wr_robust_sweep_new(f, state->request.sets[0], &state->range,
                                     state->what == SWEEP_GRAVITY, &state->finger,
                                     &wr_sweep_job_curve(state->job)->intervals, &state->robust);
    if (status == WR_OK && stopped) {
        state->robust_top = state->range.low;
        return WP_STEP_DONE;
    }
    for (bool first = true; status == WR_OK; first = false) {
        if (deadline_passed(state)) {
            state->robust_top = wr_robust_sweep_reached(state->robust);
            return WP_STEP_DONE;
        }
        if (!first && *used >= budget)
            return WP_STEP_MORE;
        unsigned long before = wr_robust_sweep_work(state->robust);
        bool done;
        status = wr_robust_sweep_run(state->robust, call->host->stop, &done);
        *used += 1 + wr_robust_sweep_work(state->robust) - before;
        if (status == WR_OK && done) {
            state->robust_top = state->range.high;
            return WP_STEP_DONE;
        }
    }
    wp_error_status(call->error, status, "params", "%s", wr_strerror(status));
    return WP_STEP_FAILED;
}

/* Over a tolerance, "push" or "gravity": the robust curve, written when
 * done or stopped (write_curve's members, the critical and the curve of
 * the robust regions). */
static wp_step sweep_robust_step(sweep_state *state, wp_call *call, wp_writer *out,
                                 unsigned long budget, unsigned long *used, bool stopped)
{
    wp_step step = sweep_robust_run(state, call, budget, used, stopped);
    if (step != WP_STEP_DONE)
        return step;
    wr_sweep_curve curve;
    const bool partial = state->robust_top < state->range.high;
    if (wr_robust_sweep_curve(state->robust, state->robust_top, &curve) != WR_OK) {
        wp_error_set(call->error, WP_INTERNAL, "", "out of memory");
        return WP_STEP_FAILED;
    }
    write_curve(out, &curve, partial, state->robust_top);
    wr_sweep_curve_release(&curve);
    return out->out->failed ? WP_STEP_FAILED : WP_STEP_DONE;
}

static wp_step sweep_step(void *stream, wp_call *call, wp_writer *out, unsigned long budget,
                          unsigned long *used)
{
    sweep_state *state = stream;
    if ((state->fixels_on_supports || state->supports_jobs) && state->what == SWEEP_WRENCHES)
        return sweep_fixels_step(state, call, out, budget, used);
    if (state->over_supports || state->fixels_on_supports)
        return state->what == SWEEP_FORCE
                   ? sweep_supports_force_step(state, call, out, budget, used)
               : state->what == SWEEP_WRENCHES ? sweep_supports_step(state, call, out, budget, used)
                                               : sweep_plate_step(state, call, out, budget, used);
    if (state->what == SWEEP_FORCE)
        return sweep_force_step(state, call, out, budget, used);
    if (state->robust)
        return sweep_robust_step(state, call, out, budget, used, false);
    const wp_classify_request *r = &state->request;
    const wr_stop *stop = call->host->stop;
    size_t start = out->out->length;
    for (bool first = true; !out->out->failed; first = false) {
        if (!first && (*used >= budget || out->out->length - start >= WP_PIECE_BYTES))
            return WP_STEP_MORE;
        if (state->what == SWEEP_WRENCHES) {
            if (!state->opened) {
                state->opened = true;
                wp_write_object(out);
                wp_write_key(out, "results");
                wp_write_array(out);
            }
            if (state->next >= r->wrench_count) {
                wp_write_array_end(out);
                wp_write_object_end(out);
                return WP_STEP_DONE;
            }
            if (!state->job) {
                wr_status status = wr_sweep_job_wrench(state->sweepers[state->set],
                                                       r->wrenches[state->next], &state->job);
                if (status != WR_OK) {
                    wp_error_status(call->error, status, "params.wrenches", "%s",
                                    wr_strerror(status));
                    return WP_STEP_FAILED;
                }
            }
        }
        /* Past the deadline: the job ends where it has got to, and is
         * answered as if done; the result then says where that was. */
        bool done = false, stopped = deadline_passed(state);
        double reached = 0;
        wr_status status = stopped ? wr_sweep_job_stop(state->job, &reached)
                                   : wr_sweep_job_run(state->job,
                                                      budget > *used ? budget - *used : 1, used,
                                                      stop, &done);
        done |= stopped;
        if (status != WR_OK) {
            wp_error_status(call->error, status, "params", "%s", wr_strerror(status));
            return WP_STEP_FAILED;
        }
        if (!done)
            continue;
        if (state->what != SWEEP_WRENCHES) {
            if (wp_call_fixture(call)->fixture->tolerance.given)
                return sweep_robust_step(state, call, out, budget, used, stopped);
            write_curve(out, wr_sweep_job_curve(state->job), stopped, reached);
            return WP_STEP_DONE;
        }
        /* A wrench's set answered: {"goal": [...], ...} as its sets end. */
        if (state->set == 0)
            wp_write_object(out);
        wp_write_key(out, wp_set_names[r->sets[state->set]]);
        const wr_fixture *f = wp_call_fixture(call)->fixture; /* held since begin */
        if (f->tolerance.given) {
            /* Over the tolerance: the nominal intervals' robust part. */
            wr_intervals robust = {0};
            status = wr_robust_sweep_wrench(f, state->fixels, state->range.kinetic_ratio,
                                            r->wrenches[state->next], r->sets[state->set],
                                            wr_sweep_job_intervals(state->job),
                                            call->host->stop, &robust);
            if (status != WR_OK) {
                wr_intervals_release(&robust);
                wp_error_status(call->error, status, "params", "%s", wr_strerror(status));
                return WP_STEP_FAILED;
            }
            write_intervals(out, &robust);
            wr_intervals_release(&robust);
        } else {
            write_intervals(out, wr_sweep_job_intervals(state->job));
        }
        wr_sweep_job_free(state->job);
        state->job = NULL;
        if (++state->set == r->set_count || stopped) {
            wp_write_object_end(out);
            state->set = 0;
            state->next++;
        }
        if (stopped) {
            /* The last result's last set is answered up to `reached`. */
            wp_write_array_end(out);
            write_stopped(out, reached);
            wp_write_object_end(out);
            return out->out->failed ? WP_STEP_FAILED : WP_STEP_DONE;
        }
    }
    return WP_STEP_FAILED; /* out of memory: the buffer says so */
}

static size_t sweep_bytes(const void *stream)
{
    const sweep_state *state = stream;
    return sizeof *state + state->request.wrench_count * sizeof(double[3]);
}

const wp_streamer wp_sweep_stream = {sweep_begin, sweep_step, sweep_free, sweep_bytes, false, NULL, NULL};
