/* load_client.h -- one client of the load generator: one connection to the
 * daemon, the lines it writes (single requests, notifications, batches, its
 * private fixture's steps) and the check of every answer it reads.
 *
 * Ownership: a client owns its connection and the lines it has in flight;
 * it reads the table and the settings, which must outlive it and not change
 * while it runs, and changes only its own private fixture and stats.  So the
 * driver may run any number of clients on as many threads at once.
 *
 * Contract: answers come in the order of the lines (the daemon answers a
 * connection's lines in order).  Each answer is matched to the oldest line
 * in flight by its id: an answer matching a later line means those before
 * it were lost; one matching nothing in flight is unexpected; one whose
 * content differs from the table's expected answer is wrong.  When it has
 * written everything, it half-closes the connection and reads to the end:
 * nothing more may come.  bench/README.md ("The load") says the same. */
#ifndef LOAD_CLIENT_H
#define LOAD_CLIENT_H

#include "load_requests.h"

#include <signal.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

typedef struct client_settings {
    const char *socket_path;
    const table *table;
    int pipeline;        /* lines in flight at most */
    int timeout_seconds; /* silence this long: the rest is lost */
    long lines;          /* lines to write, unless deadline > 0 */
    double deadline;     /* > 0: write until this bench_seconds() instead */
    volatile sig_atomic_t *stop; /* set (by a signal): write no more */
} client_settings;

/* What one client saw; the driver adds them up. */
typedef struct client_stats {
    unsigned long lines, requests, batches, notifications, answered_lines;
    unsigned long answers_expected_errors, answers_seen_errors;
    unsigned long server_requests, server_errors; /* what the daemon should count */
    unsigned long wrong, lost, unexpected;
    bool failed;                     /* the connection broke or timed out */
    char failure[160];
    double *latency;                 /* microseconds, one per answered line */
    size_t latency_count, latency_capacity;
    unsigned long by_category[CATEGORY_COUNT + 1]; /* the last: private steps */
} client_stats;

typedef struct client {
    /* Set by the driver before client_run. */
    int index;                       /* in reports and ids; -1: the warm-up */
    const client_settings *settings;
    uint64_t random;                 /* the stream its lines are drawn from */
    private_fixture *private_fixture; /* NULL: none */
    /* Non-NULL: write these once each, in order, one request a line, instead
     * of drawing lines from the table (the warm-up). */
    const request *const *script;
    size_t script_count;
    /* Read by the driver after. */
    client_stats stats;
} client;

/* Connect, write and check until done (see client_settings), then close.
 * A thread's start routine: the argument is the client; returns NULL.  A
 * connection that cannot be made or breaks is recorded in stats.failed. */
void *client_run(void *client);

/* The daemon's requests and errors counters from server.status on a new
 * connection.  False if it cannot be reached or answers otherwise. */
bool server_counts(const client_settings *settings, double *requests, double *errors);

#endif
