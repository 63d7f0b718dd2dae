/* wp_fixture.c -- JSON to wr_fixture_spec, validation, content ids. */
#include "wp_fixture.h"
#include "wp_sha256.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const char *const FIXTURE_FIELDS[] = {"name", "body", "friction", "fixels", "units",
                                             "tolerance", "supports", NULL};
static const char *const UNITS_FIELDS[] = {"length", "force", NULL};

/* The units a fixture may name (docs/PROTOCOL.md, "Units"), each with its
 * size in SI: exact by definition (the inch is 25.4 mm, the pound-force
 * 0.45359237 kg times 9.80665 m/s^2). */
typedef struct unit_name {
    const char *name;
    double si;
} unit_name;
static const unit_name LENGTH_UNITS[] = {{"mm", 1e-3}, {"m", 1.0}, {"in", 0.0254}, {NULL, 0}};
static const unit_name FORCE_UNITS[] = {{"N", 1.0}, {"mN", 1e-3}, {"lbf", 4.4482216152605},
                                        {NULL, 0}};

/* The member `key` of a units object: one of `table`'s names. */
static bool read_unit(const cJSON *json, const char *path, const char *key,
                      const unit_name *table, double *si, wp_error *error)
{
    const char *text = NULL;
    if (!wp_member_string(json, path, key, true, &text, error))
        return false;
    for (const unit_name *unit = table; unit->name; unit++)
        if (strcmp(unit->name, text) == 0) {
            *si = unit->si;
            return true;
        }
    char field[WP_FIELD_MAX], known[64] = "";
    wp_path_key(field, path, key);
    for (const unit_name *unit = table; unit->name; unit++)
        snprintf(known + strlen(known), sizeof known - strlen(known), "%s\"%s\"",
                 unit == table ? "" : ", ", unit->name);
    wp_error_set(error, WP_INVALID_PARAMS, field, "unknown unit \"%.40s\": one of %s", text,
                 known);
    return false;
}

/* {"length": "mm" | "m" | "in", "force": "N" | "mN" | "lbf"}, both required:
 * a force's size depends on both. */
static bool read_units(const cJSON *json, const char *path, wr_units *out, wp_error *error)
{
    if (!json)
        return true; /* not given: out->given stays false */
    if (!wp_check_object(json, path, UNITS_FIELDS, error) ||
        !read_unit(json, path, "length", LENGTH_UNITS, &out->length_m, error) ||
        !read_unit(json, path, "force", FORCE_UNITS, &out->force_n, error))
        return false;
    out->given = true;
    return true;
}

/* The fixture's geometric tolerance (docs/PROTOCOL.md, "Tolerance"):
 * {"position": T, "angle"?: A}; absent, out->given stays false.  Its
 * values are checked against the fixture by apply_tolerance (the contract
 * is in wp_fixture.h). */
static const char *const TOLERANCE_FIELDS[] = {"position", "angle", NULL};

bool wp_tolerance_read(const cJSON *json, const char *path, wr_tolerance *out,
                       wp_error *error)
{
    if (!json)
        return true;
    out->angle = 0;
    if (!wp_check_object(json, path, TOLERANCE_FIELDS, error) ||
        !wp_member_number(json, path, "position", true, &out->position, NULL, error) ||
        !wp_member_number(json, path, "angle", false, &out->angle, NULL, error))
        return false;
    out->given = true;
    return true;
}

/* wr_fixture_set_tolerance, its refusal at `path`.tolerance.x. */
static bool apply_tolerance(wr_fixture *fixture, const wr_tolerance *tolerance,
                            const char *path, wp_error *error)
{
    wr_error invalid;
    if (wr_fixture_set_tolerance(fixture, tolerance, &invalid) == WR_OK)
        return true;
    wp_error_refusal(error, WR_INVALID, path, &invalid);
    return false;
}


/* The name of the unit of `table` of size `si` (one read_unit gave). */
static const char *unit_text(const unit_name *table, double si)
{
    for (const unit_name *unit = table; unit->name; unit++)
        if (unit->si == si)
            return unit->name;
    return NULL;
}
static const char *const BODY_FIELDS[] = {"mass", "inertia", "com", "shape", NULL};
static const char *const CIRCLE_FIELDS[] = {"type", "center", "radius", NULL};
static const char *const POLYGON_FIELDS[] = {"type", "vertices", NULL};
static const char *const OUTLINE_FIELDS[] = {"type", "loops", NULL};

/* What a shape read from JSON borrows into its spec: a polygon's vertices,
 * an outline's loops and their (x, y, bulge) rows.  Freed by the reader. */
