/* wr_design.c -- fixture design: candidate sites, the best push by branch
 * and bound, and the search over candidates (wr_design.h). */
#include "wr_design.h"
#include "wr_internal.h"
#include "wr_locate.h"
#include "wr_outline.h"
#include "wr_support.h"
#include "wr_symmetry.h"
#include "wr_tolerance.h"

#include <assert.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ---- margins along an edge ----------------------------------------------------------- */

/* Every excluded cone of both sets must be met: the margin of the push at
 * a point is classify's for WR_SET_BOTH.  A point of the branch and bound
 * keeps the nearest (or deepest) cone's point of each set, for the
 * second-order bound. */
typedef struct bb_point {
    double t;
    double margin;
    double x[3];         /* the unit scaled push wrench */
    int near_count;
    double near[2][3];   /* points of excluded cones */
} bb_point;

typedef struct bb_node {
    int edge;
    int a, b;            /* points */
    double bound;
} bb_node;

typedef struct bb_state {
    const wr_analysis *analysis;
    const wr_fixture *fixture;
    bb_point *points;
    int point_count, point_capacity;
    bb_node *heap;
    int heap_count, heap_capacity;
} bb_state;

static bool evaluate_point(bb_state *s, int edge, double t, int *index)
{
    if (s->point_count == s->point_capacity) {
        int grown = s->point_capacity ? 2 * s->point_capacity : 64;
        bb_point *more = realloc(s->points, (size_t)grown * sizeof *more);
        if (!more)
            return false;
        s->points = more;
        s->point_capacity = grown;
    }
    bb_point *p = &s->points[s->point_count];
    p->t = t;
    double w[3];
    wr_push_wrench(s->fixture, edge, t, w);
    wr_fixture_unit_wrench(s->fixture, w, p->x);
    int goal_blocking, strong_blocking;
    double goal = wr_set_margin(s->analysis, WR_SET_GOAL, p->x, &goal_blocking);
    double strong = wr_set_margin(s->analysis, WR_SET_STRONG, p->x, &strong_blocking);
    p->margin = fmin(goal, strong);
    p->near_count = 0;
    if (goal_blocking >= 0)
        wr_cone_signed_distance(wr_analysis_cone(s->analysis, WR_SET_GOAL, goal_blocking), p->x,
                                p->near[p->near_count++]);
    if (strong_blocking >= 0)
        wr_cone_signed_distance(wr_analysis_cone(s->analysis, WR_SET_STRONG, strong_blocking),
                                p->x, p->near[p->near_count++]);
    *index = s->point_count++;
    return true;
}

/* The largest |x(psi) - p| over the great-circle arc from x_a to x_b (of
 * angle theta < pi): |x - p|^2 = 1 + |p|^2 - 2 p.x, and p.x along the arc
 * is A cos psi + B sin psi, least at an end or at atan2(B, A) + pi. */
static double farthest_on_arc(const double xa[3], const double xb[3], const double e2[3],
                              double theta, const double p[3])
{
    double a = wr_dot3(p, xa), lowest = fmin(a, wr_dot3(p, xb));
    if (theta > 0) {
        double b = wr_dot3(p, e2);
        double psi = atan2(b, a) + WR_PI;
        if (psi >= 2 * WR_PI)
            psi -= 2 * WR_PI;
        if (psi > 0 && psi < theta)
            lowest = fmin(lowest, -hypot(a, b));
    }
    return sqrt(fmax(0, 1 + wr_dot3(p, p) - 2 * lowest));
}

/* An upper bound on the margin over the interval between points a and b
 * (wr_design.h says why each part holds). */
static double node_bound(const bb_state *s, int ia, int ib)
{
    const bb_point *a = &s->points[ia], *b = &s->points[ib];
    double cross[3];
    wr_cross3(a->x, b->x, cross);
    double sine = wr_norm3(cross), cosine = wr_dot3(a->x, b->x);
    double theta = atan2(sine, cosine);
    double bound = (fmax(a->margin, 0) + fmax(b->margin, 0) + theta) / 2;
    double e2[3] = {0, 0, 0};
    if (sine > 0)
        for (int k = 0; k < 3; k++)
            e2[k] = (b->x[k] - cosine * a->x[k]) / sine;
    else
        theta = 0;
    for (int i = 0; i < a->near_count; i++)
        bound = fmin(bound, farthest_on_arc(a->x, b->x, e2, theta, a->near[i]));
    for (int i = 0; i < b->near_count; i++)
        bound = fmin(bound, farthest_on_arc(a->x, b->x, e2, theta, b->near[i]));
    return fmin(bound, 1);
}

static bool heap_push(bb_state *s, int edge, int a, int b)
{
    if (s->heap_count == s->heap_capacity) {
        int grown = s->heap_capacity ? 2 * s->heap_capacity : 64;
        bb_node *more = realloc(s->heap, (size_t)grown * sizeof *more);
        if (!more)
            return false;
        s->heap = more;
        s->heap_capacity = grown;
    }
    bb_node node = {edge, a, b, node_bound(s, a, b)};
    int i = s->heap_count++;
    while (i > 0) {
        int parent = (i - 1) / 2;
        if (s->heap[parent].bound >= node.bound)
            break;
        s->heap[i] = s->heap[parent];
        i = parent;
    }
    s->heap[i] = node;
    return true;
}

static bb_node heap_pop(bb_state *s)
{
    bb_node top = s->heap[0];
    bb_node last = s->heap[--s->heap_count];
    int i = 0;
    for (;;) {
        int child = 2 * i + 1;
        if (child >= s->heap_count)
            break;
        if (child + 1 < s->heap_count && s->heap[child + 1].bound > s->heap[child].bound)
            child++;
        if (last.bound >= s->heap[child].bound)
            break;
        s->heap[i] = s->heap[child];
        i = child;
    }
    if (s->heap_count > 0)
        s->heap[i] = last;
    return top;
}

/* How many first pieces a region is cut into, so that each spans less
 * than half a turn of the push direction (wr_design.h): an arc's t is a
 * fraction of an included angle below a whole turn, a circle's t degrees. */
static int first_pieces(const wr_fixture *fixture, const wr_region *region)
{
    wr_edge_frame frame;
    wr_edge_frame_of(fixture, region->edge, &frame);
    double span = region->t1 - region->t0;
    if (frame.kind == WR_EDGE_CIRCLE)
        return (int)ceil(span / 90);
    if (frame.kind == WR_EDGE_ARC)
        return (int)ceil(span / 0.25);
    return 1;
}

