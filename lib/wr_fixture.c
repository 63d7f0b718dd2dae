/* wr_fixture.c -- validation of a fixture spec and the derived quantities
 * (centroid, uniform inertia, inward normals, scaled contact wrenches). */
#include "wr_fixture.h"
#include "wr_support.h"
#include "wr_internal.h"
#include "wr_outline.h"

#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Geometric tolerances are relative to the body's size (docs/PROTOCOL.md:
 * "within 1e-9 of the body's size"). */
#define BOUNDARY_TOLERANCE 1e-9
#define DEGENERATE_TOLERANCE 1e-12
/* A given normal whose length is within this of 1 is used as given.  A
 * vector divided by its hypot() has a length within 3 ulp of 1 (hypot and
 * each division round once), so every normal this file computes, and every
 * normalised one, passes: normalising is then idempotent, bit for bit. */
#define UNIT_LENGTH_TOLERANCE (8 * DBL_EPSILON)
/* A given normal whose angle to the boundary is below this (its cosine with
 * the inward normal, in radians near tangency) is tangent to it. */
#define TANGENT_TOLERANCE 1e-9

/* Report the first non-finite component of a 2-vector as "path[i]". */
static bool check_finite2(const double v[2], const char *path, wr_error *error)
{
    for (int i = 0; i < 2; i++) {
        if (!isfinite(v[i])) {
            char field[128];
            snprintf(field, sizeof field, "%s[%d]", path, i);
            wr_error_set(error, field, "must be a finite number");
            return false;
        }
    }
    return true;
}

/* One coefficient at `field`: a point mu, or an interval [lo, hi] whose
 * bounds are named field[0] and field[1]. */
static bool check_coefficient(bool interval, double lo, double hi, const char *field,
                              wr_error *error)
{
    char bound[160];
    double values[2] = {lo, hi};
    for (int i = interval ? 0 : 1; i < 2; i++) {
        if (interval)
            snprintf(bound, sizeof bound, "%s[%d]", field, i);
        else
            snprintf(bound, sizeof bound, "%s", field);
        if (!isfinite(values[i])) {
            wr_error_set(error, bound, "must be a finite number");
            return false;
        }
        if (values[i] < 0) {
            wr_error_set(error, bound, "friction coefficient %g is negative", values[i]);
            return false;
        }
        if (values[i] > WR_MAX_FRICTION) {
            wr_error_set(error, bound,
                         "friction coefficient %g is above %g: no contact has it, and the cones "
                         "would lose precision",
                         values[i], WR_MAX_FRICTION);
            return false;
        }
    }
    if (interval && lo > hi) {
        wr_error_set(error, field,
                     "the interval [%g, %g] is empty: its lower bound is above its upper bound",
                     lo, hi);
        return false;
    }
    return true;
}

static bool check_friction(const wr_friction_spec *friction, const char *path,
                           wr_error *error)
{
    char field[128];
    if (!friction->given)
        return true;
    snprintf(field, sizeof field, "%s.static", path);
    double static_lo = friction->static_interval ? friction->static_min : friction->static_mu;
    double static_hi = friction->static_mu;
    if (!check_coefficient(friction->static_interval, static_lo, static_hi, field, error))
        return false;
    if (!friction->kinetic_given)
        return true;
    snprintf(field, sizeof field, "%s.kinetic", path);
    bool interval = friction->kinetic_interval;
    double lo = interval ? friction->kinetic_min : friction->kinetic_mu;
    double hi = friction->kinetic_mu;
    if (!check_coefficient(interval, lo, hi, field, error))
        return false;
    /* Every value of either interval must be attained by a pair with
     * mu_k <= mu_s: kinetic's bounds not above static's. */
    if (!interval && !friction->static_interval) {
        if (hi > static_hi) {
            wr_error_set(error, field, "kinetic friction %g exceeds static friction %g", hi,
                         static_hi);
            return false;
        }
        return true;
    }
    char bound[160];
    if (hi > static_hi) {
        snprintf(bound, sizeof bound, interval ? "%s[1]" : "%s", field);
        wr_error_set(error, bound,
                     "kinetic friction's upper bound %g exceeds static friction's upper bound %g: "
                     "kinetic bounds must not be above the static ones",
                     hi, static_hi);
        return false;
    }
    if (lo > static_lo) {
        snprintf(bound, sizeof bound, interval ? "%s[0]" : "%s", field);
        wr_error_set(error, bound,
                     "kinetic friction's lower bound %g exceeds static friction's lower bound %g: "
                     "kinetic bounds must not be above the static ones (a static coefficient of "
                     "%g would have no kinetic one below it)",
                     lo, static_lo, static_lo);
        return false;
    }
    return true;
}

/* ---- polygon geometry --------------------------------------------------- */

static double cross2(const double a[2], const double b[2]) { return a[0] * b[1] - a[1] * b[0]; }

