/* wd_worker.h -- the worker pool: threads that take tasks from a queue,
 * make a piece of each answer (wp_answer_step) against the fixture cache,
 * and hand it back; helpers share a piece's chunks.  Each worker answers
 * with its own wp_host (wd_host.h). */
#ifndef WD_WORKER_H
#define WD_WORKER_H

#include "wd_host.h"

#include <stdatomic.h>
#include <stdbool.h>
#include <time.h>


/* One request line being answered, a piece at a time.  The loop submits
 * it; a worker takes it, writes one piece of its answer (a bounded amount
 * of work: wp_answer_step) and hands it back; the loop sends the piece and,
 * when more follow and the client keeps reading, submits it again, at the
 * tail of its user's queue.  The workers take the users in turn, a piece
 * each, and each user's tasks in order: a user with a hundred connections
 * gets one piece a round, as a user with one does; and a request never
 * runs ahead of its client's reading.
 * A piece with work to share (a design's candidates) also queues a helper
 * for every other worker: each takes a bounded share at a time, queueing
 * again at the tail, until the piece is made; so one request uses every
 * idle core, and still waits its turn behind other clients' pieces.
 *
 * Ownership: the loop's while it is not submitted; a worker's from its
 * submission until `done` is called with it. */
typedef struct wd_task {
    struct wd_task *next;   /* queue link */
    void *owner;            /* the connection's queued line; opaque to workers */
    unsigned uid;           /* its client's user: the workers serve users in
                               turn (wd_pool), not connections */
    char *line;             /* malloc'd, without its "\n"; freed once parsed */
    size_t length;
    wp_answer *answer;      /* NULL until the first piece */
    atomic_bool cancelled;  /* the client is gone: stop at the next poll */
    /* Set by the worker for the loop: */
    char *piece;            /* malloc'd text to send, or NULL */
    size_t piece_length;
    wp_step step;           /* what wp_answer_step said */
    size_t held;            /* bytes the answer holds between pieces */
    /* A helper: not a request of its own but a share of another task's
     * work (wp_answer_work) while that task's piece is being made; the
     * pool makes, runs and frees helpers, and the loop never sees one. */
    struct wd_fork *fork;
} wd_task;

/* Called in a worker thread once a piece is made; must be thread-safe.
 * The callee owns the task from then on. */
typedef void (*wd_task_done)(void *argument, wd_task *task);

typedef struct wd_pool wd_pool;

/* Start `threads` workers.  NULL when a thread cannot be started. */
wd_pool *wd_pool_new(int threads, wd_cache *cache, const wp_limits *limits, wd_stats *stats,
                     wd_task_done done, void *argument);
/* Queue a task for its next piece (takes it).  A cancelled task is handed
 * back without work. */
void wd_pool_submit(wd_pool *pool, wd_task *task);
/* Stop and join the workers (each hands back the piece it is making; the
 * tasks still queued are handed back unworked), free the pool. */
void wd_pool_free(wd_pool *pool);

/* Free a task that is not with the workers, and whatever its answer holds
 * (a fixture, released through `host`). */
void wd_task_free(wd_task *task, const wp_host *host);


#endif
