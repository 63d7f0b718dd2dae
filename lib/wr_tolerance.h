/* wr_tolerance.h -- answers that hold for every fixture within a geometric
 * tolerance of the nominal one (docs/MODEL.md section 10).
 *
 * A fixture's tolerance {position T, angle A} stands for the set of
 * fixtures in which each fixel's contact lies on the part's boundary within
 * arc length T of its nominal point, its normal turned with the boundary's
 * and then tilted by up to A.  A robust answer is `inside` only when the
 * nominal answer's margin exceeds the tolerance for every fixture of the
 * set (proved by a dual certificate per excluded cone over boxes of the
 * set, refined by subdivision; one made of the rows themselves where a
 * fixed one cannot follow them), `outside` only with a fixture of the set
 * (the witness) whose own answer is `outside`, and `boundary` otherwise.
 *
 * A wr_robust is immutable once built; any number of threads may use it.
 * It uses GLPK (wr_lp.h): a thread that calls it owns a GLPK environment
 * (wr_lp_env_new) while it does. */
#ifndef WR_TOLERANCE_H
#define WR_TOLERANCE_H

#include "wr_classify.h"
#include "wr_force.h"
#include "wr_regions.h"
#include "wr_sweep.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Angles of 90 degrees or more are refused: the normal would leave the
 * half-plane it pushes into. */
#define WR_TOLERANCE_MAX_ANGLE 90.0

/* Check `tolerance` against `fixture` and, when valid, store it in
 * fixture->tolerance.  Refused, naming the field ("tolerance.position",
 * "tolerance.angle"): a negative or non-finite value; an angle of 90
 * degrees or more; a position tolerance on a fixture without a shape; a
 * position tolerance larger than a fixel's segment allows: the contact may
 * not pass the end of the segment (straight or arc) that holds it, where
 * the boundary's normal may jump, nor (on a circle) more than half way
 * round.  A fixel at a corner (no normal of the boundary there) keeps its
 * contact at the corner: a locator's face error does not move the corner
 * in the part's frame; only its normal tilts.  WR_OK or WR_INVALID. */
wr_status wr_fixture_set_tolerance(wr_fixture *fixture, const wr_tolerance *tolerance,
                                   wr_error *error);

/* How far fixel i's contact may move each way along the boundary under
 * `fixture`'s tolerance (0 at a corner or without a tolerance). */
double wr_tolerance_reach(const wr_fixture *fixture, int fixel);

/* One fixture of the set: fixel i's contact moved by s[i] along the
 * boundary (|s[i]| <= reach) and its normal tilted by tilt[i] radians
 * (|tilt[i]| <= angle), into *out: a shallow copy of `fixture` (its shape
 * borrowed; never wr_fixture_free it).  s = tilt = 0 gives the nominal
 * fixels bit for bit. */
void wr_tolerance_perturb(const wr_fixture *fixture, const double *s, const double *tilt,
                          wr_fixture *out);

typedef struct wr_robust wr_robust;

/* The robust questions of an analysis (complete: wr_analysis_new) whose
 * fixture carries a tolerance; `budget` bounds the boxes examined per
 * excluded cone and wrench (0: a default).  WR_OK or WR_NO_MEMORY. */
#define WR_ROBUST_BUDGET 256
wr_status wr_robust_new(const wr_analysis *analysis, int budget, wr_robust **out);
void wr_robust_free(wr_robust *robust);

/* A robust answer.  `answer` as wr_classify's (its margin: for inside a
 * lower bound on the worst margin over the set; for outside the witness
 * fixture's own margin; for boundary the least margin met), and for
 * outside the witness: the contact points and normals of a fixture of the
 * set on which wr_classify answers outside. */
typedef struct wr_robust_answer {
    wr_answer answer;
    bool has_perturbation;
    double points[WR_MAX_FIXELS][2];
    double normals[WR_MAX_FIXELS][2];
} wr_robust_answer;

/* Classify the physical wrench g robustly.  WR_OK; WR_INVALID as
 * wr_classify; WR_LP_FAILED; WR_NO_MEMORY. */
wr_status wr_robust_classify(const wr_robust *robust, const double wrench[3], wr_set set,
                             double tolerance, wr_robust_answer *out);

/* Is every wrench of a family inside robustly?  The family is given by an
 * interval box of scaled wrenches: lo[j] <= x[j] <= hi[j] (each x is
 * judged by its direction; the box must not hold the zero wrench).  True
 * only when proved: for every x of the box and every fixture of the set
 * the margin exceeds `tolerance`.  *status: WR_OK, or WR_LP_FAILED /
 * WR_NO_MEMORY (then false). */
