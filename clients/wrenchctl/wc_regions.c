/* wc_regions.c -- docs/MODEL.md section 6's answers: push (where a finger's push
 * seats the part), gravity (the tilts under which gravity does) and margin
 * (how large a disturbance a biasing wrench tolerates), and sweep (how the
 * push region, the gravity arcs or wrenches' verdicts change with the
 * friction); each as a table and, with --svg, a picture (wc_svg.h). */
#include "wc_call.h"
#include "wc_commands.h"
#include "wc_print.h"
#include "wc_explain.h" /* generated from clients/python/wrenchd.py */
#include "wc_svg.h"

#include "wp_fixture.h"

#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* ---- pictures ---------------------------------------------------------------- */

/* The fixture's geometry for a picture: the file, or the stored fixture.
 * NULL after saying why. */
static wr_fixture *fixture_geometry(wc_options *o, const cJSON *fixture, char *name, size_t size)
{
    cJSON *json = NULL;
    if (cJSON_IsString(fixture)) {
        int status;
        cJSON *params = cJSON_CreateObject();
        cJSON_AddStringToObject(params, "id", fixture->valuestring);
        json = wc_call(o, "fixture.get", params, &status);
        if (!json)
            return NULL;
    } else {
        json = cJSON_Duplicate(fixture, true);
    }
    wp_fixture_doc doc;
    wp_error error;
    bool ok = wp_fixture_read(json, "fixture", &doc, &error);
    cJSON_Delete(json);
    if (!ok) {
        wc_usage_error("%s: %s", error.field, error.reason);
        return NULL;
    }
    snprintf(name, size, "%s", doc.name[0] ? doc.name : "fixture");
    wr_fixture *geometry = doc.fixture;
    doc.fixture = NULL;
    wp_fixture_doc_release(&doc);
    return geometry;
}

/* A picture for --svg: the fixture's geometry (file or stored) and the
 * open file.  NULL after saying why (nothing left to release). */
static FILE *svg_begin(wc_options *o, const cJSON *fixture, const char *path, char name[128],
                       wr_fixture **geometry)
{
    *geometry = fixture_geometry(o, fixture, name, 128);
    if (!*geometry)
        return NULL;
    FILE *out = fopen(path, "w");
    if (!out) {
        wc_usage_error("--svg %s: %s", path, strerror(errno));
        wr_fixture_free(*geometry);
        *geometry = NULL;
    }
    return out;
}

static void svg_end(FILE *out, wr_fixture *geometry)
{
    fclose(out);
    wr_fixture_free(geometry);
}

/* Draws the answer `result` on the part; false after saying why not. */
typedef bool (*drawing)(const wc_run *run, const cJSON *result, FILE *out,
                        const wr_fixture *geometry, const char *name);

/* With --svg, the picture: -1, or EXIT_USAGE after saying why there is
 * none. */
static int picture(wc_run *run, const cJSON *result, drawing draw)
{
    if (!run->svg)
        return -1;
    char name[128];
    wr_fixture *geometry;
    FILE *out = svg_begin(run->o, run->fixture, run->svg, name, &geometry);
    if (!out)
        return EXIT_USAGE;
    bool drawn = draw(run, result, out, geometry, name);
    svg_end(out, geometry);
    return drawn ? -1 : EXIT_USAGE;
}

int wc_picture(wc_run *run, const cJSON *result, wc_drawing draw)
{
    return picture(run, result, draw);
}

/* The set asked, for the tables and pictures. */
static const char *set_name(const wc_run *run)
{
    return run->set ? run->set : "goal";
}

/* ---- push --------------------------------------------------------------------- */

int wc_push_request(wc_run *run, cJSON *params)
{
    if (run->set)
        cJSON_AddStringToObject(params, "set", run->set);
    if (run->friction_given)
        cJSON_AddNumberToObject(params, "finger_friction", run->finger_friction);
    if (run->radius_given)
        cJSON_AddNumberToObject(params, "finger_radius", run->finger_radius);
    int status = wc_push_on(run,
                            cJSON_IsString(run->fixture) ? run->fixture
                                                         : cJSON_GetObjectItem(run->fixture, "body"),
                            params);
    return status >= 0 ? status : wc_push_loads(run, params);
}

/* Does the answer name its regions by loop and segment (an outline)? */
static bool by_segment(const cJSON *regions)
{
    return cJSON_HasObjectItem(cJSON_GetArrayItem(regions, 0), "loop");
}

/* An empty answer's why_empty, in words: each reason with its count of
 * the edges whose middle it blocks. */
static void explain_empty(const cJSON *why)
{
    const cJSON *reasons = cJSON_GetObjectItem(why, "reasons"), *r;
    int edges = 0;
    cJSON_ArrayForEach(r, reasons) edges += (int)cJSON_GetNumberValue(cJSON_GetObjectItem(r, "edges"));
    if (edges == 0)
        return;
    printf(WC_EXPLAIN_EMPTY_REGION "\n", edges);
    cJSON_ArrayForEach(r, reasons)
    {
        char words[512];
        const char *blocking = cJSON_GetStringValue(cJSON_GetObjectItem(r, "blocking"));
        const char *set = cJSON_GetStringValue(cJSON_GetObjectItem(r, "set"));
        if (!blocking)
            snprintf(words, sizeof words, "%s", WC_EXPLAIN_NO_DESIGN_UNREACHED);
        else if (set && strcmp(set, "goal") == 0)
            wc_explain_goal(blocking, cJSON_GetObjectItem(r, "states"), words, sizeof words);
        else
            wc_explain_strong(blocking, words, sizeof words);
        printf("  %d of %d: %s\n", (int)cJSON_GetNumberValue(cJSON_GetObjectItem(r, "edges")), edges,
               words);
    }
}

/* The number of segments of loop `loop` of the fixture's shape (a
 * polygon's edges as loop 0, a circle 1), 0 when not known (a stored
 * fixture). */
static int segments_of(const cJSON *fixture, int loop)
{
    const cJSON *shape = cJSON_GetObjectItem(cJSON_GetObjectItem(fixture, "body"), "shape");
    const cJSON *loops = cJSON_GetObjectItem(shape, "loops");
    if (loops)
        return cJSON_GetArraySize(cJSON_GetArrayItem(loops, loop));
    if (cJSON_GetObjectItem(shape, "vertices"))
        return cJSON_GetArraySize(cJSON_GetObjectItem(shape, "vertices"));
    return cJSON_GetObjectItem(shape, "center") ? 1 : 0;
}

/* A row of the push table: the regions order[first..first + count - 1],
 * which continue one another across the joints between segments. */
