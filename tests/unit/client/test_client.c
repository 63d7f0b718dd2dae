/* test_client.c -- libwrenchclient against a fake daemon in a thread, which
 * answers each request line with the next canned line (or stays silent, or
 * hangs up), so every path of the client is reached without wrenchd.
 * Linked with -Wl,--wrap=malloc,--wrap=realloc,--wrap=calloc to count heap
 * allocations. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include "wrenchclient.h"

#include <errno.h>
#include <math.h>
#include <pthread.h>
#include <stdatomic.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <sys/un.h>
#include <unistd.h>

/* ---- counting allocations --------------------------------------------------- */

void *__real_malloc(size_t size);
void *__real_realloc(void *p, size_t size);
void *__real_calloc(size_t n, size_t size);
static atomic_long allocations;
void *__wrap_malloc(size_t size)
{
    atomic_fetch_add(&allocations, 1);
    return __real_malloc(size);
}
void *__wrap_realloc(void *p, size_t size)
{
    atomic_fetch_add(&allocations, 1);
    return __real_realloc(p, size);
}
void *__wrap_calloc(size_t n, size_t size)
{
    atomic_fetch_add(&allocations, 1);
    return __real_calloc(n, size);
}

/* ---- the fake daemon ---------------------------------------------------------- */

#define SILENT "<silent>"  /* read the request, answer nothing */
#define HANG_UP "<hang up>" /* read the request, close the connection */

typedef struct fake {
    char path[108];
    int listener;
    const char *const *answers; /* one per request, NULL-ended */
    char last_request[4096];
    int requests, connections;
    pthread_t thread;
} fake;

/* Answer a request with the id it carried: "%ID%" in a canned line. */
static void answer(int fd, const char *request, const char *canned)
{
    const char *id = strstr(request, "\"id\":");
    long number = id ? strtol(id + 5, NULL, 10) : 0;
    char line[4096];
    const char *mark = strstr(canned, "%ID%");
    if (mark)
        snprintf(line, sizeof line, "%.*s%ld%s\n", (int)(mark - canned), canned, number,
                 mark + 4);
    else
        snprintf(line, sizeof line, "%s\n", canned);
    ssize_t sent = send(fd, line, strlen(line), MSG_NOSIGNAL);
    (void)sent;
}

static void *serve(void *argument)
{
    fake *f = argument;
    int next = 0;
    while (f->answers[next]) {
        int fd = accept(f->listener, NULL, NULL);
        if (fd < 0)
            break;
        f->connections++;
        char buffer[4096];
        size_t length = 0;
        bool open = true;
        while (open && f->answers[next]) {
            ssize_t n = recv(fd, buffer + length, sizeof buffer - 1 - length, 0);
            if (n <= 0)
                break;
            length += (size_t)n;
            buffer[length] = 0;
            char *end;
            while (open && (end = strchr(buffer, '\n')) && f->answers[next]) {
                *end = 0;
                snprintf(f->last_request, sizeof f->last_request, "%s", buffer);
                f->requests++;
                const char *canned = f->answers[next++];
                if (strcmp(canned, HANG_UP) == 0)
                    open = false;
                else if (strcmp(canned, SILENT) != 0)
                    answer(fd, buffer, canned);
                length -= (size_t)(end + 1 - buffer);
                memmove(buffer, end + 1, length + 1);
            }
        }
        close(fd);
    }
    return NULL;
}

static void start(fake *f, const char *const *answers)
{
    memset(f, 0, sizeof *f);
    snprintf(f->path, sizeof f->path, "/tmp/wrc-test-%d.sock", (int)getpid());
    unlink(f->path);
    f->answers = answers;
    f->listener = socket(AF_UNIX, SOCK_STREAM, 0);
    struct sockaddr_un address = {.sun_family = AF_UNIX};
    strcpy(address.sun_path, f->path);
    assert_int_equal(bind(f->listener, (struct sockaddr *)&address, sizeof address), 0);
    assert_int_equal(listen(f->listener, 4), 0);
    pthread_create(&f->thread, NULL, serve, f);
}

static void stop(fake *f)
{
    shutdown(f->listener, SHUT_RDWR);
    close(f->listener);
    pthread_join(f->thread, NULL);
    unlink(f->path);
}

static const char INSIDE[] =
    "{\"jsonrpc\":\"2.0\",\"result\":{\"results\":[{\"goal\":{\"verdict\":\"inside\",\"inside\":"
    "true,\"margin\":0.3162277660168377,\"blocking\":null,\"states\":[],\"witness\":null}}]},"
    "\"id\":%ID%}";
static const char OUTSIDE[] =
    "{\"jsonrpc\":\"2.0\",\"result\":{\"results\":[{\"strong\":{\"verdict\":\"outside\",\"inside\":"
    "false,\"margin\":-0.003162,\"blocking\":\"ll\",\"states\":[],\"witness\":{\"acceleration\":"
    "[0,0,1],\"forces\":[[1,0],[1,0]],\"wrench\":[1,2,3]}}}]},\"id\":%ID%}";
