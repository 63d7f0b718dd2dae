/* test_regions.c -- push regions, gravity arcs and disturbance margins
 * (docs/MODEL.md section 6) against closed forms and against classification. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>
#include <stdio.h>

#include "test_util.h"

#define DEG (180 / TEST_PI)

static double margin_of(const wr_analysis *a, const double w[3], wr_set set)
{
    wr_answer answer;
    assert_int_equal(wr_classify(a, w, set, WR_DEFAULT_TOLERANCE, &answer), 0);
    return answer.margin;
}

/* docs/MODEL.md section 7: the disc in a corner seats from (atan mu, 90 - atan mu), empty for
 * mu >= 1; gravity seats it from (180 + atan mu, 270 - atan mu). */
static void disc_corner_closed_forms(void **state)
{
    (void)state;
    const double mus[] = {0.1, 0.2, 0.5, 0.8, 0.95, 1.0, 1.2};
    for (size_t i = 0; i < sizeof mus / sizeof mus[0]; i++) {
        double mu = mus[i], a = atan(mu) * DEG;
        wr_fixture *f = test_disc_corner(mu);
        wr_analysis *an = test_analysis_new(f);
        for (int set = WR_SET_GOAL; set <= WR_SET_BOTH; set += 2) { /* goal and both agree here */
            wr_regions r;
            assert_int_equal(wr_push_regions(an, (wr_set)set, 0, NULL, &r), 0);
            assert_true(r.resolution == 0);
            if (mu >= 1) {
                assert_int_equal(r.count, 0);
            } else {
                assert_int_equal(r.count, 1);
                assert_true(fabs(r.items[0].t0 - a) < 1e-9 && fabs(r.items[0].t1 - (90 - a)) < 1e-9);
                assert_true(fabs(wr_region_length(f, &r.items[0]) - (90 - 2 * a) / DEG) < 1e-12);
            }
            wr_regions_release(&r);
            assert_int_equal(wr_gravity_sweep(an, (wr_set)set, &r), 0);
            if (mu >= 1) {
                assert_int_equal(r.count, 0);
            } else {
                assert_int_equal(r.count, 1);
                assert_true(fabs(r.items[0].t0 - (180 + a)) < 1e-9);
                assert_true(fabs(r.items[0].t1 - (270 - a)) < 1e-9);
            }
            wr_regions_release(&r);
        }
        /* A finger with friction mu_f widens the pushed forces by atan mu_f
         * each way: the region shrinks by that much at each end. */
        if (mu < 0.9) {
            wr_regions r;
            double mu_f = 0.05, b = atan(mu_f) * DEG;
            assert_int_equal(wr_push_regions(an, WR_SET_GOAL, mu_f, NULL, &r), 0);
            assert_true(r.resolution > 0);
            assert_int_equal(r.count, 1);
            assert_true(fabs(r.items[0].t0 - (a + b)) < 1e-9);
            assert_true(fabs(r.items[0].t1 - (90 - a - b)) < 1e-9);
            wr_regions_release(&r);
        }
        wr_analysis_free(an);
        wr_fixture_free(f);
    }
}

/* On random fixtures, for each set: every endpoint strictly inside an edge
 * has margin 0, and points inside regions classify inside, others not. */