wr_status wr_best_push_find(const wr_analysis *analysis, const wr_regions *both,
                            double threshold, const wr_stop *stop, wr_best_push *out,
                            bool *below)
{
    memset(out, 0, sizeof *out);
    *below = false;
    bb_state s = {analysis, wr_analysis_fixture(analysis), NULL, 0, 0, NULL, 0, 0};
    wr_status status = WR_OK;
    int best = -1, best_edge = -1;
    for (int r = 0; r < both->count && status == WR_OK; r++) {
        const wr_region *region = &both->items[r];
        int pieces = first_pieces(s.fixture, region);
        if (pieces < 1)
            pieces = 1;
        int previous = -1;
        for (int i = 0; i <= pieces; i++) {
            double t = i == pieces ? region->t1
                                   : region->t0 + (region->t1 - region->t0) * i / pieces;
            int index;
            if (!evaluate_point(&s, region->edge, t, &index)) {
                status = WR_NO_MEMORY;
                break;
            }
            if (best < 0 || s.points[index].margin > s.points[best].margin) {
                best = index;
                best_edge = region->edge;
            }
            if (previous >= 0 && !heap_push(&s, region->edge, previous, index)) {
                status = WR_NO_MEMORY;
                break;
            }
            previous = index;
        }
    }
    while (status == WR_OK && s.heap_count > 0) {
        bb_node node = heap_pop(&s);
        if (node.bound < threshold) {
            *below = true;
            break;
        }
        if (node.bound <= s.points[best].margin + WR_DESIGN_TOLERANCE)
            break; /* every other interval's bound is below this one's */
        double ta = s.points[node.a].t, tb = s.points[node.b].t;
        double tc = ta + (tb - ta) / 2;
        if (!(tc > ta && tc < tb))
            continue; /* no double between: both ends are evaluated */
        if ((s.point_count & 63) == 0 && wr_stop_requested(stop)) {
            status = WR_STOPPED;
            break;
        }
        int c;
        if (!evaluate_point(&s, node.edge, tc, &c)) {
            status = WR_NO_MEMORY;
            break;
        }
        if (s.points[c].margin > s.points[best].margin) {
            best = c;
            best_edge = node.edge;
        }
        if (!heap_push(&s, node.edge, node.a, c) || !heap_push(&s, node.edge, c, node.b))
            status = WR_NO_MEMORY;
    }
    out->evaluations = (unsigned long)s.point_count;
    if (status == WR_OK && !*below && best >= 0) {
        out->found = true;
        out->edge = best_edge;
        out->t = s.points[best].t;
        out->margin = s.points[best].margin;
        wr_boundary_point(s.fixture, best_edge, out->t, out->at, out->direction);
    }
    free(s.points);
    free(s.heap);
    return status;
}

/* ---- one candidate ----------------------------------------------------------------- */

typedef enum outcome {
    OUTCOME_SCORED,
    OUTCOME_DEGENERATE,
    OUTCOME_UNPINNED,
    OUTCOME_NO_SEATING_PUSH,
    OUTCOME_BOUNDED,
    OUTCOME_SHARED_HOLE
} outcome;

/* Two of the candidate's sites in one hole (wr_sites.h: a pin is one
 * fixel; two pins in one hole are not a design). */
static bool shares_hole(const wr_design_spec *spec, const int *sites)
{
    for (int i = 0; i < spec->fixel_count; i++)
        for (int j = 0; j < i; j++)
            if (spec->sites[sites[i]].loop > 0 &&
                spec->sites[sites[i]].loop == spec->sites[sites[j]].loop)
                return true;
    return false;
}

static double regions_length(const wr_fixture *fixture, const wr_regions *regions)
{
    double total = 0;
    for (int i = 0; i < regions->count; i++)
        total += wr_region_length(fixture, &regions->items[i]);
    return total;
}

/* The longest arc of tilts, in degrees: arcs through 0 degrees come split
 * in two, [0, b] first and [a, 360] last. */
static double longest_arc(const wr_regions *arcs)
{
    double longest = 0;
    for (int i = 0; i < arcs->count; i++)
        longest = fmax(longest, arcs->items[i].t1 - arcs->items[i].t0);
    if (arcs->count >= 2 && arcs->items[0].t0 <= 0 && arcs->items[arcs->count - 1].t1 >= 360)
        longest = fmax(longest, arcs->items[0].t1 - arcs->items[0].t0 + 360 -
                                    arcs->items[arcs->count - 1].t0);
    return fmin(longest, 360);
}

struct wr_design_job {
    wr_design_spec spec;
    wr_plan *plan;             /* for spec.fixel_count: shared by every candidate */
    wr_push_index *index;      /* the body's edges for spec.finger; NULL when
                                  exhaustive, or for a shape or finger it does
                                  not serve (a circle, a finger with friction) */
    wr_fixel *site_fixels;     /* place_sites; NULL when exhaustive */
    bool *site_ok;
    /* The symmetries' site maps (symmetry_count rows of site_count: each
     * site's image, as the lowest of equal sites, or -1), and for listed
     * candidates their site lists sorted (tuples): NULL without symmetries. */
    int *site_maps;
    int symmetry_count;
    struct tuple *tuples;
    size_t tuple_count;
    bool failed;
    uint64_t total;            /* candidates of the shard */
    uint64_t candidates;       /* of all shards */
    uint64_t next;             /* the first candidate number not yet claimed */
    int outstanding;           /* chunks claimed, not yet merged */
    wr_design_counts counts;
    wr_design *designs;        /* spec.top, best first */
    int design_count;
    /* Why candidates have no seating push (wr_design_job_why): where the
     * push is asked about, and the count per blocking goal cone, the last
     * for a push there that is in G_goal. */
    int why_edge;
    double why_t;
    uint64_t *why;             /* plan->kept_count + 1 */
    /* After the search: the designs' figures, one at a time. */
    int detailing;             /* the design being detailed */
    wr_fixture detail_fixture;
    wr_sweeper *sweeper;
    wr_sweep_job *sweep;
};

uint64_t wr_design_candidates(int site_count, int fixel_count)
{
    if (fixel_count < 0 || site_count < 0 || fixel_count > site_count)
        return 0;
    uint64_t c = 1;
    for (int i = 1; i <= fixel_count; i++) {
        /* c * (n - k + i) / i stays an integer at every step. */
        uint64_t factor = (uint64_t)(site_count - fixel_count + i);
        if (c > UINT64_MAX / factor)
            return UINT64_MAX;
        c = c * factor / (uint64_t)i;
    }
    return c;
}

bool wr_design_before(const wr_design *a, const wr_design *b)
{
    if (a->score != b->score)
        return a->score > b->score;
    return a->candidate < b->candidate;
}

/* Each site's fixel, placed alone once (site_fixels[i]), or marked
 * unplaceable (site_ok[i] false): a candidate is placed from them with
 * only the list's checks, which is wr_fixture_place's answer, bit for bit
 * (wr_fixture.h), without locating every fixel on the outline again. */
static wr_status place_sites(wr_design_job *job)
{
    const wr_design_spec *spec = &job->spec;
    size_t n = spec->site_count > 0 ? (size_t)spec->site_count : 1;
    job->site_fixels = malloc(n * sizeof *job->site_fixels);
    job->site_ok = calloc(n, sizeof *job->site_ok);
    if (!job->site_fixels || !job->site_ok)
        return WR_NO_MEMORY;
    for (int i = 0; i < spec->site_count; i++) {
        wr_fixel_spec fixel;
        memset(&fixel, 0, sizeof fixel);
        const wr_site *site = &spec->sites[i];
        memcpy(fixel.at, site->at, sizeof fixel.at);
        fixel.normal_given = true;
        memcpy(fixel.normal, site->normal, sizeof fixel.normal);
        wr_fixture alone;
        wr_error error;
        if (wr_fixture_place(spec->body, &fixel, 1, &spec->friction, &alone, &error) == WR_OK) {
            job->site_fixels[i] = alone.fixels[0];
            job->site_ok[i] = true;
        }
    }
    return WR_OK;
}

