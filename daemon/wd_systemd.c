/* wd_systemd.c -- socket activation and sd_notify, by their protocols. */
#include "wd_systemd.h"

#include <errno.h>
#include <stdbool.h>
#include <stddef.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <sys/un.h>
#include <unistd.h>

/* sd_listen_fds(3): passed descriptors start at 3. */
#define LISTEN_FDS_START 3

int wd_systemd_listen_fd(char *why, size_t why_size)
{
    const char *pid = getenv("LISTEN_PID"), *fds = getenv("LISTEN_FDS");
    if (!pid || !fds)
        return -1;
    /* For us only: a child must not take them too. */
    bool ours = strtol(pid, NULL, 10) == (long)getpid();
    long count = strtol(fds, NULL, 10);
    unsetenv("LISTEN_PID");
    unsetenv("LISTEN_FDS");
    unsetenv("LISTEN_FDNAMES");
    if (!ours)
        return -1;
    if (count != 1) {
        snprintf(why, why_size, "systemd passed %ld sockets; wrenchd listens on exactly one", count);
        return -2;
    }
    int fd = LISTEN_FDS_START;
    int type = 0, listening = 0;
    socklen_t length = sizeof type;
    struct sockaddr_un address;
    socklen_t address_length = sizeof address;
    if (getsockopt(fd, SOL_SOCKET, SO_TYPE, &type, &length) != 0 || type != SOCK_STREAM ||
        getsockopt(fd, SOL_SOCKET, SO_ACCEPTCONN, &listening, &(socklen_t){sizeof listening}) != 0 ||
        !listening || getsockname(fd, (struct sockaddr *)&address, &address_length) != 0 ||
        address.sun_family != AF_UNIX) {
        snprintf(why, why_size, "the socket systemd passed is not a listening Unix stream socket");
        return -2;
    }
    fcntl(fd, F_SETFD, FD_CLOEXEC);
    fcntl(fd, F_SETFL, fcntl(fd, F_GETFL) | O_NONBLOCK);
    return fd;
}

int wd_systemd_notify(const char *state)
{
    const char *path = getenv("NOTIFY_SOCKET");
    if (!path || !*path)
        return 0;
    struct sockaddr_un address = {.sun_family = AF_UNIX};
    size_t length = strlen(path);
    if (length >= sizeof address.sun_path || (path[0] != '/' && path[0] != '@'))
        return -1;
    memcpy(address.sun_path, path, length);
    if (path[0] == '@')
        address.sun_path[0] = 0; /* the abstract namespace */
    int fd = socket(AF_UNIX, SOCK_DGRAM | SOCK_CLOEXEC, 0);
    if (fd < 0)
        return -1;
    socklen_t size = (socklen_t)(offsetof(struct sockaddr_un, sun_path) + length);
    ssize_t sent = sendto(fd, state, strlen(state), MSG_NOSIGNAL, (struct sockaddr *)&address, size);
    close(fd);
    return sent == (ssize_t)strlen(state) ? 0 : -1;
}
