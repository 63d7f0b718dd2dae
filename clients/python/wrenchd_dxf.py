#!/usr/bin/env python3
"""wrenchd_dxf.py -- the parts drawn in a DXF file, each as wrenchd's
`shape` object:

    {"type": "outline", "loops": [[[x, y], [x, y, bulge], ...], ...]}

The first loop is the outer boundary, the others are holes; a vertex's bulge
is that of the segment to the next vertex, tan(theta/4) of the arc's included
angle, positive counter-clockwise, left out for a straight segment.

    wrenchd_dxf.py part.dxf [--layer NAME ...] [--part N|largest|all]
                   [--units mm|in|m] [--tolerance T] [--curve-tolerance T] [--report]

prints the shape of one part (the largest by default; `--part all`: a JSON
list of every part's shape) on stdout and a report on stderr (--report: the
report as one JSON line).  From Python:

    parts, report = wrenchd_dxf.read_dxf("part.dxf")            # every part
    shape, report = wrenchd_dxf.shape_from_dxf("part.dxf")      # one part
    fixture["units"] = wrenchd_dxf.fixture_units(report)        # its unit

clients/python/README.md has the table of what is read and what is done with
each kind of entity; the rules are enforced here, in this order:

  1. Entities: from modelspace, on the layers given (any case; every layer
     when none is); block references (INSERT) are exploded.  LINE, ARC,
     CIRCLE, LWPOLYLINE, 2-D and flat 3-D POLYLINE become segments (lines
     and arcs, with their bulges); SPLINE and ELLIPSE become tangent arcs
     within the curve tolerance (wrenchd_arcs.follow, shared with the
     FreeCAD workbench; the distance is measured both ways and reported);
     annotation and other kinds are ignored and counted.
  2. Tolerance: ends closer than it are one point (default 1e-6 of the
     drawing's extent).  Segments shorter than it are dropped.
  3. Duplicates: segments with the same ends and the same midpoint (within
     the tolerance) are one, and so are overlapping pieces of one line or
     one circle: a segment is split where an end of another lies on it,
     then the duplicates merged; pieces of one entity split so and not
     needed apart are joined again.  The count is reported.
  4. Stray open geometry: segments with a free end are taken away, chain
     by chain, and reported.  An open chain around a closed loop is not
     stray but a boundary with a gap: it is refused, with the gap.
  5. Loops: where exactly two ends meet, the segments are joined into
     loops; three or more ends at one point are refused (a branch).
  6. Parts: a loop inside another (an exact point-in-loop test with arcs)
     is its hole; a loop inside a hole is the outer boundary of another
     part.  Crossing loops are refused; a loop that coincides with another
     is a duplicate.  Parts are numbered by area, largest first.
  7. Units: $INSUNITS names the unit (metric units other than m written in
     mm, imperial ones in inches, the numbers scaled); 0 or absent is not
     stated: mm is taken, and said.  $MEASUREMENT chooses a drawing's
     hatch patterns and linetypes, not its unit: it is reported, never
     used.  --units says the numbers are in that unit (nothing scaled).

Refused (DxfShapeError; exit status 1 with the message): no closed loop; a
boundary with a gap above the tolerance; a branch; crossing loops; entities
not parallel to the XY plane; a curve that cannot be followed.

The DXF is read by ezdxf (Debian: python3-ezdxf); wrenchd.py, the client,
does not need it.
"""

import argparse
import json
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import wrenchd_arcs  # noqa: E402  (beside this file)
from wrenchd_arcs import arc_of as _arc_of, bulge_of_degrees, cos_degrees, sin_degrees  # noqa: E402

try:
    import ezdxf
except ImportError as _error:     # reported when a drawing is read
    ezdxf = None
    _EZDXF_ERROR = _error

__all__ = ["read_dxf", "shape_from_dxf", "fixture_units", "DxfShapeError",
           "DEFAULT_RELATIVE_TOLERANCE", "DEFAULT_RELATIVE_CURVE_TOLERANCE", "UNITS"]

# The default joining tolerance, relative to the drawing's extent.
DEFAULT_RELATIVE_TOLERANCE = 1e-6
# The default distance of the arcs following a SPLINE or ELLIPSE from it,
# relative to the drawing's extent: the FreeCAD workbench's default for its
# curves (1 um on a part 100 mm across).
DEFAULT_RELATIVE_CURVE_TOLERANCE = 1e-5

# $INSUNITS: code -> (name, millimetres per unit).
UNITS = {
    0: ("unitless", None), 1: ("inch", 25.4), 2: ("foot", 304.8),
    3: ("mile", 1609344.0), 4: ("mm", 1.0), 5: ("cm", 10.0), 6: ("m", 1000.0),
    7: ("km", 1e6), 8: ("microinch", 2.54e-5), 9: ("mil", 0.0254),
    10: ("yard", 914.4), 11: ("angstrom", 1e-7), 12: ("nm", 1e-6),
    13: ("um", 1e-3), 14: ("dm", 100.0), 15: ("dam", 1e4), 16: ("hm", 1e5),
    17: ("Gm", 1e12), 18: ("au", 1.495978707e14), 19: ("light year", 9.4607304725808e18),
    20: ("parsec", 3.0856775814913673e19), 21: ("US survey foot", 1200e3 / 3937),
    22: ("US survey inch", 100e3 / 3937), 23: ("US survey yard", 3600e3 / 3937),
    24: ("US survey mile", 6336000e3 / 3937),
}
# The units a fixture names (docs/PROTOCOL.md, the fixture's "units"), in mm.
FIXTURE_LENGTHS = {"mm": 1.0, "m": 1000.0, "in": 25.4}
# $INSUNITS codes written in inches (the imperial ones), with inches per
# unit (exact); other codes are written in mm, or m for m and larger.
IMPERIAL = {1: 1.0, 2: 12.0, 3: 63360.0, 8: 1e-6, 9: 1e-3, 10: 36.0,
            21: 12 * 1.000002, 22: 1.000002, 23: 36 * 1.000002, 24: 63360 * 1.000002}

# Kinds that carry no part geometry: ignored, counted in the report.
ANNOTATION = {
    "TEXT", "MTEXT", "DIMENSION", "ARC_DIMENSION", "LARGE_RADIAL_DIMENSION",
    "LEADER", "MULTILEADER", "MLEADER", "HATCH", "MPOLYGON", "POINT", "ATTDEF",
    "ATTRIB", "IMAGE", "VIEWPORT", "WIPEOUT", "TOLERANCE", "ACAD_TABLE",
    "PDFUNDERLAY", "DWFUNDERLAY", "DGNUNDERLAY", "OLE2FRAME", "OLEFRAME",
}


class DxfShapeError(ValueError):
    """The drawing holds no part wrenchd can take; the message says why and
    where."""


def _num(v):
    """A plain float, -0.0 made 0.0."""
    return float(v) + 0.0


def _fmt(p):
    return "(%s, %s)" % (repr(_num(p[0])), repr(_num(p[1])))


def _area(loop):
    return wrenchd_arcs.loop_area(loop)


# ---- geometry of a loop ([(x, y, bulge)], bulge of the segment to the next) --

def _segments(loop):
    n = len(loop)
    for i in range(n):
        x0, y0, b = loop[i]
        x1, y1, _ = loop[(i + 1) % n]
        yield (x0, y0), (x1, y1), b


