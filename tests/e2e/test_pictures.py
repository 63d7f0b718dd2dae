"""wrenchctl's pictures (--svg): well-formed XML, one region path per region
of the answer, and the part drawn (outline, fixels, friction cones, centre
of mass).  The README's pictures in docs/ are what wrenchctl draws now.
Outlines of lines and arcs: arcs drawn as arcs, holes as holes,
regions on arcs as arcs, pins in holes, checked against geometry worked out
here (svg_geometry.py)."""

import json
import math
import os
import subprocess
import xml.dom.minidom
import xml.etree.ElementTree as ET

import pytest

from conftest import FIGURES, REPO
from svg_geometry import PageMap, in_material, inside_loop, loops_of, parse_path, svg_arc_center

WRENCHCTL = os.path.join(REPO, "build", "wrenchctl")
EXAMPLES = os.path.join(REPO, "examples")


def run(*args):
    return subprocess.run([WRENCHCTL, "--local"] + list(args), capture_output=True, text=True,
                          timeout=60)


def elements(path, tag, cls=None):
    document = xml.dom.minidom.parse(path)
    return [e for e in document.getElementsByTagName(tag)
            if cls is None or e.getAttribute("class") == cls]


@pytest.mark.parametrize("name", ["disc-corner", "plate-3-2-1", "plate-chamfered", "outline"])
@pytest.mark.parametrize("set_name", ["goal", "strong", "both"])
def test_push_picture_has_one_path_per_region(harness, name, set_name):
    fixture = os.path.join(EXAMPLES, name + ".json")
    svg = harness.path("%s-%s.svg" % (name, set_name))
    answer = run("push", fixture, "--set", set_name, "--json", "--svg", svg)
    assert answer.returncode in (0, 1), answer.stderr
    regions = json.loads(answer.stdout)["regions"]
    assert answer.returncode == (0 if regions else 1)
    assert len(elements(svg, "path", "region")) == len(regions)
    with open(fixture) as f:
        fixels = len(json.load(f)["fixels"])
    assert len(elements(svg, "polygon", "fixel")) == fixels
    assert len(elements(svg, "polygon", "friction-cone")) == fixels
    assert len(elements(svg, "g", "com")) == 1
    assert len(elements(svg, "polygon", "outline") + elements(svg, "circle", "outline")) == 1


@pytest.mark.parametrize("name", ["disc-corner", "plate-chamfered"])
def test_gravity_dial_and_margin_pictures(harness, name):
    fixture = os.path.join(EXAMPLES, name + ".json")
    dial = harness.path("dial.svg")
    answer = run("gravity", fixture, "--set", "goal", "--json", "--svg", dial)
    arcs = json.loads(answer.stdout)["intervals_deg"]
    assert len(elements(dial, "path", "region")) == len(arcs)
    assert len(elements(dial, "circle", "dial")) == 1
    picture = harness.path("margin.svg")
    answer = run("margin", fixture, "-1,-1,0", "--svg", picture)
    assert answer.returncode in (0, 1), answer.stderr
    assert elements(picture, "line") or elements(picture, "path")
    assert not elements(picture, "path", "region")


def test_bad_svg_path_is_a_usage_error():
    r = run("push", os.path.join(EXAMPLES, "disc-corner.json"), "--svg", "/nonexistent/x.svg")
    assert r.returncode == 2 and "--svg" in r.stderr


