/* wc_design.c -- wrenchctl design: fixture.design's request from a body
 * file and options, a progress bar on a terminal, the ranked table. */
#include "wc_call.h"
#include "wc_commands.h"
#include "wc_print.h"
#include "wc_svg.h"

#include "wc_explain.h" /* generated from clients/python/wrenchd.py */
#include "wp_fixture.h"

#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

/* Seconds as a person reads them: "40 s", "3 min 5 s", "2 h 10 min". */
static void format_eta(double seconds, char *out, size_t size)
{
    double s = floor(seconds + 0.5);
    if (s < 60)
        snprintf(out, size, "%.0f s", s);
    else if (s < 3600)
        snprintf(out, size, "%.0f min %.0f s", floor(s / 60), fmod(s, 60));
    else
        snprintf(out, size, "%.0f h %.0f min", floor(s / 3600), floor(fmod(s, 3600) / 60));
}

/* design.progress on stderr, redrawn in place: a bar, the count of the
 * stage (a lattice's poses, the candidates, the designs' figures), the
 * estimated time left of it (eta_s), the best score so far. */
static void progress_bar(const char *line, void *context)
{
    (void)context;
    cJSON *json = cJSON_Parse(line);
    const cJSON *params = cJSON_GetObjectItem(json, "params");
    double done = cJSON_GetNumberValue(cJSON_GetObjectItem(params, "done"));
    double total = cJSON_GetNumberValue(cJSON_GetObjectItem(params, "total"));
    const cJSON *best = cJSON_GetObjectItem(params, "best");
    const cJSON *eta = cJSON_GetObjectItem(params, "eta_s");
    const char *stage = cJSON_GetStringValue(cJSON_GetObjectItem(params, "stage"));
    const char *unit = !stage || strcmp(stage, "candidates") == 0 ? "candidates"
                       : strcmp(stage, "poses") == 0           ? "hole pairs"
                                                               : "designs' figures";
    if (json && total > 0 && done >= 0) {
        enum { WIDTH = 30 };
        int filled = (int)(WIDTH * done / total);
        char bar[WIDTH + 1];
        for (int i = 0; i < WIDTH; i++)
            bar[i] = i < filled ? '#' : '.';
        bar[WIDTH] = 0;
        fprintf(stderr, "\r[%s] %3.0f%% %.0f/%.0f %s", bar, 100 * done / total, done, total,
                unit);
        if (cJSON_IsNumber(eta) && done < total) {
            char text[32];
            format_eta(eta->valuedouble, text, sizeof text);
            fprintf(stderr, ", about %s left", text);
        }
        if (cJSON_IsNumber(best))
            fprintf(stderr, ", best %.6g", best->valuedouble);
        /* Spaces over what a longer line before left. */
        fputs(done >= total ? "\n" : "          ", stderr);
        fflush(stderr);
    }
    cJSON_Delete(json);
}

