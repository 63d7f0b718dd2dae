/* wp_number.c -- the text of a number (wp_number.h): a fast path in 128-bit
 * fixed point, and the exact path (snprintf + strtod) it falls back to.
 *
 * What the text is.  The exact path below is the definition: with P(p) the
 * %.{p}g text of v (correctly rounded to p significant digits, glibc's
 * printf, ties to even) it writes P(15) if P(15) reads back; then, if P(15)
 * shows 15 significant digits, P(14), P(13), ... as long as they read back;
 * else P(16) if it reads back; else P(17) (which always does).
 *
 * What that comes to for a normal double v (not subnormal), which the fast
 * path computes:
 *   - In v's rounding interval (the reals strtod rounds to v) there is at
 *     most one decimal of 15 or fewer significant digits: the interval is
 *     at most one ulp = 2^-52 * 2^E wide for v in [2^E, 2^(E+1)), and such
 *     decimals near x are more than x * 10^-15 apart.  So when P(p), p <= 15,
 *     reads back it has the value of P(15); the loop can only go on while
 *     P(p) is that same value, written in p digits.
 *   - P(15) "shows 15 significant digits" (counting the digit characters
 *     from the first non-zero one up to any 'e') when its value
 *     has 15 digits, or when it is written as an integer of 15 digits
 *     (decimal exponent 14, "100000000000000" counts 15).  In the first case
 *     P(14) is another value and the loop stops at once.  In the second, the
 *     value has k < 15 digits and P(14) ... P(k) write it (in exponent form,
 *     since its exponent 14 >= p) and P(k - 1) is another value: the text is
 *     the value in exponent form with its k digits.
 * So: the 15-digit rounding if it reads back -- in exponent form with its
 * digits if its decimal exponent is 14 and it has fewer than 15 significant
 * digits, else laid out as %.15g -- else the 16-digit rounding laid out as
 * %.16g if it reads back, else the 17-digit rounding laid out as %.17g.
 * Subnormals go to the exact path (their wide relative interval lets the
 * loop shorten below the 15-digit value's digits; they never occur in
 * wrenchd's data and are 1/2048 of all bit patterns).
 *
 * %g layout with precision P of a decimal with k significant digits (no
 * trailing zero) and decimal exponent X (first digit's place): exponent form
 * "d.ddde+XX" (at least two exponent digits) when X < -4 or X >= P, else
 * fixed notation with no trailing zeros after the point and no trailing
 * point; a leading '-' for negatives. */
#include "wp_number.h"

#include "wp_pow10.h"

#include <math.h>
#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* GCC and clang have a 128-bit integer; __extension__ keeps -pedantic quiet. */
__extension__ typedef unsigned __int128 uint128;

static const uint64_t power_of_ten[20] = {
    1u,
    10u,
    100u,
    1000u,
    10000u,
    100000u,
    1000000u,
    10000000u,
    100000000u,
    1000000000u,
    10000000000u,
    100000000000u,
    1000000000000u,
    10000000000000u,
    100000000000000u,
    1000000000000000u,
    10000000000000000u,
    100000000000000000u,
    1000000000000000000u,
    10000000000000000000u,
};

/* ---- the exact path ------------------------------------------------------ */

/* Significant digits in a %g text, as the definition counts them: every
 * digit from the first non-zero one up to an 'e'. */
static int significant_digits(const char *text)
{
    int digits = 0;
    bool leading = true;
    for (const char *c = text; *c && *c != 'e'; c++) {
        if (*c < '0' || *c > '9')
            continue;
        if (*c == '0' && leading)
            continue;
        leading = false;
        digits++;
    }
    return digits;
}

int wp_format_number_exact(double value, char text[32])
{
    if (!isfinite(value)) { /* JSON has no infinities: an overflowed result */
        strcpy(text, "null");
        return 4;
    }
    if (value == 0) { /* also -0 */
        strcpy(text, "0");
        return 1;
    }
    /* 17 digits always read back; find the fewest that do.  Most numbers
     * people write need few, and %.15g then already strips the rest. */
    int precision = 15;
    snprintf(text, 32, "%.15g", value);
    if (strtod(text, NULL) != value) {
        snprintf(text, 32, "%.16g", value);
        if (strtod(text, NULL) != value)
            snprintf(text, 32, "%.17g", value);
        return (int)strlen(text);
    }
    if (significant_digits(text) < precision)
        return (int)strlen(text);
    char shorter[32];
    for (precision = 14; precision >= 1; precision--) {
        snprintf(shorter, sizeof shorter, "%.*g", precision, value);
        if (strtod(shorter, NULL) != value)
            break;
        strcpy(text, shorter);
    }
    return (int)strlen(text);
}

