/* wp_call.c -- what a method's call offers it (wp_method.h): its fixture,
 * acquired through the host into the envelope's hold, its id, and whether
 * it may send notifications, and its response's opening; and the release
 * of a host's listing (wp_host.h). */
#include "wp_method.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* A response's opening, up to its result's value: the same for every
 * call, written by the envelope or by a stream that opens its own. */
void wp_call_open_result(wp_call *call, wp_writer *w)
{
    (void)call;
    wp_write_object(w);
    wp_write_key(w, "jsonrpc");
    wp_write_string(w, "2.0");
    wp_write_key(w, "result");
}

/* params.fixture, held for the call: a stored id, or an inline fixture
 * object (validated, then cached under its id). */
wp_fixture_use *wp_call_fixture(wp_call *call)
{
    wp_fixture_hold *hold = call->fixture;
    if (hold->holding)
        return &hold->use; /* held since the light check, or an earlier piece */
    const wp_host *host = call->host;
    wp_error *error = call->error;
    const cJSON *value = cJSON_GetObjectItemCaseSensitive(call->params, "fixture");
    wp_host_failure failure = {WP_HOST_OK, ""};
    bool ok;
    if (cJSON_IsString(value)) {
        if (!wp_fixture_id_valid(value->valuestring)) {
            wp_error_set(error, WP_INVALID_PARAMS, "params.fixture",
                         "not a fixture id (32 hexadecimal digits) nor a fixture object");
            return NULL;
        }
        ok = host->fixture_use(host->self, value->valuestring, &hold->use, &failure);
    } else if (cJSON_IsObject(value)) {
        /* Validated once: a text kept since is used as it was adopted. */
        char written[WP_ID_LENGTH + 1] = "";
        if (host->fixture_use_written && wp_fixture_written_key(value, written) &&
            host->fixture_use_written(host->self, written, &hold->use)) {
            hold->holding = true;
            return &hold->use;
        }
        wp_fixture_doc doc;
        if (!wp_fixture_read(value, "params.fixture", &doc, error))
            return NULL;
        memcpy(doc.written, written, sizeof doc.written);
        doc.text = hold->text;
        doc.text_length = hold->text_length;
        ok = host->fixture_adopt(host->self, &doc, false, &hold->use, &failure);
    } else {
        wp_error_set(error, WP_INVALID_PARAMS, "params.fixture",
                     "must be a fixture id or a fixture object, not %s", wp_type_name(value));
        return NULL;
    }
    if (!ok)
        wp_error_host(error, &failure, "params.fixture");
    hold->holding = ok;
    return ok ? &hold->use : NULL;
}

const char *wp_call_id_text(const wp_call *call) { return call->id_text; }

bool wp_call_may_notify(const wp_call *call) { return call->may_notify; }

void wp_fixture_listing_release(wp_fixture_listing *listing)
{
    for (size_t i = 0; i < listing->count; i++)
        free(listing->entries[i].name);
    free(listing->entries);
    listing->entries = NULL;
    listing->count = 0;
}
