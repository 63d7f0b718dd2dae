/* wd_log.h -- one line per event on stderr: time, level, message. */
#ifndef WD_LOG_H
#define WD_LOG_H

enum { WD_LOG_ERROR, WD_LOG_WARN, WD_LOG_INFO, WD_LOG_DEBUG };

/* The process-wide threshold (set once at start, before threads). */
void wd_log_set_level(int level);
/* Parse "error", "warn", "info", "debug"; -1 if none of them. */
int wd_log_level_named(const char *name);
void wd_log(int level, const char *format, ...) __attribute__((format(printf, 2, 3)));

/* Events that can come in floods (a peer denied, accept failing): at most
 * one line per interval for each kind, the next line saying how many were
 * left out.  One per kind of event, zeroed; used by one thread only. */
typedef struct wd_log_limit {
    long long last;              /* monotonic seconds of the last line; 0: none */
    unsigned long left_out;      /* events since that line, not logged */
} wd_log_limit;

void wd_log_limited(wd_log_limit *limit, int interval_s, int level, const char *format, ...)
    __attribute__((format(printf, 4, 5)));

#endif
