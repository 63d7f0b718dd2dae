/* wp_methods.c -- the methods of docs/PROTOCOL.md: one table of names,
 * parameters, flags and handlers.  The handlers live in proto/methods/, a
 * file per family (methods.h). */
#include "methods/methods.h"

#include <string.h>

static const char *const NONE[] = {NULL};
static const char *const FIXTURE[] = {"fixture", NULL};
static const char *const ID[] = {"id", NULL};
static const char *const LIST[] = {"after", "limit", NULL};
static const char *const CLASSIFY[] = {"fixture", "wrenches", "sets", "method", "tolerance",
                                       "fields", NULL};
static const char *const CLASSIFY_REQUIRED[] = {"fixture", "wrenches", NULL};
static const char *const CONE[] = {"fixture", "constraints", NULL};
static const char *const PUSH[] = {"fixture", "set", "finger_friction", "finger_radius", "push_on",
                                   "force", "cases", NULL};
static const char *const SWEEP[] = {"fixture", "set", "in_plane_g", NULL};
static const char *const MARGIN[] = {"fixture", "bias", NULL};
static const char *const DESIGN[] = {"body", "friction", "fixels", "sites", "spacing", "lattice",
                                     "objective", "top", "finger_radius", "finger_friction",
                                     "progress", "shard", "push_on", "corner_clearance",
                                     "pin_diameter", "cases", "collapse_symmetric", "deadline_s",
                                     "tolerance", "features", "units", "fixel_tolerance",
                                     "supports", NULL};
static const char *const DESIGN_REQUIRED[] = {"body", "friction", NULL};
static const char *const LOCATING[] = {"fixture", "tolerance", "features", "sigma_ratio", NULL};
static const char *const LOCATING_REQUIRED[] = {"fixture", "tolerance", NULL};
static const char *const FORCE_RANGE[] = {"fixture", "push", "wrench", "cases", "sets", "range",
                                          NULL};
static const char *const FORCE_REQUIRED[] = {"fixture", "cases", NULL};
static const char *const PUSH_FORCE[] = {"fixture", "set", "cases", "finger_radius", "samples", "push_on",
                                         "deadline_s", NULL};
static const char *const FRICTION_SWEEP[] = {"fixture", "range", "kinetic_ratio", "wrenches", "sets",
                                             "push", "gravity", "force", "cases", "deadline_s", "over",
                                             NULL};

/* WP_CHEAP: no derivation, no solver, no disk: a batch answers several in
 * one piece, and the event loop may answer it.  The rest end their piece
 * (wp_answer_step); WP_READY ones are light on a ready stored fixture
 * (wp_answer_light).  push.regions is not (a finger with friction samples
 * every edge), nor are cone.get (a cone derived) and stability.margin. */
const wp_method wp_methods[] = {
    {.name = "fixture.put", .handler = wp_handle_fixture_put, .fields = FIXTURE, .required = FIXTURE},
    {.name = "fixture.get", .handler = wp_handle_fixture_get, .fields = ID, .required = ID,
     .flags = WP_CHEAP},
    {.name = "fixture.delete", .handler = wp_handle_fixture_delete, .fields = ID, .required = ID},
    {.name = "fixture.list", .stream = &wp_list_stream, .fields = LIST, .required = NONE},
    {.name = "wrench.classify", .stream = &wp_classify_stream, .fields = CLASSIFY,
     .required = CLASSIFY_REQUIRED, .flags = WP_FIXTURE | WP_READY, .light = wp_classify_light,
     .raw_array = "wrenches"},
    {.name = "cone.get", .handler = wp_handle_cone_get, .fields = CONE, .required = CONE, .flags = WP_FIXTURE},
    {.name = "plan.get", .handler = wp_handle_plan_get, .fields = FIXTURE, .required = FIXTURE,
     .flags = WP_FIXTURE | WP_READY},
    {.name = "modes.get", .handler = wp_handle_modes_get, .fields = FIXTURE, .required = FIXTURE,
     .flags = WP_FIXTURE | WP_READY},
    {.name = "server.status", .handler = wp_handle_server_status, .fields = NONE, .required = NONE,
     .flags = WP_CHEAP},
    {.name = "push.regions", .stream = &wp_push_stream, .fields = PUSH, .required = FIXTURE,
     .flags = WP_FIXTURE},
    {.name = "gravity.sweep", .handler = wp_handle_gravity_sweep, .fields = SWEEP, .required = FIXTURE,
     .flags = WP_FIXTURE | WP_READY},
    {.name = "stability.margin", .handler = wp_handle_stability_margin, .fields = MARGIN,
     .required = MARGIN, .flags = WP_FIXTURE},
    {.name = "friction.sweep", .stream = &wp_sweep_stream, .fields = FRICTION_SWEEP,
     .required = FIXTURE, .flags = WP_FIXTURE},
    {.name = "fixture.locating", .handler = wp_handle_fixture_locating, .fields = LOCATING,
     .required = LOCATING_REQUIRED, .flags = WP_FIXTURE | WP_READY, .light = wp_locating_light},
    {.name = "force.range", .handler = wp_handle_force_range, .fields = FORCE_RANGE,
     .required = FORCE_REQUIRED, .flags = WP_FIXTURE, .raw_text = "cases"},
    {.name = "push.force", .handler = wp_handle_push_force, .fields = PUSH_FORCE,
     .required = FORCE_REQUIRED, .flags = WP_FIXTURE},
    {.name = "fixture.design", .stream = &wp_design_stream, .fields = DESIGN,
     .required = DESIGN_REQUIRED},
    {0},
};

const wp_method *wp_method_find(const char *name)
{
    for (const wp_method *m = wp_methods; m->name; m++)
        if (strcmp(m->name, name) == 0)
            return m;
    return NULL;
}
