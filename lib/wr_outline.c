/* wr_outline.c -- outlines of lines and circular arcs with holes: validation,
 * exact mass properties, boundary geometry (wr_outline.h).
 *
 * Every arc is handled in its chord frame (midpoint M of the chord, unit
 * chord direction e_u, unit normal e_w towards the bulge, half chord h,
 * half included angle a in (0, pi)) rather than about its centre: a nearly
 * straight arc has a radius h / sin(a) far larger than the part, and
 * coordinates relative to its centre would lose every digit the ratio
 * has.  In that frame the arc is, for phi in [-a, a] (phi = a (2t - 1)),
 *     u = h sin(phi) / sin(a),
 *     w = h (cos(phi) - cos(a)) / sin(a) = 2 h sin(a t) sin(a (1 - t)) / sin(a),
 * both without cancellation. */
#include "wr_outline.h"
#include "wr_internal.h"

#include <assert.h>
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* A segment shorter than this fraction of the size, or a loop enclosing
 * less than its square, is degenerate (as wr_fixture's polygons). */
#define DEGENERATE_TOLERANCE 1e-12

/* ---- the circular segment ------------------------------------------------------
 *
 * The region between an arc and its chord (a circular segment) of half
 * chord h and half included angle a, in the chord frame (u along the chord,
 * w towards the bulge, origin at the chord's midpoint), has, with
 * s = sin a, c = cos a (sector of the circle less the triangle it shares
 * with the centre, then moved from the centre to the midpoint):
 *     area          A   = h^2 (a - s c) / s^2
 *     first moment  Q_w = integral of w dA = h^3 (2/3 s^3 - a c + s c^2) / s^3
 *                   (Q_u = 0 by symmetry)
 *     polar moment  J_M = integral of u^2 + w^2 dA = h^4 (a (1/2 + c^2) - 3/2 s c) / s^4
 * For a half circle (a = pi/2, h = r): A = pi r^2 / 2, Q_w = 2 r^3 / 3,
 * J_M = pi r^4 / 4.  Each numerator cancels to order a^3 or a^5 for small a,
 * so below SERIES_LIMIT they are their Taylor series (exact rationals,
 * derived with sympy; truncation below 5e-17 relative at a = 0.5). */
#define SERIES_LIMIT 0.4
#define SERIES_TERMS 12

/* (a - s c) / s^2 = a * sum area_series[k] a^(2k) */
static const double area_series[SERIES_TERMS] = {
    2.0 / 3.0,
    4.0 / 45.0,
    4.0 / 315.0,
    8.0 / 4725.0,
    4.0 / 18711.0,
    5528.0 / 212837625.0,
    8.0 / 2606175.0,
    57872.0 / 162820783125.0,
    175468.0 / 4331032831125.0,
    1396888.0 / 306265893058125.0,
    621464.0 / 1222532449149375.0,
    3781825456.0 / 67306523987918840625.0,
};
/* (2/3 s^3 - a c + s c^2) / s^3 = a^2 * sum moment_series[k] a^(2k) */
static const double moment_series[SERIES_TERMS] = {
    2.0 / 15.0,
    2.0 / 63.0,
    4.0 / 675.0,
    2.0 / 2079.0,
    2764.0 / 19348875.0,
    4.0 / 200475.0,
    28936.0 / 10854718875.0,
    87734.0 / 254766637125.0,
    698444.0 / 16119257529375.0,
    310732.0 / 58215830911875.0,
    1890912728.0 / 2926370608170384375.0,
    2631724.0 / 34136867618555625.0,
};
/* Orientation of c relative to the directed line a->b: >0 left, <0 right. */
static double orient(const double a[2], const double b[2], const double c[2])
{
    return (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
}

bool wr_segments_cross(const double a[2], const double b[2], const double c[2], const double d[2],
                       double point[2])
{
    double o1 = orient(a, b, c), o2 = orient(a, b, d);
    double o3 = orient(c, d, a), o4 = orient(c, d, b);
    if (!((o1 > 0 && o2 < 0) || (o1 < 0 && o2 > 0)) ||
        !((o3 > 0 && o4 < 0) || (o3 < 0 && o4 > 0)))
        return false;
    /* a + t (b - a) with t = o3 / (o3 - o4): the orientations are the
     * signed distances of a and b from cd, times |cd|. */
    double t = o3 / (o3 - o4);
    point[0] = a[0] + t * (b[0] - a[0]);
    point[1] = a[1] + t * (b[1] - a[1]);
    return true;
}

/* ---- pairs of boxes that overlap (wr_internal.h) -------------------------------- */

typedef struct box_entry {
    double enter; /* the grown box's least x */
    size_t index;
} box_entry;

static int box_entry_order(const void *a, const void *b)
{
    const box_entry *x = a, *y = b;
    if (x->enter != y->enter)
        return x->enter < y->enter ? -1 : 1;
    return x->index < y->index ? -1 : x->index > y->index;
}

bool wr_box_pairs(const wr_box *boxes, size_t n, double margin, wr_box_visit visit,
                  void *context)
{
    if (n < 2)
        return true;
    box_entry *order = malloc(n * sizeof *order);
    size_t *active = malloc(n * sizeof *active);
    if (!order || !active) {
        free(order);
        free(active);
        return false;
    }
    for (size_t i = 0; i < n; i++)
        order[i] = (box_entry){boxes[i].min[0] - margin, i};
    qsort(order, n, sizeof *order, box_entry_order);
    /* Invariant: active holds every box entered so far whose grown x range
     * reaches the current box's least x; the boxes still to come enter at
     * or beyond it, so one left behind never overlaps again. */
    size_t active_count = 0;
    for (size_t k = 0; k < n; k++) {
        size_t i = order[k].index;
        const wr_box *box = &boxes[i];
        size_t kept = 0;
        for (size_t a = 0; a < active_count; a++) {
            size_t j = active[a];
            const wr_box *other = &boxes[j];
            if (other->max[0] + margin < order[k].enter)
                continue;
            active[kept++] = j;
            /* In x they overlap: other entered first, so its least x is
             * at most this one's. */
            if (other->min[1] - margin > box->max[1] + margin ||
                box->min[1] - margin > other->max[1] + margin)
                continue;
            visit(context, j < i ? j : i, j < i ? i : j);
        }
        active[kept++] = i;
        active_count = kept;
    }
    free(order);
    free(active);
    return true;
}

/* (a (1/2 + c^2) - 3/2 s c) / s^4 = a * sum polar_series[k] a^(2k) */
static const double polar_series[SERIES_TERMS] = {
    2.0 / 15.0,
    4.0 / 63.0,
    4.0 / 225.0,
    8.0 / 2079.0,
    2764.0 / 3869775.0,
    8.0 / 66825.0,
    28936.0 / 1550674125.0,
    701872.0 / 254766637125.0,
    698444.0 / 1791028614375.0,
    621464.0 / 11643166182375.0,
    1890912728.0 / 266033691651853125.0,
    10526896.0 / 11378955872851875.0,
};

static double series(const double coefficients[SERIES_TERMS], double x)
{
    double sum = 0;
    for (int k = SERIES_TERMS - 1; k >= 0; k--)
        sum = sum * x + coefficients[k];
    return sum;
}

/* The circular segment of `segment` (an arc): area, first moment towards
 * the bulge and polar moment about the chord's midpoint (above). */
static void circular_segment(const wr_segment *segment, double *area, double *moment,
                             double *polar)
{
    double a = segment->half_angle, s = segment->half_angle_sin, c = segment->half_angle_cos;
    double h = segment->half_chord;
    double fa, fq, fj;
    if (a < SERIES_LIMIT) {
        double a2 = a * a;
        fa = a * series(area_series, a2);
        fq = a2 * series(moment_series, a2);
        fj = a * series(polar_series, a2);
    } else {
        fa = (a - s * c) / (s * s);
        fq = (2.0 / 3.0 * s * s * s - a * c + s * c * c) / (s * s * s);
        fj = (a * (0.5 + c * c) - 1.5 * s * c) / (s * s * s * s);
    }
    *area = h * h * fa;
    *moment = h * h * h * fq;
    *polar = h * h * h * h * fj;
}

/* ---- one segment ---------------------------------------------------------------- */

static bool is_arc(const wr_segment *segment) { return segment->bulge != 0; }

/* Write `segment` from start to end with bulge, everything derived.  The
 * chord must not be of zero length for the frame to be defined (checked by
 * the caller afterwards: a zero chord gives a zero direction). */
static void segment_build(wr_segment *segment, const double start[2], const double end[2],
                          double bulge)
{
    memset(segment, 0, sizeof *segment);
    /* + 0.0: a -0 given is stored as +0 (as wr_fixture does). */
    segment->start[0] = start[0] + 0.0;
    segment->start[1] = start[1] + 0.0;
    segment->end[0] = end[0] + 0.0;
    segment->end[1] = end[1] + 0.0;
    double chord[2] = {end[0] - start[0], end[1] - start[1]};
    double chord_length = hypot(chord[0], chord[1]);
    /* A bulge so small that its arc's radius, about half the chord over the
     * bulge, is beyond the largest double (1e-310 on a chord of 4) is its
     * chord in double precision: a straight segment. */
    if (bulge != 0 && !isfinite(chord_length / (4 * fabs(bulge))))
        bulge = 0;
    segment->bulge = bulge + 0.0;
    segment->midpoint[0] = start[0] + chord[0] / 2;
    segment->midpoint[1] = start[1] + chord[1] / 2;
    segment->half_chord = chord_length / 2;
    if (chord_length > 0) {
        segment->direction[0] = chord[0] / chord_length;
        segment->direction[1] = chord[1] / chord_length;
    }
    /* The left normal; an arc of positive bulge (counter-clockwise) lies to
     * the right of its chord, so its bulge is the other way. */
    double left[2] = {-segment->direction[1], segment->direction[0]};
    double side = bulge > 0 ? -1 : 1;
    segment->bulge_normal[0] = side * left[0];
    segment->bulge_normal[1] = side * left[1];
    if (!is_arc(segment)) {
        segment->length = chord_length;
        segment->center[0] = segment->midpoint[0];
        segment->center[1] = segment->midpoint[1];
    } else {
        /* With k = |bulge| = tan(a / 2): sin a = 2k / (1 + k^2),
         * cos a = (1 - k^2) / (1 + k^2), written in 1/k beyond 1 so that
         * neither overflows and sin a keeps its digits near a = pi. */
        double k = fabs(bulge);
        double s, c;
        if (k <= 1) {
            s = 2 * k / (1 + k * k);
            c = (1 - k) * (1 + k) / (1 + k * k);
        } else {
            double inverse = 1 / k;
            s = 2 / (k + inverse);
            c = (inverse - k) / (inverse + k);
        }
        double a = 2 * atan(k);
        double h = segment->half_chord;
        segment->half_angle = a;
        segment->half_angle_sin = s;
        segment->half_angle_cos = c;
        segment->radius = h / s;
        segment->sweep = bulge > 0 ? 2 * a : -2 * a;
        segment->length = 2 * a * segment->radius;
        /* The centre lies at w = -r cos a. */
        double offset = -segment->radius * c;
        segment->center[0] = segment->midpoint[0] + offset * segment->bulge_normal[0];
        segment->center[1] = segment->midpoint[1] + offset * segment->bulge_normal[1];
        segment->start_angle =
            atan2(start[1] - segment->center[1], start[0] - segment->center[0]);
    }
}

/* The arc's point at angle phi in [-a, a] from its bisector (chord frame,
 * above). */
static void arc_point_at_angle(const wr_segment *segment, double phi, double point[2])
{
    double a = segment->half_angle, s = segment->half_angle_sin, h = segment->half_chord;
    double u = h * sin(phi) / s;
    double w = 2 * h * sin((a + phi) / 2) * sin((a - phi) / 2) / s;
    point[0] = segment->midpoint[0] + u * segment->direction[0] + w * segment->bulge_normal[0];
    point[1] = segment->midpoint[1] + u * segment->direction[1] + w * segment->bulge_normal[1];
}

/* The point at fraction t in [0, 1] of the segment's length; the vertices
 * exactly at its ends. */
static void segment_point(const wr_segment *segment, double t, double point[2])
{
    if (t <= 0) {
        point[0] = segment->start[0];
        point[1] = segment->start[1];
    } else if (t >= 1) {
        point[0] = segment->end[0];
        point[1] = segment->end[1];
    } else if (!is_arc(segment)) {
        point[0] = segment->start[0] + t * (segment->end[0] - segment->start[0]);
        point[1] = segment->start[1] + t * (segment->end[1] - segment->start[1]);
    } else {
        arc_point_at_angle(segment, segment->half_angle * (2 * t - 1), point);
    }
}

/* The unit normal to the left of the segment's direction of travel at
 * fraction t.  On an arc it is radial: the outward radial direction at phi
 * is sin(phi) e_u + cos(phi) e_w, and travelling counter-clockwise (bulge
 * > 0) the centre is on the left. */
static void segment_left_normal(const wr_segment *segment, double t, double normal[2])
{
    if (!is_arc(segment)) {
        normal[0] = -segment->direction[1];
        normal[1] = segment->direction[0];
        return;
    }
    /* At the ends phi = -+a, whose sine and cosine the bulge gives
     * exactly (a half circle's end normals are exact: (1, 0), not
     * (1, 6e-17)), so a derived normal there equals the one a user writes. */
    double sine, cosine;
    if (t <= 0 || t >= 1) {
        sine = t <= 0 ? -segment->half_angle_sin : segment->half_angle_sin;
        cosine = segment->half_angle_cos;
    } else {
        double phi = segment->half_angle * (2 * t - 1);
        sine = sin(phi);
        cosine = cos(phi);
    }
    double radial[2] = {sine * segment->direction[0] + cosine * segment->bulge_normal[0],
                        sine * segment->direction[1] + cosine * segment->bulge_normal[1]};
    double side = segment->bulge > 0 ? -1 : 1;
    /* Unit up to rounding already; normalised so that callers get a
     * normal of unit length within a few ulp, as wr_fixture expects. */
    double length = hypot(radial[0], radial[1]);
    normal[0] = side * radial[0] / length;
    normal[1] = side * radial[1] / length;
}

/* Distance from p to the segment; *t receives the fraction of the nearest
 * point, `nearest` (may be NULL) the point. */
static double segment_distance(const wr_segment *segment, const double p[2], double *t,
                               double nearest[2])
{
    double q[2] = {p[0] - segment->midpoint[0], p[1] - segment->midpoint[1]};
    double pu = q[0] * segment->direction[0] + q[1] * segment->direction[1];
    double h = segment->half_chord;
    double fraction, distance;
    if (!is_arc(segment)) {
        /* Along the chord from the midpoint: the fraction is (pu + h) / 2h. */
        fraction = h > 0 ? fmax(0.0, fmin(1.0, (pu + h) / (2 * h))) : 0;
        double point[2];
        segment_point(segment, fraction, point);
        distance = hypot(p[0] - point[0], p[1] - point[1]);
        if (nearest) {
            nearest[0] = point[0];
            nearest[1] = point[1];
        }
        *t = fraction;
        return distance;
    }
    double pw = q[0] * segment->bulge_normal[0] + q[1] * segment->bulge_normal[1];
    double a = segment->half_angle, s = segment->half_angle_sin, c = segment->half_angle_cos;
    double r = segment->radius;
    /* The centre is at (0, -k) in the chord frame, k = r cos a. */
    double k = h * c / s;
    double phi = atan2(pu, pw + k);
    if (fabs(phi) <= a) {
        /* |p - centre| - r = (|p - centre|^2 - r^2) / (|p - centre| + r),
         * the numerator pu^2 + pw^2 + 2 pw k - h^2 without r^2 in it. */
        double from_centre = hypot(pu, pw + k);
        distance = fabs(pu * pu + pw * pw + 2 * pw * k - h * h) / (from_centre + r);
        fraction = fmax(0.0, fmin(1.0, (phi + a) / (2 * a)));
    } else {
        double to_start = hypot(p[0] - segment->start[0], p[1] - segment->start[1]);
        double to_end = hypot(p[0] - segment->end[0], p[1] - segment->end[1]);
        fraction = to_start <= to_end ? 0 : 1;
        distance = fmin(to_start, to_end);
    }
    if (nearest)
        segment_point(segment, fraction, nearest);
    *t = fraction;
    return distance;
}

/* The segment's bounding box: its ends, and for an arc each of the
 * circle's four axis extremes that the arc passes through. */
static void segment_box(wr_segment *segment)
{
    for (int i = 0; i < 2; i++) {
        segment->box_min[i] = fmin(segment->start[i], segment->end[i]);
        segment->box_max[i] = fmax(segment->start[i], segment->end[i]);
    }
    if (!is_arc(segment))
        return;
    static const double axes[4][2] = {{1, 0}, {-1, 0}, {0, 1}, {0, -1}};
    for (int i = 0; i < 4; i++) {
        /* The axis direction's angle from the bisector e_w towards e_u. */
        double phi = atan2(axes[i][0] * segment->direction[0] + axes[i][1] * segment->direction[1],
                           axes[i][0] * segment->bulge_normal[0] +
                               axes[i][1] * segment->bulge_normal[1]);
        if (fabs(phi) > segment->half_angle)
            continue;
        double point[2];
        arc_point_at_angle(segment, phi, point);
        for (int j = 0; j < 2; j++) {
            segment->box_min[j] = fmin(segment->box_min[j], point[j]);
            segment->box_max[j] = fmax(segment->box_max[j], point[j]);
        }
    }
}

/* ---- where two segments meet ----------------------------------------------------- */

static bool near_point(const double p[2], const double q[2], double tolerance)
{
    return hypot(p[0] - q[0], p[1] - q[1]) <= tolerance;
}

/* The vertices two segments share (neighbours in a loop share one, the two
 * segments of a 2-vertex loop both): meetings there are allowed. */
typedef struct shared_vertices {
    int count;
    const double *points[2];
} shared_vertices;

static bool at_shared(const shared_vertices *shared, const double p[2], double tolerance)
{
    for (int i = 0; i < shared->count; i++)
        if (near_point(p, shared->points[i], tolerance))
            return true;
    return false;
}

/* Is `candidate` on both segments (within tolerance) and not at a shared
 * vertex?  Then it is where they meet. */
static bool accept(const wr_segment *first, const wr_segment *second, const double candidate[2],
                   const shared_vertices *shared, double tolerance, double point[2])
{
    double t;
    if (!isfinite(candidate[0]) || !isfinite(candidate[1]))
        return false;
    if (at_shared(shared, candidate, tolerance))
        return false;
    if (segment_distance(first, candidate, &t, NULL) > tolerance ||
        segment_distance(second, candidate, &t, NULL) > tolerance)
        return false;
    point[0] = candidate[0];
    point[1] = candidate[1];
    return true;
}

/* Two arcs on one circle (centres and radii within tolerance): do they
 * overlap along more than their ends?  Arc J overlaps arc I iff J's start or
 * end lies strictly inside I, or I's midpoint strictly inside J (I within
 * J, or equal to it); two arcs completing each other do neither. */
static bool strictly_inside_arc(const wr_segment *arc, const double p[2], double tolerance)
{
    double t;
    if (segment_distance(arc, p, &t, NULL) > tolerance)
        return false;
    double from_start = t * arc->length, to_end = (1 - t) * arc->length;
    return from_start > tolerance && to_end > tolerance;
}

static bool arcs_overlap(const wr_segment *first, const wr_segment *second, double tolerance,
                         double point[2])
{
    const double *candidates[3] = {second->start, second->end, NULL};
    for (int i = 0; i < 2; i++)
        if (strictly_inside_arc(first, candidates[i], tolerance)) {
            point[0] = candidates[i][0];
            point[1] = candidates[i][1];
            return true;
        }
    double middle[2];
    segment_point(first, 0.5, middle);
    if (strictly_inside_arc(second, middle, tolerance)) {
        point[0] = middle[0];
        point[1] = middle[1];
        return true;
    }
    return false;
}

/* Where a line and an arc's circle meet, as candidates. */
static int line_circle(const wr_segment *line, const wr_segment *arc,
                       const shared_vertices *shared, double tolerance, double candidates[2][2])
{
    const double *d = line->direction, *centre = arc->center;
    if (shared->count > 0) {
        /* Both pass through the shared vertex V: along the line from V the
         * other root is s = -2 d.(V - centre), without the square root that
         * would make a tangent join (a rounded corner) look like a crossing
         * sqrt(epsilon) away. */
        const double *v = shared->points[0];
        double s = -2 * (d[0] * (v[0] - centre[0]) + d[1] * (v[1] - centre[1]));
        candidates[0][0] = v[0] + s * d[0];
        candidates[0][1] = v[1] + s * d[1];
        return 1;
    }
    /* The foot of the perpendicular from the centre, then +- the half
     * chord of the circle along the line; a line passing within the
     * tolerance of the circle touches it. */
    const double *o = line->start;
    double along = (centre[0] - o[0]) * d[0] + (centre[1] - o[1]) * d[1];
    double foot[2] = {o[0] + along * d[0], o[1] + along * d[1]};
    double distance = hypot(centre[0] - foot[0], centre[1] - foot[1]);
    double r = arc->radius;
    if (distance > r + tolerance)
        return 0;
    double half = sqrt(fmax(0.0, (r - distance) * (r + distance)));
    for (int i = 0; i < 2; i++) {
        double sign = i == 0 ? -1 : 1;
        candidates[i][0] = foot[0] + sign * half * d[0];
        candidates[i][1] = foot[1] + sign * half * d[1];
    }
    return 2;
}

/* Where two circles (not one) meet, as candidates. */
static int circle_circle(const wr_segment *first, const wr_segment *second,
                         const shared_vertices *shared, double tolerance,
                         double candidates[2][2])
{
    const double *c1 = first->center, *c2 = second->center;
    double between[2] = {c2[0] - c1[0], c2[1] - c1[1]};
    double d = hypot(between[0], between[1]);
    if (d == 0)
        return 0; /* concentric and of different radii */
    double e[2] = {between[0] / d, between[1] / d};
    if (shared->count > 0) {
        /* Both pass through V: the other point is V mirrored in the line
         * of centres (V itself when they touch there). */
        const double *v = shared->points[0];
        double rel[2] = {v[0] - c1[0], v[1] - c1[1]};
        double along = rel[0] * e[0] + rel[1] * e[1];
        candidates[0][0] = c1[0] + 2 * along * e[0] - rel[0];
        candidates[0][1] = c1[1] + 2 * along * e[1] - rel[1];
        return 1;
    }
    double r1 = first->radius, r2 = second->radius;
    if (d > r1 + r2 + tolerance || d < fabs(r1 - r2) - tolerance)
        return 0;
    double x = (d * d + (r1 - r2) * (r1 + r2)) / (2 * d);
    double y = sqrt(fmax(0.0, (r1 - x) * (r1 + x)));
    for (int i = 0; i < 2; i++) {
        double sign = i == 0 ? -1 : 1;
        candidates[i][0] = c1[0] + x * e[0] - sign * y * e[1];
        candidates[i][1] = c1[1] + x * e[1] + sign * y * e[0];
    }
    return 2;
}

/* Do two segments meet anywhere but at their shared vertices?  If so,
 * *point receives a point where they do.  Touching counts (within the
 * tolerance), overlapping too. */
static bool segments_meet(const wr_segment *first, const wr_segment *second,
                          const shared_vertices *shared, double tolerance, double point[2])
{
    for (int i = 0; i < 2; i++)
        if (first->box_min[i] > second->box_max[i] + tolerance ||
            second->box_min[i] > first->box_max[i] + tolerance)
            return false;
    /* An end of one on the other: touching, a fold back along a line or a
     * circle, or overlapping lines. */
    const wr_segment *pair[2] = {first, second};
    for (int i = 0; i < 2; i++) {
        const wr_segment *self = pair[i], *other = pair[1 - i];
        const double *ends[2] = {self->start, self->end};
        for (int j = 0; j < 2; j++) {
            double t;
            if (at_shared(shared, ends[j], tolerance))
                continue;
            if (segment_distance(other, ends[j], &t, NULL) <= tolerance) {
                point[0] = ends[j][0];
                point[1] = ends[j][1];
                return true;
            }
        }
    }
    double candidates[2][2];
    int count = 0;
    if (!is_arc(first) && !is_arc(second)) {
        if (shared->count > 0)
            return false; /* two lines through a shared vertex meet only there */
        /* A proper crossing: each line separates the other's ends. */
        return wr_segments_cross(first->start, first->end, second->start, second->end, point);
    }
    if (is_arc(first) && is_arc(second)) {
        bool one_circle = near_point(first->center, second->center, tolerance) &&
                          fabs(first->radius - second->radius) <= tolerance;
        if (one_circle)
            return arcs_overlap(first, second, tolerance, point);
        count = circle_circle(first, second, shared, tolerance, candidates);
    } else if (is_arc(second)) {
        count = line_circle(first, second, shared, tolerance, candidates);
    } else {
        count = line_circle(second, first, shared, tolerance, candidates);
    }
    for (int i = 0; i < count; i++)
        if (accept(first, second, candidates[i], shared, tolerance, point))
            return true;
    return false;
}

/* ---- areas and winding ------------------------------------------------------------- */

/* The signed integrals over a loop's region, counter-clockwise positive as
 * written, relative to an origin o: area, integral of (p - o) dA, and of
 * |p - o|^2 dA.  By Green's theorem the loop is its chord polygon plus, for
 * each arc, its circular segment (signed: + for a counter-clockwise arc,
 * which closes counter-clockwise with its reversed chord). */
typedef struct moments {
    double area;
    double first[2];
    double second;
} moments;

static moments loop_moments(const wr_loop *loop, const double o[2])
{
    moments m = {0, {0, 0}, 0};
    for (size_t j = 0; j < loop->segment_count; j++) {
        const wr_segment *segment = &loop->segments[j];
        double x0 = segment->start[0] - o[0], y0 = segment->start[1] - o[1];
        double x1 = segment->end[0] - o[0], y1 = segment->end[1] - o[1];
        /* The chord's triangle with o (the shoelace terms). */
        double cross = x0 * y1 - x1 * y0;
        m.area += cross / 2;
        m.first[0] += (x0 + x1) * cross / 6;
        m.first[1] += (y0 + y1) * cross / 6;
        m.second += cross * (x0 * x0 + x0 * x1 + x1 * x1 + y0 * y0 + y0 * y1 + y1 * y1) / 12;
        if (!is_arc(segment))
            continue;
        double area, moment, polar;
        circular_segment(segment, &area, &moment, &polar);
        double sign = segment->bulge > 0 ? 1 : -1;
        const double *e = segment->bulge_normal;
        double mx = segment->midpoint[0] - o[0], my = segment->midpoint[1] - o[1];
        m.area += sign * area;
        m.first[0] += sign * (area * mx + moment * e[0]);
        m.first[1] += sign * (area * my + moment * e[1]);
        m.second += sign * (area * (mx * mx + my * my) + 2 * moment * (mx * e[0] + my * e[1]) + polar);
    }
    return m;
}

/* The sign of v + e dy + e^2 dx for an infinitesimal e > 0: the sign at p
 * of a quantity with those derivatives, evaluated at p moved up by e and
 * right by e^2, a point on no line through p.  Ties at p (p exactly on a
 * chord's line, which integer coordinates make common) are so broken the
 * same way everywhere. */
static int perturbed_sign(double v, double dy, double dx)
{
    if (v != 0)
        return v > 0 ? 1 : -1;
    if (dy != 0)
        return dy > 0 ? 1 : -1;
    return dx > 0 ? 1 : dx < 0 ? -1 : 0;
}

/* The winding number of the loop about p (not on it), p moved as in
 * perturbed_sign: its chord polygon's (crossings of the rightward ray,
 * half-open in y, which is the same move), plus the sign of each arc whose
 * circular segment holds p (the open disc on the bulge's side of the
 * chord).  Which side of a chord p lies on is decided once, for both: two
 * computations could round differently and count p twice or never. */
static int loop_winding(const wr_loop *loop, const double p[2])
{
    int winding = 0;
    for (size_t j = 0; j < loop->segment_count; j++) {
        const wr_segment *segment = &loop->segments[j];
        const double *a = segment->start, *b = segment->end;
        int left = perturbed_sign((b[0] - a[0]) * (p[1] - a[1]) - (p[0] - a[0]) * (b[1] - a[1]),
                                  b[0] - a[0], -(b[1] - a[1]));
        if (a[1] <= p[1]) {
            if (b[1] > p[1] && left > 0)
                winding++;
        } else if (b[1] <= p[1] && left < 0) {
            winding--;
        }
        if (!is_arc(segment))
            continue;
        /* A counter-clockwise arc bulges to the right of its chord. */
        bool bulge_side = segment->bulge > 0 ? left < 0 : left > 0;
        if (!bulge_side)
            continue;
        double q[2] = {p[0] - segment->midpoint[0], p[1] - segment->midpoint[1]};
        double pu = q[0] * segment->direction[0] + q[1] * segment->direction[1];
        double pw = q[0] * segment->bulge_normal[0] + q[1] * segment->bulge_normal[1];
        double h = segment->half_chord;
        double k = h * segment->half_angle_cos / segment->half_angle_sin;
        /* In the disc: |p - centre|^2 - r^2 = pu^2 + pw^2 + 2 pw k - h^2 < 0. */
        if (pu * pu + pw * pw + 2 * pw * k - h * h < 0)
            winding += segment->bulge > 0 ? 1 : -1;
    }
    return winding;
}

/* ---- validation ---------------------------------------------------------------------- */

static void describe_segment(char *text, size_t size, const wr_loop *loop, size_t j)
{
    snprintf(text, size, "segment %zu (vertices %zu to %zu)", j, j,
             (j + 1) % loop->segment_count);
}

static void report_simple(const wr_outline *outline, size_t i, size_t j, size_t l,
                          const double point[2], wr_error *error)
{
    const wr_loop *loop = &outline->loops[i];
    char field[96], one[96], two[96];
    snprintf(field, sizeof field, "loops[%zu]", i);
    describe_segment(one, sizeof one, loop, j);
    describe_segment(two, sizeof two, loop, l);
    wr_error_set(error, field, "the loop is not simple: %s and %s meet at (%g, %g)", one, two,
                 point[0], point[1]);
}

static void report_apart(const wr_outline *outline, size_t i, size_t other, size_t j, size_t l,
                         const double point[2], wr_error *error)
{
    char field[96], one[96], two[96];
    snprintf(field, sizeof field, "loops[%zu]", i);
    describe_segment(one, sizeof one, &outline->loops[i], j);
    describe_segment(two, sizeof two, &outline->loops[other], l);
    if (other == 0)
        wr_error_set(error, field,
                     "the hole meets the outer loop (loops[0]): its %s and the outer loop's %s "
                     "meet at (%g, %g)",
                     one, two, point[0], point[1]);
    else
        wr_error_set(error, field,
                     "the hole meets hole loops[%zu]: its %s and that hole's %s meet at (%g, %g)",
                     other, one, two, point[0], point[1]);
}

/* Segments j < l of loop i meet where a simple loop's do not?  Neighbours
 * share their common vertex (both ends in a 2-vertex loop), where meeting
 * is allowed. */
static bool loop_pair_meets(const wr_outline *outline, size_t i, size_t j, size_t l,
                            double tolerance, double point[2])
{
    const wr_loop *loop = &outline->loops[i];
    size_t n = loop->segment_count;
    const wr_segment *first = &loop->segments[j], *second = &loop->segments[l];
    shared_vertices shared = {0, {NULL, NULL}};
    if (l == j + 1)
        shared.points[shared.count++] = first->end;
    if (j == 0 && l == n - 1)
        shared.points[shared.count++] = first->start;
    return segments_meet(first, second, &shared, tolerance, point);
}

/* Every pair in index order, the first that meets reported: the reference
 * the sweep below is tested against (wr_outline_new_checked). */
static bool check_simple_exhaustively(const wr_outline *outline, size_t i, double tolerance,
                                      wr_error *error)
{
    size_t n = outline->loops[i].segment_count;
    for (size_t j = 0; j < n; j++)
        for (size_t l = j + 1; l < n; l++) {
            double point[2];
            if (loop_pair_meets(outline, i, j, l, tolerance, point)) {
                report_simple(outline, i, j, l, point, error);
                return false;
            }
        }
    return true;
}

/* Loop i against every earlier loop, pair by pair in index order. */
static bool check_apart_exhaustively(const wr_outline *outline, size_t i, double tolerance,
                                     wr_error *error)
{
    const wr_loop *loop = &outline->loops[i];
    shared_vertices none = {0, {NULL, NULL}};
    for (size_t other = 0; other < i; other++) {
        const wr_loop *earlier = &outline->loops[other];
        for (size_t j = 0; j < loop->segment_count; j++)
            for (size_t l = 0; l < earlier->segment_count; l++) {
                double point[2];
                if (segments_meet(&loop->segments[j], &earlier->segments[l], &none, tolerance,
                                  point)) {
                    report_apart(outline, i, other, j, l, point, error);
                    return false;
                }
            }
    }
    return true;
}

/* Where the segments of an outline meet, found by one sweep over all its
 * segments' boxes (wr_box_pairs): for each loop the first pair of its own
 * that meets, and the first pair of two loops, "first" in the order the
 * exhaustive checks above visit them, so that the errors are theirs:
 *   within loop i:  (j, l), j < l;
 *   across loops:   (i, other, j, l), other < i, j in loop i, l in other.
 * A pair at or after the best found so far is not tested at all. */
typedef struct meeting {
    bool found;
    size_t key[4];
    double point[2];
} meeting;

typedef struct meetings {
    const wr_outline *outline;
    double tolerance;
    const size_t *loop_of;  /* a segment's loop, by its index in the block */
    const size_t *first_of; /* a loop's first segment's index in the block */
    meeting *simple;        /* one per loop */
    meeting apart;
} meetings;

static bool key_before(const size_t *key, const meeting *best, int length)
{
    if (!best->found)
        return true;
    for (int k = 0; k < length; k++)
        if (key[k] != best->key[k])
            return key[k] < best->key[k];
    return false;
}

/* Segment s lies in the rectangle of its chord frame u in [-U, U],
 * w in [0, S]: a line on its chord (S = 0); an arc between its chord and
 * its sagitta h tan(a / 2) = h |bulge|, as wide as its chord up to a half
 * circle and as its circle beyond.  Its extent along the unit axis n,
 * relative to the point o: [*lo, *hi]. */
static void segment_extent(const wr_segment *s, const double o[2], const double n[2], double *lo,
                           double *hi)
{
    double h = s->half_chord;
    double U = is_arc(s) && s->half_angle > WR_PI / 2 ? s->radius : h;
    double S = h * fabs(s->bulge);
    double centre = (s->midpoint[0] - o[0]) * n[0] + (s->midpoint[1] - o[1]) * n[1] +
                    S / 2 * (s->bulge_normal[0] * n[0] + s->bulge_normal[1] * n[1]);
    double half = U * fabs(s->direction[0] * n[0] + s->direction[1] * n[1]) +
                  S / 2 * fabs(s->bulge_normal[0] * n[0] + s->bulge_normal[1] * n[1]);
    *lo = centre - half;
    *hi = centre + half;
}

/* Are the two segments further apart than twice the tolerance along one
 * of their chords' normals (with room for rounding)?  Then no point of one
 * is within the tolerance of the other, nor do they cross, and
 * segments_meet would say so: the pairs of long thin segments whose boxes
 * overlap (a star's spikes, a zigzag's teeth) are set aside for the cost of
 * a few products. */
static bool segments_apart(const wr_segment *first, const wr_segment *second, double tolerance)
{
    const wr_segment *pair[2] = {first, second};
    double reach = 0;
    for (int i = 0; i < 2; i++)
        reach += fabs(pair[i]->midpoint[0]) + fabs(pair[i]->midpoint[1]) + pair[i]->radius +
                 pair[i]->half_chord * (1 + fabs(pair[i]->bulge));
    double gap = 2 * tolerance + 1e-12 * reach;
    for (int i = 0; i < 2; i++) {
        const double *o = pair[i]->midpoint, *n = pair[i]->bulge_normal;
        double lo[2], hi[2];
        segment_extent(pair[0], o, n, &lo[0], &hi[0]);
        segment_extent(pair[1], o, n, &lo[1], &hi[1]);
        if (lo[1] > hi[0] + gap || lo[0] > hi[1] + gap)
            return true;
    }
    return false;
}

static void visit_segments(void *context, size_t g, size_t h)
{
    meetings *m = context;
    size_t loop_g = m->loop_of[g], loop_h = m->loop_of[h];
    size_t j = g - m->first_of[loop_g], l = h - m->first_of[loop_h];
    double point[2];
    if (loop_g == loop_h) {
        size_t key[4] = {j, l, 0, 0};
        meeting *best = &m->simple[loop_g];
        if (key_before(key, best, 2) &&
            !segments_apart(&m->outline->loops[loop_g].segments[j],
                            &m->outline->loops[loop_g].segments[l], m->tolerance) &&
            loop_pair_meets(m->outline, loop_g, j, l, m->tolerance, point))
            *best = (meeting){true, {j, l, 0, 0}, {point[0], point[1]}};
        return;
    }
    /* g < h and the block holds the loops in order: h's loop is the later. */
    size_t key[4] = {loop_h, loop_g, l, j};
    shared_vertices none = {0, {NULL, NULL}};
    const wr_segment *later = &m->outline->loops[loop_h].segments[l],
                     *earlier = &m->outline->loops[loop_g].segments[j];
    if (key_before(key, &m->apart, 4) && !segments_apart(later, earlier, m->tolerance) &&
        segments_meet(later, earlier, &none, m->tolerance, point))
        m->apart = (meeting){true, {key[0], key[1], key[2], key[3]}, {point[0], point[1]}};
}

/* Fill m (its arrays allocated here; meetings_free) by the sweep.  False
 * when out of memory. */
static bool find_meetings(const wr_outline *outline, double tolerance, meetings *m)
{
    size_t total = outline->vertex_count, loops = outline->loop_count;
    size_t *loop_of = malloc(total * sizeof *loop_of);
    size_t *first_of = malloc(loops * sizeof *first_of);
    wr_box *boxes = malloc(total * sizeof *boxes);
    *m = (meetings){outline, tolerance, loop_of, first_of, calloc(loops, sizeof(meeting)),
                    {false, {0, 0, 0, 0}, {0, 0}}};
    bool ok = loop_of && first_of && boxes && m->simple;
    if (ok) {
        size_t g = 0;
        for (size_t i = 0; i < loops; i++) {
            first_of[i] = g;
            const wr_loop *loop = &outline->loops[i];
            assert(loop->segments == outline->loops[0].segments + g);
            for (size_t j = 0; j < loop->segment_count; j++, g++) {
                loop_of[g] = i;
                for (int k = 0; k < 2; k++) {
                    boxes[g].min[k] = loop->segments[j].box_min[k];
                    boxes[g].max[k] = loop->segments[j].box_max[k];
                }
            }
        }
        /* segments_meet refuses boxes apart by more than the tolerance; a
         * margin of the tolerance on each box keeps every pair it would
         * test. */
        ok = wr_box_pairs(boxes, total, tolerance, visit_segments, m);
    }
    free(boxes);
    return ok;
}

static void meetings_free(meetings *m)
{
    free((void *)m->loop_of);
    free((void *)m->first_of);
    free(m->simple);
}

/* Hole i (meeting no other loop) inside the outer loop, outside the other
 * holes and not around them.  A loop meeting none of the others is wholly
 * inside or outside each, so one vertex tells. */
static void report_nesting(size_t i, size_t other, bool contains, const double vertex[2],
                           wr_error *error)
{
    char field[96];
    snprintf(field, sizeof field, "loops[%zu]", i);
    if (other == 0)
        wr_error_set(error, field,
                     "the hole is not inside the outer loop (loops[0]): vertex 0 (%g, %g) lies "
                     "outside it",
                     vertex[0], vertex[1]);
    else
        wr_error_set(error, field, "the hole %s hole loops[%zu]: holes must be apart",
                     contains ? "contains" : "lies inside", other);
}

/* Hole i against the outer loop and each earlier hole, one by one: the
 * reference (wr_outline_new_checked) for the boxes' sweep below. */
static bool check_nesting(const wr_outline *outline, size_t i, wr_error *error)
{
    const double *vertex = outline->loops[i].segments[0].start;
    if (loop_winding(&outline->loops[0], vertex) == 0) {
        report_nesting(i, 0, false, vertex, error);
        return false;
    }
    for (size_t other = 1; other < i; other++) {
        const double *theirs = outline->loops[other].segments[0].start;
        if (loop_winding(&outline->loops[other], vertex) != 0) {
            report_nesting(i, other, false, vertex, error);
            return false;
        }
        if (loop_winding(&outline->loops[i], theirs) != 0) {
            report_nesting(i, other, true, vertex, error);
            return false;
        }
    }
    return true;
}

/* Two holes (apart, as checked before) are nested only if their boxes
 * overlap: the sweep over the holes' boxes finds those pairs, and of the
 * nested ones keeps the first in check_nesting's order (the later hole,
 * then the earlier, "inside" before "contains"). */
typedef struct nesting {
    const wr_outline *outline;
    bool found;
    size_t key[3]; /* i, other, contains */
} nesting;

static void visit_holes(void *context, size_t a, size_t b)
{
    nesting *n = context;
    size_t other = a + 1, i = b + 1; /* the boxes are of loops 1 on */
    const wr_loop *loops = n->outline->loops;
    for (size_t contains = 0; contains < 2; contains++) {
        size_t key[3] = {i, other, contains};
        if (n->found && (key[0] > n->key[0] || (key[0] == n->key[0] && key[1] > n->key[1]) ||
                         (key[0] == n->key[0] && key[1] == n->key[1] && key[2] >= n->key[2])))
            return;
        const wr_loop *around = contains ? &loops[i] : &loops[other];
        const double *vertex = contains ? loops[other].segments[0].start : loops[i].segments[0].start;
        if (loop_winding(around, vertex) != 0) {
            *n = (nesting){n->outline, true, {i, other, contains}};
            return;
        }
    }
}

static wr_status check_holes_nested(const wr_outline *outline, wr_error *error)
{
    size_t holes = outline->loop_count - 1;
    wr_box *boxes = malloc((holes ? holes : 1) * sizeof *boxes);
    if (!boxes) {
        wr_error_set(error, "", "out of memory");
        return WR_NO_MEMORY;
    }
    for (size_t h = 0; h < holes; h++) {
        const wr_loop *loop = &outline->loops[h + 1];
        boxes[h] = (wr_box){{INFINITY, INFINITY}, {-INFINITY, -INFINITY}};
        for (size_t j = 0; j < loop->segment_count; j++)
            for (int k = 0; k < 2; k++) {
                boxes[h].min[k] = fmin(boxes[h].min[k], loop->segments[j].box_min[k]);
                boxes[h].max[k] = fmax(boxes[h].max[k], loop->segments[j].box_max[k]);
            }
    }
    nesting n = {outline, false, {0, 0, 0}};
    bool ok = wr_box_pairs(boxes, holes, 0, visit_holes, &n);
    free(boxes);
    if (!ok) {
        wr_error_set(error, "", "out of memory");
        return WR_NO_MEMORY;
    }
    /* The outer loop around each hole, up to the first nested pair's. */
    size_t last = n.found ? n.key[0] : outline->loop_count - 1;
    for (size_t i = 1; i <= last; i++) {
        const double *vertex = outline->loops[i].segments[0].start;
        if (loop_winding(&outline->loops[0], vertex) == 0) {
            report_nesting(i, 0, false, vertex, error);
            return WR_INVALID;
        }
    }
    if (n.found) {
        report_nesting(n.key[0], n.key[1], n.key[2], outline->loops[n.key[0]].segments[0].start,
                       error);
        return WR_INVALID;
    }
    return WR_OK;
}

/* The numbers one by one, then the loops' segments. */
static bool check_numbers(const wr_loop_spec *loops, size_t loop_count, wr_error *error)
{
    if (!loops || loop_count == 0) {
        wr_error_set(error, "loops", "an outline needs at least one loop, its outer boundary");
        return false;
    }
    size_t total = 0;
    for (size_t i = 0; i < loop_count; i++) {
        char field[96];
        snprintf(field, sizeof field, "loops[%zu]", i);
        size_t n = loops[i].vertex_count;
        if (n < 2 || !loops[i].vertices) {
            wr_error_set(error, field, "a loop needs at least 2 vertices, %zu given",
                         loops[i].vertices ? n : 0);
            return false;
        }
        total += n;
        if (total > WR_OUTLINE_MAX_VERTICES) {
            wr_error_set(error, "loops", "at most %d vertices are accepted over all loops",
                         WR_OUTLINE_MAX_VERTICES);
            return false;
        }
        for (size_t j = 0; j < n; j++)
            for (int k = 0; k < 3; k++)
                if (!isfinite(loops[i].vertices[j][k])) {
                    snprintf(field, sizeof field, "loops[%zu][%zu][%d]", i, j, k);
                    wr_error_set(error, field, "must be a finite number");
                    return false;
                }
        if (n == 2 && loops[i].vertices[0][2] == 0 && loops[i].vertices[1][2] == 0) {
            wr_error_set(error, field,
                         "a loop of 2 vertices encloses no area unless a bulge is nonzero");
            return false;
        }
    }
    return true;
}

static void loop_box(const wr_outline *outline, double box_min[2], double box_max[2])
{
    box_min[0] = box_min[1] = INFINITY;
    box_max[0] = box_max[1] = -INFINITY;
    for (size_t i = 0; i < outline->loop_count; i++)
        for (size_t j = 0; j < outline->loops[i].segment_count; j++) {
            const wr_segment *segment = &outline->loops[i].segments[j];
            for (int k = 0; k < 2; k++) {
                box_min[k] = fmin(box_min[k], segment->box_min[k]);
                box_max[k] = fmax(box_max[k], segment->box_max[k]);
            }
        }
}

/* check_geometry's checks from the simple loops on; m NULL: pair by pair. */
static wr_status check_loops(wr_outline *outline, const meetings *m, double tolerance,
                             wr_error *error)
{
    double size = outline->size;
    for (size_t i = 0; i < outline->loop_count; i++) {
        /* Simple before the area: a bow tie's lobes cancel, and "encloses
         * no area" would hide that its segments cross. */
        if (m && m->simple[i].found) {
            report_simple(outline, i, m->simple[i].key[0], m->simple[i].key[1],
                          m->simple[i].point, error);
            return WR_INVALID;
        }
        if (!m && !check_simple_exhaustively(outline, i, tolerance, error))
            return WR_INVALID;
        wr_loop *loop = &outline->loops[i];
        moments integrals = loop_moments(loop, loop->segments[0].start);
        /* Compared as area / size with size: size * size may overflow. */
        if (!(fabs(integrals.area) / size > DEGENERATE_TOLERANCE * size)) {
            char field[96];
            snprintf(field, sizeof field, "loops[%zu]", i);
            wr_error_set(error, field, isfinite(integrals.area)
                                           ? "the loop encloses no area"
                                           : "the loop is too large for double precision: its "
                                             "area overflows");
            return WR_INVALID;
        }
        loop->signed_area = integrals.area;
        loop->orientation = integrals.area > 0 ? 1 : -1;
        loop->material_side = i == 0 ? loop->orientation : -loop->orientation;
    }
    if (m && m->apart.found) {
        const size_t *key = m->apart.key;
        report_apart(outline, key[0], key[1], key[2], key[3], m->apart.point, error);
        return WR_INVALID;
    }
    for (size_t i = 1; !m && i < outline->loop_count; i++)
        if (!check_apart_exhaustively(outline, i, tolerance, error))
            return WR_INVALID;
    if (m)
        return check_holes_nested(outline, error);
    for (size_t i = 1; i < outline->loop_count; i++)
        if (!check_nesting(outline, i, error))
            return WR_INVALID;
    return WR_OK;
}

/* Everything after the numbers: segments of length, simple loops of area,
 * apart, nested as an outline's.  Where segments meet is found by the sweep
 * (find_meetings), or with `exhaustively` pair by pair; the first fault is
 * reported either way, the same one.  WR_OK, WR_INVALID or WR_NO_MEMORY. */
static wr_status check_geometry(wr_outline *outline, bool exhaustively, wr_error *error)
{
    loop_box(outline, outline->box_min, outline->box_max);
    outline->size = hypot(outline->box_max[0] - outline->box_min[0],
                          outline->box_max[1] - outline->box_min[1]);
    if (!isfinite(outline->size)) {
        wr_error_set(error, "loops",
                     "the outline is too large for double precision: its extent overflows");
        return WR_INVALID;
    }
    double size = outline->size;
    for (size_t i = 0; i < outline->loop_count; i++) {
        const wr_loop *loop = &outline->loops[i];
        for (size_t j = 0; j < loop->segment_count; j++) {
            const wr_segment *segment = &loop->segments[j];
            if (2 * segment->half_chord <= DEGENERATE_TOLERANCE * size) {
                char field[96];
                size_t next = (j + 1) % loop->segment_count;
                snprintf(field, sizeof field, "loops[%zu][%zu]", i, next);
                wr_error_set(error, field,
                             "repeats vertex %zu: segment %zu between them has no length", j, j);
                return WR_INVALID;
            }
        }
    }
    double tolerance = WR_OUTLINE_TOLERANCE * size;
    meetings m = {0};
    if (!exhaustively && !find_meetings(outline, tolerance, &m)) {
        meetings_free(&m);
        wr_error_set(error, "", "out of memory");
        return WR_NO_MEMORY;
    }
    wr_status status = check_loops(outline, exhaustively ? NULL : &m, tolerance, error);
    meetings_free(&m);
    return status;
}

/* Area, centroid, polar moment and perimeter of the lamina: each loop's
 * signed integrals with the sign that makes the outer loop's region count
 * and the holes' not (material_side * orientation is +1 for the outer loop,
 * -1 for a hole; times the signed integrals of the loop as written gives
 * +|outer| and -|hole|).  About the outer loop's vertex 0, so the products
 * are of the part's size rather than of its distance from the origin. */
static bool mass_properties(wr_outline *outline, wr_error *error)
{
    const double *o = outline->loops[0].segments[0].start;
    double area = 0, first[2] = {0, 0}, second = 0, perimeter = 0;
    for (size_t i = 0; i < outline->loop_count; i++) {
        wr_loop *loop = &outline->loops[i];
        moments m = loop_moments(loop, o);
        double sign = i == 0 ? loop->orientation : -loop->orientation;
        area += sign * m.area;
        first[0] += sign * m.first[0];
        first[1] += sign * m.first[1];
        second += sign * m.second;
        loop->perimeter = 0;
        for (size_t j = 0; j < loop->segment_count; j++)
            loop->perimeter += loop->segments[j].length;
        perimeter += loop->perimeter;
    }
    double cx = first[0] / area, cy = first[1] / area;
    outline->area = area;
    outline->centroid[0] = o[0] + cx;
    outline->centroid[1] = o[1] + cy;
    /* The parallel-axis theorem back from o to the centroid. */
    outline->polar_moment = second - area * (cx * cx + cy * cy);
    outline->perimeter = perimeter;
    if (!isfinite(outline->area) || !isfinite(outline->centroid[0]) ||
        !isfinite(outline->centroid[1]) || !isfinite(outline->polar_moment) ||
        !isfinite(outline->perimeter) || !(outline->polar_moment > 0)) {
        wr_error_set(error, "loops",
                     "the outline is too large for double precision: its second moment of area "
                     "overflows (it spans %g)",
                     outline->size);
        return false;
    }
    return true;
}

wr_status wr_outline_new(const wr_loop_spec *loops, size_t loop_count, wr_outline **out,
                         wr_error *error)
{
    return wr_outline_new_checked(loops, loop_count, false, out, error);
}

wr_status wr_outline_new_checked(const struct wr_loop_spec *loops, size_t loop_count,
                                 bool exhaustively, struct wr_outline **out, wr_error *error)
{
    *out = NULL;
    if (!check_numbers(loops, loop_count, error))
        return WR_INVALID;
    size_t total = 0;
    for (size_t i = 0; i < loop_count; i++)
        total += loops[i].vertex_count;
    wr_outline *outline = calloc(1, sizeof *outline);
    wr_loop *built = calloc(loop_count, sizeof *built);
    wr_segment *segments = calloc(total, sizeof *segments);
    if (!outline || !built || !segments) {
        free(outline);
        free(built);
        free(segments);
        wr_error_set(error, "", "out of memory");
        return WR_NO_MEMORY;
    }
    outline->loop_count = loop_count;
    outline->loops = built;
    outline->vertex_count = total;
    /* All segments in one block: loop 0's first owns it. */
    size_t next = 0;
    for (size_t i = 0; i < loop_count; i++) {
        size_t n = loops[i].vertex_count;
        built[i].segment_count = n;
        built[i].segments = segments + next;
        next += n;
        for (size_t j = 0; j < n; j++) {
            const double *from = loops[i].vertices[j], *to = loops[i].vertices[(j + 1) % n];
            segment_build(&built[i].segments[j], from, to, from[2]);
            segment_box(&built[i].segments[j]);
        }
    }
    wr_status status = check_geometry(outline, exhaustively, error);
    if (status == WR_OK && !mass_properties(outline, error))
        status = WR_INVALID;
    if (status != WR_OK) {
        wr_outline_free(outline);
        return status;
    }
    *out = outline;
    return WR_OK;
}

wr_status wr_outline_polygon(const double (*vertices)[2], size_t count, wr_outline **out)
{
    *out = NULL;
    assert(count >= 3);
    wr_outline *outline = calloc(1, sizeof *outline);
    wr_loop *loop = calloc(1, sizeof *loop);
    wr_segment *segments = calloc(count, sizeof *segments);
    if (!outline || !loop || !segments) {
        free(outline);
        free(loop);
        free(segments);
        return WR_NO_MEMORY;
    }
    outline->loop_count = 1;
    outline->loops = loop;
    outline->vertex_count = count;
    loop->segment_count = count;
    loop->segments = segments;
    for (size_t j = 0; j < count; j++) {
        segment_build(&segments[j], vertices[j], vertices[(j + 1) % count], 0);
        segment_box(&segments[j]);
    }
    loop_box(outline, outline->box_min, outline->box_max);
    outline->size = hypot(outline->box_max[0] - outline->box_min[0],
                          outline->box_max[1] - outline->box_min[1]);
    moments m = loop_moments(loop, segments[0].start);
    loop->signed_area = m.area;
    loop->orientation = m.area > 0 ? 1 : -1;
    loop->material_side = loop->orientation;
    if (!mass_properties(outline, NULL)) { /* validated polygons fit: never */
        wr_outline_free(outline);
        return WR_INVALID;
    }
    *out = outline;
    return WR_OK;
}

void wr_outline_free(wr_outline *outline)
{
    if (!outline)
        return;
    if (outline->loops)
        free(outline->loops[0].segments);
    free(outline->loops);
    free(outline);
}

/* ---- boundary queries ------------------------------------------------------------------ */

void wr_outline_boundary(const wr_outline *outline, size_t loop, size_t segment, double t,
                         double point[2], double normal[2])
{
    const wr_loop *l = &outline->loops[loop];
    const wr_segment *s = &l->segments[segment];
    t = fmax(0.0, fmin(1.0, t)); /* also turns a NaN into 0 */
    segment_point(s, t, point);
    if (normal) {
        segment_left_normal(s, t, normal);
        normal[0] *= l->material_side;
        normal[1] *= l->material_side;
    }
}

double wr_outline_nearest_on_loop(const wr_outline *outline, size_t loop, const double p[2],
                                  size_t *segment, double *t, double point[2])
{
    const wr_loop *l = &outline->loops[loop];
    double best = INFINITY;
    for (size_t j = 0; j < l->segment_count; j++) {
        double tj, nearest[2];
        double d = segment_distance(&l->segments[j], p, &tj, nearest);
        if (d < best) {
            best = d;
            *segment = j;
            *t = tj;
            point[0] = nearest[0];
            point[1] = nearest[1];
        }
    }
    return best;
}

/* Is the direction at angle phi within the arc's sweep from its start? */
static bool arc_passes(const wr_segment *s, double phi)
{
    double from = s->sweep > 0 ? s->start_angle : s->start_angle + s->sweep;
    double along = fmod(phi - from, 2 * WR_PI);
    if (along < 0)
        along += 2 * WR_PI;
    return along <= fabs(s->sweep);
}

double wr_outline_loop_width(const wr_outline *outline, size_t loop)
{
    const wr_loop *l = &outline->loops[loop];
    double width = INFINITY;
    for (int k = 0; k < WR_WIDTH_STEPS; k++) {
        double phi = WR_PI * k / WR_WIDTH_STEPS, u[2] = {cos(phi), sin(phi)};
        double lo = INFINITY, hi = -INFINITY;
        for (size_t j = 0; j < l->segment_count; j++) {
            const wr_segment *s = &l->segments[j];
            double along = s->start[0] * u[0] + s->start[1] * u[1];
            lo = fmin(lo, along);
            hi = fmax(hi, along);
            if (!is_arc(s))
                continue;
            /* An arc also reaches its circle's extremes along u where it
             * passes them. */
            double centre = s->center[0] * u[0] + s->center[1] * u[1];
            if (arc_passes(s, phi))
                hi = fmax(hi, centre + s->radius);
            if (arc_passes(s, phi + WR_PI))
                lo = fmin(lo, centre - s->radius);
        }
        width = fmin(width, hi - lo);
    }
    return width;
}

bool wr_outline_locate(const wr_outline *outline, const double p[2], double tolerance,
                       wr_outline_place *place)
{
    if (!isfinite(p[0]) || !isfinite(p[1]) || !isfinite(tolerance) || !(tolerance >= 0))
        return false;
    /* The nearest segment, and separately the nearest vertex within the
     * tolerance, which takes precedence. */
    wr_outline_place best;
    memset(&best, 0, sizeof best);
    best.distance = INFINITY;
    double vertex_distance = INFINITY;
    size_t vertex_loop = 0, vertex = 0;
    for (size_t i = 0; i < outline->loop_count; i++) {
        const wr_loop *loop = &outline->loops[i];
        for (size_t j = 0; j < loop->segment_count; j++) {
            const wr_segment *segment = &loop->segments[j];
            double t, nearest[2];
            double distance = segment_distance(segment, p, &t, nearest);
            if (distance < best.distance) {
                best.distance = distance;
                best.loop = i;
                best.segment = j;
                best.t = t;
                best.point[0] = nearest[0];
                best.point[1] = nearest[1];
            }
            double to_vertex = hypot(p[0] - segment->start[0], p[1] - segment->start[1]);
            if (to_vertex <= tolerance && to_vertex < vertex_distance) {
                vertex_distance = to_vertex;
                vertex_loop = i;
                vertex = j;
            }
        }
    }
    if (vertex_distance <= tolerance) {
        const wr_loop *loop = &outline->loops[vertex_loop];
        const wr_segment *leaving = &loop->segments[vertex];
        const wr_segment *arriving =
            &loop->segments[(vertex + loop->segment_count - 1) % loop->segment_count];
        best.at_vertex = true;
        best.loop = vertex_loop;
        best.vertex = vertex;
        best.segment = vertex;
        best.t = 0;
        best.point[0] = leaving->start[0];
        best.point[1] = leaving->start[1];
        best.distance = vertex_distance;
        double before[2], after[2];
        segment_left_normal(arriving, 1, before);
        segment_left_normal(leaving, 0, after);
        /* The angle between the normals, from their cross and dot products. */
        double angle = atan2(fabs(before[0] * after[1] - before[1] * after[0]),
                             before[0] * after[0] + before[1] * after[1]);
        best.smooth = angle <= WR_OUTLINE_TOLERANCE;
    }
    if (!(best.distance <= tolerance))
        return false;
    if (place)
        *place = best;
    return true;
}

double wr_outline_distance(const wr_outline *outline, const double p[2])
{
    double best = INFINITY;
    for (size_t i = 0; i < outline->loop_count; i++)
        for (size_t j = 0; j < outline->loops[i].segment_count; j++) {
            double t;
            best = fmin(best, segment_distance(&outline->loops[i].segments[j], p, &t, NULL));
        }
    return best;
}

bool wr_outline_contains(const wr_outline *outline, const double p[2], double tolerance)
{
    if (!isfinite(p[0]) || !isfinite(p[1]))
        return false;
    if (wr_outline_locate(outline, p, tolerance, NULL))
        return false;
    if (loop_winding(&outline->loops[0], p) == 0)
        return false;
    for (size_t i = 1; i < outline->loop_count; i++)
        if (loop_winding(&outline->loops[i], p) != 0)
            return false;
    return true;
}
