"""outline(): FreeCAD faces as wrenchd's outline, held against FreeCAD's own
geometry.

The mass properties wrenchd computes from the outline (fixture.put's area,
centre of mass and inertia, at unit density: mass = area) must be FreeCAD's
(face.Area, face.CenterOfMass, face.MatrixOfInertia) -- to rounding where
every edge is a line or a circle, and within what the stated tolerance
allows where curves are followed by arcs.  The arcs are rebuilt here from
the vertices and bulges alone (through each arc's midpoint, by the sagitta),
not by wrench_freecad's code, and measured against FreeCAD's edges with
FreeCAD's distToShape."""

import math

import FreeCAD
import Part
import pytest
from FreeCAD import Vector as V

import parts
import wrench_freecad as wf
from wrench_freecad import OutlineError, outline


def put_unit_density(client, shape):
    """fixture.put of the outline at unit density, one fixel on it."""
    first = shape["loops"][0]
    a, b = first[0], first[1]
    at = [(a[0] + b[0]) / 2.0, (a[1] + b[1]) / 2.0]
    if len(a) > 2:           # on an arc: its midpoint, by the sagitta
        dx, dy = b[0] - a[0], b[1] - a[1]
        at = [at[0] + dy * a[2] / 2.0, at[1] - dx * a[2] / 2.0]
    return client.put_fixture({"body": {"mass": 1.0, "shape": shape},
                               "friction": {"static": 0.3}, "fixels": [{"at": at}]})


def assert_mass_properties(client, face, shape, rel):
    """wrenchd's area, centre of mass and inertia of the outline are FreeCAD's
    of the face, to `rel` of the area, of the size and of the polar moment."""
    put = put_unit_density(client, shape)
    area, com, polar = parts.mass_properties(face, shape)
    size = face.BoundBox.DiagonalLength
    assert put.area == pytest.approx(area, rel=rel)
    assert math.hypot(put.com[0] - com[0], put.com[1] - com[1]) <= rel * size
    assert put.inertia == pytest.approx(polar, rel=rel)   # mass 1: I is the polar moment / area
    # and the centre of mass mapped back is FreeCAD's, in the document
    assert shape.to_3d(put.com).distanceToPoint(face.CenterOfMass) <= rel * size
    return put


def rebuilt_edges(shape):
    """The outline's segments as FreeCAD edges, from the vertices and bulges
    alone: a line, or the arc through its ends and its midpoint (the chord's
    midpoint moved off the chord by the sagitta, bulge x chord / 2, to the
    right of the chord for a counter-clockwise arc)."""
    edges = []
    for loop in shape["loops"]:
        for j, v in enumerate(loop):
            w = loop[(j + 1) % len(loop)]
            p, q = shape.to_3d(v[:2]), shape.to_3d(w[:2])
            bulge = v[2] if len(v) > 2 else 0.0
            if bulge == 0.0:
                edges.append(Part.LineSegment(p, q).toShape())
            else:
                dx, dy = w[0] - v[0], w[1] - v[1]
                mid = ((v[0] + w[0]) / 2.0 + dy * bulge / 2.0, (v[1] + w[1]) / 2.0 - dx * bulge / 2.0)
                edges.append(Part.Arc(p, shape.to_3d(mid), q).toShape())
    return edges


