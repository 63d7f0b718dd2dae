/* wrenchclient.c -- libwrenchclient (see wrenchclient.h). */
#include "wrenchclient.h"

#include <errno.h>
#include <math.h>
#include <poll.h>
#include <stdarg.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <sys/un.h>
#include <time.h>
#include <unistd.h>

struct wrc_client {
    int fd;                       /* -1 while disconnected */
    char path[sizeof(((struct sockaddr_un *)0)->sun_path)];
    int timeout_ms;               /* 0: no limit */
    char *request;                /* wrc_classify's request line */
    char *answer;                 /* wrc_classify's answer line */
    size_t buffer_bytes;          /* size of each */
    unsigned long next_id;
    int server_code;
    char server_field[192];
    char server_reason[256];
    char last_error[256];
};

const char *wrc_strerror(int error)
{
    switch (error) {
    case WRC_OK: return "success";
    case WRC_ECONNECT: return "cannot connect to wrenchd";
    case WRC_ETIMEOUT: return "wrenchd did not answer in time";
    case WRC_EIO: return "the connection to wrenchd broke";
    case WRC_EPROTO: return "wrenchd's answer does not follow the protocol";
    case WRC_ESERVER: return "wrenchd answered with an error";
    case WRC_ETOOBIG: return "the request or answer is too big for the client's buffer";
    case WRC_EINVAL: return "invalid argument";
    case WRC_ENOMEM: return "out of memory";
    default: return "unknown error";
    }
}

static int fail(wrc_client *c, int code, const char *format, ...)
{
    va_list args;
    va_start(args, format);
    vsnprintf(c->last_error, sizeof c->last_error, format, args);
    va_end(args);
    return code;
}

const char *wrc_last_error(const wrc_client *client) { return client->last_error; }

void wrc_server_error(const wrc_client *c, int *code, const char **field, const char **reason)
{
    if (code)
        *code = c->server_code;
    if (field)
        *field = c->server_field;
    if (reason)
        *reason = c->server_reason;
}

static long long now_ms(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (long long)t.tv_sec * 1000 + t.tv_nsec / 1000000;
}

/* Wait for `events` on the socket until the deadline (-1: none). */
static int wait_for(wrc_client *c, short events, long long deadline)
{
    for (;;) {
        int wait = -1;
        if (deadline >= 0) {
            long long left = deadline - now_ms();
            if (left <= 0)
                return fail(c, WRC_ETIMEOUT, "no answer within %d ms", c->timeout_ms);
            wait = left > 0x7fffffff ? 0x7fffffff : (int)left;
        }
        struct pollfd p = {c->fd, events, 0};
        int n = poll(&p, 1, wait);
        if (n > 0)
            return WRC_OK;
        if (n < 0 && errno != EINTR)
            return fail(c, WRC_EIO, "poll: %s", strerror(errno));
        if (n == 0)
            return fail(c, WRC_ETIMEOUT, "no answer within %d ms", c->timeout_ms);
    }
}

static void disconnect(wrc_client *c)
{
    if (c->fd >= 0)
        close(c->fd);
    c->fd = -1;
}

void wrc_connect_reason(const char *socket_path, int os_error, char *out, size_t size)
{
    switch (os_error) {
    case EACCES:
    case EPERM:
        snprintf(out, size, "permission denied on %s", socket_path);
        break;
    case ENOENT:
        snprintf(out, size, "no socket at %s: is wrenchd running?", socket_path);
        break;
    case ECONNREFUSED:
        /* The file is there but nobody listens: a daemon that died without
         * removing it, or a file that is not wrenchd's socket. */
        snprintf(out, size, "connection refused at %s: a stale socket, wrenchd is not running",
                 socket_path);
        break;
    case ETIMEDOUT:
        snprintf(out, size, "%s: the daemon does not accept in time", socket_path);
        break;
    default:
        snprintf(out, size, "%s: %s", socket_path, strerror(os_error));
        break;
    }
}

static int open_connection(wrc_client *c)
{
    struct sockaddr_un address = {.sun_family = AF_UNIX};
    memcpy(address.sun_path, c->path, sizeof address.sun_path);
    c->fd = socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC | SOCK_NONBLOCK, 0);
    if (c->fd < 0)
        return fail(c, WRC_ECONNECT, "socket: %s", strerror(errno));
    long long deadline = c->timeout_ms > 0 ? now_ms() + c->timeout_ms : -1;
    while (connect(c->fd, (struct sockaddr *)&address, sizeof address) != 0) {
        if (errno == EINTR)
            continue;
        if (errno == EAGAIN || errno == EINPROGRESS) {
            /* A full backlog: wait for the daemon to accept. */
            if (wait_for(c, POLLOUT, deadline) != WRC_OK) {
                disconnect(c);
                errno = ETIMEDOUT;
                wrc_connect_reason(c->path, ETIMEDOUT, c->last_error, sizeof c->last_error);
                return WRC_ECONNECT;
            }
            continue;
        }
        int saved = errno;
        disconnect(c);
        wrc_connect_reason(c->path, saved, c->last_error, sizeof c->last_error);
        errno = saved;
        return WRC_ECONNECT;
    }
    return WRC_OK;
}

