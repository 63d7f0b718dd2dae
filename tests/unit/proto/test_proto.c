/* test_proto.c -- the protocol layer without sockets: SHA-256, numbers,
 * canonical ids, and the envelope, against the daemon's real cache. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>
#include <math.h>
#include <pthread.h>
#include <sched.h>
#include <stdatomic.h>
#include <time.h>
#include <stdio.h>

#include "test_util.h"
#include "wd_worker.h"
#include "wp_chunks.h"
#include "wp_rpc.h"
#include "wp_sha256.h"

static void hex(const unsigned char digest[32], char out[65])
{
    for (int i = 0; i < 32; i++)
        snprintf(out + 2 * i, 3, "%02x", digest[i]);
}

/* FIPS 180-4 examples (NIST CSRC "SHA256.pdf", "SHA2_Additional.pdf"). */
static void sha256_matches_nist_vectors(void **state)
{
    (void)state;
    struct {
        const char *text;
        size_t repeat;
        const char *digest;
    } vectors[] = {
        {"abc", 1, "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad"},
        {"", 1, "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855"},
        {"abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq", 1,
         "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1"},
        {"a", 1000000, "cdc76e5c9914fb9281a1c7e284d73e67f1809a48a497200e046d39ccc7112cd0"},
    };
    for (size_t v = 0; v < sizeof vectors / sizeof vectors[0]; v++) {
        wp_sha256 hash;
        wp_sha256_init(&hash);
        for (size_t r = 0; r < vectors[v].repeat; r++)
            wp_sha256_update(&hash, vectors[v].text, strlen(vectors[v].text));
        unsigned char digest[32];
        char text[65];
        wp_sha256_final(&hash, digest);
        hex(digest, text);
        assert_string_equal(text, vectors[v].digest);
    }
}

/* Shortest round-trip text: reads back exactly, and no shorter %g text
 * does (checked on random bit patterns, so every exponent range). */
static void numbers_round_trip_shortest(void **state)
{
    (void)state;
    test_rng rng = {31337};
    int checked = 0;
    for (int i = 0; i < 200000; i++) {
        uint64_t bits = (uint64_t)(test_uniform(&rng) * 4294967296.0) << 32 |
                        (uint64_t)(test_uniform(&rng) * 4294967296.0);
        double value;
        memcpy(&value, &bits, sizeof value);
        if (!isfinite(value))
            continue;
        char text[32], shorter[400];
        wp_format_number(value, text);
        assert_true(strtod(text, NULL) == value);
        int digits = 0;
        for (const char *c = text; *c && *c != 'e'; c++)
            digits += *c >= '0' && *c <= '9';
        if (digits > 1 && value != 0) {
            snprintf(shorter, sizeof shorter, "%.*g", digits - 1, value);
            assert_true(strtod(shorter, NULL) != value || strlen(shorter) >= strlen(text));
        }
        checked++;
    }
    char text[32];
    wp_format_number(-0.0, text);
    assert_string_equal(text, "0");
    wp_format_number(1.0, text);
    assert_string_equal(text, "1");
    wp_format_number(0.1, text);
    assert_string_equal(text, "0.1");
    print_message("proto: %d random doubles round-trip through their shortest text\n", checked);
}

/* The 3-2-1 plate: a polygon of four edges, regions on two. */
static const char PLATE[] =
    "{\"body\":{\"mass\":1,\"shape\":{\"type\":\"polygon\",\"vertices\":[[0,0],[4,0],[4,2],[0,2]]}},"
    "\"friction\":{\"static\":0.3},\"fixels\":[{\"at\":[1,0]},{\"at\":[3,0]},{\"at\":[0,1]}]}";

static const char DISC[] =
    "{\"name\":\"a\",\"body\":{\"mass\":1,\"inertia\":0.5,\"com\":[0,0],"
    "\"shape\":{\"type\":\"circle\",\"center\":[0,0],\"radius\":1}},"
    "\"friction\":{\"static\":0.5},\"fixels\":[{\"at\":[-1,0],\"normal\":[1,0]},"
    "{\"at\":[0,-1],\"normal\":[0,1]}]}";
/* The same content: other key order, other number spellings, other name. */
static const char DISC_AGAIN[] =
    "{\"fixels\":[{\"normal\":[1.0,0e3],\"at\":[-1.0,0.0]},{\"at\":[0,-1E0],\"normal\":[0,1]}],"
    "\"friction\":{\"static\":5e-1},\"body\":{\"shape\":{\"radius\":1.0,\"center\":[-0,0],"
    "\"type\":\"circle\"},\"com\":[0,0],\"inertia\":0.50,\"mass\":1.0},\"name\":\"b\"}";

/* The writer keeps the commas and the nesting: the text below, written
 * value by value, across two buffers (a stream's steps), with a sequence of
 * values made apart and put in (a chunk), and a string's room. */
static void the_writer_keeps_commas_and_nesting(void **state)
{
    (void)state;
    wp_buffer first = {0}, second = {0}, chunk = {0};
    wp_writer w = wp_writer_on(&first);
    wp_write_object(&w);
    wp_write_member_number(&w, "n", -0.0);
    wp_write_member_string(&w, "s", "a\"b\\c\n\x01");
    wp_write_key(&w, "list");
    wp_write_array(&w);
    wp_write_array(&w);
    wp_write_array_end(&w);
    wp_write_object(&w);
    wp_write_object_end(&w);
    wp_write_numbers(&w, (const double[]){0.1, 1e21, 5}, 3);
    wp_write_numbers(&w, NULL, 0);
    w.out = &second; /* the next step's piece */
    wp_write_bool(&w, true);
    wp_write_null(&w);
    wp_writer apart = wp_writer_in_array(&chunk);
    wp_write_number(&apart, 1);
    wp_write_object(&apart);
    wp_write_member_bool(&apart, "b", false);
    wp_write_object_end(&apart);
    wp_write_raw(&w, chunk.data, chunk.length);
    wp_write_raw(&w, "", 0);
    char *room = wp_write_string_room(&w, 3);
    assert_non_null(room);
    memcpy(room, "iob", 3);
    wp_write_array_end(&w);
    wp_write_object_end(&w);
    assert_int_equal(w.depth, 0);
    char *a = wp_buffer_take(&first), *b = wp_buffer_take(&second), *c = wp_buffer_take(&chunk);
    assert_string_equal(a, "{\"n\":0,\"s\":\"a\\\"b\\\\c\\n\\u0001\",\"list\":[[],{},[0.1,1e+21,5],[]");
    assert_string_equal(b, ",true,null,1,{\"b\":false},\"iob\"]}");
    assert_string_equal(c, "1,{\"b\":false}");
    /* Whole, it is JSON that reads back to the values written. */
    char whole[256];
    snprintf(whole, sizeof whole, "%s%s", a, b);
    cJSON *json = cJSON_Parse(whole);
    assert_non_null(json);
    assert_int_equal(cJSON_GetArraySize(cJSON_GetObjectItem(json, "list")), 9);
    assert_string_equal(cJSON_GetObjectItem(json, "s")->valuestring, "a\"b\\c\n\x01");
    cJSON_Delete(json);
    free(a);
    free(b);
    free(c);
    /* At depth 0, values are separate texts: no comma between them. */
    wp_buffer lines = {0};
    wp_writer top = wp_writer_on(&lines);
    wp_write_number(&top, 1);
    wp_write_null(&top);
    char *text = wp_buffer_take(&lines);
    assert_string_equal(text, "1null");
    free(text);
}

static void fixture_id_ignores_order_spelling_and_name(void **state)
{
    (void)state;
    cJSON *a = cJSON_Parse(DISC), *b = cJSON_Parse(DISC_AGAIN);
    wp_fixture_doc x, y;
    wp_error error;
    assert_true(wp_fixture_read(a, "params.fixture", &x, &error));
    assert_true(wp_fixture_read(b, "params.fixture", &y, &error));
    assert_string_equal(x.id, y.id);
    assert_true(wp_fixture_id_valid(x.id));
    assert_string_equal(x.name, "a");
    assert_string_equal(y.name, "b");
    /* Another friction is another fixture. */
    cJSON_SetNumberValue(cJSON_GetObjectItem(cJSON_GetObjectItem(a, "friction"), "static"), 0.6);
    wp_fixture_doc z;
    assert_true(wp_fixture_read(a, "params.fixture", &z, &error));
    assert_string_not_equal(x.id, z.id);
    wp_fixture_doc_release(&x);
    wp_fixture_doc_release(&y);
    wp_fixture_doc_release(&z);
    cJSON_Delete(a);
    cJSON_Delete(b);
}

/* Every double of two fixtures is the same, bit for bit (memcmp: -0 and +0
 * differ). */
static void assert_same_fixture(const wr_fixture *a, const wr_fixture *b)
{
    assert_memory_equal(&a->mass, &b->mass, sizeof a->mass);
    assert_memory_equal(&a->inertia, &b->inertia, sizeof a->inertia);
    assert_memory_equal(a->com, b->com, sizeof a->com);
    assert_memory_equal(&a->gyration_radius, &b->gyration_radius, sizeof a->gyration_radius);
    assert_int_equal(a->shape, b->shape);
    assert_memory_equal(a->center, b->center, sizeof a->center);
    assert_int_equal(a->vertex_count, b->vertex_count);
    if (a->vertex_count)
        assert_memory_equal(a->vertices, b->vertices, a->vertex_count * sizeof *a->vertices);
    assert_int_equal(a->fixel_count, b->fixel_count);
    assert_memory_equal(a->fixels, b->fixels, (size_t)a->fixel_count * sizeof *a->fixels);
}

