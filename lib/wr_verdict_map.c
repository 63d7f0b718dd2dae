/* wr_verdict_map.c -- verdicts by direction: the sphere of scaled wrench
 * directions cut into cells, each decided once where it can be.
 *
 * A verdict depends only on the direction of the scaled wrench (cones are
 * cones).  Directions are mapped onto the six faces of the cube [-1, 1]^3
 * (the largest component picks the face, the other two divided by it are
 * the face's coordinates), and each face is cut into SIDE x SIDE cells.
 *
 * A cell is decided when wr_set_verdict cannot but answer the same for
 * every direction in it.  The test: a cell lies within chord r of its
 * centre c (the farthest of its corners, since the radial image of a
 * square is spherically convex, and a cap of radius below pi/2 is too), so
 * for a unit row n and any unit x of the cell, |n.x - n.c| <= r.  Each
 * cone's facet bound max n.x then lies in [lo, hi] = [max (n.c) - r,
 * max (n.c) + r], and
 *   - some cone of full dimension with hi < -tolerance: x is deeper than
 *     the band in it, and the verdict is outside;
 *   - every cone with lo > tolerance + WR_VERDICT_REACH: no cone holds x or
 *     comes within reach of the band, and the verdict is inside;
 *   - else the cell is left undecided, and its wrenches are measured.
 * r is widened by SLACK for the rounding of x (its length 1 +- 2^-52, its
 * cell found from rounded quotients) and of the dot products, so that the
 * map's answer is wr_classify_verdict's for every wrench, not nearly.
 *
 * Cells are decided top-down, a quadtree over each face: a square of cells
 * that is decided as a whole is filled without looking at its parts.  Only
 * cells near some facet plane are ever looked at singly. */
#include "wr_classify.h"
#include "wr_internal.h"

#include <assert.h>
#include <float.h>
#include <stdlib.h>
#include <string.h>

/* Cells along a face's side: 6 x 128^2 cells (96 KiB: a byte each, both
 * sets' codes in it, so that a wrench costs one load), each at most 0.013
 * radians across. */
#define SIDE 128
#define CELLS (6 * SIDE * SIDE)
/* Added to every cell's radius: far above the rounding of unit vectors and
 * dot products (about 1e-16), far below the cells (about 1e-2). */
#define SLACK 1e-12
/* A direction is found without normalising when its largest scaled
 * component is in this range: nothing overflows or goes subnormal. */
#define FAST_LOW 1e-280
#define FAST_HIGH 1e280

enum { CELL_UNDECIDED, CELL_INSIDE, CELL_OUTSIDE };

/* One set's cones as the test reads them: rows, and where each cone's are. */
typedef struct set_rows {
    int cone_count;
    struct cone_rows {
        int first, facets, equalities;
        bool full;  /* of dimension 3 */
    } *cones;
    double (*rows)[3];
} set_rows;

struct wr_verdict_map {
    const wr_analysis *analysis;
    double tolerance;
    double inverse_gyration;         /* 1 / the fixture's radius of gyration */
    unsigned char *cells;            /* CELLS: G_goal's code in bits 0-1,
                                        G_strong's in bits 2-3 */
    size_t decided;                  /* cells decided, both sets */
};

static void set_rows_release(set_rows *s)
{
    free(s->cones);
    free(s->rows);
}

static wr_status set_rows_make(const wr_analysis *a, wr_set set, set_rows *s)
{
    memset(s, 0, sizeof *s);
    int count = wr_analysis_cone_count(a, set);
    int total = 0;
    for (int i = 0; i < count; i++) {
        const wr_cone *cone = wr_analysis_cone(a, set, i);
        if (!cone->empty)
            total += cone->facet_count + cone->equality_count;
    }
    s->cones = malloc((size_t)(count > 0 ? count : 1) * sizeof *s->cones);
    s->rows = malloc((size_t)(total > 0 ? total : 1) * sizeof *s->rows);
    if (!s->cones || !s->rows) {
        set_rows_release(s);
        return WR_NO_MEMORY;
    }
    int row = 0;
    for (int i = 0; i < count; i++) {
        const wr_cone *cone = wr_analysis_cone(a, set, i);
        if (cone->empty)
            continue; /* wr_set_verdict passes them by */
        struct cone_rows *c = &s->cones[s->cone_count++];
        c->first = row;
        c->facets = cone->facet_count;
        c->equalities = cone->equality_count;
        c->full = cone->dimension == 3;
        for (int k = 0; k < cone->facet_count; k++)
            wr_copy3(cone->facets[k], s->rows[row++]);
        for (int k = 0; k < cone->equality_count; k++)
            wr_copy3(cone->equalities[k], s->rows[row++]);
    }
    assert(row == total);
    return WR_OK;
}

