/* load.c -- a load generator for wrenchd that checks every answer.
 *
 *   load --socket PATH [--clients N] [--requests M] [--pipeline K] [--seed S]
 *        [--duration SECONDS] [--quiet] [--examples DIR] [--fixtures N]
 *        [--stored N] [--lp PERCENT] [--max-wrenches N] [--max-batch N]
 *        [--max-depth N] [--timeout SECONDS] [--no-count-check] [--describe]
 *        [--dump]
 *
 * Before any load it builds a fixed table of requests from the seed: puts of
 * the fixtures in examples/ (*.json) and of generated ones, single and batch
 * classifies, cone.get, plan.get, modes.get, push.regions, gravity.sweep,
 * stability.margin, fixture.get/list, server.status, and deliberate errors
 * (bad JSON, invalid requests, unknown methods, bad params, unknown ids).
 * Each expected answer is computed once, in process, by proto/wp_local (the
 * same code the daemon runs, without its transport, store or cache): a
 * request naming a stored fixture by id is computed with the fixture inline,
 * and the answers that need the store (fixture.put, fixture.get,
 * fixture.delete of a stored id) are computed from the fixture itself.
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
#include "wp_local.h"
#include "wp_rpc.h"

#include <dirent.h>
#include <errno.h>
#include <glpk.h>
#include <math.h>
#include <poll.h>
#include <pthread.h>
#include <signal.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <sys/un.h>
#include <time.h>
#include <unistd.h>

/* ---- options -------------------------------------------------------------- */

typedef struct options {
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
    int timeout_s;        /* no answer this long: the rest is lost */
    bool count_check;
    bool describe;
    bool dump;            /* print the table: request, counts, expected answer */
} options;

static options opt = {
    .socket_path = NULL, .clients = 8, .requests = 1000, .pipeline = 4, .seed = 1,
    .duration = 0, .quiet = false, .examples = "examples", .fixtures = 24, .stored = 4,
    .max_wrenches = 100000, .max_batch = 1000, .lp_percent = 10, .max_depth = 64, .timeout_s = 60, .count_check = true,
    .describe = false,
};

static void die(const char *format, ...)
{
    va_list args;
    va_start(args, format);
    fprintf(stderr, "load: ");
    vfprintf(stderr, format, args);
    fprintf(stderr, "\n");
    va_end(args);
    exit(1);
}

static void *xmalloc(size_t size)
{
    void *p = malloc(size ? size : 1);
    if (!p)
        die("out of memory");
    return p;
}

static void *xrealloc(void *p, size_t size)
{
    p = realloc(p, size ? size : 1);
    if (!p)
        die("out of memory");
    return p;
}

static char *xstrdup(const char *s)
{
    size_t n = strlen(s) + 1;
    return memcpy(xmalloc(n), s, n);
}

static char *xprintf(const char *format, ...) __attribute__((format(printf, 1, 2)));
static char *xprintf(const char *format, ...)
{
    va_list args;
    va_start(args, format);
    int n = vsnprintf(NULL, 0, format, args);
    va_end(args);
    char *s = xmalloc((size_t)n + 1);
    va_start(args, format);
    vsnprintf(s, (size_t)n + 1, format, args);
    va_end(args);
    return s;
}

static void append(char **buffer, size_t *length, size_t *capacity, const char *text)
{
    size_t n = strlen(text);
    if (*length + n + 1 > *capacity) {
        *capacity = 2 * (*length + n + 1);
        *buffer = xrealloc(*buffer, *capacity);
    }
    memcpy(*buffer + *length, text, n + 1);
    *length += n;
}

static double now_us(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec * 1e6 + (double)t.tv_nsec / 1e3;
}

/* ---- random numbers (splitmix64: one state per table and per client) -------- */

