/* wr_lattice.c -- designs on a modular fixture plate (wr_lattice.h). */
#include "wr_lattice.h"
#include "wr_internal.h"
#include "wr_outline.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

/* A segment's offset curve at the peg radius, in the part's frame: where a
 * peg's centre is when the peg touches the segment from outside. */
typedef struct curve {
    int edge;
    bool line;
    /* line: the segment a-b, its outward unit normal n; n . q = c on the
     * offset line */
    double a[2], b[2], n[2], c;
    /* arc: centre, the arc's radius, the offset radius rho; the arc's
     * start angle and signed sweep; material inside the circle or not */
    double center[2], radius, rho, start_angle, sweep;
    bool inside;
    /* a circle holding the whole offset curve (for pruning) */
    double hull_center[2], hull_radius;
} curve;

typedef struct hole {
    int i, j;
    double at[2];
} hole;

typedef struct design_list {
    wr_lattice_design *items;
    size_t count, capacity;
} design_list;

struct wr_lattice_job {
    const wr_fixture *body;
    wr_lattice lattice;
    double reach;            /* no two peg centres are farther apart */
    double tolerance;        /* of lengths: 1e-9 of the part's size */
    curve *curves;
    int curve_count;
    hole *holes;             /* after (0, 0) in (j, i) order, within reach */
    size_t hole_count;
    size_t pair_total;       /* (second, third) hole pairs, numbered in order */
    /* The units of work: a hole pair and the curves its first two pegs
     * touch, numbered (pair * curve_count + x) * curve_count + y, so that
     * a unit's work is the curves of the third peg, whatever the number of
     * holes. */
    size_t unit_total;
    size_t claimed;          /* units handed out as chunks */
    size_t merged;           /* units whose designs are in `found`, in order */
    int outstanding;         /* chunks claimed, not yet merged or abandoned */
    /* Finished chunks ahead of their turn (claimed later than one still
     * running): at most the chunks outstanding at once, a few. */
    wr_lattice_chunk *waiting;
    size_t waiting_count, waiting_capacity;
    design_list found;
    bool failed;
    bool scan;               /* poses with arcs by the theta scan (wr_lattice_job_scan) */
    double grid[WR_LATTICE_STEPS + 1][2]; /* cos, sin of the scan's angles */
};

static double cross2(const double a[2], const double b[2]) { return a[0] * b[1] - a[1] * b[0]; }
static double dot2(const double a[2], const double b[2]) { return a[0] * b[0] + a[1] * b[1]; }

/* R(-theta) p: a plate point seen from the part's frame, before the
 * translation; theta given by its cosine and sine. */
static void unrotate_cs(const double p[2], double c, double s, double out[2])
{
    out[0] = c * p[0] + s * p[1];
    out[1] = -s * p[0] + c * p[1];
}

static void unrotate(const double p[2], double theta, double out[2])
{
    unrotate_cs(p, cos(theta), sin(theta), out);
}

static bool build_curves(wr_lattice_job *job)
{
    const wr_outline *o = job->body->outline;
    size_t total = 0;
    for (size_t l = 0; l < o->loop_count; l++)
        total += o->loops[l].segment_count;
    job->curves = calloc(total ? total : 1, sizeof *job->curves);
    if (!job->curves)
        return false;
    double r = job->lattice.peg_radius;
    int edge = 0;
    for (size_t l = 0; l < o->loop_count; l++)
        for (size_t s = 0; s < o->loops[l].segment_count; s++, edge++) {
            const wr_segment *g = &o->loops[l].segments[s];
            double mid[2], inward[2];
            wr_outline_boundary(o, l, s, 0.5, mid, inward);
            curve *k = &job->curves[job->curve_count];
            k->edge = edge;
            if (g->bulge == 0) {
                k->line = true;
                memcpy(k->a, g->start, sizeof k->a);
                memcpy(k->b, g->end, sizeof k->b);
                k->n[0] = -inward[0];
                k->n[1] = -inward[1];
                k->c = dot2(k->n, k->a) + r;
                for (int d = 0; d < 2; d++)
                    k->hull_center[d] = (g->start[d] + g->end[d]) / 2 + r * k->n[d];
                k->hull_radius = g->length / 2;
            } else {
                k->line = false;
                memcpy(k->center, g->center, sizeof k->center);
                k->radius = g->radius;
                k->start_angle = g->start_angle;
                k->sweep = g->sweep;
                double to_center[2] = {g->center[0] - mid[0], g->center[1] - mid[1]};
                k->inside = dot2(inward, to_center) > 0;
                k->rho = k->inside ? g->radius + r : g->radius - r;
                if (k->rho <= job->tolerance)
                    continue; /* a peg wider than the hole or the fillet: never touches it */
                memcpy(k->hull_center, g->center, sizeof k->hull_center);
                k->hull_radius = k->rho;
            }
            job->curve_count++;
        }
    return true;
}

