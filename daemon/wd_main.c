/* wd_main.c -- wrenchd's command line and configuration file.
 *
 * One table of options serves both: each has a name (the long option, and
 * the key in the file), a value description, help text and a setter.  The
 * file is read first; options on the command line override it (for the
 * list-valued ones, --load and --allow-*, a command-line list replaces the
 * file's). */
#include "wd_file.h"
#include "wd_log.h"
#include "wd_server.h"
#include "wd_systemd.h"
#include "wrench.h"

#include <errno.h>
#include <getopt.h>
#include <grp.h>
#include <pwd.h>
#include <stdarg.h>
#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

/* Read when no --config is given: the Makefile's SYSCONFDIR ($(PREFIX)/etc
 * unless set), so an installed daemon reads the file make install wrote there
 * and a build never reads one installed for another prefix. */
#ifndef WD_SYSCONFDIR
#error "WD_SYSCONFDIR, the configuration directory, comes from the Makefile (SYSCONFDIR)"
#endif
#define DEFAULT_CONFIG WD_SYSCONFDIR "/wrenchd/wrenchd.conf"

/* Where a setting comes from, for error messages and list replacement. */
typedef enum { FROM_FILE, FROM_COMMAND_LINE } origin;

typedef struct settings {
    wd_config config;
    const char **loads;       /* room for every argument and file line */
    int loads_capacity;
    int loads_from;           /* origin of the current --load list */
    unsigned uids[WD_MAX_ALLOWED], gids[WD_MAX_ALLOWED];
    int uids_from, gids_from;
    char *file_text;          /* the configuration file, kept: values point into it */
} settings;

typedef bool (*setter)(settings *s, const char *value, origin from, char *why, size_t size);

typedef struct option_spec {
    const char *name;
    const char *value;        /* NULL: takes no value */
    const char *help;
    setter set;
} option_spec;

/* ---- setters ---------------------------------------------------------------- */

static bool whole(const char *text, unsigned long long low, unsigned long long high,
                  unsigned long long *out, char *why, size_t size)
{
    char *end;
    errno = 0;
    unsigned long long value = strtoull(text, &end, 10);
    if (errno || end == text || *end || text[0] == '-' || value < low || value > high) {
        snprintf(why, size, "wants a whole number from %llu to %llu, not '%s'", low, high, text);
        return false;
    }
    *out = value;
    return true;
}

#define NUMBER_SETTER(function, field, type, low, high, multiplier)                             \
    static bool function(settings *s, const char *value, origin from, char *why, size_t size)  \
    {                                                                                           \
        (void)from;                                                                             \
        unsigned long long n;                                                                   \
        if (!whole(value, low, high, &n, why, size))                                            \
            return false;                                                                       \
        s->config.field = (type)(n * (multiplier));                                             \
        return true;                                                                            \
    }

NUMBER_SETTER(set_threads, threads, int, 1, 1024, 1)
NUMBER_SETTER(set_cache_mb, cache_bytes, size_t, 1, 1 << 20, 1 << 20)
NUMBER_SETTER(set_max_fixtures, max_fixtures, size_t, 1, 100000000, 1)
NUMBER_SETTER(set_max_line, max_line, size_t, 64, 1ULL << 34, 1)
NUMBER_SETTER(set_max_depth, max_depth, int, 4, 10000, 1)
NUMBER_SETTER(set_max_wrenches, max_wrenches, size_t, 1, 100000000, 1)
NUMBER_SETTER(set_max_output, max_output, size_t, 4096, 1ULL << 40, 1)
NUMBER_SETTER(set_max_clients, max_clients, unsigned long, 1, 1000000, 1)
NUMBER_SETTER(set_max_clients_per_uid, max_clients_per_uid, unsigned long, 0, 1000000, 1)
NUMBER_SETTER(set_max_batch, max_batch, size_t, 1, 1000000, 1)
NUMBER_SETTER(set_max_candidates, max_candidates, unsigned long long, 1, 1ULL << 62, 1)
NUMBER_SETTER(set_max_cases, max_cases, size_t, 1, 1000000, 1)
NUMBER_SETTER(set_idle_timeout, idle_timeout, unsigned, 0, 86400 * 7, 1)
NUMBER_SETTER(set_request_timeout, request_timeout, unsigned, 0, 86400, 1)

