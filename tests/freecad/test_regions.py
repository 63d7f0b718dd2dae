"""Push regions, fixels, the best push and the gravity dial as FreeCAD
objects, against FreeCAD's own measures of them and against wrenchd asked
directly.

Where a region is, is checked twice over: its object's Shape lies on the
face's boundary (FreeCAD's distToShape), and a push there along FreeCAD's
inward normal (the face's normal crossed with the edge's tangent, turned
into the face by face.isInside) is inside the set, while a push at any
other sampled point of the boundary is not."""

import json
import math

import FreeCAD
import Part
import pytest
from FreeCAD import Vector as V

import parts
import wrench_freecad as wf

# examples/bracket.json's fixels: a pin in the hole, a locator under the
# part, one to its left; on the bracket's face at z = 1.
HOLE_PIN = V(30 - 6 * math.sqrt(0.5), 30 + 6 * math.sqrt(0.5), 1)
BRACKET_FIXELS = [HOLE_PIN, V(100, 0, 1), V(0, 40, 1)]


def inward_normal(face, p):
    """FreeCAD's inward normal of the face's boundary at p: the face's normal
    crossed with the tangent of the edge there, into the face."""
    size = face.BoundBox.DiagonalLength
    edge = min(face.Edges, key=lambda e: e.distToShape(Part.Vertex(p))[0])
    u = edge.Curve.parameter(p)
    t = edge.tangentAt(u)
    n = face.normalAt(*face.Surface.parameter(p)).cross(t)
    n.normalize()
    if not face.isInside(p + n * (1e-4 * size), 1e-9 * size, True):
        n = -n
    assert face.isInside(p + n * (1e-4 * size), 1e-9 * size, True)
    return n


def push(p, n, frame=None):
    """A push at document point p along n, as a wrench in the outline's
    coordinates: for a face in an XY plane the document's x and y, else
    those of `frame` (a sketch's own placement)."""
    if frame is not None:
        inverse = frame.inverse()
        p, n = inverse.multVec(p), inverse.Rotation.multVec(n)
    return {"force": [n.x, n.y], "at": [p.x, p.y]}


def boundary_samples(face, per_edge=24):
    """Points of the face's boundary, evenly along each edge, ends left out."""
    out = []
    for e in face.Edges:
        for k in range(1, per_edge):
            out.append(e.valueAt(e.FirstParameter + (e.LastParameter - e.FirstParameter) * k / per_edge))
    return out


def check_regions(client, fixture, regions, which, face, frame=None, every_loop=False):
    """The region objects of one set, held against FreeCAD and wrenchd.  The
    finger is a point: it pushes on the face's outer wire only (the
    clients' default, docs/PROTOCOL.md push_on), so only there is every
    other sampled point not inside; every_loop: on every wire (PushOn all)."""
    size = face.BoundBox.DiagonalLength
    answer = client.push_regions(fixture.FixtureId, which,
                                 push_on="all" if every_loop else None)
    assert len(regions) == len(answer.regions)
    # lengths: FreeCAD's Shape.Length of each object, summed, is push.regions' total
    total = sum(r.Shape.Length for r in regions)
    assert total == pytest.approx(answer.total_length, rel=1e-9)
    wires = Part.Compound(face.Wires)
    inside = []
    for r, a in zip(regions, answer.regions):
        assert r.Set == which and r.Meaning == wf.MEANING[which]
        assert r.Shape.Length == pytest.approx(a.length, rel=1e-9)
        assert (r.Loop, r.Segment, r.T0, r.T1) == (a.loop, a.segment, a.t0, a.t1)
        # on the face's boundary, from From to To
        e = r.Shape.Edges[0]
        for k in range(5):
            p = e.valueAt(e.FirstParameter + (e.LastParameter - e.FirstParameter) * k / 4)
            assert wires.distToShape(Part.Vertex(p))[0] <= 1e-9 * size
        ends = [v.Point for v in r.Shape.Vertexes]
        assert min(ends[0].distanceToPoint(r.From), ends[-1].distanceToPoint(r.From)) <= 1e-9 * size
        assert min(ends[0].distanceToPoint(r.To), ends[-1].distanceToPoint(r.To)) <= 1e-9 * size
        mid = e.valueAt((e.FirstParameter + e.LastParameter) / 2)
        inside.append(push(mid, inward_normal(face, mid), frame))
        # the edge named is the part's edge under the region
        if r.Edge:
            part = fixture.Source[0]
            named = part.Shape.Edges[int(r.Edge.split()[0][4:]) - 1]
            assert named.distToShape(Part.Vertex(mid))[0] <= 1e-9 * size
    if inside:
        for verdicts in client.classify(fixture.FixtureId, inside, sets=[which]):
            assert verdicts[which].inside and verdicts[which].margin > 0
    # every other sampled point of the boundary: not inside
    shapes = Part.Compound([r.Shape for r in regions]) if regions else None
    outer = face.OuterWire
    outside = [p for p in boundary_samples(face)
               if (shapes is None or shapes.distToShape(Part.Vertex(p))[0] > 1e-6 * size)
               and (every_loop or outer.distToShape(Part.Vertex(p))[0] <= 1e-9 * size)]
    verdicts = client.classify(fixture.FixtureId,
                               [push(p, inward_normal(face, p), frame) for p in outside], sets=[which])
    assert len(outside) > 60
    assert not any(v[which].inside for v in verdicts)
    return answer