static uint64_t rnd(uint64_t *state)
{
    uint64_t z = (*state += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
}

static double uniform(uint64_t *state, double lo, double hi)
{
    return lo + (hi - lo) * ((double)(rnd(state) >> 11) / 9007199254740992.0);
}

static int pick(uint64_t *state, int n) { return (int)(rnd(state) % (uint64_t)n); }

/* Rounded to 4 decimals: short lines, and still a dense set of values. */
static double r4(double x) { return round(x * 1e4) / 1e4; }

/* ---- what is sent and what is expected ------------------------------------- */

enum { CHECK_EXACT, CHECK_LOOSE, CHECK_NO_WITNESS, CHECK_STATUS, CHECK_LIST };

enum {
    CAT_PUT, CAT_GET, CAT_CLASSIFY, CAT_BATCH_CLASSIFY, CAT_CONE, CAT_PLAN, CAT_MODES,
    CAT_PUSH, CAT_GRAVITY, CAT_MARGIN, CAT_STATUS, CAT_LIST, CAT_ERROR, CAT_RAW, CAT_COUNT
};

static const char *const CAT_NAMES[CAT_COUNT] = {
    "fixture.put",  "fixture.get",   "wrench.classify", "classify batch", "cone.get",
    "plan.get",     "modes.get",     "push.regions",    "gravity.sweep",  "stability.margin",
    "server.status", "fixture.list", "bad params",      "bad lines"};

/* Single lines drawn per category, out of the sum. */
static const int CAT_WEIGHTS[CAT_COUNT] = {6, 3, 22, 12, 8, 6, 6, 8, 6, 8, 1, 1, 9, 4};

#define MEMBER_RAW 1u        /* sent as is: no id is added */
#define MEMBER_NOTIFIABLE 2u /* a valid request: may go without an id */
#define MEMBER_BATCHABLE 4u  /* may be a member of a JSON-RPC batch */

typedef struct member {
    int category;
    unsigned flags;
    int check;
    char *wire;      /* object text without its closing '}', or the raw line */
    char *oracle;    /* the same for the in-process answer (fixture inline); NULL: wire */
    char *expected;  /* canonical answer, without "id" unless raw; NULL: no answer */
    int answer_errors;        /* error objects in the expected answer */
    unsigned long requests;   /* what the daemon counts for it... */
    unsigned long errors;     /* ...and of them, errors */
    bool given;      /* expected set when built, not by the oracle */
} member;

typedef struct table {
    member *items;
    size_t count, capacity;
    size_t *by_category[CAT_COUNT];
    size_t category_count[CAT_COUNT];
    size_t batchable_count;
    size_t *batchable;
} table;

static table T;

static member *add_member(int category, unsigned flags, int check, char *wire, char *oracle)
{
    if (T.count == T.capacity) {
        T.capacity = T.capacity ? 2 * T.capacity : 256;
        T.items = xrealloc(T.items, T.capacity * sizeof *T.items);
    }
    member *m = &T.items[T.count++];
    memset(m, 0, sizeof *m);
    m->category = category;
    m->flags = flags;
    m->check = check;
    m->wire = wire;
    m->oracle = oracle;
    return m;
}

/* The text of a request object without its closing brace. */
static char *request_prefix(const char *method, const cJSON *params)
{
    char *p = params ? cJSON_PrintUnformatted(params) : NULL;
    if (params && !p)
        die("out of memory");
    char *s = p ? xprintf("{\"jsonrpc\":\"2.0\",\"method\":\"%s\",\"params\":%s", method, p)
                : xprintf("{\"jsonrpc\":\"2.0\",\"method\":\"%s\"", method);
    free(p);
    return s;
}

/* ---- normalising answers for comparison ------------------------------------ */

typedef struct shared_fixture {
    char id[WP_ID_LENGTH + 1];
    char *name;
    int fixels;
} shared_fixture;

static shared_fixture *shared;
static size_t shared_count;

static int compare_ids(const void *a, const void *b)
{
    return strcmp(((const shared_fixture *)a)->id, ((const shared_fixture *)b)->id);
}

/* fixture.list: every entry with the documented members, sorted by id, the
 * shared fixtures there with their names. */
static bool list_ok(const cJSON *result)
{
    const cJSON *list = cJSON_GetObjectItemCaseSensitive(result, "fixtures");
    if (!cJSON_IsArray(list))
        return false;
    const char *previous = "";
    size_t found = 0;
    for (const cJSON *item = list->child; item; item = item->next) {
        const cJSON *id = cJSON_GetObjectItemCaseSensitive(item, "id");
        const cJSON *name = cJSON_GetObjectItemCaseSensitive(item, "name");
        const cJSON *fixels = cJSON_GetObjectItemCaseSensitive(item, "fixels");
        if (!cJSON_IsObject(item) || !cJSON_IsString(id) ||
            !wp_fixture_id_valid(id->valuestring) || !cJSON_IsString(name) ||
            !cJSON_IsNumber(fixels) || strcmp(previous, id->valuestring) >= 0)
            return false;
        previous = id->valuestring;
        shared_fixture key;
        snprintf(key.id, sizeof key.id, "%s", id->valuestring);
        shared_fixture *s = bsearch(&key, shared, shared_count, sizeof *shared, compare_ids);
        if (s) {
            if (strcmp(s->name, name->valuestring) != 0 || s->fixels != fixels->valueint)
                return false;
            found++;
        }
    }
    return found == shared_count;
}

/* server.status: only its shape, the types of the members docs/PROTOCOL.md
 * lists (members added later are not this program's business). */
static void normalize_status(cJSON *answer)
{
    static const char *const MEMBERS[] = {
        "version", "uptime_s", "fixtures", "cached",   "cache_bytes", "cache_limit_bytes",
        "threads", "clients",  "refused",  "denied",   "requests",    "errors",
        NULL};
    cJSON *result = cJSON_GetObjectItemCaseSensitive(answer, "result");
    if (!cJSON_IsObject(result))
        return;
    cJSON *shape = cJSON_CreateObject();
    for (const char *const *name = MEMBERS; *name; name++) {
        const cJSON *item = cJSON_GetObjectItemCaseSensitive(result, *name);
        if (item)
            cJSON_AddStringToObject(shape, *name,
                                    cJSON_IsNumber(item)   ? "number"
                                    : cJSON_IsString(item) ? "string"
                                                           : "other");
    }
    cJSON_ReplaceItemInObjectCaseSensitive(answer, "result", shape);
}

/* Make an answer object comparable: drop what may differ. */
static void normalize(cJSON *answer, int check)
{
    if (!cJSON_IsObject(answer))
        return;
    cJSON *result = cJSON_GetObjectItemCaseSensitive(answer, "result");
    cJSON *error = cJSON_GetObjectItemCaseSensitive(answer, "error");
    switch (check) {
    case CHECK_LOOSE: /* the daemon words "no stored fixture" its own way */
        if (error)
            cJSON_DeleteItemFromObjectCaseSensitive(
                cJSON_GetObjectItemCaseSensitive(error, "data"), "reason");
        break;
    case CHECK_NO_WITNESS: { /* LP witnesses are not unique */
        const cJSON *results = cJSON_GetObjectItemCaseSensitive(result, "results");
        for (const cJSON *r = results ? results->child : NULL; r; r = r->next)
            for (cJSON *set = r->child; set; set = set->next)
                cJSON_DeleteItemFromObjectCaseSensitive(set, "witness");
        break;
    }
    case CHECK_STATUS:
        normalize_status(answer);
        break;
    case CHECK_LIST:
        if (result && list_ok(result)) {
            cJSON *ok = cJSON_CreateObject();
            cJSON_AddTrueToObject(ok, "ok");
            cJSON_ReplaceItemInObjectCaseSensitive(answer, "result", ok);
        }
        break;
    default:
        break;
    }
}

static int count_errors(const cJSON *answer)
{
    if (cJSON_IsArray(answer)) {
        int n = 0;
        for (const cJSON *a = answer->child; a; a = a->next)
            n += count_errors(a);
        return n;
    }
    return cJSON_GetObjectItemCaseSensitive(answer, "error") != NULL;
}

/* The canonical text an answer is compared by (the caller frees). */
static char *comparable(cJSON *answer, const member *m)
{
    normalize(answer, m->check);
    char *text = wp_canonical(answer, (m->flags & MEMBER_RAW) ? NULL : "id");
    if (!text)
        die("out of memory");
    return text;
}

/* ---- fixtures ---------------------------------------------------------------- */

typedef struct fixture {
    cJSON *json;       /* as sent inline or put */
    char *text;        /* its JSON text */
    char id[WP_ID_LENGTH + 1];
    char *name;
    char *canonical;   /* what fixture.get returns */
    int fixels;
    bool has_shape;
    double size;       /* a length scale for torques and points */
    double com[2];
    int goal_cones, strong_cones;
    bool pinned;
    size_t analysis_bytes;
    size_t lp_bytes;   /* GLPK's memory for all its LPs, warm (--describe) */
} fixture;

static void add_number_array(cJSON *parent, const char *key, const double *v, int n)
{
    cJSON *a = cJSON_CreateDoubleArray(v, n);
    if (!a)
        die("out of memory");
    if (key)
        cJSON_AddItemToObject(parent, key, a);
    else
        cJSON_AddItemToArray(parent, a);
}

static void add_point(cJSON *array, double x, double y)
{
    const double p[2] = {r4(x), r4(y)};
    add_number_array(array, NULL, p, 2);
}

static cJSON *friction_json(uint64_t *r)
{
    cJSON *f = cJSON_CreateObject();
    double s = r4(uniform(r, 0.05, 0.6));
    cJSON_AddNumberToObject(f, "static", s);
    if (pick(r, 2))
        cJSON_AddNumberToObject(f, "kinetic", r4(s * uniform(r, 0.5, 1.0)));
    return f;
}

/* A random fixture: a plate (rectangle, perhaps chamfered) against locators
 * on its bottom and left edges, a disc in a corner, or a shapeless body. */
static cJSON *generate_fixture(uint64_t *r, const char *name)
{
    cJSON *f = cJSON_CreateObject();
    cJSON_AddStringToObject(f, "name", name);
    cJSON *body = cJSON_AddObjectToObject(f, "body");
    cJSON_AddNumberToObject(body, "mass", r4(uniform(r, 0.5, 3)));
    cJSON *fixels = cJSON_CreateArray();
    int kind = pick(r, 10);
    if (kind < 6) {
        double w = r4(uniform(r, 2, 6)), h = r4(uniform(r, 1, 4));
        double c = kind < 3 ? r4(uniform(r, 0.2, 0.6) * fmin(w, h)) : 0;
        cJSON *shape = cJSON_AddObjectToObject(body, "shape");
        cJSON_AddStringToObject(shape, "type", "polygon");
        cJSON *v = cJSON_AddArrayToObject(shape, "vertices");
        add_point(v, 0, 0);
        add_point(v, w, 0);
        if (c > 0) {
            add_point(v, w, h - c);
            add_point(v, w - c, h);
        } else {
            add_point(v, w, h);
        }
        add_point(v, 0, h);
        if (pick(r, 4) == 0) {
            cJSON_AddNumberToObject(body, "inertia", r4(uniform(r, 0.5, 4)));
            const double com[2] = {r4(uniform(r, 0.3, 0.6) * w), r4(uniform(r, 0.3, 0.6) * h)};
            add_number_array(body, "com", com, 2);
        }
        int k = 2 + pick(r, 3); /* 2..4 fixels */
        double a = uniform(r, 0.1, 0.45), b = uniform(r, 0.55, 0.9);
        cJSON *x;
        if (k >= 3) { /* two under it */
            x = cJSON_CreateObject();
            add_number_array(x, "at", (double[2]){r4(a * w), 0}, 2);
            cJSON_AddItemToArray(fixels, x);
            x = cJSON_CreateObject();
            add_number_array(x, "at", (double[2]){r4(b * w), 0}, 2);
            cJSON_AddItemToArray(fixels, x);
        } else {
            x = cJSON_CreateObject();
            add_number_array(x, "at", (double[2]){r4(uniform(r, 0.2, 0.8) * w), 0}, 2);
            cJSON_AddItemToArray(fixels, x);
        }
        x = cJSON_CreateObject(); /* one to its left */
        add_number_array(x, "at", (double[2]){0, r4(uniform(r, 0.15, 0.85) * h)}, 2);
        if (pick(r, 4) == 0)
            cJSON_AddItemToObject(x, "friction", friction_json(r));
        cJSON_AddItemToArray(fixels, x);
        if (k == 4) { /* and one above */
            x = cJSON_CreateObject();
            add_number_array(x, "at", (double[2]){r4(uniform(r, 0.1, 0.5) * (w - c)), h}, 2);
            cJSON_AddItemToArray(fixels, x);
        }
    } else if (kind < 8) {
        double radius = r4(uniform(r, 0.5, 2)), cx = r4(uniform(r, -1, 1)),
               cy = r4(uniform(r, -1, 1));
        cJSON *shape = cJSON_AddObjectToObject(body, "shape");
        cJSON_AddStringToObject(shape, "type", "circle");
        add_number_array(shape, "center", (double[2]){cx, cy}, 2);
        cJSON_AddNumberToObject(shape, "radius", radius);
        if (pick(r, 2))
            cJSON_AddNumberToObject(body, "inertia", r4(uniform(r, 0.2, 2)));
        int k = 2 + pick(r, 2);
        const double pi = 3.14159265358979323846;
        double angles[3] = {uniform(r, 165, 195), uniform(r, 255, 285), uniform(r, 120, 150)};
        for (int i = 0; i < k; i++) {
            /* On the circle to the last bit: the validator allows a tolerance. */
            double t = angles[i] * pi / 180;
            cJSON *x = cJSON_CreateObject();
            add_number_array(x, "at",
                             (double[2]){cx + radius * cos(t), cy + radius * sin(t)}, 2);
            cJSON_AddItemToArray(fixels, x);
        }
    } else {
        cJSON_AddNumberToObject(body, "inertia", r4(uniform(r, 0.3, 3)));
        add_number_array(body, "com", (double[2]){r4(uniform(r, -0.3, 0.3)), r4(uniform(r, -0.3, 0.3))}, 2);
        int k = 2 + pick(r, 2);
        const double at[3][2] = {{-1, r4(uniform(r, -0.5, 0.5))},
                                 {r4(uniform(r, -0.5, 0.5)), -1},
                                 {r4(uniform(r, -0.8, 0.8)), 1}};
        const double normal[3][2] = {{1, r4(uniform(r, -0.2, 0.2))},
                                     {r4(uniform(r, -0.2, 0.2)), 1},
                                     {r4(uniform(r, -0.2, 0.2)), -1}};
        for (int i = 0; i < k; i++) {
            cJSON *x = cJSON_CreateObject();
            add_number_array(x, "at", at[i], 2);
            add_number_array(x, "normal", normal[i], 2);
            cJSON_AddItemToArray(fixels, x);
        }
    }
    cJSON_AddItemToObject(f, "friction", friction_json(r));
    cJSON_AddItemToObject(f, "fixels", fixels);
    return f;
}

/* Read, analyse and describe a fixture for the table.  False if invalid. */
static bool fixture_fill(fixture *out, cJSON *json, bool measure_lp)
{
    memset(out, 0, sizeof *out);
    /* What the daemon reads is the text: cJSON prints 15 digits when they
     * read back nearly the same, so take the numbers as read back from it
     * (printing those again gives the same text). */
    char *text = cJSON_PrintUnformatted(json);
    cJSON *read_back = text ? cJSON_Parse(text) : NULL;
    free(text);
    if (!read_back)
        die("out of memory");
    cJSON_Delete(json);
    json = read_back;
    wp_fixture_doc doc;
    wp_error error = {0};
    if (!wp_fixture_read(json, "params.fixture", &doc, &error)) {
        cJSON_Delete(json);
        return false;
    }
    wr_analysis *a;
    if (wr_analysis_new(doc.fixture, &a) != WR_OK)
        die("out of memory");
    out->json = json;
    out->text = cJSON_PrintUnformatted(json);
    memcpy(out->id, doc.id, sizeof out->id);
    out->name = xstrdup(doc.name);
    out->canonical = xstrdup(doc.canonical);
    out->fixels = doc.fixture->fixel_count;
    out->has_shape = doc.fixture->shape != WR_SHAPE_NONE;
    out->size = doc.fixture->size > 0 ? doc.fixture->size : 1;
    out->com[0] = doc.fixture->com[0];
    out->com[1] = doc.fixture->com[1];
    out->goal_cones = wr_analysis_cone_count(a, WR_SET_GOAL);
    out->strong_cones = wr_analysis_cone_count(a, WR_SET_STRONG);
    out->pinned = wr_analysis_pinned(a);
    out->analysis_bytes = wr_analysis_bytes(a);
    if (measure_lp) {
        /* What a worker's warm LPs for this fixture hold: every problem built. */
        wr_lp_env *env;
        int count, peak;
        size_t before, after, tpeak;
        glp_mem_usage(&count, &peak, &before, &tpeak);
        wr_lp_set *goal, *strong;
        if (wr_lp_env_new(&env) != WR_OK || wr_analysis_lp_sets(a, env, &goal, &strong) != WR_OK)
            die("out of memory");
        const double g[3] = {-1, -1, 0};
        bool member;
        for (int i = 0; i < out->goal_cones; i++)
            wr_lp_member(goal, i, g, &member, NULL);
        for (int i = 0; i < out->strong_cones; i++)
            wr_lp_member(strong, i, g, &member, NULL);
        glp_mem_usage(&count, &peak, &after, &tpeak);
        out->lp_bytes = after - before;
        wr_lp_set_free(goal);
        wr_lp_set_free(strong);
        wr_lp_env_free(env);
    }
    wr_analysis_free(a);
    wp_fixture_doc_release(&doc);
    return true;
}

/* Free what fixture_fill made, but not the JSON it was given. */
static void fixture_release(fixture *f)
{
    free(f->text);
    free(f->name);
    free(f->canonical);
    f->text = f->name = f->canonical = NULL;
}

static fixture generated_fixture(uint64_t *r, const char *name)
{
    for (int attempt = 0; attempt < 1000; attempt++) {
        fixture f;
        if (fixture_fill(&f, generate_fixture(r, name), opt.describe))
            return f;
    }
    die("could not generate a valid fixture");
    return (fixture){0};
}

static fixture *fixtures_all;
static size_t fixtures_count;

static void load_examples(void)
{
    DIR *dir = opendir(opt.examples);
    if (!dir)
        die("%s: %s (--examples)", opt.examples, strerror(errno));
    char **names = NULL;
    size_t n = 0;
    struct dirent *d;
    while ((d = readdir(dir))) {
        size_t len = strlen(d->d_name);
        if (len > 5 && strcmp(d->d_name + len - 5, ".json") == 0) {
            names = xrealloc(names, (n + 1) * sizeof *names);
            names[n++] = xprintf("%s/%s", opt.examples, d->d_name);
        }
    }
    closedir(dir);
    for (size_t i = 0; i < n; i++) /* a stable order */
        for (size_t j = i + 1; j < n; j++)
            if (strcmp(names[i], names[j]) > 0) {
                char *t = names[i];
                names[i] = names[j];
                names[j] = t;
            }
    for (size_t i = 0; i < n; i++) {
        FILE *file = fopen(names[i], "rb");
        if (!file)
            die("%s: %s", names[i], strerror(errno));
        char *text = xmalloc(1 << 20);
        size_t length = fread(text, 1, (1 << 20) - 1, file);
        fclose(file);
        text[length] = 0;
        cJSON *json = cJSON_Parse(text);
        free(text);
        fixture f;
        if (!json || !fixture_fill(&f, json, opt.describe))
            die("%s: not a valid fixture", names[i]);
        fixtures_all[fixtures_count++] = f;
        free(names[i]);
    }
    free(names);
}

/* ---- building the table ----------------------------------------------------- */

static cJSON *wrench_json(uint64_t *r, const fixture *f)
{
    if (f->has_shape && pick(r, 4) == 0) { /* a force at a point */
        cJSON *w = cJSON_CreateObject();
        add_number_array(w, "force", (double[2]){r4(uniform(r, -1, 1)), r4(uniform(r, -1, 1))}, 2);
        add_number_array(w, "at",
                         (double[2]){r4(f->com[0] + uniform(r, -0.5, 0.5) * f->size),
                                     r4(f->com[1] + uniform(r, -0.5, 0.5) * f->size)},
                         2);
        return w;
    }
    const double g[3] = {r4(uniform(r, -1, 1)), r4(uniform(r, -1, 1)),
                         r4(uniform(r, -0.5, 0.5) * f->size)};
    return cJSON_CreateDoubleArray(g, 3);
}

static const char *const SETS[3] = {"goal", "strong", "both"};

static void add_sets(uint64_t *r, cJSON *params)
{
    int which = pick(r, 8);
    if (which == 0)
        return; /* the default */
    cJSON *sets = cJSON_AddArrayToObject(params, "sets");
    int first = pick(r, 3);
    cJSON_AddItemToArray(sets, cJSON_CreateString(SETS[first]));
    if (which >= 5)
        cJSON_AddItemToArray(sets, cJSON_CreateString(SETS[(first + 1 + pick(r, 2)) % 3]));
}

/* A request on fixture f: by id when stored, else inline. */
static member *add_on_fixture(int category, const fixture *f, bool stored, const char *method,
                              cJSON *params, int check, unsigned flags)
{
    /* params holds "fixture" as a placeholder first member: replace it. */
    cJSON_ReplaceItemInObjectCaseSensitive(params, "fixture", cJSON_Duplicate(f->json, true));
    char *oracle = request_prefix(method, params);
    char *wire = NULL;
    if (stored) {
        cJSON_ReplaceItemInObjectCaseSensitive(params, "fixture", cJSON_CreateString(f->id));
        wire = request_prefix(method, params);
    }
    cJSON_Delete(params);
    if (!wire) {
        wire = oracle;
        oracle = NULL;
    }
    return add_member(category, flags | MEMBER_NOTIFIABLE | MEMBER_BATCHABLE, check, wire, oracle);
}

static cJSON *params_on(void)
{
    cJSON *p = cJSON_CreateObject();
    cJSON_AddNullToObject(p, "fixture");
    return p;
}

static void add_given(member *m, const char *expected_json)
{
    /* An answer known without the oracle: {"jsonrpc":"2.0",...} without id. */
    cJSON *answer = cJSON_Parse(expected_json);
    if (!answer)
        die("internal: bad expected text %s", expected_json);
    m->expected = comparable(answer, m);
    m->answer_errors = count_errors(answer);
    m->requests = 1;
    m->errors = (unsigned long)m->answer_errors;
    m->given = true;
    cJSON_Delete(answer);
}

static char *put_answer(const fixture *f)
{
    cJSON *name = cJSON_CreateString(f->name);
    char *quoted = name ? cJSON_PrintUnformatted(name) : NULL;
    cJSON_Delete(name);
    if (!quoted)
        die("out of memory");
    char *answer = xprintf("{\"jsonrpc\":\"2.0\",\"result\":{\"id\":\"%s\",\"name\":%s,"
                           "\"fixels\":%d,\"goal_cones\":%d,\"strong_cones\":%d,\"pinned\":%s}}",
                           f->id, quoted, f->fixels, f->goal_cones, f->strong_cones,
                           f->pinned ? "true" : "false");
    free(quoted);
    return answer;
}

static member *add_put(const fixture *f)
{
    cJSON *params = cJSON_CreateObject();
    cJSON_AddItemToObject(params, "fixture", cJSON_Duplicate(f->json, true));
    member *m = add_member(CAT_PUT, MEMBER_NOTIFIABLE | MEMBER_BATCHABLE, CHECK_EXACT,
                           request_prefix("fixture.put", params), NULL);
    cJSON_Delete(params);
    char *answer = put_answer(f);
    add_given(m, answer);
    free(answer);
    return m;
}

static member *add_get(const fixture *f)
{
    char *wire = xprintf("{\"jsonrpc\":\"2.0\",\"method\":\"fixture.get\",\"params\":{\"id\":\"%s\"}",
                         f->id);
    member *m = add_member(CAT_GET, MEMBER_NOTIFIABLE | MEMBER_BATCHABLE, CHECK_EXACT, wire, NULL);
    char *answer = xprintf("{\"jsonrpc\":\"2.0\",\"result\":%s}", f->canonical);
    add_given(m, answer);
    free(answer);
    return m;
}

static void add_classify(uint64_t *r, const fixture *f, bool stored, int wrenches, int category)
{
    cJSON *p = params_on();
    cJSON *list = cJSON_AddArrayToObject(p, "wrenches");
    for (int i = 0; i < wrenches; i++)
        cJSON_AddItemToArray(list, wrench_json(r, f));
    add_sets(r, p);
    int check = CHECK_EXACT;
    int method = pick(r, 100);
    if (method < opt.lp_percent) { /* GLPK: the verdicts are compared, not the witnesses */
        cJSON_AddStringToObject(p, "method", "lp");
        check = CHECK_NO_WITNESS;
    } else if (method < opt.lp_percent + (100 - opt.lp_percent) / 4) {
        cJSON_AddStringToObject(p, "method", "auto");
    }
    if (pick(r, 10) == 0)
        cJSON_AddNumberToObject(p, "tolerance", pick(r, 2) ? 0 : 1e-6);
    add_on_fixture(category, f, stored, "wrench.classify", p, check, 0);
}

static void add_queries(uint64_t *r, const fixture *f, bool stored)
{
    add_classify(r, f, stored, 1, CAT_CLASSIFY);
    add_classify(r, f, stored, 1 + pick(r, 3), CAT_CLASSIFY);
    add_classify(r, f, stored, 1 + pick(r, 50), CAT_BATCH_CLASSIFY);

    static const char LETTERS[] = "saulrnm";
    for (int n = 0; n < 2; n++) {
        char text[WR_MAX_FIXELS + 1];
        for (int i = 0; i < f->fixels; i++)
            text[i] = LETTERS[pick(r, 7)];
        text[f->fixels] = 0;
        cJSON *p = params_on();
        cJSON_AddStringToObject(p, "constraints", text);
        add_on_fixture(CAT_CONE, f, stored, "cone.get", p, CHECK_EXACT, 0);
    }
    add_on_fixture(CAT_PLAN, f, stored, "plan.get", params_on(), CHECK_EXACT, 0);
    add_on_fixture(CAT_MODES, f, stored, "modes.get", params_on(), CHECK_EXACT, 0);

    cJSON *p = params_on();
    if (pick(r, 4))
        cJSON_AddStringToObject(p, "set", SETS[pick(r, 3)]);
    if (pick(r, 8) == 0) /* sampled: slower, and exercises more code */
        cJSON_AddNumberToObject(p, "finger_friction", r4(uniform(r, 0.05, 0.4)));
    add_on_fixture(CAT_PUSH, f, stored, "push.regions", p, CHECK_EXACT, 0);

    p = params_on();
    if (pick(r, 4))
        cJSON_AddStringToObject(p, "set", SETS[pick(r, 3)]);
    add_on_fixture(CAT_GRAVITY, f, stored, "gravity.sweep", p, CHECK_EXACT, 0);

    p = params_on();
    cJSON_AddItemToObject(p, "bias", wrench_json(r, f));
    add_on_fixture(CAT_MARGIN, f, stored, "stability.margin", p, CHECK_EXACT, 0);
}

/* Requests that must fail, each with its code and field. */
static void add_bad_params(uint64_t *r, const fixture *f, bool stored)
{
    static const char *const BAD_WRENCHES[] = {
        "[[1,2]]", "[[1,2,\"x\"]]", "[{\"force\":[1,0]}]", "[[1e999,0,0]]",
        "[[0,0,0],[1,2,3,4]]", "{\"x\":1}", "[{\"force\":[1,0],\"at\":[0,0],\"x\":1}]"};
    cJSON *p = params_on();
    cJSON_AddItemToObject(p, "wrenches",
                          cJSON_Parse(BAD_WRENCHES[pick(r, (int)(sizeof BAD_WRENCHES / sizeof *BAD_WRENCHES))]));
    add_on_fixture(CAT_ERROR, f, stored, "wrench.classify", p, CHECK_EXACT, 0);

    p = params_on();
    cJSON_AddItemToObject(p, "wrenches", cJSON_Parse("[[0,-1,0]]"));
    switch (pick(r, 5)) {
    case 0: cJSON_AddItemToObject(p, "sets", cJSON_Parse("[\"goal\",\"goal\"]")); break;
    case 1: cJSON_AddItemToObject(p, "sets", cJSON_Parse("[]")); break;
    case 2: cJSON_AddStringToObject(p, "method", "fast"); break;
    case 3: cJSON_AddNumberToObject(p, "tolerance", -1); break;
    default: cJSON_AddNumberToObject(p, "wrench", 1); break;
    }
    add_on_fixture(CAT_ERROR, f, stored, "wrench.classify", p, CHECK_EXACT, 0);

    p = params_on();
    cJSON_AddStringToObject(p, "constraints", pick(r, 2) ? "zz" : "s");
    add_on_fixture(CAT_ERROR, f, stored, "cone.get", p, CHECK_EXACT, 0);

    p = params_on();
    cJSON_AddNumberToObject(p, "finger_friction", -0.5);
    add_on_fixture(CAT_ERROR, f, stored, "push.regions", p, CHECK_EXACT, 0);

    p = params_on();
    cJSON_AddStringToObject(p, "set", "all");
    add_on_fixture(CAT_ERROR, f, stored, "gravity.sweep", p, CHECK_EXACT, 0);

    /* The required bias left out. */
    add_on_fixture(CAT_ERROR, f, stored, "stability.margin", params_on(), CHECK_EXACT, 0);

    if (opt.max_wrenches <= 1000) { /* over the limit: -32003 */
        p = params_on();
        cJSON *list = cJSON_AddArrayToObject(p, "wrenches");
        for (long i = 0; i <= opt.max_wrenches; i++)
            cJSON_AddItemToArray(list, cJSON_CreateDoubleArray((double[3]){0, -1, 0}, 3));
        add_on_fixture(CAT_ERROR, f, stored, "wrench.classify", p, CHECK_EXACT, 0);
    }
}

static void add_fixed_errors(uint64_t *r)
{
    /* Ids never stored: -32001; only their wording is the daemon's own. */
    char unknown[WP_ID_LENGTH + 1];
    for (int i = 0; i < WP_ID_LENGTH; i++)
        unknown[i] = "0123456789abcdef"[pick(r, 16)];
    unknown[WP_ID_LENGTH] = 0;
    const unsigned req = MEMBER_NOTIFIABLE | MEMBER_BATCHABLE;
    add_member(CAT_ERROR, req, CHECK_LOOSE,
               xprintf("{\"jsonrpc\":\"2.0\",\"method\":\"wrench.classify\",\"params\":{\"fixture\":"
                       "\"%s\",\"wrenches\":[[0,-1,0]]}", unknown), NULL);
    add_member(CAT_ERROR, req, CHECK_LOOSE,
               xprintf("{\"jsonrpc\":\"2.0\",\"method\":\"fixture.get\",\"params\":{\"id\":\"%s\"}",
                       unknown), NULL);
    add_member(CAT_ERROR, req, CHECK_LOOSE,
               xprintf("{\"jsonrpc\":\"2.0\",\"method\":\"plan.get\",\"params\":{\"fixture\":\"%s\"}",
                       unknown), NULL);
    add_member(CAT_ERROR, req, CHECK_LOOSE,
               xprintf("{\"jsonrpc\":\"2.0\",\"method\":\"fixture.delete\",\"params\":{\"id\":\"%s\"}",
                       unknown), NULL);
    static const char *const BAD_REQUESTS[] = {
        "{\"jsonrpc\":\"2.0\",\"method\":\"no.such.method\"",
        "{\"jsonrpc\":\"2.0\",\"method\":\"wrench.classify\",\"params\":[1]",
        "{\"jsonrpc\":\"2.0\",\"method\":\"wrench.classify\",\"params\":{\"wrenches\":[[0,0,0]]}",
        "{\"jsonrpc\":\"2.0\",\"method\":\"fixture.get\",\"params\":{\"id\":\"XYZ\"}",
        "{\"jsonrpc\":\"2.0\",\"method\":\"fixture.get\",\"params\":{\"id\":42}",
        "{\"jsonrpc\":\"2.0\",\"method\":\"plan.get\",\"params\":{\"fixture\":17}",
        "{\"jsonrpc\":\"2.0\",\"method\":\"server.status\",\"params\":{\"verbose\":true}",
        "{\"jsonrpc\":\"2.0\",\"method\":\"fixture.put\",\"params\":{\"fixture\":{\"body\":{\"mass\":-1},"
        "\"friction\":{\"static\":0.2},\"fixels\":[{\"at\":[0,0],\"normal\":[0,1]}]}}",
        "{\"jsonrpc\":\"2.0\",\"method\":\"fixture.put\",\"params\":{\"fixture\":{\"body\":{\"mass\":1,"
        "\"shape\":{\"type\":\"circle\",\"center\":[0,0],\"radius\":1}},\"friction\":{\"static\":0.2},"
        "\"fixels\":[{\"at\":[5,0]}]}}",
        "{\"jsonrpc\":\"2.0\",\"method\":\"fixture.list\",\"params\":{\"all\":1}",
    };
    for (size_t i = 0; i < sizeof BAD_REQUESTS / sizeof *BAD_REQUESTS; i++)
        add_member(CAT_ERROR, req, CHECK_EXACT, xstrdup(BAD_REQUESTS[i]), NULL);
    /* Invalid requests: answered even without an id, so never notifications. */
    add_member(CAT_ERROR, MEMBER_BATCHABLE, CHECK_EXACT,
               xstrdup("{\"jsonrpc\":\"1.0\",\"method\":\"server.status\""), NULL);
    add_member(CAT_ERROR, MEMBER_BATCHABLE, CHECK_EXACT,
               xstrdup("{\"jsonrpc\":\"2.0\",\"method\":7"), NULL);
    add_member(CAT_ERROR, MEMBER_BATCHABLE, CHECK_EXACT,
               xstrdup("{\"jsonrpc\":\"2.0\",\"method\":\"server.status\",\"extra\":1"), NULL);

    /* Whole lines, sent as they are. */
    static const char *const RAW[] = {
        "",
        "   ",
        "not json",
        "{\"jsonrpc\":\"2.0\",\"method\":\"server.status\"",
        "{\"jsonrpc\":\"2.0\",\"method\":\"fixture.list\",\"id\":1} trailing",
        "[]",
        "[1,2]",
        /* A notification that succeeds (not server.status: in process it
         * fails, while the daemon's succeeds, and the error counts differ). */
        "[1,{\"jsonrpc\":\"2.0\",\"method\":\"modes.get\",\"params\":{\"fixture\":"
        "{\"body\":{\"mass\":1,\"inertia\":0.5,\"shape\":{\"type\":\"circle\",\"center\":[0,0],"
        "\"radius\":1}},\"friction\":{\"static\":0.5},\"fixels\":[{\"at\":[-1,0]},{\"at\":[0,-1]}]}}}]",
        "\"just a string\"",
        "{\"jsonrpc\":\"2.0\",\"method\":\"fixture.list\",\"id\":{\"a\":1}}",
        "{\"jsonrpc\":\"2.0\",\"method\":\"fixture.li\\u0000st\",\"id\":3}",
        "{\"jsonrpc\":\"2.0\",\"method\":\"no.such\",\"id\":\"\\u00e9\\ud83d\\ude00\"}",
        "{\"jsonrpc\":\"2.0\",\"method\":\"server.status\",\"id\":\"\xff\xfe\"}",
        "{\"jsonrpc\":\"2.0\",\"method\":\"no.such\",\"id\":null}",
        "[{\"jsonrpc\":\"2.0\",\"method\":\"plan.get\"}]", /* a notification: no answer at all */
    };
    for (size_t i = 0; i < sizeof RAW / sizeof *RAW; i++)
        add_member(CAT_RAW, MEMBER_RAW, CHECK_EXACT, xstrdup(RAW[i]), NULL);
    /* Nesting deeper than --max-depth. */
    size_t depth = (size_t)opt.max_depth + 2;
    char *deep = xmalloc(2 * depth + 128);
    size_t n = (size_t)sprintf(deep, "{\"jsonrpc\":\"2.0\",\"method\":\"cone.get\",\"params\":{\"x\":");
    for (size_t i = 0; i < depth; i++)
        deep[n++] = '[';
    for (size_t i = 0; i < depth; i++)
        deep[n++] = ']';
    sprintf(deep + n, "},\"id\":9}");
    add_member(CAT_RAW, MEMBER_RAW, CHECK_EXACT, deep, NULL);
    /* A batch over --max-batch (of notifications: nothing would be answered). */
    if (opt.max_batch <= 2000) {
        char *big = NULL;
        size_t length = 0, capacity = 0;
        append(&big, &length, &capacity, "[");
        for (long i = 0; i <= opt.max_batch; i++)
            append(&big, &length, &capacity,
                   i ? ",{\"jsonrpc\":\"2.0\",\"method\":\"server.status\"}"
                     : "{\"jsonrpc\":\"2.0\",\"method\":\"server.status\"}");
        append(&big, &length, &capacity, "]");
        add_member(CAT_RAW, MEMBER_RAW, CHECK_EXACT, big, NULL);
    }
    /* Batchable invalid members: answered with id null inside a batch. */
    add_member(CAT_RAW, MEMBER_RAW | MEMBER_BATCHABLE, CHECK_EXACT, xstrdup("1"), NULL);
    add_member(CAT_RAW, MEMBER_RAW | MEMBER_BATCHABLE, CHECK_EXACT,
               xstrdup("{\"jsonrpc\":\"2.0\",\"id\":null}"), NULL);
}

static void add_status_and_list(void)
{
    member *m = add_member(CAT_STATUS, MEMBER_NOTIFIABLE | MEMBER_BATCHABLE, CHECK_STATUS,
                           xstrdup("{\"jsonrpc\":\"2.0\",\"method\":\"server.status\",\"params\":{}"),
                           NULL);
    add_given(m, "{\"jsonrpc\":\"2.0\",\"result\":{\"version\":\"string\",\"uptime_s\":0,"
                 "\"fixtures\":0,\"cached\":0,\"cache_bytes\":0,\"cache_limit_bytes\":0,"
                 "\"threads\":0,\"clients\":0,\"refused\":0,\"denied\":0,\"requests\":0,"
                 "\"errors\":0}}");
    m = add_member(CAT_LIST, MEMBER_NOTIFIABLE | MEMBER_BATCHABLE, CHECK_LIST,
                   xstrdup("{\"jsonrpc\":\"2.0\",\"method\":\"fixture.list\""), NULL);
    add_given(m, "{\"jsonrpc\":\"2.0\",\"result\":{\"ok\":true}}");
}

/* ---- the oracle: expected answers, computed in process ---------------------- */

static void oracle_answer(const wp_host *host, member *m)
{
    if (m->given)
        return;
    const char *text = m->oracle ? m->oracle : m->wire;
    char *line = (m->flags & MEMBER_RAW) ? xstrdup(text) : xprintf("%s,\"id\":0}", text);
    wp_limits limits = {.max_depth = opt.max_depth,
                        .max_wrenches = (size_t)opt.max_wrenches,
                        .max_batch = (size_t)opt.max_batch};
    wp_counts counts = {0, 0};
    char *answer = wp_answer_line(host, &limits, line, strlen(line), &counts);
    free(line);
    m->requests = counts.requests;
    m->errors = counts.errors;
    if (!answer) {
        m->expected = NULL;
        return;
    }
    cJSON *json = cJSON_Parse(answer);
    if (!json)
        die("internal: the oracle answered %s", answer);
    free(answer);
    m->answer_errors = count_errors(json);
    m->expected = comparable(json, m);
    cJSON_Delete(json);
}

typedef struct oracle_job {
    int index, of;
} oracle_job;

static void *oracle_thread(void *argument)
{
    oracle_job *job = argument;
    wp_local *local = wp_local_new();
    if (!local)
        die("out of memory");
    for (size_t i = (size_t)job->index; i < T.count; i += (size_t)job->of)
        oracle_answer(wp_local_host(local), &T.items[i]);
    wp_local_free(local);
    return NULL;
}

static void compute_expected(void)
{
    long cores = sysconf(_SC_NPROCESSORS_ONLN);
    int n = cores > 0 ? (int)cores : 1;
    if (n > 16)
        n = 16;
    pthread_t threads[16];
    oracle_job jobs[16];
    for (int i = 0; i < n; i++) {
        jobs[i] = (oracle_job){i, n};
        if (pthread_create(&threads[i], NULL, oracle_thread, &jobs[i]) != 0)
            die("cannot start a thread");
    }
    for (int i = 0; i < n; i++)
        pthread_join(threads[i], NULL);
}

/* ---- private fixtures: a store only one client changes ---------------------- */

enum { PRIV_PUT, PRIV_GET, PRIV_CLASSIFY, PRIV_DELETE, PRIV_OPS };

typedef struct private_ops {
    /* [op][stored before it ran] */
    member m[PRIV_OPS][2];
} private_ops;

static void private_member(member *m, char *wire, char *oracle, int check)
{
    memset(m, 0, sizeof *m);
    m->category = -1;
    m->flags = MEMBER_NOTIFIABLE | MEMBER_BATCHABLE;
    m->check = check;
    m->wire = wire;
    m->oracle = oracle;
}

static void make_private(private_ops *ops, int client, wp_local *local)
{
    uint64_t r = opt.seed * 1000003u + 7777u + (uint64_t)client;
    char name[64];
    snprintf(name, sizeof name, "private-%llu-%d", (unsigned long long)opt.seed, client);
    fixture f = generated_fixture(&r, name);
    /* Content no other client has: a mass of its own. */
    cJSON *json = f.json;
    fixture_release(&f);
    cJSON_ReplaceItemInObjectCaseSensitive(cJSON_GetObjectItemCaseSensitive(json, "body"), "mass",
                                           cJSON_CreateNumber(1 + 0.001 * (client + 1)));
    if (!fixture_fill(&f, json, false))
        die("internal: a private fixture is invalid");
    json = f.json;
    const wp_host *host = wp_local_host(local);
    for (int stored = 0; stored < 2; stored++) {
        cJSON *params = cJSON_CreateObject();
        cJSON_AddItemToObject(params, "fixture", cJSON_Duplicate(f.json, true));
        private_member(&ops->m[PRIV_PUT][stored], request_prefix("fixture.put", params), NULL,
                       CHECK_EXACT);
        cJSON_Delete(params);
        char *answer = put_answer(&f);
        add_given(&ops->m[PRIV_PUT][stored], answer);
        free(answer);

        char *get = xprintf("{\"jsonrpc\":\"2.0\",\"method\":\"fixture.get\",\"params\":{\"id\":\"%s\"}", f.id);
        private_member(&ops->m[PRIV_GET][stored], get, NULL, CHECK_LOOSE);
        char *del = xprintf("{\"jsonrpc\":\"2.0\",\"method\":\"fixture.delete\",\"params\":{\"id\":\"%s\"}", f.id);
        private_member(&ops->m[PRIV_DELETE][stored], del, NULL, CHECK_LOOSE);
        uint64_t wr = r; /* the same wrenches whether stored or not */
        cJSON *p = cJSON_CreateObject();
        cJSON_AddStringToObject(p, "fixture", f.id);
        cJSON *list = cJSON_AddArrayToObject(p, "wrenches");
        for (int i = 0; i < 3; i++)
            cJSON_AddItemToArray(list, wrench_json(&wr, &f));
        char *wire = request_prefix("wrench.classify", p);
        cJSON_ReplaceItemInObjectCaseSensitive(p, "fixture", cJSON_Duplicate(f.json, true));
        char *oracle = stored ? request_prefix("wrench.classify", p) : NULL;
        cJSON_Delete(p);
        private_member(&ops->m[PRIV_CLASSIFY][stored], wire, oracle, CHECK_LOOSE);
        if (stored) {
            answer = xprintf("{\"jsonrpc\":\"2.0\",\"result\":%s}", f.canonical);
            add_given(&ops->m[PRIV_GET][stored], answer);
            free(answer);
            add_given(&ops->m[PRIV_DELETE][stored], "{\"jsonrpc\":\"2.0\",\"result\":{\"deleted\":true}}");
        } else {
            oracle_answer(host, &ops->m[PRIV_GET][stored]);
            oracle_answer(host, &ops->m[PRIV_DELETE][stored]);
        }
        oracle_answer(host, &ops->m[PRIV_CLASSIFY][stored]);
    }
    fixture_release(&f);
    cJSON_Delete(json);
}

/* ---- connections ----------------------------------------------------------------- */

typedef struct conn {
    int fd;
    char *buffer;
    size_t length, capacity, consumed, scanned;
} conn;

static int conn_open(conn *c)
{
    memset(c, 0, sizeof *c);
    struct sockaddr_un address = {.sun_family = AF_UNIX};
    if (strlen(opt.socket_path) >= sizeof address.sun_path)
        return -1;
    strcpy(address.sun_path, opt.socket_path);
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
    c->capacity = 1 << 16;
    c->buffer = xmalloc(c->capacity);
    return 0;
}

static void conn_close(conn *c)
{
    if (c->fd >= 0)
        close(c->fd);
    c->fd = -1;
    free(c->buffer);
    c->buffer = NULL;
}

static bool conn_write(conn *c, const char *text, size_t length)
{
    size_t done = 0;
    while (done < length) {
        struct pollfd p = {c->fd, POLLOUT, 0};
        int ready = poll(&p, 1, opt.timeout_s * 1000);
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
static char *conn_read_line(conn *c, size_t *length, const char **why)
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
        int ready = poll(&p, 1, opt.timeout_s * 1000);
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

/* ---- clients ------------------------------------------------------------------- */

#define MAX_BATCH 8

typedef struct sent_id {
    bool numeric;
    double number;
    char text[32];
} sent_id;

typedef struct pending {
    double sent_us;
    bool batch;
    int count;                       /* answered members */
    const member *members[MAX_BATCH];
    sent_id ids[MAX_BATCH];
    char *line;                      /* the line sent, kept for reports */
} pending;

typedef struct client_stats {
    unsigned long lines, requests, batches, notifications, answered_lines;
    unsigned long answers_expected_errors, answers_seen_errors;
    unsigned long server_requests, server_errors; /* what the daemon should count */
    unsigned long wrong, lost, unexpected;
    bool failed;                     /* the connection broke or timed out */
    char failure[160];
    double *latency;
    size_t latency_count, latency_capacity;
    unsigned long by_category[CAT_COUNT + 1];
} client_stats;

typedef struct client {
    int index;
    uint64_t rng;
    conn c;
    pending *ring;
    int head, inflight;
    unsigned long next_id;
    private_ops *priv;
    bool priv_stored, priv_known;
    client_stats stats;
    /* warm-up: a script of members, each sent once */
    const member **script;
    size_t script_count, script_next;
} client;

static pthread_mutex_t report_lock = PTHREAD_MUTEX_INITIALIZER;
static int reports_printed;
#define MAX_REPORTS 12

static void report(const client *cl, const char *what, const char *sent, const char *expected,
                   const char *seen)
{
    pthread_mutex_lock(&report_lock);
    if (reports_printed++ < MAX_REPORTS) {
        fprintf(stderr, "load: client %d: %s\n", cl->index, what);
        if (sent)
            fprintf(stderr, "  request:  %.600s%s\n", sent, strlen(sent) > 600 ? "..." : "");
        if (expected)
            fprintf(stderr, "  expected: %.600s%s\n", expected, strlen(expected) > 600 ? "..." : "");
        if (seen)
            fprintf(stderr, "  observed: %.600s%s\n", seen, strlen(seen) > 600 ? "..." : "");
    }
    pthread_mutex_unlock(&report_lock);
}

static void add_latency(client_stats *s, double us)
{
    if (s->latency_count == s->latency_capacity) {
        s->latency_capacity = s->latency_capacity ? 2 * s->latency_capacity : 4096;
        s->latency = xrealloc(s->latency, s->latency_capacity * sizeof *s->latency);
    }
    s->latency[s->latency_count++] = us;
}

static sent_id make_id(client *cl)
{
    sent_id id = {0};
    unsigned long n = cl->next_id++;
    if (n % 4 == 3) {
        id.numeric = true;
        id.number = (double)cl->index * 1e9 + (double)n;
        snprintf(id.text, sizeof id.text, "%.0f", id.number);
    } else {
        snprintf(id.text, sizeof id.text, "\"c%d-%lu\"", cl->index, n);
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

/* Which member a line carries, and whether it goes as a notification. */
typedef struct choice {
    const member *m;
    bool notify;
} choice;

static const member *pick_category(client *cl, int category)
{
    size_t n = T.category_count[category];
    return n ? &T.items[T.by_category[category][rnd(&cl->rng) % n]] : NULL;
}

static const member *pick_single(client *cl)
{
    int total = 0;
    for (int i = 0; i < CAT_COUNT; i++)
        total += T.category_count[i] ? CAT_WEIGHTS[i] : 0;
    int x = pick(&cl->rng, total);
    for (int i = 0; i < CAT_COUNT; i++) {
        int w = T.category_count[i] ? CAT_WEIGHTS[i] : 0;
        if (x < w)
            return pick_category(cl, i);
        x -= w;
    }
    return pick_category(cl, CAT_CLASSIFY);
}

static const member *private_op(client *cl)
{
    int op = cl->priv_known ? pick(&cl->rng, PRIV_OPS) : PRIV_PUT;
    const member *m = &cl->priv->m[op][cl->priv_stored ? 1 : 0];
    if (op == PRIV_PUT)
        cl->priv_stored = cl->priv_known = true;
    else if (op == PRIV_DELETE)
        cl->priv_stored = false;
    return m;
}

/* Build the next line; fill `p` with what answers it expects.  Returns false
 * when it expects no answer at all. */
static bool next_line(client *cl, char **line, size_t *length, pending *p)
{
    size_t capacity = 0;
    *line = NULL;
    *length = 0;
    memset(p, 0, sizeof *p);
    choice items[MAX_BATCH];
    int count = 0;
    bool batch = false;
    if (cl->script) {
        items[count++] = (choice){cl->script[cl->script_next++], false};
    } else {
        int roll = pick(&cl->rng, 100);
        if (roll < 8) { /* a JSON-RPC batch */
            batch = true;
            count = 1 + pick(&cl->rng, MAX_BATCH);
            for (int i = 0; i < count; i++) {
                const member *m;
                int kind = pick(&cl->rng, 20);
                if (kind == 0 && cl->priv)
                    m = private_op(cl);
                else if (kind == 1)
                    m = &T.items[T.batchable[rnd(&cl->rng) % T.batchable_count]];
                else
                    do
                        m = pick_single(cl);
                    while (!(m->flags & MEMBER_BATCHABLE));
                items[i] = (choice){m, (m->flags & MEMBER_NOTIFIABLE) && pick(&cl->rng, 8) == 0};
            }
        } else if (roll < 10 && cl->priv) {
            items[count++] = (choice){private_op(cl), false};
        } else {
            const member *m = pick_single(cl);
            items[count++] = (choice){m, (m->flags & MEMBER_NOTIFIABLE) && pick(&cl->rng, 25) == 0};
        }
    }
    if (batch)
        append(line, length, &capacity, "[");
    for (int i = 0; i < count; i++) {
        const member *m = items[i].m;
        if (i)
            append(line, length, &capacity, ",");
        append(line, length, &capacity, m->wire);
        cl->stats.requests += m->requests;
        cl->stats.server_requests += m->requests;
        cl->stats.server_errors += m->errors;
        cl->stats.by_category[m->category >= 0 ? m->category : CAT_COUNT]++;
        if (m->flags & MEMBER_RAW) {
            if (m->expected) {
                p->members[p->count] = m;
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
        sent_id id = make_id(cl);
        append(line, length, &capacity, ",\"id\":");
        append(line, length, &capacity, id.text);
        append(line, length, &capacity, "}");
        p->members[p->count] = m;
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

/* Compare one answer object with what a member expects. */
static bool check_member(client *cl, const pending *p, int i, cJSON *answer, const char *line)
{
    const member *m = p->members[i];
    bool raw = (m->flags & MEMBER_RAW) != 0;
    cl->stats.answers_expected_errors += (unsigned long)m->answer_errors;
    cl->stats.answers_seen_errors += (unsigned long)count_errors(answer);
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
    char *seen = comparable(answer, m);
    bool ok = strcmp(seen, m->expected) == 0;
    if (!ok)
        report(cl, "wrong answer", p->line, m->expected, seen);
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
            ok = check_member(cl, p, i, a, line);
    } else {
        ok = check_member(cl, p, 0, answer, line);
    }
    return ok;
}

/* Which line in flight an answer is for, by the first id it carries. */
static int find_pending(client *cl, const cJSON *answer)
{
    const cJSON *first = cJSON_IsArray(answer) ? answer->child : answer;
    int found = -1;
    for (int k = 0; first && k < cl->inflight && found < 0; k++) {
        const pending *p = &cl->ring[(cl->head + k) % opt.pipeline];
        bool raw = (p->members[0]->flags & MEMBER_RAW) != 0;
        if (raw && !p->batch)
            continue; /* a raw line's answer is known only by its place */
        if (id_matches(first, &p->ids[0], raw))
            found = k;
    }
    return found;
}

static void pop_pending(client *cl)
{
    pending *p = &cl->ring[cl->head];
    free(p->line);
    p->line = NULL;
    cl->head = (cl->head + 1) % opt.pipeline;
    cl->inflight--;
}

static void take_answer(client *cl, char *line, size_t length)
{
    double arrived = now_us();
    if (cl->inflight == 0) {
        cl->stats.unexpected++;
        report(cl, "an answer to no request (a notification answered?)", NULL, NULL, line);
        return;
    }
    cJSON *answer = cJSON_ParseWithLength(line, length);
    pending *p = &cl->ring[cl->head];
    bool head_raw = (p->members[0]->flags & MEMBER_RAW) && !p->batch;
    if (!head_raw && answer) {
        int k = find_pending(cl, answer);
        if (k < 0) {
            /* Not the answer to anything in flight: answered twice, or a
             * notification answered.  The head stays in flight. */
            cl->stats.unexpected++;
            report(cl, "an answer whose id matches no request in flight", p->line, NULL, line);
            cJSON_Delete(answer);
            return;
        }
        for (int i = 0; i < k; i++) { /* answers skipped: lost */
            pending *q = &cl->ring[cl->head];
            cl->stats.lost += (unsigned long)q->count;
            report(cl, "no answer (a later one came first)", q->line, NULL, NULL);
            pop_pending(cl);
        }
        p = &cl->ring[cl->head];
    }
    add_latency(&cl->stats, arrived - p->sent_us);
    cl->stats.answered_lines++;
    if (!check_line(cl, p, answer, line))
        cl->stats.wrong++;
    cJSON_Delete(answer);
    pop_pending(cl);
}

static volatile sig_atomic_t stop_now;
static double deadline_us;

static bool more_to_send(client *cl)
{
    if (stop_now)
        return false;
    if (cl->script)
        return cl->script_next < cl->script_count;
    if (opt.duration > 0)
        return now_us() < deadline_us;
    return (long)cl->stats.lines < opt.requests;
}

static void fail(client *cl, const char *what, const char *why)
{
    cl->stats.failed = true;
    snprintf(cl->stats.failure, sizeof cl->stats.failure, "%s: %s", what, why);
}

static void *client_main(void *argument)
{
    client *cl = argument;
    cl->ring = calloc((size_t)opt.pipeline, sizeof *cl->ring);
    if (!cl->ring)
        die("out of memory");
    if (conn_open(&cl->c) != 0) {
        fail(cl, "connect", strerror(errno));
        free(cl->ring);
        return NULL;
    }
    const char *why = NULL;
    while (!cl->stats.failed) {
        while (cl->inflight < opt.pipeline && more_to_send(cl)) {
            pending p;
            char *line;
            size_t length;
            bool answered = next_line(cl, &line, &length, &p);
            p.sent_us = now_us();
            cl->stats.lines++;
            if (!conn_write(&cl->c, line, length)) {
                fail(cl, "write", strerror(errno));
                free(line);
                break;
            }
            if (answered) {
                line[length - 1] = 0;
                p.line = line;
                cl->ring[(cl->head + cl->inflight) % opt.pipeline] = p;
                cl->inflight++;
            } else {
                free(line);
            }
        }
        if (cl->stats.failed || cl->inflight == 0) {
            if (!more_to_send(cl))
                break;
            continue;
        }
        size_t length;
        char *line = conn_read_line(&cl->c, &length, &why);
        if (!line) {
            fail(cl, "read", why);
            break;
        }
        take_answer(cl, line, length);
    }
    /* Whatever is still in flight now will not be answered. */
    while (cl->inflight > 0) {
        pending *q = &cl->ring[cl->head];
        cl->stats.lost += (unsigned long)q->count;
        report(cl, "no answer", q->line, NULL, cl->stats.failure);
        pop_pending(cl);
    }
    if (!cl->stats.failed) {
        /* Nothing more may come: no answers to notifications, no extras. */
        shutdown(cl->c.fd, SHUT_WR);
        size_t length;
        char *line;
        while ((line = conn_read_line(&cl->c, &length, &why)))
            take_answer(cl, line, length);
        if (strcmp(why, "end of input") != 0)
            fail(cl, "waiting for the end of input", why);
    }
    conn_close(&cl->c);
    free(cl->ring);
    return NULL;
}

/* ---- server counters ------------------------------------------------------------ */

static bool server_counts(double *requests, double *errors)
{
    conn c;
    if (conn_open(&c) != 0)
        return false;
    const char *request = "{\"jsonrpc\":\"2.0\",\"method\":\"server.status\",\"id\":\"counts\"}\n";
    const char *why;
    size_t length;
    char *line = conn_write(&c, request, strlen(request)) ? conn_read_line(&c, &length, &why) : NULL;
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
    conn_close(&c);
    return ok;
}

/* ---- the table as a whole ------------------------------------------------------ */

static void index_table(void)
{
    for (int c = 0; c < CAT_COUNT; c++) {
        T.by_category[c] = xmalloc(T.count * sizeof(size_t));
        T.category_count[c] = 0;
    }
    T.batchable = xmalloc(T.count * sizeof(size_t));
    for (size_t i = 0; i < T.count; i++) {
        member *m = &T.items[i];
        T.by_category[m->category][T.category_count[m->category]++] = i;
        if ((m->flags & MEMBER_RAW) && (m->flags & MEMBER_BATCHABLE))
            T.batchable[T.batchable_count++] = i;
    }
}

static void build_table(void)
{
    uint64_t r = opt.seed * 0x2545f4914f6cdd1dull + 1;
    size_t capacity = 64 + (size_t)opt.stored + (size_t)opt.fixtures;
    fixtures_all = xmalloc(capacity * sizeof *fixtures_all);
    load_examples();
    for (int i = 0; i < opt.stored; i++) {
        char name[64];
        snprintf(name, sizeof name, "stored-%llu-%d", (unsigned long long)opt.seed, i);
        fixtures_all[fixtures_count++] = generated_fixture(&r, name);
    }
    size_t stored_count = fixtures_count;
    for (int i = 0; i < opt.fixtures; i++) {
        char name[64];
        snprintf(name, sizeof name, "inline-%llu-%d", (unsigned long long)opt.seed, i);
        fixtures_all[fixtures_count++] = generated_fixture(&r, name);
    }
    /* Two fixtures of equal content would be one stored fixture with two
     * names: keep the first of each id. */
    for (size_t i = 0; i < fixtures_count; i++)
        for (size_t j = 0; j < i; j++)
            if (strcmp(fixtures_all[i].id, fixtures_all[j].id) == 0)
                die("two fixtures of the table have the same content (%s); change --seed",
                    fixtures_all[i].id);
    shared = xmalloc(stored_count * sizeof *shared);
    for (size_t i = 0; i < stored_count; i++) {
        fixture *f = &fixtures_all[i];
        memcpy(shared[i].id, f->id, sizeof shared[i].id);
        shared[i].name = f->name;
        shared[i].fixels = f->fixels;
        add_put(f);
    }
    shared_count = stored_count;
    qsort(shared, shared_count, sizeof *shared, compare_ids);
    for (size_t i = 0; i < fixtures_count; i++) {
        bool stored = i < stored_count;
        if (stored)
            add_get(&fixtures_all[i]);
        add_queries(&r, &fixtures_all[i], stored);
        /* Bad params on a few fixtures, by id and inline. */
        if (i < stored_count + 4 || i % 8 == 0)
            add_bad_params(&r, &fixtures_all[i], stored);
    }
    add_fixed_errors(&r);
    add_status_and_list();
    index_table();
}

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
    for (int i = 0; i <= CAT_COUNT; i++)
        into->by_category[i] += s->by_category[i];
    if (s->latency_count) {
        into->latency = xrealloc(into->latency,
                                 (into->latency_count + s->latency_count) * sizeof *into->latency);
        memcpy(into->latency + into->latency_count, s->latency,
               s->latency_count * sizeof *s->latency);
        into->latency_count += s->latency_count;
    }
}

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
            opt.socket_path = argv[++i];
        else if (strcmp(a, "--examples") == 0 && i + 1 < argc)
            opt.examples = argv[++i];
        else if (strcmp(a, "--clients") == 0)
            opt.clients = (int)number_arg(argc, argv, &i, 1, 4096);
        else if (strcmp(a, "--requests") == 0)
            opt.requests = number_arg(argc, argv, &i, 1, 1000000000L);
        else if (strcmp(a, "--pipeline") == 0)
            opt.pipeline = (int)number_arg(argc, argv, &i, 1, 1000);
        else if (strcmp(a, "--seed") == 0)
            opt.seed = (uint64_t)number_arg(argc, argv, &i, 0, 1000000000000L);
        else if (strcmp(a, "--duration") == 0)
            opt.duration = (double)number_arg(argc, argv, &i, 1, 100000000L);
        else if (strcmp(a, "--fixtures") == 0)
            opt.fixtures = (int)number_arg(argc, argv, &i, 0, 1000000);
        else if (strcmp(a, "--stored") == 0)
            opt.stored = (int)number_arg(argc, argv, &i, 0, 100000);
        else if (strcmp(a, "--max-wrenches") == 0)
            opt.max_wrenches = number_arg(argc, argv, &i, 1, 1000000000L);
        else if (strcmp(a, "--lp") == 0)
            opt.lp_percent = (int)number_arg(argc, argv, &i, 0, 100);
        else if (strcmp(a, "--max-batch") == 0)
            opt.max_batch = number_arg(argc, argv, &i, 1, 1000000000L);
        else if (strcmp(a, "--max-depth") == 0)
            opt.max_depth = (int)number_arg(argc, argv, &i, 1, 100000);
        else if (strcmp(a, "--timeout") == 0)
            opt.timeout_s = (int)number_arg(argc, argv, &i, 1, 100000);
        else if (strcmp(a, "--quiet") == 0)
            opt.quiet = true;
        else if (strcmp(a, "--no-count-check") == 0)
            opt.count_check = false;
        else if (strcmp(a, "--describe") == 0)
            opt.describe = true;
        else if (strcmp(a, "--dump") == 0)
            opt.dump = opt.describe = true;
        else if (strcmp(a, "--help") == 0 || strcmp(a, "-h") == 0) {
            usage(stdout);
            exit(0);
        } else {
            fprintf(stderr, "load: unknown option or missing value: %s\n", a);
            usage(stderr);
            exit(2);
        }
    }
    if (!opt.socket_path && !opt.describe) {
        fprintf(stderr, "load: --socket PATH is required\n");
        usage(stderr);
        exit(2);
    }
}

static void describe(double build_seconds)
{
    size_t inline_bytes = 0, inline_max = 0, lp_max = 0, lp_sum = 0;
    size_t stored_count = shared_count;
    for (size_t i = 0; i < fixtures_count; i++) {
        const fixture *f = &fixtures_all[i];
        if (i >= stored_count) {
            inline_bytes += f->analysis_bytes;
            if (f->analysis_bytes > inline_max)
                inline_max = f->analysis_bytes;
        }
        lp_sum += f->lp_bytes;
        if (f->lp_bytes > lp_max)
            lp_max = f->lp_bytes;
    }
    size_t stored_bytes = 0;
    for (size_t i = 0; i < stored_count; i++)
        stored_bytes += fixtures_all[i].analysis_bytes;
    size_t expected_bytes = 0;
    for (size_t i = 0; i < T.count; i++)
        expected_bytes += T.items[i].expected ? strlen(T.items[i].expected) : 0;
    printf("table_members=%zu\n", T.count);
    for (int c = 0; c < CAT_COUNT; c++)
        printf("table_%s=%zu\n", CAT_NAMES[c], T.category_count[c]);
    printf("stored_fixtures=%zu\nstored_derived_bytes=%zu\n", stored_count, stored_bytes);
    printf("inline_fixtures=%zu\ninline_derived_bytes=%zu\ninline_derived_max=%zu\n",
           fixtures_count - stored_count, inline_bytes, inline_max);
    printf("lp_bytes_max=%zu\nlp_bytes_mean=%zu\n", lp_max,
           fixtures_count ? lp_sum / fixtures_count : 0);
    printf("expected_text_bytes=%zu\nbuild_seconds=%.2f\n", expected_bytes, build_seconds);
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

    double t0 = now_us();
    build_table();
    compute_expected();
    private_ops *privs = xmalloc((size_t)opt.clients * sizeof *privs);
    {
        wp_local *local = wp_local_new();
        if (!local)
            die("out of memory");
        for (int i = 0; i < opt.clients; i++)
            make_private(&privs[i], i, local);
        wp_local_free(local);
    }
    double build_seconds = (now_us() - t0) / 1e6;
    if (opt.dump) {
        /* One member per three lines: the request (with id 0 unless raw),
         * "requests errors" as the daemon counts them, the expected answer. */
        for (size_t i = 0; i < T.count; i++) {
            const member *m = &T.items[i];
            printf("%s%s\n%lu %lu\n%s\n", m->wire, (m->flags & MEMBER_RAW) ? "" : ",\"id\":0}",
                   m->requests, m->errors, m->expected ? m->expected : "(no answer)");
        }
        return 0;
    }
    if (opt.describe) {
        describe(build_seconds);
        return 0;
    }
    if (!opt.quiet)
        fprintf(stderr, "load: %zu requests in the table (%zu fixtures), expected answers in %.1f s\n",
                T.count, fixtures_count, build_seconds);

    double base_requests = 0, base_errors = 0;
    if (!server_counts(&base_requests, &base_errors)) {
        fprintf(stderr, "load: no daemon answers server.status on %s\n", opt.socket_path);
        return 3;
    }

    /* Warm-up: the shared fixtures stored, then every request once, in order. */
    client warm;
    memset(&warm, 0, sizeof warm);
    warm.index = -1;
    warm.script = xmalloc(T.count * sizeof *warm.script);
    for (size_t i = 0; i < T.count; i++) /* puts first: the table begins with them */
        warm.script[warm.script_count++] = &T.items[i];
    int saved_pipeline = opt.pipeline;
    opt.pipeline = 1;
    double w0 = now_us();
    client_main(&warm);
    double warm_seconds = (now_us() - w0) / 1e6;
    opt.pipeline = saved_pipeline;
    if (!opt.quiet)
        fprintf(stderr, "load: warm-up: %lu lines in %.1f s, %lu wrong, %lu lost%s%s\n",
                warm.stats.lines, warm_seconds, warm.stats.wrong, warm.stats.lost,
                warm.stats.failed ? ", " : "", warm.stats.failed ? warm.stats.failure : "");

    /* The load. */
    client *clients = calloc((size_t)opt.clients, sizeof *clients);
    pthread_t *threads = calloc((size_t)opt.clients, sizeof *threads);
    if (!clients || !threads)
        die("out of memory");
    double start = now_us();
    deadline_us = start + opt.duration * 1e6;
    for (int i = 0; i < opt.clients; i++) {
        clients[i].index = i;
        /* Not seed * the generator's own increment: seeds would be one stream shifted. */
        uint64_t mix = opt.seed ^ (0xd1b54a32d192ed03ull * (uint64_t)(i + 1));
        clients[i].rng = rnd(&mix);
        clients[i].priv = &privs[i];
        if (pthread_create(&threads[i], NULL, client_main, &clients[i]) != 0)
            die("cannot start client thread %d", i);
    }
    for (int i = 0; i < opt.clients; i++)
        pthread_join(threads[i], NULL);
    double seconds = (now_us() - start) / 1e6;

    client_stats total;
    memset(&total, 0, sizeof total);
    int failed_clients = 0;
    for (int i = 0; i < opt.clients; i++) {
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
    bool counted = server_counts(&end_requests, &end_errors);
    /* The first server.status counts itself once answered. */
    double delta_requests = end_requests - base_requests - 1;
    double delta_errors = end_errors - base_errors;
    bool counts_ok = !opt.count_check ||
                     (counted && delta_requests == (double)all.server_requests &&
                      delta_errors == (double)all.server_errors);

    if (!opt.quiet) {
        fprintf(stderr, "load: lines by kind:");
        for (int c = 0; c <= CAT_COUNT; c++)
            fprintf(stderr, " %s %lu%s", c < CAT_COUNT ? CAT_NAMES[c] : "private",
                    total.by_category[c], c < CAT_COUNT ? "," : "\n");
    }
    printf("load: %d clients x %s%ld lines, pipeline %d, seed %llu: %lu lines (%lu requests, "
           "%lu batches, %lu notifications) in %.2f s; warm-up %lu lines in %.2f s\n",
           opt.clients, opt.duration > 0 ? "~" : "",
           opt.duration > 0 ? (long)(total.lines / (unsigned long)opt.clients) : opt.requests,
           opt.pipeline, (unsigned long long)opt.seed, total.lines, total.requests, total.batches,
           total.notifications, seconds, warm.stats.lines, warm_seconds);
    if (counted)
        printf("load: errors expected %lu, seen %lu; the daemon counted %.0f requests and %.0f "
               "errors, expected %lu and %lu%s\n",
               all.answers_expected_errors, all.answers_seen_errors, delta_requests, delta_errors,
               all.server_requests, all.server_errors,
               !opt.count_check ? " (not checked)" : counts_ok ? "" : " MISMATCH");
    else
        printf("load: errors expected %lu, seen %lu; the daemon's counts could not be read "
               "(server.status failed)\n",
               all.answers_expected_errors, all.answers_seen_errors);
    printf("load: wrong answers %lu, lost answers %lu, unexpected answers %lu, failed connections %d\n",
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
