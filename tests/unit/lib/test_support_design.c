/* test_support_design.c -- the design search on a base plate (wr_design.h
 * with spec.supports): each candidate's score against the least push on
 * the plate of that candidate made as a fixture of its own (wr_fixture_new,
 * wr_fixture_set_supports, wr_supports_least_force_find), the chunks in any
 * order with an environment each, and the refusals. */
#include "test_util.h"

#include "wr_support.h"

#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>

#include <cmocka.h>

#define G 9.81

/* The chamfered plate (examples/plate-chamfered.json, m = 2) on three
 * buttons, mu_B 0.2; four sites, the first three its 3-2-1 fixels. */
static const double VERTICES[5][2] = {{0, 0}, {4, 0}, {4, 1}, {3, 2}, {0, 2}};
static const double BUTTONS[3][2] = {{1, 0.5}, {3, 0.5}, {1.5, 1.6}};
static const wr_site SITES[4] = {{{1, 0}, {0, 1}, 0, 0},
                                 {{3, 0}, {0, 1}, 0, 0},
                                 {{0, 0.5}, {1, 0}, 0, 0},
                                 {{0, 1.5}, {1, 0}, 0, 0}};
static const double NO_LOAD[1][3] = {{0, 0, 0}};

static void plate_spec(wr_fixture_spec *spec)
{
    memset(spec, 0, sizeof *spec);
    spec->mass = 2;
    spec->shape = WR_SHAPE_POLYGON;
    spec->vertex_count = 5;
    spec->vertices = VERTICES;
    spec->friction.given = true;
    spec->friction.static_mu = 0.1;
}

static void buttons_spec(wr_support_spec *spec)
{
    memset(spec, 0, sizeof *spec);
    spec->point_count = 3;
    spec->points = BUTTONS;
    spec->friction.given = true;
    spec->friction.static_mu = 0.2;
    spec->g = G;
}

static wr_fixture *body_on_buttons(void)
{
    wr_fixture_spec spec;
    plate_spec(&spec);
    wr_fixture *body = NULL;
    wr_error error;
    assert_int_equal(wr_fixture_body_new(&spec, &body, &error), WR_OK);
    wr_support_spec buttons;
    buttons_spec(&buttons);
    assert_int_equal(wr_fixture_set_supports(body, &buttons, &error), WR_OK);
    return body;
}

static void design_spec(wr_design_spec *spec, const wr_fixture *body)
{
    memset(spec, 0, sizeof *spec);
    spec->body = body;
    spec->friction.given = true;
    spec->friction.static_mu = 0.1;
    spec->sites = SITES;
    spec->site_count = 4;
    spec->fixel_count = 3;
    spec->objective = WR_OBJECTIVE_FORCE;
    spec->top = 4;
    spec->shard_count = 1;
    spec->loads = NO_LOAD;
    spec->case_count = 1;
    spec->supports = body->supports;
}

/* The least push on the plate of the candidate `sites`, asked of it as a
 * fixture of its own: INFINITY when none seats it. */
static double candidate_least(const int sites[3], wr_lp_env *env)
{
    wr_fixture_spec spec;
    plate_spec(&spec);
    wr_fixel_spec fixels[3];
    memset(fixels, 0, sizeof fixels);
    for (int i = 0; i < 3; i++) {
        memcpy(fixels[i].at, SITES[sites[i]].at, sizeof fixels[i].at);
        memcpy(fixels[i].normal, SITES[sites[i]].normal, sizeof fixels[i].normal);
        fixels[i].normal_given = true;
    }
    spec.fixel_count = 3;
    spec.fixels = fixels;
    wr_error error;
    wr_fixture *f = test_fixture_new(&spec, &error);
    assert_non_null(f);
    wr_support_spec buttons;
    buttons_spec(&buttons);
    assert_int_equal(wr_fixture_set_supports(f, &buttons, &error), WR_OK);
    wr_analysis *a = test_analysis_new(f);
    wr_finger finger = {0};
    wr_least_force least;
    assert_int_equal(wr_supports_least_force_find(a, f->supports, env, NO_LOAD, 1, &finger, NULL,
                                                  &least),
                     WR_OK);
    wr_analysis_free(a);
    wr_fixture_free(f);
    return least.found ? least.force : INFINITY;
}

