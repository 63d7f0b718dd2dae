/* wc_design.c -- wrenchctl design: fixture.design's request from a body
 * file and options, a progress bar on a terminal, the ranked table. */
#include "wc_call.h"
#include "wc_commands.h"
#include "wc_print.h"
#include "wc_svg.h"

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
    cJSON_Delete(json);
    /* For --svg: the body and friction, to draw each design as a fixture. */
    run->fixture = cJSON_CreateObject();
    cJSON_AddStringToObject(run->fixture, "name", name ? name : "design");
    free(name);
    cJSON_AddItemToObject(run->fixture, "body",
                          cJSON_Duplicate(cJSON_GetObjectItem(params, "body"), true));
    cJSON_AddItemToObject(run->fixture, "friction",
                          cJSON_Duplicate(cJSON_GetObjectItem(params, "friction"), true));
    if (run->fixels)
        cJSON_AddNumberToObject(params, "fixels", run->fixels);
    if (run->top)
        cJSON_AddNumberToObject(params, "top", run->top);
    if (run->objective)
        cJSON_AddStringToObject(params, "objective", run->objective);
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
    char *line = cJSON_PrintUnformatted(rest);
    if (line)
        printf("%s\n", line);
    free(line);
    cJSON_Delete(rest);
}

/* A design as a fixture: the request's body and friction with its fixels
 * (friction as a number or an interval becomes the fixture's form). */
static wr_fixture *design_fixture(const wc_run *run, const cJSON *design)
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
        wr_finger finger = {run->friction_given ? run->finger_friction : 0,
                            run->radius_given ? run->finger_radius : 0};
        if (wr_analysis_new(fixtures[count], &analysis) != WR_OK ||
            wr_push_regions_finger(analysis, WR_SET_BOTH, &finger, NULL, &regions[count]) !=
                WR_OK) {
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
        p->score = number(d, "score");
        const cJSON *push = cJSON_GetObjectItem(d, "best_push");
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

int wc_design_answer(wc_run *run, const cJSON *result)
{
    if (run->shard_given) {
        shard_lines(run, result);
        return EXIT_INSIDE;
    }
    const cJSON *designs = cJSON_GetObjectItem(result, "designs");
    const cJSON *counts = cJSON_GetObjectItem(result, "counts");
    bool any_push = false;
    const cJSON *d;
    cJSON_ArrayForEach(d, designs)
    {
        any_push = any_push || cJSON_IsObject(cJSON_GetObjectItem(d, "best_push"));
    }
    if (run->o->json)
        return any_push ? EXIT_INSIDE : EXIT_NOT_INSIDE;
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
    printf("; %.0f without a seating push, %.0f unpinned, %.0f degenerate; ranked by %s\n",
           number(counts, "no_seating_push"), number(counts, "unpinned"),
           number(counts, "degenerate"), objective ? objective : "margin");
    int symmetries = cJSON_GetArraySize(cJSON_GetObjectItem(result, "symmetries"));
    if (symmetries > 1)
        printf("the part has %d symmetries (the identity among them): designs one maps onto "
               "another are listed once, with how many more it stands for\n",
               symmetries);
    printf("%-4s  %-10s  %-34s  %-30s  %-9s  %-9s  %-7s  %s\n", "rank", "score", "fixels at",
           "best push at -> direction", "goal len", "both len", "gravity", "critical mu");
    cJSON_ArrayForEach(d, designs)
    {
        char fixels[256] = "", push[128] = "none", cell[64];
        const cJSON *f;
        cJSON_ArrayForEach(f, cJSON_GetObjectItem(d, "fixels"))
        {
            const cJSON *at = cJSON_GetObjectItem(f, "at");
            snprintf(cell, sizeof cell, "%s(%.4g, %.4g)", fixels[0] ? " " : "",
                     cJSON_GetArrayItem(at, 0)->valuedouble, cJSON_GetArrayItem(at, 1)->valuedouble);
            strncat(fixels, cell, sizeof fixels - strlen(fixels) - 1);
        }
        const cJSON *best = cJSON_GetObjectItem(d, "best_push");
        if (cJSON_IsObject(best)) {
            const cJSON *at = cJSON_GetObjectItem(best, "at");
            const cJSON *direction = cJSON_GetObjectItem(best, "direction");
            snprintf(push, sizeof push, "(%.4g, %.4g) -> (%.3g, %.3g)",
                     cJSON_GetArrayItem(at, 0)->valuedouble, cJSON_GetArrayItem(at, 1)->valuedouble,
                     cJSON_GetArrayItem(direction, 0)->valuedouble + 0.0,
                     cJSON_GetArrayItem(direction, 1)->valuedouble + 0.0);
        }
        const cJSON *critical = cJSON_GetObjectItem(d, "critical_mu");
        char critical_text[32] = "none below 2";
        if (cJSON_IsNumber(critical))
            snprintf(critical_text, sizeof critical_text, "%.6g", critical->valuedouble);
        printf("%-4.0f  %-10.6g  %-34s  %-30s  %-9.4g  %-9.4g  %-7.3g  %s\n", number(d, "rank"),
               number(d, "score"), fixels, push, number(d, "goal_length"),
               number(d, "both_length"), number(d, "gravity_goal_deg"), critical_text);
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
        printf("no design: no candidate has a push that seats the part\n");
    else
        printf("Push at the best push and let go: it is in the both region (goal seats the part,\n"
               "strong then holds it); a goal push alone may leave it sliding along its fixels.\n");
    return any_push ? EXIT_INSIDE : EXIT_NOT_INSIDE;
}

/* ---- design-merge -------------------------------------------------------------------- */

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
    cJSON *designs = cJSON_CreateArray(), *first = NULL;
    double counts[6] = {0};
    static const char *const COUNT_NAMES[6] = {"candidates", "examined", "degenerate", "unpinned",
                                               "no_seating_push", "symmetric"};
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
            for (int k = 1; k < 6; k++)
                counts[k] += number(cJSON_GetObjectItem(json, "counts"), COUNT_NAMES[k]);
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
        for (int a = 0; a < n; a++) {
            if (a < top) {
                cJSON_ReplaceItemInObject(all[a], "rank", cJSON_CreateNumber(a + 1));
                cJSON_AddItemToArray(kept, all[a]);
            } else {
                cJSON_Delete(all[a]);
            }
        }
        free(all);
        cJSON *total = cJSON_AddObjectToObject(result, "counts");
        for (int c = 0; c < 6; c++)
            cJSON_AddNumberToObject(total, COUNT_NAMES[c], counts[c]);
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
    cJSON_Delete(first);
    cJSON_Delete(designs);
    return status;
}
