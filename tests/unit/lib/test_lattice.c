/* test_lattice.c -- designs on a modular fixture plate (lib/wr_lattice.h):
 * every design is valid (pegs at lattice points, each touching the part at
 * its fixel, none overlapping it), and on a square and a triangle the
 * enumeration finds exactly the designs a brute force over poses finds:
 * for every hole triple, theta on a fine grid, the translation putting
 * pegs 1 and 2 on two edges, and peg 3's clearance from the whole polygon
 * (the distance to its nearest edge, whichever it is, minus the radius)
 * bisected wherever it changes sign. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "test_util.h"


static void run_lattice(const wr_fixture *body, const wr_lattice *lattice, wr_lattice_job **job)
{
    wr_error error;
    assert_int_equal(wr_lattice_job_new(body, lattice, job, &error), WR_OK);
    bool done = false;
    while (!done)
        assert_int_equal(wr_lattice_job_run(*job, 5000, NULL, NULL, &done), WR_OK);
}

/* ---- the brute force: the polygon's own geometry, nothing of the library's ---- */

typedef struct poly {
    const double (*v)[2];
    int n;
    int orientation; /* +1 counter-clockwise */
} poly;

static double segment_distance(const double a[2], const double b[2], const double p[2],
                               double *s)
{
    double d[2] = {b[0] - a[0], b[1] - a[1]};
    double t = ((p[0] - a[0]) * d[0] + (p[1] - a[1]) * d[1]) / (d[0] * d[0] + d[1] * d[1]);
    *s = t;
    t = fmin(1, fmax(0, t));
    return hypot(p[0] - a[0] - t * d[0], p[1] - a[1] - t * d[1]);
}

static bool inside(const poly *P, const double p[2])
{
    bool in = false;
    for (int i = 0, j = P->n - 1; i < P->n; j = i++)
        if ((P->v[i][1] > p[1]) != (P->v[j][1] > p[1]) &&
            p[0] < (P->v[j][0] - P->v[i][0]) * (p[1] - P->v[i][1]) / (P->v[j][1] - P->v[i][1]) +
                       P->v[i][0])
            in = !in;
    return in;
}

/* Distance to the polygon's boundary and the nearest edge's parameter. */
static double clearance(const poly *P, const double p[2], double *s)
{
    double best = INFINITY;
    *s = 0;
    for (int i = 0; i < P->n; i++) {
        double t, d = segment_distance(P->v[i], P->v[(i + 1) % P->n], p, &t);
        if (d < best) {
            best = d;
            *s = t;
        }
    }
    return best;
}

/* Outward unit normal of edge e. */
static void outward(const poly *P, int e, double n[2])
{
    const double *a = P->v[e], *b = P->v[(e + 1) % P->n];
    double d[2] = {b[0] - a[0], b[1] - a[1]}, l = hypot(d[0], d[1]);
    n[0] = d[1] / l * P->orientation;
    n[1] = -d[0] / l * P->orientation;
}

typedef struct found {
    int holes[3][2];
    double theta;
    double at[2]; /* the pose's translation */
} found;

/* Peg `free`'s signed clearance at theta, the other two pegs (u, v) put
 * on edges e1, e2; NAN when that cannot be (parallel edges). */
static double free_gap(const poly *P, const double pegs[3][2], int u, int v, int free, int e1,
                       int e2, double r, double theta, double tau[2], double q[3][2])
{
    double n1[2], n2[2];
    outward(P, e1, n1);
    outward(P, e2, n2);
    double det = n1[0] * n2[1] - n1[1] * n2[0];
    if (fabs(det) < 1e-9)
        return NAN;
    double c = cos(theta), s = sin(theta), p[3][2];
    for (int m = 0; m < 3; m++) {
        p[m][0] = c * pegs[m][0] + s * pegs[m][1];
        p[m][1] = -s * pegs[m][0] + c * pegs[m][1];
    }
    /* n_m . (p_m - tau) = n_m . a_m + r */
    double b1 = n1[0] * p[u][0] + n1[1] * p[u][1] - (n1[0] * P->v[e1][0] + n1[1] * P->v[e1][1] + r);
    double b2 = n2[0] * p[v][0] + n2[1] * p[v][1] - (n2[0] * P->v[e2][0] + n2[1] * P->v[e2][1] + r);
    tau[0] = (b1 * n2[1] - b2 * n1[1]) / det;
    tau[1] = (n1[0] * b2 - n2[0] * b1) / det;
    for (int m = 0; m < 3; m++) {
        q[m][0] = p[m][0] - tau[0];
        q[m][1] = p[m][1] - tau[1];
    }
    double t, d = clearance(P, q[free], &t);
    return inside(P, q[free]) ? -d - r : d - r;
}

