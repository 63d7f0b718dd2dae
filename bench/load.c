/* load.c -- a load generator for wrenchd that checks every answer: the
 * driver.
 *
 *   load --socket PATH [--clients N] [--requests M] [--pipeline K] [--seed S]
 *        [--duration SECONDS] [--quiet] [--examples DIR] [--fixtures N]
 *        [--stored N] [--lp PERCENT] [--max-wrenches N] [--max-batch N]
 *        [--max-depth N] [--timeout SECONDS] [--no-count-check] [--describe]
 *        [--dump]
 *
 * Three parts, each its own file:
 *   load_requests.c  the table: every request, built from the seed, with its
 *                    expected answer computed in process (proto/wp_local);
 *   load_client.c    one client: one connection, the lines it writes, the
 *                    check of every answer it reads;
 *   load.c           this driver: the options, the table built, a warm-up
 *                    pass, the clients on their threads, the summary.
 *
 * A warm-up pass sends every request of the table once on one connection
 * (storing the shared fixtures); then N clients, one thread and one
 * connection each, send M lines each (or until --duration is over), K in
 * flight at a time, drawn at random from the table, as single requests,
 * notifications and JSON-RPC batches.  Each client also puts, reads,
 * classifies and deletes a private fixture of its own, so the store changes
 * under load in a way only that client's order decides.  Every answer is
 * matched to its request by id and compared, as parsed JSON without the id,
 * with the expected one.  The daemon's own counters (server.status) must
 * grow by exactly the requests and errors sent.
 *
 * It prints one summary and exits 1 if anything was lost or wrong, 2 on a
 * bad command line, 3 if the daemon cannot be reached. */
#include "bench_util.h"
#include "load_client.h"
#include "load_requests.h"
#include "load_util.h"

#include <errno.h>
#include <math.h>
#include <pthread.h>
#include <signal.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ---- options -------------------------------------------------------------- */

typedef struct load_options {
    const char *socket_path;
    int clients;
    long requests;        /* lines per client */
    int pipeline;
    uint64_t seed;
    double duration;      /* > 0: run this long instead of `requests` lines */
    bool quiet;
    const char *examples; /* directory of *.json fixtures */
    int fixtures;         /* generated inline fixtures */
    int stored;           /* generated stored fixtures */
    long max_wrenches;    /* the daemon's --max-wrenches */
    long max_batch;       /* the daemon's --max-batch */
    int lp_percent;       /* classifies with "method": "lp" */
    int max_depth;        /* the daemon's --max-depth */
    int timeout_seconds;        /* no answer this long: the rest is lost */
    bool count_check;
    bool describe;
    bool dump;            /* print the table: request, counts, expected answer */
} load_options;

static load_options options = {
    .socket_path = NULL, .clients = 8, .requests = 1000, .pipeline = 4, .seed = 1,
    .duration = 0, .quiet = false, .examples = "examples", .fixtures = 24, .stored = 4,
    .max_wrenches = 100000, .max_batch = 1000, .lp_percent = 10, .max_depth = 64,
    .timeout_seconds = 60, .count_check = true, .describe = false,
};

/* ---- statistics and the summary -------------------------------------------------- */

