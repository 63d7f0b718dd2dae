/* test_fixture.c -- every validation branch of wr_fixture_new names its
 * field: one mutation of a valid fixture per row of a table. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>
#include <stdio.h>

#include "test_util.h"

/* A valid polygon fixture the mutations start from: a 4 x 2 rectangle with
 * fixels on its bottom edge and its left edge. */
typedef struct base {
    wr_fixture_spec spec;
    wr_fixel_spec fixels[WR_MAX_FIXELS + 1];
    double vertices[8][2];
} base;

static void make_base(base *b)
{
    memset(b, 0, sizeof *b);
    const double v[4][2] = {{0, 0}, {4, 0}, {4, 2}, {0, 2}};
    memcpy(b->vertices, v, sizeof v);
    b->fixels[0].at[0] = 1;
    b->fixels[1].at[0] = 3;
    b->fixels[2].at[1] = 1;
    b->spec.mass = 2;
    b->spec.shape = WR_SHAPE_POLYGON;
    b->spec.vertex_count = 4;
    b->spec.vertices = (const double (*)[2])b->vertices;
    b->spec.friction.given = true;
    b->spec.friction.static_mu = 0.3;
    b->spec.fixel_count = 3;
    b->spec.fixels = b->fixels;
}

typedef struct mutation {
    const char *name;
    void (*apply)(base *);
    const char *field;  /* expected error field, exactly */
} mutation;

#define MUTATION(id, body)                                                                     \
    static void id(base *b) { body; }

MUTATION(nan_mass, b->spec.mass = NAN)
MUTATION(negative_mass, b->spec.mass = -1)
MUTATION(infinite_inertia, (b->spec.inertia_given = true, b->spec.inertia = INFINITY))
MUTATION(zero_inertia, (b->spec.inertia_given = true, b->spec.inertia = 0))
MUTATION(nan_com, (b->spec.com_given = true, b->spec.com[1] = NAN))
MUTATION(nan_vertex, b->vertices[2][0] = NAN)
MUTATION(repeated_vertex, (b->vertices[2][0] = 4, b->vertices[2][1] = 0))
MUTATION(two_vertices, b->spec.vertex_count = 2)
MUTATION(bow_tie, (b->vertices[2][0] = 0, b->vertices[3][0] = 4))
MUTATION(nan_radius, (b->spec.shape = WR_SHAPE_CIRCLE, b->spec.radius = NAN))
MUTATION(zero_radius, (b->spec.shape = WR_SHAPE_CIRCLE, b->spec.radius = 0))
MUTATION(infinite_center, (b->spec.shape = WR_SHAPE_CIRCLE, b->spec.radius = 1,
                           b->spec.center[0] = -INFINITY))
MUTATION(nan_static, b->spec.friction.static_mu = NAN)
MUTATION(negative_static, b->spec.friction.static_mu = -0.1)
MUTATION(nan_kinetic, (b->spec.friction.kinetic_given = true, b->spec.friction.kinetic_mu = NAN))
MUTATION(kinetic_above_static,
         (b->spec.friction.kinetic_given = true, b->spec.friction.kinetic_mu = 0.4))
MUTATION(fixel_friction_above,
         (b->fixels[2].friction.given = true, b->fixels[2].friction.static_mu = 0.2,
          b->fixels[2].friction.kinetic_given = true, b->fixels[2].friction.kinetic_mu = 0.5))
MUTATION(no_friction, b->spec.friction.given = false)
MUTATION(nan_at, b->fixels[1].at[1] = NAN)
MUTATION(off_boundary, b->fixels[1].at[1] = 0.5)
MUTATION(inside_point, (b->fixels[0].at[0] = 2, b->fixels[0].at[1] = 1))
MUTATION(vertex_without_normal, b->fixels[1].at[0] = 4)
MUTATION(nan_normal, (b->fixels[2].normal_given = true, b->fixels[2].normal[0] = NAN))
MUTATION(zero_normal, b->fixels[2].normal_given = true)
MUTATION(outward_normal,
         (b->fixels[2].normal_given = true, b->fixels[2].normal[0] = -1))
MUTATION(duplicate, (b->fixels[2].at[0] = 1, b->fixels[2].at[1] = 0))
MUTATION(no_fixels, b->spec.fixel_count = 0)
static void nine_fixels(base *b)
{
    b->spec.fixel_count = 9;
    for (int i = 0; i < 9; i++) {
        b->fixels[i].at[0] = 0.4 * (i + 1);
        b->fixels[i].at[1] = 0;
    }
}
MUTATION(no_shape_no_com, b->spec.shape = WR_SHAPE_NONE)
MUTATION(no_shape_no_inertia,
         (b->spec.shape = WR_SHAPE_NONE, b->spec.com_given = true))