/* A fixture with a tolerance: the witness's contacts and normals follow
 * the answer's other members (docs/PROTOCOL.md, "Tolerance"). */
static const char ROBUST_OUTSIDE[] =
    "{\"jsonrpc\":\"2.0\",\"result\":{\"results\":[{\"goal\":{\"verdict\":\"outside\",\"inside\":"
    "false,\"margin\":-0.25,\"blocking\":\"msm\",\"states\":[\"101\"],\"witness\":null,"
    "\"perturbation\":[[1.05,0],[2.9,0],[0,1.1]],\"perturbation_normals\":[[0,1],[0,1],[1,0]]}}]},"
    "\"id\":%ID%}";
static const char NO_FIXTURE[] =
    "{\"jsonrpc\":\"2.0\",\"error\":{\"code\":-32001,\"message\":\"No such fixture\",\"data\":"
    "{\"field\":\"params.fixture\",\"reason\":\"no stored fixture has the id \\\"x\\\"\"}},"
    "\"id\":%ID%}";
static const char WRONG_ID[] =
    "{\"jsonrpc\":\"2.0\",\"result\":{\"results\":[{\"goal\":{\"verdict\":\"inside\",\"inside\":"
    "true,\"margin\":0.5,\"blocking\":null}}]},\"id\":999999}";

static const double G[3] = {-1, -1, 0};
static const char ID[] = "e0d7a1a0bd6e8bf16fe5845da1960ed9";

static void classify_reads_verdicts_without_allocating(void **state)
{
    (void)state;
    const char *const answers[] = {INSIDE, OUTSIDE, INSIDE, OUTSIDE, NULL};
    fake f;
    start(&f, answers);
    int error;
    long at_start = atomic_load(&allocations);
    wrc_client *c = wrc_connect(f.path, 2000, 0, &error);
    assert_non_null(c);
    /* The wrapping counts: connecting allocates the client and buffers. */
    assert_true(atomic_load(&allocations) - at_start >= 3);
    wrc_answer a;
    long before = atomic_load(&allocations);
    for (int i = 0; i < 2; i++) {
        assert_int_equal(wrc_classify(c, ID, G, "goal", &a), WRC_OK);
        assert_int_equal(a.verdict, WRC_INSIDE);
        assert_true(fabs(a.margin - 0.3162277660168377) < 1e-16);
        assert_string_equal(a.blocking, "");
        assert_int_equal(wrc_classify(c, ID, G, "strong", &a), WRC_OK);
        assert_int_equal(a.verdict, WRC_OUTSIDE);
        assert_true(fabs(a.margin + 0.003162) < 1e-16);
        assert_string_equal(a.blocking, "ll");
    }
    assert_int_equal(atomic_load(&allocations) - before, 0);
    /* The request carried the fixture, the wrench and the set. */
    assert_non_null(strstr(f.last_request, ID));
    assert_non_null(strstr(f.last_request, "[[-1,-1,0]]"));
    assert_non_null(strstr(f.last_request, "\"sets\":[\"strong\"]"));
    assert_int_equal(f.connections, 1);
    wrc_close(c);
    stop(&f);
}

static void classify_reads_a_robust_witness(void **state)
{
    (void)state;
    const char *const answers[] = {ROBUST_OUTSIDE, INSIDE, NULL};
    fake f;
    start(&f, answers);
    wrc_client *c = wrc_connect(f.path, 2000, 0, NULL);
    assert_non_null(c);
    wrc_answer a;
    assert_int_equal(wrc_classify(c, ID, G, "goal", &a), WRC_OK);
    assert_int_equal(a.verdict, WRC_OUTSIDE);
    assert_int_equal(a.perturbation_count, 3);
    const double expect[3][2] = {{1.05, 0}, {2.9, 0}, {0, 1.1}};
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 2; j++)
            assert_true(a.perturbation[i][j] == expect[i][j]);
    assert_int_equal(wrc_classify(c, ID, G, "goal", &a), WRC_OK);
    assert_int_equal(a.perturbation_count, 0);
    wrc_close(c);
    stop(&f);
}

static void server_errors_carry_code_field_and_reason(void **state)
{
    (void)state;
    const char *const answers[] = {NO_FIXTURE, NO_FIXTURE, NULL};
    fake f;
    start(&f, answers);
    wrc_client *c = wrc_connect(f.path, 2000, 0, NULL);
    wrc_answer a;
    assert_int_equal(wrc_classify(c, ID, G, "goal", &a), WRC_ESERVER);
    int code;
    const char *field, *reason;
    wrc_server_error(c, &code, &field, &reason);
    assert_int_equal(code, -32001);
    assert_string_equal(field, "params.fixture");
    assert_string_equal(reason, "no stored fixture has the id \"x\"");
    char *text = NULL;
    assert_int_equal(wrc_call(c, "{\"jsonrpc\":\"2.0\",\"method\":\"fixture.get\",\"id\":2}", &text),
                     WRC_ESERVER);
    assert_non_null(text); /* the whole answer is given back too */
    free(text);
    wrc_close(c);
    stop(&f);
}

