/* test_symmetry.c -- a part's symmetries (lib/wr_symmetry.h) and designs
 * collapsed by them (lib/wr_design.h): the groups of a rectangle (D2), a
 * square plate with four holes (D4), gear-like outlines (D12, and C8 with
 * teeth that lean), an asymmetric bracket and a centre of mass off the
 * axes, each symmetry checked by the test's own transform of every vertex;
 * then every design of a symmetric plate scored without symmetries,
 * grouped by the test mapping each design's fixels by each symmetry, against
 * the collapsed search: one design per group, its lowest candidate, its
 * copies the group's size. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "test_util.h"

static wr_fixture *outline_body(const wr_loop_spec *loops, size_t count, const double *com)
{
    wr_fixture *body = test_outline_body(loops, count, com);
    assert_non_null(body);
    return body;
}

/* The test's own transform: the rotation by angle_deg about c, or the
 * reflection through the line through c in direction angle_deg. */
static void transform(const wr_symmetry *g, const double p[2], double out[2])
{
    double a = g->angle_deg * TEST_PI / 180, x = p[0] - g->center[0], y = p[1] - g->center[1];
    if (g->reflection) {
        /* Mirror: keep the part along the line, negate the part across it. */
        double u[2] = {cos(a), sin(a)}, along = x * u[0] + y * u[1];
        out[0] = g->center[0] + 2 * along * u[0] - x;
        out[1] = g->center[1] + 2 * along * u[1] - y;
    } else {
        out[0] = g->center[0] + x * cos(a) - y * sin(a);
        out[1] = g->center[1] + x * sin(a) + y * cos(a);
    }
}

/* A loop of two half circles (bulge 1 both): its centre and radius. */
static bool two_halves(const wr_loop *loop, double centre[2], double *radius)
{
    if (loop->segment_count != 2 || loop->segments[0].bulge != 1 || loop->segments[1].bulge != 1)
        return false;
    const double *a = loop->segments[0].start, *b = loop->segments[1].start;
    centre[0] = (a[0] + b[0]) / 2;
    centre[1] = (a[1] + b[1]) / 2;
    *radius = hypot(a[0] - b[0], a[1] - b[1]) / 2;
    return true;
}

/* Every vertex of every loop maps onto a vertex (a round hole's onto some
 * round hole's circle), by the test's transform, and the centre of mass
 * is fixed. */
static void assert_symmetry(const wr_fixture *body, const wr_symmetry *g)
{
    const wr_outline *o = body->outline;
    double eps = 1e-6 * body->size, c[2];
    transform(g, body->com, c);
    assert_true(hypot(c[0] - body->com[0], c[1] - body->com[1]) <= eps);
    for (size_t l = 0; l < o->loop_count; l++)
        for (size_t j = 0; j < o->loops[l].segment_count; j++) {
            double p[2], centre[2], radius;
            transform(g, o->loops[l].segments[j].start, p);
            bool round = two_halves(&o->loops[l], centre, &radius);
            bool found = false;
            for (size_t m = 0; m < o->loop_count && !found; m++) {
                if (round && two_halves(&o->loops[m], centre, &radius)) {
                    found = fabs(hypot(p[0] - centre[0], p[1] - centre[1]) - radius) <= eps;
                    continue;
                }
                for (size_t k = 0; k < o->loops[m].segment_count && !found && !round; k++) {
                    const double *q = o->loops[m].segments[k].start;
                    found = hypot(p[0] - q[0], p[1] - q[1]) <= eps;
                }
            }
            assert_true(found);
        }
}

static int symmetries_of(const wr_fixture *body, int *rotations, int *reflections)
{
    wr_symmetry *list;
    int count;
    assert_int_equal(wr_symmetry_find(body, NULL, 0, &list, &count), WR_OK);
    assert_true(count >= 1);
    assert_false(list[0].reflection); /* the identity first */
    assert_true(list[0].angle_deg == 0);
    *rotations = *reflections = 0;
    for (int i = 0; i < count; i++) {
        assert_symmetry(body, &list[i]);
        if (list[i].reflection)
            ++*reflections;
        else
            ++*rotations;
    }
    free(list);
    return count;
}

/* A 10 x 4 rectangle away from the origin. */
static const double RECTANGLE[4][3] = {{3, 2, 0}, {13, 2, 0}, {13, 6, 0}, {3, 6, 0}};