typedef struct push_row {
    int first, count;
    double length;
} push_row;

/* Does region b continue region a: the same loop, b starting at the joint
 * where a ends (a circle: at 0 degrees where a ends at 360)? */
static bool continues(const cJSON *a, const cJSON *b, int segments, bool outline, bool circle)
{
    const char *key = outline ? "segment" : "edge";
    double end = circle ? 360 : 1;
    if (outline && cJSON_GetNumberValue(cJSON_GetObjectItem(a, "loop")) !=
                       cJSON_GetNumberValue(cJSON_GetObjectItem(b, "loop")))
        return false;
    int sa = (int)cJSON_GetNumberValue(cJSON_GetObjectItem(a, key));
    int sb = (int)cJSON_GetNumberValue(cJSON_GetObjectItem(b, key));
    return segments > 0 && sb == (sa + 1) % segments &&
           cJSON_GetNumberValue(cJSON_GetObjectItem(a, "t1")) >= end * (1 - 1e-9) &&
           cJSON_GetNumberValue(cJSON_GetObjectItem(b, "t0")) <= end * 1e-9;
}

static int loop_of_region(const cJSON *r, bool outline)
{
    return outline ? (int)cJSON_GetNumberValue(cJSON_GetObjectItem(r, "loop")) : 0;
}

/* The rows of `regions` (in the answer's order, by loop, segment, t0):
 * consecutive pieces that continue one another are one row, and a loop's
 * last row that runs on past its vertex 0 into the loop's first row is
 * one row with it, starting with the last's pieces.  Fills order (count
 * region indices) and rows; returns the number of rows. */
static int push_rows(const cJSON *regions, const cJSON *fixture, bool outline, bool circle,
                     int *order, push_row *rows)
{
    int count = cJSON_GetArraySize(regions), row_count = 0;
    for (int i = 0; i < count; i++) {
        const cJSON *r = cJSON_GetArrayItem(regions, i);
        int segments = fixture ? segments_of(fixture, loop_of_region(r, outline)) : 0;
        double length = cJSON_GetNumberValue(cJSON_GetObjectItem(r, "length"));
        order[i] = i;
        if (row_count > 0 && continues(cJSON_GetArrayItem(regions, i - 1), r, segments, outline,
                                       circle)) {
            rows[row_count - 1].count++;
            rows[row_count - 1].length += length;
        } else {
            rows[row_count++] = (push_row){i, 1, length};
        }
    }
    /* Each loop's rows a..b: if b runs on into a, b's pieces go first. */
    for (int a = 0; a < row_count; a++) {
        int loop = loop_of_region(cJSON_GetArrayItem(regions, order[rows[a].first]), outline);
        int b = a;
        while (b + 1 < row_count &&
               loop_of_region(cJSON_GetArrayItem(regions, order[rows[b + 1].first]), outline) == loop)
            b++;
        const cJSON *end = cJSON_GetArrayItem(regions, order[rows[b].first + rows[b].count - 1]);
        const cJSON *start = cJSON_GetArrayItem(regions, order[rows[a].first]);
        if (b > a && continues(end, start, fixture ? segments_of(fixture, loop) : 0, outline,
                               circle)) {
            /* order[a's first .. b's end]: b's pieces, then a's, then the rest. */
            int from = rows[a].first, moved = rows[b].count;
            int span = rows[b].first + moved - from;
            int *copy = malloc((size_t)span * sizeof *copy);
            if (copy) {
                memcpy(copy, order + rows[b].first, (size_t)moved * sizeof *copy);
                memcpy(copy + moved, order + from, (size_t)(span - moved) * sizeof *copy);
                memcpy(order + from, copy, (size_t)span * sizeof *copy);
                free(copy);
                rows[a].count += moved;
                rows[a].length += rows[b].length;
                for (int k = a + 1; k < b; k++)
                    rows[k].first += moved;
                memmove(rows + b, rows + b + 1, (size_t)(row_count - b - 1) * sizeof *rows);
                row_count--;
                b--;
            }
        }
        a = b;
    }
    return row_count;
}

static void print_push(const wc_run *run, const cJSON *result)
{
    const cJSON *regions = cJSON_GetObjectItem(result, "regions");
    int count = cJSON_GetArraySize(regions);
    double fraction = cJSON_GetNumberValue(cJSON_GetObjectItem(result, "fraction"));
    bool outline = by_segment(regions);
    const cJSON *fixture = cJSON_IsObject(run->fixture) ? run->fixture : NULL;
    const cJSON *shape = cJSON_GetObjectItem(cJSON_GetObjectItem(fixture, "body"), "shape");
    bool circle = cJSON_GetObjectItem(shape, "center") != NULL;
    int decimals = wc_drawing_decimals(shape);
    int *order = calloc((size_t)(count ? count : 1), sizeof *order);
    push_row *rows = calloc((size_t)(count ? count : 1), sizeof *rows);
    int row_count = order && rows ? push_rows(regions, fixture, outline, circle, order, rows) : 0;
/* No regions, no table: an outline's empty answer does not say it is
     * one, so no header could be the right one. */
    if (row_count > 0 && outline)
        printf("%4s  ", "loop");
    if (row_count > 0)
        printf("%-9s  %-26s  %-26s  %12s\n", outline ? "segments" : "edges", "from", "to",
               "length");
    for (int k = 0; k < row_count; k++) {
        const cJSON *first = cJSON_GetArrayItem(regions, order[rows[k].first]);
        const cJSON *last = cJSON_GetArrayItem(regions, order[rows[k].first + rows[k].count - 1]);
        const char *key = outline ? "segment" : "edge";
        char a_text[64], b_text[64], which[32];
        wc_point_text(cJSON_GetObjectItem(first, "from"), decimals, a_text, sizeof a_text);
        wc_point_text(cJSON_GetObjectItem(last, "to"), decimals, b_text, sizeof b_text);
        int s0 = (int)cJSON_GetNumberValue(cJSON_GetObjectItem(first, key));
        int s1 = (int)cJSON_GetNumberValue(cJSON_GetObjectItem(last, key));
        if (rows[k].count == 1)
            snprintf(which, sizeof which, "%d", s0);
        else
            snprintf(which, sizeof which, "%d-%d", s0, s1);
        if (outline)
            printf("%4d  ", (int)cJSON_GetNumberValue(cJSON_GetObjectItem(first, "loop")));
        printf("%-9s  %-26s  %-26s  %12.*f\n", which, a_text, b_text, decimals < 0 ? 6 : decimals,
               rows[k].length);
        /* Its pieces, each segment's t0 and t1 as the answer gives them. */
        printf("%s  pieces:", outline ? "    " : "");
        for (int p = 0; p < rows[k].count; p++) {
            const cJSON *r = cJSON_GetArrayItem(regions, order[rows[k].first + p]);
            printf("%s %s %d t %.6g-%.6g", p ? "," : "", key,
                   (int)cJSON_GetNumberValue(cJSON_GetObjectItem(r, key)),
                   cJSON_GetNumberValue(cJSON_GetObjectItem(r, "t0")),
                   cJSON_GetNumberValue(cJSON_GetObjectItem(r, "t1")));
        }
        printf("\n");
    }
    free(rows);
    free(order);
    printf("set %s: %d region%s (%d piece%s), length %.6g, %.2f%% of the outline", set_name(run),
           row_count, row_count == 1 ? "" : "s", count, count == 1 ? "" : "s",
           cJSON_GetNumberValue(cJSON_GetObjectItem(result, "total_length")), 100 * fraction);
    if (cJSON_IsFalse(cJSON_GetObjectItem(result, "exact")))
        printf(" (sampled: resolution %g)",
               cJSON_GetNumberValue(cJSON_GetObjectItem(result, "resolution")));
    printf("\n");
    if (count == 0)
        explain_empty(cJSON_GetObjectItem(result, "why_empty"));
    if (strcmp(set_name(run), "both") != 0)
        printf("%s\n", wc_set_promise(set_name(run)));
}

