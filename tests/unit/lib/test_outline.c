/* test_outline.c -- outlines of lines and arcs (lib/wr_outline.h): mass
 * properties against closed forms derived here independently (pieces of
 * discs and rectangles, the parallel-axis theorem, the shoelace formulas),
 * orientation independence, boundary points and normals, and the refusals
 * with their fields and points. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>
#include <stdio.h>

#include "test_util.h"
#include "wr_outline.h"

/* tan(pi / 8): the bulge of a quarter circle. */
#define QUARTER 0.4142135623730951

/* Up to 4 loops of up to 16 vertices, written in place. */
typedef struct shape {
    size_t loop_count;
    size_t counts[4];
    double vertices[4][16][3];
} shape;

static void add_loop(shape *s, size_t count, const double (*vertices)[3])
{
    s->counts[s->loop_count] = count;
    memcpy(s->vertices[s->loop_count], vertices, count * sizeof vertices[0]);
    s->loop_count++;
}

static wr_status build(const shape *s, wr_outline **out, wr_error *error)
{
    wr_loop_spec loops[4];
    for (size_t i = 0; i < s->loop_count; i++) {
        loops[i].vertex_count = s->counts[i];
        loops[i].vertices = (const double (*)[3])s->vertices[i];
    }
    memset(error, 0, sizeof *error);
    return wr_outline_new(loops, s->loop_count, out, error);
}

static wr_outline *build_ok(const shape *s)
{
    wr_outline *outline;
    wr_error error;
    wr_status status = build(s, &outline, &error);
    if (status != WR_OK)
        print_error("unexpected refusal: %s: %s\n", error.field, error.reason);
    assert_int_equal(status, WR_OK);
    return outline;
}

/* The same loop run the other way: vertex k of the reversed loop is vertex
 * n-1-k, and its segment k is segment n-2-k reversed, whose bulge changes
 * sign. */
static void reverse_loop(shape *s, size_t loop)
{
    size_t n = s->counts[loop];
    double copy[16][3];
    memcpy(copy, s->vertices[loop], sizeof copy);
    for (size_t k = 0; k < n; k++) {
        s->vertices[loop][k][0] = copy[n - 1 - k][0];
        s->vertices[loop][k][1] = copy[n - 1 - k][1];
        s->vertices[loop][k][2] = -copy[(2 * n - 2 - k) % n][2];
    }
}

static void assert_near(double actual, double expected, double tolerance)
{
    if (!(fabs(actual - expected) <= tolerance))
        fail_msg("%.17g differs from %.17g by %.3g", actual, expected, fabs(actual - expected));
}

/* Relative to the value, absolute below 1 (normals, coordinates). */
static void assert_close(double actual, double expected, double relative)
{
    assert_near(actual, expected, relative * fmax(1.0, fabs(expected)));
}

static void assert_properties(const wr_outline *o, double area, double cx, double cy,
                              double polar, double relative)
{
    assert_near(o->area, area, relative * area);
    assert_near(o->centroid[0], cx, relative * o->size);
    assert_near(o->centroid[1], cy, relative * o->size);
    assert_near(o->polar_moment, polar, relative * polar);
}

/* A circle of radius r about (cx, cy) as two half circles, the first from
 * its leftmost point through its bottom. */
static void circle_loop(shape *s, double cx, double cy, double r)
{
    const double loop[2][3] = {{cx - r, cy, 1}, {cx + r, cy, 1}};
    add_loop(s, 2, loop);
}

/* ---- mass properties --------------------------------------------------------------- */

static void test_circle_from_half_arcs(void **state)
{
    (void)state;
    shape s = {0};
    circle_loop(&s, 3, -2, 1.5);
    wr_outline *o = build_ok(&s);
    double r = 1.5;
    assert_properties(o, TEST_PI * r * r, 3, -2, TEST_PI * r * r * r * r / 2, 1e-14);
    assert_close(o->perimeter, 2 * TEST_PI * r, 1e-14);
    assert_close(o->size, hypot(2 * r, 2 * r), 1e-14);
    assert_close(o->box_min[1], -2 - r, 1e-14);
    /* Each half circle: centre, radius, angles. */
    const wr_segment *lower = &o->loops[0].segments[0];
    assert_close(lower->center[0], 3, 1e-15);
    assert_close(lower->center[1], -2, 1e-15);
    assert_close(lower->radius, r, 1e-15);
    assert_close(lower->sweep, TEST_PI, 1e-15);
    assert_close(fabs(lower->start_angle), TEST_PI, 1e-15);
    assert_close(lower->length, TEST_PI * r, 1e-15);
    assert_int_equal(o->loops[0].orientation, 1);
    assert_int_equal(o->loops[0].material_side, 1);
    wr_outline_free(o);
}

