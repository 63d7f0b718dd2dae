/* test_support_sweep_b.c -- push regions on the plate against the
 * supports' mu_B (lib/wr_support.h, wr_supports_push_regions with
 * wr_supports_with_friction), the question friction.sweep over the
 * supports asks at each mu_B, on a closed form.
 *
 * The disc in the corner (fixel friction 0.5) with the regular octagon
 * circumscribing the unit circle as its outline (edges tangent at 0, 45,
 * ... degrees; the same fixels, mass, inertia and centre, hence the same
 * cones) on three buttons, W = m g.  Every excluded goal cone holds the
 * torque axis (docs/MODEL.md section 11), so a force F u seats iff it is
 * farther than mu_B W from the complement of the goal wedge (206.565 to
 * 243.435 degrees).  Only the edge tangent at 45 degrees pushes inside the
 * wedge (along 225 degrees, atan(1/3) from both its edges): its whole
 * length seats while F / sqrt(10) > mu_B W, and no other edge ever does.
 * mu_B = 0 (nothing to overcome) is asked too. */
#include "test_util.h"

#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>

#include <cmocka.h>

#define G 9.81

static wr_fixture *octagon(void)
{
    double vertices[8][2];
    const double r = 1 / cos(TEST_PI / 8);
    for (int k = 0; k < 8; k++) {
        vertices[k][0] = r * cos(TEST_PI / 8 + k * TEST_PI / 4);
        vertices[k][1] = r * sin(TEST_PI / 8 + k * TEST_PI / 4);
    }
    wr_fixel_spec fixels[2];
    memset(fixels, 0, sizeof fixels);
    fixels[0].at[0] = -1;
    fixels[1].at[1] = -1;
    wr_fixture_spec spec;
    memset(&spec, 0, sizeof spec);
    spec.mass = 1;
    spec.inertia_given = true;
    spec.inertia = 0.5;
    spec.com_given = true;
    spec.shape = WR_SHAPE_POLYGON;
    spec.vertex_count = 8;
    spec.vertices = (const double (*)[2])vertices;
    spec.friction.given = true;
    spec.friction.static_mu = 0.5;
    spec.fixel_count = 2;
    spec.fixels = fixels;
    return test_fixture_new(&spec, NULL);
}

static void test_octagon_regions_against_mu(void **state)
{
    (void)state;
    static const double tri[3][2] = {
        {0, 0.2}, {-0.17320508075688773, -0.1}, {0.17320508075688773, -0.1}};
    wr_fixture *f = octagon();
    assert_non_null(f);
    wr_analysis *a = test_analysis_new(f);
    wr_lp_env *env = test_lp_env_new();
    wr_support_spec spec;
    memset(&spec, 0, sizeof spec);
    spec.point_count = 3;
    spec.points = tri;
    spec.friction.given = true;
    spec.friction.static_mu = 0.3;
    spec.g = G;
    wr_supports *s = NULL;
    wr_error error;
    assert_int_equal(wr_supports_new(f, &spec, &s, &error), WR_OK);
    const double force = 30, critical = force / (G * sqrt(10));
    const double mus[] = {0, 0.5, critical * (1 - 1e-6), critical * (1 + 1e-6), 1.5};
    const double zero[1][3] = {{0, 0, 0}};
    for (size_t m = 0; m < sizeof mus / sizeof mus[0]; m++) {
        wr_supports at_mu;
        wr_supports_with_friction(s, mus[m], &at_mu);
        for (int edge = 0; edge < 8; edge++) {
            wr_regions regions = {0};
            assert_int_equal(wr_supports_push_regions(a, &at_mu, env, force, zero, 1, edge,
                                                      &regions),
                             WR_OK);
            /* Edge 0 runs from 22.5 to 67.5 degrees: tangent at 45. */
            if (edge == 0 && mus[m] < critical) {
                assert_int_equal(regions.count, 1);
                assert_true(regions.items[0].t0 == 0 && regions.items[0].t1 == 1);
            } else {
                assert_int_equal(regions.count, 0);
            }
            wr_regions_release(&regions);
        }
    }
    printf("octagon, push of %g: its 45-degree edge seats below mu_B = %.9f, none above\n",
           force, critical);
    wr_supports_free(s);
    wr_lp_env_free(env);
    wr_analysis_free(a);
    wr_fixture_free(f);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_octagon_regions_against_mu),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
