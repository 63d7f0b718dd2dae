"""wrench_outline -- the outline of a planar face as wrenchd's `shape`: the
Wrench workbench's geometry (wrench_freecad.py is the workbench's one
import; wrench_objects.py its document objects, wrench_view.py their view).
FreeCAD and Part only, no GUI.

The outline
-----------

    shape = outline(face, tolerance=None)

is wrenchd's `{"type": "outline", "loops": [...]}` (docs/PROTOCOL.md) for a
planar face: its outer wire first, then its holes, each a loop of vertices
`[x, y]` or `[x, y, bulge]`.  Lines and circular arcs are exact (an arc of
more than half a turn, and a full circle, is written as equal arcs of at
most half a turn).  Every other curve -- B-spline, ellipse, Bezier, offset
curve ... -- is replaced by arcs that meet tangentially (biarcs), no farther
from it than `tolerance` (default: 1e-5 of the face's bounding-box
diagonal, 1 micrometre on a part 100 mm across); runs of them that are
straight, or on one circle, become one line or one arc.  The distance is
measured both ways, from points of the curve to the arcs and from points of
the arcs to the curve, and the largest found is `shape.deviation`.

The 2-D frame: a face in a plane z = const (its normal along +Z or -Z) is
written in the document's x and y.  A face in any other plane is written in
the plane's own frame: origin at the plane's Position, x along the plane's
first parameter direction (u), y = normal x (x), the normal being the
plane's axis.  A sketch out of the XY plane is written in its own
coordinates.  `shape.frame` is that frame as a Placement: the outline's
point (x, y) is `shape.frame.multVec(Vector(x, y, 0))` in the document.

`shape` is a dict (json.dumps writes it as wrenchd wants) that also knows
`frame`, `tolerance`, `deviation`, `size` (the bounding-box diagonal),
`segments` (per loop, one Segment per wrenchd segment: its geometry and the
FreeCAD edge it comes from) and `approximated` (the edges replaced by arcs).
"""

import math
import os
import sys

import FreeCAD
import Part
from FreeCAD import Vector


def _client_module_paths():
    """Where wrenchd.py and wrenchd_arcs.py may be: the checkout's
    clients/python beside this workbench, then this directory (make install
    puts a copy here)."""
    here = os.path.dirname(os.path.realpath(__file__))
    return [os.path.normpath(os.path.join(here, "..", "python")), here]


for _path in _client_module_paths():
    if os.path.isfile(os.path.join(_path, "wrenchd.py")):
        if _path not in sys.path:
            sys.path.insert(0, _path)
        break

import wrenchd_arcs  # noqa: E402  (after its directory is on the path)


# The default approximation tolerance, relative to the face's bounding-box
# diagonal: 1 micrometre on a part 100 mm across, a tenth of a fine machining
# tolerance.  A position that close still turns a curve's normal, on which a
# push region depends, by at most about sqrt(2 tolerance / radius of
# curvature) between the arcs' joints (where it is exact).
DEFAULT_RELATIVE_TOLERANCE = 1e-5

# wrenchd takes at most this many outline vertices over all loops.
MAX_VERTICES = 4096

# A fixel this close to the outline (relative to its size) counts as on it
# before it is moved onto it; wrenchd itself allows 1e-9.
ON_OUTLINE = 1e-7


class OutlineError(ValueError):
    """The face (or sketch) has no outline wrenchd can take; the message says
    which entity and why."""


# ---- numbers -----------------------------------------------------------------------

# A number for a message (6 significant digits; below 1e-9 in size, 0), and
# a point: the shared module's (wrenchd_arcs.py), as the DXF reader's.
_fmt, _fmt_point = wrenchd_arcs._fmt, wrenchd_arcs._fmt_point


# The plane's vector arithmetic is the shared module's (wrenchd_arcs.py).
_sub, _dot, _cross = wrenchd_arcs._sub, wrenchd_arcs._dot, wrenchd_arcs._cross
_norm, _unit, _angle = wrenchd_arcs._norm, wrenchd_arcs._unit, wrenchd_arcs._angle


# ---- segments ----------------------------------------------------------------------