@pytest.mark.parametrize("picture,command", [
    ("plate-3-2-1-push-strong.svg", ["push", "plate-3-2-1.json", "--set", "strong"]),
    ("plate-chamfered-push-both.svg", ["push", "plate-chamfered.json", "--set", "both"]),
    ("disc-corner-push-goal.svg", ["push", "disc-corner.json", "--set", "goal"]),
    ("bracket-push-both.svg", ["push", "bracket.json", "--set", "both", "--push-on", "all"]),
    ("notched-plate-push-strong-r4.svg", ["push", "notched-plate.json", "--set", "strong",
                                          "--finger-radius", "4"]),
    ("plate-chamfered-sweep-both.svg", ["sweep", "plate-chamfered.json", "--push", "both",
                                        "--range", "0:1"]),
    ("bracket-designs.svg", ["design", "bracket.json", "--spacing", "10", "--top", "3"]),
    ("bracket-locate.svg", ["locate", "bracket.json", "--tolerance", "0.02", "--feature",
                            "hole=30,30", "--feature", "slot=85,30", "--feature",
                            "drill=110,50"]),
    ("bracket-upright-push-force.svg",
     ["push-force", "bracket-upright.json"] +
     [a for x in (20, 40, 60, 80, 100)
      for a in ("--case", "x%d:gravity=9810@180;force=30,-40@%d,60" % (x, x))] +
     ["--push-on", "all"]),
])
def test_readme_pictures_are_current(harness, picture, command):
    """docs/pictures/ holds what wrenchctl draws today (make pictures)."""
    fresh = harness.path(picture)
    command = command[:1] + [os.path.join(EXAMPLES, command[1])] + command[2:]
    assert run(*command, "--svg", fresh).returncode in (0, 1)
    with open(fresh) as a, open(os.path.join(REPO, "docs", "pictures", picture)) as b:
        assert a.read() == b.read(), "run 'make pictures' and commit docs/pictures"


# ---- outlines of lines and arcs ---------------------------------------------
#
# Each picture is read back with xml.etree and checked against the outline's
# geometry worked out in svg_geometry.py from the wire's description of a
# shape: the fixture-to-page map is fitted to the drawn vertices (a uniform
# scale, y flipped), then every arc command's endpoints, radius, flags and
# centre (SVG's own reading of them, its appendix F.6.5) must be those of
# its segment, holes subpaths of the one evenodd path, regions on arcs arcs
# of their segment's circle, and fixels on a hole's boundary pins in it.

SVG = "{http://www.w3.org/2000/svg}"
# Page coordinates of outlines are written to 1e-6 px; the fitted map and
# SVG's reading of an arc (ill-conditioned near a half circle) add a little.
PX = 0.01
CENTRE_PX = 0.1

COS30 = math.cos(math.radians(30))


def reversed_loop(loop):
    """The same loop written the other way round: segment j (vertex j to
    j + 1, bulge b_j) becomes a segment from vertex j + 1 to j, bulge -b_j."""
    n = len(loop)
    out = []
    for k in range(n):
        j = (n - k) % n                       # the vertex this one is
        b = loop[(j - 1) % n][2] if len(loop[(j - 1) % n]) > 2 else 0
        out.append([loop[j][0], loop[j][1]] + ([-b] if b else []))
    return out


ISSUE_LOOPS = [[[0, 0], [40, 0, 0.4142135623730951], [50, 10], [50, 30], [0, 30]],
               [[10, 10, 1], [16, 10, 1]]]
OUTLINES = {
    # The issue's example: a quarter arc corner, a hole of two half circles
    # (counter-clockwise); fixel 3 a pin at the top of the hole.
    "issue": ({"type": "outline", "loops": ISSUE_LOOPS},
              [[20, 0], [0, 15], [13, 13]], 0.3, "strong"),
    # The same written clockwise, outer loop and hole: negative bulges.
    "issue-cw": ({"type": "outline", "loops": [reversed_loop(l) for l in ISSUE_LOOPS]},
                 [[20, 0], [0, 15], [13, 13]], 0.3, "strong"),
    # A rectangle with a bulb of 270 degrees (large-arc) and a clockwise
    # hole; fixel 3 a pin at the bottom of the hole.
    "bulb": ({"type": "outline", "loops": [
        [[0, 0], [10, 0, math.tan(math.radians(270) / 4)], [10, 4], [0, 4]],
        [[3, 2, -1], [5, 2, -1]]]},
        [[2, 0], [0, 2], [4, 1]], 0.2, "strong"),
    # A disc with a flat: one arc of 300 degrees, pushed on all of it.
    "cut-disc": ({"type": "outline", "loops": [
        [[COS30, 0.5, math.tan(math.radians(300) / 4)], [COS30, -0.5]]]},
        [[0.6, 0.8], [0.6, -0.8], [-1, 0]], 0.1, "strong"),
}


