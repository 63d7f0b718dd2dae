/* wr_symmetry.c -- a part's symmetries (wr_symmetry.h). */
#include "wr_symmetry.h"
#include "wr_internal.h"
#include "wr_outline.h"

#include <stdlib.h>
#include <string.h>

/* The rotation about c by `angle` (radians), or the reflection through the
 * line through c in direction `angle`. */
static wr_symmetry make(bool reflection, double angle, const double c[2])
{
    wr_symmetry g;
    memset(&g, 0, sizeof g);
    g.reflection = reflection;
    g.center[0] = c[0];
    g.center[1] = c[1];
    if (reflection) {
        double co = cos(2 * angle), si = sin(2 * angle);
        g.linear[0][0] = co;
        g.linear[0][1] = si;
        g.linear[1][0] = si;
        g.linear[1][1] = -co;
        double deg = fmod(angle * 180 / WR_PI, 180);
        g.angle_deg = deg < 0 ? deg + 180 : deg;
    } else {
        double co = cos(angle), si = sin(angle);
        g.linear[0][0] = co;
        g.linear[0][1] = -si;
        g.linear[1][0] = si;
        g.linear[1][1] = co;
        double deg = fmod(angle * 180 / WR_PI, 360);
        g.angle_deg = deg < 0 ? deg + 360 : deg;
    }
    /* Whole turns and half turns written exactly: 360 - 1e-14 is 0. */
    double period = reflection ? 180 : 360;
    if (period - g.angle_deg < 1e-9)
        g.angle_deg = 0;
    g.offset[0] = c[0] - (g.linear[0][0] * c[0] + g.linear[0][1] * c[1]);
    g.offset[1] = c[1] - (g.linear[1][0] * c[0] + g.linear[1][1] * c[1]);
    return g;
}

void wr_symmetry_point(const wr_symmetry *g, const double p[2], double out[2])
{
    double x = g->linear[0][0] * p[0] + g->linear[0][1] * p[1] + g->offset[0];
    double y = g->linear[1][0] * p[0] + g->linear[1][1] * p[1] + g->offset[1];
    out[0] = x;
    out[1] = y;
}

void wr_symmetry_direction(const wr_symmetry *g, const double v[2], double out[2])
{
    double x = g->linear[0][0] * v[0] + g->linear[0][1] * v[1];
    double y = g->linear[1][0] * v[0] + g->linear[1][1] * v[1];
    out[0] = x;
    out[1] = y;
}

/* ---- points looked up by x ------------------------------------------------------- */

typedef struct keyed {
    double x, y;
    int index;
} keyed;

static int by_x(const void *a, const void *b)
{
    const keyed *p = a, *q = b;
    if (p->x != q->x)
        return p->x < q->x ? -1 : 1;
    return (p->index > q->index) - (p->index < q->index);
}

/* The first item with x >= lo. */
static int lower_bound(const keyed *items, int n, double lo)
{
    int a = 0, b = n;
    while (a < b) {
        int m = a + (b - a) / 2;
        if (items[m].x < lo)
            a = m + 1;
        else
            b = m;
    }
    return a;
}

/* The lowest index among the items within eps of p for which accept()
 * holds, or -1. */
static int find_near(const keyed *items, int n, const double p[2], double eps,
                     bool (*accept)(const void *context, int index), const void *context)
{
    int best = -1;
    for (int i = lower_bound(items, n, p[0] - eps); i < n && items[i].x <= p[0] + eps; i++)
        if (fabs(items[i].y - p[1]) <= eps && (best < 0 || items[i].index < best) &&
            (!accept || accept(context, items[i].index)))
            best = items[i].index;
    return best;
}

/* ---- the outline's symmetries ---------------------------------------------------- */

typedef struct vertex_ref {
    int loop, vertex;
} vertex_ref;

/* A loop of arcs about one centre, of one radius, is a whole circle: where
 * its vertices lie says nothing of its shape (a drawing's CIRCLE becomes
 * two half circles from any point), so it is matched by centre and radius.
 * Every other loop by its vertices and segments. */
