/* supports.c -- what the methods share for a fixture on a base plate
 * (wr_support.h; docs/MODEL.md section 11): a wrench's answer, and the
 * refusal of questions whose answer does not depend on magnitudes. */
#include "methods.h"

#include <string.h>

/* A motion's witness on supports in the fixture's force unit (divided by
 * k, the force factor; the acceleration as it is, the writer's rule):
 * the fixels' forces, the supports' friction and normal forces, the
 * friction each fixel's letter uses, and the wrench they all make by
 * Newton-Euler, M q - sum(W_n c_n + W_t c_t) - sum (f_i, (p_i - com) x f_i),
 * which is the wrench classified (to the tolerance). */
static void witness_on_supports(const wr_analysis *analysis, const wr_support_strong *strong,
                                double k, wr_witness *w)
{
    const wr_fixture *f = wr_analysis_fixture(analysis);
    const wr_supports *supports = f->supports;
    for (int j = 0; j < 3; j++)
        w->acceleration[j] = strong->acceleration[j] / k;
    /* The scaled contact wrenches' torque is divided by rho (wr_fixel). */
    const double m = f->mass, rho = f->gyration_radius;
    double made[3] = {m * strong->acceleration[0], m * strong->acceleration[1],
                      f->inertia * strong->acceleration[2]};
    for (int i = 0; i < f->fixel_count; i++) {
        const wr_fixel *x = &f->fixels[i];
        for (int j = 0; j < 2; j++)
            w->force[i][j] = strong->force[i][j] / k;
        for (int j = 0; j < 3; j++)
            made[j] -= (strong->force[i][0] * x->normal_wrench[j] +
                        strong->force[i][1] * x->tangent_wrench[j]) *
                       (j == 2 ? rho : 1);
    }
    w->support_count = supports->count;
    for (int i = 0; i < supports->count; i++) {
        const double *s = strong->support_force[i];
        const double r[2] = {supports->points[i][0] - f->com[0],
                             supports->points[i][1] - f->com[1]};
        made[0] -= s[0];
        made[1] -= s[1];
        made[2] -= r[0] * s[1] - r[1] * s[0];
        w->support_force[i][0] = s[0] / k;
        w->support_force[i][1] = s[1] / k;
        w->support_normal[i] = strong->normal[i] / k;
    }
    for (int j = 0; j < 3; j++)
        w->wrench[j] = made[j] / k;
    wr_witness_friction(f, &wr_analysis_cone(analysis, WR_SET_STRONG, strong->blocking)->constraint,
                        w);
}

wr_status wp_supports_answer(const wr_analysis *analysis, const wp_host *host,
                             const double wrench[3], wr_set set, double tolerance,
                             wr_answer *answer)
{
    memset(answer, 0, sizeof *answer);
    answer->has_margin = false;
    answer->blocking = -1;
    const wr_fixture *f = wr_analysis_fixture(analysis);
    const wr_supports *supports = f->supports;
    wr_lp_env *env = host->lp_env ? host->lp_env(host->self) : NULL;
    if (!env)
        return WR_LP_FAILED;
    /* wrench.classify takes wrenches in the fixture's force unit (a cone
     * is a cone); against the supports' friction, in the model system
     * (wr_support.h), they count by their size: converted here, and the
     * witness's forces back, so that the writer's rule holds (forces in
     * the fixture's unit, the acceleration theirs times the factor). */
    const double k = wr_fixture_force_factor(f);
    const double g[3] = {wrench[0] * k, wrench[1] * k, wrench[2] * k};
    wrench = g;
    wr_verdict goal_verdict = WR_VERDICT_INSIDE;
    if (set != WR_SET_STRONG) {
        wr_support_goal goal;
        wr_status status = wr_supports_goal(analysis, supports, env, wrench, tolerance, &goal);
        if (status != WR_OK)
            return status;
        goal_verdict = answer->verdict = goal.verdict;
        answer->blocking_set = WR_SET_GOAL;
        answer->blocking = goal.blocking;
        if (set == WR_SET_GOAL || goal.verdict == WR_VERDICT_OUTSIDE)
            return WR_OK;
    }
    wr_support_strong strong;
    wr_status status =
        wr_supports_strong(analysis, supports, env, wrench, tolerance, host->stop, &strong);
    if (status != WR_OK)
        return status;
    /* Both: the worse verdict, its blocking cone (the goal's on a tie). */
    if (set == WR_SET_STRONG || strong.verdict > goal_verdict) {
        answer->verdict = strong.verdict;
        answer->blocking_set = WR_SET_STRONG;
        answer->blocking = strong.blocking;
        for (int j = 0; j < 3; j++)
            answer->witness.acceleration[j] = strong.acceleration[j] / k;
        if (strong.blocking >= 0)
            witness_on_supports(analysis, &strong, k, &answer->witness);
    }
    return WR_OK;
}

const char *wp_supports_push_unanswered(const wr_fixture *fixture, wr_set set, double radius)
{
    return set != WR_SET_GOAL                      ? "params.set"
           : fixture->shape != WR_SHAPE_POLYGON ? "params.fixture.body.shape"
           : radius > 0                         ? "params.finger_radius"
                                                : NULL;
}

bool wp_supports_refuse(wp_call *call, const wr_fixture *fixture, const char *field,
                        const char *what)
{
    if (!fixture->supports)
        return false;
    wp_error_set(call->error, WP_INVALID_PARAMS, field,
                 "the fixture rests on supports, whose friction depends on how hard the part is "
                 "pushed: give %s",
                 what);
    return true;
}
