/* wd_file.c -- the daemon's file helpers (wd_file.h). */
#include "wd_file.h"

#include <errno.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

char *wd_file_read(const char *path, size_t limit, size_t *length_out, bool *more)
{
    if (length_out)
        *length_out = 0;
    if (more)
        *more = false;
    FILE *file = fopen(path, "rb");
    if (!file)
        return NULL;
    errno = 0; /* what a failed read leaves is its own */
    char *text = NULL;
    size_t length = 0, capacity = 0; /* capacity: bytes of text, its NUL aside */
    bool beyond = false;
    for (;;) {
        if (length == capacity) {
            if (capacity == limit) {
                /* Full: one byte more says whether the file goes on. */
                beyond = fgetc(file) != EOF;
                break;
            }
            size_t grown_capacity = capacity ? 2 * capacity : 8192;
            if (grown_capacity > limit || grown_capacity < capacity)
                grown_capacity = limit;
            char *grown = grown_capacity < SIZE_MAX ? realloc(text, grown_capacity + 1) : NULL;
            if (!grown) {
                free(text);
                fclose(file);
                errno = ENOMEM;
                return NULL;
            }
            text = grown;
            capacity = grown_capacity;
        }
        size_t n = fread(text + length, 1, capacity - length, file);
        length += n;
        if (length < capacity)
            break; /* end of file, or an error */
    }
    if (ferror(file)) {
        int saved = errno ? errno : EIO;
        free(text);
        fclose(file);
        errno = saved;
        return NULL;
    }
    fclose(file);
    if (!text) { /* limit 0 */
        text = malloc(1);
        if (!text) {
            errno = ENOMEM;
            return NULL;
        }
    }
    text[length] = 0;
    if (length_out)
        *length_out = length;
    if (more)
        *more = beyond;
    return text;
}

bool wd_file_make_directories(const char *path, mode_t mode)
{
    char partial[4096];
    snprintf(partial, sizeof partial, "%s", path);
    for (char *p = partial + 1; *p; p++)
        if (*p == '/') {
            *p = 0;
            if (mkdir(partial, mode) != 0 && errno != EEXIST)
                return false;
            *p = '/';
        }
    return mkdir(partial, mode) == 0 || errno == EEXIST;
}

bool wd_file_make_parent_directories(const char *path, mode_t mode)
{
    char parent[4096];
    snprintf(parent, sizeof parent, "%s", path);
    char *slash = strrchr(parent, '/');
    if (!slash || slash == parent)
        return true;
    *slash = 0;
    return wd_file_make_directories(parent, mode);
}