MUTATION(friction_too_large, b->spec.friction.static_mu = WR_MAX_FRICTION * 1.001)
MUTATION(subnormal_mass, b->spec.mass = 1e-310)
MUTATION(subnormal_inertia, (b->spec.inertia_given = true, b->spec.inertia = 1e-310))
MUTATION(subnormal_radius, (b->spec.shape = WR_SHAPE_CIRCLE, b->spec.radius = 1e-310))
/* The rectangle's size is hypot(4, 2) = 4.47; its bounding box ends at x = 4. */
MUTATION(com_beyond_the_part, (b->spec.com_given = true, b->spec.com[0] = 4 + 4.48))
/* rho = sqrt(I / 2) against the size 4.47: 1e4 times larger, 1e4 times smaller. */
MUTATION(gyration_too_large, (b->spec.inertia_given = true, b->spec.inertia = 2 * 4.48e4 * 4.48e4))
MUTATION(gyration_too_small,
         (b->spec.inertia_given = true, b->spec.inertia = 2 * 4.46e-4 * 4.46e-4))
/* Without a shape the lever arms decide: a fixel 2e4 from the com, rho = 1. */
MUTATION(shapeless_lever_too_long,
         (b->spec.shape = WR_SHAPE_NONE, b->spec.com_given = true, b->spec.inertia_given = true,
          b->spec.inertia = 2, b->spec.fixel_count = 1, b->fixels[0].normal_given = true,
          b->fixels[0].normal[1] = 1, b->fixels[0].at[0] = 2e4))
MUTATION(no_shape_no_normal, (b->spec.shape = WR_SHAPE_NONE, b->spec.com_given = true,
                              b->spec.inertia_given = true, b->spec.inertia = 1))

MUTATION(units_no_length, (b->spec.units = (wr_units){true, 0.0, 1.0}))
MUTATION(units_nan_force, (b->spec.units = (wr_units){true, 1e-3, NAN}))

static const mutation mutations[] = {
    {"nan mass", nan_mass, "body.mass"},
    {"negative mass", negative_mass, "body.mass"},
    {"infinite inertia", infinite_inertia, "body.inertia"},
    {"zero inertia", zero_inertia, "body.inertia"},
    {"nan com", nan_com, "body.com[1]"},
    {"nan vertex", nan_vertex, "body.shape.vertices[2][0]"},
    {"repeated vertex", repeated_vertex, "body.shape.vertices[2]"},
    {"two vertices", two_vertices, "body.shape.vertices"},
    {"bow tie", bow_tie, "body.shape.vertices"},
    {"nan radius", nan_radius, "body.shape.radius"},
    {"zero radius", zero_radius, "body.shape.radius"},
    {"infinite centre", infinite_center, "body.shape.center[0]"},
    {"nan static friction", nan_static, "friction.static"},
    {"negative static friction", negative_static, "friction.static"},
    {"nan kinetic friction", nan_kinetic, "friction.kinetic"},
    {"kinetic above static", kinetic_above_static, "friction.kinetic"},
    {"a fixel's kinetic above its static", fixel_friction_above, "fixels[2].friction.kinetic"},
    {"no friction anywhere", no_friction, "fixels[0].friction"},
    {"nan at", nan_at, "fixels[1].at[1]"},
    {"off the boundary", off_boundary, "fixels[1].at"},
    {"inside the body", inside_point, "fixels[0].at"},
    {"vertex without a normal", vertex_without_normal, "fixels[1].normal"},
    {"nan normal", nan_normal, "fixels[2].normal[0]"},
    {"zero normal", zero_normal, "fixels[2].normal"},
    {"outward normal", outward_normal, "fixels[2].normal"},
    {"duplicate fixel", duplicate, "fixels[2]"},
    {"no fixels", no_fixels, "fixels"},
    {"nine fixels", nine_fixels, "fixels"},
    {"no shape, no com", no_shape_no_com, "body.com"},
    {"no shape, no inertia", no_shape_no_inertia, "body.inertia"},
    {"no shape, no normal", no_shape_no_normal, "fixels[0].normal"},
    {"friction above the limit", friction_too_large, "friction.static"},
    {"subnormal mass", subnormal_mass, "body.mass"},
    {"subnormal inertia", subnormal_inertia, "body.inertia"},
    {"subnormal radius", subnormal_radius, "body.shape.radius"},
    {"centre of mass beyond the part", com_beyond_the_part, "body.com"},
    {"radius of gyration too large", gyration_too_large, "body.inertia"},
    {"radius of gyration too small", gyration_too_small, "body.inertia"},
    {"shapeless, lever arm too long", shapeless_lever_too_long, "body.inertia"},
    {"a length unit of no size", units_no_length, "units.length"},
    {"a force unit not a number", units_nan_force, "units.force"},
};

