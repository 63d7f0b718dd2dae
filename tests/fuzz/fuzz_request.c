/* fuzz_request.c -- libFuzzer target (a): request lines through decode,
 * validation and dispatch (wp_answer_line) against the daemon's real
 * fixture cache (wd_cache) and a worker's thread host (wd_thread_host: its
 * GLPK environment and warm LPs), as one worker thread of wrenchd answers
 * them.
 *
 * The input is split at '\n' and each line is answered in turn, as the
 * daemon frames a connection's bytes; an input without '\n' is one line.
 * The cache and the thread host live for the whole process, so a fixture.put in
 * one line (or one input) is there for the queries of the next.  Stored
 * fixtures are never evicted by the cache, so once more than
 * STORE_BOUND are stored they are all deleted (through the cache's own
 * wd_cache_delete); the derived data is bounded by the cache itself
 * (DERIVED_LIMIT, least recently used out).
 *
 * Each line is handed over in a buffer of exactly its length (no NUL after
 * it), so a read past the line is an ASan report.
 *
 * Beyond "no crash, no leak, no undefined behaviour", every answer must be:
 * one line ending in "\n" and holding no other, valid UTF-8, valid JSON,
 * a JSON-RPC 2.0 response object or a non-empty array of them (no answer
 * only when every request is a notification), with the members and error
 * object of docs/PROTOCOL.md, the request's id echoed, one response per
 * request that is not a notification, in order; and for results of
 * fixture.put, wrench.classify, push.regions, gravity.sweep,
 * stability.margin, cone.get and plan.get, the invariants of their
 * numbers (margins in [-1, 1] and consistent with the verdict and the
 * tolerance, regions sorted and disjoint, ...).  See tests/fuzz/README.md.
 *
 * Skipped (not answered, counted): push.regions with a finger_friction
 * above 0 whose sampled work (SAMPLES points per edge, each against every
 * excluded cone) exceeds FRICTION_BUDGET, and wrench.classify with method
 * "lp" whose LP count exceeds LP_BUDGET, and friction.sweep's push with a
 * finger_friction above 0 whose sampled work over SWEEP_STEPS values of mu
 * exceeds FRICTION_BUDGET.  All are legitimate requests
 * that take seconds to minutes under the sanitizers; they would only make
 * the fuzzer time out.  Set FUZZ_REQUEST_NO_SKIP=1 to answer them anyway,
 * FUZZ_REQUEST_VERBOSE=1 to see each line and its answer on stderr. */
#define _GNU_SOURCE /* memmem */
#include "fuzz_util.h"

#include <ctype.h>
#include "wd_log.h"
#include "wd_worker.h"
#include "wp_rpc.h"

#include <time.h>

#define DERIVED_LIMIT (64u << 20) /* bytes of derived data the cache keeps */
#define STORE_BOUND 32           /* stored fixtures kept across inputs */
/* wr_push_regions with friction: 2049 samples per edge (lib/wr_regions.c
 * SAMPLES), each testing every excluded cone of the set. */
#define SAMPLES_PER_EDGE 2049.0
#define FRICTION_BUDGET 4e6   /* sample x cone tests per request */
#define LP_BUDGET 4096.0      /* LPs per wrench.classify request */
#define SWEEP_STEPS 256.0     /* values of mu a friction.sweep samples (wr_sweep.h) */

/* The daemon's limits, small (as its options set them): a design of more
 * candidates than max_candidates is refused at the field, as
 * --max-candidates refuses it, and so are more wrenches, batch members or
 * load cases; every method and field is still reached, and no line costs
 * more than a few milliseconds under the sanitizers. */
static const wp_limits LIMITS = {.max_depth = 32, .max_wrenches = 16, .max_batch = 8,
                                 .max_candidates = 24, .max_cases = 4};

static wd_cache *cache;
static wd_stats stats;
static wd_thread_host *thread;
static const wp_host *host;
static bool no_skip, verbose;
static const char *refusal = ""; /* why the line must be refused whole, for messages */
static unsigned long skipped;

int LLVMFuzzerInitialize(int *argc, char ***argv)
{
    fuzz_full_init(*argc, *argv);
    wd_log_set_level(WD_LOG_ERROR);
    char why[256] = "";
    cache = wd_cache_new(NULL, DERIVED_LIMIT, 10000, why, sizeof why);
    if (!cache) {
        fprintf(stderr, "fuzz_request: wd_cache_new: %s\n", why);
        abort();
    }
    stats.started = time(NULL);
    stats.threads = 1;
    thread = wd_thread_host_new(cache, &stats);
    if (!thread)
        abort();
    host = wd_thread_host_wp(thread);
    const char *env = getenv("FUZZ_REQUEST_NO_SKIP");
    no_skip = env && *env && strcmp(env, "0") != 0;
    env = getenv("FUZZ_REQUEST_VERBOSE"); /* print each line and its answer */
    verbose = env && *env && strcmp(env, "0") != 0;
    return 0;
}

/* ---- what a request line holds, read independently with cJSON ---------- */

static const char *const ENVELOPE[] = {"jsonrpc", "method", "params", "id"};

static bool only_envelope_members(const cJSON *request)
{
    for (const cJSON *m = request->child; m; m = m->next) {
        bool known = false;
        for (size_t i = 0; i < sizeof ENVELOPE / sizeof ENVELOPE[0]; i++)
            known |= m->string && strcmp(m->string, ENVELOPE[i]) == 0;
        if (!known)
            return false;
        for (const cJSON *n = m->next; n; n = n->next) /* each once */
            if (n->string && strcmp(n->string, m->string) == 0)
                return false;
    }
    return true;
}

/* A valid request (PROTOCOL: an object, a usable id or none, only the
 * envelope's members, "jsonrpc": "2.0", a string method). */
static bool valid_request(const cJSON *r)
{
    if (!cJSON_IsObject(r))
        return false;
    const cJSON *id = cJSON_GetObjectItemCaseSensitive(r, "id");
    if (id && !cJSON_IsString(id) && !cJSON_IsNumber(id) && !cJSON_IsNull(id))
        return false;
    if (cJSON_IsNumber(id) && !isfinite(id->valuedouble))
        return false;
    const cJSON *version = cJSON_GetObjectItemCaseSensitive(r, "jsonrpc");
    return only_envelope_members(r) && cJSON_IsString(version) &&
           strcmp(version->valuestring, "2.0") == 0 &&
           cJSON_IsString(cJSON_GetObjectItemCaseSensitive(r, "method"));
}

static bool notification(const cJSON *r)
{
    return valid_request(r) && !cJSON_GetObjectItemCaseSensitive(r, "id");
}

static const char *method_of(const cJSON *r)
{
    const cJSON *m = cJSON_IsObject(r) ? cJSON_GetObjectItemCaseSensitive(r, "method") : NULL;
    return cJSON_IsString(m) ? m->valuestring : "";
}

static const cJSON *param(const cJSON *r, const char *name)
{
    const cJSON *params = cJSON_GetObjectItemCaseSensitive(r, "params");
    return cJSON_IsObject(params) ? cJSON_GetObjectItemCaseSensitive(params, name) : NULL;
}

/* Is the line one JSON text by RFC 8259's rules on control characters?
 * None may appear raw inside a string, and white space between tokens is
 * only space, tab, CR (and LF, which never reaches a line).  With `trim`,
 * the ends of the line are first trimmed of any isspace() (\v and \f too),
 * as wp_answer_line trims them.  (Everything else is left to cJSON.) */
