/* test_design.c -- fixture design (lib/wr_design.h): sites by spacing in
 * closed form; fixels placed on a body equal the fixture built whole; the
 * best push against dense sampling of the region's margin, refined by
 * golden sections; the search against a brute force over every candidate;
 * shards merged against one run. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "test_util.h"

#define WR_TEST_PI 3.14159265358979323846

/* A 10 x 4 plate with its corner at the origin. */
static const double PLATE[4][2] = {{0, 0}, {10, 0}, {10, 4}, {0, 4}};
/* A 12-sided plate: a 12 x 8 rectangle with chamfered corners and a notch. */
static const double DODECAGON[12][2] = {{1, 0},  {11, 0}, {12, 1}, {12, 7}, {11, 8}, {7, 8},
                                        {7, 6},  {5, 6},  {5, 8},  {1, 8},  {0, 7},  {0, 1}};


static void spaced_sites_closed_form(void **state)
{
    (void)state;
    wr_fixture *body = test_polygon_body(PLATE, 4);
    assert_non_null(body);
    wr_site *sites = NULL;
    int count = 0;
    wr_error error;
    assert_int_equal(wr_sites_spaced(body, &(wr_spacing){2, 2 / 2.0, 0}, &sites, &count, &error), WR_OK);
    /* 10 / 2 = 5 sites on the long sides (1, 3, 5, 7, 9 from a corner),
     * 4 / 2 = 2 on the short ones (1, 3). */
    assert_int_equal(count, 14);
    static const double expected[14][4] = {
        {1, 0, 0, 1},  {3, 0, 0, 1},  {5, 0, 0, 1},  {7, 0, 0, 1},  {9, 0, 0, 1},
        {10, 1, -1, 0}, {10, 3, -1, 0}, {9, 4, 0, -1}, {7, 4, 0, -1}, {5, 4, 0, -1},
        {3, 4, 0, -1}, {1, 4, 0, -1}, {0, 3, 1, 0},  {0, 1, 1, 0}};
    for (int i = 0; i < 14; i++) {
        assert_true(fabs(sites[i].at[0] - expected[i][0]) <= 1e-12);
        assert_true(fabs(sites[i].at[1] - expected[i][1]) <= 1e-12);
        assert_true(fabs(sites[i].normal[0] - expected[i][2]) <= 1e-12);
        assert_true(fabs(sites[i].normal[1] - expected[i][3]) <= 1e-12);
    }
    /* 3 on a side of 10 fits 3 sites, 3.5 from each end: 3.5, 6.5 ... */
    count = 0;
    assert_int_equal(wr_sites_spaced(body, &(wr_spacing){3, 3 / 2.0, 0}, &sites, &count, &error), WR_OK);
    assert_int_equal(count, 3 + 1 + 3 + 1);
    assert_true(fabs(sites[0].at[0] - 2) <= 1e-12 && fabs(sites[2].at[0] - 8) <= 1e-12);
    assert_true(fabs(sites[3].at[1] - 2) <= 1e-12);
    count = 0;
    assert_int_equal(wr_sites_spaced(body, &(wr_spacing){0, 0 / 2.0, 0}, &sites, &count, &error), WR_INVALID);
    assert_int_equal(wr_sites_spaced(body, &(wr_spacing){1e-9, 1e-9 / 2.0, 0}, &sites, &count, &error), WR_INVALID);
    assert_int_equal(count, 0);
    free(sites);
    wr_fixture_free(body);
}

/* A circle drawn as 36 straight segments turns 10 degrees at each joint,
 * below the corner angle: one closed run, floor(P / h) sites P / n apart
 * from vertex 0 along the loop, walked here edge by edge; a site on a
 * joint takes the bisector of the two edges' normals, pointing to the
 * centre.  With clearance c the rectangle's long side of 10 holds
 * floor((10 - 2c) / h) + 1 sites. */
