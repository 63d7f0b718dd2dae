/* test_spec.c -- independent checks of libwrench against docs/MODEL.md and the
 * paper (Balkcom & Trinkle, "A Sensorless Insertion Strategy for Rigid Planar
 * Parts").
 *
 * Every expected number below is derived by hand from docs/MODEL.md (closed forms,
 * plane geometry), never copied from the library's output.  The derivations
 * are summarised in the comment of each test.
 *
 * Common facts about the docs/MODEL.md section 7 disc in a corner (radius 1, centre and
 * com at the origin, m = 1, I = 0.5, so rho = sqrt(I/m) = 1/sqrt(2)):
 *   fixel 1: p = (-1, 0), n = (1, 0), t = (-n_y, n_x) = (0, 1)
 *   fixel 2: p = (0, -1), n = (0, 1), t = (-1, 0)
 *   W_1n = (1, 0, 0), W_1t = (0, 1, -1), W_2n = (0, 1, 0), W_2t = (-1, 0, -1)
 * (r x n = 0 for a disc, r x t = -R = -1).  From g = M q - sum W c:
 *   G_su = {f_x >= 0}, G_us = {f_y >= 0},
 *   G_sm = {f_y <= 0, f_x >= mu f_y}, G_ms = {f_x <= 0, f_y >= mu f_x},
 * each a cylinder along tau (alpha is free), whose union's complement is
 *   G_goal = {f_x < 0, f_y < 0, |f_x| > mu |f_y|, |f_y| > mu |f_x|}.
 * In the force plane, G_goal is the open wedge of directions
 *   theta in (180 deg + atan(mu), 270 deg - atan(mu)),
 * empty for mu >= 1. */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "test_util.h"
#include "wrench.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

#define DEG (M_PI / 180.0)

/* ---- ownership: everything a test allocates is released in the teardown,
 * so a failing assertion (which longjmps out) does not leak under ASan. ---- */

#define MAX_OWNED 64
static struct {
    wr_fixture *fixtures[MAX_OWNED];
    int fixture_count;
    wr_analysis *analyses[MAX_OWNED];
    int analysis_count;
    wr_plan *plans[MAX_OWNED];
    int plan_count;
    wr_cone *cones[MAX_OWNED];
    int cone_count;
    void *blocks[MAX_OWNED];
    int block_count;
} owned;

static wr_fixture *own_fixture(wr_fixture *f)
{
    assert_non_null(f);
    assert_true(owned.fixture_count < MAX_OWNED);
    owned.fixtures[owned.fixture_count++] = f;
    return f;
}

static wr_analysis *own_analysis(wr_analysis *a)
{
    assert_non_null(a);
    assert_true(owned.analysis_count < MAX_OWNED);
    owned.analyses[owned.analysis_count++] = a;
    return a;
}

static wr_plan *own_plan(wr_plan *p)
{
    assert_non_null(p);
    assert_true(owned.plan_count < MAX_OWNED);
    owned.plans[owned.plan_count++] = p;
    return p;
}

/* Build the cone of `text` on `fixture`; the cone is released in teardown. */
static wr_cone *own_cone(const wr_fixture *fixture, const char *text)
{
    wr_constraint c;
    wr_error err;
    memset(&err, 0, sizeof err);
    assert_int_equal(wr_constraint_parse(text, fixture->fixel_count, &c, &err), WR_OK);
    wr_cone *cone = calloc(1, sizeof *cone);
    assert_non_null(cone);
    assert_true(owned.cone_count < MAX_OWNED);
    owned.cones[owned.cone_count++] = cone;
    assert_int_equal(wr_cone_build(cone, fixture, &c), WR_OK);
    return cone;
}

static void own_block(void *p)
{
    assert_true(owned.block_count < MAX_OWNED);
    owned.blocks[owned.block_count++] = p;
}

static int release_owned(void **state)
{
    (void)state;
    /* analyses borrow fixtures: free them first */
    for (int i = 0; i < owned.analysis_count; i++)
        wr_analysis_free(owned.analyses[i]);
    for (int i = 0; i < owned.fixture_count; i++)
        wr_fixture_free(owned.fixtures[i]);
    for (int i = 0; i < owned.plan_count; i++)
        wr_plan_free(owned.plans[i]);
    for (int i = 0; i < owned.cone_count; i++) {
        wr_cone_release(owned.cones[i]);
        free(owned.cones[i]);
    }
    for (int i = 0; i < owned.block_count; i++)
        free(owned.blocks[i]);
    memset(&owned, 0, sizeof owned);
    return 0;
}

/* ---- fixture builders ---------------------------------------------------- */

static void set_friction(wr_friction_spec *f, double mu_s, double mu_k)
{
    f->given = true;
    f->static_mu = mu_s;
    f->kinetic_given = true;
    f->kinetic_mu = mu_k;
}

/* A disc spec with explicit mass/inertia/com; fixels supplied by caller. */
static void disc_spec(wr_fixture_spec *s, double radius, double mass, double inertia,
                      const wr_fixel_spec *fixels, size_t count, double mu_s, double mu_k)
{
    memset(s, 0, sizeof *s);
    s->mass = mass;
    s->inertia_given = inertia > 0;
    s->inertia = inertia;
    s->com_given = true;
    s->com[0] = 0.0;
    s->com[1] = 0.0;
    s->shape = WR_SHAPE_CIRCLE;
    s->center[0] = 0.0;
    s->center[1] = 0.0;
    s->radius = radius;
    set_friction(&s->friction, mu_s, mu_k);
    s->fixel_count = count;
    s->fixels = fixels;
}

static wr_fixel_spec fixel_at(double x, double y, double nx, double ny)
{
    wr_fixel_spec f;
    memset(&f, 0, sizeof f);
    f.at[0] = x;
    f.at[1] = y;
    f.normal_given = true;
    f.normal[0] = nx;
    f.normal[1] = ny;
    return f;
}

/* A fixel on the unit circle at boundary angle theta (degrees), inward normal. */
static wr_fixel_spec fixel_on_unit_circle(double theta_deg)
{
    double c = cos(theta_deg * DEG), s = sin(theta_deg * DEG);
    return fixel_at(c, s, -c, -s);
}

/* docs/MODEL.md section 7: the disc in a corner, mu_s = mu_k = mu. */
static wr_fixture *disc_corner(double mu_s, double mu_k)
{
    wr_fixel_spec fx[2] = {fixel_at(-1, 0, 1, 0), fixel_at(0, -1, 0, 1)};
    wr_fixture_spec s;
    disc_spec(&s, 1.0, 1.0, 0.5, fx, 2, mu_s, mu_k);
    wr_error err;
    memset(&err, 0, sizeof err);
    wr_fixture *f = test_fixture_new(&s, &err);
    if (f == NULL)
        fail_msg("disc corner rejected: %s: %s", err.field, err.reason);
    return own_fixture(f);
}

