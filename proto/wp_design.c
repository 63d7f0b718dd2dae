/* wp_design.c -- fixture.design: parameters, progress, the answer. */
#include "wp_design.h"
#include "wp_fixture.h"

#include <math.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

/* Progress notifications at most this often (and at the start and the end
 * of the search). */
#define PROGRESS_INTERVAL_S 0.25

static const char *const OBJECTIVES[] = {"margin", "region", "gravity"};

struct wp_design_stream {
    /* Steps (one thread at a time) and wp_design_work (any number of
     * threads beside them) share the job: claims and merges under it. */
    pthread_mutex_t lock;
    wr_fixture *body;
    wr_site *sites;
    int site_count;
    wr_design_spec spec;
    wr_design_job *job;
    uint64_t candidates;  /* of every shard */
    bool progress;
    bool opened;          /* the response is open */
    bool search_reported; /* the notification at the search's end is sent */
    double last_report;   /* monotonic seconds; < 0 before the first */
    wr_status failure;    /* a failure seen in a shared step, said in the next */
    /* wp_design_parallel said yes since the last step began: the host may
     * have helpers in wp_design_work until the next step returns, even if
     * they have claimed every chunk by the time it begins.  Only the
     * steps' thread reads and writes it. */
    bool forked;
    /* A lattice: its designs are enumerated first, then they are the
     * candidates (their fixels the sites, three each). */
    wr_lattice_job *lattice;
    const wr_lattice_design *poses; /* the lattice's designs, once enumerated */
    int (*listed)[WR_MAX_FIXELS];
    const char *source;   /* the field giving the candidates: for refusals */
    uint64_t max_candidates; /* wp_limits' */
    /* params.deadline_s: the monotonic second after which the search takes
     * no more candidates and the answer is the best so far, "partial"
     * (0: none); `cut` once it has. */
    double deadline;
    bool cut;
};

static double now_s(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + t.tv_nsec * 1e-9;
}

/* A whole number in [lo, hi] at params.key (default kept when absent). */
static bool read_count(const cJSON *params, const char *key, double lo, double hi, int *out,
                       wp_error *error)
{
    double value;
    bool present = false;
    if (!wp_member_number(params, "params", key, false, &value, &present, error))
        return false;
    if (!present)
        return true;
    if (value != floor(value) || value < lo || value > hi) {
        char field[WP_FIELD_MAX];
        wp_path_key(field, "params", key);
        wp_error_set(error, WP_INVALID_PARAMS, field, "must be a whole number from %g to %g, got %g",
                     lo, hi, value);
        return false;
    }
    *out = (int)value;
    return true;
}

/* A site's fault, from wr_site_new's "fixels[0]..." to "params.sites[i]...". */
static void site_error(wp_error *error, size_t index, const wr_error *invalid)
{
    char prefix[WP_FIELD_MAX], field[WP_FIELD_MAX];
    wp_path_index(prefix, "params.sites", index);
    const char *rest = invalid->field;
    if (strncmp(rest, "fixels[0]", 9) == 0)
        rest += 9;
    else
        rest = "";
    snprintf(field, sizeof field, "%s%s", prefix, rest);
    wp_error_set(error, WP_INVALID_PARAMS, field, "%s", invalid->reason);
}

static const char *const SITE_FIELDS[] = {"at", "normal", NULL};

static bool read_sites(const cJSON *list, wp_design_stream *s, wp_error *error)
{
    if (!cJSON_IsArray(list)) {
        wp_error_set(error, WP_INVALID_PARAMS, "params.sites",
                     "must be an array of {\"at\": [x, y], \"normal\"?: [nx, ny]}, not %s",
                     wp_type_name(list));
        return false;
    }
    size_t count = (size_t)cJSON_GetArraySize(list);
    if (count > WR_DESIGN_MAX_SITES) {
        wp_error_set(error, WP_INVALID_PARAMS, "params.sites", "at most %d sites, %zu given",
                     WR_DESIGN_MAX_SITES, count);
        return false;
    }
    s->sites = calloc(count ? count : 1, sizeof *s->sites);
    if (!s->sites) {
        wp_error_set(error, WP_INTERNAL, "", "out of memory");
        return false;
    }
    size_t i = 0;
    for (const cJSON *item = list->child; item; item = item->next, i++) {
        char field[WP_FIELD_MAX];
        wp_path_index(field, "params.sites", i);
        double at[2], normal[2];
        bool has_normal = false;
        if (!wp_check_object(item, field, SITE_FIELDS, error) ||
            !wp_member_vector2(item, field, "at", true, at, NULL, error) ||
            !wp_member_vector2(item, field, "normal", false, normal, &has_normal, error))
            return false;
        wr_error invalid;
        wr_status status =
            wr_site_new(s->body, at, has_normal ? normal : NULL, &s->sites[i], &invalid);
        if (status != WR_OK) {
            site_error(error, i, &invalid);
            return false;
        }
    }
    s->site_count = (int)count;
    return true;
}