/* Orientation of c relative to the directed line a->b: >0 left, <0 right. */
static double orient(const double a[2], const double b[2], const double c[2])
{
    return (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
}

static bool on_segment(const double a[2], const double b[2], const double c[2])
{
    return fmin(a[0], b[0]) <= c[0] && c[0] <= fmax(a[0], b[0]) &&
           fmin(a[1], b[1]) <= c[1] && c[1] <= fmax(a[1], b[1]);
}

/* Closed segments ab and cd share a point?  If so, *point receives one:
 * where they cross, or an end of one lying on the other. */
static bool segments_meet(const double a[2], const double b[2], const double c[2],
                          const double d[2], double point[2])
{
    if (wr_segments_cross(a, b, c, d, point))
        return true;
    double o1 = orient(a, b, c), o2 = orient(a, b, d);
    double o3 = orient(c, d, a), o4 = orient(c, d, b);
    const double *on = o1 == 0 && on_segment(a, b, c)   ? c
                       : o2 == 0 && on_segment(a, b, d) ? d
                       : o3 == 0 && on_segment(c, d, a) ? a
                       : o4 == 0 && on_segment(c, d, b) ? b
                                                        : NULL;
    if (on) {
        point[0] = on[0];
        point[1] = on[1];
    }
    return on != NULL;
}

/* Distance from p to segment ab; *fraction receives the parameter of the
 * nearest point (0 at a, 1 at b). */
static double segment_distance(const double a[2], const double b[2], const double p[2],
                               double *fraction)
{
    double d[2] = {b[0] - a[0], b[1] - a[1]};
    double w[2] = {p[0] - a[0], p[1] - a[1]};
    double length2 = d[0] * d[0] + d[1] * d[1];
    double t = length2 > 0 ? (w[0] * d[0] + w[1] * d[1]) / length2 : 0;
    t = fmax(0.0, fmin(1.0, t));
    if (fraction)
        *fraction = t;
    return hypot(p[0] - (a[0] + t * d[0]), p[1] - (a[1] + t * d[1]));
}

static void polygon_moments(const double (*v)[2], size_t n, double *area, double centroid[2],
                            double *polar_moment);

/* Twice the signed area, summed about vertex 0 (as polygon_moments does):
 * the products are of the polygon's size, not of its distance from the
 * origin, so they neither overflow nor cancel as much. */
static double polygon_area2(const double (*v)[2], size_t n)
{
    double area2 = 0;
    for (size_t i = 1; i + 1 < n; i++)
        area2 += orient(v[0], v[i], v[i + 1]);
    return area2;
}

/* Neighbours i, i + 1 (mod n) collinear and turning back at their shared
 * vertex: they overlap from it on. */
static bool folds_back(const double (*v)[2], size_t n, size_t i)
{
    const double *a = v[i], *b = v[(i + 1) % n], *c = v[(i + 2) % n];
    double d1[2] = {b[0] - a[0], b[1] - a[1]}, d2[2] = {c[0] - b[0], c[1] - b[1]};
    return cross2(d1, d2) == 0 && d1[0] * d2[0] + d1[1] * d2[1] < 0;
}

/* Edges i < j, not neighbours, share a point?  Edge i runs from vertex i
 * to vertex i + 1. */
static bool edges_meet(const double (*v)[2], size_t n, size_t i, size_t j, double point[2])
{
    if (j == i + 1 || (i == 0 && j == n - 1))
        return false; /* neighbours, sharing a vertex: folds_back's */
    return segments_meet(v[i], v[(i + 1) % n], v[j], v[(j + 1) % n], point);
}

/* The pairs of edges the sweep visits (wr_box_pairs), keeping the first
 * that meets in index order; a pair at or after it is not tested. */
typedef struct edge_meeting {
    const double (*v)[2];
    size_t n;
    bool found;
    size_t first, second;
    double point[2];
} edge_meeting;

static void visit_edges(void *context, size_t i, size_t j)
{
    edge_meeting *m = context;
    if (m->found && (i > m->first || (i == m->first && j >= m->second)))
        return;
    double point[2];
    if (edges_meet(m->v, m->n, i, j, point)) {
        m->found = true;
        m->first = i;
        m->second = j;
        m->point[0] = point[0];
        m->point[1] = point[1];
    }
}

int wr_polygon_first_meeting(const double (*v)[2], size_t n, bool exhaustively, size_t *first,
                             size_t *second, double point[2])
{
    size_t fold = n;
    for (size_t i = 0; i < n && fold == n; i++)
        if (folds_back(v, n, i))
            fold = i;
    edge_meeting m = {v, n, false, 0, 0, {0, 0}};
    if (exhaustively) {
        for (size_t i = 0; i < n && !m.found && i < fold; i++)
            for (size_t j = i + 2; j < n && !m.found; j++)
                visit_edges(&m, i, j);
    } else {
        wr_box *boxes = calloc(n, sizeof *boxes);
        if (!boxes)
            return -1;
        for (size_t i = 0; i < n; i++) {
            const double *a = v[i], *b = v[(i + 1) % n];
            boxes[i] = (wr_box){{fmin(a[0], b[0]), fmin(a[1], b[1])},
                                {fmax(a[0], b[0]), fmax(a[1], b[1])}};
        }
        /* Closed boxes, no margin: edges sharing a point share it exactly
         * in their boxes, the comparisons exact. */
        bool ok = wr_box_pairs(boxes, n, 0, visit_edges, &m);
        free(boxes);
        if (!ok)
            return -1;
    }
    /* In index order, edge i's fold with i + 1 comes before its meetings
     * with edges i + 2 on. */
    if (fold < n && (!m.found || fold <= m.first)) {
        *first = fold;
        *second = (fold + 1) % n;
        point[0] = v[*second][0];
        point[1] = v[*second][1];
        return 1;
    }
    if (!m.found)
        return 0;
    *first = m.first;
    *second = m.second;
    point[0] = m.point[0];
    point[1] = m.point[1];
    return 1;
}

/* *no_memory set (and false returned) when the simplicity test ran out. */
static bool check_polygon(const wr_fixture_spec *spec, double size, wr_error *error,
                          bool *no_memory)
{
    size_t n = spec->vertex_count;
    const double (*v)[2] = spec->vertices;
    char field[96];
    if (n < 3 || !v) {
        wr_error_set(error, "body.shape.vertices",
                     "a polygon needs at least 3 vertices, %zu given", n);
        return false;
    }
    if (n > WR_MAX_VERTICES) {
        wr_error_set(error, "body.shape.vertices",
                     "at most %d vertices are accepted, %zu given", WR_MAX_VERTICES, n);
        return false;
    }
    for (size_t i = 0; i < n; i++) {
        snprintf(field, sizeof field, "body.shape.vertices[%zu]", i);
        if (!check_finite2(v[i], field, error))
            return false;
    }
    if (!isfinite(size)) {
        wr_error_set(error, "body.shape.vertices",
                     "the polygon is too large for double precision: its extent overflows");
        return false;
    }
    for (size_t i = 0; i < n; i++) {
        const double *a = v[i], *b = v[(i + 1) % n];
        if (hypot(b[0] - a[0], b[1] - a[1]) <= DEGENERATE_TOLERANCE * size) {
            snprintf(field, sizeof field, "body.shape.vertices[%zu]", (i + 1) % n);
            wr_error_set(error, field, "repeats vertex %zu: the edge between them has no length", i);
            return false;
        }
    }
    /* Simple: no two edges meet except neighbours at their shared vertex,
     * and neighbours do not fold back onto each other.  Before the area:
     * a bow tie's two lobes cancel, and "encloses no area" would hide
     * that its edges cross. */
    size_t first, second;
    double point[2];
    int meeting = wr_polygon_first_meeting(v, n, false, &first, &second, point);
    if (meeting < 0) {
        wr_error_set(error, "", "out of memory");
        *no_memory = true;
        return false;
    }
    if (meeting > 0) {
        if (second == (first + 1) % n) {
            snprintf(field, sizeof field, "body.shape.vertices[%zu]", second);
            wr_error_set(error, field,
                         "the polygon is not simple: the edges at this vertex fold back onto "
                         "each other");
        } else {
            wr_error_set(error, "body.shape.vertices",
                         "the polygon intersects itself: edge %zu (vertices %zu to %zu) and edge "
                         "%zu (vertices %zu to %zu) meet at (%g, %g)",
                         first, first, (first + 1) % n, second, second, (second + 1) % n,
                         point[0], point[1]);
        }
        return false;
    }
    double area2 = polygon_area2(v, n);
    if (!isfinite(area2)) {
        wr_error_set(error, "body.shape.vertices",
                     "the polygon is too large for double precision: its area overflows "
                     "(it spans %g)",
                     size);
        return false;
    }
    /* Compared as area / size with size: size * size may overflow. */
    if (fabs(area2) / 2 / size <= DEGENERATE_TOLERANCE * size) {
        wr_error_set(error, "body.shape.vertices", "the polygon encloses no area");
        return false;
    }
    /* The inertia needs the second moment, of order size^4. */
    double area, centroid[2], polar_moment;
    polygon_moments(v, n, &area, centroid, &polar_moment);
    if (!isfinite(area) || !isfinite(centroid[0]) || !isfinite(centroid[1]) ||
        !isfinite(polar_moment)) {
        wr_error_set(error, "body.shape.vertices",
                     "the polygon is too large for double precision: its second moment of area "
                     "overflows (it spans %g)",
                     size);
        return false;
    }
    return true;
}

/* Area, centroid and polar second moment about the centroid, for a uniform
 * polygon of unit density.  Computed about vertex 0 for accuracy. */
static void polygon_moments(const double (*v)[2], size_t n, double *area, double centroid[2],
                            double *polar_moment)
{
    double a = 0, cx = 0, cy = 0, j = 0;
    const double *o = v[0];
    for (size_t i = 0; i < n; i++) {
        double x0 = v[i][0] - o[0], y0 = v[i][1] - o[1];
        double x1 = v[(i + 1) % n][0] - o[0], y1 = v[(i + 1) % n][1] - o[1];
        double c = x0 * y1 - x1 * y0;
        a += c;
        cx += (x0 + x1) * c;
        cy += (y0 + y1) * c;
        j += c * (x0 * x0 + x0 * x1 + x1 * x1 + y0 * y0 + y0 * y1 + y1 * y1);
    }
    a /= 2;
    cx /= 6 * a;
    cy /= 6 * a;
    j /= 12;
    /* Signed a and j carry the orientation; their ratio does not. */
    *area = fabs(a);
    centroid[0] = cx + o[0];
    centroid[1] = cy + o[1];
    *polar_moment = fabs(j) - fabs(a) * (cx * cx + cy * cy);
}

/* ---- boundary queries --------------------------------------------------- */

/* Distance from p to the shape's boundary.  For a polygon, *edge and *fraction
 * receive the nearest edge and the parameter along it. */
static double boundary_distance(const wr_fixture *f, const double p[2], size_t *edge,
                                double *fraction)
{
    if (f->shape == WR_SHAPE_CIRCLE)
        return fabs(hypot(p[0] - f->center[0], p[1] - f->center[1]) - f->radius);
    double best = INFINITY;
    for (size_t i = 0; i < f->vertex_count; i++) {
        double t;
        double d = segment_distance(f->vertices[i], f->vertices[(i + 1) % f->vertex_count], p, &t);
        if (d < best) {
            best = d;
            *edge = i;
            *fraction = t;
        }
    }
    return best;
}

/* Inward unit normal of polygon edge i. */
static void edge_inward_normal(const wr_fixture *f, size_t i, double normal[2])
{
    const double *a = f->vertices[i], *b = f->vertices[(i + 1) % f->vertex_count];
    double d[2] = {b[0] - a[0], b[1] - a[1]}, u[2] = {0, 0};
    wr_unit2(d, u); /* none (zero) for an edge of no direction */
    /* Counter-clockwise: the interior lies to the left of each edge. */
    normal[0] = -u[1] * f->orientation;
    normal[1] = u[0] * f->orientation;
}

/* Is p within tolerance of a polygon vertex?  Returns its index or -1. */
static long near_vertex(const wr_fixture *f, const double p[2])
{
    for (size_t i = 0; i < f->vertex_count; i++)
        if (hypot(p[0] - f->vertices[i][0], p[1] - f->vertices[i][1]) <=
            BOUNDARY_TOLERANCE * f->size)
            return (long)i;
    return -1;
}

/* Fill in one fixel's normal and friction, checking them against the shape. */
static bool build_fixel(wr_fixture *f, const wr_fixture_spec *spec, size_t index,
                        wr_error *error)
{
    const wr_fixel_spec *in = &spec->fixels[index];
    wr_fixel *out = &f->fixels[index];
    char field[96];
    snprintf(field, sizeof field, "fixels[%zu].at", index);
    out->at[0] = in->at[0] + 0.0;
    out->at[1] = in->at[1] + 0.0;

    /* The shape's inward normal at `at`, when defined; at a corner (a
     * polygon's vertex, an outline's vertex where the boundary turns) the
     * inward normals of the two segments that meet there instead. */
    double inward[2] = {0, 0};
    bool inward_known = false;
    bool at_corner = false;
    double corner[2][2];
    char corner_name[64] = "";
    if (f->shape == WR_SHAPE_OUTLINE) {
        wr_outline_place place;
        if (!wr_outline_locate(f->outline, in->at, BOUNDARY_TOLERANCE * f->size, &place)) {
            wr_error_set(error, field,
                         "(%g, %g) is not on the workpiece boundary: %.3g away from it",
                         in->at[0], in->at[1], wr_outline_distance(f->outline, in->at));
            return false;
        }
        const wr_loop *loop = &f->outline->loops[place.loop];
        double unused[2];
        if (place.at_vertex && !place.smooth) {
            at_corner = true;
            wr_outline_boundary(f->outline, place.loop, place.vertex, 0, unused, corner[0]);
            wr_outline_boundary(f->outline, place.loop,
                                (place.vertex + loop->segment_count - 1) % loop->segment_count, 1,
                                unused, corner[1]);
            snprintf(corner_name, sizeof corner_name, "vertex %zu of loop %zu of the outline",
                     place.vertex, place.loop);
        } else {
            wr_outline_boundary(f->outline, place.loop, place.segment, place.t, unused, inward);
            inward_known = true;
        }
    } else if (f->shape != WR_SHAPE_NONE) {
        size_t edge = 0;
        double fraction = 0;
        double distance = boundary_distance(f, in->at, &edge, &fraction);
        if (distance > BOUNDARY_TOLERANCE * f->size) {
            wr_error_set(error, field,
                         "(%g, %g) is not on the workpiece boundary: %.3g away from it",
                         in->at[0], in->at[1], distance);
            return false;
        }
        if (f->shape == WR_SHAPE_CIRCLE) {
            double d[2] = {f->center[0] - in->at[0], f->center[1] - in->at[1]};
            inward[0] = inward[1] = 0; /* none at the centre of a circle of radius 0 */
            wr_unit2(d, inward);
            inward_known = true;
        } else {
            long vertex = near_vertex(f, in->at);
            if (vertex < 0) {
                edge_inward_normal(f, edge, inward);
                inward_known = true;
            } else {
                size_t n = f->vertex_count;
                at_corner = true;
                edge_inward_normal(f, (size_t)vertex, corner[0]);
                edge_inward_normal(f, ((size_t)vertex + n - 1) % n, corner[1]);
                snprintf(corner_name, sizeof corner_name, "vertex %ld of the polygon", vertex);
            }
        }
    }

    snprintf(field, sizeof field, "fixels[%zu].normal", index);
    if (in->normal_given) {
        if (!check_finite2(in->normal, field, error))
            return false;
        double length = hypot(in->normal[0], in->normal[1]);
        if (fabs(length - 1) <= UNIT_LENGTH_TOLERANCE) {
            /* Already unit: taken as it is, so that a normal written out by
             * the protocol layer (canonical text) reads back to the same
             * bits; dividing by a length an ulp off 1 would move them. */
            out->normal[0] = in->normal[0] + 0.0;
            out->normal[1] = in->normal[1] + 0.0;
        } else if (!wr_unit2(in->normal, out->normal)) {
            wr_error_set(error, field, "must not be the zero vector");
            return false;
        } else {
            out->normal[0] += 0.0; /* no negative zero */
            out->normal[1] += 0.0;
        }
        /* Scaled first (wr_unit2), any finite direction comes out unit:
         * what does not cannot be stored as a normal. */
        if (!(fabs(hypot(out->normal[0], out->normal[1]) - 1) <= UNIT_LENGTH_TOLERANCE)) {
            wr_error_set(error, field, "(%g, %g) cannot be made a unit vector", in->normal[0],
                         in->normal[1]);
            return false;
        }
        /* The cosine of the angle to the inward normal: a normal within
         * TANGENT_TOLERANCE of perpendicular to it lies along the boundary
         * and pushes nothing away (it is said so, not "points out"). */
        bool points_in = true, tangent = false;
        if (inward_known) {
            double along = out->normal[0] * inward[0] + out->normal[1] * inward[1];
            tangent = fabs(along) <= TANGENT_TOLERANCE;
            points_in = along > TANGENT_TOLERANCE;
        } else if (at_corner) {
            /* At a corner, the normal must point into the body across at
             * least one of the two segments that meet there. */
            double along_a = out->normal[0] * corner[0][0] + out->normal[1] * corner[0][1];
            double along_b = out->normal[0] * corner[1][0] + out->normal[1] * corner[1][1];
            points_in = along_a > TANGENT_TOLERANCE || along_b > TANGENT_TOLERANCE;
            tangent = fabs(along_a) <= TANGENT_TOLERANCE || fabs(along_b) <= TANGENT_TOLERANCE;
        }
        if (!points_in && tangent) {
            wr_error_set(error, field,
                         "(%g, %g) is tangent to the boundary at (%g, %g), not into the "
                         "workpiece; a fixel's normal points from the fixel into the workpiece",
                         in->normal[0], in->normal[1], in->at[0], in->at[1]);
            return false;
        }
        if (!points_in) {
            wr_error_set(error, field,
                         "(%g, %g) points out of the workpiece; a fixel's normal points from the fixel into the workpiece",
                         in->normal[0], in->normal[1]);
            return false;
        }
    } else if (inward_known) {
        out->normal[0] = inward[0] + 0.0;
        out->normal[1] = inward[1] + 0.0;
    } else if (at_corner) {
        wr_error_set(error, field,
                     "required: (%g, %g) is %s, where the inward normal is not defined",
                     in->at[0], in->at[1], corner_name);
        return false;
    } else {
        wr_error_set(error, field, "required when the body has no shape");
        return false;
    }
    out->tangent[0] = -out->normal[1];
    out->tangent[1] = out->normal[0];

    snprintf(field, sizeof field, "fixels[%zu].friction", index);
    const wr_friction_spec *friction = in->friction.given ? &in->friction : &spec->friction;
    if (!friction->given) {
        wr_error_set(error, field,
                     "required: no friction is given for this fixel nor for the fixture");
        return false;
    }
    if (in->friction.given && !check_friction(&in->friction, field, error))
        return false;
    /* An interval [a, a] is the point a: one fixture, one explicit form. */
    out->mu_static = friction->static_mu + 0.0;
    out->mu_static_min = (friction->static_interval ? friction->static_min : friction->static_mu) + 0.0;
    if (friction->kinetic_given) {
        out->mu_kinetic = friction->kinetic_mu + 0.0;
        out->mu_kinetic_min =
            (friction->kinetic_interval ? friction->kinetic_min : friction->kinetic_mu) + 0.0;
    } else { /* kinetic left out: the whole static interval */
        out->mu_kinetic = out->mu_static;
        out->mu_kinetic_min = out->mu_static_min;
    }
    return true;
}

/* Scaled contact wrenches: (n, (r x n) / rho), (t, (r x t) / rho). */
static void fixel_wrenches(const wr_fixture *f, wr_fixel *fixel)
{
    double r[2] = {fixel->at[0] - f->com[0], fixel->at[1] - f->com[1]};
    fixel->normal_wrench[0] = fixel->normal[0];
    fixel->normal_wrench[1] = fixel->normal[1];
    fixel->normal_wrench[2] = cross2(r, fixel->normal) / f->gyration_radius;
    fixel->tangent_wrench[0] = fixel->tangent[0];
    fixel->tangent_wrench[1] = fixel->tangent[1];
    fixel->tangent_wrench[2] = cross2(r, fixel->tangent) / f->gyration_radius;
}

/* The centre of mass near the part and a radius of gyration of its order
 * (WR_GYRATION_RANGE): what double precision needs, and what a rigid body
 * has.  A fixel's torque column is (r x n) / rho, so a lever arm r far
 * beyond rho swamps the forces, and one far below it flattens the cone.
 * Without a shape nothing says where the part is, so only the lever arms
 * (and the fixels' spread) are compared with rho. */
static bool check_scales(const wr_fixture *f, const wr_fixture_spec *spec, wr_error *error)
{
    double scale = f->size;
    if (spec->shape == WR_SHAPE_NONE) {
        scale = 0;
        for (size_t i = 0; i < spec->fixel_count; i++)
            scale = fmax(scale, hypot(spec->fixels[i].at[0] - f->com[0],
                                      spec->fixels[i].at[1] - f->com[1]));
        if (spec->fixel_count > 1)
            scale = fmax(scale, f->size);
        if (scale == 0)
            return true; /* every fixel at the centre of mass: no torque at all */
    } else {
        double lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY};
        for (int k = 0; k < 2; k++) {
            if (spec->shape == WR_SHAPE_CIRCLE) {
                lo[k] = f->center[k] - f->radius;
                hi[k] = f->center[k] + f->radius;
            }
            if (f->outline) { /* a polygon's: its vertices' box */
                lo[k] = f->outline->box_min[k];
                hi[k] = f->outline->box_max[k];
            }
        }
        double dx = fmax(0, fmax(lo[0] - f->com[0], f->com[0] - hi[0]));
        double dy = fmax(0, fmax(lo[1] - f->com[1], f->com[1] - hi[1]));
        if (hypot(dx, dy) > f->size) {
            wr_error_set(error, "body.com",
                         "(%g, %g) lies %.3g away from the shape, whose size is %.3g: a centre "
                         "of mass lies within the part",
                         f->com[0], f->com[1], hypot(dx, dy), f->size);
            return false;
        }
    }
    if (f->gyration_radius > WR_GYRATION_RANGE * scale ||
        f->gyration_radius < scale / WR_GYRATION_RANGE) {
        wr_error_set(error, "body.inertia",
                     "gives a radius of gyration sqrt(I/m) = %.3g for a part of size %.3g; "
                     "it must be within a factor %g of the size",
                     f->gyration_radius, scale, WR_GYRATION_RANGE);
        return false;
    }
    return true;
}

