/* test_simplicity.c -- the simplicity tests of outlines and polygons by the
 * sweep (wr_box_pairs) against the same tests pair by pair in index order:
 * on random and adversarial shapes (vertices on a small grid, so that
 * segments touch, overlap collinearly and share points exactly; stars with
 * a vertex moved onto, or just short of, or just past another segment;
 * zigzags whose long segments' boxes all overlap; holes tangent to each
 * other and to the outer loop, inside or around each other, or outside it; arcs tangent to lines and to arcs), the
 * answer must be the same every time: accepted by both, or refused by both
 * with the same field and the same reason (the same two segments, the same
 * point).  Each family must produce both answers, so neither method can
 * pass by refusing or accepting everything. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>
#include <stdio.h>

#include "test_util.h"
#include "wr_internal.h"
#include "wr_outline.h"

#define MAX_LOOPS 24
#define MAX_VERTICES 600

typedef struct shape {
    size_t loop_count;
    size_t counts[MAX_LOOPS];
    double vertices[MAX_LOOPS][MAX_VERTICES][3];
} shape;

typedef struct tally {
    int accepted, refused;
} tally;

static double *new_vertex(shape *s, double x, double y, double bulge)
{
    size_t loop = s->loop_count - 1;
    assert_true(s->counts[loop] < MAX_VERTICES);
    double *v = s->vertices[loop][s->counts[loop]++];
    v[0] = x;
    v[1] = y;
    v[2] = bulge;
    return v;
}

static void new_loop(shape *s)
{
    assert_true(s->loop_count < MAX_LOOPS);
    s->counts[s->loop_count++] = 0;
}

/* Both outline tests on s: the same status, field and reason. */
static void compare_outline(const shape *s, tally *t)
{
    wr_loop_spec loops[MAX_LOOPS];
    for (size_t i = 0; i < s->loop_count; i++)
        loops[i] = (wr_loop_spec){s->counts[i], (const double (*)[3])s->vertices[i]};
    wr_outline *swept = NULL, *exhaustive = NULL;
    wr_error e1, e2;
    memset(&e1, 0, sizeof e1);
    memset(&e2, 0, sizeof e2);
    wr_status s1 = wr_outline_new_checked(loops, s->loop_count, false, &swept, &e1);
    wr_status s2 = wr_outline_new_checked(loops, s->loop_count, true, &exhaustive, &e2);
    if (s1 != s2 || strcmp(e1.field, e2.field) != 0 || strcmp(e1.reason, e2.reason) != 0)
        fail_msg("the sweep says %d %s: %s; pair by pair %d %s: %s", s1, e1.field, e1.reason, s2,
                 e2.field, e2.reason);
    if (s1 == WR_OK)
        t->accepted++;
    else
        t->refused++;
    wr_outline_free(swept);
    wr_outline_free(exhaustive);
}

/* Both polygon tests on loop 0's vertices (bulges ignored). */
static void compare_polygon(const shape *s, tally *t)
{
    size_t n = s->counts[0];
    if (n < 3)
        return;
    double (*v)[2] = malloc(n * sizeof *v);
    assert_non_null(v);
    for (size_t i = 0; i < n; i++) {
        v[i][0] = s->vertices[0][i][0];
        v[i][1] = s->vertices[0][i][1];
    }
    size_t f1 = 0, g1 = 0, f2 = 0, g2 = 0;
    double p1[2] = {0, 0}, p2[2] = {0, 0};
    int r1 = wr_polygon_first_meeting((const double (*)[2])v, n, false, &f1, &g1, p1);
    int r2 = wr_polygon_first_meeting((const double (*)[2])v, n, true, &f2, &g2, p2);
    if (r1 != r2 || (r1 == 1 && (f1 != f2 || g1 != g2 || p1[0] != p2[0] || p1[1] != p2[1])))
        fail_msg("polygon of %zu: the sweep %d (%zu, %zu), pair by pair %d (%zu, %zu)", n, r1, f1,
                 g1, r2, f2, g2);
    if (r1 == 0)
        t->accepted++;
    else
        t->refused++;
    free(v);
}

