/* fuzz_fixture.c -- libFuzzer target (b): the fixture validator and
 * everything derived from a valid fixture.
 *
 * The input is a fixture document (docs/PROTOCOL.md), read with
 * wp_fixture_read as fixture.put reads params.fixture.  Checked:
 *
 *  - refused: a -32602 error naming a field under "fixture", with a reason
 *    (never -32603: a validation error without a field would be reported
 *    as an internal error), and nothing left allocated (ASan's leak check);
 *  - accepted: a well-formed id; the canonical text reads back as the same
 *    fixture with the same id, name and canonical text (canonicalisation is
 *    idempotent); the wr_fixture is in range (1..8 fixels, unit normals and
 *    tangents, 0 <= mu_k <= mu_s, m, I, rho positive and finite);
 *  - the analysis: k 2^(k-1) goal cones over 2^k states, every goal and
 *    mode cone well-formed (fuzz_check_cone), pivots last and only when not
 *    pinned;
 *  - a few fixed wrenches and wrenches derived from the fixture (its push
 *    wrenches, gravity) classified for goal, strong and both: margins in
 *    [-1, 1], the verdict the margin implies, both = min(goal, strong),
 *    witnesses that make g, and for fixtures of at most LP_FIXELS fixels
 *    the LP method agreeing wherever |margin| > 1e-6 (while fuzzing, for
 *    one of the wrenches, chosen by the input's hash: fuzz_full);
 *  - push regions (frictionless, and with finger friction 0.3 when the
 *    sampled work is small, for one set while fuzzing) and gravity
 *    sweeps for each set: sorted,
 *    disjoint, inside (0, 1) per edge or [0, 360]; the middle of each exact
 *    region is not inside an excluded cone (margin >= -1e-7), and the middle
 *    of each gap between regions is not clearly in the set (margin <= 1e-7);
 *  - the disturbance margin of gravity and of the fixed wrenches: bounded
 *    exactly when there are moving modes, a blocking mode in range, a finite
 *    margin with the sign and size of the strong margin. */
#include "fuzz_util.h"
#include "wp_fixture.h"

#define LP_FIXELS 4               /* LP cross-checks on fixtures up to this size */
#define FRICTION_BUDGET 2e6       /* samples x cones for push regions with friction
                                     (a fortieth of it while fuzzing: fuzz_full) */
#define SEMANTIC_TOLERANCE 1e-7   /* margins at region middles */

static wr_lp_env *env;

int LLVMFuzzerInitialize(int *argc, char ***argv)
{
    fuzz_full_init(*argc, *argv);
    env = test_lp_env_new();
    if (!env)
        abort();
    return 0;
}

