/* test_server.c -- a connection's answers come in the order asked, whatever
 * answers them: the event loop (light requests), the workers a piece at a
 * time (a long classify, push.regions edge by edge), errors found before a
 * line is read, batches, notifications (no answer), and a client that does
 * not read for a while (its work paused at a small --max-output).
 *
 * The daemon's own loop (wd_server_run) runs in a child process, so that
 * its signal handling and its exit status are the real ones: SIGTERM at the
 * end must give exit status 0. */
#define _GNU_SOURCE
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include "wd_log.h"
#include "wd_server.h"

#include <cjson/cJSON.h>
#include <errno.h>
#include <math.h>
#include <signal.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/prctl.h>
#include <sys/socket.h>
#include <sys/un.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

typedef struct daemon_under_test {
    char dir[64];
    char path[128];
    pid_t pid;
} daemon_under_test;

static const char DISC[] =
    "{\"name\":\"disc\",\"body\":{\"mass\":1,\"inertia\":0.5,\"shape\":{\"type\":\"circle\","
    "\"center\":[0,0],\"radius\":1}},\"friction\":{\"static\":0.5},"
    "\"fixels\":[{\"at\":[-1,0]},{\"at\":[0,-1]}]}";

/* A regular polygon of EDGES edges of radius 2, for push.regions answered a
 * few edges a piece, with fixels at the middles of edges 0, EDGES/3 and
 * 2 EDGES/3. */
#define EDGES 24
static void vertex(int i, double p[2])
{
    double angle = 2 * 3.141592653589793 * (i % EDGES) / EDGES;
    p[0] = 2 * cos(angle);
    p[1] = 2 * sin(angle);
}

static char *polygon_fixture(void)
{
    char *text = malloc(8192);
    int n = snprintf(text, 8192, "{\"body\":{\"mass\":1,\"shape\":{\"type\":\"polygon\",\"vertices\":[");
    for (int i = 0; i < EDGES; i++) {
        double p[2];
        vertex(i, p);
        n += snprintf(text + n, 8192 - (size_t)n, "%s[%.17g,%.17g]", i ? "," : "", p[0], p[1]);
    }
    n += snprintf(text + n, 8192 - (size_t)n, "]}},\"friction\":{\"static\":0.3},\"fixels\":[");
    for (int k = 0; k < 3; k++) {
        double a[2], b[2];
        vertex(k * EDGES / 3, a);
        vertex(k * EDGES / 3 + 1, b);
        n += snprintf(text + n, 8192 - (size_t)n, "%s{\"at\":[%.17g,%.17g]}", k ? "," : "",
                      (a[0] + b[0]) / 2, (a[1] + b[1]) / 2);
    }
    snprintf(text + n, 8192 - (size_t)n, "]}");
    return text;
}

static int connect_to(const char *path)
{
    struct sockaddr_un address = {.sun_family = AF_UNIX};
    snprintf(address.sun_path, sizeof address.sun_path, "%s", path);
    for (int attempt = 0; attempt < 500; attempt++) {
        int fd = socket(AF_UNIX, SOCK_STREAM, 0);
        assert_true(fd >= 0);
        if (connect(fd, (struct sockaddr *)&address, sizeof address) == 0)
            return fd;
        close(fd);
        usleep(10000);
    }
    fail_msg("no daemon at %s", path);
    return -1;
}

static int start(void **state)
{
    daemon_under_test *d = calloc(1, sizeof *d);
    snprintf(d->dir, sizeof d->dir, "/tmp/wd-order-XXXXXX");
    if (!mkdtemp(d->dir))
        return -1;
    snprintf(d->path, sizeof d->path, "%s/s", d->dir);
    d->pid = fork();
    if (d->pid == 0) {
        /* Should this test die (a failed assertion, a sanitizer), the
         * daemon goes with it rather than keep its output pipe open. */
        prctl(PR_SET_PDEATHSIG, SIGKILL);
        if (getppid() == 1)
            _exit(1);
        wd_log_set_level(WD_LOG_WARN);
        wd_config config = {
            .socket_path = d->path, .threads = 2, .cache_bytes = 64 << 20,
            .max_fixtures = 100, .max_line = 16 << 20, .max_depth = 64,
            .max_wrenches = 100000,
            /* Small: a long answer is made a few pieces at a time, paused
             * while this client does not read. */
            .max_output = 64 * 1024, .max_clients = 16, .max_batch = 100,
            .idle_timeout = 60, .request_timeout = 30, .listen_fd = -1};
        _exit(wd_server_run(&config));
    }
    *state = d;
    return d->pid > 0 ? 0 : -1;
}

static int stop(void **state)
{
    daemon_under_test *d = *state;
    kill(d->pid, SIGTERM);
    int status = 0;
    waitpid(d->pid, &status, 0);
    rmdir(d->dir);
    bool ok = WIFEXITED(status) && WEXITSTATUS(status) == 0;
    free(d);
    if (!ok)
        fail_msg("wrenchd did not exit with status 0 after SIGTERM (%d)", status);
    return ok ? 0 : -1;
}