/* The id hashes the explicit form (every default written out), so
 * writing out a default keeps it; the stored text reads back to the same
 * fixture, bit for bit, and to the same text and id. */
static void explicit_form_reads_back_to_the_same_fixture(void **state)
{
    (void)state;
    static const char *const fixtures[] = {
        /* derived normals (-0 components on the bottom edge), com, inertia */
        "{\"body\":{\"mass\":2,\"shape\":{\"type\":\"polygon\",\"vertices\":"
        "[[0,0],[4,0],[4,1],[3,2],[0,2]]}},\"friction\":{\"static\":0.1},"
        "\"fixels\":[{\"at\":[1,0]},{\"at\":[3.5,1.5]},{\"at\":[0,0.5]}]}",
        /* a circle's derived normal off the axes; a -0 in the input */
        "{\"name\":\"n\",\"body\":{\"mass\":1.5,\"shape\":{\"type\":\"circle\",\"center\":[-0.0,0.25],"
        "\"radius\":1.3}},\"friction\":{\"static\":0.5,\"kinetic\":0.25},"
        "\"fixels\":[{\"at\":[-1.3,0.25]},{\"at\":[0.78,-0.79],\"friction\":{\"static\":0.2}}]}",
        /* given normals: scaled, near unit, at a vertex */
        "{\"body\":{\"mass\":1,\"shape\":{\"type\":\"polygon\",\"vertices\":"
        "[[0,0],[3,0],[0,3]]}},\"friction\":{\"static\":0.3},"
        "\"fixels\":[{\"at\":[1,0],\"normal\":[0.1,3]},"
        "{\"at\":[0,0],\"normal\":[0.7071067811865476,0.7071067811865476]},"
        "{\"at\":[1.5,1.5],\"normal\":[-0.6,-0.8]}]}",
        /* no shape: com and inertia given */
        "{\"body\":{\"mass\":3,\"inertia\":0.7,\"com\":[0.1,-0.2]},\"friction\":{\"static\":0.4},"
        "\"fixels\":[{\"at\":[-1,0],\"normal\":[1,0.1]},{\"at\":[0,-1],\"normal\":[0,2]}]}",
        /* an outline with an arc, units, a friction interval, a name to escape */
        "{\"name\":\"q\\\"\\u0001\",\"units\":{\"length\":\"mm\",\"force\":\"lbf\"},"
        "\"body\":{\"mass\":1,\"shape\":{\"type\":\"outline\",\"loops\":"
        "[[[0,0],[4,0,0.5],[4,2],[0,2]]]}},\"friction\":{\"static\":[0.2,0.4]},"
        "\"fixels\":[{\"at\":[2,0]},{\"at\":[0,1]},{\"at\":[2,2]}]}",
        /* a tolerance with an angle; and one of position alone */
        "{\"tolerance\":{\"angle\":0.01,\"position\":0.05},\"body\":{\"mass\":1,\"shape\":"
        "{\"type\":\"polygon\",\"vertices\":[[0,0],[4,0],[4,2],[0,2]]}},"
        "\"friction\":{\"static\":0.3},\"fixels\":[{\"at\":[2,0]},{\"at\":[0,1]},{\"at\":[2,2]}]}",
        "{\"tolerance\":{\"position\":0.05,\"angle\":0},\"body\":{\"mass\":1,\"shape\":"
        "{\"type\":\"polygon\",\"vertices\":[[0,0],[4,0],[4,2],[0,2]]}},"
        "\"friction\":{\"static\":0.3},\"fixels\":[{\"at\":[2,0]},{\"at\":[0,1]},{\"at\":[2,2]}]}",
        /* supports with down clamps and a friction interval; and without */
        "{\"supports\":{\"g\":9.81,\"points\":[[1,1],[3,0.5],[3,1.5]],\"friction\":"
        "{\"static\":[0.3,0.5],\"kinetic\":0.2},\"down\":[{\"force\":2,\"at\":[2,1]}]},"
        "\"body\":{\"mass\":1,\"shape\":{\"type\":\"polygon\",\"vertices\":[[0,0],[4,0],[4,2],"
        "[0,2]]}},\"friction\":{\"static\":0.3},\"fixels\":[{\"at\":[2,0]},{\"at\":[0,1]},"
        "{\"at\":[2,2]}]}",
        "{\"supports\":{\"points\":[[1,1],[3,0.5],[3,1.5]],\"friction\":0.4,\"g\":9.81},"
        "\"body\":{\"mass\":1,\"shape\":{\"type\":\"polygon\",\"vertices\":[[0,0],[4,0],[4,2],"
        "[0,2]]}},\"friction\":{\"static\":0.3},\"fixels\":[{\"at\":[2,0]},{\"at\":[0,1]},"
        "{\"at\":[2,2]}]}",
    };
    for (size_t i = 0; i < sizeof fixtures / sizeof *fixtures; i++) {
        cJSON *given = cJSON_Parse(fixtures[i]);
        assert_non_null(given);
        wp_fixture_doc first, again;
        wp_error error;
        assert_true(wp_fixture_read(given, "params.fixture", &first, &error));
        cJSON *stored = cJSON_Parse(first.canonical);
        assert_non_null(stored);
        assert_null(cJSON_GetObjectItem(stored, "friction"));
        assert_non_null(cJSON_GetObjectItem(cJSON_GetObjectItem(stored, "body"), "inertia"));
        assert_true(wp_fixture_read(stored, "params.fixture", &again, &error));
        assert_string_equal(first.id, again.id);
        assert_string_equal(first.canonical, again.canonical);
        /* Canonical: written with every object's keys in sorted order. */
        char *sorted = wp_canonical(stored, NULL);
        assert_string_equal(sorted, first.canonical);
        free(sorted);
        assert_same_fixture(first.fixture, again.fixture);
        for (int k = 0; k < first.fixture->fixel_count; k++)
            for (int j = 0; j < 2; j++)
                assert_false(signbit(first.fixture->fixels[k].normal[j]) &&
                             first.fixture->fixels[k].normal[j] == 0);
        wp_fixture_doc_release(&first);
        wp_fixture_doc_release(&again);
        cJSON_Delete(stored);
        cJSON_Delete(given);
    }
}

/* The fixture's units: part of the canonical text and the id only when
 * given, so a fixture written without them keeps the id it has always had
 * (the disc's, stored in tests/e2e/test_outline.py's OLD_IDS, computed
 * before units existed); each unit's size in SI is its definition, and
 * every bad spelling is refused at its field. */
static void fixture_units_are_in_the_id_only_when_given(void **state)
{
    (void)state;
    wp_error error;
    cJSON *disc = cJSON_Parse(DISC);
    wp_fixture_doc plain;
    assert_true(wp_fixture_read(disc, "params.fixture", &plain, &error));
    assert_string_equal(plain.id, "e0d7a1a0bd6e8bf16fe5845da1960ed9");
    assert_null(strstr(plain.canonical, "units"));
    assert_false(plain.fixture->units.given);
    assert_true(wr_fixture_force_factor(plain.fixture) == 1.0);

    static const struct {
        const char *length, *force;
        double factor; /* kg * length / s^2 per force unit */
    } systems[] = {
        {"mm", "N", 1000.0},          /* 1 N = 1 kg m/s^2 = 1000 kg mm/s^2 */
        {"m", "N", 1.0},
        {"m", "mN", 1e-3},
        {"in", "lbf", 4.4482216152605 / 0.0254}, /* 0.45359237 kg * 9.80665 m/s^2 per inch */
    };
    char ids[4][WP_ID_LENGTH + 1];
    for (size_t i = 0; i < 4; i++) {
        cJSON *units = cJSON_CreateObject();
        cJSON_AddStringToObject(units, "length", systems[i].length);
        cJSON_AddStringToObject(units, "force", systems[i].force);
        cJSON_DeleteItemFromObject(disc, "units");
        cJSON_AddItemToObject(disc, "units", units);
        wp_fixture_doc doc, again;
        assert_true(wp_fixture_read(disc, "params.fixture", &doc, &error));
        assert_true(doc.fixture->units.given);
        assert_true(fabs(wr_fixture_force_factor(doc.fixture) / systems[i].factor - 1) < 1e-15);
        assert_string_not_equal(doc.id, plain.id);
        strcpy(ids[i], doc.id);
        for (size_t j = 0; j < i; j++)
            assert_string_not_equal(ids[i], ids[j]);
        char expect[96];
        snprintf(expect, sizeof expect, "\"units\":{\"force\":\"%s\",\"length\":\"%s\"}",
                 systems[i].force, systems[i].length);
        assert_non_null(strstr(doc.canonical, expect));
        /* The stored text reads back to the same fixture, text and id. */
        cJSON *stored = cJSON_Parse(doc.canonical);
        assert_true(wp_fixture_read(stored, "params.fixture", &again, &error));
        assert_string_equal(doc.id, again.id);
        assert_string_equal(doc.canonical, again.canonical);
        assert_same_fixture(doc.fixture, again.fixture);
        assert_memory_equal(&doc.fixture->units, &again.fixture->units, sizeof doc.fixture->units);
        cJSON_Delete(stored);
        wp_fixture_doc_release(&doc);
        wp_fixture_doc_release(&again);
    }

    static const struct {
        const char *units, *field, *reason;
    } bad[] = {
        {"\"mm\"", "params.fixture.units", "object"},
        {"{\"length\":\"cm\",\"force\":\"N\"}", "params.fixture.units.length", "\"cm\""},
        {"{\"length\":\"mm\",\"force\":\"kN\"}", "params.fixture.units.force", "\"kN\""},
        {"{\"length\":\"mm\"}", "params.fixture.units.force", "required"},
        {"{\"force\":\"N\"}", "params.fixture.units.length", "required"},
        {"{\"length\":1,\"force\":\"N\"}", "params.fixture.units.length", "string"},
        {"{\"length\":\"mm\",\"force\":\"N\",\"mass\":\"kg\"}", "params.fixture.units.mass", ""},
    };
    for (size_t i = 0; i < sizeof bad / sizeof *bad; i++) {
        cJSON_DeleteItemFromObject(disc, "units");
        cJSON_AddItemToObject(disc, "units", cJSON_Parse(bad[i].units));
        wp_fixture_doc doc;
        assert_false(wp_fixture_read(disc, "params.fixture", &doc, &error));
        assert_int_equal(error.code, WP_INVALID_PARAMS);
        assert_string_equal(error.field, bad[i].field);
        assert_non_null(strstr(error.reason, bad[i].reason));
    }
    wp_fixture_doc_release(&plain);
    cJSON_Delete(disc);
}