def test_filleted_plate_with_a_hole(client):
    """The top face of a plate with filleted corners and a locating hole: four
    lines and four quarter circles, then the hole as two half circles; its
    mass properties are FreeCAD's to rounding."""
    plate = parts.filleted_plate()
    face = plate.Faces[parts.face_at(plate, V(0, 0, 1), 10)]
    shape = outline(face)
    assert shape["type"] == "outline" and len(shape["loops"]) == 2
    outer, hole = shape.segments
    assert sorted(s.is_arc for s in outer) == [False] * 4 + [True] * 4
    for s in outer:
        if s.is_arc:
            assert abs(s.bulge) == pytest.approx(math.tan(math.pi / 8), rel=1e-12)
            assert s.radius == pytest.approx(8.0, rel=1e-12)
    assert [abs(s.bulge) for s in hole] == [pytest.approx(1.0, rel=1e-12)] * 2
    assert all(s.radius == pytest.approx(6.0, rel=1e-12) for s in hole)
    # the outer loop is the outer wire: its box is the face's
    xs = [v[0] for v in shape["loops"][0]]
    assert min(xs) == pytest.approx(0.0, abs=1e-12) and max(xs) == pytest.approx(120.0, rel=1e-15)
    assert shape.deviation == 0.0 and shape.approximated == []
    # the document's x and y, at the face's z
    assert shape.frame.Base == V(0, 0, 10) and shape.frame.Rotation.isIdentity()
    assert_mass_properties(client, face, shape, 1e-12)
    # every segment lies on the face's boundary, by FreeCAD's measure
    wires = Part.Compound(face.Wires)
    for e in rebuilt_edges(shape):
        for t in (0.1, 0.5, 0.9):
            p = e.valueAt(e.FirstParameter + t * (e.LastParameter - e.FirstParameter))
            assert wires.distToShape(Part.Vertex(p))[0] <= 1e-9 * face.BoundBox.DiagonalLength


def placements():
    """Orientations of the L bracket: in XY planes at several z, turned about
    z, upside down, and in planes tilted every way."""
    R = FreeCAD.Rotation
    return [
        ("xy", FreeCAD.Placement()),
        ("xy turned, z -4.5", FreeCAD.Placement(V(13, -7, -4.5), R(V(0, 0, 1), 33))),
        ("upside down", FreeCAD.Placement(V(0, 0, 20), R(V(1, 0, 0), 180))),
        ("tilted", FreeCAD.Placement(V(5, -7, 11), R(V(1, 2, 3), 37))),
        ("standing", FreeCAD.Placement(V(-40, 2, 0), R(V(0, 1, 0), 90))),
        ("skew", FreeCAD.Placement(V(1e3, 2e3, -3e3), R(0.3, -1.1, 2.2))),
    ]


@pytest.mark.parametrize("name,placement", placements(), ids=[p[0] for p in placements()])
@pytest.mark.parametrize("side", ["top", "bottom"])
def test_slotted_bracket_in_any_plane(client, name, placement, side):
    """The slotted L bracket (an inner fillet, a slot with round ends, a hole)
    placed every way: each of its two large faces, whatever its plane,
    gives FreeCAD's mass properties, and the outline's vertices sit on the
    face's boundary in the document."""
    solid = parts.l_bracket()
    solid.Placement = placement
    normal = placement.Rotation.multVec(V(0, 0, 1 if side == "top" else -1))
    base = placement.multVec(V(0, 0, 6 if side == "top" else 0))
    face = solid.Faces[parts.face_at(solid, normal, base.dot(normal))]
    shape = outline(face)
    assert len(shape["loops"]) == 3                   # the L, the slot, the hole
    assert_mass_properties(client, face, shape, 1e-11)
    size = face.BoundBox.DiagonalLength
    wires = Part.Compound(face.Wires)
    for loop in shape["loops"]:
        for v in loop:
            p = shape.to_3d(v[:2])
            assert wires.distToShape(Part.Vertex(p))[0] <= 1e-9 * size
    # a face in a plane z = const is written in the document's x and y: a
    # vertex (x, y) is the document's point (x, y, z)
    if abs(abs(normal.z) - 1) < 1e-12:
        assert shape.frame.Rotation.isIdentity()
        assert shape.frame.Base == V(0, 0, shape.frame.Base.z)
        assert shape.frame.Base.z == pytest.approx(base.z, abs=1e-12)
        corners = {(v.Point.x, v.Point.y) for v in face.Vertexes}
        assert corners <= {(v[0], v[1]) for loop in shape["loops"] for v in loop}


def test_sketch(client, doc):
    """A closed sketch (tangent arcs at two corners and a hole): its outline
    is that of FreeCAD's face of its wires."""
    sketch = parts.sketch_part(doc)
    shape = outline(sketch.Shape)
    face = parts.sketch_face(sketch)
    assert len(shape["loops"]) == 2
    assert_mass_properties(client, face, shape, 1e-12)


