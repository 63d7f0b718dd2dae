/* wr_sites.c -- candidate sites: by arc length, and pins (wr_sites.h). */
#include "wr_sites.h"
#include "wr_finger.h"
#include "wr_internal.h"
#include "wr_outline.h"

#include <assert.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* The loop a boundary point lies on (0 off an outline). */
static int loop_of(const wr_fixture *body, const double at[2])
{
    if (body->shape != WR_SHAPE_OUTLINE || !body->outline)
        return 0;
    wr_outline_place place;
    double tolerance = WR_OUTLINE_TOLERANCE * body->outline->size;
    return wr_outline_locate(body->outline, at, tolerance, &place) ? (int)place.loop : 0;
}

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
    memset(out, 0, sizeof *out);
    memcpy(out->at, placed.fixels[0].at, sizeof out->at);
    memcpy(out->normal, placed.fixels[0].normal, sizeof out->normal);
    out->loop = loop_of(body, out->at);
    return WR_OK;
}

/* Does a pin of radius `radius` fit against segment `segment` of `loop` at
 * fraction t?  *fits; WR_NO_MEMORY. */
static wr_status pin_fits(const wr_outline *o, size_t loop, size_t segment, double t,
                          double radius, bool *fits)
{
    wr_span *spans = NULL;
    int n = 0;
    wr_status status = wr_finger_blocked(o, loop, segment, radius, NULL, &spans, &n);
    *fits = true;
    for (int i = 0; status == WR_OK && i < n; i++)
        if (t >= spans[i].lo && t <= spans[i].hi)
            *fits = false;
    free(spans);
    return status;
}

wr_status wr_site_pin(const wr_fixture *body, int hole, double diameter, const double at[2],
                      wr_site *out, wr_error *error)
{
    const wr_outline *o = body->shape == WR_SHAPE_OUTLINE ? body->outline : NULL;
    if (!o || hole < 1 || (size_t)hole >= o->loop_count) {
        wr_error_set(error, "hole", "must be a hole of the body: a loop from 1 to %d, got %d",
                     o ? (int)o->loop_count - 1 : 0, hole);
        return WR_INVALID;
    }
    if (!(diameter >= 0) || !isfinite(diameter)) {
        wr_error_set(error, "diameter", "must be a non-negative number, got %g", diameter);
        return WR_INVALID;
    }
    if (!isfinite(at[0]) || !isfinite(at[1])) {
        wr_error_set(error, "at", "must be finite");
        return WR_INVALID;
    }
    double tolerance = WR_OUTLINE_TOLERANCE * o->size;
    if (wr_outline_contains(o, at, tolerance)) {
        wr_error_set(error, "at", "(%g, %g) lies in the material, not in hole %d", at[0], at[1],
                     hole);
        return WR_INVALID;
    }
    size_t segment;
    double t, q[2], normal[2], unused[2];
    wr_outline_nearest_on_loop(o, (size_t)hole, at, &segment, &t, q);
    wr_outline_boundary(o, (size_t)hole, segment, t, unused, normal);
    bool fits;
    if (pin_fits(o, (size_t)hole, segment, t, diameter / 2, &fits) != WR_OK) {
        wr_error_set(error, "", "out of memory");
        return WR_NO_MEMORY;
    }
    if (!fits) {
        wr_error_set(error, "diameter",
                     "a pin of diameter %g does not fit against the wall of hole %d at "
                     "(%g, %g): the hole is narrower there, or its wall curves tighter",
                     diameter, hole, q[0], q[1]);
        return WR_INVALID;
    }
    wr_status status = wr_site_new(body, q, NULL, out, error);
    if (status != WR_OK) {
        /* At a vertex of the wall the pin would touch two segments at once:
         * its normal is not defined. */
        wr_error_set(error, "at", "the pin touches hole %d at (%g, %g), a corner of its wall",
                     hole, q[0], q[1]);
        return status;
    }
    out->loop = hole;
    out->pin_diameter = diameter;
    return WR_OK;
}

