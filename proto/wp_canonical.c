/* wp_canonical.c -- a JSON value's canonical text (what fixture ids hash,
 * and a client's request line). */
#include "wp_json.h"

#include <stdlib.h>
#include <string.h>

/* ---- numbers and canonical text ---------------------------------------- */

static int compare_members(const void *a, const void *b)
{
    const cJSON *x = *(const cJSON *const *)a, *y = *(const cJSON *const *)b;
    return strcmp(x->string, y->string);
}

/* The canonical text of `value`: members by key. */
static void write_value(wp_buffer *b, const cJSON *value, const char *skip)
{
    if (cJSON_IsObject(value)) {
        size_t count = 0;
        for (const cJSON *m = value->child; m; m = m->next)
            count++;
        const cJSON **members = malloc((count ? count : 1) * sizeof *members);
        if (!members) {
            b->failed = true;
            return;
        }
        count = 0;
        for (const cJSON *m = value->child; m; m = m->next)
            if (!skip || strcmp(m->string, skip) != 0)
                members[count++] = m;
        qsort(members, count, sizeof *members, compare_members);
        wp_buffer_append(b, "{", 1);
        for (size_t i = 0; i < count; i++) {
            if (i)
                wp_buffer_append(b, ",", 1);
            wp_buffer_string(b, members[i]->string);
            wp_buffer_append(b, ":", 1);
            write_value(b, members[i], NULL);
        }
        wp_buffer_append(b, "}", 1);
        free(members);
    } else if (cJSON_IsArray(value)) {
        wp_buffer_append(b, "[", 1);
        for (const cJSON *m = value->child; m; m = m->next) {
            if (m != value->child)
                wp_buffer_append(b, ",", 1);
            write_value(b, m, NULL);
        }
        wp_buffer_append(b, "]", 1);
    } else if (cJSON_IsNumber(value)) {
        wp_buffer_number(b, value->valuedouble);
    } else if (cJSON_IsString(value)) {
        wp_buffer_string(b, value->valuestring);
    } else if (cJSON_IsTrue(value)) {
        wp_buffer_puts(b, "true");
    } else if (cJSON_IsFalse(value)) {
        wp_buffer_puts(b, "false");
    } else {
        wp_buffer_puts(b, "null");
    }
}

char *wp_canonical(const cJSON *value, const char *skip)
{
    wp_buffer b = {0};
    write_value(&b, value, skip);
    return wp_buffer_take(&b);
}
