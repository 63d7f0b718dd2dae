/* wrenchctl.c -- the command-line client of wrenchd.
 *
 * Each command builds one JSON-RPC request, sends it to the daemon (or, with
 * --local, answers it in process with the daemon's own request code), and
 * prints the result as a table, or raw with --json.  Exit statuses are for
 * scripts: see EXIT_* below and wrenchctl(1). */
#include "wc_svg.h"
#include "wp_local.h"
#include "wrenchclient.h"

#include <errno.h>
#include <getopt.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

enum {
    EXIT_INSIDE = 0,      /* success; for classify, every wrench inside */
    EXIT_NOT_INSIDE = 1,  /* classify: some wrench not inside */
    EXIT_USAGE = 2,       /* bad command line or input file */
    EXIT_UNREACHABLE = 3, /* no daemon answered */
    EXIT_SERVER = 4       /* the daemon (or the in-process code) answered an error */
};

typedef struct options {
    const char *socket_path;
    double timeout_seconds;
    bool json;
    bool local;
} options;

/* ---- messages -------------------------------------------------------------- */

static int usage_error(const char *format, ...) __attribute__((format(printf, 1, 2)));
static int usage_error(const char *format, ...)
{
    va_list args;
    va_start(args, format);
    fputs("wrenchctl: ", stderr);
    vfprintf(stderr, format, args);
    fputs("\n", stderr);
    va_end(args);
    return EXIT_USAGE;
}

/* ---- the request and its answer -------------------------------------------- */

/* Send {"method", "params"} and return the parsed result, or NULL with the
 * exit status in *status after saying what went wrong. */
static cJSON *call(options *o, const char *method, cJSON *params, int *status)
{
    cJSON *request = cJSON_CreateObject();
    cJSON_AddStringToObject(request, "jsonrpc", "2.0");
    cJSON_AddStringToObject(request, "method", method);
    cJSON_AddItemToObject(request, "params", params);
    cJSON_AddNumberToObject(request, "id", 1);
    char *line = cJSON_PrintUnformatted(request);
    cJSON_Delete(request);
    if (!line) {
        *status = EXIT_SERVER;
        fputs("wrenchctl: out of memory\n", stderr);
        return NULL;
    }
    char *answer = NULL;
    if (o->local) {
        wp_local *local = wp_local_new();
        wp_limits limits = {64, (size_t)-1, (size_t)-1};
        wp_counts counts = {0, 0};
        answer = local ? wp_answer_line(wp_local_host(local), &limits, line, strlen(line), &counts)
                       : NULL;
        wp_local_free(local);
    } else {
        int error;
        wrc_client *client =
            wrc_connect(o->socket_path, (int)(o->timeout_seconds * 1000), 0, &error);
        int connect_errno = errno;
        if (client) {
            error = wrc_call(client, line, &answer);
            if (error != WRC_OK && error != WRC_ESERVER) {
                fprintf(stderr, "wrenchctl: %s: %s\n", wrc_strerror(error),
                        wrc_last_error(client));
                free(answer);
                answer = NULL;
            }
        } else if (error == WRC_ECONNECT) {
            char reason[512];
            wrc_connect_reason(o->socket_path, connect_errno, reason, sizeof reason);
            fprintf(stderr, "wrenchctl: %s: %s (see --socket)\n", wrc_strerror(error), reason);
        } else {
            fprintf(stderr, "wrenchctl: %s at %s\n", wrc_strerror(error), o->socket_path);
        }
        wrc_close(client);
        if (!answer) {
            free(line);
            *status = error == WRC_EPROTO || error == WRC_ETOOBIG || error == WRC_ENOMEM
                          ? EXIT_SERVER
                          : EXIT_UNREACHABLE;
            return NULL;
        }
    }
    free(line);
    cJSON *json = answer ? cJSON_Parse(answer) : NULL;
    free(answer);
    if (!json) {
        fputs("wrenchctl: the answer is not JSON\n", stderr);
        *status = EXIT_SERVER;
        return NULL;
    }
    cJSON *error = cJSON_GetObjectItem(json, "error");
    if (error) {
        cJSON *data = cJSON_GetObjectItem(error, "data");
        const char *field = cJSON_GetStringValue(cJSON_GetObjectItem(data, "field"));
        const char *reason = cJSON_GetStringValue(cJSON_GetObjectItem(data, "reason"));
        fprintf(stderr, "wrenchctl: %s (%d)%s%s: %s\n",
                cJSON_GetStringValue(cJSON_GetObjectItem(error, "message")),
                (int)cJSON_GetNumberValue(cJSON_GetObjectItem(error, "code")),
                field && *field ? " at " : "", field ? field : "", reason ? reason : "");
        cJSON_Delete(json);
        *status = EXIT_SERVER;
        return NULL;
    }
    cJSON *result = cJSON_DetachItemFromObject(json, "result");
    cJSON_Delete(json);
    *status = EXIT_INSIDE;
    return result;
}

static void print_json(const cJSON *value)
{
    char *text = cJSON_Print(value);
    if (text)
        puts(text);
    free(text);
}

static bool looks_like_id(const char *text)
{
    if (strlen(text) != 32)
        return false;
    for (const char *c = text; *c; c++)
        if (!((*c >= '0' && *c <= '9') || (*c >= 'a' && *c <= 'f')))
            return false;
    return true;
}

/* The whole file, NUL-terminated; *length (may be NULL) its bytes. */
static char *read_all(FILE *file, size_t *length_out)
{
    size_t length = 0, capacity = 65536;
    char *text = malloc(capacity);
    while (text) {
        length += fread(text + length, 1, capacity - length - 1, file);
        if (length + 1 < capacity)
            break;
        char *grown = realloc(text, capacity *= 2);
        if (!grown)
            free(text);
        text = grown;
    }
    if (text)
        text[length] = 0;
    if (length_out)
        *length_out = length;
    return text;
}

/* A FIXTURE argument: an existing file is read as an inline fixture,
 * otherwise an id.  NULL with a message when neither. */
static cJSON *fixture_argument(options *o, const char *argument)
{
    struct stat st;
    if (stat(argument, &st) == 0) {
        FILE *file = fopen(argument, "rb");
        int open_error = errno;
        size_t length = 0;
        char *text = file ? read_all(file, &length) : NULL;
        if (file)
            fclose(file);
        /* One JSON text and nothing after it but white space: a fixture
         * followed by more is refused, not half read. */
        const char *end = NULL;
        cJSON *json = text ? cJSON_ParseWithLengthOpts(text, length, &end, false) : NULL;
        if (json) {
            end += strspn(end, " \t\r\n");
            if (end != text + length) {
                size_t line = 1;
                for (const char *c = text; c < end; c++)
                    line += *c == '\n';
                int shown = (int)strcspn(end, "\r\n");
                usage_error("%s: text after the JSON value, on line %zu: '%.*s'", argument, line,
                            shown > 24 ? 24 : shown, end);
                cJSON_Delete(json);
                json = NULL;
            }
        } else {
            usage_error("%s: %s", argument,
                        !file ? strerror(open_error) : text ? "not a JSON text" : "out of memory");
        }
        free(text);
        return json;
    }
    if (!looks_like_id(argument)) {
        usage_error("%s: no such file, and not a fixture id (32 hexadecimal digits)", argument);
        return NULL;
    }
    if (o->local) {
        usage_error("--local needs a fixture file: there is no store in process");
        return NULL;
    }
    return cJSON_CreateString(argument);
}