static bool set_socket(settings *s, const char *value, origin from, char *why, size_t size)
{
    (void)from, (void)why, (void)size;
    s->config.socket_path = value;
    return true;
}

static bool set_state_dir(settings *s, const char *value, origin from, char *why, size_t size)
{
    (void)from, (void)why, (void)size;
    s->config.state_dir = value;
    return true;
}

static bool set_load(settings *s, const char *value, origin from, char *why, size_t size)
{
    if ((int)from != s->loads_from) /* a command-line list replaces the file's */
        s->config.load_count = 0;
    s->loads_from = (int)from;
    if (s->config.load_count == s->loads_capacity) {
        snprintf(why, size, "is given more than %d times", s->loads_capacity);
        return false;
    }
    s->loads[s->config.load_count++] = value;
    return true;
}

static bool set_log_level(settings *s, const char *value, origin from, char *why, size_t size)
{
    (void)s, (void)from;
    int level = wd_log_level_named(value);
    if (level < 0) {
        snprintf(why, size, "is error, warn, info or debug, not '%s'", value);
        return false;
    }
    wd_log_set_level(level);
    return true;
}

/* A comma-separated list of users (or groups): names or numbers, or the
 * one word "any" for anyone.  A list with no entry is refused: read as "no
 * check" it would open the daemon to everyone by a slip of the pen (an
 * unset variable, a stray comma), so "anyone" must be said as "any" or by
 * leaving the option out. */
static bool set_ids(unsigned *ids, int *count, bool *any, int *list_from, origin from,
                    const char *value, bool groups, char *why, size_t size)
{
    if ((int)from != *list_from) {
        *count = 0;
        *any = false;
    }
    *list_from = (int)from;
    if (strcmp(value + strspn(value, " \t"), "any") == 0) {
        *count = 0;
        *any = true;
        return true;
    }
    char *copy = strdup(value);
    if (!copy) {
        snprintf(why, size, "out of memory");
        return false;
    }
    bool ok = true;
    int given = 0;
    char *saved;
    for (char *item = strtok_r(copy, ", ", &saved); item && ok;
         item = strtok_r(NULL, ", ", &saved)) {
        unsigned long long number;
        char *end;
        errno = 0;
        number = strtoull(item, &end, 10);
        unsigned id;
        if (strcmp(item, "any") == 0) {
            snprintf(why, size, "takes 'any' alone, not among %s", groups ? "groups" : "users");
            ok = false;
            break;
        } else if (!errno && end != item && !*end && number < 0xffffffffULL) {
            id = (unsigned)number;
        } else if (groups) {
            struct group *g = getgrnam(item);
            if (!g) {
                snprintf(why, size, "no group named '%s'", item);
                ok = false;
                break;
            }
            id = (unsigned)g->gr_gid;
        } else {
            struct passwd *p = getpwnam(item);
            if (!p) {
                snprintf(why, size, "no user named '%s'", item);
                ok = false;
                break;
            }
            id = (unsigned)p->pw_uid;
        }
        if (*count == WD_MAX_ALLOWED) {
            snprintf(why, size, "at most %d entries", WD_MAX_ALLOWED);
            ok = false;
            break;
        }
        ids[(*count)++] = id;
        given++;
    }
    free(copy);
    if (ok && given == 0) {
        snprintf(why, size, "is an empty list: name %s, or say 'any' for anyone (or leave the "
                            "option out)", groups ? "groups" : "users");
        ok = false;
    }
    return ok;
}

