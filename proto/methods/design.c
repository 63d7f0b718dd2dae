/* design.c -- fixture.design: parameters, progress, the answer; the search
 * run a budget at a time (lib/wr_design.h), its chunks shared with helpers. */
#include "common.h"
#include "loads.h"
#include "methods.h"
#include "wp_chunks.h"
#include "wr_job.h"

#include <math.h>
#include <stdio.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

/* Progress notifications at most this often (and at the start and the end
 * of the search). */
#define PROGRESS_INTERVAL_S 0.25

static const char *const OBJECTIVES[] = {"margin", "region", "gravity", "force", "accuracy",
                                         "pareto"};

typedef struct design_state design_state;

/* Chunks made ahead of the one merged, at most, in each stage. */
#define DESIGN_WINDOW 16

struct design_state {
    wr_fixture *body;
    wr_site *sites;
    int site_count;
    wr_design_spec spec;
    bool *push_on;        /* spec.finger.push_on, owned */
    wr_design_job *job;
    uint64_t candidates;  /* of every shard */
    bool progress;
    bool opened;          /* the response is open */
    bool search_reported; /* the notification at the search's end is sent */
    double last_report;   /* monotonic seconds; < 0 before the first */
    /* The engine of each stage (wp_chunks.h); the job's claims and merges
     * are made under its lock, the job's progress read by the steps. */
    wp_chunks *poses_chunks, *search;
    /* After the search: the kept designs' figures, a design a chunk, from
     * design figures_first on (NULL until then). */
    wp_chunks *figures;
    int figures_first;
    /* A lattice: its designs are enumerated first, then they are the
     * candidates (their fixels the sites, three each). */
    wr_lattice_job *lattice;
    const wr_lattice_design *poses; /* the lattice's designs, once enumerated */
    double (*features)[2]; /* objective accuracy: params.features' points (spec.features) */
    int (*listed)[WR_MAX_FIXELS];
    const char *source;      /* the field giving the candidates: for refusals */
    uint64_t max_candidates; /* wp_limits' (0: no cap) */
    int max_cases;           /* wp_case_limit of the limits */
    /* params.deadline_s: the monotonic second after which the search claims
     * no more candidates and the answer is the best so far, "partial" (0:
     * none); `cut` once it has.  Both read and written under the search
     * engine's lock (search_claim), `cut` read by the steps after the
     * search's last merge. */
    double deadline;
    bool cut;
    /* The part's symmetries (start_search), unless collapse_symmetric is
     * false: NULL then. */
    bool collapse;
    wr_symmetry *symmetries;
    int symmetry_count;
    /* The stage the last notification was of (0 poses, 1 candidates, 2
     * figures), when it began and what was done then: the rate that
     * eta_s is estimated from.  Only the steps' thread reads and writes
     * them. */
    int stage;
    double stage_started;
    uint64_t stage_done;
    double (*loads)[3];   /* params.cases, summed (spec.loads points here) */
};

static const wp_chunk_ops JOB_CHUNKS;

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

static const char *const SITE_FIELDS[] = {"at", "normal", "pin", NULL};
static const char *const PIN_FIELDS[] = {"hole", "diameter", NULL};

/* params.sites[i].pin: {"hole": L, "diameter": D}, the site where that pin
 * touches the hole's wall (wr_site_pin). */
static bool read_pin(const cJSON *pin, const char *field, const double at[2], bool has_normal,
                     design_state *s, wr_site *out, wp_error *error)
{
    char path[WP_FIELD_MAX], at_field[WP_FIELD_MAX];
    wp_path_key(path, field, "pin");
    double hole, diameter;
    if (!wp_check_object(pin, path, PIN_FIELDS, error) ||
        !wp_member_number(pin, path, "hole", true, &hole, NULL, error) ||
        !wp_member_number(pin, path, "diameter", true, &diameter, NULL, error))
        return false;
    if (has_normal) {
        wp_path_key(at_field, field, "normal");
        wp_error_set(error, WP_INVALID_PARAMS, at_field,
                     "not with a pin: its normal is the hole wall's where the pin touches");
        return false;
    }
    if (hole != floor(hole) || fabs(hole) > 1e9)
        hole = -1; /* refused below, with the hole numbers allowed */
    wr_error invalid;
    wr_status status = wr_site_pin(s->body, (int)hole, diameter, at, out, &invalid);
    if (status == WR_OK)
        return true;
    if (strcmp(invalid.field, "at") == 0)
        wp_path_key(at_field, field, "at");
    else if (invalid.field[0])
        wp_path_key(at_field, path, invalid.field);
    else
        snprintf(at_field, sizeof at_field, "%s", status == WR_INVALID ? path : "");
    wp_error_set(error, status == WR_INVALID ? WP_INVALID_PARAMS : WP_INTERNAL, at_field, "%s",
                 invalid.reason);
    return false;
}

static bool read_sites(const cJSON *list, design_state *s, wp_error *error)
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
        const cJSON *pin = cJSON_GetObjectItemCaseSensitive(item, "pin");
        if (pin) {
            if (!read_pin(pin, field, at, has_normal, s, &s->sites[i], error))
                return false;
            continue;
        }
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
static bool read_lattice(const cJSON *params, const cJSON *json, design_state *s,
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
    s->poses_chunks = wp_chunks_new(&JOB_CHUNKS, s, SIZE_MAX); /* as the job claims them */
    if (!s->poses_chunks) {
        wp_error_set(error, WP_INTERNAL, "", "out of memory");
        return false;
    }
    return true;
}

