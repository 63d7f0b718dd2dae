/* wd_log.c -- logging to stderr, one line per event, written with a single
 * write(2) so lines from different threads never interleave. */
#include "wd_log.h"

#include <stdarg.h>
#include <stdio.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

static int threshold = WD_LOG_INFO;
static const char *const NAMES[] = {"error", "warn", "info", "debug"};

void wd_log_set_level(int level) { threshold = level; }

int wd_log_level_named(const char *name)
{
    for (int i = 0; i < 4; i++)
        if (strcmp(name, NAMES[i]) == 0)
            return i;
    return -1;
}

static void log_line(int level, const char *format, va_list args, unsigned long left_out,
                     int interval_s);

void wd_log(int level, const char *format, ...)
{
    if (level > threshold)
        return;
    va_list args;
    va_start(args, format);
    log_line(level, format, args, 0, 0);
    va_end(args);
}

void wd_log_limited(wd_log_limit *limit, int interval_s, int level, const char *format, ...)
{
    if (level > threshold)
        return;
    struct timespec now;
    clock_gettime(CLOCK_MONOTONIC, &now);
    long long seconds = (long long)now.tv_sec + 1; /* never 0 */
    if (limit->last && seconds - limit->last < interval_s) {
        limit->left_out++;
        return;
    }
    va_list args;
    va_start(args, format);
    log_line(level, format, args, limit->left_out, interval_s);
    va_end(args);
    limit->last = seconds;
    limit->left_out = 0;
}

static void log_line(int level, const char *format, va_list args, unsigned long left_out,
                     int interval_s)
{
    char line[1024];
    struct timespec now;
    clock_gettime(CLOCK_REALTIME, &now);
    struct tm utc;
    gmtime_r(&now.tv_sec, &utc);
    int n = (int)strftime(line, sizeof line, "%Y-%m-%dT%H:%M:%S", &utc);
    n += snprintf(line + n, sizeof line - (size_t)n, ".%03ldZ wrenchd %s: ",
                  now.tv_nsec / 1000000, NAMES[level]);
    int m = vsnprintf(line + n, sizeof line - (size_t)n - 1, format, args);
    n = m < 0 ? n : n + m > (int)sizeof line - 2 ? (int)sizeof line - 2 : n + m;
    if (left_out > 0) {
        m = snprintf(line + n, sizeof line - (size_t)n - 1,
                     " (and %lu more like it, not logged, in the %d s before)", left_out,
                     interval_s);
        n = m < 0 ? n : n + m > (int)sizeof line - 2 ? (int)sizeof line - 2 : n + m;
    }
    line[n++] = '\n';
    ssize_t written = write(2, line, (size_t)n);
    (void)written;
}