static wr_status place(const wr_design_job *job, const int *sites, wr_fixture *out)
{
    if (job->site_fixels) {
        wr_fixel fixels[WR_MAX_FIXELS];
        for (int i = 0; i < job->spec.fixel_count; i++) {
            if (!job->site_ok[sites[i]])
                return WR_INVALID;
            fixels[i] = job->site_fixels[sites[i]];
        }
        wr_error error;
        return wr_fixture_place_placed(job->spec.body, fixels, (size_t)job->spec.fixel_count, out,
                                       &error);
    }
    wr_fixel_spec fixels[WR_MAX_FIXELS];
    memset(fixels, 0, sizeof fixels);
    for (int i = 0; i < job->spec.fixel_count; i++) {
        const wr_site *site = &job->spec.sites[sites[i]];
        fixels[i].at[0] = site->at[0];
        fixels[i].at[1] = site->at[1];
        fixels[i].normal_given = true;
        fixels[i].normal[0] = site->normal[0];
        fixels[i].normal[1] = site->normal[1];
    }
    wr_error error;
    return wr_fixture_place(job->spec.body, fixels, (size_t)job->spec.fixel_count,
                            &job->spec.friction, out, &error);
}

/* WR_OBJECTIVE_ACCURACY's score of a placed candidate: minus its worst
 * locating error (wr_design.h).  Fixels that leave a motion free are
 * unpinned; a fixture wr_locate refuses (a locator passing a corner within
 * the tolerance) degenerate. */
static wr_status accuracy_score(const wr_design_job *job, const wr_fixture *fixture,
                                outcome *result, double *score)
{
    const wr_design_spec *spec = &job->spec;
    double tolerance[WR_MAX_FIXELS];
    wr_locate_feature features[WR_DESIGN_MAX_FEATURES];
    for (int i = 0; i < WR_MAX_FIXELS; i++)
        tolerance[i] = spec->tolerance;
    for (int j = 0; j < spec->feature_count; j++) {
        features[j].at[0] = spec->features[j][0];
        features[j].at[1] = spec->features[j][1];
    }
    wr_locating locating;
    wr_error error;
    wr_status status = wr_locate(fixture, tolerance, 3, features, (size_t)spec->feature_count,
                                 &locating, &error);
    if (status == WR_NO_MEMORY)
        return status;
    if (status != WR_OK) {
        *result = OUTCOME_DEGENERATE;
        return WR_OK;
    }
    if (!locating.deterministic) {
        *result = OUTCOME_UNPINNED;
        return WR_OK;
    }
    double worst = spec->feature_count > 0 ? 0 : locating.pose_scaled;
    for (int j = 0; j < spec->feature_count; j++)
        worst = fmax(worst, features[j].exact_length);
    *score = -worst;
    return WR_OK;
}

/* The push regions of a set for the search's finger: by the job's index
 * when it has one (the same answer, bit for bit: wr_regions.h). */
static wr_status push_regions(const wr_design_job *job, const wr_analysis *analysis, wr_set set,
                              wr_regions *out)
{
    if (job->index)
        return wr_push_regions_indexed(analysis, set, job->index, NULL, out);
    return wr_push_regions_finger(analysis, set, &job->spec.finger, NULL, out);
}

/* The goal cone that blocks the push at the job's point of asking (the
 * plan's kept string index), or the plan's kept_count when none does. */
static int why_no_seating_push(const wr_design_job *job, const wr_fixture *fixture,
                               const wr_analysis *analysis, unsigned long *units)
{
    double wrench[3];
    wr_push_wrench(fixture, job->why_edge, job->why_t, wrench);
    wr_answer answer;
    *units += (unsigned long)wr_analysis_cone_count(analysis, WR_SET_GOAL) * 40;
    if (wr_classify_margin(analysis, wrench, WR_SET_GOAL, WR_DEFAULT_TOLERANCE, &answer) != WR_OK ||
        answer.blocking < 0 || answer.blocking >= job->plan->kept_count)
        return job->plan->kept_count;
    return answer.blocking;
}

/* WR_OBJECTIVE_PARETO's three figures of a placed candidate whose goal
 * region is not empty (analysis complete): the best push's margin (0
 * without a `both` region), the worst locating error, the least push
 * force (INFINITY without cases or where none does `both`). */
static wr_status pareto_figures(const wr_design_job *job, const wr_fixture *fixture,
                                const wr_analysis *analysis, outcome *result, double pareto[3],
                                unsigned long *units)
{
    const wr_design_spec *spec = &job->spec;
    double accuracy;
    wr_status status = accuracy_score(job, fixture, result, &accuracy);
    *units += 2000;
    if (status != WR_OK || *result != OUTCOME_SCORED)
        return status;
    pareto[1] = -accuracy;
    int cones = wr_analysis_cone_count(analysis, WR_SET_GOAL) +
                wr_analysis_cone_count(analysis, WR_SET_STRONG);
    wr_regions both = {0};
    status = push_regions(job, analysis, WR_SET_BOTH, &both);
    *units += (unsigned long)cones * (unsigned long)wr_push_edge_count(fixture) * 4;
    pareto[0] = 0;
    if (status == WR_OK && both.count > 0) {
        wr_best_push push;
        bool below;
        status = wr_best_push_find(analysis, &both, -INFINITY, NULL, &push, &below);
        *units += push.evaluations * (unsigned long)cones;
        pareto[0] = push.margin;
    }
    wr_regions_release(&both);
    pareto[2] = INFINITY;
    if (status == WR_OK && spec->case_count > 0) {
        wr_least_force least;
        status = wr_least_force_find(analysis, WR_SET_BOTH, spec->loads, spec->case_count,
                                     &spec->finger, NULL, &least);
        *units += least.evaluations * (unsigned long)cones * (unsigned long)spec->case_count;
        if (status == WR_OK && least.found)
            pareto[2] = least.force;
    }
    return status;
}

/* The least push on the plate (wr_supports_least_force_find) of a
 * placed candidate on the job's supports under every load case: found
 * false when no push seats it.  Only G_goal is made (seating is all that
 * is asked).  *units: about the work done (each point's forces are
 * second-order cone programmes, solved as LPs refined until they meet). */
static wr_status plate_least_push(const wr_design_job *job, const wr_fixture *fixture,
                                  const wr_stop *stop, wr_lp_env *env, wr_least_force *least,
                                  unsigned long *units)
{
    const wr_design_spec *spec = &job->spec;
    memset(least, 0, sizeof *least);
    if (!env)
        return WR_LP_FAILED;
    wr_analysis *analysis;
    wr_status status = wr_analysis_goal_new(fixture, job->plan, &analysis);
    if (status != WR_OK)
        return status;
    status = wr_supports_least_force_find(analysis, spec->supports, env, spec->loads,
                                          spec->case_count, &spec->finger, stop, least);
    *units += (least->evaluations + 1) * 400UL *
              (unsigned long)wr_analysis_cone_count(analysis, WR_SET_GOAL) *
              (unsigned long)spec->case_count;
    wr_analysis_free(analysis);
    return status;
}

/* WR_OBJECTIVE_FORCE on the plate: minus the least push that seats the
 * placed candidate on its supports, or no seating push (with *why). */
static wr_status plate_force_score(const wr_design_job *job, const wr_fixture *fixture,
                                   const wr_stop *stop, wr_lp_env *env, outcome *result,
                                   double *score, unsigned long *units, int *why)
{
    wr_least_force least;
    wr_status status = plate_least_push(job, fixture, stop, env, &least, units);
    if (status != WR_OK)
        return status;
    *result = least.found ? OUTCOME_SCORED : OUTCOME_NO_SEATING_PUSH;
    if (least.found) {
        *score = -least.force;
        return WR_OK;
    }
    /* Why, asked of the floating part: a cone that blocks the push there
     * blocks it on the plate too (C lies in C + S). */
    wr_analysis *analysis;
    status = wr_analysis_goal_new(fixture, job->plan, &analysis);
    if (status == WR_OK)
        *why = why_no_seating_push(job, fixture, analysis, units);
    wr_analysis_free(analysis);
    return status;
}

