/* load_client.c -- one client of the load generator: see load_client.h. */
#include "load_client.h"

#include "bench_util.h"
#include "load_util.h"

#include <errno.h>
#include <poll.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <sys/un.h>
#include <time.h>
#include <unistd.h>

/* ---- connections ----------------------------------------------------------------- */

typedef struct connection {
    int fd;
    int timeout_ms; /* for each wait to write or read */
    char *buffer;
    size_t length, capacity, consumed, scanned;
} connection;

static int connection_open(connection *c, const client_settings *settings)
{
    memset(c, 0, sizeof *c);
    struct sockaddr_un address = {.sun_family = AF_UNIX};
    if (strlen(settings->socket_path) >= sizeof address.sun_path)
        return -1;
    strcpy(address.sun_path, settings->socket_path);
    c->fd = socket(AF_UNIX, SOCK_STREAM, 0);
    if (c->fd < 0)
        return -1;
    for (int attempt = 0;; attempt++) {
        if (connect(c->fd, (struct sockaddr *)&address, sizeof address) == 0)
            break;
        /* The listen backlog may be full for a moment when many connect at once. */
        if ((errno != EAGAIN && errno != ECONNREFUSED) || attempt >= 50) {
            close(c->fd);
            c->fd = -1;
            return -1;
        }
        struct timespec pause = {0, 20 * 1000 * 1000};
        nanosleep(&pause, NULL);
    }
    c->timeout_ms = settings->timeout_seconds * 1000;
    c->capacity = 1 << 16;
    c->buffer = xmalloc(c->capacity);
    return 0;
}

static void connection_close(connection *c)
{
    if (c->fd >= 0)
        close(c->fd);
    c->fd = -1;
    free(c->buffer);
    c->buffer = NULL;
}

static bool connection_write(connection *c, const char *text, size_t length)
{
    size_t done = 0;
    while (done < length) {
        struct pollfd p = {c->fd, POLLOUT, 0};
        int ready = poll(&p, 1, c->timeout_ms);
        if (ready <= 0)
            return false;
        ssize_t n = send(c->fd, text + done, length - done, MSG_NOSIGNAL);
        if (n < 0 && errno == EINTR)
            continue;
        if (n <= 0)
            return false;
        done += (size_t)n;
    }
    return true;
}

/* The next line (without "\n", NUL-terminated in place), or NULL at end of
 * input, on an error or after the timeout (*why says which). */
static char *connection_read_line(connection *c, size_t *length, const char **why)
{
    if (c->consumed > 0) {
        memmove(c->buffer, c->buffer + c->consumed, c->length - c->consumed);
        c->length -= c->consumed;
        c->scanned = c->scanned > c->consumed ? c->scanned - c->consumed : 0;
        c->consumed = 0;
    }
    for (;;) {
        char *eol = memchr(c->buffer + c->scanned, '\n', c->length - c->scanned);
        if (eol) {
            *eol = 0;
            *length = (size_t)(eol - c->buffer);
            c->consumed = *length + 1;
            c->scanned = 0;
            return c->buffer;
        }
        c->scanned = c->length;
        if (c->capacity - c->length < 4096) {
            c->capacity *= 2;
            c->buffer = xrealloc(c->buffer, c->capacity);
        }
        struct pollfd p = {c->fd, POLLIN, 0};
        int ready = poll(&p, 1, c->timeout_ms);
        if (ready < 0 && errno == EINTR)
            continue;
        if (ready <= 0) {
            *why = "timed out";
            return NULL;
        }
        ssize_t n = recv(c->fd, c->buffer + c->length, c->capacity - c->length - 1, 0);
        if (n < 0 && errno == EINTR)
            continue;
        if (n <= 0) {
            *why = n == 0 ? (c->length ? "end of input inside a line" : "end of input")
                          : strerror(errno);
            return NULL;
        }
        c->length += (size_t)n;
    }
}

/* ---- lines in flight -------------------------------------------------------------- */

#define MAX_BATCH 8

typedef struct sent_id {
    bool numeric;
    double number;
    char text[32];
} sent_id;

/* A line written and not yet answered. */
typedef struct pending {
    double sent;                     /* bench_seconds() when written */
    bool batch;
    int count;                       /* answered members */
    const request *requests[MAX_BATCH];
    sent_id ids[MAX_BATCH];
    char *line;                      /* the line sent, kept for reports */
} pending;

/* What client_run keeps while it runs: the client's own state. */
typedef struct session {
    client *client;
    connection connection;
    pending *ring; /* settings->pipeline lines, the oldest at head */
    int head, in_flight;
    unsigned long next_id;
    size_t script_next;
} session;

