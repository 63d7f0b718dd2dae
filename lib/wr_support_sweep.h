/* wr_support_sweep.h -- a wrench's answer on a base plate against the
 * fixels' common coefficient of friction, or the supports' (docs/MODEL.md
 * section 11, "Against the fixels' mu" and "Against mu_B";
 * docs/PROTOCOL.md, friction.sweep).
 *
 * On every fixel mu_s = mu and mu_k = ratio * mu, mu over [low, high]
 * (wr_sweep.h's range; the fixture's own fixel friction is ignored, the
 * supports' kept).  Each answer at one mu is the point answer of the
 * fixture placed again with that friction (wr_fixture_at_friction):
 * wr_supports_goal and wr_supports_strong at WR_DEFAULT_TOLERANCE.
 *
 *   - goal: G_goal's excluded cones are nested in mu (each generator of
 *     an m fixel's friction cone at mu lies in the cone at any larger mu;
 *     the acceleration parts do not move), so each C(mu) + S is nested
 *     too and a wrench seats for mu in [low, mu*) exactly.  mu* is found
 *     by bisection on the point answer to WR_SUPPORT_SWEEP_STEP: exact,
 *     nothing missed.
 *   - strong: holding is not monotone in mu (the l and r edges turn with
 *     mu_k).  The answer is taken on a grid of WR_SUPPORT_SWEEP_GRID steps
 *     over the range, each change between neighbours bisected to
 *     WR_SUPPORT_SWEEP_STEP: an interval that begins and ends between two
 *     neighbours, or a gap inside one, may be missed (not exact; the
 *     resolution is the step).
 *   - both: inside where both are; G_both lies in G_goal, so its grid
 *     runs over the goal's interval only (the goal's end is exact, the
 *     rest sampled as strong's).
 *
 * A job does one point answer a run, so that a server can share its
 * threads (its cost: about 1000 + 400 per LP solved, in the server's work
 * units).  Re-entrant; GLPK runs in the calling thread (wr_lp.h). */
#ifndef WR_SUPPORT_SWEEP_H
#define WR_SUPPORT_SWEEP_H

#include "wr_support.h"
#include "wr_sweep.h"

#ifdef __cplusplus
extern "C" {
#endif

#define WR_SUPPORT_SWEEP_GRID 64
#define WR_SUPPORT_SWEEP_STEP 1e-9

typedef struct wr_support_sweep wr_support_sweep;

/* Whose coefficient a job sweeps: every fixel's (the supports' kept), or
 * the supports' mu_B (mu_s = mu, mu_k = ratio * mu; the fixels' kept).
 * Over mu_B the cones stay as they are and S(mu) = mu S(1) grows with mu,
 * so seating is monotone as over the fixels' (docs/MODEL.md section 11,
 * "Against mu_B"); an answer over an interval of mu_B is the holding test
 * with the supports' friction that interval, held at every mu_B of it (a
 * motion consistent at one of them is a solution of its LPs). */
typedef enum wr_support_sweep_over {
    WR_SUPPORT_SWEEP_FIXELS,
    WR_SUPPORT_SWEEP_SUPPORTS
} wr_support_sweep_over;

/* A job for `fixture` (borrowed, with supports; it must outlive the job),
 * the wrench in the model system (wr_support.h), `set`, `range` and whose
 * coefficient it sweeps.  WR_OK; WR_INVALID (no supports, a wrench not
 * finite, a range or ratio out of bounds); WR_NO_MEMORY. */
wr_status wr_support_sweep_new(const wr_fixture *fixture, const double wrench[3], wr_set set,
                               const wr_sweep_range *range, wr_support_sweep_over over,
                               wr_support_sweep **out);
void wr_support_sweep_free(wr_support_sweep *job);

/* Point answers until about `budget` work units are spent (at least one),
 * added to *used; *done when the answer is complete.  WR_OK; WR_NO_MEMORY;
 * WR_LP_FAILED; WR_STOPPED (stop asked); after a failure the job can only
 * be freed. */
wr_status wr_support_sweep_run(wr_support_sweep *job, wr_lp_env *env, unsigned long budget,
                               unsigned long *used, const wr_stop *stop, bool *done);

/* Ends a job that is not done where it has got to: *reached is the mu up
 * to which its answer is decided (the range's low end when nothing is
 * yet); its intervals keep what lies below, one still open cut there.
 * As wr_sweep_job_stop.  WR_OK; WR_NO_MEMORY. */
wr_status wr_support_sweep_stop(wr_support_sweep *job, double *reached);

/* When done: the intervals of mu where the wrench is inside (closed, their
 * ends the last mu proved inside), and whether they are exact (goal), else
 * the grid's step below which an interval may be missed. */
const wr_intervals *wr_support_sweep_intervals(const wr_support_sweep *job);
bool wr_support_sweep_exact(const wr_support_sweep *job);
double wr_support_sweep_resolution(const wr_support_sweep *job);

#ifdef __cplusplus
}
#endif

#endif