wrc_client *wrc_connect(const char *socket_path, int timeout_ms, size_t buffer_bytes, int *error)
{
    int scratch;
    if (!error)
        error = &scratch;
    if (!socket_path || timeout_ms < 0 ||
        strlen(socket_path) >= sizeof(((struct sockaddr_un *)0)->sun_path)) {
        *error = WRC_EINVAL;
        return NULL;
    }
    wrc_client *c = calloc(1, sizeof *c);
    if (!c) {
        *error = WRC_ENOMEM;
        return NULL;
    }
    c->buffer_bytes = buffer_bytes ? buffer_bytes : 64 * 1024;
    if (c->buffer_bytes < 512)
        c->buffer_bytes = 512;
    c->request = malloc(c->buffer_bytes);
    c->answer = malloc(c->buffer_bytes);
    if (!c->request || !c->answer) {
        wrc_close(c);
        *error = WRC_ENOMEM;
        return NULL;
    }
    strcpy(c->path, socket_path);
    c->timeout_ms = timeout_ms;
    c->fd = -1;
    *error = open_connection(c);
    if (*error != WRC_OK) {
        int saved = errno; /* why, for wrc_connect_reason */
        wrc_close(c);
        errno = saved;
        return NULL;
    }
    return c;
}

void wrc_close(wrc_client *c)
{
    if (!c)
        return;
    disconnect(c);
    free(c->request);
    free(c->answer);
    free(c);
}

/* Send the whole line.  *untouched stays true while no byte went out, so
 * a failure then may be retried on a new connection. */
static int send_all(wrc_client *c, const char *data, size_t length, long long deadline,
                    bool *untouched)
{
    size_t done = 0;
    while (done < length) {
        ssize_t n = send(c->fd, data + done, length - done, MSG_NOSIGNAL);
        if (n > 0) {
            done += (size_t)n;
            *untouched = false;
            continue;
        }
        if (n < 0 && errno == EINTR)
            continue;
        if (n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK)) {
            int status = wait_for(c, POLLOUT, deadline);
            if (status != WRC_OK)
                return status;
            continue;
        }
        return fail(c, WRC_EIO, "send: %s", strerror(errno));
    }
    return WRC_OK;
}

/* A notification the daemon sends before an answer (design.progress): its
 * lines, and only they, begin so. */
static const char NOTIFICATION[] = "{\"jsonrpc\":\"2.0\",\"method\":";

/* Read one answer line into buffer[0..capacity); with `grow`, *buffer is
 * malloc'd and grows.  The line ends with "\n", replaced by NUL.  With
 * `notify`, notification lines before it go there instead (each renews
 * the deadline: the timeout is a silence); without, nothing may precede
 * the answer. */
static int read_line(wrc_client *c, char **buffer, size_t *capacity, bool grow, long long deadline,
                     wrc_notify notify, void *context)
{
    size_t length = 0, scanned = 0;
    for (;;) {
        char *end;
        while ((end = memchr(*buffer + scanned, '\n', length - scanned)) != NULL) {
            size_t line_length = (size_t)(end - *buffer);
            if (notify && line_length >= sizeof NOTIFICATION - 1 &&
                memcmp(*buffer, NOTIFICATION, sizeof NOTIFICATION - 1) == 0) {
                *end = 0;
                notify(*buffer, context);
                length -= line_length + 1;
                memmove(*buffer, end + 1, length);
                scanned = 0;
                if (c->timeout_ms > 0)
                    deadline = now_ms() + c->timeout_ms;
                continue;
            }
            /* One request at a time: nothing may follow the line. */
            if (end != *buffer + length - 1)
                return fail(c, WRC_EPROTO, "more than one answer line arrived");
            *end = 0;
            return WRC_OK;
        }
        scanned = length;
        if (length + 1 >= *capacity) {
            if (!grow)
                return fail(c, WRC_ETOOBIG, "the answer is longer than %zu bytes", *capacity);
            size_t bigger = *capacity * 2;
            char *grown = realloc(*buffer, bigger);
            if (!grown)
                return fail(c, WRC_ENOMEM, "out of memory reading an answer");
            *buffer = grown;
            *capacity = bigger;
        }
        ssize_t n = recv(c->fd, *buffer + length, *capacity - 1 - length, 0);
        if (n > 0) {
            length += (size_t)n;
            continue;
        }
        if (n == 0)
            return fail(c, WRC_EIO, "the daemon closed the connection");
        if (errno == EINTR)
            continue;
        if (errno == EAGAIN || errno == EWOULDBLOCK) {
            int status = wait_for(c, POLLIN, deadline);
            if (status != WRC_OK)
                return status;
            continue;
        }
        return fail(c, WRC_EIO, "recv: %s", strerror(errno));
    }
}

/* Send `line` (ending in "\n") and read the answer; reconnect once if the
 * old connection turns out dead before anything was sent.  With `notify`,
 * notifications before the answer go to it. */
