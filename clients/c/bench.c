/* bench.c -- round-trip latency of wrc_classify against a running daemon.
 * Prints figures; asserts nothing.
 *
 *   wrenchclient-bench SOCKET FIXTURE_ID [CALLS]
 */
#include "wrenchclient.h"

#include <stdio.h>
#include <stdlib.h>
#include <time.h>

static double now_us(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return t.tv_sec * 1e6 + t.tv_nsec / 1e3;
}

static int compare(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

int main(int argc, char **argv)
{
    if (argc < 3) {
        fprintf(stderr, "usage: %s SOCKET FIXTURE_ID [CALLS]\n", argv[0]);
        return 2;
    }
    int calls = argc > 3 ? atoi(argv[3]) : 20000;
    if (calls < 1)
        calls = 1;
    int error;
    wrc_client *client = wrc_connect(argv[1], 5000, 0, &error);
    if (!client) {
        fprintf(stderr, "%s: %s\n", argv[1], wrc_strerror(error));
        return 3;
    }
    double *latency = malloc((size_t)calls * sizeof *latency);
    if (!latency)
        return 1;
    unsigned seed = 1;
    for (int i = 0; i < calls; i++) {
        double g[3];
        for (int k = 0; k < 3; k++) {
            seed = seed * 1103515245u + 12345u;
            g[k] = (double)(seed >> 8) / (1 << 24) * 2 - 1;
        }
        wrc_answer answer;
        double start = now_us();
        error = wrc_classify(client, argv[2], g, "both", &answer);
        latency[i] = now_us() - start;
        if (error != WRC_OK) {
            fprintf(stderr, "classify: %s (%s)\n", wrc_strerror(error), wrc_last_error(client));
            return 4;
        }
    }
    qsort(latency, (size_t)calls, sizeof *latency, compare);
    double sum = 0;
    for (int i = 0; i < calls; i++)
        sum += latency[i];
    printf("wrc_classify round trips: %d calls, mean %.1f us, p50 %.1f us, p99 %.1f us, "
           "max %.1f us\n",
           calls, sum / calls, latency[calls / 2], latency[(int)(calls * 0.99)],
           latency[calls - 1]);
    free(latency);
    wrc_close(client);
    return 0;
}
