/* wrenchctl.c -- the command-line client of wrenchd: its options, the table
 * of commands and the one dispatcher that runs them (wc.h says its steps).
 *
 * Each command sends one JSON-RPC request to the daemon (or, with --local,
 * answers it in process with the daemon's own request code), and prints
 * the result as a table, or raw with --json.  The commands' own code is by
 * topic: wc_fixture.c, wc_classify.c, wc_analysis.c, wc_regions.c; the
 * request itself in wc_call.c, the printing in wc_print.c.  Exit statuses
 * are for scripts: see wc.h and wrenchctl(1). */
#include "wc.h"
#include "wc_call.h"
#include "wc_commands.h"
#include "wc_print.h"

#include "wrench.h"

#include <getopt.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* ---- options ------------------------------------------------------------------ */

/* --socket, --timeout, --json, --local: before or after the command.
 * Returns 0, or EXIT_USAGE after saying why. */
static int take_global(wc_options *o, const char *name, const char *value)
{
    char *end;
    if (strcmp(name, "socket") == 0) {
        o->socket_path = value;
    } else if (strcmp(name, "timeout") == 0) {
        o->timeout_seconds = strtod(value, &end);
        if (*end || end == value || !(o->timeout_seconds > 0) || o->timeout_seconds > 86400)
            return wc_usage_error("--timeout wants seconds, more than 0, not '%s'", value);
    } else if (strcmp(name, "json") == 0) {
        o->json = true;
    } else if (strcmp(name, "local") == 0) {
        o->local = true;
    }
    return 0;
}

/* "goal", "strong" or "both". */
static bool is_set_name(const char *name)
{
    return strcmp(name, "goal") == 0 || strcmp(name, "strong") == 0 || strcmp(name, "both") == 0;
}

static int take_sets(wc_run *run, const char *value)
{
    cJSON_Delete(run->sets);
    run->sets = cJSON_CreateArray();
    char *copy = strdup(value);
    for (char *name = strtok(copy, ","); name; name = strtok(NULL, ",")) {
        if (!is_set_name(name)) {
            /* `name` points into `copy`: say it before freeing that. */
            int status = wc_usage_error("--sets: '%s' is not goal, strong or both", name);
            free(copy);
            return status;
        }
        cJSON_AddItemToArray(run->sets, cJSON_CreateString(name));
    }
    free(copy);
    return cJSON_GetArraySize(run->sets) > 0 ? 0 : wc_usage_error("--sets: no set named");
}

static int take_method(wc_run *run, const char *value)
{
    if (strcmp(value, "auto") != 0 && strcmp(value, "lp") != 0)
        return wc_usage_error("--method is auto or lp, not '%s'", value);
    run->method = value;
    return 0;
}

/* A number >= 0 for --NAME; false after saying why not. */
static bool take_number(const char *name, const char *value, double *out)
{
    char *end;
    *out = strtod(value, &end);
    if (*end || end == value || !(*out >= 0) || !isfinite(*out)) {
        wc_usage_error("--%s wants a number >= 0, not '%s'", name, value);
        return false;
    }
    return true;
}

static int take_tolerance(wc_run *run, const char *value)
{
    if (!take_number("tolerance", value, &run->tolerance))
        return EXIT_USAGE;
    run->tolerance_given = true;
    return 0;
}

static int take_set(wc_run *run, const char *value)
{
    if (!is_set_name(value))
        return wc_usage_error("--set is goal, strong or both, not '%s'", value);
    run->set = value;
    return 0;
}

static int take_friction(wc_run *run, const char *value)
{
    if (!take_number("finger-friction", value, &run->finger_friction))
        return EXIT_USAGE;
    run->friction_given = true;
    return 0;
}

static int take_radius(wc_run *run, const char *value)
{
    if (!take_number("finger-radius", value, &run->finger_radius))
        return EXIT_USAGE;
    run->radius_given = true;
    return 0;
}

/* "LO:HI" (or, with `single`, "MU", the interval [MU, MU]) for --NAME:
 * finite numbers, 0 <= LO, LO <= HI (LO < HI with `strict`), HI <= `most`.
 * False after saying why not. */
static bool take_bounds(const char *name, const char *value, bool single, bool strict,
                        double most, double *low, double *high)
{
    char *end;
    *low = strtod(value, &end);
    bool ok = end != value && isfinite(*low);
    *high = *low;
    if (ok && *end == ':') {
        const char *second = end + 1;
        *high = strtod(second, &end);
        ok = end != second && isfinite(*high);
    } else if (ok && !single) {
        ok = false; /* one number where an interval is wanted */
    }
    if (!ok || *end) {
        wc_usage_error("--%s wants %s, numbers, not '%s'", name, single ? "LO:HI or MU" : "LO:HI",
                       value);
        return false;
    }
    if (!(*low >= 0) || !(*high >= 0)) {
        wc_usage_error("--%s %s: %g is negative: the bounds are at least 0", name, value,
                       *low < 0 ? *low : *high);
        return false;
    }
    if (*high > most) {
        wc_usage_error("--%s %s: %g is above %g, the largest wrenchd takes", name, value, *high,
                       most);
        return false;
    }
    if (strict ? !(*low < *high) : !(*low <= *high)) {
        wc_usage_error("--%s %s: LO must be %s HI", name, value,
                       strict ? "below" : "at most");
        return false;
    }
    return true;
}

/* --friction LO:HI or MU: every fixel's friction, static and kinetic. */
static int take_interval(wc_run *run, const char *value)
{
    if (!take_bounds("friction", value, true, false, WC_FRICTION_MOST, &run->friction_low,
                     &run->friction_high))
        return EXIT_USAGE;
    run->friction_interval_given = true;
    return 0;
}

/* --push SET, --gravity SET, --wrench: the kind of sweep; one kind only. */
static int take_sweep_kind(wc_run *run, const char *kind, const char *option)
{
    if (run->sweep_kind && strcmp(run->sweep_kind, kind) != 0)
        return wc_usage_error("sweep: --%s and --%s: one of --push, --gravity, --least-force "
                              "or --wrench",
                              strcmp(run->sweep_kind, "wrenches") == 0 ? "wrench"
                              : strcmp(run->sweep_kind, "force") == 0  ? "least-force"
                                                                       : run->sweep_kind,
                              option);
    run->sweep_kind = kind;
    return 0;
}

static int take_push(wc_run *run, const char *value)
{
    if (!is_set_name(value))
        return wc_usage_error("--push is goal, strong or both, not '%s'", value);
    run->sweep_set = value;
    return take_sweep_kind(run, "push", "push");
}

