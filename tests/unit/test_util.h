/* test_util.h -- deterministic random numbers and random fixtures for the
 * unit tests.  Header-only; every function is static. */
#ifndef TEST_UTIL_H
#define TEST_UTIL_H

#include "wrench.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#define TEST_PI 3.14159265358979323846

/* The constructors in pointer form, for tests that need only the object:
 * NULL unless WR_OK.  (Tests of the statuses call the constructors.) */
static inline wr_fixture *test_fixture_new(const wr_fixture_spec *spec, wr_error *error)
{
    wr_fixture *fixture;
    return wr_fixture_new(spec, &fixture, error) == WR_OK ? fixture : NULL;
}

/* A body alone (wr_fixture_body_new): a polygon of mass 1; NULL when it is
 * refused (the caller asserts). */
static inline wr_fixture *test_polygon_body(const double (*vertices)[2], size_t count)
{
    wr_fixture_spec spec;
    memset(&spec, 0, sizeof spec);
    spec.mass = 1;
    spec.shape = WR_SHAPE_POLYGON;
    spec.vertex_count = count;
    spec.vertices = vertices;
    wr_fixture *body = NULL;
    wr_error error;
    if (wr_fixture_body_new(&spec, &body, &error) != WR_OK)
        return NULL;
    return body;
}

/* A body alone of an outline's loops, mass 1; with `com` (NULL: the
 * lamina's centroid) given, its inertia 50.  NULL when refused. */
static inline wr_fixture *test_outline_body(const wr_loop_spec *loops, size_t count,
                                            const double *com)
{
    wr_fixture_spec spec;
    memset(&spec, 0, sizeof spec);
    spec.mass = 1;
    spec.shape = WR_SHAPE_OUTLINE;
    spec.loops = loops;
    spec.loop_count = count;
    if (com) {
        spec.com_given = true;
        spec.com[0] = com[0];
        spec.com[1] = com[1];
        spec.inertia_given = true;
        spec.inertia = 50;
    }
    wr_fixture *body = NULL;
    wr_error error;
    return wr_fixture_body_new(&spec, &body, &error) == WR_OK ? body : NULL;
}

/* A design job made and run to the end: its first status not WR_OK, or
 * WR_OK with *out done. */
static inline wr_status test_design_run(const wr_design_spec *spec, wr_design_job **out)
{
    wr_error error;
    wr_status status = wr_design_job_new(spec, out, &error);
    for (bool done = false; status == WR_OK && !done;)
        status = wr_design_job_run(*out, 1000000, NULL, NULL, NULL, &done);
    return status;
}

static inline wr_analysis *test_analysis_new(const wr_fixture *fixture)
{
    wr_analysis *analysis;
    return wr_analysis_new(fixture, &analysis) == WR_OK ? analysis : NULL;
}

static inline wr_plan *test_plan_new(int fixel_count)
{
    wr_plan *plan;
    return wr_plan_new(fixel_count, &plan) == WR_OK ? plan : NULL;
}

static inline wr_lp_env *test_lp_env_new(void)
{
    wr_lp_env *env;
    return wr_lp_env_new(&env) == WR_OK ? env : NULL;
}

/* xorshift64*: a fixed seed gives the same sequence on every machine. */
typedef struct test_rng {
    uint64_t state;
} test_rng;

static inline double test_uniform(test_rng *rng)
{
    rng->state ^= rng->state >> 12;
    rng->state ^= rng->state << 25;
    rng->state ^= rng->state >> 27;
    return (double)((rng->state * 2685821657736338717ULL) >> 11) / 9007199254740992.0;
}

static inline double test_range(test_rng *rng, double lo, double hi)
{
    return lo + (hi - lo) * test_uniform(rng);
}

/* A direction uniform on the unit sphere. */
static inline void test_sphere(test_rng *rng, double v[3])
{
    double z = test_range(rng, -1, 1), phi = test_range(rng, 0, 2 * TEST_PI);
    double r = sqrt(1 - z * z);
    v[0] = r * cos(phi);
    v[1] = r * sin(phi);
    v[2] = z;
}

