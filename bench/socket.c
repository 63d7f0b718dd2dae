/* socket.c -- wrenchd through its socket, one connection.  Prints figures; asserts nothing but that answers are answers.
 *
 *   socket --socket PATH [--fixture FILE] [--sequential N] [--pipelined N]
 *          [--depth D] [--batch N] [--lean N] [--lp N] [--json]
 *
 *   sequential  N single-wrench wrench.classify requests, each sent when the
 *               previous answer is read: latency p50 / p99 / p999;
 *   pipelined   N such requests with D (default 64) in flight: latency from
 *               a request's write to its answer's end, and throughput;
 *   batch       one request of N wrenches (goal and strong, the default
 *               sets), from the first byte written to the answer's last byte
 *               read: wrenches per second end to end.  The request text is
 *               made before the clock starts; the answer is checked for N
 *               results but not parsed;
 *   lean        one request of N wrenches (default 1,000,000; the daemon
 *               needs --max-wrenches and --max-line for it) three times,
 *               goal and strong, fields ["verdict"], ["verdict", "margin"]
 *               and all five: wrenches per second end to end, as batch.
 *               Every verdict of the three answers is compared: the
 *               verdicts alone (by the verdict map) with the full path's;
 *               then the first --lp of them (default 20,000) again by the
 *               "lp" method, whose verdicts are compared with auto's;
 *   register    cold fixture.put of a disc with k = 2..8 fixels (a new id
 *               each time), median of 5, and the growth of server.status's
 *               cache_bytes per fixture;
 *   floor       the same sequential exchange (a 190-byte line out, the
 *               size of a single-wrench answer back) with a server that
 *               only echoes (the echo floor: another process on a
 *               Unix socket), alternated with wrenchd's exchanges request
 *               by request; and with a thread of this program over a
 *               socketpair (no process switch): what the machine's kernel
 *               costs before wrenchd does anything.
 * Wrenches are uniform in [-1, 1]^3, 6 decimals, from a fixed seed. */
#define _GNU_SOURCE /* memmem */
#include <errno.h>
#include <pthread.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <sys/un.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "bench_util.h"

static double now_us(void) { return bench_seconds() * 1e6; }

static void fail(const char *what)
{
    fprintf(stderr, "socket bench: %s%s%s\n", what, errno ? ": " : "", errno ? strerror(errno) : "");
    exit(1);
}

/* ---- a blocking connection with a line reader ----------------------------- */

typedef struct connection {
    int fd;
    char *buffer;    /* bytes read, not yet returned */
    size_t start, end, capacity;
} connection;

static void connect_to(connection *c, const char *path)
{
    memset(c, 0, sizeof *c);
    c->fd = socket(AF_UNIX, SOCK_STREAM, 0);
    struct sockaddr_un address = {.sun_family = AF_UNIX};
    if (c->fd < 0 || strlen(path) >= sizeof address.sun_path)
        fail("socket");
    strcpy(address.sun_path, path);
    if (connect(c->fd, (struct sockaddr *)&address, sizeof address) != 0)
        fail(path);
    c->capacity = 1 << 16;
    c->buffer = malloc(c->capacity);
}

static void send_all(connection *c, const char *text, size_t length)
{
    while (length > 0) {
        ssize_t n = write(c->fd, text, length);
        if (n < 0 && errno == EINTR)
            continue;
        if (n <= 0)
            fail("write");
        text += n;
        length -= (size_t)n;
    }
}

/* The next line (NUL-terminated, without "\n"), valid until the next call;
 * its length in *length. */
static char *read_line(connection *c, size_t *length)
{
    size_t searched = c->start;
    for (;;) {
        char *eol = memchr(c->buffer + searched, '\n', c->end - searched);
        if (eol) {
            char *line = c->buffer + c->start;
            *eol = 0;
            *length = (size_t)(eol - line);
            c->start = (size_t)(eol - c->buffer) + 1;
            return line;
        }
        searched = c->end;
        if (c->start > 0 && c->end == c->capacity) { /* move the partial line down */
            memmove(c->buffer, c->buffer + c->start, c->end - c->start);
            c->end -= c->start;
            searched -= c->start;
            c->start = 0;
        }
        if (c->end == c->capacity) {
            c->capacity *= 2;
            c->buffer = realloc(c->buffer, c->capacity);
            if (!c->buffer)
                fail("out of memory");
        }
        ssize_t n = read(c->fd, c->buffer + c->end, c->capacity - c->end);
        if (n < 0 && errno == EINTR)
            continue;
        if (n <= 0)
            fail("read (did the daemon close the connection?)");
        c->end += (size_t)n;
    }
}