def _reversed_loop(loop):
    """The same loop run the other way, from the same first vertex."""
    n = len(loop)
    verts = [loop[0]] + [loop[i] for i in range(n - 1, 0, -1)]
    bulges = [-loop[(i - 1) % n][2] for i in range(0, -n, -1)]
    # bulges[k] belongs to the segment verts[k] -> verts[k+1], the reverse of
    # the drawing's segment verts[k+1] -> verts[k].
    return [(v[0], v[1], _num(bb)) for v, bb in zip(verts, bulges)]


def _inside(loop, p):
    """Even-odd: is p inside the loop?  The chord polygon's crossing parity,
    flipped for each circular segment (between a chord and its arc) holding p."""
    x, y = p
    inside = False
    for p0, p1, b in _segments(loop):
        if (p0[1] > y) != (p1[1] > y):
            xc = p0[0] + (y - p0[1]) * (p1[0] - p0[0]) / (p1[1] - p0[1])
            if x < xc:
                inside = not inside
        if b:
            c, r, _ = _arc_of(p0, p1, b)
            side = (p1[0] - p0[0]) * (y - p0[1]) - (p1[1] - p0[1]) * (x - p0[0])
            # the arc lies right of p0 -> p1 for b > 0, left for b < 0
            if math.hypot(x - c[0], y - c[1]) < r and side * b < 0:
                inside = not inside
    return inside


def _prepared(loop, near):
    """A loop's segments as wrenchd_arcs.Segments, each with its box widened
    by `near`: what the containment test asks of it many times."""
    out = []
    for k, (p0, p1, b) in enumerate(_segments(loop)):
        seg = wrenchd_arcs.Segment(0, k, p0, p1, b)
        pts = [seg.point(t / 8.0) for t in range(9)]
        margin = near + (seg.radius * (1.0 - math.cos(abs(seg.sweep) / 16.0)) if b else 0.0)
        out.append((min(q[0] for q in pts) - margin, min(q[1] for q in pts) - margin,
                    max(q[0] for q in pts) + margin, max(q[1] for q in pts) + margin, seg))
    return out


def _near(prepared, p, near):
    """Whether p is within `near` of the boundary of a _prepared loop."""
    x, y = p
    return any(x0 <= x <= x1 and y0 <= y <= y1 and seg.nearest(p)[2] <= near
               for x0, y0, x1, y1, seg in prepared)


def _box(loop, margin):
    """A box holding the loop (an arc's whole circle), widened by margin."""
    xs, ys = [], []
    for p0, p1, b in _segments(loop):
        xs.append(p0[0])
        ys.append(p0[1])
        if b:
            c, r, _ = _arc_of(p0, p1, b)
            xs += [c[0] - r, c[0] + r]
            ys += [c[1] - r, c[1] + r]
    return min(xs) - margin, min(ys) - margin, max(xs) + margin, max(ys) + margin


def _apart(a, b):
    return a[2] < b[0] or b[2] < a[0] or a[3] < b[1] or b[3] < a[1]


def _off_chords(loop, p, step):
    """p moved by `step` off the lines of the loop's arcs' chords, where the
    crossing test and the circular segments' disagree at rounding level.  A
    probe further than 2 step from the boundary is inside or outside just as
    the moved one is."""
    for _ in range(4):
        for p0, p1, b in _segments(loop):
            if not b:
                continue
            dx, dy = p1[0] - p0[0], p1[1] - p0[1]
            ll = math.hypot(dx, dy)
            t = ((p[0] - p0[0]) * dx + (p[1] - p0[1]) * dy) / (ll * ll)
            if -0.5 <= t <= 1.5 and abs(dx * (p[1] - p0[1]) - dy * (p[0] - p0[0])) / ll < step / 2:
                p = (p[0] - dy / ll * step, p[1] + dx / ll * step)
                break
        else:
            break
    return p


def _probes(loop):
    """The loop's vertices and the midpoints of its segments."""
    for p0, p1, b in _segments(loop):
        yield p0
        if not b:
            yield ((p0[0] + p1[0]) / 2.0, (p0[1] + p1[1]) / 2.0)
        else:
            # the arc's midpoint: the chord's midpoint moved by the sagitta
            dx, dy = p1[0] - p0[0], p1[1] - p0[1]
            yield ((p0[0] + p1[0]) / 2.0 + dy * b / 2.0, (p0[1] + p1[1]) / 2.0 - dx * b / 2.0)


# ---- reading the drawing -------------------------------------------------------

class _Seg:
    """One line or arc from p0 to p1 (bulge 0: a line), from entity number
    `entity` (drawing order), the `order`-th of it; `where` names the
    entity; `exact`: whether each end is as drawn rather than computed (an
    ARC's ends, a curve's arcs); `origin`: the segment it was split from
    (itself if not split); n0, n1: its ends' points once joined."""

    __slots__ = ("p0", "p1", "bulge", "entity", "order", "where", "kind", "exact", "origin",
                 "n0", "n1")

    def __init__(self, p0, p1, bulge, entity, order, where, kind, exact):
        self.p0, self.p1, self.bulge = (_num(p0[0]), _num(p0[1])), (_num(p1[0]), _num(p1[1])), _num(bulge)
        self.entity, self.order, self.where, self.kind, self.exact = entity, order, where, kind, exact
        self.origin = self
        self.n0 = self.n1 = None

    def point(self, t):
        """The point at fraction t of the segment (of an arc's sweep)."""
        if not self.bulge:
            return (self.p0[0] + t * (self.p1[0] - self.p0[0]), self.p0[1] + t * (self.p1[1] - self.p0[1]))
        c, r, sweep = _arc_of(self.p0, self.p1, self.bulge)
        a = math.atan2(self.p0[1] - c[1], self.p0[0] - c[0]) + t * sweep
        return (c[0] + r * math.cos(a), c[1] + r * math.sin(a))

    def length(self):
        chord = math.hypot(self.p1[0] - self.p0[0], self.p1[1] - self.p0[1])
        if not self.bulge:
            return chord
        _, r, sweep = _arc_of(self.p0, self.p1, self.bulge)
        return r * abs(sweep)

    def locate(self, p):
        """(t, distance): where on the segment p is nearest, as a fraction."""
        if not self.bulge:
            dx, dy = self.p1[0] - self.p0[0], self.p1[1] - self.p0[1]
            ll = dx * dx + dy * dy
            t = 0.0 if ll == 0 else max(0.0, min(1.0, ((p[0] - self.p0[0]) * dx + (p[1] - self.p0[1]) * dy) / ll))
            return t, math.hypot(p[0] - self.p0[0] - t * dx, p[1] - self.p0[1] - t * dy)
        c, r, sweep = _arc_of(self.p0, self.p1, self.bulge)
        a0 = math.atan2(self.p0[1] - c[1], self.p0[0] - c[0])
        turn = ((math.atan2(p[1] - c[1], p[0] - c[0]) - a0) * math.copysign(1.0, sweep)) % (2 * math.pi)
        if turn <= abs(sweep):
            return turn / abs(sweep), abs(math.hypot(p[0] - c[0], p[1] - c[1]) - r)
        d0 = math.hypot(p[0] - self.p0[0], p[1] - self.p0[1])
        d1 = math.hypot(p[0] - self.p1[0], p[1] - self.p1[1])
        return (0.0, d0) if d0 <= d1 else (1.0, d1)

    def box(self):
        pts = [self.point(k / 8.0) for k in range(9)]
        margin = 0.0
        if self.bulge:
            _, r, sweep = _arc_of(self.p0, self.p1, self.bulge)
            margin = r * (1.0 - math.cos(abs(sweep) / 16.0))
        xs, ys = [p[0] for p in pts], [p[1] for p in pts]
        return min(xs) - margin, min(ys) - margin, max(xs) + margin, max(ys) + margin


