/* test_verdict.c -- the verdict alone (wr_classify_verdict) and the verdict
 * map (wr_verdict_map_classify) against the full classification
 * (wr_classify), and the margin without the witness (wr_classify_margin) against
 * the margin with it: on random fixtures (discs and polygons, 1 to 5 fixels),
 * random wrenches, wrenches put near the excluded cones' boundaries on
 * purpose (a cone's nearest point of a random direction, moved by a
 * fraction of the tolerance band either way), wrenches on the map's cell
 * edges and of extreme sizes, every set and several tolerances, the
 * verdicts must be the same, wrench by wrench. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>
#include <stdio.h>

#include "test_util.h"

static void agree(const wr_analysis *a, const wr_verdict_map *map, const double w[3],
                  double tolerance, long *count)
{
    for (int set = 0; set < 3; set++) {
        wr_answer full;
        wr_verdict lean, mapped;
        assert_int_equal(wr_classify(a, w, (wr_set)set, tolerance, &full), WR_OK);
        assert_int_equal(wr_classify_verdict(a, w, (wr_set)set, tolerance, &lean), WR_OK);
        assert_int_equal(wr_verdict_map_classify(map, w, (wr_set)set, &mapped), WR_OK);
        if (lean != full.verdict || mapped != full.verdict)
            print_message("set %d tolerance %g wrench (%.17g, %.17g, %.17g): full %d (margin "
                          "%.3g), verdict alone %d, map %d\n",
                          set, tolerance, w[0], w[1], w[2], full.verdict, full.margin, lean,
                          mapped);
        assert_int_equal(lean, full.verdict);
        assert_int_equal(mapped, full.verdict);
        /* The margin without the witness: the same numbers, bit for bit. */
        wr_answer margin;
        assert_int_equal(wr_classify_margin(a, w, (wr_set)set, tolerance, &margin), WR_OK);
        assert_int_equal(margin.verdict, full.verdict);
        assert_memory_equal(&margin.margin, &full.margin, sizeof margin.margin);
        assert_int_equal(margin.blocking, full.blocking);
        assert_int_equal(margin.blocking_set, full.blocking_set);
        (*count)++;
    }
}

/* A wrench whose scaled direction is on an edge or corner of the map's
 * cells (128 to a cube face's side, tests the rounding of finding one),
 * or near one. */
static void cell_edge_wrench(test_rng *rng, const wr_fixture *f, double w[3])
{
    double h[3];
    int axis = (int)test_range(rng, 0, 2.999);
    h[axis] = test_range(rng, 0, 1) < 0.5 ? -1 : 1;
    for (int k = 1; k < 3; k++) {
        double u = -1 + 2.0 * (int)test_range(rng, 0, 128.999) / 128;
        if (test_range(rng, 0, 1) < 0.3)
            u = nextafter(u, test_range(rng, 0, 1) < 0.5 ? -2 : 2);
        h[(axis + k) % 3] = u;
    }
    double size = pow(10, test_range(rng, -3, 3));
    for (int k = 0; k < 3; k++)
        h[k] *= size;
    wr_fixture_unscale_wrench(f, h, w);
}

static void verdict_alone_agrees(void **state)
{
    (void)state;
    static const double tolerances[] = {1e-9, 0, 1e-4, 0.05, 0.5};
    long compared = 0, near = 0, maps = 0;
    double decided = 0;
    for (int seed = 0; seed < 60; seed++) {
        test_rng rng = {(uint64_t)seed * 7919 + 11};
        int k = 1 + seed % 5;
        wr_fixture *f = test_random_fixture(&rng, k, seed % 2 == 0);
        if (!f)
            continue;
        wr_analysis *a = test_analysis_new(f);
        for (int t = 0; t < 5; t++) {
            double tolerance = tolerances[t];
            wr_verdict_map *map;
            assert_int_equal(wr_verdict_map_new(a, tolerance, &map), WR_OK);
            decided += wr_verdict_map_decided(map);
            maps++;
            for (int i = 0; i < 300; i++) {
                double w[3];
                test_sphere(&rng, w);
                for (int c = 0; c < 3; c++)
                    w[c] *= test_range(&rng, 0.01, 100);
                agree(a, map, w, tolerance, &compared);
            }
            for (int i = 0; i < 100; i++) {
                double w[3];
                cell_edge_wrench(&rng, f, w);
                agree(a, map, w, tolerance, &compared);
            }
            /* Sizes at the ends of the doubles: the map's general path. */
            static const double sizes[] = {1e-300, 4.9e-324, 1e300, 1.7e308};
            for (int i = 0; i < 4; i++) {
                double w[3];
                test_sphere(&rng, w);
                for (int c = 0; c < 3; c++)
                    w[c] *= sizes[i];
                agree(a, map, w, tolerance, &compared);
            }
            /* Near the boundary: a cone's nearest point to a random unit
             * direction, moved along the direction by a little. */
            for (int set = 0; set < 2; set++) {
                int cones = wr_analysis_cone_count(a, (wr_set)set);
                for (int c = 0; c < cones && c < 40; c++) {
                    const wr_cone *cone = wr_analysis_cone(a, (wr_set)set, c);
                    if (cone->empty)
                        continue;
                    for (int j = 0; j < 4; j++) {
                        double x[3], p[3];
                        test_sphere(&rng, x);
                        wr_cone_signed_distance(cone, x, p);
                        double shift = test_range(&rng, -2, 2) * (tolerance > 0 ? tolerance : 1e-12);
                        double h[3];
                        for (int m = 0; m < 3; m++)
                            h[m] = p[m] + shift * x[m];
                        double w[3];
                        wr_fixture_unscale_wrench(f, h, w);
                        agree(a, map, w, tolerance, &compared);
                        near++;
                    }
                }
            }
            double zero[3] = {0, 0, 0};
            agree(a, map, zero, tolerance, &compared);
            wr_verdict_map_free(map);
        }
        wr_analysis_free(a);
        wr_fixture_free(f);
    }
    print_message("verdict alone and map: %ld verdicts compared with the full classification, "
                  "%ld near a cone's boundary; the maps decide %.1f%% of their cells\n",
                  compared, 3 * near, 100 * decided / maps);
    assert_true(compared > 200000);
    /* A map that decided nothing would agree too, by measuring everything. */
    assert_true(decided / maps > 0.8);
}