def outline_fixture(harness, name):
    shape, fixels, mu, _ = OUTLINES[name]
    fixture = {"name": name, "body": {"mass": 1.0, "shape": shape}, "friction": {"static": mu},
               "fixels": [{"at": a} for a in fixels]}
    path = harness.path(name + ".json")
    with open(path, "w") as f:
        json.dump(fixture, f)
    return path, fixture


def svg_elements(path, tag, cls=None):
    """Elements of a tag whose class list holds cls (any when None)."""
    root = ET.parse(path).getroot()
    return [e for e in root.iter(SVG + tag)
            if cls is None or cls in (e.get("class") or "").split()]


def near(p, q, tol=PX):
    return math.dist(p, q) <= tol


def check_arc(command, segment, t0, t1, page):
    """An "A" command drawing segment's arc from t0 to t1 on the page."""
    kind, p0, rx, ry, rotation, large, sweep, p1 = command
    assert kind == "A", command
    theta = (t1 - t0) * segment.theta
    r = segment.radius * page.s
    assert abs(rx - r) <= PX and abs(ry - r) <= PX and rotation == 0, (command, r)
    assert near(p0, page.page(segment.point(t0))), (command, page.page(segment.point(t0)))
    assert near(p1, page.page(segment.point(t1))), (command, page.page(segment.point(t1)))
    # Counter-clockwise in the fixture is clockwise on the page (y down):
    # sweep-flag 0; large-arc beyond a half circle.
    assert sweep == (0 if theta > 0 else 1), (command, theta)
    if abs(abs(theta) - math.pi) > 1e-9:
        assert large == (1 if abs(theta) > math.pi else 0), (command, theta)
    # As SVG reads it: the segment's centre, and the segment's angle (the
    # page's angles turn the other way).
    centre, _, delta = svg_arc_center(p0, rx, large, sweep, p1)
    assert near(centre, page.page(segment.center), CENTRE_PX), (command, centre)
    assert abs(delta + theta) < 1e-3, (command, delta, theta)


def check_outline(path, shape):
    """The one outline path of a picture against the shape: returns the
    fitted page map and the loops' segments."""
    outlines = svg_elements(path, "path", "outline")
    assert len(outlines) == 1
    assert not svg_elements(path, "polygon", "outline") and not svg_elements(path, "circle",
                                                                             "outline")
    element = outlines[0]
    assert element.get("fill-rule") == "evenodd"
    assert element.get("fill") not in (None, "none")
    loops = loops_of(shape)
    subpaths = parse_path(element.get("d"))
    # Holes are holes: every loop a closed subpath of the same filled path.
    assert len(subpaths) == len(loops)
    pairs = []
    for segments, sub in zip(loops, subpaths):
        assert sub[0][0] == "M" and sub[-1][0] == "Z"
        drawn = sub[1:-1]
        # One command a segment; a last straight one is the closing Z.
        assert len(drawn) == len(segments) - (1 if segments[-1].bulge == 0 else 0), sub
        pairs.append((segments[0].start, sub[0][1]))
        pairs += [(s.end, c[-1]) for s, c in zip(segments, drawn)]
    page = PageMap.fit(pairs)
    assert page.s > 0
    for f, q in pairs:
        assert near(page.page(f), q), (f, q, page.page(f))
    arcs = 0
    for segments, sub in zip(loops, subpaths):
        for s, c in zip(segments, sub[1:-1]):
            if s.bulge == 0:
                assert c[0] == "L", c
            else:
                check_arc(c, s, 0.0, 1.0, page)
                arcs += 1
    assert arcs == sum(1 for l in loops for s in l if s.bulge)
    return page, loops


def segment_normal(loops, loop, segment, p):
    """The unit normal at p on a segment, pointing into the material."""
    s = loops[loop][segment]
    if s.bulge == 0:
        d = (s.end[0] - s.start[0], s.end[1] - s.start[1])
        n = (-d[1], d[0])
    else:
        n = (p[0] - s.center[0], p[1] - s.center[1])
    length = math.hypot(*n)
    n = (n[0] / length, n[1] / length)
    eps = 1e-4 * max(abs(v) for l in loops for s2 in l for v in s2.start)
    if not in_material(loops, (p[0] + eps * n[0], p[1] + eps * n[1])):
        n = (-n[0], -n[1])
    assert in_material(loops, (p[0] + eps * n[0], p[1] + eps * n[1]))
    return n