/* ---- explanations ---------------------------------------------------------- */

static void fixels_named(const int *fixels, int count, char *out, size_t size)
{
    size_t n = 0;
    out[0] = 0;
    for (int i = 0; i < count && n < size; i++)
        n += (size_t)snprintf(out + n, size - n, "%sfixel %d",
                              i == 0 ? "" : i == count - 1 ? " and " : ", ", fixels[i] + 1);
}

/* The transition a goal blocking string allows, in words (as the demo and
 * the Python client say it). */
static void explain_goal(const char *blocking, const cJSON *states, char *out, size_t size)
{
    size_t n = 0;
    out[0] = 0;
    const cJSON *state;
    cJSON_ArrayForEach(state, states)
    {
        const char *s = state->valuestring;
        int separating[16], holding[16], apart[16], ns = 0, nh = 0, na = 0;
        for (int i = 0; s[i] && i < 16; i++) {
            if (s[i] == '1' && blocking[i] == 's')
                separating[ns++] = i;
            else if (s[i] == '1')
                holding[nh++] = i;
            else
                apart[na++] = i;
        }
        char a[160], b[160];
        if (n > 0 && n < size)
            n += (size_t)snprintf(out + n, size - n, "; ");
        if (ns == 0) {
            /* Nothing breaks: the self transition.  From the no-contact
             * state nothing holds either. */
            fixels_named(holding, nh, a, sizeof a);
            fixels_named(apart, na, b, sizeof b);
            n += (size_t)snprintf(out + n, n < size ? size - n : 0,
                                  "from contact state %s it can stay as it is: ", s);
            if (nh > 0)
                n += (size_t)snprintf(out + n, n < size ? size - n : 0, "%s %s%s", a,
                                      nh == 1 ? "holds" : "hold", na > 0 ? " and " : "");
            if (na > 0)
                n += (size_t)snprintf(out + n, n < size ? size - n : 0, "%s %s never reached",
                                      b, na == 1 ? "is" : "are");
        } else {
            fixels_named(separating, ns, a, sizeof a);
            n += (size_t)snprintf(out + n, n < size ? size - n : 0,
                                  "from contact state %s %s may break away", s, a);
            if (nh > 0) {
                fixels_named(holding, nh, b, sizeof b);
                n += (size_t)snprintf(out + n, n < size ? size - n : 0, " while %s %s", b,
                                      nh == 1 ? "holds" : "hold");
            }
        }
    }
}

static void explain_strong(const char *blocking, char *out, size_t size)
{
    size_t length = strlen(blocking);
    if (length && (blocking[length - 1] == '+' || blocking[length - 1] == '-')) {
        snprintf(out, size, "it may pivot %s about its contact point",
                 blocking[length - 1] == '+' ? "counter-clockwise" : "clockwise");
        return;
    }
    size_t n = (size_t)snprintf(out, size, "it may start to move:");
    for (size_t i = 0; i < length && n < size; i++) {
        const char *motion = blocking[i] == 's'   ? "separates"
                             : blocking[i] == 'l' ? "slides left"
                             : blocking[i] == 'r' ? "slides right"
                                                  : "rolls";
        n += (size_t)snprintf(out + n, size - n, "%s fixel %zu %s", i ? "," : "", i + 1, motion);
    }
}

/* ---- commands ---------------------------------------------------------------- */

typedef int (*command_fn)(options *o, int argc, char **argv);

typedef struct command {
    const char *name;
    command_fn run;
    const char *usage;   /* arguments */
    const char *summary; /* one line, for the list of commands */
    const char *help;    /* what it does, and its options */
} command;

static const command COMMANDS[];

static int print_command_help(const char *name);

/* A command's long options (all take a value but --help). */
typedef struct command_option {
    const char *name;
    int key;
} command_option;

/* The arguments of one command once its options are taken out. */
typedef struct arguments {
    int count;
    char **items;
} arguments;

/* Take the command's options wherever they stand ("--name value",
 * "--name=value"; "--" ends them), leaving the rest, "-1,-1,0" and "-"
 * included, as arguments.  Returns -1 to go on, or an exit status. */
static int take_global(options *o, const char *name, const char *value);

static int parse_command(options *o, int argc, char **argv, const char *name,
                         const command_option *known,
                         int (*take)(int key, const char *value, void *state), void *state,
                         arguments *out, int low, int high)
{
    out->count = 0;
    out->items = argv + 1; /* reused in place: the result is never longer */
    bool options_over = false;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        if (options_over || strncmp(a, "--", 2) != 0) {
            out->items[out->count++] = argv[i];
            continue;
        }
        if (strcmp(a, "--") == 0) {
            options_over = true;
            continue;
        }
        if (strcmp(a, "--help") == 0)
            return print_command_help(name) == EXIT_INSIDE ? EXIT_INSIDE : EXIT_USAGE;
        if (strcmp(a, "--json") == 0 || strcmp(a, "--local") == 0) {
            take_global(o, a + 2, NULL); /* global options may follow the command */
            continue;
        }
        const char *equals = strchr(a, '=');
        size_t length = equals ? (size_t)(equals - a - 2) : strlen(a + 2);
        bool global = (length == 6 && strncmp(a + 2, "socket", 6) == 0) ||
                      (length == 7 && strncmp(a + 2, "timeout", 7) == 0);
        const command_option *k = known;
        while (!global && k && k->name &&
               !(strlen(k->name) == length && strncmp(k->name, a + 2, length) == 0))
            k++;
        if (!global && (!k || !k->name)) {
            fprintf(stderr, "wrenchctl %s: no option '%s'; try 'wrenchctl %s --help'\n", name, a,
                    name);
            return EXIT_USAGE;
        }
        const char *value = equals ? equals + 1 : i + 1 < argc ? argv[++i] : NULL;
        if (!value) {
            fprintf(stderr, "wrenchctl %s: %s wants a value\n", name, a);
            return EXIT_USAGE;
        }
        char option_name[16];
        snprintf(option_name, sizeof option_name, "%.*s", (int)length, a + 2);
        if (global ? take_global(o, option_name, value) != 0 : take(k->key, value, state) != 0)
            return EXIT_USAGE;
    }
    if (out->count < low || out->count > high) {
        fprintf(stderr, "wrenchctl %s: %d argument%s given; try 'wrenchctl %s --help'\n", name,
                out->count, out->count == 1 ? "" : "s", name);
        return EXIT_USAGE;
    }
    return -1;
}

