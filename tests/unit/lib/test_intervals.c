/* test_intervals.c -- friction intervals (docs/PROTOCOL.md, "Friction
 * intervals"): validation names its fields, [a, a] is the point a, and the
 * robust cones are the union over the box: checked against fixtures at
 * sampled point frictions (the box's physical corners and random points),
 * against the LP method, and through the witness's friction. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>
#include <stdio.h>

#include "test_util.h"

/* ---- validation ----------------------------------------------------------- */

typedef struct base {
    wr_fixture_spec spec;
    wr_fixel_spec fixels[3];
    double vertices[4][2];
} base;

static void make_base(base *b)
{
    memset(b, 0, sizeof *b);
    const double v[4][2] = {{0, 0}, {4, 0}, {4, 2}, {0, 2}};
    memcpy(b->vertices, v, sizeof v);
    b->fixels[0].at[0] = 1;
    b->fixels[1].at[0] = 3;
    b->fixels[2].at[1] = 1;
    b->spec.mass = 2;
    b->spec.shape = WR_SHAPE_POLYGON;
    b->spec.vertex_count = 4;
    b->spec.vertices = (const double (*)[2])b->vertices;
    b->spec.fixel_count = 3;
    b->spec.fixels = b->fixels;
}

static void set_interval(wr_friction_spec *f, double slo, double shi, bool kinetic, double klo,
                         double khi)
{
    f->given = true;
    f->static_interval = true;
    f->static_min = slo;
    f->static_mu = shi;
    f->kinetic_given = kinetic;
    f->kinetic_interval = kinetic;
    f->kinetic_min = klo;
    f->kinetic_mu = khi;
}

static void refused(const base *b, const char *field, const char *reason_part)
{
    wr_error error;
    wr_fixture *f = test_fixture_new(&b->spec, &error);
    if (f) {
        wr_fixture_free(f);
        fail_msg("accepted; expected a refusal at %s", field);
    }
    if (strcmp(error.field, field) != 0 || !strstr(error.reason, reason_part))
        fail_msg("refused at '%s' (%s); expected '%s' (... %s ...)", error.field, error.reason,
                 field, reason_part);
}

static void invalid_intervals_are_named(void **state)
{
    (void)state;
    base b;
    make_base(&b);
    set_interval(&b.spec.friction, 0.4, 0.2, false, 0, 0);
    refused(&b, "friction.static", "empty");
    set_interval(&b.spec.friction, -0.1, 0.2, false, 0, 0);
    refused(&b, "friction.static[0]", "negative");
    set_interval(&b.spec.friction, 0.1, NAN, false, 0, 0);
    refused(&b, "friction.static[1]", "finite");
    set_interval(&b.spec.friction, 0.1, WR_MAX_FRICTION * 2, false, 0, 0);
    refused(&b, "friction.static[1]", "above");
    set_interval(&b.spec.friction, 0.2, 0.35, true, 0.3, 0.2);
    refused(&b, "friction.kinetic", "empty");
    set_interval(&b.spec.friction, 0.2, 0.35, true, 0.1, 0.4);
    refused(&b, "friction.kinetic[1]", "upper bound 0.4 exceeds");
    set_interval(&b.spec.friction, 0.2, 0.35, true, 0.25, 0.3);
    refused(&b, "friction.kinetic[0]", "lower bound 0.25 exceeds");
    /* A point kinetic against an interval static: below its lower bound. */
    set_interval(&b.spec.friction, 0.2, 0.35, true, 0, 0.25);
    b.spec.friction.kinetic_interval = false;
    refused(&b, "friction.kinetic", "lower bound 0.25 exceeds");
    /* Per fixel. */
    set_interval(&b.spec.friction, 0.2, 0.35, false, 0, 0);
    set_interval(&b.fixels[2].friction, 0.1, 0.3, true, 0.05, 0.31);
    refused(&b, "fixels[2].friction.kinetic[1]", "exceeds");
}

static void valid_intervals_are_kept(void **state)
{
    (void)state;
    base b;
    make_base(&b);
    set_interval(&b.spec.friction, 0.2, 0.35, true, 0.15, 0.3);
    set_interval(&b.fixels[1].friction, 0.1, 0.5, false, 0, 0); /* kinetic: all of static */
    /* Kinetic intervals reaching above static's lower bound are valid. */
    set_interval(&b.fixels[2].friction, 0.2, 0.6, true, 0.1, 0.55);
    wr_error error;
    wr_fixture *f = test_fixture_new(&b.spec, &error);
    assert_non_null(f);
    const wr_fixel *x = f->fixels;
    assert_true(x[0].mu_static_min == 0.2 && x[0].mu_static == 0.35);
    assert_true(x[0].mu_kinetic_min == 0.15 && x[0].mu_kinetic == 0.3);
    assert_true(x[1].mu_static_min == 0.1 && x[1].mu_static == 0.5);
    assert_true(x[1].mu_kinetic_min == 0.1 && x[1].mu_kinetic == 0.5);
    assert_true(x[2].mu_kinetic_min == 0.1 && x[2].mu_kinetic == 0.55);
    wr_fixture_free(f);
}

