/* test_sweep.c -- sweeps over a common friction coefficient (lib/wr_sweep.h):
 * the disc's closed forms (docs/MODEL.md section 7.1: the goal arc is
 * (atan mu, 90 deg - atan mu)), and on random fixtures every wrench's
 * intervals against classification at sampled mu and against bisection of
 * the margin's sign at each end; the analyses a sweep makes from its frame
 * against the analyses made from scratch. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>
#include <stdio.h>
#include <string.h>

#include "test_util.h"
#include "wr_internal.h"

static const wr_sweep_range RANGE = {0, 1.5, 1};

/* The fixture at mu built from scratch, to check wr_fixture_at_friction. */
static void at_friction_is_a_fixture_at_that_friction(void **state)
{
    (void)state;
    wr_fixture *base = test_disc_corner(0.5);
    for (double mu = 0; mu <= 1.5; mu += 0.125) {
        wr_fixture copy, *fresh = test_disc_corner(mu);
        wr_fixture_at_friction(base, mu, 1, &copy);
        for (int i = 0; i < base->fixel_count; i++) {
            assert_true(copy.fixels[i].mu_static == fresh->fixels[i].mu_static);
            assert_true(copy.fixels[i].mu_kinetic == fresh->fixels[i].mu_kinetic);
            assert_true(copy.fixels[i].mu_static_min == fresh->fixels[i].mu_static_min);
            assert_true(copy.fixels[i].mu_kinetic_min == fresh->fixels[i].mu_kinetic_min);
        }
        wr_fixture_free(fresh);
    }
    wr_fixture_free(base);
}

/* Two cones the same, bit for bit (the arrays each holds included). */
static void assert_same_cone(const wr_cone *a, const wr_cone *b)
{
    assert_true(a->empty == b->empty && a->dimension == b->dimension &&
                a->zero_admitted == b->zero_admitted && a->equality_count == b->equality_count &&
                a->facet_count == b->facet_count && a->ray_count == b->ray_count &&
                a->generator_count == b->generator_count);
    assert_memory_equal(&a->constraint, &b->constraint, sizeof a->constraint);
    assert_memory_equal(a->equalities, b->equalities, sizeof a->equalities);
    if (a->facet_count > 0) {
        assert_memory_equal(a->facets, b->facets, (size_t)a->facet_count * sizeof a->facets[0]);
        assert_memory_equal(a->facet_open, b->facet_open, (size_t)a->facet_count);
    }
    if (a->ray_count > 0)
        assert_memory_equal(a->rays, b->rays, (size_t)a->ray_count * sizeof a->rays[0]);
    if (a->generator_count > 0) {
        assert_memory_equal(a->generators, b->generators,
                            (size_t)a->generator_count * sizeof a->generators[0]);
        for (int i = 0; i < a->generator_count; i++) /* field by field: padding */
            assert_true(a->origins[i].fixel == b->origins[i].fixel &&
                        !memcmp(&a->origins[i].normal_force, &b->origins[i].normal_force,
                                sizeof(double)) &&
                        !memcmp(&a->origins[i].tangent_force, &b->origins[i].tangent_force,
                                sizeof(double)));
    }
}

/* The analysis a frame makes at mu (built once, from the fixture at its own
 * friction) against wr_analysis_new of the fixture placed at mu: the same
 * plan, modes, pinned and cones, bit for bit; without `strong` G_strong's
 * cones are left out. */