static const char *const LATTICE_FIELDS[] = {"pitch", "peg_radius", "extent", NULL};

/* {"pitch", "peg_radius", "extent": [nx, ny]}: the lattice job, made here. */
static bool read_lattice(const cJSON *params, const cJSON *json, wp_design_stream *s,
                         wp_error *error)
{
    const char *path = "params.lattice";
    wr_lattice lattice;
    double extent[2];
    if (!wp_check_object(json, path, LATTICE_FIELDS, error) ||
        !wp_member_number(json, path, "pitch", true, &lattice.pitch, NULL, error) ||
        !wp_member_number(json, path, "peg_radius", true, &lattice.peg_radius, NULL, error) ||
        !wp_member_vector2(json, path, "extent", true, extent, NULL, error))
        return false;
    for (int k = 0; k < 2; k++) {
        if (extent[k] != floor(extent[k]) || extent[k] < 1 || extent[k] > WR_LATTICE_MAX_EXTENT) {
            char field[WP_FIELD_MAX];
            wp_path_index(field, "params.lattice.extent", (size_t)k);
            wp_error_set(error, WP_INVALID_PARAMS, field,
                         "must be a whole number of holes from 1 to %d, got %g",
                         WR_LATTICE_MAX_EXTENT, extent[k]);
            return false;
        }
        lattice.extent[k] = (int)extent[k];
    }
    if (cJSON_GetObjectItemCaseSensitive(params, "fixels") && s->spec.fixel_count != 3) {
        wp_error_set(error, WP_INVALID_PARAMS, "params.fixels",
                     "a lattice design has 3 pegs: 3 fixels, not %d", s->spec.fixel_count);
        return false;
    }
    s->spec.fixel_count = 3;
    wr_error invalid;
    wr_status status = wr_lattice_job_new(s->body, &lattice, &s->lattice, &invalid);
    if (status != WR_OK) {
        char field[WP_FIELD_MAX];
        if (invalid.field[0])
            wp_path_key(field, path, invalid.field);
        else
            snprintf(field, sizeof field, "%s", status == WR_INVALID ? "params.body.shape" : "");
        wp_error_set(error, status == WR_INVALID ? WP_INVALID_PARAMS : WP_INTERNAL, field, "%s",
                     invalid.reason);
        return false;
    }
    return true;
}