static int needs_daemon(options *o, const char *name)
{
    if (o->local)
        return usage_error("%s needs the daemon: --local has no store", name);
    return -1;
}

static int cmd_put(options *o, int argc, char **argv)
{
    arguments a;
    int status = parse_command(o, argc, argv, "put", NULL, NULL, NULL, &a, 1, 1);
    if (status < 0)
        status = needs_daemon(o, "put");
    if (status >= 0)
        return status;
    cJSON *fixture = fixture_argument(o, a.items[0]);
    if (!fixture || !cJSON_IsObject(fixture)) {
        if (fixture)
            usage_error("%s: a fixture file holds one JSON object", a.items[0]);
        cJSON_Delete(fixture);
        return EXIT_USAGE;
    }
    cJSON *params = cJSON_CreateObject();
    cJSON_AddItemToObject(params, "fixture", fixture);
    cJSON *result = call(o, "fixture.put", params, &status);
    if (!result)
        return status;
    if (o->json)
        print_json(result);
    else
        printf("%s  stored \"%s\": %d fixels; G_goal excludes %d cones, G_strong %d%s\n",
               cJSON_GetStringValue(cJSON_GetObjectItem(result, "id")),
               cJSON_GetStringValue(cJSON_GetObjectItem(result, "name")),
               (int)cJSON_GetNumberValue(cJSON_GetObjectItem(result, "fixels")),
               (int)cJSON_GetNumberValue(cJSON_GetObjectItem(result, "goal_cones")),
               (int)cJSON_GetNumberValue(cJSON_GetObjectItem(result, "strong_cones")),
               cJSON_IsTrue(cJSON_GetObjectItem(result, "pinned")) ? ""
                                                                   : "; the fixels do not pin it");
    cJSON_Delete(result);
    return EXIT_INSIDE;
}

/* get ID and delete ID: one id argument. */
static int id_command(options *o, int argc, char **argv, const char *name,
                      const char *method)
{
    arguments a;
    int status = parse_command(o, argc, argv, name, NULL, NULL, NULL, &a, 1, 1);
    if (status < 0)
        status = needs_daemon(o, name);
    if (status >= 0)
        return status;
    cJSON *params = cJSON_CreateObject();
    cJSON_AddStringToObject(params, "id", a.items[0]);
    cJSON *result = call(o, method, params, &status);
    if (!result)
        return status;
    if (o->json || strcmp(name, "get") == 0)
        print_json(result);
    else
        printf("deleted %s\n", a.items[0]);
    cJSON_Delete(result);
    return EXIT_INSIDE;
}

static int cmd_get(options *o, int argc, char **argv)
{
    return id_command(o, argc, argv, "get", "fixture.get");
}

static int cmd_delete(options *o, int argc, char **argv)
{
    return id_command(o, argc, argv, "delete", "fixture.delete");
}

/* list and status: no argument. */
static cJSON *bare_command(options *o, int argc, char **argv, const char *name,
                           const char *method, int *status)
{
    arguments a;
    *status = parse_command(o, argc, argv, name, NULL, NULL, NULL, &a, 0, 0);
    if (*status < 0)
        *status = needs_daemon(o, name);
    if (*status >= 0)
        return NULL;
    return call(o, method, cJSON_CreateObject(), status);
}

static int cmd_list(options *o, int argc, char **argv)
{
    int status;
    cJSON *result = bare_command(o, argc, argv, "list", "fixture.list", &status);
    if (!result)
        return status;
    if (o->json) {
        print_json(result);
    } else {
        cJSON *fixtures = cJSON_GetObjectItem(result, "fixtures");
        printf("%-32s  %6s  %s\n", "id", "fixels", "name");
        const cJSON *f;
        cJSON_ArrayForEach(f, fixtures)
        printf("%-32s  %6d  %s\n", cJSON_GetStringValue(cJSON_GetObjectItem(f, "id")),
               (int)cJSON_GetNumberValue(cJSON_GetObjectItem(f, "fixels")),
               cJSON_GetStringValue(cJSON_GetObjectItem(f, "name")));
        printf("(%d stored)\n", cJSON_GetArraySize(fixtures));
    }
    cJSON_Delete(result);
    return EXIT_INSIDE;
}

static int cmd_status(options *o, int argc, char **argv)
{
    int status;
    cJSON *result = bare_command(o, argc, argv, "status", "server.status", &status);
    if (!result)
        return status;
    if (o->json) {
        print_json(result);
    } else {
        const cJSON *item;
        cJSON_ArrayForEach(item, result)
        {
            if (cJSON_IsString(item))
                printf("%-18s %s\n", item->string, item->valuestring);
            else
                printf("%-18s %.0f\n", item->string, item->valuedouble);
        }
    }
    cJSON_Delete(result);
    return EXIT_INSIDE;
}

/* ---- classify ---------------------------------------------------------------- */

typedef struct classify_options {
    cJSON *sets;        /* array of names, or NULL for the default */
    const char *method; /* NULL: auto */
    double tolerance;
    bool tolerance_given;
} classify_options;

static int take_classify_option(int key, const char *value, void *state)
{
    classify_options *c = state;
    char *end;
    switch (key) {
    case 's': {
        cJSON_Delete(c->sets);
        c->sets = cJSON_CreateArray();
        char *copy = strdup(value);
        for (char *name = strtok(copy, ","); name; name = strtok(NULL, ",")) {
            if (strcmp(name, "goal") != 0 && strcmp(name, "strong") != 0 &&
                strcmp(name, "both") != 0) {
                /* `name` points into `copy`: say it before freeing that. */
                int status = usage_error("--sets: '%s' is not goal, strong or both", name);
                free(copy);
                return status;
            }
            cJSON_AddItemToArray(c->sets, cJSON_CreateString(name));
        }
        free(copy);
        return cJSON_GetArraySize(c->sets) > 0 ? 0 : usage_error("--sets: no set named");
    }
    case 'm':
        if (strcmp(value, "auto") != 0 && strcmp(value, "lp") != 0)
            return usage_error("--method is auto or lp, not '%s'", value);
        c->method = value;
        return 0;
    case 't':
        c->tolerance = strtod(value, &end);
        if (*end || end == value || !(c->tolerance >= 0) || !isfinite(c->tolerance))
            return usage_error("--tolerance wants a number >= 0, not '%s'", value);
        c->tolerance_given = true;
        return 0;
    default:
        return 1;
    }
}