static char *call(connection *c, const char *request, size_t *length)
{
    send_all(c, request, strlen(request));
    return read_line(c, length);
}

static void expect_result(const char *answer, const char *what)
{
    if (!strstr(answer, "\"result\"")) {
        fprintf(stderr, "socket bench: %s answered %.300s\n", what, answer);
        exit(1);
    }
}

/* ---- figures ------------------------------------------------------------ */

static int compare_doubles(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static double percentile(double *sorted, long count, double p)
{
    long index = (long)ceil(p * (double)count) - 1;
    return sorted[index < 0 ? 0 : index >= count ? count - 1 : index];
}

static char *read_file(const char *path)
{
    FILE *file = fopen(path, "rb");
    if (!file)
        fail(path);
    static char text[1 << 20];
    size_t length = fread(text, 1, sizeof text - 1, file);
    fclose(file);
    text[length] = 0;
    for (char *p = text; *p; p++) /* one line */
        if (*p == '\n' || *p == '\r')
            *p = ' ';
    return text;
}

/* The fixture id out of a fixture.put answer. */
static void id_of(const char *answer, char id[33])
{
    const char *p = strstr(answer, "\"id\":\"");
    if (!p || strlen(p) < 6 + 32)
        fail("no id in the fixture.put answer");
    memcpy(id, p + 6, 32);
    id[32] = 0;
}

static double cache_bytes(connection *c)
{
    size_t length;
    char *answer = call(c, "{\"jsonrpc\":\"2.0\",\"id\":0,\"method\":\"server.status\"}\n", &length);
    const char *p = strstr(answer, "\"cache_bytes\":");
    return p ? atof(p + 14) : NAN;
}

/* ---- the floor: a ping-pong with a thread that does nothing --------------- */

typedef struct echo {
    int fd;
    size_t answer_bytes;
} echo;

static void *echo_main(void *argument)
{
    echo *e = argument;
    char request[4096];
    char *answer = malloc(e->answer_bytes);
    memset(answer, 'x', e->answer_bytes);
    answer[e->answer_bytes - 1] = '\n';
    for (;;) {
        ssize_t n = read(e->fd, request, sizeof request);
        if (n <= 0)
            break;
        if (write(e->fd, answer, e->answer_bytes) != (ssize_t)e->answer_bytes)
            break;
    }
    free(answer);
    return NULL;
}

/* p50 of `count` exchanges of a `request_bytes` line for an answer of
 * `answer_bytes`, in microseconds. */
static double floor_p50(long count, size_t request_bytes, size_t answer_bytes)
{
    int pair[2];
    if (socketpair(AF_UNIX, SOCK_STREAM, 0, pair) != 0)
        fail("socketpair");
    echo e = {pair[1], answer_bytes};
    pthread_t thread;
    if (pthread_create(&thread, NULL, echo_main, &e) != 0)
        fail("pthread_create");
    connection c = {.fd = pair[0], .capacity = 1 << 16};
    c.buffer = malloc(c.capacity);
    char *request = malloc(request_bytes);
    memset(request, 'r', request_bytes);
    request[request_bytes - 1] = '\n';
    double *latency = malloc((size_t)count * sizeof *latency);
    size_t length;
    for (long i = 0; i < count; i++) {
        double start = now_us();
        send_all(&c, request, request_bytes);
        read_line(&c, &length);
        latency[i] = now_us() - start;
    }
    shutdown(pair[0], SHUT_RDWR);
    pthread_join(thread, NULL);
    close(pair[0]);
    close(pair[1]);
    qsort(latency, (size_t)count, sizeof *latency, compare_doubles);
    double p50 = percentile(latency, count, 0.5);
    free(latency);
    free(request);
    free(c.buffer);
    return p50;
}

/* The verdict letters of a lean answer, goal's and strong's, joined over
 * its pieces (each piece: "goal":{"verdicts":"...", then "strong":{...).
 * Returns the wrenches found. */
static long lean_verdicts(const char *answer, size_t length, char *goal, char *strong)
{
    static const char KEY[] = "\"verdicts\":\"";
    long found[2] = {0, 0};
    int set = 0;
    const char *end = answer + length;
    for (const char *p = answer; (p = memmem(p, (size_t)(end - p), KEY, sizeof KEY - 1));) {
        p += sizeof KEY - 1;
        const char *q = memchr(p, '"', (size_t)(end - p));
        if (!q)
            break;
        memcpy((set ? strong : goal) + found[set], p, (size_t)(q - p));
        found[set] += q - p;
        set ^= 1;
        p = q;
    }
    return found[0] == found[1] ? found[0] : -1;
}

/* One lean request's line: `count` wrenches from `wrenches`. */
static size_t lean_line(char *line, size_t size, const char *id, const char *fields,
                        const char *method, const double (*wrenches)[3], long count)
{
    size_t used = (size_t)snprintf(line, size,
                                   "{\"jsonrpc\":\"2.0\",\"id\":\"lean\",\"method\":\"wrench."
                                   "classify\",\"params\":{\"fixture\":\"%s\",\"fields\":%s%s"
                                   ",\"wrenches\":[",
                                   id, fields, method);
    for (long i = 0; i < count; i++)
        used += (size_t)snprintf(line + used, size - used, "%s[%.6f,%.6f,%.6f]", i ? "," : "",
                                 wrenches[i][0], wrenches[i][1], wrenches[i][2]);
    used += (size_t)snprintf(line + used, size - used, "]}}\n");
    return used;
}

/* Make room for an answer of `bytes` in the connection's buffer, touched
 * before the clock starts, so that the figure is wrenchd's. */
static void room_for(connection *c, size_t bytes)
{
    if (c->capacity >= bytes)
        return;
    memmove(c->buffer, c->buffer + c->start, c->end - c->start);
    c->end -= c->start;
    c->start = 0;
    c->buffer = realloc(c->buffer, bytes);
    if (!c->buffer)
        fail("out of memory");
    c->capacity = bytes;
    memset(c->buffer + c->end, 0, bytes - c->end);
}


/* CPU seconds (user, system) a process has used, from /proc; 0 when it
 * cannot be read. */
static void process_cpu(pid_t pid, double *user, double *system)
{
    *user = *system = 0;
    char path[64], text[1024];
    snprintf(path, sizeof path, "/proc/%d/stat", (int)pid);
    FILE *f = fopen(path, "r");
    if (!f)
        return;
    size_t n = fread(text, 1, sizeof text - 1, f);
    fclose(f);
    text[n] = 0;
    const char *p = strrchr(text, ')'); /* the name may hold spaces */
    unsigned long utime, stime;
    if (p && sscanf(p + 2, "%*c %*d %*d %*d %*d %*d %*u %*u %*u %*u %*u %lu %lu", &utime,
                    &stime) == 2) {
        double tick = (double)sysconf(_SC_CLK_TCK);
        *user = utime / tick;
        *system = stime / tick;
    }
}

/* The pid of the process at the other end of a Unix socket. */
static pid_t peer_pid(int fd)
{
    struct ucred credentials;
    socklen_t length = sizeof credentials;
    return getsockopt(fd, SOL_SOCKET, SO_PEERCRED, &credentials, &length) == 0 ? credentials.pid
                                                                               : 0;
}

/* The echo floor: a server -- another process, listening on a
 * Unix socket as wrenchd does -- that answers each line with a line of
 * `answer_bytes` and does nothing else.  The sequential figure alternates
 * its exchanges with wrenchd's and this server's, request by request, so
 * that both meet the same machine.  (floor_p50 above does the same with a
 * thread of this process over a socketpair: cheaper still, since a switch
 * between two threads of one process keeps its address space.) */
static pid_t echo_server_start(connection *c, size_t answer_bytes, const char *near)
{
    char path[sizeof(((struct sockaddr_un *)0)->sun_path)];
    snprintf(path, sizeof path, "%s.echo", near);
    unlink(path);
    int listener = socket(AF_UNIX, SOCK_STREAM, 0);
    struct sockaddr_un address = {.sun_family = AF_UNIX};
    if (listener < 0 || strlen(path) >= sizeof address.sun_path)
        fail("socket");
    strcpy(address.sun_path, path);
    if (bind(listener, (struct sockaddr *)&address, sizeof address) != 0 || listen(listener, 1) != 0)
        fail(path);
    pid_t child = fork();
    if (child < 0)
        fail("fork");
    if (child == 0) {
        int fd = accept(listener, NULL, NULL);
        char *answer = malloc(answer_bytes);
        char request[4096];
        if (fd < 0 || !answer)
            _exit(1);
        memset(answer, 'x', answer_bytes);
        answer[answer_bytes - 1] = '\n';
        for (;;) {
            ssize_t n = read(fd, request, sizeof request);
            if (n <= 0)
                _exit(0);
            if (write(fd, answer, answer_bytes) != (ssize_t)answer_bytes)
                _exit(1);
        }
    }
    close(listener);
    connect_to(c, path);
    unlink(path); /* connected: the name is no longer needed */
    return child;
}

int main(int argc, char **argv)
{
    const char *path = NULL, *fixture_path = "examples/plate-3-2-1.json";
    long sequential = 20000, pipelined = 20000, depth = 64, batch = 100000, lean = 1000000,
         lp = 20000;
    int json = 0;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        const char *value = i + 1 < argc ? argv[i + 1] : NULL;
        if (strcmp(a, "--json") == 0) {
            json = 1;
            continue;
        }
        if (!value) {
            fprintf(stderr, "usage: %s --socket PATH [--fixture FILE] [--sequential N] "
                            "[--pipelined N] [--depth D] [--batch N] [--lean N] [--lp N] [--json]\n",
                    argv[0]);
            return 2;
        }
        i++;
        if (strcmp(a, "--socket") == 0)
            path = value;
        else if (strcmp(a, "--fixture") == 0)
            fixture_path = value;
        else if (strcmp(a, "--sequential") == 0)
            sequential = atol(value);
        else if (strcmp(a, "--pipelined") == 0)
            pipelined = atol(value);
        else if (strcmp(a, "--depth") == 0)
            depth = atol(value);
        else if (strcmp(a, "--batch") == 0)
            batch = atol(value);
        else if (strcmp(a, "--lean") == 0)
            lean = atol(value);
        else if (strcmp(a, "--lp") == 0)
            lp = atol(value);
        else {
            fprintf(stderr, "%s: unknown option %s\n", argv[0], a);
            return 2;
        }
    }
    if (!path || sequential < 1 || pipelined < 1 || depth < 1 || batch < 1 || lean < 1 || lp < 1 ||
        lp > lean) {
        fprintf(stderr, "%s: --socket is required; counts are positive\n", argv[0]);
        return 2;
    }
    connection c;
    connect_to(&c, path);

    /* The fixture, stored once. */
    const char *fixture = read_file(fixture_path);
    size_t request_size = strlen(fixture) + 128;
    char *request = malloc(request_size);
    snprintf(request, request_size,
             "{\"jsonrpc\":\"2.0\",\"id\":1,\"method\":\"fixture.put\",\"params\":{\"fixture\":%s}}\n",
             fixture);
    size_t length;
    char *answer = call(&c, request, &length);
    expect_result(answer, "fixture.put");
    char id[33];
    id_of(answer, id);

    /* Single-wrench requests, made in advance. */
    long singles = sequential > pipelined ? sequential : pipelined;
    char (*lines)[192] = malloc((size_t)singles * sizeof *lines);
    uint64_t seed = 0x9e3779b97f4a7c15ULL;
    for (long i = 0; i < singles; i++) {
        double x = bench_uniform(&seed), y = bench_uniform(&seed), z = bench_uniform(&seed);
        snprintf(lines[i], sizeof lines[i],
                 "{\"jsonrpc\":\"2.0\",\"id\":%ld,\"method\":\"wrench.classify\",\"params\":"
                 "{\"fixture\":\"%s\",\"wrenches\":[[%.6f,%.6f,%.6f]]}}\n",
                 i, id, x, y, z);
    }
    /* Warm up: the worker's first answers, page faults, caches. */
    for (long i = 0; i < 200 && i < singles; i++)
        expect_result(call(&c, lines[i], &length), "wrench.classify");

    /* The echo server answers as many bytes as wrenchd did in the warm-up. */
    size_t answer_bytes = 0;
    for (long i = 0; i < 20 && i < singles; i++) {
        call(&c, lines[i], &length);
        answer_bytes += length + 1;
    }
    answer_bytes /= 20;
    connection echo;
    pid_t echo_pid = echo_server_start(&echo, answer_bytes, path);
    double *latency = malloc((size_t)singles * sizeof *latency);
    double *echo_latency = malloc((size_t)sequential * sizeof *echo_latency);
    size_t request_bytes = strlen(lines[0]);
    char *echo_request = malloc(request_bytes);
    memset(echo_request, 'r', request_bytes);
    echo_request[request_bytes - 1] = '\n';
    for (long i = 0; i < 200; i++) { /* its warm-up */
        send_all(&echo, echo_request, request_bytes);
        read_line(&echo, &length);
    }
    /* CPU per exchange, each side's: wrenchd's from /proc (its pid from
     * the socket), the echo server's from its rusage once reaped. */
    pid_t daemon_pid = peer_pid(c.fd);
    double daemon_user0, daemon_system0, daemon_user1, daemon_system1;
    process_cpu(daemon_pid, &daemon_user0, &daemon_system0);
    struct rusage children0, children1;
    getrusage(RUSAGE_CHILDREN, &children0);
    for (long i = 0; i < sequential; i++) {
        double start = now_us();
        answer = call(&c, lines[i], &length);
        latency[i] = now_us() - start;
        if (i == 0)
            expect_result(answer, "wrench.classify");
        start = now_us();
        send_all(&echo, echo_request, request_bytes);
        read_line(&echo, &length);
        echo_latency[i] = now_us() - start;
    }
    process_cpu(daemon_pid, &daemon_user1, &daemon_system1);
    close(echo.fd);
    waitpid(echo_pid, NULL, 0);
    getrusage(RUSAGE_CHILDREN, &children1);
#define SECONDS(t) ((double)(t).tv_sec + (t).tv_usec * 1e-6)
    /* The echo server's figures include its 200 warm-up exchanges. */
    double echo_user_us = (SECONDS(children1.ru_utime) - SECONDS(children0.ru_utime)) * 1e6 /
                          (double)(sequential + 200),
           echo_system_us = (SECONDS(children1.ru_stime) - SECONDS(children0.ru_stime)) * 1e6 /
                            (double)(sequential + 200),
           daemon_user_us = (daemon_user1 - daemon_user0) * 1e6 / (double)sequential,
           daemon_system_us = (daemon_system1 - daemon_system0) * 1e6 / (double)sequential;
#undef SECONDS
    free(echo.buffer);
    free(echo_request);
    qsort(latency, (size_t)sequential, sizeof *latency, compare_doubles);
    qsort(echo_latency, (size_t)sequential, sizeof *echo_latency, compare_doubles);
    double sequential_p50 = percentile(latency, sequential, 0.5),
           sequential_p99 = percentile(latency, sequential, 0.99),
           sequential_p999 = percentile(latency, sequential, 0.999),
           server_floor_us = percentile(echo_latency, sequential, 0.5);
    free(echo_latency);

    double floor_us = floor_p50(sequential, strlen(lines[0]), answer_bytes);

    /* Pipelined: `depth` in flight; answers come in request order. */
    double *sent = malloc((size_t)pipelined * sizeof *sent);
    long next = 0;
    double start = now_us();
    for (; next < depth && next < pipelined; next++) {
        sent[next] = now_us();
        send_all(&c, lines[next], strlen(lines[next]));
    }
    for (long done = 0; done < pipelined; done++) {
        answer = read_line(&c, &length);
        latency[done] = now_us() - sent[done];
        if (done == 0)
            expect_result(answer, "wrench.classify (pipelined)");
        if (next < pipelined) {
            sent[next] = now_us();
            send_all(&c, lines[next], strlen(lines[next]));
            next++;
        }
    }
    double pipelined_seconds = (now_us() - start) / 1e6;
    qsort(latency, (size_t)pipelined, sizeof *latency, compare_doubles);
    double pipelined_p50 = percentile(latency, pipelined, 0.5),
           pipelined_p99 = percentile(latency, pipelined, 0.99);

    /* One batch of `batch` wrenches. */
    size_t batch_size = (size_t)batch * 40 + 256;
    char *batch_line = malloc(batch_size);
    size_t used = (size_t)snprintf(batch_line, batch_size,
                                   "{\"jsonrpc\":\"2.0\",\"id\":\"batch\",\"method\":\"wrench."
                                   "classify\",\"params\":{\"fixture\":\"%s\",\"wrenches\":[",
                                   id);
    seed = 0x2545f4914f6cdd1dULL;
    for (long i = 0; i < batch; i++) {
        double x = bench_uniform(&seed), y = bench_uniform(&seed), z = bench_uniform(&seed);
        used += (size_t)snprintf(batch_line + used, batch_size - used, "%s[%.6f,%.6f,%.6f]",
                                 i ? "," : "", x, y, z);
    }
    used += (size_t)snprintf(batch_line + used, batch_size - used, "]}}\n");
    /* A client that answers batches keeps its receive buffer: sized and
     * touched before the clock starts, so the figure is wrenchd's. */
    size_t room = (size_t)batch * 800 + (1 << 20);
    if (c.capacity < room) {
        memmove(c.buffer, c.buffer + c.start, c.end - c.start);
        c.end -= c.start;
        c.start = 0;
        c.buffer = realloc(c.buffer, room);
        if (!c.buffer)
            fail("out of memory");
        c.capacity = room;
        memset(c.buffer + c.end, 0, room - c.end);
    }
    start = now_us();
    send_all(&c, batch_line, used);
    answer = read_line(&c, &length);
    double batch_seconds = (now_us() - start) / 1e6;
    expect_result(answer, "the batch");
    long results = 0;
    for (const char *p = answer; (p = memmem(p, (size_t)(answer + length - p), "{\"goal\":", 8));
         p += 8)
        results++;
    if (results != batch) {
        fprintf(stderr, "socket bench: the batch answered %ld results for %ld wrenches\n", results,
                batch);
        return 1;
    }
    size_t batch_answer_bytes = length;

    /* Lean batches: verdicts alone, with margins, with every field. */
    static const char *const LEAN_FIELDS[3] = {
        "[\"verdict\"]", "[\"verdict\",\"margin\"]",
        "[\"verdict\",\"margin\",\"blocking\",\"states\",\"witness\"]"};
    double (*lean_wrenches)[3] = malloc((size_t)lean * sizeof *lean_wrenches);
    seed = 0x853c49e6748fea9bULL;
    for (long i = 0; i < lean; i++)
        for (int k = 0; k < 3; k++)
            lean_wrenches[i][k] = bench_uniform(&seed);
    size_t lean_size = (size_t)lean * 40 + 512;
    char *lean_text = malloc(lean_size);
    char *letters[3][2];
    double lean_per_s[3];
    size_t lean_in = 0, lean_out[3];
    for (int f = 0; f < 3; f++) {
        size_t n = lean_line(lean_text, lean_size, id, LEAN_FIELDS[f], "",
                             (const double(*)[3])lean_wrenches, lean);
        lean_in = n;
        room_for(&c, (size_t)lean * (f == 0 ? 4 : f == 1 ? 60 : 1600) + (1 << 20));
        start = now_us();
        send_all(&c, lean_text, n);
        answer = read_line(&c, &length);
        lean_per_s[f] = (double)lean / ((now_us() - start) / 1e6);
        expect_result(answer, "a lean batch");
        lean_out[f] = length;
        letters[f][0] = malloc((size_t)lean + 1);
        letters[f][1] = malloc((size_t)lean + 1);
        if (lean_verdicts(answer, length, letters[f][0], letters[f][1]) != lean) {
            fprintf(stderr, "socket bench: a lean batch (%s) did not answer %ld verdicts\n",
                    LEAN_FIELDS[f], lean);
            return 1;
        }
    }
    /* Every verdict alone against the margin path's and the full path's. */
    long lean_disagree = 0;
    for (int set = 0; set < 2; set++)
        for (long i = 0; i < lean; i++)
            lean_disagree += (letters[0][set][i] != letters[1][set][i]) +
                             (letters[0][set][i] != letters[2][set][i]);
    /* The first `lp` wrenches by the lp method: inside or outside, against
     * auto's (a boundary verdict of auto's is within the band, either). */
    size_t n = lean_line(lean_text, lean_size, id, LEAN_FIELDS[0], ",\"method\":\"lp\"",
                         (const double(*)[3])lean_wrenches, lp);
    room_for(&c, (size_t)lp * 4 + (1 << 20));
    start = now_us();
    send_all(&c, lean_text, n);
    answer = read_line(&c, &length);
    double lp_per_s = (double)lp / ((now_us() - start) / 1e6);
    expect_result(answer, "an lp batch");
    char *lp_letters[2] = {malloc((size_t)lp + 1), malloc((size_t)lp + 1)};
    if (lean_verdicts(answer, length, lp_letters[0], lp_letters[1]) != lp) {
        fprintf(stderr, "socket bench: the lp batch did not answer %ld verdicts\n", lp);
        return 1;
    }
    long lp_agree = 0;
    for (int set = 0; set < 2; set++)
        for (long i = 0; i < lp; i++)
            lp_agree += letters[0][set][i] == 'b' || letters[0][set][i] == lp_letters[set][i];
    for (int f = 0; f < 3; f++)
        free(letters[f][0]), free(letters[f][1]);
    free(lp_letters[0]);
    free(lp_letters[1]);
    free(lean_text);
    free(lean_wrenches);

    /* Registration: a new disc each time (the radius moves the id). */
    double put_ms[9] = {0}, bytes_per_fixture[9] = {0};
    int serial = 0;
    for (int k = 2; k <= 8; k++) {
        double times[5];
        double before = cache_bytes(&c);
        for (int r = 0; r < 5; r++) {
            double radius = 1 + 1e-6 * ++serial;
            char text[2048];
            int n = snprintf(text, sizeof text,
                             "{\"jsonrpc\":\"2.0\",\"id\":2,\"method\":\"fixture.put\",\"params\":"
                             "{\"fixture\":{\"body\":{\"mass\":1,\"shape\":{\"type\":\"circle\","
                             "\"center\":[0,0],\"radius\":%.9f}},\"friction\":{\"static\":0.3},"
                             "\"fixels\":[",
                             radius);
            for (int i = 0; i < k; i++) {
                double angle = (200 + 300.0 * i / k) * 3.14159265358979323846 / 180;
                n += snprintf(text + n, sizeof text - (size_t)n, "%s{\"at\":[%.17g,%.17g]}",
                              i ? "," : "", radius * cos(angle), radius * sin(angle));
            }
            snprintf(text + n, sizeof text - (size_t)n, "]}}}\n");
            double t = now_us();
            answer = call(&c, text, &length);
            times[r] = (now_us() - t) / 1e3;
            expect_result(answer, "fixture.put (registration)");
        }
        double after = cache_bytes(&c);
        qsort(times, 5, sizeof *times, compare_doubles);
        put_ms[k] = times[2];
        bytes_per_fixture[k] = (after - before) / 5;
    }

    if (json) {
        printf("{\"sequential\": %ld, \"sequential_p50_us\": %.1f, \"sequential_p99_us\": %.1f, "
               "\"sequential_p999_us\": %.1f, \"floor_p50_us\": %.1f, \"server_floor_p50_us\": %.1f, "
               "\"daemon_cpu_us\": [%.2f, %.2f], \"echo_cpu_us\": [%.2f, %.2f], "
               "\"answer_bytes\": %zu, "
               "\"pipelined\": %ld, \"depth\": %ld, "
               "\"pipelined_p50_us\": %.1f, \"pipelined_p99_us\": %.1f, "
               "\"pipelined_per_s\": %.0f, \"batch\": %ld, \"batch_s\": %.4f, "
               "\"batch_per_s\": %.0f, \"batch_request_bytes\": %zu, \"batch_answer_bytes\": %zu, "
               "\"lean\": %ld, \"lean_verdict_per_s\": %.0f, \"lean_margin_per_s\": %.0f, "
               "\"lean_all_per_s\": %.0f, \"lean_request_bytes\": %zu, "
               "\"lean_answer_bytes\": [%zu, %zu, %zu], \"lean_disagree\": %ld, "
               "\"lean_compared\": %ld, \"lp\": %ld, \"lp_per_s\": %.0f, \"lp_agree\": %ld, "
               "\"lp_compared\": %ld, \"put_ms\": {",
               sequential, sequential_p50, sequential_p99, sequential_p999, floor_us, server_floor_us,
               daemon_user_us, daemon_system_us, echo_user_us, echo_system_us, answer_bytes,
               pipelined, depth,
               pipelined_p50, pipelined_p99, (double)pipelined / pipelined_seconds, batch,
               batch_seconds, (double)batch / batch_seconds, used, batch_answer_bytes, lean,
               lean_per_s[0], lean_per_s[1], lean_per_s[2], lean_in, lean_out[0], lean_out[1],
               lean_out[2], lean_disagree, 4 * lean, lp, lp_per_s, lp_agree, 2 * lp);
        for (int k = 2; k <= 8; k++)
            printf("%s\"%d\": %.3f", k > 2 ? ", " : "", k, put_ms[k]);
        printf("}, \"cache_bytes_per_fixture\": {");
        for (int k = 2; k <= 8; k++)
            printf("%s\"%d\": %.0f", k > 2 ? ", " : "", k, bytes_per_fixture[k]);
        printf("}}\n");
    } else {
        printf("sequential, %ld requests     p50 %7.1f us  p99 %7.1f us  p999 %7.1f us   target "
               "p50 <= 30\n",
               sequential, sequential_p50, sequential_p99, sequential_p999);
        printf("echo floor: a server process p50 %7.1f us  (%zu bytes back; p50 over it %.2f, "
               "target <= 1.25)\n",
               server_floor_us, answer_bytes, sequential_p50 / server_floor_us);
        printf("  a thread of this process   p50 %7.1f us  (socketpair)\n", floor_us);
        printf("CPU per exchange, user + system: wrenchd %.2f + %.2f us, the echo server %.2f + "
               "%.2f us\n",
               daemon_user_us, daemon_system_us, echo_user_us, echo_system_us);
        printf("pipelined %ld deep, %ld      p50 %7.1f us  p99 %7.1f us  %.0f requests/s\n", depth,
               pipelined, pipelined_p50, pipelined_p99, (double)pipelined / pipelined_seconds);
        printf("batch of %ld wrenches        %.3f s, %.0f wrenches/s (%zu bytes in, %zu out)   "
               "target >= 1000000\n",
               batch, batch_seconds, (double)batch / batch_seconds, used, batch_answer_bytes);
        printf("lean batch of %ld, verdicts       %.0f wrenches/s   target >= 2000000\n", lean,
               lean_per_s[0]);
        printf("lean batch, verdicts and margins  %.0f wrenches/s   target >= 1000000\n",
               lean_per_s[1]);
        printf("lean batch, every field           %.0f wrenches/s   target >= 400000\n",
               lean_per_s[2]);
        printf("verdicts alone differing from the margin and full paths: %ld of %ld\n",
               lean_disagree, 4 * lean);
        printf("lp batch of %ld, verdicts          %.0f wrenches/s; agrees with auto on %ld of %ld\n",
               lp, lp_per_s, lp_agree, 2 * lp);
        for (int k = 2; k <= 8; k++)
            printf("fixture.put k = %d           %8.3f ms   %.0f cache bytes per fixture%s\n", k,
                   put_ms[k], bytes_per_fixture[k], k == 8 ? "   target < 100 ms" : "");
    }
    free(batch_line);
    free(sent);
    free(latency);
    free(lines);
    free(request);
    free(c.buffer);
    close(c.fd);
    return 0;
}