static bool read_params(const cJSON *params, wp_design_stream *s, wp_error *error)
{
    wr_design_spec *spec = &s->spec;
    spec->fixel_count = 3;
    spec->top = 10;
    spec->shard_count = 1;
    spec->objective = WR_OBJECTIVE_MARGIN;
    if (!wp_body_read(params, "params", &s->body, error))
        return false;
    spec->body = s->body;
    const cJSON *friction = cJSON_GetObjectItemCaseSensitive(params, "friction");
    if (!friction) {
        wp_error_set(error, WP_INVALID_PARAMS, "params.friction", "required");
        return false;
    }
    if (!wp_friction_read(friction, "params.friction", &spec->friction, error) ||
        !read_count(params, "fixels", 1, WR_MAX_FIXELS, &spec->fixel_count, error) ||
        !read_count(params, "top", 1, WR_DESIGN_MAX_TOP, &spec->top, error))
        return false;
    const char *objective = NULL;
    if (!wp_member_string(params, "params", "objective", false, &objective, error))
        return false;
    if (objective) {
        int found = -1;
        for (int i = 0; i < 3; i++)
            if (strcmp(objective, OBJECTIVES[i]) == 0)
                found = i;
        if (found < 0) {
            wp_error_set(error, WP_INVALID_PARAMS, "params.objective",
                         "must be \"margin\", \"region\" or \"gravity\"");
            return false;
        }
        spec->objective = (wr_objective)found;
    }
    bool present;
    if (!wp_member_number(params, "params", "finger_friction", false, &spec->finger.friction,
                          NULL, error) ||
        !wp_member_number(params, "params", "finger_radius", false, &spec->finger.radius, NULL,
                          error))
        return false;
    if (spec->finger.friction < 0 || spec->finger.radius < 0) {
        wp_error_set(error, WP_INVALID_PARAMS,
                     spec->finger.friction < 0 ? "params.finger_friction" : "params.finger_radius",
                     "must not be negative");
        return false;
    }
    const cJSON *progress = cJSON_GetObjectItemCaseSensitive(params, "progress");
    if (progress && !cJSON_IsBool(progress)) {
        wp_error_set(error, WP_INVALID_PARAMS, "params.progress", "must be true or false, not %s",
                     wp_type_name(progress));
        return false;
    }
    s->progress = progress && cJSON_IsTrue(progress);
    double deadline_s = 0;
    if (!wp_member_number(params, "params", "deadline_s", false, &deadline_s, &present, error))
        return false;
    if (present && !(deadline_s > 0 && deadline_s <= 1e9)) {
        wp_error_set(error, WP_INVALID_PARAMS, "params.deadline_s",
                     "must be a number of seconds above 0 (at most 1e9), got %g", deadline_s);
        return false;
    }
    s->deadline = present ? now_s() + deadline_s : 0;
    const cJSON *shard = cJSON_GetObjectItemCaseSensitive(params, "shard");
    if (shard) {
        double pair[2];
        if (!cJSON_IsArray(shard) || cJSON_GetArraySize(shard) != 2) {
            wp_error_set(error, WP_INVALID_PARAMS, "params.shard",
                         "must be [i, n]: this request evaluates shard i of n, 0 <= i < n");
            return false;
        }
        if (!wp_vector2(shard, "params.shard", pair, error))
            return false;
        if (pair[1] != floor(pair[1]) || pair[1] < 1 || pair[1] > 1e6) {
            wp_error_set(error, WP_INVALID_PARAMS, "params.shard[1]",
                         "must be a whole number of shards from 1 to 1000000, got %g", pair[1]);
            return false;
        }
        if (pair[0] != floor(pair[0]) || pair[0] < 0 || pair[0] >= pair[1]) {
            wp_error_set(error, WP_INVALID_PARAMS, "params.shard[0]",
                         "must be a whole number from 0 to %g, got %g", pair[1] - 1, pair[0]);
            return false;
        }
        spec->shard_index = (int)pair[0];
        spec->shard_count = (int)pair[1];
    }
    /* Exactly one source of candidate sites. */
    const cJSON *sites = cJSON_GetObjectItemCaseSensitive(params, "sites");
    const cJSON *spacing = cJSON_GetObjectItemCaseSensitive(params, "spacing");
    const cJSON *lattice = cJSON_GetObjectItemCaseSensitive(params, "lattice");
    int sources = (sites != NULL) + (spacing != NULL) + (lattice != NULL);
    if (sources != 1) {
        wp_error_set(error, WP_INVALID_PARAMS, "params",
                     sources ? "give only one of sites, spacing and lattice"
                             : "candidate sites are required: sites, spacing or lattice");
        return false;
    }
    s->source = lattice ? "params.lattice" : sites ? "params.sites" : "params.spacing";
    if (lattice)
        return read_lattice(params, lattice, s, error);
    if (sites)
        return read_sites(sites, s, error);
    double h;
    if (!wp_member_number(params, "params", "spacing", true, &h, &present, error))
        return false;
    wr_error invalid;
    wr_status status = wr_sites_spaced(s->body, h, &s->sites, &s->site_count, &invalid);
    if (status != WR_OK) {
        wp_error_set(error, status == WR_INVALID ? WP_INVALID_PARAMS : WP_INTERNAL,
                     status == WR_INVALID ? "params.spacing" : "", "%s", invalid.reason);
        return false;
    }
    return true;
}

