/* wd_cache.c -- the fixture cache and its state directory.
 *
 * Locks: `lock` guards the map and every entry's mutable fields, and is held
 * only briefly, never during computation or disk I/O.  `store_lock`
 * serialises changes to what is stored (a put that stores, a delete), from
 * the decision through the disk write to the map update, so the directory
 * and the map never disagree about an id.
 *
 * Durability: a stored fixture is written to a temporary file, synced,
 * renamed over DIR/fixtures/<id>.json, and the directory is synced, before
 * the put is acknowledged; a delete unlinks and syncs the directory.
 *
 * The state directory: one daemon at a time holds a lock on it (flock of
 * the directory itself, for the daemon's life; DIR/lock holds its pid).  Invariant: every stored fixture
 * has exactly one file, DIR/fixtures/<id>.json with <id> its id, and no
 * other file there is loaded -- so a delete, which unlinks that file,
 * leaves nothing to come back at the next start.  Files named by an older
 * id rule are re-keyed at load (wd_cache_new); a file whose name matches
 * neither rule is refused and left where it is, for its owner to look at.
 *
 * Memory: stored fixtures are at most `max_stored`; a fixture that is only
 * cached (inline in a query) is charged to the derived-data bound with its
 * own texts and outline, so evicting it frees what it was charged. */
#define _DEFAULT_SOURCE /* flock */
#include "wd_cache.h"
#include "wd_file.h"
#include "wd_log.h"

#include <assert.h>
#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <pthread.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/file.h>
#include <unistd.h>

/* A file of the state directory longer than this is not loaded. */
#define STORED_FILE_LIMIT ((size_t)256 << 20)

/* Name and canonical text, shared by an entry and the requests reading them:
 * a put that renames a fixture replaces them without pulling them from under
 * a reader.  Reference counts change under the cache lock. */
typedef struct texts {
    int refs;
    char *name;
    char *canonical;
} texts;

typedef struct entry {
    char id[WP_ID_LENGTH + 1];
    texts *texts;
    wr_fixture *fixture;      /* immutable */
    wr_analysis *analysis;    /* derived; NULL until built or once evicted */
    size_t analysis_bytes;    /* charged to derived_bytes: the analysis, and for a
                                 cached-only entry its own memory too (entry_bytes) */
    uint64_t serial;          /* names the current analysis */
    uint64_t last_used;       /* LRU clock */
    int refs;                 /* requests holding it */
    bool stored;              /* put (listed, on disk) rather than only cached */
    struct entry *next;       /* hash chain */
    /* The key of the inline text it was last adopted from
     * (wp_fixture_written_key), "" none; with it the entry is also in
     * the written map, chained by next_written. */
    char written[WP_ID_LENGTH + 1];
    struct entry *next_written;
    /* An inline text it was adopted from, as written (wp_host.h,
     * fixture_use_text), or NULL; with it the entry is also in the text
     * map under text_hash (head_hash), chained by next_text.  Kept only
     * with the analysis and charged with it (analysis_bytes): it goes when
     * the analysis is evicted. */
    char *text;
    size_t text_length;
    uint64_t text_hash;
    struct entry *next_text;
} entry;

struct wd_cache {
    pthread_mutex_t lock;
    pthread_mutex_t store_lock;
    entry **buckets;
    entry **written_buckets;  /* the same count: entries by their written key */
    entry **text_buckets;     /* the same count: entries by their text's head */
    size_t bucket_count;      /* a power of two */
    size_t count;
    size_t stored_count;      /* entries with `stored`; changes under store_lock */
    size_t max_stored;        /* --max-fixtures */
    size_t derived_bytes, derived_limit;
    uint64_t clock, serial;
    char *dir;                /* DIR/fixtures, or NULL for memory only */
    int lock_fd;              /* DIR, locked while the cache lives; -1 without DIR */
};

/* ---- texts and entries --------------------------------------------------- */

static texts *texts_from(wp_fixture_doc *doc)
{
    texts *t = malloc(sizeof *t);
    if (!t)
        return NULL;
    t->refs = 1;
    t->name = doc->name;
    t->canonical = doc->canonical;
    doc->name = doc->canonical = NULL;
    return t;
}

static void texts_drop(texts *t)
{
    assert(!t || t->refs > 0);
    if (t && --t->refs == 0) {
        free(t->name);
        free(t->canonical);
        free(t);
    }
}

static void entry_free(entry *e)
{
    free(e->text);
    texts_drop(e->texts);
    wr_analysis_free(e->analysis);
    wr_fixture_free(e->fixture);
    free(e);
}

/* What an entry holds besides its analysis, freed with it. */
static size_t entry_bytes(const entry *e)
{
    return sizeof *e + sizeof *e->texts + strlen(e->texts->name) + 1 +
           strlen(e->texts->canonical) + 1 + sizeof *e->fixture +
           e->fixture->vertex_count * sizeof *e->fixture->vertices;
}

static size_t bucket_of(const wd_cache *c, const char *id)
{
    /* Ids are hex digests: their first 16 digits are already uniform. */
    char head[17];
    memcpy(head, id, 16);
    head[16] = 0;
    return (size_t)strtoull(head, NULL, 16) & (c->bucket_count - 1);
}

static entry *find(const wd_cache *c, const char *id)
{
    for (entry *e = c->buckets[bucket_of(c, id)]; e; e = e->next)
        if (strcmp(e->id, id) == 0)
            return e;
    return NULL;
}

