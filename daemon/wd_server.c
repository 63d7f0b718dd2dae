/* wd_server.c -- the event loop: listening socket, connections, answers in
 * order, limits, signals.
 *
 * Threads: everything here runs in the loop thread except job_done, which
 * workers call; it only appends to the `done` list under its lock and wakes
 * the loop.  Connections are owned by the loop thread.
 *
 * Order: each line read becomes a queued line at the tail of its
 * connection's queue.  A connection has at most one request with the workers at a time,
 * taken in queue order, so its requests run as if sent one by one (a put
 * followed by a query of its id works when pipelined); answers are written
 * from the head, in the order asked.  Connections run in parallel.
 *
 * Memory: a request's answer is made a piece at a time (wd_task), each
 * piece sent as it comes; the next piece is made only while the
 * connection's unsent output (and what its request holds) is under
 * --max-output, so a client that does not read holds at most that much
 * and one piece.  Unread output for --idle-timeout closes the connection.
 * Waiting request lines are held up to --max-line bytes; beyond that the
 * connection is not read.
 *
 * Fairness: each task carries its peer's uid; the workers take users in
 * turn and each user's tasks in order, each task going back to the tail of
 * its user's queue after each piece (wd_pool), so users share the workers
 * round-robin, a piece each, however many connections each holds;
 * --max-clients-per-uid caps those connections.
 *
 * Cancellation: a client that is gone (its socket closed, or hung up
 * while answers were still to come) has its waiting requests dropped and
 * its running one stopped at the next poll (wr_stop: between wrenches,
 * edges, samples).  A hang-up is noticed whether or not its connection is
 * being read (pause_reading). */
/* SO_PEERCRED, SO_PEERGROUPS and struct ucred are Linux's. */
#define _GNU_SOURCE
#include "wd_server.h"
#include "wd_listen.h"
#include "wd_log.h"
#include "wd_peer.h"
#include "wd_systemd.h"
#include "wd_worker.h"

#include <errno.h>
#include <event2/buffer.h>
#include <event2/bufferevent.h>
#include <event2/event.h>
#include <event2/listener.h>
#include <event2/thread.h>
#include <assert.h>
#include <fcntl.h>
#include <poll.h>
#include <pthread.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/ioctl.h>
#include <sys/types.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <unistd.h>

/* A connection stops reading while this many answers are pending. */
#define MAX_PENDING 1024
/* Answers from this size on are handed to libevent rather than copied. */
#define ZERO_COPY_BYTES 65536
/* After SIGTERM, answers in flight get this long before the daemon exits. */
#define SHUTDOWN_GRACE_SECONDS 30
/* Most bytes one read of a connection takes (a Unix socket holds a few
 * hundred KiB). */
#define READ_BYTES (1 << 20)
/* Most bytes one read takes otherwise: a request or several, and the first
 * read into an empty input. */
#define SHORT_READ_BYTES 65536
#define FIRST_READ_BYTES 4000
/* A line without its end this long is moved out of the input as it comes,
 * so that each byte is searched for the end once. */
#define PARTIAL_BYTES 65536

typedef struct wd_server wd_server;
typedef struct connection connection;

typedef struct queued_line {
    struct queued_line *next;
    connection *connection;
    char *line;           /* the request, until handed to a worker */
    size_t length;
    bool done;            /* answered (or dropped): flush may remove it */
    char *response;       /* an answer made whole in the loop; NULL: nothing
                             to write (notifications, or an answer whose
                             pieces the workers made and were sent) */
    size_t response_length; /* 0: not counted yet */
    wd_task *task;        /* the request with the workers, or parked */
} queued_line;

struct connection {
    connection *prev, *next;   /* the server's list */
    wd_server *server;
    struct bufferevent *bev;   /* NULL once the socket is closed */
    queued_line *head, *tail;
    size_t pending;            /* queued lines not yet written (or dropped) */
    queued_line *running;      /* the queued line being answered by the workers
                                  (its task with them, or parked), or NULL */
    bool parked;               /* running's task waits for the client to read */
    size_t held;               /* bytes running's answer holds between pieces */
    size_t queued_bytes;       /* bytes of request lines waiting in queued lines */
    struct event *request_timer; /* a request begun must arrive whole in time */
    bool discarding;           /* skipping the rest of an over-long line */
    int light_answered;        /* light requests answered in the loop since
                                  the last read (at most WP_LIGHT_BURST) */
    struct event *read_event;  /* the socket's reading (not the bufferevent's) */
    struct timeval read_timeout; /* idle or linger; 0: none */
    bool reading;              /* read_event is added */
    char *partial;             /* the start of a long line, moved out of the
                                  input (malloc'd): the input then holds only
                                  bytes not yet searched for its end */
    size_t partial_length, partial_capacity;
    bool paused;               /* not reading: too many requests waiting */
    struct event *hangup_event; /* while paused: the peer's hang-up (EV_CLOSED,
                                  epoll's EPOLLRDHUP), which reading would
                                  have seen */
    bool input_closed;         /* end of input, or shutting down */
    bool refusing;             /* turned away: one error line, then a lingering
                                  close (its input is read and dropped) */
    bool write_shut;           /* refusing: shutdown(SHUT_WR) done */
    int busy;                  /* callbacks running on it: not freed meanwhile */
    unsigned long number;      /* for the log */
    unsigned uid;              /* the peer's user (SO_PEERCRED); its tasks
                                  are served in that user's turn */
};

struct wd_server {
    const wd_config *config;
    const wp_host *loop_host;       /* the loop's own (s->light): frees tasks */
    struct event_base *base;
    struct evconnlistener *listener;
    struct event *done_event, *signal_events[2], *grace_timer;
    wd_pool *pool;
    wd_thread_host *light;              /* the loop's own host, for light requests */
    wd_cache *cache;
    wd_stats stats;
    wp_limits limits;
    pthread_mutex_t done_lock;
    wd_task *done_head, *done_tail; /* pieces made by workers, not yet sent */
    connection *connections;
    unsigned long connection_count, numbers;
    unsigned long refusing;         /* of the connections, those being turned away */
    bool stopping;
    wd_listen_file socket_file;     /* the socket file made, removed at exit */
    struct event *accept_timer;     /* accepting again after running out of descriptors */
    wd_log_limit denied_log, refused_log, accept_log;
};