static void spaced_sites_by_arc_length(void **state)
{
    (void)state;
    double polygon[36][2];
    for (int i = 0; i < 36; i++) {
        polygon[i][0] = 10 * cos(i * WR_TEST_PI / 18);
        polygon[i][1] = 10 * sin(i * WR_TEST_PI / 18);
    }
    wr_fixture *body = test_polygon_body(polygon, 36);
    assert_non_null(body);
    double side = 20 * sin(WR_TEST_PI / 36), perimeter = 36 * side;
    for (double h = 0.7; h < 8; h += 1.3) {
        wr_site *sites = NULL;
        int count = 0;
        wr_error error;
        assert_int_equal(wr_sites_spaced(body, &(wr_spacing){h, 0.01, 0}, &sites, &count, &error),
                         WR_OK);
        int n = (int)floor(perimeter / h);
        assert_int_equal(count, n);
        for (int k = 0; k < n; k++) {
            double s = perimeter * k / n;
            int edge = (int)floor(s / side + 1e-12);
            double t = s / side - edge;
            if (edge >= 36)
                edge = 35, t = 1;
            const double *a = polygon[edge], *b = polygon[(edge + 1) % 36];
            double p[2] = {a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])};
            assert_true(hypot(sites[k].at[0] - p[0], sites[k].at[1] - p[1]) <= 1e-9);
            /* Inward: along the edge's normal, or the bisector at a joint. */
            double mid = t < 1e-9 ? edge * WR_TEST_PI / 18 : (edge + 0.5) * WR_TEST_PI / 18;
            assert_true(hypot(sites[k].normal[0] + cos(mid), sites[k].normal[1] + sin(mid)) <= 1e-9);
        }
        free(sites);
    }
    wr_fixture_free(body);
    body = test_polygon_body(PLATE, 4);
    wr_site *sites = NULL;
    int count = 0;
    wr_error error;
    assert_int_equal(wr_sites_spaced(body, &(wr_spacing){2, 0.5, 0}, &sites, &count, &error), WR_OK);
    /* Long sides: (10 - 1) / 2 -> 5 sites at 1, 3, ..., 9 centred; short:
     * (4 - 1) / 2 -> 2 sites. */
    assert_int_equal(count, 2 * 5 + 2 * 2);
    count = 0;
    assert_int_equal(wr_sites_spaced(body, &(wr_spacing){2, 3, 0}, &sites, &count, &error), WR_OK);
    /* (10 - 6) / 2 + 1 = 3 on a long side; a short side is shorter than 6. */
    assert_int_equal(count, 6);
    assert_true(fabs(sites[0].at[0] - 3) <= 1e-12 && fabs(sites[2].at[0] - 7) <= 1e-12);
    count = 0;
    assert_int_equal(wr_sites_spaced(body, &(wr_spacing){2, 0, 0}, &sites, &count, &error),
                     WR_INVALID);
    assert_string_equal(error.field, "corner_clearance");
    free(sites);
    wr_fixture_free(body);
}

/* wr_fixture_place gives wr_fixture_new's fixture, bit for bit. */
static void placed_equals_whole(void **state)
{
    (void)state;
    wr_fixture *body = test_polygon_body(DODECAGON, 12);
    assert_non_null(body);
    wr_fixel_spec fixels[3];
    memset(fixels, 0, sizeof fixels);
    const double at[3][2] = {{4, 0}, {12, 3}, {0, 5}};
    for (int i = 0; i < 3; i++)
        memcpy(fixels[i].at, at[i], sizeof at[i]);
    wr_friction_spec friction = {.given = true, .static_mu = 0.3};
    wr_fixture_spec spec;
    memset(&spec, 0, sizeof spec);
    spec.mass = 1;
    spec.shape = WR_SHAPE_POLYGON;
    spec.vertex_count = 12;
    spec.vertices = DODECAGON;
    spec.friction = friction;
    spec.fixel_count = 3;
    spec.fixels = fixels;
    wr_error error;
    wr_fixture *whole = test_fixture_new(&spec, &error);
    wr_fixture placed;
    assert_int_equal(wr_fixture_place(body, fixels, 3, &friction, &placed, &error), WR_OK);
    assert_int_equal(placed.fixel_count, 3);
    assert_memory_equal(placed.fixels, whole->fixels, sizeof whole->fixels);
    assert_true(placed.com[0] == whole->com[0] && placed.com[1] == whole->com[1]);
    assert_true(placed.inertia == whole->inertia && placed.size == whole->size);
    /* Refusals name the fixel. */
    fixels[1].at[0] = 13;
    assert_int_equal(wr_fixture_place(body, fixels, 3, &friction, &placed, &error), WR_INVALID);
    assert_string_equal(error.field, "fixels[1].at");
    fixels[1] = fixels[0];
    assert_int_equal(wr_fixture_place(body, fixels, 3, &friction, &placed, &error), WR_INVALID);
    assert_string_equal(error.field, "fixels[1]");
    wr_fixture_free(whole);
    wr_fixture_free(body);
}

