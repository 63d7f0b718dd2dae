/* loads.h -- loads and load cases as JSON (docs/PROTOCOL.md, "Loads and
 * cases"), read into the fixture's model system: the one place where a
 * force, a torque or a gravity of a request is converted
 * (wr_fixture_force_factor), and wp_force_out the one where a magnitude
 * goes back. */
#ifndef WP_METHODS_LOADS_H
#define WP_METHODS_LOADS_H

#include "wp_method.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Most cases in one request (the default of the daemon's --max-cases, at
 * most WP_MOST_CASES), and most loads in one case: a tool path of a few
 * hundred points fits; beyond, the request is refused at the field. */
#define WP_MAX_CASES 1000
#define WP_MOST_CASES 1000000
#define WP_MAX_LOADS 100

/* The most cases a request may give: the limits' max_cases (the daemon's
 * --max-cases), WP_MAX_CASES when 0. */
static inline int wp_case_limit(const wp_limits *limits)
{
    size_t most = limits && limits->max_cases > 0 ? limits->max_cases : WP_MAX_CASES;
    return most < WP_MOST_CASES ? (int)most : WP_MOST_CASES;
}

/* One case: its name (borrowed from the request's JSON, NULL when not
 * given) and the sum of its loads, a physical wrench of the model system
 * (tau about the centre of mass). */
typedef struct wp_case {
    const char *name;
    double load[3];
} wp_case;

typedef struct wp_cases {
    int count;
    wp_case *items; /* malloc'd */
} wp_cases;

/* params.cases (at `path`): a non-empty array of {"name"?, "loads": [load,
 * ...]} with at least one load each, a load being
 *   {"gravity": {"g": G, "direction_deg": PHI}, "name"?}    m G (cos, sin, 0)
 *   {"force": [fx, fy], "at": [x, y], "name"?}               at a point
 *   {"wrench": [fx, fy, tau], "name"?}                       tau about the com
 * Refused at their field: a negative G, a point `at` farther than the part's
 * size from its centre of mass (how far is said), wrong types, unknown
 * members, more than `most` cases (wp_case_limit) or WP_MAX_LOADS loads.
 * False with nothing allocated on error. */
bool wp_cases_read(const cJSON *json, const char *path, const wr_fixture *fixture, int most,
                   wp_cases *out, wp_error *error);
/* The same cases from params.cases' text as written (wp_prepared.text,
 * which the scan has passed; names are ended in place and borrowed from
 * it), read without a tree: true with the very cases wp_cases_read would
 * give, false with nothing allocated when the text is not their common
 * shape or wp_cases_read would refuse it -- then read the tree, which says
 * why. */
bool wp_cases_read_text(char *text, size_t length, const wr_fixture *fixture, int most,
                        wp_cases *out);
void wp_cases_release(wp_cases *cases);

/* A point of the part where a force acts (a load's `at`, a push's): within
 * the part's size of its centre of mass, refused at `path` otherwise. */
bool wp_point_near_part(const wr_fixture *fixture, const double at[2], const char *path,
                        wp_error *error);

/* A magnitude of the model system in the fixture's force unit (INFINITY
 * stays so). */
static inline double wp_force_out(const wr_fixture *fixture, double force)
{
    return force / wr_fixture_force_factor(fixture) + 0.0;
}

/* push.regions' "force" F and "cases" (force.c): the regions where a push
 * of magnitude F does the set's job under every case
 * (wr_push_regions_loaded).  Without "force" there is nothing to do (given
 * false) and push.regions is what it always was; "cases" needs "force",
 * and "force" without cases is the push alone. */
typedef struct wp_push_load {
    bool given;
    double force;       /* model system */
    int count;          /* cases: at least 1 (a zero load without cases) */
    double (*loads)[3]; /* malloc'd, model system */
} wp_push_load;

/* Read params.force and params.cases; a finger with friction is refused
 * with them (the loaded regions are exact, for a frictionless finger).
 * False with nothing allocated on error. */
bool wp_push_load_read(const cJSON *params, const wr_fixture *fixture, double finger_friction,
                       int most_cases, wp_push_load *out, wp_error *error);
/* The same members of the object at `path` (friction.sweep's "push"):
 * path.force, path.cases, path.finger_friction. */
bool wp_push_load_read_at(const cJSON *params, const char *path, const wr_fixture *fixture,
                          double finger_friction, int most_cases, wp_push_load *out,
                          wp_error *error);
void wp_push_load_release(wp_push_load *load);

#ifdef __cplusplus
}
#endif

#endif
