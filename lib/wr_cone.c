/* wr_cone.c -- constraint strings and explicit cones G_X = M Q_X - W C_X.
 *
 * Scaled space.  With S = diag(1, 1, 1/rho) and h = S g, Newton-Euler
 * M q = g + W c becomes h = q' - sum_i (Wn_i c_in + Wt_i c_it), where
 * q' = S M q = m (a_x, a_y, rho alpha) and Wn_i = S W_in = (n_i, (r_i x n_i)/rho)
 * (fixel->normal_wrench).  Contact accelerations are a_in = Wn_i . q' / m, so
 * every acceleration row keeps its sign in q'.  The acceleration part of the
 * cone is Q' = {q' : rows}, the force part is cone(-(Wn_i + c_t/c_n Wt_i)) over
 * the friction-cone edges; G_X (scaled) = Q' + K. */
#include "wr_cone.h"
#include "wr_internal.h"

#include <stdlib.h>
#include <string.h>

static const char LETTERS[] = "saulrnm";

/* The bytes of the well-formed UTF-8 character at text[0] (at most 4), or
 * 0 when there is none: a message may quote it then, and '?' else. */
static size_t utf8_character(const unsigned char *text)
{
    if (text[0] < 0x80)
        return 1;
    size_t more = text[0] >= 0xc2 && text[0] <= 0xdf   ? 1
                  : text[0] >= 0xe0 && text[0] <= 0xef ? 2
                  : text[0] >= 0xf0 && text[0] <= 0xf4 ? 3
                                                       : 0;
    if (more == 0)
        return 0;
    for (size_t i = 1; i <= more; i++)
        if ((text[i] & 0xc0) != 0x80)
            return 0;
    /* Overlong three- and four-byte forms, surrogates, beyond U+10FFFF. */
    if ((text[0] == 0xe0 && text[1] < 0xa0) || (text[0] == 0xed && text[1] >= 0xa0) ||
        (text[0] == 0xf0 && text[1] < 0x90) || (text[0] == 0xf4 && text[1] >= 0x90))
        return 0;
    return more + 1;
}

wr_status wr_constraint_parse(const char *text, int fixel_count, wr_constraint *out,
                              wr_error *error)
{
    memset(out, 0, sizeof *out);
    /* Letters are characters: "sé" is two letters, not three bytes. */
    size_t characters = 0;
    for (const unsigned char *p = (const unsigned char *)text; *p; p++)
        characters += (*p & 0xc0) != 0x80;
    if (characters != (size_t)fixel_count) {
        wr_error_set(error, "", "has %zu letters, the fixture has %d fixels: one letter per fixel",
                     characters, fixel_count);
        return WR_INVALID;
    }
    const unsigned char *p = (const unsigned char *)text;
    for (int i = 0; i < fixel_count; i++) {
        if (*p >= 0x80 || !strchr(LETTERS, *p)) {
            size_t bytes = utf8_character(p);
            bool printable = bytes > 1 || (*p >= 32 && *p < 127);
            wr_error_set(error, "", "letter %d is '%.*s', not one of s a u l r n m (docs/MODEL.md section 2)",
                         i + 1, printable ? (int)bytes : 1, printable ? (const char *)p : "?");
            return WR_INVALID;
        }
        out->letters[i] = (char)*p++;
    }
    if (*p) { /* stray UTF-8 continuation bytes, which the count passed over */
        wr_error_set(error, "", "byte 0x%02x after letter %d is not a letter (not UTF-8)", *p,
                     fixel_count);
        return WR_INVALID;
    }
    out->length = fixel_count;
    return WR_OK;
}

void wr_constraint_format(const wr_constraint *constraint, char text[WR_CONSTRAINT_TEXT])
{
    memcpy(text, constraint->letters, (size_t)constraint->length);
    int n = constraint->length;
    if (constraint->pivot)
        text[n++] = constraint->pivot > 0 ? '+' : '-';
    text[n] = 0;
}