/* An outline's region (loop, segment) as wc_svg_push's edge: the segments
 * of every loop counted in order, loop 0's first.  False for a place the
 * outline does not have. */
static bool outline_edge(const wr_fixture *geometry, const cJSON *region, int *edge)
{
    const cJSON *loop = cJSON_GetObjectItem(region, "loop");
    const cJSON *segment = cJSON_GetObjectItem(region, "segment");
    const wr_outline *o = geometry->outline;
    if (geometry->shape != WR_SHAPE_OUTLINE || !o || !cJSON_IsNumber(loop) ||
        !cJSON_IsNumber(segment) || !(loop->valuedouble >= 0) ||
        !(loop->valuedouble < (double)o->loop_count))
        return false;
    size_t l = (size_t)loop->valuedouble;
    if (!(segment->valuedouble >= 0) ||
        !(segment->valuedouble < (double)o->loops[l].segment_count))
        return false;
    size_t before = 0;
    for (size_t i = 0; i < l; i++)
        before += o->loops[i].segment_count;
    *edge = (int)(before + (size_t)segment->valuedouble);
    return true;
}

static bool draw_push(const wc_run *run, const cJSON *result, FILE *out,
                      const wr_fixture *geometry, const char *name)
{
    const cJSON *regions = cJSON_GetObjectItem(result, "regions");
    int count = cJSON_GetArraySize(regions);
    wr_region *items = calloc((size_t)(count ? count : 1), sizeof *items);
    int i = 0;
    const cJSON *r;
    cJSON_ArrayForEach(r, regions)
    {
        if (cJSON_HasObjectItem(r, "loop")) {
            if (!outline_edge(geometry, r, &items[i].edge)) {
                free(items);
                wc_usage_error("--svg: region %d of the answer is on no segment of the outline", i);
                return false;
            }
        } else {
            items[i].edge = (int)cJSON_GetNumberValue(cJSON_GetObjectItem(r, "edge"));
        }
        items[i].t0 = cJSON_GetNumberValue(cJSON_GetObjectItem(r, "t0"));
        items[i].t1 = cJSON_GetNumberValue(cJSON_GetObjectItem(r, "t1"));
        i++;
    }
    wc_svg_push(out, geometry, name, set_name(run), items, count,
                cJSON_GetNumberValue(cJSON_GetObjectItem(result, "fraction")),
                run->finger_friction, run->radius_given ? run->finger_radius : -1);
    free(items);
    return true;
}

/* With --friction, the line saying so above the table. */
static void print_friction(const wc_run *run)
{
    if (!run->o->json && run->friction_interval_given)
        wc_print_friction(run->friction_low, run->friction_high);
}

int wc_push_answer(wc_run *run, const cJSON *result)
{
    print_friction(run);
    if (!run->o->json)
        print_push(run, result);
    int status = picture(run, result, draw_push);
    if (status >= 0)
        return status;
    return cJSON_GetArraySize(cJSON_GetObjectItem(result, "regions")) > 0 ? EXIT_INSIDE
                                                                          : EXIT_NOT_INSIDE;
}

/* ---- gravity ------------------------------------------------------------------ */

int wc_gravity_request(wc_run *run, cJSON *params)
{
    if (run->set)
        cJSON_AddStringToObject(params, "set", run->set);
    if (run->in_plane_g_given)
        cJSON_AddNumberToObject(params, "in_plane_g", run->in_plane_g);
    return -1;
}

static bool draw_gravity(const wc_run *run, const cJSON *result, FILE *out,
                         const wr_fixture *geometry, const char *name)
{
    const cJSON *arcs = cJSON_GetObjectItem(result, "intervals_deg");
    int count = cJSON_GetArraySize(arcs);
    wr_region *items = calloc((size_t)(count ? count : 1), sizeof *items);
    for (int i = 0; i < count; i++) {
        items[i].t0 = cJSON_GetArrayItem(cJSON_GetArrayItem(arcs, i), 0)->valuedouble;
        items[i].t1 = cJSON_GetArrayItem(cJSON_GetArrayItem(arcs, i), 1)->valuedouble;
    }
    wc_svg_gravity(out, geometry, name, set_name(run), items, count);
    free(items);
    return true;
}

int wc_gravity_answer(wc_run *run, const cJSON *result)
{
    const cJSON *arcs = cJSON_GetObjectItem(result, "intervals_deg");
    int count = cJSON_GetArraySize(arcs);
    print_friction(run);
    if (!run->o->json) {
        printf("set %s: tilts (degrees, the direction gravity pulls in the part's frame)\n",
               set_name(run));
        const cJSON *arc;
        cJSON_ArrayForEach(arc, arcs)
        printf("  from %10.6f to %10.6f  (%.6g degrees)\n", cJSON_GetArrayItem(arc, 0)->valuedouble,
               cJSON_GetArrayItem(arc, 1)->valuedouble,
               cJSON_GetArrayItem(arc, 1)->valuedouble - cJSON_GetArrayItem(arc, 0)->valuedouble);
        if (count == 0)
            printf("  none: gravity alone never does it\n");
        /* On supports: arcs at the crossings proved neither way. */
        const cJSON *undecided = cJSON_GetObjectItem(result, "undecided_deg");
        cJSON_ArrayForEach(arc, undecided)
        printf("  undecided from %.9f to %.9f\n", cJSON_GetArrayItem(arc, 0)->valuedouble,
               cJSON_GetArrayItem(arc, 1)->valuedouble);
        if (strcmp(set_name(run), "both") != 0)
            printf("%s\n", wc_set_promise(set_name(run)));
    }
    int status = picture(run, result, draw_gravity);
    if (status >= 0)
        return status;
    return count > 0 ? EXIT_INSIDE : EXIT_NOT_INSIDE;
}