/* ---- the fast path: writing the text ---------------------------------- */

/* Digits are built as ASCII in 64-bit words, character i in bits 8i to
 * 8i + 7 ("chars" words), and stored whole: no staging buffer, so no load
 * ever reads what narrower stores just wrote (which stalls the processor
 * when the store cannot be forwarded to the load). */

#define ASCII_ZEROS 0x3030303030303030u /* "00000000" */

/* Writes the 8 characters of a chars word at out[0..8). */
static inline void store_chars(char *out, uint64_t chars)
{
#if defined(__BYTE_ORDER__) && defined(__ORDER_LITTLE_ENDIAN__) && \
    __BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__
    memcpy(out, &chars, 8);
#elif defined(__BYTE_ORDER__) && defined(__ORDER_BIG_ENDIAN__) && \
    __BYTE_ORDER__ == __ORDER_BIG_ENDIAN__
    chars = __builtin_bswap64(chars);
    memcpy(out, &chars, 8);
#else
    for (int i = 0; i < 8; i++)
        out[i] = (char)(chars >> 8 * i);
#endif
}

/* The 8 decimal digits of x < 10^8, leading zeros included, as a chars
 * word (the first digit in the lowest byte).  The divisions are done in
 * all lanes of the word at once, by multiplying with a reciprocal and
 * shifting, exact for the lane values that occur:
 *   n / 100 = (n * 10486) >> 20 for n < 10^4: 10486 / 2^20 exceeds 1/100 by
 *     24 / (100 * 2^20), so the quotient is over n / 100 by less than
 *     0.0023, and n / 100 is at least 0.01 below the next integer;
 *   n / 10 = (n * 103) >> 10 for n < 100: over by less than 0.06, and n / 10
 *     is at least 0.1 below the next integer.
 * No lane's product reaches the next lane (10^4 * 10486 < 2^27 in 32-bit
 * lanes, 100 * 103 < 2^14 in 16-bit ones), and the masks keep only each
 * lane's quotient bits. */
static inline uint64_t eight_digits(uint32_t x)
{
    /* Two 32-bit lanes: the first four digits, then the last four. */
    uint64_t fours = x / 10000 | (uint64_t)(x % 10000) << 32;
    uint64_t hundreds = ((fours * 10486) >> 20) & 0x0000007f0000007fu;
    /* Four 16-bit lanes: the pairs of digits, in order. */
    uint64_t pairs = hundreds | (fours - 100 * hundreds) << 16;
    uint64_t tens = ((pairs * 103) >> 10) & 0x000f000f000f000fu;
    uint64_t ones = pairs - 10 * tens;
    /* Eight 8-bit lanes: the digits, in order. */
    return (tens | ones << 8) + ASCII_ZEROS;
}

/* Writes the decimal digits * 10^(exponent - precision + 1) -- digits has
 * exactly `precision` digits (15, 16 or 17; trailing zeros included, which
 * are not written), the first of place `exponent` -- as %.{layout}g does:
 * exponent form "d.ddde+XX" when exponent < -4 or >= layout, else fixed
 * notation.  With shorten_integer, an integer of 15 digits whose last is 0
 * ("100000000000000", exponent 14) is written in exponent form too (the
 * definition's loop goes on to %.14g and below for it).  Returns the
 * length.
 *
 * The stores have fixed sizes and may write past the end of the text,
 * later overwritten or left after the NUL; the bounds say why they stay
 * inside text[32]. */
