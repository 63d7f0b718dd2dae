/* test_locate.c -- locating accuracy (lib/wr_locate.h) against properties
 * that hold whatever the code: a rigid motion of the whole fixture rotates
 * the translation rows of G^-1 and the features' vectors with it and leaves
 * every length, angle and condition number as it was; scaling the fixture
 * and its tolerances by s scales every length by s and leaves dtheta; the
 * exact pose differs from the linear one by the tolerance's second order
 * (a tenth of the tolerance, a hundredth of the difference); and each bad
 * input is refused at its field. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>
#include <stdio.h>

#include "test_util.h"
#include "wr_locate.h"

/* The chamfered plate, its locators under it and on its left side, moved
 * by (angle, shift) and scaled by `scale`. */
static wr_fixture *plate(double angle, const double shift[2], double scale, double out_features[2][2])
{
    static const double base[5][2] = {{0, 0}, {4, 0}, {4, 1}, {3, 2}, {0, 2}};
    static const double at[3][2] = {{1, 0}, {3, 0}, {0, 0.5}};
    static const double feature[2][2] = {{3.5, 1.5}, {0.5, 1.8}};
    double c = cos(angle), s = sin(angle);
    double vertices[5][2];
    wr_fixel_spec fixels[3];
    memset(fixels, 0, sizeof fixels);
    for (int i = 0; i < 5; i++) {
        vertices[i][0] = scale * (c * base[i][0] - s * base[i][1]) + shift[0];
        vertices[i][1] = scale * (s * base[i][0] + c * base[i][1]) + shift[1];
    }
    for (int i = 0; i < 3; i++) {
        fixels[i].at[0] = scale * (c * at[i][0] - s * at[i][1]) + shift[0];
        fixels[i].at[1] = scale * (s * at[i][0] + c * at[i][1]) + shift[1];
    }
    for (int i = 0; i < 2; i++) {
        out_features[i][0] = scale * (c * feature[i][0] - s * feature[i][1]) + shift[0];
        out_features[i][1] = scale * (s * feature[i][0] + c * feature[i][1]) + shift[1];
    }
    wr_fixture_spec spec;
    memset(&spec, 0, sizeof spec);
    spec.mass = 2;
    spec.shape = WR_SHAPE_POLYGON;
    spec.vertex_count = 5;
    spec.vertices = (const double(*)[2])vertices;
    spec.friction.given = true;
    spec.friction.static_mu = 0.1;
    spec.fixel_count = 3;
    spec.fixels = fixels;
    wr_error error;
    wr_fixture *f = test_fixture_new(&spec, &error);
    assert_non_null(f);
    return f;
}

static void locate(const wr_fixture *f, const double t[3], double features[2][2],
                   wr_locating *out, wr_locate_feature ft[2])
{
    memset(ft, 0, 2 * sizeof ft[0]);
    for (int i = 0; i < 2; i++)
        memcpy(ft[i].at, features[i], sizeof ft[i].at);
    wr_error error;
    assert_int_equal(wr_locate(f, t, 3, ft, 2, out, &error), WR_OK);
    assert_true(out->deterministic);
}