# One segment of an outline, its arithmetic written once for the workbench and
# the DXF reader (clients/python/wrenchd_arcs.py).
Segment = wrenchd_arcs.Segment


# ---- the outline -------------------------------------------------------------------

class Outline(dict):
    """wrenchd's shape {"type": "outline", "loops": [...]}, with what maps
    its answers back into the document (see the module's docstring)."""

    def __init__(self, loops, frame, tolerance=0.0, deviation=0.0, approximated=(), size=None):
        segments = [list(loop) for loop in loops]
        super().__init__(type="outline", loops=[[s.vertex() for s in loop] for loop in segments])
        self.segments = segments
        self.frame = FreeCAD.Placement(frame)
        self.tolerance = tolerance
        self.deviation = deviation
        self.approximated = list(approximated)
        # what outline() left out of a shape of wires: other parts, stray open geometry
        self.other_parts, self.ignored = [], []
        if size is None:
            xs = [c for loop in segments for s in loop for c in (s.start[0], s.end[0])]
            ys = [c for loop in segments for s in loop for c in (s.start[1], s.end[1])]
            size = math.hypot(max(xs) - min(xs), max(ys) - min(ys)) if xs else 0.0
        self.size = size
        self._inverse = self.frame.inverse()
        self._inward_left = [self._signed_area(i) > 0 if i == 0 else self._signed_area(i) < 0
                             for i in range(len(segments))]

    @classmethod
    def from_shape(cls, shape, frame, edges=None, tolerance=0.0, deviation=0.0):
        """The Outline of a shape dict as wrenchd takes it (the loops of
        vertices with bulges); `edges`: per loop, per segment, the FreeCAD
        edge it came from and whether exactly ([[name, exact], ...])."""
        loops = []
        for i, loop in enumerate(shape["loops"]):
            segs = []
            n = len(loop)
            for j, v in enumerate(loop):
                w = loop[(j + 1) % n]
                name, exact = ("", True)
                if edges is not None:
                    name, exact = edges[i][j]
                segs.append(Segment(i, j, v[:2], w[:2], v[2] if len(v) > 2 else 0.0, name, exact))
            loops.append(segs)
        return cls(loops, frame, tolerance, deviation)

    def edge_table(self):
        """Per loop, per segment: [FreeCAD edge name, exact]."""
        return [[[s.edge, s.exact] for s in loop] for loop in self.segments]

    def _signed_area(self, i):
        """The signed area of loop i, counter-clockwise positive."""
        return sum(s.area for s in self.segments[i])

    # -- the frame --
    def to_3d(self, p):
        """The document point of the outline's point p = (x, y)."""
        return self.frame.multVec(Vector(p[0], p[1], 0.0))

    def direction_3d(self, d):
        return self.frame.Rotation.multVec(Vector(d[0], d[1], 0.0))

    def to_2d(self, v):
        """(x, y, off): the outline's coordinates of document point v, and
        its distance from the outline's plane."""
        q = self._inverse.multVec(v)
        return q.x, q.y, q.z

    def direction_2d(self, v):
        q = self._inverse.Rotation.multVec(v)
        return q.x, q.y

    @property
    def normal(self):
        """The plane's normal in the document (the frame's z axis)."""
        return self.frame.Rotation.multVec(Vector(0, 0, 1))

    # -- geometry --
    def all_segments(self):
        for loop in self.segments:
            for s in loop:
                yield s

    def perimeter(self):
        return sum(s.length for s in self.all_segments())

    def nearest(self, p):
        """(segment, t, point, distance): where the outline is nearest p."""
        best = None
        for s in self.all_segments():
            t, q, d = s.nearest(p)
            if best is None or d < best[3]:
                best = (s, t, q, d)
        return best

    def inward_normal(self, segment, t):
        """The unit normal at t of the segment, pointing into the material."""
        tx, ty = segment.tangent(t)
        if self._inward_left[segment.loop]:
            return (-ty, tx)
        return (ty, -tx)

    def corner_normal(self, loop, index):
        """At vertex `index` of `loop`, the inward bisector of the two
        segments that meet there (a fixel at a corner needs a normal)."""
        segs = self.segments[loop]
        before, after = segs[index - 1], segs[index]
        a = self.inward_normal(before, 1.0)
        b = self.inward_normal(after, 0.0)
        s = (a[0] + b[0], a[1] + b[1])
        if _norm(s) < 1e-9:           # a cusp: the segments turn back
            return b
        return _unit(s)

    def edge_3d(self, segment, t0=0.0, t1=1.0):
        """The document edge of the segment from t0 to t1 (a line or an arc
        on the segment's own circle)."""
        if not segment.is_arc:
            return Part.LineSegment(self.to_3d(segment.point(t0)), self.to_3d(segment.point(t1))).toShape()
        a0 = segment.start_angle + t0 * segment.sweep
        a1 = segment.start_angle + t1 * segment.sweep
        lo, hi = min(a0, a1), max(a0, a1)
        circle = Part.Circle(self.to_3d(segment.centre), self.normal, segment.radius)
        circle.XAxis = self.direction_3d((1.0, 0.0))
        return Part.ArcOfCircle(circle, lo, hi).toShape()

    def shape_3d(self):
        """Every segment in the document, as one compound of edges."""
        return Part.Compound([self.edge_3d(s) for s in self.all_segments()])

    def loop_words(self, i):
        """"the outer boundary" or "hole 2", with the FreeCAD edges of loop i."""
        what = "the outer boundary" if i == 0 else "hole %d" % i
        names = []
        for s in self.segments[i]:
            if s.edge and s.edge not in names:
                names.append(s.edge)
        if names:
            what += " (%s)" % ", ".join(names)
        return what

    def segment_words(self, i, j):
        s = self.segments[i][j]
        text = "segment %d of loop %d, a %s" % (j, i, "arc" if s.is_arc else "line")
        if s.edge:
            text += " %s %s" % ("on" if s.exact else "approximating", s.edge)
        return text


