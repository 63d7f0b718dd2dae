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
 * the put is acknowledged; a delete unlinks and syncs the directory. */
#include "wd_cache.h"
#include "wd_log.h"

#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

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
    size_t analysis_bytes;
    uint64_t serial;          /* names the current analysis */
    uint64_t last_used;       /* LRU clock */
    int refs;                 /* requests holding it */
    bool stored;              /* put (listed, on disk) rather than only cached */
    struct entry *next;       /* hash chain */
} entry;

struct wd_cache {
    pthread_mutex_t lock;
    pthread_mutex_t store_lock;
    entry **buckets;
    size_t bucket_count;      /* a power of two */
    size_t count;
    size_t derived_bytes, derived_limit;
    uint64_t clock, serial;
    char *dir;                /* DIR/fixtures, or NULL for memory only */
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
    if (t && --t->refs == 0) {
        free(t->name);
        free(t->canonical);
        free(t);
    }
}

static void entry_free(entry *e)
{
    texts_drop(e->texts);
    wr_analysis_free(e->analysis);
    wr_fixture_free(e->fixture);
    free(e);
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

static bool insert(wd_cache *c, entry *e)
{
    if (c->count + 1 > 2 * c->bucket_count) {
        size_t n = 2 * c->bucket_count;
        entry **grown = calloc(n, sizeof *grown);
        if (!grown)
            return false;
        entry **old = c->buckets;
        size_t old_count = c->bucket_count;
        c->buckets = grown;
        c->bucket_count = n;
        for (size_t i = 0; i < old_count; i++)
            for (entry *x = old[i], *next; x; x = next) {
                next = x->next;
                size_t b = bucket_of(c, x->id);
                x->next = c->buckets[b];
                c->buckets[b] = x;
            }
        free(old);
    }
    size_t b = bucket_of(c, e->id);
    e->next = c->buckets[b];
    c->buckets[b] = e;
    c->count++;
    return true;
}

static void unlink_entry(wd_cache *c, entry *e)
{
    for (entry **p = &c->buckets[bucket_of(c, e->id)]; *p; p = &(*p)->next)
        if (*p == e) {
            *p = e->next;
            c->count--;
            return;
        }
}

static void drop_analysis(wd_cache *c, entry *e)
{
    wr_analysis_free(e->analysis);
    e->analysis = NULL;
    c->derived_bytes -= e->analysis_bytes;
    e->analysis_bytes = 0;
}

/* Evict derived data, least recently used first, until within the bound.
 * Entries in use are skipped; a cached-only entry goes with its data. */
static void evict_locked(wd_cache *c)
{
    while (c->derived_bytes > c->derived_limit) {
        entry *oldest = NULL;
        for (size_t b = 0; b < c->bucket_count; b++)
            for (entry *e = c->buckets[b]; e; e = e->next)
                if (e->analysis && e->refs == 0 && (!oldest || e->last_used < oldest->last_used))
                    oldest = e;
        if (!oldest)
            return;
        wd_log(WD_LOG_DEBUG, "evicting the derived data of %s (%zu bytes)", oldest->id,
               oldest->analysis_bytes);
        drop_analysis(c, oldest);
        if (!oldest->stored) {
            unlink_entry(c, oldest);
            entry_free(oldest);
        }
    }
}

/* Hold e for a request; `t` is the texts to answer with (e's own when
 * NULL; a put passes those it stored, which a later rename may replace). */
static void fill_use(entry *e, texts *t, wp_fixture_use *use)
{
    if (!t)
        t = e->texts;
    t->refs++;
    use->id = e->id;
    use->name = t->name;
    use->canonical = t->canonical;
    use->fixture = e->fixture;
    use->analysis = e->analysis;
    use->handle[0] = e;
    use->handle[1] = t;
}

/* With e held (refs counted), make sure its analysis exists and fill `use`
 * (with the texts `t`, see fill_use; a reference to them is passed in and
 * consumed).  The analysis is built without the lock; if two threads race,
 * one keeps its result and the other's is freed. */
static bool ready(wd_cache *c, entry *e, texts *t, wp_fixture_use *use, wp_error *error)
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
    wr_analysis *a = wr_analysis_new(e->fixture);
    pthread_mutex_lock(&c->lock);
    if (!a) {
        e->refs--;
        texts_drop(t);
        pthread_mutex_unlock(&c->lock);
        wp_error_set(error, WP_INTERNAL, "", "out of memory deriving the fixture's cones");
        return false;
    }
    if (!e->analysis) {
        e->analysis = a;
        e->analysis_bytes = wr_analysis_bytes(a);
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

static bool write_fixture_file(const wd_cache *c, const char *id, const char *text,
                               wp_error *error)
{
    char final_path[4096], temporary[4096];
    snprintf(final_path, sizeof final_path, "%s/%s.json", c->dir, id);
    snprintf(temporary, sizeof temporary, "%s/.%s.tmp", c->dir, id);
    int fd = open(temporary, O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0640);
    const char *step = "create";
    if (fd >= 0) {
        size_t length = strlen(text), done = 0;
        step = "write";
        while (done < length) {
            ssize_t n = write(fd, text + done, length - done);
            if (n < 0 && errno == EINTR)
                continue;
            if (n <= 0)
                break;
            done += (size_t)n;
        }
        if (done == length && write(fd, "\n", 1) == 1) {
            step = "sync";
            if (fsync(fd) == 0) {
                step = "close";
                int closed = close(fd);
                fd = -1;
                if (closed == 0) {
                    step = "rename";
                    if (rename(temporary, final_path) == 0) {
                        step = "sync the directory of";
                        if (sync_directory(c->dir))
                            return true;
                    }
                }
            }
        }
    }
    int saved = errno;
    if (fd >= 0)
        close(fd);
    unlink(temporary);
    wp_error_set(error, WP_STORAGE, "", "could not %s %s: %s; the fixture is not stored", step,
                 final_path, strerror(saved));
    wd_log(WD_LOG_ERROR, "%s", error->reason);
    return false;
}

static bool remove_fixture_file(const wd_cache *c, const char *id, wp_error *error)
{
    char path[4096];
    snprintf(path, sizeof path, "%s/%s.json", c->dir, id);
    if ((unlink(path) != 0 && errno != ENOENT) || !sync_directory(c->dir)) {
        wp_error_set(error, WP_STORAGE, "", "could not remove %s: %s; the fixture is still stored",
                     path, strerror(errno));
        wd_log(WD_LOG_ERROR, "%s", error->reason);
        return false;
    }
    return true;
}

static char *read_file(const char *path, size_t limit)
{
    FILE *file = fopen(path, "rb");
    if (!file)
        return NULL;
    char *text = NULL;
    size_t length = 0, capacity = 0;
    for (;;) {
        if (length + 4096 + 1 > capacity) {
            capacity = capacity ? 2 * capacity : 8192;
            char *grown = capacity > limit ? NULL : realloc(text, capacity);
            if (!grown) {
                free(text);
                fclose(file);
                return NULL;
            }
            text = grown;
        }
        size_t n = fread(text + length, 1, 4096, file);
        length += n;
        if (n < 4096)
            break;
    }
    bool failed = ferror(file);
    fclose(file);
    if (failed) {
        free(text);
        return NULL;
    }
    text[length] = 0;
    return text;
}

/* Read every DIR/fixtures/<id>.json.  What does not read back is logged and
 * skipped; leftover temporary files of an interrupted put are removed. */
static void load_directory(wd_cache *c)
{
    DIR *dir = opendir(c->dir);
    if (!dir)
        return;
    size_t loaded = 0, skipped = 0;
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
        char *text = read_file(path, 256u << 20);
        cJSON *json = text ? cJSON_Parse(text) : NULL;
        wp_fixture_doc doc;
        wp_error error = {0};
        bool ok = json && wp_fixture_read(json, "", &doc, &error);
        cJSON_Delete(json);
        free(text);
        if (!ok) {
            wd_log(WD_LOG_WARN, "skipping %s: %s%s%s", path,
                   json ? error.field : "", json && error.field[0] ? ": " : "",
                   json ? error.reason : "not readable as JSON");
            skipped++;
            continue;
        }
        if (strncmp(d->d_name, doc.id, WP_ID_LENGTH) != 0 || n != WP_ID_LENGTH + 5)
            wd_log(WD_LOG_WARN, "%s holds the fixture %s; loading it under that id", path, doc.id);
        entry *e = calloc(1, sizeof *e);
        texts *t = e ? texts_from(&doc) : NULL;
        if (!e || !t || find(c, doc.id)) {
            free(e);
            texts_drop(t);
            wp_fixture_doc_release(&doc);
            continue;
        }
        memcpy(e->id, doc.id, sizeof e->id);
        e->texts = t;
        e->fixture = doc.fixture;
        e->stored = true;
        if (!insert(c, e)) {
            doc.fixture = NULL;
            entry_free(e);
            continue;
        }
        loaded++;
    }
    closedir(dir);
    wd_log(WD_LOG_INFO, "loaded %zu stored fixtures from %s%s", loaded, c->dir,
           skipped ? " (some files skipped, see above)" : "");
}

static bool make_directories(const char *path)
{
    char partial[4096];
    snprintf(partial, sizeof partial, "%s", path);
    for (char *p = partial + 1; *p; p++)
        if (*p == '/') {
            *p = 0;
            if (mkdir(partial, 0750) != 0 && errno != EEXIST)
                return false;
            *p = '/';
        }
    return mkdir(partial, 0750) == 0 || errno == EEXIST;
}

/* ---- the public functions -------------------------------------------------- */

wd_cache *wd_cache_new(const char *state_dir, size_t derived_limit, char *why, size_t why_size)
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
    c->derived_limit = derived_limit;
    if (!c->buckets) {
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
        if (!make_directories(c->dir) || access(c->dir, R_OK | X_OK) != 0) {
            snprintf(why, why_size, "cannot use the state directory %s: %s", c->dir,
                     strerror(errno));
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
    for (size_t b = 0; c->buckets && b < c->bucket_count; b++)
        for (entry *e = c->buckets[b], *next; e; e = next) {
            next = e->next;
            entry_free(e);
        }
    free(c->buckets);
    free(c->dir);
    pthread_mutex_destroy(&c->lock);
    pthread_mutex_destroy(&c->store_lock);
    free(c);
}

bool wd_cache_adopt(wd_cache *c, wp_fixture_doc *doc, bool store, wp_fixture_use *use,
                    wp_error *error)
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
            wp_error_set(error, WP_INTERNAL, "", "out of memory");
            return false;
        }
        e->texts = t;
        e->fixture = doc->fixture;
        doc->fixture = NULL;
    }
    e->refs++;
    /* A new entry has taken the doc's texts; an existing one may be renamed. */
    bool renamed = doc->name && strcmp(doc->name, e->texts->name) != 0;
    bool write = store && (!e->stored || renamed);
    /* Texts change only under store_lock, which a storing put holds. */
    const char *text = renamed ? doc->canonical : e->texts->canonical;
    pthread_mutex_unlock(&c->lock);

    if (write) {
        if (c->dir && !write_fixture_file(c, e->id, text, error)) {
            pthread_mutex_unlock(&c->store_lock);
            wp_fixture_use failed = {.handle = {e, NULL}};
            wd_cache_release(c, &failed);
            wp_fixture_doc_release(doc);
            return false;
        }
        pthread_mutex_lock(&c->lock);
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
    return ready(c, e, answered, use, error);
}

