/* wr_hull.c -- polyhedral convex cones in R^3 by elementary geometry.
 *
 * Why no polyhedral library: in three dimensions every facet of a cone is
 * spanned by two of its generators and every extreme ray is the meeting line
 * of two facets, so cross products enumerate both exactly; and distances
 * follow from the face structure.  See docs/MODEL.md section 2.
 *
 * Invariant: all vectors passed between these routines are unit length (or
 * zero, which is dropped), so the tolerances in wr_internal.h are absolute. */
#include "wr_internal.h"

#include <string.h>

/* Orthonormal basis of span(v), by Gram-Schmidt taking the largest residual
 * first (so nearly dependent vectors do not set the direction).  Returns the
 * rank; basis[rank..2] are not written. */
static int span_basis(const double (*v)[3], int count, double basis[3][3])
{
    double residual[WR_HULL_MAX][3];
    memcpy(residual, v, (size_t)count * sizeof residual[0]);
    int rank = 0;
    while (rank < 3) {
        int best = -1;
        double best_norm = WR_RANK_TOLERANCE;
        for (int i = 0; i < count; i++) {
            double n = wr_norm3(residual[i]);
            if (n > best_norm) {
                best_norm = n;
                best = i;
            }
        }
        if (best < 0)
            break;
        double b[3];
        wr_copy3(residual[best], b);
        wr_normalize3(b);
        /* Orthogonalise twice: one pass loses orthogonality for nearly
         * dependent vectors. */
        for (int pass = 0; pass < 2; pass++)
            for (int j = 0; j < rank; j++) {
                double d = wr_dot3(b, basis[j]);
                for (int k = 0; k < 3; k++)
                    b[k] -= d * basis[j][k];
            }
        wr_normalize3(b);
        wr_copy3(b, basis[rank++]);
        for (int i = 0; i < count; i++) {
            double d = wr_dot3(residual[i], b);
            for (int k = 0; k < 3; k++)
                residual[i][k] -= d * b[k];
        }
    }
    return rank;
}

