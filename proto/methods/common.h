/* common.h -- what several families of methods share: the names of the
 * sets, the wrenches and sets a request asks about, the readers of a set
 * and a finger, a stream's zeroed state with its fixture, and small
 * writers.  Each is used by two families or more; a family's own readers
 * and writers stay in its file. */
#ifndef WP_METHODS_COMMON_H
#define WP_METHODS_COMMON_H

#include "wp_method.h"

/* "goal", "strong", "both": wr_set's values, as the protocol spells them. */
extern const char *const wp_set_names[3];

/* The wrenches and sets a request asks about (wrench.classify,
 * friction.sweep), and how classify answers them. */
typedef struct wp_classify_request {
    wr_set sets[3];
    int set_count;
    bool lp;
    double tolerance;
    size_t wrench_count;
    double (*wrenches)[3];
    unsigned fields;   /* 1 << FIELD_*; 0: not given, every field in rows */
} wp_classify_request;

/* params.sets: distinct names of wp_set_names (default goal and strong). */
bool wp_read_sets(const cJSON *params, wp_classify_request *r, wp_error *error);
/* params.wrenches: each read into r->wrenches (or taken from `prepared`,
 * which may be NULL), no more than --max-wrenches of them. */
bool wp_read_wrenches(const wp_limits *limits, const cJSON *params, const wr_fixture *fixture,
                      wp_prepared *prepared, wp_classify_request *r, wp_error *error);
/* path.set: one of goal, strong, both (default goal). */
bool wp_read_set_at(const cJSON *object, const char *path, wr_set *set, wp_error *error);
/* path.finger_friction and path.finger_radius: not negative (default 0). */
bool wp_read_finger(const cJSON *object, const char *path, wr_finger *finger, wp_error *error);

/* The monotonic clock, in seconds. */
double wp_now_s(void);
/* params.deadline_s (docs/PROTOCOL.md, Bounded work): seconds above 0, at
 * most 1e9.  *deadline is the monotonic second it ends (wp_now_s), 0 when
 * not given.  False with the error at params.deadline_s. */
bool wp_read_deadline(const cJSON *params, double *deadline, wp_error *error);

/* The call's fixture (held until the stream's free) and a zeroed state of
 * `size` bytes; NULL with the error set when either fails. */
void *wp_stream_with_fixture(wp_call *call, size_t size, wp_fixture_use **use);

/* Where an edge of the push boundary is, as members of the object being
 * written: "loop" and "segment" on an outline, "edge" otherwise. */
void wp_write_edge_place(wp_writer *out, const wr_fixture *f, int edge);

/* A robust outside's witness, as members of the object being written
 * (nothing without one): "perturbation", the contact points of a fixture
 * of the tolerance's set on which the wrench is outside, and
 * "perturbation_normals", their normals (docs/PROTOCOL.md, "Tolerance"). */
void wp_write_perturbation(wp_writer *out, const wr_fixture *f, const wr_robust_answer *r);

/* path.push_on of `object` for a body or fixture `shape` (fixture.design,
 * push.regions; docs/PROTOCOL.md, push_on): absent or "all" gives *mask
 * NULL (every loop); "outer" loop 0; a list of loop numbers those.  *mask
 * is malloc'd (the caller frees it), *count entries, one per loop of the
 * shape (1 for a polygon or a circle).  False with `error` at path.push_on
 * or path.push_on[i]. */
bool wp_read_push_on(const cJSON *object, const char *path, const wr_fixture *shape, bool **mask,
                     size_t *count, wp_error *error);

#endif