def _split(seg, t, p):
    """seg cut at fraction t, the cut at point p: two segments of its origin."""
    if seg.bulge:
        sweep = 4.0 * math.atan(seg.bulge)
        b0, b1 = math.tan(t * sweep / 4.0), math.tan((1.0 - t) * sweep / 4.0)
    else:
        b0 = b1 = 0.0
    a = _Seg(seg.p0, p, b0, seg.entity, seg.order, seg.where, seg.kind, (seg.exact[0], False))
    b = _Seg(p, seg.p1, b1, seg.entity, seg.order + 0.5 * t, seg.where, seg.kind, (False, seg.exact[1]))
    a.origin = b.origin = seg.origin
    return a, b


def _where(e, block=None):
    handle = e.dxf.get("handle", None)
    if block is not None:
        return "%s (in block %r of INSERT %s)" % (e.dxftype(), block[0], block[1])
    return "%s (handle %s, layer %r)" % (e.dxftype(), handle or "?", e.dxf.get("layer", "0"))


def _a_point(e):
    """Some point of an entity, to say where it is."""
    try:
        if e.dxftype() == "SPLINE":
            pts = list(e.control_points) or list(e.fit_points)
            if pts:
                return pts[0]
        for name in ("center", "insert", "start", "location"):
            if e.dxf.hasattr(name):
                return e.dxf.get(name)
    except Exception:                       # only for a message
        pass
    return None


def _plane_sign(e, where):
    """+1 or -1: the entity's extrusion is +Z or -Z; else it is refused."""
    ex = e.dxf.get("extrusion", (0.0, 0.0, 1.0))
    x, y, z = float(ex[0]), float(ex[1]), float(ex[2])
    norm = math.sqrt(x * x + y * y + z * z)
    if norm == 0 or math.hypot(x, y) > 1e-9 * norm:
        raise DxfShapeError("%s is not parallel to the XY plane (extrusion (%g, %g, %g)); "
                            "only 2-D drawings in the XY plane are read" % (where, x, y, z))
    return 1.0 if z > 0 else -1.0


def _ocs_bulged(pts, sign):
    """OCS (x, y, bulge) -> WCS: a -Z extrusion mirrors x and every bulge."""
    return [(_num(sign * x), _num(y), _num(sign * b)) for x, y, b in pts]


class _DxfCurve:
    """A SPLINE's or ELLIPSE's curve as wrenchd_arcs.follow takes it: points,
    tangents and kinks from ezdxf's own construction tool, the distance by
    sampling the parameters about the hint and a golden-section search."""

    def __init__(self, e, kind, where):
        self.kind, self.where = kind, where
        if kind == "SPLINE":
            self.tool = e.construction_tool()
            # the curve is defined between the degree-th knot from either
            # end (the whole range of a clamped B-spline; a closed uniform
            # one's knots reach beyond it)
            degree = self.tool.degree
            knots = [float(k) for k in self.tool.knots()]
            self.u0, self.u1 = knots[degree], knots[-degree - 1]
            self.wrap = False
            self._point = self.tool.point
            self._kinks = []
            for k in sorted(set(knots)):
                if self.u0 < k < self.u1 and knots.count(k) >= degree:
                    self._kinks.append(float(k))
            a, b = self._point(self.u0), self._point(self.u1)
            self.closed = math.hypot(a[0] - b[0], a[1] - b[1]) == 0.0 or bool(e.closed)
        else:
            self.tool = e.construction_tool()
            self.centre = self.tool.center
            self.major, self.minor = self.tool.major_axis, self.tool.minor_axis
            self.u0 = float(self.tool.start_param)
            self.u1 = float(self.tool.end_param)
            if self.u1 <= self.u0:
                self.u1 += 2.0 * math.pi
            self.closed = abs(self.u1 - self.u0 - 2.0 * math.pi) <= 1e-12
            self.wrap = self.closed
            self._kinks = []

    def zs(self):
        """The z values of points spread along the curve."""
        return [float(self.point3(self.u0 + (self.u1 - self.u0) * k / 16.0)[2]) for k in range(17)]

    def point3(self, u):
        if self.kind == "SPLINE":
            return self._point(u)
        c, a, b = self.centre, self.major, self.minor
        cu, su = math.cos(u), math.sin(u)
        return (c[0] + a[0] * cu + b[0] * su, c[1] + a[1] * cu + b[1] * su, c[2] + a[2] * cu + b[2] * su)

    def point(self, u):
        q = self.point3(u)
        return (float(q[0]), float(q[1]))

    def tangent(self, u):
        if self.kind == "SPLINE":
            d = self.tool.derivative(min(max(u, self.u0), self.u1), n=1)[1]
            return (float(d[0]), float(d[1]))
        a, b = self.major, self.minor
        return (-a[0] * math.sin(u) + b[0] * math.cos(u), -a[1] * math.sin(u) + b[1] * math.cos(u))

    def kinks(self, u0, u1):
        lo, hi = min(u0, u1), max(u0, u1)
        return [k for k in self._kinks if lo < k < hi]

    def distance(self, p, a, b):
        if a > b:
            a, b = b, a
        w = b - a
        lo, hi = a - w, b + w
        if not self.wrap:
            lo, hi = max(lo, self.u0), min(hi, self.u1)

        def d(u):
            q = self.point(u)
            return math.hypot(q[0] - p[0], q[1] - p[1])
        n = 12
        us = [lo + (hi - lo) * k / n for k in range(n + 1)]
        k = min(range(n + 1), key=lambda i: d(us[i]))
        x0, x1 = us[max(0, k - 1)], us[min(n, k + 1)]
        g = (math.sqrt(5.0) - 1.0) / 2.0
        c, e = x1 - g * (x1 - x0), x0 + g * (x1 - x0)
        dc, de = d(c), d(e)
        for _ in range(32):          # the bracket shrinks to 1e-7 of the window
            if dc < de:
                x1, e, de = e, c, dc
                c = x1 - g * (x1 - x0)
                dc = d(c)
            else:
                x0, c, dc = c, e, de
                e = x0 + g * (x1 - x0)
                de = d(e)
        return min(dc, de, d(us[k]))

    def box_points(self):
        return [self.point(self.u0 + (self.u1 - self.u0) * k / 32.0) for k in range(33)]