def _frame_of(plane, shape):
    """The 2-D frame of a plane: the document's x, y when its normal is
    along Z, else the plane's own frame (the module's docstring)."""
    axis = Vector(plane.Axis)
    axis.normalize()
    if abs(axis.x) <= 1e-12 and abs(axis.y) <= 1e-12:
        z = shape.Vertexes[0].Point.z if shape.Vertexes else plane.Position.z
        return FreeCAD.Placement(Vector(0, 0, z), FreeCAD.Rotation())
    origin = plane.value(0, 0)
    u = plane.value(1, 0) - origin
    u = u - axis * u.dot(axis)
    u.normalize()
    v = axis.cross(u)
    m = FreeCAD.Matrix(u.x, v.x, axis.x, origin.x,
                       u.y, v.y, axis.y, origin.y,
                       u.z, v.z, axis.z, origin.z,
                       0, 0, 0, 1)
    return FreeCAD.Placement(m)


def _edge_kind(edge):
    try:
        return type(edge.Curve).__name__
    except Exception:             # an edge without a curve (degenerated)
        return "degenerate edge"


class _Namer:
    """Names the FreeCAD edges of a wire: "Edge3" as FreeCAD's selection
    calls them in `names_in` (the linked object's shape), else as the face's
    own edges."""

    def __init__(self, names_in, owner=""):
        self.edges = list(names_in.Edges) if names_in is not None else []
        self.owner = owner

    def __call__(self, edge):
        for i, e in enumerate(self.edges):
            if e.isSame(edge):
                return "Edge%d%s" % (i + 1, " of " + self.owner if self.owner else "")
        # the same curve, another TopoDS edge (a face made from a sketch's wires)
        mid = edge.valueAt((edge.FirstParameter + edge.LastParameter) / 2.0)
        for i, e in enumerate(self.edges):
            if abs(e.Length - edge.Length) <= 1e-7 * max(1.0, edge.Length) \
                    and e.distToShape(Part.Vertex(mid))[0] <= 1e-7 * max(1.0, edge.Length):
                return "Edge%d%s" % (i + 1, " of " + self.owner if self.owner else "")
        return ""