typedef struct shape_storage {
    double (*vertices)[2];
    wr_loop_spec *loops;
    double (*rows)[3];
} shape_storage;

static void shape_storage_free(shape_storage *storage)
{
    free(storage->vertices);
    free(storage->loops);
    free(storage->rows);
}

/* An array at `path` of at most `limit` items; its size in *count. */
static bool read_array(const cJSON *list, const char *path, const char *what, size_t limit,
                       size_t *count, wp_error *error)
{
    if (!cJSON_IsArray(list)) {
        wp_error_set(error, WP_INVALID_PARAMS, path, "must be an array of %s, not %s", what,
                     wp_type_name(list));
        return false;
    }
    *count = (size_t)cJSON_GetArraySize(list);
    if (*count > limit) {
        wp_error_set(error, WP_INVALID_PARAMS, path, "at most %zu %s, %zu given", limit, what,
                     *count);
        return false;
    }
    return true;
}

/* {"type": "outline", "loops": [[[x, y] or [x, y, bulge], ...], ...]}: the
 * numbers here, the geometry in wr_outline_new. */
static bool read_outline(const cJSON *json, const char *path, wr_fixture_spec *spec,
                         shape_storage *storage, wp_error *error)
{
    spec->shape = WR_SHAPE_OUTLINE;
    if (!wp_check_object(json, path, OUTLINE_FIELDS, error))
        return false;
    char field[WP_FIELD_MAX];
    wp_path_key(field, path, "loops");
    const cJSON *list = cJSON_GetObjectItemCaseSensitive(json, "loops");
    if (!list) {
        wp_error_set(error, WP_INVALID_PARAMS, field, "required");
        return false;
    }
    size_t loop_count, total = 0;
    if (!read_array(list, field, "loops", WR_OUTLINE_MAX_VERTICES, &loop_count, error))
        return false;
    if (loop_count == 0) {
        wp_error_set(error, WP_INVALID_PARAMS, field, "at least one loop, the outer boundary");
        return false;
    }
    size_t i = 0;
    for (const cJSON *loop = list->child; loop; loop = loop->next, i++) {
        char item[WP_FIELD_MAX];
        wp_path_index(item, field, i);
        size_t count;
        if (!read_array(loop, item, "vertices", WR_OUTLINE_MAX_VERTICES, &count, error))
            return false;
        total += count;
        if (total > WR_OUTLINE_MAX_VERTICES) {
            wp_error_set(error, WP_INVALID_PARAMS, field,
                         "at most %d vertices in all loops, more given", WR_OUTLINE_MAX_VERTICES);
            return false;
        }
    }
    storage->loops = calloc(loop_count, sizeof *storage->loops);
    storage->rows = calloc(total ? total : 1, sizeof *storage->rows);
    if (!storage->loops || !storage->rows) {
        wp_error_set(error, WP_INTERNAL, "", "out of memory");
        return false;
    }
    size_t next = 0;
    i = 0;
    for (const cJSON *loop = list->child; loop; loop = loop->next, i++) {
        char item[WP_FIELD_MAX];
        wp_path_index(item, field, i);
        storage->loops[i].vertices = (const double (*)[3])(storage->rows + next);
        size_t j = 0;
        for (const cJSON *vertex = loop->child; vertex; vertex = vertex->next, j++, next++) {
            char at[WP_FIELD_MAX];
            wp_path_index(at, item, j);
            int size = cJSON_GetArraySize(vertex);
            if (!cJSON_IsArray(vertex) || (size != 2 && size != 3)) {
                wp_error_set(error, WP_INVALID_PARAMS, at,
                             "must be [x, y] or [x, y, bulge], not %s",
                             cJSON_IsArray(vertex) ? "an array of another length"
                                                   : wp_type_name(vertex));
                return false;
            }
            int k = 0;
            for (const cJSON *number = vertex->child; number; number = number->next, k++) {
                char component[WP_FIELD_MAX];
                wp_path_index(component, at, (size_t)k);
                if (!wp_number(number, component, &storage->rows[next][k], error))
                    return false;
            }
        }
        storage->loops[i].vertex_count = j;
    }
    spec->loop_count = loop_count;
    spec->loops = storage->loops;
    return true;
}
static const char *const FRICTION_FIELDS[] = {"static", "kinetic", NULL};
static const char *const FIXEL_FIELDS[] = {"at", "normal", "friction", NULL};

/* A coefficient: a number mu, or an interval [lo, hi] of two numbers
 * (*upper = hi, *lower = lo, *interval set).  The library checks the
 * values.  `present` NULL: required. */