def test_show_regions_on_the_bracket(client, doc):
    """show_regions on the bracket's face for every set: one object per
    region, each a line or an arc of the outline, with wrenchd's numbers;
    both is what to push with and let go, and the objects say so."""
    face = parts.bracket_face()
    totals = {}
    for which in wf.SETS:
        regions = wf.show_regions(doc, face, BRACKET_FIXELS, 0.25, which, client)
        fixture = regions[0].Regions.Fixture if regions else None
        assert fixture is not None, "the bracket has %s regions" % which
        parent = regions[0].Regions
        assert parent.Count == len(regions) and parent.Meaning == wf.MEANING[which]
        assert wf.SHORT_MEANING[which] in parent.Label
        answer = check_regions(client, fixture, regions, which, face)
        totals[which] = answer.total_length
        assert parent.TotalLength == answer.total_length
    # a face given alone is held by a Part::Feature the fixture links
    parts_made = [o for o in doc.Objects if o.TypeId == "Part::Feature"]
    assert len(parts_made) == 1
    fixtures = [o for o in doc.Objects if wf._is(o, "WrenchFixture")]
    assert len(fixtures) == 3 and all(f.Source[0] == parts_made[0] for f in fixtures)
    # the README's figures for this part: both is 39.4847 long on every
    # loop (push --push-on all), 31.7654 of it on the top edge, the outer
    # boundary a point finger pushes on
    assert totals["both"] == pytest.approx(31.765419, abs=1e-4)
    assert totals["both"] <= min(totals["goal"], totals["strong"]) + 1e-9
    assert "push here and let go" in wf.MEANING["both"]
    assert "use both" in wf.MEANING["goal"] and "use both" in wf.MEANING["strong"]