/* Score one candidate, giving up (OUTCOME_BOUNDED) once its score is
 * certainly below `threshold`.  *units: about the work done.  Without a
 * seating push, *why says why (why_no_seating_push). */
static wr_status score_candidate(const wr_design_job *job, const int *sites, double threshold,
                                 const wr_stop *stop, wr_lp_env *env, outcome *result,
                                 double *score, unsigned long *units, int *why, double pareto[3])
{
    const wr_design_spec *spec = &job->spec;
    wr_fixture fixture;
    *units += 100;
    if (shares_hole(spec, sites)) {
        *result = OUTCOME_SHARED_HOLE;
        return WR_OK;
    }
    if (place(job, sites, &fixture) != WR_OK) {
        *result = OUTCOME_DEGENERATE;
        return WR_OK;
    }
    if (!wr_fixture_pinned(&fixture)) {
        *result = OUTCOME_UNPINNED;
        return WR_OK;
    }
    if (spec->supports && spec->objective == WR_OBJECTIVE_FORCE)
        return plate_force_score(job, &fixture, stop, env, result, score, units, why);
    /* G_goal first: most candidates have no seating push, and need no
     * modes nor G_strong. */
    wr_analysis *analysis;
    wr_status status = wr_analysis_goal_new(&fixture, job->plan, &analysis);
    if (status != WR_OK)
        return status;
    int cones = wr_analysis_cone_count(analysis, WR_SET_GOAL);
    int edges = wr_push_edge_count(&fixture);
    *units += (unsigned long)cones * 40;
    wr_regions goal, both = {0};
    status = push_regions(job, analysis, WR_SET_GOAL, &goal);
    *units += (unsigned long)cones * (unsigned long)edges * 4;
    if (status == WR_OK && goal.count == 0 && spec->objective != WR_OBJECTIVE_FORCE) {
        *result = OUTCOME_NO_SEATING_PUSH;
        *why = why_no_seating_push(job, &fixture, analysis, units);
    }
    else if (status == WR_OK && (spec->objective == WR_OBJECTIVE_GRAVITY ||
                                 (status = wr_analysis_complete(analysis)) == WR_OK)) {
        cones += wr_analysis_cone_count(analysis, WR_SET_STRONG);
        *units += (unsigned long)cones * 40;
        *result = OUTCOME_SCORED;
        if (spec->objective == WR_OBJECTIVE_ACCURACY) {
            status = accuracy_score(job, &fixture, result, score);
            *units += 2000;
        } else if (spec->objective == WR_OBJECTIVE_PARETO) {
            status = pareto_figures(job, &fixture, analysis, result, pareto, units);
            *score = pareto[0];
        } else if (spec->objective == WR_OBJECTIVE_FORCE) {
            wr_least_force least;
            status = wr_least_force_find(analysis, WR_SET_BOTH, spec->loads, spec->case_count,
                                         &spec->finger, NULL, &least);
            *units += least.evaluations * (unsigned long)cones * (unsigned long)spec->case_count;
            if (status == WR_OK && !least.found) {
                *result = OUTCOME_NO_SEATING_PUSH;
                *why = why_no_seating_push(job, &fixture, analysis, units);
            } else if (status == WR_OK) {
                *score = -least.force;
            }
        } else if (spec->objective == WR_OBJECTIVE_GRAVITY) {
            wr_regions arcs;
            status = wr_gravity_sweep(analysis, WR_SET_GOAL, &arcs);
            if (status == WR_OK)
                *score = longest_arc(&arcs);
            wr_regions_release(&arcs);
        } else if (spec->objective == WR_OBJECTIVE_REGION &&
                   regions_length(&fixture, &goal) * (1 + 1e-9) + 1e-12 * wr_perimeter(&fixture) <
                       threshold) {
            /* The both region lies inside the goal region. */
            *result = OUTCOME_BOUNDED;
        } else {
            status = push_regions(job, analysis, WR_SET_BOTH, &both);
            *units += (unsigned long)cones * (unsigned long)edges * 4;
            if (status == WR_OK && spec->objective == WR_OBJECTIVE_REGION) {
                *score = regions_length(&fixture, &both);
            } else if (status == WR_OK && both.count == 0) {
                *score = 0;
            } else if (status == WR_OK) {
                wr_best_push push;
                bool below;
                status = wr_best_push_find(analysis, &both, threshold, NULL, &push, &below);
                *units += push.evaluations * (unsigned long)cones;
                if (below)
                    *result = OUTCOME_BOUNDED;
                else
                    *score = push.margin;
            }
            wr_regions_release(&both);
        }
    }
    wr_regions_release(&goal);
    wr_analysis_free(analysis);
    return status;
}

/* ---- symmetric candidates ------------------------------------------------------------- */

/* A listed candidate's sites as equal sites' lowest, sorted: the key that
 * its images are looked up by. */
typedef struct tuple {
    int sites[WR_MAX_FIXELS];
    uint64_t candidate;        /* the lowest listed with these sites */
    uint64_t repeats;          /* how many are listed with them */
} tuple;

static int compare_sites(const int *a, const int *b, int k)
{
    for (int i = 0; i < k; i++)
        if (a[i] != b[i])
            return a[i] < b[i] ? -1 : 1;
    return 0;
}

static int compare_tuples(const void *a, const void *b)
{
    const tuple *x = a, *y = b;
    int c = compare_sites(x->sites, y->sites, WR_MAX_FIXELS);
    if (c != 0)
        return c;
    return (x->candidate > y->candidate) - (x->candidate < y->candidate);
}

/* The image of k sites under map (NULL: the identity, as given), sorted;
 * false when a site has no image or two share one. */
static bool image_of(const int *map, const int *sites, int k, int *out)
{
    for (int i = 0; i < k; i++) {
        int v = map ? map[sites[i]] : sites[i];
        if (v < 0)
            return false;
        int j = i;
        while (j > 0 && out[j - 1] > v) {
            out[j] = out[j - 1];
            j--;
        }
        out[j] = v;
    }
    for (int i = 1; i < k; i++)
        if (out[i] == out[i - 1])
            return false;
    return true;
}

/* The listed tuple of these sorted sites, or NULL. */
static const tuple *listed_tuple(const wr_design_job *job, const int *sites)
{
    tuple key;
    memset(&key, 0, sizeof key);
    memcpy(key.sites, sites, (size_t)job->spec.fixel_count * sizeof *sites);
    size_t a = 0, b = job->tuple_count;
    while (a < b) {
        size_t m = a + (b - a) / 2;
        int c = compare_sites(job->tuples[m].sites, key.sites, WR_MAX_FIXELS);
        if (c == 0)
            return &job->tuples[m];
        if (c < 0)
            a = m + 1;
        else
            b = m;
    }
    return NULL;
}

/* The site maps (the identity's first: each site as the lowest site equal
 * to it), and for listed candidates their tuples, one per distinct site
 * list (the lowest candidate with it and how many). */
