/* wr_plan.c -- contact states and their excluded transitions (docs/MODEL.md section 3),
 * and the search for kinematically feasible contact modes (section 4). */
#include "wr_plan.h"
#include "wr_internal.h"

#include <stdlib.h>
#include <string.h>

void wr_state_format(wr_state state, int fixel_count, char text[WR_STATE_TEXT])
{
    for (int i = 0; i < fixel_count; i++)
        text[i] = (state >> i) & 1 ? '1' : '0';
    text[fixel_count] = 0;
}

static int popcount(unsigned x)
{
    int n = 0;
    for (; x; x &= x - 1)
        n++;
    return n;
}

/* States by number of contacts, then with fixel 1's bit most significant,
 * descending: 000, 100, 010, 001, 110, 101, 011, 111 (the seed's table).
 * The sort key packs both; the state rides in the low bits. */
static unsigned state_sort_key(wr_state state, int fixel_count)
{
    unsigned reversed = 0;
    for (int i = 0; i < fixel_count; i++)
        if ((state >> i) & 1)
            reversed |= 1u << (fixel_count - 1 - i);
    unsigned descending = (1u << fixel_count) - 1 - reversed;
    return ((unsigned)popcount(state) << 24) | (descending << 12) | state;
}

static int compare_keys(const void *a, const void *b)
{
    unsigned x = *(const unsigned *)a, y = *(const unsigned *)b;
    return (x > y) - (x < y);
}

static wr_constraint make_constraint(int fixel_count, const char *letters)
{
    wr_constraint c;
    memset(&c, 0, sizeof c);
    c.length = fixel_count;
    memcpy(c.letters, letters, (size_t)fixel_count);
    return c;
}

/* Base-3 code of a string over {s, m, u}: s = 0, m = 1, u = 2 per position. */
static int code_of(const char *letters, int fixel_count)
{
    int code = 0;
    for (int i = fixel_count - 1; i >= 0; i--)
        code = code * 3 + (letters[i] == 's' ? 0 : letters[i] == 'm' ? 1 : 2);
    return code;
}

/* Is the string maximal among `present`?  Y above X differs only by s -> u
 * at some non-empty set of X's s positions (s below u is the only relation
 * among s, m, u). */
static bool is_maximal(const char *letters, int fixel_count, const unsigned char *present)
{
    int s_positions[WR_MAX_FIXELS], s_count = 0;
    int power[WR_MAX_FIXELS];
    for (int i = 0, p = 1; i < fixel_count; i++, p *= 3) {
        power[i] = p;
        if (letters[i] == 's')
            s_positions[s_count++] = i;
    }
    int code = code_of(letters, fixel_count);
    for (unsigned subset = 1; subset < (1u << s_count); subset++) {
        int upper = code;
        for (int j = 0; j < s_count; j++)
            if ((subset >> j) & 1)
                upper += 2 * power[s_positions[j]];
        if (present[upper])
            return false;
    }
    return true;
}

