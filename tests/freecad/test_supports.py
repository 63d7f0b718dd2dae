"""Rest buttons in FreeCAD: a 3-2-1 plate made with Part (a box with a
chamfered corner and three blind seats for its buttons drilled from below;
the chamfer is where a push seats it), lying on three buttons
given as points and on three picked on the part (the seats' circular
edges, on the other side of it).  The normal loads are held against the
barycentric closed form computed here from FreeCAD's own centre of mass;
four buttons against the range of the indeterminate distribution; the
least push on the plate against push.force and force.range asked directly
of wrenchd with a fixture written here; a plate that tips against the
distance of its centre of pressure from the buttons' triangle."""

import json
import math

import FreeCAD
import Part
import pytest
from FreeCAD import Vector as V

import parts
import wrench_freecad as wf

L, W_, T = 120.0, 60.0, 10.0          # the plate: length, width, thickness (mm)
MASS, G = 2.0, 9810.0                 # kg, mm/s^2 into the plate
CHAMFER = 30.0                        # the corner at (L, W_) cut from (L, 30) to (90, W_)
FIXELS = [V(30, 0, T), V(90, 0, T), V(0, 15, T)]      # 2 on the long edge, 1 on the short
SEATS = [(20.0, 10.0), (100.0, 20.0), (50.0, 52.0)]   # the blind seats' centres
MU_B = 0.2
FIXEL_MU = 0.1


def plate(doc):
    """The plate as a document object, and its top face's name."""
    solid = Part.makeBox(L, W_, T)
    corner = [e for e in solid.Edges if e.Vertexes[0].Point.x == L and e.Vertexes[0].Point.y == W_
              and e.Vertexes[1].Point.x == L and e.Vertexes[1].Point.y == W_]
    solid = solid.makeChamfer(CHAMFER, corner)
    for x, y in SEATS:
        solid = solid.cut(Part.makeCylinder(4.0, 2.0, V(x, y, 0)))
    obj = doc.addObject("Part::Feature", "Plate")
    obj.Shape = solid
    doc.recompute()
    return obj, "Face%d" % (parts.face_at(solid, V(0, 0, 1), T) + 1)


def fixture_on(doc, client, buttons, down=()):
    part, top = plate(doc)
    fixture = wf.make_fixture(doc, (part, top), FIXELS, FIXEL_MU, mass=MASS,
                              socket=client.socket_path)
    fixture.SupportStaticFriction = fixture.SupportKineticFriction = MU_B
    fixture.SupportGravity = G
    fixture.SupportPoints = list(buttons)
    fixture.DownPoints = [p for p, f in down]
    fixture.DownForces = [f for p, f in down]
    supports = wf.make_supports(fixture)
    doc.recompute()
    return part, fixture, supports


def area2(a, b, c):
    return (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])


def centre_of_mass(part):
    """FreeCAD's centre of mass of the top face: wrenchd's part is that face
    as a uniform lamina of the fixture's Mass."""
    return part.Shape.Faces[parts.face_at(part.Shape, V(0, 0, 1), T)].CenterOfMass


def barycentric_loads(buttons, part, down=()):
    """N_i = W lambda_i: the centre of pressure from FreeCAD's centre of
    mass and the clamps, its barycentric coordinates by areas."""
    weight = MASS * G / 1000.0                  # N: kg * mm/s^2 / 1000
    com = centre_of_mass(part)
    total = weight + sum(f for p, f in down)
    cx = (weight * com.x + sum(f * p.x for p, f in down)) / total
    cy = (weight * com.y + sum(f * p.y for p, f in down)) / total
    a, b, c = [(p.x, p.y) for p in buttons]
    whole = area2(a, b, c)
    lam = [area2((cx, cy), b, c) / whole, area2(a, (cx, cy), c) / whole,
           area2(a, b, (cx, cy)) / whole]
    return [total * l for l in lam], total