static wr_status symmetric_setup(wr_design_job *job)
{
    const wr_design_spec *spec = &job->spec;
    size_t n = spec->site_count > 0 ? (size_t)spec->site_count : 1;
    job->symmetry_count = spec->symmetry_count + 1;
    job->site_maps = malloc((size_t)job->symmetry_count * n * sizeof *job->site_maps);
    if (!job->site_maps)
        return WR_NO_MEMORY;
    wr_symmetry identity;
    memset(&identity, 0, sizeof identity);
    identity.linear[0][0] = identity.linear[1][1] = 1;
    for (int g = 0; g < job->symmetry_count; g++)
        if (wr_symmetry_site_map(g ? &spec->symmetries[g - 1] : &identity, spec->sites,
                                 spec->site_count, spec->body->size,
                                 job->site_maps + (size_t)g * n) != WR_OK)
            return WR_NO_MEMORY;
    if (!spec->candidates)
        return WR_OK;
    job->tuples = calloc(spec->candidate_count + 1, sizeof *job->tuples);
    if (!job->tuples)
        return WR_NO_MEMORY;
    size_t count = 0;
    for (uint64_t r = 0; r < spec->candidate_count; r++) {
        tuple *t = &job->tuples[count];
        if (image_of(job->site_maps, spec->candidates[r], spec->fixel_count, t->sites)) {
            t->candidate = r;
            t->repeats = 1;
            count++;
        }
    }
    qsort(job->tuples, count, sizeof *job->tuples, compare_tuples);
    size_t kept = 0;
    for (size_t i = 0; i < count; i++) {
        if (kept > 0 && compare_sites(job->tuples[kept - 1].sites, job->tuples[i].sites,
                                      WR_MAX_FIXELS) == 0)
            job->tuples[kept - 1].repeats++;
        else
            job->tuples[kept++] = job->tuples[i];
    }
    job->tuple_count = kept;
    return WR_OK;
}

/* Is candidate r (its sites) the lowest-numbered of the candidates that
 * the symmetries map it onto?  *copies: how many those are, itself
 * included.  `seen` has room for symmetry_count site lists. */
static bool representative(const wr_design_job *job, uint64_t r, const int *sites, int *seen,
                           int *copies)
{
    const wr_design_spec *spec = &job->spec;
    int k = spec->fixel_count;
    size_t n = spec->site_count > 0 ? (size_t)spec->site_count : 1;
    int distinct = 0;
    uint64_t total = 0;
    bool lowest = true;
    for (int g = 0; g < job->symmetry_count; g++) {
        int *image = seen + (size_t)distinct * (size_t)k;
        if (!image_of(job->site_maps + (size_t)g * n, sites, k, image))
            continue;
        bool again = false;
        for (int i = 0; i < distinct && !again; i++)
            again = compare_sites(seen + (size_t)i * (size_t)k, image, k) == 0;
        if (again)
            continue;
        if (spec->candidates) {
            const tuple *t = listed_tuple(job, image);
            if (!t)
                continue;
            lowest &= t->candidate >= r;
            total += t->repeats;
        } else {
            lowest &= compare_sites(image, sites, k) >= 0;
            total++;
        }
        distinct++;
    }
    *copies = total > 0 ? (int)total : 1;
    return lowest;
}

/* Where a candidate without a seating push is asked why: the middle of
 * the longest edge the finger may push on (the first of equals; a circle:
 * at 180 degrees, the middle of its range). */
static void why_point(const wr_design_spec *spec, int *edge, double *t)
{
    *edge = 0;
    *t = spec->body->shape == WR_SHAPE_CIRCLE ? 180 : 0.5;
    double longest = -1;
    int edges = wr_push_edge_count(spec->body);
    for (int e = 0; spec->body->shape != WR_SHAPE_CIRCLE && e < edges; e++) {
        wr_region whole = {e, 0, 1};
        double length = wr_region_length(spec->body, &whole);
        if (wr_finger_pushes_on(spec->body, &spec->finger, e) && length > longest) {
            longest = length;
            *edge = e;
        }
    }
}

/* ---- the job --------------------------------------------------------------------------- */

bool wr_design_supports_asked(const wr_design_spec *spec, wr_error *error)
{
    if (spec->objective != WR_OBJECTIVE_FORCE && spec->objective != WR_OBJECTIVE_ACCURACY) {
        wr_error_set(error, "objective", "on supports, whose friction depends on how hard "
                     "the part is pushed, this objective ranks directions alone: give \"force\" "
                     "(the least seating push, with cases) or \"accuracy\"");
        return false;
    }
    if (spec->fixel_tolerance.given) {
        wr_error_set(error, "fixel_tolerance", "a design on supports takes no fixel tolerance "
                     "(the robust answers are those of a part floating in its plane)");
        return false;
    }
    if (spec->objective != WR_OBJECTIVE_FORCE && spec->case_count == 0)
        return true; /* no push is asked */
    /* The least push on the plate (wr_supports_least_force_find). */
    if (spec->body->shape != WR_SHAPE_POLYGON) {
        wr_error_set(error, "body.shape", "the least push on supports is found along a "
                     "polygon's straight edges: give the part as a polygon");
        return false;
    }
    if (spec->finger.radius > 0 || spec->finger.friction > 0) {
        wr_error_set(error, spec->finger.radius > 0 ? "finger_radius" : "finger_friction",
                     "the least push on supports is found for a point finger without "
                     "friction: leave it out");
        return false;
    }
    return true;
}

