/* test_plan.c -- contact states, excluded strings and kept strings
 * (docs/MODEL.md section 3), checked against a brute-force reading of the rule. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>
#include <stdio.h>

#include "test_util.h"

/* Every state's strings follow the rule: backward strings are {s, m} on S,
 * not all m, u elsewhere; the self string is m on S, s elsewhere. */
static void excluded_strings_follow_the_rule(void **state)
{
    (void)state;
    for (int k = 1; k <= WR_MAX_FIXELS; k++) {
        wr_plan *plan = test_plan_new(k);
        assert_non_null(plan);
        assert_int_equal(plan->state_count, 1 << k);
        unsigned seen[1 << WR_MAX_FIXELS] = {0};
        int total = 0;
        for (int s = 0; s < plan->state_count; s++) {
            const wr_plan_state *ps = &plan->states[s];
            seen[ps->state]++;
            int touched = 0;
            for (int i = 0; i < k; i++)
                touched += (ps->state >> i) & 1;
            int expected = (1 << touched) - 1 + (touched < k ? 1 : 0);
            assert_int_equal(ps->excluded_count, expected);
            int selves = 0;
            for (int e = 0; e < ps->excluded_count; e++) {
                const wr_constraint *c = &plan->excluded[ps->excluded_first + e];
                bool self = true, all_m = true;
                for (int i = 0; i < k; i++) {
                    bool in_state = (ps->state >> i) & 1;
                    char l = c->letters[i];
                    if (in_state) {
                        assert_true(l == 's' || l == 'm');
                        self &= l == 'm';
                        all_m &= l == 'm';
                    } else {
                        assert_true(l == 'u' || l == 's');
                        self &= l == 's';
                    }
                }
                bool backward = !all_m;
                for (int i = 0; i < k && backward; i++)
                    if (!((ps->state >> i) & 1))
                        backward = c->letters[i] == 'u';
                assert_true(self || backward);
                selves += self && !backward;
            }
            assert_int_equal(selves, touched < k ? 1 : 0);
            total += ps->excluded_count;
        }
        for (int s = 0; s < plan->state_count; s++)
            assert_int_equal(seen[s], 1);
        /* Backward: sum over S of (2^|S| - 1) = 3^k - 2^k; self: one per
         * state but the full one, 2^k - 1.  Together 3^k - 1. */
        int three_k = 1;
        for (int i = 0; i < k; i++)
            three_k *= 3;
        assert_int_equal(total, three_k - 1);
        assert_int_equal(plan->kept_count, k * (1 << (k - 1)));
        wr_plan_free(plan);
    }
}

/* Kept = the strings no other listed string lies above, found here by
 * comparing every pair with wr_constraint_below (quadratic, independent of
 * the plan's own search). */
static void kept_strings_are_the_maximal_ones(void **state)
{
    (void)state;
    for (int k = 1; k <= 6; k++) {
        wr_plan *plan = test_plan_new(k);
        int n = plan->excluded_total;
        int maximal = 0;
        for (int i = 0; i < n; i++) {
            const wr_constraint *x = &plan->excluded[i];
            bool dominated = false, duplicate = false;
            for (int j = 0; j < n && !dominated; j++) {
                const wr_constraint *y = &plan->excluded[j];
                bool same = strcmp(x->letters, y->letters) == 0;
                if (same && j < i)
                    duplicate = true;
                if (!same && wr_constraint_below(x, y))
                    dominated = true;
            }
            bool listed = false;
            for (int m = 0; m < plan->kept_count; m++)
                listed |= strcmp(plan->kept[m].letters, x->letters) == 0;
            assert_int_equal(listed, !dominated);
            if (!dominated && !duplicate)
                maximal++;
        }
        assert_int_equal(plan->kept_count, maximal);
        assert_int_equal(plan->kept_count, k * (1 << (k - 1)));
        /* Origins: exactly the states whose list holds the string. */
        for (int m = 0; m < plan->kept_count; m++) {
            int holders = 0;
            for (int s = 0; s < plan->state_count; s++) {
                const wr_plan_state *ps = &plan->states[s];
                bool holds = false;
                for (int e = 0; e < ps->excluded_count; e++)
                    holds |= strcmp(plan->excluded[ps->excluded_first + e].letters,
                                    plan->kept[m].letters) == 0;
                if (!holds)
                    continue;
                holders++;
                bool found = false;
                for (int o = 0; o < plan->origins[m].count; o++)
                    found |= plan->origins[m].states[o] == ps->state;
                assert_true(found);
            }
            assert_int_equal(plan->origins[m].count, holders);
        }
        wr_plan_free(plan);
    }
}

static void seed_order_of_states(void **state)
{
    (void)state;
    wr_plan *plan = test_plan_new(3);
    const char *expected[] = {"000", "100", "010", "001", "110", "101", "011", "111"};
    for (int s = 0; s < 8; s++) {
        char text[WR_STATE_TEXT];
        wr_state_format(plan->states[s].state, 3, text);
        assert_string_equal(text, expected[s]);
    }
    /* The seed's row for 110: ssu, msu, smu, then the self transition mms. */
    const wr_plan_state *ps = &plan->states[4];
    const char *row[] = {"ssu", "msu", "smu", "mms"};
    assert_int_equal(ps->excluded_count, 4);
    for (int e = 0; e < 4; e++)
        assert_string_equal(plan->excluded[ps->excluded_first + e].letters, row[e]);
    wr_plan_free(plan);
}

static void out_of_range_fixel_counts(void **state)
{
    (void)state;
    wr_plan *plan;
    assert_int_equal(wr_plan_new(0, &plan), WR_INVALID);
    assert_null(plan);
    assert_int_equal(wr_plan_new(WR_MAX_FIXELS + 1, &plan), WR_INVALID);
    assert_null(plan);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(excluded_strings_follow_the_rule),
        cmocka_unit_test(kept_strings_are_the_maximal_ones),
        cmocka_unit_test(seed_order_of_states),
        cmocka_unit_test(out_of_range_fixel_counts),
    };
    return cmocka_run_group_tests_name("plan", tests, NULL, NULL);
}
