/* load_requests.c -- the load generator's table of requests: see
 * load_requests.h for what it holds and promises.
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
 * fixture.delete of a stored id) are computed from the fixture itself. */
#include "load_requests.h"

#include "load_util.h"
#include "wp_local.h"

#include <dirent.h>
#include <errno.h>
#include <glpk.h>
#include <math.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

static double round4(double x) { return round(x * 1e4) / 1e4; }

/* ---- what is sent and what is expected ------------------------------------- */

const char *const CATEGORY_NAMES[CATEGORY_COUNT] = {
    "fixture.put",  "fixture.get",   "wrench.classify", "classify batch", "cone.get",
    "plan.get",     "modes.get",     "push.regions",    "gravity.sweep",  "stability.margin",
    "server.status", "fixture.list", "bad params",      "bad lines"};

/* Single lines drawn per category, out of the sum. */
static const int CATEGORY_WEIGHTS[CATEGORY_COUNT] = {6, 3, 22, 12, 8, 6, 6, 8, 6, 8, 1, 1, 9, 4};

/* A fixture of the table, with what its answers are derived from. */
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
    double area, inertia; /* the mass properties fixture.put reports */
    int goal_cones, strong_cones;
    bool pinned;
    size_t analysis_bytes;
    size_t lp_bytes;   /* GLPK's memory for all its LPs, warm (--describe) */
} fixture;

/* A fixture stored by the warm-up (an example or --stored): what
 * fixture.list must show of it. */
typedef struct shared_fixture {
    char id[WP_ID_LENGTH + 1];
    char *name;
    int fixels;
} shared_fixture;

struct table {
    table_settings settings;
    request *items;
    size_t count, capacity;
    size_t *by_category[CATEGORY_COUNT];
    size_t category_count[CATEGORY_COUNT];
    size_t batchable_count;
    size_t *batchable; /* raw requests that may be batch members */
    fixture *fixtures; /* the stored ones first */
    size_t fixture_count;
    shared_fixture *shared; /* sorted by id */
    size_t shared_count;
};

static request *table_add(table *t, int category, unsigned flags, int check, char *wire,
                          char *oracle)
{
    if (t->count == t->capacity) {
        t->capacity = t->capacity ? 2 * t->capacity : 256;
        t->items = xrealloc(t->items, t->capacity * sizeof *t->items);
    }
    request *r = &t->items[t->count++];
    memset(r, 0, sizeof *r);
    r->category = category;
    r->flags = flags;
    r->check = check;
    r->wire = wire;
    r->oracle = oracle;
    return r;
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


static int compare_ids(const void *a, const void *b)
{
    return strcmp(((const shared_fixture *)a)->id, ((const shared_fixture *)b)->id);
}

/* fixture.list: every entry with the documented members, sorted by id, the
 * shared fixtures there with their names. */
static bool list_ok(const table *t, const cJSON *result)
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
        shared_fixture *s =
            bsearch(&key, t->shared, t->shared_count, sizeof *t->shared, compare_ids);
        if (s) {
            if (strcmp(s->name, name->valuestring) != 0 || s->fixels != fixels->valueint)
                return false;
            found++;
        }
    }
    return found == t->shared_count;
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
static void normalize(const table *t, cJSON *answer, int check)
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
        if (result && list_ok(t, result)) {
            cJSON *ok = cJSON_CreateObject();
            cJSON_AddTrueToObject(ok, "ok");
            cJSON_ReplaceItemInObjectCaseSensitive(answer, "result", ok);
        }
        break;
    default:
        break;
    }
}

int answer_error_count(const cJSON *answer)
{
    if (cJSON_IsArray(answer)) {
        int n = 0;
        for (const cJSON *a = answer->child; a; a = a->next)
            n += answer_error_count(a);
        return n;
    }
    return cJSON_GetObjectItemCaseSensitive(answer, "error") != NULL;
}

/* The canonical text an answer is compared by (the caller frees). */
char *table_comparable(const table *t, cJSON *answer, const request *r)
{
    normalize(t, answer, r->check);
    char *text = wp_canonical(answer, (r->flags & REQUEST_RAW) ? NULL : "id");
    if (!text)
        die("out of memory");
    return text;
}

/* ---- fixtures ---------------------------------------------------------------- */


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
    const double p[2] = {round4(x), round4(y)};
    add_number_array(array, NULL, p, 2);
}

static cJSON *friction_json(uint64_t *stream)
{
    cJSON *f = cJSON_CreateObject();
    double s = round4(random_uniform(stream, 0.05, 0.6));
    cJSON_AddNumberToObject(f, "static", s);
    if (random_pick(stream, 2))
        cJSON_AddNumberToObject(f, "kinetic", round4(s * random_uniform(stream, 0.5, 1.0)));
    return f;
}

/* A random fixture: a plate (rectangle, perhaps chamfered) against locators
 * on its bottom and left edges, a disc in a corner, or a shapeless body. */
