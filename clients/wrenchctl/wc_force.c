/* wc_force.c -- magnitudes (docs/PROTOCOL.md, force.range, push.force, and
 * push.regions' "force" and "cases"): how hard to push, how hard to clamp.
 * Load cases are written on the command line as
 *
 *     [NAME:]LOAD[;LOAD...]   LOAD = gravity=G@DEG | force=FX,FY@X,Y | wrench=FX,FY,TAU
 *
 * and sent as the protocol's cases; the daemon checks them, field by field. */
#include "wc_call.h"
#include "wc_commands.h"
#include "wc_svg.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Numbers separated by `separator`, exactly `count` of them, the whole
 * text.  False when not. */
static bool numbers(const char *text, char separator, int count, double *out)
{
    const char *p = text;
    for (int i = 0; i < count; i++) {
        char *end;
        out[i] = strtod(p, &end);
        if (end == p || !isfinite(out[i]))
            return false;
        if (i + 1 < count && *end != separator)
            return false;
        p = i + 1 < count ? end + 1 : end;
    }
    return *p == '\0';
}

static cJSON *number_array(const double *v, int n)
{
    return cJSON_CreateDoubleArray(v, n);
}

/* One LOAD of a --case, or NULL after saying why not. */
static cJSON *load_argument(const char *spec, const char *load)
{
    char text[256];
    snprintf(text, sizeof text, "%s", load);
    char *equals = strchr(text, '=');
    if (!equals)
        goto bad;
    *equals = '\0';
    const char *kind = text, *value = equals + 1;
    cJSON *out = cJSON_CreateObject();
    if (strcmp(kind, "gravity") == 0) {
        double v[2];
        if (!numbers(value, '@', 2, v)) {
            cJSON_Delete(out);
            goto bad;
        }
        cJSON *g = cJSON_AddObjectToObject(out, "gravity");
        cJSON_AddNumberToObject(g, "g", v[0]);
        cJSON_AddNumberToObject(g, "direction_deg", v[1]);
        return out;
    }
    if (strcmp(kind, "force") == 0) {
        char *at = strchr(equals + 1, '@');
        double f[2], p[2];
        if (!at) {
            cJSON_Delete(out);
            goto bad;
        }
        *at = '\0';
        if (!numbers(value, ',', 2, f) || !numbers(at + 1, ',', 2, p)) {
            cJSON_Delete(out);
            goto bad;
        }
        cJSON_AddItemToObject(out, "force", number_array(f, 2));
        cJSON_AddItemToObject(out, "at", number_array(p, 2));
        return out;
    }
    if (strcmp(kind, "wrench") == 0) {
        double w[3];
        if (!numbers(value, ',', 3, w)) {
            cJSON_Delete(out);
            goto bad;
        }
        cJSON_AddItemToObject(out, "wrench", number_array(w, 3));
        return out;
    }
    cJSON_Delete(out);
bad:
    wc_usage_error("--case '%s': '%s' is not gravity=G@DEG, force=FX,FY@X,Y or wrench=FX,FY,TAU",
                   spec, load);
    return NULL;
}

int wc_take_case(wc_run *run, const char *value)
{
    cJSON *c = cJSON_CreateObject(), *loads = cJSON_AddArrayToObject(c, "loads");
    const char *rest = value, *colon = strchr(value, ':'), *equals = strchr(value, '=');
    if (colon && (!equals || colon < equals)) {
        char name[128];
        snprintf(name, sizeof name, "%.*s", (int)(colon - value), value);
        cJSON_AddStringToObject(c, "name", name);
        rest = colon + 1;
    }
    char text[1024];
    snprintf(text, sizeof text, "%s", rest);
    for (char *save = NULL, *load = strtok_r(text, ";", &save); load;
         load = strtok_r(NULL, ";", &save)) {
        cJSON *item = load_argument(value, load);
        if (!item) {
            cJSON_Delete(c);
            return EXIT_USAGE;
        }
        cJSON_AddItemToArray(loads, item);
    }
    if (cJSON_GetArraySize(loads) == 0) {
        cJSON_Delete(c);
        return wc_usage_error("--case '%s' has no load", value);
    }
    if (!run->cases)
        run->cases = cJSON_CreateArray();
    cJSON_AddItemToArray(run->cases, c);
    return 0;
}

int wc_take_force_push(wc_run *run, const char *value)
{
    double at[2], direction[2];
    const char *sign = strchr(value, '@');
    char point[128];
    snprintf(point, sizeof point, "%.*s", sign ? (int)(sign - value) : (int)strlen(value), value);
    if (run->force_push || run->force_wrench || !numbers(point, ',', 2, at) ||
        (sign && !numbers(sign + 1, ',', 2, direction)))
        return wc_usage_error("--push wants X,Y or X,Y@DX,DY, once, not '%s'", value);
    run->force_push = cJSON_CreateObject();
    cJSON_AddItemToObject(run->force_push, "at", number_array(at, 2));
    if (sign)
        cJSON_AddItemToObject(run->force_push, "direction", number_array(direction, 2));
    return 0;
}

