/* analysis.c -- questions about one fixture: cone.get, plan.get,
 * modes.get, push.regions (written an edge at a time), gravity.sweep and
 * stability.margin. */
#include "common.h"
#include "loads.h"
#include "methods.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static void write_vector3(wp_writer *out, const double v[3])
{
    /* + 0.0 turns -0 into 0, which would be written "-0". */
    const double w[3] = {v[0] + 0.0, v[1] + 0.0, v[2] + 0.0};
    wp_write_numbers(out, w, 3);
}

/* ---- cone.get, plan.get, modes.get --------------------------------------- */

bool wp_handle_cone_get(wp_call *call, wp_writer *out)
{
    const cJSON *params = call->params;
    wp_error *error = call->error;
    const char *text;
    if (!wp_member_string(params, "params", "constraints", true, &text, error))
        return false;
    wp_fixture_use *use = wp_call_fixture(call);
    if (!use)
        return false;
    const wr_fixture *f = use->fixture;
    wr_constraint constraint;
    wr_error invalid;
    wr_cone cone;
    wr_status status = wr_constraint_parse(text, f->fixel_count, &constraint, &invalid);
    if (status != WR_OK) {
        wp_error_status(error, status, "params.constraints", "%s", invalid.reason);
        return false;
    }
    status = wr_cone_build(&cone, f, &constraint);
    if (status != WR_OK) {
        wr_cone_release(&cone);
        wp_error_status(error, status, "params.constraints", "%s", wr_strerror(status));
        return false;
    }
    wp_write_object(out);
    wp_write_member_string(out, "constraints", text);
    wp_write_member_bool(out, "empty", cone.empty);
    wp_write_member_number(out, "dimension", cone.dimension);
    double row[3];
    wp_write_key(out, "halfspaces");
    wp_write_array(out);
    for (int i = 0; i < cone.facet_count; i++) {
        wr_fixture_unscale_row(f, cone.facets[i], row);
        write_vector3(out, row);
    }
    wp_write_array_end(out);
    wp_write_key(out, "strict");
    wp_write_array(out);
    for (int i = 0; i < cone.facet_count; i++)
        wp_write_bool(out, cone.facet_open[i]);
    wp_write_array_end(out);
    wp_write_key(out, "equalities");
    wp_write_array(out);
    for (int i = 0; i < cone.equality_count && !cone.empty; i++) {
        wr_fixture_unscale_row(f, cone.equalities[i], row);
        write_vector3(out, row);
    }
    wp_write_array_end(out);
    wp_write_key(out, "generators");
    wp_write_array(out);
    for (int i = 0; i < cone.ray_count; i++) {
        wr_fixture_unscale_wrench(f, cone.rays[i], row);
        wr_fixture_unit_direction(row);
        write_vector3(out, row);
    }
    wp_write_array_end(out);
    wp_write_object_end(out);
    wr_cone_release(&cone);
    return true;
}

bool wp_handle_plan_get(wp_call *call, wp_writer *out)
{
    wp_fixture_use *use = wp_call_fixture(call);
    if (!use)
        return false;
    const wr_plan *plan = wr_analysis_plan(use->analysis);
    int k = plan->fixel_count;
    wp_write_object(out);
    wp_write_key(out, "states");
    wp_write_array(out);
    for (int s = 0; s < plan->state_count; s++) {
        const wr_plan_state *ps = &plan->states[s];
        char text[WR_STATE_TEXT];
        wr_state_format(ps->state, k, text);
        wp_write_object(out);
        wp_write_member_string(out, "state", text);
        wp_write_key(out, "excluded");
        wp_write_array(out);
        for (int e = 0; e < ps->excluded_count; e++)
            wp_write_string(out, plan->excluded[ps->excluded_first + e].letters);
        wp_write_array_end(out);
        wp_write_object_end(out);
    }
    wp_write_array_end(out);
    wp_write_key(out, "cones");
    wp_write_array(out);
    for (int i = 0; i < plan->kept_count; i++)
        wp_write_string(out, plan->kept[i].letters);
    wp_write_array_end(out);
    wp_write_object_end(out);
    return true;
}

