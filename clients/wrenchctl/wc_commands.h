/* wc_commands.h -- the request and answer functions of the commands, by
 * topic; wrenchctl.c's table names them.  Each follows the contracts of
 * wc_request_fn and wc_answer_fn (wc.h): the dispatcher has already read the
 * options, counted the arguments, refused --local where the store is
 * needed, and read the FIXTURE; the request function adds the rest of the
 * params, the answer function prints the table and says the exit status. */
#ifndef WC_COMMANDS_H
#define WC_COMMANDS_H

#include "wc.h"

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
int wc_design_merge_request(wc_run *run, cJSON *params); /* no method: the whole command */

#endif
