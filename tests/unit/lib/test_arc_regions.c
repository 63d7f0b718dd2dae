/* test_arc_regions.c -- push regions on arcs by the fast path (one atan2
 * per facet, no allocation) against the reference (every root of every
 * row sorted, every piece tested), wr_arc_regions both ways: on random
 * outlines of arcs (rounded polygons, bulges of either sign, small and
 * large, holes) with random frictional fixels, every arc against the goal
 * and strong cones, the regions must be the same: as many, each end within
 * 1e-12 (and in practice bit for bit; the count of those that differ is
 * printed).  The fast path must take most cones, so that it is what is
 * tested. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>
#include <stdio.h>

#include "test_util.h"
#include "wr_internal.h"
#include "wr_outline.h"
#include "wr_plan.h"
#include "wr_regions.h"

/* A random rounded polygon: n vertices at sorted angles, radius in
 * [0.6, 1] about the origin, each segment's bulge random (a tenth of them
 * straight), and a round hole of two arcs in half the trials. */
static wr_fixture *random_body(test_rng *rng, int trial, double (*outer)[3], double (*hole)[3])
{
    int n = 3 + (int)(test_uniform(rng) * 6);
    for (int k = 0; k < n; k++) {
        double angle = 2 * TEST_PI * (k + 0.6 * test_uniform(rng)) / n;
        double r = test_range(rng, 0.6, 1);
        outer[k][0] = 3 * r * cos(angle);
        outer[k][1] = 3 * r * sin(angle);
        double u = test_uniform(rng);
        /* Beyond a bulge of 1 an arc is more than a half circle. */
        outer[k][2] = u < 0.1    ? 0
                      : u < 0.45 ? test_range(rng, 0.05, 0.6)
                      : u < 0.55 ? 1
                      : u < 0.7  ? test_range(rng, 1, 2.5)
                                : test_range(rng, -0.3, 0);
    }
    wr_loop_spec loops[2] = {{(size_t)n, (const double (*)[3])outer}, {2, (const double (*)[3])hole}};
    hole[0][0] = 0.3;
    hole[0][1] = 0.1;
    hole[0][2] = 1;
    hole[1][0] = -0.2;
    hole[1][1] = 0.1;
    hole[1][2] = 1;
    return test_outline_body(loops, trial % 2 ? 2 : 1, NULL);
}

static void fast_matches_reference(void **state)
{
    (void)state;
    test_rng rng = {0x1234567887654321ULL};
    int fixtures = 0, arcs_compared = 0, cones_total = 0, referred = 0, differ_bits = 0;
    int regions = 0, ends = 0;
    int beyond_half = 0;
    for (int trial = 0; fixtures < 150 && trial < 6000; trial++) {
        double outer[16][3], hole[2][3];
        wr_fixture *body = random_body(&rng, trial, outer, hole);
        if (!body)
            continue;
        /* 3 or 4 fixels at random points of random segments. */
        int k = 3 + trial % 2;
        wr_fixel_spec fixels[4];
        memset(fixels, 0, sizeof fixels);
        const wr_outline *o = body->outline;
        for (int i = 0; i < k; i++) {
            size_t loop = (o->loop_count > 1 && test_uniform(&rng) < 0.2) ? 1 : 0;
            size_t seg = (size_t)(test_uniform(&rng) * o->loops[loop].segment_count);
            double normal[2];
            wr_outline_boundary(o, loop, seg, test_range(&rng, 0.1, 0.9), fixels[i].at, normal);
        }
        wr_friction_spec friction = {.given = true, .static_mu = test_range(&rng, 0, 0.6)};
        wr_fixture placed;
        wr_error error;
        if (wr_fixture_place(body, fixels, (size_t)k, &friction, &placed, &error) != WR_OK) {
            wr_fixture_free(body);
            continue;
        }
        wr_analysis *an = test_analysis_new(&placed);
        assert_non_null(an);
        fixtures++;
        for (int set = 0; set < 2; set++) {
            int goal = set == 0 ? an->plan->kept_count : 0, strong = set == 1 ? an->mode_count : 0;
            const wr_cone *cones[512];
            int count = 0;
            for (int i = 0; i < goal && count < 512; i++)
                cones[count++] = &an->goal_cones[i];
            for (int i = 0; i < strong && count < 512; i++)
                cones[count++] = &an->mode_cones[i];
            for (int edge = 0; edge < wr_push_edge_count(&placed); edge++) {
                wr_edge_frame frame;
                wr_edge_frame_of(&placed, edge, &frame);
                if (frame.kind != WR_EDGE_ARC)
                    continue;
                beyond_half += frame.half_angle > TEST_PI / 2;
                wr_regions fast = {0}, reference = {0};
                bool half = frame.half_angle <= TEST_PI / 2;
                assert_int_equal(wr_arc_regions(&frame, cones, count, false,
                                                half ? &referred : NULL, &fast),
                                 WR_OK);
                assert_int_equal(wr_arc_regions(&frame, cones, count, true, NULL, &reference),
                                 WR_OK);
                arcs_compared++;
                cones_total += half ? count : 0;
                regions += reference.count;
                for (int i = 0; i < reference.count; i++)
                    ends += (reference.items[i].t0 > 0) + (reference.items[i].t1 < 1);
                if (fast.count != reference.count)
                    fail_msg("fixture %d, edge %d, set %d: %d regions, the reference %d",
                             fixtures, edge, set, fast.count, reference.count);
                for (int i = 0; i < fast.count; i++) {
                    double d0 = fabs(fast.items[i].t0 - reference.items[i].t0);
                    double d1 = fabs(fast.items[i].t1 - reference.items[i].t1);
                    if (d0 > 1e-12 || d1 > 1e-12)
                        fail_msg("fixture %d, edge %d, set %d, region %d: (%.17g, %.17g), the "
                                 "reference (%.17g, %.17g)",
                                 fixtures, edge, set, i, fast.items[i].t0, fast.items[i].t1,
                                 reference.items[i].t0, reference.items[i].t1);
                    differ_bits += d0 != 0 || d1 != 0;
                }
                wr_regions_release(&fast);
                wr_regions_release(&reference);
            }
        }
        wr_analysis_free(an);
        wr_fixture_free(body);
    }
    print_message("    %d fixtures, %d arcs (%d beyond a half circle): %d regions, %d of their "
                  "ends inside an arc, %d not bit for bit; up to a half circle, %d of %d cones "
                  "to the reference\n",
                  fixtures, arcs_compared, beyond_half, regions, ends, differ_bits, referred,
                  cones_total);
    assert_true(ends >= 300); /* ends a cone puts inside an arc: what is compared */
    assert_true(beyond_half >= 100);
    assert_true(fixtures >= 100);
    /* Up to a half circle, the fast path decides nine cones in ten at least
     * (beyond it, the reference takes them all). */
    assert_true(referred * 10 < cones_total);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(fast_matches_reference),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