static cJSON *generate_fixture(uint64_t *stream, const char *name)
{
    cJSON *f = cJSON_CreateObject();
    cJSON_AddStringToObject(f, "name", name);
    cJSON *body = cJSON_AddObjectToObject(f, "body");
    cJSON_AddNumberToObject(body, "mass", round4(random_uniform(stream, 0.5, 3)));
    cJSON *fixels = cJSON_CreateArray();
    int kind = random_pick(stream, 10);
    if (kind < 6) {
        double w = round4(random_uniform(stream, 2, 6)), h = round4(random_uniform(stream, 1, 4));
        double c = kind < 3 ? round4(random_uniform(stream, 0.2, 0.6) * fmin(w, h)) : 0;
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
        if (random_pick(stream, 4) == 0) {
            cJSON_AddNumberToObject(body, "inertia", round4(random_uniform(stream, 0.5, 4)));
            const double com[2] = {round4(random_uniform(stream, 0.3, 0.6) * w),
                                   round4(random_uniform(stream, 0.3, 0.6) * h)};
            add_number_array(body, "com", com, 2);
        }
        int k = 2 + random_pick(stream, 3); /* 2..4 fixels */
        double a = random_uniform(stream, 0.1, 0.45), b = random_uniform(stream, 0.55, 0.9);
        cJSON *x;
        if (k >= 3) { /* two under it */
            x = cJSON_CreateObject();
            add_number_array(x, "at", (double[2]){round4(a * w), 0}, 2);
            cJSON_AddItemToArray(fixels, x);
            x = cJSON_CreateObject();
            add_number_array(x, "at", (double[2]){round4(b * w), 0}, 2);
            cJSON_AddItemToArray(fixels, x);
        } else {
            x = cJSON_CreateObject();
            add_number_array(x, "at", (double[2]){round4(random_uniform(stream, 0.2, 0.8) * w), 0},
                             2);
            cJSON_AddItemToArray(fixels, x);
        }
        x = cJSON_CreateObject(); /* one to its left */
        add_number_array(x, "at", (double[2]){0, round4(random_uniform(stream, 0.15, 0.85) * h)},
                         2);
        if (random_pick(stream, 4) == 0)
            cJSON_AddItemToObject(x, "friction", friction_json(stream));
        cJSON_AddItemToArray(fixels, x);
        if (k == 4) { /* and one above */
            x = cJSON_CreateObject();
            add_number_array(x, "at",
                             (double[2]){round4(random_uniform(stream, 0.1, 0.5) * (w - c)), h}, 2);
            cJSON_AddItemToArray(fixels, x);
        }
    } else if (kind < 8) {
        double radius = round4(random_uniform(stream, 0.5, 2)),
               cx = round4(random_uniform(stream, -1, 1)),
               cy = round4(random_uniform(stream, -1, 1));
        cJSON *shape = cJSON_AddObjectToObject(body, "shape");
        cJSON_AddStringToObject(shape, "type", "circle");
        add_number_array(shape, "center", (double[2]){cx, cy}, 2);
        cJSON_AddNumberToObject(shape, "radius", radius);
        if (random_pick(stream, 2))
            cJSON_AddNumberToObject(body, "inertia", round4(random_uniform(stream, 0.2, 2)));
        int k = 2 + random_pick(stream, 2);
        const double pi = 3.14159265358979323846;
        double angles[3] = {random_uniform(stream, 165, 195), random_uniform(stream, 255, 285),
                            random_uniform(stream, 120, 150)};
        for (int i = 0; i < k; i++) {
            /* On the circle to the last bit: the validator allows a tolerance. */
            double t = angles[i] * pi / 180;
            cJSON *x = cJSON_CreateObject();
            add_number_array(x, "at",
                             (double[2]){cx + radius * cos(t), cy + radius * sin(t)}, 2);
            cJSON_AddItemToArray(fixels, x);
        }
    } else {
        cJSON_AddNumberToObject(body, "inertia", round4(random_uniform(stream, 0.3, 3)));
        add_number_array(body, "com",
                         (double[2]){round4(random_uniform(stream, -0.3, 0.3)),
                                     round4(random_uniform(stream, -0.3, 0.3))},
                         2);
        int k = 2 + random_pick(stream, 2);
        const double at[3][2] = {{-1, round4(random_uniform(stream, -0.5, 0.5))},
                                 {round4(random_uniform(stream, -0.5, 0.5)), -1},
                                 {round4(random_uniform(stream, -0.8, 0.8)), 1}};
        const double normal[3][2] = {{1, round4(random_uniform(stream, -0.2, 0.2))},
                                     {round4(random_uniform(stream, -0.2, 0.2)), 1},
                                     {round4(random_uniform(stream, -0.2, 0.2)), -1}};
        for (int i = 0; i < k; i++) {
            cJSON *x = cJSON_CreateObject();
            add_number_array(x, "at", at[i], 2);
            add_number_array(x, "normal", normal[i], 2);
            cJSON_AddItemToArray(fixels, x);
        }
    }
    cJSON_AddItemToObject(f, "friction", friction_json(stream));
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
    out->area = doc.fixture->area;
    out->inertia = doc.fixture->inertia;
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

static fixture generated_fixture(const table *t, uint64_t *stream, const char *name)
{
    for (int attempt = 0; attempt < 1000; attempt++) {
        fixture f;
        if (fixture_fill(&f, generate_fixture(stream, name), t->settings.measure_lp))
            return f;
    }
    die("could not generate a valid fixture");
    return (fixture){0};
}

static void load_examples(table *t)
{
    DIR *dir = opendir(t->settings.examples);
    if (!dir)
        die("%s: %s (--examples)", t->settings.examples, strerror(errno));
    char **names = NULL;
    size_t n = 0;
    struct dirent *d;
    while ((d = readdir(dir))) {
        size_t len = strlen(d->d_name);
        if (len > 5 && strcmp(d->d_name + len - 5, ".json") == 0) {
            names = xrealloc(names, (n + 1) * sizeof *names);
            names[n++] = xprintf("%s/%s", t->settings.examples, d->d_name);
        }
    }
    closedir(dir);
    for (size_t i = 0; i < n; i++) /* a stable order */
        for (size_t j = i + 1; j < n; j++)
            if (strcmp(names[i], names[j]) > 0) {
                char *swap = names[i];
                names[i] = names[j];
                names[j] = swap;
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
        if (!json || !fixture_fill(&f, json, t->settings.measure_lp))
            die("%s: not a valid fixture", names[i]);
        t->fixtures[t->fixture_count++] = f;
        free(names[i]);
    }
    free(names);
}

/* ---- building the table ----------------------------------------------------- */

static cJSON *wrench_json(uint64_t *stream, const fixture *f)
{
    if (f->has_shape && random_pick(stream, 4) == 0) { /* a force at a point */
        cJSON *w = cJSON_CreateObject();
        add_number_array(w, "force",
                         (double[2]){round4(random_uniform(stream, -1, 1)),
                                     round4(random_uniform(stream, -1, 1))},
                         2);
        add_number_array(
            w, "at",
            (double[2]){round4(f->com[0] + random_uniform(stream, -0.5, 0.5) * f->size),
                        round4(f->com[1] + random_uniform(stream, -0.5, 0.5) * f->size)},
            2);
        return w;
    }
    const double g[3] = {round4(random_uniform(stream, -1, 1)),
                         round4(random_uniform(stream, -1, 1)),
                         round4(random_uniform(stream, -0.5, 0.5) * f->size)};
    return cJSON_CreateDoubleArray(g, 3);
}

static const char *const SETS[3] = {"goal", "strong", "both"};

static void add_sets(uint64_t *stream, cJSON *params)
{
    int which = random_pick(stream, 8);
    if (which == 0)
        return; /* the default */
    cJSON *sets = cJSON_AddArrayToObject(params, "sets");
    int first = random_pick(stream, 3);
    cJSON_AddItemToArray(sets, cJSON_CreateString(SETS[first]));
    if (which >= 5)
        cJSON_AddItemToArray(sets,
                             cJSON_CreateString(SETS[(first + 1 + random_pick(stream, 2)) % 3]));
}

/* A request on fixture f: by id when stored, else inline. */
static request *add_on_fixture(table *t, int category, const fixture *f, bool stored,
                               const char *method, cJSON *params, int check, unsigned flags)
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
    return table_add(t, category, flags | REQUEST_NOTIFIABLE | REQUEST_BATCHABLE, check, wire,
                     oracle);
}