/* ---- margin ------------------------------------------------------------------- */

int wc_margin_request(wc_run *run, cJSON *params)
{
    run->bias = wc_wrench_argument(run->items[1]);
    if (!run->bias)
        return wc_usage_error("'%s' is not a wrench: fx,fy,tau or fx,fy@x,y", run->items[1]);
    cJSON_AddItemToObject(params, "bias", cJSON_Duplicate(run->bias, true));
    return -1;
}

static void print_margin(const cJSON *result, bool held)
{
    const cJSON *margin = cJSON_GetObjectItem(result, "margin");
    const char *blocking = cJSON_GetStringValue(cJSON_GetObjectItem(result, "blocking"));
    const cJSON *worst = cJSON_GetObjectItem(result, "worst_direction");
    if (!blocking) {
        printf("no contact mode moves the part: it holds against any disturbance\n");
        return;
    }
    char why[512];
    wc_explain_strong(blocking, why, sizeof why);
    /* On supports the answer is bracketed (its ends null when unbounded). */
    const cJSON *bracket = cJSON_GetObjectItem(result, "bracket");
    const char *moving = bracket ? "not held: the bias itself moves the part on its supports"
                                 : "not held: the bias itself is inside G_strong's excluded cones";
    if (cJSON_IsNumber(margin))
        printf("margin    %+.9g  (%s)\n", margin->valuedouble,
               held ? "any smaller disturbance is held, in the scaled metric" : moving);
    else
        printf("margin    unknown  (%s; no held wrench found)\n", moving);
    if (cJSON_IsArray(bracket)) {
        printf("bracket  ");
        for (int k = 0; k < 2; k++) {
            const cJSON *end = cJSON_GetArrayItem(bracket, k);
            if (cJSON_IsNumber(end))
                printf(" %+.9g", end->valuedouble);
            else
                printf(" null");
        }
        printf("  (%s)\n", cJSON_IsTrue(cJSON_GetObjectItem(result, "converged"))
                               ? "converged"
                               : "not converged: the exact margin lies between");
    }
    printf("blocking  %s: %s\n", blocking, why);
    printf("worst     (%.6g, %.6g, %.6g)\n", cJSON_GetArrayItem(worst, 0)->valuedouble,
           cJSON_GetArrayItem(worst, 1)->valuedouble, cJSON_GetArrayItem(worst, 2)->valuedouble);
}

/* The bias as the daemon read it ([fx, fy, tau] or a force at a point):
 * the protocol layer's reader, which the daemon accepted. */
static bool draw_margin(const wc_run *run, const cJSON *result, FILE *out,
                        const wr_fixture *geometry, const char *name)
{
    const cJSON *margin = cJSON_GetObjectItem(result, "margin");
    const cJSON *worst = cJSON_GetObjectItem(result, "worst_direction");
    double g[3] = {0, 0, 0}, w[3] = {0, 0, 0};
    wp_error error;
    if (!wp_wrench_read(run->bias, "bias", geometry, g, &error)) {
        wc_usage_error("%s: %s", error.field, error.reason);
        return false;
    }
    for (int k = 0; k < 3 && worst && cJSON_IsArray(worst); k++)
        w[k] = cJSON_GetArrayItem(worst, k)->valuedouble;
    wc_svg_margin(out, geometry, name, g, cJSON_IsNumber(margin) ? margin->valuedouble : 0, w,
                  cJSON_GetStringValue(cJSON_GetObjectItem(result, "blocking")));
    return true;
}

int wc_margin_answer(wc_run *run, const cJSON *result)
{
    const cJSON *margin = cJSON_GetObjectItem(result, "margin");
    bool held = !cJSON_IsNumber(margin) || margin->valuedouble > 0;
    print_friction(run);
    if (!run->o->json)
        print_margin(result, held);
    int status = picture(run, result, draw_margin);
    if (status >= 0)
        return status;
    return held ? EXIT_INSIDE : EXIT_NOT_INSIDE;
}

/* ---- sweep -------------------------------------------------------------------- */

/* friction.sweep's defaults (docs/PROTOCOL.md). */
static const double DEFAULT_RANGE[2] = {0, 2};

int wc_sweep_request(wc_run *run, cJSON *params)
{
    if (!run->sweep_kind)
        return wc_usage_error("sweep wants --push SET, --gravity SET, --least-force SET or "
                              "--wrench FX,FY,TAU");
    bool wrenches = strcmp(run->sweep_kind, "wrenches") == 0;
    bool push = strcmp(run->sweep_kind, "push") == 0;
    bool force = strcmp(run->sweep_kind, "force") == 0;
    /* Over the supports a push has push.regions' force, cases and push_on,
     * a tilt its pull. */
    bool plate = run->over && strcmp(run->over, "supports") == 0;
    /* Over the fixels' mu of a fixture on supports too: the daemon refuses
     * a force or a pull for a floating part, naming the member. */
    bool plate_push = push && (plate || run->push_force_given);
    if (run->push_force_given && !push)
        return wc_usage_error("sweep: --force is for --push on supports");
    if (run->in_plane_g_given && strcmp(run->sweep_kind, "gravity") != 0)
        return wc_usage_error("sweep: --in-plane-g is for --gravity on supports");
    if (run->over)
        cJSON_AddStringToObject(params, "over", run->over);
    if (run->set && !wrenches)
        return wc_usage_error("sweep: --set is for --wrench; --%s SET names the set",
                              force ? "least-force" : run->sweep_kind);
    if (run->friction_given && !push)
        return wc_usage_error("sweep: --finger-friction is for --push");
    if (run->radius_given && !push && !force)
        return wc_usage_error("sweep: --finger-radius is for --push and --least-force");
    if (force && !run->cases)
        return wc_usage_error("sweep --least-force wants at least one --case");
    if (run->cases && !force && !plate_push)
        return wc_usage_error("sweep: --case is for --least-force (or --push with --over "
                              "supports)");
    if (run->push_on && !force && !plate_push)
        return wc_usage_error("sweep: --push-on is for --least-force (or --push with --over "
                              "supports)");
    if (run->range_given)
        cJSON_AddItemToObject(params, "range", cJSON_CreateDoubleArray(run->range, 2));
    if (run->ratio_given)
        cJSON_AddNumberToObject(params, "kinetic_ratio", run->kinetic_ratio);
    if (wrenches) {
        cJSON_AddItemToObject(params, "wrenches", cJSON_Duplicate(run->wrenches, true));
        if (run->set) {
            cJSON *sets = cJSON_AddArrayToObject(params, "sets");
            cJSON_AddItemToArray(sets, cJSON_CreateString(run->set));
        }
        return -1;
    }
    cJSON *what = cJSON_AddObjectToObject(params, run->sweep_kind);
    cJSON_AddStringToObject(what, "set", run->sweep_set);
    if (run->friction_given)
        cJSON_AddNumberToObject(what, "finger_friction", run->finger_friction);
    if (run->radius_given)
        cJSON_AddNumberToObject(what, "finger_radius", run->finger_radius);
    if (run->in_plane_g_given)
        cJSON_AddNumberToObject(what, "in_plane_g", run->in_plane_g);
    if (plate_push) {
        if (run->push_on)
            cJSON_AddItemToObject(what, "push_on", cJSON_Duplicate(run->push_on, true));
        return wc_push_loads(run, what);
    }
    if (!force)
        return -1;
    cJSON_AddItemToObject(params, "cases", cJSON_Duplicate(run->cases, true));
    return wc_push_on(run,
                      cJSON_IsString(run->fixture) ? run->fixture
                                                   : cJSON_GetObjectItem(run->fixture, "body"),
                      what);
}