static void process_input(connection *c);
static void dispatch(connection *c);

/* ---- connections ------------------------------------------------------------ */

static void free_connection(connection *c)
{
    wd_server *s = c->server;
    if (c->prev)
        c->prev->next = c->next;
    else
        s->connections = c->next;
    if (c->next)
        c->next->prev = c->prev;
    s->connection_count--;
    if (c->refusing)
        s->refusing--;
    for (queued_line *x = c->head, *next; x; x = next) {
        next = x->next;
        assert(!x->task || c->parked || s->stopping); /* none with the workers */
        wd_task_free(x->task, s->loop_host);
        free(x->line);
        free(x->response);
        free(x);
    }
    if (c->request_timer)
        event_free(c->request_timer);
    free(c->partial);
    free(c);
    if (s->stopping && !s->connections)
        event_base_loopexit(s->base, NULL);
}

/* The client is gone: drop the requests waiting, free a parked task, and
 * ask the workers to stop the one they have. */
static void cancel_work(connection *c)
{
    for (queued_line *x = c->head; x; x = x->next) {
        if (x->done)
            continue;
        if (x->task) {
            if (c->parked) {
                wd_task_free(x->task, c->server->loop_host);
                x->task = NULL;
                c->parked = false;
                c->running = NULL;
                x->done = true;
            } else {
                atomic_store(&x->task->cancelled, true); /* on_done drops it */
            }
        } else if (x->line) {
            c->queued_bytes -= x->length;
            free(x->line);
            x->line = NULL;
            x->done = true;
        }
    }
    assert(c->queued_bytes == 0);
}

/* Reading is the daemon's own: a bufferevent reads 4 KiB at a time, each
 * after an ioctl(FIONREAD) (libevent 2.1), so that a long line took a
 * wake-up per 4 KiB and every request one system call more than it needs.
 * The bufferevent keeps the writing (and its write timeout); read_event
 * (persistent, with the idle or linger timeout, which each read restarts)
 * puts what it reads into the bufferevent's input, where the rest of this
 * file finds it. */
static void reading_on(connection *c)
{
    if (!c->bev || !c->read_event)
        return;
    bool timed = c->read_timeout.tv_sec > 0 || c->read_timeout.tv_usec > 0;
    event_add(c->read_event, timed ? &c->read_timeout : NULL);
    c->reading = true;
}

static void reading_off(connection *c)
{
    if (c->read_event && c->reading)
        event_del(c->read_event);
    c->reading = false;
}

/* The idle (or linger) timeout of reading and of writing. */
static void set_timeouts(connection *c, const struct timeval *timeout)
{
    c->read_timeout = *timeout;
    bufferevent_set_timeouts(c->bev, NULL, timeout);
    if (c->reading)
        reading_on(c); /* again, with the new timeout */
}

static void on_hangup(evutil_socket_t fd, short what, void *argument);

/* Reading paused (too many requests waiting), a hang-up would go unseen
 * until reading resumes, and the work asked would run for nobody: the
 * hang-up is watched on its own meanwhile (EV_CLOSED, where the backend
 * has it), and each piece made asks too (piece_done). */
static void pause_reading(connection *c)
{
    c->paused = true;
    reading_off(c);
    if (!c->hangup_event)
        c->hangup_event = event_new(c->server->base, bufferevent_getfd(c->bev), EV_CLOSED,
                                    on_hangup, c);
    if (c->hangup_event)
        event_add(c->hangup_event, NULL);
}

static void unpause(connection *c)
{
    c->paused = false;
    if (c->hangup_event)
        event_del(c->hangup_event);
}

/* One read of at most `most` bytes into the input: 0 when some were read,
 * -1 when none were there, else BEV_EVENT_EOF or BEV_EVENT_ERROR. */
static int read_input(connection *c, size_t most)
{
    struct evbuffer *input = bufferevent_get_input(c->bev);
    struct evbuffer_iovec space;
    if (evbuffer_reserve_space(input, (ev_ssize_t)most, &space, 1) < 1)
        return BEV_EVENT_ERROR; /* no memory for it */
    size_t room = space.iov_len < most ? space.iov_len : most;
    ssize_t n = recv(bufferevent_getfd(c->bev), space.iov_base, room, MSG_DONTWAIT);
    if (n > 0) {
        space.iov_len = (size_t)n;
        evbuffer_commit_space(input, &space, 1);
        return 0;
    }
    int error = errno;
    evbuffer_commit_space(input, &space, 0);
    errno = error; /* for the log */
    if (n == 0)
        return BEV_EVENT_EOF;
    return error == EAGAIN || error == EWOULDBLOCK || error == EINTR ? -1 : BEV_EVENT_ERROR;
}

static void close_socket(connection *c)
{
    if (!c->bev)
        return;
    if (c->request_timer)
        event_del(c->request_timer);
    /* Unread input at close makes the kernel reset the connection, which
     * can destroy answers not yet delivered: read it away first. */
    evutil_socket_t fd = bufferevent_getfd(c->bev);
    char sink[4096];
    while (recv(fd, sink, sizeof sink, MSG_DONTWAIT) > 0)
        ;
    if (c->read_event)
        event_free(c->read_event);
    c->read_event = NULL;
    c->reading = false;
    if (c->hangup_event)
        event_free(c->hangup_event);
    c->hangup_event = NULL;
    bufferevent_free(c->bev);
    c->bev = NULL;
    atomic_fetch_sub(&c->server->stats.clients, 1);
    cancel_work(c);
}

/* Free the connection once nothing more will be read or written: its input
 * ended (or the socket is gone) and every answer has been written out. */
/* Take the answered queued line at the head of the queue off it. */
static void remove_head(connection *c)
{
    queued_line *x = c->head;
    assert(x && x->done && !x->task);
    c->head = x->next;
    if (!c->head)
        c->tail = NULL;
    c->pending--;
    free(x->response);
    free(x);
}