static double shape_size(const wr_fixture_spec *spec)
{
    if (spec->shape == WR_SHAPE_CIRCLE)
        return 2 * spec->radius;
    if (spec->shape == WR_SHAPE_POLYGON) {
        double lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY};
        for (size_t i = 0; i < spec->vertex_count; i++)
            for (int k = 0; k < 2; k++) {
                lo[k] = fmin(lo[k], spec->vertices[i][k]);
                hi[k] = fmax(hi[k], spec->vertices[i][k]);
            }
        return hypot(hi[0] - lo[0], hi[1] - lo[1]);
    }
    double size = 0;
    for (size_t i = 0; i < spec->fixel_count; i++)
        for (size_t j = 0; j < i; j++)
            size = fmax(size, hypot(spec->fixels[i].at[0] - spec->fixels[j].at[0],
                                    spec->fixels[i].at[1] - spec->fixels[j].at[1]));
    return size > 0 ? size : 1;
}

static bool check_body(const wr_fixture_spec *spec, wr_error *error, bool *no_memory)
{
    if (!isfinite(spec->mass)) {
        wr_error_set(error, "body.mass", "must be a finite number");
        return false;
    }
    if (!(spec->mass > 0)) {
        wr_error_set(error, "body.mass", "must be positive, got %g", spec->mass);
        return false;
    }
    if (!isnormal(spec->mass)) { /* subnormal: accelerations and forces overflow */
        wr_error_set(error, "body.mass", "%g is too small to compute with", spec->mass);
        return false;
    }
    if (spec->inertia_given) {
        if (!isfinite(spec->inertia)) {
            wr_error_set(error, "body.inertia", "must be a finite number");
            return false;
        }
        if (!(spec->inertia > 0)) {
            wr_error_set(error, "body.inertia", "must be positive, got %g", spec->inertia);
            return false;
        }
        if (!isnormal(spec->inertia)) {
            wr_error_set(error, "body.inertia", "%g is too small to compute with", spec->inertia);
            return false;
        }
    }
    if (spec->com_given && !check_finite2(spec->com, "body.com", error))
        return false;
    if (spec->shape == WR_SHAPE_CIRCLE) {
        if (!check_finite2(spec->center, "body.shape.center", error))
            return false;
        if (!isfinite(spec->radius)) {
            wr_error_set(error, "body.shape.radius", "must be a finite number");
            return false;
        }
        if (!(spec->radius > 0) || !isnormal(spec->radius)) {
            wr_error_set(error, "body.shape.radius", "must be positive, got %g", spec->radius);
            return false;
        }
    } else if (spec->shape == WR_SHAPE_POLYGON) {
        if (!check_polygon(spec, shape_size(spec), error, no_memory))
            return false;
    } else if (spec->shape == WR_SHAPE_NONE) {
        if (!spec->com_given) {
            wr_error_set(error, "body.com", "required when the body has no shape");
            return false;
        }
        if (!spec->inertia_given) {
            wr_error_set(error, "body.inertia", "required when the body has no shape");
            return false;
        }
    }
    if (spec->units.given &&
        !(isfinite(spec->units.length_m) && spec->units.length_m > 0 &&
          isnormal(spec->units.length_m))) {
        wr_error_set(error, "units.length", "must be a positive number of metres, got %g",
                     spec->units.length_m);
        return false;
    }
    if (spec->units.given &&
        !(isfinite(spec->units.force_n) && spec->units.force_n > 0 && isnormal(spec->units.force_n))) {
        wr_error_set(error, "units.force", "must be a positive number of newtons, got %g",
                     spec->units.force_n);
        return false;
    }
    return check_friction(&spec->friction, "friction", error);
}

