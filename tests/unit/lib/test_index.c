/* test_index.c -- the push index (lib/wr_regions.h, wr_push_index) and
 * placing pre-placed fixels (wr_fixture_place_placed): the indexed push
 * regions equal the exhaustive ones bit for bit, on a gear-like outline of
 * many segments, a bracket of lines and arcs with holes and a polygon,
 * for a point finger and a round one; both against the margin sampled
 * along every edge (a brute force); a design search with the index equals
 * one without, design by design and figure by figure. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "test_util.h"
#include "wr_internal.h"

static wr_fixture *outline_body(const wr_loop_spec *loops, size_t count)
{
    wr_fixture *body = test_outline_body(loops, count, NULL);
    assert_non_null(body);
    return body;
}

/* A gear-like outline: `teeth` faceted teeth of n / teeth segments each. */
static wr_fixture *gear_body(int n, int teeth)
{
    double (*v)[3] = calloc((size_t)n, sizeof *v);
    for (int i = 0; i < n; i++) {
        double theta = 2 * TEST_PI * i / n;
        double r = 10 + 1.2 * fmax(-1, fmin(1, 1.6 * cos(teeth * theta)));
        v[i][0] = r * cos(theta);
        v[i][1] = r * sin(theta);
    }
    wr_loop_spec loop = {(size_t)n, (const double(*)[3])v};
    wr_fixture *body = outline_body(&loop, 1);
    free(v);
    return body;
}

/* A bracket: an L of lines with a filleted inner corner and a rounded end,
 * a round hole (two half circles) and a slot; 18 segments. */
static wr_fixture *bracket_body(void)
{
    static const double outer[][3] = {{0, 0, 0},    {20, 0, 0},  {20, 4, 0},  {8, 4, -0.41421356237309503},
                                      {4, 8, 0},    {4, 20, 1},  {0, 20, 0}};
    static const double hole[][3] = {{13, 2, 1}, {15, 2, 1}};
    static const double slot[][3] = {{1.5, 12, 1}, {2.5, 12, 0}, {2.5, 16, 1}, {1.5, 16, 0}};
    wr_loop_spec loops[3] = {{7, outer}, {2, hole}, {4, slot}};
    return outline_body(loops, 3);
}

static wr_fixture *polygon_body(void)
{
    static const double v[12][2] = {{1, 0}, {11, 0}, {12, 1}, {12, 7}, {11, 8}, {7, 8},
                                    {7, 6}, {5, 6},  {5, 8},  {1, 8},  {0, 7},  {0, 1}};
    wr_fixture *body = test_polygon_body(v, 12);
    assert_non_null(body);
    return body;
}

/* k fixels at random points of the outline (any loop), friction 0.3. */
static bool random_fixture(const wr_fixture *body, test_rng *rng, int k, wr_fixture *out)
{
    wr_fixel_spec fixels[WR_MAX_FIXELS];
    memset(fixels, 0, sizeof fixels);
    int edges = wr_push_edge_count(body);
    for (int i = 0; i < k; i++) {
        int edge = (int)(test_uniform(rng) * edges);
        double normal[2];
        wr_boundary_point(body, edge, test_range(rng, 0.05, 0.95), fixels[i].at, normal);
        fixels[i].normal_given = true;
        memcpy(fixels[i].normal, normal, sizeof normal);
    }
    wr_friction_spec friction = {.given = true, .static_mu = 0.3};
    wr_error error;
    return wr_fixture_place(body, fixels, (size_t)k, &friction, out, &error) == WR_OK;
}

static void assert_same_regions(const wr_regions *a, const wr_regions *b)
{
    assert_int_equal(a->count, b->count);
    for (int i = 0; i < a->count; i++) {
        assert_int_equal(a->items[i].edge, b->items[i].edge);
        assert_memory_equal(&a->items[i].t0, &b->items[i].t0, sizeof(double));
        assert_memory_equal(&a->items[i].t1, &b->items[i].t1, sizeof(double));
    }
    assert_memory_equal(&a->resolution, &b->resolution, sizeof a->resolution);
}

/* Every set, for `trials` random fixtures of 3 and 4 fixels, both ways;
 * returns how many answers were not empty (so that the comparison is not
 * of empty answers alone). */