static void both_answers(const char *family, const tally *t)
{
    if (t->accepted == 0 || t->refused == 0)
        fail_msg("%s: %d accepted, %d refused: the family must give both", family, t->accepted,
                 t->refused);
}

/* Vertices on a 5 x 5 grid: shared points, touches and collinear overlaps
 * are exact; bulges a few fixed values (a half circle, quarter circles). */
static void test_grid_shapes(void **state)
{
    (void)state;
    static const double bulges[] = {0, 0, 0, 0, 1, -1, 0.4142135623730951, -0.4142135623730951};
    test_rng rng = {0x9e3779b97f4a7c15ULL};
    tally outlines = {0, 0}, polygons = {0, 0};
    shape *s = malloc(sizeof *s);
    for (int trial = 0; trial < 4000; trial++) {
        s->loop_count = 0;
        int loops = trial % 3 == 0 ? 2 : 1;
        for (int l = 0; l < loops; l++) {
            new_loop(s);
            int n = 3 + (int)(test_uniform(&rng) * (l == 0 ? 8 : 4));
            for (int k = 0; k < n; k++) {
                double x = floor(test_uniform(&rng) * 5), y = floor(test_uniform(&rng) * 5);
                if (l > 0) { /* a hole: a smaller grid inside */
                    x = 1 + x / 2;
                    y = 1 + y / 2;
                }
                new_vertex(s, x, y, bulges[(int)(test_uniform(&rng) * 8)]);
            }
        }
        compare_outline(s, &outlines);
        compare_polygon(s, &polygons);
    }
    both_answers("grid outlines", &outlines);
    both_answers("grid polygons", &polygons);
    free(s);
}

/* A star of n vertices at sorted random angles, radii in [0.6, 1], small
 * bulges (simple as drawn); then, in most trials, one vertex moved onto a
 * segment two or more away, or to a multiple of the tolerance from it
 * along its normal (short of it and past it), or onto a vertex. */
static void test_star_shapes(void **state)
{
    (void)state;
    test_rng rng = {0x2545f4914f6cdd1dULL};
    tally outlines = {0, 0}, polygons = {0, 0};
    shape *s = malloc(sizeof *s);
    static const double offsets[] = {0, 0.5, 0.99, 1.01, 2, -0.5, -1.01, 100};
    for (int trial = 0; trial < 600; trial++) {
        s->loop_count = 0;
        new_loop(s);
        int n = 8 + (int)(test_uniform(&rng) * 500);
        bool arcs = trial % 2 == 1;
        for (int k = 0; k < n; k++) {
            double angle = 2 * TEST_PI * (k + 0.8 * test_uniform(&rng)) / n;
            double r = test_range(&rng, 0.6, 1);
            double bulge = arcs ? test_range(&rng, -0.02, 0.02) : 0;
            new_vertex(s, r * cos(angle), r * sin(angle), bulge);
        }
        int move = (int)(test_uniform(&rng) * 10);
        if (move < 8) {
            /* Vertex a onto segment b's chord midpoint (b not next to a),
             * pushed along the chord's normal by a multiple of the
             * outline's tolerance (its size is about 2). */
            int a = (int)(test_uniform(&rng) * n);
            int b = (a + 2 + (int)(test_uniform(&rng) * (n - 3))) % n;
            double *p = s->vertices[0][b], *q = s->vertices[0][(b + 1) % n];
            double d[2] = {q[0] - p[0], q[1] - p[1]}, length = hypot(d[0], d[1]);
            double push = offsets[move] * WR_OUTLINE_TOLERANCE * 2;
            s->vertices[0][a][0] = (p[0] + q[0]) / 2 - push * d[1] / length;
            s->vertices[0][a][1] = (p[1] + q[1]) / 2 + push * d[0] / length;
            s->vertices[0][a][2] = 0;
            s->vertices[0][b][2] = 0;
        } else if (move == 8) {
            int a = (int)(test_uniform(&rng) * n), b = (a + n / 2) % n;
            memcpy(s->vertices[0][a], s->vertices[0][b], sizeof s->vertices[0][a]);
        }
        compare_outline(s, &outlines);
        compare_polygon(s, &polygons);
    }
    both_answers("star outlines", &outlines);
    both_answers("star polygons", &polygons);
    free(s);
}