static int take_gravity(wc_run *run, const char *value)
{
    if (!is_set_name(value))
        return wc_usage_error("--gravity is goal, strong or both, not '%s'", value);
    run->sweep_set = value;
    return take_sweep_kind(run, "gravity", "gravity");
}

static int take_least_force(wc_run *run, const char *value)
{
    if (!is_set_name(value))
        return wc_usage_error("--least-force is goal, strong or both, not '%s'", value);
    run->sweep_set = value;
    return take_sweep_kind(run, "force", "least-force");
}

static int take_wrench(wc_run *run, const char *value)
{
    cJSON *w = strchr(value, '@') ? NULL : wc_wrench_argument(value);
    if (!w)
        return wc_usage_error("--wrench wants FX,FY,TAU (the torque about the centre of mass), "
                              "not '%s'",
                              value);
    if (!run->wrenches)
        run->wrenches = cJSON_CreateArray();
    cJSON_AddItemToArray(run->wrenches, w);
    return take_sweep_kind(run, "wrenches", "wrench");
}

static int take_range(wc_run *run, const char *value)
{
    if (!take_bounds("range", value, false, true, INFINITY, &run->range[0], &run->range[1]))
        return EXIT_USAGE;
    run->range_given = true;
    return 0;
}

static int take_ratio(wc_run *run, const char *value)
{
    char *end;
    run->kinetic_ratio = strtod(value, &end);
    if (*end || end == value || !(run->kinetic_ratio > 0 && run->kinetic_ratio <= 1))
        return wc_usage_error("--kinetic-ratio wants a number above 0 and at most 1, not '%s'",
                              value);
    run->ratio_given = true;
    return 0;
}

/* --table full|summary: a sweep's curve whole, or summarised (default). */
static int take_table(wc_run *run, const char *value)
{
    if (strcmp(value, "full") != 0 && strcmp(value, "summary") != 0)
        return wc_usage_error("--table is full or summary, not '%s'", value);
    run->table_full = strcmp(value, "full") == 0;
    return 0;
}

static int take_spacing(wc_run *run, const char *value)
{
    if (!take_number("spacing", value, &run->spacing) || !(run->spacing > 0))
        return run->spacing == 0 ? wc_usage_error("--spacing wants a length above 0") : EXIT_USAGE;
    return 0;
}

/* A whole number in [lo, hi] for --NAME. */
static int take_whole(const char *name, const char *value, int lo, int hi, int *out)
{
    char *end;
    long n = strtol(value, &end, 10);
    if (*end || end == value || n < lo || n > hi)
        return wc_usage_error("--%s wants a whole number from %d to %d, not '%s'", name, lo, hi,
                              value);
    *out = (int)n;
    return 0;
}

static int take_fixels(wc_run *run, const char *value)
{
    return take_whole("fixels", value, 1, 8, &run->fixels);
}

static int take_top(wc_run *run, const char *value)
{
    return take_whole("top", value, 1, 1000, &run->top);
}

static int take_objective(wc_run *run, const char *value)
{
    if (strcmp(value, "margin") != 0 && strcmp(value, "region") != 0 &&
        strcmp(value, "gravity") != 0 && strcmp(value, "accuracy") != 0 &&
        strcmp(value, "force") != 0 && strcmp(value, "pareto") != 0)
        return wc_usage_error("--objective is margin, region, gravity, force, accuracy or "
                              "pareto, not '%s'",
                              value);
    run->objective = value;
    return 0;
}

/* --lattice PITCH,RADIUS,NXxNY: a modular fixture plate. */
static int take_lattice(wc_run *run, const char *value)
{
    char tail;
    if (sscanf(value, "%lf,%lf,%dx%d%c", &run->lattice[0], &run->lattice[1],
               &run->lattice_extent[0], &run->lattice_extent[1], &tail) != 4 ||
        !(run->lattice[0] > 0) || !(run->lattice[1] >= 0) || run->lattice_extent[0] < 1 ||
        run->lattice_extent[1] < 1)
        return wc_usage_error("--lattice wants PITCH,PEG_RADIUS,NXxNY (10,1,20x20), not '%s'",
                              value);
    run->lattice_given = true;
    return 0;
}

static int take_clearance(wc_run *run, const char *value)
{
    if (!take_number("corner-clearance", value, &run->corner_clearance) ||
        !(run->corner_clearance > 0))
        return run->corner_clearance == 0 ? wc_usage_error("--corner-clearance wants a length "
                                                           "above 0")
                                          : EXIT_USAGE;
    return 0;
}

static int take_pin_diameter(wc_run *run, const char *value)
{
    if (!take_number("pin-diameter", value, &run->pin_diameter) || !(run->pin_diameter >= 0))
        return wc_usage_error("--pin-diameter wants a length, 0 or more, not '%s'", value);
    run->pin_diameter_given = true;
    return 0;
}

/* --emit-fixture N FILE: its N here; the dispatcher takes FILE after it. */
static int take_emit(wc_run *run, const char *value)
{
    return take_whole("emit-fixture", value, 1, 1000, &run->emit_design);
}

/* --shard I/N: shard I of N, 0 <= I < N. */
static int take_symmetric(wc_run *run, const char *value)
{
    if (strcmp(value, "collapse") != 0 && strcmp(value, "all") != 0)
        return wc_usage_error("--symmetric wants collapse or all, not '%s'", value);
    run->symmetric_all = strcmp(value, "all") == 0;
    return 0;
}

static int take_shard(wc_run *run, const char *value)
{
    char *end;
    long i = strtol(value, &end, 10), n = -1;
    if (end != value && *end == '/') {
        const char *second = end + 1;
        n = strtol(second, &end, 10);
        if (end == second)
            n = -1;
    }
    if (*end || n < 1 || n > 1000000 || i < 0 || i >= n)
        return wc_usage_error("--shard wants I/N, whole numbers with 0 <= I < N, not '%s'",
                              value);
    run->shard[0] = (int)i;
    run->shard[1] = (int)n;
    run->shard_given = true;
    return 0;
}

static int take_svg(wc_run *run, const char *value)
{
    run->svg = value;
    return 0;
}

/* locate --tolerance T or T1,T2,...: numbers >= 0, one for every locator
 * or one each (the daemon checks the count against the fixels). */