/* The fixture of three sites, as fixture.design places a candidate; false
 * when the fixels are refused. */
static bool place_three(const wr_fixture *body, const wr_site *sites, int i, int j, int k,
                        const wr_friction_spec *friction, wr_fixture *fixture)
{
    wr_fixel_spec fixels[3];
    memset(fixels, 0, sizeof fixels);
    int chosen[3] = {i, j, k};
    for (int m = 0; m < 3; m++) {
        memcpy(fixels[m].at, sites[chosen[m]].at, sizeof fixels[m].at);
        fixels[m].normal_given = true;
        memcpy(fixels[m].normal, sites[chosen[m]].normal, sizeof fixels[m].normal);
    }
    wr_error error;
    return wr_fixture_place(body, fixels, 3, friction, fixture, &error) == WR_OK;
}

static double both_margin(const wr_analysis *analysis, int edge, double t)
{
    double w[3];
    wr_push_wrench(wr_analysis_fixture(analysis), edge, t, w);
    wr_answer answer;
    assert_int_equal(wr_classify(analysis, w, WR_SET_BOTH, 0, &answer), WR_OK);
    return answer.margin;
}

/* The largest margin near t in [lo, hi], by golden sections (a local
 * search: it only sharpens the sampled maximum). */
static double golden(const wr_analysis *analysis, int edge, double lo, double hi)
{
    const double g = (sqrt(5) - 1) / 2;
    double a = lo, b = hi;
    for (int i = 0; i < 80; i++) {
        double c = b - g * (b - a), d = a + g * (b - a);
        if (both_margin(analysis, edge, c) > both_margin(analysis, edge, d))
            b = d;
        else
            a = c;
    }
    return both_margin(analysis, edge, (a + b) / 2);
}

/* On every candidate of 3 of the dodecagon's sites spaced 2 apart: the
 * best push is never below any sampled margin of the region (by more than
 * the tolerance), and is a margin at a point of it. */
