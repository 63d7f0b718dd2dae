/* wr_support.h -- a part lying on a base plate: friction at the supports
 * under it (docs/MODEL.md section 11, "On a base plate").
 *
 * The part lies on rest buttons (supports) at points p_i of its plane.
 * Gravity g presses it onto them, and so may vertical clamps ("down").
 * The normal force N_i at each support follows from statics out of the
 * plane (force and the two moments); the tipping moments of the in-plane
 * loads are neglected.  With 3 supports the N_i are determined; with more,
 * every admissible distribution counts: the polytope
 *
 *     P = { N >= 0 : sum N_i = W, sum N_i p_i = W c }
 *
 * (W the total pressing force, c the centre of pressure), kept as its
 * vertices, the distributions carried by at most 3 supports.
 *
 * Seating.  The supports' friction is some wrench of the set
 *     S = union over N in P of  sum_i { (f, (p_i - com) x f) : |f| <= mu_s N_i }
 * -- convex (the image of a convex set), compact, symmetric.  A wrench g
 * seats the part when g + s is in no excluded cone C of G_goal for any s in
 * S, i.e. g is in no C + S.  Per cone the answer is the least factor rho*
 * by which S must be scaled for g to reach C + rho S (a second-order cone
 * programme; each disc is approached from inside and from outside by
 * polygons whose directions are refined until the two bounds meet):
 * g seats iff rho* > 1 for every cone.
 *
 * Holding.  The seated part under g is held when no motion is consistent:
 * no acceleration q != 0 of a moving mode X, contact forces of X, and
 * support forces that stick where the support's acceleration a_i(q) is 0
 * (|f_i| <= mu_s N_i) and slide against it elsewhere (f_i = -mu_k N_i a_i /
 * |a_i|), with Newton-Euler.  For a fixed direction of q that is an LP; over
 * the directions of a mode (a polyhedral cone of dimension <= 3) it is
 * decided by branch and bound: a cell of directions is dropped when an LP
 * in which each sliding friction ranges over a polygon enclosing its arc
 * of directions (the whole disc where a_i can vanish) is infeasible, which
 * cannot miss a consistent direction inside it.
 *
 * Units: the fixture's model system (wr_fixture.h): g in length / s^2,
 * forces in kg * length / s^2 -- but for the down clamps' forces, which
 * are given (and kept) in the fixture's force unit and converted here.  All functions are re-entrant; those taking
 * a wr_lp_env run GLPK in the calling thread (wr_lp.h). */
#ifndef WR_SUPPORT_H
#define WR_SUPPORT_H

#include "wr_force.h"

