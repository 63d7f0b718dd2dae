/* wd_host.c -- the wp_host of one thread: the shared fixture cache, that
 * thread's GLPK environment and warm LP sets, and the task in hand's stop. */
#include "wd_host.h"

#include <stdlib.h>
#include <string.h>

/* Warm LP sets of one fixture's derived data, in one thread. */
typedef struct lp_entry {
    uint64_t serial;       /* wd_cache_serial of the analysis they were built on */
    uint64_t last_used;
    wr_lp_set *goal, *strong;
} lp_entry;

/* A thread keeps warm LPs for this many fixtures, least recently used out. */
#define LP_ENTRIES 16

struct wd_thread_host {
    wp_host host;
    wd_cache *cache;
    wd_stats *stats;
    wr_lp_env *solver;
    lp_entry entries[LP_ENTRIES];
    uint64_t clock;
    wr_stop stop;         /* the task in hand's: host.stop points here */
};

static bool host_adopt(void *self, wp_fixture_doc *doc, bool store, wp_fixture_use *use,
                       wp_host_failure *failure)
{
    return wd_cache_adopt(((wd_thread_host *)self)->cache, doc, store, use, failure);
}

static bool host_use(void *self, const char *id, wp_fixture_use *use, wp_host_failure *failure)
{
    return wd_cache_use(((wd_thread_host *)self)->cache, id, use, failure);
}

static bool host_use_written(void *self, const char *key, wp_fixture_use *use)
{
    return wd_cache_use_written(((wd_thread_host *)self)->cache, key, use);
}

static size_t host_use_text(void *self, const char *text, size_t length, wp_fixture_use *use)
{
    return wd_cache_use_text(((wd_thread_host *)self)->cache, text, length, use);
}

static void host_release(void *self, wp_fixture_use *use)
{
    wd_cache_release(((wd_thread_host *)self)->cache, use);
}

static bool host_delete(void *self, const char *id, wp_host_failure *failure)
{
    return wd_cache_delete(((wd_thread_host *)self)->cache, id, failure);
}

static int host_use_ready(void *self, const char *id, wp_fixture_use *use)
{
    return wd_cache_use_ready(((wd_thread_host *)self)->cache, id, use);
}

static bool host_list(void *self, wp_fixture_listing *listing, wp_host_failure *failure)
{
    if (wd_cache_list(((wd_thread_host *)self)->cache, listing))
        return true;
    *failure = (wp_host_failure){WP_HOST_NO_MEMORY, "out of memory"};
    return false;
}

/* The daemon's counters and the cache's figures, as data: proto writes
 * the JSON. */
static bool host_state(void *self, wp_server_state *state, wp_host_failure *failure)
{
    (void)failure;
    wd_thread_host *thread = self;
    wd_cache_stats cache;
    wd_cache_stats_get(thread->cache, &cache);
    const wd_stats *s = thread->stats;
    *state = (wp_server_state){
        .uptime_s = (double)(time(NULL) - s->started),
        .fixtures = cache.stored,
        .cached = cache.cached,
        .cache_bytes = cache.derived_bytes,
        .cache_limit_bytes = cache.derived_limit,
        .threads = s->threads,
        .clients = atomic_load(&s->clients),
        .refused = atomic_load(&s->refused),
        .denied = atomic_load(&s->denied),
        .requests = atomic_load(&s->requests),
        .errors = atomic_load(&s->errors),
    };
    return true;
}

static void entry_clear(lp_entry *entry)
{
    wr_lp_set_free(entry->goal);
    wr_lp_set_free(entry->strong);
    memset(entry, 0, sizeof *entry);
}

static wr_status host_lp_sets(void *self, wp_fixture_use *use, wr_lp_set **goal,
                              wr_lp_set **strong)
{
    wd_thread_host *thread = self;
    uint64_t serial = wd_cache_serial(use);
    lp_entry *entry = &thread->entries[0];
    for (int i = 0; i < LP_ENTRIES; i++) {
        if (thread->entries[i].serial == serial && thread->entries[i].goal) {
            entry = &thread->entries[i];
            break;
        }
        if (thread->entries[i].last_used < entry->last_used)
            entry = &thread->entries[i];
    }
    if (entry->serial != serial || !entry->goal) {
        /* An entry of stale derived data only ever gets freed: its sets are
         * never used again. */
        entry_clear(entry);
        wr_status status =
            wr_analysis_lp_sets(use->analysis, thread->solver, &entry->goal, &entry->strong);
        if (status != WR_OK)
            return status;
        entry->serial = serial;
    }
    entry->last_used = ++thread->clock;
    *goal = entry->goal;
    *strong = entry->strong;
    return WR_OK;
}

static wr_lp_env *host_lp_env(void *self) { return ((wd_thread_host *)self)->solver; }

wd_thread_host *wd_thread_host_new(wd_cache *cache, wd_stats *stats)
{
    wd_thread_host *thread = calloc(1, sizeof *thread);
    if (!thread)
        return NULL;
    if (wr_lp_env_new(&thread->solver) != WR_OK) {
        free(thread);
        return NULL;
    }
    /* A test hook (wrenchd(8), ENVIRONMENT): make this thread's GLPK fail
     * fatally after N solves, to see the failure answered, not fatal. */
    const char *failure = getenv("WRENCHD_TEST_GLPK_FAILURE");
    if (failure && *failure)
        wr_lp_env_inject_failure(thread->solver, atoi(failure));
    thread->cache = cache;
    thread->stats = stats;
    thread->host = (wp_host){.self = thread,
                             .fixture_adopt = host_adopt,
                             .fixture_use = host_use,
                             .fixture_use_written = host_use_written,
                             .fixture_use_text = host_use_text,
                             .fixture_use_ready = host_use_ready,
                             .fixture_release = host_release,
                             .fixture_delete = host_delete,
                             .fixture_list = host_list,
                             .state = host_state,
                             .lp_sets = host_lp_sets,
                             .lp_env = host_lp_env};
    return thread;
}

const wp_host *wd_thread_host_wp(wd_thread_host *thread) { return &thread->host; }

void wd_thread_host_stop(wd_thread_host *thread, const wr_stop *stop)
{
    if (stop) {
        thread->stop = *stop;
        thread->host.stop = &thread->stop;
    } else {
        thread->host.stop = NULL;
    }
}

void wd_thread_host_free(wd_thread_host *thread)
{
    if (!thread)
        return;
    for (int i = 0; i < LP_ENTRIES; i++)
        entry_clear(&thread->entries[i]);
    wr_lp_env_free(thread->solver);
    free(thread);
}