bool wp_handle_modes_get(wp_call *call, wp_writer *out)
{
    wp_fixture_use *use = wp_call_fixture(call);
    if (!use)
        return false;
    const wr_analysis *a = use->analysis;
    const wr_constraint *modes = wr_analysis_constraints(a, WR_SET_STRONG);
    wp_write_object(out);
    wp_write_key(out, "feasible");
    wp_write_array(out);
    for (int i = 0; i < wr_analysis_cone_count(a, WR_SET_STRONG); i++) {
        char text[WR_CONSTRAINT_TEXT];
        wr_constraint_format(&modes[i], text);
        wp_write_string(out, text);
    }
    wp_write_array_end(out);
    wp_write_member_bool(out, "pinned", wr_analysis_pinned(a));
    wp_write_object_end(out);
    return true;
}

/* ---- push.regions, gravity.sweep, stability.margin ----------------------- */

static bool read_set(const cJSON *params, wr_set *set, wp_error *error)
{
    return wp_read_set_at(params, "params", set, error);
}

/* push.regions, written an edge at a time (a finger with friction samples
 * every edge: a long outline is seconds of work). */
typedef struct push_state {
    wr_set set;
    wr_finger finger;    /* its friction and radius; its push_on: */
    bool *push_on;       /* owned */
    int edges, next;     /* the outline's edges; the next to answer */
    unsigned long edge_cost;
    bool opened, any;    /* {"regions":[ written; a region written */
    double total, resolution;
    wp_push_load load;   /* "force" and "cases": regions under them */
    wr_robust *robust;   /* the fixture has a tolerance: the regions' robust part */
} push_state;

static void push_free(void *stream)
{
    push_state *state = stream;
    free(state->push_on);
    wp_push_load_release(&state->load);
    wr_robust_free(state->robust);
    free(state);
}

/* One reason: the blocking cone (set and index; index -1: none). */
typedef struct reason {
    wr_set set;
    int index;
    int edges;
} reason;

static void write_push_why(wp_writer *out, const wr_analysis *analysis, wr_set set,
                       const wr_finger *finger)
{
    const wr_fixture *f = wr_analysis_fixture(analysis);
    int edges = wr_push_edge_count(f);
    reason *reasons = calloc((size_t)edges + 1, sizeof *reasons);
    int count = 0;
    for (int e = 0; reasons && e < edges; e++) {
        if (!wr_finger_pushes_on(f, finger, e))
            continue;
        double wrench[3];
        wr_push_wrench(f, e, f->shape == WR_SHAPE_CIRCLE ? 180 : 0.5, wrench);
        wr_answer answer;
        if (wr_classify_margin(analysis, wrench, set, WR_DEFAULT_TOLERANCE, &answer) != WR_OK)
            continue;
        reason r = {answer.blocking >= 0 ? answer.blocking_set : set, answer.blocking, 1};
        int i = 0;
        while (i < count && (reasons[i].set != r.set || reasons[i].index != r.index))
            i++;
        if (i < count)
            reasons[i].edges++;
        else
            reasons[count++] = r;
    }
    /* Most edges first; equal counts in the order first met (insertion). */
    for (int a = 1; a < count; a++)
        for (int b = a; b > 0 && reasons[b].edges > reasons[b - 1].edges; b--) {
            reason swap = reasons[b];
            reasons[b] = reasons[b - 1];
            reasons[b - 1] = swap;
        }
    wp_write_key(out, "why_empty");
    wp_write_object(out);
    wp_write_key(out, "reasons");
    wp_write_array(out);
    for (int i = 0; i < count; i++) {
        wp_write_object(out);
        wp_write_key(out, "blocking");
        if (reasons[i].index < 0) {
            wp_write_null(out);
        } else {
            char text[WR_CONSTRAINT_TEXT];
            wr_constraint_format(&wr_analysis_cone(analysis, reasons[i].set, reasons[i].index)
                                      ->constraint,
                                 text);
            wp_write_string(out, text);
        }
        wp_write_member_string(out, "set", wp_set_names[reasons[i].set]);
        wp_write_key(out, "states");
        wp_write_array(out);
        if (reasons[i].index >= 0 && reasons[i].set == WR_SET_GOAL) {
            const wr_plan_origins *origins =
                &wr_analysis_plan(analysis)->origins[reasons[i].index];
            for (int j = 0; j < origins->count; j++) {
                char state[WR_STATE_TEXT];
                wr_state_format(origins->states[j], f->fixel_count, state);
                wp_write_string(out, state);
            }
        }
        wp_write_array_end(out);
        wp_write_member_number(out, "edges", reasons[i].edges);
        wp_write_object_end(out);
    }
    wp_write_array_end(out);
    wp_write_object_end(out);
    free(reasons);
}

