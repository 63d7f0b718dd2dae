/* wc_commands.h -- the request and answer functions of the commands, by
 * topic; wrenchctl.c's table names them.  Each follows the contracts of
 * wc_request_fn and wc_answer_fn (wc.h): the dispatcher has already read the
 * options, counted the arguments, refused --local where the store is
 * needed, and read the FIXTURE; the request function adds the rest of the
 * params, the answer function prints the table and says the exit status. */
#ifndef WC_COMMANDS_H
#define WC_COMMANDS_H

#include "wc.h"

struct wr_fixture;

/* wc_fixture.c: put, get, delete, list, status */
int wc_put_request(wc_run *run, cJSON *params);
int wc_put_answer(wc_run *run, const cJSON *result);
int wc_id_request(wc_run *run, cJSON *params);         /* get, delete: {"id"} */
int wc_delete_answer(wc_run *run, const cJSON *result);
int wc_list_request(wc_run *run, cJSON *params);
int wc_list_answer(wc_run *run, const cJSON *result);
int wc_status_answer(wc_run *run, const cJSON *result);

/* wc_classify.c: classify (WRENCH arguments, '-' for stdin) */
int wc_classify_request(wc_run *run, cJSON *params);
int wc_classify_answer(wc_run *run, const cJSON *result);

/* wc_analysis.c: cone, plan, modes */
int wc_cone_request(wc_run *run, cJSON *params);
int wc_cone_answer(wc_run *run, const cJSON *result);
int wc_plan_answer(wc_run *run, const cJSON *result);
int wc_modes_answer(wc_run *run, const cJSON *result);

/* wc_regions.c: push, gravity, margin, sweep, and their --svg pictures */
int wc_push_request(wc_run *run, cJSON *params);
int wc_push_answer(wc_run *run, const cJSON *result);
int wc_gravity_request(wc_run *run, cJSON *params);
int wc_gravity_answer(wc_run *run, const cJSON *result);
int wc_margin_request(wc_run *run, cJSON *params);
int wc_margin_answer(wc_run *run, const cJSON *result);
int wc_sweep_request(wc_run *run, cJSON *params); /* friction.sweep */
int wc_sweep_answer(wc_run *run, const cJSON *result);
int wc_design_request(wc_run *run, cJSON *params); /* fixture.design */
int wc_design_answer(wc_run *run, const cJSON *result);
int wc_locate_request(wc_run *run, cJSON *params); /* fixture.locating */
int wc_locate_answer(wc_run *run, const cJSON *result);
int wc_design_merge_request(wc_run *run, cJSON *params); /* no method: the whole command */

/* wc_reach.c: where the finger may push (push, design) */
int wc_take_push_on(wc_run *run, const char *value); /* --push-on: 0, or an exit status */
/* Adds params.push_on: --push-on's, else the clients' default for `body`
 * (a body's JSON, or a stored fixture's id string, whose body is fetched)
 * and --finger-radius; nothing when every loop is taken anyway.  -1 to go
 * on, or an exit status. */
int wc_push_on(wc_run *run, const cJSON *body, cJSON *params);

/* With --svg, the picture `draw` makes of the answer on the part (its
 * geometry read from the file or the store): -1, or EXIT_USAGE after
 * saying why there is none (wc_regions.c). */
typedef bool (*wc_drawing)(const wc_run *run, const cJSON *result, FILE *out,
                           const struct wr_fixture *geometry, const char *name);
int wc_picture(wc_run *run, const cJSON *result, wc_drawing draw);

/* wc_force.c: force, push-force, and push's --force and --case; the
 * options --case, --push X,Y (force's), --wrench (force's), --force */
int wc_take_case(wc_run *run, const char *value);
/* The force unit a fixture names ("N", "mN", "lbf"), or "(model units)". */
const char *wc_force_unit(const struct wr_fixture *fixture);
/* The same for a fixture's JSON (its "units"); a stored fixture's id
 * (a string) names none: "(model units)". */
const char *wc_named_force_unit(const cJSON *fixture);
int wc_take_force_push(wc_run *run, const char *value);
int wc_take_force_wrench(wc_run *run, const char *value);
int wc_take_push_force(wc_run *run, const char *value);
int wc_force_request(wc_run *run, cJSON *params); /* force.range */
int wc_force_answer(wc_run *run, const cJSON *result);
int wc_push_force_request(wc_run *run, cJSON *params); /* push.force */
int wc_push_force_answer(wc_run *run, const cJSON *result);
/* push.regions' "force" and "cases", when given; -1 or an exit status. */
int wc_push_loads(wc_run *run, cJSON *params);

#endif