static void every_invalid_field_is_named(void **state)
{
    (void)state;
    base b;
    make_base(&b);
    wr_error error;
    wr_fixture *f = test_fixture_new(&b.spec, &error);
    assert_non_null(f); /* the base is valid */
    wr_fixture_free(f);
    for (size_t i = 0; i < sizeof mutations / sizeof mutations[0]; i++) {
        make_base(&b);
        mutations[i].apply(&b);
        memset(&error, 0, sizeof error);
        wr_status status = wr_fixture_new(&b.spec, &f, &error);
        if (f) {
            wr_fixture_free(f);
            fail_msg("%s: accepted", mutations[i].name);
        }
        assert_int_equal(status, WR_INVALID);
        if (strcmp(error.field, mutations[i].field) != 0)
            fail_msg("%s: field \"%s\", expected \"%s\" (%s)", mutations[i].name, error.field,
                     mutations[i].field, error.reason);
        assert_true(strlen(error.reason) > 10);
    }
    print_message("fixture: %zu invalid fixtures, each refused with its field\n",
                  sizeof mutations / sizeof mutations[0]);
}

/* Refusals that say what is wrong, not something near it. */
MUTATION(huge_rectangle, (b->vertices[1][0] = b->vertices[2][0] = 4e200,
                          b->vertices[2][1] = b->vertices[3][1] = 2e200))
MUTATION(large_rectangle, (b->vertices[1][0] = b->vertices[2][0] = 4e100,
                           b->vertices[2][1] = b->vertices[3][1] = 2e100))
/* The left edge's fixel pushing along the edge, and a corner's along
 * the bottom edge, outwards. */
MUTATION(tangent_normal, (b->fixels[2].normal_given = true, b->fixels[2].normal[1] = -1))
MUTATION(tangent_at_vertex, (b->fixels[1].at[0] = 4, b->fixels[1].normal_given = true,
                             b->fixels[1].normal[0] = 1))
MUTATION(nearly_tangent_normal,
         (b->fixels[2].normal_given = true, b->fixels[2].normal[0] = 1e-12,
          b->fixels[2].normal[1] = 1))

static const struct {
    const char *name;
    void (*apply)(base *);
    const char *field, *reason; /* the reason starts with this */
} messages[] = {
    {"bow tie", bow_tie, "body.shape.vertices",
     "the polygon intersects itself: edge 1 (vertices 1 to 2) and edge 3 (vertices 3 to 0) "
     "meet at (2, 1)"},
    {"area beyond doubles", huge_rectangle, "body.shape.vertices",
     "the polygon is too large for double precision: its area overflows"},
    {"second moment beyond doubles", large_rectangle, "body.shape.vertices",
     "the polygon is too large for double precision: its second moment of area overflows"},
    {"tangent normal", tangent_normal, "fixels[2].normal",
     "(0, -1) is tangent to the boundary at (0, 1)"},
    {"nearly tangent normal", nearly_tangent_normal, "fixels[2].normal",
     "(1e-12, 1) is tangent to the boundary"},
    {"tangent at a vertex", tangent_at_vertex, "fixels[1].normal",
     "(1, 0) is tangent to the boundary at (4, 0)"},
    {"outward normal", outward_normal, "fixels[2].normal", "(-1, 0) points out of the workpiece"},
};

static void refusals_say_what_is_wrong(void **state)
{
    (void)state;
    base b;
    for (size_t i = 0; i < sizeof messages / sizeof messages[0]; i++) {
        make_base(&b);
        messages[i].apply(&b);
        wr_error error;
        memset(&error, 0, sizeof error);
        wr_fixture *f;
        wr_status status = wr_fixture_new(&b.spec, &f, &error);
        if (f) {
            wr_fixture_free(f);
            fail_msg("%s: accepted", messages[i].name);
        }
        assert_int_equal(status, WR_INVALID);
        if (strcmp(error.field, messages[i].field) != 0 ||
            strncmp(error.reason, messages[i].reason, strlen(messages[i].reason)) != 0)
            fail_msg("%s: \"%s\": \"%s\", expected \"%s\": \"%s...\"", messages[i].name,
                     error.field, error.reason, messages[i].field, messages[i].reason);
    }
}