static bool control_characters_ok(const char *text, size_t length, bool trim)
{
    const char *ends = trim ? " \t\n\v\f\r" : " \t\n\r";
    size_t start = 0;
    while (length > 0 && text[length - 1] && strchr(ends, text[length - 1]))
        length--;
    while (start < length && text[start] && strchr(ends, text[start]))
        start++;
    bool in_string = false, escaped = false;
    for (size_t i = start; i < length; i++) {
        unsigned char c = (unsigned char)text[i];
        if (in_string) {
            if (c < 0x20)
                return false;
            if (escaped)
                escaped = false;
            else if (c == '\\')
                escaped = true;
            else if (c == '"')
                in_string = false;
        } else if (c == '"') {
            in_string = true;
        } else if (c < 0x20 && c != '\t' && c != '\r') {
            return false;
        }
    }
    return true;
}

/* Is every escape in a string one RFC 8259 allows (\" \\ \/ \b \f \n \r \t,
 * \u and four hex digits)?  cJSON reads "\udu" as U+0000 and cuts the
 * string there (fuzz finding 9); the answerer must refuse such a line as not
 * JSON.  Written apart from proto/wp_json.c's check. */
static bool escapes_ok(const char *text, size_t length)
{
    bool in_string = false;
    for (size_t i = 0; i < length; i++) {
        if (!in_string) {
            in_string = text[i] == '"';
            continue;
        }
        if (text[i] == '"') {
            in_string = false;
        } else if (text[i] == '\\') {
            if (i + 1 >= length)
                return false;
            char c = text[++i];
            if (c == 'u') {
                if (i + 4 >= length)
                    return false;
                for (int k = 1; k <= 4; k++)
                    if (!isxdigit((unsigned char)text[i + k]))
                        return false;
                i += 4;
            } else if (!strchr("\"\\/bfnrt", c) || c == '\0') {
                return false;
            }
        }
    }
    return true;
}

/* Does every number outside strings follow RFC 8259's grammar?  cJSON
 * reads numbers with strtod, which also takes "012", "1." and "-.5"; the
 * answerer must refuse those lines as not JSON.  A state machine over the
 * grammar, written apart from proto/wp_json.c's check. */
static bool numbers_ok(const char *text, size_t length)
{
    enum { OUTSIDE, STRING, ESCAPE, MINUS, ZERO, INTEGER, POINT, FRACTION, E, E_SIGN, EXPONENT };
    int state = OUTSIDE;
    for (size_t i = 0; i <= length; i++) {
        int c = i < length ? (unsigned char)text[i] : ' ';
        bool digit = c >= '0' && c <= '9';
        switch (state) {
        case STRING: state = c == '\\' ? ESCAPE : c == '"' ? OUTSIDE : STRING; continue;
        case ESCAPE: state = STRING; continue;
        case MINUS: if (!digit) return false; state = c == '0' ? ZERO : INTEGER; continue;
        case ZERO:
            if (digit) return false; /* a leading zero */
            if (c == '.') { state = POINT; continue; }
            if (c == 'e' || c == 'E') { state = E; continue; }
            break;
        case INTEGER:
            if (digit) continue;
            if (c == '.') { state = POINT; continue; }
            if (c == 'e' || c == 'E') { state = E; continue; }
            break;
        case POINT: if (!digit) return false; state = FRACTION; continue;
        case FRACTION:
            if (digit) continue;
            if (c == 'e' || c == 'E') { state = E; continue; }
            break;
        case E:
            if (c == '+' || c == '-') { state = E_SIGN; continue; }
            if (!digit) return false;
            state = EXPONENT;
            continue;
        case E_SIGN: if (!digit) return false; state = EXPONENT; continue;
        case EXPONENT: if (digit) continue; break;
        default: break;
        }
        /* OUTSIDE, or just past the end of a number. */
        state = c == '"' ? STRING : c == '-' ? MINUS : c == '0' ? ZERO : digit ? INTEGER : OUTSIDE;
    }
    return true;
}

/* A whole line refused as not JSON: {"error": {"code": -32700, ...}, "id": null}. */
static bool parse_error_answer(const char *answer)
{
    cJSON *json = answer ? cJSON_Parse(answer) : NULL;
    const cJSON *error = cJSON_GetObjectItemCaseSensitive(json, "error");
    const cJSON *code = cJSON_GetObjectItemCaseSensitive(error, "code");
    bool refused = cJSON_IsNumber(code) && code->valueint == WP_PARSE_ERROR &&
                   cJSON_IsNull(cJSON_GetObjectItemCaseSensitive(json, "id"));
    cJSON_Delete(json);
    return refused;
}

/* ---- skipping the requests known to be slow ------------------------------ */

/* The fixture a request names, resolved the way the method would (an id
 * from the store, an inline object adopted into the cache), held in *use
 * until host->fixture_release.  False when it does not resolve (the
 * request then fails fast). */
static bool fixture_resolve(const cJSON *r, wp_fixture_use *use)
{
    const cJSON *value = param(r, "fixture");
    wp_error error;
    wp_host_failure failure;
    if (cJSON_IsString(value))
        return wp_fixture_id_valid(value->valuestring) &&
               host->fixture_use(host->self, value->valuestring, use, &failure);
    wp_fixture_doc doc;
    return cJSON_IsObject(value) && wp_fixture_read(value, "params.fixture", &doc, &error) &&
           host->fixture_adopt(host->self, &doc, false, use, &failure);
}

/* Whether the fixture a request names rests on supports, and whether it
 * carries a tolerance (both false when it does not resolve): their
 * answers differ (docs/PROTOCOL.md, "Supports" and "Tolerance"). */
static void fixture_traits(const cJSON *r, bool *supports, bool *toleranced)
{
    wp_fixture_use use;
    *supports = *toleranced = false;
    if (!fixture_resolve(r, &use))
        return;
    *supports = use.fixture->supports != NULL;
    *toleranced = use.fixture->tolerance.given;
    host->fixture_release(host->self, &use);
}

/* The excluded cone count of `set` and the edge count of the fixture a
 * request names; false when it does not resolve. */
static bool fixture_work(const cJSON *r, wr_set set, double *cones, double *edges)
{
    wp_fixture_use use;
    if (!fixture_resolve(r, &use))
        return false;
    const wr_analysis *a = use.analysis;
    *cones = (set != WR_SET_STRONG ? wr_analysis_plan(a)->kept_count : 0) +
             (set != WR_SET_GOAL ? wr_analysis_cone_count(a, WR_SET_STRONG) : 0);
    *edges = use.fixture->shape == WR_SHAPE_NONE ? 1 : (double)wr_push_edge_count(use.fixture);
    host->fixture_release(host->self, &use);
    return true;
}

/* The methods whose answers take milliseconds even with the limits above
 * (searches, sweeps, samplings): while fuzzing, a line asking one is
 * answered only when its hash says so (one line in SLOW_SHARE; fuzz_full),
 * so that the fuzzer spends its time over every method alike. */
#define SLOW_SHARE 4
static const char *const SLOW_METHODS[] = {"fixture.design", "friction.sweep", "push.force",
                                           "force.range", "gravity.sweep", "stability.margin"};