static int write_decimal(char text[32], bool negative, uint64_t digits, int precision,
                         int exponent, int layout, bool shorten_integer)
{
    /* The same digits as 17, the first not '0': `first`, then the 8 of
     * `middle` (digits 1 to 8), then the 8 of `last` (9 to 16). */
    uint64_t seventeen = digits * power_of_ten[17 - precision]; /* < 10^17 */
    uint64_t first = seventeen / 10000000000000000u;            /* 10^16 */
    uint64_t rest = seventeen - first * 10000000000000000u;
    uint64_t middle = eight_digits((uint32_t)(rest / 100000000u));
    uint64_t last = eight_digits((uint32_t)(rest % 100000000u));
    char first_char = (char)('0' + first);
    /* The significant digits without the trailing zeros, in [1, 17]: in a
     * chars word the last character is the highest byte, so the trailing
     * '0's are the leading zero bytes of word ^ "00000000". */
    uint64_t middle_zeros = middle ^ ASCII_ZEROS, last_zeros = last ^ ASCII_ZEROS;
    int count = last_zeros     ? 17 - __builtin_clzll(last_zeros) / 8
                : middle_zeros ? 9 - __builtin_clzll(middle_zeros) / 8
                               : 1;
    bool exponent_form = exponent < -4 || exponent >= layout ||
                         (shorten_integer && exponent == 14 && count < 15);
    char *out = text + negative; /* text or text + 1 */
    text[0] = '-';               /* overwritten when not negative */
    if (exponent_form) {
        out[0] = first_char;
        out[1] = '.';
        store_chars(out + 2, middle);
        store_chars(out + 10, last);      /* up to text[18] */
        out += count > 1 ? count + 1 : 1; /* drops the point when alone */
        /* out <= text + 19: 'e', the sign and up to 3 digits, the NUL at
         * text[24] at most. */
        *out++ = 'e';
        *out++ = exponent < 0 ? '-' : '+';
        int magnitude = exponent < 0 ? -exponent : exponent; /* at most 308 */
        if (magnitude >= 100) {
            *out++ = (char)('0' + magnitude / 100);
            magnitude %= 100;
        }
        out[0] = (char)('0' + magnitude / 10);
        out[1] = (char)('0' + magnitude % 10);
        out += 2;
    } else if (exponent >= 0) {
        /* whole = exponent + 1 <= layout <= 17 digits before the point
         * (the zeros among them are in the 17). */
        int whole = exponent + 1;
        out[0] = first_char;
        store_chars(out + 1, middle);
        store_chars(out + 9, last); /* up to text[17] */
        if (count > whole) {
            /* The point after digit whole - 1 (so whole <= 16), and digits
             * whole to 16 again one place on: digit i is character i - 1
             * of middle (i <= 8) or i - 9 of last. */
            out[whole] = '.';
            if (whole <= 8) {
                store_chars(out + whole + 1, middle >> 8 * (whole - 1)); /* text[18] */
                store_chars(out + 10, last);                             /* text[19] */
            } else {
                store_chars(out + whole + 1, last >> 8 * (whole - 9)); /* text[25] */
            }
            out += count + 1;
        } else {
            out += whole;
        }
    } else {
        /* exponent in [-4, -1]: "0." and -exponent - 1 zeros (at most 3),
         * then the digits: out <= text + 6 then, the stores reach text[22]. */
        memcpy(out, "0.000", 5);
        out += 1 - exponent;
        out[0] = first_char;
        store_chars(out + 1, middle);
        store_chars(out + 9, last);
        out += count;
    }
    *out = 0;
    return (int)(out - text);
}

/* ---- the fast path: the arithmetic ------------------------------------ */

/* The scaled value of v, N = v * 10^q, is kept in fixed point with 64 bits
 * after the point: `integer` + `fraction` / 2^64.  Quantities in these units
 * ("units" below are 2^-64) carry errors of at most about 2 units (bounds
 * where they are computed); a decision whose two sides are closer than
 * MARGIN units is left to the exact path.
 *
 * Exact ties -- a rounding exactly half-way, a candidate exactly on the
 * boundary of v's rounding interval -- are always within the error.  When
 * the fixed-point quantities are exact (10^q is, for 0 <= q <= 55, and no
 * bit of the product or of the half gaps was shifted out: v's with short
 * decimal expansions, such as 1234567890123455 or 1000000000000000.25, the
 * only ones that can be ties at 15 to 17 digits) the ties are decided here
 * as printf and strtod decide them: printf rounds half-way to the even last
 * digit, and strtod rounds a decimal on the boundary to the double with the
 * even significand.  Otherwise they go to the exact path. */
#define MARGIN 4

typedef enum { UNSURE, INSIDE, OUTSIDE } verdict;

typedef struct scaled_value {
    uint64_t integer;        /* floor(N), in [10^16 - 1, 10^18) */
    uint64_t quotient[4];    /* integer / 10^i, i in [0, 3], computed once:
                              * which one a precision needs depends on
                              * `extra`, and an index costs no branch */
    uint64_t fraction;       /* the next 64 bits of N */
    int extra;               /* 1 if N has 18 digits before the point, else 0 */
    int leading_exponent;    /* decimal exponent of v's first digit, d +
                              * extra (see the caller for N near 10^17) */
    uint128 half_above;      /* half the gap to the next double up, in units */
    uint128 half_below;      /* half the gap to the next double down */
    bool exact;              /* N and the half gaps have no error at all */
    bool even;               /* v's significand m is even */
} scaled_value;

