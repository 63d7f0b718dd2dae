/* wd_file.h -- the daemon's file helpers, one of each: a whole file read
 * into memory, and mkdir -p. */
#ifndef WD_FILE_H
#define WD_FILE_H

#include <stdbool.h>
#include <stddef.h>
#include <sys/types.h>

/* The file at `path`, NUL-terminated, malloc'd (the caller frees): at most
 * `limit` bytes of it; *length (when not NULL) is the bytes read, and *more
 * (when not NULL) says whether the file held more than `limit`.  NULL with
 * errno set when it cannot be opened or read, or out of memory (ENOMEM). */
char *wd_file_read(const char *path, size_t limit, size_t *length, bool *more);

/* mkdir -p: `path` and every directory above it that is missing, new ones
 * with `mode` (less the umask).  False with errno set. */
bool wd_file_make_directories(const char *path, mode_t mode);

/* mkdir -p of the directory holding `path` (nothing for a path without a
 * directory, or directly under /). */
bool wd_file_make_parent_directories(const char *path, mode_t mode);

#endif
