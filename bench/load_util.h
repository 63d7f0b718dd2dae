/* load_util.h -- what the load generator's three parts (load_requests.c, the
 * table; load_client.c, one connection; load.c, the driver) all need:
 * allocation that cannot fail, growing text, and its random stream.
 *
 * Running out of memory ends the program (exit status 1, after a line
 * "load: ..." on stderr): a load generator that half-ran would report
 * figures nobody could trust. */
#ifndef LOAD_UTIL_H
#define LOAD_UTIL_H

#include <stddef.h>
#include <stdint.h>

/* "load: " and the message on stderr, then exit status 1. */
_Noreturn void die(const char *format, ...) __attribute__((format(printf, 1, 2)));

void *xmalloc(size_t size);
void *xrealloc(void *p, size_t size);
char *xstrdup(const char *s);
char *xprintf(const char *format, ...) __attribute__((format(printf, 1, 2)));

/* Append `text` to the NUL-terminated buffer *buffer of *length bytes,
 * growing it (and *capacity) as needed; *buffer may start NULL. */
void append(char **buffer, size_t *length, size_t *capacity, const char *text);

/* The random stream: splitmix64, one state per table and per client.  Not
 * bench_util.h's xorshift: the table and every line sent are a function of
 * --seed, and the figures bench/README.md and the soak quote were made with
 * this stream. */
uint64_t random_next(uint64_t *state);
double random_uniform(uint64_t *state, double low, double high); /* in [low, high) */
int random_pick(uint64_t *state, int n);                         /* in [0, n) */

#endif
