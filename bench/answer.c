/* answer.c -- request lines answered in process (wp_answer_line, the code
 * the daemon runs, without a socket), for the sweep benchmark and the
 * comparison of answers between two builds (bench/sweep.py,
 * bench/compare_sweeps.py).  Each line of stdin is one request; for each,
 * one line on stdout: with --time, the median wall seconds of --runs
 * answers, a tab, then the answer; else the answer alone.  Built against
 * any revision's libraries, it answers as that revision's daemon would.
 *
 *   answer [--time] [--runs N] < requests > answers */
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

int main(int argc, char **argv)
{
    bool timed = false;
    int runs = 1;
    for (int i = 1; i < argc; i++) {
        if (strcmp(argv[i], "--time") == 0)
            timed = true;
        else if (strcmp(argv[i], "--runs") == 0 && i + 1 < argc)
            runs = atoi(argv[++i]);
        else {
            fprintf(stderr, "usage: answer [--time] [--runs N] < requests\n");
            return 2;
        }
    }
    if (runs < 1)
        runs = 1;
    wp_local *local = wp_local_new();
    if (!local)
        return 1;
    wp_limits limits = {.max_depth = 64, .max_wrenches = 1000000, .max_batch = 1000};
    char *line = NULL;
    size_t capacity = 0;
    ssize_t length;
    double *times = malloc((size_t)runs * sizeof *times);
    while (times && (length = getline(&line, &capacity, stdin)) > 0) {
        while (length > 0 && (line[length - 1] == '\n' || line[length - 1] == '\r'))
            line[--length] = 0;
        if (length == 0)
            continue;
        char *answer = NULL;
        for (int r = 0; r < runs; r++) {
            free(answer);
            wp_counts counts = {0, 0};
            double start = bench_seconds();
            answer = wp_answer_line(wp_local_host(local), &limits, line, (size_t)length, &counts);
            times[r] = bench_seconds() - start;
        }
        qsort(times, (size_t)runs, sizeof *times, compare);
        if (timed)
            printf("%.9f\t", times[runs / 2]);
        fputs(answer ? answer : "\n", stdout);
        fflush(stdout);
        free(answer);
    }
    free(times);
    free(line);
    wp_local_free(local);
    return 0;
}
