// validate.cpp -- wrenchd's answers checked against Box2D, a rigid-body
// simulator that shares no line with libwrench.
//
//   build/physics-validate [--quick | --full] [--verbose] FIXTURE.json ...
//
// For each fixture: pushes with a frictionless finger at points of the
// G_goal push region (and outside it), gravity at tilts of the G_goal arc
// (and outside it), for discs a seated disc spinning under pushes, and on
// the seated part pushes and wrenches inside and outside G_strong; then a
// friction calibration per coefficient pair.  Prints one line per (fixture,
// set) and a table; exits 1 when a criterion fails, 2 on a usage or input
// error.  docs/VALIDATION.md explains the design, the tolerances and every
// disagreement found; these options reproduce its investigations:
//
//   --friction-factor X   Box2D's friction X times the fixture's (a negative
//                         control: the criteria must then fail)
//   --static-as-kinetic   Box2D's static coefficient set to the kinetic one
//   --chains              convex polygons too given to Box2D as chain loops
//                         (a cross-check of the path non-convex outlines take)
//   --sensor-depth M      the sensor pieces M m inside the outline (below
//                         Box2D's slop they must report, a negative control)
//   --velocity-iterations N  Box2D's velocity iterations (20 otherwise)
//   --sweep N             seating rate along the whole outline, tilts all
//                         round, G_strong margin bins (no criteria)
//     --spin W            ... with the start spinning at +-W rad/s (and, for
//                         a disc, which fixel breaks when spun while seated)
//     --slide V           ... and from each partial contact state, launched
//                         at +-V m/s along the touched fixels
//   --hold-at EDGE T      one holding trial at (EDGE, T), traced
//   --tolerance T[,A]     only the robust both region's pushes (over T along
//                         the outline and A degrees), on fixtures with
//                         contacts displaced within T at random (normals the
//                         surface's, as Box2D's round fixels have them):
//                         every one must seat and hold
//   PHYSICS_TRACE=T       (environment) trace the --sweep trials at T
//
// Everything random comes from a counter-based generator keyed by (fixture
// name, set, point, trial): a run is reproducible, and does not depend on
// the order in which trials run.

#include <box2d/box2d.h>
#include <box2d/b2_distance.h>

#include "wp_fixture.h" // libwrench's headers carry their own extern "C" guards
#include "wrench.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdarg>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <unistd.h>