static void maybe_finish(connection *c)
{
    if (c->busy)
        return; /* the outermost callback comes back here */
    while (!c->bev && c->head && c->head->done)
        remove_head(c); /* gone: answered and cancelled requests leave without a word */
    if (c->bev && !c->input_closed)
        return;
    if (c->pending > 0)
        return; /* answers still to come (or to drop) */
    if (c->bev && evbuffer_get_length(bufferevent_get_output(c->bev)) > 0)
        return; /* the write callback comes back here */
    close_socket(c);
    free_connection(c);
}

static void free_response(const void *data, size_t length, void *block)
{
    (void)data;
    (void)length;
    free(block);
}

/* Write a queued line's answer.  With nothing queued before it, straight
 * to the socket: a small answer then costs one send(2), not the two epoll_ctl and
 * the extra epoll_wait of a deferred write.  What the socket does not take
 * is queued; a large remainder is handed over, not copied (the output
 * buffer frees the block once it is written).  Returns whether the answer
 * went out whole, directly. */
static bool write_response(connection *c, queued_line *x)
{
    size_t length = x->response_length ? x->response_length : strlen(x->response);
    struct evbuffer *output = bufferevent_get_output(c->bev);
    size_t sent = 0;
    /* Not while more input waits (more requests, or part of one): the
     * answers go out together, in one writev, once the loop is done. */
    if (!c->refusing && evbuffer_get_length(output) == 0 && c->partial_length == 0 &&
        evbuffer_get_length(bufferevent_get_input(c->bev)) == 0) {
        ssize_t n = send(bufferevent_getfd(c->bev), x->response, length,
                         MSG_DONTWAIT | MSG_NOSIGNAL);
        if (n > 0)
            sent = (size_t)n; /* else EAGAIN or an error the buffered write meets again */
    }
    if (sent == length)
        return true;
    if (length - sent >= ZERO_COPY_BYTES &&
        evbuffer_add_reference(output, x->response + sent, length - sent, free_response,
                               x->response) == 0) {
        x->response = NULL;
        return false;
    }
    bufferevent_write(c->bev, x->response + sent, length - sent);
    return false;
}

/* Every answer written: what the write callback does once the output
 * drains (answers sent directly never pass through it). */
static void answers_out(connection *c)
{
    if (evbuffer_get_length(bufferevent_get_output(c->bev)) > 0)
        return; /* drained to the low-water mark, not out */
    if (c->refusing && !c->write_shut) {
        /* The error line is out: say so, then wait for the peer's EOF. */
        shutdown(bufferevent_getfd(c->bev), SHUT_WR);
        c->write_shut = true;
    } else if (!c->refusing && c->pending == 0 && c->server->config->idle_timeout > 0) {
        /* Every answer is out: the idle clock starts now, not at the last
         * request (the time it took to answer was not the client's). */
        struct timeval idle = {(time_t)c->server->config->idle_timeout, 0};
        set_timeouts(c, &idle);
    }
}

/* Write the answers at the head of the queue that are ready. */
static void flush(connection *c)
{
    bool wrote_directly = false;
    while (c->head && c->head->done) {
        if (c->bev && c->head->response)
            wrote_directly |= write_response(c, c->head);
        remove_head(c);
    }
    if (c->bev && wrote_directly && evbuffer_get_length(bufferevent_get_output(c->bev)) == 0)
        answers_out(c);
    if (c->bev && c->paused && c->pending < MAX_PENDING / 2 &&
        c->queued_bytes < c->server->config->max_line) {
        unpause(c);
        if (!c->input_closed)
            reading_on(c);
        process_input(c); /* lines already buffered */
    }
    maybe_finish(c);
}

/* May the connection's next piece of work be made?  Only while its unsent
 * output and what its request holds are under --max-output -- but always
 * when nothing is unsent, so that a request larger than the bound still
 * makes progress, a piece at a time. */
static bool output_room(connection *c)
{
    if (!c->bev)
        return false;
    size_t unsent = evbuffer_get_length(bufferevent_get_output(c->bev));
    size_t limit = c->server->config->max_output;
    return unsent == 0 || unsent + c->held < limit;
}

static queued_line *add_queued_line(connection *c)
{
    queued_line *x = calloc(1, sizeof *x);
    if (!x)
        return NULL;
    x->connection = c;
    if (c->tail)
        c->tail->next = x;
    else
        c->head = x;
    c->tail = x;
    c->pending++;
    return x;
}

/* An error answer known without a worker, in its place. */
static void queue_error(connection *c, int code, const char *reason)
{
    queued_line *x = add_queued_line(c);
    if (!x)
        return;
    x->response = wp_error_line(code, "", reason);
    x->done = true;
    flush(c);
}

/* A refused line: counted like any request that failed. */
static void answer_now(connection *c, int code, const char *reason)
{
    atomic_fetch_add(&c->server->stats.requests, 1);
    atomic_fetch_add(&c->server->stats.errors, 1);
    queue_error(c, code, reason);
}

/* Answer a light request (wp_answer_light) in the loop itself: a few
 * wrenches' answer takes microseconds, and handing it to a worker and back
 * costs two thread wake-ups, more than the work.  dispatch only calls it
 * when no earlier request of the connection is still running, and flush
 * writes answers in queue order, so order is kept.  The light check holds
 * the fixture it looked up, so no worker can evict its derived data before
 * it is used. */
static bool answer_light(connection *c, queued_line *x, wp_answer **parsed)
{
    wd_server *s = c->server;
    *parsed = NULL;
    if (!s->light || c->light_answered >= WP_LIGHT_BURST || x->length > WP_LIGHT_LINE)
        return false; /* a long line is parsed by the worker, not here */
    /* Parsed here, once: light or not, the worker gets it parsed (and its
     * fixture held, when the light check looked it up). */
    wp_answer *answer = wp_answer_begin(&s->limits, s->loop_host, x->line, x->length);
    if (!answer)
        return false;
    free(x->line);
    x->line = NULL;
    if (!wp_answer_light(answer, s->loop_host)) {
        *parsed = answer;
        return false;
    }
    wp_counts counts = {0, 0};
    x->response = wp_answer_whole(answer, s->loop_host, &counts);
    atomic_fetch_add(&s->stats.requests, counts.requests);
    atomic_fetch_add(&s->stats.errors, counts.errors);
    x->done = true;
    c->light_answered++;
    return true;
}

