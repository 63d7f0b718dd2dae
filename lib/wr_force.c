/* wr_force.c -- magnitudes of pushes among loads (wr_force.h, docs/MODEL.md
 * section 6).  Everything is decided in the scaled space of wr_cone.c, as
 * the push regions are: a line or a trigonometric curve against each
 * excluded cone's rows. */
#include "wr_force.h"
#include "wr_finger.h"
#include "wr_internal.h"
#include "wr_outline.h"

#include <assert.h>
#include <stdlib.h>
#include <string.h>

/* ---- closed spans, and the open intervals between them -------------------------- */

typedef struct spanlist {
    int count, capacity;
    wr_force_interval *items;
    bool failed; /* out of memory: sticky */
} spanlist;

static void span_add(spanlist *s, double lo, double hi)
{
    if (s->failed || !(lo <= hi))
        return;
    if (s->count == s->capacity) {
        int capacity = s->capacity ? 2 * s->capacity : 32;
        wr_force_interval *grown = realloc(s->items, (size_t)capacity * sizeof *grown);
        if (!grown) {
            s->failed = true;
            return;
        }
        s->items = grown;
        s->capacity = capacity;
    }
    s->items[s->count++] = (wr_force_interval){lo, hi};
}

static int compare_lo(const void *a, const void *b)
{
    double x = ((const wr_force_interval *)a)->lo, y = ((const wr_force_interval *)b)->lo;
    return (x > y) - (x < y);
}

