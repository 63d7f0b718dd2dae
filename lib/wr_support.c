/* wr_support.c -- friction at the supports under a part on a base plate
 * (wr_support.h; docs/MODEL.md section 11). */
#include "wr_support.h"

#include "wr_internal.h"
#include "wr_outline.h"

#include <glpk.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ---- statics out of the plane ------------------------------------------ */

static bool inside_part(const wr_fixture *f, const double p[2])
{
    if (f->shape == WR_SHAPE_CIRCLE)
        return hypot(p[0] - f->center[0], p[1] - f->center[1]) <= f->radius;
    if (f->outline)
        return wr_outline_contains(f->outline, p, 0.0) ||
               wr_outline_distance(f->outline, p) <= 1e-12 * f->size;
    return true; /* no shape: nothing to be outside of */
}

static double segment_distance(const double a[2], const double b[2], const double p[2])
{
    double d[2] = {b[0] - a[0], b[1] - a[1]};
    double len2 = d[0] * d[0] + d[1] * d[1];
    double t = len2 > 0 ? ((p[0] - a[0]) * d[0] + (p[1] - a[1]) * d[1]) / len2 : 0;
    t = t < 0 ? 0 : t > 1 ? 1 : t;
    return hypot(a[0] + t * d[0] - p[0], a[1] + t * d[1] - p[1]);
}

/* Barycentric coordinates of c in triangle (a, b, d); false when the three
 * are (nearly) on a line. */
static bool barycentric(const double a[2], const double b[2], const double d[2], const double c[2],
                        double out[3])
{
    double det = (b[0] - a[0]) * (d[1] - a[1]) - (d[0] - a[0]) * (b[1] - a[1]);
    double scale = fmax(fabs(b[0] - a[0]) + fabs(b[1] - a[1]), fabs(d[0] - a[0]) + fabs(d[1] - a[1]));
    if (!(fabs(det) > 1e-12 * scale * scale))
        return false;
    double u = ((c[0] - a[0]) * (d[1] - a[1]) - (d[0] - a[0]) * (c[1] - a[1])) / det;
    double v = ((b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1])) / det;
    out[0] = 1 - u - v;
    out[1] = u;
    out[2] = v;
    return true;
}

/* The vertices of P: a vertex of {N >= 0, A N = b} with three rows has at
 * most three non-zero entries, on points whose triangle holds c; every
 * such triangle (of points not on a line) gives one, and a c on an edge or
 * a point is reached through any triangle having it. */
static wr_status distribution_vertices(wr_supports *s)
{
    int n = s->count;
    int capacity = n * (n - 1) * (n - 2) / 6;
    s->distributions = calloc((size_t)capacity + 1, sizeof s->distributions[0]);
    if (!s->distributions)
        return WR_NO_MEMORY;
    s->distribution_count = 0;
    if (s->total == 0) {
        s->distribution_count = 1;
        return WR_OK;
    }
    for (int i = 0; i < n; i++)
        for (int j = i + 1; j < n; j++)
            for (int k = j + 1; k < n; k++) {
                double w[3];
                if (!barycentric(s->points[i], s->points[j], s->points[k], s->pressure, w))
                    continue;
                if (w[0] < -1e-12 || w[1] < -1e-12 || w[2] < -1e-12)
                    continue;
                double row[WR_MAX_SUPPORTS] = {0};
                row[i] = fmax(w[0], 0) * s->total;
                row[j] = fmax(w[1], 0) * s->total;
                row[k] = fmax(w[2], 0) * s->total;
                bool seen = false;
                for (int v = 0; v < s->distribution_count && !seen; v++) {
                    double d = 0;
                    for (int m = 0; m < n; m++)
                        d = fmax(d, fabs(s->distributions[v][m] - row[m]));
                    seen = d <= 1e-12 * s->total;
                }
                if (!seen)
                    memcpy(s->distributions[s->distribution_count++], row, sizeof row);
            }
    return WR_OK;
}

wr_status wr_supports_new(const wr_fixture *fixture, const wr_support_spec *spec,
                          wr_supports **out, wr_error *error)
{
    *out = NULL;
    char field[64];
    if (spec->point_count < 3 || spec->point_count > WR_MAX_SUPPORTS) {
        wr_error_set(error, "points",
                     spec->point_count < 3 ? "at least 3 supports are needed to rest on"
                                           : "more supports than libwrench takes (16)");
        return WR_INVALID;
    }
    if (wr_friction_check(&spec->friction, "friction", error) != WR_OK)
        return WR_INVALID;
    if (!isfinite(spec->g) || spec->g < 0) {
        wr_error_set(error, "g", "must be a finite number >= 0 (gravity into the plate)");
        return WR_INVALID;
    }
    if (spec->down_count > WR_MAX_DOWN) {
        wr_error_set(error, "down", "more down clamps than libwrench takes (16)");
        return WR_INVALID;
    }
    wr_supports *s = calloc(1, sizeof *s);
    if (!s) {
        wr_error_set(error, "", "out of memory");
        return WR_NO_MEMORY;
    }
    s->count = (int)spec->point_count;
    for (int i = 0; i < s->count; i++) {
        s->points[i][0] = spec->points[i][0] + 0.0;
        s->points[i][1] = spec->points[i][1] + 0.0;
        snprintf(field, sizeof field, "points[%d]", i);
        if (!isfinite(s->points[i][0]) || !isfinite(s->points[i][1])) {
            wr_error_set(error, field, "must be finite");
            goto invalid;
        }
        if (!inside_part(fixture, s->points[i])) {
            wr_error_set(error, field, "is outside the part: a support must lie under it");
            goto invalid;
        }
    }
    const wr_friction_spec *fr = &spec->friction;
    s->mu_static = fr->static_mu + 0.0;
    s->mu_static_min = (fr->static_interval ? fr->static_min : fr->static_mu) + 0.0;
    if (fr->kinetic_given) {
        s->mu_kinetic = fr->kinetic_mu + 0.0;
        s->mu_kinetic_min = (fr->kinetic_interval ? fr->kinetic_min : fr->kinetic_mu) + 0.0;
    } else {
        s->mu_kinetic = s->mu_static;
        s->mu_kinetic_min = s->mu_static_min;
    }
    s->g = spec->g + 0.0;
    s->down_count = (int)spec->down_count;
    double moment[2] = {fixture->mass * s->g * fixture->com[0],
                        fixture->mass * s->g * fixture->com[1]};
    s->total = fixture->mass * s->g;
    for (int i = 0; i < s->down_count; i++) {
        s->down[i] = spec->down[i];
        snprintf(field, sizeof field, "down[%d].force", i);
        if (!isfinite(s->down[i].force) || s->down[i].force < 0) {
            wr_error_set(error, field, "must be a finite number >= 0 (a force into the plate)");
            goto invalid;
        }
        snprintf(field, sizeof field, "down[%d].at", i);
        if (!isfinite(s->down[i].at[0]) || !isfinite(s->down[i].at[1]) ||
            !inside_part(fixture, s->down[i].at)) {
            wr_error_set(error, field, "is outside the part: a down clamp must press on it");
            goto invalid;
        }
        double force = s->down[i].force * wr_fixture_force_factor(fixture);
        s->total += force;
        moment[0] += force * s->down[i].at[0];
        moment[1] += force * s->down[i].at[1];
    }
    bool spread = false;
    for (int i = 2; i < s->count && !spread; i++) {
        double w[3];
        for (int j = 1; j < i && !spread; j++)
            for (int k = 0; k < j && !spread; k++)
                spread = barycentric(s->points[k], s->points[j], s->points[i], s->points[0], w);
    }
    if (!spread) {
        wr_error_set(error, "points", "the supports lie on one line: the part would tip over it");
        goto invalid;
    }
    if (s->total > 0) {
        s->pressure[0] = moment[0] / s->total;
        s->pressure[1] = moment[1] / s->total;
    } else {
        s->pressure[0] = fixture->com[0];
        s->pressure[1] = fixture->com[1];
    }
    if (distribution_vertices(s) != WR_OK) {
        wr_supports_free(s);
        wr_error_set(error, "", "out of memory");
        return WR_NO_MEMORY;
    }
    if (s->distribution_count == 0) {
        double d = INFINITY;
        for (int i = 0; i < s->count; i++)
            for (int j = i + 1; j < s->count; j++)
                d = fmin(d, segment_distance(s->points[i], s->points[j], s->pressure));
        char reason[160];
        snprintf(reason, sizeof reason,
                 "the centre of pressure (%.9g, %.9g) is %.6g outside the supports' polygon: the "
                 "part tips",
                 s->pressure[0], s->pressure[1], d);
        wr_error_set(error, "points", "%s", reason);
        goto invalid;
    }
    for (int i = 0; i < s->count; i++) {
        s->normal_min[i] = INFINITY;
        s->normal_max[i] = 0;
        for (int v = 0; v < s->distribution_count; v++) {
            s->normal_min[i] = fmin(s->normal_min[i], s->distributions[v][i]);
            s->normal_max[i] = fmax(s->normal_max[i], s->distributions[v][i]);
        }
    }
    *out = s;
    return WR_OK;
invalid:
    wr_supports_free(s);
    return WR_INVALID;
}

wr_status wr_fixture_set_supports(wr_fixture *fixture, const wr_support_spec *spec,
                                  wr_error *error)
{
    wr_supports *s;
    wr_status status = wr_supports_new(fixture, spec, &s, error);
    if (status != WR_OK)
        return status;
    wr_supports_free(fixture->supports);
    fixture->supports = s;
    return WR_OK;
}

/* Support i's lever arm (p_i - com). */
static void arm(const wr_fixture *f, const wr_supports *s, int i, double r[2])
{
    r[0] = s->points[i][0] - f->com[0];
    r[1] = s->points[i][1] - f->com[1];
}

double wr_supports_support_function(const wr_fixture *fixture, const wr_supports *supports,
                                    const double row[3])
{
    double best = 0;
    for (int v = 0; v < supports->distribution_count; v++) {
        double sum = 0;
        for (int i = 0; i < supports->count; i++) {
            double r[2];
            arm(fixture, supports, i, r);
            sum += supports->mu_static * supports->distributions[v][i] *
                   hypot(row[0] - row[2] * r[1], row[1] + row[2] * r[0]);
        }
        best = fmax(best, sum);
    }
    return best;
}

/* ---- a small LP builder over GLPK ---------------------------------------- */

typedef struct lp {
    glp_prob *p;
    int rows, cols;
    int count, capacity; /* triplets, 1-based as GLPK's */
    int *ia, *ja;
    double *ar;
    bool failed;         /* out of memory */
} lp;

static void lp_init(lp *l, int direction)
{
    memset(l, 0, sizeof *l);
    l->p = glp_create_prob();
    glp_set_obj_dir(l->p, direction);
}

static void lp_release(lp *l)
{
    if (l->p)
        glp_delete_prob(l->p);
    free(l->ia);
    free(l->ja);
    free(l->ar);
    memset(l, 0, sizeof *l);
}

/* A column with bounds (type GLP_LO etc.) and objective coefficient. */
static int lp_col(lp *l, int type, double lo, double hi, double objective)
{
    int j = glp_add_cols(l->p, 1);
    glp_set_col_bnds(l->p, j, type, lo, hi);
    glp_set_obj_coef(l->p, j, objective);
    l->cols = j;
    return j;
}

static int lp_row(lp *l, int type, double lo, double hi)
{
    int i = glp_add_rows(l->p, 1);
    glp_set_row_bnds(l->p, i, type, lo, hi);
    l->rows = i;
    return i;
}

static void lp_set(lp *l, int row, int col, double value)
{
    if (value == 0 || l->failed)
        return;
    if (l->count + 2 > l->capacity) {
        int capacity = l->capacity ? 2 * l->capacity : 256;
        int *ia = realloc(l->ia, (size_t)capacity * sizeof *ia);
        if (ia)
            l->ia = ia;
        int *ja = realloc(l->ja, (size_t)capacity * sizeof *ja);
        if (ja)
            l->ja = ja;
        double *ar = realloc(l->ar, (size_t)capacity * sizeof *ar);
        if (ar)
            l->ar = ar;
        if (!ia || !ja || !ar) {
            l->failed = true;
            return;
        }
        l->capacity = capacity;
    }
    l->count++;
    l->ia[l->count] = row;
    l->ja[l->count] = col;
    l->ar[l->count] = value;
}

/* Solve: GLP_OPT, GLP_NOFEAS, GLP_UNBND, or -1 (no memory or a failed
 * solve). */
static int lp_solve(lp *l)
{
    if (l->failed)
        return -1;
    glp_load_matrix(l->p, l->count, l->ia, l->ja, l->ar);
    glp_smcp parm;
    glp_init_smcp(&parm);
    parm.msg_lev = GLP_MSG_OFF;
    parm.presolve = GLP_OFF;
    /* The discs' bounds are refined to 1e-9 and beyond: GLPK's default
     * feasibility tolerance (1e-7) would hide the rest. */
    parm.it_lim = 5000;
    for (int attempt = 0; attempt < 3; attempt++) {
        /* Tight tolerances first; GLPK's own (with scaling) if they stall,
         * which on a degenerate problem they can. */
        parm.tol_bnd = attempt < 2 ? 1e-12 : 1e-7;
        parm.tol_dj = attempt < 2 ? 1e-12 : 1e-7;
        glp_std_basis(l->p);
        if (attempt)
            glp_scale_prob(l->p, GLP_SF_AUTO);
        int rc = glp_simplex(l->p, &parm);
        if (rc != 0)
            continue;
        int status = glp_get_status(l->p);
        if (status == GLP_OPT || status == GLP_NOFEAS || status == GLP_UNBND)
            return status;
    }
    return -1;
}

