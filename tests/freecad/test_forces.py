"""How hard to push, in FreeCAD: a fixture's Gravity and Loads, the best
push's force, and the least force along the outline (Wrench_LeastForce's
object), against wrenchd asked directly and against the README's figure
for the same bracket (examples/bracket-upright.json, computed without
FreeCAD)."""

import FreeCAD
import pytest
from FreeCAD import Vector as V

import parts
import wrench_freecad as wf
from test_regions import BRACKET_FIXELS

CUTS = (20, 40, 60, 80, 100)


def bracket_under_cuts(client, doc):
    face = parts.bracket_face()
    regions = wf.show_regions(doc, face, BRACKET_FIXELS, 0.25, "both", client)
    fixture = regions[0].Regions.Fixture
    fixture.Mass = 0.8
    fixture.Gravity = 9810
    fixture.GravityDirection = 180
    fixture.Loads = ["x%d: 30,-40 @ %d,60,1" % (x, x) for x in CUTS]
    return fixture


def cases():
    gravity = {"gravity": {"g": 9810, "direction_deg": 180}, "name": "gravity"}
    return [{"name": "x%d" % x, "loads": [gravity, {"force": [30.0, -40.0], "at": [x, 60.0]}]}
            for x in CUTS]


def test_gravity_and_loads_make_cases_in_mm_and_newtons(client, doc):
    fixture = bracket_under_cuts(client, doc)
    doc.recompute()
    import json
    sent = json.loads(fixture.FixtureJson)
    assert sent["units"] == {"length": "mm", "force": "N"}
    outline = wf._Fixture(fixture, "test").outline
    assert wf.load_cases(fixture, outline) == cases()
    fixture.Loads = ["bad: 30 @ 1,2,3"]
    with pytest.raises(wf.WrenchError):
        wf.load_cases(fixture, outline)


def test_least_force_and_the_best_push_force(client, doc):
    fixture = bracket_under_cuts(client, doc)
    best = wf.make_best_push(fixture)
    least = wf.make_least_force(fixture, samples=16)
    doc.recompute()
    fid = fixture.FixtureId
    # The best push's force: force.range at its point, asked directly.
    r = client.force_range(fid, cases(), push={"at": [best.At.x, best.At.y],
                                               "direction": [best.Direction.x, best.Direction.y]},
                           sets=["both"])
    want = r["all"]["both"]["least"]
    assert want is not None and best.PushForce == pytest.approx(want, rel=1e-9)
    assert "N under every load case" in best.Label
    # The least force anywhere a point finger pushes by default (the outer
    # boundary), the best push's too: the README's figure for the same
    # bracket; with PushOn all, from inside the locating hole.
    assert least.Least == pytest.approx(168.925751, rel=1e-6)
    assert best.LeastForce == pytest.approx(least.Least, rel=1e-12)
    assert least.LeastAt.distanceToPoint(V(24.6058, 60, 1)) < 1e-3
    anywhere = wf.make_least_force(fixture, samples=16, push_on="all")
    doc.recompute()
    assert anywhere.Least == pytest.approx(47.702833, rel=1e-6)
    assert anywhere.LeastAt.distanceToPoint(V(25.9941, 25.5331, 1)) < 1e-3
    holes = sum(len(loop) for loop in wf._Fixture(fixture, "t").outline.segments[1:])
    assert sum(1 for f in least.Forces if f < 0) >= 16 * holes  # no push on the holes
    doc.removeObject(anywhere.Name)
    # A piece per sample of every segment, coloured from its F*, and the
    # least push's arrow ending where it pushes.
    segments = sum(len(loop) for loop in wf._Fixture(fixture, "t").outline.segments)
    assert len(least.Forces) == 16 * segments == len(least.Shape.Edges) - 3
    assert least.Shape.Edges[-1].Vertexes[-1].Point.distanceToPoint(least.LeastAt) < 1e-9
    assert min(f for f in least.Forces if f >= 0) >= least.Least * (1 - 1e-9)
    colours = wf.least_force_colours(list(least.Forces))
    lowest = min(range(len(least.Forces)), key=lambda i: least.Forces[i] if least.Forces[i] >= 0
                 else float("inf"))
    assert colours[lowest] == pytest.approx((0.12, 0.31, 0.61))
    assert all(c == (0.8, 0.8, 0.8) for c, f in zip(colours, least.Forces) if f < 0)
    # Without loads there is nothing to say.
    fixture.Gravity = 0
    fixture.Loads = []
    doc.recompute()
    assert least.Least == -1 and "Gravity or Loads" in least.Label
    assert best.PushForce == 0
