/* test_support.c -- a part on a base plate (lib/wr_support.h): statics by
 * hand, seating and the least push force against closed forms and against
 * an LP of this file's own in which every friction disc is replaced by an
 * inscribed and by a circumscribed 256-gon (which must bracket every
 * answer), holding against motion directions sampled densely, each an LP
 * of this file's own. */
#include "test_util.h"

#include <glpk.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>

#include <cmocka.h>

#define G 9.81

static wr_supports *supports_new(const wr_fixture *f, const double (*points)[2], int count,
                                 double mu, double g, const wr_down_spec *down, int down_count,
                                 wr_error *error)
{
    wr_support_spec spec;
    memset(&spec, 0, sizeof spec);
    spec.point_count = (size_t)count;
    spec.points = points;
    spec.friction.given = true;
    spec.friction.static_mu = mu;
    spec.g = g;
    spec.down_count = (size_t)down_count;
    spec.down = down;
    wr_supports *s = NULL;
    wr_supports_new(f, &spec, &s, error);
    return s;
}

/* Three buttons at radius 0.2 about the disc's centre, 120 degrees apart:
 * their centroid is the centre of mass, so each carries W / 3. */
static const double tri[3][2] = {{0, 0.2}, {-0.17320508075688773, -0.1}, {0.17320508075688773, -0.1}};

static void test_statics(void **state)
{
    (void)state;
    wr_fixture *f = test_disc_corner(0.5);
    wr_error error;
    wr_supports *s = supports_new(f, tri, 3, 0.3, G, NULL, 0, &error);
    assert_non_null(s);
    assert_int_equal(s->distribution_count, 1);
    for (int i = 0; i < 3; i++)
        assert_true(fabs(s->distributions[0][i] - G / 3) < 1e-12);
    wr_supports_free(s);

    /* A down clamp of 2 m g at (0, 0.2), over button 0: the total is
     * 3 m g, button 0 carries 2 m g + m g / 3, the others m g / 3 each. */
    wr_down_spec down = {{0, 0.2}, 2 * G};
    s = supports_new(f, tri, 3, 0.3, G, &down, 1, &error);
    assert_non_null(s);
    assert_true(fabs(s->total - 3 * G) < 1e-12);
    assert_true(fabs(s->distributions[0][0] - (2 * G + G / 3)) < 1e-9);
    assert_true(fabs(s->distributions[0][1] - G / 3) < 1e-9);
    wr_supports_free(s);

    /* A clamp of 10 m g at (0, -0.9): the centre of pressure is at
     * y = -9 / 11 = -0.818182, 0.718182 below the edge y = -0.1 of the
     * triangle: refused with that distance. */
    wr_down_spec far = {{0, -0.9}, 10 * G};
    s = supports_new(f, tri, 3, 0.3, G, &far, 1, &error);
    assert_null(s);
    assert_string_equal(error.field, "points");
    assert_non_null(strstr(error.reason, "0.718182"));

    /* Bad input, each naming its field. */
    assert_null(supports_new(f, tri, 2, 0.3, G, NULL, 0, &error));
    assert_string_equal(error.field, "points");
    const double outside[3][2] = {{0, 0.2}, {-0.17, -0.1}, {1.5, 0}};
    assert_null(supports_new(f, outside, 3, 0.3, G, NULL, 0, &error));
    assert_string_equal(error.field, "points[2]");
    assert_null(supports_new(f, tri, 3, -0.1, G, NULL, 0, &error));
    assert_string_equal(error.field, "friction.static");
    wr_down_spec off = {{3, 0}, 1};
    assert_null(supports_new(f, tri, 3, 0.3, G, &off, 1, &error));
    assert_string_equal(error.field, "down[0].at");

    /* Four buttons at the corners of a square about the centre of mass:
     * the distributions are the two diagonals, each carrying W / 2. */
    const double square[4][2] = {{0.3, 0.3}, {-0.3, 0.3}, {-0.3, -0.3}, {0.3, -0.3}};
    s = supports_new(f, square, 4, 0.3, G, NULL, 0, &error);
    assert_non_null(s);
    assert_int_equal(s->distribution_count, 2);
    for (int i = 0; i < 4; i++) {
        assert_true(fabs(s->normal_min[i]) < 1e-12);
        assert_true(fabs(s->normal_max[i] - G / 2) < 1e-9);
    }
    wr_supports_free(s);
    wr_fixture_free(f);
}

/* The disc in the corner (docs/MODEL.md section 7.1, fixel friction 0.5)
 * on the three buttons above, button friction mu_B, weight W = m g.
 *
 * Both fixels' normals pass through the centre, and every excluded cone of
 * G_goal holds the whole torque axis (section 5's example), so C + S =
 * C + (S's forces) x (the torque axis), and the forces of S form the disc
 * of radius sum mu_B N_i = mu_B W.  A push F u through the centre (no
 * torque) therefore seats exactly when F u is farther than mu_B W from
 * every excluded cone's force part: from the complement of the open
 * wedge of goal directions between 206.565 and 243.435 degrees.  For u at
 * an angle delta inside the wedge from its nearer edge that distance is
 * F sin(delta), so the least force is
 *
 *     F* = mu_B W / sin(delta)
 *
 * (225 degrees: delta = 18.435 degrees, sin = 1 / sqrt(10); 215 degrees:
 * delta = 8.435 degrees).  Floating (mu_B = 0), any F > 0 seats. */
static void test_disc_least_force(void **state)
{
    (void)state;
    wr_fixture *f = test_disc_corner(0.5);
    wr_analysis *a = test_analysis_new(f);
    wr_lp_env *env = test_lp_env_new();
    double mu_b = 0.3;
    wr_error error;
    wr_supports *s = supports_new(f, tri, 3, mu_b, G, NULL, 0, &error);
    assert_non_null(s);
    const double edge = atan2(-0.5, -1); /* 206.565 degrees, as -153.435 */
    double angles[2] = {225, 215};
    for (int k = 0; k < 2; k++) {
        double phi = angles[k] * TEST_PI / 180;
        double push[3] = {cos(phi), sin(phi), 0};
        double delta = fabs(remainder(phi - edge, 2 * TEST_PI));
        delta = fmin(delta, fabs(remainder(phi - atan2(-1, -0.5), 2 * TEST_PI)));
        double expected = mu_b * G / sin(delta);
        double load[1][3] = {{0, 0, 0}};
        double force, lower;
        assert_int_equal(wr_supports_least_force(a, s, env, (const double (*)[3])load, 1, push,
                                                 &force, &lower),
                         WR_OK);
        printf("disc, push at %g degrees: least force %.9g (closed form %.9g, lower %.9g)\n",
               angles[k], force, expected, lower);
        assert_true(fabs(force - expected) <= 1e-7 * expected);
        assert_true(lower <= force && force - lower <= 1e-7 * expected);
        /* The verdicts just above and below it. */
        for (int side = -1; side <= 1; side += 2) {
            double F = expected * (1 + side * 1e-4);
            double w[3] = {F * push[0], F * push[1], 0};
            wr_support_goal goal;
            assert_int_equal(wr_supports_goal(a, s, env, w, WR_DEFAULT_TOLERANCE, &goal), WR_OK);
            assert_int_equal(goal.verdict, side > 0 ? WR_VERDICT_INSIDE : WR_VERDICT_OUTSIDE);
        }
    }
    wr_supports_free(s);
    /* Floating: the least force is 0 (any push along the bisector seats). */
    s = supports_new(f, tri, 3, 0, G, NULL, 0, &error);
    double push[3] = {-sqrt(0.5), -sqrt(0.5), 0};
    double load[1][3] = {{0, 0, 0}};
    double force, lower;
    assert_int_equal(
        wr_supports_least_force(a, s, env, (const double (*)[3])load, 1, push, &force, &lower),
        WR_OK);
    assert_true(force == 0);
    wr_supports_free(s);
    wr_lp_env_free(env);
    wr_analysis_free(a);
    wr_fixture_free(f);
}

