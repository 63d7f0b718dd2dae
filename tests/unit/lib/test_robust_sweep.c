/* test_robust_sweep.c -- push regions, gravity arcs and least forces
 * against a common mu over a geometric tolerance (lib/wr_robust_sweep.h),
 * against what is derived here without it:
 *
 * - every interval kept lies in a nominal one (the nominal fixture is one
 *   of the set), and the robust critical is not above the nominal one;
 * - sampling: at mu in each interval kept (its ends and inside), fixtures
 *   of the set built here from their own geometry (a contact moved along
 *   its edge, its normal tilted) each have their nominal regions (arcs) at
 *   that mu, and their intersection is not empty: a push (a tilt) inside on
 *   every fixture of the set is inside on every sampled one;
 * - with a tolerance of 1e-9 the intervals are the nominal ones to within
 *   2^-10 of their length at each end, which is what the bisection reaches;
 * - the robust least force at mu: no less than the nominal least there,
 *   and its push does the job under the load on every sampled fixture;
 * - a stop between units: the answer below `reached`, kept intervals
 *   below it. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>
#include <stdio.h>

#include "test_util.h"
#include "wr_robust_sweep.h"

#define DEG (TEST_PI / 180)

/* The chamfered 3-2-1 plate: [0, 4] x [0, 2] with its corner (4, 2) cut
 * from (4, 1) to (3, 2); locators under it at x = 1 and 3, one on its left
 * side at y = 0.5.  Along the boundary, counter-clockwise, and the inward
 * normal of each locator's edge. */
static const double CHAMFERED[5][2] = {{0, 0}, {4, 0}, {4, 1}, {3, 2}, {0, 2}};
static const double AT[3][2] = {{1, 0}, {3, 0}, {0, 0.5}};
static const double RUN[3][2] = {{1, 0}, {1, 0}, {0, -1}};
static const double NORMAL[3][2] = {{0, 1}, {0, 1}, {1, 0}};

/* The plate with contact i moved s[i] along its edge and its normal
 * tilted by tilt[i] radians (NULL: nominal), mu_s = mu, mu_k = ratio mu. */
static wr_fixture *plate(double mu, double ratio, const double *s, const double *tilt)
{
    wr_fixel_spec fixels[3];
    memset(fixels, 0, sizeof fixels);
    for (int i = 0; i < 3; i++) {
        double d = s ? s[i] : 0, a = tilt ? tilt[i] : 0;
        fixels[i].at[0] = AT[i][0] + d * RUN[i][0];
        fixels[i].at[1] = AT[i][1] + d * RUN[i][1];
        fixels[i].normal_given = true;
        fixels[i].normal[0] = cos(a) * NORMAL[i][0] - sin(a) * NORMAL[i][1];
        fixels[i].normal[1] = sin(a) * NORMAL[i][0] + cos(a) * NORMAL[i][1];
    }
    wr_fixture_spec spec;
    memset(&spec, 0, sizeof spec);
    spec.mass = 2;
    spec.shape = WR_SHAPE_POLYGON;
    spec.vertex_count = 5;
    spec.vertices = CHAMFERED;
    spec.friction.given = true;
    spec.friction.static_mu = mu;
    spec.friction.kinetic_given = true;
    spec.friction.kinetic_mu = ratio * mu;
    spec.fixel_count = 3;
    spec.fixels = fixels;
    return test_fixture_new(&spec, NULL);
}

static wr_fixture *toleranced(double mu, double ratio, double position, double angle)
{
    wr_fixture *f = plate(mu, ratio, NULL, NULL);
    assert_non_null(f);
    wr_tolerance t = {true, position, angle};
    assert_int_equal(wr_fixture_set_tolerance(f, &t, NULL), WR_OK);
    return f;
}

/* Corners of the set first (where worst cases sit), then random points. */
static void draw(test_rng *rng, int k, double position, double angle, double s[3],
                 double tilt[3])
{
    for (int i = 0; i < 3; i++) {
        if (k < 8) {
            s[i] = (k >> i & 1) ? position : -position;
            tilt[i] = (k >> i & 1) ? -angle * DEG : angle * DEG;
        } else {
            s[i] = test_range(rng, -position, position);
            tilt[i] = test_range(rng, -angle, angle) * DEG;
        }
    }
}