/* ---- the envelope, against the real cache -------------------------------- */

typedef struct harness {
    wd_cache *cache;
    wd_stats stats;
    wd_thread_host *thread;
    wp_limits limits;
} harness;

static int setup(void **state)
{
    harness *h = calloc(1, sizeof *h);
    char why[128];
    h->cache = wd_cache_new(NULL, 1 << 20, 10000, why, sizeof why);
    h->thread = wd_thread_host_new(h->cache, &h->stats);
    h->limits = (wp_limits){16, 100, 8, 0, 0};
    *state = h;
    return h->cache && h->thread ? 0 : -1;
}

static int teardown(void **state)
{
    harness *h = *state;
    wd_thread_host_free(h->thread);
    wd_cache_free(h->cache);
    free(h);
    return 0;
}

/* The answer to `line`, parsed (the caller deletes it); NULL for none. */
static cJSON *ask(harness *h, const char *line)
{
    wp_counts counts = {0, 0};
    char *text = wp_answer_line(wd_thread_host_wp(h->thread), &h->limits, line, strlen(line),
                                &counts);
    if (!text)
        return NULL;
    assert_true(strlen(text) > 0 && text[strlen(text) - 1] == '\n');
    cJSON *json = cJSON_Parse(text);
    assert_non_null(json);
    free(text);
    return json;
}

static void expect_error(harness *h, const char *line, int code, const char *field)
{
    cJSON *answer = ask(h, line);
    assert_non_null(answer);
    cJSON *error = cJSON_GetObjectItem(answer, "error");
    if (!error)
        fail_msg("no error for %s", line);
    int got = cJSON_GetObjectItem(error, "code")->valueint;
    const char *got_field =
        cJSON_GetObjectItem(cJSON_GetObjectItem(error, "data"), "field")->valuestring;
    if (got != code || strcmp(got_field, field) != 0)
        fail_msg("%s: got %d at \"%s\", expected %d at \"%s\"", line, got, got_field, code, field);
    cJSON_Delete(answer);
}

static void envelope_errors_name_the_field(void **state)
{
    harness *h = *state;
    expect_error(h, "", WP_PARSE_ERROR, "");
    expect_error(h, "  \t ", WP_PARSE_ERROR, "");
    expect_error(h, "{\"jsonrpc\":", WP_PARSE_ERROR, "");
    expect_error(h, "{} {}", WP_PARSE_ERROR, "");
    expect_error(h, "[]", WP_INVALID_REQUEST, "");
    expect_error(h, "42", WP_INVALID_REQUEST, "");
    expect_error(h, "{\"jsonrpc\":\"1.0\",\"method\":\"fixture.list\",\"id\":1}",
                 WP_INVALID_REQUEST, "jsonrpc");
    expect_error(h, "{\"jsonrpc\":\"2.0\",\"method\":7,\"id\":1}", WP_INVALID_REQUEST, "method");
    expect_error(h, "{\"jsonrpc\":\"2.0\",\"method\":\"x\",\"id\":{}}", WP_INVALID_REQUEST, "id");
    expect_error(h, "{\"jsonrpc\":\"2.0\",\"method\":\"x\",\"id\":1,\"extra\":0}",
                 WP_INVALID_REQUEST, "extra");
    expect_error(h, "{\"jsonrpc\":\"2.0\",\"method\":\"nope\",\"id\":1}", WP_NO_METHOD, "method");
    expect_error(h, "{\"jsonrpc\":\"2.0\",\"method\":\"gravity.sweep\",\"id\":1}",
                 WP_INVALID_PARAMS, "params.fixture");
    expect_error(h, "{\"jsonrpc\":\"2.0\",\"method\":\"fixture.list\",\"params\":[],\"id\":1}",
                 WP_INVALID_PARAMS, "params");
    expect_error(h, "{\"jsonrpc\":\"2.0\",\"method\":\"fixture.list\",\"params\":{\"x\":1},\"id\":1}",
                 WP_INVALID_PARAMS, "params.x");
    expect_error(h, "{\"jsonrpc\":\"2.0\",\"method\":\"fixture.get\",\"id\":1}", WP_INVALID_PARAMS,
                 "params.id");
    expect_error(h, "{\"jsonrpc\":\"2.0\",\"method\":\"fixture.get\",\"params\":{\"id\":\"zz\"},\"id\":1}",
                 WP_INVALID_PARAMS, "params.id");
    expect_error(h,
                 "{\"jsonrpc\":\"2.0\",\"method\":\"fixture.get\",\"params\":{\"id\":"
                 "\"0123456789abcdef0123456789abcdef\"},\"id\":1}",
                 WP_NO_FIXTURE, "params.id");
    /* Nesting beyond the limit (16 here) is refused before parsing. */
    char deep[64] = "";
    for (int i = 0; i < 20; i++)
        strcat(deep, "[");
    expect_error(h, deep, WP_INVALID_REQUEST, "");
}

static void notifications_and_batches(void **state)
{
    harness *h = *state;
    /* A notification, even a failing one, gets nothing. */
    assert_null(ask(h, "{\"jsonrpc\":\"2.0\",\"method\":\"fixture.list\"}"));
    assert_null(ask(h, "{\"jsonrpc\":\"2.0\",\"method\":\"nope\"}"));
    assert_null(ask(h, "[{\"jsonrpc\":\"2.0\",\"method\":\"fixture.list\"}]"));
    /* An invalid request without an id is not a notification. */
    cJSON *answer = ask(h, "{\"method\":\"fixture.list\"}");
    assert_non_null(cJSON_GetObjectItem(answer, "error"));
    assert_true(cJSON_IsNull(cJSON_GetObjectItem(answer, "id")));
    cJSON_Delete(answer);
    /* A batch answers its requests with ids, in order. */
    answer = ask(h, "[{\"jsonrpc\":\"2.0\",\"method\":\"fixture.list\",\"id\":\"one\"},"
                    "{\"jsonrpc\":\"2.0\",\"method\":\"fixture.list\"},"
                    "1,"
                    "{\"jsonrpc\":\"2.0\",\"method\":\"server.status\",\"id\":3.5}]");
    assert_true(cJSON_IsArray(answer));
    assert_int_equal(cJSON_GetArraySize(answer), 3);
    assert_string_equal(cJSON_GetObjectItem(cJSON_GetArrayItem(answer, 0), "id")->valuestring,
                        "one");
    assert_true(cJSON_IsNull(cJSON_GetObjectItem(cJSON_GetArrayItem(answer, 1), "id")));
    assert_true(cJSON_GetObjectItem(cJSON_GetArrayItem(answer, 2), "id")->valuedouble == 3.5);
    cJSON_Delete(answer);
}

/* The raw answer to `line` (the caller frees it). */
static char *answer_text(harness *h, const char *line)
{
    wp_counts counts = {0, 0};
    char *text = wp_answer_line(wd_thread_host_wp(h->thread), &h->limits, line, strlen(line),
                                &counts);
    assert_non_null(text);
    return text;
}

/* JSON-RPC: the id comes back exactly as sent.  A double would turn
 * 9007199254740993 into ...992 and a 30-digit id into 1.2345678901234568e+29. */