static cJSON *params_on(void)
{
    cJSON *p = cJSON_CreateObject();
    cJSON_AddNullToObject(p, "fixture");
    return p;
}

static void add_given(const table *t, request *r, const char *expected_json)
{
    /* An answer known without the oracle: {"jsonrpc":"2.0",...} without id. */
    cJSON *answer = cJSON_Parse(expected_json);
    if (!answer)
        die("internal: bad expected text %s", expected_json);
    r->expected = table_comparable(t, answer, r);
    r->answer_errors = answer_error_count(answer);
    r->counted_requests = 1;
    r->counted_errors = (unsigned long)r->answer_errors;
    r->given = true;
    cJSON_Delete(answer);
}

static char *put_answer(const fixture *f)
{
    cJSON *name = cJSON_CreateString(f->name);
    char *quoted = name ? cJSON_PrintUnformatted(name) : NULL;
    cJSON_Delete(name);
    if (!quoted)
        die("out of memory");
    /* The mass properties in use: area only with a shape. */
    char area[48] = "";
    if (f->has_shape)
        snprintf(area, sizeof area, ",\"area\":%.17g", f->area);
    char *answer = xprintf("{\"jsonrpc\":\"2.0\",\"result\":{\"id\":\"%s\",\"name\":%s,"
                           "\"fixels\":%d,\"goal_cones\":%d,\"strong_cones\":%d,\"pinned\":%s%s,"
                           "\"com\":[%.17g,%.17g],\"inertia\":%.17g}}",
                           f->id, quoted, f->fixels, f->goal_cones, f->strong_cones,
                           f->pinned ? "true" : "false", area, f->com[0] + 0.0, f->com[1] + 0.0,
                           f->inertia);
    free(quoted);
    return answer;
}

/* The requests and answers of the store, shared by the table's fixtures
 * and the private ones: the wire text and the answer the store must give. */
static char *put_request(const fixture *f)
{
    cJSON *params = cJSON_CreateObject();
    cJSON_AddItemToObject(params, "fixture", cJSON_Duplicate(f->json, true));
    char *wire = request_prefix("fixture.put", params);
    cJSON_Delete(params);
    return wire;
}

static char *get_request(const fixture *f)
{
    return xprintf("{\"jsonrpc\":\"2.0\",\"method\":\"fixture.get\",\"params\":{\"id\":\"%s\"}",
                   f->id);
}