class _Reader:
    """What is read from the drawing: segments, curves to follow, counts."""

    def __init__(self, layers):
        self.layers = None if not layers else {name.lower() for name in layers}
        self.segs = []                  # _Seg
        self.curves = []                # (entity number, where, _DxfCurve)
        self.zs = []                    # (where, z min, z max)
        self.used, self.ignored = {}, {}
        self.on_layer = 0

    def ignore(self, kind, reason):
        self.ignored.setdefault(reason, {})
        self.ignored[reason][kind] = self.ignored[reason].get(kind, 0) + 1

    def count(self, kind):
        self.used[kind] = self.used.get(kind, 0) + 1

    def read(self, msp):
        for index, e in enumerate(msp):
            kind = e.dxftype()
            if self.layers is not None and e.dxf.get("layer", "0").lower() not in self.layers:
                self.ignore(kind, "on another layer")
                continue
            self.on_layer += 1
            self.entity(index, e, None, 0)

    def entity(self, index, e, block, depth):
        kind = e.dxftype()
        if kind in ANNOTATION:
            self.ignore(kind, "annotation, not geometry")
            return
        where = _where(e, block)
        add = self.segs.append
        if kind == "INSERT":
            if depth > 16:
                raise DxfShapeError("%s: blocks nested more than 16 deep" % where)
            name = (e.dxf.get("name", "?"), e.dxf.get("handle", "?"))
            try:
                inner = list(e.virtual_entities())
            except Exception as error:       # ezdxf cannot transform it (non-uniform scaling of a curve)
                raise DxfShapeError("%s: its block cannot be exploded (%s): explode it in the CAD "
                                    "program" % (where, error)) from None
            for sub in inner:
                self.entity(index, sub, name, depth + 1)
            self.count(kind)
            return
        if kind == "LINE":
            s, t = e.dxf.start, e.dxf.end
            self.zs.append((where, min(s[2], t[2]), max(s[2], t[2])))
            add(_Seg(s, t, 0.0, index, len(self.segs), where, kind, (True, True)))
        elif kind in ("ARC", "CIRCLE"):
            sign = _plane_sign(e, where)
            c, r = e.dxf.center, float(e.dxf.radius)
            if not r > 0:
                raise DxfShapeError("%s at %s has radius %r" % (where, _fmt(c), r))
            z = sign * c[2]
            self.zs.append((where, z, z))
            sweep = 0.0
            if kind == "ARC":
                a0, a1 = float(e.dxf.start_angle), float(e.dxf.end_angle)
                sweep = (a1 - a0) % 360.0
            if sweep == 0.0:            # a CIRCLE, or an ARC all the way round: two half circles
                pts = _ocs_bulged([(c[0] - r, c[1], 1.0), (c[0] + r, c[1], 1.0)], sign)
                self.polyline(index, where, kind, pts, True, True)
            else:
                p0 = (c[0] + r * cos_degrees(a0), c[1] + r * sin_degrees(a0), bulge_of_degrees(sweep))
                p1 = (c[0] + r * cos_degrees(a1), c[1] + r * sin_degrees(a1), 0.0)
                (x0, y0, b), (x1, y1, _) = _ocs_bulged([p0, p1], sign)
                add(_Seg((x0, y0), (x1, y1), b, index, len(self.segs), where, kind, (False, False)))
        elif kind == "LWPOLYLINE":
            sign = _plane_sign(e, where)
            z = sign * float(e.dxf.get("elevation", 0.0))
            self.zs.append((where, z, z))
            pts = _ocs_bulged([(p[0], p[1], p[2]) for p in e.get_points("xyb")], sign)
            self.polyline(index, where, kind, pts, e.closed, True)
        elif kind == "POLYLINE":
            mode = e.get_mode()
            if mode == "AcDb2dPolyline":
                sign = _plane_sign(e, where)
                z = sign * float(e.dxf.get("elevation", (0.0, 0.0, 0.0))[2])
                self.zs.append((where, z, z))
                # spline-fit polylines: the frame's control points (flag 16)
                # are not on the curve; the fit vertices are.
                verts = [v for v in e.vertices if not v.dxf.get("flags", 0) & 16]
                pts = _ocs_bulged([(v.dxf.location[0], v.dxf.location[1], v.dxf.get("bulge", 0.0))
                                   for v in verts], sign)
                self.polyline(index, where, kind, pts, e.is_closed, True)
            elif mode == "AcDb3dPolyline":
                locs = [v.dxf.location for v in e.vertices]
                if locs:
                    self.zs.append((where, min(p[2] for p in locs), max(p[2] for p in locs)))
                self.polyline(index, where, kind, [(p[0], p[1], 0.0) for p in locs], e.is_closed, True)
            else:
                self.ignore(kind, "a mesh, not a 2-D outline")
                return
        elif kind in ("SPLINE", "ELLIPSE"):
            try:
                curve = _DxfCurve(e, kind, where)
            except (ValueError, ZeroDivisionError, IndexError) as error:
                raise DxfShapeError("%s: ezdxf cannot evaluate it (%s)" % (where, error)) from None
            zs = curve.zs()
            self.zs.append((where, min(zs), max(zs)))
            self.curves.append((index, where, curve))
        else:
            self.ignore(kind, "a kind of entity not read")
            return
        self.count(kind)

    def polyline(self, index, where, kind, pts, closed, exact):
        """Segments between consecutive points (x, y, bulge); a closed
        polyline's last bulge is its closing segment's."""
        n = len(pts)
        stop = n if closed else n - 1
        for i in range(stop):
            x0, y0, b = pts[i]
            x1, y1, _ = pts[(i + 1) % n]
            self.segs.append(_Seg((x0, y0), (x1, y1), b, index, len(self.segs), where, kind,
                                  (exact, exact)))


def _read_units(doc, given):
    """The unit of the coordinates, the scale to write them in a fixture's
    unit, and how it was decided (the module's docstring, rule 7)."""
    code = doc.header.get("$INSUNITS", None)
    units = {"code": code}
    if code is None:
        units.update(name="not stated", mm_per_unit=None)
    else:
        name, mm = UNITS.get(int(code), ("unknown", None))
        units.update(code=int(code), name=name, mm_per_unit=mm)
    measurement = doc.header.get("$MEASUREMENT", None)
    if measurement is not None:
        units["measurement"] = "metric" if int(measurement) else "imperial"
    if given is not None:
        if given not in FIXTURE_LENGTHS:
            raise DxfShapeError("--units: %r is not a unit: one of mm, in, m" % (given,))
        unit, scale, rule = given, 1.0, "given (--units)"
    elif units["mm_per_unit"] is None:
        unit, scale = "mm", 1.0
        rule = "not stated ($INSUNITS %s): taken as mm; give --units if it is not" % (
            "absent" if code is None else code)
    else:
        mm = units["mm_per_unit"]
        if units["code"] in IMPERIAL:
            unit, scale = "in", IMPERIAL[units["code"]]
        else:
            unit = "m" if mm >= 1000.0 else "mm"
            scale = mm / FIXTURE_LENGTHS[unit]
        rule = "$INSUNITS %d (%s)" % (units["code"], units["name"])
        if scale != 1.0:
            rule += ", written in %s (x %.10g)" % (unit, scale)
    units.update(unit=unit, scale=scale, rule=rule)
    return units


# ---- joining -----------------------------------------------------------------------

class _Nodes:
    """Points closer than tol are one node (union of a grid's neighbours);
    a node's point is one drawn exactly if any, else the first drawn."""

    def __init__(self, segs, tol):
        ends = []
        for s in segs:
            ends.append((s, 0, s.p0))
            ends.append((s, 1, s.p1))
        parent = list(range(len(ends)))

        def find(i):
            while parent[i] != i:
                parent[i] = parent[parent[i]]
                i = parent[i]
            return i
        cell = tol if tol > 0 else 1.0
        grid = {}
        for n, (_, _, p) in enumerate(ends):
            grid.setdefault((math.floor(p[0] / cell), math.floor(p[1] / cell)), []).append(n)
        self.largest_gap, self.largest_gap_at = 0.0, None
        for n, (_, _, p) in enumerate(ends):
            gx, gy = math.floor(p[0] / cell), math.floor(p[1] / cell)
            for i in (-1, 0, 1):
                for j in (-1, 0, 1):
                    for m in grid.get((gx + i, gy + j), ()):
                        if m > n:
                            q = ends[m][2]
                            d = math.hypot(q[0] - p[0], q[1] - p[1])
                            if d <= tol:
                                parent[find(m)] = find(n)
                                if d > self.largest_gap:
                                    self.largest_gap, self.largest_gap_at = d, p
        best = {}
        for n, (s, side, p) in enumerate(ends):
            root = find(n)
            rank = (not s.exact[side], s.entity, s.order, side)
            if root not in best or rank < best[root][0]:
                best[root] = (rank, p)
        ids = {root: k for k, root in enumerate(sorted(best, key=lambda r: best[r][0]))}
        self.points = [None] * len(ids)
        for root, (_, p) in best.items():
            self.points[ids[root]] = p
        for n, (s, side, p) in enumerate(ends):
            if side == 0:
                s.n0 = ids[find(n)]
            else:
                s.n1 = ids[find(n)]