/* Hand the connection's next waiting request to the workers, unless one
 * of its requests is there already or its client is not reading what it
 * has been sent; light ones are answered on the way. */
static void dispatch(connection *c)
{
    queued_line *x;
    wp_answer *parsed = NULL;
    for (;;) {
        if (c->running || !output_room(c))
            return;
        x = c->head;
        while (x && (x->done || !x->line))
            x = x->next;
        if (!x)
            return;
        c->queued_bytes -= x->length;
        if (!answer_light(c, x, &parsed))
            break;
        flush(c); /* the rest still run while the client reads */
    }
    wd_task *task = calloc(1, sizeof *task);
    if (!task) {
        wp_answer_free(parsed, c->server->loop_host);
        free(x->line);
        x->line = NULL;
        x->response = wp_error_line(WP_INTERNAL, "", "out of memory");
        x->done = true;
        flush(c);
        return;
    }
    atomic_init(&task->cancelled, false);
    task->owner = x;
    task->uid = c->uid;
    task->answer = parsed;
    task->line = x->line; /* NULL when parsed already */
    task->length = x->length;
    x->line = NULL;
    x->task = task;
    c->running = x;
    c->held = x->length; /* until its first piece says what it holds */
    wd_log(WD_LOG_DEBUG, "client %lu: request of %zu bytes", c->number, task->length);
    wd_pool_submit(c->server->pool, task);
}

/* Reading stops while too many requests wait, in number or in bytes. */
static bool too_much_waiting(const connection *c)
{
    return c->pending >= MAX_PENDING || c->queued_bytes >= c->server->config->max_line;
}

static void submit(connection *c, char *line, size_t length)
{
    queued_line *x = add_queued_line(c);
    if (!x) {
        free(line);
        return;
    }
    x->line = line;
    x->length = length;
    c->queued_bytes += length;
    dispatch(c);
}

/* Forget the start of a long line. */
static void drop_partial(connection *c)
{
    free(c->partial);
    c->partial = NULL;
    c->partial_length = c->partial_capacity = 0;
}

/* Move `length` bytes of the input to the end of the long line's start,
 * with room for `spare` more; false when out of memory. */
static bool move_to_partial(connection *c, struct evbuffer *input, size_t length, size_t spare)
{
    size_t need = c->partial_length + length + spare;
    if (need > c->partial_capacity) {
        size_t capacity = c->partial_capacity ? c->partial_capacity : PARTIAL_BYTES * 4;
        while (capacity < need)
            capacity *= 2;
        char *grown = realloc(c->partial, capacity);
        if (!grown)
            return false;
        c->partial = grown;
        c->partial_capacity = capacity;
        wp_advise_huge(grown, capacity);
    }
    evbuffer_remove(input, c->partial + c->partial_length, length);
    c->partial_length += length;
    return true;
}

/* A request begun must arrive whole within --request-timeout of its first
 * byte: a client dripping a byte at a time holds no queued line for ever. */
static void watch_partial_request(connection *c, bool line_taken)
{
    if (!c->bev || !c->request_timer)
        return;
    bool partial = c->discarding ||
                   (!c->input_closed && (c->partial_length > 0 ||
                                         evbuffer_get_length(bufferevent_get_input(c->bev)) > 0));
    if (line_taken || !partial || c->paused)
        event_del(c->request_timer); /* a new request's clock, or none */
    if (partial && !c->paused && !evtimer_pending(c->request_timer, NULL)) {
        struct timeval limit = {(time_t)c->server->config->request_timeout, 0};
        evtimer_add(c->request_timer, &limit);
    }
}

static void on_request_timeout(evutil_socket_t fd, short events, void *argument)
{
    (void)fd;
    (void)events;
    connection *c = argument;
    if (!c->bev)
        return;
    c->busy++;
    wd_log(WD_LOG_INFO, "client %lu: a request not whole after %u s (--request-timeout): closed",
           c->number, c->server->config->request_timeout);
    char reason[128];
    snprintf(reason, sizeof reason, "the request did not arrive whole within %u s (--request-timeout)",
             c->server->config->request_timeout);
    struct evbuffer *input = bufferevent_get_input(c->bev);
    evbuffer_drain(input, evbuffer_get_length(input));
    drop_partial(c);
    c->discarding = false;
    c->input_closed = true;
    reading_off(c);
    answer_now(c, WP_INVALID_REQUEST, reason);
    c->busy--;
    maybe_finish(c);
}