static void numeric_ids_are_echoed_as_written(void **state)
{
    harness *h = *state;
    static const char *const ids[] = {"9007199254740993", "123456789012345678901234567890",
                                      "-0", "1.50", "1E+05", "0.5e-3", "-12", "0", "7"};
    for (size_t i = 0; i < sizeof ids / sizeof ids[0]; i++) {
        char line[256], tail[128];
        snprintf(line, sizeof line,
                 "{\"jsonrpc\":\"2.0\",\"method\":\"server.status\",\"params\":{\"x\":1},"
                 "\"id\" : %s }",
                 ids[i]);
        snprintf(tail, sizeof tail, ",\"id\":%s}\n", ids[i]);
        char *answer = answer_text(h, line);
        size_t length = strlen(answer), tail_length = strlen(tail);
        if (length < tail_length || strcmp(answer + length - tail_length, tail) != 0)
            fail_msg("id %s echoed as: %s", ids[i], answer);
        free(answer);
    }
    /* In a batch, each member's own id, wherever "id" stands among the
     * members, however spaced, and not a nested "id" of params; the name
     * may be escaped. */
    char *answer = answer_text(
        h, "[ {\"id\" :\t9007199254740993 ,\"jsonrpc\":\"2.0\",\"method\":\"fixture.get\","
           "\"params\":{\"id\":5}}, 5, {\"jsonrpc\":\"2.0\",\"method\":\"server.status\","
           "\"params\":{\"s\":\"]}\\\"{\"},\"id\":\"9007199254740993\"},"
           "{\"jsonrpc\":\"2.0\",\"method\":\"nope\",\"\\u0069d\":-1.0e+4}, "
           "{\"jsonrpc\":\"2.0\",\"method\":\"nope\",\"id\":100000000000000000000000000001} ]");
    const char *expected[] = {"\"id\":9007199254740993}", "\"id\":null}",
                              "\"id\":\"9007199254740993\"}", "\"id\":-1.0e+4}",
                              "\"id\":100000000000000000000000000001}]"};
    const char *at = answer;
    for (size_t i = 0; i < sizeof expected / sizeof expected[0]; i++) {
        const char *found = strstr(at, expected[i]);
        if (!found)
            fail_msg("answer %zu does not end with %s: %s", i, expected[i], answer);
        at = found + strlen(expected[i]);
    }
    free(answer);
}

/* RFC 8259 numbers: cJSON (strtod) reads "012", "1.", "-.5" and "1.e5";
 * JSON does not allow them, anywhere in the line. */
static void numbers_outside_the_rfc_are_parse_errors(void **state)
{
    harness *h = *state;
    static const struct {
        const char *number, *reason;
    } bad[] = {{"012", "the number 012 has a leading zero"},
               {"-012", "the number -012 has a leading zero"},
               {"00", "the number 00 has a leading zero"},
               {"-00.5", "the number -00.5 has a leading zero"},
               {"1.", "the number 1. has no digit after its decimal point"},
               {"1.e5", "the number 1.e5 has no digit after its decimal point"},
               {"-.5", "the number -.5 has no digit before its fraction"}};
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++)
        for (int where = 0; where < 2; where++) {
            char line[256];
            if (where == 0)
                snprintf(line, sizeof line,
                         "{\"jsonrpc\":\"2.0\",\"method\":\"fixture.list\",\"id\":%s}", bad[i].number);
            else
                snprintf(line, sizeof line,
                         "[{\"jsonrpc\":\"2.0\",\"method\":\"wrench.classify\",\"params\":"
                         "{\"wrenches\":[[1,%s,0]]},\"id\":1}]",
                         bad[i].number);
            cJSON *answer = ask(h, line);
            const cJSON *error = cJSON_GetObjectItem(answer, "error");
            const cJSON *reason = cJSON_GetObjectItem(cJSON_GetObjectItem(error, "data"), "reason");
            if (!cJSON_IsString(reason) || cJSON_GetObjectItem(error, "code")->valueint !=
                                               WP_PARSE_ERROR ||
                strstr(reason->valuestring, bad[i].reason) != reason->valuestring ||
                !cJSON_IsNull(cJSON_GetObjectItem(answer, "id")))
                fail_msg("%s: not refused as a parse error naming it", line);
            cJSON_Delete(answer);
        }
    /* The numbers JSON allows, and digits inside strings, pass. */
    static const char *const good[] = {"0", "-0", "0.5", "-0.5", "0e1", "0E-0", "10", "1e+05",
                                       "\"012\"", "\"1.\""};
    for (size_t i = 0; i < sizeof good / sizeof good[0]; i++) {
        char line[256];
        snprintf(line, sizeof line, "{\"jsonrpc\":\"2.0\",\"method\":\"fixture.list\",\"id\":%s}",
                 good[i]);
        cJSON *answer = ask(h, line);
        if (!cJSON_GetObjectItem(answer, "result"))
            fail_msg("%s: refused", line);
        cJSON_Delete(answer);
    }
    /* What cJSON refuses itself keeps its answer. */
    expect_error(h, "{\"jsonrpc\":\"2.0\",\"method\":\"fixture.list\",\"id\":1e}", WP_PARSE_ERROR,
                 "");
    char *answer = answer_text(h, "{\"jsonrpc\":\"2.0\",\"method\":\"fixture.list\",\"id\":0x10}");
    assert_non_null(strstr(answer, "the line is not valid JSON"));
    free(answer);
}

static void put_get_classify_delete(void **state)
{
    harness *h = *state;
    char line[2048];
    snprintf(line, sizeof line,
             "{\"jsonrpc\":\"2.0\",\"method\":\"fixture.put\",\"params\":{\"fixture\":%s},\"id\":1}",
             DISC);
    cJSON *answer = ask(h, line);
    cJSON *result = cJSON_GetObjectItem(answer, "result");
    assert_non_null(result);
    char id[WP_ID_LENGTH + 1];
    snprintf(id, sizeof id, "%s", cJSON_GetObjectItem(result, "id")->valuestring);
    assert_int_equal(cJSON_GetObjectItem(result, "goal_cones")->valueint, 4);
    assert_int_equal(cJSON_GetObjectItem(result, "strong_cones")->valueint, 9);
    cJSON_Delete(answer);
    /* The same content put again: the same id, and the new name wins. */
    snprintf(line, sizeof line,
             "{\"jsonrpc\":\"2.0\",\"method\":\"fixture.put\",\"params\":{\"fixture\":%s},\"id\":2}",
             DISC_AGAIN);
    answer = ask(h, line);
    result = cJSON_GetObjectItem(answer, "result");
    assert_string_equal(cJSON_GetObjectItem(result, "id")->valuestring, id);
    assert_string_equal(cJSON_GetObjectItem(result, "name")->valuestring, "b");
    cJSON_Delete(answer);
    /* Classify by id: docs/MODEL.md section 7's margin. */
    snprintf(line, sizeof line,
             "{\"jsonrpc\":\"2.0\",\"method\":\"wrench.classify\",\"params\":{\"fixture\":\"%s\","
             "\"wrenches\":[[-1,-1,0]],\"sets\":[\"goal\"]},\"id\":3}",
             id);
    answer = ask(h, line);
    cJSON *goal = cJSON_GetObjectItem(
        cJSON_GetArrayItem(cJSON_GetObjectItem(cJSON_GetObjectItem(answer, "result"), "results"), 0),
        "goal");
    assert_true(fabs(cJSON_GetObjectItem(goal, "margin")->valuedouble -
                     0.5 / sqrt(2 * 1.25)) < 1e-12);
    cJSON_Delete(answer);
    /* Too many wrenches: the limit's own code. */
    char *big = malloc(8192);
    int n = snprintf(big, 8192,
                     "{\"jsonrpc\":\"2.0\",\"method\":\"wrench.classify\",\"params\":{\"fixture\":"
                     "\"%s\",\"wrenches\":[",
                     id);
    for (int i = 0; i < 101; i++)
        n += snprintf(big + n, 8192 - (size_t)n, "%s[1,2,3]", i ? "," : "");
    snprintf(big + n, 8192 - (size_t)n, "]},\"id\":4}");
    expect_error(h, big, WP_LIMIT, "params.wrenches");
    free(big);
    /* Delete, then it is gone. */
    snprintf(line, sizeof line,
             "{\"jsonrpc\":\"2.0\",\"method\":\"fixture.delete\",\"params\":{\"id\":\"%s\"},\"id\":5}",
             id);
    answer = ask(h, line);
    assert_true(cJSON_IsTrue(cJSON_GetObjectItem(cJSON_GetObjectItem(answer, "result"), "deleted")));
    cJSON_Delete(answer);
    expect_error(h, line, WP_NO_FIXTURE, "params.id");
}

/* wp_answer_light says which lines are light work; either way the parsed
 * answer answers exactly what wp_answer_line would. */