def test_push_on_every_loop(client, doc):
    """PushOn: empty pushes where the clients' default does (a point finger:
    the outer boundary only, and the report view says the holes are left
    out and how to take them); all adds the hole and the slot, and the
    regions then hold against FreeCAD's boundary and wrench.classify on
    every wire; a finger 2 across reaches both holes by default; a loop the
    outline lacks is refused naming PushOn."""
    face = parts.bracket_face()
    regions = wf.show_regions(doc, face, BRACKET_FIXELS, 0.25, "both", client)
    parent = regions[0].Regions
    fixture = parent.Fixture
    assert list(parent.PushOnLoops) == [0] and set(r.Loop for r in regions) == {0}
    said = wf.describe_push_on([0], json.loads(fixture.FixtureJson)["body"], 0.0, False)
    assert "not on holes 1, 2" in said and "PushOn to all" in said
    # every loop: the hole (loop 1) and the slot (loop 2) as FreeCAD sees them
    every = wf.make_regions(fixture, "both", "all")
    doc.recompute()
    shown = [o for o in doc.Objects if wf._is(o, "WrenchRegion") and o.Regions == every]
    assert list(every.PushOnLoops) == [0, 1, 2] and len(shown) == every.Count
    answer = check_regions(client, fixture, shown, "both", face, every_loop=True)
    assert any(r.Loop > 0 for r in shown)
    # on the holes: the regions whose ends lie on the hole's and the slot's wires
    holes = Part.Compound([w for w in face.Wires if not w.isSame(face.OuterWire)])
    for r in shown:
        on_hole = holes.distToShape(Part.Vertex(r.From))[0] <= 1e-9 * face.BoundBox.DiagonalLength
        assert on_hole == (r.Loop > 0)
    assert answer.total_length > parent.TotalLength
    # the README's figure on every loop, push --push-on all
    assert every.TotalLength == pytest.approx(39.4847, abs=1e-4)
    # a list of loops: the outer boundary and the hole
    some = wf.make_regions(fixture, "both", [0, 1])
    doc.recompute()
    assert list(some.PushOnLoops) == [0, 1] and set(some.RegionLoops) <= {0, 1}
    # a finger 2 across is narrower than the hole (12) and the slot (10)
    parent.FingerRadius = 1.0
    doc.recompute()
    assert list(parent.PushOnLoops) == [0, 1, 2]
    with pytest.raises(wf.OutlineError, match="PushOn: loop 3"):
        wf.push_on_of("0, 3", json.loads(fixture.FixtureJson)["body"], 0.0)
    with pytest.raises(wf.OutlineError, match="PushOn"):
        wf.push_on_of("inner", json.loads(fixture.FixtureJson)["body"], 0.0)


def test_regions_follow_the_part(client, doc):
    """A parametric plate (Box, Fillet, Cylinder, Cut): the fixture links its
    top face; when the box grows and the hole moves, a recompute gives the
    new face's outline (FreeCAD's new area) and new regions, each checked
    as above."""
    plate = parts.parametric_plate(doc)
    top = "Face%d" % (parts.face_at(plate.Shape, V(0, 0, 1), 10) + 1)
    fixels = [V(30 - 6 * math.sqrt(0.5), 30 + 6 * math.sqrt(0.5), 10), V(100, 0, 10),
              V(0, 40, 10)]
    fixture = wf.make_fixture(doc, (plate, top), fixels, (0.25, 0.2), socket=client.socket_path)
    goal, both = wf.make_regions(fixture, "goal"), wf.make_regions(fixture, "both")
    doc.recompute()
    face = plate.Shape.getElement(top)
    assert fixture.Area == pytest.approx(face.Area, rel=1e-12)
    before = {}
    for parent in (goal, both):
        regions = wf.region_objects(parent)
        check_regions(client, fixture, regions, parent.Set, face)
        before[parent.Set] = parent.TotalLength
    old_id = fixture.FixtureId

    box = doc.getObject("Box")
    box.Length = 150
    hole = doc.getObject("Hole")
    hole.Placement = FreeCAD.Placement(V(36, 30, 0), FreeCAD.Rotation())
    doc.recompute()
    fixture.FixelPoints = [V(36 - 6 * math.sqrt(0.5), 30 + 6 * math.sqrt(0.5), 10), V(100, 0, 10),
                           V(0, 40, 10)]
    doc.recompute()
    assert top == "Face%d" % (parts.face_at(plate.Shape, V(0, 0, 1), 10) + 1)
    face = plate.Shape.getElement(top)
    assert face.BoundBox.XMax == pytest.approx(150)
    assert fixture.FixtureId != old_id
    assert fixture.Area == pytest.approx(face.Area, rel=1e-12)
    assert fixture.CenterOfMass.distanceToPoint(face.CenterOfMass) <= 1e-9 * 150
    for parent in (goal, both):
        assert "Invalid" not in parent.State and "Touched" not in parent.State
        regions = wf.region_objects(parent)
        check_regions(client, fixture, regions, parent.Set, face)
        assert parent.TotalLength != pytest.approx(before[parent.Set], rel=1e-6)