def place_of(loops, p):
    """(loop, segment) of the segment p lies on."""
    best = None
    for i, segments in enumerate(loops):
        for j, s in enumerate(segments):
            if s.bulge == 0:
                d = (s.end[0] - s.start[0], s.end[1] - s.start[1])
                t = ((p[0] - s.start[0]) * d[0] + (p[1] - s.start[1]) * d[1]) / (
                    d[0] ** 2 + d[1] ** 2)
                q = s.point(min(1.0, max(0.0, t)))
                dist = math.dist(p, q)
            else:
                a = math.atan2(p[1] - s.center[1], p[0] - s.center[0]) - s.start_angle
                t = (a % (2 * math.pi)) / s.theta if s.theta > 0 else \
                    (-a % (2 * math.pi)) / -s.theta
                dist = abs(math.dist(p, s.center) - s.radius) if t <= 1 else math.inf
            if best is None or dist < best[0]:
                best = (dist, i, j)
    assert best[0] < 1e-9
    return best[1], best[2]


def check_fixels(path, fixture, loops, page):
    """Wedges for fixels on the outer loop; a pin in the hole for each on a
    hole's boundary, with an arrow along its normal into the material."""
    fixels = [f["at"] for f in fixture["fixels"]]
    places = [place_of(loops, p) for p in fixels]
    holes = [i for i, (l, _) in enumerate(places) if l > 0]
    assert len(svg_elements(path, "polygon", "fixel")) == len(fixels) - len(holes)
    assert len(svg_elements(path, "polygon", "friction-cone")) == len(fixels)
    pins = svg_elements(path, "circle", "pin")
    arrows = svg_elements(path, "line", "fixel-normal")
    assert len(pins) == len(arrows) == len(holes)
    for i, pin, arrow in zip(holes, pins, arrows):
        assert "fixel" in pin.get("class").split()
        at = fixels[i]
        hole = loops[places[i][0]]
        centre = (float(pin.get("cx")), float(pin.get("cy")))
        r = float(pin.get("r"))
        # Touching the hole's boundary at the contact, inside the hole.
        assert abs(math.dist(centre, page.page(at)) - r) < 0.02
        for k in range(36):
            a = 2 * math.pi * k / 36
            q = page.fixture((centre[0] + 0.98 * r * math.cos(a),
                              centre[1] + 0.98 * r * math.sin(a)))
            assert inside_loop(hole, q) and not in_material(loops, q), (i, q)
        # The arrow from the pin's centre along the normal, into the material.
        x1, y1, x2, y2 = (float(arrow.get(k)) for k in ("x1", "y1", "x2", "y2"))
        assert near((x1, y1), centre, 0.02)
        n = segment_normal(loops, *places[i], at)
        d = (x2 - x1, -(y2 - y1))
        length = math.hypot(*d)
        assert abs(d[0] / length - n[0]) < 1e-3 and abs(d[1] / length - n[1]) < 1e-3, (d, n)
        assert in_material(loops, page.fixture((x2, y2)))
        assert arrow.get("marker-end")
    return len(holes)


def check_regions(path, answer, loops, page):
    """One region path per region, in order; on an arc an arc of its
    segment's circle."""
    regions = answer["regions"]
    paths = svg_elements(path, "path", "region")
    assert len(paths) == len(regions)
    arcs = 0
    for element, r in zip(paths, regions):
        s = loops[r["loop"]][r["segment"]]
        t0, t1 = r["t0"], r["t1"]
        assert 0 <= t0 < t1 <= 1
        size = max(abs(v) for v in s.start + s.end) + 1
        assert math.dist(r["from"], s.point(t0)) < 1e-9 * size, (r, s.point(t0))
        assert math.dist(r["to"], s.point(t1)) < 1e-9 * size, (r, s.point(t1))
        sub = parse_path(element.get("d"))
        assert len(sub) == 1 and len(sub[0]) == 2, element.get("d")
        move, command = sub[0]
        assert near(move[1], page.page(s.point(t0)))
        if s.bulge == 0:
            assert command[0] == "L" and near(command[2], page.page(s.point(t1)))
        elif command[0] == "L":
            # A region too short to bow on the page: its sagitta < 0.005 px.
            theta = (t1 - t0) * s.theta
            assert 2 * s.radius * page.s * math.sin(theta / 4) ** 2 < 0.005
        else:
            check_arc(command, s, t0, t1, page)
            arcs += 1
    return arcs


