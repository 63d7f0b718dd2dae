"""From a design to a fixture, and answers that explain themselves, in
wrenchctl and the Python client.

* design --emit-fixture N FILE: the file is a fixture every command takes,
  its numbers exactly the design's; its both region (push.regions) is the
  design's both_length.
* design --json --svg writes both.
* A pin is drawn at its diameter: in each panel the pin's circle against
  the hole's own arcs (the bracket's slot ends are radius 5, its hole 6).
* The clients' default push_on: widths computed here in closed form (a
  round hole's diameter, a slot's width), the Python client's and
  wrenchctl's choice against them, and wrenchctl's push against the
  daemon's regions on every loop, filtered here.
* An empty design and an empty push region explain themselves: their
  reasons recounted here with wrench.classify at the point they name, and
  wrenchctl's words equal to the Python client's.
* The push table: one row per region across segment joints (and across a
  loop's vertex 0), merged here from the JSON answer.
"""

import collections
import json
import math
import os
import re
import subprocess
import sys
import xml.dom.minidom

import pytest

from conftest import REPO
from test_wrenchctl_design import trimmed

WRENCHCTL = os.path.join(REPO, "build", "wrenchctl")
BRACKET = os.path.join(REPO, "examples", "bracket.json")
sys.path.insert(0, os.path.join(REPO, "clients", "python"))
import wrenchd  # noqa: E402


def run(*args, socket_path=None):
    env = dict(os.environ)
    if socket_path:
        env["WRENCHD_SOCKET"] = socket_path
    return subprocess.run([WRENCHCTL] + list(args), capture_output=True, text=True, env=env,
                          timeout=300)


def bracket():
    with open(BRACKET) as f:
        return json.load(f)


# a regular 12-sided plate at friction 0.2, sites at its edges' middles:
# no candidate seats it
TWELVE = {"name": "twelve", "body": {"mass": 1.0, "shape": {"type": "polygon", "vertices": [
    [math.cos(2 * math.pi * k / 12), math.sin(2 * math.pi * k / 12)] for k in range(12)]}},
    "friction": {"static": 0.2}}


@pytest.fixture
def twelve_file(tmp_path):
    path = tmp_path / "twelve.json"
    path.write_text(json.dumps(TWELVE))
    return str(path)


# ---- from a design to a fixture ---------------------------------------------------------

def test_emit_fixture_is_a_fixture(tmp_path):
    out = tmp_path / "design2.json"
    answer = json.loads(run("--local", "--json", "design", BRACKET, "--spacing", "10", "--top",
                            "3").stdout)
    r = run("--local", "design", BRACKET, "--spacing", "10", "--top", "3", "--emit-fixture", "2",
            str(out))
    assert r.returncode == 0, r.stderr
    fixture = json.loads(out.read_text())
    b = bracket()
    assert fixture["body"] == b["body"]              # every number as in the drawing
    assert fixture["friction"] == b["friction"]
    assert fixture["fixels"] == answer["designs"][1]["fixels"]
    assert fixture["name"] == "bracket, design 2"
    # every other command takes it: its both region is the design's
    both = json.loads(run("--local", "--json", "push", str(out), "--set", "both").stdout)
    assert both["total_length"] == pytest.approx(answer["designs"][1]["both_length"], abs=1e-9)
    put = run("--local", "--json", "modes", str(out))
    assert put.returncode == 0, put.stderr
    # refusals
    r = run("--local", "design", BRACKET, "--spacing", "10", "--top", "3", "--emit-fixture", "4",
            str(out))
    assert r.returncode == 2 and "the answer has 3 designs" in r.stderr
    r = run("--local", "design", BRACKET, "--spacing", "10", "--emit-fixture", "1")
    assert r.returncode == 2 and "--emit-fixture wants N and a FILE" in r.stderr
    r = run("--local", "design", BRACKET, "--spacing", "10", "--shard", "0/2", "--emit-fixture",
            "1", str(out))
    assert r.returncode == 2 and "--shard" in r.stderr


def test_json_and_svg_both_written(tmp_path):
    svg = tmp_path / "designs.svg"
    r = run("--local", "--json", "design", BRACKET, "--spacing", "10", "--top", "3", "--svg",
            str(svg))
    assert r.returncode == 0, r.stderr
    answer = json.loads(r.stdout)
    doc = xml.dom.minidom.parse(str(svg))
    panels = [g for g in doc.getElementsByTagName("g") if g.getAttribute("class") == "design"]
    assert len(panels) == len(answer["designs"]) == 3


def arc_radii(path_d):
    return [float(m) for m in re.findall(r"A ([0-9.]+) [0-9.]+ ", path_d)]