#ifdef __cplusplus
extern "C" {
#endif

/* At most this many supports and down clamps. */
#define WR_MAX_SUPPORTS 16
#define WR_MAX_DOWN 16

typedef struct wr_down_spec {
    double at[2];
    double force; /* >= 0, into the plate, in the fixture's force unit */
} wr_down_spec;

typedef struct wr_support_spec {
    size_t point_count;             /* >= 3 */
    const double (*points)[2];      /* borrowed */
    wr_friction_spec friction;      /* mu_B: number, {static, kinetic}, intervals */
    double g;                       /* >= 0, into the plate */
    size_t down_count;
    const wr_down_spec *down;       /* borrowed */
} wr_support_spec;

/* Validated supports with their normal forces.  Read-only for callers. */
typedef struct wr_supports {
    int count;
    double points[WR_MAX_SUPPORTS][2];
    double mu_static, mu_static_min, mu_kinetic, mu_kinetic_min; /* as wr_fixel's */
    double g;
    int down_count;
    wr_down_spec down[WR_MAX_DOWN];
    double total;          /* W = m g + sum of the down forces (model system) */
    double pressure[2];    /* the centre of pressure (the com when W = 0) */
    /* The vertices of P: distribution_count rows of `count` normal forces
     * (one row of zeros when W = 0). */
    int distribution_count;
    double (*distributions)[WR_MAX_SUPPORTS];
    double normal_min[WR_MAX_SUPPORTS], normal_max[WR_MAX_SUPPORTS]; /* over P */
} wr_supports;

/* Validate `spec` for `fixture` (its mass and shape) into *out.  Refused
 * (WR_INVALID, error's field relative to the member "supports"): fewer than
 * 3 points or more than WR_MAX_SUPPORTS ("points"), a point outside the part
 * ("points[i]"), bad friction ("friction", as wr_friction_check), g negative
 * or not finite ("g"), a down clamp outside the part or with a negative
 * force ("down[i].at", "down[i].force"), all points on a line ("points"),
 * and a centre of pressure outside the supports' convex hull, which tips
 * the part ("points", saying how far outside).  WR_NO_MEMORY. */
wr_status wr_supports_new(const wr_fixture *fixture, const wr_support_spec *spec,
                          wr_supports **out, wr_error *error);
/* Defined with the fixture that owns supports (wr_fixture.c). */
void wr_supports_free(wr_supports *supports);

/* wr_supports_new for `fixture`, kept by it (fixture->supports, freed with
 * it; any supports it had are freed first).  Errors as wr_supports_new's. */
wr_status wr_fixture_set_supports(wr_fixture *fixture, const wr_support_spec *spec,
                                  wr_error *error);

/* The support function of S in the physical metric: the largest w . s over
 * s in S, for a row w = (w_x, w_y, w_tau) of wrench space; equal to
 * max over P of sum_i mu_s N_i |v_i(w)|, v_i(w) = (w_x - w_tau y_i,
 * w_y + w_tau x_i) with (x_i, y_i) = p_i - com. */
double wr_supports_support_function(const wr_fixture *fixture, const wr_supports *supports,
                                    const double row[3]);

/* Seating of one wrench: per excluded cone of G_goal the least scale rho*
 * of S at which g reaches C + rho S, bracketed [lo, hi] (hi - lo within
 * the tolerance of max(1, lo)); INFINITY when no scale does.  The verdict:
 * inside when the smallest lo exceeds 1 + tolerance, outside when some hi
 * is below 1 - tolerance, boundary otherwise.  With W = 0 (S = {0}) rho is
 * 0 on the cones holding g and INFINITY elsewhere, as wr_classify's goal
 * verdict. */
typedef struct wr_support_goal {
    wr_verdict verdict;
    double rho_lo, rho_hi;   /* of the blocking cone (the least rho*) */
    int blocking;            /* its goal cone, or -1 when none can be reached */
    int solves;              /* LPs solved */
} wr_support_goal;

wr_status wr_supports_goal(const wr_analysis *analysis, const wr_supports *supports,
                           wr_lp_env *env, const double wrench[3], double tolerance,
                           wr_support_goal *out);

/* Holding of one wrench (the part seated, at rest): inside (held) when no
 * direction of any moving mode is consistent, by a margin: each cell's
 * LP misses g by more than tolerance * max(|g|, mu_s W) (scaled metric, L1);
 * outside (moves) with a witness: a mode, an acceleration direction and
 * the forces (contact and support) that make g; boundary when cells of
 * angular size below WR_SUPPORT_MIN_CELL stay undecided or the budget of
 * WR_SUPPORT_MAX_CELLS cells per mode runs out. */
#define WR_SUPPORT_MIN_CELL 1e-7
#define WR_SUPPORT_MAX_CELLS 20000
typedef struct wr_support_strong {
    wr_verdict verdict;
    int blocking;                 /* the strong cone (mode) of the witness or
                                     of an undecided cell; -1 when held */
    double acceleration[3];       /* the witness: a unit physical direction
                                     (a_x, a_y, alpha) scaled as wr_witness's */
    double force[WR_MAX_FIXELS][2]; /* (c_n, c_t) per fixel */
    double support_force[WR_MAX_SUPPORTS][2]; /* each support's friction on the part */
    double normal[WR_MAX_SUPPORTS]; /* the distribution of the witness */
    int cells;                    /* cells looked at, every mode */
    int solves;
} wr_support_strong;

wr_status wr_supports_strong(const wr_analysis *analysis, const wr_supports *supports,
                             wr_lp_env *env, const double wrench[3], double tolerance,
                             const wr_stop *stop, wr_support_strong *out);

/* The disturbance margin on the plate (docs/MODEL.md section 11, "The
 * disturbance margin"): in the scaled metric of the floating one, not
 * normalised (model-system force units), the distance from the bias b to
 * the closed set U of wrenches under which the seated part is not held --
 * the union over moving modes and their directions q of the wrenches a
 * consistent motion makes (wr_supports_strong's model).
 *
 * b held: margin = lo > 0 and bracket [lo, hi]: lo certified (the least
 * lower bound over a branch and bound on the cells of directions, each an
 * LP whose set holds every consistent wrench of its cell, its distance
 * measured in a polyhedral norm no larger than the Euclidean one), hi
 * attained (b + hi * worst_direction is a consistent wrench of mode
 * `blocking`, found by the exact LP at one direction).  Cells are split
 * until lo is within WR_SUPPORT_MARGIN_TOLERANCE of hi (converged) or
 * WR_SUPPORT_MARGIN_CELLS cells are solved (the bracket as it stands).
 *
 * b moves the part: the margin is minus the distance from b to the held
 * set, bracketed: margin = bracket[0] = -hi, hi the distance to a wrench
 * proved held (wr_supports_strong inside: along the nearest face's normal
 * of the witness's set, else towards the zero wrench), which is b + hi *
 * worst_direction; bracket[1] = -lo, lo b's depth in the convex set of the
 * witness's direction alone (its friction fixed, its cone of motion and
 * contact forces), a lower bound: every wrench nearer is still in it.  hi
 * is INFINITY when no held wrench is found (bracket[0] -INFINITY), and
 * the margin is then bracket[1].
 *
 * bounded false (the rest zero): no moving mode, nothing moves the part.
 * WR_OK, WR_INVALID (a bias not finite), WR_LP_FAILED, WR_NO_MEMORY,
 * WR_STOPPED. */
#define WR_SUPPORT_MARGIN_TOLERANCE 1e-6
#define WR_SUPPORT_MARGIN_CELLS 4000
typedef struct wr_support_margin {
    bool bounded;
    bool held;               /* b proved held (margin > 0) */
    bool moves;              /* b moves the part (a consistent motion found) */
    double margin;
    double bracket[2];       /* the signed margin lies in it */
    bool converged;          /* bracket within the tolerance (relative) */
    int blocking;            /* the strong cone (mode) of the nearest motion,
                                or of the witness when b moves */
    double worst_direction[3]; /* a physical wrench of unit scaled length */
    int cells, solves;
} wr_support_margin;

wr_status wr_supports_margin(const wr_analysis *analysis, const wr_supports *supports,
                             wr_lp_env *env, const double bias[3], const wr_stop *stop,
                             wr_support_margin *out);

/* The same supports with mu_B = mu (static and kinetic, no interval), into
 * *out: a shallow copy sharing `supports`' distributions, valid while it
 * is, never passed to wr_supports_free. */
void wr_supports_with_friction(const wr_supports *supports, double mu, wr_supports *out);

/* Seating against the supports' static coefficient mu_B (the fixture's own
 * ignored): S grows linearly with mu_B and C + rho S with rho, so the
 * wrench seats for mu_B in [0, mu*) exactly, mu* the least scale of the
 * supports' friction at mu_B = 1 at which the wrench reaches a goal cone
 * (0 when it is in one; INFINITY when no scale reaches one, or nothing
 * presses the part and the wrench seats).  mu* is bracketed in
 * [bracket[0], bracket[1]], within WR_DEFAULT_TOLERANCE of max(1, mu*);
 * a cone whose programme GLPK cannot solve brackets its own limit by
 * [0, INFINITY] (nothing proved to seat).  WR_OK, WR_INVALID (a non-finite
 * wrench). */
wr_status wr_supports_friction_limit(const wr_analysis *analysis, const wr_supports *supports,
                                     wr_lp_env *env, const double wrench[3], double bracket[2]);

/* The magnitudes F in [lo, hi] with load + F push seating the part on its
 * supports (the good magnitudes of G_goal with S), into `out` as
 * wr_force_range's; per cone the excluded magnitudes are one closed
 * interval (C + S is convex), whose ends are found from outside: the
 * answer never holds a magnitude that does not seat, and misses none by
 * more than WR_FORCE_TOLERANCE relative.  WR_OK, WR_INVALID (as
 * wr_force_range), WR_NO_MEMORY, WR_LP_FAILED. */
wr_status wr_supports_force_range(const wr_analysis *analysis, const wr_supports *supports,
                                  wr_lp_env *env, const double load[3], const double push[3],
                                  double lo, double hi, wr_forces *out);

/* The least magnitude that seats under every case, as wr_least_force_at:
 * INFINITY when none does.  Also the certified lower bound (from the
 * polygons inside the discs): no magnitude below `lower` seats. */
wr_status wr_supports_least_force(const wr_analysis *analysis, const wr_supports *supports,
                                  wr_lp_env *env, const double (*loads)[3], int case_count,
                                  const double push[3], double *force, double *lower);

/* The point of a polygon's outline where the least push seats the part on
 * its supports under every case (wr_least_force_find's question on the
 * plate, G_goal with S), for a point finger (radius 0; its push_on kept).
 * By branch and bound over pieces of each edge: the bound of a piece is
 * the component from 0 of the union over cones and cases of the
 * magnitudes that the inner polygons' spans at both its ends share (the
 * push's wrench is affine along an edge, so the magnitudes of a cone
 * grown by S form a convex set in (F, F t): what both ends exclude, every
 * point between excludes); a point's force is the outer polygons' (a
 * push just above it seats).  Split until the lowest bound is within
 * 1e-6 (relative) of the least force found, or WR_SUPPORT_MAX_POINTS
 * points are evaluated (converged false; `lower` still certified).
 * WR_OK; WR_NO_SHAPE; WR_INVALID (not a polygon, a finger radius, no
 * case, a non-finite load); WR_NO_MEMORY; WR_LP_FAILED; WR_STOPPED. */
#define WR_SUPPORT_MAX_POINTS 4000
wr_status wr_supports_least_force_find(const wr_analysis *analysis,
                                       const wr_supports *supports, wr_lp_env *env,
                                       const double (*loads)[3], int case_count,
                                       const wr_finger *finger, const wr_stop *stop,
                                       wr_least_force *out);

/* The in-plane tilt on the plate: the tilts phi (degrees, the direction the
 * in-plane part of gravity pulls, as wr_gravity_sweep's) under which the
 * wrench m a (cos phi, sin phi, 0), a = in_plane_g (length / s^2, > 0),
 * seats the part on its supports (G_goal with S; the supports' own g is the
 * part of gravity into the plate).  `good`: arcs proved to seat, every
 * point; `undecided`: arcs neither proved to seat nor proved not to (where
 * the circle meets some C + S's boundary), each of at most
 * WR_SUPPORT_MIN_ARC degrees unless WR_SUPPORT_MAX_CELLS splits did not
 * settle the circle, when the arcs still open are left undecided whole;
 * the rest is proved not to seat.  Both in order, split
 * at 0.  Per arc and cone: C + S's slice at zero torque is convex and holds
 * 0, so the arc is in it when its ends and its tangents' crossing are
 * (inner polygons), and misses it when the slice's support function along
 * the middle is below the chord's distance (outer).  WR_OK, WR_INVALID
 * (in_plane_g not positive and finite), WR_NO_MEMORY, WR_LP_FAILED,
 * WR_STOPPED (both empty on failure). */
#define WR_SUPPORT_MIN_ARC 1e-6
wr_status wr_supports_gravity_sweep(const wr_analysis *analysis, const wr_supports *supports,
                                    wr_lp_env *env, double in_plane_g, const wr_stop *stop,
                                    wr_regions *good, wr_regions *undecided);

/* Push regions on the plate: the open intervals of t on polygon edge
 * `edge` where a frictionless finger pushing with magnitude `force` along
 * the inward normal, plus each case's load, seats the part on its supports
 * (G_goal with S, under every case), appended to `regions`.  On a straight
 * edge the push's wrench is affine in t, so each C + S holds one interval
 * of t, found as wr_supports_force_range finds one of F.  WR_OK;
 * WR_INVALID (not a polygon, an edge out of range, a force not positive
 * and finite, no case); WR_NO_MEMORY; WR_LP_FAILED. */
wr_status wr_supports_push_regions(const wr_analysis *analysis, const wr_supports *supports,
                                   wr_lp_env *env, double force, const double (*loads)[3],
                                   int case_count, int edge, wr_regions *regions);

#ifdef __cplusplus
}
#endif

#endif