/* The search's job, over the sites (or the lattice's designs, once
 * enumerated: their contacts are the sites, three a candidate). */
static bool start_search(wp_design_stream *s, wp_error *error)
{
    if (s->lattice) {
        size_t count;
        s->poses = wr_lattice_job_designs(s->lattice, &count);
        s->sites = calloc(3 * count + 1, sizeof *s->sites);
        s->listed = calloc(count + 1, sizeof *s->listed);
        if (!s->sites || !s->listed) {
            wp_error_set(error, WP_INTERNAL, "", "out of memory");
            return false;
        }
        /* Not checked as sites: a contact that a fixture would refuse makes
         * its candidate degenerate, counted as such. */
        for (size_t i = 0; i < count; i++)
            for (int m = 0; m < 3; m++) {
                memcpy(s->sites[3 * i + m].at, s->poses[i].at[m], sizeof s->sites->at);
                memcpy(s->sites[3 * i + m].normal, s->poses[i].normal[m], sizeof s->sites->normal);
                s->listed[i][m] = (int)(3 * i) + m;
            }
        s->site_count = (int)(3 * count);
        s->spec.candidates = (const int (*)[WR_MAX_FIXELS])s->listed;
        s->spec.candidate_count = count;
    }
    s->spec.sites = s->sites;
    s->spec.site_count = s->site_count;
    s->candidates = s->lattice ? s->spec.candidate_count
                               : wr_design_candidates(s->site_count, s->spec.fixel_count);
    /* The cap counts this request's work: its shard's share. */
    uint64_t share = s->candidates / (uint64_t)(s->spec.shard_count > 0 ? s->spec.shard_count : 1);
    if (s->max_candidates > 0 && share > s->max_candidates) {
        wp_error_set(error, WP_INVALID_PARAMS, s->source,
                     "gives %llu candidates%s; the limit is %llu (--max-candidates): fewer sites "
                     "or fixels, a coarser spacing, or shards",
                     (unsigned long long)share, s->spec.shard_count > 1 ? " in this shard" : "",
                     (unsigned long long)s->max_candidates);
        return false;
    }
    wr_error invalid;
    wr_status status = wr_design_job_new(&s->spec, &s->job, &invalid);
    if (status != WR_OK) {
        char field[WP_FIELD_MAX];
        wp_path_key(field, "params", invalid.field);
        wp_error_set(error, status == WR_INVALID ? WP_INVALID_PARAMS : WP_INTERNAL,
                     status == WR_INVALID ? field : "", "%s", invalid.reason);
        return false;
    }
    return true;
}

wp_design_stream *wp_design_begin(wp_call *call)
{
    wp_design_stream *s = calloc(1, sizeof *s);
    if (!s) {
        wp_error_set(call->error, WP_INTERNAL, "", "out of memory");
        return NULL;
    }
    s->last_report = -1;
    s->max_candidates = call->limits->max_candidates;
    pthread_mutex_init(&s->lock, NULL);
    if (!read_params(call->params, s, call->error)) {
        wp_design_free(s);
        return NULL;
    }
    if (s->progress && !wp_call_may_notify(call)) {
        /* A batch's answer is one line: nothing can come before it. */
        s->progress = false;
    }
    if (!s->lattice && !start_search(s, call->error)) {
        wp_design_free(s);
        return NULL;
    }
    return s;
}

/* A count, exactly: above 2^53 a double would round it. */
static void write_count(wp_buffer *out, uint64_t n)
{
    char text[24];
    snprintf(text, sizeof text, "%llu", (unsigned long long)n);
    wp_buffer_puts(out, text);
}

static void write_pair(wp_buffer *out, const double v[2])
{
    WP_BUFFER_LITERAL(out, "[");
    wp_buffer_number(out, v[0] + 0.0);
    WP_BUFFER_LITERAL(out, ",");
    wp_buffer_number(out, v[1] + 0.0);
    WP_BUFFER_LITERAL(out, "]");
}

