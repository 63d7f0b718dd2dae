/* test_tolerance.c -- robust answers over a geometric tolerance
 * (lib/wr_tolerance.h) against what is derived here without it:
 *
 * - sampling: every fixture of the set is built here from its own
 *   geometry (a contact moved along its edge or round its circle, its
 *   normal the boundary's there, tilted) and classified nominally; no
 *   sample may be other than inside where the robust answer is inside, and
 *   each outside's witness, rebuilt here from its points and normals,
 *   must be outside;
 * - a closed form: on the frictionless 3-2-1 plate (centre (2, 1)) a push
 *   f = (-a, -b) with torque tau seats the part exactly when, about each
 *   point P_j where a bottom locator's normal meets the left one's, the
 *   moment tau + (c - P_j) x f keeps the other bottom locator pressed:
 *   tau + b (x_2 - 2) + a (1 - y_3) > 0 and tau - b (2 - x_1) + a (1 - y_3)
 *   < 0.  Nominally (x = 1, 3; y_3 = 1) that is |tau| < b; with every
 *   contact free to move T along its edge the worst case is
 *   |tau| < b (1 - T) - a T;
 * - each bad tolerance refused at its field. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>
#include <stdio.h>

#include "test_util.h"
#include "wr_tolerance.h"

#define DEG (TEST_PI / 180)

/* The 3-2-1 plate [0, 4] x [0, 2]: locators under it at x = 1 and 3, one
 * on its left side at y = 1. */
static const double PLATE[4][2] = {{0, 0}, {4, 0}, {4, 2}, {0, 2}};
static const double PLATE_AT[3][2] = {{1, 0}, {3, 0}, {0, 1}};
/* Along the boundary, counter-clockwise, and the inward normal: the
 * bottom edge runs +x with normal +y, the left edge runs -y with normal +x. */
static const double PLATE_RUN[3][2] = {{1, 0}, {1, 0}, {0, -1}};
static const double PLATE_NORMAL[3][2] = {{0, 1}, {0, 1}, {1, 0}};

/* The outline plate() builds on: the rectangle, or the chamfered plate
 * (its corner (4, 2) cut from (4, 1) to (3, 2)); the fixels' edges are the
 * same on both. */
static const double CHAMFERED[5][2] = {{0, 0}, {4, 0}, {4, 1}, {3, 2}, {0, 2}};
static const double (*plate_vertices)[2] = PLATE;
static size_t plate_vertex_count = 4;

static wr_fixture *plate(double mu, const double at[3][2], const double normal[3][2])
{
    wr_fixel_spec fixels[3];
    memset(fixels, 0, sizeof fixels);
    for (int i = 0; i < 3; i++) {
        fixels[i].at[0] = at[i][0];
        fixels[i].at[1] = at[i][1];
        if (normal) {
            fixels[i].normal_given = true;
            fixels[i].normal[0] = normal[i][0];
            fixels[i].normal[1] = normal[i][1];
        }
    }
    wr_fixture_spec spec;
    memset(&spec, 0, sizeof spec);
    spec.mass = 1;
    spec.shape = WR_SHAPE_POLYGON;
    spec.vertex_count = plate_vertex_count;
    spec.vertices = plate_vertices;
    spec.friction.given = true;
    spec.friction.static_mu = mu;
    spec.fixel_count = 3;
    spec.fixels = fixels;
    wr_error error;
    return test_fixture_new(&spec, &error);
}

static void set_tolerance(wr_fixture *f, double position, double angle)
{
    wr_tolerance t = {true, position, angle};
    wr_error error;
    assert_int_equal(wr_fixture_set_tolerance(f, &t, &error), WR_OK);
}

static wr_verdict nominal_verdict(const wr_fixture *f, const double w[3], wr_set set)
{
    wr_analysis *a = test_analysis_new(f);
    wr_answer answer;
    assert_int_equal(wr_classify(a, w, set, WR_DEFAULT_TOLERANCE, &answer), WR_OK);
    wr_analysis_free(a);
    return answer.verdict;
}

/* A fixture of the plate's set, built from its own geometry: s[i] along
 * the edge, the normal tilted by tilt[i]. */
static wr_fixture *plate_sample(double mu, const double s[3], const double tilt[3])
{
    double at[3][2], normal[3][2];
    for (int i = 0; i < 3; i++) {
        at[i][0] = PLATE_AT[i][0] + s[i] * PLATE_RUN[i][0];
        at[i][1] = PLATE_AT[i][1] + s[i] * PLATE_RUN[i][1];
        double c = cos(tilt[i]), sn = sin(tilt[i]);
        normal[i][0] = c * PLATE_NORMAL[i][0] - sn * PLATE_NORMAL[i][1];
        normal[i][1] = sn * PLATE_NORMAL[i][0] + c * PLATE_NORMAL[i][1];
    }
    return plate(mu, at, normal);
}

