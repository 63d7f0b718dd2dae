/* test_crosscheck.c -- the explicit cones against GLPK, on random fixtures.
 *
 * Two methods that share no code beyond the fixture model must agree: the
 * explicit cones (3-D geometry) and the seed's LP feasibility problems.
 * Witnesses are checked against the constraint rows by a checker written
 * here from docs/MODEL.md section 2's table. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>
#include <stdio.h>

#include "test_util.h"

#define FIXTURES 24
#define WRENCHES 1000

/* A random physical wrench: a uniform direction in the scaled metric, a
 * random magnitude. */
static void random_wrench(test_rng *rng, const wr_fixture *f, double g[3])
{
    double x[3];
    test_sphere(rng, x);
    wr_fixture_unscale_wrench(f, x, g);
    double magnitude = pow(10, test_range(rng, -3, 3));
    for (int k = 0; k < 3; k++)
        g[k] *= magnitude;
}

typedef struct totals {
    long compared, inside, near_boundary, witnesses;
} totals;

static void compare_sets(const wr_analysis *a, wr_lp_set *goal, wr_lp_set *strong,
                         const double g[3], totals *t)
{
    for (int s = 0; s < 2; s++) {
        wr_set set = s == 0 ? WR_SET_GOAL : WR_SET_STRONG;
        wr_answer by_cones, by_lp;
        assert_int_equal(wr_classify(a, g, set, 1e-9, &by_cones), 0);
        assert_int_equal(wr_classify_lp(a, goal, strong, g, set, &by_lp), 0);
        assert_true(by_cones.margin >= -1 && by_cones.margin <= 1);
        if (fabs(by_cones.margin) <= 1e-6) {
            t->near_boundary++;
            continue;
        }
        t->compared++;
        t->inside += by_cones.verdict == WR_VERDICT_INSIDE;
        if ((by_cones.verdict == WR_VERDICT_INSIDE) != (by_lp.verdict == WR_VERDICT_INSIDE)) {
            char text[WR_CONSTRAINT_TEXT] = "";
            if (by_cones.blocking >= 0)
                wr_constraint_format(&wr_analysis_cone(a, set, by_cones.blocking)->constraint,
                                     text);
            fail_msg("set %d: cones say %d (margin %.3g, blocking %s), LP says %d for "
                     "g = (%.17g, %.17g, %.17g)",
                     s, by_cones.verdict, by_cones.margin, text, by_lp.verdict, g[0], g[1], g[2]);
        }
        if (by_cones.verdict == WR_VERDICT_OUTSIDE) {
            /* g is inside the blocking cone: both witnesses make g itself. */
            const wr_constraint *c =
                &wr_analysis_cone(a, by_cones.blocking_set, by_cones.blocking)->constraint;
            const wr_constraint *lc =
                &wr_analysis_cone(a, by_lp.blocking_set, by_lp.blocking)->constraint;
            /* GLPK's feasibility tolerance is 1e-7 on the normalised rows. */
            const wr_fixture *f = wr_analysis_fixture(a);
            const char *why = test_witness_violation(f, c, &by_cones.witness, g, 1e-9);
            const char *lp_why = test_witness_violation(f, lc, &by_lp.witness, g, 1e-6);
            if (why || lp_why) {
                char text[WR_CONSTRAINT_TEXT], lp_text[WR_CONSTRAINT_TEXT];
                wr_constraint_format(c, text);
                wr_constraint_format(lc, lp_text);
                fail_msg("witness for g = (%.17g, %.17g, %.17g): cones %s: %s; LP %s: %s", g[0],
                         g[1], g[2], text, why ? why : "ok", lp_text, lp_why ? lp_why : "ok");
            }
            t->witnesses += 2;
        }
    }
}

/* Both methods on `first` (NULL: none), then on `count` random wrenches of
 * the fixture.  Returns how many verdicts `first` had compared (0..2). */
static long compare_on(const wr_fixture *f, wr_lp_env *env, test_rng *rng, const double *first,
                       int count, totals *t)
{
    wr_analysis *a = test_analysis_new(f);
    assert_non_null(a);
    wr_lp_set *goal, *strong;
    assert_int_equal(wr_analysis_lp_sets(a, env, &goal, &strong), 0);
    long before = t->compared;
    if (first)
        compare_sets(a, goal, strong, first, t);
    long first_compared = t->compared - before;
    for (int w = 0; w < count; w++) {
        double g[3];
        random_wrench(rng, f, g);
        compare_sets(a, goal, strong, g, t);
    }
    wr_lp_set_free(goal);
    wr_lp_set_free(strong);
    wr_analysis_free(a);
    return first_compared;
}