wr_status wr_design_job_new(const wr_design_spec *spec, wr_design_job **out, wr_error *error)
{
    *out = NULL;
    if (!spec->body || spec->body->fixel_count != 0 || spec->site_count < 0 ||
        (spec->site_count > 0 && !spec->sites)) {
        wr_error_set(error, "", "no body or sites");
        return WR_INVALID;
    }
    if (spec->fixel_count < 1 || spec->fixel_count > WR_MAX_FIXELS) {
        wr_error_set(error, "fixels", "must be from 1 to %d, got %d", WR_MAX_FIXELS,
                     spec->fixel_count);
        return WR_INVALID;
    }
    if (spec->top < 1 || spec->top > WR_DESIGN_MAX_TOP) {
        wr_error_set(error, "top", "must be from 1 to %d, got %d", WR_DESIGN_MAX_TOP, spec->top);
        return WR_INVALID;
    }
    if (spec->shard_count < 1 || spec->shard_index < 0 ||
        spec->shard_index >= spec->shard_count) {
        wr_error_set(error, "shard", "must be [i, n] with 0 <= i < n, got [%d, %d]",
                     spec->shard_index, spec->shard_count);
        return WR_INVALID;
    }
    if (!(spec->finger.friction >= 0) || !isfinite(spec->finger.friction)) {
        wr_error_set(error, "finger_friction", "must be a non-negative number");
        return WR_INVALID;
    }
    if (!(spec->finger.radius >= 0) || !isfinite(spec->finger.radius)) {
        wr_error_set(error, "finger_radius", "must be a non-negative number");
        return WR_INVALID;
    }
    if (spec->objective == WR_OBJECTIVE_ACCURACY || spec->objective == WR_OBJECTIVE_PARETO) {
        const char *name = spec->objective == WR_OBJECTIVE_ACCURACY ? "accuracy" : "pareto";
        /* A disc's 2 locating fixels leave it free to turn: never pinned. */
        if (spec->body->shape == WR_SHAPE_CIRCLE) {
            wr_error_set(error, "objective", "%s designs 3 fixels on a part with an "
                         "outline: a disc is located by 2, which never pin it", name);
            return WR_INVALID;
        }
        if (spec->fixel_count != 3) {
            wr_error_set(error, "fixels", "must be 3 for objective %s (locating accuracy "
                         "is answered for 3 fixels), got %d", name, spec->fixel_count);
            return WR_INVALID;
        }
        if (!(spec->tolerance >= 0) || !isfinite(spec->tolerance)) {
            wr_error_set(error, "tolerance", "must be a finite number >= 0");
            return WR_INVALID;
        }
        if (spec->feature_count < 0 || spec->feature_count > WR_DESIGN_MAX_FEATURES ||
            (spec->feature_count > 0 && !spec->features)) {
            wr_error_set(error, "features", "at most %d", WR_DESIGN_MAX_FEATURES);
            return WR_INVALID;
        }
        for (int j = 0; j < spec->feature_count; j++) {
            double outside = wr_locate_outside(spec->body, spec->features[j]);
            if (!isfinite(spec->features[j][0]) || !isfinite(spec->features[j][1]) ||
                outside > WR_LOCATE_FEATURE_REACH * spec->body->size) {
                char field[40];
                snprintf(field, sizeof field, "features[%d].at", j);
                wr_error_set(error, field, "must be finite and no farther than a tenth of the "
                             "part's size (%.6g) outside it; it lies %.6g outside",
                             spec->body->size, outside);
                return WR_INVALID;
            }
        }
    }
    if (spec->supports && !wr_design_supports_asked(spec, error))
        return WR_INVALID;
    if (spec->case_count < 0 || (spec->case_count > 0 && !spec->loads) ||
        (spec->objective == WR_OBJECTIVE_FORCE && spec->case_count == 0)) {
        wr_error_set(error, "cases", "required with the objective force");
        return WR_INVALID;
    }
    uint64_t candidates = spec->candidates
                              ? spec->candidate_count
                              : wr_design_candidates(spec->site_count, spec->fixel_count);
    for (uint64_t r = 0; spec->candidates && r < spec->candidate_count; r++)
        for (int k = 0; k < spec->fixel_count; k++)
            if (spec->candidates[r][k] < 0 || spec->candidates[r][k] >= spec->site_count ||
                (k > 0 && spec->candidates[r][k] <= spec->candidates[r][k - 1])) {
                wr_error_set(error, "", "candidate %llu is not increasing site indices",
                             (unsigned long long)r);
                return WR_INVALID;
            }
    if (candidates == UINT64_MAX) {
        wr_error_set(error, "fixels", "%d of %d sites give more candidates than can be counted",
                     spec->fixel_count, spec->site_count);
        return WR_INVALID;
    }
    wr_design_job *job = calloc(1, sizeof *job);
    wr_design *designs = calloc((size_t)spec->top, sizeof *designs);
    if (!job || !designs) {
        free(job);
        free(designs);
        wr_error_set(error, "", "out of memory");
        return WR_NO_MEMORY;
    }
    job->spec = *spec;
    job->designs = designs;
    if (wr_plan_new(spec->fixel_count, &job->plan) != WR_OK) {
        free(designs);
        free(job);
        wr_error_set(error, "", "out of memory");
        return WR_NO_MEMORY;
    }
    if (spec->supports) { /* a copy would have to map the supports too */
        job->spec.symmetries = NULL;
        job->spec.symmetry_count = 0;
    }
    if (job->spec.symmetries && job->spec.symmetry_count > 0 && symmetric_setup(job) != WR_OK) {
        wr_design_job_free(job);
        wr_error_set(error, "", "out of memory");
        return WR_NO_MEMORY;
    }
    if (!spec->exhaustive && place_sites(job) != WR_OK) {
        wr_design_job_free(job);
        wr_error_set(error, "", "out of memory");
        return WR_NO_MEMORY;
    }
    if (!spec->exhaustive && spec->finger.friction == 0 &&
        (spec->body->shape == WR_SHAPE_OUTLINE || spec->body->shape == WR_SHAPE_POLYGON) &&
        wr_push_index_new(spec->body, &spec->finger, &job->index) != WR_OK) {
        wr_design_job_free(job);
        wr_error_set(error, "", "out of memory");
        return WR_NO_MEMORY;
    }
    job->candidates = candidates;
    job->why = calloc((size_t)job->plan->kept_count + 1, sizeof *job->why);
    if (!job->why) {
        wr_design_job_free(job);
        wr_error_set(error, "", "out of memory");
        return WR_NO_MEMORY;
    }
    why_point(spec, &job->why_edge, &job->why_t);
    uint64_t n = (uint64_t)spec->shard_count, i = (uint64_t)spec->shard_index;
    job->total = candidates > i ? (candidates - i + n - 1) / n : 0;
    *out = job;
    return WR_OK;
}

/* The combination numbered r in lexicographic order (0 <= r < C(n, k)):
 * at each place the smallest index whose count of completions does not
 * exceed what is left of r. */
static void unrank(uint64_t r, int k, int n, int *c)
{
    int next = 0;
    for (int place = 0; place < k; place++) {
        for (int v = next;; v++) {
            uint64_t completions = wr_design_candidates(n - v - 1, k - place - 1);
            if (r < completions) {
                c[place] = v;
                next = v + 1;
                break;
            }
            r -= completions;
        }
    }
}

/* The next combination in lexicographic order; false after the last. */
static bool next_combination(int *c, int k, int n)
{
    int i = k - 1;
    while (i >= 0 && c[i] == n - k + i)
        i--;
    if (i < 0)
        return false;
    c[i]++;
    for (int j = i + 1; j < k; j++)
        c[j] = c[j - 1] + 1;
    return true;
}

/* Into a list of at most `top`, best first. */
static void keep(wr_design *list, int *count, int top, const wr_design *d)
{
    int n = *count;
    if (n == top && !wr_design_before(d, &list[n - 1]))
        return;
    int i = n < top ? n : n - 1;
    while (i > 0 && wr_design_before(d, &list[i - 1])) {
        list[i] = list[i - 1];
        i--;
    }
    list[i] = *d;
    if (n < top)
        (*count)++;
}

/* Does a beat b on the Pareto figures: at least as good on each (margin
 * higher, error and force lower), better on one? */
static bool dominates(const wr_design *a, const wr_design *b)
{
    const double *x = a->pareto, *y = b->pareto;
    if (!(x[0] >= y[0] && x[1] <= y[1] && x[2] <= y[2]))
        return false;
    return x[0] > y[0] || x[1] < y[1] || x[2] < y[2];
}

/* Into the Pareto front of a list of at most `top`, best score first: d
 * unless a design of the list beats it, and the designs d beats out. */
static void keep_pareto(wr_design *list, int *count, int top, const wr_design *d)
{
    for (int i = 0; i < *count; i++)
        if (dominates(&list[i], d))
            return;
    int n = 0;
    for (int i = 0; i < *count; i++)
        if (!dominates(d, &list[i]))
            list[n++] = list[i];
    *count = n;
    keep(list, count, top, d);
}

/* Into a chunk's or the job's list, as the objective keeps designs. */
static void keep_design(const wr_design_spec *spec, wr_design *list, int *count,
                        const wr_design *d)
{
    if (spec->objective == WR_OBJECTIVE_PARETO)
        keep_pareto(list, count, spec->top, d);
    else
        keep(list, count, spec->top, d);
}

/* The score a candidate must beat to be kept: the top-th so far (none for
 * the Pareto front, where a lower margin may be kept for its other
 * figures). */
static double threshold_of(const wr_design_spec *spec, const wr_design *list, int count)
{
    if (spec->objective == WR_OBJECTIVE_PARETO)
        return -INFINITY;
    return count == spec->top ? list[count - 1].score : -INFINITY;
}

bool wr_design_job_claim(wr_design_job *job, uint64_t *first, uint64_t *count,
                         double *threshold)
{
    if (job->next >= job->candidates || job->failed)
        return false;
    uint64_t span = (uint64_t)WR_DESIGN_CHUNK * (uint64_t)job->spec.shard_count;
    *first = job->next;
    *count = job->candidates - job->next < span ? job->candidates - job->next : span;
    job->next += *count;
    job->outstanding++;
    *threshold = threshold_of(&job->spec, job->designs, job->design_count);
    return true;
}

