/* wr_design.c -- fixture design: candidate sites, the best push by branch
 * and bound, and the search over candidates (wr_design.h). */
#include "wr_design.h"
#include "wr_internal.h"
#include "wr_outline.h"

#include <assert.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* ---- sites ------------------------------------------------------------------------- */

wr_status wr_site_new(const wr_fixture *body, const double at[2], const double *normal,
                      wr_site *out, wr_error *error)
{
    wr_fixel_spec fixel;
    memset(&fixel, 0, sizeof fixel);
    fixel.at[0] = at[0];
    fixel.at[1] = at[1];
    if (normal) {
        fixel.normal_given = true;
        fixel.normal[0] = normal[0];
        fixel.normal[1] = normal[1];
    }
    /* Friction does not place a fixel; any valid value does. */
    wr_friction_spec friction = {.given = true};
    wr_fixture placed;
    wr_status status = wr_fixture_place(body, &fixel, 1, &friction, &placed, error);
    if (status != WR_OK)
        return status;
    memcpy(out->at, placed.fixels[0].at, sizeof out->at);
    memcpy(out->normal, placed.fixels[0].normal, sizeof out->normal);
    return WR_OK;
}

static wr_status site_append(const wr_fixture *body, const double point[2], wr_site **sites,
                             int *count, int *capacity, wr_error *error)
{
    if (*count >= WR_DESIGN_MAX_SITES) {
        wr_error_set(error, "", "more than %d sites", WR_DESIGN_MAX_SITES);
        return WR_INVALID;
    }
    if (*count == *capacity) {
        int grown = *capacity ? 2 * *capacity : 64;
        wr_site *more = realloc(*sites, (size_t)grown * sizeof *more);
        if (!more) {
            wr_error_set(error, "", "out of memory");
            return WR_NO_MEMORY;
        }
        *sites = more;
        *capacity = grown;
    }
    /* The normal is derived as a fixel's there would be: the site is the
     * fixel fixture.put would make of the point. */
    wr_status status = wr_site_new(body, point, NULL, &(*sites)[*count], error);
    if (status == WR_OK)
        (*count)++;
    return status;
}

wr_status wr_sites_spaced(const wr_fixture *body, double spacing, wr_site **sites, int *count,
                          wr_error *error)
{
    if (!(spacing > 0) || !isfinite(spacing)) {
        wr_error_set(error, "", "must be a positive number, got %g", spacing);
        return WR_INVALID;
    }
    wr_site *list = *sites;
    int n = *count, capacity = *count;
    wr_status status = WR_OK;
    if (body->shape == WR_SHAPE_CIRCLE) {
        double circumference = 2 * WR_PI * body->radius;
        double steps = floor(circumference / spacing + 1e-9);
        if (steps > WR_DESIGN_MAX_SITES) {
            wr_error_set(error, "", "gives %.3g sites, more than %d", steps, WR_DESIGN_MAX_SITES);
            return WR_INVALID;
        }
        for (int i = 0; i < (int)steps && status == WR_OK; i++) {
            double angle = 2 * WR_PI * i / steps;
            double p[2] = {body->center[0] + body->radius * cos(angle),
                           body->center[1] + body->radius * sin(angle)};
            status = site_append(body, p, &list, &n, &capacity, error);
        }
    } else if (body->outline) {
        const wr_outline *o = body->outline;
        double total = 0;
        for (size_t l = 0; l < o->loop_count; l++)
            for (size_t s = 0; s < o->loops[l].segment_count; s++)
                total += floor(o->loops[l].segments[s].length / spacing + 1e-9);
        if (total > WR_DESIGN_MAX_SITES) {
            wr_error_set(error, "", "gives %.3g sites, more than %d", total, WR_DESIGN_MAX_SITES);
            return WR_INVALID;
        }
        for (size_t l = 0; l < o->loop_count && status == WR_OK; l++)
            for (size_t s = 0; s < o->loops[l].segment_count && status == WR_OK; s++) {
                double length = o->loops[l].segments[s].length;
                int steps = (int)floor(length / spacing + 1e-9);
                double first = (length - (steps - 1) * spacing) / 2;
                for (int i = 0; i < steps && status == WR_OK; i++) {
                    double p[2], normal[2];
                    wr_outline_boundary(o, l, s, (first + i * spacing) / length, p, normal);
                    status = site_append(body, p, &list, &n, &capacity, error);
                }
            }
    }
    if (status != WR_OK && n > *count) {
        /* Nothing appended after all: the caller's array keeps its items. */
        n = *count;
    }
    *sites = list;
    *count = n;
    return status;
}

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
    OUTCOME_BOUNDED
} outcome;

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
    bool failed;
    uint64_t total;            /* candidates of the shard */
    uint64_t candidates;       /* of all shards */
    uint64_t next;             /* the first candidate number not yet claimed */
    int outstanding;           /* chunks claimed, not yet merged */
    wr_design_counts counts;
    wr_design *designs;        /* spec.top, best first */
    int design_count;
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

