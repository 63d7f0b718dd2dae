/* test_lattice_arcs.c -- lattice poses with arcs from the polynomial in
 * tan(theta / 2) against the theta scan (wr_lattice_job_scan), on parts of
 * lines and arcs: a rounded rectangle, a plate with a round hole and a
 * slot, a D (a half circle on a line), a disc of two arcs with a flat.
 * Every pose the scan finds the polynomial must find (the same holes, the
 * same pose within 1e-7 of the part's size); the polynomial may find more
 * (a crossing the scan's step hid): each of those is listed and checked by
 * its three distances, worked out here from the pose alone: each peg's
 * centre R(-theta) (P - t) is the peg radius from its contact point, the
 * contact point is on the outline, and no point of the outline is nearer
 * the centre than the peg radius. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>
#include <stdio.h>

#include "test_util.h"
#include "wr_internal.h"
#include "wr_lattice.h"
#include "wr_outline.h"

#define QUARTER 0.41421356237309503 /* tan(pi / 8): a quarter circle's bulge */

static wr_lattice_job *run(const wr_fixture *body, const wr_lattice *L, bool scan)
{
    wr_lattice_job *job;
    wr_error error;
    assert_int_equal(wr_lattice_job_new(body, L, &job, &error), WR_OK);
    if (scan)
        wr_lattice_job_scan(job);
    bool done = false;
    while (!done)
        assert_int_equal(wr_lattice_job_run(job, 1000000, NULL, NULL, &done), WR_OK);
    return job;
}

static bool same_design(const wr_lattice_design *a, const wr_lattice_design *b, double size)
{
    if (memcmp(a->holes, b->holes, sizeof a->holes) != 0)
        return false;
    double dtheta = fabs(remainder(a->pose[2] - b->pose[2], 2 * TEST_PI));
    return dtheta <= 1e-7 && hypot(a->pose[0] - b->pose[0], a->pose[1] - b->pose[1]) <= 1e-7 * size;
}

/* The three distances of a design, from its pose alone. */
static void check_distances(const wr_fixture *body, const wr_lattice *L,
                            const wr_lattice_design *d)
{
    double c = cos(d->pose[2]), s = sin(d->pose[2]), size = body->size;
    for (int m = 0; m < 3; m++) {
        double P[2] = {L->pitch * d->holes[m][0] - d->pose[0],
                       L->pitch * d->holes[m][1] - d->pose[1]};
        double q[2] = {c * P[0] + s * P[1], -s * P[0] + c * P[1]};
        double to_contact = hypot(q[0] - d->at[m][0], q[1] - d->at[m][1]);
        if (fabs(to_contact - L->peg_radius) > 1e-6 * size)
            fail_msg("peg %d is %.9g from its contact, not the radius %g", m, to_contact,
                     L->peg_radius);
        if (wr_outline_distance(body->outline, d->at[m]) > 1e-6 * size)
            fail_msg("peg %d's contact is off the outline", m);
        if (wr_outline_distance(body->outline, q) < L->peg_radius - 1e-6 * size ||
            wr_outline_contains(body->outline, q, 1e-9 * size))
            fail_msg("peg %d overlaps the part", m);
    }
}