typedef struct shape_state {
    const wr_outline *o;
    double eps;
    int n;               /* vertices over all loops */
    vertex_ref *refs;    /* by flat index */
    int *first;          /* loop's first flat index */
    bool *circle;        /* per loop */
    keyed *sorted;       /* the vertices of loops that are not circles */
    int sorted_count;
    int *image;          /* a candidate's vertex map */
    bool *taken;         /* per vertex; per loop for circles */
} shape_state;

static bool is_circle(const wr_loop *loop, double eps)
{
    const wr_segment *a = &loop->segments[0];
    for (size_t j = 0; j < loop->segment_count; j++) {
        const wr_segment *s = &loop->segments[j];
        if (s->bulge == 0 || hypot(s->center[0] - a->center[0], s->center[1] - a->center[1]) > eps ||
            fabs(s->radius - a->radius) > eps)
            return false;
    }
    return true;
}

static const double *vertex_point(const shape_state *s, int flat)
{
    const wr_loop *loop = &s->o->loops[s->refs[flat].loop];
    return loop->segments[s->refs[flat].vertex].start;
}

static bool same_bulge(double a, double b)
{
    return fabs(a - b) <= WR_SYMMETRY_TOLERANCE * (1 + fabs(a));
}

/* Does g map every vertex onto a vertex, one to one, and every segment onto
 * a segment of the same kind? */
static bool maps_onto(shape_state *s, const wr_symmetry *g)
{
    size_t loops = s->o->loop_count;
    memset(s->taken, 0, ((size_t)s->n + loops) * sizeof *s->taken);
    for (int v = 0; v < s->n; v++) {
        if (s->circle[s->refs[v].loop])
            continue;
        double p[2];
        wr_symmetry_point(g, vertex_point(s, v), p);
        int w = find_near(s->sorted, s->sorted_count, p, s->eps, NULL, NULL);
        if (w < 0 || s->taken[w])
            return false;
        s->taken[w] = true;
        s->image[v] = w;
    }
    bool *circle_taken = s->taken + s->n;
    for (size_t l = 0; l < loops; l++) {
        if (!s->circle[l])
            continue;
        const wr_segment *a = &s->o->loops[l].segments[0];
        double p[2];
        wr_symmetry_point(g, a->center, p);
        bool found = false;
        for (size_t m = 0; m < loops && !found; m++) {
            const wr_segment *b = &s->o->loops[m].segments[0];
            found = s->circle[m] && !circle_taken[m] &&
                    hypot(p[0] - b->center[0], p[1] - b->center[1]) <= s->eps &&
                    fabs(a->radius - b->radius) <= s->eps;
            if (found)
                circle_taken[m] = true;
        }
        if (!found)
            return false;
    }
    double sense = g->reflection ? -1 : 1;
    for (int v = 0; v < s->n; v++) {
        if (s->circle[s->refs[v].loop])
            continue;
        int l = s->refs[v].loop, j = s->refs[v].vertex;
        const wr_loop *loop = &s->o->loops[l];
        int next = s->first[l] + (int)(((size_t)j + 1) % loop->segment_count);
        int p = s->image[v], q = s->image[next];
        int lp = s->refs[p].loop;
        if (s->refs[q].loop != lp)
            return false;
        const wr_loop *to = &s->o->loops[lp];
        size_t count = to->segment_count;
        size_t jp = (size_t)s->refs[p].vertex, jq = (size_t)s->refs[q].vertex;
        double bulge = loop->segments[j].bulge;
        /* Forward: segment jp runs p to q; reversed: segment jq runs q to p. */
        bool forward = (jp + 1) % count == jq && same_bulge(sense * bulge, to->segments[jp].bulge);
        bool backward = (jq + 1) % count == jp && same_bulge(-sense * bulge, to->segments[jq].bulge);
        if (!forward && !backward)
            return false;
    }
    return true;
}

