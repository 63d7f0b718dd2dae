/* wp_canonical.c -- a JSON value's canonical text (what fixture ids hash,
 * and a client's request line). */
#include "wp_json.h"
#include "wp_sha256.h"

#include <stdint.h>
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

/* ---- the canonical digest ------------------------------------------------ */

/* SHA-256 fed through a block, so that a value's many small pieces cost one
 * update per block. */
typedef struct digest_feed {
    wp_sha256 hash;
    size_t used;
    bool failed;
    unsigned char block[4096];
} digest_feed;

static void feed(digest_feed *f, const void *data, size_t size)
{
    if (f->used + size > sizeof f->block) {
        wp_sha256_update(&f->hash, f->block, f->used);
        f->used = 0;
        if (size > sizeof f->block) {
            wp_sha256_update(&f->hash, data, size);
            return;
        }
    }
    memcpy(f->block + f->used, data, size);
    f->used += size;
}

/* Strings by length and bytes, so that no two values feed the same bytes. */
static void feed_string(digest_feed *f, char tag, const char *text)
{
    uint64_t length = strlen(text);
    feed(f, &tag, 1);
    feed(f, &length, sizeof length);
    feed(f, text, length);
}

static void digest_value(digest_feed *f, const cJSON *value)
{
    if (cJSON_IsObject(value)) {
        size_t count = 0;
        for (const cJSON *m = value->child; m; m = m->next)
            count++;
        const cJSON *few[16];
        const cJSON **members = count <= 16 ? few : malloc(count * sizeof *members);
        if (!members) {
            f->failed = true;
            return;
        }
        count = 0;
        for (const cJSON *m = value->child; m; m = m->next)
            members[count++] = m;
        qsort(members, count, sizeof *members, compare_members);
        feed(f, "{", 1);
        for (size_t i = 0; i < count; i++) {
            feed_string(f, 'k', members[i]->string);
            digest_value(f, members[i]);
        }
        feed(f, "}", 1);
        if (members != few)
            free(members);
    } else if (cJSON_IsArray(value)) {
        feed(f, "[", 1);
        for (const cJSON *m = value->child; m; m = m->next)
            digest_value(f, m);
        feed(f, "]", 1);
    } else if (cJSON_IsNumber(value)) {
        /* The double itself, bit for bit: equal bits are equal numbers,
         * whose canonical texts are equal. */
        feed(f, "n", 1);
        feed(f, &value->valuedouble, sizeof value->valuedouble);
    } else if (cJSON_IsString(value) || cJSON_IsRaw(value)) {
        feed_string(f, cJSON_IsString(value) ? 's' : 'r', value->valuestring);
    } else {
        feed(f, cJSON_IsTrue(value) ? "t" : cJSON_IsFalse(value) ? "f" : "z", 1);
    }
}

bool wp_canonical_digest(const cJSON *value, unsigned char digest[32])
{
    digest_feed *f = malloc(sizeof *f);
    if (!f)
        return false;
    f->used = 0;
    f->failed = false;
    wp_sha256_init(&f->hash);
    digest_value(f, value);
    wp_sha256_update(&f->hash, f->block, f->used);
    wp_sha256_final(&f->hash, digest);
    bool ok = !f->failed;
    free(f);
    return ok;
}