static void bad_arguments_and_bad_answers(void **state)
{
    (void)state;
    const char *const answers[] = {WRONG_ID, "not json at all", NULL};
    fake f;
    start(&f, answers);
    wrc_client *c = wrc_connect(f.path, 2000, 0, NULL);
    wrc_answer a;
    double bad[3] = {0, NAN, 0};
    assert_int_equal(wrc_classify(c, ID, bad, "goal", &a), WRC_EINVAL);
    assert_int_equal(wrc_classify(c, ID, G, "nope", &a), WRC_EINVAL);
    assert_int_equal(wrc_classify(c, "a\"b", G, "goal", &a), WRC_EINVAL);
    assert_int_equal(f.requests, 0); /* refused before sending */
    assert_int_equal(wrc_classify(c, ID, G, "goal", &a), WRC_EPROTO);
    assert_int_equal(wrc_classify(c, ID, G, "goal", &a), WRC_EPROTO);
    char *text;
    assert_int_equal(wrc_call(c, "two\nlines", &text), WRC_EINVAL);
    wrc_close(c);
    stop(&f);
    int error;
    assert_null(wrc_connect("/nonexistent/wrenchd.sock", 100, 0, &error));
    assert_int_equal(error, WRC_ECONNECT);
    assert_string_equal(wrc_strerror(WRC_ETIMEOUT), "wrenchd did not answer in time");
}

/* A failed connect names its cause, not "is wrenchd running?" for all:
 * errno after wrc_connect, and wrc_connect_reason's words for it. */
static void connect_failures_name_their_cause(void **state)
{
    (void)state;
    int error;
    errno = 0;
    assert_null(wrc_connect("/nonexistent/wrenchd.sock", 100, 0, &error));
    assert_int_equal(error, WRC_ECONNECT);
    assert_int_equal(errno, ENOENT);
    char reason[256];
    wrc_connect_reason("/nonexistent/wrenchd.sock", ENOENT, reason, sizeof reason);
    assert_string_equal(reason, "no socket at /nonexistent/wrenchd.sock: is wrenchd running?");
    wrc_connect_reason("/run/w.sock", EACCES, reason, sizeof reason);
    assert_string_equal(reason, "permission denied on /run/w.sock");
    wrc_connect_reason("/run/w.sock", ECONNREFUSED, reason, sizeof reason);
    assert_string_equal(reason,
                        "connection refused at /run/w.sock: a stale socket, wrenchd is not running");
    wrc_connect_reason("/run/w.sock", ENOTDIR, reason, sizeof reason);
    assert_string_equal(reason, "/run/w.sock: Not a directory");
    /* A socket file nobody listens on: refused, and said so. */
    char path[] = "/tmp/wrc-stale-XXXXXX";
    assert_non_null(mkdtemp(path));
    char socket_path[64];
    snprintf(socket_path, sizeof socket_path, "%s/s.sock", path);
    int fd = socket(AF_UNIX, SOCK_STREAM, 0);
    struct sockaddr_un address = {.sun_family = AF_UNIX};
    snprintf(address.sun_path, sizeof address.sun_path, "%s", socket_path);
    assert_int_equal(bind(fd, (struct sockaddr *)&address, sizeof address), 0);
    close(fd); /* never listened: connecting is refused */
    errno = 0;
    assert_null(wrc_connect(socket_path, 100, 0, &error));
    assert_int_equal(error, WRC_ECONNECT);
    assert_int_equal(errno, ECONNREFUSED);
    unlink(socket_path);
    rmdir(path);
}

static void a_silent_daemon_times_out(void **state)
{
    (void)state;
    const char *const answers[] = {SILENT, INSIDE, NULL};
    fake f;
    start(&f, answers);
    wrc_client *c = wrc_connect(f.path, 200, 0, NULL);
    wrc_answer a;
    assert_int_equal(wrc_classify(c, ID, G, "goal", &a), WRC_ETIMEOUT);
    /* The timed-out connection is closed; the next call opens a new one. */
    assert_int_equal(wrc_classify(c, ID, G, "goal", &a), WRC_OK);
    assert_int_equal(f.connections, 2);
    wrc_close(c);
    stop(&f);
}