static bool slow_request(const cJSON *r, bool answer_slow)
{
    if (!valid_request(r))
        return false;
    const char *method = method_of(r);
    for (size_t i = 0; !answer_slow && i < sizeof SLOW_METHODS / sizeof SLOW_METHODS[0]; i++)
        if (strcmp(method, SLOW_METHODS[i]) == 0)
            return true;
    double cones, edges;
    if (strcmp(method, "push.regions") == 0) {
        const cJSON *friction = param(r, "finger_friction");
        if (!cJSON_IsNumber(friction) || !(friction->valuedouble > 0))
            return false;
        const cJSON *set = param(r, "set");
        wr_set s = WR_SET_GOAL;
        for (int i = 0; i < 3 && cJSON_IsString(set); i++)
            if (strcmp(set->valuestring, FUZZ_SET_NAMES[i]) == 0)
                s = (wr_set)i;
        return fixture_work(r, s, &cones, &edges) &&
               edges * SAMPLES_PER_EDGE * cones > FRICTION_BUDGET;
    }
    if (strcmp(method, "friction.sweep") == 0) {
        /* A push sweep with a finger with friction: push regions so sampled
         * at each of SWEEP_STEPS values of mu. */
        const cJSON *push = param(r, "push");
        const cJSON *friction = cJSON_GetObjectItemCaseSensitive(push, "finger_friction");
        if (!cJSON_IsNumber(friction) || !(friction->valuedouble > 0))
            return false;
        return fixture_work(r, WR_SET_GOAL, &cones, &edges) &&
               edges * SAMPLES_PER_EDGE * cones * SWEEP_STEPS > FRICTION_BUDGET;
    }
    if (strcmp(method, "wrench.classify") == 0) {
        const cJSON *how = param(r, "method");
        const cJSON *wrenches = param(r, "wrenches");
        if (!cJSON_IsString(how) || strcmp(how->valuestring, "lp") != 0 ||
            !cJSON_IsArray(wrenches))
            return false;
        return fixture_work(r, WR_SET_BOTH, &cones, &edges) &&
               cones * cJSON_GetArraySize(wrenches) > LP_BUDGET;
    }
    return false;
}

static bool too_slow(const cJSON *json, bool answer_slow)
{
    if (no_skip || !json)
        return false;
    if (!cJSON_IsArray(json))
        return slow_request(json, answer_slow);
    for (const cJSON *r = json->child; r; r = r->next)
        if (slow_request(r, answer_slow))
            return true;
    return false;
}

/* ---- the invariants of an answer ----------------------------------------- */

static const struct {
    int code;
    const char *message;
} CODES[] = {
    {WP_PARSE_ERROR, "Parse error"},       {WP_INVALID_REQUEST, "Invalid Request"},
    {WP_NO_METHOD, "Method not found"},    {WP_INVALID_PARAMS, "Invalid params"},
    {WP_INTERNAL, "Internal error"},       {WP_NO_FIXTURE, "No such fixture"},
    {WP_STORAGE, "Storage failure"},       {WP_LIMIT, "Limit exceeded"},
    {WP_SOLVER, "Solver failure"},         {WP_ACCESS, "Access denied"},
};

static bool has_exactly(const cJSON *object, const char *const *names, int count)
{
    if (!cJSON_IsObject(object) || cJSON_GetArraySize(object) != count)
        return false;
    for (int i = 0; i < count; i++)
        if (!cJSON_GetObjectItemCaseSensitive(object, names[i]))
            return false;
    return true;
}

static bool is_number_in(const cJSON *v, double low, double high)
{
    return cJSON_IsNumber(v) && v->valuedouble >= low && v->valuedouble <= high;
}

/* The error object of a response. */
static void check_error(const cJSON *error, const char *line)
{
    static const char *const ERROR_MEMBERS[] = {"code", "message", "data"};
    static const char *const DATA_MEMBERS[] = {"field", "reason"};
    FUZZ_CHECK(has_exactly(error, ERROR_MEMBERS, 3), "error members wrong for %s", line);
    const cJSON *code = cJSON_GetObjectItemCaseSensitive(error, "code");
    const cJSON *message = cJSON_GetObjectItemCaseSensitive(error, "message");
    const cJSON *data = cJSON_GetObjectItemCaseSensitive(error, "data");
    FUZZ_CHECK(cJSON_IsNumber(code) && code->valuedouble == (double)code->valueint,
               "error code not an integer for %s", line);
    const char *expected = NULL;
    for (size_t i = 0; i < sizeof CODES / sizeof CODES[0]; i++)
        if (CODES[i].code == code->valueint)
            expected = CODES[i].message;
    FUZZ_CHECK(expected, "unknown error code %d for %s", code->valueint, line);
    FUZZ_CHECK(code->valueint != WP_INTERNAL, "internal error (out of memory?) for %s", line);
    FUZZ_CHECK(cJSON_IsString(message) && strcmp(message->valuestring, expected) == 0,
               "error %d: message not \"%s\" for %s", code->valueint, expected, line);
    FUZZ_CHECK(has_exactly(data, DATA_MEMBERS, 2), "error data members wrong for %s", line);
    const cJSON *field = cJSON_GetObjectItemCaseSensitive(data, "field");
    const cJSON *reason = cJSON_GetObjectItemCaseSensitive(data, "reason");
    FUZZ_CHECK(cJSON_IsString(field), "error data.field not a string for %s", line);
    FUZZ_CHECK(cJSON_IsString(reason) && reason->valuestring[0], "error data.reason empty for %s",
               line);
    /* A field names where the request went wrong: empty, an envelope
     * member, or a path under params. */
    const char *f = field->valuestring;
    FUZZ_CHECK(!f[0] || strncmp(f, "params", 6) == 0 || strcmp(f, "jsonrpc") == 0 ||
                   strcmp(f, "method") == 0 || strcmp(f, "id") == 0 || code->valueint ==
                   WP_INVALID_REQUEST,
               "error %d names field \"%s\" for %s", code->valueint, f, line);
}

/* Whether a request's wrench is the zero wrench: [0, 0, 0], or a zero
 * force anywhere (docs/MODEL.md section 5 gives it margin 0). */
static bool wrench_is_zero(const cJSON *wrench)
{
    const cJSON *force = cJSON_IsArray(wrench) ? wrench
                                               : cJSON_GetObjectItemCaseSensitive(wrench, "force");
    return cJSON_GetArrayItem(force, 0)->valuedouble == 0 &&
           cJSON_GetArrayItem(force, 1)->valuedouble == 0 &&
           (!cJSON_IsArray(wrench) || cJSON_GetArrayItem(wrench, 2)->valuedouble == 0);
}

/* wrench.classify with "fields", by column (docs/PROTOCOL.md, Lean
 * answers): "count" the wrenches, pieces whose counts add up to it, in
 * each one object per set asked, in order, holding only the columns asked,
 * each with one entry per wrench of the piece; verdict letters of "iob"
 * and, with margins (method "auto"), the letter the margin implies under
 * the tolerance asked; the zero wrench has margin 0 and is outside, or
 * inside G_strong when no moving mode admits it (docs/MODEL.md section 5). */