static int compare_on(const wr_fixture *body, double radius, int trials, uint64_t seed)
{
    wr_finger finger = {.friction = 0, .radius = radius};
    wr_push_index *index;
    assert_int_equal(wr_push_index_new(body, &finger, &index), WR_OK);
    test_rng rng = {seed};
    int nonempty = 0;
    for (int trial = 0; trial < trials; trial++) {
        wr_fixture fixture;
        if (!random_fixture(body, &rng, 3 + trial % 2, &fixture))
            continue;
        wr_analysis *analysis = test_analysis_new(&fixture);
        assert_non_null(analysis);
        for (int set = WR_SET_GOAL; set <= WR_SET_BOTH; set++) {
            wr_regions exhaustive, indexed;
            assert_int_equal(wr_push_regions_finger(analysis, set, &finger, NULL, &exhaustive),
                             WR_OK);
            assert_int_equal(wr_push_regions_indexed(analysis, set, index, NULL, &indexed), WR_OK);
            assert_same_regions(&exhaustive, &indexed);
            nonempty += exhaustive.count > 0;
            wr_regions_release(&exhaustive);
            wr_regions_release(&indexed);
        }
        wr_analysis_free(analysis);
    }
    wr_push_index_free(index);
    return nonempty;
}

static void indexed_equals_exhaustive(void **state)
{
    (void)state;
    wr_fixture *gear = gear_body(800, 12), *bracket = bracket_body(), *polygon = polygon_body();
    assert_true(compare_on(gear, 0, 60, 1) > 20);
    wr_fixture *small_gear = gear_body(120, 4);
    assert_true(compare_on(small_gear, 0.4, 8, 2) > 3);
    wr_fixture_free(small_gear);
    assert_true(compare_on(bracket, 0, 120, 3) > 40);
    assert_true(compare_on(bracket, 0.6, 60, 4) > 20);
    assert_true(compare_on(polygon, 0, 120, 5) > 40);
    assert_true(compare_on(polygon, 1.5, 60, 6) > 20);
    wr_fixture_free(gear);
    wr_fixture_free(bracket);
    wr_fixture_free(polygon);
}

/* The brute force: the margin (both sets' cones for WR_SET_BOTH, as
 * classify's) at 200 points of every edge; clearly positive is in a
 * region, clearly negative in none. */
static void indexed_against_sampling(void **state)
{
    (void)state;
    wr_fixture *bodies[2] = {gear_body(400, 8), bracket_body()};
    wr_finger point = {.radius = 0};
    test_rng rng = {7};
    int inside = 0, outside = 0;
    for (int b = 0; b < 2; b++) {
        wr_push_index *index;
        assert_int_equal(wr_push_index_new(bodies[b], &point, &index), WR_OK);
        for (int trial = 0; trial < 12; trial++) {
            wr_fixture fixture;
            if (!random_fixture(bodies[b], &rng, 3, &fixture))
                continue;
            wr_analysis *analysis = test_analysis_new(&fixture);
            wr_regions regions;
            assert_int_equal(wr_push_regions_indexed(analysis, WR_SET_BOTH, index, NULL, &regions),
                             WR_OK);
            int edges = wr_push_edge_count(&fixture);
            for (int e = 0; e < edges; e++)
                for (int i = 1; i < 200; i++) {
                    double t = i / 200.0, w[3], x[3];
                    wr_push_wrench(&fixture, e, t, w);
                    wr_fixture_unit_wrench(&fixture, w, x);
                    int blocking;
                    double margin = fmin(wr_set_margin(analysis, WR_SET_GOAL, x, &blocking),
                                         wr_set_margin(analysis, WR_SET_STRONG, x, &blocking));
                    bool in = false;
                    for (int r = 0; r < regions.count; r++)
                        in |= regions.items[r].edge == e && regions.items[r].t0 < t &&
                              t < regions.items[r].t1;
                    if (margin > 1e-6) {
                        assert_true(in);
                        inside++;
                    } else if (margin < -1e-6) {
                        assert_false(in);
                        outside++;
                    }
                }
            wr_regions_release(&regions);
            wr_analysis_free(analysis);
        }
        wr_push_index_free(index);
        wr_fixture_free(bodies[b]);
    }
    assert_true(inside > 1000);
    assert_true(outside > 1000);
}

/* A placed list from fixels placed alone is the fixture placed whole,
 * bit for bit, and refused alike (duplicates, spread). */