/* "fx,fy,tau" or "fx,fy@x,y" as a wrench JSON value; NULL if neither. */
static cJSON *wrench_argument(const char *text)
{
    double v[4];
    int used = 0;
    char tail;
    const char *at = strchr(text, '@');
    if (!at) {
        if (sscanf(text, "%lf,%lf,%lf%n%c", &v[0], &v[1], &v[2], &used, &tail) != 3 ||
            text[used] != 0)
            return NULL;
        for (int k = 0; k < 3; k++)
            if (!isfinite(v[k]))
                return NULL;
        return cJSON_CreateDoubleArray(v, 3);
    }
    double force[2], point[2];
    if (sscanf(text, "%lf,%lf@%lf,%lf%n%c", &force[0], &force[1], &point[0], &point[1], &used,
               &tail) != 4 ||
        text[used] != 0 || !isfinite(force[0]) || !isfinite(force[1]) || !isfinite(point[0]) ||
        !isfinite(point[1]))
        return NULL;
    cJSON *w = cJSON_CreateObject();
    cJSON_AddItemToObject(w, "force", cJSON_CreateDoubleArray(force, 2));
    cJSON_AddItemToObject(w, "at", cJSON_CreateDoubleArray(point, 2));
    return w;
}

/* JSON wrenches from stdin, appended to `wrenches`: every value on every
 * line (white space between them), so that none is dropped; anything else
 * on a line is an error naming it, and so is a stdin without a wrench. */
static int read_wrenches(cJSON *wrenches)
{
    size_t length = 0;
    char *text = read_all(stdin, &length);
    if (!text)
        return usage_error("stdin: out of memory");
    int line_number = 0, read = 0;
    for (size_t start = 0; start < length;) {
        line_number++;
        const char *line = text + start;
        const char *newline = memchr(line, '\n', length - start);
        size_t line_length = newline ? (size_t)(newline - line) : length - start;
        start += line_length + 1;
        size_t at = 0;
        for (;;) {
            at += strspn(line + at, " \t\r"); /* stops at the NUL read_all ends with */
            if (at >= line_length)
                break;
            const char *end = NULL;
            cJSON *w = cJSON_ParseWithLengthOpts(line + at, line_length - at, &end, false);
            if (!w) {
                int shown = (int)(line_length - at > 24 ? 24 : line_length - at);
                int status = usage_error("stdin line %d, column %zu: not a JSON wrench: '%.*s'",
                                         line_number, at + 1, shown, line + at);
                free(text);
                return status;
            }
            cJSON_AddItemToArray(wrenches, w);
            read++;
            at = (size_t)(end - line);
        }
    }
    free(text);
    if (read == 0)
        return usage_error("stdin: no wrenches given (one JSON wrench or more per line)");
    return -1;
}

/* "(fx, fy, tau)" or "(fx, fy) at (x, y)". */
static void describe_wrench(const cJSON *w, char *out, size_t size)
{
    const cJSON *force = cJSON_GetObjectItem(w, "force"), *at = cJSON_GetObjectItem(w, "at");
    if (cJSON_IsArray(w) && cJSON_GetArraySize(w) == 3)
        snprintf(out, size, "(%g, %g, %g)", cJSON_GetArrayItem(w, 0)->valuedouble,
                 cJSON_GetArrayItem(w, 1)->valuedouble, cJSON_GetArrayItem(w, 2)->valuedouble);
    else if (cJSON_GetArraySize(force) == 2 && cJSON_GetArraySize(at) == 2)
        snprintf(out, size, "(%g, %g) at (%g, %g)", cJSON_GetArrayItem(force, 0)->valuedouble,
                 cJSON_GetArrayItem(force, 1)->valuedouble, cJSON_GetArrayItem(at, 0)->valuedouble,
                 cJSON_GetArrayItem(at, 1)->valuedouble);
    else {
        char *text = cJSON_PrintUnformatted(w);
        snprintf(out, size, "%s", text ? text : "?");
        free(text);
    }
}

static int cmd_classify(options *o, int argc, char **argv)
{
    static const command_option extra[] = {{"sets", 's'}, {"method", 'm'}, {"tolerance", 't'},
                                           {NULL, 0}};
    classify_options c = {NULL, NULL, 0, false};
    arguments a;
    int status = parse_command(o, argc, argv, "classify", extra, take_classify_option, &c, &a, 2,
                               1 << 20);
    cJSON *fixture = status < 0 ? fixture_argument(o, a.items[0]) : NULL;
    if (status < 0 && !fixture)
        status = EXIT_USAGE;
    cJSON *wrenches = cJSON_CreateArray();
    for (int i = 1; status < 0 && i < a.count; i++) {
        if (strcmp(a.items[i], "-") == 0) {
            status = read_wrenches(wrenches);
            continue;
        }
        cJSON *w = wrench_argument(a.items[i]);
        if (!w)
            status = usage_error("'%s' is not a wrench: fx,fy,tau or fx,fy@x,y", a.items[i]);
        else
            cJSON_AddItemToArray(wrenches, w);
    }
    if (status >= 0) {
        cJSON_Delete(fixture);
        cJSON_Delete(wrenches);
        cJSON_Delete(c.sets);
        return status;
    }
    cJSON *params = cJSON_CreateObject();
    cJSON_AddItemToObject(params, "fixture", fixture);
    cJSON_AddItemToObject(params, "wrenches", cJSON_Duplicate(wrenches, true));
    if (c.sets)
        cJSON_AddItemToObject(params, "sets", c.sets);
    if (c.method)
        cJSON_AddStringToObject(params, "method", c.method);
    if (c.tolerance_given)
        cJSON_AddNumberToObject(params, "tolerance", c.tolerance);
    cJSON *result = call(o, "wrench.classify", params, &status);
    if (!result) {
        cJSON_Delete(wrenches);
        return status;
    }
    cJSON *results = cJSON_GetObjectItem(result, "results");
    bool all_inside = true;
    const cJSON *r, *v;
    cJSON_ArrayForEach(r, results)
    cJSON_ArrayForEach(v, r) all_inside &= cJSON_IsTrue(cJSON_GetObjectItem(v, "inside"));
    if (o->json) {
        print_json(result);
    } else {
        int width = 6;
        const cJSON *w;
        cJSON_ArrayForEach(w, wrenches)
        {
            char text[96];
            describe_wrench(w, text, sizeof text);
            width = (int)strlen(text) > width ? (int)strlen(text) : width;
        }
        printf("%4s  %-*s  %-6s  %-8s  %10s  %-8s  %s\n", "#", width, "wrench", "set", "verdict",
               "margin", "blocking", "why");
        int index = 0;
        cJSON_ArrayForEach(r, results)
        {
            char wrench[96];
            describe_wrench(cJSON_GetArrayItem(wrenches, index), wrench, sizeof wrench);
            bool first = true;
            cJSON_ArrayForEach(v, r)
            {
                const char *blocking = cJSON_GetStringValue(cJSON_GetObjectItem(v, "blocking"));
                const cJSON *margin = cJSON_GetObjectItem(v, "margin");
                char margin_text[32] = "-", why[1024] = "";
                if (cJSON_IsNumber(margin))
                    snprintf(margin_text, sizeof margin_text, "%+.6f", margin->valuedouble);
                if (blocking && strcmp(v->string, "strong") == 0)
                    explain_strong(blocking, why, sizeof why);
                else if (blocking && strcmp(v->string, "goal") == 0)
                    explain_goal(blocking, cJSON_GetObjectItem(v, "states"), why, sizeof why);
                else if (blocking && cJSON_GetArraySize(cJSON_GetObjectItem(v, "states")) > 0)
                    explain_goal(blocking, cJSON_GetObjectItem(v, "states"), why, sizeof why);
                else if (blocking) /* both, blocked by a strong-set mode */
                    explain_strong(blocking, why, sizeof why);
                char number[16] = "";
                if (first)
                    snprintf(number, sizeof number, "%d", index + 1);
                printf("%4s  %-*s  %-6s  %-8s  %10s  %-8s  %s\n", number, width,
                       first ? wrench : "", v->string,
                       cJSON_GetStringValue(cJSON_GetObjectItem(v, "verdict")), margin_text,
                       blocking ? blocking : "", why);
                first = false;
            }
            index++;
        }
    }
    cJSON_Delete(result);
    cJSON_Delete(wrenches);
    return all_inside ? EXIT_INSIDE : EXIT_NOT_INSIDE;
}