static int take_locate_tolerance(wc_run *run, const char *value)
{
    cJSON *list = cJSON_CreateArray();
    const char *p = value;
    for (;;) {
        char *end;
        double t = strtod(p, &end);
        if (end == p || !(t >= 0) || !isfinite(t) || (*end && *end != ',')) {
            cJSON_Delete(list);
            return wc_usage_error("--tolerance wants T or T1,T2,T3 (numbers >= 0), not '%s'",
                                  value);
        }
        cJSON_AddItemToArray(list, cJSON_CreateNumber(t));
        if (!*end)
            break;
        p = end + 1;
    }
    cJSON_Delete(run->locate_tolerance);
    if (cJSON_GetArraySize(list) == 1) {
        run->locate_tolerance = cJSON_DetachItemFromArray(list, 0);
        cJSON_Delete(list);
    } else {
        run->locate_tolerance = list;
    }
    return 0;
}

/* --tolerance T[,A] of the analyses: each contact within T along the
 * outline, each normal within A degrees (the daemon checks them against
 * the fixture). */
static int take_geometric(wc_run *run, const char *value)
{
    double v[2] = {0, 0};
    char tail;
    int n = sscanf(value, "%lf,%lf%c", &v[0], &v[1], &tail);
    if ((n != 1 && n != 2) || !(v[0] >= 0) || !(v[1] >= 0) || !isfinite(v[0]) ||
        !isfinite(v[1]))
        return wc_usage_error("--tolerance wants T or T,A (numbers >= 0: a length along the "
                              "outline, an angle in degrees), not '%s'",
                              value);
    run->geometric[0] = v[0];
    run->geometric[1] = v[1];
    run->geometric_given = true;
    return 0;
}

/* locate --feature [NAME=]X,Y, repeated. */
static int take_feature(wc_run *run, const char *value)
{
    const char *equals = strchr(value, '=');
    const char *xy = equals ? equals + 1 : value;
    double at[2];
    char tail;
    if (sscanf(xy, "%lf,%lf%c", &at[0], &at[1], &tail) != 2 || !isfinite(at[0]) ||
        !isfinite(at[1]) || (equals && equals == value))
        return wc_usage_error("--feature wants NAME=X,Y or X,Y (hole=60,30), not '%s'", value);
    if (!run->features)
        run->features = cJSON_CreateArray();
    cJSON *f = cJSON_CreateObject();
    if (equals) {
        char name[128];
        snprintf(name, sizeof name, "%.*s", (int)(equals - value), value);
        cJSON_AddStringToObject(f, "name", name);
    }
    cJSON_AddItemToObject(f, "at", cJSON_CreateDoubleArray(at, 2));
    cJSON_AddItemToArray(run->features, f);
    return 0;
}

static int take_sigma_ratio(wc_run *run, const char *value)
{
    if (!take_number("sigma-ratio", value, &run->sigma_ratio) || !(run->sigma_ratio > 0))
        return run->sigma_ratio == 0 ? wc_usage_error("--sigma-ratio wants a number above 0")
                                     : EXIT_USAGE;
    run->sigma_ratio_given = true;
    return 0;
}

/* The options a command may take (its row's WC_OPT_* say which); each
 * takes a value. */
typedef struct command_option {
    const char *name;
    unsigned flag;
    int (*take)(wc_run *run, const char *value); /* 0, or an exit status */
} command_option;

static int take_supports(wc_run *run, const char *value)
{
    run->supports = value;
    return 0;
}

static int take_in_plane_g(wc_run *run, const char *value)
{
    char *end;
    run->in_plane_g = strtod(value, &end);
    if (end == value || *end || !(run->in_plane_g > 0) || !isfinite(run->in_plane_g))
        return wc_usage_error("--in-plane-g '%s': a number above 0 (length / s^2)", value);
    run->in_plane_g_given = true;
    return 0;
}

static int take_samples(wc_run *run, const char *value)
{
    char *end;
    long n = strtol(value, &end, 10);
    if (end == value || *end || n < 1 || n > 4096)
        return wc_usage_error("--samples '%s': a whole number from 1 to 4096", value);
    run->samples = (int)n;
    return 0;
}

/* sweep --over: the fixels' friction (the default) or the supports' mu_B. */
static int take_over(wc_run *run, const char *value)
{
    if (strcmp(value, "fixels") != 0 && strcmp(value, "supports") != 0)
        return wc_usage_error("--over is fixels or supports, not '%s'", value);
    run->over = value;
    return 0;
}

static const command_option COMMAND_OPTIONS[] = {
    {"over", WC_OPT_OVER, take_over},
    {"supports", WC_FIXTURE | WC_OPT_DESIGN, take_supports},
    {"in-plane-g", WC_OPT_TILT, take_in_plane_g},
    {"samples", WC_OPT_SAMPLES, take_samples},
    {"sets", WC_OPT_SETS, take_sets},
    {"method", WC_OPT_METHOD, take_method},
    {"tolerance", WC_OPT_TOLERANCE, take_tolerance},
    {"set", WC_OPT_SET, take_set},
    {"finger-friction", WC_OPT_FRICTION, take_friction},
    {"finger-radius", WC_OPT_RADIUS, take_radius},
    {"svg", WC_OPT_SVG, take_svg},
    {"friction", WC_OPT_INTERVAL, take_interval},
    {"push", WC_OPT_SWEEP, take_push},
    {"gravity", WC_OPT_SWEEP, take_gravity},
    {"least-force", WC_OPT_SWEEP, take_least_force},
    {"wrench", WC_OPT_SWEEP, take_wrench},
    {"range", WC_OPT_SWEEP, take_range},
    {"kinetic-ratio", WC_OPT_SWEEP, take_ratio},
    {"table", WC_OPT_SWEEP, take_table},
    {"spacing", WC_OPT_DESIGN, take_spacing},
    {"lattice", WC_OPT_DESIGN, take_lattice},
    {"fixels", WC_OPT_DESIGN, take_fixels},
    {"top", WC_OPT_DESIGN, take_top},
    {"objective", WC_OPT_DESIGN, take_objective},
    {"fixel-tolerance", WC_OPT_DESIGN, take_geometric},
    {"shard", WC_OPT_DESIGN, take_shard},
    {"tolerance", WC_OPT_LOCATE, take_locate_tolerance},
    {"tolerance", WC_OPT_GEOMETRIC, take_geometric},
    {"fixture-tolerance", WC_OPT_METHOD, take_geometric},
    {"feature", WC_OPT_LOCATE, take_feature},
    {"sigma-ratio", WC_OPT_LOCATE, take_sigma_ratio},
    {"corner-clearance", WC_OPT_DESIGN, take_clearance},
    {"pin-diameter", WC_OPT_DESIGN, take_pin_diameter},
    {"emit-fixture", WC_OPT_DESIGN, take_emit},
    {"symmetric", WC_OPT_DESIGN, take_symmetric},
    {"push-on", WC_OPT_PUSH_ON, wc_take_push_on},
    {"case", WC_OPT_CASE, wc_take_case},
    {"push", WC_OPT_FORCE, wc_take_force_push},
    {"wrench", WC_OPT_FORCE, wc_take_force_wrench},
    {"range", WC_OPT_FORCE, take_range},
    {"force", WC_OPT_PUSH_FORCE, wc_take_push_force},
    {NULL, 0, NULL},
};