void wr_design_job_cut(wr_design_job *job)
{
    job->candidates = job->next; /* nothing more to claim */
}

uint64_t wr_design_job_total(const wr_design_job *job) { return job->total; }

bool wr_design_job_claimable(const wr_design_job *job)
{
    return job->next < job->candidates && !job->failed;
}

void wr_design_chunk_release(wr_design_chunk *chunk)
{
    free(chunk->designs);
    free(chunk->why);
    memset(chunk, 0, sizeof *chunk);
}

wr_status wr_design_chunk_run(const wr_design_job *job, uint64_t first, uint64_t count,
                              double threshold, const wr_stop *stop, wr_lp_env *env,
                              wr_design_chunk *out, unsigned long *used)
{
    const wr_design_spec *spec = &job->spec;
    memset(out, 0, sizeof *out);
    out->designs = calloc((size_t)spec->top, sizeof *out->designs);
    out->why = calloc((size_t)job->plan->kept_count + 1, sizeof *out->why);
    if (!out->designs || !out->why) {
        wr_design_chunk_release(out);
        return WR_NO_MEMORY;
    }
    int combination[WR_MAX_FIXELS];
    if (spec->candidates)
        memcpy(combination, spec->candidates[first], sizeof combination);
    else
        unrank(first, spec->fixel_count, spec->site_count, combination);
    uint64_t n = (uint64_t)spec->shard_count, shard = (uint64_t)spec->shard_index;
    unsigned long spent = 0;
    wr_status status = WR_OK;
    int *seen = NULL;
    if (job->site_maps) {
        seen = malloc((size_t)job->symmetry_count * (size_t)spec->fixel_count * sizeof *seen);
        if (!seen) {
            wr_design_chunk_release(out);
            return WR_NO_MEMORY;
        }
    }
    for (uint64_t r = first; r < first + count; r++) {
        int copies = 1;
        if (r % n == shard && seen && !representative(job, r, combination, seen, &copies)) {
            out->counts.examined++;
            out->counts.symmetric++;
        } else if (r % n == shard) {
            if (wr_stop_requested(stop)) {
                status = WR_STOPPED;
                break;
            }
            /* The bound is the better of the job's when claimed and this
             * chunk's own: either only ever rises. */
            double bar = fmax(threshold, threshold_of(spec, out->designs, out->design_count));
            outcome result;
            double score = 0, pareto[3] = {0, 0, 0};
            int why = 0;
            status = score_candidate(job, combination, bar, stop, env, &result, &score, &spent,
                                     &why, pareto);
            if (status != WR_OK)
                break;
            out->counts.examined++;
            switch (result) {
            case OUTCOME_DEGENERATE: out->counts.degenerate++; break;
            case OUTCOME_UNPINNED: out->counts.unpinned++; break;
            case OUTCOME_NO_SEATING_PUSH:
                out->counts.no_seating_push++;
                out->why[why]++;
                break;
            case OUTCOME_SHARED_HOLE: out->counts.shared_hole++; break;
            case OUTCOME_BOUNDED: out->counts.bounded++; break;
            case OUTCOME_SCORED: {
                wr_design d;
                memset(&d, 0, sizeof d);
                d.candidate = r;
                memcpy(d.sites, combination, (size_t)spec->fixel_count * sizeof *combination);
                d.score = score;
                d.copies = copies;
                memcpy(d.pareto, pareto, sizeof d.pareto);
                keep_design(spec, out->designs, &out->design_count, &d);
                break;
            }
            }
        }
        if (r + 1 < first + count && spec->candidates)
            memcpy(combination, spec->candidates[r + 1], sizeof combination);
        else if (r + 1 < first + count)
            next_combination(combination, spec->fixel_count, spec->site_count);
    }
    free(seen);
    if (used)
        *used += spent;
    if (status != WR_OK)
        wr_design_chunk_release(out);
    return status;
}

void wr_design_job_merge(wr_design_job *job, const wr_design_chunk *chunk)
{
    assert(job->outstanding > 0);
    job->outstanding--;
    for (int i = 0; i < chunk->design_count; i++)
        keep_design(&job->spec, job->designs, &job->design_count, &chunk->designs[i]);
    job->counts.examined += chunk->counts.examined;
    job->counts.degenerate += chunk->counts.degenerate;
    job->counts.unpinned += chunk->counts.unpinned;
    job->counts.no_seating_push += chunk->counts.no_seating_push;
    job->counts.shared_hole += chunk->counts.shared_hole;
    job->counts.bounded += chunk->counts.bounded;
    job->counts.symmetric += chunk->counts.symmetric;
    for (int i = 0; i <= job->plan->kept_count; i++)
        job->why[i] += chunk->why[i];
}

void wr_design_job_abandon(wr_design_job *job)
{
    assert(job->outstanding > 0);
    job->outstanding--;
    job->failed = true;
}

/* One design's figures but its critical mu (which the sweep job finds),
 * placed into *fixture.  Reads the job, writes *d.  On supports its least
 * push on the plate alone (wr_design.h). */
static wr_status detail(const wr_design_job *job, wr_design *d, wr_fixture *fixture,
                        const wr_stop *stop, wr_lp_env *env, unsigned long *units)
{
    if (place(job, d->sites, fixture) != WR_OK)
        return WR_NO_MEMORY; /* it was placed once: only memory can fail */
    const wr_design_spec *spec = &job->spec;
    if (spec->supports)
        return spec->case_count > 0
                   ? plate_least_push(job, fixture, stop, env, &d->least_force, units)
                   : WR_OK;
    wr_error refused;
    /* A position tolerance a fixel's segment cannot hold: no robust region. */
    bool robust_ok = !spec->fixel_tolerance.given ||
                     wr_fixture_set_tolerance(fixture, &spec->fixel_tolerance, &refused) == WR_OK;
    wr_analysis *analysis;
    wr_status status = wr_analysis_new(fixture, &analysis);
    if (status != WR_OK)
        return status;
    wr_regions goal = {0}, both = {0}, arcs = {0};
    status = push_regions(job, analysis, WR_SET_GOAL, &goal);
    if (status == WR_OK)
        status = push_regions(job, analysis, WR_SET_BOTH, &both);
    if (status == WR_OK && spec->fixel_tolerance.given) {
        /* The both region's robust part, whose best push is then robust. */
        wr_regions robust = {0};
        wr_robust *rb = NULL;
        if (robust_ok)
            status = wr_robust_new(analysis, 0, &rb);
        if (status == WR_OK && robust_ok)
            status = wr_robust_regions(rb, WR_SET_BOTH, &both, false, NULL, &robust);
        wr_robust_free(rb);
        *units += 1000000;
        if (status == WR_OK) {
            wr_regions_release(&both);
            both = robust;
        }
    }
    if (status == WR_OK)
        status = wr_gravity_sweep(analysis, WR_SET_GOAL, &arcs);
    bool below;
    if (status == WR_OK)
        status = wr_best_push_find(analysis, &both, -INFINITY, NULL, &d->best_push, &below);
    if (status == WR_OK && spec->case_count > 0) {
        status = wr_least_force_find(analysis, WR_SET_BOTH, spec->loads, spec->case_count,
                                     &spec->finger, NULL, &d->least_force);
        *units += d->least_force.evaluations * (unsigned long)spec->case_count * 40;
    }
    if (status == WR_OK) {
        d->goal_length = regions_length(fixture, &goal);
        d->both_length = regions_length(fixture, &both);
        d->gravity_goal_deg = longest_arc(&arcs);
        int cones = wr_analysis_cone_count(analysis, WR_SET_GOAL) +
                    wr_analysis_cone_count(analysis, WR_SET_STRONG);
        *units += (unsigned long)cones *
                  (8UL * (unsigned long)wr_push_edge_count(fixture) + d->best_push.evaluations);
    }
    wr_regions_release(&goal);
    wr_regions_release(&both);
    wr_regions_release(&arcs);
    wr_analysis_free(analysis);
    return status;
}