def outline(face, tolerance=None, frame=None, names=None, owner=""):
    """wrenchd's shape of a planar face (see the module's docstring).

    face: a Part.Face, or a shape whose faces are one planar face, or a
    shape of planar wires (a sketch's): as the DXF reader does, open wires
    and loose edges are left out (listed in `shape.ignored`) while a closed
    wire remains; a wire inside another is its hole, one inside a hole the
    outer boundary of another part; the largest part is taken and the
    others listed in `shape.other_parts`.
    tolerance: how far an approximating arc may be from a curve that is not
    a line or a circle; default DEFAULT_RELATIVE_TOLERANCE times the face's
    bounding-box diagonal.
    frame: a Placement whose XY plane is the face's plane, to write the
    outline in; default as the module's docstring says.
    names, owner: the shape whose edges name the segments' edges ("Edge3")
    and the name of the object it belongs to (for messages); default the
    face itself.

    Raises OutlineError naming what is wrong: not planar, an open wire,
    no face, more vertices than wrenchd takes."""
    shape = face
    ignored, others = [], []
    if not isinstance(shape, Part.Shape) or shape.isNull():
        raise OutlineError("outline() takes a FreeCAD face (Part.Face), not %s"
                           % type(face).__name__)
    faces = shape.Faces
    if len(faces) > 1:
        raise OutlineError("the shape has %d faces: an outline is one planar face" % len(faces))
    if faces:
        the_face = faces[0]
        outer = the_face.OuterWire
        wires = [outer] + [w for w in the_face.Wires if not w.isSame(outer)]
    else:
        the_face = None
        wires = list(shape.Wires)
        loose = [e for e in shape.Edges if not any(w.isSame(e) or any(x.isSame(e) for x in w.Edges)
                                                  for w in wires)]
        if not wires and not loose:
            raise OutlineError("the shape has no face and no wire: nothing to outline")
        # Stray open geometry (open wires, loose edges) is left out and
        # reported while a closed wire remains (the DXF reader's rule).
        closed = [w for w in wires if w.isClosed()]
        if closed:
            for w in wires:
                if not w.isClosed():
                    ignored.append("an open wire of %d edge%s from %s to %s" % (
                        len(w.Edges), "" if len(w.Edges) == 1 else "s",
                        _fmt_point(w.OrderedVertexes[0].Point), _fmt_point(w.OrderedVertexes[-1].Point)))
            for e in loose:
                ignored.append("an edge in no wire at %s" % _fmt_point(e.valueAt(e.FirstParameter)))
            wires = closed
        elif loose:
            raise OutlineError("%d edge%s belong to no wire (the first at %s): close the outline"
                               % (len(loose), "" if len(loose) == 1 else "s",
                                  _fmt_point(loose[0].valueAt(loose[0].FirstParameter))))
    size = shape.BoundBox.DiagonalLength
    if not size > 0:
        raise OutlineError("the shape has no extent")
    namer = _Namer(names if names is not None else (the_face if the_face is not None else shape), owner)

    for w in wires:
        if not w.isClosed():
            a = w.OrderedVertexes[0].Point
            b = w.OrderedVertexes[-1].Point
            raise OutlineError("the wire through %s is open: its ends %s and %s are %s apart"
                               % (", ".join(n for n in (namer(e) for e in w.OrderedEdges[:4]) if n)
                                  or "%d edges" % len(w.Edges),
                                  _fmt_point(a), _fmt_point(b), _fmt(a.distanceToPoint(b))))
    plane = shape.findPlane() if the_face is None else the_face.findPlane()
    if plane is None:
        kind = type(the_face.Surface).__name__ if the_face is not None else "curve"
        raise OutlineError("the %s is not planar (its surface is a %s): an outline is a planar face"
                           % ("face" if the_face is not None else "wire", kind))
    if frame is None:
        frame = _frame_of(plane, shape)
    else:
        frame = FreeCAD.Placement(frame)
        z = frame.Rotation.multVec(Vector(0, 0, 1))
        axis = Vector(plane.Axis)
        axis.normalize()
        off = max(abs(frame.inverse().multVec(v.Point).z) for v in shape.Vertexes)
        if abs(abs(z.dot(axis)) - 1.0) > 1e-9 or off > 1e-7 * size:
            raise OutlineError("the frame given is not the face's plane (%s off it)" % _fmt(off))

    if tolerance is None or tolerance == 0:
        tol = DEFAULT_RELATIVE_TOLERANCE * size
    else:
        tol = float(tolerance)
        if not (math.isfinite(tol) and tol > 0):
            raise OutlineError("the tolerance is a positive length, not %r" % (tolerance,))

    if the_face is None and len(wires) > 1:
        wires, others = _largest_part(wires, size)

    inverse = frame.inverse()

    def to2d(v):
        q = inverse.multVec(v)
        return (q.x, q.y)

    normal = frame.Rotation.multVec(Vector(0, 0, 1))
    loops = []
    approximated = []
    deviation = 0.0
    for i, w in enumerate(wires):
        pieces = []           # (start point, bulge, edge name, exact)
        edges = w.OrderedEdges
        vertexes = w.OrderedVertexes
        n = len(edges)
        for k, e in enumerate(edges):
            if e.Length <= 1e-12 * size:
                continue
            v0 = vertexes[k % len(vertexes)].Point
            v1 = vertexes[(k + 1) % len(vertexes)].Point
            first, last = e.FirstParameter, e.LastParameter
            a, b = e.valueAt(first), e.valueAt(last)
            if n == 1 or e.isClosed():
                forward = True
            else:
                forward = a.distanceToPoint(v0) + b.distanceToPoint(v1) <= \
                    b.distanceToPoint(v0) + a.distanceToPoint(v1)
            u0, u1 = (first, last) if forward else (last, first)
            gap = (e.valueAt(u1)).distanceToPoint(v1)
            if gap > max(1e-7 * size, 10 * max(e.Tolerance, 1e-7)):
                raise OutlineError("the wire is open after %s: its end %s is %s from the next vertex %s"
                                   % (namer(e) or "an edge", _fmt_point(e.valueAt(u1)), _fmt(gap),
                                      _fmt_point(v1)))
            p0, p1 = to2d(v0), to2d(v1)
            name = namer(e)
            kind = _edge_kind(e)
            if kind in ("Line", "LineSegment"):
                pieces.append((p0, 0.0, name, True))
            elif kind == "Circle" and abs(abs(Vector(e.Curve.Axis).normalize().dot(normal)) - 1) <= 1e-12:
                sense = 1.0 if Vector(e.Curve.Axis).dot(normal) > 0 else -1.0
                if not forward:
                    sense = -sense
                sweep = last - first
                count = max(1, int(math.ceil(sweep / math.pi - 1e-9)))
                if e.isClosed():
                    count = max(count, 2)
                bulge = wrenchd_arcs.bulge_of_sweep(sense * sweep / count)
                for m in range(count):
                    if m == 0:
                        p = p0
                    else:
                        p = to2d(e.valueAt(u0 + (u1 - u0) * m / count))
                    pieces.append((p, bulge, name, True))
            else:
                arcs, measured = _approximate(e, u0, u1, p0, p1, frame, tol, size)
                deviation = max(deviation, measured)
                approximated.append({"edge": name, "kind": kind, "arcs": len(arcs),
                                     "deviation": measured})
                for p, bulge in arcs:
                    pieces.append((p, bulge, name, False))
        if len(pieces) < 2:
            raise OutlineError("the wire of %s encloses no area" % (
                ", ".join(n for n in (namer(e) for e in edges) if n) or "%d edges" % n))
        segs = []
        for j, (p, bulge, name, exact) in enumerate(pieces):
            q = pieces[(j + 1) % len(pieces)][0]
            segs.append(Segment(i, j, p, q, bulge, name, exact))
        loops.append(segs)
    count = sum(len(loop) for loop in loops)
    if count > MAX_VERTICES:
        raise OutlineError("the outline has %d vertices, wrenchd takes at most %d%s"
                           % (count, MAX_VERTICES,
                              ": give a larger tolerance (%s now) for the curves approximated by arcs"
                              % _fmt(tol) if approximated else ""))
    result = Outline(loops, frame, tol, deviation, approximated, size)
    result.other_parts, result.ignored = others, ignored
    return result