/* ---- small helpers ------------------------------------------------------- */

static bool in_list(const char *text, const char *const *list, int n)
{
    for (int i = 0; i < n; i++)
        if (strcmp(text, list[i]) == 0)
            return true;
    return false;
}

static const char *verdict_name(wr_verdict v)
{
    switch (v) {
    case WR_VERDICT_INSIDE: return "inside";
    case WR_VERDICT_BOUNDARY: return "boundary";
    case WR_VERDICT_OUTSIDE: return "outside";
    }
    return "?";
}

/* The constraint strings of `list` (count n) are exactly `expected` (count m),
 * as sets, with no repetition. */
static void expect_string_set(const wr_constraint *list, int n, const char *const *expected,
                              int m, const char *what)
{
    if (n != m)
        fail_msg("%s: %d strings, expected %d", what, n, m);
    for (int i = 0; i < n; i++) {
        char text[WR_CONSTRAINT_TEXT];
        wr_constraint_format(&list[i], text);
        if (!in_list(text, expected, m))
            fail_msg("%s: unexpected string \"%s\"", what, text);
        for (int j = 0; j < i; j++) {
            char other[WR_CONSTRAINT_TEXT];
            wr_constraint_format(&list[j], other);
            if (strcmp(text, other) == 0)
                fail_msg("%s: \"%s\" listed twice", what, text);
        }
    }
}

/* ========================================================================= */
/* 1. G_goal of the docs/MODEL.md section 7 disc in a corner.
 *
 * Test points g = (r cos theta, r sin theta, tau) are placed on both sides of
 * each bounding line of G_goal (see the file comment): with a = atan(mu),
 *   inside  at theta = 180+a+d, 225, 270-a-d   (only when mu < 1),
 *   outside at theta = 180+a-d (crosses |f_y| = mu|f_x|),
 *           at theta = 270-a+d (crosses |f_x| = mu|f_y|),
 *           at theta = 270 +- d, 180 +- d (both sides of f_x = 0, f_y = 0:
 *           the G_goal side there still fails the friction inequality,
 *           since d < a for every mu tested), and in the other quadrants.
 * d = 3 deg.  Every cone is a cylinder along tau, so a torque never changes
 * membership; with tau = 1000 the scaled wrench has length ~1414 and the
 * margin is ~ sin(3 deg)/1414 ~ 4e-5, far above the 1e-9 tolerance.
 *
 * Margin of (-1, -1, 0): normalised x = (-1, -1, 0)/sqrt(2).  For mu < 1 x is
 * outside every cone; the nearest is G_sm (or G_ms, by symmetry), whose
 * nearest face is the plane f_x - mu f_y = 0 (x's angle 225 deg is within
 * 90 deg of the wedge's edge ray (-mu, -1)), at distance
 *   |(-1) - mu (-1)| / sqrt(1 + mu^2) / sqrt(2) = (1 - mu)/sqrt(2(1 + mu^2)),
 * smaller than the 1/sqrt(2) to G_su = {f_x >= 0}.  For mu > 1, x lies inside
 * G_sm = wedge [180 + atan(1/mu), 360] deg; its depth (distance to the
 * complement) is the distance to the same plane, (mu - 1)/sqrt(2(1 + mu^2)),
 * so the same formula gives the (negative) margin.  With a torque tau the
 * scaled wrench is (-1, -1, tau/rho), |.| = sqrt(2 + 2 tau^2), and the margin
 * is (1 - mu)/sqrt(2(1 + mu^2)(1 + tau^2)): this checks the rho scaling. */
static void test_disc_corner_goal_membership_and_margin(void **state)
{
    (void)state;
    const double mus[] = {0.2, 0.5, 0.8, 1.2};
    const double taus[] = {0.0, 1.0, -1.0, 1000.0, -1000.0};
    const double radii[] = {1.0, 3.7};
    const double d = 3.0;
    for (size_t im = 0; im < sizeof mus / sizeof mus[0]; im++) {
        double mu = mus[im];
        wr_fixture *fx = disc_corner(mu, mu);
        wr_analysis *an = own_analysis(test_analysis_new(fx));
        assert_int_equal(wr_analysis_cone_count(an, WR_SET_GOAL), 4);
        double a = atan(mu) / DEG;
        struct { double theta; bool inside; } pts[] = {
            {180 + a + d, mu < 1}, {225, mu < 1}, {270 - a - d, mu < 1},
            {180 + a - d, false}, {270 - a + d, false},
            {270 - d, false}, {270 + d, false},
            {180 - d, false}, {180 + d, false},
            {45, false}, {135, false}, {315, false}, {0, false}, {90, false},
        };
        for (size_t ip = 0; ip < sizeof pts / sizeof pts[0]; ip++)
            for (size_t it = 0; it < sizeof taus / sizeof taus[0]; it++)
                for (size_t ir = 0; ir < sizeof radii / sizeof radii[0]; ir++) {
                    double th = pts[ip].theta * DEG;
                    double g[3] = {radii[ir] * cos(th), radii[ir] * sin(th), taus[it]};
                    wr_answer ans;
                    memset(&ans, 0, sizeof ans);
                    assert_int_equal(wr_classify(an, g, WR_SET_GOAL, 1e-9, &ans), 0);
                    wr_verdict want = pts[ip].inside ? WR_VERDICT_INSIDE : WR_VERDICT_OUTSIDE;
                    if (ans.verdict != want)
                        fail_msg("mu=%g theta=%g tau=%g |f|=%g: %s (margin %.3e), expected %s",
                                 mu, pts[ip].theta, taus[it], radii[ir],
                                 verdict_name(ans.verdict), ans.margin, verdict_name(want));
                }

        /* the closed-form margin of (-1, -1, tau) */
        const double mtaus[] = {0.0, 1.0, -3.0};
        for (size_t it = 0; it < sizeof mtaus / sizeof mtaus[0]; it++) {
            double tau = mtaus[it];
            double g[3] = {-1.0, -1.0, tau};
            double want = (1.0 - mu) / sqrt(2.0 * (1.0 + mu * mu) * (1.0 + tau * tau));
            wr_answer ans;
            memset(&ans, 0, sizeof ans);
            assert_int_equal(wr_classify(an, g, WR_SET_GOAL, 1e-9, &ans), 0);
            assert_true(ans.has_margin);
            if (fabs(ans.margin - want) > 1e-9)
                fail_msg("mu=%g tau=%g: margin %.12f, expected (1-mu)/sqrt(2(1+mu^2)(1+tau^2)) = %.12f",
                         mu, tau, ans.margin, want);
            assert_int_equal(ans.verdict, mu < 1 ? WR_VERDICT_INSIDE : WR_VERDICT_OUTSIDE);
        }
    }
}