wr_status wr_design_job_run(wr_design_job *job, unsigned long budget, unsigned long *used,
                            const wr_stop *stop, wr_lp_env *env, bool *done)
{
    *done = false;
    if (job->failed)
        return WR_NO_MEMORY;
    unsigned long spent = 0;
    wr_status status = WR_OK;
    const wr_design_spec *spec = &job->spec;
    /* The search, a chunk at a time. */
    uint64_t first, count;
    double threshold;
    while (status == WR_OK && (spent == 0 || spent < budget) &&
           wr_design_job_claim(job, &first, &count, &threshold)) {
        wr_design_chunk chunk;
        status = wr_design_chunk_run(job, first, count, threshold, stop, env, &chunk, &spent);
        if (status != WR_OK) {
            wr_design_job_abandon(job);
            break;
        }
        wr_design_job_merge(job, &chunk);
        wr_design_chunk_release(&chunk);
    }
    /* The designs' figures. */
    while (status == WR_OK && job->next >= job->candidates && job->outstanding == 0 &&
           job->detailing < job->design_count && (spent == 0 || spent < budget)) {
        if (wr_stop_requested(stop)) {
            status = WR_STOPPED;
            break;
        }
        wr_design *d = &job->designs[job->detailing];
        if (!job->sweep) {
            status = detail(job, d, &job->detail_fixture, stop, env, &spent);
            if (status != WR_OK)
                break;
            if (spec->supports) { /* no critical mu on the plate */
                job->detailing++;
                continue;
            }
            wr_sweep_range range = {0, WR_DESIGN_SWEEP_HIGH, 1};
            status = wr_sweeper_new(&job->detail_fixture, WR_SET_GOAL, &range, &job->sweeper);
            if (status == WR_OK)
                status = wr_sweep_job_push(job->sweeper, &spec->finger, &job->sweep);
            if (status == WR_OK && job->index)
                wr_sweep_job_use_index(job->sweep, job->index);
            continue;
        }
        bool finished = false;
        unsigned long sweep_used = 0;
        status = wr_sweep_job_run(job->sweep, budget > spent ? budget - spent : 1, &sweep_used,
                                  stop, &finished);
        spent += sweep_used;
        if (status == WR_OK && finished) {
            const wr_sweep_curve *curve = wr_sweep_job_curve(job->sweep);
            d->has_critical = curve->has_critical;
            d->critical_mu = curve->critical;
            wr_sweep_job_free(job->sweep);
            wr_sweeper_free(job->sweeper);
            job->sweep = NULL;
            job->sweeper = NULL;
            job->detailing++;
        }
    }
    if (used)
        *used += spent;
    if (status != WR_OK) {
        job->failed = true;
        return status;
    }
    *done = job->next >= job->candidates && job->outstanding == 0 &&
            job->detailing >= job->design_count;
    return WR_OK;
}

bool wr_design_job_searched(const wr_design_job *job)
{
    return !job->failed && job->next >= job->candidates && job->outstanding == 0;
}

int wr_design_job_figures_left(const wr_design_job *job)
{
    return wr_design_job_searched(job) ? job->design_count - job->detailing : 0;
}

wr_status wr_design_job_figure(const wr_design_job *job, int index, const wr_stop *stop,
                               wr_lp_env *env, unsigned long *used)
{
    /* Not job->detailing: merges change it while other designs' figures
     * are made. */
    assert(wr_design_job_searched(job) && index >= 0 && index < job->design_count);
    /* The design is written only here, by one thread: the cast keeps the
     * job's other readers' const. */
    wr_design *d = (wr_design *)&job->designs[index];
    wr_fixture fixture;
    unsigned long spent = 0;
    wr_status status = detail(job, d, &fixture, stop, env, &spent);
    if (job->spec.supports) { /* no critical mu on the plate */
        if (used)
            *used += spent;
        return status;
    }
    wr_sweeper *sweeper = NULL;
    wr_sweep_job *sweep = NULL;
    wr_sweep_range range = {0, WR_DESIGN_SWEEP_HIGH, 1};
    if (status == WR_OK)
        status = wr_sweeper_new(&fixture, WR_SET_GOAL, &range, &sweeper);
    if (status == WR_OK)
        status = wr_sweep_job_push(sweeper, &job->spec.finger, &sweep);
    if (status == WR_OK && job->index)
        wr_sweep_job_use_index(sweep, job->index);
    bool finished = false;
    if (status == WR_OK)
        status = wr_sweep_job_run(sweep, (unsigned long)-1, &spent, stop, &finished);
    if (status == WR_OK) {
        assert(finished);
        const wr_sweep_curve *curve = wr_sweep_job_curve(sweep);
        d->has_critical = curve->has_critical;
        d->critical_mu = curve->critical;
    }
    wr_sweep_job_free(sweep);
    wr_sweeper_free(sweeper);
    if (used)
        *used += spent;
    return status;
}

void wr_design_job_figure_merged(wr_design_job *job)
{
    assert(job->detailing < job->design_count && !job->sweep);
    job->detailing++;
}

void wr_design_job_progress(const wr_design_job *job, uint64_t *done, uint64_t *total,
                            bool *has_best, double *best)
{
    *done = job->counts.examined;
    *total = job->total;
    *has_best = job->design_count > 0;
    *best = *has_best ? job->designs[0].score : 0;
}

void wr_design_job_figures_progress(const wr_design_job *job, int *done, int *total)
{
    bool searched = job->next >= job->candidates && job->outstanding == 0;
    *done = searched ? job->detailing : 0;
    *total = searched ? job->design_count : 0;
}

const wr_design *wr_design_job_designs(const wr_design_job *job, int *count)
{
    *count = job->design_count;
    return job->designs;
}

const wr_design_counts *wr_design_job_counts(const wr_design_job *job) { return &job->counts; }

void wr_design_job_fixture(const wr_design_job *job, const wr_design *design, wr_fixture *out)
{
    wr_status status = place(job, design->sites, out);
    assert(status == WR_OK); /* it was placed before: the same checks pass */
    (void)status;
}

const uint64_t *wr_design_job_why(const wr_design_job *job, const wr_plan **plan, int *edge,
                                  double *t)
{
    *plan = job->plan;
    *edge = job->why_edge;
    *t = job->why_t;
    return job->why;
}

size_t wr_design_job_bytes(const wr_design_job *job)
{
    return sizeof *job + (size_t)job->spec.top * sizeof *job->designs +
           (job->index ? wr_push_index_bytes(job->index) : 0) +
           (job->site_fixels ? (size_t)job->spec.site_count *
                                   (sizeof *job->site_fixels + sizeof *job->site_ok)
                             : 0);
}

void wr_design_job_free(wr_design_job *job)
{
    if (!job)
        return;
    wr_sweep_job_free(job->sweep);
    wr_sweeper_free(job->sweeper);
    wr_plan_free(job->plan);
    wr_push_index_free(job->index);
    free(job->site_fixels);
    free(job->site_ok);
    free(job->site_maps);
    free(job->tuples);
    free(job->designs);
    free(job->why);
    free(job);
}
