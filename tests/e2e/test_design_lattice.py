"""fixture.design on a modular fixture plate (docs/PROTOCOL.md, "lattice"):
every design the daemon returns is valid, checked with this file's own
geometry: the pegs are at lattice points (the first at hole (0, 0)), each
peg's centre is its fixel minus the peg radius along the fixel's normal
(it touches the part there), no peg's centre is inside the part nor nearer
to its outline than the radius (no overlap), and each fixel is on the
outline; on a rounded rectangle (lines and arcs) and a triangle.  The
designs' fixtures answer push.regions as the designs say; refusals."""

import math

import pytest

R = 0.15
FILLET = math.tan(math.pi / 8)  # a quarter circle's bulge
ROUNDED = {"mass": 1, "shape": {"type": "outline", "loops": [[
    [0.5, 0], [2.5, 0, FILLET], [3, 0.5], [3, 1.5, FILLET], [2.5, 2], [0.5, 2, FILLET],
    [0, 1.5], [0, 0.5, FILLET]]]}}
# The rounded rectangle's pieces: lines, and arcs as (centre, radius, from, to) in radians.
ROUNDED_LINES = [((0.5, 0), (2.5, 0)), ((3, 0.5), (3, 1.5)), ((2.5, 2), (0.5, 2)),
                 ((0, 1.5), (0, 0.5))]
ROUNDED_ARCS = [((2.5, 0.5), 0.5, -math.pi / 2, 0), ((2.5, 1.5), 0.5, 0, math.pi / 2),
                ((0.5, 1.5), 0.5, math.pi / 2, math.pi), ((0.5, 0.5), 0.5, math.pi, 1.5 * math.pi)]
TRIANGLE = {"mass": 1, "shape": {"type": "polygon", "vertices": [[0, 0], [3.2, 0], [0.7, 2.1]]}}
TRIANGLE_LINES = [((0, 0), (3.2, 0)), ((3.2, 0), (0.7, 2.1)), ((0.7, 2.1), (0, 0))]