static entry *find_written(const wd_cache *c, const char *key)
{
    for (entry *e = c->written_buckets[bucket_of(c, key)]; e; e = e->next_written)
        if (strcmp(e->written, key) == 0)
            return e;
    return NULL;
}

static void unlink_written(wd_cache *c, entry *e)
{
    if (!e->written[0])
        return;
    for (entry **p = &c->written_buckets[bucket_of(c, e->written)]; *p; p = &(*p)->next_written)
        if (*p == e) {
            *p = e->next_written;
            break;
        }
    e->written[0] = 0;
    e->next_written = NULL;
}

/* The text map's hash: of a text's first TEXT_HEAD bytes (FNV-1a), which
 * every kept text has.  Texts that share their head (a fixel moved at the
 * end of the same outline) share a chain, and are told apart by their last
 * TEXT_TAIL bytes before the whole is compared. */
#define TEXT_HEAD 256
#define TEXT_TAIL 64
_Static_assert(WP_INLINE_TEXT_MIN >= TEXT_HEAD && TEXT_HEAD >= TEXT_TAIL,
               "a kept text has a head and a tail");

static uint64_t head_hash(const char *text)
{
    uint64_t h = 14695981039346656037ULL;
    for (size_t i = 0; i < TEXT_HEAD; i++)
        h = (h ^ (unsigned char)text[i]) * 1099511628211ULL;
    return h;
}

/* The entry whose text begins text[0, length): at most one, since each
 * kept text is a whole JSON object (its end is where its brackets close)
 * and one text validates to one fixture. */
static entry *find_text(const wd_cache *c, const char *text, size_t length)
{
    if (length < WP_INLINE_TEXT_MIN)
        return NULL;
    uint64_t h = head_hash(text);
    for (entry *e = c->text_buckets[h & (c->bucket_count - 1)]; e; e = e->next_text) {
        size_t n = e->text_length;
        if (e->text_hash == h && n <= length &&
            memcmp(e->text + n - TEXT_TAIL, text + n - TEXT_TAIL, TEXT_TAIL) == 0 &&
            memcmp(e->text, text, n) == 0)
            return e;
    }
    return NULL;
}

static void link_text(wd_cache *c, entry *e)
{
    size_t b = e->text_hash & (c->bucket_count - 1);
    e->next_text = c->text_buckets[b];
    c->text_buckets[b] = e;
}

static void unlink_text(wd_cache *c, entry *e)
{
    if (!e->text)
        return;
    for (entry **p = &c->text_buckets[e->text_hash & (c->bucket_count - 1)]; *p;
         p = &(*p)->next_text)
        if (*p == e) {
            *p = e->next_text;
            break;
        }
    e->next_text = NULL;
}

static void drop_text(wd_cache *c, entry *e)
{
    unlink_text(c, e);
    free(e->text);
    e->text = NULL;
    e->text_length = 0;
}

/* Keep e under the written key too (one per entry: the latest). */
static void set_written(wd_cache *c, entry *e, const char *key)
{
    if (!key[0] || strcmp(e->written, key) == 0)
        return;
    unlink_written(c, e);
    entry *other = find_written(c, key);
    if (other) /* one text validates to one fixture: never, but for a hash collision */
        unlink_written(c, other);
    memcpy(e->written, key, sizeof e->written);
    size_t b = bucket_of(c, key);
    e->next_written = c->written_buckets[b];
    c->written_buckets[b] = e;
}

static bool insert(wd_cache *c, entry *e)
{
    if (c->count + 1 > 2 * c->bucket_count) {
        size_t n = 2 * c->bucket_count;
        entry **grown = calloc(n, sizeof *grown);
        entry **grown_written = calloc(n, sizeof *grown_written);
        entry **grown_text = calloc(n, sizeof *grown_text);
        if (!grown || !grown_written || !grown_text) {
            free(grown);
            free(grown_written);
            free(grown_text);
            return false;
        }
        entry **old = c->buckets, **old_written = c->written_buckets;
        entry **old_text = c->text_buckets;
        size_t old_count = c->bucket_count;
        c->buckets = grown;
        c->written_buckets = grown_written;
        c->text_buckets = grown_text;
        c->bucket_count = n;
        for (size_t i = 0; i < old_count; i++) {
            for (entry *x = old[i], *next; x; x = next) {
                next = x->next;
                size_t b = bucket_of(c, x->id);
                x->next = c->buckets[b];
                c->buckets[b] = x;
            }
            for (entry *x = old_written[i], *next; x; x = next) {
                next = x->next_written;
                size_t b = bucket_of(c, x->written);
                x->next_written = c->written_buckets[b];
                c->written_buckets[b] = x;
            }
            for (entry *x = old_text[i], *next; x; x = next) {
                next = x->next_text;
                link_text(c, x);
            }
        }
        free(old);
        free(old_written);
        free(old_text);
    }
    size_t b = bucket_of(c, e->id);
    e->next = c->buckets[b];
    c->buckets[b] = e;
    c->count++;
    return true;
}

static void unlink_entry(wd_cache *c, entry *e)
{
    unlink_written(c, e);
    unlink_text(c, e);
    for (entry **p = &c->buckets[bucket_of(c, e->id)]; *p; p = &(*p)->next)
        if (*p == e) {
            assert(c->count > 0);
            *p = e->next;
            c->count--;
            return;
        }
    assert(!"an entry to unlink is in its bucket");
}