/* params.fixel_tolerance: a geometric tolerance on every design's fixels
 * ({"position", "angle"?}, as a fixture's "tolerance"), which makes each
 * design's both region and best push robust (wr_design_spec).  Its values
 * are checked on the body (no fixels: a segment's room is each design's
 * own matter); a finger's friction is refused with it, as push.regions
 * refuses it with a tolerance. */
static bool read_fixel_tolerance(const cJSON *params, design_state *s, wp_error *error)
{
    wr_design_spec *spec = &s->spec;
    if (!wp_tolerance_read(cJSON_GetObjectItemCaseSensitive(params, "fixel_tolerance"),
                           "params.fixel_tolerance", &spec->fixel_tolerance, error))
        return false;
    if (!spec->fixel_tolerance.given)
        return true;
    wr_fixture body = *s->body;
    wr_error invalid;
    if (wr_fixture_set_tolerance(&body, &spec->fixel_tolerance, &invalid) != WR_OK) {
        char field[WP_FIELD_MAX]; /* tolerance.position -> params.fixel_tolerance.position */
        snprintf(field, sizeof field, "params.fixel_%s", invalid.field);
        wp_error_status(error, WR_INVALID, field, "%s", invalid.reason);
        return false;
    }
    if (spec->finger.friction > 0) {
        wp_error_set(error, WP_INVALID_PARAMS, "params.finger_friction",
                     "robust push regions (params.fixel_tolerance) are for a frictionless "
                     "finger");
        return false;
    }
    return true;
}

/* params.supports: the base plate under every candidate, read as a
 * fixture's (on the body), and what a design on it answers
 * (wr_design_supports_asked), refused here before any work. */
static bool read_plate(const cJSON *params, design_state *s, wp_error *error)
{
    const cJSON *supports = cJSON_GetObjectItemCaseSensitive(params, "supports");
    if (!supports)
        return true;
    if (!wp_supports_read(supports, "params.supports", s->body, error))
        return false;
    s->spec.supports = s->body->supports;
    wr_error invalid;
    if (!wr_design_supports_asked(&s->spec, &invalid)) {
        wp_error_refusal(error, WR_INVALID, "params", &invalid);
        return false;
    }
    return true;
}

/* params.tolerance and params.features, which objective accuracy needs
 * (and nothing else takes): each locator off by +-tolerance, and the
 * points whose error counts ([{"name"?, "at"}], as fixture.locating's). */
static bool read_accuracy(const cJSON *params, design_state *s, wp_error *error)
{
    wr_design_spec *spec = &s->spec;
    const cJSON *tolerance = cJSON_GetObjectItemCaseSensitive(params, "tolerance");
    const cJSON *features = cJSON_GetObjectItemCaseSensitive(params, "features");
    if (spec->objective != WR_OBJECTIVE_ACCURACY && spec->objective != WR_OBJECTIVE_PARETO) {
        if (tolerance || features)
            wp_error_set(error, WP_INVALID_PARAMS, tolerance ? "params.tolerance" : "params.features",
                         "is for objective \"accuracy\" or \"pareto\"");
        return !(tolerance || features);
    }
    if (!tolerance) {
        wp_error_set(error, WP_INVALID_PARAMS, "params.tolerance",
                     "required with objective \"%s\": how far each locator may be off",
                     OBJECTIVES[spec->objective]);
        return false;
    }
    if (!wp_number(tolerance, "params.tolerance", &spec->tolerance, error))
        return false;
    if (!(spec->tolerance >= 0)) {
        wp_error_set(error, WP_INVALID_PARAMS, "params.tolerance", "must not be negative, not %g",
                     spec->tolerance);
        return false;
    }
    if (!features)
        return true;
    if (!cJSON_IsArray(features) || cJSON_GetArraySize(features) > WR_DESIGN_MAX_FEATURES) {
        wp_error_set(error, WP_INVALID_PARAMS, "params.features",
                     "must be an array of at most %d {\"name\", \"at\": [x, y]}",
                     WR_DESIGN_MAX_FEATURES);
        return false;
    }
    int n = cJSON_GetArraySize(features);
    s->features = calloc((size_t)n + 1, sizeof *s->features);
    if (!s->features) {
        wp_error_status(error, WR_NO_MEMORY, "", "out of memory");
        return false;
    }
    static const char *const FEATURE[] = {"name", "at", NULL};
    int i = 0;
    for (const cJSON *f = features->child; f; f = f->next, i++) {
        char path[WP_FIELD_MAX];
        const char *name;
        wp_path_index(path, "params.features", (size_t)i);
        if (!wp_check_object(f, path, FEATURE, error) ||
            !wp_member_vector2(f, path, "at", true, s->features[i], NULL, error) ||
            !wp_member_string(f, path, "name", false, &name, error))
            return false;
    }
    spec->features = (const double(*)[2])s->features;
    spec->feature_count = n;
    return true;
}

