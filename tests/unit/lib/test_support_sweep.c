/* test_support_sweep.c -- a wrench on a base plate against the fixels'
 * common mu, and against the buttons' mu_B (lib/wr_support_sweep.h):
 * seating's end against a closed form
 * on the disc in the corner, holding's against the 3-2-1 plate's sliding
 * translation, every answer against the point answers at many mu in and
 * around its intervals, and a job stopped part way. */
#include "test_util.h"

#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>

#include <cmocka.h>

#define G 9.81

/* `f` on three buttons with mu_B (gravity G, no clamp). */
static void rest_on(wr_fixture *f, const double (*points)[2], double mu_b)
{
    wr_support_spec spec;
    memset(&spec, 0, sizeof spec);
    spec.point_count = 3;
    spec.points = points;
    spec.friction.given = true;
    spec.friction.static_mu = mu_b;
    spec.g = G;
    wr_error error;
    assert_int_equal(wr_fixture_set_supports(f, &spec, &error), WR_OK);
}

/* The 3-2-1 plate of docs/MODEL.md section 7.2 (m = 2) on buttons (1, 0.5),
 * (3, 0.5), (2, 1.7) with mu_B. */
static wr_fixture *plate_on_buttons(double mu_b)
{
    static const double buttons[3][2] = {{1, 0.5}, {3, 0.5}, {2, 1.7}};
    wr_fixture *f = test_plate_321();
    rest_on(f, buttons, mu_b);
    return f;
}

/* Runs a job over `over`'s coefficient to the end in small budgets (every
 * run does some work). */
static wr_support_sweep *sweep_over(const wr_fixture *f, wr_lp_env *env, const double w[3],
                                    wr_set set, double low, double high, double ratio,
                                    wr_support_sweep_over over)
{
    wr_sweep_range range = {low, high, ratio};
    wr_support_sweep *job;
    assert_int_equal(wr_support_sweep_new(f, w, set, &range, over, &job), WR_OK);
    bool done = false;
    unsigned long used = 0;
    int runs = 0;
    while (!done) {
        assert_int_equal(wr_support_sweep_run(job, env, 5000, &used, NULL, &done), WR_OK);
        assert_true(++runs < 100000);
    }
    assert_true(used > 0);
    return job;
}

/* Over the fixels' mu. */
static wr_support_sweep *sweep(const wr_fixture *f, wr_lp_env *env, const double w[3], wr_set set,
                               double low, double high, double ratio)
{
    return sweep_over(f, env, w, set, low, high, ratio, WR_SUPPORT_SWEEP_FIXELS);
}

/* The point answer at mu, as wrench.classify gives it for the fixture
 * with that friction on every fixel (mu_k = ratio mu). */
static bool inside_at(const wr_fixture *f, wr_lp_env *env, const double w[3], wr_set set, double mu,
                      double ratio)
{
    wr_fixture at;
    wr_fixture_at_friction(f, mu, ratio, &at);
    wr_analysis *a = test_analysis_new(&at);
    bool inside = true;
    if (set != WR_SET_STRONG) {
        wr_support_goal goal;
        assert_int_equal(wr_supports_goal(a, at.supports, env, w, WR_DEFAULT_TOLERANCE, &goal),
                         WR_OK);
        inside = goal.verdict == WR_VERDICT_INSIDE;
    }
    if (inside && set != WR_SET_GOAL) {
        wr_support_strong strong;
        assert_int_equal(
            wr_supports_strong(a, at.supports, env, w, WR_DEFAULT_TOLERANCE, NULL, &strong), WR_OK);
        inside = strong.verdict == WR_VERDICT_INSIDE;
    }
    wr_analysis_free(a);
    return inside;
}

/* Every interval's points are inside (its ends, 64 points across it); the
 * points between intervals, 1e-6 past each end and 64 across each gap
 * wider than the grid's step, are not.  Returns the points checked. */