static bool on_edge_interior(const poly *P, int e, const double q[2])
{
    double s;
    segment_distance(P->v[e], P->v[(e + 1) % P->n], q, &s);
    return s >= -1e-9 && s <= 1 + 1e-9;
}

static int brute_force(const poly *P, const wr_lattice *L, double size, found *out, int most)
{
    int count = 0;
    double r = L->peg_radius, reach = size + 2 * r + 1e-9;
    enum { STEPS = 7200 };
    /* Holes after (0, 0) in (j, i) order, within reach. */
    int holes[4096][2], h = 0;
    for (int j = 0; j < L->extent[1]; j++)
        for (int i = -(L->extent[0] - 1); i < L->extent[0]; i++)
            if ((j > 0 || i > 0) && hypot(i * L->pitch, j * L->pitch) <= reach) {
                holes[h][0] = i;
                holes[h][1] = j;
                h++;
            }
    for (int x = 0; x < h; x++)
        for (int y = x + 1; y < h; y++) {
            int lo = fmin(0, fmin(holes[x][0], holes[y][0]));
            int hi = fmax(0, fmax(holes[x][0], holes[y][0]));
            int top = fmax(holes[x][1], holes[y][1]);
            if (hi - lo >= L->extent[0] || top >= L->extent[1])
                continue;
            double pegs[3][2] = {{0, 0},
                                 {holes[x][0] * L->pitch, holes[x][1] * L->pitch},
                                 {holes[y][0] * L->pitch, holes[y][1] * L->pitch}};
            if (hypot(pegs[1][0] - pegs[2][0], pegs[1][1] - pegs[2][1]) > reach)
                continue;
            for (int free = 0; free < 3; free++)
            for (int e1 = 0; e1 < P->n; e1++)
                for (int e2 = 0; e2 < P->n; e2++) {
                    int u = free == 0 ? 1 : 0, v = free == 2 ? 1 : 2;
                    double tau[2], q[3][2];
                    double previous = free_gap(P, pegs, u, v, free, e1, e2, r, 0, tau, q);
                    if (isnan(previous))
                        continue;
                    for (int k = 1; k <= STEPS; k++) {
                        double a = 2 * TEST_PI * (k - 1) / STEPS, b = 2 * TEST_PI * k / STEPS;
                        double g = free_gap(P, pegs, u, v, free, e1, e2, r, b, tau, q);
                        if ((previous <= 0) != (g <= 0)) {
                            double ga = previous;
                            for (int it = 0; it < 100; it++) {
                                double m = (a + b) / 2;
                                double gm = free_gap(P, pegs, u, v, free, e1, e2, r, m, tau, q);
                                if ((gm <= 0) == (ga <= 0)) {
                                    a = m;
                                    ga = gm;
                                } else {
                                    b = m;
                                }
                            }
                            double theta = (a + b) / 2, s = 0;
                            free_gap(P, pegs, u, v, free, e1, e2, r, theta, tau, q);
                            /* Valid: pegs u, v on their edges, the free peg
                             * on its nearest edge's interior, nobody
                             * inside, all at least r away. */
                            bool ok = on_edge_interior(P, e1, q[u]) && on_edge_interior(P, e2, q[v]);
                            for (int m = 0; m < 3 && ok; m++)
                                ok = !inside(P, q[m]) && clearance(P, q[m], &s) >= r - 1e-7;
                            double d = clearance(P, q[free], &s);
                            ok = ok && s > 1e-6 && s < 1 - 1e-6 && fabs(d - r) < 1e-7;
                            if (ok && count < most) {
                                found f = {{{0, 0}, {holes[x][0], holes[x][1]},
                                            {holes[y][0], holes[y][1]}},
                                           fmod(theta + 2 * TEST_PI, 2 * TEST_PI),
                                           {cos(theta) * tau[0] - sin(theta) * tau[1],
                                            sin(theta) * tau[0] + cos(theta) * tau[1]}};
                                bool seen = false;
                                for (int z = 0; z < count && !seen; z++)
                                    seen = memcmp(out[z].holes, f.holes, sizeof f.holes) == 0 &&
                                           fabs(remainder(out[z].theta - f.theta, 2 * TEST_PI)) <
                                               1e-7 &&
                                           hypot(out[z].at[0] - f.at[0], out[z].at[1] - f.at[1]) <
                                               1e-6;
                                if (!seen)
                                    out[count++] = f;
                            }
                        }
                        previous = g;
                    }
                }
        }
    return count;
}