static bool build_holes(wr_lattice_job *job)
{
    const wr_lattice *L = &job->lattice;
    int nx = L->extent[0], ny = L->extent[1];
    /* Only holes within reach of (0, 0): counted first, so that a fine
     * lattice's far holes cost nothing. */
    int reach_i = (int)fmin(nx - 1, floor(job->reach / L->pitch));
    int reach_j = (int)fmin(ny - 1, floor(job->reach / L->pitch));
    for (int pass = 0; pass < 2; pass++) {
        size_t count = 0;
        for (int j = 0; j <= reach_j; j++)
            for (int i = -reach_i; i <= reach_i; i++) {
                if (j == 0 && i <= 0)
                    continue; /* (0, 0) is the first peg's; the others come after it */
                double at[2] = {L->pitch * i, L->pitch * j};
                if (hypot(at[0], at[1]) > job->reach)
                    continue;
                if (pass == 1)
                    job->holes[count] = (hole){i, j, {at[0], at[1]}};
                count++;
            }
        if (pass == 0) {
            if (count > WR_LATTICE_MAX_HOLES) {
                job->hole_count = count;
                return true; /* the caller refuses it */
            }
            job->holes = calloc(count ? count : 1, sizeof *job->holes);
            if (!job->holes)
                return false;
        }
        job->hole_count = count;
    }
    job->pair_total = job->hole_count * (job->hole_count ? job->hole_count - 1 : 0) / 2;
    job->unit_total = job->pair_total * (size_t)job->curve_count * (size_t)job->curve_count;
    return true;
}

wr_status wr_lattice_job_new(const wr_fixture *body, const wr_lattice *lattice,
                             wr_lattice_job **out, wr_error *error)
{
    *out = NULL;
    if (!body->outline) {
        wr_error_set(error, "", "a lattice design needs a polygon or an outline (a circle "
                                "touches every peg along its own normal line)");
        return WR_INVALID;
    }
    if (!(lattice->pitch > 0) || !isfinite(lattice->pitch) ||
        lattice->pitch < body->size * 1e-6) {
        wr_error_set(error, "pitch", "must be a positive length above 1e-6 of the part's size");
        return WR_INVALID;
    }
    if (!(lattice->peg_radius >= 0) || !isfinite(lattice->peg_radius) ||
        lattice->peg_radius >= lattice->pitch / 2) {
        wr_error_set(error, "peg_radius", "must be at least 0 and below half the pitch");
        return WR_INVALID;
    }
    if (lattice->extent[0] < 1 || lattice->extent[1] < 1 ||
        lattice->extent[0] > WR_LATTICE_MAX_EXTENT || lattice->extent[1] > WR_LATTICE_MAX_EXTENT) {
        wr_error_set(error, "extent", "must be [nx, ny], whole numbers from 1 to %d",
                     WR_LATTICE_MAX_EXTENT);
        return WR_INVALID;
    }
    wr_lattice_job *job = calloc(1, sizeof *job);
    if (!job) {
        wr_error_set(error, "", "out of memory");
        return WR_NO_MEMORY;
    }
    job->body = body;
    job->lattice = *lattice;
    for (int i = 0; i <= WR_LATTICE_STEPS; i++) {
        double theta = 2 * WR_PI * i / WR_LATTICE_STEPS;
        job->grid[i][0] = cos(theta);
        job->grid[i][1] = sin(theta);
    }
    job->tolerance = 1e-9 * body->size;
    /* Every peg centre lies within r of the part, so within the circle
     * about its bounding box's centre of radius size / 2 + r. */
    job->reach = body->size + 2 * lattice->peg_radius + job->tolerance;
    if (!build_curves(job) || !build_holes(job)) {
        wr_lattice_job_free(job);
        wr_error_set(error, "", "out of memory");
        return WR_NO_MEMORY;
    }
    if (job->hole_count > WR_LATTICE_MAX_HOLES) {
        wr_error_set(error, "pitch",
                     "gives %zu holes within reach of a peg across the part, more than %d: "
                     "the pitch is too fine for a part this size",
                     job->hole_count, WR_LATTICE_MAX_HOLES);
        wr_lattice_job_free(job);
        return WR_INVALID;
    }
    *out = job;
    return WR_OK;
}

/* ---- one pose ----------------------------------------------------------------------- */

/* The residual of peg centre q on curve k: signed distance to the full
 * offset line or circle. */
static double residual(const curve *k, const double q[2])
{
    if (k->line)
        return dot2(k->n, q) - k->c;
    return hypot(q[0] - k->center[0], q[1] - k->center[1]) - k->rho;
}

/* Is the contact of a peg centred at q on curve k on the segment itself?
 * The contact point and inward normal into at and normal. */
static bool contact_on_segment(const wr_lattice_job *job, const curve *k, const double q[2],
                               double at[2], double normal[2])
{
    const double eps = 1e-9;
    double r = job->lattice.peg_radius;
    if (k->line) {
        double d[2] = {k->b[0] - k->a[0], k->b[1] - k->a[1]};
        double foot[2] = {q[0] - r * k->n[0], q[1] - r * k->n[1]};
        double rel[2] = {foot[0] - k->a[0], foot[1] - k->a[1]};
        double s = dot2(rel, d) / dot2(d, d);
        if (s < -eps || s > 1 + eps)
            return false;
        s = fmin(1, fmax(0, s));
        at[0] = k->a[0] + s * d[0];
        at[1] = k->a[1] + s * d[1];
        normal[0] = -k->n[0];
        normal[1] = -k->n[1];
        return true;
    }
    double v[2] = {q[0] - k->center[0], q[1] - k->center[1]};
    double length = hypot(v[0], v[1]);
    if (!(length > 0))
        return false;
    double u[2] = {v[0] / length, v[1] / length};
    double angle = atan2(u[1], u[0]) - k->start_angle;
    double span = fabs(k->sweep);
    if (k->sweep < 0)
        angle = -angle;
    angle = fmod(angle, 2 * WR_PI);
    if (angle < 0)
        angle += 2 * WR_PI;
    if (angle > span + eps && angle < 2 * WR_PI - eps)
        return false;
    at[0] = k->center[0] + k->radius * u[0];
    at[1] = k->center[1] + k->radius * u[1];
    normal[0] = k->inside ? -u[0] : u[0];
    normal[1] = k->inside ? -u[1] : u[1];
    return true;
}

