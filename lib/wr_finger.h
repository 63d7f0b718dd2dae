/* wr_finger.h -- where a round finger fits against an outline.
 *
 * A finger of radius r pushing at boundary point p, whose unit normal into
 * the material is nu, is a disc centred at c = p - r nu: it touches the
 * boundary at p from outside the material.  It fits there when the open
 * disc overlaps no part of the workpiece.  Narrow slots, tight concave
 * corners and holes smaller than the finger then drop out.
 *
 * Exact: along a straight segment c moves on a line, along an arc on a
 * circle, and the places where the disc starts or stops overlapping are
 * where c crosses the boundary of some segment's r-neighbourhood (lines
 * parallel to a straight segment, circles about an arc's centre and about
 * every vertex): roots of linear and quadratic equations.  Between two
 * consecutive roots overlap does not change, so one test at a point
 * between them decides the whole piece.
 *
 * Touching is not overlapping: the disc touches its own segment along p,
 * and at a convex vertex touches the next segment's end.  Distances within
 * WR_OUTLINE_TOLERANCE of the outline's size of r count as touching. */
#ifndef WR_FINGER_H
#define WR_FINGER_H

#include "wr_classify.h"
#include "wr_outline.h"

#ifdef __cplusplus
extern "C" {
#endif

/* A closed interval of a segment's parameter t (fraction of its length). */
typedef struct wr_span {
    double lo, hi;
} wr_span;

/* The closed parts of segment `segment` of loop `loop` where a finger of
 * radius `radius` overlaps the workpiece, sorted by lo, disjoint, within
 * [0, 1], appended to the array *spans of *count items (grown with
 * realloc; the caller frees it).  radius 0 (or within the tolerance of
 * 0): none.  Endpoints to 1e-12 relative.  `stop` (may be NULL) is polled
 * between the segments looked at and between the pieces tested.  WR_OK;
 * WR_INVALID for a negative or non-finite radius or a loop or segment out
 * of range; WR_NO_MEMORY and WR_STOPPED with *spans and *count as they
 * were. */
wr_status wr_finger_blocked(const wr_outline *outline, size_t loop, size_t segment, double radius,
                            const wr_stop *stop, wr_span **spans, int *count);

#ifdef __cplusplus
}
#endif

#endif
