/* wr_locate.c -- locating accuracy: the locating matrix, its inverse, the
 * worst pose and feature errors over the tolerance box, linear and exact,
 * and the covariance of the features (docs/MODEL.md section 9). */
#include "wr_locate.h"
#include "wr_internal.h"
#include "wr_outline.h"

#include <assert.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

/* A fixel's normal at a smooth point of the outline must be the outline's
 * within this angle (radians): a point locator's contact normal is the
 * outline's, and the locating matrix is built from the fixel's. */
#define NORMAL_AGREEMENT 1e-6
/* Newton: iterations per solve, halvings of a step that does not lower the
 * residual, and the intermediate displacements tried when the full one
 * fails from the linear start. */
#define NEWTON_ITERATIONS 60
#define NEWTON_HALVINGS 40
#define CONTINUATION_STEPS 16
/* A locator passing onto a neighbouring segment: at most this many moves
 * per solve (more means it is caught at a corner). */
#define SEGMENT_MOVES 6

typedef enum contact_kind {
    ON_LINE,   /* the locator point lies on a straight segment's line */
    ON_ARC,    /* ... on an arc's circle (a circle shape's own) */
    AT_CORNER  /* a corner of the outline lies on the locator's face */
} contact_kind;

/* How locator i meets the part, in the part's nominal frame. */
typedef struct contact {
    contact_kind kind;
    double point[2];   /* line: its segment's start; arc: the centre;
                          corner: the vertex */
    double normal[2];  /* line: unit normal of the line; corner: n_i */
    double radius;     /* arc */
    bool on_outline;   /* its segment is outline->loops[loop].segments[segment] */
    size_t loop, segment;
} contact;

/* The problem wr_locate_pose solves: the fixture's contacts and the
 * number of unknowns (3, or 2 for a circle: dtheta is 0). */
typedef struct locate_problem {
    const wr_fixture *fixture;
    int k;
    int unknowns;
    contact contacts[3];
} locate_problem;

static double cross2(const double a[2], const double b[2]) { return a[0] * b[1] - a[1] * b[0]; }

static void set_segment(contact *c, const wr_outline *outline, size_t loop, size_t segment)
{
    const wr_segment *s = &outline->loops[loop].segments[segment];
    c->on_outline = true;
    c->loop = loop;
    c->segment = segment;
    if (s->bulge == 0) {
        c->kind = ON_LINE;
        c->point[0] = s->start[0];
        c->point[1] = s->start[1];
        c->normal[0] = -s->direction[1];
        c->normal[1] = s->direction[0];
    } else {
        c->kind = ON_ARC;
        c->point[0] = s->center[0];
        c->point[1] = s->center[1];
        c->radius = s->radius;
    }
}

/* R(-theta) y and its derivative in theta, and the displacement
 * R(theta) w - w written without cancellation (cos - 1 = -2 sin^2(t/2)). */
static void turn_displacement(double theta, const double w[2], double out[2])
{
    double s = sin(theta), h = sin(theta / 2), cm1 = -2 * h * h;
    out[0] = cm1 * w[0] - s * w[1];
    out[1] = s * w[0] + cm1 * w[1];
}

/* Contact equation i at pose z (dx, dy, dtheta) with locator move e_i, and
 * its gradient.  Zero when the moved locator lies on the displaced part
 * (a point on a line or circle), or the displaced corner on the moved
 * face.  Linearised at z = 0 with the fixel's normal the outline's, each is
 * e_i - G_i z (up to sign): the locating matrix. */
