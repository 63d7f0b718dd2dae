/* test_number.c -- wp_format_number (proto/wp_number.c) against the
 * formatter it replaced, kept below as the oracle: the same text, byte for
 * byte, for every double tried (fixture ids hash these texts), the length
 * it returns, and a text that reads back as the same double.  Each test
 * prints how many values it checked and how many the fast path left to the
 * exact one.
 *
 * WR_NUMBER_COUNT=N sets the number of random 64-bit patterns (default 1.5
 * million, a quarter of that under AddressSanitizer), and a quarter of N
 * the number of random doubles of the sizes wrenchd writes, for a long
 * run on demand:
 *     WR_NUMBER_COUNT=100000000 build/tests/test_number */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>
#include <float.h>
#include <inttypes.h>
#include <math.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "wp_json.h"
#include "wp_number.h"

#if defined(__SANITIZE_ADDRESS__)
#define SANITIZED 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define SANITIZED 1
#endif
#endif
#ifndef SANITIZED
#define SANITIZED 0
#endif

/* Values per set; a quarter under ASan (about 4 times slower). */
#define SCALE(count) (SANITIZED ? (count) / 4 : (count))

/* ---- the oracle: wp_format_number as it was (proto/wp_json.c before
 * wp_number.c), unchanged ----------------------------------------------- */

static int oracle_significant_digits(const char *text)
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

static void oracle_format_number(double value, char text[32])
{
    if (!isfinite(value)) {
        strcpy(text, "null");
        return;
    }
    if (value == 0) {
        strcpy(text, "0");
        return;
    }
    int precision = 15;
    snprintf(text, 32, "%.15g", value);
    if (strtod(text, NULL) != value) {
        snprintf(text, 32, "%.16g", value);
        if (strtod(text, NULL) != value)
            snprintf(text, 32, "%.17g", value);
        return;
    }
    if (oracle_significant_digits(text) < precision)
        return;
    char shorter[32];
    for (precision = 14; precision >= 1; precision--) {
        snprintf(shorter, sizeof shorter, "%.*g", precision, value);
        if (strtod(shorter, NULL) != value)
            return;
        strcpy(text, shorter);
    }
}

/* ---- checking ------------------------------------------------------------- */

typedef struct tally {
    long checked;
    long exact_path;           /* values the fast path left to the exact one */
    long exact_path_subnormal; /* of which subnormals (all of them go) */
} tally;

static uint64_t bits_of(double value)
{
    uint64_t bits;
    memcpy(&bits, &value, sizeof bits);
    return bits;
}

static double double_of(uint64_t bits)
{
    double value;
    memcpy(&value, &bits, sizeof value);
    return value;
}

static void check(tally *t, double value)
{
    char expected[32], got[32], fast[32];
    oracle_format_number(value, expected);
    memset(got, 'z', sizeof got);
    int length = wp_format_number(value, got);
    if (strcmp(got, expected) != 0 || length != (int)strlen(got)) {
        print_message("number: %a (bits %016" PRIx64 "): wanted \"%s\", got \"%s\" (length %d)\n",
                      value, bits_of(value), expected, got, length);
        fail();
    }
    if (isfinite(value) && strtod(got, NULL) != value) {
        print_message("number: %a: \"%s\" does not read back\n", value, got);
        fail();
    }
    int fast_length = wp_format_number_fast(value, fast);
    if (fast_length < 0) {
        t->exact_path++;
        t->exact_path_subnormal += fpclassify(value) == FP_SUBNORMAL;
    } else if (fast_length != length || strcmp(fast, got) != 0) {
        print_message("number: %a: the fast path wrote \"%s\"\n", value, fast);
        fail();
    }
    t->checked++;
}

/* The value, its negation, and both neighbours of each. */
static void check_around(tally *t, double value)
{
    for (int sign = 0; sign < 2; sign++, value = -value) {
        check(t, value);
        check(t, nextafter(value, -INFINITY));
        check(t, nextafter(value, INFINITY));
    }
}

static void report(const char *what, const tally *t)
{
    print_message("number: %-38s %9ld checked, %7ld (%.4f%%) by the exact path", what,
                  t->checked, t->exact_path,
                  t->checked ? 100.0 * (double)t->exact_path / (double)t->checked : 0.0);
    if (t->exact_path_subnormal)
        print_message(", %ld of them subnormal", t->exact_path_subnormal);
    print_message("\n");
}