static char *get_answer(const fixture *f)
{
    return xprintf("{\"jsonrpc\":\"2.0\",\"result\":%s}", f->canonical);
}

/* add_given, then free the text (made by the functions above). */
static void add_given_and_free(const table *t, request *r, char *expected_json)
{
    add_given(t, r, expected_json);
    free(expected_json);
}

static request *add_put(table *t, const fixture *f)
{
    request *r = table_add(t, CATEGORY_PUT, REQUEST_NOTIFIABLE | REQUEST_BATCHABLE, CHECK_EXACT,
                           put_request(f), NULL);
    add_given_and_free(t, r, put_answer(f));
    return r;
}

static request *add_get(table *t, const fixture *f)
{
    request *r = table_add(t, CATEGORY_GET, REQUEST_NOTIFIABLE | REQUEST_BATCHABLE, CHECK_EXACT,
                           get_request(f), NULL);
    add_given_and_free(t, r, get_answer(f));
    return r;
}

static const char *const FIELDS[5] = {"verdict", "margin", "blocking", "states", "witness"};

/* "fields": a random non-empty subset, in a random order; with `witness`,
 * one that holds "witness" (chunks of 256: a long batch is answered by
 * several workers at once). */
static void add_fields(uint64_t *stream, cJSON *params, bool witness)
{
    int mask = 1 + random_pick(stream, 31);
    if (witness)
        mask |= 1 << 4;
    cJSON *fields = cJSON_AddArrayToObject(params, "fields");
    int start = random_pick(stream, 5);
    for (int k = 0; k < 5; k++)
        if (mask & (1 << ((start + k) % 5)))
            cJSON_AddItemToArray(fields, cJSON_CreateString(FIELDS[(start + k) % 5]));
}

static void add_classify_lean(table *t, uint64_t *stream, const fixture *f, bool stored,
                              int wrenches, int category, int lean);

static void add_classify(table *t, uint64_t *stream, const fixture *f, bool stored, int wrenches,
                         int category)
{
    add_classify_lean(t, stream, f, stored, wrenches, category, 0);
}

/* lean: 0 a quarter of the auto ones with random "fields", 2 always with
 * "fields" holding "witness" (and never by LP, whose witnesses differ). */
static void add_classify_lean(table *t, uint64_t *stream, const fixture *f, bool stored,
                              int wrenches, int category, int lean)
{
    cJSON *p = params_on();
    cJSON *list = cJSON_AddArrayToObject(p, "wrenches");
    for (int i = 0; i < wrenches; i++)
        cJSON_AddItemToArray(list, wrench_json(stream, f));
    add_sets(stream, p);
    int check = CHECK_EXACT;
    int method = lean ? 100 : random_pick(stream, 100);
    if (method < t->settings.lp_percent) { /* GLPK: the verdicts are compared, not the witnesses */
        cJSON_AddStringToObject(p, "method", "lp");
        check = CHECK_NO_WITNESS;
    } else {
        if (method < t->settings.lp_percent + (100 - t->settings.lp_percent) / 4)
            cJSON_AddStringToObject(p, "method", "auto");
        if (lean || random_pick(stream, 4) == 0)
            add_fields(stream, p, lean == 2);
    }
    if (random_pick(stream, 10) == 0)
        cJSON_AddNumberToObject(p, "tolerance", random_pick(stream, 2) ? 0 : 1e-6);
    add_on_fixture(t, category, f, stored, "wrench.classify", p, check, 0);
}

static void add_queries(table *t, uint64_t *stream, const fixture *f, bool stored)
{
    add_classify(t, stream, f, stored, 1, CATEGORY_CLASSIFY);
    add_classify(t, stream, f, stored, 1 + random_pick(stream, 3), CATEGORY_CLASSIFY);
    add_classify(t, stream, f, stored, 1 + random_pick(stream, 50), CATEGORY_BATCH_CLASSIFY);
    add_classify_lean(t, stream, f, stored, 257 + random_pick(stream, 600), CATEGORY_BATCH_CLASSIFY,
                      2);

    static const char LETTERS[] = "saulrnm";
    for (int n = 0; n < 2; n++) {
        char text[WR_MAX_FIXELS + 1];
        for (int i = 0; i < f->fixels; i++)
            text[i] = LETTERS[random_pick(stream, 7)];
        text[f->fixels] = 0;
        cJSON *p = params_on();
        cJSON_AddStringToObject(p, "constraints", text);
        add_on_fixture(t, CATEGORY_CONE, f, stored, "cone.get", p, CHECK_EXACT, 0);
    }
    add_on_fixture(t, CATEGORY_PLAN, f, stored, "plan.get", params_on(), CHECK_EXACT, 0);
    add_on_fixture(t, CATEGORY_MODES, f, stored, "modes.get", params_on(), CHECK_EXACT, 0);

    cJSON *p = params_on();
    if (random_pick(stream, 4))
        cJSON_AddStringToObject(p, "set", SETS[random_pick(stream, 3)]);
    if (random_pick(stream, 8) == 0) /* sampled: slower, and exercises more code */
        cJSON_AddNumberToObject(p, "finger_friction", round4(random_uniform(stream, 0.05, 0.4)));
    add_on_fixture(t, CATEGORY_PUSH, f, stored, "push.regions", p, CHECK_EXACT, 0);

    p = params_on();
    if (random_pick(stream, 4))
        cJSON_AddStringToObject(p, "set", SETS[random_pick(stream, 3)]);
    add_on_fixture(t, CATEGORY_GRAVITY, f, stored, "gravity.sweep", p, CHECK_EXACT, 0);

    p = params_on();
    cJSON_AddItemToObject(p, "bias", wrench_json(stream, f));
    add_on_fixture(t, CATEGORY_MARGIN, f, stored, "stability.margin", p, CHECK_EXACT, 0);
}