/* ---- the common model ---------------------------------------------------- */

/* A disc's directions: angles, refined by the solutions met. */
#define MAX_DIRECTIONS 160
#define PI 3.14159265358979323846
typedef struct directions {
    int count;
    double angle[MAX_DIRECTIONS];
} directions;

static void directions_start(directions *d)
{
    d->count = 8;
    for (int k = 0; k < 8; k++)
        d->angle[k] = k * (PI / 4);
}

/* Add the direction of (x, y); false when it is (nearly) there already or
 * there is no room. */
static bool directions_add(directions *d, double x, double y)
{
    if (!(hypot(x, y) > 0) || d->count == MAX_DIRECTIONS)
        return false;
    double a = atan2(y, x);
    for (int k = 0; k < d->count; k++) {
        double diff = remainder(a - d->angle[k], 2 * PI);
        if (fabs(diff) < 1e-13)
            return false;
    }
    d->angle[d->count++] = a;
    return true;
}

/* What the LPs share: the fixture, the supports and the scale. */
typedef struct model {
    const wr_fixture *f;
    const wr_supports *s;
    double scale;                         /* wrenches and forces are divided by it */
    double unit[WR_MAX_SUPPORTS][2][3];   /* scaled wrench of a unit force along x, y */
} model;

static void model_init(model *m, const wr_fixture *f, const wr_supports *s, double scale)
{
    m->f = f;
    m->s = s;
    m->scale = scale;
    for (int i = 0; i < s->count; i++) {
        double r[2];
        arm(f, s, i, r);
        double rho = f->gyration_radius;
        double ux[3] = {1, 0, -r[1] / rho}, uy[3] = {0, 1, r[0] / rho};
        memcpy(m->unit[i][0], ux, sizeof ux);
        memcpy(m->unit[i][1], uy, sizeof uy);
    }
}

/* Columns theta_v >= 0 of the distributions, with objective `objective`
 * each; returns the first. */
static int distribution_columns(lp *l, const model *m, double objective)
{
    int first = 0;
    for (int v = 0; v < m->s->distribution_count; v++) {
        int j = lp_col(l, GLP_LO, 0, 0, objective);
        if (v == 0)
            first = j;
    }
    return first;
}

/* sum_v theta_v N^v_i * factor / scale, into row `row`. */
static void add_normal(lp *l, const model *m, int row, int theta, int i, double factor)
{
    for (int v = 0; v < m->s->distribution_count; v++)
        lp_set(l, row, theta + v, factor * m->s->distributions[v][i] / m->scale);
}

/* The friction force (fx, fy) of support i within the disc |f| <= mu_s N_i:
 * from outside (one row per direction) or from inside (a convex
 * combination of the polygon's vertices).  `wrench` are the three equality
 * rows, to which the force contributes its scaled wrench.  Returns the
 * column of fx (fy follows). */
static int disc_columns(lp *l, const model *m, int i, const directions *d, bool inner,
                        int theta, const int wrench[3])
{
    int fx = lp_col(l, GLP_FR, 0, 0, 0);
    int fy = lp_col(l, GLP_FR, 0, 0, 0);
    for (int k = 0; k < 3; k++) {
        lp_set(l, wrench[k], fx, m->unit[i][0][k]);
        lp_set(l, wrench[k], fy, m->unit[i][1][k]);
    }
    double mu = m->s->mu_static;
    if (!inner) {
        for (int k = 0; k < d->count; k++) {
            int row = lp_row(l, GLP_UP, 0, 0);
            lp_set(l, row, fx, cos(d->angle[k]));
            lp_set(l, row, fy, sin(d->angle[k]));
            add_normal(l, m, row, theta, i, -mu);
        }
    } else {
        int rx = lp_row(l, GLP_FX, 0, 0), ry = lp_row(l, GLP_FX, 0, 0);
        int total = lp_row(l, GLP_UP, 0, 0);
        lp_set(l, rx, fx, 1);
        lp_set(l, ry, fy, 1);
        add_normal(l, m, total, theta, i, -mu);
        for (int k = 0; k < d->count; k++) {
            int eta = lp_col(l, GLP_LO, 0, 0, 0);
            lp_set(l, rx, eta, -cos(d->angle[k]));
            lp_set(l, ry, eta, -sin(d->angle[k]));
            lp_set(l, total, eta, 1);
        }
    }
    return fx;
}

/* ---- seating ------------------------------------------------------------- */

/* What one LP of a cone asks: the least scale rho (RHO), the least or
 * largest push magnitude (F_MIN, F_MAX), or the largest alpha + beta with
 * alpha u + beta u2 in C + S, alpha, beta >= 0 (SECTOR: how far the sector
 * between two pure forces reaches into C + S's slice at zero torque). */
typedef enum question { RHO, F_MIN, F_MAX, SECTOR } question;

typedef struct cone_lp {
    const model *m;
    const wr_cone *cone;
    question q;
    double target[3];   /* h(g) / scale, or h(L) / scale */
    double push[3];     /* h(u) / |h(u)| */
    double second[3];   /* SECTOR's u2, as push */
    bool inner;
    const directions *dirs; /* one per support */
    /* out */
    int status;         /* GLP_OPT, GLP_NOFEAS, GLP_UNBND, -1 */
    double value;
    double force[WR_MAX_SUPPORTS][2];
} cone_lp;

static void cone_lp_solve(cone_lp *c)
{
    const model *m = c->m;
    lp l;
    lp_init(&l, c->q == F_MAX || c->q == SECTOR ? GLP_MAX : GLP_MIN);
    int wrench[3];
    for (int k = 0; k < 3; k++)
        wrench[k] = lp_row(&l, GLP_FX, c->target[k], c->target[k]);
    for (int j = 0; j < c->cone->generator_count; j++) {
        int col = lp_col(&l, GLP_LO, 0, 0, 0);
        for (int k = 0; k < 3; k++)
            lp_set(&l, wrench[k], col, c->cone->generators[j][k]);
    }
    int theta = distribution_columns(&l, m, c->q == RHO ? 1 : 0);
    if (c->q != RHO) {
        int one = lp_row(&l, GLP_FX, 1, 1);
        for (int v = 0; v < m->s->distribution_count; v++)
            lp_set(&l, one, theta + v, 1);
    }
    int fx[WR_MAX_SUPPORTS];
    for (int i = 0; i < m->s->count; i++)
        fx[i] = disc_columns(&l, m, i, &c->dirs[i], c->inner, theta, wrench);
    int magnitude = 0;
    if (c->q != RHO) {
        magnitude = lp_col(&l, GLP_LO, 0, 0, 1);
        for (int k = 0; k < 3; k++)
            lp_set(&l, wrench[k], magnitude, -c->push[k]);
    }
    if (c->q == SECTOR) {
        int beta = lp_col(&l, GLP_LO, 0, 0, 1);
        for (int k = 0; k < 3; k++)
            lp_set(&l, wrench[k], beta, -c->second[k]);
    }
    c->status = lp_solve(&l);
    if (c->status == GLP_OPT) {
        c->value = glp_get_obj_val(l.p);
        for (int i = 0; i < m->s->count; i++) {
            c->force[i][0] = glp_get_col_prim(l.p, fx[i]);
            c->force[i][1] = glp_get_col_prim(l.p, fx[i] + 1);
        }
    }
    lp_release(&l);
}

/* The bracket [lo, hi] of one cone's optimum, the disc polygons refined
 * from the outer solutions until hi - lo <= tolerance * max(1, |lo|), or
 * until `decided` says the bracket is enough.  Infeasible from outside:
 * lo = hi = the value of "no answer" (INFINITY for RHO and F_MIN, -INFINITY
 * for F_MAX); unbounded (F_MAX): +INFINITY.  Returns WR_OK or
 * WR_LP_FAILED. */
typedef bool (*bracket_decided)(double lo, double hi, void *context);

static wr_status cone_bracket(const model *m, const wr_cone *cone, question q, const double target[3],
                              const double push[3], const double *second, double tolerance,
                              bracket_decided decided,
                              void *context, double *lo, double *hi, int *solves)
{
    directions dirs[WR_MAX_SUPPORTS];
    for (int i = 0; i < m->s->count; i++)
        directions_start(&dirs[i]);
    bool largest = q == F_MAX || q == SECTOR;
    double none = largest ? -INFINITY : INFINITY;
    double sign = largest ? -1 : 1; /* sign * value: a minimum */
    double outer_best = -INFINITY, inner_best = INFINITY; /* of sign * value */
    bool retried = false;
    for (int round = 0; round < 60; round++) {
        cone_lp c = {.m = m, .cone = cone, .q = q, .dirs = dirs};
        memcpy(c.target, target, sizeof c.target);
        memcpy(c.push, push, sizeof c.push);
        if (second)
            memcpy(c.second, second, sizeof c.second);
        c.inner = false;
        cone_lp_solve(&c);
        (*solves)++;
        /* A refinement GLPK cannot solve leaves the bracket of the round
         * before: still bounds from both sides, only wider. */
        if (c.status < 0 && round == 0 && !retried) {
            /* A first polygon GLPK cannot solve (degenerate): once more
             * with 16 directions a disc, turned half a step. */
            retried = true;
            for (int i = 0; i < m->s->count; i++)
                for (int k = 0; k < 8; k++)
                    directions_add(&dirs[i], cos((k + 0.5) * (PI / 4)), sin((k + 0.5) * (PI / 4)));
            round--;
            continue;
        }
        if (c.status < 0)
            return round ? WR_OK : WR_LP_FAILED;
        if (c.status == GLP_NOFEAS) {
            *lo = *hi = none;
            return WR_OK;
        }
        if (c.status == GLP_UNBND) {
            *lo = *hi = INFINITY; /* only a largest can be unbounded from outside */
            if (!largest)
                return WR_LP_FAILED;
            /* Unbounded from inside too?  Any inner solution with a push
             * ray: ask the inner LP. */
        } else {
            outer_best = fmax(outer_best, sign * c.value);
        }
        cone_lp in = c;
        in.inner = true;
        cone_lp_solve(&in);
        (*solves)++;
        if (in.status < 0)
            return round ? WR_OK : WR_LP_FAILED;
        if (in.status == GLP_UNBND) {
            *lo = *hi = INFINITY;
            return WR_OK;
        }
        if (in.status == GLP_OPT)
            inner_best = fmin(inner_best, sign * in.value);
        /* The optimum lies in [outer_best, inner_best] (as a minimum). */
        double a = outer_best, b = inner_best;
        *lo = sign > 0 ? a : -b;
        *hi = sign > 0 ? b : -a;
        if (b - a <= tolerance * fmax(1, fabs(a)))
            return WR_OK;
        if (decided && decided(*lo, *hi, context))
            return WR_OK;
        bool added = false;
        if (c.status == GLP_OPT)
            for (int i = 0; i < m->s->count; i++) {
                double x = c.force[i][0], y = c.force[i][1];
                /* Only where the outer force leaves the disc. */
                double r = 0;
                for (int v = 0; v < m->s->distribution_count; v++)
                    r = fmax(r, m->s->distributions[v][i]);
                if (hypot(x, y) > 0 && r > 0)
                    added |= directions_add(&dirs[i], x, y);
                if (in.status == GLP_OPT)
                    added |= directions_add(&dirs[i], in.force[i][0], in.force[i][1]);
            }
        if (!added)
            return WR_OK;
    }
    return WR_OK;
}

static bool rho_decided(double lo, double hi, void *context)
{
    double tolerance = *(const double *)context;
    return lo > 1 + tolerance || hi < 1 - tolerance;
}

/* The scale of a problem: the wrench's and S's sizes. */
static double problem_scale(const wr_fixture *f, const wr_supports *s, const double wrench[3])
{
    double h[3];
    double n = wr_fixture_scale_wrench(f, wrench, h);
    return fmax(n, s->mu_static * s->total);
}

/* The model of one wrench's question, and the wrench in it (scaled metric,
 * divided by the model's scale). */
static void model_for(model *m, const wr_analysis *analysis, const wr_supports *supports,
                      const double wrench[3], double target[3])
{
    const wr_fixture *f = wr_analysis_fixture(analysis);
    model_init(m, f, supports, problem_scale(f, supports, wrench));
    wr_fixture_scale_wrench(f, wrench, target);
    for (int k = 0; k < 3; k++)
        target[k] /= m->scale;
}

typedef struct goal_call {
    const wr_analysis *analysis;
    const wr_supports *supports;
    const double *wrench;
    double tolerance;
    wr_support_goal *out;
} goal_call;

static wr_status goal_body(void *context)
{
    goal_call *call = context;
    model m;
    double target[3];
    model_for(&m, call->analysis, call->supports, call->wrench, target);
    double push[3] = {0, 0, 0};
    wr_support_goal *out = call->out;
    out->verdict = WR_VERDICT_INSIDE;
    out->rho_lo = out->rho_hi = INFINITY;
    out->blocking = -1;
    int count = wr_analysis_cone_count(call->analysis, WR_SET_GOAL);
    for (int c = 0; c < count; c++) {
        const wr_cone *cone = wr_analysis_cone(call->analysis, WR_SET_GOAL, c);
        if (cone->empty)
            continue;
        double lo, hi;
        wr_status st = cone_bracket(&m, cone, RHO, target, push, NULL, call->tolerance, rho_decided,
                                    &call->tolerance, &lo, &hi, &out->solves);
        if (st != WR_OK)
            return st;
        wr_verdict v = lo > 1 + call->tolerance   ? WR_VERDICT_INSIDE
                       : hi < 1 - call->tolerance ? WR_VERDICT_OUTSIDE
                                                  : WR_VERDICT_BOUNDARY;
        /* The blocking cone: the worst verdict, then the least rho. */
        if (v > out->verdict || (v == out->verdict && lo < out->rho_lo)) {
            out->verdict = v;
            out->rho_lo = lo;
            out->rho_hi = hi;
            out->blocking = c;
        }
    }
    return WR_OK;
}

