/* wr_tolerance.c -- robust answers over a fixture's geometric tolerance
 * (docs/MODEL.md section 10; the contract is in wr_tolerance.h).
 *
 * The argument, in short.  An excluded cone is G_X = Q_X + K_X (scaled
 * space): Q_X = {q : E q = 0, F q >= 0} from the letters' acceleration rows
 * (strict rows taken closed: the closure has the same distances), K_X the
 * cone of the friction edges -(N_i + kappa T_i).  Its polar is
 * G_X° = {y = E^T lambda - F^T mu, mu >= 0 : y . g <= 0 for every edge g},
 * and the distance of a unit x to G_X is the largest y . x over y in G_X°
 * with |y| <= 1.  A certificate for a whole box B of perturbations is one
 * choice of (lambda, mu): y(theta) = E(theta)^T lambda - F(theta)^T mu is
 * in Q_X(theta)° for every theta by construction, and the remaining
 * conditions (y . g <= 0, |y|_1 <= 1, y . x >= t) are bounded over B by
 * interval arithmetic on the rows and edges, which makes them linear in
 * (lambda, mu): an LP whose optimum t > tolerance proves that x is farther
 * than t from G_X(theta) for every theta in B (|y|_2 <= |y|_1).  A box
 * the LP does not prove is tried with certificates made of the rows
 * themselves (certify_turning), which follow them across the box.  Boxes
 * that no certificate covers are split; the centre of each is a fixture
 * of the set, and x deep in its cone is the witness of `outside`, searched
 * for at the set's corners too (search_witness). */
#include "wr_tolerance.h"

#include "wr_internal.h"
#include "wr_outline.h"
#include "wr_plan.h"

#include <assert.h>
#include <glpk.h>
#include <stdlib.h>
#include <string.h>

/* ---- intervals ---------------------------------------------------------
 * Closed intervals of reals, each result widened outwards by a few ulp of
 * its size so that rounding never drops a value it should hold. */
typedef struct iv {
    double lo, hi;
} iv;

static iv widen(iv a)
{
    double e = 4e-16 * fmax(fabs(a.lo), fabs(a.hi)) + 1e-300;
    a.lo -= e;
    a.hi += e;
    return a;
}
static iv iv_point(double v) { return (iv){v, v}; }
static iv iv_add(iv a, iv b) { return widen((iv){a.lo + b.lo, a.hi + b.hi}); }
static iv iv_sub(iv a, iv b) { return widen((iv){a.lo - b.hi, a.hi - b.lo}); }
static iv iv_mul(iv a, iv b)
{
    double p[4] = {a.lo * b.lo, a.lo * b.hi, a.hi * b.lo, a.hi * b.hi};
    iv r = {p[0], p[0]};
    for (int i = 1; i < 4; i++) {
        r.lo = fmin(r.lo, p[i]);
        r.hi = fmax(r.hi, p[i]);
    }
    return widen(r);
}
static iv iv_scale(iv a, double k)
{
    return widen(k >= 0 ? (iv){a.lo * k, a.hi * k} : (iv){a.hi * k, a.lo * k});
}
/* cos over [a, b] (b - a < 2 pi): the ends, and 1 or -1 where a crest or
 * trough lies inside. */
static iv iv_cos(double a, double b)
{
    iv r = {fmin(cos(a), cos(b)), fmax(cos(a), cos(b))};
    double k = ceil(a / (2 * WR_PI));
    if (2 * WR_PI * k <= b)
        r.hi = 1;
    k = ceil((a - WR_PI) / (2 * WR_PI));
    if (WR_PI + 2 * WR_PI * k <= b)
        r.lo = -1;
    return widen(r);
}
static iv iv_sin(double a, double b) { return iv_cos(a - WR_PI / 2, b - WR_PI / 2); }

typedef struct ivec {
    iv v[3];
} ivec;

static iv ivec_dot(const ivec *a, const ivec *b)
{
    return iv_add(iv_add(iv_mul(a->v[0], b->v[0]), iv_mul(a->v[1], b->v[1])),
                  iv_mul(a->v[2], b->v[2]));
}

/* ---- the set of fixtures ----------------------------------------------- */

/* How one fixel's contact moves: along a line, round an arc (or circle),
 * or not at all (a corner, no shape, no position tolerance). */
enum { MOVE_FIXED, MOVE_LINE, MOVE_ARC };

typedef struct fixel_motion {
    int kind;
    double direction[2]; /* line: unit, the way s grows */
    double center[2];    /* arc */
    double radius;
    double angle0;       /* arc: of the nominal point about the centre */
    double turn;         /* arc: d(angle)/ds = +-1/radius; line and fixed: 0 */
    double reach;        /* |s| <= reach */
    double allowed;      /* the most reach the geometry allows */
} fixel_motion;

/* Where fixel i can move, and how far the geometry lets it. */
static void fixel_motion_of(const wr_fixture *f, int i, fixel_motion *m)
{
    memset(m, 0, sizeof *m);
    const wr_fixel *fixel = &f->fixels[i];
    if (f->shape == WR_SHAPE_CIRCLE) {
        m->kind = MOVE_ARC;
        m->center[0] = f->center[0];
        m->center[1] = f->center[1];
        m->radius = f->radius;
        m->angle0 = atan2(fixel->at[1] - f->center[1], fixel->at[0] - f->center[0]);
        m->turn = 1 / f->radius;
        m->allowed = WR_PI * f->radius;
        return;
    }
    if (!f->outline) {
        m->kind = MOVE_FIXED;
        return;
    }
    wr_outline_place place;
    if (!wr_outline_locate(f->outline, fixel->at, 1e-9 * f->size, &place) ||
        (place.at_vertex && !place.smooth)) {
        m->kind = MOVE_FIXED; /* a corner: the contact stays there */
        m->allowed = INFINITY;
        return;
    }
    const wr_segment *seg = &f->outline->loops[place.loop].segments[place.segment];
    double t = place.t;
    m->allowed = fmin(t, 1 - t) * seg->length;
    if (seg->bulge == 0) {
        m->kind = MOVE_LINE;
        m->direction[0] = seg->direction[0];
        m->direction[1] = seg->direction[1];
    } else {
        m->kind = MOVE_ARC;
        m->center[0] = seg->center[0];
        m->center[1] = seg->center[1];
        m->radius = seg->radius;
        m->angle0 = atan2(fixel->at[1] - seg->center[1], fixel->at[0] - seg->center[0]);
        m->turn = (seg->sweep > 0 ? 1 : -1) / seg->radius;
    }
}

wr_status wr_fixture_set_tolerance(wr_fixture *fixture, const wr_tolerance *tolerance,
                                   wr_error *error)
{
    if (!tolerance->given) {
        memset(&fixture->tolerance, 0, sizeof fixture->tolerance);
        return WR_OK;
    }
    if (!isfinite(tolerance->position) || tolerance->position < 0) {
        wr_error_set(error, "tolerance.position", "must be a finite number >= 0, got %g",
                     tolerance->position);
        return WR_INVALID;
    }
    if (!isfinite(tolerance->angle) || tolerance->angle < 0 ||
        tolerance->angle >= WR_TOLERANCE_MAX_ANGLE) {
        wr_error_set(error, "tolerance.angle",
                     "must be at least 0 and below %g degrees, got %g",
                     WR_TOLERANCE_MAX_ANGLE, tolerance->angle);
        return WR_INVALID;
    }
    if (tolerance->position > 0) {
        if (fixture->shape == WR_SHAPE_NONE) {
            wr_error_set(error, "tolerance.position",
                         "a fixture without a shape has no boundary for a contact to move along");
            return WR_INVALID;
        }
        for (int i = 0; i < fixture->fixel_count; i++) {
            fixel_motion m;
            fixel_motion_of(fixture, i, &m);
            if (tolerance->position > m.allowed) {
                wr_error_set(error, "tolerance.position",
                             "%g is %g more than fixel %d's contact may move along its %s "
                             "(%g to the nearer end%s)",
                             tolerance->position, tolerance->position - m.allowed, i + 1,
                             fixture->shape == WR_SHAPE_CIRCLE ? "circle" : "segment",
                             m.allowed,
                             fixture->shape == WR_SHAPE_CIRCLE ? ": half way round" : "");
                return WR_INVALID;
            }
        }
    }
    fixture->tolerance = *tolerance;
    fixture->tolerance.position += 0.0;
    fixture->tolerance.angle += 0.0;
    return WR_OK;
}

double wr_tolerance_reach(const wr_fixture *fixture, int fixel)
{
    if (!fixture->tolerance.given || fixture->tolerance.position == 0)
        return 0;
    fixel_motion m;
    fixel_motion_of(fixture, fixel, &m);
    return m.kind == MOVE_FIXED ? 0 : fixture->tolerance.position;
}

static double tilt_reach(const wr_fixture *f)
{
    return f->tolerance.given ? f->tolerance.angle * WR_PI / 180 : 0;
}

/* Fixel i of `f` moved by s along the boundary and tilted by `tilt`. */
static void perturb_fixel(const wr_fixture *f, const fixel_motion *m, int i, double s,
                          double tilt, wr_fixel *out)
{
    const wr_fixel *in = &f->fixels[i];
    *out = *in;
    if (s == 0 && tilt == 0)
        return;
    if (s != 0 && m->kind == MOVE_LINE) {
        out->at[0] = in->at[0] + s * m->direction[0];
        out->at[1] = in->at[1] + s * m->direction[1];
    } else if (s != 0 && m->kind == MOVE_ARC) {
        double a = m->angle0 + m->turn * s;
        out->at[0] = m->center[0] + m->radius * cos(a);
        out->at[1] = m->center[1] + m->radius * sin(a);
    }
    double turn = (m->kind == MOVE_ARC ? m->turn * s : 0) + tilt;
    double c = cos(turn), sn = sin(turn);
    out->normal[0] = c * in->normal[0] - sn * in->normal[1];
    out->normal[1] = sn * in->normal[0] + c * in->normal[1];
    out->tangent[0] = -out->normal[1];
    out->tangent[1] = out->normal[0];
    double r[2] = {out->at[0] - f->com[0], out->at[1] - f->com[1]};
    out->normal_wrench[0] = out->normal[0];
    out->normal_wrench[1] = out->normal[1];
    out->normal_wrench[2] = (r[0] * out->normal[1] - r[1] * out->normal[0]) / f->gyration_radius;
    out->tangent_wrench[0] = out->tangent[0];
    out->tangent_wrench[1] = out->tangent[1];
    out->tangent_wrench[2] =
        (r[0] * out->tangent[1] - r[1] * out->tangent[0]) / f->gyration_radius;
}