/* Cut complete lines out of the input and submit them. */
static void process_input(connection *c)
{
    if (!c->bev)
        return;
    struct evbuffer *input = bufferevent_get_input(c->bev);
    if (c->refusing) { /* read and dropped: closing now would reset the line sent */
        evbuffer_drain(input, evbuffer_get_length(input));
        drop_partial(c);
        return;
    }
    size_t max_line = c->server->config->max_line;
    bool line_taken = false;
    while (!c->paused && c->bev) {
        /* The input holds no byte searched before: a long line's start is
         * moved out of it (c->partial) once it is long. */
        struct evbuffer_ptr eol = evbuffer_search(input, "\n", 1, NULL);
        if (c->discarding) {
            if (eol.pos < 0) {
                evbuffer_drain(input, evbuffer_get_length(input));
                break;
            }
            evbuffer_drain(input, (size_t)eol.pos + 1);
            c->discarding = false;
            line_taken = true;
            continue;
        }
        size_t available = evbuffer_get_length(input);
        size_t tail = eol.pos < 0 ? available : (size_t)eol.pos; /* of the input */
        size_t length = c->partial_length + tail;
        if (length > max_line) {
            char reason[128];
            snprintf(reason, sizeof reason, "the line is longer than %zu bytes (--max-line)",
                     max_line);
            drop_partial(c);
            answer_now(c, WP_INVALID_REQUEST, reason);
            c->discarding = true;
            continue;
        }
        if (eol.pos < 0) {
            if (!c->input_closed || length == 0) {
                if (available >= PARTIAL_BYTES && !move_to_partial(c, input, available, 0)) {
                    drop_partial(c);
                    answer_now(c, WP_INTERNAL, "out of memory");
                    c->discarding = true;
                    continue;
                }
                break;
            }
            /* The last line, without its "\n": answer it all the same. */
        }
        char *line;
        if (c->partial_length > 0) {
            if (!move_to_partial(c, input, tail, 1)) {
                drop_partial(c);
                answer_now(c, WP_INTERNAL, "out of memory");
                c->discarding = true;
                continue;
            }
            line = c->partial; /* the line's, now */
            c->partial = NULL;
            c->partial_length = c->partial_capacity = 0;
        } else {
            line = malloc(length + 1);
            if (!line) {
                answer_now(c, WP_INTERNAL, "out of memory");
                evbuffer_drain(input, length + (eol.pos >= 0));
                continue;
            }
            evbuffer_remove(input, line, length);
        }
        if (eol.pos >= 0)
            evbuffer_drain(input, 1);
        line[length] = 0;
        line_taken = true;
        submit(c, line, length);
        if (c->bev && too_much_waiting(c) && !c->input_closed)
            pause_reading(c);
    }
    watch_partial_request(c, line_taken);
}

/* Callbacks hold the connection busy so that nothing they call frees it;
 * the last thing each does is to see whether it is finished. */
static void on_read(struct bufferevent *bev, void *argument)
{
    (void)bev;
    connection *c = argument;
    c->busy++;
    c->light_answered = 0;
    process_input(c);
    c->busy--;
    maybe_finish(c);
}

/* The output drained to its low-water mark (half of --max-output), or out. */
static void on_write(struct bufferevent *bev, void *argument)
{
    connection *c = argument;
    (void)bev;
    c->busy++;
    if (c->parked && output_room(c)) {
        c->parked = false;
        wd_pool_submit(c->server->pool, c->running->task);
    } else if (!c->running) {
        dispatch(c); /* requests held back while the client was not reading */
    }
    if (c->bev)
        answers_out(c);
    c->busy--;
    maybe_finish(c);
}

/* Has the peer closed its socket entirely (not only its sending side)?
 * Then nobody reads what would be answered. */
static bool peer_gone(connection *c)
{
    struct pollfd p = {.fd = bufferevent_getfd(c->bev), .events = POLLOUT};
    return poll(&p, 1, 0) == 1 && (p.revents & (POLLHUP | POLLERR));
}

/* The peer shut its sending side (or hung up) while reading was paused. */
static void on_hangup(evutil_socket_t fd, short what, void *argument)
{
    (void)fd;
    (void)what;
    connection *c = argument;
    if (!c->bev)
        return;
    c->busy++;
    if (peer_gone(c)) {
        wd_log(WD_LOG_DEBUG, "client %lu: hung up while its reading was paused; its requests "
                             "are cancelled", c->number);
        c->input_closed = true;
        close_socket(c);
    } /* else only its sending side: it may still read; pieces ask again */
    c->busy--;
    maybe_finish(c);
}

static void on_event(struct bufferevent *bev, short events, void *argument)
{
    (void)bev;
    connection *c = argument;
    c->busy++;
    if ((events & BEV_EVENT_EOF) && !c->refusing && peer_gone(c)) {
        /* Hung up entirely: what it asked is dropped, not computed. */
        wd_log(WD_LOG_DEBUG, "client %lu: hung up; its requests are cancelled", c->number);
        c->input_closed = true;
        close_socket(c);
    } else if (events & BEV_EVENT_EOF) {
        /* The client is done sending; it may still read. */
        c->input_closed = true;
        process_input(c);
    } else if ((events & BEV_EVENT_TIMEOUT) && (events & BEV_EVENT_WRITING) && !c->refusing) {
        wd_log(WD_LOG_WARN, "client %lu: %zu bytes of answers unread for --idle-timeout: closed",
               c->number, evbuffer_get_length(bufferevent_get_output(c->bev)));
        c->input_closed = true;
        close_socket(c);
    } else if ((events & BEV_EVENT_TIMEOUT) && !c->refusing &&
               (c->pending > 0 || evbuffer_get_length(bufferevent_get_output(c->bev)) > 0)) {
        /* Not idle: a request is in flight or an answer is still going out
         * (reading goes on: its event persists). */
    } else if (events & (BEV_EVENT_ERROR | BEV_EVENT_TIMEOUT)) {
        if (events & BEV_EVENT_TIMEOUT)
            wd_log(c->refusing ? WD_LOG_DEBUG : WD_LOG_INFO, "client %lu: %s", c->number,
                   c->refusing ? "gone silent after being turned away"
                               : "idle for --idle-timeout: closed");
        else
            wd_log(WD_LOG_DEBUG, "client %lu: %s", c->number, strerror(errno));
        c->input_closed = true;
        close_socket(c);
    }
    c->busy--;
    maybe_finish(c);
}

/* The socket is readable, or has been silent for the read timeout. */
static void on_readable(evutil_socket_t fd, short what, void *argument)
{
    (void)fd;
    connection *c = argument;
    if (what & EV_TIMEOUT) {
        on_event(c->bev, BEV_EVENT_TIMEOUT | BEV_EVENT_READING, c);
        return;
    }
    /* A long line in the making takes what the socket holds at once; a
     * read into an empty input takes a request's worth first (a small
     * block from malloc's free lists, where 64 KiB would cost a trip to
     * the top of the heap and back for every request); more takes more. */
    struct evbuffer *input = bufferevent_get_input(c->bev);
    size_t most = c->partial_length > 0                 ? READ_BYTES
                  : evbuffer_get_length(input) == 0 ? FIRST_READ_BYTES
                                                    : SHORT_READ_BYTES;
    int result = read_input(c, most);
    if (result == 0) {
        on_read(c->bev, c);
    } else if (result > 0) {
        reading_off(c);
        on_event(c->bev, (short)(result | BEV_EVENT_READING), c);
    }
}

