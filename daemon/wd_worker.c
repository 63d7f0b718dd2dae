/* wd_worker.c -- the worker pool: tasks queued round-robin, a piece at a
 * time, and the helpers that make a piece's chunks on the other workers
 * (docs/ARCHITECTURE.md, "Parallel work").  Each worker answers with its
 * own wp_host (wd_host.c). */
#include "wd_worker.h"
#include "wd_log.h"

#include <assert.h>
#include <pthread.h>
#include <stdlib.h>
#include <string.h>

/* ---- the pool ------------------------------------------------------------- */

/* One user's queued tasks (helpers of its pieces included), in order. */
typedef struct user_queue {
    struct user_queue *next;   /* in the pool's round */
    unsigned uid;
    wd_task *head, *tail;
} user_queue;

struct wd_pool {
    pthread_mutex_t lock;      /* guards everything below but the constants */
    pthread_cond_t ready;      /* a task was queued, or stop was set */
    /* The round: the users with tasks queued, each once, served from the
     * head: one task taken, the user back at the tail if it has more.  So
     * fairness is by user, whatever the number of connections each holds,
     * and every task runs one piece, then queues again at its user's tail.
     * Invariant: a user is in the round iff its queue is not empty. */
    user_queue *first, *last;
    user_queue spare;          /* used when no memory is left for a queue */
    bool stop;
    int thread_count;
    pthread_t *threads;
    wd_cache *cache;
    wp_limits limits;
    wd_stats *stats;
    wd_task_done done;
    void *argument;
};

static bool task_cancelled(void *argument)
{
    return atomic_load_explicit(&((wd_task *)argument)->cancelled, memory_order_relaxed);
}

/* The helpers of one piece being made.  Invariant: a helper calls
 * wp_answer_work only while registered in `active`, and registers only
 * while `open`; the piece's worker closes the fork and waits for `active`
 * to reach 0 as soon as its step returns, so no helper touches the answer
 * after that (wp_chunks.h: the next step may end it).  Freed by the last of
 * the piece's worker and its helpers to let go of it. */
typedef struct wd_fork {
    pthread_mutex_t lock;
    pthread_cond_t idle;     /* active fell to 0 */
    wd_task *task;           /* the task whose piece is being made */
    bool open;
    int active;              /* helpers inside wp_answer_work */
    int references;          /* the worker's, and each queued or running helper's */
} wd_fork;

static void fork_release(wd_fork *fork)
{
    pthread_mutex_lock(&fork->lock);
    bool last = --fork->references == 0;
    pthread_mutex_unlock(&fork->lock);
    if (last) {
        pthread_mutex_destroy(&fork->lock);
        pthread_cond_destroy(&fork->idle);
        free(fork);
    }
}

static void round_append(wd_pool *pool, user_queue *user)
{
    user->next = NULL;
    if (pool->last)
        pool->last->next = user;
    else
        pool->first = user;
    pool->last = user;
}

static void queue_locked(wd_pool *pool, wd_task *task)
{
    unsigned uid = task->fork ? task->fork->task->uid : task->uid;
    user_queue *user = pool->first;
    while (user && (user == &pool->spare || user->uid != uid))
        user = user->next;
    if (!user) {
        user = calloc(1, sizeof *user);
        if (!user) {
            user = &pool->spare; /* shared, out of memory: fair to none, lost to none */
            if (!user->head) {
                user->uid = uid;
                round_append(pool, user);
            }
        } else {
            user->uid = uid;
            round_append(pool, user);
        }
    }
    task->next = NULL;
    if (user->tail)
        user->tail->next = task;
    else
        user->head = task;
    user->tail = task;
}

/* The next task in the round, or NULL. */
static wd_task *take_locked(wd_pool *pool)
{
    user_queue *user = pool->first;
    if (!user)
        return NULL;
    wd_task *task = user->head;
    user->head = task->next;
    if (!user->head)
        user->tail = NULL;
    pool->first = user->next;
    if (!pool->first)
        pool->last = NULL;
    if (user->head)
        round_append(pool, user);
    else if (user != &pool->spare)
        free(user);
    task->next = NULL;
    return task;
}

