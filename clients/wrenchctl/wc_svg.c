/* wc_svg.c -- SVG pictures of push regions, gravity sweeps and disturbance
 * margins, and plots of friction sweeps against mu (see wc_svg.h). */
#include "wc_svg.h"

#include <math.h>
#include <string.h>

#define WIDTH 640.0
#define PI 3.14159265358979323846

/* Fixture coordinates to the page: uniform scale, y up. */
typedef struct frame {
    double x0, y1;   /* the fixture point at the page's top left */
    double scale;    /* pixels per unit length */
    double size;     /* the part's size, fixture units */
    double height;   /* page height, pixels */
    double top;      /* pixels above the drawing, for the legend */
} frame;

static double page_x(const frame *f, double x) { return (x - f->x0) * f->scale; }
static double page_y(const frame *f, double y) { return f->top + (f->y1 - y) * f->scale; }

static void bounds(const wr_fixture *fx, double lo[2], double hi[2])
{
    lo[0] = lo[1] = INFINITY;
    hi[0] = hi[1] = -INFINITY;
    if (fx->shape == WR_SHAPE_CIRCLE) {
        for (int k = 0; k < 2; k++) {
            lo[k] = fx->center[k] - fx->radius;
            hi[k] = fx->center[k] + fx->radius;
        }
    }
    if (fx->shape == WR_SHAPE_OUTLINE && fx->outline) {
        /* The box of every loop, arcs included. */
        for (int k = 0; k < 2; k++) {
            lo[k] = fx->outline->box_min[k];
            hi[k] = fx->outline->box_max[k];
        }
    }
    for (size_t i = 0; fx->shape != WR_SHAPE_OUTLINE && i < fx->vertex_count; i++)
        for (int k = 0; k < 2; k++) {
            lo[k] = fmin(lo[k], fx->vertices[i][k]);
            hi[k] = fmax(hi[k], fx->vertices[i][k]);
        }
    for (int i = 0; i < fx->fixel_count; i++)
        for (int k = 0; k < 2; k++) {
            lo[k] = fmin(lo[k], fx->fixels[i].at[k]);
            hi[k] = fmax(hi[k], fx->fixels[i].at[k]);
        }
    for (int k = 0; k < 2; k++) {
        lo[k] = fmin(lo[k], fx->com[k]);
        hi[k] = fmax(hi[k], fx->com[k]);
    }
}

/* A frame around the part with `pad` (a fraction of its size) on each side
 * and `legend_lines` of text above. */
static frame frame_for(const wr_fixture *fx, double pad, int legend_lines)
{
    double lo[2], hi[2];
    bounds(fx, lo, hi);
    double size = fmax(hi[0] - lo[0], hi[1] - lo[1]);
    if (!(size > 0))
        size = 1;
    frame f;
    f.size = size;
    f.x0 = lo[0] - pad * size;
    f.y1 = hi[1] + pad * size;
    f.scale = WIDTH / (hi[0] - lo[0] + 2 * pad * size);
    f.top = 20 + 18 * legend_lines;
    f.height = f.top + (hi[1] - lo[1] + 2 * pad * size) * f.scale;
    return f;
}

static void text_escaped(FILE *out, const char *text)
{
    for (; *text; text++) {
        switch (*text) {
        case '<': fputs("&lt;", out); break;
        case '>': fputs("&gt;", out); break;
        case '&': fputs("&amp;", out); break;
        case '"': fputs("&quot;", out); break;
        default: fputc(*text, out);
        }
    }
}

/* The unit of a fixture's lengths, from its size in metres (those a
 * fixture may name: docs/PROTOCOL.md), or NULL without units. */
static const char *length_unit(const wr_fixture *fx)
{
    if (!fx || !fx->units.given)
        return NULL;
    static const struct {
        double m;
        const char *name;
    } names[] = {{1e-3, "mm"}, {1.0, "m"}, {0.0254, "in"}};
    for (size_t i = 0; i < sizeof names / sizeof names[0]; i++)
        if (fx->units.length_m == names[i].m)
            return names[i].name;
    return NULL;
}

/* With a fixture that names its units, the unit of its coordinates, ending
 * at (x, y): <text class="units">. */
static void units_note(FILE *out, double x, double y, const wr_fixture *fx)
{
    const char *unit = length_unit(fx);
    if (unit)
        fprintf(out,
                "<text class=\"units\" x=\"%.0f\" y=\"%.0f\" text-anchor=\"end\" "
                "font-size=\"12\" fill=\"#666\">lengths in %s</text>\n",
                x, y, unit);
}

/* The picture's start, and units_note at the bottom right. */
static void begin(FILE *out, const frame *f, const char *title, const wr_fixture *fx)
{
    fprintf(out,
            "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
            "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%.0f\" height=\"%.0f\" "
            "viewBox=\"0 0 %.0f %.0f\" font-family=\"sans-serif\" font-size=\"14\">\n<title>",
            WIDTH, f->height, WIDTH, f->height);
    text_escaped(out, title);
    fputs("</title>\n<defs>", out);
    /* One arrowhead per colour: markers do not take the line's colour. */
    static const char *const colours[] = {"1f4e9c", "c0392b"};
    for (int i = 0; i < 2; i++)
        fprintf(out,
                "<marker id=\"arrow-%s\" viewBox=\"0 0 10 10\" refX=\"9\" refY=\"5\" "
                "markerWidth=\"6\" markerHeight=\"6\" orient=\"auto-start-reverse\">"
                "<path d=\"M 0 0 L 10 5 L 0 10 z\" fill=\"#%s\"/></marker>",
                colours[i], colours[i]);
    fputs("</defs>\n<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n", out);
    units_note(out, WIDTH - 12, f->height - 8, fx);
}

static void legend(FILE *out, int line, const char *text)
{
    fprintf(out, "<text x=\"12\" y=\"%d\">", 22 + 18 * line);
    text_escaped(out, text);
    fputs("</text>\n", out);
}

/* ---- outlines of lines and arcs ---------------------------------------------- */

/* Which loop and segment an outline's edge is: the edges count the
 * segments of every loop in order, loop 0's first (wr_region).  False for
 * an edge past the last. */
static bool edge_place(const wr_outline *o, int edge, size_t *loop, size_t *segment)
{
    if (edge < 0)
        return false;
    size_t rest = (size_t)edge;
    for (size_t i = 0; i < o->loop_count; i++) {
        if (rest < o->loops[i].segment_count) {
            *loop = i;
            *segment = rest;
            return true;
        }
        rest -= o->loops[i].segment_count;
    }
    return false;
}

/* Path data from the point at t0 of a segment (the current point) to the
 * point at t1 (fractions of its length, or of an arc's included angle):
 * " L x y" for a straight segment, " A r r 0 large sweep x y" along an arc.
 * The fixture's counter-clockwise is clockwise on the page, whose y points
 * down: a positive sweep is sweep-flag 0.  The large-arc flag is set beyond
 * a half circle.  An arc whose sagitta is below 0.005 pixels is a line on
 * the page (a nearly straight arc's radius may be beyond what a viewer
 * computes with); one of more than a half circle whose ends print as the
 * same point (SVG leaves such an arc out) is drawn as its two halves.
 *
 * Outline paths are written to six decimals, not two: an arc near a half
 * circle is ill-conditioned in its endpoints and radius (a rounding delta
 * moves its middle by about sqrt(2 r delta): a pixel at two decimals). */