def test_regions_follow_a_sketch(client, doc):
    """A fixture on a sketch: changing a constraint (the length, the hole's
    radius) and recomputing gives the new outline and regions."""
    sketch = parts.sketch_part(doc)
    fixels = [V(20, 0, 0), V(60, 0, 0), V(0, 25, 0)]
    fixture = wf.make_fixture(doc, sketch, fixels, 0.2, socket=client.socket_path)
    regions = wf.make_regions(fixture, "strong")
    doc.recompute()
    face = parts.sketch_face(sketch)
    assert fixture.Area == pytest.approx(face.Area, rel=1e-12)
    check_regions(client, fixture, wf.region_objects(regions), "strong", face)
    first = regions.TotalLength
    sketch.setDatum("Length", FreeCAD.Units.Quantity("110 mm"))
    sketch.setDatum("HoleRadius", FreeCAD.Units.Quantity("7 mm"))
    doc.recompute()
    face = parts.sketch_face(sketch)
    assert face.BoundBox.XMax == pytest.approx(110)
    assert fixture.Area == pytest.approx(face.Area, rel=1e-12)
    check_regions(client, fixture, wf.region_objects(regions), "strong", face)
    assert regions.TotalLength != pytest.approx(first, rel=1e-6)
    # the edges are the sketch's
    assert all(r.Edge.endswith("of Sketch") for r in wf.region_objects(regions))


def test_a_sketch_in_another_plane(client, doc):
    """A sketch on a vertical plane: the outline is written in the sketch's
    own coordinates, and the regions are where FreeCAD's geometry says."""
    sketch = parts.sketch_part(doc)
    sketch.Placement = FreeCAD.Placement(V(5, 7, 9), FreeCAD.Rotation(V(1, 0, 0), 90))
    doc.recompute()
    frame = sketch.getGlobalPlacement()
    fixels = [frame.multVec(V(20, 0, 0)), frame.multVec(V(60, 0, 0)), frame.multVec(V(0, 25, 0))]
    regions = wf.show_regions(doc, sketch, fixels, 0.2, "strong", client)
    fixture = regions[0].Regions.Fixture
    assert fixture.Frame.toMatrix() == frame.toMatrix()
    face = parts.sketch_face(sketch)
    assert fixture.Area == pytest.approx(face.Area, rel=1e-12)
    assert fixture.CenterOfMass.distanceToPoint(face.CenterOfMass) <= 1e-9
    check_regions(client, fixture, regions, "strong", face, frame)


def test_friction_and_its_critical_value(client, doc):
    """The regions recompute when the friction changes, and the critical mu
    they report is where the region ends: not empty just below it, empty
    just above it."""
    face = parts.bracket_face()
    regions = wf.show_regions(doc, face, BRACKET_FIXELS, 0.25, "both", client)
    parent = regions[0].Regions
    fixture = parent.Fixture
    critical = parent.CriticalMu
    assert 0.25 < critical < 2
    for mu, empty in ((critical * (1 - 1e-6), False), (critical * (1 + 1e-6), True)):
        fixture.StaticFriction = fixture.KineticFriction = mu
        doc.recompute()
        assert (parent.Count == 0) == empty, (mu, parent.Count)
        assert len(wf.region_objects(parent)) == parent.Count
        assert sum(r.Shape.Length for r in wf.region_objects(parent)) == \
            pytest.approx(parent.TotalLength, rel=1e-9, abs=1e-12)