/* The invariants of the map, checked entry by entry (under the lock, where
 * the caller walks every entry anyway -- never on a request's fast path):
 * the hash and the count agree, each entry is in the bucket of its id and
 * found by it; reference counts are never negative; the derived bytes are
 * the sum of what the entries are charged, and an entry without derived
 * data is charged nothing; the stored count is the entries stored; the LRU
 * clock is ahead of every entry; and beyond the bound, every entry with
 * derived data is in use (eviction took everything it could). */
static void check_locked(const wd_cache *c)
{
#ifdef NDEBUG
    (void)c;
#else
    size_t count = 0, stored = 0, derived = 0;
    bool all_derived_in_use = true;
    for (size_t b = 0; b < c->bucket_count; b++)
        for (const entry *e = c->buckets[b]; e; e = e->next) {
            count++;
            stored += e->stored;
            derived += e->analysis_bytes;
            assert(bucket_of(c, e->id) == b && find(c, e->id) == e);
            assert(!e->written[0] || find_written(c, e->written) == e);
            assert(!e->text || find_text(c, e->text, e->text_length) == e);
            /* kept with what it is charged to, or about to be derived */
            assert(!e->text || e->analysis || e->refs > 0);
            assert(e->refs >= 0 && e->texts && e->texts->refs > 0);
            assert(e->analysis || e->analysis_bytes == 0);
            assert(e->last_used <= c->clock && e->serial <= c->serial);
            if (e->analysis && e->refs == 0)
                all_derived_in_use = false;
        }
    assert(count == c->count);
    assert(stored == c->stored_count);
    assert(derived == c->derived_bytes);
    assert(c->derived_bytes <= c->derived_limit || all_derived_in_use);
#endif
}

static void drop_analysis(wd_cache *c, entry *e)
{
    assert(e->refs == 0); /* an entry in use is never evicted */
    assert(c->derived_bytes >= e->analysis_bytes);
    drop_text(c, e);
    wr_analysis_free(e->analysis);
    e->analysis = NULL;
    c->derived_bytes -= e->analysis_bytes;
    e->analysis_bytes = 0;
}

/* Evict derived data, least recently used first, until within the bound.
 * Entries in use are skipped; a cached-only entry goes with its data. */
static void evict_locked(wd_cache *c)
{
    bool walked = false;
    while (c->derived_bytes > c->derived_limit) {
        walked = true;
        entry *oldest = NULL;
        for (size_t b = 0; b < c->bucket_count; b++)
            for (entry *e = c->buckets[b]; e; e = e->next)
                if (e->analysis && e->refs == 0 && (!oldest || e->last_used < oldest->last_used))
                    oldest = e;
        if (!oldest)
            break; /* the rest is in use */
        wd_log(WD_LOG_DEBUG, "evicting the derived data of %s (%zu bytes)", oldest->id,
               oldest->analysis_bytes);
        drop_analysis(c, oldest);
        if (!oldest->stored) {
            unlink_entry(c, oldest);
            entry_free(oldest);
        }
    }
    if (walked)
        check_locked(c); /* done, over the bound only with everything in use;
                            one more walk where each step walked them all */
}

/* Hold e for a request; `t` is the texts to answer with (e's own when
 * NULL; a put passes those it stored, which a later rename may replace). */
static void fill_use(entry *e, texts *t, wp_fixture_use *use)
{
    if (!t)
        t = e->texts;
    assert(e->refs > 0 && e->analysis && t->refs > 0);
    t->refs++;
    use->id = e->id;
    use->name = t->name;
    use->canonical = t->canonical;
    use->fixture = e->fixture;
    use->analysis = e->analysis;
    use->handle[0] = e;
    use->handle[1] = t;
}

/* Fill *failure (the cache's status and words; proto makes the JSON-RPC
 * error of them, wp_error_host) and return false. */
static bool fail(wp_host_failure *failure, wp_host_status status, const char *format, ...)
    __attribute__((format(printf, 3, 4)));

static bool fail(wp_host_failure *failure, wp_host_status status, const char *format, ...)
{
    failure->status = status;
    va_list args;
    va_start(args, format);
    vsnprintf(failure->reason, sizeof failure->reason, format, args);
    va_end(args);
    return false;
}

/* With e held (refs counted), derive its analysis unless it exists, and
 * fill `use` (with the texts `t`, see fill_use; a reference to them is
 * passed in and consumed).  The analysis is built without the lock; if two
 * threads race, one keeps its result and the other's is freed.  (Not to be
 * confused with wd_cache_ready, which asks whether it exists.) */
static bool derive_for_use(wd_cache *c, entry *e, texts *t, wp_fixture_use *use,
                           wp_host_failure *failure)
{
    pthread_mutex_lock(&c->lock);
    e->last_used = ++c->clock;
    if (e->analysis) {
        fill_use(e, t, use);
        texts_drop(t);
        pthread_mutex_unlock(&c->lock);
        return true;
    }
    pthread_mutex_unlock(&c->lock);
    wr_analysis *a;
    wr_status status = wr_analysis_new(e->fixture, &a);
    pthread_mutex_lock(&c->lock);
    if (status != WR_OK) {
        assert(e->refs > 0);
        e->refs--;
        if (!e->analysis)
            drop_text(c, e); /* nothing to charge it to */
        texts_drop(t);
        pthread_mutex_unlock(&c->lock);
        fail(failure, WP_HOST_NO_MEMORY, "out of memory deriving the fixture's cones");
        return false;
    }
    if (!e->analysis) {
        e->analysis = a;
        /* A cached-only entry goes when its analysis is evicted: charge its
         * own memory too, so that inline fixtures, however large, stay
         * within the bound.  The charge is fixed here; a later put or
         * delete of the entry does not change it. */
        e->analysis_bytes =
            wr_analysis_bytes(a) + (e->stored ? 0 : entry_bytes(e)) + e->text_length;
        e->serial = ++c->serial;
        c->derived_bytes += e->analysis_bytes;
        evict_locked(c);
    } else {
        wr_analysis_free(a);
    }
    fill_use(e, t, use);
    texts_drop(t);
    pthread_mutex_unlock(&c->lock);
    return true;
}