/* splitmix64: a fixed seed gives the same values on every machine. */
static uint64_t next_random(uint64_t *state)
{
    uint64_t z = (*state += 0x9e3779b97f4a7c15u);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9u;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebu;
    return z ^ (z >> 31);
}

/* In [0, 1), 53 random bits. */
static double random_unit(uint64_t *state)
{
    return (double)(next_random(state) >> 11) / 9007199254740992.0;
}

/* In [0, n). */
static uint64_t random_below(uint64_t *state, uint64_t n)
{
    return next_random(state) % n;
}

/* A random integer of exactly `digits` decimal digits (1..19). */
static uint64_t random_digits(uint64_t *state, int digits)
{
    uint64_t low = 1;
    for (int i = 1; i < digits; i++)
        low *= 10;
    uint64_t span = digits == 1 ? 9 : (digits >= 20 ? UINT64_MAX : 9 * low);
    return low + random_below(state, span);
}

/* ---- the tests ------------------------------------------------------------ */

/* Fixed texts: the layout rules, written out. */
static void number_known_texts(void **state)
{
    (void)state;
    struct {
        double value;
        const char *text;
    } known[] = {
        {0.0, "0"},
        {-0.0, "0"},
        {1.0, "1"},
        {-1.0, "-1"},
        {0.1, "0.1"},
        {0.25, "0.25"},
        {-2.5, "-2.5"},
        {1.0 / 3, "0.3333333333333333"},
        {2.0 / 3, "0.6666666666666666"},
        {0.1 + 0.2, "0.30000000000000004"},
        {100, "100"},
        {1e-4, "0.0001"},
        {1.5e-4, "0.00015"},
        {1e-5, "1e-05"},
        {1.5e-5, "1.5e-05"},
        {1e13, "10000000000000"},
        {123456789012345.0, "123456789012345"},
        {1e14, "1e+14"},          /* %.15g shows 15 digits: the loop shortens it */
        {1.2e14, "1.2e+14"},      /* likewise */
        {123456789012340.0, "1.2345678901234e+14"},
        {1e15, "1e+15"},
        {1234567890123456.0, "1234567890123456"},
        {9007199254740992.0, "9007199254740992"},
        {1e16, "1e+16"},
        {12345678901234568.0, "12345678901234568"},
        {1e21, "1e+21"},
        {1e23, "1e+23"}, /* 10^23 is half-way between two doubles */
        {1234567890123455.0, "1234567890123455"}, /* %.15g is a tie */
        {DBL_MAX, "1.7976931348623157e+308"},
        {-DBL_MAX, "-1.7976931348623157e+308"},
        {DBL_MIN, "2.2250738585072014e-308"},
        {DBL_TRUE_MIN, "5e-324"},
        {DBL_EPSILON, "2.220446049250313e-16"},
        {INFINITY, "null"},
        {-INFINITY, "null"},
        {NAN, "null"},
    };
    tally t = {0, 0, 0};
    for (size_t i = 0; i < sizeof known / sizeof known[0]; i++) {
        char text[32];
        int length = wp_format_number(known[i].value, text);
        assert_string_equal(text, known[i].text);
        assert_int_equal(length, (int)strlen(known[i].text));
        check(&t, known[i].value);
    }
}

/* WR_NUMBER_COUNT, or the default. */
static long random_count(void)
{
    const char *given = getenv("WR_NUMBER_COUNT");
    if (given && *given)
        return strtol(given, NULL, 10);
    return SCALE(1500000);
}

/* Random 64-bit patterns: every exponent, sign and significand alike. */
static void number_random_bit_patterns(void **state)
{
    (void)state;
    long count = random_count();
    uint64_t random = 20240601;
    tally t = {0, 0, 0}, subnormal = {0, 0, 0};
    long non_finite = 0;
    for (long i = 0; i < count; i++) {
        double value = double_of(next_random(&random));
        if (!isfinite(value)) {
            non_finite++;
            check(&t, value); /* "null" both */
            continue;
        }
        check(fpclassify(value) == FP_SUBNORMAL ? &subnormal : &t, value);
    }
    report("random bit patterns (normal)", &t);
    report("random bit patterns (subnormal)", &subnormal);
    print_message("number: %ld of the patterns were not finite (\"null\")\n", non_finite);
}