static bool read_params(const cJSON *params, design_state *s, wp_error *error)
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
        for (int i = 0; i < (int)(sizeof OBJECTIVES / sizeof *OBJECTIVES); i++)
            if (strcmp(objective, OBJECTIVES[i]) == 0)
                found = i;
        if (found < 0) {
            wp_error_set(error, WP_INVALID_PARAMS, "params.objective",
                         "must be \"margin\", \"region\", \"gravity\", \"force\", "
                         "\"accuracy\" or \"pareto\"");
            return false;
        }
        spec->objective = (wr_objective)found;
    }
    /* Load cases, on the body (its mass, centre of mass and size). */
    const cJSON *cases_json = cJSON_GetObjectItemCaseSensitive(params, "cases");
    if (!cases_json && spec->objective == WR_OBJECTIVE_FORCE) {
        wp_error_set(error, WP_INVALID_PARAMS, "params.cases",
                     "required with the objective \"force\": the loads the push works against");
        return false;
    }
    if (cases_json) {
        wp_cases cases;
        if (!wp_cases_read(cases_json, "params.cases", s->body, s->max_cases, &cases, error))
            return false;
        s->loads = malloc((size_t)cases.count * sizeof *s->loads);
        if (!s->loads) {
            wp_cases_release(&cases);
            wp_error_set(error, WP_INTERNAL, "", "out of memory");
            return false;
        }
        for (int c = 0; c < cases.count; c++)
            memcpy(s->loads[c], cases.items[c].load, sizeof s->loads[c]);
        spec->loads = (const double (*)[3])s->loads;
        spec->case_count = cases.count;
        wp_cases_release(&cases);
    }
    if (!read_accuracy(params, s, error))
        return false;
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
    if (!wp_read_push_on(params, "params", s->body, &s->push_on, &spec->finger.push_on_count,
                         error))
        return false;
    spec->finger.push_on = s->push_on;
    if (!read_fixel_tolerance(params, s, error) || !read_plate(params, s, error))
        return false;
    const cJSON *progress = cJSON_GetObjectItemCaseSensitive(params, "progress");
    if (progress && !cJSON_IsBool(progress)) {
        wp_error_set(error, WP_INVALID_PARAMS, "params.progress", "must be true or false, not %s",
                     wp_type_name(progress));
        return false;
    }
    s->progress = progress && cJSON_IsTrue(progress);
    if (!wp_read_deadline(params, &s->deadline, error))
        return false;
    const cJSON *collapse = cJSON_GetObjectItemCaseSensitive(params, "collapse_symmetric");
    if (collapse && !cJSON_IsBool(collapse)) {
        wp_error_set(error, WP_INVALID_PARAMS, "params.collapse_symmetric",
                     "must be true or false, not %s", wp_type_name(collapse));
        return false;
    }
    s->collapse = !collapse || cJSON_IsTrue(collapse);
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
    const char *spacing_only[] = {"corner_clearance", "pin_diameter"};
    for (int i = 0; i < 2 && !spacing; i++)
        if (cJSON_GetObjectItemCaseSensitive(params, spacing_only[i])) {
            char field[WP_FIELD_MAX];
            wp_path_key(field, "params", spacing_only[i]);
            wp_error_set(error, WP_INVALID_PARAMS, field, "only with spacing");
            return false;
        }
    s->source = lattice ? "params.lattice" : sites ? "params.sites" : "params.spacing";
    if (lattice)
        return read_lattice(params, lattice, s, error);
    if (sites)
        return read_sites(sites, s, error);
    wr_spacing rule = {0, 0, 0};
    bool clearance_given;
    if (!wp_member_number(params, "params", "spacing", true, &rule.spacing, &present, error) ||
        !wp_member_number(params, "params", "corner_clearance", false, &rule.corner_clearance,
                          &clearance_given, error) ||
        !wp_member_number(params, "params", "pin_diameter", false, &rule.pin_diameter, NULL,
                          error))
        return false;
    if (!clearance_given)
        rule.corner_clearance = rule.spacing / 2;
    wr_error invalid;
    wr_status status = wr_sites_spaced(s->body, &rule, &s->sites, &s->site_count, &invalid);
    if (status != WR_OK) {
        wp_error_refusal(error, status, "params", &invalid);
        return false;
    }
    return true;
}

/* The search's job, over the sites (or the lattice's designs, once
 * enumerated: their contacts are the sites, three a candidate). */
