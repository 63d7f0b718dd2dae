/* wd_host.h -- the daemon's wp_host (proto/wp_host.h), one per thread, and
 * the counters server.status reports. */
#ifndef WD_HOST_H
#define WD_HOST_H

#include "wd_cache.h"
#include "wp_rpc.h"

#include <stdatomic.h>
#include <time.h>

/* Counters shared by the event loop and the workers. */
typedef struct wd_stats {
    atomic_ulong requests;      /* requests answered, batch members included */
    atomic_ulong errors;        /* of them, errors */
    atomic_ulong clients;       /* connections open now */
    atomic_ulong refused;       /* connections refused (over --max-clients) */
    atomic_ulong denied;        /* connections denied (peer not in the allow lists) */
    time_t started;
    int threads;
} wd_stats;

/* What one thread needs to answer requests: a wp_host on the shared cache,
 * with that thread's GLPK environment and warm LPs.  Workers make one each;
 * anything else answering lines in a thread of its own (a test, a fuzzer)
 * may too.  Create, use and free it in the same thread. */
typedef struct wd_thread_host wd_thread_host;
wd_thread_host *wd_thread_host_new(wd_cache *cache, wd_stats *stats);
const wp_host *wd_thread_host_wp(wd_thread_host *thread);
/* The task in hand's stop (copied), for the host's `stop`; NULL: none. */
void wd_thread_host_stop(wd_thread_host *thread, const wr_stop *stop);
void wd_thread_host_free(wd_thread_host *thread);

#endif
