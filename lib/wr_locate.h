/* wr_locate.h -- locating accuracy (docs/MODEL.md section 9): where the
 * seated part ends up when each locator is off along its normal by up to
 * its tolerance, linearly (the locating matrix and its inverse) and exactly
 * (the pose solved on the outline's lines and arcs).
 *
 * Pose: the part point x moves to c + d + R(dtheta) (x - c), c the centre
 * of mass, d = (dx, dy), dtheta in radians, counter-clockwise positive.
 * Locator i moves by e_i along its normal n_i (into the part: e_i > 0
 * pushes the part away).  Lengths are in the fixture's length unit.
 *
 * Scope: a part with a shape, seated by 3 fixels (a circle: by 2, whose
 * turning about its centre moves no contact and is taken as 0).  Any other
 * fixture is refused by wr_locate with the reason saying what is missing. */
#ifndef WR_LOCATE_H
#define WR_LOCATE_H

#include "wr_fixture.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The 99.73 % ellipse: chi-square of 2 degrees of freedom at that
 * probability, -2 ln(1 - 0.9973). */
#define WR_LOCATE_CHI2 11.829007011943707
/* A feature farther than this fraction of the part's size outside its
 * outer boundary is refused (no point of the part lies there). */
#define WR_LOCATE_FEATURE_REACH 0.1
/* The exact pose's residual: every contact equation within this fraction
 * of the part's size. */
#define WR_LOCATE_RESIDUAL 1e-12
/* Smallest singular value of the scaled locating matrix, relative to its
 * largest, below which the fixels do not determine the pose. */
#define WR_LOCATE_RANK 1e-9

/* One point of the part, and where the locators' errors take it. */
typedef struct wr_locate_feature {
    double at[2];           /* in: the point, in the fixture's frame */
    /* out: the worst displacement over the tolerance box's vertices, of
     * the linear model and of the exact pose (the vertex's vector and its
     * length; the first vertex of the largest, vertices in the order of
     * wr_locate_vertex). */
    double linear[2];
    double linear_length;
    double exact[2];
    double exact_length;
    double covariance[3];   /* [[a, b], [b, d]] as (a, b, d) */
    double axes[2];         /* semi-axes of the 99.73 % ellipse, major first */
    double angle_deg;       /* of the major axis from +x, in (-90, 90] */
} wr_locate_feature;

/* What wr_locate answers.  When `deterministic` is false only
 * free_motion's fields are written. */
typedef struct wr_locating {
    bool deterministic;
    /* The motion the fixels leave free (deterministic false): a twist
     * (vx, vy, w), the velocity of the centre of mass and the angular
     * velocity, of length 1 in the scaled metric (vx, vy, rho w), w > 0 for
     * a rotation; for a translation its first nonzero component is
     * positive.  A rotation turns about `about`. */
    double twist[3];
    bool rotation;
    double about[2];
    int fixel_count;
    /* G^-1: row j is (dx, dy, dtheta)[j] per unit e_i, column i fixel i.
     * For a circle with 2 fixels the dtheta row is 0. */
    double sensitivity[3][3];
    /* The condition number of the scaled locating matrix (rows
     * (n_i, (p_i - c) x n_i / rho)): its largest singular value over its
     * smallest, which does not depend on the units. */
    double condition;
    double pose_linear[3];  /* worst |dx|, |dy|, |dtheta| over the box */
    double pose_exact[3];
    /* The largest exact pose over the box's vertices in the scaled metric,
     * |(dx, dy, rho dtheta)|: one length for the pose's error. */
    double pose_scaled;
} wr_locating;

/* Vertex v of the tolerance box, 0 <= v < 2^k: e_i = +t_i where bit i of
 * v is set, else -t_i. */
void wr_locate_vertex(const double *tolerance, int k, unsigned v, double *e);

/* The exact seated pose (dx, dy, dtheta) when locator i is moved by e[i]
 * along its normal, for a fixture wr_locate accepts: each locator, a point
 * where the outline is smooth, lies on the displaced outline (on the same
 * segment, or the neighbour it passes onto); at a corner of the outline the
 * locator is a face with normal n_i through p_i + e_i n_i, and the corner
 * lies on it.  Newton's method on the three equations from the linear
 * solution (from intermediate displacements if that fails), verified:
 * each equation's residual within WR_LOCATE_RESIDUAL of the part's size.
 * WR_OK; WR_INVALID (a locator passes a corner of the outline, or no pose
 * meets the equations) with `error` saying which fixel, or the refusals of
 * wr_locate. */
wr_status wr_locate_pose(const wr_fixture *fixture, const double *e, double pose[3],
                         wr_error *error);

/* How far p lies outside the part's outer boundary (0 inside it, or in a
 * hole); a fixture without a shape: 0. */
double wr_locate_outside(const wr_fixture *fixture, const double p[2]);

/* Locating accuracy of `fixture` under tolerances t_i >= 0 (tolerance[i],
 * one per fixel) and sigma_i = t_i / sigma_ratio, for `count` features
 * (their `at` read, every other field written).  Into *out.
 *
 * WR_OK.  WR_NO_SHAPE: no outline (field "fixture.body.shape").
 * WR_INVALID, `error` naming the field ("tolerance[i]", "sigma_ratio",
 * "features[i].at", "fixture.fixels", "fixture.fixels[i].normal") and
 * saying why: a tolerance negative or not finite, sigma_ratio not positive
 * and finite, a feature not finite or farther outside the part than
 * WR_LOCATE_FEATURE_REACH of its size (the reason says how far); a fixture
 * out of scope (too few fixels, saying the motion left free; too many; a
 * circle with 3); a locator on a smooth part of the outline whose normal is
 * not the outline's (a point locator's contact normal is the outline's);
 * and wr_locate_pose's.  A 3-fixel fixture whose fixels do not determine
 * the pose is WR_OK with deterministic false. */
wr_status wr_locate(const wr_fixture *fixture, const double *tolerance, double sigma_ratio,
                    wr_locate_feature *features, size_t count, wr_locating *out,
                    wr_error *error);

#ifdef __cplusplus
}
#endif

#endif