static void check_classify_columns(const cJSON *request, const cJSON *result, const char *line)
{
    static const char *const COLUMNS[][2] = {{"verdict", "verdicts"}, {"margin", "margins"},
                                            {"blocking", "blocking"}, {"states", "states"},
                                            {"witness", "witness"}};
    const cJSON *wrenches = param(request, "wrenches");
    const cJSON *fields = param(request, "fields");
    const cJSON *sets = param(request, "sets");
    const cJSON *given = param(request, "tolerance");
    double tolerance = cJSON_IsNumber(given) ? given->valuedouble : WR_DEFAULT_TOLERANCE;
    const cJSON *count = cJSON_GetObjectItemCaseSensitive(result, "count");
    const cJSON *pieces = cJSON_GetObjectItemCaseSensitive(result, "pieces");
    FUZZ_CHECK(cJSON_IsArray(wrenches) && cJSON_IsNumber(count) && cJSON_IsArray(pieces) &&
                   count->valuedouble == cJSON_GetArraySize(wrenches) &&
                   cJSON_GetArraySize(result) == 2,
               "classify by columns: count and pieces for %s", line);
    int total = 0;
    for (const cJSON *piece = pieces->child; piece; piece = piece->next) {
        const cJSON *n = cJSON_GetObjectItemCaseSensitive(piece, "count");
        FUZZ_CHECK(is_number_in(n, 1, 1e9), "classify by columns: a piece's count for %s", line);
        int m = n->valueint;
        total += m;
        const cJSON *set = piece->child->next; /* after "count" */
        for (int i = 0; i < (sets ? cJSON_GetArraySize(sets) : 2); i++, set = set->next) {
            const char *name = sets ? cJSON_GetArrayItem(sets, i)->valuestring
                                    : (i == 0 ? "goal" : "strong");
            FUZZ_CHECK(set && set->string && strcmp(set->string, name) == 0,
                       "classify by columns: set %s not in its place for %s", name, line);
            const cJSON *column = set->child;
            for (size_t c = 0; c < sizeof COLUMNS / sizeof COLUMNS[0]; c++) {
                bool asked = false;
                for (const cJSON *f = fields->child; f; f = f->next)
                    asked |= strcmp(f->valuestring, COLUMNS[c][0]) == 0;
                if (!asked)
                    continue;
                FUZZ_CHECK(column && strcmp(column->string, COLUMNS[c][1]) == 0 &&
                               (c == 0 ? cJSON_IsString(column) &&
                                             strlen(column->valuestring) == (size_t)m &&
                                             strspn(column->valuestring, "iob") == (size_t)m
                                       : cJSON_GetArraySize(column) == m),
                           "classify by columns: column %s of set %s for %s", COLUMNS[c][1],
                           name, line);
                column = column->next;
            }
            FUZZ_CHECK(!column, "classify by columns: a column not asked for %s", line);
            const cJSON *verdicts = cJSON_GetObjectItemCaseSensitive(set, "verdicts");
            const cJSON *margins = cJSON_GetObjectItemCaseSensitive(set, "margins");
            if (!verdicts || !margins)
                continue;
            int k = 0;
            for (const cJSON *x = margins->child; x; x = x->next, k++) {
                if (cJSON_IsNull(x))
                    continue; /* method "lp" */
                FUZZ_CHECK(is_number_in(x, -1, 1), "classify by columns: a margin for %s", line);
                char expected = x->valuedouble > tolerance    ? 'i'
                                : x->valuedouble < -tolerance ? 'o'
                                                              : 'b';
                if (wrench_is_zero(cJSON_GetArrayItem(wrenches, total - m + k))) {
                    FUZZ_CHECK(x->valuedouble == 0,
                               "classify by columns: the zero wrench has margin %.17g for %s",
                               x->valuedouble, line);
                    expected = strcmp(name, "strong") == 0 && verdicts->valuestring[k] == 'i'
                                   ? 'i'
                                   : 'o';
                }
                FUZZ_CHECK(verdicts->valuestring[k] == expected,
                           "classify by columns: margin %.17g, verdict %c for %s",
                           x->valuedouble, verdicts->valuestring[k], line);
            }
        }
        FUZZ_CHECK(!set, "classify by columns: a set not asked for %s", line);
    }
    FUZZ_CHECK(total == count->valueint, "classify by columns: pieces of %d wrenches, not %d "
                                         "for %s",
               total, count->valueint, line);
}

/* wrench.classify: one result per wrench, one answer per set asked, each
 * answer consistent (margin in [-1, 1] and the verdict it implies). */
static void check_classify(const cJSON *request, const cJSON *result, const char *line)
{
    if (param(request, "fields")) {
        check_classify_columns(request, result, line);
        return;
    }
    const cJSON *wrenches = param(request, "wrenches");
    const cJSON *results = cJSON_GetObjectItemCaseSensitive(result, "results");
    FUZZ_CHECK(cJSON_IsArray(results) && cJSON_IsArray(wrenches) &&
                   cJSON_GetArraySize(results) == cJSON_GetArraySize(wrenches),
               "classify: results do not match the wrenches for %s", line);
    const cJSON *sets = param(request, "sets");
    const cJSON *how = param(request, "method");
    bool lp = cJSON_IsString(how) && strcmp(how->valuestring, "lp") == 0;
    const cJSON *given = param(request, "tolerance");
    double tolerance = cJSON_IsNumber(given) ? given->valuedouble : WR_DEFAULT_TOLERANCE;
    int set_count = sets ? cJSON_GetArraySize(sets) : 2;
    /* On supports the verdicts are the seating and holding tests', without
     * margins; with a tolerance they are robust: an outside may name the
     * perturbed fixture that has it, and a boundary is whatever was not
     * proved (its margin the least met, of either sign). */
    bool supports, toleranced;
    fixture_traits(request, &supports, &toleranced);
    const cJSON *wrench = wrenches->child;
    for (const cJSON *item = results->child; item; item = item->next, wrench = wrench->next) {
        FUZZ_CHECK(cJSON_IsObject(item) && cJSON_GetArraySize(item) == set_count,
                   "classify: a result without one answer per set for %s", line);
        for (const cJSON *v = item->child; v; v = v->next) {
            const char *set = v->string;
            bool asked = false;
            if (sets) {
                for (const cJSON *s = sets->child; s; s = s->next)
                    asked |= cJSON_IsString(s) && strcmp(s->valuestring, set) == 0;
            } else {
                asked = strcmp(set, "goal") == 0 || strcmp(set, "strong") == 0;
            }
            FUZZ_CHECK(asked, "classify: answer for set \"%s\", not asked, for %s", set, line);
            const cJSON *verdict = cJSON_GetObjectItemCaseSensitive(v, "verdict");
            const cJSON *inside = cJSON_GetObjectItemCaseSensitive(v, "inside");
            const cJSON *margin = cJSON_GetObjectItemCaseSensitive(v, "margin");
            const cJSON *blocking = cJSON_GetObjectItemCaseSensitive(v, "blocking");
            const cJSON *states = cJSON_GetObjectItemCaseSensitive(v, "states");
            const cJSON *witness = cJSON_GetObjectItemCaseSensitive(v, "witness");
            const cJSON *perturbation = cJSON_GetObjectItemCaseSensitive(v, "perturbation");
            const cJSON *normals = cJSON_GetObjectItemCaseSensitive(v, "perturbation_normals");
            int extra = perturbation || normals ? 2 : 0;
            FUZZ_CHECK(cJSON_IsString(verdict) && cJSON_IsBool(inside) && margin && blocking &&
                           cJSON_IsArray(states) && witness &&
                           cJSON_GetArraySize(v) == 6 + extra,
                       "classify: answer members wrong for %s", line);
            FUZZ_CHECK(!extra || (toleranced && cJSON_IsArray(perturbation) &&
                                  cJSON_IsArray(normals) &&
                                  cJSON_GetArraySize(perturbation) == cJSON_GetArraySize(normals) &&
                                  strcmp(verdict->valuestring, "outside") == 0),
                       "classify: a perturbation but not an outside of a fixture with a "
                       "tolerance for %s", line);
            const char *word = verdict->valuestring;
            bool is_inside = strcmp(word, "inside") == 0;
            bool is_outside = strcmp(word, "outside") == 0;
            bool is_boundary = strcmp(word, "boundary") == 0;
            FUZZ_CHECK(is_inside || is_outside || is_boundary, "classify: verdict \"%s\" for %s",
                       word, line);
            FUZZ_CHECK(cJSON_IsTrue(inside) == is_inside,
                       "classify: \"inside\" disagrees with verdict \"%s\" for %s", word, line);
            FUZZ_CHECK(cJSON_IsNull(blocking) == cJSON_IsNull(witness),
                       "classify: blocking and witness disagree for %s", line);
            FUZZ_CHECK(!is_inside || cJSON_IsNull(blocking),
                       "classify: inside yet blocked for %s", line);
            FUZZ_CHECK(!cJSON_IsNull(blocking) || cJSON_GetArraySize(states) == 0,
                       "classify: states without a blocking cone for %s", line);
            /* No margin from either; no boundary from the LPs, while the
             * supports' holding may leave cells undecided (wr_support.h). */
            if (lp || supports) {
                FUZZ_CHECK(cJSON_IsNull(margin) && (supports || !is_boundary),
                           "classify: the lp method or supports gave a margin, or the lp "
                           "method a boundary, for %s", line);
                continue;
            }
            FUZZ_CHECK(is_number_in(margin, -1, 1), "classify: margin %.17g not in [-1, 1] for %s",
                       cJSON_IsNumber(margin) ? margin->valuedouble : NAN, line);
            double m = margin->valuedouble;
            if (wrench_is_zero(wrench)) {
                FUZZ_CHECK(m == 0, "classify: the zero wrench has margin %.17g for %s", m, line);
            } else if (toleranced) {
                FUZZ_CHECK(is_boundary || (is_inside ? m > tolerance : m < -tolerance),
                           "classify: robust margin %.17g, tolerance %.17g, verdict \"%s\" for "
                           "%s", m, tolerance, word, line);
            } else {
                /* The margin is printed shortest-round-trip: exactly the
                 * double the verdict was decided on. */
                const char *expected = m > tolerance    ? "inside"
                                       : m < -tolerance ? "outside"
                                                        : "boundary";
                FUZZ_CHECK(strcmp(word, expected) == 0,
                           "classify: margin %.17g, tolerance %.17g, verdict \"%s\" for %s", m,
                           tolerance, word, line);
            }
        }
    }
}

