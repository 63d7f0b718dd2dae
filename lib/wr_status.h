/* wr_status.h -- the one vocabulary libwrench reports outcomes in.
 *
 * A function that can fail returns a wr_status; what it computes comes back
 * through pointer arguments, which are written only as its documentation
 * says (on failure an out-pointer of a constructor is set to NULL, and a
 * result structure is left empty, safe to release).  Detail for a person,
 * when there is more to say than the status (which field of a fixture spec,
 * which letter of a constraint string), comes in a wr_error.
 *
 * Constructors follow the same rule: wr_status x_new(..., T **out), so that
 * every constructor can say why it failed (bad input or memory) in the same
 * words, and a NULL never has to be decoded.
 *
 * What does not return a wr_status, and why:
 *   - pure queries, which cannot fail on valid objects: counts, sizes and
 *     lengths (wr_analysis_cone_count, wr_analysis_bytes, wr_perimeter,
 *     wr_region_length), distances and scalings (wr_cone_signed_distance,
 *     wr_fixture_unit_wrench, wr_fixture_scale_wrench), predicates
 *     (wr_letter_below, wr_constraint_below, wr_analysis_pinned,
 *     wr_stop_requested) and the accessors of wr_analysis;
 *   - formatting into caller buffers of a fixed, sufficient size
 *     (wr_constraint_format, wr_state_format) and computations into caller
 *     arrays (wr_cone_witness, wr_newton_euler_wrench, wr_boundary_point,
 *     wr_push_wrench, wr_fixture_force_wrench, ...);
 *   - releasing (*_free, *_release), which accepts NULL or an empty object
 *     and cannot fail, and the test hook wr_lp_env_inject_failure.
 * A status there would be WR_OK on every path: noise at every call. */
#ifndef WR_STATUS_H
#define WR_STATUS_H

#ifdef __cplusplus
extern "C" {
#endif

typedef enum wr_status {
    /* Done; the outputs are written. */
    WR_OK = 0,
    /* Bad input: an argument outside the function's domain (a wrench that
     * is not finite, a negative tolerance or friction coefficient, a fixture
     * spec or constraint string that does not validate, a fixel count out of
     * range, a bias whose margin is beyond the largest double).  The
     * function's documentation says which; a wr_error, where the function
     * takes one, says what exactly. */
    WR_INVALID,
    /* Out of memory; nothing was kept. */
    WR_NO_MEMORY,
    /* The LP solver (GLPK) failed: the answer is unknown.  The thread's
     * solver state is rebuilt, so a later call may succeed (wr_lp.h). */
    WR_LP_FAILED,
    /* The caller's wr_stop asked to stop; nothing is returned. */
    WR_STOPPED,
    /* The question needs the part's outline and the fixture has none
     * (WR_SHAPE_NONE): push regions, say. */
    WR_NO_SHAPE
} wr_status;

/* An error: which field, and why.  Both NUL-terminated, possibly truncated. */
typedef struct wr_error {
    char field[96];   /* "fixels[2].normal"; empty when no field is to blame */
    char reason[192]; /* a sentence for a person */
} wr_error;

/* A short English phrase for the status ("out of memory"), constant and
 * never NULL; "unknown status" for a value outside the enum. */
const char *wr_strerror(wr_status status);

#ifdef __cplusplus
}
#endif

#endif