static int exchange(wrc_client *c, const char *line, size_t length, char **answer,
                    size_t *capacity, bool grow, wrc_notify notify, void *context)
{
    for (int attempt = 0; attempt < 2; attempt++) {
        bool reconnected = false;
        if (c->fd < 0) {
            int status = open_connection(c);
            if (status != WRC_OK)
                return status;
            reconnected = true;
        }
        long long deadline = c->timeout_ms > 0 ? now_ms() + c->timeout_ms : -1;
        bool untouched = true;
        int status = send_all(c, line, length, deadline, &untouched);
        if (status == WRC_EIO && untouched && !reconnected) {
            disconnect(c); /* the daemon went away meanwhile: try a new connection */
            continue;
        }
        if (status == WRC_OK)
            status = read_line(c, answer, capacity, grow, deadline, notify, context);
        if (status != WRC_OK && status != WRC_ETOOBIG)
            disconnect(c); /* a late answer would be read as the next one's */
        if (status == WRC_ETOOBIG)
            disconnect(c);
        return status;
    }
    return WRC_EIO;
}

/* ---- reading answers without allocating ---------------------------------- */

/* Copy a JSON string starting after its opening quote, unescaped (\uXXXX
 * beyond ASCII becomes '?'), into out[0..size). */
static const char *copy_string(const char *p, char *out, size_t size)
{
    size_t n = 0;
    while (*p && *p != '"') {
        char ch = *p++;
        if (ch == '\\' && *p) {
            char e = *p++;
            ch = e == 'n' ? '\n' : e == 't' ? '\t' : e == 'r' ? '\r' : e == 'b' ? '\b'
                 : e == 'f' ? '\f' : e;
            if (e == 'u') {
                unsigned code = 0;
                for (int i = 0; i < 4 && *p; i++, p++)
                    code = code * 16 + (unsigned)(*p <= '9' ? *p - '0' : (*p | 32) - 'a' + 10);
                ch = code < 128 ? (char)code : '?';
            }
        }
        if (n + 1 < size)
            out[n++] = ch;
    }
    if (size)
        out[n] = 0;
    return *p == '"' ? p + 1 : p;
}

static bool read_numbers(const char *p, double *out, int n);

/* The value after "key": in text, or NULL. */
static const char *value_of(const char *text, const char *key)
{
    char pattern[40];
    snprintf(pattern, sizeof pattern, "\"%s\":", key);
    const char *p = strstr(text, pattern);
    return p ? p + strlen(pattern) : NULL;
}

/* An error answer: remember its code, field and reason. */
static bool read_server_error(wrc_client *c, const char *answer)
{
    const char *error = value_of(answer, "error");
    if (!error || *error != '{')
        return false;
    const char *code = value_of(error, "code");
    const char *field = value_of(error, "field");
    const char *reason = value_of(error, "reason");
    c->server_code = code ? (int)strtol(code, NULL, 10) : 0;
    c->server_field[0] = c->server_reason[0] = 0;
    if (field && *field == '"')
        copy_string(field + 1, c->server_field, sizeof c->server_field);
    if (reason && *reason == '"')
        copy_string(reason + 1, c->server_reason, sizeof c->server_reason);
    return true;
}

int wrc_classify(wrc_client *c, const char *fixture_id, const double wrench[3], const char *set,
                 wrc_answer *answer)
{
    if (!c || !fixture_id || !wrench || !set || !answer)
        return WRC_EINVAL;
    if (strcmp(set, "goal") != 0 && strcmp(set, "strong") != 0 && strcmp(set, "both") != 0)
        return fail(c, WRC_EINVAL, "set is \"goal\", \"strong\" or \"both\", not \"%.20s\"", set);
    for (const char *p = fixture_id; *p; p++)
        if (*p == '"' || *p == '\\' || (unsigned char)*p < 32)
            return fail(c, WRC_EINVAL, "a fixture id has no quotes, backslashes or controls");
    for (int k = 0; k < 3; k++)
        if (!isfinite(wrench[k]))
            return fail(c, WRC_EINVAL, "wrench component %d is not finite", k);
    unsigned long id = ++c->next_id;
    int length = snprintf(c->request, c->buffer_bytes,
                          "{\"jsonrpc\":\"2.0\",\"method\":\"wrench.classify\",\"params\":{"
                          "\"fixture\":\"%s\",\"wrenches\":[[%.17g,%.17g,%.17g]],"
                          "\"sets\":[\"%s\"]},\"id\":%lu}\n",
                          fixture_id, wrench[0], wrench[1], wrench[2], set, id);
    if (length < 0 || (size_t)length >= c->buffer_bytes)
        return fail(c, WRC_ETOOBIG, "the request is longer than %zu bytes", c->buffer_bytes);
    size_t capacity = c->buffer_bytes;
    int status = exchange(c, c->request, (size_t)length, &c->answer, &capacity, false, NULL, NULL);
    if (status != WRC_OK)
        return status;
    const char *text = c->answer;
    const char *answer_id = value_of(text, "id");
    if (!answer_id || strtoul(answer_id, NULL, 10) != id)
        return fail(c, WRC_EPROTO, "the answer's id is not the request's");
    if (read_server_error(c, text))
        return fail(c, WRC_ESERVER, "wrenchd: %s: %s", c->server_field, c->server_reason);
    const char *verdict = value_of(text, "verdict");
    const char *margin = value_of(text, "margin");
    const char *blocking = value_of(text, "blocking");
    if (!verdict || !margin || !blocking || *verdict != '"')
        return fail(c, WRC_EPROTO, "the answer has no verdict, margin or blocking");
    if (strncmp(verdict, "\"inside\"", 8) == 0)
        answer->verdict = WRC_INSIDE;
    else if (strncmp(verdict, "\"boundary\"", 10) == 0)
        answer->verdict = WRC_BOUNDARY;
    else if (strncmp(verdict, "\"outside\"", 9) == 0)
        answer->verdict = WRC_OUTSIDE;
    else
        return fail(c, WRC_EPROTO, "an unknown verdict");
    answer->margin = strncmp(margin, "null", 4) == 0 ? NAN : strtod(margin, NULL);
    answer->blocking[0] = 0;
    if (*blocking == '"')
        copy_string(blocking + 1, answer->blocking, sizeof answer->blocking);
    answer->perturbation_count = 0;
    const char *points = value_of(text, "perturbation");
    if (points && *points == '[') {
        /* [[x, y], ...]: each point's two numbers */
        const char *p = points + 1;
        while (*p == '[' && answer->perturbation_count < 8) {
            if (!read_numbers(p, answer->perturbation[answer->perturbation_count], 2))
                return fail(c, WRC_EPROTO, "a perturbation point is not two numbers");
            answer->perturbation_count++;
            p = strchr(p, ']');
            p = p ? p + 1 + (p[1] == ',') : "";
        }
    }
    return WRC_OK;
}

