/* supports.c -- what the methods share for a fixture on a base plate
 * (wr_support.h; docs/MODEL.md section 11): a wrench's answer, and the
 * refusal of questions whose answer does not depend on magnitudes. */
#include "methods.h"

#include <string.h>

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
        for (int i = 0; i < f->fixel_count; i++)
            for (int j = 0; j < 2; j++)
                answer->witness.force[i][j] = strong.force[i][j] / k;
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