static bool add_design(const wr_lattice_job *job, design_list *list, const wr_lattice_design *d)
{
    /* The same holes and pose from another assignment (a peg on a vertex
     * touches both its segments): one design. */
    for (size_t i = list->count; i-- > 0;) {
        const wr_lattice_design *e = &list->items[i];
        if (memcmp(e->holes, d->holes, sizeof d->holes) != 0)
            break; /* designs of one hole triple are consecutive */
        double dtheta = fabs(remainder(e->pose[2] - d->pose[2], 2 * WR_PI));
        if (dtheta <= 1e-9 && hypot(e->pose[0] - d->pose[0], e->pose[1] - d->pose[1]) <=
                                  1e-7 * job->body->size)
            return true;
    }
    if (list->count >= WR_LATTICE_MAX_DESIGNS)
        return true; /* more than any search would take: the rest are dropped */
    if (list->count == list->capacity) {
        size_t grown = list->capacity ? 2 * list->capacity : 16;
        wr_lattice_design *more = realloc(list->items, grown * sizeof *more);
        if (!more)
            return false;
        list->items = more;
        list->capacity = grown;
    }
    list->items[list->count++] = *d;
    return true;
}

/* Check a pose (theta, tau: the translation seen in the part's frame) of
 * the part against pegs at P with curves k, and keep it. */
static bool try_pose(const wr_lattice_job *job, design_list *out, const hole *const P[3],
                     const curve *const k[3], double theta, const double tau[2])
{
    wr_lattice_design d;
    memset(&d, 0, sizeof d);
    double r = job->lattice.peg_radius;
    const wr_outline *o = job->body->outline;
    for (int m = 0; m < 3; m++) {
        double p[2], q[2];
        unrotate(P[m]->at, theta, p);
        q[0] = p[0] - tau[0];
        q[1] = p[1] - tau[1];
        if (fabs(residual(k[m], q)) > 1e-7 * job->body->size)
            return true;
        if (!contact_on_segment(job, k[m], q, d.at[m], d.normal[m]))
            return true;
        /* Touching is not overlapping: the peg's centre outside the
         * material, at least its radius from every segment. */
        if (wr_outline_contains(o, q, job->tolerance) ||
            wr_outline_distance(o, q) < r - 1e-7 * job->body->size)
            return true;
        d.holes[m][0] = P[m]->i;
        d.holes[m][1] = P[m]->j;
        d.edges[m] = k[m]->edge;
    }
    theta = fmod(theta, 2 * WR_PI);
    if (theta < 0)
        theta += 2 * WR_PI;
    double c = cos(theta), s = sin(theta);
    d.pose[0] = c * tau[0] - s * tau[1];
    d.pose[1] = s * tau[0] + c * tau[1];
    d.pose[2] = theta;
    return add_design(job, out, &d);
}

/* Three lines: sum_m lambda_m n_m = 0 with lambda from cross products, so
 * sum_m lambda_m (n_m . p_m(theta) - c_m) = 0, that is A cos + B sin = C. */
static bool three_lines(const wr_lattice_job *job, design_list *out, const hole *const P[3],
                        const curve *const k[3])
{
    double lambda[3] = {cross2(k[1]->n, k[2]->n), cross2(k[2]->n, k[0]->n),
                        cross2(k[0]->n, k[1]->n)};
    if (fabs(lambda[0]) + fabs(lambda[1]) + fabs(lambda[2]) < 1e-9)
        return true; /* all parallel: the part slides along them, no pose is fixed */
    double A = 0, B = 0, C = 0;
    for (int m = 0; m < 3; m++) {
        double perp[2] = {-k[m]->n[1], k[m]->n[0]};
        A += lambda[m] * dot2(k[m]->n, P[m]->at);
        B += lambda[m] * dot2(perp, P[m]->at);
        C += lambda[m] * k[m]->c;
    }
    double R = hypot(A, B);
    if (!(R > 0) || fabs(C) > R * (1 + 1e-12))
        return true;
    double phi = atan2(B, A), delta = acos(fmax(-1, fmin(1, C / R)));
    int count = delta < 1e-12 ? 1 : 2;
    /* The translation from the two lines whose normals are farthest from
     * parallel. */
    int u = 0, v = 1;
    double best = fabs(lambda[2]);
    if (fabs(lambda[0]) > best) {
        u = 1, v = 2;
        best = fabs(lambda[0]);
    }
    if (fabs(lambda[1]) > best) {
        u = 2, v = 0;
        best = fabs(lambda[1]);
    }
    for (int e = 0; e < count; e++) {
        double theta = phi + (e ? -delta : delta);
        double pu[2], pv[2];
        unrotate(P[u]->at, theta, pu);
        unrotate(P[v]->at, theta, pv);
        double bu = dot2(k[u]->n, pu) - k[u]->c, bv = dot2(k[v]->n, pv) - k[v]->c;
        double det = cross2(k[u]->n, k[v]->n);
        double tau[2] = {(bu * k[v]->n[1] - bv * k[u]->n[1]) / det,
                         (k[u]->n[0] * bv - k[v]->n[0] * bu) / det};
        if (!try_pose(job, out, P, k, theta, tau))
            return false;
    }
    return true;
}

/* With an arc: the translation from the first two curves (lines first),
 * branch 0 or 1 of a circle's two points; false where it has none. */