/* A constraint string's length is counted in letters (characters), and a
 * letter that is not one is quoted whole. */
static void constraint_letters_are_characters(void **state)
{
    (void)state;
    static const struct {
        const char *text;
        int fixels;
        const char *reason;
    } bad[] = {
        {"s\xc3\xa9", 2, "letter 2 is '\xc3\xa9', not one of s a u l r n m"},     /* sé */
        {"\xc3\xa9s", 2, "letter 1 is '\xc3\xa9', not one of s a u l r n m"},     /* és */
        {"s\xe2\x9c\x93m", 2, "has 3 letters, the fixture has 2 fixels"},       /* s✓m */
        {"\xf0\x9f\x94\xa7", 1, "letter 1 is '\xf0\x9f\x94\xa7', not one"}, /* a wrench */
        {"s\x80", 1, "byte 0x80 after letter 1 is not a letter"},
        {"\xff", 1, "letter 1 is '?', not one"},
        {"Sm", 2, "letter 1 is 'S', not one"},
        {"smu", 2, "has 3 letters, the fixture has 2 fixels"},
    };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        wr_constraint constraint;
        wr_error error = {{0}, {0}};
        if (wr_constraint_parse(bad[i].text, bad[i].fixels, &constraint, &error) != WR_INVALID)
            fail_msg("\"%s\": accepted", bad[i].text);
        if (strncmp(error.reason, bad[i].reason, strlen(bad[i].reason)) != 0)
            fail_msg("\"%s\": \"%s\", expected \"%s...\"", bad[i].text, error.reason,
                     bad[i].reason);
    }
    wr_constraint constraint;
    assert_int_equal(wr_constraint_parse("sm", 2, &constraint, NULL), WR_OK);
}

/* A fixture without a shape is accepted when com, inertia and normals are
 * given, and a null error pointer is allowed. */
static void shapeless_fixture_is_accepted(void **state)
{
    (void)state;
    base b;
    make_base(&b);
    b.spec.shape = WR_SHAPE_NONE;
    b.spec.com_given = true;
    b.spec.inertia_given = true;
    b.spec.inertia = 1;
    for (int i = 0; i < 3; i++)
        b.fixels[i].normal_given = true;
    b.fixels[0].normal[1] = b.fixels[1].normal[1] = 2; /* normalised */
    b.fixels[2].normal[0] = 1;
    wr_fixture *f = test_fixture_new(&b.spec, NULL);
    assert_non_null(f);
    assert_true(fabs(f->fixels[0].normal[1] - 1) < 1e-15);
    assert_true(fabs(f->gyration_radius - sqrt(0.5)) < 1e-15);
    wr_fixture_free(f);
    /* One fixel far from the centre of mass, and then two close together
     * at one end of a long part: nothing says where a shapeless part is,
     * so neither is refused for its centre of mass (the two are 1e-2 rho
     * apart: 1e-3 rho is the least spread taken, WR_FIXEL_SPREAD). */
    b.spec.inertia = 2; /* rho = 1 */
    b.spec.fixel_count = 1;
    b.fixels[0].at[0] = 500;
    b.fixels[0].at[1] = 300;
    f = test_fixture_new(&b.spec, NULL);
    assert_non_null(f);
    wr_fixture_free(f);
    b.spec.fixel_count = 2;
    b.fixels[1].at[0] = 500.01;
    b.fixels[1].at[1] = 300;
    f = test_fixture_new(&b.spec, NULL);
    assert_non_null(f);
    wr_fixture_free(f);
    /* The limits on the lever arm are inclusive of a factor just under 1e4. */
    b.fixels[0].at[0] = b.fixels[1].at[0] = 0.99e4;
    b.fixels[0].at[1] = 0;
    b.fixels[1].at[1] = 0.001;
    f = test_fixture_new(&b.spec, NULL);
    assert_non_null(f);
    wr_fixture_free(f);
    b.spec.mass = 0;
    assert_int_equal(wr_fixture_new(&b.spec, &f, NULL), WR_INVALID);
    assert_null(f);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(every_invalid_field_is_named),
        cmocka_unit_test(shapeless_fixture_is_accepted),
        cmocka_unit_test(refusals_say_what_is_wrong),
        cmocka_unit_test(constraint_letters_are_characters),
    };
    return cmocka_run_group_tests_name("fixture", tests, NULL, NULL);
}