static void test_rigid_motion_and_scale(void **state)
{
    (void)state;
    const double t[3] = {0.02, 0.01, 0.03}, zero[2] = {0, 0};
    double at[2][2];
    wr_fixture *f = plate(0, zero, 1, at);
    wr_locating a;
    wr_locate_feature fa[2];
    locate(f, t, at, &a, fa);
    wr_fixture_free(f);
    test_rng rng = {0x10ca7e};
    for (int trial = 0; trial < 20; trial++) {
        double angle = test_range(&rng, -TEST_PI, TEST_PI);
        double shift[2] = {test_range(&rng, -50, 50), test_range(&rng, -50, 50)};
        double scale = trial % 2 ? 1 : test_range(&rng, 0.01, 100);
        f = plate(angle, shift, scale, at);
        double ts[3] = {t[0] * scale, t[1] * scale, t[2] * scale};
        wr_locating b;
        wr_locate_feature fb[2];
        locate(f, ts, at, &b, fb);
        assert_true(fabs(b.condition - a.condition) <= 1e-12 * a.condition);
        double c = cos(angle), s = sin(angle);
        for (int i = 0; i < 3; i++) {
            /* Rows dx, dy turn with the fixture; per unit e they scale by 1. */
            double dx = c * a.sensitivity[0][i] - s * a.sensitivity[1][i];
            double dy = s * a.sensitivity[0][i] + c * a.sensitivity[1][i];
            assert_true(fabs(b.sensitivity[0][i] - dx) <= 1e-12);
            assert_true(fabs(b.sensitivity[1][i] - dy) <= 1e-12);
            assert_true(fabs(b.sensitivity[2][i] * scale - a.sensitivity[2][i]) <= 1e-12);
        }
        assert_true(fabs(b.pose_exact[2] - a.pose_exact[2]) <= 1e-10 * a.pose_exact[2]);
        for (int j = 0; j < 2; j++) {
            assert_true(fabs(fb[j].linear_length - scale * fa[j].linear_length) <=
                        1e-11 * scale * fa[j].linear_length);
            assert_true(fabs(fb[j].exact_length - scale * fa[j].exact_length) <=
                        1e-9 * scale * fa[j].exact_length);
            assert_true(fabs(fb[j].axes[0] - scale * fa[j].axes[0]) <= 1e-11 * scale * fa[j].axes[0]);
            double turned = fa[j].angle_deg + angle * 180 / TEST_PI;
            double off = remainder(fb[j].angle_deg - turned, 180.0);
            assert_true(fabs(off) <= 1e-8);
        }
        wr_fixture_free(f);
    }
}

static void test_exact_is_linear_to_second_order(void **state)
{
    (void)state;
    const double zero[2] = {0, 0};
    double at[2][2];
    wr_fixture *f = plate(0.3, zero, 1, at);
    double gap[2];
    for (int n = 0; n < 2; n++) {
        double t = n == 0 ? 0.05 : 0.005;
        const double ts[3] = {t, t, t};
        wr_locating r;
        wr_locate_feature ft[2];
        locate(f, ts, at, &r, ft);
        gap[n] = fabs(ft[0].exact_length - ft[0].linear_length);
        assert_true(gap[n] > 0);
    }
    /* A tenth of the tolerance, a hundredth of the gap (within 15 %). */
    assert_true(fabs(gap[1] / gap[0] - 0.01) <= 0.0015);
    wr_fixture_free(f);
}

static void test_refusals(void **state)
{
    (void)state;
    const double zero[2] = {0, 0};
    double at[2][2];
    wr_fixture *f = plate(0, zero, 1, at);
    wr_locating r;
    wr_locate_feature ft[1] = {{.at = {1, 1}}};
    wr_error error;
    const double bad_t[3] = {0.1, -0.1, 0};
    assert_int_equal(wr_locate(f, bad_t, 3, ft, 1, &r, &error), WR_INVALID);
    assert_string_equal(error.field, "tolerance[1]");
    const double nan_t[3] = {0.1, 0, NAN};
    assert_int_equal(wr_locate(f, nan_t, 3, ft, 1, &r, &error), WR_INVALID);
    assert_string_equal(error.field, "tolerance[2]");
    const double t[3] = {0.1, 0.1, 0.1};
    assert_int_equal(wr_locate(f, t, 0, ft, 1, &r, &error), WR_INVALID);
    assert_string_equal(error.field, "sigma_ratio");
    ft[0].at[0] = 10; /* 6 beyond x = 4; the size is sqrt(20), its tenth 0.447 */
    assert_int_equal(wr_locate(f, t, 3, ft, 1, &r, &error), WR_INVALID);
    assert_string_equal(error.field, "features[0].at");
    assert_non_null(strstr(error.reason, "lies 6 outside"));
    ft[0].at[0] = NAN;
    assert_int_equal(wr_locate(f, t, 3, ft, 1, &r, &error), WR_INVALID);
    assert_string_equal(error.field, "features[0].at");
    wr_fixture_free(f);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_rigid_motion_and_scale),
        cmocka_unit_test(test_exact_is_linear_to_second_order),
        cmocka_unit_test(test_refusals),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
