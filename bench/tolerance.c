/* tolerance.c -- robust push regions against the exact nominal ones, side
 * by side in one run: push.regions of a fixture (set both) in process,
 * JSON in and out (wp_answer_line), with and without a geometric tolerance
 * {"position": T, "angle": A} added to it.  Prints medians and their
 * ratio; asserts nothing but that the answers are answers.
 *
 *   tolerance [FIXTURE.json] [--position T] [--angle A] [--batches N] [--json]
 *   (default examples/bracket.json, T 0.02, A 0.2, 7 batches) */
#include "bench_util.h"
#include "wp_local.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

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

/* Seconds per request, the median of `batches` batches of `runs`. */
static double measure(wp_local *local, const char *line, size_t length, int batches, int runs,
                      double *regions_length)
{
    double times[64];
    wp_limits limits = {.max_depth = 64, .max_wrenches = 1000, .max_batch = 1};
    for (int b = 0; b < batches; b++) {
        double start = bench_seconds();
        for (int r = 0; r < runs; r++) {
            wp_counts counts = {0, 0};
            char *answer = wp_answer_line(wp_local_host(local), &limits, line, length, &counts);
            const char *total = answer ? strstr(answer, "\"total_length\":") : NULL;
            if (!total) {
                fprintf(stderr, "push.regions failed: %.300s\n", answer ? answer : "(none)");
                exit(1);
            }
            *regions_length = strtod(total + strlen("\"total_length\":"), NULL);
            free(answer);
        }
        times[b] = (bench_seconds() - start) / runs;
    }
    return median(times, batches);
}

int main(int argc, char **argv)
{
    const char *path = "examples/bracket.json";
    double position = 0.02, angle = 0.2;
    int batches = 7;
    bool json = false;
    for (int i = 1; i < argc; i++) {
        if (strcmp(argv[i], "--json") == 0)
            json = true;
        else if (strcmp(argv[i], "--position") == 0 && i + 1 < argc)
            position = strtod(argv[++i], NULL);
        else if (strcmp(argv[i], "--angle") == 0 && i + 1 < argc)
            angle = strtod(argv[++i], NULL);
        else if (strcmp(argv[i], "--batches") == 0 && i + 1 < argc)
            batches = atoi(argv[++i]);
        else
            path = argv[i];
    }
    if (batches < 1 || batches > 64)
        batches = 7;
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
    /* The fixture object with the tolerance as its first member. */
    char *open = strchr(text, '{');
    if (!open) {
        fprintf(stderr, "%s: not a JSON object\n", path);
        return 1;
    }
    static char nominal[(1 << 20) + 512], robust[(1 << 20) + 512];
    int n_nominal = snprintf(nominal, sizeof nominal,
                             "{\"jsonrpc\":\"2.0\",\"id\":1,\"method\":\"push.regions\",\"params\":"
                             "{\"set\":\"both\",\"fixture\":%s}}",
                             text);
    int n_robust = snprintf(robust, sizeof robust,
                            "{\"jsonrpc\":\"2.0\",\"id\":1,\"method\":\"push.regions\",\"params\":"
                            "{\"set\":\"both\",\"fixture\":{\"tolerance\":{\"position\":%.17g,"
                            "\"angle\":%.17g},%s}}",
                            position, angle, open + 1);
    wp_local *local = wp_local_new();
    if (!local)
        return 1;
    double nominal_length = 0, robust_length = 0;
    /* The nominal answer is fast: enough runs a batch to time it. */
    double t_nominal = measure(local, nominal, (size_t)n_nominal, batches, 20, &nominal_length);
    double t_robust = measure(local, robust, (size_t)n_robust, batches, 1, &robust_length);
    wp_local_free(local);
    double ratio = t_robust / t_nominal;
    if (json)
        printf("{\"fixture\": \"%s\", \"position\": %g, \"angle\": %g, \"nominal_ms\": %.3f, "
               "\"robust_ms\": %.3f, \"ratio\": %.2f, \"nominal_length\": %.6g, "
               "\"robust_length\": %.6g}\n",
               path, position, angle, 1e3 * t_nominal, 1e3 * t_robust, ratio, nominal_length,
               robust_length);
    else
        printf("%s, push.regions set both, in process (medians of %d batches):\n"
               "nominal (exact)                            %9.3f ms   length %g\n"
               "robust, tolerance %g along, %g degrees    %9.3f ms   length %g\n"
               "ratio                                      %9.2f      target <= 20\n",
               path, batches, 1e3 * t_nominal, nominal_length, position, angle, 1e3 * t_robust,
               robust_length, ratio);
    return 0;
}