def test_curves_followed_by_arcs_within_the_tolerance(client):
    """A B-spline side and an ellipse hole are followed by tangent arcs within
    the stated tolerance (1e-5 of the face's diagonal by default), the full
    circle hole is exact.  Measured here with FreeCAD's distToShape, both
    ways, on arcs rebuilt from the bulges; the area differs from FreeCAD's
    by at most the deviation times the curves' length."""
    face = parts.curved_face()
    size = face.BoundBox.DiagonalLength
    for tolerance in (None, 1e-3, 0.05):
        shape = outline(face, tolerance=tolerance)
        stated = 1e-5 * size if tolerance is None else tolerance
        assert shape.tolerance == pytest.approx(stated, rel=1e-15)
        assert 0 < shape.deviation <= stated
        kinds = sorted(a["kind"] for a in shape.approximated)
        assert kinds == ["BSplineCurve", "Ellipse"]
        rebuilt = rebuilt_edges(shape)
        approximating = [e for e, s in zip(rebuilt, [s for loop in shape.segments for s in loop])
                         if not s.exact]
        compound = Part.Compound(approximating)
        curved = [e for e in face.Edges if type(e.Curve).__name__ in ("BSplineCurve", "Ellipse")]
        worst = 0.0
        for e in curved:
            for k in range(201):
                p = e.valueAt(e.FirstParameter + (e.LastParameter - e.FirstParameter) * k / 200)
                worst = max(worst, compound.distToShape(Part.Vertex(p))[0])
        curves = Part.Compound(curved)
        for e in approximating:
            for k in range(1, 8):
                p = e.valueAt(e.FirstParameter + (e.LastParameter - e.FirstParameter) * k / 8)
                worst = max(worst, curves.distToShape(Part.Vertex(p))[0])
        assert worst <= stated * (1 + 1e-6)
        # the deviation stated is measured, not a guess: near what FreeCAD finds
        assert 0.9 * worst <= shape.deviation <= stated
        # the arcs meet tangentially: each joint turns by rounding only
        segs = [s for loop in shape.segments for s in loop]
        for a, b in zip(segs, segs[1:]):
            if not a.exact and not b.exact and a.loop == b.loop and a.edge == b.edge:
                ta, tb = a.tangent(1.0), b.tangent(0.0)
                assert abs(math.atan2(ta[0] * tb[1] - ta[1] * tb[0], ta[0] * tb[0] + ta[1] * tb[1])) < 1e-6
        # the full circle is exact: two half circles of radius 5
        circle = [loop for loop in shape.segments if all(s.exact for s in loop) and len(loop) == 2]
        assert len(circle) == 1 and all(s.radius == pytest.approx(5, rel=1e-12) for s in circle[0])
        put = put_unit_density(client, shape)
        length = sum(e.Length for e in curved)
        assert abs(put.area - face.Area) <= shape.deviation * length
        assert abs(put.area - parts.sampled_area(face)) <= shape.deviation * length + 1e-6 * face.Area
        # a tighter tolerance takes more arcs
        if tolerance == 1e-3:
            fine = sum(a["arcs"] for a in shape.approximated)
        if tolerance == 0.05:
            assert sum(a["arcs"] for a in shape.approximated) < fine


def test_a_closed_bspline_hole(client):
    """A hole bounded by one periodic B-spline: followed by arcs within the
    tolerance; its area, against the area of FreeCAD's own samples of the
    wires (FreeCAD 0.20's face.Area of it is off by about 2e-4 of itself,
    more than the arcs are: the samples are the reference)."""
    spline = Part.BSplineCurve()
    spline.interpolate([V(100, 20, 0), V(120, 30, 0), V(110, 60, 0), V(90, 40, 0)],
                       PeriodicFlag=True)
    plate = Part.Face(Part.makePolygon([V(0, 0, 0), V(200, 0, 0), V(200, 100, 0), V(0, 100, 0),
                                        V(0, 0, 0)]))
    face = plate.cut(Part.Face(Part.Wire(spline.toShape()))).Faces[0]
    for tolerance in (None, 1e-4):
        shape = outline(face, tolerance=tolerance)
        assert [a["kind"] for a in shape.approximated] == ["BSplineCurve"]
        assert shape.deviation <= shape.tolerance
        put = put_unit_density(client, shape)
        length = spline.toShape().Length
        reference = parts.sampled_area(face)
        # the samples' own error: a chord's sagitta, below 1e-6 of the area here
        assert abs(put.area - reference) <= shape.deviation * length + 1e-6 * reference