static int by_angle(const void *a, const void *b)
{
    const wr_symmetry *p = a, *q = b;
    if (p->reflection != q->reflection)
        return p->reflection ? 1 : -1;
    return (p->angle_deg > q->angle_deg) - (p->angle_deg < q->angle_deg);
}

static wr_status add(wr_symmetry **list, int *count, int *capacity, const wr_symmetry *g)
{
    if (*count == *capacity) {
        int grown = *capacity ? 2 * *capacity : 8;
        wr_symmetry *more = realloc(*list, (size_t)grown * sizeof *more);
        if (!more)
            return WR_NO_MEMORY;
        *list = more;
        *capacity = grown;
    }
    (*list)[(*count)++] = *g;
    return WR_OK;
}

/* Candidates: the anchor (the vertex farthest from the centre of mass c,
 * or without such vertices the farthest circle's centre) taken to each
 * point of its kind as far from c, by the rotation about c and by the
 * reflection through a line through c; each kept when it maps the shape
 * onto itself.  Circles about c alone (a washer) have every turn and
 * every mirror, which no list holds: then the identity alone is found. */
static wr_status outline_symmetries(const wr_fixture *body, wr_symmetry **list, int *count,
                                    int *capacity)
{
    shape_state s;
    memset(&s, 0, sizeof s);
    s.o = body->outline;
    s.eps = WR_SYMMETRY_TOLERANCE * body->size;
    s.n = (int)s.o->vertex_count;
    size_t loops = s.o->loop_count;
    s.refs = malloc((size_t)s.n * sizeof *s.refs);
    s.first = malloc(loops * sizeof *s.first);
    s.circle = malloc(loops * sizeof *s.circle);
    s.sorted = malloc((size_t)s.n * sizeof *s.sorted);
    s.image = malloc((size_t)s.n * sizeof *s.image);
    s.taken = malloc(((size_t)s.n + loops) * sizeof *s.taken);
    /* The anchors: points of one kind, vertices or circles' centres. */
    double (*anchors)[2] = malloc(((size_t)s.n + loops) * sizeof *anchors);
    int anchor_count = 0;
    wr_status status = WR_OK;
    if (!s.refs || !s.first || !s.circle || !s.sorted || !s.image || !s.taken || !anchors)
        status = WR_NO_MEMORY;
    const double *c = body->com;
    for (size_t l = 0, flat = 0; status == WR_OK && l < loops; l++) {
        s.first[l] = (int)flat;
        s.circle[l] = is_circle(&s.o->loops[l], s.eps);
        for (size_t j = 0; j < s.o->loops[l].segment_count; j++, flat++) {
            s.refs[flat] = (vertex_ref){(int)l, (int)j};
            const double *p = s.o->loops[l].segments[j].start;
            if (!s.circle[l]) {
                s.sorted[s.sorted_count++] = (keyed){p[0], p[1], (int)flat};
                memcpy(anchors[anchor_count++], p, sizeof anchors[0]);
            }
        }
    }
    if (status == WR_OK && anchor_count == 0)
        for (size_t l = 0; l < loops; l++)
            memcpy(anchors[anchor_count++], s.o->loops[l].segments[0].center, sizeof anchors[0]);
    int anchor = -1;
    double far = 0;
    for (int i = 0; status == WR_OK && i < anchor_count; i++) {
        double r = hypot(anchors[i][0] - c[0], anchors[i][1] - c[1]);
        if (r > far) {
            far = r;
            anchor = i;
        }
    }
    if (status == WR_OK && anchor >= 0 && far > s.eps) {
        qsort(s.sorted, (size_t)s.sorted_count, sizeof *s.sorted, by_x);
        const double *a = anchors[anchor];
        double alpha = atan2(a[1] - c[1], a[0] - c[0]);
        for (int b = 0; b < anchor_count && status == WR_OK; b++) {
            const double *q = anchors[b];
            if (fabs(hypot(q[0] - c[0], q[1] - c[1]) - far) > s.eps)
                continue;
            double beta = atan2(q[1] - c[1], q[0] - c[0]);
            for (int reflect = 0; reflect < 2 && status == WR_OK; reflect++) {
                wr_symmetry g = reflect ? make(true, (alpha + beta) / 2, c)
                                        : make(false, b == anchor ? 0 : beta - alpha, c);
                if (maps_onto(&s, &g))
                    status = add(list, count, capacity, &g);
            }
        }
    }
    free(anchors);
    free(s.refs);
    free(s.first);
    free(s.circle);
    free(s.sorted);
    free(s.image);
    free(s.taken);
    return status;
}