/* ---- cone, plan, modes ----------------------------------------------------------- */

static void print_rows(const char *label, const cJSON *rows, const cJSON *flags,
                       const char *flag_text)
{
    int i = 0;
    const cJSON *row;
    cJSON_ArrayForEach(row, rows)
    {
        printf("  %-11s [%+.6f, %+.6f, %+.6f]%s\n", i ? "" : label,
               cJSON_GetArrayItem(row, 0)->valuedouble, cJSON_GetArrayItem(row, 1)->valuedouble,
               cJSON_GetArrayItem(row, 2)->valuedouble,
               flags && cJSON_IsTrue(cJSON_GetArrayItem(flags, i)) ? flag_text : "");
        i++;
    }
    if (i == 0)
        printf("  %-11s none\n", label);
}

/* cone, plan and modes: FIXTURE, and for cone a constraint string. */
static int fixture_query(options *o, int argc, char **argv, const char *name,
                         const char *method, cJSON **result)
{
    bool cone = strcmp(name, "cone") == 0;
    arguments a;
    int status = parse_command(o, argc, argv, name, NULL, NULL, NULL, &a, cone ? 2 : 1, cone ? 2 : 1);
    cJSON *fixture = status < 0 ? fixture_argument(o, a.items[0]) : NULL;
    if (status < 0 && !fixture)
        status = EXIT_USAGE;
    if (status >= 0)
        return status;
    cJSON *params = cJSON_CreateObject();
    cJSON_AddItemToObject(params, "fixture", fixture);
    if (cone)
        cJSON_AddStringToObject(params, "constraints", a.items[1]);
    *result = call(o, method, params, &status);
    if (*result && o->json) {
        print_json(*result);
        cJSON_Delete(*result);
        *result = NULL;
    }
    return status;
}

static int cmd_cone(options *o, int argc, char **argv)
{
    cJSON *result = NULL;
    int status = fixture_query(o, argc, argv, "cone", "cone.get", &result);
    if (!result)
        return status;
    const char *constraints = cJSON_GetStringValue(cJSON_GetObjectItem(result, "constraints"));
    if (cJSON_IsTrue(cJSON_GetObjectItem(result, "empty"))) {
        printf("G_%s is empty: no wrench satisfies %s\n", constraints, constraints);
    } else {
        cJSON *halfspaces = cJSON_GetObjectItem(result, "halfspaces");
        int dimension = (int)cJSON_GetNumberValue(cJSON_GetObjectItem(result, "dimension"));
        printf("G_%s: dimension %d, %d half-space%s (F g <= 0, physical units)%s\n", constraints,
               dimension, cJSON_GetArraySize(halfspaces),
               cJSON_GetArraySize(halfspaces) == 1 ? "" : "s",
               dimension == 3 && cJSON_GetArraySize(halfspaces) == 0 ? ": every wrench" : "");
        print_rows("half-spaces", halfspaces, cJSON_GetObjectItem(result, "strict"), "  open");
        print_rows("equalities", cJSON_GetObjectItem(result, "equalities"), NULL, "");
        print_rows("generators", cJSON_GetObjectItem(result, "generators"), NULL, "");
    }
    cJSON_Delete(result);
    return EXIT_INSIDE;
}

static void print_strings(const cJSON *list)
{
    const cJSON *item;
    cJSON_ArrayForEach(item, list) printf(" %s", item->valuestring);
    printf("\n");
}

static int cmd_plan(options *o, int argc, char **argv)
{
    cJSON *result = NULL;
    int status = fixture_query(o, argc, argv, "plan", "plan.get", &result);
    if (!result)
        return status;
    printf("%-10s  %s\n", "state", "excluded transitions");
    const cJSON *state;
    cJSON_ArrayForEach(state, cJSON_GetObjectItem(result, "states"))
    {
        printf("%-10s ", cJSON_GetStringValue(cJSON_GetObjectItem(state, "state")));
        print_strings(cJSON_GetObjectItem(state, "excluded"));
    }
    cJSON *cones = cJSON_GetObjectItem(result, "cones");
    printf("G_goal excludes %d cones:", cJSON_GetArraySize(cones));
    print_strings(cones);
    cJSON_Delete(result);
    return EXIT_INSIDE;
}

static int cmd_modes(options *o, int argc, char **argv)
{
    cJSON *result = NULL;
    int status = fixture_query(o, argc, argv, "modes", "modes.get", &result);
    if (!result)
        return status;
    cJSON *feasible = cJSON_GetObjectItem(result, "feasible");
    printf("%d feasible moving modes:", cJSON_GetArraySize(feasible));
    print_strings(feasible);
    printf("%s\n", cJSON_IsTrue(cJSON_GetObjectItem(result, "pinned"))
                       ? "pinned: rolling at every fixel holds the part still"
                       : "not pinned: the part can pivot about its contact point");
    cJSON_Delete(result);
    return EXIT_INSIDE;
}

/* ---- push, gravity, margin ------------------------------------------------------------ */

typedef struct section6_options {
    const char *set;     /* NULL: goal */
    const char *svg;     /* NULL: no picture */
    double finger_friction;
    bool friction_given;
} section6_options;

static int take_section6_option(int key, const char *value, void *state)
{
    section6_options *s = state;
    char *end;
    switch (key) {
    case 's':
        if (strcmp(value, "goal") != 0 && strcmp(value, "strong") != 0 &&
            strcmp(value, "both") != 0)
            return usage_error("--set is goal, strong or both, not '%s'", value);
        s->set = value;
        return 0;
    case 'f':
        s->finger_friction = strtod(value, &end);
        if (*end || end == value || !(s->finger_friction >= 0) || !isfinite(s->finger_friction))
            return usage_error("--finger-friction wants a number >= 0, not '%s'", value);
        s->friction_given = true;
        return 0;
    case 'v':
        s->svg = value;
        return 0;
    default:
        return 1;
    }
}

/* The fixture's geometry for a picture: the file, or the stored fixture.
 * NULL after saying why. */