static void regions_agree_with_classification(void **state)
{
    (void)state;
    test_rng rng = {606};
    long endpoints = 0, points = 0;
    for (int i = 0; i < 40; i++) {
        wr_fixture *f = test_random_fixture(&rng, 2 + i % 3, i % 2 == 0);
        assert_non_null(f);
        wr_analysis *a = test_analysis_new(f);
        int edges = f->shape == WR_SHAPE_CIRCLE ? 1 : (int)f->vertex_count;
        double span = f->shape == WR_SHAPE_CIRCLE ? 360 : 1;
        for (int set = WR_SET_GOAL; set <= WR_SET_BOTH; set++) {
            wr_regions r;
            assert_int_equal(wr_push_regions(a, (wr_set)set, 0, NULL, &r), 0);
            for (int k = 0; k < r.count; k++) {
                const wr_region *x = &r.items[k];
                assert_true(x->t1 > x->t0);
                double ends[2] = {x->t0, x->t1};
                for (int e = 0; e < 2; e++) {
                    if (ends[e] <= 0 || ends[e] >= span)
                        continue; /* a vertex, or the cut at 0 degrees */
                    double w[3];
                    wr_push_wrench(f, x->edge, ends[e], w);
                    double m = margin_of(a, w, (wr_set)set);
                    if (fabs(m) > 1e-9)
                        fail_msg("endpoint margin %.3g on edge %d t %.17g", m, x->edge, ends[e]);
                    endpoints++;
                }
            }
            for (int edge = 0; edge < edges; edge++)
                for (int s = 1; s < 200; s++) {
                    double t = span * s / 200;
                    bool in = false, near = false;
                    for (int k = 0; k < r.count; k++) {
                        const wr_region *x = &r.items[k];
                        if (x->edge != edge)
                            continue;
                        in |= t > x->t0 && t < x->t1;
                        near |= fabs(t - x->t0) < 1e-7 * span || fabs(t - x->t1) < 1e-7 * span;
                    }
                    if (near)
                        continue;
                    double w[3];
                    wr_push_wrench(f, edge, t, w);
                    double m = margin_of(a, w, (wr_set)set);
                    if (in != (m > 0))
                        fail_msg("set %d edge %d t %.9g: %s a region, margin %.3g", set, edge, t,
                                 in ? "in" : "outside", m);
                    points++;
                }
            wr_regions_release(&r);
        }
        wr_analysis_free(a);
        wr_fixture_free(f);
    }
    print_message("regions: %ld endpoints at margin 0, %ld points agree with classify\n",
                  endpoints, points);
    assert_true(endpoints > 100);
}

/* Gravity arcs: inside each arc the gravity wrench has a positive margin,
 * outside not. */
static void gravity_arcs_agree_with_classification(void **state)
{
    (void)state;
    test_rng rng = {707};
    for (int i = 0; i < 12; i++) {
        wr_fixture *f = test_random_fixture(&rng, 2 + i % 3, i % 2 == 1);
        wr_analysis *a = test_analysis_new(f);
        for (int set = WR_SET_GOAL; set <= WR_SET_BOTH; set++) {
            wr_regions r;
            assert_int_equal(wr_gravity_sweep(a, (wr_set)set, &r), 0);
            for (int s = 0; s < 720; s++) {
                double phi = s * 0.5 + 0.25;
                bool in = false, near = false;
                for (int k = 0; k < r.count; k++) {
                    in |= phi > r.items[k].t0 && phi < r.items[k].t1;
                    near |= fabs(phi - r.items[k].t0) < 1e-6 || fabs(phi - r.items[k].t1) < 1e-6;
                }
                if (near)
                    continue;
                double w[3] = {9.81 * f->mass * cos(phi / DEG), 9.81 * f->mass * sin(phi / DEG), 0};
                assert_int_equal(in, margin_of(a, w, (wr_set)set) > 0);
            }
            wr_regions_release(&r);
        }
        wr_analysis_free(a);
        wr_fixture_free(f);
    }
}

/* A bias held with margin M tolerates any disturbance smaller than M in the
 * scaled metric, and M along the worst direction reaches the boundary. */