/* k random angles (radians) on a circle, each pair at least `degrees`
 * apart and at least that far from opposite: fixels there neither
 * coincide nor face each other across a disc. */
static inline void test_spaced_angles(test_rng *rng, int k, double degrees, double angles[])
{
    double gap = degrees * TEST_PI / 180;
    for (int i = 0; i < k; i++) {
        bool spaced;
        do {
            angles[i] = test_range(rng, 0, 2 * TEST_PI);
            spaced = true;
            for (int j = 0; j < i; j++) {
                double d = fabs(angles[i] - angles[j]);
                d = fmin(d, 2 * TEST_PI - d);
                spaced &= d > gap && fabs(d - TEST_PI) > gap;
            }
        } while (!spaced);
    }
}

/* A random fixture: even seeds give a disc, odd seeds a convex polygon (in
 * either orientation); k fixels on the boundary with the normal left out
 * (so the library's inward normal is used), fixels at least 12 degrees
 * apart on a disc and off the polygon's vertices; friction mu_s in [0, 1.2],
 * mu_k <= mu_s, sometimes per fixel.  Caller frees with wr_fixture_free(). */
static inline wr_fixture *test_random_fixture(test_rng *rng, int k, bool disc)
{
    wr_fixture_spec spec;
    memset(&spec, 0, sizeof spec);
    wr_fixel_spec fixels[WR_MAX_FIXELS];
    memset(fixels, 0, sizeof fixels);
    double vertices[8][2];
    spec.mass = test_range(rng, 0.5, 3);
    spec.friction.given = true;
    spec.friction.static_mu = test_range(rng, 0, 1.2);
    spec.friction.kinetic_given = true;
    spec.friction.kinetic_mu = spec.friction.static_mu * test_range(rng, 0.5, 1);
    if (disc) {
        spec.shape = WR_SHAPE_CIRCLE;
        spec.radius = test_range(rng, 0.5, 2);
        spec.center[0] = test_range(rng, -1, 1);
        spec.center[1] = test_range(rng, -1, 1);
        double angles[WR_MAX_FIXELS];
        test_spaced_angles(rng, k, 12, angles);
        for (int i = 0; i < k; i++) {
            fixels[i].at[0] = spec.center[0] + spec.radius * cos(angles[i]);
            fixels[i].at[1] = spec.center[1] + spec.radius * sin(angles[i]);
        }
        /* Sometimes the centre of mass is off the centre. */
        if (test_uniform(rng) < 0.5) {
            spec.com_given = true;
            spec.com[0] = spec.center[0] + test_range(rng, -0.3, 0.3) * spec.radius;
            spec.com[1] = spec.center[1] + test_range(rng, -0.3, 0.3) * spec.radius;
        }
    } else {
        int n = 4 + (int)(test_uniform(rng) * 5); /* 4..8 vertices */
        bool clockwise = test_uniform(rng) < 0.5;
        for (int i = 0; i < n; i++) {
            double angle = 2 * TEST_PI * (i + test_range(rng, 0.1, 0.9)) / n;
            double radius = test_range(rng, 0.7, 1.5);
            int at = clockwise ? n - 1 - i : i;
            vertices[at][0] = radius * cos(angle);
            vertices[at][1] = radius * sin(angle);
        }
        spec.shape = WR_SHAPE_POLYGON;
        spec.vertex_count = (size_t)n;
        spec.vertices = (const double (*)[2])vertices;
        /* Distinct edges when there are enough, so fixels are not all
         * parallel; a polygon this random is convex only by chance, which
         * does not matter here. */
        for (int i = 0; i < k; i++) {
            int edge = (int)(test_uniform(rng) * n);
            double t = test_range(rng, 0.15, 0.85);
            const double *a = vertices[edge], *b = vertices[(edge + 1) % n];
            fixels[i].at[0] = a[0] + t * (b[0] - a[0]);
            fixels[i].at[1] = a[1] + t * (b[1] - a[1]);
        }
    }
    for (int i = 0; i < k; i++)
        if (test_uniform(rng) < 0.2) {
            fixels[i].friction.given = true;
            fixels[i].friction.static_mu = test_range(rng, 0, 1);
        }
    spec.fixel_count = (size_t)k;
    spec.fixels = fixels;
    wr_error error;
    return test_fixture_new(&spec, &error);
}