@pytest.mark.parametrize("name", sorted(OUTLINES))
def test_outline_push_picture_draws_arcs_holes_and_pins(harness, name):
    path, fixture = outline_fixture(harness, name)
    set_name = OUTLINES[name][3]
    svg = harness.path(name + ".svg")
    answer = run("push", path, "--set", set_name, "--json", "--svg", svg)
    assert answer.returncode == 0, answer.stderr
    result = json.loads(answer.stdout)
    assert result["regions"] and all("loop" in r and "segment" in r for r in result["regions"])
    page, loops = check_outline(svg, fixture["body"]["shape"])
    arcs = check_regions(svg, result, loops, page)
    pins = check_fixels(svg, fixture, loops, page)
    assert len(svg_elements(svg, "g", "com")) == 1
    FIGURES["outline region arcs checked"] = FIGURES.get("outline region arcs checked", 0) + arcs
    FIGURES["outline pins checked"] = FIGURES.get("outline pins checked", 0) + pins
    assert arcs > 0
    if name in ("issue", "issue-cw", "bulb"):
        assert pins == 1
    if name == "cut-disc":
        # The whole 300 degree arc is a region: one arc with large-arc set.
        large = [c for e in svg_elements(svg, "path", "region")
                 for c in parse_path(e.get("d"))[0] if c[0] == "A" and c[5] == 1]
        assert large


def outline_examples():
    names = []
    for n in sorted(os.listdir(EXAMPLES)):
        if n.endswith(".json"):
            with open(os.path.join(EXAMPLES, n)) as f:
                shape = json.load(f)["body"].get("shape") or {}
            if shape.get("type") == "outline":
                names.append(n[:-len(".json")])
    return names


@pytest.mark.parametrize("name", outline_examples())
@pytest.mark.parametrize("set_name", ["goal", "strong", "both"])
def test_outline_example_pictures(harness, name, set_name):
    """Every example written as an outline, drawn and checked as above."""
    path = os.path.join(EXAMPLES, name + ".json")
    with open(path) as f:
        fixture = json.load(f)
    svg = harness.path("%s-%s.svg" % (name, set_name))
    answer = run("push", path, "--set", set_name, "--json", "--svg", svg)
    assert answer.returncode in (0, 1), answer.stderr
    page, loops = check_outline(svg, fixture["body"]["shape"])
    arcs = check_regions(svg, json.loads(answer.stdout), loops, page)
    pins = check_fixels(svg, fixture, loops, page)
    FIGURES["outline region arcs checked"] = FIGURES.get("outline region arcs checked", 0) + arcs
    FIGURES["outline pins checked"] = FIGURES.get("outline pins checked", 0) + pins


@pytest.mark.parametrize("name", ["issue", "bulb"])
def test_outline_gravity_and_margin_pictures(harness, name):
    path, fixture = outline_fixture(harness, name)
    shape = fixture["body"]["shape"]
    dial = harness.path("dial.svg")
    answer = run("gravity", path, "--set", "strong", "--json", "--svg", dial)
    assert answer.returncode in (0, 1), answer.stderr
    arcs = json.loads(answer.stdout)["intervals_deg"]
    assert len(svg_elements(dial, "path", "region")) == len(arcs)
    assert len(svg_elements(dial, "circle", "dial")) == 1
    page, loops = check_outline(dial, shape)
    check_fixels(dial, fixture, loops, page)
    picture = harness.path("margin.svg")
    answer = run("margin", path, "-1,-1,0", "--svg", picture)
    assert answer.returncode in (0, 1), answer.stderr
    page, loops = check_outline(picture, shape)
    check_fixels(picture, fixture, loops, page)
    assert not svg_elements(picture, "path", "region")