/* Reads "[[a, b], [c, d], ...]" at p into sweep's intervals; the end of the
 * array, or NULL when it is not one. */
static const char *read_intervals(const char *p, wrc_sweep *sweep)
{
    sweep->interval_count = 0;
    p += strspn(p, " ");
    if (*p++ != '[')
        return NULL;
    for (;;) {
        p += strspn(p, " ,");
        if (*p == ']')
            return p + 1;
        if (*p++ != '[')
            return NULL;
        double bounds[2];
        for (int k = 0; k < 2; k++) {
            p += strspn(p, " ,");
            char *end;
            bounds[k] = strtod(p, &end);
            if (end == p)
                return NULL;
            p = end;
        }
        p += strspn(p, " ");
        if (*p++ != ']')
            return NULL;
        if (sweep->interval_count < WRC_SWEEP_INTERVALS) {
            sweep->intervals[sweep->interval_count][0] = bounds[0];
            sweep->intervals[sweep->interval_count][1] = bounds[1];
        }
        sweep->interval_count++;
    }
}

/* Append to a request being written into q (size bytes, n used so far):
 * n counts on past the end, so that n >= size says it did not fit. */
/* The request of `n` bytes in c->request (written into `size`) sent, its
 * answer in c->answer and checked: the answer's id is its last "id" member
 * (the results' numbers come before it) and must be `id`; a server error is
 * said.  WRC_OK with *text the answer, or the failure, said. */
static int call_checked(wrc_client *c, size_t n, size_t size, unsigned long id,
                        const char **text)
{
    if (n >= size)
        return fail(c, WRC_ETOOBIG, "the request is longer than %zu bytes", c->buffer_bytes);
    size_t capacity = c->buffer_bytes;
    int status = exchange(c, c->request, n, &c->answer, &capacity, false, NULL, NULL);
    if (status != WRC_OK)
        return status;
    const char *answer_id = strstr(c->answer, "\"id\":");
    while (answer_id && strstr(answer_id + 1, "\"id\":"))
        answer_id = strstr(answer_id + 1, "\"id\":");
    if (!answer_id || strtoul(answer_id + 5, NULL, 10) != id)
        return fail(c, WRC_EPROTO, "the answer's id is not the request's");
    if (read_server_error(c, c->answer))
        return fail(c, WRC_ESERVER, "wrenchd: %s: %s", c->server_field, c->server_reason);
    *text = c->answer;
    return WRC_OK;
}

#define PUT(...)                                                                                   \
    do {                                                                                           \
        int written = snprintf(q + (n < size ? n : size), n < size ? size - n : 0, __VA_ARGS__);  \
        n += written > 0 ? (size_t)written : 0;                                                    \
    } while (0)

/* A friction.sweep request's start: the fixture, and the range and ratio
 * unless they are the defaults' zeros. */
static void put_sweep_head(char *q, size_t *at, size_t size, const char *fixture_id,
                           const double range[2], double kinetic_ratio)
{
    size_t n = *at;
    PUT("{\"jsonrpc\":\"2.0\",\"method\":\"friction.sweep\",\"params\":{\"fixture\":\"%s\"",
        fixture_id);
    if (range[0] != 0 || range[1] != 0)
        PUT(",\"range\":[%.17g,%.17g]", range[0], range[1]);
    if (kinetic_ratio != 0)
        PUT(",\"kinetic_ratio\":%.17g", kinetic_ratio);
    *at = n;
}