/* Random doubles of the sizes wrenchd writes (forces, torques, positions,
 * witnesses: 17 significant digits mostly): uniform in [-1, 1] times 10^k,
 * k in [-8, 8]. */
static void number_random_typical(void **state)
{
    (void)state;
    long count = random_count() / 4;
    uint64_t random = 424242;
    tally t = {0, 0, 0};
    for (long i = 0; i < count; i++) {
        double scale = pow(10, (double)random_below(&random, 17) - 8);
        check(&t, (random_unit(&random) * 2 - 1) * scale);
    }
    report("random in [-1, 1] * 10^(-8..8)", &t);
}

/* What people type: doubles in [-1, 1] rounded to 1..8 decimals, and
 * numbers of 1 to 17 significant digits at every scale. */
static void number_typed_decimals(void **state)
{
    (void)state;
    uint64_t random = 7;
    tally typed = {0, 0, 0}, scaled = {0, 0, 0};
    char text[64];
    for (int decimals = 1; decimals <= 8; decimals++)
        for (long i = 0; i < SCALE(15000); i++) {
            snprintf(text, sizeof text, "%.*f", decimals, random_unit(&random) * 2 - 1);
            check(&typed, strtod(text, NULL));
        }
    for (long i = 0; i < SCALE(30000); i++) {
        int digits = 1 + (int)random_below(&random, 17);
        int exponent = -330 + (int)random_below(&random, 640);
        snprintf(text, sizeof text, "%" PRIu64 "e%d", random_digits(&random, digits), exponent);
        double value = strtod(text, NULL);
        if (value != 0 && isfinite(value))
            check_around(&scaled, value);
    }
    report("[-1, 1] with 1..8 decimals", &typed);
    report("1..17 digits, 10^-330..10^310, +-1ulp", &scaled);
}

/* Powers of two and of ten with their neighbours, the extremes, and
 * subnormals. */
static void number_powers_and_extremes(void **state)
{
    (void)state;
    tally two = {0, 0, 0}, ten = {0, 0, 0}, extremes = {0, 0, 0}, subnormal = {0, 0, 0};
    for (int i = -1074; i <= 1023; i++)
        check_around(&two, ldexp(1, i));
    char text[32];
    for (int i = -323; i <= 308; i++)
        for (int digit = 1; digit <= 9; digit++) {
            snprintf(text, sizeof text, "%de%d", digit, i);
            check_around(&ten, strtod(text, NULL));
        }
    double extreme[] = {DBL_MAX, DBL_MIN, DBL_TRUE_MIN, DBL_EPSILON, 1, 0.5, 2,
                        nextafter(DBL_MIN, 0), 0x1p-1022, 0x1.fffffffffffffp-1, 0x1p53, 0x1p64,
                        0x1p1023, 0x1.8p1023};
    for (size_t i = 0; i < sizeof extreme / sizeof extreme[0]; i++)
        check_around(&extremes, extreme[i]);
    /* Subnormals: the smallest, those below DBL_MIN, random ones. */
    uint64_t random = 99;
    for (uint64_t k = 1; k <= (uint64_t)SCALE(2000); k++) {
        check(&subnormal, double_of(k));
        check(&subnormal, double_of(0x000fffffffffffffu - k + 1));
    }
    for (long i = 0; i < SCALE(6000); i++)
        check(&subnormal, double_of(next_random(&random) & 0x800fffffffffffffu));
    report("2^-1074..2^1023, +-1ulp", &two);
    report("d*10^-323..d*10^308, +-1ulp", &ten);
    report("extremes, +-1ulp", &extremes);
    report("subnormals", &subnormal);
}