/* Annulus: area pi (R^2 - r^2), polar moment pi (R^4 - r^4) / 2 about the
 * centre, which is the centroid. */
static void test_annulus(void **state)
{
    (void)state;
    double R = 5, r = 2, cx = 10, cy = 7;
    shape s = {0};
    circle_loop(&s, cx, cy, R);
    circle_loop(&s, cx, cy, r);
    wr_outline *o = build_ok(&s);
    assert_properties(o, TEST_PI * (R * R - r * r), cx, cy,
                      TEST_PI * (R * R * R * R - r * r * r * r) / 2, 1e-14);
    assert_close(o->perimeter, 2 * TEST_PI * (R + r), 1e-14);
    assert_close(o->loops[1].perimeter, 2 * TEST_PI * r, 1e-14);
    /* Both written counter-clockwise: the hole's material is on its right. */
    assert_int_equal(o->loops[1].orientation, 1);
    assert_int_equal(o->loops[1].material_side, -1);
    wr_outline_free(o);
}

/* A w x h rectangle centred at (cx, cy) with corners rounded to radius rho
 * by quarter circles (bulge tan(pi/8)), counter-clockwise from the bottom
 * edge's left end. */
static void rounded_rectangle(shape *s, double cx, double cy, double w, double h, double rho)
{
    double x0 = cx - w / 2, x1 = cx + w / 2, y0 = cy - h / 2, y1 = cy + h / 2;
    const double loop[8][3] = {
        {x0 + rho, y0, 0},       {x1 - rho, y0, QUARTER}, {x1, y0 + rho, 0},
        {x1, y1 - rho, QUARTER}, {x1 - rho, y1, 0},       {x0 + rho, y1, QUARTER},
        {x0, y1 - rho, 0},       {x0, y0 + rho, QUARTER},
    };
    add_loop(s, 8, loop);
}

/* Polar moment about the origin of an a x b rectangle centred at (x, y). */
static double rectangle_polar(double a, double b, double x, double y)
{
    return a * b * (a * a + b * b) / 12 + a * b * (x * x + y * y);
}

/* Polar moment about the origin of a quarter disc of radius rho whose
 * circle is centred at (x, y), lying in the quadrant (sx, sy) = (+-1, +-1):
 * pi rho^4 / 8 about its circle's centre, moved to the origin with its
 * first moment A (4 rho / 3 pi)(sx, sy) about that centre. */
static double quarter_disc_polar(double rho, double x, double y, double sx, double sy)
{
    double area = TEST_PI * rho * rho / 4, offset = 4 * rho / (3 * TEST_PI);
    return TEST_PI * rho * rho * rho * rho / 8 + 2 * area * offset * (sx * x + sy * y) +
           area * (x * x + y * y);
}

static void test_rounded_rectangle(void **state)
{
    (void)state;
    double w = 8, h = 5, rho = 1.25;
    shape s = {0};
    rounded_rectangle(&s, 0, 0, w, h, rho);
    wr_outline *o = build_ok(&s);
    /* The pieces: a w x (h - 2 rho) band, two (w - 2 rho) x rho bands and
     * four quarter discs, about the centre (the centroid by symmetry). */
    double polar = rectangle_polar(w, h - 2 * rho, 0, 0) +
                   rectangle_polar(w - 2 * rho, rho, 0, h / 2 - rho / 2) +
                   rectangle_polar(w - 2 * rho, rho, 0, -(h / 2 - rho / 2));
    for (int sx = -1; sx <= 1; sx += 2)
        for (int sy = -1; sy <= 1; sy += 2)
            polar += quarter_disc_polar(rho, sx * (w / 2 - rho), sy * (h / 2 - rho), sx, sy);
    assert_properties(o, w * h - (4 - TEST_PI) * rho * rho, 0, 0, polar, 1e-14);
    assert_close(o->perimeter, 2 * (w + h) - 8 * rho + 2 * TEST_PI * rho, 1e-14);
    assert_close(o->loops[0].segments[1].length, TEST_PI * rho / 2, 1e-14);
    assert_close(o->loops[0].segments[0].length, w - 2 * rho, 1e-14);
    assert_close(o->box_max[0], w / 2, 1e-14);
    assert_close(o->box_max[1], h / 2, 1e-14);
    wr_outline_free(o);
}

/* A W x H plate, corner at the origin, with a stadium-shaped slot: two half
 * discs of radius r whose centres are L apart, joined by an L x 2r
 * rectangle, centred at (sx, sy). */