wr_status wr_supports_goal(const wr_analysis *analysis, const wr_supports *supports,
                           wr_lp_env *env, const double wrench[3], double tolerance,
                           wr_support_goal *out)
{
    memset(out, 0, sizeof *out);
    if (!isfinite(wrench[0]) || !isfinite(wrench[1]) || !isfinite(wrench[2]) ||
        !(tolerance >= 0))
        return WR_INVALID;
    if (supports->total == 0 || supports->mu_static == 0) {
        /* S = {0}: the cones alone. */
        wr_answer answer;
        wr_status st = wr_classify_margin(analysis, wrench, WR_SET_GOAL, tolerance, &answer);
        out->verdict = answer.verdict;
        out->blocking = answer.blocking;
        out->rho_lo = out->rho_hi = answer.verdict == WR_VERDICT_INSIDE ? INFINITY : 0;
        return st;
    }
    goal_call call = {analysis, supports, wrench, tolerance, out};
    return wr_lp_guarded(env, goal_body, &call);
}

/* ---- seating against the supports' friction coefficient ------------------ */

typedef struct limit_call {
    const wr_analysis *analysis;
    const wr_supports *supports; /* with mu_s = 1 */
    const double *wrench;
    double *bracket;
} limit_call;

static wr_status limit_body(void *context)
{
    limit_call *call = context;
    model m;
    double target[3], push[3] = {0, 0, 0};
    model_for(&m, call->analysis, call->supports, call->wrench, target);
    call->bracket[0] = call->bracket[1] = INFINITY;
    int count = wr_analysis_cone_count(call->analysis, WR_SET_GOAL), solves = 0;
    for (int c = 0; c < count; c++) {
        const wr_cone *cone = wr_analysis_cone(call->analysis, WR_SET_GOAL, c);
        if (cone->empty)
            continue;
        double lo, hi;
        wr_status st = cone_bracket(&m, cone, RHO, target, push, NULL, WR_DEFAULT_TOLERANCE, NULL,
                                    NULL, &lo, &hi, &solves);
        if (st == WR_LP_FAILED) {
            /* Unknown for this cone: no coefficient is proved to seat. */
            lo = 0;
            hi = INFINITY;
        } else if (st != WR_OK) {
            return st;
        }
        call->bracket[0] = fmin(call->bracket[0], lo);
        call->bracket[1] = fmin(call->bracket[1], hi);
    }
    return WR_OK;
}

wr_status wr_supports_friction_limit(const wr_analysis *analysis, const wr_supports *supports,
                                     wr_lp_env *env, const double wrench[3], double bracket[2])
{
    if (!isfinite(wrench[0]) || !isfinite(wrench[1]) || !isfinite(wrench[2]))
        return WR_INVALID;
    if (supports->total == 0) {
        /* S = {0} whatever mu_B: the cones alone. */
        wr_verdict v;
        wr_status st = wr_classify_verdict(analysis, wrench, WR_SET_GOAL, WR_DEFAULT_TOLERANCE, &v);
        bracket[0] = bracket[1] = v == WR_VERDICT_INSIDE ? INFINITY : 0;
        return st;
    }
    /* S scales with mu_s: at mu_s = 1 the least scale rho* of S that
     * reaches a cone is the coefficient where seating ends. */
    wr_supports unit = *supports; /* shares the distributions */
    unit.mu_static = unit.mu_static_min = 1;
    limit_call call = {analysis, &unit, wrench, bracket};
    return wr_lp_guarded(env, limit_body, &call);
}

void wr_supports_with_friction(const wr_supports *supports, double mu, wr_supports *out)
{
    *out = *supports;
    out->mu_static = out->mu_static_min = out->mu_kinetic = out->mu_kinetic_min = mu;
}

/* ---- magnitudes along a push --------------------------------------------- */

static wr_status forces_append(wr_forces *out, double lo, double hi)
{
    if (out->count == out->capacity) {
        int capacity = out->capacity ? 2 * out->capacity : 8;
        wr_force_interval *items = realloc(out->items, (size_t)capacity * sizeof *items);
        if (!items)
            return WR_NO_MEMORY;
        out->items = items;
        out->capacity = capacity;
    }
    out->items[out->count++] = (wr_force_interval){lo, hi};
    return WR_OK;
}

static int interval_order(const void *a, const void *b)
{
    const wr_force_interval *x = a, *y = b;
    return (x->lo > y->lo) - (x->lo < y->lo);
}

/* The complement in [lo, hi] of the union of closed intervals `excluded`
 * (sorted here), as open intervals, into `good`. */
static wr_status complement(wr_forces *excluded, double lo, double hi, wr_forces *good)
{
    if (excluded->count > 0) /* none: items may be NULL, which qsort may not take */
        qsort(excluded->items, (size_t)excluded->count, sizeof excluded->items[0], interval_order);
    good->count = 0;
    double at = lo;
    for (int i = 0; i < excluded->count && at < hi; i++) {
        const wr_force_interval *e = &excluded->items[i];
        if (e->hi < at)
            continue;
        if (e->lo > at && forces_append(good, at, fmin(e->lo, hi)) != WR_OK)
            return WR_NO_MEMORY;
        at = fmax(at, e->hi);
    }
    if (at < hi && forces_append(good, at, hi) != WR_OK)
        return WR_NO_MEMORY;
    return WR_OK;
}

/* One cone's magnitudes along a line L + F u (F >= 0, in the units of the
 * force asked): from outside, a closed interval [out_lo, out_hi] holding
 * every F with L + F u in C + S; from inside, [in_lo, in_hi], every F of
 * which is in C + S (none when in_lo > in_hi).  `reached` false: no F
 * reaches C + S even from outside (the cone is then no constraint). */
typedef struct cone_span {
    bool reached;
    double out_lo, out_hi, in_lo, in_hi;
} cone_span;

/* The spans of every goal cone (empty cones unreached) along load + F push,
 * into spans[count of goal cones].  Runs GLPK: call within wr_lp_guarded.
 * Returns WR_OK or WR_LP_FAILED. */
static wr_status line_spans(const wr_analysis *analysis, const wr_supports *supports,
                            const double load[3], const double push[3], double tolerance,
                            cone_span *spans, int *solves)
{
    const wr_fixture *f = wr_analysis_fixture(analysis);
    double hu[3], hl[3];
    double push_length = wr_fixture_scale_wrench(f, push, hu);
    double scale = fmax(problem_scale(f, supports, load), push_length);
    model m;
    model_init(&m, f, supports, scale);
    wr_fixture_scale_wrench(f, load, hl);
    for (int k = 0; k < 3; k++) {
        hl[k] /= scale;
        hu[k] /= push_length;
    }
    /* Magnitudes in the LP: F' = F |h(u)| / scale. */
    double to_force = scale / push_length;
    int count = wr_analysis_cone_count(analysis, WR_SET_GOAL);
    for (int c = 0; c < count; c++) {
        cone_span *span = &spans[c];
        span->reached = false;
        const wr_cone *cone = wr_analysis_cone(analysis, WR_SET_GOAL, c);
        if (cone->empty)
            continue;
        double a_lo, a_hi, b_lo, b_hi;
        wr_status st = cone_bracket(&m, cone, F_MIN, hl, hu, NULL, tolerance, NULL, NULL,
                                    &a_lo, &a_hi, solves);
        if (st != WR_OK)
            return st;
        if (a_lo == INFINITY)
            continue; /* no magnitude reaches this cone */
        st = cone_bracket(&m, cone, F_MAX, hl, hu, NULL, tolerance, NULL, NULL, &b_lo, &b_hi,
                          solves);
        if (st != WR_OK)
            return st;
        /* Outer: [a_lo, b_hi] holds the cone's magnitudes; inner:
         * [a_hi, b_lo] is held by them (when not empty). */
        *span = (cone_span){true, a_lo * to_force, b_hi * to_force, a_hi * to_force,
                            b_lo * to_force};
    }
    return WR_OK;
}

typedef struct range_call {
    const wr_analysis *analysis;
    const wr_supports *supports;
    const double *load, *push;
    double lo, hi;
    wr_forces *outer, *inner; /* good magnitudes from the outer and inner excluded sets */
} range_call;

static wr_status range_body(void *context)
{
    range_call *call = context;
    int count = wr_analysis_cone_count(call->analysis, WR_SET_GOAL);
    cone_span *spans = malloc((size_t)(count ? count : 1) * sizeof *spans);
    if (!spans)
        return WR_NO_MEMORY;
    wr_forces outer_excluded = {0}, inner_excluded = {0};
    int solves = 0;
    wr_status st =
        line_spans(call->analysis, call->supports, call->load, call->push, WR_FORCE_TOLERANCE,
                   spans, &solves);
    for (int c = 0; c < count && st == WR_OK; c++) {
        const cone_span *span = &spans[c];
        if (!span->reached)
            continue;
        st = forces_append(&outer_excluded, span->out_lo, span->out_hi);
        if (st == WR_OK && span->in_lo <= span->in_hi)
            st = forces_append(&inner_excluded, span->in_lo, span->in_hi);
    }
    if (st == WR_OK)
        st = complement(&outer_excluded, call->lo, call->hi, call->outer);
    if (st == WR_OK && call->inner)
        st = complement(&inner_excluded, call->lo, call->hi, call->inner);
    wr_forces_release(&outer_excluded);
    wr_forces_release(&inner_excluded);
    free(spans);
    return st;
}

static wr_status range_both(const wr_analysis *analysis, const wr_supports *supports,
                            wr_lp_env *env, const double load[3], const double push[3], double lo,
                            double hi, wr_forces *outer, wr_forces *inner)
{
    outer->count = 0;
    if (inner)
        inner->count = 0;
    for (int k = 0; k < 3; k++)
        if (!isfinite(load[k]) || !isfinite(push[k]))
            return WR_INVALID;
    if ((push[0] == 0 && push[1] == 0 && push[2] == 0) || !(lo >= 0) || !(lo <= hi))
        return WR_INVALID;
    if (supports->total == 0 || supports->mu_static == 0) {
        wr_status st = wr_force_range(analysis, WR_SET_GOAL, load, push, lo, hi, outer);
        if (st == WR_OK && inner)
            st = wr_force_range(analysis, WR_SET_GOAL, load, push, lo, hi, inner);
        return st;
    }
    range_call call = {analysis, supports, load, push, lo, hi, outer, inner};
    return wr_lp_guarded(env, range_body, &call);
}

wr_status wr_supports_force_range(const wr_analysis *analysis, const wr_supports *supports,
                                  wr_lp_env *env, const double load[3], const double push[3],
                                  double lo, double hi, wr_forces *out)
{
    return range_both(analysis, supports, env, load, push, lo, hi, out, NULL);
}

wr_status wr_supports_least_force(const wr_analysis *analysis, const wr_supports *supports,
                                  wr_lp_env *env, const double (*loads)[3], int case_count,
                                  const double push[3], double *force, double *lower)
{
    *force = *lower = INFINITY;
    if (case_count < 1)
        return WR_INVALID;
    wr_forces sets[2][2] = {{{0}}}; /* [outer, inner][running, this case] */
    wr_forces scratch = {0};
    wr_status st = WR_OK;
    for (int c = 0; c < case_count && st == WR_OK; c++) {
        st = range_both(analysis, supports, env, loads[c], push, 0, INFINITY,
                        c ? &sets[0][1] : &sets[0][0], c ? &sets[1][1] : &sets[1][0]);
        for (int k = 0; k < 2 && st == WR_OK && c; k++) {
            st = wr_forces_intersect(&sets[k][0], &sets[k][1], &scratch);
            wr_forces swap = sets[k][0];
            sets[k][0] = scratch;
            scratch = swap;
        }
    }
    if (st == WR_OK) {
        if (sets[0][0].count)
            *force = sets[0][0].items[0].lo;
        if (sets[1][0].count)
            *lower = sets[1][0].items[0].lo;
    }
    for (int k = 0; k < 2; k++) {
        wr_forces_release(&sets[k][0]);
        wr_forces_release(&sets[k][1]);
    }
    wr_forces_release(&scratch);
    return st;
}

/* ---- the least push over the outline ------------------------------------ */

/* The spans' brackets in the search: a tenth of its own tolerance
 * (OUTLINE_TOLERANCE), so that a piece shrunk to a point is decided. */
#define OUTLINE_SPAN_TOLERANCE 1e-7

/* A point of an edge where the spans of every case were found: spans[case
 * * cones + cone].  Shared by the two intervals it ends (refs). */
typedef struct outline_point {
    int refs;
    double t;
    double upper; /* the least F from outside: pushes just above it seat */
    cone_span spans[];
} outline_point;

typedef struct outline_piece {
    double bound; /* no push on the piece seats below it */
    int edge;
    outline_point *p0, *p1;
} outline_piece;

typedef struct outline_call {
    const wr_analysis *analysis;
    const wr_supports *supports;
    const double (*loads)[3];
    int case_count, cones;
    const wr_finger *finger;
    const wr_stop *stop;
    wr_least_force *out;
    outline_piece *pieces; /* a min-heap by bound */
    int count, capacity;
    int solves;
} outline_call;