/* Orthonormal basis of the orthogonal complement of an orthonormal set. */
static void complement_basis(double basis[3][3], int rank, double out[3][3])
{
    if (rank == 3)
        return;
    if (rank == 2) {
        wr_cross3(basis[0], basis[1], out[0]);
        wr_normalize3(out[0]);
        return;
    }
    if (rank == 0) {
        double identity[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
        memcpy(out, identity, sizeof identity);
        return;
    }
    /* rank 1: the axis least aligned with basis[0], made orthogonal. */
    int axis = 0;
    for (int k = 1; k < 3; k++)
        if (fabs(basis[0][k]) < fabs(basis[0][axis]))
            axis = k;
    double e[3] = {0, 0, 0};
    e[axis] = 1;
    double d = wr_dot3(e, basis[0]);
    for (int k = 0; k < 3; k++)
        out[0][k] = e[k] - d * basis[0][k];
    wr_normalize3(out[0]);
    wr_cross3(basis[0], out[0], out[1]);
    wr_normalize3(out[1]);
}

/* Append a unit vector unless it repeats one already listed. */
static bool add_unique(double (*list)[3], int *count, int max, const double v[3])
{
    for (int i = 0; i < *count; i++) {
        double d[3] = {list[i][0] - v[0], list[i][1] - v[1], list[i][2] - v[2]};
        if (wr_norm3(d) < 1e-7)
            return true;
    }
    if (*count >= max)
        return false;
    wr_copy3(v, list[(*count)++]);
    return true;
}

/* Does every vector satisfy f . v <= tolerance? */
static bool supports(const double f[3], const double (*v)[3], int count)
{
    for (int i = 0; i < count; i++)
        if (wr_dot3(f, v[i]) > WR_SIDE_TOLERANCE)
            return false;
    return true;
}

/* Try f and -f as a supporting row of the generators. */
static void try_facet(const double f[3], const double (*v)[3], int count, wr_hrep *out)
{
    double negative[3] = {-f[0], -f[1], -f[2]};
    if (supports(f, v, count))
        add_unique(out->facets, &out->facet_count, WR_HULL_MAX, f);
    if (supports(negative, v, count))
        add_unique(out->facets, &out->facet_count, WR_HULL_MAX, negative);
}

bool wr_hull_from_generators(const double (*generators)[3], int count, wr_hrep *out)
{
    memset(out, 0, sizeof *out);
    double v[WR_HULL_MAX][3];
    int n = 0;
    for (int i = 0; i < count; i++) {
        double u[3];
        wr_copy3(generators[i], u);
        if (wr_normalize3(u) < 1e-12)
            continue;
        if (!add_unique(v, &n, WR_HULL_MAX, u))
            return false;
    }
    double basis[3][3];
    int rank = span_basis((const double (*)[3])v, n, basis);
    out->dimension = rank;
    out->equality_count = 3 - rank;
    complement_basis(basis, rank, out->equalities);

    if (rank == 3) {
        /* Each facet holds two independent generators: its normal is their
         * cross product, with every generator on one side. */
        for (int i = 0; i < n; i++)
            for (int j = i + 1; j < n; j++) {
                double f[3];
                wr_cross3(v[i], v[j], f);
                if (wr_normalize3(f) < 1e-9)
                    continue;
                try_facet(f, (const double (*)[3])v, n, out);
            }
    } else if (rank == 2) {
        /* In the plane with normal p, a facet is a line through a generator. */
        for (int i = 0; i < n; i++) {
            double f[3];
            wr_cross3(out->equalities[0], v[i], f);
            if (wr_normalize3(f) < 1e-9)
                continue;
            try_facet(f, (const double (*)[3])v, n, out);
        }
    } else if (rank == 1) {
        bool positive = false, negative = false;
        for (int i = 0; i < n; i++) {
            double d = wr_dot3(v[i], basis[0]);
            positive |= d > 0;
            negative |= d < 0;
        }
        if (positive != negative) {
            double f[3] = {basis[0][0], basis[0][1], basis[0][2]};
            if (positive)
                for (int k = 0; k < 3; k++)
                    f[k] = -f[k];
            wr_copy3(f, out->facets[out->facet_count++]);
        }
    }
    return true;
}

int wr_hull_null_space(const double (*rows)[3], int count, double basis[3][3])
{
    double span[3][3];
    int rank = span_basis(rows, count, span);
    complement_basis(span, rank, basis);
    return 3 - rank;
}

int wr_hull_generators_of_rows(const double (*inequalities)[3], int inequality_count,
                               const double (*equalities)[3], int equality_count,
                               double (*generators)[3], int max)
{
    /* The polar cone {y : y . x <= 0 for all x in C} of C = {E x = 0, A x <= 0}
     * is cone(rows of A) + span(rows of E); the polar of its hull
     * {F y <= 0, E' y = 0} is C again = cone(F) + span(E'). */
    double polar[WR_HULL_MAX][3];
    int n = 0;
    for (int i = 0; i < inequality_count && n < WR_HULL_MAX; i++)
        wr_copy3(inequalities[i], polar[n++]);
    for (int i = 0; i < equality_count && n + 1 < WR_HULL_MAX; i++) {
        wr_copy3(equalities[i], polar[n++]);
        for (int k = 0; k < 3; k++)
            polar[n][k] = -equalities[i][k];
        n++;
    }
    wr_hrep h;
    wr_hull_from_generators((const double (*)[3])polar, n, &h);
    int written = 0;
    for (int i = 0; i < h.facet_count && written < max; i++)
        wr_copy3(h.facets[i], generators[written++]);
    for (int i = 0; i < h.equality_count && written + 1 < max; i++) {
        wr_copy3(h.equalities[i], generators[written++]);
        for (int k = 0; k < 3; k++)
            generators[written][k] = -h.equalities[i][k];
        written++;
    }
    return written;
}

/* Is r in the cone (all facets and equalities within tolerance)? */
static bool contains(const wr_hrep *h, const double r[3], double tolerance)
{
    for (int i = 0; i < h->facet_count; i++)
        if (wr_dot3(h->facets[i], r) > tolerance)
            return false;
    for (int i = 0; i < h->equality_count; i++)
        if (fabs(wr_dot3(h->equalities[i], r)) > tolerance)
            return false;
    return true;
}

/* Add whichever of +r, -r lies in the cone. */
static void add_ray_if_inside(const wr_hrep *h, double r[3], double (*rays)[3], int *count,
                              int max)
{
    if (wr_normalize3(r) < 1e-9)
        return;
    for (int sign = 0; sign < 2; sign++) {
        if (contains(h, r, WR_SIDE_TOLERANCE))
            add_unique(rays, count, max, r);
        for (int k = 0; k < 3; k++)
            r[k] = -r[k];
    }
}

int wr_hull_rays(const wr_hrep *h, double (*rays)[3], int max)
{
    /* Lineality space: the null space of every facet and equality row. */
    double rows[WR_HULL_MAX + 3][3];
    int row_count = 0;
    for (int i = 0; i < h->facet_count; i++)
        wr_copy3(h->facets[i], rows[row_count++]);
    for (int i = 0; i < h->equality_count; i++)
        wr_copy3(h->equalities[i], rows[row_count++]);
    double row_basis[3][3], lineality[3][3];
    int row_rank = span_basis((const double (*)[3])rows, row_count, row_basis);
    complement_basis(row_basis, row_rank, lineality);
    int lineality_dimension = 3 - row_rank;

    int count = 0;
    for (int i = 0; i < lineality_dimension && count + 1 < max; i++) {
        wr_copy3(lineality[i], rays[count++]);
        for (int k = 0; k < 3; k++)
            rays[count][k] = -lineality[i][k];
        count++;
    }
    int pointed = h->dimension - lineality_dimension;
    if (pointed == 1) {
        /* A half-line (or half-space within the span): one facet; the ray
         * points away from it. */
        if (h->facet_count > 0) {
            double r[3] = {-h->facets[0][0], -h->facets[0][1], -h->facets[0][2]};
            add_ray_if_inside(h, r, rays, &count, max);
        }
    } else if (pointed == 2) {
        /* A wedge: in a plane (normal = the equality) or around a line (the
         * lineality); each facet contributes the ray along its edge. */
        const double *axis = h->dimension == 2 ? h->equalities[0] : lineality[0];
        for (int i = 0; i < h->facet_count; i++) {
            double r[3];
            wr_cross3(axis, h->facets[i], r);
            add_ray_if_inside(h, r, rays, &count, max);
        }
    } else if (pointed == 3) {
        for (int i = 0; i < h->facet_count; i++)
            for (int j = i + 1; j < h->facet_count; j++) {
                double r[3];
                wr_cross3(h->facets[i], h->facets[j], r);
                add_ray_if_inside(h, r, rays, &count, max);
            }
    }
    return count;
}

double wr_hull_distance(const wr_hull_view *h, const double x[3], double projection[3])
{
    const double (*rays)[3] = h->rays;
    int ray_count = h->ray_count;
    /* Split x into its part in the span and the part orthogonal to it. */
    double y[3];
    wr_copy3(x, y);
    double off_span2 = 0;
    for (int i = 0; i < h->equality_count; i++) {
        double d = wr_dot3(h->equalities[i], x);
        off_span2 += d * d;
        for (int k = 0; k < 3; k++)
            y[k] -= d * h->equalities[i][k];
    }
    bool inside = true;
    for (int i = 0; i < h->facet_count && inside; i++)
        inside = wr_dot3(h->facets[i], y) <= 0;
    if (inside) {
        wr_copy3(y, projection);
        return sqrt(off_span2);
    }
    /* The nearest point lies in the relative interior of some face: the apex,
     * an edge ray, or a facet.  Every candidate that lies in the cone is an
     * upper bound and the true nearest point is among them. */
    double best = wr_dot3(y, y);
    projection[0] = projection[1] = projection[2] = 0;
    for (int i = 0; i < ray_count; i++) {
        double t = wr_dot3(y, rays[i]);
        if (t <= 0)
            continue;
        double d2 = wr_dot3(y, y) - t * t;
        if (d2 < best) {
            best = d2;
            for (int k = 0; k < 3; k++)
                projection[k] = t * rays[i][k];
        }
    }
    for (int i = 0; i < h->facet_count; i++) {
        double s = wr_dot3(h->facets[i], y);
        if (s <= 0 || s * s >= best)
            continue;
        double z[3] = {y[0] - s * h->facets[i][0], y[1] - s * h->facets[i][1],
                       y[2] - s * h->facets[i][2]};
        bool feasible = true;
        for (int j = 0; j < h->facet_count && feasible; j++)
            feasible = j == i || wr_dot3(h->facets[j], z) <= 1e-12;
        if (feasible) {
            best = s * s;
            wr_copy3(z, projection);
        }
    }
    if (best < 0)
        best = 0;
    return sqrt(off_span2 + best);
}

double wr_hull_depth(const wr_hull_view *h, const double x[3])
{
    if (h->dimension < 3)
        return 0;
    if (h->facet_count == 0)
        return wr_norm3(x);
    double depth = INFINITY;
    for (int i = 0; i < h->facet_count; i++)
        depth = fmin(depth, -wr_dot3(h->facets[i], x));
    return depth > 0 ? depth : 0;
}

/* Least squares over the passive columns (at most 3, independent), by QR:
 * modified Gram-Schmidt, orthogonalised twice.  The normal equations would
 * square the columns' condition number, and nearly parallel generators
 * (a normal tilted by 1e-7) then give witnesses 10% off. */
static bool solve_passive(const double (*columns)[3], const int *passive, int count,
                          const double y[3], double *z)
{
    double q[3][3], r[3][3] = {{0}};
    for (int j = 0; j < count; j++) {
        wr_copy3(columns[passive[j]], q[j]);
        for (int pass = 0; pass < 2; pass++)
            for (int i = 0; i < j; i++) {
                double d = wr_dot3(q[i], q[j]);
                r[i][j] += d;
                for (int k = 0; k < 3; k++)
                    q[j][k] -= d * q[i][k];
            }
        r[j][j] = wr_normalize3(q[j]);
        if (r[j][j] < 1e-14 * wr_norm3(columns[passive[j]]))
            return false; /* dependent on the others */
    }
    /* R z = Q^T y, by back substitution. */
    for (int i = count - 1; i >= 0; i--) {
        double sum = wr_dot3(q[i], y);
        for (int j = i + 1; j < count; j++)
            sum -= r[i][j] * z[j];
        z[i] = sum / r[i][i];
    }
    return true;
}

double wr_nnls3(const double (*columns)[3], int count, const double y[3], double *lambda)
{
    /* Lawson and Hanson's active-set method.  The passive columns stay
     * linearly independent (a column enters only when the residual, which
     * is orthogonal to their span, has a positive component along it), so
     * at most three are passive in R^3. */
    int passive[3];
    int passive_count = 0;
    bool blocked[WR_HULL_MAX] = {false}; /* dependent on the passive set */
    for (int j = 0; j < count; j++)
        lambda[j] = 0;
    double residual[3];
    wr_copy3(y, residual);
    for (int iteration = 0; iteration < 3 * count + 10; iteration++) {
        int enter = -1;
        double best = 1e-13;
        for (int j = 0; j < count; j++) {
            bool is_passive = false;
            for (int p = 0; p < passive_count; p++)
                is_passive |= passive[p] == j;
            double w = wr_dot3(columns[j], residual);
            if (!is_passive && j < WR_HULL_MAX && !blocked[j] && w > best) {
                best = w;
                enter = j;
            }
        }
        if (enter < 0 || passive_count == 3)
            break;
        passive[passive_count++] = enter;
        for (;;) {
            double z[3];
            if (!solve_passive(columns, passive, passive_count, y, z)) {
                blocked[enter] = true; /* dependent: the column cannot help */
                passive_count--;
                break;
            }
            bool positive = true;
            for (int p = 0; p < passive_count; p++)
                positive &= z[p] > 0;
            if (positive) {
                for (int p = 0; p < passive_count; p++)
                    lambda[passive[p]] = z[p];
                break;
            }
            /* Step towards z until a passive coefficient reaches zero. */
            double alpha = 1;
            for (int p = 0; p < passive_count; p++)
                if (z[p] <= 0) {
                    double l = lambda[passive[p]];
                    double a = l / (l - z[p]);
                    if (a < alpha)
                        alpha = a;
                }
            int kept = 0;
            for (int p = 0; p < passive_count; p++) {
                double *l = &lambda[passive[p]];
                *l += alpha * (z[p] - *l);
                if (*l > 1e-15)
                    passive[kept++] = passive[p];
                else
                    *l = 0;
            }
            passive_count = kept;
            if (passive_count == 0)
                break;
        }
        wr_copy3(y, residual);
        for (int j = 0; j < count; j++)
            for (int k = 0; k < 3; k++)
                residual[k] -= lambda[j] * columns[j][k];
    }
    return wr_norm3(residual);
}
