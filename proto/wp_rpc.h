/* wp_rpc.h -- the JSON-RPC 2.0 envelope and the method table of
 * docs/PROTOCOL.md.  No sockets: a line of text in, a line of text out.
 *
 * Methods reach the fixture store and the solver state through a wp_host,
 * which the daemon implements (one per worker thread, so `self` may hold
 * that thread's GLPK environment). */
#ifndef WP_RPC_H
#define WP_RPC_H

#include "wp_fixture.h"

#ifdef __cplusplus
extern "C" {
#endif

/* A fixture held for the length of one request. */
typedef struct wp_fixture_use {
    const char *id;
    const char *name;
    const char *canonical;       /* the stored JSON text */
    const wr_fixture *fixture;
    const wr_analysis *analysis; /* derived data, built if it had been evicted */
    void *handle[2];             /* the host's */
} wp_fixture_use;

/* One stored fixture, as fixture.list shows it. */
typedef struct wp_fixture_entry {
    char id[WP_ID_LENGTH + 1];
    char *name;                  /* malloc'd */
    int fixels;
} wp_fixture_entry;

/* The stored fixtures, by id. */
typedef struct wp_fixture_listing {
    size_t count;
    wp_fixture_entry *entries;   /* malloc'd */
} wp_fixture_listing;
void wp_fixture_listing_release(wp_fixture_listing *listing);

/* What server.status reports. */
typedef struct wp_server_state {
    double uptime_s;
    size_t fixtures;             /* stored */
    size_t cached;               /* with derived data in memory */
    size_t cache_bytes, cache_limit_bytes;
    int threads;
    unsigned long clients, refused, denied, requests, errors;
} wp_server_state;

/* The daemon's side of the seam: the fixture store and the solver state a
 * request needs, as data.  One per thread (so `self` may hold that thread's
 * GLPK environment).  The envelope acquires and releases a request's
 * fixture; handlers only read what it holds. */
typedef struct wp_host {
    void *self;
    /* Keep a validated fixture and hold it: stored (persisted, listed) when
     * `store`, else only cached under its id (an inline fixture).  Takes
     * the doc's contents whatever the outcome. */
    bool (*fixture_adopt)(void *self, wp_fixture_doc *doc, bool store, wp_fixture_use *use,
                          wp_error *error);
    /* Hold the stored fixture `id`; WP_NO_FIXTURE when there is none. */
    bool (*fixture_use)(void *self, const char *id, wp_fixture_use *use, wp_error *error);
    /* Hold the stored fixture `id` only if its derived data is ready (using
     * it then costs no derivation): its number of cones (goal + strong), or
     * -1 with nothing held.  May be NULL: never ready. */
    int (*fixture_use_ready)(void *self, const char *id, wp_fixture_use *use);
    void (*fixture_release)(void *self, wp_fixture_use *use);
    /* Forget the stored fixture `id` (and its file); WP_NO_FIXTURE, WP_STORAGE. */
    bool (*fixture_delete)(void *self, const char *id, wp_error *error);
    /* The stored fixtures, and the server's state. */
    bool (*fixture_list)(void *self, wp_fixture_listing *listing, wp_error *error);
    bool (*state)(void *self, wp_server_state *state, wp_error *error);
    /* This thread's warm LP sets for a fixture in use. */
    bool (*lp_sets)(void *self, wp_fixture_use *use, wr_lp_set **goal, wr_lp_set **strong,
                    wp_error *error);
    /* Polled by long work between bounded units (wrenches, edges): set by
     * the host to the request's own stop before each piece of work, so that
     * work for a client that hung up ends.  NULL: never stops. */
    const wr_stop *stop;
} wp_host;

typedef struct wp_limits {
    int max_depth;        /* deepest nesting of arrays and objects */
    size_t max_wrenches;  /* most wrenches in one wrench.classify */
    size_t max_batch;     /* most requests in one batch */
    uint64_t max_candidates; /* most candidates of one fixture.design (its
                              shard's); 0: no cap */
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
 * WP_READY whose fixture is a stored one with its derived data ready -- a
 * classify only by the "auto" method and with wrenches x cones at most
 * WP_LIGHT_CONE_CHECKS (tens of microseconds).  A loop answers at most
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

/* Parse a line (without its "\n").  The line is not kept.  NULL only when
 * out of memory. */
wp_answer *wp_answer_begin(const wp_limits *limits, const char *line, size_t length);
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
/* Work for other threads beside the answer's steps (a design's chunks of
 * candidates): wp_answer_parallel, asked between steps, says whether there
 * is some now; wp_answer_work does a bounded piece of it, in any thread,
 * with the thread's own host (its stop is the request's), while one step
 * of the answer runs -- and only then: never once that step has returned,
 * for the step that follows may end the answer.  False when there was
 * none left. */
bool wp_answer_parallel(wp_answer *answer);
bool wp_answer_work(wp_answer *answer, const wp_host *host);
/* Bytes the answer holds between steps (its parsed request, wrenches, a
 * stream's work in hand).  Between steps only: not while helpers work. */
size_t wp_answer_bytes(const wp_answer *answer);
/* Free it, finished or not (a fixture it holds is released through `host`). */
void wp_answer_free(wp_answer *answer, const wp_host *host);

/* One call of a method: what its handler reads and where it says what
 * went wrong. */
typedef struct wp_call {
    const wp_host *host;
    const wp_limits *limits;
    cJSON *params;               /* the request's params ({} when left out);
                                    a stream's begin may take out what it
                                    has read, to free it early */
    wp_error *error;
    struct wp_answer *answer;    /* the envelope's, for wp_call_fixture */
} wp_call;

/* The call's fixture (params.fixture: a stored id, or an inline fixture),
 * for a method flagged WP_FIXTURE: looked up on the first call (so that a
 * handler reads its cheaper params first), then held by the envelope until
 * the call ends -- for a streamed result, until its last piece.  NULL with
 * call->error set when there is none. */
wp_fixture_use *wp_call_fixture(wp_call *call);

/* A method whose result is written in pieces: begin reads the params,
 * step appends the next part of the result's JSON text (all of it, from
 * its opening brace), spending at most
 * about `budget` units (added to *used), free ends it.  Step returns
 * WP_STEP_FAILED with `error` set when it cannot go on.  The call's fixture
 * stays held until free. */
typedef struct wp_stream wp_stream;
/* params.wrenches of a long line, read by the envelope straight from the
 * text as numbers (their place in params holds []): begin takes the array
 * (sets `wrenches` NULL) when it uses it. */
typedef struct wp_prepared {
    double (*wrenches)[3];
    size_t count;
} wp_prepared;
typedef struct wp_streamer {
    wp_stream *(*begin)(wp_call *call, wp_prepared *prepared);
    wp_step (*step)(wp_stream *stream, wp_call *call, wp_buffer *out, unsigned long budget,
                    unsigned long *used);
    void (*free)(wp_stream *stream);
    size_t (*bytes)(const wp_stream *stream); /* what it holds */
    /* True: the envelope does not open the response; step may first write
     * whole notification lines (progress) and then opens it with
     * wp_call_open_result before its result's text. */
    bool opens_result;
    /* Optional, both or neither: work that other threads may do while a
     * step runs.  `parallel`: is some to be had now?  `work`: do a bounded
     * piece of it (false when there was none, or it failed).  A step that
     * begins while `parallel` is true must not end the stream (return
     * WP_STEP_DONE or FAILED), since `work` may still be running in
     * another thread until that step returns. */
    bool (*parallel)(wp_stream *stream);
    bool (*work)(wp_stream *stream, const wp_host *host);
} wp_streamer;

/* Open the response whose result follows (a streamer with opens_result). */
void wp_call_open_result(wp_call *call, wp_buffer *out);
/* The call's id as the response will write it ("null" for none). */
const char *wp_call_id_text(const wp_call *call);
/* Can the call send notifications before its response: a request of its
 * own (not a batch member) answered in pieces (not wp_answer_line)? */
bool wp_call_may_notify(const wp_call *call);

/* Method flags: what the envelope needs to know of a method, checked in
 * one place (wp_rpc.c). */
#define WP_FIXTURE 1u /* takes params.fixture, an id or an inline fixture,
                         held by the envelope for the call (wp_call_fixture) */
#define WP_CHEAP 2u   /* no derivation, no solver, no disk: microseconds,
                         always; a batch answers several in one piece */
#define WP_READY 4u   /* as cheap when its fixture is a stored one whose
                         derived data is ready (and `light` agrees, if set) */

/* The method table: every method name, served or announced. */
typedef struct wp_method {
    const char *name;
    /* Returns the result, or NULL with call->error set.  A method with
     * neither handler nor stream is announced but not served yet (-32601). */
    cJSON *(*handler)(wp_call *call);
    const wp_streamer *stream;    /* or a result written in pieces */
    const char *const *fields;    /* params it accepts, NULL-ended */
    const char *const *required;  /* of those, the ones it needs */
    unsigned flags;               /* WP_FIXTURE, WP_CHEAP, WP_READY */
    /* With WP_READY: is this call light, given the fixture's number of
     * cones?  NULL: yes.  A cost estimate, in the table's own terms. */
    bool (*light)(const cJSON *params, int cones);
    const char *summary;          /* one line, for --help and the README */
} wp_method;

extern const wp_method wp_methods[];   /* ends with a zeroed entry */
const wp_method *wp_method_find(const char *name);

#ifdef __cplusplus
}
#endif

#endif
