/* wr_classify.c -- the analysis of a fixture and the answers of
 * docs/MODEL.md section 5: verdict, margin, blocking cone, witness. */
#include "wr_classify.h"
#include "wr_internal.h"

#include <assert.h>
#include <stdlib.h>
#include <string.h>

static wr_status build_cones(const wr_fixture *fixture, const wr_constraint *constraints,
                             int count, wr_cone **cones)
{
    *cones = calloc((size_t)(count > 0 ? count : 1), sizeof **cones);
    if (!*cones)
        return WR_NO_MEMORY;
    for (int i = 0; i < count; i++) {
        wr_status status = wr_cone_build(&(*cones)[i], fixture, &constraints[i]);
        if (status != WR_OK)
            return status;
    }
    return WR_OK;
}

/* `shared` (NULL: none) marks the cones that are a frame's, not to free. */
static void release_cones(wr_cone *cones, int count, const bool *shared)
{
    if (!cones)
        return;
    for (int i = 0; i < count; i++)
        if (!shared || !shared[i])
            wr_cone_release(&cones[i]);
    free(cones);
}

wr_status wr_analysis_goal_new(const wr_fixture *fixture, const wr_plan *plan,
                               wr_analysis **out)
{
    *out = NULL;
    assert(!plan || plan->fixel_count == fixture->fixel_count);
    wr_analysis *a = calloc(1, sizeof *a);
    if (!a)
        return WR_NO_MEMORY;
    a->fixture = fixture;
    wr_status status = WR_OK;
    if (plan) {
        /* Only read: the cast keeps the struct's one field type. */
        a->plan = (wr_plan *)plan;
        a->plan_borrowed = true;
    } else {
        status = wr_plan_new(fixture->fixel_count, &a->plan);
    }
    if (status == WR_OK)
        status = build_cones(fixture, a->plan->kept, a->plan->kept_count, &a->goal_cones);
    if (status != WR_OK) {
        wr_analysis_free(a);
        return status;
    }
    *out = a;
    return WR_OK;
}

wr_status wr_analysis_complete(wr_analysis *a)
{
    if (a->complete)
        return WR_OK;
    wr_status status = wr_modes_find(a->fixture, &a->modes, &a->mode_count, &a->pinned);
    if (status == WR_OK)
        status = build_cones(a->fixture, a->modes, a->mode_count, &a->mode_cones);
    if (status != WR_OK) {
        release_cones(a->mode_cones, a->mode_count, NULL);
        free(a->modes);
        a->mode_cones = NULL;
        a->modes = NULL;
        a->mode_count = 0;
        return status;
    }
    a->complete = true;
    return WR_OK;
}

wr_status wr_analysis_new(const wr_fixture *fixture, wr_analysis **out)
{
    wr_status status = wr_analysis_goal_new(fixture, NULL, out);
    if (status == WR_OK && (status = wr_analysis_complete(*out)) != WR_OK) {
        wr_analysis_free(*out);
        *out = NULL;
    }
    return status;
}

void wr_analysis_free(wr_analysis *analysis)
{
    if (!analysis)
        return;
    release_cones(analysis->goal_cones, analysis->plan ? analysis->plan->kept_count : 0,
                  analysis->goal_shared);
    release_cones(analysis->mode_cones, analysis->mode_count, analysis->modes_shared);
    if (!analysis->modes_borrowed)
        free(analysis->modes);
    if (!analysis->plan_borrowed)
        wr_plan_free(analysis->plan);
    free(analysis);
}

/* ---- the analysis at any friction (wr_internal.h) ------------------------------- */

/* The acceleration generators of one set's cones, packed: cone i's are
 * generators[first[i] .. first[i] + count[i]), count -1 for an empty cone. */
typedef struct frame_cones {
    int *first, *count;
    double (*generators)[3];
    /* A cone with no friction edge (no l, r, n or m) is the same at every
     * coefficient: built once, shared by every analysis. */
    bool *shared;
    wr_cone *cones; /* the shared ones built, the others zero */
} frame_cones;