/* Queue a helper for every other worker; NULL when there is no memory for
 * it (the piece is then made by its worker alone). */
static wd_fork *fork_open(wd_pool *pool, wd_task *task)
{
    int helpers = pool->thread_count - 1;
    wd_fork *fork = calloc(1, sizeof *fork);
    if (!fork)
        return NULL;
    pthread_mutex_init(&fork->lock, NULL);
    pthread_cond_init(&fork->idle, NULL);
    fork->task = task;
    fork->open = true;
    fork->references = 1;
    wd_task *made[helpers > 0 ? helpers : 1];
    int count = 0;
    for (int i = 0; i < helpers; i++) {
        made[count] = calloc(1, sizeof **made);
        if (!made[count])
            break;
        made[count]->fork = fork;
        count++;
    }
    fork->references += count;
    pthread_mutex_lock(&pool->lock);
    for (int i = 0; i < count; i++)
        queue_locked(pool, made[i]);
    pthread_cond_broadcast(&pool->ready);
    pthread_mutex_unlock(&pool->lock);
    return fork;
}

static void fork_close(wd_fork *fork)
{
    pthread_mutex_lock(&fork->lock);
    fork->open = false;
    while (fork->active > 0)
        pthread_cond_wait(&fork->idle, &fork->lock);
    pthread_mutex_unlock(&fork->lock);
    fork_release(fork);
}

/* A helper's turn: a share of its fork's work, then queued again while
 * the fork is open and work is left, else let go of. */
static void run_helper(wd_pool *pool, wd_thread_host *thread, wd_task *helper)
{
    wd_fork *fork = helper->fork;
    pthread_mutex_lock(&fork->lock);
    bool go = fork->open && thread && !pool->stop;
    if (go)
        fork->active++;
    pthread_mutex_unlock(&fork->lock);
    if (go) {
        wd_thread_host_stop(thread, &(wr_stop){task_cancelled, fork->task});
        bool more = wp_answer_work(fork->task->answer, wd_thread_host_wp(thread));
        wd_thread_host_stop(thread, NULL);
        pthread_mutex_lock(&fork->lock);
        if (--fork->active == 0)
            pthread_cond_broadcast(&fork->idle);
        go = more && fork->open;
        pthread_mutex_unlock(&fork->lock);
    }
    if (go) {
        pthread_mutex_lock(&pool->lock);
        queue_locked(pool, helper);
        pthread_cond_signal(&pool->ready);
        pthread_mutex_unlock(&pool->lock);
        return;
    }
    fork_release(fork);
    free(helper);
}

/* One piece of the task's answer, into task->piece. */
static void run_piece(wd_pool *pool, wd_thread_host *thread, wd_task *task)
{
    task->piece = NULL;
    task->piece_length = 0;
    if (atomic_load(&task->cancelled)) {
        task->step = WP_STEP_DONE; /* handed back unworked: the loop drops it */
        return;
    }
    wp_counts counts = {0, 0};
    if (!thread) {
        task->piece = wp_error_line(WP_INTERNAL, "", "out of memory");
        task->step = WP_STEP_DONE;
        counts.requests = counts.errors = 1;
    } else {
        wd_thread_host_stop(thread, &(wr_stop){task_cancelled, task});
        if (!task->answer) {
            task->answer = wp_answer_begin(&pool->limits, wd_thread_host_wp(thread), task->line,
                                           task->length);
            free(task->line); /* parsed: the line is not needed again */
            task->line = NULL;
        }
        if (!task->answer) {
            task->piece = wp_error_line(WP_INTERNAL, "", "out of memory");
            task->step = WP_STEP_DONE;
            counts.requests = counts.errors = 1;
        } else {
            wp_buffer piece = {0};
            wd_fork *fork = pool->thread_count > 1 && wp_answer_parallel(task->answer)
                                ? fork_open(pool, task)
                                : NULL;
            task->step = wp_answer_step(task->answer, wd_thread_host_wp(thread), &piece, &counts);
            if (fork)
                fork_close(fork);
            if (piece.failed) {
                /* The piece did not fit in memory: the answer cannot go on
                 * (what was sent of it cannot be taken back). */
                free(piece.data);
                task->step = WP_STEP_FAILED;
            } else {
                task->piece_length = piece.length;
                if (piece.length)
                    task->piece = wp_buffer_take(&piece);
                else
                    free(piece.data);
            }
        }
        if (task->step != WP_STEP_MORE) {
            wp_answer_free(task->answer, wd_thread_host_wp(thread));
            task->answer = NULL;
        }
        wd_thread_host_stop(thread, NULL);
    }
    task->held = wp_answer_bytes(task->answer);
    atomic_fetch_add(&pool->stats->requests, counts.requests);
    atomic_fetch_add(&pool->stats->errors, counts.errors);
}