static void test_slotted_plate(void **state)
{
    (void)state;
    double W = 20, H = 10, L = 6, r = 1.5, sx = 12, sy = 4;
    shape s = {0};
    const double plate[4][3] = {{0, 0, 0}, {W, 0, 0}, {W, H, 0}, {0, H, 0}};
    add_loop(&s, 4, plate);
    const double slot[4][3] = {
        {sx - L / 2, sy - r, 0}, {sx + L / 2, sy - r, 1},
        {sx + L / 2, sy + r, 0}, {sx - L / 2, sy + r, 1},
    };
    add_loop(&s, 4, slot);
    wr_outline *o = build_ok(&s);

    double slot_area = 2 * r * L + TEST_PI * r * r;
    double area = W * H - slot_area;
    double cx = (W * H * W / 2 - slot_area * sx) / area;
    double cy = (W * H * H / 2 - slot_area * sy) / area;
    /* The slot about its centre: its rectangle, and each half disc
     * (pi r^4 / 4 about its circle's centre, first moment 2 r^3 / 3
     * outwards, that centre L/2 away). */
    double half_disc = TEST_PI * r * r * r * r / 4 + 2 * (L / 2) * (2 * r * r * r / 3) +
                       TEST_PI * r * r / 2 * (L / 2) * (L / 2);
    double slot_polar = rectangle_polar(L, 2 * r, 0, 0) + 2 * half_disc;
    /* Both about the plate's centroid, by the parallel-axis theorem. */
    double plate_polar = rectangle_polar(W, H, W / 2 - cx, H / 2 - cy);
    double slot_about = slot_polar + slot_area * ((sx - cx) * (sx - cx) + (sy - cy) * (sy - cy));
    assert_properties(o, area, cx, cy, plate_polar - slot_about, 1e-13);
    assert_close(o->perimeter, 2 * (W + H) + 2 * L + 2 * TEST_PI * r, 1e-14);
    /* Written counter-clockwise, the slot's material is on its right. */
    assert_int_equal(o->loops[1].material_side, -1);
    wr_outline_free(o);
}

/* Zero bulges: the shoelace formulas, written out here for a concave
 * polygon (an arrow). */
static void test_polygon_matches_shoelace(void **state)
{
    (void)state;
    const double v[7][3] = {{0, 1, 0}, {4, 1, 0}, {4, 0, 0}, {7, 2.5, 0},
                            {4, 5, 0}, {4, 4, 0}, {0, 4, 0}};
    shape s = {0};
    add_loop(&s, 7, v);
    wr_outline *o = build_ok(&s);
    double a = 0, mx = 0, my = 0, j = 0;
    for (int i = 0; i < 7; i++) {
        double x0 = v[i][0], y0 = v[i][1], x1 = v[(i + 1) % 7][0], y1 = v[(i + 1) % 7][1];
        double c = x0 * y1 - x1 * y0;
        a += c / 2;
        mx += (x0 + x1) * c / 6;
        my += (y0 + y1) * c / 6;
        j += c * (x0 * x0 + x0 * x1 + x1 * x1 + y0 * y0 + y0 * y1 + y1 * y1) / 12;
    }
    double cx = mx / a, cy = my / a;
    assert_close(a, 12 + 7.5, 1e-15); /* the shaft and the head, by hand */
    assert_properties(o, a, cx, cy, j - a * (cx * cx + cy * cy), 1e-14);
    wr_outline_free(o);
}

/* The issue's own example: a 50 x 30 rectangle whose corner at (50, 0) is
 * rounded to radius 10 about (40, 10), with a hole of diameter 6 about
 * (13, 10). */
static void test_issue_example(void **state)
{
    (void)state;
    shape s = {0};
    const double outer[5][3] = {{0, 0, 0}, {40, 0, 0.4142135623730951}, {50, 10, 0},
                                {50, 30, 0}, {0, 30, 0}};
    const double hole[2][3] = {{10, 10, 1}, {16, 10, 1}};
    add_loop(&s, 5, outer);
    add_loop(&s, 2, hole);
    wr_outline *o = build_ok(&s);
    /* The rectangle less its corner (a 10 x 10 square less a quarter disc
     * whose centroid is 40 / 3 pi from (40, 10) towards the corner), less
     * the hole. */
    double quarter = 25 * TEST_PI, offset = 40 / (3 * TEST_PI);
    double corner = 100 - quarter;
    double corner_mx = 100 * 45 - quarter * (40 + offset);
    double corner_my = 100 * 5 - quarter * (10 - offset);
    double hole_area = 9 * TEST_PI;
    double area = 1500 - corner - hole_area;
    assert_close(area, 1400 + 16 * TEST_PI, 1e-13);
    double cx = (1500 * 25 - corner_mx - hole_area * 13) / area;
    double cy = (1500 * 15 - corner_my - hole_area * 10) / area;
    /* Polar moment about the origin, then about the centroid: the
     * rectangle, less the square, plus the quarter disc, less the hole. */
    double about_origin = rectangle_polar(50, 30, 25, 15) - rectangle_polar(10, 10, 45, 5) +
                          quarter_disc_polar(10, 40, 10, 1, -1) -
                          (TEST_PI * 81 / 2 + hole_area * (13 * 13 + 10 * 10));
    double polar = about_origin - area * (cx * cx + cy * cy);
    assert_properties(o, area, cx, cy, polar, 1e-13);
    assert_close(o->loops[1].perimeter, 6 * TEST_PI, 1e-14);
    assert_close(o->perimeter, 160 - 20 + 5 * TEST_PI + 6 * TEST_PI, 1e-14);
    wr_outline_free(o);
}