/* A refused client gets this long to read its error line and hang up,
 * counted from the refusal: what it sends meanwhile is read and dropped
 * and does not extend it, so a refused peer holds a descriptor at most
 * this long. */
#define LINGER_SECONDS 2
/* At most this many refused connections linger at once; beyond, the error
 * line is sent as the socket takes it and the connection closed at once
 * (a flood of refused peers then costs an accept and a close each, never
 * the daemon's descriptors). */
#define MAX_LINGERING 64
/* After accept(2) runs out of descriptors (or memory), accepting pauses for
 * this long: the waiting connections stay in the listen backlog until
 * descriptors are free, instead of the loop retrying accept at once. */
#define ACCEPT_PAUSE_MS 100
/* Floods (peers denied or refused, accept failing) log a line per this
 * many seconds. */
#define FLOOD_LOG_SECONDS 10

static void on_linger_over(evutil_socket_t fd, short events, void *argument)
{
    (void)fd;
    (void)events;
    connection *c = argument;
    c->busy++;
    wd_log(WD_LOG_DEBUG, "client %lu: turned away, its linger over: closed", c->number);
    c->input_closed = true;
    close_socket(c);
    c->busy--;
    maybe_finish(c);
}

/* Turn a peer away without a connection of ours: the error line as the
 * socket takes it, then close. */
static void refuse_at_once(evutil_socket_t fd, int code, const char *reason)
{
    char *line = wp_error_line(code, "", reason);
    if (line) {
        ssize_t sent = send(fd, line, strlen(line), MSG_DONTWAIT | MSG_NOSIGNAL);
        (void)sent;
        free(line);
    }
    shutdown(fd, SHUT_WR);
    close(fd);
}

static void on_accept_again(evutil_socket_t fd, short events, void *argument)
{
    (void)fd;
    (void)events;
    wd_server *s = argument;
    if (s->listener)
        evconnlistener_enable(s->listener);
}

/* accept(2) failed (libevent retries EINTR and EAGAIN itself).  Out of
 * descriptors or memory, retrying at once would spin the loop and the log:
 * pause accepting a moment, log once per FLOOD_LOG_SECONDS. */
static void on_accept_error(struct evconnlistener *listener, void *argument)
{
    wd_server *s = argument;
    int error = EVUTIL_SOCKET_ERROR();
    wd_log_limited(&s->accept_log, FLOOD_LOG_SECONDS, WD_LOG_WARN,
                   "cannot accept a client: %s; accepting paused for %d ms", strerror(error),
                   ACCEPT_PAUSE_MS);
    evconnlistener_disable(listener);
    struct timeval pause = {0, ACCEPT_PAUSE_MS * 1000};
    event_add(s->accept_timer, &pause);
}

/* Connections of user `uid` now (those being turned away aside). */
static unsigned long clients_of(const wd_server *s, unsigned uid)
{
    unsigned long count = 0;
    for (const connection *c = s->connections; c; c = c->next)
        count += c->bev && !c->refusing && c->uid == uid;
    return count;
}

static void on_accept(struct evconnlistener *listener, evutil_socket_t fd, struct sockaddr *address,
                      int length, void *argument)
{
    (void)listener;
    (void)address;
    (void)length;
    wd_server *s = argument;
    char who[64], reason[128];
    int refusal = 0;
    unsigned uid = 0;
    bool have_uid = wd_peer_uid(fd, &uid);
    if (!wd_peer_allowed(s->config, fd, who, sizeof who)) {
        refusal = WP_ACCESS;
        snprintf(reason, sizeof reason, "%s may not use this daemon (allow-uid, allow-gid)", who);
        atomic_fetch_add(&s->stats.denied, 1);
        wd_log_limited(&s->denied_log, FLOOD_LOG_SECONDS, WD_LOG_WARN,
                       "denied %s: not in the allow lists", who);
    } else if (s->config->max_clients_per_uid > 0 && have_uid &&
               clients_of(s, uid) >= s->config->max_clients_per_uid) {
        refusal = WP_LIMIT;
        snprintf(reason, sizeof reason,
                 "too many clients of uid %u (--max-clients-per-uid %lu); try again later", uid,
                 s->config->max_clients_per_uid);
        atomic_fetch_add(&s->stats.refused, 1);
        wd_log_limited(&s->refused_log, FLOOD_LOG_SECONDS, WD_LOG_WARN,
                       "refused a client of uid %u: %lu of its clients already connected "
                       "(--max-clients-per-uid)", uid, s->config->max_clients_per_uid);
    } else if (atomic_load(&s->stats.clients) - s->refusing >= s->config->max_clients) {
        refusal = WP_LIMIT;
        snprintf(reason, sizeof reason, "too many clients (--max-clients); try again later");
        atomic_fetch_add(&s->stats.refused, 1);
        wd_log_limited(&s->refused_log, FLOOD_LOG_SECONDS, WD_LOG_WARN,
                       "refused a client: %lu already connected (--max-clients)",
                       (unsigned long)(atomic_load(&s->stats.clients) - s->refusing));
    }
    if (refusal && s->refusing >= MAX_LINGERING) {
        refuse_at_once(fd, refusal, reason);
        return;
    }
    connection *c = calloc(1, sizeof *c);
    struct bufferevent *bev = c ? bufferevent_socket_new(s->base, fd, BEV_OPT_CLOSE_ON_FREE) : NULL;
    if (!bev) {
        free(c);
        close(fd);
        wd_log(WD_LOG_ERROR, "out of memory accepting a client");
        return;
    }
    c->server = s;
    c->bev = bev;
    c->uid = uid;
    c->number = ++s->numbers;
    c->next = s->connections;
    if (s->connections)
        s->connections->prev = c;
    s->connections = c;
    s->connection_count++;
    atomic_fetch_add(&s->stats.clients, 1);
    bufferevent_setcb(bev, NULL, on_write, on_event, c);
    bufferevent_enable(bev, EV_WRITE);
    /* A socket bufferevent freezes its input's end for its own reads:
     * ours are the only ones now. */
    evbuffer_unfreeze(bufferevent_get_input(bev), 0);
    c->read_event = event_new(s->base, fd, EV_READ | EV_PERSIST, on_readable, c);
    if (!c->read_event) {
        wd_log(WD_LOG_ERROR, "out of memory accepting a client");
        c->input_closed = true;
        close_socket(c);
        maybe_finish(c);
        return;
    }
    if (refusal) {
        c->refusing = true;
        s->refusing++;
        /* The write's timeout is the linger too; reading has none (input
         * would restart it): the timer ends the linger. */
        struct timeval linger = {LINGER_SECONDS, 0};
        bufferevent_set_timeouts(c->bev, NULL, &linger);
        reading_on(c);
        c->request_timer = evtimer_new(s->base, on_linger_over, c);
        if (c->request_timer)
            evtimer_add(c->request_timer, &linger);
        c->busy++;
        queue_error(c, refusal, reason);
        c->busy--;
        maybe_finish(c);
        return;
    }
    reading_on(c);
    c->request_timer = s->config->request_timeout > 0 ? evtimer_new(s->base, on_request_timeout, c)
                                                      : NULL;
    /* on_write comes when the output is down to half the bound: the next
     * piece is then made while the rest is still being sent. */
    bufferevent_setwatermark(bev, EV_WRITE, s->config->max_output / 2, 0);
    if (s->config->idle_timeout > 0) {
        /* Silence for so long closes it; so does output left unread. */
        struct timeval idle = {(time_t)s->config->idle_timeout, 0};
        set_timeouts(c, &idle);
    }
    wd_log(WD_LOG_DEBUG, "client %lu: connected", c->number);
}