bool wd_cache_use(wd_cache *c, const char *id, wp_fixture_use *use, wp_error *error)
{
    pthread_mutex_lock(&c->lock);
    entry *e = find(c, id);
    if (!e || !e->stored) {
        pthread_mutex_unlock(&c->lock);
        wp_error_set(error, WP_NO_FIXTURE, "", "no stored fixture has the id %s", id);
        return false;
    }
    e->refs++;
    pthread_mutex_unlock(&c->lock);
    return ready(c, e, NULL, use, error);
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

void wd_cache_release(wd_cache *c, wp_fixture_use *use)
{
    entry *e = use->handle[0];
    pthread_mutex_lock(&c->lock);
    texts_drop(use->handle[1]);
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

bool wd_cache_delete(wd_cache *c, const char *id, wp_error *error)
{
    pthread_mutex_lock(&c->store_lock);
    pthread_mutex_lock(&c->lock);
    entry *e = find(c, id);
    bool stored = e && e->stored;
    pthread_mutex_unlock(&c->lock);
    bool ok = false;
    if (!stored)
        wp_error_set(error, WP_NO_FIXTURE, "", "no stored fixture has the id %s", id);
    else if (!c->dir || remove_fixture_file(c, id, error)) {
        /* It stays as a cached fixture until its derived data is evicted. */
        pthread_mutex_lock(&c->lock);
        e->stored = false;
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

cJSON *wd_cache_list(wd_cache *c)
{
    cJSON *result = cJSON_CreateObject();
    cJSON *list = cJSON_AddArrayToObject(result, "fixtures");
    if (!list) {
        cJSON_Delete(result);
        return NULL;
    }
    pthread_mutex_lock(&c->lock);
    entry **sorted = malloc((c->count ? c->count : 1) * sizeof *sorted);
    size_t n = 0;
    for (size_t b = 0; sorted && b < c->bucket_count; b++)
        for (entry *e = c->buckets[b]; e; e = e->next)
            if (e->stored)
                sorted[n++] = e;
    if (sorted)
        qsort(sorted, n, sizeof *sorted, compare_ids);
    bool ok = sorted != NULL;
    for (size_t i = 0; ok && i < n; i++) {
        cJSON *item = cJSON_CreateObject();
        ok = item && cJSON_AddStringToObject(item, "id", sorted[i]->id) &&
             cJSON_AddStringToObject(item, "name", sorted[i]->texts->name) &&
             cJSON_AddNumberToObject(item, "fixels", sorted[i]->fixture->fixel_count);
        if (item)
            cJSON_AddItemToArray(list, item);
    }
    pthread_mutex_unlock(&c->lock);
    free(sorted);
    if (!ok) {
        cJSON_Delete(result);
        return NULL;
    }
    return result;
}

uint64_t wd_cache_serial(const wp_fixture_use *use)
{
    /* Stable while the fixture is in use: its analysis cannot be evicted. */
    return ((const entry *)use->handle[0])->serial;
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
    stats->derived_bytes = c->derived_bytes;
    stats->derived_limit = c->derived_limit;
    pthread_mutex_unlock(&c->lock);
}