/* A circle: the rotations and reflections about its centre (the centre of
 * mass) that map the site set onto itself, from site 0 to each site. */
static wr_status circle_symmetries(const wr_fixture *body, const wr_site *sites, int site_count,
                                   wr_symmetry **list, int *count, int *capacity)
{
    const double *c = body->center;
    if (site_count == 0 || hypot(body->com[0] - c[0], body->com[1] - c[1]) >
                               WR_SYMMETRY_TOLERANCE * body->size)
        return WR_OK;
    int *map = malloc((size_t)site_count * sizeof *map);
    if (!map)
        return WR_NO_MEMORY;
    wr_status status = WR_OK;
    const double *a = sites[0].at;
    double alpha = atan2(a[1] - c[1], a[0] - c[0]);
    for (int b = 0; b < site_count && status == WR_OK; b++) {
        double beta = atan2(sites[b].at[1] - c[1], sites[b].at[0] - c[0]);
        for (int reflect = 0; reflect < 2 && status == WR_OK; reflect++) {
            wr_symmetry g = reflect ? make(true, (alpha + beta) / 2, c)
                                    : make(false, b == 0 ? 0 : beta - alpha, c);
            status = wr_symmetry_site_map(&g, sites, site_count, body->size, map);
            bool onto = true;
            for (int i = 0; status == WR_OK && i < site_count && onto; i++)
                onto = map[i] >= 0;
            /* Sites repeated would be counted twice: kept only once. */
            for (int i = 0; onto && i < *count; i++)
                onto = (*list)[i].reflection != g.reflection ||
                       fabs((*list)[i].angle_deg - g.angle_deg) > 1e-9;
            if (status == WR_OK && onto)
                status = add(list, count, capacity, &g);
        }
    }
    free(map);
    return status;
}

wr_status wr_symmetry_find(const wr_fixture *body, const wr_site *sites, int site_count,
                           wr_symmetry **out, int *count)
{
    *out = NULL;
    *count = 0;
    wr_symmetry *list = NULL;
    int n = 0, capacity = 0;
    wr_status status;
    if (body->outline)
        status = outline_symmetries(body, &list, &n, &capacity);
    else if (body->shape == WR_SHAPE_CIRCLE)
        status = circle_symmetries(body, sites, site_count, &list, &n, &capacity);
    else
        status = WR_OK;
    if (status == WR_OK && n == 0) {
        /* No shape, or a circle whose sites are not symmetric. */
        wr_symmetry identity = make(false, 0, body->com);
        status = add(&list, &n, &capacity, &identity);
    }
    if (status != WR_OK) {
        free(list);
        return status;
    }
    qsort(list, (size_t)n, sizeof *list, by_angle);
    *out = list;
    *count = n;
    return WR_OK;
}

/* ---- the rest of a design's question ------------------------------------------------ */

/* The loop of the outline that g maps loop l onto (a point of its first
 * segment, located), or -1. */
static int loop_image(const wr_fixture *body, const wr_symmetry *g, size_t l)
{
    double p[2], q[2], normal[2];
    wr_outline_boundary(body->outline, l, 0, 0.5, p, normal);
    wr_symmetry_point(g, p, q);
    wr_outline_place place;
    if (!wr_outline_locate(body->outline, q, WR_SYMMETRY_TOLERANCE * body->size, &place))
        return -1;
    return (int)place.loop;
}