def _midpoint(s):
    return s.point(0.5)


def _merge_duplicates(segs, tol):
    """Segments with the same two nodes and midpoints within tol: the first
    drawn kept.  Returns the kept and the merged."""
    kept, merged = [], []
    seen = {}
    for s in sorted(segs, key=lambda s: (s.entity, s.order)):
        key = (min(s.n0, s.n1), max(s.n0, s.n1))
        m = _midpoint(s)
        twin = None
        for other in seen.get(key, ()):
            q = _midpoint(other)
            if math.hypot(q[0] - m[0], q[1] - m[1]) <= tol:
                twin = other
                break
        if twin is None:
            seen.setdefault(key, []).append(s)
            kept.append(s)
        else:
            merged.append(s)
    return kept, merged


def _on_carrier(s, p, tol):
    """Whether p lies on the line or the circle s is a piece of."""
    if not s.bulge:
        dx, dy = s.p1[0] - s.p0[0], s.p1[1] - s.p0[1]
        ll = math.hypot(dx, dy)
        return ll > 0 and abs(dx * (p[1] - s.p0[1]) - dy * (p[0] - s.p0[0])) / ll <= tol
    c, r, _ = _arc_of(s.p0, s.p1, s.bulge)
    return abs(math.hypot(p[0] - c[0], p[1] - c[1]) - r) <= tol


def _split_at_ends(segs, nodes, tol, extent):
    """Segments cut where an end of an overlapping segment lies on them,
    away from their ends: the other segment, of the same kind, runs along
    the same line or circle (its midpoint on it).  Overlapping pieces then
    share nodes, and are merged as duplicates.  (An end of another kind of
    segment on one -- a centreline through a circle's quadrant point, a
    T-junction -- cuts nothing.)  Returns the segments and whether any was
    cut."""
    at = {}
    for s in segs:
        at.setdefault(s.n0, []).append(s)
        at.setdefault(s.n1, []).append(s)
    every = range(len(nodes.points))
    cell = max(extent / 256.0, 4.0 * tol, 1e-300)
    grid = {}
    for k in every:
        p = nodes.points[k]
        grid.setdefault((math.floor(p[0] / cell), math.floor(p[1] / cell)), []).append(k)
    out, cut = [], False
    for s in segs:
        x0, y0, x1, y1 = s.box()
        hits = []
        for gx in range(math.floor((x0 - tol) / cell), math.floor((x1 + tol) / cell) + 1):
            for gy in range(math.floor((y0 - tol) / cell), math.floor((y1 + tol) / cell) + 1):
                for k in grid.get((gx, gy), ()):
                    if k in (s.n0, s.n1):
                        continue
                    p = nodes.points[k]
                    t, d = s.locate(p)
                    if d <= tol and 0.0 < t < 1.0 and any(
                            o is not s and bool(o.bulge) == bool(s.bulge) and
                            _on_carrier(s, o.point(0.5), tol) for o in at.get(k, ())):
                        q0, q1 = s.p0, s.p1
                        if math.hypot(p[0] - q0[0], p[1] - q0[1]) > tol and \
                                math.hypot(p[0] - q1[0], p[1] - q1[1]) > tol:
                            hits.append((t, k))
        if not hits:
            out.append(s)
            continue
        cut = True
        rest = s
        done = 0.0
        for t, k in sorted(set(hits)):
            # t along the original; along what is left of it:
            tt = (t - done) / (1.0 - done)
            a, rest = _split(rest, tt, nodes.points[k])
            done = t
            out.append(a)
        out.append(rest)
    return out, cut


def _strip_stray(segs, n_nodes):
    """Take away, again and again, the segments with a free end.  Returns
    the kept segments and the stray ones in chains: [[segments]]."""
    at = [[] for _ in range(n_nodes)]
    for i, s in enumerate(segs):
        at[s.n0].append(i)
        at[s.n1].append(i)
    alive = [True] * len(segs)
    degree = [len(a) for a in at]
    todo = [k for k in range(n_nodes) if degree[k] == 1]
    gone = []
    while todo:
        k = todo.pop()
        if degree[k] != 1:
            continue
        i = next(i for i in at[k] if alive[i])
        alive[i] = False
        gone.append(i)
        for n in (segs[i].n0, segs[i].n1):
            degree[n] -= 1
            if degree[n] == 1:
                todo.append(n)
    # the stray segments in chains: connected through their nodes
    parent = {}

    def find(x):
        while parent.setdefault(x, x) != x:
            parent[x] = parent[parent[x]]
            x = parent[x]
        return x
    for i in gone:
        parent[find(segs[i].n0)] = find(segs[i].n1)
    chains = {}
    for i in sorted(gone):
        chains.setdefault(find(segs[i].n0), []).append(segs[i])
    return [s for i, s in enumerate(segs) if alive[i]], list(chains.values())


def _walk(segs, nodes):
    """Loops [(entity, where, [(x, y, b)])] of segments where exactly two
    ends meet at every node; refuses a branch."""
    at = {}
    for i, s in enumerate(segs):
        at.setdefault(s.n0, []).append(i)
        at.setdefault(s.n1, []).append(i)
    for k, idx in sorted(at.items()):
        if len(idx) > 2:
            names = []
            for i in idx:
                if segs[i].where not in names:
                    names.append(segs[i].where)
            raise DxfShapeError("%d ends meet at %s (%s): a branch; an outline is a chain where "
                                "exactly two ends meet" % (len(idx), _fmt(nodes.points[k]),
                                                           ", ".join(names)))
    done = [False] * len(segs)
    loops = []
    order = sorted(range(len(segs)), key=lambda i: (segs[i].entity, segs[i].order))
    for first in order:
        if done[first]:
            continue
        run = []                                  # (segment, forward)
        i, forward = first, True
        while not done[i]:
            done[i] = True
            s = segs[i]
            run.append((s, forward))
            end = s.n1 if forward else s.n0
            nxt = [j for j in at[end] if j != i] or [i]
            j = nxt[0]
            forward = segs[j].n0 == end
            i = j
        loop = []
        for s, fw in run:
            node = s.n0 if fw else s.n1
            loop.append((s, fw, nodes.points[node]))
        loops.append(_rejoin(loop))
    return loops