static wr_status site_append(const wr_site *site, wr_site **sites, int *count, int *capacity,
                             wr_error *error)
{
    if (*count >= WR_DESIGN_MAX_SITES) {
        wr_error_set(error, "spacing", "gives more than %d sites", WR_DESIGN_MAX_SITES);
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
    (*sites)[(*count)++] = *site;
    return WR_OK;
}

static int compare_doubles(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* The angle between two unit normals, in degrees. */
static double turn_deg(const double a[2], const double b[2])
{
    return atan2(fabs(a[0] * b[1] - a[1] * b[0]), a[0] * b[0] + a[1] * b[1]) * 180 / WR_PI;
}

/* The positions (distances along loop l from its vertex 0, in [0, P)) of
 * its sites by the rule: malloc'd into *out, *n of them; or just counted
 * when out is NULL.  False: out of memory. */
static bool loop_positions(const wr_outline *o, size_t l, const wr_spacing *rule, double **out,
                           double *n_out)
{
    const wr_loop *loop = &o->loops[l];
    size_t m = loop->segment_count;
    double h = rule->spacing, c = rule->corner_clearance;
    double *starts = malloc((m + 1) * sizeof *starts);
    double *corners = malloc((m + 1) * sizeof *corners);
    if (!starts || !corners) {
        free(starts);
        free(corners);
        return false;
    }
    starts[0] = 0;
    for (size_t j = 0; j < m; j++)
        starts[j + 1] = starts[j] + loop->segments[j].length;
    double perimeter = starts[m];
    size_t corner_count = 0;
    for (size_t j = 0; j < m; j++) {
        double p[2], before[2], after[2];
        wr_outline_boundary(o, l, (j + m - 1) % m, 1, p, before);
        wr_outline_boundary(o, l, j, 0, p, after);
        if (turn_deg(before, after) > WR_SITE_CORNER_DEG)
            corners[corner_count++] = starts[j];
    }
    double total = 0;
    double *positions = NULL;
    if (corner_count == 0) {
        total = floor(perimeter / h + 1e-9);
    } else {
        for (size_t i = 0; i < corner_count; i++) {
            double next = i + 1 < corner_count ? corners[i + 1] : corners[0] + perimeter;
            double usable = next - corners[i] - 2 * c;
            if (usable >= -1e-9 * h)
                total += floor(fmax(usable, 0) / h + 1e-9) + 1;
        }
    }
    *n_out = total;
    if (out && total > 0 && total <= WR_DESIGN_MAX_SITES) {
        positions = malloc((size_t)total * sizeof *positions);
        if (!positions) {
            free(starts);
            free(corners);
            return false;
        }
        size_t k = 0;
        if (corner_count == 0) {
            for (size_t i = 0; i < (size_t)total; i++)
                positions[k++] = perimeter * (double)i / total;
        } else {
            for (size_t i = 0; i < corner_count; i++) {
                double next = i + 1 < corner_count ? corners[i + 1] : corners[0] + perimeter;
                double usable = next - corners[i] - 2 * c;
                if (usable < -1e-9 * h)
                    continue;
                usable = fmax(usable, 0);
                int count = (int)floor(usable / h + 1e-9) + 1;
                double first = corners[i] + c + (usable - (count - 1) * h) / 2;
                for (int s = 0; s < count; s++) {
                    double at = first + s * h;
                    positions[k++] = at >= perimeter ? at - perimeter : at;
                }
            }
        }
        assert(k == (size_t)total);
        qsort(positions, k, sizeof *positions, compare_doubles);
    }
    if (out)
        *out = positions;
    else
        free(positions);
    free(starts);
    free(corners);
    return true;
}

/* The site at distance `position` along loop l: on its segment, or at a
 * joint with the bisector of the two normals. */
static wr_status site_at(const wr_fixture *body, size_t l, double position, wr_site *site,
                         wr_error *error)
{
    const wr_outline *o = body->outline;
    const wr_loop *loop = &o->loops[l];
    size_t m = loop->segment_count, j = 0;
    double start = 0;
    while (j + 1 < m && start + loop->segments[j].length <= position) {
        start += loop->segments[j].length;
        j++;
    }
    double length = loop->segments[j].length;
    double t = fmin(1, fmax(0, (position - start) / length));
    /* Within this fraction of a joint the site is at the joint: its
     * position then falls on the vertex whatever the rounding. */
    const double joint = 1e-9;
    double p[2], normal[2];
    if (t < joint || t > 1 - joint) {
        size_t after = t < joint ? j : (j + 1) % m;
        size_t before = (after + m - 1) % m;
        double a[2], b[2];
        wr_outline_boundary(o, l, before, 1, p, a);
        wr_outline_boundary(o, l, after, 0, p, b);
        double sum[2] = {a[0] + b[0], a[1] + b[1]};
        double norm = hypot(sum[0], sum[1]);
        normal[0] = sum[0] / norm;
        normal[1] = sum[1] / norm;
        return wr_site_new(body, p, normal, site, error);
    }
    wr_outline_boundary(o, l, j, t, p, normal);
    return wr_site_new(body, p, NULL, site, error);
}

wr_status wr_sites_spaced(const wr_fixture *body, const wr_spacing *rule, wr_site **sites,
                          int *count, wr_error *error)
{
    double h = rule->spacing;
    if (!(h > 0) || !isfinite(h)) {
        wr_error_set(error, "spacing", "must be a positive number, got %g", h);
        return WR_INVALID;
    }
    if (!(rule->corner_clearance > 0) || !isfinite(rule->corner_clearance)) {
        wr_error_set(error, "corner_clearance", "must be a positive number, got %g",
                     rule->corner_clearance);
        return WR_INVALID;
    }
    if (!(rule->pin_diameter >= 0) || !isfinite(rule->pin_diameter)) {
        wr_error_set(error, "pin_diameter", "must be a non-negative number, got %g",
                     rule->pin_diameter);
        return WR_INVALID;
    }
    wr_site *list = *sites;
    int n = *count, capacity = *count;
    wr_status status = WR_OK;
    if (body->shape == WR_SHAPE_CIRCLE) {
        double circumference = 2 * WR_PI * body->radius;
        double steps = floor(circumference / h + 1e-9);
        if (steps > WR_DESIGN_MAX_SITES) {
            wr_error_set(error, "spacing", "gives %.3g sites, more than %d", steps,
                         WR_DESIGN_MAX_SITES);
            return WR_INVALID;
        }
        for (int i = 0; i < (int)steps && status == WR_OK; i++) {
            double angle = 2 * WR_PI * i / steps;
            double p[2] = {body->center[0] + body->radius * cos(angle),
                           body->center[1] + body->radius * sin(angle)};
            wr_site site;
            status = wr_site_new(body, p, NULL, &site, error);
            if (status == WR_OK)
                status = site_append(&site, &list, &n, &capacity, error);
        }
    } else if (body->outline) {
        const wr_outline *o = body->outline;
        double total = 0;
        for (size_t l = 0; l < o->loop_count; l++) {
            double loop_total;
            if (!loop_positions(o, l, rule, NULL, &loop_total)) {
                wr_error_set(error, "", "out of memory");
                return WR_NO_MEMORY;
            }
            total += loop_total;
        }
        if (total > WR_DESIGN_MAX_SITES) {
            wr_error_set(error, "spacing", "gives %.3g sites, more than %d", total,
                         WR_DESIGN_MAX_SITES);
            return WR_INVALID;
        }
        for (size_t l = 0; l < o->loop_count && status == WR_OK; l++) {
            double *positions = NULL, loop_total;
            if (!loop_positions(o, l, rule, &positions, &loop_total)) {
                wr_error_set(error, "", "out of memory");
                status = WR_NO_MEMORY;
                break;
            }
            for (int i = 0; i < (int)loop_total && status == WR_OK; i++) {
                wr_site site;
                status = site_at(body, l, positions[i], &site, error);
                if (status != WR_OK)
                    break;
                site.loop = (int)l;
                if (l > 0) {
                    /* A pin: kept where one of its diameter fits. */
                    wr_outline_place place;
                    bool fits = true;
                    if (rule->pin_diameter > 0 &&
                        wr_outline_locate(o, site.at, WR_OUTLINE_TOLERANCE * o->size, &place))
                        status = pin_fits(o, place.loop, place.segment, place.t,
                                          rule->pin_diameter / 2, &fits);
                    if (!fits)
                        continue;
                    site.pin_diameter = rule->pin_diameter;
                }
                if (status == WR_OK)
                    status = site_append(&site, &list, &n, &capacity, error);
            }
            free(positions);
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