/* Boxes per excluded cone for one piece of a robust region: a piece that
 * so few do not prove is split instead (wr_robust_regions). */
#define ROBUST_REGION_BUDGET 16

/* What robust regions cover (docs/PROTOCOL.md, "Tolerance"): the push of a
 * frictionless finger alone; a finger's friction or loads are refused. */
static bool robust_push_supported(const wp_push_load *load, double friction, wp_error *error)
{
    if (friction > 0) {
        wp_error_set(error, WP_INVALID_PARAMS, "params.finger_friction",
                     "a fixture with a tolerance has robust regions for a frictionless "
                     "finger only");
        return false;
    }
    if (load->given) {
        wp_error_set(error, WP_INVALID_PARAMS, "params.force",
                     "a fixture with a tolerance has robust regions without loads only");
        return false;
    }
    return true;
}

/* On supports (wr_support.h) the regions are those of a push of a given
 * force that seats the part (goal), on a polygon's straight edges, for a
 * point finger: false with the error set otherwise. */
static bool supports_push_ok(wp_call *call, const wr_fixture *f, wr_set set, double radius,
                             const wp_push_load *load)
{
    if (!f->supports)
        return true;
    if (!load->given)
        return !wp_supports_refuse(call, f, "params.force",
                                   "\"force\", the push's magnitude: the regions where a push "
                                   "that hard seats the part");
    const char *why = wp_supports_push_unanswered(f, set, radius);
    if (!why)
        return true;
    wp_error_set(call->error, WP_INVALID_PARAMS, why,
                 "the fixture rests on supports: its push regions are where a push of the given "
                 "force seats it (set \"goal\"), along a polygon's straight edges, for a point "
                 "finger; whether the seated part is held is wrench.classify's \"strong\"");
    return false;
}

static void *push_begin(wp_call *call, wp_prepared *prepared)
{
    (void)prepared;
    wr_set set;
    wr_finger finger;
    if (!read_set(call->params, &set, call->error) ||
        !wp_read_finger(call->params, "params", &finger, call->error))
        return NULL;
    double friction = finger.friction, radius = finger.radius;
    wp_fixture_use *use = wp_call_fixture(call);
    if (!use)
        return NULL;
    if (use->fixture->shape == WR_SHAPE_NONE) {
        wp_error_set(call->error, WP_INVALID_PARAMS, "params.fixture.body.shape",
                     "push regions need the part's outline: the fixture has no shape");
        return NULL;
    }
    wp_push_load load;
    if (!wp_push_load_read(call->params, use->fixture, friction, wp_case_limit(call->limits),
                           &load, call->error))
        return NULL;
    if ((use->fixture->tolerance.given && !robust_push_supported(&load, friction, call->error)) ||
        !supports_push_ok(call, use->fixture, set, radius, &load)) {
        wp_push_load_release(&load);
        return NULL;
    }
    push_state *state = calloc(1, sizeof *state);
    if (!state) {
        wp_push_load_release(&load);
        wp_error_set(call->error, WP_INTERNAL, "", "out of memory");
        return NULL;
    }
    state->load = load;
    state->set = set;
    state->finger = (wr_finger){.friction = friction, .radius = radius};
    if (!wp_read_push_on(call->params, "params", use->fixture, &state->push_on,
                         &state->finger.push_on_count, call->error)) {
        wp_push_load_release(&state->load);
        free(state);
        return NULL;
    }
    state->finger.push_on = state->push_on;
    state->edges = wr_push_edge_count(use->fixture);
    if (use->fixture->tolerance.given &&
        wr_robust_new(use->analysis, ROBUST_REGION_BUDGET, &state->robust) != WR_OK) {
        push_free(state);
        wp_error_set(call->error, WP_INTERNAL, "", "out of memory");
        return NULL;
    }
    /* An edge against every cone: a few dot products each, or, with a
     * finger's friction, a segment test at every sample and bisection. */
    const wr_analysis *a = use->analysis;
    unsigned long cones = (unsigned long)(set == WR_SET_GOAL     ? wr_analysis_cone_count(a, WR_SET_GOAL)
                                          : set == WR_SET_STRONG ? wr_analysis_cone_count(a, WR_SET_STRONG)
                                                                 : wr_analysis_cone_count(a, WR_SET_GOAL) +
                                                                       wr_analysis_cone_count(a, WR_SET_STRONG));
    /* A finger with a size is tested against every segment of the outline. */
    state->edge_cost = (cones + 1) * (friction > 0 ? 2200 : 4) * (unsigned long)(load.count + 1) +
                       (radius > 0 ? 8 * (unsigned long)state->edges : 0);
    return state;
}