def test_bsplines_that_are_lines_and_circles(client):
    """A B-spline that is straight becomes one line, one that is a circle's
    quarter one arc of that circle: the part is then exactly a quarter disc
    of radius 30 on a 30 x 30 square (area 900 + 225 pi)."""
    r = 30.0
    # the rational quadratic B-spline of a quarter circle, exact (weights 1,
    # sqrt(2)/2, 1 on the corners of its square)
    quarter = Part.BSplineCurve()
    quarter.buildFromPolesMultsKnots([V(60, 30, 0), V(60, 60, 0), V(30, 60, 0)], [3, 3], [0, 1],
                                     False, 2, [1, math.sqrt(0.5), 1])
    straight = Part.LineSegment(V(0, 0, 0), V(60, 0, 0)).toBSpline()
    wire = Part.Wire(Part.__sortEdges__([
        straight.toShape(), Part.LineSegment(V(60, 0, 0), V(60, 30, 0)).toShape(),
        quarter.toShape(), Part.LineSegment(V(30, 60, 0), V(0, 60, 0)).toShape(),
        Part.LineSegment(V(0, 60, 0), V(0, 0, 0)).toShape()]))
    face = Part.Face(wire)
    shape = outline(face)
    assert sorted(a["kind"] for a in shape.approximated) == ["BSplineCurve", "BSplineCurve"]
    assert [a["arcs"] for a in shape.approximated] == [1, 1]
    (loop,) = shape.segments
    arcs = [s for s in loop if s.is_arc]
    assert len(loop) == 5 and len(arcs) == 1
    assert arcs[0].radius == pytest.approx(r, rel=1e-9)
    assert abs(arcs[0].sweep) == pytest.approx(math.pi / 2, rel=1e-9)
    put = put_unit_density(client, shape)
    assert put.area == pytest.approx(3600 - 900 + math.pi * r * r / 4, rel=1e-9)


def test_bsplines_with_corners(client):
    """A B-spline with corners (knots of multiplicity at least its degree) is
    followed piece by piece: a polyline of degree 1 becomes its own lines,
    a cubic with a corner stays within the tolerance, in few arcs."""
    poles = [V(0, 0, 0), V(20, 5, 0), V(40, 0, 0), V(60, 8, 0), V(80, 0, 0)]
    polyline = Part.BSplineCurve()
    polyline.buildFromPoles(poles, False, 1)
    wire = Part.Wire([polyline.toShape(), Part.LineSegment(V(80, 0, 0), V(80, 40, 0)).toShape(),
                      Part.LineSegment(V(80, 40, 0), V(0, 40, 0)).toShape(),
                      Part.LineSegment(V(0, 40, 0), V(0, 0, 0)).toShape()])
    shape = outline(Part.Face(wire))
    assert sorted((v[0], v[1]) for v in shape["loops"][0]) == \
        sorted([(p.x, p.y) for p in poles] + [(80, 40), (0, 40)])
    assert all(len(v) == 2 for v in shape["loops"][0])          # lines only
    put = put_unit_density(client, shape)
    polygon = [(p.x, p.y) for p in poles] + [(80, 40), (0, 40)]
    area = 0.5 * abs(sum(polygon[k][0] * polygon[k - 1][1] - polygon[k - 1][0] * polygon[k][1]
                         for k in range(len(polygon))))
    assert put.area == pytest.approx(area, rel=1e-12)
    cubic = Part.BSplineCurve()
    cubic.buildFromPolesMultsKnots([V(0, 0, 0), V(10, 10, 0), V(20, 10, 0), V(30, 0, 0),
                                    V(40, 10, 0), V(50, 10, 0), V(60, 0, 0)],
                                   [4, 3, 4], [0, 1, 2], False, 3)
    wire = Part.Wire([cubic.toShape(), Part.LineSegment(V(60, 0, 0), V(60, -30, 0)).toShape(),
                      Part.LineSegment(V(60, -30, 0), V(0, -30, 0)).toShape(),
                      Part.LineSegment(V(0, -30, 0), V(0, 0, 0)).toShape()])
    face = Part.Face(wire)
    shape = outline(face)
    (curve,) = shape.approximated
    assert curve["arcs"] < 200 and shape.deviation <= shape.tolerance
    assert [30.0, 0.0] in [v[:2] for v in shape["loops"][0]]     # the corner is a vertex
    put = put_unit_density(client, shape)
    assert abs(put.area - parts.sampled_area(face)) <= \
        shape.deviation * cubic.toShape().Length + 1e-6 * face.Area


