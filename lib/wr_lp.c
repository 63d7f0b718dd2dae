/* wr_lp.c -- GLPK membership LPs (docs/MODEL.md section 2).
 *
 * Variables, in the scaled space of wr_cone.c: the motion y (columns 1..3,
 * free; those past the motion's dimension d fixed at 0), then (c_in, c_it)
 * per fixel, then the slack t in [0, 1].  The acceleration is
 * q' = m (a_x, a_y, rho alpha) = B y, B an orthonormal basis of the span
 * of the constraint's motion cone as the cones compute it (motion_basis),
 * inside the null space of its equality rows (a_n = 0, a_t = 0), so those
 * rows hold exactly and are not rows of the LP.  Rows: the three
 * wrench rows B y - sum(Wn_i c_in + Wt_i c_it) = h (h the unit scaled
 * wrench; only their bounds change between wrenches), then each letter's
 * inequality rows.  Maximise t: strict rows hold with margin t, so the
 * wrench is in G_X iff the LP is feasible with t above the threshold.
 *
 * Why y and not q': GLPK meets a row within an absolute tolerance (1e-7).
 * A row u . q' (u unit) may be tiny on every motion the equalities leave:
 * on a part whose fixels are close together far from its centre of mass
 * it is spread / rho of |q'| (1e-4 and less).  Over q', GLPK would take a
 * motion 1e-4 long going the wrong way as feasible, and call a wrench a
 * member 1e-4 outside the cone (tests/fuzz/README.md, finding 12).  Over
 * y each inequality row is scaled to unit length on the motion space itself
 * (add_row), so its tolerance is relative to the motion, as the explicit
 * cones judge their rows on unit generators. */
#include "wr_lp.h"
#include "wr_internal.h"

#include <glpk.h>
#include <setjmp.h>
#include <stdlib.h>
#include <string.h>

struct wr_lp_env {
    jmp_buf jump;          /* where a fatal GLPK error resumes */
    unsigned generation;   /* bumped whenever GLPK's environment was freed */
    int inject_after;      /* test hook: fail after this many solves; <0 off */
};

struct wr_lp_set {
    wr_lp_env *env;
    const wr_fixture *fixture;
    const wr_constraint *constraints;
    int count;
    glp_prob **problems;     /* NULL until first use */
    unsigned *generations;   /* env->generation when each was built */
    signed char *possible;   /* per constraint: -1 not yet known, else whether
                                its motion is possible (strict rows met) */
};

static int swallow_output(void *info, const char *text)
{
    (void)info;
    (void)text;
    return 1; /* nonzero: GLPK prints nothing */
}

static void on_fatal_error(void *info)
{
    /* GLPK must not return from here, or it aborts the process. */
    longjmp(((wr_lp_env *)info)->jump, 1);
}

static void configure_thread(wr_lp_env *env)
{
    glp_term_out(GLP_OFF);
    glp_term_hook(swallow_output, NULL);
    glp_error_hook(on_fatal_error, env);
}

wr_status wr_lp_env_new(wr_lp_env **out)
{
    wr_lp_env *env = calloc(1, sizeof *env);
    *out = env;
    if (!env)
        return WR_NO_MEMORY;
    env->inject_after = -1;
    configure_thread(env);
    return WR_OK;
}

void wr_lp_env_free(wr_lp_env *env)
{
    if (!env)
        return;
    glp_free_env();
    free(env);
}

void wr_lp_env_inject_failure(wr_lp_env *env, int calls) { env->inject_after = calls; }

wr_status wr_lp_set_new(wr_lp_env *env, const wr_fixture *fixture,
                        const wr_constraint *constraints, int count, wr_lp_set **out)
{
    *out = NULL;
    wr_lp_set *set = calloc(1, sizeof *set);
    if (!set)
        return WR_NO_MEMORY;
    set->env = env;
    set->fixture = fixture;
    set->constraints = constraints;
    set->count = count;
    set->problems = calloc((size_t)(count > 0 ? count : 1), sizeof *set->problems);
    set->generations = calloc((size_t)(count > 0 ? count : 1), sizeof *set->generations);
    set->possible = malloc((size_t)(count > 0 ? count : 1));
    if (!set->problems || !set->generations || !set->possible) {
        wr_lp_set_free(set);
        return WR_NO_MEMORY;
    }
    memset(set->possible, -1, (size_t)(count > 0 ? count : 1));
    *out = set;
    return WR_OK;
}