int wc_design_request(wc_run *run, cJSON *params)
{
    FILE *file = fopen(run->items[0], "r");
    if (!file)
        return wc_usage_error("design: cannot open '%s'", run->items[0]);
    char *text = wc_read_all(file, NULL);
    fclose(file);
    cJSON *json = text ? cJSON_Parse(text) : NULL;
    free(text);
    if (!cJSON_IsObject(json)) {
        cJSON_Delete(json);
        return wc_usage_error("design: '%s' is not a JSON object (a fixture or a body)",
                              run->items[0]);
    }
    cJSON *body = cJSON_GetObjectItem(json, "body");
    cJSON_AddItemToObject(params, "body", cJSON_Duplicate(body ? body : json, true));
    /* The pictures' name: the file's, else the file name without its path. */
    const char *base = strrchr(run->items[0], '/');
    const cJSON *named = cJSON_GetObjectItem(json, "name");
    char *name = strdup(cJSON_IsString(named) ? named->valuestring : base ? base + 1 : run->items[0]);
    if (run->friction_interval_given) {
        if (run->friction_low == run->friction_high)
            cJSON_AddNumberToObject(params, "friction", run->friction_low);
        else
            cJSON_AddItemToObject(params, "friction",
                                  cJSON_CreateDoubleArray((double[2]){run->friction_low,
                                                                      run->friction_high},
                                                          2));
    } else if (body && cJSON_GetObjectItem(json, "friction")) {
        cJSON_AddItemToObject(params, "friction",
                              cJSON_Duplicate(cJSON_GetObjectItem(json, "friction"), true));
    } else {
        cJSON_Delete(json);
        free(name);
        return wc_usage_error("design: no friction: give --friction or a fixture with one");
    }
    if (run->spacing > 0 && run->lattice_given) {
        cJSON_Delete(json);
        free(name);
        return wc_usage_error("design: --spacing or --lattice, not both");
    }
    if (run->lattice_given) {
        cJSON *lattice = cJSON_AddObjectToObject(params, "lattice");
        cJSON_AddNumberToObject(lattice, "pitch", run->lattice[0]);
        cJSON_AddNumberToObject(lattice, "peg_radius", run->lattice[1]);
        cJSON_AddItemToObject(lattice, "extent", cJSON_CreateIntArray(run->lattice_extent, 2));
    } else if (run->spacing > 0) {
        cJSON_AddNumberToObject(params, "spacing", run->spacing);
        if (run->corner_clearance > 0)
            cJSON_AddNumberToObject(params, "corner_clearance", run->corner_clearance);
        if (run->pin_diameter_given)
            cJSON_AddNumberToObject(params, "pin_diameter", run->pin_diameter);
    } else if (body && cJSON_IsArray(cJSON_GetObjectItem(json, "fixels"))) {
        /* The fixture's fixels are the candidate sites. */
        cJSON *sites = cJSON_AddArrayToObject(params, "sites");
        const cJSON *fixel;
        cJSON_ArrayForEach(fixel, cJSON_GetObjectItem(json, "fixels"))
        {
            cJSON *site = cJSON_CreateObject();
            const cJSON *at = cJSON_GetObjectItem(fixel, "at");
            const cJSON *normal = cJSON_GetObjectItem(fixel, "normal");
            if (at)
                cJSON_AddItemToObject(site, "at", cJSON_Duplicate(at, true));
            if (normal)
                cJSON_AddItemToObject(site, "normal", cJSON_Duplicate(normal, true));
            cJSON_AddItemToArray(sites, site);
        }
    } else {
        cJSON_Delete(json);
        free(name);
        return wc_usage_error("design: no candidate sites: give --spacing H, or a fixture whose "
                              "fixels are the sites");
    }
    if ((run->corner_clearance > 0 || run->pin_diameter_given) &&
        !cJSON_GetObjectItem(params, "spacing")) {
        cJSON_Delete(json);
        free(name);
        return wc_usage_error("design: --corner-clearance and --pin-diameter go with --spacing");
    }
    /* For --svg and --emit-fixture: the body and friction, to draw each
     * design as a fixture and to write one; and the file's units, which the
     * table and the pictures name and the fixture written keeps. */
    run->fixture = cJSON_CreateObject();
    cJSON_AddStringToObject(run->fixture, "name", name ? name : "design");
    free(name);
    if (body && cJSON_GetObjectItem(json, "units")) {
        /* The daemon converts the cases' forces and the least pushes by them. */
        cJSON_AddItemToObject(run->fixture, "units",
                              cJSON_Duplicate(cJSON_GetObjectItem(json, "units"), true));
        cJSON_AddItemToObject(params, "units",
                              cJSON_Duplicate(cJSON_GetObjectItem(json, "units"), true));
    }
    /* The base plate: --supports, else the fixture file's own; the
     * designs drawn and written stand on it too. */
    cJSON *plate = body ? cJSON_DetachItemFromObject(json, "supports") : NULL;
    cJSON_Delete(json);
    if (run->supports) {
        cJSON *holder = cJSON_CreateObject();
        int status = wc_fixture_supports(run->o, &holder, run->supports);
        cJSON_Delete(plate);
        plate = cJSON_DetachItemFromObject(holder, "supports");
        cJSON_Delete(holder);
        if (status >= 0)
            return status;
    }
    if (plate) {
        cJSON_AddItemToObject(params, "supports", cJSON_Duplicate(plate, true));
        cJSON_AddItemToObject(run->fixture, "supports", plate);
    }
    cJSON_AddItemToObject(run->fixture, "body",
                          cJSON_Duplicate(cJSON_GetObjectItem(params, "body"), true));
    cJSON_AddItemToObject(run->fixture, "friction",
                          cJSON_Duplicate(cJSON_GetObjectItem(params, "friction"), true));
    int reach = wc_push_on(run, cJSON_GetObjectItem(params, "body"), params);
    if (reach >= 0)
        return reach;
    if (run->emit_design && run->shard_given)
        return wc_usage_error("design: --emit-fixture needs the whole answer, not a --shard");
    if (run->fixels)
        cJSON_AddNumberToObject(params, "fixels", run->fixels);
    if (run->top)
        cJSON_AddNumberToObject(params, "top", run->top);
    if (run->objective)
        cJSON_AddStringToObject(params, "objective", run->objective);
    if (run->objective && strcmp(run->objective, "force") == 0 && !run->cases)
        return wc_usage_error("design --objective force wants at least one --case");
    if (run->cases)
        cJSON_AddItemToObject(params, "cases", cJSON_Duplicate(run->cases, true));
    if (run->locate_tolerance) /* objective accuracy: one number for every locator */
        cJSON_AddItemToObject(params, "tolerance", cJSON_Duplicate(run->locate_tolerance, true));
    if (run->features)
        cJSON_AddItemToObject(params, "features", cJSON_Duplicate(run->features, true));
    if (run->geometric_given) { /* --fixel-tolerance */
        cJSON *tolerance = cJSON_AddObjectToObject(params, "fixel_tolerance");
        cJSON_AddNumberToObject(tolerance, "position", run->geometric[0]);
        if (run->geometric[1] > 0)
            cJSON_AddNumberToObject(tolerance, "angle", run->geometric[1]);
    }
    if (run->radius_given)
        cJSON_AddNumberToObject(params, "finger_radius", run->finger_radius);
    if (run->symmetric_all)
        cJSON_AddBoolToObject(params, "collapse_symmetric", false);
    if (run->friction_given)
        cJSON_AddNumberToObject(params, "finger_friction", run->finger_friction);
    if (run->shard_given)
        cJSON_AddItemToObject(params, "shard", cJSON_CreateIntArray(run->shard, 2));
    if (run->shard_given && run->o->json)
        return wc_usage_error("design: --shard writes JSON lines for design-merge; no --json");
    if (!run->o->local && isatty(STDERR_FILENO)) {
        cJSON_AddBoolToObject(params, "progress", true);
        run->o->notify = progress_bar;
    }
    return -1;
}

static double number(const cJSON *object, const char *key)
{
    return cJSON_GetNumberValue(cJSON_GetObjectItem(object, key));
}

/* --shard: a line per design, then one of the rest ({"counts", "sites",
 * "objective", "shard", "top"}): what design-merge reads. */