static void light_lines_answer_as_any_other(void **state)
{
    harness *h = *state;
    const wp_host *host = wd_thread_host_wp(h->thread);
    char line[4096];
    snprintf(line, sizeof line,
             "{\"jsonrpc\":\"2.0\",\"method\":\"fixture.put\",\"params\":{\"fixture\":%s},\"id\":1}",
             DISC);
    cJSON *answer = ask(h, line);
    char id[WP_ID_LENGTH + 1];
    snprintf(id, sizeof id, "%s",
             cJSON_GetObjectItem(cJSON_GetObjectItem(answer, "result"), "id")->valuestring);
    cJSON_Delete(answer);
    struct {
        const char *format; /* %s: the id */
        bool light;
    } cases[] = {
        {"{\"jsonrpc\":\"2.0\",\"method\":\"wrench.classify\",\"params\":{\"fixture\":\"%s\","
         "\"wrenches\":[[-1,-1,0],[0,0,1]]},\"id\":2}", true},
        {"{\"jsonrpc\":\"2.0\",\"method\":\"wrench.classify\",\"params\":{\"fixture\":\"%s\","
         "\"wrenches\":[[-1,-1,0]],\"method\":\"lp\"},\"id\":3}", false},
        {"{\"jsonrpc\":\"2.0\",\"method\":\"wrench.classify\",\"params\":{\"fixture\":\"%s\","
         "\"wrenches\":[[1,1,1],[1,1,1],[1,1,1],[1,1,1],[1,1,1],[1,1,1],[1,1,1],[1,1,1],[1,1,1],"
         "[1,1,1],[1,1,1],[1,1,1],[1,1,1],[1,1,1],[1,1,1],[1,1,1],[1,1,1]]},\"id\":4}", true},
        /* The disc has 4 + 9 cones: 80 wrenches are 1040 cone checks, over the
         * WP_LIGHT_CONE_CHECKS of a light request (filled in below). */
        {NULL, false},
        {"{\"jsonrpc\":\"2.0\",\"method\":\"wrench.classify\",\"params\":{\"fixture\":"
         "\"00000000000000000000000000000000\",\"wrenches\":[[1,1,1]]},\"id\":5}%.0s", false},
        /* Flagged WP_READY: light on a ready stored fixture; not so
         * cone.get (a cone to derive) nor push.regions. */
        {"{\"jsonrpc\":\"2.0\",\"method\":\"modes.get\",\"params\":{\"fixture\":\"%s\"},\"id\":6}",
         true},
        {"{\"jsonrpc\":\"2.0\",\"method\":\"cone.get\",\"params\":{\"fixture\":\"%s\","
         "\"constraints\":\"ss\"},\"id\":11}", false},
        {"{\"jsonrpc\":\"2.0\",\"method\":\"push.regions\",\"params\":{\"fixture\":\"%s\"},\"id\":12}",
         false},
        {"{\"jsonrpc\":\"2.0\",\"method\":\"no.such\",\"id\":13}%.0s", true},
        {"[{\"jsonrpc\":\"2.0\",\"method\":\"server.status\",\"id\":7}]%.0s", false},
        {"{\"jsonrpc\":\"2.0\",\"method\":\"server.status\",\"id\":8}%.0s", true},
        {"{\"jsonrpc\":\"2.0\",\"method\":\"server.status\"}%.0s", true}, /* a notification */
        {"{not json%.0s", true},
        {"{\"jsonrpc\":\"1.0\",\"method\":3,\"id\":9}%.0s", true},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        if (cases[i].format) {
            snprintf(line, sizeof line, cases[i].format, id);
        } else {
            int n = snprintf(line, sizeof line,
                             "{\"jsonrpc\":\"2.0\",\"method\":\"wrench.classify\",\"params\":"
                             "{\"fixture\":\"%s\",\"wrenches\":[",
                             id);
            for (int w = 0; w < 80; w++)
                n += snprintf(line + n, sizeof line - (size_t)n, "%s[1,1,1]", w ? "," : "");
            snprintf(line + n, sizeof line - (size_t)n, "]},\"id\":10}");
        }
        wp_counts counts = {0, 0};
        char *light = NULL;
        wp_answer *answer = wp_answer_begin(&h->limits, host, line, strlen(line));
        assert_non_null(answer);
        bool answered = wp_answer_light(answer, host);
        if (answered != cases[i].light)
            fail_msg("case %zu: light %d, expected %d: %s", i, answered, cases[i].light, line);
        if (!answered) {
            /* Not light: made whole all the same (as a worker would), it is
             * the ordinary answer. */
            char *worked = wp_answer_whole(answer, host, &counts);
            wp_counts again = {0, 0};
            char *full = wp_answer_line(host, &h->limits, line, strlen(line), &again);
            assert_string_equal(worked, full);
            free(worked);
            free(full);
            continue;
        }
        light = wp_answer_whole(answer, host, &counts);
        assert_int_equal(counts.requests, 1);
        wp_counts again = {0, 0};
        char *full = wp_answer_line(host, &h->limits, line, strlen(line), &again);
        if (strstr(line, "server.status")) { /* the counts in it moved on */
            assert_true((light == NULL) == (full == NULL));
        } else if (!light || !full || strcmp(light, full) != 0) {
            fail_msg("case %zu: \"%s\" against \"%s\"", i, light ? light : "(none)",
                     full ? full : "(none)");
        }
        free(light);
        free(full);
    }
}

/* A stored fixture on supports, or with a tolerance, is never light work,
 * whatever the method asks (LPs disc by disc; boxes of the perturbation
 * set): each such line is left to a worker, and answers as any other. */
static void robust_and_plate_fixtures_are_not_light(void **state)
{
    harness *h = *state;
    const wp_host *host = wd_thread_host_wp(h->thread);
    static const char *const fixtures[] = {
        "{\"body\":{\"mass\":2,\"shape\":{\"type\":\"polygon\",\"vertices\":[[0,0],[4,0],"
        "[4,2],[0,2]]}},\"friction\":{\"static\":0.3},\"fixels\":[{\"at\":[1,0]},{\"at\":[3,0]},"
        "{\"at\":[0,1]}],\"supports\":{\"points\":[[1,0.5],[3,0.5],[2,1.7]],"
        "\"friction\":0.15,\"g\":9.81}}",
        "{\"body\":{\"mass\":2,\"shape\":{\"type\":\"polygon\",\"vertices\":[[0,0],[4,0],"
        "[4,2],[0,2]]}},\"friction\":{\"static\":0.3},\"fixels\":[{\"at\":[1,0]},{\"at\":[3,0]},"
        "{\"at\":[0,1]}],\"tolerance\":{\"position\":0.01}}",
    };
    static const char *const asks[] = {
        "{\"jsonrpc\":\"2.0\",\"method\":\"wrench.classify\",\"params\":{\"fixture\":\"%s\","
        "\"wrenches\":[[0,1,0]]},\"id\":2}",
        "{\"jsonrpc\":\"2.0\",\"method\":\"gravity.sweep\",\"params\":{\"fixture\":\"%s\"},"
        "\"id\":3}",
        "{\"jsonrpc\":\"2.0\",\"method\":\"modes.get\",\"params\":{\"fixture\":\"%s\"},"
        "\"id\":4}",
    };
    for (size_t f = 0; f < sizeof fixtures / sizeof *fixtures; f++) {
        char line[2048];
        snprintf(line, sizeof line,
                 "{\"jsonrpc\":\"2.0\",\"method\":\"fixture.put\",\"params\":{\"fixture\":%s},"
                 "\"id\":1}",
                 fixtures[f]);
        cJSON *put = ask(h, line);
        const cJSON *result = cJSON_GetObjectItem(put, "result");
        assert_non_null(result);
        char id[WP_ID_LENGTH + 1];
        snprintf(id, sizeof id, "%s", cJSON_GetObjectItem(result, "id")->valuestring);
        cJSON_Delete(put);
        for (size_t a = 0; a < sizeof asks / sizeof *asks; a++) {
            snprintf(line, sizeof line, asks[a], id);
            /* Once to derive its cones (a ready fixture is what the loop asks
             * about), then the line the loop would be given. */
            cJSON_Delete(ask(h, line));
            wp_answer *answer = wp_answer_begin(&h->limits, host, line, strlen(line));
            assert_non_null(answer);
            if (wp_answer_light(answer, host))
                fail_msg("fixture %zu: light: %s", f, line);
            wp_counts counts = {0, 0}, again = {0, 0};
            char *worked = wp_answer_whole(answer, host, &counts);
            char *full = wp_answer_line(host, &h->limits, line, strlen(line), &again);
            assert_non_null(worked);
            assert_string_equal(worked, full);
            free(worked);
            free(full);
        }
    }
}

/* ---- answers in pieces ---------------------------------------------------- */

/* The answer to `line` made a piece at a time, as the daemon makes it, the
 * pieces joined; *pieces counts them.  NULL for no answer. */
static char *answer_in_pieces(const wp_host *host, const wp_limits *limits, const char *line,
                              bool tiny, int *pieces, wp_counts *counts)
{
    wp_answer *answer = wp_answer_begin(limits, host, line, strlen(line));
    assert_non_null(answer);
    if (tiny)
        wp_answer_pieces(answer, 1, 1); /* cut wherever it may be cut */
    wp_buffer joined = {0};
    wp_step step;
    *pieces = 0;
    do {
        wp_buffer piece = {0};
        step = wp_answer_step(answer, host, &piece, counts);
        assert_int_not_equal(step, WP_STEP_FAILED);
        if (piece.length) {
            (*pieces)++;
            wp_buffer_append(&joined, piece.data, piece.length);
        }
        free(piece.data);
    } while (step == WP_STEP_MORE);
    wp_answer_free(answer, host);
    if (!joined.length)
        return NULL;
    return wp_buffer_take(&joined);
}

