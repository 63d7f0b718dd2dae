/* wr_design.h -- designing a fixture (docs/PROTOCOL.md, fixture.design):
 * where the fixels go and where the push is made.
 *
 * A candidate is a choice of k of n candidate sites (points of the
 * boundary with their inward normals), in increasing order of site index;
 * candidates are numbered in lexicographic order of their index lists,
 * from 0.  Each is judged as the fixture of the body with fixels at its
 * sites, the design's friction on every fixel:
 *
 *   - shared hole: two of its sites lie in one hole (a pin is one fixel);
 *   - degenerate: the fixels are refused as a fixture's would be (two at
 *     one point with one normal, all within WR_FIXEL_SPREAD);
 *   - unpinned: the fixels let the seated part turn about a point with
 *     every contact kept (a pivot mode): they do not locate the part, so
 *     no push makes it a fixture;
 *   - no seating push: the push region of G_goal is empty (for the
 *     finger given);
 *   - else scored by the objective:
 *       WR_OBJECTIVE_MARGIN   the best push's margin (0 without a `both`
 *                             region: it ranks after every design with one);
 *       WR_OBJECTIVE_REGION   the total length of the `both` push region;
 *       WR_OBJECTIVE_GRAVITY  the longest arc of gravity tilts in G_goal, in
 *                             degrees;
 *       WR_OBJECTIVE_FORCE    minus the least force of a frictionless push
 *                             that does `both` under every load case
 *                             (wr_least_force_find: smaller first); a
 *                             candidate where no magnitude does counts as
 *                             having no seating push.  Its goal region
 *                             without loads is not asked first: gravity
 *                             may seat a part no push alone does.
 *       WR_OBJECTIVE_ACCURACY minus the worst locating error (wr_locate.h)
 *                             with every locator off by +-tolerance: the
 *                             largest exact worst displacement of the
 *                             features, or without features the largest
 *                             exact pose in the scaled metric; a candidate
 *                             whose fixels do not determine the pose is
 *                             unpinned, one wr_locate refuses degenerate.
 *       WR_OBJECTIVE_PARETO   every candidate scored on all three of the
 *                             best push's margin (as MARGIN), its worst
 *                             locating error (as ACCURACY, which it needs)
 *                             and, with load cases, its least push force
 *                             (as FORCE; INFINITY where none does `both`):
 *                             wr_design.pareto.  The designs kept are the
 *                             Pareto front, those no other candidate beats
 *                             on all three together (at least as good on
 *                             each, better on one; equal ones all kept),
 *                             up to `top` of them; its score is the margin.
 *                             No candidate is bounded: each needs all
 *                             three.
 * On a base plate (spec.supports, wr_support.h) the answers depend on
 * magnitudes, and only two objectives are asked (others are refused,
 * WR_INVALID at "objective"):
 *       WR_OBJECTIVE_FORCE    minus the least force of a push (a point
 *                             finger without friction, on a polygon) that
 *                             seats the part on its supports under every
 *                             load case: wr_supports_least_force_find, G_goal
 *                             grown by the supports' friction (a seating
 *                             push: every fixel reached, not that the part
 *                             then rests, which wrench.classify's strong
 *                             answers for the push with the load); none:
 *                             no seating push.
 *       WR_OBJECTIVE_ACCURACY as without supports: locating does not
 *                             depend on magnitudes, and a candidate has a
 *                             push of some size that seats it on the plate
 *                             iff the floating part has a seating push
 *                             (S is bounded, so F u + s tends to F u's
 *                             direction as F grows; and S holds 0).
 *   A kept design's figures are then its least push on the plate (with
 *   load cases) alone: best push, regions, tilts and critical mu are
 *   questions of directions, not made.  Symmetries are not used (a copy
 *   would have to map the supports and their loads too).
 * Designs rank by score, higher first, ties by candidate number, lower
 * first.  A candidate's score depends on nothing but the candidate, so the
 * ranking is the same however the candidates are split (shards, threads).
 *
 * The best push: the point of the `both` push region whose frictionless
 * push (the inward normal there) has the largest margin.  Found by branch
 * and bound over the region's intervals, which cannot miss the maximum:
 *   - along one edge the unit push wrench moves on a great circle of the
 *     unit sphere (its scaled form is c1 + t c2 on a line, an ellipse about
 *     the origin on an arc), monotonically, so the arc it travels between
 *     two parameters of less than half a turn apart is the angle between
 *     their two directions;
 *   - the margin, the distance to the union of the excluded cones, is
 *     1-Lipschitz in that arc (a chord is shorter than its arc), so over an
 *     interval whose ends have margins m_a, m_b and arc theta it is at most
 *     (m_a + m_b + theta) / 2;
 *   - and at most |x - p| for any point p of any excluded cone: the
 *     nearest points of the nearest cones found at the interval's ends give
 *     a bound that is tight to second order at a smooth maximum, where the
 *     first bound alone would need ever more intervals.
 * The interval with the largest bound is split until that bound is within
 * WR_DESIGN_TOLERANCE of the best margin found at a point: the answer is
 * then the maximum to that tolerance, and never above it (it is the margin
 * at a point of the region).  The push at an end of an edge is along that
 * edge's normal. */
