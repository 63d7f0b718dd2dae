/* wr_fixture.h -- the fixture model of docs/MODEL.md section 1: a planar workpiece, its
 * shape and the point contacts ("fixels") that seat it.
 *
 * A caller describes a fixture with a wr_fixture_spec (borrowed memory,
 * optional fields flagged), and wr_fixture_new() validates it into a
 * wr_fixture (owned, every optional value filled in).  Field paths in errors
 * mirror the JSON of docs/PROTOCOL.md ("fixels[2].normal", "body.mass"), so the
 * protocol layer only has to prefix them.
 *
 * Units: any consistent set, or those a fixture names (wr_units).  Angles
 * nowhere.  The frame is the fixture's. */
#ifndef WR_FIXTURE_H
#define WR_FIXTURE_H

#include "wr_status.h"

#include <stdbool.h>
#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

/* At most 8 fixels: G_goal has k * 2^(k-1) cones (1024 at k = 8). */
#define WR_MAX_FIXELS 8
/* At most this many supports under the part (wr_support.h). */
#define WR_MAX_SUPPORTS 16
/* A polygon outline has at most this many vertices (the simplicity check is
 * quadratic in it). */
#define WR_MAX_VERTICES 4096
/* Larger friction coefficients are refused: no contact has them, and beyond
 * about 1e8 the friction-cone edges come within the rank tolerance of the
 * tangent, so the cones would lose a dimension. */
#define WR_MAX_FRICTION 1000.0
/* The radius of gyration sqrt(I/m) must lie within this factor of the
 * part's size (without a shape: of the fixels' lever arms about the centre
 * of mass), and a given shape's centre of mass within one size of its
 * bounding box: beyond them torques, scaled by 1/rho, swamp the forces in
 * double precision (and no rigid body has its centre of mass outside it). */
#define WR_GYRATION_RANGE 1e4
/* Fixels at distinct points must spread over at least this fraction of
 * the radius of gyration: closer, their torque rows differ only in digits
 * that rounding decides (no fixture puts all its locators within 0.1 %
 * of the part's size of each other). */
#define WR_FIXEL_SPREAD 1e-3

typedef enum wr_shape_type {
    WR_SHAPE_NONE = 0, /* no outline: com and inertia are then required */
    WR_SHAPE_CIRCLE,
    WR_SHAPE_POLYGON,
    WR_SHAPE_OUTLINE   /* loops of lines and arcs, holes (wr_outline.h) */
} wr_shape_type;

struct wr_loop_spec;
struct wr_outline;

/* Friction as given: static, optional kinetic (equals static when absent).
 *
 * Either coefficient may be an interval [lo, hi] (docs/PROTOCOL.md,
 * "Friction intervals"): then *_interval is set, *_min is lo and *_mu is hi.
 * Without the flag the coefficient is the point *_mu (*_min is ignored).
 * Valid: 0 <= lo <= hi <= WR_MAX_FRICTION for each, and kinetic's bounds
 * not above static's (kinetic lo <= static lo, kinetic hi <= static hi), so
 * that every value of either interval is attained by a pair mu_k <= mu_s. */
typedef struct wr_friction_spec {
    bool given;            /* false: not given here */
    double static_mu;      /* mu_s >= 0; an interval's upper bound */
    bool kinetic_given;
    double kinetic_mu;     /* 0 <= mu_k <= mu_s; an interval's upper bound */
    bool static_interval;  /* static is [static_min, static_mu] */
    double static_min;
    bool kinetic_interval; /* kinetic is [kinetic_min, kinetic_mu] */
    double kinetic_min;
} wr_friction_spec;

/* The units a fixture names (docs/MODEL.md section 1, "Units"): what one of
 * its length units is in metres and one of its force units in newtons; mass
 * is always in kilograms.  Not given: the numbers are one consistent system
 * (a force is a mass times a length per s^2) and both factors are 1.
 *
 * libwrench computes in the fixture's model system: mass kg, the fixture's
 * length unit, force kg * length / s^2.  Inertia is already in it (kg *
 * length^2) and so is G (length / s^2); a force or torque in the fixture's
 * units becomes one of the model system when multiplied by
 * wr_fixture_force_factor().  The protocol layer does that, once, where the
 * number comes in, and divides by it where a force goes out. */
typedef struct wr_units {
    bool given;
    double length_m; /* metres per length unit, > 0 */
    double force_n;  /* newtons per force unit, > 0 */
} wr_units;