static char *classify_line(const char *id, int count, bool objects, const char *key)
{
    wp_buffer b = {0};
    wp_buffer_puts(&b, "{\"jsonrpc\":\"2.0\",\"method\":\"wrench.classify\",\"id\":7,\"params\":{\"fixture\":\"");
    wp_buffer_puts(&b, id);
    wp_buffer_puts(&b, "\",\"sets\":[\"goal\",\"strong\",\"both\"],\"");
    wp_buffer_puts(&b, key);
    wp_buffer_puts(&b, "\": [");
    for (int i = 0; i < count; i++) {
        /* Directions all round, magnitudes and torques varied: inside,
         * outside and boundary cases all occur. */
        double angle = 2 * 3.141592653589793 * i / 97.0, size = 0.5 + (i % 7) * 0.25;
        char text[160];
        if (objects)
            snprintf(text, sizeof text, "%s{\"force\":[%.17g,%.17g],\"at\":[%.17g, 0]}", i ? "," : "",
                     size * cos(angle), size * sin(angle), 0.1 * (i % 11) - 0.5);
        else
            snprintf(text, sizeof text, "%s[%.17g, %.17g ,%.17g]", i ? "," : "", size * cos(angle),
                     size * sin(angle), 0.05 * (i % 13) - 0.3);
        wp_buffer_puts(&b, text);
    }
    wp_buffer_puts(&b, "]}}");
    return wp_buffer_take(&b);
}

/* Made a piece at a time, an answer is byte for byte the whole one; a long
 * classify read straight from the text (its wrenches as numbers) answers
 * as the same line read through the tree; a batch's pieces fall between
 * its requests. */
static void pieces_join_to_the_whole_answer(void **state)
{
    harness *h = *state;
    const wp_host *host = wd_thread_host_wp(h->thread);
    wp_limits limits = {16, 100000, 16, 0, 0};
    char line[8192];
    snprintf(line, sizeof line,
             "{\"jsonrpc\":\"2.0\",\"method\":\"fixture.put\",\"params\":{\"fixture\":%s},\"id\":1}",
             DISC);
    cJSON *put = ask(h, line);
    char id[WP_ID_LENGTH + 1];
    snprintf(id, sizeof id, "%s", cJSON_GetObjectItem(cJSON_GetObjectItem(put, "result"), "id")->valuestring);
    cJSON_Delete(put);

    char *fast = classify_line(id, 6000, false, "wrenches");
    /* "wr\u0065nches" is "wrenches" to the tree, but not to the text
     * reader: the same request, read the ordinary way. */
    char *slow = classify_line(id, 6000, false, "wr\\u0065nches");
    char *objects = classify_line(id, 3000, true, "wrenches");
    snprintf(line, sizeof line,
             "[{\"jsonrpc\":\"2.0\",\"method\":\"modes.get\",\"params\":{\"fixture\":\"%s\"},\"id\":1},"
             "{\"jsonrpc\":\"2.0\",\"method\":\"server.status\"},"
             "{\"jsonrpc\":\"2.0\",\"method\":\"wrench.classify\",\"params\":{\"fixture\":\"%s\","
             "\"wrenches\":[[1,2,3],[-1,-1,0]],\"method\":\"lp\"},\"id\":2},"
             "{\"jsonrpc\":\"2.0\",\"method\":\"plan.get\",\"params\":{\"fixture\":\"%s\"},\"id\":3},"
             "7,{\"jsonrpc\":\"2.0\",\"method\":\"no.such\",\"id\":4},"
             /* work answered with nothing (a notification), then a stream:
              * the piece's budget is spent before the stream begins */
             "{\"jsonrpc\":\"2.0\",\"method\":\"push.regions\",\"params\":{\"fixture\":\"%s\"}},"
             /* regions written an edge at a time, with and without friction */
             "{\"jsonrpc\":\"2.0\",\"method\":\"push.regions\",\"params\":{\"fixture\":%s,"
             "\"set\":\"strong\",\"finger_friction\":0.1},\"id\":6},"
             "{\"jsonrpc\":\"2.0\",\"method\":\"push.regions\",\"params\":{\"fixture\":%s,"
             "\"set\":\"strong\"},\"id\":7},"
             "{\"jsonrpc\":\"2.0\",\"method\":\"wrench.classify\",\"params\":{\"fixture\":\"%s\","
             "\"wrenches\":[[1,2,3],[-1,-1,0]]},\"id\":5}]",
             id, id, id, id, PLATE, PLATE, id);
    const char *lines[] = {fast, slow, objects, line,
                           "[{\"jsonrpc\":\"2.0\",\"method\":\"server.status\"}]", "{\"x\":"};
    const int min_pieces[] = {2, 2, 2, 2, 0, 1};
    /* (the batch, line 3, is cut within its push.regions too: tiny pieces
     * end after every edge) */
    char *answers[6];
    for (int i = 0; i < 6; i++) {
        wp_counts whole_counts = {0, 0}, piece_counts = {0, 0}, tiny_counts = {0, 0};
        char *whole = wp_answer_line(host, &limits, lines[i], strlen(lines[i]), &whole_counts);
        int pieces, tiny_pieces;
        char *tiny = answer_in_pieces(host, &limits, lines[i], true, &tiny_pieces, &tiny_counts);
        answers[i] = answer_in_pieces(host, &limits, lines[i], false, &pieces, &piece_counts);
        if (whole)
            assert_string_equal(whole, tiny);
        assert_true(tiny_pieces >= pieces);
        assert_int_equal(whole_counts.errors, tiny_counts.errors);
        free(tiny);
        if (!whole || !answers[i]) {
            assert_null(whole);
            assert_null(answers[i]);
        } else {
            assert_string_equal(whole, answers[i]);
        }
        if (pieces < min_pieces[i])
            fail_msg("line %d: %d pieces, at least %d expected", i, pieces, min_pieces[i]);
        assert_int_equal(whole_counts.requests, piece_counts.requests);
        assert_int_equal(whole_counts.errors, piece_counts.errors);
        free(whole);
    }
    assert_string_equal(answers[0], answers[1]);
    /* A number JSON does not allow among a long line's wrenches is refused
     * as in any other line, though the wrenches are read from the text. */
    char *wrong = malloc(strlen(fast) + 16);
    const char *at = strstr(fast, "\"wrenches\": [") + strlen("\"wrenches\": [");
    sprintf(wrong, "%.*s[012,1,1],%s", (int)(at - fast), fast, at);
    wp_counts counts = {0, 0};
    char *refused = wp_answer_line(host, &limits, wrong, strlen(wrong), &counts);
    assert_non_null(strstr(refused, "\"code\":-32700"));
    assert_non_null(strstr(refused, "leading zero"));
    free(refused);
    free(wrong);
    cJSON *parsed = cJSON_Parse(answers[0]);
    assert_int_equal(cJSON_GetArraySize(cJSON_GetObjectItem(cJSON_GetObjectItem(parsed, "result"),
                                                            "results")), 6000);
    cJSON_Delete(parsed);
    for (int i = 0; i < 6; i++)
        free(answers[i]);
    free(fast);
    free(slow);
    free(objects);
}

/* The daemon's worker (wd_worker.c run_piece) asks wp_answer_parallel,
 * opens a fork when there is work to share, queues the helpers, and only
 * then runs the step; a helper may claim chunks before the step begins,
 * and may be inside wp_answer_work until the step returns (the fork is
 * closed after it).  So a step that follows a "yes" from
 * wp_answer_parallel must not end the answer (the rule in wp_chunks.h):
 * ending it frees the stream (its lock, its chunks, the fixture held)
 * under a helper -- even when the helpers had claimed every chunk left
 * by the time the step began.  Here the helpers' turns run, in this
 * thread, between the question and the step, as they may in the daemon. */
