/* wp_method.h -- what a method uses: its call (params, host, error), its
 * fixture, the shape of a result written in pieces, and its row of the
 * method table (wp_methods.c).  The envelope (wp_rpc.c) acts on the rows;
 * the handlers (proto/methods/) see only this header. */
#ifndef WP_METHOD_H
#define WP_METHOD_H

#include "wp_rpc.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The fixture of a request in hand, held for the envelope (invariant:
 * `holding` iff use.handle[0] is the host's): from the light check on, or
 * for the call, or until a streamed result's last piece. */
typedef struct wp_fixture_hold {
    wp_fixture_use use;
    bool holding;
    /* params.fixture's text as the line wrote it (not NUL-ended), for the
     * host to keep at the adoption (wp_host.h, fixture_use_text), or NULL;
     * owned by the envelope, freed with the hold. */
    char *text;
    size_t text_length;
} wp_fixture_hold;

/* One call of a method: what its handler reads and where it says what
 * went wrong. */
typedef struct wp_call {
    const wp_host *host;
    const wp_limits *limits;
    cJSON *params;               /* the request's params ({} when left out);
                                    a stream's begin may take out what it
                                    has read, to free it early */
    wp_error *error;
    wp_fixture_hold *fixture;    /* the envelope's, for wp_call_fixture */
    const char *id_text;         /* the id as the response writes it ("null") */
    bool may_notify;             /* wp_call_may_notify */
    /* params.<raw_text> as written (wp_method.raw_text), or NULL: a
     * request of its own only, not a batch member. */
    struct wp_prepared *prepared;
} wp_call;

/* The call's fixture (params.fixture: a stored id, or an inline fixture),
 * for a method flagged WP_FIXTURE: looked up on the first call (so that a
 * handler reads its cheaper params first), then held by the envelope until
 * the call ends -- for a streamed result, until its last piece.  NULL with
 * call->error set when there is none. */
wp_fixture_use *wp_call_fixture(wp_call *call);

/* params.<raw_array> of a long line (wp_method.raw_array), read by the
 * envelope straight from the text as triples of numbers (their place in
 * params holds []): begin takes the array (sets `wrenches` NULL) when it
 * uses it. */
typedef struct wp_prepared {
    double (*wrenches)[3];
    size_t count;
    /* params.<raw_text> (wp_method.raw_text): its text, NUL-ended and the
     * method's to write in (it may end strings in place), from a line the
     * scan passed (wp_json_scan: numbers in JSON's form, escapes, UTF-8);
     * the tree holds [] in its place.  NULL when the request has none. */
    char *text;
    size_t length;
} wp_prepared;

/* A method whose result is written in pieces: begin reads the params and
 * returns the stream's own state (opaque to the envelope), step writes
 * the next part of the result with the response's writer (all of it, from
 * its opening brace; the writer keeps its nesting from one step to the
 * next, each step's text going to the writer's `out`), spending at most about `budget` units (added to *used), free
 * ends it.  Step returns WP_STEP_FAILED with `error` set when it cannot go
 * on.  The call's fixture stays held until free. */
typedef struct wp_streamer {
    void *(*begin)(wp_call *call, wp_prepared *prepared);
    wp_step (*step)(void *stream, wp_call *call, wp_writer *out, unsigned long budget,
                    unsigned long *used);
    void (*free)(void *stream);
    size_t (*bytes)(const void *stream); /* what it holds */
    /* True: the envelope does not open the response; step may first write
     * whole notification lines (progress) and then opens it with
     * wp_call_open_result before its result's text. */
    bool opens_result;
    /* Optional, both or neither: chunks that helpers may make while a step
     * runs, by the engine (wp_chunks.h, which states and enforces the rule
     * that keeps the stream alive while a helper is in it): `parallel` is
     * wp_chunks_parallel, `work` wp_chunks_work. */
    bool (*parallel)(void *stream);
    bool (*work)(void *stream, const wp_host *host);
} wp_streamer;

/* Open the response whose result follows (a streamer with opens_result). */
void wp_call_open_result(wp_call *call, wp_writer *out);
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

/* The method table: a row per method.  Every row has a handler or a
 * stream. */
typedef struct wp_method {
    const char *name;
    /* Writes the result with `out`; false with call->error set (the
     * envelope takes back what it wrote). */
    bool (*handler)(wp_call *call, wp_writer *out);
    const wp_streamer *stream;    /* or a result written in pieces */
    const char *const *fields;    /* params it accepts, NULL-ended */
    const char *const *required;  /* of those, the ones it needs */
    unsigned flags;               /* WP_FIXTURE, WP_CHEAP, WP_READY */
    /* With WP_READY: is this call light, given the fixture's number of
     * cones?  NULL: yes.  A cost estimate, in the table's own terms. */
    bool (*light)(const cJSON *params, int cones);
    /* A member of params that a long line may hold as a long array of
     * [x, y, z] numbers: read straight from the text, without a tree node
     * per number (wp_prepared), for the stream's begin.  NULL: none. */
    const char *raw_array;
    /* A member of params the handler reads from its text, at any length
     * (wp_prepared.text), without a tree node per value: cut from the line
     * before it is parsed.  NULL: none. */
    const char *raw_text;
} wp_method;

extern const wp_method wp_methods[];   /* ends with a zeroed entry */
const wp_method *wp_method_find(const char *name);

#ifdef __cplusplus
}
#endif

#endif