bool wr_robust_box_inside(const wr_robust *robust, const double lo[3], const double hi[3],
                          wr_set set, double tolerance, wr_status *status);

/* The robust part of nominal push regions (wr_push_regions of the same
 * set, frictionless finger) or gravity arcs (wr_gravity_sweep; `edge` -1:
 * t is the tilt in degrees): each nominal interval is bisected down to
 * 2^-WR_ROBUST_DEPTH of its length, and the pieces proved inside
 * (wr_robust_box_inside over the push wrenches of the piece) are kept,
 * contiguous ones joined.  So the result lies inside the robust region
 * exactly, and reaches within a 2^-WR_ROBUST_DEPTH share of each nominal
 * interval's length of every end that its proofs reach.  WR_OK;
 * WR_STOPPED; WR_LP_FAILED; WR_NO_MEMORY (`out` empty unless WR_OK). */
#define WR_ROBUST_DEPTH 10
wr_status wr_robust_regions(const wr_robust *robust, wr_set set, const wr_regions *nominal,
                            bool gravity, const wr_stop *stop, wr_regions *out);

/* Is some piece of `candidates` (regions or arcs of the fixture, as
 * wr_robust_regions takes them) robustly inside?  Each is bisected down to
 * 2^-depth of its length (0 <= depth <= WR_ROBUST_DEPTH) as
 * wr_robust_regions does, and the search ends at the first piece proved:
 * *found then says that some push (some tilt) is inside on every fixture of
 * the set.  WR_OK; WR_INVALID (a depth out of bounds); WR_STOPPED;
 * WR_LP_FAILED; WR_NO_MEMORY (*found false unless WR_OK). */
wr_status wr_robust_regions_meet(const wr_robust *robust, wr_set set,
                                 const wr_regions *candidates, bool gravity, int depth,
                                 const wr_stop *stop, bool *found);

/* The robust part of nominal good magnitudes (wr_force_range of the same
 * set, load and push, both physical wrenches of the model system): each
 * nominal interval bisected as wr_robust_regions does, on the parameter
 * F / (F + c) (an unbounded interval is a bounded one of it).  `out`
 * (emptied first, its array reused) lies inside the robust magnitudes.
 * WR_OK; WR_STOPPED; WR_LP_FAILED; WR_NO_MEMORY. */
wr_status wr_robust_forces(const wr_robust *robust, wr_set set, const double load[3],
                           const double push[3], const wr_forces *nominal, const wr_stop *stop,
                           wr_forces *out);

/* The robust F*(p): the least magnitude of the proved robust ones
 * (wr_robust_forces of each case's nominal good magnitudes, intersected
 * over the cases) with which `push` (as wr_least_force_at's) does the
 * set's job under every case on every fixture of the set; INFINITY when
 * none is proved.  It is at least the nominal fixture's F*(p), and may
 * lie above the least robust magnitude (the bisection's resolution; with
 * one case the finest pieces get a few boxes each, so that a push no
 * magnitude does is given up quickly): a push of that force works on
 * every fixture of the set.  WR_OK;
 * WR_INVALID (as wr_force_range); WR_STOPPED; WR_LP_FAILED; WR_NO_MEMORY. */
wr_status wr_robust_least_force_at(const wr_robust *robust, wr_set set,
                                   const double (*loads)[3], int case_count,
                                   const double push[3], const wr_stop *stop, double *force);

/* The robust part of a wrench's nominal intervals of mu (wr_sweep_wrench
 * of the same set on `fixture`, mu_s = mu, mu_k = kinetic_ratio mu), over
 * `fixture`'s tolerance: each interval bisected down to
 * 2^-WR_ROBUST_DEPTH of its length, a piece [m0, m1] kept when the wrench
 * is robustly inside (wr_robust_classify) on the fixture with `fixels`
 * placed again with the friction intervals mu_s in [m0, m1] and mu_k in
 * [kinetic_ratio m0, kinetic_ratio m1]: an answer over friction intervals
 * holds for every coefficient in them, so the piece holds for every mu of
 * it and every fixture of the set at once.  Contiguous pieces are joined;
 * `out` (emptied first) lies inside the robust intervals.  WR_OK;
 * WR_STOPPED; WR_LP_FAILED; WR_NO_MEMORY; WR_INVALID (a placement
 * refused). */
wr_status wr_robust_sweep_wrench(const wr_fixture *fixture, const wr_fixel_spec *fixels,
                                 double kinetic_ratio, const double wrench[3], wr_set set,
                                 const wr_intervals *nominal, const wr_stop *stop,
                                 wr_intervals *out);

#ifdef __cplusplus
}
#endif

#endif