static void send_all(int fd, const char *text, size_t length)
{
    while (length > 0) {
        ssize_t n = send(fd, text, length, MSG_NOSIGNAL);
        if (n < 0 && errno == EINTR)
            continue;
        if (n <= 0)
            fail_msg("send: %s", n < 0 ? strerror(errno) : "nothing sent");
        text += n;
        length -= (size_t)n;
    }
}

/* Read lines into a growing buffer until `count` have come. */
typedef struct reader {
    int fd;
    char *buffer;
    size_t length, capacity, start;
} reader;

static char *read_line(reader *r)
{
    for (;;) {
        char *newline = r->buffer ? memchr(r->buffer + r->start, '\n', r->length - r->start)
                                  : NULL;
        if (newline) {
            *newline = 0;
            char *line = r->buffer + r->start;
            r->start = (size_t)(newline - r->buffer) + 1;
            return line;
        }
        if (r->length + 65536 > r->capacity) {
            r->capacity = 2 * (r->length + 65536);
            r->buffer = realloc(r->buffer, r->capacity);
        }
        ssize_t n = recv(r->fd, r->buffer + r->length, 65536, 0);
        if (n <= 0)
            fail_msg("the daemon closed the connection: %s", n < 0 ? strerror(errno) : "EOF");
        r->length += (size_t)n;
    }
}

/* The id of a single answer, or of the first member of a batch answer. */
static long answer_id(const char *line)
{
    cJSON *json = cJSON_Parse(line);
    if (!json)
        fail_msg("an answer that is not JSON: %.200s", line);
    const cJSON *first = cJSON_IsArray(json) ? json->child : json;
    const cJSON *id = cJSON_GetObjectItemCaseSensitive(first, "id");
    long value = cJSON_IsNumber(id) ? (long)id->valuedouble : -1;
    cJSON_Delete(json);
    return value;
}

/* The buffer a text of `size` bytes is kept in: powers of two, so that
 * appending is linear (ASan's realloc always moves: growing by what each
 * piece needs copied the whole text every time, and building 40 requests
 * under ASan on a loaded machine took longer than the idle timeout). */
static size_t capacity_for(size_t size)
{
    size_t capacity = 256;
    while (capacity < size)
        capacity *= 2;
    return capacity;
}

static void append(char **text, size_t *length, const char *format, ...)
{
    va_list args;
    va_start(args, format);
    int n = vsnprintf(NULL, 0, format, args);
    va_end(args);
    size_t need = *length + (size_t)n + 1;
    if (!*text || capacity_for(*length + 1) < need)
        *text = realloc(*text, capacity_for(need));
    va_start(args, format);
    vsnprintf(*text + *length, (size_t)n + 1, format, args);
    va_end(args);
    *length += (size_t)n;
}

/* Requests of every kind, pipelined on one connection; the answers' ids
 * must come back in the order sent (notifications and id-less refusals
 * answered with id null or not at all, in their place). */