@pytest.mark.parametrize("diameter", [2.0, 4.0, 9.0])
def test_pins_drawn_at_their_diameter(tmp_path, diameter):
    """Sites on the bracket's hole (radius 6) and slot (10 wide, ends of
    radius 5) are pins of the diameter asked; where a design has one, its
    circle's radius is diameter / 2 in the panel's scale, which the slot's
    end arcs (radius 5, the smallest arcs of the outline) give."""
    svg = tmp_path / "pins.svg"
    r = run("--local", "--json", "design", BRACKET, "--spacing", "6", "--top", "6",
            "--pin-diameter", str(diameter), "--objective", "region", "--push-on", "all",
            "--svg", str(svg))
    assert r.returncode == 0, r.stderr
    answer = json.loads(r.stdout)
    doc = xml.dom.minidom.parse(str(svg))
    panels = [g for g in doc.getElementsByTagName("g") if g.getAttribute("class") == "design"]
    pinned = 0
    for g, d in zip(panels, answer["designs"]):
        outline = [p for p in g.getElementsByTagName("path") if p.getAttribute("class") == "outline"]
        scale = min(arc_radii(outline[0].getAttribute("d"))) / 5.0
        pins = [c for c in g.getElementsByTagName("circle") if "pin" in c.getAttribute("class")]
        assert len(pins) == len(d["pins"]), (d["pins"], len(pins))
        for c, p in zip(pins, d["pins"]):
            assert p["diameter"] == diameter
            assert float(c.getAttribute("r")) == pytest.approx(diameter / 2 * scale, abs=0.01)
            # the disc touches the wall at the fixel, inside the hole
            pinned += 1
    if diameter < 10:
        assert pinned >= 1, "no design with a pin: the case shows nothing"


# ---- where the finger may push ----------------------------------------------------------

def test_default_push_on_by_width(tmp_path):
    """The bracket's hole is 12 across and its slot 10 wide (closed forms);
    the outer boundary is 60 high.  A point finger: the outer boundary only;
    radius r: the holes wider than 2r."""
    body = bracket()["body"]
    loops = body["shape"]["loops"]
    assert wrenchd.loop_width(loops[0]) == pytest.approx(60, abs=1e-9)
    assert wrenchd.loop_width(loops[1]) == pytest.approx(12, abs=1e-9)
    assert wrenchd.loop_width(loops[2]) == pytest.approx(10, abs=1e-9)
    cases = [(0, "outer"), (4.9, [0, 1, 2]), (5.5, [0, 1]), (6.1, "outer")]
    for radius, expected in cases:
        assert wrenchd.default_push_on(body, radius) == expected
    # wrenchctl chooses alike: its regions are those of every loop, on the
    # loops the rule allows
    for radius, expected in cases:
        allowed = {0} if expected == "outer" else set(expected)
        args = ["--local", "--json", "push", BRACKET, "--set", "goal"]
        if radius:
            args += ["--finger-radius", str(radius)]
        default = json.loads(run(*args).stdout)
        everywhere = json.loads(run(*args, "--push-on", "all").stdout)
        want = [g for g in everywhere["regions"] if g["loop"] in allowed]
        assert default["regions"] == want, (radius, default["regions"], want)
    # an M3 screw hole (3.2 across) in a 40 x 30 plate: a point finger never
    # pushes in it
    plate = {"mass": 0.1, "shape": {"type": "outline", "loops": [
        [[0, 0], [40, 0], [40, 30], [0, 30]], [[8.4, 8, 1], [11.6, 8, 1]]]}}
    assert wrenchd.loop_width(plate["shape"]["loops"][1]) == pytest.approx(3.2, abs=1e-9)
    assert wrenchd.default_push_on(plate, 0) == "outer"
    assert wrenchd.default_push_on(plate, 1.5) == [0, 1]
    assert wrenchd.default_push_on(plate, 2) == "outer"


def test_python_client_sends_the_default(daemon):
    b = bracket()
    with wrenchd.Client(daemon.path, timeout=120) as client:
        got = client.design(b["body"], b["friction"], spacing=12, top=3)
        raw = client.call("fixture.design", {"body": b["body"], "friction": b["friction"],
                                             "spacing": 12, "top": 3, "push_on": "outer"})
        assert [d.candidate for d in got.designs] == [d["candidate"] for d in raw["designs"]]
        everywhere = client.design(b["body"], b["friction"], spacing=12, top=3, push_on="all")
        assert everywhere.counts["no_seating_push"] < got.counts["no_seating_push"]
        put = client.put_fixture(b)
        regions = client.push_regions(put.id, "both")
        assert {r.loop for r in regions.regions} <= {0}


# ---- empty answers explain themselves ---------------------------------------------------