/* The disc in a corner of docs/MODEL.md section 7, as a spec whose fixels
 * are `fixels` (the caller's, two): another outline may replace the
 * circle. */
static inline void test_disc_corner_spec(double mu, wr_fixel_spec fixels[2],
                                         wr_fixture_spec *spec)
{
    memset(fixels, 0, 2 * sizeof fixels[0]);
    fixels[0].at[0] = -1;
    fixels[1].at[1] = -1;
    memset(spec, 0, sizeof *spec);
    spec->mass = 1;
    spec->inertia_given = true;
    spec->inertia = 0.5;
    spec->shape = WR_SHAPE_CIRCLE;
    spec->radius = 1;
    spec->friction.given = true;
    spec->friction.static_mu = mu;
    spec->fixel_count = 2;
    spec->fixels = fixels;
}

static inline wr_fixture *test_disc_corner(double mu)
{
    wr_fixel_spec fixels[2];
    wr_fixture_spec spec;
    test_disc_corner_spec(mu, fixels, &spec);
    return test_fixture_new(&spec, NULL);
}

/* A quadrilateral of mass 2 with the 3-2-1 plate's fixels at (1, 0),
 * (3, 0) and (0, 1), friction mu_s, mu_k. */
static inline wr_fixture *test_quad_321(const double (*vertices)[2], double mu_s, double mu_k)
{
    wr_fixel_spec fixels[3];
    memset(fixels, 0, sizeof fixels);
    fixels[0].at[0] = 1;
    fixels[1].at[0] = 3;
    fixels[2].at[1] = 1;
    wr_fixture_spec spec;
    memset(&spec, 0, sizeof spec);
    spec.mass = 2;
    spec.shape = WR_SHAPE_POLYGON;
    spec.vertex_count = 4;
    spec.vertices = vertices;
    spec.friction.given = true;
    spec.friction.static_mu = mu_s;
    spec.friction.kinetic_given = true;
    spec.friction.kinetic_mu = mu_k;
    spec.fixel_count = 3;
    spec.fixels = fixels;
    return test_fixture_new(&spec, NULL);
}

/* The 3-2-1 plate of docs/MODEL.md section 7.2 (4 by 2, m = 2, fixels at
 * (1, 0), (3, 0) and (0, 1)) with fixels of friction mu_s, mu_k. */
static inline wr_fixture *test_plate_321_friction(double mu_s, double mu_k)
{
    static const double vertices[4][2] = {{0, 0}, {4, 0}, {4, 2}, {0, 2}};
    return test_quad_321(vertices, mu_s, mu_k);
}

/* The 3-2-1 plate with its own friction: mu_s 0.3, mu_k 0.25. */
static inline wr_fixture *test_plate_321(void)
{
    return test_plate_321_friction(0.3, 0.25);
}

/* Does (q, c) of a witness satisfy the closure of the constraint's rows
 * (docs/MODEL.md section 2's table) and make the wrench g by Newton-Euler, within
 * `relative` of |g|?  NULL, or which row fails.  Written from docs/MODEL.md, not
 * from lib/; the acceleration tolerance scales with the longest lever arm
 * (far fixels cancel digits), and a NaN fails every comparison.  Used by
 * test_crosscheck and by the fuzz targets. */