/* [a, a] is a: the same fixture, bit for bit; a point fixture has
 * min == max. */
static void point_intervals_are_points(void **state)
{
    (void)state;
    base b, p;
    make_base(&b);
    make_base(&p);
    set_interval(&b.spec.friction, 0.3, 0.3, true, 0.2, 0.2);
    p.spec.friction = (wr_friction_spec){.given = true, .static_mu = 0.3, .kinetic_given = true,
                                         .kinetic_mu = 0.2};
    wr_fixture *f = test_fixture_new(&b.spec, NULL), *g = test_fixture_new(&p.spec, NULL);
    assert_non_null(f);
    assert_non_null(g);
    assert_memory_equal(f->fixels, g->fixels, sizeof f->fixels);
    assert_true(g->fixels[0].mu_static_min == 0.3 && g->fixels[0].mu_kinetic_min == 0.2);
    wr_fixture_free(f);
    wr_fixture_free(g);
}

/* ---- the union over the box ----------------------------------------------- */

/* A random disc fixture with interval friction, kept as a spec so that
 * point-friction variants of it can be built. */
typedef struct interval_case {
    wr_fixture_spec spec;
    wr_fixel_spec fixels[WR_MAX_FIXELS];
    double lo_s[WR_MAX_FIXELS], hi_s[WR_MAX_FIXELS], lo_k[WR_MAX_FIXELS], hi_k[WR_MAX_FIXELS];
} interval_case;

static void make_case(test_rng *rng, int k, interval_case *c)
{
    memset(c, 0, sizeof *c);
    c->spec.mass = test_range(rng, 0.5, 2);
    c->spec.shape = WR_SHAPE_CIRCLE;
    c->spec.radius = 1;
    if (test_uniform(rng) < 0.5) {
        c->spec.com_given = true;
        c->spec.com[0] = test_range(rng, -0.3, 0.3);
        c->spec.com[1] = test_range(rng, -0.3, 0.3);
    }
    double angles[WR_MAX_FIXELS];
    test_spaced_angles(rng, k, 15, angles);
    for (int i = 0; i < k; i++) {
        c->fixels[i].at[0] = cos(angles[i]);
        c->fixels[i].at[1] = sin(angles[i]);
        double s1 = test_range(rng, 0, 1), s2 = test_range(rng, 0, 1);
        c->lo_s[i] = fmin(s1, s2);
        c->hi_s[i] = fmax(s1, s2);
        /* Kinetic: below static's bounds, sometimes reaching above its
         * lower bound, sometimes a point. */
        double k1 = c->lo_s[i] * test_uniform(rng);
        double k2 = k1 + (c->hi_s[i] - k1) * test_uniform(rng);
        c->lo_k[i] = k1;
        c->hi_k[i] = test_uniform(rng) < 0.2 ? k1 : k2;
        set_interval(&c->fixels[i].friction, c->lo_s[i], c->hi_s[i], true, c->lo_k[i],
                     c->hi_k[i]);
    }
    c->spec.fixel_count = (size_t)k;
    c->spec.fixels = c->fixels;
}

/* The fixture at one point of the box: per fixel (mu_s, mu_k), mu_k <= mu_s. */
static wr_fixture *point_fixture(const interval_case *c, const double (*mu)[2])
{
    interval_case p = *c;
    p.spec.fixels = p.fixels;
    for (size_t i = 0; i < c->spec.fixel_count; i++)
        p.fixels[i].friction = (wr_friction_spec){.given = true, .static_mu = mu[i][0],
                                                  .kinetic_given = true, .kinetic_mu = mu[i][1]};
    wr_error error;
    wr_fixture *f = test_fixture_new(&p.spec, &error);
    if (!f)
        fail_msg("point fixture refused: %s %s", error.field, error.reason);
    return f;
}

#define CASES 12
#define WRENCHES 60
#define SAMPLES 24