typedef struct wr_fixel_spec {
    double at[2];              /* contact point, on the workpiece boundary */
    bool normal_given;
    double normal[2];          /* into the workpiece; normalised on validation
                                  unless already of unit length */
    wr_friction_spec friction; /* overrides the fixture's */
} wr_fixel_spec;

typedef struct wr_fixture_spec {
    double mass;                    /* m > 0 */
    bool inertia_given;
    double inertia;                 /* I > 0, about the centre of mass */
    bool com_given;
    double com[2];                  /* centre of mass */
    wr_shape_type shape;
    double center[2];               /* circle */
    double radius;                  /* circle */
    size_t vertex_count;            /* polygon */
    const double (*vertices)[2];    /* polygon, either orientation; borrowed */
    size_t loop_count;              /* outline: the outer loop, then holes */
    const struct wr_loop_spec *loops; /* outline; borrowed */
    wr_friction_spec friction;      /* global friction */
    size_t fixel_count;
    const wr_fixel_spec *fixels;    /* borrowed */
    wr_units units;                 /* not given: both factors 1 */
} wr_fixture_spec;

/* A fixture's geometric tolerance (wr_tolerance.h, docs/MODEL.md section
 * 10): each contact within arc length `position` of its nominal point along
 * the boundary, each normal tilted by up to `angle` degrees. */
typedef struct wr_tolerance {
    bool given;          /* false: every answer is the nominal one */
    double position;     /* >= 0, the fixture's length unit */
    double angle;        /* in [0, 90), degrees */
} wr_tolerance;

/* A validated fixel.  t = n turned +90 degrees: (-n_y, n_x). */
typedef struct wr_fixel {
    double at[2];
    double normal[2];   /* unit, into the workpiece */
    double tangent[2];  /* unit */
    /* Friction: each coefficient is an interval [*_min, *]; a point when
     * the two are equal, as every fixture without intervals has. */
    double mu_static;       /* static, upper bound */
    double mu_kinetic;      /* kinetic, upper bound */
    /* Scaled contact wrenches (docs/MODEL.md section 5 metric): for a unit normal
     * force, (n_x, n_y, (r x n) / rho); likewise for the tangent. */
    double normal_wrench[3];
    double tangent_wrench[3];
    double mu_static_min;   /* static, lower bound (<= mu_static) */
    double mu_kinetic_min;  /* kinetic, lower bound (<= mu_kinetic, <= mu_static_min) */
} wr_fixel;

/* A validated fixture; every field is filled in.  Read-only for callers.
 *
 * Invariant: writing the fixture's values back into a spec with every
 * optional field given (mass, inertia, com, shape as stored, each fixel's
 * at, normal, static and kinetic friction, intervals as intervals) and validating it gives the same
 * fixture, bit for bit.  Hence no field holds -0 (a -0 of the spec is +0:
 * text writes both as 0), and a given normal already of unit length (within
 * a few ulp, as every normalised or computed one is) is kept as given. */
typedef struct wr_fixture {
    double mass;
    double inertia;
    double com[2];
    double gyration_radius;       /* rho = sqrt(I / m): scales torque to force */
    double size;                  /* circle: diameter; polygon, outline:
                                     bounding-box diagonal (arcs included);
                                     none: spread of the fixels */
    /* The uniform lamina of the shape (0 without one): what com and
     * inertia default to, reported by fixture.put. */
    double area;
    wr_shape_type shape;
    double center[2];             /* circle */
    double radius;                /* circle */
    size_t vertex_count;          /* polygon, as given (same order) */
    double (*vertices)[2];        /* owned */
    int orientation;              /* polygon: +1 counter-clockwise, -1 not */
    /* Outline: the validated loops (owned).  Polygon: also set, its one
     * loop of straight segments built from the vertices (owned), so that
     * boundary geometry (a finger's clearance) has one form for both.
     * Circle and no shape: NULL. */
    struct wr_outline *outline;
    int fixel_count;
    wr_fixel fixels[WR_MAX_FIXELS];
    wr_units units;               /* as given; not given: both factors 1 */
    wr_tolerance tolerance;       /* set by wr_fixture_set_tolerance only */
    /* The base plate's supports under the part (wr_support.h), owned:
     * wr_fixture_free frees them.  NULL: the part floats in its plane.
     * Set once by wr_fixture_set_supports, before the fixture is shared. */
    struct wr_supports *supports;
} wr_fixture;

/* Validate `spec` and build a fixture into *out.  WR_INVALID when anything
 * is invalid, with `error` (which may be NULL) filled in: the first problem
 * found.  WR_NO_MEMORY with field "" and a reason saying so.  *out is NULL
 * unless WR_OK. */
