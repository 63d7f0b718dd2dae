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

typedef struct wp_host {
    void *self;
    /* Keep a validated fixture and hold it: stored (persisted, listed) when
     * `store`, else only cached under its id (an inline fixture).  Takes
     * the doc's contents whatever the outcome. */
    bool (*fixture_adopt)(void *self, wp_fixture_doc *doc, bool store, wp_fixture_use *use,
                          wp_error *error);
    /* Hold the stored fixture `id`; WP_NO_FIXTURE when there is none. */
    bool (*fixture_use)(void *self, const char *id, wp_fixture_use *use, wp_error *error);
    void (*fixture_release)(void *self, wp_fixture_use *use);
    /* Forget the stored fixture `id` (and its file); WP_NO_FIXTURE, WP_STORAGE. */
    bool (*fixture_delete)(void *self, const char *id, wp_error *error);
    /* The result of fixture.list and of server.status (NULL: out of memory). */
    cJSON *(*fixture_list)(void *self);
    cJSON *(*status)(void *self);
    /* This thread's warm LP sets for a fixture in use. */
    bool (*lp_sets)(void *self, wp_fixture_use *use, wr_lp_set **goal, wr_lp_set **strong,
                    wp_error *error);
    /* Is the stored fixture `id` there with its derived data, so that using
     * it costs no derivation?  Its number of cones (goal + strong), or -1.
     * May be NULL: never. */
    int (*fixture_ready)(void *self, const char *id);
} wp_host;

typedef struct wp_limits {
    int max_depth;        /* deepest nesting of arrays and objects */
    size_t max_wrenches;  /* most wrenches in one wrench.classify */
    size_t max_batch;     /* most requests in one batch */
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

/* Lines up to this long may be light; a classify, when its wrenches times
 * its fixture's cones are at most WP_LIGHT_CONE_CHECKS (tens of
 * microseconds). */
#define WP_LIGHT_LINE 2048
#define WP_LIGHT_CONE_CHECKS 1024
/* Answer `line` as wp_answer_line does -- but only if that is light work:
 * microseconds, no GLPK, no derivation, no disk -- so that an event loop
 * may answer it itself rather than pay two thread hand-offs.  Light: a line
 * refused before any request is read (not JSON, too deep), an invalid
 * request object, server.status, and wrench.classify by the "auto" method
 * against a stored fixture whose derived data is ready
 * (host->fixture_ready), of so few wrenches that wrenches x cones <=
 * WP_LIGHT_CONE_CHECKS.  Conservative: anything else,
 * batches included, is not.  Returns true with *answer set (NULL for a
 * notification) and counts added, or false with nothing counted: answer it
 * with wp_answer_line elsewhere. */
bool wp_answer_light(const wp_host *host, const wp_limits *limits, const char *line,
                     size_t length, wp_counts *counts, char **answer);

/* A response line for an error found before the line was read (a line over
 * the length limit, too many clients): id null.  Malloc'd, or NULL. */
char *wp_error_line(int code, const char *field, const char *reason);

/* The method table: every method name, served or announced. */
typedef struct wp_method {
    const char *name;
    /* Returns the result, or NULL with `error` set.  NULL handler: the method
     * is announced but not served yet (answered -32601). */
    cJSON *(*handler)(const wp_host *host, const wp_limits *limits, const cJSON *params,
                      wp_error *error);
    const char *const *fields;    /* params it accepts, NULL-ended */
    const char *const *required;  /* of those, the ones it needs */
    const char *summary;          /* one line, for --help and the README */
} wp_method;

extern const wp_method wp_methods[];   /* ends with a zeroed entry */
const wp_method *wp_method_find(const char *name);

#ifdef __cplusplus
}
#endif

#endif