bool wr_letter_below(char x, char y)
{
    if (x == y)
        return true;
    if (y == 'u')
        return x == 's' || x == 'a';
    if (y == 'm')
        return x == 'l' || x == 'r' || x == 'n';
    return false;
}

bool wr_constraint_below(const wr_constraint *x, const wr_constraint *y)
{
    if (x->length != y->length || x->pivot != y->pivot ||
        x->strict_separation != y->strict_separation)
        return false;
    for (int i = 0; i < x->length; i++)
        if (!wr_letter_below(x->letters[i], y->letters[i]))
            return false;
    return true;
}

/* The acceleration rows of a constraint, all written as `row . q' <= 0`
 * (possibly strict) or `row . q' = 0`. */
typedef struct rows {
    int inequality_count;
    double inequalities[2 * WR_MAX_FIXELS + 1][3];
    bool strict[2 * WR_MAX_FIXELS + 1];
    int equality_count;
    double equalities[2 * WR_MAX_FIXELS][3];
} rows;

static void add_inequality(rows *r, const double v[3], double sign, bool strict)
{
    double *row = r->inequalities[r->inequality_count];
    for (int k = 0; k < 3; k++)
        row[k] = sign * v[k];
    wr_normalize3(row);
    r->strict[r->inequality_count++] = strict;
}

static void add_equality(rows *r, const double v[3])
{
    double *row = r->equalities[r->equality_count++];
    wr_copy3(v, row);
    wr_normalize3(row);
}

static void acceleration_rows(const wr_fixture *f, const wr_constraint *c, rows *r)
{
    memset(r, 0, sizeof *r);
    for (int i = 0; i < c->length; i++) {
        const double *wn = f->fixels[i].normal_wrench, *wt = f->fixels[i].tangent_wrench;
        switch (c->letters[i]) {
        case 's': /* a_n >= 0 (> 0 as a mode) */
            add_inequality(r, wn, -1, c->strict_separation);
            break;
        case 'a': /* a_n < 0 */
            add_inequality(r, wn, 1, true);
            break;
        case 'l': /* a_n = 0, a_t > 0 */
            add_equality(r, wn);
            add_inequality(r, wt, -1, true);
            break;
        case 'r': /* a_n = 0, a_t < 0 */
            add_equality(r, wn);
            add_inequality(r, wt, 1, true);
            break;
        case 'n': /* a_n = 0, a_t = 0 */
            add_equality(r, wn);
            add_equality(r, wt);
            break;
        case 'm': /* a_n = 0 */
            add_equality(r, wn);
            break;
        default: /* u: free */
            break;
        }
    }
    if (c->pivot) {
        /* Rotation in the direction of the pivot: sign(alpha) = pivot. */
        double e[3] = {0, 0, 1};
        add_inequality(r, e, -c->pivot, true);
    }
}

/* Friction-cone edges as wrench generators -(Wn + (c_t/c_n) Wt), with the
 * unit-coefficient forces they stand for. */
static int force_generators(const wr_fixture *f, const wr_constraint *c, double (*gens)[3],
                            wr_generator_origin *origins)
{
    int count = 0;
    for (int i = 0; i < c->length; i++) {
        const wr_fixel *fixel = &f->fixels[i];
        double ratios[2];
        int ratio_count = 0;
        switch (c->letters[i]) {
        /* With friction intervals (docs/PROTOCOL.md) the union over the box
         * of the coefficients: l and r take every force between the
         * kinetic edges at the two bounds, n and m the static cone at the
         * upper bound (which contains every smaller one).  A point interval
         * gives the one edge of the single coefficient. */
        case 'l': /* c_t = -mu_k c_n: friction opposes sliding along +t */
            ratios[ratio_count++] = -fixel->mu_kinetic;
            if (fixel->mu_kinetic_min < fixel->mu_kinetic)
                ratios[ratio_count++] = -fixel->mu_kinetic_min;
            break;
        case 'r':
            ratios[ratio_count++] = fixel->mu_kinetic;
            if (fixel->mu_kinetic_min < fixel->mu_kinetic)
                ratios[ratio_count++] = fixel->mu_kinetic_min;
            break;
        case 'n':
        case 'm':
            ratios[ratio_count++] = fixel->mu_static;
            ratios[ratio_count++] = -fixel->mu_static;
            break;
        default:
            break;
        }
        for (int e = 0; e < ratio_count; e++) {
            double *g = gens[count];
            for (int k = 0; k < 3; k++)
                g[k] = -(fixel->normal_wrench[k] + ratios[e] * fixel->tangent_wrench[k]);
            double length = wr_normalize3(g);
            origins[count].fixel = i;
            origins[count].normal_force = 1 / length;
            origins[count].tangent_force = ratios[e] / length;
            count++;
        }
    }
    return count;
}