/* A perturbation drawn from the set: each coordinate at an end of its
 * range half the time (where worst cases live), uniform otherwise. */
static void draw(test_rng *rng, double position, double angle, double s[3], double tilt[3])
{
    for (int i = 0; i < 3; i++) {
        double u = test_uniform(rng), v = test_uniform(rng);
        s[i] = u < 0.25 ? -position : u < 0.5 ? position : test_range(rng, -position, position);
        double a = angle * DEG;
        tilt[i] = v < 0.25 ? -a : v < 0.5 ? a : test_range(rng, -a, a);
    }
}

/* The witness: each point on its fixel's edge within T of nominal, each
 * normal within A of the boundary's; rebuilt from them, the fixture's
 * answer is outside. */
static void check_witness(double mu, double position, double tol_angle,
                          const wr_robust_answer *r, const double w[3], wr_set set)
{
    assert_true(r->has_perturbation);
    double s[3], tilt[3];
    for (int i = 0; i < 3; i++) {
        const double *p = r->points[i], *n = r->normals[i];
        double d[2] = {p[0] - PLATE_AT[i][0], p[1] - PLATE_AT[i][1]};
        s[i] = d[0] * PLATE_RUN[i][0] + d[1] * PLATE_RUN[i][1];
        /* on the edge: no motion across it */
        assert_true(fabs(d[0] * PLATE_NORMAL[i][0] + d[1] * PLATE_NORMAL[i][1]) < 1e-12);
        const double *boundary_normal = PLATE_NORMAL[i];
        assert_true(fabs(s[i]) <= position * (1 + 1e-12));
        tilt[i] = atan2(boundary_normal[0] * n[1] - boundary_normal[1] * n[0],
                        boundary_normal[0] * n[0] + boundary_normal[1] * n[1]);
        assert_true(fabs(tilt[i]) <= tol_angle * DEG * (1 + 1e-9) + 1e-12);
    }
    wr_fixture *g = plate_sample(mu, s, tilt);
    assert_non_null(g);
    assert_int_equal(nominal_verdict(g, w, set), WR_VERDICT_OUTSIDE);
    wr_fixture_free(g);
}

static void sample_test(double mu, double position, double angle, int wrenches, int samples,
                        uint64_t seed, int last_set, int counts[3])
{
    wr_fixture *f = plate(mu, PLATE_AT, NULL);
    assert_non_null(f);
    set_tolerance(f, position, angle);
    wr_analysis *a = test_analysis_new(f);
    wr_robust *rb;
    assert_int_equal(wr_robust_new(a, 0, &rb), WR_OK);
    test_rng rng = {seed};
    /* Wrenches nominally inside, most of them, since only those can be
     * robustly inside; the rest drawn from the whole sphere. */
    for (int n = 0; n < wrenches; n++) {
        double w[3];
        for (int tries = 0; tries < 10000; tries++) {
            test_sphere(&rng, w);
            if (n % 4 == 0 ||
                nominal_verdict(f, w, (wr_set)(n % (last_set + 1))) == WR_VERDICT_INSIDE)
                break;
        }
        for (int set = WR_SET_GOAL; set <= last_set; set++) {
            wr_robust_answer r;
            assert_int_equal(wr_robust_classify(rb, w, (wr_set)set, WR_DEFAULT_TOLERANCE, &r),
                             WR_OK);
            counts[r.answer.verdict]++;
            if (r.answer.verdict == WR_VERDICT_OUTSIDE) {
                check_witness(mu, position, angle, &r, w, (wr_set)set);
                continue;
            }
            if (r.answer.verdict != WR_VERDICT_INSIDE)
                continue;
            for (int k = 0; k < samples; k++) {
                double s[3], tilt[3];
                draw(&rng, position, angle, s, tilt);
                wr_fixture *g = plate_sample(mu, s, tilt);
                assert_non_null(g);
                if (nominal_verdict(g, w, (wr_set)set) != WR_VERDICT_INSIDE) {
                    print_error("inside contradicted: wrench (%g, %g, %g) set %d sample "
                                "s (%g %g %g) tilt (%g %g %g)\n",
                                w[0], w[1], w[2], set, s[0], s[1], s[2], tilt[0], tilt[1],
                                tilt[2]);
                    fail();
                }
                wr_fixture_free(g);
            }
        }
    }
    wr_robust_free(rb);
    wr_analysis_free(a);
    wr_fixture_free(f);
}

