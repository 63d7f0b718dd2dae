/* wrenchclient.h -- libwrenchclient: a small blocking client of wrenchd for
 * cell controllers.
 *
 * One wrc_client is one connection to the daemon's Unix socket.  Calls block
 * until the answer arrives or the client's timeout passes.  After a broken
 * connection or a timeout the connection is closed, and the next call opens
 * it again (once) before giving up.
 *
 * Memory: wrc_connect allocates the client and its buffers; wrc_classify
 * and wrc_friction_sweep then allocate nothing, whatever they are asked.
 * wrc_call allocates its answer.
 *
 * Threads: a client belongs to one thread at a time (calls on one client
 * must not overlap); different clients are independent.  Nothing is global.
 *
 * Errors: every function that can fail returns WRC_OK or one of the negative
 * codes below; wrc_strerror names it, wrc_last_error says more. */
#ifndef WRENCHCLIENT_H
#define WRENCHCLIENT_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

enum {
    WRC_OK = 0,
    WRC_ECONNECT = -1, /* cannot connect: no daemon on the socket, or no permission */
    WRC_ETIMEOUT = -2, /* no answer within the timeout; the connection was closed */
    WRC_EIO = -3,      /* the connection broke; it was closed */
    WRC_EPROTO = -4,   /* the daemon answered something the protocol does not allow */
    WRC_ESERVER = -5,  /* the daemon answered with an error: see wrc_server_error */
    WRC_ETOOBIG = -6,  /* the request or answer does not fit the client's buffer */
    WRC_EINVAL = -7,   /* an argument is invalid (NULL, not finite, too long) */
    WRC_ENOMEM = -8    /* out of memory */
};

typedef struct wrc_client wrc_client;

/* Connect to the daemon at `socket_path`.  `timeout_ms` bounds connecting
 * and every later call (0: wait forever).  `buffer_bytes` sizes the
 * request and answer buffers of wrc_classify (0: 64 KiB).  Returns NULL
 * with *error set when it cannot connect; after WRC_ECONNECT, errno says
 * why (EACCES, ENOENT, ECONNREFUSED, ETIMEDOUT when the daemon does not
 * accept in time, ...), and wrc_connect_reason puts that in words. */
wrc_client *wrc_connect(const char *socket_path, int timeout_ms, size_t buffer_bytes,
                        int *error);

/* Why connecting to `socket_path` failed with errno `os_error`, naming the
 * cause: "permission denied on PATH", "no socket at PATH: is wrenchd
 * running?", "connection refused at PATH: a stale socket, wrenchd is not
 * running", else PATH and strerror.  Into `out` (`size` bytes, cut to fit).
 * wrc_last_error gives the same sentence when a call reconnects. */
void wrc_connect_reason(const char *socket_path, int os_error, char *out, size_t size);

/* Close the connection and free the client (NULL is allowed). */
void wrc_close(wrc_client *client);

typedef enum wrc_verdict {
    WRC_INSIDE = 0,   /* margin > tolerance */
    WRC_BOUNDARY = 1, /* floating point cannot tell */
    WRC_OUTSIDE = 2   /* margin < -tolerance */
} wrc_verdict;

typedef struct wrc_answer {
    wrc_verdict verdict;
    double margin;        /* in [-1, 1]; docs/MODEL.md section 5 */
    char blocking[16];    /* the blocking string ("ms", "ll", "nn+"), "" when inside */
    /* A fixture stored with a tolerance (docs/PROTOCOL.md, "Tolerance"),
     * the answer outside: the contact points of a fixture of its set on
     * which the wrench is outside, one per fixel (perturbation_count of
     * them); 0 otherwise. */
    int perturbation_count;
    double perturbation[8][2];
} wrc_answer;

/* Classify one wrench (f_x, f_y, tau) for the stored fixture `fixture_id`
 * and one set, "goal", "strong" or "both".  Allocates nothing.
 * Returns WRC_OK, or an error code (WRC_ESERVER for an unknown fixture). */
int wrc_classify(wrc_client *client, const char *fixture_id, const double wrench[3],
                 const char *set, wrc_answer *answer);

/* friction.sweep, for a stored fixture: mu_s = mu and mu_k = kinetic_ratio
 * mu at every fixel (the fixture's own friction ignored), mu over a range.
 * `kind` says what is swept:
 *   "push"     the push region of `set` (a finger as in push.regions:
 *              finger_friction, finger_radius, 0 for none);
 *   "gravity"  the gravity arcs of `set`;
 *   "wrench"   `wrench` (f_x, f_y, tau) against `set`.
 * range {0, 0} and kinetic_ratio 0 ask for the daemon's defaults ([0, 2]
 * and 1). */