def test_three_buttons_given_as_points(client, doc):
    given = [V(30, 15, 0), V(90, 15, 0), V(60, 50, 0)]          # under the part: z = 0
    clamp = [(V(70, 35, T), 50.0)]
    part, fixture, supports = fixture_on(doc, client, given, clamp)
    assert "Invalid" not in fixture.State, fixture.getStatusString()
    want, total = barycentric_loads(given, part, clamp)
    assert fixture.SupportWeight == pytest.approx(total, rel=1e-12)
    assert list(fixture.NormalLoads) == pytest.approx(want, rel=1e-9)
    assert list(fixture.NormalLoadsMin) == list(fixture.NormalLoadsMax) == list(fixture.NormalLoads)
    assert sum(fixture.NormalLoads) == pytest.approx(total, rel=1e-12)
    # without the clamp
    fixture.DownPoints, fixture.DownForces = [], []
    doc.recompute()
    want, total = barycentric_loads(given, part)
    assert list(fixture.NormalLoads) == pytest.approx(want, rel=1e-9)
    assert total == pytest.approx(2 * 9.81, rel=1e-12)
    # the buttons in the face's plane, the supports member in its frame
    sent = json.loads(fixture.FixtureJson)["supports"]
    assert sent == {"points": [[30, 15], [90, 15], [60, 50]], "friction": MU_B, "g": G}
    # shown: a label and an arrow a button, and the report
    assert "Invalid" not in supports.State, supports.getStatusString()
    assert list(supports.LoadLabels) == ["N%d %.4g N" % (i + 1, n)
                                         for i, n in enumerate(fixture.NormalLoads)]
    assert len(supports.Shape.Solids) == 3 and len(supports.LabelPoints) == 3
    # each arrow leaves its button upwards, 15 % of the plate's diagonal
    # for the largest load and in proportion for the others; its label at its tip
    reach = 0.15 * math.hypot(L, W_)
    top = max(fixture.NormalLoads)
    for solid, n, at, label in zip(supports.Shape.Solids, fixture.NormalLoads,
                                   fixture.SupportPoints, supports.LabelPoints):
        box = solid.BoundBox
        assert (box.ZMin, box.ZMax) == pytest.approx((T, T + reach * n / top), abs=1e-9)
        assert (box.Center.x, box.Center.y) == pytest.approx((at.x, at.y), abs=1e-9)
        assert label.distanceToPoint(V(at.x, at.y, T + reach * n / top)) < 1e-9
    assert supports.Report[1].startswith("rest button 1: N = %.6g N" % fixture.NormalLoads[0])
    assert "W = m g + down clamps = %.6g N" % total in supports.Report[0]
    # the id changes with the buttons, and without them it is the floating one's
    with_buttons = fixture.FixtureId
    fixture.SupportStaticFriction = fixture.SupportKineticFriction = 0.25
    doc.recompute()
    assert fixture.FixtureId != with_buttons
    fixture.SupportKineticFriction = 0.2         # mu_B as {static, kinetic}
    doc.recompute()
    assert json.loads(fixture.FixtureJson)["supports"]["friction"] == {"static": 0.25,
                                                                       "kinetic": 0.2}
    assert client.get_fixture(fixture.FixtureId)["supports"]["friction"] == {
        "static": 0.25, "kinetic": 0.2}
    fixture.SupportKineticFriction = 0.3         # above the static: refused, named
    doc.recompute()
    assert "wrenchd refused the rest buttons' friction (SupportStaticFriction, " \
        "SupportKineticFriction)" in fixture.getStatusString()
    fixture.SupportKineticFriction = 0.25
    fixture.SupportPoints = []
    doc.recompute()
    assert fixture.FixtureId not in ("", with_buttons) and fixture.NormalLoads == []
    assert "supports" not in json.loads(fixture.FixtureJson)


def seat_centres(part):
    """The seats' circular edges' centres, as a pick of each gives them
    (z = 2, the seat's floor, or z = 0, its mouth)."""
    centres = []
    for e in part.Shape.Edges:
        if isinstance(e.Curve, Part.Circle) and abs(e.Curve.Center.z - 2.0) < 1e-9:
            centres.append(e.Curve.Center)
    return sorted(centres, key=lambda c: (c.x, c.y))