void wr_tolerance_perturb(const wr_fixture *fixture, const double *s, const double *tilt,
                          wr_fixture *out)
{
    *out = *fixture;
    for (int i = 0; i < fixture->fixel_count; i++) {
        fixel_motion m;
        fixel_motion_of(fixture, i, &m);
        perturb_fixel(fixture, &m, i, s ? s[i] : 0, tilt ? tilt[i] : 0, &out->fixels[i]);
    }
}

/* A box of the set: per fixel, s in [s[i][0], s[i][1]] and the tilt in
 * [tilt[i][0], tilt[i][1]]. */
typedef struct box {
    double s[WR_MAX_FIXELS][2];
    double tilt[WR_MAX_FIXELS][2];
    double key; /* the least margin met at its parent's centre: who is split first */
} box;

/* The scaled normal and tangent wrenches of fixel i over a box. */
static void fixel_enclosure(const wr_fixture *f, const fixel_motion *m, int i, const box *b,
                            ivec *normal, ivec *tangent)
{
    const wr_fixel *fixel = &f->fixels[i];
    double s0 = b->s[i][0], s1 = b->s[i][1];
    iv p[2];
    if (m->kind == MOVE_LINE) {
        for (int j = 0; j < 2; j++)
            p[j] = iv_add(iv_point(fixel->at[j]), iv_scale((iv){s0, s1}, m->direction[j]));
    } else if (m->kind == MOVE_ARC && s0 != s1) {
        double a0 = m->angle0 + m->turn * s0, a1 = m->angle0 + m->turn * s1;
        double lo = fmin(a0, a1), hi = fmax(a0, a1);
        p[0] = iv_add(iv_point(m->center[0]), iv_scale(iv_cos(lo, hi), m->radius));
        p[1] = iv_add(iv_point(m->center[1]), iv_scale(iv_sin(lo, hi), m->radius));
    } else {
        p[0] = iv_point(fixel->at[0]);
        p[1] = iv_point(fixel->at[1]);
    }
    /* The normal's angle: the nominal one, turned with the boundary on an
     * arc, then tilted. */
    double beta = atan2(fixel->normal[1], fixel->normal[0]);
    double t0 = m->kind == MOVE_ARC ? m->turn * s0 : 0, t1 = m->kind == MOVE_ARC ? m->turn * s1 : 0;
    double lo = beta + fmin(t0, t1) + b->tilt[i][0], hi = beta + fmax(t0, t1) + b->tilt[i][1];
    iv n[2], t[2];
    if (lo == hi || (t0 == t1 && b->tilt[i][0] == b->tilt[i][1] && t0 == 0 &&
                     b->tilt[i][0] == 0)) {
        n[0] = iv_point(fixel->normal[0]);
        n[1] = iv_point(fixel->normal[1]);
    } else {
        n[0] = iv_cos(lo, hi);
        n[1] = iv_sin(lo, hi);
    }
    t[0] = (iv){-n[1].hi, -n[1].lo};
    t[1] = n[0];
    iv r[2] = {iv_sub(p[0], iv_point(f->com[0])), iv_sub(p[1], iv_point(f->com[1]))};
    double rho = f->gyration_radius;
    normal->v[0] = n[0];
    normal->v[1] = n[1];
    normal->v[2] = iv_scale(iv_sub(iv_mul(r[0], n[1]), iv_mul(r[1], n[0])), 1 / rho);
    tangent->v[0] = t[0];
    tangent->v[1] = t[1];
    tangent->v[2] = iv_scale(iv_sub(iv_mul(r[0], t[1]), iv_mul(r[1], t[0])), 1 / rho);
}

/* ---- the robust object ------------------------------------------------- */

struct wr_robust {
    const wr_analysis *analysis;
    const wr_fixture *fixture;
    int budget;
    fixel_motion motion[WR_MAX_FIXELS];
    /* Each fixel's wrenches over the whole set, the first box of every
     * cone's search: made once. */
    ivec whole_normal[WR_MAX_FIXELS], whole_tangent[WR_MAX_FIXELS];
    int cone_count[2];          /* goal, strong */
    wr_constraint *cones[2];    /* strings examined: goal's kept, strong's candidates */
};

/* Rows and edges of one constraint over one box. */
typedef struct system {
    int equality_count, inequality_count, edge_count;
    ivec equality[2 * WR_MAX_FIXELS];
    ivec inequality[WR_MAX_FIXELS + 1];
    ivec edge[2 * WR_MAX_FIXELS];
    /* Which function of the box each edge is, n_i + kappa t_i: the fixel
     * and kappa.  Two edges are the same function exactly when both agree
     * (same_edge); equal enclosures alone would not say so. */
    int edge_fixel[2 * WR_MAX_FIXELS];
    double edge_kappa[2 * WR_MAX_FIXELS];
} system_t;


static ivec ivec_neg(const ivec *a)
{
    ivec r;
    for (int j = 0; j < 3; j++)
        r.v[j] = (iv){-a->v[j].hi, -a->v[j].lo};
    return r;
}
/* -(N + kappa T) */
static ivec edge_of(const ivec *n, const ivec *t, double kappa)
{
    ivec r;
    for (int j = 0; j < 3; j++) {
        iv e = iv_add(n->v[j], iv_scale(t->v[j], kappa));
        r.v[j] = (iv){-e.hi, -e.lo};
    }
    return r;
}

/* Append edge n + kappa t of fixel i. */
static void add_edge(system_t *sys, int i, const ivec *n, const ivec *t, double kappa)
{
    sys->edge_fixel[sys->edge_count] = i;
    sys->edge_kappa[sys->edge_count] = kappa;
    sys->edge[sys->edge_count++] = edge_of(n, t, kappa);
}

/* Are edges a and b the same function of the box (so that y . g_a = 0
 * identically wherever y . g_b = 0 does)? */
static bool same_edge(const system_t *sys, int a, int b)
{
    return sys->edge_fixel[a] == sys->edge_fixel[b] && sys->edge_kappa[a] == sys->edge_kappa[b];
}

/* `whole`: b is the whole set, whose enclosures rb holds. */
static void build_system(const wr_robust *rb, const wr_constraint *c, const box *b, bool whole,
                         system_t *sys)
{
    const wr_fixture *f = rb->fixture;
    memset(sys, 0, sizeof *sys);
    for (int i = 0; i < f->fixel_count; i++) {
        char letter = c->letters[i];
        if (letter == 'u')
            continue;
        ivec n, t;
        if (whole) {
            n = rb->whole_normal[i];
            t = rb->whole_tangent[i];
        } else {
            fixel_enclosure(f, &rb->motion[i], i, b, &n, &t);
        }
        const wr_fixel *fx = &f->fixels[i];
        switch (letter) {
        case 's':
            sys->inequality[sys->inequality_count++] = n;
            break;
        case 'a':
            sys->inequality[sys->inequality_count++] = ivec_neg(&n);
            break;
        case 'l':
        case 'r':
            sys->equality[sys->equality_count++] = n;
            sys->inequality[sys->inequality_count++] = letter == 'l' ? t : ivec_neg(&t);
            add_edge(sys, i, &n, &t, letter == 'l' ? -fx->mu_kinetic : fx->mu_kinetic);
            if (fx->mu_kinetic_min != fx->mu_kinetic)
                add_edge(sys, i, &n, &t,
                         letter == 'l' ? -fx->mu_kinetic_min : fx->mu_kinetic_min);
            break;
        case 'n':
        case 'm':
            sys->equality[sys->equality_count++] = n;
            if (letter == 'n')
                sys->equality[sys->equality_count++] = t;
            add_edge(sys, i, &n, &t, fx->mu_static);
            add_edge(sys, i, &n, &t, -fx->mu_static);
            break;
        default:
            break;
        }
    }
    if (c->pivot) {
        ivec e = {{{0, 0}, {0, 0}, {c->pivot, c->pivot}}};
        sys->inequality[sys->inequality_count++] = e;
    }
}

/* A certificate found: lambda+, lambda- (interleaved per equality row),
 * then mu per inequality row, as the LP's columns. */
#define CERTIFICATE_MAX (2 * 2 * WR_MAX_FIXELS + WR_MAX_FIXELS + 1)
typedef struct certificate {
    bool valid;
    int equality_count, inequality_count;
    double value[CERTIFICATE_MAX];
} certificate;

/* The distance a given certificate proves over the box: the lower bound of
 * y . x over the bound of |y|_1, or -1 when some edge's bound is above 0
 * (no proof).  The same bounds the LP states, evaluated: a certificate
 * found for one box is tried on its neighbours before an LP is solved. */