#ifndef WR_DESIGN_H
#define WR_DESIGN_H

#include "wr_force.h"
#include "wr_regions.h"
#include "wr_sites.h"
#include "wr_sweep.h"

#include <stdint.h>

struct wr_supports;

#ifdef __cplusplus
extern "C" {
#endif

struct wr_symmetry;

/* The best push's margin is the maximum to within this. */
#define WR_DESIGN_TOLERANCE 1e-9
/* At most this many designs kept (`top`); sites: wr_sites.h. */
#define WR_DESIGN_MAX_TOP 1000
/* The range of common friction the critical mu of a design is sought in
 * (friction.sweep's default). */
#define WR_DESIGN_SWEEP_HIGH 2.0

typedef enum wr_objective {
    WR_OBJECTIVE_MARGIN,
    WR_OBJECTIVE_REGION,
    WR_OBJECTIVE_GRAVITY,
    WR_OBJECTIVE_FORCE,
    WR_OBJECTIVE_ACCURACY,
    WR_OBJECTIVE_PARETO
} wr_objective;

/* With WR_OBJECTIVE_ACCURACY, at most this many features. */
#define WR_DESIGN_MAX_FEATURES 64

/* The best push of a set of regions (wr_push_regions_finger of
 * WR_SET_BOTH on the analysis's fixture), or none. */
typedef struct wr_best_push {
    bool found;            /* false: the regions are empty */
    int edge;
    double t;              /* as wr_region's t */
    double at[2];          /* the boundary point */
    double direction[2];   /* the push: the inward normal there */
    double margin;
    unsigned long evaluations; /* margins computed */
} wr_best_push;

/* The branch and bound above.  It gives up, with *below set and `out` not
 * found, as soon as the maximum is certainly below `threshold` (use
 * -INFINITY never to give up).  WR_OK; WR_NO_MEMORY; WR_STOPPED. */
wr_status wr_best_push_find(const wr_analysis *analysis, const wr_regions *both,
                            double threshold, const wr_stop *stop, wr_best_push *out,
                            bool *below);

/* What a design search is asked. */
typedef struct wr_design_spec {
    const wr_fixture *body;          /* borrowed; from wr_fixture_body_new */
    wr_friction_spec friction;       /* on every fixel */
    const wr_site *sites;            /* borrowed */
    int site_count;
    int fixel_count;                 /* k, 1..WR_MAX_FIXELS */
    wr_objective objective;
    int top;                         /* designs kept, 1..WR_DESIGN_MAX_TOP */
    wr_finger finger;
    int shard_index, shard_count;    /* candidates numbered r with
                                        r mod shard_count = shard_index;
                                        0 and 1 for all */
    /* Or the candidates listed, numbered in this order (a lattice's
     * designs): each fixel_count site indices, increasing.  NULL: every
     * combination of the sites. */
    const int (*candidates)[WR_MAX_FIXELS];
    uint64_t candidate_count;
    /* True: every segment's push regions tested against every cone, as
     * wr_push_regions_finger does, without the job's wr_push_index: the
     * reference the index is checked and measured against.  The answer is
     * the same either way, bit for bit. */
    bool exhaustive;
    /* The part's symmetries (wr_symmetry_find on the body and these
     * sites); NULL or 0: none.  Candidates that a symmetry maps onto each
     * other (their sites onto each other's, wr_symmetry_site_map) are one
     * design: only the lowest-numbered is scored, and it says how many it
     * stands for (wr_design.copies; counts.symmetric the others).  So is a
     * listed candidate whose sites repeat an earlier one's. */
    const struct wr_symmetry *symmetries;
    int symmetry_count;
    /* Load cases (wr_force.h), each one summed wrench of the model system;
     * borrowed.  Required (at least one) for WR_OBJECTIVE_FORCE; with any
     * objective, each design kept reports its least push force. */
    const double (*loads)[3];
    int case_count;
    /* WR_OBJECTIVE_ACCURACY: each locator off by +-tolerance (finite,
     * >= 0), and the features whose error counts (borrowed; none: the
     * pose's). */
    double tolerance;
    const double (*features)[2];
    int feature_count;
    /* Given: a geometric tolerance on each design's fixels (wr_tolerance.h):
     * the figures of every design kept (not the search's scores) are then
     * robust: its both region the part proved for every fixture of the
     * set (wr_robust_regions; empty when a fixel's segment cannot hold
     * the position tolerance), its best push the best of that region.  A
     * frictionless finger only. */
    wr_tolerance fixel_tolerance;
    /* The base plate under every candidate (wr_supports_new on the body;
     * borrowed), or NULL.  With it, the runs below need a GLPK environment
     * of the calling thread (wr_lp.h), and fixel_tolerance is refused. */
    const struct wr_supports *supports;
} wr_design_spec;

/* A ranked design. */
typedef struct wr_design {
    uint64_t candidate;              /* its number */
    int sites[WR_MAX_FIXELS];        /* the sites chosen, increasing */
    double score;
    wr_best_push best_push;
    double goal_length, both_length; /* of the push regions */
    double gravity_goal_deg;         /* the longest arc of G_goal's tilts */
    bool has_critical;               /* false: the goal region is not empty
                                        at mu = WR_DESIGN_SWEEP_HIGH */
    double critical_mu;
    int copies;                      /* the candidates it stands for, itself
                                        included: its images under the
                                        symmetries (1 without) */
    wr_least_force least_force;      /* with load cases: the least push
                                        doing `both` under all of them (on
                                        supports: seating on the plate) */
    /* WR_OBJECTIVE_PARETO: the best push's margin, the worst locating
     * error, the least push force (INFINITY without cases or none). */
    double pareto[3];
} wr_design;

typedef struct wr_design_counts {
    uint64_t examined;               /* candidates of this shard */
    uint64_t degenerate;
    uint64_t unpinned;
    uint64_t no_seating_push;
    uint64_t symmetric;              /* images of a lower-numbered candidate
                                        under a symmetry: not scored, counted
                                        in that one's copies */
    uint64_t shared_hole;            /* two sites in one hole */
    uint64_t bounded;                /* ended early by the bound: below the
                                        top designs so far (depends on the
                                        order of work; not part of the answer) */
} wr_design_counts;

/* Is the spec's question one a design on supports answers (the objective,
 * the finger, the shape: wr_design.h's rules; wr_design_job_new asks it
 * too)?  False with `error` set at the field that asks otherwise. */
bool wr_design_supports_asked(const wr_design_spec *spec, wr_error *error);

/* The number of candidates, C(site_count, fixel_count); UINT64_MAX when
 * it does not fit. */
uint64_t wr_design_candidates(int site_count, int fixel_count);

/* The search, a bounded amount of work at a time (as wr_sweep_job): made,
 * run until *done, then read.  Each run evaluates candidates (a unit: one
 * wrench against one cone, about) until about `budget` units are spent
 * (at least one candidate, or one design's details), adds them to *used
 * (may be NULL).  First the candidates of the shard, then for each design
 * kept the rest of its figures (best push, lengths, gravity, critical mu).
 * WR_OK; WR_INVALID for a spec out of bounds (with `error`); WR_NO_MEMORY;
 * WR_STOPPED when `stop` asks; WR_LP_FAILED (on supports: GLPK, or no
 * `env`).  `env`: the calling thread's GLPK environment, used only on
 * supports (may be NULL without).  The spec's memory must outlive the job. */
typedef struct wr_design_job wr_design_job;

wr_status wr_design_job_new(const wr_design_spec *spec, wr_design_job **out, wr_error *error);
wr_status wr_design_job_run(wr_design_job *job, unsigned long budget, unsigned long *used,
                            const wr_stop *stop, wr_lp_env *env, bool *done);
/* The same in chunks that several threads may evaluate at once, for a
 * server that spreads one search over its workers: a chunk is a range of
 * candidate numbers holding at most WR_DESIGN_CHUNK of the shard's.  Claim
 * and merge change the job (the caller serialises them, with each other
 * and with wr_design_job_run); wr_design_chunk_run only reads it, and any
 * number may run at once.  A claimed chunk is merged, or abandoned after a
 * failure (the job then fails); the job is done only when every claimed
 * chunk is merged.  The threshold a chunk gets is the top-th score when it
 * was claimed: it ends candidates early, never changes a score. */
#define WR_DESIGN_CHUNK 32

typedef struct wr_design_chunk {
    wr_design *designs;      /* at most `top`, best first (malloc'd) */
    int design_count;
    wr_design_counts counts;
    uint64_t *why;           /* as wr_design_job_why's (malloc'd) */
} wr_design_chunk;

/* False when no candidate is left to claim (or the job failed). */
bool wr_design_job_claim(wr_design_job *job, uint64_t *first, uint64_t *count,
                         double *threshold);
/* WR_OK; WR_NO_MEMORY; WR_STOPPED; WR_LP_FAILED (`out` empty unless
 * WR_OK).  `env` as wr_design_job_run's. */
wr_status wr_design_chunk_run(const wr_design_job *job, uint64_t first, uint64_t count,
                              double threshold, const wr_stop *stop, wr_lp_env *env,
                              wr_design_chunk *out, unsigned long *used);
void wr_design_job_merge(wr_design_job *job, const wr_design_chunk *chunk);
/* Is a chunk left to claim? */
bool wr_design_job_claimable(const wr_design_job *job);
/* End the search where it stands: no candidate is claimed from now on;
 * the chunks claimed are merged as usual, then the designs kept so far get
 * their figures (a time limit's answer).  Under the job's lock. */
void wr_design_job_cut(wr_design_job *job);
/* The candidates of the job's shard (examined reaches it when not cut). */
uint64_t wr_design_job_total(const wr_design_job *job);
void wr_design_job_abandon(wr_design_job *job);
void wr_design_chunk_release(wr_design_chunk *chunk);

/* The designs' figures in parallel too, once the search is over (every
 * chunk claimed and merged: wr_design_job_searched): the designs still
 * without figures are those from the first of wr_design_job_figures_left,
 * in order.  wr_design_job_figure makes design `index`'s figures, critical
 * mu included, in its own fixture, analysis and sweep: it reads the job
 * and writes that design only, so any number may run at once on different
 * designs.  wr_design_job_figure_merged then counts the next design in
 * order as done (under the caller's lock, serialised with
 * wr_design_job_run): the same figures, bit for bit, as wr_design_job_run
 * makes one at a time.  WR_OK; WR_NO_MEMORY; WR_STOPPED; WR_LP_FAILED
 * (`env` as wr_design_job_run's). */
bool wr_design_job_searched(const wr_design_job *job);
int wr_design_job_figures_left(const wr_design_job *job);
wr_status wr_design_job_figure(const wr_design_job *job, int index, const wr_stop *stop,
                               wr_lp_env *env, unsigned long *used);
void wr_design_job_figure_merged(wr_design_job *job);

/* Progress: candidates of the shard looked at, of how many, and the best
 * score so far (has_best false before any). */
void wr_design_job_progress(const wr_design_job *job, uint64_t *done, uint64_t *total,
                            bool *has_best, double *best);
/* The designs' figures, after the search: how many of the designs kept
 * have them, of how many (0 of 0 while the search goes on). */
void wr_design_job_figures_progress(const wr_design_job *job, int *done, int *total);
/* When done: the designs, best first (at most `top`), and the counts. */
const wr_design *wr_design_job_designs(const wr_design_job *job, int *count);
const wr_design_counts *wr_design_job_counts(const wr_design_job *job);
/* Why candidates have no seating push: each is asked about the push at one
 * point, the middle of the longest edge the finger may push on (*edge, *t
 * as wr_region's; a circle: 180 degrees), and counted under the goal cone
 * that blocks it there: an array of (*plan)->kept_count + 1 counts, index
 * i for the plan's kept string i (its contact states in origins[i]), the
 * last for a push there that is in G_goal (the finger cannot push there,
 * or the region was cut by rounding).  The counts sum to no_seating_push.
 * Valid while the job is. */
const uint64_t *wr_design_job_why(const wr_design_job *job, const struct wr_plan **plan,
                                  int *edge, double *t);
/* The fixture of a design (a shallow copy of the body, valid while the
 * job is). */
void wr_design_job_fixture(const wr_design_job *job, const wr_design *design, wr_fixture *out);
size_t wr_design_job_bytes(const wr_design_job *job);
void wr_design_job_free(wr_design_job *job);

/* Does design a rank before design b (score, then candidate number)? */
bool wr_design_before(const wr_design *a, const wr_design *b);

#ifdef __cplusplus
}
#endif

#endif