static void frame_analyses_are_the_analyses_at_each_mu(void **state)
{
    (void)state;
    test_rng rng = {0xf7a3e1ULL};
    int cones = 0;
    for (int trial = 0; trial < 12; trial++) {
        int k = 2 + trial % 4;
        wr_fixture *f = test_random_fixture(&rng, k, trial % 3 == 0);
        assert_non_null(f);
        for (int strong = 0; strong < 2; strong++) {
            wr_analysis_frame *frame;
            assert_int_equal(wr_analysis_frame_new(f, strong, &frame), WR_OK);
            for (int step = 0; step < 5; step++) {
                double mu = step == 0 ? 0 : test_range(&rng, 0, 2);
                double ratio = step % 2 ? 1 : test_range(&rng, 0.2, 1);
                wr_fixture at;
                wr_fixture_at_friction(f, mu, ratio, &at);
                wr_analysis *fresh, *framed;
                assert_int_equal(wr_analysis_new(&at, &fresh), WR_OK);
                assert_int_equal(wr_analysis_frame_at(frame, &at, strong, &framed), WR_OK);
                int goal = wr_analysis_cone_count(fresh, WR_SET_GOAL);
                assert_int_equal(wr_analysis_cone_count(framed, WR_SET_GOAL), goal);
                for (int i = 0; i < goal; i++)
                    assert_same_cone(wr_analysis_cone(fresh, WR_SET_GOAL, i),
                                     wr_analysis_cone(framed, WR_SET_GOAL, i));
                int modes = wr_analysis_cone_count(fresh, WR_SET_STRONG);
                assert_int_equal(wr_analysis_cone_count(framed, WR_SET_STRONG),
                                 strong ? modes : 0);
                if (strong) {
                    assert_true(wr_analysis_pinned(framed) == wr_analysis_pinned(fresh));
                    for (int i = 0; i < modes; i++)
                        assert_same_cone(wr_analysis_cone(fresh, WR_SET_STRONG, i),
                                         wr_analysis_cone(framed, WR_SET_STRONG, i));
                }
                cones += goal + (strong ? modes : 0);
                wr_analysis_free(framed);
                wr_analysis_free(fresh);
            }
            wr_analysis_frame_free(frame);
        }
        wr_fixture_free(f);
    }
    assert_true(cones > 1000);
}

static void disc_closed_forms(void **state)
{
    (void)state;
    wr_fixture *disc = test_disc_corner(0.5);
    wr_sweep_range range = {0, 3, 1};
    wr_sweeper *goal;
    assert_int_equal(wr_sweeper_new(disc, WR_SET_GOAL, &range, &goal), WR_OK);

    /* Push: length pi/2 - 2 atan mu on the unit circle, empty from mu = 1. */
    wr_sweep_curve curve;
    wr_finger point = {.friction = 0};
    assert_int_equal(wr_sweep_push(goal, &point, NULL, &curve), WR_OK);
    assert_true(curve.exact);
    assert_int_equal(curve.intervals.count, 1);
    assert_true(curve.intervals.items[0][0] == 0);
    assert_true(fabs(curve.intervals.items[0][1] - 1) <= 1e-12);
    assert_true(curve.has_critical && fabs(curve.critical - 1) <= 1e-12);
    assert_true(curve.point_count >= 64);
    for (int i = 0; i < curve.point_count; i++) {
        double mu = curve.points[i][0];
        double expected = fmax(0, TEST_PI / 2 - 2 * atan(mu));
        assert_true(fabs(curve.points[i][1] - expected) <= 1e-12);
        assert_true(i == 0 || curve.points[i][0] > curve.points[i - 1][0]);
        assert_true(i > 0 || mu == 0);
        assert_true(i < curve.point_count - 1 || mu == 3);
        assert_true(i == 0 || curve.points[i][0] - curve.points[i - 1][0] <= 3.0 / 64 + 1e-12);
    }
    wr_sweep_curve_release(&curve);

    /* Gravity: the arc (180 + atan mu, 270 - atan mu), in degrees. */
    assert_int_equal(wr_sweep_gravity(goal, NULL, &curve), WR_OK);
    assert_true(curve.has_critical && fabs(curve.critical - 1) <= 1e-12);
    for (int i = 0; i < curve.point_count; i++) {
        double mu = curve.points[i][0];
        double expected = fmax(0, 90 - 360 / TEST_PI * atan(mu));
        assert_true(fabs(curve.points[i][1] - expected) <= 1e-9);
    }
    wr_sweep_curve_release(&curve);

    /* A wrench (-a, -b, 0) seats the disc while mu < min(a/b, b/a). */
    const double pushes[3][3] = {{-1, -0.5, 0}, {-0.25, -1, 0.3}, {-1, -1, 0}};
    const double ends[3] = {0.5, 0.25, 1};
    for (int i = 0; i < 3; i++) {
        wr_intervals list;
        assert_int_equal(wr_sweep_wrench(goal, pushes[i], NULL, &list), WR_OK);
        assert_int_equal(list.count, 1);
        assert_true(list.items[0][0] == 0);
        assert_true(fabs(list.items[0][1] - ends[i]) <= 1e-12);
        wr_intervals_release(&list);
    }
    const double away[3] = {1, 0, 0};
    wr_intervals list;
    assert_int_equal(wr_sweep_wrench(goal, away, NULL, &list), WR_OK);
    assert_int_equal(list.count, 0);
    wr_sweeper_free(goal);
    wr_fixture_free(disc);
}

