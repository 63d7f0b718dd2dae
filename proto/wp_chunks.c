/* wp_chunks.c -- the engine of chunked, parallel work (wp_chunks.h). */
#include "wp_chunks.h"

#include <assert.h>
#include <pthread.h>
#include <stdlib.h>
#include <string.h>

/* Chunk i has states[i % window] and the method's record i % window from
 * its claim until it is merged. */
typedef struct chunk_state {
    bool done;              /* made (or failed): the step may merge it */
    wr_status status;       /* not WR_OK: the answer ends at this chunk */
    wp_error error;         /* what to say then */
} chunk_state;

struct wp_chunks {
    const wp_chunk_ops *ops;
    void *method;
    size_t window;
    /* Guards everything below, the chunks' states and each merge.  A
     * chunk's state and its method record are its claimer's alone from the
     * claim until `done`: the step reads them only then. */
    pthread_mutex_t lock;
    pthread_cond_t made;     /* a chunk is done */
    size_t count;            /* chunks; SIZE_MAX until claim says the end */
    size_t claimed;          /* chunks [0, claimed) are claimed, in order */
    size_t merged;           /* chunks [0, merged) are merged */
    bool failing;            /* a chunk failed: nothing more is claimed */
    /* wp_chunks_parallel said yes since the last step began: helpers may be
     * in make until the next step returns. */
    bool forked;
    chunk_state *states;     /* window of them */
    unsigned char *data;     /* window method records of ops->record_size */
};

static void *data_of(wp_chunks *c, size_t index)
{
    return c->data + (index % c->window) * c->ops->record_size;
}

wp_chunks *wp_chunks_new(const wp_chunk_ops *ops, void *method, size_t count)
{
    wp_chunks *c = calloc(1, sizeof *c);
    if (!c)
        return NULL;
    c->ops = ops;
    c->method = method;
    c->window = ops->window ? ops->window : 1;
    c->count = count;
    c->states = calloc(c->window, sizeof *c->states);
    c->data = calloc(c->window, ops->record_size ? ops->record_size : 1);
    if (!c->states || !c->data) {
        free(c->states);
        free(c->data);
        free(c);
        return NULL;
    }
    pthread_mutex_init(&c->lock, NULL);
    pthread_cond_init(&c->made, NULL);
    return c;
}

void wp_chunks_free(wp_chunks *c)
{
    if (!c)
        return;
    if (c->ops->release)
        for (size_t i = 0; i < c->window; i++)
            c->ops->release(c->data + i * c->ops->record_size);
    pthread_mutex_destroy(&c->lock);
    pthread_cond_destroy(&c->made);
    free(c->states);
    free(c->data);
    free(c);
}

/* Under the lock: is a chunk left to claim now (window permitting)? */
static bool claimable_locked(const wp_chunks *c)
{
    return !c->failing && c->claimed < c->count && c->claimed < c->merged + c->window;
}

/* Claim the next chunk and make it; false when none can be claimed now.
 * Any thread.  A step passes its answer as `out`: with ops->direct, the
 * chunk next to be merged is then made straight into it. */
static bool claim_and_make(wp_chunks *c, const wp_host *host, wp_buffer *out,
                           unsigned long *used)
{
    pthread_mutex_lock(&c->lock);
    bool claimable = claimable_locked(c);
    size_t index = c->claimed;
    if (claimable && c->ops->claim && !c->ops->claim(c->method, index, data_of(c, index))) {
        c->count = index; /* the end: nothing at or after it */
        claimable = false;
    }
    if (claimable)
        c->claimed++;
    bool direct = claimable && out && c->ops->direct && index == c->merged;
    pthread_mutex_unlock(&c->lock);
    if (!claimable)
        return false;
    chunk_state *s = &c->states[index % c->window];
    assert(!s->done);
    wp_error error = {0};
    unsigned long spent = 0;
    wr_status status = c->ops->make(c->method, index, data_of(c, index), direct ? out : NULL,
                                    host, &spent, &error);
    if (used)
        *used += spent;
    pthread_mutex_lock(&c->lock);
    s->status = status;
    if (status != WR_OK) {
        s->error = error;
        c->failing = true; /* no more claims: the answer ends at this chunk */
    }
    if (direct && status == WR_OK)
        c->merged++; /* in the answer already */
    else
        s->done = true;
    pthread_cond_broadcast(&c->made);
    pthread_mutex_unlock(&c->lock);
    return true;
}