void wr_lp_set_free(wr_lp_set *set)
{
    if (!set)
        return;
    if (set->problems)
        for (int i = 0; i < set->count; i++)
            /* Problems of an older generation died with GLPK's environment. */
            if (set->problems[i] && set->generations[i] == set->env->generation)
                glp_delete_prob(set->problems[i]);
    free(set->problems);
    free(set->generations);
    free(set->possible);
    free(set);
}

/* Non-zeros: 3 wrench rows of 3 + 2k; per fixel at most one acceleration row
 * of 4 (y and t; at most two were counted) and two friction rows of 2 (l and
 * r with a kinetic interval have two, as n and m); the pivot row's 4. */
#define TRIPLETS_MAX (3 * (3 + 2 * WR_MAX_FIXELS) + 12 * WR_MAX_FIXELS + 4)

/* Triplets for glp_load_matrix (1-based). */
typedef struct triplets {
    int count;
    int row[1 + TRIPLETS_MAX];
    int column[1 + TRIPLETS_MAX];
    double value[1 + TRIPLETS_MAX];
} triplets;

static void put(triplets *t, int row, int column, double value)
{
    if (value == 0)
        return;
    t->count++;
    t->row[t->count] = row;
    t->column[t->count] = column;
    t->value[t->count] = value;
}

/* The motion space of a constraint: an orthonormal basis of the span of
 * the cones' own motion generators (wr_cone_acceleration: the closure of
 * {a_n = 0, a_t = 0 as the letters say, the inequalities}), so that the LP
 * and the cones decide its rank alike -- four a_n = 0 rows whose lines all
 * but meet (within 4.6e-9) are rank 2 or 3 by which code asks
 * (tests/fuzz/README.md, finding 15).  An impossible motion (-1) or the
 * origin alone: dimension 0.  Returns the dimension, 0..3. */
static int motion_basis(const wr_fixture *f, const wr_constraint *c, double basis[3][3])
{
    double generators[WR_HULL_MAX][3];
    int count = wr_cone_acceleration(f, c, generators);
    if (count <= 0)
        return 0;
    /* The span of the generators: the null space of their null space. */
    double normal[3][3];
    int n = wr_hull_null_space((const double (*)[3])generators, count, normal);
    return wr_hull_null_space((const double (*)[3])normal, n, basis);
}

/* A constraint's motion space: q' = sum_j basis[j] y_j. */
typedef struct motion_space {
    double basis[3][3]; /* orthonormal rows */
    int dimension;
} motion_space;

/* An inequality row sign * (v / |v|) . q' + slack t over the motion y,
 * scaled so that its part over y is a unit row: its slack t is then
 * measured on unit motions of the motion space, as the cones measure a
 * strict row on the unit generators of their motion cone.  (Measuring t in
 * the row's unscaled units instead would divide t's coefficient by the
 * row's length, up to 1e9: GLPK then misses rows by that much more than
 * its tolerance, and loses the best slack.)  A row that vanishes on the
 * motion space (length below the rank tolerance, as a cone's generator
 * would find it) keeps only its slack: 0 + slack t. */
static void add_row(glp_prob *p, triplets *t, const double v[3], double sign, double slack,
                    int type, int t_column, const motion_space *space)
{
    const double (*basis)[3] = space->basis;
    int dimension = space->dimension;
    int row = glp_add_rows(p, 1);
    double u[3], projected[3] = {0, 0, 0};
    wr_copy3(v, u);
    wr_normalize3(u);
    for (int j = 0; j < dimension; j++)
        projected[j] = sign * wr_dot3(u, basis[j]);
    double length = wr_norm3(projected);
    if (length > WR_RANK_TOLERANCE)
        for (int j = 0; j < dimension; j++)
            put(t, row, 1 + j, projected[j] / length);
    put(t, row, t_column, slack);
    glp_set_row_bnds(p, row, type, 0, 0);
}

/* The membership problem of a constraint, or (`motion`) the problem of its
 * motion alone: y in the box [-1, 1]^d, the wrench rows free, so that the
 * best slack is the strict rows' margin relative to the motion's size. */
