/* wr_robust_sweep.c -- robust push regions, gravity arcs and least forces
 * against a common mu (wr_robust_sweep.h says what is proved and why). */
#include "wr_robust_sweep.h"

#include "wr_finger.h"
#include "wr_internal.h"

#include <assert.h>
#include <stdlib.h>
#include <string.h>

/* A robust answer at one exact mu: its regions (kept: the pushes a piece's
 * proof tries) and their total length. */
typedef struct sample {
    double mu;
    double length;
    wr_regions regions;
} sample;

typedef struct piece {
    double m0, m1;
    int depth;
} piece;

struct wr_robust_sweep {
    const wr_fixture *fixture; /* borrowed */
    wr_set set;
    wr_sweep_range range;
    bool gravity;
    wr_finger finger;
    wr_intervals nominal;      /* owned copy */
    /* Samples, increasing in mu (grid points and pieces' middles). */
    sample *samples;
    int sample_count, sample_capacity;
    /* The nominal interval under way; its grid points are sampled first
     * (next_grid the next), then its pieces bisected from the stack. */
    int interval;
    int next_grid;
    bool bisecting;
    piece stack[2 * WR_ROBUST_DEPTH + 2];
    int top;
    wr_intervals kept;         /* the pieces proved, joined */
    unsigned long work;
    bool done;
};

/* The boxes of one LP are about this many of a server's work units. */
#define BOX_WORK 40

static double grid_mu(const wr_robust_sweep *job, int i)
{
    const wr_sweep_range *r = &job->range;
    return i == WR_ROBUST_SWEEP_GRID ? r->high
                                     : r->low + (r->high - r->low) * i / WR_ROBUST_SWEEP_GRID;
}

/* The fixture with mu_s in [m0, m1] and mu_k in ratio [m0, m1] on every
 * fixel (a point when m0 == m1): a shallow copy, as wr_fixture_at_friction
 * makes, the same fixture wr_fixture_place makes of its fixels with that
 * friction (only the coefficients differ); the tolerance is kept. */
static void at_friction(const wr_fixture *f, double m0, double m1, double ratio, wr_fixture *out)
{
    wr_fixture_at_friction(f, m1, ratio, out);
    for (int i = 0; i < out->fixel_count; i++) {
        out->fixels[i].mu_static_min = m0;
        out->fixels[i].mu_kinetic_min = ratio * m0;
    }
}

wr_status wr_robust_sweep_new(const wr_fixture *fixture, wr_set set, const wr_sweep_range *range,
                              bool gravity, const wr_finger *finger, const wr_intervals *nominal,
                              wr_robust_sweep **out)
{
    *out = NULL;
    if (!fixture->tolerance.given || (!gravity && (!finger || finger->friction != 0)))
        return WR_INVALID;
    wr_robust_sweep *job = calloc(1, sizeof *job);
    if (!job)
        return WR_NO_MEMORY;
    job->fixture = fixture;
    job->set = set;
    job->range = *range;
    job->gravity = gravity;
    if (!gravity)
        job->finger = *finger;
    for (int i = 0; i < nominal->count; i++)
        if (!wr_intervals_append(&job->nominal, nominal->items[i][0], nominal->items[i][1])) {
            wr_robust_sweep_free(job);
            return WR_NO_MEMORY;
        }
    *out = job;
    return WR_OK;
}

void wr_robust_sweep_free(wr_robust_sweep *job)
{
    if (!job)
        return;
    for (int i = 0; i < job->sample_count; i++)
        wr_regions_release(&job->samples[i].regions);
    free(job->samples);
    wr_intervals_release(&job->nominal);
    wr_intervals_release(&job->kept);
    free(job);
}

unsigned long wr_robust_sweep_work(const wr_robust_sweep *job) { return job->work; }

/* The robust regions at exact mu, as push.regions or gravity.sweep answers
 * them over a tolerance: the nominal ones' robust part. */
static wr_status robust_at(wr_robust_sweep *job, double mu, const wr_stop *stop, wr_regions *out)
{
    memset(out, 0, sizeof *out);
    wr_fixture at;
    at_friction(job->fixture, mu, mu, job->range.kinetic_ratio, &at);
    wr_analysis *analysis = NULL;
    wr_robust *robust = NULL;
    wr_regions nominal = {0};
    wr_status status = wr_analysis_new(&at, &analysis);
    if (status == WR_OK)
        status = job->gravity ? wr_gravity_sweep(analysis, job->set, &nominal)
                              : wr_push_regions_finger(analysis, job->set, &job->finger, stop,
                                                       &nominal);
    if (status == WR_OK && nominal.count > 0)
        status = wr_robust_new(analysis, WR_ROBUST_SWEEP_BUDGET, &robust);
    if (status == WR_OK && nominal.count > 0)
        status = wr_robust_regions(robust, job->set, &nominal, job->gravity, stop, out);
    job->work += BOX_WORK * (unsigned long)(1 + 64 * nominal.count);
    wr_regions_release(&nominal);
    wr_robust_free(robust);
    wr_analysis_free(analysis);
    return status;
}

