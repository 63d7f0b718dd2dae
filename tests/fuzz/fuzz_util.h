/* fuzz_util.h -- what the libFuzzer targets of tests/fuzz share: invariant
 * checks that abort (libFuzzer then saves the input as a crash), and small
 * helpers.  Header-only: each target is one translation unit. */
#ifndef FUZZ_UTIL_H
#define FUZZ_UTIL_H

#include <math.h>
#include <stdarg.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "wrench.h"
#include "../unit/test_util.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);
int LLVMFuzzerInitialize(int *argc, char ***argv);

/* An invariant broke: say which, with the details, and abort. */
__attribute__((noreturn, format(printf, 4, 5))) static void
fuzz_fail(const char *file, int line, const char *condition, const char *format, ...)
{
    fprintf(stderr, "\n==fuzz== INVARIANT FAILED at %s:%d: %s\n==fuzz== ", file, line, condition);
    va_list args;
    va_start(args, format);
    vfprintf(stderr, format, args);
    va_end(args);
    fputs("\n", stderr);
    fflush(stderr);
    abort();
}

#define FUZZ_CHECK(condition, ...)                                                \
    do {                                                                          \
        if (!(condition))                                                         \
            fuzz_fail(__FILE__, __LINE__, #condition, __VA_ARGS__);               \
    } while (0)

/* A NUL-terminated copy of data[0..size) (malloc'd; aborts when out of memory). */
static inline char *fuzz_strndup(const uint8_t *data, size_t size)
{
    char *text = malloc(size + 1);
    if (!text)
        abort();
    if (size)
        memcpy(text, data, size);
    text[size] = 0;
    return text;
}

/* Known findings (tests/fuzz/README.md, "Findings") can be stepped over in
 * long runs, so that the fuzzer looks for new ones instead of finding the
 * same again: FUZZ_SKIP_KNOWN is a comma-separated list of names, or "all".
 * By default nothing is skipped (make fuzz-smoke replays them all). */
static inline bool fuzz_skip_known(const char *name)
{
    const char *list = getenv("FUZZ_SKIP_KNOWN");
    if (!list || !*list)
        return false;
    if (strcmp(list, "all") == 0)
        return true;
    size_t n = strlen(name);
    for (const char *p = list; (p = strstr(p, name)) != NULL; p += n)
        if ((p == list || p[-1] == ',') && (p[n] == 0 || p[n] == ','))
            return true;
    return false;
}

/* Whether every check runs on every input.  While fuzzing, the targets
 * spread their costliest checks over the inputs (each input takes one
 * share, chosen by fuzz_hash); replaying files (make fuzz-smoke, a
 * regression, a crash) runs them all, as does FUZZ_FULL=1.  Set by
 * fuzz_full_init from LLVMFuzzerInitialize's arguments: a regular file
 * among them means a replay. */
static bool fuzz_full;

static inline void fuzz_full_init(int argc, char **argv)
{
    const char *env = getenv("FUZZ_FULL");
    fuzz_full = env && *env && strcmp(env, "0") != 0;
    struct stat st;
    for (int i = 1; i < argc; i++)
        if (argv[i][0] != '-' && stat(argv[i], &st) == 0 && S_ISREG(st.st_mode))
            fuzz_full = true;
}

/* FNV-1a of an input: which share of the costly checks it takes. */
static inline unsigned fuzz_hash(const uint8_t *data, size_t size)
{
    unsigned h = 2166136261u;
    for (size_t i = 0; i < size; i++)
        h = (h ^ data[i]) * 16777619u;
    return h;
}

static inline bool fuzz_finite3(const double v[3])
{
    return isfinite(v[0]) && isfinite(v[1]) && isfinite(v[2]);
}

static const char *const FUZZ_SET_NAMES[] = {"goal", "strong", "both"};

/* The invariants of one wr_classify answer (docs/MODEL.md section 5): a margin in
 * [-1, 1], the verdict its margin and the tolerance say (the zero wrench:
 * margin 0, outside for goal and both, docs/MODEL.md section 5), no blocking cone
 * when inside, and a blocking cone within the set it names. */
static inline void fuzz_check_answer(const wr_analysis *a, const double wrench[3], wr_set set,
                              double tolerance, const wr_answer *answer, const char *what)
{
    FUZZ_CHECK(answer->has_margin, "%s: set %s: no margin from the explicit method", what,
               FUZZ_SET_NAMES[set]);
    double m = answer->margin;
    FUZZ_CHECK(m >= -1 && m <= 1, "%s: set %s: margin %.17g outside [-1, 1]", what,
               FUZZ_SET_NAMES[set], m);
    bool zero = wrench[0] == 0 && wrench[1] == 0 && wrench[2] == 0;
    wr_verdict expected = m > tolerance    ? WR_VERDICT_INSIDE
                          : m < -tolerance ? WR_VERDICT_OUTSIDE
                                           : WR_VERDICT_BOUNDARY;
    if (zero) {
        FUZZ_CHECK(m == 0, "%s: set %s: the zero wrench has margin %.17g", what,
                   FUZZ_SET_NAMES[set], m);
        expected = set == WR_SET_STRONG && answer->verdict == WR_VERDICT_INSIDE
                       ? WR_VERDICT_INSIDE
                       : WR_VERDICT_OUTSIDE;
    }
    FUZZ_CHECK(answer->verdict == expected,
               "%s: set %s: verdict %d but margin %.17g and tolerance %.17g say %d", what,
               FUZZ_SET_NAMES[set], (int)answer->verdict, m, tolerance, (int)expected);
    if (answer->verdict == WR_VERDICT_INSIDE) {
        FUZZ_CHECK(answer->blocking == -1, "%s: set %s: inside but blocking %d", what,
                   FUZZ_SET_NAMES[set], answer->blocking);
    } else if (answer->blocking >= 0) {
        wr_set in = answer->blocking_set;
        FUZZ_CHECK(in == WR_SET_GOAL || in == WR_SET_STRONG, "%s: blocking set %d", what, (int)in);
        FUZZ_CHECK(set == WR_SET_BOTH || in == set, "%s: set %s blocked by a cone of set %s",
                   what, FUZZ_SET_NAMES[set], FUZZ_SET_NAMES[in]);
        FUZZ_CHECK(answer->blocking < wr_analysis_cone_count(a, in),
                   "%s: set %s: blocking %d of %d cones", what, FUZZ_SET_NAMES[set],
                   answer->blocking, wr_analysis_cone_count(a, in));
    }
}

/* The regions of wr_push_regions or wr_gravity_sweep: each a non-empty
 * open interval within [low, high] on an edge below `edges`, sorted by edge
 * then t0, and disjoint. */
static inline void fuzz_check_regions(const wr_regions *r, int edges, double low, double high,
                               const char *what)
{
    FUZZ_CHECK(r->count >= 0 && r->count <= r->capacity, "%s: count %d, capacity %d", what,
               r->count, r->capacity);
    FUZZ_CHECK(r->resolution >= 0 && isfinite(r->resolution), "%s: resolution %.17g", what,
               r->resolution);
    for (int i = 0; i < r->count; i++) {
        const wr_region *x = &r->items[i];
        FUZZ_CHECK(x->edge >= 0 && x->edge < edges, "%s: region %d on edge %d of %d", what, i,
                   x->edge, edges);
        FUZZ_CHECK(x->t0 < x->t1, "%s: region %d (edge %d) is [%.17g, %.17g]", what, i, x->edge,
                   x->t0, x->t1);
        FUZZ_CHECK(x->t0 >= low && x->t1 <= high, "%s: region %d [%.17g, %.17g] outside [%g, %g]",
                   what, i, x->t0, x->t1, low, high);
        if (i > 0) {
            const wr_region *p = &r->items[i - 1];
            FUZZ_CHECK(p->edge < x->edge || (p->edge == x->edge && p->t1 <= x->t0),
                       "%s: regions %d (edge %d, [%.17g, %.17g]) and %d (edge %d, [%.17g, %.17g]) "
                       "out of order or overlapping",
                       what, i - 1, p->edge, p->t0, p->t1, i, x->edge, x->t0, x->t1);
        }
    }
}

static inline double fuzz_dot3(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/* The invariants of an explicit cone (lib/wr_cone.h): dimension and
 * emptiness agree, 3 - dimension orthonormal equalities, unit facet rows,
 * unit rays inside every facet and equality, and every ray (a point of
 * the closure) at signed distance <= 0 from the cone. */
static inline void fuzz_check_cone(const wr_cone *c, const wr_fixture *f, const char *what)
{
    char text[WR_CONSTRAINT_TEXT];
    wr_constraint_format(&c->constraint, text);
    FUZZ_CHECK(c->constraint.length == f->fixel_count, "%s: cone %s of length %d for %d fixels",
               what, text, c->constraint.length, f->fixel_count);
    FUZZ_CHECK(c->dimension >= -1 && c->dimension <= 3, "%s: cone %s: dimension %d", what, text,
               c->dimension);
    FUZZ_CHECK(c->empty == (c->dimension == -1), "%s: cone %s: empty %d, dimension %d", what,
               text, c->empty, c->dimension);
    if (c->empty)
        return;
    FUZZ_CHECK(c->equality_count == 3 - c->dimension, "%s: cone %s: %d equalities at dimension %d",
               what, text, c->equality_count, c->dimension);
    FUZZ_CHECK(c->facet_count >= 0 && c->ray_count >= 0 && c->generator_count >= 0,
               "%s: cone %s: negative counts", what, text);
    for (int i = 0; i < c->equality_count; i++)
        for (int j = 0; j <= i; j++) {
            double d = fuzz_dot3(c->equalities[i], c->equalities[j]);
            FUZZ_CHECK(fabs(d - (i == j)) < 1e-9, "%s: cone %s: equalities %d.%d = %.17g", what,
                       text, i, j, d);
        }
    for (int i = 0; i < c->facet_count; i++) {
        double n = sqrt(fuzz_dot3(c->facets[i], c->facets[i]));
        FUZZ_CHECK(fabs(n - 1) < 1e-9, "%s: cone %s: facet %d has length %.17g", what, text, i, n);
    }
    for (int r = 0; r < c->ray_count; r++) {
        const double *ray = c->rays[r];
        double n = sqrt(fuzz_dot3(ray, ray));
        FUZZ_CHECK(fabs(n - 1) < 1e-9, "%s: cone %s: ray %d has length %.17g", what, text, r, n);
        for (int i = 0; i < c->facet_count; i++)
            FUZZ_CHECK(fuzz_dot3(c->facets[i], ray) <= 1e-9,
                       "%s: cone %s: ray %d violates facet %d by %.3g", what, text, r, i,
                       fuzz_dot3(c->facets[i], ray));
        for (int i = 0; i < c->equality_count; i++)
            FUZZ_CHECK(fabs(fuzz_dot3(c->equalities[i], ray)) <= 1e-9,
                       "%s: cone %s: ray %d violates equality %d by %.3g", what, text, r, i,
                       fuzz_dot3(c->equalities[i], ray));
        double d = wr_cone_signed_distance(c, ray, NULL);
        FUZZ_CHECK(d <= 1e-9, "%s: cone %s: ray %d at signed distance %.17g", what, text, r, d);
    }
    FUZZ_CHECK(c->dimension == 0 || c->ray_count > 0, "%s: cone %s: dimension %d, no ray", what,
               text, c->dimension);
}


/* A fixture whose numbers are out of scale with each other: a fixel more
 * than 10 gyration radii from the centre of mass, or fixels spread over
 * less than a tenth of one.  Known findings live there. */
static inline bool fuzz_badly_scaled(const wr_fixture *f)
{
    double rho = f->gyration_radius, spread = 0;
    for (int i = 0; i < f->fixel_count; i++) {
        const double *p = f->fixels[i].at;
        if (hypot(p[0] - f->com[0], p[1] - f->com[1]) > 10 * rho)
            return true;
        for (int j = 0; j < i; j++)
            spread = fmax(spread, hypot(p[0] - f->fixels[j].at[0], p[1] - f->fixels[j].at[1]));
    }
    return f->fixel_count > 1 && spread < rho / 10;
}

/* Everything wr_classify says about g, for the three sets, checked; the
 * answers in out[3] (may be NULL).  With LP sets, the LP method must agree
 * on the verdict wherever the margin is beyond 1e-6 (as in
 * tests/unit/lib/test_crosscheck.c). */
static inline void fuzz_classify_all(const wr_analysis *a, const double g[3], wr_lp_set *goal,
                                     wr_lp_set *strong, const char *what)
{
    wr_answer answers[3];
    for (int s = 0; s < 3; s++) {
        wr_answer *answer = &answers[s];
        FUZZ_CHECK(wr_classify(a, g, (wr_set)s, WR_DEFAULT_TOLERANCE, answer) == 0,
                   "%s: wr_classify refused the finite wrench (%.17g, %.17g, %.17g)", what, g[0],
                   g[1], g[2]);
        fuzz_check_answer(a, g, (wr_set)s, WR_DEFAULT_TOLERANCE, answer, what);
        /* (Witnesses of wrenches near the largest doubles overflow by
         * design, lib/wr_classify.c: only moderate wrenches are checked.) */
        double largest = fmax(fabs(g[0]), fmax(fabs(g[1]), fabs(g[2])));
        if (answer->verdict == WR_VERDICT_OUTSIDE && answer->blocking >= 0 &&
            answer->margin < -1e-6 && largest < 1e100 && largest > 1e-100) {
            /* g is inside the blocking cone: the witness makes g itself. */
            const wr_cone *cone = wr_analysis_cone(a, answer->blocking_set, answer->blocking);
            /* Known: witnesses of near-degenerate cones lose digits
             * (finding "witness"): then only gross errors of well-scaled
             * fixtures count. */
            bool known = fuzz_skip_known("witness");
            const wr_fixture *f = wr_analysis_fixture(a);
            const char *why =
                known && fuzz_badly_scaled(f)
                    ? NULL
                    : test_witness_violation(f, &cone->constraint, &answer->witness, g,
                                             known ? 1e-2 : 1e-6);
            char text[WR_CONSTRAINT_TEXT];
            wr_constraint_format(&cone->constraint, text);
            FUZZ_CHECK(!why, "%s: set %s: witness of cone %s for g = (%.17g, %.17g, %.17g), "
                             "margin %.17g: %s",
                       what, FUZZ_SET_NAMES[s], text, g[0], g[1], g[2], answer->margin, why);
        }
    }
    double both = fmin(answers[0].margin, answers[1].margin);
    FUZZ_CHECK(answers[2].margin == both,
               "%s: margin for both %.17g, not the smaller of goal %.17g and strong %.17g", what,
               answers[2].margin, answers[0].margin, answers[1].margin);
    if (!goal || !strong)
        return;
    /* Known: the LPs' absolute slack threshold misjudges badly scaled
     * fixtures (finding "lp-slack"). */
    if (fuzz_skip_known("lp-slack") && fuzz_badly_scaled(wr_analysis_fixture(a)))
        return;
    for (int s = 0; s < 3; s++) {
        if (fabs(answers[s].margin) <= 1e-6)
            continue;
        wr_answer lp;
        wr_status status = wr_classify_lp(a, goal, strong, g, (wr_set)s, &lp);
        FUZZ_CHECK(status == WR_OK, "%s: wr_classify_lp failed: %s", what, wr_strerror(status));
        FUZZ_CHECK(!lp.has_margin && lp.verdict != WR_VERDICT_BOUNDARY,
                   "%s: the LP method gave a margin or a boundary", what);
        bool cones_inside = answers[s].verdict == WR_VERDICT_INSIDE;
        bool lp_inside = lp.verdict == WR_VERDICT_INSIDE;
        FUZZ_CHECK(cones_inside == lp_inside,
                   "%s: set %s: the cones say %s (margin %.17g), the LPs say %s, for g = "
                   "(%.17g, %.17g, %.17g)",
                   what, FUZZ_SET_NAMES[s], cones_inside ? "inside" : "not inside",
                   answers[s].margin, lp_inside ? "inside" : "outside", g[0], g[1], g[2]);
    }
}

#endif