static bool solve_two(const hole *const P[3], const curve *const k[3], double c, double s,
                      int branch, double tau[2])
{
    double p0[2], p1[2];
    unrotate_cs(P[0]->at, c, s, p0);
    unrotate_cs(P[1]->at, c, s, p1);
    if (k[0]->line && k[1]->line) {
        double b0 = dot2(k[0]->n, p0) - k[0]->c, b1 = dot2(k[1]->n, p1) - k[1]->c;
        double det = cross2(k[0]->n, k[1]->n);
        if (fabs(det) < 1e-9 || branch)
            return false;
        tau[0] = (b0 * k[1]->n[1] - b1 * k[0]->n[1]) / det;
        tau[1] = (k[0]->n[0] * b1 - k[1]->n[0] * b0) / det;
        return true;
    }
    /* The circle: tau on the circle about m1 = p1 - C of radius rho. */
    double m1[2] = {p1[0] - k[1]->center[0], p1[1] - k[1]->center[1]};
    double sign = branch ? -1 : 1;
    if (k[0]->line) {
        /* n . tau = v: tau = v n + s n_perp. */
        double v = dot2(k[0]->n, p0) - k[0]->c;
        double perp[2] = {-k[0]->n[1], k[0]->n[0]};
        double off = v - dot2(k[0]->n, m1);
        double h2 = k[1]->rho * k[1]->rho - off * off;
        if (h2 < 0)
            return false;
        double s = dot2(perp, m1) + sign * sqrt(h2);
        tau[0] = v * k[0]->n[0] + s * perp[0];
        tau[1] = v * k[0]->n[1] + s * perp[1];
        return true;
    }
    double m0[2] = {p0[0] - k[0]->center[0], p0[1] - k[0]->center[1]};
    double d[2] = {m1[0] - m0[0], m1[1] - m0[1]};
    double D = hypot(d[0], d[1]);
    if (!(D > 0))
        return false;
    double r0 = k[0]->rho, r1 = k[1]->rho;
    double along = (D * D + r0 * r0 - r1 * r1) / (2 * D);
    double h2 = r0 * r0 - along * along;
    if (h2 < 0)
        return false;
    double h = sign * sqrt(h2);
    tau[0] = m0[0] + (along * d[0] - h * d[1]) / D;
    tau[1] = m0[1] + (along * d[1] + h * d[0]) / D;
    return true;
}

static double residual_cs(const hole *const P[3], const curve *const k[3], double c, double s,
                          int branch, double tau[2])
{
    if (!solve_two(P, k, c, s, branch, tau))
        return NAN;
    double p2[2], q[2];
    unrotate_cs(P[2]->at, c, s, p2);
    q[0] = p2[0] - tau[0];
    q[1] = p2[1] - tau[1];
    return residual(k[2], q);
}

static double third_residual(const hole *const P[3], const curve *const k[3], double theta,
                             int branch, double tau[2])
{
    return residual_cs(P, k, cos(theta), sin(theta), branch, tau);
}

/* Q, K: the holes and curves with the lines first, to solve with; P, k:
 * as the design has them. */
static bool with_arcs(const wr_lattice_job *job, design_list *out, const hole *const Q[3],
                      const curve *const K[3], const hole *const P[3], const curve *const k[3])
{
    const int n = WR_LATTICE_STEPS;
    const double step = 2 * WR_PI / n;
    double tau[2];
    for (int branch = 0; branch < 2; branch++) {
        if (branch && K[0]->line && K[1]->line)
            break;
        double f[WR_LATTICE_STEPS + 1];
        for (int i = 0; i <= n; i++)
            f[i] = residual_cs(Q, K, job->grid[i][0], job->grid[i][1], branch, tau);
        for (int i = 0; i < n; i++) {
            double lo = i * step, hi = lo + step, flo = f[i], fhi = f[i + 1];
            if (isnan(flo) || isnan(fhi))
                continue;
            bool root = (flo <= 0) != (fhi <= 0) || flo == 0;
            bool touch = false;
            if (!root && i > 0 && !isnan(f[i - 1]) && fabs(flo) <= fabs(f[i - 1]) &&
                fabs(flo) <= fabs(fhi) && fabs(flo) < 0.05 * job->body->size) {
                /* A small local minimum of |f|: perhaps a touch of zero. */
                double a = lo - step, b = hi;
                const double g = (sqrt(5) - 1) / 2;
                for (int it = 0; it < 100; it++) {
                    double c = b - g * (b - a), e = a + g * (b - a);
                    double fc = fabs(third_residual(Q, K, c, branch, tau));
                    double fe = fabs(third_residual(Q, K, e, branch, tau));
                    if (!(fc > fe))
                        b = e;
                    else
                        a = c;
                }
                lo = (a + b) / 2;
                double fm = third_residual(Q, K, lo, branch, tau);
                touch = fabs(fm) <= 1e-9 * job->body->size;
            }
            if (root) {
                for (int it = 0; it < 100 && hi - lo > 1e-15; it++) {
                    double mid = (lo + hi) / 2, fm = third_residual(Q, K, mid, branch, tau);
                    if (isnan(fm))
                        break;
                    if ((fm <= 0) == (flo <= 0)) {
                        lo = mid;
                        flo = fm;
                    } else {
                        hi = mid;
                    }
                }
            }
            if (root || touch) {
                double theta = root ? (lo + hi) / 2 : lo;
                if (!isnan(third_residual(Q, K, theta, branch, tau)) &&
                    !try_pose(job, out, P, k, theta, tau))
                    return false;
            }
        }
    }
    return true;
}