int wrc_friction_sweep(wrc_client *c, const char *fixture_id, const wrc_sweep_request *r,
                       wrc_sweep *sweep)
{
    if (!c || !fixture_id || !r || !r->kind || !r->set || !sweep)
        return WRC_EINVAL;
    bool push = strcmp(r->kind, "push") == 0, wrench = strcmp(r->kind, "wrench") == 0;
    if (!push && !wrench && strcmp(r->kind, "gravity") != 0)
        return fail(c, WRC_EINVAL, "kind is \"push\", \"gravity\" or \"wrench\", not \"%.20s\"",
                    r->kind);
    if (strcmp(r->set, "goal") != 0 && strcmp(r->set, "strong") != 0 &&
        strcmp(r->set, "both") != 0)
        return fail(c, WRC_EINVAL, "set is \"goal\", \"strong\" or \"both\", not \"%.20s\"",
                    r->set);
    for (const char *p = fixture_id; *p; p++)
        if (*p == '"' || *p == '\\' || (unsigned char)*p < 32)
            return fail(c, WRC_EINVAL, "a fixture id has no quotes, backslashes or controls");
    const double numbers[] = {r->wrench[0], r->wrench[1], r->wrench[2], r->range[0],
                              r->range[1], r->kinetic_ratio, r->finger_friction,
                              r->finger_radius};
    for (size_t k = 0; k < sizeof numbers / sizeof numbers[0]; k++)
        if (!isfinite(numbers[k]))
            return fail(c, WRC_EINVAL, "a number of the request is not finite");
    unsigned long id = ++c->next_id;
    size_t n = 0, size = c->buffer_bytes;
    char *q = c->request;
    put_sweep_head(q, &n, size, fixture_id, r->range, r->kinetic_ratio);
    if (wrench) {
        PUT(",\"wrenches\":[[%.17g,%.17g,%.17g]],\"sets\":[\"%s\"]", r->wrench[0], r->wrench[1],
            r->wrench[2], r->set);
    } else {
        PUT(",\"%s\":{\"set\":\"%s\"", r->kind, r->set);
        if (push && r->finger_friction != 0)
            PUT(",\"finger_friction\":%.17g", r->finger_friction);
        if (push && r->finger_radius != 0)
            PUT(",\"finger_radius\":%.17g", r->finger_radius);
        PUT("}");
    }
    PUT("},\"id\":%lu}\n", id);
    const char *text;
    int status = call_checked(c, n, size, id, &text);
    if (status != WRC_OK)
        return status;
    sweep->critical = NAN;
    const char *intervals = value_of(text, wrench ? r->set : "intervals");
    if (!intervals || !read_intervals(intervals, sweep))
        return fail(c, WRC_EPROTO, "the answer has no intervals");
    if (!wrench) {
        const char *critical = value_of(text, "critical");
        if (!critical)
            return fail(c, WRC_EPROTO, "the answer has no critical mu");
        if (strncmp(critical, "null", 4) != 0)
            sweep->critical = strtod(critical, NULL);
    }
    return WRC_OK;
}

/* n numbers of a JSON array at p ("[a,b,...]"); false if it is not one. */
static bool read_numbers(const char *p, double *out, int n)
{
    if (!p || *p != '[')
        return false;
    p++;
    for (int i = 0; i < n; i++) {
        char *end;
        out[i] = strtod(p, &end);
        if (end == p)
            return false;
        p = end + 1;
    }
    return true;
}