def push_wrench_at(shape, where, t):
    """The push at (edge, t) of a polygon, as the daemon applies it: the
    inward normal at the point."""
    v = shape["vertices"]
    a, b = v[where], v[(where + 1) % len(v)]
    p = (a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1]))
    d = (b[0] - a[0], b[1] - a[1])
    n = math.hypot(*d)
    return {"force": [-d[1] / n, d[0] / n], "at": list(p)}   # counter-clockwise: inward is left


def test_empty_design_explained(daemon, twelve_file):
    """The 12-sided plate: every candidate has no seating push; the answer
    says so and, at the point it names, why, per blocking string.  Recounted
    here: each candidate's fixture classified (wrench.classify, set goal)
    at that point; wrenchctl's words are the Python client's."""
    with wrenchd.Client(daemon.path, timeout=120) as client:
        body, friction = TWELVE["body"], TWELVE["friction"]
        # the sites: the middle of each edge, given, so that the fixtures
        # built here have the design's fixels to the bit
        v = body["shape"]["vertices"]
        sites = [[(v[i][0] + v[(i + 1) % 12][0]) / 2, (v[i][1] + v[(i + 1) % 12][1]) / 2]
                 for i in range(12)]
        # every candidate scored, not one per symmetric group: the tally
        # below classifies all 220
        answer = client.call("fixture.design", {"body": body, "friction": friction,
                                                "sites": [{"at": s} for s in sites],
                                                "collapse_symmetric": False})
        assert answer["designs"] == [] and answer["counts"]["no_seating_push"] == 220
        why = answer["why_no_seating_push"]
        asked = why["asked_at"]
        # the middle of the longest edge (here all are equal, to rounding)
        v = body["shape"]["vertices"]
        lengths = [math.dist(v[i], v[(i + 1) % 12]) for i in range(12)]
        assert asked["t"] == 0.5 and lengths[asked["edge"]] >= max(lengths) * (1 - 1e-12)
        import itertools
        tally = collections.Counter()
        push = push_wrench_at(body["shape"], asked["edge"], 0.5)
        assert push["at"] == pytest.approx(asked["at"], abs=1e-12)
        for combo in itertools.combinations(range(12), 3):
            fixture = {"body": body, "friction": friction,
                       "fixels": [{"at": sites[i]} for i in combo]}
            v_ = client.call("wrench.classify", {"fixture": fixture, "wrenches": [push],
                                                 "sets": ["goal"]})["results"][0]["goal"]
            tally[v_["blocking"] if not v_["inside"] else None] += 1
        got = {r["blocking"]: r["candidates"] for r in why["reasons"]}
        assert got == dict(tally), (got, tally)
        counts = [r["candidates"] for r in why["reasons"]]
        assert counts == sorted(counts, reverse=True)
        assert wrenchd.explain_no_design(answer)[1] == "  220 have no seating push"
    # wrenchctl's words, the Python client's of the same answer
    spaced = json.loads(run("--json", "design", twelve_file, "--spacing", "0.4", "--symmetric",
                            "all", socket_path=daemon.path).stdout)
    lines = wrenchd.explain_no_design(spaced)
    r = run("design", twelve_file, "--spacing", "0.4", "--symmetric", "all",
            socket_path=daemon.path)
    assert r.returncode == 1
    text = r.stdout.splitlines()
    start = text.index(lines[0])
    assert text[start:start + len(lines)] == lines
    assert lines[1] == "  220 have no seating push"
    assert any(re.match(r"    \d+ of 220: from contact state 100 fixel 1 may break away$", x)
               for x in lines)


def test_empty_push_region_explained(daemon, tmp_path):
    """A fixture of the 12-sided plate with no goal region: why_empty counts
    the blocking cone at the middle of each edge, recounted here with
    wrench.classify; wrenchctl prints the Python client's lines."""
    v = TWELVE["body"]["shape"]["vertices"]
    mids = [[(v[i][0] + v[(i + 1) % 12][0]) / 2, (v[i][1] + v[(i + 1) % 12][1]) / 2]
            for i in (0, 3, 7)]
    fixture = dict(TWELVE, fixels=[{"at": m} for m in mids])
    path = tmp_path / "f.json"
    path.write_text(json.dumps(fixture))
    with wrenchd.Client(daemon.path, timeout=120) as client:
        answer = client.call("push.regions", {"fixture": fixture, "set": "goal"})
        assert answer["regions"] == []
        pushes = [push_wrench_at(fixture["body"]["shape"], e, 0.5) for e in range(12)]
        verdicts = client.call("wrench.classify", {"fixture": fixture, "wrenches": pushes,
                                                   "sets": ["goal"]})["results"]
        tally = collections.Counter(x["goal"]["blocking"] for x in verdicts)
        got = {r["blocking"]: r["edges"] for r in answer["why_empty"]["reasons"]}
        assert got == dict(tally)
        for r in answer["why_empty"]["reasons"]:
            assert r["set"] == "goal"
            assert r["states"] == next(x["goal"]["states"] for x in verdicts
                                       if x["goal"]["blocking"] == r["blocking"])
        lines = wrenchd.explain_empty_regions(answer)
        assert lines[0] == "no region: the push at the middle of each of the 12 edges pushed on:"
        # and with regions, no why
        regions = client.call("push.regions", {"fixture": fixture, "set": "strong"})
        assert regions["regions"] and "why_empty" not in regions
    r = run("push", str(path), "--set", "goal", socket_path=daemon.path)
    assert r.returncode == 1
    text = r.stdout.splitlines()
    start = text.index(lines[0])
    assert text[start:start + len(lines)] == lines