/* The range and the kinetic ratio swept: those given, or the defaults. */
static double sweep_low(const wc_run *run)
{
    return run->range_given ? run->range[0] : DEFAULT_RANGE[0];
}

static double sweep_high(const wc_run *run)
{
    return run->range_given ? run->range[1] : DEFAULT_RANGE[1];
}

static double sweep_ratio(const wc_run *run)
{
    if (run->over && strcmp(run->over, "supports") == 0)
        return 0; /* the pictures' word for the supports' mu_B (wc_svg.h) */
    return run->ratio_given ? run->kinetic_ratio : 1;
}

/* The first line: what was swept, and how. */
static void print_sweep_header(const wc_run *run, const char *what)
{
    if (run->over && strcmp(run->over, "supports") == 0) {
        printf("friction sweep of %s: the supports' mu_B from %g to %g (the fixels' friction as "
               "the fixture gives it)\n",
               what, sweep_low(run), sweep_high(run));
        return;
    }
    printf("friction sweep of %s: mu_s = mu, mu_k = %g mu at every fixel, mu from %g to %g\n",
           what, sweep_ratio(run), sweep_low(run), sweep_high(run));
}

/* "[0, 0.5], [0.8, 2]", or "none". */
static void print_intervals(const cJSON *intervals)
{
    int i = 0;
    const cJSON *interval;
    cJSON_ArrayForEach(interval, intervals)
    printf("%s[%g, %g]", i++ ? ", " : "", cJSON_GetNumberValue(cJSON_GetArrayItem(interval, 0)),
           cJSON_GetNumberValue(cJSON_GetArrayItem(interval, 1)));
    printf("%s\n", i ? "" : "none");
}

/* The intervals of the answer, as the pictures take them (freed by the
 * caller); *count their number. */
static wc_interval *intervals_of(const cJSON *intervals, int *count)
{
    *count = cJSON_GetArraySize(intervals);
    wc_interval *out = calloc((size_t)(*count ? *count : 1), sizeof *out);
    for (int i = 0; i < *count; i++) {
        const cJSON *interval = cJSON_GetArrayItem(intervals, i);
        out[i].low = cJSON_GetNumberValue(cJSON_GetArrayItem(interval, 0));
        out[i].high = cJSON_GetNumberValue(cJSON_GetArrayItem(interval, 1));
    }
    return out;
}

/* friction.sweep "force": the intervals, then the least force (and where)
 * at the samples: every one with --table full, else about 12 evenly. */
static void print_force_sweep(const wc_run *run, const cJSON *result)
{
    char what[96];
    snprintf(what, sizeof what, "the least push force, set %s", run->sweep_set);
    print_sweep_header(run, what);
    /* On a base plate the answer has no intervals of the push alone. */
    const cJSON *intervals = cJSON_GetObjectItem(result, "intervals");
    if (intervals) {
        printf("the push alone has a region (a large enough push does it whatever the loads) "
               "%sfor mu in ",
               run->geometric_given ? "on every fixture of the tolerance's set " : "");
        print_intervals(intervals);
    }
    printf("sampled: each value %s at its mu; grid step %g%s\n",
           run->geometric_given
               ? "push-force's robust least (the nominal least's point and 4 points an edge)"
               : "exact",
           cJSON_GetNumberValue(cJSON_GetObjectItem(result, "resolution")),
           intervals ? ", and every interval end" : "");
    printf("%12s  %16s  %s\n", "mu", "least force", "at");
    const cJSON *curve = cJSON_GetObjectItem(result, "curve"), *at = cJSON_GetObjectItem(result, "at");
    int n = cJSON_GetArraySize(curve), every = run->table_full || n <= 24 ? 1 : n / 12, shown = 0;
    for (int i = 0; i < n; i++) {
        if (i % every != 0 && i != n - 1)
            continue;
        const cJSON *point = cJSON_GetArrayItem(curve, i), *where = cJSON_GetArrayItem(at, i);
        const cJSON *value = cJSON_GetArrayItem(point, 1);
        printf("%12.6f  ", cJSON_GetNumberValue(cJSON_GetArrayItem(point, 0)));
        if (cJSON_IsNumber(value))
            printf("%12.6g %-3s  (%g, %g)\n", value->valuedouble, wc_named_force_unit(run->fixture),
                   cJSON_GetNumberValue(cJSON_GetArrayItem(where, 0)),
                   cJSON_GetNumberValue(cJSON_GetArrayItem(where, 1)));
        else
            printf("%16s  no push does it under every case\n", "none");
        shown++;
    }
    if (shown < n)
        printf("(%d of the %d samples; --table full for all, --json for the answer)\n", shown, n);
    printf("%s\n", wc_set_promise(run->sweep_set));
}