static double contact_residual(const locate_problem *pr, int i, double e, const double z[3],
                               double grad[3])
{
    const wr_fixture *f = pr->fixture;
    const wr_fixel *x = &f->fixels[i];
    const contact *c = &pr->contacts[i];
    double cs = cos(z[2]), sn = sin(z[2]);
    double locator[2] = {x->at[0] + e * x->normal[0], x->at[1] + e * x->normal[1]};
    if (c->kind == AT_CORNER) {
        double w[2] = {c->point[0] - f->com[0], c->point[1] - f->com[1]};
        double turned[2];
        turn_displacement(z[2], w, turned);
        double moved[2] = {c->point[0] + z[0] + turned[0], c->point[1] + z[1] + turned[1]};
        grad[0] = c->normal[0];
        grad[1] = c->normal[1];
        grad[2] = c->normal[0] * (-sn * w[0] - cs * w[1]) + c->normal[1] * (cs * w[0] - sn * w[1]);
        return c->normal[0] * (moved[0] - locator[0]) + c->normal[1] * (moved[1] - locator[1]);
    }
    /* The locator in the part's frame: q = c + R(-dtheta) (locator - c - d). */
    double y[2] = {locator[0] - f->com[0] - z[0], locator[1] - f->com[1] - z[1]};
    double q[2] = {f->com[0] + cs * y[0] + sn * y[1], f->com[1] - sn * y[0] + cs * y[1]};
    double dq[3][2] = {{-cs, sn}, {-sn, -cs}, {-sn * y[0] + cs * y[1], -cs * y[0] - sn * y[1]}};
    double along[2], value;
    if (c->kind == ON_LINE) {
        along[0] = c->normal[0];
        along[1] = c->normal[1];
        value = c->normal[0] * (q[0] - c->point[0]) + c->normal[1] * (q[1] - c->point[1]);
    } else {
        double r[2] = {q[0] - c->point[0], q[1] - c->point[1]};
        double length = hypot(r[0], r[1]);
        along[0] = length > 0 ? r[0] / length : 1;
        along[1] = length > 0 ? r[1] / length : 0;
        value = length - c->radius;
    }
    for (int j = 0; j < 3; j++)
        grad[j] = along[0] * dq[j][0] + along[1] * dq[j][1];
    return value;
}

/* Solve the n x n system a z = b in place (partial pivoting).  False when
 * a pivot vanishes. */
static bool solve_small(int n, double a[3][3], double b[3], double z[3])
{
    int order[3] = {0, 1, 2};
    for (int col = 0; col < n; col++) {
        int best = col;
        for (int r = col + 1; r < n; r++)
            if (fabs(a[order[r]][col]) > fabs(a[order[best]][col]))
                best = r;
        int t = order[col];
        order[col] = order[best];
        order[best] = t;
        double pivot = a[order[col]][col];
        if (!(fabs(pivot) > 0) || !isfinite(pivot))
            return false;
        for (int r = col + 1; r < n; r++) {
            double factor = a[order[r]][col] / pivot;
            for (int j = col; j < n; j++)
                a[order[r]][j] -= factor * a[order[col]][j];
            b[order[r]] -= factor * b[order[col]];
        }
    }
    for (int col = n - 1; col >= 0; col--) {
        double sum = b[order[col]];
        for (int j = col + 1; j < n; j++)
            sum -= a[order[col]][j] * z[j];
        z[col] = sum / a[order[col]][col];
    }
    return true;
}

static double residuals(const locate_problem *pr, const double *e, const double z[3],
                        double f[3], double jac[3][3])
{
    double worst = 0;
    for (int i = 0; i < pr->unknowns; i++) {
        f[i] = contact_residual(pr, i, e[i], z, jac[i]);
        worst = fmax(worst, fabs(f[i]));
        if (!isfinite(f[i]))
            worst = INFINITY;
    }
    return worst;
}

/* Newton from z on the current contacts, damped by halving; true when the
 * residual reaches `goal`. */
static bool newton(const locate_problem *pr, const double *e, double z[3], double goal)
{
    double f[3], jac[3][3];
    double worst = residuals(pr, e, z, f, jac);
    for (int it = 0; it < NEWTON_ITERATIONS && worst > goal; it++) {
        double a[3][3], b[3], step[3] = {0, 0, 0};
        for (int i = 0; i < pr->unknowns; i++) {
            b[i] = -f[i];
            for (int j = 0; j < pr->unknowns; j++)
                a[i][j] = jac[i][j];
        }
        if (!solve_small(pr->unknowns, a, b, step))
            return false;
        double scale = 1, trial[3], tf[3], tjac[3][3], tworst = INFINITY;
        for (int h = 0; h < NEWTON_HALVINGS; h++, scale /= 2) {
            for (int j = 0; j < 3; j++)
                trial[j] = z[j] + scale * (j < pr->unknowns ? step[j] : 0);
            tworst = residuals(pr, e, trial, tf, tjac);
            if (tworst < worst)
                break;
        }
        if (!(tworst < worst))
            return worst <= goal;
        memcpy(z, trial, sizeof trial);
        memcpy(f, tf, sizeof tf);
        memcpy(jac, tjac, sizeof tjac);
        worst = tworst;
    }
    return worst <= goal;
}

