/* wr_lp.h -- cone membership as an LP feasibility problem, solved with GLPK
 * (docs/MODEL.md section 2): the method of the seed, and the cross-check of the
 * explicit cones.
 *
 * Threads.  GLPK keeps one environment per thread.  A thread that solves
 * creates one wr_lp_env and uses it, and every wr_lp_set made from it, only
 * in that thread; wr_lp_env_free() (in the same thread) releases GLPK's
 * environment.  Nothing is shared between threads, so any number of threads
 * may solve at once, each with its own env.
 *
 * Failures.  GLPK never aborts the process nor prints: a fatal GLPK error is
 * caught (error hook and longjmp), the thread's GLPK environment is rebuilt,
 * every problem of the thread is rebuilt on its next use, and the call that
 * met the error returns WR_LP_FAILED (wr_status.h). */
#ifndef WR_LP_H
#define WR_LP_H

#include "wr_cone.h"

#ifdef __cplusplus
extern "C" {
#endif

/* A constraint's motion is possible when an acceleration in the box
 * [-1, 1]^3 (scaled) meets its strict rows with a slack above this
 * (docs/MODEL.md section 2): relative to the motion's size, as the
 * explicit cones judge strict rows on unit generators.  A wrench is then
 * in G_X when it is in the closure. */
#define WR_LP_SLACK_THRESHOLD 1e-9

typedef struct wr_lp_env wr_lp_env;
typedef struct wr_lp_set wr_lp_set;

/* Start using GLPK in the calling thread: terminal output off, fatal errors
 * caught.  WR_OK, or WR_NO_MEMORY (*out NULL). */
wr_status wr_lp_env_new(wr_lp_env **out);
/* Free the env and the calling thread's GLPK environment.  Every wr_lp_set
 * of this env must be freed first. */
void wr_lp_env_free(wr_lp_env *env);
/* Test hook: make the GLPK call after `calls` more solves fail fatally
 * (a negative value disarms it). */
void wr_lp_env_inject_failure(wr_lp_env *env, int calls);

/* Membership problems for `count` constraints of one fixture, each built on
 * first use and then reused with new wrench bounds (warm start).  The fixture
 * and the constraints array must outlive the set.  WR_OK, or WR_NO_MEMORY
 * (*out NULL). */
wr_status wr_lp_set_new(wr_lp_env *env, const wr_fixture *fixture,
                        const wr_constraint *constraints, int count, wr_lp_set **out);
void wr_lp_set_free(wr_lp_set *set);

/* Is the physical wrench in G_X for constraint `index`?  Decided on the
 * scaled, normalised problem: the motion possible, the wrench in the
 * closure.  On membership `witness` (may be NULL) receives
 * an acceleration and forces that make the wrench.  Returns WR_OK or
 * WR_LP_FAILED. */
wr_status wr_lp_member(wr_lp_set *set, int index, const double wrench[3], bool *member,
                       wr_witness *witness);

/* Run `body(context)` in the env's thread with GLPK's fatal errors caught:
 * a body that builds its own problems (glp_create_prob) returns its own
 * status; a fatal GLPK error inside it ends it at once, frees the thread's
 * GLPK environment (every problem of the thread with it) and returns
 * WR_LP_FAILED.  Memory the body allocated other than GLPK's must be
 * reachable from `context`, for the caller to free either way. */
wr_status wr_lp_guarded(wr_lp_env *env, wr_status (*body)(void *context), void *context);

#ifdef __cplusplus
}
#endif

#endif