static void scores_are_each_candidates_least_push(void **state)
{
    (void)state;
    wr_lp_env *env = test_lp_env_new();
    wr_fixture *body = body_on_buttons();
    wr_design_spec spec;
    design_spec(&spec, body);
    wr_design_job *job;
    wr_error error;
    assert_int_equal(wr_design_job_new(&spec, &job, &error), WR_OK);
    bool done = false;
    while (!done)
        assert_int_equal(wr_design_job_run(job, 1UL << 30, NULL, NULL, env, &done), WR_OK);
    int count;
    const wr_design *designs = wr_design_job_designs(job, &count);
    int scored = 0;
    for (int a = 0; a < 4; a++)
        for (int b = a + 1; b < 4; b++)
            for (int c = b + 1; c < 4; c++) {
                const int sites[3] = {a, b, c};
                double least = candidate_least(sites, env);
                const wr_design *found = NULL;
                for (int i = 0; i < count; i++)
                    if (memcmp(designs[i].sites, sites, sizeof sites) == 0)
                        found = &designs[i];
                printf("sites %d %d %d: least push on the plate %.9g, design %.9g\n", a, b, c,
                       least, found ? -found->score : INFINITY);
                assert_true((found != NULL) == isfinite(least));
                if (!found)
                    continue;
                scored++;
                assert_true(fabs(-found->score - least) <= 1e-9 * least);
                assert_true(found->least_force.found &&
                            fabs(found->least_force.force - least) <= 1e-9 * least);
            }
    /* The plate's own fixels: docs/MODEL.md's 10.6650 (256-gon LPs). */
    assert_true(scored >= 2);
    assert_true(count == scored && designs[0].score >= designs[count - 1].score);
    const wr_design *own = NULL;
    for (int i = 0; i < count; i++)
        if (designs[i].sites[0] == 0 && designs[i].sites[1] == 1 && designs[i].sites[2] == 2)
            own = &designs[i];
    assert_non_null(own);
    assert_true(fabs(-own->score - 10.6650) < 1e-4);
    assert_int_equal(wr_design_job_counts(job)->no_seating_push, 4 - (uint64_t)scored);
    wr_design_job_free(job);
    wr_fixture_free(body);
    wr_lp_env_free(env);
}

/* The search's chunk and the designs' figures made with other
 * environments than the whole job's, the figures last first: the same
 * designs, bit for bit. */
static void chunks_with_an_environment_each(void **state)
{
    (void)state;
    wr_lp_env *envs[4];
    for (int i = 0; i < 4; i++)
        envs[i] = test_lp_env_new();
    wr_fixture *body = body_on_buttons();
    wr_design_spec spec;
    design_spec(&spec, body);
    wr_design_job *whole, *parts;
    wr_error error;
    assert_int_equal(wr_design_job_new(&spec, &whole, &error), WR_OK);
    assert_int_equal(wr_design_job_new(&spec, &parts, &error), WR_OK);
    bool done = false;
    while (!done)
        assert_int_equal(wr_design_job_run(whole, 1UL << 30, NULL, NULL, envs[0], &done), WR_OK);
    uint64_t first, span;
    double threshold;
    assert_true(wr_design_job_claim(parts, &first, &span, &threshold));
    wr_design_chunk chunk;
    assert_int_equal(wr_design_chunk_run(parts, first, span, threshold, NULL, envs[1], &chunk,
                                         NULL),
                     WR_OK);
    wr_design_job_merge(parts, &chunk);
    wr_design_chunk_release(&chunk);
    assert_true(wr_design_job_searched(parts));
    int left = wr_design_job_figures_left(parts);
    assert_true(left >= 2);
    for (int i = left - 1; i >= 0; i--)
        assert_int_equal(wr_design_job_figure(parts, i, NULL, envs[2 + i % 2], NULL), WR_OK);
    for (int i = 0; i < left; i++)
        wr_design_job_figure_merged(parts);
    int n1, n2;
    const wr_design *d1 = wr_design_job_designs(whole, &n1);
    const wr_design *d2 = wr_design_job_designs(parts, &n2);
    assert_int_equal(n1, n2);
    for (int i = 0; i < n1; i++)
        assert_memory_equal(&d1[i], &d2[i], sizeof d1[i]);
    wr_design_job_free(whole);
    wr_design_job_free(parts);
    wr_fixture_free(body);
    for (int i = 0; i < 4; i++)
        wr_lp_env_free(envs[i]);
}

static void refusals(void **state)
{
    (void)state;
    wr_fixture *body = body_on_buttons();
    wr_design_spec spec;
    wr_design_job *job = NULL;
    wr_error error;
    const wr_objective directions[] = {WR_OBJECTIVE_MARGIN, WR_OBJECTIVE_REGION,
                                       WR_OBJECTIVE_GRAVITY, WR_OBJECTIVE_PARETO};
    for (int i = 0; i < 4; i++) {
        design_spec(&spec, body);
        spec.objective = directions[i];
        spec.tolerance = 0.01;
        assert_int_equal(wr_design_job_new(&spec, &job, &error), WR_INVALID);
        assert_string_equal(error.field, "objective");
        assert_non_null(strstr(error.reason, "\"force\""));
    }
    design_spec(&spec, body);
    spec.finger.radius = 0.1;
    assert_int_equal(wr_design_job_new(&spec, &job, &error), WR_INVALID);
    assert_string_equal(error.field, "finger_radius");
    design_spec(&spec, body);
    spec.fixel_tolerance.given = true;
    assert_int_equal(wr_design_job_new(&spec, &job, &error), WR_INVALID);
    assert_string_equal(error.field, "fixel_tolerance");
    /* No environment: the plate's LPs cannot be solved. */
    design_spec(&spec, body);
    assert_int_equal(wr_design_job_new(&spec, &job, &error), WR_OK);
    bool done = false;
    assert_int_equal(wr_design_job_run(job, 1UL << 30, NULL, NULL, NULL, &done), WR_LP_FAILED);
    wr_design_job_free(job);
    wr_fixture_free(body);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(scores_are_each_candidates_least_push),
        cmocka_unit_test(chunks_with_an_environment_each),
        cmocka_unit_test(refusals),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