int wrc_locating_get(wrc_client *c, const char *fixture_id, const double *tolerance,
                     int tolerance_count, double sigma_ratio, wrc_locate_feature *features,
                     int feature_count, wrc_locating *out)
{
    if (!c || !fixture_id || !tolerance || tolerance_count < 1 || tolerance_count > 8 || !out ||
        feature_count < 0 || feature_count > WRC_LOCATE_FEATURES ||
        (feature_count > 0 && !features))
        return WRC_EINVAL;
    for (const char *p = fixture_id; *p; p++)
        if (*p == '"' || *p == '\\' || (unsigned char)*p < 32)
            return fail(c, WRC_EINVAL, "a fixture id has no quotes, backslashes or controls");
    bool finite = isfinite(sigma_ratio);
    for (int i = 0; i < tolerance_count; i++)
        finite = finite && isfinite(tolerance[i]);
    for (int i = 0; i < feature_count; i++)
        finite = finite && isfinite(features[i].at[0]) && isfinite(features[i].at[1]);
    if (!finite)
        return fail(c, WRC_EINVAL, "a number of the request is not finite");
    unsigned long id = ++c->next_id;
    size_t n = 0, size = c->buffer_bytes;
    char *q = c->request;
    PUT("{\"jsonrpc\":\"2.0\",\"method\":\"fixture.locating\",\"params\":{\"fixture\":\"%s\","
        "\"tolerance\":", fixture_id);
    if (tolerance_count == 1)
        PUT("%.17g", tolerance[0]);
    for (int i = 0; tolerance_count > 1 && i < tolerance_count; i++)
        PUT("%s%.17g%s", i ? "," : "[", tolerance[i], i + 1 == tolerance_count ? "]" : "");
    if (sigma_ratio != 0)
        PUT(",\"sigma_ratio\":%.17g", sigma_ratio);
    PUT(",\"features\":[");
    for (int i = 0; i < feature_count; i++)
        PUT("%s{\"at\":[%.17g,%.17g]}", i ? "," : "", features[i].at[0], features[i].at[1]);
    PUT("]},\"id\":%lu}\n", id);
    const char *text;
    int status = call_checked(c, n, size, id, &text);
    if (status != WRC_OK)
        return status;
    /* The result's members in the order the daemon writes them
     * (docs/PROTOCOL.md): each looked for after the one before. */
    memset(out, 0, sizeof *out);
    const char *p = value_of(text, "deterministic");
    if (!p)
        return fail(c, WRC_EPROTO, "the answer has no \"deterministic\"");
    out->deterministic = strncmp(p, "true", 4) == 0;
    if (!out->deterministic) {
        if (!read_numbers(value_of(p, "twist"), out->twist, 3))
            return fail(c, WRC_EPROTO, "the answer has no free motion");
        return WRC_OK;
    }
    const char *condition = value_of(p, "condition");
    const char *linear = condition ? value_of(condition, "linear") : NULL;
    const char *exact = linear ? value_of(linear, "exact") : NULL;
    if (!exact || !read_numbers(linear, out->pose_linear, 3) ||
        !read_numbers(exact, out->pose_exact, 3))
        return fail(c, WRC_EPROTO, "the answer has no pose error");
    out->condition = strtod(condition, NULL);
    p = value_of(exact, "features");
    for (int i = 0; i < feature_count; i++) {
        wrc_locate_feature *f = &features[i];
        const char *l = p ? value_of(p, "linear") : NULL;
        const char *ll = l ? value_of(l, "length") : NULL;
        const char *e = ll ? value_of(ll, "exact") : NULL;
        const char *el = e ? value_of(e, "length") : NULL;
        const char *axes = el ? value_of(el, "axes") : NULL;
        const char *angle = axes ? value_of(axes, "angle_deg") : NULL;
        if (!angle || !read_numbers(axes, f->axes, 2))
            return fail(c, WRC_EPROTO, "the answer has no feature %d", i + 1);
        f->linear = strtod(ll, NULL);
        f->exact = strtod(el, NULL);
        f->angle_deg = strtod(angle, NULL);
        p = angle;
    }
    return WRC_OK;
}

/* "[[a, b], [c, null], ...]" at p into force's intervals (null: INFINITY). */
static bool read_force_intervals(const char *p, wrc_force *force)
{
    force->interval_count = 0;
    p += strspn(p, " ");
    if (*p++ != '[')
        return false;
    for (;;) {
        p += strspn(p, " ,");
        if (*p == ']')
            return true;
        if (*p++ != '[')
            return false;
        double bounds[2];
        for (int k = 0; k < 2; k++) {
            p += strspn(p, " ,");
            if (k == 1 && strncmp(p, "null", 4) == 0) {
                bounds[k] = INFINITY;
                p += 4;
                continue;
            }
            char *end;
            bounds[k] = strtod(p, &end);
            if (end == p)
                return false;
            p = end;
        }
        p += strspn(p, " ");
        if (*p++ != ']')
            return false;
        if (force->interval_count < WRC_SWEEP_INTERVALS) {
            force->intervals[force->interval_count][0] = bounds[0];
            force->intervals[force->interval_count][1] = bounds[1];
        }
        force->interval_count++;
    }
}

/* The checks every force call makes of its arguments: WRC_OK or WRC_EINVAL
 * (said why). */
static int check_force_call(wrc_client *c, const char *fixture_id, const wrc_load *loads,
                            int count, const char *set)
{
    if (strcmp(set, "goal") != 0 && strcmp(set, "strong") != 0 && strcmp(set, "both") != 0)
        return fail(c, WRC_EINVAL, "set is \"goal\", \"strong\" or \"both\", not \"%.20s\"", set);
    for (const char *p = fixture_id; *p; p++)
        if (*p == '"' || *p == '\\' || (unsigned char)*p < 32)
            return fail(c, WRC_EINVAL, "a fixture id has no quotes, backslashes or controls");
    for (int i = 0; i < count; i++) {
        const wrc_load *l = &loads[i];
        const double values[] = {l->g, l->direction_deg, l->force[0], l->force[1], l->at[0],
                                 l->at[1], l->wrench[0], l->wrench[1], l->wrench[2]};
        for (size_t k = 0; k < sizeof values / sizeof values[0]; k++)
            if (!isfinite(values[k]))
                return fail(c, WRC_EINVAL, "load %d has a number that is not finite", i);
        if (l->kind != WRC_LOAD_GRAVITY && l->kind != WRC_LOAD_FORCE && l->kind != WRC_LOAD_WRENCH)
            return fail(c, WRC_EINVAL, "load %d: kind is WRC_LOAD_GRAVITY, _FORCE or _WRENCH", i);
    }
    return WRC_OK;
}

/* One case of `count` loads, {"loads": [...]}, appended at q + *n (checked
 * by check_force_call). */
/* A finger (push.force, friction.sweep's force): its radius and the loops
 * it pushes on. */
