/* wr_support.c -- friction at the supports under a part on a base plate
 * (wr_support.h; docs/MODEL.md section 10). */
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

void wr_supports_free(wr_supports *supports)
{
    if (!supports)
        return;
    free(supports->distributions);
    free(supports);
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
        s->total += s->down[i].force;
        moment[0] += s->down[i].force * s->down[i].at[0];
        moment[1] += s->down[i].force * s->down[i].at[1];
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
        wr_error_set(error, "points", reason);
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
    parm.tol_bnd = 1e-12;
    parm.tol_dj = 1e-12;
    for (int attempt = 0; attempt < 2; attempt++) {
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

/* What one LP of a cone asks: the least scale rho (RHO), or the least or
 * largest push magnitude (F_MIN, F_MAX). */
typedef enum question { RHO, F_MIN, F_MAX } question;

typedef struct cone_lp {
    const model *m;
    const wr_cone *cone;
    question q;
    double target[3];   /* h(g) / scale, or h(L) / scale */
    double push[3];     /* h(u) / |h(u)| */
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
    lp_init(&l, c->q == F_MAX ? GLP_MAX : GLP_MIN);
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
                              const double push[3], double tolerance, bracket_decided decided,
                              void *context, double *lo, double *hi, int *solves)
{
    directions dirs[WR_MAX_SUPPORTS];
    for (int i = 0; i < m->s->count; i++)
        directions_start(&dirs[i]);
    double none = q == F_MAX ? -INFINITY : INFINITY;
    double sign = q == F_MAX ? -1 : 1; /* sign * value: a minimum */
    double outer_best = -INFINITY, inner_best = INFINITY; /* of sign * value */
    for (int round = 0; round < 60; round++) {
        cone_lp c = {.m = m, .cone = cone, .q = q, .dirs = dirs};
        memcpy(c.target, target, sizeof c.target);
        memcpy(c.push, push, sizeof c.push);
        c.inner = false;
        cone_lp_solve(&c);
        (*solves)++;
        if (c.status < 0)
            return WR_LP_FAILED;
        if (c.status == GLP_NOFEAS) {
            *lo = *hi = none;
            return WR_OK;
        }
        if (c.status == GLP_UNBND) {
            *lo = *hi = INFINITY; /* only F_MAX can be unbounded from outside */
            if (q != F_MAX)
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
            return WR_LP_FAILED;
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
    const wr_fixture *f = wr_analysis_fixture(call->analysis);
    model m;
    model_init(&m, f, call->supports, problem_scale(f, call->supports, call->wrench));
    double target[3];
    wr_fixture_scale_wrench(f, call->wrench, target);
    for (int k = 0; k < 3; k++)
        target[k] /= m.scale;
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
        wr_status st = cone_bracket(&m, cone, RHO, target, push, call->tolerance, rho_decided,
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
    const wr_fixture *f = wr_analysis_fixture(call->analysis);
    double hu[3], hl[3];
    double push_length = wr_fixture_scale_wrench(f, call->push, hu);
    double scale = fmax(problem_scale(f, call->supports, call->load), push_length);
    model m;
    model_init(&m, f, call->supports, scale);
    wr_fixture_scale_wrench(f, call->load, hl);
    for (int k = 0; k < 3; k++) {
        hl[k] /= scale;
        hu[k] /= push_length;
    }
    /* Magnitudes in the LP: F' = F |h(u)| / scale. */
    double to_force = scale / push_length;
    wr_forces outer_excluded = {0}, inner_excluded = {0};
    wr_status st = WR_OK;
    int solves = 0;
    int count = wr_analysis_cone_count(call->analysis, WR_SET_GOAL);
    for (int c = 0; c < count && st == WR_OK; c++) {
        const wr_cone *cone = wr_analysis_cone(call->analysis, WR_SET_GOAL, c);
        if (cone->empty)
            continue;
        double a_lo, a_hi, b_lo, b_hi;
        st = cone_bracket(&m, cone, F_MIN, hl, hu, WR_FORCE_TOLERANCE, NULL, NULL, &a_lo, &a_hi,
                          &solves);
        if (st != WR_OK || a_lo == INFINITY)
            continue; /* no magnitude reaches this cone */
        st = cone_bracket(&m, cone, F_MAX, hl, hu, WR_FORCE_TOLERANCE, NULL, NULL, &b_lo, &b_hi,
                          &solves);
        if (st != WR_OK)
            break;
        /* Outer: [a_lo, b_hi] holds the cone's magnitudes; inner:
         * [a_hi, b_lo] is held by them (when not empty). */
        st = forces_append(&outer_excluded, a_lo * to_force, b_hi * to_force);
        if (st == WR_OK && a_hi <= b_lo)
            st = forces_append(&inner_excluded, a_hi * to_force, b_lo * to_force);
    }
    if (st == WR_OK)
        st = complement(&outer_excluded, call->lo, call->hi, call->outer);
    if (st == WR_OK && call->inner)
        st = complement(&inner_excluded, call->lo, call->hi, call->inner);
    wr_forces_release(&outer_excluded);
    wr_forces_release(&inner_excluded);
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