static void print_region_sweep(const wc_run *run, const cJSON *result)
{
    bool push = strcmp(run->sweep_kind, "push") == 0;
    char what[96];
    snprintf(what, sizeof what, "the %s, set %s", push ? "push region" : "gravity arcs",
             run->sweep_set);
    print_sweep_header(run, what);
    const cJSON *intervals = cJSON_GetObjectItem(result, "intervals");
    const cJSON *critical = cJSON_GetObjectItem(result, "critical");
    printf("not empty for mu in ");
    print_intervals(intervals);
    if (!cJSON_IsNumber(critical))
        printf("critical mu: none, not empty at the top of the range (mu = %g)\n",
               sweep_high(run));
    else if (cJSON_GetArraySize(intervals) == 0)
        printf("critical mu %g: empty throughout the range\n", critical->valuedouble);
    else
        printf("critical mu %g: empty above it\n", critical->valuedouble);
    if (run->over && strcmp(run->over, "supports") == 0)
        printf("each point exact at its mu_B, every %g; seating only gets harder as mu_B grows, "
               "so the critical mu_B is bisected on those answers (to 1e-9)\n",
               cJSON_GetNumberValue(cJSON_GetObjectItem(result, "resolution")));
    else if (run->geometric_given)
        printf("robust over the tolerance: each interval proved for every mu in it and every "
               "fixture of the set; an interval narrower than %g may be missed; the curve is "
               "the robust %s at each mu\n",
               cJSON_GetNumberValue(cJSON_GetObjectItem(result, "resolution")),
               push ? "region's length" : "arcs' total");
    else if (cJSON_IsFalse(cJSON_GetObjectItem(result, "exact")))
        printf("sampled: resolution %g\n",
               cJSON_GetNumberValue(cJSON_GetObjectItem(result, "resolution")));
    printf("%12s  %14s\n", "mu", push ? "length" : "arc (degrees)");
    /* Summarised unless --table full: the points nearest SUMMARY_ROWS
     * evenly spaced mu up to the critical mu (where the curve changes),
     * those at the intervals' ends, and the last. */
    enum { SUMMARY_ROWS = 9 };
    const cJSON *curve = cJSON_GetObjectItem(result, "curve");
    int n = cJSON_GetArraySize(curve), shown = 0;
    bool full = run->table_full || n <= 2 * SUMMARY_ROWS;
    bool *keep = calloc((size_t)(n ? n : 1), sizeof *keep);
    for (int i = 0; keep && i < n; i++)
        keep[i] = full;
    double low = sweep_low(run), high = sweep_high(run);
    if (cJSON_IsNumber(critical) && critical->valuedouble > low)
        high = critical->valuedouble;
    if (keep && n > 0)
        keep[n - 1] = true;
    for (int k = 0; keep && !full && n > 0 && k < SUMMARY_ROWS; k++) {
        double mu = low + (high - low) * k / (SUMMARY_ROWS - 1);
        int best = 0;
        for (int i = 1; i < n; i++)
            if (fabs(cJSON_GetArrayItem(cJSON_GetArrayItem(curve, i), 0)->valuedouble - mu) <
                fabs(cJSON_GetArrayItem(cJSON_GetArrayItem(curve, best), 0)->valuedouble - mu))
                best = i;
        keep[best] = true;
    }
    const cJSON *interval;
    cJSON_ArrayForEach(interval, intervals)
    for (int e = 0; keep && !full && e < 2; e++) {
        double end = cJSON_GetNumberValue(cJSON_GetArrayItem(interval, e));
        for (int i = 0; i < n; i++)
            if (cJSON_GetArrayItem(cJSON_GetArrayItem(curve, i), 0)->valuedouble == end)
                keep[i] = true;
    }
    for (int i = 0; keep && i < n; i++) {
        if (!keep[i])
            continue;
        const cJSON *point = cJSON_GetArrayItem(curve, i);
        printf("%12.6f  %14.6f\n", cJSON_GetNumberValue(cJSON_GetArrayItem(point, 0)),
               cJSON_GetNumberValue(cJSON_GetArrayItem(point, 1)));
        shown++;
    }
    free(keep);
    if (shown < n)
        printf("(%d of the curve's %d points; --table full for all, --json for the answer)\n",
               shown, n);
    printf("%s\n", wc_set_promise(run->sweep_set));
}

static bool draw_region_sweep(const wc_run *run, const cJSON *result, FILE *out,
                              const wr_fixture *geometry, const char *name)
{
    const cJSON *curve = cJSON_GetObjectItem(result, "curve");
    int points = cJSON_GetArraySize(curve);
    double(*xy)[2] = calloc((size_t)(points ? points : 1), sizeof *xy);
    for (int i = 0; i < points; i++)
        for (int k = 0; k < 2; k++)
            xy[i][k] = cJSON_GetNumberValue(cJSON_GetArrayItem(cJSON_GetArrayItem(curve, i), k));
    const cJSON *critical = cJSON_GetObjectItem(result, "critical");
    wc_sweep_plot plot = {
        .name = name,
        .what = run->sweep_kind,
        .force_unit = geometry ? wc_force_unit(geometry) : "(model units)",
        .set = run->sweep_set,
        .range = {sweep_low(run), sweep_high(run)},
        .kinetic_ratio = sweep_ratio(run),
        .critical = cJSON_IsNumber(critical) ? critical->valuedouble : NAN,
        .curve = (const double(*)[2])xy,
        .curve_count = points,
        .fixture = geometry,
    };
    wc_interval *intervals = intervals_of(cJSON_GetObjectItem(result, "intervals"),
                                          &plot.interval_count);
    plot.intervals = intervals;
    wc_svg_sweep(out, &plot);
    free(intervals);
    free(xy);
    return true;
}

/* The sets of a sweep of wrenches, in the answer's order: those of its
 * first result. */
static int sweep_sets(const cJSON *results, const char *sets[3])
{
    int count = 0;
    const cJSON *set;
    cJSON_ArrayForEach(set, cJSON_GetArrayItem(results, 0))
    {
        if (count < 3)
            sets[count++] = set->string;
    }
    return count;
}

static void print_wrench_sweep(const wc_run *run, const cJSON *result)
{
    print_sweep_header(run, "wrenches");
    const cJSON *results = cJSON_GetObjectItem(result, "results");
    int width = 6;
    const cJSON *w, *r, *set;
    cJSON_ArrayForEach(w, run->wrenches)
    {
        char text[96];
        wc_describe_wrench(w, text, sizeof text);
        width = (int)strlen(text) > width ? (int)strlen(text) : width;
    }
    printf("%4s  %-*s  %-6s  %s\n", "#", width, "wrench", "set", "inside for mu in");
    int index = 0;
    cJSON_ArrayForEach(r, results)
    {
        char wrench[96];
        wc_describe_wrench(cJSON_GetArrayItem(run->wrenches, index), wrench, sizeof wrench);
        bool first = true;
        cJSON_ArrayForEach(set, r)
        {
            char number[16] = "";
            if (first)
                snprintf(number, sizeof number, "%d", index + 1);
            printf("%4s  %-*s  %-6s  ", number, width, first ? wrench : "", set->string);
            print_intervals(set);
            first = false;
        }
        index++;
    }
    if (cJSON_IsFalse(cJSON_GetObjectItem(result, "exact")))
        printf("on the plate, strong and both sampled: grid step %g, each change bisected; "
               "every mu given is proved held, an interval narrower than the step may be "
               "missed\n",
               cJSON_GetNumberValue(cJSON_GetObjectItem(result, "resolution")));
    const char *sets[3];
    int set_count = sweep_sets(results, sets);
    for (int i = 0; i < set_count; i++)
        printf("%s\n", wc_set_promise(sets[i]));
}