static bool start_search(design_state *s, wp_error *error)
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
    /* On supports no symmetry is used: a copy would have to map the
     * supports and their loads too (wr_design.h). */
    if (s->collapse && !s->spec.supports) {
        if (wr_symmetry_find(s->body, s->sites, s->site_count, &s->symmetries,
                             &s->symmetry_count) != WR_OK) {
            wp_error_set(error, WP_INTERNAL, "", "out of memory");
            return false;
        }
        /* The part's symmetries that the push_on loops and the load cases
         * allow: a copy must be the same question, not only the same part. */
        s->symmetry_count = wr_symmetry_filter(s->body, &s->spec.finger, s->spec.loads,
                                               s->spec.case_count, s->symmetries,
                                               s->symmetry_count);
        /* Objective accuracy weighs its features by the worst: a copy must
         * map them onto themselves too (the pose's error alone, measured
         * about the centre of mass, every symmetry keeps). */
        if (s->spec.objective == WR_OBJECTIVE_ACCURACY || s->spec.objective == WR_OBJECTIVE_PARETO)
            s->symmetry_count = wr_symmetry_filter_points(s->spec.features,
                                                          s->spec.feature_count, s->body->size,
                                                          s->symmetries, s->symmetry_count);
        s->spec.symmetries = s->symmetries;
        s->spec.symmetry_count = s->symmetry_count;
    }
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
        wp_error_refusal(error, status, "params", &invalid);
        return false;
    }
    /* The job claims WR_DESIGN_CHUNK candidates of this shard at a time:
     * that many of every shard's. */
    uint64_t span = (uint64_t)WR_DESIGN_CHUNK * (uint64_t)s->spec.shard_count;
    s->search = wp_chunks_new(&JOB_CHUNKS, s, (size_t)((s->candidates + span - 1) / span));
    if (!s->search) {
        wp_error_set(error, WP_INTERNAL, "", "out of memory");
        return false;
    }
    return true;
}

static void design_free(void *stream);

static void *design_begin(wp_call *call, wp_prepared *prepared)
{
    (void)prepared;
    design_state *s = calloc(1, sizeof *s);
    if (!s) {
        wp_error_set(call->error, WP_INTERNAL, "", "out of memory");
        return NULL;
    }
    s->last_report = -1;
    s->max_candidates = call->limits->max_candidates;
    s->max_cases = wp_case_limit(call->limits);
    if (!read_params(call->params, s, call->error)) {
        design_free(s);
        return NULL;
    }
    if (s->progress && !wp_call_may_notify(call)) {
        /* A batch's answer is one line: nothing can come before it. */
        s->progress = false;
    }
    if (!s->lattice && !start_search(s, call->error)) {
        design_free(s);
        return NULL;
    }
    return s;
}

/* A count, exactly: above 2^53 a double would round it. */
static void write_count(wp_writer *out, uint64_t n)
{
    char text[24];
    int length = snprintf(text, sizeof text, "%llu", (unsigned long long)n);
    wp_write_raw(out, text, (size_t)length);
}

static void write_member_count(wp_writer *out, const char *key, uint64_t n)
{
    wp_write_key(out, key);
    write_count(out, n);
}

static void write_pair(wp_writer *out, const double v[2])
{
    const double pair[2] = {v[0] + 0.0, v[1] + 0.0};
    wp_write_numbers(out, pair, 2);
}

static const char *const STAGES[] = {"poses", "candidates", "figures"};

/* Where a design's answer says a push is, as push.regions names places:
 * {"at", "loop", "segment"} on an outline, {"at", "edge"} otherwise, then
 * "t". */
static void write_place(wp_writer *out, const wr_fixture *body, int edge, double t)
{
    double at[2], normal[2];
    wr_boundary_point(body, edge, t, at, normal);
    wp_write_object(out);
    wp_write_key(out, "at");
    write_pair(out, at);
    wp_write_edge_place(out, body, edge);
    wp_write_member_number(out, "t", t);
    wp_write_object_end(out);
}

/* "why_no_seating_push" (docs/PROTOCOL.md): where the push was asked
 * about, and the reasons with their counts, most first, equal counts by
 * their blocking strings (strcmp), the push in G_goal (null) last: an
 * order design-merge can keep. */
static void write_why(design_state *s, wp_writer *out)
{
    const wr_plan *plan;
    int edge;
    double t;
    const uint64_t *why = wr_design_job_why(s->job, &plan, &edge, &t);
    wp_write_key(out, "why_no_seating_push");
    wp_write_object(out);
    wp_write_key(out, "asked_at");
    write_place(out, s->body, edge, t);
    wp_write_key(out, "reasons");
    wp_write_array(out);
    int n = plan->kept_count + 1;
    bool *written = calloc((size_t)n, sizeof *written);
    for (int round = 0; written && round < n; round++) {
        int most = -1;
        char a[WR_CONSTRAINT_TEXT], b[WR_CONSTRAINT_TEXT];
        for (int i = 0; i < n; i++) {
            if (written[i] || why[i] == 0)
                continue;
            bool before = most < 0 || why[i] > why[most];
            if (!before && why[i] == why[most] && i < plan->kept_count) {
                wr_constraint_format(&plan->kept[i], a);
                if (most == plan->kept_count)
                    before = true;
                else {
                    wr_constraint_format(&plan->kept[most], b);
                    before = strcmp(a, b) < 0;
                }
            }
            if (before)
                most = i;
        }
        if (most < 0)
            break;
        written[most] = true;
        wp_write_object(out);
        wp_write_key(out, "blocking");
        if (most == plan->kept_count) {
            wp_write_null(out);
            wp_write_key(out, "states");
            wp_write_array(out);
        } else {
            char text[WR_CONSTRAINT_TEXT], state[WR_STATE_TEXT];
            wr_constraint_format(&plan->kept[most], text);
            wp_write_string(out, text);
            wp_write_key(out, "states");
            wp_write_array(out);
            for (int j = 0; j < plan->origins[most].count; j++) {
                wr_state_format(plan->origins[most].states[j], plan->fixel_count, state);
                wp_write_string(out, state);
            }
        }
        wp_write_array_end(out);
        write_member_count(out, "candidates", why[most]);
        wp_write_object_end(out);
    }
    free(written);
    wp_write_array_end(out);
    wp_write_object_end(out);
}