static void write_region(wp_writer *out, const wr_fixture *f, const wr_region *r, double length)
{
    double from[2], to[2], normal[2];
    wr_boundary_point(f, r->edge, r->t0, from, normal);
    wr_boundary_point(f, r->edge, r->t1, to, normal);
    /* + 0.0: a -0 is written 0. */
    const double ends[2][2] = {{from[0] + 0.0, from[1] + 0.0}, {to[0] + 0.0, to[1] + 0.0}};
    wp_write_object(out);
    wp_write_edge_place(out, f, r->edge);
    wp_write_key(out, "from");
    wp_write_numbers(out, ends[0], 2);
    wp_write_key(out, "to");
    wp_write_numbers(out, ends[1], 2);
    wp_write_member_number(out, "t0", r->t0);
    wp_write_member_number(out, "t1", r->t1);
    wp_write_member_number(out, "length", length);
    wp_write_object_end(out);
}

static wp_step push_step(void *stream, wp_call *call, wp_writer *out, unsigned long budget,
                         unsigned long *used)
{
    push_state *state = stream;
    wp_fixture_use *use = wp_call_fixture(call); /* held since begin */
    if (!use)
        return WP_STEP_FAILED;
    const wr_fixture *f = use->fixture;
    size_t start = out->out->length;
    if (!state->opened) {
        state->opened = true;
        wp_write_object(out);
        wp_write_key(out, "regions");
        wp_write_array(out);
    }
    /* At least one edge a step: every step makes progress. */
    for (bool first = true; state->next < state->edges && !out->out->failed; first = false) {
        if (!first && (*used >= budget || out->out->length - start >= WP_PIECE_BYTES))
            return WP_STEP_MORE;
        wr_regions part = {0};
        const wp_push_load *load = &state->load;
        /* On supports, only the edges the finger may push on (push_on); the
         * other paths ask the finger itself. */
        bool skip = f->supports && load->given && !wr_finger_pushes_on(f, &state->finger, state->next);
        wr_lp_env *env = call->host->lp_env ? call->host->lp_env(call->host->self) : NULL;
        wr_status status =
            skip ? WR_OK
            : f->supports
                ? (env ? wr_supports_push_regions(use->analysis, f->supports, env, load->force,
                                                  (const double (*)[3])load->loads, load->count,
                                                  state->next, &part)
                       : WR_LP_FAILED)
            : load->given
                ? wr_push_regions_loaded(use->analysis, state->set, load->force,
                                         (const double (*)[3])load->loads, load->count,
                                         &state->finger, state->next, 1, call->host->stop, &part)
                : wr_push_regions_part(use->analysis, state->set, &state->finger, state->next, 1,
                                       call->host->stop, &part);
        if (status == WR_OK && state->robust) {
            wr_regions nominal = part;
            status = wr_robust_regions(state->robust, state->set, &nominal, false,
                                       call->host->stop, &part);
            wr_regions_release(&nominal);
        }
        if (status != WR_OK) {
            wr_regions_release(&part);
            wp_error_status(call->error, status, "", "%s", wr_strerror(status));
            return WP_STEP_FAILED;
        }
        for (int i = 0; i < part.count; i++) {
            /* Summed in the order written, as the whole answer always was. */
            double length = wr_region_length(f, &part.items[i]);
            state->total += length;
            state->any = true;
            write_region(out, f, &part.items[i], length);
        }
        state->resolution = part.resolution;
        wr_regions_release(&part);
        state->next++;
        *used += state->edge_cost;
    }
    wp_write_array_end(out);
    wp_write_member_number(out, "total_length", state->total);
    wp_write_member_number(out, "fraction", state->total / wr_perimeter(f));
    wp_write_member_bool(out, "exact", state->resolution == 0);
    wp_write_member_number(out, "resolution", state->resolution);
    /* Why there is none: the blocking cones of the push alone (without
     * loads; under loads force.range says it per point). */
    if (!state->any && !state->load.given)
        write_push_why(out, use->analysis, state->set, &state->finger);
    wp_write_object_end(out);
    return WP_STEP_DONE;
}