/* A circular segment alone (a chord and its arc) of every size of bulge,
 * both sides of the library's switch to series (half angle 0.4, bulge
 * tan(0.2)) and near a whole circle, by the textbook forms about the
 * circle's centre: area r^2 (theta - sin theta) / 2, centroid
 * 4 r sin^3(theta/2) / (3 (theta - sin theta)) from the centre, polar
 * moment about the centre the sector's r^4 theta / 4 less the triangle's
 * r^4 sin theta (2 + cos theta) / 12. */
static void test_circular_segments(void **state)
{
    (void)state;
    const double bulges[] = {0.05, 0.2, tan(0.2) - 1e-12, tan(0.2) + 1e-12, 0.5, 1, 3, 40};
    for (size_t i = 0; i < sizeof bulges / sizeof bulges[0]; i++) {
        double b = bulges[i];
        /* Chord from (2, 0) to (-2, 0), arc back to (2, 0) bulging
         * downwards (counter-clockwise, b > 0, lies to its right). */
        shape s = {0};
        const double loop[2][3] = {{2, 1, 0}, {-2, 1, b}};
        add_loop(&s, 2, loop);
        wr_outline *o = build_ok(&s);
        double theta = 4 * atan(b), half = 2;
        double r = half / sin(theta / 2);
        double area = r * r * (theta - sin(theta)) / 2;
        double distance = 4 * r * pow(sin(theta / 2), 3) / (3 * (theta - sin(theta)));
        double centre_y = 1 + r * cos(theta / 2); /* above the chord for theta < pi */
        double about_centre = r * r * r * r * theta / 4 - r * r * r * r * sin(theta) * (2 + cos(theta)) / 12;
        double polar = about_centre - area * distance * distance;
        /* The closed forms here lose digits to cancellation for flat arcs
         * (theta - sin theta): compare to what they keep. */
        double relative = theta < 0.5 ? 1e-9 : 1e-12;
        assert_properties(o, area, 0, centre_y - distance, polar, relative);
        assert_near(o->loops[0].segments[1].length, r * theta, 1e-14 * r * theta);
        wr_outline_free(o);
    }
}

/* Reversing any loop changes no mass property, and the normals still point
 * into the material. */
static void test_orientation_independent(void **state)
{
    (void)state;
    shape base = {0};
    const double outer[5][3] = {{0, 0, 0}, {40, 0, QUARTER}, {50, 10, 0}, {50, 30, -0.3},
                                {0, 30, 0}};
    add_loop(&base, 5, outer);
    circle_loop(&base, 13, 10, 3);
    const double slot[4][3] = {{25, 15, 0}, {35, 15, 1}, {35, 20, 0}, {25, 20, 1}};
    add_loop(&base, 4, slot);
    wr_outline *reference = build_ok(&base);
    for (int mask = 1; mask < 8; mask++) {
        shape s = base;
        for (size_t loop = 0; loop < 3; loop++)
            if (mask & (1 << loop))
                reverse_loop(&s, loop);
        wr_outline *o = build_ok(&s);
        assert_properties(o, reference->area, reference->centroid[0], reference->centroid[1],
                          reference->polar_moment, 1e-13);
        assert_near(o->perimeter, reference->perimeter, 1e-14 * reference->perimeter);
        for (size_t loop = 0; loop < 3; loop++) {
            bool reversed = mask & (1 << loop);
            assert_int_equal(o->loops[loop].orientation,
                             reversed ? -reference->loops[loop].orientation
                                      : reference->loops[loop].orientation);
            /* The same point of the boundary has the same normal. */
            size_t n = o->loops[loop].segment_count;
            for (size_t j = 0; j < n; j++) {
                double p[2], normal[2], q[2], other[2];
                wr_outline_boundary(reference, loop, j, 0.3, p, normal);
                size_t k = reversed ? (2 * n - 2 - j) % n : j;
                wr_outline_boundary(o, loop, k, reversed ? 0.7 : 0.3, q, other);
                assert_near(q[0], p[0], 1e-13 * o->size);
                assert_near(q[1], p[1], 1e-13 * o->size);
                assert_close(other[0], normal[0], 1e-13);
                assert_close(other[1], normal[1], 1e-13);
            }
        }
        wr_outline_free(o);
    }
    wr_outline_free(reference);
}