static void test_sampling_plate(void **state)
{
    (void)state;
    int counts[3] = {0, 0, 0};
    sample_test(0.3, 0.02, 1, 24, 30, 0x1234567ULL, WR_SET_BOTH, counts);
    print_message("plate: inside %d, boundary %d, outside %d\n", counts[0], counts[1],
                  counts[2]);
    assert_true(counts[WR_VERDICT_INSIDE] > 10);
    assert_true(counts[WR_VERDICT_OUTSIDE] > 10);
    assert_true(counts[WR_VERDICT_BOUNDARY] * 10 < counts[0] + counts[1] + counts[2]);
}

/* The frictionless plate with every contact free to move T along its
 * edge, its analysis and robust questions. */
typedef struct robust_plate {
    wr_fixture *f;
    wr_analysis *a;
    wr_robust *rb;
} robust_plate;

static robust_plate robust_plate_new(double T)
{
    robust_plate p;
    p.f = plate(0, PLATE_AT, NULL);
    assert_non_null(p.f);
    set_tolerance(p.f, T, 0);
    p.a = test_analysis_new(p.f);
    assert_int_equal(wr_robust_new(p.a, 0, &p.rb), WR_OK);
    return p;
}

static void robust_plate_free(robust_plate *p)
{
    wr_robust_free(p->rb);
    wr_analysis_free(p->a);
    wr_fixture_free(p->f);
}

/* The frictionless plate: (-a, -b, tau) = (-0.5, -1, tau) seats it robustly
 * for |tau| below b (1 - T) - a T = 0.85 and not above. */
static void test_closed_form(void **state)
{
    (void)state;
    const double T = 0.1;
    robust_plate p = robust_plate_new(T);
    wr_fixture *f = p.f;
    wr_robust *rb = p.rb;
    static const double taus[] = {0.3, 0.7, 0.75, 0.95, 0.99};
    const double fa = 0.5, fb = 1;
    for (size_t i = 0; i < sizeof taus / sizeof *taus; i++)
        for (int sign = -1; sign <= 1; sign += 2) {
            double tau = sign * taus[i];
            double w[3] = {-fa, -fb, tau};
            /* nominally inside: |tau| < b */
            assert_int_equal(nominal_verdict(f, w, WR_SET_GOAL), WR_VERDICT_INSIDE);
            wr_robust_answer r;
            assert_int_equal(wr_robust_classify(rb, w, WR_SET_GOAL, WR_DEFAULT_TOLERANCE, &r),
                             WR_OK);
            wr_verdict expect =
                fabs(tau) < fb * (1 - T) - fa * T ? WR_VERDICT_INSIDE : WR_VERDICT_OUTSIDE;
            if (r.answer.verdict != expect)
                print_error("tau %g: verdict %d, expected %d (margin %g)\n", tau,
                            r.answer.verdict, expect, r.answer.margin);
            assert_int_equal(r.answer.verdict, expect);
            if (expect == WR_VERDICT_OUTSIDE) {
                /* The witness breaks the closed form's condition on its
                 * side: the moment about the pivot turns the wrong way. */
                double x1 = r.points[0][0], x2 = r.points[1][0], y3 = r.points[2][1];
                if (tau < 0)
                    assert_true(tau + fb * (x2 - 2) + fa * (1 - y3) < 0);
                else
                    assert_true(tau - fb * (2 - x1) + fa * (1 - y3) > 0);
                check_witness(0, T, 0, &r, w, WR_SET_GOAL);
            }
        }
    robust_plate_free(&p);
}

/* Robust push regions on the chamfered plate: inside the nominal ones,
 * shorter, and every point of them inside on every sampled fixture of the
 * set, built here. */