/* Does the strict row vanish on every generator (so on their whole cone)? */
static bool vanishes(const double row[3], const double (*gens)[3], int count)
{
    for (int i = 0; i < count; i++)
        if (fabs(wr_dot3(row, gens[i])) > WR_SIDE_TOLERANCE)
            return false;
    return true;
}

/* By density: a cone C whose closure is cone(gens) meets the strict rows iff
 * no strict row vanishes identically on the closure (each strict row is <= 0
 * there and is either < 0 on a dense subset or zero everywhere). */
static bool strict_rows_met(const rows *r, const double (*gens)[3], int count)
{
    for (int i = 0; i < r->inequality_count; i++)
        if (r->strict[i] && vanishes(r->inequalities[i], gens, count))
            return false;
    return true;
}

static bool has_strict_rows(const rows *r)
{
    for (int i = 0; i < r->inequality_count; i++)
        if (r->strict[i])
            return true;
    return false;
}

/* g = 0 is admitted iff some q' in Q' equals a contact wrench +W c: decide on
 * D = closure(Q') intersected with cone(W c). */
static bool zero_admitted(const rows *r, const double (*force_gens)[3], int force_count)
{
    if (!has_strict_rows(r))
        return true; /* q = 0, c = 0 */
    double contact[WR_HULL_MAX][3];
    for (int i = 0; i < force_count; i++)
        for (int k = 0; k < 3; k++)
            contact[i][k] = -force_gens[i][k];
    wr_hrep contact_hull;
    wr_hull_from_generators((const double (*)[3])contact, force_count, &contact_hull);
    double inequalities[WR_HULL_MAX][3], equalities[2 * WR_MAX_FIXELS + 3][3];
    int ni = 0, ne = 0;
    for (int i = 0; i < r->inequality_count; i++)
        wr_copy3(r->inequalities[i], inequalities[ni++]);
    for (int i = 0; i < contact_hull.facet_count && ni < WR_HULL_MAX; i++)
        wr_copy3(contact_hull.facets[i], inequalities[ni++]);
    for (int i = 0; i < r->equality_count; i++)
        wr_copy3(r->equalities[i], equalities[ne++]);
    for (int i = 0; i < contact_hull.equality_count; i++)
        wr_copy3(contact_hull.equalities[i], equalities[ne++]);
    double gens[WR_HULL_MAX][3];
    int count = wr_hull_generators_of_rows((const double (*)[3])inequalities, ni,
                                           (const double (*)[3])equalities, ne, gens,
                                           WR_HULL_MAX);
    return strict_rows_met(r, (const double (*)[3])gens, count);
}

bool wr_constraint_kinematically_feasible(const wr_fixture *fixture,
                                          const wr_constraint *constraint)
{
    rows r;
    acceleration_rows(fixture, constraint, &r);
    double gens[WR_HULL_MAX][3];
    int count = wr_hull_generators_of_rows((const double (*)[3])r.inequalities,
                                           r.inequality_count,
                                           (const double (*)[3])r.equalities,
                                           r.equality_count, gens, WR_HULL_MAX);
    return strict_rows_met(&r, (const double (*)[3])gens, count);
}