/* The nominal intervals of mu where the region (arcs) is not empty. */
static void nominal_sweep(const wr_fixture *f, wr_set set, const wr_sweep_range *range,
                          bool gravity, const wr_finger *finger, wr_sweep_curve *out)
{
    wr_sweeper *sweeper;
    assert_int_equal(wr_sweeper_new(f, set, range, &sweeper), WR_OK);
    assert_int_equal(gravity ? wr_sweep_gravity(sweeper, NULL, out)
                             : wr_sweep_push(sweeper, finger, NULL, out),
                     WR_OK);
    wr_sweeper_free(sweeper);
}

static void run_to_end(wr_robust_sweep *job)
{
    bool done = false;
    while (!done)
        assert_int_equal(wr_robust_sweep_run(job, NULL, &done), WR_OK);
}

/* The intersection of the regions of `count` fixtures, edge by edge: is
 * some (edge, t) in all of them?  Each edge's intersection is a union of
 * intervals, narrowed by each fixture in turn. */
#define MOST 64
static bool common_point(const wr_regions *regions, int count)
{
    for (int edge = 0; edge < 5; edge++) {
        double have[MOST][2];
        int n = 0;
        for (int j = 0; j < regions[0].count && n < MOST; j++)
            if (regions[0].items[j].edge == edge) {
                have[n][0] = regions[0].items[j].t0;
                have[n++][1] = regions[0].items[j].t1;
            }
        for (int k = 1; k < count && n > 0; k++) {
            double next[MOST][2];
            int m = 0;
            for (int a = 0; a < n; a++)
                for (int j = 0; j < regions[k].count && m < MOST; j++) {
                    const wr_region *r = &regions[k].items[j];
                    double lo = fmax(have[a][0], r->t0), hi = fmin(have[a][1], r->t1);
                    if (r->edge == edge && lo <= hi) {
                        next[m][0] = lo;
                        next[m++][1] = hi;
                    }
                }
            memcpy(have, next, sizeof have[0] * (size_t)m);
            n = m;
        }
        if (n > 0)
            return true;
    }
    return false;
}

#define SAMPLES 12

/* At mu: the regions (arcs) of SAMPLES fixtures of the set meet. */
static void check_meet(double mu, double ratio, double position, double angle, wr_set set,
                       bool gravity, test_rng *rng)
{
    wr_regions regions[SAMPLES];
    for (int k = 0; k < SAMPLES; k++) {
        double s[3], tilt[3];
        draw(rng, k, position, angle, s, tilt);
        wr_fixture *g = plate(mu, ratio, s, tilt);
        assert_non_null(g);
        wr_analysis *a = test_analysis_new(g);
        assert_int_equal(gravity ? wr_gravity_sweep(a, set, &regions[k])
                                 : wr_push_regions(a, set, 0, NULL, &regions[k]),
                         WR_OK);
        wr_analysis_free(a);
        wr_fixture_free(g);
    }
    if (!common_point(regions, SAMPLES)) {
        print_error("mu %.17g kept, but the sampled fixtures' %s have nothing in common\n", mu,
                    gravity ? "arcs" : "regions");
        fail();
    }
    for (int k = 0; k < SAMPLES; k++)
        wr_regions_release(&regions[k]);
}

/* The robust sweep of the chamfered plate against the nominal one and
 * against sampling. */
