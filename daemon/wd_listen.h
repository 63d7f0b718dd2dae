/* wd_listen.h -- the daemon's listening socket: a Unix stream socket bound
 * at a path (when systemd does not pass one, wd_systemd.h). */
#ifndef WD_LISTEN_H
#define WD_LISTEN_H

#include <stddef.h>
#include <sys/types.h>

/* The socket file a daemon made: its device and inode, taken just after
 * bind.  Another daemon may later replace the file at the path (after this
 * one stopped answering, say); only the file this one made is its to
 * remove. */
typedef struct wd_listen_file {
    dev_t device;
    ino_t inode;
    int made;       /* 0: none made (systemd's socket, or bind failed) */
} wd_listen_file;

/* Bind and listen on `path`, mode 0660, creating the directories above it
 * (0755): refuse when a live daemon answers there, replace a stale socket
 * file.  Returns the fd (non-blocking, close-on-exec) and fills `file`, or
 * -1 with `why`. */
int wd_listen_open(const char *path, wd_listen_file *file, char *why, size_t why_size);

/* Remove the socket file at `path` if it is still the one `file` says this
 * daemon made. */
void wd_listen_remove(const char *path, const wd_listen_file *file);

#endif
