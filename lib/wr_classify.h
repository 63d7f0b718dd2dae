/* wr_classify.h -- G_goal and G_strong of a fixture (docs/MODEL.md sections 3-5), and
 * three-valued answers for wrenches.
 *
 * A wr_analysis holds everything derived from one fixture: the plan, the
 * explicit cones G_goal excludes, the feasible modes and the cones G_strong
 * excludes.  It is immutable once built, so any number of threads may
 * classify against it at once. */
#ifndef WR_CLASSIFY_H
#define WR_CLASSIFY_H

#include "wr_lp.h"
#include "wr_plan.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum wr_set {
    WR_SET_GOAL,   /* seats the part from any contact state */
    WR_SET_STRONG, /* the seated part cannot move */
    WR_SET_BOTH    /* seats it and then holds it still */
} wr_set;

typedef enum wr_verdict {
    WR_VERDICT_INSIDE,   /* margin > tolerance */
    WR_VERDICT_BOUNDARY, /* |margin| <= tolerance: floating point cannot tell */
    WR_VERDICT_OUTSIDE   /* margin < -tolerance */
} wr_verdict;

#define WR_DEFAULT_TOLERANCE 1e-9

/* A caller's way to end long work early (a client that hung up).  Long
 * functions that take one poll `requested` between bounded units of work
 * (an edge, a cone, a sample run) and give up when it returns true.  NULL:
 * never stop.  The callback must be cheap and thread-safe. */
typedef struct wr_stop {
    bool (*requested)(void *context);
    void *context;
} wr_stop;

/* Has the caller asked to stop?  False for a NULL stop. */
static inline bool wr_stop_requested(const wr_stop *stop)
{
    return stop && stop->requested(stop->context);
}

/* Opaque: read it through the accessors below. */
typedef struct wr_analysis wr_analysis;

/* Derive everything for `fixture` (borrowed: it must outlive the analysis)
 * into *out.  WR_OK, or WR_NO_MEMORY (*out NULL). */
wr_status wr_analysis_new(const wr_fixture *fixture, wr_analysis **out);
void wr_analysis_free(wr_analysis *analysis);

/* The same in two stages, for a caller that may stop after G_goal (a design
 * search: most candidates have no seating push).  wr_analysis_goal_new
 * derives G_goal's cones only, with `plan` (borrowed, made for the
 * fixture's fixel count; it must outlive the analysis) or, when NULL, a
 * plan of its own; until wr_analysis_complete adds the modes and G_strong's
 * cones, the strong set has no cones and wr_analysis_pinned is false (ask
 * wr_fixture_pinned).  Complete, it is what wr_analysis_new gives.  Both
 * WR_OK or WR_NO_MEMORY (goal_new: *out NULL; complete: as it was). */
wr_status wr_analysis_goal_new(const wr_fixture *fixture, const wr_plan *plan,
                               wr_analysis **out);
wr_status wr_analysis_complete(wr_analysis *analysis);

/* Bytes the analysis holds (for a cache's memory bound). */
size_t wr_analysis_bytes(const wr_analysis *analysis);

/* The fixture it was derived from. */
const wr_fixture *wr_analysis_fixture(const wr_analysis *analysis);
/* The insertion plan: its kept strings are G_goal's excluded strings, in
 * the order of the goal cones, and plan->origins[i] the states goal cone i
 * comes from. */
const wr_plan *wr_analysis_plan(const wr_analysis *analysis);
/* Does rolling at every fixel force q = 0 (no pivot among the modes)? */
bool wr_analysis_pinned(const wr_analysis *analysis);

/* The excluded cones of a set (WR_SET_GOAL or WR_SET_STRONG): for the goal,
 * one per kept string of the plan; for strong, one per feasible moving
 * mode (pivots last). */
int wr_analysis_cone_count(const wr_analysis *analysis, wr_set set);
const wr_cone *wr_analysis_cone(const wr_analysis *analysis, wr_set set, int index);
/* Their constraint strings, as one array of wr_analysis_cone_count()
 * (the plan's kept strings, or the modes), for wr_lp_set_new(). */