static void sweep_test(wr_set set, bool gravity, double position, double angle, double ratio,
                       uint64_t seed)
{
    const wr_sweep_range range = {0, 2, ratio};
    wr_fixture *f = toleranced(0.3, ratio, position, angle);
    wr_finger finger = {0};
    wr_sweep_curve nominal, robust;
    nominal_sweep(f, set, &range, gravity, &finger, &nominal);
    wr_robust_sweep *job;
    assert_int_equal(wr_robust_sweep_new(f, set, &range, gravity, &finger, &nominal.intervals,
                                         &job),
                     WR_OK);
    run_to_end(job);
    assert_true(wr_robust_sweep_reached(job) == range.high);
    assert_int_equal(wr_robust_sweep_curve(job, range.high, &robust), WR_OK);
    assert_false(robust.exact);
    assert_true(robust.resolution == 2.0 / WR_ROBUST_SWEEP_GRID);
    test_rng rng = {seed};
    double kept = 0;
    for (int i = 0; i < robust.intervals.count; i++) {
        const double *r = robust.intervals.items[i];
        bool within = false;
        for (int j = 0; j < nominal.intervals.count; j++)
            within |= nominal.intervals.items[j][0] <= r[0] && r[1] <= nominal.intervals.items[j][1];
        assert_true(within);
        kept += r[1] - r[0];
        for (int k = 0; k < 4; k++) {
            double mu = k == 0 ? r[0] : k == 1 ? r[1] : test_range(&rng, r[0], r[1]);
            check_meet(mu, ratio, position, angle, set, gravity, &rng);
        }
    }
    /* The critical by the nominal rule, from the robust intervals. */
    if (nominal.has_critical) {
        assert_true(robust.has_critical && robust.critical <= nominal.critical);
        const wr_intervals *k = &robust.intervals;
        assert_true(robust.critical == (k->count ? k->items[k->count - 1][1] : range.low));
    }
    /* The curve: increasing mu, lengths 0 outside the nominal intervals. */
    for (int i = 0; i < robust.point_count; i++) {
        assert_true(i == 0 || robust.points[i][0] > robust.points[i - 1][0]);
        bool in_nominal = false;
        for (int j = 0; j < nominal.intervals.count; j++)
            in_nominal |= robust.points[i][0] >= nominal.intervals.items[j][0] &&
                          robust.points[i][0] <= nominal.intervals.items[j][1];
        assert_true(in_nominal || robust.points[i][1] == 0);
    }
    print_message("%s %s T %g A %g: nominal critical %.6f, robust %.6f (kept %.6f of mu)\n",
                  gravity ? "gravity" : "push", set == WR_SET_GOAL ? "goal" : "both", position,
                  angle, nominal.has_critical ? nominal.critical : range.high,
                  robust.has_critical ? robust.critical : range.high, kept);
    assert_true(kept > 0);
    wr_sweep_curve_release(&nominal);
    wr_sweep_curve_release(&robust);
    wr_robust_sweep_free(job);
    wr_fixture_free(f);
}

static void test_push_both(void **state)
{
    (void)state;
    sweep_test(WR_SET_BOTH, false, 0.02, 0.5, 0.8, 0x51ULL);
}

static void test_gravity_goal(void **state)
{
    (void)state;
    sweep_test(WR_SET_GOAL, true, 0.02, 0.5, 1, 0x52ULL);
}

/* T = 1e-9: every end the nominal sweep has is reached to within the
 * bisection's finest piece, a 2^-10 share of the nominal interval. */
static void test_tiny_tolerance(void **state)
{
    (void)state;
    const wr_sweep_range range = {0, 2, 1};
    wr_fixture *f = toleranced(0.3, 1, 1e-9, 0);
    wr_finger finger = {0};
    wr_sweep_curve nominal, robust;
    nominal_sweep(f, WR_SET_GOAL, &range, false, &finger, &nominal);
    assert_int_equal(nominal.intervals.count, 1);
    wr_robust_sweep *job;
    assert_int_equal(wr_robust_sweep_new(f, WR_SET_GOAL, &range, false, &finger,
                                         &nominal.intervals, &job),
                     WR_OK);
    run_to_end(job);
    assert_int_equal(wr_robust_sweep_curve(job, range.high, &robust), WR_OK);
    assert_int_equal(robust.intervals.count, 1);
    const double *n = nominal.intervals.items[0], *r = robust.intervals.items[0];
    const double finest = (n[1] - n[0]) / (1 << WR_ROBUST_DEPTH);
    print_message("T 1e-9: nominal [%.9f, %.9f], robust [%.9f, %.9f], finest %.3g\n", n[0],
                  n[1], r[0], r[1], finest);
    assert_true(r[0] == n[0]);
    assert_true(r[1] <= n[1] && r[1] >= n[1] - 2 * finest);
    assert_true(robust.critical == r[1]);
    wr_sweep_curve_release(&nominal);
    wr_sweep_curve_release(&robust);
    wr_robust_sweep_free(job);
    wr_fixture_free(f);
}