/* The end of the component holding 0 of the union of closed intervals
 * [lo[i], hi[i]]: 0 when none holds 0; INFINITY when the union from 0 has
 * no end. */
static double cover_from_zero(const double *lo, const double *hi, int n)
{
    double at = 0;
    bool covered = false;
    for (bool moved = true; moved && isfinite(at);) {
        moved = false;
        for (int i = 0; i < n; i++)
            if (lo[i] <= at && hi[i] > at) {
                at = hi[i];
                moved = covered = true;
            } else if (lo[i] <= at && hi[i] >= at) {
                covered = true;
            }
    }
    return covered ? at : 0;
}

static void point_release(outline_point *p)
{
    if (p && --p->refs == 0)
        free(p);
}

/* The spans at t of edge `edge` under every case, and the least force
 * from outside there (the component from 0 of the outer spans' union). */
static wr_status point_new(outline_call *c, int edge, double t, outline_point **out)
{
    const wr_fixture *f = wr_analysis_fixture(c->analysis);
    size_t spans = (size_t)c->case_count * (size_t)c->cones;
    outline_point *p = malloc(sizeof *p + spans * sizeof p->spans[0]);
    double *lo = malloc((spans ? spans : 1) * 2 * sizeof *lo);
    if (!p || !lo) {
        free(p);
        free(lo);
        return WR_NO_MEMORY;
    }
    p->refs = 1;
    p->t = t;
    double push[3];
    wr_push_wrench(f, edge, t, push);
    wr_status st = WR_OK;
    for (int k = 0; k < c->case_count && st == WR_OK; k++)
        st = line_spans(c->analysis, c->supports, c->loads[k], push, OUTLINE_SPAN_TOLERANCE,
                        &p->spans[k * c->cones], &c->solves);
    int n = 0;
    double *hi = lo + spans;
    for (size_t i = 0; st == WR_OK && i < spans; i++)
        if (p->spans[i].reached) {
            lo[n] = p->spans[i].out_lo;
            hi[n++] = p->spans[i].out_hi;
        }
    p->upper = cover_from_zero(lo, hi, n);
    free(lo);
    c->out->evaluations++;
    if (st != WR_OK) {
        free(p);
        return st;
    }
    *out = p;
    return WR_OK;
}

/* A lower bound on the least seating force over the piece between a and
 * b (MODEL.md section 11, "The least push on the plate"): a magnitude in
 * the inner spans of one cone at both ends is in that cone grown by S at
 * every point between, since the push's wrench is affine in t on a
 * straight edge and the set of (F, F t) it maps into C + S is convex. */
static wr_status piece_bound(const outline_call *c, const outline_point *a,
                             const outline_point *b, double *bound)
{
    size_t spans = (size_t)c->case_count * (size_t)c->cones;
    double *lo = malloc((spans ? spans : 1) * 2 * sizeof *lo);
    if (!lo)
        return WR_NO_MEMORY;
    double *hi = lo + spans;
    int n = 0;
    for (size_t i = 0; i < spans; i++) {
        const cone_span *x = &a->spans[i], *y = &b->spans[i];
        if (!x->reached || !y->reached)
            continue;
        double l = fmax(x->in_lo, y->in_lo), h = fmin(x->in_hi, y->in_hi);
        if (l <= h) {
            lo[n] = l;
            hi[n++] = h;
        }
    }
    *bound = cover_from_zero(lo, hi, n);
    free(lo);
    return WR_OK;
}

static bool piece_push(outline_call *c, outline_piece piece)
{
    if (c->count == c->capacity) {
        int capacity = c->capacity ? 2 * c->capacity : 64;
        outline_piece *items = realloc(c->pieces, (size_t)capacity * sizeof *items);
        if (!items)
            return false;
        c->pieces = items;
        c->capacity = capacity;
    }
    int i = c->count++;
    while (i > 0 && c->pieces[(i - 1) / 2].bound > piece.bound) {
        c->pieces[i] = c->pieces[(i - 1) / 2];
        i = (i - 1) / 2;
    }
    c->pieces[i] = piece;
    piece.p0->refs++;
    piece.p1->refs++;
    return true;
}

static outline_piece piece_pop(outline_call *c)
{
    outline_piece top = c->pieces[0], last = c->pieces[--c->count];
    int i = 0;
    for (;;) {
        int child = 2 * i + 1;
        if (child >= c->count)
            break;
        if (child + 1 < c->count && c->pieces[child + 1].bound < c->pieces[child].bound)
            child++;
        if (c->pieces[child].bound >= last.bound)
            break;
        c->pieces[i] = c->pieces[child];
        i = child;
    }
    if (c->count)
        c->pieces[i] = last;
    return top;
}

/* The search's relative tolerance: above the spans' own
 * (OUTLINE_SPAN_TOLERANCE). */
#define OUTLINE_TOLERANCE 1e-6

static double outline_enough(double best)
{
    return isfinite(best) ? best * (1 - OUTLINE_TOLERANCE) : INFINITY;
}

static wr_status outline_body(void *context)
{
    outline_call *c = context;
    const wr_fixture *f = wr_analysis_fixture(c->analysis);
    wr_least_force *out = c->out;
    double best = INFINITY;
    wr_status st = WR_OK;
    /* Each edge pushed on, in 2 pieces to start with. */
    enum { START = 2 };
    for (int e = 0; st == WR_OK && e < (int)f->vertex_count; e++) {
        if (!wr_finger_pushes_on(f, c->finger, e))
            continue;
        outline_point *prev = NULL;
        for (int k = 0; st == WR_OK && k <= START; k++) {
            outline_point *p;
            st = point_new(c, e, (double)k / START, &p);
            if (st != WR_OK)
                break;
            if (p->upper < best) {
                best = p->upper;
                out->edge = e;
                out->t = p->t;
            }
            if (prev) {
                double bound;
                st = piece_bound(c, prev, p, &bound);
                if (st == WR_OK && !piece_push(c, (outline_piece){bound, e, prev, p}))
                    st = WR_NO_MEMORY;
            }
            point_release(prev);
            prev = p;
        }
        point_release(prev);
    }
    bool converged = true;
    while (st == WR_OK && c->count && c->pieces[0].bound < outline_enough(best)) {
        if (out->evaluations >= WR_SUPPORT_MAX_POINTS) {
            converged = false;
            break;
        }
        if (wr_stop_requested(c->stop)) {
            st = WR_STOPPED;
            break;
        }
        outline_piece piece = piece_pop(c);
        double mid = (piece.p0->t + piece.p1->t) / 2;
        outline_point *m = NULL;
        if (mid > piece.p0->t && mid < piece.p1->t)
            st = point_new(c, piece.edge, mid, &m);
        if (st == WR_OK && m) {
            if (m->upper < best) {
                best = m->upper;
                out->edge = piece.edge;
                out->t = mid;
            }
            for (int half = 0; st == WR_OK && half < 2; half++) {
                outline_point *a = half ? m : piece.p0, *b = half ? piece.p1 : m;
                double bound;
                st = piece_bound(c, a, b, &bound);
                bound = fmax(bound, piece.bound); /* a part's bound is at least its whole's */
                if (st == WR_OK && bound < outline_enough(best) &&
                    !piece_push(c, (outline_piece){bound, piece.edge, a, b}))
                    st = WR_NO_MEMORY;
            }
        } else if (st == WR_OK) {
            converged = false; /* a piece too short to split, still undecided */
            st = piece_push(c, piece) ? WR_OK : WR_NO_MEMORY;
            point_release(piece.p0);
            point_release(piece.p1);
            break;
        }
        point_release(m);
        point_release(piece.p0);
        point_release(piece.p1);
    }
    if (st == WR_OK) {
        /* Pieces pruned are certified down to outline_enough(best). */
        double lower = fmin(best, outline_enough(best));
        for (int i = 0; i < c->count; i++)
            lower = fmin(lower, c->pieces[i].bound);
        out->found = isfinite(best);
        out->force = best;
        out->lower = lower;
        out->converged = converged;
        if (out->found)
            wr_boundary_point(f, out->edge, out->t, out->at, out->direction);
    }
    for (int i = 0; i < c->count; i++) {
        point_release(c->pieces[i].p0);
        point_release(c->pieces[i].p1);
    }
    free(c->pieces);
    return st;
}

wr_status wr_supports_least_force_find(const wr_analysis *analysis,
                                       const wr_supports *supports, wr_lp_env *env,
                                       const double (*loads)[3], int case_count,
                                       const wr_finger *finger, const wr_stop *stop,
                                       wr_least_force *out)
{
    memset(out, 0, sizeof *out);
    const wr_fixture *f = wr_analysis_fixture(analysis);
    if (f->shape != WR_SHAPE_POLYGON)
        return f->shape == WR_SHAPE_NONE ? WR_NO_SHAPE : WR_INVALID;
    if (case_count < 1 || !finger || finger->radius != 0)
        return WR_INVALID;
    for (int c = 0; c < case_count; c++)
        for (int k = 0; k < 3; k++)
            if (!isfinite(loads[c][k]))
                return WR_INVALID;
    if (supports->total == 0 || supports->mu_static == 0) /* S = {0}: the cones alone */
        return wr_least_force_find(analysis, WR_SET_GOAL, loads, case_count, finger, stop, out);
    outline_call call = {analysis, supports, loads, case_count,
                         wr_analysis_cone_count(analysis, WR_SET_GOAL), finger, stop, out,
                         NULL, 0, 0, 0};
    return wr_lp_guarded(env, outline_body, &call);
}

/* ---- the in-plane tilt --------------------------------------------------- */

static wr_status regions_add(wr_regions *regions, int edge, double t0, double t1)
{
    /* Joined to the last one when they touch. */
    if (regions->count && regions->items[regions->count - 1].edge == edge &&
        regions->items[regions->count - 1].t1 == t0) {
        regions->items[regions->count - 1].t1 = t1;
        return WR_OK;
    }
    if (regions->count == regions->capacity) {
        int capacity = regions->capacity ? 2 * regions->capacity : 8;
        wr_region *items = realloc(regions->items, (size_t)capacity * sizeof *items);
        if (!items)
            return WR_NO_MEMORY;
        regions->items = items;
        regions->capacity = capacity;
    }
    regions->items[regions->count++] = (wr_region){edge, t0, t1};
    return WR_OK;
}

typedef struct tilt_call {
    const wr_analysis *analysis;
    const wr_supports *supports;
    double weight; /* m times the in-plane gravity (model system) */
    const wr_stop *stop;
    model m;
    double to_force; /* an LP magnitude times this is a force */
    wr_regions *good, *undecided;
    int solves;
    int arcs; /* split so far: past WR_SUPPORT_MAX_CELLS, the rest stays undecided */
} tilt_call;

typedef struct threshold {
    double value; /* in LP units */
} threshold;

static bool threshold_decided(double lo, double hi, void *context)
{
    double t = ((const threshold *)context)->value;
    return hi < t || lo >= t;
}

/* The scaled unit force along phi degrees. */
static void tilt_push(const tilt_call *c, double phi, double push[3])
{
    double u[3] = {cos(phi * WR_PI / 180), sin(phi * WR_PI / 180), 0};
    double length = wr_fixture_scale_wrench(c->m.f, u, push);
    for (int k = 0; k < 3; k++)
        push[k] /= length;
}

/* One cone against the arc [phi0, phi1] (under 180 degrees) of the circle
 * of radius r = weight: *out 1 when every point of the arc is in C + S
 * (found from inside), -1 when none is (from outside), 0 when neither is
 * proved.  C + S holds 0 (both hold it), so its slice K at zero torque is
 * convex and star-shaped from 0, and:
 * - the arc lies in the quadrilateral of 0, its ends and the crossing of
 *   their tangents, at r / cos(half) along the middle: in K when those
 *   three points are (inner magnitudes along the three rays);
 * - the arc lies in the sector between its ends' rays, beyond the chord,
 *   where alpha e0 + beta e1 has alpha + beta >= r: K misses it when the
 *   largest alpha + beta in K is below r (outer). */
static wr_status arc_against_cone(tilt_call *c, const wr_cone *cone, double phi0, double phi1,
                                  int *out)
{
    static const double zero[3] = {0, 0, 0};
    double half = (phi1 - phi0) / 2 * WR_PI / 180, mid = (phi0 + phi1) / 2;
    double r = c->weight / c->to_force, e0[3], e1[3], lo, hi;
    threshold near = {r};
    tilt_push(c, phi0, e0);
    tilt_push(c, phi1, e1);
    wr_status st = cone_bracket(&c->m, cone, SECTOR, zero, e0, e1, WR_FORCE_TOLERANCE,
                                threshold_decided, &near, &lo, &hi, &c->solves);
    if (st != WR_OK)
        return st;
    if (hi < near.value) {
        *out = -1;
        return WR_OK;
    }
    *out = 0;
    const double rays[3] = {phi0, phi1, mid};
    for (int k = 0; k < 3; k++) {
        threshold far = {k < 2 ? r : r / cos(half)};
        double push[3];
        tilt_push(c, rays[k], push);
        st = cone_bracket(&c->m, cone, F_MAX, zero, push, NULL, WR_FORCE_TOLERANCE,
                          threshold_decided, &far, &lo, &hi, &c->solves);
        if (st != WR_OK || lo < far.value)
            return st;
    }
    *out = 1;
    return WR_OK;
}

/* The arc [phi0, phi1]: good when every cone misses it, excluded when one
 * cone holds it, else split down to WR_SUPPORT_MIN_ARC degrees, where it is
 * undecided.  Appended in order of phi. */
