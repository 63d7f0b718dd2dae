/* wr_finger.c -- where a round finger fits against an outline (wr_finger.h).
 *
 * Along segment S the finger's centre is c(t) = p(t) - r nu(t).  It is
 * blocked at t iff the open disc of radius r about c(t) meets the
 * material, i.e. iff c(t) lies in the open set
 *     B = {x : dist(x, boundary) < r}
 * (c inside the material is in B: see overlaps() below),
 * whose boundary is within {x : dist(x, boundary) = r}: c(t) can enter or
 * leave B only where it crosses the curve at distance r from some segment.
 * For a straight segment that curve lies on the two lines parallel to it
 * at distance r and the circles of radius r about its ends; for an arc on
 * the circles of radius R + r and R - r about its centre and the circles
 * about its ends.  Using the whole lines and circles gives more crossings
 * than needed, which costs nothing: a crossing where nothing changes only
 * splits a piece into two that are decided alike and merged again.  What
 * must not happen is to miss one, and a crossing missed to rounding (a
 * discriminant just below 0) is a tangency, where the overlap between the
 * two roots is of the order of the rounding, far below the tolerance.
 *
 * Everything is computed in S's chord frame (origin at the chord's
 * midpoint, u along the chord, w towards the bulge; for a line w is its
 * left normal), where c is
 *     a line:   c(t) = (-h + 2 h t, w_c),  w_c = -r nu_w, nu_w = +-1;
 *     an arc:   c(phi) = (rho sin phi, rho cos phi - k), phi = a (2 t - 1),
 * with the arc's centre at (0, -k), k = R cos a, and rho = R + r when the
 * material is inside the arc's circle (nu points to the centre), R - r
 * (possibly negative: c then runs on the far side of the centre) when
 * outside it. */
#include "wr_finger.h"
#include "wr_internal.h"

#include <assert.h>
#include <limits.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* The most crossings one obstacle can add: an arc path meets each of two
 * lines or each of three circles at most twice; a straight path meets a
 * circle twice and a line once. */
#define CROSSINGS_PER_SEGMENT 6

/* The finger centre's path, in the chord frame of the segment pushed on. */
typedef struct path {
    bool arc;
    double origin[2], axis_u[2], axis_w[2]; /* the frame */
    double half_chord;                      /* line: h */
    double w;                               /* line: w_c */
    double half_angle;                      /* arc: a */
    double rho, k;                          /* arc: as above */
    double tolerance;
} path;

/* Crossing parameters in [0, 1], at most CROSSINGS_PER_SEGMENT per
 * obstacle plus the ends. */
typedef struct crossings {
    double *t;
    size_t count, capacity;
} crossings;

static void add(crossings *out, double t)
{
    assert(out->count < out->capacity);
    if (t >= 0 && t <= 1)
        out->t[out->count++] = t;
}

static void to_frame(const path *p, const double x[2], double out[2])
{
    double d[2] = {x[0] - p->origin[0], x[1] - p->origin[1]};
    out[0] = d[0] * p->axis_u[0] + d[1] * p->axis_u[1];
    out[1] = d[0] * p->axis_w[0] + d[1] * p->axis_w[1];
}

/* An arc path: the phi in [-a, a] with cos(phi - psi) = x, as t. */
static void cross_angle(const path *p, double psi, double x, crossings *out)
{
    if (!(fabs(x) <= 1))
        return; /* no crossing, or a tangency lost to rounding (above) */
    double delta = acos(x);
    for (int sign = -1; sign <= 1; sign += 2) {
        /* Into (-pi, pi]: [-a, a] is shorter than a turn (a < pi), so each
         * angle has at most one place on it. */
        double phi = remainder(psi + sign * delta, 2 * WR_PI);
        if (fabs(phi) <= p->half_angle)
            add(out, (phi + p->half_angle) / (2 * p->half_angle));
    }
}

/* Where the path crosses the line {x : n . x = level} (n a unit vector). */
static void cross_line(const path *p, const double n[2], double level, crossings *out)
{
    if (!p->arc) {
        /* n_u u + n_w w_c = level; parallel lines (n_u = 0) never cross. */
        if (n[0] == 0)
            return;
        double u = (level - n[1] * p->w) / n[0];
        add(out, (u + p->half_chord) / (2 * p->half_chord));
        return;
    }
    /* n . c = rho (n_u sin phi + n_w cos phi) - n_w k = rho cos(phi - psi) - n_w k. */
    cross_angle(p, atan2(n[0], n[1]), (level + n[1] * p->k) / p->rho, out);
}

