/* wd_listen.c -- the daemon's listening socket (wd_listen.h). */
#include "wd_listen.h"
#include "wd_file.h"
#include "wd_log.h"

#include <errno.h>
#include <stdio.h>
#include <string.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <unistd.h>

int wd_listen_open(const char *path, wd_listen_file *file, char *why, size_t why_size)
{
    *file = (wd_listen_file){0, 0, 0};
    struct sockaddr_un address = {.sun_family = AF_UNIX};
    if (strlen(path) >= sizeof address.sun_path) {
        snprintf(why, why_size, "the socket path %s is longer than %zu bytes", path,
                 sizeof address.sun_path - 1);
        return -1;
    }
    strcpy(address.sun_path, path);
    if (!wd_file_make_parent_directories(path, 0755)) {
        snprintf(why, why_size, "cannot create the directory of %s: %s", path, strerror(errno));
        return -1;
    }
    struct stat st;
    if (lstat(path, &st) == 0) {
        if (!S_ISSOCK(st.st_mode)) {
            snprintf(why, why_size, "%s exists and is not a socket", path);
            return -1;
        }
        int probe = socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0);
        if (probe >= 0 && connect(probe, (struct sockaddr *)&address, sizeof address) == 0) {
            close(probe);
            snprintf(why, why_size, "a wrenchd is already answering on %s", path);
            return -1;
        }
        if (probe >= 0)
            close(probe);
        wd_log(WD_LOG_INFO, "replacing the stale socket %s", path);
        unlink(path);
    }
    int fd = socket(AF_UNIX, SOCK_STREAM | SOCK_NONBLOCK | SOCK_CLOEXEC, 0);
    if (fd < 0) {
        snprintf(why, why_size, "socket: %s", strerror(errno));
        return -1;
    }
    mode_t old = umask(0117);
    int bound = bind(fd, (struct sockaddr *)&address, sizeof address);
    umask(old);
    if (bound == 0 && lstat(path, &st) == 0)
        *file = (wd_listen_file){st.st_dev, st.st_ino, 1};
    if (bound != 0 || chmod(path, 0660) != 0 || listen(fd, 256) != 0) {
        snprintf(why, why_size, "cannot listen on %s: %s", path, strerror(errno));
        close(fd);
        wd_listen_remove(path, file);
        return -1;
    }
    return fd;
}

void wd_listen_remove(const char *path, const wd_listen_file *file)
{
    struct stat st;
    if (!file->made || lstat(path, &st) != 0)
        return;
    if (st.st_dev != file->device || st.st_ino != file->inode) {
        wd_log(WD_LOG_INFO, "%s is no longer the socket this daemon made: left in place", path);
        return;
    }
    unlink(path);
}
