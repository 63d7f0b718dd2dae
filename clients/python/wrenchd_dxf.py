#!/usr/bin/env python3
"""wrenchd_dxf.py -- the outline of a part from a DXF drawing, as wrenchd's
`shape` object (issue 16):

    {"type": "outline", "loops": [[[x, y], [x, y, bulge], ...], ...]}

The first loop is the outer boundary, the others are holes; a vertex's bulge
is that of the segment to the next vertex, tan(theta/4) of the arc's included
angle, positive counter-clockwise, left out for a straight segment.

    wrenchd_dxf.py part.dxf [--layer NAME] [--tolerance T] [--report]

prints the shape as JSON on stdout and a report on stderr (--report: the
report as one JSON line).  From Python:

    shape, report = wrenchd_dxf.shape_from_dxf("part.dxf", layer="PART")

What is read, from modelspace (on one layer with --layer, else every layer):

  * closed LWPOLYLINEs and 2-D POLYLINEs, with their bulges (a closed
    polyline's last bulge is its closing segment's), and 3-D POLYLINEs lying
    in a plane parallel to XY;
  * CIRCLEs: a loop of two half circles (bulge 1 each);
  * LINEs, ARCs and open polylines, joined end to end into loops: two ends
    closer than the tolerance are one point.  An ARC becomes a vertex whose
    bulge is tan(sweep/4), negated when the chain runs through it backwards.

The tolerance defaults to 1e-6 of the drawing's extent (the diagonal of the
box around what is read); the report gives it and the largest gap it closed.
Entities are in their object coordinate system: an extrusion of (0, 0, -1)
mirrors x (and so an arc's direction); any other extrusion is out of the XY
plane and refused.  Output loops run outer counter-clockwise, holes clockwise,
each from the vertex the drawing gives first.

Containment: loop B lies inside loop A when a probe point of B (its vertices
and the midpoints of its segments) is inside A by an exact point-in-loop test
with arcs -- even-odd crossing of A's chord polygon, flipped inside each
circular segment between a chord and its arc -- and none is outside; probes
within the tolerance of A's boundary do not count, and a probe on the line of
one of A's chords is first moved off it by half the tolerance.  The loop that holds all
others comes first.

Refused (DxfShapeError; exit status 1 with the message): no closed loop; an
open chain (the dangling end, and the nearest other end and its distance);
three or more ends meeting at one point; more than one outermost loop (two
disjoint parts), or a loop inside a hole; crossing loops; SPLINE, ELLIPSE,
INSERT and other kinds of geometry not read here; entities not parallel to
the XY plane.  Annotation (TEXT, DIMENSION, HATCH, POINT, ...) is ignored
and counted in the report.

The DXF is read by ezdxf (Debian: python3-ezdxf); wrenchd.py, the client,
does not need it.
"""

import argparse
import json
import math
import sys

try:
    import ezdxf
except ImportError as _error:     # reported when a drawing is read
    ezdxf = None
    _EZDXF_ERROR = _error

__all__ = ["shape_from_dxf", "DxfShapeError", "DEFAULT_RELATIVE_TOLERANCE"]

# The default joining tolerance, relative to the drawing's extent.
DEFAULT_RELATIVE_TOLERANCE = 1e-6

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

# Kinds that carry no part geometry: ignored, counted in the report.
ANNOTATION = {
    "TEXT", "MTEXT", "DIMENSION", "ARC_DIMENSION", "LARGE_RADIAL_DIMENSION",
    "LEADER", "MULTILEADER", "MLEADER", "HATCH", "MPOLYGON", "POINT", "ATTDEF",
    "ATTRIB", "IMAGE", "VIEWPORT", "WIPEOUT", "TOLERANCE", "ACAD_TABLE",
    "PDFUNDERLAY", "DWFUNDERLAY", "DGNUNDERLAY", "OLE2FRAME", "OLEFRAME",
}

# Kinds of geometry not read here, with what to do about them.
UNSUPPORTED = {
    "SPLINE": "approximate it by arcs or a polyline in the CAD program",
    "ELLIPSE": "approximate it by arcs or a polyline in the CAD program",
    "INSERT": "a block reference: explode it in the CAD program",
    "HELIX": "a 3-D curve",
}


