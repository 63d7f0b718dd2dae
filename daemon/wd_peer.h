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

/* The peer's user id (SO_PEERCRED); false when the kernel does not say. */
bool wd_peer_uid(int fd, unsigned *uid);

/* Does the configuration admit anyone who can open the socket (no list,
 * or "any")? */
bool wd_peer_anyone(const wd_config *config);

/* The effective allow lists, for the log: "anyone ..." or "uids 0, 1000;
 * no gid". */
void wd_peer_describe(const wd_config *config, char *text, size_t size);

#endif