/* ---- the state directory ------------------------------------------------- */

static bool sync_directory(const char *dir)
{
    int fd = open(dir, O_RDONLY | O_DIRECTORY);
    if (fd < 0)
        return false;
    bool ok = fsync(fd) == 0;
    close(fd);
    return ok;
}

/* The steps of storing a fixture's file, in their order (the durability
 * order): a put is answered only once the last is reached. */
typedef enum store_step {
    STEP_CREATE, STEP_WRITE, STEP_SYNC, STEP_CLOSE, STEP_RENAME, STEP_SYNC_DIRECTORY,
    STEP_DURABLE /* written, synced, renamed, its directory synced */
} store_step;

static const char *const store_step_verbs[] = {"create", "write", "sync", "close", "rename",
                                               "sync the directory of"};

static bool write_fixture_file(const wd_cache *c, const char *id, const char *text,
                               wp_host_failure *failure)
{
    char final_path[4096], temporary[4096];
    snprintf(final_path, sizeof final_path, "%s/%s.json", c->dir, id);
    snprintf(temporary, sizeof temporary, "%s/.%s.tmp", c->dir, id);
    int fd = open(temporary, O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0640);
    store_step step = STEP_CREATE;
    if (fd >= 0) {
        size_t length = strlen(text), done = 0;
        step = STEP_WRITE;
        while (done < length) {
            ssize_t n = write(fd, text + done, length - done);
            if (n < 0 && errno == EINTR)
                continue;
            if (n <= 0)
                break;
            done += (size_t)n;
        }
        if (done == length && write(fd, "\n", 1) == 1) {
            step = STEP_SYNC;
            if (fsync(fd) == 0) {
                step = STEP_CLOSE;
                int closed = close(fd);
                fd = -1;
                if (closed == 0) {
                    step = STEP_RENAME;
                    if (rename(temporary, final_path) == 0) {
                        step = STEP_SYNC_DIRECTORY;
                        if (sync_directory(c->dir))
                            step = STEP_DURABLE;
                    }
                }
            }
        }
    }
    if (step == STEP_DURABLE) {
        assert(fd < 0); /* synced and closed before the rename */
        return true;
    }
    int saved = errno;
    if (fd >= 0)
        close(fd);
    unlink(temporary);
    fail(failure, WP_HOST_STORAGE, "could not %s %s: %s; the fixture is not stored",
         store_step_verbs[step], final_path, strerror(saved));
    wd_log(WD_LOG_ERROR, "%s", failure->reason);
    return false;
}

static bool remove_fixture_file(const wd_cache *c, const char *id, wp_host_failure *failure)
{
    char path[4096];
    snprintf(path, sizeof path, "%s/%s.json", c->dir, id);
    if ((unlink(path) != 0 && errno != ENOENT) || !sync_directory(c->dir)) {
        fail(failure, WP_HOST_STORAGE, "could not remove %s: %s; the fixture is still stored",
             path, strerror(errno));
        wd_log(WD_LOG_ERROR, "%s", failure->reason);
        return false;
    }
    return true;
}

/* What reading a fixture file came to. */
typedef enum file_read {
    FILE_UNREADABLE,  /* not opened, not read, or too long: errno says why */
    FILE_NOT_JSON,
    FILE_NOT_FIXTURE, /* JSON that wp_fixture_read refused: `error` says why */
    FILE_FIXTURE
} file_read;

/* Read the fixture in the file `path` into `doc`: one reader for --load
 * (wd_cache_load_file) and the state directory (load_directory).  At most
 * `limit` bytes are read; a longer file is unreadable (EFBIG), unless
 * `cut`, when the rest is ignored (--load has always read a line's worth).
 * *json is its JSON, for the caller's further questions (the caller deletes
 * it), or NULL when the file is not read as JSON. */
static file_read read_fixture_file(const char *path, size_t limit, bool cut, cJSON **json,
                                   wp_fixture_doc *doc, wp_error *error)
{
    *json = NULL;
    bool more;
    char *text = wd_file_read(path, limit, NULL, &more);
    if (!text)
        return FILE_UNREADABLE;
    if (more && !cut) {
        free(text);
        errno = EFBIG;
        return FILE_UNREADABLE;
    }
    *json = cJSON_Parse(text);
    free(text);
    if (!*json)
        return FILE_NOT_JSON;
    return wp_fixture_read(*json, "", doc, error) ? FILE_FIXTURE : FILE_NOT_FIXTURE;
}