static pthread_mutex_t report_lock = PTHREAD_MUTEX_INITIALIZER;
static int reports_printed;
#define MAX_REPORTS 12 /* the first few tell what broke; thousands would bury it */

static void report(const client *cl, const char *what, const char *sent, const char *expected,
                   const char *seen)
{
    pthread_mutex_lock(&report_lock);
    if (reports_printed++ < MAX_REPORTS) {
        fprintf(stderr, "load: client %d: %s\n", cl->index, what);
        if (sent)
            fprintf(stderr, "  request:  %.600s%s\n", sent, strlen(sent) > 600 ? "..." : "");
        if (expected)
            fprintf(stderr, "  expected: %.600s%s\n", expected,
                    strlen(expected) > 600 ? "..." : "");
        if (seen)
            fprintf(stderr, "  observed: %.600s%s\n", seen, strlen(seen) > 600 ? "..." : "");
    }
    pthread_mutex_unlock(&report_lock);
}

static void add_latency(client_stats *stats, double us)
{
    if (stats->latency_count == stats->latency_capacity) {
        stats->latency_capacity = stats->latency_capacity ? 2 * stats->latency_capacity : 4096;
        stats->latency = xrealloc(stats->latency, stats->latency_capacity * sizeof *stats->latency);
    }
    stats->latency[stats->latency_count++] = us;
}

/* Ids are strings and numbers, unique per request: both forms must come
 * back as they went. */
static sent_id make_id(session *s)
{
    sent_id id = {0};
    unsigned long n = s->next_id++;
    if (n % 4 == 3) {
        id.numeric = true;
        id.number = (double)s->client->index * 1e9 + (double)n;
        snprintf(id.text, sizeof id.text, "%.0f", id.number);
    } else {
        snprintf(id.text, sizeof id.text, "\"c%d-%lu\"", s->client->index, n);
    }
    return id;
}

static bool id_matches(const cJSON *answer, const sent_id *id, bool expect_null)
{
    const cJSON *got = cJSON_GetObjectItemCaseSensitive(answer, "id");
    if (expect_null)
        return cJSON_IsNull(got);
    if (id->numeric)
        return cJSON_IsNumber(got) && got->valuedouble == id->number;
    if (!cJSON_IsString(got))
        return false;
    size_t n = strlen(id->text) - 2; /* without the quotes */
    return strlen(got->valuestring) == n && memcmp(got->valuestring, id->text + 1, n) == 0;
}

/* ---- writing --------------------------------------------------------------------- */

/* Which request a line carries, and whether it goes as a notification. */
typedef struct choice {
    const request *request;
    bool notify;
} choice;

/* Build the next line; fill `p` with what answers it expects.  Returns false
 * when it expects no answer at all. */
static bool next_line(session *s, char **line, size_t *length, pending *p)
{
    client *cl = s->client;
    const table *t = cl->settings->table;
    size_t capacity = 0;
    *line = NULL;
    *length = 0;
    memset(p, 0, sizeof *p);
    choice items[MAX_BATCH];
    int count = 0;
    bool batch = false;
    if (cl->script) {
        items[count++] = (choice){cl->script[s->script_next++], false};
    } else {
        int roll = random_pick(&cl->random, 100);
        if (roll < 8) { /* a JSON-RPC batch */
            batch = true;
            count = 1 + random_pick(&cl->random, MAX_BATCH);
            for (int i = 0; i < count; i++) {
                const request *r;
                int kind = random_pick(&cl->random, 20);
                if (kind == 0 && cl->private_fixture)
                    r = private_fixture_next(cl->private_fixture, &cl->random);
                else if (kind == 1)
                    r = table_pick_raw_batchable(t, &cl->random);
                else
                    do
                        r = table_pick(t, &cl->random);
                    while (!(r->flags & REQUEST_BATCHABLE));
                items[i] = (choice){r, (r->flags & REQUEST_NOTIFIABLE) &&
                                           random_pick(&cl->random, 8) == 0};
            }
        } else if (roll < 10 && cl->private_fixture) {
            items[count++] =
                (choice){private_fixture_next(cl->private_fixture, &cl->random), false};
        } else {
            const request *r = table_pick(t, &cl->random);
            items[count++] =
                (choice){r, (r->flags & REQUEST_NOTIFIABLE) && random_pick(&cl->random, 25) == 0};
        }
    }
    if (batch)
        append(line, length, &capacity, "[");
    for (int i = 0; i < count; i++) {
        const request *r = items[i].request;
        if (i)
            append(line, length, &capacity, ",");
        append(line, length, &capacity, r->wire);
        cl->stats.requests += r->counted_requests;
        cl->stats.server_requests += r->counted_requests;
        cl->stats.server_errors += r->counted_errors;
        cl->stats.by_category[r->category >= 0 ? r->category : CATEGORY_COUNT]++;
        if (r->flags & REQUEST_RAW) {
            if (r->expected) {
                p->requests[p->count] = r;
                p->ids[p->count].text[0] = 0;
                p->count++;
            }
            continue;
        }
        if (items[i].notify) {
            cl->stats.notifications++;
            append(line, length, &capacity, "}");
            continue;
        }
        sent_id id = make_id(s);
        append(line, length, &capacity, ",\"id\":");
        append(line, length, &capacity, id.text);
        append(line, length, &capacity, "}");
        p->requests[p->count] = r;
        p->ids[p->count] = id;
        p->count++;
    }
    if (batch) {
        append(line, length, &capacity, "]");
        cl->stats.batches++;
        /* A batch of notifications only: one request line, no answer. */
    }
    append(line, length, &capacity, "\n");
    p->batch = batch;
    return p->count > 0;
}