static bool set_allow_uid(settings *s, const char *value, origin from, char *why, size_t size)
{
    return set_ids(s->uids, &s->config.allow_uid_count, &s->config.allow_any_uid, &s->uids_from,
                   from, value, false, why, size);
}

static bool set_allow_gid(settings *s, const char *value, origin from, char *why, size_t size)
{
    return set_ids(s->gids, &s->config.allow_gid_count, &s->config.allow_any_gid, &s->gids_from,
                   from, value, true, why, size);
}

/* ---- the table ---------------------------------------------------------------- */

static const option_spec OPTIONS[] = {
    {"socket", "PATH", "listening socket (default ./run/wrenchd.sock);\n"
                       "its directory is created; mode 0660; ignored\n"
                       "when systemd passes the socket", set_socket},
    {"state-dir", "DIR", "keep stored fixtures in DIR/fixtures\n"
                         "(default: memory only)", set_state_dir},
    {"load", "FILE", "put the fixture in FILE at start; repeatable", set_load},
    {"threads", "N", "worker threads (default: the number of cores)", set_threads},
    {"cache-mb", "N", "memory for derived data, least recently used\n"
                      "evicted (default 256)", set_cache_mb},
    {"max-fixtures", "N", "most stored fixtures; a put of another one is\n"
                          "refused (default 10000)", set_max_fixtures},
    {"max-line", "BYTES", "longest request line, with room for\n"
                          "--max-wrenches wrenches however written\n"
                          "(default 16777216)", set_max_line},
    {"max-depth", "N", "deepest JSON nesting of a request (default 64)", set_max_depth},
    {"max-wrenches", "N", "most wrenches in one request (default 100000)",
     set_max_wrenches},
    {"max-output", "BYTES", "most unsent answer bytes per client: its\n"
                            "work pauses above it until it reads\n"
                            "(default 16777216)", set_max_output},
    {"max-clients", "N", "most clients connected at once (default 256)", set_max_clients},
    {"max-clients-per-uid", "N", "most clients of one user connected at once\n"
                                 "(default 0: no cap but max-clients); the\n"
                                 "workers serve users in turn whatever the\n"
                                 "number of connections each holds",
     set_max_clients_per_uid},
    {"max-batch", "N", "most requests in one batch (default 1000)", set_max_batch},
    {"max-candidates", "N", "most candidates one fixture.design (or its\n"
                            "shard) may examine; more are refused at the\n"
                            "field giving them, with the count\n"
                            "(default 100000000)", set_max_candidates},
    {"max-cases", "N", "most load cases in one request (force.range,\n"
                       "push.force, push.regions, fixture.design,\n"
                       "friction.sweep); more are refused at\n"
                       "params.cases (default 1000)", set_max_cases},
    {"idle-timeout", "SECONDS", "close a connection with nothing in flight\n"
                                "after this long without a request, or one\n"
                                "that leaves answers unread this long\n"
                                "(default 300; 0: never)", set_idle_timeout},
    {"request-timeout", "SECONDS", "a request must arrive whole within this\n"
                                   "long of its first byte, else it is refused\n"
                                   "and the connection closed (default 30;\n"
                                   "0: no limit)", set_request_timeout},
    {"allow-uid", "LIST", "only these users (names or numbers, comma-\n"
                          "separated) may connect; with allow-gid,\n"
                          "either list admits; 'any': anyone who can\n"
                          "open the socket (the default); an empty\n"
                          "list is an error", set_allow_uid},
    {"allow-gid", "LIST", "only members of these groups (primary or\n"
                          "supplementary) may connect; 'any' as above", set_allow_gid},
    {"log-level", "LEVEL", "error, warn, info or debug (default info);\n"
                           "logs go to stderr, one line per event, none\n"
                           "per request below debug", set_log_level},
    {NULL, NULL, NULL, NULL},
};