def test_outline_picture_of_a_stored_fixture(harness):
    """Through the daemon: wrenchctl draws a stored outline from fixture.get
    (bulges written only when nonzero)."""
    daemon = harness.start()
    path, fixture = outline_fixture(harness, "issue")
    env = dict(os.environ, WRENCHD_SOCKET=daemon.path)
    put = subprocess.run([WRENCHCTL, "put", path], capture_output=True, text=True, env=env,
                         timeout=60)
    assert put.returncode == 0, put.stderr
    fixture_id = put.stdout.split()[0]
    svg = harness.path("stored.svg")
    answer = subprocess.run([WRENCHCTL, "push", fixture_id, "--set", "strong", "--json",
                             "--svg", svg], capture_output=True, text=True, env=env, timeout=60)
    assert answer.returncode == 0, answer.stderr
    page, loops = check_outline(svg, fixture["body"]["shape"])
    assert check_regions(svg, json.loads(answer.stdout), loops, page) > 0
    assert check_fixels(svg, fixture, loops, page) == 1
    local = harness.path("local.svg")
    assert run("push", path, "--set", "strong", "--svg", local).returncode == 0
    with open(svg) as a, open(local) as b:
        assert a.read() == b.read()


def region_intervals(path, centre):
    """The region arcs of a picture as angles (degrees, counter-clockwise in
    the fixture's frame, about `centre` on the page), merged where they
    meet, as [a, b] with 0 <= a < 360 and a < b."""
    def angle(q):
        return math.degrees(math.atan2(-(q[1] - centre[1]), q[0] - centre[0])) % 360

    spans = []
    for element in svg_elements(path, "path", "region"):
        sub = parse_path(element.get("d"))
        assert len(sub) == 1
        # The ends give the angles (well conditioned); SVG's reading of the
        # arcs only which way round and roughly how far.
        rough = 0.0
        for command in sub[0][1:]:
            assert command[0] == "A", command
            _, delta = svg_arc_center(command[1], command[2], command[5], command[6],
                                      command[7])[1:]
            rough -= math.degrees(delta)     # the page's angles turn the other way
        a, b = angle(sub[0][0][1]), angle(sub[0][-1][-1])
        total = (b - a) % 360 if rough > 0 else -((a - b) % 360)
        if abs(total - rough) > 180:
            total += 360 if rough > total else -360
        spans.append([a, a + total] if total > 0 else [a + total, a])
    spans = sorted([s[0] % 360, s[0] % 360 + (s[1] - s[0])] for s in spans)
    merged = []
    for s in spans:
        if merged and s[0] - merged[-1][1] < 1e-3:
            merged[-1][1] = max(merged[-1][1], s[1])
        else:
            merged.append(s)
    if len(merged) > 1 and merged[-1][1] - 360 > merged[0][0] - 1e-3:
        merged[0] = [merged[-1][0], merged[0][1] + 360]
        merged.pop()
    return merged


