/* wr_sweep.c -- answers against one common friction coefficient: the roots
 * where they can change, then one decision per piece between roots
 * (wr_sweep.h says why that misses nothing). */
#include "wr_sweep.h"
#include "wr_finger.h"
#include "wr_internal.h"
#include "wr_outline.h"

#include <assert.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* A wrench this close to a plane, or this far on the wrong side of a
 * generator, still counts as on the face: a root kept for nothing costs
 * one more piece, a root dropped could lose an interval. */
#define FACE_SLACK 1e-7
/* Roots closer than this (relative to the range's scale) are one. */
#define ROOT_MERGE 1e-12
/* Points of a curve between roots: a gap at most 1/GRID of the range. */
#define GRID 64
/* A finger with friction: steps of the sampled sweep. */
#define FRICTION_STEPS 256

/* A generator as a function of mu: base + mu * slope (scaled space). */
typedef struct affine {
    double base[3], slope[3];
} affine;

/* The plane of two generators: normal(mu) = n[0] + mu n[1] + mu^2 n[2]. */
typedef struct plane {
    int a, b;              /* family members, a < b */
    double n[3][3];
    int cone_first, cone_count; /* into sweeper->plane_cones */
} plane;

/* A growing array of doubles. */
typedef struct values {
    int count, capacity;
    double *items;
    bool failed;
} values;

struct wr_sweeper {
    const wr_fixture *fixture;
    wr_set set;
    wr_sweep_range range;
    int family_count;
    affine *family;
    int cone_count;
    int *cone_first;       /* cone i's members: members[cone_first[i] ..
                              cone_first[i + 1]) */
    int *members;
    int plane_count;
    plane *planes;
    int *plane_cones;
    int analysis_cones; /* the cones each analysis builds */
    values structure;   /* where a cone's faces change (settled) */
    /* What every analysis at one mu shares: plan, modes, acceleration
     * generators (G_strong's only when the set needs them). */
    wr_analysis_frame *frame;
};

/* ---- small things ------------------------------------------------------------------ */

void wr_intervals_release(wr_intervals *intervals)
{
    free(intervals->items);
    memset(intervals, 0, sizeof *intervals);
}

bool wr_intervals_append(wr_intervals *out, double lo, double hi)
{
    if (out->count > 0 && out->items[out->count - 1][1] == lo) {
        out->items[out->count - 1][1] = hi;
        return true;
    }
    if (out->count == out->capacity) {
        int capacity = out->capacity ? 2 * out->capacity : 8;
        double (*items)[2] = realloc(out->items, sizeof *items * (size_t)capacity);
        if (!items)
            return false;
        out->items = items;
        out->capacity = capacity;
    }
    out->items[out->count][0] = lo;
    out->items[out->count++][1] = hi;
    return true;
}

void wr_sweep_curve_release(wr_sweep_curve *curve)
{
    wr_intervals_release(&curve->intervals);
    free(curve->points);
    memset(curve, 0, sizeof *curve);
}

static bool add_interval(wr_intervals *list, double lo, double hi)
{
    if (list->count > 0 && lo <= list->items[list->count - 1][1]) {
        /* Touching the last one: one interval. */
        if (hi > list->items[list->count - 1][1])
            list->items[list->count - 1][1] = hi;
        return true;
    }
    if (list->count == list->capacity) {
        int capacity = list->capacity ? 2 * list->capacity : 8;
        double (*items)[2] = realloc(list->items, (size_t)capacity * sizeof *items);
        if (!items)
            return false;
        list->items = items;
        list->capacity = capacity;
    }
    list->items[list->count][0] = lo;
    list->items[list->count][1] = hi;
    list->count++;
    return true;
}

static void add_value(values *v, double x)
{
    if (v->failed)
        return;
    if (v->count == v->capacity) {
        int capacity = v->capacity ? 2 * v->capacity : 64;
        double *items = realloc(v->items, (size_t)capacity * sizeof *items);
        if (!items) {
            v->failed = true;
            return;
        }
        v->items = items;
        v->capacity = capacity;
    }
    v->items[v->count++] = x;
}