struct wr_analysis_frame {
    wr_plan *plan;
    bool strong;             /* the modes and their cones' generators are here */
    bool pinned;
    int mode_count;
    wr_constraint *modes;
    frame_cones goal, modes_cones;
};

static void frame_cones_release(frame_cones *c, int n)
{
    free(c->first);
    free(c->count);
    free(c->generators);
    for (int i = 0; c->cones && i < n; i++)
        wr_cone_release(&c->cones[i]);
    free(c->cones);
    free(c->shared);
}

static bool has_friction_edge(const wr_constraint *constraint)
{
    for (int i = 0; i < constraint->length; i++)
        if (strchr("lrnm", constraint->letters[i]))
            return true;
    return false;
}

static wr_status frame_cones_make(const wr_fixture *fixture, const wr_constraint *constraints,
                                  int n, frame_cones *out)
{
    out->first = malloc((size_t)(n + 1) * sizeof *out->first);
    out->count = malloc((size_t)(n + 1) * sizeof *out->count);
    int capacity = 4 * n + 16, used = 0;
    out->generators = malloc((size_t)capacity * sizeof *out->generators);
    out->shared = calloc((size_t)(n + 1), sizeof *out->shared);
    out->cones = calloc((size_t)(n + 1), sizeof *out->cones);
    if (!out->first || !out->count || !out->generators || !out->shared || !out->cones)
        return WR_NO_MEMORY;
    for (int i = 0; i < n; i++) {
        double generators[WR_HULL_MAX][3];
        int count = wr_cone_acceleration(fixture, &constraints[i], generators);
        if (used + (count > 0 ? count : 0) > capacity) {
            capacity = 2 * capacity + WR_HULL_MAX;
            double (*grown)[3] = realloc(out->generators, (size_t)capacity * sizeof *grown);
            if (!grown)
                return WR_NO_MEMORY;
            out->generators = grown;
        }
        out->first[i] = used;
        out->count[i] = count;
        if (count > 0) {
            memcpy(out->generators + used, generators, (size_t)count * sizeof generators[0]);
            used += count;
        }
        if (!has_friction_edge(&constraints[i])) {
            wr_status status = wr_cone_build_from(&out->cones[i], fixture, &constraints[i],
                                                  (const double (*)[3])generators, count);
            if (status != WR_OK)
                return status;
            out->shared[i] = true;
        }
    }
    return WR_OK;
}

void wr_analysis_frame_free(wr_analysis_frame *frame)
{
    if (!frame)
        return;
    /* The goal cones are counted by the plan: released before it. */
    frame_cones_release(&frame->goal, frame->plan ? frame->plan->kept_count : 0);
    wr_plan_free(frame->plan);
    frame_cones_release(&frame->modes_cones, frame->mode_count);
    free(frame->modes);
    free(frame);
}

wr_status wr_analysis_frame_new(const wr_fixture *fixture, bool strong, wr_analysis_frame **out)
{
    *out = NULL;
    wr_analysis_frame *frame = calloc(1, sizeof *frame);
    if (!frame)
        return WR_NO_MEMORY;
    frame->strong = strong;
    wr_status status = wr_plan_new(fixture->fixel_count, &frame->plan);
    if (status == WR_OK)
        status = frame_cones_make(fixture, frame->plan->kept, frame->plan->kept_count,
                                  &frame->goal);
    if (status == WR_OK && strong)
        status = wr_modes_find(fixture, &frame->modes, &frame->mode_count, &frame->pinned);
    if (status == WR_OK && strong)
        status = frame_cones_make(fixture, frame->modes, frame->mode_count, &frame->modes_cones);
    if (status != WR_OK) {
        wr_analysis_frame_free(frame);
        return status;
    }
    *out = frame;
    return WR_OK;
}