/* A zigzag of long parallel diagonals joined by short steps: every box
 * overlaps nearly every other, the sweep's worst case.  Sometimes the
 * last diagonal is swung across the others, or onto one of them. */
static void test_zigzags(void **state)
{
    (void)state;
    test_rng rng = {0x853c49e6748fea9bULL};
    tally outlines = {0, 0}, polygons = {0, 0};
    shape *s = malloc(sizeof *s);
    for (int trial = 0; trial < 120; trial++) {
        s->loop_count = 0;
        new_loop(s);
        int teeth = 4 + (int)(test_uniform(&rng) * 120);
        double slope = test_range(&rng, 0.5, 2);
        for (int k = 0; k < teeth; k++) {
            double x = k * 0.01;
            new_vertex(s, x, 0, 0);
            new_vertex(s, x + 1, slope, 0);
            new_vertex(s, x + 1.005, slope, 0);
            new_vertex(s, x + 0.005, 0, 0);
        }
        /* Close it below: down and back to the start. */
        new_vertex(s, teeth * 0.01, -1, 0);
        new_vertex(s, 0, -1, trial % 4 == 1 ? 0.3 : 0);
        int kind = trial % 4;
        if (kind == 2) { /* a tooth's top pushed across its neighbour */
            int k = (int)(test_uniform(&rng) * (teeth - 1));
            s->vertices[0][4 * k + 1][0] += 0.012;
        } else if (kind == 3) { /* onto its neighbour's diagonal */
            int k = (int)(test_uniform(&rng) * (teeth - 1));
            s->vertices[0][4 * k + 1][0] = s->vertices[0][4 * k + 4][0] + 1;
            s->vertices[0][4 * k + 1][1] = slope;
        }
        compare_outline(s, &outlines);
        compare_polygon(s, &polygons);
    }
    both_answers("zigzag outlines", &outlines);
    both_answers("zigzag polygons", &polygons);
    free(s);
}

/* An outer square with circular holes of two half arcs: random, or tangent
 * to an earlier hole or to the outer loop (exactly, or a multiple of the
 * tolerance apart), or a square hole sharing part of an edge with
 * another's line (collinear overlap). */