static void compare(const char *name, const double (*const *loops)[3], const size_t *counts,
                    size_t loop_count, const wr_lattice *L, int *extra_total)
{
    wr_loop_spec specs[4];
    for (size_t i = 0; i < loop_count; i++)
        specs[i] = (wr_loop_spec){counts[i], loops[i]};
    wr_fixture *body = test_outline_body(specs, loop_count, NULL);
    assert_non_null(body);
    wr_lattice_job *exact = run(body, L, false), *scan = run(body, L, true);
    size_t n_exact, n_scan;
    const wr_lattice_design *e = wr_lattice_job_designs(exact, &n_exact);
    const wr_lattice_design *sc = wr_lattice_job_designs(scan, &n_scan);
    for (size_t i = 0; i < n_scan; i++) {
        bool found = false;
        for (size_t j = 0; j < n_exact && !found; j++)
            found = same_design(&sc[i], &e[j], body->size);
        if (!found)
            fail_msg("%s: the scan's pose %zu (holes (%d,%d) (%d,%d), edges %d %d %d, pose "
                     "(%.12g, %.12g, %.12g)) is missing",
                     name, i, sc[i].holes[1][0], sc[i].holes[1][1], sc[i].holes[2][0],
                     sc[i].holes[2][1], sc[i].edges[0], sc[i].edges[1], sc[i].edges[2],
                     sc[i].pose[0], sc[i].pose[1], sc[i].pose[2]);
    }
    int extra = 0;
    for (size_t j = 0; j < n_exact; j++) {
        check_distances(body, L, &e[j]);
        bool found = false;
        for (size_t i = 0; i < n_scan && !found; i++)
            found = same_design(&sc[i], &e[j], body->size);
        if (!found) {
            extra++;
            print_message("    %s: more than the scan: holes (0,0) (%d,%d) (%d,%d), edges %d %d %d, "
                          "pose (%.9g, %.9g, %.9g)\n",
                          name, e[j].holes[1][0], e[j].holes[1][1], e[j].holes[2][0],
                          e[j].holes[2][1], e[j].edges[0], e[j].edges[1], e[j].edges[2],
                          e[j].pose[0], e[j].pose[1], e[j].pose[2]);
        }
    }
    print_message("    %s: %zu poses by the polynomial, %zu by the scan, %d more\n", name,
                  n_exact, n_scan, extra);
    assert_true(n_scan > 0);
    *extra_total += extra;
    wr_lattice_job_free(exact);
    wr_lattice_job_free(scan);
    wr_fixture_free(body);
}

static void polynomial_finds_what_the_scan_finds(void **state)
{
    (void)state;
    int extra = 0;
    /* A rounded rectangle 3 x 2, fillets of 0.5. */
    static const double rounded[8][3] = {{0.5, 0, 0},   {2.5, 0, QUARTER}, {3, 0.5, 0},
                                         {3, 1.5, QUARTER}, {2.5, 2, 0},   {0.5, 2, QUARTER},
                                         {0, 1.5, 0},   {0, 0.5, QUARTER}};
    const double (*r_loops[1])[3] = {rounded};
    size_t r_counts[1] = {8};
    compare("rounded rectangle", r_loops, r_counts, 1,
            &(wr_lattice){.pitch = 1, .peg_radius = 0.15, .extent = {4, 4}}, &extra);
    /* A plate 4 x 2.5 with a round hole (two half circles) and a slot. */
    static const double plate[4][3] = {{0, 0, 0}, {4, 0, 0}, {4, 2.5, 0}, {0, 2.5, 0}};
    static const double hole[2][3] = {{1.4, 1.2, 1}, {0.8, 1.2, 1}};
    static const double slot[4][3] = {{2.4, 1.0, 0}, {3.2, 1.0, 1}, {3.2, 1.5, 0}, {2.4, 1.5, 1}};
    const double (*p_loops[3])[3] = {plate, hole, slot};
    size_t p_counts[3] = {4, 2, 4};
    compare("plate with hole and slot", p_loops, p_counts, 3,
            &(wr_lattice){.pitch = 1, .peg_radius = 0.2, .extent = {5, 4}}, &extra);
    /* A D: a half circle of radius 1.5 closed by its diameter. */
    static const double d_shape[2][3] = {{0, 0, 0}, {0, 3, 1}};
    const double (*d_loops[1])[3] = {d_shape};
    size_t d_counts[1] = {2};
    compare("D", d_loops, d_counts, 1,
            &(wr_lattice){.pitch = 0.9, .peg_radius = 0.1, .extent = {4, 5}}, &extra);
    /* A disc of radius 1.2 with a flat: an arc of 300 degrees and its chord. */
    double a = 2 * TEST_PI / 3; /* half the chord's angle */
    static double flat[2][3];
    flat[0][0] = 1.2 * cos(-a / 2 + TEST_PI / 2);
    flat[0][1] = 1.2 * sin(-a / 2 + TEST_PI / 2);
    flat[0][2] = 0;
    flat[1][0] = 1.2 * cos(a / 2 + TEST_PI / 2);
    flat[1][1] = 1.2 * sin(a / 2 + TEST_PI / 2);
    flat[1][2] = tan((2 * TEST_PI - a) / 4);
    const double (*f_loops[1])[3] = {(const double (*)[3])flat};
    size_t f_counts[1] = {2};
    compare("disc with a flat", f_loops, f_counts, 1,
            &(wr_lattice){.pitch = 0.8, .peg_radius = 0.12, .extent = {5, 5}}, &extra);
    print_message("    %d poses in all that the scan missed\n", extra);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(polynomial_finds_what_the_scan_finds),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
