/* wp_number.h -- the text of a number, as wrenchd writes every number
 * (answers and the canonical text that fixture ids hash).  Included by
 * wp_json.h. */
#ifndef WP_NUMBER_H
#define WP_NUMBER_H

#ifdef __cplusplus
extern "C" {
#endif

/* Shortest decimal text that reads back as the same double ("1", "0.5",
 * "1e+21"); -0 is written "0", and a non-finite value (which JSON cannot
 * hold) "null".  Needs 32 bytes; returns the length written (without the
 * NUL).
 *
 * The text is the one this historical definition gives, byte for byte
 * (fixture ids hash it, so it must never change): the %.15g text if it
 * reads back -- and then, if it shows 15 significant digits, %.14g, %.13g,
 * ... for as long as they still read back -- else %.16g if it reads back,
 * else %.17g.  wp_format_number_exact below is that definition, run
 * literally; wp_format_number computes the same text faster (bench/number.c
 * measures by how much) and falls back to the exact path when it cannot be sure. */
int wp_format_number(double value, char text[32]);

/* For the tests and the benchmark.  The fast path alone: the length, or -1
 * (text undefined) when the value needs the exact path -- a subnormal, or
 * a rounding or a read-back too close to call (an exact tie). */
int wp_format_number_fast(double value, char text[32]);
/* The exact path alone: snprintf and strtod, slow but plainly right. */
int wp_format_number_exact(double value, char text[32]);

#ifdef __cplusplus
}
#endif

#endif