static int cross_check(const wr_fixture *f, wr_lp_env *env, const double w[3], wr_set set,
                       const wr_intervals *list, double low, double high, double ratio)
{
    int checked = 0;
    for (int i = 0; i < list->count; i++) {
        double lo = list->items[i][0], hi = list->items[i][1];
        assert_true(lo >= low && hi <= high && lo < hi);
        if (i > 0)
            assert_true(lo > list->items[i - 1][1]);
        for (int k = 0; k <= 64; k++, checked++)
            assert_true(inside_at(f, env, w, set, lo + (hi - lo) * k / 64, ratio));
        if (lo > low + 1e-6) {
            assert_false(inside_at(f, env, w, set, lo - 1e-6, ratio));
            checked++;
        }
        if (hi < high - 1e-6) {
            assert_false(inside_at(f, env, w, set, hi + 1e-6, ratio));
            checked++;
        }
    }
    /* The gaps (between intervals and at the range's ends). */
    double from = low;
    for (int i = 0; i <= list->count; i++) {
        double to = i < list->count ? list->items[i][0] : high;
        if (to - from > (high - low) / WR_SUPPORT_SWEEP_GRID)
            for (int k = 1; k < 64; k++, checked++)
                assert_false(inside_at(f, env, w, set, from + (to - from) * k / 64, ratio));
        if (i < list->count)
            from = list->items[i][1];
    }
    return checked;
}

/* The disc in the corner (fixel friction mu) on three buttons 0.2 from its
 * centre, mu_B = 0.3, W = m g = 9.81.  Every excluded goal cone holds the
 * whole torque axis (both normals pass through the centre), so C + S is C
 * grown in its force plane by the disc of radius mu_B W.  In the force
 * plane the goal cones leave the wedge of directions (180 + atan mu, 270 -
 * atan mu) degrees: G_ms is f_x <= 0 with f_y >= mu f_x, whose edge is the
 * ray at 180 + atan mu, and G_sm its mirror image.  A force F along 225
 * degrees is F sin(45 deg - atan mu) from the nearer edge, so it seats iff
 * F sin(45 deg - atan mu) > mu_B W:
 *     mu* = tan(45 deg - asin(mu_B W / F)),
 * 0.529124931 for F = 10, 0.740993333 for F = 20; for F < sqrt(2) mu_B W
 * (4.162) it seats at no mu. */
static void test_disc_goal_closed_form(void **state)
{
    (void)state;
    wr_lp_env *env = test_lp_env_new();
    wr_fixture *f = test_disc_corner(0.5);
    static const double tri[3][2] = {
        {0, 0.2}, {-0.17320508075688773, -0.1}, {0.17320508075688773, -0.1}};
    const double mu_b = 0.3;
    rest_on(f, tri, mu_b);
    const double forces[] = {10, 20, 4};
    int checked = 0;
    for (int i = 0; i < 3; i++) {
        double F = forces[i];
        const double w[3] = {-F / sqrt(2), -F / sqrt(2), 0};
        wr_support_sweep *job = sweep(f, env, w, WR_SET_GOAL, 0, 2, 1);
        const wr_intervals *got = wr_support_sweep_intervals(job);
        assert_true(wr_support_sweep_exact(job));
        assert_true(wr_support_sweep_resolution(job) == 0);
        double ratio = mu_b * G / F;
        if (ratio >= sin(atan(1.0))) {
            assert_int_equal(got->count, 0);
        } else {
            double expected = tan(atan(1.0) - asin(ratio));
            assert_int_equal(got->count, 1);
            assert_true(got->items[0][0] == 0);
            printf("disc, F = %g: seats below mu = %.10f (closed form %.10f)\n", F,
                   got->items[0][1], expected);
            assert_true(fabs(got->items[0][1] - expected) < 1e-8);
        }
        checked += cross_check(f, env, w, WR_SET_GOAL, got, 0, 2, 1);
        wr_support_sweep_free(job);
    }
    /* A range inside the seating interval: all of it. */
    const double w[3] = {-10 / sqrt(2), -10 / sqrt(2), 0};
    wr_support_sweep *job = sweep(f, env, w, WR_SET_GOAL, 0.1, 0.3, 1);
    const wr_intervals *got = wr_support_sweep_intervals(job);
    assert_int_equal(got->count, 1);
    assert_true(got->items[0][0] == 0.1 && got->items[0][1] == 0.3);
    wr_support_sweep_free(job);
    printf("disc: %d point answers agree\n", checked);
    wr_fixture_free(f);
    wr_lp_env_free(env);
}