/* ---- the 256-gon LP of this file ------------------------------------------
 *
 * Is g in C + S_poly, for C = cone(generators) and S_poly the sum over the
 * supports of regular 256-gons of "radius" mu N_i (vertices on the circle:
 * inscribed; edges tangent to it: circumscribed, vertices at radius
 * mu N_i / cos(pi / 256)), N any distribution with N >= 0, sum N = W and
 * sum N_i p_i = W c, taken as variables (not as wrenchd's vertices)?  The
 * LP minimises the L1 residual of g = sum lambda_j G_j + sum_i wrench(f_i)
 * in the scaled metric.  With `push` the question is instead the least
 * (maximise: largest) F with load + F push in C + S_poly; NAN when none. */
#define POLY 256

/* Columns e+, e- >= 0 on the three wrench rows, each costing 1: the
 * least L1 residual of the rows.  Returns the triplets' new count. */
static int residual_columns(glp_prob *p, int count, int *ia, int *ja, double *ar)
{
    for (int k = 0; k < 3; k++) {
        int e = glp_add_cols(p, 2);
        for (int side = 0; side < 2; side++) {
            glp_set_col_bnds(p, e + side, GLP_LO, 0, 0);
            glp_set_obj_coef(p, e + side, 1);
            count++;
            ia[count] = 1 + k;
            ja[count] = e + side;
            ar[count] = side ? -1 : 1;
        }
    }
    return count;
}


static double poly_lp(const wr_fixture *f, const wr_supports *s, const wr_cone *cone,
                      const double g[3], const double *push, int direction, bool outer)
{
    glp_prob *p = glp_create_prob();
    glp_set_obj_dir(p, direction);
    int n = s->count;
    int rows = 3 + 3 + 2 * n + n;
    glp_add_rows(p, rows);
    double h[3];
    wr_fixture_scale_wrench(f, g, h);
    for (int k = 0; k < 3; k++)
        glp_set_row_bnds(p, 1 + k, GLP_FX, h[k], h[k]);
    /* Statics: sum N = W, sum N x = W c_x, sum N y = W c_y. */
    glp_set_row_bnds(p, 4, GLP_FX, s->total, s->total);
    glp_set_row_bnds(p, 5, GLP_FX, s->total * s->pressure[0], s->total * s->pressure[0]);
    glp_set_row_bnds(p, 6, GLP_FX, s->total * s->pressure[1], s->total * s->pressure[1]);
    /* Rows 7.. : f_i = sum_k eta_ik v_k (2 per support), sum_k eta_ik <= mu N_i. */
    for (int i = 0; i < n; i++) {
        glp_set_row_bnds(p, 7 + 2 * i, GLP_FX, 0, 0);
        glp_set_row_bnds(p, 8 + 2 * i, GLP_FX, 0, 0);
        glp_set_row_bnds(p, 7 + 2 * n + i, GLP_UP, 0, 0);
    }
    int cap = 64 + 3 * cone->generator_count + n * (8 + 4 * POLY) + 8;
    int *ia = malloc(sizeof(int) * (size_t)cap), *ja = malloc(sizeof(int) * (size_t)cap);
    double *ar = malloc(sizeof(double) * (size_t)cap);
    int count = 0;
#define SET(r, c, v) (count++, ia[count] = (r), ja[count] = (c), ar[count] = (v))
    int col = 0;
    for (int j = 0; j < cone->generator_count; j++) {
        col = glp_add_cols(p, 1);
        glp_set_col_bnds(p, col, GLP_LO, 0, 0);
        for (int k = 0; k < 3; k++)
            SET(1 + k, col, cone->generators[j][k]);
    }
    double rho = f->gyration_radius;
    double radius = outer ? 1 / cos(TEST_PI / POLY) : 1;
    for (int i = 0; i < n; i++) {
        double rx = s->points[i][0] - f->com[0], ry = s->points[i][1] - f->com[1];
        int N = glp_add_cols(p, 1);
        glp_set_col_bnds(p, N, GLP_LO, 0, 0);
        SET(4, N, 1);
        SET(5, N, s->points[i][0]);
        SET(6, N, s->points[i][1]);
        SET(7 + 2 * n + i, N, -s->mu_static);
        int fx = glp_add_cols(p, 2);
        glp_set_col_bnds(p, fx, GLP_FR, 0, 0);
        glp_set_col_bnds(p, fx + 1, GLP_FR, 0, 0);
        SET(1, fx, 1);
        SET(3, fx, -ry / rho);
        SET(2, fx + 1, 1);
        SET(3, fx + 1, rx / rho);
        SET(7 + 2 * i, fx, 1);
        SET(8 + 2 * i, fx + 1, 1);
        int eta = glp_add_cols(p, POLY);
        for (int k = 0; k < POLY; k++) {
            double angle = 2 * TEST_PI * k / POLY;
            glp_set_col_bnds(p, eta + k, GLP_LO, 0, 0);
            SET(7 + 2 * i, eta + k, -radius * cos(angle));
            SET(8 + 2 * i, eta + k, -radius * sin(angle));
            SET(7 + 2 * n + i, eta + k, 1);
        }
    }
    int magnitude = 0;
    if (push) {
        double hu[3];
        wr_fixture_scale_wrench(f, push, hu);
        magnitude = glp_add_cols(p, 1);
        glp_set_col_bnds(p, magnitude, GLP_LO, 0, 0);
        glp_set_obj_coef(p, magnitude, 1);
        for (int k = 0; k < 3; k++)
            SET(1 + k, magnitude, -hu[k]);
    } else {
        count = residual_columns(p, count, ia, ja, ar);
    }
#undef SET
    glp_load_matrix(p, count, ia, ja, ar);
    glp_smcp parm;
    glp_init_smcp(&parm);
    parm.msg_lev = GLP_MSG_OFF;
    parm.presolve = GLP_OFF; /* with it, an unbounded LP has no status */
    int rc = glp_simplex(p, &parm);
    double value = NAN;
    if (rc == 0 && glp_get_status(p) == GLP_OPT)
        value = glp_get_obj_val(p);
    else if (rc == 0 && glp_get_status(p) == GLP_UNBND)
        value = INFINITY;
    glp_delete_prob(p);
    free(ia);
    free(ja);
    free(ar);
    return value;
}

