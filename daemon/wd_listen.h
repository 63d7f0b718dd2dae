/* wd_listen.h -- the daemon's listening socket: a Unix stream socket bound
 * at a path (when systemd does not pass one, wd_systemd.h). */
#ifndef WD_LISTEN_H
#define WD_LISTEN_H

#include <stddef.h>

/* Bind and listen on `path`, mode 0660, creating the directories above it
 * (0755): refuse when a live daemon answers there, replace a stale socket
 * file.  Returns the fd (non-blocking, close-on-exec) or -1 with `why`. */
int wd_listen_open(const char *path, char *why, size_t why_size);

#endif
