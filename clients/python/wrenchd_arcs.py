"""wrenchd_arcs.py -- the arithmetic of wrenchd's bulged vertices, and curves
followed by tangent arcs: written once for the DXF reader (wrenchd_dxf.py)
and the FreeCAD workbench (clients/freecad/wrench_outline.py).  Pure Python,
no FreeCAD, no ezdxf.

Bulges
------
A vertex [x, y, bulge] of a loop starts a segment to the next vertex: a line
when bulge is 0, else an arc of included angle 4 atan(bulge), counter-
clockwise positive (docs/PROTOCOL.md, the outline).  `arc_of` gives its
centre, radius and sweep; `bulge_of_sweep` and `bulge_of_degrees` the bulge
of a sweep (exactly 1 for a half circle in degrees, as DXF angles are);
`Segment` is one segment with its points, tangents and nearest points;
`loop_area` a loop's signed area.

Curves by arcs
--------------
`follow(curve, u0, u1, ...)` replaces a curve that is not a line or a circle
(a B-spline, an ellipse) from parameter u0 to u1 by arcs that meet
tangentially (biarcs), each no farther from it than a tolerance.  The curve
is any object with

    point(u)       -> (x, y)
    tangent(u)     -> a direction (x, y) of increasing u, or None where the
                      derivative vanishes (then a difference is taken)
    distance(p, a, b) -> the distance from p to the curve; [a, b] is the
                      parameter range the point came from (a hint: the
                      distance to the whole curve is never larger)
    kinks(u0, u1)  -> parameters strictly between where it may have a corner
    closed         -> whether the curve is closed (a true value: start from
                      8 pieces, else 4)

Each piece is fitted to half the tolerance, checked at 16 points; runs that
are straight or on one circle are made one line or one arc; then the
distance is measured both ways -- from points of the curve to the arcs, and
from points of the arcs to the curve (curve.distance) -- and should it
exceed the tolerance the fit is made again, finer.  The largest distance
measured is returned with the arcs: callers report it.
"""

import math

__all__ = ["ArcFitError", "Segment", "arc_of", "bulge_of_sweep", "bulge_of_degrees",
           "sin_degrees", "cos_degrees", "loop_area", "biarc", "follow", "MAX_ARCS"]

# The most arcs one curve may become (wrenchd's outline takes 4096 vertices).
MAX_ARCS = 4096


class ArcFitError(ValueError):
    """A curve that cannot be followed within the tolerance; the message says
    where."""


# ---- vectors ------------------------------------------------------------------------

def _sub(a, b):
    return (a[0] - b[0], a[1] - b[1])


def _dot(a, b):
    return a[0] * b[0] + a[1] * b[1]


def _cross(a, b):
    return a[0] * b[1] - a[1] * b[0]


def _norm(a):
    return math.hypot(a[0], a[1])


def _unit(a):
    n = _norm(a)
    return (a[0] / n, a[1] / n)


def _angle(a, b):
    """The signed angle from direction a to direction b, counter-clockwise
    positive, in (-pi, pi]."""
    return math.atan2(_cross(a, b), _dot(a, b))


def _fmt(x):
    text = "%.6g" % (x if abs(x) >= 1e-9 else 0.0)
    return "0" if text in ("-0", "0") else text


def _fmt_point(p):
    return "(" + ", ".join(_fmt(c) for c in p) + ")"


# ---- bulges -----------------------------------------------------------------------