def test_fixels_as_locators_with_friction_cones(client, doc):
    """Each fixel is a pin outside the material touching the part at its
    point, with its friction cone's sides at atan(mu) from the normal."""
    face = parts.bracket_face()
    regions = wf.show_regions(doc, face, BRACKET_FIXELS, 0.25, "both", client)
    fixture = regions[0].Regions.Fixture
    fixels = wf.make_fixels(fixture)
    doc.recompute()
    size = face.BoundBox.DiagonalLength
    pins = fixels.Shape.Solids
    assert len(pins) == 3 and len(fixels.Normals) == 3
    for p, n, pin in zip(BRACKET_FIXELS, fixels.Normals, pins):
        assert pin.distToShape(Part.Vertex(p))[0] <= 1e-9 * size       # touching
        centre = pin.CenterOfMass
        assert not face.isInside(V(centre.x, centre.y, 1), 1e-9, True)  # outside the material
        assert n.getAngle(inward_normal(face, p)) < 1e-9
        sides = [e for e in fixels.Shape.Edges if type(e.Curve).__name__ in ("Line", "LineSegment")
                 and e.Vertexes[0].Point.distanceToPoint(p) < 1e-9 * size]
        assert len(sides) == 2
        for side in sides:
            d = side.Vertexes[1].Point - side.Vertexes[0].Point
            assert d.getAngle(n) == pytest.approx(math.atan(0.25), rel=1e-9)


def test_best_push(client, doc):
    """The best push: an arrow ending at a point of the both region, pointing
    along the inward normal there; a push there has the margin it states."""
    face = parts.bracket_face()
    regions = wf.show_regions(doc, face, BRACKET_FIXELS, 0.25, "both", client)
    fixture = regions[0].Regions.Fixture
    best = wf.make_best_push(fixture)
    doc.recompute()
    size = face.BoundBox.DiagonalLength
    assert best.Found and 0 < best.Margin < 1
    assert "push here and let go" in best.Label and best.Meaning == wf.MEANING["both"]
    # in the both region (its closure: the best push may be at a region's end)
    on_region = Part.Compound([r.Shape for r in regions]).distToShape(Part.Vertex(best.At))[0]
    assert on_region <= 1e-9 * size
    assert best.Direction.getAngle(inward_normal(face, best.At)) < 1e-9
    (verdict,) = client.classify(fixture.FixtureId, [push(best.At, best.Direction)], sets=["both"])
    assert verdict["both"].margin == pytest.approx(best.Margin, abs=1e-9)
    # no push of both is better, among the boundary's samples
    samples = boundary_samples(face, 48)
    verdicts = client.classify(fixture.FixtureId, [push(p, inward_normal(face, p)) for p in samples],
                               sets=["both"])
    assert max(v["both"].margin for v in verdicts) <= best.Margin + 1e-9
    # the arrow ends at the push point and comes from outside the material
    tip = min(best.Shape.Vertexes, key=lambda v: v.Point.distanceToPoint(best.At)).Point
    assert tip.distanceToPoint(best.At) <= 1e-9 * size
    tail = best.At - best.Direction * (0.15 * size)
    assert best.Shape.distToShape(Part.Vertex(tail))[0] <= 1e-9 * size
    assert not face.isInside(tail, 1e-9, True)
    # a plate against the 3-2-1 locators has no push that seats it
    doc2 = FreeCAD.newDocument("three_two_one")
    try:
        box = doc2.addObject("Part::Box", "Plate")
        doc2.recompute()
        fixture2 = wf.make_fixture(doc2, (box, "Face6"), [V(2, 0, 10), V(8, 0, 10), V(0, 5, 10)],
                                   0.3, socket=client.socket_path)
        best2 = wf.make_best_push(fixture2)
        doc2.recompute()
        assert not best2.Found and best2.Shape.isNull()
        assert "no push seats the part from every contact state" in best2.Label
    finally:
        FreeCAD.closeDocument(doc2.Name)