/* The fixels of `spec` checked and placed on the body `f` (its shape and
 * mass properties final), with the checks that need them all. */
static bool place_fixels(wr_fixture *f, const wr_fixture_spec *spec, wr_error *error);

/* The fixel count and the points' finiteness: what must hold before
 * anything is derived from the fixels. */
static bool check_fixel_list(const wr_fixture_spec *spec, wr_error *error)
{
    if (spec->fixel_count == 0 || !spec->fixels) {
        wr_error_set(error, "fixels", "at least one fixel is required");
        return false;
    }
    if (spec->fixel_count > WR_MAX_FIXELS) {
        wr_error_set(error, "fixels",
                     "%zu fixels given, at most %d are supported: G_goal has k*2^(k-1) cones, "
                     "1024 at k = 8 and doubling with every fixel",
                     spec->fixel_count, WR_MAX_FIXELS);
        return false;
    }
    for (size_t i = 0; i < spec->fixel_count; i++) {
        char field[96];
        snprintf(field, sizeof field, "fixels[%zu].at", i);
        if (!check_finite2(spec->fixels[i].at, field, error))
            return false;
    }
    return true;
}

/* wr_fixture_new but for the status: NULL with *no_memory set when out of
 * memory, NULL alone when invalid.  `body_only`: the body alone, no fixels
 * (wr_fixture_body_new). */