/* A design.progress notification, a line of its own. */
static void write_progress(design_state *s, wp_call *call, wp_buffer *line)
{
    uint64_t done = 0, total = 0;
    bool has_best = false;
    double best = 0;
    int stage = 0;
    /* Merges are the steps' own (wp_chunks_run): nothing to lock. */
    if (s->job) {
        wr_design_job_progress(s->job, &done, &total, &has_best, &best);
        stage = 1;
        if (done == total && s->search_reported) {
            int figured, of;
            wr_design_job_figures_progress(s->job, &figured, &of);
            done = (uint64_t)figured;
            total = (uint64_t)of;
            stage = 2;
        }
    } else {
        size_t pairs, of;
        wr_lattice_job_progress(s->lattice, &pairs, &of);
        done = pairs;
        total = of;
    }
    double now = wp_now_s();
    if (s->last_report < 0 || stage != s->stage) {
        s->stage = stage;
        s->stage_started = now;
        s->stage_done = done;
    }
    wp_writer w = wp_writer_on(line);
    wp_write_object(&w);
    wp_write_member_string(&w, "jsonrpc", "2.0");
    wp_write_member_string(&w, "method", "design.progress");
    wp_write_key(&w, "params");
    wp_write_object(&w);
    const char *id = wp_call_id_text(call);
    wp_write_key(&w, "id");
    wp_write_raw(&w, id, strlen(id));
    /* The stage: "poses" while a lattice's designs are enumerated (done and
     * total count its units: a hole pair with the first peg's segment),
     * then "candidates", then "figures" (the designs kept). */
    wp_write_member_string(&w, "stage", STAGES[stage]);
    write_member_count(&w, "done", done);
    write_member_count(&w, "total", total);
    wp_write_key(&w, "best");
    if (has_best)
        wp_write_number(&w, best);
    else
        wp_write_null(&w);
    /* The stage's seconds left at its rate so far (docs/PROTOCOL.md):
     * unknown until some of it is done. */
    wp_write_key(&w, "eta_s");
    if (done >= total)
        wp_write_number(&w, 0);
    else if (done > s->stage_done && now > s->stage_started)
        wp_write_number(&w, round((now - s->stage_started) / (double)(done - s->stage_done) *
                                  (double)(total - done) * 10) / 10);
    else
        wp_write_null(&w);
    wp_write_object_end(&w);
    wp_write_object_end(&w);
    wp_buffer_append(line, "\n", 1);
    s->last_report = now;
}