static void shard_lines(const wc_run *run, const cJSON *result)
{
    const cJSON *d;
    cJSON_ArrayForEach(d, cJSON_GetObjectItem(result, "designs"))
    {
        char *line = cJSON_PrintUnformatted(d);
        if (line)
            printf("%s\n", line);
        free(line);
    }
    cJSON *rest = cJSON_Duplicate(result, true);
    cJSON_DeleteItemFromObject(rest, "designs");
    cJSON_AddNumberToObject(rest, "top", run->top ? run->top : 10);
    /* The merged table prints points as this one would. */
    cJSON_AddNumberToObject(rest, "decimals", wc_drawing_decimals(cJSON_GetObjectItem(
                                                  cJSON_GetObjectItem(run->fixture, "body"),
                                                  "shape")));
    char *line = cJSON_PrintUnformatted(rest);
    if (line)
        printf("%s\n", line);
    free(line);
    cJSON_Delete(rest);
}

/* A design as a fixture's JSON: the request's body and friction with its
 * fixels (friction as a number or an interval becomes the fixture's
 * form). */
static cJSON *design_fixture_json(const wc_run *run, const cJSON *design)
{
    cJSON *json = cJSON_CreateObject();
    cJSON_AddItemToObject(json, "body",
                          cJSON_Duplicate(cJSON_GetObjectItem(run->fixture, "body"), true));
    const cJSON *friction = cJSON_GetObjectItem(run->fixture, "friction");
    cJSON *form = cJSON_IsObject(friction) ? cJSON_Duplicate(friction, true) : cJSON_CreateObject();
    if (!cJSON_IsObject(friction))
        cJSON_AddItemToObject(form, "static", cJSON_Duplicate(friction, true));
    cJSON_AddItemToObject(json, "friction", form);
    cJSON_AddItemToObject(json, "fixels",
                          cJSON_Duplicate(cJSON_GetObjectItem(design, "fixels"), true));
    if (cJSON_GetObjectItem(run->fixture, "units"))
        cJSON_AddItemToObject(json, "units",
                              cJSON_Duplicate(cJSON_GetObjectItem(run->fixture, "units"), true));
    if (cJSON_GetObjectItem(run->fixture, "supports"))
        cJSON_AddItemToObject(json, "supports",
                              cJSON_Duplicate(cJSON_GetObjectItem(run->fixture, "supports"), true));
    return json;
}

/* --emit-fixture N FILE: design N as a fixture file, named after the
 * part and the design.  -1, or an exit status after saying why not. */
static int emit_fixture(const wc_run *run, const cJSON *result)
{
    const cJSON *designs = cJSON_GetObjectItem(result, "designs");
    int count = cJSON_GetArraySize(designs);
    if (run->emit_design > count)
        return wc_usage_error("design: --emit-fixture %d: the answer has %d design%s",
                              run->emit_design, count, count == 1 ? "" : "s");
    const cJSON *design = cJSON_GetArrayItem(designs, run->emit_design - 1);
    cJSON *body = design_fixture_json(run, design);
    cJSON *json = cJSON_CreateObject();
    char name[256];
    snprintf(name, sizeof name, "%s, design %d",
             cJSON_GetStringValue(cJSON_GetObjectItem(run->fixture, "name")), run->emit_design);
    cJSON_AddStringToObject(json, "name", name);
    const char *keys[] = {"body", "friction", "fixels", "supports"};
    for (int k = 0; k < 4; k++)
        if (cJSON_GetObjectItem(body, keys[k]))
            cJSON_AddItemToObject(json, keys[k], cJSON_DetachItemFromObject(body, keys[k]));
    cJSON_Delete(body);
    const cJSON *units = cJSON_GetObjectItem(run->fixture, "units");
    if (units)
        cJSON_AddItemToObject(json, "units", cJSON_Duplicate(units, true));
    /* Every number as read (cJSON_Print would round some to 15 digits,
     * and a fixel could then leave the boundary). */
    char *text = wp_canonical(json, NULL);
    cJSON_Delete(json);
    FILE *out = fopen(run->emit_file, "w");
    int status = -1;
    if (!out || !text || fprintf(out, "%s\n", text) < 0)
        status = wc_usage_error("--emit-fixture %s: %s", run->emit_file,
                                out ? "cannot write" : strerror(errno));
    if (out && fclose(out) != 0 && status < 0)
        status = wc_usage_error("--emit-fixture %s: %s", run->emit_file, strerror(errno));
    free(text);
    return status;
}

/* A design as a fixture, read as the daemon reads one. */
static wr_fixture *design_fixture(const wc_run *run, const cJSON *design)
{
    cJSON *json = design_fixture_json(run, design);
    wp_fixture_doc doc;
    wp_error error;
    bool ok = wp_fixture_read(json, "fixture", &doc, &error);
    cJSON_Delete(json);
    if (!ok) {
        wc_usage_error("design: a design's fixture: %s: %s", error.field, error.reason);
        return NULL;
    }
    wr_fixture *fixture = doc.fixture;
    doc.fixture = NULL;
    wp_fixture_doc_release(&doc);
    return fixture;
}

/* --svg: the first six designs side by side, their both regions computed
 * here (the same library the daemon uses). */
