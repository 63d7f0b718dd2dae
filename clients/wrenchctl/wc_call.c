/* wc_call.c -- one request to wrenchd, or answered in process with the
 * daemon's own request code (--local); the readers of FIXTURE and WRENCH
 * arguments. */
#include "wc_call.h"

#include "wp_local.h"
#include "wrenchclient.h"

#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

int wc_usage_error(const char *format, ...)
{
    va_list args;
    va_start(args, format);
    fputs("wrenchctl: ", stderr);
    vfprintf(stderr, format, args);
    fputs("\n", stderr);
    va_end(args);
    return EXIT_USAGE;
}

/* ---- the request and its answer -------------------------------------------- */

/* Send {"method", "params"} and return the parsed result, or NULL with the
 * exit status in *status after saying what went wrong. */
cJSON *wc_call(wc_options *o, const char *method, cJSON *params, int *status)
{
    cJSON *request = cJSON_CreateObject();
    cJSON_AddStringToObject(request, "jsonrpc", "2.0");
    cJSON_AddStringToObject(request, "method", method);
    cJSON_AddItemToObject(request, "params", params);
    cJSON_AddNumberToObject(request, "id", 1);
    /* Every number exactly as read: cJSON's own printer writes some doubles
     * to 15 digits (a bulge of tan(pi/8) moves by 1e-16), and the daemon
     * would answer for another drawing. */
    char *line = wp_canonical(request, NULL);
    cJSON_Delete(request);
    if (!line) {
        *status = EXIT_SERVER;
        fputs("wrenchctl: out of memory\n", stderr);
        return NULL;
    }
    char *answer = NULL;
    if (o->local) {
        wp_local *local = wp_local_new();
        wp_limits limits = {64, (size_t)-1, (size_t)-1, 0, (size_t)-1};
        wp_counts counts = {0, 0};
        answer = local ? wp_answer_line(wp_local_host(local), &limits, line, strlen(line), &counts)
                       : NULL;
        wp_local_free(local);
    } else {
        int error;
        wrc_client *client =
            wrc_connect(o->socket_path, (int)(o->timeout_seconds * 1000), 0, &error);
        int connect_errno = errno;
        if (client) {
            error = o->notify ? wrc_call_notified(client, line, &answer, o->notify,
                                                  o->notify_context)
                              : wrc_call(client, line, &answer);
            if (error != WRC_OK && error != WRC_ESERVER) {
                fprintf(stderr, "wrenchctl: %s: %s\n", wrc_strerror(error),
                        wrc_last_error(client));
                free(answer);
                answer = NULL;
            }
        } else if (error == WRC_ECONNECT) {
            char reason[512];
            wrc_connect_reason(o->socket_path, connect_errno, reason, sizeof reason);
            fprintf(stderr, "wrenchctl: %s: %s (see --socket)\n", wrc_strerror(error), reason);
        } else {
            fprintf(stderr, "wrenchctl: %s at %s\n", wrc_strerror(error), o->socket_path);
        }
        wrc_close(client);
        if (!answer) {
            free(line);
            *status = error == WRC_EPROTO || error == WRC_ETOOBIG || error == WRC_ENOMEM
                          ? EXIT_SERVER
                          : EXIT_UNREACHABLE;
            return NULL;
        }
    }
    free(line);
    cJSON *json = answer ? cJSON_Parse(answer) : NULL;
    free(answer);
    if (!json) {
        fputs("wrenchctl: the answer is not JSON\n", stderr);
        *status = EXIT_SERVER;
        return NULL;
    }
    cJSON *error = cJSON_GetObjectItem(json, "error");
    if (error) {
        cJSON *data = cJSON_GetObjectItem(error, "data");
        const char *field = cJSON_GetStringValue(cJSON_GetObjectItem(data, "field"));
        const char *reason = cJSON_GetStringValue(cJSON_GetObjectItem(data, "reason"));
        fprintf(stderr, "wrenchctl: %s (%d)%s%s: %s\n",
                cJSON_GetStringValue(cJSON_GetObjectItem(error, "message")),
                (int)cJSON_GetNumberValue(cJSON_GetObjectItem(error, "code")),
                field && *field ? " at " : "", field ? field : "", reason ? reason : "");
        cJSON_Delete(json);
        *status = EXIT_SERVER;
        return NULL;
    }
    cJSON *result = cJSON_DetachItemFromObject(json, "result");
    cJSON_Delete(json);
    *status = EXIT_INSIDE;
    return result;
}