static void check_fixture(const wr_fixture *f)
{
    FUZZ_CHECK(f->fixel_count >= 1 && f->fixel_count <= WR_MAX_FIXELS, "%d fixels",
               f->fixel_count);
    FUZZ_CHECK(f->mass > 0 && isfinite(f->mass), "mass %.17g", f->mass);
    FUZZ_CHECK(f->inertia > 0 && isfinite(f->inertia), "inertia %.17g", f->inertia);
    FUZZ_CHECK(f->gyration_radius > 0 && isfinite(f->gyration_radius), "rho %.17g",
               f->gyration_radius);
    FUZZ_CHECK(isfinite(f->com[0]) && isfinite(f->com[1]), "com not finite");
    FUZZ_CHECK(f->size > 0 && isfinite(f->size), "size %.17g", f->size);
    FUZZ_CHECK(f->shape != WR_SHAPE_POLYGON ||
                   (f->vertex_count >= 3 && f->vertex_count <= WR_MAX_VERTICES &&
                    (f->orientation == 1 || f->orientation == -1)),
               "polygon: %zu vertices, orientation %d", f->vertex_count, f->orientation);
    FUZZ_CHECK(f->shape != WR_SHAPE_CIRCLE || (f->radius > 0 && isfinite(f->radius)),
               "circle: radius %.17g", f->radius);
    /* Polygons and outlines carry an outline; the lamina has area. */
    FUZZ_CHECK((f->outline != NULL) ==
                   (f->shape == WR_SHAPE_POLYGON || f->shape == WR_SHAPE_OUTLINE),
               "outline %p for shape %d", (void *)f->outline, (int)f->shape);
    FUZZ_CHECK(f->shape == WR_SHAPE_NONE || (f->area > 0 && isfinite(f->area)), "area %.17g",
               f->area);
    FUZZ_CHECK(f->shape != WR_SHAPE_OUTLINE ||
                   (f->outline->loop_count >= 1 && f->outline->area == f->area &&
                    f->outline->vertex_count <= WR_OUTLINE_MAX_VERTICES),
               "outline: %zu loops, area %.17g", f->outline->loop_count, f->outline->area);
    for (int i = 0; i < f->fixel_count; i++) {
        const wr_fixel *x = &f->fixels[i];
        FUZZ_CHECK(fabs(hypot(x->normal[0], x->normal[1]) - 1) < 1e-12, "fixel %d: normal not unit",
                   i);
        FUZZ_CHECK(x->tangent[0] == -x->normal[1] && x->tangent[1] == x->normal[0],
                   "fixel %d: tangent is not the normal turned +90 degrees", i);
        FUZZ_CHECK(x->mu_static >= 0 && x->mu_kinetic >= 0 && x->mu_kinetic <= x->mu_static &&
                       isfinite(x->mu_static),
                   "fixel %d: mu_s %.17g, mu_k %.17g", i, x->mu_static, x->mu_kinetic);
        /* Friction intervals: 0 <= min <= max, kinetic bounds not above
         * static's. */
        FUZZ_CHECK(x->mu_static_min >= 0 && x->mu_static_min <= x->mu_static &&
                       x->mu_kinetic_min >= 0 && x->mu_kinetic_min <= x->mu_kinetic &&
                       x->mu_kinetic_min <= x->mu_static_min,
                   "fixel %d: mu_s [%.17g, %.17g], mu_k [%.17g, %.17g]", i, x->mu_static_min,
                   x->mu_static, x->mu_kinetic_min, x->mu_kinetic);
        FUZZ_CHECK(fuzz_finite3(x->normal_wrench) && fuzz_finite3(x->tangent_wrench),
                   "fixel %d: contact wrenches not finite", i);
    }
}

static void check_doc(const cJSON *json, const wp_fixture_doc *doc)
{
    FUZZ_CHECK(wp_fixture_id_valid(doc->id), "id \"%s\"", doc->id);
    FUZZ_CHECK(doc->name && doc->canonical && doc->fixture, "a part of the doc is missing");
    const cJSON *name = cJSON_GetObjectItemCaseSensitive(json, "name");
    FUZZ_CHECK(strcmp(doc->name, cJSON_IsString(name) ? name->valuestring : "") == 0,
               "name \"%s\"", doc->name);
    /* The canonical text reads back as the same fixture. */
    cJSON *again = cJSON_Parse(doc->canonical);
    FUZZ_CHECK(again, "the canonical text is not JSON: %s", doc->canonical);
    wp_fixture_doc second;
    wp_error error = {0};
    FUZZ_CHECK(wp_fixture_read(again, "fixture", &second, &error),
               "the canonical text does not read back: %s: %s\n%s", error.field, error.reason,
               doc->canonical);
    FUZZ_CHECK(strcmp(second.id, doc->id) == 0, "canonical text has id %s, not %s", second.id,
               doc->id);
    FUZZ_CHECK(strcmp(second.name, doc->name) == 0, "canonical name differs");
    FUZZ_CHECK(strcmp(second.canonical, doc->canonical) == 0,
               "canonicalisation is not idempotent:\n%s\n%s", doc->canonical, second.canonical);
    const wr_fixture *f = doc->fixture, *g = second.fixture;
    FUZZ_CHECK(f->fixel_count == g->fixel_count && f->mass == g->mass &&
                   f->inertia == g->inertia && f->com[0] == g->com[0] && f->com[1] == g->com[1] &&
                   f->shape == g->shape && f->vertex_count == g->vertex_count &&
                   (f->shape != WR_SHAPE_OUTLINE ||
                    f->outline->vertex_count == g->outline->vertex_count) &&
                   f->area == g->area,
               "the canonical text is another fixture");
    wp_fixture_doc_release(&second);
    cJSON_Delete(again);
}