static wr_fixture *validate(const wr_fixture_spec *spec, bool body_only, wr_error *error,
                            bool *no_memory)
{
    if (!check_body(spec, error, no_memory))
        return NULL;
    /* Before anything is derived from them (a shapeless body's size). */
    if (!body_only && !check_fixel_list(spec, error))
        return NULL;
    if (body_only && spec->shape == WR_SHAPE_NONE) {
        wr_error_set(error, "body.shape", "required: fixels are placed on the shape's boundary");
        return NULL;
    }

    wr_fixture *f = calloc(1, sizeof *f);
    if (!f) {
        wr_error_set(error, "", "out of memory");
        *no_memory = true;
        return NULL;
    }
    f->shape = spec->shape;
    f->mass = spec->mass;
    f->units = spec->units.given ? spec->units : (wr_units){false, 1.0, 1.0};
    double area = 0, centroid[2] = {0, 0}, polar_moment = 0;
    if (spec->shape == WR_SHAPE_OUTLINE) {
        wr_error outline_error;
        wr_status status = wr_outline_new(spec->loops, spec->loop_count, &f->outline, &outline_error);
        if (status != WR_OK) {
            /* Its fields are the shape's: "loops[1][2]" is
             * "body.shape.loops[1][2]" of the fixture.  (Loop fields are
             * short: "loops[4095][4095][2]" at most.) */
            *no_memory = status == WR_NO_MEMORY;
            char field[96];
            snprintf(field, sizeof field, "body.shape%s%.80s", outline_error.field[0] ? "." : "",
                     outline_error.field);
            wr_error_set(error, *no_memory ? "" : field, "%s", outline_error.reason);
            free(f);
            return NULL;
        }
        f->size = f->outline->size;
        area = f->outline->area;
        centroid[0] = f->outline->centroid[0];
        centroid[1] = f->outline->centroid[1];
        polar_moment = f->outline->polar_moment;
    } else {
        f->size = shape_size(spec);
    }
    if (spec->shape == WR_SHAPE_CIRCLE) {
        f->center[0] = spec->center[0] + 0.0;
        f->center[1] = spec->center[1] + 0.0;
        f->radius = spec->radius;
        centroid[0] = f->center[0];
        centroid[1] = f->center[1];
        /* Uniform disc: I = m r^2 / 2 about its centre. */
        area = WR_PI * f->radius * f->radius;
        polar_moment = area * f->radius * f->radius / 2;
    } else if (spec->shape == WR_SHAPE_POLYGON) {
        f->vertex_count = spec->vertex_count;
        f->vertices = malloc(spec->vertex_count * sizeof *f->vertices);
        if (!f->vertices) {
            free(f);
            wr_error_set(error, "", "out of memory");
            *no_memory = true;
            return NULL;
        }
        for (size_t i = 0; i < spec->vertex_count; i++)
            for (int k = 0; k < 2; k++)
                f->vertices[i][k] = spec->vertices[i][k] + 0.0;
        f->orientation = polygon_area2(spec->vertices, spec->vertex_count) > 0 ? 1 : -1;
        polygon_moments(spec->vertices, spec->vertex_count, &area, centroid, &polar_moment);
        if (wr_outline_polygon((const double (*)[2])f->vertices, f->vertex_count, &f->outline) !=
            WR_OK) {
            wr_fixture_free(f);
            wr_error_set(error, "", "out of memory");
            *no_memory = true;
            return NULL;
        }
    }
    f->area = area;
    if (spec->com_given) {
        f->com[0] = spec->com[0] + 0.0;
        f->com[1] = spec->com[1] + 0.0;
    } else {
        f->com[0] = centroid[0] + 0.0;
        f->com[1] = centroid[1] + 0.0;
    }
    if (spec->inertia_given) {
        f->inertia = spec->inertia;
    } else {
        /* Uniform density about the centroid, moved to com by parallel axes. */
        double offset2 = (f->com[0] - centroid[0]) * (f->com[0] - centroid[0]) +
                         (f->com[1] - centroid[1]) * (f->com[1] - centroid[1]);
        f->inertia = f->mass * (polar_moment / area + offset2);
    }
    if (!isfinite(f->inertia)) {
        /* The shape fits in doubles, but mass times its size squared does not. */
        wr_error_set(error, "body.inertia",
                     "the uniform inertia of this shape (mass %g, size %g) overflows a double",
                     f->mass, f->size);
        wr_fixture_free(f);
        return NULL;
    }
    if (!(f->inertia > 0)) {
        wr_error_set(error, "body.inertia", "the uniform inertia of this shape is not positive");
        wr_fixture_free(f);
        return NULL;
    }
    f->gyration_radius = sqrt(f->inertia / f->mass);
    if (!(f->gyration_radius > 0) || !isfinite(f->gyration_radius)) {
        wr_error_set(error, "body.inertia", "inertia / mass must be a positive finite number");
        wr_fixture_free(f);
        return NULL;
    }
    if (!check_scales(f, spec, error) || (!body_only && !place_fixels(f, spec, error))) {
        wr_fixture_free(f);
        return NULL;
    }
    return f;
}