/* Sorted, disjoint, non-empty intervals [t0, t1] within [low, high]; for
 * push regions also by edge. */
static void check_intervals(const cJSON *list, bool regions, const char *line)
{
    FUZZ_CHECK(cJSON_IsArray(list), "regions/intervals not an array for %s", line);
    double last_edge = -1, last_t1 = -INFINITY;
    for (const cJSON *item = list->child; item; item = item->next) {
        double edge = 0, t0, t1;
        if (regions) {
            /* An outline's region names its loop and segment, in that
             * order; another shape's its edge. */
            const cJSON *e = cJSON_GetObjectItemCaseSensitive(item, "edge");
            const cJSON *loop = cJSON_GetObjectItemCaseSensitive(item, "loop");
            const cJSON *segment = cJSON_GetObjectItemCaseSensitive(item, "segment");
            const cJSON *a = cJSON_GetObjectItemCaseSensitive(item, "t0");
            const cJSON *b = cJSON_GetObjectItemCaseSensitive(item, "t1");
            const cJSON *length = cJSON_GetObjectItemCaseSensitive(item, "length");
            FUZZ_CHECK((e ? cJSON_IsNumber(e) && !loop && !segment
                          : is_number_in(loop, 0, 1e6) && is_number_in(segment, 0, 1e6)) &&
                           cJSON_IsNumber(a) && cJSON_IsNumber(b) && cJSON_IsNumber(length) &&
                           length->valuedouble >= 0,
                       "push.regions: a region's members for %s", line);
            edge = e ? e->valuedouble : loop->valuedouble * 1e6 + segment->valuedouble;
            t0 = a->valuedouble;
            t1 = b->valuedouble;
            FUZZ_CHECK(edge >= 0 && edge == floor(edge), "push.regions: edge %.17g for %s", edge,
                       line);
        } else {
            FUZZ_CHECK(cJSON_IsArray(item) && cJSON_GetArraySize(item) == 2 &&
                           cJSON_IsNumber(item->child) && cJSON_IsNumber(item->child->next),
                       "gravity.sweep: an interval is not [a, b] for %s", line);
            t0 = item->child->valuedouble;
            t1 = item->child->next->valuedouble;
        }
        FUZZ_CHECK(t0 < t1 && t0 >= 0 && t1 <= 360, "interval [%.17g, %.17g] for %s", t0, t1,
                   line);
        if (edge != last_edge)
            last_t1 = -INFINITY;
        FUZZ_CHECK(edge >= last_edge && t0 >= last_t1,
                   "intervals out of order or overlapping at edge %g [%.17g, %.17g] for %s", edge,
                   t0, t1, line);
        last_edge = edge;
        last_t1 = t1;
    }
}

static bool is_unit_or_null_vector(const cJSON *v, int n)
{
    if (!cJSON_IsArray(v) || cJSON_GetArraySize(v) != n)
        return false;
    double length = 0;
    for (const cJSON *x = v->child; x; x = x->next) {
        if (!cJSON_IsNumber(x))
            return false;
        length += x->valuedouble * x->valuedouble;
    }
    return fabs(sqrt(length) - 1) < 1e-6;
}

/* Intervals of mu: sorted, disjoint (touching at most), each [lo, hi]
 * with low <= lo <= hi <= top. */
static void check_mu_intervals(const cJSON *list, double low, double top, const char *line)
{
    FUZZ_CHECK(cJSON_IsArray(list), "friction.sweep: intervals not an array for %s", line);
    double last = -INFINITY;
    for (const cJSON *i = list->child; i; i = i->next) {
        const cJSON *lo = cJSON_GetArrayItem(i, 0), *hi = cJSON_GetArrayItem(i, 1);
        FUZZ_CHECK(cJSON_GetArraySize(i) == 2 && cJSON_IsNumber(lo) && cJSON_IsNumber(hi) &&
                       lo->valuedouble >= low && lo->valuedouble <= hi->valuedouble &&
                       hi->valuedouble <= top && lo->valuedouble > last,
                   "friction.sweep: an interval out of [%.17g, %.17g], of order or overlapping "
                   "for %s",
                   low, top, line);
        last = hi->valuedouble;
    }
}

/* friction.sweep: the intervals of mu within the range, and a deadline's
 * partial answer ("partial" only true, with "stopped_at" in the range and
 * nothing said above it; a whole answer has neither). */
static void check_sweep(const cJSON *request, const cJSON *result, const char *line)
{
    const cJSON *range = param(request, "range");
    double low = range ? cJSON_GetArrayItem(range, 0)->valuedouble : 0;
    double high = range ? cJSON_GetArrayItem(range, 1)->valuedouble : 2;
    const cJSON *partial = cJSON_GetObjectItemCaseSensitive(result, "partial");
    const cJSON *stopped = cJSON_GetObjectItemCaseSensitive(result, "stopped_at");
    FUZZ_CHECK((partial == NULL) == (stopped == NULL) && (!partial || cJSON_IsTrue(partial)),
               "friction.sweep: partial and stopped_at for %s", line);
    FUZZ_CHECK(!partial || (param(request, "deadline_s") && is_number_in(stopped, low, high)),
               "friction.sweep: a partial answer without a deadline or stopped out of the range "
               "for %s",
               line);
    double top = partial ? stopped->valuedouble : high;
    const cJSON *results = cJSON_GetObjectItemCaseSensitive(result, "results");
    const cJSON *curve = cJSON_GetObjectItemCaseSensitive(result, "curve");
    if (results) {
        FUZZ_CHECK(cJSON_IsArray(results), "friction.sweep: results for %s", line);
        for (const cJSON *r = results->child; r; r = r->next)
            for (const cJSON *set = r->child; set; set = set->next)
                check_mu_intervals(set, low, top, line);
    } else {
        const cJSON *intervals = cJSON_GetObjectItemCaseSensitive(result, "intervals");
        if (intervals)
            check_mu_intervals(intervals, low, top, line);
        FUZZ_CHECK(cJSON_IsArray(curve), "friction.sweep: curve for %s", line);
        double last = -INFINITY;
        for (const cJSON *p = curve->child; p; p = p->next) {
            const cJSON *mu = cJSON_GetArrayItem(p, 0);
            FUZZ_CHECK(cJSON_IsNumber(mu) && mu->valuedouble > last && mu->valuedouble >= low &&
                           mu->valuedouble <= top,
                       "friction.sweep: a curve's mu out of order or of [%.17g, %.17g] for %s",
                       low, top, line);
            last = mu->valuedouble;
        }
    }
}