/* ---- boundary geometry ---------------------------------------------------------------- */

/* On the annulus the normal into the material points towards the centre on
 * the outer circle and away from it on the hole (a pin in the hole pushes
 * outwards), in either orientation; lengths are uniform in t. */
static void test_annulus_normals(void **state)
{
    (void)state;
    double R = 5, r = 2, cx = 1, cy = -1;
    for (int reversed = 0; reversed < 2; reversed++) {
        shape s = {0};
        circle_loop(&s, cx, cy, R);
        circle_loop(&s, cx, cy, r);
        if (reversed)
            reverse_loop(&s, 1);
        wr_outline *o = build_ok(&s);
        for (size_t loop = 0; loop < 2; loop++)
            for (size_t j = 0; j < 2; j++)
                for (double t = 0; t <= 1; t += 0.125) {
                    double p[2], n[2];
                    wr_outline_boundary(o, loop, j, t, p, n);
                    double radius = loop == 0 ? R : r;
                    double d[2] = {(p[0] - cx) / radius, (p[1] - cy) / radius};
                    assert_close(hypot(p[0] - cx, p[1] - cy), radius, 1e-15);
                    double sign = loop == 0 ? -1 : 1;
                    assert_close(n[0], sign * d[0], 1e-14);
                    assert_close(n[1], sign * d[1], 1e-14);
                }
        /* The hole's segment 0 is its lower half, written from the left
         * (reversed: segment n-2-0 = 0 run from the right); either way it
         * passes the bottom at t = 0.5. */
        double p[2];
        wr_outline_boundary(o, 1, 0, 0.5, p, NULL);
        assert_close(p[0], cx, 1e-15);
        assert_close(p[1], cy - r, 1e-15);
        assert_true(o->loops[1].segments[0].start[0] == (reversed ? cx + r : cx - r));
        wr_outline_free(o);
    }
}

static void test_rounded_rectangle_boundary(void **state)
{
    (void)state;
    double w = 8, h = 5, rho = 1.25;
    shape s = {0};
    rounded_rectangle(&s, 0, 0, w, h, rho);
    wr_outline *o = build_ok(&s);
    /* The bottom-right corner's arc (segment 1) at its middle: 45 degrees
     * below-right of its centre, the normal pointing back at the centre. */
    double p[2], n[2], centre[2] = {w / 2 - rho, -h / 2 + rho};
    wr_outline_boundary(o, 0, 1, 0.5, p, n);
    double diagonal = sqrt(0.5);
    assert_close(p[0], centre[0] + rho * diagonal, 1e-15);
    assert_close(p[1], centre[1] - rho * diagonal, 1e-15);
    assert_close(n[0], -diagonal, 1e-15);
    assert_close(n[1], diagonal, 1e-15);
    /* The bottom edge: straight up. */
    wr_outline_boundary(o, 0, 0, 0.25, p, n);
    assert_close(p[0], -w / 2 + rho + 0.25 * (w - 2 * rho), 1e-15);
    assert_close(p[1], -h / 2, 1e-15);
    assert_true(n[0] == 0 && n[1] == 1);

    /* Located back: on the arc at a third of its length. */
    wr_outline_place place;
    wr_outline_boundary(o, 0, 1, 1.0 / 3, p, NULL);
    double tolerance = WR_OUTLINE_TOLERANCE * o->size;
    assert_true(wr_outline_locate(o, p, tolerance, &place));
    assert_int_equal(place.loop, 0);
    assert_int_equal(place.segment, 1);
    assert_close(place.t, 1.0 / 3, 1e-14);
    assert_false(place.at_vertex);
    /* A hair off the boundary outwards, within the tolerance. */
    double off[2] = {p[0] + 0.5 * tolerance * diagonal, p[1] - 0.5 * tolerance * diagonal};
    assert_true(wr_outline_locate(o, off, tolerance, &place));
    assert_int_equal(place.segment, 1);
    /* Further off, not on it; inside, contained. */
    off[0] = p[0] + 3 * tolerance;
    assert_false(wr_outline_locate(o, off, tolerance, &place));
    double inside[2] = {3.8, -1.9}; /* 1.235 from the corner's centre */
    assert_true(wr_outline_contains(o, inside, tolerance));
    /* The corner of the rectangle is cut off by the arc. */
    double corner[2] = {w / 2 - 0.01, -h / 2 + 0.01};
    assert_false(wr_outline_contains(o, corner, tolerance));
    assert_false(wr_outline_locate(o, corner, tolerance, &place));

    /* At vertex 2, where the arc meets the right edge tangentially: a
     * vertex, smooth.  At vertex 0 likewise. */
    double v2[2] = {w / 2, -h / 2 + rho};
    assert_true(wr_outline_locate(o, v2, tolerance, &place));
    assert_true(place.at_vertex);
    assert_int_equal(place.vertex, 2);
    assert_int_equal(place.segment, 2);
    assert_true(place.t == 0);
    assert_true(place.smooth);
    wr_outline_free(o);
}