static void a_dropped_connection_is_reopened(void **state)
{
    (void)state;
    const char *const answers[] = {HANG_UP, INSIDE, NULL};
    fake f;
    start(&f, answers);
    wrc_client *c = wrc_connect(f.path, 2000, 0, NULL);
    wrc_answer a;
    /* The request was read, then the daemon hung up: the client cannot tell
     * whether it ran, so it reports the break rather than sending it twice. */
    assert_int_equal(wrc_classify(c, ID, G, "goal", &a), WRC_EIO);
    assert_int_equal(wrc_classify(c, ID, G, "goal", &a), WRC_OK);
    assert_int_equal(a.verdict, WRC_INSIDE);
    assert_int_equal(f.connections, 2);
    wrc_close(c);
    stop(&f);
}

static void a_small_buffer_refuses_a_big_answer(void **state)
{
    (void)state;
    const char *const answers[] = {OUTSIDE, INSIDE, NULL};
    fake f;
    start(&f, answers);
    wrc_client *c = wrc_connect(f.path, 2000, 512, NULL); /* the smallest buffer */
    wrc_answer a;
    /* The answer (about 300 bytes) fits; a request of 700 does not. */
    assert_int_equal(wrc_classify(c, ID, G, "strong", &a), WRC_OK);
    char long_id[700];
    memset(long_id, 'a', sizeof long_id - 1);
    long_id[sizeof long_id - 1] = 0;
    assert_int_equal(wrc_classify(c, long_id, G, "goal", &a), WRC_ETOOBIG);
    wrc_close(c);
    stop(&f);
}

static const char SWEEP_PUSH[] =
    "{\"jsonrpc\":\"2.0\",\"result\":{\"intervals\":[[0,0.25],[0.5,1]],\"critical\":1,"
    "\"curve\":[[0,1.5],[0.25,0],[0.5,0.5],[1,0],[2,0]],\"exact\":true,\"resolution\":0},"
    "\"id\":%ID%}";
static const char SWEEP_GRAVITY[] =
    "{\"jsonrpc\":\"2.0\",\"result\":{\"intervals\":[[0.1,2]],\"critical\":null,"
    "\"curve\":[[0.1,0],[2,33.5]]},\"id\":%ID%}";
static const char SWEEP_WRENCH[] =
    "{\"jsonrpc\":\"2.0\",\"result\":{\"results\":[{\"strong\":[[0,0.5],[1.25,2]]}]},"
    "\"id\":%ID%}";
static const char NO_METHOD[] =
    "{\"jsonrpc\":\"2.0\",\"error\":{\"code\":-32601,\"message\":\"Method not found\","
    "\"data\":{\"field\":\"method\",\"reason\":\"no method friction.sweep\"}},\"id\":%ID%}";

static void friction_sweep_reads_intervals_without_allocating(void **state)
{
    (void)state;
    const char *const answers[] = {SWEEP_PUSH, SWEEP_GRAVITY, SWEEP_WRENCH, NO_METHOD, NULL};
    fake f;
    start(&f, answers);
    wrc_client *c = wrc_connect(f.path, 2000, 0, NULL);
    assert_non_null(c);
    wrc_sweep sweep;
    long before = atomic_load(&allocations);
    wrc_sweep_request push = {.kind = "push", .set = "goal", .finger_radius = 0.5};
    assert_int_equal(wrc_friction_sweep(c, ID, &push, &sweep), WRC_OK);
    assert_int_equal(sweep.interval_count, 2);
    assert_true(sweep.intervals[0][0] == 0 && sweep.intervals[0][1] == 0.25);
    assert_true(sweep.intervals[1][0] == 0.5 && sweep.intervals[1][1] == 1);
    assert_true(sweep.critical == 1);
    /* The defaults are left to the daemon; the finger is the push's. */
    assert_non_null(strstr(f.last_request, "\"method\":\"friction.sweep\""));
    assert_non_null(strstr(f.last_request, "\"push\":{\"set\":\"goal\",\"finger_radius\":0.5}"));
    assert_null(strstr(f.last_request, "range"));
    assert_null(strstr(f.last_request, "kinetic_ratio"));
    wrc_sweep_request gravity = {.kind = "gravity", .set = "both", .range = {0.1, 2},
                                 .kinetic_ratio = 0.5};
    assert_int_equal(wrc_friction_sweep(c, ID, &gravity, &sweep), WRC_OK);
    assert_int_equal(sweep.interval_count, 1);
    assert_true(sweep.intervals[0][0] == 0.1 && sweep.intervals[0][1] == 2);
    assert_true(isnan(sweep.critical)); /* not empty at the top of the range */
    assert_non_null(strstr(f.last_request, "\"range\":[0.10000000000000001,2]"));
    assert_non_null(strstr(f.last_request, "\"kinetic_ratio\":0.5"));
    assert_non_null(strstr(f.last_request, "\"gravity\":{\"set\":\"both\"}"));
    wrc_sweep_request wrench = {.kind = "wrench", .set = "strong", .wrench = {-1, -1, 0}};
    assert_int_equal(wrc_friction_sweep(c, ID, &wrench, &sweep), WRC_OK);
    assert_int_equal(sweep.interval_count, 2);
    assert_true(sweep.intervals[1][0] == 1.25 && sweep.intervals[1][1] == 2);
    assert_true(isnan(sweep.critical));
    assert_non_null(strstr(f.last_request, "\"wrenches\":[[-1,-1,0]],\"sets\":[\"strong\"]"));
    assert_int_equal(atomic_load(&allocations) - before, 0);
    /* A daemon without the method: its error. */
    assert_int_equal(wrc_friction_sweep(c, ID, &push, &sweep), WRC_ESERVER);
    int code;
    wrc_server_error(c, &code, NULL, NULL);
    assert_int_equal(code, -32601);
    /* Refused before sending. */
    wrc_sweep_request bad = {.kind = "tilt", .set = "goal"};
    assert_int_equal(wrc_friction_sweep(c, ID, &bad, &sweep), WRC_EINVAL);
    bad = (wrc_sweep_request){.kind = "push", .set = "gaol"};
    assert_int_equal(wrc_friction_sweep(c, ID, &bad, &sweep), WRC_EINVAL);
    bad = (wrc_sweep_request){.kind = "wrench", .set = "goal", .wrench = {NAN, 0, 0}};
    assert_int_equal(wrc_friction_sweep(c, ID, &bad, &sweep), WRC_EINVAL);
    assert_int_equal(wrc_friction_sweep(c, ID, NULL, &sweep), WRC_EINVAL);
    assert_int_equal(f.requests, 4);
    wrc_close(c);
    stop(&f);
}