static void a_step_after_parallel_does_not_end_the_answer(void **state)
{
    harness *h = *state;
    const wp_host *host = wd_thread_host_wp(h->thread);
    wp_limits limits = {16, 100000, 16, 0, 0};
    char line[8192];
    snprintf(line, sizeof line,
             "{\"jsonrpc\":\"2.0\",\"method\":\"fixture.put\",\"params\":{\"fixture\":%s},\"id\":1}",
             DISC);
    cJSON *put = ask(h, line);
    char id[WP_ID_LENGTH + 1];
    snprintf(id, sizeof id, "%s", cJSON_GetObjectItem(cJSON_GetObjectItem(put, "result"), "id")->valuestring);
    cJSON_Delete(put);
    /* By rows (256 wrenches a chunk) and lean (1,024 a chunk with margins):
     * three chunks each. */
    char *rows = classify_line(id, 600, false, "wrenches");
    char *plain = classify_line(id, 2100, false, "wrenches");
    const char *params = strstr(plain, "\"params\":{") + strlen("\"params\":{");
    char *lean = malloc(strlen(plain) + 64);
    sprintf(lean, "%.*s\"fields\":[\"verdict\",\"margin\"],%s", (int)(params - plain), plain,
            params);
    const char *lines[] = {rows, lean};
    for (int l = 0; l < 2; l++) {
        wp_counts counts = {0, 0};
        char *whole = wp_answer_line(host, &limits, lines[l], strlen(lines[l]), &counts);
        wp_answer *answer = wp_answer_begin(&limits, host, lines[l], strlen(lines[l]));
        assert_non_null(answer);
        wp_answer_pieces(answer, 1, 1); /* a chunk a step */
        wp_buffer joined = {0};
        assert_int_equal(wp_answer_step(answer, host, &joined, &counts), WP_STEP_MORE);
        /* Chunks are left to share: a fork is opened, its helper queued. */
        assert_true(wp_answer_parallel(answer));
        /* The helper's turns come before the step's: it claims the rest. */
        size_t held = wp_answer_bytes(answer);
        int made = 0;
        while (wp_answer_work(answer, host))
            made++;
        assert_int_equal(made, 2);
        /* What they made waits for its turn, and counts as held (the
         * daemon's --max-output bound asks between pieces). */
        assert_true(wp_answer_bytes(answer) > held);
        /* The step the fork was opened for: the helper may still be in
         * wp_answer_work (its next turn) until it returns. */
        wp_step step = wp_answer_step(answer, host, &joined, &counts);
        if (step != WP_STEP_MORE)
            fail_msg("line %d: the step after wp_answer_parallel said yes returned %s: the "
                     "stream is freed while a helper may be in it",
                     l, step == WP_STEP_DONE ? "DONE" : "FAILED");
        /* No fork for the rest (wp_answer_parallel is not asked): it ends. */
        while (step == WP_STEP_MORE)
            step = wp_answer_step(answer, host, &joined, &counts);
        assert_int_equal(step, WP_STEP_DONE);
        wp_answer_free(answer, host);
        char *text = wp_buffer_take(&joined);
        assert_string_equal(text, whole);
        free(text);
        free(whole);
    }
    free(rows);
    free(plain);
    free(lean);

    /* The same for fixture.design, whose chunks of candidates helpers share
     * the same way (2,024 candidates: 64 chunks). */
    const char *design =
        "{\"jsonrpc\":\"2.0\",\"method\":\"fixture.design\",\"params\":{\"body\":{\"mass\":1,"
        "\"shape\":{\"type\":\"polygon\",\"vertices\":[[0,0],[4,0],[4,2],[0,2]]}},"
        "\"friction\":0.3,\"spacing\":0.5,\"top\":3},\"id\":7}";
    wp_counts counts = {0, 0};
    char *whole = wp_answer_line(host, &limits, design, strlen(design), &counts);
    wp_answer *answer = wp_answer_begin(&limits, host, design, strlen(design));
    assert_non_null(answer);
    wp_answer_pieces(answer, 1, 1);
    wp_buffer joined = {0};
    wp_step step = wp_answer_step(answer, host, &joined, &counts);
    int shared = 0;
    while (step == WP_STEP_MORE) {
        bool parallel = wp_answer_parallel(answer);
        while (parallel && wp_answer_work(answer, host))
            continue; /* the helpers claim every chunk before the step begins */
        /* A step with budget enough to finish what is left: it must not. */
        wp_answer_pieces(answer, parallel ? 1ul << 40 : 1, parallel ? (size_t)1 << 40 : 1);
        step = wp_answer_step(answer, host, &joined, &counts);
        if (parallel && step != WP_STEP_MORE)
            fail_msg("fixture.design: the step after wp_answer_parallel said yes returned %s",
                     step == WP_STEP_DONE ? "DONE" : "FAILED");
        shared += parallel;
    }
    assert_true(shared > 0);
    assert_int_equal(step, WP_STEP_DONE);
    wp_answer_free(answer, host);
    char *text = wp_buffer_take(&joined);
    assert_string_equal(text, whole);
    free(text);
    free(whole);
}

/* A long line's wrenches are read from the text (wp_json_triples), each
 * number "as cJSON reads a number": numbers of more than 63 characters
 * (valid JSON, such as 1 with a 67-digit exponent 0...01, or
 * 0.000...1e71, both of which Clinger's fast path would take) are left to
 * the tree, and the line must be answered as the tree reads it ("wr\u0065nches",
 * which the text reader does not match, makes the tree read the same
 * request).  A guard on read_number's hand-over to strtod and cJSON. */
static void long_numbers_read_as_the_tree_reads_them(void **state)
{
    harness *h = *state;
    const wp_host *host = wd_thread_host_wp(h->thread);
    wp_limits limits = {16, 100000, 16, 0, 0};
    char line[8192];
    snprintf(line, sizeof line,
             "{\"jsonrpc\":\"2.0\",\"method\":\"fixture.put\",\"params\":{\"fixture\":%s},\"id\":1}",
             DISC);
    cJSON *put = ask(h, line);
    char id[WP_ID_LENGTH + 1];
    snprintf(id, sizeof id, "%s", cJSON_GetObjectItem(cJSON_GetObjectItem(put, "result"), "id")->valuestring);
    cJSON_Delete(put);
    char exponent[128], fraction[128], long_ok[128];
    /* 1e000...01 (70 characters) and 0.000...01e71 (76): Clinger's fast
     * path takes both (1 digit, exponent 1 and 0). */
    snprintf(exponent, sizeof exponent, "1e%067d", 1);
    snprintf(fraction, sizeof fraction, "0.%070de71", 1);
    /* 63 characters: cJSON reads it whole. */
    snprintf(long_ok, sizeof long_ok, "1e%060d", 1);
    const char *numbers[] = {exponent, fraction, long_ok};
    for (int n = 0; n < 3; n++) {
        char *texts[2];
        for (int k = 0; k < 2; k++) {
            char *base = classify_line(id, 2000, false, k ? "wr\\u0065nches" : "wrenches");
            assert_true(strlen(base) >= 65536);
            const char *at = strstr(base, "\": [") + strlen("\": [");
            char *edited = malloc(strlen(base) + 256);
            sprintf(edited, "%.*s[%s,0,0],%s", (int)(at - base), base, numbers[n], at);
            wp_counts counts = {0, 0};
            texts[k] = wp_answer_line(host, &limits, edited, strlen(edited), &counts);
            free(edited);
            free(base);
        }
        if (strcmp(texts[0], texts[1]) != 0)
            fail_msg("%s (%zu characters): read from the text %.100s..., through the tree "
                     "%.100s...",
                     numbers[n], strlen(numbers[n]), texts[0], texts[1]);
        free(texts[0]);
        free(texts[1]);
    }
}

static int polls;
static bool stop_after_three(void *argument)
{
    (void)argument;
    return ++polls > 3;
}

/* A stop the host sets ends long work early: push.regions with a finger's
 * friction gives up within a few polls, and a classify ends its piece at
 * once (its next step would go on). */
static void a_stop_ends_long_work(void **state)
{
    harness *h = *state;
    wp_host host = *wd_thread_host_wp(h->thread);
    wr_stop stop = {stop_after_three, NULL};
    host.stop = &stop;
    char line[4096];
    snprintf(line, sizeof line,
             "{\"jsonrpc\":\"2.0\",\"method\":\"push.regions\",\"params\":{\"fixture\":%s,"
             "\"finger_friction\":0.2},\"id\":1}", DISC);
    polls = 0;
    wp_counts counts = {0, 0};
    char *text = wp_answer_line(&host, &h->limits, line, strlen(line), &counts);
    assert_non_null(strstr(text, "stopped"));
    assert_int_equal(polls, 4);
    free(text);
}

/* ---- the engine of chunked work (wp_chunks.h), alone -------------------- */

/* A method of the engine's tests: chunk i is the text "<i>"; `fail_at`
 * fails its make (WR_STOPPED), `slow_at` makes it take a while (a helper
 * still inside make while the step goes on). */
typedef struct toy {
    size_t fail_at, slow_at;
    atomic_int claimed; /* chunks a make has begun */
} toy;

typedef struct toy_record {
    char text[24];
} toy_record;

static wr_status toy_make(void *method, size_t index, void *record, wp_buffer *direct,
                          const wp_host *host, unsigned long *used, wp_error *error)
{
    (void)host;
    toy *t = method;
    atomic_fetch_add(&t->claimed, 1);
    if (index == t->slow_at) {
        struct timespec pause = {0, 100 * 1000 * 1000};
        nanosleep(&pause, NULL);
    }
    if (index == t->fail_at) {
        wp_error_set(error, WP_INTERNAL, "", "chunk %zu failed", index);
        return WR_STOPPED;
    }
    char text[24];
    snprintf(text, sizeof text, "<%zu>", index);
    if (direct)
        wp_buffer_puts(direct, text);
    else
        snprintf(((toy_record *)record)->text, sizeof text, "%s", text);
    *used += 1;
    return WR_OK;
}

static wr_status toy_merge(void *method, size_t index, void *record, wp_buffer *out,
                           wp_error *error)
{
    (void)method;
    (void)index;
    (void)error;
    wp_buffer_puts(out, ((toy_record *)record)->text);
    return WR_OK;
}

static const wp_chunk_ops TOY = {.record_size = sizeof(toy_record), .make = toy_make,
                                 .merge = toy_merge, .window = 4};