/* The verdict every unit direction within chord r of unit c has, as a cell
 * code: see the top of the file. */
static int region_code(const set_rows *s, const double c[3], double r, double tolerance)
{
    const double reach = tolerance + WR_VERDICT_REACH;
    bool far = true;
    for (int i = 0; i < s->cone_count; i++) {
        const struct cone_rows *cone = &s->cones[i];
        if (cone->full && cone->facets == 0) {
            /* All of space: every direction is 1 deep in it. */
            if (1 > tolerance)
                return CELL_OUTSIDE;
            far = false;
            continue;
        }
        double lo = -INFINITY, hi = -INFINITY;
        const double(*rows)[3] = s->rows + cone->first;
        for (int k = 0; k < cone->facets; k++) {
            double d = wr_dot3(rows[k], c);
            lo = fmax(lo, d - r);
            hi = fmax(hi, d + r);
        }
        for (int k = 0; k < cone->equalities; k++) {
            double d = fabs(wr_dot3(rows[cone->facets + k], c));
            lo = fmax(lo, d - r);
            hi = fmax(hi, d + r);
        }
        if (cone->full && hi < -tolerance)
            return CELL_OUTSIDE;
        if (!(lo > reach))
            far = false;
    }
    return far ? CELL_INSIDE : CELL_UNDECIDED;
}

/* The direction of the point (u, v) of cube face `face` (axis face / 2,
 * negative when odd), unit. */
static void face_direction(int face, double u, double v, double out[3])
{
    int axis = face / 2;
    out[axis] = face & 1 ? -1 : 1;
    out[(axis + 1) % 3] = u;
    out[(axis + 2) % 3] = v;
    wr_normalize3(out);
}

/* Decide the square of cells [i0, i0 + size) x [j0, j0 + size) of a face,
 * whole when it can be, else by quarters. */
static void fill(unsigned char *cells, int set, const set_rows *s, double tolerance, int face,
                 int i0, int j0, int size, size_t *decided)
{
    double u0 = -1 + 2.0 * i0 / SIDE, u1 = -1 + 2.0 * (i0 + size) / SIDE;
    double v0 = -1 + 2.0 * j0 / SIDE, v1 = -1 + 2.0 * (j0 + size) / SIDE;
    double centre[3];
    face_direction(face, (u0 + u1) / 2, (v0 + v1) / 2, centre);
    double r = 0;
    for (int corner = 0; corner < 4; corner++) {
        double p[3], d[3];
        face_direction(face, corner & 1 ? u1 : u0, corner & 2 ? v1 : v0, p);
        for (int k = 0; k < 3; k++)
            d[k] = p[k] - centre[k];
        r = fmax(r, wr_norm3(d));
    }
    int code = region_code(s, centre, r * (1 + 1e-9) + SLACK, tolerance);
    if (code != CELL_UNDECIDED || size == 1) {
        for (int i = i0; i < i0 + size; i++) {
            unsigned char *row = cells + ((size_t)face * SIDE + (size_t)i) * SIDE;
            for (int j = j0; j < j0 + size; j++)
                row[j] |= (unsigned char)(code << (2 * set));
        }
        if (code != CELL_UNDECIDED)
            *decided += (size_t)size * (size_t)size;
        return;
    }
    int half = size / 2;
    for (int q = 0; q < 4; q++)
        fill(cells, set, s, tolerance, face, i0 + (q & 1 ? half : 0), j0 + (q & 2 ? half : 0),
             half, decided);
}

