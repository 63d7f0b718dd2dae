/* test_cache.c -- the fixture cache (daemon/wd_cache.c) on its own: LRU
 * order and eviction of derived data under a small bound, serial numbers,
 * inline against stored fixtures, --max-fixtures, the state directory
 * (files, a round trip, its lock) and the durability order of a put.
 *
 * The durability order is watched by defining fsync and rename here: the
 * test program's definitions take the place of the C library's for the
 * daemon's code linked into it (they pass on to the kernel), record what
 * was done to which path, and fail on demand. */
#define _GNU_SOURCE /* syscall */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include "wd_cache.h"
#include "wd_log.h"
#include "wp_fixture.h"

#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/syscall.h>
#include <unistd.h>

/* ---- fsync and rename, watched ------------------------------------------- */

#define MAX_EVENTS 64

static struct {
    char events[MAX_EVENTS][2 * PATH_MAX + 64]; /* "fsync PATH", "rename FROM TO" */
    int count;
    char renamed_text[4096];                /* what the file held when renamed */
    int fail_fsync, fail_rename;            /* fail the next call (with EIO) */
} watch;

static void record(const char *format, ...) __attribute__((format(printf, 1, 2)));
static void record(const char *format, ...)
{
    if (watch.count == MAX_EVENTS)
        return;
    va_list args;
    va_start(args, format);
    vsnprintf(watch.events[watch.count++], sizeof watch.events[0], format, args);
    va_end(args);
}

int fsync(int fd)
{
    char link[64], path[PATH_MAX] = "";
    snprintf(link, sizeof link, "/proc/self/fd/%d", fd);
    ssize_t n = readlink(link, path, sizeof path - 1);
    path[n > 0 ? n : 0] = 0;
    record("fsync %s", path);
    if (watch.fail_fsync) {
        watch.fail_fsync = 0;
        errno = EIO;
        return -1;
    }
    return (int)syscall(SYS_fsync, fd);
}

int rename(const char *from, const char *to)
{
    record("rename %s %s", from, to);
    FILE *file = fopen(from, "rb");
    size_t n = file ? fread(watch.renamed_text, 1, sizeof watch.renamed_text - 1, file) : 0;
    watch.renamed_text[n] = 0;
    if (file)
        fclose(file);
    if (watch.fail_rename) {
        watch.fail_rename = 0;
        errno = EIO;
        return -1;
    }
    return renameat(AT_FDCWD, from, AT_FDCWD, to);
}

/* ---- fixtures and the cache ------------------------------------------------ */

/* Small fixtures, all different (and so with different ids): a plate of
 * mass 1 + i/8 held by three fixels. */
static char *fixture_text(int i)
{
    static char text[512];
    snprintf(text, sizeof text,
             "{\"name\": \"f%d\", \"body\": {\"mass\": %g, \"shape\": {\"type\": \"polygon\", "
             "\"vertices\": [[0, 0], [4, 0], [4, 2], [0, 2]]}}, "
             "\"friction\": {\"static\": 0.3}, "
             "\"fixels\": [{\"at\": [1, 0]}, {\"at\": [3, 0]}, {\"at\": [0, 1]}]}",
             i, 1 + i / 8.0);
    return text;
}

/* The cache's functions, their failure (the cache's own status and words)
 * made a JSON-RPC error as proto makes it (wp_error_host). */
static bool cache_adopt(wd_cache *cache, wp_fixture_doc *doc, bool store, wp_fixture_use *use,
                        wp_error *error)
{
    wp_host_failure failure = {WP_HOST_OK, ""};
    if (wd_cache_adopt(cache, doc, store, use, &failure))
        return true;
    wp_error_host(error, &failure, "");
    return false;
}

static bool cache_use(wd_cache *cache, const char *id, wp_fixture_use *use, wp_error *error)
{
    wp_host_failure failure = {WP_HOST_OK, ""};
    if (wd_cache_use(cache, id, use, &failure))
        return true;
    wp_error_host(error, &failure, "");
    return false;
}

static bool cache_delete(wd_cache *cache, const char *id, wp_error *error)
{
    wp_host_failure failure = {WP_HOST_OK, ""};
    if (wd_cache_delete(cache, id, &failure))
        return true;
    wp_error_host(error, &failure, "");
    return false;
}