/* Is the locator's foot on its segment at pose z?  0 yes; -1 it passed the
 * segment's start, +1 its end. */
static int foot_side(const locate_problem *pr, int i, double e, const double z[3])
{
    const contact *c = &pr->contacts[i];
    if (!c->on_outline || c->kind == AT_CORNER)
        return 0;
    const wr_fixture *f = pr->fixture;
    const wr_segment *s = &f->outline->loops[c->loop].segments[c->segment];
    const wr_fixel *x = &f->fixels[i];
    double cs = cos(z[2]), sn = sin(z[2]);
    double y[2] = {x->at[0] + e * x->normal[0] - f->com[0] - z[0],
                   x->at[1] + e * x->normal[1] - f->com[1] - z[1]};
    double q[2] = {f->com[0] + cs * y[0] + sn * y[1], f->com[1] - sn * y[0] + cs * y[1]};
    double slack = WR_LOCATE_RESIDUAL * f->size;
    if (c->kind == ON_LINE) {
        double along = (q[0] - s->start[0]) * s->direction[0] + (q[1] - s->start[1]) * s->direction[1];
        return along < -slack ? -1 : along > s->length + slack ? 1 : 0;
    }
    double mid = s->start_angle + s->sweep / 2;
    double off = remainder(atan2(q[1] - s->center[1], q[0] - s->center[0]) - mid, 2 * WR_PI);
    if (fabs(off) <= fabs(s->sweep) / 2 + slack / s->radius)
        return 0;
    return (off > 0) == (s->sweep > 0) ? 1 : -1;
}

/* The contacts of a fixture in scope (checked by the caller), each fixel's
 * normal checked against the outline's where that is smooth. */
static wr_status contacts_build(const wr_fixture *f, locate_problem *pr, wr_error *error)
{
    pr->fixture = f;
    pr->k = f->fixel_count;
    pr->unknowns = f->shape == WR_SHAPE_CIRCLE ? 2 : 3;
    for (int i = 0; i < f->fixel_count; i++) {
        const wr_fixel *x = &f->fixels[i];
        contact *c = &pr->contacts[i];
        memset(c, 0, sizeof *c);
        double boundary_normal[2];
        if (f->shape == WR_SHAPE_CIRCLE) {
            c->kind = ON_ARC;
            c->point[0] = f->center[0];
            c->point[1] = f->center[1];
            c->radius = f->radius;
            boundary_normal[0] = (f->center[0] - x->at[0]) / f->radius;
            boundary_normal[1] = (f->center[1] - x->at[1]) / f->radius;
        } else {
            wr_outline_place place;
            bool on = wr_outline_locate(f->outline, x->at, WR_OUTLINE_TOLERANCE * f->size, &place);
            assert(on); /* wr_fixture_new put it there */
            (void)on;
            if (place.at_vertex && !place.smooth) {
                c->kind = AT_CORNER;
                c->point[0] = f->outline->loops[place.loop].segments[place.vertex].start[0];
                c->point[1] = f->outline->loops[place.loop].segments[place.vertex].start[1];
                c->normal[0] = x->normal[0];
                c->normal[1] = x->normal[1];
                continue;
            }
            set_segment(c, f->outline, place.loop, place.segment);
            double point[2];
            wr_outline_boundary(f->outline, place.loop, place.segment, place.t, point,
                                boundary_normal);
        }
        double off = atan2(fabs(cross2(x->normal, boundary_normal)),
                           x->normal[0] * boundary_normal[0] + x->normal[1] * boundary_normal[1]);
        if (off > NORMAL_AGREEMENT) {
            char field[40];
            snprintf(field, sizeof field, "fixture.fixels[%d].normal", i);
            wr_error_set(error, field,
                         "a locator touching a smooth part of the outline pushes along the "
                         "outline's normal (%.9g, %.9g); this one is %.3g degrees off it",
                         boundary_normal[0], boundary_normal[1], off * 180 / WR_PI);
            return WR_INVALID;
        }
    }
    return WR_OK;
}

/* The pose for moves e, on the contacts in *pr (which may move to
 * neighbouring segments), from the start z. */