static bool read_coefficient(const cJSON *json, const char *path, const char *key,
                             double *upper, bool *interval, double *lower, bool *present,
                             wp_error *error)
{
    const cJSON *value = cJSON_GetObjectItemCaseSensitive(json, key);
    if (!cJSON_IsArray(value))
        return wp_member_number(json, path, key, present == NULL, upper, present, error);
    if (present)
        *present = true;
    char field[WP_FIELD_MAX];
    wp_path_key(field, path, key);
    if (cJSON_GetArraySize(value) != 2) {
        wp_error_set(error, WP_INVALID_PARAMS, field,
                     "must be a number or an interval [lo, hi] of 2 numbers, not an array of "
                     "%d",
                     cJSON_GetArraySize(value));
        return false;
    }
    double bounds[2];
    if (!wp_vector2(value, field, bounds, error))
        return false;
    *interval = true;
    *lower = bounds[0];
    *upper = bounds[1];
    return true;
}

static bool read_friction(const cJSON *json, const char *path, wr_friction_spec *out,
                          wp_error *error)
{
    if (!json)
        return true;
    if (!wp_check_object(json, path, FRICTION_FIELDS, error))
        return false;
    out->given = true;
    return read_coefficient(json, path, "static", &out->static_mu, &out->static_interval,
                            &out->static_min, NULL, error) &&
           read_coefficient(json, path, "kinetic", &out->kinetic_mu, &out->kinetic_interval,
                            &out->kinetic_min, &out->kinetic_given, error);
}

static bool read_shape(const cJSON *json, const char *path, wr_fixture_spec *spec,
                       shape_storage *storage, wp_error *error)
{
    if (!cJSON_IsObject(json)) {
        wp_error_set(error, WP_INVALID_PARAMS, path, "must be an object, not %s",
                     wp_type_name(json));
        return false;
    }
    char field[WP_FIELD_MAX];
    wp_path_key(field, path, "type");
    const cJSON *type = cJSON_GetObjectItemCaseSensitive(json, "type");
    if (!type) {
        wp_error_set(error, WP_INVALID_PARAMS, field,
                     "required: \"circle\", \"polygon\" or \"outline\"");
        return false;
    }
    if (!cJSON_IsString(type) ||
        (strcmp(type->valuestring, "circle") != 0 && strcmp(type->valuestring, "polygon") != 0 &&
         strcmp(type->valuestring, "outline") != 0)) {
        wp_error_set(error, WP_INVALID_PARAMS, field,
                     "must be \"circle\", \"polygon\" or \"outline\"");
        return false;
    }
    if (strcmp(type->valuestring, "outline") == 0)
        return read_outline(json, path, spec, storage, error);
    if (strcmp(type->valuestring, "circle") == 0) {
        spec->shape = WR_SHAPE_CIRCLE;
        return wp_check_object(json, path, CIRCLE_FIELDS, error) &&
               wp_member_vector2(json, path, "center", true, spec->center, NULL, error) &&
               wp_member_number(json, path, "radius", true, &spec->radius, NULL, error);
    }
    spec->shape = WR_SHAPE_POLYGON;
    if (!wp_check_object(json, path, POLYGON_FIELDS, error))
        return false;
    wp_path_key(field, path, "vertices");
    const cJSON *list = cJSON_GetObjectItemCaseSensitive(json, "vertices");
    if (!list) {
        wp_error_set(error, WP_INVALID_PARAMS, field, "required");
        return false;
    }
    if (!cJSON_IsArray(list)) {
        wp_error_set(error, WP_INVALID_PARAMS, field, "must be an array of [x, y], not %s",
                     wp_type_name(list));
        return false;
    }
    size_t count = (size_t)cJSON_GetArraySize(list);
    if (count > WR_MAX_VERTICES) {
        wp_error_set(error, WP_INVALID_PARAMS, field, "at most %d vertices, %zu given",
                     WR_MAX_VERTICES, count);
        return false;
    }
    double (**vertices)[2] = &storage->vertices;
    *vertices = malloc((count ? count : 1) * sizeof **vertices);
    if (!*vertices) {
        wp_error_set(error, WP_INTERNAL, "", "out of memory");
        return false;
    }
    size_t i = 0;
    for (const cJSON *v = list->child; v; v = v->next, i++) {
        char item[WP_FIELD_MAX];
        wp_path_index(item, field, i);
        if (!wp_vector2(v, item, (*vertices)[i], error))
            return false;
    }
    spec->vertex_count = count;
    spec->vertices = (const double (*)[2]) * vertices;
    return true;
}