@pytest.mark.parametrize("set_name", ["goal", "strong", "both"])
def test_circle_as_two_half_arcs_draws_the_circles_regions(harness, set_name):
    """disc-corner, and the same disc written as an outline of two half
    circles (split at 30 and 210 degrees, not where the circle splits its
    regions): the same region arcs."""
    with open(os.path.join(EXAMPLES, "disc-corner.json")) as f:
        disc = json.load(f)
    outline = json.loads(json.dumps(disc))
    outline["name"] = "disc-corner-outline"
    outline["body"]["shape"] = {"type": "outline", "loops": [
        [[COS30, 0.5, 1], [-COS30, -0.5, 1]]]}
    disc_path, outline_path = harness.path("disc.json"), harness.path("outline.json")
    for fixture, p in ((disc, disc_path), (outline, outline_path)):
        with open(p, "w") as f:
            json.dump(fixture, f)
    disc_svg, outline_svg = harness.path("disc.svg"), harness.path("outline.svg")
    a = run("push", disc_path, "--set", set_name, "--json", "--svg", disc_svg)
    b = run("push", outline_path, "--set", set_name, "--json", "--svg", outline_svg)
    assert a.returncode == b.returncode and a.returncode in (0, 1), (a.stderr, b.stderr)
    circle = svg_elements(disc_svg, "circle", "outline")[0]
    expected = region_intervals(disc_svg, (float(circle.get("cx")), float(circle.get("cy"))))
    page, loops = check_outline(outline_svg, outline["body"]["shape"])
    check_regions(outline_svg, json.loads(b.stdout), loops, page)
    got = region_intervals(outline_svg, page.page((0.0, 0.0)))
    assert len(got) == len(expected), (got, expected)
    for g, e in zip(got, expected):
        assert abs(g[0] - e[0]) < 0.01 and abs(g[1] - e[1]) < 0.01, (got, expected)
    if set_name == "goal":
        assert expected      # the disc in a corner has a goal region
    # The page is the same (same bounds): the outline's circle is the disc's.
    assert near(page.page((0.0, 0.0)), (float(circle.get("cx")), float(circle.get("cy"))), 0.02)
    assert abs(page.s - float(circle.get("r"))) < 0.02


def legend(path):
    return [e.text for e in svg_elements(path, "text") if e.get("y") in ("22", "40", "58")]


def test_finger_radius_in_the_legend(harness):
    """--finger-radius is sent as finger_radius and named in the picture's
    legend when given; without it the legend is as before."""
    disc = os.path.join(EXAMPLES, "disc-corner.json")
    svg = harness.path("r.svg")
    answer = run("push", disc, "--finger-radius", "0.5", "--finger-friction", "0.2", "--svg", svg)
    assert answer.returncode in (0, 1), answer.stderr
    assert "fixel friction \u03bc = 0.5; finger friction 0.2; finger radius 0.5" in legend(svg)
    answer = run("push", disc, "--finger-radius", "0.5", "--svg", svg)
    assert answer.returncode in (0, 1), answer.stderr
    assert "fixel friction \u03bc = 0.5; finger radius 0.5" in legend(svg)
    path, _ = outline_fixture(harness, "issue")
    answer = run("push", path, "--set", "strong", "--finger-radius", "0", "--svg", svg)
    assert answer.returncode == 0, answer.stderr
    assert "fixel friction \u03bc = 0.3; finger radius 0" in legend(svg)
    answer = run("push", path, "--set", "strong", "--svg", svg)
    assert not [t for t in legend(svg) if "radius" in t]


@pytest.mark.parametrize("value", ["-1", "x", "nan", "inf"])
def test_bad_finger_radius_is_a_usage_error(value):
    r = run("push", os.path.join(EXAMPLES, "disc-corner.json"), "--finger-radius", value)
    assert r.returncode == 2 and "--finger-radius" in r.stderr


def test_finger_radius_in_help():
    r = subprocess.run([WRENCHCTL, "push", "--help"], capture_output=True, text=True,
                       timeout=60)
    assert "--finger-radius R" in r.stdout
    with open(os.path.join(REPO, "clients", "wrenchctl", "wrenchctl.1")) as f:
        assert "finger\\-radius" in f.read()


def test_outline_regions_printed_by_loop_and_segment(harness):
    path, _ = outline_fixture(harness, "issue")
    answer = run("push", path, "--set", "strong", "--push-on", "all")
    assert answer.returncode == 0, answer.stderr
    lines = answer.stdout.splitlines()
    assert lines[0].split()[:4] == ["loop", "segments", "from", "to"]
    # The table (a row per region, its pieces under it), its summary, and
    # what the strong set promises.
    assert lines[-2].startswith("set strong: ") and lines[-1].startswith("strong: "), lines
    rows = [l.split() for l in lines[1:-2] if not l.lstrip().startswith("pieces:")]
    assert rows and all(r[0] in ("0", "1") for r in rows)
    assert any(r[0] == "1" for r in rows)    # a region in the hole
    # By default a point finger pushes on the outer boundary only.
    outer = run("push", path, "--set", "strong").stdout.splitlines()
    assert all(l.split()[0] == "0" for l in outer[1:-2] if not l.lstrip().startswith("pieces:"))