namespace {

// ---- the parameters of every trial (canonical units: metres, seconds) ----
// The fixture is scaled uniformly so that its size (docs/MODEL.md section 1: a circle's
// diameter, a polygon's bounding-box diagonal) is SIZE metres.  Box2D's
// tolerances are absolute (linear slop 0.005 m, polygon skin 0.01 m), so a
// fixed size makes every run see them in the same proportion.
constexpr double SIZE = 4.0;
constexpr double HZ = 240.0;              // time step 1/240 s
int VELOCITY_ITERATIONS = 20;              // --velocity-iterations N: an investigation
constexpr int POSITION_ITERATIONS = 10;
constexpr double ACCEL = 10.0;            // finger force = mass * ACCEL; |gravity| = ACCEL
constexpr double FIXEL_RADIUS = 0.02 * SIZE;
constexpr double GAP_MAX = 0.02 * SIZE;   // start: gap at a fixel up to 2% of the size
constexpr double TOUCH_PROBABILITY = 0.25; // start: a fixel touches already
constexpr double V0_MAX = 0.1;            // start: |v| <= 0.1 m/s (2.5% of the size per s)
constexpr double W0_MAX = 0.1;            // start: |omega| <= 0.1 rad/s
constexpr double TIME_LIMIT = 10.0;       // s
constexpr double REST_TIME = 0.5;         // s of rest with every fixel touching
constexpr double REST_SPEED = 1e-3 * SIZE; // m/s at the centre of mass
constexpr double REST_SPIN = 1e-3;        // rad/s
constexpr double POSE_TOLERANCE = 0.01 * SIZE;  // m: 1% of the size
constexpr double ANGLE_TOLERANCE = 1.0;   // degrees (polygons: a disc may turn freely)
constexpr double HOLD_TIME = 3.0;         // s under a constant wrench
constexpr double MOVE_TOLERANCE = 2 * b2_linearSlop; // m: 0.01 m = 0.25% of the size
constexpr double SLIP_SPEED = 0.005;      // m/s: faster tangential speed = sliding (mu_k)
constexpr double STRONG_MARGIN = 0.05;    // wrenches "clearly" inside / outside G_strong
// Pushes this close to G_strong's boundary are not asserted to hold: Box2D's
// iterative solver has not converged there in 20 velocity iterations (the
// bracket's pushes at margins +0.0002 and +0.0014 crept 0.013 and 0.011 m,
// 0.0023 m at 200 iterations); docs/VALIDATION.md.
constexpr double HOLD_PUSH_MARGIN = 0.005;
constexpr double PI = 3.14159265358979323846;
constexpr double DEG = 180.0 / PI;

// A negative control: Box2D's friction is the fixture's times this factor
// (the model keeps the fixture's).  1 for every real run.
double friction_factor = 1.0;
// An investigation: Box2D's static coefficient set to the kinetic one.
bool static_as_kinetic = false;

// ---- a counter-based random generator (splitmix64) ----
struct Rng {
    uint64_t state;
    explicit Rng(uint64_t seed) : state(seed) {}
    uint64_t next()
    {
        uint64_t z = (state += 0x9E3779B97F4A7C15ull);
        z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
        z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
        return z ^ (z >> 31);
    }
    double uniform() { return (double)(next() >> 11) * (1.0 / 9007199254740992.0); } // [0, 1)
    double uniform(double a, double b) { return a + (b - a) * uniform(); }
};

uint64_t fnv1a(const std::string &text)
{
    uint64_t h = 1469598103934665603ull;
    for (unsigned char c : text) {
        h ^= c;
        h *= 1099511628211ull;
    }
    return h;
}

uint64_t seed_of(const std::string &fixture, const char *set, int point, int trial)
{
    Rng r(fnv1a(fixture) ^ (fnv1a(set) * 31));
    r.state ^= (uint64_t)point * 0x632BE59BD9B4E019ull + (uint64_t)trial * 0x8CB92BA72F3D8DD7ull;
    r.next();
    return r.next();
}

// ---- small vector helpers (double precision, the model's side) ----
struct V2 {
    double x, y;
};
V2 operator+(V2 a, V2 b) { return {a.x + b.x, a.y + b.y}; }
V2 operator-(V2 a, V2 b) { return {a.x - b.x, a.y - b.y}; }
V2 operator*(double s, V2 a) { return {s * a.x, s * a.y}; }
double dot(V2 a, V2 b) { return a.x * b.x + a.y * b.y; }
double cross(V2 a, V2 b) { return a.x * b.y - a.y * b.x; }
double norm(V2 a) { return std::hypot(a.x, a.y); }
V2 rotate(V2 a, double th) { return {std::cos(th) * a.x - std::sin(th) * a.y, std::sin(th) * a.x + std::cos(th) * a.y}; }
b2Vec2 b2(V2 a) { return b2Vec2((float)a.x, (float)a.y); }
V2 v2(b2Vec2 a) { return {a.x, a.y}; }

std::string fmt(const char *format, ...) __attribute__((format(printf, 1, 2)));
std::string fmt(const char *format, ...)
{
    char buf[512];
    va_list args;
    va_start(args, format);
    std::vsnprintf(buf, sizeof buf, format, args);
    va_end(args);
    return buf;
}

// Intersection of the lines a + s u and b + t v.
V2 intersect(V2 a, V2 u, V2 b, V2 v)
{
    double s = cross(b - a, v) / cross(u, v);
    return a + s * u;
}

// ---- outlines that are not one convex polygon: exact loops, their polyline
// approximation, Box2D chain loops, and convex pieces ----
//
// A non-convex polygon (and, later, an outline of lines and arcs with holes)
// is given to Box2D as one b2ChainShape loop per boundary loop, inset by the
// skin: chains are one-sided, their edges' ghost vertices hand a contact
// over smoothly from one edge to the next, and they have no interior, so no
// internal edge exists for a fixel to touch.  The convex pieces of a
// decomposition (ear clipping, then Hertel-Mehlhorn merging within
// b2_maxPolygonVertices) ride on the same body as sensors, shrunk well
// inside the outline: they take part in no contact's response, and a fixel
// that ever overlaps one has sunk DEEP_PENETRATION into the part, which
// fails the row.  Mass, centre of mass and inertia are the fixture's
// (SetMassData); the pieces' areas are checked against the outline's.

// Arcs become polylines whose edges are tangent to the arc (circumscribed):
// at each tangent point the polyline touches the arc with the arc's own
// normal, and every fixel on an arc is made a tangent point.  Between
// tangent points an angle Delta apart the polyline's vertex lies
// r (sec(Delta / 2) - 1) outside the arc: at most ARC_DEVIATION.
constexpr double ARC_DEVIATION = 1e-4 * SIZE;   // m: 1e-4 of the size
// m: a sensor piece's depth (--sensor-depth: the detector's negative control)
double DEEP_PENETRATION = 4 * b2_linearSlop;
// Near a fixel (within its radius plus GAP_MAX of its circle's centre) the
// boundary must be one piece without a concave corner, turning by less
// than 90 degrees: elsewhere the circle could touch the part twice.
constexpr double CLEARANCE = GAP_MAX;
// Force the chain path on convex polygons too (a cross-check of it).
bool force_chains = false;

struct Seg {
    V2 a, b;         // from a to b, the material on the left
    bool arc = false;
    V2 c{};          // arc: centre, radius, start angle, signed sweep
    double r = 0, a0 = 0, sweep = 0;
};

V2 seg_point(const Seg &s, double t)
{
    if (!s.arc)
        return s.a + t * (s.b - s.a);
    double phi = s.a0 + t * s.sweep;
    return s.c + s.r * V2{std::cos(phi), std::sin(phi)};
}

// Unit tangent along the direction of travel, and the normal into the
// material (its left).
V2 seg_tangent(const Seg &s, double t)
{
    if (!s.arc) {
        V2 e = s.b - s.a;
        return (1.0 / norm(e)) * e;
    }
    double phi = s.a0 + t * s.sweep, sg = s.sweep > 0 ? 1 : -1;
    return {-sg * std::sin(phi), sg * std::cos(phi)};
}
V2 seg_normal(const Seg &s, double t)
{
    V2 u = seg_tangent(s, t);
    return {-u.y, u.x};
}
double seg_length(const Seg &s) { return s.arc ? s.r * std::fabs(s.sweep) : norm(s.b - s.a); }

// The parameter of the point of s nearest to q, and the distance.
double seg_nearest(const Seg &s, V2 q, double *t)
{
    if (!s.arc) {
        V2 e = s.b - s.a;
        double u = std::clamp(dot(q - s.a, e) / dot(e, e), 0.0, 1.0);
        *t = u;
        return norm(q - (s.a + u * e));
    }
    double ang = std::atan2(q.y - s.c.y, q.x - s.c.x);
    double d = s.sweep > 0 ? ang - s.a0 : s.a0 - ang;
    d = std::fmod(d, 2 * PI);
    if (d < 0)
        d += 2 * PI;
    if (d <= std::fabs(s.sweep)) {
        *t = d / std::fabs(s.sweep);
        return std::fabs(norm(q - s.c) - s.r);
    }
    double da = norm(q - s.a), db = norm(q - s.b);
    *t = da <= db ? 0 : 1;
    return std::min(da, db);
}

// Is q inside the closed polyline `poly` (crossing number)?
bool inside_polyline(const std::vector<V2> &poly, V2 q)
{
    bool in = false;
    for (size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++) {
        V2 a = poly[j], b = poly[i];
        if ((a.y > q.y) != (b.y > q.y) && q.x < a.x + (q.y - a.y) / (b.y - a.y) * (b.x - a.x))
            in = !in;
    }
    return in;
}

double polyline_area(const std::vector<V2> &poly)
{
    double a = 0;
    for (size_t i = 0; i < poly.size(); i++)
        a += cross(poly[i], poly[(i + 1) % poly.size()]);
    return a / 2;
}

// Ear clipping of one weakly simple counter-clockwise polygon (holes
// already bridged in, so a position may appear twice): triangles as index
// triples.
bool ear_clip(const std::vector<V2> &v, std::vector<std::array<int, 3>> *tris)
{
    std::vector<int> idx(v.size());
    for (size_t i = 0; i < v.size(); i++)
        idx[i] = (int)i;
    double scale = 0;
    for (V2 x : v)
        scale = std::max(scale, norm(x));
    const double eps = 1e-12 * scale * scale;
    auto in_triangle = [&](V2 q, V2 a, V2 b, V2 c) {
        return cross(b - a, q - a) >= -eps && cross(c - b, q - b) >= -eps && cross(a - c, q - c) >= -eps;
    };
    size_t guard = 0;
    while (idx.size() > 3) {
        bool clipped = false;
        size_t m = idx.size();
        // Prefer the ear with the largest smallest angle: fewer slivers.
        int best = -1;
        double best_q = -1;
        for (size_t i = 0; i < m; i++) {
            int ia = idx[(i + m - 1) % m], ib = idx[i], ic = idx[(i + 1) % m];
            V2 a = v[ia], b = v[ib], c = v[ic];
            if (cross(b - a, c - b) <= eps)
                continue; // reflex or flat: not an ear
            bool empty = true;
            for (size_t j = 0; j < m && empty; j++) {
                int ij = idx[j];
                if (ij == ia || ij == ib || ij == ic)
                    continue;
                V2 q = v[ij];
                if (norm(q - a) == 0 || norm(q - b) == 0 || norm(q - c) == 0)
                    continue; // a bridge's twin
                if (in_triangle(q, a, b, c))
                    empty = false;
            }
            if (!empty)
                continue;
            auto angle = [](V2 p, V2 q, V2 r) {
                V2 u = q - p, w = r - p;
                return std::atan2(std::fabs(cross(u, w)), dot(u, w));
            };
            double quality = std::min({angle(a, b, c), angle(b, c, a), angle(c, a, b)});
            if (quality > best_q) {
                best_q = quality;
                best = (int)i;
            }
        }
        if (best >= 0) {
            size_t i = (size_t)best;
            tris->push_back({idx[(i + m - 1) % m], idx[i], idx[(i + 1) % m]});
            idx.erase(idx.begin() + (long)i);
            clipped = true;
        }
        if (!clipped) {
            // Only flat vertices left (collinear runs): drop one.
            for (size_t i = 0; i < m && !clipped; i++) {
                V2 a = v[idx[(i + m - 1) % m]], b = v[idx[i]], c = v[idx[(i + 1) % m]];
                if (std::fabs(cross(b - a, c - b)) <= eps && dot(b - a, c - b) > 0) {
                    idx.erase(idx.begin() + (long)i);
                    clipped = true;
                }
            }
        }
        if (!clipped || ++guard > 4 * v.size())
            return false;
    }
    if (cross(v[idx[1]] - v[idx[0]], v[idx[2]] - v[idx[1]]) > eps)
        tris->push_back({idx[0], idx[1], idx[2]});
    return true;
}

// Hertel-Mehlhorn: merge neighbouring pieces across their shared diagonal
// while the union stays strictly convex and within max_vertices.
std::vector<std::vector<int>> merge_convex(const std::vector<V2> &v, const std::vector<std::array<int, 3>> &tris,
                                           size_t max_vertices)
{
    std::vector<std::vector<int>> pieces;
    for (auto &t : tris)
        pieces.push_back({t[0], t[1], t[2]});
    double scale = 0;
    for (V2 x : v)
        scale = std::max(scale, norm(x));
    auto convex = [&](const std::vector<int> &p) {
        size_t m = p.size();
        for (size_t i = 0; i < m; i++) {
            V2 a = v[p[i]], b = v[p[(i + 1) % m]], c = v[p[(i + 2) % m]];
            if (cross(b - a, c - b) <= 1e-9 * norm(b - a) * norm(c - b))
                return false;
        }
        return true;
    };
    for (bool merged = true; merged;) {
        merged = false;
        for (size_t A = 0; A < pieces.size() && !merged; A++) {
            for (size_t i = 0; i < pieces[A].size() && !merged; i++) {
                int u = pieces[A][i], w = pieces[A][(i + 1) % pieces[A].size()];
                for (size_t B = A + 1; B < pieces.size() && !merged; B++) {
                    const std::vector<int> &pb = pieces[B];
                    size_t m = pb.size(), j = 0;
                    while (j < m && !(pb[j] == w && pb[(j + 1) % m] == u))
                        j++;
                    if (j == m)
                        continue;
                    if (pieces[A].size() + m - 2 > max_vertices)
                        continue;
                    // A from w round to u, then B's vertices after u up to before w.
                    std::vector<int> un;
                    size_t n = pieces[A].size();
                    for (size_t k = 0; k < n; k++)
                        un.push_back(pieces[A][(i + 1 + k) % n]);
                    for (size_t k = 2; k < m; k++)
                        un.push_back(pb[(j + k) % m]);
                    if (!convex(un))
                        continue;
                    pieces[A] = un;
                    pieces.erase(pieces.begin() + (long)B);
                    merged = true;
                }
            }
        }
    }
    return pieces;
}

// Bridge holes (clockwise) into the outer loop (counter-clockwise): one
// weakly simple polygon, and which of its edges are bridges.
bool bridge_holes(std::vector<V2> outer, std::vector<std::vector<V2>> holes, std::vector<V2> *out,
                  std::vector<std::pair<V2, V2>> *bridges)
{
    std::sort(holes.begin(), holes.end(), [](const std::vector<V2> &a, const std::vector<V2> &b) {
        double xa = -1e300, xb = -1e300;
        for (V2 q : a)
            xa = std::max(xa, q.x);
        for (V2 q : b)
            xb = std::max(xb, q.x);
        return xa > xb;
    });
    for (const std::vector<V2> &h : holes) {
        size_t mi = 0;
        for (size_t i = 1; i < h.size(); i++)
            if (h[i].x > h[mi].x)
                mi = i;
        V2 M = h[mi];
        // The nearest edge of `outer` the ray M + s (1, 0) meets.
        double best = 1e300;
        size_t bi = SIZE_MAX;
        size_t n = outer.size();
        for (size_t i = 0; i < n; i++) {
            V2 a = outer[i], b = outer[(i + 1) % n];
            if ((a.y > M.y) == (b.y > M.y))
                continue;
            double x = a.x + (M.y - a.y) / (b.y - a.y) * (b.x - a.x);
            if (x > M.x && x - M.x < best) {
                best = x - M.x;
                bi = i;
            }
        }
        if (bi == SIZE_MAX)
            return false;
        V2 I{M.x + best, M.y};
        size_t P = outer[bi].x > outer[(bi + 1) % n].x ? bi : (bi + 1) % n;
        // A reflex vertex inside the triangle (M, I, P) hides P: take the
        // one nearest the ray in angle.
        double best_angle = 1e300;
        size_t chosen = P;
        for (size_t i = 0; i < n; i++) {
            V2 q = outer[i], a = outer[(i + n - 1) % n], c = outer[(i + 1) % n];
            if (i == P || cross(q - a, c - q) >= 0)
                continue;
            V2 t0 = M, t1 = I, t2 = outer[P];
            double o = cross(t1 - t0, t2 - t0) > 0 ? 1 : -1;
            if (o * cross(t1 - t0, q - t0) < 0 || o * cross(t2 - t1, q - t1) < 0 || o * cross(t0 - t2, q - t2) < 0)
                continue;
            double ang = std::atan2(std::fabs(q.y - M.y), q.x - M.x);
            if (ang < best_angle) {
                best_angle = ang;
                chosen = i;
            }
        }
        if (chosen != P)
            P = chosen;
        std::vector<V2> next;
        for (size_t i = 0; i <= P; i++)
            next.push_back(outer[i]);
        for (size_t k = 0; k <= h.size(); k++)
            next.push_back(h[(mi + k) % h.size()]);
        next.push_back(outer[P]);
        for (size_t i = P + 1; i < n; i++)
            next.push_back(outer[i]);
        bridges->push_back({outer[P], M});
        outer = next;
    }
    *out = outer;
    return true;
}

// Offset a closed polyline (material on the left) by d towards its left:
// each vertex where the two offset lines meet (the offset point itself
// where they are parallel).  False when an edge would reverse or become
// shorter than min_edge.
bool inset_loop(const std::vector<V2> &x, const std::vector<double> &shift, double min_edge, std::vector<V2> *out)
{
    size_t n = x.size();
    out->assign(n, V2{0, 0});
    for (size_t i = 0; i < n; i++) {
        size_t h = (i + n - 1) % n;
        V2 u = x[i] - x[h], w = x[(i + 1) % n] - x[i];
        V2 nu = (1.0 / norm(u)) * V2{-u.y, u.x}, nw = (1.0 / norm(w)) * V2{-w.y, w.x};
        V2 a = x[h] + shift[h] * nu, b = x[i] + shift[i] * nw;
        if (std::fabs(cross(u, w)) <= 1e-9 * norm(u) * norm(w)) {
            if (std::fabs(shift[h] - shift[i]) > 1e-12)
                return false;
            (*out)[i] = b;
        } else {
            (*out)[i] = intersect(a, u, b, w);
        }
    }
    for (size_t i = 0; i < n; i++) {
        V2 e = x[(i + 1) % n] - x[i], f = (*out)[(i + 1) % n] - (*out)[i];
        if (dot(e, f) <= 0 || norm(f) < min_edge)
            return false;
    }
    return true;
}

// ---- a fixture, read by wrenchd's own reader, and its Box2D geometry ----
struct Prepared {
    std::string file, name;
    wp_fixture_doc doc{};
    const wr_fixture *f = nullptr;
    wr_analysis *an = nullptr;
    std::string unsupported;  // non-empty: cannot be simulated, and why
    double scale = 1;         // fixture units -> metres
    bool circle = false;
    V2 com{};                 // seated centre of mass, world (metres)
    double mass = 0, inertia = 0, rho = 0;
    // Body frame: origin at the centre of mass, axes as the fixture's.
    std::vector<V2> outline;  // polygon as given, CCW, body frame
    std::vector<V2> out_normal; // outward unit normal of edge i (CCW)
    std::vector<V2> core;     // outline inset by the skin: what Box2D is given
    // Not one convex polygon: Box2D gets chain loops (docs/VALIDATION.md).
    bool chains = false;
    std::vector<std::vector<Seg>> loops;      // exact, body frame, material on the left
    std::vector<std::vector<V2>> polylines;   // arcs approximated (ARC_DEVIATION)
    std::vector<std::vector<V2>> cores;       // the polylines inset by the skin: the chains
    std::vector<std::vector<V2>> pieces;      // convex pieces of the polylines
    std::vector<std::vector<V2>> sensors;     // the pieces shrunk by DEEP_PENETRATION
    int sensorless_pieces = 0;                // pieces too thin to shrink
    double deviation = 0;                     // largest distance polyline - arc (m)
    double normal_error = 0;                  // largest angle polyline normal - arc normal (rad)
    double piece_area_error = 0;              // |pieces' area - polylines'| / polylines'
    std::vector<size_t> fixel_loop, fixel_seg;
    std::vector<double> fixel_t;
    V2 center{};              // circle centre, body frame
    double radius = 0;
    // Fixels (world).
    int k = 0;
    std::vector<V2> fixel_at, fixel_normal, fixel_center;
    std::vector<double> mu_s, mu_k;
};

bool read_text(const std::string &path, std::string *text)
{
    std::ifstream in(path, std::ios::binary);
    if (!in)
        return false;
    std::ostringstream s;
    s << in.rdbuf();
    *text = s.str();
    return true;
}


// The polylines, the chains and the pieces of p->loops; false with
// p->unsupported set when Box2D cannot be given them faithfully.
bool build_chains(Prepared *p)
{
    p->polylines.clear();
    p->cores.clear();
    p->outline.clear();
    p->deviation = 0;
    std::vector<std::vector<bool>> concave(p->loops.size());
    for (size_t l = 0; l < p->loops.size(); l++) {
        const std::vector<Seg> &loop = p->loops[l];
        std::vector<V2> poly;
        std::vector<bool> corner;
        for (size_t s = 0; s < loop.size(); s++) {
            const Seg &g = loop[s], &prev = loop[(s + loop.size() - 1) % loop.size()];
            poly.push_back(g.a);
            V2 t0 = seg_tangent(prev, 1), t1 = seg_tangent(g, 0);
            corner.push_back(cross(t0, t1) < -1e-9); // turning right: a concave corner
            if (!g.arc)
                continue;
            // Tangent points: the ends, every fixel on the arc, and enough
            // between them that no vertex is farther than ARC_DEVIATION out.
            std::vector<double> ts = {0, 1};
            for (int i = 0; i < p->k; i++)
                if (p->fixel_loop[i] == l && p->fixel_seg[i] == s)
                    ts.push_back(p->fixel_t[i]);
            std::sort(ts.begin(), ts.end());
            double step = 2 * std::acos(1 / (1 + ARC_DEVIATION / g.r)) / std::fabs(g.sweep);
            std::vector<double> all;
            for (size_t j = 0; j + 1 < ts.size(); j++) {
                int parts = std::max(1, (int)std::ceil((ts[j + 1] - ts[j]) / step));
                for (int q = 0; q < parts; q++)
                    all.push_back(ts[j] + (ts[j + 1] - ts[j]) * q / parts);
            }
            all.push_back(1);
            for (size_t j = 0; j + 1 < all.size(); j++) {
                double half = 0.5 * (all[j + 1] - all[j]) * g.sweep;
                double phi = g.a0 + 0.5 * (all[j] + all[j + 1]) * g.sweep;
                double rr = g.r / std::cos(half);
                poly.push_back(g.c + rr * V2{std::cos(phi), std::sin(phi)});
                corner.push_back(false);
                p->deviation = std::max(p->deviation, rr - g.r);
                p->normal_error = std::max(p->normal_error, std::fabs(half));
            }
        }
        p->polylines.push_back(poly);
        concave[l] = corner;
        for (V2 x : poly)
            p->outline.push_back(x);
    }
    // The chains: each polyline inset by the skin (Box2D adds it back).
    for (const std::vector<V2> &poly : p->polylines) {
        std::vector<V2> core;
        if (!inset_loop(poly, std::vector<double>(poly.size(), b2_polygonRadius), 1.5 * b2_linearSlop, &core)) {
            p->unsupported = "a feature smaller than Box2D's skin: an edge of the outline inset by 0.01 m "
                             "would vanish or be shorter than the linear slop";
            return false;
        }
        p->cores.push_back(core);
    }
    // Near each fixel the boundary must be one smooth or convex piece.
    for (int i = 0; i < p->k; i++) {
        V2 c = p->fixel_center[i] - p->com, n = p->fixel_normal[i];
        double reach = FIXEL_RADIUS + CLEARANCE;
        for (size_t l = 0; l < p->loops.size(); l++) {
            const std::vector<Seg> &loop = p->loops[l];
            // Samples every 0.002 m in order round the loop.
            struct Sample {
                bool near, concave_corner, faces;
                bool own;
            };
            std::vector<Sample> sm;
            size_t own_at = SIZE_MAX;
            for (size_t s = 0; s < loop.size(); s++) {
                int parts = std::max(2, (int)std::ceil(seg_length(loop[s]) / 0.002));
                for (int q = 0; q < parts; q++) {
                    double t = (double)q / parts;
                    V2 x = seg_point(loop[s], t);
                    Sample a;
                    a.near = norm(x - c) < reach;
                    a.concave_corner = q == 0 && concave[l][s];
                    a.faces = dot(seg_normal(loop[s], t), n) > 0;
                    a.own = l == p->fixel_loop[i] && s == p->fixel_seg[i] && std::fabs(t - p->fixel_t[i]) * parts < 1;
                    if (a.own && own_at == SIZE_MAX)
                        own_at = sm.size();
                    sm.push_back(a);
                }
            }
            size_t total = 0;
            for (const Sample &a : sm)
                total += a.near;
            size_t run = 0;
            bool bad = false;
            if (own_at != SIZE_MAX) {
                size_t m = sm.size();
                for (size_t j = own_at; sm[j].near && run < m; j = (j + 1) % m) {
                    run++;
                    bad = bad || sm[j].concave_corner || !sm[j].faces;
                }
                for (size_t j = (own_at + m - 1) % m; sm[j].near && run < m; j = (j + m - 1) % m) {
                    run++;
                    bad = bad || sm[j].concave_corner || !sm[j].faces;
                }
                bad = bad || run >= m;
            }
            if (bad || total != run) {
                p->unsupported = fmt("fixel %d: within %.2f m of its circle's centre the outline has a concave "
                                     "corner, turns by 90 degrees or more, or comes back: the circle could touch "
                                     "the part twice",
                                     i + 1, reach);
                return false;
            }
        }
    }
    // The convex pieces: holes bridged in, ear clipping, Hertel-Mehlhorn.
    std::vector<V2> outer = p->polylines[0], merged;
    std::vector<std::vector<V2>> holes;
    for (size_t l = 1; l < p->polylines.size(); l++) {
        std::vector<V2> h = p->polylines[l];
        holes.push_back(h);
    }
    std::vector<std::pair<V2, V2>> bridges;
    std::vector<std::array<int, 3>> tris;
    if (!bridge_holes(outer, holes, &merged, &bridges) || !ear_clip(merged, &tris)) {
        p->unsupported = "harness: the outline could not be decomposed into convex pieces";
        return false;
    }
    auto pieces = merge_convex(merged, tris, b2_maxPolygonVertices);
    double area = 0, want = 0;
    for (const std::vector<V2> &poly : p->polylines)
        want += polyline_area(poly);
    p->pieces.clear();
    p->sensors.clear();
    for (const std::vector<int> &pc : pieces) {
        std::vector<V2> x;
        std::vector<double> shift;
        size_t N = merged.size();
        for (size_t j = 0; j < pc.size(); j++) {
            int a = pc[j], b = pc[(j + 1) % pc.size()];
            x.push_back(merged[a]);
            bool boundary = (size_t)b == ((size_t)a + 1) % N;
            for (auto &br : bridges)
                if ((norm(merged[a] - br.first) == 0 && norm(merged[b] - br.second) == 0) ||
                    (norm(merged[a] - br.second) == 0 && norm(merged[b] - br.first) == 0))
                    boundary = false;
            shift.push_back(boundary ? b2_polygonRadius + DEEP_PENETRATION : 0);
        }
        area += polyline_area(x);
        p->pieces.push_back(x);
        std::vector<V2> core;
        if (!inset_loop(x, shift, 1.5 * b2_linearSlop, &core) || polyline_area(core) <= 0) {
            p->sensorless_pieces++;
            continue;
        }
        p->sensors.push_back(core);
    }
    p->piece_area_error = std::fabs(area - want) / want;
    if (p->piece_area_error > 1e-9) {
        p->unsupported = fmt("harness: the convex pieces' area is off by %.2e of the outline's", p->piece_area_error);
        return false;
    }
    return true;
}

bool prepare(const std::string &path, Prepared *p, std::string *error)
{
    p->file = path;
    std::string text;
    if (!read_text(path, &text)) {
        *error = path + ": cannot read";
        return false;
    }
    cJSON *json = cJSON_Parse(text.c_str());
    if (!json) {
        *error = path + ": not JSON";
        return false;
    }
    wp_error werr{};
    bool ok = wp_fixture_read(json, "fixture", &p->doc, &werr);
    cJSON_Delete(json);
    if (!ok) {
        *error = path + ": " + werr.field + ": " + werr.reason;
        return false;
    }
    p->f = p->doc.fixture;
    p->name = p->doc.name && *p->doc.name ? p->doc.name : path;
    wr_status status = wr_analysis_new(p->f, &p->an);
    if (status != WR_OK) {
        *error = path + ": wr_analysis_new: " + wr_strerror(status);
        return false;
    }
    const wr_fixture *f = p->f;
    p->k = f->fixel_count;
    if (f->shape == WR_SHAPE_NONE) {
        p->unsupported = "no shape: nothing to simulate";
        return true;
    }
    double s = p->scale = SIZE / f->size;
    p->com = {s * f->com[0], s * f->com[1]};
    p->mass = f->mass;
    p->inertia = f->inertia * s * s;
    p->rho = std::sqrt(p->inertia / p->mass);
    p->circle = f->shape == WR_SHAPE_CIRCLE;
    auto body = [&](const double a[2]) { return V2{s * a[0], s * a[1]} - p->com; };
    if (p->circle) {
        p->center = body(f->center);
        p->radius = s * f->radius;
    } else if (f->shape == WR_SHAPE_POLYGON) {
        size_t n = f->vertex_count;
        std::vector<V2> ccw;
        for (size_t i = 0; i < n; i++) {
            size_t j = f->orientation > 0 ? i : n - 1 - i;
            ccw.push_back(body(f->vertices[j]));
        }
        bool convex = n <= (size_t)b2_maxPolygonVertices;
        for (size_t i = 0; i < n && convex; i++) {
            V2 a = ccw[i], b = ccw[(i + 1) % n], c = ccw[(i + 2) % n];
            convex = cross(b - a, c - b) > 1e-12 * SIZE * SIZE;
        }
        if (!convex || force_chains) {
            p->chains = true;
            std::vector<Seg> loop;
            for (size_t i = 0; i < n; i++) {
                Seg g;
                g.a = ccw[i];
                g.b = ccw[(i + 1) % n];
                loop.push_back(g);
            }
            p->loops.push_back(loop);
        } else {
            p->outline = ccw;
            for (size_t i = 0; i < n; i++) {
                V2 e = p->outline[(i + 1) % n] - p->outline[i];
                p->out_normal.push_back((1.0 / norm(e)) * V2{e.y, -e.x});
            }
            // Box2D rounds every polygon by a skin of b2_polygonRadius: give it the
            // outline inset by the skin, so that its surface is the outline itself
            // along every edge (corners become arcs of radius 0.01 m).
            double d = b2_polygonRadius;
            for (size_t i = 0; i < n; i++) {
                size_t h = (i + n - 1) % n;
                V2 a = p->outline[h] - d * p->out_normal[h], u = p->outline[i] - p->outline[h];
                V2 b = p->outline[i] - d * p->out_normal[i], v = p->outline[(i + 1) % n] - p->outline[i];
                p->core.push_back(intersect(a, u, b, v));
            }
            std::vector<b2Vec2> vs;
            for (V2 c : p->core)
                vs.push_back(b2(c));
            b2PolygonShape poly;
            poly.Set(vs.data(), (int32)vs.size());
            bool same = poly.m_count == (int32)n;
            for (int32 i = 0; same && i < poly.m_count; i++) {
                bool found = false;
                for (b2Vec2 c : vs)
                    found = found || (c - poly.m_vertices[i]).Length() == 0;
                same = found;
            }
            if (!same) {
                p->unsupported = "Box2D's b2PolygonShape::Set welded or dropped vertices";
                return true;
            }
        }
    } else if (f->shape == WR_SHAPE_OUTLINE && f->outline) {
        // Every loop turned so that the material lies on its left (the outer
        // loop counter-clockwise, holes clockwise).
        p->chains = true;
        for (size_t l = 0; l < f->outline->loop_count; l++) {
            const wr_loop &wl = f->outline->loops[l];
            std::vector<Seg> loop;
            for (size_t j = 0; j < wl.segment_count; j++) {
                const wr_segment &ws = wl.segments[j];
                Seg g;
                g.a = body(ws.start);
                g.b = body(ws.end);
                // An arc flatter than 1e-3 of ARC_DEVIATION (its radius may
                // be near the largest double) is taken for its chord.
                double sagitta = s * ws.radius * 2 * std::pow(std::sin(std::fabs(ws.sweep) / 4), 2);
                if (ws.bulge != 0 && sagitta > 1e-3 * ARC_DEVIATION) {
                    g.arc = true;
                    g.c = body(ws.center);
                    g.r = s * ws.radius;
                    g.a0 = ws.start_angle;
                    g.sweep = ws.sweep;
                }
                if (wl.material_side < 0) {
                    std::swap(g.a, g.b);
                    g.a0 += g.sweep;
                    g.sweep = -g.sweep;
                }
                loop.push_back(g);
            }
            if (wl.material_side < 0)
                std::reverse(loop.begin(), loop.end());
            p->loops.push_back(loop);
        }
    } else {
        p->unsupported = "a shape the harness does not know";
        return true;
    }
    for (int i = 0; i < p->k; i++) {
        const wr_fixel &x = f->fixels[i];
        V2 at{s * x.at[0], s * x.at[1]}, nrm{x.normal[0], x.normal[1]};
        // Box2D's contact normal at a small circle is the body's surface
        // normal; the model's is the fixel's.  They must agree.
        V2 geometric{};
        V2 local = at - p->com;
        if (p->circle) {
            geometric = (1.0 / norm(p->center - local)) * (p->center - local);
        } else if (p->chains) {
            // The nearest point of the exact outline, not at a vertex.
            double best = 1e300, bt = 0;
            size_t bl = 0, bs = 0;
            for (size_t l = 0; l < p->loops.size(); l++)
                for (size_t g = 0; g < p->loops[l].size(); g++) {
                    double t, d = seg_nearest(p->loops[l][g], local, &t);
                    if (d < best) {
                        best = d, bt = t, bl = l, bs = g;
                    }
                }
            if (best > 1e-6 * SIZE || bt < 1e-6 || bt > 1 - 1e-6) {
                p->unsupported = "fixel " + std::to_string(i + 1) +
                                 (best > 1e-6 * SIZE ? " not on the outline" : " at a vertex: its normal is not defined");
                return true;
            }
            geometric = seg_normal(p->loops[bl][bs], bt);
            p->fixel_loop.push_back(bl);
            p->fixel_seg.push_back(bs);
            p->fixel_t.push_back(bt);
        } else {
            double best = 1e300;
            size_t n = p->outline.size();
            for (size_t e = 0; e < n; e++) {
                V2 a = p->outline[e], b = p->outline[(e + 1) % n];
                double t = dot(local - a, b - a) / dot(b - a, b - a);
                double dist = std::fabs(dot(local - a, p->out_normal[e]));
                if (t > 1e-6 && t < 1 - 1e-6 && dist < best) {
                    best = dist;
                    geometric = -1.0 * p->out_normal[e];
                }
            }
            if (best > 1e-6 * SIZE) {
                p->unsupported = "fixel " + std::to_string(i + 1) +
                                 " at a vertex: a circle fixel would see the vertex's rounded skin";
                return true;
            }
        }
        if (norm(geometric - nrm) > 1e-9) {
            p->unsupported = "fixel " + std::to_string(i + 1) +
                             ": its normal is not the surface normal, which Box2D would use";
            return true;
        }
        p->fixel_at.push_back(at);
        p->fixel_normal.push_back(nrm);
        p->fixel_center.push_back(at - FIXEL_RADIUS * nrm);
        p->mu_s.push_back(friction_factor * (static_as_kinetic ? x.mu_kinetic : x.mu_static));
        p->mu_k.push_back(friction_factor * x.mu_kinetic);
    }
    if (p->k > 3) {
        p->unsupported = "more than 3 fixels: the start sampler sets one gap per fixel";
        return true;
    }
    if (p->chains)
        build_chains(p); // sets p->unsupported when it fails
    return true;
}

// ---- poses, gaps, start sampling (the model's geometry, double precision) ----
struct Pose {
    V2 x;      // centre of mass, world
    double th; // angle
};

// Signed distance from a body-frame point to the outline, positive outside
// (polygon: the largest distance to an edge's line, exact near an edge's
// interior, which is where the fixels are).
double signed_distance(const Prepared &p, V2 local)
{
    if (p.circle)
        return norm(local - p.center) - p.radius;
    if (p.chains) {
        // The distance to the exact outline, negative inside the material.
        double best = 1e300, t;
        for (const std::vector<Seg> &loop : p.loops)
            for (const Seg &g : loop)
                best = std::min(best, seg_nearest(g, local, &t));
        bool inside = inside_polyline(p.polylines[0], local);
        for (size_t l = 1; l < p.polylines.size() && inside; l++)
            inside = !inside_polyline(p.polylines[l], local);
        return inside ? -best : best;
    }
    double best = -1e300;
    for (size_t e = 0; e < p.outline.size(); e++)
        best = std::max(best, dot(local - p.outline[e], p.out_normal[e]));
    return best;
}

// Gap between fixel i's circle and the body at `pose` (negative: overlap).
double gap(const Prepared &p, const Pose &pose, int i)
{
    V2 local = rotate(p.fixel_center[i] - pose.x, -pose.th);
    return signed_distance(p, local) - FIXEL_RADIUS;
}

// Solve the k x k system A z = b (k <= 3), Gaussian elimination with pivots.
bool solve(int k, double A[3][3], double b[3], double z[3])
{
    int idx[3] = {0, 1, 2};
    for (int c = 0; c < k; c++) {
        int piv = c;
        for (int r = c + 1; r < k; r++)
            if (std::fabs(A[r][c]) > std::fabs(A[piv][c]))
                piv = r;
        if (std::fabs(A[piv][c]) < 1e-14)
            return false;
        std::swap(A[c], A[piv]);
        std::swap(b[c], b[piv]);
        for (int r = c + 1; r < k; r++) {
            double m = A[r][c] / A[c][c];
            for (int j = c; j < k; j++)
                A[r][j] -= m * A[c][j];
            b[r] -= m * b[c];
        }
    }
    for (int c = k - 1; c >= 0; c--) {
        double v = b[c];
        for (int j = c + 1; j < k; j++)
            v -= A[c][j] * z[j];
        z[c] = v / A[c][c];
    }
    (void)idx;
    return true;
}

// Least-norm step in the scaled metric q = (dx, dy, rho dth) with J q = r.
bool least_norm(const Prepared &p, const double J[3][3], const double r[3], double q[3])
{
    int k = p.k;
    double A[3][3] = {}, b[3] = {}, z[3] = {};
    for (int i = 0; i < k; i++) {
        b[i] = r[i];
        for (int j = 0; j < k; j++)
            for (int c = 0; c < 3; c++)
                A[i][j] += J[i][c] * J[j][c];
    }
    if (!solve(k, A, b, z))
        return false;
    for (int c = 0; c < 3; c++) {
        q[c] = 0;
        for (int i = 0; i < k; i++)
            q[c] += J[i][c] * z[i];
    }
    return true;
}

Pose apply(const Prepared &p, const Pose &base, const double q[3])
{
    return {base.x + V2{q[0], q[1]}, base.th + q[2] / p.rho};
}

// Jacobian of the gaps in the scaled metric, by central differences.
void gap_jacobian(const Prepared &p, const Pose &pose, double J[3][3])
{
    const double h = 1e-6 * SIZE;
    for (int c = 0; c < 3; c++) {
        double dq[3] = {0, 0, 0};
        dq[c] = h;
        Pose a = apply(p, pose, dq);
        dq[c] = -h;
        Pose b = apply(p, pose, dq);
        for (int i = 0; i < p.k; i++)
            J[i][c] = (gap(p, a, i) - gap(p, b, i)) / (2 * h);
    }
}

double boundary_displacement(const Prepared &p, const Pose &a, const Pose &b);
// A start moves no boundary point farther than this from the seated pose.
constexpr double START_REACH = 4 * GAP_MAX;

struct Start {
    Pose pose;
    V2 v;
    double w;
    int touching; // fixels touching at the start
    double scale; // the gaps' scale (1 but for pins in holes, below)
};

// A start displaced from the seated pose away from the fixels: a target gap
// per fixel (0 with probability TOUCH_PROBABILITY, else up to GAP_MAX, never
// all 0), the least-norm rigid motion that makes them (plus a random motion
// the fixels do not see, for k < 3), refined by Newton on the exact gaps.
// Newton from the seated pose moved by q to the pose with the gaps `goal`,
// near the seated pose; false when there is none.
bool newton_start(const Prepared &p, const Pose &seated, const double q[3], const double goal[3], Pose *out)
{
    double J[3][3];
    Pose pose = apply(p, seated, q);
    // Newton, its step halved until the residual's norm decreases: on a
    // curved outline (a fixel in a concave arc) a full step can leave the
    // arc for a line and jump to a far pose that has the same gaps.
    auto residual = [&](const Pose &at, double r[3]) {
        double sum = 0;
        for (int i = 0; i < p.k; i++) {
            r[i] = goal[i] - gap(p, at, i);
            sum += r[i] * r[i];
        }
        return std::sqrt(sum);
    };
    for (int it = 0; it < 40; it++) {
        double r[3] = {0, 0, 0}, worst = residual(pose, r);
        if (worst < 1e-12 * SIZE)
            break;
        gap_jacobian(p, pose, J);
        double dq[3];
        if (!least_norm(p, J, r, dq))
            return false;
        Pose next = apply(p, pose, dq);
        double r2[3];
        for (int halving = 0; halving < 30 && residual(next, r2) >= worst; halving++) {
            for (double &c : dq)
                c *= 0.5;
            next = apply(p, pose, dq);
        }
        pose = next;
    }
    for (int i = 0; i < p.k; i++)
        if (std::fabs(gap(p, pose, i) - goal[i]) > 1e-9 * SIZE)
            return false;
    // The start must be near the seated pose (the model is local): a far
    // pose with the same gaps is no start.
    if (boundary_displacement(p, seated, pose) > START_REACH)
        return false;
    *out = pose;
    return true;
}

bool sample_start(const Prepared &p, Rng &rng, Start *out)
{
    Pose seated{p.com, 0};
    double target[3] = {0, 0, 0};
    int touching = 0;
    for (;;) {
        touching = 0;
        for (int i = 0; i < p.k; i++) {
            if (rng.uniform() < TOUCH_PROBABILITY) {
                target[i] = 0;
                touching++;
            } else {
                target[i] = GAP_MAX * rng.uniform(0.05, 1.0);
            }
        }
        if (touching < p.k)
            break;
    }
    double J[3][3];
    gap_jacobian(p, seated, J);
    double q[3];
    if (!least_norm(p, J, target, q))
        return false;
    if (p.k < 3) {
        // Add a random motion in the null space of J: z - J^+ J z.
        double z[3], Jz[3] = {0, 0, 0}, back[3];
        double len;
        do {
            for (double &c : z)
                c = rng.uniform(-1, 1);
            len = std::sqrt(z[0] * z[0] + z[1] * z[1] + z[2] * z[2]);
        } while (len > 1 || len < 1e-3);
        for (double &c : z)
            c *= GAP_MAX;
        for (int i = 0; i < p.k; i++)
            for (int c = 0; c < 3; c++)
                Jz[i] += J[i][c] * z[c];
        if (!least_norm(p, J, Jz, back))
            return false;
        for (int c = 0; c < 3; c++)
            q[c] += z[c] - back[c];
    }
    // A pin in a hole has only the hole's clearance: targets it cannot
    // reach together are halved (up to 3 times; q is linear in them).
    Pose pose{};
    double scale = 1;
    bool found = false;
    for (int attempt = 0; attempt < 4 && !found; attempt++, scale *= 0.5) {
        double goal[3], q0[3];
        for (int c = 0; c < 3; c++) {
            goal[c] = scale * target[c];
            q0[c] = scale * q[c];
        }
        found = newton_start(p, seated, q0, goal, &pose);
    }
    if (!found)
        return false;
    out->scale = scale * 2;
    double speed = V0_MAX * std::sqrt(rng.uniform()), dir = rng.uniform(0, 2 * PI);
    out->pose = pose;
    out->v = {speed * std::cos(dir), speed * std::sin(dir)};
    out->w = rng.uniform(-W0_MAX, W0_MAX);
    out->touching = touching;
    return true;
}

// The seated pose pressed PRELOAD into every fixel.  Box2D creates a
// contact point only when the shapes overlap or touch, and at exactly zero
// distance float rounding decides: started at the exact seated pose, some
// contacts appear one step late, the part falls freely for that step and
// the impulses that catch it set it rocking.  A preload well inside
// Box2D's allowed penetration (b2_linearSlop, 0.005 m) makes every contact
// exist from the first step and is not pushed out by the position solver.
constexpr double PRELOAD = 0.25 * b2_linearSlop;

Pose preloaded(const Prepared &p)
{
    Pose pose{p.com, 0};
    double target[3] = {-PRELOAD, -PRELOAD, -PRELOAD}, J[3][3];
    for (int it = 0; it < 20; it++) {
        double r[3] = {0, 0, 0}, worst = 0, dq[3];
        for (int i = 0; i < p.k; i++) {
            r[i] = target[i] - gap(p, pose, i);
            worst = std::max(worst, std::fabs(r[i]));
        }
        if (worst < 1e-12 * SIZE)
            break;
        gap_jacobian(p, pose, J);
        if (!least_norm(p, J, r, dq))
            break;
        pose = apply(p, pose, dq);
    }
    return pose;
}

// ---- the Box2D world ----
double deep_speed = 0; // the part's fastest boundary speed at a sensor contact, this row

// Friction: Box2D mixes two fixtures' coefficients as sqrt(f_a f_b).  The
// part's fixture has friction 1 and fixel i's has mu_s(i)^2, so the mix is
// mu_s(i); on top of that this listener sets every contact's coefficient
// before each solve: mu_k(i) when the contact point slides faster than
// SLIP_SPEED, mu_s(i) otherwise (Box2D itself has one coefficient).
struct Friction : b2ContactListener {
    const Prepared *p = nullptr;
    long long set_static = 0, set_kinetic = 0;
    long long deep = 0; // a fixel met a sensor piece: sunk DEEP_PENETRATION into the part
    void BeginContact(b2Contact *contact) override
    {
        b2Fixture *a = contact->GetFixtureA(), *b = contact->GetFixtureB();
        if (a->IsSensor() || b->IsSensor()) {
            deep++;
            b2Body *part = a->IsSensor() ? a->GetBody() : b->GetBody();
            deep_speed = std::max(deep_speed, (double)part->GetLinearVelocity().Length() +
                                                  std::fabs(part->GetAngularVelocity()) * SIZE);
        }
    }
    void PreSolve(b2Contact *contact, const b2Manifold *) override
    {
        b2Fixture *a = contact->GetFixtureA(), *b = contact->GetFixtureB();
        uintptr_t ia = a->GetUserData().pointer, ib = b->GetUserData().pointer;
        int i = (int)(ia ? ia : ib) - 1;
        b2Body *body = ia ? b->GetBody() : a->GetBody();
        if (i < 0 || i >= p->k)
            return;
        b2WorldManifold wm;
        contact->GetWorldManifold(&wm);
        double slip = 0;
        for (int c = 0; c < contact->GetManifold()->pointCount; c++) {
            b2Vec2 v = body->GetLinearVelocityFromWorldPoint(wm.points[c]);
            slip = std::max(slip, (double)std::fabs(b2Cross(wm.normal, v)));
        }
        bool sliding = slip > SLIP_SPEED;
        contact->SetFriction((float)(sliding ? p->mu_k[i] : p->mu_s[i]));
        (sliding ? set_kinetic : set_static)++;
    }
    // The last step's impulses at each fixel (normal, tangent), for traces.
    double impulse[WR_MAX_FIXELS][2] = {};
    void PostSolve(b2Contact *contact, const b2ContactImpulse *imp) override
    {
        uintptr_t ia = contact->GetFixtureA()->GetUserData().pointer;
        uintptr_t ib = contact->GetFixtureB()->GetUserData().pointer;
        int i = (int)(ia ? ia : ib) - 1;
        if (i < 0 || i >= p->k)
            return;
        impulse[i][0] = imp->normalImpulses[0];
        impulse[i][1] = imp->tangentImpulses[0];
    }
};

struct Sim {
    b2World world;
    b2Body *part = nullptr;
    std::vector<b2Fixture *> part_fixtures; // the colliding ones (not the sensor pieces)
    std::vector<b2Fixture *> fixel_fixtures;
    Friction friction;
    Sim(const Prepared &p, const Pose &pose, V2 v, double w, V2 gravity)
        : world(b2(gravity))
    {
        friction.p = &p;
        world.SetContactListener(&friction);
        b2BodyDef fixed;
        b2Body *fixels = world.CreateBody(&fixed);
        for (int i = 0; i < p.k; i++) {
            b2CircleShape c;
            c.m_p = b2(p.fixel_center[i]);
            c.m_radius = (float)FIXEL_RADIUS;
            b2FixtureDef fd;
            fd.shape = &c;
            fd.friction = (float)(p.mu_s[i] * p.mu_s[i]);
            fd.restitution = 0;
            fd.userData.pointer = (uintptr_t)(i + 1);
            fixel_fixtures.push_back(fixels->CreateFixture(&fd));
        }
        b2BodyDef bd;
        bd.type = b2_dynamicBody;
        bd.position = b2(pose.x);
        bd.angle = (float)pose.th;
        bd.linearVelocity = b2(v);
        bd.angularVelocity = (float)w;
        bd.allowSleep = false;
        part = world.CreateBody(&bd);
        b2FixtureDef fd;
        b2PolygonShape poly;
        b2CircleShape disc;
        fd.density = 1;
        fd.friction = 1;
        fd.restitution = 0;
        if (p.circle) {
            disc.m_p = b2(p.center);
            disc.m_radius = (float)p.radius;
            fd.shape = &disc;
            part_fixtures.push_back(part->CreateFixture(&fd));
        } else if (!p.chains) {
            std::vector<b2Vec2> vs;
            for (V2 c : p.core)
                vs.push_back(b2(c));
            poly.Set(vs.data(), (int32)vs.size());
            fd.shape = &poly;
            part_fixtures.push_back(part->CreateFixture(&fd));
        } else {
            // One chain loop per boundary loop (they collide), and the convex
            // pieces as sensors (they only watch for deep penetration).
            for (const std::vector<V2> &core : p.cores) {
                std::vector<b2Vec2> vs;
                for (V2 c : core)
                    vs.push_back(b2(c));
                b2ChainShape chain;
                chain.CreateLoop(vs.data(), (int32)vs.size());
                fd.shape = &chain;
                fd.density = 0;
                part_fixtures.push_back(part->CreateFixture(&fd));
            }
            for (const std::vector<V2> &piece : p.sensors) {
                std::vector<b2Vec2> vs;
                for (V2 c : piece)
                    vs.push_back(b2(c));
                b2PolygonShape sp;
                sp.Set(vs.data(), (int32)vs.size());
                b2FixtureDef sd;
                sd.shape = &sp;
                sd.density = 0;
                sd.isSensor = true;
                part->CreateFixture(&sd);
            }
        }
        b2MassData md;
        md.mass = (float)p.mass;
        md.center = b2Vec2(0, 0);
        md.I = (float)p.inertia;
        part->SetMassData(&md);
    }
    Pose pose() const { return {v2(part->GetPosition()), part->GetAngle()}; }
    // Bit i: fixel i's contact is touching (Box2D's manifold has points).
    unsigned touching()
    {
        unsigned bits = 0;
        for (b2ContactEdge *e = part->GetContactList(); e; e = e->next) {
            b2Contact *c = e->contact;
            if (!c->IsTouching() || c->GetFixtureA()->IsSensor() || c->GetFixtureB()->IsSensor())
                continue;
            uintptr_t ia = c->GetFixtureA()->GetUserData().pointer;
            uintptr_t ib = c->GetFixtureB()->GetUserData().pointer;
            int i = (int)(ia ? ia : ib) - 1;
            if (i >= 0)
                bits |= 1u << i;
        }
        return bits;
    }
    void step() { world.Step((float)(1.0 / HZ), VELOCITY_ITERATIONS, POSITION_ITERATIONS); }
    // Box2D's own distance (b2Distance, with the skins) between fixel i and
    // the part: 0 when they touch, negative never (it reports overlap as 0).
    double distance(int i)
    {
        double best = 1e300;
        for (b2Fixture *pf : part_fixtures)
            for (int32 child = 0; child < pf->GetShape()->GetChildCount(); child++) {
                b2DistanceInput in;
                in.proxyA.Set(fixel_fixtures[i]->GetShape(), 0);
                in.proxyB.Set(pf->GetShape(), child);
                in.transformA = fixel_fixtures[i]->GetBody()->GetTransform();
                in.transformB = part->GetTransform();
                in.useRadii = true;
                b2SimplexCache cache;
                cache.count = 0;
                b2DistanceOutput out;
                b2Distance(&out, &cache, &in);
                best = std::min(best, (double)out.distance);
            }
        return best;
    }
};

// Largest displacement of the body's boundary between two poses.
double boundary_displacement(const Prepared &p, const Pose &a, const Pose &b)
{
    if (p.circle)
        return norm((a.x + rotate(p.center, a.th)) - (b.x + rotate(p.center, b.th))) +
               p.radius * std::fabs(a.th - b.th);
    double worst = 0;
    for (V2 c : p.outline)
        worst = std::max(worst, norm((a.x + rotate(c, a.th)) - (b.x + rotate(c, b.th))));
    return worst;
}

// ---- seating trials ----
bool trace = false; // PHYSICS_TRACE=t: print the trials of --sweep at t
struct Load {
    bool gravity = false;
    V2 g{};           // gravity (world)
    V2 at{}, dir{};   // finger: body-frame point and inward normal
    bool world_fixed = false; // disc only: the finger stays put while the
                              // disc turns under it (frictionless)
};

void push(b2Body *part, const Prepared &p, const Load &load)
{
    const float force = (float)(p.mass * ACCEL);
    if (load.world_fixed) {
        b2Vec2 c = part->GetWorldPoint(b2(p.center));
        part->ApplyForce(force * b2(load.dir), c + b2(load.at - p.center), true);
    } else {
        part->ApplyForce(force * part->GetWorldVector(b2(load.dir)), part->GetWorldPoint(b2(load.at)), true);
    }
}

struct Seat {
    bool seated = false;
    double time = 0;       // s to the start of the final rest
    double pos_err = 0, ang_err = 0, penetration = 0;
    unsigned touching = 0; // at the end
    bool rest = false;     // came to rest (possibly not seated)
    long long deep = 0;    // fixels that met a sensor piece (the trial counts against its row)
    double moved = 0;      // distance of the com from the seated pose at the end
};

Seat run_seat(const Prepared &p, const Start &st, const Load &load)
{
    Sim sim(p, st.pose, st.v, st.w, load.gravity ? load.g : V2{0, 0});
    const unsigned all = (1u << p.k) - 1;
    const int rest_steps = (int)std::lround(REST_TIME * HZ);
    const int limit = (int)std::lround(TIME_LIMIT * HZ);
    int calm = 0;
    Seat out;
    for (int n = 1; n <= limit; n++) {
        if (!load.gravity)
            push(sim.part, p, load);
        sim.step();
        unsigned t = sim.touching();
        double v = sim.part->GetLinearVelocity().Length(), w = std::fabs(sim.part->GetAngularVelocity());
        bool slow = v < REST_SPEED && w < REST_SPIN;
        if (slow && t == all)
            calm++;
        else
            calm = 0;
        out.touching = t;
        if (trace && n % 24 == 0) {
            Pose q = sim.pose();
            std::fprintf(stderr, "t %.2f x %.4f %.4f th %.2f v %.4f w %.4f touching %u\n", n / HZ, q.x.x - p.com.x,
                         q.x.y - p.com.y, q.th * DEG, v, sim.part->GetAngularVelocity(), t);
        }
        if (calm >= rest_steps) {
            out.rest = true;
            out.time = (n - rest_steps) / HZ;
            break;
        }
    }
    Pose end = sim.pose();
    out.pos_err = p.circle ? norm((end.x + rotate(p.center, end.th)) - (p.com + p.center))
                           : norm(end.x - p.com);
    out.ang_err = p.circle ? 0 : std::fabs(end.th) * DEG;
    out.moved = norm(end.x - p.com);
    for (int i = 0; i < p.k; i++)
        out.penetration = std::max(out.penetration, -gap(p, end, i));
    out.deep = sim.friction.deep;
    out.seated = out.rest && out.pos_err < POSE_TOLERANCE && out.ang_err < ANGLE_TOLERANCE && out.deep == 0;
    return out;
}

// ---- holding trials: the part seated (preloaded), at rest, under a wrench ----
struct Hold {
    double moved = 0; // largest boundary displacement over HOLD_TIME
    long long deep = 0; // fixels that met a sensor piece (the trial counts against its row)
};

bool hold_trace = std::getenv("PHYSICS_HOLD_TRACE") != nullptr;

// wrench: world force (N) and torque (N m) about the com, constant; or a finger.
Hold run_hold(const Prepared &p, V2 force, double torque, const Load *finger)
{
    Pose seated = preloaded(p);
    Sim sim(p, seated, {0, 0}, 0, {0, 0});
    const int steps = (int)std::lround(HOLD_TIME * HZ);
    Hold out;
    for (int n = 0; n < steps; n++) {
        if (finger) {
            push(sim.part, p, *finger);
        } else {
            sim.part->ApplyForceToCenter(b2(force), true);
            sim.part->ApplyTorque((float)torque, true);
        }
        sim.step();
        out.moved = std::max(out.moved, boundary_displacement(p, seated, sim.pose()));
        if (hold_trace && n % 48 == 0) {
            Pose q = sim.pose();
            std::fprintf(stderr, "t %.2f dx %.6f %.6f th %.6f deg N", (n + 1) / HZ, q.x.x - p.com.x, q.x.y - p.com.y,
                         q.th * DEG);
            for (int i = 0; i < p.k; i++)
                std::fprintf(stderr, " %.4f/%.4f", sim.friction.impulse[i][0] * HZ, sim.friction.impulse[i][1] * HZ);
            std::fprintf(stderr, " touching %u\n", sim.touching());
        }
        if (out.moved > 100 * MOVE_TOLERANCE)
            break; // it moves: no need to watch it fly
    }
    out.deep = sim.friction.deep;
    return out;
}

// ---- the model's side: regions, arcs, margins ----
double margin_of(const Prepared &p, const double w[3], wr_set set)
{
    wr_answer a;
    if (wr_classify(p.an, w, set, WR_DEFAULT_TOLERANCE, &a) != 0)
        return NAN;
    return a.margin;
}

std::string blocking_of(const Prepared &p, const double w[3], wr_set set)
{
    wr_answer a;
    if (wr_classify(p.an, w, set, WR_DEFAULT_TOLERANCE, &a) != 0 || a.blocking < 0)
        return "-";
    char text[WR_CONSTRAINT_TEXT];
    wr_constraint_format(&wr_analysis_cone(p.an, a.blocking_set, a.blocking)->constraint, text);
    return text;
}

struct Interval {
    int edge;
    double t0, t1;
};

std::vector<Interval> regions(const Prepared &p, wr_set set)
{
    wr_regions r{};
    std::vector<Interval> out;
    if (wr_push_regions(p.an, set, 0, NULL, &r) == 0)
        for (int i = 0; i < r.count; i++)
            out.push_back({r.items[i].edge, r.items[i].t0, r.items[i].t1});
    wr_regions_release(&r);
    return out;
}

std::vector<Interval> arcs(const Prepared &p, wr_set set)
{
    wr_regions r{};
    std::vector<Interval> out;
    if (wr_gravity_sweep(p.an, set, &r) == 0)
        for (int i = 0; i < r.count; i++)
            out.push_back({-1, r.items[i].t0, r.items[i].t1});
    wr_regions_release(&r);
    return out;
}

// The finger at (edge, t): its body-frame point and inward normal, and the
// push wrench in fixture units.
Load finger_at(const Prepared &p, int edge, double t, double wrench[3])
{
    double at[2], nu[2];
    wr_boundary_point(p.f, edge, t, at, nu);
    wr_push_wrench(p.f, edge, t, wrench);
    Load l;
    l.at = V2{p.scale * at[0], p.scale * at[1]} - p.com;
    l.dir = {nu[0], nu[1]};
    return l;
}

// wrenchd's edges: a polygon's sides, the circle, an outline's segments
// over all its loops in order.
int edge_count(const Prepared &p)
{
    if (p.circle)
        return 1;
    if (p.f->shape == WR_SHAPE_OUTLINE) {
        size_t n = 0;
        for (size_t l = 0; l < p.f->outline->loop_count; l++)
            n += p.f->outline->loops[l].segment_count;
        return (int)n;
    }
    return (int)p.f->vertex_count;
}
double edge_range(const Prepared &p) { return p.circle ? 360.0 : 1.0; }
double edge_length(const Prepared &p, int e)
{
    if (p.circle)
        return 2 * PI * p.f->radius;
    if (p.f->shape == WR_SHAPE_OUTLINE) {
        for (size_t l = 0; l < p.f->outline->loop_count; l++) {
            const wr_loop &wl = p.f->outline->loops[l];
            if ((size_t)e < wl.segment_count)
                return wl.segments[e].length;
            e -= (int)wl.segment_count;
        }
        return 0;
    }
    const double *a = p.f->vertices[e], *b = p.f->vertices[(e + 1) % p.f->vertex_count];
    return std::hypot(b[0] - a[0], b[1] - a[1]);
}

bool in_intervals(const std::vector<Interval> &iv, int edge, double t)
{
    for (const Interval &r : iv)
        if (r.edge == edge && t >= r.t0 && t <= r.t1)
            return true;
    return false;
}

// Point j of n, stratified along the intervals' total length (each point
// uniform in its stratum, strictly inside an interval).
bool point_in(const std::vector<Interval> &iv, int j, int n, Rng &rng, int *edge, double *t)
{
    double total = 0;
    for (const Interval &r : iv)
        total += r.t1 - r.t0;
    if (total <= 0)
        return false;
    for (int tries = 0; tries < 100; tries++) {
        double u = (j + rng.uniform()) / n * total;
        for (const Interval &r : iv) {
            double len = r.t1 - r.t0;
            if (u <= len) {
                *edge = r.edge;
                *t = r.t0 + u;
                if (*t > r.t0 && *t < r.t1)
                    return true;
                break;
            }
            u -= len;
        }
    }
    return false;
}

// A boundary point outside the intervals, uniform by arc length, away from
// vertices (where no normal is defined).
void point_outside(const Prepared &p, const std::vector<Interval> &iv, Rng &rng, int *edge, double *t)
{
    double total = 0;
    for (int e = 0; e < edge_count(p); e++)
        total += edge_length(p, e);
    for (;;) {
        double u = rng.uniform() * total;
        int e = 0;
        while (e + 1 < edge_count(p) && u > edge_length(p, e)) {
            u -= edge_length(p, e);
            e++;
        }
        double tt = std::min(u / edge_length(p, e), 1.0) * edge_range(p);
        if (!p.circle && (tt < 1e-6 || tt > 1 - 1e-6))
            continue;
        if (in_intervals(iv, e, tt))
            continue;
        *edge = e;
        *t = tt;
        return;
    }
}

// ---- the report ----
enum Criterion { AT_LEAST_99, REPORT, NONE_MOVES, SOME_MOVE, NOT_APPLICABLE, ALL, NO_BREAK };

struct Row {
    std::string fixture, set, note;
    int deep_trials = 0; // trials in which a fixel met a sensor piece
    int points = 0, trials = 0, successes = 0;
    Criterion criterion = REPORT;
    bool pass = true;
    double seconds = 0;
};

const char *criterion_text(Criterion c)
{
    switch (c) {
    case AT_LEAST_99: return ">= 99% seated";
    case REPORT: return "reported";
    case NONE_MOVES: return "100% hold";
    case SOME_MOVE: return "some move";
    case NOT_APPLICABLE: return "n/a";
    case ALL: return "100% as expected";
    case NO_BREAK: return "100% no fixel breaks";
    }
    return "?";
}

struct Config {
    bool quick = true, verbose = false;
    int goal_points, goal_trials;   // per point
    int out_points, out_trials;
    int hold_points;                // pushes in the G_strong region, seated
    int wrenches_in, wrenches_out;  // random wrenches
    int tilt_points, tilt_trials;
    int tilt_out_points, tilt_out_trials;
    int spin_points;                // discs: spinning, seated
    int force_points, force_trials; // a finger of finite force, gravity, cuts
};

void finish(Row &row)
{

    switch (row.criterion) {
    case AT_LEAST_99:
        row.pass = row.trials >= 200 && row.successes * 100 >= 99 * row.trials;
        break;
    case NONE_MOVES:
    case NO_BREAK:
    case ALL:
        row.pass = row.successes == row.trials;
        break;
    case SOME_MOVE:
        row.pass = row.successes > 0;
        break;
    default:
        row.pass = true;
    }
    if (row.deep_trials > 0)
        // A fixel sank DEEP_PENETRATION into the part (Box2D's chain let it
        // through): such a trial counts against the criterion.
        row.note += fmt("; %d trial(s) with a fixel sunk %.3f m into the part (sensor pieces; part speed up to "
                        "%.2f m/s), counted against the criterion",
                        row.deep_trials, DEEP_PENETRATION, deep_speed);
    deep_speed = 0;
}

void print_row(const Row &r)
{
    std::printf("%-18s %-26s %6d %7d %7d  %6.2f%%  %-20s %-4s %s\n", r.fixture.c_str(), r.set.c_str(),
                r.points, r.trials, r.successes, r.trials ? 100.0 * r.successes / r.trials : 0.0,
                criterion_text(r.criterion), r.pass ? "ok" : "FAIL", r.note.c_str());
    std::fflush(stdout);
}

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

// Seating trials at the points of `where` (push) or tilts (gravity).
Row seat_trials(const Prepared &p, const Config &cfg, const char *set, bool gravity, bool inside,
                const std::vector<Interval> &iv, int points, int trials)
{
    auto t0 = Clock::now();
    Row row;
    row.fixture = p.name;
    row.set = set;
    row.criterion = inside ? AT_LEAST_99 : REPORT;
    if (inside && iv.empty()) {
        row.criterion = NOT_APPLICABLE;
        row.note = gravity ? "no G_goal arc" : "no G_goal push region";
        return row;
    }
    double worst_time = 0, worst_pos = 0, worst_ang = 0, worst_pen = 0, least_margin = 1;
    int failures_shown = 0, starts_touching = 0, starts = 0, starts_scaled = 0;
    double least_scale = 1;
    for (int j = 0; j < points; j++) {
        Rng prng(seed_of(p.name, set, j, -1));
        int edge = -1;
        double t = 0, w[3];
        Load load;
        if (gravity) {
            if (inside) {
                if (!point_in(iv, j, points, prng, &edge, &t))
                    continue;
            } else {
                do
                    t = prng.uniform(0, 360);
                while (in_intervals(iv, -1, t));
            }
            load.gravity = true;
            load.g = {ACCEL * std::cos(t / DEG), ACCEL * std::sin(t / DEG)};
            w[0] = p.mass * std::cos(t / DEG);
            w[1] = p.mass * std::sin(t / DEG);
            w[2] = 0;
        } else {
            if (inside) {
                if (!point_in(iv, j, points, prng, &edge, &t))
                    continue;
            } else {
                point_outside(p, iv, prng, &edge, &t);
            }
            load = finger_at(p, edge, t, w);
        }
        double mg = margin_of(p, w, WR_SET_GOAL);
        if (inside)
            least_margin = std::min(least_margin, mg);
        row.points++;
        for (int r = 0; r < trials; r++) {
            Rng rng(seed_of(p.name, set, j, r));
            Start st;
            if (!sample_start(p, rng, &st)) {
                std::fprintf(stderr, "%s: no start for trial %d of point %d\n", p.name.c_str(), r, j);
                continue;
            }
            starts++;
            starts_touching += st.touching > 0;
            starts_scaled += st.scale < 1;
            least_scale = std::min(least_scale, st.scale);
            Seat s = run_seat(p, st, load);
            row.trials++;
            row.deep_trials += s.deep > 0;
            if (s.seated) {
                row.successes++;
                worst_time = std::max(worst_time, s.time);
                worst_pos = std::max(worst_pos, s.pos_err);
                worst_ang = std::max(worst_ang, s.ang_err);
                worst_pen = std::max(worst_pen, s.penetration);
            } else if (inside && (cfg.verbose || failures_shown < 10)) {
                failures_shown++;
                char bits[WR_MAX_FIXELS + 1] = {};
                for (int i = 0; i < p.k; i++)
                    bits[i] = (s.touching >> i & 1) ? '1' : '0';
                std::fprintf(stderr,
                             "  not seated: %s %s %s %.6f (margin %+.4f) trial %d: rest %d, "
                             "touching %s, pose error %.4f m %.3f deg\n",
                             p.name.c_str(), set, gravity ? "tilt" : "edge/t",
                             gravity ? t : edge + t, mg, r, (int)s.rest, bits, s.pos_err, s.ang_err);
            }
        }
    }
    if (row.successes)
        row.note = fmt("seated within %.2f s; pose error <= %.4f m, %.3f deg; penetration <= %.4f m",
                       worst_time, worst_pos, worst_ang, worst_pen);
    if (inside)
        row.note += fmt("; least margin %.4f", least_margin);
    row.note += fmt("; %d/%d starts touching", starts_touching, starts);
    if (starts_scaled)
        row.note += fmt("; %d starts with their gaps scaled down (to %g at least)", starts_scaled, least_scale);
    finish(row);
    row.seconds = since(t0);
    return row;
}

// ---- forces: a finger of finite force under gravity and a cutting sequence ----
//
// wrenchd's magnitudes (force.range, push.force, lib/wr_force.h) checked in
// Box2D.  Gravity ACCEL pulls along -y of the fixture's frame (270 degrees);
// a cutter presses on the part's upward-facing straight edges (or, on a
// disc, at its top), one cut at a time: a force of 0.4 m ACCEL into the
// part along the inward normal plus half that along the edge (the feed),
// at each edge's middle.  The cases are gravity alone (the seating) and
// gravity with each cut (the sequence).  At a boundary point p the least
// force F*(p) that does `both` under every case is wrenchd's; a push of
// 1.05 F*(p) (when that is still inside every case's interval: pushing
// harder can turn a part) must seat the part from a random start under
// gravity and come to rest, and then hold it (boundary displacement under
// MOVE_TOLERANCE) through every cut applied after seating, one after the
// other.  A push of half F*(p) is reported: the sets are sufficient, not
// necessary.
//
// The holding criterion is asserted for a cut whose wrench (gravity, cut
// and push) has a G_strong margin above HOLD_MARGIN, as for the random
// wrenches: Box2D has one friction coefficient and lets contacts overlap
// by its slop, and just inside G_strong (1.05 F* is often within 0.01 of
// a sliding mode's cone when that cone decides F*) its contacts creep.
// Cuts below that margin are held or not as Box2D decides, and reported.
//
// Units: the analysis is in the fixture's units and the simulation in
// metres, scaled by p.scale with the mass kept; an acceleration scales by
// p.scale and so does a force (F_sim = p.scale F_model), gravity G_model =
// ACCEL / p.scale.
constexpr double HOLD_MARGIN = 0.05;

struct Cut {
    V2 at, dir;        // body frame (m), unit
    double magnitude;  // N
    double wrench[3];  // fixture units (model system)
    bool asserted = true; // this trial: its wrench's G_strong margin > HOLD_MARGIN
};

std::vector<Cut> cutting_sequence(const Prepared &p)
{
    std::vector<Cut> cuts;
    const double g_model = ACCEL / p.scale;
    auto add = [&](int e, double t) {
        double at[2], nu[2];
        wr_boundary_point(p.f, e, t, at, nu);
        if (!(nu[1] < -0.5))
            return; // not facing up
        const double tangent[2] = {-nu[1], nu[0]};
        const double force[2] = {0.4 * p.mass * g_model * (nu[0] + 0.5 * tangent[0]),
                                 0.4 * p.mass * g_model * (nu[1] + 0.5 * tangent[1])};
        Cut c;
        wr_fixture_force_wrench(p.f, force, at, c.wrench);
        c.at = V2{p.scale * at[0], p.scale * at[1]} - p.com;
        double length = std::hypot(force[0], force[1]);
        c.dir = {force[0] / length, force[1] / length};
        c.magnitude = p.scale * length;
        cuts.push_back(c);
    };
    if (p.circle) {
        add(0, 90);
    } else {
        for (int e = 0; e < edge_count(p); e++)
            add(e, 0.5);
    }
    if (cuts.size() > 4)
        cuts.resize(4);
    return cuts;
}

struct ForceTrial {
    bool seated = false, held = false;
    double moved = 0;          // largest boundary displacement under the asserted cuts
    double moved_marginal = 0; // ... under the others (reported)
    long long deep = 0;
};

ForceTrial run_force_trial(const Prepared &p, const Start &st, const Load &finger, double force,
                           const std::vector<Cut> &cuts)
{
    Sim sim(p, st.pose, st.v, st.w, {0, -ACCEL});
    const unsigned all = (1u << p.k) - 1;
    const int rest_steps = (int)std::lround(REST_TIME * HZ);
    const int limit = (int)std::lround(TIME_LIMIT * HZ);
    auto press = [&]() {
        sim.part->ApplyForce((float)force * sim.part->GetWorldVector(b2(finger.dir)),
                             sim.part->GetWorldPoint(b2(finger.at)), true);
    };
    ForceTrial out;
    int calm = 0;
    for (int n = 1; n <= limit && calm < rest_steps; n++) {
        press();
        sim.step();
        double v = sim.part->GetLinearVelocity().Length(), w = std::fabs(sim.part->GetAngularVelocity());
        calm = v < REST_SPEED && w < REST_SPIN && sim.touching() == all ? calm + 1 : 0;
    }
    Pose rest = sim.pose();
    double pos_err = p.circle ? norm((rest.x + rotate(p.center, rest.th)) - (p.com + p.center))
                              : norm(rest.x - p.com);
    double ang_err = p.circle ? 0 : std::fabs(rest.th) * DEG;
    out.seated = calm >= rest_steps && pos_err < POSE_TOLERANCE && ang_err < ANGLE_TOLERANCE;
    if (out.seated) {
        // The cuts one after the other, the finger pushing throughout.
        // A cut's displacement is from where the last one left the part.
        const int steps = (int)std::lround(HOLD_TIME / 3 * HZ);
        for (const Cut &c : cuts) {
            Pose from = sim.pose();
            double &moved = c.asserted ? out.moved : out.moved_marginal;
            for (int n = 0; n < steps; n++) {
                press();
                sim.part->ApplyForce((float)c.magnitude * sim.part->GetWorldVector(b2(c.dir)),
                                     sim.part->GetWorldPoint(b2(c.at)), true);
                sim.step();
                moved = std::max(moved, boundary_displacement(p, from, sim.pose()));
            }
        }
        out.held = out.moved < MOVE_TOLERANCE;
    }
    out.deep = sim.friction.deep;
    return out;
}

// factor 1.05: the criterion (>= 99% seated and held); below 1: reported.
Row force_trials(const Prepared &p, const char *set, double factor, int points, int trials)
{
    auto t0 = Clock::now();
    Row row;
    row.fixture = p.name;
    row.set = set;
    row.criterion = factor > 1 ? AT_LEAST_99 : REPORT;
    std::vector<Cut> cuts = cutting_sequence(p);
    std::vector<std::array<double, 3>> loads;
    const double g_model = ACCEL / p.scale;
    loads.push_back({0, -p.mass * g_model, 0});
    for (const Cut &c : cuts)
        loads.push_back({c.wrench[0], -p.mass * g_model + c.wrench[1], c.wrench[2]});
    const int cases = (int)loads.size();
    const double(*lp)[3] = reinterpret_cast<const double(*)[3]>(loads.data());
    wr_least_force best;
    if (wr_least_force_find(p.an, WR_SET_BOTH, lp, cases, 0, nullptr, &best) != WR_OK || !best.found) {
        row.criterion = NOT_APPLICABLE;
        row.note = "no push of any force does both under every case";
        return row;
    }
    double least_seen = INFINITY, most_seen = 0, worst_move = 0;
    int attempts = 0, failures_shown = 0, marginal_cuts = 0, marginal_held = 0;
    Rng prng(seed_of(p.name, set, 0, -1));
    int edges = edge_count(p);
    while (row.points < points && attempts++ < 200 * points) {
        int edge = (int)prng.uniform(0, edges);
        double t = p.circle ? prng.uniform(0, 360) : prng.uniform(0.02, 0.98);
        double w[3], least;
        Load finger = finger_at(p, edge, t, w);
        if (wr_least_force_at(p.an, WR_SET_BOTH, lp, cases, w, &least) != WR_OK || !std::isfinite(least))
            continue;
        // 1.05 F* must still do the job under every case.
        bool inside = true;
        wr_forces good = {0, 0, nullptr};
        for (int c = 0; c < cases && inside; c++) {
            inside = false;
            if (wr_force_range(p.an, WR_SET_BOTH, lp[c], w, 0, INFINITY, &good) == WR_OK)
                for (int i = 0; i < good.count; i++)
                    inside |= good.items[i].lo < 1.05 * least && 1.05 * least < good.items[i].hi;
        }
        wr_forces_release(&good);
        if (!inside || least <= 0)
            continue;
        row.points++;
        least_seen = std::min(least_seen, least);
        most_seen = std::max(most_seen, least);
        double force = factor * least * p.scale;
        for (size_t c = 0; c < cuts.size(); c++) {
            double cw[3];
            for (int k = 0; k < 3; k++)
                cw[k] = lp[c + 1][k] + factor * least * w[k];
            cuts[c].asserted = margin_of(p, cw, WR_SET_STRONG) > HOLD_MARGIN;
        }
        for (int r = 0; r < trials; r++) {
            Rng rng(seed_of(p.name, set, row.points, r));
            Start st;
            if (!sample_start(p, rng, &st))
                continue;
            ForceTrial ft = run_force_trial(p, st, finger, force, cuts);
            for (const Cut &c : cuts)
                if (!c.asserted && ft.seated) {
                    marginal_cuts++;
                    marginal_held += ft.moved_marginal < MOVE_TOLERANCE;
                }
            row.trials++;
            row.deep_trials += ft.deep > 0;
            if (ft.seated && ft.held) {
                row.successes++;
                worst_move = std::max(worst_move, ft.moved);
            } else if (factor > 1 && failures_shown < 10) {
                failures_shown++;
                std::fprintf(stderr, "  %s %s: edge %d t %.4f F* %.6g: seated %d, moved %.4f m\n",
                             p.name.c_str(), set, edge, t, least, (int)ft.seated, ft.moved);
            }
        }
    }
    if (row.points == 0) {
        row.criterion = NOT_APPLICABLE;
        row.note = "no point where 1.05 F* stays inside every case's interval";
        return row;
    }
    row.note = fmt("%zu cuts after seating; F* %.4g..%.4g N (scaled), least over the outline %.4g; "
                   "displacement <= %.4f m while cut",
                   cuts.size(), least_seen * p.scale, most_seen * p.scale, best.force * p.scale, worst_move);
    if (marginal_cuts)
        row.note += fmt("; %d cut(s) with G_strong margin <= %.2f (reported): %d held", marginal_cuts,
                        HOLD_MARGIN, marginal_held);
    finish(row);
    row.seconds = since(t0);
    return row;
}

// The seated part under pushes at points of the G_strong region.
Row hold_pushes(const Prepared &p, const Config &cfg, const char *set, bool inside,
                const std::vector<Interval> &iv, int points)
{
    auto t0 = Clock::now();
    Row row;
    row.fixture = p.name;
    row.set = set;
    row.criterion = inside ? NONE_MOVES : SOME_MOVE;
    if (iv.empty()) {
        row.criterion = NOT_APPLICABLE;
        row.note = "no G_strong push region";
        return row;
    }
    double worst = 0;
    int near_boundary = 0;
    for (int j = 0; j < points; j++) {
        Rng prng(seed_of(p.name, set, j, -1));
        int edge;
        double t, w[3];
        if (inside) {
            if (!point_in(iv, j, points, prng, &edge, &t))
                continue;
        } else {
            point_outside(p, iv, prng, &edge, &t);
        }
        Load finger = finger_at(p, edge, t, w);
        double ms = margin_of(p, w, WR_SET_STRONG);
        if (inside && ms < HOLD_PUSH_MARGIN) {
            near_boundary++;
            continue;
        }
        Hold h = run_hold(p, {0, 0}, 0, &finger);
        row.points++;
        row.trials++;
        // A trial in which a fixel sank into the part counts as moved where
        // nothing may move, and as not moved where something must.
        row.deep_trials += h.deep > 0;
        bool moved = h.moved > MOVE_TOLERANCE;
        if (inside) {
            moved = moved || h.deep > 0;
            row.successes += !moved;
            worst = std::max(worst, h.moved);
            if (moved && (cfg.verbose || row.trials - row.successes <= 10))
                std::fprintf(stderr, "  moved: %s %s edge %d t %.6f (strong margin %+.4f): %.4f m\n",
                             p.name.c_str(), set, edge, t, ms, h.moved);
        } else {
            moved = moved && h.deep == 0;
            row.successes += moved;
            if (!moved && cfg.verbose)
                std::fprintf(stderr, "  held: %s %s edge %d t %.6f (strong margin %+.4f, by %s): %.2e m\n",
                             p.name.c_str(), set, edge, t, ms, blocking_of(p, w, WR_SET_STRONG).c_str(), h.moved);
        }
    }
    row.note = inside ? fmt("largest displacement %.2e m", worst)
                      : fmt("success = moved more than %.3f m", MOVE_TOLERANCE);
    if (near_boundary > 0)
        row.note += fmt("; %d points within %.3g of the boundary not tried", near_boundary,
                        HOLD_PUSH_MARGIN);
    finish(row);
    row.seconds = since(t0);
    return row;
}

// The seated part under random wrenches clearly inside (margin > 0.05) or
// outside (margin < -0.05) G_strong, of magnitude mass * ACCEL in the
// scaled metric.
Row hold_wrenches(const Prepared &p, const Config &cfg, const char *set, bool inside, int count)
{
    auto t0 = Clock::now();
    Row row;
    row.fixture = p.name;
    row.set = set;
    row.criterion = inside ? NONE_MOVES : SOME_MOVE;
    double worst = 0;
    int drawn = 0;
    Rng rng(seed_of(p.name, set, 0, 0));
    std::vector<std::string> modes;
    while (row.trials < count && drawn < 200000) {
        drawn++;
        double u[3], len;
        do {
            for (double &c : u)
                c = rng.uniform(-1, 1);
            len = std::sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
        } while (len > 1 || len < 1e-3);
        for (double &c : u)
            c /= len;
        double w[3] = {u[0], u[1], u[2] * p.f->gyration_radius}; // fixture units
        double ms = margin_of(p, w, WR_SET_STRONG);
        if (inside ? !(ms > STRONG_MARGIN) : !(ms < -STRONG_MARGIN))
            continue;
        double F = p.mass * ACCEL;
        Hold h = run_hold(p, {F * u[0], F * u[1]}, F * u[2] * p.rho, nullptr);
        row.points++;
        row.trials++;
        row.deep_trials += h.deep > 0;
        bool moved = h.moved > MOVE_TOLERANCE;
        if (inside) {
            moved = moved || h.deep > 0;
            row.successes += !moved;
            worst = std::max(worst, h.moved);
            if (moved && (cfg.verbose || row.trials - row.successes <= 10))
                std::fprintf(stderr, "  moved: %s %s w (%.4f, %.4f, %.4f) strong margin %+.4f: %.4f m\n",
                             p.name.c_str(), set, w[0], w[1], w[2], ms, h.moved);
        } else {
            moved = moved && h.deep == 0;
            row.successes += moved;
            if (!moved && cfg.verbose)
                std::fprintf(stderr, "  held: %s w (%.4f, %.4f, %.4f) strong margin %+.4f by %s: %.2e m\n",
                             p.name.c_str(), w[0], w[1], w[2], ms, blocking_of(p, w, WR_SET_STRONG).c_str(),
                             h.moved);
        }
    }
    if (row.trials == 0) {
        row.criterion = NOT_APPLICABLE;
        row.note = inside ? "no wrench with margin > 0.05" : "no wrench with margin < -0.05";
        return row;
    }
    row.note = inside ? fmt("largest displacement %.2e m", worst)
                      : fmt("success = moved more than %.3f m", MOVE_TOLERANCE);
    finish(row);
    row.seconds = since(t0);
    return row;
}

std::string region_text(const Prepared &p, const std::vector<Interval> &iv)
{
    std::string s;
    for (const Interval &r : iv)
        s += (s.empty() ? "" : ", ") +
             (p.circle || r.edge < 0 ? fmt("(%.4f, %.4f) deg", r.t0, r.t1)
                                     : fmt("edge %d t (%.4f, %.4f)", r.edge, r.t0, r.t1));
    return s.empty() ? "none" : s;
}

// Box2D's distance between each fixel and the part at the seated pose: the
// geometry given to Box2D must touch exactly there.
double seated_distance(const Prepared &p)
{
    Sim sim(p, {p.com, 0}, {0, 0}, 0, {0, 0});
    double worst = 0;
    for (int i = 0; i < p.k; i++)
        worst = std::max(worst, sim.distance(i));
    return worst;
}

// Friction calibration: a 4 m x 1 m block (same skin, same fixel circles,
// same listener) on two fixels 2 m apart under its bottom edge, under
// gravity tilted so that the tangential load over the normal load is
// `ratio`, starting with tangential speed v0.  Over CALIBRATION_TIME (or
// until it has slid 0.8 m) it returns the distance slid and the friction coefficient that explains its
// mean acceleration from 0.05 s after it first slid faster than SLIP_SPEED
// (when the listener turns to mu_k): ratio - a / (g cos alpha).
constexpr double CALIBRATION_TIME = 2.0;

void slide(double mu_s, double mu_k, double ratio, double v0, double *distance, double *mu_seen,
           double *speed)
{
    Prepared p;
    p.name = "calibration";
    p.k = 2;
    p.mass = 1;
    p.inertia = (16.0 + 1.0) / 12.0;
    p.rho = std::sqrt(p.inertia);
    p.com = {0, 0.5};
    p.outline = {{-2, -0.5}, {2, -0.5}, {2, 0.5}, {-2, 0.5}};
    p.out_normal = {{0, -1}, {1, 0}, {0, 1}, {-1, 0}};
    double d = b2_polygonRadius;
    p.core = {{-2 + d, -0.5 + d}, {2 - d, -0.5 + d}, {2 - d, 0.5 - d}, {-2 + d, 0.5 - d}};
    for (double x : {-1.0, 1.0}) {
        p.fixel_at.push_back({x, 0});
        p.fixel_normal.push_back({0, 1});
        p.fixel_center.push_back({x, -FIXEL_RADIUS});
        p.mu_s.push_back(mu_s);
        p.mu_k.push_back(mu_k);
    }
    double a = std::atan(ratio);
    Sim sim(p, preloaded(p), {v0, 0}, 0, {ACCEL * std::sin(a), -ACCEL * std::cos(a)});
    const int steps = (int)std::lround(CALIBRATION_TIME * HZ), settle = (int)std::lround(0.05 * HZ);
    int slipped = -1, from = -1, n = 1;
    double v1 = 0;
    for (; n <= steps; n++) {
        sim.step();
        double v = sim.part->GetLinearVelocity().x;
        if (slipped < 0 && std::fabs(v) > SLIP_SPEED)
            slipped = n;
        if (slipped >= 0 && n == slipped + settle) {
            from = n;
            v1 = v;
        }
        // The block stays on both fixels for 1 m either way: stop at 0.8 m.
        if (std::fabs(sim.part->GetPosition().x - p.com.x) > 0.8)
            break;
    }
    n = std::min(n, steps);
    *distance = sim.part->GetPosition().x - p.com.x;
    *speed = sim.part->GetLinearVelocity().x;
    *mu_seen = NAN;
    if (from >= 0 && from < n) {
        double accel = (*speed - v1) / ((n - from) / HZ);
        *mu_seen = ratio - accel / (ACCEL * std::cos(a));
    }
}

// Checks that the coefficient Box2D applies is the fixture's: at rest the
// block holds under a load of 0.95 mu_s; under max(1.05 mu_s, mu_s + 0.01)
// it slides, and
// while it slides (from rest, or launched at 0.5 m/s under loads between
// mu_k and mu_s and below mu_k) the coefficient its acceleration shows is
// mu_k within 1%.
Row calibrate(double mu_s, double mu_k)
{
    auto t0 = Clock::now();
    Row row;
    row.fixture = "(calibration)";
    row.set = fmt("friction %g/%g", mu_s, mu_k);
    row.criterion = ALL;
    double dist, seen, speed;
    std::string notes;
    auto check = [&](bool ok, const std::string &what) {
        row.points++;
        row.trials++;
        row.successes += ok;
        notes += (notes.empty() ? "" : "; ") + what + (ok ? "" : " FAILED");
    };
    auto close = [&](double mu) { return std::fabs(mu - mu_k) <= 0.01 * std::max(mu_k, 0.01); };
    if (mu_s > 0) {
        slide(mu_s, mu_k, 0.95 * mu_s, 0, &dist, &seen, &speed);
        check(std::fabs(dist) < MOVE_TOLERANCE, fmt("rest, 0.95 mu_s: held (%.1e m)", dist));
    }
    double over = std::max(1.05 * mu_s, mu_s + 0.01);
    slide(mu_s, mu_k, over, 0, &dist, &seen, &speed);
    check(dist > MOVE_TOLERANCE && close(seen), fmt("rest, max(1.05 mu_s, mu_s + 0.01): slid, mu %.4f", seen));
    if (mu_k < mu_s) {
        slide(mu_s, mu_k, 0.5 * (mu_s + mu_k), 0.5, &dist, &seen, &speed);
        check(speed > 0.5 && close(seen), fmt("sliding, (mu_s+mu_k)/2: kept sliding, mu %.4f", seen));
    }
    if (mu_k > 0) {
        slide(mu_s, mu_k, 0.9 * mu_k, 0.5, &dist, &seen, &speed);
        check(speed < 0.5 && (speed < REST_SPEED || close(seen)),
              speed < REST_SPEED ? fmt("sliding, 0.9 mu_k: stopped") : fmt("sliding, 0.9 mu_k: slowed, mu %.4f", seen));
    }
    row.note = notes;
    finish(row);
    row.seconds = since(t0);
    return row;
}

// ---- investigations (--sweep): not criteria, the numbers behind the
// "where Box2D and the model disagree" section of docs/VALIDATION.md ----

// Seating rate and mean time at n points of every edge (or n angles of a
// circle), `reps` trials each; `spin` > 0 replaces the start's angular
// velocity by +-spin rad/s (random sign).
void sweep_pushes(const Prepared &p, int n, int reps, double spin)
{
    std::printf("\n%s: pushes along the outline, %d trials a point%s\n", p.name.c_str(), reps,
                spin > 0 ? fmt(", spinning at +-%g rad/s (half each way)%s", spin,
                               p.circle ? ", the finger fixed in the world" : "").c_str() : "");
    std::printf("%4s %10s %9s %9s %-6s %7s %8s\n", "edge", "t", "goal", "strong", "block", "seated", "time");
    for (int e = 0; e < edge_count(p); e++) {
        for (int j = 0; j < n; j++) {
            double t = (j + 0.5) / n * edge_range(p), w[3];
            Load load = finger_at(p, e, t, w);
            load.world_fixed = spin > 0 && p.circle;
            const char *tr = std::getenv("PHYSICS_TRACE");
            trace = tr && std::fabs(std::atof(tr) - t) < 1e-6;
            int ok = 0;
            double time = 0;
            for (int r = 0; r < reps; r++) {
                Rng rng(seed_of(p.name, "sweep", e * n + j, r));
                Start st;
                if (!sample_start(p, rng, &st))
                    continue;
                if (spin > 0)
                    st.w = (r % 2 ? -spin : spin);
                if (trace)
                    std::fprintf(stderr, "trial %d: start x %.4f %.4f th %.3f v %.4f %.4f w %.3f\n", r,
                                 st.pose.x.x - p.com.x, st.pose.x.y - p.com.y, st.pose.th * DEG, st.v.x, st.v.y, st.w);
                Seat sres = run_seat(p, st, load);
                ok += sres.seated;
                time += sres.seated ? sres.time : 0;
            }
            trace = false;
            std::printf("%4d %10.4f %+9.4f %+9.4f %-6s %6.0f%% %7.2fs\n", e, t, margin_of(p, w, WR_SET_GOAL),
                        margin_of(p, w, WR_SET_STRONG), blocking_of(p, w, WR_SET_GOAL).c_str(),
                        100.0 * ok / reps, ok ? time / ok : 0.0);
        }
    }
}

// A seated disc spinning at +-spin rad/s under a world-fixed frictionless
// finger: which fixels open a gap wider than MOVE_TOLERANCE within
// HOLD_TIME.  From state "all touching" with every contact sliding, this is
// the seed's figure 5: a contact breaks exactly where the model puts a
// backward transition (ms / sm for the disc in a corner).
// The seated disc spinning at `spin` rad/s under a world-fixed finger at
// (0, t): the fixels (bits) whose gap opened wider than MOVE_TOLERANCE
// within HOLD_TIME.
unsigned spin_breaks(const Prepared &p, double t, double spin)
{
    double w[3];
    Load load = finger_at(p, 0, t, w);
    load.world_fixed = true;
    Sim sim(p, preloaded(p), {0, 0}, spin, {0, 0});
    unsigned bits = 0;
    for (int k = 0; k < (int)std::lround(HOLD_TIME * HZ); k++) {
        push(sim.part, p, load);
        sim.step();
        for (int i = 0; i < p.k; i++)
            if (gap(p, sim.pose(), i) > MOVE_TOLERANCE)
                bits |= 1u << i;
    }
    return bits;
}

std::string bit_text(const Prepared &p, unsigned bits)
{
    std::string s;
    for (int i = 0; i < p.k; i++)
        s += (bits >> i & 1) ? '1' : '0';
    return s;
}

// A seated disc spinning at +-spin rad/s under a world-fixed frictionless
// finger: which fixels open a gap.  With every contact sliding, this is the
// seed's figure 5: a contact breaks where the model puts a backward
// transition (ms / sm for the disc in a corner).
void sweep_spin_seated(const Prepared &p, int n, double spin)
{
    std::printf("\n%s: the seated disc spinning at +-%g rad/s, finger fixed in the world\n", p.name.c_str(), spin);
    std::printf("%10s %9s %-6s %12s %12s\n", "t", "goal", "block", "broke (+)", "broke (-)");
    for (int j = 0; j < n; j++) {
        double t = (j + 0.5) / n * 360.0, w[3];
        wr_push_wrench(p.f, 0, t, w);
        std::printf("%10.4f %+9.4f %-6s %12s %12s\n", t, margin_of(p, w, WR_SET_GOAL),
                    blocking_of(p, w, WR_SET_GOAL).c_str(), bit_text(p, spin_breaks(p, t, spin)).c_str(),
                    bit_text(p, spin_breaks(p, t, -spin)).c_str());
    }
}

// From contact state `state` (those fixels touching, the others GAP_MAX
// away), the part launched at `speed` m/s along the motion that keeps the
// touched fixels touching (both ways), pushed at n points of every edge:
// which touched fixels open a gap wider than MOVE_TOLERANCE during the
// launch (until the velocity along the launch turns, an untouched fixel is
// reached, or the part has gone 10% of its size).  It probes the m letters
// (sliding either way) of G_goal's backward transitions; the start's gap
// and the slide itself displace the part, which moves the boundary (see
// docs/VALIDATION.md).
void sweep_slide(const Prepared &p, unsigned state, int n, double speed)
{
    Pose seated{p.com, 0};
    double J[3][3], target[3] = {0, 0, 0}, q[3];
    for (int i = 0; i < p.k; i++)
        target[i] = (state >> i & 1) ? 0 : GAP_MAX;
    gap_jacobian(p, seated, J);
    if (!least_norm(p, J, target, q))
        return;
    Pose start = apply(p, seated, q);
    // A translation d with n_i . d = 0 for every touched fixel.
    V2 d{0, 0};
    for (int i = 0; i < p.k; i++)
        if (state >> i & 1)
            d = {-p.fixel_normal[i].y, p.fixel_normal[i].x};
    for (int i = 0; i < p.k; i++)
        if ((state >> i & 1) && std::fabs(dot(d, p.fixel_normal[i])) > 1e-9) {
            std::printf("\n%s: state %x: no translation keeps every touched fixel\n", p.name.c_str(), state);
            return;
        }
    char bits[WR_MAX_FIXELS + 1] = {};
    for (int i = 0; i < p.k; i++)
        bits[i] = (state >> i & 1) ? '1' : '0';
    std::printf("\n%s: from state %s sliding at +-%g m/s along (%.3f, %.3f): touched fixels that broke\n",
                p.name.c_str(), bits, speed, d.x, d.y);
    std::printf("%4s %10s %9s %-6s %10s %10s\n", "edge", "t", "goal", "block", "broke (+)", "broke (-)");
    for (int e = 0; e < edge_count(p); e++) {
        for (int j = 0; j < n; j++) {
            double t = (j + 0.5) / n * edge_range(p), w[3];
            Load load = finger_at(p, e, t, w);
            std::string broke[2];
            for (int sign = 0; sign < 2; sign++) {
                V2 v0 = (sign ? -speed : speed) * d;
                Sim sim(p, start, v0, 0, {0, 0});
                unsigned b = 0;
                for (int k = 0; k < (int)std::lround(HOLD_TIME * HZ); k++) {
                    push(sim.part, p, load);
                    sim.step();
                    // Only while the launch lasts, near the seated pose.
                    if (dot(v2(sim.part->GetLinearVelocity()), v0) <= 0 ||
                        norm(sim.pose().x - start.x) > 0.1 * SIZE || (sim.touching() & ~state))
                        break;
                    for (int i = 0; i < p.k; i++)
                        if ((state >> i & 1) && gap(p, sim.pose(), i) > MOVE_TOLERANCE)
                            b |= 1u << i;
                    const char *tr = std::getenv("PHYSICS_TRACE");
                    if (tr && p.k == 3 && std::fabs(std::atof(tr) - t) < 1e-6 && k % 6 == 0 && k < 60)
                        std::fprintf(stderr, "state %x edge %d sign %c k %d N %.5f %.5f T %.5f %.5f v %.4f %.4f w %.5f th %.5f gaps %.5f %.5f %.5f touching %u\n", state, e,
                                     sign ? '-' : '+', k, sim.friction.impulse[0][0] * HZ, sim.friction.impulse[1][0] * HZ,
                                     sim.friction.impulse[0][1] * HZ, sim.friction.impulse[1][1] * HZ,
                                     sim.part->GetLinearVelocity().x, sim.part->GetLinearVelocity().y,
                                     sim.part->GetAngularVelocity(), sim.pose().th, gap(p, sim.pose(), 0),
                                     gap(p, sim.pose(), 1), gap(p, sim.pose(), 2), sim.touching());
                }
                for (int i = 0; i < p.k; i++)
                    broke[sign] += (b >> i & 1) ? '1' : '0';
            }
            std::printf("%4d %10.4f %+9.4f %-6s %10s %10s\n", e, t, margin_of(p, w, WR_SET_GOAL),
                        blocking_of(p, w, WR_SET_GOAL).c_str(), broke[0].c_str(), broke[1].c_str());
        }
    }
}

void sweep_tilts(const Prepared &p, int n, int reps)
{
    std::printf("\n%s: gravity tilts, %d trials a tilt\n", p.name.c_str(), reps);
    std::printf("%8s %9s %-6s %7s %8s\n", "phi", "goal", "block", "seated", "time");
    for (int j = 0; j < n; j++) {
        double phi = (j + 0.5) / n * 360.0;
        Load load;
        load.gravity = true;
        load.g = {ACCEL * std::cos(phi / DEG), ACCEL * std::sin(phi / DEG)};
        double w[3] = {p.f->mass * std::cos(phi / DEG), p.f->mass * std::sin(phi / DEG), 0};
        int ok = 0;
        double time = 0;
        for (int r = 0; r < reps; r++) {
            Rng rng(seed_of(p.name, "sweep-tilt", j, r));
            Start st;
            if (!sample_start(p, rng, &st))
                continue;
            Seat sres = run_seat(p, st, load);
            ok += sres.seated;
            time += sres.seated ? sres.time : 0;
        }
        std::printf("%8.2f %+9.4f %-6s %6.0f%% %7.2fs\n", phi, margin_of(p, w, WR_SET_GOAL),
                    blocking_of(p, w, WR_SET_GOAL).c_str(), 100.0 * ok / reps, ok ? time / ok : 0.0);
    }
}

// Random unit wrenches on the seated part, binned by G_strong margin: the
// fraction that moved more than MOVE_TOLERANCE in HOLD_TIME.
void sweep_strong(const Prepared &p, int count)
{
    const double edges[] = {-1, -0.2, -0.05, -0.01, 0, 0.01, 0.05, 0.2, 1.0000001};
    const int bins = 8;
    int total[bins] = {}, moved[bins] = {};
    double largest_held[bins] = {};
    Rng rng(seed_of(p.name, "sweep-strong", 0, 0));
    for (int c = 0; c < count; c++) {
        double u[3], len;
        do {
            for (double &x : u)
                x = rng.uniform(-1, 1);
            len = std::sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
        } while (len > 1 || len < 1e-3);
        for (double &x : u)
            x /= len;
        double w[3] = {u[0], u[1], u[2] * p.f->gyration_radius};
        double ms = margin_of(p, w, WR_SET_STRONG);
        int b = 0;
        while (b + 1 < bins && ms >= edges[b + 1])
            b++;
        double F = p.mass * ACCEL;
        Hold h = run_hold(p, {F * u[0], F * u[1]}, F * u[2] * p.rho, nullptr);
        total[b]++;
        if (h.moved > MOVE_TOLERANCE)
            moved[b]++;
        else
            largest_held[b] = std::max(largest_held[b], h.moved);
    }
    std::printf("\n%s: %d random unit wrenches on the seated part, by G_strong margin\n", p.name.c_str(), count);
    std::printf("%-16s %7s %7s %8s %12s\n", "margin", "wrenches", "moved", "rate", "largest held");
    for (int b = 0; b < bins; b++)
        std::printf("[%+.2f, %+.2f)  %7d %7d %7.1f%% %10.2e m\n", edges[b], std::min(edges[b + 1], 1.0), total[b],
                    moved[b], total[b] ? 100.0 * moved[b] / total[b] : 0.0, largest_held[b]);
}

// Discs only: the seated disc spinning at +-SPIN rad/s (both ways at every
// point) under a world-fixed finger at points inside G_goal (no fixel may
// break: G_goal excludes every backward transition whatever the sliding
// direction, and a disc spinning about its centre of mass has no
// velocity-product terms) or inside G_strong but outside G_goal (reported:
// the rate at which some fixel broke).
constexpr double SPIN = 5.0;

Row spin_trials(const Prepared &p, const char *set, bool inside, const std::vector<Interval> &goal,
                const std::vector<Interval> &strong, int points)
{
    auto t0 = Clock::now();
    Row row;
    row.fixture = p.name;
    row.set = set;
    row.criterion = inside ? NO_BREAK : REPORT;
    std::vector<Interval> iv;
    if (inside) {
        iv = goal;
    } else {
        // G_strong minus G_goal, on the circle.
        for (const Interval &r : strong) {
            double a = r.t0;
            for (const Interval &g : goal)
                if (g.t0 >= a && g.t1 <= r.t1) {
                    if (g.t0 > a)
                        iv.push_back({0, a, g.t0});
                    a = g.t1;
                }
            if (a < r.t1)
                iv.push_back({0, a, r.t1});
        }
    }
    if (iv.empty()) {
        row.criterion = NOT_APPLICABLE;
        row.note = "no such arc";
        return row;
    }
    double least = 1;
    for (int j = 0; j < points; j++) {
        Rng prng(seed_of(p.name, set, j, -1));
        int edge;
        double t, w[3];
        if (!point_in(iv, j, points, prng, &edge, &t))
            continue;
        wr_push_wrench(p.f, 0, t, w);
        least = std::min(least, std::fabs(margin_of(p, w, WR_SET_GOAL)));
        row.points++;
        for (double sp : {SPIN, -SPIN}) {
            unsigned broke = spin_breaks(p, t, sp);
            row.trials++;
            if (inside) {
                row.successes += broke == 0;
                if (broke)
                    std::fprintf(stderr, "  broke: %s %s at %.4f deg, spin %+g: fixels %s\n", p.name.c_str(), set, t,
                                 sp, bit_text(p, broke).c_str());
            } else {
                row.successes += broke != 0;
            }
        }
    }
    row.note = inside ? fmt("success = no fixel opens %.3f m; least |goal margin| %.4f", MOVE_TOLERANCE, least)
                      : fmt("success = a fixel opened %.3f m; least |goal margin| %.4f", MOVE_TOLERANCE, least);
    finish(row);
    row.seconds = since(t0);
    return row;
}

// ---- tolerance: robust pushes on fixtures with displaced locators ----
//
// --tolerance T,A: the fixture's geometric tolerance (docs/MODEL.md section
// 10).  wrenchd's robust both region is asked (wr_robust_regions); then,
// for random displacements of the set (each contact moved along its
// segment within T, its normal tilted within A: wr_tolerance_perturb), the
// displaced fixture is written out as a fixture of its own and given to
// Box2D, and pushes at points of the robust region must seat the part from
// random starts and hold it once seated, every one.

// The fixture file's JSON with its fixels at `moved`'s points and normals.
bool write_displaced(const std::string &file, const wr_fixture &moved, const std::string &out)
{
    std::string text;
    if (!read_text(file, &text))
        return false;
    cJSON *json = cJSON_Parse(text.c_str());
    if (!json)
        return false;
    cJSON *fixels = cJSON_GetObjectItem(json, "fixels");
    for (int i = 0; i < moved.fixel_count; i++) {
        cJSON *fixel = cJSON_GetArrayItem(fixels, i);
        cJSON_DeleteItemFromObject(fixel, "at");
        cJSON_DeleteItemFromObject(fixel, "normal");
        cJSON_AddItemToObject(fixel, "at", cJSON_CreateDoubleArray(moved.fixels[i].at, 2));
        cJSON_AddItemToObject(fixel, "normal", cJSON_CreateDoubleArray(moved.fixels[i].normal, 2));
    }
    cJSON_DeleteItemFromObject(json, "tolerance");
    char *printed = cJSON_PrintUnformatted(json);
    cJSON_Delete(json);
    std::ofstream f(out);
    bool ok = printed && (f << printed);
    std::free(printed);
    return ok;
}

Row tolerance_trials(Prepared &p, double position, double angle, int displacements, int points,
                     int trials)
{
    auto t0 = Clock::now();
    Row row;
    row.fixture = p.name;
    row.set = fmt("both, robust (T %g, A %g)", position, angle);
    row.criterion = ALL;
    wr_tolerance tolerance = {true, position / 1.0, angle};
    wr_error why{};
    if (wr_fixture_set_tolerance(p.doc.fixture, &tolerance, &why) != WR_OK) {
        row.criterion = NOT_APPLICABLE;
        row.note = fmt("%s: %s", why.field, why.reason);
        finish(row);
        return row;
    }
    wr_robust *robust = nullptr;
    wr_regions nominal{}, found{};
    std::vector<Interval> iv;
    if (wr_robust_new(p.an, 16, &robust) == WR_OK &&
        wr_push_regions(p.an, WR_SET_BOTH, 0, NULL, &nominal) == WR_OK &&
        wr_robust_regions(robust, WR_SET_BOTH, &nominal, false, NULL, &found) == WR_OK)
        for (int i = 0; i < found.count; i++)
            iv.push_back({found.items[i].edge, found.items[i].t0, found.items[i].t1});
    wr_regions_release(&nominal);
    wr_regions_release(&found);
    row.note = "robust both region " + region_text(p, iv);
    const wr_fixture *f = p.f;
    std::string tmp = fmt("/tmp/physics-tolerance-%d.json", (int)getpid());
    for (int d = 0; d < displacements && !iv.empty(); d++) {
        Rng drng(seed_of(p.name, "tolerance", d, 0));
        double s[WR_MAX_FIXELS], tilt[WR_MAX_FIXELS];
        for (int i = 0; i < f->fixel_count; i++) {
            double reach = wr_tolerance_reach(f, i), a = angle * M_PI / 180;
            // the ends of the ranges half the time: where worst cases live
            s[i] = drng.uniform() < 0.5 ? (drng.uniform() < 0.5 ? -reach : reach)
                                        : reach * (2 * drng.uniform() - 1);
            // Box2D's round fixels push along the surface's normal: the
            // displacements keep it (tilts are checked by the unit and e2e
            // tests' sampling, not here).
            tilt[i] = 0 * a;
        }
        wr_fixture moved;
        wr_tolerance_perturb(f, s, tilt, &moved);
        Prepared q;
        std::string error;
        if (!write_displaced(p.file, moved, tmp) || !prepare(tmp, &q, &error) || !q.unsupported.empty()) {
            error += q.unsupported;
            row.note += "; displaced fixture not built: " + error;
            row.pass = false;
            break;
        }
        q.name = p.name;
        for (int j = 0; j < points; j++) {
            Rng prng(seed_of(p.name, "tolerance point", d, j));
            int edge;
            double t, w[3];
            if (!point_in(iv, j, points, prng, &edge, &t))
                continue;
            Load finger = finger_at(q, edge, t, w);
            row.points++;
            for (int r = 0; r < trials; r++) {
                Rng rng(seed_of(p.name, "tolerance start", d * 1000 + j, r));
                Start st;
                if (!sample_start(q, rng, &st))
                    continue;
                Seat seat = run_seat(q, st, finger);
                Hold hold = run_hold(q, {0, 0}, 0, &finger);
                row.trials++;
                row.deep_trials += seat.deep > 0 || hold.deep > 0;
                bool ok = seat.seated && hold.moved <= MOVE_TOLERANCE && hold.deep == 0;
                row.successes += ok;
                if (!ok)
                    std::fprintf(stderr, "  robust push failed: %s displacement %d edge %d t %.6f: seated %d, "
                                 "held moved %.4f m\n", p.name.c_str(), d, edge, t, (int)seat.seated, hold.moved);
            }
        }
        wr_analysis_free(q.an);
        wp_fixture_doc_release(&q.doc);
    }
    std::remove(tmp.c_str());
    wr_robust_free(robust);
    row.note += fmt("; %d displacements", displacements);
    finish(row);
    if (row.trials == 0) { // nothing tried: no criterion met
        row.pass = false;
        row.note += "; no robust push to try";
    }
    row.seconds = since(t0);
    return row;
}

void usage()
{
    std::fprintf(stderr, "usage: physics-validate [--quick | --full] [--verbose] FIXTURE.json ...\n"
                 "investigations (docs/VALIDATION.md): [--friction-factor X] [--static-as-kinetic] [--chains]\n"
                 "    [--sensor-depth M] [--velocity-iterations N]\n"
                 "    [--sweep N [--spin W] [--slide V]] [--hold-at EDGE T] [--tolerance T[,A]]\n");
}

} // namespace