static double check_certificate(const system_t *sys, const ivec *x, const certificate *cert)
{
    int ne = sys->equality_count, nf = sys->inequality_count;
    if (!cert->valid || cert->equality_count != ne || cert->inequality_count != nf)
        return -1;
    const double *v = cert->value;
    for (int k = 0; k < sys->edge_count; k++) {
        double up = 0;
        for (int e = 0; e < ne; e++) {
            iv d = ivec_dot(&sys->equality[e], &sys->edge[k]);
            up += v[2 * e] * d.hi - v[2 * e + 1] * d.lo;
        }
        for (int q = 0; q < nf; q++)
            up -= v[2 * ne + q] * ivec_dot(&sys->inequality[q], &sys->edge[k]).lo;
        if (up > 0)
            return -1;
    }
    double norm = 0, lower = 0;
    for (int j = 0; j < 3; j++) {
        double hi = 0, lo = 0;
        for (int e = 0; e < ne; e++) {
            hi += v[2 * e] * sys->equality[e].v[j].hi - v[2 * e + 1] * sys->equality[e].v[j].lo;
            lo += v[2 * e] * sys->equality[e].v[j].lo - v[2 * e + 1] * sys->equality[e].v[j].hi;
        }
        for (int q = 0; q < nf; q++) {
            hi -= v[2 * ne + q] * sys->inequality[q].v[j].lo;
            lo -= v[2 * ne + q] * sys->inequality[q].v[j].hi;
        }
        norm += fmax(fabs(hi), fabs(lo));
    }
    for (int e = 0; e < ne; e++) {
        iv d = ivec_dot(&sys->equality[e], x);
        lower += v[2 * e] * d.lo - v[2 * e + 1] * d.hi;
    }
    for (int q = 0; q < nf; q++)
        lower -= v[2 * ne + q] * ivec_dot(&sys->inequality[q], x).hi;
    /* Rounding in these sums: a proof must clear it. */
    return norm > 0 && lower > 0 ? lower / norm * (1 - 1e-12) : -1;
}

static iv det3(const ivec *r0, const ivec *r1, const ivec *r2);

/* ---- certificates that turn with the perturbation -----------------------
 * A fixed (lambda, mu) loses to first order in the box's width along every
 * coordinate that moves a row it uses, even where the margin does not
 * move: near the robust boundary such a coordinate would need boxes as
 * narrow as the margin.  These certificates are built from the rows
 * themselves, so that the conditions that hold with equality at the
 * optimum hold identically over the box.  G_X° = Q_X° ∩ K_X°, with
 * Q_X° = span(E) + cone(-F) and K_X° = {y : y . g <= 0 for every edge}.
 * Its extreme rays are
 *   (a) a generator of Q_X° (+-E_e, -F_q) with y . g <= 0 for every edge;
 *   (b) in the plane of two generators a, b of Q_X°, orthogonal to an
 *       edge g_k: y = sigma (g_k x (a x b)) = sigma (a (g_k . b) - b (g_k . a)),
 *       in Q_X° when the coefficient of each of a, b that is some -F_q is
 *       >= 0, and y . g_k = 0 identically;
 *   (c) orthogonal to two edges: y = sigma (g_k x g_m), in Q_X° when it
 *       is a combination of three independent generators of Q_X° whose
 *       coefficients (Cramer's rule) have the signs they must.
 * Each is a function of the rows; over a box its conditions (the sign of
 * each coefficient that must have one, y . g <= 0 for every other edge)
 * are checked by interval arithmetic, and a y valid over the box proves
 * that every x of the family is at least (y . x)_lo / |y|_1,hi from G_X:
 * the distance is the largest y . x over y in G_X° with |y|_2 <= 1, and
 * |y|_2 <= |y|_1.  A combination of such y's proves no more than the best
 * one with this bound on its norm, so the best single ratio is taken.
 * Built from cross products, such a y involves only the rows of the face
 * it stands for: a fixel that does not move the face does not enter it. */

static double ivec_norm1_hi(const ivec *y)
{
    double n = 0;
    for (int j = 0; j < 3; j++)
        n += fmax(fabs(y->v[j].lo), fabs(y->v[j].hi));
    return n;
}

static ivec ivec_cross(const ivec *a, const ivec *b)
{
    ivec r;
    r.v[0] = iv_sub(iv_mul(a->v[1], b->v[2]), iv_mul(a->v[2], b->v[1]));
    r.v[1] = iv_sub(iv_mul(a->v[2], b->v[0]), iv_mul(a->v[0], b->v[2]));
    r.v[2] = iv_sub(iv_mul(a->v[0], b->v[1]), iv_mul(a->v[1], b->v[0]));
    return r;
}

static iv iv_neg(iv a) { return (iv){-a.hi, -a.lo}; }

/* (g . b)(h . c) - (g . c)(h . b): det(g x h, b, c). */
static iv cross_det(const ivec *g, const ivec *h, const ivec *b, const ivec *c)
{
    return iv_sub(iv_mul(ivec_dot(g, b), ivec_dot(h, c)), iv_mul(ivec_dot(g, c), ivec_dot(h, b)));
}

/* Is sigma (g x h) in Q_X° over the box: a combination of three
 * generators of Q_X° whose determinant is bounded away from 0, with the
 * coefficient of each that is some -F_q provably >= 0 (Cramer's rule:
 * the coefficient of a is det(y, b, c) / det(a, b, c), and so round)? */
static bool cross_in_polar(const ivec *gen, const bool *free_sign, int n, const ivec *g,
                           const ivec *h, int sigma)
{
    for (int a = 0; a < n; a++)
        for (int b = a + 1; b < n; b++)
            for (int c = b + 1; c < n; c++) {
                /* Cheapest first: a triple whose every member is free
                 * needs no sign, and one member's sign fails most. */
                bool all_free = free_sign[a] && free_sign[b] && free_sign[c];
                iv d = det3(&gen[a], &gen[b], &gen[c]);
                if (!(d.lo > 0 || d.hi < 0))
                    continue;
                if (all_free)
                    return true;
                int order[3][3] = {{a, b, c}, {b, c, a}, {c, a, b}};
                bool ok = true;
                for (int r = 0; ok && r < 3; r++) {
                    if (free_sign[order[r][0]])
                        continue;
                    iv num = cross_det(g, h, &gen[order[r][1]], &gen[order[r][2]]);
                    if (sigma < 0)
                        num = iv_neg(num);
                    ok = d.lo > 0 ? num.lo >= 0 : num.hi <= 0;
                }
                if (ok)
                    return true;
            }
    return false;
}

/* The best distance these certificates prove over the box of `sys` for
 * every x of the family, or -1. */
static double certify_turning(const system_t *sys, const ivec *x)
{
    int ne = sys->equality_count, nf = sys->inequality_count, ng = sys->edge_count;
    /* Q_X°'s generators: the equality rows (either sign: `free`), minus
     * the inequality rows. */
    ivec gen[2 * WR_MAX_FIXELS + WR_MAX_FIXELS + 1];
    bool free_sign[2 * WR_MAX_FIXELS + WR_MAX_FIXELS + 1];
    int n = 0;
    for (int e = 0; e < ne; e++) {
        gen[n] = sys->equality[e];
        free_sign[n++] = true;
    }
    for (int q = 0; q < nf; q++) {
        gen[n] = ivec_neg(&sys->inequality[q]);
        free_sign[n++] = false;
    }
    /* Each candidate's ratio is cheap; its conditions are checked only
     * when it would beat the best so far. */
    iv gx[2 * WR_MAX_FIXELS + WR_MAX_FIXELS + 1];
    iv ge[2 * WR_MAX_FIXELS + WR_MAX_FIXELS + 1][2 * WR_MAX_FIXELS];
    for (int a = 0; a < n; a++) {
        gx[a] = ivec_dot(&gen[a], x);
        for (int m = 0; m < ng; m++)
            ge[a][m] = ivec_dot(&gen[a], &sys->edge[m]);
    }
    double best = -1;
    /* (a) */
    for (int a = 0; a < n; a++)
        for (int sigma = -1; sigma <= 1; sigma += 2) {
            if (sigma < 0 && !free_sign[a])
                continue;
            iv p = sigma > 0 ? gx[a] : iv_neg(gx[a]);
            double norm = ivec_norm1_hi(&gen[a]);
            if (!(p.lo > 0 && norm > 0 && p.lo / norm > best))
                continue;
            bool valid = true;
            for (int m = 0; valid && m < ng; m++)
                valid = (sigma > 0 ? ge[a][m].hi : -ge[a][m].lo) <= 0;
            if (valid)
                best = p.lo / norm;
        }
    /* (b) */
    for (int k = 0; k < ng; k++)
        for (int a = 0; a < n; a++)
            for (int b = a + 1; b < n; b++) {
                iv da = ge[a][k], db = ge[b][k];
                for (int sigma = -1; sigma <= 1; sigma += 2) {
                    iv ca = sigma > 0 ? db : iv_neg(db), cb = sigma > 0 ? iv_neg(da) : da;
                    if ((!free_sign[a] && ca.lo < 0) || (!free_sign[b] && cb.lo < 0))
                        continue;
                    iv p = iv_add(iv_mul(ca, gx[a]), iv_mul(cb, gx[b]));
                    if (!(p.lo > 0))
                        continue;
                    ivec y;
                    for (int j = 0; j < 3; j++)
                        y.v[j] = iv_add(iv_mul(ca, gen[a].v[j]), iv_mul(cb, gen[b].v[j]));
                    double norm = ivec_norm1_hi(&y);
                    if (!(p.lo > 0 && norm > 0 && p.lo / norm > best))
                        continue;
                    bool valid = true;
                    for (int m = 0; valid && m < ng; m++) {
                        if (m == k || same_edge(sys, m, k))
                            continue; /* y . g_k = 0 identically */
                        iv v = iv_add(iv_mul(ca, ge[a][m]), iv_mul(cb, ge[b][m]));
                        valid = v.hi <= 0;
                    }
                    if (valid)
                        best = p.lo / norm;
                }
            }
    /* (c) */
    for (int k = 0; k < ng; k++)
        for (int m = k + 1; m < ng; m++) {
            if (same_edge(sys, m, k))
                continue;
            iv p0 = det3(&sys->edge[k], &sys->edge[m], x);
            if (!(p0.lo > 0 || p0.hi < 0))
                continue;
            ivec y = ivec_cross(&sys->edge[k], &sys->edge[m]);
            double norm = ivec_norm1_hi(&y);
            for (int sigma = -1; sigma <= 1; sigma += 2) {
                iv p = sigma > 0 ? p0 : iv_neg(p0);
                if (!(p.lo > 0 && norm > 0 && p.lo / norm > best))
                    continue;
                bool valid = true;
                for (int o = 0; valid && o < ng; o++) {
                    if (same_edge(sys, o, k) ||
                        same_edge(sys, o, m))
                        continue;
                    iv d = det3(&sys->edge[k], &sys->edge[m], &sys->edge[o]);
                    valid = (sigma > 0 ? d.hi : -d.lo) <= 0;
                }
                if (valid && cross_in_polar(gen, free_sign, n, &sys->edge[k], &sys->edge[m],
                                            sigma))
                    best = p.lo / norm;
            }
        }
    return best * (1 - 1e-12);
}