static int compare_doubles(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* Sort, keep [low, high], merge roots within ROOT_MERGE of each other, and
 * make sure both ends are there. */
static void settle(values *v, const wr_sweep_range *range)
{
    add_value(v, range->low);
    add_value(v, range->high);
    if (v->failed)
        return;
    qsort(v->items, (size_t)v->count, sizeof *v->items, compare_doubles);
    double merge = ROOT_MERGE * fmax(1, range->high);
    int n = 0;
    for (int i = 0; i < v->count; i++) {
        double x = v->items[i];
        if (x < range->low || x > range->high)
            continue;
        if (n > 0 && x - v->items[n - 1] <= merge)
            continue;
        v->items[n++] = x;
    }
    /* The top of the range is the last point even if a root merged it. */
    if (n > 0 && v->items[n - 1] != range->high) {
        if (range->high - v->items[n - 1] <= merge && n > 1)
            v->items[n - 1] = range->high;
        else
            v->items[n++] = range->high;
    }
    v->count = n;
}

void wr_fixture_at_friction(const wr_fixture *fixture, double mu, double ratio, wr_fixture *out)
{
    *out = *fixture;
    for (int i = 0; i < out->fixel_count; i++) {
        wr_fixel *fixel = &out->fixels[i];
        fixel->mu_static = fixel->mu_static_min = mu;
        fixel->mu_kinetic = fixel->mu_kinetic_min = ratio * mu;
    }
}

static void affine_at(const affine *g, double mu, double out[3])
{
    for (int k = 0; k < 3; k++)
        out[k] = g->base[k] + mu * g->slope[k];
}

/* ---- real roots of a polynomial in an interval ------------------------------------ */

#define MAX_DEGREE 4

static double poly_value(const double *c, int degree, double x)
{
    double v = c[degree];
    for (int i = degree - 1; i >= 0; i--)
        v = v * x + c[i];
    return v;
}

/* Is |p| above `margin` on all of [lo, hi], by the Bernstein coefficients
 * of p on the interval (p lies between the smallest and the largest)?
 * Most of a sweep's polynomials have no root in the range: this settles
 * them without their derivatives' roots.  The margin is far above the
 * rounding of the coefficients and of poly_roots' own evaluations, so
 * where this says yes poly_roots would find no root, nor a touch. */
static bool clear_of_zero(const double *c, int degree, double lo, double hi, double margin)
{
    /* p(lo + w t) = sum e_i (w t)^i: the Taylor shift to lo. */
    double e[MAX_DEGREE + 1];
    memcpy(e, c, (size_t)(degree + 1) * sizeof *e);
    for (int i = 0; i < degree; i++)
        for (int j = degree - 1; j >= i; j--)
            e[j] += lo * e[j + 1];
    double w = hi - lo, power = 1;
    for (int i = 0; i <= degree; i++, power *= w)
        e[i] *= power;
    /* b_k = sum_{i <= k} C(k, i) / C(n, i) e_i. */
    static const double binomial[MAX_DEGREE + 1][MAX_DEGREE + 1] = {
        {1, 0, 0, 0, 0}, {1, 1, 0, 0, 0}, {1, 2, 1, 0, 0}, {1, 3, 3, 1, 0}, {1, 4, 6, 4, 1}};
    bool above = true, below = true;
    for (int k = 0; k <= degree && (above || below); k++) {
        double b = 0;
        for (int i = 0; i <= k; i++)
            b += binomial[k][i] / binomial[degree][i] * e[i];
        above &= b > margin;
        below &= b < -margin;
    }
    return above || below;
}

/* The root of a polynomial that changes sign on [lo, hi], bisected until
 * the interval cannot shrink. */
static double bisect(const double *c, int degree, double lo, double hi, double value_lo)
{
    for (int i = 0; i < 200; i++) {
        double mid = lo + (hi - lo) / 2;
        if (mid <= lo || mid >= hi)
            break;
        double v = poly_value(c, degree, mid);
        if (v == 0)
            return mid;
        if ((v < 0) == (value_lo < 0)) {
            lo = mid;
            value_lo = v;
        } else {
            hi = mid;
        }
    }
    return lo + (hi - lo) / 2;
}

/* Every real root of c[0] + c[1] x + ... + c[degree] x^degree in [lo, hi]
 * into roots (at most degree + 1 of them: a touching root may come with
 * its neighbours).  Its monotone pieces lie between the roots of its
 * derivative, found the same way, so two roots however close are both
 * found.  A root where the polynomial only touches zero (to within
 * rounding of its size) is kept too.  -1 when the polynomial is zero on
 * the whole interval, to rounding. */
static int poly_roots(const double *coefficients, int degree, double lo, double hi,
                      double *roots)
{
    double reach = fabs(lo) > fabs(hi) ? fabs(lo) : fabs(hi);
    reach = reach > 1 ? reach : 1;
    double size = 0, power[MAX_DEGREE + 1];
    for (int i = 0; i <= degree; i++) {
        power[i] = i ? power[i - 1] * reach : 1; /* reach^i, as a product */
        size += fabs(coefficients[i]) * power[i];
    }
    if (size == 0 || !isfinite(size))
        return size == 0 ? -1 : 0;
    if (degree >= 2 && clear_of_zero(coefficients, degree, lo, hi, 1e-11 * size))
        return 0;
    /* Terms that cannot matter on the interval are dropped: the degree
     * the polynomial really has there. */
    double c[MAX_DEGREE + 1];
    memcpy(c, coefficients, (size_t)(degree + 1) * sizeof *c);
    while (degree > 0 && fabs(c[degree]) * power[degree] <= 1e-15 * size)
        degree--;
    double zero = 1e-13 * size;
    if (degree == 0)
        return fabs(c[0]) <= zero ? -1 : 0;
    if (degree == 1) {
        double x = -c[0] / c[1];
        if (x >= lo && x <= hi) {
            roots[0] = x;
            return 1;
        }
        return 0;
    }
    double derivative[MAX_DEGREE] = {0}, critical[MAX_DEGREE + 2];
    for (int i = 1; i <= degree; i++)
        derivative[i - 1] = i * c[i];
    int n = poly_roots(derivative, degree - 1, lo, hi, critical + 1);
    if (n < 0)
        n = 0; /* a constant derivative on the interval: none */
    critical[0] = lo;
    critical[n + 1] = hi;
    int found = 0;
    double previous = poly_value(c, degree, lo);
    if (previous == 0)
        roots[found++] = lo;
    for (int i = 1; i <= n + 1; i++) {
        double x = critical[i];
        double v = poly_value(c, degree, x);
        if (v != 0 && previous != 0 && (v < 0) != (previous < 0))
            roots[found++] = bisect(c, degree, critical[i - 1], x, previous);
        else if (i <= n && fabs(v) <= zero)
            roots[found++] = x; /* touches zero at an extremum */
        if (v == 0 && found <= degree && (found == 0 || roots[found - 1] != x))
            roots[found++] = x;
        previous = v;
        if (found > degree)
            break;
    }
    return found;
}

/* ---- the family of generators and the planes of faces ----------------------------- */

static int family_add(wr_sweeper *s, int *capacity, const affine *g)
{
    for (int i = 0; i < s->family_count; i++) {
        const affine *h = &s->family[i];
        double d = 0;
        for (int k = 0; k < 3; k++)
            d = fmax(d, fmax(fabs(h->base[k] - g->base[k]), fabs(h->slope[k] - g->slope[k])));
        if (d <= 1e-12)
            return i;
    }
    if (s->family_count == *capacity) {
        int grown = *capacity ? 2 * *capacity : 32;
        affine *family = realloc(s->family, (size_t)grown * sizeof *family);
        if (!family)
            return -1;
        s->family = family;
        *capacity = grown;
    }
    s->family[s->family_count] = *g;
    return s->family_count++;
}

typedef struct pair {
    int a, b, cone;
} pair;

static int compare_pairs(const void *x, const void *y)
{
    const pair *p = x, *q = y;
    if (p->a != q->a)
        return (p->a > q->a) - (p->a < q->a);
    if (p->b != q->b)
        return (p->b > q->b) - (p->b < q->b);
    return (p->cone > q->cone) - (p->cone < q->cone);
}

/* The cones of the set at mu = 1, read back as affine generators: an
 * acceleration generator (origin fixel -1) does not depend on mu; a
 * friction edge -(W_n + r W_t) / |.| with r = c mu becomes
 * -(W_n + c mu W_t) (its length only scales it: planes and sides stay). */
static wr_status build_family(wr_sweeper *s)
{
    wr_fixture at_one;
    wr_fixture_at_friction(s->fixture, 1, s->range.kinetic_ratio, &at_one);
    if (wr_analysis_frame_new(s->fixture, s->set != WR_SET_GOAL, &s->frame) != WR_OK)
        return WR_NO_MEMORY;
    wr_analysis *analysis;
    if (wr_analysis_frame_at(s->frame, &at_one, s->set != WR_SET_GOAL, &analysis) != WR_OK)
        return WR_NO_MEMORY;
    wr_status status = WR_NO_MEMORY;
    int sets[2], set_count = 0;
    if (s->set != WR_SET_STRONG)
        sets[set_count++] = WR_SET_GOAL;
    if (s->set != WR_SET_GOAL)
        sets[set_count++] = WR_SET_STRONG;
    int total = 0, generators = 0;
    s->analysis_cones = wr_analysis_cone_count(analysis, WR_SET_GOAL) +
                        (s->set != WR_SET_GOAL ? wr_analysis_cone_count(analysis, WR_SET_STRONG) : 0);
    for (int i = 0; i < set_count; i++) {
        int n = wr_analysis_cone_count(analysis, (wr_set)sets[i]);
        total += n;
        for (int j = 0; j < n; j++)
            generators += wr_analysis_cone(analysis, (wr_set)sets[i], j)->generator_count;
    }
    int capacity = 0, pair_count = 0;
    pair *pairs = NULL;
    s->cone_first = malloc((size_t)(total + 1) * sizeof *s->cone_first);
    s->members = malloc((size_t)(generators + 1) * sizeof *s->members);
    if (!s->cone_first || !s->members)
        goto done;
    int member_count = 0;
    s->cone_count = 0;
    for (int i = 0; i < set_count; i++) {
        for (int j = 0; j < wr_analysis_cone_count(analysis, (wr_set)sets[i]); j++) {
            const wr_cone *cone = wr_analysis_cone(analysis, (wr_set)sets[i], j);
            if (cone->empty)
                continue; /* empty at every mu: emptiness is kinematic */
            int first = member_count;
            for (int g = 0; g < cone->generator_count; g++) {
                const wr_generator_origin *o = &cone->origins[g];
                affine a;
                if (o->fixel < 0) {
                    wr_copy3(cone->generators[g], a.base);
                    memset(a.slope, 0, sizeof a.slope);
                } else {
                    const wr_fixel *fixel = &s->fixture->fixels[o->fixel];
                    double c = o->tangent_force / o->normal_force; /* at mu = 1 */
                    for (int k = 0; k < 3; k++) {
                        a.base[k] = -fixel->normal_wrench[k];
                        a.slope[k] = -c * fixel->tangent_wrench[k];
                    }
                }
                int index = family_add(s, &capacity, &a);
                if (index < 0)
                    goto done;
                bool seen = false;
                for (int m = first; m < member_count && !seen; m++)
                    seen = s->members[m] == index;
                if (!seen)
                    s->members[member_count++] = index;
            }
            s->cone_first[s->cone_count++] = first;
        }
    }
    s->cone_first[s->cone_count] = member_count;

    /* Every pair of members of a cone spans a plane that may hold a face. */
    for (int c = 0; c < s->cone_count; c++)
        for (int i = s->cone_first[c]; i < s->cone_first[c + 1]; i++)
            for (int j = i + 1; j < s->cone_first[c + 1]; j++)
                pair_count++;
    pairs = malloc((size_t)(pair_count + 1) * sizeof *pairs);
    s->plane_cones = malloc((size_t)(pair_count + 1) * sizeof *s->plane_cones);
    s->planes = malloc((size_t)(pair_count + 1) * sizeof *s->planes);
    if (!pairs || !s->plane_cones || !s->planes)
        goto done;
    int n = 0;
    for (int c = 0; c < s->cone_count; c++)
        for (int i = s->cone_first[c]; i < s->cone_first[c + 1]; i++)
            for (int j = i + 1; j < s->cone_first[c + 1]; j++) {
                int a = s->members[i], b = s->members[j];
                pairs[n++] = (pair){a < b ? a : b, a < b ? b : a, c};
            }
    qsort(pairs, (size_t)n, sizeof *pairs, compare_pairs);
    s->plane_count = 0;
    for (int i = 0; i < n; i++) {
        s->plane_cones[i] = pairs[i].cone;
        if (i > 0 && pairs[i].a == pairs[i - 1].a && pairs[i].b == pairs[i - 1].b) {
            s->planes[s->plane_count - 1].cone_count++;
            continue;
        }
        plane *p = &s->planes[s->plane_count++];
        p->a = pairs[i].a;
        p->b = pairs[i].b;
        p->cone_first = i;
        p->cone_count = 1;
        const affine *ga = &s->family[p->a], *gb = &s->family[p->b];
        double x[3], y[3];
        wr_cross3(ga->base, gb->base, p->n[0]);
        wr_cross3(ga->base, gb->slope, x);
        wr_cross3(ga->slope, gb->base, y);
        for (int k = 0; k < 3; k++)
            p->n[1][k] = x[k] + y[k];
        wr_cross3(ga->slope, gb->slope, p->n[2]);
    }
    status = WR_OK;
done:
    free(pairs);
    wr_analysis_free(analysis);
    return status;
}

static wr_status structure_roots(wr_sweeper *s);

wr_status wr_sweeper_new(const wr_fixture *fixture, wr_set set, const wr_sweep_range *range,
                         wr_sweeper **out)
{
    *out = NULL;
    if (!(range->low >= 0) || !(range->high > range->low) || !(range->high <= WR_MAX_FRICTION) ||
        !(range->kinetic_ratio > 0) || !(range->kinetic_ratio <= 1))
        return WR_INVALID;
    wr_sweeper *s = calloc(1, sizeof *s);
    if (!s)
        return WR_NO_MEMORY;
    s->fixture = fixture;
    s->set = set;
    s->range = *range;
    if (build_family(s) != WR_OK || structure_roots(s) != WR_OK) {
        wr_sweeper_free(s);
        return WR_NO_MEMORY;
    }
    *out = s;
    return WR_OK;
}

void wr_sweeper_free(wr_sweeper *s)
{
    if (!s)
        return;
    free(s->family);
    free(s->cone_first);
    free(s->members);
    free(s->planes);
    free(s->plane_cones);
    free(s->structure.items);
    wr_analysis_frame_free(s->frame);
    free(s);
}

/* ---- is a root real? -------------------------------------------------------------- */

/* At mu, does the scaled wrench h (which lies in plane p, to rounding) lie
 * on the part of it between the plane's two generators, and does the
 * plane support one of its cones (every other generator on one side)?
 * Only then can h be on a face there.  Degenerate planes say yes. */
static bool on_face(const wr_sweeper *s, const plane *p, const double h[3], double mu)
{
    double ga[3], gb[3], n[3], x[3], unit_h[3];
    affine_at(&s->family[p->a], mu, ga);
    affine_at(&s->family[p->b], mu, gb);
    if (wr_normalize3(ga) == 0 || wr_normalize3(gb) == 0)
        return true;
    wr_copy3(h, unit_h);
    if (wr_normalize3(unit_h) == 0)
        return true;
    wr_cross3(ga, gb, n);
    double sine = wr_normalize3(n);
    if (sine <= 1e-9)
        return true;
    /* h = alpha ga + beta gb: alpha ~ (h x gb) . n, beta ~ (ga x h) . n. */
    wr_cross3(unit_h, gb, x);
    if (wr_dot3(x, n) < -FACE_SLACK * sine)
        return false;
    wr_cross3(ga, unit_h, x);
    if (wr_dot3(x, n) < -FACE_SLACK * sine)
        return false;
    for (int i = 0; i < p->cone_count; i++) {
        int c = s->plane_cones[p->cone_first + i];
        double lowest = 0, highest = 0;
        for (int m = s->cone_first[c]; m < s->cone_first[c + 1]; m++) {
            double g[3];
            affine_at(&s->family[s->members[m]], mu, g);
            if (wr_normalize3(g) == 0)
                continue;
            double side = wr_dot3(n, g);
            lowest = fmin(lowest, side);
            highest = fmax(highest, side);
        }
        if (highest <= FACE_SLACK || lowest >= -FACE_SLACK)
            return true;
    }
    return false;
}

/* det(a, b, c) of three 3-vectors. */
static double det3(const double a[3], const double b[3], const double c[3])
{
    double x[3];
    wr_cross3(b, c, x);
    return wr_dot3(a, x);
}

/* Where the faces of a cone change: three of its generators become
 * coplanar (det(g_a, g_b, g_c)(mu) = 0, a cubic) in a plane that supports
 * the cone.  A face can appear or vanish there without any wrench crossing
 * a face -- a cone turning into a half-space or into all of space swallows
 * the wrenches beyond its vanishing face -- so these roots are every
 * sweep's roots too. */
static wr_status structure_roots(wr_sweeper *s)
{
    const wr_sweep_range *r = &s->range;
    for (int c = 0; c < s->cone_count; c++) {
        int first = s->cone_first[c], last = s->cone_first[c + 1];
        for (int i = first; i < last; i++)
            for (int j = i + 1; j < last; j++)
                for (int l = j + 1; l < last; l++) {
                    const affine *g[3] = {&s->family[s->members[i]], &s->family[s->members[j]],
                                          &s->family[s->members[l]]};
                    bool moves = false;
                    for (int m = 0; m < 3; m++)
                        moves |= g[m]->slope[0] != 0 || g[m]->slope[1] != 0 ||
                                 g[m]->slope[2] != 0;
                    if (!moves)
                        continue; /* a constant determinant: no event */
                    const double *A0 = g[0]->base, *A1 = g[0]->slope, *B0 = g[1]->base,
                                 *B1 = g[1]->slope, *C0 = g[2]->base, *C1 = g[2]->slope;
                    double coefficients[4] = {
                        det3(A0, B0, C0),
                        det3(A1, B0, C0) + det3(A0, B1, C0) + det3(A0, B0, C1),
                        det3(A1, B1, C0) + det3(A1, B0, C1) + det3(A0, B1, C1),
                        det3(A1, B1, C1)};
                    double roots[MAX_DEGREE + 2];
                    int found = poly_roots(coefficients, 3, r->low, r->high, roots);
                    for (int k = 0; k < found; k++) {
                        double mu = roots[k], v[3][3], n[3], best = 0;
                        for (int m = 0; m < 3; m++) {
                            affine_at(g[m], mu, v[m]);
                            wr_normalize3(v[m]);
                        }
                        /* The plane: of the two that span it best. */
                        for (int m = 0; m < 3; m++) {
                            double x[3];
                            wr_cross3(v[m], v[(m + 1) % 3], x);
                            double length = wr_norm3(x);
                            if (length > best) {
                                best = length;
                                for (int q = 0; q < 3; q++)
                                    n[q] = x[q] / length;
                            }
                        }
                        if (best <= 1e-9) {
                            add_value(&s->structure, mu); /* degenerate: keep */
                            continue;
                        }
                        double lowest = 0, highest = 0;
                        for (int m = first; m < last; m++) {
                            double w[3];
                            affine_at(&s->family[s->members[m]], mu, w);
                            if (wr_normalize3(w) == 0)
                                continue;
                            double side = wr_dot3(n, w);
                            lowest = fmin(lowest, side);
                            highest = fmax(highest, side);
                        }
                        if (highest <= FACE_SLACK || lowest >= -FACE_SLACK)
                            add_value(&s->structure, mu);
                    }
                }
    }
    return s->structure.failed ? WR_NO_MEMORY : WR_OK;
}

/* Where a fixed scaled wrench h meets a face: roots of h . n(mu) for every
 * plane, kept when on the face. */
static void fixed_roots(const wr_sweeper *s, const double h[3], values *out)
{
    const wr_sweep_range *r = &s->range;
    for (int i = 0; i < s->plane_count; i++) {
        const plane *p = &s->planes[i];
        double c[3] = {wr_dot3(h, p->n[0]), wr_dot3(h, p->n[1]), wr_dot3(h, p->n[2])};
        double roots[MAX_DEGREE + 2];
        int found = poly_roots(c, 2, r->low, r->high, roots);
        if (found < 0) {
            /* h lies in the plane at every mu: it can still meet the face
             * where a generator turns through it, h x g(mu) = 0. */
            int ends[2] = {p->a, p->b};
            for (int e = 0; e < 2; e++) {
                const affine *g = &s->family[ends[e]];
                double u[3], v[3];
                wr_cross3(h, g->base, u);
                wr_cross3(h, g->slope, v);
                double vv = wr_dot3(v, v);
                if (vv == 0)
                    continue;
                double mu = -wr_dot3(u, v) / vv;
                double residual[3];
                for (int k = 0; k < 3; k++)
                    residual[k] = u[k] + mu * v[k];
                if (wr_norm3(residual) <= 1e-9 * (wr_norm3(u) + fabs(mu) * sqrt(vv)))
                    add_value(out, mu);
            }
            continue;
        }
        for (int j = 0; j < found; j++)
            if (on_face(s, p, h, roots[j]))
                add_value(out, roots[j]);
    }
}

/* ---- deciding a piece ------------------------------------------------------------- */

typedef enum what {
    WHAT_WRENCH,
    WHAT_PUSH,
    WHAT_GRAVITY
} what;

typedef enum phase {
    PHASE_ROOTS,   /* the roots, an edge's plane row at a time */
    PHASE_DECIDE,  /* one piece between roots at a time */
    PHASE_SAMPLED, /* a finger with friction: a step of mu, or a bisection */
    PHASE_CURVE,   /* one point of the curve at a time */
    PHASE_DONE
} phase;

struct wr_sweep_job {
    const wr_sweeper *sweeper;
    what what;
    double wrench[3];          /* WHAT_WRENCH: physical */
    wr_finger finger;          /* WHAT_PUSH */
    const wr_push_index *push_index; /* WHAT_PUSH: NULL, or the regions' index */
    const wr_stop *stop;       /* of the current run */
    phase phase;
    /* PHASE_ROOTS: the edge (gravity: one circle), its frame once set up
     * (row >= 0), the next plane row, each plane's alpha and beta. */
    int edge, edge_count, row;
    wr_edge_frame frame;
    double (*alpha)[3], (*beta)[3];
    double *cut_from, *cut_to; /* where in mu each plane may cut the edge (edge_cut_span) */
    values roots;
    /* PHASE_DECIDE, PHASE_CURVE: the next piece or point; for G_goal
     * (decide_shrinking) the pieces known non-empty, [0, full_below), the
     * first known empty, empty_at (-1 before the bisection), and the mu
     * beyond which the answer is empty (+inf: none). */
    int index;
    int full_below, empty_at;
    double empty_from;
    values points;
    /* PHASE_SAMPLED: the step of mu, the emptiness before it, where the
     * current interval started, and a change being bisected in [lo, hi]. */
    int step;
    bool previous, bisecting;
    double start, lo, hi;
    wr_intervals intervals;    /* a wrench's answer */
    wr_sweep_curve curve;      /* a region's */
    unsigned long evaluation_cost, row_cost;
};

/* The answer at mu for `set` (the sweeper's, or G_goal: wr_sweep.c's
 * decide_shrinking): for a wrench 1 inside, 0 not; for a region its total
 * length.  -1 with *status set on failure. */
static double answer_in(const wr_sweep_job *job, double mu, wr_set set, wr_status *status)
{
    const wr_sweeper *s = job->sweeper;
    wr_fixture at;
    wr_fixture_at_friction(s->fixture, mu, s->range.kinetic_ratio, &at);
    wr_analysis *analysis;
    *status = wr_analysis_frame_at(s->frame, &at, set != WR_SET_GOAL, &analysis);
    if (*status != WR_OK)
        return -1;
    double result = 0;
    if (job->what == WHAT_WRENCH) {
        wr_answer answer;
        *status = wr_classify(analysis, job->wrench, set, WR_DEFAULT_TOLERANCE, &answer);
        result = answer.verdict == WR_VERDICT_INSIDE;
    } else {
        wr_regions regions;
        if (job->what == WHAT_PUSH)
            *status = job->push_index
                          ? wr_push_regions_indexed(analysis, set, job->push_index, job->stop,
                                                    &regions)
                          : wr_push_regions_finger(analysis, set, &job->finger, job->stop,
                                                   &regions);
        else
            *status = wr_gravity_sweep(analysis, set, &regions);
        for (int i = 0; *status == WR_OK && i < regions.count; i++)
            result += job->what == WHAT_PUSH ? wr_region_length(&at, &regions.items[i])
                                             : regions.items[i].t1 - regions.items[i].t0;
        /* An empty region has length 0; a region has more. */
        if (*status == WR_OK && regions.count > 0 && !(result > 0))
            result = 0;
        wr_regions_release(&regions);
    }
    wr_analysis_free(analysis);
    return *status == WR_OK ? result : -1;
}

static double answer_at(const wr_sweep_job *job, double mu, wr_status *status)
{
    return answer_in(job, mu, job->sweeper->set, status);
}

/* ---- push and gravity: where two planes meet the edge at one point ---------------- */

/* A plane cuts an edge where its two coordinates on the edge meet
 * (wr_internal.h's frames): a straight edge c1 + t c2 where alpha + t beta
 * = 0, an arc (sin phi / s) c1 + cos phi c2 where (tan phi / s) alpha +
 * beta = 0 (cos phi > 0 on an arc below a half circle), with alpha = c1 .
 * n(mu), beta = c2 . n(mu).  Two planes' roots on the edge are kept only
 * where t is within 1e-9 of [0, 1] or phi of [-a, a] (edge_row); this much
 * wider slack covers that and every rounding of a root. */
#define CUT_SLACK 1e-6

/* The smallest interval [*from, *to] of the range holding every mu at
 * which the plane's cut lies within the slack of the edge: where A(mu) and
 * B(mu), the values of the form that vanishes at the cut (affine in the
 * edge's parameter) at the slack's two ends, do not have one strict sign.  Their
 * sign changes only at their roots, so a test at the middle of each piece
 * between them decides the piece.  *from > *to: the plane never cuts the
 * edge.  The whole range when A or B vanishes throughout.  Widened by far
 * more than a root's rounding. */
static void cut_span(const double A[3], const double B[3], const wr_sweep_range *r,
                     double *from, double *to)
{
    double points[2 * (MAX_DEGREE + 2) + 2];
    double widen = 1e-9 * fmax(1, r->high);
    int n = 0, fa = poly_roots(A, 2, r->low, r->high, points);
    int fb = fa < 0 ? -1 : poly_roots(B, 2, r->low, r->high, points + fa);
    if (fa < 0 || fb < 0) {
        *from = r->low;
        *to = r->high;
        return;
    }
    n = fa + fb;
    *from = INFINITY;
    *to = -INFINITY;
    for (int i = 0; i < n; i++) { /* the roots cut at an end of the slack */
        *from = fmin(*from, points[i]);
        *to = fmax(*to, points[i]);
    }
    points[n++] = r->low;
    points[n++] = r->high;
    for (int i = 1; i < n; i++) /* insertion sort: at most six */
        for (int j = i; j > 0 && points[j] < points[j - 1]; j--) {
            double t = points[j];
            points[j] = points[j - 1];
            points[j - 1] = t;
        }
    for (int i = 0; i + 1 < n; i++) {
        double mid = points[i] + (points[i + 1] - points[i]) / 2;
        if (poly_value(A, 2, mid) * poly_value(B, 2, mid) <= 0) {
            *from = fmin(*from, points[i]);
            *to = fmax(*to, points[i + 1]);
        }
    }
    if (*from <= *to) {
        *from -= widen;
        *to += widen;
    }
}

/* cut_span for the job's current edge and plane i: a line's form at t =
 * -CUT_SLACK and 1 + CUT_SLACK; an arc's (in u = tan phi) at phi = -+(a +
 * CUT_SLACK); the whole range on a circle, or an arc too near a half
 * circle for tan. */
static void edge_cut_span(const wr_sweep_job *job, int i, double *from, double *to)
{
    const wr_sweep_range *r = &job->sweeper->range;
    const wr_edge_frame *frame = &job->frame;
    const double *alpha = job->alpha[i], *beta = job->beta[i];
    double A[3], B[3];
    if (frame->kind == WR_EDGE_LINE) {
        for (int k = 0; k < 3; k++) {
            A[k] = alpha[k] - CUT_SLACK * beta[k];
            B[k] = alpha[k] + (1 + CUT_SLACK) * beta[k];
        }
    } else if (frame->kind == WR_EDGE_ARC && frame->half_angle + CUT_SLACK < WR_PI / 2 - 1e-3 &&
               frame->half_angle_sin > 0) {
        double reach = tan(frame->half_angle + CUT_SLACK) / frame->half_angle_sin;
        for (int k = 0; k < 3; k++) {
            A[k] = beta[k] - reach * alpha[k];
            B[k] = beta[k] + reach * alpha[k];
        }
    } else {
        *from = r->low;
        *to = r->high;
        return;
    }
    cut_span(A, B, r, from, to);
}

/* The frame of the job's current edge, each plane's alpha = c1 . n(mu) and
 * beta = c2 . n(mu) on it, and for a push the roots of the edge's ends
 * and of its finger's blocked spans (fixed wrenches). */
static wr_status edge_begin(wr_sweep_job *job)
{
    const wr_sweeper *s = job->sweeper;
    const wr_fixture *f = s->fixture;
    if (job->what == WHAT_GRAVITY) {
        job->frame = (wr_edge_frame){WR_EDGE_CIRCLE, {1, 0, 0}, {0, 1, 0}, 0, 0};
    } else {
        int e = job->edge;
        wr_edge_frame_of(f, e, &job->frame);
        const wr_edge_frame *frame = &job->frame;
        if (frame->kind != WR_EDGE_CIRCLE) {
            double ends[2][3];
            for (int k = 0; k < 3; k++) {
                if (frame->kind == WR_EDGE_LINE) {
                    ends[0][k] = frame->c1[k];
                    ends[1][k] = frame->c1[k] + frame->c2[k];
                } else {
                    double c = cos(frame->half_angle);
                    ends[0][k] = -frame->c1[k] + c * frame->c2[k];
                    ends[1][k] = frame->c1[k] + c * frame->c2[k];
                }
            }
            fixed_roots(s, ends[0], &job->roots);
            fixed_roots(s, ends[1], &job->roots);
        }
        if (job->finger.radius > 0 && f->outline) {
            size_t loop, segment;
            wr_push_edge_place(f, e, &loop, &segment);
            wr_span *spans = NULL;
            int count = 0;
            wr_status status = WR_OK;
            if (job->push_index) {
                const wr_span *found;
                wr_push_index_blocked(job->push_index, e, &found, &count);
                spans = malloc((size_t)(count > 0 ? count : 1) * sizeof *spans);
                if (spans && count > 0)
                    memcpy(spans, found, (size_t)count * sizeof *spans);
                if (!spans)
                    status = WR_NO_MEMORY;
            } else {
                status = wr_finger_blocked(f->outline, loop, segment, job->finger.radius,
                                           job->stop, &spans, &count);
            }
            for (int i = 0; status == WR_OK && i < count; i++) {
                const double ts[2] = {spans[i].lo, spans[i].hi};
                for (int m = 0; m < 2; m++) {
                    double w[3], h[3];
                    wr_push_wrench(f, e, ts[m], w);
                    h[0] = w[0];
                    h[1] = w[1];
                    h[2] = w[2] / f->gyration_radius;
                    fixed_roots(s, h, &job->roots);
                }
            }
            free(spans);
            if (status != WR_OK)
                return status;
        }
    }
    for (int i = 0; i < s->plane_count; i++) {
        for (int k = 0; k < 3; k++) {
            job->alpha[i][k] = wr_dot3(job->frame.c1, s->planes[i].n[k]);
            job->beta[i][k] = wr_dot3(job->frame.c2, s->planes[i].n[k]);
        }
        edge_cut_span(job, i, &job->cut_from[i], &job->cut_to[i]);
    }
    return job->roots.failed ? WR_NO_MEMORY : WR_OK;
}

/* Plane i against every later plane j on the current edge: two planes meet
 * the edge's wrench s1 c1 + s2 c2 at one point where alpha_i beta_j -
 * alpha_j beta_i = 0 (a quartic in mu).  Each root is kept when the point
 * is on the edge and on both faces. */
static void edge_row(wr_sweep_job *job, int i)
{
    const wr_sweeper *s = job->sweeper;
    const wr_sweep_range *r = &s->range;
    const wr_edge_frame *frame = &job->frame;
    double (*alpha)[3] = job->alpha, (*beta)[3] = job->beta;
    double from = job->cut_from[i], to = job->cut_to[i];
    if (from > to)
        return; /* never on the edge */
    for (int j = i + 1; j < s->plane_count; j++) {
        /* A root kept is where both planes cut the edge. */
        if (job->cut_to[j] < from || job->cut_from[j] > to || job->cut_from[j] > job->cut_to[j])
            continue;
        double c[5] = {0, 0, 0, 0, 0};
        for (int x = 0; x < 3; x++)
            for (int y = 0; y < 3; y++)
                c[x + y] += alpha[i][x] * beta[j][y] - alpha[j][x] * beta[i][y];
        double roots[MAX_DEGREE + 2];
        int found = poly_roots(c, 4, r->low, r->high, roots);
        for (int k = 0; k < found; k++) {
            double mu = roots[k];
            /* Where on the edge: from the plane that cuts it more steeply. */
            double ai = poly_value(alpha[i], 2, mu), bi = poly_value(beta[i], 2, mu);
            double aj = poly_value(alpha[j], 2, mu), bj = poly_value(beta[j], 2, mu);
            double a = ai, b = bi;
            if (hypot(aj, bj) > hypot(ai, bi)) {
                a = aj;
                b = bj;
            }
            double points[5][2]; /* (s1, s2) */
            int point_count = 0;
            if (frame->kind == WR_EDGE_LINE) {
                /* a + t b = 0 */
                if (b == 0)
                    continue;
                double t = -a / b;
                if (t >= -1e-9 && t <= 1 + 1e-9) {
                    points[point_count][0] = 1;
                    points[point_count++][1] = t;
                }
            } else if (frame->kind == WR_EDGE_ARC) {
                /* (sin phi / s) a + cos phi b = 0 */
                double sa = frame->half_angle_sin, half = frame->half_angle;
                double root = a >= 0 ? atan2(-b * sa, a) : atan2(b * sa, -a);
                for (int turn = -2; turn <= 2; turn++) {
                    double phi = root + turn * WR_PI;
                    if (phi >= -half - 1e-9 && phi <= half + 1e-9) {
                        points[point_count][0] = sin(phi) / sa;
                        points[point_count++][1] = cos(phi);
                    }
                }
            } else {
                /* cos theta a + sin theta b = 0: two opposite points */
                double theta = atan2(-a, b);
                points[0][0] = cos(theta);
                points[0][1] = sin(theta);
                points[1][0] = -points[0][0];
                points[1][1] = -points[0][1];
                point_count = 2;
            }
            for (int m = 0; m < point_count; m++) {
                double h[3];
                for (int q = 0; q < 3; q++)
                    h[q] = points[m][0] * frame->c1[q] + points[m][1] * frame->c2[q];
                if (on_face(s, &s->planes[i], h, mu) && on_face(s, &s->planes[j], h, mu)) {
                    add_value(&job->roots, mu);
                    break;
                }
            }
        }
    }
}

/* ---- the job, a unit of work at a time ------------------------------------------- */

/* The critical mu, once the curve is known: the last interval's end when
 * the region is empty at the top of the range (an interval reaching the
 * top where the region vanishes exactly there ends at the top: critical is
 * the top), none when it is not empty there, the bottom of the range when
 * it is empty throughout. */
static void set_critical(const wr_sweeper *s, wr_sweep_curve *out)
{
    const wr_intervals *list = &out->intervals;
    assert(out->point_count > 0 && out->points[out->point_count - 1][0] == s->range.high);
    bool empty_at_top = !(out->points[out->point_count - 1][1] > 0);
    if (list->count == 0) {
        out->has_critical = true;
        out->critical = s->range.low;
    } else if (list->items[list->count - 1][1] < s->range.high || empty_at_top) {
        out->has_critical = true;
        out->critical = list->items[list->count - 1][1];
    } else {
        out->has_critical = false;
    }
}

/* The intervals are known: the points of the curve are every root kept,
 * every interval end and a grid between. */
static wr_status curve_begin(wr_sweep_job *job)
{
    const wr_sweeper *s = job->sweeper;
    values *points = &job->points;
    for (int i = 0; i < job->roots.count; i++)
        add_value(points, job->roots.items[i]);
    double width = s->range.high - s->range.low;
    for (int i = 1; i < GRID; i++)
        add_value(points, s->range.low + width * i / GRID);
    for (int i = 0; i < job->curve.intervals.count; i++) {
        add_value(points, job->curve.intervals.items[i][0]);
        add_value(points, job->curve.intervals.items[i][1]);
    }
    settle(points, &s->range);
    if (points->failed)
        return WR_NO_MEMORY;
    job->curve.points = malloc((size_t)points->count * sizeof *job->curve.points);
    if (!job->curve.points)
        return WR_NO_MEMORY;
    job->curve.point_count = 0;
    job->index = 0;
    job->phase = PHASE_CURVE;
    return WR_OK;
}

/* One step of the sampled sweep (a finger with friction): FRICTION_STEPS
 * steps of mu, each change of emptiness bisected. */
static wr_status sampled_unit(wr_sweep_job *job, unsigned long *spent)
{
    const wr_sweep_range *r = &job->sweeper->range;
    double width = r->high - r->low;
    wr_intervals *out = &job->curve.intervals;
    wr_status status = WR_OK;
    if (job->step == 0) {
        job->previous = answer_at(job, r->low, &status) > 0;
        job->start = r->low;
        job->step = 1;
        *spent += job->evaluation_cost;
        return status;
    }
    if (!job->bisecting) {
        if (job->step > FRICTION_STEPS) {
            if (job->previous && !add_interval(out, job->start, r->high))
                return WR_NO_MEMORY;
            return curve_begin(job);
        }
        double lo = r->low + width * (job->step - 1) / FRICTION_STEPS;
        double hi = job->step == FRICTION_STEPS ? r->high : r->low + width * job->step / FRICTION_STEPS;
        bool now = answer_at(job, hi, &status) > 0;
        *spent += job->evaluation_cost;
        if (status != WR_OK)
            return status;
        if (now == job->previous) {
            job->step++;
        } else {
            job->bisecting = true;
            job->lo = lo;
            job->hi = hi;
        }
        return WR_OK;
    }
    if (job->hi - job->lo > ROOT_MERGE * fmax(1, r->high)) {
        double mid = job->lo + (job->hi - job->lo) / 2;
        bool m = answer_at(job, mid, &status) > 0;
        *spent += job->evaluation_cost;
        if (status != WR_OK)
            return status;
        if (m == job->previous)
            job->lo = mid;
        else
            job->hi = mid;
        return WR_OK;
    }
    double change = job->lo + (job->hi - job->lo) / 2;
    if (job->previous && !add_interval(out, job->start, change))
        return WR_NO_MEMORY;
    job->start = change;
    job->previous = !job->previous;
    job->bisecting = false;
    job->step++;
    return WR_OK;
}

/* Piece job->index decided at its middle; its interval added when the
 * answer there is non-empty. */
static wr_status decide_piece(wr_sweep_job *job, wr_intervals *out, unsigned long *spent)
{
    wr_status status = WR_OK;
    double lo = job->roots.items[job->index], hi = job->roots.items[job->index + 1];
    double value = answer_at(job, lo + (hi - lo) / 2, &status);
    *spent += job->evaluation_cost;
    job->index++;
    if (status == WR_OK && value > 0 && !add_interval(out, lo, hi))
        status = WR_NO_MEMORY;
    return status;
}

/* The pieces of a G_goal or a both sweep.  G_goal only shrinks as mu
 * grows (its strings use s, u and m, and an m cone widens with mu_s:
 * docs/PROTOCOL.md), and so do its push regions, its gravity arcs and the
 * set of mu at which a wrench is in it: the pieces in which G_goal's answer
 * is non-empty come first, and the first empty one is found by bisection,
 * each piece's G_goal answer taken at its middle.  A goal sweep's intervals
 * are then the union of the pieces before it, as deciding every piece
 * would make them.  G_both lies in G_goal, so a both sweep decides only
 * the pieces before it, one at a time.  For either, the curve's points
 * beyond it are empty (empty_from). */
static wr_status decide_shrinking(wr_sweep_job *job, wr_intervals *out, unsigned long *spent)
{
    const wr_sweeper *s = job->sweeper;
    int pieces = job->roots.count - 1;
    wr_status status = WR_OK;
    if (job->full_below < 0) {
        job->full_below = 0;    /* pieces [0, full_below): G_goal non-empty */
        job->empty_at = pieces; /* the first piece known empty (pieces: none) */
    }
    if (job->full_below < job->empty_at) {
        int piece = job->full_below + (job->empty_at - job->full_below) / 2;
        double lo = job->roots.items[piece], hi = job->roots.items[piece + 1];
        double value = answer_in(job, lo + (hi - lo) / 2, WR_SET_GOAL, &status);
        *spent += job->evaluation_cost;
        if (status != WR_OK)
            return status;
        if (value > 0)
            job->full_below = piece + 1;
        else
            job->empty_at = piece;
        return WR_OK;
    }
    if (s->set == WR_SET_GOAL) {
        if (job->empty_at > 0 &&
            !add_interval(out, job->roots.items[0], job->roots.items[job->empty_at]))
            return WR_NO_MEMORY;
    } else if (job->index < job->empty_at) {
        return decide_piece(job, out, spent);
    }
    if (job->empty_at < pieces)
        job->empty_from = job->roots.items[job->empty_at];
    if (job->what == WHAT_WRENCH) {
        job->phase = PHASE_DONE;
        return WR_OK;
    }
    return curve_begin(job);
}

/* One unit of work: a plane row of an edge, a piece decided, a point of the
 * curve, a step of the sampled sweep. */
static wr_status job_unit(wr_sweep_job *job, unsigned long *spent)
{
    const wr_sweeper *s = job->sweeper;
    wr_status status = WR_OK;
    switch (job->phase) {
    case PHASE_ROOTS:
        if (job->what == WHAT_WRENCH) {
            double h[3];
            wr_fixture_unit_wrench(s->fixture, job->wrench, h);
            fixed_roots(s, h, &job->roots);
            *spent += (unsigned long)s->plane_count * 4 + 1;
            job->edge = job->edge_count;
        } else if (job->edge < job->edge_count &&
                   !wr_finger_pushes_on(s->fixture, &job->finger, job->edge)) {
            /* Not pushed on: no region there, nothing changes there. */
            job->edge++;
        } else if (job->edge < job->edge_count) {
            if (job->row < 0) {
                status = edge_begin(job);
                job->row = 0;
                *spent += (unsigned long)s->plane_count * 8 + 1;
            } else if (job->row < s->plane_count) {
                edge_row(job, job->row);
                *spent += (unsigned long)(s->plane_count - job->row) * job->row_cost + 1;
                job->row++;
            }
            if (job->row >= s->plane_count) {
                job->edge++;
                job->row = -1;
            }
        }
        if (status == WR_OK && job->edge >= job->edge_count) {
            settle(&job->roots, &s->range);
            job->phase = PHASE_DECIDE;
            job->index = 0;
        }
        if (status == WR_OK && job->roots.failed)
            status = WR_NO_MEMORY;
        return status;
    case PHASE_DECIDE: {
        wr_intervals *out = job->what == WHAT_WRENCH ? &job->intervals : &job->curve.intervals;
        if (s->set != WR_SET_STRONG)
            return decide_shrinking(job, out, spent);
        if (job->index + 1 >= job->roots.count) {
            if (job->what == WHAT_WRENCH) {
                job->phase = PHASE_DONE;
                return WR_OK;
            }
            return curve_begin(job);
        }
        return decide_piece(job, out, spent);
    }
    case PHASE_SAMPLED:
        return sampled_unit(job, spent);
    case PHASE_CURVE: {
        if (job->index >= job->points.count) {
            set_critical(job->sweeper, &job->curve);
            job->phase = PHASE_DONE;
            return WR_OK;
        }
        double mu = job->points.items[job->index];
        /* Beyond the end of a shrinking set's last interval: empty. */
        double length = 0;
        if (!(mu > job->empty_from)) {
            length = answer_at(job, mu, &status);
            *spent += job->evaluation_cost;
        }
        if (status != WR_OK)
            return status;
        job->curve.points[job->index][0] = mu;
        job->curve.points[job->index][1] = length;
        job->curve.point_count = ++job->index;
        return WR_OK;
    }
    case PHASE_DONE:
        break;
    }
    return WR_OK;
}

void wr_sweep_job_free(wr_sweep_job *job)
{
    if (!job)
        return;
    free(job->alpha);
    free(job->beta);
    free(job->cut_from);
    free(job->cut_to);
    free(job->roots.items);
    free(job->points.items);
    wr_intervals_release(&job->intervals);
    wr_sweep_curve_release(&job->curve);
    free(job);
}

static wr_sweep_job *job_new(const wr_sweeper *s, what what)
{
    wr_sweep_job *job = calloc(1, sizeof *job);
    if (!job)
        return NULL;
    job->sweeper = s;
    job->what = what;
    job->row = -1;
    job->edge_count = 1;
    job->curve.exact = true;
    job->row_cost = 32; /* a quartic's roots and their checks */
    job->full_below = -1;
    job->empty_from = INFINITY;
    /* An analysis at one mu: every cone's hull; then the question. */
    unsigned long cones = (unsigned long)s->cone_count + 1;
    job->evaluation_cost = (unsigned long)s->analysis_cones * 300 + cones * 4;
    /* Where the cones' faces change, every answer may change too. */
    for (int i = 0; i < s->structure.count; i++)
        add_value(&job->roots, s->structure.items[i]);
    if (job->roots.failed) {
        wr_sweep_job_free(job);
        return NULL;
    }
    if (what != WHAT_WRENCH) {
        size_t planes = (size_t)s->plane_count + 1;
        job->alpha = malloc(planes * sizeof *job->alpha);
        job->beta = malloc(planes * sizeof *job->beta);
        job->cut_from = malloc(planes * sizeof *job->cut_from);
        job->cut_to = malloc(planes * sizeof *job->cut_to);
        if (!job->alpha || !job->beta || !job->cut_from || !job->cut_to) {
            wr_sweep_job_free(job);
            return NULL;
        }
    }
    return job;
}

wr_status wr_sweep_job_wrench(const wr_sweeper *s, const double wrench[3], wr_sweep_job **out)
{
    *out = NULL;
    if (!isfinite(wrench[0]) || !isfinite(wrench[1]) || !isfinite(wrench[2]))
        return WR_INVALID;
    wr_sweep_job *job = job_new(s, WHAT_WRENCH);
    if (!job)
        return WR_NO_MEMORY;
    wr_copy3(wrench, job->wrench);
    *out = job;
    return WR_OK;
}

wr_status wr_sweep_job_push(const wr_sweeper *s, const wr_finger *finger, wr_sweep_job **out)
{
    *out = NULL;
    if (s->fixture->shape == WR_SHAPE_NONE)
        return WR_NO_SHAPE;
    if (!(finger->friction >= 0) || !isfinite(finger->friction) || !(finger->radius >= 0) ||
        !isfinite(finger->radius))
        return WR_INVALID;
    wr_sweep_job *job = job_new(s, WHAT_PUSH);
    if (!job)
        return WR_NO_MEMORY;
    job->finger = *finger;
    int edges = wr_push_edge_count(s->fixture);
    job->edge_count = edges;
    unsigned long per_edge = finger->friction > 0 ? 2200 : 4;
    job->evaluation_cost += (unsigned long)edges * ((unsigned long)s->cone_count + 1) * per_edge;
    if (finger->friction > 0) {
        /* Its regions are sampled, and so is the sweep. */
        job->phase = PHASE_SAMPLED;
        job->curve.exact = false;
        job->curve.resolution = (s->range.high - s->range.low) / FRICTION_STEPS;
    }
    *out = job;
    return WR_OK;
}

void wr_sweep_job_use_index(wr_sweep_job *job, const wr_push_index *index)
{
    assert(job->what == WHAT_PUSH);
    job->push_index = index;
}

wr_status wr_sweep_job_gravity(const wr_sweeper *s, wr_sweep_job **out)
{
    *out = job_new(s, WHAT_GRAVITY);
    return *out ? WR_OK : WR_NO_MEMORY;
}

wr_status wr_sweep_job_run(wr_sweep_job *job, unsigned long budget, unsigned long *used,
                           const wr_stop *stop, bool *done)
{
    job->stop = stop;
    unsigned long spent = 0;
    wr_status status = WR_OK;
    while (job->phase != PHASE_DONE && status == WR_OK) {
        if (wr_stop_requested(stop)) {
            status = WR_STOPPED;
            break;
        }
        status = job_unit(job, &spent);
        if (spent >= budget)
            break;
    }
    if (used)
        *used += spent;
    *done = status == WR_OK && job->phase == PHASE_DONE;
    return status;
}

wr_status wr_sweep_job_stop(wr_sweep_job *job, double *reached)
{
    const wr_sweep_range *r = &job->sweeper->range;
    wr_intervals *list = job->what == WHAT_WRENCH ? &job->intervals : &job->curve.intervals;
    double at = r->low;
    switch (job->phase) {
    case PHASE_ROOTS: /* no piece decided yet */
        break;
    case PHASE_DECIDE: /* pieces below roots[index] decided */
        at = job->roots.items[job->index];
        break;
    case PHASE_SAMPLED:
        /* Decided at the step's low end (or, bisecting, at lo): the answer
         * there is `previous`, as it has been since `start`. */
        if (job->step > 0) {
            at = job->bisecting ? job->lo
                                : r->low + (r->high - r->low) * (job->step - 1) / FRICTION_STEPS;
            if (job->previous && !add_interval(list, job->start, at))
                return WR_NO_MEMORY;
        }
        break;
    case PHASE_CURVE: /* every interval; the points below index */
        at = job->index > 0 ? job->points.items[job->index - 1] : r->low;
        break;
    case PHASE_DONE:
        *reached = r->high;
        return WR_OK;
    }
    /* Keep what lies below `at`, cut there. */
    int n = 0;
    for (int i = 0; i < list->count; i++) {
        if (!(list->items[i][0] < at))
            break;
        list->items[n][0] = list->items[i][0];
        list->items[n++][1] = fmin(list->items[i][1], at);
    }
    list->count = n;
    job->curve.has_critical = false;
    job->phase = PHASE_DONE;
    *reached = at;
    return WR_OK;
}

const wr_intervals *wr_sweep_job_intervals(const wr_sweep_job *job)
{
    return job->what == WHAT_WRENCH ? &job->intervals : &job->curve.intervals;
}

const wr_sweep_curve *wr_sweep_job_curve(const wr_sweep_job *job) { return &job->curve; }

/* ---- all at once ------------------------------------------------------------------- */

static wr_status run_all(wr_sweep_job *job, const wr_stop *stop)
{
    bool done = false;
    wr_status status = wr_sweep_job_run(job, (unsigned long)-1, NULL, stop, &done);
    assert(status != WR_OK || done);
    return status;
}

wr_status wr_sweep_wrench(const wr_sweeper *s, const double wrench[3], const wr_stop *stop,
                          wr_intervals *out)
{
    memset(out, 0, sizeof *out);
    wr_sweep_job *job;
    wr_status status = wr_sweep_job_wrench(s, wrench, &job);
    if (status == WR_OK)
        status = run_all(job, stop);
    if (status == WR_OK) {
        *out = job->intervals;
        memset(&job->intervals, 0, sizeof job->intervals);
    }
    wr_sweep_job_free(job);
    return status;
}

static wr_status take_curve(wr_sweep_job *job, wr_status status, const wr_stop *stop,
                            wr_sweep_curve *out)
{
    memset(out, 0, sizeof *out);
    if (status == WR_OK)
        status = run_all(job, stop);
    if (status == WR_OK) {
        *out = job->curve;
        memset(&job->curve, 0, sizeof job->curve);
    }
    wr_sweep_job_free(job);
    return status;
}

wr_status wr_sweep_push(const wr_sweeper *s, const wr_finger *finger, const wr_stop *stop,
                        wr_sweep_curve *out)
{
    wr_sweep_job *job;
    wr_status status = wr_sweep_job_push(s, finger, &job);
    return take_curve(job, status, stop, out);
}

wr_status wr_sweep_gravity(const wr_sweeper *s, const wr_stop *stop, wr_sweep_curve *out)
{
    wr_sweep_job *job;
    wr_status status = wr_sweep_job_gravity(s, &job);
    return take_curve(job, status, stop, out);
}