static glp_prob *build_problem(const wr_fixture *f, const wr_constraint *c, bool motion)
{
    int k = f->fixel_count;
    int t_column = 4 + 2 * k;
    motion_space space;
    space.dimension = motion_basis(f, c, space.basis);
    const double (*basis)[3] = space.basis;
    int dimension = space.dimension;
    glp_prob *p = glp_create_prob();
    glp_set_obj_dir(p, GLP_MAX);
    glp_add_cols(p, t_column);
    for (int j = 1; j <= 3; j++)
        if (j > dimension)
            glp_set_col_bnds(p, j, GLP_FX, 0, 0);
        else
            glp_set_col_bnds(p, j, motion ? GLP_DB : GLP_FR, -1, 1);
    glp_set_col_bnds(p, t_column, GLP_DB, 0, 1);
    glp_set_obj_coef(p, t_column, 1);

    /* On the stack: a fatal GLPK error longjmps out of here, and GLPK's own
     * memory is then freed with its environment; nothing else may leak. */
    triplets storage;
    triplets *t = &storage;
    t->count = 0;
    /* Wrench rows: (B y)_j - sum_i (Wn_i[j] c_in + Wt_i[j] c_it) = h_j. */
    glp_add_rows(p, 3);
    for (int j = 0; j < 3; j++) {
        for (int d = 0; d < dimension; d++)
            put(t, 1 + j, 1 + d, basis[d][j]);
        for (int i = 0; i < k; i++) {
            put(t, 1 + j, 4 + 2 * i, -f->fixels[i].normal_wrench[j]);
            put(t, 1 + j, 5 + 2 * i, -f->fixels[i].tangent_wrench[j]);
        }
        glp_set_row_bnds(p, 1 + j, motion ? GLP_FR : GLP_FX, 0, 0);
    }
    for (int i = 0; i < k; i++) {
        const wr_fixel *fixel = &f->fixels[i];
        const double *wn = fixel->normal_wrench, *wt = fixel->tangent_wrench;
        int cn = 4 + 2 * i, ct = 5 + 2 * i;
        char letter = c->letters[i];
        bool touching = strchr("lrnm", letter) != NULL;
        glp_set_col_bnds(p, cn, touching ? GLP_LO : GLP_FX, 0, 0);
        glp_set_col_bnds(p, ct, touching ? GLP_FR : GLP_FX, 0, 0);
        int row;
        switch (letter) {
        case 's': /* a_n >= 0, or a_n >= t strictly separating */
            add_row(p, t, wn, 1, c->strict_separation ? -1 : 0, GLP_LO, t_column, &space);
            break;
        case 'a': /* a_n <= -t */
            add_row(p, t, wn, 1, 1, GLP_UP, t_column, &space);
            break;
        case 'l': /* a_n = 0 (in the basis), a_t >= t, c_t = -mu_k c_n */
        case 'r': /* a_n = 0, a_t <= -t, c_t = +mu_k c_n */
            add_row(p, t, wt, letter == 'l' ? 1 : -1, -1, GLP_LO, t_column, &space);
            row = glp_add_rows(p, 1);
            put(t, row, ct, 1);
            put(t, row, cn, letter == 'l' ? fixel->mu_kinetic : -fixel->mu_kinetic);
            if (fixel->mu_kinetic_min == fixel->mu_kinetic) {
                glp_set_row_bnds(p, row, GLP_FX, 0, 0);
                break;
            }
            /* A kinetic interval: -mu_max c_n <= c_t <= -mu_min c_n for l,
             * mu_min c_n <= c_t <= mu_max c_n for r. */
            glp_set_row_bnds(p, row, letter == 'l' ? GLP_LO : GLP_UP, 0, 0);
            row = glp_add_rows(p, 1);
            put(t, row, ct, 1);
            put(t, row, cn, letter == 'l' ? fixel->mu_kinetic_min : -fixel->mu_kinetic_min);
            glp_set_row_bnds(p, row, letter == 'l' ? GLP_UP : GLP_LO, 0, 0);
            break;
        case 'n': /* a_n = 0, a_t = 0 (in the basis), |c_t| <= mu_s c_n */
        case 'm': /* a_n = 0, |c_t| <= mu_s c_n */
            row = glp_add_rows(p, 1);
            put(t, row, ct, 1);
            put(t, row, cn, -fixel->mu_static);
            glp_set_row_bnds(p, row, GLP_UP, 0, 0);
            row = glp_add_rows(p, 1);
            put(t, row, ct, 1);
            put(t, row, cn, fixel->mu_static);
            glp_set_row_bnds(p, row, GLP_LO, 0, 0);
            break;
        default: /* u */
            break;
        }
    }
    if (c->pivot) {
        double e[3] = {0, 0, 1}; /* pivot * alpha >= t */
        add_row(p, t, e, c->pivot, -1, GLP_LO, t_column, &space);
    }
    glp_load_matrix(p, t->count, t->row, t->column, t->value);
    return p;
}

/* Solve after the bounds changed.  Returns GLP_OPT, GLP_NOFEAS, or -1 when
 * GLPK could not decide. */
