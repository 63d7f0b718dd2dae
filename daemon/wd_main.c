/* wd_main.c -- wrenchd's command line. */
#include "wd_log.h"
#include "wd_server.h"
#include "wrench.h"

#include <errno.h>
#include <getopt.h>
#include <stdbool.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

static const char USAGE[] =
    "Usage: wrenchd [OPTION]...\n"
    "Serve wrench cones of planar fixtures (SPEC.md) as JSON-RPC 2.0 over a Unix socket.\n"
    "\n"
    "  --socket PATH        listening socket (default ./run/wrenchd.sock); its directory\n"
    "                       is created; mode 0660\n"
    "  --state-dir DIR      keep stored fixtures in DIR/fixtures (default: memory only)\n"
    "  --load FILE          put the fixture in FILE at start; may be repeated\n"
    "  --threads N          worker threads (default: the number of cores)\n"
    "  --cache-mb N         memory for derived data, least recently used evicted\n"
    "                       (default 256)\n"
    "  --max-line BYTES     longest request line (default 1048576)\n"
    "  --max-depth N        deepest JSON nesting of a request (default 64)\n"
    "  --max-wrenches N     most wrenches in one request (default 100000)\n"
    "  --max-output BYTES   most unread answers per client before it is dropped\n"
    "                       (default 16777216)\n"
    "  --max-clients N      most clients connected at once (default 256)\n"
    "  --log-level LEVEL    error, warn, info or debug (default info); logs go to stderr,\n"
    "                       one line per event, none per request below debug\n"
    "  --help               this text\n"
    "  --version            the version\n"
    "\n"
    "Exit status: 0 after SIGTERM or SIGINT (in-flight requests answered, socket\n"
    "removed); 1 cannot start (a live daemon answers on the socket, the socket or the\n"
    "state directory cannot be used, a --load file is invalid); 2 bad command line.\n"
    "The protocol: docs/PROTOCOL.md.\n";

enum {
    OPT_SOCKET = 256, OPT_STATE_DIR, OPT_LOAD, OPT_THREADS, OPT_CACHE_MB, OPT_MAX_LINE,
    OPT_MAX_DEPTH, OPT_MAX_WRENCHES, OPT_MAX_OUTPUT, OPT_MAX_CLIENTS, OPT_LOG_LEVEL,
    OPT_HELP, OPT_VERSION
};

static const struct option OPTIONS[] = {
    {"socket", required_argument, NULL, OPT_SOCKET},
    {"state-dir", required_argument, NULL, OPT_STATE_DIR},
    {"load", required_argument, NULL, OPT_LOAD},
    {"threads", required_argument, NULL, OPT_THREADS},
    {"cache-mb", required_argument, NULL, OPT_CACHE_MB},
    {"max-line", required_argument, NULL, OPT_MAX_LINE},
    {"max-depth", required_argument, NULL, OPT_MAX_DEPTH},
    {"max-wrenches", required_argument, NULL, OPT_MAX_WRENCHES},
    {"max-output", required_argument, NULL, OPT_MAX_OUTPUT},
    {"max-clients", required_argument, NULL, OPT_MAX_CLIENTS},
    {"log-level", required_argument, NULL, OPT_LOG_LEVEL},
    {"help", no_argument, NULL, OPT_HELP},
    {"version", no_argument, NULL, OPT_VERSION},
    {NULL, 0, NULL, 0},
};

/* A whole number in [low, high] into *out; false (with a message naming the
 * option) if it is not one. */
static bool number(const char *option, const char *text, unsigned long long low,
                   unsigned long long high, unsigned long long *out)
{
    char *end;
    errno = 0;
    unsigned long long value = strtoull(text, &end, 10);
    if (errno || end == text || *end || text[0] == '-' || value < low || value > high) {
        fprintf(stderr, "wrenchd: --%s wants a whole number from %llu to %llu, not '%s'\n",
                option, low, high, text);
        return false;
    }
    *out = value;
    return true;
}

int main(int argc, char **argv)
{
    long cores = sysconf(_SC_NPROCESSORS_ONLN);
    wd_config config = {
        .socket_path = "./run/wrenchd.sock",
        .threads = cores > 0 ? (int)cores : 1,
        .cache_bytes = (size_t)256 << 20,
        .max_line = 1 << 20,
        .max_depth = 64,
        .max_wrenches = 100000,
        .max_output = (size_t)16 << 20,
        .max_clients = 256,
    };
    const char **loads = calloc((size_t)argc, sizeof *loads);
    if (!loads)
        return WD_EXIT_START;
    config.load_files = loads;
    int option, exit_now = -1;
    unsigned long long value;
    while (exit_now < 0 && (option = getopt_long(argc, argv, "", OPTIONS, NULL)) != -1) {
        bool ok = true;
        switch (option) {
        case OPT_SOCKET: config.socket_path = optarg; break;
        case OPT_STATE_DIR: config.state_dir = optarg; break;
        case OPT_LOAD: loads[config.load_count++] = optarg; break;
        case OPT_THREADS:
            if ((ok = number("threads", optarg, 1, 1024, &value)))
                config.threads = (int)value;
            break;
        case OPT_CACHE_MB:
            if ((ok = number("cache-mb", optarg, 1, 1 << 20, &value)))
                config.cache_bytes = (size_t)value << 20;
            break;
        case OPT_MAX_LINE:
            if ((ok = number("max-line", optarg, 64, (size_t)1 << 34, &value)))
                config.max_line = (size_t)value;
            break;
        case OPT_MAX_DEPTH:
            if ((ok = number("max-depth", optarg, 4, 10000, &value)))
                config.max_depth = (int)value;
            break;
        case OPT_MAX_WRENCHES:
            if ((ok = number("max-wrenches", optarg, 1, 100000000, &value)))
                config.max_wrenches = (size_t)value;
            break;
        case OPT_MAX_OUTPUT:
            if ((ok = number("max-output", optarg, 4096, (size_t)1 << 40, &value)))
                config.max_output = (size_t)value;
            break;
        case OPT_MAX_CLIENTS:
            if ((ok = number("max-clients", optarg, 1, 1000000, &value)))
                config.max_clients = (unsigned long)value;
            break;
        case OPT_LOG_LEVEL: {
            int level = wd_log_level_named(optarg);
            if (level < 0) {
                fprintf(stderr, "wrenchd: --log-level is error, warn, info or debug, not '%s'\n",
                        optarg);
                ok = false;
            } else {
                wd_log_set_level(level);
            }
            break;
        }
        case OPT_HELP:
            fputs(USAGE, stdout);
            exit_now = WD_EXIT_OK;
            break;
        case OPT_VERSION:
            printf("wrenchd %s\n", WR_VERSION);
            exit_now = WD_EXIT_OK;
            break;
        default:
            fputs("Try 'wrenchd --help'.\n", stderr);
            ok = false;
            break;
        }
        if (!ok)
            exit_now = WD_EXIT_USAGE;
    }
    if (exit_now < 0 && optind < argc) {
        fprintf(stderr, "wrenchd: unexpected argument '%s'; try 'wrenchd --help'\n", argv[optind]);
        exit_now = WD_EXIT_USAGE;
    }
    if (exit_now >= 0) {
        free(loads);
        return exit_now;
    }
    int status = wd_server_run(&config);
    free(loads);
    return status;
}