/* The least F >= 0 outside every cone's closed interval [min, max] of
 * the 256-gon LPs. */
static double poly_least_force(const wr_analysis *a, const wr_supports *s, const double load[3],
                               const double push[3], bool outer)
{
    const wr_fixture *f = wr_analysis_fixture(a);
    int count = wr_analysis_cone_count(a, WR_SET_GOAL);
    double lo[2048], hi[2048];
    int n = 0;
    for (int c = 0; c < count; c++) {
        const wr_cone *cone = wr_analysis_cone(a, WR_SET_GOAL, c);
        if (cone->empty)
            continue;
        double a_lo = poly_lp(f, s, cone, load, push, GLP_MIN, outer);
        if (isnan(a_lo))
            continue;
        lo[n] = a_lo;
        hi[n++] = poly_lp(f, s, cone, load, push, GLP_MAX, outer);
    }
    double at = 0;
    for (bool moved = true; moved;) {
        moved = false;
        for (int i = 0; i < n; i++)
            if (lo[i] <= at && hi[i] > at) {
                at = hi[i];
                moved = true;
            }
    }
    return at;
}

/* Random fixtures, 3 to 5 buttons, random friction and clamps: wrenchd's
 * seating verdict and least push force lie between the inscribed and the
 * circumscribed 256-gons'. */
static void test_polygon_bracket(void **state)
{
    (void)state;
    test_rng rng = {20261128};
    wr_lp_env *env = test_lp_env_new();
    int checked = 0, forces = 0, inside = 0, outside = 0;
    for (int trial = 0; trial < 16; trial++) {
        /* The disc in the corner with random friction, the 3-2-1 plate,
         * random discs and polygons with two fixels. */
        wr_fixture *f = trial % 4 == 0   ? test_disc_corner(test_range(&rng, 0.1, 0.8))
                        : trial % 4 == 1 ? test_plate_321()
                                         : test_random_fixture(&rng, 2, trial % 4 == 2);
        if (!f) {
            printf("trial %d: no fixture\n", trial);
            continue;
        }
        wr_analysis *a = test_analysis_new(f);
        /* Buttons inside the part: about the centre of mass, within 0.3 of
         * its size; the centre of pressure within their hull by the clamp
         * left out or put at the buttons' centroid. */
        int n = 3 + trial % 3;
        double points[5][2];
        for (int i = 0; i < n; i++) {
            double angle = 2 * TEST_PI * (i + test_range(&rng, 0.2, 0.8)) / n;
            double r = test_range(&rng, 0.1, 0.25) * f->size;
            points[i][0] = f->com[0] + r * cos(angle);
            points[i][1] = f->com[1] + r * sin(angle);
        }
        wr_error error;
        wr_supports *s = supports_new(f, (const double (*)[2])points, n,
                                      test_range(&rng, 0.05, 0.6), G, NULL, 0, &error);
        if (!s) { /* a button off the part, or the centre of mass off their hull */
            printf("trial %d: %s %s\n", trial, error.field, error.reason);
            wr_analysis_free(a);
            wr_fixture_free(f);
            continue;
        }
        /* Directions of the floating part's G_goal, by rejection: a push
         * the supports may defeat or not, depending on its size. */
        double dirs[8][3];
        int dir_count = 0;
        for (int tries = 0; tries < 4000 && dir_count < 8; tries++) {
            test_sphere(&rng, dirs[dir_count]);
            wr_verdict v;
            assert_int_equal(wr_classify_verdict(a, dirs[dir_count], WR_SET_GOAL,
                                                 WR_DEFAULT_TOLERANCE, &v),
                             WR_OK);
            if (v == WR_VERDICT_INSIDE)
                dir_count++;
        }
        for (int w = 0; w < 2 * dir_count; w++) {
            double g[3];
            memcpy(g, dirs[w / 2], sizeof g);
            double size = test_range(&rng, 0.2, 6) * s->mu_static * s->total;
            for (int k = 0; k < 3; k++)
                g[k] *= size;
            wr_support_goal goal;
            assert_int_equal(wr_supports_goal(a, s, env, g, WR_DEFAULT_TOLERANCE, &goal), WR_OK);
            /* Inscribed: g in C + S_in means g in C + S (not seated);
             * circumscribed: g in no C + S_out means seated. */
            bool in_inner = false, in_outer = false;
            int count = wr_analysis_cone_count(a, WR_SET_GOAL);
            for (int c = 0; c < count; c++) {
                const wr_cone *cone = wr_analysis_cone(a, WR_SET_GOAL, c);
                if (cone->empty)
                    continue;
                double scale = fmax(1, size);
                in_inner |= poly_lp(f, s, cone, g, NULL, GLP_MIN, false) <= 1e-9 * scale;
                in_outer |= poly_lp(f, s, cone, g, NULL, GLP_MIN, true) <= 1e-9 * scale;
            }
            if (goal.verdict == WR_VERDICT_INSIDE) {
                assert_false(in_inner);
                inside++;
            }
            if (goal.verdict == WR_VERDICT_OUTSIDE) {
                assert_true(in_outer);
                outside++;
            }
            checked++;
        }
        /* The least force along a random push with a random load. */
        if (dir_count == 0)
            goto next;
        double push[3], load[3];
        memcpy(push, dirs[0], sizeof push);
        test_sphere(&rng, load);
        for (int k = 0; k < 3; k++)
            load[k] *= 0.5 * s->mu_static * s->total;
        double force, lower;
        assert_int_equal(wr_supports_least_force(a, s, env, (const double (*)[3])&load, 1, push,
                                                 &force, &lower),
                         WR_OK);
        double inner = poly_least_force(a, s, load, push, false);
        double outer = poly_least_force(a, s, load, push, true);
        double slack = 1e-7 * fmax(1, isfinite(outer) ? outer : 0);
        if (!(inner - slack <= force && force <= outer + slack))
            printf("trial %d: inner %.12g force %.12g (lower %.12g) outer %.12g\n", trial, inner,
                   force, lower, outer);
        if (isfinite(force) || isfinite(outer)) {
            assert_true(inner - slack <= force && force <= outer + slack);
            forces++;
        }
    next:
        wr_supports_free(s);
        wr_analysis_free(a);
        wr_fixture_free(f);
    }
    printf("256-gon bracket: %d wrenches (%d seat, %d do not), %d least forces\n", checked,
           inside, outside, forces);
    assert_true(checked >= 60 && inside > 0 && outside > 0 && forces >= 6);
    wr_lp_env_free(env);
}