const wp_streamer wp_push_stream = {push_begin, push_step, push_free, NULL, false, NULL, NULL};

/* Nominal regions or arcs replaced by their robust part. */
static wr_status robust_part(const wr_analysis *a, wr_set set, bool gravity, const wr_stop *stop,
                             wr_regions *regions)
{
    wr_robust *robust;
    wr_status status = wr_robust_new(a, ROBUST_REGION_BUDGET, &robust);
    wr_regions nominal = *regions;
    if (status == WR_OK)
        status = wr_robust_regions(robust, set, &nominal, gravity, stop, regions);
    else
        memset(regions, 0, sizeof *regions);
    wr_regions_release(&nominal);
    wr_robust_free(robust);
    return status;
}

static void write_arcs(wp_writer *out, const char *key, const wr_regions *arcs)
{
    wp_write_key(out, key);
    wp_write_array(out);
    for (int i = 0; i < arcs->count; i++) {
        const double arc[2] = {arcs->items[i].t0 + 0.0, arcs->items[i].t1 + 0.0};
        wp_write_numbers(out, arc, 2);
    }
    wp_write_array_end(out);
}

/* gravity.sweep on supports (wr_supports_gravity_sweep): the tilts whose
 * in-plane pull m in_plane_g seats the part (set "goal"), the arcs proved
 * and those left undecided. */
static bool tilt_on_supports(wp_call *call, wp_fixture_use *use, wr_set set, double pull,
                             bool given, wp_writer *out)
{
    if (!given)
        return !wp_supports_refuse(call, use->fixture, "params.in_plane_g",
                                   "\"in_plane_g\", the part of gravity in the plate's plane "
                                   "(g sin(tilt), in the fixture's length / s^2): whether a pull "
                                   "seats the part depends on its size");
    if (set != WR_SET_GOAL) {
        wp_error_set(call->error, WP_INVALID_PARAMS, "params.set",
                     "the fixture rests on supports: gravity.sweep gives the tilts whose pull "
                     "seats it (set \"goal\"); whether the seated part is held under that "
                     "pull is wrench.classify's \"strong\" with it");
        return false;
    }
    wr_lp_env *env = call->host->lp_env ? call->host->lp_env(call->host->self) : NULL;
    wr_regions good, undecided;
    wr_status status = env ? wr_supports_gravity_sweep(use->analysis, use->fixture->supports, env,
                                                       pull, call->host->stop, &good, &undecided)
                           : WR_LP_FAILED;
    if (status != WR_OK) {
        wp_error_status(call->error, status, "params.in_plane_g", "%s", wr_strerror(status));
        return false;
    }
    wp_write_object(out);
    write_arcs(out, "intervals_deg", &good);
    write_arcs(out, "undecided_deg", &undecided);
    wp_write_object_end(out);
    wr_regions_release(&good);
    wr_regions_release(&undecided);
    return true;
}

