/* wc_print.h -- how wrenchctl prints: JSON, rows of tables, and a blocking
 * verdict in words.  The words of the explanations are those of the
 * Python client's table (clients/python/wrenchd.py, _EXPLAIN_WORDS), from
 * which the build generates wc_explain.h: one source for every client. */
#ifndef WC_PRINT_H
#define WC_PRINT_H

#include <cjson/cJSON.h>
#include <stddef.h>

/* The value, indented, and a newline. */
void wc_print_json(const cJSON *value);

/* Rows [a, b, c] under a label ("none" when there is none); a row whose
 * flag (may be NULL) is true ends with flag_text. */
void wc_print_rows(const char *label, const cJSON *rows, const cJSON *flags,
                   const char *flag_text);

/* With --friction, the line above a table saying the friction every fixel
 * was given, [low, high] (or low when high == low), and that the answers
 * below are robust: each holds for every friction in the interval. */
void wc_print_friction(double low, double high);

/* The units a fixture names (its "units" member, docs/PROTOCOL.md), as one
 * line above a table: "units: lengths in mm, forces in N (the fixture's)".
 * Nothing for a fixture without units (its tables are as they always
 * were) or for a stored one given by id. */
void wc_print_units(const cJSON *fixture);

/* The strings of a list, each after a space, and a newline. */
void wc_print_strings(const cJSON *list);

/* A wrench as written: "(fx, fy, tau)" or "(fx, fy) at (x, y)". */
void wc_describe_wrench(const cJSON *w, char *out, size_t size);

/* The transitions a goal blocking string allows, from each of its contact
 * `states` (a JSON array of strings), in words. */
void wc_explain_goal(const char *blocking, const cJSON *states, char *out, size_t size);

/* The motion a strong-set blocking mode allows, in words. */
void wc_explain_strong(const char *blocking, char *out, size_t size);

/* ---- coordinates to the drawing's precision ---------------------------------- */

/* The decimals of the drawing (WC_MAX_DECIMALS at most): the median of the
 * decimals its coordinates (a body's "shape": its vertices, centre, radius;
 * not bulges) have in their shortest exact form, and never fewer than show
 * 1/10,000 of the shape's size.  What
 * tables print points to (wrenchctl(1), push); -1 for no shape (a
 * stored fixture not at hand): then %g. */
#define WC_MAX_DECIMALS 6
int wc_drawing_decimals(const cJSON *shape);
/* "(x, y)" rounded to `decimals` places, trailing zeros dropped ("(120,
 * 52.5)"; -1: 6 significant digits). */
void wc_point_text(const cJSON *point, int decimals, char *out, size_t size);

#endif