static int design_pictures(const wc_run *run, const cJSON *result)
{
    enum { MOST = 6 };
    wc_design_panel panels[MOST];
    wr_fixture *fixtures[MOST] = {NULL};
    wr_regions regions[MOST];
    memset(panels, 0, sizeof panels);
    memset(regions, 0, sizeof regions);
    int count = 0, status = -1;
    const cJSON *d;
    cJSON_ArrayForEach(d, cJSON_GetObjectItem(result, "designs"))
    {
        if (count == MOST)
            break;
        fixtures[count] = design_fixture(run, d);
        if (!fixtures[count]) {
            status = EXIT_USAGE;
            break;
        }
        wr_analysis *analysis;
        wr_finger finger = {.friction = run->friction_given ? run->finger_friction : 0,
                            .radius = run->radius_given ? run->finger_radius : 0};
        /* On supports no both region is drawn: the push is the least one
         * that seats the part there (a region of directions is no answer). */
        bool plate = fixtures[count]->supports != NULL;
        if (wr_analysis_new(fixtures[count], &analysis) != WR_OK ||
            (!plate && wr_push_regions_finger(analysis, WR_SET_BOTH, &finger, NULL,
                                              &regions[count]) != WR_OK)) {
            wr_fixture_free(fixtures[count]);
            status = wc_usage_error("design: out of memory drawing");
            break;
        }
        wr_analysis_free(analysis);
        wc_design_panel *p = &panels[count];
        p->fixture = fixtures[count];
        p->regions = regions[count].items;
        p->region_count = regions[count].count;
        p->rank = (int)number(d, "rank");
        for (int k = 0; k < WR_MAX_FIXELS; k++)
            p->pin_diameter[k] = -1;
        const cJSON *pin;
        cJSON_ArrayForEach(pin, cJSON_GetObjectItem(d, "pins"))
        {
            int fixel = (int)number(pin, "fixel");
            if (fixel >= 0 && fixel < WR_MAX_FIXELS)
                p->pin_diameter[fixel] = number(pin, "diameter");
        }
        p->score = number(d, "score");
        p->plate = plate;
        const cJSON *push = cJSON_GetObjectItem(d, plate ? "least_push" : "best_push");
        p->force = plate && cJSON_IsObject(push) ? number(push, "force") : 0;
        if (cJSON_IsObject(push)) {
            p->has_push = true;
            for (int k = 0; k < 2; k++) {
                p->push_at[k] = cJSON_GetArrayItem(cJSON_GetObjectItem(push, "at"), k)->valuedouble;
                p->push_direction[k] =
                    cJSON_GetArrayItem(cJSON_GetObjectItem(push, "direction"), k)->valuedouble;
            }
            p->margin = number(push, "margin");
        }
        const cJSON *pegs = cJSON_GetObjectItem(d, "pegs"), *pose = cJSON_GetObjectItem(d, "pose");
        if (run->lattice_given && cJSON_GetArraySize(pegs) == 3 && cJSON_GetArraySize(pose) == 3) {
            p->lattice = true;
            p->peg_radius = run->lattice[1];
            double x = cJSON_GetArrayItem(pose, 0)->valuedouble;
            double y = cJSON_GetArrayItem(pose, 1)->valuedouble;
            double theta = cJSON_GetArrayItem(pose, 2)->valuedouble * 3.14159265358979323846 / 180;
            for (int m = 0; m < 3; m++) {
                const cJSON *hole = cJSON_GetArrayItem(pegs, m);
                p->holes[m][0] = (int)cJSON_GetArrayItem(hole, 0)->valuedouble;
                p->holes[m][1] = (int)cJSON_GetArrayItem(hole, 1)->valuedouble;
                /* The peg's centre in the part's frame: R(-theta)(P - t). */
                double rel[2] = {run->lattice[0] * p->holes[m][0] - x,
                                 run->lattice[0] * p->holes[m][1] - y};
                p->pegs[m][0] = cos(theta) * rel[0] + sin(theta) * rel[1];
                p->pegs[m][1] = -sin(theta) * rel[0] + cos(theta) * rel[1];
            }
        }
        count++;
    }
    if (status < 0) {
        FILE *out = fopen(run->svg, "w");
        if (!out) {
            status = wc_usage_error("--svg %s: %s", run->svg, strerror(errno));
        } else {
            const char *objective = cJSON_GetStringValue(cJSON_GetObjectItem(result, "objective"));
            wc_svg_designs(out, cJSON_GetStringValue(cJSON_GetObjectItem(run->fixture, "name")),
                           objective ? objective : "margin", panels, count);
            fclose(out);
        }
    }
    for (int i = 0; i < count; i++) {
        wr_regions_release(&regions[i]);
        wr_fixture_free(fixtures[i]);
    }
    return status;
}

/* n with a comma every three digits: "1,001". */
static void grouped(double n, char *out, size_t size)
{
    char digits[32];
    snprintf(digits, sizeof digits, "%.0f", n);
    size_t length = strlen(digits), k = 0;
    for (size_t i = 0; i < length && k + 2 < size; i++) {
        if (i > 0 && (length - i) % 3 == 0)
            out[k++] = ',';
        out[k++] = digits[i];
    }
    out[k] = 0;
}

/* Why no candidate is a design: each reason with its count, and for those
 * without a seating push, why the push asked about does not seat them
 * (why_no_seating_push, in the words of classify's explanations). */
static void explain_no_design(const cJSON *result)
{
    const cJSON *counts = cJSON_GetObjectItem(result, "counts");
    char of[32], n[32];
    grouped(number(counts, "examined"), of, sizeof of);
    printf(WC_EXPLAIN_NO_DESIGN "\n", of);
    static const char *const REASONS[][2] = {
        {"shared_hole", WC_EXPLAIN_NO_DESIGN_SHARED_HOLE},
        {"degenerate", WC_EXPLAIN_NO_DESIGN_DEGENERATE},
        {"unpinned", WC_EXPLAIN_NO_DESIGN_UNPINNED},
        {"no_seating_push", WC_EXPLAIN_NO_DESIGN_NO_SEATING_PUSH}};
    for (size_t i = 0; i < sizeof REASONS / sizeof *REASONS; i++) {
        double count = number(counts, REASONS[i][0]);
        if (count > 0) {
            grouped(count, n, sizeof n);
            printf("  %s %s\n", n, REASONS[i][1]);
        }
    }
    const cJSON *why = cJSON_GetObjectItem(result, "why_no_seating_push");
    const cJSON *asked = cJSON_GetObjectItem(why, "asked_at");
    const cJSON *at = cJSON_GetObjectItem(asked, "at");
    if (cJSON_GetArraySize(cJSON_GetObjectItem(why, "reasons")) == 0 || cJSON_GetArraySize(at) != 2)
        return;
    char place[64] = "";
    if (cJSON_GetObjectItem(asked, "loop"))
        snprintf(place, sizeof place, ", loop %.0f segment %.0f", number(asked, "loop"),
                 number(asked, "segment"));
    else if (cJSON_GetObjectItem(asked, "edge"))
        snprintf(place, sizeof place, ", edge %.0f", number(asked, "edge"));
    grouped(number(counts, "no_seating_push"), of, sizeof of);
    char where[128];
    snprintf(where, sizeof where, "(%.6g, %.6g)%s", cJSON_GetArrayItem(at, 0)->valuedouble,
             cJSON_GetArrayItem(at, 1)->valuedouble, place);
    printf("  " WC_EXPLAIN_NO_DESIGN_ASKED "\n", where);
    const cJSON *reason;
    cJSON_ArrayForEach(reason, cJSON_GetObjectItem(why, "reasons"))
    {
        char words[512];
        const char *blocking = cJSON_GetStringValue(cJSON_GetObjectItem(reason, "blocking"));
        if (blocking)
            wc_explain_goal(blocking, cJSON_GetObjectItem(reason, "states"), words, sizeof words);
        else
            snprintf(words, sizeof words, "%s", WC_EXPLAIN_NO_DESIGN_UNREACHED);
        grouped(number(reason, "candidates"), n, sizeof n);
        printf("    %s of %s: %s\n", n, of, words);
    }
}

