/* wr_support_sweep.c -- a wrench's answer on a base plate against the
 * fixels' common mu: bisection for seating, a grid and bisection for
 * holding (wr_support_sweep.h says why). */
#include "wr_support_sweep.h"

#include <assert.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

enum { PHASE_GOAL_LOW, PHASE_GOAL_HIGH, PHASE_GOAL_BISECT, PHASE_GRID, PHASE_DONE };

struct wr_support_sweep {
    const wr_fixture *fixture; /* borrowed, with supports */
    wr_support_sweep_over over;
    wr_analysis *analysis;     /* over mu_B: the fixture's, made at the first answer */
    double wrench[3];          /* model system */
    wr_set set;
    wr_sweep_range range;
    int phase;
    /* Seating: inside at lo, not at hi (PHASE_GOAL_BISECT). */
    double lo, hi;
    /* The grid (strong, both): its points low + k step up to top (the
     * range's top, or for both the goal's end), the last one answered
     * (pos, its answer prev), a change being bisected in [a, b] (a answers
     * prev), and where the interval still open began (when prev). */
    double step, top, pos, a, b, start;
    bool prev, bisecting;
    /* Holding found at grid points and bisected ends, to certify: pieces
     * of mu, the lowest on top; each is certified held whole by the
     * relaxation, dropped when narrower than WR_SUPPORT_SWEEP_STEP, or
     * halved (certify_unit).  Every point below the lowest is decided. */
    wr_intervals pending;
    int certifications;         /* relaxed answers spent on the current candidate */
    wr_intervals intervals;
};

/* The relaxed answers one candidate interval of holding may spend; what
 * is left uncertified then is dropped (never claimed held). */
#define CERTIFY_MAX 400

/* Appends [lo, hi] to the list.  WR_NO_MEMORY. */
static wr_status append(wr_intervals *list, double lo, double hi)
{
    if (list->count == list->capacity) {
        int capacity = list->capacity ? 2 * list->capacity : 8;
        double (*items)[2] = realloc(list->items, (size_t)capacity * sizeof *items);
        if (!items)
            return WR_NO_MEMORY;
        list->items = items;
        list->capacity = capacity;
    }
    list->items[list->count][0] = lo;
    list->items[list->count][1] = hi;
    list->count++;
    return WR_OK;
}

/* Adds [lo, hi] (nothing unless hi > lo) to the sorted answer, one
 * interval with the last when they touch (certified pieces).  WR_NO_MEMORY. */
static wr_status add(wr_intervals *list, double lo, double hi)
{
    if (!(hi > lo))
        return WR_OK;
    if (list->count > 0 && list->items[list->count - 1][1] == lo) {
        list->items[list->count - 1][1] = hi;
        return WR_OK;
    }
    return append(list, lo, hi);
}

wr_status wr_support_sweep_new(const wr_fixture *fixture, const double wrench[3], wr_set set,
                               const wr_sweep_range *range, wr_support_sweep_over over,
                               wr_support_sweep **out)
{
    *out = NULL;
    if (!fixture->supports || !isfinite(wrench[0]) || !isfinite(wrench[1]) ||
        !isfinite(wrench[2]) || !(range->low >= 0 && range->low < range->high &&
                                  range->high <= WR_MAX_FRICTION) ||
        !(range->kinetic_ratio > 0 && range->kinetic_ratio <= 1))
        return WR_INVALID;
    wr_support_sweep *job = calloc(1, sizeof *job);
    if (!job)
        return WR_NO_MEMORY;
    job->fixture = fixture;
    job->over = over;
    memcpy(job->wrench, wrench, sizeof job->wrench);
    job->set = set;
    job->range = *range;
    job->step = (range->high - range->low) / WR_SUPPORT_SWEEP_GRID;
    job->phase = set == WR_SET_STRONG ? PHASE_GRID : PHASE_GOAL_LOW;
    job->top = range->high;
    job->pos = NAN; /* the grid's first point not answered yet */
    *out = job;
    return WR_OK;
}

void wr_support_sweep_free(wr_support_sweep *job)
{
    if (!job)
        return;
    wr_intervals_release(&job->intervals);
    wr_intervals_release(&job->pending);
    wr_analysis_free(job->analysis);
    free(job);
}

/* The answer for `which` (goal or strong) with every fixel's friction in
 * [lo, hi] (static, and ratio times that kinetic; a point when lo == hi:
 * wr_fixture_at_friction): the fixture placed again so, its analysis, the
 * supports' test.  Over an interval each cone is the union of the cones of
 * the friction box (docs/MODEL.md section 2, friction intervals), so
 * "inside" for strong there is held at every mu of [lo, hi]. */
