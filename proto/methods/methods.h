/* methods.h -- each family's handlers and streams, for the method table
 * (wp_methods.c), one section per file of proto/methods/. */
#ifndef WP_METHODS_METHODS_H
#define WP_METHODS_METHODS_H

#include "wp_method.h"

/* store.c */
bool wp_handle_fixture_put(wp_call *call, wp_writer *out);
bool wp_handle_fixture_get(wp_call *call, wp_writer *out);
bool wp_handle_fixture_delete(wp_call *call, wp_writer *out);
extern const wp_streamer wp_list_stream;
bool wp_handle_server_status(wp_call *call, wp_writer *out);

/* classify.c */
extern const wp_streamer wp_classify_stream;
bool wp_classify_light(const cJSON *params, int cones);

/* analysis.c */
bool wp_handle_cone_get(wp_call *call, wp_writer *out);
bool wp_handle_plan_get(wp_call *call, wp_writer *out);
bool wp_handle_modes_get(wp_call *call, wp_writer *out);
extern const wp_streamer wp_push_stream;
bool wp_handle_gravity_sweep(wp_call *call, wp_writer *out);
/* Is a gravity.sweep light (no "in_plane_g": no LP)? */
bool wp_handle_stability_margin(wp_call *call, wp_writer *out);

/* sweep.c */
extern const wp_streamer wp_sweep_stream;

/* locate.c */
bool wp_handle_fixture_locating(wp_call *call, wp_writer *out);
bool wp_locating_light(const cJSON *params, int cones);

/* design.c */
extern const wp_streamer wp_design_stream;

/* force.c: force.range (the magnitudes of one push that do each set's job
 * under each load case, and under all of them) and push.force (the least
 * push force along the outline, and where it is least) */
bool wp_handle_force_range(wp_call *call, wp_writer *out);
bool wp_handle_push_force(wp_call *call, wp_writer *out);

/* supports.c: a fixture on a base plate (wr_support.h) */
/* One wrench's answer by the supports' seating and holding (no margin; a
 * motion's witness for strong): as wr_classify's, with the host's GLPK
 * environment.  WR_LP_FAILED without one. */
wr_status wp_supports_answer(const wr_analysis *analysis, const wp_host *host,
                             const double wrench[3], wr_set set, double tolerance,
                             wr_answer *answer);
/* A question about directions alone cannot be answered for a fixture on
 * supports: true (the call's error set at `field`, naming `what` to give
 * instead) when the fixture has supports, else false. */
bool wp_supports_refuse(wp_call *call, const wr_fixture *fixture, const char *field,
                        const char *what);
/* What a push on supports is not answered for (wr_support.h: set "goal",
 * a polygon's straight edges, a point finger): the field of the first
 * thing that is not so, or NULL when the push may be answered. */
const char *wp_supports_push_unanswered(const wr_fixture *fixture, wr_set set, double radius);

#endif