static wr_status frame_cones_build(const wr_fixture *at, const wr_constraint *constraints, int n,
                                   const frame_cones *c, wr_cone **cones)
{
    *cones = calloc((size_t)(n > 0 ? n : 1), sizeof **cones);
    if (!*cones)
        return WR_NO_MEMORY;
    for (int i = 0; i < n; i++) {
        if (c->shared[i]) {
            (*cones)[i] = c->cones[i];
            continue;
        }
        wr_status status = wr_cone_build_from(&(*cones)[i], at, &constraints[i],
                                              (const double (*)[3])(c->generators + c->first[i]),
                                              c->count[i]);
        if (status != WR_OK)
            return status;
    }
    return WR_OK;
}

wr_status wr_analysis_frame_at(const wr_analysis_frame *frame, const wr_fixture *at, bool strong,
                               wr_analysis **out)
{
    *out = NULL;
    assert(frame->plan->fixel_count == at->fixel_count);
    wr_analysis *a = calloc(1, sizeof *a);
    if (!a)
        return WR_NO_MEMORY;
    a->fixture = at;
    a->plan = frame->plan;
    a->plan_borrowed = true;
    a->goal_shared = frame->goal.shared;
    wr_status status =
        frame_cones_build(at, a->plan->kept, a->plan->kept_count, &frame->goal, &a->goal_cones);
    if (status == WR_OK && strong && frame->strong) {
        a->modes = frame->modes;
        a->modes_borrowed = true;
        a->modes_shared = frame->modes_cones.shared;
        a->mode_count = frame->mode_count;
        a->pinned = frame->pinned;
        status = frame_cones_build(at, a->modes, a->mode_count, &frame->modes_cones,
                                   &a->mode_cones);
        a->complete = status == WR_OK;
    }
    if (status != WR_OK) {
        wr_analysis_free(a);
        return status;
    }
    *out = a;
    return WR_OK;
}

static size_t cones_bytes(const wr_cone *cones, int count)
{
    size_t bytes = (size_t)count * sizeof *cones;
    for (int i = 0; i < count; i++) {
        const wr_cone *c = &cones[i];
        bytes += (size_t)(c->facet_count + c->ray_count + c->generator_count) * sizeof(double[3]) +
                 (size_t)c->generator_count * sizeof(wr_generator_origin) +
                 (size_t)c->facet_count * sizeof(bool);
    }
    return bytes;
}

size_t wr_analysis_bytes(const wr_analysis *a)
{
    const wr_plan *p = a->plan;
    return sizeof *a + sizeof *p + (size_t)p->state_count * sizeof *p->states +
           (size_t)p->excluded_total * sizeof *p->excluded +
           (size_t)p->kept_count * (sizeof *p->kept + sizeof *p->origins) +
           (size_t)a->mode_count * sizeof *a->modes + cones_bytes(a->goal_cones, p->kept_count) +
           cones_bytes(a->mode_cones, a->mode_count);
}

const wr_fixture *wr_analysis_fixture(const wr_analysis *analysis) { return analysis->fixture; }

const wr_plan *wr_analysis_plan(const wr_analysis *analysis) { return analysis->plan; }

bool wr_analysis_pinned(const wr_analysis *analysis) { return analysis->pinned; }

int wr_analysis_cone_count(const wr_analysis *analysis, wr_set set)
{
    return set == WR_SET_GOAL ? analysis->plan->kept_count : analysis->mode_count;
}

const wr_cone *wr_analysis_cone(const wr_analysis *analysis, wr_set set, int index)
{
    return set == WR_SET_GOAL ? &analysis->goal_cones[index] : &analysis->mode_cones[index];
}

const wr_constraint *wr_analysis_constraints(const wr_analysis *analysis, wr_set set)
{
    return set == WR_SET_GOAL ? analysis->plan->kept : analysis->modes;
}

/* A lower bound on the distance from x to the cone's closure: the largest
 * violation of a facet or equality.  <= 0 means x is in the closure. */