typedef struct toy_helper {
    wp_chunks *chunks;
    const wp_host *host;
    int turns;
} toy_helper;

/* A helper of the daemon's pool: its turns of wp_chunks_work. */
static void *toy_helper_main(void *argument)
{
    toy_helper *helper = argument;
    for (int i = 0; i < helper->turns; i++)
        wp_chunks_work(helper->chunks, helper->host);
    return NULL;
}

/* The rule: a step that begins after wp_chunks_parallel said yes does not
 * end the answer, though every chunk is merged by the time it returns: a
 * helper claimed the last chunk before the step began and is still inside
 * make while it runs (the classify case, a step that asked for chunks left
 * at its start, and the design case, a step that asked again, both ended
 * the answer here, freeing what the helper was using). */
static void a_shared_step_never_ends_the_answer(void **state)
{
    (void)state;
    wp_host host = {0};
    toy t = {.fail_at = SIZE_MAX, .slow_at = 0};
    wp_chunks *chunks = wp_chunks_new(&TOY, &t, 1);
    assert_non_null(chunks);
    assert_true(wp_chunks_parallel(chunks));
    toy_helper helper = {chunks, &host, 1};
    pthread_t thread;
    assert_int_equal(pthread_create(&thread, NULL, toy_helper_main, &helper), 0);
    while (atomic_load(&t.claimed) == 0) /* the helper holds the only chunk */
        sched_yield();
    wp_buffer out = {0};
    wp_error error = {0};
    unsigned long used = 0;
    bool shared = wp_chunks_shared(chunks);
    assert_true(shared);
    assert_int_equal(wp_chunks_run(chunks, shared, &host, &out, 100, &used, 1 << 20, &error),
                     WP_STEP_MORE);
    assert_true(wp_chunks_done(chunks));
    pthread_join(thread, NULL);
    /* The next step shares nothing (nothing was left to share): it ends it. */
    assert_false(wp_chunks_parallel(chunks));
    shared = wp_chunks_shared(chunks);
    assert_false(shared);
    assert_int_equal(wp_chunks_run(chunks, shared, &host, &out, 100, &used, 1 << 20, &error),
                     WP_STEP_DONE);
    assert_string_equal(out.data, "<0>");
    free(out.data);
    wp_chunks_free(chunks);
}

/* Chunks made out of order, by helpers and the step, are merged in order;
 * no more than the window are made ahead of the one next merged. */
static void chunks_merge_in_order_within_the_window(void **state)
{
    (void)state;
    wp_host host = {0};
    toy t = {.fail_at = SIZE_MAX, .slow_at = 0};
    wp_chunks *chunks = wp_chunks_new(&TOY, &t, 9);
    assert_true(wp_chunks_parallel(chunks));
    toy_helper slow = {chunks, &host, 1}, fast = {chunks, &host, 8};
    pthread_t first, second;
    assert_int_equal(pthread_create(&first, NULL, toy_helper_main, &slow), 0);
    while (atomic_load(&t.claimed) == 0) /* chunk 0 is the slow helper's */
        sched_yield();
    assert_int_equal(pthread_create(&second, NULL, toy_helper_main, &fast), 0);
    pthread_join(second, NULL);
    /* Chunk 0 is not merged: the window (4) stopped the fast helper. */
    assert_true(atomic_load(&t.claimed) <= 4);
    wp_buffer out = {0};
    wp_error error = {0};
    unsigned long used = 0;
    bool shared = wp_chunks_shared(chunks);
    while (wp_chunks_run(chunks, shared, &host, &out, 1000, &used, 1 << 20, &error) !=
           WP_STEP_DONE)
        shared = wp_chunks_shared(chunks);
    pthread_join(first, NULL);
    assert_string_equal(out.data, "<0><1><2><3><4><5><6><7><8>");
    free(out.data);
    wp_chunks_free(chunks);
}

/* A helper's failure is kept: the chunks before it are merged, a step that
 * shares goes on, and the next step that shares nothing says it. */
static void a_failure_is_said_by_a_step_that_shares_nothing(void **state)
{
    (void)state;
    wp_host host = {0};
    toy t = {.fail_at = 1, .slow_at = SIZE_MAX};
    wp_chunks *chunks = wp_chunks_new(&TOY, &t, 3);
    assert_true(wp_chunks_parallel(chunks));
    assert_true(wp_chunks_work(chunks, &host));  /* chunk 0 */
    assert_true(wp_chunks_work(chunks, &host));  /* chunk 1: fails */
    assert_false(wp_chunks_work(chunks, &host)); /* nothing more is claimed */
    assert_false(wp_chunks_parallel(chunks));
    wp_buffer out = {0};
    wp_error error = {0};
    unsigned long used = 0;
    bool shared = wp_chunks_shared(chunks);
    assert_true(shared);
    assert_int_equal(wp_chunks_run(chunks, shared, &host, &out, 100, &used, 1 << 20, &error),
                     WP_STEP_MORE);
    shared = wp_chunks_shared(chunks);
    assert_false(shared);
    assert_int_equal(wp_chunks_run(chunks, shared, &host, &out, 100, &used, 1 << 20, &error),
                     WP_STEP_FAILED);
    assert_string_equal(error.reason, "chunk 1 failed");
    assert_string_equal(out.data, "<0>");
    free(out.data);
    wp_chunks_free(chunks);
}

/* wp_json_valid against the envelope's own reading (the scan, then
 * cJSON's parse, which alone takes "01"): the same yes or no on texts
 * valid and broken each way (structure, strings, escapes, numbers,
 * literals), so a member cut from a line is refused as the parse would. */
static void cut_members_checked_as_the_parse_checks(void **state)
{
    (void)state;
    static const char *const TEXTS[] = {
        "[]", "{}", " [1, 2.5e-3, -0, true, false, null] ", "{\"a\":{\"b\":[\"x\\u00e9\\n\"]}}",
        "[{\"loads\":[{\"gravity\":{\"g\":9.81,\"direction_deg\":270}}]}]",
        "[{\"loads\":[{\"gravity\":{\"g\":9.81,\"fixture\"\"direction_deg\":270}}]}]",
        "[1,]", "[,1]", "{\"a\" 1}", "{\"a\":}", "{1:2}", "[01]", "[1.]", "[.5]", "[1e]",
        "[-]", "[tru]", "[nul]", "[truex]", "[\"a\\x\"]", "[\"\\u12g4\"]", "[\"open]", "[1] [2]",
        "[[[]]", "{\"a\":1,}", "[\"tab\there\"]", "",
    };
    for (size_t i = 0; i < sizeof TEXTS / sizeof *TEXTS; i++) {
        size_t n = strlen(TEXTS[i]);
        wp_json_shape shape = wp_json_scan(TEXTS[i], n, 64);
        cJSON *tree = cJSON_ParseWithOpts(TEXTS[i], NULL, true);
        bool parsed = tree != NULL && !shape.control && !shape.nul_escape && !shape.bad_escape &&
                      !shape.number_problem;
        cJSON_Delete(tree);
        if (wp_json_valid(TEXTS[i], n) != parsed)
            fail_msg("%s: wp_json_valid says %d, cJSON %d", TEXTS[i], !parsed, parsed);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(sha256_matches_nist_vectors),
        cmocka_unit_test(numbers_round_trip_shortest),
        cmocka_unit_test(the_writer_keeps_commas_and_nesting),
        cmocka_unit_test(fixture_id_ignores_order_spelling_and_name),
        cmocka_unit_test(explicit_form_reads_back_to_the_same_fixture),
        cmocka_unit_test(fixture_units_are_in_the_id_only_when_given),
        cmocka_unit_test_setup_teardown(envelope_errors_name_the_field, setup, teardown),
        cmocka_unit_test_setup_teardown(notifications_and_batches, setup, teardown),
        cmocka_unit_test_setup_teardown(numeric_ids_are_echoed_as_written, setup, teardown),
        cmocka_unit_test_setup_teardown(numbers_outside_the_rfc_are_parse_errors, setup, teardown),
        cmocka_unit_test_setup_teardown(put_get_classify_delete, setup, teardown),
        cmocka_unit_test_setup_teardown(light_lines_answer_as_any_other, setup, teardown),
        cmocka_unit_test_setup_teardown(robust_and_plate_fixtures_are_not_light, setup, teardown),
        cmocka_unit_test_setup_teardown(pieces_join_to_the_whole_answer, setup, teardown),
        cmocka_unit_test_setup_teardown(a_stop_ends_long_work, setup, teardown),
        cmocka_unit_test(a_shared_step_never_ends_the_answer),
        cmocka_unit_test(chunks_merge_in_order_within_the_window),
        cmocka_unit_test(a_failure_is_said_by_a_step_that_shares_nothing),
        cmocka_unit_test(cut_members_checked_as_the_parse_checks),
        cmocka_unit_test_setup_teardown(a_step_after_parallel_does_not_end_the_answer, setup,
                                        teardown),
        cmocka_unit_test_setup_teardown(long_numbers_read_as_the_tree_reads_them, setup,
                                        teardown),
    };
    return cmocka_run_group_tests_name("proto", tests, NULL, NULL);
}