static void best_push_against_sampling(void **state)
{
    (void)state;
    wr_fixture *body = test_polygon_body(DODECAGON, 12);
    assert_non_null(body);
    wr_site *sites = NULL;
    int count = 0;
    wr_error error;
    assert_int_equal(wr_sites_spaced(body, &(wr_spacing){2, 2 / 2.0, 0}, &sites, &count, &error), WR_OK);
    wr_friction_spec friction = {.given = true, .static_mu = 0.25};
    int checked = 0, samples = 0;
    double worst_gap = 0;
    for (int i = 0; i < count; i += 1)
        for (int j = i + 1; j < count; j++)
            for (int k = j + 1; k < count; k++) {
                wr_fixture fixture;
                if (!place_three(body, sites, i, j, k, &friction, &fixture))
                    continue;
                wr_analysis *analysis = test_analysis_new(&fixture);
                wr_regions both;
                assert_int_equal(wr_push_regions(analysis, WR_SET_BOTH, 0, NULL, &both), WR_OK);
                wr_best_push best;
                bool below;
                assert_int_equal(wr_best_push_find(analysis, &both, -INFINITY, NULL, &best, &below),
                                 WR_OK);
                assert_false(below);
                assert_int_equal(best.found, both.count > 0);
                if (best.found) {
                    checked++;
                    /* A margin at a point: classify agrees, to the last bits. */
                    assert_true(fabs(both_margin(analysis, best.edge, best.t) - best.margin) <=
                                1e-15);
                    for (int r = 0; r < both.count; r++) {
                        const wr_region *region = &both.items[r];
                        int n = 200, top = 0;
                        double top_margin = -2;
                        for (int s = 0; s <= n; s++) {
                            double t = region->t0 + (region->t1 - region->t0) * s / n;
                            double m = both_margin(analysis, region->edge, t);
                            samples++;
                            assert_true(m <= best.margin + WR_DESIGN_TOLERANCE);
                            if (m > top_margin) {
                                top_margin = m;
                                top = s;
                            }
                        }
                        double step = (region->t1 - region->t0) / n;
                        double lo = fmax(region->t0, region->t0 + (top - 1) * step);
                        double hi = fmin(region->t1, region->t0 + (top + 1) * step);
                        double refined = golden(analysis, region->edge, lo, hi);
                        assert_true(refined <= best.margin + WR_DESIGN_TOLERANCE);
                        worst_gap = fmax(worst_gap, refined - best.margin);
                    }
                }
                wr_regions_release(&both);
                wr_analysis_free(analysis);
            }
    print_message("best push: %d candidates with a both region, %d samples; the refined "
                  "samples exceed the best push by at most %.3g\n",
                  checked, samples, worst_gap);
    assert_true(checked >= 20);
    free(sites);
    wr_fixture_free(body);
}

typedef struct brute {
    uint64_t candidate;
    double score;
} brute;

static int brute_order(const void *x, const void *y)
{
    const brute *a = x, *b = y;
    if (a->score != b->score)
        return a->score > b->score ? -1 : 1;
    return a->candidate < b->candidate ? -1 : a->candidate > b->candidate;
}

static void run_job(const wr_design_spec *spec, wr_design_job **out)
{
    wr_error error;
    assert_int_equal(wr_design_job_new(spec, out, &error), WR_OK);
    bool done = false;
    int runs = 0;
    while (!done) {
        assert_int_equal(wr_design_job_run(*out, 20000, NULL, NULL, NULL, &done), WR_OK);
        runs++;
    }
    assert_true(runs > 1);
}

/* The search against scoring every candidate without any bound, and one
 * run against three shards merged. */
