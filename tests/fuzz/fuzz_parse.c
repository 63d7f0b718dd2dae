/* fuzz_parse.c -- libFuzzer target (c): constraint strings and wrenches.
 *
 * The input is: one byte choosing a fixed fixture (its value modulo
 * FIXTURE_COUNT: the disc in a corner of docs/MODEL.md section 7, the 3-fixel
 * 3-2-1 plate, the chamfered plate, a disc on one fixel (not pinned)),
 * then a constraint string up to the first '\n', then a wrench as JSON
 * (the rest).  For example "\x01" "smu\n" "[-1, -1, 0]".
 *
 * Constraint strings: wr_constraint_parse must accept exactly the strings
 * of one letter of "saulrnm" per fixel (an oracle written here); an
 * accepted string formats back to itself and is below itself; its cone
 * (wr_cone_build) is well-formed (fuzz_check_cone), lies inside the cone
 * of the string with every letter raised (s, a -> u; l, r, n -> m: the order of
 * docs/MODEL.md section 2, G_X inside G_Y), and equals the analysis's goal cone
 * when the string is one of them.
 *
 * Wrenches: wp_wrench_read refuses with a -32602 error under "wrench", or
 * gives a finite wrench; that wrench is classified for the three sets
 * (margins in [-1, 1], verdicts, both = min(goal, strong), witnesses, the
 * LP method agreeing beyond 1e-6), twice it has the same margins and
 * verdicts (cones are cones), and its disturbance margin (docs/MODEL.md section 6)
 * is bounded exactly when there are moving modes, with the sign and size
 * of its strong margin. */
#include "fuzz_util.h"
#include "wp_fixture.h"

static const char *const FIXTURES[] = {
    /* docs/MODEL.md section 7: the unit disc in a corner. */
    "{\"name\":\"disc-corner\",\"body\":{\"mass\":1,\"inertia\":0.5,\"com\":[0,0],"
    "\"shape\":{\"type\":\"circle\",\"center\":[0,0],\"radius\":1}},"
    "\"friction\":{\"static\":0.5,\"kinetic\":0.5},"
    "\"fixels\":[{\"at\":[-1,0],\"normal\":[1,0]},{\"at\":[0,-1],\"normal\":[0,1]}]}",
    /* A 4 x 2 plate on three fixels (3-2-1). */
    "{\"name\":\"plate-3-2-1\",\"body\":{\"mass\":1,\"shape\":{\"type\":\"polygon\","
    "\"vertices\":[[0,0],[4,0],[4,2],[0,2]]}},\"friction\":{\"static\":0.3},"
    "\"fixels\":[{\"at\":[1,0]},{\"at\":[3,0]},{\"at\":[0,1]}]}",
    /* The chamfered plate, low friction. */
    "{\"name\":\"chamfer\",\"body\":{\"mass\":1,\"shape\":{\"type\":\"polygon\","
    "\"vertices\":[[0,0],[4,0],[4,1],[3,2],[0,2]]}},\"friction\":{\"static\":0.05},"
    "\"fixels\":[{\"at\":[1,0]},{\"at\":[3,0]},{\"at\":[0,1]}]}",
    /* A disc with an offset centre of mass on one fixel: not pinned. */
    "{\"name\":\"disc-one\",\"body\":{\"mass\":2,\"inertia\":0.8,\"com\":[0.2,0.1],"
    "\"shape\":{\"type\":\"circle\",\"center\":[0,0],\"radius\":1}},"
    "\"friction\":{\"static\":0.4,\"kinetic\":0.2},\"fixels\":[{\"at\":[0,-1]}]}",
};
#define FIXTURE_COUNT ((int)(sizeof FIXTURES / sizeof FIXTURES[0]))

static struct {
    wp_fixture_doc doc;
    wr_analysis *analysis;
    wr_lp_set *goal, *strong;
} fixed[FIXTURE_COUNT];
static wr_lp_env *env;

