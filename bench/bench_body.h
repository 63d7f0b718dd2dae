/* bench_body.h -- a body alone of one loop of (x, y, bulge), mass 1, for the
 * benchmarks that run lib in process (segments, regions, lattice).
 * Header-only, as bench_util.h. */
#ifndef BENCH_BODY_H
#define BENCH_BODY_H

#include "wrench.h"

#include <stdio.h>
#include <string.h>

/* NULL, with the reason on stderr under `name`, when it is refused. */
static inline wr_fixture *bench_outline_body(const char *name, const double (*vertices)[3],
                                             size_t count)
{
    wr_loop_spec loop = {count, vertices};
    wr_fixture_spec spec;
    memset(&spec, 0, sizeof spec);
    spec.mass = 1;
    spec.shape = WR_SHAPE_OUTLINE;
    spec.loops = &loop;
    spec.loop_count = 1;
    wr_fixture *body = NULL;
    wr_error error;
    if (wr_fixture_body_new(&spec, &body, &error) != WR_OK)
        fprintf(stderr, "%s: %s: %s\n", name, error.field, error.reason);
    return body;
}

#endif