static bool looks_like_id(const char *text)
{
    if (strlen(text) != 32)
        return false;
    for (const char *c = text; *c; c++)
        if (!((*c >= '0' && *c <= '9') || (*c >= 'a' && *c <= 'f')))
            return false;
    return true;
}

/* The whole file, NUL-terminated; *length (may be NULL) its bytes. */
char *wc_read_all(FILE *file, size_t *length_out)
{
    size_t length = 0, capacity = 65536;
    char *text = malloc(capacity);
    while (text) {
        length += fread(text + length, 1, capacity - length - 1, file);
        if (length + 1 < capacity)
            break;
        char *grown = realloc(text, capacity *= 2);
        if (!grown)
            free(text);
        text = grown;
    }
    if (text)
        text[length] = 0;
    if (length_out)
        *length_out = length;
    return text;
}

/* A FIXTURE argument: an existing file is read as an inline fixture,
 * otherwise an id.  NULL with a message when neither. */
cJSON *wc_fixture_argument(wc_options *o, const char *argument)
{
    struct stat st;
    if (stat(argument, &st) == 0) {
        FILE *file = fopen(argument, "rb");
        int open_error = errno;
        size_t length = 0;
        char *text = file ? wc_read_all(file, &length) : NULL;
        if (file)
            fclose(file);
        /* One JSON text and nothing after it but white space: a fixture
         * followed by more is refused, not half read. */
        const char *end = NULL;
        cJSON *json = text ? cJSON_ParseWithLengthOpts(text, length, &end, false) : NULL;
        if (json) {
            end += strspn(end, " \t\r\n");
            if (end != text + length) {
                size_t line = 1;
                for (const char *c = text; c < end; c++)
                    line += *c == '\n';
                int shown = (int)strcspn(end, "\r\n");
                wc_usage_error("%s: text after the JSON value, on line %zu: '%.*s'", argument, line,
                            shown > 24 ? 24 : shown, end);
                cJSON_Delete(json);
                json = NULL;
            }
        } else {
            wc_usage_error("%s: %s", argument,
                        !file ? strerror(open_error) : text ? "not a JSON text" : "out of memory");
        }
        free(text);
        return json;
    }
    if (!looks_like_id(argument)) {
        wc_usage_error("%s: no such file, and not a fixture id (32 hexadecimal digits)", argument);
        return NULL;
    }
    if (o->local) {
        wc_usage_error("--local needs a fixture file: there is no store in process");
        return NULL;
    }
    return cJSON_CreateString(argument);
}

/* --friction LO:HI: the fixture inline, its friction the interval at every
 * fixel. */
/* A stored fixture fetched in place of its id, so that it can be sent
 * inline with a member replaced; -1, or an exit status (`option` names the
 * option that asked, for the error). */
static int fixture_inline(wc_options *o, cJSON **fixture, const char *option)
{
    if (cJSON_IsString(*fixture)) {
        int status;
        cJSON *params = cJSON_CreateObject();
        cJSON_AddStringToObject(params, "id", (*fixture)->valuestring);
        cJSON *stored = wc_call(o, "fixture.get", params, &status);
        if (!stored)
            return status;
        cJSON_Delete(*fixture);
        *fixture = stored;
    }
    if (!cJSON_IsObject(*fixture))
        return wc_usage_error("%s: the fixture is not a JSON object", option);
    return -1;
}