def _largest_part(wires, size):
    """The closed wires of a shape without a face, as the DXF reader takes
    its loops: a wire inside an odd number of others is a hole of the
    innermost, inside an even number the outer boundary of a part (an
    island in a hole is a part of its own).  Returns the largest part's
    wires (outer first) and the others' descriptions, largest first."""
    def enclosed(w):
        try:
            return abs(Part.Face(w).Area)
        except Part.OCCError:
            return w.BoundBox.DiagonalLength ** 2
    areas = [enclosed(w) for w in wires]
    faces = []
    for w in wires:
        try:
            faces.append(Part.Face(w))
        except Part.OCCError:
            faces.append(None)

    def probe(w):
        e = w.Edges[0]
        return e.valueAt((e.FirstParameter + e.LastParameter) / 2.0)
    inside = [[i for i in range(len(wires)) if i != j and faces[i] is not None and areas[i] > areas[j]
               and faces[i].isInside(probe(wires[j]), 1e-9 * size, True)] for j in range(len(wires))]
    depth = [len(x) for x in inside]
    parts = {j: [] for j in range(len(wires)) if depth[j] % 2 == 0}
    for j in range(len(wires)):
        if depth[j] % 2:
            parts[max(inside[j], key=lambda i: depth[i])].append(j)
    ranked = sorted(parts, key=lambda j: (-(areas[j] - sum(areas[h] for h in parts[j])), j))
    others = []
    for j in ranked[1:]:
        box = wires[j].BoundBox
        others.append("a part of area %s mm^2 with %d hole%s, x %s to %s, y %s to %s, z %s" % (
            _fmt(areas[j] - sum(areas[h] for h in parts[j])), len(parts[j]),
            "" if len(parts[j]) == 1 else "s", _fmt(box.XMin), _fmt(box.XMax), _fmt(box.YMin),
            _fmt(box.YMax), _fmt(box.ZMin)))
    best = ranked[0]
    return [wires[best]] + [wires[h] for h in sorted(parts[best])], others