static void test_holes(void **state)
{
    (void)state;
    test_rng rng = {0xda942042e4dd58b5ULL};
    tally outlines = {0, 0};
    shape *s = malloc(sizeof *s);
    static const double gaps[] = {0, 0, 0.5, 1.5, 3, -1};
    for (int trial = 0; trial < 1500; trial++) {
        s->loop_count = 0;
        new_loop(s);
        new_vertex(s, 0, 0, 0);
        new_vertex(s, 10, 0, 0);
        new_vertex(s, 10, 10, trial % 5 == 0 ? 0.2 : 0);
        new_vertex(s, 0, 10, 0);
        double tolerance = WR_OUTLINE_TOLERANCE * hypot(10, 10);
        int holes = 1 + (int)(test_uniform(&rng) * 20);
        double centres[MAX_LOOPS][2], radii[MAX_LOOPS];
        for (int h = 0; h < holes; h++) {
            new_loop(s);
            double r = test_range(&rng, 0.2, 1), cx, cy;
            int kind = (int)(test_uniform(&rng) * 7);
            double gap = gaps[(int)(test_uniform(&rng) * 6)] * tolerance;
            if (kind == 5 && h > 0) { /* about an earlier hole's centre: in it, or around it */
                int other = (int)(test_uniform(&rng) * h);
                cx = centres[other][0];
                cy = centres[other][1];
                r = radii[other] * (test_uniform(&rng) < 0.5 ? test_range(&rng, 0.2, 0.6)
                                                             : test_range(&rng, 1.5, 2));
                kind = 2;
            } else if (kind == 6) { /* outside the outer loop */
                cx = 11 + r;
                cy = test_range(&rng, 1, 9);
                kind = 2;
            } else if (kind == 0 && h > 0) { /* beside an earlier hole */
                int other = (int)(test_uniform(&rng) * h);
                double angle = test_range(&rng, 0, 2 * TEST_PI);
                double d = radii[other] + r + gap;
                cx = centres[other][0] + d * cos(angle);
                cy = centres[other][1] + d * sin(angle);
            } else if (kind == 1) { /* beside the outer loop's bottom edge */
                cx = test_range(&rng, 1, 9);
                cy = r + gap;
            } else {
                cx = test_range(&rng, 1, 9);
                cy = test_range(&rng, 1, 9);
            }
            centres[h][0] = cx;
            centres[h][1] = cy;
            radii[h] = r;
            if (kind == 4) { /* a square hole of half side r */
                new_vertex(s, cx - r, cy - r, 0);
                new_vertex(s, cx + r, cy - r, 0);
                new_vertex(s, cx + r, cy + r, 0);
                new_vertex(s, cx - r, cy + r, 0);
            } else if (kind == 0) { /* ends on the line of centres' normal */
                new_vertex(s, cx, cy - r, 1);
                new_vertex(s, cx, cy + r, 1);
            } else {
                new_vertex(s, cx + r, cy, 1);
                new_vertex(s, cx - r, cy, 1);
            }
        }
        compare_outline(s, &outlines);
    }
    both_answers("holes", &outlines);
    free(s);
}

/* Arcs meeting lines and arcs tangentially inside one loop: a slot whose
 * end arcs touch a line of the loop at their apex, exactly or a multiple
 * of the tolerance away, and a figure of two circles touching. */
static void test_tangent_arcs(void **state)
{
    (void)state;
    test_rng rng = {0x5851f42d4c957f2dULL};
    tally outlines = {0, 0};
    shape *s = malloc(sizeof *s);
    static const double gaps[] = {0, 0.5, 0.99, 1.01, 2, -0.5};
    for (int trial = 0; trial < 600; trial++) {
        s->loop_count = 0;
        new_loop(s);
        double gap = gaps[trial % 6] * WR_OUTLINE_TOLERANCE * test_range(&rng, 4, 6);
        double r = test_range(&rng, 0.5, 1.5);
        if (trial % 2 == 0) {
            /* A U: up the left, a half circle down at the right whose
             * apex comes to the line y = -gap from above... the bottom
             * line passes under the arc at y = 1 - r - gap. */
            new_vertex(s, 0, 1 - r - gap, 0);
            new_vertex(s, 4, 1 - r - gap, 0);
            new_vertex(s, 4, 3, 0);
            new_vertex(s, 2 + r, 3, 0);
            new_vertex(s, 2 + r, 1, -1); /* clockwise half circle down */
            new_vertex(s, 2 - r, 1, 0);
            new_vertex(s, 2 - r, 3, 0);
            new_vertex(s, 0, 3, 0);
        } else {
            /* Two circles of arcs through the same loop, touching at
             * their nearest points (or apart by the gap). */
            double d = 2 * r + gap;
            new_vertex(s, 0, -r, 0.4142135623730951 * 2.414213562373095);
            new_vertex(s, 0, r, 0.4142135623730951);
            new_vertex(s, -r, 0, 0.4142135623730951);
            new_vertex(s, 0, -r, 0);
            new_vertex(s, d, -r, 1);
            new_vertex(s, d, r, 1);
        }
        compare_outline(s, &outlines);
    }
    both_answers("tangent arcs", &outlines);
    free(s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_grid_shapes),
        cmocka_unit_test(test_star_shapes),
        cmocka_unit_test(test_zigzags),
        cmocka_unit_test(test_holes),
        cmocka_unit_test(test_tangent_arcs),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