int wc_design_answer(wc_run *run, const cJSON *result)
{
    if (run->shard_given) {
        shard_lines(run, result);
        return EXIT_INSIDE;
    }
    const cJSON *designs = cJSON_GetObjectItem(result, "designs");
    const cJSON *counts = cJSON_GetObjectItem(result, "counts");
    /* On supports a design's push is its least push on the plate (the
     * figures of directions are not made: design-merge, which has no
     * fixture, sees it by their absence). */
    const cJSON *first = cJSON_GetArrayItem(designs, 0);
    bool plate = (run->fixture && cJSON_IsObject(cJSON_GetObjectItem(run->fixture, "supports"))) ||
                 (first && !cJSON_GetObjectItem(first, "goal_length"));
    bool any_push = false;
    const cJSON *d;
    cJSON_ArrayForEach(d, designs)
    {
        any_push = any_push ||
                   cJSON_IsObject(cJSON_GetObjectItem(d, plate ? "least_push" : "best_push"));
    }
    if (run->emit_design) {
        int status = emit_fixture(run, result);
        if (status >= 0)
            return status;
    }
    if (run->o->json) {
        /* --json --svg: the picture too. */
        int status = run->svg && run->fixture ? design_pictures(run, result) : -1;
        if (status >= 0)
            return status;
        return any_push ? EXIT_INSIDE : EXIT_NOT_INSIDE;
    }
    const char *objective = cJSON_GetStringValue(cJSON_GetObjectItem(result, "objective"));
    if (cJSON_GetObjectItem(result, "poses"))
        printf("design: 3 pegs on the lattice, %.0f poses of the part touching three",
               number(result, "poses"));
    else
        printf("design: %.0f fixels from %.0f sites, %.0f candidates",
               run->fixels ? run->fixels : 3.0, number(result, "sites"),
               number(counts, "candidates"));
    const cJSON *shard = cJSON_GetObjectItem(result, "shard");
    if (cJSON_GetArraySize(shard) == 2 && cJSON_GetArrayItem(shard, 1)->valuedouble > 1)
        printf(" (shard %.0f of %.0f: %.0f of them)", cJSON_GetArrayItem(shard, 0)->valuedouble,
               cJSON_GetArrayItem(shard, 1)->valuedouble, number(counts, "examined"));
    printf("; %.0f without a seating push, %.0f unpinned, %.0f degenerate", 
           number(counts, "no_seating_push"), number(counts, "unpinned"),
           number(counts, "degenerate"));
    if (number(counts, "shared_hole") > 0)
        printf(", %.0f with two fixels in one hole", number(counts, "shared_hole"));
    printf("; ranked by %s\n", objective ? objective : "margin");
    if (objective && strcmp(objective, "force") == 0 && plate)
        printf("score: minus the least push force, in %s, that seats the part on its supports "
               "under every case (goal: it reaches every fixel, not that the part then rests)\n",
               wc_named_force_unit(run->fixture));
    else if (objective && strcmp(objective, "force") == 0)
        printf("score: minus the least push force (%s) that does both under every case\n",
               wc_named_force_unit(run->fixture));
    if (objective && strcmp(objective, "accuracy") == 0)
        printf("score: minus the worst locating error, locators off by +-%g (the features' worst "
               "displacement, else the pose's in the scaled metric)\n",
               cJSON_IsNumber(run->locate_tolerance) ? run->locate_tolerance->valuedouble : NAN);
    if (objective && strcmp(objective, "pareto") == 0)
        printf("the designs no other beats on the best push's margin, the worst locating error "
               "(locators off by +-%g) and the least push force together; score: the margin\n",
               cJSON_IsNumber(run->locate_tolerance) ? run->locate_tolerance->valuedouble : NAN);
    int symmetries = cJSON_GetArraySize(cJSON_GetObjectItem(result, "symmetries"));
    if (symmetries > 1)
        printf("the part has %d symmetries (the identity among them): designs one maps onto "
               "another are listed once, with how many more it stands for\n",
               symmetries);
    if (cJSON_GetArraySize(designs) > 0 && plate)
        printf("%-4s  %-10s  %s\n", "rank", "score", "fixels at");
    else if (cJSON_GetArraySize(designs) > 0)
        printf("%-4s  %-10s  %-34s  %-30s  %-9s  %-9s  %-7s  %s\n", "rank", "score", "fixels at",
           "best push at -> direction", "goal len", "both len", "gravity", "critical mu");
    /* Points to the drawing's precision (wc_drawing_decimals). */
    int decimals = run->fixture ? wc_drawing_decimals(cJSON_GetObjectItem(
                                      cJSON_GetObjectItem(run->fixture, "body"), "shape"))
                                : run->decimals;
    cJSON_ArrayForEach(d, designs)
    {
        char fixels[512] = "", push[160] = "none", cell[96];
        const cJSON *f;
        cJSON_ArrayForEach(f, cJSON_GetObjectItem(d, "fixels"))
        {
            if (fixels[0])
                strncat(fixels, " ", sizeof fixels - strlen(fixels) - 1);
            wc_point_text(cJSON_GetObjectItem(f, "at"), decimals, cell, sizeof cell);
            strncat(fixels, cell, sizeof fixels - strlen(fixels) - 1);
        }
        const cJSON *best = cJSON_GetObjectItem(d, "best_push");
        if (cJSON_IsObject(best)) {
            const cJSON *direction = cJSON_GetObjectItem(best, "direction");
            wc_point_text(cJSON_GetObjectItem(best, "at"), decimals, cell, sizeof cell);
            snprintf(push, sizeof push, "%s -> (%.3f, %.3f)", cell,
                     cJSON_GetArrayItem(direction, 0)->valuedouble + 0.0,
                     cJSON_GetArrayItem(direction, 1)->valuedouble + 0.0);
        }
        const cJSON *critical = cJSON_GetObjectItem(d, "critical_mu");
        char critical_text[32] = "none below 2";
        if (cJSON_IsNumber(critical))
            snprintf(critical_text, sizeof critical_text, "%.6g", critical->valuedouble);
        if (plate)
            printf("%-4.0f  %-10.6g  %s\n", number(d, "rank"), number(d, "score"), fixels);
        else
            printf("%-4.0f  %-10.6g  %-34s  %-30s  %-9.4g  %-9.4g  %-7.3g  %s\n",
                   number(d, "rank"), number(d, "score"), fixels, push, number(d, "goal_length"),
                   number(d, "both_length"), number(d, "gravity_goal_deg"), critical_text);
        const cJSON *least = cJSON_GetObjectItem(d, "least_push");
        if (cJSON_IsObject(least)) {
            const cJSON *direction = cJSON_GetObjectItem(least, "direction");
            wc_point_text(cJSON_GetObjectItem(least, "at"), decimals, cell, sizeof cell);
            printf("      least push%s %.9g %s at %s -> (%.3f, %.3f)\n",
                   plate ? " on the plate" : "", number(least, "force"),
                   wc_named_force_unit(run->fixture), cell,
                   cJSON_GetArrayItem(direction, 0)->valuedouble + 0.0,
                   cJSON_GetArrayItem(direction, 1)->valuedouble + 0.0);
        } else if (least) {
            printf("      least push: none %s under every case\n",
                   plate ? "seats the part on its supports" : "does both");
        }
        const cJSON *pareto = cJSON_GetObjectItem(d, "pareto");
        if (cJSON_IsObject(pareto)) {
            const cJSON *force = cJSON_GetObjectItem(pareto, "force");
            char force_text[64] = "none";
            if (cJSON_IsNumber(force))
                snprintf(force_text, sizeof force_text, "%.6g %s", force->valuedouble,
                         wc_named_force_unit(run->fixture));
            printf("      pareto: margin %.6g, worst locating error %.6g, least push force %s\n",
                   number(pareto, "margin"), number(pareto, "accuracy"), force_text);
        }
        if (number(d, "copies") > 1)
            printf("      and %.0f more: its images under the part's symmetries\n",
                   number(d, "copies") - 1);
        const cJSON *pegs = cJSON_GetObjectItem(d, "pegs"), *pose = cJSON_GetObjectItem(d, "pose");
        if (cJSON_GetArraySize(pegs) == 3 && cJSON_GetArraySize(pose) == 3) {
            printf("      pegs in holes");
            const cJSON *hole;
            cJSON_ArrayForEach(hole, pegs)
            {
                printf(" (%.0f, %.0f)", cJSON_GetArrayItem(hole, 0)->valuedouble,
                       cJSON_GetArrayItem(hole, 1)->valuedouble);
            }
            printf("; the part at (%.6g, %.6g) turned %.6g degrees\n",
                   cJSON_GetArrayItem(pose, 0)->valuedouble,
                   cJSON_GetArrayItem(pose, 1)->valuedouble,
                   cJSON_GetArrayItem(pose, 2)->valuedouble);
        }
    }
    if (run->svg && run->fixture) {
        int status = design_pictures(run, result);
        if (status >= 0)
            return status;
    }
    if (cJSON_GetArraySize(designs) == 0)
        explain_no_design(result);
    else if (plate)
        printf("Each least push on the plate seats the part (goal: every fixel reached); whether\n"
               "it then rests under a load is wrench.classify --sets strong with push and load.\n");
    else
        printf("Push at the best push and let go: it is in the both region (goal seats the part,\n"
               "strong then holds it); a goal push alone may leave it sliding along its fixels.\n");
    return any_push ? EXIT_INSIDE : EXIT_NOT_INSIDE;
}