/* Requests that must fail, each with its code and field. */
static void add_bad_params(table *t, uint64_t *stream, const fixture *f, bool stored)
{
    static const char *const BAD_WRENCHES[] = {
        "[[1,2]]", "[[1,2,\"x\"]]", "[{\"force\":[1,0]}]", "[[1e999,0,0]]",
        "[[0,0,0],[1,2,3,4]]", "{\"x\":1}", "[{\"force\":[1,0],\"at\":[0,0],\"x\":1}]"};
    cJSON *p = params_on();
    cJSON_AddItemToObject(
        p, "wrenches",
        cJSON_Parse(
            BAD_WRENCHES[random_pick(stream, (int)(sizeof BAD_WRENCHES / sizeof *BAD_WRENCHES))]));
    add_on_fixture(t, CATEGORY_ERROR, f, stored, "wrench.classify", p, CHECK_EXACT, 0);

    p = params_on();
    cJSON_AddItemToObject(p, "wrenches", cJSON_Parse("[[0,-1,0]]"));
    switch (random_pick(stream, 5)) {
    case 0: cJSON_AddItemToObject(p, "sets", cJSON_Parse("[\"goal\",\"goal\"]")); break;
    case 1: cJSON_AddItemToObject(p, "sets", cJSON_Parse("[]")); break;
    case 2: cJSON_AddStringToObject(p, "method", "fast"); break;
    case 3: cJSON_AddNumberToObject(p, "tolerance", -1); break;
    default: cJSON_AddNumberToObject(p, "wrench", 1); break;
    }
    add_on_fixture(t, CATEGORY_ERROR, f, stored, "wrench.classify", p, CHECK_EXACT, 0);

    p = params_on();
    cJSON_AddStringToObject(p, "constraints", random_pick(stream, 2) ? "zz" : "s");
    add_on_fixture(t, CATEGORY_ERROR, f, stored, "cone.get", p, CHECK_EXACT, 0);

    p = params_on();
    cJSON_AddNumberToObject(p, "finger_friction", -0.5);
    add_on_fixture(t, CATEGORY_ERROR, f, stored, "push.regions", p, CHECK_EXACT, 0);

    p = params_on();
    cJSON_AddStringToObject(p, "set", "all");
    add_on_fixture(t, CATEGORY_ERROR, f, stored, "gravity.sweep", p, CHECK_EXACT, 0);

    /* The required bias left out. */
    add_on_fixture(t, CATEGORY_ERROR, f, stored, "stability.margin", params_on(), CHECK_EXACT, 0);

    if (t->settings.max_wrenches <= 1000) { /* over the limit: -32003 */
        p = params_on();
        cJSON *list = cJSON_AddArrayToObject(p, "wrenches");
        for (long i = 0; i <= t->settings.max_wrenches; i++)
            cJSON_AddItemToArray(list, cJSON_CreateDoubleArray((double[3]){0, -1, 0}, 3));
        add_on_fixture(t, CATEGORY_ERROR, f, stored, "wrench.classify", p, CHECK_EXACT, 0);
    }
}

