/* wd_log.h -- one line per event on stderr: time, level, message. */
#ifndef WD_LOG_H
#define WD_LOG_H

enum { WD_LOG_ERROR, WD_LOG_WARN, WD_LOG_INFO, WD_LOG_DEBUG };

/* The process-wide threshold (set once at start, before threads). */
void wd_log_set_level(int level);
/* Parse "error", "warn", "info", "debug"; -1 if none of them. */
int wd_log_level_named(const char *name);
void wd_log(int level, const char *format, ...) __attribute__((format(printf, 2, 3)));

#endif
