/* micro.c -- in-process costs of classifying one wrench
 * and of deriving a fixture (part 5).  Prints figures; asserts nothing.
 *
 *   micro [FIXTURE.json] [--wrenches N] [--lp-wrenches N] [--json]
 *
 * Rows:
 *   auto     wr_classify for goal and then strong, with witnesses, as the
 *            daemon answers (explicit cones);
 *   lp       wr_classify_lp for goal and strong (GLPK, warm problems);
 *   warm LP  one wr_lp_member on an already built problem, averaged over
 *            every excluded cone of both sets;
 *   cone     one wr_cone_signed_distance, averaged over the same cones;
 *   derive   wr_fixture_new + wr_analysis_new for a disc with k = 2..8
 *            fixels, and the bytes the analysis holds.
 * Wrenches are uniform in [-1, 1]^3 from a fixed seed, so runs compare. */
#include "wp_fixture.h"
#include "wp_local.h"
#include "wrench.h"
#include "bench_util.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

static char fixture_text[1 << 20];

static wr_fixture *read_fixture(const char *path)
{
    FILE *file = fopen(path, "rb");
    if (!file) {
        perror(path);
        return NULL;
    }
    char *text = fixture_text;
    size_t length = fread(text, 1, sizeof fixture_text - 1, file);
    fclose(file);
    text[length] = 0;
    for (char *p = text; *p; p++) /* one line, for the batch request */
        if (*p == '\n' || *p == '\r')
            *p = ' ';
    cJSON *json = cJSON_Parse(text);
    wp_fixture_doc doc;
    wp_error error;
    if (!json || !wp_fixture_read(json, "fixture", &doc, &error)) {
        fprintf(stderr, "%s: not a valid fixture\n", path);
        cJSON_Delete(json);
        return NULL;
    }
    cJSON_Delete(json);
    wr_fixture *fixture = doc.fixture;
    doc.fixture = NULL;
    wp_fixture_doc_release(&doc);
    return fixture;
}

/* A unit disc with k fixels spread over 300 degrees, friction 0.3: the
 * fixture registration is timed on (k = 2..8). */
static wr_fixture *disc_fixture(int k, double radius_jitter)
{
    wr_fixel_spec fixels[WR_MAX_FIXELS];
    memset(fixels, 0, sizeof fixels);
    double radius = 1 + radius_jitter;
    for (int i = 0; i < k; i++) {
        double angle = (200 + 300.0 * i / k) * 3.14159265358979323846 / 180;
        fixels[i].at[0] = radius * cos(angle);
        fixels[i].at[1] = radius * sin(angle);
    }
    wr_fixture_spec spec = {
        .mass = 1,
        .shape = WR_SHAPE_CIRCLE,
        .radius = radius,
        .friction = {.given = true, .static_mu = 0.3},
        .fixel_count = (size_t)k,
        .fixels = fixels,
    };
    wr_fixture *fixture;
    return wr_fixture_new(&spec, &fixture, NULL) == WR_OK ? fixture : NULL;
}

