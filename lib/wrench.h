/* wrench.h -- libwrench: sensorless insertion of rigid planar parts
 * (Balkcom and Trinkle), as docs/MODEL.md states it.
 *
 *   wr_status.h    wr_status: how every function that can fail says so
 *   wr_fixture.h   the fixture model and its validation
 *   wr_outline.h   outlines of lines and arcs with holes: validation, mass properties
 *   wr_cone.h      constraint strings and explicit wrench cones G_X
 *   wr_plan.h      contact states, the strings G_goal excludes, contact modes
 *   wr_lp.h        GLPK membership LPs (per-thread environments)
 *   wr_classify.h  G_goal, G_strong: verdicts, margins, blocking cones
 *   wr_regions.h   push regions, gravity arcs, disturbance margins
 *   wr_finger.h    where a round finger fits against an outline
 *   wr_sweep.h     answers as functions of a common friction coefficient
 *   wr_design.h    fixture design: sites, the best push, the search
 *   wr_lattice.h   designs on a modular fixture plate: pegs and poses
 *   wr_tolerance.h robust answers over a fixture's geometric tolerance
 *   wr_robust_sweep.h  robust push regions, arcs and least forces against mu
 *
 * Pure computation: no I/O, no global state; every function is re-entrant.
 * Objects are created by wr_status *_new(..., T **out) and released by
 * *_free; an object passed by const pointer is borrowed.  wr_analysis is
 * opaque (accessors in wr_classify.h); the fixture, plan, cone and region
 * structures are plain read-only data. */
#ifndef WRENCH_H
#define WRENCH_H

#define WR_VERSION "0.1.0"

#include "wr_classify.h"
#include "wr_cone.h"
#include "wr_design.h"
#include "wr_job.h"
#include "wr_sites.h"
#include "wr_finger.h"
#include "wr_force.h"
#include "wr_lattice.h"
#include "wr_locate.h"
#include "wr_fixture.h"
#include "wr_lp.h"
#include "wr_outline.h"
#include "wr_plan.h"
#include "wr_regions.h"
#include "wr_status.h"
#include "wr_tolerance.h"
#include "wr_robust_sweep.h"
#include "wr_support.h"
#include "wr_support_sweep.h"
#include "wr_sweep.h"
#include "wr_symmetry.h"

#ifdef __cplusplus
extern "C" {
#endif

#ifdef __cplusplus
}
#endif

#endif