static void check_analysis(const wr_analysis *a)
{
    const wr_fixture *f = wr_analysis_fixture(a);
    int k = f->fixel_count;
    const wr_plan *plan = wr_analysis_plan(a);
    FUZZ_CHECK(plan && plan->fixel_count == k && plan->state_count == 1 << k &&
                   plan->kept_count == k << (k - 1) &&
                   wr_analysis_cone_count(a, WR_SET_GOAL) == plan->kept_count &&
                   wr_analysis_constraints(a, WR_SET_GOAL) == plan->kept,
               "plan of %d fixels: %d states, %d kept", k, plan->state_count, plan->kept_count);
    for (int i = 0; i < plan->kept_count; i++)
        fuzz_check_cone(wr_analysis_cone(a, WR_SET_GOAL, i), f, "goal cone");
    int mode_count = wr_analysis_cone_count(a, WR_SET_STRONG);
    FUZZ_CHECK(mode_count >= 0, "%d modes", mode_count);
    int pivots = 0;
    for (int i = 0; i < mode_count; i++) {
        const wr_constraint *m = &wr_analysis_constraints(a, WR_SET_STRONG)[i];
        FUZZ_CHECK(m->length == k && m->strict_separation, "mode %d malformed", i);
        FUZZ_CHECK(strspn(m->letters, "slrn") == (size_t)k, "mode %d: letters %s", i, m->letters);
        if (m->pivot) {
            pivots++;
            FUZZ_CHECK(strspn(m->letters, "n") == (size_t)k, "pivot mode %d: %s", i, m->letters);
        } else {
            FUZZ_CHECK(pivots == 0, "mode %d after a pivot", i);
            FUZZ_CHECK(strspn(m->letters, "n") != (size_t)k, "mode %d is n...n", i);
        }
        const wr_cone *cone = wr_analysis_cone(a, WR_SET_STRONG, i);
        fuzz_check_cone(cone, f, "mode cone");
        FUZZ_CHECK(wr_constraint_below(m, &cone->constraint) &&
                       wr_constraint_below(&cone->constraint, m),
                   "mode cone %d is of another constraint", i);
    }
    bool pinned = wr_analysis_pinned(a);
    FUZZ_CHECK(pivots == (pinned ? 0 : 2), "%d pivots, pinned %d", pivots, pinned);
    FUZZ_CHECK(wr_analysis_bytes(a) > 0, "no bytes");
}

/* The disturbance margin of `bias`, against the strong margin of it. */
static void check_disturbance(const wr_analysis *a, const double bias[3])
{
    wr_disturbance d;
    wr_status status = wr_disturbance_margin(a, bias, &d);
    FUZZ_CHECK(status == WR_OK || status == WR_INVALID, "wr_disturbance_margin returned %d",
               status);
    if (status != WR_OK)
        return;
    int modes = wr_analysis_cone_count(a, WR_SET_STRONG);
    FUZZ_CHECK(d.bounded == (modes > 0), "bounded %d with %d modes", d.bounded, modes);
    if (!d.bounded)
        return;
    FUZZ_CHECK(d.blocking >= 0 && d.blocking < modes, "blocking mode %d of %d", d.blocking,
               modes);
    FUZZ_CHECK(isfinite(d.margin) && fuzz_finite3(d.worst_direction),
               "disturbance margin %.17g or its direction not finite", d.margin);
    double unit[3];
    double length = wr_fixture_unit_wrench(wr_analysis_fixture(a), bias, unit);
    if (!(length > 1e-280 && length < 1e280)) /* subnormal last bits: not compared */
        return;
    wr_answer strong;
    FUZZ_CHECK(wr_classify(a, bias, WR_SET_STRONG, 0, &strong) == 0, "classify refused the bias");
    double expected = strong.margin * length;
    FUZZ_CHECK(fabs(d.margin - expected) <= 1e-9 * fabs(expected) + 1e-300,
               "disturbance margin %.17g, but the strong margin %.17g times |h| %.17g is %.17g",
               d.margin, strong.margin, length, expected);
}

/* The middles of push regions and of the gaps between them, against
 * wr_classify of the push wrench there. */
