/* wr_symmetry.h -- a part's symmetries, and candidate designs that they map
 * onto each other (docs/PROTOCOL.md, fixture.design, "symmetries").
 *
 * A symmetry is a rotation or a reflection g(p) = L p + o that maps the
 * part onto itself: its shape, and its mass properties.  The mass and the
 * moment of inertia about the centre of mass are scalars, unchanged by any
 * isometry; the centre of mass must be fixed, g(com) = com.  So every
 * symmetry turns about, or mirrors through a line through, the centre of
 * mass (for a uniform lamina the centroid, which every symmetry of the
 * outline fixes; a centre of mass given elsewhere leaves only those that
 * fix it).
 *
 * The shape maps onto itself when, within WR_SYMMETRY_TOLERANCE of its
 * size, every vertex of every loop maps onto a vertex, one to one, and every
 * segment onto a segment: a line onto a line, an arc onto an arc of the same
 * bulge, turned the other way by a reflection.  This is the rule: a part
 * drawn symmetric (arrayed, mirrored) has its vertices where the symmetry
 * puts them; the same geometry cut into different segments on two sides is
 * not found symmetric.  A circle's symmetries are those of its candidate
 * sites (below): the rotations and reflections about its centre, which
 * must be the centre of mass, that map the site set onto itself.
 *
 * Designs: a fixture's fixels mapped by a symmetry, with the part and its
 * friction, make the same fixture seen after the isometry: every figure of
 * a design (margins, region lengths, the gravity arc, the critical
 * friction) is the same for both, and its pushes and regions are the
 * images.  So candidates that a symmetry maps onto each other are one
 * design, counted once, with the number of copies it stands for. */
#ifndef WR_SYMMETRY_H
#define WR_SYMMETRY_H

#include "wr_design.h"
#include "wr_outline.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Points within this fraction of the part's size are the same point; unit
 * normals within it (as vectors) the same direction; bulges within it
 * (relative to 1 + |bulge|) the same. */
#define WR_SYMMETRY_TOLERANCE 1e-6
/* At most this many symmetries are kept: a regular n-gon has 2n. */
#define WR_SYMMETRY_MAX (2 * WR_OUTLINE_MAX_VERTICES)

typedef struct wr_symmetry {
    bool reflection;       /* false: a rotation (the identity is one, by 0) */
    double angle_deg;      /* a rotation: the turn, counter-clockwise, in
                              [0, 360); a reflection: the direction of its
                              mirror line, in [0, 180) */
    double center[2];      /* the fixed point: the centre of mass */
    double linear[2][2];   /* g(p) = linear p + offset */
    double offset[2];
} wr_symmetry;

/* The symmetries of `body` (wr_fixture_body_new), the identity first, then
 * rotations by increasing angle, then reflections by increasing angle:
 * into *out (malloc'd, *count items; the caller frees it).  A polygon's or
 * an outline's are found from the shape alone (`sites` ignored); a circle's
 * from the sites (site_count of them).  Without a shape: the identity.
 * WR_OK; WR_NO_MEMORY (*out NULL). */
wr_status wr_symmetry_find(const wr_fixture *body, const wr_site *sites, int site_count,
                           wr_symmetry **out, int *count);

/* Keep, of `count` symmetries in `list`, those that also map the rest of a
 * design's question onto itself: every loop the finger may push on onto a
 * loop it may push on (push_on), and every load case (a physical wrench
 * (f_x, f_y, tau), tau about the centre of mass) onto itself: its force
 * turned by g and its torque, about the fixed centre, kept by a rotation
 * and negated by a reflection (within WR_SYMMETRY_TOLERANCE of the
 * wrench's size).  In place, in order; returns how many are kept (the
 * identity always is). */
int wr_symmetry_filter(const wr_fixture *body, const wr_finger *finger, const double (*loads)[3],
                       int case_count, wr_symmetry *list, int count);

/* Keep, of `count` symmetries in `list`, those that map the set of
 * `point_count` points onto itself (each image within WR_SYMMETRY_TOLERANCE
 * * size of one of the points): a question that weighs points of the part
 * by their worst (the features of a design's objective accuracy) asks the
 * same of a candidate and of its image under these alone.  In place, in
 * order; returns how many are kept (the identity always is). */
int wr_symmetry_filter_points(const double (*points)[2], int point_count, double size,
                              wr_symmetry *list, int count);

/* g(p), and g's linear part applied to a direction (a normal). */
void wr_symmetry_point(const wr_symmetry *g, const double p[2], double out[2]);
void wr_symmetry_direction(const wr_symmetry *g, const double v[2], double out[2]);

/* Where g takes each site: map[i] = the lowest j whose site is g's image
 * of site i (point and normal within the tolerance), or -1 when no site
 * is.  `size` is the part's (the body's size).  WR_OK; WR_NO_MEMORY. */
wr_status wr_symmetry_site_map(const wr_symmetry *g, const wr_site *sites, int site_count,
                               double size, int *map);

#ifdef __cplusplus
}
#endif

#endif