static bool add_loaded(wd_cache *c, wp_fixture_doc *doc)
{
    entry *e = calloc(1, sizeof *e);
    texts *t = e ? texts_from(doc) : NULL;
    if (!t) {
        free(e);
        wp_fixture_doc_release(doc);
        return false;
    }
    memcpy(e->id, doc->id, sizeof e->id);
    e->texts = t;
    e->fixture = doc->fixture;
    doc->fixture = NULL;
    e->stored = true;
    if (!insert(c, e)) {
        entry_free(e);
        return false;
    }
    c->stored_count++;
    return true;
}

/* A file DIR/fixtures/<old>.json whose name is the fixture's id by the
 * older rule (the hash of the fixture as written): write it under its id
 * and remove the old name, durably, so that one file is left.  When the
 * fixture is already loaded (another spelling of it, or the new file of a
 * re-keying cut short) the old file only goes.  False, with the old file
 * left in place and nothing loaded, when the directory cannot be changed. */
static bool rekey(wd_cache *c, const char *path, const char *old_id, wp_fixture_doc *doc,
                  bool *loaded)
{
    wp_host_failure failure;
    *loaded = false;
    if (find(c, doc->id)) {
        wd_log(WD_LOG_INFO, "%s is stored already as %s (another spelling of it); removing %s",
               old_id, doc->id, path);
    } else {
        if (!write_fixture_file(c, doc->id, doc->canonical, &failure))
            return false; /* logged */
        wd_log(WD_LOG_INFO, "re-keyed the fixture %s to %s (ids now hash the explicit fixture)",
               old_id, doc->id);
        *loaded = true;
    }
    if (unlink(path) != 0 || !sync_directory(c->dir)) {
        wd_log(WD_LOG_ERROR, "could not remove %s after re-keying it: %s", path, strerror(errno));
        return false;
    }
    return true;
}

/* Read every DIR/fixtures/<id>.json.  What does not read back is logged and
 * skipped; a file named by the fixture's id by the older rule is re-keyed;
 * a file whose name is not its fixture's id is refused, left in place;
 * leftover temporary files of an interrupted put are removed. */
static void load_directory(wd_cache *c)
{
    DIR *dir = opendir(c->dir);
    if (!dir)
        return;
    size_t loaded = 0, skipped = 0, rekeyed = 0;
    struct dirent *d;
    while ((d = readdir(dir))) {
        char path[4096];
        snprintf(path, sizeof path, "%s/%s", c->dir, d->d_name);
        size_t n = strlen(d->d_name);
        if (d->d_name[0] == '.') {
            if (n > 4 && strcmp(d->d_name + n - 4, ".tmp") == 0)
                unlink(path);
            continue;
        }
        if (n < 6 || strcmp(d->d_name + n - 5, ".json") != 0)
            continue;
        char named[WP_ID_LENGTH + 1] = ""; /* the id its name says, if it says one */
        if (n == WP_ID_LENGTH + 5) {
            memcpy(named, d->d_name, WP_ID_LENGTH);
            named[WP_ID_LENGTH] = 0;
        }
        cJSON *json;
        wp_fixture_doc doc;
        wp_error error = {0};
        char legacy[WP_ID_LENGTH + 1] = "";
        file_read read = read_fixture_file(path, STORED_FILE_LIMIT, false, &json, &doc, &error);
        bool ok = read == FILE_FIXTURE;
        if (ok && strcmp(named, doc.id) != 0 && !wp_fixture_legacy_id(json, legacy)) {
            wp_fixture_doc_release(&doc);
            ok = false;
            snprintf(error.reason, sizeof error.reason, "out of memory");
        }
        cJSON_Delete(json);
        if (!ok) {
            bool parsed = read >= FILE_NOT_FIXTURE;
            wd_log(WD_LOG_WARN, "skipping %s: %s%s%s", path,
                   parsed ? error.field : "", parsed && error.field[0] ? ": " : "",
                   parsed ? error.reason : "not readable as JSON");
            skipped++;
            continue;
        }
        if (strcmp(named, doc.id) == 0) {
            /* Named by its id: the usual case.  A second file of the same
             * fixture cannot have this name. */
            if (!find(c, doc.id) && add_loaded(c, &doc))
                loaded++;
            else
                wp_fixture_doc_release(&doc);
        } else if (strcmp(named, legacy) == 0) {
            bool load = false;
            if (rekey(c, path, legacy, &doc, &load)) {
                rekeyed++;
                if (load && add_loaded(c, &doc))
                    loaded++;
            } else {
                skipped++;
            }
            wp_fixture_doc_release(&doc);
        } else {
            /* Loading it under the content's id would let a delete of that
             * id leave this file to come back at the next start; removing
             * it would destroy what may be someone's only copy. */
            wd_log(WD_LOG_WARN,
                   "refusing %s: it holds the fixture %s, not the one its name says; "
                   "left in place, not loaded",
                   path, doc.id);
            wp_fixture_doc_release(&doc);
            skipped++;
        }
    }
    closedir(dir);
    check_locked(c);
    wd_log(WD_LOG_INFO, "loaded %zu stored fixtures from %s%s%s", loaded, c->dir,
           rekeyed ? " (some re-keyed, see above)" : "",
           skipped ? " (some files skipped, see above)" : "");
    if (c->stored_count > c->max_stored)
        wd_log(WD_LOG_WARN,
               "%zu fixtures are stored, more than --max-fixtures %zu: all are kept, and "
               "new ones are refused until some are deleted",
               c->stored_count, c->max_stored);
}