static void write_progress(wp_design_stream *s, wp_call *call, wp_buffer *out)
{
    uint64_t done = 0, total = 0;
    bool has_best = false;
    double best = 0;
    /* Helpers may be merging meanwhile. */
    pthread_mutex_lock(&s->lock);
    if (s->job) {
        wr_design_job_progress(s->job, &done, &total, &has_best, &best);
    } else {
        size_t pairs, of;
        wr_lattice_job_progress(s->lattice, &pairs, &of);
        done = pairs;
        total = of;
    }
    pthread_mutex_unlock(&s->lock);
    WP_BUFFER_LITERAL(out, "{\"jsonrpc\":\"2.0\",\"method\":\"design.progress\",\"params\":{\"id\":");
    wp_buffer_puts(out, wp_call_id_text(call));
    /* The stage: "poses" while a lattice's designs are enumerated (done and
     * total count its hole pairs), then "candidates". */
    wp_buffer_puts(out, s->job ? ",\"stage\":\"candidates\"" : ",\"stage\":\"poses\"");
    WP_BUFFER_LITERAL(out, ",\"done\":");
    write_count(out, done);
    WP_BUFFER_LITERAL(out, ",\"total\":");
    write_count(out, total);
    WP_BUFFER_LITERAL(out, ",\"best\":");
    if (has_best)
        wp_buffer_number(out, best);
    else
        WP_BUFFER_LITERAL(out, "null");
    WP_BUFFER_LITERAL(out, "}}\n");
    s->last_report = now_s();
}

static void write_design(wp_design_stream *s, wp_buffer *out, const wr_design *d, int rank)
{
    wr_fixture fixture;
    wr_design_job_fixture(s->job, d, &fixture);
    WP_BUFFER_LITERAL(out, "{\"rank\":");
    wp_buffer_number(out, rank);
    WP_BUFFER_LITERAL(out, ",\"candidate\":");
    write_count(out, d->candidate);
    if (!s->poses) {
        WP_BUFFER_LITERAL(out, ",\"sites\":[");
        for (int i = 0; i < s->spec.fixel_count; i++) {
            if (i)
                WP_BUFFER_LITERAL(out, ",");
            wp_buffer_number(out, (double)d->sites[i]);
        }
        WP_BUFFER_LITERAL(out, "]");
    }
    WP_BUFFER_LITERAL(out, ",\"fixels\":[");
    for (int i = 0; i < fixture.fixel_count; i++) {
        wp_buffer_puts(out, i ? ",{\"at\":" : "{\"at\":");
        write_pair(out, fixture.fixels[i].at);
        WP_BUFFER_LITERAL(out, ",\"normal\":");
        write_pair(out, fixture.fixels[i].normal);
        WP_BUFFER_LITERAL(out, "}");
    }
    WP_BUFFER_LITERAL(out, "]");
    if (s->poses) {
        const wr_lattice_design *pose = &s->poses[d->candidate];
        WP_BUFFER_LITERAL(out, ",\"pegs\":[");
        for (int m = 0; m < 3; m++) {
            double hole[2] = {pose->holes[m][0], pose->holes[m][1]};
            if (m)
                WP_BUFFER_LITERAL(out, ",");
            write_pair(out, hole);
        }
        WP_BUFFER_LITERAL(out, "],\"pose\":[");
        wp_buffer_number(out, pose->pose[0] + 0.0);
        WP_BUFFER_LITERAL(out, ",");
        wp_buffer_number(out, pose->pose[1] + 0.0);
        WP_BUFFER_LITERAL(out, ",");
        wp_buffer_number(out, pose->pose[2] * 180 / 3.14159265358979323846 + 0.0);
        WP_BUFFER_LITERAL(out, "]");
    }
    WP_BUFFER_LITERAL(out, ",\"best_push\":");
    const wr_best_push *push = &d->best_push;
    if (push->found) {
        WP_BUFFER_LITERAL(out, "{\"at\":");
        write_pair(out, push->at);
        WP_BUFFER_LITERAL(out, ",\"direction\":");
        write_pair(out, push->direction);
        WP_BUFFER_LITERAL(out, ",\"margin\":");
        wp_buffer_number(out, push->margin);
        if (fixture.shape == WR_SHAPE_OUTLINE) {
            size_t loop, segment;
            wr_push_edge_place(&fixture, push->edge, &loop, &segment);
            WP_BUFFER_LITERAL(out, ",\"loop\":");
            wp_buffer_number(out, (double)loop);
            WP_BUFFER_LITERAL(out, ",\"segment\":");
            wp_buffer_number(out, (double)segment);
        } else {
            WP_BUFFER_LITERAL(out, ",\"edge\":");
            wp_buffer_number(out, push->edge);
        }
        WP_BUFFER_LITERAL(out, ",\"t\":");
        wp_buffer_number(out, push->t);
        WP_BUFFER_LITERAL(out, "}");
    } else {
        WP_BUFFER_LITERAL(out, "null");
    }
    WP_BUFFER_LITERAL(out, ",\"goal_length\":");
    wp_buffer_number(out, d->goal_length);
    WP_BUFFER_LITERAL(out, ",\"both_length\":");
    wp_buffer_number(out, d->both_length);
    WP_BUFFER_LITERAL(out, ",\"gravity_goal_deg\":");
    wp_buffer_number(out, d->gravity_goal_deg);
    WP_BUFFER_LITERAL(out, ",\"critical_mu\":");
    if (d->has_critical)
        wp_buffer_number(out, d->critical_mu);
    else
        WP_BUFFER_LITERAL(out, "null");
    WP_BUFFER_LITERAL(out, ",\"score\":");
    wp_buffer_number(out, d->score);
    WP_BUFFER_LITERAL(out, "}");
}