const wr_constraint *wr_analysis_constraints(const wr_analysis *analysis, wr_set set);

typedef struct wr_answer {
    wr_verdict verdict;
    bool has_margin;          /* false for the lp method */
    double margin;            /* docs/MODEL.md section 5, in [-1, 1] */
    wr_set blocking_set;      /* which set's cone blocks (for WR_SET_BOTH) */
    int blocking;             /* index of the blocking cone in that set, or -1
                                 (inside) */
    wr_witness witness;       /* for the blocking cone: makes g, or its
                                 projection onto the cone */
} wr_answer;

/* Classify the physical wrench g with the explicit cones (method "auto").
 * For WR_SET_BOTH the margin is the smaller of the two.  WR_OK, or
 * WR_INVALID if g is not finite or the tolerance is negative. */
wr_status wr_classify(const wr_analysis *analysis, const double wrench[3], wr_set set,
                      double tolerance, wr_answer *answer);

/* The same without the witness (answer->witness is zeroed): verdict,
 * margin and blocking cone exactly as wr_classify's, for the cost of the
 * margin alone. */
wr_status wr_classify_margin(const wr_analysis *analysis, const double wrench[3], wr_set set,
                             double tolerance, wr_answer *answer);

/* The verdict alone: exactly wr_classify's, for a fraction of the work
 * (no margin is computed unless the wrench lies within the tolerance band
 * of some cone by its facets' bound, no witness ever).  WR_OK, or
 * WR_INVALID as wr_classify. */
wr_status wr_classify_verdict(const wr_analysis *analysis, const double wrench[3], wr_set set,
                              double tolerance, wr_verdict *verdict);

/* The verdicts of many wrenches at the cost of a look-up each: a map of
 * the sphere of scaled directions (a cube's faces, cut into cells), in
 * which a cell is decided once, for both sets, when every direction in it
 * has the same verdict by a margin, and left to wr_classify_verdict when
 * not.  Its answers are exactly wr_classify_verdict's at the tolerance it
 * was built for.  Immutable once built: any number of threads may read
 * it.  It borrows the analysis (complete: wr_analysis_new), which must
 * outlive it. */
typedef struct wr_verdict_map wr_verdict_map;

/* Build the map.  WR_OK; WR_INVALID for a tolerance outside [0, 1) or an
 * analysis without G_strong's cones; WR_NO_MEMORY. */
wr_status wr_verdict_map_new(const wr_analysis *analysis, double tolerance,
                             wr_verdict_map **out);
void wr_verdict_map_free(wr_verdict_map *map);
/* The bytes it holds. */
size_t wr_verdict_map_bytes(const wr_verdict_map *map);
/* wr_classify_verdict(analysis, wrench, set, tolerance, verdict), by the map. */
wr_status wr_verdict_map_classify(const wr_verdict_map *map, const double wrench[3], wr_set set,
                                  wr_verdict *verdict);
/* The share of the sphere's cells the map decides, in [0, 1] (a figure
 * for benchmarks: the rest are measured wrench by wrench). */
double wr_verdict_map_decided(const wr_verdict_map *map);

/* The same with GLPK LPs against every excluded cone (method "lp"): verdict
 * inside or outside, no margin.  `goal` and `strong` are LP sets over the
 * analysis's goal and mode constraints (see wr_analysis_lp_sets).  WR_OK,
 * WR_INVALID if g is not finite, or WR_LP_FAILED. */
wr_status wr_classify_lp(const wr_analysis *analysis, wr_lp_set *goal, wr_lp_set *strong,
                         const double wrench[3], wr_set set, wr_answer *answer);

/* LP sets for an analysis, in one thread's env.  WR_OK, or WR_NO_MEMORY
 * (nothing allocated, both NULL). */
wr_status wr_analysis_lp_sets(const wr_analysis *analysis, wr_lp_env *env, wr_lp_set **goal,
                              wr_lp_set **strong);

#ifdef __cplusplus
}
#endif

#endif