static wr_status pose_solve(locate_problem *pr, const double *e, double z[3], wr_error *error)
{
    const wr_fixture *f = pr->fixture;
    double goal = WR_LOCATE_RESIDUAL * f->size / 16, limit = WR_LOCATE_RESIDUAL * f->size;
    double start[3];
    memcpy(start, z, sizeof start);
    for (int moves = 0;; moves++) {
        bool found = newton(pr, e, z, goal);
        if (!found) {
            /* From the nominal pose through intermediate displacements. */
            double part[WR_MAX_FIXELS];
            z[0] = z[1] = z[2] = 0;
            found = true;
            for (int s = 1; s <= CONTINUATION_STEPS && found; s++) {
                for (int i = 0; i < pr->k; i++)
                    part[i] = e[i] * s / CONTINUATION_STEPS;
                found = newton(pr, part, z, s == CONTINUATION_STEPS ? goal : limit);
            }
        }
        double fv[3], jac[3][3];
        if (!found || !(residuals(pr, e, z, fv, jac) <= limit)) {
            wr_error_set(error, "fixture.fixels",
                         "no pose puts every displaced locator on the outline (Newton's method "
                         "did not converge)");
            return WR_INVALID;
        }
        int moved = -1, side = 0;
        for (int i = 0; i < pr->unknowns && moved < 0; i++)
            if ((side = foot_side(pr, i, e[i], z)) != 0)
                moved = i;
        if (moved < 0)
            return WR_OK;
        if (moves >= SEGMENT_MOVES) {
            char field[40];
            snprintf(field, sizeof field, "fixture.fixels[%d]", moved);
            wr_error_set(error, field,
                         "within the tolerance this locator passes a corner of the outline: "
                         "the part's pose there is not determined by a point contact");
            return WR_INVALID;
        }
        contact *c = &pr->contacts[moved];
        size_t count = f->outline->loops[c->loop].segment_count;
        set_segment(c, f->outline, c->loop, (c->segment + count + (size_t)(side > 0 ? 1 : -1)) % count);
        memcpy(z, start, sizeof start);
    }
}

void wr_locate_vertex(const double *tolerance, int k, unsigned v, double *e)
{
    for (int i = 0; i < k; i++)
        e[i] = (v >> i & 1u) ? tolerance[i] : -tolerance[i];
}

/* The locating matrix, physical (rows n_i, (p_i - c) x n_i) and scaled
 * (torque column over rho); for a circle with 2 fixels the 2 x 2 of
 * normals. */
static void locating_matrix(const wr_fixture *f, int unknowns, double g[3][3], double gs[3][3])
{
    memset(g, 0, 9 * sizeof g[0][0]);
    memset(gs, 0, 9 * sizeof gs[0][0]);
    for (int i = 0; i < f->fixel_count && i < 3; i++) {
        const wr_fixel *x = &f->fixels[i];
        double r[2] = {x->at[0] - f->com[0], x->at[1] - f->com[1]};
        g[i][0] = gs[i][0] = x->normal[0];
        g[i][1] = gs[i][1] = x->normal[1];
        if (unknowns == 3) {
            g[i][2] = cross2(r, x->normal);
            gs[i][2] = g[i][2] / f->gyration_radius;
        }
    }
}

/* Singular values of the n x n matrix a (n <= 3), by one-sided Jacobi
 * rotations of its columns, and the right singular vectors (columns of v),
 * sorted largest first.  Accurate for small singular values, which the
 * rank decision needs (the eigenvalues of a^T a square them). */
