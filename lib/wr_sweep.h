/* wr_sweep.h -- answers as functions of one common friction coefficient
 * (docs/PROTOCOL.md, friction.sweep).
 *
 * On every fixel mu_s = mu and mu_k = ratio * mu, mu over [low, high]; the
 * fixture's own friction is ignored.  Each answer changes only where some
 * wrench meets the boundary of an excluded cone, and those values of mu
 * are roots of polynomials:
 *
 *   - every generator of every excluded cone is affine in mu: an
 *     acceleration direction of M Q_X (no mu at all) or a friction edge
 *     -(W_n + c mu W_t), c in {+-1, +-ratio};
 *   - a face of a cone lies in the plane of two of its generators, whose
 *     normal g_a(mu) x g_b(mu) is quadratic in mu;
 *   - a fixed wrench h (a classified wrench, the push at an end of an edge
 *     or of a finger's blocked span) meets the plane where h . n(mu) = 0:
 *     degree 2;
 *   - a cone's faces change where three of its generators become coplanar
 *     in a plane that supports it, det(g_a, g_b, g_c)(mu) = 0: degree 3
 *     (a face may vanish there with no wrench crossing it: the cone opens
 *     into a half-space or all of space);
 *   - the push wrench along an edge (or gravity over the circle of tilts)
 *     is s1 c1 + s2 c2 in two coordinates (wr_internal.h), so two planes
 *     meet it at the same point where (c1.n_P)(c2.n_Q) - (c1.n_Q)(c2.n_P)
 *     vanishes: degree 4.  A push region (an arc) can only appear or
 *     vanish where two of its ends meet, which is such a point or an end
 *     of the edge.
 *
 * Every real root in the range is found, however close to another (each
 * polynomial's monotone pieces come from its derivative's roots, and each
 * is bisected to the last bit), and kept when the wrench there lies on the
 * face itself in a plane that supports its cone.  Between two consecutive
 * roots nothing changes, so the answer is decided at the middle of each
 * piece: no interval can hide between samples, however narrow.  Each
 * answer at one mu is the analysis of the fixture at that mu, made from
 * what the sweeper built once (wr_analysis_frame, wr_internal.h: the plan,
 * the modes, every cone's acceleration generators, the cones with no
 * friction edge), bit for bit the analysis made from scratch.  G_goal
 * needs no special case (it shrinks as mu grows, so its intervals start at
 * the bottom of the range); G_strong's, which do not, come out the same
 * way. */
#ifndef WR_SWEEP_H
#define WR_SWEEP_H

#include "wr_regions.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct wr_sweep_range {
    double low, high;     /* 0 <= low < high <= WR_MAX_FRICTION */
    double kinetic_ratio; /* mu_k / mu_s, in (0, 1] */
} wr_sweep_range;

/* Closed intervals [lo, hi] of mu, sorted and disjoint. */
typedef struct wr_intervals {
    int count;
    int capacity;
    double (*items)[2];
} wr_intervals;

void wr_intervals_release(wr_intervals *intervals);
/* [lo, hi] after the last interval (lo not below its end), joined to it
 * when it ends at lo.  false: no memory (the list as it was). */
bool wr_intervals_append(wr_intervals *intervals, double lo, double hi);

/* A push region's total length (or a gravity arc's, in degrees) against mu. */
typedef struct wr_sweep_curve {
    wr_intervals intervals; /* where the region is non-empty */
    bool has_critical;      /* false: non-empty at the top of the range */
    double critical;        /* the upper end of the last interval, or the
                               bottom of the range when there is none */
    int point_count;
    double (*points)[2];    /* (mu, length), increasing in mu, from low to
                               high: every root kept and a grid between */
    bool exact;             /* false with a finger with friction */
    double resolution;      /* 0 when exact; else the step in mu below
                               which an interval may be missed */
} wr_sweep_curve;

void wr_sweep_curve_release(wr_sweep_curve *curve);

/* Opaque: the excluded cones of a set, their generators as functions of mu
 * and the planes of their faces.  Immutable once built: any number of
 * threads may sweep with it at once. */
typedef struct wr_sweeper wr_sweeper;

/* For `fixture` (borrowed: it must outlive the sweeper), `set` and
 * `range`.  WR_OK; WR_INVALID for a range or ratio out of bounds;
 * WR_NO_MEMORY.  *out is NULL unless WR_OK. */