static bool keeps(const wr_fixture *body, const wr_finger *finger, const double (*loads)[3],
                  int case_count, const wr_symmetry *g)
{
    if (finger && finger->push_on && body->outline)
        for (size_t l = 0; l < body->outline->loop_count; l++) {
            int m = loop_image(body, g, l);
            bool here = l < finger->push_on_count && finger->push_on[l];
            bool there = m >= 0 && (size_t)m < finger->push_on_count && finger->push_on[m];
            if (m < 0 || here != there)
                return false;
        }
    for (int c = 0; c < case_count; c++) {
        double f[2], size = fabs(loads[c][0]) + fabs(loads[c][1]) +
                            fabs(loads[c][2]) / (body->gyration_radius > 0 ? body->gyration_radius : 1);
        wr_symmetry_direction(g, loads[c], f);
        double tau = g->reflection ? -loads[c][2] : loads[c][2];
        double off = fabs(f[0] - loads[c][0]) + fabs(f[1] - loads[c][1]) +
                     fabs(tau - loads[c][2]) / (body->gyration_radius > 0 ? body->gyration_radius : 1);
        if (off > WR_SYMMETRY_TOLERANCE * size)
            return false;
    }
    return true;
}

int wr_symmetry_filter(const wr_fixture *body, const wr_finger *finger, const double (*loads)[3],
                       int case_count, wr_symmetry *list, int count)
{
    int kept = 0;
    for (int i = 0; i < count; i++)
        if (i == 0 || keeps(body, finger, loads, case_count, &list[i]))
            list[kept++] = list[i];
    return kept;
}

int wr_symmetry_filter_points(const double (*points)[2], int point_count, double size,
                              wr_symmetry *list, int count)
{
    double eps = WR_SYMMETRY_TOLERANCE * size;
    int kept = 0;
    for (int i = 0; i < count; i++) {
        bool maps = true;
        for (int j = 0; i > 0 && maps && j < point_count; j++) {
            double p[2];
            wr_symmetry_point(&list[i], points[j], p);
            maps = false;
            for (int k = 0; !maps && k < point_count; k++)
                maps = hypot(p[0] - points[k][0], p[1] - points[k][1]) <= eps;
        }
        if (maps)
            list[kept++] = list[i];
    }
    return kept;
}

/* ---- sites ------------------------------------------------------------------------ */

typedef struct normal_match {
    const wr_site *sites;
    double normal[2];
    double pin_diameter;
} normal_match;

static bool normal_agrees(const void *context, int index)
{
    const normal_match *m = context;
    const double *n = m->sites[index].normal;
    /* A pin's image is a pin of the same diameter. */
    return hypot(n[0] - m->normal[0], n[1] - m->normal[1]) <= WR_SYMMETRY_TOLERANCE &&
           m->sites[index].pin_diameter == m->pin_diameter;
}

wr_status wr_symmetry_site_map(const wr_symmetry *g, const wr_site *sites, int site_count,
                               double size, int *map)
{
    keyed *sorted = malloc((size_t)(site_count > 0 ? site_count : 1) * sizeof *sorted);
    if (!sorted)
        return WR_NO_MEMORY;
    for (int i = 0; i < site_count; i++)
        sorted[i] = (keyed){sites[i].at[0], sites[i].at[1], i};
    qsort(sorted, (size_t)site_count, sizeof *sorted, by_x);
    double eps = WR_SYMMETRY_TOLERANCE * size;
    for (int i = 0; i < site_count; i++) {
        double p[2];
        normal_match m = {sites, {0, 0}, sites[i].pin_diameter};
        wr_symmetry_point(g, sites[i].at, p);
        wr_symmetry_direction(g, sites[i].normal, m.normal);
        map[i] = find_near(sorted, site_count, p, eps, normal_agrees, &m);
    }
    free(sorted);
    return WR_OK;
}