#define OUTLINE_XY "%.6f %.6f"
static void segment_to(FILE *out, const frame *f, const wr_outline *o, size_t loop,
                       size_t segment, double t0, double t1)
{
    const wr_segment *s = &o->loops[loop].segments[segment];
    double a[2], b[2];
    wr_outline_boundary(o, loop, segment, t0, a, NULL);
    wr_outline_boundary(o, loop, segment, t1, b, NULL);
    char from[64], to[64];
    snprintf(from, sizeof from, OUTLINE_XY, page_x(f, a[0]), page_y(f, a[1]));
    snprintf(to, sizeof to, OUTLINE_XY, page_x(f, b[0]), page_y(f, b[1]));
    double sweep = (t1 - t0) * s->sweep;
    double r = s->radius * f->scale;
    double quarter = sin(sweep / 4);
    if (s->bulge == 0 || !(2 * r * quarter * quarter >= 0.005)) {
        fprintf(out, " L %s", to);
        return;
    }
    if (fabs(sweep) > PI && strcmp(from, to) == 0) {
        segment_to(out, f, o, loop, segment, t0, (t0 + t1) / 2);
        segment_to(out, f, o, loop, segment, (t0 + t1) / 2, t1);
        return;
    }
    fprintf(out, " A %.6f %.6f 0 %d %d %s", r, r, fabs(sweep) > PI ? 1 : 0, sweep > 0 ? 0 : 1, to);
}

/* Every loop as a closed subpath of one path: with fill-rule evenodd the
 * holes (the loops after the first) are left unfilled. */
static void outline_path(FILE *out, const frame *f, const wr_outline *o)
{
    for (size_t i = 0; i < o->loop_count; i++) {
        const wr_loop *l = &o->loops[i];
        fprintf(out, "%sM " OUTLINE_XY, i ? " " : "", page_x(f, l->segments[0].start[0]),
                page_y(f, l->segments[0].start[1]));
        for (size_t j = 0; j < l->segment_count; j++) {
            if (j + 1 == l->segment_count && l->segments[j].bulge == 0)
                break; /* z draws the closing line */
            segment_to(out, f, o, i, j, 0, 1);
        }
        fputs(" z", out);
    }
}

/* The hole whose boundary holds p (a fixel there is a pin in the hole):
 * its loop, > 0; 0 when p is on the outer loop or on no outline. */
static size_t hole_at(const wr_fixture *fx, const double p[2])
{
    if (fx->shape != WR_SHAPE_OUTLINE || !fx->outline)
        return 0;
    wr_outline_place place;
    if (!wr_outline_locate(fx->outline, p, 1e-7 * fx->outline->size, &place))
        return 0;
    return place.loop;
}

/* The outline, filled light and stroked grey: the boundary outside any
 * region. */
static void outline(FILE *out, const frame *f, const wr_fixture *fx)
{
    if (fx->shape == WR_SHAPE_CIRCLE) {
        fprintf(out,
                "<circle class=\"outline\" cx=\"%.2f\" cy=\"%.2f\" r=\"%.2f\" fill=\"#f2f2f2\" "
                "stroke=\"#a0a0a0\" stroke-width=\"3\"/>\n",
                page_x(f, fx->center[0]), page_y(f, fx->center[1]), fx->radius * f->scale);
        return;
    }
    if (fx->shape == WR_SHAPE_OUTLINE && fx->outline) {
        fputs("<path class=\"outline\" d=\"", out);
        outline_path(out, f, fx->outline);
        fputs("\" fill=\"#f2f2f2\" fill-rule=\"evenodd\" stroke=\"#a0a0a0\" stroke-width=\"3\" "
              "stroke-linejoin=\"round\"/>\n",
              out);
        return;
    }
    fputs("<polygon class=\"outline\" points=\"", out);
    for (size_t i = 0; i < fx->vertex_count; i++)
        fprintf(out, "%s%.2f,%.2f", i ? " " : "", page_x(f, fx->vertices[i][0]),
                page_y(f, fx->vertices[i][1]));
    fputs("\" fill=\"#f2f2f2\" stroke=\"#a0a0a0\" stroke-width=\"3\" "
          "stroke-linejoin=\"round\"/>\n",
          out);
}

/* A fixel's friction cone, its apex at the contact, opening into the part. */
static void friction_cone(FILE *out, const frame *f, const wr_fixel *x, double cone)
{
    const double *p = x->at, *n = x->normal, *t = x->tangent;
    double mu = x->mu_static;
    double length = cone / sqrt(1 + mu * mu);
    double a[2] = {p[0] + length * (n[0] + mu * t[0]), p[1] + length * (n[1] + mu * t[1])};
    double b[2] = {p[0] + length * (n[0] - mu * t[0]), p[1] + length * (n[1] - mu * t[1])};
    fprintf(out,
            "<polygon class=\"friction-cone\" points=\"%.2f,%.2f %.2f,%.2f %.2f,%.2f\" "
            "fill=\"#c0392b\" fill-opacity=\"0.18\" stroke=\"#c0392b\" stroke-width=\"1.2\"/>\n",
            page_x(f, p[0]), page_y(f, p[1]), page_x(f, a[0]), page_y(f, a[1]), page_x(f, b[0]),
            page_y(f, b[1]));
}

/* A pin's disc when its diameter is not known (or 0, a point), in page
 * units: a dot, not a size it does not have. */
#define PIN_DOT 7.0

/* A fixel on a hole's boundary: a pin in the hole, a dark disc touching the
 * boundary at the contact, at its diameter when known (`diameter` > 0),
 * else a dot; its friction cone, and an arrow from its centre along the
 * normal, its head half the pin's radius into the material (short: the
 * wall beyond a hole may be thin); its number on it. */
static void pin(FILE *out, const frame *f, const wr_fixture *fx, int i, double diameter,
                double cone)
{
    const wr_fixel *x = &fx->fixels[i];
    const double *p = x->at, *n = x->normal;
    double radius = diameter > 0 ? diameter / 2 : PIN_DOT / f->scale;
    double c[2] = {p[0] - radius * n[0], p[1] - radius * n[1]};
    fprintf(out, "<circle class=\"fixel pin\" cx=\"%.2f\" cy=\"%.2f\" r=\"%.2f\" fill=\"#444\"/>\n",
            page_x(f, c[0]), page_y(f, c[1]), radius * f->scale);
    friction_cone(out, f, x, cone);
    fprintf(out,
            "<line class=\"fixel-normal\" x1=\"%.2f\" y1=\"%.2f\" x2=\"%.2f\" y2=\"%.2f\" "
            "stroke=\"#c0392b\" stroke-width=\"2\" marker-end=\"url(#arrow-c0392b)\"/>\n",
            page_x(f, c[0]), page_y(f, c[1]), page_x(f, p[0] + 0.5 * radius * n[0]),
            page_y(f, p[1] + 0.5 * radius * n[1]));
    fprintf(out,
            "<text x=\"%.2f\" y=\"%.2f\" font-size=\"13\" fill=\"white\" "
            "text-anchor=\"middle\">%d</text>\n",
            page_x(f, c[0]), page_y(f, c[1]) + 5, i + 1);
}

/* A fixture on supports (wr_support.h): each support a small square, and
 * its friction disc |f| <= mu_s N_i drawn about it, dashed, to a scale
 * where the whole capacity mu_s W would be 0.3 of the part's size (the
 * largest N_i over the admissible distributions); the normal force beside
 * it in the fixture's force unit. */