/* ---- the dispatcher --------------------------------------------------------------- */

/* Take the command's options wherever they stand ("--name value",
 * "--name=value"; "--" ends them), leaving the rest, "-1,-1,0" and "-"
 * included, as its arguments, and count those.  Returns -1 to go on, or an
 * exit status. */
static int parse_command(wc_run *run, int argc, char **argv)
{
    const wc_command *c = run->command;
    run->count = 0;
    run->items = argv + 1; /* reused in place: the result is never longer */
    bool options_over = false;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        if (options_over || strncmp(a, "--", 2) != 0) {
            run->items[run->count++] = argv[i];
            continue;
        }
        if (strcmp(a, "--") == 0) {
            options_over = true;
            continue;
        }
        if (strcmp(a, "--help") == 0)
            return wc_command_help(c->name) == EXIT_INSIDE ? EXIT_INSIDE : EXIT_USAGE;
        if (strcmp(a, "--json") == 0 || strcmp(a, "--local") == 0) {
            take_global(run->o, a + 2, NULL); /* global options may follow the command */
            continue;
        }
        const char *equals = strchr(a, '=');
        size_t length = equals ? (size_t)(equals - a - 2) : strlen(a + 2);
        bool global = (length == 6 && strncmp(a + 2, "socket", 6) == 0) ||
                      (length == 7 && strncmp(a + 2, "timeout", 7) == 0);
        const command_option *k = COMMAND_OPTIONS;
        while (!global && k->name &&
               !((c->flags & k->flag) && strlen(k->name) == length &&
                 strncmp(k->name, a + 2, length) == 0))
            k++;
        if (!global && !k->name) {
            fprintf(stderr, "wrenchctl %s: no option '%s'; try 'wrenchctl %s --help'\n", c->name,
                    a, c->name);
            return EXIT_USAGE;
        }
        const char *value = equals ? equals + 1 : i + 1 < argc ? argv[++i] : NULL;
        if (!value) {
            fprintf(stderr, "wrenchctl %s: %s wants a value\n", c->name, a);
            return EXIT_USAGE;
        }
        char option_name[24];
        snprintf(option_name, sizeof option_name, "%.*s", (int)length, a + 2);
        if (global ? take_global(run->o, option_name, value) != 0 : k->take(run, value) != 0)
            return EXIT_USAGE;
        if (!global && k->take == take_emit) {
            /* The one option of two values: N, then FILE. */
            if (i + 1 >= argc) {
                fprintf(stderr, "wrenchctl %s: --emit-fixture wants N and a FILE\n", c->name);
                return EXIT_USAGE;
            }
            run->emit_file = argv[++i];
        }
    }
    if (run->count < c->min_args || run->count > c->max_args) {
        fprintf(stderr, "wrenchctl %s: %d argument%s given; try 'wrenchctl %s --help'\n", c->name,
                run->count, run->count == 1 ? "" : "s", c->name);
        return EXIT_USAGE;
    }
    return -1;
}

/* One command, its steps in the order wc.h gives. */
static int run_command(wc_options *o, const wc_command *c, int argc, char **argv)
{
    wc_run run = {.o = o, .command = c};
    int status = parse_command(&run, argc, argv);
    if (status < 0 && (c->flags & WC_DAEMON) && o->local)
        status = wc_usage_error("%s needs the daemon: --local has no store", c->name);
    if (status < 0 && (c->flags & WC_FIXTURE)) {
        run.fixture = wc_fixture_argument(o, run.items[0]);
        if (!run.fixture)
            status = EXIT_USAGE;
        else if (run.friction_interval_given)
            status = wc_fixture_friction(o, &run.fixture, run.friction_low, run.friction_high);
        if (status < 0 && run.geometric_given)
            status = wc_fixture_tolerance(o, &run.fixture, run.geometric[0], run.geometric[1]);
        if (status < 0 && run.supports)
            status = wc_fixture_supports(o, &run.fixture, run.supports);
    }
    if (status < 0 && !c->method)
        status = c->request(&run, NULL);
    cJSON *result = NULL;
    if (status < 0) {
        cJSON *params = cJSON_CreateObject();
        if (run.fixture)
            cJSON_AddItemToObject(params, "fixture", cJSON_Duplicate(run.fixture, true));
        if (c->request)
            status = c->request(&run, params);
        if (status < 0)
            result = wc_call(o, c->method, params, &status); /* takes params */
        else
            cJSON_Delete(params);
    }
    if (result) {
        if (o->json || (c->flags & WC_JSON))
            wc_print_json(result);
        else if (c->answer && run.fixture)
            wc_print_units(run.fixture);
        status = c->answer ? c->answer(&run, result) : EXIT_INSIDE;
    }
    cJSON_Delete(result);
    cJSON_Delete(run.fixture);
    cJSON_Delete(run.sets);
    cJSON_Delete(run.wrenches);
    cJSON_Delete(run.bias);
    cJSON_Delete(run.locate_tolerance);
    cJSON_Delete(run.features);
    cJSON_Delete(run.push_on);
    cJSON_Delete(run.cases);
    cJSON_Delete(run.force_push);
    cJSON_Delete(run.force_wrench);
    return status;
}

/* ---- the table of commands ---------------------------------------------------------- */

static int help_request(wc_run *run, cJSON *params);

/* --push-on, in the help of push and design; PAD as for FRICTION_HELP. */
#define PUSH_ON_HELP(PAD)                                                                    \
    "  --push-on LOOPS  " PAD "where the finger may push: outer, all, or loop numbers\n"       \
    "                   " PAD "(0,2,5; 0 the outer boundary).  Default: the outer boundary\n"  \
    "                   " PAD "and the holes wider than the finger (--finger-radius); a\n"    \
    "                   " PAD "point finger pushes on the outer boundary only\n"

/* --friction, in the help of every command that takes it; PAD (spaces)
 * brings its text to the column of the command's other options'. */
#define FRICTION_HELP(PAD)                                                                   \
    "  --friction LO:HI" PAD "every fixel's friction, static and kinetic, anywhere in\n"     \
    "                  " PAD "[LO, HI] (or MU: exactly MU), in place of the fixture's;\n"   \
    "                  " PAD "the answers are robust: each holds for every friction in\n"   \
    "                  " PAD "the interval (a stored fixture is fetched, sent inline)\n"