/* The least push over the outline on the plate, against brute force: at
 * points spaced evenly along every edge, the 256-gon LPs' least force
 * (from inside, a lower bound of that point's F*; from outside, an upper
 * one).  wrenchd's least force is at most every point's upper value (no
 * sampled push seating with less), its certified lower bound at most
 * every sampled upper value, and at its own point its force is at least
 * the inscribed polygons' there (it is not below that point's F*).  The
 * chamfered plate (examples/plate-chamfered.json) with no load and under
 * a load along -y, and random polygons, each on three buttons. */
static wr_fixture *plate_chamfered(void)
{
    static const double vertices[5][2] = {{0, 0}, {4, 0}, {4, 1}, {3, 2}, {0, 2}};
    wr_fixel_spec fixels[3];
    memset(fixels, 0, sizeof fixels);
    fixels[0].at[0] = 1;
    fixels[1].at[0] = 3;
    fixels[2].at[1] = 0.5;
    wr_fixture_spec spec;
    memset(&spec, 0, sizeof spec);
    spec.mass = 2;
    spec.shape = WR_SHAPE_POLYGON;
    spec.vertex_count = 5;
    spec.vertices = vertices;
    spec.friction.given = true;
    spec.friction.static_mu = 0.1;
    spec.fixel_count = 3;
    spec.fixels = fixels;
    return test_fixture_new(&spec, NULL);
}

static void test_outline_least_sampled(void **state)
{
    (void)state;
    wr_lp_env *env = test_lp_env_new();
    test_rng rng = {20261129};
    const double buttons[3][2] = {{1, 0.5}, {3, 0.5}, {1.5, 1.6}};
    int checked = 0;
    for (int trial = 0; trial < 4; trial++) {
        wr_fixture *f = trial < 2 ? plate_chamfered() : test_random_fixture(&rng, 2, false);
        if (!f)
            continue;
        wr_analysis *a = test_analysis_new(f);
        double points[3][2];
        for (int i = 0; i < 3; i++) {
            double angle = 2 * TEST_PI * (i + 0.5) / 3;
            points[i][0] = trial < 2 ? buttons[i][0] : f->com[0] + 0.2 * f->size * cos(angle);
            points[i][1] = trial < 2 ? buttons[i][1] : f->com[1] + 0.2 * f->size * sin(angle);
        }
        wr_error error;
        wr_supports *s = supports_new(f, (const double (*)[2])points, 3, 0.2, G, NULL, 0, &error);
        if (!s) {
            printf("outline trial %d: %s %s\n", trial, error.field, error.reason);
            wr_analysis_free(a);
            wr_fixture_free(f);
            continue;
        }
        double load[3] = {0, trial == 1 ? -3.0 : 0, 0};
        wr_finger finger = {0};
        wr_least_force least;
        assert_int_equal(wr_supports_least_force_find(a, s, env, (const double (*)[3])&load, 1,
                                                      &finger, NULL, &least),
                         WR_OK);
        double sampled = INFINITY;
        enum { PER_EDGE = 24 };
        for (size_t e = 0; e < f->vertex_count; e++)
            for (int j = 0; j <= PER_EDGE; j++) {
                double push[3];
                wr_push_wrench(f, (int)e, (double)j / PER_EDGE, push);
                sampled = fmin(sampled, poly_least_force(a, s, load, push, true));
            }
        printf("outline trial %d: least %.9g (lower %.9g, %s, %lu points) at edge %d t %.6f; "
               "sampled %.9g\n",
               trial, least.force, least.lower, least.converged ? "converged" : "not converged",
               least.evaluations, least.edge, least.t, sampled);
        assert_true(least.found == isfinite(sampled));
        if (least.found) {
            assert_true(least.converged);
            assert_true(least.force <= sampled * (1 + 1e-6) + 1e-9);
            assert_true(least.lower <= sampled + 1e-9);
            assert_true(least.lower <= least.force &&
                        least.force - least.lower <= 2e-6 * least.force + 1e-9);
            double push[3];
            wr_push_wrench(f, least.edge, least.t, push);
            double inner = poly_least_force(a, s, load, push, false);
            assert_true(least.force >= inner * (1 - 1e-7) - 1e-9);
            checked++;
        }
        wr_supports_free(s);
        wr_analysis_free(a);
        wr_fixture_free(f);
    }
    assert_true(checked >= 3);
    wr_lp_env_free(env);
}

/* The in-plane tilt of the disc in the corner (fixel friction 0.5) on the
 * three buttons `tri`, W = m g.  As for a push through the centre (MODEL.md
 * section 11's worked example), every excluded cone holds the torque axis,
 * so gravity's in-plane pull m a (cos phi, sin phi) seats iff it is farther
 * than mu_B W from the complement of the goal wedge, whose edges are at
 * 180 + atan(1/2) and 270 - atan(1/2) degrees: m a sin(delta) > mu_B m g,
 * delta the angle to the nearer edge.  The arc is (180 + atan(1/2) +
 * delta*, 270 - atan(1/2) - delta*), sin(delta*) = mu_B g / a, none when
 * delta* exceeds the wedge's half, 18.435 degrees.  Floating (g = 0) it is
 * the whole wedge. */
static void test_tilt_disc(void **state)
{
    (void)state;
    wr_lp_env *env = test_lp_env_new();
    wr_fixture *f = test_disc_corner(0.5);
    wr_analysis *a = test_analysis_new(f);
    double edge = atan(0.5) * 180 / TEST_PI;
    const double pulls[3] = {20, 60, 9};
    for (int k = 0; k < 4; k++) {
        double mu = 0.3, g = k == 3 ? 0 : G;
        wr_error error;
        wr_supports *s = supports_new(f, tri, 3, mu, g, NULL, 0, &error);
        assert_non_null(s);
        double pull = k == 3 ? 20 : pulls[k];
        wr_regions good, undecided;
        assert_int_equal(wr_supports_gravity_sweep(a, s, env, pull, NULL, &good, &undecided),
                         WR_OK);
        double ratio = mu * g / pull;
        double delta = asin(fmin(1, ratio)) * 180 / TEST_PI;
        double from = 180 + edge + delta, to = 270 - edge - delta;
        printf("tilt, pull %g on g %g: %d arcs", pull, g, good.count);
        for (int i = 0; i < good.count; i++)
            printf(" (%.9f, %.9f)", good.items[i].t0, good.items[i].t1);
        printf("; closed form (%.9f, %.9f); %d undecided\n", from, to, undecided.count);
        if (from < to) {
            assert_int_equal(good.count, 1);
            assert_true(fabs(good.items[0].t0 - from) < 1e-5);
            assert_true(fabs(good.items[0].t1 - to) < 1e-5);
        } else {
            assert_int_equal(good.count, 0);
        }
        /* Undecided only where the circle meets a boundary. */
        for (int i = 0; i < undecided.count; i++) {
            double at = (undecided.items[i].t0 + undecided.items[i].t1) / 2;
            assert_true(undecided.items[i].t1 - undecided.items[i].t0 <= 1e-5);
            assert_true(fabs(at - from) < 1e-5 || fabs(at - to) < 1e-5);
        }
        wr_regions_release(&good);
        wr_regions_release(&undecided);
        wr_supports_free(s);
    }
    wr_analysis_free(a);
    wr_fixture_free(f);
    wr_lp_env_free(env);
}