typedef struct wrc_sweep_request {
    const char *kind;       /* "push", "gravity" or "wrench" */
    const char *set;        /* "goal", "strong" or "both" */
    double wrench[3];       /* kind "wrench" */
    double range[2];        /* 0 <= range[0] < range[1]; {0, 0}: the default */
    double kinetic_ratio;   /* in (0, 1]; 0: the default */
    double finger_friction; /* kind "push" */
    double finger_radius;   /* kind "push" */
} wrc_sweep_request;

#define WRC_SWEEP_INTERVALS 16

typedef struct wrc_sweep {
    /* The mu intervals where the region is not empty (for a wrench: where
     * it is inside the set), in order.  interval_count may exceed
     * WRC_SWEEP_INTERVALS: the first ones are kept. */
    int interval_count;
    double intervals[WRC_SWEEP_INTERVALS][2];
    /* push and gravity: the mu above which the region is empty (the bottom
     * of the range when it is empty throughout); NAN when it is not empty
     * at the top of the range, and for a wrench. */
    double critical;
} wrc_sweep;

/* One friction.sweep; allocates nothing.  The answer's curve (the region's
 * size at many mu, which this leaves out) must fit the client's buffer
 * (buffer_bytes of wrc_connect; WRC_ETOOBIG otherwise): for the curve
 * itself, send the request with wrc_call.  Returns WRC_OK, or an error code
 * (WRC_ESERVER for an unknown fixture, or a daemon without friction.sweep:
 * -32601). */
int wrc_friction_sweep(wrc_client *client, const char *fixture_id,
                       const wrc_sweep_request *request, wrc_sweep *sweep);

/* fixture.locating, for a stored fixture: each locator off by up to
 * +-tolerance along its normal (tolerance_count 1: one number for every
 * fixel; else one per fixel), sigma = tolerance / sigma_ratio (0: the
 * daemon's default, 3).  Each feature's `at` is read, the rest written.
 * Lengths in the fixture's unit, angles in radians (the ellipse's in
 * degrees).  Allocates nothing; the answer must fit the client's buffer
 * (WRC_ETOOBIG otherwise).  Returns WRC_OK, or an error code (WRC_ESERVER
 * for a refusal: wrc_server_error names the field). */
#define WRC_LOCATE_FEATURES 256

typedef struct wrc_locate_feature {
    double at[2];
    double linear;          /* the worst displacement's length, linear model */
    double exact;           /* ... the exact pose's */
    double axes[2];         /* the 99.73 % ellipse's semi-axes, major first */
    double angle_deg;       /* its major axis from +x */
} wrc_locate_feature;

typedef struct wrc_locating {
    int deterministic;      /* 0: the rest but twist is not set */
    double twist[3];        /* not deterministic: the motion left free (vx, vy, w) */
    double condition;
    double pose_linear[3];  /* worst |dx|, |dy|, |dtheta| over the tolerance box */
    double pose_exact[3];
} wrc_locating;

int wrc_locating_get(wrc_client *client, const char *fixture_id, const double *tolerance,
                     int tolerance_count, double sigma_ratio, wrc_locate_feature *features,
                     int feature_count, wrc_locating *out);
/* A load (docs/PROTOCOL.md, "Loads and cases"), in the fixture's units. */
enum { WRC_LOAD_GRAVITY, WRC_LOAD_FORCE, WRC_LOAD_WRENCH };
typedef struct wrc_load {
    int kind;                 /* WRC_LOAD_* */
    double g, direction_deg;  /* gravity: m g pulling along direction_deg */
    double force[2], at[2];   /* a force at a point of the part */
    double wrench[3];         /* f_x, f_y, tau about the centre of mass */
} wrc_load;

typedef struct wrc_force {
    /* The magnitudes that do the set's job, in order; an upper end of
     * INFINITY is none.  interval_count may exceed WRC_SWEEP_INTERVALS:
     * the first ones are kept. */
    int interval_count;
    double intervals[WRC_SWEEP_INTERVALS][2];
    double least;             /* the first interval's lower end; NAN: none */
} wrc_force;

/* force.range for a stored fixture: a push at `at` (on the outline, along
 * the inward normal there) against one case of `count` loads (1 to 100),
 * for `set`; its intervals of magnitude in the fixture's force unit.
 * Allocates nothing.  Returns WRC_OK, or an error code (WRC_ESERVER with
 * the field at fault: wrc_server_error). */