def _rejoin(loop):
    """Consecutive pieces of one split segment, run the same way, made one
    again: (entity, where, [(x, y, bulge)], [entities])."""
    # [segment, forward, start point, bulge]: the drawing's bulge unless two
    # pieces are joined (their sweeps added)
    items = [[s, fw, p, s.bulge if fw else -s.bulge] for s, fw, p in loop]
    if len(items) > 2:
        changed = True
        while changed and len(items) > 2:
            changed = False
            for k in range(len(items)):
                a, b = items[k], items[(k + 1) % len(items)]
                if a[0].origin is b[0].origin and a[0] is not b[0] and a[1] == b[1] \
                        and abs(math.atan(a[3]) + math.atan(b[3])) < math.pi / 2:
                    if a[3] or b[3]:
                        a[3] = wrenchd_arcs.bulge_of_sweep(4.0 * math.atan(a[3]) + 4.0 * math.atan(b[3]))
                    items.remove(b)
                    changed = True
                    break
    first = min(items, key=lambda it: (it[0].entity, it[0].order))
    k = items.index(first)
    items = items[k:] + items[:k]
    verts = [(_num(p[0]), _num(p[1]), _num(bulge)) for _, _, p, bulge in items]
    where = []
    for s, _, _, _ in items:
        if s.where not in where:
            where.append(s.where)
    text = " + ".join(where[:3]) + (" + %d more" % (len(where) - 3) if len(where) > 3 else "")
    return first[0].entity, text, verts


# ---- the whole ---------------------------------------------------------------

def _dangling_message(chain, all_segs, tol):
    """The open-chain refusal: where each free end of the chain is, and the
    nearest other end."""
    count = {}
    for s in chain:
        count[s.n0] = count.get(s.n0, 0) + 1
        count[s.n1] = count.get(s.n1, 0) + 1
    ends = []
    for s in chain:
        for side, n, p in ((0, s.n0, s.p0), (1, s.n1, s.p1)):
            if count[n] == 1:
                ends.append((s, side, p))
    lines = []
    for s, side, p in ends[:4]:
        best = None
        for o in all_segs:
            for q in (o.p0, o.p1):
                d = math.hypot(q[0] - p[0], q[1] - p[1])
                if d > 0 and (best is None or d < best[0]):
                    best = (d, q)
        near = "" if best is None else "; the nearest other end is %s, %.6g away" % (_fmt(best[1]), best[0])
        lines.append("  the %s of %s at %s meets nothing%s" % (
            "start" if side == 0 else "end", s.where, _fmt(p), near))
    if len(ends) > 4:
        lines.append("  ... %d open ends in all" % len(ends))
    return ("open chain: a boundary with a gap above the tolerance %.6g at %s\n%s\n"
            "(close the outline in the CAD program, or give a larger --tolerance)" % (
                tol, _fmt(ends[0][2]) if ends else "?", "\n".join(lines)))


def _extent(loop):
    """The box of a loop of (x, y, bulge): its vertices, and each arc's
    points farthest left, right, down and up where the arc passes them."""
    pts = []
    for p0, p1, b in _segments(loop):
        pts.append(p0)
        if b:
            c, r, sweep = _arc_of(p0, p1, b)
            a0 = math.atan2(p0[1] - c[1], p0[0] - c[0])
            for k in range(4):
                turn = ((k * math.pi / 2 - a0) * math.copysign(1.0, sweep)) % (2 * math.pi)
                if turn <= abs(sweep):
                    pts.append((c[0] + r * (1, 0, -1, 0)[k], c[1] + r * (0, 1, 0, -1)[k]))
    return _box_of(pts)


def _box_of(points):
    xs = [p[0] for p in points]
    ys = [p[1] for p in points]
    return min(xs), min(ys), max(xs), max(ys)