def test_three_buttons_picked_on_the_part_and_the_least_push(client, doc):
    part, fixture, supports = fixture_on(doc, client, [])
    picked = seat_centres(part)
    assert len(picked) == 3
    # picked one at a time: refused, naming the property, until there are three
    added = wf.add_supports(fixture, picked[:1])
    assert "Invalid" in fixture.State
    assert "wrenchd refused the rest buttons (SupportPoints): at least 3 supports" in \
        fixture.getStatusString()
    added += wf.add_supports(fixture, picked[1:])
    # taken into the top face's plane, along its normal
    assert [(p.x, p.y, p.z) for p in added] == [(x, y, T) for x, y in sorted(SEATS)]
    assert "Invalid" not in fixture.State, fixture.getStatusString()
    want, total = barycentric_loads(added, part)
    assert list(fixture.NormalLoads) == pytest.approx(want, rel=1e-9)

    # The least push on the plate: the workbench's against push.force asked
    # directly with the plate written here as a polygon, and floating.
    least = wf.make_least_force(fixture, samples=4)
    doc.recompute()
    assert "Invalid" not in least.State, least.getStatusString()
    assert least.Set == "goal"
    direct = {"body": {"mass": MASS, "shape": {"type": "polygon", "vertices": [
        [0, 0], [L, 0], [L, W_ - CHAMFER], [L - CHAMFER, W_], [0, W_]]}},
        "friction": {"static": FIXEL_MU}, "units": {"length": "mm", "force": "N"},
        "fixels": [{"at": [p.x, p.y]} for p in FIXELS],
        "supports": {"points": [[x, y] for x, y in sorted(SEATS)], "friction": MU_B, "g": G}}
    none = [{"name": "none", "loads": [{"wrench": [0, 0, 0]}]}]
    r = client.push_force(direct, none, set="goal", samples=1)["least"]
    assert least.Least == pytest.approx(r["force"], rel=1e-9)
    assert least.LeastAt.distanceToPoint(V(r["at"][0], r["at"][1], T)) < 1e-9
    floating = dict(direct)
    del floating["supports"]
    f = client.push_force(floating, none, set="goal", samples=1)["least"]
    assert least.FloatingLeast == pytest.approx(f["force"], rel=1e-9, abs=1e-12)
    assert least.Least > least.FloatingLeast + 1.0
    # force.range at that point gives the same least magnitude
    fr = client.force_range(direct, none, push={"at": r["at"], "direction": r["direction"]},
                            sets=["goal"])
    assert fr["all"]["goal"]["least"] == pytest.approx(least.Least, rel=1e-6)
    # floating, a push along that line of any size seats the plate: 0; the
    # README's figure on the buttons
    assert least.FloatingLeast == 0
    assert least.Least == pytest.approx(12.0262135, rel=1e-8)
    # drawn: the pieces, then the arrow at the least push (three edges)
    edges = least.Shape.Edges
    assert len(edges) == len(least.Forces) + 3
    assert edges[-1].Vertexes[-1].Point.distanceToPoint(least.LeastAt) < 1e-9
    assert "on the rest buttons" in least.Label and "floating" in least.Label


def test_four_buttons_leave_a_range(client, doc):
    # At the corners of a rectangle [x0, x1] x [y0, y1], counter-clockwise:
    # with u, v the centre of mass's place in it, the bilinear weights
    # W ((1-u)(1-v), u(1-v), uv, (1-u)v) balance, and so does that plus
    # t (1, -1, 1, -1) (no net force or moment), for every t keeping all
    # four >= 0: the whole range, P being one-dimensional here.
    x0, x1, y0, y1 = 10.0, 100.0, 10.0, 45.0
    four = [V(x0, y0, 0), V(x1, y0, 0), V(x1, y1, 0), V(x0, y1, 0)]
    part, fixture, supports = fixture_on(doc, client, four)
    com = centre_of_mass(part)
    total = MASS * G / 1000
    u, v = (com.x - x0) / (x1 - x0), (com.y - y0) / (y1 - y0)
    p = [total * (1 - u) * (1 - v), total * u * (1 - v), total * u * v, total * (1 - u) * v]
    t_lo, t_hi = -min(p[0], p[2]), min(p[1], p[3])
    sign = [1, -1, 1, -1]
    lo = [p[i] + sign[i] * (t_lo if sign[i] > 0 else t_hi) for i in range(4)]
    hi = [p[i] + sign[i] * (t_hi if sign[i] > 0 else t_lo) for i in range(4)]
    assert list(fixture.NormalLoadsMin) == pytest.approx(lo, abs=1e-9)
    assert list(fixture.NormalLoadsMax) == pytest.approx(hi, rel=1e-9)
    assert min(lo) == pytest.approx(0, abs=1e-12) and sum(fixture.NormalLoads) == \
        pytest.approx(total, rel=1e-12)
    assert "between" in fixture.SupportsReport[1]
    assert supports.LoadLabels[0] == "N1 %.4g..%.4g N" % (lo[0], hi[0])