/* wd_cache_adopt of fixture i; the result, with *use and *error. */
static bool adopt(wd_cache *cache, int i, bool store, wp_fixture_use *use, wp_error *error)
{
    cJSON *json = cJSON_Parse(fixture_text(i));
    assert_non_null(json);
    wp_fixture_doc doc;
    assert_true(wp_fixture_read(json, "", &doc, error));
    cJSON_Delete(json);
    return cache_adopt(cache, &doc, store, use, error);
}

/* The id of fixture i. */
static void id_of(int i, char id[WP_ID_LENGTH + 1])
{
    cJSON *json = cJSON_Parse(fixture_text(i));
    wp_fixture_doc doc;
    wp_error error = {0};
    assert_true(wp_fixture_read(json, "", &doc, &error));
    memcpy(id, doc.id, WP_ID_LENGTH + 1);
    wp_fixture_doc_release(&doc);
    cJSON_Delete(json);
}

/* Put fixture i (stored) and let it go. */
static void put(wd_cache *cache, int i)
{
    wp_fixture_use use;
    wp_error error = {0};
    if (!adopt(cache, i, true, &use, &error))
        fail_msg("put of fixture %d: %s", i, error.reason);
    wd_cache_release(cache, &use);
}

/* Use the stored fixture i and let it go. */
static void touch(wd_cache *cache, int i)
{
    char id[WP_ID_LENGTH + 1];
    id_of(i, id);
    wp_fixture_use use;
    wp_error error = {0};
    assert_true(cache_use(cache, id, &use, &error));
    wd_cache_release(cache, &use);
}

/* Has fixture i (stored) its derived data in memory? */
static bool derived(wd_cache *cache, int i)
{
    char id[WP_ID_LENGTH + 1];
    id_of(i, id);
    return wd_cache_ready(cache, id) >= 0;
}

static size_t listed(wd_cache *cache)
{
    wp_fixture_listing listing;
    assert_true(wd_cache_list(cache, &listing));
    size_t n = listing.count;
    wp_fixture_listing_release(&listing);
    return n;
}

static wd_cache_stats stats_of(wd_cache *cache)
{
    wd_cache_stats stats;
    wd_cache_stats_get(cache, &stats);
    return stats;
}

/* The bytes of derived data of one of these fixtures (all alike). */
static size_t one_analysis(void)
{
    char why[256];
    wd_cache *cache = wd_cache_new(NULL, SIZE_MAX, 100, why, sizeof why);
    assert_non_null(cache);
    put(cache, 0);
    size_t bytes = stats_of(cache).derived_bytes;
    for (int i = 1; i < 6; i++) {
        put(cache, i);
        assert_int_equal(stats_of(cache).derived_bytes, (size_t)(i + 1) * bytes);
    }
    wd_cache_free(cache);
    assert_true(bytes > 0);
    return bytes;
}

/* A fresh state directory, removed by remove_state. */
static char *make_state(void)
{
    char *dir = strdup("/tmp/test_cache.XXXXXX");
    assert_non_null(mkdtemp(dir));
    return dir;
}

static void remove_state(char *dir)
{
    char command[128];
    snprintf(command, sizeof command, "rm -rf '%s'", dir);
    assert_int_equal(system(command), 0);
    free(dir);
}

static bool exists(const char *format, const char *dir, const char *id)
{
    char path[PATH_MAX];
    snprintf(path, sizeof path, format, dir, id);
    struct stat st;
    return stat(path, &st) == 0;
}

/* ---- the tests ----------------------------------------------------------------- */

/* Derived data goes least recently used first, beyond the bound; an entry
 * in use is never evicted (the cache stays over its bound instead, until
 * it is released); stored fixtures stay stored and are derived again. */
