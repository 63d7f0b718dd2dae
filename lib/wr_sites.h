/* wr_sites.h -- candidate sites of a design (docs/PROTOCOL.md,
 * fixture.design, "Candidate sites"): points of a body's boundary where a
 * fixel may go, each with the normal a fixel there would have; on a hole's
 * wall, a pin.
 *
 * Sites by arc length.  On an outline each loop is measured along its
 * length, across the joints between its segments.  A joint is a corner
 * when the boundary turns there by more than WR_SITE_CORNER_DEG (the
 * normals of the two segments meeting there differ by more): a curve drawn
 * as many short segments (a faceted arc) has no corners, a rectangle four.
 * The corners cut a loop into runs; a run of length L gets, clear of the
 * corners at its ends by c (the corner clearance), n = floor((L - 2c) / h)
 * + 1 sites h apart, centred on the run (none when L < 2c).  A loop without
 * corners is one closed run of length P: n = floor(P / h) sites P / n
 * apart, the first at the loop's vertex 0.  A site takes the boundary's
 * normal: its segment's, or at a joint (not a corner) the bisector of the
 * two segments' normals.  Sites are numbered loop by loop, and within a
 * loop by their distance along it from vertex 0 in the direction written.
 * With c = h / 2 and a corner at every joint this is floor(L / h) sites
 * per segment, h apart, centred.  A circle body: floor(2 pi R / h) sites
 * at the angles 2 pi k / n.
 *
 * Pins.  A site on a hole's wall is a pin in the hole: a disc of its
 * diameter (0: a point) inside the hole, touching the wall at the site,
 * centred at at - (diameter / 2) normal.  It fits there when the disc
 * overlaps no part of the workpiece, as a finger's would (wr_finger.h).  A
 * design never puts two fixels in one hole (wr_design.h). */
#ifndef WR_SITES_H
#define WR_SITES_H

#include "wr_fixture.h"
#include "wr_status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* At most this many candidate sites. */
#define WR_DESIGN_MAX_SITES 100000
/* A joint of a loop where the boundary turns by more than this many
 * degrees is a corner. */
#define WR_SITE_CORNER_DEG 20.0

/* A candidate site: a boundary point and its unit inward normal, as a
 * fixel there would have them; the loop it lies on (0: the outer boundary,
 * a polygon's or a circle's boundary; > 0: a hole, and the site is a pin)
 * and, on a hole, the pin's diameter. */
typedef struct wr_site {
    double at[2];
    double normal[2];
    int loop;
    double pin_diameter;
} wr_site;

/* The site at `at` on `body` (from wr_fixture_body_new), with `normal`
 * (NULL: the boundary's, required at a corner): checked as a fixel there
 * would be; a pin of diameter 0 if on a hole.  WR_OK, or WR_INVALID with
 * `error` ("fixels[0].at" and the like: the caller renames the field). */
wr_status wr_site_new(const wr_fixture *body, const double at[2], const double *normal,
                      wr_site *out, wr_error *error);

/* A pin of diameter `diameter` in hole `hole` (a loop > 0 of the body's
 * outline), moved from `at` (its centre, or any point of the hole on the
 * way to the wall) straight to the nearest point of the hole's wall (the
 * first of equals in segment order): the site is where it touches.  It
 * must fit there (above).  WR_OK; WR_INVALID with `error`, its field
 * "hole" (not a hole of the body), "diameter" (negative, not finite) or ""
 * (`at` in the material, the pin does not fit, the wall has no normal
 * there); WR_NO_MEMORY. */
wr_status wr_site_pin(const wr_fixture *body, int hole, double diameter, const double at[2],
                      wr_site *out, wr_error *error);

/* The rule of sites by arc length. */
typedef struct wr_spacing {
    double spacing;          /* h > 0 */
    double corner_clearance; /* c > 0 */
    double pin_diameter;     /* >= 0: a site on a hole is a pin of this
                                diameter, kept only where it fits */
} wr_spacing;

/* The sites of `rule` (above), appended to *sites (malloc'd, *count
 * items).  WR_OK; WR_INVALID with the field ("spacing": not positive and
 * finite, or more than WR_DESIGN_MAX_SITES sites; "corner_clearance";
 * "pin_diameter"); WR_NO_MEMORY (*sites as it was). */
wr_status wr_sites_spaced(const wr_fixture *body, const wr_spacing *rule, wr_site **sites,
                          int *count, wr_error *error);

#ifdef __cplusplus
}
#endif

#endif