static void write_answer(wp_design_stream *s, wp_buffer *out)
{
    int count;
    const wr_design *designs = wr_design_job_designs(s->job, &count);
    WP_BUFFER_LITERAL(out, "{\"designs\":[");
    for (int i = 0; i < count; i++) {
        if (i)
            WP_BUFFER_LITERAL(out, ",");
        write_design(s, out, &designs[i], i + 1);
    }
    const wr_design_counts *c = wr_design_job_counts(s->job);
    WP_BUFFER_LITERAL(out, "],");
    if (s->cut && c->examined < wr_design_job_total(s->job))
        WP_BUFFER_LITERAL(out, "\"partial\":true,");
    WP_BUFFER_LITERAL(out, "\"counts\":{\"candidates\":");
    write_count(out, s->candidates);
    WP_BUFFER_LITERAL(out, ",\"examined\":");
    write_count(out, c->examined);
    WP_BUFFER_LITERAL(out, ",\"degenerate\":");
    write_count(out, c->degenerate);
    WP_BUFFER_LITERAL(out, ",\"unpinned\":");
    write_count(out, c->unpinned);
    WP_BUFFER_LITERAL(out, ",\"no_seating_push\":");
    write_count(out, c->no_seating_push);
    if (s->poses) {
        WP_BUFFER_LITERAL(out, "},\"poses\":");
        write_count(out, s->spec.candidate_count);
    } else {
        WP_BUFFER_LITERAL(out, "},\"sites\":");
        wp_buffer_number(out, s->site_count);
    }
    WP_BUFFER_LITERAL(out, ",\"objective\":\"");
    wp_buffer_puts(out, OBJECTIVES[s->spec.objective]);
    WP_BUFFER_LITERAL(out, "\",\"shard\":[");
    wp_buffer_number(out, s->spec.shard_index);
    WP_BUFFER_LITERAL(out, ",");
    wp_buffer_number(out, s->spec.shard_count);
    WP_BUFFER_LITERAL(out, "]}");
}

/* Claim a chunk, run it outside the lock, merge it.  False when none was
 * left; WR_OK or the failure in *status. */
static bool run_chunk(wp_design_stream *s, const wr_stop *stop, unsigned long *used,
                      wr_status *status)
{
    uint64_t first, count;
    double threshold;
    pthread_mutex_lock(&s->lock);
    bool claimed = wr_design_job_claim(s->job, &first, &count, &threshold);
    pthread_mutex_unlock(&s->lock);
    *status = WR_OK;
    if (!claimed)
        return false;
    wr_design_chunk chunk;
    *status = wr_design_chunk_run(s->job, first, count, threshold, stop, &chunk, used);
    pthread_mutex_lock(&s->lock);
    if (*status == WR_OK)
        wr_design_job_merge(s->job, &chunk);
    else
        wr_design_job_abandon(s->job);
    pthread_mutex_unlock(&s->lock);
    wr_design_chunk_release(&chunk);
    return true;
}