static bool check_placed_list(const wr_fixture *f, wr_error *error);

static bool place_fixels(wr_fixture *f, const wr_fixture_spec *spec, wr_error *error)
{
    f->fixel_count = (int)spec->fixel_count;
    for (size_t i = 0; i < spec->fixel_count; i++) {
        if (!build_fixel(f, spec, i, error)) {
            return false;
        }
        fixel_wrenches(f, &f->fixels[i]);
    }
    return check_placed_list(f, error);
}

/* The checks of the fixels as a list, once each is built: each fixel is
 * built from its own spec alone, so these are all that differ between
 * placing a list and placing its fixels one at a time. */
static bool check_placed_list(const wr_fixture *f, wr_error *error)
{
    /* Fixels spread over less than WR_FIXEL_SPREAD of the radius of
     * gyration have torque rows (r x n) / rho that differ by less than that
     * fraction: the cones' rank decisions and witnesses then rest on the
     * last digits (tests/fuzz/README.md, finding 8).  Fixels all at one
     * point are exact, and kept. */
    double spread = 0;
    for (int i = 0; i < f->fixel_count; i++)
        for (int j = 0; j < i; j++)
            spread = fmax(spread, hypot(f->fixels[i].at[0] - f->fixels[j].at[0],
                                        f->fixels[i].at[1] - f->fixels[j].at[1]));
    if (spread > 0 && spread < WR_FIXEL_SPREAD * f->gyration_radius) {
        wr_error_set(error, "fixels",
                     "the fixels lie within %.3g of each other, less than %g of the radius of "
                     "gyration sqrt(I/m) = %.3g: their torques cannot be told apart",
                     spread, WR_FIXEL_SPREAD, f->gyration_radius);
        return false;
    }
    for (int i = 0; i < f->fixel_count; i++)
        for (int j = 0; j < i; j++) {
            const wr_fixel *a = &f->fixels[j], *b = &f->fixels[i];
            if (hypot(a->at[0] - b->at[0], a->at[1] - b->at[1]) <= BOUNDARY_TOLERANCE * f->size &&
                hypot(a->normal[0] - b->normal[0], a->normal[1] - b->normal[1]) <= BOUNDARY_TOLERANCE) {
                char field[96];
                snprintf(field, sizeof field, "fixels[%d]", i);
                wr_error_set(error, field, "duplicates fixels[%d]: same point and same normal", j);
                return false;
            }
        }
    return true;
}