static void auto_and_lp_agree_on_random_fixtures(void **state)
{
    (void)state;
    test_rng rng = {20261122};
    wr_lp_env *env = test_lp_env_new();
    totals t = {0, 0, 0, 0};
    int discs = 0, polygons = 0;
    for (int i = 0; i < FIXTURES; i++) {
        int k = 2 + i % 3;
        bool disc = (i / 3) % 2 == 0;
        wr_fixture *f = test_random_fixture(&rng, k, disc);
        assert_non_null(f);
        discs += disc;
        polygons += !disc;
        compare_on(f, env, &rng, NULL, WRENCHES, &t);
        wr_fixture_free(f);
    }
    wr_lp_env_free(env);
    print_message("crosscheck: %d discs + %d polygons x %d wrenches x 2 sets: %ld verdicts "
                  "agree (%ld inside), %ld within 1e-6 of a boundary (not compared), %ld "
                  "witnesses checked\n",
                  discs, polygons, WRENCHES, t.compared, t.inside, t.near_boundary, t.witnesses);
    assert_true(t.compared > 40000);
    assert_true(t.inside > 1000 && t.compared - t.inside > 1000);
}

/* Every explicit cone, against LP membership of points on both sides. */
static void every_cone_agrees_with_lp_membership(void **state)
{
    (void)state;
    test_rng rng = {777};
    wr_lp_env *env = test_lp_env_new();
    long inside = 0, outside = 0, relative_interior = 0, cones = 0, near = 0;
    for (int i = 0; i < FIXTURES; i++) {
        int k = 2 + i % 3;
        wr_fixture *f = test_random_fixture(&rng, k, i % 2 == 0);
        assert_non_null(f);
        wr_analysis *a = test_analysis_new(f);
        for (int s = 0; s < 2; s++) {
            wr_set set = s == 0 ? WR_SET_GOAL : WR_SET_STRONG;
            int count = wr_analysis_cone_count(a, set);
            wr_lp_set *lp;
            assert_int_equal(wr_lp_set_new(env, f, wr_analysis_constraints(a, set), count, &lp),
                             WR_OK);
            for (int c = 0; c < count; c++) {
                const wr_cone *cone = wr_analysis_cone(a, set, c);
                assert_false(cone->empty); /* feasible by construction */
                cones++;
                for (int p = 0; p < 80; p++) {
                    double x[3], g[3];
                    if (p >= 60 && cone->facet_count > 0) {
                        /* 1e-4 to either side of a facet, near its middle:
                         * the projection of a random interior-ish point. */
                        const double *facet = cone->facets[p % cone->facet_count];
                        double y[3];
                        test_sphere(&rng, y);
                        double along = y[0] * facet[0] + y[1] * facet[1] + y[2] * facet[2];
                        double offset = p % 2 ? 1e-4 : -1e-4;
                        for (int j = 0; j < 3; j++)
                            x[j] = y[j] - along * facet[j] + offset * facet[j];
                        for (int e = 0; e < cone->equality_count; e++) {
                            double off = 0;
                            for (int j = 0; j < 3; j++)
                                off += cone->equalities[e][j] * x[j];
                            for (int j = 0; j < 3; j++)
                                x[j] -= off * cone->equalities[e][j];
                        }
                        double length = sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]);
                        for (int j = 0; j < 3; j++)
                            x[j] /= length;
                    } else if (p < 10 && cone->ray_count > 0) {
                        /* A point of the relative interior. */
                        x[0] = x[1] = x[2] = 0;
                        for (int r = 0; r < cone->ray_count; r++) {
                            double coefficient = test_range(&rng, 0.1, 1);
                            for (int j = 0; j < 3; j++)
                                x[j] += coefficient * cone->rays[r][j];
                        }
                        double length = sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]);
                        if (length < 1e-9)
                            continue;
                        for (int j = 0; j < 3; j++)
                            x[j] /= length;
                    } else {
                        test_sphere(&rng, x);
                    }
                    double d = wr_cone_signed_distance(cone, x, NULL);
                    wr_fixture_unscale_wrench(f, x, g);
                    bool member;
                    assert_int_equal(wr_lp_member(lp, c, g, &member, NULL), WR_OK);
                    if (p < 10) {
                        /* Relative interior: in G_X even with strict rows. */
                        if (d > 1e-9) {
                            char text[WR_CONSTRAINT_TEXT];
                            wr_constraint_format(&cone->constraint, text);
                            fail_msg("relative interior point of %s (dim %d, %d facets, %d "
                                     "rays) is %.3g outside", text, cone->dimension,
                                     cone->facet_count, cone->ray_count, d);
                        }
                        if (!member) {
                            char text[WR_CONSTRAINT_TEXT];
                            wr_constraint_format(&cone->constraint, text);
                            fail_msg("relative interior point of %s (dim %d) not a member", text,
                                     cone->dimension);
                        }
                        relative_interior++;
                    } else if (d < -1e-6) {
                        assert_true(member);
                        inside++;
                        near += p >= 60;
                    } else if (d > 1e-6) {
                        assert_false(member);
                        outside++;
                        near += p >= 60;
                    }
                }
            }
            wr_lp_set_free(lp);
        }
        wr_analysis_free(a);
        wr_fixture_free(f);
    }
    wr_lp_env_free(env);
    print_message("crosscheck: %ld cones; LP agrees on %ld interior, %ld exterior (%ld of "
                  "them 1e-4 from a facet) and %ld relative-interior points\n",
                  cones, inside, outside, near, relative_interior);
    assert_true(near > 5000);
}