/* The issue's example: a pin in the hole, fixels on the arc and at the
 * sharp corner (0, 30), a vertex without a normal. */
static void test_issue_example_places(void **state)
{
    (void)state;
    shape s = {0};
    const double outer[5][3] = {{0, 0, 0}, {40, 0, QUARTER}, {50, 10, 0}, {50, 30, 0},
                                {0, 30, 0}};
    const double hole[2][3] = {{10, 10, 1}, {16, 10, 1}};
    add_loop(&s, 5, outer);
    add_loop(&s, 2, hole);
    wr_outline *o = build_ok(&s);
    double tolerance = WR_OUTLINE_TOLERANCE * o->size;
    wr_outline_place place;
    /* The top of the hole: segment 1 (the upper half, from (16, 10)) at its
     * middle; the pin pushes the part upwards, away from the hole. */
    double top[2] = {13, 13};
    assert_true(wr_outline_locate(o, top, tolerance, &place));
    assert_int_equal(place.loop, 1);
    assert_int_equal(place.segment, 1);
    assert_close(place.t, 0.5, 1e-15);
    double p[2], n[2];
    wr_outline_boundary(o, 1, place.segment, place.t, p, n);
    assert_close(n[0], 0, 1e-15);
    assert_close(n[1], 1, 1e-15);
    /* The corner arc at 30 degrees below the horizontal from (40, 10). */
    double angle = -TEST_PI / 6;
    double on_arc[2] = {40 + 10 * cos(angle), 10 + 10 * sin(angle)};
    assert_true(wr_outline_locate(o, on_arc, tolerance, &place));
    assert_int_equal(place.loop, 0);
    assert_int_equal(place.segment, 1);
    assert_close(place.t, 2.0 / 3, 1e-14);
    wr_outline_boundary(o, 0, 1, place.t, p, n);
    assert_close(n[0], -cos(angle), 1e-14);
    assert_close(n[1], -sin(angle), 1e-14);
    /* (0, 30) is vertex 4, a right angle: not smooth. */
    double corner[2] = {0, 30};
    assert_true(wr_outline_locate(o, corner, tolerance, &place));
    assert_true(place.at_vertex);
    assert_int_equal(place.loop, 0);
    assert_int_equal(place.vertex, 4);
    assert_false(place.smooth);
    /* The material: not in the hole, nor past the rounded corner. */
    double in_hole[2] = {13, 10}, material[2] = {25, 15}, past[2] = {49.5, 0.5};
    assert_false(wr_outline_contains(o, in_hole, tolerance));
    assert_true(wr_outline_contains(o, material, tolerance));
    assert_false(wr_outline_contains(o, past, tolerance));
    wr_outline_free(o);
}

/* A very flat arc (bulge 1e-9: its radius 1e9 times its chord) is located
 * and has its normal as precisely as a line. */
static void test_flat_arc(void **state)
{
    (void)state;
    double b = 1e-9;
    shape s = {0};
    const double loop[3][3] = {{0, 0, b}, {10, 0, 0}, {5, 5, 0}};
    add_loop(&s, 3, loop);
    wr_outline *o = build_ok(&s);
    /* The sagitta b * chord / 2 below the chord's middle (counter-clockwise
     * bulges to the right of (1, 0)). */
    double p[2], n[2];
    wr_outline_boundary(o, 0, 0, 0.5, p, n);
    assert_close(p[0], 5, 1e-15);
    assert_near(p[1], -b * 10 / 2, 1e-14 * b);
    assert_close(n[0], 0, 1e-15);
    assert_close(n[1], 1, 1e-15);
    wr_outline_place place;
    assert_true(wr_outline_locate(o, p, 1e-15, &place));
    assert_int_equal(place.segment, 0);
    assert_close(place.t, 0.5, 1e-12);
    /* Area: the triangle plus the segment 2/3 * chord * sagitta. */
    assert_close(o->area, 25 + 2.0 / 3 * 10 * (b * 5), 1e-15);
    wr_outline_free(o);
}

/* ---- refusals ------------------------------------------------------------------------- */

