"""Locating accuracy as a FreeCAD object (WrenchLocating): the bracket's
fixture, each locator off by +-0.02, the hole's centre and a point to
drill as features.  Its ellipses are checked with FreeCAD's own geometry
(each edge's centre, radii and axis direction) against wrenchd asked
directly for the same fixture, and its report lines against the answer."""

import math

import FreeCAD
import Part
import pytest
from FreeCAD import Vector as V

import parts
import wrench_freecad as wf

HOLE_PIN = V(30 - 6 * math.sqrt(0.5), 30 + 6 * math.sqrt(0.5), 1)
BRACKET_FIXELS = [HOLE_PIN, V(100, 0, 1), V(0, 40, 1)]


def test_locating_on_the_bracket(client, doc):
    part = doc.addObject("Part::Feature", "Bracket")
    part.Shape = parts.bracket_face()
    fixture = wf.make_fixture(doc, part, BRACKET_FIXELS, 0.25, socket=client.socket_path)
    features = [V(30, 30, 1), V(110, 50, 1)]
    locating = wf.make_locating(fixture, 0.02, features, ["hole"])
    doc.recompute()
    assert "Invalid" not in locating.State, locating.getStatusString()
    assert locating.Deterministic
    answer = client.locating(fixture.FixtureId, 0.02,
                             [{"name": "hole", "at": [30, 30]}, {"name": "feature 2",
                                                                 "at": [110, 50]}])
    # the figures of the README's bracket, through FreeCAD's outline
    assert answer.features[0]["exact"]["length"] == pytest.approx(0.047874, rel=1e-5)
    scale = float(locating.Label.split("x")[-1])
    assert scale == 200
    ellipses = [e for e in locating.Shape.Edges if isinstance(e.Curve, Part.Ellipse)]
    arrows = [e for e in locating.Shape.Edges if isinstance(e.Curve, Part.Line)]
    assert len(ellipses) == 2 and len(arrows) == 2
    for e, f, p in zip(ellipses, answer.features, features):
        c = e.Curve
        assert c.Center.distanceToPoint(p) <= 1e-9
        assert c.MajorRadius == pytest.approx(scale * f["ellipse"]["axes"][0], rel=1e-9)
        assert c.MinorRadius == pytest.approx(scale * f["ellipse"]["axes"][1], rel=1e-9)
        phi = math.radians(f["ellipse"]["angle_deg"])
        assert abs(c.XAxis.dot(V(math.cos(phi), math.sin(phi), 0))) == pytest.approx(1, abs=1e-9)
        # FreeCAD's perimeter of the ellipse, against Ramanujan's formula
        a, b = c.MajorRadius, c.MinorRadius
        h = ((a - b) / (a + b)) ** 2
        assert e.Length == pytest.approx(math.pi * (a + b) * (1 + 3 * h / (10 + math.sqrt(4 - 3 * h))),
                                         rel=1e-6)
    for e, f, p in zip(arrows, answer.features, features):
        ends = [v.Point for v in e.Vertexes]
        start = min(ends, key=lambda q: q.distanceToPoint(p))
        tip = max(ends, key=lambda q: q.distanceToPoint(p))
        assert start.distanceToPoint(p) <= 1e-9
        u = f["exact"]["vector"]
        assert tip.distanceToPoint(p + V(scale * u[0], scale * u[1], 0)) <= 1e-9
    report = locating.Report
    assert len(report) == 4 and report[0].startswith("locators off by +-0.02 mm")
    assert report[2].startswith("hole at (30, 30): worst 0.047874 mm")


def test_locating_not_deterministic(client, doc):
    """Three fixels on the bottom edge: free to slide along it, said so and
    nothing drawn."""
    part = doc.addObject("Part::Feature", "Bracket")
    part.Shape = parts.bracket_face()
    fixture = wf.make_fixture(doc, part, [V(20, 0, 1), V(60, 0, 1), V(100, 0, 1)], 0.25,
                              socket=client.socket_path)
    locating = wf.make_locating(fixture, 0.02, [V(30, 30, 1)])
    doc.recompute()
    assert not locating.Deterministic and locating.Shape.isNull()
    assert locating.Report == ["not deterministic: the fixels leave the part free to slide "
                               "along (1, 0)"]