/* fixture.locating of the 3-2-1 plate, as the daemon writes it (the
 * members in its order), and a fixture that does not locate. */
static const char LOCATING[] =
    "{\"jsonrpc\":\"2.0\",\"result\":{\"deterministic\":true,\"free_motion\":null,"
    "\"sensitivity\":[[0,0,1],[0.5,0.5,0],[-0.5,0.5,0]],\"condition\":2.5,"
    "\"pose_error\":{\"linear\":[0.01,0.01,0.01],\"exact\":[0.0100001,0.01,0.00999967]},"
    "\"features\":[{\"name\":null,\"at\":[4,2],\"linear\":{\"vector\":[-0.02,0.02],"
    "\"length\":0.0282843},\"exact\":{\"vector\":[-0.02,0.02],\"length\":0.0282846},"
    "\"covariance\":[[1,-1],[-1,2.5]],\"ellipse\":{\"axes\":[0.02,0.01],\"angle_deg\":-60}}]},"
    "\"id\":%ID%}";
static const char NOT_LOCATING[] =
    "{\"jsonrpc\":\"2.0\",\"result\":{\"deterministic\":false,\"free_motion\":{\"twist\":"
    "[0,0,0.7746],\"kind\":\"rotation\",\"about\":[2,1]},\"sensitivity\":null,"
    "\"condition\":null,\"pose_error\":null,\"features\":null},\"id\":%ID%}";

static void locating_reads_the_answer_without_allocating(void **state)
{
    (void)state;
    const char *const answers[] = {LOCATING, NOT_LOCATING, NULL};
    fake f;
    start(&f, answers);
    wrc_client *c = wrc_connect(f.path, 2000, 0, NULL);
    assert_non_null(c);
    wrc_locating r;
    wrc_locate_feature corner = {.at = {4, 2}};
    const double t[3] = {0.01, 0.02, 0.01};
    long before = atomic_load(&allocations);
    assert_int_equal(wrc_locating_get(c, ID, t, 3, 0, &corner, 1, &r), WRC_OK);
    assert_int_equal(atomic_load(&allocations) - before, 0);
    assert_non_null(strstr(f.last_request, "\"tolerance\":[0.01,0.02,0.01]"));
    assert_non_null(strstr(f.last_request, "\"features\":[{\"at\":[4,2]}]"));
    assert_null(strstr(f.last_request, "sigma_ratio"));
    assert_true(r.deterministic && r.condition == 2.5);
    assert_true(r.pose_linear[2] == 0.01 && r.pose_exact[0] == 0.0100001);
    assert_true(corner.linear == 0.0282843 && corner.exact == 0.0282846);
    assert_true(corner.axes[0] == 0.02 && corner.axes[1] == 0.01 && corner.angle_deg == -60);
    assert_int_equal(wrc_locating_get(c, ID, t, 1, 2, NULL, 0, &r), WRC_OK);
    assert_non_null(strstr(f.last_request, "\"tolerance\":0.01,\"sigma_ratio\":2"));
    assert_true(!r.deterministic && r.twist[2] == 0.7746);
    const double bad[1] = {NAN};
    assert_int_equal(wrc_locating_get(c, ID, bad, 1, 0, NULL, 0, &r), WRC_EINVAL);
    assert_int_equal(wrc_locating_get(c, ID, t, 0, 0, NULL, 0, &r), WRC_EINVAL);
    assert_int_equal(f.requests, 2);
    wrc_close(c);
    stop(&f);
}

