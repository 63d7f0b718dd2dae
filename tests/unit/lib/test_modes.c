/* test_modes.c -- kinematically feasible contact modes (docs/MODEL.md section 4),
 * against an enumeration that shares nothing with the library's search.
 *
 * A mode is the sign pattern of the contact accelerations of some q != 0 that
 * penetrates no fixel.  The patterns are constant on the faces of the central
 * arrangement of the planes a_in(q) = 0, a_it(q) = 0, so one point per face
 * finds them all: the lines where two planes meet (both signs), the midpoints
 * between neighbouring lines on each plane, and random points for the open
 * cells (where every a_n > 0: the all-s mode). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>
#include <stdio.h>

#include "test_util.h"

#define MAX_TEXTS 4096
#define ZERO 1e-10

typedef struct text_set {
    int count;
    char text[MAX_TEXTS][WR_CONSTRAINT_TEXT];
} text_set;

static void add_text(text_set *set, const char *text)
{
    for (int i = 0; i < set->count; i++)
        if (strcmp(set->text[i], text) == 0)
            return;
    assert_true(set->count < MAX_TEXTS);
    strcpy(set->text[set->count++], text);
}

static double dot(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static void cross(const double a[3], const double b[3], double c[3])
{
    c[0] = a[1] * b[2] - a[2] * b[1];
    c[1] = a[2] * b[0] - a[0] * b[2];
    c[2] = a[0] * b[1] - a[1] * b[0];
}

static bool unit(double v[3])
{
    double n = sqrt(dot(v, v));
    if (n < 1e-9)
        return false;
    for (int k = 0; k < 3; k++)
        v[k] /= n;
    return true;
}

/* The mode of direction q, or false if q penetrates a fixel. */
static bool mode_of(const wr_fixture *f, const double q[3], char text[WR_CONSTRAINT_TEXT])
{
    int k = f->fixel_count;
    bool all_rolling = true;
    for (int i = 0; i < k; i++) {
        double wn[3], wt[3];
        memcpy(wn, f->fixels[i].normal_wrench, sizeof wn);
        memcpy(wt, f->fixels[i].tangent_wrench, sizeof wt);
        unit(wn);
        unit(wt);
        double an = dot(wn, q), at = dot(wt, q);
        if (an < -ZERO)
            return false;
        if (an > ZERO)
            text[i] = 's';
        else
            text[i] = at > ZERO ? 'l' : at < -ZERO ? 'r' : 'n';
        all_rolling &= text[i] == 'n';
    }
    text[k] = 0;
    if (all_rolling) { /* q != 0 with every contact rolling: a pivot */
        text[k] = q[2] > 0 ? '+' : '-';
        text[k + 1] = 0;
    }
    return true;
}

static void sampled_modes(const wr_fixture *f, test_rng *rng, text_set *out)
{
    int k = f->fixel_count;
    double planes[2 * WR_MAX_FIXELS][3];
    for (int i = 0; i < k; i++) {
        memcpy(planes[2 * i], f->fixels[i].normal_wrench, sizeof planes[0]);
        memcpy(planes[2 * i + 1], f->fixels[i].tangent_wrench, sizeof planes[0]);
        unit(planes[2 * i]);
        unit(planes[2 * i + 1]);
    }
    int n = 2 * k;
    static double lines[4 * 64 * 64][3];
    int line_count = 0;
    for (int a = 0; a < n; a++)
        for (int b = a + 1; b < n; b++) {
            double c[3];
            cross(planes[a], planes[b], c);
            if (!unit(c))
                continue;
            memcpy(lines[line_count++], c, sizeof c);
            for (int j = 0; j < 3; j++)
                lines[line_count][j] = -c[j];
            line_count++;
        }
    char text[WR_CONSTRAINT_TEXT];
    for (int l = 0; l < line_count; l++)
        if (mode_of(f, lines[l], text))
            add_text(out, text);
    /* On each plane: angles of the lines on it, and the arcs between them. */
    for (int p = 0; p < n; p++) {
        double u[3] = {0, 0, 0}, w[3];
        /* An in-plane basis u, w. */
        int axis = fabs(planes[p][0]) < 0.6 ? 0 : fabs(planes[p][1]) < 0.6 ? 1 : 2;
        u[axis] = 1;
        double d = dot(u, planes[p]);
        for (int j = 0; j < 3; j++)
            u[j] -= d * planes[p][j];
        unit(u);
        cross(planes[p], u, w);
        double angles[4 * 64 * 64 + 4];
        int count = 0;
        for (int l = 0; l < line_count; l++)
            if (fabs(dot(lines[l], planes[p])) < 1e-9)
                angles[count++] = atan2(dot(lines[l], w), dot(lines[l], u));
        if (count < 2) { /* no lines: sample the circle */
            for (int j = 0; j < 4; j++)
                angles[count++] = j * TEST_PI / 2;
        }
        /* Sort, then midpoints of neighbours (cyclically). */
        for (int i = 1; i < count; i++)
            for (int j = i; j > 0 && angles[j] < angles[j - 1]; j--) {
                double t = angles[j];
                angles[j] = angles[j - 1];
                angles[j - 1] = t;
            }
        for (int i = 0; i < count; i++) {
            double a0 = angles[i], a1 = i + 1 < count ? angles[i + 1] : angles[0] + 2 * TEST_PI;
            if (a1 - a0 < 1e-9)
                continue;
            double mid = (a0 + a1) / 2;
            double q[3];
            for (int j = 0; j < 3; j++)
                q[j] = cos(mid) * u[j] + sin(mid) * w[j];
            if (mode_of(f, q, text))
                add_text(out, text);
        }
    }
    for (int s = 0; s < 2000; s++) {
        double q[3];
        test_sphere(rng, q);
        if (mode_of(f, q, text))
            add_text(out, text);
    }
}