static void lru_evicts_oldest_unused(void **state)
{
    (void)state;
    size_t one = one_analysis();
    char why[256];
    wd_cache *cache = wd_cache_new(NULL, 2 * one + one / 2, 100, why, sizeof why);
    assert_non_null(cache);
    put(cache, 0);
    put(cache, 1);
    assert_true(derived(cache, 0) && derived(cache, 1));
    put(cache, 2); /* three over a bound of two and a half: 0 goes */
    assert_false(derived(cache, 0));
    assert_true(derived(cache, 1) && derived(cache, 2));
    touch(cache, 1); /* now 2 is the oldest */
    put(cache, 3);
    assert_false(derived(cache, 2));
    assert_true(derived(cache, 1) && derived(cache, 3));
    wd_cache_stats stats = stats_of(cache);
    assert_int_equal(stats.stored, 4);
    assert_int_equal(stats.cached, 2);
    assert_int_equal(stats.derived_bytes, 2 * one);
    assert_int_equal(listed(cache), 4); /* stored fixtures are never evicted */

    /* In use: held, not evicted, though the cache goes over its bound. */
    char ids[3][WP_ID_LENGTH + 1];
    wp_fixture_use uses[3];
    wp_error error = {0};
    int held[3] = {1, 0, 2};
    for (int k = 0; k < 3; k++) {
        id_of(held[k], ids[k]);
        assert_true(cache_use(cache, ids[k], &uses[k], &error));
        assert_non_null(uses[k].analysis);
    }
    /* 3 was the only one not in use: it went; the three held stay. */
    assert_false(derived(cache, 3));
    stats = stats_of(cache);
    assert_int_equal(stats.derived_bytes, 3 * one);
    assert_true(stats.derived_bytes > stats.derived_limit);
    for (int k = 0; k < 3; k++)
        assert_true(derived(cache, held[k]));
    /* Released, the oldest goes: 1, used first. */
    wd_cache_release(cache, &uses[0]);
    assert_false(derived(cache, 1));
    assert_true(derived(cache, 0) && derived(cache, 2));
    wd_cache_release(cache, &uses[1]);
    wd_cache_release(cache, &uses[2]);
    stats = stats_of(cache);
    assert_int_equal(stats.derived_bytes, 2 * one);
    assert_int_equal(stats.cached, 2);
    assert_int_equal(listed(cache), 4);
    wd_cache_free(cache);
}

/* A large fixture: eight fixels on the plate's edges. */
static const char *const LARGE =
    "{\"name\": \"large\", \"body\": {\"mass\": 2, \"shape\": {\"type\": \"polygon\", "
    "\"vertices\": [[0, 0], [4, 0], [4, 2], [0, 2]]}}, \"friction\": {\"static\": 0.3}, "
    "\"fixels\": [{\"at\": [0.5, 0]}, {\"at\": [1.5, 0]}, {\"at\": [2.5, 0]}, {\"at\": [3.5, 0]}, "
    "{\"at\": [4, 0.5]}, {\"at\": [4, 1.5]}, {\"at\": [0, 1.5]}, {\"at\": [0, 0.5]}]}";

static bool adopt_large(wd_cache *cache, wp_fixture_use *use)
{
    cJSON *json = cJSON_Parse(LARGE);
    wp_fixture_doc doc;
    wp_error error = {0};
    assert_true(wp_fixture_read(json, "", &doc, &error));
    cJSON_Delete(json);
    return cache_adopt(cache, &doc, false, use, &error);
}

/* One eviction may take several entries: a large analysis derived pushes
 * out as many small ones as it takes. */
static void eviction_takes_what_it_needs(void **state)
{
    (void)state;
    size_t one = one_analysis();
    char why[256];
    wd_cache *cache = wd_cache_new(NULL, SIZE_MAX, 100, why, sizeof why);
    assert_non_null(cache);
    wp_fixture_use use;
    assert_true(adopt_large(cache, &use));
    wd_cache_release(cache, &use);
    size_t large = stats_of(cache).derived_bytes; /* its own memory included */
    wd_cache_free(cache);
    assert_true(large > one + one / 2);

    cache = wd_cache_new(NULL, 2 * one + one / 2, 100, why, sizeof why);
    assert_non_null(cache);
    put(cache, 0);
    put(cache, 1);
    assert_true(derived(cache, 0) && derived(cache, 1));
    assert_true(adopt_large(cache, &use)); /* both small ones must go */
    assert_false(derived(cache, 0));
    assert_false(derived(cache, 1));
    assert_int_equal(stats_of(cache).derived_bytes, large);
    wd_cache_release(cache, &use);
    wd_cache_free(cache);
}

/* The serial names the derived data: the same while it is held, another
 * once it has been evicted and derived again. */