int wc_take_force_wrench(wc_run *run, const char *value)
{
    double w[3];
    if (run->force_push || run->force_wrench || !numbers(value, ',', 3, w))
        return wc_usage_error("--wrench wants FX,FY,TAU, once, not '%s'", value);
    run->force_wrench = number_array(w, 3);
    return 0;
}

int wc_take_push_force(wc_run *run, const char *value)
{
    char *end;
    run->push_force = strtod(value, &end);
    if (end == value || *end || !(run->push_force > 0) || !isfinite(run->push_force))
        return wc_usage_error("--force wants a magnitude above 0, not '%s'", value);
    run->push_force_given = true;
    return 0;
}

int wc_push_loads(wc_run *run, cJSON *params)
{
    if (run->cases && !run->push_force_given)
        return wc_usage_error("--case needs --force: the push's magnitude");
    if (run->push_force_given)
        cJSON_AddNumberToObject(params, "force", run->push_force);
    if (run->cases)
        cJSON_AddItemToObject(params, "cases", cJSON_Duplicate(run->cases, true));
    return -1;
}

/* The force unit named by an inline fixture, for the tables. */
static const char *unit_of(const wc_run *run)
{
    const cJSON *units = cJSON_IsObject(run->fixture)
                             ? cJSON_GetObjectItem(run->fixture, "units")
                             : NULL;
    const char *force = cJSON_GetStringValue(cJSON_GetObjectItem(units, "force"));
    return force ? force : cJSON_IsObject(run->fixture) ? "(model units)" : "(the fixture's unit)";
}

/* ---- force -------------------------------------------------------------------- */

int wc_force_request(wc_run *run, cJSON *params)
{
    if (!run->force_push && !run->force_wrench)
        return wc_usage_error("force: --push X,Y or --wrench FX,FY,TAU is required");
    if (!run->cases)
        return wc_usage_error("force: at least one --case is required");
    if (run->force_push)
        cJSON_AddItemToObject(params, "push", cJSON_Duplicate(run->force_push, true));
    else
        cJSON_AddItemToObject(params, "wrench", cJSON_Duplicate(run->force_wrench, true));
    cJSON_AddItemToObject(params, "cases", cJSON_Duplicate(run->cases, true));
    if (run->sets) {
        cJSON_AddItemToObject(params, "sets", run->sets);
        run->sets = NULL;
    }
    if (run->range_given) {
        double range[2] = {run->range[0], run->range[1]};
        cJSON_AddItemToObject(params, "range", number_array(range, 2));
    }
    return -1;
}

/* "[a, b) [c, inf)" for S's intervals. */
static void intervals_text(const cJSON *set, char *out, size_t size)
{
    const cJSON *list = cJSON_GetObjectItem(set, "intervals"), *pair;
    size_t used = 0;
    out[0] = '\0';
    cJSON_ArrayForEach(pair, list)
    {
        const cJSON *b = cJSON_GetArrayItem(pair, 1);
        int n = cJSON_IsNumber(b)
                    ? snprintf(out + used, size - used, "%s(%.6g, %.6g)", used ? " " : "",
                               cJSON_GetArrayItem(pair, 0)->valuedouble, b->valuedouble)
                    : snprintf(out + used, size - used, "%s(%.6g, inf)", used ? " " : "",
                               cJSON_GetArrayItem(pair, 0)->valuedouble);
        if (n < 0 || (size_t)n >= size - used)
            break;
        used += (size_t)n;
    }
    if (!out[0])
        snprintf(out, size, "none");
}

static void print_row(const char *name, const char *set_name, const cJSON *set)
{
    char text[512];
    intervals_text(set, text, sizeof text);
    const cJSON *least = cJSON_GetObjectItem(set, "least");
    char least_text[32] = "none";
    if (cJSON_IsNumber(least))
        snprintf(least_text, sizeof least_text, "%.9g", least->valuedouble);
    printf("%-16s  %-6s  %-14s  %s\n", name, set_name, least_text, text);
}

/* --svg: the part with its supports, the push and the least force over
 * all cases (goal's, else the first set's). */