static double distance_bound(const wr_cone *cone, const double x[3])
{
    double bound = -INFINITY;
    for (int i = 0; i < cone->facet_count; i++)
        bound = fmax(bound, wr_dot3(cone->facets[i], x));
    for (int i = 0; i < cone->equality_count; i++)
        bound = fmax(bound, fabs(wr_dot3(cone->equalities[i], x)));
    return bound;
}

/* Margin of unit x for one set: minus the largest depth when x is in some
 * excluded cone, else the smallest distance; 1 with no cone at all. */
double wr_set_margin(const wr_analysis *a, int set, const double x[3], int *blocking)
{
    int count = wr_analysis_cone_count(a, (wr_set)set);
    double deepest = -1;
    int deepest_index = -1;
    for (int i = 0; i < count; i++) {
        const wr_cone *cone = wr_analysis_cone(a, (wr_set)set, i);
        if (cone->empty || distance_bound(cone, x) > 0)
            continue;
        /* Inside: for a full cone the depth is the smallest facet distance
         * (the whole space: |x| = 1); a thinner cone has no interior. */
        double depth = cone->dimension < 3 ? 0
                       : cone->facet_count == 0 ? 1
                                                : -distance_bound(cone, x);
        if (depth > deepest) {
            deepest = depth;
            deepest_index = i;
        }
    }
    if (deepest_index >= 0) {
        *blocking = deepest_index;
        return -fmin(deepest, 1);
    }
    double nearest = INFINITY;
    int nearest_index = -1;
    for (int i = 0; i < count; i++) {
        const wr_cone *cone = wr_analysis_cone(a, (wr_set)set, i);
        if (cone->empty || distance_bound(cone, x) >= nearest)
            continue;
        double d = wr_cone_signed_distance(cone, x, NULL);
        if (d < nearest) {
            nearest = d;
            nearest_index = i;
        }
    }
    *blocking = nearest_index;
    return nearest_index < 0 ? 1 : fmin(nearest, 1);
}

static wr_verdict verdict_of(double margin, double tolerance)
{
    if (margin > tolerance)
        return WR_VERDICT_INSIDE;
    if (margin < -tolerance)
        return WR_VERDICT_OUTSIDE;
    return WR_VERDICT_BOUNDARY;
}

static bool finite3(const double v[3])
{
    return isfinite(v[0]) && isfinite(v[1]) && isfinite(v[2]);
}

/* docs/MODEL.md section 5: the zero wrench seats nothing, and is held unless some
 * moving mode admits it.  Its margin is 0 either way. */
static void classify_zero(const wr_analysis *a, wr_set set, wr_answer *answer)
{
    answer->has_margin = true;
    answer->margin = 0;
    if (set != WR_SET_STRONG) {
        answer->verdict = WR_VERDICT_OUTSIDE;
        answer->blocking_set = WR_SET_GOAL;
        answer->blocking = a->plan->kept_count > 0 ? 0 : -1;
        return;
    }
    answer->blocking_set = WR_SET_STRONG;
    answer->verdict = WR_VERDICT_INSIDE;
    answer->blocking = -1;
    for (int i = 0; i < a->mode_count; i++)
        if (a->mode_cones[i].zero_admitted) {
            answer->verdict = WR_VERDICT_OUTSIDE;
            answer->blocking = i;
            return;
        }
}

/* The verdict of unit x for one set, as verdict_of(wr_set_margin(...))
 * gives it, from the same formulas but no more of them than it needs: a
 * cone whose facet bound is beyond the tolerance cannot bring the margin
 * within it, and the depth in a cone x is in is the bound itself. */