/* Every design: pegs at lattice points, each at distance r from its
 * contact point along the normal, none inside the part nor nearer than r. */
static void check_valid(const wr_fixture *body, const poly *P, const wr_lattice *L,
                        const wr_lattice_design *d)
{
    double c = cos(d->pose[2]), s = sin(d->pose[2]);
    for (int m = 0; m < 3; m++) {
        double peg[2] = {d->holes[m][0] * L->pitch, d->holes[m][1] * L->pitch};
        double rel[2] = {peg[0] - d->pose[0], peg[1] - d->pose[1]};
        double q[2] = {c * rel[0] + s * rel[1], -s * rel[0] + c * rel[1]};
        double t;
        assert_false(inside(P, q));
        assert_true(fabs(clearance(P, q, &t) - L->peg_radius) <= 1e-9 * body->size);
        /* The fixel: the peg's centre is r behind it along the normal. */
        assert_true(fabs(q[0] + L->peg_radius * d->normal[m][0] - d->at[m][0]) <= 1e-9 * body->size);
        assert_true(fabs(q[1] + L->peg_radius * d->normal[m][1] - d->at[m][1]) <= 1e-9 * body->size);
    }
    assert_true(d->holes[0][0] == 0 && d->holes[0][1] == 0);
}

static void against_brute_force(const double (*v)[2], int n, const wr_lattice *L,
                                const char *name)
{
    wr_fixture *body = test_polygon_body(v, (size_t)n);
    assert_non_null(body);
    poly P = {v, n, body->orientation};
    wr_lattice_job *job;
    run_lattice(body, L, &job);
    size_t count;
    const wr_lattice_design *designs = wr_lattice_job_designs(job, &count);
    for (size_t i = 0; i < count; i++)
        check_valid(body, &P, L, &designs[i]);
    enum { MOST = 20000 };
    found *brute = calloc(MOST, sizeof *brute);
    int b = brute_force(&P, L, body->size, brute, MOST);
    /* Every design of either is one of the other's. */
    int matched = 0;
    for (int z = 0; z < b; z++) {
        bool hit = false;
        for (size_t i = 0; i < count && !hit; i++)
            hit = memcmp(designs[i].holes, brute[z].holes, sizeof brute[z].holes) == 0 &&
                  fabs(remainder(designs[i].pose[2] - brute[z].theta, 2 * TEST_PI)) < 1e-6 &&
                  hypot(designs[i].pose[0] - brute[z].at[0], designs[i].pose[1] - brute[z].at[1]) <
                      1e-6;
        if (!hit)
            print_message("%s: brute force's design not enumerated: holes (%d,%d) (%d,%d) "
                          "(%d,%d), theta %.9f\n",
                          name, brute[z].holes[0][0], brute[z].holes[0][1], brute[z].holes[1][0],
                          brute[z].holes[1][1], brute[z].holes[2][0], brute[z].holes[2][1],
                          brute[z].theta);
        matched += hit;
    }
    int extra = 0;
    for (size_t i = 0; i < count; i++) {
        bool hit = false;
        for (int z = 0; z < b && !hit; z++)
            hit = memcmp(designs[i].holes, brute[z].holes, sizeof brute[z].holes) == 0 &&
                  fabs(remainder(designs[i].pose[2] - brute[z].theta, 2 * TEST_PI)) < 1e-6 &&
                  hypot(designs[i].pose[0] - brute[z].at[0], designs[i].pose[1] - brute[z].at[1]) <
                      1e-6;
        if (!hit && extra++ < 5)
            print_message("%s: enumerated, not found by brute force: holes (%d,%d) (%d,%d) "
                          "(%d,%d), edges %d %d %d, pose %.9f %.9f %.9f\n",
                          name, designs[i].holes[0][0], designs[i].holes[0][1],
                          designs[i].holes[1][0], designs[i].holes[1][1], designs[i].holes[2][0],
                          designs[i].holes[2][1], designs[i].edges[0], designs[i].edges[1],
                          designs[i].edges[2], designs[i].pose[0], designs[i].pose[1],
                          designs[i].pose[2]);
    }
    print_message("%s: %zu designs enumerated, %d found by brute force, %d matched\n", name,
                  count, b, matched);
    assert_int_equal(matched, b);
    assert_int_equal((int)count, b);
    assert_true(b > 0);
    free(brute);
    wr_lattice_job_free(job);
    wr_fixture_free(body);
}

