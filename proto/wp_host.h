/* wp_host.h -- what the daemon implements for proto: the fixture store and
 * the solver state a request needs, handed over as data.  proto calls it;
 * it never calls proto (docs/ARCHITECTURE.md, "The seam between proto and
 * the daemon"). */
#ifndef WP_HOST_H
#define WP_HOST_H

#include "wp_fixture.h"

#ifdef __cplusplus
extern "C" {
#endif


/* What a host's function reports when it fails: data, in the host's own
 * words, never a JSON-RPC code.  proto maps it to a code and a field, in
 * one place (wp_error_host, next to wp_error_status in wp_error.c). */
typedef enum wp_host_status {
    WP_HOST_OK = 0,
    WP_HOST_NO_MEMORY,     /* out of memory (deriving the cones, say) */
    WP_HOST_NO_FIXTURE,    /* no stored fixture has the id; or no store at all */
    WP_HOST_STORAGE,       /* the state directory failed; the reason says how */
    WP_HOST_LIMIT,         /* --max-fixtures fixtures are stored already */
    WP_HOST_UNSUPPORTED    /* the host does not serve the method (no daemon) */
} wp_host_status;

typedef struct wp_host_failure {
    wp_host_status status;
    char reason[256];      /* a sentence for a person */
} wp_host_failure;

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

/* An inline fixture's text this long or longer is given to the host to
 * keep (fixture_use_text): below it, reading the object costs less than
 * keeping it. */
#define WP_INLINE_TEXT_MIN 4096

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
                          wp_host_failure *failure);
    /* Hold the fixture adopted from an inline object whose written key
     * (wp_fixture_written_key, doc->written at the adoption) is `key`, if
     * it is still kept: true, held, and the object need not be read again.
     * False: not kept (or out of memory), nothing held.  May be NULL. */
    bool (*fixture_use_written)(void *self, const char *key, wp_fixture_use *use);
    /* Hold the fixture adopted from an inline object whose text as written
     * (doc->text at the adoption; only texts of WP_INLINE_TEXT_MIN bytes on
     * are given) begins text[0, length), if it is still kept: the kept
     * text's length, held.  0: none kept (or out of memory), nothing held.
     * The envelope then need not read the object at all (wp_rpc.c,
     * recognise_fixture, says why that is sound).  May be NULL. */
    size_t (*fixture_use_text)(void *self, const char *text, size_t length, wp_fixture_use *use);
    /* Hold the stored fixture `id`; WP_HOST_NO_FIXTURE when there is none. */
    bool (*fixture_use)(void *self, const char *id, wp_fixture_use *use,
                        wp_host_failure *failure);
    /* Hold the stored fixture `id` only if its derived data is ready (using
     * it then costs no derivation): its number of cones (goal + strong), or
     * -1 with nothing held.  May be NULL: never ready. */
    int (*fixture_use_ready)(void *self, const char *id, wp_fixture_use *use);
    void (*fixture_release)(void *self, wp_fixture_use *use);
    /* Forget the stored fixture `id` (and its file); WP_HOST_NO_FIXTURE,
     * WP_HOST_STORAGE. */
    bool (*fixture_delete)(void *self, const char *id, wp_host_failure *failure);
    /* The stored fixtures, and the server's state. */
    bool (*fixture_list)(void *self, wp_fixture_listing *listing, wp_host_failure *failure);
    bool (*state)(void *self, wp_server_state *state, wp_host_failure *failure);
    /* This thread's warm LP sets for a fixture in use: WR_OK, or why not. */
    wr_status (*lp_sets)(void *self, wp_fixture_use *use, wr_lp_set **goal,
                         wr_lp_set **strong);
    /* Polled by long work between bounded units (wrenches, edges): set by
     * the host to the request's own stop before each piece of work, so that
     * work for a client that hung up ends.  NULL: never stops. */
    const wr_stop *stop;
    /* This thread's GLPK environment, for LPs a method builds itself (a
     * fixture on supports: wr_support.h).  Never freed by the caller. */
    wr_lp_env *(*lp_env)(void *self);
} wp_host;

/* The error of a host function that failed, the one place host statuses
 * become JSON-RPC codes (wp_error.c): WP_HOST_NO_MEMORY is WP_INTERNAL,
 * NO_FIXTURE WP_NO_FIXTURE, STORAGE WP_STORAGE, each at `field` (the
 * parameter that named the fixture, or ""); LIMIT is WP_LIMIT at
 * params.fixture (what a put would add); UNSUPPORTED is WP_NO_METHOD at
 * "method".  The reason is the host's. */
void wp_error_host(wp_error *error, const wp_host_failure *failure, const char *field);

#ifdef __cplusplus
}
#endif

#endif
