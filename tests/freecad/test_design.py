"""design(): fixture.design on a FreeCAD face, its best design placed."""

import pytest
from FreeCAD import Vector as V

import parts
import wrench_freecad as wf


def test_a_design_is_placed(client, doc):
    """The bracket with no fixels: design() ranks every choice of three sites
    10 apart, places the best, and the regions and the best push recompute
    with them -- the design's own figures.  The README's run of the same
    bracket (wrenchctl design examples/bracket.json --spacing 10) found 44
    sites and 13244 candidates; the scores differ where a hole's loop starts
    elsewhere (a loop without corners has its sites from its vertex 0), so
    they are compared with wrenchd's answer for this test's own outline."""
    face = parts.bracket_face()
    fixture = wf.make_fixture(doc, wf._object_of_face(doc, face), [], 0.25,
                              socket=client.socket_path)
    both = wf.make_regions(fixture, "both")
    best = wf.make_best_push(fixture)
    doc.recompute()
    assert both.Count == 0 and "no fixels yet" in both.Label and not best.Found
    seen = []
    result = wf.design(fixture, client, progress=seen.append, spacing=10, top=3)
    assert result.sites == 44 and result.counts["candidates"] == 13244
    top = result.designs[0]
    # the same question asked of wrenchd directly, of this test's own outline
    # (the Python client's default push_on: a point finger, the outer boundary)
    direct = client.design({"mass": 1.0, "shape": wf.outline(face)},
                           {"static": 0.25, "kinetic": 0.25}, fixels=3, spacing=10, top=3)
    assert [d.fixels for d in result.designs] == [d.fixels for d in direct.designs]
    assert top.score == direct.designs[0].score
    assert top.best_push["loop"] == 0
    # placed: the fixels are the design's, in the document (the face is at z = 1)
    assert [(p.x, p.y, p.z) for p in fixture.FixelPoints] == \
        [(f["at"][0], f["at"][1], 1.0) for f in top.fixels]
    assert [(n.x, n.y, n.z) for n in fixture.FixelNormals] == \
        [(f["normal"][0], f["normal"][1], 0.0) for f in top.fixels]
    # the objects recomputed with them
    assert both.TotalLength == pytest.approx(top.both_length, rel=1e-9)
    assert sum(r.Shape.Length for r in wf.region_objects(both)) == \
        pytest.approx(top.both_length, rel=1e-9)
    assert best.Found and best.Margin == pytest.approx(top.best_push["margin"], abs=1e-9)
    at = top.best_push["at"]
    assert best.At.distanceToPoint(V(at[0], at[1], 1)) <= 1e-9
    # progress reached the end of the candidates (the designs' figures may
    # follow, stage "figures"), with the time left said on the way
    search = [p for p in seen if p["stage"] == "candidates"]
    assert search and search[-1]["done"] == search[-1]["total"] == 13244
    assert search[-1]["eta_s"] == 0
    assert all(p["stage"] == "figures" for p in seen[len(search):])
    # the ranking, in the fixture and the report view, says to push with both
    assert fixture.Designs[0].startswith("3 fixels from 44 sites 10 mm apart, 13244 candidates")
    assert fixture.Designs[0].endswith("; lengths in mm")
    assert "the margin of the best push in both" in fixture.Designs[0]
    assert fixture.Designs[1].startswith("1. score %g" % top.score)
    assert "it lies in both" in fixture.Designs[-1] and "let go" in fixture.Designs[-1]
    assert "goal alone" in fixture.Designs[-1]


def test_design_with_the_progress_indicator(client, doc):
    """FreeCAD's own progress indicator (the console's, here), the fixture's
    Design properties, and a design whose fixels are then placed on a part
    in a tilted plane: they lie on the face."""
    import FreeCAD
    solid = parts.l_bracket()
    solid.Placement = FreeCAD.Placement(V(5, -7, 11), FreeCAD.Rotation(V(1, 2, 3), 37))
    normal = solid.Placement.Rotation.multVec(V(0, 0, 1))
    index = parts.face_at(solid, normal, solid.Placement.multVec(V(0, 0, 6)).dot(normal))
    holder = doc.addObject("Part::Feature", "Bracket")
    holder.Shape = solid
    fixture = wf.make_fixture(doc, (holder, "Face%d" % (index + 1)), [], 0.2,
                              socket=client.socket_path)
    fixture.DesignSpacing = 12
    fixture.DesignObjective = "region"
    doc.recompute()
    result = wf.design(fixture, client, progress=True)
    assert result.objective == "region" and result.designs
    face = holder.Shape.Faces[index]
    for p in fixture.FixelPoints:
        assert face.distToShape(__import__("Part").Vertex(p))[0] <= 1e-9 * face.BoundBox.DiagonalLength
    assert fixture.FixtureId and "Invalid" not in fixture.State


