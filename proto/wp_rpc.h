/* wp_rpc.h -- what the daemon calls: a line's answer, from its parsing to
 * its last piece (the JSON-RPC 2.0 envelope of docs/PROTOCOL.md).  No
 * sockets: a line of text in, a line of text out.  The methods are behind
 * wp_method.h; the store and the solver state behind wp_host.h, which the
 * daemon implements (one per worker thread, so `self` may hold that
 * thread's GLPK environment). */
#ifndef WP_RPC_H
#define WP_RPC_H

#include "wp_host.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct wp_limits {
    int max_depth;        /* deepest nesting of arrays and objects */
    size_t max_wrenches;  /* most wrenches in one wrench.classify */
    size_t max_batch;     /* most requests in one batch */
    uint64_t max_candidates; /* most candidates of one fixture.design (its
                              shard's); 0: no cap */
    size_t max_cases;     /* most load cases in one request; 0: WP_MAX_CASES
                             (proto/methods/loads.h) */
} wp_limits;

typedef struct wp_counts {
    unsigned long requests; /* requests read, batch members included */
    unsigned long errors;   /* of them answered (or, for notifications, failed) with an error */
} wp_counts;

/* Answer one line (without its "\n").  Returns the response line, ending in
 * "\n" (malloc'd; the caller frees), or NULL when nothing is to be sent:
 * notifications only.  Adds to *counts. */
char *wp_answer_line(const wp_host *host, const wp_limits *limits, const char *line,
                     size_t length, wp_counts *counts);

/* What may be answered on an event loop (wp_answer_light): the one place
 * this policy lives.  Lines up to WP_LIGHT_LINE bytes are parsed there; of
 * them, light are a line refused before any request is read, an invalid
 * request, an unknown method, a method flagged WP_CHEAP, and one flagged
 * WP_READY whose fixture is a stored one with its derived data ready, not
 * on supports and without a tolerance -- a classify only by the "auto"
 * method and with wrenches x cones at most WP_LIGHT_CONE_CHECKS (tens of
 * microseconds).  A loop answers at most
 * WP_LIGHT_BURST of one connection's light requests per read, so that a
 * client pipelining thousands shares the workers with everyone else rather
 * than holding the loop. */
#define WP_LIGHT_LINE 2048
#define WP_LIGHT_CONE_CHECKS 1024
#define WP_LIGHT_BURST 32

/* A response line for an error found before the line was read (a line over
 * the length limit, too many clients): id null.  Malloc'd, or NULL. */
char *wp_error_line(int code, const char *field, const char *reason);

/* ---- answering a line in pieces ------------------------------------------ */

/* A line's answer in the making.  wp_answer_begin parses the line; each
 * wp_answer_step then writes the next piece of the answer, doing a bounded
 * amount of work, so that the caller can send pieces as they are made,
 * pause while the client does not read, share its threads fairly among
 * clients, and give up on a client that is gone.  The pieces, joined, are
 * byte for byte the line wp_answer_line answers.  Successive steps may run
 * in different threads (each with its own host), one at a time. */
typedef struct wp_answer wp_answer;

typedef enum wp_step {
    WP_STEP_MORE,   /* a piece written; more follow */
    WP_STEP_DONE,   /* the last piece written (it ends in "\n", or the answer
                       is empty: notifications only) */
    WP_STEP_FAILED  /* the answer cannot be completed after pieces already
                       handed out (a solver failure midway through a long
                       classify): the caller closes the connection, as the
                       only honest end of a line it cannot finish */
} wp_step;

/* Work units per piece: a unit is about one wrench against one cone (tens
 * of nanoseconds); other methods count as a whole piece each, but for the
 * cheap ones (WP_CHEAP). */
#define WP_PIECE_BUDGET 200000UL
/* Bytes of answer after which a piece ends (between wrenches, edges or
 * requests of a batch): the daemon checks its bound on a connection's
 * unsent output between pieces. */
#define WP_PIECE_BYTES (256 * 1024)

/* Parse a line (without its "\n").  The line is not kept.  With a `host`
 * that keeps inline fixtures' texts (wp_host.h, fixture_use_text), a long
 * line's inline fixture may be recognised from its text and held from
 * here: steps and wp_answer_free must then be given the same host.  NULL
 * only when out of memory. */
wp_answer *wp_answer_begin(const wp_limits *limits, const wp_host *host, const char *line,
                           size_t length);
/* Is the answer light work, to be made on an event loop now (the policy
 * above)?  Ask it only of lines up to WP_LIGHT_LINE: a loop parses no
 * longer ones.  The fixture of a WP_READY request is looked up here, once,
 * and held from here on, light or not. */
bool wp_answer_light(wp_answer *answer, const wp_host *host);
/* The whole answer at once, and the answer freed: the line (malloc'd), or
 * NULL when there is none (notifications only). */
char *wp_answer_whole(wp_answer *answer, const wp_host *host, wp_counts *counts);
/* Append the next piece to `out`, counting what it answers in *counts. */
wp_step wp_answer_step(wp_answer *answer, const wp_host *host, wp_buffer *out,
                       wp_counts *counts);
/* Smaller pieces than the default (tests and fuzzing, to cut answers at
 * every place they may be cut): `budget` work units, `bytes` of text. */
void wp_answer_pieces(wp_answer *answer, unsigned long budget, size_t bytes);
/* Chunks for helpers beside the answer's steps (wp_chunks.h):
 * wp_answer_parallel, asked between steps, says whether there are some
 * now; wp_answer_work makes one, in any thread, with the thread's own host
 * (its stop is the request's), while the step that follows the yes runs --
 * and only then: never once that step has returned, for the step after it
 * may end the answer.  False when there was none left. */
bool wp_answer_parallel(wp_answer *answer);
bool wp_answer_work(wp_answer *answer, const wp_host *host);
/* Bytes the answer holds between steps (its parsed request, wrenches, a
 * stream's work in hand).  Between steps only: not while helpers work. */
size_t wp_answer_bytes(const wp_answer *answer);
/* Free it, finished or not (a fixture it holds is released through `host`). */
void wp_answer_free(wp_answer *answer, const wp_host *host);

#ifdef __cplusplus
}
#endif

#endif