/* The fixture's geometric tolerance (docs/PROTOCOL.md, "Tolerance"), PAD
 * after the option as FRICTION_HELP's. */
#define GEOMETRIC_HELP(PAD)                                                                  \
    "  --tolerance T[,A]" PAD "each contact anywhere within T along the outline, each\n"     \
    "                   " PAD "normal tilted by up to A degrees: robust answers, inside\n"   \
    "                   " PAD "only if for every such fixture, outside with one that\n"      \
    "                   " PAD "shows it\n"

/* name, usage, flags, arguments (fewest, most), method, request, answer,
 * summary, help. */
const wc_command wc_commands[] = {
    {"put", "FILE",
     WC_DAEMON | WC_FIXTURE, 1, 1,
     "fixture.put", wc_put_request, wc_put_answer,
     "store a fixture; print its id",
     "Store the fixture in FILE (docs/PROTOCOL.md's JSON); print its id."},
    {"get", "ID",
     WC_DAEMON | WC_JSON, 1, 1,
     "fixture.get", wc_id_request, NULL,
     "print a stored fixture",
     "Print the stored fixture ID as JSON."},
    {"list", "",
     WC_DAEMON, 0, 0,
     "fixture.list", wc_list_request, NULL,
     "list the stored fixtures",
     "List the stored fixtures."},
    {"delete", "ID",
     WC_DAEMON, 1, 1,
     "fixture.delete", wc_id_request, wc_delete_answer,
     "forget a stored fixture",
     "Forget the stored fixture ID."},
    {"classify",
     "FIXTURE WRENCH... [--sets LIST] [--method auto|lp] [--tolerance T] [--friction LO:HI]\n"
     "       [--fixture-tolerance T[,A]]",
     WC_FIXTURE | WC_STDIN | WC_OPT_SETS | WC_OPT_METHOD | WC_OPT_TOLERANCE | WC_OPT_INTERVAL, 2,
     1 << 20,
     "wrench.classify", wc_classify_request, wc_classify_answer,
     "verdicts, margins and blocking transitions of wrenches",
     "Classify wrenches: for each set, the verdict (inside, boundary, outside), the margin, and\n"
     "when not inside the blocking transition, said in words.\n"
     "  FIXTURE          a stored fixture's id, or a fixture file (sent inline)\n"
     "  WRENCH           fx,fy,tau (torque about the centre of mass), or fx,fy@x,y (a force at\n"
     "                   a point); '-' reads JSON wrenches from stdin, one or more per line,\n"
     "                   as one batch\n"
     "  --sets LIST      comma-separated: goal, strong, both (default goal,strong)\n"
     "  --method M       auto (explicit cones, with margins; default) or lp (GLPK, no margin)\n"
     "  --tolerance T    |margin| <= T is 'boundary' (default 1e-9)\n"
     FRICTION_HELP(" ")
     "  --fixture-tolerance T[,A]  each contact anywhere within T along the outline, each\n"
     "                   normal tilted by up to A degrees: robust verdicts, inside only if\n"
     "                   for every such fixture, outside with one that shows it\n"
     "Exit status 0 when every wrench is inside every set asked, 1 when one is not."},
    {"cone", "FIXTURE STRING",
     WC_FIXTURE, 2, 2,
     "cone.get", wc_cone_request, wc_cone_answer,
     "the explicit cone of a constraint string",
     "The explicit cone G_X of a constraint string (one of s a u l r n m per fixel): its\n"
     "half-spaces F g <= 0 (open ones marked), equalities and generators, in physical units."},
    {"plan", "FIXTURE",
     WC_FIXTURE, 1, 1,
     "plan.get", NULL, wc_plan_answer,
     "contact states, excluded transitions, G_goal's cones",
     "Every contact state, the transitions it must rule out, and the cones G_goal excludes."},
    {"modes", "FIXTURE",
     WC_FIXTURE, 1, 1,
     "modes.get", NULL, wc_modes_answer,
     "the feasible moving contact modes",
     "The kinematically feasible moving contact modes, and whether the fixels pin the part."},
    {"push",
     "FIXTURE [--set SET] [--finger-friction MU] [--finger-radius R] [--push-on LOOPS]\n"
     "       [--friction LO:HI] [--tolerance T[,A]] [--svg FILE] [--force F --case SPEC...]",
     WC_FIXTURE | WC_OPT_SET | WC_OPT_FRICTION | WC_OPT_RADIUS | WC_OPT_SVG | WC_OPT_INTERVAL |
         WC_OPT_PUSH_ON | WC_OPT_CASE | WC_OPT_PUSH_FORCE | WC_OPT_GEOMETRIC,
     1, 1,
     "push.regions", wc_push_request, wc_push_answer,
     "where a finger's push seats the part",
     "The push region of a set: the open intervals of the outline where a finger pushing along\n"
     "the inward normal gives a wrench in the set, exact (a polygon edge i runs from vertex i to\n"
     "vertex i+1, t is the fraction along it; on a circle t is the angle in degrees; on an\n"
     "outline, segment S of loop L, t the fraction of its length, or of an arc's angle).\n"
     "  --set SET              goal (default), strong or both: goal reaches every fixel but\n"
     "                         may leave the part sliding on, strong holds it only once\n"
     "                         seated; push with both's region and let go\n"
     "  --finger-friction MU   a finger with friction: every force of its friction cone must be\n"
     "                         in the set (sampled and bisected; the resolution is printed)\n"
     "  --finger-radius R      a round finger of radius R (default 0, a point): only where it\n"
     "                         fits against the part without overlapping it\n"
     PUSH_ON_HELP("      ")
     "  --svg FILE             also draw the part, its fixels and the region\n"
     "  --force F              the region of a push of magnitude F (the fixture's force unit)\n"
     "                         under every --case (exact; a frictionless finger)\n"
     "  --case SPEC            a load case, repeated: see 'wrenchctl force --help'\n"
     FRICTION_HELP("       ")
     GEOMETRIC_HELP("      ")
     "Exit status 0 when there is a region, 1 when there is none."},
    {"force",
     "FIXTURE (--push X,Y[@DX,DY] | --wrench FX,FY,TAU) --case SPEC... [--sets LIST]\n"
     "       [--range LO:HI] [--tolerance T[,A]] [--svg FILE]",
     WC_FIXTURE | WC_OPT_FORCE | WC_OPT_CASE | WC_OPT_SETS | WC_OPT_GEOMETRIC | WC_OPT_SVG, 1, 1,
     "force.range", wc_force_request, wc_force_answer,
     "how hard to push: the magnitudes that do a set's job under load cases",
     "The magnitudes F of one push that seat the part (goal), hold it (strong) or both, under\n"
     "each load case and under all of them (one force for the whole sequence): exact intervals,\n"
     "in the fixture's force unit.\n"
     "  --push X,Y          a unit force at (X, Y) on the outline, along the inward normal;\n"
     "                      X,Y@DX,DY along (DX, DY) instead\n"
     "  --wrench FX,FY,TAU  or a direction of wrench (scaled to unit length)\n"
     "  --case SPEC         a case, repeated: [NAME:]LOAD[;LOAD...] with LOAD one of\n"
     "                      gravity=G@DEG (m G pulling along DEG degrees: 270 is down),\n"
     "                      force=FX,FY@X,Y (a force at a point), wrench=FX,FY,TAU\n"
     "  --sets LIST         comma-separated: goal, strong, both (default all three)\n"
     "  --range LO:HI       only magnitudes in [LO, HI]\n"
     "  --svg FILE          also draw the part, its fixels, its supports with their friction\n"
     "                      discs, the push and the least force\n"
     GEOMETRIC_HELP(" ")
     "A fixture on supports (its \"supports\" member) answers goal alone: the magnitudes that\n"
     "seat it against the supports' friction; its least is the least push force on the plate.\n"
     "Exit status 0 when one magnitude does 'both' under every case, 1 when none does."},
    {"push-force",
     "FIXTURE --case SPEC... [--set SET] [--finger-radius R] [--push-on LOOPS] [--samples N]\n"
     "       [--svg FILE] [--tolerance T[,A]]",
     WC_FIXTURE | WC_OPT_CASE | WC_OPT_SET | WC_OPT_RADIUS | WC_OPT_SVG | WC_OPT_PUSH_ON |
         WC_OPT_GEOMETRIC | WC_OPT_SAMPLES,
     1, 1,
     "push.force", wc_push_force_request, wc_push_force_answer,
     "the least push force along the outline, and where it is least",
     "F*(p), the least force of a push along the inward normal at p that does the set's job\n"
     "(default both) under every case, sampled exactly along every segment, and its minimum\n"
     "over the outline (branch and bound: the point where the smallest push suffices).\n"
     "  --case SPEC         a load case, repeated (see 'wrenchctl force --help')\n"
     "  --set SET           goal, strong or both (default)\n"
     "  --finger-radius R   only where a round finger of radius R fits\n"
     PUSH_ON_HELP("  ")
     "  --samples N         exact samples a segment (1 to 4096, default 64); without\n"
     "                      --tolerance the least is found by branch and bound whatever N is\n"
     "  --svg FILE          draw F* as a coloured band along the outline, with the least push\n"
     "On supports (--supports, or the fixture's member) with --set goal: the least push that\n"
     "seats the part against the supports' friction, on a polygon, for a point finger.\n"
     GEOMETRIC_HELP("   ")
     "With --tolerance each F* is robust: a push of that force does the job on every such\n"
     "fixture, and the least is the least of the samples (and of the nominal least's point).\n"
     "Exit status 0 when some push does the job, 1 when none does."},
    {"gravity", "FIXTURE [--set SET] [--friction LO:HI] [--tolerance T[,A]] [--svg FILE]\n"
     "       [--supports FILE|JSON --in-plane-g A]",
     WC_FIXTURE | WC_OPT_SET | WC_OPT_SVG | WC_OPT_INTERVAL | WC_OPT_GEOMETRIC | WC_OPT_TILT, 1, 1,
     "gravity.sweep", wc_gravity_request, wc_gravity_answer,
     "the tilts under which gravity seats the part",
     "The arcs of tilt (the direction gravity pulls, degrees, in the part's frame) under which\n"
     "gravity alone gives a wrench in the set.\n"
     "  --set SET         goal (default), strong or both (goal may leave the part sliding\n"
     "                    on, strong holds it only once seated; both does both)\n"
     "  --svg FILE        also draw the sweep as a dial around the part\n"
     "  --in-plane-g A    on supports (its \"supports\" member, or --supports): the pull in\n"
     "                    the tilted plate's plane, g sin(tilt); the tilts whose pull m A\n"
     "                    seats the part against the supports' friction (set goal)\n"
     FRICTION_HELP("  ")
     GEOMETRIC_HELP(" ")
     "Exit status 0 when there is an arc, 1 when there is none."},
    {"margin", "FIXTURE BIAS [--friction LO:HI] [--tolerance T[,A]] [--svg FILE]",
     WC_FIXTURE | WC_OPT_SVG | WC_OPT_INTERVAL | WC_OPT_GEOMETRIC, 2, 2,
     "stability.margin", wc_margin_request, wc_margin_answer,
     "how large a disturbance a biasing wrench tolerates",
     "The disturbance margin of a biasing wrench (fx,fy,tau or fx,fy@x,y): how large a\n"
     "disturbance, in the scaled metric (f_x, f_y, tau/rho), the seated part holds under it,\n"
     "the contact mode the worst one starts, and that worst direction.\n"
     "  --svg FILE        also draw the bias and the worst disturbance on the part\n"
     FRICTION_HELP("  ")
     GEOMETRIC_HELP(" ")
     "Exit status 0 when the bias holds the part (margin > 0), 1 when it does not."},
    {"sweep",
     "FIXTURE (--push SET | --gravity SET | --least-force SET --case SPEC... |\n"
     "       --wrench FX,FY,TAU... [--set SET]) [--range LO:HI] [--kinetic-ratio R]\n"
     "       [--finger-friction MU] [--finger-radius R] [--push-on LOOPS] [--svg FILE]\n"
     "       [--table full|summary] [--tolerance T[,A]]\n"
     "       [--over supports [--supports FILE|JSON] [--force F] [--in-plane-g A]]",
     WC_FIXTURE | WC_OPT_SWEEP | WC_OPT_SET | WC_OPT_FRICTION | WC_OPT_RADIUS | WC_OPT_SVG |
         WC_OPT_CASE | WC_OPT_PUSH_ON | WC_OPT_GEOMETRIC | WC_OPT_OVER | WC_OPT_PUSH_FORCE |
         WC_OPT_TILT,
     1, 1,
     "friction.sweep", wc_sweep_request, wc_sweep_answer,
     "how the answers change with the friction",
     "Sweep the friction: mu_s = mu and mu_k = R mu at every fixel (the fixture's own friction\n"
     "ignored), for mu over a range; one of:\n"
     "  --push SET          the push region of SET (goal, strong or both): the mu where it is\n"
     "                      not empty, the critical mu above which it is (none when it is not\n"
     "                      empty at the top of the range), and its length against mu\n"
     "  --gravity SET       the same for the gravity arcs, their total in degrees\n"
     "  --least-force SET   the least push force doing SET's job under every --case (a load\n"
     "                      case, as for force), minimised over the outline, and where: each\n"
     "                      value exact at its mu, on a grid of 128 and at the ends of the\n"
     "                      exact intervals of mu where the push alone has a region\n"
     "  --wrench FX,FY,TAU  a wrench (torque about the centre of mass), repeated for more: for\n"
     "                      each, and each set, the mu where it is inside\n"
     "  --set SET           with --wrench: one set (default goal and strong)\n"
     "  --range LO:HI       the range of mu, 0 <= LO < HI (default 0:2)\n"
     "  --kinetic-ratio R   mu_k = R mu, 0 < R <= 1 (default 1)\n"
     "  --finger-friction MU, --finger-radius R\n"
     "                      with --push: the finger, as for push (--least-force: the radius)\n"
     PUSH_ON_HELP("   ")
     "  --table full        every point of the curve (default: a summary, the points nearest\n"
     "                      9 evenly spaced mu and those at the intervals' ends)\n"
     "  --svg FILE          also plot the length (or the arcs) against mu, the intervals shaded\n"
     "                      and the critical mu marked; for wrenches a band per wrench and set\n"
     "  --tolerance T[,A]   robust over every fixture with each contact within T along the\n"
     "                      outline, each normal tilted by up to A degrees: --wrench the mu\n"
     "                      where the wrench is inside on all of them; --push and --gravity\n"
     "                      the mu where the robust region is proved not empty, its length\n"
     "                      at each mu; --least-force push-force's robust least at each mu\n"
     "                      (a frictionless finger: --finger-friction is refused)\n"
     "  --over supports     a fixture on a base plate (its \"supports\", or --supports): sweep\n"
     "                      the supports' mu_B instead: --wrench goal exact, strong and\n"
     "                      both sampled (every mu_B given proved held);\n"
     "                      --push goal with --force F (and --case, --push-on): where a push\n"
     "                      that hard seats it; --gravity goal with --in-plane-g A: the tilts\n"
     "                      whose pull seats it; both shrink as mu_B grows, and the critical\n"
     "                      mu_B is bisected to 1e-9\n"
     "On supports without --over: the fixels' mu swept, the buttons' friction kept: for\n"
     "--wrench goal is exact, strong and both sampled (every mu given proved held);\n"
     "--least-force, --push and --gravity as with --over supports.\n"     "Exit status 0 when the region is not empty for some mu (for wrenches: when each wrench is\n"
     "inside each set for some mu; for the least force: when some push does it at some mu),\n"
     "1 when not."},
    {"locate", "FIXTURE --tolerance T[,T2,T3] [--feature [NAME=]X,Y]... [--sigma-ratio R]\n"
     "       [--svg FILE]",
     WC_FIXTURE | WC_OPT_LOCATE | WC_OPT_SVG, 1, 1,
     "fixture.locating", wc_locate_request, wc_locate_answer,
     "where locator errors put the part, and its features",
     "Locating accuracy: each locator may be off by +-T along its normal (one T for all, or\n"
     "one per fixel).  Prints whether the fixels determine the pose (else the motion left\n"
     "free), G^-1 (the pose's change per unit locator error) and its condition number, the\n"
     "worst pose error over the tolerance box, linear and exact (the pose solved on the\n"
     "outline), and for each feature its worst displacement, linear and exact, and its\n"
     "99.73 % error ellipse under normal errors of sigma = T / R.  Lengths in the fixture's\n"
     "unit, angles in radians.\n"
     "  --tolerance T       how far each locator may be off (T1,T2,T3: one per fixel)\n"
     "  --feature NAME=X,Y  a point of the part (a hole to drill), repeated for more\n"
     "  --sigma-ratio R     sigma = T / R for the ellipses (default 3)\n"
     "  --svg FILE          also draw the ellipses, the worst displacements and the part at\n"
     "                      the worst corner of the box, magnified (the scale stated)\n"
     "Exit status 0 when the fixels determine the pose, 1 when they do not."},
    {"design",
     "BODY [--spacing H | --lattice P,R,NXxNY] [--fixels K]\n"
     "       [--objective margin|region|gravity|force|accuracy|pareto] [--top N] [--friction LO:HI]\n"
     "       [--finger-radius R] [--finger-friction MU] [--case SPEC...]\n"
     "       [--tolerance T [--feature NAME=X,Y]...] [--push-on LOOPS]\n"
     "       [--corner-clearance C] [--pin-diameter D]\n"
     "       [--shard I/N] [--symmetric collapse|all] [--svg FILE] [--emit-fixture N FILE]\n"
     "       [--fixel-tolerance T[,A]] [--supports FILE|JSON]",
     WC_OPT_DESIGN | WC_OPT_INTERVAL | WC_OPT_RADIUS | WC_OPT_FRICTION | WC_OPT_SVG |
         WC_OPT_PUSH_ON | WC_OPT_LOCATE | WC_OPT_CASE, 1, 1,
     "fixture.design", wc_design_request, wc_design_answer,
     "where to put the fixels, and where to push",
     "Design a fixture for a body: every choice of K candidate sites is a candidate; the best\n"
     "are ranked, each with its best push (the point of the both region whose push has the\n"
     "largest margin: push there and let go), its push regions' lengths, its longest gravity\n"
     "arc and its critical mu.  A progress bar on a terminal, with the time left.\n"
     "  BODY               a JSON file: a fixture (its body and friction are used, and its\n"
     "                     fixels are the candidate sites unless --spacing is given) or a\n"
     "                     body alone\n"
     "  --spacing H        candidate sites every H along each loop's length, across the\n"
     "                     joints of faceted curves, clear of corners (turns of more than\n"
     "                     20 degrees) by --corner-clearance C (default H/2)\n"
     "  --pin-diameter D   sites on a hole are pins of diameter D, kept where one fits\n"
     "  --lattice P,R,NXxNY  a modular fixture plate: holes at pitch P, pegs of radius R,\n"
     "                     NX by NY holes; every pose of the part touching three pegs\n"
     "  --fixels K         fixels per design (default 3)\n"
     "  --objective O      margin (the best push's; default), region (the both region's\n"
     "                     length), gravity (the longest goal arc of tilts), force (the least\n"
     "                     push force doing both under every --case, smallest first) or\n"
     "                     accuracy (the smallest worst locating error with --tolerance T and\n"
     "                     the --feature points, as for locate; without features the pose's,\n"
     "                     scaled) or pareto (with --tolerance T: the designs no other beats\n"
     "                     on margin, accuracy and, with --case, least force together)\n"
     "  --case SPEC        a load case, repeated (see 'wrenchctl force --help'): each design\n"
     "                     also reports its least push under them, with any objective; in the\n"
     "                     file's units (its \"units\", else one consistent system)\n"
     "  --top N            how many designs (default 10)\n"
     "  --fixel-tolerance T[,A]  each design's fixels anywhere within T along the outline,\n"
     "                     each normal tilted by up to A degrees: its both region and best\n"
     "                     push are those that work for every such fixture\n"
     "  --supports FILE|JSON  the base plate under every candidate (a fixture's \"supports\",\n"
     "                     else the file's own): --objective force ranks by the least push\n"
     "                     that seats the part on it (accuracy as floating; others refused)\n"
     "  --friction LO:HI   the friction on every fixel (or MU); default the file's\n"
     "  --finger-radius R, --finger-friction MU\n"
     "                     the finger that pushes, as for push\n"
     PUSH_ON_HELP("  ")
     "  --shard I/N        evaluate shard I of N of the candidates only, and write JSON lines\n"
     "                     for design-merge (examples/design-array.sbatch runs it on Slurm)\n"
     "  --symmetric collapse|all  designs that a symmetry of the part (a turn or a mirror)\n"
     "                     maps onto each other: listed once with how many more it stands\n"
     "                     for (collapse, the default), or every one (all)\n"
     "  --svg FILE         also draw the best designs side by side: the part, its fixels\n"
     "                     (pegs on a lattice, pins at their diameter), the both region and\n"
     "                     the best push (with --json too)\n"
     "  --emit-fixture N FILE  write design N (its rank) as a fixture file that every other\n"
     "                     command takes: the body, the friction, the design's fixels\n"
     "Exit status 0 when some design has a push that seats and holds the part, 1 when none."},
    {"design-merge", "SHARD_OUTPUT...",
     WC_STDIN, 1, 1 << 20,
     NULL, wc_design_merge_request, NULL,
     "merge the outputs of design --shard into one answer",
     "Merge the JSON lines that 'design --shard I/N' wrote (files, or '-' for stdin) into\n"
     "exactly the answer of one design over every candidate: the designs ranked again by\n"
     "score, then candidate number, the first --top kept, the counts summed.  Shards missing\n"
     "are named on stderr.  With --json the merged answer as fixture.design gives it.\n"
     "Exit status 0 when some design has a push that seats and holds the part, 1 when none."},
    {"status", "",
     WC_DAEMON, 0, 0,
     "server.status", NULL, wc_status_answer,
     "the daemon's version, uptime and counts",
     "The daemon's version, uptime and counts."},
    {"help", "[COMMAND]",
     0, 0, 1,
     NULL, help_request, NULL,
     "help on wrenchctl or on one command",
     "Help on wrenchctl, or on one command."},
    {NULL, NULL, 0, 0, 0, NULL, NULL, NULL, NULL, NULL},
};