/* Seating against mu_B, the disc again: a force F through the centre along
 * 225 degrees seats iff F sin(delta) > mu_B W, delta = 18.435 degrees
 * (sin = 1 / sqrt 10), so it seats for mu_B below F / (W sqrt 10): 0.96705
 * for F = 30, W = 9.81.  And for random wrenches of the 3-2-1 plate on
 * buttons, wr_supports_goal at 0.999 and 1.001 times the limit (the
 * fixture placed again with that mu_B) says inside and outside. */
static void test_friction_limit(void **state)
{
    (void)state;
    wr_lp_env *env = test_lp_env_new();
    wr_fixture *f = test_disc_corner(0.5);
    wr_analysis *a = test_analysis_new(f);
    wr_error error;
    wr_supports *s = supports_new(f, tri, 3, 0.3, G, NULL, 0, &error);
    double g[3] = {-30 / sqrt(2), -30 / sqrt(2), 0}, bracket[2];
    assert_int_equal(wr_supports_friction_limit(a, s, env, g, bracket), WR_OK);
    double expected = 30 / (G * sqrt(10));
    printf("mu_B limit, disc: [%.12g, %.12g], closed form %.12g\n", bracket[0], bracket[1],
           expected);
    assert_true(fabs(bracket[0] - expected) < 1e-8 && fabs(bracket[1] - expected) < 1e-8);
    wr_supports_free(s);
    wr_analysis_free(a);
    wr_fixture_free(f);

    f = test_plate_321();
    a = test_analysis_new(f);
    const double buttons[3][2] = {{1, 0.5}, {3, 0.5}, {2, 1.7}};
    test_rng rng = {20261130};
    int checked = 0;
    for (int tries = 0; tries < 400 && checked < 6; tries++) {
        double w[3];
        test_sphere(&rng, w);
        for (int k = 0; k < 3; k++)
            w[k] *= 20;
        s = supports_new(f, buttons, 3, 0.2, G, NULL, 0, &error);
        assert_int_equal(wr_supports_friction_limit(a, s, env, w, bracket), WR_OK);
        wr_supports_free(s);
        if (!(bracket[0] > 0.01 && bracket[1] < 5))
            continue;
        for (int side = -1; side <= 1; side += 2) {
            s = supports_new(f, buttons, 3, bracket[side > 0] * (1 + side * 1e-3), G, NULL, 0,
                             &error);
            wr_support_goal goal;
            assert_int_equal(wr_supports_goal(a, s, env, w, WR_DEFAULT_TOLERANCE, &goal), WR_OK);
            assert_int_equal(goal.verdict, side < 0 ? WR_VERDICT_INSIDE : WR_VERDICT_OUTSIDE);
            wr_supports_free(s);
        }
        checked++;
    }
    printf("mu_B limit, 3-2-1 plate: %d wrenches seat below their limit, not above\n", checked);
    assert_true(checked >= 4);
    wr_analysis_free(a);
    wr_fixture_free(f);
    wr_lp_env_free(env);
}

/* ---- holding --------------------------------------------------------------- */

/* At zero load nothing moves the part: for every fixture and buttons of
 * the bracket test below, and for the two worked examples. */
static void test_zero_load_held(void **state)
{
    (void)state;
    wr_lp_env *env = test_lp_env_new();
    wr_fixture *fixtures[2] = {test_disc_corner(0.5), test_plate_321()};
    const double plate_buttons[3][2] = {{1, 0.5}, {3, 0.5}, {2, 1.7}};
    for (int k = 0; k < 2; k++) {
        wr_analysis *a = test_analysis_new(fixtures[k]);
        wr_error error;
        wr_supports *s = supports_new(fixtures[k], k ? plate_buttons : tri, 3, 0.2, G, NULL, 0,
                                      &error);
        assert_non_null(s);
        double zero[3] = {0, 0, 0};
        wr_support_strong strong;
        assert_int_equal(
            wr_supports_strong(a, s, env, zero, WR_DEFAULT_TOLERANCE, NULL, &strong), WR_OK);
        printf("zero load, %s: %s after %d cells\n", k ? "3-2-1 plate" : "disc",
               strong.verdict == WR_VERDICT_INSIDE ? "held" : "not held", strong.cells);
        assert_int_equal(strong.verdict, WR_VERDICT_INSIDE);
        wr_supports_free(s);
        wr_analysis_free(a);
        wr_fixture_free(fixtures[k]);
    }
    wr_lp_env_free(env);
}

/* The 3-2-1 plate (m = 2, centre of mass (2, 1)) on buttons at (1, 0.5),
 * (3, 0.5) and (2, 1.7), mu_B = 0.2 (static and kinetic), a down clamp of
 * D at the centre of mass: the centre of pressure stays at the centre of
 * mass, W = m g + D.  A cutting force F_c along +x through the centre of
 * mass pulls the plate off its left locator.
 *
 * Any motion q of the seated plate has, dotted with q (as a power), on
 * the load's side F_c a_x (the force acts at the centre of mass) and on the
 * other the inertia q.M.q >= 0, the fixels' forces' share >= 0 (they push
 * and their friction opposes sliding) and the buttons' friction
 * sum mu_B N_i |a_i| >= mu_B |sum N_i a_i| = mu_B W |a_com| (the buttons'
 * weighted mean acceleration is the centre of pressure's).  So a motion
 * needs F_c >= mu_B W, and at F_c > mu_B W the translation along +x is one
 * (fixels 1 and 2 sliding unloaded, fixel 3 leaving, a_x = (F_c - mu_B W)
 * / m).  The least clamp that holds is
 *
 *     D* = F_c / mu_B - m g.
 *
 * wrenchd: held at 1.001 D*, moves (with that translation) at 0.999 D*. */
static void test_plate_clamp(void **state)
{
    (void)state;
    wr_lp_env *env = test_lp_env_new();
    wr_fixture *f = test_plate_321();
    wr_analysis *a = test_analysis_new(f);
    const double buttons[3][2] = {{1, 0.5}, {3, 0.5}, {2, 1.7}};
    double mu_b = 0.2, cutting = 30;
    double expected = cutting / mu_b - 2 * G;
    double load[3] = {cutting, 0, 0};
    for (int side = -1; side <= 1; side += 2) {
        wr_down_spec down = {{2, 1}, expected * (1 + side * 1e-3)};
        wr_error error;
        wr_supports *s = supports_new(f, buttons, 3, mu_b, G, &down, 1, &error);
        assert_non_null(s);
        wr_support_strong strong;
        assert_int_equal(
            wr_supports_strong(a, s, env, load, WR_DEFAULT_TOLERANCE, NULL, &strong), WR_OK);
        printf("3-2-1 plate, clamp %.6g (D* = %.6g): %s, %d cells, %d LPs\n", down.force,
               expected, strong.verdict == WR_VERDICT_INSIDE ? "held" : "moves", strong.cells,
               strong.solves);
        if (side > 0) {
            assert_int_equal(strong.verdict, WR_VERDICT_INSIDE);
        } else {
            assert_int_equal(strong.verdict, WR_VERDICT_OUTSIDE);
            /* The witness: the translation along +x, a_x = (F_c - mu W) / m. */
            double w = 2 * G + down.force;
            assert_true(fabs(strong.acceleration[0] - (cutting - mu_b * w) / 2) <
                        1e-6 * cutting);
            assert_true(fabs(strong.acceleration[1]) < 1e-6 && fabs(strong.acceleration[2]) < 1e-6);
        }
        wr_supports_free(s);
    }
    wr_analysis_free(a);
    wr_fixture_free(f);
    wr_lp_env_free(env);
}

