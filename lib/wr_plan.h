/* wr_plan.h -- the insertion plan of docs/MODEL.md section 3 (contact states, the
 * transitions each must rule out, the maximal strings whose cones G_goal
 * excludes) and the contact modes of docs/MODEL.md section 4. */
#ifndef WR_PLAN_H
#define WR_PLAN_H

#include "wr_cone.h"

#ifdef __cplusplus
extern "C" {
#endif

/* A contact state is a set of touched fixels: bit i set = fixel i touched.
 * Its text is one '0'/'1' per fixel, fixel 1 first ("010": only fixel 2). */
typedef unsigned wr_state;
#define WR_STATE_TEXT (WR_MAX_FIXELS + 1)
void wr_state_format(wr_state state, int fixel_count, char text[WR_STATE_TEXT]);

/* A kept string comes from at most two states (docs/MODEL.md section 3: "sm" from 01
 * and from 11); room is left for more. */
#define WR_PLAN_MAX_ORIGINS 4

typedef struct wr_plan_state {
    wr_state state;
    int excluded_first;   /* index of its first string in plan->excluded */
    int excluded_count;   /* backward transitions, then the self transition */
} wr_plan_state;

/* The states a kept string comes from: those whose excluded list holds it. */
typedef struct wr_plan_origins {
    int count;
    wr_state states[WR_PLAN_MAX_ORIGINS];
} wr_plan_origins;

typedef struct wr_plan {
    int fixel_count;
    int state_count;          /* 2^k: by number of contacts, then "100" before "010" */
    wr_plan_state *states;
    int excluded_total;
    wr_constraint *excluded;  /* every state's strings, state after state */
    int kept_count;           /* k * 2^(k-1) */
    wr_constraint *kept;      /* maximal strings, in order of first appearance */
    wr_plan_origins *origins; /* one per kept string */
} wr_plan;

/* The plan for `fixel_count` fixels (1..WR_MAX_FIXELS), derived from the rule
 * and the order of docs/MODEL.md section 3, into *out.  WR_INVALID when the count is
 * out of range, WR_NO_MEMORY; *out is NULL unless WR_OK. */
wr_status wr_plan_new(int fixel_count, wr_plan **out);
void wr_plan_free(wr_plan *plan);

/* Kinematically feasible contact modes other than n...n (docs/MODEL.md section 4): mode
 * strings over {s, l, r, n} with strict separation, ordered by number of
 * contacts, then letters in the order s < l < r < n; then, for a body the
 * fixels do not pin, the pivots n...n+ and n...n-.  WR_OK with the count in
 * *count and a malloc'd array in *modes (free() it; NULL for none), or
 * WR_NO_MEMORY.  *pinned says whether rolling at every fixel forces q = 0. */
/* Do the fixels pin the part: does rolling at every fixel force q = 0 (as
 * wr_modes_find says it)?  Without deriving the modes. */
bool wr_fixture_pinned(const wr_fixture *fixture);

wr_status wr_modes_find(const wr_fixture *fixture, wr_constraint **modes, int *count,
                        bool *pinned);

#ifdef __cplusplus
}
#endif

#endif