/* ---- help ------------------------------------------------------------------------- */

static const char GENERAL[] =
    "Usage: wrenchctl [OPTION]... COMMAND [ARGUMENT]...\n"
    "Ask wrenchd where and how a planar part can be pushed to seat in its fixture.\n"
    "\n"
    "Options (before or after the command):\n"
    "  --socket PATH      the daemon's socket (default $WRENCHD_SOCKET, else ./run/wrenchd.sock)\n"
    "  --timeout SECONDS  give up on the daemon after this long (default 30)\n"
    "  --json             print the result as JSON instead of a table\n"
    "  --local            compute in process with libwrench: no daemon, fixtures from files\n"
    "  --help, --version\n"
    "\n"
    "Commands:\n";

static const char EXIT_TEXT[] =
    "\nExit status: 0 done (classify: every wrench inside; push, gravity: a region; margin:\n"
    "the bias holds; sweep: not empty for some mu); 1 not so; 2 usage error; 3 the daemon is\n"
    "unreachable; 4 the daemon answered an error.\n";

int wc_command_help(const char *name)
{
    for (const wc_command *c = wc_commands; c->name; c++)
        if (strcmp(c->name, name) == 0) {
            printf("Usage: wrenchctl [OPTION]... %s %s\n%s\n", c->name, c->usage, c->help);
            return EXIT_INSIDE;
        }
    return wc_usage_error("no command '%s'; try 'wrenchctl --help'", name);
}