/* ---- exact poses with arcs: a polynomial in t = tan(theta / 2) ------------------------
 *
 * docs/MODEL.md ("Lattice poses with arcs") derives it.  With
 * c = (1 - t^2) / (1 + t^2) and s = 2 t / (1 + t^2), a quantity linear in
 * (c, s, 1) is a quadratic in t over (1 + t^2); products add the powers of
 * the denominator, and an equation's terms are brought to one power before
 * its numerator is taken.  Two lines and an arc give a quartic, a line and
 * two arcs degree 8, three arcs degree 12. */
#define TRIG_TERMS 13

typedef struct trig {
    int den;                 /* the value is sum c[i] t^i / (1 + t^2)^den */
    double c[TRIG_TERMS];    /* degree at most 2 den */
} trig;

/* a cos + b sin + e. */
static trig trig_linear(double a, double b, double e)
{
    trig x = {1, {a + e, 2 * b, e - a}};
    return x;
}

static trig trig_constant(double e)
{
    trig x = {0, {e}};
    return x;
}

/* x times (1 + t^2)^k: the same value at a higher power. */
static trig trig_raise(trig x, int k)
{
    for (; k > 0; k--) {
        trig y = {x.den + 1, {0}};
        for (int i = 0; i <= 2 * x.den; i++) {
            y.c[i] += x.c[i];
            y.c[i + 2] += x.c[i];
        }
        x = y;
    }
    return x;
}

static trig trig_add(trig x, trig y, double sign)
{
    if (x.den < y.den)
        x = trig_raise(x, y.den - x.den);
    else
        y = trig_raise(y, x.den - y.den);
    for (int i = 0; i <= 2 * x.den; i++)
        x.c[i] += sign * y.c[i];
    return x;
}

static trig trig_mul(trig x, trig y)
{
    trig z = {x.den + y.den, {0}};
    for (int i = 0; i <= 2 * x.den; i++)
        for (int j = 0; j <= 2 * y.den; j++)
            z.c[i + j] += x.c[i] * y.c[j];
    return z;
}

/* A vector of two such quantities. */
typedef struct trig2 {
    trig x, y;
} trig2;

static trig trig_dot(trig2 u, trig2 v) { return trig_add(trig_mul(u.x, v.x), trig_mul(u.y, v.y), 1); }

/* p(theta) = R(-theta) P - C: the plate point P seen from the part, less
 * C, linear in (c, s, 1). */
static trig2 seen(const double P[2], const double C[2])
{
    trig2 v = {trig_linear(P[0], P[1], -C[0]), trig_linear(P[1], -P[0], -C[1])};
    return v;
}

/* sum c[i] x^i. */
static double poly_at(const double *c, int degree, double x)
{
    double value = 0;
    for (int i = degree; i >= 0; i--)
        value = value * x + c[i];
    return value;
}

/* The real roots of the polynomial in [-1, 1], into roots (at most degree
 * of them), each once: between consecutive roots of its derivative (found
 * the same way) the polynomial is monotone, so a change of sign there is
 * one root, found by false position with the Illinois step; a root of the
 * derivative where the polynomial is zero to rounding is a double root (a
 * curve touched, not crossed). */
static int poly_roots(const double *c, int degree, double *roots)
{
    while (degree > 0 && c[degree] == 0)
        degree--;
    if (degree <= 0)
        return 0;
    if (degree == 1) {
        double x = -c[0] / c[1];
        roots[0] = x;
        return x >= -1 && x <= 1;
    }
    double derivative[TRIG_TERMS], critical[TRIG_TERMS + 1];
    for (int i = 1; i <= degree; i++)
        derivative[i - 1] = i * c[i];
    int n = 0;
    critical[n++] = -1;
    double inner[TRIG_TERMS];
    int m = poly_roots(derivative, degree - 1, inner);
    for (int i = 0; i < m; i++)
        critical[n++] = inner[i];
    critical[n++] = 1;
    /* Zero to rounding: against the largest value the terms can reach on
     * [-1, 1], not the terms at x (near x = 0 they would be c[0] alone). */
    double size = 0;
    for (int i = 0; i <= degree; i++)
        size += fabs(c[i]);
    double zero = 1e-9 * size;
    int found = 0;
    for (int i = 0; i < n; i++) {
        double x = critical[i], f = poly_at(c, degree, x);
        if (fabs(f) <= zero && (found == 0 || x > roots[found - 1])) {
            roots[found++] = x;
            continue;
        }
        if (i + 1 == n)
            break;
        double lo = x, hi = critical[i + 1], flo = f, fhi = poly_at(c, degree, hi);
        if (fabs(fhi) <= zero || (flo < 0) == (fhi < 0))
            continue; /* a root at hi is the next step's */
        int side = 0;
        for (int it = 0; it < 100 && hi - lo > 4e-16 * (1 + fabs(lo)); it++) {
            double mid = (lo * fhi - hi * flo) / (fhi - flo);
            if (!(mid > lo && mid < hi))
                mid = (lo + hi) / 2;
            double fm = poly_at(c, degree, mid);
            if (fabs(fm) <= 1e-15 * size) { /* zero to the evaluation's rounding */
                lo = hi = mid;
                break;
            }
            if ((fm < 0) == (flo < 0)) {
                lo = mid;
                flo = fm;
                if (side == -1)
                    fhi /= 2;
                side = -1;
            } else {
                hi = mid;
                fhi = fm;
                if (side == 1)
                    flo /= 2;
                side = 1;
            }
        }
        roots[found++] = (lo + hi) / 2;
    }
    return found;
}

/* The angles theta where the numerator of e vanishes: its roots t in
 * [-1, 1] (|theta| <= pi/2) and, for the rest of the circle, the roots u
 * in [-1, 1] of the same polynomial reversed (u = 1 / t: theta beyond
 * pi/2 either way, u = 0 at theta = pi), so that no root is far out. */