static void serial_changes_on_rebuild(void **state)
{
    (void)state;
    char why[256], id[WP_ID_LENGTH + 1];
    wd_cache *cache = wd_cache_new(NULL, 0, 100, why, sizeof why); /* evict on release */
    assert_non_null(cache);
    put(cache, 0);
    assert_false(derived(cache, 0));
    id_of(0, id);
    wp_fixture_use first, second, again;
    wp_error error = {0};
    assert_true(cache_use(cache, id, &first, &error));
    assert_true(cache_use(cache, id, &second, &error));
    assert_true(wd_cache_serial(&first) == wd_cache_serial(&second));
    uint64_t serial = wd_cache_serial(&first);
    wd_cache_release(cache, &first);
    assert_true(derived(cache, 0)); /* still held by `second` */
    wd_cache_release(cache, &second);
    assert_false(derived(cache, 0));
    assert_true(cache_use(cache, id, &again, &error));
    assert_true(wd_cache_serial(&again) != serial);
    wd_cache_release(cache, &again);
    wd_cache_free(cache);
}

/* A fixture only cached (inline in a query) is not listed nor usable by
 * id; it goes with its derived data.  Putting it stores it. */
static void inline_is_not_stored(void **state)
{
    (void)state;
    char why[256], id[WP_ID_LENGTH + 1];
    id_of(0, id);
    wd_cache *cache = wd_cache_new(NULL, 0, 100, why, sizeof why);
    assert_non_null(cache);
    wp_fixture_use use, by_id;
    wp_error error = {0};
    assert_true(adopt(cache, 0, false, &use, &error));
    assert_string_equal(use.id, id);
    assert_string_equal(use.name, "f0");
    assert_non_null(use.analysis);
    assert_int_equal(listed(cache), 0);
    assert_int_equal(wd_cache_ready(cache, id), -1); /* only stored ones are asked */
    assert_false(cache_use(cache, id, &by_id, &error));
    assert_int_equal(error.code, WP_NO_FIXTURE);
    wd_cache_stats stats = stats_of(cache);
    assert_int_equal(stats.stored, 0);
    assert_int_equal(stats.cached, 1);
    wd_cache_release(cache, &use);
    stats = stats_of(cache);
    assert_int_equal(stats.cached, 0); /* gone with its derived data */
    assert_int_equal(stats.derived_bytes, 0);

    put(cache, 0);
    assert_int_equal(listed(cache), 1);
    assert_true(cache_use(cache, id, &by_id, &error));
    wd_cache_release(cache, &by_id);
    wd_cache_free(cache);
}

/* The key of a text as written (wp_fixture_written_key). */
static void written_key_of(const char *text, char key[WP_ID_LENGTH + 1])
{
    cJSON *json = cJSON_Parse(text);
    assert_non_null(json);
    assert_true(wp_fixture_written_key(json, key));
    cJSON_Delete(json);
}

/* An inline fixture is kept under the key of its text as written: asked
 * again in any spelling of the same values it is found without being read,
 * the same entry and the same derived data; other values, or the same ones
 * once their derived data is evicted, are not found. */
static void inline_found_by_written_text(void **state)
{
    (void)state;
    char why[256], key[WP_ID_LENGTH + 1], respelled[WP_ID_LENGTH + 1], other[WP_ID_LENGTH + 1];
    written_key_of(fixture_text(0), key);
    written_key_of("{\"fixels\": [{\"at\": [1.0, 0]}, {\"at\": [3, 0e0]}, {\"at\": [0, 1]}], "
                   "\"friction\": {\"static\": 0.30}, \"name\": \"f0\", \"body\": {\"shape\": "
                   "{\"vertices\": [[0, 0], [4, 0], [4, 2], [0, 2]], \"type\": \"polygon\"}, "
                   "\"mass\": 1}}",
                   respelled);
    written_key_of(fixture_text(1), other);
    assert_string_equal(key, respelled);
    assert_string_not_equal(key, other);

    wd_cache *cache = wd_cache_new(NULL, SIZE_MAX, 100, why, sizeof why);
    assert_non_null(cache);
    wp_fixture_use use, again;
    wp_error error = {0};
    assert_false(wd_cache_use_written(cache, key, &again)); /* nothing kept yet */
    cJSON *json = cJSON_Parse(fixture_text(0));
    wp_fixture_doc doc;
    assert_true(wp_fixture_read(json, "", &doc, &error));
    cJSON_Delete(json);
    memcpy(doc.written, key, sizeof doc.written);
    assert_true(cache_adopt(cache, &doc, false, &use, &error));
    const wr_analysis *analysis = use.analysis;
    char id[WP_ID_LENGTH + 1];
    memcpy(id, use.id, sizeof id);
    wd_cache_release(cache, &use);
    assert_true(wd_cache_use_written(cache, respelled, &again));
    assert_string_equal(again.id, id);
    assert_ptr_equal(again.analysis, analysis);
    assert_string_equal(again.name, "f0");
    wd_cache_release(cache, &again);
    assert_false(wd_cache_use_written(cache, other, &again));
    assert_int_equal(listed(cache), 0); /* kept, not stored */
    wd_cache_free(cache);

    /* No room for derived data: the inline entry goes when let go, and
     * its key with it. */
    cache = wd_cache_new(NULL, 0, 100, why, sizeof why);
    assert_non_null(cache);
    json = cJSON_Parse(fixture_text(0));
    assert_true(wp_fixture_read(json, "", &doc, &error));
    cJSON_Delete(json);
    memcpy(doc.written, key, sizeof doc.written);
    assert_true(cache_adopt(cache, &doc, false, &use, &error));
    wd_cache_release(cache, &use);
    assert_int_equal(stats_of(cache).cached, 0);
    assert_false(wd_cache_use_written(cache, key, &again));
    wd_cache_free(cache);
}