static bool read_body(const cJSON *json, const char *path, wr_fixture_spec *spec,
                      shape_storage *storage, wp_error *error)
{
    if (!wp_check_object(json, path, BODY_FIELDS, error) ||
        !wp_member_number(json, path, "mass", true, &spec->mass, NULL, error) ||
        !wp_member_number(json, path, "inertia", false, &spec->inertia, &spec->inertia_given,
                          error) ||
        !wp_member_vector2(json, path, "com", false, spec->com, &spec->com_given, error))
        return false;
    const cJSON *shape = cJSON_GetObjectItemCaseSensitive(json, "shape");
    if (!shape)
        return true;
    char field[WP_FIELD_MAX];
    wp_path_key(field, path, "shape");
    return read_shape(shape, field, spec, storage, error);
}

static bool read_fixels(const cJSON *json, const char *path, wr_fixel_spec **fixels,
                        size_t *count, wp_error *error)
{
    if (!cJSON_IsArray(json)) {
        wp_error_set(error, WP_INVALID_PARAMS, path, "must be an array of fixels, not %s",
                     wp_type_name(json));
        return false;
    }
    /* Any number is read (the line length bounds it); wr_fixture_new says
     * why more than WR_MAX_FIXELS are refused. */
    size_t n = (size_t)cJSON_GetArraySize(json);
    *fixels = calloc(n ? n : 1, sizeof **fixels);
    if (!*fixels) {
        wp_error_set(error, WP_INTERNAL, "", "out of memory");
        return false;
    }
    size_t i = 0;
    for (const cJSON *item = json->child; item; item = item->next, i++) {
        char field[WP_FIELD_MAX], friction[WP_FIELD_MAX];
        wp_path_index(field, path, i);
        wr_fixel_spec *fixel = &(*fixels)[i];
        if (!wp_check_object(item, field, FIXEL_FIELDS, error) ||
            !wp_member_vector2(item, field, "at", true, fixel->at, NULL, error) ||
            !wp_member_vector2(item, field, "normal", false, fixel->normal, &fixel->normal_given,
                               error))
            return false;
        wp_path_key(friction, field, "friction");
        if (!read_friction(cJSON_GetObjectItemCaseSensitive(item, "friction"), friction,
                           &fixel->friction, error))
            return false;
    }
    *count = n;
    return true;
}

/* ---- supports (a base plate under the part) ------------------------------ */

static const char *const SUPPORTS_FIELDS[] = {"points", "friction", "g", "down", NULL};
static const char *const DOWN_FIELDS[] = {"at", "force", NULL};

bool wp_supports_read(const cJSON *json, const char *path, wr_fixture *fixture,
                      wp_error *error)
{
    if (!wp_check_object(json, path, SUPPORTS_FIELDS, error))
        return false;
    double points[WR_MAX_SUPPORTS][2];
    wr_down_spec down[WR_MAX_DOWN];
    wr_support_spec spec;
    memset(&spec, 0, sizeof spec);
    char field[WP_FIELD_MAX], item_field[WP_FIELD_MAX];
    const cJSON *list = cJSON_GetObjectItemCaseSensitive(json, "points");
    wp_path_key(field, path, "points");
    if (!list) {
        wp_error_set(error, WP_INVALID_PARAMS, field, "required: the supports' points [[x, y], ...]");
        return false;
    }
    if (!read_array(list, field, "points", WR_MAX_SUPPORTS, &spec.point_count, error))
        return false;
    size_t i = 0;
    for (const cJSON *item = list->child; item; item = item->next, i++) {
        wp_path_index(item_field, field, i);
        if (!wp_vector2(item, item_field, points[i], error))
            return false;
    }
    spec.points = (const double (*)[2])points;
    wp_path_key(field, path, "friction");
    const cJSON *friction = cJSON_GetObjectItemCaseSensitive(json, "friction");
    if (!friction) {
        wp_error_set(error, WP_INVALID_PARAMS, field,
                     "required: the supports' coefficient of friction mu_B");
        return false;
    }
    if (!wp_friction_read(friction, field, &spec.friction, error))
        return false;
    if (!wp_member_number(json, path, "g", true, &spec.g, NULL, error))
        return false;
    list = cJSON_GetObjectItemCaseSensitive(json, "down");
    if (list) {
        wp_path_key(field, path, "down");
        if (!read_array(list, field, "down clamps", WR_MAX_DOWN, &spec.down_count, error))
            return false;
        i = 0;
        for (const cJSON *item = list->child; item; item = item->next, i++) {
            wp_path_index(item_field, field, i);
            if (!wp_check_object(item, item_field, DOWN_FIELDS, error) ||
                !wp_member_vector2(item, item_field, "at", true, down[i].at, NULL, error) ||
                !wp_member_number(item, item_field, "force", true, &down[i].force, NULL, error))
                return false;
        }
        spec.down = down;
    }
    wr_error invalid;
    wr_status status = wr_fixture_set_supports(fixture, &spec, &invalid);
    if (status != WR_OK) {
        wp_error_refusal(error, status, path, &invalid);
        return false;
    }
    return true;
}