/* The certificate LP of the file's comment over one box: the largest t
 * with y(theta) . x >= t for all theta and x of the box.  Returns t (-1 when
 * none is positive), or NAN when GLPK failed; a positive one's multipliers
 * into *cert (may be NULL). */
static double certify(const system_t *sys, const ivec *x, certificate *cert)
{
    int ne = sys->equality_count, nf = sys->inequality_count, ng = sys->edge_count;
    int cols = 2 * ne + nf + 3 + 1;
    int u_col = 2 * ne + nf + 1, t_col = cols;
    /* The calling thread's GLPK environment may be one GLPK made itself
     * (no wr_lp_env in this thread): it must print nothing either. */
    glp_term_out(GLP_OFF);
    glp_prob *p = glp_create_prob();
    glp_set_obj_dir(p, GLP_MAX);
    glp_add_cols(p, cols);
    for (int j = 1; j < t_col; j++)
        glp_set_col_bnds(p, j, GLP_LO, 0, 0);
    glp_set_col_bnds(p, t_col, GLP_DB, -1, 1);
    glp_set_obj_coef(p, t_col, 1);
    int rows = ng + 6 + 2;
    glp_add_rows(p, rows);
    int cap = rows * cols + 1;
    int *ri = malloc(sizeof *ri * (size_t)cap), *ci = malloc(sizeof *ci * (size_t)cap);
    double *v = malloc(sizeof *v * (size_t)cap);
    if (!ri || !ci || !v) {
        free(ri);
        free(ci);
        free(v);
        glp_delete_prob(p);
        return NAN;
    }
    int count = 0;
#define PUT(row, col, value)                                                                   \
    do {                                                                                       \
        double value_ = (value);                                                               \
        if (value_ != 0) {                                                                     \
            count++;                                                                           \
            ri[count] = (row);                                                                 \
            ci[count] = (col);                                                                 \
            v[count] = value_;                                                                 \
        }                                                                                      \
    } while (0)
    /* An upper bound of y . w as a linear form in (lambda+, lambda-, mu),
     * given each row's product interval with w. */
    int row = 0;
    for (int k = 0; k < ng; k++) { /* y . g <= 0 */
        row++;
        for (int e = 0; e < ne; e++) {
            iv d = ivec_dot(&sys->equality[e], &sys->edge[k]);
            PUT(row, 1 + 2 * e, d.hi);
            PUT(row, 2 + 2 * e, -d.lo);
        }
        for (int q = 0; q < nf; q++)
            PUT(row, 1 + 2 * ne + q, -ivec_dot(&sys->inequality[q], &sys->edge[k]).lo);
        glp_set_row_bnds(p, row, GLP_UP, 0, 0);
    }
    for (int j = 0; j < 3; j++) { /* -u_j <= y_j <= u_j */
        row++;
        for (int e = 0; e < ne; e++) {
            PUT(row, 1 + 2 * e, sys->equality[e].v[j].hi);
            PUT(row, 2 + 2 * e, -sys->equality[e].v[j].lo);
        }
        for (int q = 0; q < nf; q++)
            PUT(row, 1 + 2 * ne + q, -sys->inequality[q].v[j].lo);
        PUT(row, u_col + j, -1);
        glp_set_row_bnds(p, row, GLP_UP, 0, 0);
        row++;
        for (int e = 0; e < ne; e++) {
            PUT(row, 1 + 2 * e, sys->equality[e].v[j].lo);
            PUT(row, 2 + 2 * e, -sys->equality[e].v[j].hi);
        }
        for (int q = 0; q < nf; q++)
            PUT(row, 1 + 2 * ne + q, -sys->inequality[q].v[j].hi);
        PUT(row, u_col + j, 1);
        glp_set_row_bnds(p, row, GLP_LO, 0, 0);
    }
    row++; /* |y|_1 <= u_1 + u_2 + u_3 <= 1 */
    for (int j = 0; j < 3; j++)
        PUT(row, u_col + j, 1);
    glp_set_row_bnds(p, row, GLP_UP, 0, 1);
    row++; /* t <= a lower bound of y . x */
    for (int e = 0; e < ne; e++) {
        iv d = ivec_dot(&sys->equality[e], x);
        PUT(row, 1 + 2 * e, -d.lo);
        PUT(row, 2 + 2 * e, d.hi);
    }
    for (int q = 0; q < nf; q++)
        PUT(row, 1 + 2 * ne + q, ivec_dot(&sys->inequality[q], x).hi);
    PUT(row, t_col, 1);
    glp_set_row_bnds(p, row, GLP_UP, 0, 0);
#undef PUT
    glp_load_matrix(p, count, ri, ci, v);
    free(ri);
    free(ci);
    free(v);
    glp_smcp parm;
    glp_init_smcp(&parm);
    parm.msg_lev = GLP_MSG_OFF;
    double t = NAN;
    if (glp_simplex(p, &parm) == 0 && glp_get_status(p) == GLP_OPT)
        t = glp_get_obj_val(p);
    else {
        parm.meth = GLP_DUALP;
        glp_std_basis(p);
        if (glp_simplex(p, &parm) == 0 && glp_get_status(p) == GLP_OPT)
            t = glp_get_obj_val(p);
    }
    if (cert && t > 0) {
        cert->valid = true;
        cert->equality_count = ne;
        cert->inequality_count = nf;
        for (int j = 0; j < 2 * ne + nf; j++)
            cert->value[j] = glp_get_col_prim(p, 1 + j);
    }
    glp_delete_prob(p);
    return t;
}

/* The mode strings' equality rows are drawn from 2k rows, N_i and T_i
 * (row 2i and 2i + 1).  A triple of them whose determinant is bounded away
 * from 0 over the whole set forces q = 0 wherever a mode keeps all three
 * at zero, and every mode has a strict row that q = 0 violates: such a
 * mode is infeasible on every fixture of the set.  The robustly
 * independent triples, as bit masks. */
static int independent_triples(const wr_robust *rb, const box *whole, unsigned *masks)
{
    const wr_fixture *f = rb->fixture;
    ivec rows[2 * WR_MAX_FIXELS];
    int k = f->fixel_count;
    for (int i = 0; i < k; i++)
        fixel_enclosure(f, &rb->motion[i], i, whole, &rows[2 * i], &rows[2 * i + 1]);
    int count = 0;
    for (int a = 0; a < 2 * k; a++)
        for (int b = a + 1; b < 2 * k; b++)
            for (int d = b + 1; d < 2 * k; d++) {
                const ivec *r0 = &rows[a], *r1 = &rows[b], *r2 = &rows[d];
                iv det = iv_add(
                    iv_add(iv_mul(r0->v[0], iv_sub(iv_mul(r1->v[1], r2->v[2]),
                                                   iv_mul(r1->v[2], r2->v[1]))),
                           iv_mul(r0->v[1], iv_sub(iv_mul(r1->v[2], r2->v[0]),
                                                   iv_mul(r1->v[0], r2->v[2])))),
                    iv_mul(r0->v[2],
                           iv_sub(iv_mul(r1->v[0], r2->v[1]), iv_mul(r1->v[1], r2->v[0]))));
                if (det.lo > 0 || det.hi < 0)
                    masks[count++] = (1u << a) | (1u << b) | (1u << d);
            }
    return count;
}

/* Up to this many fixels the four-row test below is made for every mode
 * string (4^k of them, each with up to C(2k + 1, 4) subsets); beyond it a
 * mode it would exclude is kept, and answers are only more cautious. */
#define WR_ROBUST_SUBSETS_MAX_FIXELS 4

/* Could some fixture of the set make mode c feasible? */
static bool mode_possible(const wr_constraint *c, const unsigned *masks, int count)
{
    unsigned rows = 0;
    for (int i = 0; i < c->length; i++) {
        char letter = c->letters[i];
        if (strchr("lrn", letter))
            rows |= 1u << (2 * i);
        if (letter == 'n')
            rows |= 1u << (2 * i + 1);
    }
    for (int i = 0; i < count; i++)
        if ((masks[i] & rows) == masks[i])
            return false;
    return true;
}

static iv det3(const ivec *r0, const ivec *r1, const ivec *r2)
{
    return iv_add(
        iv_add(iv_mul(r0->v[0], iv_sub(iv_mul(r1->v[1], r2->v[2]), iv_mul(r1->v[2], r2->v[1]))),
               iv_mul(r0->v[1], iv_sub(iv_mul(r1->v[2], r2->v[0]), iv_mul(r1->v[0], r2->v[2])))),
        iv_mul(r0->v[2], iv_sub(iv_mul(r1->v[0], r2->v[1]), iv_mul(r1->v[1], r2->v[0]))));
}

/* Is mode c's motion impossible on every fixture of the set, by four of
 * its rows?  Any four vectors of R^3 satisfy sum_i c_i r_i = 0 with c_i =
 * (-1)^i det(the other three).  If over the whole set the c_i of the
 * inequality rows among four (F q >= 0, strict ones > 0) keep one sign,
 * some strict one's away from 0, then for q meeting the equality rows
 * sum over inequalities of c_i (r_i . q) = 0 while each term has that sign
 * and one is not 0: no such q.  `whole` the set's box. */