/* Adopt the fixture of `text` inline, as the envelope does with a line's
 * params.fixture (its text given to keep), and hold it. */
static void adopt_inline(wd_cache *cache, const char *text, size_t length, wp_fixture_use *use)
{
    wp_error error = {0};
    cJSON *json = cJSON_Parse(text);
    assert_non_null(json);
    wp_fixture_doc doc;
    assert_true(wp_fixture_read(json, "", &doc, &error));
    cJSON_Delete(json);
    doc.text = text;
    doc.text_length = length;
    assert_true(cache_adopt(cache, &doc, false, use, &error));
}

/* An inline fixture's text of WP_INLINE_TEXT_MIN bytes on is kept with the
 * entry it made: a text that begins with it (the rest of a line) finds it,
 * with the kept length; a text differing in one byte anywhere, one cut
 * short, or one that only contains it further on does not; a text shorter
 * than the minimum is not kept; and the text goes with its entry. */
static void inline_found_by_its_text(void **state)
{
    (void)state;
    /* The fixture's text padded with white space to a long text, as a
     * long outline makes it: the same object. */
    size_t pad = WP_INLINE_TEXT_MIN;
    const char *base = fixture_text(0);
    size_t n = strlen(base) + pad;
    char *kept = malloc(n + 64);
    memcpy(kept, "{ ", 2);
    memset(kept + 2, ' ', pad - 2);
    memcpy(kept + pad, base + 1, strlen(base) - 1);
    kept[n - 1] = 0;
    size_t kept_length = strlen(kept);
    char *line = malloc(kept_length + 64);
    snprintf(line, kept_length + 64, "%s,\"wrenches\":[[0,1,0]]}}", kept);

    char why[256];
    wd_cache *cache = wd_cache_new(NULL, SIZE_MAX, 100, why, sizeof why);
    assert_non_null(cache);
    wp_fixture_use use, again;
    assert_int_equal(wd_cache_use_text(cache, line, strlen(line), &again), 0);
    adopt_inline(cache, kept, kept_length, &use);
    const wr_analysis *analysis = use.analysis;
    wd_cache_release(cache, &use);

    assert_int_equal(wd_cache_use_text(cache, line, strlen(line), &again), kept_length);
    assert_ptr_equal(again.analysis, analysis);
    wd_cache_release(cache, &again);
    assert_int_equal(wd_cache_use_text(cache, kept, kept_length, &again), kept_length);
    wd_cache_release(cache, &again);
    assert_int_equal(wd_cache_use_text(cache, kept, kept_length - 1, &again), 0);
    size_t places[] = {0, 1, 100, kept_length / 2, kept_length - 70, kept_length - 2};
    for (size_t i = 0; i < sizeof places / sizeof *places; i++) {
        line[places[i]] ^= 1;
        assert_int_equal(wd_cache_use_text(cache, line, strlen(line), &again), 0);
        line[places[i]] ^= 1;
    }
    char *further = malloc(strlen(line) + 2);
    snprintf(further, strlen(line) + 2, " %s", line);
    assert_int_equal(wd_cache_use_text(cache, further, strlen(further), &again), 0);
    free(further);
    wd_cache_free(cache);

    /* A stored fixture asked inline keeps the text too, charged to its
     * derived data: the bytes grow by the text's length. */
    cache = wd_cache_new(NULL, SIZE_MAX, 100, why, sizeof why);
    assert_non_null(cache);
    put(cache, 0);
    size_t before = stats_of(cache).derived_bytes;
    assert_true(before > 0);
    adopt_inline(cache, kept, kept_length, &use);
    wd_cache_release(cache, &use);
    assert_int_equal(stats_of(cache).derived_bytes, before + kept_length);
    assert_int_equal(wd_cache_use_text(cache, line, strlen(line), &again), kept_length);
    assert_int_equal(listed(cache), 1);
    wd_cache_release(cache, &again);
    wd_cache_free(cache);

    /* A bound that holds the stored fixture's derived data but not the text
     * too: the text's charge puts it over, the derived data (and the text
     * with it) go once let go, and the stored fixture stays. */
    cache = wd_cache_new(NULL, before + kept_length / 2, 100, why, sizeof why);
    assert_non_null(cache);
    put(cache, 0);
    assert_int_equal(stats_of(cache).derived_bytes, before);
    adopt_inline(cache, kept, kept_length, &use);
    assert_int_equal(stats_of(cache).derived_bytes, before + kept_length); /* held: stays */
    wd_cache_release(cache, &use);
    assert_int_equal(wd_cache_use_text(cache, line, strlen(line), &again), 0);
    assert_int_equal(stats_of(cache).derived_bytes, 0);
    assert_int_equal(listed(cache), 1);
    wd_cache_free(cache);

    /* Short texts are not kept; a kept one goes with its entry. */
    cache = wd_cache_new(NULL, 0, 100, why, sizeof why);
    assert_non_null(cache);
    adopt_inline(cache, base, strlen(base), &use);
    assert_int_equal(wd_cache_use_text(cache, base, strlen(base), &again), 0);
    wd_cache_release(cache, &use);
    adopt_inline(cache, kept, kept_length, &use);
    assert_int_equal(wd_cache_use_text(cache, line, strlen(line), &again), kept_length);
    wd_cache_release(cache, &again);
    wd_cache_release(cache, &use); /* no room: the entry goes, and its text */
    assert_int_equal(stats_of(cache).cached, 0);
    assert_int_equal(wd_cache_use_text(cache, line, strlen(line), &again), 0);
    wd_cache_free(cache);
    free(line);
    free(kept);
}