static void test_regions(void **state)
{
    (void)state;
    const double T = 0.01, A = 0.5, mu = 0.1;
    plate_vertices = CHAMFERED;
    plate_vertex_count = 5;
    wr_fixture *f = plate(mu, PLATE_AT, NULL);
    assert_non_null(f);
    set_tolerance(f, T, A);
    wr_analysis *a = test_analysis_new(f);
    wr_robust *rb;
    assert_int_equal(wr_robust_new(a, 16, &rb), WR_OK);
    wr_regions nominal, robust;
    assert_int_equal(wr_push_regions(a, WR_SET_BOTH, 0, NULL, &nominal), WR_OK);
    assert_int_equal(wr_robust_regions(rb, WR_SET_BOTH, &nominal, false, NULL, &robust), WR_OK);
    double nominal_length = 0, robust_length = 0;
    for (int i = 0; i < nominal.count; i++)
        nominal_length += wr_region_length(f, &nominal.items[i]);
    assert_true(robust.count >= 1);
    test_rng rng = {0x5eedULL};
    for (int i = 0; i < robust.count; i++) {
        const wr_region *r = &robust.items[i];
        robust_length += wr_region_length(f, r);
        bool within = false;
        for (int j = 0; j < nominal.count; j++)
            within |= nominal.items[j].edge == r->edge && nominal.items[j].t0 <= r->t0 &&
                      r->t1 <= nominal.items[j].t1;
        assert_true(within);
        for (int k = 0; k < 20; k++) {
            double t = k == 0 ? r->t0 : k == 1 ? r->t1 : test_range(&rng, r->t0, r->t1);
            double w[3];
            wr_push_wrench(f, r->edge, t, w);
            for (int n = 0; n < 20; n++) {
                double s[3], tilt[3];
                draw(&rng, T, A, s, tilt);
                wr_fixture *g = plate_sample(mu, s, tilt);
                assert_non_null(g);
                assert_int_equal(nominal_verdict(g, w, WR_SET_BOTH), WR_VERDICT_INSIDE);
                wr_fixture_free(g);
            }
        }
    }
    print_message("chamfered plate, both: nominal %g, robust %g\n", nominal_length,
                  robust_length);
    assert_true(robust_length < nominal_length);
    assert_true(robust_length > 0.5 * nominal_length);
    wr_regions_release(&nominal);
    wr_regions_release(&robust);
    wr_robust_free(rb);
    wr_analysis_free(a);
    wr_fixture_free(f);
    plate_vertices = PLATE;
    plate_vertex_count = 4;
}

/* The frictionless plate under its weight (m G = 1, straight down) pushed
 * along -x at (4, y): (-F, -1, F (y - 1)), so by the closed form above it
 * with a = F, b = 1, tau = F (y - 1) it seats robustly for
 * F |y - 1| < (1 - T) - F T, that is 0 < F < (1 - T) / (|y - 1| + T);
 * nominally 0 < F < 1 / |y - 1|. */
static void test_force_closed_form(void **state)
{
    (void)state;
    const double T = 0.1;
    wr_fixture *f = plate(0, PLATE_AT, NULL);
    assert_non_null(f);
    set_tolerance(f, T, 0);
    wr_analysis *a = test_analysis_new(f);
    wr_robust *rb;
    assert_int_equal(wr_robust_new(a, 256, &rb), WR_OK);
    static const double heights[] = {1.5, 0.4, 1.9};
    for (size_t i = 0; i < sizeof heights / sizeof *heights; i++) {
        double y = heights[i];
        double load[3] = {0, -f->mass, 0}, push[3];
        wr_fixture_force_wrench(f, (const double[2]){-1, 0}, (const double[2]){4, y}, push);
        wr_forces nominal = {0}, robust = {0};
        assert_int_equal(wr_force_range(a, WR_SET_GOAL, load, push, 0, INFINITY, &nominal),
                         WR_OK);
        assert_int_equal(nominal.count, 1);
        assert_true(fabs(nominal.items[0].hi - 1 / fabs(y - 1)) < 1e-9);
        assert_int_equal(
            wr_robust_forces(rb, WR_SET_GOAL, load, push, &nominal, NULL, &robust), WR_OK);
        assert_true(robust.count >= 1);
        double hi = (1 - T) / (fabs(y - 1) + T);
        double lo_found = robust.items[0].lo, hi_found = robust.items[robust.count - 1].hi;
        print_message("y %g: robust (%g, %g), closed form (0, %g)\n", y, lo_found, hi_found,
                      hi);
        assert_true(lo_found >= 0 && lo_found < 0.05 * hi);
        assert_true(hi_found <= hi * (1 + 1e-9) && hi_found > 0.97 * hi);
        wr_forces_release(&nominal);
        wr_forces_release(&robust);
    }
    wr_robust_free(rb);
    wr_analysis_free(a);
    wr_fixture_free(f);
}

/* The nominal margin of wrench w on the frictionless plate's fixture at
 * (s, 0), built here. */