/* Where the path crosses the circle about q of radius `radius`. */
static void cross_circle(const path *p, const double q[2], double radius, crossings *out)
{
    if (!p->arc) {
        /* (u - q_u)^2 = radius^2 - (w_c - q_w)^2, the difference of squares
         * as a product so that it keeps its digits near a tangency. */
        double dw = p->w - q[1];
        double square = (radius - dw) * (radius + dw);
        if (!(square >= 0))
            return;
        double root = sqrt(square), h = p->half_chord;
        add(out, (q[0] - root + h) / (2 * h));
        add(out, (q[0] + root + h) / (2 * h));
        return;
    }
    /* c - q = rho (sin phi, cos phi) + d, d = centre - q, so
     * |c - q|^2 = rho^2 + |d|^2 + 2 rho |d| cos(phi - psi). */
    double d[2] = {-q[0], -p->k - q[1]};
    double distance = hypot(d[0], d[1]);
    /* Concentric: the distance from c to q does not change along the path. */
    if (distance <= p->tolerance)
        return;
    double x = ((radius - p->rho) * (radius + p->rho) - distance * distance) /
               (2 * p->rho * distance);
    cross_angle(p, atan2(d[0], d[1]), x, out);
}

/* The crossings of the path with the curves at distance r from obstacle s. */
static void obstacle_crossings(const path *p, const wr_segment *s, double r, crossings *out)
{
    double start[2];
    to_frame(p, s->start, start);
    /* Only the start's circle: each vertex starts one segment, and that
     * segment is near whenever the vertex is. */
    cross_circle(p, start, r, out);
    if (s->bulge == 0) {
        double middle[2];
        to_frame(p, s->midpoint, middle);
        /* The unit normal in the frame: the direction rotated by a quarter turn. */
        double along[2] = {s->direction[0] * p->axis_u[0] + s->direction[1] * p->axis_u[1],
                           s->direction[0] * p->axis_w[0] + s->direction[1] * p->axis_w[1]};
        double n[2] = {-along[1], along[0]};
        double level = n[0] * middle[0] + n[1] * middle[1];
        cross_line(p, n, level + r, out);
        cross_line(p, n, level - r, out);
    } else {
        double centre[2];
        to_frame(p, s->center, centre);
        cross_circle(p, centre, s->radius + r, out);
        /* Within R - r of the centre only when R > r: the circle exists. */
        if (s->radius > r)
            cross_circle(p, centre, s->radius - r, out);
    }
}

/* The distance from x to segment s, in s's chord frame (as wr_outline.c
 * does, so that a nearly straight arc of huge radius keeps its digits). */
static double segment_distance(const wr_segment *s, const double x[2])
{
    double q[2] = {x[0] - s->midpoint[0], x[1] - s->midpoint[1]};
    double u = q[0] * s->direction[0] + q[1] * s->direction[1];
    double w = q[0] * s->bulge_normal[0] + q[1] * s->bulge_normal[1];
    double h = s->half_chord;
    if (s->bulge == 0)
        return hypot(fmax(0.0, fabs(u) - h), w);
    /* The centre at (0, -k), k = R cos a.  Within the arc's angle the
     * nearest point is radial: | |x - centre| - R | = |u^2 + w^2 + 2 w k - h^2|
     * / (|x - centre| + R), since k^2 - R^2 = -h^2: no cancellation. */
    double k = h * s->half_angle_cos / s->half_angle_sin;
    if (fabs(atan2(u, w + k)) <= s->half_angle)
        return fabs(u * u + w * w + 2 * w * k - h * h) / (hypot(u, w + k) + s->radius);
    return fmin(hypot(x[0] - s->start[0], x[1] - s->start[1]),
                hypot(x[0] - s->end[0], x[1] - s->end[1]));
}

/* The finger at t overlaps the workpiece: some segment nearer to c than
 * r - tolerance (only the `near` ones can be).  That c might lie inside
 * the material with all of the boundary r away needs no test: the
 * segment from p to c (length r) leaves p into the free side, so to end in
 * the material it crosses the boundary at some q != p, and
 * |c - q| < r. */
static bool overlaps(const wr_outline *outline, size_t loop, size_t segment, double t, double r,
                     const wr_segment *const *near, size_t near_count)
{
    double tolerance = WR_OUTLINE_TOLERANCE * outline->size;
    double point[2], normal[2];
    wr_outline_boundary(outline, loop, segment, t, point, normal);
    double c[2] = {point[0] - r * normal[0], point[1] - r * normal[1]};
    for (size_t i = 0; i < near_count; i++)
        if (segment_distance(near[i], c) < r - tolerance)
            return true;
    return false;
}

/* Can any point of s be within r of the path?  c is at distance r from
 * the pushed segment's points, so within r of its box; s must come within
 * 2 r of that box (and a little more, for the tolerance). */
static bool near_box(const wr_segment *own, const wr_segment *s, double reach)
{
    for (int i = 0; i < 2; i++)
        if (s->box_min[i] > own->box_max[i] + reach || s->box_max[i] < own->box_min[i] - reach)
            return false;
    return true;
}