static int check_finger(wrc_client *c, double finger_radius, const char *push_on)
{
    if (!(finger_radius >= 0) || !isfinite(finger_radius))
        return fail(c, WRC_EINVAL, "the finger's radius is a finite number >= 0");
    if (push_on && strcmp(push_on, "outer") != 0 && strcmp(push_on, "all") != 0)
        return fail(c, WRC_EINVAL, "push_on is \"outer\", \"all\" or NULL, not \"%.20s\"",
                    push_on);
    return WRC_OK;
}

static void put_case(char *q, size_t *at, size_t size, const wrc_load *loads, int count)
{
    size_t n = *at;
    PUT("{\"loads\":[");
    for (int i = 0; i < count; i++) {
        const wrc_load *l = &loads[i];
        if (l->kind == WRC_LOAD_GRAVITY)
            PUT("%s{\"gravity\":{\"g\":%.17g,\"direction_deg\":%.17g}}", i ? "," : "", l->g,
                l->direction_deg);
        else if (l->kind == WRC_LOAD_FORCE)
            PUT("%s{\"force\":[%.17g,%.17g],\"at\":[%.17g,%.17g]}", i ? "," : "", l->force[0],
                l->force[1], l->at[0], l->at[1]);
        else
            PUT("%s{\"wrench\":[%.17g,%.17g,%.17g]}", i ? "," : "", l->wrench[0], l->wrench[1],
                l->wrench[2]);
    }
    PUT("]}");
    *at = n;
}

int wrc_force_range(wrc_client *c, const char *fixture_id, const double at[2],
                    const wrc_load *loads, int count, const char *set, wrc_force *force)
{
    if (!c || !fixture_id || !at || !loads || !set || !force || count < 1 || count > 100)
        return WRC_EINVAL;
    int checked = check_force_call(c, fixture_id, loads, count, set);
    if (checked != WRC_OK)
        return checked;
    if (!isfinite(at[0]) || !isfinite(at[1]))
        return fail(c, WRC_EINVAL, "the push's point is not finite");
    unsigned long id = ++c->next_id;
    size_t n = 0, size = c->buffer_bytes;
    char *q = c->request;
    PUT("{\"jsonrpc\":\"2.0\",\"method\":\"force.range\",\"params\":{\"fixture\":\"%s\","
        "\"push\":{\"at\":[%.17g,%.17g]},\"sets\":[\"%s\"],\"cases\":[",
        fixture_id, at[0], at[1], set);
    put_case(q, &n, size, loads, count);
    PUT("]},\"id\":%lu}\n", id);
    const char *text;
    int status = call_checked(c, n, size, id, &text);
    if (status != WRC_OK)
        return status;
    /* "all" comes after the cases: its set's intervals and least. */
    const char *all = value_of(text, "all");
    const char *intervals = all ? value_of(all, "intervals") : NULL;
    const char *least = all ? value_of(all, "least") : NULL;
    if (!intervals || !least || !read_force_intervals(intervals, force))
        return fail(c, WRC_EPROTO, "the answer has no intervals for all the cases");
    force->least = strncmp(least, "null", 4) == 0 ? NAN : strtod(least, NULL);
    return WRC_OK;
}

int wrc_push_force(wrc_client *c, const char *fixture_id, const wrc_load *loads, int count,
                   const char *set, double finger_radius, const char *push_on,
                   wrc_least_push *least)
{
    if (!c || !fixture_id || !loads || !set || !least || count < 1 || count > 100)
        return WRC_EINVAL;
    int checked = check_force_call(c, fixture_id, loads, count, set);
    if (checked != WRC_OK)
        return checked;
    checked = check_finger(c, finger_radius, push_on);
    if (checked != WRC_OK)
        return checked;
    unsigned long id = ++c->next_id;
    size_t n = 0, size = c->buffer_bytes;
    char *q = c->request;
    PUT("{\"jsonrpc\":\"2.0\",\"method\":\"push.force\",\"params\":{\"fixture\":\"%s\","
        "\"set\":\"%s\",\"samples\":1,\"finger_radius\":%.17g,",
        fixture_id, set, finger_radius);
    if (push_on)
        PUT("\"push_on\":\"%s\",", push_on);
    PUT("\"cases\":[");
    put_case(q, &n, size, loads, count);
    PUT("]},\"id\":%lu}\n", id);
    const char *text;
    int status = call_checked(c, n, size, id, &text);
    if (status != WRC_OK)
        return status;
    memset(least, 0, sizeof *least);
    const char *best = value_of(text, "least");
    if (!best)
        return fail(c, WRC_EPROTO, "the answer has no least push");
    if (strncmp(best, "null", 4) == 0)
        return WRC_OK;
    const char *at = value_of(best, "at"), *direction = value_of(best, "direction");
    const char *force = value_of(best, "force"), *lower = value_of(best, "lower_bound");
    const char *converged = value_of(best, "converged");
    if (!at || !direction || !force || !lower || !converged ||
        !read_numbers(at, least->at, 2) || !read_numbers(direction, least->direction, 2))
        return fail(c, WRC_EPROTO, "the least push lacks at, direction, force or lower_bound");
    least->found = 1;
    least->force = strtod(force, NULL);
    least->lower_bound = strtod(lower, NULL);
    least->converged = strncmp(converged, "true", 4) == 0;
    return WRC_OK;
}