int wrc_force_range(wrc_client *client, const char *fixture_id, const double at[2],
                    const wrc_load *loads, int count, const char *set, wrc_force *force);

/* The point of the outline where the smallest push suffices (push.force's
 * "least"). */
typedef struct wrc_least_push {
    int found;                /* 0: no push does the job under the case */
    double at[2], direction[2];
    double force;             /* in the fixture's force unit */
    double lower_bound;       /* no point needs less */
    int converged;
} wrc_least_push;

/* push.force for a stored fixture against one case of `count` loads (1 to
 * 100), for `set`: the least push over the outline, for a finger of
 * `finger_radius` (0: a point) pushing on `push_on` ("outer", "all", or
 * NULL: the daemon's default, every loop).  Allocates nothing.  Returns
 * WRC_OK, or an error code (WRC_ESERVER with the field at fault). */
int wrc_push_force(wrc_client *client, const char *fixture_id, const wrc_load *loads, int count,
                   const char *set, double finger_radius, const char *push_on,
                   wrc_least_push *least);

/* friction.sweep's "force" for a stored fixture: the least push force
 * over the outline against mu (push.force's least at each sampled mu),
 * under one case of `count` loads (1 to 100).  range {0, 0} and
 * kinetic_ratio 0 ask for the daemon's defaults; finger and push_on as in
 * wrc_push_force. */
typedef struct wrc_force_sweep_request {
    const char *set;        /* "goal", "strong" or "both" */
    double range[2];        /* 0 <= range[0] < range[1]; {0, 0}: the default */
    double kinetic_ratio;   /* in (0, 1]; 0: the default */
    double finger_radius;   /* 0: a point finger */
    const char *push_on;    /* "outer", "all", or NULL: every loop */
    /* Non-zero: sweep the supports' mu_B of a fixture on a base plate
     * ("over": "supports"; set "goal", a point finger) instead of the
     * fixels' mu; the answer then has no intervals (interval_count 0), as
     * for any fixture on supports. */
    int over_supports;
} wrc_force_sweep_request;

typedef struct wrc_force_curve {
    /* The mu intervals where the push alone has a region for the set (the
     * least force is finite there whatever the loads), in order;
     * interval_count may exceed WRC_SWEEP_INTERVALS: the first are kept. */
    int interval_count;
    double intervals[WRC_SWEEP_INTERVALS][2];
    /* The samples in the answer; more than the caller's capacity: the
     * first `capacity` are kept. */
    int sample_count;
} wrc_force_curve;

/* One friction.sweep with "force": each sample's {mu, F} into curve[i]
 * (F NAN where no push does the job) and, with `at` not NULL, the point
 * where the force is least into at[i] (NAN, NAN with no push), for the
 * first `capacity` samples, increasing in mu.  Allocates nothing; the
 * answer must fit the client's buffer (WRC_ETOOBIG otherwise).  Returns
 * WRC_OK, or an error code (WRC_ESERVER with the field at fault). */
int wrc_force_sweep(wrc_client *client, const char *fixture_id, const wrc_load *loads, int count,
                    const wrc_force_sweep_request *request, double (*curve)[2], double (*at)[2],
                    int capacity, wrc_force_curve *sweep);

/* Send one JSON-RPC request (a JSON text without "\n") and return its
 * answer line, malloc'd (the caller frees it).  For notifications nothing
 * comes back: do not send them here. */
int wrc_call(wrc_client *client, const char *request, char **answer);

/* wrc_call for a request that may be preceded by notifications (fixture.design
 * with "progress": true): each notification line (NUL-terminated, without
 * its "\n") goes to `notify` as it arrives, and each renews the timeout. */
typedef void (*wrc_notify)(const char *line, void *context);
int wrc_call_notified(wrc_client *client, const char *request, char **answer, wrc_notify notify,
                      void *context);

/* After WRC_ESERVER: the JSON-RPC error code, the field it names and why.
 * The strings live until the next call on the client. */
void wrc_server_error(const wrc_client *client, int *code, const char **field,
                      const char **reason);

/* A constant text naming an error code. */
const char *wrc_strerror(int error);

/* A sentence about the client's last failure (which system call, which
 * errno); constant until the next call on the client. */
const char *wrc_last_error(const wrc_client *client);

#ifdef __cplusplus
}
#endif

#endif