/* ========================================================================= */
/* 2. G_ss of the disc corner (docs/MODEL.md section 7, the seed's eq. 4).  With c = 0,
 * g = M q = (a_x, a_y, I alpha) with a_1n = a_x >= 0, a_2n = a_y >= 0 and
 * alpha free: G_ss = {f_x >= 0, f_y >= 0}, a 3-D cone whose only facets, as
 * rows of F g <= 0, are (-1, 0, 0) and (0, -1, 0); no equalities. */
static void test_disc_corner_G_ss_is_positive_quadrant(void **state)
{
    (void)state;
    wr_fixture *fx = disc_corner(0.5, 0.5);
    wr_cone *cone = own_cone(fx, "ss");
    assert_false(cone->empty);
    assert_int_equal(cone->dimension, 3);
    assert_int_equal(cone->equality_count, 0);
    assert_int_equal(cone->facet_count, 2);
    const double want[2][3] = {{-1, 0, 0}, {0, -1, 0}};
    bool seen[2] = {false, false};
    for (int i = 0; i < cone->facet_count; i++) {
        double row[3];
        wr_fixture_unscale_row(fx, cone->facets[i], row);
        int match = -1;
        for (int j = 0; j < 2; j++)
            if (fabs(row[0] - want[j][0]) < 1e-9 && fabs(row[1] - want[j][1]) < 1e-9 &&
                fabs(row[2] - want[j][2]) < 1e-9)
                match = j;
        if (match < 0)
            fail_msg("unexpected facet row (%g, %g, %g)", row[0], row[1], row[2]);
        assert_false(seen[match]);
        seen[match] = true;
    }
    assert_true(seen[0] && seen[1]);
}

/* ========================================================================= */
/* 3. Kept strings of docs/MODEL.md section 3.
 *
 * k = 2: state 00 excludes ss; 10: su, ms; 01: us, sm; 11: ss, sm, ms.  ss is
 * below su, so the kept set is {su, us, sm, ms} (seed eq. 6).
 * k = 3 (seed section 4 table, with 111's row = every {s,m} string but mmm):
 *   000 sss; 100 suu mss; 010 usu sms; 001 uus ssm;
 *   110 ssu smu msu mms; 101 sus sum mus msm; 011 uss usm ums smm;
 *   111 sss ssm sms smm mss msm mms.
 * X is below Y iff each letter is equal or s -> u.  Dropped: sss (< suu),
 * mss (< msu), sms (< smu), ssm (< sum), ssu (< suu), sus (< suu), uss (< usu).
 * Kept: suu usu uus smu msu mms sum mus msm usm ums smm (twelve).
 *
 * General k: a backward string from S with s on A (nonempty, within S) lies
 * below the backward string from S \ (A \ {i}) with s only at i (s -> u);
 * a self string from S != all lies below the backward string from S + {j}
 * with s at j (j not in S).  So every maximal string has exactly one s and
 * m/u elsewhere; conversely each such string (s at i, m on B, u elsewhere) is
 * the backward string of state B + {i}, and none is below another (that
 * would need an s -> u, leaving a string with no s, which is never excluded).
 * Hence kept = all strings with exactly one s, m/u elsewhere: k 2^(k-1).
 * Origins ("states whose excluded list holds it"): s at i, m on B, u on the
 * rest comes from state B + {i} (backward); when there is no u it also comes
 * from the state "all but i" (its self transition): 2 origins, else 1. */
static const char *plan_string(const wr_plan *plan, int index, char text[WR_CONSTRAINT_TEXT])
{
    wr_constraint_format(&plan->kept[index], text);
    return text;
}

static int kept_index(const wr_plan *plan, const char *text)
{
    for (int i = 0; i < plan->kept_count; i++) {
        char t[WR_CONSTRAINT_TEXT];
        if (strcmp(plan_string(plan, i, t), text) == 0)
            return i;
    }
    return -1;
}

static void expect_origins(const wr_plan *plan, const char *text, const char *const *states, int n)
{
    int idx = kept_index(plan, text);
    if (idx < 0)
        fail_msg("\"%s\" not kept", text);
    const wr_plan_origins *o = &plan->origins[idx];
    if (o->count != n)
        fail_msg("\"%s\": %d origins, expected %d", text, o->count, n);
    for (int i = 0; i < o->count; i++) {
        char st[WR_STATE_TEXT];
        wr_state_format(o->states[i], plan->fixel_count, st);
        if (!in_list(st, states, n))
            fail_msg("\"%s\": unexpected origin state %s", text, st);
        for (int j = 0; j < i; j++)
            assert_true(o->states[j] != o->states[i]);
    }
}

static void test_plan_kept_strings_two_fixels(void **state)
{
    (void)state;
    wr_plan *plan = own_plan(test_plan_new(2));
    assert_int_equal(plan->fixel_count, 2);
    assert_int_equal(plan->state_count, 4);
    const char *const want[] = {"su", "us", "sm", "ms"};
    expect_string_set(plan->kept, plan->kept_count, want, 4, "k=2 kept");
    /* sm: from 01 (nothing changes) and from 11 (fixel 1 breaks) */
    const char *const sm_states[] = {"01", "11"};
    expect_origins(plan, "sm", sm_states, 2);
    const char *const ms_states[] = {"10", "11"};
    expect_origins(plan, "ms", ms_states, 2);
    const char *const su_states[] = {"10"};
    expect_origins(plan, "su", su_states, 1);
    const char *const us_states[] = {"01"};
    expect_origins(plan, "us", us_states, 1);
}

static void test_plan_kept_strings_three_fixels(void **state)
{
    (void)state;
    wr_plan *plan = own_plan(test_plan_new(3));
    assert_int_equal(plan->state_count, 8);
    const char *const want[] = {"suu", "usu", "uus", "smu", "msu", "mms",
                                "sum", "mus", "msm", "usm", "ums", "smm"};
    expect_string_set(plan->kept, plan->kept_count, want, 12, "k=3 kept");

    /* state 010 excludes exactly usu (fixel 2 breaks) and sms (self) */
    int found = -1;
    for (int i = 0; i < plan->state_count; i++) {
        char st[WR_STATE_TEXT];
        wr_state_format(plan->states[i].state, 3, st);
        if (strcmp(st, "010") == 0) {
            assert_int_equal(found, -1);
            found = i;
        }
    }
    assert_true(found >= 0);
    assert_int_equal(plan->states[found].state, 2u); /* bit 1 = fixel 2 */
    const wr_plan_state *ps = &plan->states[found];
    assert_true(ps->excluded_first >= 0);
    assert_true(ps->excluded_first + ps->excluded_count <= plan->excluded_total);
    const char *const ex[] = {"usu", "sms"};
    expect_string_set(plan->excluded + ps->excluded_first, ps->excluded_count, ex, 2,
                      "state 010 excluded");

    const char *const smm_states[] = {"011", "111"};
    expect_origins(plan, "smm", smm_states, 2);
    const char *const msu_states[] = {"110"};
    expect_origins(plan, "msu", msu_states, 1);
}

