/* libwrench_example.c -- the disc in a corner of docs/MODEL.md section 7, classified
 * in process with libwrench (no daemon).  Built by `make` as
 * build/libwrench-example. */
#include "wrench.h"

#include <stdio.h>

int main(void)
{
    /* A disc of radius 1 seated against two fixels, friction 0.5. */
    const wr_fixel_spec fixels[2] = {
        {.at = {-1, 0}, .normal_given = true, .normal = {1, 0}},
        {.at = {0, -1}, .normal_given = true, .normal = {0, 1}},
    };
    const wr_fixture_spec spec = {
        .mass = 1,
        .shape = WR_SHAPE_CIRCLE, .center = {0, 0}, .radius = 1,
        .friction = {.given = true, .static_mu = 0.5},
        .fixel_count = 2, .fixels = fixels,
    };
    wr_error error;
    wr_fixture *fixture;
    if (wr_fixture_new(&spec, &fixture, &error) != WR_OK) {
        fprintf(stderr, "%s: %s\n", error.field, error.reason);
        return 1;
    }
    wr_analysis *analysis;
    wr_status status = wr_analysis_new(fixture, &analysis);
    if (status != WR_OK) {
        fprintf(stderr, "%s\n", wr_strerror(status));
        wr_fixture_free(fixture);
        return 1;
    }

    static const char *const verdicts[] = {"inside", "boundary", "outside"};
    const double wrenches[3][3] = {{-1, -1, 0}, {-1, -0.2, 0}, {-1, -1, -100}};
    for (int i = 0; i < 3; i++) {
        const double *g = wrenches[i];
        for (int set = WR_SET_GOAL; set <= WR_SET_STRONG; set++) {
            wr_answer answer;
            wr_classify(analysis, g, (wr_set)set, WR_DEFAULT_TOLERANCE, &answer);
            printf("g = (%g, %g, %g)  %-6s %-8s margin %+.6f", g[0], g[1], g[2],
                   set == WR_SET_GOAL ? "goal" : "strong", verdicts[answer.verdict],
                   answer.margin);
            if (answer.blocking >= 0) {
                char text[WR_CONSTRAINT_TEXT];
                wr_constraint_format(
                    &wr_analysis_cone(analysis, answer.blocking_set, answer.blocking)->constraint,
                    text);
                printf("  blocked by %s", text);
            }
            printf("\n");
        }
    }
    wr_analysis_free(analysis);
    wr_fixture_free(fixture);
    return 0;
}
