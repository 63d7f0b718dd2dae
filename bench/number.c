/* number.c -- the cost of writing one number (proto/wp_number.c): the exact
 * path (snprintf + strtod, the formatter wrenchd had before) against
 * wp_format_number.  Prints figures; asserts nothing.
 *
 *   number [--count N] [--json]
 *
 * Mixes of N doubles each (default 100000), from a fixed seed:
 *   uniform   random doubles in [-1e3, 1e3] (17 significant digits mostly);
 *   short     what people write: 0.25, 1.5, 3, -0.125, values in [-100, 100]
 *             with 1 to 4 decimals, integers;
 *   witness   results of arithmetic, as in answers: sums, products,
 *             quotients, square roots and cosines of other doubles;
 *   all       the three interleaved.
 * Each row: ns per number for the old and the new formatter (the fastest of
 * 3 and of 15 passes over the mix), the speed-up, and the share of the
 * numbers the new one sent to the exact path. */
#include "wp_number.h"
#include "bench_util.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

static double range(uint64_t *state, double low, double high)
{
    return low + (high - low) * bench_uniform01(state);
}

static void fill_uniform(double *values, size_t count, uint64_t *state)
{
    for (size_t i = 0; i < count; i++)
        values[i] = range(state, -1e3, 1e3);
}

static void fill_short(double *values, size_t count, uint64_t *state)
{
    static const double common[] = {0.25, 1.5, 3, -0.125, 0.5, 1, 2, 10, 0.1, -1, 100, 0.75};
    for (size_t i = 0; i < count; i++) {
        double pick = bench_uniform01(state);
        if (pick < 0.3) {
            values[i] = common[(size_t)(bench_uniform01(state) * (sizeof common / sizeof common[0]))];
        } else if (pick < 0.8) {
            /* 1 to 4 decimals, as typed: the double nearest that decimal. */
            int decimals = 1 + (int)(bench_uniform01(state) * 4);
            char text[64];
            snprintf(text, sizeof text, "%.*f", decimals, range(state, -100, 100));
            values[i] = strtod(text, NULL);
        } else {
            values[i] = floor(range(state, -10000, 10000));
        }
    }
}

static void fill_witness(double *values, size_t count, uint64_t *state)
{
    for (size_t i = 0; i < count; i++) {
        double a = range(state, -2, 2), b = range(state, -2, 2);
        switch ((int)(bench_uniform01(state) * 5)) {
        case 0: values[i] = a + b; break;
        case 1: values[i] = a * b; break;
        case 2: values[i] = a / (fabs(b) + 0.1); break;
        case 3: values[i] = sqrt(fabs(a)); break;
        default: values[i] = cos(a) * 0.5; break;
        }
    }
}

typedef int (*formatter)(double value, char text[32]);

/* ns per number: the fastest of `passes` passes over the values (the
 * machine may be shared; the minimum is the least disturbed). */
static double time_formatter(formatter format, const double *values, size_t count, int passes,
                             unsigned long *checksum)
{
    char text[32];
    double best = INFINITY;
    for (int pass = 0; pass < passes; pass++) {
        double start = bench_seconds();
        for (size_t i = 0; i < count; i++)
            *checksum += (unsigned long)format(values[i], text) + (unsigned char)text[0];
        double seconds = bench_seconds() - start;
        if (seconds < best)
            best = seconds;
    }
    return best * 1e9 / (double)count;
}

/* One mix: prints its row (unless json) and gives the two timings. */
static void row(const char *name, const double *values, size_t count, int json, double *old_out,
                double *new_out)
{
    unsigned long checksum = 0;
    time_formatter(wp_format_number, values, count < 1000 ? count : 1000, 1, &checksum); /* warm */
    double old_ns = time_formatter(wp_format_number_exact, values, count, 3, &checksum);
    double new_ns = time_formatter(wp_format_number, values, count, 15, &checksum);
    size_t fallbacks = 0;
    char text[32];
    for (size_t i = 0; i < count; i++)
        fallbacks += wp_format_number_fast(values[i], text) < 0;
    *old_out = old_ns;
    *new_out = new_ns;
    if (json)
        printf("%s\"%s\": {\"old_ns\": %.2f, \"new_ns\": %.2f, \"exact_path\": %.6f}, ",
               strcmp(name, "uniform") == 0 ? "{" : "", name, old_ns, new_ns,
               (double)fallbacks / (double)count);
    else
        printf("%-8s %9.1f %9.1f %8.1fx %9.4f%%   (checksum %lu)\n", name, old_ns, new_ns,
               old_ns / new_ns, 100.0 * (double)fallbacks / (double)count, checksum % 1000);
}

int main(int argc, char **argv)
{
    size_t count = 100000;
    int json = 0;
    for (int i = 1; i < argc; i++) {
        if (strcmp(argv[i], "--count") == 0 && i + 1 < argc) {
            count = (size_t)strtoul(argv[++i], NULL, 10);
        } else if (strcmp(argv[i], "--json") == 0) {
            json = 1;
        } else {
            fprintf(stderr, "usage: number [--count N] [--json]\n");
            return 2;
        }
    }
    if (count == 0)
        count = 1;
    double *uniform_values = malloc(count * sizeof *uniform_values);
    double *short_values = malloc(count * sizeof *short_values);
    double *witness_values = malloc(count * sizeof *witness_values);
    double *all_values = malloc(3 * count * sizeof *all_values);
    if (!uniform_values || !short_values || !witness_values || !all_values) {
        fprintf(stderr, "number: out of memory\n");
        return 1;
    }
    uint64_t state = 0x9e3779b97f4a7c15u;
    fill_uniform(uniform_values, count, &state);
    fill_short(short_values, count, &state);
    fill_witness(witness_values, count, &state);
    for (size_t i = 0; i < count; i++) {
        all_values[3 * i] = uniform_values[i];
        all_values[3 * i + 1] = short_values[i];
        all_values[3 * i + 2] = witness_values[i];
    }
    if (!json) {
        printf("%zu numbers per mix; ns per number\n", count);
        printf("%-8s %9s %9s %9s %10s\n", "mix", "old", "new", "speed-up", "exact path");
    }
    double old_ns, new_ns;
    row("uniform", uniform_values, count, json, &old_ns, &new_ns);
    row("short", short_values, count, json, &old_ns, &new_ns);
    row("witness", witness_values, count, json, &old_ns, &new_ns);
    row("all", all_values, 3 * count, json, &old_ns, &new_ns);
    if (json) /* the top level: the interleaved mix */
        printf("\"count\": %zu, \"old_ns\": %.2f, \"new_ns\": %.2f}\n", count, old_ns, new_ns);
    free(uniform_values);
    free(short_values);
    free(witness_values);
    free(all_values);
    return 0;
}