wr_status wr_verdict_map_new(const wr_analysis *analysis, double tolerance, wr_verdict_map **out)
{
    *out = NULL;
    if (!(tolerance >= 0 && tolerance < 1) || !analysis->complete)
        return WR_INVALID;
    wr_verdict_map *m = calloc(1, sizeof *m);
    if (!m)
        return WR_NO_MEMORY;
    m->analysis = analysis;
    m->tolerance = tolerance;
    m->inverse_gyration = 1 / analysis->fixture->gyration_radius;
    m->cells = calloc(CELLS, 1);
    if (!m->cells) {
        wr_verdict_map_free(m);
        return WR_NO_MEMORY;
    }
    for (int set = 0; set < 2; set++) {
        set_rows rows;
        if (set_rows_make(analysis, (wr_set)set, &rows) != WR_OK) {
            wr_verdict_map_free(m);
            return WR_NO_MEMORY;
        }
        for (int face = 0; face < 6; face++)
            fill(m->cells, set, &rows, tolerance, face, 0, 0, SIDE, &m->decided);
        set_rows_release(&rows);
    }
    *out = m;
    return WR_OK;
}

void wr_verdict_map_free(wr_verdict_map *map)
{
    if (!map)
        return;
    free(map->cells);
    free(map);
}

size_t wr_verdict_map_bytes(const wr_verdict_map *map) { return sizeof *map + (size_t)CELLS; }

double wr_verdict_map_decided(const wr_verdict_map *map)
{
    return (double)map->decided / (2.0 * CELLS);
}

/* The cell of scaled direction h (any length in the fast range). */
static size_t cell_of(const double h[3])
{
    double a0 = fabs(h[0]), a1 = fabs(h[1]), a2 = fabs(h[2]);
    int axis = a0 >= a1 ? (a0 >= a2 ? 0 : 2) : (a1 >= a2 ? 1 : 2);
    double largest = fabs(h[axis]);
    int face = 2 * axis + (h[axis] < 0);
    double scale = SIDE / (2 * largest);
    /* u in [-1, 1] to a cell in [0, SIDE): the top edge belongs to the
     * last cell. */
    int i = (int)((h[(axis + 1) % 3] + largest) * scale);
    int j = (int)((h[(axis + 2) % 3] + largest) * scale);
    i = i < 0 ? 0 : i >= SIDE ? SIDE - 1 : i;
    j = j < 0 ? 0 : j >= SIDE ? SIDE - 1 : j;
    return ((size_t)face * SIDE + (size_t)i) * SIDE + (size_t)j;
}

/* One set's verdict: the cell's, else measured (x computed once, lazily). */
static wr_verdict set_verdict(const wr_verdict_map *m, int set, unsigned cell,
                              const double wrench[3], double x[3], bool *have_x)
{
    int code = (int)(cell >> (2 * set)) & 3;
    if (code == CELL_INSIDE)
        return WR_VERDICT_INSIDE;
    if (code == CELL_OUTSIDE)
        return WR_VERDICT_OUTSIDE;
    if (!*have_x) {
        wr_fixture_unit_wrench(m->analysis->fixture, wrench, x);
        *have_x = true;
    }
    return wr_set_verdict(m->analysis, set, x, m->tolerance);
}

wr_status wr_verdict_map_classify(const wr_verdict_map *m, const double wrench[3], wr_set set,
                                  wr_verdict *verdict)
{
    double h[3] = {wrench[0], wrench[1], wrench[2] * m->inverse_gyration};
    double largest = fmax(fabs(h[0]), fmax(fabs(h[1]), fabs(h[2])));
    /* Zero, huge, tiny and non-finite wrenches take the general path, which
     * answers or refuses them.  fmax drops a NaN beside a number, so a NaN
     * component is looked for in the sum (no overflow in the fast range). */
    if (!(largest >= FAST_LOW && largest <= FAST_HIGH) || isnan(h[0] + h[1] + h[2]))
        return wr_classify_verdict(m->analysis, wrench, set, m->tolerance, verdict);
    unsigned cell = m->cells[cell_of(h)];
    double x[3];
    bool have_x = false;
    if (set != WR_SET_BOTH) {
        *verdict = set_verdict(m, set, cell, wrench, x, &have_x);
        return WR_OK;
    }
    /* As wr_classify_verdict combines them. */
    wr_verdict goal = set_verdict(m, WR_SET_GOAL, cell, wrench, x, &have_x);
    if (goal == WR_VERDICT_OUTSIDE) {
        *verdict = goal;
        return WR_OK;
    }
    wr_verdict strong = set_verdict(m, WR_SET_STRONG, cell, wrench, x, &have_x);
    *verdict = strong == WR_VERDICT_OUTSIDE ? strong : goal == WR_VERDICT_INSIDE ? strong : goal;
    return WR_OK;
}
