/* wr_lattice.h -- designs on a modular fixture plate (Brost and Goldberg):
 * three round pegs in holes of a square lattice, and a pose of the part in
 * which it touches all three and overlaps none (docs/PROTOCOL.md,
 * fixture.design, "lattice").
 *
 * The plate's holes are at pitch * (i, j); a pose (x, y, theta) puts the
 * part's point p at R(theta) p + (x, y).  Designs are enumerated up to the
 * lattice's translations: the first peg is at hole (0, 0), the others at
 * holes after it in the order (j, then i), all three within an extent of
 * nx by ny holes.  For three holes and three segments of the outline (one
 * per peg, a segment may serve two), the pose follows from three distance
 * equations: in the part's frame peg k's centre q_k = R(-theta)(P_k - t)
 * lies on the segment's offset curve at the peg's radius (a line parallel
 * to a straight segment, a circle about an arc's centre), its contact
 * point on the segment itself.
 *
 *   - Three straight segments: eliminating the translation leaves
 *     A cos theta + B sin theta = C, solved in closed form (at most two
 *     poses), the translation then from two of the lines.
 *   - With an arc: eliminating the translation leaves one polynomial in
 *     t = tan(theta / 2) (docs/MODEL.md, "Lattice poses with arcs"): of
 *     degree 4 for two lines and an arc, 8 for a line and two arcs, 12
 *     for three arcs.  Its real roots are the candidate angles (a double
 *     root is a pose where a peg touches without crossing); each is made
 *     a root of the geometry by Newton's steps and its translation solved
 *     from two of the curves (lines first: one point, or the two points
 *     where a line or circle meets a circle).  WR_LATTICE_STEPS is the
 *     step of the theta scan that the tests hold the polynomial against
 *     (wr_lattice_job_scan, wr_internal.h).
 *
 * At most WR_LATTICE_MAX_DESIGNS poses are kept (those found first);
 * the answer's count of poses says how many.
 *
 * A pose is kept when each contact point lies on its segment, each peg's
 * centre is outside the material at least its radius from the outline
 * (touching is not overlapping), and it is not a pose already found for
 * the same holes (a peg on a vertex touches two segments). */
#ifndef WR_LATTICE_H
#define WR_LATTICE_H

#include "wr_classify.h"

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

#define WR_LATTICE_STEPS 1440
/* At most this many holes a side, and designs in all. */
#define WR_LATTICE_MAX_EXTENT 1000
#define WR_LATTICE_MAX_DESIGNS 1000000
/* At most this many holes within reach of the first peg (a pitch much
 * finer than the part is refused: its pairs would be billions). */
#define WR_LATTICE_MAX_HOLES 20000

typedef struct wr_lattice {
    double pitch;        /* > 0 */
    double peg_radius;   /* >= 0 */
    int extent[2];       /* nx, ny: holes a side, >= 1 */
} wr_lattice;

typedef struct wr_lattice_design {
    int holes[3][2];     /* (i, j) of each peg; the first (0, 0) */
    double pose[3];      /* x, y, theta in radians, theta in [0, 2 pi) */
    int edges[3];        /* the outline segment each peg touches (wr_push_edge numbering) */
    double at[3][2];     /* the contact points, in the part's frame */
    double normal[3][2]; /* unit, into the material */
} wr_lattice_design;

/* A bounded amount of work at a time, as the other jobs: made, run until
 * *done, then read.  WR_INVALID (`error` at "pitch", "peg_radius",
 * "extent", or "" for a body without an outline); WR_NO_MEMORY;
 * WR_STOPPED.  The body (wr_fixture_body_new: a polygon or an outline)
 * must outlive the job. */
typedef struct wr_lattice_job wr_lattice_job;

wr_status wr_lattice_job_new(const wr_fixture *body, const wr_lattice *lattice,
                             wr_lattice_job **out, wr_error *error);
wr_status wr_lattice_job_run(wr_lattice_job *job, unsigned long budget, unsigned long *used,
                             const wr_stop *stop, bool *done);
/* The same in chunks that threads may run at once (as wr_design.h's).
 * The unit of work is a hole pair with the segments the first two pegs
 * touch (numbered (pair * segments + first) * segments + second): its work
 * is the segments of the third peg, bounded by the outline alone, however
 * many holes the lattice has.  A chunk is consecutive units, as many as
 * make WR_LATTICE_CHUNK segments for the third peg, at least one; their
 * count is known only as they are claimed.  Claim, merge and abandon
 * change the job (the caller serialises them, and wr_lattice_job_run);
 * wr_lattice_chunk_run only reads it.  Merged chunks are kept in the order
 * of their units, whatever order they finish in, so the designs are the
 * same however the work was split; the job is done when every unit's
 * chunk is merged.  Merge takes the chunk's designs. */
#define WR_LATTICE_CHUNK 16384

typedef struct wr_lattice_chunk {
    size_t first, count;            /* its units */
    wr_lattice_design *designs;     /* malloc'd */
    size_t design_count;
} wr_lattice_chunk;

bool wr_lattice_job_claim(wr_lattice_job *job, size_t *first, size_t *count);
bool wr_lattice_job_claimable(const wr_lattice_job *job);
wr_status wr_lattice_chunk_run(const wr_lattice_job *job, size_t first, size_t count,
                               const wr_stop *stop, wr_lattice_chunk *out, unsigned long *used);
wr_status wr_lattice_job_merge(wr_lattice_job *job, wr_lattice_chunk *chunk);
void wr_lattice_job_abandon(wr_lattice_job *job);
void wr_lattice_chunk_release(wr_lattice_chunk *chunk);

/* Progress: units (a hole pair and the first two pegs' segments) looked
 * at (merged), of how many. */
void wr_lattice_job_progress(const wr_lattice_job *job, size_t *done, size_t *total);
/* When done: the designs, in the order found (hole triples in order, then
 * segment triples, then theta). */
const wr_lattice_design *wr_lattice_job_designs(const wr_lattice_job *job, size_t *count);
void wr_lattice_job_free(wr_lattice_job *job);

#ifdef __cplusplus
}
#endif

#endif