def test_ellipse_alone_and_offset_plane(client):
    """A whole ellipse (one closed edge, no line at all) in a tilted plane."""
    ellipse = Part.Face(Part.Wire(Part.Ellipse(V(0, 0, 0), 40, 15).toShape()))
    ellipse.Placement = FreeCAD.Placement(V(3, 4, 5), FreeCAD.Rotation(V(1, 1, 0), 50))
    shape = outline(ellipse, tolerance=1e-3)
    assert len(shape["loops"]) == 1 and shape.deviation <= 1e-3
    put = put_unit_density(client, shape)
    area, com, polar = parts.mass_properties(ellipse, shape)
    assert abs(put.area - area) <= 1e-3 * ellipse.Edges[0].Length
    assert put.inertia == pytest.approx(polar, rel=1e-4)
    assert math.hypot(put.com[0] - com[0], put.com[1] - com[1]) <= 1e-3


def test_refusals(doc):
    """What outline() refuses, and how it says so."""
    cylinder = Part.makeCylinder(5, 10)
    side = [f for f in cylinder.Faces if f.findPlane() is None][0]
    with pytest.raises(OutlineError, match="not planar.*Cylinder"):
        outline(side)
    with pytest.raises(OutlineError, match="has 3 faces"):
        outline(cylinder)
    open_wire = Part.Wire([Part.LineSegment(V(0, 0, 0), V(10, 0, 0)).toShape(),
                           Part.LineSegment(V(10, 0, 0), V(10, 10, 0)).toShape()])
    with pytest.raises(OutlineError, match=r"open: its ends \(0, 0, 0\) and \(10, 10, 0\) are 14.1421 apart"):
        outline(open_wire)
    with pytest.raises(OutlineError, match="tolerance is a positive length"):
        outline(parts.curved_face(), tolerance=-1)
    with pytest.raises(OutlineError, match="takes a FreeCAD face"):
        outline("Face1")
    # too fine a tolerance for wrenchd's 4096 vertices
    with pytest.raises(OutlineError, match="wrenchd takes at most 4096|larger tolerance"):
        outline(parts.curved_face(), tolerance=1e-9)


