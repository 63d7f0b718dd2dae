/* test_support_margin.c -- the disturbance margin on a base plate
 * (wr_supports_margin, docs/MODEL.md section 11): two closed forms by the
 * power argument, and every bracket checked against wr_supports_strong's
 * own verdicts on disturbances sampled around the bias. */
#include "test_util.h"

#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>

#include <cmocka.h>

#define G 9.81

static wr_supports *supports_new(const wr_fixture *f, const double (*points)[2], double mu,
                                 const wr_down_spec *down, int down_count)
{
    wr_support_spec spec;
    memset(&spec, 0, sizeof spec);
    spec.point_count = 3;
    spec.points = points;
    spec.friction.given = true;
    spec.friction.static_mu = mu;
    spec.g = G;
    spec.down_count = (size_t)down_count;
    spec.down = down;
    wr_supports *s = NULL;
    wr_error error;
    assert_int_equal(wr_supports_new(f, &spec, &s, &error), WR_OK);
    return s;
}

static const double tri[3][2] = {{0, 0.2}, {-0.17320508075688773, -0.1}, {0.17320508075688773, -0.1}};
static const double buttons[3][2] = {{1, 0.5}, {3, 0.5}, {2, 1.7}};

static double scaled_length(const wr_fixture *f, const double w[3])
{
    return hypot(hypot(w[0], w[1]), w[2] / f->gyration_radius);
}

/* A closed form's check: the bias held (expected > 0) or moving, the
 * bracket holding `expected` and converged onto it within 1e-6, the worst
 * direction along `worst` (a unit scaled wrench; either sign when
 * `either`). */
static void check_closed_form(const char *what, const wr_analysis *a, const wr_supports *s,
                              wr_lp_env *env, const double bias[3], double expected,
                              const double worst[3], bool either)
{
    wr_support_margin m;
    assert_int_equal(wr_supports_margin(a, s, env, bias, NULL, &m), WR_OK);
    printf("%s: margin %.9f [%.9f, %.9f] (closed form %.9f), %s, %d cells, %d LPs, "
           "worst (%.6f, %.6f, %.6f)\n",
           what, m.margin, m.bracket[0], m.bracket[1], expected,
           m.converged ? "converged" : "not converged", m.cells, m.solves, m.worst_direction[0],
           m.worst_direction[1], m.worst_direction[2]);
    assert_true(m.bounded && m.converged);
    assert_true(expected > 0 ? m.held && !m.moves : m.moves && !m.held);
    double slack = 1e-9 * fabs(expected);
    assert_true(m.bracket[0] <= expected + slack && m.bracket[1] >= expected - slack);
    assert_true(fabs(m.margin - expected) < 1e-6 * fabs(expected));
    for (int k = 0; k < 3; k++)
        assert_true(fabs(m.worst_direction[k] - worst[k]) < 1e-4 ||
                    (either && fabs(m.worst_direction[k] + worst[k]) < 1e-4));
}

static bool held(const wr_analysis *a, const wr_supports *s, wr_lp_env *env, const double g[3])
{
    wr_support_strong strong;
    assert_int_equal(wr_supports_strong(a, s, env, g, WR_DEFAULT_TOLERANCE, NULL, &strong), WR_OK);
    return strong.verdict == WR_VERDICT_INSIDE;
}

static bool moves(const wr_analysis *a, const wr_supports *s, wr_lp_env *env, const double g[3])
{
    wr_support_strong strong;
    assert_int_equal(wr_supports_strong(a, s, env, g, WR_DEFAULT_TOLERANCE, NULL, &strong), WR_OK);
    return strong.verdict == WR_VERDICT_OUTSIDE;
}