int main(int argc, char **argv)
{
    const char *path = "examples/plate-3-2-1.json";
    long wrench_count = 200000, lp_wrench_count = 2000;
    int json = 0;
    for (int i = 1; i < argc; i++) {
        if (strcmp(argv[i], "--wrenches") == 0 && i + 1 < argc)
            wrench_count = atol(argv[++i]);
        else if (strcmp(argv[i], "--lp-wrenches") == 0 && i + 1 < argc)
            lp_wrench_count = atol(argv[++i]);
        else if (strcmp(argv[i], "--json") == 0)
            json = 1;
        else if (argv[i][0] == '-') {
            fprintf(stderr, "usage: %s [FIXTURE.json] [--wrenches N] [--lp-wrenches N] [--json]\n",
                    argv[0]);
            return 2;
        } else
            path = argv[i];
    }
    if (wrench_count < 1 || lp_wrench_count < 1)
        return 2;
    wr_fixture *fixture = read_fixture(path);
    if (!fixture)
        return 1;
    wr_analysis *analysis;
    wr_lp_env *env;
    wr_lp_set *goal = NULL, *strong = NULL;
    if (wr_analysis_new(fixture, &analysis) != WR_OK || wr_lp_env_new(&env) != WR_OK ||
        wr_analysis_lp_sets(analysis, env, &goal, &strong) != WR_OK) {
        fprintf(stderr, "out of memory\n");
        return 1;
    }
    int goal_cones = wr_analysis_cone_count(analysis, WR_SET_GOAL);
    int strong_cones = wr_analysis_cone_count(analysis, WR_SET_STRONG);
    int cones = goal_cones + strong_cones;

    double (*wrenches)[3] = malloc((size_t)wrench_count * sizeof *wrenches);
    uint64_t seed = 0x9e3779b97f4a7c15ULL;
    for (long i = 0; i < wrench_count; i++)
        for (int k = 0; k < 3; k++)
            wrenches[i][k] = bench_uniform(&seed);

    /* auto: goal and strong, with witnesses, as the daemon answers. */
    long inside[2] = {0, 0};
    double start = bench_seconds();
    for (long i = 0; i < wrench_count; i++)
        for (int set = WR_SET_GOAL; set <= WR_SET_STRONG; set++) {
            wr_answer answer;
            wr_classify(analysis, wrenches[i], (wr_set)set, WR_DEFAULT_TOLERANCE, &answer);
            inside[set] += answer.verdict == WR_VERDICT_INSIDE;
        }
    double auto_us = (bench_seconds() - start) * 1e6 / (double)wrench_count;

    /* The verdict alone (fields: ["verdict"]): the same wrenches, and every
     * verdict compared with the full path's. */
    long verdict_disagree = 0;
    start = bench_seconds();
    for (long i = 0; i < wrench_count; i++)
        for (int set = WR_SET_GOAL; set <= WR_SET_STRONG; set++) {
            wr_verdict verdict;
            wr_classify_verdict(analysis, wrenches[i], (wr_set)set, WR_DEFAULT_TOLERANCE,
                                &verdict);
            inside[set] -= verdict == WR_VERDICT_INSIDE; /* back to 0 if they agree */
        }
    double verdict_ns = (bench_seconds() - start) * 1e9 / (double)wrench_count;
    for (long i = 0; i < wrench_count && i < 200000; i++)
        for (int set = WR_SET_GOAL; set <= WR_SET_STRONG; set++) {
            wr_verdict verdict;
            wr_answer full;
            wr_classify_verdict(analysis, wrenches[i], (wr_set)set, WR_DEFAULT_TOLERANCE,
                                &verdict);
            wr_classify(analysis, wrenches[i], (wr_set)set, WR_DEFAULT_TOLERANCE, &full);
            verdict_disagree += verdict != full.verdict;
        }
    long verdict_compared = 2 * (wrench_count < 200000 ? wrench_count : 200000);
    /* The inside counts again, for the summary. */
    inside[0] = inside[1] = 0;
    for (long i = 0; i < wrench_count; i++)
        for (int set = WR_SET_GOAL; set <= WR_SET_STRONG; set++) {
            wr_verdict verdict;
            wr_classify_verdict(analysis, wrenches[i], (wr_set)set, WR_DEFAULT_TOLERANCE,
                                &verdict);
            inside[set] += verdict == WR_VERDICT_INSIDE;
        }

    /* The verdict map (a long lean batch's way): built once, then every
     * wrench looked up, and every verdict compared with the verdict
     * alone's, which agrees with the full path's (above). */
    start = bench_seconds();
    wr_verdict_map *map;
    if (wr_verdict_map_new(analysis, WR_DEFAULT_TOLERANCE, &map) != WR_OK) {
        fprintf(stderr, "out of memory\n");
        return 1;
    }
    double map_build_ms = (bench_seconds() - start) * 1e3;
    long map_inside = 0;
    start = bench_seconds();
    for (long i = 0; i < wrench_count; i++)
        for (int set = WR_SET_GOAL; set <= WR_SET_STRONG; set++) {
            wr_verdict verdict;
            wr_verdict_map_classify(map, wrenches[i], (wr_set)set, &verdict);
            map_inside += verdict == WR_VERDICT_INSIDE;
        }
    double map_ns = (bench_seconds() - start) * 1e9 / (double)wrench_count;
    long map_disagree = 0;
    for (long i = 0; i < wrench_count; i++)
        for (int set = WR_SET_GOAL; set <= WR_SET_STRONG; set++) {
            wr_verdict mapped, alone;
            wr_verdict_map_classify(map, wrenches[i], (wr_set)set, &mapped);
            wr_classify_verdict(analysis, wrenches[i], (wr_set)set, WR_DEFAULT_TOLERANCE, &alone);
            map_disagree += mapped != alone;
        }
    double map_decided = wr_verdict_map_decided(map);
    size_t map_bytes = wr_verdict_map_bytes(map);
    wr_verdict_map_free(map);

    /* lp: the same with GLPK (warm problems: every one solved once first). */
    wr_answer answer;
    wr_classify_lp(analysis, goal, strong, wrenches[0], WR_SET_GOAL, &answer);
    wr_classify_lp(analysis, goal, strong, wrenches[0], WR_SET_STRONG, &answer);
    for (int c = 0; c < goal_cones; c++) {
        bool member;
        wr_lp_member(goal, c, wrenches[0], &member, NULL);
    }
    for (int c = 0; c < strong_cones; c++) {
        bool member;
        wr_lp_member(strong, c, wrenches[0], &member, NULL);
    }
    long agree = 0;
    start = bench_seconds();
    for (long i = 0; i < lp_wrench_count; i++)
        for (int set = WR_SET_GOAL; set <= WR_SET_STRONG; set++)
            wr_classify_lp(analysis, goal, strong, wrenches[i], (wr_set)set, &answer);
    double lp_us = (bench_seconds() - start) * 1e6 / (double)lp_wrench_count;
    for (long i = 0; i < lp_wrench_count; i++)
        for (int set = WR_SET_GOAL; set <= WR_SET_STRONG; set++) {
            wr_answer by_cones;
            wr_classify_lp(analysis, goal, strong, wrenches[i], (wr_set)set, &answer);
            wr_classify(analysis, wrenches[i], (wr_set)set, WR_DEFAULT_TOLERANCE, &by_cones);
            agree += by_cones.verdict == WR_VERDICT_BOUNDARY ||
                     (answer.verdict == WR_VERDICT_INSIDE) ==
                         (by_cones.verdict == WR_VERDICT_INSIDE);
        }

    /* One warm LP, and one explicit-cone check, per cone of both sets. */
    long lp_solves = 0, cone_checks = 0;
    start = bench_seconds();
    for (long i = 0; i < lp_wrench_count; i++)
        for (int c = 0; c < cones; c++) {
            bool member;
            wr_lp_member(c < goal_cones ? goal : strong, c < goal_cones ? c : c - goal_cones,
                         wrenches[i], &member, NULL);
            lp_solves++;
        }
    double warm_us = (bench_seconds() - start) * 1e6 / (double)lp_solves;
    double checksum = 0;
    start = bench_seconds();
    for (long i = 0; i < wrench_count; i++) {
        double x[3];
        double norm = sqrt(wrenches[i][0] * wrenches[i][0] + wrenches[i][1] * wrenches[i][1] +
                           wrenches[i][2] * wrenches[i][2]);
        for (int k = 0; k < 3; k++)
            x[k] = wrenches[i][k] / norm;
        for (int c = 0; c < cones; c++) {
            const wr_cone *cone = wr_analysis_cone(
                analysis, c < goal_cones ? WR_SET_GOAL : WR_SET_STRONG,
                c < goal_cones ? c : c - goal_cones);
            checksum += wr_cone_signed_distance(cone, x, NULL);
            cone_checks++;
        }
    }
    double cone_us = (bench_seconds() - start) * 1e6 / (double)cone_checks;

    /* GLPK has one environment per thread: this one goes before wp_local
     * makes its own. */
    wr_lp_set_free(goal);
    wr_lp_set_free(strong);
    wr_lp_env_free(env);

    /* One batch request of all the wrenches, JSON in and out, answered in
     * this thread by the daemon's code (wp_answer_line): the daemon's work
     * on a batch without the socket.  The best of three runs after one. */
    size_t batch_size = (size_t)wrench_count * 80 + sizeof fixture_text + 256;
    char *batch_line = malloc(batch_size);
    size_t used = (size_t)snprintf(batch_line, batch_size,
                                   "{\"jsonrpc\":\"2.0\",\"id\":1,\"method\":\"wrench.classify\","
                                   "\"params\":{\"fixture\":%s,\"wrenches\":[",
                                   fixture_text);
    for (long i = 0; i < wrench_count; i++)
        used += (size_t)snprintf(batch_line + used, batch_size - used, "%s[%.6f,%.6f,%.6f]",
                                 i ? "," : "", wrenches[i][0], wrenches[i][1], wrenches[i][2]);
    used += (size_t)snprintf(batch_line + used, batch_size - used, "]}}");
    wp_local *local = wp_local_new();
    wp_limits limits = {.max_depth = 64, .max_wrenches = (size_t)wrench_count, .max_batch = 1};
    double batch_us = INFINITY;
    size_t batch_answer = 0;
    for (int run = 0; run < 4 && local; run++) {
        wp_counts counts = {0, 0};
        start = bench_seconds();
        char *answer = wp_answer_line(wp_local_host(local), &limits, batch_line, used, &counts);
        double us = (bench_seconds() - start) * 1e6 / (double)wrench_count;
        if (run > 0 && us < batch_us) /* the best of three, after a first run */
            batch_us = us;
        batch_answer = answer ? strlen(answer) : 0;
        if (!answer || counts.errors) {
            fprintf(stderr, "the batch failed: %.200s\n", answer ? answer : "(no answer)");
            return 1;
        }
        free(answer);
    }
    wp_local_free(local);
    free(batch_line);

    /* Registration in process: fixture and analysis, k = 2..8. */
    double derive_ms[WR_MAX_FIXELS + 1] = {0};
    size_t derive_bytes[WR_MAX_FIXELS + 1] = {0};
    for (int k = 2; k <= WR_MAX_FIXELS; k++) {
        int repeats = k < 6 ? 50 : k < 8 ? 10 : 5;
        start = bench_seconds();
        for (int r = 0; r < repeats; r++) {
            wr_fixture *disc = disc_fixture(k, 1e-3 * r);
            wr_analysis *disc_analysis;
            if (!disc || wr_analysis_new(disc, &disc_analysis) != WR_OK) {
                fprintf(stderr, "k = %d: no analysis\n", k);
                return 1;
            }
            derive_bytes[k] = wr_analysis_bytes(disc_analysis) + sizeof *disc;
            wr_analysis_free(disc_analysis);
            wr_fixture_free(disc);
        }
        derive_ms[k] = (bench_seconds() - start) * 1e3 / repeats;
    }

    if (json) {
        printf("{\"fixture\": \"%s\", \"goal_cones\": %d, \"strong_cones\": %d, "
               "\"wrenches\": %ld, \"lp_wrenches\": %ld, \"auto_us\": %.4f, \"lp_us\": %.3f, "
               "\"warm_lp_us\": %.4f, \"cone_us\": %.5f, \"lp_agree\": %ld, \"lp_compared\": %ld, "
               "\"batch_us\": %.4f, \"batch_answer_bytes\": %zu, \"verdict_ns\": %.2f, "
               "\"verdict_disagree\": %ld, \"verdict_compared\": %ld, \"map_ns\": %.2f, "
               "\"map_build_ms\": %.3f, \"map_decided\": %.4f, \"map_bytes\": %zu, "
               "\"map_disagree\": %ld, \"map_compared\": %ld, \"derive_ms\": {",
               path, goal_cones, strong_cones, wrench_count, lp_wrench_count, auto_us, lp_us,
               warm_us, cone_us, agree, 2 * lp_wrench_count, batch_us, batch_answer, verdict_ns,
               verdict_disagree, verdict_compared, map_ns, map_build_ms, map_decided, map_bytes,
               map_disagree, 2 * wrench_count);
        for (int k = 2; k <= WR_MAX_FIXELS; k++)
            printf("%s\"%d\": %.3f", k > 2 ? ", " : "", k, derive_ms[k]);
        printf("}, \"derive_bytes\": {");
        for (int k = 2; k <= WR_MAX_FIXELS; k++)
            printf("%s\"%d\": %zu", k > 2 ? ", " : "", k, derive_bytes[k]);
        printf("}}\n");
    } else {
        printf("%s: %d goal cones, %d strong cones; %ld wrenches (%ld goal inside, %ld strong "
               "inside)\n",
               path, goal_cones, strong_cones, wrench_count, inside[0], inside[1]);
        printf("auto (goal + strong, witnesses)  %9.3f us/wrench   target <= 1\n", auto_us);
        printf("the verdict alone (goal + strong) %8.1f ns/wrench  target <= 50; %ld of %ld "
               "verdicts differ from the full path's\n",
               verdict_ns, verdict_disagree, verdict_compared);
        printf("the verdict by the map            %8.1f ns/wrench  target <= 50; built in %.2f ms "
               "(%zu bytes, %.1f%% of cells decided); %ld of %ld verdicts differ from the verdict "
               "alone's\n",
               map_ns, map_build_ms, map_bytes, 100 * map_decided, map_disagree, 2 * wrench_count);
        printf("lp (goal + strong)               %9.3f us/wrench   target <= %.1f "
               "(2 x %d cones x warm LP); agrees on %ld of %ld verdicts\n",
               lp_us, 2 * cones * warm_us, cones, agree, 2 * lp_wrench_count);
        printf("one warm GLPK LP                 %9.3f us\n", warm_us);
        printf("one explicit-cone distance       %9.4f us   (checksum %.6g)\n", cone_us, checksum);
        printf("batch, JSON in and out, no socket %8.3f us/wrench (%.0f wrenches/s, %zu bytes "
               "out)\n",
               batch_us, 1e6 / batch_us, batch_answer);
        for (int k = 2; k <= WR_MAX_FIXELS; k++)
            printf("derive k = %d                     %9.3f ms   %zu bytes\n", k, derive_ms[k],
                   derive_bytes[k]);
    }
    free(wrenches);
    wr_analysis_free(analysis);
    wr_fixture_free(fixture);
    return 0;
}