static wr_status answer_with(const wr_support_sweep *job, const wr_analysis *analysis,
                             const wr_supports *supports, wr_lp_env *env, wr_set which,
                             const wr_stop *stop, bool *inside, unsigned long *cost)
{
    wr_status status;
    int solves = 0;
    if (which == WR_SET_GOAL) {
        wr_support_goal goal;
        status = wr_supports_goal(analysis, supports, env, job->wrench, WR_DEFAULT_TOLERANCE,
                                  &goal);
        *inside = goal.verdict == WR_VERDICT_INSIDE;
        solves = goal.solves;
    } else {
        wr_support_strong strong;
        status = wr_supports_strong(analysis, supports, env, job->wrench, WR_DEFAULT_TOLERANCE,
                                    stop, &strong);
        *inside = strong.verdict == WR_VERDICT_INSIDE;
        solves = strong.solves;
    }
    *cost += 1000 + 400 * (unsigned long)(solves > 0 ? solves : 0);
    return status;
}

/* Over mu_B: the fixture's own analysis (made once) and its supports with
 * mu_s in [lo, hi] and mu_k in ratio times that. */
static wr_status inside_over_supports(wr_support_sweep *job, wr_lp_env *env, double lo,
                                      double hi, wr_set which, const wr_stop *stop,
                                      bool *inside, unsigned long *cost)
{
    if (!job->analysis) {
        wr_status status = wr_analysis_new(job->fixture, &job->analysis);
        if (status != WR_OK)
            return status;
    }
    wr_supports at;
    wr_supports_with_friction(job->fixture->supports, hi, &at);
    at.mu_static_min = lo;
    at.mu_kinetic = job->range.kinetic_ratio * hi;
    at.mu_kinetic_min = job->range.kinetic_ratio * lo;
    return answer_with(job, job->analysis, &at, env, which, stop, inside, cost);
}

static wr_status inside_at(wr_support_sweep *job, wr_lp_env *env, double lo, double hi,
                           wr_set which, const wr_stop *stop, bool *inside, unsigned long *cost)
{
    if (job->over == WR_SUPPORT_SWEEP_SUPPORTS)
        return inside_over_supports(job, env, lo, hi, which, stop, inside, cost);
    wr_fixture at;
    wr_fixture_at_friction(job->fixture, hi, job->range.kinetic_ratio, &at);
    for (int i = 0; i < at.fixel_count; i++) {
        at.fixels[i].mu_static_min = lo;
        at.fixels[i].mu_kinetic_min = job->range.kinetic_ratio * lo;
    }
    wr_analysis *analysis;
    wr_status status = wr_analysis_new(&at, &analysis);
    if (status != WR_OK)
        return status;
    status = answer_with(job, analysis, at.supports, env, which, stop, inside, cost);
    wr_analysis_free(analysis);
    return status;
}

/* A candidate interval of holding [lo, hi] (its ends held at their
 * points), to certify before the grid goes on. */
static wr_status candidate(wr_support_sweep *job, double lo, double hi)
{
    if (!(hi > lo))
        return WR_OK;
    job->certifications = 0;
    job->pending.count = 0;
    return append(&job->pending, lo, hi);
}

/* One relaxed answer: the lowest pending piece held whole (certified), or
 * halved (the lower half on top), or dropped when too narrow or the
 * candidate's answers are spent. */
static wr_status certify_unit(wr_support_sweep *job, wr_lp_env *env, const wr_stop *stop,
                              unsigned long *cost)
{
    wr_intervals *p = &job->pending;
    double lo = p->items[p->count - 1][0], hi = p->items[p->count - 1][1];
    bool held;
    wr_status status = inside_at(job, env, lo, hi, WR_SET_STRONG, stop, &held, cost);
    if (status != WR_OK)
        return status;
    job->certifications++;
    p->count--;
    if (held)
        return add(&job->intervals, lo, hi);
    if (hi - lo <= WR_SUPPORT_SWEEP_STEP || job->certifications >= CERTIFY_MAX) {
        if (job->certifications >= CERTIFY_MAX)
            p->count = 0; /* the rest of the candidate left uncertified */
        return WR_OK;
    }
    double middle = lo + (hi - lo) / 2;
    status = append(p, middle, hi);
    return status == WR_OK ? append(p, lo, middle) : status;
}

/* The goal's end found: a goal job is done with [low, end], a both job
 * samples holding over [low, end] (nothing when the wrench seats at low
 * alone).  WR_OK; WR_NO_MEMORY. */
static wr_status goal_found(wr_support_sweep *job, double end)
{
    if (job->set == WR_SET_GOAL) {
        job->phase = PHASE_DONE;
        return add(&job->intervals, job->range.low, end);
    }
    job->top = end;
    job->phase = end > job->range.low ? PHASE_GRID : PHASE_DONE;
    return WR_OK;
}

/* One point answer of the seating phase: at low, at high, then the
 * middle of [lo, hi] until it is within WR_SUPPORT_SWEEP_STEP. */
static wr_status goal_unit(wr_support_sweep *job, wr_lp_env *env, const wr_stop *stop,
                           unsigned long *cost)
{
    double mu = job->phase == PHASE_GOAL_LOW    ? job->range.low
                : job->phase == PHASE_GOAL_HIGH ? job->range.high
                                                : job->lo + (job->hi - job->lo) / 2;
    bool inside;
    wr_status status = inside_at(job, env, mu, mu, WR_SET_GOAL, stop, &inside, cost);
    if (status != WR_OK)
        return status;
    if (job->phase == PHASE_GOAL_LOW) {
        job->lo = mu;
        job->phase = inside ? PHASE_GOAL_HIGH : PHASE_DONE;
        return WR_OK;
    }
    if (job->phase == PHASE_GOAL_HIGH && inside)
        return goal_found(job, mu);
    job->phase = PHASE_GOAL_BISECT;
    if (inside)
        job->lo = mu;
    else
        job->hi = mu;
    return job->hi - job->lo <= WR_SUPPORT_SWEEP_STEP ? goal_found(job, job->lo) : WR_OK;
}