def segment_distance(p, a, b):
    dx, dy = b[0] - a[0], b[1] - a[1]
    s = max(0.0, min(1.0, ((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / (dx * dx + dy * dy)))
    return math.hypot(a[0] + s * dx - p[0], a[1] + s * dy - p[1])


def arc_distance(p, arc):
    (cx, cy), r, lo, hi = arc
    angle = math.atan2(p[1] - cy, p[0] - cx)
    while angle < lo:
        angle += 2 * math.pi
    if angle <= hi:
        return abs(math.hypot(p[0] - cx, p[1] - cy) - r)
    ends = [(cx + r * math.cos(t), cy + r * math.sin(t)) for t in (lo, hi)]
    return min(math.hypot(p[0] - e[0], p[1] - e[1]) for e in ends)


def outline_distance(p, lines, arcs):
    return min([segment_distance(p, a, b) for a, b in lines] +
               [arc_distance(p, arc) for arc in arcs])


def inside(p, lines, arcs):
    """Inside the part: the rounded rectangle as its rectangle less the
    corners outside the fillets; the triangle by its three half-planes."""
    if arcs:
        x, y = p
        if not (0 < x < 3 and 0 < y < 2):
            return False
        for (cx, cy), r, _, _ in arcs:
            corner_x = x > cx if cx > 1.5 else x < cx
            corner_y = y > cy if cy > 1 else y < cy
            if corner_x and corner_y and math.hypot(x - cx, y - cy) > r:
                return False
        return True
    sign = None
    for a, b in lines:
        c = (b[0] - a[0]) * (p[1] - a[1]) - (b[1] - a[1]) * (p[0] - a[0])
        if sign is None:
            sign = c > 0
        elif (c > 0) != sign:
            return False
    return True


@pytest.mark.parametrize("body,lines,arcs", [
    (ROUNDED, ROUNDED_LINES, ROUNDED_ARCS),
    (TRIANGLE, TRIANGLE_LINES, []),
])
def test_every_lattice_design_is_valid(client, body, lines, arcs):
    answer = client.result("fixture.design", {
        "body": body, "friction": 0.3, "lattice": {"pitch": 1, "peg_radius": R, "extent": [4, 4]},
        "top": 1000, "objective": "region"})
    designs = answer["designs"]
    assert answer["poses"] == answer["counts"]["candidates"] > 0
    assert designs
    checked = 0
    for d in designs:
        x, y, degrees = d["pose"]
        theta = math.radians(degrees)
        assert d["pegs"][0] == [0, 0]
        for hole, fixel in zip(d["pegs"], d["fixels"]):
            assert all(isinstance(v, int) for v in hole)
            assert 0 <= hole[1] < 4 and abs(hole[0]) < 4
            # The peg's centre in the part's frame: R(-theta) (P - t).
            px, py = hole[0] - x, hole[1] - y
            q = (math.cos(theta) * px + math.sin(theta) * py,
                 -math.sin(theta) * px + math.cos(theta) * py)
            at, n = fixel["at"], fixel["normal"]
            assert math.hypot(*n) == pytest.approx(1, abs=1e-12)
            assert q[0] == pytest.approx(at[0] - R * n[0], abs=1e-7)
            assert q[1] == pytest.approx(at[1] - R * n[1], abs=1e-7)
            assert outline_distance(at, lines, arcs) < 1e-7
            assert not inside(q, lines, arcs)
            assert outline_distance(q, lines, arcs) >= R - 1e-7
            checked += 1
        # The fixture of the design has the lengths it says.
        fixture = {"body": body, "friction": {"static": 0.3}, "fixels": d["fixels"]}
        regions = client.result("push.regions", {"fixture": fixture, "set": "both"})
        assert regions["total_length"] == pytest.approx(d["both_length"], abs=1e-12)
        assert d["score"] == d["both_length"]
    assert checked == 3 * len(designs)


def test_lattice_designs_do_not_depend_on_top_or_shards(client):
    params = {"body": ROUNDED, "friction": 0.3,
              "lattice": {"pitch": 1, "peg_radius": R, "extent": [3, 3]}, "top": 5}
    whole = client.result("fixture.design", params)
    merged = []
    for i in range(3):
        part = client.result("fixture.design", dict(params, shard=[i, 3]))
        assert part["counts"]["candidates"] == whole["counts"]["candidates"]
        merged += part["designs"]
    merged.sort(key=lambda d: (-d["score"], d["candidate"]))
    for a, b in zip(merged[:5], whole["designs"]):
        a = dict(a, rank=b["rank"])
        assert a == b


@pytest.mark.parametrize("lattice,field", [
    ({"pitch": 0, "peg_radius": 0.1, "extent": [3, 3]}, "params.lattice.pitch"),
    ({"pitch": 1, "peg_radius": 0.5, "extent": [3, 3]}, "params.lattice.peg_radius"),
    ({"pitch": 1, "peg_radius": -1, "extent": [3, 3]}, "params.lattice.peg_radius"),
    ({"pitch": 1, "peg_radius": 0.1, "extent": [0, 3]}, "params.lattice.extent[0]"),
    ({"pitch": 1, "peg_radius": 0.1, "extent": [3, 2.5]}, "params.lattice.extent[1]"),
    ({"pitch": 1, "peg_radius": 0.1}, "params.lattice.extent"),
    ({"pitch": 1, "peg_radius": 0.1, "extent": [3, 3], "holes": 1}, "params.lattice.holes"),
])
def test_lattice_refusals(client, lattice, field):
    error = client.error("fixture.design", {"body": ROUNDED, "friction": 0.3, "lattice": lattice})
    assert error["code"] == -32602 and error["data"]["field"] == field, error


def test_lattice_wants_three_fixels_and_an_outline(client):
    lattice = {"pitch": 1, "peg_radius": 0.1, "extent": [3, 3]}
    error = client.error("fixture.design", {"body": ROUNDED, "friction": 0.3, "lattice": lattice,
                                            "fixels": 4})
    assert error["data"]["field"] == "params.fixels"
    disc = {"mass": 1, "shape": {"type": "circle", "center": [0, 0], "radius": 1}}
    error = client.error("fixture.design", {"body": disc, "friction": 0.3, "lattice": lattice})
    assert error["data"]["field"] == "params.body.shape"


def test_lattice_answer_does_not_depend_on_the_workers(harness):
    """The poses are found in chunks of hole pairs that every worker takes:
    the answer of one worker and of two, byte for byte."""
    params = {"body": ROUNDED, "friction": 0.3, "top": 4,
              "lattice": {"pitch": 1, "peg_radius": R, "extent": [4, 4]}}
    lines = []
    for threads in ("1", "2"):
        d = harness.start("--threads", threads)
        try:
            c = d.client()
            c.send({"jsonrpc": "2.0", "method": "fixture.design", "params": params, "id": 1})
            lines.append(c.read_line(60))
            c.close()
        finally:
            d.stop()
    assert lines[0] == lines[1]
    assert '"pegs"' in (lines[0].decode() if isinstance(lines[0], bytes) else lines[0])