static void assert_refused(const shape *s, const char *field, const char *words)
{
    wr_outline *o = (wr_outline *)&o; /* not NULL: the call must clear it */
    wr_error error;
    wr_status status = build(s, &o, &error);
    assert_int_equal(status, WR_INVALID);
    assert_null(o);
    if (strcmp(error.field, field) != 0 || (words && !strstr(error.reason, words)))
        fail_msg("expected %s (\"%s\"), got %s: %s", field, words ? words : "", error.field,
                 error.reason);
}

static void test_refuses_bow_tie(void **state)
{
    (void)state;
    shape s = {0};
    const double bow_tie[4][3] = {{0, 0, 0}, {4, 0, 0}, {0, 2, 0}, {4, 2, 0}};
    add_loop(&s, 4, bow_tie);
    assert_refused(&s, "loops[0]",
                   "segment 1 (vertices 1 to 2) and segment 3 (vertices 3 to 0) meet at (2, 1)");
}

/* A thin rectangle whose top edge is a half circle bulging down through
 * the bottom edge: it crosses y = 0 at x = 5 -+ sqrt(24). */
static void test_refuses_arc_crossing_line(void **state)
{
    (void)state;
    shape s = {0};
    const double loop[4][3] = {{0, 0, 0}, {10, 0, 0}, {10, 1, -1}, {0, 1, 0}};
    add_loop(&s, 4, loop);
    char point[160];
    snprintf(point, sizeof point, "meet at (%g, 0)", 5 - sqrt(24));
    assert_refused(&s, "loops[0]", "segment 0 (vertices 0 to 1) and segment 2 (vertices 2 to 3)");
    assert_refused(&s, "loops[0]", point);
}

/* Two arcs crossing: a loop whose two half circles are of different
 * circles folding over each other. */
static void test_refuses_arc_crossing_arc(void **state)
{
    (void)state;
    shape s = {0};
    /* A square whose bottom edge bulges up (half circle of radius 2 about
     * (2, 0)) and whose top edge bulges down (about (2, 3)): they cross at
     * y = 1.5, x = 2 -+ sqrt(4 - 2.25), reported at the right. */
    const double loop[4][3] = {{0, 0, -1}, {4, 0, 0}, {4, 3, -1}, {0, 3, 0}};
    add_loop(&s, 4, loop);
    char point[160];
    snprintf(point, sizeof point, "segment 0 (vertices 0 to 1) and segment 2 (vertices 2 to 3) "
             "meet at (%g, 1.5)", 2 + sqrt(1.75));
    assert_refused(&s, "loops[0]", point);
}

static void test_refuses_hole_outside(void **state)
{
    (void)state;
    shape s = {0};
    const double square[4][3] = {{0, 0, 0}, {10, 0, 0}, {10, 10, 0}, {0, 10, 0}};
    add_loop(&s, 4, square);
    circle_loop(&s, 20, 5, 1);
    assert_refused(&s, "loops[1]", "not inside the outer loop");
    /* Around the whole square: also outside (its vertex is). */
    s.loop_count = 1;
    circle_loop(&s, 5, 5, 20);
    assert_refused(&s, "loops[1]", "not inside the outer loop");
    /* Crossing the outer boundary: named with the point, (10, 5 +- 0.8). */
    s.loop_count = 1;
    circle_loop(&s, 10.6, 5, 1);
    assert_refused(&s, "loops[1]",
                   "the hole meets the outer loop (loops[0]): its segment 0 (vertices 0 to 1) "
                   "and the outer loop's segment 1 (vertices 1 to 2) meet at (10, 4.2)");
    /* Touching it from inside. */
    s.loop_count = 1;
    circle_loop(&s, 9, 5, 1);
    assert_refused(&s, "loops[1]", "meet at (10, 5)");
}

/* Circles of radius 2 about (3, 5) and (6, 5) cross at x = 4.5,
 * y = 5 -+ sqrt(1.75). */
static void test_refuses_overlapping_holes(void **state)
{
    (void)state;
    shape s = {0};
    const double square[4][3] = {{0, 0, 0}, {10, 0, 0}, {10, 10, 0}, {0, 10, 0}};
    add_loop(&s, 4, square);
    circle_loop(&s, 3, 5, 2);
    circle_loop(&s, 6, 5, 2);
    char point[160];
    snprintf(point, sizeof point, "meet at (4.5, %g)", 5 - sqrt(1.75));
    assert_refused(&s, "loops[2]", "the hole meets hole loops[1]");
    assert_refused(&s, "loops[2]", point);
}

static void test_refuses_nested_holes(void **state)
{
    (void)state;
    shape s = {0};
    const double square[4][3] = {{0, 0, 0}, {10, 0, 0}, {10, 10, 0}, {0, 10, 0}};
    add_loop(&s, 4, square);
    circle_loop(&s, 5, 5, 3);
    circle_loop(&s, 5, 5, 1);
    assert_refused(&s, "loops[2]", "lies inside hole loops[1]");
    /* The other way round. */
    s.loop_count = 1;
    circle_loop(&s, 5, 5, 1);
    circle_loop(&s, 5, 5, 3);
    assert_refused(&s, "loops[2]", "contains hole loops[1]");
}