/* --max-fixtures: a new stored fixture beyond it is refused; storing one
 * already stored, or using a fixture inline, is not. */
static void max_fixtures_refuses(void **state)
{
    (void)state;
    char why[256], id[WP_ID_LENGTH + 1];
    wd_cache *cache = wd_cache_new(NULL, SIZE_MAX, 2, why, sizeof why);
    assert_non_null(cache);
    put(cache, 0);
    put(cache, 1);
    wp_fixture_use use;
    wp_error error = {0};
    assert_false(adopt(cache, 2, true, &use, &error));
    assert_int_equal(error.code, WP_LIMIT);
    assert_string_equal(error.field, "params.fixture");
    assert_string_equal(error.reason,
                        "2 fixtures are stored, the most --max-fixtures allows; delete one first");
    assert_int_equal(listed(cache), 2);
    put(cache, 1); /* already stored */
    assert_true(adopt(cache, 2, false, &use, &error));
    wd_cache_release(cache, &use);
    id_of(0, id);
    assert_true(cache_delete(cache, id, &error));
    put(cache, 2);
    assert_int_equal(listed(cache), 2);
    wd_cache_free(cache);
}

/* With a state directory: a put writes DIR/fixtures/<id>.json (the
 * canonical text and a newline), a delete removes it. */