static void hex_id(const char *canonical, char id[WP_ID_LENGTH + 1])
{
    wp_sha256 hash;
    unsigned char digest[32];
    wp_sha256_init(&hash);
    wp_sha256_update(&hash, canonical, strlen(canonical));
    wp_sha256_final(&hash, digest);
    for (int i = 0; i < WP_ID_LENGTH / 2; i++)
        snprintf(id + 2 * i, 3, "%02x", digest[i]);
}

/* ---- the explicit form ------------------------------------------------------
 *
 * A fixture's explicit form is what the validated wr_fixture holds, every
 * default written out: the body's mass, inertia and com (computed from the
 * shape when not given), the shape as given, and for each fixel its point,
 * its unit normal (computed when not given) and its own friction with both
 * coefficients (the fixture's friction is copied into every fixel that does
 * not override it, so the explicit form has no top-level "friction").
 * Numbers are the doubles the fixture computes with, written by
 * wp_format_number: reading the text back gives the same doubles, hence
 * the same fixture (wr_fixture.h states that invariant) and the same text. */

static void write_pair(wp_writer *w, const double v[2]) { wp_write_numbers(w, v, 2); }

/* [[x, y], ...]: n points. */
static void write_pairs(wp_writer *w, const double (*v)[2], size_t n)
{
    wp_write_array(w);
    for (size_t i = 0; i < n; i++)
        write_pair(w, v[i]);
    wp_write_array_end(w);
}

/* An outline's loops as given: [x, y] for a straight segment, [x, y,
 * bulge] for an arc (a bulge of 0, or -0, is the straight form: one
 * fixture, one id). */
static void write_loops(wp_writer *w, const wr_outline *outline)
{
    wp_write_array(w);
    for (size_t i = 0; i < outline->loop_count; i++) {
        wp_write_array(w);
        for (size_t j = 0; j < outline->loops[i].segment_count; j++) {
            const wr_segment *segment = &outline->loops[i].segments[j];
            double row[3] = {segment->start[0], segment->start[1], segment->bulge + 0.0};
            wp_write_numbers(w, row, row[2] != 0 ? 3 : 2);
        }
        wp_write_array_end(w);
    }
    wp_write_array_end(w);
}

static void write_shape(wp_writer *w, const wr_fixture *f)
{
    wp_write_object(w);
    if (f->shape == WR_SHAPE_CIRCLE) {
        wp_write_key(w, "center");
        write_pair(w, f->center);
        wp_write_member_number(w, "radius", f->radius);
        wp_write_member_string(w, "type", "circle");
    } else if (f->shape == WR_SHAPE_OUTLINE) {
        wp_write_key(w, "loops");
        write_loops(w, f->outline);
        wp_write_member_string(w, "type", "outline");
    } else {
        wp_write_member_string(w, "type", "polygon");
        wp_write_key(w, "vertices");
        write_pairs(w, (const double (*)[2])f->vertices, f->vertex_count);
    }
    wp_write_object_end(w);
}

/* A coefficient: the number itself when a point (as every fixture without
 * intervals has, and [a, a] is a), else [lo, hi]. */
static void write_coefficient(wp_writer *w, double lo, double hi)
{
    if (lo == hi) {
        wp_write_number(w, hi);
    } else {
        double bounds[2] = {lo, hi};
        wp_write_numbers(w, bounds, 2);
    }
}

/* "friction": {"kinetic": ..., "static": ...}, keys in the canonical
 * order, each coefficient as write_coefficient writes it. */
static void write_friction(wp_writer *w, double static_min, double mu_static, double kinetic_min,
                           double mu_kinetic)
{
    wp_write_key(w, "friction");
    wp_write_object(w);
    wp_write_key(w, "kinetic");
    write_coefficient(w, kinetic_min, mu_kinetic);
    wp_write_key(w, "static");
    write_coefficient(w, static_min, mu_static);
    wp_write_object_end(w);
}

/* {"angle": A, "position": T} (keys sorted, as explicit_text writes
 * them), the angle only when not 0 (so that a tolerance written with
 * "angle": 0 and one without share an id). */
