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
/* Sorts by lo: a point's few spans by insertion (qsort's set-up costs more
 * than the sort), many by qsort. */
static void sort_spans(spanlist *s)
{
    if (s->count > 16) {
        qsort(s->items, (size_t)s->count, sizeof *s->items, compare_lo);
        return;
    }
    for (int i = 1; i < s->count; i++) {
        wr_force_interval item = s->items[i];
        int j = i;
        for (; j > 0 && s->items[j - 1].lo > item.lo; j--)
            s->items[j] = s->items[j - 1];
        s->items[j] = item;
    }
}

static void gaps(spanlist *bad, double low, double high, double (*sliver)(double, double, double),
                 double sliver_arg, spanlist *good)
{
    sort_spans(bad);
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

/* Spans held on the stack before a call needs the heap: both sets' cones
 * for up to four fixels. */
#define STACK_SPANS 128

/* The good magnitudes in [lo, hi] of one set, from its cones' spans `bad`
 * (in s = F k; sorted here), into `out`.  WR_OK or WR_NO_MEMORY (out
 * empty). */
static wr_status good_forces(spanlist *bad, double k, double lo, double hi, wr_forces *out)
{
    double s_lo = lo * k, s_hi = hi * k;
    spanlist good = {0, out->capacity, out->items, false};
    gaps(bad, s_lo, s_hi, force_sliver, 0, &good);
    out->items = good.items;
    out->capacity = good.capacity;
    if (good.failed) {
        wr_forces_release(out);
        return WR_NO_MEMORY;
    }
    /* Back to magnitudes: the range's own ends exactly as given. */
    for (int i = 0; i < good.count; i++) {
        wr_force_interval *g = &good.items[i];
        g->lo = g->lo == s_lo ? lo : g->lo / k;
        g->hi = g->hi == s_hi ? hi : g->hi / k;
    }
    out->count = good.count;
    return WR_OK;
}

wr_status wr_force_ranges(const wr_analysis *a, const bool sets[3], const double load[3],
                          const double push[3], double lo, double hi, wr_forces out[3])
{
    for (int s = 0; s < 3; s++)
        if (sets[s])
            out[s].count = 0; /* its array is reused */
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
    /* Each cone's span once: goal's first, then strong's (both is all of
     * them), and room for every one in each set's copy. */
    int goal = wr_analysis_cone_count(a, WR_SET_GOAL);
    int count = goal + wr_analysis_cone_count(a, WR_SET_STRONG);
    wr_force_interval stack[2 * STACK_SPANS];
    wr_force_interval *spans = stack, *work = stack + STACK_SPANS;
    if (count + 1 > STACK_SPANS) {
        spans = malloc(2 * (size_t)(count + 1) * sizeof *spans);
        if (!spans)
            return WR_NO_MEMORY;
        work = spans + count + 1;
    }
    int found = 0, goal_found = 0;
    for (int i = 0; i < count; i++) {
        const wr_cone *cone = i < goal ? wr_analysis_cone(a, WR_SET_GOAL, i)
                                       : wr_analysis_cone(a, WR_SET_STRONG, i - goal);
        double s0, s1;
        if (!cone->empty) {
            wr_line_in_cone(cone, hl, hu, 2, &s0, &s1);
            s0 = fmax(s0, 0);
            if (s0 <= s1)
                spans[found++] = (wr_force_interval){s0, s1};
        }
        if (i + 1 == goal)
            goal_found = found;
    }
    if (goal == 0)
        goal_found = 0;
    wr_status status = WR_OK;
    for (int s = 0; status == WR_OK && s < 3; s++) {
        if (!sets[s])
            continue;
        int from = s == WR_SET_STRONG ? goal_found : 0, to = s == WR_SET_GOAL ? goal_found : found;
        spanlist bad = {0, count + 1, work, false};
        for (int i = from; i < to; i++)
            bad.items[bad.count++] = spans[i];
        /* s = 0 without a load is the zero wrench: on every cone's boundary. */
        if (!(nl > 0))
            span_add(&bad, 0, 0);
        assert(!bad.failed && bad.items == work); /* room for every cone and the zero wrench */
        status = good_forces(&bad, k, lo, hi, &out[s]);
    }
    if (spans != stack)
        free(spans);
    return status;
}

wr_status wr_force_range(const wr_analysis *a, wr_set set, const double load[3],
                         const double push[3], double lo, double hi, wr_forces *out)
{
    bool sets[3] = {false, false, false};
    wr_forces all[3] = {{0}};
    sets[set] = true;
    all[set] = *out;
    wr_status status = wr_force_ranges(a, sets, load, push, lo, hi, all);
    *out = all[set];
    return status;
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

/* The finger of the force paths: its radius and push_on (its friction is
 * not used: the push is along the inward normal). */
static bool finger_valid(const wr_finger *finger)
{
    return finger && finger->radius >= 0 && isfinite(finger->radius);
}

/* The regions of one edge (a circle: its one edge), appended to `out`. */
static bool edge_loaded(const wr_analysis *a, wr_set set, const double (*offsets)[3], int cases,
                        const wr_finger *finger, int edge, const wr_stop *stop,
                        wr_status *failure, wr_regions *out)
{
    const wr_fixture *f = wr_analysis_fixture(a);
    double radius = finger->radius;
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
                                 const double (*loads)[3], int case_count,
                                 const wr_finger *finger, int first_edge, int edge_count,
                                 const wr_stop *stop, wr_regions *out)
{
    const wr_fixture *f = wr_analysis_fixture(a);
    int edges = wr_push_edge_count(f);
    if (f->shape == WR_SHAPE_NONE)
        return WR_NO_SHAPE;
    if (!(force > 0) || !isfinite(force) || case_count < 1 || !finger_valid(finger) ||
        first_edge < 0 || edge_count < 0 ||
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
        /* A loop not pushed on has no region (push_on). */
        if (wr_finger_pushes_on(f, finger, e))
            ok = edge_loaded(a, set, (const double (*)[3])offsets, case_count, finger, e, stop,
                             &failure, out);
    }
    free(offsets);
    if (!ok) {
        out->count = before;
        return failure;
    }
    return WR_OK;
}

/* ---- the least force at a point, and its minimum over the outline ----------------- */

/* The closed spans of F >= 0 where load + F push is in some excluded cone
 * of the set, appended to `bad` in magnitudes; *unit_gap (may be NULL)
 * receives the magnitude that 1e-9 of is a sliver (|L| / |u|, scaled).
 * False for a zero or non-finite push. */
static bool bad_forces(const wr_analysis *a, wr_set set, const double load[3],
                       const double push[3], spanlist *bad, double *unit_gap)
{
    const wr_fixture *f = wr_analysis_fixture(a);
    double hl[3], hu[3];
    scaled(f, load, hl);
    scaled(f, push, hu);
    double nl = wr_normalize3(hl), nu = wr_normalize3(hu);
    if (!(nu > 0) || !isfinite(nl) || !isfinite(nu))
        return false;
    double k = nl > 0 ? nu / nl : nu; /* as wr_force_range: s = F k */
    if (unit_gap)
        *unit_gap = 1 / k;
    int count = set_cone_count(a, set);
    for (int i = 0; i < count; i++) {
        const wr_cone *cone = set_cone(a, set, i);
        if (cone->empty)
            continue;
        double s0, s1;
        wr_line_in_cone(cone, hl, hu, 2, &s0, &s1);
        if (s1 >= 0 && s0 <= s1)
            span_add(bad, fmax(s0, 0) / k, s1 / k);
    }
    if (!(nl > 0))
        span_add(bad, 0, 0);
    return true;
}

/* The end of the component of the union of `bad` (sorted here) that holds
 * 0, gaps no wider than 1e-9 of max(gap end, unit) closed; 0 when 0 is not
 * covered. */
static double covered_from_zero(spanlist *bad, double unit)
{
    sort_spans(bad);
    double end = 0;
    bool covered = false;
    for (int i = 0; i < bad->count; i++) {
        double lo = bad->items[i].lo, hi = bad->items[i].hi;
        double sliver = 1e-9 * fmax(isfinite(lo) ? lo : 0, unit);
        if (!covered) {
            if (lo > 0)
                break;
            covered = true;
            end = hi;
            continue;
        }
        if (lo > end + sliver)
            break;
        end = fmax(end, hi);
    }
    return end;
}

wr_status wr_least_force_at(const wr_analysis *a, wr_set set, const double (*loads)[3],
                            int case_count, const double push[3], double *force)
{
    spanlist bad = {0};
    double unit = 0;
    for (int c = 0; c < case_count; c++) {
        double gap;
        if (!finite3(loads[c]) || !bad_forces(a, set, loads[c], push, &bad, &gap)) {
            free(bad.items);
            return WR_INVALID;
        }
        unit = fmax(unit, gap);
    }
    if (bad.failed) {
        free(bad.items);
        return WR_NO_MEMORY;
    }
    /* An upper end at infinity: no magnitude is good. */
    *force = covered_from_zero(&bad, unit);
    free(bad.items);
    return WR_OK;
}

/* An edge's push, per unit force, as P cos phi + Q sin phi (arcs and the
 * circle, phi = (t - shift) * scale in radians, rows' values multiplied
 * by `s` > 0) or c1 + t c2 (lines). */
typedef struct edge_push {
    int edge;
    int kind;
    double c1[3], c2[3]; /* lines */
    double p[3], q[3], s; /* arcs and the circle */
    double shift, scale;  /* t -> phi */
    double size;          /* |c1| + |c2|: what counts as zero */
} edge_push;

static void edge_push_of(const wr_fixture *f, int edge, edge_push *e)
{
    wr_edge_frame frame;
    wr_edge_frame_of(f, edge, &frame);
    memset(e, 0, sizeof *e);
    e->edge = edge;
    e->kind = frame.kind;
    e->size = wr_norm3(frame.c1) + wr_norm3(frame.c2);
    if (frame.kind == WR_EDGE_LINE) {
        wr_copy3(frame.c1, e->c1);
        wr_copy3(frame.c2, e->c2);
    } else if (frame.kind == WR_EDGE_CIRCLE) {
        wr_copy3(frame.c1, e->p);
        wr_copy3(frame.c2, e->q);
        e->s = 1;
        e->shift = 0;
        e->scale = WR_PI / 180;
    } else {
        /* w = c1 sin(phi) / s + c2 cos(phi), phi = (2 t - 1) a: times s,
         * s c2 cos + c1 sin. */
        e->s = frame.half_angle_sin;
        for (int k = 0; k < 3; k++) {
            e->p[k] = e->s * frame.c2[k];
            e->q[k] = frame.c1[k];
        }
        e->shift = 0.5;
        e->scale = 2 * frame.half_angle;
    }
}

/* The range of the row f . (push per unit force, times s) over [t0, t1]. */
static void row_range(const edge_push *e, const double row[3], double t0, double t1, double *lo,
                      double *hi)
{
    if (e->kind == WR_EDGE_LINE) {
        double a = wr_dot3(row, e->c1), b = wr_dot3(row, e->c2);
        double x = a + b * t0, y = a + b * t1;
        *lo = fmin(x, y);
        *hi = fmax(x, y);
        return;
    }
    double P = wr_dot3(row, e->p), Q = wr_dot3(row, e->q);
    double f0 = (t0 - e->shift) * e->scale, f1 = (t1 - e->shift) * e->scale;
    double x = P * cos(f0) + Q * sin(f0), y = P * cos(f1) + Q * sin(f1);
    *lo = fmin(x, y);
    *hi = fmax(x, y);
    /* Turning points: where -P sin + Q cos = 0, a half turn apart, with
     * values +-hypot(P, Q). */
    double turn = atan2(Q, P), R = hypot(P, Q);
    for (int k = -3; k <= 3; k++) {
        double phi = turn + k * WR_PI;
        if (phi > f0 && phi < f1) {
            *lo = fmin(*lo, k % 2 == 0 ? R : -R);
            *hi = fmax(*hi, k % 2 == 0 ? R : -R);
        }
    }
}

/* A cone's magnitudes covered at every t of an interval T: [lo, hi]. */
typedef struct sure_span {
    double lo, hi;
    int c, i; /* case, cone */
} sure_span;

typedef struct bound_work {
    int count, capacity;
    sure_span *items;
    bool failed;
} bound_work;

static int compare_sure(const void *a, const void *b)
{
    double x = ((const sure_span *)a)->lo, y = ((const sure_span *)b)->lo;
    return (x > y) - (x < y);
}

typedef struct bound_context {
    const wr_analysis *a;
    wr_set set;
    const double (*hl)[3];
    int cases;
    const edge_push *e;
    double t0, t1, s, zero, unit;
} bound_context;

/* Over T, the least of row r's upper bound -alpha / beta(t) (as an upper
 * row: INFINITY where it bounds nothing) and the greatest of its lower
 * bound (as a lower row: 0 where it bounds nothing).  False when somewhere
 * on T the row admits no F >= 0 at all (the cone holds nothing there). */
static bool row_bounds(const bound_context *x, int c, const double row[3], double *upper,
                       double *lower)
{
    double alpha = wr_dot3(row, x->hl[c]) * x->s, b0, b1;
    double zero_load = 1e-12 * wr_norm3(x->hl[c]) * x->s;
    row_range(x->e, row, x->t0, x->t1, &b0, &b1);
    *upper = INFINITY;
    *lower = 0;
    if (alpha <= zero_load) {
        /* The load meets the row: F <= |alpha| / beta where beta > 0,
         * nothing where beta <= 0 (a pole inside T harms nothing). */
        if (b1 > x->zero)
            *upper = fmax(-alpha, 0) / b1;
        return true;
    }
    if (b1 < -x->zero) {
        /* F >= alpha / |beta|: at most alpha / |b1| over T. */
        *lower = alpha / -b1;
        return true;
    }
    return false;
}

/* May cone A's and cone B's covered magnitudes be joined over T: at every
 * t is A's upper end at or above B's lower end?  Yes when each upper row of
 * A stays above each lower row of B over T, or the two are one plane met
 * from both sides (the same case, opposite rows: equal at every t). */
static bool bridge(const bound_context *x, const sure_span *A, const sure_span *B)
{
    const wr_cone *ca = set_cone(x->a, x->set, A->i), *cb = set_cone(x->a, x->set, B->i);
    for (int r = 0; r < ca->facet_count; r++) {
        double upper, unused;
        if (!row_bounds(x, A->c, ca->facets[r], &upper, &unused))
            return false;
        if (!(upper < INFINITY))
            continue;
        for (int q = 0; q < cb->facet_count; q++) {
            double lower, unused_upper;
            if (!row_bounds(x, B->c, cb->facets[q], &unused_upper, &lower))
                return false;
            if (upper >= lower)
                continue;
            if (A->c == B->c && wr_dot3(ca->facets[r], cb->facets[q]) <= -1 + 1e-12)
                continue;
            return false;
        }
    }
    return true;
}

/* The end of the component holding 0 of what is covered at every t of T,
 * the spans sorted here; bridges join cones that meet along one plane. */
static double covered_surely(const bound_context *x, bound_work *w)
{
    if (w->count > 0)
        qsort(w->items, (size_t)w->count, sizeof *w->items, compare_sure);
    if (w->count == 0 || w->items[0].lo > 0)
        return 0;
    double end = 0;
    int members = 0; /* w->items[0, members) are in the component */
    for (;;) {
        /* Merge what overlaps (up to a sliver) the component. */
        bool grew = false;
        for (int i = members; i < w->count; i++) {
            double sliver = 1e-9 * fmax(w->items[i].lo, x->unit);
            if (w->items[i].lo > end + sliver)
                break;
            end = fmax(end, w->items[i].hi);
            members = i + 1;
            grew = true;
        }
        if (members == w->count)
            return end;
        /* A bridge from a member to a later span: the nearest few. */
        for (int j = members; j < w->count && j < members + 8 && !grew; j++)
            for (int m = 0; m < members && !grew; m++) {
                if (!bridge(x, &w->items[m], &w->items[j]))
                    continue;
                end = fmax(end, w->items[j].hi);
                /* j joins: moved next to the members, order kept after. */
                sure_span joined = w->items[j];
                memmove(&w->items[members + 1], &w->items[members],
                        (size_t)(j - members) * sizeof *w->items);
                w->items[members++] = joined;
                grew = true;
            }
        if (!grew)
            return end;
    }
}

static double bound_over(const wr_analysis *a, wr_set set, const double (*hl)[3], int cases,
                         const edge_push *e, double t0, double t1, double unit, bound_work *w)
{
    bound_context x = {a, set, hl, cases, e, t0, t1, e->kind == WR_EDGE_LINE ? 1 : e->s,
                       1e-12 * e->size, unit};
    w->count = 0;
    int count = set_cone_count(a, set);
    for (int c = 0; c < cases; c++)
        for (int i = 0; i < count; i++) {
            const wr_cone *cone = set_cone(a, set, i);
            if (cone->empty || cone->dimension < 3)
                continue;
            double lo = 0, hi = INFINITY;
            bool holds = true;
            for (int r = 0; r < cone->facet_count && holds && lo <= hi; r++) {
                double upper, lower;
                holds = row_bounds(&x, c, cone->facets[r], &upper, &lower);
                hi = fmin(hi, upper);
                lo = fmax(lo, lower);
            }
            if (!holds || !(lo <= hi))
                continue;
            if (w->count == w->capacity) {
                int capacity = w->capacity ? 2 * w->capacity : 64;
                sure_span *grown = realloc(w->items, (size_t)capacity * sizeof *grown);
                if (!grown) {
                    w->failed = true;
                    return 0;
                }
                w->items = grown;
                w->capacity = capacity;
            }
            w->items[w->count++] = (sure_span){lo, hi, c, i};
        }
    return covered_surely(&x, w);
}

typedef struct bb_item {
    double bound;
    int edge;
    double t0, t1;
} bb_item;

typedef struct bb_heap {
    int count, capacity;
    bb_item *items;
} bb_heap;

static bool heap_push(bb_heap *h, bb_item item)
{
    if (h->count == h->capacity) {
        int capacity = h->capacity ? 2 * h->capacity : 64;
        bb_item *grown = realloc(h->items, (size_t)capacity * sizeof *grown);
        if (!grown)
            return false;
        h->items = grown;
        h->capacity = capacity;
    }
    int i = h->count++;
    while (i > 0 && h->items[(i - 1) / 2].bound > item.bound) {
        h->items[i] = h->items[(i - 1) / 2];
        i = (i - 1) / 2;
    }
    h->items[i] = item;
    return true;
}

static bb_item heap_pop(bb_heap *h)
{
    bb_item top = h->items[0], last = h->items[--h->count];
    int i = 0;
    for (;;) {
        int child = 2 * i + 1;
        if (child >= h->count)
            break;
        if (child + 1 < h->count && h->items[child + 1].bound < h->items[child].bound)
            child++;
        if (h->items[child].bound >= last.bound)
            break;
        h->items[i] = h->items[child];
        i = child;
    }
    if (h->count > 0)
        h->items[i] = last;
    return top;
}

/* A bound at least this close to the best F* found needs no more work
 * (none while nothing finite is found). */
static double enough(double best)
{
    return isfinite(best) ? best - WR_FORCE_TOLERANCE * best : INFINITY;
}

/* Initial intervals per reachable span of an edge. */
#define BB_START 8

wr_status wr_least_force_find(const wr_analysis *a, wr_set set, const double (*loads)[3],
                              int case_count, const wr_finger *finger, const wr_stop *stop,
                              wr_least_force *out)
{
    memset(out, 0, sizeof *out);
    out->force = out->lower = INFINITY;
    const wr_fixture *f = wr_analysis_fixture(a);
    if (f->shape == WR_SHAPE_NONE)
        return WR_NO_SHAPE;
    if (case_count < 1 || !finger_valid(finger))
        return WR_INVALID;
    double finger_radius = finger->radius;
    double (*hl)[3] = malloc((size_t)case_count * sizeof *hl);
    if (!hl)
        return WR_NO_MEMORY;
    double unit = 0;
    for (int c = 0; c < case_count; c++) {
        if (!finite3(loads[c])) {
            free(hl);
            return WR_INVALID;
        }
        scaled(f, loads[c], hl[c]);
        unit = fmax(unit, wr_norm3(hl[c]));
    }
    unit = unit > 0 ? unit : 1;
    int edges = wr_push_edge_count(f);
    edge_push *pushes = calloc((size_t)edges, sizeof *pushes);
    bb_heap heap = {0};
    bound_work sure = {0};
    wr_status status = pushes ? WR_OK : WR_NO_MEMORY;
    double best = INFINITY;
    /* F* at (edge, t): the upper bound, and the answer where it is least. */
#define EVALUATE(E, T)                                                                       \
    do {                                                                                     \
        double w_[3], least_;                                                                \
        wr_push_wrench(f, (E), (T), w_);                                                     \
        wr_status s_ = wr_least_force_at(a, set, (const double (*)[3])loads, case_count, w_,  \
                                         &least_);                                           \
        out->evaluations++;                                                                  \
        if (s_ != WR_OK)                                                                     \
            status = s_;                                                                     \
        else if (least_ < best) {                                                            \
            best = least_;                                                                   \
            out->edge = (E);                                                                 \
            out->t = (T);                                                                    \
        }                                                                                    \
    } while (0)
    double top = f->shape == WR_SHAPE_CIRCLE ? 360 : 1;
    for (int e = 0; status == WR_OK && e < edges; e++) {
        edge_push_of(f, e, &pushes[e]);
        spanlist reach = {0};
        if (!wr_finger_pushes_on(f, finger, e)) {
            /* A loop not pushed on (push_on): nothing of this edge is reached. */
        } else if (finger_radius > 0 && f->shape != WR_SHAPE_CIRCLE) {
            size_t loop, segment;
            wr_push_edge_place(f, e, &loop, &segment);
            wr_span *items = NULL;
            int n = 0;
            status = wr_finger_blocked(f->outline, loop, segment, finger_radius, stop, &items, &n);
            spanlist blocked = {0};
            for (int i = 0; i < n; i++)
                span_add(&blocked, items[i].lo, items[i].hi);
            free(items);
            if (status == WR_OK)
                gaps(&blocked, 0, 1, range_sliver, 1, &reach);
            if (blocked.failed)
                status = WR_NO_MEMORY;
            free(blocked.items);
        } else {
            span_add(&reach, 0, top);
        }
        if (reach.failed)
            status = WR_NO_MEMORY;
        for (int r = 0; status == WR_OK && r < reach.count; r++) {
            double lo = reach.items[r].lo, hi = reach.items[r].hi;
            for (int i = 0; status == WR_OK && i < BB_START; i++) {
                double t0 = lo + (hi - lo) * i / BB_START, t1 = lo + (hi - lo) * (i + 1) / BB_START;
                EVALUATE(e, (t0 + t1) / 2);
                double bound = bound_over(a, set, (const double (*)[3])hl, case_count, &pushes[e],
                                          t0, t1, unit, &sure);
                if (!heap_push(&heap, (bb_item){bound, e, t0, t1}))
                    status = WR_NO_MEMORY;
            }
        }
        free(reach.items);
    }
    bool converged = true;
    while (status == WR_OK && heap.count > 0) {
        if (sure.failed) {
            status = WR_NO_MEMORY;
            break;
        }
        bb_item item = heap_pop(&heap);
        if (item.bound >= enough(best) || !(item.bound < INFINITY)) {
            heap_push(&heap, item); /* the lowest bound left: the certificate */
            break;
        }
        if (out->evaluations >= WR_FORCE_MAX_EVALUATIONS ||
            item.t1 - item.t0 <= 1e-15 * top) {
            converged = false;
            heap_push(&heap, item);
            break;
        }
        if ((out->evaluations & 255) == 0 && wr_stop_requested(stop)) {
            status = WR_STOPPED;
            break;
        }
        double mid = (item.t0 + item.t1) / 2;
        EVALUATE(item.edge, mid);
        for (int half = 0; status == WR_OK && half < 2; half++) {
            double t0 = half ? mid : item.t0, t1 = half ? item.t1 : mid;
            double bound = bound_over(a, set, (const double (*)[3])hl, case_count,
                                      &pushes[item.edge], t0, t1, unit, &sure);
            bound = fmax(bound, item.bound); /* a part's bound is at least its whole's */
            if (bound < enough(best) &&
                !heap_push(&heap, (bb_item){bound, item.edge, t0, t1}))
                status = WR_NO_MEMORY;
        }
    }
#undef EVALUATE
    if (status == WR_OK) {
        /* Pruned intervals are certified down to enough(best). */
        double lower = fmin(best, enough(best));
        for (int i = 0; i < heap.count; i++)
            lower = fmin(lower, heap.items[i].bound);
        out->found = isfinite(best);
        out->force = best;
        out->lower = lower;
        out->converged = converged;
        if (out->found) {
            wr_boundary_point(f, out->edge, out->t, out->at, out->direction);
        }
    }
    free(heap.items);
    free(sure.items);
    free(pushes);
    free(hl);
    return status;
}