/* The 3-2-1 plate (m = 2, fixels at (1, 0), (3, 0) below and (0, 1) to the
 * left) on buttons (1, 0.5), (3, 0.5), (2, 1.7) with mu_B = 0.2, W = 2 g,
 * under a load (8, -10, 0) at the centre of mass: pressed onto the lower
 * fixels by 10, pulled along +x (away from the left fixel) by 8.  The
 * translation along +x is consistent when the fixels' sliding friction
 * (mu_k times their normal forces, which sum to 10) and the buttons'
 * (mu_B W) are below 8: the part moves for mu_k < (8 - mu_B W) / 10, and
 * with mu_k = ratio mu the end of holding is mu_c = (8 - 0.2 * 2 * 9.81)
 * / (10 ratio): 0.4076 at ratio 1, 0.8152 at ratio 0.5.  It is held above
 * it (the point answers say so at every mu checked).  It never seats (no
 * push on the left fixel). */
static void test_plate_strong(void **state)
{
    (void)state;
    wr_lp_env *env = test_lp_env_new();
    wr_fixture *f = plate_on_buttons(0.2);
    const double w[3] = {8, -10, 0};
    int checked = 0;
    for (int r = 0; r < 2; r++) {
        double ratio = r ? 0.5 : 1;
        double mu_c = (8 - 0.2 * 2 * G) / (10 * ratio);
        for (int set = WR_SET_GOAL; set <= WR_SET_BOTH; set++) {
            wr_support_sweep *job = sweep(f, env, w, (wr_set)set, 0, 2, ratio);
            const wr_intervals *got = wr_support_sweep_intervals(job);
            if (set == WR_SET_STRONG) {
                assert_false(wr_support_sweep_exact(job));
                assert_true(wr_support_sweep_resolution(job) == 2.0 / WR_SUPPORT_SWEEP_GRID);
                assert_int_equal(got->count, 1);
                printf("plate, ratio %g: held from mu = %.10f (closed form %.10f)\n", ratio,
                       got->items[0][0], mu_c);
                assert_true(fabs(got->items[0][0] - mu_c) < 1e-7 && got->items[0][1] == 2);
            } else {
                assert_int_equal(got->count, 0);
            }
            checked += cross_check(f, env, w, (wr_set)set, got, 0, 2, ratio);
            wr_support_sweep_free(job);
        }
    }
    printf("plate: %d point answers agree\n", checked);
    wr_fixture_free(f);
    wr_lp_env_free(env);
}

/* Over the buttons' mu_B.  Holding: the plate cut by F_c along +x
 * through its centre of mass (no clamp, W = m g).  Any motion needs
 * F_c a_x >= mu_B sum N_i |a_i| >= mu_B W |a_com| (the power argument of
 * docs/MODEL.md section 11), so it is held for mu_B above F_c / W, and
 * below it the translation along +x (fixels 1 and 2 sliding unloaded,
 * fixel 3 leaving) is consistent: held exactly on [F_c / W, high].
 * Seating: the job's end against wr_supports_friction_limit, which decides
 * it as the least scale of S(1) (another computation).  Each holding
 * answer also against point answers either side of its end and across. */
static bool held_at(const wr_analysis *a, const wr_supports *s, wr_lp_env *env,
                    const double w[3], double mu)
{
    wr_supports at;
    wr_supports_with_friction(s, mu, &at);
    wr_support_strong strong;
    assert_int_equal(wr_supports_strong(a, &at, env, w, WR_DEFAULT_TOLERANCE, NULL, &strong),
                     WR_OK);
    return strong.verdict == WR_VERDICT_INSIDE;
}