wr_status wr_fixture_new(const wr_fixture_spec *spec, wr_fixture **out, wr_error *error)
{
    bool no_memory = false;
    *out = validate(spec, false, error, &no_memory);
    if (*out)
        return WR_OK;
    return no_memory ? WR_NO_MEMORY : WR_INVALID;
}

wr_status wr_friction_check(const wr_friction_spec *friction, const char *field, wr_error *error)
{
    if (!friction->given) {
        wr_error_set(error, field, "required");
        return WR_INVALID;
    }
    return check_friction(friction, field, error) ? WR_OK : WR_INVALID;
}

wr_status wr_fixture_body_new(const wr_fixture_spec *spec, wr_fixture **out, wr_error *error)
{
    bool no_memory = false;
    *out = validate(spec, true, error, &no_memory);
    if (*out)
        return WR_OK;
    return no_memory ? WR_NO_MEMORY : WR_INVALID;
}

wr_status wr_fixture_place(const wr_fixture *body, const wr_fixel_spec *fixels, size_t count,
                           const wr_friction_spec *friction, wr_fixture *out, wr_error *error)
{
    /* Only what build_fixel and the list checks read of a spec. */
    wr_fixture_spec spec;
    memset(&spec, 0, sizeof spec);
    spec.fixel_count = count;
    spec.fixels = fixels;
    spec.friction = *friction;
    if (!check_friction(friction, "friction", error) || !check_fixel_list(&spec, error))
        return WR_INVALID;
    *out = *body;
    memset(out->fixels, 0, sizeof out->fixels);
    if (!place_fixels(out, &spec, error))
        return WR_INVALID;
    return WR_OK;
}

