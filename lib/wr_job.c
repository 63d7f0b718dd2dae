/* wr_job.c -- the design search and the lattice's poses as wr_job_chunks
 * (wr_job.h): each job's own chunk functions, in the one contract. */
#include "wr_design.h"
#include "wr_job.h"
#include "wr_lattice.h"

static bool design_claim(void *job, wr_job_claim *claim)
{
    return wr_design_job_claim(job, &claim->first, &claim->count, &claim->threshold);
}

static wr_status design_run(const void *job, const wr_job_claim *claim, const wr_stop *stop,
                            wr_lp_env *env, void *chunk, unsigned long *used)
{
    return wr_design_chunk_run(job, claim->first, claim->count, claim->threshold, stop, env,
                               chunk, used);
}

static wr_status design_merge(void *job, void *chunk)
{
    wr_design_job_merge(job, chunk); /* copies what it keeps */
    wr_design_chunk_release(chunk);
    return WR_OK;
}

static void design_release(void *chunk) { wr_design_chunk_release(chunk); }

const wr_job_chunks wr_design_job_chunks = {sizeof(wr_design_chunk), design_claim, design_run,
                                            design_merge, design_release};

static bool lattice_claim(void *job, wr_job_claim *claim)
{
    size_t first, count;
    if (!wr_lattice_job_claim(job, &first, &count))
        return false;
    *claim = (wr_job_claim){first, count, 0};
    return true;
}

static wr_status lattice_run(const void *job, const wr_job_claim *claim, const wr_stop *stop,
                             wr_lp_env *env, void *chunk, unsigned long *used)
{
    (void)env; /* the poses solve no LP */
    return wr_lattice_chunk_run(job, (size_t)claim->first, (size_t)claim->count, stop, chunk,
                                used);
}

static wr_status lattice_merge(void *job, void *chunk)
{
    return wr_lattice_job_merge(job, chunk); /* takes its designs */
}

static void lattice_release(void *chunk) { wr_lattice_chunk_release(chunk); }

const wr_job_chunks wr_lattice_job_chunks = {sizeof(wr_lattice_chunk), lattice_claim,
                                             lattice_run, lattice_merge, lattice_release};