def test_a_plate_that_tips_is_refused_with_wrenchd_s_reason(client, doc):
    # all three buttons near one corner: the centre of mass (about (60, 30))
    # is far outside their triangle
    corner = [V(5, 5, 0), V(25, 5, 0), V(15, 25, 0)]
    part, fixture, supports = fixture_on(doc, client, corner)
    assert "Invalid" in fixture.State
    com = centre_of_mass(part)
    # its distance from the triangle: from the edge (25, 5)-(15, 25), which
    # the centre of mass faces
    a, b = (25.0, 5.0), (15.0, 25.0)
    d = (b[0] - a[0], b[1] - a[1])
    t = ((com.x - a[0]) * d[0] + (com.y - a[1]) * d[1]) / (d[0] ** 2 + d[1] ** 2)
    assert 0 < t < 1
    gap = math.hypot(com.x - a[0] - t * d[0], com.y - a[1] - t * d[1])
    message = fixture.getStatusString()
    reason = fixture.SupportsReport[0]
    assert reason.startswith("refused: ")
    for text in (message, reason):
        assert "wrenchd refused the rest buttons (SupportPoints)" in text
        assert "outside the supports' polygon: the part tips" in text
        assert "is %.6g outside" % gap in text
        assert "[params.fixture.supports.points]" in text
    # the buttons' object (not recomputed after its fixture failed) says it too
    assert list(supports.Report) == [reason] and supports.Label.startswith("Rest buttons: refused")
    assert supports.Shape.isNull() and list(supports.LoadLabels) == []
    # a button off the part: named
    fixture.SupportPoints = [V(30, 15, 0), V(90, 15, 0), V(60, 80, 0)]
    doc.recompute()
    assert "wrenchd refused rest button 3 (SupportPoints[2] = (60, 80, 0))" in \
        fixture.getStatusString()
    assert "is outside the part" in fixture.getStatusString()
    # put right, the fixture and its buttons recover
    fixture.SupportPoints = [V(30, 15, 0), V(90, 15, 0), V(60, 50, 0)]
    doc.recompute()
    assert "Invalid" not in fixture.State and "Invalid" not in supports.State
    assert len(supports.LoadLabels) == 3


def test_the_best_push_and_the_gravity_dial_on_the_buttons(client, doc):
    given = [V(30, 15, 0), V(90, 15, 0), V(60, 50, 0)]
    part, fixture, supports = fixture_on(doc, client, given)
    best = wf.make_best_push(fixture)
    dial = wf.make_gravity_dial(fixture)
    doc.recompute()
    # no in-plane pull: the dial says what to give
    assert "Invalid" in dial.State and "set WrenchFixture's Gravity" in dial.getStatusString()
    assert "Invalid" not in best.State, best.getStatusString()
    # how hard this push must be to seat the part on its buttons: force.range
    # (goal) at its point, asked directly of the fixture as sent
    sent = json.loads(fixture.FixtureJson)
    sent["body"]["shape"] = {"type": "polygon", "vertices": [
        [0, 0], [L, 0], [L, W_ - CHAMFER], [L - CHAMFER, W_], [0, W_]]}
    at = [best.At.x, best.At.y]
    direction = [best.Direction.x, best.Direction.y]
    none = [{"name": "none", "loads": [{"wrench": [0, 0, 0]}]}]
    want = client.force_range(sent, none, push={"at": at, "direction": direction},
                              sets=["goal"])["all"]["goal"]["least"]
    assert want is not None and best.PushForce == pytest.approx(want, rel=1e-9)
    assert "floating" in best.Label and "on the rest buttons at least" in best.Label
    # tilted 45 degrees: the in-plane pull, the arcs as gravity.sweep gives them
    fixture.Gravity = G * math.sin(math.radians(45))
    doc.recompute()
    assert "Invalid" not in dial.State, dial.getStatusString()
    arcs = client.tilt_on_supports(sent, fixture.Gravity)["intervals_deg"]
    assert list(dial.Arcs) == pytest.approx([x for arc in arcs for x in arc], rel=1e-12)
    floating = client.gravity_sweep({k: v for k, v in sent.items() if k != "supports"}, "goal")
    assert 0 < dial.TotalDegrees < sum(b - a for a, b in floating)


def test_saved_and_opened_again(client, doc, tmp_path):
    """The buttons are the fixture's, the WrenchSupports an object of its
    own: saved and opened again, both are there, and moving a button
    recomputes the loads to the new closed form."""
    given = [V(30, 15, 0), V(90, 15, 0), V(60, 50, 0)]
    part, fixture, supports = fixture_on(doc, client, given)
    labels = list(supports.LoadLabels)
    name = part.Name
    path = str(tmp_path / "plate.FCStd")
    doc.saveAs(path)
    FreeCAD.closeDocument(doc.Name)
    again = FreeCAD.openDocument(path)
    try:
        fixture = [o for o in again.Objects if wf._is(o, "WrenchFixture")][0]
        supports = wf.supports_of(fixture)
        assert len(supports) == 1 and list(supports[0].LoadLabels) == labels
        assert [(p.x, p.y, p.z) for p in fixture.SupportPoints] == [(p.x, p.y, p.z) for p in given]
        moved = given[:2] + [V(40, 45, 0)]
        fixture.SupportPoints = moved
        again.recompute()
        assert all("Invalid" not in o.State for o in again.Objects)
        want, total = barycentric_loads(moved, again.getObject(name))
        assert list(fixture.NormalLoads) == pytest.approx(want, rel=1e-9)
        assert supports[0].LoadLabels[2] == "N3 %.4g N" % want[2]
    finally:
        FreeCAD.closeDocument(again.Name)