/* A result of a served method, against what the request asked. */
static void check_result(const cJSON *request, const cJSON *result, const char *line)
{
    const char *method = method_of(request);
    if (strcmp(method, "fixture.put") == 0) {
        const cJSON *id = cJSON_GetObjectItemCaseSensitive(result, "id");
        const cJSON *fixels = cJSON_GetObjectItemCaseSensitive(result, "fixels");
        const cJSON *goal = cJSON_GetObjectItemCaseSensitive(result, "goal_cones");
        const cJSON *strong = cJSON_GetObjectItemCaseSensitive(result, "strong_cones");
        FUZZ_CHECK(cJSON_IsString(id) && wp_fixture_id_valid(id->valuestring),
                   "fixture.put: bad id for %s", line);
        FUZZ_CHECK(is_number_in(fixels, 1, WR_MAX_FIXELS), "fixture.put: fixels for %s", line);
        int k = fixels->valueint;
        FUZZ_CHECK(cJSON_IsNumber(goal) && goal->valueint == k << (k - 1),
                   "fixture.put: %d goal cones for %d fixels for %s", goal ? goal->valueint : -1,
                   k, line);
        FUZZ_CHECK(is_number_in(strong, 0, 1e6), "fixture.put: strong_cones for %s", line);
        FUZZ_CHECK(cJSON_IsBool(cJSON_GetObjectItemCaseSensitive(result, "pinned")),
                   "fixture.put: pinned for %s", line);
    } else if (strcmp(method, "wrench.classify") == 0) {
        check_classify(request, result, line);
    } else if (strcmp(method, "push.regions") == 0) {
        check_intervals(cJSON_GetObjectItemCaseSensitive(result, "regions"), true, line);
        const cJSON *fraction = cJSON_GetObjectItemCaseSensitive(result, "fraction");
        const cJSON *exact = cJSON_GetObjectItemCaseSensitive(result, "exact");
        const cJSON *resolution = cJSON_GetObjectItemCaseSensitive(result, "resolution");
        FUZZ_CHECK(is_number_in(fraction, 0, 1 + 1e-9), "push.regions: fraction %.17g for %s",
                   cJSON_IsNumber(fraction) ? fraction->valuedouble : NAN, line);
        FUZZ_CHECK(cJSON_IsBool(exact) && cJSON_IsNumber(resolution) &&
                       cJSON_IsTrue(exact) == (resolution->valuedouble == 0),
                   "push.regions: exact and resolution disagree for %s", line);
    } else if (strcmp(method, "gravity.sweep") == 0) {
        check_intervals(cJSON_GetObjectItemCaseSensitive(result, "intervals_deg"), false, line);
    } else if (strcmp(method, "stability.margin") == 0) {
        const cJSON *margin = cJSON_GetObjectItemCaseSensitive(result, "margin");
        const cJSON *blocking = cJSON_GetObjectItemCaseSensitive(result, "blocking");
        const cJSON *worst = cJSON_GetObjectItemCaseSensitive(result, "worst_direction");
        FUZZ_CHECK(margin && blocking && worst, "stability.margin: members for %s", line);
        if (cJSON_IsNull(margin)) {
            FUZZ_CHECK(cJSON_IsNull(blocking) && cJSON_IsNull(worst),
                       "stability.margin: unbounded but blocking for %s", line);
        } else {
            FUZZ_CHECK(cJSON_IsNumber(margin) && isfinite(margin->valuedouble) &&
                           cJSON_IsString(blocking) && cJSON_IsArray(worst) &&
                           cJSON_GetArraySize(worst) == 3,
                       "stability.margin: bounded answer malformed for %s", line);
            for (const cJSON *x = worst->child; x; x = x->next)
                FUZZ_CHECK(cJSON_IsNumber(x), "stability.margin: worst_direction has %s for %s",
                           wp_type_name(x), line);
        }
    } else if (strcmp(method, "cone.get") == 0) {
        const cJSON *empty = cJSON_GetObjectItemCaseSensitive(result, "empty");
        const cJSON *dimension = cJSON_GetObjectItemCaseSensitive(result, "dimension");
        const cJSON *halfspaces = cJSON_GetObjectItemCaseSensitive(result, "halfspaces");
        const cJSON *strict = cJSON_GetObjectItemCaseSensitive(result, "strict");
        const cJSON *equalities = cJSON_GetObjectItemCaseSensitive(result, "equalities");
        const cJSON *generators = cJSON_GetObjectItemCaseSensitive(result, "generators");
        FUZZ_CHECK(cJSON_IsBool(empty) && is_number_in(dimension, -1, 3) &&
                       cJSON_IsArray(halfspaces) && cJSON_IsArray(strict) &&
                       cJSON_IsArray(equalities) && cJSON_IsArray(generators),
                   "cone.get: members for %s", line);
        FUZZ_CHECK(cJSON_IsTrue(empty) == (dimension->valueint == -1),
                   "cone.get: empty and dimension %d disagree for %s", dimension->valueint, line);
        FUZZ_CHECK(cJSON_GetArraySize(halfspaces) == cJSON_GetArraySize(strict),
                   "cone.get: halfspaces and strict differ in length for %s", line);
        FUZZ_CHECK(cJSON_IsTrue(empty) ||
                       cJSON_GetArraySize(equalities) == 3 - dimension->valueint,
                   "cone.get: %d equalities at dimension %d for %s",
                   cJSON_GetArraySize(equalities), dimension->valueint, line);
        for (const cJSON *g = generators->child; g; g = g->next)
            FUZZ_CHECK(is_unit_or_null_vector(g, 3), "cone.get: a generator not of unit length for %s",
                       line);
        for (const cJSON *h = halfspaces->child; h; h = h->next)
            FUZZ_CHECK(is_unit_or_null_vector(h, 3), "cone.get: a halfspace row not of unit length for %s",
                       line);
    } else if (strcmp(method, "plan.get") == 0) {
        const cJSON *states = cJSON_GetObjectItemCaseSensitive(result, "states");
        const cJSON *cones = cJSON_GetObjectItemCaseSensitive(result, "cones");
        FUZZ_CHECK(cJSON_IsArray(states) && cJSON_IsArray(cones), "plan.get: members for %s",
                   line);
        int n = cJSON_GetArraySize(states), k = 0;
        while (k < WR_MAX_FIXELS && 1 << k < n)
            k++;
        FUZZ_CHECK(n == 1 << k && k >= 1 && cJSON_GetArraySize(cones) == k << (k - 1),
                   "plan.get: %d states, %d cones for %s", n, cJSON_GetArraySize(cones), line);
    } else if (strcmp(method, "server.status") == 0) {
        const cJSON *version = cJSON_GetObjectItemCaseSensitive(result, "version");
        FUZZ_CHECK(cJSON_IsString(version) && strcmp(version->valuestring, WR_VERSION) == 0,
                   "server.status: version for %s", line);
    } else if (strcmp(method, "fixture.list") == 0) {
        /* A page: sorted ids after params.after, at most params.limit
         * (1000 by default), names at most WP_NAME_MAX bytes, `more` a
         * boolean. */
        const cJSON *list = cJSON_GetObjectItemCaseSensitive(result, "fixtures");
        const cJSON *limit = param(request, "limit");
        const cJSON *after = param(request, "after");
        FUZZ_CHECK(cJSON_IsArray(list) && cJSON_IsBool(cJSON_GetObjectItemCaseSensitive(result, "more")),
                   "fixture.list: fixtures and more for %s", line);
        FUZZ_CHECK(cJSON_GetArraySize(list) <= (cJSON_IsNumber(limit) ? limit->valuedouble : 1000),
                   "fixture.list: a page over its limit for %s", line);
        const char *previous = cJSON_IsString(after) ? after->valuestring : "";
        const cJSON *item;
        cJSON_ArrayForEach(item, list) {
            const cJSON *id = cJSON_GetObjectItemCaseSensitive(item, "id");
            const cJSON *name = cJSON_GetObjectItemCaseSensitive(item, "name");
            FUZZ_CHECK(cJSON_IsString(id) && strcmp(id->valuestring, previous) > 0,
                       "fixture.list: ids not sorted after params.after for %s", line);
            FUZZ_CHECK(!cJSON_IsString(name) || strlen(name->valuestring) <= WP_NAME_MAX,
                       "fixture.list: a name over %d bytes for %s", WP_NAME_MAX, line);
            previous = id->valuestring;
        }
    } else if (strcmp(method, "friction.sweep") == 0) {
        check_sweep(request, result, line);
    } else if (strcmp(method, "fixture.design") == 0) {
        /* Within --max-candidates, and "partial" only as true, with fewer
         * examined than candidates. */
        const cJSON *counts = cJSON_GetObjectItemCaseSensitive(result, "counts");
        const cJSON *candidates = cJSON_GetObjectItemCaseSensitive(counts, "candidates");
        const cJSON *examined = cJSON_GetObjectItemCaseSensitive(counts, "examined");
        const cJSON *partial = cJSON_GetObjectItemCaseSensitive(result, "partial");
        FUZZ_CHECK(is_number_in(candidates, 0, 1e18) && is_number_in(examined, 0, 1e18),
                   "fixture.design: counts for %s", line);
        FUZZ_CHECK(!partial || (cJSON_IsTrue(partial) &&
                                examined->valuedouble < candidates->valuedouble),
                   "fixture.design: partial for %s", line);
        const cJSON *shard = cJSON_GetObjectItemCaseSensitive(result, "shard");
        const cJSON *shards = cJSON_IsArray(shard) ? cJSON_GetArrayItem(shard, 1) : NULL;
        FUZZ_CHECK(partial || examined->valuedouble == candidates->valuedouble ||
                       (cJSON_IsNumber(shards) && shards->valuedouble > 1),
                   "fixture.design: a whole answer examined %g of %g for %s",
                   examined->valuedouble, candidates->valuedouble, line);
    }
}