wr_status wr_fixture_place_placed(const wr_fixture *body, const wr_fixel *fixels, size_t count,
                                  wr_fixture *out, wr_error *error)
{
    if (count == 0 || count > WR_MAX_FIXELS) {
        wr_error_set(error, "fixels", "from 1 to %d fixels, got %zu", WR_MAX_FIXELS, count);
        return WR_INVALID;
    }
    *out = *body;
    memset(out->fixels, 0, sizeof out->fixels);
    out->fixel_count = (int)count;
    memcpy(out->fixels, fixels, count * sizeof *fixels);
    return check_placed_list(out, error) ? WR_OK : WR_INVALID;
}

/* Here, not in wr_support.c: the fixture owns its supports and frees them,
 * and the supports' analysis depends on the fixture, not the other way. */
void wr_supports_free(wr_supports *supports)
{
    if (!supports)
        return;
    free(supports->distributions);
    free(supports);
}

void wr_fixture_free(wr_fixture *fixture)
{
    if (!fixture)
        return;
    free(fixture->vertices);
    wr_outline_free(fixture->outline);
    wr_supports_free(fixture->supports);
    free(fixture);
}

double wr_fixture_scale_wrench(const wr_fixture *fixture, const double wrench[3],
                               double scaled[3])
{
    scaled[0] = wrench[0];
    scaled[1] = wrench[1];
    scaled[2] = wrench[2] / fixture->gyration_radius;
    return wr_norm3(scaled);
}

double wr_fixture_unit_wrench(const wr_fixture *fixture, const double wrench[3], double unit[3])
{
    double largest = fmax(fabs(wrench[0]), fmax(fabs(wrench[1]), fabs(wrench[2])));
    if (!(largest > 0)) {
        unit[0] = unit[1] = unit[2] = 0;
        return 0;
    }
    /* Components at most 1 before torque meets 1/rho, at most 1 again before
     * squaring: nothing overflows, and the smallest wrenches do not vanish. */
    double h[3] = {wrench[0] / largest, wrench[1] / largest,
                   wrench[2] / largest / fixture->gyration_radius};
    double scaled_largest = fmax(fabs(h[0]), fmax(fabs(h[1]), fabs(h[2])));
    for (int k = 0; k < 3; k++)
        h[k] /= scaled_largest;
    double length = wr_norm3(h);
    for (int k = 0; k < 3; k++)
        unit[k] = h[k] / length;
    return largest * scaled_largest * length;
}

double wr_fixture_unit_direction(double v[3]) { return wr_normalize3(v); }

double wr_fixture_scale_back(const wr_fixture *fixture, const double wrench[3], double length,
                             double value)
{
    if (isfinite(length))
        return value * length;
    /* The length overflowed: the wrench over its largest component has a
     * finite one, and that component comes last. */
    double largest = fmax(fabs(wrench[0]), fmax(fabs(wrench[1]), fabs(wrench[2])));
    double reduced[3] = {wrench[0] / largest, wrench[1] / largest, wrench[2] / largest}, unit[3];
    return value * wr_fixture_unit_wrench(fixture, reduced, unit) * largest;
}

void wr_fixture_unscale_wrench(const wr_fixture *fixture, const double scaled[3],
                               double wrench[3])
{
    wrench[0] = scaled[0];
    wrench[1] = scaled[1];
    wrench[2] = scaled[2] * fixture->gyration_radius;
}

void wr_fixture_unscale_row(const wr_fixture *fixture, const double scaled_row[3],
                            double row[3])
{
    /* f . S g <= 0 with S = diag(1, 1, 1/rho): the physical row is S f. */
    row[0] = scaled_row[0];
    row[1] = scaled_row[1];
    row[2] = scaled_row[2] / fixture->gyration_radius;
    wr_normalize3(row);
}

double wr_fixture_force_factor(const wr_fixture *fixture)
{
    return fixture->units.force_n / fixture->units.length_m;
}

void wr_fixture_edge_normal(const wr_fixture *fixture, size_t edge, double normal[2])
{
    edge_inward_normal(fixture, edge, normal);
}

void wr_fixture_force_wrench(const wr_fixture *fixture, const double force[2],
                             const double at[2], double wrench[3])
{
    double r[2] = {at[0] - fixture->com[0], at[1] - fixture->com[1]};
    wrench[0] = force[0];
    wrench[1] = force[1];
    wrench[2] = cross2(r, force);
}