static void test_refuses_bad_numbers_and_degenerate_loops(void **state)
{
    (void)state;
    wr_outline *o;
    wr_error error;
    assert_int_equal(wr_outline_new(NULL, 0, &o, &error), WR_INVALID);
    assert_null(o);
    assert_string_equal(error.field, "loops");

    const double triangle[3][3] = {{0, 0, 0}, {4, 0, 0}, {0, 3, 0}};
    shape s = {0};
    add_loop(&s, 3, triangle);
    s.counts[0] = 1;
    assert_refused(&s, "loops[0]", "at least 2 vertices, 1 given");
    s.counts[0] = 3;
    s.vertices[0][1][2] = INFINITY;
    assert_refused(&s, "loops[0][1][2]", "finite");
    s.vertices[0][1][2] = 0;
    s.vertices[0][2][1] = NAN;
    assert_refused(&s, "loops[0][2][1]", "finite");
    s.vertices[0][2][1] = 0;
    /* Now (0, 0), (4, 0), (0, 0): segment 2 has no length. */
    assert_refused(&s, "loops[0][0]", "repeats vertex 2: segment 2 between them has no length");
}

static void test_refuses_degenerate(void **state)
{
    (void)state;
    /* A repeated vertex: segment 1 has no length, blamed on vertex 2. */
    shape s = {0};
    const double repeated[4][3] = {{0, 0, 0}, {4, 0, 0.5}, {4, 0, 0}, {0, 3, 0}};
    add_loop(&s, 4, repeated);
    assert_refused(&s, "loops[0][2]", "repeats vertex 1: segment 1 between them has no length");
    /* Two vertices, both straight. */
    s = (shape){0};
    const double two[2][3] = {{0, 0, 0}, {4, 0, 0}};
    add_loop(&s, 2, two);
    assert_refused(&s, "loops[0]", "2 vertices encloses no area");
    /* Two vertices, one arc there and back: they overlap. */
    s.vertices[0][0][2] = 0.5;
    s.vertices[0][1][2] = -0.5;
    assert_refused(&s, "loops[0]",
                   "segment 0 (vertices 0 to 1) and segment 1 (vertices 1 to 0) meet at");
    /* Two vertices, a chord and an arc: a circular segment, accepted; two
     * arcs of different circles, a lens, also. */
    s.vertices[0][1][2] = 0;
    wr_outline *o = build_ok(&s);
    wr_outline_free(o);
    s.vertices[0][1][2] = 0.25;
    o = build_ok(&s);
    assert_true(o->area > 0);
    wr_outline_free(o);
    /* A fold back along a line: the third vertex back on the first edge. */
    s = (shape){0};
    const double fold[3][3] = {{0, 0, 0}, {4, 0, 0}, {2, 0, 0}};
    add_loop(&s, 3, fold);
    assert_refused(&s, "loops[0]",
                   "segment 0 (vertices 0 to 1) and segment 1 (vertices 1 to 2) meet at (2, 0)");
    /* Arcs so large their second moment is beyond double precision. */
    s = (shape){0};
    const double huge[2][3] = {{0, 0, 1e10}, {1e150, 0, 1e10}};
    add_loop(&s, 2, huge);
    assert_refused(&s, "loops", "too large for double precision");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_circle_from_half_arcs),
        cmocka_unit_test(test_annulus),
        cmocka_unit_test(test_rounded_rectangle),
        cmocka_unit_test(test_slotted_plate),
        cmocka_unit_test(test_polygon_matches_shoelace),
        cmocka_unit_test(test_issue_example),
        cmocka_unit_test(test_circular_segments),
        cmocka_unit_test(test_orientation_independent),
        cmocka_unit_test(test_annulus_normals),
        cmocka_unit_test(test_rounded_rectangle_boundary),
        cmocka_unit_test(test_issue_example_places),
        cmocka_unit_test(test_flat_arc),
        cmocka_unit_test(test_refuses_bow_tie),
        cmocka_unit_test(test_refuses_arc_crossing_line),
        cmocka_unit_test(test_refuses_arc_crossing_arc),
        cmocka_unit_test(test_refuses_hole_outside),
        cmocka_unit_test(test_refuses_overlapping_holes),
        cmocka_unit_test(test_refuses_nested_holes),
        cmocka_unit_test(test_refuses_bad_numbers_and_degenerate_loops),
        cmocka_unit_test(test_refuses_degenerate),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