static wr_fixture *fixture_geometry(options *o, const cJSON *fixture, char *name, size_t size)
{
    cJSON *json = NULL;
    if (cJSON_IsString(fixture)) {
        int status;
        cJSON *params = cJSON_CreateObject();
        cJSON_AddStringToObject(params, "id", fixture->valuestring);
        json = call(o, "fixture.get", params, &status);
        if (!json)
            return NULL;
    } else {
        json = cJSON_Duplicate(fixture, true);
    }
    wp_fixture_doc doc;
    wp_error error;
    bool ok = wp_fixture_read(json, "fixture", &doc, &error);
    cJSON_Delete(json);
    if (!ok) {
        usage_error("%s: %s", error.field, error.reason);
        return NULL;
    }
    snprintf(name, size, "%s", doc.name[0] ? doc.name : "fixture");
    wr_fixture *geometry = doc.fixture;
    doc.fixture = NULL;
    wp_fixture_doc_release(&doc);
    return geometry;
}

/* A picture for --svg: the fixture's geometry (file or stored) and the
 * open file.  NULL after saying why (nothing left to release). */
static FILE *svg_begin(options *o, const cJSON *fixture, const char *path, char name[128],
                       wr_fixture **geometry)
{
    *geometry = fixture_geometry(o, fixture, name, 128);
    if (!*geometry)
        return NULL;
    FILE *out = fopen(path, "w");
    if (!out) {
        usage_error("--svg %s: %s", path, strerror(errno));
        wr_fixture_free(*geometry);
        *geometry = NULL;
    }
    return out;
}

static void svg_end(FILE *out, wr_fixture *geometry)
{
    fclose(out);
    wr_fixture_free(geometry);
}

static int cmd_push(options *o, int argc, char **argv)
{
    static const command_option extra[] = {
        {"set", 's'}, {"finger-friction", 'f'}, {"svg", 'v'}, {NULL, 0}};
    section6_options s = {NULL, NULL, 0, false};
    arguments a;
    int status = parse_command(o, argc, argv, "push", extra, take_section6_option, &s, &a, 1, 1);
    cJSON *fixture = status < 0 ? fixture_argument(o, a.items[0]) : NULL;
    if (status >= 0 || !fixture)
        return status >= 0 ? status : EXIT_USAGE;
    cJSON *params = cJSON_CreateObject();
    cJSON_AddItemToObject(params, "fixture", cJSON_Duplicate(fixture, true));
    if (s.set)
        cJSON_AddStringToObject(params, "set", s.set);
    if (s.friction_given)
        cJSON_AddNumberToObject(params, "finger_friction", s.finger_friction);
    cJSON *result = call(o, "push.regions", params, &status);
    if (!result) {
        cJSON_Delete(fixture);
        return status;
    }
    cJSON *regions = cJSON_GetObjectItem(result, "regions");
    int count = cJSON_GetArraySize(regions);
    double fraction = cJSON_GetNumberValue(cJSON_GetObjectItem(result, "fraction"));
    if (o->json) {
        print_json(result);
    } else {
        printf("%4s  %-24s  %-24s  %10s  %10s  %9s\n", "edge", "from", "to", "t0", "t1",
               "length");
        const cJSON *r;
        cJSON_ArrayForEach(r, regions)
        {
            const cJSON *from = cJSON_GetObjectItem(r, "from"), *to = cJSON_GetObjectItem(r, "to");
            char a_text[64], b_text[64];
            snprintf(a_text, sizeof a_text, "(%.6g, %.6g)", cJSON_GetArrayItem(from, 0)->valuedouble,
                     cJSON_GetArrayItem(from, 1)->valuedouble);
            snprintf(b_text, sizeof b_text, "(%.6g, %.6g)", cJSON_GetArrayItem(to, 0)->valuedouble,
                     cJSON_GetArrayItem(to, 1)->valuedouble);
            printf("%4d  %-24s  %-24s  %10.6f  %10.6f  %9.6f\n",
                   (int)cJSON_GetNumberValue(cJSON_GetObjectItem(r, "edge")), a_text, b_text,
                   cJSON_GetNumberValue(cJSON_GetObjectItem(r, "t0")),
                   cJSON_GetNumberValue(cJSON_GetObjectItem(r, "t1")),
                   cJSON_GetNumberValue(cJSON_GetObjectItem(r, "length")));
        }
        printf("set %s: %d region%s, length %.6g, %.2f%% of the outline", s.set ? s.set : "goal",
               count, count == 1 ? "" : "s",
               cJSON_GetNumberValue(cJSON_GetObjectItem(result, "total_length")), 100 * fraction);
        if (cJSON_IsFalse(cJSON_GetObjectItem(result, "exact")))
            printf(" (sampled: resolution %g)",
                   cJSON_GetNumberValue(cJSON_GetObjectItem(result, "resolution")));
        printf("\n");
    }
    if (s.svg) {
        char name[128];
        wr_fixture *geometry;
        FILE *out = svg_begin(o, fixture, s.svg, name, &geometry);
        if (out) {
            wr_region *items = calloc((size_t)(count ? count : 1), sizeof *items);
            int i = 0;
            const cJSON *r;
            cJSON_ArrayForEach(r, regions)
            {
                items[i].edge = (int)cJSON_GetNumberValue(cJSON_GetObjectItem(r, "edge"));
                items[i].t0 = cJSON_GetNumberValue(cJSON_GetObjectItem(r, "t0"));
                items[i].t1 = cJSON_GetNumberValue(cJSON_GetObjectItem(r, "t1"));
                i++;
            }
            wc_svg_push(out, geometry, name, s.set ? s.set : "goal", items, count, fraction,
                        s.finger_friction);
            free(items);
            svg_end(out, geometry);
        } else {
            status = EXIT_USAGE;
        }
    }
    cJSON_Delete(fixture);
    cJSON_Delete(result);
    if (status != EXIT_INSIDE)
        return status;
    return count > 0 ? EXIT_INSIDE : EXIT_NOT_INSIDE;
}

