/* wd_worker.h -- the worker threads: they take request lines from a queue,
 * answer them (wp_answer_line) against the fixture cache, and hand the
 * answers back.  Each worker has its own GLPK environment and warm LPs. */
#ifndef WD_WORKER_H
#define WD_WORKER_H

#include "wd_cache.h"

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

/* One request line and, once answered, its response. */
typedef struct wd_job {
    struct wd_job *next;  /* queue link */
    void *owner;          /* the connection's slot; opaque to workers */
    char *line;           /* malloc'd, without its "\n" */
    size_t length;
    char *response;       /* malloc'd by the worker; NULL: nothing to send */
    size_t response_length; /* strlen(response), counted in the worker */
} wd_job;

/* Called in a worker thread once `job->response` is set; must be
 * thread-safe.  The callee owns the job from then on. */
typedef void (*wd_job_done)(void *context, wd_job *job);

typedef struct wd_pool wd_pool;

/* Start `threads` workers.  NULL when a thread cannot be started. */
wd_pool *wd_pool_new(int threads, wd_cache *cache, const wp_limits *limits, wd_stats *stats,
                     wd_job_done done, void *context);
/* Queue a job (takes it). */
void wd_pool_submit(wd_pool *pool, wd_job *job);
/* Answer everything queued, stop and join the workers, free the pool. */
void wd_pool_free(wd_pool *pool);

/* What one thread needs to answer requests: a wp_host on the shared cache,
 * with that thread's GLPK environment and warm LPs.  Workers make one each;
 * anything else answering lines in a thread of its own (a test, a fuzzer)
 * may too.  Create, use and free it in the same thread. */
typedef struct wd_context wd_context;
wd_context *wd_context_new(wd_cache *cache, wd_stats *stats);
const wp_host *wd_context_host(wd_context *context);
void wd_context_free(wd_context *context);

#endif