static void refusals(void **state)
{
    (void)state;
    wr_fixture *f = test_disc_corner(0.5);
    wr_analysis *a = test_analysis_new(f);
    wr_verdict v;
    double bad[3] = {NAN, 0, 0}, ok[3] = {-1, -1, 0};
    assert_int_equal(wr_classify_verdict(a, bad, WR_SET_GOAL, 1e-9, &v), WR_INVALID);
    assert_int_equal(wr_classify_verdict(a, ok, WR_SET_GOAL, -1, &v), WR_INVALID);
    /* The disc in a corner, docs/MODEL.md section 7.1: (-1, -1, 0) seats it. */
    assert_int_equal(wr_classify_verdict(a, ok, WR_SET_GOAL, 1e-9, &v), WR_OK);
    assert_int_equal(v, WR_VERDICT_INSIDE);
    wr_verdict_map *map;
    assert_int_equal(wr_verdict_map_new(a, 1, &map), WR_INVALID);
    assert_null(map);
    assert_int_equal(wr_verdict_map_new(a, -1e-9, &map), WR_INVALID);
    assert_int_equal(wr_verdict_map_new(a, 1e-9, &map), WR_OK);
    assert_int_equal(wr_verdict_map_classify(map, bad, WR_SET_GOAL, &v), WR_INVALID);
    assert_int_equal(wr_verdict_map_classify(map, ok, WR_SET_GOAL, &v), WR_OK);
    assert_int_equal(v, WR_VERDICT_INSIDE);
    wr_verdict_map_free(map);
    /* G_goal alone: no map of G_strong to make. */
    wr_analysis *goal_only;
    assert_int_equal(wr_analysis_goal_new(f, NULL, &goal_only), WR_OK);
    assert_int_equal(wr_verdict_map_new(goal_only, 1e-9, &map), WR_INVALID);
    wr_analysis_free(goal_only);
    wr_analysis_free(a);
    wr_fixture_free(f);
}

/* A NaN among finite components: fmax drops a NaN, so the map's size check
 * must not be the only guard; wr_classify_verdict refuses every such
 * wrench, and so must the map (its answers are wr_classify_verdict's). */
static void map_refuses_partial_nan(void **state)
{
    (void)state;
    wr_fixture *f = test_disc_corner(0.5);
    wr_analysis *a = test_analysis_new(f);
    wr_verdict_map *map;
    assert_int_equal(wr_verdict_map_new(a, 1e-9, &map), WR_OK);
    const double wrenches[][3] = {{NAN, -1, 0}, {-1, NAN, 0}, {-1, -1, NAN},
                                  {NAN, NAN, 1}, {1, NAN, NAN}, {-NAN, 1e-3, 0}};
    for (size_t i = 0; i < sizeof wrenches / sizeof wrenches[0]; i++)
        for (int set = 0; set < 3; set++) {
            wr_verdict v = WR_VERDICT_INSIDE, mapped = WR_VERDICT_INSIDE;
            wr_status lean = wr_classify_verdict(a, wrenches[i], (wr_set)set, 1e-9, &v);
            wr_status by_map = wr_verdict_map_classify(map, wrenches[i], (wr_set)set, &mapped);
            if (by_map != lean)
                print_message("wrench %zu (%g, %g, %g), set %d: wr_classify_verdict %d, map %d\n",
                              i, wrenches[i][0], wrenches[i][1], wrenches[i][2], set, lean,
                              by_map);
            assert_int_equal(lean, WR_INVALID);
            assert_int_equal(by_map, WR_INVALID);
        }
    wr_verdict_map_free(map);
    wr_analysis_free(a);
    wr_fixture_free(f);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(verdict_alone_agrees),
        cmocka_unit_test(refusals),
        cmocka_unit_test(map_refuses_partial_nan),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