static void test_plan_kept_count_and_shape_k1_to_8(void **state)
{
    (void)state;
    for (int k = 1; k <= WR_MAX_FIXELS; k++) {
        wr_plan *plan = own_plan(test_plan_new(k));
        int want = k * (1 << (k - 1));
        if (plan->kept_count != want)
            fail_msg("k=%d: %d kept strings, expected k*2^(k-1) = %d", k, plan->kept_count, want);
        assert_int_equal(plan->state_count, 1 << k);
        for (int i = 0; i < plan->kept_count; i++) {
            char t[WR_CONSTRAINT_TEXT];
            plan_string(plan, i, t);
            assert_int_equal((int)strlen(t), k);
            int s_count = 0, s_at = -1;
            bool has_u = false;
            unsigned non_u = 0;
            for (int j = 0; j < k; j++) {
                if (t[j] == 's') {
                    s_count++;
                    s_at = j;
                } else if (t[j] != 'm' && t[j] != 'u') {
                    fail_msg("k=%d: kept \"%s\" has letter '%c'", k, t, t[j]);
                }
                if (t[j] == 'u')
                    has_u = true;
                else
                    non_u |= 1u << j;
            }
            if (s_count != 1)
                fail_msg("k=%d: kept \"%s\" has %d s", k, t, s_count);
            /* distinct: together with the count, the set is all such strings */
            for (int j = 0; j < i; j++) {
                char o[WR_CONSTRAINT_TEXT];
                if (strcmp(plan_string(plan, j, o), t) == 0)
                    fail_msg("k=%d: \"%s\" kept twice", k, t);
            }
            /* origins: state (non-u positions), plus "all but s" when no u */
            const wr_plan_origins *o = &plan->origins[i];
            unsigned all = (1u << k) - 1;
            if (o->count != (has_u ? 1 : 2))
                fail_msg("k=%d: \"%s\" has %d origins, expected %d", k, t, o->count,
                         has_u ? 1 : 2);
            for (int j = 0; j < o->count; j++) {
                wr_state st = o->states[j];
                bool ok = st == non_u || (!has_u && st == (all & ~(1u << s_at)));
                if (!ok) {
                    char txt[WR_STATE_TEXT];
                    wr_state_format(st, k, txt);
                    fail_msg("k=%d: \"%s\" has unexpected origin %s", k, t, txt);
                }
            }
        }
    }
}

/* wr_state_format: '1' at position i means fixel i+1 touched (bit i). */
static void test_state_format_bit_order(void **state)
{
    (void)state;
    char t[WR_STATE_TEXT];
    wr_state_format(1u, 3, t);
    assert_string_equal(t, "100");
    wr_state_format(2u, 3, t);
    assert_string_equal(t, "010");
    wr_state_format(6u, 3, t);
    assert_string_equal(t, "011");
    wr_state_format(0u, 2, t);
    assert_string_equal(t, "00");
}

/* ========================================================================= */
/* 4. The seed's figure 8: a disc (centre c, radius R) against two fixels with
 * independent normals.  For a point of a circle with inward normal n,
 * r = -R n, so a_n = n . a (no torque arm) and a_t = t . a - R alpha.
 *   s (strict): n . a > 0.  Two fixels both in contact force a = 0 (n1, n2
 *   independent), hence a_t1 = a_t2 = -R alpha: ll (alpha < 0), rr
 *   (alpha > 0), nn (q = 0, so pinned); mixed lr, ln, ... are infeasible.
 *   One contact (say fixel 2): a = lambda t2 with lambda fixed in sign by
 *   n1 . a > 0 (n1 . t2 != 0), alpha free: sl, sr, sn all feasible; same for
 *   ls, rs, ns.  ss: any a with both n . a > 0.
 * Feasible moving modes: ss sl sr sn ls rs ns ll rr; pinned; no pivots.
 * A single fixel: s, l, r feasible, and n allows q = (lambda t, lambda / R)
 * != 0: not pinned, so the pivots n+ and n- are listed. */
static void expect_modes(const wr_fixture *fx, const char *const *want, int n, bool pinned_want,
                         const char *what)
{
    wr_constraint *modes = NULL;
    bool pinned = !pinned_want;
    int count;
    assert_int_equal(wr_modes_find(fx, &modes, &count, &pinned), WR_OK);
    own_block(modes);
    expect_string_set(modes, count, want, n, what);
    if (pinned != pinned_want)
        fail_msg("%s: pinned = %d, expected %d", what, pinned, pinned_want);
    for (int i = 0; i < count; i++) {
        if (pinned_want)
            assert_int_equal(modes[i].pivot, 0);
        if (strchr(modes[i].letters, 's') != NULL)
            assert_true(modes[i].strict_separation); /* s of a mode: a_n > 0 */
    }
}

static void test_figure8_disc_two_fixels_modes(void **state)
{
    (void)state;
    const char *const want[] = {"ss", "sl", "sr", "sn", "ls", "rs", "ns", "ll", "rr"};
    /* pairs of boundary angles: 90 and 120 degrees apart, and a skewed pair */
    const double placements[][2] = {{180, 270}, {180, 300}, {200, 290}, {10, 140}};
    for (size_t i = 0; i < sizeof placements / sizeof placements[0]; i++) {
        wr_fixel_spec fxs[2] = {fixel_on_unit_circle(placements[i][0]),
                                fixel_on_unit_circle(placements[i][1])};
        wr_fixture_spec s;
        disc_spec(&s, 1.0, 1.0, 0.5, fxs, 2, 1.5, 1.0);
        wr_error err;
        memset(&err, 0, sizeof err);
        wr_fixture *fx = test_fixture_new(&s, &err);
        if (fx == NULL)
            fail_msg("placement %zu rejected: %s: %s", i, err.field, err.reason);
        own_fixture(fx);
        char what[64];
        snprintf(what, sizeof what, "fixels at %g and %g deg", placements[i][0], placements[i][1]);
        expect_modes(fx, want, 9, true, what);
        /* the analysis agrees: nine strong cones, pinned */
        wr_analysis *an = own_analysis(test_analysis_new(fx));
        assert_true(wr_analysis_pinned(an));
        assert_int_equal(wr_analysis_cone_count(an, WR_SET_STRONG), 9);
        assert_int_equal(wr_analysis_cone_count(an, WR_SET_STRONG), 9);
    }
}