static bool draw_force(const wc_run *run, const cJSON *result, FILE *out,
                       const wr_fixture *geometry, const char *name)
{
    const cJSON *all = cJSON_GetObjectItem(result, "all");
    const cJSON *set = cJSON_HasObjectItem(all, "goal") ? cJSON_GetObjectItem(all, "goal")
                                                        : all->child;
    const cJSON *least = cJSON_GetObjectItem(set, "least");
    double push[3], *drawn = NULL;
    if (run->force_wrench) {
        for (int k = 0; k < 3; k++)
            push[k] = cJSON_GetArrayItem(run->force_wrench, k)->valuedouble;
        drawn = push;
    } else if (cJSON_HasObjectItem(run->force_push, "direction")) {
        const cJSON *at = cJSON_GetObjectItem(run->force_push, "at");
        const cJSON *d = cJSON_GetObjectItem(run->force_push, "direction");
        double p[2] = {cJSON_GetArrayItem(at, 0)->valuedouble, cJSON_GetArrayItem(at, 1)->valuedouble};
        double v[2] = {cJSON_GetArrayItem(d, 0)->valuedouble, cJSON_GetArrayItem(d, 1)->valuedouble};
        wr_fixture_force_wrench(geometry, v, p, push);
        drawn = push;
    }
    wc_svg_force(out, geometry, name, drawn,
                 cJSON_IsNumber(least) ? least->valuedouble : INFINITY, wc_force_unit(geometry));
    return true;
}

int wc_force_answer(wc_run *run, const cJSON *result)
{
    int pictured = wc_picture(run, result, draw_force);
    if (pictured >= 0)
        return pictured;
    static const char *const sets[] = {"goal", "strong", "both"};
    const cJSON *all = cJSON_GetObjectItem(result, "all");
    if (!run->o->json) {
        printf("forces in %s; an interval's ends are on the boundary, its inside inside\n",
               unit_of(run));
        printf("%-16s  %-6s  %-14s  %s\n", "case", "set", "least", "magnitudes that do it");
        const cJSON *c;
        int i = 0;
        cJSON_ArrayForEach(c, cJSON_GetObjectItem(result, "cases"))
        {
            char name[32];
            const char *given = cJSON_GetStringValue(cJSON_GetObjectItem(c, "name"));
            snprintf(name, sizeof name, "%s", given ? given : "");
            if (!given)
                snprintf(name, sizeof name, "case %d", i + 1);
            for (int s = 0; s < 3; s++)
                if (cJSON_HasObjectItem(c, sets[s]))
                    print_row(name, sets[s], cJSON_GetObjectItem(c, sets[s]));
            i++;
        }
        for (int s = 0; s < 3; s++)
            if (cJSON_HasObjectItem(all, sets[s]))
                print_row("all cases", sets[s], cJSON_GetObjectItem(all, sets[s]));
    }
    const cJSON *decisive = cJSON_HasObjectItem(all, "both") ? cJSON_GetObjectItem(all, "both")
                                                             : all->child;
    return cJSON_IsNumber(cJSON_GetObjectItem(decisive, "least")) ? EXIT_INSIDE : EXIT_NOT_INSIDE;
}

/* ---- push-force --------------------------------------------------------------- */

int wc_push_force_request(wc_run *run, cJSON *params)
{
    if (!run->cases)
        return wc_usage_error("push-force: at least one --case is required");
    cJSON_AddItemToObject(params, "cases", cJSON_Duplicate(run->cases, true));
    if (run->set)
        cJSON_AddStringToObject(params, "set", run->set);
    if (run->radius_given)
        cJSON_AddNumberToObject(params, "finger_radius", run->finger_radius);
    if (run->samples)
        cJSON_AddNumberToObject(params, "samples", run->samples);
    return wc_push_on(run,
                      cJSON_IsString(run->fixture) ? run->fixture
                                                   : cJSON_GetObjectItem(run->fixture, "body"),
                      params);
}

const char *wc_named_force_unit(const cJSON *fixture)
{
    const char *unit = cJSON_GetStringValue(
        cJSON_GetObjectItem(cJSON_GetObjectItem(fixture, "units"), "force"));
    return unit ? unit : "(model units)";
}

const char *wc_force_unit(const wr_fixture *f)
{
    if (!f->units.given)
        return "(model units)";
    return f->units.force_n == 1.0 ? "N" : f->units.force_n == 1e-3 ? "mN" : "lbf";
}

/* An outline's (loop, segment) or a polygon's edge as wr_region's edge. */
static int edge_of(const wr_fixture *f, const cJSON *place)
{
    const cJSON *loop = cJSON_GetObjectItem(place, "loop");
    if (!cJSON_IsNumber(loop) || f->shape != WR_SHAPE_OUTLINE)
        return (int)cJSON_GetNumberValue(cJSON_GetObjectItem(place, "edge"));
    int edge = 0;
    for (int l = 0; l < (int)loop->valuedouble && (size_t)l < f->outline->loop_count; l++)
        edge += (int)f->outline->loops[l].segment_count;
    return edge + (int)cJSON_GetNumberValue(cJSON_GetObjectItem(place, "segment"));
}