static void write_design(design_state *s, wp_writer *out, const wr_design *d, int rank)
{
    bool accuracy = s->spec.objective == WR_OBJECTIVE_ACCURACY;
    wr_fixture fixture;
    wr_design_job_fixture(s->job, d, &fixture);
    wp_write_object(out);
    wp_write_member_number(out, "rank", rank);
    write_member_count(out, "candidate", d->candidate);
    if (!s->poses) {
        wp_write_key(out, "sites");
        wp_write_array(out);
        for (int i = 0; i < s->spec.fixel_count; i++)
            wp_write_number(out, (double)d->sites[i]);
        wp_write_array_end(out);
    }
    wp_write_key(out, "fixels");
    wp_write_array(out);
    for (int i = 0; i < fixture.fixel_count; i++) {
        wp_write_object(out);
        wp_write_key(out, "at");
        write_pair(out, fixture.fixels[i].at);
        wp_write_key(out, "normal");
        write_pair(out, fixture.fixels[i].normal);
        wp_write_object_end(out);
    }
    wp_write_array_end(out);
    if (!s->poses) {
        /* The fixels on holes: pins, each where one of its diameter touches
         * the wall (wr_sites.h); its centre is at - diameter / 2 normal. */
        wp_write_key(out, "pins");
        wp_write_array(out);
        for (int i = 0; i < s->spec.fixel_count; i++) {
            const wr_site *site = &s->sites[d->sites[i]];
            if (site->loop <= 0)
                continue;
            wp_write_object(out);
            wp_write_member_number(out, "fixel", i);
            wp_write_member_number(out, "hole", site->loop);
            wp_write_member_number(out, "diameter", site->pin_diameter);
            wp_write_object_end(out);
        }
        wp_write_array_end(out);
    }
    if (s->poses) {
        const wr_lattice_design *pose = &s->poses[d->candidate];
        wp_write_key(out, "pegs");
        wp_write_array(out);
        for (int m = 0; m < 3; m++) {
            double hole[2] = {pose->holes[m][0], pose->holes[m][1]};
            write_pair(out, hole);
        }
        wp_write_array_end(out);
        const double placed[3] = {pose->pose[0] + 0.0, pose->pose[1] + 0.0,
                                  pose->pose[2] * 180 / 3.14159265358979323846 + 0.0};
        wp_write_key(out, "pose");
        wp_write_numbers(out, placed, 3);
    }
    /* On supports the figures of directions are not made (wr_design.h). */
    bool plate = s->spec.supports != NULL;
    const wr_best_push *push = &d->best_push;
    if (!plate)
        wp_write_key(out, "best_push");
    if (plate) {
    } else if (push->found) {
        wp_write_object(out);
        wp_write_key(out, "at");
        write_pair(out, push->at);
        wp_write_key(out, "direction");
        write_pair(out, push->direction);
        wp_write_member_number(out, "margin", push->margin);
        wp_write_edge_place(out, &fixture, push->edge);
        wp_write_member_number(out, "t", push->t);
        wp_write_object_end(out);
    } else {
        wp_write_null(out);
    }
    if (s->spec.case_count > 0) {
        /* The least push doing both under every case (wr_force.h), or on
         * supports seating the part on them. */
        const wr_least_force *least = &d->least_force;
        wp_write_key(out, "least_push");
        if (least->found) {
            wp_write_object(out);
            wp_write_member_string(out, "set", plate ? "goal" : "both");
            wp_write_key(out, "at");
            write_pair(out, least->at);
            wp_write_key(out, "direction");
            write_pair(out, least->direction);
            wp_write_member_number(out, "force", wp_force_out(s->body, least->force));
            wp_write_member_number(out, "lower_bound", wp_force_out(s->body, least->lower));
            wp_write_edge_place(out, &fixture, least->edge);
            wp_write_member_number(out, "t", least->t);
            wp_write_object_end(out);
        } else {
            wp_write_null(out);
        }
    }
    if (!plate) {
        wp_write_member_number(out, "goal_length", d->goal_length);
        wp_write_member_number(out, "both_length", d->both_length);
        wp_write_member_number(out, "gravity_goal_deg", d->gravity_goal_deg);
        wp_write_key(out, "critical_mu");
        if (d->has_critical)
            wp_write_number(out, d->critical_mu);
        else
            wp_write_null(out);
    }
    /* Objective force: minus a force, in the body's force unit. */
    wp_write_member_number(out, "score",
                           s->spec.objective == WR_OBJECTIVE_FORCE
                               ? -wp_force_out(s->body, -d->score)
                               : d->score);
    if (accuracy) /* the worst locating error, whose negative is the score */
        wp_write_member_number(out, "accuracy", -d->score + 0.0);
    if (s->spec.objective == WR_OBJECTIVE_PARETO) {
        /* The three figures the front is made on. */
        wp_write_key(out, "pareto");
        wp_write_object(out);
        wp_write_member_number(out, "margin", d->pareto[0] + 0.0);
        wp_write_member_number(out, "accuracy", d->pareto[1] + 0.0);
        wp_write_key(out, "force");
        if (isfinite(d->pareto[2]))
            wp_write_number(out, wp_force_out(s->body, d->pareto[2]));
        else
            wp_write_null(out);
        wp_write_object_end(out);
    }
    wp_write_member_number(out, "copies", d->copies);
    wp_write_object_end(out);
}

/* [{"kind": "rotation"|"reflection", "angle_deg", "center"}], the identity
 * first: what collapsed the designs. */
static void write_symmetries(design_state *s, wp_writer *out)
{
    wp_write_key(out, "symmetries");
    wp_write_array(out);
    for (int i = 0; i < s->symmetry_count; i++) {
        const wr_symmetry *g = &s->symmetries[i];
        wp_write_object(out);
        wp_write_member_string(out, "kind", g->reflection ? "reflection" : "rotation");
        wp_write_member_number(out, "angle_deg", g->angle_deg);
        wp_write_key(out, "center");
        write_pair(out, g->center);
        wp_write_object_end(out);
    }
    wp_write_array_end(out);
}

static void write_answer(design_state *s, wp_writer *out)
{
    int count;
    const wr_design *designs = wr_design_job_designs(s->job, &count);
    wp_write_object(out);
    wp_write_key(out, "designs");
    wp_write_array(out);
    for (int i = 0; i < count; i++)
        write_design(s, out, &designs[i], i + 1);
    wp_write_array_end(out);
    const wr_design_counts *c = wr_design_job_counts(s->job);
    if (s->cut && c->examined < wr_design_job_total(s->job))
        wp_write_member_bool(out, "partial", true);
    wp_write_key(out, "counts");
    wp_write_object(out);
    write_member_count(out, "candidates", s->candidates);
    write_member_count(out, "examined", c->examined);
    write_member_count(out, "degenerate", c->degenerate);
    write_member_count(out, "unpinned", c->unpinned);
    write_member_count(out, "no_seating_push", c->no_seating_push);
    write_member_count(out, "symmetric", c->symmetric);
    write_member_count(out, "shared_hole", c->shared_hole);
    wp_write_object_end(out);
    write_why(s, out);
    if (s->poses)
        write_member_count(out, "poses", s->spec.candidate_count);
    else
        wp_write_member_number(out, "sites", s->site_count);
    wp_write_member_string(out, "objective", OBJECTIVES[s->spec.objective]);
    if (s->symmetries)
        write_symmetries(s, out);
    const double shard[2] = {s->spec.shard_index, s->spec.shard_count};
    wp_write_key(out, "shard");
    wp_write_numbers(out, shard, 2);
    wp_write_object_end(out);
}