static wr_status tilt_arc(tilt_call *c, double phi0, double phi1)
{
    if (wr_stop_requested(c->stop))
        return WR_STOPPED;
    int count = wr_analysis_cone_count(c->analysis, WR_SET_GOAL);
    bool all_miss = true;
    for (int k = 0; k < count; k++) {
        const wr_cone *cone = wr_analysis_cone(c->analysis, WR_SET_GOAL, k);
        if (cone->empty)
            continue;
        int side;
        wr_status st = arc_against_cone(c, cone, phi0, phi1, &side);
        if (st != WR_OK)
            return st;
        if (side > 0)
            return WR_OK; /* excluded */
        all_miss &= side < 0;
    }
    if (all_miss)
        return regions_add(c->good, 0, phi0, phi1);
    if (phi1 - phi0 <= WR_SUPPORT_MIN_ARC || ++c->arcs > WR_SUPPORT_MAX_CELLS)
        return regions_add(c->undecided, 0, phi0, phi1);
    double mid = (phi0 + phi1) / 2;
    wr_status st = tilt_arc(c, phi0, mid);
    return st == WR_OK ? tilt_arc(c, mid, phi1) : st;
}

static wr_status tilt_body(void *context)
{
    tilt_call *c = context;
    for (int k = 0; k < 8; k++) {
        wr_status st = tilt_arc(c, 45.0 * k, 45.0 * (k + 1));
        if (st != WR_OK)
            return st;
    }
    return WR_OK;
}

wr_status wr_supports_gravity_sweep(const wr_analysis *analysis, const wr_supports *supports,
                                    wr_lp_env *env, double in_plane_g, const wr_stop *stop,
                                    wr_regions *good, wr_regions *undecided)
{
    memset(good, 0, sizeof *good);
    memset(undecided, 0, sizeof *undecided);
    if (!(in_plane_g > 0) || !isfinite(in_plane_g))
        return WR_INVALID;
    const wr_fixture *f = wr_analysis_fixture(analysis);
    wr_status st;
    if (supports->total == 0 || supports->mu_static == 0) {
        st = wr_gravity_sweep(analysis, WR_SET_GOAL, good); /* S = {0}: the cones alone */
    } else {
        tilt_call call = {.analysis = analysis, .supports = supports,
                          .weight = f->mass * in_plane_g, .stop = stop, .good = good,
                          .undecided = undecided};
        double w[3] = {call.weight, 0, 0}, h[3];
        double scale = problem_scale(f, supports, w);
        model_init(&call.m, f, supports, scale);
        double unit[3] = {1, 0, 0};
        call.to_force = scale / wr_fixture_scale_wrench(f, unit, h);
        st = wr_lp_guarded(env, tilt_body, &call);
    }
    if (st != WR_OK) {
        wr_regions_release(good);
        wr_regions_release(undecided);
    }
    return st;
}

/* ---- holding ------------------------------------------------------------- */

/* A cell of motion directions: the cone of 1 to 3 unit scaled
 * accelerations q' = m (a_x, a_y, rho alpha) of one mode. */
typedef struct cell {
    int count;
    double ray[3][3];
} cell;

/* The acceleration of support i's point under the scaled acceleration q'. */
static void point_acceleration(const model *m, int i, const double q[3], double a[2])
{
    const wr_fixture *f = m->f;
    double r[2];
    arm(f, m->s, i, r);
    double ax = q[0] / f->mass, ay = q[1] / f->mass;
    double alpha = q[2] / (f->mass * f->gyration_radius);
    a[0] = ax - alpha * r[1];
    a[1] = ay + alpha * r[0];
}

/* Below this (relative to the part's size times |q'| / m), a support's
 * point counts as not accelerating: it may stick. */
#define STILL 1e-12

/* The directions of sliding friction over a cell at support i: up to 3
 * unit-length points whose convex hull, scaled by the friction's size,
 * holds every -f_i / |f_i| = a_i / |a_i| the cell's directions give.
 * false when a_i may vanish in the cell or its directions spread over
 * more than 120 degrees: the whole disc then. */
static bool arc_hull(const model *m, int i, const cell *c, double points[3][2], int *count)
{
    double u[3][2];
    double still = STILL * m->f->size / m->f->mass;
    for (int j = 0; j < c->count; j++) {
        point_acceleration(m, i, c->ray[j], u[j]);
        double n = hypot(u[j][0], u[j][1]);
        if (!(n > still))
            return false;
        u[j][0] /= n;
        u[j][1] /= n;
    }
    if (c->count == 1) {
        memcpy(points[0], u[0], sizeof u[0]);
        *count = 1;
        return true;
    }
    /* The pair farthest apart spans an arc holding the third (a linear
     * image of a cone is the cone of the images, and a pointed cone of
     * the plane is the arc between its two extreme directions). */
    int best_a = -1, best_b = -1;
    double best_cos = 2;
    for (int a = 0; a < c->count; a++)
        for (int b = a + 1; b < c->count; b++) {
            double cosine = u[a][0] * u[b][0] + u[a][1] * u[b][1];
            if (cosine < best_cos) {
                best_cos = cosine;
                best_a = a;
                best_b = b;
            }
        }
    if (best_cos < -0.5) /* wider than 120 degrees */
        return false;
    const double *ua = u[best_a], *ub = u[best_b];
    double cross_ab = ua[0] * ub[1] - ua[1] * ub[0];
    for (int j = 0; j < c->count; j++) {
        if (j == best_a || j == best_b)
            continue;
        double ca = ua[0] * u[j][1] - ua[1] * u[j][0];
        double cb = u[j][0] * ub[1] - u[j][1] * ub[0];
        if (ca * cross_ab < -1e-15 || cb * cross_ab < -1e-15)
            return false; /* the third lies outside: the cone is wider */
    }
    memcpy(points[0], ua, sizeof points[0]);
    memcpy(points[1], ub, sizeof points[1]);
    /* The tangents at the arc's ends meet at (ua + ub) / (1 + cos). */
    points[2][0] = (ua[0] + ub[0]) / (1 + best_cos);
    points[2][1] = (ua[1] + ub[1]) / (1 + best_cos);
    *count = 3;
    return true;
}

/* One LP of holding: over a cell (relaxed: each sliding friction in the
 * hull of its arc) or at a single direction (exact: the cell's one ray).
 * Minimises the L1 residual of
 *     h(g) = q' + sum kappa_j G_j + sum_i W_i phi_i
 * with q' in the cell's cone, G_j the mode's contact generators, phi_i =
 * -f_i the support's friction reversed, sliding (|phi_i| between mu_k_min
 * N_i and mu_k N_i, along the arc) or, where the point may stay still,
 * anywhere in the disc |phi_i| <= mu_s N_i (from outside, cut by the
 * solutions until they lie in it). */
typedef struct hold_lp {
    const model *m;
    const wr_cone *cone;
    const cell *c;
    double target[3];
    /* A step of sequential LP (a single direction only): free columns
     * Delta_k, |Delta_k| <= trust, along `tangent` k, with the wrench's
     * change linearised about the direction at the magnitudes t0 and each
     * support's m0. */
    int tangent_count;
    double tangent[2][3];
    double trust, t0, m0[WR_MAX_SUPPORTS];
    double delta[2];
    /* The distance form (the disturbance margin): the residual e = target -
     * h(g) is free and the objective is a polyhedral norm r >= n_k . e over
     * unit rows n_k whose unit ball holds the Euclidean ball (r <= |e|, so
     * r bounds the distance from below); a row along e is added while |e|
     * exceeds r, so that the two meet. */
    bool distance;
    double seed[3];      /* a unit row to begin with (zero: none): the
                            direction of a solution nearby */
    double prune;        /* > 0: refine only while r < prune <= |e| (past
                            it the cell is dropped; below it, kept whatever
                            the exact distance: either way decided) */
    double error[3];     /* out: e of the last solution (|e| attained) */
    /* The caller reads the residual as a lower bound only (a cell dropped
     * when it exceeds the margin; the distance form, always): a refinement
     * GLPK cannot solve then leaves the last solution, whose discs held the
     * true ones, instead of failing the cell.  Never for a witness, whose
     * forces must lie in their discs. */
    bool bound_only;
    /* out */
    double residual;     /* L1, or r in the distance form */
    double lambda[3];
    double kappa[WR_HULL_MAX];
    double theta[WR_MAX_SUPPORTS * WR_MAX_SUPPORTS * WR_MAX_SUPPORTS / 6 + 1];
    double phi[WR_MAX_SUPPORTS][2];
    int solves;
} hold_lp;

static int hold_lp_solve(hold_lp *h)
{
    const model *m = h->m;
    const wr_supports *s = m->s;
    directions dirs[WR_MAX_SUPPORTS];
    bool disc[WR_MAX_SUPPORTS];
    double points[WR_MAX_SUPPORTS][3][2];
    int point_count[WR_MAX_SUPPORTS];
    for (int i = 0; i < s->count; i++) {
        disc[i] = !arc_hull(m, i, h->c, points[i], &point_count[i]);
        directions_start(&dirs[i]);
    }
    /* The distance form's norm: the cube's and the octahedron's faces to
     * begin with (each unit ball holds the Euclidean one). */
    enum { NORM_MAX = 96 };
    double norm[NORM_MAX][3];
    int norm_count = 0;
    if (h->distance)
        for (int k = 0; k < 27; k++) {
            double n[3] = {k % 3 - 1, k / 3 % 3 - 1, k / 9 - 1};
            int nonzero = (n[0] != 0) + (n[1] != 0) + (n[2] != 0);
            if (nonzero == 1 || nonzero == 3) {
                wr_normalize3(n);
                wr_copy3(n, norm[norm_count++]);
            }
        }
    if (h->distance && wr_norm3(h->seed) > 0)
        wr_copy3(h->seed, norm[norm_count++]);
    for (int round = 0; round < (h->distance ? 80 : 40); round++) {
        lp l;
        lp_init(&l, GLP_MIN);
        int wrench[3];
        for (int k = 0; k < 3; k++)
            wrench[k] = lp_row(&l, GLP_FX, h->target[k], h->target[k]);
        int error = 0;
        if (h->distance) {
            for (int k = 0; k < 3; k++) {
                int e = lp_col(&l, GLP_FR, 0, 0, 0);
                if (k == 0)
                    error = e;
                lp_set(&l, wrench[k], e, 1);
            }
            int r = lp_col(&l, GLP_LO, 0, 0, 1);
            for (int k = 0; k < norm_count; k++) {
                int row = lp_row(&l, GLP_LO, 0, 0);
                lp_set(&l, row, r, 1);
                for (int j = 0; j < 3; j++)
                    lp_set(&l, row, error + j, -norm[k][j]);
            }
        } else {
            for (int k = 0; k < 3; k++) {
                int e = lp_col(&l, GLP_LO, 0, 0, 1);
                lp_set(&l, wrench[k], e, 1);
                e = lp_col(&l, GLP_LO, 0, 0, 1);
                lp_set(&l, wrench[k], e, -1);
            }
        }
        int lambda = 0;
        for (int j = 0; j < h->c->count; j++) {
            int col = lp_col(&l, GLP_LO, 0, 0, 0);
            if (j == 0)
                lambda = col;
            for (int k = 0; k < 3; k++)
                lp_set(&l, wrench[k], col, h->c->ray[j][k]);
        }
        int kappa = 0, kappa_count = 0;
        for (int j = 0; j < h->cone->generator_count; j++) {
            if (h->cone->origins[j].fixel < 0)
                continue;
            int col = lp_col(&l, GLP_LO, 0, 0, 0);
            if (!kappa_count++)
                kappa = col;
            for (int k = 0; k < 3; k++)
                lp_set(&l, wrench[k], col, h->cone->generators[j][k]);
        }
        int theta = distribution_columns(&l, m, 0);
        int one = lp_row(&l, GLP_FX, 1, 1);
        for (int v = 0; v < s->distribution_count; v++)
            lp_set(&l, one, theta + v, 1);
        int first[WR_MAX_SUPPORTS];
        for (int i = 0; i < s->count; i++) {
            if (disc[i]) {
                first[i] = disc_columns(&l, m, i, &dirs[i], false, theta, wrench);
                continue;
            }
            /* mu_k_min N_i <= sum eta <= mu_k N_i. */
            int upper = lp_row(&l, GLP_UP, 0, 0), lower = lp_row(&l, GLP_LO, 0, 0);
            add_normal(&l, m, upper, theta, i, -s->mu_kinetic);
            add_normal(&l, m, lower, theta, i, -s->mu_kinetic_min);
            first[i] = l.cols + 1;
            for (int k = 0; k < point_count[i]; k++) {
                int eta = lp_col(&l, GLP_LO, 0, 0, 0);
                lp_set(&l, upper, eta, 1);
                lp_set(&l, lower, eta, 1);
                for (int r = 0; r < 3; r++)
                    lp_set(&l, wrench[r], eta,
                           points[i][k][0] * m->unit[i][0][r] + points[i][k][1] * m->unit[i][1][r]);
            }
        }
        int delta = 0;
        for (int k = 0; k < h->tangent_count; k++) {
            int col = lp_col(&l, GLP_DB, -h->trust, h->trust, 0);
            if (k == 0)
                delta = col;
            double column[3];
            for (int r = 0; r < 3; r++)
                column[r] = h->t0 * h->tangent[k][r];
            for (int i = 0; i < s->count; i++) {
                if (disc[i])
                    continue;
                /* d(a / |a|) = (I - a^ a^T) (A_i dq) / |a|. */
                double a[2], da[2];
                point_acceleration(m, i, h->c->ray[0], a);
                point_acceleration(m, i, h->tangent[k], da);
                double n = hypot(a[0], a[1]);
                double u[2] = {a[0] / n, a[1] / n};
                double along = u[0] * da[0] + u[1] * da[1];
                double d[2] = {(da[0] - along * u[0]) / n, (da[1] - along * u[1]) / n};
                for (int r = 0; r < 3; r++)
                    column[r] += h->m0[i] * (d[0] * m->unit[i][0][r] + d[1] * m->unit[i][1][r]);
            }
            for (int r = 0; r < 3; r++)
                lp_set(&l, wrench[r], col, column[r]);
        }
        int status = lp_solve(&l);
        h->solves++;
        for (int k = 0; k < h->tangent_count && status == GLP_OPT; k++)
            h->delta[k] = glp_get_col_prim(l.p, delta + k);
        if (status != GLP_OPT) {
            lp_release(&l);
            /* The residual columns make every LP feasible and bounded; a
             * refinement GLPK cannot solve leaves the last solution, whose
             * bound holds (its sets held the true ones too). */
            return h->bound_only && round > 0 ? 0 : -1;
        }
        h->residual = glp_get_obj_val(l.p);
        for (int j = 0; j < h->c->count; j++)
            h->lambda[j] = glp_get_col_prim(l.p, lambda + j);
        for (int j = 0; j < kappa_count; j++)
            h->kappa[j] = glp_get_col_prim(l.p, kappa + j);
        double normal[WR_MAX_SUPPORTS] = {0};
        for (int v = 0; v < s->distribution_count; v++) {
            h->theta[v] = glp_get_col_prim(l.p, theta + v);
            for (int i = 0; i < s->count; i++)
                normal[i] += h->theta[v] * s->distributions[v][i] / m->scale;
        }
        bool cut = false;
        if (h->distance) {
            for (int k = 0; k < 3; k++)
                h->error[k] = glp_get_col_prim(l.p, error + k);
            double n = wr_norm3(h->error);
            bool decided = h->prune > 0 && (h->residual >= h->prune || n < h->prune);
            if (!decided && n > h->residual * (1 + 1e-9) + 1e-15 && norm_count < NORM_MAX) {
                for (int k = 0; k < 3; k++)
                    norm[norm_count][k] = h->error[k] / n;
                norm_count++;
                cut = true;
            }
        }
        for (int i = 0; i < s->count; i++) {
            if (disc[i]) {
                h->phi[i][0] = glp_get_col_prim(l.p, first[i]);
                h->phi[i][1] = glp_get_col_prim(l.p, first[i] + 1);
                if (hypot(h->phi[i][0], h->phi[i][1]) > s->mu_static * normal[i] * (1 + 1e-12) + 1e-15)
                    cut |= directions_add(&dirs[i], h->phi[i][0], h->phi[i][1]);
            } else {
                h->phi[i][0] = h->phi[i][1] = 0;
                for (int k = 0; k < point_count[i]; k++) {
                    double eta = glp_get_col_prim(l.p, first[i] + k);
                    h->phi[i][0] += eta * points[i][k][0];
                    h->phi[i][1] += eta * points[i][k][1];
                }
            }
        }
        lp_release(&l);
        if (!cut)
            break;
    }
    return 0;
}