static inline const char *test_witness_violation(const wr_fixture *f, const wr_constraint *c,
                                                 const wr_witness *w, const double g[3],
                                                 double relative)
{
    double scaled[3];
    double size = wr_fixture_scale_wrench(f, g, scaled);
    double tol = relative * (size > 0 ? size : 1);
    const double *q = w->acceleration;
    double made[3] = {f->mass * q[0], f->mass * q[1], f->inertia * q[2]};
    for (int i = 0; i < f->fixel_count; i++) {
        const wr_fixel *x = &f->fixels[i];
        double r[2] = {x->at[0] - f->com[0], x->at[1] - f->com[1]};
        double force[2] = {x->normal[0] * w->force[i][0] + x->tangent[0] * w->force[i][1],
                           x->normal[1] * w->force[i][0] + x->tangent[1] * w->force[i][1]};
        made[0] -= force[0];
        made[1] -= force[1];
        made[2] -= r[0] * force[1] - r[1] * force[0];
    }
    double made_scaled[3];
    wr_fixture_scale_wrench(f, made, made_scaled);
    for (int k = 0; k < 3; k++)
        if (!(fabs(made_scaled[k] - scaled[k]) <= tol))
            return "Newton-Euler: (q, c) does not make g";
    /* Contact accelerations a_c + alpha z x r: relative to |q|, to |g| / m
     * (q may be 0), and to |alpha| |r| (far fixels cancel digits). */
    double lever = f->gyration_radius;
    for (int i = 0; i < f->fixel_count; i++)
        lever = fmax(lever, hypot(f->fixels[i].at[0] - f->com[0], f->fixels[i].at[1] - f->com[1]));
    double qsize = fabs(q[0]) + fabs(q[1]) + fabs(q[2]) * lever;
    double atol = relative * (qsize + size / f->mass);
    for (int i = 0; i < f->fixel_count; i++) {
        const wr_fixel *x = &f->fixels[i];
        double r[2] = {x->at[0] - f->com[0], x->at[1] - f->com[1]};
        double a[2] = {q[0] - q[2] * r[1], q[1] + q[2] * r[0]};
        double an = a[0] * x->normal[0] + a[1] * x->normal[1];
        double at = a[0] * x->tangent[0] + a[1] * x->tangent[1];
        double cn = w->force[i][0], ct = w->force[i][1];
        double ftol = relative * (fabs(cn) + fabs(ct) + size);
        switch (c->letters[i]) {
        case 's':
            if (an < -atol || fabs(cn) > ftol || fabs(ct) > ftol)
                return "s: a_n < 0 or a force";
            break;
        case 'u':
            if (fabs(cn) > ftol || fabs(ct) > ftol)
                return "u: a force";
            break;
        case 'l':
        case 'r':
            if (fabs(an) > atol || cn < -ftol)
                return "l/r: a_n != 0 or c_n < 0";
            if (c->letters[i] == 'l' ? at < -atol : at > atol)
                return "l/r: a_t of the wrong sign";
            /* With a kinetic interval, the coefficient the witness names,
             * which must lie in it (docs/PROTOCOL.md, friction intervals). */
            double mu = x->mu_kinetic;
            if (x->mu_kinetic_min < x->mu_kinetic) {
                mu = w->friction[i];
                if (!(mu >= x->mu_kinetic_min && mu <= x->mu_kinetic))
                    return "l/r: the witness's kinetic friction is outside the interval";
            }
            if (fabs(ct - (c->letters[i] == 'l' ? -1 : 1) * mu * cn) > ftol)
                return "l/r: c_t off the friction-cone edge";
            break;
        case 'n':
        case 'm':
            if (fabs(an) > atol || cn < -ftol || fabs(ct) > x->mu_static * cn + ftol)
                return "n/m: a_n != 0, c_n < 0 or outside the friction cone";
            if (c->letters[i] == 'n' && fabs(at) > atol)
                return "n: a_t != 0";
            break;
        default:
            return "unknown letter";
        }
    }
    if (c->pivot && c->pivot * q[2] < -atol)
        return "pivot: alpha of the wrong sign";
    return NULL;
}

#endif