/* Does design a beat b on its "pareto" figures (objective pareto): margin
 * at least b's, worst error and least force (null: none) at most b's,
 * one of them strictly?  False for designs without them. */
static bool pareto_beats(const cJSON *a, const cJSON *b)
{
    const cJSON *pa = cJSON_GetObjectItem(a, "pareto"), *pb = cJSON_GetObjectItem(b, "pareto");
    if (!cJSON_IsObject(pa) || !cJSON_IsObject(pb))
        return false;
    const cJSON *fa = cJSON_GetObjectItem(pa, "force"), *fb = cJSON_GetObjectItem(pb, "force");
    double x[3] = {number(pa, "margin"), number(pa, "accuracy"),
                   cJSON_IsNumber(fa) ? fa->valuedouble : INFINITY};
    double y[3] = {number(pb, "margin"), number(pb, "accuracy"),
                   cJSON_IsNumber(fb) ? fb->valuedouble : INFINITY};
    if (!(x[0] >= y[0] && x[1] <= y[1] && x[2] <= y[2]))
        return false;
    return x[0] > y[0] || x[1] < y[1] || x[2] < y[2];
}

/* ---- design-merge -------------------------------------------------------------------- */

/* Adds a shard's why_no_seating_push reasons to `into` ({"asked_at",
 * "reasons"}), summing the candidates of equal blocking strings; the
 * reasons are sorted again, most first, when the last is in. */