def read_dxf(path, layers=None, tolerance=None, units=None, curve_tolerance=None, layer=None):
    """Every part drawn in the DXF file at `path`, and a report.

    layers: read only these layers (a name or a list of names, any case),
    else all of modelspace (`layer`: the same, one name).
    tolerance: ends closer than this are joined, in drawing units; default
    DEFAULT_RELATIVE_TOLERANCE times the extent of the drawing.
    units: "mm", "in" or "m": the unit of the drawing's numbers, overriding
    $INSUNITS; nothing is scaled.
    curve_tolerance: how far the arcs following a SPLINE or ELLIPSE may be
    from it, in drawing units; default DEFAULT_RELATIVE_CURVE_TOLERANCE
    times the extent.

    Returns (parts, report): parts, largest area first, each {"number",
    "shape", "area", "extent": [xmin, ymin, xmax, ymax], "holes", "unit"};
    report = {"file", "layers", "units": {"code", "name", "mm_per_unit",
    "measurement", "unit", "scale", "rule"}, "tolerance", "tolerance_rule",
    "extent", "largest_gap", "largest_gap_at", "used": {kind: n},
    "ignored": {reason: {kind: n}}, "zero_length_segments_dropped",
    "duplicates_merged", "duplicates": [where, ...], "stray": [{"segments",
    "entities", "extent"}], "curve_tolerance", "curves": [{"entity",
    "kind", "arcs", "deviation"}], "curve_deviation", "z", "containment",
    "parts": [{"number", "area", "extent", "holes"}]}.  Raises
    DxfShapeError (a ValueError) when the drawing has no part, OSError
    when the file cannot be read."""
    if ezdxf is None:
        raise DxfShapeError("reading DXF needs ezdxf (Debian: apt-get install python3-ezdxf), "
                            "not importable by %s: %s" % (sys.executable, _EZDXF_ERROR))
    if isinstance(layers, str):
        layers = [layers]
    if layer is not None:
        layers = list(layers or []) + [layer]
    for name, value in (("tolerance", tolerance), ("curve tolerance", curve_tolerance)):
        if value is not None and not (value >= 0 and math.isfinite(value)):
            raise DxfShapeError("the %s must be a finite number >= 0, not %r" % (name, value))
    if curve_tolerance is not None and curve_tolerance == 0:
        raise DxfShapeError("the curve tolerance must be above 0")
    try:
        doc = ezdxf.readfile(path)
    except ezdxf.DXFError as error:
        raise DxfShapeError("%s is not a DXF file ezdxf can read: %s" % (path, error)) from None
    msp = doc.modelspace()
    report = {"file": str(path), "layers": layers, "units": _read_units(doc, units)}

    reader = _Reader(layers)
    reader.read(msp)
    report["used"], report["ignored"] = reader.used, reader.ignored
    if layers and reader.on_layer == 0:
        found = {}
        for e in msp:
            name = e.dxf.get("layer", "0")
            found[name] = found.get(name, 0) + 1
        raise DxfShapeError("no entity on layer %s; modelspace's layers: %s" % (
            " or ".join(repr(n) for n in layers),
            ", ".join("%r (%d)" % kv for kv in sorted(found.items())) or "none"))

    # extent and tolerances
    pts = [p for s in reader.segs for p in (s.p0, s.p1)]
    for _, _, curve in reader.curves:
        pts += curve.box_points()
    if not pts:
        raise DxfShapeError("no closed loop found: no LINE, ARC, CIRCLE, polyline, SPLINE or "
                            "ELLIPSE%s" % ("" if not layers else " on layer %s" % " or ".join(
                                repr(n) for n in layers)))
    box = _box_of(pts)
    extent = math.hypot(box[2] - box[0], box[3] - box[1])
    report["extent"] = extent
    if tolerance is None:
        tol = DEFAULT_RELATIVE_TOLERANCE * extent
        report["tolerance_rule"] = "default: %g x the extent %.6g" % (DEFAULT_RELATIVE_TOLERANCE, extent)
    else:
        tol = float(tolerance)
        report["tolerance_rule"] = "given"
    report["tolerance"] = tol
    for where, z0, z1 in reader.zs:
        if abs(float(z1) - float(z0)) > tol:
            raise DxfShapeError("%s is not in a plane parallel to XY (z from %g to %g)" % (where, z0, z1))
    report["z"] = [min(float(z[1]) for z in reader.zs), max(float(z[2]) for z in reader.zs)] \
        if reader.zs else None

    # curves by arcs
    ctol = curve_tolerance if curve_tolerance is not None else DEFAULT_RELATIVE_CURVE_TOLERANCE * extent
    report["curve_tolerance"] = ctol
    report["curves"] = []
    worst = 0.0
    for index, where, curve in reader.curves:
        p0 = curve.point(curve.u0)
        p1 = p0 if curve.closed else curve.point(curve.u1)
        try:
            arcs, measured = wrenchd_arcs.follow(curve, curve.u0, curve.u1, p0, p1, ctol,
                                                 max(extent, 1e-300), where)
        except wrenchd_arcs.ArcFitError as error:
            raise DxfShapeError("%s (give a larger --curve-tolerance)" % error) from None
        worst = max(worst, measured)
        report["curves"].append({"entity": where, "kind": curve.kind, "arcs": len(arcs),
                                 "deviation": measured})
        for k, (start, bulge) in enumerate(arcs):
            stop = arcs[k + 1][0] if k + 1 < len(arcs) else p1
            # a curve's ends are computed: at a joint a LINE's drawn end is kept
            reader.segs.append(_Seg(start, stop, bulge, index, k, where, curve.kind,
                                    (False, False)))
    report["curve_deviation"] = worst

    # segments shorter than the tolerance: a LINE or ARC is left out, a
    # polyline's segment dropped
    segs, dropped = [], 0
    for s in reader.segs:
        if s.length() <= tol and math.hypot(s.p1[0] - s.p0[0], s.p1[1] - s.p0[1]) <= tol:
            if s.kind in ("LINE", "ARC"):
                reader.used[s.kind] -= 1
                if not reader.used[s.kind]:
                    del reader.used[s.kind]
                reader.ignore(s.kind, "shorter than the tolerance")
            else:
                dropped += 1
            continue
        segs.append(s)
    report["zero_length_segments_dropped"] = dropped

    # joints, duplicates, overlaps
    merged_all = []
    for _ in range(4):
        nodes = _Nodes(segs, tol)
        segs = [s for s in segs if s.n0 != s.n1 or s.bulge]
        segs, merged = _merge_duplicates(segs, tol)
        merged_all += merged
        segs, cut = _split_at_ends(segs, nodes, tol, extent)
        if not cut:
            break
    nodes = _Nodes(segs, tol)
    report["largest_gap"] = nodes.largest_gap
    report["largest_gap_at"] = None if nodes.largest_gap_at is None else [
        _num(nodes.largest_gap_at[0]), _num(nodes.largest_gap_at[1])]
    # a merged piece of a split segment whose origin is kept is no duplicate entity
    report["duplicates_merged"] = len(merged_all)
    names = []
    for s in merged_all:
        if s.where not in names:
            names.append(s.where)
    report["duplicates"] = names

    # stray open geometry
    segs, chains = _strip_stray(segs, len(nodes.points))
    report["stray"] = []
    for chain in chains:
        ents = []
        for s in chain:
            if s.where not in ents:
                ents.append(s.where)
        report["stray"].append({"segments": len(chain), "entities": ents,
                                "extent": list(_box_of([p for s in chain for p in (s.p0, s.p1)]))})

    loops = _walk(segs, nodes) if segs else []
    clean = []
    for index, where, lp in loops:
        area = _area(lp) if len(lp) >= 2 else 0.0
        if len(lp) < 2 or abs(area) <= tol * extent:
            report["stray"].append({"segments": len(lp), "entities": [where], "extent": list(
                _box_of(lp)), "no_area": True})
            continue
        clean.append((index, where, lp, area))
    if not clean:
        for chain in chains:
            raise DxfShapeError(_dangling_message(chain, reader.segs, tol))
        raise DxfShapeError("no closed loop found")
    clean.sort(key=lambda item: item[0])

    # a stray chain around a loop is that loop's boundary with a gap
    for chain in chains:
        cb = _box_of([s.point(k / 4.0) for s in chain for k in range(5)])
        for _, _, lp, _ in clean:
            lb = _extent(lp)
            if cb[0] <= lb[0] and cb[1] <= lb[1] and cb[2] >= lb[2] and cb[3] >= lb[3]:
                raise DxfShapeError(_dangling_message(chain, reader.segs, tol))

    parts = _parts(clean, tol, extent, report)
    scale = report["units"]["scale"]
    unit = report["units"]["unit"]
    out = []
    for number, (outer, holes) in enumerate(parts, 1):
        loops_out = []
        net = 0.0
        for rank, (_, _, lp, area) in enumerate([outer] + holes):
            if (area > 0) != (rank == 0):          # outer counter-clockwise, holes clockwise
                lp = _reversed_loop(lp)
            net += abs(area) if rank == 0 else -abs(area)
            loops_out.append([[_num(x * scale), _num(y * scale)] + ([_num(b)] if b else [])
                              for x, y, b in lp])
        ob = _extent(outer[2])
        out.append({"number": number, "shape": {"type": "outline", "loops": loops_out},
                    "area": net * scale * scale, "extent": [c * scale for c in ob],
                    "holes": len(holes), "unit": unit})
    report["parts"] = [{k: p[k] for k in ("number", "area", "extent", "holes")} for p in out]
    report["containment"] = ("exact point-in-loop test with arcs of every loop's vertices and "
                             "segment midpoints")
    return out, report


def _parts(clean, tol, extent, report):
    """[(outer, [holes])], largest net area first: a loop inside an odd
    number of others is a hole of the innermost; inside an even number, the
    outer boundary of a part."""
    n = len(clean)
    near = max(tol, 1e-9 * extent)       # probes nearer A's boundary do not count
    inside_of = [[] for _ in range(n)]
    boxes = [_box(lp, near) for _, _, lp, _ in clean]
    prepared = [_prepared(lp, near) for _, _, lp, _ in clean]
    gone = set()
    for i in range(n):
        for j in range(n):
            if i == j or i in gone or j in gone or _apart(boxes[i], boxes[j]):
                continue
            a, b = clean[i][2], clean[j][2]
            votes = set()
            for p in _probes(b):
                if not _near(prepared[i], p, near):
                    votes.add(_inside(a, _off_chords(a, p, near / 2)))
            if votes == {True, False}:
                raise DxfShapeError("the loops of %s and of %s cross" % (clean[i][1], clean[j][1]))
            if not votes:                 # the same loop drawn twice: a duplicate
                later = max(i, j)
                gone.add(later)
                report["duplicates_merged"] += len(clean[later][2])
                if clean[later][1] not in report["duplicates"]:
                    report["duplicates"].append(clean[later][1])
                continue
            if votes == {True}:
                inside_of[j].append(i)
    keep = [i for i in range(n) if i not in gone]
    depth = {i: len([k for k in inside_of[i] if k not in gone]) for i in keep}
    parts = {}
    for i in keep:
        if depth[i] % 2 == 0:
            parts[i] = []
    for i in keep:
        if depth[i] % 2 == 1:
            parent = max((k for k in inside_of[i] if k not in gone), key=lambda k: depth[k])
            parts[parent].append(clean[i])
    out = []
    for i, holes in parts.items():
        net = abs(clean[i][3]) - sum(abs(h[3]) for h in holes)
        out.append((net, i, (clean[i], holes)))
    out.sort(key=lambda item: (-item[0], item[1]))
    return [p for _, _, p in out]


