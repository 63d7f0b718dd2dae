/* wr_robust_sweep.h -- push regions, gravity arcs and the least push force
 * against a common coefficient of friction, over a fixture's geometric
 * tolerance (docs/MODEL.md section 10, "Friction sweeps and least forces").
 *
 * On every fixel mu_s = mu and mu_k = kinetic_ratio mu, mu over the range,
 * as wr_sweep.h; each answer holds for every fixture of the tolerance's set
 * (wr_tolerance.h).  The exact machinery of wr_sweep.h varies mu on the
 * nominal fixels only, so the robust answers are proved piece by piece:
 *
 *   - a piece [m0, m1] of mu (inside a nominal interval, bisected down to
 *     2^-WR_ROBUST_DEPTH of it) is kept when some push (some tilt) is
 *     proved robustly inside on the fixture whose friction is the interval
 *     itself (mu_s in [m0, m1], mu_k in kinetic_ratio [m0, m1]): the cones
 *     of friction intervals are the unions over their coefficients, so that
 *     push is inside for every mu of the piece and every fixture of the set,
 *     and the robust region is non-empty all over the piece;
 *   - the pushes tried there are the robust regions at exact mu (samples:
 *     a grid of WR_ROBUST_SWEEP_GRID steps over the range, and the middle
 *     of a piece with none), bisected down to 2^-WR_ROBUST_SWEEP_MEET_DEPTH
 *     of their length;
 *   - a piece holding a sample whose robust region is empty cannot be kept
 *     whole (the interval's cones contain that mu's): it is split without
 *     a proof tried; one lying between two such samples is given up (an
 *     interval narrower than the grid's step may be missed: the answer's
 *     resolution).
 *
 * Whatever is given up only narrows the answer: every interval kept is
 * proved.  The curve is the robust region's total length (degrees for the
 * arcs) at each sample, the fixture at that exact mu: wr_robust_regions of
 * its nominal regions, what push.regions and gravity.sweep answer over a
 * tolerance. */
#ifndef WR_ROBUST_SWEEP_H
#define WR_ROBUST_SWEEP_H

#include "wr_force.h"
#include "wr_sweep.h"
#include "wr_tolerance.h"

#ifdef __cplusplus
extern "C" {
#endif

#define WR_ROBUST_SWEEP_GRID 32
#define WR_ROBUST_SWEEP_MEET_DEPTH 6
/* Boxes per excluded cone for a finest piece of a sample's regions (as
 * push.regions over a tolerance) and of a piece's proof. */
#define WR_ROBUST_SWEEP_BUDGET 16

/* A sweep of the robust push regions (a frictionless finger: its radius
 * and push_on as wr_push_regions_finger's) or gravity arcs, done a unit of
 * work at a time (a sample at one mu, or a piece's proof), so that a server
 * can share its threads and stop at a deadline. */
typedef struct wr_robust_sweep wr_robust_sweep;

/* For `fixture` (with a tolerance; borrowed, it must outlive the job),
 * `set`, `range`, `gravity` (else a push of `finger`, copied, its push_on
 * borrowed) and `nominal`, the nominal intervals of mu where the region is
 * non-empty (wr_sweep_push or wr_sweep_gravity of the same set and range;
 * copied).  WR_OK; WR_INVALID (no tolerance; a finger with friction);
 * WR_NO_MEMORY.  *out NULL unless WR_OK. */
wr_status wr_robust_sweep_new(const wr_fixture *fixture, wr_set set, const wr_sweep_range *range,
                              bool gravity, const wr_finger *finger, const wr_intervals *nominal,
                              wr_robust_sweep **out);

/* One unit of work; *done when the answer is complete (then nothing more
 * is done).  WR_OK; WR_STOPPED (`stop`, polled inside the unit); WR_LP_FAILED;
 * WR_NO_MEMORY.  After a failure the job can only be freed. */
wr_status wr_robust_sweep_run(wr_robust_sweep *job, const wr_stop *stop, bool *done);

/* The mu below which the answer is decided: the range's top when done. */
double wr_robust_sweep_reached(const wr_robust_sweep *job);

/* The answer below `top` (the range's top, or wr_robust_sweep_reached for
 * a job stopped before it is done): the intervals kept (cut at top), the
 * critical by wr_sweep_curve's rule (none when top is below the range's
 * top: not known), the samples' lengths (the grid's points outside the
 * nominal intervals 0), "exact" false and the resolution the grid's step.
 * WR_OK; WR_NO_MEMORY (`out` empty). */
wr_status wr_robust_sweep_curve(const wr_robust_sweep *job, double top, wr_sweep_curve *out);

/* Work units spent so far (a box's LP is about one). */
unsigned long wr_robust_sweep_work(const wr_robust_sweep *job);

void wr_robust_sweep_free(wr_robust_sweep *job);

/* The robust least push force at one mu: the fixture (with a tolerance) at
 * mu_s = mu, mu_k = kinetic_ratio mu; the least robust F*
 * (wr_robust_least_force_at) among the nominal least's point (wr_least_force_find
 * at that mu) and `samples` points evenly spaced along every edge the
 * finger reaches (off its ends), as push.force's over a tolerance.  Its
 * edge, t and point in *out; out->found false when no point has a robust
 * F* proved (force INFINITY); out->lower the nominal search's bound (no
 * fixture of the set needs less).  WR_OK; WR_INVALID (as
 * wr_least_force_find); WR_STOPPED; WR_LP_FAILED; WR_NO_MEMORY. */
wr_status wr_robust_least_force_at_mu(const wr_fixture *fixture, double mu, double kinetic_ratio,
                                      wr_set set, const double (*loads)[3], int case_count,
                                      const wr_finger *finger, int samples,
                                      const wr_stop *stop, wr_least_force *out);

#ifdef __cplusplus
}
#endif

#endif