wr_status wr_plan_new(int fixel_count, wr_plan **out)
{
    *out = NULL;
    if (fixel_count < 1 || fixel_count > WR_MAX_FIXELS)
        return WR_INVALID;
    int k = fixel_count;
    int state_count = 1 << k;
    int excluded_max = 1;
    for (int i = 0; i < k; i++)
        excluded_max *= 3; /* sum over S of 2^|S| */
    int code_space = excluded_max;

    wr_plan *plan = calloc(1, sizeof *plan);
    unsigned char *present = calloc((size_t)code_space, 1);
    int *kept_index = malloc((size_t)code_space * sizeof *kept_index);
    if (!plan || !present || !kept_index)
        goto fail;
    plan->fixel_count = k;
    plan->state_count = state_count;
    plan->states = calloc((size_t)state_count, sizeof *plan->states);
    plan->excluded = calloc((size_t)excluded_max + 1, sizeof *plan->excluded);
    if (!plan->states || !plan->excluded)
        goto fail;

    unsigned order[1 << WR_MAX_FIXELS];
    for (int i = 0; i < state_count; i++)
        order[i] = state_sort_key((wr_state)i, k);
    qsort(order, (size_t)state_count, sizeof order[0], compare_keys);

    for (int si = 0; si < state_count; si++) {
        wr_state state = order[si] & 0xfffu;
        wr_plan_state *ps = &plan->states[si];
        ps->state = state;
        ps->excluded_first = plan->excluded_total;
        int touched[WR_MAX_FIXELS], touched_count = 0;
        for (int i = 0; i < k; i++)
            if ((state >> i) & 1)
                touched[touched_count++] = i;
        /* Backward: every {s, m} assignment on S but all-m, u elsewhere;
         * by number of m, then "ms" before "sm". */
        for (int m_count = 0; m_count < touched_count; m_count++) {
            for (int assignment = (1 << touched_count) - 1; assignment >= 0; assignment--) {
                /* bit j of `assignment` (from the left) set: touched[j] is m */
                if (popcount((unsigned)assignment) != m_count)
                    continue;
                char letters[WR_MAX_FIXELS];
                memset(letters, 'u', (size_t)k);
                for (int j = 0; j < touched_count; j++)
                    letters[touched[j]] = (assignment >> (touched_count - 1 - j)) & 1 ? 'm' : 's';
                plan->excluded[plan->excluded_total++] = make_constraint(k, letters);
            }
        }
        /* Self: all-m on S, s elsewhere (none when every fixel is touched). */
        if (touched_count < k) {
            char letters[WR_MAX_FIXELS];
            for (int i = 0; i < k; i++)
                letters[i] = (state >> i) & 1 ? 'm' : 's';
            plan->excluded[plan->excluded_total++] = make_constraint(k, letters);
        }
        ps->excluded_count = plan->excluded_total - ps->excluded_first;
    }

    for (int i = 0; i < plan->excluded_total; i++)
        present[code_of(plan->excluded[i].letters, k)] = 1;
    plan->kept = calloc((size_t)plan->excluded_total, sizeof *plan->kept);
    plan->origins = calloc((size_t)plan->excluded_total, sizeof *plan->origins);
    if (!plan->kept || !plan->origins)
        goto fail;
    for (int i = 0; i < code_space; i++)
        kept_index[i] = -1;
    for (int si = 0; si < state_count; si++) {
        const wr_plan_state *ps = &plan->states[si];
        for (int e = 0; e < ps->excluded_count; e++) {
            const wr_constraint *c = &plan->excluded[ps->excluded_first + e];
            int code = code_of(c->letters, k);
            if (kept_index[code] < 0) {
                if (!is_maximal(c->letters, k, present))
                    continue;
                kept_index[code] = plan->kept_count;
                plan->kept[plan->kept_count++] = *c;
            }
            wr_plan_origins *origins = &plan->origins[kept_index[code]];
            bool known = false;
            for (int o = 0; o < origins->count; o++)
                known |= origins->states[o] == ps->state;
            if (!known && origins->count < WR_PLAN_MAX_ORIGINS)
                origins->states[origins->count++] = ps->state;
        }
    }
    free(present);
    free(kept_index);
    *out = plan;
    return WR_OK;
fail:
    free(present);
    free(kept_index);
    wr_plan_free(plan);
    return WR_NO_MEMORY;
}

void wr_plan_free(wr_plan *plan)
{
    if (!plan)
        return;
    free(plan->states);
    free(plan->excluded);
    free(plan->kept);
    free(plan->origins);
    free(plan);
}

/* ---- contact modes ------------------------------------------------------ */

typedef struct mode_search {
    const wr_fixture *fixture;
    wr_constraint current;   /* letters assigned so far, 'u' (no rows) after */
    wr_constraint *found;
    int count, capacity;
    bool out_of_memory;
} mode_search;

static const char MODE_LETTERS[] = "slrn";

static int letter_rank(char c) { return (int)(strchr(MODE_LETTERS, c) - MODE_LETTERS); }