/* The chunks of either stage, by the engine (wp_chunks.h), in the lib's
 * one job contract (wr_job.h): the lattice's poses (its units, wr_lattice.h) while
 * there is no search job, then the search's candidates, whose claims stop
 * at the deadline.  A record is a claim, the contract it was claimed
 * under (NULL before its first claim) and the job's chunk. */
typedef struct job_record {
    wr_job_claim claim;
    const wr_job_chunks *ops;
    union {
        wr_design_chunk design;
        wr_lattice_chunk lattice;
    } chunk;
} job_record;

/* The stage's job and its contract.  The search begins in a step that
 * shares nothing (design_step), so no helper is in a chunk when s->job
 * appears. */
static const wr_job_chunks *stage_job(const design_state *s, void **job)
{
    *job = s->job ? (void *)s->job : (void *)s->lattice;
    return s->job ? &wr_design_job_chunks : &wr_lattice_job_chunks;
}

/* The GLPK environment of the thread making a chunk (each worker has its
 * own, through the host), for a design on supports, whose LPs the lib
 * builds itself (wr_support.h); NULL without supports, which need none. */
static wr_lp_env *plate_env(const design_state *s, const wp_host *host)
{
    return s->spec.supports && host->lp_env ? host->lp_env(host->self) : NULL;
}

/* A job's status as the chunk's: a failure names no field of its own. */
static wr_status job_status(wr_status status, wp_error *error)
{
    if (status != WR_OK)
        wp_error_status(error, status, "params", "%s", wr_strerror(status));
    return status;
}

static bool job_claim(void *method, size_t index, void *record)
{
    (void)index;
    design_state *s = method;
    /* The deadline: no candidate is claimed after it.  The chunks claimed
     * are merged as usual, then the designs kept so far get their figures
     * and the answer is "partial". */
    if (s->job && s->deadline > 0 && !s->cut && wp_now_s() >= s->deadline) {
        wr_design_job_cut(s->job);
        s->cut = true;
    }
    void *job;
    job_record *r = record;
    r->ops = stage_job(s, &job);
    return r->ops->claim(job, &r->claim);
}

static wr_status job_make(void *method, size_t index, void *record, wp_buffer *direct,
                          const wp_host *host, unsigned long *used, wp_error *error)
{
    (void)index;
    (void)direct;
    void *job;
    const wr_job_chunks *ops = stage_job(method, &job);
    job_record *r = record;
    return job_status(ops->run(job, &r->claim, host->stop, plate_env(method, host), &r->chunk,
                               used),
                      error);
}

static wr_status job_merge(void *method, size_t index, void *record, wp_buffer *out,
                           wp_error *error)
{
    (void)index;
    (void)out;
    void *job;
    const wr_job_chunks *ops = stage_job(method, &job);
    return job_status(ops->merge(job, &((job_record *)record)->chunk), error);
}

static void job_release(void *record)
{
    job_record *r = record;
    if (r->ops)
        r->ops->release(&r->chunk);
}

/* Each stage has an engine of its own (s->poses_chunks, s->search). */
static const wp_chunk_ops JOB_CHUNKS = {
    .record_size = sizeof(job_record),
    .claim = job_claim,
    .make = job_make,
    .merge = job_merge,
    .release = job_release,
    .window = DESIGN_WINDOW,
};

/* The designs' figures: chunk i is design figures_first + i. */
static wr_status figure_make(void *method, size_t index, void *record, wp_buffer *direct,
                             const wp_host *host, unsigned long *used, wp_error *error)
{
    (void)record;
    (void)direct;
    const design_state *s = method;
    wr_status status = wr_design_job_figure(s->job, s->figures_first + (int)index, host->stop,
                                            plate_env(s, host), used);
    return job_status(status, error);
}

static wr_status figure_merge(void *method, size_t index, void *record, wp_buffer *out,
                              wp_error *error)
{
    (void)index;
    (void)record;
    (void)out;
    (void)error;
    wr_design_job_figure_merged(((design_state *)method)->job);
    return WR_OK;
}

static void figure_release(void *record) { (void)record; }

static const wp_chunk_ops FIGURE_CHUNKS = {
    .record_size = 1,
    .make = figure_make,
    .merge = figure_merge,
    .release = figure_release,
    .window = DESIGN_WINDOW,
};

/* The stage on: the lattice's poses, then the search's candidates, then
 * the kept designs' figures. */
static wp_chunks *stage(design_state *s)
{
    return s->figures ? s->figures : s->job ? s->search : s->poses_chunks;
}

static bool design_parallel(void *stream) { return wp_chunks_parallel(stage(stream)); }

static bool design_work(void *stream, const wp_host *host)
{
    return wp_chunks_work(stage(stream), host);
}