static void answers_come_in_the_order_asked(void **state)
{
    daemon_under_test *d = *state;
    int fd = connect_to(d->path);
    reader r = {fd, NULL, 0, 0, 0};
    char *put = NULL;
    size_t put_length = 0;
    append(&put, &put_length, "{\"jsonrpc\":\"2.0\",\"method\":\"fixture.put\",\"params\":{\"fixture\":%s},\"id\":0}\n",
           DISC);
    send_all(fd, put, put_length);
    cJSON *answer = cJSON_Parse(read_line(&r));
    char id[64];
    snprintf(id, sizeof id, "%s",
             cJSON_GetObjectItem(cJSON_GetObjectItem(answer, "result"), "id")->valuestring);
    cJSON_Delete(answer);
    free(put);

    char *polygon = polygon_fixture();
    char *lines = NULL;
    size_t length = 0;
    long expected[400];
    int expected_count = 0;
    for (int i = 1; i <= 300; i++) {
        switch (i % 10) {
        case 0: /* light: a classify of a stored, ready fixture */
            append(&lines, &length,
                   "{\"jsonrpc\":\"2.0\",\"method\":\"wrench.classify\",\"params\":{\"fixture\":\"%s\","
                   "\"wrenches\":[[-1,-1,%d]]},\"id\":%d}\n", id, i, i);
            break;
        case 1: /* a long classify, many pieces */
            append(&lines, &length,
                   "{\"jsonrpc\":\"2.0\",\"method\":\"wrench.classify\",\"params\":{\"fixture\":\"%s\","
                   "\"sets\":[\"goal\",\"strong\",\"both\"],\"wrenches\":[", id);
            for (int w = 0; w < 600; w++)
                append(&lines, &length, "%s[%d,-1,0.5]", w ? "," : "", w % 7 - 3);
            append(&lines, &length, "]},\"id\":%d}\n", i);
            break;
        case 2: /* push.regions with a finger's friction: edge by edge (every
                 * fifth time: seconds of work under a sanitizer) */
            if (i % 50 != 2) {
                append(&lines, &length,
                       "{\"jsonrpc\":\"2.0\",\"method\":\"modes.get\",\"params\":{\"fixture\":\"%s\"},"
                       "\"id\":%d}\n", id, i);
                break;
            }
            append(&lines, &length,
                   "{\"jsonrpc\":\"2.0\",\"method\":\"push.regions\",\"params\":{\"fixture\":%s,"
                   "\"set\":\"strong\",\"finger_friction\":0.1},\"id\":%d}\n", polygon, i);
            break;
        case 3: /* a notification: no answer */
            append(&lines, &length, "{\"jsonrpc\":\"2.0\",\"method\":\"server.status\"}\n");
            continue; /* nothing in its place */
        case 4: /* not JSON: refused before any request is read, id null */
            append(&lines, &length, "{not json\n");
            expected[expected_count++] = -1;
            continue;
        case 5: /* a batch, its first member's id */
            append(&lines, &length,
                   "[{\"jsonrpc\":\"2.0\",\"method\":\"modes.get\",\"params\":{\"fixture\":\"%s\"},\"id\":%d},"
                   "{\"jsonrpc\":\"2.0\",\"method\":\"server.status\"},"
                   "{\"jsonrpc\":\"2.0\",\"method\":\"plan.get\",\"params\":{\"fixture\":%s},\"id\":7}]\n",
                   id, i, DISC);
            break;
        case 6: /* an error found by a handler */
            append(&lines, &length,
                   "{\"jsonrpc\":\"2.0\",\"method\":\"cone.get\",\"params\":{\"fixture\":\"%s\","
                   "\"constraints\":\"sx\"},\"id\":%d}\n", id, i);
            break;
        default: /* light and cheap */
            append(&lines, &length, "{\"jsonrpc\":\"2.0\",\"method\":\"server.status\",\"id\":%d}\n", i);
            break;
        }
        expected[expected_count++] = i;
    }
    /* Sent whole before reading anything: the daemon pauses the long
     * answers at --max-output until this client reads. */
    send_all(fd, lines, length);
    usleep(200000);
    for (int k = 0; k < expected_count; k++) {
        long got = answer_id(read_line(&r));
        if (got != expected[k])
            fail_msg("answer %d has id %ld, expected %ld", k, got, expected[k]);
    }
    free(lines);
    free(polygon);
    free(r.buffer);
    close(fd);
}

/* Two connections at once, each pipelining long and light requests: each
 * gets its own answers, in its own order. */
static void connections_keep_their_own_order(void **state)
{
    daemon_under_test *d = *state;
    int fds[2];
    reader readers[2];
    char *text[2] = {NULL, NULL};
    size_t lengths[2] = {0, 0};
    /* Both texts are made before connecting: a connection is not left idle
     * while they are built. */
    for (int c = 0; c < 2; c++) {
        char *lines = NULL;
        size_t length = 0;
        for (int i = 0; i < 40; i++) {
            if (i % 4 == 0) {
                append(&lines, &length,
                       "{\"jsonrpc\":\"2.0\",\"method\":\"wrench.classify\",\"params\":{\"fixture\":%s,"
                       "\"wrenches\":[", DISC);
                for (int w = 0; w < 3000; w++)
                    append(&lines, &length, "%s[1,%d,0]", w ? "," : "", w % 5 - 2);
                append(&lines, &length, "]},\"id\":%d}\n", 1000 * c + i);
            } else {
                append(&lines, &length, "{\"jsonrpc\":\"2.0\",\"method\":\"server.status\",\"id\":%d}\n",
                       1000 * c + i);
            }
        }
        text[c] = lines;
        lengths[c] = length;
    }
    for (int c = 0; c < 2; c++) {
        fds[c] = connect_to(d->path);
        readers[c] = (reader){fds[c], NULL, 0, 0, 0};
        send_all(fds[c], text[c], lengths[c]);
        free(text[c]);
    }
    for (int i = 0; i < 40; i++)
        for (int c = 0; c < 2; c++) {
            long got = answer_id(read_line(&readers[c]));
            if (got != 1000 * c + i)
                fail_msg("connection %d: answer %d has id %ld", c, i, got);
        }
    for (int c = 0; c < 2; c++) {
        free(readers[c].buffer);
        close(fds[c]);
    }
}

int main(void)
{
    signal(SIGPIPE, SIG_IGN);
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup_teardown(answers_come_in_the_order_asked, start, stop),
        cmocka_unit_test_setup_teardown(connections_keep_their_own_order, start, stop),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