static void check_fixture(const wr_fixture *f, test_rng *rng, int *compared)
{
    text_set *expected = calloc(1, sizeof *expected);
    sampled_modes(f, rng, expected);
    wr_constraint *modes;
    bool pinned;
    int count;
    assert_int_equal(wr_modes_find(f, &modes, &count, &pinned), WR_OK);
    text_set *found = calloc(1, sizeof *found);
    bool pivots = false;
    for (int i = 0; i < count; i++) {
        char text[WR_CONSTRAINT_TEXT];
        wr_constraint_format(&modes[i], text);
        add_text(found, text);
        pivots |= modes[i].pivot != 0;
    }
    assert_int_equal(found->count, count); /* no repeats */
    assert_int_equal(pinned, !pivots);
    for (int i = 0; i < expected->count; i++) {
        bool listed = false;
        for (int j = 0; j < found->count; j++)
            listed |= strcmp(expected->text[i], found->text[j]) == 0;
        if (!listed)
            fail_msg("mode %s is realised by some q but not listed", expected->text[i]);
    }
    for (int j = 0; j < found->count; j++) {
        bool sampled = false;
        for (int i = 0; i < expected->count; i++)
            sampled |= strcmp(expected->text[i], found->text[j]) == 0;
        if (!sampled)
            fail_msg("mode %s is listed but no q realises it", found->text[j]);
    }
    *compared += count;
    free(modes);
    free(expected);
    free(found);
}

static void random_fixtures_match_the_arrangement(void **state)
{
    (void)state;
    test_rng rng = {4242};
    int compared = 0, fixtures = 0;
    for (int i = 0; i < 40; i++) {
        int k = 1 + i % 4;
        wr_fixture *f = test_random_fixture(&rng, k, i % 2 == 0);
        assert_non_null(f);
        check_fixture(f, &rng, &compared);
        fixtures++;
        wr_fixture_free(f);
    }
    print_message("modes: %d random fixtures, %d modes all realised and all found\n", fixtures,
                  compared);
}

static wr_fixture *disc_with_fixels_at(const double *degrees, int k)
{
    wr_fixel_spec fixels[WR_MAX_FIXELS];
    memset(fixels, 0, sizeof fixels);
    for (int i = 0; i < k; i++) {
        fixels[i].at[0] = cos(degrees[i] * TEST_PI / 180);
        fixels[i].at[1] = sin(degrees[i] * TEST_PI / 180);
    }
    wr_fixture_spec spec;
    memset(&spec, 0, sizeof spec);
    spec.mass = 1;
    spec.shape = WR_SHAPE_CIRCLE;
    spec.radius = 1;
    spec.friction.given = true;
    spec.friction.static_mu = 0.3;
    spec.fixel_count = (size_t)k;
    spec.fixels = fixels;
    return test_fixture_new(&spec, NULL);
}

/* Degenerate placements the random ones avoid: opposite fixels on a disc (a
 * common tangent lets it translate while both contacts slide), three fixels
 * on a disc, and a single fixel (which cannot pin the body). */
static void special_placements_match_the_arrangement(void **state)
{
    (void)state;
    test_rng rng = {5};
    int compared = 0;
    const double opposite[] = {0, 180}, three[] = {10, 130, 250}, one[] = {45};
    const double *placements[] = {opposite, three, one};
    int counts[] = {2, 3, 1};
    for (int p = 0; p < 3; p++) {
        wr_fixture *f = disc_with_fixels_at(placements[p], counts[p]);
        assert_non_null(f);
        check_fixture(f, &rng, &compared);
        wr_fixture_free(f);
    }
    /* Opposite fixels: translation along the common tangent slides one
     * fixel left and the other right, so lr and rl are feasible. */
    wr_fixture *f = disc_with_fixels_at(opposite, 2);
    wr_constraint *modes;
    bool pinned;
    int count;
    assert_int_equal(wr_modes_find(f, &modes, &count, &pinned), WR_OK);
    bool lr = false, rl = false;
    for (int i = 0; i < count; i++) {
        lr |= strcmp(modes[i].letters, "lr") == 0;
        rl |= strcmp(modes[i].letters, "rl") == 0;
    }
    assert_true(lr && rl && pinned);
    free(modes);
    wr_fixture_free(f);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(random_fixtures_match_the_arrangement),
        cmocka_unit_test(special_placements_match_the_arrangement),
    };
    return cmocka_run_group_tests_name("modes", tests, NULL, NULL);
}