# ---- curves by arcs ----------------------------------------------------------------

class _EdgeCurve:
    """A FreeCAD edge as wrenchd_arcs.follow takes a curve: its points and
    tangents in the outline's frame, its distance by FreeCAD's distToShape."""

    def __init__(self, edge, frame):
        self.edge, self.frame = edge, frame
        self.inverse = frame.inverse()
        self.rotation = self.inverse.Rotation
        self.closed = edge.isClosed()

    def point(self, u):
        q = self.inverse.multVec(self.edge.valueAt(u))
        return (q.x, q.y)

    def tangent(self, u):
        try:
            d = self.rotation.multVec(self.edge.tangentAt(u))
        except Part.OCCError:
            return None
        return (d.x, d.y) if math.hypot(d.x, d.y) > 0.5 else None

    def distance(self, p, a, b):
        vertex = Part.Vertex(self.frame.multVec(Vector(p[0], p[1], 0.0)))
        return self.edge.distToShape(vertex)[0]

    def kinks(self, u0, u1):
        """A B-spline's knots of multiplicity at least its degree, strictly
        between u0 and u1: where the curve may have a corner."""
        curve = self.edge.Curve
        if type(curve).__name__ != "BSplineCurve":
            return []
        lo, hi = min(u0, u1), max(u0, u1)
        margin = 1e-12 * (hi - lo)
        return [k for k, m in zip(curve.getKnots(), curve.getMultiplicities())
                if m >= curve.Degree and lo + margin < k < hi - margin]


def _approximate(edge, u0, u1, p0, p1, frame, tolerance, size):
    """Arcs [(start point, bulge)] from p0 to p1 (p1 not included) along the
    edge from parameter u0 to u1, within `tolerance` of it, and the largest
    distance measured between them both ways (wrenchd_arcs.follow)."""
    try:
        return wrenchd_arcs.follow(_EdgeCurve(edge, frame), u0, u1, p0, p1, tolerance, size,
                                   _edge_kind(edge))
    except wrenchd_arcs.ArcFitError as error:
        raise OutlineError(str(error)) from None