/* ---- reading and checking ---------------------------------------------------------- */

/* Compare one answer object with what a request expects. */
static bool check_request(client *cl, const pending *p, int i, cJSON *answer, const char *line)
{
    const request *r = p->requests[i];
    bool raw = (r->flags & REQUEST_RAW) != 0;
    cl->stats.answers_expected_errors += (unsigned long)r->answer_errors;
    cl->stats.answers_seen_errors += (unsigned long)answer_error_count(answer);
    if (!raw || p->batch) {
        /* Inside a batch a raw member is answered with id null. */
        if (!id_matches(answer, &p->ids[i], raw)) {
            char *seen = cJSON_PrintUnformatted(cJSON_GetObjectItemCaseSensitive(answer, "id"));
            char what[128];
            snprintf(what, sizeof what, "answer id %s, expected %s", seen ? seen : "(none)",
                     raw ? "null" : p->ids[i].text);
            report(cl, what, p->line, NULL, line);
            free(seen);
            return false;
        }
    }
    char *seen = table_comparable(cl->settings->table, answer, r);
    bool ok = strcmp(seen, r->expected) == 0;
    if (!ok)
        report(cl, "wrong answer", p->line, r->expected, seen);
    free(seen);
    return ok;
}

static bool check_line(client *cl, const pending *p, cJSON *answer, const char *line)
{
    bool ok = answer != NULL;
    if (!ok) {
        report(cl, "an answer that is not JSON", p->line, NULL, line);
    } else if (p->batch) {
        ok = cJSON_IsArray(answer) && cJSON_GetArraySize(answer) == p->count;
        if (!ok)
            report(cl, "a batch answer of the wrong shape", p->line, NULL, line);
        int i = 0;
        for (cJSON *a = answer->child; ok && a; a = a->next, i++)
            ok = check_request(cl, p, i, a, line);
    } else {
        ok = check_request(cl, p, 0, answer, line);
    }
    return ok;
}

/* Which line in flight an answer is for, by the first id it carries. */
static int find_pending(const session *s, const cJSON *answer)
{
    const cJSON *first = cJSON_IsArray(answer) ? answer->child : answer;
    int found = -1;
    for (int k = 0; first && k < s->in_flight && found < 0; k++) {
        const pending *p = &s->ring[(s->head + k) % s->client->settings->pipeline];
        bool raw = (p->requests[0]->flags & REQUEST_RAW) != 0;
        if (raw && !p->batch)
            continue; /* a raw line's answer is known only by its place */
        if (id_matches(first, &p->ids[0], raw))
            found = k;
    }
    return found;
}

static void pop_pending(session *s)
{
    pending *p = &s->ring[s->head];
    free(p->line);
    p->line = NULL;
    s->head = (s->head + 1) % s->client->settings->pipeline;
    s->in_flight--;
}

static void take_answer(session *s, char *line, size_t length)
{
    client *cl = s->client;
    double arrived = bench_seconds();
    if (s->in_flight == 0) {
        cl->stats.unexpected++;
        report(cl, "an answer to no request (a notification answered?)", NULL, NULL, line);
        return;
    }
    cJSON *answer = cJSON_ParseWithLength(line, length);
    pending *p = &s->ring[s->head];
    bool head_raw = (p->requests[0]->flags & REQUEST_RAW) && !p->batch;
    if (!head_raw && answer) {
        int k = find_pending(s, answer);
        if (k < 0) {
            /* Not the answer to anything in flight: answered twice, or a
             * notification answered.  The head stays in flight. */
            cl->stats.unexpected++;
            report(cl, "an answer whose id matches no request in flight", p->line, NULL, line);
            cJSON_Delete(answer);
            return;
        }
        for (int i = 0; i < k; i++) { /* answers skipped: lost */
            pending *q = &s->ring[s->head];
            cl->stats.lost += (unsigned long)q->count;
            report(cl, "no answer (a later one came first)", q->line, NULL, NULL);
            pop_pending(s);
        }
        p = &s->ring[s->head];
    }
    add_latency(&cl->stats, (arrived - p->sent) * 1e6);
    cl->stats.answered_lines++;
    if (!check_line(cl, p, answer, line))
        cl->stats.wrong++;
    cJSON_Delete(answer);
    pop_pending(s);
}