/* The margin of `wrench` for `set` at mu (tolerance 0). */
static double margin_at(const wr_fixture *f, double mu, double ratio, wr_set set,
                        const double wrench[3])
{
    wr_fixture at;
    wr_fixture_at_friction(f, mu, ratio, &at);
    wr_analysis *a = test_analysis_new(&at);
    wr_answer answer;
    assert_int_equal(wr_classify(a, wrench, set, 0, &answer), WR_OK);
    wr_analysis_free(a);
    return answer.margin;
}

static bool in_list(const wr_intervals *list, double mu, double away, bool *near)
{
    *near = false;
    for (int i = 0; i < list->count; i++) {
        if (fabs(mu - list->items[i][0]) <= away || fabs(mu - list->items[i][1]) <= away)
            *near = true;
        if (mu > list->items[i][0] && mu < list->items[i][1])
            return true;
    }
    return false;
}

static void random_wrench_intervals(void **state)
{
    (void)state;
    test_rng rng = {0x5eed5eedULL};
    int samples = 0, ends = 0, interior = 0;
    for (int trial = 0; trial < 24; trial++) {
        int k = 2 + trial % 3;
        wr_fixture *f = test_random_fixture(&rng, k, trial % 2 == 0);
        assert_non_null(f);
        wr_sweep_range range = RANGE;
        range.kinetic_ratio = trial % 4 < 2 ? 1 : test_range(&rng, 0.3, 1);
        for (int set = 0; set < 3; set++) {
            wr_sweeper *s;
            assert_int_equal(wr_sweeper_new(f, (wr_set)set, &range, &s), WR_OK);
            for (int w = 0; w < 3; w++) {
                double wrench[3];
                test_sphere(&rng, wrench);
                wr_intervals list;
                assert_int_equal(wr_sweep_wrench(s, wrench, NULL, &list), WR_OK);
                for (int i = 0; i < list.count; i++) {
                    assert_true(list.items[i][0] < list.items[i][1]);
                    assert_true(i == 0 || list.items[i][0] > list.items[i - 1][1]);
                }
                /* Sampled: inside exactly inside the intervals. */
                for (int j = 0; j < 60; j++) {
                    double mu = range.low + (range.high - range.low) * (j + 0.41) / 60;
                    bool near;
                    bool inside = in_list(&list, mu, 1e-7, &near);
                    if (near)
                        continue;
                    double m = margin_at(f, mu, range.kinetic_ratio, (wr_set)set, wrench);
                    if (fabs(m) <= 1e-9)
                        continue; /* the tolerance band of the verdict */
                    if (inside != (m > 0))
                        fail_msg("trial %d set %d mu %.17g margin %g inside %d", trial, set, mu,
                                 m, inside);
                    samples++;
                }
                /* Each end inside the range: the margin changes sign there. */
                for (int i = 0; i < list.count; i++)
                    for (int e = 0; e < 2; e++) {
                        double end = list.items[i][e];
                        if (end <= range.low || end >= range.high)
                            continue;
                        interior++;
                        double a = end - 1e-4, b = end + 1e-4;
                        double ma = margin_at(f, a, range.kinetic_ratio, (wr_set)set, wrench);
                        double mb = margin_at(f, b, range.kinetic_ratio, (wr_set)set, wrench);
                        if ((ma > 0) == (mb > 0))
                            continue; /* a touching end: inside on neither side */
                        for (int n = 0; n < 44; n++) {
                            double mid = (a + b) / 2;
                            double mm = margin_at(f, mid, range.kinetic_ratio, (wr_set)set,
                                                  wrench);
                            if ((mm > 0) == (ma > 0))
                                a = mid;
                            else
                                b = mid;
                        }
                        /* The verdict's band of 1e-9 in margin moves the
                         * end by about 1e-9 over the margin's slope. */
                        if (fabs((a + b) / 2 - end) > 1e-8)
                            fail_msg("trial %d set %d end %.17g bisected %.17g", trial, set,
                                     end, (a + b) / 2);
                        ends++;
                    }
                wr_intervals_release(&list);
            }
            wr_sweeper_free(s);
        }
        wr_fixture_free(f);
    }
    print_message("sweep: %d samples, %d interior ends, %d bisected\n", samples, interior, ends);
    assert_true(samples > 5000);
    assert_true(ends >= 10);
}

