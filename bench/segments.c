/* segments.c -- fixture.design's cost per candidate against the number of
 * segments of the outline.  Prints figures; asserts nothing but that the
 * indexed search and the exhaustive one agree.
 *
 *   segments [--runs N] [--json] [--only PART MODE]
 *
 * Two parts, the same search on each: 24 candidate sites spread evenly
 * over the outer loop (at segment midpoints), 3 fixels (2,024 candidates),
 * objective margin, top 10, a point finger, friction 0.3.
 *   plate  a 20-segment plate: a 12 x 8 rectangle with two corners
 *          filleted and a slot (lines and arcs);
 *   gear   a gear-like outline of 2,000 straight segments: 20 teeth, each
 *          a faceted trapezoid of 100 segments, about a centre.
 *   round  the gear with a round finger of radius 0.3 (what it cannot
 *          reach is found for every segment), on every 16th candidate
 *          (127 of them: the exhaustive search takes seconds a candidate).
 * Each is timed searching with the segment index (as the daemon does) and
 * exhaustively (every segment against every cone: the reference), one
 * thread, median of --runs runs (default 3).  The designs of the two must
 * be the same, bit for bit; the program exits 1 if not.
 * --only PART MODE: one search of one part (plate, gear, round), indexed
 * or exhaustive, and nothing else: for callgrind's instruction counts.
 * The time of a search includes making its job (the index is built then).
 * Left out: the designs' figures after the search (best push, gravity,
 * critical friction), which cost the same per design whatever the index. */
#include "wrench.h"
#include "bench_body.h"
#include "bench_util.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define SITES 24

static double sorted_median(double *v, int n)
{
    for (int i = 1; i < n; i++)
        for (int j = i; j > 0 && v[j] < v[j - 1]; j--) {
            double t = v[j];
            v[j] = v[j - 1];
            v[j - 1] = t;
        }
    return n % 2 ? v[n / 2] : (v[n / 2 - 1] + v[n / 2]) / 2;
}

/* The gear: radius 10 + 1.2 * clamp(1.6 cos(20 theta)), 2,000 vertices. */
static wr_fixture *gear(void)
{
    static double v[2000][3];
    for (int i = 0; i < 2000; i++) {
        double theta = 2 * 3.14159265358979323846 * i / 2000;
        double c = 1.6 * cos(20 * theta);
        double r = 10 + 1.2 * fmax(-1, fmin(1, c));
        v[i][0] = r * cos(theta);
        v[i][1] = r * sin(theta);
        v[i][2] = 0;
    }
    return bench_outline_body("gear", (const double(*)[3])v, 2000);
}

static wr_fixture *plate(void)
{
    const double f = 0.41421356237309503;
    static const double v[20][3] = {
        {1, 0, 0},  {6, 0, 0},  {6, 1, 0},  {7, 1, 0},  {7, 0, 0},  {11, 0, f}, {12, 1, 0},
        {12, 4, 0}, {12, 7, 0}, {11, 8, 0}, {9, 8, 0},  {7, 8, 0},  {7, 6, 0},  {5, 6, 0},
        {5, 8, 0},  {3, 8, 0},  {1, 8, f},  {0, 7, 0},  {0, 4, 0},  {0, 1, 0}};
    return bench_outline_body("plate", v, 20);
}

/* SITES sites at the midpoints of segments spread evenly over loop 0. */
static int sites_of(const wr_fixture *body, wr_site *sites)
{
    const wr_loop *loop = &body->outline->loops[0];
    for (int i = 0; i < SITES; i++) {
        size_t s = (size_t)i * loop->segment_count / SITES;
        double p[2], n[2];
        wr_outline_boundary(body->outline, 0, s, 0.5, p, n);
        wr_error error;
        if (wr_site_new(body, p, n, &sites[i], &error) != WR_OK)
            return -1;
    }
    return SITES;
}

typedef struct result {
    double seconds;
    int count;
    wr_design designs[10];
    uint64_t examined;
} result;

/* Every 16th combination of 3 of the SITES sites, for the round finger. */
static int (*sampled_candidates(uint64_t *count))[WR_MAX_FIXELS]
{
    static int list[200][WR_MAX_FIXELS];
    uint64_t n = 0, r = 0;
    for (int a = 0; a < SITES; a++)
        for (int b = a + 1; b < SITES; b++)
            for (int c = b + 1; c < SITES; c++, r++)
                if (r % 16 == 0 && n < 200) {
                    list[n][0] = a;
                    list[n][1] = b;
                    list[n][2] = c;
                    n++;
                }
    *count = n;
    return list;
}