def test_gravity_dial(client, doc):
    """The dial's arcs are gravity.sweep's, and FreeCAD measures them to its
    total in degrees."""
    face = parts.bracket_face()
    # the best design of the README's "Designing the fixture" (gravity 46.2 deg)
    fixture = wf.make_fixture(doc, wf._object_of_face(doc, face),
                              [V(105, 60, 1), V(25, 60, 1), V(100, 30, 1)], 0.25,
                              socket=client.socket_path)
    dial = wf.make_gravity_dial(fixture, "goal")
    doc.recompute()
    arcs = client.gravity_sweep(fixture.FixtureId, "goal")
    assert dial.Arcs == [x for arc in arcs for x in arc]
    assert dial.TotalDegrees > 0
    circles = [e for e in dial.Shape.Edges if type(e.Curve).__name__ == "Circle"]
    radius = circles[0].Curve.Radius
    # just around the part: every point of its outer boundary inside the dial
    com = fixture.CenterOfMass
    farthest = max(v.Point.distanceToPoint(com) for v in face.OuterWire.Vertexes)
    assert farthest < radius < 1.3 * farthest
    measured = sum(math.degrees(e.Length / radius) for e in dial.Shape.Edges
                   if type(e.Curve).__name__ == "Circle")
    assert measured == pytest.approx(dial.TotalDegrees, rel=1e-9)
    for e in dial.Shape.Edges:
        if type(e.Curve).__name__ == "Circle":
            assert e.Curve.Center.distanceToPoint(fixture.CenterOfMass) <= 1e-9
            assert e.Curve.Radius == pytest.approx(radius, rel=1e-12)
    assert dial.Meaning == wf.GRAVITY_MEANING["goal"] and "gravity pulling" in dial.Meaning


def test_a_fixel_off_the_outline(client, doc):
    """wrenchd refuses a fixel off the outline: the fixture's error names
    the fixel, where it is, and wrenchd's field."""
    face = parts.bracket_face()
    fixels = [HOLE_PIN, V(100, 0.5, 1), V(0, 40, 1)]
    with pytest.raises(wf.WrenchError) as raised:
        wf.show_regions(doc, face, fixels, 0.25, "both", client)
    text = str(raised.value)
    assert "fixel 2 (FixelPoints[1] = (100, 0.5, 1)): (100, 0.5) is not on the workpiece " \
           "boundary: 0.5 away from it" in text                # as the README quotes it
    assert "params.fixture.fixels[1].at" in text
    fixture = [o for o in doc.Objects if wf._is(o, "WrenchFixture")][0]
    assert "Invalid" in fixture.State and "fixel 2" in fixture.getStatusString()
    # moved back onto the outline, it recomputes
    fixture.FixelPoints = BRACKET_FIXELS
    doc.recompute()
    assert "Invalid" not in fixture.State and fixture.FixtureId


def test_a_crossing_loop(client, doc):
    """A sketch whose circle crosses its rectangle: wrenchd refuses the
    outline, and the error names the loops and the sketch's edges."""
    sketch = doc.addObject("Sketcher::SketchObject", "Crossing")
    for a, b in (((0, 0), (40, 0)), ((40, 0), (40, 30)), ((40, 30), (0, 30)), ((0, 30), (0, 0))):
        sketch.addGeometry(Part.LineSegment(V(a[0], a[1], 0), V(b[0], b[1], 0)))
    sketch.addGeometry(Part.Circle(V(38, 15, 0), V(0, 0, 1), 5))
    doc.recompute()
    with pytest.raises(wf.WrenchError) as raised:
        wf.show_regions(doc, sketch, [V(10, 0, 0), V(30, 0, 0), V(0, 10, 0)], 0.3, "both", client)
    text = str(raised.value)
    assert "loop 1 of the outline, hole 1 (Edge5 of Crossing)" in text
    assert "loop 0 is the outer boundary (Edge" in text
    assert "params.fixture.body.shape.loops[1]" in text