static bool always(void *context)
{
    (void)context;
    return true;
}

static void refusals_and_stops(void **state)
{
    (void)state;
    wr_fixture *disc = test_disc_corner(0.5);
    wr_sweeper *s = NULL;
    const wr_sweep_range bad[] = {{-0.1, 1, 1}, {1, 1, 1}, {0, 2000, 1}, {0, 1, 0}, {0, 1, 1.5},
                                  {0, NAN, 1}};
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        assert_int_equal(wr_sweeper_new(disc, WR_SET_GOAL, &bad[i], &s), WR_INVALID);
        assert_null(s);
    }
    assert_int_equal(wr_sweeper_new(disc, WR_SET_BOTH, &RANGE, &s), WR_OK);
    wr_stop stop = {always, NULL};
    wr_sweep_curve curve;
    wr_finger point = {.friction = 0}, negative = {.friction = -1};
    assert_int_equal(wr_sweep_push(s, &point, &stop, &curve), WR_STOPPED);
    assert_int_equal(curve.point_count, 0);
    assert_int_equal(wr_sweep_push(s, &negative, NULL, &curve), WR_INVALID);
    wr_intervals list;
    const double w[3] = {-1, -1, 0}, nan_wrench[3] = {NAN, 0, 0};
    assert_int_equal(wr_sweep_wrench(s, w, &stop, &list), WR_STOPPED);
    assert_int_equal(list.count, 0);
    assert_int_equal(wr_sweep_wrench(s, nan_wrench, NULL, &list), WR_INVALID);
    wr_sweeper_free(s);

    /* No shape: no push sweep, but gravity is fine. */
    wr_fixel_spec fixels[2];
    memset(fixels, 0, sizeof fixels);
    fixels[0].at[0] = -1;
    fixels[0].normal_given = true;
    fixels[0].normal[0] = 1;
    fixels[1].at[1] = -1;
    fixels[1].normal_given = true;
    fixels[1].normal[1] = 1;
    wr_fixture_spec spec;
    memset(&spec, 0, sizeof spec);
    spec.mass = 1;
    spec.inertia_given = true;
    spec.inertia = 0.5;
    spec.com_given = true;
    spec.friction.given = true;
    spec.friction.static_mu = 0.3; /* ignored by the sweep */
    spec.fixel_count = 2;
    spec.fixels = fixels;
    wr_error error;
    wr_fixture *bare = test_fixture_new(&spec, &error);
    if (!bare)
        fail_msg("the shapeless disc: %s: %s", error.field, error.reason);
    assert_int_equal(wr_sweeper_new(bare, WR_SET_GOAL, &RANGE, &s), WR_OK);
    assert_int_equal(wr_sweep_push(s, &point, NULL, &curve), WR_NO_SHAPE);
    assert_int_equal(wr_sweep_gravity(s, NULL, &curve), WR_OK);
    assert_true(curve.has_critical && fabs(curve.critical - 1) <= 1e-12);
    wr_sweep_curve_release(&curve);
    wr_sweeper_free(s);
    wr_fixture_free(bare);
    wr_fixture_free(disc);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(at_friction_is_a_fixture_at_that_friction),
        cmocka_unit_test(frame_analyses_are_the_analyses_at_each_mu),
        cmocka_unit_test(disc_closed_forms),
        cmocka_unit_test(random_wrench_intervals),
        cmocka_unit_test(refusals_and_stops),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