static bool draw_push_force(const wc_run *run, const cJSON *result, FILE *out,
                            const wr_fixture *geometry, const char *name)
{
    const cJSON *segments = cJSON_GetObjectItem(result, "segments");
    int count = cJSON_GetArraySize(segments), samples = 0;
    const cJSON *s;
    cJSON_ArrayForEach(s, segments)
    samples += cJSON_GetArraySize(cJSON_GetObjectItem(s, "t"));
    wc_force_band *bands = calloc((size_t)(count ? count : 1), sizeof *bands);
    double *values = calloc((size_t)(2 * samples + 1), sizeof *values);
    if (!bands || !values) {
        free(bands);
        free(values);
        wc_usage_error("--svg: out of memory");
        return false;
    }
    int b = 0, used = 0;
    cJSON_ArrayForEach(s, segments)
    {
        const cJSON *ts = cJSON_GetObjectItem(s, "t"), *fs = cJSON_GetObjectItem(s, "force");
        int n = cJSON_GetArraySize(ts);
        double *t = values + used, *force = values + used + n;
        for (int j = 0; j < n; j++) {
            const cJSON *v = cJSON_GetArrayItem(fs, j);
            t[j] = cJSON_GetArrayItem(ts, j)->valuedouble;
            force[j] = cJSON_IsNumber(v) ? v->valuedouble : NAN;
        }
        bands[b++] = (wc_force_band){edge_of(geometry, s), n, t, force};
        used += 2 * n;
    }
    const cJSON *least = cJSON_GetObjectItem(result, "least");
    double at[2] = {0, 0}, direction[2] = {0, 0}, force = NAN;
    if (cJSON_IsObject(least)) {
        for (int k = 0; k < 2; k++) {
            at[k] = cJSON_GetArrayItem(cJSON_GetObjectItem(least, "at"), k)->valuedouble;
            direction[k] =
                cJSON_GetArrayItem(cJSON_GetObjectItem(least, "direction"), k)->valuedouble;
        }
        force = cJSON_GetNumberValue(cJSON_GetObjectItem(least, "force"));
    }
    wc_svg_push_force(out, geometry, name, run->set ? run->set : "both", bands, count, at,
                      direction, force, wc_force_unit(geometry));
    free(bands);
    free(values);
    return true;
}

int wc_push_force_answer(wc_run *run, const cJSON *result)
{
    const cJSON *least = cJSON_GetObjectItem(result, "least");
    if (!run->o->json) {
        const char *unit = unit_of(run);
        printf("%-14s  %-16s  %s\n", "segment", "least F* sampled", "samples (no push: -)");
        const cJSON *s;
        cJSON_ArrayForEach(s, cJSON_GetObjectItem(result, "segments"))
        {
            double low = INFINITY;
            int none = 0, n = 0;
            const cJSON *v;
            cJSON_ArrayForEach(v, cJSON_GetObjectItem(s, "force"))
            {
                n++;
                if (cJSON_IsNumber(v))
                    low = fmin(low, v->valuedouble);
                else
                    none++;
            }
            char place[32];
            if (cJSON_HasObjectItem(s, "loop"))
                snprintf(place, sizeof place, "loop %d seg %d",
                         (int)cJSON_GetNumberValue(cJSON_GetObjectItem(s, "loop")),
                         (int)cJSON_GetNumberValue(cJSON_GetObjectItem(s, "segment")));
            else
                snprintf(place, sizeof place, "edge %d",
                         (int)cJSON_GetNumberValue(cJSON_GetObjectItem(s, "edge")));
            char low_text[32] = "-";
            if (isfinite(low))
                snprintf(low_text, sizeof low_text, "%.6g", low);
            printf("%-14s  %-16s  %d, %d without\n", place, low_text, n, none);
        }
        if (cJSON_IsObject(least)) {
            const cJSON *at = cJSON_GetObjectItem(least, "at");
            const cJSON *d = cJSON_GetObjectItem(least, "direction");
            printf("least push %.9g %s at (%.6g, %.6g) along (%.4g, %.4g)%s\n",
                   cJSON_GetNumberValue(cJSON_GetObjectItem(least, "force")), unit,
                   cJSON_GetArrayItem(at, 0)->valuedouble, cJSON_GetArrayItem(at, 1)->valuedouble,
                   cJSON_GetArrayItem(d, 0)->valuedouble, cJSON_GetArrayItem(d, 1)->valuedouble,
                   cJSON_IsTrue(cJSON_GetObjectItem(least, "converged"))
                       ? ""
                       : " (not converged: see lower_bound)");
        } else {
            printf("no push of any force does the job under every case\n");
        }
    }
    int status = wc_picture(run, result, draw_push_force);
    if (status >= 0)
        return status;
    return cJSON_IsObject(least) ? EXIT_INSIDE : EXIT_NOT_INSIDE;
}