int wr_cone_acceleration(const wr_fixture *fixture, const wr_constraint *constraint,
                         double (*generators)[3])
{
    rows r;
    acceleration_rows(fixture, constraint, &r);
    int count = wr_hull_generators_of_rows((const double (*)[3])r.inequalities,
                                           r.inequality_count,
                                           (const double (*)[3])r.equalities, r.equality_count,
                                           generators, WR_HULL_MAX);
    return strict_rows_met(&r, (const double (*)[3])generators, count) ? count : -1;
}

wr_status wr_cone_build(wr_cone *cone, const wr_fixture *fixture,
                        const wr_constraint *constraint)
{
    double acceleration[WR_HULL_MAX][3];
    int count = wr_cone_acceleration(fixture, constraint, acceleration);
    return wr_cone_build_from(cone, fixture, constraint, (const double (*)[3])acceleration, count);
}

wr_status wr_cone_build_from(wr_cone *cone, const wr_fixture *fixture,
                             const wr_constraint *constraint, const double (*acceleration)[3],
                             int accel_count)
{
    memset(cone, 0, sizeof *cone);
    cone->constraint = *constraint;
    if (accel_count < 0) {
        cone->empty = true;
        cone->dimension = -1;
        return WR_OK;
    }

    rows r;
    acceleration_rows(fixture, constraint, &r);
    double gens[WR_HULL_MAX][3];
    wr_generator_origin origins[WR_HULL_MAX];
    memcpy(gens, acceleration, (size_t)accel_count * sizeof gens[0]);
    for (int i = 0; i < accel_count; i++)
        origins[i] = (wr_generator_origin){-1, 0, 0};
    int force_count = force_generators(fixture, constraint, gens + accel_count,
                                       origins + accel_count);
    int total = accel_count + force_count;

    cone->zero_admitted = zero_admitted(&r, (const double (*)[3])(gens + accel_count), force_count);

    wr_hrep h;
    wr_hull_from_generators((const double (*)[3])gens, total, &h);
    double rays[WR_HULL_MAX][3];
    int ray_count = wr_hull_rays(&h, rays, WR_HULL_MAX);

    /* One block for the variable-length arrays. */
    size_t vectors = (size_t)(h.facet_count + ray_count + total);
    char *block = malloc(vectors * sizeof(double[3]) + (size_t)total * sizeof(wr_generator_origin) +
                         (size_t)h.facet_count * sizeof(bool) + 1);
    if (!block)
        return WR_NO_MEMORY;
    cone->facets = (double (*)[3])block;
    cone->rays = cone->facets + h.facet_count;
    cone->generators = cone->rays + ray_count;
    cone->origins = (wr_generator_origin *)(cone->generators + total);
    cone->facet_open = (bool *)(cone->origins + total);

    cone->dimension = h.dimension;
    cone->equality_count = h.equality_count;
    memcpy(cone->equalities, h.equalities, sizeof h.equalities);
    cone->facet_count = h.facet_count;
    memcpy(cone->facets, h.facets, (size_t)h.facet_count * sizeof h.facets[0]);
    cone->ray_count = ray_count;
    memcpy(cone->rays, rays, (size_t)ray_count * sizeof rays[0]);
    cone->generator_count = total;
    memcpy(cone->generators, gens, (size_t)total * sizeof gens[0]);
    memcpy(cone->origins, origins, (size_t)total * sizeof origins[0]);

    /* A facet is open when the face of closure(Q') it exposes misses Q':
     * G_X meets the facet only through q' on that face. */
    for (int i = 0; i < h.facet_count; i++) {
        double face[WR_HULL_MAX][3];
        int face_count = 0;
        for (int j = 0; j < accel_count; j++)
            if (fabs(wr_dot3(h.facets[i], gens[j])) <= WR_SIDE_TOLERANCE)
                wr_copy3(gens[j], face[face_count++]);
        cone->facet_open[i] = !strict_rows_met(&r, (const double (*)[3])face, face_count);
    }
    return WR_OK;
}

void wr_cone_release(wr_cone *cone)
{
    if (!cone)
        return;
    free(cone->facets);
    cone->facets = NULL;
}