def test_refusals_in_freecad_terms(client, doc):
    """Friction, a bad set and an unreachable daemon: each error says what is
    wrong, and for the daemon how to start one."""
    face = parts.bracket_face()
    with pytest.raises(wf.WrenchError, match=r"KineticFriction 0.4 must lie between 0 and "
                                             r"StaticFriction 0.3"):
        wf.show_regions(doc, face, BRACKET_FIXELS, (0.3, 0.4), "both", client)
    with pytest.raises(ValueError, match="set: one of goal, strong, both, not 'all'"):
        wf.show_regions(doc, face, BRACKET_FIXELS, 0.3, "all", client)
    with pytest.raises(ValueError, match=r"fixels\[1\]: a fixel is"):
        wf.show_regions(doc, face, [HOLE_PIN, (1, 2)], 0.3, "both", client)


def test_an_unreachable_daemon_says_how_to_start_one(doc, tmp_path):
    import wrenchd
    path = str(tmp_path / "nobody.sock")
    face = parts.bracket_face()
    with pytest.raises(wf.WrenchError) as raised:
        wf.show_regions(doc, face, BRACKET_FIXELS, 0.3, "both", wrenchd.Client(path, timeout=5))
    text = str(raised.value)
    assert "wrenchd is not reachable at %s" % path in text
    assert "`wrenchd --socket %s`" % path in text
    assert "make run" in text and "$WRENCHD_SOCKET" in text and "Socket property" in text


def test_the_fixture_names_its_units(client, doc):
    """The workbench's fixture says its lengths are FreeCAD's mm (and forces
    N, the Mass kg), and wrenchd keeps them."""
    import json
    regions = wf.show_regions(doc, parts.bracket_face(), BRACKET_FIXELS, 0.3, "both", client)
    fixture = regions[0].Regions.Fixture
    sent = json.loads(fixture.FixtureJson)
    assert sent["units"] == {"length": "mm", "force": "N"} == wf.UNITS
    assert client.get_fixture(fixture.FixtureId)["units"] == sent["units"]


def test_a_busy_daemon_is_busy(doc, tmp_path):
    """A daemon that answers nothing in time (a socket that accepts and never
    answers, as a daemon whose workers are on a long design), and one with
    too many clients: each is said to be busy, not unreachable."""
    import socket
    import time
    import wrenchd
    from conftest import Daemon
    face = parts.bracket_face()
    path = str(tmp_path / "busy.sock")
    server = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
    server.bind(path)
    server.listen(8)
    try:
        with pytest.raises(wf.WrenchError) as raised:
            wf.show_regions(doc, face, BRACKET_FIXELS, 0.3, "both", wrenchd.Client(path, timeout=0.5))
    finally:
        server.close()
    text = str(raised.value)
    assert "wrenchd at %s is busy (" % path in text and "it is running" in text
    assert "not reachable" not in text and "Start one" not in text
    daemon = Daemon("--max-clients", "1")
    holder = wrenchd.Client(daemon.socket, timeout=10)
    try:
        # connected: the one client it takes (once the daemon has seen
        # its start-up probe's connection close)
        deadline = time.monotonic() + 5
        while True:
            try:
                holder.status()
                break
            except wrenchd.WrenchdError:
                assert time.monotonic() < deadline
                time.sleep(0.05)
        with pytest.raises(wf.WrenchError) as raised:
            wf.show_regions(doc, face, BRACKET_FIXELS, 0.3, "both", wrenchd.Client(daemon.socket, timeout=10))
        text = str(raised.value)
        assert "wrenchd at %s is busy (" % daemon.socket in text and "too many clients" in text
        assert "not reachable" not in text
    finally:
        holder.close()
        daemon.stop()


