/* wp_buffer.c -- the text buffer every answer is written into. */
#define _DEFAULT_SOURCE /* madvise's MADV_HUGEPAGE */
#include "wp_json.h"

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>

/* ---- buffer ------------------------------------------------------------- */

char *wp_buffer_grow_room(wp_buffer *b, size_t n)
{
    if (b->failed)
        return NULL;
    if (b->length + n + 1 > b->capacity) {
        size_t capacity = b->capacity ? b->capacity : 256;
        while (capacity < b->length + n + 1)
            capacity *= 2;
        char *grown = realloc(b->data, capacity);
        if (!grown) {
            b->failed = true;
            return NULL;
        }
        b->data = grown;
        b->capacity = capacity;
    }
    return b->data + b->length;
}

void wp_buffer_grow_append(wp_buffer *b, const char *text, size_t length)
{
    char *at = wp_buffer_grow_room(b, length);
    if (!at)
        return;
    memcpy(at, text, length);
    wp_buffer_commit(b, length);
}

void wp_buffer_reserve(wp_buffer *b, size_t bytes)
{
    if (b->failed || b->capacity >= bytes + 1)
        return;
    char *grown = realloc(b->data, bytes + 1);
    if (!grown)
        return; /* only a hint: appends grow the buffer as they need */
    if (!b->data)
        grown[0] = 0;
    b->data = grown;
    b->capacity = bytes + 1;
    wp_advise_huge(grown, bytes);
}

void wp_advise_huge(void *p, size_t bytes)
{
#ifdef MADV_HUGEPAGE
    /* A buffer of megabytes (a batch's answer, a long line, its wrenches)
     * is written once, front to back: in 2 MiB pages it takes a few dozen
     * page faults instead of thousands, which on a virtual machine cost
     * more than the writing.  Only a hint (malloc mapped it; the kernel may
     * decline). */
    const uintptr_t huge = (uintptr_t)2 << 20;
    if (bytes >= 4 * huge) {
        uintptr_t from = ((uintptr_t)p + huge - 1) & ~(huge - 1);
        uintptr_t to = ((uintptr_t)p + bytes) & ~(huge - 1);
        if (to > from)
            madvise((void *)from, to - from, MADV_HUGEPAGE);
    }
#else
    (void)p;
    (void)bytes;
#endif
}

void wp_buffer_puts(wp_buffer *b, const char *text) { wp_buffer_append(b, text, strlen(text)); }

void wp_buffer_number(wp_buffer *b, double value)
{
    char text[32];
    int length = wp_format_number(value, text);
    wp_buffer_append(b, text, (size_t)length);
}

void wp_buffer_string(wp_buffer *b, const char *text)
{
    wp_buffer_append(b, "\"", 1);
    const unsigned char *p = (const unsigned char *)text;
    const unsigned char *run = p;
    for (; *p; p++) {
        if (*p >= 0x20 && *p != '"' && *p != '\\')
            continue;
        wp_buffer_append(b, (const char *)run, (size_t)(p - run));
        char escape[8];
        switch (*p) {
        case '"': strcpy(escape, "\\\""); break;
        case '\\': strcpy(escape, "\\\\"); break;
        case '\n': strcpy(escape, "\\n"); break;
        case '\r': strcpy(escape, "\\r"); break;
        case '\t': strcpy(escape, "\\t"); break;
        case '\b': strcpy(escape, "\\b"); break;
        case '\f': strcpy(escape, "\\f"); break;
        default: snprintf(escape, sizeof escape, "\\u%04x", *p); break;
        }
        wp_buffer_puts(b, escape);
        run = p + 1;
    }
    wp_buffer_append(b, (const char *)run, (size_t)(p - run));
    wp_buffer_append(b, "\"", 1);
}

char *wp_buffer_take(wp_buffer *b)
{
    if (!b->failed && !b->data)
        wp_buffer_append(b, "", 0); /* nothing appended: the empty string */
    char *data = b->failed ? NULL : b->data;
    if (b->failed)
        free(b->data);
    b->data = NULL;
    b->length = b->capacity = 0;
    return data;
}