static void singular_values(int n, const double a[3][3], double sigma[3], double v[3][3])
{
    double u[3][3];
    memcpy(u, a, sizeof u);
    memset(v, 0, 9 * sizeof v[0][0]);
    for (int i = 0; i < 3; i++)
        v[i][i] = 1;
    for (int sweep = 0; sweep < 60; sweep++) {
        bool rotated = false;
        for (int p = 0; p < n - 1; p++)
            for (int q = p + 1; q < n; q++) {
                double alpha = 0, beta = 0, gamma = 0;
                for (int r = 0; r < n; r++) {
                    alpha += u[r][p] * u[r][p];
                    beta += u[r][q] * u[r][q];
                    gamma += u[r][p] * u[r][q];
                }
                if (fabs(gamma) <= 1e-300 || fabs(gamma) <= 1e-17 * sqrt(alpha * beta))
                    continue;
                rotated = true;
                double zeta = (beta - alpha) / (2 * gamma);
                double t = copysign(1.0, zeta) / (fabs(zeta) + sqrt(1 + zeta * zeta));
                double cs = 1 / sqrt(1 + t * t), sn = cs * t;
                for (int r = 0; r < n; r++) {
                    double up = u[r][p], uq = u[r][q];
                    u[r][p] = cs * up - sn * uq;
                    u[r][q] = sn * up + cs * uq;
                    double vp = v[r][p], vq = v[r][q];
                    v[r][p] = cs * vp - sn * vq;
                    v[r][q] = sn * vp + cs * vq;
                }
            }
        if (!rotated)
            break;
    }
    for (int j = 0; j < n; j++) {
        double s = 0;
        for (int r = 0; r < n; r++)
            s += u[r][j] * u[r][j];
        sigma[j] = sqrt(s);
    }
    for (int j = 0; j < n; j++) /* selection sort, columns of v with them */
        for (int l = j + 1; l < n; l++)
            if (sigma[l] > sigma[j]) {
                double t = sigma[j];
                sigma[j] = sigma[l];
                sigma[l] = t;
                for (int r = 0; r < 3; r++) {
                    t = v[r][j];
                    v[r][j] = v[r][l];
                    v[r][l] = t;
                }
            }
}

/* The twist (vx, vy, w) of scaled null vector z (length 1), signed and
 * named as wr_locating says. */
static void free_motion(const wr_fixture *f, const double z[3], wr_locating *out)
{
    double sign = fabs(z[2]) > WR_LOCATE_RANK ? (z[2] > 0 ? 1 : -1)
                  : fabs(z[0]) > WR_LOCATE_RANK ? (z[0] > 0 ? 1 : -1)
                  : (z[1] > 0 ? 1 : -1);
    out->twist[0] = sign * z[0] + 0.0;
    out->twist[1] = sign * z[1] + 0.0;
    out->twist[2] = sign * z[2] / f->gyration_radius + 0.0;
    out->rotation = fabs(z[2]) > WR_LOCATE_RANK;
    if (out->rotation) {
        /* v + w J (x - c) = 0 at x = c + J v / w, J the quarter turn. */
        out->about[0] = f->com[0] - out->twist[1] / out->twist[2];
        out->about[1] = f->com[1] + out->twist[0] / out->twist[2];
    }
}

static void describe_motion(const wr_locating *m, char *text, size_t size)
{
    if (m->rotation)
        snprintf(text, size, "turn about (%.6g, %.6g)", m->about[0], m->about[1]);
    else
        snprintf(text, size, "slide along (%.6g, %.6g)", m->twist[0], m->twist[1]);
}

/* Fixtures out of scope, refused with what is missing. */
static wr_status check_scope(const wr_fixture *f, wr_error *error)
{
    int k = f->fixel_count;
    bool circle = f->shape == WR_SHAPE_CIRCLE;
    int wanted = circle ? 2 : 3;
    if (k > wanted) {
        wr_error_set(error, "fixture.fixels",
                     "%d fixels over-constrain %s: locating is answered for %d fixels (%s), "
                     "which determine the seated pose",
                     k, circle ? "a disc" : "the part", wanted,
                     circle ? "a disc's turning about its centre moves no contact" :
                              "a disc takes 2");
        return WR_INVALID;
    }
    if (k == wanted)
        return WR_OK;
    char motion[96] = "slide along its fixels and turn";
    if (k == 2) { /* 3 wanted: one motion left, the null vector of the two scaled rows */
        double g[3][3], gs[3][3], z[3];
        locating_matrix(f, 3, g, gs);
        wr_cross3(gs[0], gs[1], z);
        if (wr_normalize3(z) > 0) {
            wr_locating m;
            free_motion(f, z, &m);
            describe_motion(&m, motion, sizeof motion);
        }
    } else if (circle)
        snprintf(motion, sizeof motion, "slide along the fixel's tangent");
    wr_error_set(error, "fixture.fixels",
                 "%d fixel%s leave%s the part free to %s: %d more %s missing (locating needs %d%s)",
                 k, k == 1 ? "" : "s", k == 1 ? "s" : "", motion, wanted - k,
                 wanted - k == 1 ? "is" : "are", wanted, circle ? " on a disc" : "");
    return WR_INVALID;
}