static int cmd_gravity(options *o, int argc, char **argv)
{
    static const command_option extra[] = {{"set", 's'}, {"svg", 'v'}, {NULL, 0}};
    section6_options s = {NULL, NULL, 0, false};
    arguments a;
    int status = parse_command(o, argc, argv, "gravity", extra, take_section6_option, &s, &a, 1, 1);
    cJSON *fixture = status < 0 ? fixture_argument(o, a.items[0]) : NULL;
    if (status >= 0 || !fixture)
        return status >= 0 ? status : EXIT_USAGE;
    cJSON *params = cJSON_CreateObject();
    cJSON_AddItemToObject(params, "fixture", cJSON_Duplicate(fixture, true));
    if (s.set)
        cJSON_AddStringToObject(params, "set", s.set);
    cJSON *result = call(o, "gravity.sweep", params, &status);
    if (!result) {
        cJSON_Delete(fixture);
        return status;
    }
    cJSON *arcs = cJSON_GetObjectItem(result, "intervals_deg");
    int count = cJSON_GetArraySize(arcs);
    if (o->json) {
        print_json(result);
    } else {
        printf("set %s: tilts (degrees, the direction gravity pulls in the part's frame)\n",
               s.set ? s.set : "goal");
        const cJSON *arc;
        cJSON_ArrayForEach(arc, arcs)
        printf("  from %10.6f to %10.6f  (%.6g degrees)\n", cJSON_GetArrayItem(arc, 0)->valuedouble,
               cJSON_GetArrayItem(arc, 1)->valuedouble,
               cJSON_GetArrayItem(arc, 1)->valuedouble - cJSON_GetArrayItem(arc, 0)->valuedouble);
        if (count == 0)
            printf("  none: gravity alone never does it\n");
    }
    if (s.svg) {
        char name[128];
        wr_fixture *geometry;
        FILE *out = svg_begin(o, fixture, s.svg, name, &geometry);
        if (out) {
            wr_region *items = calloc((size_t)(count ? count : 1), sizeof *items);
            for (int i = 0; i < count; i++) {
                items[i].t0 = cJSON_GetArrayItem(cJSON_GetArrayItem(arcs, i), 0)->valuedouble;
                items[i].t1 = cJSON_GetArrayItem(cJSON_GetArrayItem(arcs, i), 1)->valuedouble;
            }
            wc_svg_gravity(out, geometry, name, s.set ? s.set : "goal", items, count);
            free(items);
            svg_end(out, geometry);
        } else {
            status = EXIT_USAGE;
        }
    }
    cJSON_Delete(fixture);
    cJSON_Delete(result);
    if (status != EXIT_INSIDE)
        return status;
    return count > 0 ? EXIT_INSIDE : EXIT_NOT_INSIDE;
}

static int cmd_margin(options *o, int argc, char **argv)
{
    static const command_option extra[] = {{"svg", 'v'}, {NULL, 0}};
    section6_options s = {NULL, NULL, 0, false};
    arguments a;
    int status = parse_command(o, argc, argv, "margin", extra, take_section6_option, &s, &a, 2, 2);
    cJSON *fixture = status < 0 ? fixture_argument(o, a.items[0]) : NULL;
    if (status >= 0 || !fixture)
        return status >= 0 ? status : EXIT_USAGE;
    cJSON *bias = wrench_argument(a.items[1]);
    if (!bias) {
        cJSON_Delete(fixture);
        return usage_error("'%s' is not a wrench: fx,fy,tau or fx,fy@x,y", a.items[1]);
    }
    cJSON *params = cJSON_CreateObject(); /* call() takes it */
    cJSON_AddItemToObject(params, "fixture", cJSON_Duplicate(fixture, true));
    cJSON_AddItemToObject(params, "bias", cJSON_Duplicate(bias, true));
    cJSON *result = call(o, "stability.margin", params, &status);
    if (!result) {
        cJSON_Delete(fixture);
        cJSON_Delete(bias);
        return status;
    }
    const cJSON *margin = cJSON_GetObjectItem(result, "margin");
    const char *blocking = cJSON_GetStringValue(cJSON_GetObjectItem(result, "blocking"));
    const cJSON *worst = cJSON_GetObjectItem(result, "worst_direction");
    bool held = !cJSON_IsNumber(margin) || margin->valuedouble > 0;
    if (o->json) {
        print_json(result);
    } else if (!blocking) {
        printf("no contact mode moves the part: it holds against any disturbance\n");
    } else {
        char why[512];
        explain_strong(blocking, why, sizeof why);
        printf("margin    %+.9g  (%s)\n", margin->valuedouble,
               held ? "any smaller disturbance is held, in the scaled metric"
                    : "not held: the bias itself is inside G_strong's excluded cones");
        printf("blocking  %s: %s\n", blocking, why);
        printf("worst     (%.6g, %.6g, %.6g)\n", cJSON_GetArrayItem(worst, 0)->valuedouble,
               cJSON_GetArrayItem(worst, 1)->valuedouble, cJSON_GetArrayItem(worst, 2)->valuedouble);
    }
    if (s.svg) {
        char name[128];
        wr_fixture *geometry;
        FILE *out = svg_begin(o, fixture, s.svg, name, &geometry);
        double g[3] = {0, 0, 0}, w[3] = {0, 0, 0};
        wp_error error;
        /* The bias as the daemon read it ([fx, fy, tau] or a force at a
         * point): the protocol layer's reader, which the daemon accepted. */
        if (out && wp_wrench_read(bias, "bias", geometry, g, &error)) {
            for (int k = 0; k < 3 && worst && cJSON_IsArray(worst); k++)
                w[k] = cJSON_GetArrayItem(worst, k)->valuedouble;
            wc_svg_margin(out, geometry, name, g, cJSON_IsNumber(margin) ? margin->valuedouble : 0,
                          w, blocking);
            svg_end(out, geometry);
        } else {
            if (out) {
                usage_error("%s: %s", error.field, error.reason);
                svg_end(out, geometry);
            }
            status = EXIT_USAGE;
        }
    }
    cJSON_Delete(fixture);
    cJSON_Delete(bias);
    cJSON_Delete(result);
    if (status != EXIT_INSIDE)
        return status;
    return held ? EXIT_INSIDE : EXIT_NOT_INSIDE;
}

/* ---- the table of commands ---------------------------------------------------------- */

static int cmd_help(options *o, int argc, char **argv);

