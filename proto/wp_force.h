/* wp_force.h -- the force methods' handlers (docs/PROTOCOL.md, "force.range"),
 * for the method table. */
#ifndef WP_FORCE_H
#define WP_FORCE_H

#include "wp_loads.h"
#include "wp_rpc.h"

#ifdef __cplusplus
extern "C" {
#endif

/* force.range: the magnitudes of one push that do each set's job under
 * each case, and under all of them. */
cJSON *wp_force_range(wp_call *call);

/* push.force: the least force F*(p) along the outline, sampled exactly,
 * and its minimum over the outline (wr_least_force_find). */
cJSON *wp_push_force(wp_call *call);

/* Samples of F* per segment: the default and the most. */
#define WP_FORCE_SAMPLES 64
#define WP_FORCE_MAX_SAMPLES 4096

/* push.regions' "force" F and "cases": the regions where a push of
 * magnitude F does the set's job under every case (wr_push_regions_loaded).
 * Without "force" there is nothing to do (given false) and push.regions is
 * what it always was; "cases" needs "force", and "force" without cases is
 * the push alone. */
typedef struct wp_push_load {
    bool given;
    double force;      /* model system */
    int count;         /* cases: at least 1 (a zero load without cases) */
    double (*loads)[3]; /* malloc'd, model system */
} wp_push_load;

/* Read params.force and params.cases; a finger with friction is refused
 * with them (the loaded regions are exact, for a frictionless finger).
 * False with nothing allocated on error. */
bool wp_push_load_read(const cJSON *params, const wr_fixture *fixture, double finger_friction,
                       wp_push_load *out, wp_error *error);
void wp_push_load_release(wp_push_load *load);

#ifdef __cplusplus
}
#endif

#endif