double wr_cone_signed_distance(const wr_cone *cone, const double x[3], double projection[3])
{
    double scratch[3];
    if (!projection)
        projection = scratch;
    if (cone->empty) {
        projection[0] = projection[1] = projection[2] = 0;
        return INFINITY;
    }
    wr_hull_view h = {cone->dimension,
                      cone->equality_count, (const double (*)[3])cone->equalities,
                      cone->facet_count,    (const double (*)[3])cone->facets,
                      cone->ray_count,      (const double (*)[3])cone->rays};
    double distance = wr_hull_distance(&h, x, projection);
    if (distance > 0)
        return distance;
    wr_copy3(x, projection);
    return -wr_hull_depth(&h, x);
}

void wr_newton_euler_wrench(const wr_fixture *fixture, const double acceleration[3],
                            const double (*force)[2], double wrench[3])
{
    /* g = M q - sum_i (W_in c_in + W_it c_it), W_i = (d, r_i x d). */
    wrench[0] = fixture->mass * acceleration[0];
    wrench[1] = fixture->mass * acceleration[1];
    wrench[2] = fixture->inertia * acceleration[2];
    for (int i = 0; i < fixture->fixel_count; i++) {
        const wr_fixel *fixel = &fixture->fixels[i];
        double r[2] = {fixel->at[0] - fixture->com[0], fixel->at[1] - fixture->com[1]};
        double d[2] = {fixel->normal[0] * force[i][0] + fixel->tangent[0] * force[i][1],
                       fixel->normal[1] * force[i][0] + fixel->tangent[1] * force[i][1]};
        wrench[0] -= d[0];
        wrench[1] -= d[1];
        wrench[2] -= r[0] * d[1] - r[1] * d[0];
    }
}

void wr_witness_friction(const wr_fixture *fixture, const wr_constraint *constraint,
                         wr_witness *witness)
{
    for (int i = 0; i < fixture->fixel_count; i++) {
        const wr_fixel *fixel = &fixture->fixels[i];
        char letter = i < constraint->length ? constraint->letters[i] : 'u';
        double cn = witness->force[i][0], ct = witness->force[i][1];
        if (letter == 'n' || letter == 'm') {
            witness->friction[i] = fixel->mu_static;
        } else if (letter == 'l' || letter == 'r') {
            double lo = fixel->mu_kinetic_min, hi = fixel->mu_kinetic;
            double mu = lo;
            if (lo < hi && cn > 0) {
                mu = (letter == 'l' ? -ct : ct) / cn;
                mu = !(mu >= lo) ? lo : mu > hi ? hi : mu; /* NaN: lo */
            }
            witness->friction[i] = mu;
        } else {
            witness->friction[i] = NAN;
        }
    }
}

void wr_cone_witness(const wr_cone *cone, const wr_fixture *fixture, const double point[3],
                     wr_witness *out)
{
    memset(out, 0, sizeof *out);
    if (cone->empty)
        return;
    double lambda[WR_HULL_MAX];
    wr_nnls3((const double (*)[3])cone->generators, cone->generator_count, point, lambda);
    double scaled_acceleration[3] = {0, 0, 0};
    for (int j = 0; j < cone->generator_count; j++) {
        const wr_generator_origin *o = &cone->origins[j];
        if (o->fixel < 0) {
            for (int k = 0; k < 3; k++)
                scaled_acceleration[k] += lambda[j] * cone->generators[j][k];
        } else {
            out->force[o->fixel][0] += lambda[j] * o->normal_force;
            out->force[o->fixel][1] += lambda[j] * o->tangent_force;
        }
    }
    /* q' = m (a_x, a_y, rho alpha). */
    out->acceleration[0] = scaled_acceleration[0] / fixture->mass;
    out->acceleration[1] = scaled_acceleration[1] / fixture->mass;
    out->acceleration[2] = scaled_acceleration[2] / (fixture->mass * fixture->gyration_radius);
    wr_newton_euler_wrench(fixture, out->acceleration, (const double (*)[2])out->force,
                           out->wrench);
    wr_witness_friction(fixture, &cone->constraint, out);
}