static void merge_why(cJSON *into, const cJSON *why)
{
    if (!cJSON_GetObjectItem(into, "asked_at") && cJSON_GetObjectItem(why, "asked_at"))
        cJSON_AddItemToObject(into, "asked_at",
                              cJSON_Duplicate(cJSON_GetObjectItem(why, "asked_at"), true));
    cJSON *reasons = cJSON_GetObjectItem(into, "reasons");
    if (!reasons)
        reasons = cJSON_AddArrayToObject(into, "reasons");
    const cJSON *r;
    cJSON_ArrayForEach(r, cJSON_GetObjectItem(why, "reasons"))
    {
        const char *blocking = cJSON_GetStringValue(cJSON_GetObjectItem(r, "blocking"));
        cJSON *same = NULL, *mine;
        cJSON_ArrayForEach(mine, reasons)
        {
            const char *other = cJSON_GetStringValue(cJSON_GetObjectItem(mine, "blocking"));
            if ((!blocking && !other) || (blocking && other && strcmp(blocking, other) == 0))
                same = mine;
        }
        if (same)
            cJSON_ReplaceItemInObject(same, "candidates",
                                      cJSON_CreateNumber(number(same, "candidates") +
                                                         number(r, "candidates")));
        else
            cJSON_AddItemToArray(reasons, cJSON_Duplicate(r, true));
    }
}

/* Does reason a come before b: more candidates, then by blocking string,
 * null last (as the daemon orders them)? */
static bool reason_before(const cJSON *a, const cJSON *b)
{
    double na = number(a, "candidates"), nb = number(b, "candidates");
    if (na != nb)
        return na > nb;
    const char *sa = cJSON_GetStringValue(cJSON_GetObjectItem(a, "blocking"));
    const char *sb = cJSON_GetStringValue(cJSON_GetObjectItem(b, "blocking"));
    return sa && (!sb || strcmp(sa, sb) < 0);
}

/* The merged reasons in the daemon's order. */
static void sort_why(cJSON *why)
{
    cJSON *reasons = cJSON_GetObjectItem(why, "reasons");
    int n = cJSON_GetArraySize(reasons);
    cJSON **all = calloc((size_t)(n ? n : 1), sizeof *all);
    for (int k = 0; all && k < n; k++)
        all[k] = cJSON_DetachItemViaPointer(reasons, reasons->child);
    for (int a = 1; all && a < n; a++)
        for (int b = a; b > 0 && reason_before(all[b], all[b - 1]); b--) {
            cJSON *swap = all[b];
            all[b] = all[b - 1];
            all[b - 1] = swap;
        }
    for (int k = 0; all && k < n; k++)
        cJSON_AddItemToArray(reasons, all[k]);
    free(all);
}

static bool same_number(const cJSON *a, const cJSON *b)
{
    return cJSON_IsNumber(a) && cJSON_IsNumber(b) && a->valuedouble == b->valuedouble;
}

/* Does design a rank before b: score, then candidate number. */
static bool ranks_before(const cJSON *a, const cJSON *b)
{
    double sa = number(a, "score"), sb = number(b, "score");
    if (sa != sb)
        return sa > sb;
    return number(a, "candidate") < number(b, "candidate");
}