/* The 3-2-1 plate cut by F_c = 3 along +x through its centre of mass, no
 * clamp, on the buttons above: by test_plate_clamp's power argument held
 * exactly for mu_B >= F_c / W (0.1529; W = m g), moved below by the
 * translation along +x.  Every mu_B of a fine grid either side must say
 * so, not boundary: a refinement of a cell's discs that GLPK cannot solve
 * leaves the cell's last bound, which still drops it (it failed at about
 * one mu_B in four between 0.48 and 0.49). */
static void test_plate_held_every_mu(void **state)
{
    (void)state;
    wr_lp_env *env = test_lp_env_new();
    wr_fixture *f = test_plate_321();
    wr_analysis *a = test_analysis_new(f);
    const double buttons[3][2] = {{1, 0.5}, {3, 0.5}, {2, 1.7}};
    const double cutting = 3, threshold = cutting / (2 * G);
    const double load[3] = {cutting, 0, 0};
    int held = 0, moved = 0;
    for (int k = 0; k <= 160; k++) {
        double mu = k < 16 ? threshold * (0.2 + 0.05 * k) : threshold * 1.001 + 0.005 * (k - 16);
        wr_error error;
        wr_supports *s = supports_new(f, buttons, 3, mu, G, NULL, 0, &error);
        assert_non_null(s);
        wr_support_strong strong;
        assert_int_equal(
            wr_supports_strong(a, s, env, load, WR_DEFAULT_TOLERANCE, NULL, &strong), WR_OK);
        if (mu > threshold) {
            assert_int_equal(strong.verdict, WR_VERDICT_INSIDE);
            held++;
        } else {
            assert_int_equal(strong.verdict, WR_VERDICT_OUTSIDE);
            moved++;
        }
        wr_supports_free(s);
    }
    printf("plate cut by %g: held at %d mu_B above %.6f, moves at %d below\n", cutting, held,
           threshold, moved);
    wr_analysis_free(a);
    wr_fixture_free(f);
    wr_lp_env_free(env);
}

/* A pivot on a button.  The trapezoid (0,0) (4,0) (5,2) (0,2), m = 2, on
 * buttons p1 = (0, 0.5), p2 = (3, 0.5), p3 = (2, 1.7), mu_B = 0.15, its
 * three fixels (1,0), (3,0) below and (0,1) on the left, pulled by a force
 * (0, s) at its corner (0, 0).  The part can turn clockwise about p2 while
 * leaving every fixel: p2 sticks (its force anywhere in |f2| <= mu N2),
 * p1 and p3 slide against their accelerations.  With the direction fixed,
 * Newton-Euler is linear in (f2, t), t >= 0 the size of the motion:
 *
 *     g(s) + f1 + f3 (with their moments) + (f2, r2 x f2) = t M q,
 *
 * three equations in three unknowns, and t is affine in s: the part
 * moves for s above the root s* of t(s) = 0 (here, where |f2| is well
 * inside its disc).  That motion is one direction, at which p2's sliding
 * direction is undefined: wrenchd must find it as the witness above s*,
 * and hold the part below.  Everything here is computed from the
 * geometry: centre of mass and inertia by the polygon's integrals,
 * normal forces by barycentric coordinates. */
static double pivot_t(double s, const double com[2], double m, double inertia,
                      const double (*p)[2], const double *n, double mu, double *f2)
{
    double r2[2] = {p[1][0] - com[0], p[1][1] - com[1]};
    /* Clockwise about p2: a_com = -(-r2y, r2x), alpha = -1. */
    double q[3] = {-r2[1], r2[0], -1};
    double rhs[3] = {0, s, (0 - com[0]) * s - (0 - com[1]) * 0};
    for (int j = 0; j < 3; j += 2) {
        double r[2] = {p[j][0] - com[0], p[j][1] - com[1]};
        double a[2] = {q[0] - q[2] * r[1], q[1] + q[2] * r[0]};
        double len = hypot(a[0], a[1]);
        double f[2] = {-mu * n[j] * a[0] / len, -mu * n[j] * a[1] / len};
        rhs[0] += f[0];
        rhs[1] += f[1];
        rhs[2] += r[0] * f[1] - r[1] * f[0];
    }
    /* [1 0 -m qx; 0 1 -m qy; -r2y r2x -I alpha] (f2x, f2y, t) = -rhs. */
    double A[3][3] = {{1, 0, -m * q[0]}, {0, 1, -m * q[1]}, {-r2[1], r2[0], -inertia * q[2]}};
    double b[3] = {-rhs[0], -rhs[1], -rhs[2]};
    double det = A[0][0] * (A[1][1] * A[2][2] - A[1][2] * A[2][1]) -
                 A[0][1] * (A[1][0] * A[2][2] - A[1][2] * A[2][0]) +
                 A[0][2] * (A[1][0] * A[2][1] - A[1][1] * A[2][0]);
    double x[3];
    for (int k = 0; k < 3; k++) { /* Cramer */
        double B[3][3];
        memcpy(B, A, sizeof B);
        for (int r = 0; r < 3; r++)
            B[r][k] = b[r];
        x[k] = (B[0][0] * (B[1][1] * B[2][2] - B[1][2] * B[2][1]) -
                B[0][1] * (B[1][0] * B[2][2] - B[1][2] * B[2][0]) +
                B[0][2] * (B[1][0] * B[2][1] - B[1][1] * B[2][0])) /
               det;
    }
    *f2 = hypot(x[0], x[1]);
    return x[2];
}