wr_status wr_sweeper_new(const wr_fixture *fixture, wr_set set, const wr_sweep_range *range,
                         wr_sweeper **out);
void wr_sweeper_free(wr_sweeper *sweeper);

/* The intervals of mu in which the physical wrench is inside the set (its
 * margin above WR_DEFAULT_TOLERANCE).  WR_OK; WR_INVALID for a wrench that
 * is not finite; WR_NO_MEMORY; WR_STOPPED.  `out` is empty unless WR_OK. */
wr_status wr_sweep_wrench(const wr_sweeper *sweeper, const double wrench[3],
                          const wr_stop *stop, wr_intervals *out);

/* The push region's total length against mu for a finger (as
 * wr_push_regions_finger).  Exact unless the finger has friction: its
 * regions are sampled, and so is the sweep (256 steps of mu, each change
 * bisected).  WR_OK; WR_NO_SHAPE; WR_INVALID for a bad finger;
 * WR_NO_MEMORY; WR_STOPPED.  `out` is empty unless WR_OK. */
wr_status wr_sweep_push(const wr_sweeper *sweeper, const wr_finger *finger,
                        const wr_stop *stop, wr_sweep_curve *out);

/* The total gravity arc of the set, in degrees, against mu (always exact).
 * WR_OK; WR_NO_MEMORY; WR_STOPPED. */
wr_status wr_sweep_gravity(const wr_sweeper *sweeper, const wr_stop *stop, wr_sweep_curve *out);

/* The same a bounded amount of work at a time, so that a server can share
 * its threads among clients: a job is made by one of the three functions
 * below (returning as the functions above do before any work), then run
 * until done.  Each run does units of work (an edge's row of plane pairs,
 * one analysis at one mu) until about `budget` work units are spent (a
 * unit is about one wrench against one cone, as the server counts them;
 * at least one unit a run), adds them to *used (may be NULL), and sets
 * *done when the answer is complete.  WR_OK; WR_NO_MEMORY; WR_STOPPED when
 * `stop` asks (between units); after a failure the job can only be freed.
 * The sweeper must outlive the job. */
typedef struct wr_sweep_job wr_sweep_job;

wr_status wr_sweep_job_wrench(const wr_sweeper *sweeper, const double wrench[3],
                              wr_sweep_job **out);
wr_status wr_sweep_job_push(const wr_sweeper *sweeper, const wr_finger *finger,
                            wr_sweep_job **out);
/* A push job's regions at each coefficient asked through `index` (built
 * for the swept fixture's body and the job's finger; wr_regions.h), and
 * the finger's blocked spans taken from it: the same answer, bit for bit.
 * The index must outlive the job. */
void wr_sweep_job_use_index(wr_sweep_job *job, const wr_push_index *index);
wr_status wr_sweep_job_gravity(const wr_sweeper *sweeper, wr_sweep_job **out);
wr_status wr_sweep_job_run(wr_sweep_job *job, unsigned long budget, unsigned long *used,
                           const wr_stop *stop, bool *done);
/* Ends a job that is not done where it has got to (a server's deadline):
 * *reached is the mu up to which its answer is decided, the range's low end
 * when nothing is yet, the top when the job is done.  Its intervals keep
 * what lies below *reached, an interval still open there cut at *reached;
 * a region's curve keeps its points up to *reached and has_critical is
 * false (not known).  The job is then done: its answers below can be
 * taken, it runs no more.  WR_OK; WR_NO_MEMORY (an interval to close). */
wr_status wr_sweep_job_stop(wr_sweep_job *job, double *reached);
/* When done: a wrench's intervals (also a region's), a region's curve. */
const wr_intervals *wr_sweep_job_intervals(const wr_sweep_job *job);
const wr_sweep_curve *wr_sweep_job_curve(const wr_sweep_job *job);
void wr_sweep_job_free(wr_sweep_job *job);

/* The fixture at a common coefficient: a shallow copy of `fixture` (its
 * shape borrowed, never to be freed) with mu_s = mu and mu_k = ratio * mu
 * on every fixel. */
void wr_fixture_at_friction(const wr_fixture *fixture, double mu, double ratio, wr_fixture *out);

#ifdef __cplusplus
}
#endif

#endif