/* One point answer of the grid: its first point, the next grid point, or
 * the middle of a change being bisected.  Holding for strong; for both,
 * holding too (the grid lies where the wrench seats). */
static wr_status grid_unit(wr_support_sweep *job, wr_lp_env *env, const wr_stop *stop,
                           unsigned long *cost)
{
    const double low = job->range.low;
    double mu;
    if (job->bisecting)
        mu = job->a + (job->b - job->a) / 2;
    else if (isnan(job->pos))
        mu = low;
    else {
        /* The next grid point after pos (the top the last one). */
        double k = floor((job->pos - low) / job->step + 0.5) + 1;
        mu = k >= WR_SUPPORT_SWEEP_GRID ? job->top : fmin(low + k * job->step, job->top);
    }
    bool inside;
    wr_status status = inside_at(job, env, mu, mu, WR_SET_STRONG, stop, &inside, cost);
    if (status != WR_OK)
        return status;
    if (job->bisecting) {
        if (inside == job->prev)
            job->a = mu;
        else
            job->b = mu;
        if (job->b - job->a > WR_SUPPORT_SWEEP_STEP)
            return WR_OK;
        /* The change lies in (a, b]: an interval ends at a or begins at b. */
        job->bisecting = false;
        if (job->prev) {
            status = candidate(job, job->start, job->a);
        } else {
            job->start = job->b;
        }
        job->prev = !job->prev; /* pos's answer */
    } else if (isnan(job->pos)) {
        job->pos = mu;
        job->prev = inside;
        job->start = mu;
    } else if (inside != job->prev) {
        job->bisecting = true;
        job->a = job->pos;
        job->b = mu;
        job->pos = mu;
        if (mu - job->a > WR_SUPPORT_SWEEP_STEP)
            return WR_OK;
        job->bisecting = false;
        if (job->prev)
            status = candidate(job, job->start, job->a);
        else
            job->start = mu;
        job->prev = inside;
    } else {
        job->pos = mu;
    }
    if (status == WR_OK && !job->bisecting && job->pos >= job->top) {
        job->phase = PHASE_DONE;
        if (job->prev)
            status = candidate(job, job->start, job->top);
    }
    return status;
}

wr_status wr_support_sweep_run(wr_support_sweep *job, wr_lp_env *env, unsigned long budget,
                               unsigned long *used, const wr_stop *stop, bool *done)
{
    unsigned long spent = 0;
    wr_status status = WR_OK;
    while (status == WR_OK && (job->phase != PHASE_DONE || job->pending.count > 0) &&
           (spent == 0 || spent < budget)) {
        if (wr_stop_requested(stop))
            return WR_STOPPED;
        status = job->pending.count > 0   ? certify_unit(job, env, stop, &spent)
                 : job->phase == PHASE_GRID ? grid_unit(job, env, stop, &spent)
                                            : goal_unit(job, env, stop, &spent);
    }
    if (used)
        *used += spent;
    *done = job->phase == PHASE_DONE && job->pending.count == 0;
    return status;
}

wr_status wr_support_sweep_stop(wr_support_sweep *job, double *reached)
{
    wr_status status = WR_OK;
    *reached = job->range.high;
    if (job->pending.count > 0) {
        /* Certifying: decided up to the lowest piece left. */
        *reached = job->pending.items[job->pending.count - 1][0];
        job->pending.count = 0;
    } else if (job->phase == PHASE_GRID) {
        /* Holding is claimed only where certified: an interval still open
         * is not, and nothing from its start on is decided. */
        *reached = job->bisecting ? job->a : isnan(job->pos) ? job->range.low : job->pos;
        if (!isnan(job->pos) && job->prev)
            *reached = job->start;
    } else if (job->phase != PHASE_DONE) {
        /* Seating is decided up to lo once low seats; both's holding not
         * at all yet. */
        bool seated = job->phase != PHASE_GOAL_LOW && job->set == WR_SET_GOAL;
        *reached = seated ? job->lo : job->range.low;
        if (seated)
            status = add(&job->intervals, job->range.low, job->lo);
    }
    job->phase = PHASE_DONE;
    return status;
}

const wr_intervals *wr_support_sweep_intervals(const wr_support_sweep *job)
{
    assert(job->phase == PHASE_DONE);
    return &job->intervals;
}

bool wr_support_sweep_exact(const wr_support_sweep *job)
{
    return job->set == WR_SET_GOAL;
}

double wr_support_sweep_resolution(const wr_support_sweep *job)
{
    return job->set == WR_SET_GOAL ? 0 : job->step;
}