static void placed_alone_equals_whole(void **state)
{
    (void)state;
    wr_fixture *body = bracket_body();
    test_rng rng = {11};
    wr_friction_spec friction = {.given = true, .static_mu = 0.25};
    int refused = 0;
    for (int trial = 0; trial < 300; trial++) {
        int k = 1 + trial % 4;
        wr_fixel_spec specs[WR_MAX_FIXELS];
        wr_fixel alone[WR_MAX_FIXELS];
        memset(specs, 0, sizeof specs);
        int edges = wr_push_edge_count(body);
        for (int i = 0; i < k; i++) {
            if (i > 0 && trial % 7 == 0) {
                specs[i] = specs[i - 1]; /* a duplicate */
            } else {
                int edge = (int)(test_uniform(&rng) * edges);
                wr_boundary_point(body, edge, test_range(&rng, 0.1, 0.9), specs[i].at,
                                  specs[i].normal);
                specs[i].normal_given = true;
            }
            wr_fixture one;
            wr_error error;
            assert_int_equal(wr_fixture_place(body, &specs[i], 1, &friction, &one, &error), WR_OK);
            alone[i] = one.fixels[0];
        }
        wr_fixture whole, placed;
        wr_error e1, e2;
        wr_status s1 = wr_fixture_place(body, specs, (size_t)k, &friction, &whole, &e1);
        wr_status s2 = wr_fixture_place_placed(body, alone, (size_t)k, &placed, &e2);
        assert_int_equal(s1, s2);
        if (s1 == WR_OK)
            assert_memory_equal(&whole, &placed, sizeof whole);
        else {
            assert_string_equal(e1.field, e2.field);
            refused++;
        }
    }
    assert_true(refused > 10);
    wr_fixture_free(body);
}

/* A design search with the index and sites placed once against one
 * without: the same designs, every figure bit for bit, the same counts. */
static void design_indexed_equals_exhaustive(void **state)
{
    (void)state;
    wr_fixture *bodies[2] = {gear_body(240, 8), bracket_body()};
    for (int b = 0; b < 2; b++)
        for (int r = b == 0; r < 2; r++) { /* the gear with a round finger: minutes */
            const wr_fixture *body = bodies[b];
            int edges = wr_push_edge_count(body);
            wr_site sites[14];
            for (int i = 0; i < 14; i++) {
                double at[2], normal[2];
                wr_boundary_point(body, i * edges / 14, 0.5, at, normal);
                wr_error error;
                assert_int_equal(wr_site_new(body, at, normal, &sites[i], &error), WR_OK);
            }
            wr_design_spec spec;
            memset(&spec, 0, sizeof spec);
            spec.body = body;
            spec.friction = (wr_friction_spec){.given = true, .static_mu = 0.3};
            spec.sites = sites;
            spec.site_count = 14;
            spec.fixel_count = 3;
            spec.objective = r ? WR_OBJECTIVE_REGION : WR_OBJECTIVE_MARGIN;
            spec.top = 2;
            spec.finger.radius = r ? 0.3 : 0;
            spec.shard_count = 1;
            wr_design_job *indexed, *exhaustive;
            assert_int_equal(test_design_run(&spec, &indexed), WR_OK);
            spec.exhaustive = true;
            assert_int_equal(test_design_run(&spec, &exhaustive), WR_OK);
            int n1, n2;
            const wr_design *d1 = wr_design_job_designs(indexed, &n1);
            const wr_design *d2 = wr_design_job_designs(exhaustive, &n2);
            assert_int_equal(n1, n2);
            assert_true(n1 > 0);
            for (int i = 0; i < n1; i++)
                assert_memory_equal(&d1[i], &d2[i], sizeof d1[i]);
            const wr_design_counts *c1 = wr_design_job_counts(indexed),
                                   *c2 = wr_design_job_counts(exhaustive);
            assert_int_equal(c1->examined, c2->examined);
            assert_int_equal(c1->degenerate, c2->degenerate);
            assert_int_equal(c1->unpinned, c2->unpinned);
            assert_int_equal(c1->no_seating_push, c2->no_seating_push);
            wr_design_job_free(indexed);
            wr_design_job_free(exhaustive);
        }
    wr_fixture_free(bodies[0]);
    wr_fixture_free(bodies[1]);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(indexed_equals_exhaustive),
        cmocka_unit_test(indexed_against_sampling),
        cmocka_unit_test(placed_alone_equals_whole),
        cmocka_unit_test(design_indexed_equals_exhaustive),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
