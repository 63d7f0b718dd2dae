/* test_finger.c -- where a round finger fits (lib/wr_finger.h).
 *
 * Closed forms derived here: a disc of radius r wedged into a corner whose
 * free space has angle alpha touches both sides at r cot(alpha / 2) from
 * the corner, so each side is blocked over that length; a slot of width w
 * is blocked wholly when r > w / 2; a hole of radius R takes any finger of
 * r <= R and none larger; a concave fillet of radius f blocks itself and
 * r - f of each side for r > f.  Endpoints to 1e-12 relative.  Then random
 * outlines of lines and arcs against a direct test: the disc against a fine
 * polyline of the boundary, at dense samples away from the spans' ends. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>
#include <stdio.h>

#include "test_util.h"
#include "wr_finger.h"

/* tan(pi / 8): the bulge of a quarter circle. */
#define QUARTER 0.4142135623730951

/* ---- outlines ------------------------------------------------------------------------ */

/* Up to 4 loops of up to 24 vertices, written in place. */
typedef struct shape {
    size_t loop_count;
    size_t counts[4];
    double vertices[4][24][3];
} shape;

static void add_loop(shape *s, size_t count, const double (*vertices)[3])
{
    s->counts[s->loop_count] = count;
    memcpy(s->vertices[s->loop_count], vertices, count * sizeof vertices[0]);
    s->loop_count++;
}

static void add_vertex(shape *s, double x, double y, double bulge)
{
    size_t loop = s->loop_count - 1, n = s->counts[loop]++;
    assert_true(n < 24);
    s->vertices[loop][n][0] = x;
    s->vertices[loop][n][1] = y;
    s->vertices[loop][n][2] = bulge;
}

static void begin_loop(shape *s) { s->counts[s->loop_count++] = 0; }

static wr_outline *build(const shape *s)
{
    wr_loop_spec loops[4];
    for (size_t i = 0; i < s->loop_count; i++) {
        loops[i].vertex_count = s->counts[i];
        loops[i].vertices = (const double (*)[3])s->vertices[i];
    }
    wr_outline *outline;
    wr_error error;
    memset(&error, 0, sizeof error);
    wr_status status = wr_outline_new(loops, s->loop_count, &outline, &error);
    if (status != WR_OK)
        print_error("unexpected refusal: %s: %s\n", error.field, error.reason);
    assert_int_equal(status, WR_OK);
    return outline;
}

/* A circle of radius r about (cx, cy) as two half circles, counter-clockwise
 * (direction +1) or clockwise (-1). */
static void circle_loop(shape *s, double cx, double cy, double r, int direction)
{
    const double loop[2][3] = {{cx - r, cy, direction}, {cx + r, cy, direction}};
    add_loop(s, 2, loop);
}

/* A D-shaped hole: the circle of radius R about (cx, cy) cut by the chord
 * y = cy - e (|e| < R), counter-clockwise: the chord from left to right,
 * then the arc back over the top, of included angle pi + 2 beta,
 * beta = atan2(e, m), m the chord's half length. */
static void d_hole_loop(shape *s, double cx, double cy, double R, double e)
{
    double m = sqrt((R - e) * (R + e)), beta = atan2(e, m);
    double bulge = tan((TEST_PI + 2 * beta) / 4);
    const double loop[2][3] = {{cx - m, cy - e, 0}, {cx + m, cy - e, bulge}};
    add_loop(s, 2, loop);
}

/* The same loop run the other way: segment k becomes segment n - 2 - k
 * (mod n) reversed, its bulge negated. */
static void reverse_loop(shape *s, size_t loop)
{
    size_t n = s->counts[loop];
    double copy[24][3];
    memcpy(copy, s->vertices[loop], sizeof copy);
    for (size_t k = 0; k < n; k++) {
        s->vertices[loop][k][0] = copy[n - 1 - k][0];
        s->vertices[loop][k][1] = copy[n - 1 - k][1];
        s->vertices[loop][k][2] = -copy[(2 * n - 2 - k) % n][2];
    }
}

/* ---- the spans ----------------------------------------------------------------------- */

typedef struct found {
    int count;
    wr_span *spans;
} found;

static found blocked(const wr_outline *o, size_t loop, size_t segment, double r)
{
    found f = {0, NULL};
    assert_int_equal(wr_finger_blocked(o, loop, segment, r, NULL, &f.spans, &f.count), WR_OK);
    /* The contract: sorted, disjoint (a free piece between two), in [0, 1]. */
    for (int i = 0; i < f.count; i++) {
        assert_true(f.spans[i].lo >= 0 && f.spans[i].lo <= f.spans[i].hi && f.spans[i].hi <= 1);
        if (i > 0)
            assert_true(f.spans[i - 1].hi < f.spans[i].lo);
    }
    return f;
}

/* t to 1e-12 relative, and near 0 to 1e-15: the vertices' own rounding
 * (1 + f is not exactly 1 + f) is of that order there. */
static void assert_t(double actual, double expected)
{
    if (!(fabs(actual - expected) <= 1e-12 * fabs(expected) + 1e-15))
        fail_msg("t %.17g differs from %.17g by %.3g", actual, expected, fabs(actual - expected));
}