def test_least_force_on_a_face_with_a_hole_is_refused_saying_why(client, doc):
    """wrenchd finds the least push on the plate along a polygon's edges: a
    face with a hole goes as an outline, which it refuses, and the
    workbench says what in the face made it one."""
    part, fixture, supports = fixture_on(doc, client, [V(30, 15, 0), V(90, 15, 0),
                                                       V(60, 50, 0)])
    holed = doc.addObject("Part::Feature", "Holed")
    holed.Shape = part.Shape.cut(Part.makeCylinder(5, T, V(60, 30, 0)))
    doc.recompute()
    fixture.Source = (holed, ["Face%d" % (parts.face_at(holed.Shape, V(0, 0, 1), T) + 1)])
    least = wf.make_least_force(fixture, samples=2)
    doc.recompute()
    assert "Invalid" not in fixture.State, fixture.getStatusString()
    assert "Invalid" in least.State
    message = least.getStatusString()
    assert "[params.fixture.body.shape]" in message and "polygon" in message
    assert message.endswith("WrenchFixture has holes, so it is sent as an outline")


def test_a_design_on_rest_buttons_says_it_is_the_floating_part_s(client, doc):
    part, fixture, supports = fixture_on(doc, client, [V(30, 15, 0), V(90, 15, 0),
                                                       V(60, 50, 0)])
    result = wf.design(fixture, progress=False, spacing=30, top=1, place=False)
    # the same ranking as the part floating asks for
    floating = client.design({"mass": MASS, "shape": {"type": "polygon", "vertices": [
        [0, 0], [L, 0], [L, W_ - CHAMFER], [L - CHAMFER, W_], [0, W_]]}},
        {"static": FIXEL_MU, "kinetic": FIXEL_MU}, fixels=3, spacing=30, top=1)
    assert result.designs[0].score == pytest.approx(floating.designs[0].score, rel=1e-9)
    assert fixture.Designs[1].startswith("the designs are the floating part's")


def test_push_regions_under_a_force_on_the_buttons(client, doc):
    """Regions goal with a PushForce: where a push that hard seats the part
    on its buttons.  Just above the least push they hold its point; just
    below it they are empty (no point of the outline does it with less);
    and they are push.regions' asked directly."""
    part, fixture, supports = fixture_on(doc, client, [V(30, 15, 0), V(90, 15, 0),
                                                       V(60, 50, 0)])
    least = wf.make_least_force(fixture, samples=2)
    regions = wf.make_regions(fixture, "goal")
    doc.recompute()
    assert regions.Count == 0 and "set PushForce" in regions.Label
    regions.PushForce = 1.05 * least.Least
    doc.recompute()
    children = wf.sync_regions(regions)
    assert "Invalid" not in regions.State, regions.getStatusString()
    assert regions.Count >= 1 and len(children) == regions.Count
    assert any(c.Shape.distToShape(Part.Vertex(least.LeastAt))[0] < 1e-9 for c in children)
    sent = json.loads(fixture.FixtureJson)
    sent["body"]["shape"] = {"type": "polygon", "vertices": [
        [0, 0], [L, 0], [L, W_ - CHAMFER], [L - CHAMFER, W_], [0, W_]]}
    none = [{"name": "none", "loads": [{"wrench": [0, 0, 0]}]}]
    direct = client.push_regions(sent, "goal", force=regions.PushForce, cases=none)
    assert list(regions.RegionLengths) == pytest.approx([r.length for r in direct.regions],
                                                        rel=1e-12)
    regions.PushForce = 0.95 * least.Least
    doc.recompute()
    assert "Invalid" not in regions.State and regions.Count == 0
    # strong is no question wrenchd answers with a force on the buttons: its words
    strong = wf.make_regions(fixture, "strong")
    strong.PushForce = least.Least
    doc.recompute()
    assert "Invalid" in strong.State and "[params.set]" in strong.getStatusString()
