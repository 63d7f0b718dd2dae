/* wd_systemd.h -- what wrenchd takes from systemd, without libsystemd: a
 * listening socket passed by socket activation (sd_listen_fds(3)) and state
 * notifications (sd_notify(3)).  Both protocols are a few lines each. */
#ifndef WD_SYSTEMD_H
#define WD_SYSTEMD_H

#include <stddef.h>

/* The socket systemd passed (LISTEN_PID is us, LISTEN_FDS = 1), checked to be
 * a listening Unix stream socket; the variables are then unset.  Returns the
 * fd, -1 when nothing was passed, -2 (with `why`) when what was passed is
 * unusable. */
int wd_systemd_listen_fd(char *why, size_t why_size);

/* Send "READY=1", "STATUS=...", "STOPPING=1" ... to NOTIFY_SOCKET; nothing
 * without one.  Returns 0, or -1 if the send failed. */
int wd_systemd_notify(const char *state);

#endif