/* The p-digit rounding of v: digits (exactly p of them, trailing zeros
 * included) and the decimal exponent of the first; whether it reads back
 * as v (INSIDE), or not (OUTSIDE), or UNSURE when the rounding or the
 * read-back is too close to call.  With check false only the rounding is
 * decided (for p = 17, which always reads back). */
static inline verdict round_to_precision(const scaled_value *n, int precision, bool check,
                                         uint64_t *digits, int *exponent)
{
    /* The p-digit rounding of v is the multiple of unit = 10^power nearest
     * to N: N has 17 + extra digits before the point. */
    int power = 17 - precision + n->extra;
    uint64_t quotient = n->quotient[power];
    uint64_t remainder_integer = n->integer - quotient * power_of_ten[power];
    /* The remainder N mod unit in units: < 10^3 * 2^64.  N's error (below)
     * makes it too small by less than 1.02 units -- or, when the true N has
     * just passed a multiple of unit, close to unit while the true one is
     * close to 0: then both round to that same multiple, and the distance
     * to it is still off by less than 1.02 units. */
    uint128 remainder = (uint128)remainder_integer << 64 | n->fraction;
    uint128 unit = (uint128)power_of_ten[power] << 64;
    uint128 half = unit >> 1;
    bool up;
    if (n->exact)
        up = remainder > half || (remainder == half && quotient % 2 == 1); /* ties to even */
    else if (remainder + MARGIN > half && remainder < half + MARGIN)
        return UNSURE; /* a tie or near one */
    else
        up = remainder > half;
    uint128 distance = up ? unit - remainder : remainder; /* from N to the candidate */
    quotient += up;
    /* quotient has p digits, or is 10^p after carrying (999...9 rounded
     * up).  Fewer digits cannot occur (gen_pow10.py checks N >= 10^16 - 1,
     * and rounding 10^16 - 1 + x for x in [0, 1) takes it up to 10^16), but
     * a wrong answer must not come out of a broken table. */
    *exponent = n->leading_exponent;
    if (quotient >= power_of_ten[precision]) {
        quotient /= 10;
        ++*exponent;
    }
    if (quotient < power_of_ten[precision - 1] || quotient >= power_of_ten[precision])
        return UNSURE;
    *digits = quotient;
    if (!check)
        return INSIDE;
    /* It reads back iff it lies in v's rounding interval: within half a gap
     * of N on its side.  The half gap is off by less than 1.01 units, the
     * distance by less than 1.02: together less than MARGIN. */
    uint128 reach = up ? n->half_above : n->half_below;
    if (n->exact) {
        /* On the boundary, strtod rounds to the even significand. */
        if (distance == reach)
            return n->even ? INSIDE : OUTSIDE;
        return distance < reach ? INSIDE : OUTSIDE;
    }
    if (distance + MARGIN > reach && distance < reach + MARGIN)
        return UNSURE; /* on the boundary or near it */
    return distance < reach ? INSIDE : OUTSIDE;
}

