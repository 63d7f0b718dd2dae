/* wc_call.h -- one request to wrenchd (or answered in process), and the
 * readers of wrenchctl's arguments. */
#ifndef WC_CALL_H
#define WC_CALL_H

#include "wc.h"

#include <stddef.h>

/* "wrenchctl: " and the message on stderr; returns EXIT_USAGE. */
int wc_usage_error(const char *format, ...) __attribute__((format(printf, 1, 2)));

/* Sends {"method", "params"} (taking `params`) to the daemon, or answers it
 * in process with --local, and returns the parsed result.  NULL after
 * saying what went wrong on stderr, with the exit status in *status:
 * EXIT_UNREACHABLE when no daemon answered, EXIT_SERVER for an error
 * answer (its message, code, field and reason said) or a broken one. */
cJSON *wc_call(wc_options *o, const char *method, cJSON *params, int *status);

/* The whole file, NUL-terminated; *length (may be NULL) its bytes.  NULL
 * when out of memory. */
char *wc_read_all(FILE *file, size_t *length);

/* A FIXTURE argument: an existing file is read as one JSON value (sent
 * inline), otherwise a fixture id (a string; refused with --local).  NULL
 * after saying why when neither. */
cJSON *wc_fixture_argument(wc_options *o, const char *argument);

/* The largest friction coefficient wrenchd takes (docs/PROTOCOL.md). */
#define WC_FRICTION_MOST 1000.0

/* --friction: *fixture (an object, or a stored fixture's id, which is
 * fetched with fixture.get) becomes an object whose friction is
 * {"static": [low, high], "kinetic": [low, high]} (numbers when low ==
 * high) at the top level, every fixel's own "friction" removed so that the
 * interval applies to every fixel.  Returns -1 to go on, or the exit status
 * after saying why not (the fetch's, or EXIT_USAGE for a fixture that is
 * not an object). */
int wc_fixture_friction(wc_options *o, cJSON **fixture, double low, double high);
/* The same with the fixture's geometric tolerance (--tolerance T[,A] of the
 * analyses; classify's is --fixture-tolerance, its --tolerance being the
 * verdicts' band) replaced. */
int wc_fixture_tolerance(wc_options *o, cJSON **fixture, double position, double angle);
/* --supports FILE|JSON: the fixture inline with that "supports" member
 * (a stored one fetched first); -1, or an exit status. */
int wc_fixture_supports(wc_options *o, cJSON **fixture, const char *supports);

/* "fx,fy,tau" or "fx,fy@x,y" as a wrench JSON value; NULL if neither. */
cJSON *wc_wrench_argument(const char *text);

#endif