static void search_against_brute_force(void **state)
{
    (void)state;
    wr_fixture *body = test_polygon_body(DODECAGON, 12);
    assert_non_null(body);
    wr_site *sites = NULL;
    int count = 0;
    wr_error error;
    assert_int_equal(wr_sites_spaced(body, &(wr_spacing){3, 3 / 2.0, 0}, &sites, &count, &error), WR_OK);
    for (int objective = 0; objective < 3; objective++) {
        wr_design_spec spec = {
            .body = body,
            .friction = {.given = true, .static_mu = 0.2},
            .sites = sites,
            .site_count = count,
            .fixel_count = 3,
            .objective = (wr_objective)objective,
            .top = 6,
            .finger = {0, 0},
            .shard_index = 0,
            .shard_count = 1,
        };
        uint64_t total = wr_design_candidates(count, 3);
        brute *all = calloc(total, sizeof *all);
        uint64_t scored = 0, unpinned = 0, degenerate = 0, no_push = 0, r = 0;
        for (int i = 0; i < count; i++)
            for (int j = i + 1; j < count; j++)
                for (int k = j + 1; k < count; k++, r++) {
                    wr_fixture fixture;
                    if (!place_three(body, sites, i, j, k, &spec.friction, &fixture)) {
                        degenerate++;
                        continue;
                    }
                    wr_analysis *analysis = test_analysis_new(&fixture);
                    wr_regions goal, both, arcs;
                    assert_int_equal(wr_push_regions(analysis, WR_SET_GOAL, 0, NULL, &goal), WR_OK);
                    if (!wr_analysis_pinned(analysis))
                        unpinned++;
                    else if (goal.count == 0)
                        no_push++;
                    else {
                        double score = 0;
                        assert_int_equal(wr_push_regions(analysis, WR_SET_BOTH, 0, NULL, &both),
                                         WR_OK);
                        if (objective == WR_OBJECTIVE_MARGIN) {
                            wr_best_push best;
                            bool below;
                            assert_int_equal(wr_best_push_find(analysis, &both, -INFINITY, NULL,
                                                               &best, &below),
                                             WR_OK);
                            score = best.found ? best.margin : 0;
                        } else if (objective == WR_OBJECTIVE_REGION) {
                            for (int m = 0; m < both.count; m++)
                                score += wr_region_length(&fixture, &both.items[m]);
                        } else {
                            assert_int_equal(wr_gravity_sweep(analysis, WR_SET_GOAL, &arcs), WR_OK);
                            /* The longest arc, joined across 0 degrees. */
                            for (int m = 0; m < arcs.count; m++)
                                score = fmax(score, arcs.items[m].t1 - arcs.items[m].t0);
                            if (arcs.count > 1 && arcs.items[0].t0 == 0 &&
                                arcs.items[arcs.count - 1].t1 == 360)
                                score = fmax(score, arcs.items[0].t1 + 360 -
                                                        arcs.items[arcs.count - 1].t0);
                            wr_regions_release(&arcs);
                        }
                        all[scored++] = (brute){r, score};
                        wr_regions_release(&both);
                    }
                    wr_regions_release(&goal);
                    wr_analysis_free(analysis);
                }
        qsort(all, scored, sizeof *all, brute_order);
        wr_design_job *job;
        run_job(&spec, &job);
        int n;
        const wr_design *designs = wr_design_job_designs(job, &n);
        const wr_design_counts *counts = wr_design_job_counts(job);
        assert_int_equal(counts->examined, total);
        assert_int_equal(counts->degenerate, degenerate);
        assert_int_equal(counts->unpinned, unpinned);
        assert_int_equal(counts->no_seating_push, no_push);
        assert_int_equal(n, scored < 6 ? scored : 6);
        for (int i = 0; i < n; i++) {
            assert_int_equal(designs[i].candidate, all[i].candidate);
            assert_true(designs[i].score == all[i].score);
            assert_true(designs[i].both_length >= 0 && designs[i].goal_length > 0);
            if (objective == WR_OBJECTIVE_MARGIN)
                assert_true(designs[i].best_push.found
                                ? designs[i].best_push.margin == designs[i].score
                                : designs[i].score == 0);
        }
        print_message("objective %d: %llu candidates, %llu scored, %llu unpinned, %llu "
                      "degenerate, %llu without a seating push, %llu ended by the bound; best "
                      "%.9g\n",
                      objective, (unsigned long long)total, (unsigned long long)scored,
                      (unsigned long long)unpinned, (unsigned long long)degenerate,
                      (unsigned long long)no_push, (unsigned long long)counts->bounded,
                      n ? designs[0].score : 0.0);
        /* Three shards, merged. */
        wr_design merged[3 * 6];
        int merged_count = 0;
        uint64_t examined = 0;
        for (int s = 0; s < 3; s++) {
            wr_design_spec shard = spec;
            shard.shard_index = s;
            shard.shard_count = 3;
            wr_design_job *part;
            run_job(&shard, &part);
            int m;
            const wr_design *d = wr_design_job_designs(part, &m);
            for (int i = 0; i < m; i++) {
                assert_int_equal(d[i].candidate % 3, s);
                merged[merged_count++] = d[i];
            }
            examined += wr_design_job_counts(part)->examined;
            wr_design_job_free(part);
        }
        assert_int_equal(examined, total);
        for (int i = 1; i < merged_count; i++)
            for (int j = i; j > 0 && wr_design_before(&merged[j], &merged[j - 1]); j--) {
                wr_design swap = merged[j];
                merged[j] = merged[j - 1];
                merged[j - 1] = swap;
            }
        for (int i = 0; i < n; i++) {
            assert_int_equal(merged[i].candidate, designs[i].candidate);
            assert_memory_equal(&merged[i], &designs[i], sizeof merged[i]);
        }
        wr_design_job_free(job);
        free(all);
    }
    free(sites);
    wr_fixture_free(body);
}

