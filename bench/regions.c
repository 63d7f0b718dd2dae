/* regions.c -- push.regions per pair of an edge and a cone: a 24-sided part
 * of lines against the same part with every side an arc (bulge 0.15), the
 * arcs by the fast path and by the reference (wr_arc_regions), in process.
 *
 *     build/bench/regions [--only lines|arcs|reference] [--repeats N] [--json]
 *
 * Prints ns per pair for each.  With --only, runs that one N times and
 * nothing else: bench/geometry.py runs it under callgrind with N and with
 * 0 to count the instructions per pair, which the noise of a shared
 * machine does not move. */
#include "wr_internal.h"
#include "wr_outline.h"
#include "wr_plan.h"
#include "wr_regions.h"
#include "wrench.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#define SIDES 24

static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec + ts.tv_nsec * 1e-9;
}

/* The part with its three fixels (on sides 0, 8 and 15, at their middles),
 * and its analysis. */
static wr_analysis *part(double bulge, wr_fixture **body_out, wr_fixture *placed)
{
    double vertices[SIDES][3];
    for (int k = 0; k < SIDES; k++) {
        double angle = 2 * WR_PI * k / SIDES;
        vertices[k][0] = 50 * cos(angle) * (k % 2 ? 1.1 : 1);
        vertices[k][1] = 40 * sin(angle);
        vertices[k][2] = bulge;
    }
    wr_loop_spec loop = {SIDES, (const double (*)[3])vertices};
    wr_fixture_spec spec;
    memset(&spec, 0, sizeof spec);
    spec.mass = 1;
    spec.shape = WR_SHAPE_OUTLINE;
    spec.loops = &loop;
    spec.loop_count = 1;
    wr_fixture *body;
    wr_error error;
    if (wr_fixture_body_new(&spec, &body, &error) != WR_OK) {
        fprintf(stderr, "regions: %s: %s\n", error.field, error.reason);
        exit(1);
    }
    wr_fixel_spec fixels[3];
    memset(fixels, 0, sizeof fixels);
    const int sides[3] = {0, 8, 15};
    for (int i = 0; i < 3; i++) {
        double normal[2];
        wr_outline_boundary(body->outline, 0, (size_t)sides[i], 0.5, fixels[i].at, normal);
    }
    wr_friction_spec friction = {.given = true, .static_mu = 0.3};
    if (wr_fixture_place(body, fixels, 3, &friction, placed, &error) != WR_OK) {
        fprintf(stderr, "regions: %s: %s\n", error.field, error.reason);
        exit(1);
    }
    wr_analysis *analysis;
    if (wr_analysis_new(placed, &analysis) != WR_OK)
        exit(1);
    *body_out = body;
    return analysis;
}

/* The regions of every side, `repeats` times: by wr_push_regions (lines,
 * or arcs by the fast path) or by the reference on each arc. */
static void run(wr_analysis *analysis, const wr_fixture *placed, bool reference, int repeats)
{
    const wr_cone *cones[64];
    int count = 0;
    for (int i = 0; i < analysis->plan->kept_count && count < 64; i++)
        cones[count++] = &analysis->goal_cones[i];
    for (int r = 0; r < repeats; r++) {
        wr_regions regions = {0};
        if (!reference) {
            if (wr_push_regions(analysis, WR_SET_GOAL, 0, NULL, &regions) != WR_OK)
                exit(1);
        } else {
            for (int edge = 0; edge < SIDES; edge++) {
                wr_edge_frame frame;
                wr_edge_frame_of(placed, edge, &frame);
                wr_arc_regions(&frame, cones, count, true, NULL, &regions);
            }
        }
        wr_regions_release(&regions);
    }
}

int main(int argc, char **argv)
{
    const char *only = NULL;
    int repeats = 2000;
    bool json = false;
    for (int i = 1; i < argc; i++) {
        if (strcmp(argv[i], "--only") == 0 && i + 1 < argc)
            only = argv[++i];
        else if (strcmp(argv[i], "--repeats") == 0 && i + 1 < argc)
            repeats = atoi(argv[++i]);
        else if (strcmp(argv[i], "--json") == 0)
            json = true;
    }
    wr_fixture *bodies[2], placed[2];
    wr_analysis *lines = part(0, &bodies[0], &placed[0]);
    wr_analysis *arcs = part(0.15, &bodies[1], &placed[1]);
    int pairs[2] = {SIDES * lines->plan->kept_count, SIDES * arcs->plan->kept_count};
    if (only) {
        if (strcmp(only, "lines") == 0)
            run(lines, &placed[0], false, repeats);
        else
            run(arcs, &placed[1], strcmp(only, "reference") == 0, repeats);
        printf("{\"pairs\": %d}\n", strcmp(only, "lines") == 0 ? pairs[0] : pairs[1]);
    } else {
        double ns[3];
        for (int m = 0; m < 3; m++) {
            double start = now();
            run(m == 0 ? lines : arcs, &placed[m == 0 ? 0 : 1], m == 2, repeats);
            ns[m] = (now() - start) * 1e9 / repeats / pairs[m == 0 ? 0 : 1];
        }
        if (json)
            printf("{\"line_ns\": %.2f, \"arc_ns\": %.2f, \"reference_ns\": %.2f, \"pairs\": [%d, %d]}\n",
                   ns[0], ns[1], ns[2], pairs[0], pairs[1]);
        else
            printf("ns per pair: line %.1f, arc %.1f, arc by the reference %.1f (%d, %d pairs)\n",
                   ns[0], ns[1], ns[2], pairs[0], pairs[1]);
    }
    wr_analysis_free(lines);
    wr_analysis_free(arcs);
    wr_fixture_free(bodies[0]);
    wr_fixture_free(bodies[1]);
    return 0;
}