static bool mode_impossible(const wr_robust *rb, const wr_constraint *c, const box *whole)
{
    ivec rows[2 * WR_MAX_FIXELS + 1];
    int kind[2 * WR_MAX_FIXELS + 1]; /* 0 equality, 1 inequality, 2 strict */
    int n = 0;
    const wr_fixture *f = rb->fixture;
    for (int i = 0; i < f->fixel_count; i++) {
        ivec nw, tw;
        fixel_enclosure(f, &rb->motion[i], i, whole, &nw, &tw);
        switch (c->letters[i]) {
        case 's':
            rows[n] = nw, kind[n++] = c->strict_separation ? 2 : 1;
            break;
        case 'l':
        case 'r':
            rows[n] = nw, kind[n++] = 0;
            rows[n] = c->letters[i] == 'l' ? tw : ivec_neg(&tw), kind[n++] = 2;
            break;
        case 'n':
            rows[n] = nw, kind[n++] = 0;
            rows[n] = tw, kind[n++] = 0;
            break;
        default:
            break;
        }
    }
    if (c->pivot) {
        ivec e = {{{0, 0}, {0, 0}, {c->pivot, c->pivot}}};
        rows[n] = e, kind[n++] = 2;
    }
    int pick[4];
    for (pick[0] = 0; pick[0] < n; pick[0]++)
        for (pick[1] = pick[0] + 1; pick[1] < n; pick[1]++)
            for (pick[2] = pick[1] + 1; pick[2] < n; pick[2]++)
                for (pick[3] = pick[2] + 1; pick[3] < n; pick[3]++) {
                    int positive = 0, negative = 0, strict_positive = 0, strict_negative = 0;
                    int inequalities = 0;
                    for (int m = 0; m < 4; m++) {
                        if (kind[pick[m]] == 0)
                            continue;
                        inequalities++;
                        const ivec *o[3];
                        for (int j = 0, k = 0; j < 4; j++)
                            if (j != m)
                                o[k++] = &rows[pick[j]];
                        iv d = det3(o[0], o[1], o[2]);
                        if (m % 2)
                            d = (iv){-d.hi, -d.lo};
                        positive += d.lo >= 0;
                        negative += d.hi <= 0;
                        strict_positive += kind[pick[m]] == 2 && d.lo > 0;
                        strict_negative += kind[pick[m]] == 2 && d.hi < 0;
                    }
                    if (inequalities == 0)
                        continue;
                    if ((positive == inequalities && strict_positive > 0) ||
                        (negative == inequalities && strict_negative > 0))
                        return true;
                }
    return false;
}

static void whole_box(const wr_robust *rb, box *b)
{
    memset(b, 0, sizeof *b);
    double a = tilt_reach(rb->fixture), position = rb->fixture->tolerance.given
                                                        ? rb->fixture->tolerance.position
                                                        : 0;
    for (int i = 0; i < rb->fixture->fixel_count; i++) {
        /* wr_tolerance_reach, from the motions found once */
        double s = rb->motion[i].kind == MOVE_FIXED ? 0 : position;
        b->s[i][0] = -s;
        b->s[i][1] = s;
        b->tilt[i][0] = -a;
        b->tilt[i][1] = a;
    }
}

static bool in_list(const wr_constraint *list, int count, const wr_constraint *c)
{
    for (int i = 0; i < count; i++)
        if (strcmp(list[i].letters, c->letters) == 0 && list[i].pivot == c->pivot)
            return true;
    return false;
}

wr_status wr_robust_new(const wr_analysis *analysis, int budget, wr_robust **out)
{
    *out = NULL;
    wr_robust *rb = calloc(1, sizeof *rb);
    if (!rb)
        return WR_NO_MEMORY;
    rb->analysis = analysis;
    rb->fixture = wr_analysis_fixture(analysis);
    rb->budget = budget > 0 ? budget : WR_ROBUST_BUDGET;
    const wr_fixture *f = rb->fixture;
    int k = f->fixel_count;
    for (int i = 0; i < k; i++)
        fixel_motion_of(f, i, &rb->motion[i]);
    int goal = wr_analysis_cone_count(analysis, WR_SET_GOAL);
    rb->cones[0] = malloc(sizeof(wr_constraint) * (size_t)(goal > 0 ? goal : 1));
    if (!rb->cones[0]) {
        free(rb);
        return WR_NO_MEMORY;
    }
    memcpy(rb->cones[0], wr_analysis_constraints(analysis, WR_SET_GOAL),
           sizeof(wr_constraint) * (size_t)goal);
    rb->cone_count[0] = goal;
    /* Strong: every mode feasible at the nominal fixture, and every other
     * mode string that some fixture of the set might make feasible. */
    int nominal = wr_analysis_cone_count(analysis, WR_SET_STRONG);
    const wr_constraint *modes = wr_analysis_constraints(analysis, WR_SET_STRONG);
    int total = 1;
    for (int i = 0; i < k; i++)
        total *= 4;
    rb->cones[1] = malloc(sizeof(wr_constraint) * (size_t)(total + 2 + nominal));
    if (!rb->cones[1]) {
        free(rb->cones[0]);
        free(rb);
        return WR_NO_MEMORY;
    }
    memcpy(rb->cones[1], modes, sizeof(wr_constraint) * (size_t)nominal);
    int count = nominal;
    box whole;
    whole_box(rb, &whole);
    for (int i = 0; i < k; i++)
        fixel_enclosure(f, &rb->motion[i], i, &whole, &rb->whole_normal[i], &rb->whole_tangent[i]);
    unsigned masks[560]; /* C(16, 3) */
    int mask_count = independent_triples(rb, &whole, masks);
    static const char letters[] = "slrn";
    for (int code = 0; code < total; code++) {
        wr_constraint c;
        memset(&c, 0, sizeof c);
        c.length = k;
        c.strict_separation = true;
        int v = code;
        for (int i = k - 1; i >= 0; i--) {
            c.letters[i] = letters[v % 4];
            v /= 4;
        }
        if (strspn(c.letters, "n") == (size_t)k)
            continue; /* rolling everywhere: the part at rest, or a pivot below */
        if (in_list(rb->cones[1], count, &c) || !mode_possible(&c, masks, mask_count) ||
            (k <= WR_ROBUST_SUBSETS_MAX_FIXELS && mode_impossible(rb, &c, &whole)))
            continue;
        rb->cones[1][count++] = c;
    }
    rb->cone_count[1] = count;
    *out = rb;
    return WR_OK;
}

void wr_robust_free(wr_robust *robust)
{
    if (!robust)
        return;
    free(robust->cones[0]);
    free(robust->cones[1]);
    free(robust);
}

/* The signed distance of unit x to constraint c's cone on the fixture of
 * the set at (s, tilt) (+inf for a cone empty there). */
static wr_status distance_at(const wr_robust *rb, const wr_constraint *c, const double *s,
                             const double *tilt, const double x[3], double *distance)
{
    wr_fixture moved;
    wr_tolerance_perturb(rb->fixture, s, tilt, &moved);
    wr_cone cone;
    wr_status status = wr_cone_build(&cone, &moved, c);
    if (status == WR_OK)
        *distance = cone.empty ? INFINITY : wr_cone_signed_distance(&cone, x, NULL);
    wr_cone_release(&cone);
    return status;
}

/* The same at the box's centre, which goes to *s, *tilt. */
static wr_status centre_distance(const wr_robust *rb, const wr_constraint *c, const box *b,
                                 const double x[3], double *s, double *tilt, double *distance)
{
    for (int i = 0; i < rb->fixture->fixel_count; i++) {
        s[i] = 0.5 * (b->s[i][0] + b->s[i][1]);
        tilt[i] = 0.5 * (b->tilt[i][0] + b->tilt[i][1]);
    }
    return distance_at(rb, c, s, tilt, x, distance);
}

/* The coordinates of the set that move constraint c's rows: each fixel's
 * position and tilt, where its letter is not u and its range not a point. */
#define WITNESS_MAX_DIMS 8
typedef struct coordinate {
    int fixel;
    bool tilt;
    double lo, hi;
} coordinate;

static int coordinates_of(const wr_robust *rb, const wr_constraint *c, const box *whole,
                          coordinate *out)
{
    int n = 0;
    for (int i = 0; i < rb->fixture->fixel_count; i++) {
        if (c->letters[i] == 'u')
            continue;
        for (int tilt = 0; tilt < 2; tilt++) {
            const double *range = tilt ? whole->tilt[i] : whole->s[i];
            if (range[1] > range[0] && n < WITNESS_MAX_DIMS)
                out[n++] = (coordinate){i, tilt, range[0], range[1]};
        }
    }
    return n;
}

/* The fixture (ts, tt) of the set: x's distance there, and when deeper
 * than *depth, it becomes the deepest point (*s, *tilt, *depth). */
static wr_status try_point(const wr_robust *rb, const wr_constraint *c, const double x[3],
                          const double *ts, const double *tt, double *s, double *tilt,
                          double *depth, bool *deeper)
{
    double d;
    wr_status status = distance_at(rb, c, ts, tt, x, &d);
    *deeper = status == WR_OK && d < *depth;
    if (*deeper) {
        *depth = d;
        memcpy(s, ts, sizeof(double) * WR_MAX_FIXELS);
        memcpy(tilt, tt, sizeof(double) * WR_MAX_FIXELS);
    }
    return status;
}

/* A deepest point of x in c's cone over the set, searched for where the
 * boxes' centres reach slowly: worst cases sit at the set's corners (a row
 * moves monotonically with a coordinate over most of its range), or near
 * one.  Each corner of the whole set (up to 2^WITNESS_MAX_DIMS), then a
 * descent from the deepest point found so far (*s, *tilt, *depth on entry
 * and exit): each coordinate moved by +-h within its range while that
 * deepens, h halved from half the range down to 1e-13 of it.  This finds
 * witnesses, it proves nothing: a point it finds is a fixture of the set
 * whose own answer wr_robust_classify confirms. */
