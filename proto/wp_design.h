/* wp_design.h -- fixture.design as a streamed method (docs/PROTOCOL.md):
 * its parameters read and checked, the search run a budget at a time
 * (lib/wr_design.h), progress notifications, the answer written.
 * wp_methods.c puts it in the method table. */
#ifndef WP_DESIGN_H
#define WP_DESIGN_H

#include "wp_rpc.h"

typedef struct wp_design_stream wp_design_stream;

/* NULL with call->error set when the parameters are refused. */
wp_design_stream *wp_design_begin(wp_call *call);
wp_step wp_design_step(wp_design_stream *stream, wp_call *call, wp_buffer *out,
                       unsigned long budget, unsigned long *used);
void wp_design_free(wp_design_stream *stream);
/* Work any number of other threads may do beside the steps: is there a
 * chunk of candidates left, and evaluate one (false when none was left or
 * it failed; a failure is the step's to report). */
bool wp_design_parallel(wp_design_stream *stream);
bool wp_design_work(wp_design_stream *stream, const wp_host *host);
size_t wp_design_bytes(const wp_design_stream *stream);

#endif