/* ---- answers from the workers -------------------------------------------- */

static void task_done(void *argument, wd_task *task)
{
    wd_server *s = argument;
    pthread_mutex_lock(&s->done_lock);
    task->next = NULL;
    if (s->done_tail)
        s->done_tail->next = task;
    else
        s->done_head = task;
    s->done_tail = task;
    pthread_mutex_unlock(&s->done_lock);
    event_active(s->done_event, EV_READ, 0);
}

/* Send a piece the workers made (taking it): the running queued line is at
 * the head of the queue, every answer before it written, so the piece goes
 * straight out in order. */
static void send_piece(connection *c, wd_task *task)
{
    if (!task->piece)
        return;
    queued_line piece = {.response = task->piece, .response_length = task->piece_length};
    task->piece = NULL;
    write_response(c, &piece);
    free(piece.response); /* NULL when the output buffer took it by reference */
}

/* A piece is back from the workers. */
static void piece_done(wd_server *s, wd_task *task)
{
    queued_line *x = task->owner;
    connection *c = x->connection;
    assert(c->running == x && x->task == task && !c->parked);
    assert(c->head == x); /* every earlier answer written */
    c->busy++;
    if (c->bev && (c->input_closed || c->paused) && task->step == WP_STEP_MORE &&
        peer_gone(c)) {
        /* It closed its sending side first, then hung up entirely, or hung
         * up while its reading was paused: no event may say so (the input
         * ended long ago; EV_CLOSED fires once, at the first half), so
         * each piece asks. */
        wd_log(WD_LOG_DEBUG, "client %lu: hung up after closing its input; its requests are "
                             "cancelled", c->number);
        close_socket(c);
    }
    if (c->bev && !atomic_load(&task->cancelled))
        send_piece(c, task);
    if (task->step == WP_STEP_FAILED && c->bev) {
        wd_log(WD_LOG_ERROR, "client %lu: an answer could not be completed after %s; closed",
               c->number, "part of it was sent");
        c->input_closed = true;
        close_socket(c);
    }
    if (task->step == WP_STEP_MORE && c->bev && !atomic_load(&task->cancelled)) {
        c->held = task->held;
        if (output_room(c))
            wd_pool_submit(s->pool, task); /* at the tail: everyone gets a turn */
        else
            c->parked = true; /* on_write submits it once the client reads */
    } else {
        wd_task_free(task, s->loop_host);
        x->task = NULL;
        x->done = true;
        c->running = NULL;
        c->held = 0;
        flush(c); /* the answered head leaves the queue, then the next runs */
        if (c->bev && evbuffer_get_length(bufferevent_get_output(c->bev)) == 0)
            answers_out(c); /* sent whole, directly: the write callback will not say so */
        if (c->bev)
            dispatch(c);
    }
    c->busy--;
    maybe_finish(c);
}

static void on_done(evutil_socket_t fd, short events, void *argument)
{
    (void)fd;
    (void)events;
    wd_server *s = argument;
    pthread_mutex_lock(&s->done_lock);
    wd_task *task = s->done_head;
    s->done_head = s->done_tail = NULL;
    pthread_mutex_unlock(&s->done_lock);
    while (task) {
        wd_task *next = task->next;
        piece_done(s, task);
        task = next;
    }
}

/* ---- start and stop ---------------------------------------------------------- */

static void on_grace_over(evutil_socket_t fd, short events, void *argument)
{
    (void)fd;
    (void)events;
    wd_server *s = argument;
    wd_log(WD_LOG_WARN, "answers still in flight after %d s; exiting anyway",
           SHUTDOWN_GRACE_SECONDS);
    event_base_loopexit(s->base, NULL);
}