def test_saved_and_opened_again(client, doc, tmp_path):
    """The objects are stored in the document: saved, closed and opened
    again, they hold their shapes and numbers, and recompute as before."""
    face = parts.bracket_face()
    regions = wf.show_regions(doc, face, BRACKET_FIXELS, 0.25, "both", client)
    fixture = regions[0].Regions.Fixture
    wf.make_fixels(fixture)
    wf.make_best_push(fixture)
    wf.make_gravity_dial(fixture, "both")
    doc.recompute()
    before = {o.Name: (o.Label, round(o.Shape.Length, 9) if not o.Shape.isNull() else None)
              for o in doc.Objects}
    lengths = [r.Length for r in regions]
    path = str(tmp_path / "bracket.FCStd")
    doc.saveAs(path)
    name = doc.Name
    FreeCAD.closeDocument(name)
    again = FreeCAD.openDocument(path)
    try:
        after = {o.Name: (o.Label, round(o.Shape.Length, 9) if not o.Shape.isNull() else None)
                 for o in again.Objects}
        assert after == before
        kinds = sorted(wf._proxy_name(o) for o in again.Objects if wf._proxy_name(o))
        assert kinds == sorted(["WrenchFixture", "WrenchRegions", "WrenchFixels", "WrenchBestPush",
                                "WrenchGravityDial"] + ["WrenchRegion"] * len(regions))
        parent = [o for o in again.Objects if wf._is(o, "WrenchRegions")][0]
        assert [r.Length for r in wf.region_objects(parent)] == lengths
        # still live: a lower friction, a recompute, the regions of wrenchd
        fixture = parent.Fixture
        fixture.StaticFriction = fixture.KineticFriction = 0.1
        again.recompute()
        assert all("Invalid" not in o.State for o in again.Objects)
        answer = client.push_regions(fixture.FixtureId, "both")
        assert [r.Length for r in wf.region_objects(parent)] == [r.length for r in answer.regions]
    finally:
        FreeCAD.closeDocument(again.Name)


def test_fixels_picked_at_vertices_and_on_edges(client, doc):
    """fixel_at, as Add fixels uses it: a point picked near an edge is moved
    onto it (its normal left to wrenchd); a corner gets the inward bisector
    of its two sides; a vertex where a line meets an arc tangentially is no
    corner.  wrenchd then takes them all."""
    box = doc.addObject("Part::Box", "Box")
    box.Length, box.Width, box.Height = 50, 30, 4
    doc.recompute()
    top = "Face%d" % (parts.face_at(box.Shape, V(0, 0, 1), 4) + 1)
    fixture = wf.make_fixture(doc, (box, top), [], 0.3, socket=client.socket_path)
    doc.recompute()
    p, n = wf.fixel_at(fixture, V(20, 0.004, 4.2))       # near the bottom edge, above the face
    assert (p.x, p.y, p.z) == (20, 0, 4) and n.Length == 0
    p, n = wf.fixel_at(fixture, V(0, 0, 4))              # the bottom-left corner
    assert p == V(0, 0, 4) and n.getAngle(V(1, 1, 0)) < 1e-12
    p2, n2 = wf.fixel_at(fixture, V(50, 30, 4))          # the top-right corner
    assert n2.getAngle(V(-1, -1, 0)) < 1e-12
    fixture.FixelPoints = [V(20, 0, 4), p, V(50, 15, 4)]
    fixture.FixelNormals = [V(), n, V()]
    doc.recompute()
    assert "Invalid" not in fixture.State and fixture.Pinned
    explicit = client.get_fixture(fixture.FixtureId)
    assert explicit["fixels"][1]["normal"] == pytest.approx([math.sqrt(0.5), math.sqrt(0.5)])
    # a tangent joint of the filleted plate: no corner, no normal given
    plate = doc.addObject("Part::Feature", "Plate")
    plate.Shape = parts.filleted_plate()
    fixture2 = wf.make_fixture(doc, (plate, "Face%d" % (parts.face_at(plate.Shape, V(0, 0, 1), 10) + 1)),
                               [], 0.3, socket=client.socket_path)
    doc.recompute()
    p, n = wf.fixel_at(fixture2, V(8, 0, 10))            # where the bottom line meets a fillet
    assert p.distanceToPoint(V(8, 0, 10)) < 1e-12 and n.Length == 0
