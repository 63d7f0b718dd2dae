/* wp_chunks.h -- the one engine for a long answer made in chunks, in
 * parallel.  A method gives it `make` (chunk i, in any thread) and `merge`
 * (in order, in a step); the engine owns the rest: the lock, the window of
 * chunks made ahead of their turn, the "shared" flag, the kept failure and
 * the merging in order.  Classify (chunks of wrenches), design (chunks of
 * candidates, then a chunk per kept design's figures) and the lattice
 * (chunks of hole pairs) use it; nothing else runs work on helpers
 * (docs/ARCHITECTURE.md, "Parallel work").
 *
 * The threads: a stream's steps run one at a time (wp_answer_step); while
 * one runs, the daemon's helpers may call wp_chunks_work, any number at
 * once, but only after wp_chunks_parallel said yes before that step began.
 * The rule that keeps an answer alive while a helper holds it is enforced
 * here, once: a step that began after a yes (it "shares") never returns
 * WP_STEP_DONE or WP_STEP_FAILED from wp_chunks_run -- a helper may still
 * be inside make until that step returns; the next step, which shares
 * nothing, ends the answer. */
#ifndef WP_CHUNKS_H
#define WP_CHUNKS_H

#include "wp_method.h"

typedef struct wp_chunks wp_chunks;

typedef struct wp_chunk_ops {
    /* Bytes of a chunk's record: the method's own record, zeroed at first and
     * kept from one chunk to the next that uses it (room reused). */
    size_t record_size;
    /* Optional, under the engine's lock as chunk `index` is claimed (in
     * order): copy into the record what make needs of the state merge
     * changes.  False: there is no chunk `index`, nor any after it (for a
     * method whose count of chunks is not known up front). */
    bool (*claim)(void *method, size_t index, void *record);
    /* Make chunk `index` into its record, outside the lock, in any thread with
     * that thread's host; add the units spent to *used.  `direct`, when the
     * method allows it (`direct` below), is the answer itself: the chunk is
     * next in order and made by a step, so it is written there and never
     * merged.  Not WR_OK: the answer ends at this chunk, with `error` said
     * (by a step that shares nothing) when its turn comes. */
    wr_status (*make)(void *method, size_t index, void *record, wp_buffer *direct,
                      const wp_host *host, unsigned long *used, wp_error *error);
    /* Merge chunk `index`, in order, under the lock, in a step's thread:
     * text into `out`, or results into the method's state.  Not WR_OK: the
     * answer ends here. */
    wr_status (*merge)(void *method, size_t index, void *record, wp_buffer *out, wp_error *error);
    /* Free what a record holds (its room), at the end. */
    void (*release)(void *record);
    /* Optional: bytes a record holds beyond record_size. */
    size_t (*bytes)(const void *record);
    bool direct;       /* make may write the next chunk straight into the answer */
    size_t window;     /* chunks made ahead of the one next merged, at most */
} wp_chunk_ops;

/* `count` chunks (SIZE_MAX: until claim says there are no more).  NULL
 * when out of memory.  `method` is the caller's, passed to each op. */
wp_chunks *wp_chunks_new(const wp_chunk_ops *ops, void *method, size_t count);
/* Free it and every record's holdings.  No helper may be in it. */
void wp_chunks_free(wp_chunks *chunks);

/* The streamer's `parallel`: is a chunk left to claim?  A yes marks the
 * next step as shared. */
bool wp_chunks_parallel(wp_chunks *chunks);
/* The streamer's `work`, in a helper: claim the next chunk and make it;
 * false when none could be claimed (or it failed). */
bool wp_chunks_work(wp_chunks *chunks, const wp_host *host);

/* Does the step now beginning share (wp_chunks_parallel said yes since the
 * last step began; helpers may be in make until it returns)?  Ask it once,
 * first thing in every step of the stream, and pass it to wp_chunks_run. */
bool wp_chunks_shared(wp_chunks *chunks);
/* A step's share of the work: claim and make chunks, merge the done ones
 * in order into `out`, waiting for a helper's chunk when it is next, until
 * every chunk is merged, a chunk failed, or (after at least one chunk made
 * or merged) `budget` units are spent, `piece_bytes` of text written or the
 * host's stop asks.  WP_STEP_DONE: every chunk merged; FAILED: `error` set
 * (the kept failure) or `out` out of memory; MORE otherwise -- and always
 * MORE in a step that `shared` (the rule above). */
wp_step wp_chunks_run(wp_chunks *chunks, bool shared, const wp_host *host, wp_buffer *out,
                      unsigned long budget, unsigned long *used, size_t piece_bytes,
                      wp_error *error);

/* Are all chunks merged?  Between steps, or in one. */
bool wp_chunks_done(wp_chunks *chunks);
/* Bytes held: the records and what they hold.  Between steps only. */
size_t wp_chunks_bytes(const wp_chunks *chunks);

#endif
