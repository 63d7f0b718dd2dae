/* test_lp.c -- GLPK environments: threads, fatal-error recovery, silence. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>
#include <pthread.h>
#include <stdio.h>
#include <unistd.h>

#include "test_util.h"

#define SAMPLES 1500

typedef struct job {
    const wr_analysis *analysis;
    const double (*wrenches)[3];
    wr_answer answers[SAMPLES];
    int failures;
} job;

static void classify_all(job *j)
{
    wr_lp_env *env = test_lp_env_new();
    wr_lp_set *goal, *strong;
    assert_int_equal(wr_analysis_lp_sets(j->analysis, env, &goal, &strong), 0);
    for (int i = 0; i < SAMPLES; i++)
        if (wr_classify_lp(j->analysis, goal, strong, j->wrenches[i],
                           i % 2 ? WR_SET_STRONG : WR_SET_GOAL, &j->answers[i]) != 0)
            j->failures++;
    wr_lp_set_free(goal);
    wr_lp_set_free(strong);
    wr_lp_env_free(env);
}

static void *thread_main(void *argument)
{
    classify_all(argument);
    return NULL;
}

static void two_threads_solve_concurrently(void **state)
{
    (void)state;
    test_rng rng = {99};
    wr_fixture *f = test_random_fixture(&rng, 3, false);
    assert_non_null(f);
    wr_analysis *a = test_analysis_new(f);
    static double wrenches[SAMPLES][3];
    for (int i = 0; i < SAMPLES; i++)
        for (int k = 0; k < 3; k++)
            wrenches[i][k] = test_range(&rng, -1, 1);
    static job reference, first, second;
    reference = (job){a, (const double (*)[3])wrenches, {{0}}, 0};
    first = reference;
    second = reference;
    classify_all(&reference); /* in this thread, alone */
    pthread_t t1, t2;
    assert_int_equal(pthread_create(&t1, NULL, thread_main, &first), 0);
    assert_int_equal(pthread_create(&t2, NULL, thread_main, &second), 0);
    pthread_join(t1, NULL);
    pthread_join(t2, NULL);
    assert_int_equal(reference.failures + first.failures + second.failures, 0);
    int outside = 0;
    for (int i = 0; i < SAMPLES; i++) {
        assert_int_equal(first.answers[i].verdict, reference.answers[i].verdict);
        assert_int_equal(second.answers[i].verdict, reference.answers[i].verdict);
        assert_int_equal(first.answers[i].blocking, reference.answers[i].blocking);
        assert_int_equal(second.answers[i].blocking, reference.answers[i].blocking);
        outside += reference.answers[i].verdict == WR_VERDICT_OUTSIDE;
    }
    /* Both verdicts occur, so the comparison means something. */
    assert_true(outside > 0 && outside < SAMPLES);
    wr_analysis_free(a);
    wr_fixture_free(f);
}

/* Run `body` with file descriptor 2 sent to a temporary file; return how many
 * bytes were written to it. */
static long stderr_bytes_during(void (*body)(void *), void *argument)
{
    fflush(stderr);
    FILE *capture = tmpfile();
    int saved = dup(2);
    dup2(fileno(capture), 2);
    body(argument);
    fflush(stderr);
    dup2(saved, 2);
    close(saved);
    fseek(capture, 0, SEEK_END);
    long bytes = ftell(capture);
    fclose(capture);
    return bytes;
}

typedef struct recovery {
    const wr_analysis *analysis;
    bool member_before[8], member_after[8], other_after[8];
    int failed_calls;
} recovery;

static void inject_and_recover(void *argument)
{
    recovery *r = argument;
    const wr_analysis *a = r->analysis;
    wr_lp_env *env = test_lp_env_new();
    /* Two sets in one env: a fatal error invalidates both. */
    const wr_fixture *f = wr_analysis_fixture(a);
    int modes = wr_analysis_cone_count(a, WR_SET_STRONG);
    wr_lp_set *set, *other;
    assert_int_equal(wr_lp_set_new(env, f, wr_analysis_constraints(a, WR_SET_GOAL),
                                   wr_analysis_cone_count(a, WR_SET_GOAL), &set),
                     WR_OK);
    assert_int_equal(
        wr_lp_set_new(env, f, wr_analysis_constraints(a, WR_SET_STRONG), modes, &other), WR_OK);
    double g[3] = {-1, -1, 0.3};
    for (int i = 0; i < 4; i++) {
        wr_lp_member(set, i, g, &r->member_before[i], NULL);
        bool unused;
        wr_lp_member(other, i % modes, g, &unused, NULL);
    }
    wr_lp_env_inject_failure(env, 2);
    for (int i = 0; i < 4; i++) {
        bool member = false;
        wr_status status = wr_lp_member(set, i, g, &member, NULL);
        if (status == WR_LP_FAILED)
            r->failed_calls++;
        else
            assert_int_equal(status, WR_OK);
    }
    /* Every problem is rebuilt on its next use, in both sets. */
    for (int i = 0; i < 4; i++) {
        assert_int_equal(wr_lp_member(set, i, g, &r->member_after[i], NULL), WR_OK);
        assert_int_equal(wr_lp_member(other, i % modes, g, &r->other_after[i], NULL), WR_OK);
    }
    wr_lp_set_free(set);
    wr_lp_set_free(other);
    wr_lp_env_free(env);
}

static void fatal_glpk_error_is_caught_silently(void **state)
{
    (void)state;
    wr_fixture *f = test_disc_corner(0.5);
    wr_analysis *a = test_analysis_new(f);
    recovery r;
    memset(&r, 0, sizeof r);
    r.analysis = a;
    long bytes = stderr_bytes_during(inject_and_recover, &r);
    assert_int_equal(r.failed_calls, 1);
    assert_int_equal(bytes, 0); /* GLPK printed nothing, not even its error */
    for (int i = 0; i < 4; i++)
        assert_int_equal(r.member_after[i], r.member_before[i]);
    /* (-1, -1, 0.3) is in no goal cone of the disc corner at mu = 0.5, and
     * the modes' verdicts are those of the explicit cones. */
    for (int i = 0; i < 4; i++) {
        assert_false(r.member_after[i]);
        double x[3], g[3] = {-1, -1, 0.3};
        double n = wr_fixture_scale_wrench(f, g, x);
        for (int k = 0; k < 3; k++)
            x[k] /= n;
        int modes = wr_analysis_cone_count(a, WR_SET_STRONG);
        double d = wr_cone_signed_distance(wr_analysis_cone(a, WR_SET_STRONG, i % modes), x, NULL);
        assert_int_equal(r.other_after[i], d < 0);
    }
    wr_analysis_free(a);
    wr_fixture_free(f);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(two_threads_solve_concurrently),
        cmocka_unit_test(fatal_glpk_error_is_caught_silently),
    };
    return cmocka_run_group_tests_name("lp", tests, NULL, NULL);
}