/* Segment `segment` of loop `loop` is blocked exactly on the n spans given
 * as lo, hi pairs. */
static void expect(const wr_outline *o, size_t loop, size_t segment, double r, int n, ...)
{
    found f = blocked(o, loop, segment, r);
    if (f.count != n) {
        for (int i = 0; i < f.count; i++)
            print_error("  [%.17g, %.17g]\n", f.spans[i].lo, f.spans[i].hi);
        fail_msg("loop %zu segment %zu, r %g: %d spans, %d expected", loop, segment, r, f.count, n);
    }
    va_list args;
    va_start(args, n);
    for (int i = 0; i < n; i++) {
        double lo = va_arg(args, double), hi = va_arg(args, double);
        assert_t(f.spans[i].lo, lo);
        assert_t(f.spans[i].hi, hi);
    }
    va_end(args);
    free(f.spans);
}

/* Every segment of the outline free but those listed (their spans checked
 * by the caller). */
static void expect_free_but(const wr_outline *o, double r, size_t loop, size_t skip_count,
                            const size_t *skip)
{
    for (size_t i = 0; i < o->loop_count; i++)
        for (size_t j = 0; j < o->loops[i].segment_count; j++) {
            bool skipped = false;
            for (size_t k = 0; k < skip_count; k++)
                skipped |= i == loop && j == skip[k];
            if (!skipped)
                expect(o, i, j, r, 0);
        }
}

/* ---- the contract's edges ------------------------------------------------------------ */

static bool always(void *context)
{
    (void)context;
    return true;
}

static void test_radius_zero_invalid_append_stop(void **state)
{
    (void)state;
    shape s = {0};
    const double square[4][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
    add_loop(&s, 4, square);
    circle_loop(&s, 0.5, 0.5, 0.1, 1);
    wr_outline *o = build(&s);
    wr_span *spans = NULL;
    int count = 0;
    /* Radius 0: a point fits anywhere, even in the smallest hole. */
    assert_int_equal(wr_finger_blocked(o, 1, 0, 0, NULL, &spans, &count), WR_OK);
    assert_int_equal(count, 0);
    assert_null(spans);
    const double bad[] = {-1e-300, -1, NAN, INFINITY, -INFINITY};
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++)
        assert_int_equal(wr_finger_blocked(o, 0, 0, bad[i], NULL, &spans, &count), WR_INVALID);
    assert_int_equal(wr_finger_blocked(o, 2, 0, 0.1, NULL, &spans, &count), WR_INVALID);
    assert_int_equal(wr_finger_blocked(o, 0, 4, 0.1, NULL, &spans, &count), WR_INVALID);
    assert_int_equal(wr_finger_blocked(o, 1, 2, 0.1, NULL, &spans, &count), WR_INVALID);
    assert_int_equal(count, 0);
    /* Appended after what the array holds; a stop leaves it as it was. */
    spans = malloc(sizeof *spans);
    spans[0] = (wr_span){0.25, 0.5};
    count = 1;
    assert_int_equal(wr_finger_blocked(o, 1, 0, 0.2, NULL, &spans, &count), WR_OK);
    assert_int_equal(wr_finger_blocked(o, 1, 1, 0.2, NULL, &spans, &count), WR_OK);
    assert_int_equal(count, 3);
    assert_true(spans[0].lo == 0.25 && spans[0].hi == 0.5);
    assert_true(spans[1].lo == 0 && spans[1].hi == 1 && spans[2].lo == 0 && spans[2].hi == 1);
    wr_stop stop = {always, NULL};
    wr_span *before = spans;
    assert_int_equal(wr_finger_blocked(o, 1, 0, 0.05, &stop, &spans, &count), WR_STOPPED);
    assert_int_equal(count, 3);
    assert_ptr_equal(spans, before);
    free(spans);
    wr_outline_free(o);
}

/* ---- polygons ------------------------------------------------------------------------ */

/* A convex polygon has no concave corner: nothing blocks, whatever r, in
 * either orientation. */
