/* wc_svg.h -- pictures of answers, drawn like the seed's figures 3f, 7 and
 * 8: the part's outline in grey, the fixels as small wedges with their
 * friction cones, the centre of mass, the answer in thick black, a legend.
 *
 * Every region (a push region, a gravity arc) is one <path class="region">,
 * so a reader (or a test) can count them; nothing else is a path of that
 * class.  Coordinates: the fixture's, y up, scaled to fit. */
#ifndef WC_SVG_H
#define WC_SVG_H

#include "wrench.h"

#include <stdio.h>

/* The push region of a set: `regions` as wr_push_regions gives them. */
void wc_svg_push(FILE *out, const wr_fixture *fixture, const char *name, const char *set,
                 const wr_region *regions, int count, double fraction, double finger_friction);

/* The gravity sweep as a dial around the part: arcs of tilt, in degrees. */
void wc_svg_gravity(FILE *out, const wr_fixture *fixture, const char *name, const char *set,
                    const wr_region *arcs, int count);

/* A biasing wrench, drawn along its line of action, and the worst
 * disturbance direction; `blocking` may be NULL (nothing moves the part). */
void wc_svg_margin(FILE *out, const wr_fixture *fixture, const char *name, const double bias[3],
                   double margin, const double worst_direction[3], const char *blocking);

#endif
