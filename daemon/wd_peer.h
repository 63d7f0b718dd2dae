/* wd_peer.h -- who is at the other end of an accepted connection, from the
 * kernel's credentials of the peer (SO_PEERCRED, SO_PEERGROUPS), and whether
 * --allow-uid / --allow-gid admit them. */
#ifndef WD_PEER_H
#define WD_PEER_H

#include "wd_server.h"

#include <stdbool.h>
#include <stddef.h>

/* Is the peer on `fd` admitted?  Its user id, its primary group or any of
 * its supplementary groups, however many, must be listed; with neither list
 * everyone who can open the socket is.  `who` receives "uid U (gid G)" for
 * the log and the refusal. */
bool wd_peer_allowed(const wd_config *config, int fd, char *who, size_t who_size);

#endif