static int search(const wr_fixture *body, const wr_site *sites, bool exhaustive, bool round,
                  result *out)
{
    wr_design_spec spec;
    memset(&spec, 0, sizeof spec);
    spec.body = body;
    spec.friction.given = true;
    spec.friction.static_mu = 0.3;
    spec.sites = sites;
    spec.site_count = SITES;
    spec.fixel_count = 3;
    spec.objective = WR_OBJECTIVE_MARGIN;
    spec.top = 10;
    spec.shard_count = 1;
    spec.exhaustive = exhaustive;
    if (round) {
        spec.finger.radius = 0.3;
        spec.candidates = (const int (*)[WR_MAX_FIXELS])sampled_candidates(&spec.candidate_count);
    }
    wr_design_job *job;
    wr_error error;
    /* The job's making counts: it builds the index (and finds what a round
     * finger cannot reach), once a search. */
    double start = bench_seconds();
    if (wr_design_job_new(&spec, &job, &error) != WR_OK)
        return -1;
    uint64_t first, count;
    double threshold;
    /* The search alone: chunks claimed and merged as a worker would. */
    while (wr_design_job_claim(job, &first, &count, &threshold)) {
        wr_design_chunk chunk;
        if (wr_design_chunk_run(job, first, count, threshold, NULL, NULL, &chunk, NULL) != WR_OK) {
            wr_design_job_free(job);
            return -1;
        }
        wr_design_job_merge(job, &chunk);
        wr_design_chunk_release(&chunk);
    }
    out->seconds = bench_seconds() - start;
    const wr_design *d = wr_design_job_designs(job, &out->count);
    memcpy(out->designs, d, (size_t)out->count * sizeof *d);
    out->examined = wr_design_job_counts(job)->examined;
    wr_design_job_free(job);
    return 0;
}

static bool same(const result *a, const result *b)
{
    if (a->count != b->count)
        return false;
    for (int i = 0; i < a->count; i++)
        if (a->designs[i].candidate != b->designs[i].candidate ||
            memcmp(&a->designs[i].score, &b->designs[i].score, sizeof(double)) != 0)
            return false;
    return true;
}

int main(int argc, char **argv)
{
    int runs = 3;
    bool json = false;
    const char *only_part = NULL, *only_mode = NULL;
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--runs") && i + 1 < argc)
            runs = atoi(argv[++i]);
        else if (!strcmp(argv[i], "--json"))
            json = true;
        else if (!strcmp(argv[i], "--only") && i + 2 < argc) {
            only_part = argv[++i];
            only_mode = argv[++i];
        } else {
            fprintf(stderr, "usage: segments [--runs N] [--json] [--only PART MODE]\n");
            return 2;
        }
    }
    if (runs < 1 || runs > 99)
        runs = 3;
    wr_fixture *bodies[2] = {plate(), gear()};
    if (!bodies[0] || !bodies[1])
        return 1;
    /* The parts: the plate, the gear, the gear with a round finger. */
    const char *names[3] = {"plate", "gear", "round"};
    const int body_of[3] = {0, 1, 1};
    if (only_part) {
        int p = -1;
        for (int i = 0; i < 3; i++)
            if (!strcmp(only_part, names[i]))
                p = i;
        bool exhaustive = !strcmp(only_mode, "exhaustive");
        if (p < 0 || (!exhaustive && strcmp(only_mode, "indexed"))) {
            fprintf(stderr, "segments: --only plate|gear|round indexed|exhaustive\n");
            return 2;
        }
        wr_site sites[SITES];
        result r;
        if (sites_of(bodies[body_of[p]], sites) != SITES ||
            search(bodies[body_of[p]], sites, exhaustive, p == 2, &r) != 0)
            return 1;
        printf("%s, %s: %.0f candidates/s\n", names[p], only_mode, (double)r.examined / r.seconds);
        return 0;
    }
    double rate[3][2]; /* part, exhaustive */
    bool agree = true;
    for (int p = 0; p < 3; p++) {
        wr_site sites[SITES];
        if (sites_of(bodies[body_of[p]], sites) != SITES)
            return 1;
        result r[2];
        for (int x = 0; x < 2; x++) {
            double seconds[99];
            /* The round finger's exhaustive search: once (minutes else). */
            int n = p == 2 && x == 1 ? 1 : runs;
            for (int k = 0; k < n; k++) {
                if (search(bodies[body_of[p]], sites, x == 1, p == 2, &r[x]) != 0)
                    return 1;
                seconds[k] = r[x].seconds;
            }
            rate[p][x] = (double)r[x].examined / sorted_median(seconds, n);
        }
        agree &= same(&r[0], &r[1]);
    }
    size_t segs[3] = {bodies[0]->outline->vertex_count, bodies[1]->outline->vertex_count,
                      bodies[1]->outline->vertex_count};
    if (json) {
        printf("{\"plate_segments\":%zu,\"gear_segments\":%zu,"
               "\"plate_indexed\":%.1f,\"plate_exhaustive\":%.1f,"
               "\"gear_indexed\":%.1f,\"gear_exhaustive\":%.1f,"
               "\"round_indexed\":%.1f,\"round_exhaustive\":%.1f,\"agree\":%s}\n",
               segs[0], segs[1], rate[0][0], rate[0][1], rate[1][0], rate[1][1], rate[2][0],
               rate[2][1], agree ? "true" : "false");
    } else {
        printf("candidates/s, one thread, median of %d runs\n", runs);
        printf("%-34s %12s %12s %8s\n", "", "indexed", "exhaustive", "ratio");
        for (int p = 0; p < 3; p++)
            printf("%-6s (%4zu segments%s) %12.0f %12.0f %7.1fx\n", names[p], segs[p],
                   p == 2 ? ", r = 0.3" : "         ", rate[p][0], rate[p][1],
                   rate[p][0] / rate[p][1]);
        printf("plate / gear, indexed: %.2fx (target: within 5x); exhaustive: %.2fx\n",
               rate[0][0] / rate[1][0], rate[0][1] / rate[1][1]);
        printf("designs of the two searches: %s\n", agree ? "the same" : "DIFFERENT");
    }
    for (int b = 0; b < 2; b++)
        wr_fixture_free(bodies[b]);
    return agree ? 0 : 1;
}