def shape_from_dxf(path, layer=None, tolerance=None, part=None, units=None, curve_tolerance=None,
                   layers=None):
    """The `shape` of one part drawn in the DXF file at `path` (read_dxf's
    arguments; `part`: its number, 1 the largest (the default), or
    "largest"), and the report, which also names the part taken
    ("part") and lists every part ("parts")."""
    parts, report = read_dxf(path, layers=layers, tolerance=tolerance, units=units,
                             curve_tolerance=curve_tolerance, layer=layer)
    number = _part_number(part, len(parts))
    chosen = parts[number - 1]
    report["part"] = number
    report["loops"] = len(chosen["shape"]["loops"])
    report["holes"] = chosen["holes"]
    return chosen["shape"], report


def _part_number(part, count):
    if part is None or part == "largest":
        return 1
    try:
        number = int(part)
    except (TypeError, ValueError):
        raise DxfShapeError("--part: %r is not a part: a number from 1 to %d, largest or all"
                            % (part, count)) from None
    if not 1 <= number <= count:
        raise DxfShapeError("--part %d: the drawing holds %d part%s (1 to %d, largest first)"
                            % (number, count, "" if count == 1 else "s", count))
    return number


def fixture_units(report, force="N"):
    """The fixture's "units" member for a shape read so: {"length": the
    drawing's unit ("mm", "in" or "m"), "force": force}.  A drawing has no
    forces: `force` ("N", "mN" or "lbf") is the caller's."""
    return {"length": report["units"]["unit"], "force": force}


def _report_text(report, chosen):
    u = report["units"]
    lines = []
    parts = report["parts"]
    unit = u["unit"]
    for p in parts:
        if chosen is None or p["number"] in chosen:
            lines.append("%s: part %d of %d: %d loop%s (1 outer, %d hole%s), area %.6g %s^2" % (
                report["file"], p["number"], len(parts), p["holes"] + 1, "" if p["holes"] == 0 else "s",
                p["holes"], "" if p["holes"] == 1 else "s", p["area"], unit))
    others = [p for p in parts if chosen is not None and p["number"] not in chosen]
    if others:
        lines.append("%d other part%s (--part N to take one, --part all for every one):" % (
            len(others), "" if len(others) == 1 else "s"))
        for p in others[:20]:
            lines.append("  part %d: area %.6g %s^2, %d hole%s, x %.6g to %.6g, y %.6g to %.6g" % (
                p["number"], p["area"], unit, p["holes"], "" if p["holes"] == 1 else "s",
                p["extent"][0], p["extent"][2], p["extent"][1], p["extent"][3]))
        if len(others) > 20:
            lines.append("  ... %d more" % (len(others) - 20))
    lines.append("read: " + ", ".join("%s %d" % kv for kv in sorted(report["used"].items())))
    for reason, kinds in sorted(report["ignored"].items()):
        lines.append("ignored (%s): %s" % (reason, ", ".join("%s %d" % kv for kv in sorted(kinds.items()))))
    text = "unit: %s (%s)" % (unit, u["rule"])
    if u.get("measurement"):
        text += "; $MEASUREMENT %s (patterns and linetypes only)" % u["measurement"]
    lines.append(text)
    gap = "largest gap closed %.6g" % report["largest_gap"]
    if report["largest_gap_at"]:
        gap += " at %s" % _fmt(report["largest_gap_at"])
    lines.append("tolerance %.6g (%s); %s" % (report["tolerance"], report["tolerance_rule"], gap))
    if report["duplicates_merged"]:
        lines.append("duplicates merged: %d segment%s (%s%s)" % (
            report["duplicates_merged"], "" if report["duplicates_merged"] == 1 else "s",
            ", ".join(report["duplicates"][:3]),
            " and %d more" % (len(report["duplicates"]) - 3) if len(report["duplicates"]) > 3 else ""))
    if report["stray"]:
        segs = sum(c["segments"] for c in report["stray"])
        first = report["stray"][0]
        lines.append("stray open geometry ignored: %d chain%s, %d segment%s (the first: %s, x %.6g "
                     "to %.6g, y %.6g to %.6g)" % (
                         len(report["stray"]), "" if len(report["stray"]) == 1 else "s", segs,
                         "" if segs == 1 else "s", ", ".join(first["entities"][:3]),
                         first["extent"][0], first["extent"][2], first["extent"][1], first["extent"][3]))
    if report["curves"]:
        arcs = sum(c["arcs"] for c in report["curves"])
        lines.append("curves by tangent arcs: %d (%d arcs), within %.6g of them (measured both ways; "
                     "the tolerance %.6g)" % (len(report["curves"]), arcs, report["curve_deviation"],
                                              report["curve_tolerance"]))
    if report["zero_length_segments_dropped"]:
        lines.append("zero-length segments dropped: %d" % report["zero_length_segments_dropped"])
    return "".join("wrenchd_dxf: %s\n" % line for line in lines)


def main(argv=None):
    parser = argparse.ArgumentParser(
        prog="wrenchd_dxf.py",
        description="Print the shape (an outline with holes) of a part drawn in a DXF "
                    "file as wrenchd's JSON `shape` object.")
    parser.add_argument("dxf", help="the DXF file")
    parser.add_argument("--layer", metavar="NAME", action="append",
                        help="read only this layer (repeat for several; default: every layer)")
    parser.add_argument("--part", metavar="N|largest|all", default="largest",
                        help="the part to print: its number (1 is the largest), largest "
                             "(the default), or all (a JSON list of every part's shape)")
    parser.add_argument("--units", choices=sorted(FIXTURE_LENGTHS),
                        help="the unit of the drawing's numbers (overrides $INSUNITS)")
    parser.add_argument("--tolerance", metavar="T", type=float,
                        help="join ends closer than T, in drawing units (default: %g of the "
                             "drawing's extent)" % DEFAULT_RELATIVE_TOLERANCE)
    parser.add_argument("--curve-tolerance", metavar="T", type=float,
                        help="the arcs following a SPLINE or ELLIPSE within T of it, in drawing "
                             "units (default: %g of the drawing's extent)"
                             % DEFAULT_RELATIVE_CURVE_TOLERANCE)
    parser.add_argument("--report", action="store_true", help="the report on stderr as JSON")
    args = parser.parse_args(argv)
    try:
        parts, report = read_dxf(args.dxf, layers=args.layer, tolerance=args.tolerance,
                                 units=args.units, curve_tolerance=args.curve_tolerance)
        if args.part == "all":
            chosen = [p["number"] for p in parts]
            text = json.dumps([p["shape"] for p in parts])
        else:
            number = _part_number(args.part, len(parts))
            chosen = [number]
            text = json.dumps(parts[number - 1]["shape"])
            report["part"] = number
            report["loops"] = len(parts[number - 1]["shape"]["loops"])
            report["holes"] = parts[number - 1]["holes"]
    except (DxfShapeError, OSError) as error:
        sys.stderr.write("wrenchd_dxf: %s: %s\n" % (args.dxf, error))
        return 1
    sys.stdout.write(text + "\n")
    sys.stderr.write(json.dumps(report) + "\n" if args.report else _report_text(report, chosen))
    return 0


if __name__ == "__main__":
    sys.exit(main())