int LLVMFuzzerInitialize(int *argc, char ***argv)
{
    (void)argc;
    (void)argv;
    env = test_lp_env_new();
    if (!env)
        abort();
    for (int i = 0; i < FIXTURE_COUNT; i++) {
        cJSON *json = cJSON_Parse(FIXTURES[i]);
        wp_error error;
        if (!json || !wp_fixture_read(json, "fixture", &fixed[i].doc, &error)) {
            fprintf(stderr, "fuzz_parse: fixture %d does not read\n", i);
            abort();
        }
        cJSON_Delete(json);
        fixed[i].analysis = test_analysis_new(fixed[i].doc.fixture);
        if (!fixed[i].analysis ||
            wr_analysis_lp_sets(fixed[i].analysis, env, &fixed[i].goal, &fixed[i].strong) != 0)
            abort();
    }
    return 0;
}

/* ---- constraint strings ------------------------------------------------------- */

static void check_constraint(const wr_analysis *a, const char *text)
{
    const wr_fixture *f = wr_analysis_fixture(a);
    int k = f->fixel_count;
    bool expected = strlen(text) == (size_t)k && strspn(text, "saulrnm") == (size_t)k;
    wr_constraint c;
    wr_error error;
    memset(&error, 0, sizeof error);
    bool parsed = wr_constraint_parse(text, k, &c, &error) == WR_OK;
    FUZZ_CHECK(parsed == expected, "wr_constraint_parse(\"%s\", %d) says %d", text, k, parsed);
    if (!parsed) {
        FUZZ_CHECK(error.reason[0], "refused \"%s\" without a reason", text);
        return;
    }
    FUZZ_CHECK(c.length == k && strcmp(c.letters, text) == 0 && !c.pivot && !c.strict_separation,
               "\"%s\" parsed as \"%s\" (length %d, pivot %d)", text, c.letters, c.length,
               c.pivot);
    char back[WR_CONSTRAINT_TEXT];
    wr_constraint_format(&c, back);
    FUZZ_CHECK(strcmp(back, text) == 0, "\"%s\" formats as \"%s\"", text, back);
    FUZZ_CHECK(wr_constraint_below(&c, &c), "\"%s\" is not below itself", text);

    wr_cone cone;
    FUZZ_CHECK(wr_cone_build(&cone, f, &c) == WR_OK, "wr_cone_build(\"%s\") failed", text);
    fuzz_check_cone(&cone, f, "parsed cone");

    /* Raised letter by letter: a larger cone (docs/MODEL.md section 2). */
    wr_constraint up = c;
    for (int i = 0; i < k; i++)
        up.letters[i] = strchr("sa", c.letters[i]) ? 'u' : strchr("lrn", c.letters[i]) ? 'm'
                                                                                       : c.letters[i];
    FUZZ_CHECK(wr_constraint_below(&c, &up), "\"%s\" not below \"%s\"", text, up.letters);
    wr_cone upper;
    FUZZ_CHECK(wr_cone_build(&upper, f, &up) == WR_OK, "wr_cone_build(\"%s\") failed", up.letters);
    fuzz_check_cone(&upper, f, "raised cone");
    FUZZ_CHECK(!upper.empty || cone.empty, "\"%s\" is empty but \"%s\" is not", up.letters, text);
    for (int r = 0; r < cone.ray_count; r++) {
        double d = wr_cone_signed_distance(&upper, cone.rays[r], NULL);
        FUZZ_CHECK(d <= 1e-9, "ray %d of \"%s\" is %.3g outside \"%s\"", r, text, d, up.letters);
    }
    wr_cone_release(&upper);

    /* One of the analysis's goal cones: the same cone. */
    for (int i = 0; i < wr_analysis_plan(a)->kept_count; i++) {
        const wr_cone *g = wr_analysis_cone(a, WR_SET_GOAL, i);
        if (strcmp(g->constraint.letters, text) != 0)
            continue;
        FUZZ_CHECK(g->dimension == cone.dimension && g->facet_count == cone.facet_count &&
                       g->ray_count == cone.ray_count,
                   "\"%s\" built again differs from the goal cone", text);
    }
    wr_cone_release(&cone);
}

/* ---- wrenches -------------------------------------------------------------------- */