static int compare_doubles(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static double percentile(const double *sorted, size_t n, double q)
{
    if (n == 0)
        return 0;
    size_t i = (size_t)ceil(q * (double)n);
    return sorted[i > 0 ? i - 1 : 0];
}

static void merge(client_stats *into, const client_stats *s)
{
    into->lines += s->lines;
    into->requests += s->requests;
    into->batches += s->batches;
    into->notifications += s->notifications;
    into->answered_lines += s->answered_lines;
    into->answers_expected_errors += s->answers_expected_errors;
    into->answers_seen_errors += s->answers_seen_errors;
    into->server_requests += s->server_requests;
    into->server_errors += s->server_errors;
    into->wrong += s->wrong;
    into->lost += s->lost;
    into->unexpected += s->unexpected;
    for (int i = 0; i <= CATEGORY_COUNT; i++)
        into->by_category[i] += s->by_category[i];
    if (s->latency_count) {
        into->latency = xrealloc(into->latency,
                                 (into->latency_count + s->latency_count) * sizeof *into->latency);
        memcpy(into->latency + into->latency_count, s->latency,
               s->latency_count * sizeof *s->latency);
        into->latency_count += s->latency_count;
    }
}

static volatile sig_atomic_t stop_now; /* SIGINT, SIGTERM: finish early, and FAIL */

static void on_signal(int signal_number)
{
    (void)signal_number;
    stop_now = 1;
}

static void usage(FILE *to)
{
    fprintf(to,
            "usage: load --socket PATH [--clients N] [--requests M] [--pipeline K] [--seed S]\n"
            "            [--duration SECONDS] [--quiet] [--examples DIR] [--fixtures N]\n"
            "            [--stored N] [--lp PERCENT] [--max-wrenches N] [--max-batch N]\n"
            "            [--max-depth N] [--timeout SECONDS] [--no-count-check] [--describe]\n"
            "            [--dump]\n"
            "N clients (threads, one connection each) send M lines each, K in flight, drawn\n"
            "from a table of requests whose answers are computed in process first; every\n"
            "answer is checked.  --duration runs that long instead of M lines.  --fixtures\n"
            "distinct generated fixtures are sent inline (more: more cache evictions),\n"
            "--stored generated ones are put with the examples in DIR; --lp of the\n"
            "classifies (default 10%%) use GLPK.  --max-wrenches, --max-batch and\n"
            "--max-depth must be the daemon's.  --describe prints the table and the sizes\n"
            "of its fixtures' derived data and warm LPs, and sends nothing; --dump prints\n"
            "every request of the table, its counts and its expected answer.\n"
            "Exit status: 0 all answers right, 1 something lost or wrong, 2 usage, 3 no daemon.\n");
}

static long number_arg(int argc, char **argv, int *i, long lo, long hi)
{
    if (*i + 1 >= argc) {
        fprintf(stderr, "load: %s needs a value\n", argv[*i]);
        exit(2);
    }
    char *end;
    errno = 0;
    long v = strtol(argv[*i + 1], &end, 10);
    if (errno || *end || end == argv[*i + 1] || v < lo || v > hi) {
        fprintf(stderr, "load: %s %s: a number from %ld to %ld\n", argv[*i], argv[*i + 1], lo, hi);
        exit(2);
    }
    (*i)++;
    return v;
}

static void parse_options(int argc, char **argv)
{
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        if (strcmp(a, "--socket") == 0 && i + 1 < argc)
            options.socket_path = argv[++i];
        else if (strcmp(a, "--examples") == 0 && i + 1 < argc)
            options.examples = argv[++i];
        else if (strcmp(a, "--clients") == 0)
            options.clients = (int)number_arg(argc, argv, &i, 1, 4096);
        else if (strcmp(a, "--requests") == 0)
            options.requests = number_arg(argc, argv, &i, 1, 1000000000L);
        else if (strcmp(a, "--pipeline") == 0)
            options.pipeline = (int)number_arg(argc, argv, &i, 1, 1000);
        else if (strcmp(a, "--seed") == 0)
            options.seed = (uint64_t)number_arg(argc, argv, &i, 0, 1000000000000L);
        else if (strcmp(a, "--duration") == 0)
            options.duration = (double)number_arg(argc, argv, &i, 1, 100000000L);
        else if (strcmp(a, "--fixtures") == 0)
            options.fixtures = (int)number_arg(argc, argv, &i, 0, 1000000);
        else if (strcmp(a, "--stored") == 0)
            options.stored = (int)number_arg(argc, argv, &i, 0, 100000);
        else if (strcmp(a, "--max-wrenches") == 0)
            options.max_wrenches = number_arg(argc, argv, &i, 1, 1000000000L);
        else if (strcmp(a, "--lp") == 0)
            options.lp_percent = (int)number_arg(argc, argv, &i, 0, 100);
        else if (strcmp(a, "--max-batch") == 0)
            options.max_batch = number_arg(argc, argv, &i, 1, 1000000000L);
        else if (strcmp(a, "--max-depth") == 0)
            options.max_depth = (int)number_arg(argc, argv, &i, 1, 100000);
        else if (strcmp(a, "--timeout") == 0)
            options.timeout_seconds = (int)number_arg(argc, argv, &i, 1, 100000);
        else if (strcmp(a, "--quiet") == 0)
            options.quiet = true;
        else if (strcmp(a, "--no-count-check") == 0)
            options.count_check = false;
        else if (strcmp(a, "--describe") == 0)
            options.describe = true;
        else if (strcmp(a, "--dump") == 0)
            options.dump = options.describe = true;
        else if (strcmp(a, "--help") == 0 || strcmp(a, "-h") == 0) {
            usage(stdout);
            exit(0);
        } else {
            fprintf(stderr, "load: unknown option or missing value: %s\n", a);
            usage(stderr);
            exit(2);
        }
    }
    if (!options.socket_path && !options.describe) {
        fprintf(stderr, "load: --socket PATH is required\n");
        usage(stderr);
        exit(2);
    }
}