/* Sample mu (one unit): its robust regions, kept in order. */
static wr_status add_sample(wr_robust_sweep *job, double mu, const wr_stop *stop)
{
    if (job->sample_count == job->sample_capacity) {
        int capacity = job->sample_capacity ? 2 * job->sample_capacity : 64;
        sample *grown = realloc(job->samples, sizeof *grown * (size_t)capacity);
        if (!grown)
            return WR_NO_MEMORY;
        job->samples = grown;
        job->sample_capacity = capacity;
    }
    sample s = {.mu = mu};
    wr_status status = robust_at(job, mu, stop, &s.regions);
    if (status != WR_OK)
        return status;
    for (int i = 0; i < s.regions.count; i++)
        s.length += job->gravity ? s.regions.items[i].t1 - s.regions.items[i].t0
                                 : wr_region_length(job->fixture, &s.regions.items[i]);
    int at = job->sample_count;
    while (at > 0 && job->samples[at - 1].mu > mu)
        at--;
    memmove(job->samples + at + 1, job->samples + at,
            sizeof *job->samples * (size_t)(job->sample_count - at));
    job->samples[at] = s;
    job->sample_count++;
    return WR_OK;
}

static bool sampled(const wr_robust_sweep *job, double mu)
{
    for (int i = 0; i < job->sample_count; i++)
        if (job->samples[i].mu == mu)
            return true;
    return false;
}

/* Is some push of the candidates robustly inside for every mu of the piece
 * and every fixture of the set (one unit)? */
static wr_status prove_piece(wr_robust_sweep *job, const piece *p, const int *candidates,
                             int count, const wr_stop *stop, bool *proved)
{
    *proved = false;
    wr_fixture at;
    at_friction(job->fixture, p->m0, p->m1, job->range.kinetic_ratio, &at);
    wr_analysis *analysis = NULL;
    wr_robust *robust = NULL;
    wr_status status = wr_analysis_new(&at, &analysis);
    if (status == WR_OK)
        status = wr_robust_new(analysis, WR_ROBUST_SWEEP_BUDGET, &robust);
    for (int c = 0; status == WR_OK && c < count && !*proved; c++) {
        const wr_regions *regions = &job->samples[candidates[c]].regions;
        status = wr_robust_regions_meet(robust, job->set, regions, job->gravity,
                                        WR_ROBUST_SWEEP_MEET_DEPTH, stop, proved);
        job->work += BOX_WORK * (unsigned long)(8 * regions->count);
    }
    wr_robust_free(robust);
    wr_analysis_free(analysis);
    return status;
}

static void split(wr_robust_sweep *job, const piece *p)
{
    if (p->depth >= WR_ROBUST_DEPTH)
        return; /* the finest piece not kept: given up */
    /* Left piece on top, so that pieces come out in order. */
    double mid = 0.5 * (p->m0 + p->m1);
    job->stack[job->top++] = (piece){mid, p->m1, p->depth + 1};
    job->stack[job->top++] = (piece){p->m0, mid, p->depth + 1};
}

/* The next step for the piece on top of the stack: *unit set when a unit
 * of work was done (a sample or a proof), else the piece was split or given
 * up at no cost. */