int main(int argc, char **argv)
{
    Config cfg{};
    std::vector<std::string> files;
    int sweep = 0;
    double spin = 0, slide_speed = 0;
    int hold_edge = -1;
    double tol_position = -1, tol_angle = 0; // --tolerance T,A
    double hold_t = 0;
    for (int i = 1; i < argc; i++) {
        if (!std::strcmp(argv[i], "--quick"))
            cfg.quick = true;
        else if (!std::strcmp(argv[i], "--full"))
            cfg.quick = false;
        else if (!std::strcmp(argv[i], "--verbose"))
            cfg.verbose = true;
        else if (!std::strcmp(argv[i], "--sweep") && i + 1 < argc)
            sweep = std::atoi(argv[++i]);
        else if (!std::strcmp(argv[i], "--hold-at") && i + 2 < argc) {
            hold_edge = std::atoi(argv[++i]);
            hold_t = std::atof(argv[++i]);
        } else if (!std::strcmp(argv[i], "--slide") && i + 1 < argc)
            slide_speed = std::atof(argv[++i]);
        else if (!std::strcmp(argv[i], "--spin") && i + 1 < argc)
            spin = std::atof(argv[++i]);
        else if (!std::strcmp(argv[i], "--tolerance") && i + 1 < argc) {
            if (std::sscanf(argv[++i], "%lf,%lf", &tol_position, &tol_angle) < 1) {
                usage();
                return 2;
            }
        } else if (!std::strcmp(argv[i], "--velocity-iterations") && i + 1 < argc)
            VELOCITY_ITERATIONS = std::atoi(argv[++i]);
        else if (!std::strcmp(argv[i], "--chains"))
            force_chains = true;
        else if (!std::strcmp(argv[i], "--sensor-depth") && i + 1 < argc)
            DEEP_PENETRATION = std::atof(argv[++i]);
        else if (!std::strcmp(argv[i], "--static-as-kinetic"))
            static_as_kinetic = true;
        else if (!std::strcmp(argv[i], "--friction-factor") && i + 1 < argc)
            friction_factor = std::atof(argv[++i]);
        else if (argv[i][0] == '-') {
            usage();
            return 2;
        } else
            files.push_back(argv[i]);
    }
    if (files.empty()) {
        usage();
        return 2;
    }
    if (cfg.quick) {
        cfg.goal_points = 50, cfg.goal_trials = 4;
        cfg.out_points = 25, cfg.out_trials = 2;
        cfg.hold_points = 50;
        cfg.wrenches_in = 100, cfg.wrenches_out = 100;
        cfg.tilt_points = 50, cfg.tilt_trials = 4;
        cfg.tilt_out_points = 25, cfg.tilt_out_trials = 2;
        cfg.spin_points = 50;
        cfg.force_points = 25, cfg.force_trials = 8;
    } else {
        cfg.goal_points = 200, cfg.goal_trials = 5;
        cfg.out_points = 100, cfg.out_trials = 5;
        cfg.hold_points = 300;
        cfg.wrenches_in = 1000, cfg.wrenches_out = 1000;
        cfg.tilt_points = 200, cfg.tilt_trials = 5;
        cfg.tilt_out_points = 100, cfg.tilt_out_trials = 5;
        cfg.spin_points = 200;
        cfg.force_points = 100, cfg.force_trials = 5;
    }
    auto start = Clock::now();
    if (friction_factor != 1.0)
        std::printf("NEGATIVE CONTROL: Box2D's friction is %g times the fixture's\n", friction_factor);
    if (static_as_kinetic)
        std::printf("INVESTIGATION: Box2D's static friction is the fixture's kinetic friction\n");
    std::printf("physics validation (%s): Box2D %d.%d.%d, %g Hz, %d velocity / %d position iterations\n",
                cfg.quick ? "quick" : "full", b2_version.major, b2_version.minor, b2_version.revision, HZ,
                VELOCITY_ITERATIONS, POSITION_ITERATIONS);
    std::vector<Row> rows;
    std::vector<std::pair<double, double>> frictions;
    bool input_error = false;
    for (const std::string &file : files) {
        Prepared p;
        std::string error;
        if (!prepare(file, &p, &error)) {
            std::fprintf(stderr, "%s\n", error.c_str());
            input_error = true;
            continue;
        }
        if (!p.unsupported.empty()) {
            Row row;
            row.fixture = p.name;
            row.set = "(not simulated)";
            row.criterion = NOT_APPLICABLE;
            row.note = p.unsupported;
            print_row(row);
            rows.push_back(row);
            if (p.an)
                wr_analysis_free(p.an);
            wp_fixture_doc_release(&p.doc);
            continue;
        }
        double touch = seated_distance(p);
        if (touch > 1e-5) {
            std::fprintf(stderr, "%s: harness error: Box2D sees a gap of %g m at the seated pose\n",
                         p.name.c_str(), touch);
            return 2;
        }
        for (int i = 0; i < p.k; i++)
            frictions.push_back({p.mu_s[i], p.mu_k[i]});
        if (tol_position >= 0) {
            int displacements = cfg.quick ? 6 : 20;
            rows.push_back(tolerance_trials(p, tol_position, tol_angle, displacements, cfg.quick ? 5 : 10, 2));
            print_row(rows.back());
            wr_analysis_free(p.an);
            wp_fixture_doc_release(&p.doc);
            continue;
        }
        if (hold_edge >= 0) {
            double w[3];
            Load finger = finger_at(p, hold_edge, hold_t, w);
            hold_trace = true;
            Hold h = run_hold(p, {0, 0}, 0, &finger);
            std::printf("%s: push at edge %d t %.9g, strong margin %+.6f (%s): moved %.3e m\n", p.name.c_str(),
                        hold_edge, hold_t, margin_of(p, w, WR_SET_STRONG), blocking_of(p, w, WR_SET_STRONG).c_str(),
                        h.moved);
            wr_analysis_free(p.an);
            wp_fixture_doc_release(&p.doc);
            continue;
        }
        if (sweep > 0) {
            sweep_pushes(p, sweep, 10, spin);
            if (p.circle && spin > 0)
                sweep_spin_seated(p, sweep, spin);
            if (slide_speed > 0)
                for (unsigned st = 1; st + 1 < (1u << p.k); st++)
                    sweep_slide(p, st, sweep, slide_speed);
            sweep_tilts(p, 4 * sweep, 10);
            sweep_strong(p, 50 * sweep);
            wr_analysis_free(p.an);
            wp_fixture_doc_release(&p.doc);
            continue;
        }
        auto goal = regions(p, WR_SET_GOAL), strong = regions(p, WR_SET_STRONG);
        auto tilt = arcs(p, WR_SET_GOAL);
        std::printf("%s (%s): scale %.6g m per unit, %d fixels, mu_s/mu_k", p.name.c_str(), file.c_str(),
                    p.scale, p.k);
        for (int i = 0; i < p.k; i++)
            std::printf(" %g/%g", p.mu_s[i], p.mu_k[i]);
        if (p.chains) {
            size_t vertices = 0, most = 0;
            for (auto &c : p.cores)
                vertices += c.size();
            for (auto &pc : p.pieces)
                most = std::max(most, pc.size());
            std::printf("\n  chains: %zu loop(s), %zu vertices, arcs within %.1e m and %.2f deg; %zu convex pieces "
                        "(at most %zu vertices), %zu sensors, area matched to %.1e",
                        p.cores.size(), vertices, p.deviation, p.normal_error * DEG, p.pieces.size(), most,
                        p.sensors.size(), p.piece_area_error);
        }
        std::printf("\n  G_goal push region: %s\n  G_strong push region: %s\n  G_goal tilts: %s\n",
                    region_text(p, goal).c_str(), region_text(p, strong).c_str(), region_text(p, tilt).c_str());
        std::vector<Row> mine;
        mine.push_back(seat_trials(p, cfg, "push in G_goal", false, true, goal, cfg.goal_points, cfg.goal_trials));
        print_row(mine.back());
        mine.push_back(seat_trials(p, cfg, "push outside G_goal", false, false, goal, cfg.out_points, cfg.out_trials));
        print_row(mine.back());
        mine.push_back(seat_trials(p, cfg, "tilt in G_goal", true, true, tilt, cfg.tilt_points, cfg.tilt_trials));
        print_row(mine.back());
        mine.push_back(seat_trials(p, cfg, "tilt outside G_goal", true, false, tilt, cfg.tilt_out_points,
                                   cfg.tilt_out_trials));
        print_row(mine.back());
        if (p.circle) {
            mine.push_back(spin_trials(p, "spin: push in G_goal", true, goal, strong, cfg.spin_points));
            print_row(mine.back());
            mine.push_back(spin_trials(p, "spin: G_strong - G_goal", false, goal, strong, cfg.spin_points));
            print_row(mine.back());
        }
        mine.push_back(hold_pushes(p, cfg, "hold: push in G_strong", true, strong, cfg.hold_points));
        print_row(mine.back());
        mine.push_back(hold_pushes(p, cfg, "move: push outside G_strong", false, strong, cfg.hold_points));
        print_row(mine.back());
        mine.push_back(hold_wrenches(p, cfg, "hold: margin > 0.05", true, cfg.wrenches_in));
        print_row(mine.back());
        mine.push_back(hold_wrenches(p, cfg, "move: margin < -0.05", false, cfg.wrenches_out));
        print_row(mine.back());
        mine.push_back(force_trials(p, "force: 1.05 F*, cuts", 1.05, cfg.force_points, cfg.force_trials));
        print_row(mine.back());
        mine.push_back(force_trials(p, "force: 0.5 F*, cuts", 0.5, cfg.force_points / 2, cfg.force_trials));
        print_row(mine.back());
        rows.insert(rows.end(), mine.begin(), mine.end());
        wr_analysis_free(p.an);
        wp_fixture_doc_release(&p.doc);
    }
    std::sort(frictions.begin(), frictions.end());
    frictions.erase(std::unique(frictions.begin(), frictions.end()), frictions.end());
    for (auto mu : frictions) {
        rows.push_back(calibrate(mu.first, mu.second));
        print_row(rows.back());
    }
    int failed = 0;
    std::printf("\n| fixture | set | points | trials | success | rate | criterion | |\n");
    std::printf("|---|---|---:|---:|---:|---:|---|---|\n");
    for (const Row &r : rows) {
        std::printf("| %s | %s | %d | %d | %d | %s | %s | %s |\n", r.fixture.c_str(), r.set.c_str(), r.points,
                    r.trials, r.successes,
                    r.trials ? fmt("%.2f%%", 100.0 * r.successes / r.trials).c_str() : "-",
                    criterion_text(r.criterion), r.pass ? "ok" : "**FAIL**");
        failed += !r.pass;
    }
    std::printf("\nphysics: %zu rows, %d failed, %.1f s\n", rows.size(), failed, since(start));
    if (input_error)
        return 2;
    return failed ? 1 : 0;
}
