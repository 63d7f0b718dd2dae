/* wr_job.h -- the one contract of a job whose work comes in chunks, for a
 * server's engine that runs chunks on several threads: the design search
 * (wr_design.h) and the lattice's poses (wr_lattice.h) keep it, each in
 * its own units (candidates; the lattice's units, wr_lattice.h).
 *
 * claim and merge change the job: the caller serialises them, with each
 * other and with the job's own run.  run only reads the job, and any
 * number may run at once, each into its own chunk.  A claimed chunk is
 * merged, or abandoned after a failure (the job then fails).  Merge takes
 * what the job keeps of the chunk; release frees the rest (and a chunk
 * never merged). */
#ifndef WR_JOB_H
#define WR_JOB_H

#include "wr_status.h"

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

struct wr_lp_env;

/* A chunk as claimed: which of the job's units, and what the claim fixed
 * for them (the design search's threshold, the top-th score merged when
 * the chunk was claimed; 0 for the lattice). */
typedef struct wr_job_claim {
    uint64_t first, count;
    double threshold;
} wr_job_claim;

typedef struct wr_job_chunks {
    size_t chunk_size; /* bytes of a chunk (zeroed before its first run) */
    /* False when nothing is left to claim (or the job failed). */
    bool (*claim)(void *job, wr_job_claim *claim);
    /* WR_OK; WR_NO_MEMORY; WR_STOPPED; WR_LP_FAILED (the chunk empty
     * unless WR_OK).  `env`: the running thread's GLPK environment
     * (wr_lp.h), for a job whose LPs need one (a design on supports);
     * NULL where none is. */
    wr_status (*run)(const void *job, const wr_job_claim *claim, const wr_stop *stop,
                     struct wr_lp_env *env, void *chunk, unsigned long *used);
    wr_status (*merge)(void *job, void *chunk);
    void (*release)(void *chunk);
} wr_job_chunks;

extern const wr_job_chunks wr_design_job_chunks;  /* job: a wr_design_job */
extern const wr_job_chunks wr_lattice_job_chunks; /* job: a wr_lattice_job */

#ifdef __cplusplus
}
#endif

#endif
