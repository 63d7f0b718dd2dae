/* wp_writer.c -- the JSON writer of every answer (wp_json.h): each value
 * says only what it is; the commas and the nesting are the writer's. */
#include "wp_json.h"

#include <assert.h>
#include <string.h>

static void open_container(wp_writer *w, char bracket)
{
    const char text[2] = {',', bracket};
    bool comma = wp_write_comma_due(w);
    assert(w->depth < WP_WRITER_DEPTH);
    wp_buffer_append(w->out, text + !comma, 1 + comma);
    w->depth++;
    w->filled &= ~((uint64_t)1 << (w->depth - 1));
}

static void close_container(wp_writer *w, char bracket)
{
    assert(w->depth > 0 && !w->keyed);
    wp_buffer_append(w->out, &bracket, 1);
    w->depth--;
}

void wp_write_object(wp_writer *w) { open_container(w, '{'); }
void wp_write_object_end(wp_writer *w) { close_container(w, '}'); }
void wp_write_array(wp_writer *w) { open_container(w, '['); }
void wp_write_array_end(wp_writer *w) { close_container(w, ']'); }

void wp_write_key(wp_writer *w, const char *key)
{
    assert(w->depth > 0 && !w->keyed);
    bool comma = wp_write_comma_due(w);
    size_t length = strlen(key);
    char *at = wp_buffer_room(w->out, length + 4); /* ,"key": */
    if (at) {
        *at = ',';
        at += comma;
        at[0] = '"';
        memcpy(at + 1, key, length);
        at[length + 1] = '"';
        at[length + 2] = ':';
        wp_buffer_commit(w->out, length + 3 + comma);
    }
    w->keyed = true;
}

void wp_write_number(wp_writer *w, double value)
{
    bool comma = wp_write_comma_due(w);
    char *at = wp_buffer_room(w->out, 33); /* a comma and wp_format_number's 32 */
    if (at) {
        *at = ',';
        int length = wp_format_number(value, at + comma);
        wp_buffer_commit(w->out, (size_t)length + comma);
    }
}

void wp_write_string(wp_writer *w, const char *text)
{
    wp_write_separate(w);
    wp_buffer_string(w->out, text);
}

void wp_write_bool(wp_writer *w, bool value)
{
    bool comma = wp_write_comma_due(w);
    if (value)
        wp_buffer_append(w->out, &",true"[!comma], 4 + comma);
    else
        wp_buffer_append(w->out, &",false"[!comma], 5 + comma);
}

void wp_write_null(wp_writer *w)
{
    bool comma = wp_write_comma_due(w);
    wp_buffer_append(w->out, &",null"[!comma], 4 + comma);
}

void wp_write_raw(wp_writer *w, const char *text, size_t length)
{
    if (length == 0)
        return;
    wp_write_separate(w);
    wp_buffer_append(w->out, text, length);
}

void wp_write_numbers(wp_writer *w, const double *v, size_t n)
{
    wp_write_array(w);
    for (size_t i = 0; i < n; i++)
        wp_write_number(w, v[i]);
    wp_write_array_end(w);
}

char *wp_write_string_room(wp_writer *w, size_t n)
{
    wp_write_separate(w);
    wp_buffer *b = w->out;
    /* Room for the quotes and the characters, so that the closing quote's
     * append does not move the text the caller is about to write. */
    wp_buffer_reserve(b, b->length + n + 3);
    if (b->failed || b->capacity < b->length + n + 3) {
        b->failed = true;
        return NULL;
    }
    b->data[b->length++] = '"';
    char *room = b->data + b->length;
    b->length += n;
    b->data[b->length++] = '"';
    b->data[b->length] = 0;
    return room;
}