/* ---- running ------------------------------------------------------------------------ */

static bool more_to_send(const session *s)
{
    const client *cl = s->client;
    const client_settings *settings = cl->settings;
    if (*settings->stop)
        return false;
    if (cl->script)
        return s->script_next < cl->script_count;
    if (settings->deadline > 0)
        return bench_seconds() < settings->deadline;
    return (long)cl->stats.lines < settings->lines;
}

static void fail(client *cl, const char *what, const char *why)
{
    cl->stats.failed = true;
    snprintf(cl->stats.failure, sizeof cl->stats.failure, "%s: %s", what, why);
}

void *client_run(void *argument)
{
    session s = {.client = argument};
    client *cl = s.client;
    int pipeline = cl->settings->pipeline;
    s.ring = calloc((size_t)pipeline, sizeof *s.ring);
    if (!s.ring)
        die("out of memory");
    if (connection_open(&s.connection, cl->settings) != 0) {
        fail(cl, "connect", strerror(errno));
        free(s.ring);
        return NULL;
    }
    const char *why = NULL;
    while (!cl->stats.failed) {
        while (s.in_flight < pipeline && more_to_send(&s)) {
            pending p;
            char *line;
            size_t length;
            bool answered = next_line(&s, &line, &length, &p);
            p.sent = bench_seconds();
            cl->stats.lines++;
            if (!connection_write(&s.connection, line, length)) {
                fail(cl, "write", strerror(errno));
                free(line);
                break;
            }
            if (answered) {
                line[length - 1] = 0;
                p.line = line;
                s.ring[(s.head + s.in_flight) % pipeline] = p;
                s.in_flight++;
            } else {
                free(line);
            }
        }
        if (cl->stats.failed || s.in_flight == 0) {
            if (!more_to_send(&s))
                break;
            continue;
        }
        size_t length;
        char *line = connection_read_line(&s.connection, &length, &why);
        if (!line) {
            fail(cl, "read", why);
            break;
        }
        take_answer(&s, line, length);
    }
    /* Whatever is still in flight now will not be answered. */
    while (s.in_flight > 0) {
        pending *q = &s.ring[s.head];
        cl->stats.lost += (unsigned long)q->count;
        report(cl, "no answer", q->line, NULL, cl->stats.failure);
        pop_pending(&s);
    }
    if (!cl->stats.failed) {
        /* Nothing more may come: no answers to notifications, no extras. */
        shutdown(s.connection.fd, SHUT_WR);
        size_t length;
        char *line;
        while ((line = connection_read_line(&s.connection, &length, &why)))
            take_answer(&s, line, length);
        if (strcmp(why, "end of input") != 0)
            fail(cl, "waiting for the end of input", why);
    }
    connection_close(&s.connection);
    free(s.ring);
    return NULL;
}

/* ---- server counters ------------------------------------------------------------ */

bool server_counts(const client_settings *settings, double *requests, double *errors)
{
    connection c;
    if (connection_open(&c, settings) != 0)
        return false;
    const char *status_line =
        "{\"jsonrpc\":\"2.0\",\"method\":\"server.status\",\"id\":\"counts\"}\n";
    const char *why;
    size_t length;
    char *line = connection_write(&c, status_line, strlen(status_line))
                     ? connection_read_line(&c, &length, &why)
                     : NULL;
    cJSON *answer = line ? cJSON_Parse(line) : NULL;
    const cJSON *result = cJSON_GetObjectItemCaseSensitive(answer, "result");
    const cJSON *r = cJSON_GetObjectItemCaseSensitive(result, "requests");
    const cJSON *e = cJSON_GetObjectItemCaseSensitive(result, "errors");
    bool ok = cJSON_IsNumber(r) && cJSON_IsNumber(e);
    if (ok) {
        *requests = r->valuedouble;
        *errors = e->valuedouble;
    }
    cJSON_Delete(answer);
    connection_close(&c);
    return ok;
}