static const char FORCE_RANGE[] =
    "{\"jsonrpc\":\"2.0\",\"result\":{\"cases\":[{\"name\":null,\"both\":{\"intervals\":"
    "[[1,2],[3.5,null]],\"least\":1}}],\"all\":{\"both\":{\"intervals\":[[1.5,2],[3.5,null]],"
    "\"least\":1.5}}},\"id\":%ID%}";
static const char FORCE_NONE[] =
    "{\"jsonrpc\":\"2.0\",\"result\":{\"cases\":[{\"name\":null,\"goal\":{\"intervals\":[],"
    "\"least\":null}}],\"all\":{\"goal\":{\"intervals\":[],\"least\":null}}},\"id\":%ID%}";

/* force.range: the request as the protocol spells it, all's intervals read
 * (a null upper end is none), nothing allocated. */
static void force_range_reads_all_without_allocating(void **state)
{
    (void)state;
    const char *const answers[] = {FORCE_RANGE, FORCE_NONE, NULL};
    fake f;
    start(&f, answers);
    wrc_client *c = wrc_connect(f.path, 2000, 0, NULL);
    assert_non_null(c);
    wrc_force force;
    const wrc_load loads[] = {
        {.kind = WRC_LOAD_GRAVITY, .g = 9810, .direction_deg = 270},
        {.kind = WRC_LOAD_FORCE, .force = {-20, 0}, .at = {60, 60}},
        {.kind = WRC_LOAD_WRENCH, .wrench = {1, 2, 3}},
    };
    const double at[2] = {110, 50};
    long before = atomic_load(&allocations);
    assert_int_equal(wrc_force_range(c, ID, at, loads, 3, "both", &force), WRC_OK);
    assert_int_equal(atomic_load(&allocations) - before, 0);
    assert_int_equal(force.interval_count, 2);
    assert_true(force.intervals[0][0] == 1.5 && force.intervals[0][1] == 2);
    assert_true(force.intervals[1][0] == 3.5 && isinf(force.intervals[1][1]));
    assert_true(force.least == 1.5);
    assert_non_null(strstr(f.last_request, "\"method\":\"force.range\""));
    assert_non_null(strstr(f.last_request,
                           "\"push\":{\"at\":[110,50]},\"sets\":[\"both\"],\"cases\":[{\"loads\":["
                           "{\"gravity\":{\"g\":9810,\"direction_deg\":270}},"
                           "{\"force\":[-20,0],\"at\":[60,60]},{\"wrench\":[1,2,3]}]}]"));
    assert_int_equal(wrc_force_range(c, ID, at, loads, 1, "goal", &force), WRC_OK);
    assert_int_equal(force.interval_count, 0);
    assert_true(isnan(force.least));
    /* Refused before sending. */
    assert_int_equal(wrc_force_range(c, ID, at, loads, 0, "goal", &force), WRC_EINVAL);
    assert_int_equal(wrc_force_range(c, ID, at, loads, 1, "gaol", &force), WRC_EINVAL);
    wrc_load bad = {.kind = 7};
    assert_int_equal(wrc_force_range(c, ID, at, &bad, 1, "goal", &force), WRC_EINVAL);
    bad = (wrc_load){.kind = WRC_LOAD_GRAVITY, .g = NAN};
    assert_int_equal(wrc_force_range(c, ID, at, &bad, 1, "goal", &force), WRC_EINVAL);
    assert_int_equal(f.requests, 2);
    wrc_close(c);
    stop(&f);
}

static const char PUSH_FORCE[] =
    "{\"jsonrpc\":\"2.0\",\"result\":{\"least\":{\"loop\":0,\"segment\":2,\"t\":0.25,"
    "\"at\":[24.5,60],\"direction\":[0,-1],\"force\":168.925751,\"lower_bound\":168.9257,"
    "\"converged\":true},\"evaluations\":40,\"samples\":1,\"segments\":[{\"loop\":0,"
    "\"segment\":0,\"t\":[0.5],\"force\":[200]}]},\"id\":%ID%}";
static const char PUSH_FORCE_NONE[] =
    "{\"jsonrpc\":\"2.0\",\"result\":{\"least\":null,\"evaluations\":8,\"samples\":1,"
    "\"segments\":[]},\"id\":%ID%}";

/* push.force: the request as the protocol spells it (push_on only when
 * given), the least push read, none read as not found, nothing allocated. */