/* The settings of the table, from the options. */
static table_settings table_settings_from_options(void)
{
    return (table_settings){
        .seed = options.seed,
        .examples = options.examples,
        .fixtures = options.fixtures,
        .stored = options.stored,
        .lp_percent = options.lp_percent,
        .max_wrenches = options.max_wrenches,
        .max_batch = options.max_batch,
        .max_depth = options.max_depth,
        .measure_lp = options.describe,
    };
}

int main(int argc, char **argv)
{
    parse_options(argc, argv);
    signal(SIGPIPE, SIG_IGN);
    struct sigaction action;
    memset(&action, 0, sizeof action);
    action.sa_handler = on_signal;
    sigaction(SIGINT, &action, NULL);
    sigaction(SIGTERM, &action, NULL);

    double t0 = bench_seconds();
    const table_settings settings = table_settings_from_options();
    const table *t = table_build(&settings);
    private_fixture *private_fixtures = private_fixtures_make(t, options.clients);
    double build_seconds = bench_seconds() - t0;
    if (options.dump) {
        table_dump(t);
        return 0;
    }
    if (options.describe) {
        table_describe(t, build_seconds);
        return 0;
    }
    if (!options.quiet)
        fprintf(stderr,
                "load: %zu requests in the table (%zu fixtures), expected answers in %.1f s\n",
                table_size(t), table_fixture_count(t), build_seconds);

    client_settings load = {
        .socket_path = options.socket_path,
        .table = t,
        .pipeline = options.pipeline,
        .timeout_seconds = options.timeout_seconds,
        .lines = options.requests,
        .deadline = 0,
        .stop = &stop_now,
    };
    double base_requests = 0, base_errors = 0;
    if (!server_counts(&load, &base_requests, &base_errors)) {
        fprintf(stderr, "load: no daemon answers server.status on %s\n", options.socket_path);
        return 3;
    }

    /* Warm-up: the shared fixtures stored, then every request once, in
     * order, one at a time (a put must be answered before its id is used). */
    client_settings warm_settings = load;
    warm_settings.pipeline = 1;
    client warm;
    memset(&warm, 0, sizeof warm);
    warm.index = -1;
    warm.settings = &warm_settings;
    const request **script = xmalloc(table_size(t) * sizeof *script);
    for (size_t i = 0; i < table_size(t); i++) /* puts first: the table begins with them */
        script[i] = table_request(t, i);
    warm.script = script;
    warm.script_count = table_size(t);
    double w0 = bench_seconds();
    client_run(&warm);
    double warm_seconds = bench_seconds() - w0;
    if (!options.quiet)
        fprintf(stderr, "load: warm-up: %lu lines in %.1f s, %lu wrong, %lu lost%s%s\n",
                warm.stats.lines, warm_seconds, warm.stats.wrong, warm.stats.lost,
                warm.stats.failed ? ", " : "", warm.stats.failed ? warm.stats.failure : "");

    /* The load. */
    client *clients = calloc((size_t)options.clients, sizeof *clients);
    pthread_t *threads = calloc((size_t)options.clients, sizeof *threads);
    if (!clients || !threads)
        die("out of memory");
    double start = bench_seconds();
    if (options.duration > 0)
        load.deadline = start + options.duration;
    for (int i = 0; i < options.clients; i++) {
        clients[i].index = i;
        clients[i].settings = &load;
        /* Not seed * the generator's own increment: seeds would be one stream shifted. */
        uint64_t mix = options.seed ^ (0xd1b54a32d192ed03ull * (uint64_t)(i + 1));
        clients[i].random = random_next(&mix);
        clients[i].private_fixture = &private_fixtures[i];
        if (pthread_create(&threads[i], NULL, client_run, &clients[i]) != 0)
            die("cannot start client thread %d", i);
    }
    for (int i = 0; i < options.clients; i++)
        pthread_join(threads[i], NULL);
    double seconds = bench_seconds() - start;

    client_stats total;
    memset(&total, 0, sizeof total);
    int failed_clients = 0;
    for (int i = 0; i < options.clients; i++) {
        merge(&total, &clients[i].stats);
        if (clients[i].stats.failed) {
            failed_clients++;
            fprintf(stderr, "load: client %d: %s\n", i, clients[i].stats.failure);
        }
    }
    /* The load's latencies only; the warm-up counts for correctness. */
    double *latency = total.latency;
    size_t latency_count = total.latency_count;
    qsort(latency, latency_count, sizeof *latency, compare_doubles);
    client_stats all = total;
    all.latency = NULL;
    all.latency_count = 0;
    merge(&all, &warm.stats);
    if (warm.stats.failed) {
        failed_clients++;
        fprintf(stderr, "load: warm-up: %s\n", warm.stats.failure);
    }

    double end_requests = 0, end_errors = 0;
    bool counted = server_counts(&load, &end_requests, &end_errors);
    /* The first server.status counts itself once answered. */
    double delta_requests = end_requests - base_requests - 1;
    double delta_errors = end_errors - base_errors;
    bool counts_ok = !options.count_check ||
                     (counted && delta_requests == (double)all.server_requests &&
                      delta_errors == (double)all.server_errors);

    if (!options.quiet) {
        fprintf(stderr, "load: lines by kind:");
        for (int c = 0; c <= CATEGORY_COUNT; c++)
            fprintf(stderr, " %s %lu%s", c < CATEGORY_COUNT ? CATEGORY_NAMES[c] : "private",
                    total.by_category[c], c < CATEGORY_COUNT ? "," : "\n");
    }
    printf("load: %d clients x %s%ld lines, pipeline %d, seed %llu: %lu lines (%lu requests, "
           "%lu batches, %lu notifications) in %.2f s; warm-up %lu lines in %.2f s\n",
           options.clients, options.duration > 0 ? "~" : "",
           options.duration > 0 ? (long)(total.lines / (unsigned long)options.clients)
                                : options.requests,
           options.pipeline, (unsigned long long)options.seed, total.lines, total.requests,
           total.batches, total.notifications, seconds, warm.stats.lines, warm_seconds);
    if (counted)
        printf("load: errors expected %lu, seen %lu; the daemon counted %.0f requests and %.0f "
               "errors, expected %lu and %lu%s\n",
               all.answers_expected_errors, all.answers_seen_errors, delta_requests, delta_errors,
               all.server_requests, all.server_errors,
               !options.count_check ? " (not checked)" : counts_ok ? "" : " MISMATCH");
    else
        printf("load: errors expected %lu, seen %lu; the daemon's counts could not be read "
               "(server.status failed)\n",
               all.answers_expected_errors, all.answers_seen_errors);
    printf("load: wrong answers %lu, lost answers %lu, unexpected answers %lu, "
           "failed connections %d\n",
           all.wrong, all.lost, all.unexpected, failed_clients);
    printf("load: throughput %.0f requests/s (%.0f lines/s)\n", (double)total.requests / seconds,
           (double)total.lines / seconds);
    printf("load: latency us p50 %.0f p99 %.0f p999 %.0f max %.0f (%zu answered lines)\n",
           percentile(latency, latency_count, 0.50), percentile(latency, latency_count, 0.99),
           percentile(latency, latency_count, 0.999),
           latency_count ? latency[latency_count - 1] : 0.0, latency_count);
    bool ok = all.wrong == 0 && all.lost == 0 && all.unexpected == 0 && failed_clients == 0 &&
              all.answers_expected_errors == all.answers_seen_errors && counts_ok && !stop_now;
    printf("load: %s\n", ok ? "PASS: nothing lost, nothing wrong" : "FAIL");
    return ok ? 0 : 1;
}