/* A lattice's chunk of hole pairs, as run_chunk does the search's. */
static bool run_lattice_chunk(wp_design_stream *s, const wr_stop *stop, unsigned long *used,
                              wr_status *status)
{
    size_t first, count;
    pthread_mutex_lock(&s->lock);
    bool claimed = wr_lattice_job_claim(s->lattice, &first, &count);
    pthread_mutex_unlock(&s->lock);
    *status = WR_OK;
    if (!claimed)
        return false;
    wr_lattice_chunk chunk;
    *status = wr_lattice_chunk_run(s->lattice, first, count, stop, &chunk, used);
    pthread_mutex_lock(&s->lock);
    if (*status == WR_OK)
        *status = wr_lattice_job_merge(s->lattice, &chunk);
    else
        wr_lattice_job_abandon(s->lattice);
    pthread_mutex_unlock(&s->lock);
    return true;
}

/* The next chunk of whichever stage is on: the lattice's poses, then the
 * search's candidates. */
static bool run_some(wp_design_stream *s, const wr_stop *stop, unsigned long *used,
                     wr_status *status)
{
    return s->job ? run_chunk(s, stop, used, status) : run_lattice_chunk(s, stop, used, status);
}

/* Keep the first failure, for the step that can say it (helpers, or a
 * step that shares, cannot end the answer). */
static void note_failure(wp_design_stream *s, wr_status status)
{
    pthread_mutex_lock(&s->lock);
    if (s->failure == WR_OK)
        s->failure = status;
    pthread_mutex_unlock(&s->lock);
}

/* Are chunks left to claim? */
static bool claimable(wp_design_stream *s)
{
    pthread_mutex_lock(&s->lock);
    bool more = s->job ? wr_design_job_claimable(s->job) : wr_lattice_job_claimable(s->lattice);
    pthread_mutex_unlock(&s->lock);
    return more;
}

bool wp_design_parallel(wp_design_stream *s)
{
    /* Past the deadline, the next step shares nothing, so that it may cut
     * the search (wp_design_step). */
    bool more = claimable(s) && !(s->deadline > 0 && !s->cut && now_s() >= s->deadline);
    s->forked = s->forked || more;
    return more;
}

bool wp_design_work(wp_design_stream *s, const wp_host *host)
{
    unsigned long used = 0;
    wr_status status;
    /* s->job is set only by a step that shares nothing (below): it does
     * not change while this runs. */
    bool ran = run_some(s, host->stop, &used, &status);
    if (ran && status != WR_OK)
        note_failure(s, status); /* the step says it, as it is */
    return ran && status == WR_OK;
}