def sin_degrees(deg):
    """sin of an angle in degrees, exact at multiples of 90."""
    deg = math.fmod(deg, 360.0)
    if deg % 90.0 == 0.0:
        return (0.0, 1.0, 0.0, -1.0)[int(deg // 90.0) % 4]
    return math.sin(math.radians(deg))


def cos_degrees(deg):
    """cos of an angle in degrees, exact at multiples of 90."""
    deg = math.fmod(deg, 360.0)
    if deg % 90.0 == 0.0:
        return (1.0, 0.0, -1.0, 0.0)[int(deg // 90.0) % 4]
    return math.cos(math.radians(deg))


def bulge_of_degrees(sweep_deg):
    """tan(sweep/4) for a signed sweep in degrees, |sweep| < 360: exactly +-1
    for a half circle, the exact values at multiples of 90 degrees."""
    half = sweep_deg / 2.0
    return sin_degrees(half) / (1.0 + cos_degrees(half))


def bulge_of_sweep(sweep):
    """tan(sweep/4) for a signed sweep in radians, |sweep| < 2 pi."""
    return math.tan(sweep / 4.0)


def arc_of(p0, p1, bulge):
    """(centre, radius, sweep) of the arc from p0 to p1 of this bulge (not 0):
    the centre lies on the chord's perpendicular bisector, left of p0 -> p1
    by chord (1 - b^2) / (4 b) (right for b < 0); sweep is signed, radians."""
    dx, dy = p1[0] - p0[0], p1[1] - p0[1]
    chord = math.hypot(dx, dy)
    h = (1.0 - bulge * bulge) / (4.0 * bulge)
    centre = ((p0[0] + p1[0]) / 2.0 - dy * h, (p0[1] + p1[1]) / 2.0 + dx * h)
    radius = chord * (1.0 + bulge * bulge) / (4.0 * abs(bulge))
    return centre, radius, 4.0 * math.atan(bulge)


def _circular_segment(radius, sweep):
    """The signed area between an arc and its chord: r^2/2 (t - sin t)."""
    t = abs(sweep)
    return math.copysign(radius * radius / 2.0 * (t - math.sin(t)), sweep)


def loop_area(loop):
    """The signed area (counter-clockwise positive) of a loop of vertices
    (x, y[, bulge]): the chord polygon plus each arc's circular segment."""
    area = 0.0
    n = len(loop)
    for i in range(n):
        p0, p1 = loop[i], loop[(i + 1) % n]
        area += (p0[0] * p1[1] - p1[0] * p0[1]) / 2.0
        b = p0[2] if len(p0) > 2 else 0.0
        if b:
            _, r, sweep = arc_of(p0, p1, b)
            area += _circular_segment(r, sweep)
    return area


class Segment:
    """Segment `index` of loop `loop` of an outline: from `start` to `end`
    (2-D tuples), a straight line when `bulge` is 0, else an arc of included
    angle 4 atan(bulge).  `edge`: what it comes from (a FreeCAD edge's name
    "Edge3", a DXF entity), `exact`: False where it approximates a curve by
    arcs.  `t` along it is the fraction of its length (of an arc's included
    angle), push.regions' t."""

    def __init__(self, loop, index, start, end, bulge=0.0, edge="", exact=True):
        self.loop, self.index = loop, index
        self.start, self.end = (float(start[0]), float(start[1])), (float(end[0]), float(end[1]))
        self.bulge = float(bulge)
        self.edge, self.exact = edge, exact
        self.chord = _norm(_sub(self.end, self.start))
        if self.bulge:
            self.centre, self.radius, self.sweep = arc_of(self.start, self.end, self.bulge)
            self.start_angle = math.atan2(self.start[1] - self.centre[1],
                                          self.start[0] - self.centre[0])
        else:
            self.sweep = 0.0
            self.radius = math.inf
            self.centre = None
            self.start_angle = 0.0

    @property
    def is_arc(self):
        return self.bulge != 0.0

    @property
    def length(self):
        return self.radius * abs(self.sweep) if self.is_arc else self.chord

    @property
    def area(self):
        """This segment's share of its loop's signed area (loop_area)."""
        a = _cross(self.start, self.end) / 2.0
        return a + _circular_segment(self.radius, self.sweep) if self.is_arc else a

    def point(self, t):
        """The point at t (t = 0 at start, 1 at end)."""
        if t == 0.0:
            return self.start
        if t == 1.0:
            return self.end
        if self.is_arc:
            a = self.start_angle + t * self.sweep
            return (self.centre[0] + self.radius * math.cos(a),
                    self.centre[1] + self.radius * math.sin(a))
        return (self.start[0] + t * (self.end[0] - self.start[0]),
                self.start[1] + t * (self.end[1] - self.start[1]))

    def tangent(self, t):
        """The unit direction of travel at t."""
        if self.is_arc:
            a = self.start_angle + t * self.sweep
            s = 1.0 if self.sweep > 0 else -1.0
            return (-s * math.sin(a), s * math.cos(a))
        return _unit(_sub(self.end, self.start))

    def nearest(self, p):
        """(t, point, distance): the point of the segment nearest p."""
        if self.is_arc:
            a = math.atan2(p[1] - self.centre[1], p[0] - self.centre[0])
            turn = (a - self.start_angle) * (1.0 if self.sweep > 0 else -1.0)
            turn = math.fmod(turn, 2.0 * math.pi)
            if turn < 0:
                turn += 2.0 * math.pi
            if turn <= abs(self.sweep):
                t = turn / abs(self.sweep)
                q = self.point(t)
                return t, q, _norm(_sub(p, q))
            ends = [(0.0, self.start), (1.0, self.end)]
        else:
            d = _sub(self.end, self.start)
            ll = _dot(d, d)
            t = 0.0 if ll == 0 else min(1.0, max(0.0, _dot(_sub(p, self.start), d) / ll))
            q = self.point(t)
            return t, q, _norm(_sub(p, q))
        t, q = min(ends, key=lambda e: _norm(_sub(p, e[1])))
        return t, q, _norm(_sub(p, q))

    def vertex(self):
        """The segment's start vertex as wrenchd writes it."""
        if self.bulge:
            return [self.start[0], self.start[1], self.bulge]
        return [self.start[0], self.start[1]]

    def __repr__(self):
        kind = "arc %.6g deg" % math.degrees(self.sweep) if self.is_arc else "line"
        return "<Segment %d.%d %s %s -> %s%s>" % (self.loop, self.index, kind, _fmt_point(self.start),
                                                   _fmt_point(self.end),
                                                   " of " + self.edge if self.edge else "")


# ---- curves by arcs -------------------------------------------------------------------

def biarc(p0, t0, p1, t1):
    """Two arcs from p0 (unit tangent t0) to p1 (unit tangent t1) that meet
    tangentially, each turning at most half a turn: [(p0, bulge), (joint,
    bulge)], or None where none does (the piece is then split).  The joint
    is where the arcs' tangent lines from p0 and p1 are equally long (the
    equal-chord biarc)."""
    v = _sub(p1, p0)
    vv = _dot(v, v)
    if vv == 0:
        return None
    t = (t0[0] + t1[0], t0[1] + t1[1])
    vt = _dot(v, t)
    room = 2.0 * (1.0 - _dot(t0, t1))           # 4 - |t|^2
    if room < 1e-14:
        if vt <= 0:
            return None
        d = vv / (2.0 * vt)
    else:
        d = (-vt + math.sqrt(vt * vt + room * vv)) / room
    if not (d > 0) or d > 4.0 * math.sqrt(vv):
        return None
    q0 = (p0[0] + d * t0[0], p0[1] + d * t0[1])
    q1 = (p1[0] - d * t1[0], p1[1] - d * t1[1])
    joint = ((q0[0] + q1[0]) / 2.0, (q0[1] + q1[1]) / 2.0)
    out = []
    for start, tangent, end, at_start in ((p0, t0, joint, True), (joint, t1, p1, False)):
        chord = _sub(end, start)
        if _norm(chord) <= 1e-15 * math.sqrt(vv):
            continue
        # the included angle is twice the angle between a tangent and the chord
        half = _angle(tangent, chord) if at_start else _angle(chord, tangent)
        if abs(half) > math.pi / 2.0 - 1e-9:
            return None
        # an arc bulging less than 1e-9 of its chord is that chord (a far
        # centre would cost its points their digits)
        out.append((start, math.tan(half / 2.0) if abs(half) > 4e-9 else 0.0))
    return out or None


def follow(curve, u0, u1, p0, p1, tolerance, size, what="curve"):
    """Arcs [(start point, bulge)] from p0 = curve.point(u0) to p1 (p1 not
    included; u1 < u0 runs the curve backwards), each within `tolerance` of
    the curve, and the largest distance measured between them both ways
    (the module's docstring).  `size`: the drawing's extent (runs closer
    than 1e-9 of it are merged); `what` names the curve in messages.
    Raises ArcFitError."""
    fraction = 0.5
    worst = math.inf
    for _ in range(4):
        arcs = _fit(curve, u0, u1, p0, p1, fraction * tolerance, size, what)
        worst = _measure(curve, u0, u1, arcs, p1, tolerance)
        if worst <= tolerance:
            return [(start, bulge) for start, bulge, _, _ in arcs], worst
        fraction /= 4.0
    raise ArcFitError("the arcs following the %s are %s from it, above the tolerance %s"
                      % (what, _fmt(worst), _fmt(tolerance)))


def _fit(curve, u0, u1, p0, p1, tolerance, size, what):
    """Biarcs along the curve, each within `tolerance` of it at 16 points,
    then merged (_merge): [(start, bulge, ua, ub)], [ua, ub] the parameters
    the arc follows."""
    sign = 1.0 if u1 > u0 else -1.0

    def tangent(u):
        d = curve.tangent(u)
        if d is not None and _norm(d) > 0:
            d = _unit(d)
            return (sign * d[0], sign * d[1])
        h = 1e-7 * (u1 - u0)         # where the derivative vanishes: a difference
        a = curve.point(u - h if u != u0 else u)
        b = curve.point(u + h if u != u1 else u)
        return _unit(_sub(b, a))

    def within(arcs, a, b, pb):
        segs = [Segment(0, k, s, arcs[k + 1][0] if k + 1 < len(arcs) else pb, bulge)
                for k, (s, bulge) in enumerate(arcs)]
        samples = 16
        for m in range(1, samples):
            p = curve.point(a + (b - a) * m / samples)
            if min(s.nearest(p)[2] for s in segs) > tolerance:
                return False
        return True

    out = []

    def piece(a, b, pa, pb, ta, tb, depth):
        arcs = biarc(pa, ta, pb, tb)
        if arcs is not None and within(arcs, a, b, pb):
            out.extend((s, bulge, a, b) for s, bulge in arcs)
            return
        if depth >= 40 or abs(b - a) <= 1e-12 * max(1.0, abs(u1 - u0)):
            if _norm(_sub(pb, pa)) <= tolerance:
                out.append((pa, 0.0, a, b))
                return
            raise ArcFitError("cannot follow the %s within %s by arcs near %s"
                              % (what, _fmt(tolerance), _fmt_point(pa)))
        m = (a + b) / 2.0
        pm, tm = curve.point(m), tangent(m)
        piece(a, m, pa, pm, ta, tm, depth + 1)
        piece(m, b, pm, pb, tm, tb, depth + 1)
        if len(out) > MAX_ARCS:
            raise ArcFitError("following the %s within %s takes more than %d arcs: give a "
                              "larger tolerance" % (what, _fmt(tolerance), MAX_ARCS))

    def one_sided(u, toward):
        """The tangent at a kink, as the piece from u toward `toward` has it."""
        return tangent(u + 1e-9 * (toward - u))

    # Start from pieces that each turn little (8 of a closed curve, 4 of an
    # open one), split also where the curve may turn sharply: there each
    # piece has its own tangent.
    count = 8 if curve.closed else 4
    kinks = list(curve.kinks(u0, u1))
    us = sorted(set([u0 + (u1 - u0) * k / count for k in range(count + 1)] + kinks),
                key=lambda u: (u - u0) / (u1 - u0))
    ps = [p0] + [curve.point(u) for u in us[1:-1]] + [p1]
    for k in range(len(us) - 1):
        a, b = us[k], us[k + 1]
        ta = one_sided(a, b) if a in kinks else tangent(a)
        tb = one_sided(b, a) if b in kinks else tangent(b)
        piece(a, b, ps[k], ps[k + 1], ta, tb, 0)
    return _merge(out, p1, size)


def _merge(arcs, end, size):
    """Consecutive pieces on one line, or on one circle turning one way (at
    most half a turn together), made one: a curve that is straight or
    circular becomes the line or the arc it is."""
    close = 1e-9 * size
    out = []
    for k, (start, bulge, ua, ub) in enumerate(arcs):
        stop = arcs[k + 1][0] if k + 1 < len(arcs) else end
        if out:
            first, first_bulge, last, fa, _ = out[-1]
            joined = None
            if bulge == 0.0 and first_bulge == 0.0:
                # start lies on the line from first to stop
                d = _sub(stop, first)
                if _norm(d) > 0 and abs(_cross(d, _sub(start, first))) / _norm(d) <= close:
                    joined = 0.0
            elif bulge != 0.0 and first_bulge != 0.0 and (bulge > 0) == (first_bulge > 0):
                a = Segment(0, 0, first, start, first_bulge)
                b = Segment(0, 0, start, stop, bulge)
                sweep = a.sweep + b.sweep
                if _norm(_sub(a.centre, b.centre)) <= close and abs(a.radius - b.radius) <= close \
                        and abs(sweep) <= math.pi:
                    joined = math.tan(sweep / 4.0)
            if joined is not None:
                out[-1] = (first, joined, stop, fa, ub)
                continue
        out.append((start, bulge, stop, ua, ub))
    return [(start, bulge, ua, ub) for start, bulge, _, ua, ub in out]


def _measure(curve, u0, u1, arcs, p1, tolerance):
    """The largest distance found between the curve and the arcs: from 8
    points a piece (64 at least) of the curve to the arcs, and from 7 points
    of each arc to the curve (curve.distance, told the parameters the arc
    follows)."""
    segs = [Segment(0, k, s, arcs[k + 1][0] if k + 1 < len(arcs) else p1, bulge)
            for k, (s, bulge, _, _) in enumerate(arcs)]
    worst = 0.0
    dense = max(64, 8 * len(segs))
    near = 0                     # the arc nearest the last sample: the next is near it
    for m in range(dense + 1):
        p = curve.point(u0 + (u1 - u0) * m / dense)
        window = range(max(0, near - 2), min(len(segs), near + 4))
        d, near = min((segs[k].nearest(p)[2], k) for k in window)
        if d > 0.5 * tolerance:  # far from the arcs about: ask them all
            d, near = min((s.nearest(p)[2], k) for k, s in enumerate(segs))
        worst = max(worst, d)
    for s, (_, _, ua, ub) in zip(segs, arcs):
        for t in (0.125, 0.25, 0.375, 0.5, 0.625, 0.75, 0.875):
            worst = max(worst, curve.distance(s.point(t), ua, ub))
    return worst