static wp_step design_step(void *stream, wp_call *call, wp_writer *out, unsigned long budget,
                           unsigned long *used)
{
    design_state *s = stream;
    bool shared = wp_chunks_shared(stage(s));
    if (s->progress && s->last_report < 0)
        write_progress(s, call, out->out);
    if (!s->job) {
        /* A lattice: its designs first, in chunks of hole pairs that
         * helpers share; the search begins in a step that shares nothing,
         * so that no helper is in a chunk when s->job appears. */
        wp_step step = wp_chunks_run(s->poses_chunks, shared, call->host, out->out, budget, used,
                                     (size_t)-1, call->error);
        if (step == WP_STEP_FAILED)
            return WP_STEP_FAILED;
        if (step == WP_STEP_DONE) {
            bool enumerated = false;
            wr_status status = wr_lattice_job_run(s->lattice, 1, used, call->host->stop,
                                                  &enumerated);
            if (status != WR_OK) {
                wp_error_status(call->error, status, "params", "%s", wr_strerror(status));
                return WP_STEP_FAILED;
            }
            if (enumerated && !start_search(s, call->error))
                return WP_STEP_FAILED;
        }
        if (s->progress && wp_now_s() - s->last_report >= PROGRESS_INTERVAL_S)
            write_progress(s, call, out->out);
        return out->out->failed && !shared ? WP_STEP_FAILED : WP_STEP_MORE;
    }
    /* The search: chunks while the budget lasts (helpers may make others
     * meanwhile); then the kept designs' figures, a design a chunk; then,
     * in a step that shares nothing, the job itself says it is done. */
    if (s->figures) {
        wp_step step = wp_chunks_run(s->figures, shared, call->host, out->out, budget, used,
                                     (size_t)-1, call->error);
        if (step == WP_STEP_FAILED)
            return WP_STEP_FAILED;
        if (step != WP_STEP_DONE) {
            if (s->progress && wp_now_s() - s->last_report >= PROGRESS_INTERVAL_S)
                write_progress(s, call, out->out);
            return out->out->failed && !shared ? WP_STEP_FAILED : WP_STEP_MORE;
        }
    }
    unsigned long start = *used;
    wp_step step = wp_chunks_run(s->search, shared, call->host, out->out, budget, used, (size_t)-1,
                                 call->error);
    if (step == WP_STEP_FAILED)
        return WP_STEP_FAILED;
    if (step == WP_STEP_DONE && !s->figures && wr_design_job_figures_left(s->job) > 0) {
        /* The search is over and no helper is in it (a step that shares
         * nothing): the figures' stage begins. */
        int figured, of;
        wr_design_job_figures_progress(s->job, &figured, &of);
        s->figures_first = figured;
        s->figures = wp_chunks_new(&FIGURE_CHUNKS, s, (size_t)(of - figured));
        if (!s->figures) {
            wp_error_status(call->error, WR_NO_MEMORY, "params", "%s",
                            wr_strerror(WR_NO_MEMORY));
            return WP_STEP_FAILED;
        }
        if (s->progress && !s->search_reported)
            write_progress(s, call, out->out);
        s->search_reported = true;
        return out->out->failed ? WP_STEP_FAILED : WP_STEP_MORE;
    }
    bool done = false;
    if (step == WP_STEP_DONE && *used - start < budget) {
        wr_status status = wr_design_job_run(s->job, budget - (*used - start), used,
                                             call->host->stop, plate_env(s, call->host), &done);
        if (status != WR_OK) {
            wp_error_status(call->error, status, "params", "%s", wr_strerror(status));
            return WP_STEP_FAILED;
        }
    }
    uint64_t examined, total;
    bool has_best;
    double best;
    wr_design_job_progress(s->job, &examined, &total, &has_best, &best);
    if (s->progress && !s->search_reported &&
        (examined == total || wp_now_s() - s->last_report >= PROGRESS_INTERVAL_S)) {
        write_progress(s, call, out->out);
        s->search_reported = examined == total;
    } else if (s->progress && !done && wp_now_s() - s->last_report >= PROGRESS_INTERVAL_S) {
        write_progress(s, call, out->out); /* the designs' figures */
    }
    /* A shared step never ends the answer, not even for a piece that did
     * not fit in memory: the caller sees that in the buffer. */
    if (!done)
        return out->out->failed && !shared ? WP_STEP_FAILED : WP_STEP_MORE;
    wp_call_open_result(call, out);
    write_answer(s, out);
    return out->out->failed ? WP_STEP_FAILED : WP_STEP_DONE;
}

static void design_free(void *stream)
{
    design_state *s = stream;
    if (!s)
        return;
    wp_chunks_free(s->figures);
    wp_chunks_free(s->search);
    wp_chunks_free(s->poses_chunks);
    wr_design_job_free(s->job);
    wr_lattice_job_free(s->lattice);
    free(s->symmetries);
    free(s->listed);
    free(s->features);
    free(s->loads);
    free(s->sites);
    free(s->push_on);
    wr_fixture_free(s->body);
    free(s);
}

static size_t design_bytes(const void *stream)
{
    const design_state *s = stream;
    size_t poses = 0;
    if (s->lattice)
        wr_lattice_job_designs(s->lattice, &poses);
    return sizeof *s + (size_t)s->site_count * sizeof *s->sites +
           (s->job ? wr_design_job_bytes(s->job) : 0) +
           poses * (sizeof(wr_lattice_design) + sizeof *s->listed) +
           (s->poses_chunks ? wp_chunks_bytes(s->poses_chunks) : 0) +
           (s->search ? wp_chunks_bytes(s->search) : 0) +
           (s->figures ? wp_chunks_bytes(s->figures) : 0);
}

const wp_streamer wp_design_stream = {design_begin, design_step,     design_free,    design_bytes,
                                     true,         design_parallel, design_work};