static void test_pivot_on_button(void **state)
{
    (void)state;
    static const double v[4][2] = {{0, 0}, {4, 0}, {5, 2}, {0, 2}};
    const double buttons[3][2] = {{0, 0.5}, {3, 0.5}, {2, 1.7}};
    const double mu = 0.15, m = 2;
    wr_fixture *f = test_quad_321(v, 0.3, 0.25);
    assert_non_null(f);
    /* The polygon's area, centroid and polar moment about the origin. */
    double area = 0, cx = 0, cy = 0, j0 = 0;
    for (int k = 0; k < 4; k++) {
        const double *a = v[k], *b = v[(k + 1) % 4];
        double cr = a[0] * b[1] - b[0] * a[1];
        area += cr / 2;
        cx += (a[0] + b[0]) * cr / 6;
        cy += (a[1] + b[1]) * cr / 6;
        j0 += (a[0] * a[0] + a[0] * b[0] + b[0] * b[0] + a[1] * a[1] + a[1] * b[1] + b[1] * b[1]) *
              cr / 12;
    }
    double com[2] = {cx / area, cy / area};
    double inertia = m * j0 / area - m * (com[0] * com[0] + com[1] * com[1]);
    /* N_i = W times the barycentric coordinates of the centre of mass. */
    const double (*p)[2] = buttons;
    double w = m * G, n[3];
    double d = (p[1][1] - p[2][1]) * (p[0][0] - p[2][0]) + (p[2][0] - p[1][0]) * (p[0][1] - p[2][1]);
    n[0] = w * ((p[1][1] - p[2][1]) * (com[0] - p[2][0]) + (p[2][0] - p[1][0]) * (com[1] - p[2][1])) / d;
    n[1] = w * ((p[2][1] - p[0][1]) * (com[0] - p[2][0]) + (p[0][0] - p[2][0]) * (com[1] - p[2][1])) / d;
    n[2] = w - n[0] - n[1];
    double f2, t0 = pivot_t(0, com, m, inertia, p, n, mu, &f2);
    double t1 = pivot_t(1, com, m, inertia, p, n, mu, &f2) - t0;
    double star = -t0 / t1;
    pivot_t(star, com, m, inertia, p, n, mu, &f2);
    assert_true(f2 < 0.9 * mu * n[1]); /* p2 sticks, well inside its disc */
    wr_lp_env *env = test_lp_env_new();
    wr_analysis *a = test_analysis_new(f);
    wr_error error;
    wr_supports *s = supports_new(f, buttons, 3, mu, G, NULL, 0, &error);
    assert_non_null(s);
    for (int side = -1; side <= 1; side += 2) {
        double size = star * (1 + side * 1e-6);
        double g[3] = {0, size, (0 - com[0]) * size};
        wr_support_strong strong;
        assert_int_equal(wr_supports_strong(a, s, env, g, WR_DEFAULT_TOLERANCE, NULL, &strong),
                         WR_OK);
        printf("pivot on a button: s* = %.9f, at %+.0e: %s\n", star, side * 1e-6,
               strong.verdict == WR_VERDICT_INSIDE    ? "held"
               : strong.verdict == WR_VERDICT_OUTSIDE ? "moves"
                                                      : "boundary");
        if (side < 0) {
            assert_int_equal(strong.verdict, WR_VERDICT_INSIDE);
            continue;
        }
        assert_int_equal(strong.verdict, WR_VERDICT_OUTSIDE);
        /* The witness turns clockwise about p2: that point stands still. */
        double r2[2] = {p[1][0] - com[0], p[1][1] - com[1]};
        const double *q = strong.acceleration;
        assert_true(q[2] < 0);
        assert_true(hypot(q[0] - q[2] * r2[1], q[1] + q[2] * r2[0]) < 1e-6 * fabs(q[2]));
        assert_true(hypot(strong.support_force[1][0], strong.support_force[1][1]) <=
                    mu * strong.normal[1] * (1 + 1e-9));
    }
    wr_supports_free(s);
    wr_analysis_free(a);
    wr_fixture_free(f);
    wr_lp_env_free(env);
}

/* Is the motion along the scaled acceleration direction q' of mode `cone`
 * consistent with g?  This file's own LP: g = t q' + sum kappa_j G_j (the
 * mode's contact generators) + sum_i m_i W(a_i / |a_i|) at p_i, t >= 0,
 * mu_k_min N_i <= m_i <= mu_k N_i, N >= 0 with the statics rows (not
 * wrenchd's distributions); returns the least L1 residual in the scaled
 * metric.  A point whose acceleration vanishes (the part pivots on it: a
 * measure-zero set of directions, never sampled, but a witness may be
 * one) sticks: its friction is any force of an inscribed 256-gon of its
 * disc |f| <= mu_s N_i, so a residual of 0 still proves the motion. */
static double motion_residual(const wr_fixture *f, const wr_supports *s, const wr_cone *cone,
                              const double g[3], const double q[3])
{
    glp_prob *p = glp_create_prob();
    glp_set_obj_dir(p, GLP_MIN);
    int n = s->count;
    glp_add_rows(p, 6 + 2 * n);
    double h[3];
    wr_fixture_scale_wrench(f, g, h);
    for (int k = 0; k < 3; k++)
        glp_set_row_bnds(p, 1 + k, GLP_FX, h[k], h[k]);
    glp_set_row_bnds(p, 4, GLP_FX, s->total, s->total);
    glp_set_row_bnds(p, 5, GLP_FX, s->total * s->pressure[0], s->total * s->pressure[0]);
    glp_set_row_bnds(p, 6, GLP_FX, s->total * s->pressure[1], s->total * s->pressure[1]);
    for (int i = 0; i < n; i++) {
        glp_set_row_bnds(p, 7 + 2 * i, GLP_UP, 0, 0); /* m_i - mu_k N_i <= 0 */
        glp_set_row_bnds(p, 8 + 2 * i, GLP_LO, 0, 0); /* m_i - mu_k_min N_i >= 0 */
    }
    enum { ENTRIES = 8192 };
    int *ia = malloc(ENTRIES * sizeof *ia), *ja = malloc(ENTRIES * sizeof *ja);
    double *ar = malloc(ENTRIES * sizeof *ar);
    assert_true(ia && ja && ar);
    int count = 0;
#define SET(r, c, v) (count++, ia[count] = (r), ja[count] = (c), ar[count] = (v))
    int t = glp_add_cols(p, 1);
    glp_set_col_bnds(p, t, GLP_LO, 0, 0);
    for (int k = 0; k < 3; k++)
        SET(1 + k, t, q[k]);
    for (int j = 0; j < cone->generator_count; j++) {
        if (cone->origins[j].fixel < 0)
            continue;
        int c = glp_add_cols(p, 1);
        glp_set_col_bnds(p, c, GLP_LO, 0, 0);
        for (int k = 0; k < 3; k++)
            SET(1 + k, c, cone->generators[j][k]);
    }
    double rho = f->gyration_radius;
    double ax = q[0] / f->mass, ay = q[1] / f->mass, alpha = q[2] / (f->mass * rho);
    for (int i = 0; i < n; i++) {
        double rx = s->points[i][0] - f->com[0], ry = s->points[i][1] - f->com[1];
        double a[2] = {ax - alpha * ry, ay + alpha * rx};
        double norm = hypot(a[0], a[1]);
        int N = glp_add_cols(p, 2);
        glp_set_col_bnds(p, N, GLP_LO, 0, 0);
        glp_set_col_bnds(p, N + 1, GLP_LO, 0, 0);
        SET(4, N, 1);
        SET(5, N, s->points[i][0]);
        SET(6, N, s->points[i][1]);
        if (!(norm > 1e-9 * (fabs(ax) + fabs(ay) + fabs(alpha) * f->size))) {
            /* Sticking: sum lambda_k <= mu_s N_i over the 256-gon's
             * vertices (its sliding rows stay empty, its size column 0). */
            glp_set_col_bnds(p, N + 1, GLP_FX, 0, 0);
            int row = glp_add_rows(p, 1);
            glp_set_row_bnds(p, row, GLP_UP, 0, 0);
            SET(row, N, -s->mu_static);
            int first = glp_add_cols(p, 256);
            for (int k = 0; k < 256; k++) {
                double u[2] = {cos(2 * acos(-1.0) * k / 256), sin(2 * acos(-1.0) * k / 256)};
                glp_set_col_bnds(p, first + k, GLP_LO, 0, 0);
                SET(row, first + k, 1);
                SET(1, first + k, u[0]);
                SET(2, first + k, u[1]);
                SET(3, first + k, (rx * u[1] - ry * u[0]) / rho);
            }
            continue;
        }
        a[0] /= norm;
        a[1] /= norm;
        SET(7 + 2 * i, N, -s->mu_kinetic);
        SET(8 + 2 * i, N, -s->mu_kinetic_min);
        int m = N + 1; /* the friction's size, along a_i (it opposes the motion: -f = m a) */
        SET(7 + 2 * i, m, 1);
        SET(8 + 2 * i, m, 1);
        SET(1, m, a[0]);
        SET(2, m, a[1]);
        SET(3, m, (rx * a[1] - ry * a[0]) / rho);
    }
    count = residual_columns(p, count, ia, ja, ar);
#undef SET
    glp_load_matrix(p, count, ia, ja, ar);
    glp_smcp parm;
    glp_init_smcp(&parm);
    parm.msg_lev = GLP_MSG_OFF;
    assert_int_equal(glp_simplex(p, &parm), 0);
    assert_int_equal(glp_get_status(p), GLP_OPT);
    double residual = glp_get_obj_val(p);
    glp_delete_prob(p);
    free(ia);
    free(ja);
    free(ar);
    return residual;
}