static double angle_between(const double a[3], const double b[3])
{
    double c[3];
    wr_cross3(a, b, c);
    return atan2(wr_norm3(c), wr_dot3(a, b));
}

/* The cells of a mode's directions: its cone of accelerations cut by the
 * eight orthants (so each piece is pointed, at most 90 degrees across),
 * each piece of full dimension fanned into simplicial cells.  Returns the
 * number written (at most `max`). */
static int mode_cells(const wr_cone *cone, cell *cells, int max)
{
    double accel[WR_HULL_MAX][3];
    int n = 0;
    for (int j = 0; j < cone->generator_count; j++)
        if (cone->origins[j].fixel < 0)
            wr_copy3(cone->generators[j], accel[n++]);
    if (n == 0)
        return 0;
    wr_hrep q;
    wr_hull_from_generators((const double (*)[3])accel, n, &q);
    int count = 0;
    for (int o = 0; o < 8; o++) {
        double rows[WR_HULL_MAX + 3][3];
        int rc = 0;
        for (int i = 0; i < q.facet_count && rc < WR_HULL_MAX; i++)
            wr_copy3(q.facets[i], rows[rc++]);
        for (int k = 0; k < 3; k++) {
            double row[3] = {0, 0, 0};
            row[k] = (o >> k & 1) ? 1 : -1; /* sign s_k: -s_k x_k <= 0 */
            wr_copy3(row, rows[rc++]);
        }
        double gens[WR_HULL_MAX][3];
        int g = wr_hull_generators_of_rows((const double (*)[3])rows, rc,
                                           (const double (*)[3])q.equalities, q.equality_count,
                                           gens, WR_HULL_MAX);
        if (g == 0)
            continue;
        wr_hrep piece;
        wr_hull_from_generators((const double (*)[3])gens, g, &piece);
        if (piece.dimension != q.dimension)
            continue;
        double rays[WR_HULL_MAX][3];
        int r = wr_hull_rays(&piece, rays, WR_HULL_MAX);
        for (int i = 0; i < r; i++)
            wr_normalize3(rays[i]);
        if (q.dimension == 1 || q.dimension == 2) {
            /* One ray, or the two extreme ones of a planar piece. */
            cell c = {.count = q.dimension};
            wr_copy3(rays[0], c.ray[0]);
            if (q.dimension == 2) {
                double worst = -2;
                for (int i = 0; i < r; i++)
                    for (int j = i + 1; j < r; j++) {
                        double a = angle_between(rays[i], rays[j]);
                        if (a > worst) {
                            worst = a;
                            wr_copy3(rays[i], c.ray[0]);
                            wr_copy3(rays[j], c.ray[1]);
                        }
                    }
            }
            if (count < max)
                cells[count++] = c;
            continue;
        }
        /* Three dimensions: the extreme rays in turn about their mean,
         * fanned from the first. */
        double axis[3] = {0, 0, 0};
        for (int i = 0; i < r; i++)
            for (int k = 0; k < 3; k++)
                axis[k] += rays[i][k];
        wr_normalize3(axis);
        double e1[3], e2[3], any[3] = {1, 0, 0};
        if (fabs(axis[0]) > 0.9)
            any[0] = 0, any[1] = 1;
        wr_cross3(axis, any, e1);
        wr_normalize3(e1);
        wr_cross3(axis, e1, e2);
        double angle[WR_HULL_MAX];
        int order[WR_HULL_MAX];
        for (int i = 0; i < r; i++) {
            angle[i] = atan2(wr_dot3(rays[i], e2), wr_dot3(rays[i], e1));
            order[i] = i;
        }
        for (int i = 1; i < r; i++) /* insertion sort by angle */
            for (int j = i; j > 0 && angle[order[j]] < angle[order[j - 1]]; j--) {
                int t = order[j];
                order[j] = order[j - 1];
                order[j - 1] = t;
            }
        for (int i = 1; i + 1 < r && count < max; i++) {
            cell c = {.count = 3};
            wr_copy3(rays[order[0]], c.ray[0]);
            wr_copy3(rays[order[i]], c.ray[1]);
            wr_copy3(rays[order[i + 1]], c.ray[2]);
            cells[count++] = c;
        }
    }
    return count;
}

typedef struct strong_call {
    const wr_analysis *analysis;
    const wr_supports *supports;
    const double *wrench;
    double tolerance;
    const wr_stop *stop;
    wr_support_strong *out;
} strong_call;

/* The witness's forces, back in physical units. */
static void witness_fill(const model *m, const wr_cone *cone, const hold_lp *h,
                         const double direction[3], double t, wr_support_strong *out)
{
    const wr_fixture *f = m->f;
    double q[3];
    for (int k = 0; k < 3; k++)
        q[k] = t * direction[k] * m->scale;
    out->acceleration[0] = q[0] / f->mass;
    out->acceleration[1] = q[1] / f->mass;
    out->acceleration[2] = q[2] / (f->mass * f->gyration_radius);
    memset(out->force, 0, sizeof out->force);
    int k = 0;
    for (int j = 0; j < cone->generator_count; j++) {
        const wr_generator_origin *o = &cone->origins[j];
        if (o->fixel < 0)
            continue;
        out->force[o->fixel][0] += h->kappa[k] * o->normal_force * m->scale;
        out->force[o->fixel][1] += h->kappa[k] * o->tangent_force * m->scale;
        k++;
    }
    for (int i = 0; i < m->s->count; i++) {
        out->support_force[i][0] = -h->phi[i][0] * m->scale;
        out->support_force[i][1] = -h->phi[i][1] * m->scale;
        out->normal[i] = 0;
        for (int v = 0; v < m->s->distribution_count; v++)
            out->normal[i] += h->theta[v] * m->s->distributions[v][i];
    }
}

/* A motion about a support point: the part pivots on that button, which
 * sticks (its friction anywhere in its disc) while the others slide.  It
 * is one direction of each sign, where the button's sliding direction is
 * undefined, so no cell around it can be dropped and the sequential LP,
 * which linearises every sliding direction, cannot reach it: the cells
 * shrink onto it until they are too small to decide.  The exact LP at
 * that one direction decides it instead.  1 with the witness in *out when
 * a pivot of the mode (among its directions `q`) is consistent; 0 when
 * none is; -1 when GLPK failed. */
/* The pivot on support i of sense `sign` (+-1), a unit scaled direction
 * into d; whether it is among a mode's directions `q`. */
static bool pivot_direction(const model *m, const wr_hrep *q, int i, int sign, double d[3])
{
    /* a_i = a_com + alpha x r_i = 0: a_com = alpha (r_y, -r_x), so
     * q' = m (a_x, a_y, rho alpha) is along (r_y, -r_x, rho) alpha. */
    double r[2];
    arm(m->f, m->s, i, r);
    d[0] = sign * r[1];
    d[1] = -sign * r[0];
    d[2] = sign * m->f->gyration_radius;
    wr_normalize3(d);
    bool among = true;
    for (int k = 0; k < q->facet_count; k++)
        among &= wr_dot3(q->facets[k], d) <= 1e-12;
    for (int k = 0; k < q->equality_count; k++)
        among &= fabs(wr_dot3(q->equalities[k], d)) <= 1e-12;
    return among;
}

static int pivot_witness(const model *m, const wr_cone *cone, const wr_hrep *q,
                         const hold_lp *base, int *solves, wr_support_strong *out)
{
    int result = 0;
    for (int i = 0; i < m->s->count && result == 0; i++) {
        for (int sign = -1; sign <= 1 && result == 0; sign += 2) {
            double d[3];
            if (!pivot_direction(m, q, i, sign, d))
                continue;
            cell at = {.count = 1};
            wr_copy3(d, at.ray[0]);
            hold_lp w = *base;
            w.bound_only = false;
            w.c = &at;
            w.tangent_count = 0;
            w.solves = 0;
            if (hold_lp_solve(&w) < 0)
                return -1;
            *solves += w.solves;
            if (w.residual <= 1e-10) {
                witness_fill(m, cone, &w, d, w.lambda[0], out);
                result = 1;
            }
        }
    }
    return result;
}

/* Branch and bound over one mode's cells: 1 a witness (out filled), 0 no
 * direction consistent by the margin, 2 undecided (a cell whose LP GLPK
 * could not solve included), -2 stopped, -3 out of memory. */