int wp_format_number_fast(double value, char text[32])
{
    uint64_t bits;
    memcpy(&bits, &value, sizeof bits);
    bool negative = bits >> 63;
    int biased_exponent = (int)(bits >> 52 & 0x7ff);
    uint64_t stored_fraction = bits & ((UINT64_C(1) << 52) - 1);
    if (biased_exponent == 0x7ff) { /* JSON has no infinities: an overflowed result */
        memcpy(text, "null", 5);
        return 4;
    }
    if (biased_exponent == 0) {
        if (stored_fraction != 0)
            return -1; /* subnormal: the exact path */
        memcpy(text, "0", 2); /* also -0 */
        return 1;
    }

    /* v = m * 2^e exactly, 2^52 <= m < 2^53, v in [2^E, 2^(E + 1)). */
    uint64_t m = stored_fraction | UINT64_C(1) << 52;
    int E = biased_exponent - 1023;
    int e = E - 52;
    /* d = floor(E log10 2) (78913 / 2^18 is just above log10 2; the bias
     * keeps the shifted value non-negative; gen_pow10.py checks the formula
     * exact for every E).  v's first digit has place d or d + 1, as
     * 10^d <= 2^E <= v < 2^(E + 1) < 10^(d + 2). */
    int d = ((E * 78913 + 400 * 262144) >> 18) - 400;
    /* Scale by 10^q so that N = v * 10^q is in [10^16, 10^18): 17 or 18
     * digits before the point.  (q in [-291, 324]: the table's range.) */
    int q = 16 - d;
    const uint64_t *significand = wp_pow10_significand[q - WP_POW10_MIN];
    int binary_exponent = wp_pow10_binary_exponent[q - WP_POW10_MIN];
    /* 10^q = (T + tau) * 2^t with tau in [0, 1) (wp_pow10.h), so, with
     * S = -(e + t + 64) -- in [59, 62] for every E (gen_pow10.py checks) --
     *     N * 2^64 = m * (T + tau) / 2^S.
     * We compute floor(m * T / 2^S) from the full 181-bit product; it is
     * below N * 2^64 by the truncated part (< 1) plus m * tau / 2^S (< 2^53
     * / 2^59): by less than 1.02 units. */
    int shift = -(e + binary_exponent + 64);
    uint128 low_product = (uint128)m * significand[1];
    uint128 high_product = (uint128)m * significand[0] + (low_product >> 64);
    /* high_product << (64 - S) stays below 2^128: it is at most
     * floor(N * 2^64) < 10^18 * 2^64 < 2^124. */
    uint128 fixed = high_product << (64 - shift) | (uint64_t)low_product >> shift;
    scaled_value n;
    n.integer = (uint64_t)(fixed >> 64);
    n.fraction = (uint64_t)fixed;
    if (n.integer < power_of_ten[16] - 1 || n.integer >= power_of_ten[18])
        return -1; /* cannot happen (gen_pow10.py checks the range) */
    n.extra = n.integer >= power_of_ten[17];
    n.quotient[0] = n.integer;
    n.quotient[1] = n.integer / 10;
    n.quotient[2] = n.integer / 100;
    n.quotient[3] = n.integer / 1000;
    /* If the true N is within the error (1.02 units) of 10^17, the
     * computed one may sit on the other side of it and `extra` be wrong; but
     * then every rounding of either is 10^17 (after a carry when extra is
     * 0), with the same exponent d + 1, so the text does not change. */
    n.leading_exponent = d + n.extra;
    /* Half the gap to the next double up: 2^(e - 1) * 10^q * 2^64 =
     * (T + tau) / 2^(S + 1), computed as floor(T / 2^(S + 1)): below it by
     * less than 1 + 2^-60 units.  Down, the gap is half as wide when m is
     * 2^52 (v a power of two), except for the least normal, whose neighbour
     * below is a subnormal as far away as the one above. */
    uint128 whole_significand = (uint128)significand[0] << 64 | significand[1];
    bool narrower_below = stored_fraction == 0 && biased_exponent > 1;
    n.half_above = whole_significand >> (shift + 1);
    n.half_below = whole_significand >> (shift + 1 + narrower_below);
    /* Exact: tau = 0 (10^q = T * 2^t exactly for 0 <= q <= 55), no bit of
     * m * T below 2^S, and no bit of T below 2^(S + 2) (the half gaps drop
     * S + 1 or S + 2 bits; S + 2 <= 64, so they are all in the low word:
     * shifting it left by 62 - S keeps just them). */
    n.exact = q >= 0 && q <= WP_POW10_EXACT_MAX &&
              ((uint64_t)low_product << (64 - shift)) == 0 &&
              (significand[1] << (62 - shift)) == 0;
    n.even = m % 2 == 0;

    uint64_t digits;
    int exponent;
    verdict fifteen = round_to_precision(&n, 15, true, &digits, &exponent);
    if (fifteen == UNSURE)
        return -1;
    if (fifteen == INSIDE)
        return write_decimal(text, negative, digits, 15, exponent, 15, true);
    verdict sixteen = round_to_precision(&n, 16, true, &digits, &exponent);
    if (sixteen == UNSURE)
        return -1;
    if (sixteen == INSIDE)
        return write_decimal(text, negative, digits, 16, exponent, 16, false);
    if (round_to_precision(&n, 17, false, &digits, &exponent) == UNSURE)
        return -1;
    return write_decimal(text, negative, digits, 17, exponent, 17, false);
}

int wp_format_number(double value, char text[32])
{
    int length = wp_format_number_fast(value, text);
    return length >= 0 ? length : wp_format_number_exact(value, text);
}