void wc_general_help(void)
{
    fputs(GENERAL, stdout);
    for (const wc_command *c = wc_commands; c->name; c++)
        printf("  %-9s %s\n", c->name, c->summary);
    fputs("\n'wrenchctl COMMAND --help' says more about one command.", stdout);
    fputs(EXIT_TEXT, stdout);
}

static int help_request(wc_run *run, cJSON *params)
{
    (void)params;
    if (run->count == 1)
        return wc_command_help(run->items[0]);
    wc_general_help();
    return EXIT_INSIDE;
}

/* ---- main ------------------------------------------------------------------------- */

int main(int argc, char **argv)
{
    wc_options o = {getenv("WRENCHD_SOCKET"), 30, false, false, NULL, NULL};
    if (!o.socket_path || !*o.socket_path)
        o.socket_path = "./run/wrenchd.sock";
    static const struct option global[] = {
        {"socket", required_argument, NULL, 'S'}, {"timeout", required_argument, NULL, 'T'},
        {"json", no_argument, NULL, 'j'},         {"local", no_argument, NULL, 'l'},
        {"help", no_argument, NULL, 'h'},         {"version", no_argument, NULL, 'V'},
        {NULL, 0, NULL, 0},
    };
    int option;
    /* "+": stop at the command; its own options are parsed after it. */
    while ((option = getopt_long(argc, argv, "+", global, NULL)) != -1) {
        switch (option) {
        case 'S': take_global(&o, "socket", optarg); break;
        case 'T':
            if (take_global(&o, "timeout", optarg) != 0)
                return EXIT_USAGE;
            break;
        case 'j': o.json = true; break;
        case 'l': o.local = true; break;
        case 'h': wc_general_help(); return EXIT_INSIDE;
        case 'V': printf("wrenchctl %s\n", WR_VERSION); return EXIT_INSIDE;
        default: fputs("Try 'wrenchctl --help'.\n", stderr); return EXIT_USAGE;
        }
    }
    if (optind >= argc) {
        wc_general_help();
        return EXIT_USAGE;
    }
    for (const wc_command *c = wc_commands; c->name; c++)
        if (strcmp(c->name, argv[optind]) == 0)
            return run_command(&o, c, argc - optind, argv + optind);
    return wc_usage_error("no command '%s'; try 'wrenchctl --help'", argv[optind]);
}