int wc_fixture_friction(wc_options *o, cJSON **fixture, double low, double high)
{
    int status = fixture_inline(o, fixture, "--friction");
    if (status >= 0)
        return status;
    cJSON *fixels = cJSON_GetObjectItem(*fixture, "fixels");
    cJSON *fixel;
    cJSON_ArrayForEach(fixel, fixels)
    {
        if (cJSON_IsObject(fixel))
            cJSON_DeleteItemFromObject(fixel, "friction");
    }
    cJSON *friction = cJSON_CreateObject();
    const char *const names[] = {"static", "kinetic"};
    for (int k = 0; k < 2; k++) {
        if (low == high)
            cJSON_AddNumberToObject(friction, names[k], low);
        else
            cJSON_AddItemToObject(friction, names[k],
                                  cJSON_CreateDoubleArray((double[]){low, high}, 2));
    }
    cJSON_DeleteItemFromObject(*fixture, "friction");
    cJSON_AddItemToObject(*fixture, "friction", friction);
    return -1;
}

/* A stored fixture fetched (an inline one as it is) and sent inline with
 * the tolerance {"position", "angle"} in place of its own. */
int wc_fixture_tolerance(wc_options *o, cJSON **fixture, double position, double angle)
{
    int status = fixture_inline(o, fixture, "--tolerance");
    if (status >= 0)
        return status;
    cJSON *tolerance = cJSON_CreateObject();
    cJSON_AddNumberToObject(tolerance, "position", position);
    if (angle > 0)
        cJSON_AddNumberToObject(tolerance, "angle", angle);
    cJSON_DeleteItemFromObject(*fixture, "tolerance");
    cJSON_AddItemToObject(*fixture, "tolerance", tolerance);
    return -1;
}

/* A stored fixture fetched (an inline one as it is) and sent inline with
 * `supports` (a JSON object, or a file holding one) as its member. */
int wc_fixture_supports(wc_options *o, cJSON **fixture, const char *supports)
{
    int status = fixture_inline(o, fixture, "--supports");
    if (status >= 0)
        return status;
    const char *text = supports + strspn(supports, " \t\r\n");
    cJSON *member = *text == '{' ? cJSON_Parse(text) : wc_fixture_argument(o, supports);
    if (!cJSON_IsObject(member)) {
        cJSON_Delete(member);
        return wc_usage_error("--supports '%s': a JSON object {\"points\", \"friction\", \"g\", "
                              "\"down\"?}, or a file holding one",
                              supports);
    }
    cJSON_DeleteItemFromObject(*fixture, "supports");
    cJSON_AddItemToObject(*fixture, "supports", member);
    return -1;
}

/* ---- wrenches ---------------------------------------------------------------- */

/* "fx,fy,tau" or "fx,fy@x,y" as a wrench JSON value; NULL if neither. */
cJSON *wc_wrench_argument(const char *text)
{
    double v[4];
    int used = 0;
    char tail;
    const char *at = strchr(text, '@');
    if (!at) {
        if (sscanf(text, "%lf,%lf,%lf%n%c", &v[0], &v[1], &v[2], &used, &tail) != 3 ||
            text[used] != 0)
            return NULL;
        for (int k = 0; k < 3; k++)
            if (!isfinite(v[k]))
                return NULL;
        return cJSON_CreateDoubleArray(v, 3);
    }
    double force[2], point[2];
    if (sscanf(text, "%lf,%lf@%lf,%lf%n%c", &force[0], &force[1], &point[0], &point[1], &used,
               &tail) != 4 ||
        text[used] != 0 || !isfinite(force[0]) || !isfinite(force[1]) || !isfinite(point[0]) ||
        !isfinite(point[1]))
        return NULL;
    cJSON *w = cJSON_CreateObject();
    cJSON_AddItemToObject(w, "force", cJSON_CreateDoubleArray(force, 2));
    cJSON_AddItemToObject(w, "at", cJSON_CreateDoubleArray(point, 2));
    return w;
}