static void robust_verdicts_are_the_union_over_the_box(void **state)
{
    (void)state;
    test_rng rng = {20260417};
    int checked = 0, outside = 0, witnessed = 0, deeper = 0;
    wr_lp_env *env = test_lp_env_new();
    for (int n = 0; n < CASES; n++) {
        interval_case c;
        int k = 2 + n % 2;
        make_case(&rng, k, &c);
        wr_fixture *f = test_fixture_new(&c.spec, NULL);
        assert_non_null(f);
        wr_analysis *a = test_analysis_new(f);
        assert_non_null(a);
        /* Samples: the corners with mu_k <= mu_s, then random points. */
        wr_fixture *points[SAMPLES];
        wr_analysis *point_analyses[SAMPLES];
        int sample_count = 0;
        for (int s = 0; s < SAMPLES; s++) {
            double mu[WR_MAX_FIXELS][2];
            for (int i = 0; i < k; i++) {
                int corner = s < 4 ? s : -1;
                double ms = corner >= 0 ? (corner & 1 ? c.hi_s[i] : c.lo_s[i])
                                        : test_range(&rng, c.lo_s[i], c.hi_s[i]);
                double mk = corner >= 0 ? (corner & 2 ? c.hi_k[i] : c.lo_k[i])
                                        : test_range(&rng, c.lo_k[i], c.hi_k[i]);
                mu[i][0] = ms;
                mu[i][1] = fmin(mk, ms); /* the physical part of the box */
            }
            points[sample_count] = point_fixture(&c, (const double (*)[2])mu);
            point_analyses[sample_count] = test_analysis_new(points[sample_count]);
            sample_count++;
        }
        /* The goal set uses static upper bounds only: its margins are
         * those at the corner of every static upper bound. */
        double top[WR_MAX_FIXELS][2];
        for (int i = 0; i < k; i++) {
            top[i][0] = c.hi_s[i];
            top[i][1] = c.lo_k[i];
        }
        wr_fixture *top_fixture = point_fixture(&c, (const double (*)[2])top);
        wr_analysis *top_analysis = test_analysis_new(top_fixture);
        wr_lp_set *goal_lp, *strong_lp;
        assert_int_equal(wr_analysis_lp_sets(a, env, &goal_lp, &strong_lp), WR_OK);

        for (int w = 0; w < WRENCHES; w++) {
            double g[3];
            test_sphere(&rng, g);
            for (int set = WR_SET_GOAL; set <= WR_SET_STRONG; set++) {
                wr_answer robust;
                assert_int_equal(wr_classify(a, g, (wr_set)set, 1e-9, &robust), WR_OK);
                double least = INFINITY;
                for (int s = 0; s < sample_count; s++) {
                    wr_answer point;
                    assert_int_equal(
                        wr_classify(point_analyses[s], g, (wr_set)set, 1e-9, &point), WR_OK);
                    least = fmin(least, point.margin);
                }
                /* The union is at least as large as any member. */
                if (!(robust.margin <= least + 1e-9))
                    fail_msg("case %d wrench %d set %d: robust margin %.17g above a sample's %.17g",
                             n, w, set, robust.margin, least);
                deeper += robust.margin < least - 1e-6;
                if (set == WR_SET_GOAL) {
                    wr_answer at_top;
                    assert_int_equal(wr_classify(top_analysis, g, WR_SET_GOAL, 1e-9, &at_top),
                                     WR_OK);
                    if (fabs(at_top.margin - robust.margin) > 1e-12)
                        fail_msg("case %d: goal margin %.17g, at the static upper bounds %.17g",
                                 n, robust.margin, at_top.margin);
                }
                /* The LP method gets the same rows. */
                if (fabs(robust.margin) > 1e-6) {
                    wr_answer lp;
                    assert_int_equal(wr_classify_lp(a, goal_lp, strong_lp, g, (wr_set)set, &lp),
                                     WR_OK);
                    if ((lp.verdict == WR_VERDICT_INSIDE) != (robust.verdict == WR_VERDICT_INSIDE))
                        fail_msg("case %d wrench %d set %d: lp %d, cones %d (margin %g)", n, w,
                                 set, lp.verdict, robust.verdict, robust.margin);
                    if (lp.blocking >= 0) {
                        const wr_cone *cone = wr_analysis_cone(a, (wr_set)set, lp.blocking);
                        const char *why =
                            test_witness_violation(f, &cone->constraint, &lp.witness, g, 1e-6);
                        if (why)
                            fail_msg("case %d: lp witness: %s", n, why);
                    }
                }
                checked++;
                if (robust.blocking < 0)
                    continue;
                outside++;
                /* The witness: its friction in the intervals, its forces
                 * satisfying the letters with it, and at that friction the
                 * point fixture blocks the wrench too. */
                const wr_cone *cone = wr_analysis_cone(a, (wr_set)set, robust.blocking);
                const wr_witness *wit = &robust.witness;
                double mu[WR_MAX_FIXELS][2];
                for (int i = 0; i < k; i++) {
                    char letter = cone->constraint.letters[i];
                    double m = wit->friction[i];
                    mu[i][0] = c.hi_s[i];
                    mu[i][1] = c.lo_k[i];
                    if (strchr("sau", letter)) {
                        assert_true(isnan(m));
                    } else if (strchr("nm", letter)) {
                        assert_true(m == c.hi_s[i]);
                    } else {
                        assert_true(m >= c.lo_k[i] && m <= c.hi_k[i]);
                        mu[i][1] = m;
                    }
                }
                double projection[3];
                double scaled[3];
                double length = wr_fixture_unit_wrench(f, g, scaled);
                wr_cone_signed_distance(cone, scaled, projection);
                double target[3];
                wr_fixture_unscale_wrench(f, projection, target);
                for (int j = 0; j < 3; j++)
                    target[j] *= length;
                const char *why = test_witness_violation(f, &cone->constraint, wit, target, 1e-6);
                if (why)
                    fail_msg("case %d wrench %d set %d %s: %s", n, w, set,
                             cone->constraint.letters, why);
                if (robust.verdict == WR_VERDICT_OUTSIDE) {
                    wr_fixture *at = point_fixture(&c, (const double (*)[2])mu);
                    wr_analysis *at_analysis = test_analysis_new(at);
                    wr_answer point;
                    assert_int_equal(wr_classify(at_analysis, g, (wr_set)set, 1e-9, &point),
                                     WR_OK);
                    if (point.margin > 1e-7)
                        fail_msg("case %d wrench %d set %d: at the witness's friction the "
                                 "margin is %.17g, robust %.17g",
                                 n, w, set, point.margin, robust.margin);
                    witnessed++;
                    wr_analysis_free(at_analysis);
                    wr_fixture_free(at);
                }
            }
        }
        wr_lp_set_free(goal_lp);
        wr_lp_set_free(strong_lp);
        wr_analysis_free(top_analysis);
        wr_fixture_free(top_fixture);
        for (int s = 0; s < sample_count; s++) {
            wr_analysis_free(point_analyses[s]);
            wr_fixture_free(points[s]);
        }
        wr_analysis_free(a);
        wr_fixture_free(f);
    }
    wr_lp_env_free(env);
    print_message("%d answers, %d not inside, %d witnesses re-checked at their friction, "
                  "%d margins below every sample's\n",
                  checked, outside, witnessed, deeper);
    assert_true(witnessed > 50);
}

