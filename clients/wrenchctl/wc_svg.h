/* wc_svg.h -- pictures of answers, drawn like the seed's figures 3f, 7 and
 * 8: the part's outline in grey, the fixels as small wedges with their
 * friction cones, the centre of mass, the answer in thick black, a legend.
 *
 * An outline of lines and arcs (issue 16) is one <path class="outline">,
 * each loop a closed subpath, straight segments as lines and arcs as SVG
 * arcs, with fill-rule evenodd so that holes are holes; a push region on an
 * arc is an arc.  A fixel on a hole's boundary is a pin in the hole (a
 * <circle class="fixel pin">), with an arrow (class "fixel-normal") along
 * its normal into the material.
 *
 * Every region (a push region, a gravity arc) is one <path class="region">,
 * so a reader (or a test) can count them; nothing else is a path of that
 * class.  Coordinates: the fixture's, y up, scaled to fit. */
#ifndef WC_SVG_H
#define WC_SVG_H

#include "wrench.h"

#include <stdio.h>

/* The push region of a set: `regions` as wr_push_regions gives them (on an
 * outline, edge counts the segments of every loop, loop 0's first).
 * finger_radius < 0: none was asked for, and the legend names none. */
void wc_svg_push(FILE *out, const wr_fixture *fixture, const char *name, const char *set,
                 const wr_region *regions, int count, double fraction, double finger_friction,
                 double finger_radius);

/* The gravity sweep as a dial around the part: arcs of tilt, in degrees. */
void wc_svg_gravity(FILE *out, const wr_fixture *fixture, const char *name, const char *set,
                    const wr_region *arcs, int count);

/* A biasing wrench, drawn along its line of action, and the worst
 * disturbance direction; `blocking` may be NULL (nothing moves the part). */
void wc_svg_margin(FILE *out, const wr_fixture *fixture, const char *name, const double bias[3],
                   double margin, const double worst_direction[3], const char *blocking);

/* What a set's push region or tilt promises, in one line ("goal: reaches
 * every fixel, then the part may slide on; ..."): G_goal does not promise
 * the part rests, G_strong does not promise it seats; "both" is what to
 * push with and let go. */
const char *wc_set_promise(const char *set);

#endif