static const command COMMANDS[] = {
    {"put", cmd_put, "FILE", "store a fixture; print its id",
     "Store the fixture in FILE (docs/PROTOCOL.md's JSON); print its id."},
    {"get", cmd_get, "ID", "print a stored fixture", "Print the stored fixture ID as JSON."},
    {"list", cmd_list, "", "list the stored fixtures", "List the stored fixtures."},
    {"delete", cmd_delete, "ID", "forget a stored fixture", "Forget the stored fixture ID."},
    {"classify", cmd_classify, "FIXTURE WRENCH... [--sets LIST] [--method auto|lp] [--tolerance T]",
     "verdicts, margins and blocking transitions of wrenches",
     "Classify wrenches: for each set, the verdict (inside, boundary, outside), the margin, and\n"
     "when not inside the blocking transition, said in words.\n"
     "  FIXTURE          a stored fixture's id, or a fixture file (sent inline)\n"
     "  WRENCH           fx,fy,tau (torque about the centre of mass), or fx,fy@x,y (a force at\n"
     "                   a point); '-' reads JSON wrenches from stdin, one or more per line,\n"
     "                   as one batch\n"
     "  --sets LIST      comma-separated: goal, strong, both (default goal,strong)\n"
     "  --method M       auto (explicit cones, with margins; default) or lp (GLPK, no margin)\n"
     "  --tolerance T    |margin| <= T is 'boundary' (default 1e-9)\n"
     "Exit status 0 when every wrench is inside every set asked, 1 when one is not."},
    {"cone", cmd_cone, "FIXTURE STRING", "the explicit cone of a constraint string",
     "The explicit cone G_X of a constraint string (one of s a u l r n m per fixel): its\n"
     "half-spaces F g <= 0 (open ones marked), equalities and generators, in physical units."},
    {"plan", cmd_plan, "FIXTURE", "contact states, excluded transitions, G_goal's cones",
     "Every contact state, the transitions it must rule out, and the cones G_goal excludes."},
    {"modes", cmd_modes, "FIXTURE", "the feasible moving contact modes",
     "The kinematically feasible moving contact modes, and whether the fixels pin the part."},
    {"push", cmd_push, "FIXTURE [--set SET] [--finger-friction MU] [--svg FILE]",
     "where a finger's push seats the part",
     "The push region of a set: the open intervals of the outline where a finger pushing along\n"
     "the inward normal gives a wrench in the set, exact (a polygon edge i runs from vertex i to\n"
     "vertex i+1, t is the fraction along it; on a circle t is the angle in degrees).\n"
     "  --set SET              goal (default), strong or both\n"
     "  --finger-friction MU   a finger with friction: every force of its friction cone must be\n"
     "                         in the set (sampled and bisected; the resolution is printed)\n"
     "  --svg FILE             also draw the part, its fixels and the region\n"
     "Exit status 0 when there is a region, 1 when there is none."},
    {"gravity", cmd_gravity, "FIXTURE [--set SET] [--svg FILE]",
     "the tilts under which gravity seats the part",
     "The arcs of tilt (the direction gravity pulls, degrees, in the part's frame) under which\n"
     "gravity alone gives a wrench in the set.\n"
     "  --set SET   goal (default), strong or both\n"
     "  --svg FILE  also draw the sweep as a dial around the part\n"
     "Exit status 0 when there is an arc, 1 when there is none."},
    {"margin", cmd_margin, "FIXTURE BIAS [--svg FILE]",
     "how large a disturbance a biasing wrench tolerates",
     "The disturbance margin of a biasing wrench (fx,fy,tau or fx,fy@x,y): how large a\n"
     "disturbance, in the scaled metric (f_x, f_y, tau/rho), the seated part holds under it,\n"
     "the contact mode the worst one starts, and that worst direction.\n"
     "  --svg FILE  also draw the bias and the worst disturbance on the part\n"
     "Exit status 0 when the bias holds the part (margin > 0), 1 when it does not."},
    {"status", cmd_status, "", "the daemon's version, uptime and counts",
     "The daemon's version, uptime and counts."},
    {"help", cmd_help, "[COMMAND]", "help on wrenchctl or on one command",
     "Help on wrenchctl, or on one command."},
    {NULL, NULL, NULL, NULL, NULL},
};

static const char GENERAL[] =
    "Usage: wrenchctl [OPTION]... COMMAND [ARGUMENT]...\n"
    "Ask wrenchd where and how a planar part can be pushed to seat in its fixture.\n"
    "\n"
    "Options (before or after the command):\n"
    "  --socket PATH      the daemon's socket (default $WRENCHD_SOCKET, else ./run/wrenchd.sock)\n"
    "  --timeout SECONDS  give up on the daemon after this long (default 30)\n"
    "  --json             print the result as JSON instead of a table\n"
    "  --local            compute in process with libwrench: no daemon, fixtures from files\n"
    "  --help, --version\n"
    "\n"
    "Commands:\n";

static const char EXIT_TEXT[] =
    "\nExit status: 0 done (classify: every wrench inside; push, gravity: a region; margin:\n"
    "the bias holds); 1 not so; 2 usage error; 3 the daemon is unreachable; 4 the daemon\n"
    "answered an error.\n";

static int print_command_help(const char *name)
{
    for (const command *c = COMMANDS; c->name; c++)
        if (strcmp(c->name, name) == 0) {
            printf("Usage: wrenchctl [OPTION]... %s %s\n%s\n", c->name, c->usage, c->help);
            return EXIT_INSIDE;
        }
    return usage_error("no command '%s'; try 'wrenchctl --help'", name);
}

static void print_general_help(void)
{
    fputs(GENERAL, stdout);
    for (const command *c = COMMANDS; c->name; c++)
        printf("  %-9s %s\n", c->name, c->summary);
    fputs("\n'wrenchctl COMMAND --help' says more about one command.", stdout);
    fputs(EXIT_TEXT, stdout);
}

static int cmd_help(options *o, int argc, char **argv)
{
    arguments a;
    int status = parse_command(o, argc, argv, "help", NULL, NULL, NULL, &a, 0, 1);
    if (status >= 0)
        return status;
    if (a.count == 1)
        return print_command_help(a.items[0]);
    print_general_help();
    return EXIT_INSIDE;
}

/* --socket, --timeout, --json, --local: before or after the command. */
static int take_global(options *o, const char *name, const char *value)
{
    char *end;
    if (strcmp(name, "socket") == 0) {
        o->socket_path = value;
    } else if (strcmp(name, "timeout") == 0) {
        o->timeout_seconds = strtod(value, &end);
        if (*end || end == value || !(o->timeout_seconds > 0) || o->timeout_seconds > 86400)
            return usage_error("--timeout wants seconds, more than 0, not '%s'", value);
    } else if (strcmp(name, "json") == 0) {
        o->json = true;
    } else if (strcmp(name, "local") == 0) {
        o->local = true;
    }
    return 0;
}

int main(int argc, char **argv)
{
    options o = {getenv("WRENCHD_SOCKET"), 30, false, false};
    if (!o.socket_path || !*o.socket_path)
        o.socket_path = "./run/wrenchd.sock";
    static const struct option global[] = {
        {"socket", required_argument, NULL, 'S'}, {"timeout", required_argument, NULL, 'T'},
        {"json", no_argument, NULL, 'j'},         {"local", no_argument, NULL, 'l'},
        {"help", no_argument, NULL, 'h'},         {"version", no_argument, NULL, 'V'},
        {NULL, 0, NULL, 0},
    };
    int option;
    /* "+": stop at the command; its own options are parsed after it. */
    while ((option = getopt_long(argc, argv, "+", global, NULL)) != -1) {
        switch (option) {
        case 'S': take_global(&o, "socket", optarg); break;
        case 'T':
            if (take_global(&o, "timeout", optarg) != 0)
                return EXIT_USAGE;
            break;
        case 'j': o.json = true; break;
        case 'l': o.local = true; break;
        case 'h': print_general_help(); return EXIT_INSIDE;
        case 'V': printf("wrenchctl %s\n", WR_VERSION); return EXIT_INSIDE;
        default: fputs("Try 'wrenchctl --help'.\n", stderr); return EXIT_USAGE;
        }
    }
    if (optind >= argc) {
        print_general_help();
        return EXIT_USAGE;
    }
    for (const command *c = COMMANDS; c->name; c++)
        if (strcmp(c->name, argv[optind]) == 0)
            return c->run(&o, argc - optind, argv + optind);
    return usage_error("no command '%s'; try 'wrenchctl --help'", argv[optind]);
}