static void delete_removes_the_file(void **state)
{
    (void)state;
    char *dir = make_state(), why[256], id[WP_ID_LENGTH + 1];
    wd_cache *cache = wd_cache_new(dir, SIZE_MAX, 100, why, sizeof why);
    assert_non_null(cache);
    wp_fixture_use use;
    wp_error error = {0};
    assert_true(adopt(cache, 0, true, &use, &error));
    memcpy(id, use.id, sizeof id);
    char path[PATH_MAX], text[4096] = "";
    snprintf(path, sizeof path, "%s/fixtures/%s.json", dir, id);
    FILE *file = fopen(path, "rb");
    assert_non_null(file);
    text[fread(text, 1, sizeof text - 1, file)] = 0;
    fclose(file);
    char expected[4096];
    snprintf(expected, sizeof expected, "%s\n", use.canonical);
    assert_string_equal(text, expected);
    wd_cache_release(cache, &use);

    assert_true(cache_delete(cache, id, &error));
    assert_false(exists("%s/fixtures/%s.json", dir, id));
    assert_int_equal(listed(cache), 0);
    assert_false(cache_use(cache, id, &use, &error));
    assert_int_equal(error.code, WP_NO_FIXTURE);
    assert_false(cache_delete(cache, id, &error));
    assert_int_equal(error.code, WP_NO_FIXTURE);
    wd_cache_free(cache);
    remove_state(dir);
}

/* Put N, free the cache; a new cache on the same directory has the same N
 * (ids, names), stored and not yet derived. */
static void state_directory_round_trip(void **state)
{
    (void)state;
    enum { N = 5 };
    char *dir = make_state(), why[256];
    wd_cache *cache = wd_cache_new(dir, SIZE_MAX, 100, why, sizeof why);
    assert_non_null(cache);
    for (int i = 0; i < N; i++)
        put(cache, i);
    wp_fixture_listing before, after;
    assert_true(wd_cache_list(cache, &before));
    wd_cache_free(cache);

    cache = wd_cache_new(dir, SIZE_MAX, 100, why, sizeof why);
    assert_non_null(cache);
    assert_true(wd_cache_list(cache, &after));
    assert_int_equal(after.count, N);
    assert_int_equal(before.count, after.count);
    for (size_t i = 0; i < after.count; i++) {
        assert_string_equal(before.entries[i].id, after.entries[i].id);
        assert_string_equal(before.entries[i].name, after.entries[i].name);
        assert_int_equal(before.entries[i].fixels, after.entries[i].fixels);
    }
    wd_cache_stats stats = stats_of(cache);
    assert_int_equal(stats.stored, N);
    assert_int_equal(stats.cached, 0);
    for (int i = 0; i < N; i++) {
        assert_false(derived(cache, i));
        touch(cache, i);
        assert_true(derived(cache, i));
    }
    wp_fixture_listing_release(&before);
    wp_fixture_listing_release(&after);
    wd_cache_free(cache);
    remove_state(dir);
}

/* A put is answered only once its file is durable: written to a temporary
 * file, that synced, renamed to its name, the directory synced -- in that
 * order.  A step that fails leaves no file and answers WP_STORAGE. */
static void put_is_durable_in_order(void **state)
{
    (void)state;
    char *dir = make_state(), why[256], id[WP_ID_LENGTH + 1];
    char real_dir[PATH_MAX];
    assert_non_null(realpath(dir, real_dir));
    wd_cache *cache = wd_cache_new(dir, SIZE_MAX, 100, why, sizeof why);
    assert_non_null(cache);
    id_of(0, id);
    memset(&watch, 0, sizeof watch);
    wp_fixture_use use;
    wp_error error = {0};
    assert_true(adopt(cache, 0, true, &use, &error));
    char expected[3][2 * PATH_MAX + 64];
    snprintf(expected[0], sizeof expected[0], "fsync %s/fixtures/.%s.tmp", real_dir, id);
    snprintf(expected[1], sizeof expected[1], "rename %s/fixtures/.%s.tmp %s/fixtures/%s.json",
             dir, id, dir, id);
    snprintf(expected[2], sizeof expected[2], "fsync %s/fixtures", real_dir);
    assert_int_equal(watch.count, 3);
    for (int k = 0; k < 3; k++)
        assert_string_equal(watch.events[k], expected[k]);
    char text[4096];
    snprintf(text, sizeof text, "%s\n", use.canonical);
    assert_string_equal(watch.renamed_text, text); /* whole before the rename */
    wd_cache_release(cache, &use);
    assert_true(cache_delete(cache, id, &error));

    /* The file's sync fails: nothing stored, no file left. */
    memset(&watch, 0, sizeof watch);
    watch.fail_fsync = 1;
    assert_false(adopt(cache, 0, true, &use, &error));
    assert_int_equal(error.code, WP_STORAGE);
    snprintf(text, sizeof text,
             "could not sync %s/fixtures/%s.json: Input/output error; the fixture is not stored",
             dir, id);
    assert_string_equal(error.reason, text);
    assert_int_equal(watch.count, 1); /* never renamed */
    assert_false(exists("%s/fixtures/%s.json", dir, id));
    assert_false(exists("%s/fixtures/.%s.tmp", dir, id));
    assert_int_equal(listed(cache), 0);

    /* The rename fails: the same. */
    memset(&watch, 0, sizeof watch);
    watch.fail_rename = 1;
    assert_false(adopt(cache, 0, true, &use, &error));
    assert_int_equal(error.code, WP_STORAGE);
    assert_non_null(strstr(error.reason, "could not rename"));
    assert_false(exists("%s/fixtures/%s.json", dir, id));
    assert_false(exists("%s/fixtures/.%s.tmp", dir, id));
    assert_int_equal(listed(cache), 0);
    assert_int_equal(stats_of(cache).stored, 0);

    /* And then it works. */
    put(cache, 0);
    assert_true(exists("%s/fixtures/%s.json", dir, id));
    wd_cache_free(cache);
    remove_state(dir);
}