/* Random loads on the disc and on the 3-2-1 plate on 3 and 4 buttons:
 * where wrenchd says held, no direction of a dense sample of every moving
 * mode's directions (each mode's acceleration generators combined with
 * random weights, 400 per mode) is consistent; where it says moves, its
 * witness direction is consistent by this file's LP. */
static void test_holding_sampled(void **state)
{
    (void)state;
    test_rng rng = {8128};
    wr_lp_env *env = test_lp_env_new();
    int held = 0, moves = 0, boundary = 0, samples = 0;
    for (int trial = 0; trial < 8; trial++) {
        wr_fixture *f = trial % 2 ? test_plate_321() : test_disc_corner(test_range(&rng, 0.2, 0.6));
        wr_analysis *a = test_analysis_new(f);
        const double plate4[4][2] = {{0.5, 0.4}, {3.5, 0.4}, {3.5, 1.6}, {0.5, 1.6}};
        const double disc4[4][2] = {{0.3, 0.3}, {-0.3, 0.3}, {-0.3, -0.3}, {0.3, -0.3}};
        const double plate3[3][2] = {{1, 0.5}, {3, 0.5}, {2, 1.7}};
        int n = trial % 4 < 2 ? 3 : 4;
        const double (*points)[2] = trial % 2 ? (n == 3 ? plate3 : plate4) : (n == 3 ? tri : disc4);
        wr_error error;
        wr_supports *s = supports_new(f, points, n, test_range(&rng, 0.1, 0.5), G, NULL, 0, &error);
        assert_non_null(s);
        for (int w = 0; w < 6; w++) {
            double g[3];
            test_sphere(&rng, g);
            double size = test_range(&rng, 0.3, 3) * s->mu_static * s->total;
            g[2] *= f->gyration_radius;
            for (int k = 0; k < 3; k++)
                g[k] *= size;
            wr_support_strong strong;
            assert_int_equal(
                wr_supports_strong(a, s, env, g, WR_DEFAULT_TOLERANCE, NULL, &strong), WR_OK);
            double scale = fmax(size, s->mu_static * s->total);
            if (strong.verdict == WR_VERDICT_OUTSIDE) {
                const wr_cone *cone = wr_analysis_cone(a, WR_SET_STRONG, strong.blocking);
                double q[3] = {strong.acceleration[0] * f->mass, strong.acceleration[1] * f->mass,
                               strong.acceleration[2] * f->mass * f->gyration_radius};
                double norm = sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2]);
                if (norm > 0) {
                    for (int k = 0; k < 3; k++)
                        q[k] /= norm;
                    assert_true(motion_residual(f, s, cone, g, q) <= 1e-8 * scale);
                }
                moves++;
                continue;
            }
            if (strong.verdict == WR_VERDICT_BOUNDARY) {
                boundary++;
                continue;
            }
            held++;
            int modes = wr_analysis_cone_count(a, WR_SET_STRONG);
            for (int c = 0; c < modes; c++) {
                const wr_cone *cone = wr_analysis_cone(a, WR_SET_STRONG, c);
                if (cone->empty)
                    continue;
                for (int k = 0; k < 400; k++) {
                    double q[3] = {0, 0, 0};
                    for (int j = 0; j < cone->generator_count; j++) {
                        if (cone->origins[j].fixel >= 0)
                            continue;
                        double weight = test_uniform(&rng);
                        weight = weight * weight * weight; /* some near the edges */
                        for (int r = 0; r < 3; r++)
                            q[r] += weight * cone->generators[j][r];
                    }
                    double norm = sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2]);
                    if (!(norm > 1e-9))
                        continue;
                    for (int r = 0; r < 3; r++)
                        q[r] /= norm;
                    assert_true(motion_residual(f, s, cone, g, q) > 1e-9 * scale);
                    samples++;
                }
            }
        }
        wr_supports_free(s);
        wr_analysis_free(a);
        wr_fixture_free(f);
    }
    printf("holding: %d held (%d directions sampled, none consistent), %d move (witness "
           "found again), %d boundary\n",
           held, samples, moves, boundary);
    assert_true(held > 0 && moves > 0);
    wr_lp_env_free(env);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_statics),
        cmocka_unit_test(test_disc_least_force),
        cmocka_unit_test(test_polygon_bracket),
        cmocka_unit_test(test_outline_least_sampled),
        cmocka_unit_test(test_tilt_disc),
        cmocka_unit_test(test_friction_limit),
        cmocka_unit_test(test_zero_load_held),
        cmocka_unit_test(test_plate_clamp),
        cmocka_unit_test(test_pivot_on_button),
        cmocka_unit_test(test_plate_held_every_mu),
        cmocka_unit_test(test_holding_sampled),
    };
    if (getenv("TEST_FILTER")) /* one test by name, while working on it */
        cmocka_set_test_filter(getenv("TEST_FILTER"));
    return cmocka_run_group_tests(tests, NULL, NULL);
}