static int mode_search(const model *m, const wr_cone *cone, const double target[3], double margin,
                       const wr_stop *stop, wr_support_strong *out)
{
    enum { STACK = 4096 };
    cell *stack = malloc(STACK * sizeof *stack);
    if (!stack)
        return -3;
    int top = mode_cells(cone, stack, 64);
    /* The mode's directions, to keep a refined witness among them. */
    double accel[WR_HULL_MAX][3];
    int accel_count = 0;
    for (int j = 0; j < cone->generator_count; j++)
        if (cone->origins[j].fixel < 0)
            wr_copy3(cone->generators[j], accel[accel_count++]);
    wr_hrep q;
    wr_hull_from_generators((const double (*)[3])accel, accel_count, &q);
    int result = 0, looked = 0;
    hold_lp h = {.m = m, .cone = cone, .bound_only = true};
    memcpy(h.target, target, sizeof h.target);
    while (top > 0) {
        if (wr_stop_requested(stop)) {
            result = -2;
            break;
        }
        cell c = stack[--top];
        if (++looked > WR_SUPPORT_MAX_CELLS) {
            result = 2;
            break;
        }
        out->cells++;
        h.c = &c;
        /* An LP GLPK cannot solve (numerically) proves nothing of its
         * cell: the cell stays undecided, so `held` is never claimed past
         * it and the answer is at worst boundary. */
        if (hold_lp_solve(&h) < 0) {
            result = 2;
            continue;
        }
        if (h.residual > margin)
            continue; /* no direction of the cell is consistent */
        /* A witness: the relaxation's own direction, else the centre. */
        double direction[3] = {0, 0, 0};
        for (int j = 0; j < c.count; j++)
            for (int k = 0; k < 3; k++)
                direction[k] += h.lambda[j] * c.ray[j][k];
        if (!(wr_norm3(direction) > 1e-12))
            for (int j = 0; j < c.count; j++)
                for (int k = 0; k < 3; k++)
                    direction[k] += c.ray[j][k];
        wr_normalize3(direction);
        cell single = {.count = 1};
        wr_copy3(direction, single.ray[0]);
        hold_lp w = h;
        w.bound_only = false;
        w.c = &single;
        w.solves = 0;
        if (hold_lp_solve(&w) < 0) {
            result = 2; /* undecided, as above */
            continue;
        }
        h.solves += w.solves;
        /* A motion consistent with g is usually one direction alone (three
         * equations, as many unknowns): close in on it by sequential LP,
         * the friction's directions linearised about the last one. */
        double span = 0;
        for (int i = 0; i < c.count; i++)
            for (int j = i + 1; j < c.count; j++)
                span = fmax(span, angle_between(c.ray[i], c.ray[j]));
        for (int step = 0; step < 16 && w.residual > 1e-10 && c.count > 1; step++) {
            hold_lp n = w;
            n.tangent_count = 0;
            /* Tangents within the cell's span, orthogonal to the direction. */
            for (int j = 0; j < c.count && n.tangent_count < c.count - 1; j++) {
                double b[3];
                wr_copy3(c.ray[j], b);
                double along = wr_dot3(b, direction);
                for (int k = 0; k < 3; k++)
                    b[k] -= along * direction[k];
                for (int t = 0; t < n.tangent_count; t++) {
                    double d = wr_dot3(b, n.tangent[t]);
                    for (int k = 0; k < 3; k++)
                        b[k] -= d * n.tangent[t][k];
                }
                if (wr_norm3(b) > 1e-6) {
                    wr_normalize3(b);
                    wr_copy3(b, n.tangent[n.tangent_count++]);
                }
            }
            n.trust = fmax(2 * span, 1e-9);
            n.solves = 0;
            n.t0 = w.lambda[0];
            for (int i = 0; i < m->s->count; i++)
                n.m0[i] = hypot(w.phi[i][0], w.phi[i][1]);
            if (hold_lp_solve(&n) < 0)
                break;
            double next[3];
            wr_copy3(direction, next);
            for (int t = 0; t < n.tangent_count; t++)
                for (int k = 0; k < 3; k++)
                    next[k] += n.delta[t] * n.tangent[t][k];
            wr_normalize3(next);
            bool among = true;
            for (int i = 0; i < q.facet_count; i++)
                among &= wr_dot3(q.facets[i], next) <= 1e-12;
            for (int i = 0; i < q.equality_count; i++)
                among &= fabs(wr_dot3(q.equalities[i], next)) <= 1e-12;
            if (!among)
                break;
            hold_lp v = h;
            v.bound_only = false;
            cell at = {.count = 1};
            wr_copy3(next, at.ray[0]);
            v.c = &at;
            v.solves = 0;
            if (hold_lp_solve(&v) < 0)
                break;
            h.solves += n.solves + v.solves;
            if (!(v.residual < w.residual))
                break;
            w = v;
            wr_copy3(next, direction);
            single = at;
            w.c = &single;
        }
        if (w.residual <= 1e-10) {
            witness_fill(m, cone, &w, direction, w.lambda[0], out);
            result = 1;
            break;
        }
        if (c.count == 1) { /* nothing to split: exact and not consistent */
            if (w.residual <= margin)
                result = 2;
            continue;
        }
        /* Split the longest edge. */
        int a = 0, b = 1;
        double longest = -1;
        for (int i = 0; i < c.count; i++)
            for (int j = i + 1; j < c.count; j++) {
                double angle = angle_between(c.ray[i], c.ray[j]);
                if (angle > longest) {
                    longest = angle;
                    a = i;
                    b = j;
                }
            }
        if (longest < WR_SUPPORT_MIN_CELL) {
            result = 2;
            continue;
        }
        if (top + 2 > STACK) {
            result = 2;
            break;
        }
        double mid[3];
        for (int k = 0; k < 3; k++)
            mid[k] = c.ray[a][k] + c.ray[b][k];
        wr_normalize3(mid);
        cell left = c, right = c;
        wr_copy3(mid, left.ray[a]);
        wr_copy3(mid, right.ray[b]);
        stack[top++] = left;
        stack[top++] = right;
    }
    /* Cells left undecided: a pivot on a button is what they shrink onto
     * when the wrench turns the part about one (pivot_witness says why
     * the search above cannot find it). */
    if (result == 2) {
        int r = pivot_witness(m, cone, &q, &h, &h.solves, out);
        if (r == 1)
            result = 1;
    }
    out->solves += h.solves;
    free(stack);
    return result;
}

static wr_status strong_body(void *context)
{
    strong_call *call = context;
    model m;
    double target[3];
    model_for(&m, call->analysis, call->supports, call->wrench, target);
    wr_support_strong *out = call->out;
    out->verdict = WR_VERDICT_INSIDE;
    out->blocking = -1;
    int count = wr_analysis_cone_count(call->analysis, WR_SET_STRONG);
    for (int c = 0; c < count; c++) {
        const wr_cone *cone = wr_analysis_cone(call->analysis, WR_SET_STRONG, c);
        if (cone->empty)
            continue;
        int r = mode_search(&m, cone, target, call->tolerance, call->stop, out);
        if (r == -1)
            return WR_LP_FAILED;
        if (r == -2)
            return WR_STOPPED;
        if (r == -3)
            return WR_NO_MEMORY;
        if (r == 1) {
            out->verdict = WR_VERDICT_OUTSIDE;
            out->blocking = c;
            return WR_OK;
        }
        if (r == 2 && out->verdict == WR_VERDICT_INSIDE) {
            out->verdict = WR_VERDICT_BOUNDARY;
            out->blocking = c;
        }
    }
    return WR_OK;
}

wr_status wr_supports_strong(const wr_analysis *analysis, const wr_supports *supports,
                             wr_lp_env *env, const double wrench[3], double tolerance,
                             const wr_stop *stop, wr_support_strong *out)
{
    memset(out, 0, sizeof *out);
    if (!isfinite(wrench[0]) || !isfinite(wrench[1]) || !isfinite(wrench[2]) ||
        !(tolerance >= 0))
        return WR_INVALID;
    if (supports->total == 0 ||
        (supports->mu_static == 0 && supports->mu_kinetic == 0)) {
        /* No support friction: the cones alone. */
        wr_answer answer;
        wr_status st = wr_classify(analysis, wrench, WR_SET_STRONG, tolerance, &answer);
        out->verdict = answer.verdict;
        out->blocking = answer.blocking;
        memcpy(out->acceleration, answer.witness.acceleration, sizeof out->acceleration);
        memcpy(out->force, answer.witness.force, sizeof out->force);
        return st;
    }
    strong_call call = {analysis, supports, wrench, tolerance, stop, out};
    return wr_lp_guarded(env, strong_body, &call);
}

/* ---- the disturbance margin on the plate ---------------------------------- */

/* A cell of one mode in the margin's search, with the lower bound of its
 * LP on the distance from the bias to its consistent wrenches. */
typedef struct margin_cell {
    cell c;
    int mode;
    double lower;
    double direction[3]; /* the LP's own direction of motion (zero: none) */
    double near[3];      /* the unit direction of its nearest wrench */
} margin_cell;

typedef struct margin_heap {
    margin_cell *cells; /* a binary heap, least lower bound first */
    int count, capacity;
} margin_heap;

static bool heap_push(margin_heap *h, const margin_cell *c)
{
    if (h->count == h->capacity) {
        int capacity = h->capacity ? 2 * h->capacity : 256;
        margin_cell *cells = realloc(h->cells, (size_t)capacity * sizeof *cells);
        if (!cells)
            return false;
        h->cells = cells;
        h->capacity = capacity;
    }
    int i = h->count++;
    while (i > 0 && h->cells[(i - 1) / 2].lower > c->lower) {
        h->cells[i] = h->cells[(i - 1) / 2];
        i = (i - 1) / 2;
    }
    h->cells[i] = *c;
    return true;
}

static margin_cell heap_pop(margin_heap *h)
{
    margin_cell top = h->cells[0], last = h->cells[--h->count];
    int i = 0;
    for (;;) {
        int child = 2 * i + 1;
        if (child >= h->count)
            break;
        if (child + 1 < h->count && h->cells[child + 1].lower < h->cells[child].lower)
            child++;
        if (!(h->cells[child].lower < last.lower))
            break;
        h->cells[i] = h->cells[child];
        i = child;
    }
    if (h->count)
        h->cells[i] = last;
    return top;
}

typedef struct margin_call {
    const wr_analysis *analysis;
    const wr_supports *supports;
    const double *bias;
    const wr_stop *stop;
    wr_support_margin *out;
    /* The nearest consistent wrench found: its distance (in the model's
     * units, divided by the scale) and e = target - h(g). */
    double hi, error[3];
    int hi_mode;
} margin_call;

/* The distance LP over cell `c` of mode `cone` (its bound is h->residual),
 * its norm begun with `seed`; -1 when GLPK fails. */
static int margin_cell_solve(const model *m, const wr_cone *cone, const double target[3],
                             const cell *c, const double seed[3], double prune, hold_lp *h,
                             int *solves)
{
    memset(h, 0, sizeof *h);
    h->m = m;
    h->cone = cone;
    h->c = c;
    h->distance = true;
    h->bound_only = true;
    h->prune = prune;
    wr_copy3(target, h->target);
    if (seed)
        wr_copy3(seed, h->seed);
    int rc = hold_lp_solve(h);
    *solves += h->solves;
    return rc;
}

/* A cell's entry in the search from its LP's solution. */
static void margin_cell_fill(margin_cell *mc, const hold_lp *h)
{
    memset(mc->direction, 0, sizeof mc->direction);
    for (int j = 0; j < mc->c.count; j++)
        for (int k = 0; k < 3; k++)
            mc->direction[k] += h->lambda[j] * mc->c.ray[j][k];
    if (!(wr_norm3(mc->direction) > 1e-9))
        memset(mc->direction, 0, sizeof mc->direction);
    wr_copy3(h->error, mc->near);
    if (!(wr_fixture_unit_direction(mc->near) > 0))
        memset(mc->near, 0, sizeof mc->near);
}

/* The exact LP at one direction of cell `c` (the relaxation's own, else
 * the cell's centre): a consistent wrench, whose distance bounds the
 * margin from above. */
static int margin_exact(margin_call *call, const model *m, const double target[3], int mode,
                        const double direction[3], const double seed[3])
{
    const wr_cone *cone = wr_analysis_cone(call->analysis, WR_SET_STRONG, mode);
    cell single = {.count = 1};
    wr_copy3(direction, single.ray[0]);
    hold_lp h;
    if (margin_cell_solve(m, cone, target, &single, seed, 0, &h, &call->out->solves) < 0)
        return -1;
    double d = wr_norm3(h.error);
    if (d < call->hi) {
        call->hi = d;
        wr_copy3(h.error, call->error);
        call->hi_mode = mode;
    }
    return 0;
}

static int margin_upper(margin_call *call, const model *m, const double target[3],
                        const margin_cell *mc)
{
    double direction[3];
    wr_copy3(mc->direction, direction);
    if (!(wr_norm3(direction) > 0))
        for (int j = 0; j < mc->c.count; j++)
            for (int k = 0; k < 3; k++)
                direction[k] += mc->c.ray[j][k];
    wr_normalize3(direction);
    return margin_exact(call, m, target, mc->mode, direction, mc->near);
}

/* The exact LPs at the pivots on each support (both senses) that are
 * directions of `mode`: there that support sticks, its friction anywhere
 * in its disc, which no direction nearby gives (pivot_witness says why),
 * so the search's upper bounds, taken at other directions, would never
 * reach such a nearest motion. */
static int margin_still(margin_call *call, const model *m, const double target[3], int mode)
{
    const wr_cone *cone = wr_analysis_cone(call->analysis, WR_SET_STRONG, mode);
    double accel[WR_HULL_MAX][3];
    int n = 0;
    for (int j = 0; j < cone->generator_count; j++)
        if (cone->origins[j].fixel < 0)
            wr_copy3(cone->generators[j], accel[n++]);
    wr_hrep q;
    if (n == 0 || !wr_hull_from_generators((const double (*)[3])accel, n, &q))
        return 0;
    for (int i = 0; i < m->s->count; i++)
        for (int sign = -1; sign <= 1; sign += 2) {
            double d[3];
            if (pivot_direction(m, &q, i, sign, d) &&
                margin_exact(call, m, target, mode, d, NULL) < 0)
                return -1;
        }
    return 0;
}

/* Best first over every mode's cells: the cell of least lower bound is
 * bounded from above at one direction and split, until that bound reaches
 * the best upper one (within the tolerance) or the budget is spent.  The
 * cells left (and those too narrow to split) keep their lower bounds, so
 * the least of them is a certified lower bound on the distance. */