static bool draw_wrench_sweep(const wc_run *run, const cJSON *result, FILE *out,
                              const wr_fixture *geometry, const char *name)
{
    (void)geometry;
    const cJSON *results = cJSON_GetObjectItem(result, "results");
    const char *sets[3];
    int set_count = sweep_sets(results, sets);
    int count = cJSON_GetArraySize(results) * set_count;
    wc_sweep_band *bands = calloc((size_t)(count ? count : 1), sizeof *bands);
    int n = 0, index = 0;
    const cJSON *r, *set;
    cJSON_ArrayForEach(r, results)
    {
        char wrench[96];
        wc_describe_wrench(cJSON_GetArrayItem(run->wrenches, index), wrench, sizeof wrench);
        cJSON_ArrayForEach(set, r)
        {
            if (n == count)
                break;
            snprintf(bands[n].label, sizeof bands[n].label, "%d %s", index + 1, wrench);
            bands[n].set = set->string;
            bands[n].intervals = intervals_of(set, &bands[n].count);
            n++;
        }
        index++;
    }
    double range[2] = {sweep_low(run), sweep_high(run)};
    wc_svg_sweep_bands(out, name, range, sweep_ratio(run), bands, n, sets, set_count);
    for (int i = 0; i < n; i++)
        free((void *)bands[i].intervals);
    free(bands);
    return true;
}

int wc_sweep_answer(wc_run *run, const cJSON *result)
{
    bool wrenches = strcmp(run->sweep_kind, "wrenches") == 0;
    bool force = strcmp(run->sweep_kind, "force") == 0;
    if (!run->o->json) {
        if (wrenches)
            print_wrench_sweep(run, result);
        else if (force)
            print_force_sweep(run, result);
        else
            print_region_sweep(run, result);
    }
    int status = picture(run, result, wrenches ? draw_wrench_sweep : draw_region_sweep);
    if (status >= 0)
        return status;
    if (force) { /* 0 when some push does the job at some mu */
        const cJSON *point;
        cJSON_ArrayForEach(point, cJSON_GetObjectItem(result, "curve"))
        if (cJSON_IsNumber(cJSON_GetArrayItem(point, 1))) return EXIT_INSIDE;
        return EXIT_NOT_INSIDE;
    }
    if (!wrenches)
        return cJSON_GetArraySize(cJSON_GetObjectItem(result, "intervals")) > 0 ? EXIT_INSIDE
                                                                                 : EXIT_NOT_INSIDE;
    /* Wrenches: 0 when each is inside each set for some mu. */
    const cJSON *r, *set;
    cJSON_ArrayForEach(r, cJSON_GetObjectItem(result, "results"))
    cJSON_ArrayForEach(set, r) if (cJSON_GetArraySize(set) == 0) return EXIT_NOT_INSIDE;
    return EXIT_INSIDE;
}

/* ---- locate (fixture.locating) ------------------------------------------------ */

int wc_locate_request(wc_run *run, cJSON *params)
{
    if (!run->locate_tolerance)
        return wc_usage_error("locate wants --tolerance T (or T1,T2,T3: one per fixel)");
    cJSON_AddItemToObject(params, "tolerance", cJSON_Duplicate(run->locate_tolerance, true));
    if (run->features)
        cJSON_AddItemToObject(params, "features", cJSON_Duplicate(run->features, true));
    if (run->sigma_ratio_given)
        cJSON_AddNumberToObject(params, "sigma_ratio", run->sigma_ratio);
    return -1;
}

static double item(const cJSON *array, int i)
{
    const cJSON *v = cJSON_GetArrayItem(array, i);
    return cJSON_IsNumber(v) ? v->valuedouble : NAN;
}

/* The fixture's length unit as " [mm]", or "" (a stored fixture by id, or
 * none named). */
static void length_label(const wc_run *run, char *out, size_t size)
{
    const cJSON *units = cJSON_GetObjectItem(run->fixture, "units");
    const char *length = cJSON_GetStringValue(cJSON_GetObjectItem(units, "length"));
    snprintf(out, size, length ? " [%s]" : "", length);
}

/* Tolerance of locator i as asked: one number for all, or one each. */
static double tolerance_of(const wc_run *run, int i)
{
    return cJSON_IsNumber(run->locate_tolerance) ? run->locate_tolerance->valuedouble
                                                 : item(run->locate_tolerance, i);
}