/* Lock the state directory for the daemon's life: a second daemon on the
 * same directory would serve fixtures the first one deletes, and the two
 * would overwrite each other's files.  The lock is on the directory's own
 * descriptor, not on a file in it: a file can be deleted and made anew (a
 * second daemon would then lock the new one), the directory it names
 * cannot while a descriptor holds it.  flock, not fcntl: it is released
 * only when the descriptor is closed (or the process dies), never by an
 * unrelated close of the same file.  DIR/lock only says who holds it (the
 * pid), for the refusal. */
static int lock_state_directory(const char *state_dir, char *why, size_t why_size)
{
    char path[4096];
    snprintf(path, sizeof path, "%s/lock", state_dir);
    int fd = open(state_dir, O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (fd < 0) {
        snprintf(why, why_size, "cannot use the state directory %s: %s", state_dir,
                 strerror(errno));
        return -1;
    }
    if (flock(fd, LOCK_EX | LOCK_NB) != 0) {
        int saved = errno;
        char holder[32] = "";
        int pid_fd = open(path, O_RDONLY | O_CLOEXEC);
        ssize_t n = pid_fd >= 0 ? pread(pid_fd, holder, sizeof holder - 1, 0) : -1;
        if (pid_fd >= 0)
            close(pid_fd);
        holder[n > 0 ? n : 0] = 0;
        holder[strcspn(holder, "\n")] = 0;
        close(fd);
        if (saved == EWOULDBLOCK)
            snprintf(why, why_size,
                     "the state directory %s is in use by another wrenchd (pid %s, which "
                     "holds a lock on the directory)",
                     state_dir, holder[0] ? holder : "unknown");
        else
            snprintf(why, why_size, "cannot lock the state directory %s: %s", state_dir,
                     strerror(saved));
        return -1;
    }
    char pid[32];
    int length = snprintf(pid, sizeof pid, "%ld\n", (long)getpid());
    int pid_fd = open(path, O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0640);
    if (pid_fd < 0 || write(pid_fd, pid, (size_t)length) != length)
        wd_log(WD_LOG_WARN, "could not write the pid into %s: %s", path, strerror(errno));
    if (pid_fd >= 0)
        close(pid_fd);
    return fd;
}

/* ---- the public functions -------------------------------------------------- */

wd_cache *wd_cache_new(const char *state_dir, size_t derived_limit, size_t max_stored, char *why,
                       size_t why_size)
{
    wd_cache *c = calloc(1, sizeof *c);
    if (!c) {
        snprintf(why, why_size, "out of memory");
        return NULL;
    }
    pthread_mutex_init(&c->lock, NULL);
    pthread_mutex_init(&c->store_lock, NULL);
    c->bucket_count = 64;
    c->buckets = calloc(c->bucket_count, sizeof *c->buckets);
    c->written_buckets = calloc(c->bucket_count, sizeof *c->written_buckets);
    c->text_buckets = calloc(c->bucket_count, sizeof *c->text_buckets);
    c->derived_limit = derived_limit;
    c->max_stored = max_stored;
    c->lock_fd = -1;
    if (!c->buckets || !c->written_buckets || !c->text_buckets) {
        snprintf(why, why_size, "out of memory");
        wd_cache_free(c);
        return NULL;
    }
    if (state_dir) {
        size_t size = strlen(state_dir) + sizeof "/fixtures";
        c->dir = malloc(size);
        if (!c->dir) {
            snprintf(why, why_size, "out of memory");
            wd_cache_free(c);
            return NULL;
        }
        snprintf(c->dir, size, "%s/fixtures", state_dir);
        if (!wd_file_make_directories(c->dir, 0750) || access(c->dir, R_OK | X_OK) != 0) {
            snprintf(why, why_size, "cannot use the state directory %s: %s", c->dir,
                     strerror(errno));
            wd_cache_free(c);
            return NULL;
        }
        c->lock_fd = lock_state_directory(state_dir, why, why_size);
        if (c->lock_fd < 0) {
            wd_cache_free(c);
            return NULL;
        }
        load_directory(c);
    }
    return c;
}

void wd_cache_free(wd_cache *c)
{
    if (!c)
        return;
    if (c->buckets && c->written_buckets && c->text_buckets)
        check_locked(c);
    for (size_t b = 0; c->buckets && b < c->bucket_count; b++)
        for (entry *e = c->buckets[b], *next; e; e = next) {
            next = e->next;
            assert(e->refs == 0); /* every use released */
            entry_free(e);
        }
    free(c->buckets);
    free(c->written_buckets);
    free(c->text_buckets);
    free(c->dir);
    if (c->lock_fd >= 0)
        close(c->lock_fd); /* releases the lock; DIR/lock stays, harmless */
    pthread_mutex_destroy(&c->lock);
    pthread_mutex_destroy(&c->store_lock);
    free(c);
}

bool wd_cache_load_file(wd_cache *c, const char *path, size_t limit)
{
    cJSON *json;
    wp_fixture_doc doc;
    wp_error error = {0};
    file_read read = read_fixture_file(path, limit, true, &json, &doc, &error);
    cJSON_Delete(json);
    if (read == FILE_UNREADABLE) {
        wd_log(WD_LOG_ERROR, "--load %s: %s", path, strerror(errno));
        return false;
    }
    wp_fixture_use use;
    wp_host_failure failure;
    if (read != FILE_FIXTURE) {
        wd_log(WD_LOG_ERROR, "--load %s: %s%s%s", path, error.field, error.field[0] ? ": " : "",
               read == FILE_NOT_JSON ? "not a JSON text" : error.reason);
        return false;
    }
    if (!wd_cache_adopt(c, &doc, true, &use, &failure)) {
        wd_log(WD_LOG_ERROR, "--load %s: %s", path, failure.reason);
        return false;
    }
    wd_log(WD_LOG_INFO, "loaded %s as %s (%s)", path, use.id, use.name);
    wd_cache_release(c, &use);
    return true;
}

/* Keep the inline text an adoption read e from, if e keeps none: charged
 * with the analysis (now if it is there, else when it is derived).
 * Without memory for it, it is just not kept. */
static void keep_text(wd_cache *c, entry *e, const wp_fixture_doc *doc)
{
    if (!doc->text || doc->text_length < WP_INLINE_TEXT_MIN || e->text ||
        !(e->text = malloc(doc->text_length)))
        return;
    memcpy(e->text, doc->text, doc->text_length);
    e->text_length = doc->text_length;
    e->text_hash = head_hash(e->text);
    link_text(c, e);
    if (e->analysis) {
        e->analysis_bytes += e->text_length;
        c->derived_bytes += e->text_length;
        evict_locked(c); /* e is held: others go */
    }
}

bool wd_cache_adopt(wd_cache *c, wp_fixture_doc *doc, bool store, wp_fixture_use *use,
                    wp_host_failure *failure)
{
    if (store)
        pthread_mutex_lock(&c->store_lock);
    pthread_mutex_lock(&c->lock);
    entry *e = find(c, doc->id);
    if (!e) {
        e = calloc(1, sizeof *e);
        texts *t = e ? texts_from(doc) : NULL;
        if (e)
            memcpy(e->id, doc->id, sizeof e->id); /* before insert: it picks the bucket */
        if (!t || !insert(c, e)) {
            pthread_mutex_unlock(&c->lock);
            if (store)
                pthread_mutex_unlock(&c->store_lock);
            if (t) {
                e->texts = t;
                entry_free(e);
            } else {
                free(e);
            }
            wp_fixture_doc_release(doc);
            fail(failure, WP_HOST_NO_MEMORY, "out of memory");
            return false;
        }
        e->texts = t;
        e->fixture = doc->fixture;
        doc->fixture = NULL;
    }
    set_written(c, e, doc->written);
    e->refs++;
    keep_text(c, e, doc);
    /* A new entry has taken the doc's texts; an existing one may be renamed. */
    bool renamed = doc->name && strcmp(doc->name, e->texts->name) != 0;
    bool write = store && (!e->stored || renamed);
    bool over_limit = store && !e->stored && c->stored_count >= c->max_stored;
    /* Texts change only under store_lock, which a storing put holds. */
    const char *text = renamed ? doc->canonical : e->texts->canonical;
    pthread_mutex_unlock(&c->lock);

    if (over_limit) {
        /* stored_count changes only under store_lock, held here. */
        fail(failure, WP_HOST_LIMIT,
             "%zu fixtures are stored, the most --max-fixtures allows; delete one first",
             c->stored_count);
        pthread_mutex_unlock(&c->store_lock);
        wp_fixture_use refused = {.handle = {e, NULL}};
        wd_cache_release(c, &refused);
        wp_fixture_doc_release(doc);
        return false;
    }

    if (write) {
        if (c->dir && !write_fixture_file(c, e->id, text, failure)) {
            pthread_mutex_unlock(&c->store_lock);
            wp_fixture_use failed = {.handle = {e, NULL}};
            wd_cache_release(c, &failed);
            wp_fixture_doc_release(doc);
            return false;
        }
        /* The file is durable (write_fixture_file: written, synced,
         * renamed, its directory synced): only now is the fixture stored,
         * and only then is the put answered. */
        pthread_mutex_lock(&c->lock);
        c->stored_count += !e->stored;
        e->stored = true;
        texts *t = renamed ? texts_from(doc) : NULL;
        if (t) {
            texts_drop(e->texts);
            e->texts = t;
        }
        pthread_mutex_unlock(&c->lock);
    }
    /* The texts this request answers with: those it stored, taken while no
     * other put can rename the fixture. */
    pthread_mutex_lock(&c->lock);
    texts *answered = e->texts;
    answered->refs++;
    pthread_mutex_unlock(&c->lock);
    if (store)
        pthread_mutex_unlock(&c->store_lock);
    wp_fixture_doc_release(doc);
    return derive_for_use(c, e, answered, use, failure);
}

bool wd_cache_use(wd_cache *c, const char *id, wp_fixture_use *use, wp_host_failure *failure)
{
    pthread_mutex_lock(&c->lock);
    entry *e = find(c, id);
    if (!e || !e->stored) {
        pthread_mutex_unlock(&c->lock);
        fail(failure, WP_HOST_NO_FIXTURE, "no stored fixture has the id %s", id);
        return false;
    }
    e->refs++;
    pthread_mutex_unlock(&c->lock);
    return derive_for_use(c, e, NULL, use, failure);
}

bool wd_cache_use_written(wd_cache *c, const char *key, wp_fixture_use *use)
{
    pthread_mutex_lock(&c->lock);
    entry *e = find_written(c, key);
    if (e)
        e->refs++;
    pthread_mutex_unlock(&c->lock);
    wp_host_failure failure;
    return e && derive_for_use(c, e, NULL, use, &failure);
}

size_t wd_cache_use_text(wd_cache *c, const char *text, size_t length, wp_fixture_use *use)
{
    pthread_mutex_lock(&c->lock);
    entry *e = find_text(c, text, length);
    size_t span = e ? e->text_length : 0;
    if (e)
        e->refs++;
    pthread_mutex_unlock(&c->lock);
    if (!e)
        return 0;
    wd_log(WD_LOG_DEBUG, "fixture %s recognised from its inline text (%zu bytes)", e->id, span);
    wp_host_failure failure;
    return derive_for_use(c, e, NULL, use, &failure) ? span : 0;
}

int wd_cache_ready(wd_cache *c, const char *id)
{
    pthread_mutex_lock(&c->lock);
    const entry *e = find(c, id);
    int cones = e && e->stored && e->analysis
                    ? wr_analysis_cone_count(e->analysis, WR_SET_GOAL) +
                          wr_analysis_cone_count(e->analysis, WR_SET_STRONG)
                    : -1;
    pthread_mutex_unlock(&c->lock);
    return cones;
}

int wd_cache_use_ready(wd_cache *c, const char *id, wp_fixture_use *use)
{
    pthread_mutex_lock(&c->lock);
    entry *e = find(c, id);
    int cones = -1;
    if (e && e->stored && e->analysis) {
        cones = wr_analysis_cone_count(e->analysis, WR_SET_GOAL) +
                wr_analysis_cone_count(e->analysis, WR_SET_STRONG);
        e->refs++;
        e->last_used = ++c->clock;
        fill_use(e, NULL, use);
    }
    pthread_mutex_unlock(&c->lock);
    return cones;
}

void wd_cache_release(wd_cache *c, wp_fixture_use *use)
{
    entry *e = use->handle[0];
    pthread_mutex_lock(&c->lock);
    texts_drop(use->handle[1]);
    assert(e->refs > 0);
    e->refs--;
    if (e->refs == 0 && !e->stored && !e->analysis) {
        unlink_entry(c, e);
        entry_free(e);
    } else {
        evict_locked(c);
    }
    pthread_mutex_unlock(&c->lock);
    memset(use, 0, sizeof *use);
}

bool wd_cache_delete(wd_cache *c, const char *id, wp_host_failure *failure)
{
    pthread_mutex_lock(&c->store_lock);
    pthread_mutex_lock(&c->lock);
    entry *e = find(c, id);
    bool stored = e && e->stored;
    pthread_mutex_unlock(&c->lock);
    bool ok = false;
    if (!stored)
        fail(failure, WP_HOST_NO_FIXTURE, "no stored fixture has the id %s", id);
    else if (!c->dir || remove_fixture_file(c, id, failure)) {
        /* It stays as a cached fixture until its derived data is evicted. */
        pthread_mutex_lock(&c->lock);
        assert(e->stored && c->stored_count > 0);
        e->stored = false;
        c->stored_count--;
        if (e->refs == 0 && !e->analysis) {
            unlink_entry(c, e);
            entry_free(e);
        }
        pthread_mutex_unlock(&c->lock);
        ok = true;
    }
    pthread_mutex_unlock(&c->store_lock);
    return ok;
}

static int compare_ids(const void *a, const void *b)
{
    return strcmp((*(const entry *const *)a)->id, (*(const entry *const *)b)->id);
}

bool wd_cache_list(wd_cache *c, wp_fixture_listing *listing)
{
    listing->count = 0;
    pthread_mutex_lock(&c->lock);
    entry **sorted = malloc((c->count ? c->count : 1) * sizeof *sorted);
    listing->entries = calloc(c->count ? c->count : 1, sizeof *listing->entries);
    size_t n = 0;
    for (size_t b = 0; sorted && listing->entries && b < c->bucket_count; b++)
        for (entry *e = c->buckets[b]; e; e = e->next)
            if (e->stored)
                sorted[n++] = e;
    bool ok = sorted && listing->entries;
    if (ok)
        check_locked(c);
    if (ok)
        qsort(sorted, n, sizeof *sorted, compare_ids);
    for (size_t i = 0; ok && i < n; i++) {
        wp_fixture_entry *item = &listing->entries[i];
        snprintf(item->id, sizeof item->id, "%s", sorted[i]->id);
        item->name = strdup(sorted[i]->texts->name);
        item->fixels = sorted[i]->fixture->fixel_count;
        ok = item->name != NULL;
        listing->count = i + 1;
    }
    pthread_mutex_unlock(&c->lock);
    free(sorted);
    if (!ok)
        wp_fixture_listing_release(listing);
    return ok;
}

uint64_t wd_cache_serial(const wp_fixture_use *use)
{
    /* Stable while the fixture is in use: its analysis cannot be evicted. */
    const entry *e = use->handle[0];
    assert(e->refs > 0 && e->analysis);
    return e->serial;
}

void wd_cache_stats_get(wd_cache *c, wd_cache_stats *stats)
{
    memset(stats, 0, sizeof *stats);
    pthread_mutex_lock(&c->lock);
    for (size_t b = 0; b < c->bucket_count; b++)
        for (entry *e = c->buckets[b]; e; e = e->next) {
            stats->stored += e->stored;
            stats->cached += e->analysis != NULL;
        }
    check_locked(c);
    stats->derived_bytes = c->derived_bytes;
    stats->derived_limit = c->derived_limit;
    pthread_mutex_unlock(&c->lock);
}