static void rectangle_d2(void **state)
{
    (void)state;
    wr_loop_spec loop = {4, RECTANGLE};
    wr_fixture *body = outline_body(&loop, 1, NULL);
    int rot, ref;
    assert_int_equal(symmetries_of(body, &rot, &ref), 4);
    assert_int_equal(rot, 2);
    assert_int_equal(ref, 2);
    wr_fixture_free(body);
    /* A polygon of the same rectangle: the same. */
    static const double v[4][2] = {{3, 2}, {13, 2}, {13, 6}, {3, 6}};
    body = test_polygon_body(v, 4);
    assert_int_equal(symmetries_of(body, &rot, &ref), 4);
    wr_fixture_free(body);
    /* The centre of mass given on the long axis, off the short one: only
     * the mirror in the long axis keeps it. */
    double com[2] = {10, 4};
    body = outline_body(&loop, 1, com);
    assert_int_equal(symmetries_of(body, &rot, &ref), 2);
    assert_int_equal(ref, 1);
    wr_fixture_free(body);
}

/* The rectangle's four symmetries filtered by sets of points: kept are
 * those mapping the set onto itself, counted by hand (the centre is fixed
 * by all; the two diagonal corners swap under the half turn alone; one
 * corner is fixed by the identity alone). */
static void points_filter(void **state)
{
    (void)state;
    wr_loop_spec loop = {4, RECTANGLE};
    wr_fixture *body = outline_body(&loop, 1, NULL);
    static const double centre[1][2] = {{8, 4}};
    static const double diagonal[2][2] = {{13, 6}, {3, 2}};
    static const double corner[1][2] = {{3, 2}};
    const struct {
        const double (*points)[2];
        int count, kept;
    } cases[] = {{NULL, 0, 4}, {centre, 1, 4}, {diagonal, 2, 2}, {corner, 1, 1}};
    for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++) {
        wr_symmetry *list;
        int count;
        assert_int_equal(wr_symmetry_find(body, NULL, 0, &list, &count), WR_OK);
        assert_int_equal(count, 4);
        int kept = wr_symmetry_filter_points(cases[c].points, cases[c].count, body->size, list,
                                             count);
        assert_int_equal(kept, cases[c].kept);
        assert_true(list[0].angle_deg == 0 && !list[0].reflection);
        if (cases[c].kept == 2)
            assert_true(!list[1].reflection && fabs(list[1].angle_deg - 180) < 1e-9);
        free(list);
    }
    wr_fixture_free(body);
}

/* A 20 x 20 square, rounded corners, four round holes (two half circles
 * each, drawn from different vertices) near its corners. */
static void square_with_holes_d4(void **state)
{
    (void)state;
    const double f = 0.41421356237309503; /* a quarter circle */
    static double outer[8][3];
    const double o[8][3] = {{2, 0, 0}, {18, 0, f}, {20, 2, 0}, {20, 18, f},
                            {18, 20, 0}, {2, 20, f}, {0, 18, 0}, {0, 2, f}};
    memcpy(outer, o, sizeof o);
    const double h1[2][3] = {{4, 5, 1}, {6, 5, 1}}, h2[2][3] = {{15, 4, 1}, {15, 6, 1}},
                 h3[2][3] = {{16, 15, 1}, {14, 15, 1}}, h4[2][3] = {{5, 16, 1}, {5, 14, 1}};
    wr_loop_spec loops[5] = {{8, outer}, {2, h1}, {2, h2}, {2, h3}, {2, h4}};
    wr_fixture *body = outline_body(loops, 5, NULL);
    int rot, ref;
    assert_int_equal(symmetries_of(body, &rot, &ref), 8);
    assert_int_equal(rot, 4);
    assert_int_equal(ref, 4);
    wr_fixture_free(body);
    /* One hole moved: the identity alone. */
    const double moved[2][3] = {{4, 5.5, 1}, {6, 5.5, 1}};
    loops[1].vertices = moved;
    body = outline_body(loops, 5, NULL);
    assert_int_equal(symmetries_of(body, &rot, &ref), 1);
    wr_fixture_free(body);
}

/* n vertices on r(theta): teeth symmetric about their axes (lean 0) or
 * leaning (a sawtooth). */