static void check_push_semantics(const wr_analysis *a, wr_set set, const wr_regions *r)
{
    const wr_fixture *f = wr_analysis_fixture(a);
    int edges = wr_push_edge_count(f);
    double high = f->shape == WR_SHAPE_CIRCLE ? 360 : 1;
    int next = 0;
    for (int e = 0; e < edges; e++) {
        double from = 0;
        for (;;) {
            bool region = next < r->count && r->items[next].edge == e;
            double to = region ? r->items[next].t0 : high;
            /* A gap [from, to]: not clearly in the set (too narrow ones
             * are left alone: rounding at the ends). */
            if (to - from > 1e-6 * high) {
                double w[3];
                wr_push_wrench(f, e, (from + to) / 2, w);
                wr_answer answer;
                if (fuzz_finite3(w) && wr_classify(a, w, set, 0, &answer) == 0)
                    FUZZ_CHECK(answer.margin <= SEMANTIC_TOLERANCE,
                               "push %s: edge %d, middle of the gap [%.17g, %.17g] has margin "
                               "%.17g: a region was missed",
                               FUZZ_SET_NAMES[set], e, from, to, answer.margin);
            }
            if (!region)
                break;
            const wr_region *x = &r->items[next++];
            double w[3];
            wr_push_wrench(f, e, (x->t0 + x->t1) / 2, w);
            wr_answer answer;
            if (fuzz_finite3(w) && wr_classify(a, w, set, 0, &answer) == 0)
                FUZZ_CHECK(answer.margin >= -SEMANTIC_TOLERANCE,
                           "push %s: edge %d, middle of the region [%.17g, %.17g] has margin "
                           "%.17g: it is excluded",
                           FUZZ_SET_NAMES[set], e, x->t0, x->t1, answer.margin);
            from = x->t1;
        }
    }
}

static void check_gravity_semantics(const wr_analysis *a, wr_set set, const wr_regions *r)
{
    double from = 0;
    for (int i = 0; i <= r->count; i++) {
        double to = i < r->count ? r->items[i].t0 : 360;
        double middles[2] = {(from + to) / 2, i < r->count ? (r->items[i].t0 + r->items[i].t1) / 2
                                                           : NAN};
        for (int m = 0; m < 2; m++) {
            if (m == 0 && !(to - from > 1e-6 * 360))
                continue;
            if (m == 1 && i == r->count)
                continue;
            double phi = middles[m] * 3.14159265358979323846 / 180;
            double g[3] = {cos(phi), sin(phi), 0};
            wr_answer answer;
            FUZZ_CHECK(wr_classify(a, g, set, 0, &answer) == 0, "classify refused gravity");
            if (m == 0)
                FUZZ_CHECK(answer.margin <= SEMANTIC_TOLERANCE,
                           "gravity %s: middle of the gap [%.17g, %.17g] has margin %.17g", 
                           FUZZ_SET_NAMES[set], from, to, answer.margin);
            else
                FUZZ_CHECK(answer.margin >= -SEMANTIC_TOLERANCE,
                           "gravity %s: middle of the arc [%.17g, %.17g] has margin %.17g",
                           FUZZ_SET_NAMES[set], r->items[i].t0, r->items[i].t1, answer.margin);
        }
        if (i < r->count)
            from = r->items[i].t1;
    }
}