/* Integers: small ones, random ones up to 2^53, and around 2^53..2^64. */
static void number_integers(void **state)
{
    (void)state;
    tally small = {0, 0, 0}, random_integers = {0, 0, 0}, large = {0, 0, 0};
    for (long i = 0; i <= SCALE(30000); i++)
        check(&small, (double)i);
    uint64_t random = 5;
    for (long i = 0; i < SCALE(60000); i++) {
        int bits = 1 + (int)random_below(&random, 53);
        check(&random_integers, (double)(next_random(&random) >> (64 - bits)));
    }
    /* 300 doubles either side of each power of two from 2^53 to 2^64, and
     * random integers up to 2^64 (rounded to doubles). */
    for (int k = 53; k <= 64; k++) {
        double up = ldexp(1, k), down = up;
        for (int i = 0; i < SCALE(300); i++) {
            check(&large, up);
            check(&large, down);
            up = nextafter(up, INFINITY);
            down = nextafter(down, 0);
        }
    }
    for (long i = 0; i < SCALE(30000); i++) {
        int bits = 54 + (int)random_below(&random, 11);
        check(&large, (double)(next_random(&random) >> (64 - bits)));
    }
    char what[64];
    snprintf(what, sizeof what, "integers 0..%ld", (long)SCALE(30000));
    report(what, &small);
    report("random integers below 2^53", &random_integers);
    report("around 2^53..2^64", &large);
}

/* Near and at the decision points: roundings half-way at 15, 16 and 17
 * digits (exactly, for doubles with short binary fractions, and nearly,
 * for decimals ending in 5), and decimals exactly half-way between two
 * doubles (the boundary of both rounding intervals). */
static void number_near_ties(void **state)
{
    (void)state;
    uint64_t random = 11;
    tally exact_ties = {0, 0, 0}, decimal_ties = {0, 0, 0}, midpoints = {0, 0, 0};
    /* A * 2^-j, A odd: exactly j digits after the point, the last a 5. */
    for (long i = 0; i < SCALE(60000); i++) {
        int bits = 1 + (int)random_below(&random, 53);
        uint64_t a = next_random(&random) >> (64 - bits) | 1;
        int j = 1 + (int)random_below(&random, 70);
        check(&exact_ties, ldexp((double)a, -j));
        check(&exact_ties, -ldexp((double)a, -j));
    }
    /* 16-, 17- and 18-digit decimals ending in 5, at every scale. */
    char text[64];
    for (long i = 0; i < SCALE(20000); i++) {
        int digits = 15 + (int)random_below(&random, 3);
        int exponent = -300 + (int)random_below(&random, 600);
        snprintf(text, sizeof text, "%" PRIu64 "5e%d", random_digits(&random, digits), exponent);
        check_around(&decimal_ties, strtod(text, NULL));
    }
    /* Midpoints: for v in [2^E, 2^(E+1)), E >= 53, the ulp is 2^(E-52) and
     * the midpoints are the odd multiples of 2^(E-53).  M = c * 10^z with c
     * of at most 16 digits is one when c is an odd multiple of 2^(E-53-z);
     * strtod(M) is the even neighbour, and the odd one is next to it. */
    for (int E = 53; E <= 140; E++)
        for (int attempt = 0; attempt < SCALE(500); attempt++) {
            int z = (int)floor(E * 0.30102999566398120) - 15;
            if (z < 0)
                z = 0;
            int twos = E - 53 - z; /* c must be an odd multiple of 2^twos */
            if (twos < 0 || twos > 52)
                continue;
            /* c near 2^E / 10^z, chosen at random in the binade. */
            double target = ldexp(1 + random_unit(&random), E) / pow(10, z);
            uint64_t odd = (uint64_t)(target / ldexp(1, twos));
            if (odd == 0)
                continue;
            odd |= 1;
            if (odd >= (UINT64_C(1) << (63 - twos)))
                continue;
            uint64_t c = odd << twos;
            snprintf(text, sizeof text, "%" PRIu64 "e%d", c, z);
            double even = strtod(text, NULL);
            if (ilogb(even) != E)
                continue;
            check(&midpoints, even);
            check(&midpoints, nextafter(even, 0));
            check(&midpoints, nextafter(even, INFINITY));
        }
    report("A*2^-j (exact ties)", &exact_ties);
    report("decimals ending in 5, +-1ulp", &decimal_ties);
    report("decimals half-way between doubles", &midpoints);
}

/* ---- reading: wp_json_triples against strtod ------------------------------- */

/* One number's text of a random form: %g and %f and %e at every precision,
 * random digit strings with and without a fraction and an exponent (up to
 * 25 digits, exponents to +-40), zeros and negative zeros. */