/* The disc in the corner (MODEL.md section 7.1) with frictionless walls on
 * three buttons 0.2 from its centre, each carrying W / 3, mu_B; a bias
 * b = (-F, -F, 0) pressing it into the corner.
 *
 * Power: for a motion of unit scaled twist v = (a_x, a_y, rho alpha), the
 * wrench g that makes it has g . v = t (v.v) + (the walls' power, 0: they
 * are frictionless and a seated wall's normal acceleration is 0 or its
 * force is) + mu_B sum N_i |a_i|, so a disturbance d with b + d moving
 * the disc has |d| >= mu_B sum N_i |a_i| - b . v.  The seated disc may
 * only leave the walls: a_x, a_y >= 0, alpha any, so -b . v = F (a_x +
 * a_y) >= F |a|.  And sum_i |a + alpha x r_i| >= |sum| = 3 |a|, and >=
 * sum_i (a + alpha x r_i) . t_i = 0.6 |alpha| (t_i the buttons' unit
 * tangents, summing to 0), so with N_i = W / 3, s = |a| and
 * rho |alpha| = sqrt(1 - s^2) (rho^2 = 0.5):
 *
 *     |d| >= mu_B W max(s, c sqrt(1 - s^2)) + F s
 *         >= mu_B W c sqrt(1 - s^2) + F s,        c = 0.2 / rho = 0.2 sqrt 2,
 *
 * concave in s, so at least its smaller end: mu_B W c (s = 0) when F >=
 * mu_B W c.  The pure rotation attains it: the buttons slide along their
 * tangents, their friction sums to no force and a torque 0.2 mu_B W, the
 * walls take b's forces, so b + (0, 0, 0.2 mu_B W) is consistent.  The
 * margin is 0.2 sqrt(2) mu_B W along the torque axis. */
static void test_disc_rotation(void **state)
{
    (void)state;
    wr_lp_env *env = test_lp_env_new();
    wr_fixture *f = test_disc_corner(0);
    wr_analysis *a = test_analysis_new(f);
    double mu_b = 0.3;
    wr_supports *s = supports_new(f, tri, mu_b, NULL, 0);
    double expected = 0.2 * sqrt(2) * mu_b * G;
    const double forces[2] = {1, 5};
    /* Along the torque axis: (0, 0, rho) has unit scaled length. */
    const double worst[3] = {0, 0, sqrt(0.5)};
    for (int k = 0; k < 2; k++) {
        double bias[3] = {-forces[k], -forces[k], 0};
        char what[64];
        snprintf(what, sizeof what, "disc, bias -%g (1, 1)", forces[k]);
        check_closed_form(what, a, s, env, bias, expected, worst, true);
    }
    wr_supports_free(s);
    wr_analysis_free(a);
    wr_fixture_free(f);
    wr_lp_env_free(env);
}

/* The 3-2-1 plate with frictionless fixels on buttons (1, 0.5), (3, 0.5),
 * (2, 1.7), mu_B = 0.2, a down clamp D = 20 at the centre of mass (W = m g
 * + D, the centre of pressure at the centre of mass, so sum N_i r_i = 0).
 * The bias: a cutting force F_c along +x and a clamp P pressing the plate
 * down onto fixels 1 and 2, both through the centre of mass:
 * b = (F_c, -P, 0).
 *
 * The seated plate may move only with a_x >= 0 (fixel 3 at (0, 1)) and
 * a_y >= |alpha| (fixels 1 and 2).  As for the disc, a moving b + d needs
 * |d| >= mu_B sum N_i |a_i| - b . v >= mu_B W |a| - F_c a_x + P a_y >=
 * (mu_B W - F_c) |a| + P a_y, with |a|^2 = 1 - rho^2 alpha^2 >= 1 -
 * rho^2 a_y^2, so 1 - |a| <= rho^2 a_y^2 <= rho^2 a_y: when P >= (mu_B W -
 * F_c) rho^2 (rho^2 = 5/3) the bound is at least mu_B W - F_c, which the
 * translation along +x attains (fixels 1 and 2 take P, half each, the
 * buttons' friction is mu_B W along -x): the margin is mu_B W - F_c along
 * +x.
 *
 * Past it, F_c > mu_B W moves the plate: the same bound shows
 * (F', -P, 0) held for every F' < mu_B W, so the depth is at most
 * F_c - mu_B W (along -x); and b lies in the translation's own set
 * (mu_B W, 0, 0) + cone{e_x, fixel 1's and fixel 2's generators
 * (0, -1, +-1/rho)}, whose face x = 0 is F_c - mu_B W away and whose other
 * faces P / sqrt(1 + rho^2) away: the depth is exactly F_c - mu_B W. */