bool wp_chunks_parallel(wp_chunks *c)
{
    pthread_mutex_lock(&c->lock);
    bool more = !c->failing && c->claimed < c->count;
    /* The host opens its helpers on a yes and runs the step after it: they
     * may claim every chunk left before that step begins, so the step
     * cannot tell from the claims alone that it shares. */
    c->forked = c->forked || more;
    pthread_mutex_unlock(&c->lock);
    return more;
}

bool wp_chunks_work(wp_chunks *c, const wp_host *host)
{
    /* A helper's failure is its chunk's, said by a step in its turn. */
    return claim_and_make(c, host, NULL, NULL);
}

bool wp_chunks_shared(wp_chunks *c)
{
    pthread_mutex_lock(&c->lock);
    bool shared = c->forked;
    c->forked = false;
    pthread_mutex_unlock(&c->lock);
    return shared;
}

/* Merge the chunks that are done, in order.  A failed chunk ends the
 * answer: its status, with `error` set. */
static wr_status merge_done(wp_chunks *c, wp_buffer *out, bool *merged_any, wp_error *error)
{
    wr_status status = WR_OK;
    pthread_mutex_lock(&c->lock);
    while (c->merged < c->claimed && status == WR_OK) {
        chunk_state *s = &c->states[c->merged % c->window];
        if (!s->done)
            break;
        if (s->status != WR_OK) {
            status = s->status;
            *error = s->error;
            break;
        }
        status = c->ops->merge(c->method, c->merged, data_of(c, c->merged), out, error);
        if (status != WR_OK) {
            c->failing = true;
            break;
        }
        s->done = false;
        c->merged++;
        *merged_any = true;
    }
    pthread_mutex_unlock(&c->lock);
    return status;
}

wp_step wp_chunks_run(wp_chunks *c, bool shared, const wp_host *host, wp_buffer *out,
                      unsigned long budget, unsigned long *used, size_t piece_bytes,
                      wp_error *error)
{
    size_t start = out->length;
    bool progress = false;
    for (;;) {
        if (merge_done(c, out, &progress, error) != WR_OK || out->failed)
            return shared ? WP_STEP_MORE : WP_STEP_FAILED;
        pthread_mutex_lock(&c->lock);
        bool all = c->merged == c->count;
        pthread_mutex_unlock(&c->lock);
        if (all)
            return shared ? WP_STEP_MORE : WP_STEP_DONE; /* shared: the next step ends it */
        /* At least one chunk a step, whatever the piece spent before it:
         * every step makes progress. */
        if (progress && (*used >= budget || out->length - start >= piece_bytes ||
                         wr_stop_requested(host->stop)))
            return WP_STEP_MORE;
        if (claim_and_make(c, host, out, used)) {
            progress = true;
            continue;
        }
        /* Nothing to claim now: the next chunk to merge is a helper's,
         * being made; wait for it (helpers never wait for a step). */
        pthread_mutex_lock(&c->lock);
        while (c->merged < c->claimed && !c->states[c->merged % c->window].done)
            pthread_cond_wait(&c->made, &c->lock);
        pthread_mutex_unlock(&c->lock);
    }
}

bool wp_chunks_done(wp_chunks *c)
{
    pthread_mutex_lock(&c->lock);
    bool done = c->merged == c->count;
    pthread_mutex_unlock(&c->lock);
    return done;
}

size_t wp_chunks_bytes(const wp_chunks *c)
{
    size_t bytes = sizeof *c + c->window * (sizeof *c->states + c->ops->record_size);
    if (c->ops->bytes)
        for (size_t i = 0; i < c->window; i++)
            bytes += c->ops->bytes(c->data + i * c->ops->record_size);
    return bytes;
}