static void disturbance_margin_is_the_distance(void **state)
{
    (void)state;
    test_rng rng = {808};
    int held = 0, not_held = 0;
    for (int i = 0; i < 12; i++) {
        wr_fixture *f = test_random_fixture(&rng, 2 + i % 3, i % 2 == 0);
        wr_analysis *a = test_analysis_new(f);
        for (int b = 0; b < 40; b++) {
            double bias[3];
            for (int k = 0; k < 3; k++)
                bias[k] = test_range(&rng, -2, 2);
            wr_disturbance d;
            assert_int_equal(wr_disturbance_margin(a, bias, &d), 0);
            if (!d.bounded)
                continue;
            /* margin = |scaled bias| * the strong margin of classify */
            double unit[3];
            double length = wr_fixture_unit_wrench(f, bias, unit);
            double m = margin_of(a, bias, WR_SET_STRONG);
            assert_true(fabs(d.margin - length * m) < 1e-12 * (1 + length));
            double worst[3];
            assert_true(fabs(wr_fixture_scale_wrench(f, d.worst_direction, worst) - 1) < 1e-12);
            if (d.margin <= 1e-6)
                continue;
            double g[3];
            for (int k = 0; k < 3; k++)
                g[k] = bias[k] + 0.999 * d.margin * d.worst_direction[k];
            assert_true(margin_of(a, g, WR_SET_STRONG) > 0);
            for (int k = 0; k < 3; k++)
                g[k] = bias[k] + 1.001 * d.margin * d.worst_direction[k];
            assert_true(margin_of(a, g, WR_SET_STRONG) < 1e-9);
            /* Random disturbances a little smaller than the margin are held. */
            for (int s = 0; s < 50; s++) {
                double x[3], h[3];
                test_sphere(&rng, x);
                wr_fixture_unscale_wrench(f, x, h);
                for (int k = 0; k < 3; k++)
                    g[k] = bias[k] + 0.99 * d.margin * h[k];
                assert_true(margin_of(a, g, WR_SET_STRONG) > 0);
            }
            held++;
        }
        for (int b = 0; b < 5; b++) {
            /* A bias in an excluded cone: a negative margin, and leaving
             * through the worst direction by more than |margin| exits that
             * cone. */
            int modes = wr_analysis_cone_count(a, WR_SET_STRONG);
            const wr_cone *cone = wr_analysis_cone(a, WR_SET_STRONG, b % (modes ? modes : 1));
            if (modes == 0 || cone->dimension < 3 || cone->ray_count == 0)
                continue;
            double inside[3] = {0, 0, 0}, bias[3];
            for (int r = 0; r < cone->ray_count; r++)
                for (int k = 0; k < 3; k++)
                    inside[k] += cone->rays[r][k];
            wr_fixture_unscale_wrench(f, inside, bias);
            wr_disturbance d;
            wr_disturbance_margin(a, bias, &d);
            if (d.margin < -1e-6)
                not_held++;
        }
        wr_analysis_free(a);
        wr_fixture_free(f);
    }
    print_message("regions: %d biases held exactly up to their margin, %d not held\n", held,
                  not_held);
    assert_true(held > 20);
}

static void no_shape_and_bad_friction_are_refused(void **state)
{
    (void)state;
    wr_fixel_spec fixels[1] = {{{1, 0}, true, {-1, 0}, {.given = true, .static_mu = 0.3}}};
    wr_fixture_spec spec;
    memset(&spec, 0, sizeof spec);
    spec.mass = 1;
    spec.inertia_given = spec.com_given = true;
    spec.inertia = 1;
    spec.fixel_count = 1;
    spec.fixels = fixels;
    wr_fixture *f = test_fixture_new(&spec, NULL);
    wr_analysis *a = test_analysis_new(f);
    wr_regions r;
    assert_int_equal(wr_push_regions(a, WR_SET_GOAL, 0, NULL, &r), WR_NO_SHAPE);
    wr_analysis_free(a);
    wr_fixture_free(f);
    f = test_disc_corner(0.5);
    a = test_analysis_new(f);
    assert_int_equal(wr_push_regions(a, WR_SET_GOAL, -0.1, NULL, &r), WR_INVALID);
    assert_int_equal(wr_push_regions(a, WR_SET_GOAL, NAN, NULL, &r), WR_INVALID);
    wr_analysis_free(a);
    wr_fixture_free(f);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(disc_corner_closed_forms),
        cmocka_unit_test(regions_agree_with_classification),
        cmocka_unit_test(gravity_arcs_agree_with_classification),
        cmocka_unit_test(disturbance_margin_is_the_distance),
        cmocka_unit_test(no_shape_and_bad_friction_are_refused),
    };
    return cmocka_run_group_tests_name("regions", tests, NULL, NULL);
}