static const option_spec *find_option(const char *name)
{
    for (const option_spec *o = OPTIONS; o->name; o++)
        if (strcmp(o->name, name) == 0)
            return o;
    return NULL;
}

static void usage(FILE *out)
{
    fputs("Usage: wrenchd [OPTION]...\n"
          "Serve wrench cones of planar fixtures (docs/MODEL.md): JSON-RPC 2.0, Unix socket.\n"
          "\n"
          "  --config FILE            read settings from FILE, 'option = value' per line\n"
          "                           (default, when it exists:\n"
          "                           " DEFAULT_CONFIG ");\n"
          "                           options given here override it\n",
          out);
    for (const option_spec *o = OPTIONS; o->name; o++) {
        char head[64];
        snprintf(head, sizeof head, "--%s %s", o->name, o->value);
        fprintf(out, "  %-24s ", head);
        for (const char *c = o->help; *c; c++) {
            fputc(*c, out);
            if (*c == '\n')
                fputs("                           ", out);
        }
        fputc('\n', out);
    }
    fputs("  --help                   this text\n"
          "  --version                the version\n"
          "\n"
          "Under systemd it takes its socket by socket activation and reports with\n"
          "sd_notify (READY, STATUS, STOPPING).  SIGTERM or SIGINT: stop accepting,\n"
          "answer what is in flight, remove the socket file, exit 0.\n"
          "Exit status: 0 after SIGTERM or SIGINT; 1 cannot start (a live daemon answers on\n"
          "the socket, the socket or the state directory cannot be used, a --load file is\n"
          "invalid); 2 bad command line or configuration file.  See wrenchd(8) and\n"
          "docs/PROTOCOL.md.\n",
          out);
}

/* ---- the configuration file ------------------------------------------------------ */

/* Read the configuration file `path`: one "option = value" per line, '#'
 * starts a comment.  Missing and not required: nothing to do.  Returns
 * false after saying why. */
static bool read_config_file(settings *s, const char *path, bool required)
{
    char *text = wd_file_read(path, SIZE_MAX, NULL, NULL);
    if (!text) {
        if (!required && errno == ENOENT)
            return true;
        if (errno == ENOMEM)
            fprintf(stderr, "wrenchd: %s: out of memory\n", path);
        else
            fprintf(stderr, "wrenchd: --config %s: %s\n", path, strerror(errno));
        return false;
    }
    s->file_text = text;
    int number = 0;
    for (char *line = text, *next; line; line = next) {
        /* Line by line, empty ones counted: errors name the right line. */
        next = strchr(line, '\n');
        if (next)
            *next++ = 0;
        number++;
        char *hash = strchr(line, '#');
        if (hash)
            *hash = 0;
        char *key = line + strspn(line, " \t\r");
        if (!*key)
            continue;
        char *equals = strchr(key, '=');
        char *value = equals ? equals + 1 : NULL;
        char *end = equals ? equals : key + strlen(key);
        while (end > key && strchr(" \t\r", end[-1]))
            *--end = 0;
        *end = 0;
        const option_spec *o = find_option(key);
        if (!o || !equals) {
            fprintf(stderr, "wrenchd: %s:%d: %s\n", path, number,
                    !o ? "no such option (the keys are the long options without --)"
                       : "wants 'option = value'");
            return false;
        }
        value += strspn(value, " \t");
        char *value_end = value + strlen(value);
        while (value_end > value && strchr(" \t\r", value_end[-1]))
            *--value_end = 0;
        char why[256];
        if (!o->set(s, value, FROM_FILE, why, sizeof why)) {
            fprintf(stderr, "wrenchd: %s:%d: %s %s\n", path, number, o->name, why);
            return false;
        }
    }
    return true;
}

