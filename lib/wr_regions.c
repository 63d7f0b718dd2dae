/* wr_regions.c -- push regions, gravity arcs, disturbance margins (docs/MODEL.md section 6).
 *
 * Everything here is in the scaled space of wr_cone.c, where the excluded
 * cones live: a wrench g is scaled to h = (f_x, f_y, tau / rho).  A point is
 * in a region when h is outside the closure of every excluded cone of the
 * set; membership of a closed cone {F h <= 0, E h = 0} along an affine or
 * trigonometric curve reduces to one linear condition per row. */
#include "wr_regions.h"
#include "wr_finger.h"
#include "wr_internal.h"
#include "wr_outline.h"

#include <assert.h>
#include <stdlib.h>
#include <string.h>

/* ---- closed spans: the excluded parts of one edge or of the circle ---------- */

typedef struct span {
    double lo, hi;
} span;

typedef struct spans {
    int count, capacity;
    span *items;
    bool failed; /* out of memory */
} spans;

static void add_span(spans *s, double lo, double hi)
{
    if (s->failed || lo > hi)
        return;
    if (s->count == s->capacity) {
        int capacity = s->capacity ? 2 * s->capacity : 32;
        span *grown = realloc(s->items, (size_t)capacity * sizeof *grown);
        if (!grown) {
            s->failed = true;
            return;
        }
        s->items = grown;
        s->capacity = capacity;
    }
    s->items[s->count++] = (span){lo, hi};
}