static void print_locate(const wc_run *run, const cJSON *result)
{
    char unit[24];
    length_label(run, unit, sizeof unit);
    const cJSON *motion = cJSON_GetObjectItem(result, "free_motion");
    if (!cJSON_IsTrue(cJSON_GetObjectItem(result, "deterministic"))) {
        const cJSON *twist = cJSON_GetObjectItem(motion, "twist");
        const cJSON *about = cJSON_GetObjectItem(motion, "about");
        printf("not deterministic: the fixels leave the part free to ");
        if (cJSON_IsArray(about))
            printf("turn about (%.6g, %.6g)", item(about, 0), item(about, 1));
        else
            printf("slide along (%.6g, %.6g)", item(twist, 0), item(twist, 1));
        printf("\ntwist     (%.6g, %.6g, %.6g)  (vx, vy, w)\n", item(twist, 0), item(twist, 1),
               item(twist, 2));
        return;
    }
    const cJSON *s = cJSON_GetObjectItem(result, "sensitivity");
    int k = cJSON_GetArraySize(cJSON_GetArrayItem(s, 0));
    printf("deterministic: yes, condition number %.6g (scaled locating matrix)\n",
           cJSON_GetObjectItem(result, "condition")->valuedouble);
    printf("sensitivity G^-1: the pose's change per unit move of each locator\n%-14s", "");
    for (int i = 0; i < k; i++)
        printf("  %12s%d", "fixel ", i + 1);
    printf("\n");
    static const char *const rows[3] = {"dx", "dy", "dtheta"};
    for (int j = 0; j < 3; j++) {
        printf("  %-12s", rows[j]);
        for (int i = 0; i < k; i++)
            printf("  %13.6g", item(cJSON_GetArrayItem(s, j), i));
        printf("\n");
    }
    const cJSON *pose = cJSON_GetObjectItem(result, "pose_error");
    const cJSON *linear = cJSON_GetObjectItem(pose, "linear"), *exact = cJSON_GetObjectItem(pose, "exact");
    printf("pose error: the worst over the tolerance box (locators off by");
    for (int i = 0; i < k; i++)
        printf("%s +-%g", i ? "," : "", tolerance_of(run, i));
    printf(")\n%-14s  %13s  %13s\n", "", "linear", "exact");
    for (int j = 0; j < 3; j++) {
        char label[40];
        snprintf(label, sizeof label, "%s%s", rows[j], j < 2 ? unit : " [rad]");
        printf("  %-12s  %13.6g  %13.6g\n", label, item(linear, j), item(exact, j));
    }
    const cJSON *features = cJSON_GetObjectItem(result, "features");
    if (cJSON_GetArraySize(features) == 0)
        return;
    printf("features%s: worst displacement (linear, exact) and the 99.73 %% ellipse, sigma = "
           "tolerance / %g\n", unit, run->sigma_ratio_given ? run->sigma_ratio : 3.0);
    printf("  %-10s %-22s %-32s %-32s %s\n", "name", "at", "linear", "exact",
           "ellipse semi-axes, angle");
    int n = 1;
    for (const cJSON *f = features->child; f; f = f->next, n++) {
        const char *name = cJSON_GetStringValue(cJSON_GetObjectItem(f, "name"));
        char label[32], at[48], lin[64], ex[64];
        snprintf(label, sizeof label, "%s", name ? name : "");
        if (!name)
            snprintf(label, sizeof label, "%d", n);
        const cJSON *a = cJSON_GetObjectItem(f, "at");
        snprintf(at, sizeof at, "(%g, %g)", item(a, 0), item(a, 1));
        const cJSON *l = cJSON_GetObjectItem(f, "linear"), *e = cJSON_GetObjectItem(f, "exact");
        const cJSON *lv = cJSON_GetObjectItem(l, "vector"), *ev = cJSON_GetObjectItem(e, "vector");
        snprintf(lin, sizeof lin, "%.6g (%.4g, %.4g)", cJSON_GetObjectItem(l, "length")->valuedouble,
                 item(lv, 0), item(lv, 1));
        snprintf(ex, sizeof ex, "%.6g (%.4g, %.4g)", cJSON_GetObjectItem(e, "length")->valuedouble,
                 item(ev, 0), item(ev, 1));
        const cJSON *el = cJSON_GetObjectItem(f, "ellipse");
        const cJSON *axes = cJSON_GetObjectItem(el, "axes");
        printf("  %-10s %-22s %-32s %-32s %.6g, %.6g at %.4g deg\n", label, at, lin, ex,
               item(axes, 0), item(axes, 1), cJSON_GetObjectItem(el, "angle_deg")->valuedouble);
    }
}

/* A 1, 2 or 5 times a power of ten, at most x (x > 0). */
static double nice_below(double x)
{
    double p = pow(10, floor(log10(x)));
    return x >= 5 * p ? 5 * p : x >= 2 * p ? 2 * p : p;
}

static bool draw_locate(const wc_run *run, const cJSON *result, FILE *out,
                        const wr_fixture *geometry, const char *name)
{
    const cJSON *s = cJSON_GetObjectItem(result, "sensitivity");
    const cJSON *features = cJSON_GetObjectItem(result, "features");
    int k = cJSON_GetArraySize(cJSON_GetArrayItem(s, 0)), count = cJSON_GetArraySize(features);
    /* The corner of the box that moves the part most (scaled metric). */
    double pose[3] = {0, 0, 0}, largest = -1;
    for (unsigned v = 0; cJSON_IsArray(s) && v < 1u << k; v++) {
        double q[3] = {0, 0, 0};
        for (int j = 0; j < 3; j++)
            for (int i = 0; i < k; i++)
                q[j] += item(cJSON_GetArrayItem(s, j), i) *
                        ((v >> i & 1u) ? tolerance_of(run, i) : -tolerance_of(run, i));
        double size = hypot(hypot(q[0], q[1]), geometry->gyration_radius * q[2]);
        if (size > largest) {
            largest = size;
            memcpy(pose, q, sizeof pose);
        }
    }
    wc_locate_mark *marks = calloc((size_t)count + 1, sizeof *marks);
    if (!marks)
        return false;
    double biggest = hypot(pose[0], pose[1]) + fabs(pose[2]) * geometry->size / 2;
    int n = 0;
    for (const cJSON *f = features ? features->child : NULL; f; f = f->next, n++) {
        wc_locate_mark *m = &marks[n];
        m->name = cJSON_GetStringValue(cJSON_GetObjectItem(f, "name"));
        const cJSON *at = cJSON_GetObjectItem(f, "at");
        const cJSON *worst = cJSON_GetObjectItem(cJSON_GetObjectItem(f, "exact"), "vector");
        const cJSON *el = cJSON_GetObjectItem(f, "ellipse");
        for (int c = 0; c < 2; c++) {
            m->at[c] = item(at, c);
            m->worst[c] = item(worst, c);
            m->axes[c] = item(cJSON_GetObjectItem(el, "axes"), c);
        }
        m->angle_deg = cJSON_GetObjectItem(el, "angle_deg")->valuedouble;
        biggest = fmax(biggest, fmax(hypot(m->worst[0], m->worst[1]), m->axes[0]));
    }
    /* Errors drawn at about an eighth of the part's size. */
    double magnification = biggest > 0 ? nice_below(geometry->size / 8 / biggest) : 1;
    char tolerance[96] = "";
    for (int i = 0; i < k; i++) {
        size_t used = strlen(tolerance);
        snprintf(tolerance + used, sizeof tolerance - used, "%s+-%g", i ? ", " : "",
                 tolerance_of(run, i));
        if (cJSON_IsNumber(run->locate_tolerance))
            break;
    }
    wc_svg_locate(out, geometry, name, marks, count, pose, magnification, tolerance);
    free(marks);
    return true;
}

int wc_locate_answer(wc_run *run, const cJSON *result)
{
    bool deterministic = cJSON_IsTrue(cJSON_GetObjectItem(result, "deterministic"));
    if (!run->o->json)
        print_locate(run, result);
    if (deterministic) {
        int status = picture(run, result, draw_locate);
        if (status >= 0)
            return status;
    }
    return deterministic ? EXIT_INSIDE : EXIT_NOT_INSIDE;
}