static int compare_modes(const void *a, const void *b)
{
    const wr_constraint *x = a, *y = b;
    /* Pivots last, n...n+ before n...n-. */
    int x_pivots = x->pivot != 0, y_pivots = y->pivot != 0;
    if (x_pivots != y_pivots)
        return x_pivots - y_pivots;
    if (x->pivot != y->pivot)
        return y->pivot - x->pivot;
    int cx = 0, cy = 0;
    for (int i = 0; i < x->length; i++) {
        cx += x->letters[i] != 's';
        cy += y->letters[i] != 's';
    }
    if (cx != cy)
        return cx - cy;
    for (int i = 0; i < x->length; i++)
        if (x->letters[i] != y->letters[i])
            return letter_rank(x->letters[i]) - letter_rank(y->letters[i]);
    return 0;
}

static bool record(mode_search *search, const wr_constraint *mode)
{
    if (search->count == search->capacity) {
        int capacity = search->capacity ? 2 * search->capacity : 64;
        wr_constraint *grown = realloc(search->found, (size_t)capacity * sizeof *grown);
        if (!grown) {
            search->out_of_memory = true;
            return false;
        }
        search->found = grown;
        search->capacity = capacity;
    }
    search->found[search->count++] = *mode;
    return true;
}

/* Depth-first over fixels: a prefix that no acceleration satisfies has no
 * feasible completion (adding rows only shrinks the set), so it is cut. */
static void search_modes(mode_search *search, int fixel)
{
    if (search->out_of_memory ||
        !wr_constraint_kinematically_feasible(search->fixture, &search->current))
        return;
    int k = search->current.length;
    if (fixel == k) {
        if (strspn(search->current.letters, "n") != (size_t)k)
            record(search, &search->current);
        return;
    }
    for (int l = 0; l < 4; l++) {
        search->current.letters[fixel] = MODE_LETTERS[l];
        search_modes(search, fixel + 1);
    }
    search->current.letters[fixel] = 'u';
}

/* The rolling string n...n with a pivot: feasible iff the fixels leave the
 * part a rotation about their common point (wr_modes_find's pinned). */
static wr_constraint rolling_pivot(int k)
{
    wr_constraint rolling;
    memset(&rolling, 0, sizeof rolling);
    rolling.length = k;
    rolling.strict_separation = true;
    memset(rolling.letters, 'n', (size_t)k);
    rolling.pivot = 1;
    return rolling;
}

bool wr_fixture_pinned(const wr_fixture *fixture)
{
    wr_constraint rolling = rolling_pivot(fixture->fixel_count);
    return !wr_constraint_kinematically_feasible(fixture, &rolling);
}

wr_status wr_modes_find(const wr_fixture *fixture, wr_constraint **modes, int *count,
                        bool *pinned)
{
    mode_search search;
    memset(&search, 0, sizeof search);
    search.fixture = fixture;
    int k = fixture->fixel_count;
    search.current.length = k;
    search.current.strict_separation = true;
    memset(search.current.letters, 'u', (size_t)k);
    search_modes(&search, 0);

    /* Pinned: rolling everywhere (a_n = a_t = 0 at every fixel) forces q = 0,
     * i.e. the rows span R^3.  Otherwise the body can pivot about the common
     * contact point, and both senses of rotation count as moving. */
    wr_constraint rolling = search.current;
    memset(rolling.letters, 'n', (size_t)k);
    rolling.pivot = 1;
    bool can_pivot = wr_constraint_kinematically_feasible(fixture, &rolling);
    *pinned = !can_pivot;
    if (can_pivot) {
        record(&search, &rolling);
        rolling.pivot = -1;
        record(&search, &rolling);
    }
    if (search.out_of_memory) {
        free(search.found);
        *modes = NULL;
        *count = 0;
        return WR_NO_MEMORY;
    }
    /* A form-closed fixture has no moving mode at all: count 0, no array. */
    if (search.count > 0)
        qsort(search.found, (size_t)search.count, sizeof *search.found, compare_modes);
    *modes = search.found;
    *count = search.count;
    return WR_OK;
}