static wr_status piece_step(wr_robust_sweep *job, const wr_stop *stop, bool *unit)
{
    *unit = false;
    assert(job->top > 0 && job->bisecting);
    piece p = job->stack[job->top - 1];
    const double middle = 0.5 * (p.m0 + p.m1);
    /* The samples in the piece: one empty forbids keeping it whole; the
     * non-empty ones nearest the middle and each end are the candidates. */
    int first = -1, last = -1, nearest = -1, before = -1, after = -1;
    bool empty_inside = false;
    for (int i = 0; i < job->sample_count && !empty_inside; i++) {
        const sample *s = &job->samples[i];
        if (s->mu < p.m0)
            before = i;
        else if (s->mu > p.m1)
            after = after < 0 ? i : after;
        else if (s->length == 0)
            empty_inside = true;
        else {
            first = first < 0 ? i : first;
            last = i;
            if (nearest < 0 || fabs(s->mu - middle) < fabs(job->samples[nearest].mu - middle))
                nearest = i;
        }
    }
    if (empty_inside) {
        job->top--;
        split(job, &p);
        return WR_OK;
    }
    if (first < 0) {
        /* Between two empty samples: given up (the resolution).  The
         * nominal interval's ends inside the range count as empty ones:
         * the nominal region appears or vanishes there. */
        const double *nominal = job->nominal.items[job->interval];
        bool empty_before = before >= 0 && job->samples[before].mu >= nominal[0]
                                ? job->samples[before].length == 0
                                : nominal[0] > job->range.low;
        bool empty_after = after >= 0 && job->samples[after].mu <= nominal[1]
                               ? job->samples[after].length == 0
                               : nominal[1] < job->range.high;
        if (empty_before && empty_after) {
            job->top--;
            return WR_OK;
        }
        *unit = true;
        return add_sample(job, middle, stop); /* the piece is looked at again */
    }
    /* The middle's first: nearest the pushes the whole piece needs. */
    int order[3] = {nearest}, n = 1;
    if (first != nearest)
        order[n++] = first;
    if (last != nearest && last != first)
        order[n++] = last;
    *unit = true;
    job->top--;
    bool proved;
    wr_status status = prove_piece(job, &p, order, n, stop, &proved);
    if (status != WR_OK)
        return status;
    if (proved)
        return wr_intervals_append(&job->kept, p.m0, p.m1) ? WR_OK : WR_NO_MEMORY;
    split(job, &p);
    return WR_OK;
}

wr_status wr_robust_sweep_run(wr_robust_sweep *job, const wr_stop *stop, bool *done)
{
    for (;;) {
        if (job->interval == job->nominal.count) {
            job->done = true;
            *done = true;
            return WR_OK;
        }
        *done = false;
        if (wr_stop_requested(stop))
            return WR_STOPPED;
        const double a = job->nominal.items[job->interval][0];
        const double b = job->nominal.items[job->interval][1];
        if (!job->bisecting) {
            /* The grid's points in [a, b] first, a unit each. */
            while (job->next_grid <= WR_ROBUST_SWEEP_GRID && grid_mu(job, job->next_grid) < a)
                job->next_grid++;
            if (job->next_grid <= WR_ROBUST_SWEEP_GRID && grid_mu(job, job->next_grid) <= b) {
                double mu = grid_mu(job, job->next_grid++);
                if (!sampled(job, mu))
                    return add_sample(job, mu, stop);
                continue;
            }
            job->bisecting = true;
            job->top = 0;
            job->stack[job->top++] = (piece){a, b, 0};
        }
        if (job->top == 0) {
            job->interval++;
            job->bisecting = false;
            continue;
        }
        bool unit;
        wr_status status = piece_step(job, stop, &unit);
        if (status != WR_OK || unit)
            return status;
    }
}

double wr_robust_sweep_reached(const wr_robust_sweep *job)
{
    if (job->done)
        return job->range.high;
    if (job->interval == job->nominal.count)
        return job->range.high;
    if (job->bisecting && job->top > 0)
        return job->stack[job->top - 1].m0;
    return job->bisecting ? job->nominal.items[job->interval][1]
                          : job->nominal.items[job->interval][0];
}

static bool inside_nominal(const wr_robust_sweep *job, double mu)
{
    for (int i = 0; i < job->nominal.count; i++)
        if (mu >= job->nominal.items[i][0] && mu <= job->nominal.items[i][1])
            return true;
    return false;
}