/* One cache at a time on a state directory: the second is refused, with
 * the holder's pid, also once DIR/lock is deleted. */
static void state_directory_is_locked(void **state)
{
    (void)state;
    char *dir = make_state(), why[512] = "";
    wd_cache *first = wd_cache_new(dir, SIZE_MAX, 100, why, sizeof why);
    assert_non_null(first);
    assert_null(wd_cache_new(dir, SIZE_MAX, 100, why, sizeof why));
    char expected[512];
    snprintf(expected, sizeof expected,
             "the state directory %s is in use by another wrenchd (pid %ld, which holds a lock on "
             "the directory)",
             dir, (long)getpid());
    assert_string_equal(why, expected);
    /* The lock is the directory's: deleting DIR/lock (or replacing it)
     * frees nothing. */
    char lock_path[PATH_MAX + 16];
    snprintf(lock_path, sizeof lock_path, "%s/lock", dir);
    assert_int_equal(unlink(lock_path), 0);
    assert_null(wd_cache_new(dir, SIZE_MAX, 100, why, sizeof why));
    assert_non_null(strstr(why, "is in use by another wrenchd (pid unknown"));
    wd_cache_free(first);
    wd_cache *second = wd_cache_new(dir, SIZE_MAX, 100, why, sizeof why);
    assert_non_null(second); /* released with the first */
    wd_cache_free(second);
    remove_state(dir);
}

/* --load FILE: stored as a put would store it; a file that is not a
 * fixture is refused. */
static void load_file_puts(void **state)
{
    (void)state;
    char *dir = make_state(), why[256], id[WP_ID_LENGTH + 1], path[PATH_MAX + 64];
    id_of(3, id);
    snprintf(path, sizeof path, "%s/f3.json", dir);
    FILE *file = fopen(path, "w");
    assert_non_null(file);
    fputs(fixture_text(3), file);
    fclose(file);
    wd_cache *cache = wd_cache_new(NULL, SIZE_MAX, 100, why, sizeof why);
    assert_non_null(cache);
    assert_true(wd_cache_load_file(cache, path, 1 << 20));
    assert_int_equal(listed(cache), 1);
    assert_true(derived(cache, 3));
    snprintf(path, sizeof path, "%s/nowhere.json", dir);
    assert_false(wd_cache_load_file(cache, path, 1 << 20));
    assert_int_equal(listed(cache), 1);
    wd_cache_free(cache);
    remove_state(dir);
}

int main(void)
{
    wd_log_set_level(-1); /* the failures provoked here are logged as errors */
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(lru_evicts_oldest_unused),
        cmocka_unit_test(eviction_takes_what_it_needs),
        cmocka_unit_test(serial_changes_on_rebuild),
        cmocka_unit_test(inline_is_not_stored),
        cmocka_unit_test(inline_found_by_written_text),
        cmocka_unit_test(inline_found_by_its_text),
        cmocka_unit_test(max_fixtures_refuses),
        cmocka_unit_test(delete_removes_the_file),
        cmocka_unit_test(state_directory_round_trip),
        cmocka_unit_test(put_is_durable_in_order),
        cmocka_unit_test(state_directory_is_locked),
        cmocka_unit_test(load_file_puts),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