static void write_tolerance(wp_writer *w, const wr_tolerance *t)
{
    wp_write_object(w);
    if (t->angle != 0)
        wp_write_member_number(w, "angle", t->angle);
    wp_write_member_number(w, "position", t->position);
    wp_write_object_end(w);
}

/* The supports' explicit form (keys sorted): the down clamps when there are
 * any (forces as given), friction {kinetic, static}, g, points. */
static void write_supports(wp_writer *w, const wr_supports *s)
{
    wp_write_object(w);
    if (s->down_count) {
        wp_write_key(w, "down");
        wp_write_array(w);
        for (int i = 0; i < s->down_count; i++) {
            wp_write_object(w);
            wp_write_key(w, "at");
            write_pair(w, s->down[i].at);
            wp_write_member_number(w, "force", s->down[i].force);
            wp_write_object_end(w);
        }
        wp_write_array_end(w);
    }
    write_friction(w, s->mu_static_min, s->mu_static, s->mu_kinetic_min, s->mu_kinetic);
    wp_write_member_number(w, "g", s->g);
    wp_write_key(w, "points");
    write_pairs(w, s->points, (size_t)s->count);
    wp_write_object_end(w);
}

static void write_fixel(wp_writer *w, const wr_fixel *fixel)
{
    wp_write_object(w);
    wp_write_key(w, "at");
    write_pair(w, fixel->at);
    write_friction(w, fixel->mu_static_min, fixel->mu_static, fixel->mu_kinetic_min,
                   fixel->mu_kinetic);
    wp_write_key(w, "normal");
    write_pair(w, fixel->normal);
    wp_write_object_end(w);
}

/* The explicit form's canonical text (wp_canonical: every object's members
 * sorted by key, so each object below writes its keys in that order), with
 * the name when `name` is not NULL.  Malloc'd; NULL when out of memory. */
static char *explicit_text(const wr_fixture *f, const char *name)
{
    wp_buffer b = {0};
    wp_writer w = wp_writer_on(&b);
    wp_write_object(&w);
    wp_write_key(&w, "body");
    wp_write_object(&w);
    wp_write_key(&w, "com");
    write_pair(&w, f->com);
    wp_write_member_number(&w, "inertia", f->inertia);
    wp_write_member_number(&w, "mass", f->mass);
    if (f->shape != WR_SHAPE_NONE) {
        wp_write_key(&w, "shape");
        write_shape(&w, f);
    }
    wp_write_object_end(&w);
    wp_write_key(&w, "fixels");
    wp_write_array(&w);
    for (int i = 0; i < f->fixel_count; i++)
        write_fixel(&w, &f->fixels[i]);
    wp_write_array_end(&w);
    if (name)
        wp_write_member_string(&w, "name", name);
    if (f->supports) {
        wp_write_key(&w, "supports");
        write_supports(&w, f->supports);
    }
    if (f->tolerance.given) {
        wp_write_key(&w, "tolerance");
        write_tolerance(&w, &f->tolerance);
    }
    if (f->units.given) {
        /* Only when given: a fixture without units keeps the id it had. */
        wp_write_key(&w, "units");
        wp_write_object(&w);
        wp_write_member_string(&w, "force", unit_text(FORCE_UNITS, f->units.force_n));
        wp_write_member_string(&w, "length", unit_text(LENGTH_UNITS, f->units.length_m));
        wp_write_object_end(&w);
    }
    wp_write_object_end(&w);
    return wp_buffer_take(&b);
}

/* Fill the doc's id, canonical text and name from its fixture. */
static bool describe(wp_fixture_doc *doc, const char *name)
{
    char *content = explicit_text(doc->fixture, NULL);
    doc->canonical = content ? explicit_text(doc->fixture, name) : NULL;
    doc->name = strdup(name ? name : "");
    if (!content || !doc->canonical || !doc->name) {
        free(content);
        return false;
    }
    hex_id(content, doc->id);
    free(content);
    return true;
}

bool wp_fixture_legacy_id(const cJSON *json, char id[WP_ID_LENGTH + 1])
{
    char *content = wp_canonical(json, "name");
    if (!content)
        return false;
    hex_id(content, id);
    free(content);
    return true;
}

bool wp_fixture_written_key(const cJSON *json, char key[WP_ID_LENGTH + 1])
{
    unsigned char digest[32];
    if (!wp_canonical_digest(json, digest))
        return false;
    for (int i = 0; i < WP_ID_LENGTH / 2; i++)
        snprintf(key + 2 * i, 3, "%02x", digest[i]);
    return true;
}