static wr_status search_witness(const wr_robust *rb, const wr_constraint *c, const double x[3],
                                double *s, double *tilt, double *depth)
{
    box whole;
    whole_box(rb, &whole);
    coordinate dims[WITNESS_MAX_DIMS];
    int nd = coordinates_of(rb, c, &whole, dims);
    if (nd == 0)
        return WR_OK;
    double ts[WR_MAX_FIXELS], tt[WR_MAX_FIXELS];
    for (unsigned corner = 0; corner < 1u << nd; corner++) {
        memcpy(ts, s, sizeof ts);
        memcpy(tt, tilt, sizeof tt);
        for (int k = 0; k < nd; k++)
            (dims[k].tilt ? tt : ts)[dims[k].fixel] = corner >> k & 1 ? dims[k].hi : dims[k].lo;
        bool deeper;
        wr_status status = try_point(rb, c, x, ts, tt, s, tilt, depth, &deeper);
        if (status != WR_OK)
            return status;
    }
    for (double h = 0.5; h > 1e-13; h *= 0.5) {
        bool moved = true;
        while (moved) {
            moved = false;
            for (int k = 0; k < nd; k++)
                for (int sign = -1; sign <= 1; sign += 2) {
                    memcpy(ts, s, sizeof ts);
                    memcpy(tt, tilt, sizeof tt);
                    double *v = &(dims[k].tilt ? tt : ts)[dims[k].fixel];
                    *v = fmin(dims[k].hi,
                              fmax(dims[k].lo, *v + sign * h * (dims[k].hi - dims[k].lo)));
                    bool deeper;
                    wr_status status = try_point(rb, c, x, ts, tt, s, tilt, depth, &deeper);
                    if (status != WR_OK)
                        return status;
                    moved |= deeper;
                }
        }
    }
    return WR_OK;
}

/* Split b in two along its widest side (positions measured against the
 * radius of gyration, tilts in radians); false when no side is wider than
 * `floor`. */
static bool split(const wr_robust *rb, const wr_constraint *c, const box *b, box *one,
                  box *two, double floor)
{
    double widest = floor;
    int which = -1, kind = 0;
    for (int i = 0; i < rb->fixture->fixel_count; i++) {
        if (c->letters[i] == 'u')
            continue;
        double ws = (b->s[i][1] - b->s[i][0]) / rb->fixture->gyration_radius;
        double wt = b->tilt[i][1] - b->tilt[i][0];
        if (ws > widest) {
            widest = ws;
            which = i;
            kind = 0;
        }
        if (wt > widest) {
            widest = wt;
            which = i;
            kind = 1;
        }
    }
    if (which < 0)
        return false;
    *one = *b;
    *two = *b;
    double (*side)[2] = kind == 0 ? one->s : one->tilt;
    double (*other)[2] = kind == 0 ? two->s : two->tilt;
    double mid = 0.5 * (side[which][0] + side[which][1]);
    side[which][1] = mid;
    other[which][0] = mid;
    return true;
}

enum { CONE_CLEAR, CONE_WITNESS, CONE_UNDECIDED, CONE_FAILED };

/* One excluded cone against the interval family x (a point family for a
 * single wrench, whose unit direction is `point`; NULL for a family that
 * is only to be proved inside).  CONE_CLEAR with *lower, the least
 * certified distance; CONE_WITNESS with the fixture (s, tilt) and the depth
 * found (*least, < -tolerance); CONE_UNDECIDED with the least distance met
 * in *least. */
static int examine_cone(const wr_robust *rb, const wr_constraint *c, const ivec *x,
                        const double *point, double tolerance, double nominal,
                        certificate *cache, int budget, double *lower, double *least,
                        double *s, double *tilt)
{
    box *queue = malloc(sizeof *queue * (size_t)(budget + 1));
    if (!queue)
        return CONE_FAILED;
    int count = 0;
    whole_box(rb, &queue[count]);
    queue[count++].key = nominal;
    *lower = INFINITY;
    *least = nominal;
    int result = CONE_CLEAR;
    int examined = 0;
    /* The deepest box centre met: where the witness search starts. */
    double deep_s[WR_MAX_FIXELS] = {0}, deep_tilt[WR_MAX_FIXELS] = {0}, deepest = INFINITY;
    while (count > 0) {
        int pick = 0;
        for (int i = 1; i < count; i++)
            if (queue[i].key < queue[pick].key)
                pick = i;
        box b = queue[pick];
        queue[pick] = queue[--count];
        examined++;
        system_t sys;
        build_system(rb, c, &b, examined == 1, &sys);
        /* The last certificate of this cone first: a neighbouring box's
         * often proves this one too, without an LP. */
        double t = cache ? check_certificate(&sys, x, cache) : -1;
        if (!(t > tolerance))
            t = fmax(t, certify_turning(&sys, x));
        if (!(t > tolerance))
            t = certify(&sys, x, cache);
        if (isnan(t)) {
            result = CONE_FAILED;
            break;
        }
        if (t > tolerance) {
            *lower = fmin(*lower, t);
            continue;
        }
        double d = INFINITY;
        if (point) {
            double cs[WR_MAX_FIXELS], ct[WR_MAX_FIXELS];
            if (centre_distance(rb, c, &b, point, cs, ct, &d) != WR_OK) {
                result = CONE_FAILED;
                break;
            }
            *least = fmin(*least, d);
            if (d < deepest) {
                deepest = d;
                memcpy(deep_s, cs, sizeof cs);
                memcpy(deep_tilt, ct, sizeof ct);
            }
            if (d < -tolerance) {
                memcpy(s, cs, sizeof cs);
                memcpy(tilt, ct, sizeof ct);
                result = CONE_WITNESS;
                break;
            }
        }
        box one, two;
        /* Undecided: the budget spent, or the box as small as it gets. */
        if (examined + count + 2 > budget ||
            !split(rb, c, &b, &one, &two, 1e-12)) {
            result = CONE_UNDECIDED;
            *lower = fmin(*lower, t);
            continue;
        }
        one.key = two.key = d;
        queue[count++] = one;
        queue[count++] = two;
    }
    free(queue);
    if (result == CONE_UNDECIDED && point) {
        if (search_witness(rb, c, point, deep_s, deep_tilt, &deepest) != WR_OK)
            return CONE_FAILED;
        *least = fmin(*least, deepest);
        if (deepest < -tolerance) {
            memcpy(s, deep_s, sizeof deep_s);
            memcpy(tilt, deep_tilt, sizeof deep_tilt);
            result = CONE_WITNESS;
        }
    }
    return result;
}

/* The index of constraint c among the nominal analysis's cones of `set`,
 * or -1 for a mode only a perturbed fixture may have. */
static int nominal_index(const wr_robust *rb, wr_set set, const wr_constraint *c)
{
    int count = wr_analysis_cone_count(rb->analysis, set);
    const wr_constraint *list = wr_analysis_constraints(rb->analysis, set);
    for (int i = 0; i < count; i++)
        if (strcmp(list[i].letters, c->letters) == 0 && list[i].pivot == c->pivot)
            return i;
    return -1;
}

static void unit_family(const double x[3], ivec *family)
{
    for (int j = 0; j < 3; j++)
        family->v[j] = iv_point(x[j]);
}

/* The nominal fixture's answer, then the robust one.  */
wr_status wr_robust_classify(const wr_robust *rb, const double wrench[3], wr_set set,
                             double tolerance, wr_robust_answer *out)
{
    memset(out, 0, sizeof *out);
    const wr_fixture *f = rb->fixture;
    wr_status status = wr_classify(rb->analysis, wrench, set, tolerance, &out->answer);
    if (status != WR_OK)
        return status;
    double x[3];
    if (wr_fixture_unit_wrench(f, wrench, x) == 0 || !f->tolerance.given ||
        out->answer.verdict == WR_VERDICT_OUTSIDE) {
        if (out->answer.verdict == WR_VERDICT_OUTSIDE && f->tolerance.given) {
            /* The nominal fixture is in the set: it is the witness. */
            out->has_perturbation = true;
            for (int i = 0; i < f->fixel_count; i++) {
                memcpy(out->points[i], f->fixels[i].at, sizeof out->points[i]);
                memcpy(out->normals[i], f->fixels[i].normal, sizeof out->normals[i]);
            }
        }
        return WR_OK;
    }
    ivec family;
    unit_family(x, &family);
    double lower = INFINITY, least = out->answer.margin;
    bool undecided = false;
    int undecided_set = -1, undecided_cone = -1;
    for (int which = 0; which < 2; which++) {
        if ((which == 0 && set == WR_SET_STRONG) || (which == 1 && set == WR_SET_GOAL))
            continue;
        for (int i = 0; i < rb->cone_count[which]; i++) {
            const wr_constraint *c = &rb->cones[which][i];
            wr_fixture nominal_fixture = *f;
            wr_cone cone;
            if (wr_cone_build(&cone, &nominal_fixture, c) != WR_OK) {
                wr_cone_release(&cone);
                return WR_NO_MEMORY;
            }
            double nominal = cone.empty ? INFINITY : wr_cone_signed_distance(&cone, x, NULL);
            wr_cone_release(&cone);
            double lo, le, s[WR_MAX_FIXELS], tilt[WR_MAX_FIXELS];
            int r = examine_cone(rb, c, &family, x, tolerance, nominal, NULL, rb->budget, &lo,
                                 &le, s, tilt);
            if (r == CONE_FAILED)
                return WR_LP_FAILED;
            least = fmin(least, le);
            if (r == CONE_WITNESS) {
                wr_fixture moved;
                wr_tolerance_perturb(f, s, tilt, &moved);
                wr_analysis *a;
                if (wr_analysis_new(&moved, &a) != WR_OK)
                    return WR_NO_MEMORY;
                wr_answer answer;
                status = wr_classify(a, wrench, set, tolerance, &answer);
                if (status != WR_OK) {
                    wr_analysis_free(a);
                    return status;
                }
                if (answer.verdict == WR_VERDICT_OUTSIDE) {
                    out->answer = answer;
                    /* Named by the nominal analysis's cones: the goal's are
                     * the plan's on every fixture; a mode the nominal
                     * fixture lacks has none (-1). */
                    out->answer.blocking = nominal_index(rb, answer.blocking_set,
                        wr_analysis_constraints(a, answer.blocking_set) + answer.blocking);
                    out->has_perturbation = true;
                    for (int j = 0; j < f->fixel_count; j++) {
                        memcpy(out->points[j], moved.fixels[j].at, sizeof out->points[j]);
                        memcpy(out->normals[j], moved.fixels[j].normal, sizeof out->normals[j]);
                    }
                    wr_analysis_free(a);
                    return WR_OK;
                }
                wr_analysis_free(a);
                r = CONE_UNDECIDED; /* rounding kept the witness at the edge */
            }
            if (r == CONE_UNDECIDED && !undecided) {
                undecided = true;
                undecided_set = which;
                undecided_cone = i;
            }
            lower = fmin(lower, lo);
        }
    }
    if (!undecided) {
        /* Inside for every fixture of the set: the margin is the least
         * certified distance, a lower bound of the worst margin. */
        out->answer.verdict = WR_VERDICT_INSIDE;
        out->answer.margin = fmin(out->answer.margin, lower);
        out->answer.blocking = -1;
        return WR_OK;
    }
    out->answer.verdict = WR_VERDICT_BOUNDARY;
    out->answer.margin = least;
    out->answer.blocking_set = undecided_set == 0 ? WR_SET_GOAL : WR_SET_STRONG;
    out->answer.blocking = nominal_index(rb, out->answer.blocking_set,
                                         &rb->cones[undecided_set][undecided_cone]);
    memset(&out->answer.witness, 0, sizeof out->answer.witness);
    return WR_OK;
}