static void test_over_supports(void **state)
{
    (void)state;
    wr_lp_env *env = test_lp_env_new();
    wr_fixture *f = plate_on_buttons(0.2); /* its own mu_B is not used */
    wr_analysis *a = test_analysis_new(f);
    for (int k = 0; k < 2; k++) {
        double cutting = k ? 6 : 3, expected = cutting / (2 * G);
        const double w[3] = {cutting, 0, 0};
        wr_support_sweep *job = sweep_over(f, env, w, WR_SET_STRONG, 0, 1, 1,
                                           WR_SUPPORT_SWEEP_SUPPORTS);
        const wr_intervals *got = wr_support_sweep_intervals(job);
        assert_false(wr_support_sweep_exact(job));
        assert_int_equal(got->count, 1);
        printf("plate cut by %g: held from mu_B = %.10f (closed form F_c / W = %.10f)\n",
               cutting, got->items[0][0], expected);
        assert_true(fabs(got->items[0][0] - expected) < 1e-7 && got->items[0][1] == 1);
        assert_true(held_at(a, f->supports, env, w, expected * (1 + 1e-6)));
        assert_false(held_at(a, f->supports, env, w, expected * (1 - 1e-6)));
        for (int j = 1; j < 16; j++)
            assert_true(held_at(a, f->supports, env, w,
                                got->items[0][0] + (1 - got->items[0][0]) * j / 16));
        wr_support_sweep_free(job);
    }
    /* Pushes into the corner: seating's end by the job's bisection and by
     * the least scale of S(1). */
    const double pushes[4][3] = {{-10, -17.3205, 4}, {-12.1752, -15.8671, 4},
                                 {-7.65367, -18.4776, 0}, {-8, -10, 0}};
    for (int k = 0; k < 4; k++) {
        wr_support_sweep *job = sweep_over(f, env, pushes[k], WR_SET_GOAL, 0, 1, 1,
                                           WR_SUPPORT_SWEEP_SUPPORTS);
        const wr_intervals *got = wr_support_sweep_intervals(job);
        double bracket[2];
        assert_int_equal(wr_supports_friction_limit(a, f->supports, env, pushes[k], bracket),
                         WR_OK);
        assert_true(wr_support_sweep_exact(job));
        printf("push (%g, %g, %g): seats below mu_B = %.10f (limit [%.10f, %.10f])\n",
               pushes[k][0], pushes[k][1], pushes[k][2],
               got->count ? got->items[0][1] : 0.0, bracket[0], bracket[1]);
        if (bracket[0] >= 1) {
            assert_true(got->count == 1 && got->items[0][1] == 1);
        } else if (bracket[1] <= 0) {
            assert_int_equal(got->count, 0);
        } else {
            assert_int_equal(got->count, 1);
            assert_true(got->items[0][0] == 0);
            assert_true(got->items[0][1] >= bracket[0] - 2e-9 &&
                        got->items[0][1] <= bracket[1] + 2e-9);
        }
        wr_support_sweep_free(job);
    }
    wr_analysis_free(a);
    wr_fixture_free(f);
    wr_lp_env_free(env);
}

/* Seating and holding together on the plate: both is goal's interval
 * within strong's, each cross-checked at points; wrenches pushing into the
 * corner with torques either way. */