static wr_fixture *gear(int n, int teeth, double lean)
{
    double (*v)[3] = calloc((size_t)n, sizeof *v);
    for (int i = 0; i < n; i++) {
        double theta = 2 * TEST_PI * i / n;
        double phase = teeth * theta;
        double r = 10 + 1.2 * fmax(-1, fmin(1, 1.6 * cos(phase) + lean * sin(phase)));
        v[i][0] = 3 + r * cos(theta);
        v[i][1] = -1 + r * sin(theta);
    }
    wr_loop_spec loop = {(size_t)n, (const double(*)[3])v};
    wr_fixture *body = outline_body(&loop, 1, NULL);
    free(v);
    return body;
}

static void gears_dn_and_cn(void **state)
{
    (void)state;
    int rot, ref;
    wr_fixture *body = gear(1200, 12, 0);
    assert_int_equal(symmetries_of(body, &rot, &ref), 24);
    assert_int_equal(rot, 12);
    wr_fixture_free(body);
    body = gear(800, 8, 0.9);
    assert_int_equal(symmetries_of(body, &rot, &ref), 8);
    assert_int_equal(ref, 0);
    wr_fixture_free(body);
}

static void asymmetric_bracket_identity(void **state)
{
    (void)state;
    static const double outer[7][3] = {{0, 0, 0}, {20, 0, 0}, {20, 4, 0}, {8, 4, -0.41421356237309503},
                                       {4, 8, 0}, {4, 20, 1}, {0, 20, 0}};
    static const double hole[2][3] = {{13, 2, 1}, {15, 2, 1}};
    wr_loop_spec loops[2] = {{7, outer}, {2, hole}};
    wr_fixture *body = outline_body(loops, 2, NULL);
    int rot, ref;
    assert_int_equal(symmetries_of(body, &rot, &ref), 1);
    wr_fixture_free(body);
    /* An L with equal legs and no hole is mirror symmetric about its
     * diagonal. */
    static const double l[6][3] = {{0, 0, 0}, {10, 0, 0}, {10, 3, 0}, {3, 3, 0}, {3, 10, 0},
                                   {0, 10, 0}};
    wr_loop_spec loop = {6, l};
    body = outline_body(&loop, 1, NULL);
    assert_int_equal(symmetries_of(body, &rot, &ref), 2);
    assert_int_equal(ref, 1);
    wr_fixture_free(body);
}

/* Does the test's transform take design a's fixels onto design b's? */
static bool maps_design(const wr_symmetry *g, const wr_site *sites, int k, const wr_design *a,
                        const wr_design *b, double eps)
{
    for (int i = 0; i < k; i++) {
        double p[2], n[2], zero[2] = {0, 0}, tip[2];
        const wr_site *s = &sites[a->sites[i]];
        transform(g, s->at, p);
        /* A normal is a direction: the transform of its tip less the
         * transform's of the origin's image. */
        double end[2] = {s->at[0] + s->normal[0], s->at[1] + s->normal[1]};
        transform(g, end, tip);
        n[0] = tip[0] - p[0];
        n[1] = tip[1] - p[1];
        (void)zero;
        bool found = false;
        for (int j = 0; j < k && !found; j++) {
            const wr_site *t = &sites[b->sites[j]];
            found = hypot(p[0] - t->at[0], p[1] - t->at[1]) <= eps &&
                    hypot(n[0] - t->normal[0], n[1] - t->normal[1]) <= 1e-6;
        }
        if (!found)
            return false;
    }
    return true;
}

/* Every design of a part scored (symmetries off, top large), grouped by
 * the test; against the collapsed search. */