/* One response object, answering `request` (NULL: a line refused whole). */
static void check_response(const cJSON *response, const cJSON *request, const char *line)
{
    static const char *const RESULT_MEMBERS[] = {"jsonrpc", "result", "id"};
    static const char *const ERROR_MEMBERS[] = {"jsonrpc", "error", "id"};
    bool is_result = has_exactly(response, RESULT_MEMBERS, 3);
    FUZZ_CHECK(is_result || has_exactly(response, ERROR_MEMBERS, 3),
               "a response's members are not jsonrpc, result|error, id for %s", line);
    const cJSON *version = cJSON_GetObjectItemCaseSensitive(response, "jsonrpc");
    FUZZ_CHECK(cJSON_IsString(version) && strcmp(version->valuestring, "2.0") == 0,
               "response jsonrpc is not \"2.0\" for %s", line);
    const cJSON *id = cJSON_GetObjectItemCaseSensitive(response, "id");
    /* The id: the request's when it is a string or a finite number, else null. */
    const cJSON *asked = cJSON_IsObject(request) ? cJSON_GetObjectItemCaseSensitive(request, "id")
                                                 : NULL;
    bool echo = cJSON_IsString(asked) || (cJSON_IsNumber(asked) && isfinite(asked->valuedouble));
    if (echo)
        FUZZ_CHECK(cJSON_Compare(id, asked, true) &&
                       (!cJSON_IsNumber(id) || id->valuedouble == asked->valuedouble),
                   "the response's id is not the request's for %s", line);
    else
        FUZZ_CHECK(cJSON_IsNull(id), "a response id that is not null for %s", line);
    if (!is_result) {
        check_error(cJSON_GetObjectItemCaseSensitive(response, "error"), line);
        return;
    }
    FUZZ_CHECK(request && valid_request(request), "a result for an invalid request: %s", line);
    check_result(request, cJSON_GetObjectItemCaseSensitive(response, "result"), line);
}

/* The answer to a line: NULL or one line of JSON-RPC responses.  `json` is
 * the line as cJSON reads it (NULL when it does not); `whole` says the
 * answerer must refuse the line before reading its requests (not UTF-8,
 * nested deeper than the limit, a \u0000 escape, a batch over the limit). */
static void check_answer(const cJSON *json, bool whole, const char *answer, const char *line,
                         const wp_counts *counts)
{
    if (!answer) {
        FUZZ_CHECK(json && !whole, "no answer to a line refused whole: %s", line);
        if (cJSON_IsArray(json)) {
            FUZZ_CHECK(json->child, "no answer to an empty batch: %s", line);
            for (const cJSON *r = json->child; r; r = r->next)
                FUZZ_CHECK(notification(r), "no answer to a batch with a request: %s", line);
        } else {
            FUZZ_CHECK(notification(json), "no answer to a request: %s", line);
        }
        return;
    }
    size_t length = strlen(answer);
    FUZZ_CHECK(length >= 2 && answer[length - 1] == '\n', "the answer does not end in \\n: %s",
               line);
    FUZZ_CHECK(memchr(answer, '\n', length - 1) == NULL, "the answer is more than one line: %s",
               line);
    FUZZ_CHECK(wp_utf8_valid(answer, length), "the answer is not UTF-8: %s", line);
    const char *end = NULL;
    cJSON *response = cJSON_ParseWithLengthOpts(answer, length - 1, &end, false);
    FUZZ_CHECK(response && end == answer + length - 1, "the answer is not one JSON text: %s\n%s",
               line, answer);
    FUZZ_CHECK(counts->requests >= 1 && counts->errors <= counts->requests,
               "counts %lu requests, %lu errors", counts->requests, counts->errors);
    bool batch = cJSON_IsArray(json) && json->child && !whole;
    if (batch) {
        /* One response per request that is not a notification, in order. */
        FUZZ_CHECK(cJSON_IsArray(response), "a batch not answered by an array: %s\n%s", line,
                   answer);
        const cJSON *r = json->child;
        int responses = 0;
        for (const cJSON *a = response->child; a; a = a->next, r = r->next) {
            while (r && notification(r))
                r = r->next;
            FUZZ_CHECK(r, "more responses than requests: %s\n%s", line, answer);
            check_response(a, r, line);
            responses++;
        }
        while (r && notification(r))
            r = r->next;
        FUZZ_CHECK(!r, "fewer responses than requests: %s\n%s", line, answer);
        FUZZ_CHECK(responses > 0, "an empty batch answer: %s", line);
        FUZZ_CHECK(counts->requests == (unsigned long)cJSON_GetArraySize(json),
                   "counts %lu requests for a batch of %d", counts->requests,
                   cJSON_GetArraySize(json));
    } else if (!json || whole || cJSON_IsArray(json)) {
        /* Refused whole: not JSON, not to be read, or an empty batch. */
        FUZZ_CHECK(cJSON_IsObject(response), "a line refused whole, answered by %s: %s\n%s",
                   wp_type_name(response), line, answer);
        const cJSON *error = cJSON_GetObjectItemCaseSensitive(response, "error");
        const cJSON *code = cJSON_GetObjectItemCaseSensitive(error, "code");
        FUZZ_CHECK(cJSON_IsNumber(code) &&
                       (code->valueint == WP_PARSE_ERROR || code->valueint == WP_INVALID_REQUEST),
                   "a line to be refused whole (%s) was answered: %s\n%s", refusal, line,
                   answer);
        check_response(response, NULL, line);
        FUZZ_CHECK(counts->requests == 1 && counts->errors == 1,
                   "counts %lu, %lu for a line refused whole", counts->requests, counts->errors);
    } else {
        FUZZ_CHECK(cJSON_IsObject(response), "a request answered by %s: %s\n%s",
                   wp_type_name(response), line, answer);
        check_response(response, json, line);
        FUZZ_CHECK(counts->requests == 1, "counts %lu requests for one", counts->requests);
    }
    cJSON_Delete(response);
}