static void push_force_reads_the_least_push(void **state)
{
    (void)state;
    const char *const answers[] = {PUSH_FORCE, PUSH_FORCE_NONE, NULL};
    fake f;
    start(&f, answers);
    wrc_client *c = wrc_connect(f.path, 2000, 0, NULL);
    assert_non_null(c);
    const wrc_load loads[] = {
        {.kind = WRC_LOAD_GRAVITY, .g = 9810, .direction_deg = 180},
        {.kind = WRC_LOAD_FORCE, .force = {30, -40}, .at = {20, 60}},
    };
    wrc_least_push least;
    long before = atomic_load(&allocations);
    assert_int_equal(wrc_push_force(c, ID, loads, 2, "both", 0, "outer", &least), WRC_OK);
    assert_int_equal(atomic_load(&allocations) - before, 0);
    assert_true(least.found && least.converged);
    assert_true(least.at[0] == 24.5 && least.at[1] == 60 && least.direction[1] == -1);
    assert_true(least.force == 168.925751 && least.lower_bound == 168.9257);
    assert_non_null(strstr(f.last_request, "\"method\":\"push.force\""));
    assert_non_null(strstr(f.last_request,
                           "\"set\":\"both\",\"samples\":1,\"finger_radius\":0,"
                           "\"push_on\":\"outer\",\"cases\":[{\"loads\":["
                           "{\"gravity\":{\"g\":9810,\"direction_deg\":180}},"
                           "{\"force\":[30,-40],\"at\":[20,60]}]}]"));
    assert_int_equal(wrc_push_force(c, ID, loads, 1, "goal", 8, NULL, &least), WRC_OK);
    assert_false(least.found);
    assert_null(strstr(f.last_request, "push_on"));
    assert_non_null(strstr(f.last_request, "\"finger_radius\":8,"));
    /* Refused before sending. */
    assert_int_equal(wrc_push_force(c, ID, loads, 1, "goal", 0, "inner", &least), WRC_EINVAL);
    assert_int_equal(wrc_push_force(c, ID, loads, 1, "goal", -1, NULL, &least), WRC_EINVAL);
    assert_int_equal(wrc_push_force(c, ID, loads, 0, "goal", 0, NULL, &least), WRC_EINVAL);
    wrc_load bad = {.kind = 7};
    assert_int_equal(wrc_push_force(c, ID, &bad, 1, "goal", 0, NULL, &least), WRC_EINVAL);
    assert_int_equal(f.requests, 2);
    wrc_close(c);
    stop(&f);
}

static const char FORCE_SWEEP[] =
    "{\"jsonrpc\":\"2.0\",\"result\":{\"curve\":[[0,null],[0.25,12.5],[0.5,7.25e1],"
    "[1,null]],\"at\":[null,[4,1.5],[4,0.75],null],\"intervals\":[[0.125,0.625]],"
    "\"exact\":false,\"resolution\":0.0078125},\"id\":%ID%}";

static const char FORCE_SWEEP_SUPPORTS[] =
    "{\"jsonrpc\":\"2.0\",\"result\":{\"curve\":[[0,3.5],[0.1,null]],\"at\":[[1,2],null],"
    "\"exact\":false,\"resolution\":0.1},\"id\":%ID%}";

/* friction.sweep's force over the supports' mu_B: "over" sent, an answer
 * without intervals read (interval_count 0); without over_supports (the
 * fixels' mu of a fixture on supports) the same answer reads the same,
 * and "over" is not sent. */
static void force_sweep_over_the_supports(void **state)
{
    (void)state;
    const char *const answers[] = {FORCE_SWEEP_SUPPORTS, FORCE_SWEEP_SUPPORTS, NULL};
    fake f;
    start(&f, answers);
    wrc_client *c = wrc_connect(f.path, 2000, 0, NULL);
    assert_non_null(c);
    const wrc_load loads[] = {{.kind = WRC_LOAD_FORCE, .force = {0, 0}, .at = {1, 1}}};
    wrc_force_sweep_request r = {.set = "goal", .range = {0, 0.1}, .over_supports = 1};
    double curve[2][2], at[2][2];
    wrc_force_curve sweep;
    assert_int_equal(wrc_force_sweep(c, ID, loads, 1, &r, curve, at, 2, &sweep), WRC_OK);
    assert_int_equal(sweep.sample_count, 2);
    assert_int_equal(sweep.interval_count, 0);
    assert_true(curve[0][1] == 3.5 && at[0][1] == 2 && isnan(curve[1][1]) && isnan(at[1][0]));
    assert_non_null(strstr(f.last_request, "\"over\":\"supports\",\"force\":{\"set\":\"goal\"}"));
    r.over_supports = 0;
    assert_int_equal(wrc_force_sweep(c, ID, loads, 1, &r, curve, at, 2, &sweep), WRC_OK);
    assert_int_equal(sweep.interval_count, 0);
    assert_true(curve[0][1] == 3.5 && isnan(curve[1][1]));
    assert_null(strstr(f.last_request, "\"over\""));
    wrc_close(c);
    stop(&f);
}

/* friction.sweep's force: the request as the protocol spells it (defaults
 * left out, the case's loads), each sample's mu and force with null as
 * NAN, the points, the intervals, beyond the capacity only counted, and
 * nothing allocated. */