wr_status wr_fixture_new(const wr_fixture_spec *spec, wr_fixture **out, wr_error *error);
void wr_fixture_free(wr_fixture *fixture);

/* Friction as a fixture's would be checked, its faults at `field`.  WR_OK
 * or WR_INVALID (also when not given). */
wr_status wr_friction_check(const wr_friction_spec *friction, const char *field, wr_error *error);
/* A body alone, for placing fixels on again and again (fixture.design):
 * `spec` validated as wr_fixture_new does but for its fixels, which are
 * ignored; a shape is required.  The result has no fixels. */
wr_status wr_fixture_body_new(const wr_fixture_spec *spec, wr_fixture **out, wr_error *error);
/* `body` (from wr_fixture_body_new) with `count` fixels, each with its own
 * friction or else `friction`: into *out, a shallow copy whose shape is
 * borrowed from `body` (never wr_fixture_free it; `body` must outlive it).
 * Checked exactly as wr_fixture_new checks the same fixels on the same
 * body, so it is the fixture fixture.put builds from them, bit for bit.
 * WR_OK, or WR_INVALID with `error` set (fields "fixels[i].at", ...). */
wr_status wr_fixture_place(const wr_fixture *body, const wr_fixel_spec *fixels, size_t count,
                           const wr_friction_spec *friction, wr_fixture *out, wr_error *error);

/* wr_fixture_place of fixels each already placed alone on `body` (the
 * fixels[0] of a wr_fixture_place of it by itself, with the friction the
 * list would have): only the checks of the list as a whole are made (the
 * spread, duplicates), since a fixel is built from its own spec alone.
 * The same fixture as wr_fixture_place of their specs, bit for bit, and
 * the same verdict.  WR_OK, or WR_INVALID with `error` set. */
wr_status wr_fixture_place_placed(const wr_fixture *body, const wr_fixel *fixels, size_t count,
                                  wr_fixture *out, wr_error *error);

/* The unit direction, in the scaled metric, of a physical wrench, and the
 * length of its scaled form (docs/MODEL.md section 5).  Exact for any finite wrench,
 * however large or small: it divides by the largest component first.  The
 * length may be +inf for wrenches near the largest double; for the zero
 * wrench it is 0 and `unit` is zero. */
double wr_fixture_unit_wrench(const wr_fixture *fixture, const double wrench[3], double unit[3]);
/* `value`, a figure of the unit wrench's answer (a witness's force,
 * acceleration or wrench component), scaled back to `wrench`, whose length
 * wr_fixture_unit_wrench gave: value * length, and when that length is
 * +inf, the same product made so that it overflows only where the result
 * is beyond a double. */
double wr_fixture_scale_back(const wr_fixture *fixture, const double wrench[3], double length,
                             double value);

/* Scale a physical wrench g = (f_x, f_y, tau) to (f_x, f_y, tau / rho).
 * Returns the length of the scaled wrench. */
double wr_fixture_scale_wrench(const wr_fixture *fixture, const double wrench[3],
                               double scaled[3]);
/* Inverse: a scaled wrench back to physical units. */
/* Normalise v in place, scaled first (exactly, by a power of two) so that
 * no finite v overflows or loses its digits; returns its former length
 * (+inf near the largest double), 0 leaving the zero vector as it is. */
double wr_fixture_unit_direction(double v[3]);

void wr_fixture_unscale_wrench(const wr_fixture *fixture, const double scaled[3],
                               double wrench[3]);
/* A row f of a half-space f . h <= 0 in scaled space, as a unit row in
 * physical units (f_1, f_2, f_3 / rho), normalised. */
void wr_fixture_unscale_row(const wr_fixture *fixture, const double scaled_row[3],
                            double row[3]);

/* Model-system force (kg * length / s^2) per force unit of the fixture:
 * force_n / length_m (1 without units).  A torque converts by the same
 * factor, its length being the fixture's own. */
double wr_fixture_force_factor(const wr_fixture *fixture);

/* The inward unit normal of polygon edge i (vertex i to vertex i+1). */
void wr_fixture_edge_normal(const wr_fixture *fixture, size_t edge, double normal[2]);

/* The wrench (f_x, f_y, (at - com) x force) of a force applied at a point. */
void wr_fixture_force_wrench(const wr_fixture *fixture, const double force[2],
                             const double at[2], double wrench[3]);

#ifdef __cplusplus
}
#endif

#endif
