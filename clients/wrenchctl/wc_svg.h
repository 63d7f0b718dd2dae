/* wc_svg.h -- pictures of answers, drawn like the seed's figures 3f, 7 and
 * 8: the part's outline in grey, the fixels as small wedges with their
 * friction cones, the centre of mass, the answer in thick black, a legend.
 *
 * An outline of lines and arcs is one <path class="outline">,
 * each loop a closed subpath, straight segments as lines and arcs as SVG
 * arcs, with fill-rule evenodd so that holes are holes; a push region on an
 * arc is an arc.  A fixel on a hole's boundary is a pin in the hole (a
 * <circle class="fixel pin">) at its diameter where the picture knows it
 * (a design's pins), else a dot, with an arrow (class "fixel-normal")
 * along its normal into the material.
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

/* push.force's samples of the least force F* along one edge (as
 * wr_region's edge): t and F* (NAN where no push does the job). */
typedef struct wc_force_band {
    int edge;
    int count;
    const double *t, *force;
} wc_force_band;

/* F* as a coloured band along the outline (each sample's stretch, blue at
 * the least force drawn to red at the most; grey where none works), the
 * least push as an arrow, and a legend with the colour scale in `unit`.
 * `least` NAN: no push does the job. */
void wc_svg_push_force(FILE *out, const wr_fixture *fixture, const char *name, const char *set,
                       const wc_force_band *bands, int band_count, const double at[2],
                       const double direction[2], double least, const char *unit);

/* The gravity sweep as a dial around the part: arcs of tilt, in degrees. */
void wc_svg_gravity(FILE *out, const wr_fixture *fixture, const char *name, const char *set,
                    const wr_region *arcs, int count);

/* A biasing wrench, drawn along its line of action, and the worst
 * disturbance direction; `blocking` may be NULL (nothing moves the part). */
void wc_svg_margin(FILE *out, const wr_fixture *fixture, const char *name, const double bias[3],
                   double margin, const double worst_direction[3], const char *blocking);

/* The force command's picture: the part, its fixels and supports (each
 * support's friction disc to scale), the push's wrench `push` (NULL: none
 * drawn) and the least force that seats the part (NAN or INFINITY: none),
 * in `unit`. */
void wc_svg_force(FILE *out, const wr_fixture *fixture, const char *name, const double *push,
                  double least, const char *unit);

/* An interval [low, high] of friction coefficients. */
typedef struct wc_interval {
    double low, high;
} wc_interval;

/* A friction sweep of a push region or of the gravity arcs (friction.sweep):
 * mu_s = mu and mu_k = kinetic_ratio * mu at every fixel, or (kinetic_ratio
 * 0, also in wc_svg_sweep_bands) the supports' mu_B. */
typedef struct wc_sweep_plot {
    const char *name;      /* the fixture's */
    const char *what;      /* "push" (length, the fixture's units), "gravity" (degrees) or
                              "force" (the least push force; NAN where none does it) */
    const char *force_unit; /* with "force": the unit of the forces */
    const char *set;
    double range[2];       /* of mu, the plot's horizontal axis */
    double kinetic_ratio;  /* 0: the supports' mu_B is swept instead */
    const wc_interval *intervals; /* where the region is not empty */
    int interval_count;
    double critical;       /* the mu above which it is empty; NAN: none */
    const double (*curve)[2]; /* (mu, length), increasing in mu */
    int curve_count;
    const wr_fixture *fixture; /* the unit of its lengths, when it names one; may be NULL */
} wc_sweep_plot;

/* The region's size against mu: the curve (a <polyline class="curve">),
 * each interval shaded (a <rect class="interval">), the critical mu a
 * vertical line (<line class="critical">) with its value, and what the set
 * promises. */
void wc_svg_sweep(FILE *out, const wc_sweep_plot *plot);

/* One row of a sweep of wrenches: where wrench `label` is inside `set`. */
typedef struct wc_sweep_band {
    char label[112];
    const char *set;
    const wc_interval *intervals;
    int count;
} wc_sweep_band;

/* One horizontal band per wrench and set (<rect class="band">), black
 * where the wrench is inside (one <rect class="inside"> per interval),
 * against mu over `range`; the legend says what each set in `sets`
 * promises. */
void wc_svg_sweep_bands(FILE *out, const char *name, const double range[2], double kinetic_ratio,
                        const wc_sweep_band *bands, int count, const char *const *sets,
                        int set_count);

/* One design of fixture.design, for wc_svg_designs. */
typedef struct wc_design_panel {
    const wr_fixture *fixture;    /* the body with the design's fixels */
    const wr_region *regions;     /* its both push region (wc_svg_push's edges) */
    int region_count;
    bool has_push;
    double push_at[2], push_direction[2], margin;
    int rank;
    double score;
    bool lattice;                 /* pegs: their centres in the part's frame */
    double pegs[3][2];
    int holes[3][2];
    double peg_radius;
    double pin_diameter[WR_MAX_FIXELS]; /* a pin's (the design's "pins"); -1 elsewhere */
} wc_design_panel;

/* The best designs side by side, three to a row: each part with its
 * fixels (and pegs, <circle class="peg">), its both region (<path
 * class="region">) and its best push as an arrow into the part (<line
 * class="best-push">), its rank and score; the legend says why the push
 * is both's. */
void wc_svg_designs(FILE *out, const char *name, const char *objective,
                    const wc_design_panel *panels, int count);

/* What a set's push region or tilt promises, in one line ("goal: reaches
 * every fixel, then the part may slide on; ..."): G_goal does not promise
 * the part rests, G_strong does not promise it seats; "both" is what to
 * push with and let go. */
const char *wc_set_promise(const char *set);

/* One feature of fixture.locating, for wc_svg_locate. */
typedef struct wc_locate_mark {
    const char *name;      /* NULL: unnamed */
    double at[2];
    double worst[2];       /* the exact worst displacement */
    double axes[2];        /* the 99.73 % ellipse's semi-axes, major first */
    double angle_deg;      /* of the major axis */
} wc_locate_mark;

/* Where locator errors put the part (fixture.locating): each feature a dot
 * with its 99.73 % ellipse (<ellipse class="error-ellipse">) and its worst
 * displacement as an arrow (<line class="worst">), and the part at the
 * pose `pose` (dx, dy, dtheta: one corner of the tolerance box) dashed
 * (<path class="displaced">), all magnified `magnification` times, which
 * the legend states with `tolerance`, the tolerances in words. */
void wc_svg_locate(FILE *out, const wr_fixture *fixture, const char *name,
                   const wc_locate_mark *marks, int count, const double pose[3],
                   double magnification, const char *tolerance);

#endif