int main(int argc, char **argv)
{
    long cores = sysconf(_SC_NPROCESSORS_ONLN);
    settings s;
    memset(&s, 0, sizeof s);
    s.config = (wd_config){
        .socket_path = "./run/wrenchd.sock",
        .threads = cores > 0 ? (int)cores : 1,
        .cache_bytes = (size_t)256 << 20,
        .max_fixtures = 10000,
        /* 100000 wrenches written {"force": [x, y], "at": [x, y]} with
         * 17-digit numbers take about 12 MB. */
        .max_line = (size_t)16 << 20,
        .max_depth = 64,
        .max_wrenches = 100000,
        .max_output = (size_t)16 << 20,
        .max_clients = 256,
        .max_batch = 1000,
        .max_candidates = 100000000,
        .max_cases = 1000,
        .idle_timeout = 300,
        .request_timeout = 30,
        .listen_fd = -1,
    };
    s.config.allow_uids = s.uids;
    s.config.allow_gids = s.gids;
    /* Every argument and file line could be a --load. */
    s.loads_capacity = argc + 4096;
    s.loads = calloc((size_t)s.loads_capacity, sizeof *s.loads);
    if (!s.loads)
        return WD_EXIT_START;
    s.config.load_files = s.loads;
    s.loads_from = s.uids_from = s.gids_from = -1;

    /* getopt's table from ours, plus --config, --help, --version. */
    struct option long_options[sizeof OPTIONS / sizeof OPTIONS[0] + 3];
    int n = 0;
    for (const option_spec *o = OPTIONS; o->name; o++, n++)
        long_options[n] = (struct option){o->name, required_argument, NULL, 256 + n};
    long_options[n++] = (struct option){"config", required_argument, NULL, 'c'};
    long_options[n++] = (struct option){"help", no_argument, NULL, 'h'};
    long_options[n++] = (struct option){"version", no_argument, NULL, 'V'};
    long_options[n] = (struct option){NULL, 0, NULL, 0};

    /* First pass: --config, --help, --version, and errors; second pass
     * (after the file): the rest, which override it. */
    const char *config_path = NULL;
    int exit_now = -1, option;
    opterr = 1;
    while (exit_now < 0 && (option = getopt_long(argc, argv, "", long_options, NULL)) != -1) {
        if (option == 'c')
            config_path = optarg;
        else if (option == 'h') {
            usage(stdout);
            exit_now = WD_EXIT_OK;
        } else if (option == 'V') {
            printf("wrenchd %s\n", WR_VERSION);
            exit_now = WD_EXIT_OK;
        } else if (option == '?') {
            fputs("Try 'wrenchd --help'.\n", stderr);
            exit_now = WD_EXIT_USAGE;
        }
    }
    if (exit_now < 0 && optind < argc) {
        fprintf(stderr, "wrenchd: unexpected argument '%s'; try 'wrenchd --help'\n", argv[optind]);
        exit_now = WD_EXIT_USAGE;
    }
    if (exit_now < 0 && !read_config_file(&s, config_path ? config_path : DEFAULT_CONFIG,
                                          config_path != NULL))
        exit_now = WD_EXIT_USAGE;
    optind = 1;
    while (exit_now < 0 && (option = getopt_long(argc, argv, "", long_options, NULL)) != -1) {
        if (option < 256)
            continue; /* --config and friends: done */
        const option_spec *o = &OPTIONS[option - 256];
        char why[256];
        if (!o->set(&s, optarg, FROM_COMMAND_LINE, why, sizeof why)) {
            fprintf(stderr, "wrenchd: --%s %s\n", o->name, why);
            exit_now = WD_EXIT_USAGE;
        }
    }
    if (exit_now < 0) {
        char why[256];
        s.config.listen_fd = wd_systemd_listen_fd(why, sizeof why);
        if (s.config.listen_fd == -2) {
            wd_log(WD_LOG_ERROR, "%s", why);
            exit_now = WD_EXIT_START;
        }
    }
    int status = exit_now >= 0 ? exit_now : wd_server_run(&s.config);
    free(s.loads);
    free(s.file_text);
    return status;
}