class DxfShapeError(ValueError):
    """The drawing holds no shape wrenchd can take, or one that is not a
    single part; the message says why and where."""


# ---- numbers ------------------------------------------------------------------

def _sind(deg):
    """sin of an angle in degrees, exact at multiples of 90."""
    deg = math.fmod(deg, 360.0)
    if deg % 90.0 == 0.0:
        return (0.0, 1.0, 0.0, -1.0)[int(deg // 90.0) % 4]
    return math.sin(math.radians(deg))


def _cosd(deg):
    """cos of an angle in degrees, exact at multiples of 90."""
    deg = math.fmod(deg, 360.0)
    if deg % 90.0 == 0.0:
        return (1.0, 0.0, -1.0, 0.0)[int(deg // 90.0) % 4]
    return math.cos(math.radians(deg))


def _bulge_of_sweep(sweep_deg):
    """tan(sweep/4) for a sweep in degrees, 0 < sweep < 360: exactly 1 for a
    half circle."""
    half = sweep_deg / 2.0
    return _sind(half) / (1.0 + _cosd(half))


def _num(v):
    """A plain float, -0.0 made 0.0."""
    return float(v) + 0.0


def _fmt(p):
    return "(%s, %s)" % (repr(_num(p[0])), repr(_num(p[1])))


# ---- geometry of a loop ([(x, y, bulge)], bulge of the segment to the next) --

def _arc_of(p0, p1, b):
    """Centre, radius and signed sweep (radians) of the arc p0 -> p1, bulge b."""
    dx, dy = p1[0] - p0[0], p1[1] - p0[1]
    chord = math.hypot(dx, dy)
    theta = 4.0 * math.atan(b)
    d = (1.0 - b * b) / (4.0 * b)           # centre offset / chord, left normal
    cx = (p0[0] + p1[0]) / 2.0 - dy * d
    cy = (p0[1] + p1[1]) / 2.0 + dx * d
    r = chord * (1.0 + b * b) / (4.0 * abs(b))
    return (cx, cy), r, theta


def _segments(loop):
    n = len(loop)
    for i in range(n):
        x0, y0, b = loop[i]
        x1, y1, _ = loop[(i + 1) % n]
        yield (x0, y0), (x1, y1), b


def _area(loop):
    """Signed area (counter-clockwise positive): the chord polygon plus a
    circular segment per arc."""
    a = 0.0
    for p0, p1, b in _segments(loop):
        a += (p0[0] * p1[1] - p1[0] * p0[1]) / 2.0
        if b:
            _, r, theta = _arc_of(p0, p1, b)
            a += math.copysign(r * r / 2.0 * (abs(theta) - math.sin(abs(theta))), b)
    return a


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


def _distance(loop, p):
    """Distance from p to the loop's boundary."""
    best = math.inf
    for p0, p1, b in _segments(loop):
        if not b:
            dx, dy = p1[0] - p0[0], p1[1] - p0[1]
            ll = dx * dx + dy * dy
            t = 0.0 if ll == 0 else max(0.0, min(1.0, ((p[0] - p0[0]) * dx + (p[1] - p0[1]) * dy) / ll))
            d = math.hypot(p[0] - p0[0] - t * dx, p[1] - p0[1] - t * dy)
        else:
            c, r, theta = _arc_of(p0, p1, b)
            start = p0 if b > 0 else p1          # counter-clockwise from start
            a0 = math.atan2(start[1] - c[1], start[0] - c[0])
            ap = math.atan2(p[1] - c[1], p[0] - c[0])
            if (ap - a0) % (2 * math.pi) <= abs(theta):
                d = abs(math.hypot(p[0] - c[0], p[1] - c[1]) - r)
            else:
                d = min(math.hypot(p[0] - p0[0], p[1] - p0[1]),
                        math.hypot(p[0] - p1[0], p[1] - p1[1]))
        best = min(best, d)
    return best


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

class _Piece:
    """An open run of segments from one entity: points [(x, y)], bulges (one
    per segment), whether each end point is as drawn (not computed)."""

    def __init__(self, index, where, points, bulges, exact):
        self.index, self.where = index, where
        self.points, self.bulges, self.exact = points, bulges, exact


def _where(e):
    handle = e.dxf.get("handle", "?")
    return "%s (handle %s, layer %r)" % (e.dxftype(), handle, e.dxf.get("layer", "0"))


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


def _plane_sign(e):
    """+1 or -1: the entity's extrusion is +Z or -Z; else it is refused."""
    ex = e.dxf.get("extrusion", (0.0, 0.0, 1.0))
    x, y, z = float(ex[0]), float(ex[1]), float(ex[2])
    norm = math.sqrt(x * x + y * y + z * z)
    if norm == 0 or math.hypot(x, y) > 1e-9 * norm:
        raise DxfShapeError("%s is not parallel to the XY plane (extrusion (%g, %g, %g)); "
                            "only 2-D drawings in the XY plane are read" % (_where(e), x, y, z))
    return 1.0 if z > 0 else -1.0


def _ocs_bulged(e, pts, sign):
    """OCS (x, y, bulge) -> WCS: a -Z extrusion mirrors x and every bulge."""
    return [(_num(sign * x), _num(y), _num(sign * b)) for x, y, b in pts]


def _read_units(doc):
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
    return units


def _collect(msp, layer, report):
    """Loops given whole, pieces to join, z values, per entity; refuses what
    cannot be read."""
    loops, pieces, zs = [], [], []     # loops: (index, where, [(x, y, b)])
    used, ignored = {}, {}
    unsupported = []
    on_layer = 0

    def ignore(kind, reason):
        ignored.setdefault(reason, {})
        ignored[reason][kind] = ignored[reason].get(kind, 0) + 1

    for index, e in enumerate(msp):
        kind = e.dxftype()
        if layer is not None and e.dxf.get("layer", "0").lower() != layer.lower():
            ignore(kind, "on another layer")
            continue
        on_layer += 1
        if kind in ANNOTATION:
            ignore(kind, "annotation, not geometry")
            continue
        where = _where(e)
        if kind == "LINE":
            s, t = e.dxf.start, e.dxf.end
            zs.append((where, s[2], t[2]))
            pieces.append(_Piece(index, where, [(_num(s[0]), _num(s[1])), (_num(t[0]), _num(t[1]))],
                                 [0.0], (True, True)))
        elif kind in ("ARC", "CIRCLE"):
            sign = _plane_sign(e)
            c, r = e.dxf.center, float(e.dxf.radius)
            if not r > 0:
                raise DxfShapeError("%s at %s has radius %r" % (where, _fmt(c), r))
            z = sign * c[2]
            zs.append((where, z, z))
            sweep = 0.0
            if kind == "ARC":
                a0, a1 = float(e.dxf.start_angle), float(e.dxf.end_angle)
                sweep = (a1 - a0) % 360.0
            if sweep == 0.0:            # a CIRCLE, or an ARC all the way round
                loops.append((index, where, _ocs_bulged(
                    e, [(c[0] - r, c[1], 1.0), (c[0] + r, c[1], 1.0)], sign)))
            else:
                p0 = (c[0] + r * _cosd(a0), c[1] + r * _sind(a0), _bulge_of_sweep(sweep))
                p1 = (c[0] + r * _cosd(a1), c[1] + r * _sind(a1), 0.0)
                (x0, y0, b), (x1, y1, _) = _ocs_bulged(e, [p0, p1], sign)
                pieces.append(_Piece(index, where, [(x0, y0), (x1, y1)], [b], (False, False)))
        elif kind == "LWPOLYLINE":
            sign = _plane_sign(e)
            z = sign * float(e.dxf.get("elevation", 0.0))
            zs.append((where, z, z))
            pts = _ocs_bulged(e, [(p[0], p[1], p[2]) for p in e.get_points("xyb")], sign)
            _polyline(index, where, pts, e.closed, loops, pieces)
        elif kind == "POLYLINE":
            mode = e.get_mode()
            if mode == "AcDb2dPolyline":
                sign = _plane_sign(e)
                z = sign * float(e.dxf.get("elevation", (0.0, 0.0, 0.0))[2])
                zs.append((where, z, z))
                # spline-fit polylines: the frame's control points (flag 16)
                # are not on the curve; the fit vertices are.
                verts = [v for v in e.vertices if not v.dxf.get("flags", 0) & 16]
                pts = _ocs_bulged(e, [(v.dxf.location[0], v.dxf.location[1], v.dxf.get("bulge", 0.0))
                                      for v in verts], sign)
                _polyline(index, where, pts, e.is_closed, loops, pieces)
            elif mode == "AcDb3dPolyline":
                locs = [v.dxf.location for v in e.vertices]
                if locs:
                    zs.append((where, min(p[2] for p in locs), max(p[2] for p in locs)))
                pts = [(_num(p[0]), _num(p[1]), 0.0) for p in locs]
                _polyline(index, where, pts, e.is_closed, loops, pieces)
            else:
                unsupported.append((e, "a polygon or polyface mesh, a 3-D surface"))
                continue
        else:
            unsupported.append((e, UNSUPPORTED.get(kind, "a kind of entity not read here; "
                                                   "move it to another layer and use --layer")))
            continue
        used[kind] = used.get(kind, 0) + 1

    if unsupported:
        lines = []
        for e, advice in unsupported[:5]:
            p = _a_point(e)
            lines.append("  %s%s: not supported -- %s" % (
                _where(e), "" if p is None else " at " + _fmt(p), advice))
        if len(unsupported) > 5:
            lines.append("  ... and %d more" % (len(unsupported) - 5))
        raise DxfShapeError("entities of kinds not supported%s:\n%s\n(LINE, ARC, CIRCLE, LWPOLYLINE "
                            "and POLYLINE are read; a FreeCAD tool to approximate splines and "
                            "ellipses is planned)" % (
                                "" if layer is None else " on layer %r" % layer, "\n".join(lines)))
    report["used"] = used
    report["ignored"] = ignored
    return loops, pieces, zs, on_layer


def _polyline(index, where, pts, closed, loops, pieces):
    """A polyline's points [(x, y, bulge)]: a loop when closed (the last bulge
    closes it), else a piece (the last bulge means nothing)."""
    if not pts:
        return
    if closed:
        loops.append((index, where, list(pts)))
    elif len(pts) >= 2:
        pieces.append(_Piece(index, where, [(x, y) for x, y, _ in pts],
                             [b for _, _, b in pts[:-1]], (True, True)))


# ---- joining pieces ------------------------------------------------------------

def _join(pieces, tol, report):
    """Loops [(index, where, [(x, y, b)])] from the pieces, two ends within
    tol being one point."""
    ends = []                         # (piece number, 0 start / 1 end, point)
    for k, pc in enumerate(pieces):
        ends.append((k, 0, pc.points[0]))
        ends.append((k, 1, pc.points[-1]))
    cell = tol if tol > 0 else 1.0
    grid = {}
    for n, (_, _, p) in enumerate(ends):
        grid.setdefault((math.floor(p[0] / cell), math.floor(p[1] / cell)), []).append(n)

    partner = {}
    dangling = []
    for n, (k, side, p) in enumerate(ends):
        gx, gy = math.floor(p[0] / cell), math.floor(p[1] / cell)
        near = [m for i in (-1, 0, 1) for j in (-1, 0, 1) for m in grid.get((gx + i, gy + j), ())
                if m != n and math.hypot(ends[m][2][0] - p[0], ends[m][2][1] - p[1]) <= tol]
        if len(near) > 1:
            raise DxfShapeError("%d ends meet at %s (%s): a branch or a duplicated entity; an outline "
                                "is a chain where exactly two ends meet" % (
                                    len(near) + 1, _fmt(p),
                                    ", ".join(pieces[ends[m][0]].where for m in [n] + near)))
        if not near:
            dangling.append(n)
        else:
            partner[n] = near[0]
    if dangling:
        lines = []
        for n in dangling[:4]:
            k, side, p = ends[n]
            others = [m for m in range(len(ends)) if m != n]
            if others:
                m = min(others, key=lambda m: math.hypot(ends[m][2][0] - p[0], ends[m][2][1] - p[1]))
                q = ends[m][2]
                near = "; the nearest other end is %s, %.6g away" % (
                    _fmt(q), math.hypot(q[0] - p[0], q[1] - p[1]))
            else:
                near = ""
            lines.append("  the %s of %s at %s meets nothing%s" % (
                "start" if side == 0 else "end", pieces[k].where, _fmt(p), near))
        if len(dangling) > 4:
            lines.append("  ... %d open ends in all" % len(dangling))
        raise DxfShapeError("open chain: a gap above the tolerance %.6g at %s\n%s\n"
                            "(close the outline in the CAD program, or give a larger --tolerance)" % (
                                tol, _fmt(ends[dangling[0]][2]), "\n".join(lines)))

    gap, gap_at = 0.0, None
    done = [False] * len(pieces)
    loops = []
    for first in range(len(pieces)):
        if done[first]:
            continue
        run = []                      # (piece number, forward)
        n = 2 * first                 # the start of the first piece
        while True:
            k = ends[n][0]
            forward = ends[n][1] == 0
            run.append((k, forward))
            done[k] = True
            out = 2 * k + (1 if forward else 0)
            n = partner[out]
            d = math.hypot(ends[n][2][0] - ends[out][2][0], ends[n][2][1] - ends[out][2][1])
            if d > gap:
                gap, gap_at = d, ends[out][2]
            if n == 2 * first:
                break
            if done[ends[n][0]]:      # cannot happen with a matching; guard
                raise DxfShapeError("cannot join %s" % pieces[ends[n][0]].where)
        loop = []
        for i, (k, forward) in enumerate(run):
            pc = pieces[k]
            pts, bs, ex = pc.points, pc.bulges, pc.exact
            if not forward:
                pts, bs, ex = pts[::-1], [-b for b in bs[::-1]], ex[::-1]
            # the joint with the previous piece: the point as drawn rather than
            # computed (an ARC's ends), else the one drawn first
            pk, pf = run[i - 1]
            ppc = pieces[pk]
            prev_end = ppc.points[-1] if pf else ppc.points[0]
            prev_exact = ppc.exact[1] if pf else ppc.exact[0]
            joint = min((not ex[0], pc.index, pts[0]), (not prev_exact, ppc.index, prev_end))[2]
            loop.append((joint[0], joint[1], _num(bs[0])))
            for p, b in zip(pts[1:-1], bs[1:]):
                loop.append((p[0], p[1], _num(b)))
        loops.append((pieces[run[0][0]].index, " + ".join(pieces[k].where for k, _ in run[:3])
                      + (" + %d more" % (len(run) - 3) if len(run) > 3 else ""), loop))
    report["largest_gap"] = gap
    report["largest_gap_at"] = None if gap_at is None else [_num(gap_at[0]), _num(gap_at[1])]
    return loops


def _drop_zero_segments(loop, tol):
    """Remove segments shorter than tol (a closed polyline's repeated first
    point, joints within the tolerance): the later vertex goes, the earlier
    one taking its bulge, but the first vertex stays.  Returns the loop and
    how many went."""
    out = list(loop)
    dropped = 0
    i = 0
    while len(out) > 1 and i < len(out):
        j = (i + 1) % len(out)
        if math.hypot(out[j][0] - out[i][0], out[j][1] - out[i][1]) <= tol:
            if j == 0:                # the closing segment: the first vertex stays
                del out[i]
            else:
                out[i] = (out[i][0], out[i][1], out[j][2])
                del out[j]
            dropped += 1
        else:
            i += 1
    return out, dropped


# ---- the whole ---------------------------------------------------------------

def shape_from_dxf(path, layer=None, tolerance=None):
    """The `shape` of the part drawn in the DXF file at `path`, and a report.

    layer: read only this layer (case-insensitive), else all of modelspace.
    tolerance: ends closer than this are joined, in drawing units; default
    DEFAULT_RELATIVE_TOLERANCE times the extent of the drawing.

    Returns (shape, report): shape = {"type": "outline", "loops": [...]};
    report = {"file", "layer", "units": {"code", "name", "mm_per_unit",
    "measurement"}, "tolerance", "tolerance_rule", "extent", "largest_gap",
    "largest_gap_at", "loops", "holes", "used": {kind: n}, "ignored":
    {reason: {kind: n}}, "zero_length_segments_dropped", "z": [min, max],
    "containment"}.  Raises DxfShapeError (a ValueError) when the drawing
    has no single part, OSError when the file cannot be read."""
    if ezdxf is None:
        raise DxfShapeError("reading DXF needs ezdxf (Debian: apt-get install python3-ezdxf), "
                            "not importable by %s: %s" % (sys.executable, _EZDXF_ERROR))
    if tolerance is not None and not (tolerance >= 0 and math.isfinite(tolerance)):
        raise DxfShapeError("the tolerance must be a finite number >= 0, not %r" % (tolerance,))
    try:
        doc = ezdxf.readfile(path)
    except ezdxf.DXFError as error:
        raise DxfShapeError("%s is not a DXF file ezdxf can read: %s" % (path, error)) from None
    msp = doc.modelspace()
    report = {"file": str(path), "layer": layer, "units": _read_units(doc)}

    loops, pieces, zs, on_layer = _collect(msp, layer, report)
    if layer is not None and on_layer == 0:
        layers = {}
        for e in msp:
            name = e.dxf.get("layer", "0")
            layers[name] = layers.get(name, 0) + 1
        raise DxfShapeError("no entity on layer %r; modelspace's layers: %s" % (
            layer, ", ".join("%r (%d)" % kv for kv in sorted(layers.items())) or "none"))

    # extent and tolerance
    xs, ys = [], []
    for _, _, lp in loops:
        for x, y, b in lp:
            xs.append(x)
            ys.append(y)
    for pc in pieces:
        for x, y in pc.points:
            xs.append(x)
            ys.append(y)
    if not xs:
        raise DxfShapeError("no closed loop found: no LINE, ARC, CIRCLE or polyline%s" % (
            "" if layer is None else " on layer %r" % layer))
    extent = math.hypot(max(xs) - min(xs), max(ys) - min(ys))
    report["extent"] = extent
    if tolerance is None:
        tol = DEFAULT_RELATIVE_TOLERANCE * extent
        report["tolerance_rule"] = "default: %g x the extent %.6g" % (DEFAULT_RELATIVE_TOLERANCE, extent)
    else:
        tol = float(tolerance)
        report["tolerance_rule"] = "given"
    report["tolerance"] = tol

    for where, z0, z1 in zs:
        if abs(float(z1) - float(z0)) > tol:
            raise DxfShapeError("%s is not in a plane parallel to XY (z from %g to %g)" % (where, z0, z1))
    report["z"] = [min(float(z[1]) for z in zs), max(float(z[2]) for z in zs)] if zs else None

    # a LINE or ARC shorter than the tolerance would be a third end at a joint
    kept = []
    for pc in pieces:
        x0, y0 = pc.points[0]
        if all(math.hypot(x - x0, y - y0) <= tol for x, y in pc.points):
            kind = pc.where.split(" ", 1)[0]
            report["used"][kind] -= 1
            if not report["used"][kind]:
                del report["used"][kind]
            reason = report["ignored"].setdefault("shorter than the tolerance", {})
            reason[kind] = reason.get(kind, 0) + 1
        else:
            kept.append(pc)
    pieces = kept
    loops = loops + _join(pieces, tol, report) if pieces else loops
    if not pieces:
        report["largest_gap"] = 0.0
        report["largest_gap_at"] = None
    if not loops:
        raise DxfShapeError("no closed loop found")
    loops.sort(key=lambda item: item[0])        # the drawing's order

    dropped = 0
    clean = []
    for index, where, lp in loops:
        lp, d = _drop_zero_segments(lp, tol)
        dropped += d
        area = _area(lp) if len(lp) >= 2 else 0.0
        if len(lp) < 2 or abs(area) <= tol * extent:
            raise DxfShapeError("the loop of %s at %s encloses no area" % (where, _fmt(lp[0])))
        clean.append((where, lp, area))
    report["zero_length_segments_dropped"] = dropped

    # containment
    n = len(clean)
    near = max(tol, 1e-9 * extent)       # probes nearer A's boundary do not count
    inside_of = [[] for _ in range(n)]
    boxes = [_box(lp, near) for _, lp, _ in clean]
    for i in range(n):
        for j in range(n):
            if i == j or _apart(boxes[i], boxes[j]):
                continue
            a, b = clean[i][1], clean[j][1]
            votes = set()
            for p in _probes(b):
                if _distance(a, p) > near:
                    votes.add(_inside(a, _off_chords(a, p, near / 2)))
            if votes == {True, False}:
                raise DxfShapeError("the loops of %s and of %s cross" % (clean[i][0], clean[j][0]))
            if not votes:
                raise DxfShapeError("the loops of %s and of %s coincide" % (clean[i][0], clean[j][0]))
            if votes == {True}:
                inside_of[j].append(i)
    outer = [i for i in range(n) if not inside_of[i]]
    if not outer:
        raise DxfShapeError("no outermost loop: the loops lie inside one another in a cycle")
    if len(outer) > 1:
        raise DxfShapeError("%d outermost loops: the drawing holds disjoint parts (%s); put one part "
                            "on a layer of its own and give --layer" % (
                                len(outer), "; ".join("%s at %s" % (clean[i][0], _fmt(clean[i][1][0]))
                                                      for i in outer)))
    for i in range(n):
        if len(inside_of[i]) > 1:
            k = [h for h in inside_of[i] if h != outer[0]][0]
            raise DxfShapeError("the loop of %s at %s lies inside the hole %s: a second part" % (
                clean[i][0], _fmt(clean[i][1][0]), clean[k][0]))
    order = outer + [i for i in range(n) if i != outer[0]]
    report["containment"] = ("exact point-in-loop test with arcs of every loop's vertices and "
                             "segment midpoints")
    report["loops"] = n
    report["holes"] = n - 1

    out = []
    for rank, i in enumerate(order):
        _, lp, area = clean[i]
        if (area > 0) != (rank == 0):          # outer counter-clockwise, holes clockwise
            lp = _reversed_loop(lp)
        out.append([[_num(x), _num(y)] + ([_num(b)] if b else []) for x, y, b in lp])
    return {"type": "outline", "loops": out}, report


def _report_text(report):
    u = report["units"]
    lines = ["%s: %d loop%s (1 outer, %d hole%s)" % (
        report["file"], report["loops"], "" if report["loops"] == 1 else "s",
        report["holes"], "" if report["holes"] == 1 else "s")]
    lines.append("read: " + ", ".join("%s %d" % kv for kv in sorted(report["used"].items())))
    for reason, kinds in sorted(report["ignored"].items()):
        lines.append("ignored (%s): %s" % (reason, ", ".join("%s %d" % kv for kv in sorted(kinds.items()))))
    unit = "units: %s ($INSUNITS %s)" % (u["name"], u["code"])
    if u.get("mm_per_unit") not in (None, 1.0):
        unit += ", 1 unit = %g mm" % u["mm_per_unit"]
    if u.get("measurement") and u["code"] in (None, 0):
        unit += "; $MEASUREMENT says %s" % u["measurement"]
    lines.append(unit)
    gap = "largest gap closed %.6g" % report["largest_gap"]
    if report["largest_gap_at"]:
        gap += " at %s" % _fmt(report["largest_gap_at"])
    lines.append("tolerance %.6g (%s); %s" % (report["tolerance"], report["tolerance_rule"], gap))
    if report["zero_length_segments_dropped"]:
        lines.append("zero-length segments dropped: %d" % report["zero_length_segments_dropped"])
    return "".join("wrenchd_dxf: %s\n" % line for line in lines)


def main(argv=None):
    parser = argparse.ArgumentParser(
        prog="wrenchd_dxf.py",
        description="Print the shape (an outline with holes) of the part drawn in a DXF "
                    "file as wrenchd's JSON `shape` object.")
    parser.add_argument("dxf", help="the DXF file")
    parser.add_argument("--layer", metavar="NAME", help="read only this layer (default: every layer)")
    parser.add_argument("--tolerance", metavar="T", type=float,
                        help="join ends closer than T, in drawing units (default: %g of the "
                             "drawing's extent)" % DEFAULT_RELATIVE_TOLERANCE)
    parser.add_argument("--report", action="store_true", help="the report on stderr as JSON")
    args = parser.parse_args(argv)
    try:
        shape, report = shape_from_dxf(args.dxf, layer=args.layer, tolerance=args.tolerance)
    except (DxfShapeError, OSError) as error:
        sys.stderr.write("wrenchd_dxf: %s: %s\n" % (args.dxf, error))
        return 1
    sys.stdout.write(json.dumps(shape) + "\n")
    sys.stderr.write(json.dumps(report) + "\n" if args.report else _report_text(report))
    return 0


if __name__ == "__main__":
    sys.exit(main())
