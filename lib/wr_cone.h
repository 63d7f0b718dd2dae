/* wr_cone.h -- constraint strings and the explicit wrench cone G_X of
 * docs/MODEL.md section 2.
 *
 * G_X is the set of external wrenches g for which some acceleration q and
 * contact forces c satisfy Newton-Euler and every fixel's letter of X.  It is
 * computed as G_X = M Q_X - W C_X: generators of both parts, then facets by
 * 3-D geometry.  All geometry is in the scaled space h = (f_x, f_y, tau/rho)
 * of docs/MODEL.md section 5, where the metric does not depend on units. */
#ifndef WR_CONE_H
#define WR_CONE_H

#include "wr_fixture.h"

#include <stdbool.h>

#ifdef __cplusplus
extern "C" {
#endif

/* A constraint string: one letter per fixel, in fixel order, over "saulrnm"
 * (docs/MODEL.md section 2).  As a contact mode (docs/MODEL.md section 4) `s` is strictly
 * separating, and an unpinned body's pivots are n...n with a sign. */
typedef struct wr_constraint {
    int length;                        /* = the fixture's fixel count */
    char letters[WR_MAX_FIXELS + 1];   /* NUL-terminated */
    bool strict_separation;            /* mode semantics: s means a_n > 0 */
    int pivot;                         /* +1 n...n+ (alpha > 0), -1 n...n-, else 0 */
} wr_constraint;

/* Text form: the letters, then "+" or "-" for a pivot.  Needs
 * WR_MAX_FIXELS + 2 bytes. */
#define WR_CONSTRAINT_TEXT (WR_MAX_FIXELS + 2)

/* Parse `text` (letters only) for a fixture of `fixel_count` fixels.  On a bad
 * letter or length, returns WR_INVALID and sets error->reason (field left
 * empty). */
wr_status wr_constraint_parse(const char *text, int fixel_count, wr_constraint *out,
                              wr_error *error);
void wr_constraint_format(const wr_constraint *constraint, char text[WR_CONSTRAINT_TEXT]);

/* The order of letters (docs/MODEL.md section 2): s, a below u; l, r, n
 * below m; each letter below itself; strings letter by letter.  X below Y implies G_X inside G_Y. */
bool wr_letter_below(char x, char y);
bool wr_constraint_below(const wr_constraint *x, const wr_constraint *y);

/* Where a generator of a cone comes from, to turn a point of the cone back
 * into an acceleration and contact forces (a witness). */
typedef struct wr_generator_origin {
    int fixel;            /* -1: a direction of the acceleration part M Q_X */
    double normal_force;  /* c_n per unit coefficient (physical units) */
    double tangent_force; /* c_t per unit coefficient */
} wr_generator_origin;

/* The explicit cone of one constraint string on one fixture. */
typedef struct wr_cone {
    wr_constraint constraint;
    bool empty;                 /* no wrench at all satisfies X */
    int dimension;              /* of closure(G_X), 0..3; -1 when empty */
    bool zero_admitted;         /* g = 0 satisfies X (strict rows honoured) */
    int equality_count;         /* rows with E h = 0 on the cone: 3 - dimension */
    double equalities[3][3];    /* orthonormal, scaled space */
    int facet_count;
    double (*facets)[3];        /* unit rows, scaled: f . h <= 0 on the closure */
    bool *facet_open;           /* the facet's relative interior is outside
                                   G_X (a strict row makes it an open face) */
    int ray_count;
    double (*rays)[3];          /* minimal generators, scaled: both signs of a
                                   lineality basis, then extreme rays */
    int generator_count;
    double (*generators)[3];    /* the generators M Q_X and -W C_X, unit, scaled */
    wr_generator_origin *origins; /* one per generator */
} wr_cone;

/* Compute the cone of `constraint` (whose length must equal the fixture's
 * fixel count).  WR_OK, or WR_NO_MEMORY.  Release with wr_cone_release()
 * either way. */
wr_status wr_cone_build(wr_cone *cone, const wr_fixture *fixture,
                        const wr_constraint *constraint);
void wr_cone_release(wr_cone *cone);

/* Signed distance of a unit scaled wrench x to closure(G_X), docs/MODEL.md section 5:
 * its distance when outside, minus its depth (distance to the complement)
 * when inside.  +INFINITY for an empty cone.  `projection` (may be NULL)
 * receives the nearest point of the closure. */
double wr_cone_signed_distance(const wr_cone *cone, const double x[3], double projection[3]);

/* A witness (docs/MODEL.md section 5): an acceleration and contact forces satisfying
 * the constraint's closure, and the wrench they make by Newton-Euler. */
typedef struct wr_witness {
    double acceleration[3];            /* (a_cx, a_cy, alpha), physical */
    double force[WR_MAX_FIXELS][2];    /* (c_n, c_t) per fixel, physical */
    double wrench[3];                  /* M q - sum(W_n c_n + W_t c_t) */
    /* Per fixel the coefficient its letter uses, at which the forces
     * satisfy the letter (docs/PROTOCOL.md, friction intervals): static
     * for n and m (the upper bound), kinetic for l and r (-c_t / c_n,
     * resp. c_t / c_n, clamped into the interval; its lower bound when
     * c_n = 0); NAN for s, a and u, which use none. */
    double friction[WR_MAX_FIXELS];
    /* On supports (wr_support.h), a motion's witness: each support's
     * friction force on the part (f_x, f_y) and its normal force N_i in the
     * witness's distribution, physical, and `wrench` then subtracts the
     * supports' wrenches too.  support_count is 0 otherwise. */
    int support_count;
    double support_force[WR_MAX_SUPPORTS][2];
    double support_normal[WR_MAX_SUPPORTS];
} wr_witness;

/* Fill in witness->friction from its forces and the constraint's letters. */
void wr_witness_friction(const wr_fixture *fixture, const wr_constraint *constraint,
                         wr_witness *witness);

/* Express `point` (a scaled wrench in the closure of the cone, any length) as
 * an acceleration and contact forces: a non-negative combination of the
 * cone's generators, found by non-negative least squares. */
void wr_cone_witness(const wr_cone *cone, const wr_fixture *fixture, const double point[3],
                     wr_witness *out);

/* The physical wrench M q - sum_i (W_in c_in + W_it c_it). */
void wr_newton_euler_wrench(const wr_fixture *fixture, const double acceleration[3],
                            const double (*force)[2], double wrench[3]);

#ifdef __cplusplus
}
#endif

#endif