static void supports(FILE *out, const frame *f, const wr_fixture *fx)
{
    const wr_supports *s = fx->supports;
    if (!s)
        return;
    double half = 4, reach = 0.3 * f->size / (s->total > 0 ? s->total : 1);
    for (int i = 0; i < s->count; i++) {
        double x = page_x(f, s->points[i][0]), y = page_y(f, s->points[i][1]);
        if (s->mu_static > 0 && s->normal_max[i] > 0)
            fprintf(out,
                    "<circle class=\"friction-disc\" cx=\"%.2f\" cy=\"%.2f\" r=\"%.2f\" "
                    "fill=\"#2e86c1\" fill-opacity=\"0.12\" stroke=\"#2e86c1\" "
                    "stroke-dasharray=\"4 3\"/>\n",
                    x, y, reach * s->normal_max[i] * f->scale);
        fprintf(out,
                "<rect class=\"support\" x=\"%.2f\" y=\"%.2f\" width=\"%.2f\" height=\"%.2f\" "
                "fill=\"#2e86c1\"/>\n",
                x - half, y - half, 2 * half, 2 * half);
        double n = s->normal_min[i] == s->normal_max[i] ? s->normal_max[i] : -1;
        double unit = wr_fixture_force_factor(fx);
        if (n >= 0)
            fprintf(out,
                    "<text class=\"support-load\" x=\"%.2f\" y=\"%.2f\" font-size=\"11\" "
                    "fill=\"#1b4f72\">N=%.4g</text>\n",
                    x + 7, y - 6, n / unit);
        else
            fprintf(out,
                    "<text class=\"support-load\" x=\"%.2f\" y=\"%.2f\" font-size=\"11\" "
                    "fill=\"#1b4f72\">N=%.4g..%.4g</text>\n",
                    x + 7, y - 6, s->normal_min[i] / unit, s->normal_max[i] / unit);
    }
}

/* Each fixel: a dark wedge outside the part, its apex at the contact, and
 * its friction cone opening into the part; on a hole's boundary, a pin of
 * pin_diameters[i] (NULL or < 0: not known). */
static void fixels(FILE *out, const frame *f, const wr_fixture *fx, const double *pin_diameters)
{
    supports(out, f, fx);
    double wedge = 0.06 * f->size, cone = 0.16 * f->size;
    for (int i = 0; i < fx->fixel_count; i++) {
        const wr_fixel *x = &fx->fixels[i];
        if (hole_at(fx, x->at) > 0) {
            pin(out, f, fx, i, pin_diameters ? pin_diameters[i] : -1, cone);
            continue;
        }
        const double *p = x->at, *n = x->normal, *t = x->tangent;
        fprintf(out,
                "<polygon class=\"fixel\" points=\"%.2f,%.2f %.2f,%.2f %.2f,%.2f\" "
                "fill=\"#444\"/>\n",
                page_x(f, p[0]), page_y(f, p[1]),
                page_x(f, p[0] - wedge * (n[0] + 0.6 * t[0])),
                page_y(f, p[1] - wedge * (n[1] + 0.6 * t[1])),
                page_x(f, p[0] - wedge * (n[0] - 0.6 * t[0])),
                page_y(f, p[1] - wedge * (n[1] - 0.6 * t[1])));
        friction_cone(out, f, x, cone);
        fprintf(out, "<text x=\"%.2f\" y=\"%.2f\" font-size=\"13\" text-anchor=\"middle\">%d</text>\n",
                page_x(f, p[0] - 0.12 * f->size * n[0]),
                page_y(f, p[1] - 0.12 * f->size * n[1]) + 5, i + 1);
    }
}

static void centre_of_mass(FILE *out, const frame *f, const wr_fixture *fx)
{
    double x = page_x(f, fx->com[0]), y = page_y(f, fx->com[1]);
    fprintf(out,
            "<g class=\"com\"><circle cx=\"%.2f\" cy=\"%.2f\" r=\"6\" fill=\"white\" "
            "stroke=\"black\" stroke-width=\"1.5\"/><path d=\"M %.2f %.2f A 6 6 0 0 1 %.2f %.2f "
            "L %.2f %.2f z M %.2f %.2f A 6 6 0 0 1 %.2f %.2f L %.2f %.2f z\" fill=\"black\"/></g>\n",
            x, y, x, y - 6, x + 6, y, x, y, x, y + 6, x - 6, y, x, y);
}

/* One coefficient: "0.5", or "[0.2, 0.35]" for an interval. */
static void coefficient_text(double lo, double hi, char *out, size_t size)
{
    if (lo == hi)
        snprintf(out, size, "%g", hi);
    else
        snprintf(out, size, "[%g, %g]", lo, hi);
}

/* "mu = 0.5", "mu = [0.2, 0.35]", or "mu per fixel". */
static void friction_text(const wr_fixture *fx, char *out, size_t size)
{
    bool same = true;
    const wr_fixel *first = &fx->fixels[0];
    for (int i = 1; i < fx->fixel_count; i++)
        same &= fx->fixels[i].mu_static == first->mu_static &&
                fx->fixels[i].mu_kinetic == first->mu_kinetic &&
                fx->fixels[i].mu_static_min == first->mu_static_min &&
                fx->fixels[i].mu_kinetic_min == first->mu_kinetic_min;
    char s[32], k[32];
    coefficient_text(first->mu_static_min, first->mu_static, s, sizeof s);
    coefficient_text(first->mu_kinetic_min, first->mu_kinetic, k, sizeof k);
    if (!same)
        snprintf(out, size, "\xce\xbc per fixel");
    else if (first->mu_kinetic != first->mu_static || first->mu_kinetic_min != first->mu_static_min)
        snprintf(out, size, "\xce\xbc_s = %s, \xce\xbc_k = %s", s, k);
    else
        snprintf(out, size, "\xce\xbc = %s", s);
}

static void end(FILE *out) { fputs("</svg>\n", out); }

/* An arc of a circle on the page from angle a to b (degrees, counter-
 * clockwise in the fixture's frame), as path data. */
static void arc_path(FILE *out, const frame *f, const double centre[2], double radius, double a,
                     double b)
{
    double ra = a * PI / 180, rb = b * PI / 180;
    double r = radius * f->scale;
    /* With y flipped, counter-clockwise in the fixture is sweep-flag 0. */
    fprintf(out, "M %.2f %.2f A %.2f %.2f 0 %d 0 %.2f %.2f",
            page_x(f, centre[0] + radius * cos(ra)), page_y(f, centre[1] + radius * sin(ra)), r, r,
            b - a > 180 ? 1 : 0, page_x(f, centre[0] + radius * cos(rb)),
            page_y(f, centre[1] + radius * sin(rb)));
}

/* What a set's region promises, for the legend: G_goal reaches every fixel
 * but does not promise the part then rests (on a part two fixels do not
 * pin it slides on along them), G_strong holds the part only once seated;
 * what to push with and let go is "both". */
const char *wc_set_promise(const char *set)
{
    if (strcmp(set, "goal") == 0)
        return "goal: reaches every fixel, then the part may slide on; to push and let go, use "
               "set both";
    if (strcmp(set, "strong") == 0)
        return "strong: holds the part once seated, may not seat it; to push and let go, use "
               "set both";
    return "both: seats the part from any contact state and holds it: push here and let go";
}