static void test_single_fixel_disc_not_pinned_has_pivots(void **state)
{
    (void)state;
    wr_fixel_spec fxs[1] = {fixel_at(-1, 0, 1, 0)};
    wr_fixture_spec s;
    disc_spec(&s, 1.0, 1.0, 0.5, fxs, 1, 0.5, 0.5);
    wr_fixture *fx = own_fixture(test_fixture_new(&s, NULL));
    const char *const want[] = {"s", "l", "r", "n+", "n-"};
    expect_modes(fx, want, 5, false, "single fixel");
    wr_constraint *modes = NULL;
    bool pinned = true;
    int count;
    assert_int_equal(wr_modes_find(fx, &modes, &count, &pinned), WR_OK);
    own_block(modes);
    int plus = 0, minus = 0;
    for (int i = 0; i < count; i++) {
        if (modes[i].pivot == 1) {
            plus++;
            assert_string_equal(modes[i].letters, "n");
        } else if (modes[i].pivot == -1) {
            minus++;
            assert_string_equal(modes[i].letters, "n");
        }
    }
    assert_int_equal(plus, 1);
    assert_int_equal(minus, 1);
}

/* A square in first-order form closure (an addition to the brief's list):
 * [-1, 1]^2, com at the centroid (0, 0), fixels bottom (0.5, -1) n (0, 1),
 * top (0, 1) n (0, -1), left (-1, 0.5) n (1, 0), right (1, 0) n (-1, 0).
 * Normal wrenches (n, r x n): (0, 1, 0.5), (0, -1, 0), (1, 0, -0.5),
 * (-1, 0, 0); they sum to 0 and the first three are independent (det 0.5),
 * so they positively span R^3: every q with all a_n >= 0 has all a_n = 0 and
 * then q = 0.  No moving mode is feasible (not even with friction 0), the body
 * is pinned, G_strong excludes nothing and, by docs/MODEL.md section 5 (with no
 * excluded cone at all the margin is 1), every nonzero wrench is inside
 * G_strong with margin 1. */