/* wr_robust_box_inside with a certificate cache per cone (goal's, then
 * strong's; NULL: none). */
static bool box_inside(const wr_robust *rb, const double lo[3], const double hi[3], wr_set set,
                       double tolerance, certificate *caches, int budget, wr_status *status)
{
    *status = WR_OK;
    ivec family;
    for (int j = 0; j < 3; j++)
        family.v[j] = (iv){lo[j], hi[j]};
    /* Dividing by |x| <= the box's largest length turns the certified
     * y . x >= t into a distance of the unit direction. */
    double big = 0;
    for (int j = 0; j < 3; j++)
        big += fmax(lo[j] * lo[j], hi[j] * hi[j]);
    big = sqrt(big);
    for (int which = 0; which < 2; which++) {
        if ((which == 0 && set == WR_SET_STRONG) || (which == 1 && set == WR_SET_GOAL))
            continue;
        for (int i = 0; i < rb->cone_count[which]; i++) {
            double lower, least, s[WR_MAX_FIXELS], tilt[WR_MAX_FIXELS];
            certificate *cache = caches ? &caches[which * rb->cone_count[0] + i] : NULL;
            int r = examine_cone(rb, &rb->cones[which][i], &family, NULL, tolerance * big,
                                 INFINITY, cache, budget, &lower, &least, s, tilt);
            if (r == CONE_FAILED) {
                *status = WR_LP_FAILED;
                return false;
            }
            if (r != CONE_CLEAR)
                return false;
        }
    }
    return true;
}

bool wr_robust_box_inside(const wr_robust *rb, const double lo[3], const double hi[3],
                          wr_set set, double tolerance, wr_status *status)
{
    return box_inside(rb, lo, hi, set, tolerance, NULL, rb->budget, status);
}

/* ---- regions ----------------------------------------------------------- */

/* The scaled wrenches of a push along (edge, t) for t in [ta, tb], or of
 * gravity for tilts in [ta, tb] degrees, in a box [lo, hi]: the ends'
 * componentwise bounds, widened where the family turns (an arc, a circle,
 * the tilt), since a sinusoid of amplitude A over an angle D rises at most
 * A (1 - cos(D / 2)) above the larger of its ends. */
static void family_box(const wr_fixture *f, int edge, bool gravity, double ta, double tb,
                       double lo[3], double hi[3])
{
    double w[2][3], amplitude[3] = {1, 1, 0}, turn = 0;
    for (int k = 0; k < 2; k++) {
        double t = k ? tb : ta;
        if (gravity) {
            w[k][0] = cos(t * WR_PI / 180);
            w[k][1] = sin(t * WR_PI / 180);
            w[k][2] = 0;
        } else {
            wr_push_wrench(f, edge, t, w[k]);
            w[k][2] /= f->gyration_radius;
        }
    }
    if (gravity) {
        turn = (tb - ta) * WR_PI / 180;
    } else if (f->shape == WR_SHAPE_CIRCLE) {
        turn = (tb - ta) * WR_PI / 180;
        amplitude[2] = hypot(f->center[0] - f->com[0], f->center[1] - f->com[1]) /
                       f->gyration_radius;
    } else if (f->shape == WR_SHAPE_OUTLINE) {
        size_t loop, segment;
        wr_push_edge_place(f, edge, &loop, &segment);
        const wr_segment *seg = &f->outline->loops[loop].segments[segment];
        if (seg->bulge != 0) {
            turn = fabs(seg->sweep) * (tb - ta);
            amplitude[2] = hypot(seg->center[0] - f->com[0], seg->center[1] - f->com[1]) /
                           f->gyration_radius;
        }
    }
    double bulge = turn > 0 ? 1 - cos(0.5 * turn) : 0;
    for (int j = 0; j < 3; j++) {
        double e = amplitude[j] * bulge + 1e-15 * (fabs(w[0][j]) + fabs(w[1][j]) + 1e-300);
        lo[j] = fmin(w[0][j], w[1][j]) - e;
        hi[j] = fmax(w[0][j], w[1][j]) + e;
    }
}

static bool append_region(wr_regions *out, int edge, double t0, double t1)
{
    if (out->count > 0 && out->items[out->count - 1].edge == edge &&
        out->items[out->count - 1].t1 == t0) {
        out->items[out->count - 1].t1 = t1;
        return true;
    }
    if (out->count == out->capacity) {
        int capacity = out->capacity ? 2 * out->capacity : 16;
        wr_region *items = realloc(out->items, sizeof *items * (size_t)capacity);
        if (!items)
            return false;
        out->items = items;
        out->capacity = capacity;
    }
    out->items[out->count++] = (wr_region){edge, t0, t1};
    return true;
}

/* A family of wrenches over a parameter interval, as a box. */
typedef void (*family_fn)(const void *context, double ta, double tb, double lo[3], double hi[3]);

/* What a sink says of a piece given to it. */
enum { KEEP_MORE, KEEP_FAILED, KEEP_ENOUGH };

/* The pieces of [t0, t1], bisected down to 2^-depth of it (depth at most
 * WR_ROBUST_DEPTH), whose family is proved robustly inside, each passed to
 * `keep` in order, until it says KEEP_ENOUGH (or KEEP_FAILED: no memory). */
static wr_status bisect(const wr_robust *rb, wr_set set, double t0, double t1, family_fn family,
                        const void *context, const wr_stop *stop, int depth, int leaf_budget,
                        int (*keep)(void *sink, double t0, double t1), void *sink)
{
    assert(depth >= 0 && depth <= WR_ROBUST_DEPTH);
    struct piece {
        double t0, t1;
        int depth;
    } stack[2 * WR_ROBUST_DEPTH + 2];
    int top = 0;
    stack[top++] = (struct piece){t0, t1, 0};
    /* Neighbouring pieces share certificates: one cache per cone. */
    certificate *caches = calloc((size_t)(rb->cone_count[0] + rb->cone_count[1]) + 1,
                                 sizeof *caches);
    if (!caches)
        return WR_NO_MEMORY;
    wr_status result = WR_OK;
    while (top > 0 && result == WR_OK) {
        struct piece p = stack[--top];
        if (wr_stop_requested(stop)) {
            result = WR_STOPPED;
            break;
        }
        double lo[3], hi[3];
        family(context, p.t0, p.t1, lo, hi);
        wr_status status;
        /* A piece that one box per cone does not prove is split along the
         * family first: the boxes of the set are split (the whole budget)
         * only for the finest pieces. */
        int budget = p.depth < depth ? 1 : leaf_budget;
        if (box_inside(rb, lo, hi, set, WR_DEFAULT_TOLERANCE, caches, budget, &status)) {
            int kept = keep(sink, p.t0, p.t1);
            if (kept == KEEP_FAILED)
                result = WR_NO_MEMORY;
            else if (kept == KEEP_ENOUGH)
                break;
            continue;
        }
        if (status != WR_OK) {
            result = status;
            break;
        }
        if (p.depth < depth) {
            /* Left piece on top, so that pieces come out in order. */
            double mid = 0.5 * (p.t0 + p.t1);
            stack[top++] = (struct piece){mid, p.t1, p.depth + 1};
            stack[top++] = (struct piece){p.t0, mid, p.depth + 1};
        }
    }
    free(caches);
    return result;
}

typedef struct region_family {
    const wr_fixture *fixture;
    int edge;
    bool gravity;
} region_family;

static void region_box(const void *context, double ta, double tb, double lo[3], double hi[3])
{
    const region_family *r = context;
    family_box(r->fixture, r->edge, r->gravity, ta, tb, lo, hi);
}

typedef struct region_sink {
    wr_regions *out;
    int edge;
} region_sink;

static int keep_region(void *sink, double t0, double t1)
{
    region_sink *r = sink;
    return append_region(r->out, r->edge, t0, t1) ? KEEP_MORE : KEEP_FAILED;
}

