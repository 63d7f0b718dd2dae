/* wr_outline.h -- a part's outline as CAD writes it: loops of
 * straight segments and circular arcs, the first loop the outer boundary,
 * the others holes; its validation, the exact mass properties of the
 * uniform lamina it bounds, and its boundary geometry (points, normals
 * into the material, where a point lies on it).
 *
 * A loop is written as DXF writes an LWPOLYLINE: vertices (x, y, bulge),
 * closed.  Segment j of a loop runs from vertex j to vertex j + 1 (the last
 * back to vertex 0) in the order written, whatever the loop's orientation;
 * the bulge of vertex j describes segment j: tan(theta / 4) of the arc's
 * included angle theta, positive counter-clockwise, 0 a straight line.  A
 * bulge of 1 is a half circle; any finite bulge is accepted (its magnitude
 * beyond 1 makes an arc of more than a half circle).
 *
 * Either orientation is accepted for every loop; each loop records how it
 * was written (orientation) and on which side of its written direction
 * the material lies (material_side), so that nothing is reordered: indices
 * of vertices and segments are always the caller's.
 *
 * Field paths in errors mirror the JSON of the shape, without its
 * prefix (the protocol layer adds "params.fixture.body.shape."):
 *   "loops"              the list of loops as a whole
 *   "loops[i]"           loop i (too few vertices, not simple, no area,
 *                        not inside the outer loop, crossing another loop)
 *   "loops[i][j]"        vertex j of loop i (repeating vertex j - 1)
 *   "loops[i][j][k]"     component k of that vertex: 0 x, 1 y, 2 bulge
 * Reasons name the segments at fault and, where two meet, the point.
 *
 * Tolerances are relative to the outline's size (the diagonal of its
 * bounding box, arcs included), as for wr_fixture: WR_OUTLINE_TOLERANCE for
 * segments meeting and points lying on the boundary, 1e-12 of it for a
 * segment without length or a loop without area.
 *
 * Units: any consistent set.  Angles in radians. */
#ifndef WR_OUTLINE_H
#define WR_OUTLINE_H

#include "wr_status.h"

#include <stdbool.h>
#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

/* At most this many vertices over all loops: the simplicity check compares
 * every segment with every other. */
#define WR_OUTLINE_MAX_VERTICES 4096
/* Two segments within this fraction of the outline's size of each other
 * meet; a point within it of the boundary lies on it. */
#define WR_OUTLINE_TOLERANCE 1e-9

/* One loop as given: vertex_count rows of (x, y, bulge).  Borrowed. */
typedef struct wr_loop_spec {
    size_t vertex_count;
    const double (*vertices)[3];
} wr_loop_spec;

/* A validated segment, from `start` to `end` (the caller's vertices j and
 * j + 1).  Read-only for callers. */
typedef struct wr_segment {
    double start[2];
    double end[2];
    double bulge;          /* as given; 0 for a straight line */
    double length;         /* along the segment: an arc's is radius * |sweep| */
    /* An arc's circle (bulge != 0); for a line radius, start_angle and sweep
     * are 0 and center is the midpoint. */
    double center[2];
    double radius;
    double start_angle;    /* of start about center, atan2, in (-pi, pi] */
    double sweep;          /* signed included angle 4 atan(bulge), > 0
                              counter-clockwise, in (-2 pi, 2 pi) */
    /* The chord frame the library computes in: far from the centre of a
     * nearly straight arc, whose radius is huge, and exact for a line.
     * midpoint of the chord, its unit direction (start to end), the unit
     * normal to it on the side the arc bulges to (for a line: the left
     * normal), half the chord's length, and for an arc half its included
     * angle |sweep| / 2 in (0, pi) with its sine and cosine (computed from
     * the bulge, not from the angle: exact near a whole circle). */
    double midpoint[2];
    double direction[2];
    double bulge_normal[2];
    double half_chord;
    double half_angle;
    double half_angle_sin;
    double half_angle_cos;
    double box_min[2];     /* the segment's bounding box */
    double box_max[2];
} wr_segment;

/* A validated loop: segment j runs from vertex j to vertex j + 1 as
 * written. */
typedef struct wr_loop {
    size_t segment_count;  /* = the loop's vertex count */
    wr_segment *segments;  /* owned by the outline */
    int orientation;       /* +1: written counter-clockwise, -1: clockwise */
    int material_side;     /* +1: the material lies to the left of the
                              written direction, -1: to the right.  The
                              outer loop: = orientation; a hole: the
                              opposite */
    double signed_area;    /* enclosed, > 0 counter-clockwise as written */
    double perimeter;
} wr_loop;