double wr_locate_outside(const wr_fixture *f, const double p[2])
{
    if (f->shape == WR_SHAPE_CIRCLE)
        return fmax(0.0, hypot(p[0] - f->center[0], p[1] - f->center[1]) - f->radius);
    if (!f->outline)
        return 0;
    wr_outline outer = *f->outline; /* the outer loop alone: a hole's inside is the part's */
    outer.loop_count = 1;
    return wr_outline_contains(&outer, p, 0) ? 0 : wr_outline_distance(&outer, p);
}

wr_status wr_locate_pose(const wr_fixture *fixture, const double *e, double pose[3],
                         wr_error *error)
{
    locate_problem pr;
    if (fixture->shape == WR_SHAPE_NONE) {
        wr_error_set(error, "fixture.body.shape",
                     "locating solves the seated pose on the part's outline: a shape is required");
        return WR_NO_SHAPE;
    }
    wr_status status = check_scope(fixture, error);
    if (status == WR_OK)
        status = contacts_build(fixture, &pr, error);
    if (status != WR_OK)
        return status;
    double g[3][3], gs[3][3], b[3] = {0, 0, 0}, z[3] = {0, 0, 0};
    locating_matrix(fixture, pr.unknowns, g, gs);
    for (int i = 0; i < pr.unknowns; i++)
        b[i] = e[i];
    if (!solve_small(pr.unknowns, g, b, z))
        z[0] = z[1] = z[2] = 0;
    status = pose_solve(&pr, e, z, error);
    if (status == WR_OK)
        for (int j = 0; j < 3; j++)
            pose[j] = z[j] + 0.0;
    return status;
}

/* The 99.73 % ellipse of the covariance (a, b, d). */
static void ellipse(const double cov[3], double axes[2], double *angle_deg)
{
    double mean = (cov[0] + cov[2]) / 2, half = (cov[0] - cov[2]) / 2;
    double radius = hypot(half, cov[1]);
    double major = fmax(0.0, mean + radius), minor = fmax(0.0, mean - radius);
    axes[0] = sqrt(WR_LOCATE_CHI2 * major);
    axes[1] = sqrt(WR_LOCATE_CHI2 * minor);
    double angle = radius > 0 ? 0.5 * atan2(2 * cov[1], cov[0] - cov[2]) * 180 / WR_PI : 0;
    if (angle <= -90)
        angle += 180;
    *angle_deg = angle + 0.0;
}

