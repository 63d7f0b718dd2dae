/* wd_peer.c -- the allow lists against the peer's credentials. */
/* SO_PEERCRED, SO_PEERGROUPS and struct ucred are Linux's. */
#define _GNU_SOURCE
#include "wd_peer.h"
#include "wd_log.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <sys/types.h>

static bool gid_listed(const wd_config *config, gid_t gid)
{
    for (int i = 0; i < config->allow_gid_count; i++)
        if (config->allow_gids[i] == gid)
            return true;
    return false;
}

/* Is any of the peer's supplementary groups listed?  A user may be in up to
 * NGROUPS_MAX (65536) of them, so no fixed array: ask with no room, which
 * the kernel answers ERANGE with the length the list needs, then read it
 * into that much.  The list is fixed when the peer connected, but should the
 * second read still want more, it is asked again. */
static bool supplementary_group_listed(const wd_config *config, int fd)
{
    gid_t *groups = NULL;
    socklen_t length = 0, capacity = 0;
    while (getsockopt(fd, SOL_SOCKET, SO_PEERGROUPS, groups, &length) != 0) {
        if (errno != ERANGE || length <= capacity) {
            /* ENOPROTOOPT (a kernel before 4.13) or worse: the primary group
             * was all there was to go by. */
            wd_log(WD_LOG_WARN, "cannot read a peer's groups (SO_PEERGROUPS): %s",
                   strerror(errno));
            free(groups);
            return false;
        }
        gid_t *grown = realloc(groups, length);
        if (!grown) {
            wd_log(WD_LOG_ERROR, "out of memory reading a peer's %zu groups",
                   (size_t)length / sizeof *groups);
            free(groups);
            return false;
        }
        groups = grown;
        capacity = length;
    }
    bool listed = false;
    for (size_t i = 0; !listed && i < length / sizeof *groups; i++)
        listed = gid_listed(config, groups[i]);
    free(groups);
    return listed;
}

bool wd_peer_allowed(const wd_config *config, int fd, char *who, size_t who_size)
{
    if (wd_peer_anyone(config))
        return true;
    struct ucred credentials;
    socklen_t length = sizeof credentials;
    if (getsockopt(fd, SOL_SOCKET, SO_PEERCRED, &credentials, &length) != 0) {
        snprintf(who, who_size, "a peer of unknown identity");
        return false;
    }
    snprintf(who, who_size, "uid %u (gid %u)", (unsigned)credentials.uid,
             (unsigned)credentials.gid);
    for (int i = 0; i < config->allow_uid_count; i++)
        if (config->allow_uids[i] == credentials.uid)
            return true;
    if (config->allow_gid_count == 0)
        return false;
    return gid_listed(config, credentials.gid) || supplementary_group_listed(config, fd);
}

bool wd_peer_anyone(const wd_config *config)
{
    return config->allow_any_uid || config->allow_any_gid ||
           (config->allow_uid_count == 0 && config->allow_gid_count == 0);
}

/* One list, "uids 0, 1000" or "no uid", appended at `at`. */
static size_t describe_list(char *text, size_t size, size_t at, const char *what,
                            const unsigned *ids, int count)
{
    if (at >= size)
        return at;
    if (count == 0)
        return at + (size_t)snprintf(text + at, size - at, "no %s", what);
    at += (size_t)snprintf(text + at, size - at, "%ss", what);
    for (int i = 0; i < count && at < size; i++)
        at += (size_t)snprintf(text + at, size - at, "%s%u", i ? ", " : " ", ids[i]);
    return at;
}

void wd_peer_describe(const wd_config *config, char *text, size_t size)
{
    if (wd_peer_anyone(config)) {
        snprintf(text, size, "anyone who can open the socket%s",
                 config->allow_any_uid || config->allow_any_gid ? " ('any' given)" : "");
        return;
    }
    size_t at = describe_list(text, size, 0, "uid", config->allow_uids, config->allow_uid_count);
    if (at < size)
        at += (size_t)snprintf(text + at, size - at, "; ");
    describe_list(text, size, at, "gid", config->allow_gids, config->allow_gid_count);
}

bool wd_peer_uid(int fd, unsigned *uid)
{
    struct ucred credentials;
    socklen_t length = sizeof credentials;
    if (getsockopt(fd, SOL_SOCKET, SO_PEERCRED, &credentials, &length) != 0)
        return false;
    *uid = (unsigned)credentials.uid;
    return true;
}