wr_verdict wr_set_verdict(const wr_analysis *a, int set, const double x[3], double tolerance)
{
    /* A distance is at least its bound, up to rounding in the projection
     * that computes it: |y|^2 - t^2 to an edge ray loses half the digits,
     * so a distance below about 1e-8 may come out 0.  Cones this close to
     * the band are measured. */
    const double reach = tolerance + WR_VERDICT_REACH;
    int count = wr_analysis_cone_count(a, (wr_set)set);
    double deepest = -1;
    bool near = false;
    for (int i = 0; i < count; i++) {
        const wr_cone *cone = wr_analysis_cone(a, (wr_set)set, i);
        if (cone->empty)
            continue;
        double bound = distance_bound(cone, x);
        if (bound > 0) {
            near = near || bound <= reach;
            continue;
        }
        double depth = cone->dimension < 3 ? 0 : cone->facet_count == 0 ? 1 : -bound;
        if (fmin(depth, 1) > tolerance)
            return WR_VERDICT_OUTSIDE; /* deeper than the band in this cone: the margin is too */
        deepest = fmax(deepest, depth);
    }
    if (deepest >= 0)
        return verdict_of(-fmin(deepest, 1), tolerance);
    if (!near)
        return WR_VERDICT_INSIDE; /* every distance is at least its bound, above the band */
    /* Outside every cone, some within reach of the band by its bound: the
     * margin itself decides, computed as wr_classify computes it (tiny
     * distances are rounded, and which cones it measures depends on the
     * order it meets them, so nothing else would agree to the last case). */
    int blocking;
    return verdict_of(wr_set_margin(a, set, x, &blocking), tolerance);
}

wr_status wr_classify_verdict(const wr_analysis *a, const double wrench[3], wr_set set,
                              double tolerance, wr_verdict *verdict)
{
    if (!finite3(wrench) || !(tolerance >= 0))
        return WR_INVALID;
    double x[3];
    double scale = wr_fixture_unit_wrench(a->fixture, wrench, x);
    if (!(scale > 0)) {
        wr_answer answer;
        classify_zero(a, set, &answer);
        *verdict = answer.verdict;
        return WR_OK;
    }
    if (set != WR_SET_BOTH) {
        *verdict = wr_set_verdict(a, set, x, tolerance);
        return WR_OK;
    }
    /* Both: the smaller margin; outside when either is, inside when both are. */
    wr_verdict goal = wr_set_verdict(a, WR_SET_GOAL, x, tolerance);
    if (goal == WR_VERDICT_OUTSIDE) {
        *verdict = goal;
        return WR_OK;
    }
    wr_verdict strong = wr_set_verdict(a, WR_SET_STRONG, x, tolerance);
    *verdict = strong == WR_VERDICT_OUTSIDE ? strong
               : goal == WR_VERDICT_INSIDE  ? strong
                                            : goal;
    return WR_OK;
}

