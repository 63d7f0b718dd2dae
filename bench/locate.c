/* locate.c -- the cost of fixture.locating at 3 fixels with features:
 * wr_locate alone (the locating matrix, its inverse, the exact pose at the
 * box's 8 corners, the features), and the whole request in process, JSON in
 * and out (wp_answer_line), whose inline fixture is validated every time.
 * Prints figures (medians of 21 batches); asserts nothing but that the
 * answers are answers.
 *
 *   locate [FIXTURE.json] [--runs N] [--json]     (default examples/bracket.json) */
#include "bench_util.h"
#include "wp_fixture.h"
#include "wp_local.h"
#include "wrench.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define BATCHES 21

static int compare(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

static double median(double *v, int n)
{
    qsort(v, (size_t)n, sizeof *v, compare);
    return v[n / 2];
}

int main(int argc, char **argv)
{
    const char *path = "examples/bracket.json";
    long runs = 2000;
    bool json = false;
    for (int i = 1; i < argc; i++) {
        if (strcmp(argv[i], "--json") == 0)
            json = true;
        else if (strcmp(argv[i], "--runs") == 0 && i + 1 < argc)
            runs = strtol(argv[++i], NULL, 10);
        else
            path = argv[i];
    }
    static char text[1 << 20];
    FILE *file = fopen(path, "rb");
    if (!file) {
        perror(path);
        return 1;
    }
    size_t length = fread(text, 1, sizeof text - 1, file);
    fclose(file);
    text[length] = 0;
    for (char *p = text; *p; p++)
        if (*p == '\n' || *p == '\r')
            *p = ' ';
    cJSON *tree = cJSON_Parse(text);
    wp_fixture_doc doc;
    wp_error error;
    if (!tree || !wp_fixture_read(tree, "fixture", &doc, &error)) {
        fprintf(stderr, "%s: not a valid fixture\n", path);
        return 1;
    }
    cJSON_Delete(tree);
    const wr_fixture *f = doc.fixture;
    /* Three features: the centre of mass and two points across the part. */
    double box_lo[2] = {f->com[0] - f->size / 4, f->com[1]}, box_hi[2] = {f->com[0] + f->size / 4, f->com[1]};
    wr_locate_feature features[3];
    memset(features, 0, sizeof features);
    memcpy(features[0].at, f->com, sizeof features[0].at);
    memcpy(features[1].at, box_lo, sizeof features[1].at);
    memcpy(features[2].at, box_hi, sizeof features[2].at);
    double tolerance[WR_MAX_FIXELS];
    for (int i = 0; i < WR_MAX_FIXELS; i++)
        tolerance[i] = 1e-3 * f->size;
    wr_locating out;
    wr_error why;
    if (wr_locate(f, tolerance, 3, features, 3, &out, &why) != WR_OK) {
        fprintf(stderr, "%s: %s: %s\n", path, why.field, why.reason);
        return 1;
    }
    double lib[BATCHES], request[BATCHES];
    for (int b = 0; b < BATCHES; b++) {
        double start = bench_seconds();
        for (long r = 0; r < runs; r++)
            wr_locate(f, tolerance, 3, features, 3, &out, &why);
        lib[b] = (bench_seconds() - start) * 1e6 / (double)runs;
    }
    static char line[(1 << 20) + 512];
    int used = snprintf(line, sizeof line,
                        "{\"jsonrpc\":\"2.0\",\"id\":1,\"method\":\"fixture.locating\",\"params\":"
                        "{\"fixture\":%s,\"tolerance\":%.17g,\"features\":[{\"name\":\"com\","
                        "\"at\":[%.17g,%.17g]},{\"at\":[%.17g,%.17g]},{\"at\":[%.17g,%.17g]}]}}",
                        text, tolerance[0], f->com[0], f->com[1], box_lo[0], box_lo[1], box_hi[0],
                        box_hi[1]);
    wp_local *local = wp_local_new();
    wp_limits limits = {.max_depth = 64, .max_wrenches = 1000, .max_batch = 1};
    long request_runs = runs / 10 > 0 ? runs / 10 : 1;
    for (int b = 0; b < BATCHES && local; b++) {
        double start = bench_seconds();
        for (long r = 0; r < request_runs; r++) {
            wp_counts counts = {0, 0};
            char *answer = wp_answer_line(wp_local_host(local), &limits, line, (size_t)used, &counts);
            if (!answer || !strstr(answer, "\"deterministic\":true")) {
                fprintf(stderr, "fixture.locating failed: %.300s\n", answer ? answer : "(none)");
                return 1;
            }
            free(answer);
        }
        request[b] = (bench_seconds() - start) * 1e6 / (double)request_runs;
    }
    wp_local_free(local);
    double lib_us = median(lib, BATCHES), request_us = median(request, BATCHES);
    if (json)
        printf("{\"fixture\": \"%s\", \"fixels\": %d, \"features\": 3, \"lib_us\": %.3f, "
               "\"request_us\": %.3f}\n", path, f->fixel_count, lib_us, request_us);
    else
        printf("%s, %d fixels, 3 features:\n"
               "wr_locate                                  %9.3f us   target < 1000\n"
               "the request in process, inline fixture     %9.3f us\n",
               path, f->fixel_count, lib_us, request_us);
    wp_fixture_doc_release(&doc);
    return 0;
}