bool wp_handle_gravity_sweep(wp_call *call, wp_writer *out)
{
    const cJSON *params = call->params;
    wp_error *error = call->error;
    wr_set set;
    if (!read_set(params, &set, error))
        return false;
    /* Checked whether used or not (a floating part's arcs do not depend on
     * the pull's size). */
    double pull = 0;
    bool given = false;
    if (!wp_member_number(params, "params", "in_plane_g", false, &pull, &given, error))
        return false;
    if (given && (!(pull > 0) || !isfinite(pull))) {
        wp_error_set(error, WP_INVALID_PARAMS, "params.in_plane_g", "must be above 0 and finite");
        return false;
    }
    wp_fixture_use *use = wp_call_fixture(call);
    if (!use)
        return false;
    if (use->fixture->supports)
        return tilt_on_supports(call, use, set, pull, given, out);
    wr_regions arcs;
    wr_status status = wr_gravity_sweep(use->analysis, set, &arcs);
    if (status == WR_OK && use->fixture->tolerance.given)
        status = robust_part(use->analysis, set, true, call->host->stop, &arcs);
    if (status != WR_OK) {
        wp_error_status(error, status, "params.set", "%s", wr_strerror(status));
        return false;
    }
    wp_write_object(out);
    write_arcs(out, "intervals_deg", &arcs);
    wp_write_object_end(out);
    wr_regions_release(&arcs);
    return true;
}

/* The disturbance margin over a fixture's tolerance: the robust answer of
 * the bias in G_strong, its margin (for inside, a lower bound of the worst
 * over the set; for outside, the witness fixture's) times |h(bias)|,
 * blocking at the nominal cone named when it has one. */
static wr_status robust_margin(const wr_analysis *a, const double bias[3], wr_disturbance *d,
                               wr_robust_answer *robust)
{
    wr_robust *rb;
    wr_status status = wr_robust_new(a, 0, &rb);
    if (status != WR_OK)
        return status;
    status = wr_robust_classify(rb, bias, WR_SET_STRONG, WR_DEFAULT_TOLERANCE, robust);
    wr_robust_free(rb);
    if (status != WR_OK)
        return status;
    double unit[3];
    double length = wr_fixture_unit_wrench(wr_analysis_fixture(a), bias, unit);
    d->margin = fmin(d->margin, robust->answer.margin * length);
    if (robust->answer.blocking >= 0)
        d->blocking = robust->answer.blocking;
    return WR_OK;
}

/* "robust": the verdict over the set, and an outside's witness, as
 * members of the object being written. */
static void write_robust_verdict(wp_writer *out, const wr_fixture *f, const wr_robust_answer *r)
{
    static const char *const NAMES[] = {"inside", "boundary", "outside"};
    wp_write_member_string(out, "robust", NAMES[r->answer.verdict]);
    wp_write_perturbation(out, f, r);
}

/* A bracket's end: null when no wrench bounds it (no held wrench found). */
static void write_bound(wp_writer *out, double value)
{
    if (isfinite(value))
        wp_write_number(out, value + 0.0);
    else
        wp_write_null(out);
}

/* stability.margin on supports (wr_supports_margin): the distance from the
 * bias to the wrenches that move the seated part, in the fixture's force
 * unit, with the bracket proved around it. */
