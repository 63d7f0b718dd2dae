/* wp_force.h -- the force methods' handlers (docs/PROTOCOL.md, "force.range"),
 * for the method table. */
#ifndef WP_FORCE_H
#define WP_FORCE_H

#include "wp_rpc.h"

#ifdef __cplusplus
extern "C" {
#endif

/* force.range: the magnitudes of one push that do each set's job under
 * each case, and under all of them. */
cJSON *wp_force_range(wp_call *call);

#ifdef __cplusplus
}
#endif

#endif