/* Chunks claimed at once and run in reverse order (as threads might finish
 * them) merge to the designs of one run: a chunk starts anywhere (the
 * combination unranked from its number) and scores never depend on the
 * bound a chunk was given. */
static void chunks_in_any_order(void **state)
{
    (void)state;
    wr_fixture *body = test_polygon_body(DODECAGON, 12);
    assert_non_null(body);
    wr_site *sites = NULL;
    int count = 0;
    wr_error error;
    assert_int_equal(wr_sites_spaced(body, &(wr_spacing){2, 2 / 2.0, 0}, &sites, &count, &error), WR_OK);
    wr_design_spec spec = {.body = body, .friction = {.given = true, .static_mu = 0.25},
                           .sites = sites, .site_count = count, .fixel_count = 3,
                           .objective = WR_OBJECTIVE_MARGIN, .top = 5, .shard_count = 1};
    wr_design_job *whole, *parts;
    run_job(&spec, &whole);
    assert_int_equal(wr_design_job_new(&spec, &parts, &error), WR_OK);
    enum { MOST = 64 };
    uint64_t first[MOST], span[MOST];
    double threshold;
    int chunks = 0;
    while (chunks < MOST && wr_design_job_claim(parts, &first[chunks], &span[chunks], &threshold))
        chunks++;
    assert_int_equal(chunks, (int)((wr_design_candidates(count, 3) + WR_DESIGN_CHUNK - 1) /
                                   WR_DESIGN_CHUNK));
    for (int i = chunks - 1; i >= 0; i--) {
        wr_design_chunk chunk;
        assert_int_equal(wr_design_chunk_run(parts, first[i], span[i], -INFINITY, NULL, NULL, &chunk,
                                             NULL),
                         WR_OK);
        wr_design_job_merge(parts, &chunk);
        wr_design_chunk_release(&chunk);
    }
    /* The figures as chunks too, the last design first. */
    assert_true(wr_design_job_searched(parts));
    int left = wr_design_job_figures_left(parts);
    assert_int_equal(left, 5);
    unsigned long units = 0;
    for (int i = left - 1; i >= 0; i--)
        assert_int_equal(wr_design_job_figure(parts, i, NULL, NULL, &units), WR_OK);
    assert_true(units > 0);
    for (int i = 0; i < left; i++)
        wr_design_job_figure_merged(parts);
    assert_int_equal(wr_design_job_figures_left(parts), 0);
    bool done = false;
    while (!done)
        assert_int_equal(wr_design_job_run(parts, 1 << 20, NULL, NULL, NULL, &done), WR_OK);
    int n, m;
    const wr_design *a = wr_design_job_designs(whole, &n), *b = wr_design_job_designs(parts, &m);
    assert_int_equal(n, m);
    assert_true(n == 5);
    for (int i = 0; i < n; i++)
        assert_memory_equal(&a[i], &b[i], sizeof a[i]);
    assert_int_equal(wr_design_job_counts(whole)->examined, wr_design_job_counts(parts)->examined);
    assert_int_equal(wr_design_job_counts(whole)->no_seating_push,
                     wr_design_job_counts(parts)->no_seating_push);
    wr_design_job_free(whole);
    wr_design_job_free(parts);
    free(sites);
    wr_fixture_free(body);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(spaced_sites_closed_form),
        cmocka_unit_test(spaced_sites_by_arc_length),
        cmocka_unit_test(placed_equals_whole),
        cmocka_unit_test(best_push_against_sampling),
        cmocka_unit_test(search_against_brute_force),
        cmocka_unit_test(chunks_in_any_order),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