/* ---- driving ----------------------------------------------------------------- */

/* The daemon makes answers a piece at a time: cut into the smallest pieces
 * there are, the same line answers byte for byte what it answered whole --
 * unless it asks what changes between two askings (a deletion, the
 * server's counters, a store past its bound, an LP's witness, where a
 * deadline stopped it). */
static void pieces_agree(const char *line, size_t length, const char *whole, const char *text)
{
    if (memmem(line, length, "delete", 6) || memmem(line, length, "status", 6) ||
        memmem(line, length, "list", 4) ||
        /* A deadline's answer ends where the clock stopped it. */
        memmem(line, length, "deadline", 8) ||
        /* The LP method's witnesses hang on the solver's warm start: asked
         * again, their last bits may differ (load-check drops them too). */
        memmem(line, length, "\"lp\"", 4))
        return;
    wp_answer *answer = wp_answer_begin(&LIMITS, host, line, length);
    FUZZ_CHECK(answer, "wp_answer_begin failed for %s", text);
    wp_answer_pieces(answer, 1, 1);
    wp_buffer joined = {0};
    wp_counts counts = {0, 0};
    wp_step step;
    do {
        step = wp_answer_step(answer, host, &joined, &counts);
        FUZZ_CHECK(step != WP_STEP_FAILED, "an answer in pieces failed for %s", text);
    } while (step == WP_STEP_MORE);
    wp_answer_free(answer, host);
    FUZZ_CHECK(!joined.failed, "out of memory in pieces for %s", text);
    FUZZ_CHECK((joined.length == 0) == (whole == NULL) &&
                   (!whole || (joined.length == strlen(whole) &&
                               memcmp(joined.data, whole, joined.length) == 0)),
               "in pieces the answer differs for %s:\n%s\n%.*s", text, whole ? whole : "(none)",
               (int)joined.length, joined.data ? joined.data : "");
    free(joined.data);
}


static void answer_line(const uint8_t *data, size_t length)
{
    /* The request as cJSON reads it, for the checks (the answerer's own
     * refusals, such as nesting or \u0000, are checked by their form). */
    const char *end = NULL;
    char *text = fuzz_strndup(data, length); /* for messages and for cJSON */
    cJSON *json = cJSON_ParseWithLengthOpts(text, length, &end, false);
    if (json) {
        /* Trailing white space is allowed, anything else is not one text. */
        while (end < text + length && (*end == ' ' || *end == '\t' || *end == '\r' ||
                                       *end == '\n' || *end == '\f' || *end == '\v'))
            end++;
        if (end != text + length) {
            cJSON_Delete(json);
            json = NULL;
        }
    }
    wp_json_shape shape = wp_json_scan(text, length, LIMITS.max_depth);
    refusal = json ? "" : "not JSON";
    /* Raw control characters: not JSON, whatever cJSON makes of them, so
     * the line must be refused as a parse error.  Either answer will do
     * when the only ones are \v or \f at an end of the line (trimmed as
     * white space, or refused), or when the known finding "controls" (cJSON
     * reads them) is stepped over. */
    bool either = false;
    if (json && !control_characters_ok(text, length, false)) {
        either = control_characters_ok(text, length, true) || fuzz_skip_known("controls");
        if (!either) {
            refusal = "a raw control character: not JSON (RFC 8259), though cJSON reads it";
            cJSON_Delete(json);
            json = NULL;
        }
    }
    if (json && !escapes_ok(text, length)) {
        refusal = "an escape RFC 8259 does not allow, though cJSON reads it";
        cJSON_Delete(json);
        json = NULL;
    }
    if (json && !numbers_ok(text, length)) {
        refusal = "a number RFC 8259 does not allow, though cJSON reads it";
        cJSON_Delete(json);
        json = NULL;
    }
    bool whole = !wp_utf8_valid(text, length) || shape.depth > LIMITS.max_depth ||
                 shape.nul_escape ||
                 (cJSON_IsArray(json) && (size_t)cJSON_GetArraySize(json) > LIMITS.max_batch);
    unsigned hash = fuzz_hash(data, length);
    if (!whole && too_slow(json, fuzz_full || hash % SLOW_SHARE == 0)) {
        skipped++;
        if (verbose)
            fprintf(stderr, "> %s\n(skipped: slow)\n", text);
        cJSON_Delete(json);
        free(text);
        return;
    }
    /* Exactly `length` bytes: no NUL after the line. */
    char *line = malloc(length ? length : 1);
    if (!line)
        abort();
    if (length)
        memcpy(line, data, length);
    wp_counts counts = {0, 0};
    struct timespec before, after;
    clock_gettime(CLOCK_MONOTONIC, &before);
    char *answer = wp_answer_line(host, &LIMITS, line, length, &counts);
    clock_gettime(CLOCK_MONOTONIC, &after);
    /* Asked again in pieces, but only when that is cheap: a line that
     * derives a large fixture's cones would double an input's time; and
     * while fuzzing, one line in four (by its hash: fuzz_full). */
    long elapsed = (after.tv_sec - before.tv_sec) * 1000000000L + (after.tv_nsec - before.tv_nsec);
    if (elapsed < 20000000L && (fuzz_full || hash / SLOW_SHARE % 4 == 0))
        pieces_agree(line, length, answer, text);
    if (verbose)
        fprintf(stderr, "> %s\n< %s", text, answer ? answer : "(no answer)\n");
    if (either && parse_error_answer(answer))
        check_answer(NULL, whole, answer, text, &counts); /* refused: as for non-JSON */
    else
        check_answer(json, whole, answer, text, &counts);
    free(answer);
    free(line);
    cJSON_Delete(json);
    free(text);
}

/* Keep the store bounded across inputs: past STORE_BOUND, forget it all. */
static void bound_store(void)
{
    wd_cache_stats s;
    wd_cache_stats_get(cache, &s);
    FUZZ_CHECK(s.derived_limit == DERIVED_LIMIT, "derived limit %zu", s.derived_limit);
    /* Nothing is in use between inputs: the derived data is within bound. */
    FUZZ_CHECK(s.derived_bytes <= s.derived_limit, "%zu bytes of derived data, the limit is %zu",
               s.derived_bytes, s.derived_limit);
    if (s.stored <= STORE_BOUND)
        return;
    wp_fixture_listing listing;
    wp_host_failure failure;
    FUZZ_CHECK(host->fixture_list(host->self, &listing, &failure), "fixture_list failed");
    FUZZ_CHECK(listing.count == s.stored, "%zu listed, %zu stored", listing.count, s.stored);
    for (size_t i = 0; i < listing.count; i++)
        FUZZ_CHECK(host->fixture_delete(host->self, listing.entries[i].id, &failure),
                   "deleting a listed fixture failed");
    wp_fixture_listing_release(&listing);
    wd_cache_stats_get(cache, &s);
    FUZZ_CHECK(s.stored == 0, "%zu stored after deleting all", s.stored);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    size_t start = 0;
    for (size_t i = 0; i <= size; i++)
        if (i == size || data[i] == '\n') {
            if (i < size || start < size || size == 0)
                answer_line(data + start, i - start);
            start = i + 1;
        }
    bound_store();
    return 0;
}