static void test_convex_polygons_free(void **state)
{
    (void)state;
    const double radii[] = {1e-6, 0.01, 0.3, 0.5, 1, 3, 1e3};
    for (int written = 0; written < 2; written++) {
        shape s = {0};
        const double square[4][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
        add_loop(&s, 4, square);
        if (written)
            reverse_loop(&s, 0);
        wr_outline *o = build(&s);
        for (size_t i = 0; i < sizeof radii / sizeof radii[0]; i++)
            expect_free_but(o, radii[i], 0, 0, NULL);
        wr_outline_free(o);
    }
    shape s = {0};
    begin_loop(&s);
    for (int k = 0; k < 7; k++)
        add_vertex(&s, 2 + cos(2 * TEST_PI * k / 7), -1 + 1.5 * sin(2 * TEST_PI * k / 7), 0);
    wr_outline *o = build(&s);
    for (size_t i = 0; i < sizeof radii / sizeof radii[0]; i++)
        expect_free_but(o, radii[i], 0, 0, NULL);
    wr_outline_free(o);
}

/* A plate [-2, w + 2] x [-2, d] with a slot [0, w] x [0, d] cut from its
 * top; its right wall rises to step (the plate right of the slot is lower
 * when step < d).  Segments: 0 bottom, 1 right side, 2 top right of the
 * slot (leftwards), 3 the slot's right wall (down), 4 its bottom
 * (leftwards), 5 its left wall (up), 6 top left, 7 left side. */
static void slot_plate(shape *s, double w, double d, double step)
{
    const double loop[8][3] = {{-2, -2, 0}, {w + 2, -2, 0}, {w + 2, step, 0}, {w, step, 0},
                               {w, 0, 0},   {0, 0, 0},      {0, d, 0},      {-2, d, 0}};
    add_loop(s, 8, loop);
}

static void test_slot(void **state)
{
    (void)state;
    const double w = 1, d = 3;
    shape s = {0};
    slot_plate(&s, w, d, d);
    wr_outline *o = build(&s);
    const size_t slot[] = {3, 4, 5};
    /* r < w / 2: blocked within r of each inner (90 degree) corner:
     * r cot(45 degrees) = r. */
    const double narrow[] = {0.01, 0.1, 0.3, 0.49};
    for (size_t i = 0; i < sizeof narrow / sizeof narrow[0]; i++) {
        double r = narrow[i];
        expect(o, 0, 3, r, 1, 1 - r / d, 1.0);
        expect(o, 0, 4, r, 2, 0.0, r / w, 1 - r / w, 1.0);
        expect(o, 0, 5, r, 1, 0.0, r / d);
        expect_free_but(o, r, 0, 3, slot);
    }
    /* r = w / 2: the finger touches both walls (tangency, not overlap), and
     * is wedged only at the bottom, which it fills. */
    expect(o, 0, 3, 0.5, 1, 1 - 0.5 / d, 1.0);
    expect(o, 0, 4, 0.5, 1, 0.0, 1.0);
    expect(o, 0, 5, 0.5, 1, 0.0, 0.5 / d);
    /* r > w / 2: the opposite wall is within w - r < r everywhere; beyond
     * w the centre is in the material. */
    const double wide[] = {0.51, 0.7, 1.5, 4};
    for (size_t i = 0; i < sizeof wide / sizeof wide[0]; i++) {
        for (size_t k = 0; k < 3; k++)
            expect(o, 0, slot[k], wide[i], 1, 0.0, 1.0);
        expect_free_but(o, wide[i], 0, 3, slot);
    }
    wr_outline_free(o);

    /* The right of the slot lower (step < d): past the step the left wall
     * is blocked while the step's corner (w, step) is within r of the
     * centre (r, y): (w - r)^2 + (y - step)^2 < r^2, up to
     * y = step + sqrt(w (2 r - w)). */
    const double step = 1.5;
    s = (shape){0};
    slot_plate(&s, w, d, step);
    o = build(&s);
    const double radii[] = {0.51, 0.7, 0.9, 0.99};
    for (size_t i = 0; i < sizeof radii / sizeof radii[0]; i++) {
        double r = radii[i];
        expect(o, 0, 3, r, 1, 0.0, 1.0);
        expect(o, 0, 4, r, 1, 0.0, 1.0);
        expect(o, 0, 5, r, 1, 0.0, (step + sqrt(w * (2 * r - w))) / d);
        expect_free_but(o, r, 0, 3, slot);
    }
    expect(o, 0, 3, 0.3, 1, 1 - 0.3 / step, 1.0);
    expect(o, 0, 5, 0.3, 1, 0.0, 0.3 / d);

    /* Written clockwise: segment k is segment 6 - k (mod 8) reversed, its
     * spans [1 - hi, 1 - lo]. */
    shape reversed = s;
    reverse_loop(&reversed, 0);
    wr_outline *back = build(&reversed);
    for (size_t k = 0; k < 8; k++) {
        found forward = blocked(o, 0, k, 0.7), other = blocked(back, 0, (14 - k) % 8, 0.7);
        assert_int_equal(forward.count, other.count);
        for (int i = 0; i < forward.count; i++) {
            int j = forward.count - 1 - i;
            assert_true(fabs(forward.spans[i].lo - (1 - other.spans[j].hi)) <= 1e-12);
            assert_true(fabs(forward.spans[i].hi - (1 - other.spans[j].lo)) <= 1e-12);
        }
        free(forward.spans);
        free(other.spans);
    }
    wr_outline_free(back);
    wr_outline_free(o);
}

/* A V notch of free angle alpha, its walls of length 2, cut into the top
 * of a plate: each wall is blocked over r cot(alpha / 2) from the apex. */
static void test_corner_angles(void **state)
{
    (void)state;
    const double degrees[] = {20, 45, 60, 90, 120, 150, 170};
    const double radii[] = {0.05, 0.2};
    const double length = 2;
    for (size_t i = 0; i < sizeof degrees / sizeof degrees[0]; i++) {
        double half = degrees[i] * TEST_PI / 360;
        double x = length * sin(half), h = length * cos(half);
        shape s = {0};
        const double loop[7][3] = {{-x - 2, -2, 0}, {x + 2, -2, 0}, {x + 2, h, 0}, {x, h, 0},
                                   {0, 0, 0},       {-x, h, 0},     {-x - 2, h, 0}};
        add_loop(&s, 7, loop);
        wr_outline *o = build(&s);
        for (size_t j = 0; j < sizeof radii / sizeof radii[0]; j++) {
            double r = radii[j], blocked_length = r / tan(half);
            /* Segment 3 runs down the right wall to the apex, 4 up the left. */
            expect(o, 0, 3, r, 1, 1 - blocked_length / length, 1.0);
            expect(o, 0, 4, r, 1, 0.0, blocked_length / length);
            expect_free_but(o, r, 0, 2, (const size_t[]){3, 4});
        }
        wr_outline_free(o);
    }
}

/* ---- arcs ------------------------------------------------------------------------------ */

/* A hole of radius R: a finger inside it fits iff r <= R (at r = R it
 * touches the whole circle), in either orientation of the hole; a disc
 * part is convex and takes any finger. */
static void test_hole_and_disc(void **state)
{
    (void)state;
    const double R = 1;
    for (int direction = -1; direction <= 1; direction += 2) {
        shape s = {0};
        const double square[4][3] = {{-5, -5, 0}, {5, -5, 0}, {5, 5, 0}, {-5, 5, 0}};
        add_loop(&s, 4, square);
        circle_loop(&s, 0.25, -0.5, R, direction);
        wr_outline *o = build(&s);
        const double fits[] = {0.01, 0.5, 0.999999, 1};
        for (size_t i = 0; i < sizeof fits / sizeof fits[0]; i++)
            expect_free_but(o, fits[i], 0, 0, NULL);
        const double too_big[] = {1.000001, 1.5, 2, 3};
        for (size_t i = 0; i < sizeof too_big / sizeof too_big[0]; i++) {
            expect(o, 1, 0, too_big[i], 1, 0.0, 1.0);
            expect(o, 1, 1, too_big[i], 1, 0.0, 1.0);
            expect_free_but(o, too_big[i], 1, 2, (const size_t[]){0, 1});
        }
        wr_outline_free(o);
    }
    shape s = {0};
    circle_loop(&s, 3, 4, 2, 1);
    wr_outline *o = build(&s);
    const double radii[] = {0.1, 2, 5, 100};
    for (size_t i = 0; i < sizeof radii / sizeof radii[0]; i++)
        expect_free_but(o, radii[i], 0, 0, NULL);
    wr_outline_free(o);
}

/* An L whose inner corner (1, 1) is filleted with radius f (a concave
 * quarter circle, its centre (1 + f, 1 + f) in the free space).  For
 * r <= f the finger fits everywhere; for r > f the fillet is blocked wholly
 * and each wall over r - f from the fillet: the centre (x, 1 + r) comes
 * within r of the other wall while x < 1 + r. */
static void test_concave_fillet(void **state)
{
    (void)state;
    const double fillets[] = {0.1, 0.3};
    for (size_t i = 0; i < sizeof fillets / sizeof fillets[0]; i++) {
        double f = fillets[i];
        shape s = {0};
        const double loop[7][3] = {{0, 0, 0}, {4, 0, 0},         {4, 1, 0}, {1 + f, 1, -QUARTER},
                                   {1, 1 + f, 0}, {1, 4, 0}, {0, 4, 0}};
        add_loop(&s, 7, loop);
        wr_outline *o = build(&s);
        double wall = 3 - f;
        const double fits[] = {f / 2, f};
        for (size_t j = 0; j < sizeof fits / sizeof fits[0]; j++)
            expect_free_but(o, fits[j], 0, 0, NULL);
        const double radii[] = {f * 1.001, 0.5, 0.8, 0.95};
        for (size_t j = 0; j < sizeof radii / sizeof radii[0]; j++) {
            double r = radii[j];
            expect(o, 0, 2, r, 1, 1 - (r - f) / wall, 1.0);
            expect(o, 0, 3, r, 1, 0.0, 1.0);
            expect(o, 0, 4, r, 1, 0.0, (r - f) / wall);
            expect_free_but(o, r, 0, 3, (const size_t[]){2, 3, 4});
        }
        wr_outline_free(o);
    }
}

/* A slot of width w with a round end (a concave half circle, bulge -1):
 * up to r = w / 2 the finger fits everywhere, touching at r = w / 2 both
 * walls and the end; beyond it the walls and the end are blocked wholly.
 * A rounded (convex) corner of the plate blocks nothing. */
static void test_round_ended_slot(void **state)
{
    (void)state;
    const double w = 1, d = 3;
    shape s = {0};
    const double loop[9][3] = {{-2, -2, 0},      {w + 1.5, -2, QUARTER}, {w + 2, -1.5, 0},
                               {w + 2, d, 0},    {w, d, 0},              {w, 0, -1},
                               {0, 0, 0},        {0, d, 0},              {-2, d, 0}};
    add_loop(&s, 9, loop);
    wr_outline *o = build(&s);
    const double fits[] = {0.01, 0.25, 0.4999999, 0.5};
    for (size_t i = 0; i < sizeof fits / sizeof fits[0]; i++)
        expect_free_but(o, fits[i], 0, 0, NULL);
    const double wide[] = {0.5000001, 0.6, 0.75, 1.2};
    for (size_t i = 0; i < sizeof wide / sizeof wide[0]; i++) {
        for (size_t k = 4; k <= 6; k++)
            expect(o, 0, k, wide[i], 1, 0.0, 1.0);
        expect_free_but(o, wide[i], 0, 3, (const size_t[]){4, 5, 6});
    }
    wr_outline_free(o);
}

/* The slot's right lip rounded (a convex quarter circle of radius g about
 * (w + g, d - g)).  For w / 2 < r the left wall is blocked while the
 * centre (r, y) is within g + r of the lip's centre: up to
 * y = d - g + sqrt((g + r)^2 - (w + g - r)^2)
 *   = d - g + sqrt((2 r - w) (2 g + w)),
 * on the lip there while the finger's centre, at angle theta about the
 * lip's centre, is nearer than r to the left wall: w + g + (g + r) cos
 * theta < r (both below the lip's top for r < 0.5625 here). */
static void test_rounded_lip(void **state)
{
    (void)state;
    const double w = 1, d = 3, g = 0.5;
    shape s = {0};
    const double loop[9][3] = {{-2, -2, 0},        {w + 2, -2, 0}, {w + 2, d, 0},
                               {w + g, d, QUARTER}, {w, d - g, 0},  {w, 0, 0},
                               {0, 0, 0},          {0, d, 0},      {-2, d, 0}};
    add_loop(&s, 9, loop);
    wr_outline *o = build(&s);
    const size_t slot[] = {3, 4, 5, 6};
    expect(o, 0, 4, 0.3, 1, 1 - 0.3 / (d - g), 1.0);
    expect(o, 0, 5, 0.3, 2, 0.0, 0.3, 0.7, 1.0);
    expect(o, 0, 6, 0.3, 1, 0.0, 0.1);
    expect_free_but(o, 0.3, 0, 3, (const size_t[]){4, 5, 6});
    const double radii[] = {0.51, 0.53, 0.56};
    for (size_t i = 0; i < sizeof radii / sizeof radii[0]; i++) {
        double r = radii[i];
        double theta = acos((r - w - g) / (g + r));
        expect(o, 0, 3, r, 1, (theta - TEST_PI / 2) / (TEST_PI / 2), 1.0);
        expect(o, 0, 4, r, 1, 0.0, 1.0);
        expect(o, 0, 5, r, 1, 0.0, 1.0);
        expect(o, 0, 6, r, 1, 0.0, (d - g + sqrt((2 * r - w) * (2 * g + w))) / d);
        expect_free_but(o, r, 0, 4, slot);
    }
    wr_outline_free(o);
}

/* A D-shaped hole (test d_hole_loop's circle R = 1 about the origin, its
 * chord at y = -e, e = 0.4).  On the chord (segment 0, x from -m to m) the
 * disc above it fits iff it is inside the circle: |c| <= R - r with
 * c = (x, r - e), so blocked for |x| > X = sqrt((R - r)^2 - (r - e)^2).
 * On the arc (segment 1, angle theta from -beta to pi + beta) the centre
 * runs at (R - r) (cos theta, sin theta) and the disc crosses the chord's
 * line where (R - r) sin theta < r - e: below theta_1 = asin((r - e) /
 * (R - r)) and above pi - theta_1.  Past R - r < |r - e| nothing fits. */
static void test_d_hole(void **state)
{
    (void)state;
    const double R = 1, e = 0.4, m = sqrt((R - e) * (R + e)), beta = atan2(e, m);
    shape s = {0};
    const double square[4][3] = {{-3, -3, 0}, {3, -3, 0}, {3, 3, 0}, {-3, 3, 0}};
    add_loop(&s, 4, square);
    d_hole_loop(&s, 0, 0, R, e);
    for (int written = 0; written < 2; written++) {
        wr_outline *o = build(&s);
        const double radii[] = {0.1, 0.3, 0.5, 0.6};
        for (size_t i = 0; i < sizeof radii / sizeof radii[0]; i++) {
            double r = radii[i];
            double x = sqrt((R - r) * (R - r) - (r - e) * (r - e));
            double theta = asin((r - e) / (R - r)), sweep = TEST_PI + 2 * beta;
            /* Written clockwise, each segment is run backwards: the same
             * spans, mirrored. */
            double chord[4] = {0, (m - x) / (2 * m), (m + x) / (2 * m), 1};
            double arc[4] = {0, (theta + beta) / sweep, (TEST_PI - theta + beta) / sweep, 1};
            if (!written) {
                expect(o, 1, 0, r, 2, chord[0], chord[1], chord[2], chord[3]);
                expect(o, 1, 1, r, 2, arc[0], arc[1], arc[2], arc[3]);
            } else {
                expect(o, 1, 0, r, 2, 1 - chord[3], 1 - chord[2], 1 - chord[1], 1 - chord[0]);
                expect(o, 1, 1, r, 2, 1 - arc[3], 1 - arc[2], 1 - arc[1], 1 - arc[0]);
            }
            expect_free_but(o, r, 1, 2, (const size_t[]){0, 1});
        }
        expect(o, 1, 0, 0.75, 1, 0.0, 1.0);
        expect(o, 1, 1, 0.75, 1, 0.0, 1.0);
        wr_outline_free(o);
        reverse_loop(&s, 1);
    }
}

/* ---- random outlines against a direct test ------------------------------------------ */

/* The boundary as a polyline: each segment's points from t = 0 to 1, an
 * arc's so close that its chords stray less than SAGITTA * size from it;
 * in pieces of at most PIECE edges, each with its points' box, so that the
 * direct test looks only at those within reach. */
#define SAGITTA 1e-10
#define PIECE 32
typedef struct piece {
    size_t first, count; /* edges first .. first + count - 1 of `points` */
    double box_min[2], box_max[2];
} piece;
typedef struct polyline {
    double (*points)[2];
    piece *pieces;
    size_t piece_count;
} polyline;

static polyline polyline_new(const wr_outline *o)
{
    polyline p = {NULL, NULL, 0};
    size_t capacity = 0, used = 0, piece_capacity = 0;
    for (size_t i = 0; i < o->loop_count; i++)
        for (size_t j = 0; j < o->loops[i].segment_count; j++) {
            const wr_segment *s = &o->loops[i].segments[j];
            size_t n = 1;
            if (s->bulge != 0) /* a chord of angle x strays R x^2 / 8 */
                n = (size_t)ceil(fabs(s->sweep) / sqrt(8 * SAGITTA * o->size / s->radius));
            if (used + n + 1 > capacity) {
                capacity = 2 * (used + n + 1);
                p.points = realloc(p.points, capacity * sizeof *p.points);
            }
            for (size_t k = 0; k <= n; k++)
                wr_outline_boundary(o, i, j, (double)k / n, p.points[used + k], NULL);
            for (size_t first = 0; first < n; first += PIECE) {
                if (p.piece_count == piece_capacity) {
                    piece_capacity = 2 * piece_capacity + 16;
                    p.pieces = realloc(p.pieces, piece_capacity * sizeof *p.pieces);
                }
                piece *q = &p.pieces[p.piece_count++];
                q->first = used + first;
                q->count = n - first < PIECE ? n - first : PIECE;
                q->box_min[0] = q->box_min[1] = INFINITY;
                q->box_max[0] = q->box_max[1] = -INFINITY;
                for (size_t k = q->first; k <= q->first + q->count; k++)
                    for (int a = 0; a < 2; a++) {
                        q->box_min[a] = fmin(q->box_min[a], p.points[k][a]);
                        q->box_max[a] = fmax(q->box_max[a], p.points[k][a]);
                    }
            }
            used += n + 1;
        }
    return p;
}

static void polyline_free(polyline *p)
{
    free(p->points);
    free(p->pieces);
}

/* The squared distance from c to edge ab. */
static double point_edge(const double c[2], const double a[2], const double b[2])
{
    double d[2] = {b[0] - a[0], b[1] - a[1]}, e[2] = {c[0] - a[0], c[1] - a[1]};
    double s = fmax(0.0, fmin(1.0, (d[0] * e[0] + d[1] * e[1]) / (d[0] * d[0] + d[1] * d[1])));
    double x = e[0] - s * d[0], y = e[1] - s * d[1];
    return x * x + y * y;
}

/* The disc of radius `reach` about c meets the polyline, or c is inside it
 * (an odd number of its edges cross the ray from c to +x). */
static bool direct_blocked(const polyline *p, const double c[2], double reach)
{
    for (size_t i = 0; i < p->piece_count; i++) {
        const piece *q = &p->pieces[i];
        double dx = fmax(0.0, fmax(q->box_min[0] - c[0], c[0] - q->box_max[0]));
        double dy = fmax(0.0, fmax(q->box_min[1] - c[1], c[1] - q->box_max[1]));
        if (dx * dx + dy * dy >= reach * reach)
            continue;
        for (size_t k = q->first; k < q->first + q->count; k++)
            if (point_edge(c, p->points[k], p->points[k + 1]) < reach * reach)
                return true;
    }
    bool inside = false;
    for (size_t i = 0; i < p->piece_count; i++) {
        const piece *q = &p->pieces[i];
        if (c[1] < q->box_min[1] || c[1] > q->box_max[1] || c[0] > q->box_max[0])
            continue;
        for (size_t k = q->first; k < q->first + q->count; k++) {
            const double *a = p->points[k], *b = p->points[k + 1];
            if ((a[1] > c[1]) != (b[1] > c[1]) &&
                a[0] + (c[1] - a[1]) * (b[0] - a[0]) / (b[1] - a[1]) > c[0])
                inside = !inside;
        }
    }
    return inside;
}

/* The distance from c to the polyline. */
static double direct_distance(const polyline *p, const double c[2])
{
    double best = INFINITY;
    for (size_t i = 0; i < p->piece_count; i++) {
        const piece *q = &p->pieces[i];
        double dx = fmax(0.0, fmax(q->box_min[0] - c[0], c[0] - q->box_max[0]));
        double dy = fmax(0.0, fmax(q->box_min[1] - c[1], c[1] - q->box_max[1]));
        if (dx * dx + dy * dy >= best)
            continue;
        for (size_t k = q->first; k < q->first + q->count; k++)
            best = fmin(best, point_edge(c, p->points[k], p->points[k + 1]));
    }
    return sqrt(best);
}

/* An L of random arms; its inner corner filleted (concave) or not, two
 * outer corners rounded (convex) or not, a round or D-shaped hole in the
 * upright or none. */
static void random_l(test_rng *rng, shape *s)
{
    double a = test_range(rng, 2.5, 4), d = test_range(rng, 2.5, 4);
    double cx = test_range(rng, 0.6, 1.5), b = test_range(rng, 0.6, 1.5);
    double f = test_uniform(rng) < 0.67 ? test_range(rng, 0.05, 0.4) * fmin(a - cx, d - b) : 0;
    double g0 = test_uniform(rng) < 0.5 ? test_range(rng, 0.05, 0.3) * b : 0;
    double g1 = test_uniform(rng) < 0.5 ? test_range(rng, 0.05, 0.3) * b : 0;
    begin_loop(s);
    add_vertex(s, 0, 0, 0);
    if (g0 > 0) {
        add_vertex(s, a - g0, 0, QUARTER);
        add_vertex(s, a, g0, 0);
    } else {
        add_vertex(s, a, 0, 0);
    }
    if (g1 > 0) {
        add_vertex(s, a, b - g1, QUARTER);
        add_vertex(s, a - g1, b, 0);
    } else {
        add_vertex(s, a, b, 0);
    }
    if (f > 0) {
        add_vertex(s, cx + f, b, -QUARTER);
        add_vertex(s, cx, b + f, 0);
    } else {
        add_vertex(s, cx, b, 0);
    }
    add_vertex(s, cx, d, 0);
    add_vertex(s, 0, d, 0);
    double hole = test_range(rng, 0.1, 0.3) * fmin(cx, d - b), choice = test_uniform(rng);
    if (choice < 0.33) {
        circle_loop(s, cx / 2, (b + d) / 2, hole, choice < 0.16 ? 1 : -1);
    } else if (choice < 0.67) {
        d_hole_loop(s, cx / 2, (b + d) / 2, hole, test_range(rng, -0.8, 0.8) * hole);
        if (choice < 0.5)
            reverse_loop(s, s->loop_count - 1);
    }
}

/* A plate with a slot from its top, its end square or round (a concave
 * half circle), its lips sharp or rounded, and a hole below it. */
static void random_slot(test_rng *rng, shape *s)
{
    double W = test_range(rng, 3, 5), H = test_range(rng, 2.5, 4);
    double w = test_range(rng, 0.3, 1.2), x0 = test_range(rng, 0.5, W - 0.5 - w);
    bool round = test_uniform(rng) < 0.5;
    double depth = test_range(rng, 0.5, H - 1.2 - (round ? w / 2 : 0));
    double floor = H - depth - (round ? w / 2 : 0); /* the lowest point of the slot */
    begin_loop(s);
    add_vertex(s, 0, 0, 0);
    add_vertex(s, W, 0, 0);
    add_vertex(s, W, H, 0);
    /* Either lip rounded (convex quarter circles) or sharp. */
    double right = test_uniform(rng) < 0.5 ? test_range(rng, 0.1, 0.9) * fmin(depth, 0.45) : 0;
    double left = test_uniform(rng) < 0.5 ? test_range(rng, 0.1, 0.9) * fmin(depth, 0.45) : 0;
    if (right > 0)
        add_vertex(s, x0 + w + right, H, QUARTER);
    add_vertex(s, x0 + w, H - right, 0);
    add_vertex(s, x0 + w, H - depth, round ? -1 : 0);
    add_vertex(s, x0, H - depth, 0);
    add_vertex(s, x0, H - left, left > 0 ? QUARTER : 0);
    if (left > 0)
        add_vertex(s, x0 - left, H, 0);
    add_vertex(s, 0, H, 0);
    double radius = test_range(rng, 0.1, 0.35) * floor;
    circle_loop(s, test_range(rng, radius + 0.2, W - radius - 0.2), floor / 2, radius,
                test_uniform(rng) < 0.5 ? 1 : -1);
}

/* A plate with a keyhole notch in its top: a concave arc of more than a
 * half circle, its mouth narrower than it. */
static void random_keyhole(test_rng *rng, shape *s)
{
    double W = test_range(rng, 3, 5), H = test_range(rng, 2, 3);
    double R = test_range(rng, 0.3, 0.8), e = test_range(rng, 0.05, 0.8) * R;
    double m = sqrt(R * R - e * e), x0 = test_range(rng, R + 0.3, W - R - 0.3);
    double beta = atan2(e, m);
    begin_loop(s);
    add_vertex(s, 0, 0, 0);
    add_vertex(s, W, 0, 0);
    add_vertex(s, W, H, 0);
    add_vertex(s, x0 + m, H, -tan((TEST_PI + 2 * beta) / 4));
    add_vertex(s, x0 - m, H, 0);
    add_vertex(s, 0, H, 0);
}

/* A convex arc of more than a half circle over a chord with a square
 * notch. */
static void random_mushroom(test_rng *rng, shape *s)
{
    double theta = test_range(rng, 200, 320) * TEST_PI / 180;
    double half = theta / 2, R = 1 / sin(half), top = R - R * cos(half);
    double nw = test_range(rng, 0.1, 0.5), nd = test_range(rng, 0.1, 0.8) * top;
    begin_loop(s);
    add_vertex(s, -1, 0, 0);
    add_vertex(s, -nw, 0, 0);
    add_vertex(s, -nw, nd, 0);
    add_vertex(s, nw, nd, 0);
    add_vertex(s, nw, 0, 0);
    add_vertex(s, 1, 0, tan(theta / 4));
}

/* Each segment at SAMPLES jittered points: the spans against the direct
 * test, away from their ends.  The direct test blocks below r - BAND: above
 * the library's tolerance (the polyline's chords of a concave arc come
 * SAGITTA nearer than the arc), so that both disagree only where the
 * disc's overlap is within BAND, next to a span's end. */
#define SAMPLES 400
#define BAND 2e-9
#ifndef RANDOM_OUTLINES /* per family; more for a longer hunt */
#define RANDOM_OUTLINES 6
#endif
#define END_MARGIN 1e-6
static void cross_check(const wr_outline *o, double r, test_rng *rng, long *samples, long *ends)
{
    polyline p = polyline_new(o);
    double reach = r - BAND * o->size;
    for (size_t i = 0; i < o->loop_count; i++)
        for (size_t j = 0; j < o->loops[i].segment_count; j++) {
            found f = blocked(o, i, j, r);
            /* At a span's end inside the segment the disc touches the
             * material: its centre is r from the boundary (the polyline
             * strays SAGITTA from it). */
            for (int m = 0; m < 2 * f.count; m++) {
                double t = m % 2 ? f.spans[m / 2].hi : f.spans[m / 2].lo;
                if (t == 0 || t == 1)
                    continue;
                double point[2], normal[2];
                wr_outline_boundary(o, i, j, t, point, normal);
                double c[2] = {point[0] - r * normal[0], point[1] - r * normal[1]};
                double distance = direct_distance(&p, c);
                if (!(fabs(distance - r) <= 2 * SAGITTA * o->size))
                    fail_msg("loop %zu segment %zu, r %.17g: at the end t %.17g the centre is "
                             "%.17g from the boundary",
                             i, j, r, t, distance);
                (*ends)++;
            }
            for (int k = 0; k < SAMPLES; k++) {
                double t = (k + test_uniform(rng)) / SAMPLES;
                bool exact = false, near_end = false;
                for (int m = 0; m < f.count; m++) {
                    exact |= f.spans[m].lo <= t && t <= f.spans[m].hi;
                    near_end |= (fabs(t - f.spans[m].lo) < END_MARGIN && f.spans[m].lo > 0) ||
                                (fabs(t - f.spans[m].hi) < END_MARGIN && f.spans[m].hi < 1);
                }
                if (near_end)
                    continue;
                double point[2], normal[2];
                wr_outline_boundary(o, i, j, t, point, normal);
                double c[2] = {point[0] - r * normal[0], point[1] - r * normal[1]};
                bool direct = direct_blocked(&p, c, reach);
                if (direct != exact) {
                    for (int m = 0; m < f.count; m++)
                        print_error("  [%.17g, %.17g]\n", f.spans[m].lo, f.spans[m].hi);
                    fail_msg("loop %zu segment %zu, r %.17g, t %.17g: blocked %d, directly %d", i,
                             j, r, t, exact, direct);
                }
                (*samples)++;
            }
            free(f.spans);
        }
    polyline_free(&p);
}

static void test_random_outlines(void **state)
{
    (void)state;
    void (*const families[])(test_rng *, shape *) = {random_l, random_slot, random_keyhole,
                                                      random_mushroom};
    const char *names[] = {"L", "slot", "keyhole", "mushroom"};
    test_rng rng = {0x5eed0f1f6e12ULL};
    long samples = 0, ends = 0;
    int outlines = 0;
    for (size_t family = 0; family < 4; family++)
        for (int k = 0; k < RANDOM_OUTLINES; k++) {
            shape s = {0};
            families[family](&rng, &s);
            if (test_uniform(&rng) < 0.5)
                reverse_loop(&s, 0);
            wr_outline *o = build(&s);
            for (int m = 0; m < 3; m++) {
                double r = 0.02 * pow(75, test_uniform(&rng));
                long before = samples;
                cross_check(o, r, &rng, &samples, &ends);
                assert_true(samples > before);
                (void)names;
            }
            outlines++;
            wr_outline_free(o);
        }
    print_message("finger: %d random outlines x 3 radii: %ld samples agree with the direct "
                  "test; at %ld span ends the finger touches\n",
                  outlines, samples, ends);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_radius_zero_invalid_append_stop),
        cmocka_unit_test(test_convex_polygons_free),
        cmocka_unit_test(test_slot),
        cmocka_unit_test(test_corner_angles),
        cmocka_unit_test(test_hole_and_disc),
        cmocka_unit_test(test_concave_fillet),
        cmocka_unit_test(test_round_ended_slot),
        cmocka_unit_test(test_rounded_lip),
        cmocka_unit_test(test_d_hole),
        cmocka_unit_test(test_random_outlines),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
