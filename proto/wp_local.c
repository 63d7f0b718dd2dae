/* wp_local.c -- an in-process wp_host: each request's inline fixture is
 * validated, analysed, used and freed; nothing is kept between requests. */
#include "wp_local.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

struct wp_local {
    wp_host host;
    wr_lp_env *solver;
};

/* What one request holds: the fixture, its analysis, its LPs. */
typedef struct held {
    wp_fixture_doc doc;
    wr_analysis *analysis;
    wr_lp_set *goal, *strong;
} held;

static bool fail(wp_host_failure *failure, wp_host_status status, const char *reason)
{
    failure->status = status;
    snprintf(failure->reason, sizeof failure->reason, "%s", reason);
    return false;
}

static bool no_store(wp_host_failure *failure)
{
    return fail(failure, WP_HOST_NO_FIXTURE,
                "there are no stored fixtures in process: give the fixture inline, or ask "
                "the daemon");
}

static bool local_adopt(void *self, wp_fixture_doc *doc, bool store, wp_fixture_use *use,
                        wp_host_failure *failure)
{
    (void)self;
    if (store) {
        wp_fixture_doc_release(doc);
        return fail(failure, WP_HOST_STORAGE, "storing fixtures needs the daemon");
    }
    held *h = calloc(1, sizeof *h);
    if (!h || wr_analysis_new(doc->fixture, &h->analysis) != WR_OK) {
        free(h);
        wp_fixture_doc_release(doc);
        return fail(failure, WP_HOST_NO_MEMORY, "out of memory");
    }
    wp_fixture_doc_move(&h->doc, doc);
    /* The analysis borrows the fixture: both live in `h` until release. */
    *use = (wp_fixture_use){h->doc.id,       h->doc.name, h->doc.canonical, h->doc.fixture,
                            h->analysis,     {h, NULL}};
    return true;
}

static bool local_use(void *self, const char *id, wp_fixture_use *use,
                      wp_host_failure *failure)
{
    (void)self;
    (void)id;
    (void)use;
    return no_store(failure);
}

static void local_release(void *self, wp_fixture_use *use)
{
    (void)self;
    held *h = use->handle[0];
    wr_lp_set_free(h->goal);
    wr_lp_set_free(h->strong);
    wr_analysis_free(h->analysis);
    wp_fixture_doc_release(&h->doc);
    free(h);
    memset(use, 0, sizeof *use);
}

static bool local_delete(void *self, const char *id, wp_host_failure *failure)
{
    (void)self;
    (void)id;
    return no_store(failure);
}

static bool local_list(void *self, wp_fixture_listing *listing, wp_host_failure *failure)
{
    (void)self;
    (void)listing;
    return no_store(failure);
}

static bool local_state(void *self, wp_server_state *state, wp_host_failure *failure)
{
    (void)self;
    (void)state;
    return fail(failure, WP_HOST_UNSUPPORTED, "server.status needs the daemon");
}

static wr_status local_lp_sets(void *self, wp_fixture_use *use, wr_lp_set **goal,
                               wr_lp_set **strong)
{
    wp_local *local = self;
    held *h = use->handle[0];
    wr_status status =
        h->goal ? WR_OK : wr_analysis_lp_sets(h->analysis, local->solver, &h->goal, &h->strong);
    if (status != WR_OK)
        return status;
    *goal = h->goal;
    *strong = h->strong;
    return WR_OK;
}

static wr_lp_env *local_lp_env(void *self) { return ((wp_local *)self)->solver; }

wp_local *wp_local_new(void)
{
    wp_local *local = calloc(1, sizeof *local);
    if (!local)
        return NULL;
    if (wr_lp_env_new(&local->solver) != WR_OK) {
        free(local);
        return NULL;
    }
    local->host = (wp_host){.self = local,
                            .fixture_adopt = local_adopt,
                            .fixture_use = local_use,
                            .fixture_release = local_release,
                            .fixture_delete = local_delete,
                            .fixture_list = local_list,
                            .state = local_state,
                            .lp_sets = local_lp_sets,
                            .lp_env = local_lp_env};
    return local;
}

const wp_host *wp_local_host(wp_local *local) { return &local->host; }

void wp_local_free(wp_local *local)
{
    if (!local)
        return;
    wr_lp_env_free(local->solver);
    free(local);
}