/* Reads "[[a, b], null, ...]" at p, a or b a number or null (NAN), a null
 * item both NAN: the first `capacity` pairs into out (out may be NULL),
 * their count into *count; the end of the array, or NULL when it is not
 * one. */
static const char *read_pairs(const char *p, double (*out)[2], int capacity, int *count)
{
    *count = 0;
    p += strspn(p, " ");
    if (*p++ != '[')
        return NULL;
    for (;;) {
        p += strspn(p, " ,");
        if (*p == ']')
            return p + 1;
        double pair[2] = {NAN, NAN};
        if (strncmp(p, "null", 4) == 0) {
            p += 4;
        } else {
            if (*p++ != '[')
                return NULL;
            for (int k = 0; k < 2; k++) {
                p += strspn(p, " ,");
                char *end;
                if (strncmp(p, "null", 4) == 0) {
                    p += 4;
                    continue;
                }
                pair[k] = strtod(p, &end);
                if (end == p)
                    return NULL;
                p = end;
            }
            p += strspn(p, " ");
            if (*p++ != ']')
                return NULL;
        }
        if (out && *count < capacity) {
            out[*count][0] = pair[0];
            out[*count][1] = pair[1];
        }
        (*count)++;
    }
}

int wrc_force_sweep(wrc_client *c, const char *fixture_id, const wrc_load *loads, int count,
                    const wrc_force_sweep_request *r, double (*curve)[2], double (*at)[2],
                    int capacity, wrc_force_curve *sweep)
{
    if (!c || !fixture_id || !loads || !r || !r->set || !curve || capacity < 0 || !sweep ||
        count < 1 || count > 100)
        return WRC_EINVAL;
    int checked = check_force_call(c, fixture_id, loads, count, r->set);
    if (checked != WRC_OK)
        return checked;
    const double numbers[] = {r->range[0], r->range[1], r->kinetic_ratio, r->finger_radius};
    for (size_t k = 0; k < sizeof numbers / sizeof numbers[0]; k++)
        if (!isfinite(numbers[k]))
            return fail(c, WRC_EINVAL, "a number of the request is not finite");
    checked = check_finger(c, r->finger_radius, r->push_on);
    if (checked != WRC_OK)
        return checked;
    unsigned long id = ++c->next_id;
    size_t n = 0, size = c->buffer_bytes;
    char *q = c->request;
    put_sweep_head(q, &n, size, fixture_id, r->range, r->kinetic_ratio);
    if (r->over_supports)
        PUT(",\"over\":\"supports\"");
    PUT(",\"force\":{\"set\":\"%s\"", r->set);
    if (r->finger_radius != 0)
        PUT(",\"finger_radius\":%.17g", r->finger_radius);
    if (r->push_on)
        PUT(",\"push_on\":\"%s\"", r->push_on);
    PUT("},\"cases\":[");
    put_case(q, &n, size, loads, count);
    PUT("]},\"id\":%lu}\n", id);
    const char *text;
    int status = call_checked(c, n, size, id, &text);
    if (status != WRC_OK)
        return status;
    memset(sweep, 0, sizeof *sweep);
    const char *samples = value_of(text, "curve"), *end = NULL, *points = NULL;
    const char *intervals = value_of(text, "intervals");
    int located = 0;
    wrc_sweep alone;
    if (samples)
        end = read_pairs(samples, curve, capacity, &sweep->sample_count);
    if (end)
        points = value_of(end, "at");
    /* On supports (over either friction) the answer has no intervals of
     * the push alone. */
    if (!end || !points || !read_pairs(points, at, capacity, &located) ||
        located != sweep->sample_count ||
        (intervals && !read_intervals(intervals, &alone)))
        return fail(c, WRC_EPROTO, "the answer has no curve or points, or bad intervals");
    if (!intervals)
        return WRC_OK;
    sweep->interval_count = alone.interval_count;
    memcpy(sweep->intervals, alone.intervals, sizeof sweep->intervals);
    return WRC_OK;
}

int wrc_call(wrc_client *c, const char *request, char **answer)
{
    return wrc_call_notified(c, request, answer, NULL, NULL);
}

int wrc_call_notified(wrc_client *c, const char *request, char **answer, wrc_notify notify,
                      void *context)
{
    if (!c || !request || !answer)
        return WRC_EINVAL;
    *answer = NULL;
    size_t length = strlen(request);
    if (memchr(request, '\n', length))
        return fail(c, WRC_EINVAL, "a request is one line: it has no newline");
    char *line = malloc(length + 2);
    size_t capacity = 4096;
    char *buffer = malloc(capacity);
    if (!line || !buffer) {
        free(line);
        free(buffer);
        return fail(c, WRC_ENOMEM, "out of memory");
    }
    memcpy(line, request, length);
    line[length] = '\n';
    line[length + 1] = 0;
    int status = exchange(c, line, length + 1, &buffer, &capacity, true, notify, context);
    free(line);
    if (status != WRC_OK) {
        free(buffer);
        return status;
    }
    *answer = buffer;
    if (buffer[0] == '{' && read_server_error(c, buffer))
        return WRC_ESERVER;
    return WRC_OK;
}
