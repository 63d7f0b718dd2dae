/* wp_push_on.h -- the push_on parameter of fixture.design and push.regions
 * (docs/PROTOCOL.md, "Where a push may be made: push_on"): which loops of
 * the part's boundary a finger may push on. */
#ifndef WP_PUSH_ON_H
#define WP_PUSH_ON_H

#include "wp_json.h"
#include "wrench.h"

/* path.push_on of `object` for a body or fixture `shape`: absent or "all"
 * gives *mask NULL (every loop); "outer" loop 0; a list of loop numbers
 * those.  *mask is malloc'd (the caller frees it), *count entries, one per
 * loop of the shape (1 for a polygon or a circle).  False with `error` at
 * path.push_on or path.push_on[i]. */
bool wp_read_push_on(const cJSON *object, const char *path, const wr_fixture *shape, bool **mask,
                     size_t *count, wp_error *error);

/* An empty push.regions answer's ,"why_empty":{...} (docs/PROTOCOL.md):
 * the push at the middle of every edge the finger may push on, classified
 * in `set`; the reasons (the blocking cone's string, its set and contact
 * states; null when the push there is in the set but the finger cannot
 * push there) with the number of edges each, most first. */
void wp_write_push_why(wp_buffer *out, const wr_analysis *analysis, wr_set set,
                       const wr_finger *finger);

#endif
