/* wd_server.h -- the daemon: a libevent loop on a Unix stream socket, worker
 * threads, the fixture cache. */
#ifndef WD_SERVER_H
#define WD_SERVER_H

#include <stdbool.h>
#include <stddef.h>

typedef struct wd_config {
    const char *socket_path;    /* listening socket */
    const char *state_dir;      /* NULL: fixtures kept in memory only */
    const char **load_files;    /* fixtures to put at start */
    int load_count;
    int threads;                /* worker threads */
    size_t cache_bytes;         /* bound on derived data */
    size_t max_fixtures;        /* most stored fixtures */
    size_t max_line;            /* longest request line, bytes */
    int max_depth;              /* deepest JSON nesting */
    size_t max_wrenches;        /* most wrenches in one request */
    size_t max_output;          /* most unsent output per client, bytes: its
                                   work pauses above it */
    unsigned long max_clients;  /* most concurrent clients */
    unsigned long max_clients_per_uid; /* most concurrent clients of one user;
                                   0: no cap but max_clients */
    size_t max_batch;           /* most requests in one batch */
    unsigned long long max_candidates; /* most candidates of one design */
    size_t max_cases;           /* most load cases in one request */
    unsigned idle_timeout;      /* seconds without a request in flight, or with
                                   answers left unread, before a connection is
                                   closed; 0: never */
    unsigned request_timeout;   /* seconds from a request's first byte to its
                                   last; 0: no limit */
    const unsigned *allow_uids; /* peers admitted by user id; none: no check */
    int allow_uid_count;
    const unsigned *allow_gids; /* ... or by primary or supplementary group */
    int allow_gid_count;
    bool allow_any_uid;         /* "any" given for a list: everyone is admitted */
    bool allow_any_gid;
    int listen_fd;              /* a socket systemd passed, or -1 to bind socket_path */
} wd_config;

/* Most entries in each allow list. */
#define WD_MAX_ALLOWED 64

/* Exit statuses of wrenchd. */
enum { WD_EXIT_OK = 0, WD_EXIT_START = 1, WD_EXIT_USAGE = 2 };

/* Serve until SIGTERM or SIGINT: then stop accepting, answer what is in
 * flight, remove the socket file.  Returns the exit status. */
int wd_server_run(const wd_config *config);

#endif