void wc_svg_push(FILE *out, const wr_fixture *fx, const char *name, const char *set,
                 const wr_region *regions, int count, double fraction, double finger_friction,
                 double finger_radius)
{
    frame f = frame_for(fx, 0.2, 4);
    char text[256], mu[96];
    snprintf(text, sizeof text, "%s: push region of G_%s", name, set);
    begin(out, &f, text, fx);
    outline(out, &f, fx);
    for (int i = 0; i < count; i++) {
        const wr_region *r = &regions[i];
        size_t loop, segment;
        bool on_outline = fx->shape == WR_SHAPE_OUTLINE && fx->outline;
        if (on_outline && !edge_place(fx->outline, r->edge, &loop, &segment))
            continue; /* no such segment: nothing to draw */
        fputs("<path class=\"region\" d=\"", out);
        if (fx->shape == WR_SHAPE_CIRCLE) {
            arc_path(out, &f, fx->center, fx->radius, r->t0, r->t1);
        } else if (on_outline) {
            /* Along its segment: on an arc, an arc. */
            double a[2];
            wr_outline_boundary(fx->outline, loop, segment, r->t0, a, NULL);
            fprintf(out, "M " OUTLINE_XY, page_x(&f, a[0]), page_y(&f, a[1]));
            segment_to(out, &f, fx->outline, loop, segment, r->t0, r->t1);
        } else {
            double a[2], b[2], n[2];
            wr_boundary_point(fx, r->edge, r->t0, a, n);
            wr_boundary_point(fx, r->edge, r->t1, b, n);
            fprintf(out, "M %.2f %.2f L %.2f %.2f", page_x(&f, a[0]), page_y(&f, a[1]),
                    page_x(&f, b[0]), page_y(&f, b[1]));
        }
        fputs("\" fill=\"none\" stroke=\"black\" stroke-width=\"7\"/>\n", out);
    }
    fixels(out, &f, fx, NULL);
    centre_of_mass(out, &f, fx);
    friction_text(fx, mu, sizeof mu);
    snprintf(text, sizeof text, "%s, set %s: push here (thick black) with a %s finger", name, set,
             finger_friction > 0 ? "frictional" : "frictionless");
    legend(out, 0, text);
    int used;
    if (finger_friction > 0)
        used = snprintf(text, sizeof text, "fixel friction %s; finger friction %g", mu,
                        finger_friction);
    else
        used = snprintf(text, sizeof text, "fixel friction %s", mu);
    if (finger_radius >= 0 && used > 0 && (size_t)used < sizeof text)
        snprintf(text + used, sizeof text - (size_t)used, "; finger radius %g", finger_radius);
    legend(out, 1, text);
    if (count)
        snprintf(text, sizeof text, "%d region%s, %.1f%% of the outline", count,
                 count == 1 ? "" : "s", fraction * 100);
    else
        snprintf(text, sizeof text, "no push region: no point of the outline will do");
    legend(out, 2, text);
    legend(out, 3, wc_set_promise(set));
    end(out);
}

/* Blue (#1f4e9c) at 0 to red (#c0392b) at 1. */
static void band_colour(double x, char colour[8])
{
    x = fmin(fmax(x, 0), 1);
    snprintf(colour, 8, "#%02x%02x%02x", (int)(0x1f + x * (0xc0 - 0x1f)),
             (int)(0x4e + x * (0x39 - 0x4e)), (int)(0x9c + x * (0x2b - 0x9c)));
}

void wc_svg_push_force(FILE *out, const wr_fixture *fx, const char *name, const char *set,
                       const wc_force_band *bands, int band_count, const double at[2],
                       const double direction[2], double least, const char *unit)
{
    frame f = frame_for(fx, 0.3, 4);
    char text[256];
    snprintf(text, sizeof text, "%s: least push force, set %s", name, set);
    begin(out, &f, text, fx);
    outline(out, &f, fx);
    double lo = INFINITY, hi = -INFINITY;
    for (int b = 0; b < band_count; b++)
        for (int j = 0; j < bands[b].count; j++)
            if (isfinite(bands[b].force[j])) {
                lo = fmin(lo, bands[b].force[j]);
                hi = fmax(hi, bands[b].force[j]);
            }
    double top = fx->shape == WR_SHAPE_CIRCLE ? 360 : 1;
    for (int b = 0; b < band_count; b++) {
        const wc_force_band *band = &bands[b];
        size_t loop = 0, segment = 0;
        if (fx->shape == WR_SHAPE_OUTLINE && !edge_place(fx->outline, band->edge, &loop, &segment))
            continue;
        for (int j = 0; j < band->count; j++) {
            /* The sample's stretch: halfway to its neighbours. */
            double t0 = j == 0 ? 0 : (band->t[j - 1] + band->t[j]) / 2;
            double t1 = j + 1 == band->count ? top : (band->t[j] + band->t[j + 1]) / 2;
            char colour[8] = "#cccccc";
            bool finite = isfinite(band->force[j]);
            if (finite)
                band_colour(hi > lo ? (band->force[j] - lo) / (hi - lo) : 0, colour);
            fputs("<path class=\"force-band\" d=\"", out);
            if (fx->shape == WR_SHAPE_CIRCLE) {
                arc_path(out, &f, fx->center, fx->radius, t0, t1);
            } else if (fx->shape == WR_SHAPE_OUTLINE) {
                double a[2];
                wr_outline_boundary(fx->outline, loop, segment, t0, a, NULL);
                fprintf(out, "M " OUTLINE_XY, page_x(&f, a[0]), page_y(&f, a[1]));
                segment_to(out, &f, fx->outline, loop, segment, t0, t1);
            } else {
                double a[2], c[2], n[2];
                wr_boundary_point(fx, band->edge, t0, a, n);
                wr_boundary_point(fx, band->edge, t1, c, n);
                fprintf(out, "M %.2f %.2f L %.2f %.2f", page_x(&f, a[0]), page_y(&f, a[1]),
                        page_x(&f, c[0]), page_y(&f, c[1]));
            }
            fprintf(out, "\" fill=\"none\" stroke=\"%s\" stroke-width=\"9\"%s/>\n", colour,
                    finite ? "" : " stroke-dasharray=\"4 4\"");
        }
    }
    fixels(out, &f, fx, NULL);
    centre_of_mass(out, &f, fx);
    if (isfinite(least)) {
        /* The least push: an arrow onto the point, along the push. */
        double length = 0.25 * f.size;
        double tail[2] = {at[0] - length * direction[0], at[1] - length * direction[1]};
        fprintf(out,
                "<line class=\"least-push\" x1=\"%.2f\" y1=\"%.2f\" x2=\"%.2f\" y2=\"%.2f\" "
                "stroke=\"#1f4e9c\" stroke-width=\"3\" marker-end=\"url(#arrow-1f4e9c)\"/>\n",
                page_x(&f, tail[0]), page_y(&f, tail[1]), page_x(&f, at[0]), page_y(&f, at[1]));
        fprintf(out, "<text x=\"%.2f\" y=\"%.2f\" fill=\"#1f4e9c\">%.4g %s</text>\n",
                page_x(&f, tail[0]) + 4, page_y(&f, tail[1]) - 4, least, unit);
        snprintf(text, sizeof text, "%s, set %s: least push %.6g %s at (%.4g, %.4g) (arrow)", name,
                 set, least, unit, at[0], at[1]);
    } else {
        snprintf(text, sizeof text, "%s, set %s: no push of any force does the job", name, set);
    }
    legend(out, 0, text);
    /* The colour scale, drawn as a bar with its ends' values. */
    if (isfinite(lo)) {
        fputs("<defs><linearGradient id=\"force-scale\"><stop offset=\"0\" stop-color=\"#1f4e9c\"/>"
              "<stop offset=\"1\" stop-color=\"#c0392b\"/></linearGradient></defs>\n",
              out);
        fprintf(out, "<rect class=\"force-scale\" x=\"12\" y=\"%d\" width=\"200\" height=\"10\" "
                     "fill=\"url(#force-scale)\"/>\n",
                22 + 18 * 1 - 10);
        snprintf(text, sizeof text, "%*s%.4g to %.4g %s (least force F* along the outline)", 36,
                 "", lo, hi, unit);
        legend(out, 1, text);
    }
    legend(out, 2, "grey dashes: no push of any force does the job there");
    legend(out, 3, wc_set_promise(set));
    end(out);
}