static int compare_doubles(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* The open gaps of [low, high] between the closed spans `bad`, into `good`
 * (appended), each mapped by `map` (NULL: as they are).  A gap no wider than
 * sliver(from, to) is rounding where two spans meet.  Sorts `bad`. */
static void gaps(spanlist *bad, double low, double high, double (*sliver)(double, double, double),
                 double sliver_arg, spanlist *good)
{
    if (bad->count > 0)
        qsort(bad->items, (size_t)bad->count, sizeof *bad->items, compare_lo);
    double from = low;
    for (int i = 0; i <= bad->count; i++) {
        double to = i < bad->count ? bad->items[i].lo : high;
        if (i < bad->count && (bad->items[i].hi < low || bad->items[i].lo > high))
            continue;
        to = fmin(to, high);
        if (to > from && to - from > sliver(from, to, sliver_arg))
            span_add(good, from, to);
        if (i < bad->count && bad->items[i].hi > from)
            from = bad->items[i].hi;
    }
}

/* The excluded cones of a set, one after another: goal's, then strong's. */
static int set_cone_count(const wr_analysis *a, wr_set set)
{
    return (set == WR_SET_STRONG ? 0 : wr_analysis_cone_count(a, WR_SET_GOAL)) +
           (set == WR_SET_GOAL ? 0 : wr_analysis_cone_count(a, WR_SET_STRONG));
}

static const wr_cone *set_cone(const wr_analysis *a, wr_set set, int index)
{
    int goal = set == WR_SET_STRONG ? 0 : wr_analysis_cone_count(a, WR_SET_GOAL);
    return index < goal ? wr_analysis_cone(a, WR_SET_GOAL, index)
                        : wr_analysis_cone(a, WR_SET_STRONG, index - goal);
}

static bool finite3(const double v[3])
{
    return isfinite(v[0]) && isfinite(v[1]) && isfinite(v[2]);
}

static void scaled(const wr_fixture *f, const double w[3], double h[3])
{
    h[0] = w[0];
    h[1] = w[1];
    h[2] = w[2] / f->gyration_radius;
}

/* ---- the magnitudes of one push against one load --------------------------------- */

void wr_forces_release(wr_forces *forces)
{
    free(forces->items);
    memset(forces, 0, sizeof *forces);
}

/* In units of s = F |u| / |L|, where the load is 1: 1e-9 of the larger of
 * the gap's upper end and the load. */
static double force_sliver(double from, double to, double unused)
{
    (void)from;
    (void)unused;
    return 1e-9 * fmax(1, isfinite(to) ? fabs(to) : 1);
}

wr_status wr_force_range(const wr_analysis *a, wr_set set, const double load[3],
                         const double push[3], double lo, double hi, wr_forces *out)
{
    wr_forces_release(out);
    if (!finite3(load) || !finite3(push) || !(lo >= 0) || !isfinite(lo) || !(hi >= lo))
        return WR_INVALID;
    const wr_fixture *f = wr_analysis_fixture(a);
    double hl[3], hu[3];
    scaled(f, load, hl);
    scaled(f, push, hu);
    double nl = wr_normalize3(hl), nu = wr_normalize3(hu);
    if (!(nu > 0) || !isfinite(nl) || !isfinite(nu))
        return WR_INVALID;
    /* The line is nl (x_L + s x_u) with s = F nu / nl: unit vectors, so the
     * rows' zero is absolute.  Without a load, s = F nu. */
    double k = nl > 0 ? nu / nl : nu;
    spanlist bad = {0}, good = {0};
    int count = set_cone_count(a, set);
    for (int i = 0; i < count; i++) {
        const wr_cone *cone = set_cone(a, set, i);
        if (cone->empty)
            continue;
        double s0, s1;
        wr_line_in_cone(cone, hl, hu, 2, &s0, &s1);
        span_add(&bad, fmax(s0, 0), s1);
    }
    /* s = 0 without a load is the zero wrench: on every cone's boundary. */
    if (!(nl > 0))
        span_add(&bad, 0, 0);
    double s_lo = lo * k, s_hi = hi * k;
    gaps(&bad, s_lo, s_hi, force_sliver, 0, &good);
    free(bad.items);
    if (good.failed) {
        free(good.items);
        return WR_NO_MEMORY;
    }
    /* Back to magnitudes: the range's own ends exactly as given. */
    for (int i = 0; i < good.count; i++) {
        wr_force_interval *g = &good.items[i];
        g->lo = g->lo == s_lo ? lo : g->lo / k;
        g->hi = g->hi == s_hi ? hi : g->hi / k;
    }
    out->items = good.items;
    out->count = good.count;
    out->capacity = good.capacity;
    return WR_OK;
}

wr_status wr_forces_intersect(const wr_forces *a, const wr_forces *b, wr_forces *out)
{
    spanlist both = {0};
    for (int i = 0, j = 0; i < a->count && j < b->count;) {
        double lo = fmax(a->items[i].lo, b->items[j].lo);
        double hi = fmin(a->items[i].hi, b->items[j].hi);
        if (lo < hi)
            span_add(&both, lo, hi);
        if (a->items[i].hi < b->items[j].hi)
            i++;
        else
            j++;
    }
    if (both.failed) {
        free(both.items);
        return WR_NO_MEMORY;
    }
    wr_forces_release(out);
    out->items = both.items;
    out->count = both.count;
    out->capacity = both.capacity;
    return WR_OK;
}

/* ---- push regions under loads ----------------------------------------------------- */

/* 1e-9 of the parameter's whole range (of t, or of 360 degrees), as the
 * push regions' own (wr_regions.h). */
static double range_sliver(double from, double to, double range)
{
    (void)from;
    (void)to;
    return 1e-9 * range;
}

/* Where on a straight edge, w(t) = c1 + t c2 (scaled, per unit force), the
 * wrench F w(t) + L of each case is in some cone's closure: closed t-spans
 * into `bad`.  `offsets` are the cases' scaled loads over F. */
static void line_bad(const wr_analysis *a, wr_set set, const wr_edge_frame *frame,
                     const double (*offsets)[3], int cases, spanlist *bad)
{
    int count = set_cone_count(a, set);
    for (int c = 0; c < cases; c++) {
        double h0[3];
        for (int k = 0; k < 3; k++)
            h0[k] = frame->c1[k] + offsets[c][k];
        double scale = wr_norm3(h0) + wr_norm3(frame->c2);
        for (int i = 0; i < count; i++) {
            const wr_cone *cone = set_cone(a, set, i);
            if (cone->empty)
                continue;
            double t0, t1;
            wr_line_in_cone(cone, h0, frame->c2, scale, &t0, &t1);
            span_add(bad, fmax(t0, 0), fmin(t1, 1));
        }
    }
}

/* A curve phi -> P cos phi + Q sin phi + o over [p0, p1], and how its phi
 * maps to the answer's t (t = (phi - t_shift) * t_scale). */
typedef struct trig_curve {
    double p[3], q[3];
    double p0, p1;
    double t_shift, t_scale;
    /* An arc's Q is c1 / s, s its half angle's sine, which may be tiny:
     * rows are solved multiplied through by s, and wrenches made with
     * sin(phi) / s, so no huge coefficient appears. */
    double s;
} trig_curve;

static double curve_wrench(const trig_curve *c, const double o[3], double phi, double w[3])
{
    double cp = cos(phi), sp = sin(phi) / c->s;
    for (int k = 0; k < 3; k++)
        w[k] = c->p[k] * cp + c->q[k] * sp + o[k];
    return fabs(cp) * wr_norm3(c->p) + fabs(sp) * wr_norm3(c->q) + wr_norm3(o);
}

static bool in_closure(const wr_cone *cone, const double w[3], double zero)
{
    for (int k = 0; k < cone->facet_count; k++)
        if (wr_dot3(cone->facets[k], w) > zero)
            return false;
    for (int k = 0; k < cone->equality_count; k++)
        if (fabs(wr_dot3(cone->equalities[k], w)) > zero)
            return false;
    return true;
}

/* The closed phi-spans where the curve plus `o` is in the cone's closure,
 * as t-spans into `bad`.  Each row r is zero where
 * (r.P) s cos phi + (r.Q) s sin phi = -(r.o) s: two roots at most per
 * turn; between consecutive roots membership does not change, and it is
 * tested at each root too (a thin cone is met at points only).  `roots`
 * has room for 4 per row and 2 more. */
static void curve_bad(const wr_cone *cone, const trig_curve *c, const double o[3], double *roots,
                      spanlist *bad)
{
    int rows = cone->facet_count + cone->equality_count, found = 0;
    roots[found++] = c->p0;
    roots[found++] = c->p1;
    for (int i = 0; i < rows; i++) {
        const double *row =
            i < cone->facet_count ? cone->facets[i] : cone->equalities[i - cone->facet_count];
        double A = wr_dot3(row, c->p) * c->s, B = wr_dot3(row, c->q), C = -wr_dot3(row, o) * c->s;
        double R = hypot(A, B);
        if (!(R > 0) || fabs(C) > R)
            continue;
        double psi = atan2(B, A), delta = acos(C / R);
        for (int sign = -1; sign <= 1; sign += 2)
            for (int turn = -1; turn <= 1; turn++) {
                double phi = psi + sign * delta + 2 * WR_PI * turn;
                if (phi > c->p0 && phi < c->p1)
                    roots[found++] = phi;
            }
    }
    qsort(roots, (size_t)found, sizeof *roots, compare_doubles);
    for (int i = 0; i < 2 * found - 1; i++) {
        bool at_root = i % 2 == 0;
        double phi = at_root ? roots[i / 2] : (roots[i / 2] + roots[i / 2 + 1]) / 2;
        double w[3];
        double zero = 1e-12 * curve_wrench(c, o, phi, w);
        if (!in_closure(cone, w, zero))
            continue;
        double lo = at_root ? phi : roots[i / 2], hi = at_root ? phi : roots[i / 2 + 1];
        span_add(bad, (lo - c->t_shift) * c->t_scale, (hi - c->t_shift) * c->t_scale);
    }
}

static bool trig_bad(const wr_analysis *a, wr_set set, const trig_curve *curve,
                     const double (*offsets)[3], int cases, spanlist *bad)
{
    int count = set_cone_count(a, set), most = 0;
    for (int i = 0; i < count; i++) {
        const wr_cone *cone = set_cone(a, set, i);
        int rows = cone->facet_count + cone->equality_count;
        most = rows > most ? rows : most;
    }
    double *roots = malloc((size_t)(6 * most + 2) * sizeof *roots);
    if (!roots)
        return false;
    for (int c = 0; c < cases; c++)
        for (int i = 0; i < count; i++)
            if (!set_cone(a, set, i)->empty)
                curve_bad(set_cone(a, set, i), curve, offsets[c], roots, bad);
    free(roots);
    return !bad->failed;
}

/* The regions of one edge (a circle: its one edge), appended to `out`. */
static bool edge_loaded(const wr_analysis *a, wr_set set, const double (*offsets)[3], int cases,
                        double radius, int edge, const wr_stop *stop, wr_status *failure,
                        wr_regions *out)
{
    const wr_fixture *f = wr_analysis_fixture(a);
    spanlist bad = {0}, good = {0};
    wr_edge_frame frame;
    wr_edge_frame_of(f, edge, &frame);
    double high = 1;
    bool ok = true;
    if (frame.kind == WR_EDGE_LINE) {
        line_bad(a, set, &frame, offsets, cases, &bad);
    } else {
        trig_curve curve;
        memset(&curve, 0, sizeof curve);
        if (frame.kind == WR_EDGE_CIRCLE) {
            /* w = c1 cos theta + c2 sin theta, theta the boundary angle. */
            wr_copy3(frame.c1, curve.p);
            wr_copy3(frame.c2, curve.q);
            curve.s = 1;
            curve.p0 = 0;
            curve.p1 = 2 * WR_PI;
            curve.t_shift = 0;
            curve.t_scale = 180 / WR_PI;
            high = 360;
        } else {
            /* w = c1 sin(phi) / s + c2 cos(phi), phi in [-a, a] from the
             * bisector (wr_edge_frame_of), t = (phi / a + 1) / 2. */
            wr_copy3(frame.c2, curve.p);
            wr_copy3(frame.c1, curve.q);
            curve.s = frame.half_angle_sin;
            curve.p0 = -frame.half_angle;
            curve.p1 = frame.half_angle;
            curve.t_shift = -frame.half_angle;
            curve.t_scale = 1 / (2 * frame.half_angle);
        }
        ok = trig_bad(a, set, &curve, offsets, cases, &bad);
    }
    if (ok && radius > 0 && f->shape != WR_SHAPE_CIRCLE) {
        /* A disc is convex: a finger of any radius reaches all of it. */
        size_t loop, segment;
        wr_push_edge_place(f, edge, &loop, &segment);
        wr_span *items = NULL;
        int n = 0;
        wr_status status = wr_finger_blocked(f->outline, loop, segment, radius, stop, &items, &n);
        if (status != WR_OK) {
            *failure = status;
            ok = false;
        }
        for (int i = 0; i < n; i++)
            span_add(&bad, items[i].lo, items[i].hi);
        free(items);
    }
    if (ok)
        gaps(&bad, 0, high, range_sliver, high, &good);
    ok = ok && !bad.failed && !good.failed;
    for (int i = 0; ok && i < good.count; i++) {
        if (out->count == out->capacity) {
            int capacity = out->capacity ? 2 * out->capacity : 32;
            wr_region *grown = realloc(out->items, (size_t)capacity * sizeof *grown);
            if (!grown) {
                ok = false;
                break;
            }
            out->items = grown;
            out->capacity = capacity;
        }
        out->items[out->count++] = (wr_region){edge, good.items[i].lo, good.items[i].hi};
    }
    free(bad.items);
    free(good.items);
    return ok;
}

wr_status wr_push_regions_loaded(const wr_analysis *a, wr_set set, double force,
                                 const double (*loads)[3], int case_count, double finger_radius,
                                 int first_edge, int edge_count, const wr_stop *stop,
                                 wr_regions *out)
{
    const wr_fixture *f = wr_analysis_fixture(a);
    int edges = wr_push_edge_count(f);
    if (f->shape == WR_SHAPE_NONE)
        return WR_NO_SHAPE;
    if (!(force > 0) || !isfinite(force) || case_count < 1 || !(finger_radius >= 0) ||
        !isfinite(finger_radius) || first_edge < 0 || edge_count < 0 ||
        edge_count > edges - first_edge)
        return WR_INVALID;
    for (int c = 0; c < case_count; c++)
        if (!finite3(loads[c]))
            return WR_INVALID;
    /* Cones are cones: F w + L is in one exactly when w + L / F is. */
    double (*offsets)[3] = malloc((size_t)case_count * sizeof *offsets);
    if (!offsets)
        return WR_NO_MEMORY;
    for (int c = 0; c < case_count; c++) {
        scaled(f, loads[c], offsets[c]);
        for (int k = 0; k < 3; k++)
            offsets[c][k] /= force;
    }
    int before = out->count;
    wr_status failure = WR_NO_MEMORY;
    bool ok = true;
    for (int e = first_edge; e < first_edge + edge_count && ok; e++) {
        if (wr_stop_requested(stop)) {
            failure = WR_STOPPED;
            ok = false;
            break;
        }
        ok = edge_loaded(a, set, (const double (*)[3])offsets, case_count, finger_radius, e,
                         stop, &failure, out);
    }
    free(offsets);
    if (!ok) {
        out->count = before;
        return failure;
    }
    return WR_OK;
}