static void random_number_text(uint64_t *state, char *out, size_t size)
{
    uint64_t r = next_random(state);
    double value;
    memcpy(&value, &(uint64_t){next_random(state)}, sizeof value);
    if (!isfinite(value))
        value = 1.5;
    double typical = ((double)(next_random(state) >> 11) / 9007199254740992.0 - 0.5) *
                     pow(10, (int)(r % 13) - 6);
    switch (r % 7) {
    case 0:
        snprintf(out, size, "%.*g", 1 + (int)((r >> 8) % 17), value);
        break;
    case 1:
        snprintf(out, size, "%.*f", (int)((r >> 8) % 10), typical);
        break;
    case 2:
        snprintf(out, size, "%.*e", (int)((r >> 8) % 17), typical);
        break;
    case 3:
        snprintf(out, size, "%.17g", typical);
        break;
    case 4: {
        /* Digits: an integer part (no leading zero), maybe a fraction,
         * maybe an exponent. */
        size_t n = 0;
        if (r & 256)
            out[n++] = '-';
        int whole = 1 + (int)((r >> 10) % 12);
        for (int k = 0; k < whole; k++)
            out[n++] = (char)('0' + (k == 0 && whole > 1 ? 1 + next_random(state) % 9
                                                       : next_random(state) % 10));
        if (r & 512) {
            out[n++] = '.';
            int fraction = 1 + (int)((r >> 14) % 13);
            for (int k = 0; k < fraction; k++)
                out[n++] = (char)('0' + next_random(state) % 10);
        }
        if (r & 1024)
            n += (size_t)snprintf(out + n, size - n, "%s%d", (r & 2048) ? "e" : "E",
                                  (int)((r >> 20) % 81) - 40);
        out[n] = 0;
        break;
    }
    case 5:
        snprintf(out, size, "%s", (const char *[]){"0", "-0", "0.0", "-0.000", "0e5", "-0E-3",
                                                  "1e22", "1e23", "9007199254740993",
                                                  "123456789012345678901234"}[(r >> 8) % 10]);
        break;
    default:
        snprintf(out, size, "%.6f", typical * 1e6);
        break;
    }
}

static void number_reading(void **state)
{
    (void)state;
    uint64_t seed = 0x1234abcd5678ef90ULL;
    enum { TRIPLES = 100000 };
    size_t size = (size_t)TRIPLES * 3 * 64 + 16;
    char *text = malloc(size);
    double(*expected)[3] = malloc(TRIPLES * sizeof *expected);
    assert_non_null(text);
    assert_non_null(expected);
    size_t used = 0;
    text[used++] = '[';
    long count = SCALE(TRIPLES);
    for (long i = 0; i < count; i++) {
        used += (size_t)snprintf(text + used, size - used, "%s[", i ? "," : "");
        for (int k = 0; k < 3; k++) {
            char number[64];
            do /* "2e+308", %.1g of the largest double, is refused as infinite */
                random_number_text(&seed, number, sizeof number);
            while (!isfinite(expected[i][k] = strtod(number, NULL)));
            used += (size_t)snprintf(text + used, size - used, "%s%s", k ? ", " : "", number);
        }
        text[used++] = ']';
    }
    text[used++] = ']';
    double(*read)[3];
    assert_int_equal(wp_json_triples(text, used, &read, NULL), count);
    for (long i = 0; i < count; i++)
        for (int k = 0; k < 3; k++)
            if (memcmp(&read[i][k], &expected[i][k], sizeof(double)) != 0)
                fail_msg("wrench %ld, number %d: read %.17g, strtod %.17g", i, k, read[i][k],
                         expected[i][k]);
    print_message("reading: %ld numbers read as strtod reads them, bit for bit\n", 3 * count);
    free(read);
    free(text);
    free(expected);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(number_known_texts),
        cmocka_unit_test(number_random_bit_patterns),
        cmocka_unit_test(number_random_typical),
        cmocka_unit_test(number_typed_decimals),
        cmocka_unit_test(number_powers_and_extremes),
        cmocka_unit_test(number_integers),
        cmocka_unit_test(number_near_ties),
        cmocka_unit_test(number_reading),
    };
    return cmocka_run_group_tests_name("number", tests, NULL, NULL);
}
