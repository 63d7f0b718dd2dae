/* wd_cache.h -- the fixture cache: content-addressed fixtures, stored (on
 * disk when there is a state directory, listed) or only cached (inline in
 * a query), each with its derived data (the wr_analysis), which is built on
 * demand and evicted least-recently-used beyond a memory bound.  Stored
 * fixtures themselves are never evicted.  Thread-safe. */
#ifndef WD_CACHE_H
#define WD_CACHE_H

#include "wp_host.h"

#include <stdint.h>

typedef struct wd_cache wd_cache;

/* Create the cache; with a state directory, lock it (DIR/lock, held until
 * wd_cache_free) and load every stored fixture from DIR/fixtures: a file
 * that does not read back, or whose name is not its fixture's id, is logged
 * and skipped; one named by the older id rule is re-keyed.  At most
 * `max_stored` fixtures are stored by puts (all files are loaded, though).
 * NULL with a message in `why` when the directory cannot be used or
 * another daemon holds it. */
wd_cache *wd_cache_new(const char *state_dir, size_t derived_limit, size_t max_stored, char *why,
                       size_t why_size);
void wd_cache_free(wd_cache *cache);

/* --load FILE: put the fixture in the file as fixture.put would (stored,
 * on disk with a state directory; --max-fixtures applies), reading at most
 * `limit` bytes of it.  Logs "loaded FILE as ID (NAME)", or the error. */
bool wd_cache_load_file(wd_cache *cache, const char *path, size_t limit);

/* The wp_host fixture functions (docs in wp_host.h), on the shared cache.
 * A failure is the cache's own status and words (wp_host_failure): proto
 * makes the JSON-RPC error of it. */
bool wd_cache_adopt(wd_cache *cache, wp_fixture_doc *doc, bool store, wp_fixture_use *use,
                    wp_host_failure *failure);
bool wd_cache_use(wd_cache *cache, const char *id, wp_fixture_use *use,
                  wp_host_failure *failure);
/* Hold the fixture adopted from an inline text of written key `key`
 * (stored or only cached), while it is kept: false when it is not. */
bool wd_cache_use_written(wd_cache *cache, const char *key, wp_fixture_use *use);
/* Hold the fixture made from an inline text that begins text[0, length),
 * while it is kept: the kept text's length, or 0 when none is. */
size_t wd_cache_use_text(wd_cache *cache, const char *text, size_t length, wp_fixture_use *use);
/* Hold the stored fixture `id` if its derived data is there (so that using
 * it derives nothing): its number of cones (goal + strong), or -1 with
 * nothing held. */
int wd_cache_use_ready(wd_cache *cache, const char *id, wp_fixture_use *use);
/* The same question without holding it or counting it as a use (which
 * would move it in the least-recently-used order): for inspection. */
int wd_cache_ready(wd_cache *cache, const char *id);
void wd_cache_release(wd_cache *cache, wp_fixture_use *use);
bool wd_cache_delete(wd_cache *cache, const char *id, wp_host_failure *failure);
/* The stored fixtures, by id (false: out of memory, nothing held). */
bool wd_cache_list(wd_cache *cache, wp_fixture_listing *listing);

/* A number naming the derived data of a fixture in use: it changes whenever
 * that data is rebuilt, so per-thread state derived from it (warm LPs) can
 * tell it is stale. */
uint64_t wd_cache_serial(const wp_fixture_use *use);

typedef struct wd_cache_stats {
    size_t stored;         /* fixtures stored */
    size_t cached;         /* fixtures with derived data in memory */
    size_t derived_bytes;  /* memory held by derived data */
    size_t derived_limit;
} wd_cache_stats;
void wd_cache_stats_get(wd_cache *cache, wd_cache_stats *stats);

#endif
