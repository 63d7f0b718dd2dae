/* load_requests.h -- the load generator's table of requests: which requests
 * it sends, how each is built from the seed, what answer each must get and
 * how an answer is compared with it.  bench/README.md ("The table",
 * "Expected answers") says what is in it.
 *
 * Ownership: the table owns every request, the text sent and the expected
 * answer, and the fixtures they were made of; it lives until the program
 * ends.  table_build is the only writer; after it returns the table is
 * read-only, so the clients read it from many threads without a lock.  A
 * private fixture belongs to one client: only that client's thread may call
 * private_fixture_next on it. */
#ifndef LOAD_REQUESTS_H
#define LOAD_REQUESTS_H

#include <cjson/cJSON.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

/* What the table is made from.  The daemon's limits matter because the
 * expected answers depend on them: they must be the daemon's. */
typedef struct table_settings {
    uint64_t seed;
    const char *examples; /* directory of *.json fixtures, put and named by id */
    int fixtures;         /* generated fixtures only ever sent inline */
    int stored;           /* generated fixtures put with the examples */
    int lp_percent;       /* classifies with "method": "lp" */
    long max_wrenches;    /* the daemon's --max-wrenches */
    long max_batch;       /* the daemon's --max-batch */
    int max_depth;        /* the daemon's --max-depth */
    bool measure_lp;      /* measure each fixture's warm LPs (slow; table_describe) */
} table_settings;

/* How an answer is compared with the expected one, after both are
 * canonicalised without their "id". */
enum {
    CHECK_EXACT,
    CHECK_LOOSE,      /* a -32001 error without its data.reason: the daemon's wording */
    CHECK_NO_WITNESS, /* an "lp" classify without witnesses: LP witnesses are not unique */
    CHECK_STATUS,     /* server.status: the names and types of its members */
    CHECK_LIST        /* fixture.list: sorted, well formed, the shared fixtures there */
};

/* The kinds of request, for drawing single lines by weight and counting
 * what was sent. */
enum {
    CATEGORY_PUT, CATEGORY_GET, CATEGORY_CLASSIFY, CATEGORY_BATCH_CLASSIFY, CATEGORY_CONE,
    CATEGORY_PLAN, CATEGORY_MODES, CATEGORY_PUSH, CATEGORY_GRAVITY, CATEGORY_MARGIN,
    CATEGORY_STATUS, CATEGORY_LIST, CATEGORY_ERROR, CATEGORY_RAW, CATEGORY_COUNT
};
#define CATEGORY_PRIVATE (-1) /* a private fixture's request: in no category */

extern const char *const CATEGORY_NAMES[CATEGORY_COUNT];

#define REQUEST_RAW 1u        /* sent as is: no id is added */
#define REQUEST_NOTIFIABLE 2u /* a valid request: may go without an id */
#define REQUEST_BATCHABLE 4u  /* may be a member of a JSON-RPC batch */

/* One request of the table. */
typedef struct request {
    int category;    /* CATEGORY_*, or CATEGORY_PRIVATE */
    unsigned flags;  /* REQUEST_* */
    int check;       /* CHECK_* */
    char *wire;      /* object text without its closing '}', or the raw line */
    char *oracle;    /* the same for the in-process answer (fixture inline); NULL: wire */
    char *expected;  /* canonical answer, without "id" unless raw; NULL: no answer */
    int answer_errors;              /* error objects in the expected answer */
    unsigned long counted_requests; /* what the daemon counts for it... */
    unsigned long counted_errors;   /* ...and of them, errors */
    bool given;      /* expected set when built, not by the oracle */
} request;

typedef struct table table;

/* Build the table and compute every expected answer (on every core).  Dies
 * on an invalid example or when two fixtures have the same content. */
table *table_build(const table_settings *settings);

size_t table_size(const table *t);
const request *table_request(const table *t, size_t index); /* in the order built: puts first */
size_t table_fixture_count(const table *t);

/* A request for a single line: a category by CATEGORY weight, then one of
 * its requests, both drawn from *stream. */
const request *table_pick(const table *t, uint64_t *stream);

/* A raw request that may stand in a batch (an invalid member). */
const request *table_pick_raw_batchable(const table *t, uint64_t *stream);

/* The canonical text an answer to r is compared by, r->expected's form
 * (the caller frees).  Normalising changes `answer`. */
char *table_comparable(const table *t, cJSON *answer, const request *r);

/* Error objects in an answer, a batch's answer counting each member. */
int answer_error_count(const cJSON *answer);

/* --describe: the table's make-up and the sizes of its fixtures' derived
 * data and warm LPs, as name=value lines on stdout. */
void table_describe(const table *t, double build_seconds);

/* --dump: every request, three lines each: the request (with id 0 unless
 * raw), "requests errors" as the daemon counts them, the expected answer. */
void table_dump(const table *t);

/* ---- private fixtures: a store only one client changes ----------------- */

enum { PRIVATE_PUT, PRIVATE_GET, PRIVATE_CLASSIFY, PRIVATE_DELETE, PRIVATE_STEPS };

/* A fixture only one client puts, reads, classifies by id and deletes: the
 * expected answer of each step depends on whether it is stored then, which
 * only that client's order of steps decides. */
typedef struct private_fixture {
    request steps[PRIVATE_STEPS][2]; /* [step][stored before it ran] */
    bool stored;                     /* as that client's steps so far leave it */
    bool put_once;                   /* put at least once: other steps may come */
} private_fixture;

/* One private fixture per client, made from the table's seed. */
private_fixture *private_fixtures_make(const table *t, int clients);

/* The next step, drawn from *stream (a put until there has been one). */
const request *private_fixture_next(private_fixture *p, uint64_t *stream);

#endif