void wc_svg_gravity(FILE *out, const wr_fixture *fx, const char *name, const char *set,
                    const wr_region *arcs, int count)
{
    /* The part in the middle, the dial around it. */
    frame f = frame_for(fx, 0.8, 4);
    double lo[2], hi[2];
    bounds(fx, lo, hi);
    double centre[2] = {(lo[0] + hi[0]) / 2, (lo[1] + hi[1]) / 2};
    double radius = 0.5 * hypot(hi[0] - lo[0], hi[1] - lo[1]) + 0.2 * f.size;
    char text[256], mu[96];
    snprintf(text, sizeof text, "%s: gravity sweep of G_%s", name, set);
    begin(out, &f, text, fx);
    fprintf(out,
            "<circle class=\"dial\" cx=\"%.2f\" cy=\"%.2f\" r=\"%.2f\" fill=\"none\" "
            "stroke=\"#a0a0a0\" stroke-width=\"3\"/>\n",
            page_x(&f, centre[0]), page_y(&f, centre[1]), radius * f.scale);
    for (int degrees = 0; degrees < 360; degrees += 30) {
        double a = degrees * PI / 180, u[2] = {cos(a), sin(a)};
        fprintf(out,
                "<line x1=\"%.2f\" y1=\"%.2f\" x2=\"%.2f\" y2=\"%.2f\" stroke=\"#a0a0a0\"/>\n",
                page_x(&f, centre[0] + 0.95 * radius * u[0]),
                page_y(&f, centre[1] + 0.95 * radius * u[1]),
                page_x(&f, centre[0] + 1.05 * radius * u[0]),
                page_y(&f, centre[1] + 1.05 * radius * u[1]));
        fprintf(out,
                "<text x=\"%.2f\" y=\"%.2f\" font-size=\"12\" fill=\"#666\" "
                "text-anchor=\"middle\">%d\xc2\xb0</text>\n",
                page_x(&f, centre[0] + 1.15 * radius * u[0]),
                page_y(&f, centre[1] + 1.15 * radius * u[1]) + 4, degrees);
    }
    for (int i = 0; i < count; i++) {
        fputs("<path class=\"region\" d=\"", out);
        arc_path(out, &f, centre, radius, arcs[i].t0, arcs[i].t1);
        fputs("\" fill=\"none\" stroke=\"black\" stroke-width=\"9\"/>\n", out);
    }
    outline(out, &f, fx);
    fixels(out, &f, fx, NULL);
    centre_of_mass(out, &f, fx);
    friction_text(fx, mu, sizeof mu);
    snprintf(text, sizeof text, "%s, set %s, %s", name, set, mu);
    legend(out, 0, text);
    legend(out, 1, "thick black: the directions gravity may pull in (the part's frame)");
    if (count == 0) {
        legend(out, 2, "no tilt: gravity alone never does it");
    } else {
        double total = 0;
        for (int i = 0; i < count; i++)
            total += arcs[i].t1 - arcs[i].t0;
        snprintf(text, sizeof text, "%d arc%s, %.1f\xc2\xb0 in all", count, count == 1 ? "" : "s",
                 total);
        legend(out, 2, text);
    }
    legend(out, 3, wc_set_promise(set));
    end(out);
}

/* A wrench as an arrow on its line of action: the point of that line
 * nearest the centre of mass is (tau / |f|^2) (f_y, -f_x) from it. */
static void wrench_arrow(FILE *out, const frame *f, const wr_fixture *fx, const double w[3],
                         const char *colour, const char *dash)
{
    double force = hypot(w[0], w[1]);
    double length = 0.35 * f->size;
    if (force < 1e-12 * (fabs(w[2]) + 1)) {
        /* A pure torque: a curved arrow around the centre of mass. */
        double r = 0.15 * f->size, c[2] = {fx->com[0], fx->com[1]};
        double a = w[2] > 0 ? 30 : 150, b = w[2] > 0 ? 150 : 30;
        fprintf(out, "<path d=\"");
        arc_path(out, f, c, r, fmin(a, b), fmax(a, b));
        fprintf(out, "\" fill=\"none\" stroke=\"#%s\" stroke-width=\"3\" %s %s=\"url(#arrow-%s)\"/>\n",
                colour, dash, w[2] > 0 ? "marker-end" : "marker-start", colour);
        return;
    }
    double k = w[2] / (force * force);
    double tip[2] = {fx->com[0] + k * w[1], fx->com[1] - k * w[0]};
    double tail[2] = {tip[0] - length * w[0] / force, tip[1] - length * w[1] / force};
    fprintf(out,
            "<line x1=\"%.2f\" y1=\"%.2f\" x2=\"%.2f\" y2=\"%.2f\" stroke=\"#%s\" "
            "stroke-width=\"3\" %s marker-end=\"url(#arrow-%s)\"/>\n",
            page_x(f, tail[0]), page_y(f, tail[1]), page_x(f, tip[0]), page_y(f, tip[1]), colour,
            dash, colour);
}

void wc_svg_margin(FILE *out, const wr_fixture *fx, const char *name, const double bias[3],
                   double margin, const double worst[3], const char *blocking)
{
    frame f = frame_for(fx, 0.5, 3);
    char text[256], mu[96];
    snprintf(text, sizeof text, "%s: disturbance margin", name);
    begin(out, &f, text, fx);
    outline(out, &f, fx);
    fixels(out, &f, fx, NULL);
    centre_of_mass(out, &f, fx);
    wrench_arrow(out, &f, fx, bias, "1f4e9c", "");
    if (blocking)
        wrench_arrow(out, &f, fx, worst, "c0392b", "stroke-dasharray=\"8 5\"");
    friction_text(fx, mu, sizeof mu);
    snprintf(text, sizeof text, "%s, %s: the biasing wrench (blue) on its line of action", name,
             mu);
    legend(out, 0, text);
    if (!blocking) {
        legend(out, 1, "no contact mode moves the part: any disturbance is held");
    } else {
        snprintf(text, sizeof text,
                 margin > 0 ? "held against any disturbance smaller than %.4g (scaled metric)"
                            : "not held: %.4g inside G_strong's excluded cones",
                 fabs(margin));
        legend(out, 1, text);
        snprintf(text, sizeof text, "dashed red: the worst disturbance, which starts mode %s",
                 blocking);
        legend(out, 2, text);
    }
    end(out);
}

void wc_svg_force(FILE *out, const wr_fixture *fx, const char *name, const double *push,
                  double least, const char *unit)
{
    frame f = frame_for(fx, 0.5, 3);
    char text[256], mu[96];
    snprintf(text, sizeof text, "%s: the least push force", name);
    begin(out, &f, text, fx);
    outline(out, &f, fx);
    fixels(out, &f, fx, NULL);
    centre_of_mass(out, &f, fx);
    if (push)
        wrench_arrow(out, &f, fx, push, "1f4e9c", "");
    friction_text(fx, mu, sizeof mu);
    snprintf(text, sizeof text, "%s, %s: the push (blue) on its line of action", name, mu);
    legend(out, 0, text);
    if (isfinite(least))
        snprintf(text, sizeof text, "the least force that seats the part (goal): %.6g %s", least,
                 unit);
    else
        snprintf(text, sizeof text, "no force of this push seats the part");
    legend(out, 1, text);
    if (fx->supports) {
        snprintf(text, sizeof text,
                 "on %d supports (blue squares), mu_B %.4g: dashed, each one's friction disc "
                 "|f| <= mu_B N_i to scale",
                 fx->supports->count, fx->supports->mu_static);
        legend(out, 2, text);
    }
    end(out);
}

/* ---- designs side by side ------------------------------------------------------- */

#define PANEL_WIDTH 420.0
#define PANEL_COLUMNS 3

