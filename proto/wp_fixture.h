/* wp_fixture.h -- fixtures and wrenches as JSON (docs/PROTOCOL.md). */
#ifndef WP_FIXTURE_H
#define WP_FIXTURE_H

#include "wp_json.h"
#include "wrench.h"

#ifdef __cplusplus
extern "C" {
#endif

#define WP_ID_LENGTH 32 /* hex digits of a fixture id */
/* Most bytes (UTF-8) of a fixture's name: a name is a label for people and
 * listings; without a bound, names alone could fill the store's memory
 * and a listing's answer. */
#define WP_NAME_MAX 1024

/* A fixture read from JSON: validated, with its content id and canonical
 * text.  Owns everything it points to. */
typedef struct wp_fixture_doc {
    char id[WP_ID_LENGTH + 1];  /* SHA-256 of the canonical text without name */
    char *name;                 /* "" when not given */
    char *canonical;            /* canonical text of the explicit form, with the
                                   name when one was given: what is stored */
    wr_fixture *fixture;
    char written[WP_ID_LENGTH + 1]; /* inline: the key of the text as written
                                       (wp_fixture_written_key), "" unknown */
    const char *text;               /* inline: the object's text as written, */
    size_t text_length;             /* borrowed for the adoption, or NULL
                                       (wp_host.h, fixture_use_text) */
} wp_fixture_doc;

/* The explicit form of a fixture (docs/PROTOCOL.md, "Fixture id"): the
 * validated fixture with every default written out -- mass, inertia and com
 * of the body, the shape as given, each fixel's at, unit normal and own
 * friction {static, kinetic}; no top-level friction.  Its canonical text
 * (keys sorted, numbers by wp_format_number) reads back to the same fixture
 * and the same text, so any two spellings of one fixture share an id, and
 * putting what fixture.get returns gives the id back. */

/* Read a fixture object at `path` ("params.fixture").  Unknown fields, wrong
 * types, non-finite numbers and everything wr_fixture_new refuses are
 * -32602 errors naming the field.  Returns false on error, with nothing
 * allocated. */
bool wp_fixture_read(const cJSON *json, const char *path, wp_fixture_doc *out, wp_error *error);
void wp_fixture_doc_release(wp_fixture_doc *doc);
/* The body at path.body of `params` alone (fixture.design): read as a
 * fixture's body, a shape required, into *body (wr_fixture_body_new), with
 * the units at path.units (optional, as a fixture's "units").  False on
 * error, with nothing allocated. */
bool wp_body_read(const cJSON *params, const char *path, wr_fixture **body, wp_error *error);
/* A fixture's "supports" at `path` (present; docs/PROTOCOL.md, Supports),
 * for the validated `fixture` (a body too): read, then checked and kept by
 * wr_fixture_set_supports, its faults at path.field. */
bool wp_supports_read(const cJSON *json, const char *path, wr_fixture *fixture,
                      wp_error *error);
/* Friction at `path` (present): a number (static), an interval [lo, hi]
 * (static) or a fixture's {"static", "kinetic"}, checked. */
bool wp_friction_read(const cJSON *json, const char *path, wr_friction_spec *out,
                      wp_error *error);

/* The id a fixture had before ids hashed the explicit form: the canonical
 * text of the JSON as written, without its name.  Only for recognising
 * files stored under such ids (the daemon re-keys them).  False out of
 * memory. */
bool wp_fixture_legacy_id(const cJSON *json, char id[WP_ID_LENGTH + 1]);
/* The key of a fixture object as written, name and all, before anything
 * is validated: its canonical digest (wp_canonical_digest).  Spellings with
 * one digest have one canonical text, the same values, so they validate to
 * the same fixture: the daemon keeps a validated inline fixture under this key too
 * (wp_host.h, fixture_use_written) and a request repeating it skips
 * wp_fixture_read.  False out of memory. */
bool wp_fixture_written_key(const cJSON *json, char key[WP_ID_LENGTH + 1]);
/* Move: `to` takes what `from` owned; `from` is left empty. */
void wp_fixture_doc_move(wp_fixture_doc *to, wp_fixture_doc *from);

/* Is `text` shaped like a fixture id (32 lowercase hex digits)? */
bool wp_fixture_id_valid(const char *text);

/* A wrench at `path`: [f_x, f_y, tau], or {"force": [f_x, f_y], "at": [x, y]}
 * whose torque about the fixture's centre of mass is (at - com) x force. */
bool wp_wrench_read(const cJSON *json, const char *path, const wr_fixture *fixture,
                    double wrench[3], wp_error *error);

/* A geometric tolerance at `path`: {"position": T, "angle"?: A}; NULL
 * json leaves out->given false.  Its shape only: its values are checked
 * against a fixture by wr_fixture_set_tolerance. */
bool wp_tolerance_read(const cJSON *json, const char *path, wr_tolerance *out,
                       wp_error *error);

#ifdef __cplusplus
}
#endif

#endif
