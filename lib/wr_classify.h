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

typedef struct wr_analysis {
    const wr_fixture *fixture;  /* borrowed: must outlive the analysis */
    wr_plan *plan;
    wr_cone *goal_cones;        /* plan->kept_count, in the plan's order */
    int mode_count;
    wr_constraint *modes;       /* feasible moving modes, pivots last */
    wr_cone *mode_cones;        /* one per mode */
    bool pinned;                /* rolling at every fixel forces q = 0 */
} wr_analysis;

/* Derive everything for `fixture`.  NULL when out of memory. */
wr_analysis *wr_analysis_new(const wr_fixture *fixture);
void wr_analysis_free(wr_analysis *analysis);

/* Bytes the analysis holds (for a cache's memory bound). */
size_t wr_analysis_bytes(const wr_analysis *analysis);

/* The excluded cones of a set (WR_SET_GOAL or WR_SET_STRONG). */
int wr_analysis_cone_count(const wr_analysis *analysis, wr_set set);
const wr_cone *wr_analysis_cone(const wr_analysis *analysis, wr_set set, int index);

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
 * For WR_SET_BOTH the margin is the smaller of the two.  Returns 0, or -1 if
 * g is not finite or the tolerance is negative. */
int wr_classify(const wr_analysis *analysis, const double wrench[3], wr_set set,
                double tolerance, wr_answer *answer);

/* The same with GLPK LPs against every excluded cone (method "lp"): verdict
 * inside or outside, no margin.  `goal` and `strong` are LP sets over the
 * analysis's goal and mode constraints (see wr_analysis_lp_sets).  Returns 0,
 * -1 on bad input, or WR_LP_FAILED. */
int wr_classify_lp(const wr_analysis *analysis, wr_lp_set *goal, wr_lp_set *strong,
                   const double wrench[3], wr_set set, wr_answer *answer);

/* LP sets for an analysis, in one thread's env.  Returns 0 or -1 (out of
 * memory, nothing allocated). */
int wr_analysis_lp_sets(const wr_analysis *analysis, wr_lp_env *env, wr_lp_set **goal,
                        wr_lp_set **strong);

#ifdef __cplusplus
}
#endif

#endif