/* An l letter with a kinetic interval has the two edges; with the interval
 * shrunk to a point, the one edge of today. */
static void sliding_cones_span_both_edges(void **state)
{
    (void)state;
    /* The disc in the corner, static [0.3, 0.6], kinetic [0.1, 0.5]. */
    wr_fixel_spec fixels[2];
    memset(fixels, 0, sizeof fixels);
    fixels[0].at[0] = -1;
    fixels[1].at[1] = -1;
    wr_fixture_spec spec;
    memset(&spec, 0, sizeof spec);
    spec.mass = 1;
    spec.inertia_given = true;
    spec.inertia = 0.5;
    spec.shape = WR_SHAPE_CIRCLE;
    spec.radius = 1;
    set_interval(&spec.friction, 0.3, 0.6, true, 0.1, 0.5);
    spec.fixel_count = 2;
    spec.fixels = fixels;
    wr_fixture *f = test_fixture_new(&spec, NULL);
    assert_non_null(f);
    wr_constraint c;
    assert_int_equal(wr_constraint_parse("ls", 2, &c, NULL), WR_OK);
    wr_cone cone;
    assert_int_equal(wr_cone_build(&cone, f, &c), WR_OK);
    int edges = 0;
    for (int j = 0; j < cone.generator_count; j++)
        if (cone.origins[j].fixel == 0) {
            double ratio = cone.origins[j].tangent_force / cone.origins[j].normal_force;
            assert_true(fabs(ratio + 0.5) < 1e-15 || fabs(ratio + 0.1) < 1e-15);
            edges++;
        }
    assert_int_equal(edges, 2);
    wr_cone_release(&cone);
    wr_fixture_free(f);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(invalid_intervals_are_named),
        cmocka_unit_test(valid_intervals_are_kept),
        cmocka_unit_test(point_intervals_are_points),
        cmocka_unit_test(sliding_cones_span_both_edges),
        cmocka_unit_test(robust_verdicts_are_the_union_over_the_box),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