static wr_status margin_body(void *context)
{
    margin_call *call = context;
    wr_support_margin *out = call->out;
    const wr_fixture *f = wr_analysis_fixture(call->analysis);
    model m;
    double target[3];
    double n = wr_fixture_scale_wrench(f, call->bias, target);
    double scale = fmax(n, call->supports->mu_static * call->supports->total);
    if (!(scale > 0))
        scale = 1; /* the zero bias and nothing pressing: any unit */
    model_init(&m, f, call->supports, scale);
    for (int k = 0; k < 3; k++)
        target[k] /= scale;
    margin_heap heap = {0};
    wr_status status = WR_OK;
    double floor = INFINITY;
    int count = wr_analysis_cone_count(call->analysis, WR_SET_STRONG);
    call->hi = INFINITY;
    call->hi_mode = -1;
    cell *start = malloc(64 * sizeof *start);
    if (!start)
        return WR_NO_MEMORY;
    for (int mode = 0; mode < count && status == WR_OK; mode++) {
        const wr_cone *cone = wr_analysis_cone(call->analysis, WR_SET_STRONG, mode);
        if (cone->empty)
            continue;
        if (margin_still(call, &m, target, mode) < 0) {
            status = WR_LP_FAILED;
            break;
        }
        int cells = mode_cells(cone, start, 64);
        for (int i = 0; i < cells; i++) {
            hold_lp h;
            out->cells++;
            if (margin_cell_solve(&m, cone, target, &start[i], NULL, 0, &h, &out->solves) < 0) {
                status = WR_LP_FAILED;
                break;
            }
            margin_cell mc = {.c = start[i], .mode = mode, .lower = h.residual};
            margin_cell_fill(&mc, &h);
            if (!heap_push(&heap, &mc)) {
                status = WR_NO_MEMORY;
                break;
            }
        }
    }
    free(start);
    out->bounded = heap.count > 0;
    double lo = 0;
    while (status == WR_OK && heap.count > 0) {
        if (wr_stop_requested(call->stop)) {
            status = WR_STOPPED;
            break;
        }
        if (heap.cells[0].lower >= call->hi * (1 - WR_SUPPORT_MARGIN_TOLERANCE) ||
            out->cells >= WR_SUPPORT_MARGIN_CELLS)
            break;
        margin_cell top = heap_pop(&heap);
        const wr_cone *cone = wr_analysis_cone(call->analysis, WR_SET_STRONG, top.mode);
        if (margin_upper(call, &m, target, &top) < 0) {
            status = WR_LP_FAILED;
            break;
        }
        if (call->hi <= 1e-10)
            break; /* a motion consistent with the bias itself */
        int a = 0, b = 1;
        double longest = -1;
        for (int i = 0; i < top.c.count; i++)
            for (int j = i + 1; j < top.c.count; j++) {
                double angle = angle_between(top.c.ray[i], top.c.ray[j]);
                if (angle > longest) {
                    longest = angle;
                    a = i;
                    b = j;
                }
            }
        if (top.c.count == 1 || longest < WR_SUPPORT_MIN_CELL) {
            floor = fmin(floor, top.lower); /* nothing more to split */
            continue;
        }
        double mid[3];
        for (int k = 0; k < 3; k++)
            mid[k] = top.c.ray[a][k] + top.c.ray[b][k];
        wr_normalize3(mid);
        margin_cell halves[2] = {top, top};
        wr_copy3(mid, halves[0].c.ray[a]);
        wr_copy3(mid, halves[1].c.ray[b]);
        for (int k = 0; k < 2 && status == WR_OK; k++) {
            hold_lp h;
            out->cells++;
            /* Its bound needs refining only while it may decide whether the
             * half is dropped. */
            double prune = call->hi * (1 - WR_SUPPORT_MARGIN_TOLERANCE);
            if (margin_cell_solve(&m, cone, target, &halves[k].c, top.near,
                                  isfinite(prune) ? prune : 0, &h, &out->solves) < 0) {
                status = WR_LP_FAILED;
                break;
            }
            /* A half's set is in its parent's: its bound is at least the
             * parent's. */
            halves[k].lower = fmax(top.lower, h.residual);
            margin_cell_fill(&halves[k], &h);
            if (status == WR_OK && !heap_push(&heap, &halves[k]))
                status = WR_NO_MEMORY;
        }
    }
    if (status == WR_OK && out->bounded) {
        lo = fmin(floor, call->hi);
        if (heap.count > 0)
            lo = fmin(lo, heap.cells[0].lower);
        if (call->hi <= 1e-10)
            lo = 0;
        out->moves = call->hi <= 1e-10;
        out->held = !out->moves && lo > 0;
        /* Some mode's cell is always bounded from above before the search
         * ends; the heap's least cell's mode should none be. */
        out->blocking = call->hi_mode >= 0 ? call->hi_mode
                        : heap.count > 0   ? heap.cells[0].mode
                                           : -1;
        out->bracket[0] = out->margin = lo * scale;
        out->bracket[1] = call->hi * scale;
        out->converged = lo >= call->hi * (1 - WR_SUPPORT_MARGIN_TOLERANCE);
        /* The worst direction: from the bias to the nearest consistent
         * wrench found, -e, a unit scaled wrench back in physical units. */
        double d[3] = {-call->error[0], -call->error[1], -call->error[2]};
        if (wr_fixture_unit_direction(d) > 0)
            wr_fixture_unscale_wrench(f, d, out->worst_direction);
    }
    free(heap.cells);
    return status;
}

/* Is the scaled wrench h proved held? */
static wr_status held_at(const wr_analysis *analysis, const wr_supports *supports, wr_lp_env *env,
                         const double h[3], const wr_stop *stop, bool *held, int *solves)
{
    double g[3];
    wr_fixture_unscale_wrench(wr_analysis_fixture(analysis), h, g);
    wr_support_strong strong;
    wr_status status =
        wr_supports_strong(analysis, supports, env, g, WR_DEFAULT_TOLERANCE, stop, &strong);
    *held = status == WR_OK && strong.verdict == WR_VERDICT_INSIDE;
    *solves += strong.solves;
    return status;
}

/* The least s found with h(b) + s u proved held, u a unit scaled
 * direction, s in (from, to]: the first held point of the probes just past
 * `from`, then from + (to - from) 2^-k for k = 10 .. 0, bisected against
 * the last moving one to a tenth of the margin's tolerance.  INFINITY when
 * none is held. */
static wr_status held_along(const wr_analysis *analysis, const wr_supports *supports,
                            wr_lp_env *env, const double h[3], const double u[3], double from,
                            double to, const wr_stop *stop, double *found, int *solves)
{
    *found = INFINITY;
    double moving = from, s = from;
    bool held = false;
    for (int k = -1; k <= 10 && !held; k++) {
        s = k < 0 ? from * (1 + WR_SUPPORT_MARGIN_TOLERANCE / 10) + 1e-12 * to
                  : from + (to - from) * ldexp(1, k - 10);
        if (!(s > moving) && k >= 0)
            continue;
        double p[3];
        for (int j = 0; j < 3; j++)
            p[j] = h[j] + s * u[j];
        wr_status status = held_at(analysis, supports, env, p, stop, &held, solves);
        if (status != WR_OK)
            return status;
        if (!held)
            moving = s;
    }
    if (!held)
        return WR_OK;
    for (int k = 0; k < 40 && s - moving > WR_SUPPORT_MARGIN_TOLERANCE / 10 * s; k++) {
        double mid = (s + moving) / 2, p[3];
        for (int j = 0; j < 3; j++)
            p[j] = h[j] + mid * u[j];
        bool mid_held;
        wr_status status = held_at(analysis, supports, env, p, stop, &mid_held, solves);
        if (status != WR_OK)
            return status;
        if (mid_held)
            s = mid;
        else
            moving = mid;
    }
    *found = s;
    return WR_OK;
}

/* A bias that moves the part: its depth bracketed (wr_supports_margin). */
static wr_status margin_moving(const wr_analysis *analysis, const wr_supports *supports,
                               wr_lp_env *env, const double bias[3], const wr_stop *stop,
                               wr_support_margin *out)
{
    const wr_fixture *f = wr_analysis_fixture(analysis);
    double hb[3];
    double length = wr_fixture_scale_wrench(f, bias, hb);
    wr_support_strong strong;
    wr_status status =
        wr_supports_strong(analysis, supports, env, bias, WR_DEFAULT_TOLERANCE, stop, &strong);
    if (status != WR_OK)
        return status;
    out->solves += strong.solves;
    /* The lower bound: b's depth in p + K, the witness's set with its
     * friction fixed (p, the supports' share of the witness) and K the
     * cone of its direction and the mode's contact generators.  p + K is
     * in U, so a wrench nearer b than the depth is in U too. */
    double lower = 0, face[3] = {0, 0, 0};
    if (strong.verdict == WR_VERDICT_OUTSIDE) {
        const wr_cone *cone = wr_analysis_cone(analysis, WR_SET_STRONG, strong.blocking);
        double generators[WR_HULL_MAX][3], p[3] = {0, 0, 0}, rest[3];
        int n = 0;
        double q[3] = {strong.acceleration[0] * f->mass, strong.acceleration[1] * f->mass,
                       strong.acceleration[2] * f->mass * f->gyration_radius};
        if (wr_fixture_unit_direction(q) > 0)
            wr_copy3(q, generators[n++]);
        for (int j = 0; j < cone->generator_count && n < WR_HULL_MAX; j++)
            if (cone->origins[j].fixel >= 0)
                wr_copy3(cone->generators[j], generators[n++]);
        for (int i = 0; i < supports->count; i++) {
            /* -f_i as a wrench about the centre of mass, scaled. */
            double r[2], w[3];
            arm(f, supports, i, r);
            double fx = -strong.support_force[i][0], fy = -strong.support_force[i][1];
            w[0] = fx;
            w[1] = fy;
            w[2] = (r[0] * fy - r[1] * fx) / f->gyration_radius;
            for (int k = 0; k < 3; k++)
                p[k] += w[k];
        }
        for (int k = 0; k < 3; k++)
            rest[k] = hb[k] - p[k];
        wr_hrep k;
        if (n > 0 && wr_hull_from_generators((const double (*)[3])generators, n, &k) &&
            k.dimension == 3) {
            lower = INFINITY;
            for (int i = 0; i < k.facet_count; i++) {
                double depth = -wr_dot3(k.facets[i], rest);
                if (depth < lower) {
                    lower = depth;
                    wr_copy3(k.facets[i], face);
                }
            }
            if (!(lower > 0) || !isfinite(lower))
                lower = 0;
        }
        out->blocking = strong.blocking;
    }
    /* The upper bound: a held wrench, along the nearest face's normal,
     * then towards the zero wrench (held at zero load: MODEL.md). */
    double best = INFINITY, direction[3] = {0, 0, 0};
    if (wr_norm3(face) > 0) {
        double s;
        status = held_along(analysis, supports, env, hb, face, lower, lower + 2 * length + 1e-9,
                            stop, &s, &out->solves);
        if (status != WR_OK)
            return status;
        if (s < best) {
            best = s;
            wr_copy3(face, direction);
        }
    }
    if (length > 0) {
        double toward[3] = {-hb[0] / length, -hb[1] / length, -hb[2] / length};
        double s;
        status = held_along(analysis, supports, env, hb, toward, lower,
                            fmin(length, best), stop, &s, &out->solves);
        if (status != WR_OK)
            return status;
        if (s < best) {
            best = s;
            wr_copy3(toward, direction);
        }
    }
    /* The margin is the attained end, or the certified one when no held
     * wrench was found (holding undecided even at zero). */
    out->bracket[0] = -best;
    out->bracket[1] = -lower;
    out->margin = isfinite(best) ? -best : -lower;
    out->converged = lower >= best * (1 - WR_SUPPORT_MARGIN_TOLERANCE);
    memset(out->worst_direction, 0, sizeof out->worst_direction);
    if (!isfinite(best) && length > 0)
        for (int k = 0; k < 3; k++)
            direction[k] = -hb[k] / length;
    wr_fixture_unscale_wrench(f, direction, out->worst_direction);
    return WR_OK;
}

wr_status wr_supports_margin(const wr_analysis *analysis, const wr_supports *supports,
                             wr_lp_env *env, const double bias[3], const wr_stop *stop,
                             wr_support_margin *out)
{
    memset(out, 0, sizeof *out);
    out->blocking = -1;
    if (!isfinite(bias[0]) || !isfinite(bias[1]) || !isfinite(bias[2]))
        return WR_INVALID;
    margin_call call = {.analysis = analysis, .supports = supports, .bias = bias, .stop = stop,
                        .out = out};
    wr_status status = wr_lp_guarded(env, margin_body, &call);
    if (status != WR_OK || !out->moves)
        return status;
    return margin_moving(analysis, supports, env, bias, stop, out);
}

/* ---- push regions on the plate -------------------------------------------- */

wr_status wr_supports_push_regions(const wr_analysis *analysis, const wr_supports *supports,
                                   wr_lp_env *env, double force, const double (*loads)[3],
                                   int case_count, int edge, wr_regions *regions)
{
    const wr_fixture *f = wr_analysis_fixture(analysis);
    if (f->shape != WR_SHAPE_POLYGON || edge < 0 || edge >= (int)f->vertex_count ||
        !(force > 0) || !isfinite(force) || case_count < 1)
        return WR_INVALID;
    /* On a straight edge the unit push's wrench is affine in t. */
    double w0[3], w1[3], push[3];
    wr_push_wrench(f, edge, 0, w0);
    wr_push_wrench(f, edge, 1, w1);
    for (int k = 0; k < 3; k++)
        push[k] = force * (w1[k] - w0[k]);
    wr_forces all = {0}, one = {0}, meet = {0};
    wr_status status = WR_OK;
    for (int c = 0; c < case_count && status == WR_OK; c++) {
        double load[3];
        for (int k = 0; k < 3; k++)
            load[k] = loads[c][k] + force * w0[k];
        status = wr_supports_force_range(analysis, supports, env, load, push, 0, 1,
                                         c ? &one : &all);
        if (status == WR_OK && c) {
            status = wr_forces_intersect(&all, &one, &meet);
            wr_forces swap = all;
            all = meet;
            meet = swap;
        }
    }
    for (int i = 0; status == WR_OK && i < all.count; i++) {
        if (all.items[i].hi > all.items[i].lo)
            status = regions_add(regions, edge, all.items[i].lo, all.items[i].hi);
    }
    wr_forces_release(&all);
    wr_forces_release(&one);
    wr_forces_release(&meet);
    return status;
}