static void on_signal(evutil_socket_t signal_number, short events, void *argument)
{
    (void)events;
    wd_server *s = argument;
    if (s->stopping)
        return;
    s->stopping = true;
    wd_systemd_notify("STOPPING=1\nSTATUS=stopping: answering what is in flight");
    wd_log(WD_LOG_INFO, "%s: no new clients; answering what is in flight",
           signal_number == SIGINT ? "SIGINT" : "SIGTERM");
    if (s->listener) {
        evconnlistener_free(s->listener);
        s->listener = NULL;
        wd_listen_remove(s->config->socket_path, &s->socket_file); /* none: systemd's */
    }
    struct timeval grace = {SHUTDOWN_GRACE_SECONDS, 0};
    event_add(s->grace_timer, &grace);
    for (connection *c = s->connections, *next; c; c = next) {
        next = c->next;
        c->busy++;
        /* Complete lines that have arrived are in flight, even those still
         * in the kernel's buffer: read exactly what is there now. */
        int queued = 0;
        if (c->bev && ioctl(bufferevent_getfd(c->bev), FIONREAD, &queued) == 0)
            while (queued > 0 && read_input(c, (size_t)queued) == 0)
                queued = ioctl(bufferevent_getfd(c->bev), FIONREAD, &queued) == 0 ? queued : 0;
        process_input(c);
        c->input_closed = true;
        reading_off(c);
        c->busy--;
        maybe_finish(c);
    }
    if (!s->connections)
        event_base_loopexit(s->base, NULL);
}

int wd_server_run(const wd_config *config)
{
    wd_server server;
    memset(&server, 0, sizeof server);
    wd_server *s = &server;
    s->config = config;
    s->limits = (wp_limits){config->max_depth, config->max_wrenches, config->max_batch,
                            config->max_candidates, config->max_cases};
    s->stats.started = time(NULL);
    s->stats.threads = config->threads;
    pthread_mutex_init(&s->done_lock, NULL);
    signal(SIGPIPE, SIG_IGN);
    evthread_use_pthreads();

    int status = WD_EXIT_START;
    char why[512];
    int fd = -1;
    s->cache = wd_cache_new(config->state_dir, config->cache_bytes, config->max_fixtures, why,
                            sizeof why);
    if (!s->cache) {
        wd_log(WD_LOG_ERROR, "%s", why);
        goto out;
    }
    for (int i = 0; i < config->load_count; i++)
        if (!wd_cache_load_file(s->cache, config->load_files[i], config->max_line))
            goto out; /* logged */
    /* Signals are caught and workers run before the socket listens: a
     * client (or a supervisor's SIGTERM) may come the moment it does. */
    s->base = event_base_new();
    if (!s->base)
        goto out;
    s->done_event = event_new(s->base, -1, 0, on_done, s);
    s->signal_events[0] = evsignal_new(s->base, SIGTERM, on_signal, s);
    s->signal_events[1] = evsignal_new(s->base, SIGINT, on_signal, s);
    s->grace_timer = evtimer_new(s->base, on_grace_over, s);
    s->accept_timer = evtimer_new(s->base, on_accept_again, s);
    s->pool = wd_pool_new(config->threads, s->cache, &s->limits, &s->stats, task_done, s);
    s->light = wd_thread_host_new(s->cache, &s->stats);
    s->loop_host = s->light ? wd_thread_host_wp(s->light) : NULL;
    if (!s->done_event || !s->signal_events[0] || !s->signal_events[1] || !s->grace_timer ||
        !s->accept_timer ||
        !s->pool || !s->light) {
        wd_log(WD_LOG_ERROR, "cannot start: out of memory or threads");
        goto out;
    }
    event_add(s->signal_events[0], NULL);
    event_add(s->signal_events[1], NULL);
    /* Who may connect is said before the socket exists: a client that
     * finds the socket finds the line already written. */
    {
        char admitted[WD_MAX_ALLOWED * 24 + 64];
        wd_peer_describe(config, admitted, sizeof admitted);
        wd_log(WD_LOG_INFO, "admitted: %s", admitted);
    }
    fd = config->listen_fd >= 0 ? config->listen_fd : wd_listen_open(config->socket_path, &s->socket_file, why, sizeof why);
    if (fd < 0) {
        wd_log(WD_LOG_ERROR, "%s", why);
        goto out;
    }
    s->listener = evconnlistener_new(s->base, on_accept, s, LEV_OPT_CLOSE_ON_FREE, -1, fd);
    if (!s->listener) {
        close(fd);
        wd_listen_remove(config->socket_path, &s->socket_file);
        wd_log(WD_LOG_ERROR, "cannot listen on %s: out of memory", config->socket_path);
        goto out;
    }
    evconnlistener_set_error_cb(s->listener, on_accept_error);
    wd_log(WD_LOG_INFO, "wrenchd %s listening on %s (%d threads, state %s, cache %zu MiB)",
           WR_VERSION, config->listen_fd >= 0 ? "the socket systemd passed" : config->socket_path,
           config->threads, config->state_dir ? config->state_dir : "in memory only",
           config->cache_bytes >> 20);
    {
        wd_cache_stats held;
        wd_cache_stats_get(s->cache, &held);
        char state[256];
        snprintf(state, sizeof state, "READY=1\nSTATUS=serving %zu stored fixtures, %d threads",
                 held.stored, config->threads);
        wd_systemd_notify(state);
    }
    event_base_dispatch(s->base);
    status = WD_EXIT_OK;
    wd_log(WD_LOG_INFO, "stopped");

out:
    wd_pool_free(s->pool); /* every task handed back; their pieces are dropped */
    for (wd_task *task = s->done_head, *next; task; task = next) {
        next = task->next;
        queued_line *x = task->owner;
        x->task = NULL;
        wd_task_free(task, s->loop_host);
    }
    while (s->connections) {
        s->connections->parked = true; /* its queued lines' tasks are the loop's now */
        close_socket(s->connections);
        free_connection(s->connections);
    }
    wd_thread_host_free(s->light);
    if (s->listener) {
        evconnlistener_free(s->listener);
        wd_listen_remove(config->socket_path, &s->socket_file);
    }
    for (int i = 0; i < 2; i++)
        if (s->signal_events[i])
            event_free(s->signal_events[i]);
    if (s->done_event)
        event_free(s->done_event);
    if (s->grace_timer)
        event_free(s->grace_timer);
    if (s->accept_timer)
        event_free(s->accept_timer);
    if (s->base)
        event_base_free(s->base);
    wd_cache_free(s->cache);
    pthread_mutex_destroy(&s->done_lock);
    libevent_global_shutdown();
    return status;
}