static void *worker_main(void *argument)
{
    wd_pool *pool = argument;
    wd_thread_host *thread = wd_thread_host_new(pool->cache, pool->stats);
    if (!thread)
        wd_log(WD_LOG_ERROR, "a worker could not start: out of memory");
    for (;;) {
        pthread_mutex_lock(&pool->lock);
        while (!pool->first && !pool->stop)
            pthread_cond_wait(&pool->ready, &pool->lock);
        wd_task *task = take_locked(pool);
        pthread_mutex_unlock(&pool->lock);
        if (!task)
            break; /* stopping, and nothing left */
        if (task->fork) {
            run_helper(pool, thread, task);
            continue;
        }
        if (pool->stop)
            atomic_store(&task->cancelled, true); /* handed back unworked */
        run_piece(pool, thread, task);
        pool->done(pool->argument, task);
    }
    wd_thread_host_free(thread);
    return NULL;
}

wd_pool *wd_pool_new(int threads, wd_cache *cache, const wp_limits *limits, wd_stats *stats,
                     wd_task_done done, void *argument)
{
    wd_pool *pool = calloc(1, sizeof *pool);
    if (!pool)
        return NULL;
    pthread_mutex_init(&pool->lock, NULL);
    pthread_cond_init(&pool->ready, NULL);
    pool->cache = cache;
    pool->limits = *limits;
    pool->stats = stats;
    pool->done = done;
    pool->argument = argument;
    pool->threads = calloc((size_t)threads, sizeof *pool->threads);
    if (!pool->threads) {
        wd_pool_free(pool);
        return NULL;
    }
    for (int i = 0; i < threads; i++) {
        if (pthread_create(&pool->threads[i], NULL, worker_main, pool) != 0) {
            wd_pool_free(pool);
            return NULL;
        }
        pool->thread_count++;
    }
    return pool;
}

void wd_pool_submit(wd_pool *pool, wd_task *task)
{
    /* Submitted with its last piece sent, and with work left: a task that
     * finished or failed is never queued again. */
    assert(!task->piece && (!task->answer || task->step == WP_STEP_MORE) && !task->fork);
    pthread_mutex_lock(&pool->lock);
    queue_locked(pool, task);
    pthread_cond_signal(&pool->ready);
    pthread_mutex_unlock(&pool->lock);
}

void wd_pool_free(wd_pool *pool)
{
    if (!pool)
        return;
    pthread_mutex_lock(&pool->lock);
    pool->stop = true;
    pthread_cond_broadcast(&pool->ready);
    pthread_mutex_unlock(&pool->lock);
    for (int i = 0; i < pool->thread_count; i++)
        pthread_join(pool->threads[i], NULL);
    free(pool->threads);
    pthread_mutex_destroy(&pool->lock);
    pthread_cond_destroy(&pool->ready);
    free(pool);
}

void wd_task_free(wd_task *task, const wp_host *host)
{
    if (!task)
        return;
    wp_answer_free(task->answer, host);
    free(task->line);
    free(task->piece);
    free(task);
}