/* A validated outline.  Read-only for callers. */
typedef struct wr_outline {
    size_t loop_count;     /* >= 1: loops[0] the outer boundary, then holes */
    wr_loop *loops;        /* owned */
    size_t vertex_count;   /* over all loops */
    double box_min[2];     /* bounding box, arcs included */
    double box_max[2];
    double size;           /* the bounding box's diagonal: tolerances' scale */
    /* The uniform lamina: the outer loop's region less the holes'. */
    double area;
    double centroid[2];
    /* The polar second moment of area about the centroid, integral of
     * |p - centroid|^2 dA: a part of mass m has the moment of inertia
     * m * polar_moment / area. */
    double polar_moment;
    double perimeter;      /* every loop's */
} wr_outline;

/* Where a point lies on an outline (wr_outline_locate). */
typedef struct wr_outline_place {
    size_t loop;
    size_t segment;
    double t;              /* fraction of the segment's length, in [0, 1] */
    double point[2];       /* the nearest point of the boundary */
    double distance;       /* from the point asked about to `point` */
    /* Within the tolerance of a vertex: the vertex (its index in the loop;
     * then segment = vertex and t = 0, the segment leaving it), and whether
     * the boundary is smooth there (the two segments' normals agree within
     * WR_OUTLINE_TOLERANCE radians: a line tangent to an arc, say), so a
     * normal is defined at it. */
    bool at_vertex;
    size_t vertex;
    bool smooth;
} wr_outline_place;

/* Validate loop_count loops (the first the outer boundary) into an outline
 * in *out.  Checks, in order, each reported with its field (above) and the
 * first found: at least one loop; each with at least 2 vertices, at most
 * WR_OUTLINE_MAX_VERTICES in all; finite numbers; a 2-vertex loop with a
 * nonzero bulge; sizes within double precision; no segment without length;
 * each loop simple (no two segments meet but neighbours at their shared
 * vertex, nor overlap), naming the two segments and where they meet; each
 * loop enclosing area; no two loops meeting; every hole strictly inside
 * the outer loop and outside every other hole.  WR_INVALID with `error`
 * (which may be NULL) filled in; WR_NO_MEMORY with field "" and a reason.
 * *out is NULL unless WR_OK.  Release with wr_outline_free. */
wr_status wr_outline_new(const wr_loop_spec *loops, size_t loop_count, wr_outline **out,
                         wr_error *error);
void wr_outline_free(wr_outline *outline);

/* The outline of a polygon wr_fixture has validated (at least 3 vertices,
 * simple, with area): one loop of straight segments, without checks.
 * WR_OK, or WR_NO_MEMORY. */
wr_status wr_outline_polygon(const double (*vertices)[2], size_t count, wr_outline **out);

/* The point at fraction t of the length of segment `segment` of loop
 * `loop` (t clamped to [0, 1]; t = 0 and t = 1 give the segment's vertices
 * exactly), and, if `normal` is not NULL, the unit normal there pointing
 * into the material: on an arc radial, on a hole's boundary away from the
 * hole's inside.  At t = 0 or 1 the normal is the segment's own (one-sided).
 * loop and segment must be in range. */
void wr_outline_boundary(const wr_outline *outline, size_t loop, size_t segment, double t,
                         double point[2], double normal[2]);

/* Does p lie within `tolerance` (a distance, >= 0; typically
 * WR_OUTLINE_TOLERANCE * outline->size) of the boundary?  If so, and
 * `place` is not NULL, where: the nearest segment (the first of equals in
 * loop and segment order) and, within the tolerance of a vertex, that
 * vertex (the nearest).  False for a non-finite p or tolerance. */
bool wr_outline_locate(const wr_outline *outline, const double p[2], double tolerance,
                       wr_outline_place *place);

/* The point of loop `loop` nearest p (the first of equals in segment
 * order): its segment, its fraction t of that segment's length, the point,
 * and (returned) the distance.  loop must be in range; p finite. */
double wr_outline_nearest_on_loop(const wr_outline *outline, size_t loop, const double p[2],
                                  size_t *segment, double *t, double point[2]);

/* A loop's width: the least distance between two parallel lines that
 * hold it between them, over WR_WIDTH_STEPS directions (every 1 degree of
 * a half turn), arcs' bulges included.  A circle's is its diameter.  What
 * the clients compare with a finger's diameter to push in a hole by
 * default (docs/PROTOCOL.md, push_on). */
#define WR_WIDTH_STEPS 180
double wr_outline_loop_width(const wr_outline *outline, size_t loop);

/* The distance from p to the nearest point of the boundary. */
double wr_outline_distance(const wr_outline *outline, const double p[2]);

/* Is p strictly inside the material (inside the outer loop, outside every
 * hole)?  Points within `tolerance` of the boundary are not. */
bool wr_outline_contains(const wr_outline *outline, const double p[2], double tolerance);

#ifdef __cplusplus
}
#endif

#endif