static bool always(void *context)
{
    (void)context;
    return true;
}

/* Stopped after a few units: the answer below `reached` (the intervals
 * cut there, no critical), and a stop asked is WR_STOPPED. */
static void test_stop(void **state)
{
    (void)state;
    const wr_sweep_range range = {0, 2, 1};
    wr_fixture *f = toleranced(0.3, 1, 0.02, 0.5);
    wr_finger finger = {0};
    wr_sweep_curve nominal, cut;
    nominal_sweep(f, WR_SET_GOAL, &range, false, &finger, &nominal);
    wr_robust_sweep *job;
    assert_int_equal(wr_robust_sweep_new(f, WR_SET_GOAL, &range, false, &finger,
                                         &nominal.intervals, &job),
                     WR_OK);
    bool done = false;
    double last = range.low;
    for (int unit = 0; unit < 12 && !done; unit++) {
        assert_int_equal(wr_robust_sweep_run(job, NULL, &done), WR_OK);
        double reached = wr_robust_sweep_reached(job);
        assert_true(reached >= last && reached <= range.high);
        last = reached;
    }
    assert_false(done);
    assert_int_equal(wr_robust_sweep_curve(job, last, &cut), WR_OK);
    assert_false(cut.has_critical);
    for (int i = 0; i < cut.intervals.count; i++)
        assert_true(cut.intervals.items[i][1] <= last);
    for (int i = 0; i < cut.point_count; i++)
        assert_true(cut.points[i][0] <= last);
    const wr_stop stop = {always, NULL};
    assert_int_equal(wr_robust_sweep_run(job, &stop, &done), WR_STOPPED);
    wr_sweep_curve_release(&nominal);
    wr_sweep_curve_release(&cut);
    wr_robust_sweep_free(job);
    /* Refused: no tolerance; a finger with friction. */
    wr_fixture *plain = plate(0.3, 1, NULL, NULL);
    const wr_intervals none = {0};
    assert_int_equal(wr_robust_sweep_new(plain, WR_SET_GOAL, &range, false, &finger, &none, &job),
                     WR_INVALID);
    const wr_finger rough = {.friction = 0.2};
    assert_int_equal(wr_robust_sweep_new(f, WR_SET_GOAL, &range, false, &rough, &none, &job),
                     WR_INVALID);
    assert_null(job);
    wr_fixture_free(plain);
    wr_fixture_free(f);
}

/* The robust least force at mu under the plate's weight: no less than the
 * nominal least, and its push with the load inside (both) on every sampled
 * fixture of the set at that mu. */
static void test_least_force(void **state)
{
    (void)state;
    const double position = 0.02, angle = 0.5, ratio = 1;
    wr_fixture *f = toleranced(0.3, ratio, position, angle);
    const double load[1][3] = {{0, -2 * 9.81, 0}};
    const wr_finger finger = {0};
    test_rng rng = {0x53ULL};
    int found = 0;
    for (int m = 0; m < 3; m++) {
        const double mu = 0.05 + 0.12 * m;
        wr_least_force robust;
        assert_int_equal(wr_robust_least_force_at_mu(f, mu, ratio, WR_SET_BOTH, load, 1,
                                                     &finger, 2, NULL, &robust),
                         WR_OK);
        wr_fixture *g = plate(mu, ratio, NULL, NULL);
        wr_analysis *a = test_analysis_new(g);
        wr_least_force nominal;
        assert_int_equal(wr_least_force_find(a, WR_SET_BOTH, load, 1, &finger, NULL, &nominal),
                         WR_OK);
        wr_analysis_free(a);
        wr_fixture_free(g);
        print_message("mu %g: nominal least %.6g, robust %.6g\n", mu,
                      nominal.found ? nominal.force : INFINITY, robust.force);
        if (!robust.found)
            continue;
        found++;
        assert_true(nominal.found && robust.force >= nominal.force * (1 - 1e-9));
        assert_true(robust.lower == nominal.lower);
        /* The push of that force at its point, built here: along the
         * inward normal `direction` at `at`, its torque about the centre
         * of mass. */
        const double *p = robust.at, *d = robust.direction, *c = f->com;
        const double F = robust.force;
        const double w[3] = {F * d[0] + load[0][0], F * d[1] + load[0][1],
                             F * ((p[0] - c[0]) * d[1] - (p[1] - c[1]) * d[0])};
        for (int k = 0; k < SAMPLES; k++) {
            double s[3], tilt[3];
            draw(&rng, k, position, angle, s, tilt);
            wr_fixture *h = plate(mu, ratio, s, tilt);
            wr_analysis *b = test_analysis_new(h);
            wr_answer answer;
            assert_int_equal(wr_classify(b, w, WR_SET_BOTH, WR_DEFAULT_TOLERANCE, &answer),
                             WR_OK);
            assert_int_equal(answer.verdict, WR_VERDICT_INSIDE);
            wr_analysis_free(b);
            wr_fixture_free(h);
        }
    }
    assert_true(found >= 2);
    wr_fixture_free(f);
}