bool wp_fixture_read(const cJSON *json, const char *path, wp_fixture_doc *out, wp_error *error)
{
    memset(out, 0, sizeof *out);
    if (!wp_check_object(json, path, FIXTURE_FIELDS, error))
        return false;
    wr_fixture_spec spec;
    memset(&spec, 0, sizeof spec);
    shape_storage storage = {NULL, NULL, NULL};
    wr_fixel_spec *fixels = NULL;
    const char *name = NULL;
    char field[WP_FIELD_MAX];
    bool ok = wp_member_string(json, path, "name", false, &name, error);
    if (ok && name && strlen(name) > WP_NAME_MAX) {
        wp_path_key(field, path, "name");
        wp_error_set(error, WP_INVALID_PARAMS, field, "is %zu bytes long; at most %d", strlen(name),
                     WP_NAME_MAX);
        ok = false;
    }
    if (ok) {
        const cJSON *body = cJSON_GetObjectItemCaseSensitive(json, "body");
        wp_path_key(field, path, "body");
        if (!body) {
            wp_error_set(error, WP_INVALID_PARAMS, field, "required");
            ok = false;
        } else {
            ok = read_body(body, field, &spec, &storage, error);
        }
    }
    if (ok) {
        wp_path_key(field, path, "friction");
        ok = read_friction(cJSON_GetObjectItemCaseSensitive(json, "friction"), field,
                           &spec.friction, error);
    }
    if (ok) {
        wp_path_key(field, path, "units");
        ok = read_units(cJSON_GetObjectItemCaseSensitive(json, "units"), field, &spec.units,
                        error);
    }
    wr_tolerance tolerance = {false, 0, 0};
    if (ok) {
        wp_path_key(field, path, "tolerance");
        ok = wp_tolerance_read(cJSON_GetObjectItemCaseSensitive(json, "tolerance"), field,
                               &tolerance, error);
    }
    if (ok) {
        const cJSON *list = cJSON_GetObjectItemCaseSensitive(json, "fixels");
        wp_path_key(field, path, "fixels");
        if (!list) {
            wp_error_set(error, WP_INVALID_PARAMS, field, "required");
            ok = false;
        } else {
            ok = read_fixels(list, field, &fixels, &spec.fixel_count, error);
            spec.fixels = fixels;
        }
    }
    if (ok) {
        wr_error invalid;
        wr_status status = wr_fixture_new(&spec, &out->fixture, &invalid);
        if (status != WR_OK) {
            wp_error_refusal(error, status, path, &invalid);
            ok = false;
        }
    }
    if (ok && !apply_tolerance(out->fixture, &tolerance, path, error)) {
        wr_fixture_free(out->fixture);
        out->fixture = NULL;
        ok = false;
    }
    const cJSON *supports = cJSON_GetObjectItemCaseSensitive(json, "supports");
    if (ok && supports && out->fixture->tolerance.given) {
        /* The robust answers (wr_tolerance.h) are made over the cones of a
         * floating part; a part on supports answers by its discs. */
        wp_path_key(field, path, "supports");
        wp_error_set(error, WP_INVALID_PARAMS, field,
                     "a fixture on supports takes no tolerance: give supports or a "
                     "tolerance, not both");
        wr_fixture_free(out->fixture);
        out->fixture = NULL;
        ok = false;
    }
    if (ok && supports) {
        wp_path_key(field, path, "supports");
        ok = wp_supports_read(supports, field, out->fixture, error);
        if (!ok) {
            wr_fixture_free(out->fixture);
            out->fixture = NULL;
        }
    }
    shape_storage_free(&storage);
    free(fixels);
    if (!ok)
        return false;
    /* The name is borrowed from `json`, which outlives this call. */
    if (!describe(out, name)) {
        wp_fixture_doc_release(out);
        wp_error_set(error, WP_INTERNAL, "", "out of memory");
        return false;
    }
    return true;
}

bool wp_body_read(const cJSON *params, const char *path, wr_fixture **body, wp_error *error)
{
    *body = NULL;
    wr_fixture_spec spec;
    memset(&spec, 0, sizeof spec);
    shape_storage storage = {NULL, NULL, NULL};
    char field[WP_FIELD_MAX];
    wp_path_key(field, path, "body");
    const cJSON *json = cJSON_GetObjectItemCaseSensitive(params, "body");
    bool ok = json != NULL;
    if (!ok)
        wp_error_set(error, WP_INVALID_PARAMS, field, "required");
    else
        ok = read_body(json, field, &spec, &storage, error);
    if (ok) {
        /* Its units, as a fixture's: the loads' forces and G are in them. */
        wp_path_key(field, path, "units");
        ok = read_units(cJSON_GetObjectItemCaseSensitive(params, "units"), field, &spec.units,
                        error);
    }
    if (ok) {
        wr_error invalid;
        wr_status status = wr_fixture_body_new(&spec, body, &invalid);
        if (status != WR_OK) {
            wp_error_refusal(error, status, path, &invalid);
            ok = false;
        }
    }
    shape_storage_free(&storage);
    return ok;
}