# ---- the push table ---------------------------------------------------------------------

def rows_of(answer, segments):
    """Regions merged here: consecutive pieces of one loop where one ends at
    its segment's end (t1 = 1) and the next starts at the following
    segment's start (t0 = 0), and a loop's last row into its first across
    vertex 0.  [(pieces, length)]."""
    key = "segment" if answer["regions"] and "loop" in answer["regions"][0] else "edge"

    def joins(a, b):
        la, lb = a.get("loop", 0), b.get("loop", 0)
        n = segments[la]
        return (la == lb and b[key] == (a[key] + 1) % n and a["t1"] >= 1 - 1e-9
                and b["t0"] <= 1e-9)

    rows = []
    for g in answer["regions"]:
        if rows and joins(rows[-1][-1], g):
            rows[-1].append(g)
        else:
            rows.append([g])
    by_loop = collections.defaultdict(list)
    for row in rows:
        by_loop[row[0].get("loop", 0)].append(row)
    out = []
    for loop, group in by_loop.items():
        if len(group) > 1 and joins(group[-1][-1], group[0][0]):
            group[0] = group[-1] + group[0]
            group.pop()
        out += group
    return [(row, sum(g["length"] for g in row)) for row in out]


def table_rows(text):
    """(first cell(s), from, to, length) of each row of wrenchctl's push
    table, and its pieces line."""
    lines = [x for x in text.splitlines()[1:] if x.strip()]
    rows = []
    for i, line in enumerate(lines):
        m = re.match(r"\s*(?:(\d+)\s+)?([\d-]+)\s+(\([^)]*\))\s+(\([^)]*\))\s+([\d.]+)$", line)
        if m:
            rows.append((m.groups(), lines[i + 1].strip()))
    return rows


def test_push_rows_across_joints_and_vertex_zero(tmp_path):
    """A 10 x 4 plate written from the middle of its bottom edge ((5, 0) is a
    straight joint) and a faceted fillet: a region on the bottom runs from
    the last edge into edge 0 across vertex 0, and one on the fillet
    crosses its facets.  Each is one row, its pieces listed; coordinates to
    the drawing's precision (computed here: the median of the vertices'
    decimals, 0, and never coarser than 1/10,000 of the box's diagonal,
    11.2: 3)."""
    verts = [[5, 0], [10, 0], [10, 2.5], [10.5, 3.1], [9.9, 4], [0, 4], [0, 0]]
    fixture = {"body": {"mass": 1.0, "shape": {"type": "polygon", "vertices": verts}},
               "friction": {"static": 0.1},
               "fixels": [{"at": [0, 2]}, {"at": [5, 4]}, {"at": [10, 1]}]}
    path = tmp_path / "f.json"
    path.write_text(json.dumps(fixture))
    places = sorted(next(p for p in range(7) if float("%.*f" % (p, x)) == x)
                    for v in verts for x in v)
    places = places[len(places) // 2]
    xs, ys = [v[0] for v in verts], [v[1] for v in verts]
    places = max(places, math.ceil(-math.log10(1e-4 * math.hypot(max(xs) - min(xs),
                                                                 max(ys) - min(ys)))))
    assert places == 3
    found_wrap = False
    for set_name in ("goal", "strong", "both"):
        answer = json.loads(run("--local", "--json", "push", str(path), "--set", set_name).stdout)
        expected = rows_of(answer, {0: len(verts)})
        table = table_rows(run("--local", "push", str(path), "--set", set_name).stdout)
        assert len(table) == len(expected), (table, expected)
        for ((_, which, a, b, length), pieces), (row, want) in zip(table, expected):
            assert float(length) == pytest.approx(want, abs=0.5 * 10 ** -places)
            first, last = row[0], row[-1]
            assert a == "(%s, %s)" % (trimmed(first["from"][0], places),
                                      trimmed(first["from"][1], places))
            assert b == "(%s, %s)" % (trimmed(last["to"][0], places), trimmed(last["to"][1], places))
            assert pieces.count("edge ") == len(row)
            found_wrap |= len(row) > 1 and row[0]["edge"] > row[-1]["edge"]
    assert found_wrap, "no region across vertex 0: the case shows nothing"