static void check_collapse(const wr_fixture *body, double spacing, int k, wr_objective objective)
{
    wr_site *sites = NULL;
    int site_count = 0;
    wr_error error;
    wr_spacing rule = {spacing, spacing / 2, 0};
    assert_int_equal(wr_sites_spaced(body, &rule, &sites, &site_count, &error), WR_OK);
    wr_symmetry *symmetries;
    int symmetry_count;
    assert_int_equal(wr_symmetry_find(body, sites, site_count, &symmetries, &symmetry_count),
                     WR_OK);
    assert_true(symmetry_count > 1);
    wr_design_spec spec;
    memset(&spec, 0, sizeof spec);
    spec.body = body;
    spec.friction = (wr_friction_spec){.given = true, .static_mu = 0.2};
    spec.sites = sites;
    spec.site_count = site_count;
    spec.fixel_count = k;
    spec.objective = objective;
    spec.top = WR_DESIGN_MAX_TOP;
    spec.shard_count = 1;
    wr_design_job *all, *collapsed;
    assert_int_equal(test_design_run(&spec, &all), WR_OK);
    spec.symmetries = symmetries;
    spec.symmetry_count = symmetry_count;
    assert_int_equal(test_design_run(&spec, &collapsed), WR_OK);
    int n_all, n_collapsed;
    const wr_design *every = wr_design_job_designs(all, &n_all);
    const wr_design *kept = wr_design_job_designs(collapsed, &n_collapsed);
    assert_true(n_all < WR_DESIGN_MAX_TOP); /* every scored design is listed */
    /* The test's groups: a design's group is every design some symmetry
     * maps it onto. */
    int *group = malloc((size_t)n_all * sizeof *group), groups = 0;
    for (int i = 0; i < n_all; i++)
        group[i] = -1;
    for (int i = 0; i < n_all; i++) {
        if (group[i] >= 0)
            continue;
        group[i] = groups;
        for (int j = i + 1; j < n_all; j++)
            for (int g = 0; g < symmetry_count && group[j] < 0; g++)
                if (maps_design(&symmetries[g], sites, k, &every[i], &every[j], 1e-6 * body->size)) {
                    group[j] = groups;
                    /* The same fixture seen turned: the same score. */
                    assert_true(fabs(every[j].score - every[i].score) <=
                                1e-7 * (1 + fabs(every[i].score)));
                }
        groups++;
    }
    assert_int_equal(n_collapsed, groups);
    assert_true(groups < n_all); /* something was collapsed */
    for (int c = 0; c < n_collapsed; c++) {
        /* The collapsed design is its group's lowest candidate, with the
         * group's size as copies and that candidate's score. */
        int at = -1, size = 0;
        for (int i = 0; i < n_all; i++)
            if (every[i].candidate == kept[c].candidate)
                at = i;
        assert_true(at >= 0);
        for (int i = 0; i < n_all; i++)
            if (group[i] == group[at]) {
                size++;
                assert_true(every[i].candidate >= kept[c].candidate);
            }
        assert_int_equal(kept[c].copies, size);
        assert_memory_equal(&kept[c].score, &every[at].score, sizeof(double));
    }
    const wr_design_counts *counts = wr_design_job_counts(collapsed);
    assert_int_equal(counts->examined, wr_design_job_counts(all)->examined);
    assert_true(counts->symmetric > 0);
    free(group);
    wr_design_job_free(all);
    wr_design_job_free(collapsed);
    free(symmetries);
    free(sites);
}

static void designs_collapsed(void **state)
{
    (void)state;
    wr_loop_spec loop = {4, RECTANGLE};
    wr_fixture *body = outline_body(&loop, 1, NULL);
    check_collapse(body, 2, 3, WR_OBJECTIVE_MARGIN);
    check_collapse(body, 2.5, 3, WR_OBJECTIVE_REGION);
    wr_fixture_free(body);
    /* A square: D4. */
    static const double square[4][3] = {{0, 0, 0}, {8, 0, 0}, {8, 8, 0}, {0, 8, 0}};
    loop.vertices = square;
    body = outline_body(&loop, 1, NULL);
    check_collapse(body, 2, 3, WR_OBJECTIVE_MARGIN);
    wr_fixture_free(body);
}

/* A disc: its symmetries are its sites' (evenly spaced: D_n). */
static void disc_from_sites(void **state)
{
    (void)state;
    wr_fixture_spec spec;
    memset(&spec, 0, sizeof spec);
    spec.mass = 1;
    spec.shape = WR_SHAPE_CIRCLE;
    spec.center[0] = 1;
    spec.radius = 5;
    wr_fixture *body;
    wr_error error;
    assert_int_equal(wr_fixture_body_new(&spec, &body, &error), WR_OK);
    wr_site *sites = NULL;
    int n = 0;
    wr_spacing rule = {2 * TEST_PI * 5 / 12, TEST_PI * 5 / 12, 0};
    assert_int_equal(wr_sites_spaced(body, &rule, &sites, &n, &error), WR_OK);
    assert_int_equal(n, 12);
    wr_symmetry *list;
    int count;
    assert_int_equal(wr_symmetry_find(body, sites, n, &list, &count), WR_OK);
    assert_int_equal(count, 24);
    free(list);
    free(sites);
    wr_fixture_free(body);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(rectangle_d2),
        cmocka_unit_test(points_filter),
        cmocka_unit_test(square_with_holes_d4),
        cmocka_unit_test(gears_dn_and_cn),
        cmocka_unit_test(asymmetric_bracket_identity),
        cmocka_unit_test(designs_collapsed),
        cmocka_unit_test(disc_from_sites),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