static void test_plate_both(void **state)
{
    (void)state;
    wr_lp_env *env = test_lp_env_new();
    wr_fixture *f = plate_on_buttons(0.05);
    const double wrenches[][3] = {{-3, -10, 0.5}, {-10, -4, 1}, {-10, -10, -4}, {2, -10, 3}};
    int checked = 0;
    for (int i = 0; i < 4; i++) {
        wr_support_sweep *jobs[3];
        for (int set = WR_SET_GOAL; set <= WR_SET_BOTH; set++) {
            jobs[set] = sweep(f, env, wrenches[i], (wr_set)set, 0, 1.5, 0.8);
            checked += cross_check(f, env, wrenches[i], (wr_set)set,
                                   wr_support_sweep_intervals(jobs[set]), 0, 1.5, 0.8);
        }
        /* Seating ends once (a nested family), from the bottom. */
        const wr_intervals *goal = wr_support_sweep_intervals(jobs[WR_SET_GOAL]);
        assert_true(goal->count <= 1);
        if (goal->count)
            assert_true(goal->items[0][0] == 0);
        const wr_intervals *both = wr_support_sweep_intervals(jobs[WR_SET_BOTH]);
        for (int k = 0; k < both->count; k++)
            assert_true(goal->count && both->items[k][1] <= goal->items[0][1]);
        for (int set = WR_SET_GOAL; set <= WR_SET_BOTH; set++)
            wr_support_sweep_free(jobs[set]);
    }
    printf("plate, both: %d point answers agree\n", checked);
    wr_fixture_free(f);
    wr_lp_env_free(env);
}

/* Stopped part way: what it gives lies below where it stopped and is part
 * of the whole answer; stopped before any work, nothing and the low end. */
static void test_stopped(void **state)
{
    (void)state;
    wr_lp_env *env = test_lp_env_new();
    wr_fixture *f = plate_on_buttons(0.2);
    const double w[3] = {8, -10, 0};
    wr_sweep_range range = {0.25, 2, 1};
    for (int set = WR_SET_GOAL; set <= WR_SET_BOTH; set++) {
        for (int runs = 0; runs < 70; runs += 23) {
            wr_support_sweep *job;
            assert_int_equal(wr_support_sweep_new(f, w, (wr_set)set, &range, WR_SUPPORT_SWEEP_FIXELS, &job), WR_OK);
            bool done = false;
            for (int k = 0; k < runs && !done; k++)
                assert_int_equal(wr_support_sweep_run(job, env, 1, NULL, NULL, &done), WR_OK);
            double reached = -1;
            assert_int_equal(wr_support_sweep_stop(job, &reached), WR_OK);
            assert_true(reached >= range.low && reached <= range.high);
            if (runs == 0)
                assert_true(reached == range.low);
            const wr_intervals *got = wr_support_sweep_intervals(job);
            for (int i = 0; i < got->count; i++) {
                assert_true(got->items[i][1] <= reached);
                /* Held from mu_c = 0.4076 on (strong), nowhere (goal, both). */
                assert_true(set == WR_SET_STRONG && got->items[i][0] > 0.4076 - 1e-7);
            }
            wr_support_sweep_free(job);
        }
    }
    wr_fixture_free(f);
    wr_lp_env_free(env);
}

static void test_refused(void **state)
{
    (void)state;
    wr_fixture *f = test_plate_321();
    const double w[3] = {1, 0, 0}, bad[3] = {NAN, 0, 0};
    wr_sweep_range range = {0, 2, 1};
    wr_support_sweep *job = NULL;
    assert_int_equal(wr_support_sweep_new(f, w, WR_SET_GOAL, &range, WR_SUPPORT_SWEEP_FIXELS, &job), WR_INVALID);
    static const double buttons[3][2] = {{1, 0.5}, {3, 0.5}, {2, 1.7}};
    rest_on(f, buttons, 0.2);
    assert_int_equal(wr_support_sweep_new(f, bad, WR_SET_GOAL, &range, WR_SUPPORT_SWEEP_FIXELS, &job), WR_INVALID);
    wr_sweep_range upside = {1, 0.5, 1};
    assert_int_equal(wr_support_sweep_new(f, w, WR_SET_GOAL, &upside, WR_SUPPORT_SWEEP_FIXELS, &job), WR_INVALID);
    assert_null(job);
    wr_fixture_free(f);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_disc_goal_closed_form),
        cmocka_unit_test(test_plate_strong),
        cmocka_unit_test(test_plate_both),
        cmocka_unit_test(test_stopped),
        cmocka_unit_test(test_over_supports),
        cmocka_unit_test(test_refused),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