static int compare_doubles(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* Spans by their lower ends, in place (a heap sort: no allocation, no
 * call per comparison; complement's answer does not depend on the order
 * of spans with the same lower end). */
static void sift_down(span *items, int root, int count)
{
    span moving = items[root];
    for (;;) {
        int child = 2 * root + 1;
        if (child >= count)
            break;
        if (child + 1 < count && items[child + 1].lo > items[child].lo)
            child++;
        if (!(items[child].lo > moving.lo))
            break;
        items[root] = items[child];
        root = child;
    }
    items[root] = moving;
}

static void sort_spans(span *items, int count)
{
    for (int i = count / 2 - 1; i >= 0; i--)
        sift_down(items, i, count);
    for (int end = count - 1; end > 0; end--) {
        span top = items[0];
        items[0] = items[end];
        items[end] = top;
        sift_down(items, 0, end);
    }
}

static bool add_region(wr_regions *r, int edge, double t0, double t1)
{
    if (!(t1 > t0))
        return true;
    if (r->count == r->capacity) {
        int capacity = r->capacity ? 2 * r->capacity : 32;
        wr_region *grown = realloc(r->items, (size_t)capacity * sizeof *grown);
        if (!grown)
            return false;
        r->items = grown;
        r->capacity = capacity;
    }
    r->items[r->count++] = (wr_region){edge, t0, t1};
    return true;
}

/* Gaps narrower than this fraction of the range, between excluded spans
 * that meet in exact arithmetic, are rounding: no region. */
#define SLIVER 1e-9

/* The open complement of the closed spans within (low, high), as regions. */
static bool complement(spans *bad, double low, double high, int edge, wr_regions *out)
{
    sort_spans(bad->items, bad->count);
    double sliver = SLIVER * (high - low);
    double from = low;
    for (int i = 0; i < bad->count; i++) {
        if (bad->items[i].hi < low || bad->items[i].lo > high)
            continue;
        if (bad->items[i].lo > from + sliver && !add_region(out, edge, from, bad->items[i].lo))
            return false;
        if (bad->items[i].hi > from)
            from = bad->items[i].hi;
    }
    return high > from + sliver ? add_region(out, edge, from, high) : true;
}

void wr_regions_release(wr_regions *regions)
{
    free(regions->items);
    memset(regions, 0, sizeof *regions);
}

/* The excluded cones of a set: the goal cones, the mode cones, or both. */
static int set_cones(const wr_analysis *a, wr_set set, const wr_cone ***cones)
{
    int goal = set == WR_SET_STRONG ? 0 : a->plan->kept_count;
    int strong = set == WR_SET_GOAL ? 0 : a->mode_count;
    *cones = malloc((size_t)(goal + strong + 1) * sizeof **cones);
    if (!*cones)
        return -1;
    int n = 0;
    for (int i = 0; i < goal; i++)
        (*cones)[n++] = &a->goal_cones[i];
    for (int i = 0; i < strong; i++)
        (*cones)[n++] = &a->mode_cones[i];
    return n;
}

/* ---- the boundary ---------------------------------------------------------------- */

/* The segment of an outline edge. */
static const wr_segment *edge_segment(const wr_fixture *f, int edge)
{
    size_t loop, segment;
    wr_push_edge_place(f, edge, &loop, &segment);
    return &f->outline->loops[loop].segments[segment];
}

void wr_boundary_point(const wr_fixture *f, int edge, double t, double point[2], double normal[2])
{
    if (f->shape == WR_SHAPE_OUTLINE) {
        size_t loop, segment;
        wr_push_edge_place(f, edge, &loop, &segment);
        wr_outline_boundary(f->outline, loop, segment, t, point, normal);
        return;
    }
    if (f->shape == WR_SHAPE_CIRCLE) {
        double angle = t * WR_PI / 180;
        double u[2] = {cos(angle), sin(angle)};
        point[0] = f->center[0] + f->radius * u[0];
        point[1] = f->center[1] + f->radius * u[1];
        normal[0] = -u[0];
        normal[1] = -u[1];
        return;
    }
    const double *a = f->vertices[edge], *b = f->vertices[((size_t)edge + 1) % f->vertex_count];
    point[0] = a[0] + t * (b[0] - a[0]);
    point[1] = a[1] + t * (b[1] - a[1]);
    wr_fixture_edge_normal(f, (size_t)edge, normal);
}

void wr_push_wrench(const wr_fixture *f, int edge, double t, double wrench[3])
{
    double p[2], nu[2];
    wr_boundary_point(f, edge, t, p, nu);
    wr_fixture_force_wrench(f, nu, p, wrench);
}

double wr_region_length(const wr_fixture *f, const wr_region *r)
{
    if (f->shape == WR_SHAPE_CIRCLE)
        return f->radius * (r->t1 - r->t0) * WR_PI / 180;
    if (f->shape == WR_SHAPE_OUTLINE)
        return (r->t1 - r->t0) * edge_segment(f, r->edge)->length;
    const double *a = f->vertices[r->edge], *b = f->vertices[((size_t)r->edge + 1) % f->vertex_count];
    return (r->t1 - r->t0) * hypot(b[0] - a[0], b[1] - a[1]);
}

double wr_perimeter(const wr_fixture *f)
{
    if (f->shape == WR_SHAPE_CIRCLE)
        return 2 * WR_PI * f->radius;
    if (f->shape == WR_SHAPE_OUTLINE)
        return f->outline->perimeter;
    double length = 0;
    for (size_t i = 0; i < f->vertex_count; i++) {
        const double *a = f->vertices[i], *b = f->vertices[(i + 1) % f->vertex_count];
        length += hypot(b[0] - a[0], b[1] - a[1]);
    }
    return length;
}

/* ---- exact: a line h0 + t h1 against each cone ----------------------------------- */

/* The closed t-interval where h0 + t h1 is in the cone's closure (lo > hi
 * when never).  A row that does not change along the line holds throughout
 * or never; `scale` sizes what counts as zero. */
static span line_in_cone(const wr_cone *cone, const double h0[3], const double h1[3], double scale)
{
    span s = {-INFINITY, INFINITY};
    double zero = 1e-12 * scale;
    for (int i = 0; i < cone->facet_count && s.lo <= s.hi; i++) {
        double alpha = wr_dot3(cone->facets[i], h0), beta = wr_dot3(cone->facets[i], h1);
        if (fabs(beta) <= zero) {
            if (alpha > zero)
                s.lo = INFINITY;
        } else if (beta > 0) {
            s.hi = fmin(s.hi, -alpha / beta);
        } else {
            s.lo = fmax(s.lo, -alpha / beta);
        }
    }
    for (int i = 0; i < cone->equality_count && s.lo <= s.hi; i++) {
        double alpha = wr_dot3(cone->equalities[i], h0), beta = wr_dot3(cone->equalities[i], h1);
        if (fabs(beta) <= zero) {
            if (fabs(alpha) > zero)
                s.lo = INFINITY;
        } else {
            /* One point; rows met at the same point may differ in the last
             * bits, so they are allowed to agree within 1e-12. */
            double t = -alpha / beta;
            if (t > s.hi + 1e-12 || t < s.lo - 1e-12)
                s.lo = INFINITY;
            else
                s.lo = s.hi = fmin(fmax(t, s.lo), s.hi);
        }
    }
    return s;
}

void wr_line_in_cone(const wr_cone *cone, const double h0[3], const double h1[3], double scale,
                     double *lo, double *hi)
{
    span s = line_in_cone(cone, h0, h1, scale);
    *lo = s.lo;
    *hi = s.hi;
}

static void scale_wrench(const wr_fixture *f, const double w[3], double h[3])
{
    h[0] = w[0];
    h[1] = w[1];
    h[2] = w[2] / f->gyration_radius;
}

/* The closed t-spans of a straight edge (a polygon's side, an outline's
 * line) where its push wrench is in some cone: w is affine in t. */
static void line_bad_spans(const wr_fixture *f, const wr_cone **cones, int count, int edge,
                           spans *bad)
{
    double w0[3], w1[3], h0[3], h1[3];
    wr_push_wrench(f, edge, 0, w0);
    wr_push_wrench(f, edge, 1, w1);
    for (int k = 0; k < 3; k++)
        w1[k] -= w0[k]; /* affine: w(t) = w0 + t w1 */
    scale_wrench(f, w0, h0);
    scale_wrench(f, w1, h1);
    double scale = wr_norm3(h0) + wr_norm3(h1);
    for (int c = 0; c < count; c++) {
        if (cones[c]->empty)
            continue;
        span s = line_in_cone(cones[c], h0, h1, scale);
        add_span(bad, s.lo, s.hi);
    }
}

/* ---- exact: a circle of directions u(theta) against each cone -------------------- */

/* Closed arcs in degrees within [0, 360]; wrapping arcs are stored split. */
static void add_arc(spans *s, double from, double length)
{
    from = fmod(from, 360);
    if (from < 0)
        from += 360;
    if (from + length <= 360) {
        add_span(s, from, from + length);
    } else {
        add_span(s, from, 360);
        add_span(s, 0, from + length - 360);
    }
}

/* Intersection of two sets of closed spans. */
static spans intersect(const spans *x, const spans *y)
{
    spans out = {0, 0, NULL, x->failed || y->failed};
    for (int i = 0; i < x->count; i++)
        for (int j = 0; j < y->count; j++)
            add_span(&out, fmax(x->items[i].lo, y->items[j].lo),
                     fmin(x->items[i].hi, y->items[j].hi));
    return out;
}

/* The angles theta where A u(theta), u = (cos, sin), lies in the cone's
 * closure: each facet row r = A^T f asks r . u <= 0, a closed half circle;
 * each equality a pair of opposite points.  A is 3 x 2 (scaled space). */
static spans circle_in_cone(const wr_cone *cone, const double a[3][2])
{
    spans set = {0, 0, NULL, false};
    add_span(&set, 0, 360);
    for (int i = 0; i < cone->facet_count + cone->equality_count && set.count > 0; i++) {
        bool equality = i >= cone->facet_count;
        const double *row = equality ? cone->equalities[i - cone->facet_count] : cone->facets[i];
        double r[2] = {0, 0};
        for (int k = 0; k < 3; k++) {
            r[0] += row[k] * a[k][0];
            r[1] += row[k] * a[k][1];
        }
        if (hypot(r[0], r[1]) <= 1e-12)
            continue; /* the row is 0 . u: it holds everywhere */
        double phi = atan2(r[1], r[0]) * 180 / WR_PI;
        spans half = {0, 0, NULL, false};
        if (equality) {
            add_arc(&half, phi + 90, 0);
            add_arc(&half, phi + 270, 0);
        } else {
            add_arc(&half, phi + 90, 180); /* cos(theta - phi) <= 0 */
        }
        spans next = intersect(&set, &half);
        free(half.items);
        free(set.items);
        set = next;
    }
    return set;
}

/* The closed arcs of [0, 360] degrees where A u(theta) is in some cone's
 * closure, added to `bad`. */
static bool circle_bad_spans(const double a[3][2], const wr_cone **cones, int count,
                             const wr_stop *stop, bool *stopped, spans *bad)
{
    for (int c = 0; c < count && !bad->failed; c++) {
        if (wr_stop_requested(stop)) {
            *stopped = true;
            return false;
        }
        if (cones[c]->empty)
            continue;
        spans arcs = circle_in_cone(cones[c], a);
        for (int i = 0; i < arcs.count; i++)
            add_span(bad, arcs.items[i].lo, arcs.items[i].hi);
        bad->failed |= arcs.failed;
        free(arcs.items);
    }
    return !bad->failed;
}

/* The open arcs of [0, 360) where A u(theta) is outside every cone's
 * closure, split at 0 degrees. */
static bool circle_exact(const double a[3][2], const wr_cone **cones, int count,
                         const wr_stop *stop, bool *stopped, wr_regions *out)
{
    spans bad = {0, 0, NULL, false};
    bool ok = circle_bad_spans(a, cones, count, stop, stopped, &bad) &&
              complement(&bad, 0, 360, 0, out);
    free(bad.items);
    return ok;
}

/* The closed t-spans of an outline's arc where its push wrench is in some
 * cone, worked out in the arc's chord frame rather than about its centre,
 * which for a nearly straight arc lies far away (a bulge of 1e-18 puts it
 * 1e19 out, and angles about it would carry no digits of t).
 *
 * With the chord's midpoint M, unit direction e_d, the unit normal e_n on
 * the side the arc bulges to, half chord h and half angle a (s = sin a,
 * c = cos a), the point at angle phi in [-a, a] from the bisector is
 * M + h (sin phi / s) e_d + h ((cos phi - c) / s) e_n, its outward radial
 * direction sin phi e_d + cos phi e_n, and the inward normal sigma times
 * that.  The scaled push wrench is then C1 b1(phi) + C2 b2(phi) with
 * b1 = sin phi / s, b2 = cos phi and, with D = M - x_c and
 * kappa = e_d x e_n,
 *     C1 = sigma (s e_d, (s D x e_d + kappa h c) / rho),
 *     C2 = sigma (e_n, D x e_n / rho):
 * no coefficient is large.  A row f of a cone is zero where
 * tan phi = -(f.C2) s / (f.C1): atan2 keeps every digit of a small root,
 * and t = (phi / a + 1) / 2 keeps them.  Between consecutive roots the
 * cone's membership does not change and is tested at the middle; at each
 * root it is tested too (a thin cone is met at points only).  arc_wrench
 * gives the scaled wrench at phi. */
static double arc_wrench(const double c1[3], const double c2[3], double s, double phi,
                         double wrench[3])
{
    double b1 = s > 0 ? sin(phi) / s : 0, b2 = cos(phi);
    for (int k = 0; k < 3; k++)
        wrench[k] = c1[k] * b1 + c2[k] * b2;
    /* The size of its parts: what counts as zero against it. */
    return fabs(b1) * wr_norm3(c1) + fabs(b2) * wr_norm3(c2);
}

void wr_edge_frame_of(const wr_fixture *f, int edge, wr_edge_frame *out)
{
    memset(out, 0, sizeof *out);
    double rho = f->gyration_radius;
    if (f->shape == WR_SHAPE_CIRCLE) {
        /* w = (-u, -(d x u)) with d = centre - com: linear in u. */
        double d[2] = {f->center[0] - f->com[0], f->center[1] - f->com[1]};
        out->kind = WR_EDGE_CIRCLE;
        const double c1[3] = {-1, 0, d[1] / rho}, c2[3] = {0, -1, -d[0] / rho};
        wr_copy3(c1, out->c1);
        wr_copy3(c2, out->c2);
        return;
    }
    if (f->shape != WR_SHAPE_OUTLINE || edge_segment(f, edge)->bulge == 0) {
        double w0[3], w1[3];
        wr_push_wrench(f, edge, 0, w0);
        wr_push_wrench(f, edge, 1, w1);
        for (int k = 0; k < 3; k++)
            w1[k] -= w0[k]; /* affine: w(t) = w0 + t w1 */
        out->kind = WR_EDGE_LINE;
        scale_wrench(f, w0, out->c1);
        scale_wrench(f, w1, out->c2);
        return;
    }
    size_t loop, segment;
    wr_push_edge_place(f, edge, &loop, &segment);
    const wr_segment *arc = &f->outline->loops[loop].segments[segment];
    double inward[2], point[2];
    wr_outline_boundary(f->outline, loop, segment, 0.5, point, inward);
    const double *ed = arc->direction, *en = arc->bulge_normal;
    double sigma = inward[0] * en[0] + inward[1] * en[1] > 0 ? 1 : -1;
    double s = arc->half_angle_sin, c = arc->half_angle_cos, h = arc->half_chord;
    double d[2] = {arc->midpoint[0] - f->com[0], arc->midpoint[1] - f->com[1]};
    double kappa = ed[0] * en[1] - ed[1] * en[0];
    double d_ed = d[0] * ed[1] - d[1] * ed[0], d_en = d[0] * en[1] - d[1] * en[0];
    const double c1[3] = {sigma * s * ed[0], sigma * s * ed[1],
                          sigma * (s * d_ed + kappa * h * c) / rho};
    const double c2[3] = {sigma * en[0], sigma * en[1], sigma * d_en / rho};
    out->kind = WR_EDGE_ARC;
    wr_copy3(c1, out->c1);
    wr_copy3(c2, out->c2);
    out->half_angle = arc->half_angle;
    out->half_angle_sin = s;
}

/* The reference for one arc and one cone: every root of every row sorted,
 * then each root and each piece between two tested against every row.
 * False out of memory. */
static bool arc_cone_reference(const wr_edge_frame *frame, const wr_cone *cone, spans *bad)
{
    const double *c1 = frame->c1, *c2 = frame->c2;
    double a = frame->half_angle, s = frame->half_angle_sin;
    int rows = cone->facet_count + cone->equality_count;
    double *roots = malloc((size_t)(5 * rows + 2) * sizeof *roots);
    if (!roots)
        return false;
    int found = 0;
    roots[found++] = -a;
    roots[found++] = a;
    for (int i = 0; i < rows; i++) {
        const double *row =
            i < cone->facet_count ? cone->facets[i] : cone->equalities[i - cone->facet_count];
        double alpha = wr_dot3(row, c1), beta = wr_dot3(row, c2);
        if (alpha == 0 && beta == 0)
            continue;
        /* The root in [-pi/2, pi/2], the other pi away: taken from
         * atan2 as it is, a small root beside pi would keep only
         * pi's ulp of its digits once pi is taken off. */
        double root = alpha >= 0 ? atan2(-beta * s, alpha) : atan2(beta * s, -alpha);
        for (int turn = -2; turn <= 2; turn++) {
            double phi = root + turn * WR_PI;
            if (phi > -a && phi < a)
                roots[found++] = phi;
        }
    }
    qsort(roots, (size_t)found, sizeof *roots, compare_doubles);
    /* Each root, then each piece between two: in the cone's closure? */
    for (int i = 0; i < 2 * found - 1; i++) {
        double phi = i % 2 == 0 ? roots[i / 2] : (roots[i / 2] + roots[i / 2 + 1]) / 2;
        double wrench[3];
        double zero = 1e-12 * arc_wrench(c1, c2, s, phi, wrench);
        bool inside = true;
        for (int k = 0; k < cone->facet_count && inside; k++)
            inside = wr_dot3(cone->facets[k], wrench) <= zero;
        for (int k = 0; k < cone->equality_count && inside; k++)
            inside = fabs(wr_dot3(cone->equalities[k], wrench)) <= zero;
        if (!inside)
            continue;
        double lo = i % 2 == 0 ? phi : roots[i / 2], hi = i % 2 == 0 ? phi : roots[i / 2 + 1];
        add_span(bad, (lo / a + 1) / 2, (hi / a + 1) / 2);
    }
    free(roots);
    return !bad->failed;
}

/* Roots closer than this (radians) to where the fast path puts a span's
 * end, and rows weaker than ARC_WEAK of the curve's size, are where the
 * reference's tolerances could decide otherwise than exact arithmetic: the
 * fast path leaves them to it. */
#define ARC_NEAR 1e-5
#define ARC_WEAK 1e-6

/* Is the angle of (x, y), x >= 0, below that of (u, v), u >= 0?  Both in
 * [-pi/2, pi/2]: by the sign of the cross product, and on the y axis
 * (cross 0, opposite) by y. */
static bool angle_below(double x, double y, double u, double v)
{
    double cross = x * v - y * u;
    return cross != 0 ? cross > 0 : y < v;
}

/* Is any row's root, other than row `self`'s, within ARC_NEAR modulo pi of
 * the direction (dx, dy)?  Roots are the rows' angles (x, y) modulo pi, so
 * near means nearly parallel: |sin| of the angle between them small. */
static bool root_near(const double (*v)[2], int count, int self, double dx, double dy)
{
    double d2 = dx * dx + dy * dy;
    for (int i = 0; i < count; i++) {
        double cross = v[i][0] * dy - v[i][1] * dx;
        if (i != self && cross * cross <= ARC_NEAR * ARC_NEAR * (v[i][0] * v[i][0] + v[i][1] * v[i][1]) * d2)
            return true;
    }
    return false;
}

/* One arc and one full-dimensional cone, with no allocation and at most
 * four atan2: facet row f holds where g(phi) = (f.C1) sin(phi) / s +
 * (f.C2) cos(phi) <= 0, which is everywhere but an open interval of length
 * pi between two of its roots: with the reference's root r in [-pi/2, pi/2]
 * (the angle of (f.C1, -(f.C2) s), its sign made x >= 0), the interval is
 * (r - pi, r) when f.C1 < 0 (a "low" row) and (r, r + pi) otherwise (a
 * "high" row).  Intervals of one length leave of [-a, a] at most three
 * closed pieces: before every start (the least low r less pi, else the
 * least high r), between the greatest low r and the least high r, and
 * after every end (the greatest high r plus pi, else the greatest low r).
 * Only those four extremes need their angles, ordered meanwhile by cross
 * products.  Up to a half circle (a <= pi/2): beyond it, an interval's
 * copy 2 pi away would reach into [-a, a] too.  The reference finds the same pieces between the same roots,
 * computed the same way, unless a row is weak, a piece is nearly a point,
 * or another root lies near a piece's end (its tolerance may then take in
 * a sliver more): false in those cases, with nothing added, and the caller
 * asks the reference. */
static bool arc_cone_fast(const wr_edge_frame *frame, const wr_cone *cone, spans *bad)
{
    const double *c1 = frame->c1, *c2 = frame->c2;
    double a = frame->half_angle, s = frame->half_angle_sin;
    /* Beyond a half circle a row's interval comes back, 2 pi on, within
     * [-a, a]: the reference's. */
    if (cone->equality_count > 0 || cone->facet_count > WR_HULL_MAX || a > WR_PI / 2)
        return false;
    /* The curve's size times s: a row is weak when |(alpha / s, beta)| is
     * below ARC_WEAK of it, compared here times s. */
    double size_s = wr_norm3(c1) + s * wr_norm3(c2), weak = ARC_WEAK * size_s;
    double v[WR_HULL_MAX][2];
    int count = 0;
    int extreme[4] = {-1, -1, -1, -1}; /* low min, low max, high min, high max */
    for (int i = 0; i < cone->facet_count; i++) {
        double alpha = wr_dot3(cone->facets[i], c1), beta = wr_dot3(cone->facets[i], c2);
        if (alpha == 0 && beta == 0)
            continue; /* 0 <= 0 everywhere, as the reference's test finds */
        double x = alpha >= 0 ? alpha : -alpha, y = alpha >= 0 ? -beta * s : beta * s;
        if (x * x + y * y <= weak * weak)
            return false;
        v[count][0] = x;
        v[count][1] = y;
        int *group = alpha < 0 ? extreme : extreme + 2;
        if (group[0] < 0 || angle_below(x, y, v[group[0]][0], v[group[0]][1]))
            group[0] = count;
        if (group[1] < 0 || angle_below(v[group[1]][0], v[group[1]][1], x, y))
            group[1] = count;
        count++;
    }
    /* The extremes' roots, as the reference computes them (root + turn * pi
     * for the pieces' ends); below a half circle by a margin (a < pi/2),
     * the piece before every start is empty when a low row starts at or
     * before -pi/2, and the piece after every end when a high row ends at
     * or after pi/2: their roots are not needed. */
    bool low = extreme[0] >= 0, high = extreme[2] >= 0;
    bool small = a < WR_PI / 2 - 2 * ARC_NEAR;
    bool need[4] = {low && !small, low, high, high && !small};
    double r[4];
    for (int e = 0; e < 4; e++)
        r[e] = need[e] ? atan2(v[extreme[e]][1], v[extreme[e]][0]) : NAN;
    double start_min = low ? (small ? -INFINITY : r[0] + -1 * WR_PI) : high ? r[2] : INFINITY;
    double end_max = high ? (small ? INFINITY : r[3] + 1 * WR_PI) : low ? r[1] : -INFINITY;
    /* Each piece with the rows whose roots are its ends (-1: -a or a). */
    double pieces[3][2] = {{-a, fmin(a, start_min)},
                           {low && high ? fmax(-a, r[1]) : INFINITY, high ? fmin(a, r[2]) : -INFINITY},
                           {fmax(-a, end_max), a}};
    int rows[3][2] = {{-1, low ? extreme[0] : extreme[2]},
                      {extreme[1], extreme[2]},
                      {high ? extreme[3] : extreme[1], -1}};
    for (int p = 0; p < 3; p++) {
        double length = pieces[p][1] - pieces[p][0];
        if (fabs(length) <= ARC_NEAR)
            return false; /* nearly a point, or nearly one and empty */
        if (!(length > 0))
            continue;
        for (int e = 0; e < 2; e++) {
            double end = pieces[p][e];
            /* cos a from sin a: only which roots are near it is asked. */
            double cosine = sqrt(fmax(0.0, (1 - s) * (1 + s))) * (a < WR_PI / 2 ? 1 : -1);
            int row = end == a || end == -a ? -1 : rows[p][e];
            bool near = row >= 0 ? root_near(v, count, row, v[row][0], v[row][1])
                                 : root_near(v, count, -1, cosine, end > 0 ? s : -s);
            if (near)
                return false;
        }
    }
    for (int p = 0; p < 3; p++)
        if (pieces[p][0] < pieces[p][1])
            add_span(bad, (pieces[p][0] / a + 1) / 2, (pieces[p][1] / a + 1) / 2);
    return true;
}

wr_status wr_arc_regions(const wr_edge_frame *frame, const wr_cone **cones, int count,
                         bool reference, int *referred, wr_regions *out)
{
    spans bad = {0, 0, NULL, false};
    bool ok = true;
    for (int n = 0; n < count && ok; n++) {
        if (cones[n]->empty)
            continue;
        bool fast = !reference && arc_cone_fast(frame, cones[n], &bad);
        if (!fast && referred)
            (*referred)++;
        ok = fast || arc_cone_reference(frame, cones[n], &bad);
    }
    ok = ok && complement(&bad, 0, 1, 0, out);
    free(bad.items);
    return ok ? WR_OK : WR_NO_MEMORY;
}

static bool arc_bad_spans(const wr_fixture *f, const wr_cone **cones, int count, int edge,
                          const wr_stop *stop, bool *stopped, spans *bad)
{
    wr_edge_frame frame;
    wr_edge_frame_of(f, edge, &frame);
    for (int n = 0; n < count && !bad->failed; n++) {
        if (wr_stop_requested(stop)) {
            *stopped = true;
            return false;
        }
        if (cones[n]->empty)
            continue;
        if (!arc_cone_fast(&frame, cones[n], bad) && !arc_cone_reference(&frame, cones[n], bad))
            return false;
    }
    return !bad->failed;
}

/* ---- sampled: a finger with friction --------------------------------------------- */

/* Does the segment between scaled wrenches p and q meet the cone's closure? */
static bool segment_meets(const wr_cone *cone, const double p[3], const double q[3])
{
    double d[3] = {q[0] - p[0], q[1] - p[1], q[2] - p[2]};
    span s = line_in_cone(cone, p, d, wr_norm3(p) + wr_norm3(q));
    return s.lo <= s.hi && s.hi >= 0 && s.lo <= 1;
}

/* Is every force of the finger's friction cone at (edge, t) in the set? */
static bool finger_good(const wr_fixture *f, const wr_cone **cones, int count, int edge, double t,
                        double mu)
{
    double p[2], nu[2];
    wr_boundary_point(f, edge, t, p, nu);
    double tangent[2] = {-nu[1], nu[0]};
    double edges[2][3];
    for (int side = 0; side < 2; side++) {
        double sign = side ? 1 : -1;
        double force[2] = {nu[0] + sign * mu * tangent[0], nu[1] + sign * mu * tangent[1]};
        double w[3];
        wr_fixture_force_wrench(f, force, p, w);
        scale_wrench(f, w, edges[side]);
    }
    for (int c = 0; c < count; c++)
        if (!cones[c]->empty && segment_meets(cones[c], edges[0], edges[1]))
            return false;
    return true;
}

/* Samples per edge (or per turn of a circle), and bisection steps. */
#define SAMPLES 2048
#define BISECTIONS 60

/* Samples between two polls of the caller's stop. */
#define SAMPLES_PER_POLL 256

static bool sampled(const wr_fixture *f, const wr_cone **cones, int count, double mu, int edge,
                    double low, double high, const wr_stop *stop, bool *stopped,
                    wr_regions *out)
{
    double step = (high - low) / SAMPLES;
    bool inside = false;
    double start = low;
    bool previous = false;
    for (int k = 0; k <= SAMPLES; k++) {
        if (k % SAMPLES_PER_POLL == 0 && wr_stop_requested(stop)) {
            *stopped = true;
            return false;
        }
        /* The ends of a polygon edge are vertices, in no region: sample
         * just inside them. */
        double t = k == 0 ? low + step * 1e-6 : k == SAMPLES ? high - step * 1e-6 : low + k * step;
        bool good = finger_good(f, cones, count, edge, t, mu);
        if (k > 0 && good != previous) {
            double a = t - step, b = t; /* bisect the change */
            for (int i = 0; i < BISECTIONS; i++) {
                double m = (a + b) / 2;
                if (finger_good(f, cones, count, edge, m, mu) == previous)
                    a = m;
                else
                    b = m;
            }
            double change = (a + b) / 2;
            if (good) {
                start = change;
            } else if (!add_region(out, edge, start, change)) {
                return false;
            }
            inside = good;
        } else if (k == 0) {
            inside = good;
            start = low;
        }
        previous = good;
    }
    return !inside || add_region(out, edge, start, high);
}

/* ---- the public functions ------------------------------------------------------- */

int wr_push_edge_count(const wr_fixture *f)
{
    switch (f->shape) {
    case WR_SHAPE_CIRCLE:
        return 1;
    case WR_SHAPE_POLYGON:
        return (int)f->vertex_count;
    case WR_SHAPE_OUTLINE:
        return (int)f->outline->vertex_count;
    default:
        return 0;
    }
}

void wr_push_edge_place(const wr_fixture *f, int edge, size_t *loop, size_t *segment)
{
    *loop = 0;
    *segment = edge < 0 ? 0 : (size_t)edge;
    if (f->shape != WR_SHAPE_OUTLINE)
        return;
    while (*loop + 1 < f->outline->loop_count &&
           *segment >= f->outline->loops[*loop].segment_count)
        *segment -= f->outline->loops[(*loop)++].segment_count;
    assert(*segment < f->outline->loops[*loop].segment_count);
}

/* The regions of one edge of a polygon or an outline: exact for a
 * frictionless finger (affine on a line, trigonometric on an arc), sampled
 * with friction; less what a finger of the given radius cannot reach. */
static bool edge_regions_blocked(const wr_fixture *f, const wr_cone **cones, int count,
                                 const wr_finger *finger, int edge, const wr_span *items, int n,
                                 const wr_stop *stop, bool *stopped, wr_regions *out);

static bool edge_regions(const wr_fixture *f, const wr_cone **cones, int count,
                         const wr_finger *finger, int edge, const wr_stop *stop, bool *stopped,
                         wr_status *failure, wr_regions *out)
{
    if (wr_stop_requested(stop)) {
        *stopped = true;
        return false;
    }
    wr_span *items = NULL;
    int n = 0;
    if (finger->radius > 0) {
        size_t loop, segment;
        wr_push_edge_place(f, edge, &loop, &segment);
        wr_status status =
            wr_finger_blocked(f->outline, loop, segment, finger->radius, stop, &items, &n);
        if (status != WR_OK) {
            *stopped = status == WR_STOPPED;
            *failure = status;
            free(items);
            return false;
        }
    }
    bool ok = edge_regions_blocked(f, cones, count, finger, edge, items, n, stop, stopped, out);
    free(items);
    return ok;
}

/* edge_regions with the finger's blocked spans of the edge given (n
 * items): what the finger cannot reach depends on the outline alone. */
static bool edge_regions_blocked(const wr_fixture *f, const wr_cone **cones, int count,
                                 const wr_finger *finger, int edge, const wr_span *items, int n,
                                 const wr_stop *stop, bool *stopped, wr_regions *out)
{
    spans blocked = {0, 0, NULL, false};
    for (int i = 0; i < n; i++)
        add_span(&blocked, items[i].lo, items[i].hi);
    bool ok;
    if (finger->friction > 0) {
        /* Sampled regions, then each less the blocked spans. */
        wr_regions sampled_regions = {0};
        ok = sampled(f, cones, count, finger->friction, edge, 0, 1, stop, stopped,
                     &sampled_regions);
        for (int i = 0; ok && i < sampled_regions.count; i++)
            ok = complement(&blocked, sampled_regions.items[i].t0, sampled_regions.items[i].t1,
                            edge, out);
        wr_regions_release(&sampled_regions);
    } else {
        bool arc = f->shape == WR_SHAPE_OUTLINE && edge_segment(f, edge)->bulge != 0;
        if (arc)
            ok = arc_bad_spans(f, cones, count, edge, stop, stopped, &blocked);
        else {
            line_bad_spans(f, cones, count, edge, &blocked);
            ok = !blocked.failed;
        }
        ok = ok && complement(&blocked, 0, 1, edge, out);
    }
    ok = ok && !blocked.failed;
    free(blocked.items);
    return ok;
}

bool wr_finger_pushes_on(const wr_fixture *fixture, const wr_finger *finger, int edge)
{
    if (!finger->push_on)
        return true;
    size_t loop = 0, segment;
    if (fixture->shape == WR_SHAPE_OUTLINE)
        wr_push_edge_place(fixture, edge, &loop, &segment);
    return loop < finger->push_on_count && finger->push_on[loop];
}

wr_status wr_push_regions_part(const wr_analysis *a, wr_set set, const wr_finger *finger,
                               int first_edge, int edge_count, const wr_stop *stop,
                               wr_regions *out)
{
    const wr_fixture *f = a->fixture;
    int edges = wr_push_edge_count(f);
    if (f->shape == WR_SHAPE_NONE)
        return WR_NO_SHAPE;
    if (!(finger->friction >= 0) || !isfinite(finger->friction) || !(finger->radius >= 0) ||
        !isfinite(finger->radius) || first_edge < 0 || edge_count < 0 ||
        edge_count > edges - first_edge)
        return WR_INVALID;
    const wr_cone **cones;
    int count = set_cones(a, set, &cones);
    if (count < 0)
        return WR_NO_MEMORY;
    /* What this part adds is taken back if it fails: `out` is as it was. */
    int before = out->count;
    bool ok = true;
    bool stopped = false;
    wr_status failure = WR_NO_MEMORY; /* what a failure is unless said */
    if (finger->friction > 0)
        out->resolution = f->shape == WR_SHAPE_CIRCLE ? 360.0 / SAMPLES : 1.0 / SAMPLES;
    if (edge_count > 0 && !wr_finger_pushes_on(f, finger, 0) && f->shape != WR_SHAPE_OUTLINE) {
        /* A circle's or a polygon's only loop, not pushed on: no region. */
    } else if (f->shape == WR_SHAPE_CIRCLE) {
        /* A disc is convex: a finger of any radius reaches all of it. */
        if (finger->friction > 0) {
            ok = edge_count == 0 ||
                 sampled(f, cones, count, finger->friction, 0, 0, 360, stop, &stopped, out);
        } else {
            /* w = (-u, -(d x u)) with d = centre - com: linear in u. */
            double d[2] = {f->center[0] - f->com[0], f->center[1] - f->com[1]};
            double rho = f->gyration_radius;
            const double matrix[3][2] = {{-1, 0}, {0, -1}, {d[1] / rho, -d[0] / rho}};
            ok = edge_count == 0 || circle_exact(matrix, cones, count, stop, &stopped, out);
        }
    } else {
        for (int e = first_edge; e < first_edge + edge_count && ok; e++)
            if (wr_finger_pushes_on(f, finger, e))
                ok = edge_regions(f, cones, count, finger, e, stop, &stopped, &failure, out);
    }
    free(cones);
    if (!ok) {
        out->count = before;
        return stopped ? WR_STOPPED : failure;
    }
    return WR_OK;
}

wr_status wr_push_regions_finger(const wr_analysis *a, wr_set set, const wr_finger *finger,
                                 const wr_stop *stop, wr_regions *out)
{
    memset(out, 0, sizeof *out);
    wr_status status =
        wr_push_regions_part(a, set, finger, 0, wr_push_edge_count(a->fixture), stop, out);
    if (status != WR_OK)
        wr_regions_release(out);
    return status;
}

wr_status wr_push_regions(const wr_analysis *a, wr_set set, double finger_friction,
                          const wr_stop *stop, wr_regions *out)
{
    wr_finger finger = {.friction = finger_friction};
    return wr_push_regions_finger(a, set, &finger, stop, out);
}

wr_status wr_gravity_sweep(const wr_analysis *a, wr_set set, wr_regions *out)
{
    memset(out, 0, sizeof *out);
    const wr_cone **cones;
    int count = set_cones(a, set, &cones);
    if (count < 0)
        return WR_NO_MEMORY;
    /* m g0 (cos phi, sin phi, 0): gravity acts at the centre of mass. */
    const double matrix[3][2] = {{1, 0}, {0, 1}, {0, 0}};
    bool ok = circle_exact(matrix, cones, count, NULL, &(bool){false}, out);
    free(cones);
    if (!ok) {
        wr_regions_release(out);
        return WR_NO_MEMORY;
    }
    return WR_OK;
}

wr_status wr_disturbance_margin(const wr_analysis *a, const double bias[3], wr_disturbance *out)
{
    memset(out, 0, sizeof *out);
    out->blocking = -1;
    if (!isfinite(bias[0]) || !isfinite(bias[1]) || !isfinite(bias[2]))
        return WR_INVALID;
    if (a->mode_count == 0)
        return WR_OK; /* nothing moves the part */
    out->bounded = true;
    const wr_fixture *f = a->fixture;
    double x[3];
    double length = wr_fixture_unit_wrench(f, bias, x);
    double direction[3] = {0, 0, 0};
    if (!(length > 0)) {
        /* The zero bias: any disturbance along an excluded cone moves it. */
        out->blocking = 0;
        const wr_cone *cone = &a->mode_cones[0];
        if (cone->ray_count > 0)
            wr_copy3(cone->rays[0], direction);
    } else {
        double unit_margin = wr_set_margin(a, WR_SET_STRONG, x, &out->blocking);
        /* Distances in a cone scale with |h|.  |h| itself may overflow for
         * a bias near the largest double while the margin does not: scale
         * by the largest component last. */
        double largest = fmax(fabs(bias[0]), fmax(fabs(bias[1]), fabs(bias[2])));
        double reduced[3] = {bias[0] / largest, bias[1] / largest, bias[2] / largest}, unused[3];
        out->margin = unit_margin * wr_fixture_unit_wrench(f, reduced, unused) * largest;
        if (!isfinite(out->margin)) {
            memset(out, 0, sizeof *out);
            out->blocking = -1;
            return WR_INVALID;
        }
        const wr_cone *cone = &a->mode_cones[out->blocking];
        if (unit_margin > 0) {
            double projection[3];
            wr_cone_signed_distance(cone, x, projection);
            for (int k = 0; k < 3; k++)
                direction[k] = projection[k] - x[k];
        } else if (cone->dimension == 3 && cone->facet_count > 0) {
            /* Out of the deepest cone through its nearest facet. */
            int nearest = 0;
            for (int i = 1; i < cone->facet_count; i++)
                if (wr_dot3(cone->facets[i], x) > wr_dot3(cone->facets[nearest], x))
                    nearest = i;
            wr_copy3(cone->facets[nearest], direction);
        } else if (cone->equality_count > 0) {
            wr_copy3(cone->equalities[0], direction); /* off a thin cone */
        } else {
            for (int k = 0; k < 3; k++) /* the whole space: only less bias helps */
                direction[k] = -x[k];
        }
    }
    wr_normalize3(direction);
    wr_fixture_unscale_wrench(f, direction, out->worst_direction);
    return WR_OK;
}

/* ---- the push index: edges by the wrench directions they can produce ------------- */

/* A cap of the unit sphere of scaled wrench directions: every direction
 * within `radius` (radians) of the unit `center`. */
typedef struct cap {
    double center[3];
    double radius;
    double reach;  /* sin(radius) + CAP_ROOM: what cap_against compares with */
} cap;

/* A node covers the reachable edges leaves[lo, hi) in edge order; a leaf
 * has hi = lo + 1 and no children. */
typedef struct index_node {
    int lo, hi;
    int left, right; /* node indices; -1 for a leaf */
    cap cap;
} index_node;

struct wr_push_index {
    const wr_fixture *body;  /* borrowed: its outline, com and rho are the index's */
    wr_finger finger;
    int edge_count;
    /* Each edge's blocked spans: spans[offsets[e], offsets[e + 1]). */
    int *offsets;
    wr_span *spans;
    int *leaves;             /* the reachable edges, increasing */
    int leaf_count;
    index_node *nodes;       /* nodes[0] the root (when leaf_count > 0) */
    int node_count;
};

/* A cap is tested against a cone only with this much room (radians, about):
 * far above the 1e-12 that the exact tests of an edge allow for rounding,
 * so that a cone the cap clears, or that holds the cap, contributes to the
 * exact answer exactly what the test says (nothing, or everything). */
#define CAP_ROOM 1e-7

static double angle3(const double a[3], const double b[3])
{
    double cross[3];
    wr_cross3(a, b, cross);
    return atan2(wr_norm3(cross), wr_dot3(a, b));
}

/* The cap of the shorter great-circle arc from direction u to v (neither
 * zero, not opposite). */
static cap arc_cap(const double u[3], const double v[3])
{
    double a[3], b[3];
    wr_copy3(u, a);
    wr_copy3(v, b);
    wr_normalize3(a);
    wr_normalize3(b);
    cap c;
    for (int k = 0; k < 3; k++)
        c.center[k] = a[k] + b[k];
    if (!(wr_norm3(c.center) > 1e-6)) {
        wr_copy3(a, c.center);
        c.radius = WR_PI;
        return c;
    }
    wr_normalize3(c.center);
    c.radius = fmax(angle3(c.center, a), angle3(c.center, b)) + 1e-12;
    return c;
}

/* A cap holding both. */
static cap cap_union(const cap *x, const cap *y)
{
    cap c;
    for (int k = 0; k < 3; k++)
        c.center[k] = x->center[k] + y->center[k];
    if (!(wr_norm3(c.center) > 1e-6)) {
        wr_copy3(x->center, c.center);
        c.radius = WR_PI;
        return c;
    }
    wr_normalize3(c.center);
    c.radius = fmin(WR_PI, fmax(angle3(c.center, x->center) + x->radius,
                                angle3(c.center, y->center) + y->radius) + 1e-12);
    return c;
}

/* The cap of every push direction along an edge.  A line's scaled push
 * wrench c1 + t c2 is never zero (its force is a unit normal), so its
 * directions are the shorter arc between its ends; an arc's,
 * c1 sin(phi) / s + c2 cos(phi), is an ellipse about the origin, whose
 * direction turns monotonically, less than half a turn from phi = -a to 0
 * and from 0 to a (a < pi). */
static cap edge_cap(const wr_fixture *f, int edge)
{
    wr_edge_frame frame;
    wr_edge_frame_of(f, edge, &frame);
    if (frame.kind == WR_EDGE_LINE) {
        double end[3];
        for (int k = 0; k < 3; k++)
            end[k] = frame.c1[k] + frame.c2[k];
        return arc_cap(frame.c1, end);
    }
    double c = cos(frame.half_angle), from[3], to[3];
    for (int k = 0; k < 3; k++) {
        from[k] = -frame.c1[k] + c * frame.c2[k];
        to[k] = frame.c1[k] + c * frame.c2[k];
    }
    cap first = arc_cap(from, frame.c2), second = arc_cap(frame.c2, to);
    return cap_union(&first, &second);
}

/* Is the cap inside the cone's closure (1), clear of it (-1), or neither
 * (0), each with CAP_ROOM to spare?  Unit facet rows f: f . x <= 0 over the
 * cap when the angle from f to the centre is at least pi/2 + radius, and
 * f . x > 0 over it when at most pi/2 - radius. */
static int cap_against(const cap *c, const wr_cone *cone)
{
    if (c->radius >= WR_PI / 2 - 2 * CAP_ROOM)
        return 0;
    double edge = c->reach;
    bool inside = cone->equality_count == 0;
    for (int i = 0; i < cone->facet_count; i++) {
        double d = wr_dot3(cone->facets[i], c->center);
        if (d >= edge)
            return -1;
        if (d > -edge)
            inside = false;
    }
    for (int i = 0; i < cone->equality_count; i++)
        if (fabs(wr_dot3(cone->equalities[i], c->center)) >= edge)
            return -1;
    return inside ? 1 : 0;
}

static int index_build(wr_push_index *x, const cap *leaf_caps, int lo, int hi)
{
    int n = x->node_count++;
    index_node *node = &x->nodes[n];
    node->lo = lo;
    node->hi = hi;
    if (hi - lo == 1) {
        node->left = node->right = -1;
        node->cap = leaf_caps[lo];
        node->cap.reach = sin(node->cap.radius) + CAP_ROOM;
        return n;
    }
    int mid = lo + (hi - lo) / 2;
    int left = index_build(x, leaf_caps, lo, mid);
    int right = index_build(x, leaf_caps, mid, hi);
    /* x->nodes does not move: it was sized for every node. */
    x->nodes[n].left = left;
    x->nodes[n].right = right;
    x->nodes[n].cap = cap_union(&x->nodes[left].cap, &x->nodes[right].cap);
    x->nodes[n].cap.reach = sin(x->nodes[n].cap.radius) + CAP_ROOM;
    return n;
}

wr_status wr_push_index_new(const wr_fixture *body, const wr_finger *finger,
                            wr_push_index **out)
{
    *out = NULL;
    if (!(finger->friction >= 0) || !isfinite(finger->friction) || !(finger->radius >= 0) ||
        !isfinite(finger->radius))
        return WR_INVALID;
    if (body->shape != WR_SHAPE_OUTLINE && body->shape != WR_SHAPE_POLYGON)
        return WR_NO_SHAPE;
    wr_push_index *x = calloc(1, sizeof *x);
    if (!x)
        return WR_NO_MEMORY;
    x->body = body;
    x->finger = *finger;
    x->edge_count = wr_push_edge_count(body);
    int edges = x->edge_count;
    x->offsets = calloc((size_t)edges + 1, sizeof *x->offsets);
    x->leaves = malloc((size_t)edges * sizeof *x->leaves);
    x->nodes = malloc((size_t)(2 * edges) * sizeof *x->nodes);
    cap *leaf_caps = malloc((size_t)edges * sizeof *leaf_caps);
    wr_status status = x->offsets && x->leaves && x->nodes && leaf_caps ? WR_OK : WR_NO_MEMORY;
    int span_count = 0;
    for (int e = 0; e < edges && status == WR_OK; e++) {
        if (finger->radius > 0) {
            size_t loop, segment;
            wr_push_edge_place(body, e, &loop, &segment);
            status = wr_finger_blocked(body->outline, loop, segment, finger->radius, NULL,
                                       &x->spans, &span_count);
        }
        x->offsets[e + 1] = span_count;
        if (status != WR_OK)
            break;
        /* An edge the finger reaches nowhere has no region whatever the
         * cones: the exact answer is the complement of the spans excluded,
         * which only more spans can shrink. */
        spans blocked = {0, 0, NULL, false};
        for (int i = x->offsets[e]; i < span_count; i++)
            add_span(&blocked, x->spans[i].lo, x->spans[i].hi);
        wr_regions reach = {0};
        if (!blocked.failed && complement(&blocked, 0, 1, e, &reach)) {
            /* An edge not pushed on (push_on) has no region either. */
            if (reach.count > 0 && wr_finger_pushes_on(body, finger, e)) {
                leaf_caps[x->leaf_count] = edge_cap(body, e);
                x->leaves[x->leaf_count++] = e;
            }
        } else {
            status = WR_NO_MEMORY;
        }
        free(blocked.items);
        wr_regions_release(&reach);
    }
    /* Never NULL, so that an edge's spans are always at spans + offset. */
    if (status == WR_OK && !x->spans && !(x->spans = malloc(sizeof *x->spans)))
        status = WR_NO_MEMORY;
    if (status == WR_OK && x->leaf_count > 0)
        index_build(x, leaf_caps, 0, x->leaf_count);
    free(leaf_caps);
    if (status != WR_OK) {
        wr_push_index_free(x);
        return status;
    }
    *out = x;
    return WR_OK;
}

void wr_push_index_free(wr_push_index *index)
{
    if (!index)
        return;
    free(index->offsets);
    free(index->spans);
    free(index->leaves);
    free(index->nodes);
    free(index);
}

size_t wr_push_index_bytes(const wr_push_index *index)
{
    return sizeof *index + (size_t)(index->edge_count + 1) * sizeof *index->offsets +
           (size_t)index->offsets[index->edge_count] * sizeof *index->spans +
           (size_t)index->edge_count * (sizeof *index->leaves + 2 * sizeof *index->nodes);
}

void wr_push_index_blocked(const wr_push_index *index, int edge, const wr_span **spans,
                           int *count)
{
    assert(edge >= 0 && edge < index->edge_count);
    *spans = index->spans + index->offsets[edge];
    *count = index->offsets[edge + 1] - index->offsets[edge];
}

/* The regions of the node's edges, in edge order, against the cones left
 * (count of them; room holds what the node's descendants need). */
static bool index_visit(const wr_push_index *x, int n, const wr_fixture *f, const wr_cone **cones,
                        int count, const wr_cone **room, const wr_stop *stop, bool *stopped,
                        wr_regions *out)
{
    const index_node *node = &x->nodes[n];
    int kept = 0;
    for (int i = 0; i < count; i++) {
        if (cones[i]->empty)
            continue;
        int where = cap_against(&node->cap, cones[i]);
        if (where > 0)
            return true; /* every direction of every edge here is excluded */
        if (where == 0)
            room[kept++] = cones[i];
    }
    if (node->left < 0) {
        if (wr_stop_requested(stop)) {
            *stopped = true;
            return false;
        }
        int e = x->leaves[node->lo];
        return edge_regions_blocked(f, room, kept, &x->finger, e, x->spans + x->offsets[e],
                                    x->offsets[e + 1] - x->offsets[e], stop, stopped, out);
    }
    return index_visit(x, node->left, f, room, kept, room + kept, stop, stopped, out) &&
           index_visit(x, node->right, f, room, kept, room + kept, stop, stopped, out);
}

wr_status wr_push_regions_indexed(const wr_analysis *a, wr_set set, const wr_push_index *index,
                                  const wr_stop *stop, wr_regions *out)
{
    memset(out, 0, sizeof *out);
    const wr_fixture *f = a->fixture;
    /* The index describes the body the fixture was placed on. */
    assert(f->outline == index->body->outline && f->com[0] == index->body->com[0] &&
           f->com[1] == index->body->com[1] &&
           f->gyration_radius == index->body->gyration_radius);
    if (index->finger.friction > 0)
        return wr_push_regions_finger(a, set, &index->finger, stop, out);
    const wr_cone **cones;
    int count = set_cones(a, set, &cones);
    if (count < 0)
        return WR_NO_MEMORY;
    /* Each level of the tree keeps at most the cones of the one above. */
    int depth = 2;
    for (int n = index->leaf_count; n > 1; n = (n + 1) / 2)
        depth++;
    const wr_cone **room = malloc((size_t)(depth * (count + 1)) * sizeof *room);
    bool stopped = false, ok = room != NULL;
    if (ok && index->leaf_count > 0)
        ok = index_visit(index, 0, f, cones, count, room, stop, &stopped, out);
    free(room);
    free(cones);
    if (!ok) {
        wr_regions_release(out);
        return stopped ? WR_STOPPED : WR_NO_MEMORY;
    }
    return WR_OK;
}