static void square_on_a_small_lattice(void **state)
{
    (void)state;
    static const double square[4][2] = {{0, 0}, {2.5, 0}, {2.5, 2.5}, {0, 2.5}};
    wr_lattice L = {1, 0.2, {4, 4}};
    against_brute_force(square, 4, &L, "square");
}

static void triangle_on_a_small_lattice(void **state)
{
    (void)state;
    static const double triangle[3][2] = {{0, 0}, {3.2, 0}, {0.7, 2.1}};
    wr_lattice L = {1, 0.15, {4, 4}};
    against_brute_force(triangle, 3, &L, "triangle");
}

/* Chunks claimed at once and run in reverse order merge to the designs
 * of one run, bit for bit. */
static void chunks_in_any_order(void **state)
{
    (void)state;
    static const double triangle[3][2] = {{0, 0}, {3.2, 0}, {0.7, 2.1}};
    wr_fixture *body = test_polygon_body(triangle, 3);
    assert_non_null(body);
    /* Fine enough for several chunks of a segment triangle's units. */
    wr_lattice L = {0.5, 0.15, {8, 8}};
    wr_lattice_job *whole, *parts;
    run_lattice(body, &L, &whole);
    wr_error error;
    assert_int_equal(wr_lattice_job_new(body, &L, &parts, &error), WR_OK);
    enum { MOST = 4096 };
    size_t first[MOST], count[MOST];
    int chunks = 0;
    while (chunks < MOST && wr_lattice_job_claim(parts, &first[chunks], &count[chunks]))
        chunks++;
    assert_true(chunks > 2);
    for (int i = chunks - 1; i >= 0; i--) {
        wr_lattice_chunk chunk;
        assert_int_equal(wr_lattice_chunk_run(parts, first[i], count[i], NULL, &chunk, NULL),
                         WR_OK);
        assert_int_equal(wr_lattice_job_merge(parts, &chunk), WR_OK);
    }
    bool done = false;
    assert_int_equal(wr_lattice_job_run(parts, 1, NULL, NULL, &done), WR_OK);
    assert_true(done);
    size_t n, m;
    const wr_lattice_design *a = wr_lattice_job_designs(whole, &n);
    const wr_lattice_design *b = wr_lattice_job_designs(parts, &m);
    assert_int_equal(n, m);
    assert_memory_equal(a, b, n * sizeof *a);
    print_message("triangle: %d chunks in reverse order, %zu designs, the same\n", chunks, m);
    wr_lattice_job_free(whole);
    wr_lattice_job_free(parts);
    wr_fixture_free(body);
}

static void refusals(void **state)
{
    (void)state;
    static const double square[4][2] = {{0, 0}, {2.5, 0}, {2.5, 2.5}, {0, 2.5}};
    wr_fixture *body = test_polygon_body(square, 4);
    assert_non_null(body);
    wr_lattice_job *job;
    wr_error error;
    wr_lattice bad[] = {{0, 0.1, {4, 4}}, {1, 0.5, {4, 4}}, {1, -0.1, {4, 4}}, {1, 0.1, {0, 4}}};
    const char *fields[] = {"pitch", "peg_radius", "peg_radius", "extent"};
    for (int i = 0; i < 4; i++) {
        assert_int_equal(wr_lattice_job_new(body, &bad[i], &job, &error), WR_INVALID);
        assert_string_equal(error.field, fields[i]);
    }
    wr_fixture_free(body);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(square_on_a_small_lattice),
        cmocka_unit_test(triangle_on_a_small_lattice),
        cmocka_unit_test(chunks_in_any_order),
        cmocka_unit_test(refusals),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
