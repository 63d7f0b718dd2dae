/* wr_force.h -- magnitudes: how hard a push must be, among given loads, to
 * do a set's job (docs/MODEL.md section 6, "Forces and loads").
 *
 * A *load* is a physical wrench (f_x, f_y, tau about the centre of mass) in
 * the fixture's model system (wr_fixture.h, wr_units); a *case* is the sum
 * of the loads acting together.  A push of magnitude F >= 0 along a unit
 * wrench u adds F u, so a case L sees the line
 *
 *     g(F) = L + F u,    F >= 0.
 *
 * Every excluded cone of a set is a closed polyhedral cone {f_i . h <= 0,
 * e_j . h = 0} (scaled space); along the line each row is affine in F, so
 * the cone holds g(F) for a closed interval of F (possibly empty or a
 * point), found from its rows alone.  The set's good magnitudes are the
 * complement of the union of those intervals: maximal open intervals,
 * exact, no sampling.  Their ends are where g(F) reaches some cone's
 * boundary, where wr_classify's margin is 0: just inside an interval
 * wr_classify says `inside`, just outside it does not.
 *
 * The zero wrench (a load exactly cancelled by the push) is a single F, on
 * the boundary of every cone: excluded, as its margin is 0.
 *
 * Gaps between excluded intervals narrower than 1e-9 of the magnitude
 * (of max(F, |L| / |u|) in the scaled metric) are rounding where two
 * cones meet, and are no interval. */
#ifndef WR_FORCE_H
#define WR_FORCE_H

#include "wr_regions.h"