static int trig_angles(const trig *e, double *thetas)
{
    int degree = 2 * e->den, count = 0;
    double reversed[TRIG_TERMS], roots[TRIG_TERMS];
    for (int i = 0; i <= degree; i++)
        reversed[i] = e->c[degree - i];
    int n = poly_roots(e->c, degree, roots);
    for (int i = 0; i < n; i++)
        thetas[count++] = 2 * atan(roots[i]);
    n = poly_roots(reversed, degree, roots);
    for (int i = 0; i < n; i++)
        thetas[count++] = roots[i] == 0 ? WR_PI : 2 * atan2(1, roots[i]);
    return count;
}

/* A root of the polynomial made a root of the geometry: Newton's steps on
 * the third curve's residual with the translation from the first two
 * (branch `branch`), while they shorten; the polynomial's coefficients
 * carry the rounding of their products, the residual does not.  A touch
 * (a double root) converges too, more slowly, to where the residual is
 * least. */
static double polish(const wr_lattice_job *job, const hole *const Q[3], const curve *const K[3],
                     double theta, int branch)
{
    double tau[2], last = INFINITY;
    for (int it = 0; it < 8; it++) {
        double f = third_residual(Q, K, theta, branch, tau);
        if (!(fabs(f) > 1e-15 * job->body->size))
            break;
        double h = 1e-7, g = third_residual(Q, K, theta + h, branch, tau);
        double step = f * h / (g - f);
        if (!isfinite(step) || fabs(step) > 1e-3 || fabs(step) >= last)
            break;
        theta -= step;
        last = fabs(step);
    }
    return theta;
}

/* The poses of the holes Q with curves K, lines first, each from a root
 * of one polynomial: the translation is eliminated between the three
 * equations (below), the roots are the angles, and at each the
 * translation is solved from the first two curves (both of a circle's
 * branches; try_pose keeps only what meets all three within its
 * tolerance).  P, k: as the design has them. */
static bool exact_arcs(const wr_lattice_job *job, design_list *out, const hole *const Q[3],
                       const curve *const K[3], const hole *const P[3], const curve *const k[3])
{
    static const double origin[2] = {0, 0};
    trig equation;
    if (K[0]->line && K[1]->line) {
        /* n_m . tau = n_m . p_m - c_m for the lines, tau by Cramer's rule,
         * then |p_2 - C_2 - tau|^2 = rho^2 (degree 4). */
        double det = cross2(K[0]->n, K[1]->n);
        if (fabs(det) < 1e-9)
            return true; /* parallel lines: no translation is fixed (solve_two) */
        trig2 p0 = seen(Q[0]->at, origin), p1 = seen(Q[1]->at, origin);
        trig b0 = trig_add(trig_add(trig_mul(trig_constant(K[0]->n[0]), p0.x),
                                    trig_mul(trig_constant(K[0]->n[1]), p0.y), 1),
                           trig_constant(K[0]->c), -1);
        trig b1 = trig_add(trig_add(trig_mul(trig_constant(K[1]->n[0]), p1.x),
                                    trig_mul(trig_constant(K[1]->n[1]), p1.y), 1),
                           trig_constant(K[1]->c), -1);
        trig2 tau = {trig_add(trig_mul(b0, trig_constant(K[1]->n[1] / det)),
                              trig_mul(b1, trig_constant(K[0]->n[1] / det)), -1),
                     trig_add(trig_mul(b1, trig_constant(K[0]->n[0] / det)),
                              trig_mul(b0, trig_constant(K[1]->n[0] / det)), -1)};
        trig2 w = seen(Q[2]->at, K[2]->center);
        w.x = trig_add(w.x, tau.x, -1);
        w.y = trig_add(w.y, tau.y, -1);
        equation = trig_add(trig_dot(w, w), trig_constant(K[2]->rho * K[2]->rho), -1);
    } else {
        /* Two linear equations in tau: the line's (when there is one) and
         * the difference of two circles' (|u_i - tau|^2 - |u_j - tau|^2 =
         * rho_i^2 - rho_j^2 with u = p - C, the |tau|^2 cancelling):
         * g . tau = h with g, h linear in (c, s, 1) or constant.  Then
         * tau = N / det, and the last circle's |u det - N|^2 =
         * rho^2 det^2 (degree 8 with a line, 12 without). */
        trig2 g[2];
        trig h[2];
        int first = 0, row = 0;
        if (K[0]->line) {
            trig2 p0 = seen(Q[0]->at, origin);
            g[0] = (trig2){trig_constant(K[0]->n[0]), trig_constant(K[0]->n[1])};
            h[0] = trig_add(trig_add(trig_mul(g[0].x, p0.x), trig_mul(g[0].y, p0.y), 1),
                            trig_constant(K[0]->c), -1);
            first = 1;
            row = 1;
        }
        /* Circles first .. 2: u_i = p_i - C_i, |u_i|^2 = |P_i|^2 +
         * |C_i|^2 - 2 C_i . p_i, linear in (c, s, 1). */
        trig2 u[3];
        trig norm2[3];
        for (int i = first; i < 3; i++) {
            u[i] = seen(Q[i]->at, K[i]->center);
            const double *Pi = Q[i]->at, *C = K[i]->center;
            trig2 p = seen(Pi, origin);
            norm2[i] = trig_add(trig_constant(dot2(Pi, Pi) + dot2(C, C)),
                                trig_add(trig_mul(trig_constant(2 * C[0]), p.x),
                                         trig_mul(trig_constant(2 * C[1]), p.y), 1),
                                -1);
        }
        for (int j = first + 1; row < 2; j++, row++) {
            /* 2 (u_j - u_first) . tau = rho_first^2 - rho_j^2 - |u_first|^2 + |u_j|^2 */
            g[row].x = trig_mul(trig_add(u[j].x, u[first].x, -1), trig_constant(2));
            g[row].y = trig_mul(trig_add(u[j].y, u[first].y, -1), trig_constant(2));
            h[row] = trig_add(trig_add(norm2[j], norm2[first], -1),
                              trig_constant(K[first]->rho * K[first]->rho -
                                            K[j]->rho * K[j]->rho),
                              1);
        }
        trig det = trig_add(trig_mul(g[0].x, g[1].y), trig_mul(g[0].y, g[1].x), -1);
        trig2 N = {trig_add(trig_mul(h[0], g[1].y), trig_mul(h[1], g[0].y), -1),
                   trig_add(trig_mul(g[0].x, h[1]), trig_mul(g[1].x, h[0]), -1)};
        trig2 w = {trig_add(trig_mul(u[first].x, det), N.x, -1),
                   trig_add(trig_mul(u[first].y, det), N.y, -1)};
        equation = trig_add(trig_dot(w, w),
                            trig_mul(trig_constant(K[first]->rho * K[first]->rho),
                                     trig_mul(det, det)),
                            -1);
    }
    double thetas[2 * TRIG_TERMS];
    int count = trig_angles(&equation, thetas);
    double tau[2];
    for (int i = 0; i < count; i++)
        for (int branch = 0; branch < 2; branch++) {
            if (branch && K[0]->line && K[1]->line)
                break;
            double theta = polish(job, Q, K, thetas[i], branch);
            if (!isnan(third_residual(Q, K, theta, branch, tau)) &&
                !try_pose(job, out, P, k, theta, tau))
                return false;
        }
    return true;
}