static bool margin_on_supports(wp_call *call, wp_fixture_use *use, wp_writer *out)
{
    const wr_fixture *f = use->fixture;
    double bias[3];
    if (!wp_wrench_read(cJSON_GetObjectItemCaseSensitive(call->params, "bias"), "params.bias", f,
                        bias, call->error))
        return false;
    /* The bias is read in the fixture's force unit; the supports' friction
     * counts in the model system (wr_support.h): converted there and back,
     * as wp_supports_answer does. */
    const double k = wr_fixture_force_factor(f);
    for (int j = 0; j < 3; j++)
        bias[j] *= k;
    wr_lp_env *env = call->host->lp_env ? call->host->lp_env(call->host->self) : NULL;
    wr_support_margin m;
    wr_status status = env ? wr_supports_margin(use->analysis, f->supports, env, bias,
                                                call->host->stop, &m)
                           : WR_LP_FAILED;
    if (status != WR_OK) {
        wp_error_status(call->error, status, status == WR_INVALID ? "params.bias" : "", "%s",
                        status == WR_INVALID ? "not finite in the model's units"
                                             : wr_strerror(status));
        return false;
    }
    wp_write_object(out);
    if (!m.bounded) {
        /* No moving mode at all: no disturbance moves the part. */
        static const char *const keys[] = {"margin", "blocking", "worst_direction", "bracket"};
        for (size_t i = 0; i < sizeof keys / sizeof keys[0]; i++) {
            wp_write_key(out, keys[i]);
            wp_write_null(out);
        }
        wp_write_object_end(out);
        return true;
    }
    wp_write_key(out, "margin");
    write_bound(out, m.margin / k);
    wp_write_key(out, "blocking");
    if (m.blocking >= 0) {
        char text[WR_CONSTRAINT_TEXT];
        wr_constraint_format(&wr_analysis_constraints(use->analysis, WR_SET_STRONG)[m.blocking],
                             text);
        wp_write_string(out, text);
    } else {
        wp_write_null(out);
    }
    wp_write_key(out, "worst_direction");
    write_vector3(out, m.worst_direction);
    wp_write_key(out, "bracket");
    wp_write_array(out);
    write_bound(out, m.bracket[0] / k);
    write_bound(out, m.bracket[1] / k);
    wp_write_array_end(out);
    wp_write_member_bool(out, "converged", m.converged);
    wp_write_object_end(out);
    return true;
}

bool wp_handle_stability_margin(wp_call *call, wp_writer *out)
{
    const cJSON *params = call->params;
    wp_error *error = call->error;
    wp_fixture_use *use = wp_call_fixture(call);
    if (!use)
        return false;
    if (use->fixture->supports)
        return margin_on_supports(call, use, out);
    double bias[3];
    wr_disturbance d;
    bool read = wp_wrench_read(cJSON_GetObjectItemCaseSensitive(params, "bias"), "params.bias",
                               use->fixture, bias, error);
    wr_status status = read ? wr_disturbance_margin(use->analysis, bias, &d) : WR_OK;
    wr_robust_answer robust = {.has_perturbation = false};
    if (status == WR_OK && read && d.bounded && use->fixture->tolerance.given)
        status = robust_margin(use->analysis, bias, &d, &robust);
    if (status == WR_LP_FAILED || status == WR_NO_MEMORY) {
        wp_error_status(error, status, "", "%s", wr_strerror(status));
        return false;
    }
    if (status != WR_OK) {
        wp_error_status(error, status, "params.bias",
                        "so large that its margin is beyond the largest number");
        return false;
    }
    if (!read)
        return false;
    wp_write_object(out);
    if (d.bounded) {
        char text[WR_CONSTRAINT_TEXT];
        wr_constraint_format(&wr_analysis_constraints(use->analysis, WR_SET_STRONG)[d.blocking],
                             text);
        wp_write_member_number(out, "margin", d.margin + 0.0);
        wp_write_member_string(out, "blocking", text);
        wp_write_key(out, "worst_direction");
        write_vector3(out, d.worst_direction);
        if (use->fixture->tolerance.given)
            write_robust_verdict(out, use->fixture, &robust);
    } else {
        /* No moving mode at all: no disturbance moves the part. */
        wp_write_key(out, "margin");
        wp_write_null(out);
        wp_write_key(out, "blocking");
        wp_write_null(out);
        wp_write_key(out, "worst_direction");
        wp_write_null(out);
    }
    wp_write_object_end(out);
    return true;
}