/* wr_robust_regions_meet: found on the nominal regions when their robust
 * part is not empty; never on pushes nominally outside (the nominal
 * fixture is one of the set), checked here by classifying them; a depth
 * out of bounds refused. */
static void test_meet(void **state)
{
    (void)state;
    wr_fixture *f = toleranced(0.1, 1, 0.01, 0.5);
    wr_analysis *a = test_analysis_new(f);
    wr_robust *rb;
    assert_int_equal(wr_robust_new(a, WR_ROBUST_SWEEP_BUDGET, &rb), WR_OK);
    wr_regions nominal, robust;
    assert_int_equal(wr_push_regions(a, WR_SET_BOTH, 0, NULL, &nominal), WR_OK);
    assert_int_equal(wr_robust_regions(rb, WR_SET_BOTH, &nominal, false, NULL, &robust), WR_OK);
    assert_true(robust.count > 0);
    bool found;
    assert_int_equal(wr_robust_regions_meet(rb, WR_SET_BOTH, &nominal, false, 6, NULL, &found),
                     WR_OK);
    assert_true(found);
    /* Every edge's stretch outside the nominal regions, as candidates:
     * each push there is nominally outside, so none can be proved. */
    wr_regions outside = {0};
    wr_region items[16];
    for (int e = 0; e < 5; e++) {
        double from = 0;
        for (int i = 0; i <= nominal.count; i++) {
            bool last = i == nominal.count;
            if (!last && nominal.items[i].edge != e)
                continue;
            double to = last ? 1 : nominal.items[i].t0;
            /* a margin off the region's ends, where the verdict is boundary */
            if (to - from > 2e-6 && outside.count < 16)
                items[outside.count++] = (wr_region){e, from + 1e-6, to - 1e-6};
            from = last ? 1 : nominal.items[i].t1;
        }
    }
    outside.items = items;
    assert_true(outside.count >= 5);
    for (int i = 0; i < outside.count; i++)
        for (int k = 0; k <= 8; k++) {
            double t = items[i].t0 + (items[i].t1 - items[i].t0) * k / 8, w[3];
            wr_push_wrench(f, items[i].edge, t, w);
            wr_answer answer;
            assert_int_equal(wr_classify(a, w, WR_SET_BOTH, WR_DEFAULT_TOLERANCE, &answer),
                             WR_OK);
            assert_int_not_equal(answer.verdict, WR_VERDICT_INSIDE);
        }
    assert_int_equal(wr_robust_regions_meet(rb, WR_SET_BOTH, &outside, false, 6, NULL, &found),
                     WR_OK);
    assert_false(found);
    assert_int_equal(wr_robust_regions_meet(rb, WR_SET_BOTH, &nominal, false,
                                            WR_ROBUST_DEPTH + 1, NULL, &found),
                     WR_INVALID);
    wr_regions_release(&nominal);
    wr_regions_release(&robust);
    wr_robust_free(rb);
    wr_analysis_free(a);
    wr_fixture_free(f);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_meet),
        cmocka_unit_test(test_stop),
        cmocka_unit_test(test_tiny_tolerance),
        cmocka_unit_test(test_least_force),
        cmocka_unit_test(test_push_both),
        cmocka_unit_test(test_gravity_goal),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