wr_status wr_locate(const wr_fixture *f, const double *tolerance, double sigma_ratio,
                    wr_locate_feature *features, size_t count, wr_locating *out,
                    wr_error *error)
{
    memset(out, 0, sizeof *out);
    if (f->shape == WR_SHAPE_NONE) {
        wr_error_set(error, "fixture.body.shape",
                     "locating solves the seated pose on the part's outline: a shape is required");
        return WR_NO_SHAPE;
    }
    for (int i = 0; i < f->fixel_count; i++)
        if (!isfinite(tolerance[i]) || !(tolerance[i] >= 0)) {
            char field[32];
            snprintf(field, sizeof field, "tolerance[%d]", i);
            wr_error_set(error, field, "must be a finite number >= 0 (locator %d is off by "
                         "at most this along its normal)", i + 1);
            return WR_INVALID;
        }
    if (!isfinite(sigma_ratio) || !(sigma_ratio > 0)) {
        wr_error_set(error, "sigma_ratio", "must be a finite number > 0 (sigma = tolerance / "
                     "sigma_ratio)");
        return WR_INVALID;
    }
    double reach = WR_LOCATE_FEATURE_REACH * f->size;
    for (size_t j = 0; j < count; j++) {
        char field[48];
        snprintf(field, sizeof field, "features[%zu].at", j);
        const double *p = features[j].at;
        if (!isfinite(p[0]) || !isfinite(p[1])) {
            wr_error_set(error, field, "must be finite");
            return WR_INVALID;
        }
        double outside = wr_locate_outside(f, p);
        if (outside > reach) {
            wr_error_set(error, field,
                         "(%.9g, %.9g) lies %.6g outside the part, farther than %.6g (a tenth of "
                         "its size %.6g): a feature is a point of the part",
                         p[0], p[1], outside, reach, f->size);
            return WR_INVALID;
        }
    }
    wr_status status = check_scope(f, error);
    locate_problem pr;
    if (status == WR_OK)
        status = contacts_build(f, &pr, error);
    if (status != WR_OK)
        return status;
    int k = f->fixel_count, n = pr.unknowns;
    out->fixel_count = k;

    double g[3][3], gs[3][3], sigma[3] = {0, 0, 0}, v[3][3];
    locating_matrix(f, n, g, gs);
    singular_values(n, gs, sigma, v);
    if (!(sigma[n - 1] > WR_LOCATE_RANK * sigma[0])) {
        double z[3] = {v[0][n - 1], v[1][n - 1], n == 3 ? v[2][n - 1] : 0};
        wr_normalize3(z);
        free_motion(f, z, out);
        return WR_OK;
    }
    out->deterministic = true;
    out->condition = sigma[0] / sigma[n - 1];
    for (int i = 0; i < n; i++) { /* column i of G^-1 solves G s = unit i */
        double a[3][3], b[3] = {0, 0, 0}, s[3] = {0, 0, 0};
        memcpy(a, g, sizeof a);
        b[i] = 1;
        bool solved = solve_small(n, a, b, s);
        assert(solved); /* full rank */
        (void)solved;
        for (int j = 0; j < 3; j++)
            out->sensitivity[j][i] = s[j] + 0.0;
    }

    /* Every vertex of the box: its linear and exact pose. */
    unsigned vertices = 1u << k;
    double linear[8][3], exact[8][3], e[3];
    assert(vertices <= 8);
    for (unsigned vx = 0; vx < vertices; vx++) {
        wr_locate_vertex(tolerance, k, vx, e);
        for (int j = 0; j < 3; j++) {
            linear[vx][j] = 0;
            for (int i = 0; i < k; i++)
                linear[vx][j] += out->sensitivity[j][i] * e[i];
        }
        memcpy(exact[vx], linear[vx], sizeof exact[vx]);
        locate_problem trial = pr;
        status = pose_solve(&trial, e, exact[vx], error);
        if (status != WR_OK)
            return status;
        for (int j = 0; j < 3; j++) {
            out->pose_linear[j] = fmax(out->pose_linear[j], fabs(linear[vx][j]));
            out->pose_exact[j] = fmax(out->pose_exact[j], fabs(exact[vx][j]));
        }
        out->pose_scaled = fmax(out->pose_scaled, hypot(hypot(exact[vx][0], exact[vx][1]),
                                                        f->gyration_radius * exact[vx][2]));
    }

    for (size_t j = 0; j < count; j++) {
        wr_locate_feature *ft = &features[j];
        double w[2] = {ft->at[0] - f->com[0], ft->at[1] - f->com[1]};
        /* B = [[1, 0, -w_y], [0, 1, w_x]] G^-1: the feature's motion per e. */
        double bm[2][3];
        for (int i = 0; i < 3; i++) {
            bm[0][i] = out->sensitivity[0][i] - w[1] * out->sensitivity[2][i];
            bm[1][i] = out->sensitivity[1][i] + w[0] * out->sensitivity[2][i];
        }
        ft->linear_length = ft->exact_length = -1;
        for (unsigned vx = 0; vx < vertices; vx++) {
            wr_locate_vertex(tolerance, k, vx, e);
            double u[2] = {0, 0}, x[2];
            for (int i = 0; i < k; i++) {
                u[0] += bm[0][i] * e[i];
                u[1] += bm[1][i] * e[i];
            }
            double length = hypot(u[0], u[1]);
            if (length > ft->linear_length) {
                ft->linear_length = length;
                ft->linear[0] = u[0] + 0.0;
                ft->linear[1] = u[1] + 0.0;
            }
            turn_displacement(exact[vx][2], w, x);
            x[0] += exact[vx][0];
            x[1] += exact[vx][1];
            length = hypot(x[0], x[1]);
            if (length > ft->exact_length) {
                ft->exact_length = length;
                ft->exact[0] = x[0] + 0.0;
                ft->exact[1] = x[1] + 0.0;
            }
        }
        double cov[3] = {0, 0, 0};
        for (int i = 0; i < k; i++) {
            double s = tolerance[i] / sigma_ratio, var = s * s;
            cov[0] += bm[0][i] * bm[0][i] * var;
            cov[1] += bm[0][i] * bm[1][i] * var;
            cov[2] += bm[1][i] * bm[1][i] * var;
        }
        for (int c = 0; c < 3; c++)
            ft->covariance[c] = cov[c] + 0.0;
        ellipse(cov, ft->axes, &ft->angle_deg);
    }
    return WR_OK;
}