/* One design in the page's frame of WIDTH (its group scales it down). */
static void design_panel(FILE *out, const frame *f, const wc_design_panel *p)
{
    const wr_fixture *fx = p->fixture;
    outline(out, f, fx);
    for (int i = 0; i < p->region_count; i++) {
        const wr_region *r = &p->regions[i];
        size_t loop, segment;
        bool on_outline = fx->shape == WR_SHAPE_OUTLINE && fx->outline;
        if (on_outline && !edge_place(fx->outline, r->edge, &loop, &segment))
            continue;
        fputs("<path class=\"region\" d=\"", out);
        if (fx->shape == WR_SHAPE_CIRCLE) {
            arc_path(out, f, fx->center, fx->radius, r->t0, r->t1);
        } else if (on_outline) {
            double a[2];
            wr_outline_boundary(fx->outline, loop, segment, r->t0, a, NULL);
            fprintf(out, "M " OUTLINE_XY, page_x(f, a[0]), page_y(f, a[1]));
            segment_to(out, f, fx->outline, loop, segment, r->t0, r->t1);
        } else {
            double a[2], b[2], n[2];
            wr_boundary_point(fx, r->edge, r->t0, a, n);
            wr_boundary_point(fx, r->edge, r->t1, b, n);
            fprintf(out, "M %.2f %.2f L %.2f %.2f", page_x(f, a[0]), page_y(f, a[1]),
                    page_x(f, b[0]), page_y(f, b[1]));
        }
        fputs("\" fill=\"none\" stroke=\"black\" stroke-width=\"7\"/>\n", out);
    }
    for (int m = 0; p->lattice && m < 3; m++)
        fprintf(out,
                "<circle class=\"peg\" cx=\"%.2f\" cy=\"%.2f\" r=\"%.2f\" fill=\"#bbb\" "
                "stroke=\"#444\" stroke-width=\"2\"/>\n",
                page_x(f, p->pegs[m][0]), page_y(f, p->pegs[m][1]),
                fmax(3, p->peg_radius * f->scale));
    fixels(out, f, fx, p->pin_diameter);
    centre_of_mass(out, f, fx);
    if (p->has_push) {
        /* The finger's push: an arrow ending at the point, along the push. */
        double length = 0.3 * f->size;
        double tail[2] = {p->push_at[0] - length * p->push_direction[0],
                          p->push_at[1] - length * p->push_direction[1]};
        fprintf(out,
                "<line class=\"best-push\" x1=\"%.2f\" y1=\"%.2f\" x2=\"%.2f\" y2=\"%.2f\" "
                "stroke=\"#c0392b\" stroke-width=\"5\" marker-end=\"url(#arrow-c0392b)\"/>\n",
                page_x(f, tail[0]), page_y(f, tail[1]), page_x(f, p->push_at[0]),
                page_y(f, p->push_at[1]));
    }
}

void wc_svg_designs(FILE *out, const char *name, const char *objective,
                    const wc_design_panel *panels, int count)
{
    int columns = count < PANEL_COLUMNS ? (count > 0 ? count : 1) : PANEL_COLUMNS;
    int rows = (count + columns - 1) / columns;
    double scale = PANEL_WIDTH / WIDTH;
    /* Every panel as tall as the tallest. */
    double tallest = 0;
    for (int i = 0; i < count; i++) {
        frame f = frame_for(panels[i].fixture, 0.35, 2);
        tallest = fmax(tallest, f.height * scale);
    }
    double top = 66, width = columns * PANEL_WIDTH, height = top + rows * tallest + 10;
    fprintf(out,
            "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
            "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%.0f\" height=\"%.0f\" "
            "viewBox=\"0 0 %.0f %.0f\" font-family=\"sans-serif\" font-size=\"14\">\n<title>",
            width, height, width, height);
    text_escaped(out, name);
    fputs(": designs</title>\n<defs>", out);
    fputs("<marker id=\"arrow-c0392b\" viewBox=\"0 0 10 10\" refX=\"9\" refY=\"5\" "
          "markerWidth=\"4\" markerHeight=\"4\" orient=\"auto-start-reverse\">"
          "<path d=\"M 0 0 L 10 5 L 0 10 z\" fill=\"#c0392b\"/></marker>",
          out);
    fputs("</defs>\n<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n", out);
    units_note(out, width - 12, height - 4, count > 0 ? panels[0].fixture : NULL);
    char text[256];
    snprintf(text, sizeof text, "%s: the best %d design%s by %s, best first", name, count,
             count == 1 ? "" : "s", objective);
    legend(out, 0, text);
    legend(out, 1, "thick black: the both region; red arrow: the best push (largest margin) -");
    legend(out, 2, "push there and let go: goal seats the part, strong then holds it");
    for (int i = 0; i < count; i++) {
        const wc_design_panel *p = &panels[i];
        frame f = frame_for(p->fixture, 0.35, 2);
        double x = (i % columns) * PANEL_WIDTH, y = top + (i / columns) * tallest;
        fprintf(out, "<g class=\"design\" transform=\"translate(%.2f %.2f) scale(%.4f)\">\n", x,
                y, scale);
        fprintf(out,
                "<rect x=\"4\" y=\"4\" width=\"%.0f\" height=\"%.0f\" fill=\"none\" "
                "stroke=\"#ddd\" stroke-width=\"2\"/>\n",
                WIDTH - 8, tallest / scale - 8);
        design_panel(out, &f, p);
        if (p->has_push)
            snprintf(text, sizeof text, "#%d  score %.6g  best push margin %.4g", p->rank,
                     p->score, p->margin);
        else
            snprintf(text, sizeof text, "#%d  score %.6g  no both region: no push to let go",
                     p->rank, p->score);
        fprintf(out, "<text x=\"16\" y=\"30\" font-size=\"22\">");
        text_escaped(out, text);
        fputs("</text>\n", out);
        if (p->lattice) {
            snprintf(text, sizeof text, "pegs in holes (%d, %d) (%d, %d) (%d, %d)", p->holes[0][0],
                     p->holes[0][1], p->holes[1][0], p->holes[1][1], p->holes[2][0],
                     p->holes[2][1]);
            fprintf(out, "<text x=\"16\" y=\"56\" font-size=\"20\">");
            text_escaped(out, text);
            fputs("</text>\n", out);
        }
        fputs("</g>\n", out);
    }
    end(out);
}

/* ---- friction sweeps: plots against mu ------------------------------------------ */

#define PLOT_LEFT 80.0
#define PLOT_RIGHT 24.0
#define PLOT_HEIGHT 300.0
#define PLOT_BOTTOM 64.0 /* below the plot: tick labels and the axis's title */

/* A round step near span / parts: 1, 2 or 5 times a power of ten. */
static double round_step(double span, int parts)
{
    double raw = span / parts;
    if (!(raw > 0) || !isfinite(raw))
        return 1;
    double power = pow(10, floor(log10(raw)));
    double ratio = raw / power;
    return (ratio < 1.5 ? 1 : ratio < 3.5 ? 2 : ratio < 7.5 ? 5 : 10) * power;
}

/* The plot's horizontal axis: mu over range, from x = PLOT_LEFT. */
typedef struct axis {
    double low, high; /* the values at either end */
    double from, to;  /* the page coordinates of low and high */
} axis;

static double on_axis(const axis *a, double value)
{
    return a->from + (value - a->low) / (a->high - a->low) * (a->to - a->from);
}

/* The mu axis along y = `bottom`: its line, round ticks and their values,
 * and its title below. */