static int solve(glp_prob *p)
{
    glp_smcp parm;
    glp_init_smcp(&parm);
    parm.msg_lev = GLP_MSG_OFF;
    parm.presolve = GLP_OFF; /* keeps the basis for the next wrench */
    parm.meth = GLP_DUALP;   /* new row bounds keep the basis dual feasible */
    for (int attempt = 0; attempt < 2; attempt++) {
        int rc = glp_simplex(p, &parm);
        if (rc == 0) {
            int status = glp_get_status(p);
            if (status == GLP_OPT || status == GLP_NOFEAS)
                return status;
        }
        /* A singular or stale basis: start again from scratch. */
        glp_std_basis(p);
        parm.meth = GLP_PRIMAL;
    }
    return -1;
}

wr_status wr_lp_member(wr_lp_set *set, int index, const double wrench[3], bool *member,
                       wr_witness *witness)
{
    wr_lp_env *env = set->env;
    const wr_fixture *f = set->fixture;
    if (setjmp(env->jump)) {
        /* A fatal GLPK error: every problem of this thread is invalid now. */
        glp_free_env();
        env->generation++;
        configure_thread(env);
        return WR_LP_FAILED;
    }
    if (set->possible[index] < 0) {
        /* Is the motion possible at all: its strict rows met with a slack
         * above the threshold by an acceleration in the box [-1, 1]^3?  A
         * property of the constraint, not of the wrench: asked once. */
        glp_prob *motion = build_problem(f, &set->constraints[index], true);
        int status = solve(motion);
        bool possible = status == GLP_OPT && glp_get_obj_val(motion) > WR_LP_SLACK_THRESHOLD;
        glp_delete_prob(motion);
        if (status < 0)
            return WR_LP_FAILED;
        set->possible[index] = possible;
    }
    glp_prob *p = set->problems[index];
    if (!p || set->generations[index] != env->generation) {
        p = build_problem(f, &set->constraints[index], false);
        set->problems[index] = p;
        set->generations[index] = env->generation;
    }
    double h[3];
    double scale = wr_fixture_unit_wrench(f, wrench, h);
    if (env->inject_after == 0) {
        env->inject_after = -1;
        glp_set_row_bnds(p, 0, GLP_FX, 0, 0); /* row 0 does not exist: fatal */
    } else if (env->inject_after > 0) {
        env->inject_after--;
    }
    for (int j = 0; j < 3; j++)
        glp_set_row_bnds(p, 1 + j, GLP_FX, h[j], h[j]);
    int status = solve(p);
    if (status < 0)
        return WR_LP_FAILED;
    /* In G_X: the motion is possible and the wrench is in the closure (the
     * relative interior of the closure lies in G_X; only its open faces,
     * where margins are 0, are not). */
    *member = set->possible[index] && status == GLP_OPT;
    if (*member && witness) {
        memset(witness, 0, sizeof *witness);
        /* The witness of the unit wrench, scaled back (as wr_classify's):
         * overflow only ever reaches the figures beyond a double. */
        double basis[3][3], q[3] = {0, 0, 0};
        int dimension = motion_basis(f, &set->constraints[index], basis);
        for (int d = 0; d < dimension; d++)
            for (int j = 0; j < 3; j++)
                q[j] += basis[d][j] * glp_get_col_prim(p, 1 + d);
        witness->acceleration[0] = q[0] / f->mass;
        witness->acceleration[1] = q[1] / f->mass;
        witness->acceleration[2] = q[2] / (f->mass * f->gyration_radius);
        for (int i = 0; i < f->fixel_count; i++) {
            witness->force[i][0] = glp_get_col_prim(p, 4 + 2 * i);
            witness->force[i][1] = glp_get_col_prim(p, 5 + 2 * i);
        }
        wr_newton_euler_wrench(f, witness->acceleration, (const double (*)[2])witness->force,
                               witness->wrench);
        wr_witness_friction(f, &set->constraints[index], witness); /* ratios: before scaling */
        for (int k = 0; scale > 0 && k < 3; k++) {
            witness->acceleration[k] =
                wr_fixture_scale_back(f, wrench, scale, witness->acceleration[k]);
            witness->wrench[k] = wr_fixture_scale_back(f, wrench, scale, witness->wrench[k]);
        }
        for (int i = 0; scale > 0 && i < f->fixel_count; i++)
            for (int k = 0; k < 2; k++)
                witness->force[i][k] = wr_fixture_scale_back(f, wrench, scale, witness->force[i][k]);
    }
    return WR_OK;
}

wr_status wr_lp_guarded(wr_lp_env *env, wr_status (*body)(void *context), void *context)
{
    if (setjmp(env->jump)) {
        /* As wr_lp_member: every problem of this thread is invalid now. */
        glp_free_env();
        env->generation++;
        configure_thread(env);
        return WR_LP_FAILED;
    }
    return body(context);
}