wr_status wr_robust_sweep_curve(const wr_robust_sweep *job, double top, wr_sweep_curve *out)
{
    memset(out, 0, sizeof *out);
    const wr_sweep_range *r = &job->range;
    for (int i = 0; i < job->kept.count && job->kept.items[i][0] < top; i++)
        if (!wr_intervals_append(&out->intervals, job->kept.items[i][0],
                                 fmin(job->kept.items[i][1], top)))
            goto no_memory;
    if (top >= r->high) {
        const wr_intervals *k = &out->intervals;
        out->has_critical = k->count == 0 || k->items[k->count - 1][1] < r->high;
        out->critical = k->count == 0 ? r->low : k->items[k->count - 1][1];
    }
    /* The samples and the grid's points outside the nominal intervals (0
     * there: the nominal fixture is one of the set), merged in order. */
    int most = job->sample_count + WR_ROBUST_SWEEP_GRID + 1;
    out->points = malloc(sizeof *out->points * (size_t)most);
    if (!out->points)
        goto no_memory;
    int s = 0;
    for (int g = 0; g <= WR_ROBUST_SWEEP_GRID + 1; g++) {
        double mu = g <= WR_ROBUST_SWEEP_GRID ? grid_mu(job, g) : INFINITY;
        for (; s < job->sample_count && job->samples[s].mu <= mu; s++)
            if (job->samples[s].mu <= top) {
                out->points[out->point_count][0] = job->samples[s].mu;
                out->points[out->point_count++][1] = job->samples[s].length;
            }
        if (g <= WR_ROBUST_SWEEP_GRID && mu <= top && !inside_nominal(job, mu)) {
            out->points[out->point_count][0] = mu;
            out->points[out->point_count++][1] = 0;
        }
    }
    out->exact = false;
    out->resolution = (r->high - r->low) / WR_ROBUST_SWEEP_GRID;
    return WR_OK;
no_memory:
    wr_sweep_curve_release(out);
    memset(out, 0, sizeof *out);
    return WR_NO_MEMORY;
}

/* ---- the least push force ---------------------------------------------- */

/* As push.force over a tolerance: ROBUST_FORCE_BUDGET boxes per cone. */
#define ROBUST_FORCE_BUDGET 64

/* The robust F* at (edge, t), kept in *out when below it. */
static wr_status try_least(const wr_robust *robust, const wr_fixture *f, wr_set set,
                           const double (*loads)[3], int case_count, int edge, double t,
                           const wr_stop *stop, wr_least_force *out)
{
    double push[3], force;
    wr_push_wrench(f, edge, t, push);
    wr_status status =
        wr_robust_least_force_at(robust, set, loads, case_count, push, stop, &force);
    if (status == WR_OK && force < out->force) {
        out->force = force;
        out->found = true;
        out->edge = edge;
        out->t = t;
        wr_boundary_point(f, edge, t, out->at, out->direction);
    }
    return status;
}

wr_status wr_robust_least_force_at_mu(const wr_fixture *fixture, double mu, double kinetic_ratio,
                                      wr_set set, const double (*loads)[3], int case_count,
                                      const wr_finger *finger, int samples,
                                      const wr_stop *stop, wr_least_force *out)
{
    memset(out, 0, sizeof *out);
    out->force = INFINITY;
    wr_fixture at;
    at_friction(fixture, mu, mu, kinetic_ratio, &at);
    wr_analysis *analysis = NULL;
    wr_robust *robust = NULL;
    wr_least_force nominal = {0};
    wr_status status = wr_analysis_new(&at, &analysis);
    if (status == WR_OK)
        status = wr_least_force_find(analysis, set, loads, case_count, finger, stop, &nominal);
    if (status == WR_OK)
        status = wr_robust_new(analysis, ROBUST_FORCE_BUDGET, &robust);
    out->lower = nominal.lower;
    out->evaluations = nominal.evaluations;
    if (status == WR_OK && nominal.found)
        status = try_least(robust, &at, set, loads, case_count, nominal.edge, nominal.t, stop,
                           out);
    /* The samples: where the finger reaches on each edge it pushes on;
     * none when no point has a nominal F*, since no fixture of the set
     * needs less than the nominal one. */
    const double top = at.shape == WR_SHAPE_CIRCLE ? 360 : 1;
    for (int e = 0; status == WR_OK && nominal.found && e < wr_push_edge_count(&at); e++) {
        if (!wr_finger_pushes_on(&at, finger, e))
            continue;
        wr_span *blocked = NULL;
        int blocked_count = 0;
        if (finger->radius > 0 && at.shape != WR_SHAPE_CIRCLE) {
            size_t loop, segment;
            wr_push_edge_place(&at, e, &loop, &segment);
            status = wr_finger_blocked(at.outline, loop, segment, finger->radius, stop,
                                       &blocked, &blocked_count);
        }
        for (int j = 0; status == WR_OK && j < samples; j++) {
            double t = top * (j + 0.5) / samples;
            bool reached = true;
            for (int k = 0; reached && k < blocked_count; k++)
                reached = !(t >= blocked[k].lo && t <= blocked[k].hi);
            if (reached)
                status = try_least(robust, &at, set, loads, case_count, e, t, stop, out);
            out->evaluations++;
        }
        free(blocked);
    }
    out->converged = out->found && out->force <= out->lower * (1 + 1e-9);
    wr_robust_free(robust);
    wr_analysis_free(analysis);
    if (status != WR_OK) {
        memset(out, 0, sizeof *out);
        out->force = INFINITY;
    }
    return status;
}