/* wr_classify, and wr_classify_margin when `witness` is false. */
static wr_status classify(const wr_analysis *a, const double wrench[3], wr_set set,
                          double tolerance, bool witness, wr_answer *answer)
{
    memset(answer, 0, sizeof *answer);
    answer->blocking = -1;
    if (!finite3(wrench) || !(tolerance >= 0))
        return WR_INVALID;
    double x[3];
    double scale = wr_fixture_unit_wrench(a->fixture, wrench, x);
    if (!(scale > 0)) {
        classify_zero(a, set, answer);
        return WR_OK;
    }

    int goal_blocking = -1, strong_blocking = -1;
    double goal_margin = 1, strong_margin = 1;
    if (set != WR_SET_STRONG)
        goal_margin = wr_set_margin(a, WR_SET_GOAL, x, &goal_blocking);
    if (set != WR_SET_GOAL)
        strong_margin = wr_set_margin(a, WR_SET_STRONG, x, &strong_blocking);
    bool goal_decides = set == WR_SET_GOAL || (set == WR_SET_BOTH && goal_margin <= strong_margin);
    answer->has_margin = true;
    answer->margin = goal_decides ? goal_margin : strong_margin;
    answer->blocking_set = goal_decides ? WR_SET_GOAL : WR_SET_STRONG;
    answer->verdict = verdict_of(answer->margin, tolerance);
    if (answer->verdict == WR_VERDICT_INSIDE)
        return WR_OK;
    answer->blocking = goal_decides ? goal_blocking : strong_blocking;
    if (answer->blocking >= 0 && witness) {
        const wr_cone *cone = wr_analysis_cone(a, answer->blocking_set, answer->blocking);
        /* The witness of the unit wrench, scaled back: the same numbers as
         * for g itself (cones are cones), and overflow only ever reaches
         * the results, never the decomposition. */
        double projection[3];
        wr_cone_signed_distance(cone, x, projection);
        wr_witness *w = &answer->witness;
        wr_cone_witness(cone, a->fixture, projection, w);
        const wr_fixture *f = a->fixture;
        for (int k = 0; k < 3; k++) {
            w->acceleration[k] = wr_fixture_scale_back(f, wrench, scale, w->acceleration[k]);
            w->wrench[k] = wr_fixture_scale_back(f, wrench, scale, w->wrench[k]);
        }
        for (int i = 0; i < f->fixel_count; i++)
            for (int k = 0; k < 2; k++)
                w->force[i][k] = wr_fixture_scale_back(f, wrench, scale, w->force[i][k]);
    }
    return WR_OK;
}

wr_status wr_classify(const wr_analysis *a, const double wrench[3], wr_set set,
                      double tolerance, wr_answer *answer)
{
    return classify(a, wrench, set, tolerance, true, answer);
}

wr_status wr_classify_margin(const wr_analysis *a, const double wrench[3], wr_set set,
                             double tolerance, wr_answer *answer)
{
    return classify(a, wrench, set, tolerance, false, answer);
}

wr_status wr_analysis_lp_sets(const wr_analysis *a, wr_lp_env *env, wr_lp_set **goal,
                              wr_lp_set **strong)
{
    wr_status status = wr_lp_set_new(env, a->fixture, a->plan->kept, a->plan->kept_count, goal);
    wr_status other = wr_lp_set_new(env, a->fixture, a->modes, a->mode_count, strong);
    if (status == WR_OK)
        status = other;
    if (status != WR_OK) {
        wr_lp_set_free(*goal);
        wr_lp_set_free(*strong);
        *goal = *strong = NULL;
    }
    return status;
}

/* The first excluded cone holding g, by LP; -1 if none. */
static int first_member(wr_lp_set *lp, int count, const double wrench[3], wr_witness *witness,
                        wr_status *status)
{
    for (int i = 0; i < count; i++) {
        bool member = false;
        *status = wr_lp_member(lp, i, wrench, &member, witness);
        if (*status != WR_OK)
            return -1;
        if (member)
            return i;
    }
    return -1;
}

wr_status wr_classify_lp(const wr_analysis *a, wr_lp_set *goal, wr_lp_set *strong,
                         const double wrench[3], wr_set set, wr_answer *answer)
{
    memset(answer, 0, sizeof *answer);
    answer->blocking = -1;
    if (!finite3(wrench))
        return WR_INVALID;
    wr_status status = WR_OK;
    if (set != WR_SET_STRONG) {
        answer->blocking_set = WR_SET_GOAL;
        answer->blocking = first_member(goal, a->plan->kept_count, wrench, &answer->witness,
                                        &status);
    }
    if (status == WR_OK && answer->blocking < 0 && set != WR_SET_GOAL) {
        answer->blocking_set = WR_SET_STRONG;
        answer->blocking = first_member(strong, a->mode_count, wrench, &answer->witness, &status);
    }
    if (status != WR_OK)
        return status;
    answer->verdict = answer->blocking < 0 ? WR_VERDICT_INSIDE : WR_VERDICT_OUTSIDE;
    if (answer->blocking < 0)
        memset(&answer->witness, 0, sizeof answer->witness);
    return WR_OK;
}