#ifdef __cplusplus
extern "C" {
#endif

/* A maximal interval of magnitudes: lo < hi, hi = INFINITY when the
 * interval has no upper end.  Its interior is inside the set; its ends are
 * on the boundary (or the ends of the range asked). */
typedef struct wr_force_interval {
    double lo, hi;
} wr_force_interval;

/* Sorted, disjoint intervals.  Owns `items`. */
typedef struct wr_forces {
    int count, capacity;
    wr_force_interval *items;
} wr_forces;

void wr_forces_release(wr_forces *forces);

/* The magnitudes F in [lo, hi] (hi may be INFINITY) with `load` + F `push`
 * inside `set`, into `out` (emptied first; its array is reused, so one
 * wr_forces serves many calls).  `load` and `push` are physical
 * wrenches of the model system; `push` is the wrench of a unit push (a unit
 * force at its point: wr_fixture_force_wrench), any non-zero wrench.
 * WR_OK; WR_INVALID for a non-finite or zero push, a non-finite load, or a
 * range not 0 <= lo <= hi; WR_NO_MEMORY (out empty). */
wr_status wr_force_range(const wr_analysis *analysis, wr_set set, const double load[3],
                         const double push[3], double lo, double hi, wr_forces *out);

/* wr_force_range for each set s with sets[s] (indexed by wr_set: goal,
 * strong, both), into out[s] (the others untouched): every cone's span of
 * the line found once for all three, the same answers.  Returns as
 * wr_force_range. */
wr_status wr_force_ranges(const wr_analysis *analysis, const bool sets[3], const double load[3],
                          const double push[3], double lo, double hi, wr_forces out[3]);

/* The intersection of two interval sets, into `out` (which may be neither
 * of them).  WR_OK or WR_NO_MEMORY. */
wr_status wr_forces_intersect(const wr_forces *a, const wr_forces *b, wr_forces *out);

/* The push region under loads: the open intervals of the outline where a
 * frictionless finger pushing with magnitude `force` along the inward
 * normal, plus the load of each of the `case_count` cases, is inside the
 * set for every case -- exact: on a straight segment the wrench is affine
 * in t, on an arc and on a circle it is A cos phi + B sin phi + L, each row
 * of a cone met at the roots of A cos phi + B sin phi = C.  Edges
 * [first_edge, first_edge + edge_count) only, appended to `regions` (the
 * parts of all edges, in order, make the whole answer).  The `finger`
 * (wr_regions.h) is used for its radius and its push_on: a finger of
 * radius > 0 loses the points it cannot reach (wr_finger.h) and a loop not
 * pushed on has no region, as in wr_push_regions_finger; its friction is
 * not used (every force path pushes along the inward normal).  `loads` are
 * physical wrenches of the model system.  WR_OK; WR_NO_SHAPE; WR_INVALID
 * for a force not positive and finite, a non-finite load, no case, a
 * negative or non-finite radius or edges past the outline's; WR_NO_MEMORY;
 * WR_STOPPED.  On failure `regions` is as it was. */
wr_status wr_push_regions_loaded(const wr_analysis *analysis, wr_set set, double force,
                                 const double (*loads)[3], int case_count,
                                 const wr_finger *finger, int first_edge, int edge_count,
                                 const wr_stop *stop, wr_regions *regions);

/* The least magnitude F*(p) with which a push at p along the inward normal
 * does the set's job under every case: the lower end of the first interval
 * of the intersection of the cases' good magnitudes (INFINITY when there is
 * none; 0 when the loads alone do the job).  `push` as wr_force_range's.
 * WR_OK, WR_INVALID (as wr_force_range), WR_NO_MEMORY. */
wr_status wr_least_force_at(const wr_analysis *analysis, wr_set set, const double (*loads)[3],
                            int case_count, const double push[3], double *force);

/* The point of the outline where the smallest push suffices: the minimum
 * of F*(p) over the points the `finger` reaches and may push on (its radius
 * and push_on, as wr_push_regions_loaded's; its friction not used), by
 * branch and bound over intervals of each edge, which cannot miss it.
 *
 * The bound.  Over an interval T of an edge, each row f of an excluded
 * cone (of full dimension; thinner ones cover single magnitudes, which do
 * not move an infimum) is f . h(L) + F f . h(u(t)) <= 0, with f . h(u(t))
 * affine in t on a line and A cos phi + B sin phi on an arc or a circle:
 * its range [b0, b1] over T is exact (the ends, and the one turning point
 * per half turn).  A row the load meets (f . h(L) = alpha <= 0) allows
 * F <= -alpha / b where b > 0 and every F where b <= 0: at every t of T
 * at least F <= -alpha / b1.  A row the load breaks (alpha > 0) allows
 * F >= alpha / |b| where b < 0 and nothing where b >= 0: if b1 < 0, at
 * every t at most F >= alpha / |b1| is needed; otherwise the cone holds
 * nothing at some t and is left out (which only lowers the bound).  So
 * [max of the lower ends, min of the upper ends] is covered at every t of
 * T, and the component of the union of those (over every cone of every
 * case) that holds 0 ends at or below F*(t) for every t in T.  F* at the middle of an interval is an upper
 * bound on the minimum.  The interval with the lowest bound is split until
 * that bound is within WR_FORCE_TOLERANCE (relative) of the least F* found
 * at a point; on pieces where F* keeps its form the bound is exact, so
 * splitting stops there at once.
 *
 * WR_OK; WR_NO_SHAPE; WR_INVALID (a negative radius, no case, a
 * non-finite load); WR_NO_MEMORY; WR_STOPPED. */
#define WR_FORCE_TOLERANCE 1e-9
/* Intervals evaluated at most; beyond, the answer says it did not converge
 * and gives its certified lower bound. */
#define WR_FORCE_MAX_EVALUATIONS 200000

typedef struct wr_least_force {
    bool found;            /* some reachable point has a finite F* */
    int edge;
    double t;              /* as wr_region's t */
    double at[2];          /* the boundary point */
    double direction[2];   /* the push: the inward normal there */
    double force;          /* F* there: the minimum to the tolerance */
    double lower;          /* certified: no point has F* below this */
    bool converged;        /* force - lower <= WR_FORCE_TOLERANCE * force */
    unsigned long evaluations; /* F* computed at points */
} wr_least_force;

wr_status wr_least_force_find(const wr_analysis *analysis, wr_set set, const double (*loads)[3],
                              int case_count, const wr_finger *finger, const wr_stop *stop,
                              wr_least_force *out);

#ifdef __cplusplus
}
#endif

#endif