static void force_sweep_reads_the_curve(void **state)
{
    (void)state;
    const char *const answers[] = {FORCE_SWEEP, FORCE_SWEEP, NULL};
    fake f;
    start(&f, answers);
    wrc_client *c = wrc_connect(f.path, 2000, 0, NULL);
    assert_non_null(c);
    const wrc_load loads[] = {{.kind = WRC_LOAD_GRAVITY, .g = 9.81, .direction_deg = 270}};
    wrc_force_sweep_request r = {.set = "both", .push_on = "all", .finger_radius = 0.5};
    double curve[4][2], at[4][2];
    wrc_force_curve sweep;
    long before = atomic_load(&allocations);
    assert_int_equal(wrc_force_sweep(c, ID, loads, 1, &r, curve, at, 4, &sweep), WRC_OK);
    assert_int_equal(atomic_load(&allocations) - before, 0);
    assert_int_equal(sweep.sample_count, 4);
    assert_true(curve[0][0] == 0 && isnan(curve[0][1]) && isnan(at[0][0]) && isnan(at[0][1]));
    assert_true(curve[1][0] == 0.25 && curve[1][1] == 12.5 && at[1][0] == 4 && at[1][1] == 1.5);
    assert_true(curve[2][0] == 0.5 && curve[2][1] == 72.5 && at[2][1] == 0.75);
    assert_true(curve[3][0] == 1 && isnan(curve[3][1]));
    assert_int_equal(sweep.interval_count, 1);
    assert_true(sweep.intervals[0][0] == 0.125 && sweep.intervals[0][1] == 0.625);
    assert_non_null(strstr(f.last_request,
                           "\"method\":\"friction.sweep\",\"params\":{\"fixture\":\""
                           "e0d7a1a0bd6e8bf16fe5845da1960ed9\","
                           "\"force\":{\"set\":\"both\",\"finger_radius\":0.5,"
                           "\"push_on\":\"all\"},\"cases\":[{\"loads\":["
                           "{\"gravity\":{\"g\":9.8100000000000005,\"direction_deg\":270}}]}]}"));
    /* A range and a ratio given; two samples kept of four, no points. */
    r = (wrc_force_sweep_request){.set = "goal", .range = {0.25, 0.5}, .kinetic_ratio = 0.5};
    assert_int_equal(wrc_force_sweep(c, ID, loads, 1, &r, curve, NULL, 2, &sweep), WRC_OK);
    assert_int_equal(sweep.sample_count, 4);
    assert_true(curve[1][1] == 12.5);
    assert_non_null(strstr(f.last_request, "\"range\":[0.25,0.5],\"kinetic_ratio\":0.5,"
                                           "\"force\":{\"set\":\"goal\"},\"cases\""));
    /* Refused before sending. */
    r.set = "all";
    assert_int_equal(wrc_force_sweep(c, ID, loads, 1, &r, curve, at, 4, &sweep), WRC_EINVAL);
    r = (wrc_force_sweep_request){.set = "both", .push_on = "inner"};
    assert_int_equal(wrc_force_sweep(c, ID, loads, 1, &r, curve, at, 4, &sweep), WRC_EINVAL);
    r = (wrc_force_sweep_request){.set = "both", .finger_radius = -1};
    assert_int_equal(wrc_force_sweep(c, ID, loads, 1, &r, curve, at, 4, &sweep), WRC_EINVAL);
    r = (wrc_force_sweep_request){.set = "both", .range = {0, NAN}};
    assert_int_equal(wrc_force_sweep(c, ID, loads, 1, &r, curve, at, 4, &sweep), WRC_EINVAL);
    r = (wrc_force_sweep_request){.set = "both"};
    assert_int_equal(wrc_force_sweep(c, ID, loads, 0, &r, curve, at, 4, &sweep), WRC_EINVAL);
    assert_int_equal(f.requests, 2);
    wrc_close(c);
    stop(&f);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(classify_reads_verdicts_without_allocating),
        cmocka_unit_test(classify_reads_a_robust_witness),
        cmocka_unit_test(server_errors_carry_code_field_and_reason),
        cmocka_unit_test(bad_arguments_and_bad_answers),
        cmocka_unit_test(a_silent_daemon_times_out),
        cmocka_unit_test(a_dropped_connection_is_reopened),
        cmocka_unit_test(connect_failures_name_their_cause),
        cmocka_unit_test(a_small_buffer_refuses_a_big_answer),
        cmocka_unit_test(friction_sweep_reads_intervals_without_allocating),
        cmocka_unit_test(locating_reads_the_answer_without_allocating),
        cmocka_unit_test(push_force_reads_the_least_push),
        cmocka_unit_test(force_sweep_reads_the_curve),
        cmocka_unit_test(force_sweep_over_the_supports),
        cmocka_unit_test(force_range_reads_all_without_allocating),
    };
    return cmocka_run_group_tests_name("client", tests, NULL, NULL);
}