bool wp_friction_read(const cJSON *json, const char *path, wr_friction_spec *out,
                      wp_error *error)
{
    memset(out, 0, sizeof *out);
    bool ok;
    if (cJSON_IsNumber(json)) {
        out->given = true;
        ok = wp_number(json, path, &out->static_mu, error);
    } else if (cJSON_IsArray(json)) {
        double bounds[2];
        if (cJSON_GetArraySize(json) != 2) {
            wp_error_set(error, WP_INVALID_PARAMS, path,
                         "must be a number, an interval [lo, hi] or {\"static\", \"kinetic\"}, "
                         "not an array of %d",
                         cJSON_GetArraySize(json));
            return false;
        }
        if (!wp_vector2(json, path, bounds, error))
            return false;
        ok = true;
        out->given = out->static_interval = true;
        out->static_min = bounds[0];
        out->static_mu = bounds[1];
    } else if (cJSON_IsObject(json)) {
        ok = read_friction(json, path, out, error);
    } else {
        wp_error_set(error, WP_INVALID_PARAMS, path,
                     "must be a number, an interval [lo, hi] or {\"static\", \"kinetic\"}, not %s",
                     wp_type_name(json));
        ok = false;
    }
    if (!ok)
        return false;
    wr_error invalid;
    if (wr_friction_check(out, "friction", &invalid) != WR_OK) {
        /* "friction.static[1]" is path.static[1] of an object, path[1] of
         * an interval, path of a number. */
        const char *suffix = invalid.field + strlen("friction");
        if (!cJSON_IsObject(json) && strncmp(suffix, ".static", 7) == 0)
            suffix += 7;
        char field[WP_FIELD_MAX];
        snprintf(field, sizeof field, "%.120s%.60s", path, suffix);
        wp_error_set(error, WP_INVALID_PARAMS, field, "%s", invalid.reason);
        return false;
    }
    return true;
}

void wp_fixture_doc_release(wp_fixture_doc *doc)
{
    if (!doc)
        return;
    free(doc->name);
    free(doc->canonical);
    wr_fixture_free(doc->fixture);
    memset(doc, 0, sizeof *doc);
}

void wp_fixture_doc_move(wp_fixture_doc *to, wp_fixture_doc *from)
{
    *to = *from;
    memset(from, 0, sizeof *from);
}

bool wp_fixture_id_valid(const char *text)
{
    if (strlen(text) != WP_ID_LENGTH)
        return false;
    for (const char *c = text; *c; c++)
        if (!((*c >= '0' && *c <= '9') || (*c >= 'a' && *c <= 'f')))
            return false;
    return true;
}

static const char *const WRENCH_FIELDS[] = {"force", "at", NULL};

bool wp_wrench_read(const cJSON *json, const char *path, const wr_fixture *fixture,
                    double wrench[3], wp_error *error)
{
    if (cJSON_IsArray(json)) {
        if (cJSON_GetArraySize(json) != 3) {
            wp_error_set(error, WP_INVALID_PARAMS, path,
                         "a wrench is [f_x, f_y, tau]: 3 numbers, not %d", cJSON_GetArraySize(json));
            return false;
        }
        const cJSON *item = json->child;
        for (int i = 0; i < 3; i++, item = item->next) {
            char field[WP_FIELD_MAX];
            wp_path_index(field, path, (size_t)i);
            if (!wp_number(item, field, &wrench[i], error))
                return false;
        }
        return true;
    }
    if (!cJSON_IsObject(json)) {
        wp_error_set(error, WP_INVALID_PARAMS, path,
                     "a wrench is [f_x, f_y, tau] or {\"force\": [f_x, f_y], \"at\": [x, y]}, "
                     "not %s",
                     wp_type_name(json));
        return false;
    }
    double force[2], at[2];
    if (!wp_check_object(json, path, WRENCH_FIELDS, error) ||
        !wp_member_vector2(json, path, "force", true, force, NULL, error) ||
        !wp_member_vector2(json, path, "at", true, at, NULL, error))
        return false;
    wr_fixture_force_wrench(fixture, force, at, wrench);
    if (!isfinite(wrench[2])) {
        wp_error_set(error, WP_INVALID_PARAMS, path, "its torque overflows");
        return false;
    }
    return true;
}