static void add_fixed_errors(table *t, uint64_t *stream)
{
    /* Ids never stored: -32001; only their wording is the daemon's own. */
    char unknown[WP_ID_LENGTH + 1];
    for (int i = 0; i < WP_ID_LENGTH; i++)
        unknown[i] = "0123456789abcdef"[random_pick(stream, 16)];
    unknown[WP_ID_LENGTH] = 0;
    const unsigned req = REQUEST_NOTIFIABLE | REQUEST_BATCHABLE;
    table_add(t, CATEGORY_ERROR, req, CHECK_LOOSE,
              xprintf("{\"jsonrpc\":\"2.0\",\"method\":\"wrench.classify\",\"params\":{\"fixture\":"
                      "\"%s\",\"wrenches\":[[0,-1,0]]}", unknown), NULL);
    table_add(t, CATEGORY_ERROR, req, CHECK_LOOSE,
              xprintf("{\"jsonrpc\":\"2.0\",\"method\":\"fixture.get\",\"params\":{\"id\":\"%s\"}",
                      unknown), NULL);
    table_add(t, CATEGORY_ERROR, req, CHECK_LOOSE,
              xprintf("{\"jsonrpc\":\"2.0\",\"method\":\"plan.get\",\"params\":{\"fixture\":\"%s\"}",
                      unknown), NULL);
    table_add(t, CATEGORY_ERROR, req, CHECK_LOOSE,
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
        table_add(t, CATEGORY_ERROR, req, CHECK_EXACT, xstrdup(BAD_REQUESTS[i]), NULL);
    /* Invalid requests: answered even without an id, so never notifications. */
    table_add(t, CATEGORY_ERROR, REQUEST_BATCHABLE, CHECK_EXACT,
              xstrdup("{\"jsonrpc\":\"1.0\",\"method\":\"server.status\""), NULL);
    table_add(t, CATEGORY_ERROR, REQUEST_BATCHABLE, CHECK_EXACT,
              xstrdup("{\"jsonrpc\":\"2.0\",\"method\":7"), NULL);
    table_add(t, CATEGORY_ERROR, REQUEST_BATCHABLE, CHECK_EXACT,
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
        table_add(t, CATEGORY_RAW, REQUEST_RAW, CHECK_EXACT, xstrdup(RAW[i]), NULL);
    /* Nesting deeper than --max-depth. */
    size_t depth = (size_t)t->settings.max_depth + 2;
    char *deep = xmalloc(2 * depth + 128);
    size_t n =
        (size_t)sprintf(deep, "{\"jsonrpc\":\"2.0\",\"method\":\"cone.get\",\"params\":{\"x\":");
    for (size_t i = 0; i < depth; i++)
        deep[n++] = '[';
    for (size_t i = 0; i < depth; i++)
        deep[n++] = ']';
    sprintf(deep + n, "},\"id\":9}");
    table_add(t, CATEGORY_RAW, REQUEST_RAW, CHECK_EXACT, deep, NULL);
    /* A batch over --max-batch (of notifications: nothing would be answered). */
    if (t->settings.max_batch <= 2000) {
        char *big = NULL;
        size_t length = 0, capacity = 0;
        append(&big, &length, &capacity, "[");
        for (long i = 0; i <= t->settings.max_batch; i++)
            append(&big, &length, &capacity,
                   i ? ",{\"jsonrpc\":\"2.0\",\"method\":\"server.status\"}"
                     : "{\"jsonrpc\":\"2.0\",\"method\":\"server.status\"}");
        append(&big, &length, &capacity, "]");
        table_add(t, CATEGORY_RAW, REQUEST_RAW, CHECK_EXACT, big, NULL);
    }
    /* Batchable invalid members: answered with id null inside a batch. */
    table_add(t, CATEGORY_RAW, REQUEST_RAW | REQUEST_BATCHABLE, CHECK_EXACT, xstrdup("1"), NULL);
    table_add(t, CATEGORY_RAW, REQUEST_RAW | REQUEST_BATCHABLE, CHECK_EXACT,
              xstrdup("{\"jsonrpc\":\"2.0\",\"id\":null}"), NULL);
}

static void add_status_and_list(table *t)
{
    request *r =
        table_add(t, CATEGORY_STATUS, REQUEST_NOTIFIABLE | REQUEST_BATCHABLE, CHECK_STATUS,
                  xstrdup("{\"jsonrpc\":\"2.0\",\"method\":\"server.status\",\"params\":{}"), NULL);
    add_given(t, r, "{\"jsonrpc\":\"2.0\",\"result\":{\"version\":\"string\",\"uptime_s\":0,"
                    "\"fixtures\":0,\"cached\":0,\"cache_bytes\":0,\"cache_limit_bytes\":0,"
                    "\"threads\":0,\"clients\":0,\"refused\":0,\"denied\":0,\"requests\":0,"
                    "\"errors\":0}}");
    r = table_add(t, CATEGORY_LIST, REQUEST_NOTIFIABLE | REQUEST_BATCHABLE, CHECK_LIST,
                  xstrdup("{\"jsonrpc\":\"2.0\",\"method\":\"fixture.list\""), NULL);
    add_given(t, r, "{\"jsonrpc\":\"2.0\",\"result\":{\"ok\":true}}");
}

/* ---- the oracle: expected answers, computed in process ---------------------- */

static void oracle_answer(const table *t, const wp_host *host, request *r)
{
    if (r->given)
        return;
    const char *text = r->oracle ? r->oracle : r->wire;
    char *line = (r->flags & REQUEST_RAW) ? xstrdup(text) : xprintf("%s,\"id\":0}", text);
    wp_limits limits = {.max_depth = t->settings.max_depth,
                        .max_wrenches = (size_t)t->settings.max_wrenches,
                        .max_batch = (size_t)t->settings.max_batch};
    wp_counts counts = {0, 0};
    char *answer = wp_answer_line(host, &limits, line, strlen(line), &counts);
    free(line);
    r->counted_requests = counts.requests;
    r->counted_errors = counts.errors;
    if (!answer) {
        r->expected = NULL;
        return;
    }
    cJSON *json = cJSON_Parse(answer);
    if (!json)
        die("internal: the oracle answered %s", answer);
    free(answer);
    r->answer_errors = answer_error_count(json);
    r->expected = table_comparable(t, json, r);
    cJSON_Delete(json);
}

/* Every core computes answers: the table of `make soak` (2000 fixtures)
 * takes seconds on one.  Each thread needs its own wp_local. */
typedef struct oracle_job {
    table *t;
    int index, of;
} oracle_job;

static void *oracle_thread(void *argument)
{
    oracle_job *job = argument;
    table *t = job->t;
    wp_local *local = wp_local_new();
    if (!local)
        die("out of memory");
    for (size_t i = (size_t)job->index; i < t->count; i += (size_t)job->of)
        oracle_answer(t, wp_local_host(local), &t->items[i]);
    wp_local_free(local);
    return NULL;
}

static void compute_expected(table *t)
{
    long cores = sysconf(_SC_NPROCESSORS_ONLN);
    int n = cores > 0 ? (int)cores : 1;
    if (n > 16)
        n = 16;
    pthread_t threads[16];
    oracle_job jobs[16];
    for (int i = 0; i < n; i++) {
        jobs[i] = (oracle_job){t, i, n};
        if (pthread_create(&threads[i], NULL, oracle_thread, &jobs[i]) != 0)
            die("cannot start a thread");
    }
    for (int i = 0; i < n; i++)
        pthread_join(threads[i], NULL);
}

/* ---- private fixtures: a store only one client changes ---------------------- */

static void private_step(request *r, char *wire, char *oracle, int check)
{
    memset(r, 0, sizeof *r);
    r->category = CATEGORY_PRIVATE;
    r->flags = REQUEST_NOTIFIABLE | REQUEST_BATCHABLE;
    r->check = check;
    r->wire = wire;
    r->oracle = oracle;
}

static void make_private(const table *t, private_fixture *private, int client, wp_local *local)
{
    uint64_t stream = t->settings.seed * 1000003u + 7777u + (uint64_t)client;
    char name[64];
    snprintf(name, sizeof name, "private-%llu-%d", (unsigned long long)t->settings.seed, client);
    fixture f = generated_fixture(t, &stream, name);
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
        private_step(&private->steps[PRIVATE_PUT][stored], put_request(&f), NULL, CHECK_EXACT);
        add_given_and_free(t, &private->steps[PRIVATE_PUT][stored], put_answer(&f));

        private_step(&private->steps[PRIVATE_GET][stored], get_request(&f), NULL, CHECK_LOOSE);
        char *del = xprintf(
            "{\"jsonrpc\":\"2.0\",\"method\":\"fixture.delete\",\"params\":{\"id\":\"%s\"}", f.id);
        private_step(&private->steps[PRIVATE_DELETE][stored], del, NULL, CHECK_LOOSE);
        uint64_t wrench_stream = stream; /* the same wrenches whether stored or not */
        cJSON *p = cJSON_CreateObject();
        cJSON_AddStringToObject(p, "fixture", f.id);
        cJSON *list = cJSON_AddArrayToObject(p, "wrenches");
        for (int i = 0; i < 3; i++)
            cJSON_AddItemToArray(list, wrench_json(&wrench_stream, &f));
        char *wire = request_prefix("wrench.classify", p);
        cJSON_ReplaceItemInObjectCaseSensitive(p, "fixture", cJSON_Duplicate(f.json, true));
        char *oracle = stored ? request_prefix("wrench.classify", p) : NULL;
        cJSON_Delete(p);
        private_step(&private->steps[PRIVATE_CLASSIFY][stored], wire, oracle, CHECK_LOOSE);
        if (stored) {
            add_given_and_free(t, &private->steps[PRIVATE_GET][stored], get_answer(&f));
            add_given(t, &private->steps[PRIVATE_DELETE][stored],
                      "{\"jsonrpc\":\"2.0\",\"result\":{\"deleted\":true}}");
        } else {
            oracle_answer(t, host, &private->steps[PRIVATE_GET][stored]);
            oracle_answer(t, host, &private->steps[PRIVATE_DELETE][stored]);
        }
        oracle_answer(t, host, &private->steps[PRIVATE_CLASSIFY][stored]);
    }
    fixture_release(&f);
    cJSON_Delete(json);
}

private_fixture *private_fixtures_make(const table *t, int clients)
{
    private_fixture *all = xmalloc((size_t)clients * sizeof *all);
    wp_local *local = wp_local_new();
    if (!local)
        die("out of memory");
    for (int i = 0; i < clients; i++) {
        make_private(t, &all[i], i, local);
        all[i].stored = all[i].put_once = false;
    }
    wp_local_free(local);
    return all;
}

const request *private_fixture_next(private_fixture *p, uint64_t *stream)
{
    int step = p->put_once ? random_pick(stream, PRIVATE_STEPS) : PRIVATE_PUT;
    const request *r = &p->steps[step][p->stored ? 1 : 0];
    if (step == PRIVATE_PUT)
        p->stored = p->put_once = true;
    else if (step == PRIVATE_DELETE)
        p->stored = false;
    return r;
}

/* ---- the table as a whole ------------------------------------------------------ */

static void index_table(table *t)
{
    for (int c = 0; c < CATEGORY_COUNT; c++) {
        t->by_category[c] = xmalloc(t->count * sizeof(size_t));
        t->category_count[c] = 0;
    }
    t->batchable = xmalloc(t->count * sizeof(size_t));
    for (size_t i = 0; i < t->count; i++) {
        request *r = &t->items[i];
        t->by_category[r->category][t->category_count[r->category]++] = i;
        if ((r->flags & REQUEST_RAW) && (r->flags & REQUEST_BATCHABLE))
            t->batchable[t->batchable_count++] = i;
    }
}

table *table_build(const table_settings *settings)
{
    table *t = xmalloc(sizeof *t);
    memset(t, 0, sizeof *t);
    t->settings = *settings;
    uint64_t stream = t->settings.seed * 0x2545f4914f6cdd1dull + 1;
    size_t capacity = 64 + (size_t)t->settings.stored + (size_t)t->settings.fixtures;
    t->fixtures = xmalloc(capacity * sizeof *t->fixtures);
    load_examples(t);
    for (int i = 0; i < t->settings.stored; i++) {
        char name[64];
        snprintf(name, sizeof name, "stored-%llu-%d", (unsigned long long)t->settings.seed, i);
        t->fixtures[t->fixture_count++] = generated_fixture(t, &stream, name);
    }
    size_t stored_count = t->fixture_count;
    for (int i = 0; i < t->settings.fixtures; i++) {
        char name[64];
        snprintf(name, sizeof name, "inline-%llu-%d", (unsigned long long)t->settings.seed, i);
        t->fixtures[t->fixture_count++] = generated_fixture(t, &stream, name);
    }
    /* Two fixtures of equal content would be one stored fixture with two
     * names: keep the first of each id. */
    for (size_t i = 0; i < t->fixture_count; i++)
        for (size_t j = 0; j < i; j++)
            if (strcmp(t->fixtures[i].id, t->fixtures[j].id) == 0)
                die("two fixtures of the table have the same content (%s); change --seed",
                    t->fixtures[i].id);
    t->shared = xmalloc(stored_count * sizeof *t->shared);
    for (size_t i = 0; i < stored_count; i++) {
        fixture *f = &t->fixtures[i];
        memcpy(t->shared[i].id, f->id, sizeof t->shared[i].id);
        t->shared[i].name = f->name;
        t->shared[i].fixels = f->fixels;
        add_put(t, f);
    }
    t->shared_count = stored_count;
    qsort(t->shared, t->shared_count, sizeof *t->shared, compare_ids);
    for (size_t i = 0; i < t->fixture_count; i++) {
        bool stored = i < stored_count;
        if (stored)
            add_get(t, &t->fixtures[i]);
        add_queries(t, &stream, &t->fixtures[i], stored);
        /* Bad params on a few fixtures, by id and inline. */
        if (i < stored_count + 4 || i % 8 == 0)
            add_bad_params(t, &stream, &t->fixtures[i], stored);
    }
    add_fixed_errors(t, &stream);
    add_status_and_list(t);
    index_table(t);
    compute_expected(t);
    return t;
}


void table_describe(const table *t, double build_seconds)
{
    size_t inline_bytes = 0, inline_max = 0, lp_max = 0, lp_sum = 0;
    size_t stored_count = t->shared_count;
    for (size_t i = 0; i < t->fixture_count; i++) {
        const fixture *f = &t->fixtures[i];
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
        stored_bytes += t->fixtures[i].analysis_bytes;
    size_t expected_bytes = 0;
    for (size_t i = 0; i < t->count; i++)
        expected_bytes += t->items[i].expected ? strlen(t->items[i].expected) : 0;
    printf("table_members=%zu\n", t->count);
    for (int c = 0; c < CATEGORY_COUNT; c++)
        printf("table_%s=%zu\n", CATEGORY_NAMES[c], t->category_count[c]);
    printf("stored_fixtures=%zu\nstored_derived_bytes=%zu\n", stored_count, stored_bytes);
    printf("inline_fixtures=%zu\ninline_derived_bytes=%zu\ninline_derived_max=%zu\n",
           t->fixture_count - stored_count, inline_bytes, inline_max);
    printf("lp_bytes_max=%zu\nlp_bytes_mean=%zu\n", lp_max,
           t->fixture_count ? lp_sum / t->fixture_count : 0);
    printf("expected_text_bytes=%zu\nbuild_seconds=%.2f\n", expected_bytes, build_seconds);
}

void table_dump(const table *t)
{
    for (size_t i = 0; i < t->count; i++) {
        const request *r = &t->items[i];
        printf("%s%s\n%lu %lu\n%s\n", r->wire, (r->flags & REQUEST_RAW) ? "" : ",\"id\":0}",
               r->counted_requests, r->counted_errors, r->expected ? r->expected : "(no answer)");
    }
}

size_t table_size(const table *t) { return t->count; }

const request *table_request(const table *t, size_t index) { return &t->items[index]; }

size_t table_fixture_count(const table *t) { return t->fixture_count; }

/* ---- drawing requests for the load -------------------------------------------- */

static const request *pick_in_category(const table *t, uint64_t *stream, int category)
{
    size_t n = t->category_count[category];
    return n ? &t->items[t->by_category[category][random_next(stream) % n]] : NULL;
}

const request *table_pick(const table *t, uint64_t *stream)
{
    int total = 0;
    for (int i = 0; i < CATEGORY_COUNT; i++)
        total += t->category_count[i] ? CATEGORY_WEIGHTS[i] : 0;
    int x = random_pick(stream, total);
    for (int i = 0; i < CATEGORY_COUNT; i++) {
        int weight = t->category_count[i] ? CATEGORY_WEIGHTS[i] : 0;
        if (x < weight)
            return pick_in_category(t, stream, i);
        x -= weight;
    }
    return pick_in_category(t, stream, CATEGORY_CLASSIFY);
}

const request *table_pick_raw_batchable(const table *t, uint64_t *stream)
{
    return &t->items[t->batchable[random_next(stream) % t->batchable_count]];
}