static void check_regions(const wr_analysis *a, unsigned pick)
{
    const wr_fixture *f = wr_analysis_fixture(a);
    for (int s = 0; s < 3; s++) {
        wr_set set = (wr_set)s;
        wr_regions r;
        FUZZ_CHECK(wr_gravity_sweep(a, set, &r) == 0, "wr_gravity_sweep failed");
        fuzz_check_regions(&r, 1, 0, 360, "gravity");
        FUZZ_CHECK(r.resolution == 0, "gravity arcs not exact");
        check_gravity_semantics(a, set, &r);
        wr_regions_release(&r);
        if (f->shape == WR_SHAPE_NONE) {
            FUZZ_CHECK(wr_push_regions(a, set, 0, NULL, &r) == WR_NO_SHAPE,
                       "push regions without a shape");
            continue;
        }
        int edges = wr_push_edge_count(f);
        double high = f->shape == WR_SHAPE_CIRCLE ? 360 : 1;
        FUZZ_CHECK(wr_push_regions(a, set, 0, NULL, &r) == 0, "wr_push_regions failed");
        fuzz_check_regions(&r, edges, 0, high, "push");
        FUZZ_CHECK(r.resolution == 0, "frictionless push regions not exact");
        check_push_semantics(a, set, &r);
        wr_regions_release(&r);
        double cones = (set != WR_SET_STRONG ? wr_analysis_plan(a)->kept_count : 0) +
                       (set != WR_SET_GOAL ? wr_analysis_cone_count(a, WR_SET_STRONG) : 0);
        if ((fuzz_full || s == (int)(pick % 3)) && edges * 2049.0 * cones <= FRICTION_BUDGET / (fuzz_full ? 1 : 40)) {
            FUZZ_CHECK(wr_push_regions(a, set, 0.3, NULL, &r) == 0, "wr_push_regions with friction");
            fuzz_check_regions(&r, edges, 0, high, "push with friction");
            FUZZ_CHECK(r.resolution > 0, "sampled push regions claim exactness");
            wr_regions_release(&r);
        }
    }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    unsigned pick = fuzz_hash(data, size);
    char *text = fuzz_strndup(data, size);
    cJSON *json = cJSON_ParseWithLength(text, size);
    if (!json) {
        free(text);
        return 0;
    }
    wp_fixture_doc doc;
    wp_error error = {0};
    if (!wp_fixture_read(json, "fixture", &doc, &error)) {
        FUZZ_CHECK(error.code == WP_INVALID_PARAMS, "refused with code %d (%s: %s)", error.code,
                   error.field, error.reason);
        FUZZ_CHECK(strncmp(error.field, "fixture", 7) == 0, "refused at field \"%s\" (%s)",
                   error.field, error.reason);
        FUZZ_CHECK(error.reason[0], "refused without a reason at \"%s\"", error.field);
        FUZZ_CHECK(!doc.fixture && !doc.canonical && !doc.name, "a refused doc holds memory");
        cJSON_Delete(json);
        free(text);
        return 0;
    }
    check_doc(json, &doc);
    const wr_fixture *f = doc.fixture;
    check_fixture(f);
    /* Known: friction coefficients past ~1e8 break the cones (finding
     * "friction"); such fixtures are skipped when asked to. */
    bool huge = false;
    for (int i = 0; i < f->fixel_count; i++)
        huge |= f->fixels[i].mu_static > 1e6;
    if (huge && fuzz_skip_known("friction")) {
        wp_fixture_doc_release(&doc);
        cJSON_Delete(json);
        free(text);
        return 0;
    }
    wr_analysis *a = test_analysis_new(f);
    FUZZ_CHECK(a, "wr_analysis_new failed");
    check_analysis(a);

    wr_lp_set *goal = NULL, *strong = NULL;
    if (f->fixel_count <= LP_FIXELS)
        FUZZ_CHECK(wr_analysis_lp_sets(a, env, &goal, &strong) == 0, "no LP sets");
    /* Fixed wrenches, gravity, and the push wrench at each fixel's
     * opposite point. */
    double wrenches[8][3] = {{-1, -1, 0}, {1, 0, 0}, {0, -1, 0.5}, {0, 0, 1},
                             {0, 0, 0},   {-0.3, 2, -1}};
    int n = 6;
    wrenches[n][0] = 0;
    wrenches[n][1] = -9.81 * f->mass;
    wrenches[n++][2] = 0;
    if (f->shape != WR_SHAPE_NONE)
        wr_push_wrench(f, 0, f->shape == WR_SHAPE_CIRCLE ? 45 : 0.5, wrenches[n++]);
    int lp_wrench = (int)((pick >> 2) % (unsigned)n);
    for (int i = 0; i < n; i++) {
        if (!fuzz_finite3(wrenches[i]))
            continue;
        bool lp = fuzz_full || i == lp_wrench;
        fuzz_classify_all(a, wrenches[i], lp ? goal : NULL, lp ? strong : NULL, "fixed wrench");
        check_disturbance(a, wrenches[i]);
    }
    wr_lp_set_free(goal);
    wr_lp_set_free(strong);
    check_regions(a, pick);

    wr_analysis_free(a);
    wp_fixture_doc_release(&doc);
    cJSON_Delete(json);
    free(text);
    return 0;
}
