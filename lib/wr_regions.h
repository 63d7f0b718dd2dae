/* wr_regions.h -- where to push, which tilt, how much disturbance
 * (docs/MODEL.md section 6).
 *
 * A frictionless finger at boundary point p with inward normal nu applies
 * w(p) = (nu, (p - x_c) x nu) times a positive magnitude.  The push region of
 * a set is the open set of boundary points where the margin of w(p) is
 * positive: outside the closure of every excluded cone.
 *
 * Exact, not sampled: along a polygon edge w is affine in the edge
 * parameter t, so each cone's facets cut the edge at roots of linear
 * equations; on a circle w is linear in (cos theta, sin theta), so each cone
 * is met along an arc.  With a finger with friction the wrenches at a point
 * form a wedge that varies bilinearly; that case is sampled and bisected,
 * and the answer says its resolution.
 *
 * A gap narrower than 1e-9 of the range (of t, or of 360 degrees) between
 * two excluded intervals is taken for rounding where they meet, and is no
 * region. */
#ifndef WR_REGIONS_H
#define WR_REGIONS_H

#include "wr_classify.h"
#include "wr_finger.h"

#ifdef __cplusplus
extern "C" {
#endif

/* An open interval of the boundary.  On a polygon, edge i runs from vertex
 * i to vertex i+1 and t is the fraction along it, in (0, 1).  On an
 * outline, the edges are the segments of every loop in order (loop 0's
 * first; wr_push_edge_place names them) and t is the fraction of the
 * segment's length (on an arc, of its included angle).  On a circle
 * (edge 0), and for gravity, t is an angle in degrees, counter-clockwise
 * from +x, in [0, 360]; an interval through 0 degrees is split in two. */
typedef struct wr_region {
    int edge;
    double t0, t1;
} wr_region;

typedef struct wr_regions {
    int count;
    int capacity;
    wr_region *items;    /* by edge, then t0 */
    double resolution;   /* 0: exact; else the sampling step (in t, or in
                            degrees) below which a region may be missed */
} wr_regions;

void wr_regions_release(wr_regions *regions);

/* The push region of a set on the fixture's outline.  finger_friction is
 * the finger's Coulomb coefficient (0: frictionless); with friction a point
 * counts only if every force of the finger's friction cone is in the set.
 * `stop` (may be NULL) is polled between edges and between runs of samples.
 * WR_OK; WR_NO_SHAPE for a fixture without a shape; WR_INVALID for a
 * negative or infinite coefficient; WR_NO_MEMORY; WR_STOPPED.  Unless WR_OK
 * `regions` is empty. */
wr_status wr_push_regions(const wr_analysis *analysis, wr_set set, double finger_friction,
                          const wr_stop *stop, wr_regions *regions);

/* A finger's shape: its Coulomb coefficient (0: frictionless) and its
 * radius (0: a point).  With a radius r > 0 a boundary point p (inward
 * normal nu) counts only if the disc of radius r centred at p - r nu
 * overlaps no part of the workpiece (wr_finger.h); on a circle every point
 * passes. */
typedef struct wr_finger {
    double friction;
    double radius;
    /* The loops it may push on (push_on): push_on[l] for loop l of an
     * outline, push_on_count of them (a loop past them: not pushed on).
     * NULL: every loop.  Borrowed.  A polygon's and a circle's boundary is
     * loop 0.  A loop not pushed on has no push region at all. */
    const bool *push_on;
    size_t push_on_count;
} wr_finger;

/* May `finger` push on edge `edge` of the fixture (its loop in push_on)? */
bool wr_finger_pushes_on(const wr_fixture *fixture, const wr_finger *finger, int edge);

/* wr_push_regions with a finger of any size: WR_INVALID also for a
 * negative or infinite radius. */
wr_status wr_push_regions_finger(const wr_analysis *analysis, wr_set set, const wr_finger *finger,
                                 const wr_stop *stop, wr_regions *regions);

/* The same for edges [first_edge, first_edge + edge_count) only, appended
 * to `regions` (which may hold earlier parts': the parts of all edges, in
 * order, make wr_push_regions' answer), so that long work can be done a
 * part at a time.  A circle is one edge.  On failure `regions` is as it
 * was.  Returns as wr_push_regions, and WR_INVALID for a range past the
 * edges. */
wr_status wr_push_regions_part(const wr_analysis *analysis, wr_set set, const wr_finger *finger,
                               int first_edge, int edge_count, const wr_stop *stop,
                               wr_regions *regions);
/* An index of an outline's edges by the push directions they can produce,
 * for asking the push regions of many fixtures placed on one body
 * (fixture.design): the answer is wr_push_regions_finger's, bit for bit,
 * at a cost that grows with the edges near the excluded cones' boundaries
 * rather than with every edge.
 *
 * Each edge's unit scaled push wrenches lie in a cap of the sphere (a line's
 * between its ends' directions, an arc's on an ellipse about the origin);
 * a balanced tree over the edges in order holds caps of caps.  Against one
 * fixture's cones, a node whose cap lies inside a cone (with room to spare)
 * has no region, a cone the cap clears is dropped for the node's edges, and
 * a leaf is solved exactly against the cones left: a cone dropped or
 * holding the cap changes nothing in the exact answer, since it is decided
 * with far more room than the exact test's rounding allowance.  The
 * finger's blocked spans depend on the outline alone and are found once;
 * edges the finger reaches nowhere, or may not push on (push_on), are
 * left out.  A finger with friction is
 * sampled, not indexed: its regions are wr_push_regions_finger's own.
 *
 * Built from a body of outline or polygon shape (wr_fixture_body_new) and
 * the finger; the body must outlive the index, and every fixture the index
 * is used with must be placed on it (same outline, centre of mass and
 * radius of gyration: asserted).  Read-only once built: any number of
 * threads may use one index at once.  WR_OK; WR_INVALID for a finger out of
 * range; WR_NO_SHAPE for another shape; WR_NO_MEMORY. */
typedef struct wr_push_index wr_push_index;
wr_status wr_push_index_new(const wr_fixture *body, const wr_finger *finger,
                            wr_push_index **out);
void wr_push_index_free(wr_push_index *index);
size_t wr_push_index_bytes(const wr_push_index *index);
/* The finger's blocked spans of one edge (wr_finger_blocked's, found when
 * the index was built): *count of them at *spans, owned by the index. */
void wr_push_index_blocked(const wr_push_index *index, int edge, const wr_span **spans,
                           int *count);
/* wr_push_regions_finger(a, set, index's finger, stop, regions) by the
 * index.  WR_OK; WR_NO_MEMORY; WR_STOPPED (`regions` empty unless WR_OK). */
wr_status wr_push_regions_indexed(const wr_analysis *analysis, wr_set set,
                                  const wr_push_index *index, const wr_stop *stop,
                                  wr_regions *regions);

/* The edges of the outline: a polygon's sides, 1 for a circle, an
 * outline's segments over all its loops, 0 without a shape. */
int wr_push_edge_count(const wr_fixture *fixture);
/* Which loop and segment of an outline edge `edge` is (polygon: loop 0,
 * segment = edge; circle: 0, 0). */
void wr_push_edge_place(const wr_fixture *fixture, int edge, size_t *loop, size_t *segment);

/* The tilts phi (degrees, the direction gravity pulls) under which the
 * gravity wrench m g (cos phi, sin phi, 0) is in the set: exact arcs.
 * WR_OK, or WR_NO_MEMORY (`arcs` empty). */
wr_status wr_gravity_sweep(const wr_analysis *analysis, wr_set set, wr_regions *arcs);

/* The boundary point at (edge, t) and its inward unit normal. */
void wr_boundary_point(const wr_fixture *fixture, int edge, double t, double point[2],
                       double normal[2]);
/* The push wrench (nu, (p - x_c) x nu) at (edge, t). */
void wr_push_wrench(const wr_fixture *fixture, int edge, double t, double wrench[3]);
/* Length of the boundary covered by a region, and of the whole outline. */
double wr_region_length(const wr_fixture *fixture, const wr_region *region);
double wr_perimeter(const wr_fixture *fixture);

/* The disturbance margin of a biasing wrench (docs/MODEL.md section 6): in the
 * scaled metric but not normalised (force units), the distance from the
 * bias to the union of G_strong's excluded cones, or minus its depth in the
 * deepest one. */
typedef struct wr_disturbance {
    bool bounded;          /* false: no excluded cone at all (nothing moves
                              the part); the rest is then zero */
    double margin;
    int blocking;          /* the nearest (or deepest) mode: an index of
                              the strong set's cones (and constraints) */
    double worst_direction[3]; /* a physical wrench of unit scaled length:
                              with margin > 0, bias + margin * it lies on the
                              nearest cone; with margin < 0, adding |margin|
                              of it leaves the deepest cone */
} wr_disturbance;

/* WR_OK, or WR_INVALID when the bias is not finite or so large that its
 * margin is beyond the largest double. */
wr_status wr_disturbance_margin(const wr_analysis *analysis, const double bias[3],
                                wr_disturbance *out);

#ifdef __cplusplus
}
#endif

#endif