static void check_wrench(int which, const char *text, size_t length)
{
    const wr_analysis *a = fixed[which].analysis;
    const wr_fixture *f = wr_analysis_fixture(a);
    cJSON *json = cJSON_ParseWithLength(text, length);
    if (!json)
        return;
    double g[3];
    wp_error error;
    memset(&error, 0, sizeof error);
    if (!wp_wrench_read(json, "wrench", f, g, &error)) {
        FUZZ_CHECK(error.code == WP_INVALID_PARAMS, "refused with code %d", error.code);
        FUZZ_CHECK(strncmp(error.field, "wrench", 6) == 0, "refused at field \"%s\" (%s)",
                   error.field, error.reason);
        FUZZ_CHECK(error.reason[0], "refused without a reason");
        cJSON_Delete(json);
        return;
    }
    cJSON_Delete(json);
    FUZZ_CHECK(fuzz_finite3(g), "wp_wrench_read gave (%.17g, %.17g, %.17g)", g[0], g[1], g[2]);
    fuzz_classify_all(a, g, fixed[which].goal, fixed[which].strong, "wrench");

    /* Twice the wrench: the same margins, to the last bit (the unit
     * wrench is computed by dividing by the largest component). */
    double twice[3] = {2 * g[0], 2 * g[1], 2 * g[2]};
    if (fuzz_finite3(twice)) {
        for (int s = 0; s < 3; s++) {
            wr_answer x, y;
            FUZZ_CHECK(wr_classify(a, g, (wr_set)s, WR_DEFAULT_TOLERANCE, &x) == 0 &&
                           wr_classify(a, twice, (wr_set)s, WR_DEFAULT_TOLERANCE, &y) == 0,
                       "classify refused");
            FUZZ_CHECK(x.margin == y.margin && x.verdict == y.verdict && x.blocking == y.blocking,
                       "set %s: g = (%.17g, %.17g, %.17g) has margin %.17g (verdict %d), 2g has "
                       "%.17g (verdict %d)",
                       FUZZ_SET_NAMES[s], g[0], g[1], g[2], x.margin, x.verdict, y.margin,
                       y.verdict);
        }
    }

    wr_disturbance d;
    wr_status status = wr_disturbance_margin(a, g, &d);
    FUZZ_CHECK(status == WR_OK || status == WR_INVALID, "wr_disturbance_margin returned %d",
               status);
    if (status == WR_OK) {
        int modes = wr_analysis_cone_count(a, WR_SET_STRONG);
        FUZZ_CHECK(d.bounded == (modes > 0), "bounded %d with %d modes", d.bounded, modes);
        if (d.bounded) {
            FUZZ_CHECK(d.blocking >= 0 && d.blocking < modes, "blocking %d of %d", d.blocking,
                       modes);
            FUZZ_CHECK(isfinite(d.margin) && fuzz_finite3(d.worst_direction),
                       "margin %.17g or direction not finite", d.margin);
            double unit[3];
            double length = wr_fixture_unit_wrench(f, g, unit);
            wr_answer strong;
            FUZZ_CHECK(wr_classify(a, g, WR_SET_STRONG, 0, &strong) == 0, "classify refused");
            /* (Beyond 1e+-280 the margin's last bits are subnormal: not compared.) */
            if (length > 1e-280 && length < 1e280) {
                double expected = strong.margin * length;
                FUZZ_CHECK(fabs(d.margin - expected) <= 1e-9 * fabs(expected) + 1e-300,
                           "disturbance margin %.17g, strong margin %.17g x |h| %.17g = %.17g",
                           d.margin, strong.margin, length, expected);
            }
        }
    }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (size == 0)
        return 0;
    int which = data[0] % FIXTURE_COUNT;
    const uint8_t *rest = data + 1;
    size_t left = size - 1;
    const uint8_t *newline = memchr(rest, '\n', left);
    size_t first = newline ? (size_t)(newline - rest) : left;
    char *constraint = fuzz_strndup(rest, first);
    check_constraint(fixed[which].analysis, constraint);
    free(constraint);
    if (newline) {
        char *wrench = fuzz_strndup(newline + 1, left - first - 1);
        check_wrench(which, wrench, left - first - 1);
        free(wrench);
    }
    return 0;
}