static int compare_doubles(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* Append spans[0 .. n) to the caller's array. */
static wr_status append(const wr_span *found, int n, wr_span **spans, int *count)
{
    if (n == 0)
        return WR_OK;
    if (*count > INT_MAX - n)
        return WR_NO_MEMORY;
    wr_span *grown = realloc(*spans, (size_t)(*count + n) * sizeof *grown);
    if (!grown)
        return WR_NO_MEMORY;
    memcpy(grown + *count, found, (size_t)n * sizeof *found);
    *spans = grown;
    *count += n;
    return WR_OK;
}

/* The path of the finger's centre along `own` (above). */
static path path_of(const wr_loop *loop, const wr_segment *own, double r, double tolerance)
{
    path p;
    memset(&p, 0, sizeof p);
    p.arc = own->bulge != 0;
    p.origin[0] = own->midpoint[0];
    p.origin[1] = own->midpoint[1];
    p.axis_u[0] = own->direction[0];
    p.axis_u[1] = own->direction[1];
    p.axis_w[0] = own->bulge_normal[0];
    p.axis_w[1] = own->bulge_normal[1];
    p.half_chord = own->half_chord;
    p.tolerance = tolerance;
    if (!p.arc) {
        /* A line's bulge normal is its left normal; nu = material_side times it. */
        p.w = -r * loop->material_side;
    } else {
        /* Travelling counter-clockwise (bulge > 0) the centre is on the
         * left, so the material is inside the circle iff it is on the
         * side the arc turns to. */
        bool inside = (own->bulge > 0) == (loop->material_side > 0);
        p.half_angle = own->half_angle;
        p.k = own->half_chord * own->half_angle_cos / own->half_angle_sin;
        p.rho = inside ? own->radius + r : own->radius - r;
    }
    return p;
}

wr_status wr_finger_blocked(const wr_outline *outline, size_t loop, size_t segment, double radius,
                            const wr_stop *stop, wr_span **spans, int *count)
{
    assert(outline && spans && count && *count >= 0);
    if (!isfinite(radius) || !(radius >= 0) || loop >= outline->loop_count ||
        segment >= outline->loops[loop].segment_count)
        return WR_INVALID;
    double tolerance = WR_OUTLINE_TOLERANCE * outline->size;
    /* A finger within the tolerance of a point is a point: it fits anywhere. */
    if (radius <= tolerance)
        return WR_OK;
    const wr_loop *l = &outline->loops[loop];
    const wr_segment *own = &l->segments[segment];
    path p = path_of(l, own, radius, tolerance);
    /* A concave arc tighter than the finger: the disc, touching it at p
     * from inside its circle, holds that whole circle, so every other point
     * of the arc is strictly inside the disc, with material beyond it. */
    if (p.arc && p.rho < -tolerance)
        return append(&(wr_span){0, 1}, 1, spans, count);
    /* rho within the tolerance of 0: the finger is the arc's own circle and
     * its centre does not move; the ends decide alone. */
    bool fixed = p.arc && fabs(p.rho) <= tolerance;

    size_t total = outline->vertex_count;
    const wr_segment **near = malloc(total * sizeof *near);
    crossings found = {malloc((CROSSINGS_PER_SEGMENT * total + 2) * sizeof(double)), 0,
                       CROSSINGS_PER_SEGMENT * total + 2};
    wr_span *blocked = NULL;
    wr_status status = WR_NO_MEMORY;
    if (!near || !found.t)
        goto done;
    size_t near_count = 0;
    add(&found, 0);
    add(&found, 1);
    status = WR_STOPPED;
    for (size_t i = 0; i < outline->loop_count; i++)
        for (size_t j = 0; j < outline->loops[i].segment_count; j++) {
            if (wr_stop_requested(stop))
                goto done;
            const wr_segment *s = &outline->loops[i].segments[j];
            if (!near_box(own, s, 2 * radius + 2 * tolerance))
                continue;
            near[near_count++] = s;
            /* Its own segment is at distance exactly r from c, never
             * nearer: it adds no crossing. */
            if (s != own && !fixed)
                obstacle_crossings(&p, s, radius, &found);
        }
    qsort(found.t, found.count, sizeof(double), compare_doubles);

    /* One test inside each piece between consecutive crossings; adjacent
     * blocked pieces make one closed span. */
    blocked = malloc(found.count * sizeof *blocked);
    status = WR_NO_MEMORY;
    if (!blocked)
        goto done;
    int n = 0;
    bool previous = false;
    status = WR_STOPPED;
    for (size_t i = 0; i + 1 < found.count; i++) {
        double lo = found.t[i], hi = found.t[i + 1];
        if (!(hi > lo))
            continue;
        if (wr_stop_requested(stop))
            goto done;
        bool now = overlaps(outline, loop, segment, lo + (hi - lo) / 2, radius, near, near_count);
        if (now && previous) {
            blocked[n - 1].hi = hi;
        } else if (now) {
            blocked[n++] = (wr_span){lo, hi};
        }
        previous = now;
    }
    assert(found.t[0] == 0 && found.t[found.count - 1] == 1);
    status = append(blocked, n, spans, count);
done:
    free(near);
    free(found.t);
    free(blocked);
    return status;
}