static double plate_margin(const double s[3], const double w[3], wr_set set)
{
    wr_fixture *g = plate_sample(0, s, (const double[3]){0, 0, 0});
    assert_non_null(g);
    wr_analysis *a = test_analysis_new(g);
    wr_answer answer;
    assert_int_equal(wr_classify(a, w, set, WR_DEFAULT_TOLERANCE, &answer), WR_OK);
    wr_analysis_free(a);
    wr_fixture_free(g);
    return answer.margin;
}

/* Near the robust boundary of the frictionless plate, |tau| = b (1 - T) -
 * a T (the closed form above): wrenches 1e-8 of torque either side of it
 * (worst margins -+4.9e-9 over the set) are decided, and so are 2.5e-9
 * beyond it (worst margin -1.2e-9) and 3.5e-9 within it (1.7e-9): the
 * undecided band is under 1e-9 beyond the tolerance of 1e-9.  Outside:
 * its witness confirmed here.  Inside: its margin a lower bound of the
 * worst over the set's corners (each fixture built here), where the closed
 * form puts the worst case, and above the tolerance. */
static void test_band(void **state)
{
    (void)state;
    const double T = 0.1, fa = 0.5, fb = 1, edge = fb * (1 - T) - fa * T;
    robust_plate p = robust_plate_new(T);
    wr_robust *rb = p.rb;
    static const double offsets[] = {1e-8, 2.5e-9, 1e-7, -1e-8, -3.5e-9, -1e-6};
    for (size_t i = 0; i < sizeof offsets / sizeof *offsets; i++)
        for (int sign = -1; sign <= 1; sign += 2) {
            double tau = sign * (edge + offsets[i]);
            double w[3] = {-fa, -fb, tau};
            wr_robust_answer r;
            assert_int_equal(wr_robust_classify(rb, w, WR_SET_GOAL, WR_DEFAULT_TOLERANCE, &r),
                             WR_OK);
            if (offsets[i] > 0) {
                assert_int_equal(r.answer.verdict, WR_VERDICT_OUTSIDE);
                check_witness(0, T, 0, &r, w, WR_SET_GOAL);
                continue;
            }
            assert_int_equal(r.answer.verdict, WR_VERDICT_INSIDE);
            double worst = INFINITY;
            for (int corner = 0; corner < 8; corner++) {
                double s[3];
                for (int k = 0; k < 3; k++)
                    s[k] = corner >> k & 1 ? T : -T;
                worst = fmin(worst, plate_margin(s, w, WR_SET_GOAL));
            }
            assert_true(worst > 0 && worst < 1e-5);
            assert_true(r.answer.margin > WR_DEFAULT_TOLERANCE && r.answer.margin <= worst);
            print_message("tau %.10g: verdict %d, margin %g, worst at the corners %g\n", tau,
                          r.answer.verdict, r.answer.margin, worst);
        }
    robust_plate_free(&p);
}

static void test_refusals(void **state)
{
    (void)state;
    wr_fixture *f = plate(0.3, PLATE_AT, NULL);
    assert_non_null(f);
    struct {
        wr_tolerance t;
        const char *field;
        const char *words;
    } bad[] = {
        {{true, -0.1, 0}, "tolerance.position", ">= 0"},
        {{true, NAN, 0}, "tolerance.position", ">= 0"},
        {{true, 0.1, 90}, "tolerance.angle", "below 90"},
        {{true, 0.1, -1}, "tolerance.angle", "below 90"},
        {{true, 0.1, INFINITY}, "tolerance.angle", "below 90"},
        /* fixel 1 at x = 1 on the bottom edge [0, 4]: 1 to the nearer end */
        {{true, 1.25, 0}, "tolerance.position", "0.25 more than fixel 1"},
    };
    for (size_t i = 0; i < sizeof bad / sizeof *bad; i++) {
        wr_error error;
        assert_int_equal(wr_fixture_set_tolerance(f, &bad[i].t, &error), WR_INVALID);
        assert_string_equal(error.field, bad[i].field);
        if (!strstr(error.reason, bad[i].words))
            print_error("%s\n", error.reason);
        assert_non_null(strstr(error.reason, bad[i].words));
    }
    wr_tolerance fine = {true, 1, 89.9};
    wr_error error;
    assert_int_equal(wr_fixture_set_tolerance(f, &fine, &error), WR_OK);
    wr_fixture_free(f);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_refusals),
        cmocka_unit_test(test_closed_form),
        cmocka_unit_test(test_band),
        cmocka_unit_test(test_sampling_plate),
        cmocka_unit_test(test_regions),
        cmocka_unit_test(test_force_closed_form),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