static void mu_axis(FILE *out, const axis *x, double bottom, double kinetic_ratio)
{
    fprintf(out,
            "<line class=\"axis\" x1=\"%.2f\" y1=\"%.2f\" x2=\"%.2f\" y2=\"%.2f\" "
            "stroke=\"black\" stroke-width=\"1.5\"/>\n",
            x->from, bottom, x->to, bottom);
    double step = round_step(x->high - x->low, 5);
    for (double k = ceil(x->low / step - 1e-9); k * step <= x->high + 1e-9 * step; k++) {
        double value = k == 0 ? 0 : k * step; /* not -0 */
        double px = on_axis(x, value);
        fprintf(out,
                "<line x1=\"%.2f\" y1=\"%.2f\" x2=\"%.2f\" y2=\"%.2f\" stroke=\"black\"/>\n"
                "<text x=\"%.2f\" y=\"%.2f\" font-size=\"12\" text-anchor=\"middle\">%g</text>\n",
                px, bottom, px, bottom + 5, px, bottom + 19, value);
    }
    char title[128];
    if (kinetic_ratio == 0)
        snprintf(title, sizeof title, "\xce\xbc_B  (the supports' friction)");
    else if (kinetic_ratio == 1)
        snprintf(title, sizeof title, "\xce\xbc  (\xce\xbc_s = \xce\xbc_k = \xce\xbc at every fixel)");
    else
        snprintf(title, sizeof title,
                 "\xce\xbc  (\xce\xbc_s = \xce\xbc, \xce\xbc_k = %g \xce\xbc at every fixel)",
                 kinetic_ratio);
    fprintf(out, "<text x=\"%.2f\" y=\"%.2f\" text-anchor=\"middle\">", (x->from + x->to) / 2,
            bottom + 42);
    text_escaped(out, title);
    fputs("</text>\n", out);
}

/* "[0, 0.5], [0.8, 2]" or "none", for a legend. */
static void intervals_text(const wc_interval *intervals, int count, char *out, size_t size)
{
    size_t n = 0;
    out[0] = 0;
    for (int i = 0; i < count && n < size; i++) {
        int written = snprintf(out + n, size - n, "%s[%g, %g]", i ? ", " : "",
                               intervals[i].low, intervals[i].high);
        n += written > 0 ? (size_t)written : 0;
    }
    if (count == 0)
        snprintf(out, size, "none");
}

void wc_svg_sweep(FILE *out, const wc_sweep_plot *p)
{
    bool push = strcmp(p->what, "push") == 0, force = strcmp(p->what, "force") == 0;
    int lines = 4;
    frame f = {0};
    f.top = 20 + 18 * lines;
    f.height = f.top + 20 + PLOT_HEIGHT + PLOT_BOTTOM;
    char text[512], spans[256];
    snprintf(text, sizeof text, "%s: friction sweep of the %s of G_%s", p->name,
             force ? "least push force" : push ? "push region" : "gravity arcs", p->set);
    begin(out, &f, text, p->fixture);
    double top = f.top + 20, bottom = top + PLOT_HEIGHT;
    axis x = {p->range[0], p->range[1], PLOT_LEFT, WIDTH - PLOT_RIGHT};
    double most = 0;
    for (int i = 0; i < p->curve_count; i++)
        most = fmax(most, p->curve[i][1]);
    double y_step = round_step(most > 0 ? most : 1, 4);
    double y_high = y_step * ceil((most > 0 ? most : 1) / y_step);
    axis y = {0, y_high, bottom, top};
    /* The intervals, shaded behind the rest. */
    for (int i = 0; i < p->interval_count; i++) {
        double a = fmax(p->intervals[i].low, x.low), b = fmin(p->intervals[i].high, x.high);
        fprintf(out,
                "<rect class=\"interval\" x=\"%.2f\" y=\"%.2f\" width=\"%.2f\" height=\"%.2f\" "
                "fill=\"#1f4e9c\" fill-opacity=\"0.15\"/>\n",
                on_axis(&x, a), top, fmax(0, on_axis(&x, b) - on_axis(&x, a)), PLOT_HEIGHT);
    }
    /* The vertical axis, its ticks and title. */
    fprintf(out,
            "<line class=\"axis\" x1=\"%.2f\" y1=\"%.2f\" x2=\"%.2f\" y2=\"%.2f\" "
            "stroke=\"black\" stroke-width=\"1.5\"/>\n",
            x.from, bottom, x.from, top);
    for (double k = 0; k * y_step <= y_high + 1e-9 * y_step; k++) {
        double py = on_axis(&y, k * y_step);
        fprintf(out,
                "<line x1=\"%.2f\" y1=\"%.2f\" x2=\"%.2f\" y2=\"%.2f\" stroke=\"black\"/>\n"
                "<text x=\"%.2f\" y=\"%.2f\" font-size=\"12\" text-anchor=\"end\">%g</text>\n",
                x.from - 5, py, x.from, py, x.from - 8, py + 4, k * y_step);
    }
    char axis[64] = "push region length";
    if (force)
        snprintf(axis, sizeof axis, "least push force (%s)", p->force_unit);
    else if (length_unit(p->fixture))
        snprintf(axis, sizeof axis, "push region length (%s)", length_unit(p->fixture));
    fprintf(out,
            "<text x=\"%.2f\" y=\"%.2f\" text-anchor=\"middle\" "
            "transform=\"rotate(-90 %.2f %.2f)\">%s</text>\n",
            22.0, (top + bottom) / 2, 22.0, (top + bottom) / 2,
            push || force ? axis : "gravity arcs (\xc2\xb0)");
    mu_axis(out, &x, bottom, p->kinetic_ratio);
    /* The curve: a polyline per run of points with a value (a force
     * sweep's is none where no push does the job). */
    for (int i = 0; i < p->curve_count;) {
        if (isnan(p->curve[i][1])) {
            i++;
            continue;
        }
        fputs("<polyline class=\"curve\" points=\"", out);
        for (int first = i; i < p->curve_count && !isnan(p->curve[i][1]); i++)
            fprintf(out, "%s%.2f,%.2f", i > first ? " " : "", on_axis(&x, p->curve[i][0]),
                    on_axis(&y, p->curve[i][1]));
        fputs("\" fill=\"none\" stroke=\"black\" stroke-width=\"2.5\" "
              "stroke-linejoin=\"round\"/>\n",
              out);
    }
    /* The critical mu. */
    if (isfinite(p->critical)) {
        double px = on_axis(&x, p->critical);
        fprintf(out,
                "<line class=\"critical\" x1=\"%.2f\" y1=\"%.2f\" x2=\"%.2f\" y2=\"%.2f\" "
                "stroke=\"#c0392b\" stroke-width=\"2\" stroke-dasharray=\"6 4\"/>\n",
                px, top, px, bottom);
        bool right = px > (x.from + x.to) / 2;
        fprintf(out,
                "<text class=\"critical\" x=\"%.2f\" y=\"%.2f\" fill=\"#c0392b\" "
                "text-anchor=\"%s\">critical \xce\xbc = %g</text>\n",
                px + (right ? -6 : 6), top + 16, right ? "end" : "start", p->critical);
    }
    snprintf(text, sizeof text, "%s, set %s: %s against the friction \xce\xbc", p->name, p->set,
             force  ? "the least push force under every case (exact at each \xce\xbc drawn)"
             : push ? "the push region's length"
                    : "the gravity arcs, in degrees,");
    legend(out, 0, text);
    intervals_text(p->intervals, p->interval_count, spans, sizeof spans);
    if (force)
        snprintf(text, sizeof text, "shaded: \xce\xbc where the push alone has a region (a "
                 "large enough push does it whatever the loads): %s", spans);
    else
        snprintf(text, sizeof text, "shaded: \xce\xbc where the %s is not empty: %s",
                 push ? "push region" : "gravity sweep", spans);
    legend(out, 1, text);
    if (force)
        snprintf(text, sizeof text, "no line: no push does the job under every case");
    else if (!isfinite(p->critical))
        snprintf(text, sizeof text,
                 "not empty at the top of the range, \xce\xbc = %g: no critical \xce\xbc",
                 p->range[1]);
    else if (p->interval_count == 0)
        snprintf(text, sizeof text, "red: empty for every \xce\xbc from %g to %g", p->range[0],
                 p->range[1]);
    else
        snprintf(text, sizeof text, "red: the critical \xce\xbc = %g, above which it is empty",
                 p->critical);
    legend(out, 2, text);
    legend(out, 3, wc_set_promise(p->set));
    end(out);
}