int wc_design_merge_request(wc_run *run, cJSON *params)
{
    (void)params;
    cJSON *designs = cJSON_CreateArray(), *first = NULL, *why = cJSON_CreateObject();
    enum { COUNTS = 7 };
    double counts[COUNTS] = {0};
    static const char *const COUNT_NAMES[COUNTS] = {"candidates", "examined", "degenerate",
                                                    "unpinned", "no_seating_push", "shared_hole",
                                                    "symmetric"};
    int shard_count = 0, summaries = 0;
    bool *seen = NULL;
    int status = EXIT_INSIDE;
    for (int f = 0; f < run->count && status == EXIT_INSIDE; f++) {
        FILE *file = strcmp(run->items[f], "-") == 0 ? stdin : fopen(run->items[f], "r");
        if (!file) {
            status = wc_usage_error("design-merge: cannot open '%s'", run->items[f]);
            break;
        }
        char *text = wc_read_all(file, NULL);
        if (file != stdin)
            fclose(file);
        int line_number = 0;
        for (char *line = text ? strtok(text, "\n") : NULL; line && status == EXIT_INSIDE;
             line = strtok(NULL, "\n")) {
            line_number++;
            cJSON *json = cJSON_Parse(line);
            if (!cJSON_IsObject(json)) {
                cJSON_Delete(json);
                status = wc_usage_error("design-merge: %s line %d is not a JSON object",
                                        run->items[f], line_number);
                break;
            }
            if (cJSON_GetObjectItem(json, "candidate")) {
                cJSON_AddItemToArray(designs, json);
                continue;
            }
            const cJSON *shard = cJSON_GetObjectItem(json, "shard");
            const cJSON *n = cJSON_GetArrayItem(shard, 1), *i = cJSON_GetArrayItem(shard, 0);
            if (!cJSON_GetObjectItem(json, "counts") || !cJSON_IsNumber(n) || !cJSON_IsNumber(i) ||
                n->valuedouble < 1 || i->valuedouble < 0 || i->valuedouble >= n->valuedouble) {
                cJSON_Delete(json);
                status = wc_usage_error("design-merge: %s line %d is neither a design nor a "
                                        "shard's summary", run->items[f], line_number);
                break;
            }
            if (!first) {
                first = json;
                const cJSON *decimals = cJSON_GetObjectItem(json, "decimals");
                run->decimals = cJSON_IsNumber(decimals) ? (int)decimals->valuedouble : -1;
                shard_count = (int)n->valuedouble;
                seen = calloc((size_t)shard_count, sizeof *seen);
                counts[0] = number(cJSON_GetObjectItem(json, "counts"), "candidates");
            } else {
                /* Shards of one design: the same candidates, objective and top. */
                const char *keys[] = {"sites", "poses", "top"};
                bool same = same_number(cJSON_GetArrayItem(cJSON_GetObjectItem(first, "shard"), 1), n);
                for (int k = 0; k < 3; k++)
                    if (cJSON_GetObjectItem(first, keys[k]) || cJSON_GetObjectItem(json, keys[k]))
                    same = same && same_number(cJSON_GetObjectItem(first, keys[k]),
                                               cJSON_GetObjectItem(json, keys[k]));
                same = same && strcmp(cJSON_GetStringValue(cJSON_GetObjectItem(first, "objective")),
                                      cJSON_GetStringValue(cJSON_GetObjectItem(json, "objective"))) == 0;
                if (!same) {
                    cJSON_Delete(json);
                    status = wc_usage_error("design-merge: %s line %d is a shard of another design "
                                            "(its shard count, sites, objective or top differ)",
                                            run->items[f], line_number);
                    break;
                }
            }
            int index = (int)i->valuedouble;
            if (seen[index]) {
                if (json != first)
                    cJSON_Delete(json);
                status = wc_usage_error("design-merge: shard %d of %d given twice", index,
                                        shard_count);
                break;
            }
            seen[index] = true;
            summaries++;
            for (int k = 1; k < COUNTS; k++)
                counts[k] += number(cJSON_GetObjectItem(json, "counts"), COUNT_NAMES[k]);
            merge_why(why, cJSON_GetObjectItem(json, "why_no_seating_push"));
            if (json != first)
                cJSON_Delete(json);
        }
        free(text);
    }
    if (status == EXIT_INSIDE && !first)
        status = wc_usage_error("design-merge: no shard's summary line in the input");
    if (status == EXIT_INSIDE && summaries < shard_count) {
        fprintf(stderr, "wrenchctl: design-merge: %d of %d shards given; missing:", summaries,
                shard_count);
        for (int k = 0; k < shard_count; k++)
            if (!seen[k])
                fprintf(stderr, " %d", k);
        fputs("; the answer covers only those given\n", stderr);
    }
    if (status == EXIT_INSIDE) {
        /* Sort by rank (insertion: shards' outputs are short), keep top. */
        int n = cJSON_GetArraySize(designs);
        cJSON **all = calloc((size_t)(n ? n : 1), sizeof *all);
        int k = 0;
        while (designs->child)
            all[k++] = cJSON_DetachItemViaPointer(designs, designs->child);
        for (int a = 1; a < n; a++)
            for (int b = a; b > 0 && ranks_before(all[b], all[b - 1]); b--) {
                cJSON *swap = all[b];
                all[b] = all[b - 1];
                all[b - 1] = swap;
            }
        int top = (int)number(first, "top");
        cJSON *result = cJSON_CreateObject();
        cJSON *kept = cJSON_AddArrayToObject(result, "designs");
        /* A Pareto front's shards each hold their own front: a design
         * another shard's beats is not on the whole front. */
        for (int a = 0; a < n; a++)
            for (int b = 0; all[a] && b < n; b++)
                if (b != a && all[b] && pareto_beats(all[b], all[a])) {
                    cJSON_Delete(all[a]);
                    all[a] = NULL;
                }
        int listed = 0;
        for (int a = 0; a < n; a++) {
            if (!all[a])
                continue;
            if (listed++ < top) {
                int a_rank = listed;
                cJSON_ReplaceItemInObject(all[a], "rank", cJSON_CreateNumber(a_rank));
                cJSON_AddItemToArray(kept, all[a]);
            } else {
                cJSON_Delete(all[a]);
            }
        }
        free(all);
        cJSON *total = cJSON_AddObjectToObject(result, "counts");
        for (int c = 0; c < COUNTS; c++)
            cJSON_AddNumberToObject(total, COUNT_NAMES[c], counts[c]);
        sort_why(why);
        cJSON_AddItemToObject(result, "why_no_seating_push", why);
        why = NULL;
        const cJSON *symmetries = cJSON_GetObjectItem(first, "symmetries");
        if (symmetries)
            cJSON_AddItemToObject(result, "symmetries", cJSON_Duplicate(symmetries, true));
        const char *source = cJSON_GetObjectItem(first, "poses") ? "poses" : "sites";
        cJSON_AddItemToObject(result, source,
                              cJSON_Duplicate(cJSON_GetObjectItem(first, source), true));
        cJSON_AddItemToObject(result, "objective",
                              cJSON_Duplicate(cJSON_GetObjectItem(first, "objective"), true));
        cJSON_AddItemToObject(result, "shard", cJSON_CreateIntArray((int[2]){0, 1}, 2));
        run->fixels = cJSON_GetArraySize(cJSON_GetObjectItem(cJSON_GetArrayItem(kept, 0), "sites"));
        if (run->o->json)
            wc_print_json(result);
        status = wc_design_answer(run, result);
        cJSON_Delete(result);
    }
    free(seen);
    cJSON_Delete(why);
    cJSON_Delete(first);
    cJSON_Delete(designs);
    return status;
}