/* The offset curves' centre distance range: can pegs this far apart touch
 * these two curves? */
static bool reachable(const curve *a, const curve *b, double distance, double slack)
{
    double between = hypot(a->hull_center[0] - b->hull_center[0],
                           a->hull_center[1] - b->hull_center[1]);
    return distance <= between + a->hull_radius + b->hull_radius + slack &&
           distance >= between - a->hull_radius - b->hull_radius - slack;
}

/* Every pose for the holes P with the first two pegs on curves x and y,
 * every curve for the third. */
static bool hole_triple(const wr_lattice_job *job, design_list *out, const hole *const P[3], int x,
                        int y, unsigned long *units)
{
    double d01 = hypot(P[0]->at[0] - P[1]->at[0], P[0]->at[1] - P[1]->at[1]);
    double d02 = hypot(P[0]->at[0] - P[2]->at[0], P[0]->at[1] - P[2]->at[1]);
    double d12 = hypot(P[1]->at[0] - P[2]->at[0], P[1]->at[1] - P[2]->at[1]);
    double slack = 1e-6 * job->body->size;
    if (!reachable(&job->curves[x], &job->curves[y], d01, slack))
        return true;
    for (int z = 0; z < job->curve_count; z++) {
        const curve *k[3] = {&job->curves[x], &job->curves[y], &job->curves[z]};
        if (!reachable(k[0], k[2], d02, slack) || !reachable(k[1], k[2], d12, slack))
            continue;
        *units += 8;
        if (k[0]->line && k[1]->line && k[2]->line) {
            if (!three_lines(job, out, P, k))
                return false;
            continue;
        }
        /* Lines first: the translation comes from them. */
        int order[3] = {0, 1, 2};
        for (int a = 0; a < 3; a++)
            for (int b = 0; b < 2; b++)
                if (!k[order[b]]->line && k[order[b + 1]]->line) {
                    int t = order[b];
                    order[b] = order[b + 1];
                    order[b + 1] = t;
                }
        const hole *Q[3] = {P[order[0]], P[order[1]], P[order[2]]};
        const curve *K[3] = {k[order[0]], k[order[1]], k[order[2]]};
        if (job->scan) {
            *units += 40 * WR_LATTICE_STEPS;
            if (!with_arcs(job, out, Q, K, P, k))
                return false;
        } else {
            *units += 400;
            if (!exact_arcs(job, out, Q, K, P, k))
                return false;
        }
    }
    return true;
}

/* Pair number p as the indices of its second and third holes. */
static void pair_holes(const wr_lattice_job *job, size_t p, size_t *second, size_t *third)
{
    size_t i = 0, row = job->hole_count - 1;
    while (p >= row) {
        p -= row;
        i++;
        row--;
    }
    *second = i;
    *third = i + 1 + p;
}

bool wr_lattice_job_claim(wr_lattice_job *job, size_t *first, size_t *count)
{
    if (job->failed || job->claimed >= job->unit_total)
        return false;
    /* As many units as make WR_LATTICE_CHUNK curves for the third peg (a
     * unit's work), at least one. */
    size_t curves = (size_t)job->curve_count, per = WR_LATTICE_CHUNK / curves;
    if (per < 1)
        per = 1;
    *first = job->claimed;
    *count = job->unit_total - job->claimed < per ? job->unit_total - job->claimed : per;
    job->claimed += *count;
    job->outstanding++;
    return true;
}

bool wr_lattice_job_claimable(const wr_lattice_job *job)
{
    return !job->failed && job->claimed < job->unit_total;
}

void wr_lattice_chunk_release(wr_lattice_chunk *chunk)
{
    free(chunk->designs);
    memset(chunk, 0, sizeof *chunk);
}