wp_step wp_design_step(wp_design_stream *s, wp_call *call, wp_buffer *out, unsigned long budget,
                       unsigned long *used)
{
    /* Helpers may be in wp_design_work until this step returns only if the
     * host was told there was work to share before it began (asking now
     * would miss helpers that have claimed the last chunks meanwhile). */
    bool shared = s->forked;
    s->forked = false;
    pthread_mutex_lock(&s->lock);
    wr_status failure = s->failure;
    pthread_mutex_unlock(&s->lock);
    if (failure != WR_OK) {
        if (shared)
            return WP_STEP_MORE; /* said by a step that shares nothing */
        wp_error_status(call->error, failure, "params", "%s", wr_strerror(failure));
        return WP_STEP_FAILED;
    }
    if (s->progress && s->last_report < 0)
        write_progress(s, call, out);
    if (!s->job) {
        /* A lattice: its designs first, in chunks of hole pairs that
         * helpers share; the search begins in a step that shares nothing,
         * so that no helper is in a chunk when s->job appears. */
        wr_status status = WR_OK;
        unsigned long start = *used;
        while (*used - start < budget && run_some(s, call->host->stop, used, &status) &&
               status == WR_OK)
            continue;
        if (status != WR_OK && shared) {
            note_failure(s, status);
            return WP_STEP_MORE;
        }
        if (status != WR_OK) {
            wp_error_status(call->error, status, "params", "%s", wr_strerror(status));
            return WP_STEP_FAILED;
        }
        bool enumerated = false;
        if (!shared) {
            pthread_mutex_lock(&s->lock);
            status = wr_lattice_job_run(s->lattice, 1, used, call->host->stop, &enumerated);
            pthread_mutex_unlock(&s->lock);
            if (status != WR_OK) {
                wp_error_status(call->error, status, "params", "%s", wr_strerror(status));
                return WP_STEP_FAILED;
            }
            if (enumerated && !start_search(s, call->error))
                return WP_STEP_FAILED;
        }
        if (s->progress && now_s() - s->last_report >= PROGRESS_INTERVAL_S)
            write_progress(s, call, out);
        return out->failed && !shared ? WP_STEP_FAILED : WP_STEP_MORE;
    }
    /* The deadline: no candidate is claimed after it (in a step that
     * shares nothing, so no helper is in a chunk): the chunks running end,
     * then the figures of the best so far make the answer, "partial". */
    if (s->deadline > 0 && !s->cut && !shared && now_s() >= s->deadline) {
        pthread_mutex_lock(&s->lock);
        wr_design_job_cut(s->job);
        pthread_mutex_unlock(&s->lock);
        s->cut = true;
    }
    /* The search: chunks while the budget lasts (helpers may run others
     * meanwhile); then the rest (the designs' figures) by the job itself. */
    wr_status status = WR_OK;
    unsigned long start = *used;
    /* A step that begins with chunks to share never ends the answer:
     * other threads may be in wp_design_work until it returns
     * (wp_streamer.work), so the figures and the answer come in a later
     * step, when the search is over. */
    while (*used - start < budget && run_some(s, call->host->stop, used, &status) &&
           status == WR_OK)
        continue;
    bool done = false;
    if (status == WR_OK && !shared && *used - start < budget) {
        pthread_mutex_lock(&s->lock);
        status = wr_design_job_run(s->job, budget - (*used - start), used, call->host->stop,
                                   &done);
        pthread_mutex_unlock(&s->lock);
    }
    if (status != WR_OK && shared) {
        note_failure(s, status); /* helpers may still be working: end in the next step */
        return WP_STEP_MORE;
    }
    if (status != WR_OK) {
        wp_error_status(call->error, status, "params", "%s", wr_strerror(status));
        return WP_STEP_FAILED;
    }
    uint64_t examined, total;
    bool has_best;
    double best;
    pthread_mutex_lock(&s->lock);
    wr_design_job_progress(s->job, &examined, &total, &has_best, &best);
    pthread_mutex_unlock(&s->lock);
    if (s->progress && !s->search_reported &&
        (examined == total || now_s() - s->last_report >= PROGRESS_INTERVAL_S)) {
        s->search_reported = examined == total;
        write_progress(s, call, out);
    }
    /* A shared step never ends the answer, not even for a piece that did
     * not fit in memory: the caller sees that in the buffer. */
    if (!done)
        return out->failed && !shared ? WP_STEP_FAILED : WP_STEP_MORE;
    wp_call_open_result(call, out);
    write_answer(s, out);
    return out->failed ? WP_STEP_FAILED : WP_STEP_DONE;
}

void wp_design_free(wp_design_stream *s)
{
    if (!s)
        return;
    wr_design_job_free(s->job);
    wr_lattice_job_free(s->lattice);
    free(s->listed);
    free(s->sites);
    wr_fixture_free(s->body);
    pthread_mutex_destroy(&s->lock);
    free(s);
}

size_t wp_design_bytes(const wp_design_stream *s)
{
    size_t poses = 0;
    if (s->lattice)
        wr_lattice_job_designs(s->lattice, &poses);
    return sizeof *s + (size_t)s->site_count * sizeof *s->sites +
           (s->job ? wr_design_job_bytes(s->job) : 0) +
           poses * (sizeof(wr_lattice_design) + sizeof *s->listed);
}
