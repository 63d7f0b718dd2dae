/* wp_local.h -- a wp_host in the calling thread, without a daemon: requests
 * are answered in process by the same code the daemon runs.  It has no
 * store: a fixture must be given inline; fixture.put/get/delete/list and
 * server.status answer an error saying they need the daemon. */
#ifndef WP_LOCAL_H
#define WP_LOCAL_H

#include "wp_rpc.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct wp_local wp_local;

/* Create, use and free in one thread (it holds that thread's GLPK env). */
wp_local *wp_local_new(void);
const wp_host *wp_local_host(wp_local *local);
void wp_local_free(wp_local *local);

#ifdef __cplusplus
}
#endif

#endif