static wr_status place(const wr_design_job *job, const int *sites, wr_fixture *out)
{
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

/* Score one candidate, giving up (OUTCOME_BOUNDED) once its score is
 * certainly below `threshold`.  *units: about the work done. */
static wr_status score_candidate(const wr_design_job *job, const int *sites, double threshold,
                                 outcome *result, double *score, unsigned long *units)
{
    const wr_design_spec *spec = &job->spec;
    wr_fixture fixture;
    *units += 100;
    if (place(job, sites, &fixture) != WR_OK) {
        *result = OUTCOME_DEGENERATE;
        return WR_OK;
    }
    if (!wr_fixture_pinned(&fixture)) {
        *result = OUTCOME_UNPINNED;
        return WR_OK;
    }
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
    status = wr_push_regions_finger(analysis, WR_SET_GOAL, &spec->finger, NULL, &goal);
    *units += (unsigned long)cones * (unsigned long)edges * 4;
    if (status == WR_OK && goal.count == 0)
        *result = OUTCOME_NO_SEATING_PUSH;
    else if (status == WR_OK && (spec->objective == WR_OBJECTIVE_GRAVITY ||
                                 (status = wr_analysis_complete(analysis)) == WR_OK)) {
        cones += wr_analysis_cone_count(analysis, WR_SET_STRONG);
        *units += (unsigned long)cones * 40;
        *result = OUTCOME_SCORED;
        if (spec->objective == WR_OBJECTIVE_GRAVITY) {
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
            status = wr_push_regions_finger(analysis, WR_SET_BOTH, &spec->finger, NULL, &both);
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

/* ---- the job --------------------------------------------------------------------------- */

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
    job->candidates = candidates;
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

/* The score a candidate must beat to be kept: the top-th so far. */
static double threshold_of(const wr_design *list, int count, int top)
{
    return count == top ? list[count - 1].score : -INFINITY;
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
    *threshold = threshold_of(job->designs, job->design_count, job->spec.top);
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
    memset(chunk, 0, sizeof *chunk);
}

wr_status wr_design_chunk_run(const wr_design_job *job, uint64_t first, uint64_t count,
                              double threshold, const wr_stop *stop, wr_design_chunk *out,
                              unsigned long *used)
{
    const wr_design_spec *spec = &job->spec;
    memset(out, 0, sizeof *out);
    out->designs = calloc((size_t)spec->top, sizeof *out->designs);
    if (!out->designs)
        return WR_NO_MEMORY;
    int combination[WR_MAX_FIXELS];
    if (spec->candidates)
        memcpy(combination, spec->candidates[first], sizeof combination);
    else
        unrank(first, spec->fixel_count, spec->site_count, combination);
    uint64_t n = (uint64_t)spec->shard_count, shard = (uint64_t)spec->shard_index;
    unsigned long spent = 0;
    wr_status status = WR_OK;
    for (uint64_t r = first; r < first + count; r++) {
        if (r % n == shard) {
            if (wr_stop_requested(stop)) {
                status = WR_STOPPED;
                break;
            }
            /* The bound is the better of the job's when claimed and this
             * chunk's own: either only ever rises. */
            double bar = fmax(threshold, threshold_of(out->designs, out->design_count, spec->top));
            outcome result;
            double score = 0;
            status = score_candidate(job, combination, bar, &result, &score, &spent);
            if (status != WR_OK)
                break;
            out->counts.examined++;
            switch (result) {
            case OUTCOME_DEGENERATE: out->counts.degenerate++; break;
            case OUTCOME_UNPINNED: out->counts.unpinned++; break;
            case OUTCOME_NO_SEATING_PUSH: out->counts.no_seating_push++; break;
            case OUTCOME_BOUNDED: out->counts.bounded++; break;
            case OUTCOME_SCORED: {
                wr_design d;
                memset(&d, 0, sizeof d);
                d.candidate = r;
                memcpy(d.sites, combination, (size_t)spec->fixel_count * sizeof *combination);
                d.score = score;
                keep(out->designs, &out->design_count, spec->top, &d);
                break;
            }
            }
        }
        if (r + 1 < first + count && spec->candidates)
            memcpy(combination, spec->candidates[r + 1], sizeof combination);
        else if (r + 1 < first + count)
            next_combination(combination, spec->fixel_count, spec->site_count);
    }
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
        keep(job->designs, &job->design_count, job->spec.top, &chunk->designs[i]);
    job->counts.examined += chunk->counts.examined;
    job->counts.degenerate += chunk->counts.degenerate;
    job->counts.unpinned += chunk->counts.unpinned;
    job->counts.no_seating_push += chunk->counts.no_seating_push;
    job->counts.bounded += chunk->counts.bounded;
}

void wr_design_job_abandon(wr_design_job *job)
{
    assert(job->outstanding > 0);
    job->outstanding--;
    job->failed = true;
}

/* One design's figures but its critical mu (which the sweep job finds). */
static wr_status detail(wr_design_job *job, wr_design *d, unsigned long *units)
{
    const wr_design_spec *spec = &job->spec;
    if (place(job, d->sites, &job->detail_fixture) != WR_OK)
        return WR_NO_MEMORY; /* it was placed once: only memory can fail */
    wr_fixture *fixture = &job->detail_fixture;
    wr_analysis *analysis;
    wr_status status = wr_analysis_new(fixture, &analysis);
    if (status != WR_OK)
        return status;
    wr_regions goal = {0}, both = {0}, arcs = {0};
    status = wr_push_regions_finger(analysis, WR_SET_GOAL, &spec->finger, NULL, &goal);
    if (status == WR_OK)
        status = wr_push_regions_finger(analysis, WR_SET_BOTH, &spec->finger, NULL, &both);
    if (status == WR_OK)
        status = wr_gravity_sweep(analysis, WR_SET_GOAL, &arcs);
    bool below;
    if (status == WR_OK)
        status = wr_best_push_find(analysis, &both, -INFINITY, NULL, &d->best_push, &below);
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
                            const wr_stop *stop, bool *done)
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
        status = wr_design_chunk_run(job, first, count, threshold, stop, &chunk, &spent);
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
            status = detail(job, d, &spent);
            if (status != WR_OK)
                break;
            wr_sweep_range range = {0, WR_DESIGN_SWEEP_HIGH, 1};
            status = wr_sweeper_new(&job->detail_fixture, WR_SET_GOAL, &range, &job->sweeper);
            if (status == WR_OK)
                status = wr_sweep_job_push(job->sweeper, &spec->finger, &job->sweep);
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

void wr_design_job_progress(const wr_design_job *job, uint64_t *done, uint64_t *total,
                            bool *has_best, double *best)
{
    *done = job->counts.examined;
    *total = job->total;
    *has_best = job->design_count > 0;
    *best = *has_best ? job->designs[0].score : 0;
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

size_t wr_design_job_bytes(const wr_design_job *job)
{
    return sizeof *job + (size_t)job->spec.top * sizeof *job->designs;
}

void wr_design_job_free(wr_design_job *job)
{
    if (!job)
        return;
    wr_sweep_job_free(job->sweep);
    wr_sweeper_free(job->sweeper);
    wr_plan_free(job->plan);
    free(job->designs);
    free(job);
}