wr_status wr_robust_regions(const wr_robust *rb, wr_set set, const wr_regions *nominal,
                            bool gravity, const wr_stop *stop, wr_regions *out)
{
    memset(out, 0, sizeof *out);
    out->resolution = nominal->resolution;
    for (int r = 0; r < nominal->count; r++) {
        const wr_region *region = &nominal->items[r];
        region_family family = {rb->fixture, region->edge, gravity};
        region_sink sink = {out, region->edge};
        wr_status status = bisect(rb, set, region->t0, region->t1, region_box, &family, stop,
                                  WR_ROBUST_DEPTH, rb->budget, keep_region, &sink);
        if (status != WR_OK) {
            wr_regions_release(out);
            return status;
        }
    }
    return WR_OK;
}

static int keep_first(void *sink, double t0, double t1)
{
    (void)t0;
    (void)t1;
    *(bool *)sink = true;
    return KEEP_ENOUGH;
}

wr_status wr_robust_regions_meet(const wr_robust *rb, wr_set set, const wr_regions *candidates,
                                 bool gravity, int depth, const wr_stop *stop, bool *found)
{
    *found = false;
    if (depth < 0 || depth > WR_ROBUST_DEPTH)
        return WR_INVALID;
    for (int r = 0; r < candidates->count && !*found; r++) {
        const wr_region *region = &candidates->items[r];
        region_family family = {rb->fixture, region->edge, gravity};
        wr_status status = bisect(rb, set, region->t0, region->t1, region_box, &family, stop,
                                  depth, rb->budget, keep_first, found);
        if (status != WR_OK) {
            *found = false;
            return status;
        }
    }
    return WR_OK;
}

/* Magnitudes F of load + F push, on the parameter s = F / (F + c) in
 * [0, 1] (c > 0 a force of the problem's size): (1 - s) L + s c u is
 * (L + F u) c / (F + c), the same direction, and affine in s, so its box
 * over [sa, sb] is its ends'.  `push` holds c u. */
typedef struct force_family {
    double load[3], push[3], c;
} force_family;

static void force_box(const void *context, double sa, double sb, double lo[3], double hi[3])
{
    const force_family *f = context;
    for (int j = 0; j < 3; j++) {
        double a = (1 - sa) * f->load[j] + sa * f->push[j];
        double b = (1 - sb) * f->load[j] + sb * f->push[j];
        double e = 1e-15 * (fabs(a) + fabs(b) + 1e-300);
        lo[j] = fmin(a, b) - e;
        hi[j] = fmax(a, b) + e;
    }
}

typedef struct force_sink {
    wr_forces *out;
    double c;
    bool first_only; /* the least magnitude is all that is asked */
} force_sink;

static double magnitude(double s, double c) { return s >= 1 ? INFINITY : c * s / (1 - s); }

static int keep_force(void *sink, double s0, double s1)
{
    force_sink *f = sink;
    wr_forces *out = f->out;
    double lo = magnitude(s0, f->c), hi = magnitude(s1, f->c);
    if (out->count > 0 && out->items[out->count - 1].hi == lo) {
        out->items[out->count - 1].hi = hi;
        return KEEP_MORE;
    }
    if (out->count == out->capacity) {
        int capacity = out->capacity ? 2 * out->capacity : 8;
        wr_force_interval *items = realloc(out->items, sizeof *items * (size_t)capacity);
        if (!items)
            return KEEP_FAILED;
        out->items = items;
        out->capacity = capacity;
    }
    out->items[out->count++] = (wr_force_interval){lo, hi};
    return f->first_only ? KEEP_ENOUGH : KEEP_MORE;
}

#define LEAST_LEAF_BUDGET 8

/* wr_robust_forces, or with `first_only` its first interval's first
 * piece alone (its lower end the least robust magnitude proved). */
static wr_status robust_forces(const wr_robust *rb, wr_set set, const double load[3],
                               const double push[3], const wr_forces *nominal,
                               const wr_stop *stop, bool first_only, wr_forces *out)
{
    out->count = 0;
    const wr_fixture *f = rb->fixture;
    force_family family;
    memcpy(family.load, load, sizeof family.load);
    memcpy(family.push, push, sizeof family.push);
    family.load[2] /= f->gyration_radius;
    family.push[2] /= f->gyration_radius;
    double lengths[2] = {wr_norm3(family.load), wr_norm3(family.push)};
    family.c = lengths[0] > 0 && lengths[1] > 0 ? lengths[0] / lengths[1] : 1;
    for (int j = 0; j < 3; j++)
        family.push[j] *= family.c;
    force_sink sink = {out, family.c, first_only};
    for (int i = 0; i < nominal->count && !(first_only && out->count > 0); i++) {
        const wr_force_interval *g = &nominal->items[i];
        double s0 = g->lo / (g->lo + family.c);
        double s1 = isinf(g->hi) ? 1 : g->hi / (g->hi + family.c);
        /* The least alone: a magnitude no piece proves costs every
         * finest piece its boxes, so those get a few only (the least is
         * then proved where fewer boxes suffice, a little higher at most). */
        wr_status status = bisect(rb, set, s0, s1, force_box, &family, stop, WR_ROBUST_DEPTH,
                                  first_only ? LEAST_LEAF_BUDGET : rb->budget, keep_force, &sink);
        if (status != WR_OK) {
            out->count = 0;
            return status;
        }
    }
    return WR_OK;
}

wr_status wr_robust_forces(const wr_robust *rb, wr_set set, const double load[3],
                           const double push[3], const wr_forces *nominal, const wr_stop *stop,
                           wr_forces *out)
{
    return robust_forces(rb, set, load, push, nominal, stop, false, out);
}

wr_status wr_robust_least_force_at(const wr_robust *rb, wr_set set, const double (*loads)[3],
                                   int case_count, const double push[3], const wr_stop *stop,
                                   double *force)
{
    *force = INFINITY;
    wr_forces all = {0}, nominal = {0}, robust = {0}, meet = {0};
    wr_status status = WR_OK;
    for (int c = 0; status == WR_OK && c < case_count; c++) {
        status = wr_force_range(rb->analysis, set, loads[c], push, 0, INFINITY, &nominal);
        /* One case: the first piece proved is the least (pieces come in
         * order); with more, their intersection needs each whole. */
        if (status == WR_OK)
            status = robust_forces(rb, set, loads[c], push, &nominal, stop, case_count == 1,
                                   &robust);
        if (status != WR_OK)
            break;
        if (c > 0) {
            status = wr_forces_intersect(&all, &robust, &meet);
            wr_forces swap = all;
            all = meet;
            meet = swap;
        } else {
            wr_forces swap = all;
            all = robust;
            robust = swap;
        }
        if (all.count == 0)
            break; /* no magnitude for the cases so far */
    }
    if (status == WR_OK && all.count > 0)
        *force = all.items[0].lo;
    wr_forces_release(&all);
    wr_forces_release(&nominal);
    wr_forces_release(&robust);
    wr_forces_release(&meet);
    return status;
}

/* ---- friction sweeps --------------------------------------------------- */

/* Is the wrench robustly inside for every mu of [m0, m1]? */
static wr_status mu_piece_inside(const wr_fixture *fixture, const wr_fixel_spec *fixels,
                                 double ratio, const double wrench[3], wr_set set, double m0,
                                 double m1, bool *inside)
{
    *inside = false;
    wr_friction_spec friction = {.given = true, .static_mu = m1, .static_interval = m0 < m1,
                                 .static_min = m0, .kinetic_given = true,
                                 .kinetic_mu = ratio * m1, .kinetic_interval = m0 < m1,
                                 .kinetic_min = ratio * m0};
    wr_fixture placed;
    wr_error error;
    wr_status status = wr_fixture_place(fixture, fixels, (size_t)fixture->fixel_count, &friction,
                                        &placed, &error);
    if (status == WR_OK)
        status = wr_fixture_set_tolerance(&placed, &fixture->tolerance, &error);
    wr_analysis *analysis = NULL;
    wr_robust *robust = NULL;
    if (status == WR_OK)
        status = wr_analysis_new(&placed, &analysis);
    if (status == WR_OK)
        status = wr_robust_new(analysis, 0, &robust);
    wr_robust_answer answer;
    if (status == WR_OK)
        status = wr_robust_classify(robust, wrench, set, WR_DEFAULT_TOLERANCE, &answer);
    if (status == WR_OK)
        *inside = answer.answer.verdict == WR_VERDICT_INSIDE;
    wr_robust_free(robust);
    wr_analysis_free(analysis);
    return status;
}

wr_status wr_robust_sweep_wrench(const wr_fixture *fixture, const wr_fixel_spec *fixels,
                                 double kinetic_ratio, const double wrench[3], wr_set set,
                                 const wr_intervals *nominal, const wr_stop *stop,
                                 wr_intervals *out)
{
    out->count = 0;
    wr_status status = WR_OK;
    for (int i = 0; status == WR_OK && i < nominal->count; i++) {
        struct piece {
            double m0, m1;
            int depth;
        } stack[2 * WR_ROBUST_DEPTH + 2];
        int top = 0;
        stack[top++] = (struct piece){nominal->items[i][0], nominal->items[i][1], 0};
        while (top > 0 && status == WR_OK) {
            struct piece p = stack[--top];
            if (wr_stop_requested(stop)) {
                status = WR_STOPPED;
                break;
            }
            bool inside;
            status = mu_piece_inside(fixture, fixels, kinetic_ratio, wrench, set, p.m0, p.m1,
                                     &inside);
            if (status != WR_OK)
                break;
            if (inside) {
                if (!wr_intervals_append(out, p.m0, p.m1))
                    status = WR_NO_MEMORY;
            } else if (p.depth < WR_ROBUST_DEPTH) {
                /* Left piece on top, so that pieces come out in order. */
                double mid = 0.5 * (p.m0 + p.m1);
                stack[top++] = (struct piece){mid, p.m1, p.depth + 1};
                stack[top++] = (struct piece){p.m0, mid, p.depth + 1};
            }
        }
    }
    if (status != WR_OK)
        out->count = 0;
    return status;
}