static void test_plate_cutting(void **state)
{
    (void)state;
    wr_lp_env *env = test_lp_env_new();
    wr_fixture *f = test_plate_321_friction(0, 0);
    wr_analysis *a = test_analysis_new(f);
    double mu_b = 0.2;
    wr_down_spec down = {{2, 1}, 20};
    wr_supports *s = supports_new(f, buttons, mu_b, &down, 1);
    double capacity = mu_b * (2 * G + 20);
    const double cutting[3] = {3, 0, 12};
    for (int k = 0; k < 3; k++) {
        double bias[3] = {cutting[k], -20, 0};
        double expected = capacity - cutting[k];
        const double worst[3] = {expected > 0 ? 1 : -1, 0, 0};
        char what[64];
        snprintf(what, sizeof what, "3-2-1 plate, cutting %g", cutting[k]);
        check_closed_form(what, a, s, env, bias, expected, worst, false);
    }
    wr_supports_free(s);
    wr_analysis_free(a);
    wr_fixture_free(f);
    wr_lp_env_free(env);
}

/* Every bracket against wr_supports_strong: of a held bias, disturbances
 * of scaled length just below lo, sampled in many directions, are never
 * proved to move it (most are proved held; the classifier may leave one
 * near a sticking direction undecided), and b + hi (1 + 1e-3)
 * worst_direction is never proved held; of a moving bias, disturbances
 * just below its certified depth are never proved held, and b + |margin|
 * worst_direction is. */
static void test_sampled(void **state)
{
    (void)state;
    wr_lp_env *env = test_lp_env_new();
    test_rng rng = {12345};
    struct {
        wr_fixture *f;
        const double (*points)[2];
        double mu_b;
        double bias[3];
    } cases[] = {
        {test_disc_corner(0.5), tri, 0.3, {-3, -3, 0}},
        {test_disc_corner(0.5), tri, 0.3, {-2, -0.5, 0.4}},
        {test_disc_corner(0.5), tri, 0.3, {0, 0, 0}},
        {test_disc_corner(0.5), tri, 0.3, {2, -1, 0}},
        {test_plate_321(), buttons, 0.2, {0, 0, 0}},
        {test_plate_321(), buttons, 0.2, {1, -4, 0.5}},
        {test_plate_321(), buttons, 0.2, {-2, -3, -1}},
        {test_plate_321(), buttons, 0.2, {6, -1, 0}},
    };
    int samples = 0, proved = 0;
    for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++) {
        wr_fixture *f = cases[c].f;
        wr_analysis *a = test_analysis_new(f);
        wr_supports *s = supports_new(f, cases[c].points, cases[c].mu_b, NULL, 0);
        const double *b = cases[c].bias;
        wr_support_margin m;
        assert_int_equal(wr_supports_margin(a, s, env, b, NULL, &m), WR_OK);
        printf("case %zu: margin %.9f [%.9f, %.9f], %s, %s, %d cells, %d LPs\n", c, m.margin,
               m.bracket[0], m.bracket[1], m.held ? "held" : m.moves ? "moves" : "undecided",
               m.converged ? "converged" : "not converged", m.cells, m.solves);
        assert_true(m.bounded);
        assert_true(m.bracket[0] <= m.bracket[1]);
        assert_true(fabs(scaled_length(f, m.worst_direction) - 1) < 1e-9);
        /* The sign agrees with the holding classifier. */
        assert_true(m.held ? held(a, s, env, b) : m.moves ? moves(a, s, env, b) : true);
        double inner = m.held ? m.bracket[0] : -m.bracket[1];
        double outer = m.held ? m.bracket[1] : -m.bracket[0];
        for (int k = 0; k < 48 && inner > 0; k++) {
            double u[3], g[3];
            test_sphere(&rng, u);
            u[2] *= f->gyration_radius; /* a unit scaled direction */
            for (int j = 0; j < 3; j++)
                g[j] = b[j] + inner * (1 - 1e-3) * u[j];
            if (m.held) {
                assert_false(moves(a, s, env, g));
                proved += held(a, s, env, g);
            } else {
                assert_false(held(a, s, env, g));
                proved += moves(a, s, env, g);
            }
            samples++;
        }
        double g[3];
        for (int j = 0; j < 3; j++)
            g[j] = b[j] + outer * (m.held ? 1 + 1e-3 : 1) * m.worst_direction[j];
        assert_true(m.held ? !held(a, s, env, g) : held(a, s, env, g));
        wr_supports_free(s);
        wr_analysis_free(a);
        wr_fixture_free(f);
    }
    printf("%d disturbances sampled inside the brackets, none on the wrong side, %d proved on "
           "the bias's side\n",
           samples, proved);
    wr_lp_env_free(env);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_disc_rotation),
        cmocka_unit_test(test_plate_cutting),
        cmocka_unit_test(test_sampled),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