wr_status wr_lattice_chunk_run(const wr_lattice_job *job, size_t first, size_t count,
                               const wr_stop *stop, wr_lattice_chunk *out, unsigned long *used)
{
    static const hole origin = {0, 0, {0, 0}};
    memset(out, 0, sizeof *out);
    out->first = first;
    out->count = count;
    design_list list = {NULL, 0, 0};
    unsigned long spent = 0;
    int nx = job->lattice.extent[0], ny = job->lattice.extent[1];
    size_t curves = (size_t)job->curve_count;
    wr_status status = WR_OK;
    size_t a = 0, b = 0, pair = SIZE_MAX;
    for (size_t u = first; u < first + count; u++) {
        if (wr_stop_requested(stop)) {
            status = WR_STOPPED;
            break;
        }
        size_t p = u / curves / curves;
        int x = (int)(u / curves % curves), y = (int)(u % curves);
        if (p != pair) {
            pair_holes(job, p, &a, &b);
            pair = p;
        }
        const hole *second = &job->holes[a], *third = &job->holes[b];
        int lo_i = second->i < third->i ? second->i : third->i;
        int hi_i = second->i > third->i ? second->i : third->i;
        lo_i = lo_i < 0 ? lo_i : 0;
        hi_i = hi_i > 0 ? hi_i : 0;
        int hi_j = second->j > third->j ? second->j : third->j;
        spent += 1;
        if (hi_i - lo_i < nx && hi_j < ny &&
            hypot(second->at[0] - third->at[0], second->at[1] - third->at[1]) <= job->reach) {
            const hole *P[3] = {&origin, second, third};
            if (!hole_triple(job, &list, P, x, y, &spent)) {
                status = WR_NO_MEMORY;
                break;
            }
        }
    }
    if (used)
        *used += spent;
    if (status != WR_OK) {
        free(list.items);
        return status;
    }
    out->designs = list.items;
    out->design_count = list.count;
    return WR_OK;
}

/* Append the chunk's designs to `found`, and any waiting chunks that now
 * come next: designs stay in the order of their hole pairs. */
static bool append(wr_lattice_job *job, wr_lattice_chunk *chunk)
{
    for (size_t i = 0; i < chunk->design_count; i++)
        if (!add_design(job, &job->found, &chunk->designs[i]))
            return false;
    job->merged += chunk->count;
    wr_lattice_chunk_release(chunk);
    return true;
}

wr_status wr_lattice_job_merge(wr_lattice_job *job, wr_lattice_chunk *chunk)
{
    job->outstanding--;
    if (chunk->first != job->merged) {
        /* Ahead of its turn: it waits for the chunks before it. */
        if (job->waiting_count == job->waiting_capacity) {
            size_t grown = job->waiting_capacity ? 2 * job->waiting_capacity : 8;
            wr_lattice_chunk *more = realloc(job->waiting, grown * sizeof *more);
            if (!more) {
                wr_lattice_chunk_release(chunk);
                job->failed = true;
                return WR_NO_MEMORY;
            }
            job->waiting = more;
            job->waiting_capacity = grown;
        }
        job->waiting[job->waiting_count++] = *chunk;
        memset(chunk, 0, sizeof *chunk);
        return WR_OK;
    }
    if (!append(job, chunk)) {
        job->failed = true;
        return WR_NO_MEMORY;
    }
    /* Then every waiting chunk whose turn has come. */
    for (size_t i = 0; i < job->waiting_count;) {
        if (job->waiting[i].first != job->merged) {
            i++;
            continue;
        }
        wr_lattice_chunk next = job->waiting[i];
        job->waiting[i] = job->waiting[--job->waiting_count];
        if (!append(job, &next)) {
            job->failed = true;
            return WR_NO_MEMORY;
        }
        i = 0;
    }
    return WR_OK;
}

void wr_lattice_job_abandon(wr_lattice_job *job)
{
    job->outstanding--;
    job->failed = true;
}

wr_status wr_lattice_job_run(wr_lattice_job *job, unsigned long budget, unsigned long *used,
                             const wr_stop *stop, bool *done)
{
    *done = false;
    if (job->failed)
        return WR_NO_MEMORY;
    unsigned long spent = 0;
    size_t first, count;
    while ((spent == 0 || spent < budget) && wr_lattice_job_claim(job, &first, &count)) {
        wr_lattice_chunk chunk;
        wr_status status = wr_lattice_chunk_run(job, first, count, stop, &chunk, &spent);
        if (status != WR_OK) {
            wr_lattice_job_abandon(job);
            if (used)
                *used += spent;
            return status;
        }
        status = wr_lattice_job_merge(job, &chunk);
        if (status != WR_OK) {
            if (used)
                *used += spent;
            return status;
        }
    }
    if (used)
        *used += spent;
    *done = job->merged >= job->unit_total && job->outstanding == 0;
    return WR_OK;
}

void wr_lattice_job_scan(wr_lattice_job *job) { job->scan = true; }

void wr_lattice_job_progress(const wr_lattice_job *job, size_t *done, size_t *total)
{
    *done = job->merged;
    *total = job->unit_total;
}

const wr_lattice_design *wr_lattice_job_designs(const wr_lattice_job *job, size_t *count)
{
    *count = job->found.count;
    return job->found.items;
}

void wr_lattice_job_free(wr_lattice_job *job)
{
    if (!job)
        return;
    for (size_t i = 0; i < job->waiting_count; i++)
        wr_lattice_chunk_release(&job->waiting[i]);
    free(job->waiting);
    free(job->curves);
    free(job->holes);
    free(job->found.items);
    free(job);
}