#define BAND_HEIGHT 26.0
/* A band's label is right-aligned before it; at 13 px a character of it is
 * at most about 7.5 px wide, and the plot keeps at least half the page. */
#define LABEL_CHAR 7.5

void wc_svg_sweep_bands(FILE *out, const char *name, const double range[2], double kinetic_ratio,
                        const wc_sweep_band *bands, int count, const char *const *sets,
                        int set_count)
{
    int lines = 2 + set_count;
    frame f = {0};
    f.top = 20 + 18 * lines;
    f.height = f.top + 20 + BAND_HEIGHT * count + PLOT_BOTTOM;
    char text[256];
    snprintf(text, sizeof text, "%s: friction sweep of wrenches", name);
    begin(out, &f, text, NULL);
    double top = f.top + 20, bottom = top + BAND_HEIGHT * count;
    size_t longest = 0;
    for (int i = 0; i < count; i++) {
        size_t length = strlen(bands[i].label) + 2 + strlen(bands[i].set);
        longest = length > longest ? length : longest;
    }
    double left = fmin(WIDTH / 2.0, 20 + LABEL_CHAR * (double)longest);
    axis x = {range[0], range[1], left, WIDTH - PLOT_RIGHT};
    for (int i = 0; i < count; i++) {
        double y = top + BAND_HEIGHT * i;
        fprintf(out,
                "<rect class=\"band\" x=\"%.2f\" y=\"%.2f\" width=\"%.2f\" height=\"%.2f\" "
                "fill=\"#f2f2f2\" stroke=\"#a0a0a0\"/>\n",
                x.from, y + 3, x.to - x.from, BAND_HEIGHT - 6);
        for (int j = 0; j < bands[i].count; j++) {
            double a = fmax(bands[i].intervals[j].low, x.low);
            double b = fmin(bands[i].intervals[j].high, x.high);
            fprintf(out,
                    "<rect class=\"inside\" x=\"%.2f\" y=\"%.2f\" width=\"%.2f\" height=\"%.2f\" "
                    "fill=\"black\"/>\n",
                    on_axis(&x, a), y + 6, fmax(0, on_axis(&x, b) - on_axis(&x, a)),
                    BAND_HEIGHT - 12);
        }
        fprintf(out, "<text x=\"%.2f\" y=\"%.2f\" font-size=\"13\" text-anchor=\"end\">",
                x.from - 8, y + BAND_HEIGHT / 2 + 5);
        text_escaped(out, bands[i].label);
        fprintf(out, "  %s</text>\n", bands[i].set);
    }
    mu_axis(out, &x, bottom, kinetic_ratio);
    snprintf(text, sizeof text,
             "%s: where each wrench is inside each set, against the friction \xce\xbc", name);
    legend(out, 0, text);
    legend(out, 1, "black: \xce\xbc where the wrench is inside the set");
    for (int i = 0; i < set_count; i++)
        legend(out, 2 + i, wc_set_promise(sets[i]));
    end(out);
}

/* ---- locating accuracy -------------------------------------------------------- */

/* The part moved by `pose` (dx, dy, dtheta about the centre of mass), dashed:
 * a rotation by dtheta in the fixture's frame is one by -dtheta on the page
 * (y down), about the centre of mass, then the translation. */
static void displaced_outline(FILE *out, const frame *f, const wr_fixture *fx, const double pose[3])
{
    double cx = page_x(f, fx->com[0]), cy = page_y(f, fx->com[1]);
    fprintf(out, "<g transform=\"translate(%.4f %.4f) rotate(%.6f %.4f %.4f)\">",
            pose[0] * f->scale, -pose[1] * f->scale, -pose[2] * 180 / PI, cx, cy);
    const char *style = "fill=\"none\" stroke=\"#c0392b\" stroke-width=\"1.5\" "
                        "stroke-dasharray=\"6 4\"";
    if (fx->shape == WR_SHAPE_CIRCLE) {
        fprintf(out, "<circle class=\"displaced\" cx=\"%.2f\" cy=\"%.2f\" r=\"%.2f\" %s/>",
                page_x(f, fx->center[0]), page_y(f, fx->center[1]), fx->radius * f->scale, style);
    } else if (fx->outline) {
        fputs("<path class=\"displaced\" d=\"", out);
        outline_path(out, f, fx->outline);
        fprintf(out, "\" fill-rule=\"evenodd\" %s/>", style);
    }
    fputs("</g>\n", out);
}

void wc_svg_locate(FILE *out, const wr_fixture *fx, const char *name, const wc_locate_mark *marks,
                   int count, const double pose[3], double magnification, const char *tolerance)
{
    frame f = frame_for(fx, 0.15, 4);
    char text[256];
    snprintf(text, sizeof text, "%s: where the part ends up", name);
    begin(out, &f, text, fx);
    outline(out, &f, fx);
    double moved[3] = {magnification * pose[0], magnification * pose[1],
                       magnification * pose[2]};
    displaced_outline(out, &f, fx, moved);
    fixels(out, &f, fx, NULL);
    centre_of_mass(out, &f, fx);
    for (int i = 0; i < count; i++) {
        const wc_locate_mark *m = &marks[i];
        double x = page_x(&f, m->at[0]), y = page_y(&f, m->at[1]);
        fprintf(out,
                "<ellipse class=\"error-ellipse\" cx=\"%.2f\" cy=\"%.2f\" rx=\"%.3f\" ry=\"%.3f\" "
                "transform=\"rotate(%.4f %.2f %.2f)\" fill=\"#1f4e9c\" fill-opacity=\"0.15\" "
                "stroke=\"#1f4e9c\" stroke-width=\"1.5\"/>\n",
                x, y, m->axes[0] * magnification * f.scale, m->axes[1] * magnification * f.scale,
                -m->angle_deg, x, y);
        double tip[2] = {x + m->worst[0] * magnification * f.scale,
                         y - m->worst[1] * magnification * f.scale};
        if (hypot(tip[0] - x, tip[1] - y) >= 1)
            fprintf(out,
                    "<line class=\"worst\" x1=\"%.2f\" y1=\"%.2f\" x2=\"%.2f\" y2=\"%.2f\" "
                    "stroke=\"#c0392b\" stroke-width=\"2\" marker-end=\"url(#arrow-c0392b)\"/>\n",
                    x, y, tip[0], tip[1]);
        fprintf(out, "<circle class=\"feature\" cx=\"%.2f\" cy=\"%.2f\" r=\"3\" fill=\"black\"/>\n",
                x, y);
        if (m->name) {
            fprintf(out, "<text x=\"%.2f\" y=\"%.2f\" font-size=\"13\">", x + 8, y - 8);
            text_escaped(out, m->name);
            fputs("</text>\n", out);
        }
    }
    snprintf(text, sizeof text, "%s, locators off by %s along their normals", name, tolerance);
    legend(out, 0, text);
    snprintf(text, sizeof text,
             "errors magnified %g times: blue, each feature's 99.73 %% ellipse", magnification);
    legend(out, 1, text);
    legend(out, 2, "red arrow: its worst displacement (exact pose, corners of the tolerance box)");
    legend(out, 3, "dashed red: the part at the box's corner that moves it most");
    end(out);
}
