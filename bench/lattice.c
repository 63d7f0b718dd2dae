/* lattice.c -- lattice designs per pose: an octagon of lines against the
 * rounded rectangle of the same extent (lines and quarter-circle fillets),
 * its poses with arcs by the polynomial and by the theta scan.
 *
 *     build/bench/lattice [--only lines|arcs|scan] [--json]
 *
 * Prints microseconds per pose for each; with --only, runs that one once
 * (bench/geometry.py counts its instructions under callgrind, less a run
 * of --only none, which builds the parts and nothing else). */
#include "wr_internal.h"
#include "wr_lattice.h"
#include "wrench.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#define QUARTER 0.41421356237309503

static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec + ts.tv_nsec * 1e-9;
}

static wr_fixture *body_of(const double (*v)[3], size_t n)
{
    wr_loop_spec loop = {n, v};
    wr_fixture_spec spec;
    memset(&spec, 0, sizeof spec);
    spec.mass = 1;
    spec.shape = WR_SHAPE_OUTLINE;
    spec.loops = &loop;
    spec.loop_count = 1;
    wr_fixture *body;
    wr_error error;
    if (wr_fixture_body_new(&spec, &body, &error) != WR_OK) {
        fprintf(stderr, "lattice: %s\n", error.reason);
        exit(1);
    }
    return body;
}

/* The poses found, and the seconds taken. */
static size_t run(const wr_fixture *body, bool scan, double *seconds)
{
    const wr_lattice L = {.pitch = 1, .peg_radius = 0.15, .extent = {5, 5}};
    double start = now();
    wr_lattice_job *job;
    wr_error error;
    if (wr_lattice_job_new(body, &L, &job, &error) != WR_OK)
        exit(1);
    if (scan)
        wr_lattice_job_scan(job);
    bool done = false;
    while (!done)
        if (wr_lattice_job_run(job, 1000000, NULL, NULL, &done) != WR_OK)
            exit(1);
    size_t count;
    wr_lattice_job_designs(job, &count);
    wr_lattice_job_free(job);
    *seconds = now() - start;
    return count;
}

int main(int argc, char **argv)
{
    const char *only = NULL;
    bool json = false;
    for (int i = 1; i < argc; i++) {
        if (strcmp(argv[i], "--only") == 0 && i + 1 < argc)
            only = argv[++i];
        else if (strcmp(argv[i], "--json") == 0)
            json = true;
    }
    /* The rounded rectangle 3 x 2 with fillets of 0.5, and the octagon
     * of its lines' ends (the fillets cut straight). */
    static const double rounded[8][3] = {{0.5, 0, 0},       {2.5, 0, QUARTER}, {3, 0.5, 0},
                                         {3, 1.5, QUARTER}, {2.5, 2, 0},       {0.5, 2, QUARTER},
                                         {0, 1.5, 0},       {0, 0.5, QUARTER}};
    double octagon[8][3];
    memcpy(octagon, rounded, sizeof octagon);
    for (int i = 0; i < 8; i++)
        octagon[i][2] = 0;
    wr_fixture *arcs = body_of(rounded, 8), *lines = body_of((const double (*)[3])octagon, 8);
    double seconds[3];
    size_t poses[3];
    if (only) {
        size_t n = 0;
        if (strcmp(only, "lines") == 0)
            n = run(lines, false, &seconds[0]);
        else if (strcmp(only, "arcs") == 0)
            n = run(arcs, false, &seconds[0]);
        else if (strcmp(only, "scan") == 0)
            n = run(arcs, true, &seconds[0]);
        printf("{\"poses\": %zu}\n", n);
    } else {
        poses[0] = run(lines, false, &seconds[0]);
        poses[1] = run(arcs, false, &seconds[1]);
        poses[2] = run(arcs, true, &seconds[2]);
        if (json)
            printf("{\"lines_us\": %.3f, \"arcs_us\": %.3f, \"scan_us\": %.3f, \"poses\": [%zu, %zu, "
                   "%zu]}\n",
                   seconds[0] * 1e6 / poses[0], seconds[1] * 1e6 / poses[1],
                   seconds[2] * 1e6 / poses[2], poses[0], poses[1], poses[2]);
        else
            printf("us per pose: lines %.2f (%zu poses), arcs %.2f (%zu), arcs by the scan %.2f "
                   "(%zu)\n",
                   seconds[0] * 1e6 / poses[0], poses[0], seconds[1] * 1e6 / poses[1], poses[1],
                   seconds[2] * 1e6 / poses[2], poses[2]);
    }
    wr_fixture_free(arcs);
    wr_fixture_free(lines);
    return 0;
}