static void test_form_closure_square_has_no_moving_modes(void **state)
{
    (void)state;
    static const double sq[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
    wr_fixel_spec fx[4] = {fixel_at(0.5, -1, 0, 1), fixel_at(0, 1, 0, -1),
                           fixel_at(-1, 0.5, 1, 0), fixel_at(1, 0, -1, 0)};
    wr_fixture_spec s;
    memset(&s, 0, sizeof s);
    s.mass = 1.0;
    s.shape = WR_SHAPE_POLYGON;
    s.vertices = sq;
    s.vertex_count = 4;
    set_friction(&s.friction, 0.3, 0.3);
    s.fixels = fx;
    s.fixel_count = 4;
    wr_fixture *f = own_fixture(test_fixture_new(&s, NULL));
    assert_true(fabs(f->inertia - 8.0 / 12.0) < 1e-12); /* m (w^2 + h^2)/12 */

    wr_constraint *modes = NULL;
    bool pinned = false;
    int count;
    assert_int_equal(wr_modes_find(f, &modes, &count, &pinned), WR_OK);
    own_block(modes);
    assert_int_equal(count, 0);
    assert_true(pinned);

    wr_analysis *an = own_analysis(test_analysis_new(f));
    assert_int_equal(wr_analysis_cone_count(an, WR_SET_STRONG), 0);
    const double gs[][3] = {{1, 2, 3}, {-1, 0, 0}, {0, 0, -5}, {0.3, -0.7, 0.1}};
    for (size_t i = 0; i < sizeof gs / sizeof gs[0]; i++) {
        wr_answer ans;
        memset(&ans, 0, sizeof ans);
        assert_int_equal(wr_classify(an, gs[i], WR_SET_STRONG, 1e-9, &ans), 0);
        assert_int_equal(ans.verdict, WR_VERDICT_INSIDE);
        assert_true(fabs(ans.margin - 1.0) < 1e-12);
        assert_int_equal(ans.blocking, -1);
    }
}

/* ========================================================================= */
/* 5. Force closure (seed section 5, Nguyen).  Disc corner, mu_s = 1.5: the
 * segment between the fixels, direction (1, -1)/sqrt(2), makes 45 deg with
 * n1 = (1, 0) and with n2 = (0, 1), less than atan(1.5) = 56.3 deg: it lies
 * inside both friction cones, so the two contacts are in force closure.
 * Directly: Q_nn = {0} (pinned), G_nn = -W C_nn, C_nn spanned by the edge
 * wrenches A = (1, 1.5, -1.5), B = (1, -1.5, 1.5) (fixel 1, n +- 1.5 t) and
 * C = (-1.5, 1, -1.5), D = (1.5, 1, 1.5) (fixel 2); 0.5 A + 2.5 B + 2.5 C +
 * 0.5 D = 0 with all weights positive, and A+B, C+D, A-B span R^3, so they
 * positively span R^3: G_nn is the whole wrench space (dimension 3, no
 * facets, no equalities).  With mu_s = 0.8 (atan 0.8 = 38.7 deg < 45 deg)
 * there is no force closure and G_nn has at least one facet. */
static void test_force_closure_G_nn_whole_space(void **state)
{
    (void)state;
    wr_fixture *fx = disc_corner(1.5, 1.5);
    wr_cone *cone = own_cone(fx, "nn");
    assert_false(cone->empty);
    assert_int_equal(cone->dimension, 3);
    assert_int_equal(cone->facet_count, 0);
    assert_int_equal(cone->equality_count, 0);

    wr_fixture *fx2 = disc_corner(0.8, 0.8);
    wr_cone *cone2 = own_cone(fx2, "nn");
    assert_false(cone2->empty);
    assert_true(cone2->facet_count > 0);
}

/* ========================================================================= */
/* 6. docs/MODEL.md section 4's counterexample to "G_goal subset of G_strong".  Disc
 * corner, mu = 0.5, g = (-1, -1, -100).  Force direction 225 deg lies in
 * G_goal's wedge (206.6, 243.4) deg: inside.  Mode ll: a = 0, alpha < 0,
 * c_t = -mu c_n, so g = (-c1 - mu c2, mu c1 - c2, I alpha - mu (c1 + c2));
 * solving gives c1 = 0.4, c2 = 1.2 (both > 0) and 0.5 alpha - 0.8 = -100,
 * alpha = -198.4 < 0: g is strictly inside G_ll.  No other feasible mode
 * admits g (s at a fixel needs f_x > ... e.g. sl: a_x = f_x + mu c2 = -0.5 <
 * 0; sn: a_x = -1 - c2t > 0 needs |c2t| > 1 > mu c2 = 0.5; rr needs tau > 0),
 * so the strong verdict is outside and the blocking mode is ll.  For both,
 * the margin is the smaller one: outside. */
static void test_goal_not_subset_of_strong_counterexample(void **state)
{
    (void)state;
    wr_fixture *fx = disc_corner(0.5, 0.5);
    wr_analysis *an = own_analysis(test_analysis_new(fx));
    const double g[3] = {-1.0, -1.0, -100.0};
    wr_answer goal, strong, both;
    memset(&goal, 0, sizeof goal);
    memset(&strong, 0, sizeof strong);
    memset(&both, 0, sizeof both);

    assert_int_equal(wr_classify(an, g, WR_SET_GOAL, 1e-9, &goal), 0);
    assert_int_equal(goal.verdict, WR_VERDICT_INSIDE);
    assert_true(goal.margin > 0);
    assert_int_equal(goal.blocking, -1);

    assert_int_equal(wr_classify(an, g, WR_SET_STRONG, 1e-9, &strong), 0);
    assert_int_equal(strong.verdict, WR_VERDICT_OUTSIDE);
    assert_true(strong.margin < 0);
    assert_int_equal(strong.blocking_set, WR_SET_STRONG);
    assert_true(strong.blocking >= 0 &&
                strong.blocking < wr_analysis_cone_count(an, WR_SET_STRONG));
    char text[WR_CONSTRAINT_TEXT];
    wr_constraint_format(&wr_analysis_constraints(an, WR_SET_STRONG)[strong.blocking], text);
    assert_string_equal(text, "ll");

    assert_int_equal(wr_classify(an, g, WR_SET_BOTH, 1e-9, &both), 0);
    assert_int_equal(both.verdict, WR_VERDICT_OUTSIDE);
    assert_true(fabs(both.margin - fmin(goal.margin, strong.margin)) < 1e-12);
}

/* ========================================================================= */
/* 7. The zero wrench (docs/MODEL.md section 5): margin 0; it seats nothing (goal:
 * outside).  For the disc corner no moving mode admits g = 0: every feasible
 * mode has a strict row (a_n > 0, a_t > 0 or < 0), and with g = 0 each forces
 * q = 0 (e.g. ll: -c1 - mu c2 = 0 and mu c1 - c2 = 0 give c = 0, then
 * alpha = 0), so strong: inside, margin 0.  Both = goal and strong: outside. */
static void test_zero_wrench(void **state)
{
    (void)state;
    wr_fixture *fx = disc_corner(0.5, 0.5);
    wr_analysis *an = own_analysis(test_analysis_new(fx));
    const double g[3] = {0.0, 0.0, 0.0};
    wr_answer ans;

    memset(&ans, 0, sizeof ans);
    assert_int_equal(wr_classify(an, g, WR_SET_GOAL, 1e-9, &ans), 0);
    assert_int_equal(ans.verdict, WR_VERDICT_OUTSIDE);
    assert_true(ans.has_margin);
    assert_true(fabs(ans.margin) <= 1e-12);

    memset(&ans, 0, sizeof ans);
    assert_int_equal(wr_classify(an, g, WR_SET_STRONG, 1e-9, &ans), 0);
    assert_int_equal(ans.verdict, WR_VERDICT_INSIDE);
    assert_true(ans.has_margin);
    assert_true(fabs(ans.margin) <= 1e-12);

    memset(&ans, 0, sizeof ans);
    assert_int_equal(wr_classify(an, g, WR_SET_BOTH, 1e-9, &ans), 0);
    assert_int_equal(ans.verdict, WR_VERDICT_OUTSIDE);
}

/* ========================================================================= */
/* 8. Fixture validation (docs/PROTOCOL.md): each invalid spec is rejected with
 * the offending field's path (JSON of section 8) and a non-empty reason.
 * Each case starts from a valid disc-corner spec and breaks one thing. */
typedef struct valid_case {
    wr_fixture_spec spec;
    wr_fixel_spec fixels[WR_MAX_FIXELS + 1];
} valid_case;

static void base_case(valid_case *c)
{
    memset(c, 0, sizeof *c);
    c->fixels[0] = fixel_at(-1, 0, 1, 0);
    c->fixels[1] = fixel_at(0, -1, 0, 1);
    disc_spec(&c->spec, 1.0, 1.0, 0.5, c->fixels, 2, 0.5, 0.5);
}

/* Expect rejection; `exact` compares the whole field, else a prefix. */
static void expect_reject(const valid_case *c, const char *field, bool exact)
{
    wr_error err;
    memset(&err, 0, sizeof err);
    wr_fixture *f;
    wr_status status = wr_fixture_new(&c->spec, &f, &err);
    if (f != NULL) {
        wr_fixture_free(f);
        fail_msg("accepted; expected an error on %s", field);
    }
    assert_int_equal(status, WR_INVALID);
    if (exact ? strcmp(err.field, field) != 0 : strncmp(err.field, field, strlen(field)) != 0)
        fail_msg("field \"%s\" (reason \"%s\"), expected %s\"%s\"", err.field, err.reason,
                 exact ? "" : "a path starting with ", field);
    assert_true(strlen(err.reason) > 0);
    /* NULL error pointer is allowed */
    assert_int_equal(wr_fixture_new(&c->spec, &f, NULL), WR_INVALID);
    assert_null(f);
}

static void test_validation_base_case_is_valid(void **state)
{
    (void)state;
    valid_case c;
    base_case(&c);
    own_fixture(test_fixture_new(&c.spec, NULL));
}

static void test_validation_mass_not_finite(void **state)
{
    (void)state;
    valid_case c;
    base_case(&c);
    c.spec.mass = NAN;
    expect_reject(&c, "body.mass", true);
    c.spec.mass = INFINITY;
    expect_reject(&c, "body.mass", true);
}

static void test_validation_mass_not_positive(void **state)
{
    (void)state;
    valid_case c;
    base_case(&c);
    c.spec.mass = 0.0;
    expect_reject(&c, "body.mass", true);
    c.spec.mass = -2.0;
    expect_reject(&c, "body.mass", true);
}

static void test_validation_inertia_not_positive(void **state)
{
    (void)state;
    valid_case c;
    base_case(&c);
    c.spec.inertia_given = true;
    c.spec.inertia = 0.0;
    expect_reject(&c, "body.inertia", true);
    c.spec.inertia = -1.0;
    expect_reject(&c, "body.inertia", true);
}

static void test_validation_zero_normal(void **state)
{
    (void)state;
    valid_case c;
    base_case(&c);
    c.fixels[1].normal[0] = 0.0;
    c.fixels[1].normal[1] = 0.0;
    expect_reject(&c, "fixels[1].normal", true);
}

static void test_validation_negative_static_friction(void **state)
{
    (void)state;
    valid_case c;
    base_case(&c);
    c.spec.friction.static_mu = -0.1;
    c.spec.friction.kinetic_given = false;
    expect_reject(&c, "friction.static", true);
}

static void test_validation_kinetic_above_static(void **state)
{
    (void)state;
    valid_case c;
    base_case(&c);
    c.spec.friction.static_mu = 0.3;
    c.spec.friction.kinetic_mu = 0.4;
    expect_reject(&c, "friction.kinetic", true);
}

static void test_validation_fixel_off_boundary(void **state)
{
    (void)state;
    valid_case c;
    base_case(&c);
    c.fixels[0].at[0] = -1.1; /* 0.1 inside the disc's size of 2: far off */
    expect_reject(&c, "fixels[0].at", true);
}

/* A 2 x 2 square; fixels[1] sits on the vertex (2, 0) with no normal. */
static const double square[4][2] = {{0, 0}, {2, 0}, {2, 2}, {0, 2}};

static void test_validation_normal_missing_at_polygon_vertex(void **state)
{
    (void)state;
    valid_case c;
    base_case(&c);
    c.spec.shape = WR_SHAPE_POLYGON;
    c.spec.vertices = square;
    c.spec.vertex_count = 4;
    c.spec.com_given = false;
    c.spec.inertia_given = false;
    c.fixels[0] = fixel_at(0, 1, 1, 0);
    c.fixels[1] = fixel_at(2, 0, 0, 1);
    c.fixels[1].normal_given = false;
    expect_reject(&c, "fixels[1].normal", true);
    /* the same fixel with its normal given is fine */
    c.fixels[1].normal_given = true;
    own_fixture(test_fixture_new(&c.spec, NULL));
}

static void test_validation_bow_tie_polygon(void **state)
{
    (void)state;
    static const double bow_tie[4][2] = {{0, 0}, {2, 2}, {2, 0}, {0, 2}};
    valid_case c;
    base_case(&c);
    c.spec.shape = WR_SHAPE_POLYGON;
    c.spec.vertices = bow_tie;
    c.spec.vertex_count = 4;
    c.spec.com_given = true;
    c.spec.com[0] = 1.0;
    c.spec.com[1] = 1.0;
    c.spec.inertia_given = true;
    c.fixels[0] = fixel_at(0.5, 0.5, 1, -1);  /* on edge (0,0)-(2,2) */
    c.fixels[1] = fixel_at(2, 1, -1, 0);      /* on edge (2,2)-(2,0) */
    expect_reject(&c, "body.shape.vertices", false);
}

static void test_validation_zero_area_polygon(void **state)
{
    (void)state;
    static const double flat[3][2] = {{0, 0}, {1, 0}, {2, 0}};
    valid_case c;
    base_case(&c);
    c.spec.shape = WR_SHAPE_POLYGON;
    c.spec.vertices = flat;
    c.spec.vertex_count = 3;
    c.spec.com_given = true;
    c.spec.com[0] = 1.0;
    c.spec.com[1] = 0.0;
    c.spec.inertia_given = true;
    c.fixels[0] = fixel_at(0.5, 0, 0, 1);
    c.fixels[1] = fixel_at(1.5, 0, 0, 1);
    expect_reject(&c, "body.shape.vertices", false);
}

static void test_validation_duplicate_fixels(void **state)
{
    (void)state;
    valid_case c;
    base_case(&c);
    c.fixels[1] = c.fixels[0];
    expect_reject(&c, "fixels[1]", true);
}

static void test_validation_no_fixels(void **state)
{
    (void)state;
    valid_case c;
    base_case(&c);
    c.spec.fixel_count = 0;
    expect_reject(&c, "fixels", true);
}

/* Nine distinct, valid fixels on the disc: too many (at most 8, since G_goal
 * needs k 2^(k-1) cones: 2304 at k = 9); the reason mentions cones. */
static void test_validation_nine_fixels(void **state)
{
    (void)state;
    valid_case c;
    base_case(&c);
    for (int i = 0; i < 9; i++)
        c.fixels[i] = fixel_on_unit_circle(40.0 * i);
    c.spec.fixel_count = 9;
    wr_error err;
    memset(&err, 0, sizeof err);
    wr_fixture *f;
    assert_int_equal(wr_fixture_new(&c.spec, &f, &err), WR_INVALID);
    assert_null(f);
    assert_string_equal(err.field, "fixels");
    assert_true(strlen(err.reason) > 0);
    if (strstr(err.reason, "cone") == NULL)
        fail_msg("reason \"%s\" does not mention the cone count", err.reason);
    /* eight of them are fine */
    c.spec.fixel_count = 8;
    own_fixture(test_fixture_new(&c.spec, NULL));
}

static void test_validation_missing_friction(void **state)
{
    (void)state;
    valid_case c;
    base_case(&c);
    c.spec.friction.given = false;
    expect_reject(&c, "fixels[0].friction", false);
    /* friction on every fixel instead is fine */
    set_friction(&c.fixels[0].friction, 0.5, 0.5);
    set_friction(&c.fixels[1].friction, 0.3, 0.2);
    wr_fixture *f = own_fixture(test_fixture_new(&c.spec, NULL));
    assert_true(fabs(f->fixels[1].mu_static - 0.3) < 1e-15);
    assert_true(fabs(f->fixels[1].mu_kinetic - 0.2) < 1e-15);
}

/* ========================================================================= */
/* 9. Derived quantities (docs/PROTOCOL.md).  Rectangle [1, 5] x [2, 4]
 * (w = 4, h = 2), m = 3: centroid (3, 3); uniform inertia about it
 * m (w^2 + h^2)/12 = 3 * 20 / 12 = 5; inward normals: bottom (0, 1),
 * right (-1, 0), top (0, -1), left (1, 0), whichever the orientation; tangent
 * t = (-n_y, n_x).  Fixel on the bottom at (2, 2): r = (-1, -1), r x n =
 * (-1)(1) - (-1)(0) = -1, rho = sqrt(5/3), scaled normal wrench
 * (0, 1, -1/rho).  Com given at (4, 3), d = 1 from the centroid: I = 5 + 3 = 8.
 * Disc of radius 2, m = 3: I = m r^2 / 2 = 6 about the centre (default com);
 * com given at distance 0.5: I = 6 + 3 * 0.25 = 6.75. */
static wr_fixture *rectangle(const double (*v)[2], bool com_given, double cx, double cy)
{
    static wr_fixel_spec fx[4];
    fx[0] = fixel_at(2, 2, 0, 0);
    fx[1] = fixel_at(5, 3.5, 0, 0);
    fx[2] = fixel_at(4, 4, 0, 0);
    fx[3] = fixel_at(1, 2.5, 0, 0);
    for (int i = 0; i < 4; i++)
        fx[i].normal_given = false;
    wr_fixture_spec s;
    memset(&s, 0, sizeof s);
    s.mass = 3.0;
    s.com_given = com_given;
    s.com[0] = cx;
    s.com[1] = cy;
    s.shape = WR_SHAPE_POLYGON;
    s.vertices = v;
    s.vertex_count = 4;
    set_friction(&s.friction, 0.4, 0.4);
    s.fixels = fx;
    s.fixel_count = 4;
    wr_error err;
    memset(&err, 0, sizeof err);
    wr_fixture *f = test_fixture_new(&s, &err);
    if (f == NULL)
        fail_msg("rectangle rejected: %s: %s", err.field, err.reason);
    return own_fixture(f);
}

static void test_polygon_orientation_normals_centroid_inertia(void **state)
{
    (void)state;
    static const double ccw[4][2] = {{1, 2}, {5, 2}, {5, 4}, {1, 4}};
    static const double cw[4][2] = {{1, 2}, {1, 4}, {5, 4}, {5, 2}};
    const double normals[4][2] = {{0, 1}, {-1, 0}, {0, -1}, {1, 0}};
    wr_fixture *both[2] = {rectangle(ccw, false, 0, 0), rectangle(cw, false, 0, 0)};
    assert_int_equal(both[0]->orientation, 1);
    assert_int_equal(both[1]->orientation, -1);
    for (int k = 0; k < 2; k++) {
        const wr_fixture *f = both[k];
        assert_int_equal(f->fixel_count, 4);
        assert_true(fabs(f->com[0] - 3.0) < 1e-12);
        assert_true(fabs(f->com[1] - 3.0) < 1e-12);
        assert_true(fabs(f->mass - 3.0) < 1e-15);
        assert_true(fabs(f->inertia - 5.0) < 1e-12);
        assert_true(fabs(f->gyration_radius - sqrt(5.0 / 3.0)) < 1e-12);
        for (int i = 0; i < 4; i++) {
            const wr_fixel *x = &f->fixels[i];
            if (fabs(x->normal[0] - normals[i][0]) > 1e-12 ||
                fabs(x->normal[1] - normals[i][1]) > 1e-12)
                fail_msg("%s fixel %d: normal (%g, %g), expected (%g, %g)", k ? "cw" : "ccw",
                         i, x->normal[0], x->normal[1], normals[i][0], normals[i][1]);
            assert_true(fabs(x->tangent[0] + normals[i][1]) < 1e-12);
            assert_true(fabs(x->tangent[1] - normals[i][0]) < 1e-12);
        }
        const double *w = f->fixels[0].normal_wrench;
        assert_true(fabs(w[0]) < 1e-12);
        assert_true(fabs(w[1] - 1.0) < 1e-12);
        assert_true(fabs(w[2] + 1.0 / sqrt(5.0 / 3.0)) < 1e-12);
    }
    /* com off the centroid by d = 1: parallel axes, 5 + 3 * 1^2 = 8 */
    wr_fixture *off = rectangle(ccw, true, 4, 3);
    assert_true(fabs(off->com[0] - 4.0) < 1e-15);
    assert_true(fabs(off->inertia - 8.0) < 1e-12);
}

static void test_disc_default_and_parallel_axis_inertia(void **state)
{
    (void)state;
    wr_fixel_spec fx[1] = {fixel_at(3, -2, -1, 0)}; /* on the circle of centre (1, -2), r = 2 */
    fx[0].normal_given = false;                    /* inward normal of the circle: (-1, 0) */
    wr_fixture_spec s;
    memset(&s, 0, sizeof s);
    s.mass = 3.0;
    s.shape = WR_SHAPE_CIRCLE;
    s.center[0] = 1.0;
    s.center[1] = -2.0;
    s.radius = 2.0;
    set_friction(&s.friction, 0.2, 0.2);
    s.fixels = fx;
    s.fixel_count = 1;
    wr_fixture *f = own_fixture(test_fixture_new(&s, NULL));
    assert_true(fabs(f->com[0] - 1.0) < 1e-15);
    assert_true(fabs(f->com[1] + 2.0) < 1e-15);
    assert_true(fabs(f->inertia - 6.0) < 1e-12);
    assert_true(fabs(f->fixels[0].normal[0] + 1.0) < 1e-12);
    assert_true(fabs(f->fixels[0].normal[1]) < 1e-12);

    s.com_given = true;
    s.com[0] = 1.0;
    s.com[1] = -1.5; /* d = 0.5 */
    wr_fixture *g = own_fixture(test_fixture_new(&s, NULL));
    assert_true(fabs(g->inertia - 6.75) < 1e-12);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_teardown(test_disc_corner_goal_membership_and_margin, release_owned),
        cmocka_unit_test_teardown(test_disc_corner_G_ss_is_positive_quadrant, release_owned),
        cmocka_unit_test_teardown(test_plan_kept_strings_two_fixels, release_owned),
        cmocka_unit_test_teardown(test_plan_kept_strings_three_fixels, release_owned),
        cmocka_unit_test_teardown(test_plan_kept_count_and_shape_k1_to_8, release_owned),
        cmocka_unit_test_teardown(test_state_format_bit_order, release_owned),
        cmocka_unit_test_teardown(test_figure8_disc_two_fixels_modes, release_owned),
        cmocka_unit_test_teardown(test_single_fixel_disc_not_pinned_has_pivots, release_owned),
        cmocka_unit_test_teardown(test_form_closure_square_has_no_moving_modes, release_owned),
        cmocka_unit_test_teardown(test_force_closure_G_nn_whole_space, release_owned),
        cmocka_unit_test_teardown(test_goal_not_subset_of_strong_counterexample, release_owned),
        cmocka_unit_test_teardown(test_zero_wrench, release_owned),
        cmocka_unit_test_teardown(test_validation_base_case_is_valid, release_owned),
        cmocka_unit_test_teardown(test_validation_mass_not_finite, release_owned),
        cmocka_unit_test_teardown(test_validation_mass_not_positive, release_owned),
        cmocka_unit_test_teardown(test_validation_inertia_not_positive, release_owned),
        cmocka_unit_test_teardown(test_validation_zero_normal, release_owned),
        cmocka_unit_test_teardown(test_validation_negative_static_friction, release_owned),
        cmocka_unit_test_teardown(test_validation_kinetic_above_static, release_owned),
        cmocka_unit_test_teardown(test_validation_fixel_off_boundary, release_owned),
        cmocka_unit_test_teardown(test_validation_normal_missing_at_polygon_vertex, release_owned),
        cmocka_unit_test_teardown(test_validation_bow_tie_polygon, release_owned),
        cmocka_unit_test_teardown(test_validation_zero_area_polygon, release_owned),
        cmocka_unit_test_teardown(test_validation_duplicate_fixels, release_owned),
        cmocka_unit_test_teardown(test_validation_no_fixels, release_owned),
        cmocka_unit_test_teardown(test_validation_nine_fixels, release_owned),
        cmocka_unit_test_teardown(test_validation_missing_friction, release_owned),
        cmocka_unit_test_teardown(test_polygon_orientation_normals_centroid_inertia, release_owned),
        cmocka_unit_test_teardown(test_disc_default_and_parallel_axis_inertia, release_owned),
    };
    return cmocka_run_group_tests_name("spec", tests, NULL, NULL);
}
