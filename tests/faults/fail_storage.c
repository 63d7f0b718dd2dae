/* fail_storage.c -- an LD_PRELOAD library for fault tests: every attempt to
 * write under one directory fails as a full or read-only disk would.
 *
 *   FAIL_STORAGE_DIR=/path     the directory (and everything under it)
 *   FAIL_STORAGE_ERRNO=ENOSPC  or EROFS (default ENOSPC)
 *
 * Opening for writing, creating, renaming and unlinking there fail with
 * that errno; reading works, so what is stored can still be loaded.  Root
 * ignores permission bits, so a chmod cannot make such a directory. */
#define _GNU_SOURCE
#include <dlfcn.h>
#include <errno.h>
#include <fcntl.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

static int failing(const char *path)
{
    const char *dir = getenv("FAIL_STORAGE_DIR");
    if (!dir || !*dir || !path)
        return 0;
    size_t n = strlen(dir);
    if (strncmp(path, dir, n) != 0 || (path[n] != '/' && path[n] != 0))
        return 0;
    const char *name = getenv("FAIL_STORAGE_ERRNO");
    errno = name && strcmp(name, "EROFS") == 0 ? EROFS : ENOSPC;
    return 1;
}

static int writes(int flags) { return (flags & (O_WRONLY | O_RDWR | O_CREAT | O_TRUNC)) != 0; }

int open(const char *path, int flags, ...)
{
    static int (*real)(const char *, int, ...);
    if (!real)
        real = (int (*)(const char *, int, ...))dlsym(RTLD_NEXT, "open");
    if (writes(flags) && failing(path))
        return -1;
    va_list args;
    va_start(args, flags);
    int mode = (flags & O_CREAT) ? va_arg(args, int) : 0;
    va_end(args);
    return real(path, flags, mode);
}

int openat(int dirfd, const char *path, int flags, ...)
{
    static int (*real)(int, const char *, int, ...);
    if (!real)
        real = (int (*)(int, const char *, int, ...))dlsym(RTLD_NEXT, "openat");
    if (writes(flags) && failing(path))
        return -1;
    va_list args;
    va_start(args, flags);
    int mode = (flags & O_CREAT) ? va_arg(args, int) : 0;
    va_end(args);
    return real(dirfd, path, flags, mode);
}

int rename(const char *from, const char *to)
{
    static int (*real)(const char *, const char *);
    if (!real)
        real = (int (*)(const char *, const char *))dlsym(RTLD_NEXT, "rename");
    if (failing(from) || failing(to))
        return -1;
    return real(from, to);
}

int unlink(const char *path)
{
    static int (*real)(const char *);
    if (!real)
        real = (int (*)(const char *))dlsym(RTLD_NEXT, "unlink");
    if (failing(path))
        return -1;
    return real(path);
}