def test_design_refusals(client, doc):
    face = parts.bracket_face()
    fixture = wf.make_fixture(doc, wf._object_of_face(doc, face), [], 0.25,
                              socket=client.socket_path)
    doc.recompute()
    with pytest.raises(wf.WrenchError, match=r"design: wrenchd refused DesignSpacing \(-1\): "
                                             r".*\[params.spacing\]"):
        wf.design(fixture, client, progress=None, spacing=-1)
    with pytest.raises(wf.WrenchError, match=r"design: wrenchd refused DesignFixels \(9\): "
                                             r".*\[params.fixels\]"):
        wf.design(fixture, client, progress=None, spacing=20, fixels=9)
    # one fixel never pins the part: no design at all
    with pytest.raises(wf.WrenchError, match=r"no design: 1 fixels from .* 0 degenerate\)"):
        wf.design(fixture, client, progress=None, spacing=20, fixels=1)
    assert list(fixture.FixelPoints) == []


def test_design_objectives_force_and_accuracy(client, doc):
    """DesignObjective force ranks by the least push under the fixture's
    Gravity and Loads, accuracy by the worst locating error with locators
    off by DesignTolerance at the DesignFeatures points: each the same
    ranking, least pushes and errors as wrenchd asked directly for the same
    outline, cases and units."""
    face = parts.bracket_face()
    fixture = wf.make_fixture(doc, wf._object_of_face(doc, face), [], 0.25,
                              socket=client.socket_path)
    fixture.Mass = 0.8
    fixture.DesignObjective = "force"
    doc.recompute()
    with pytest.raises(wf.WrenchError) as e:
        wf.design(fixture, client, progress=None, spacing=20, top=3, place=False)
    assert "set Gravity or Loads" in str(e.value)
    fixture.Gravity = 9810
    fixture.GravityDirection = 180
    fixture.Loads = ["cut: 30,-40 @ 60,60,1"]
    doc.recompute()
    result = wf.design(fixture, client, progress=None, spacing=20, top=3, place=False)
    shape = wf.outline(face)
    gravity = {"gravity": {"g": 9810.0, "direction_deg": 180.0}, "name": "gravity"}
    cases = [{"name": "cut", "loads": [gravity, {"force": [30.0, -40.0], "at": [60.0, 60.0]}]}]
    direct = client.design({"mass": 0.8, "shape": shape}, {"static": 0.25, "kinetic": 0.25},
                           fixels=3, spacing=20, top=3, objective="force", cases=cases,
                           units={"length": "mm", "force": "N"})
    assert result.objective == "force" and result.designs
    assert [d.fixels for d in result.designs] == [d.fixels for d in direct.designs]
    assert [d.least_push["force"] for d in result.designs] == \
        [d.least_push["force"] for d in direct.designs]
    assert "the least push force (N)" in fixture.Designs[0]
    assert "least push %.6g N" % result.designs[0].least_push["force"] in fixture.Designs[1]
    # Accuracy: the pose's error, then a feature's (a document point).
    fixture.DesignObjective = "accuracy"
    fixture.DesignTolerance = 0.05
    fixture.DesignFeatures = [V(110, 50, 1)]
    doc.recompute()
    result = wf.design(fixture, client, progress=None, spacing=20, top=3, place=False)
    direct = client.design({"mass": 0.8, "shape": shape}, {"static": 0.25, "kinetic": 0.25},
                           fixels=3, spacing=20, top=3, objective="accuracy", tolerance=0.05,
                           features=[(110.0, 50.0)], cases=cases,
                           units={"length": "mm", "force": "N"})
    assert [d.fixels for d in result.designs] == [d.fixels for d in direct.designs]
    assert [d.accuracy for d in result.designs] == [d.accuracy for d in direct.designs]
    assert "worst locating error %s mm" % wf._fmt(result.designs[0].accuracy) in \
        fixture.Designs[1]
    # Pareto: the front under the same cases, each design's three figures
    # listed in the report.
    fixture.DesignObjective = "pareto"
    doc.recompute()
    result = wf.design(fixture, client, progress=None, spacing=20, top=50, place=False)
    direct = client.design({"mass": 0.8, "shape": shape}, {"static": 0.25, "kinetic": 0.25},
                           fixels=3, spacing=20, top=50, objective="pareto", tolerance=0.05,
                           features=[(110.0, 50.0)], cases=cases,
                           units={"length": "mm", "force": "N"})
    assert result.objective == "pareto" and result.designs
    assert [d.pareto for d in result.designs] == [d.pareto for d in direct.designs]
    assert "the Pareto front" in fixture.Designs[0]
    for d, line in zip(result.designs, fixture.Designs[1:]):
        assert "pareto: margin %.4g" % d.pareto["margin"] in line