def test_a_sketch_of_several_parts_and_stray_lines(client):
    """A shape of wires as a sketch holds them, read by the DXF reader's
    rules: a plate with a bore, a washer drawn in the bore (a part of its
    own), a small tab, an open construction line and a loose edge.  The
    largest part is taken, its area FreeCAD's own; the others are listed
    with their areas, the open geometry left out and listed."""
    def rect(x0, y0, x1, y1):
        return Part.makePolygon([V(x0, y0, 0), V(x1, y0, 0), V(x1, y1, 0), V(x0, y1, 0), V(x0, y0, 0)])

    def circle(x, y, r):
        return Part.Wire(Part.makeCircle(r, V(x, y, 0)))
    plate, bore = rect(0, 0, 100, 60), circle(40, 30, 20)
    washer, washer_hole = circle(40, 30, 15), circle(40, 30, 7)
    tab = rect(120, 0, 150, 20)
    construction = Part.Wire([Part.LineSegment(V(-10, 70, 0), V(160, 70, 0)).toShape(),
                              Part.LineSegment(V(160, 70, 0), V(160, 80, 0)).toShape()])
    loose = Part.LineSegment(V(0, -10, 0), V(50, -10, 0)).toShape()
    compound = Part.Compound([tab, washer_hole, construction, washer, plate, loose, bore])
    shape = outline(compound)
    assert len(shape["loops"]) == 2                       # the plate and its bore
    want = Part.Face(plate).Area - Part.Face(bore).Area   # FreeCAD's areas
    put = put_unit_density(client, shape)
    assert put.area == pytest.approx(want, rel=1e-12)
    washer_area = Part.Face(washer).Area - Part.Face(washer_hole).Area
    assert len(shape.other_parts) == 2
    # largest first: the tab (600), the washer (553)
    assert shape.other_parts[0].startswith("a part of area 600 mm^2 with 0 holes, x 120 to 150")
    assert shape.other_parts[1].startswith("a part of area %s mm^2 with 1 hole, x 25 to 55" % wf._fmt(washer_area))
    assert len(shape.ignored) == 2
    assert "an open wire of 2 edges" in shape.ignored[0]
    assert shape.ignored[1] == "an edge in no wire at (0, -10, 0)"
    # nothing closed: refused as before
    with pytest.raises(OutlineError, match="open"):
        outline(Part.Compound([construction]))


def test_the_dxf_reader_and_the_workbench_follow_curves_alike(tmp_path):
    """One ellipse and one B-spline, as FreeCAD edges and as DXF entities
    (written with ezdxf, read by wrenchd_dxf): both are followed by
    wrenchd_arcs.follow, to the same tolerance, and their areas agree with
    the closed forms: the ellipse's pi a b, the B-spline's by ezdxf's
    flattening."""
    ezdxf = pytest.importorskip("ezdxf")
    import wrenchd_dxf
    tol = 1e-3
    # the ellipse: centre (10, 5), semi-axes 30 and 12, its major axis along x
    doc = ezdxf.new("R2010")
    msp = doc.modelspace()
    msp.add_ellipse((10, 5), major_axis=(30, 0, 0), ratio=0.4)
    # a closed B-spline of degree 3 through its control points, clamped, as both write it
    poles = [(60, 0), (100, -10), (120, 20), (95, 45), (70, 30), (60, 0)]
    msp.add_open_spline(poles, degree=3)
    path = str(tmp_path / "curves.dxf")
    doc.saveas(path)
    parts, report = wrenchd_dxf.read_dxf(path, curve_tolerance=tol)
    assert len(parts) == 2 and len(report["curves"]) == 2

    ellipse = Part.Face(Part.Wire(Part.Ellipse(V(10, 5, 0), 30, 12).toShape()))
    spline = Part.BSplineCurve()
    spline.buildFromPolesMultsKnots([V(x, y, 0) for x, y in poles], [4, 1, 1, 4], [0, 1 / 3, 2 / 3, 1],
                                    False, 3)
    spline_face = Part.Face(Part.Wire(spline.toShape()))
    # the B-spline's area by ezdxf's flattening (FreeCAD 0.20's face.Area of
    # a B-spline face is off by 2e-4: test_a_closed_bspline_hole)
    flat = [(v.x, v.y) for v in msp.query("SPLINE")[0].flattening(1e-6)]
    flat_area = abs(sum(a[0] * b[1] - b[0] * a[1] for a, b in zip(flat, flat[1:] + flat[:1]))) / 2
    for face, want in ((ellipse, math.pi * 30 * 12), (spline_face, flat_area)):
        shape = outline(face, tolerance=tol)
        got = [p for p in parts if abs(p["extent"][0] - face.BoundBox.XMin) < 1e-2][0]
        perimeter = face.OuterWire.Length
        # each within tol of the curve: the areas within tol x the perimeter
        assert abs(got["area"] - want) <= tol * perimeter, (got["area"], want)
        assert abs(abs(wf.wrenchd_arcs.loop_area([tuple(v) + (0.0,) * (3 - len(v))
                                                  for v in shape["loops"][0]])) - want) <= tol * perimeter