/* The bracket of examples/ with its right side bulged out (bulge 44201 draws
 * an arc of radius about 486,000 through the 44-long chord): the centre of
 * mass (88518, 88458) and the radius of gyration 88,402 are those of a part
 * a million across, held by three fixels spread over 107.7 at one end,
 * 1.2e-3 of the radius of gyration.  Every motion that slides at two fixels
 * turns about a point among them, so its inequality rows are 1e-4 of the
 * motion: an LP posing them over q' takes a motion going the wrong way
 * (within GLPK's absolute tolerance) and calls g = (-1, -1, 0) a member of
 * G_sll, which the cones put 1.4e-4 outside (tests/fuzz/README.md,
 * finding 12).  The smaller bulges are the same part less extreme. */
static void lp_agrees_on_fixels_bunched_far_from_the_centre(void **state)
{
    (void)state;
    const double bulges[] = {44201.1356237309503, 4420.1, 442, 44.2};
    test_rng rng = {1212};
    wr_lp_env *env = test_lp_env_new();
    totals t = {0, 0, 0, 0};
    for (size_t b = 0; b < sizeof bulges / sizeof bulges[0]; b++) {
        const double arc = 0.41421356237309503;
        const double outer[][3] = {{8, 0, 0},  {112, 0, arc},         {120, 8, 0},
                                   {120, 52, bulges[b]}, {112, 60, 0}, {8, 60, arc},
                                   {0, 52, 0}, {0, 8, arc}};
        const double pin[][3] = {{36, 30, 1}, {24, 30, 1}};
        const double slot[][3] = {{75, 25, 0}, {95, 25, 1}, {95, 35, 0}, {75, 35, 1}};
        const wr_loop_spec loops[] = {{8, outer}, {2, pin}, {4, slot}};
        wr_fixel_spec fixels[3];
        memset(fixels, 0, sizeof fixels);
        const double at[3][2] = {{25.757359312880716, 34.242640687119284}, {100, 0}, {0, 40}};
        for (int i = 0; i < 3; i++)
            memcpy(fixels[i].at, at[i], sizeof at[i]);
        wr_fixture_spec spec;
        memset(&spec, 0, sizeof spec);
        spec.mass = 0.8;
        spec.shape = WR_SHAPE_OUTLINE;
        spec.loops = loops;
        spec.loop_count = 3;
        spec.friction.given = true;
        spec.friction.static_mu = 0.25;
        spec.fixel_count = 3;
        spec.fixels = fixels;
        wr_error error;
        wr_fixture *f = test_fixture_new(&spec, &error);
        assert_non_null(f);
        const double g[3] = {-1, -1, 0};
        assert_int_equal(compare_on(f, env, &rng, g, 300, &t), 2); /* both far from 0 */
        wr_fixture_free(f);
    }
    wr_lp_env_free(env);
    print_message("crosscheck, bunched fixels: %ld compared (%ld inside), %ld near a boundary, "
                  "%ld witnesses\n", t.compared, t.inside, t.near_boundary, t.witnesses);
    assert_true(t.inside > 0 && t.compared - t.inside > 0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(auto_and_lp_agree_on_random_fixtures),
        cmocka_unit_test(every_cone_agrees_with_lp_membership),
        cmocka_unit_test(lp_agrees_on_fixels_bunched_far_from_the_centre),
    };
    return cmocka_run_group_tests_name("crosscheck", tests, NULL, NULL);
}
