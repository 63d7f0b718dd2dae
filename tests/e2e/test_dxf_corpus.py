"""clients/python/wrenchd_dxf.py on the corpus of tests/e2e/dxf_corpus.py:
drawings made the way real ones are (several parts, duplicates, stray lines,
splines and ellipses, inches, faceted arcs, 72 holes, symmetric parts, a
washer in its bore, block references).  Each is read with default options
(but the layers its facts name) and checked against what the drawing holds,
computed here: each part's area and extent by ezdxf's own flattening of the
entities drawn for it, its holes, and the counts of duplicates, stray
chains and curves; the arcs that follow each SPLINE and ELLIPSE against
ezdxf's own evaluation of the curve, both ways."""

import json
import math
import os
import sys

import pytest

from conftest import REPO

try:
    import ezdxf
except ImportError as error:            # pragma: no cover
    pytest.skip("ezdxf is not importable by %s (%s): apt-get install python3-ezdxf"
                % (sys.executable, error), allow_module_level=True)

sys.path.insert(0, os.path.join(REPO, "clients", "python"))
import wrenchd_dxf  # noqa: E402

import dxf_corpus  # noqa: E402

NAMES = [make.__name__ for make in dxf_corpus.DRAWINGS]
FLAT = 1e-5            # ezdxf's flattening: chords within this of the curves


@pytest.fixture(scope="module")
def corpus(tmp_path_factory):
    out = tmp_path_factory.mktemp("corpus")
    assert dxf_corpus.write(str(out)) == NAMES
    return str(out)


def facts_of(corpus, name):
    with open(os.path.join(corpus, name + ".json")) as fh:
        return json.load(fh)


# ---- this test's own geometry: ezdxf's flattening -------------------------------

def entity(doc, ref):
    """The entity a fact names: a handle, or "H#k", the k-th entity block
    reference H explodes into."""
    if "#" in ref:
        handle, k = ref.split("#")
        return list(doc.entitydb[handle].virtual_entities())[int(k)]
    return doc.entitydb[ref]


def chain(pieces):
    """Pieces of a loop in order around it, each turned to continue the one
    before."""
    pts = []
    for piece in pieces:
        piece = list(piece)
        if pts:
            last = pts[-1]
            if math.dist(piece[-1], last) < math.dist(piece[0], last):
                piece.reverse()
        elif len(pieces) > 1:
            # the first piece runs towards the second
            nxt = pieces[1]
            ends = (nxt[0], nxt[-1])
            if min(math.dist(piece[0], q) for q in ends) < min(math.dist(piece[-1], q) for q in ends):
                piece.reverse()
        pts += piece
    return pts


def flattened(doc, refs):
    """The polygon of a loop drawn as these entities in order around it."""
    return chain([flatten(entity(doc, ref), FLAT) for ref in refs])


def flatten(e, distance):
    """ezdxf's points along an entity, chords within `distance` of it: each
    curve's own flattening (ezdxf 0.18's paths put cubic Beziers for arcs
    and ellipses, 1.5e-3 off on an ellipse 12 across, and run an unclamped
    B-spline over all its knots); a polyline's LINEs and ARCs, as ezdxf
    explodes it."""
    kind = e.dxftype()
    if kind == "LINE":
        return [(e.dxf.start.x, e.dxf.start.y), (e.dxf.end.x, e.dxf.end.y)]
    if kind in ("LWPOLYLINE", "POLYLINE"):
        pieces = [flatten(v, distance) for v in e.virtual_entities()]
        pts = chain(pieces)
        return pts
    return [(v.x, v.y) for v in e.flattening(distance)]


def shoelace(pts):
    return sum(pts[i][0] * pts[(i + 1) % len(pts)][1] - pts[(i + 1) % len(pts)][0] * pts[i][1]
               for i in range(len(pts))) / 2.0


def drawn_parts(doc, facts):
    """Per part: its net area and extent as drawn, and its hole count,
    largest first, in the fixture's unit."""
    k = facts["scale"]
    out = []
    for part in facts["parts"]:
        outer = flattened(doc, part["outer"])
        area = abs(shoelace(outer)) - sum(abs(shoelace(flattened(doc, h))) for h in part["holes"])
        xs, ys = [p[0] for p in outer], [p[1] for p in outer]
        out.append({"area": area * k * k, "extent": [min(xs) * k, min(ys) * k, max(xs) * k, max(ys) * k],
                    "holes": len(part["holes"])})
    return sorted(out, key=lambda p: -p["area"])


# ---- the reader against the drawings ------------------------------------------------

AGREEMENT = {}
READ = {}              # name -> read_dxf's answer, read once a session


def read(corpus, name):
    if name not in READ:
        facts = facts_of(corpus, name)
        READ[name] = wrenchd_dxf.read_dxf(os.path.join(corpus, name + ".dxf"), layers=facts["layers"])
    return READ[name]


@pytest.mark.parametrize("name", NAMES)
def test_corpus_drawing(corpus, name):
    facts = facts_of(corpus, name)
    path = os.path.join(corpus, name + ".dxf")
    parts, report = read(corpus, name)
    doc = ezdxf.readfile(path)
    want = drawn_parts(doc, facts)
    assert len(parts) == len(want), (name, [p["area"] for p in parts], want)
    # the arcs' distance from the curves and the flattening's chords, over
    # each part's perimeter, bound the areas' difference
    size = report["extent"] * facts["scale"]
    worst = 0.0
    for got, drawn in zip(parts, want):
        assert got["holes"] == drawn["holes"], name
        perimeter = 2 * (drawn["extent"][2] - drawn["extent"][0] + drawn["extent"][3] - drawn["extent"][1])
        perimeter *= 1 + drawn["holes"]
        slack = (FLAT * facts["scale"] + report["curve_tolerance"] * facts["scale"]) * perimeter * 4
        assert abs(got["area"] - drawn["area"]) <= slack, (name, got["area"], drawn["area"])
        worst = max(worst, abs(got["area"] - drawn["area"]) / drawn["area"])
        for a, b in zip(got["extent"], drawn["extent"]):
            assert abs(a - b) <= 2 * (FLAT + report["curve_tolerance"]) * facts["scale"] + 1e-12 * size, \
                (name, got["extent"], drawn["extent"])
        # the shape's own loops give that area (outer counter-clockwise, holes clockwise)
        loops = got["shape"]["loops"]
        assert len(loops) == 1 + drawn["holes"]
    AGREEMENT[name] = worst
    assert report["duplicates_merged"] == facts["duplicates"], (name, report["duplicates"])
    assert len(report["stray"]) == facts["stray"], (name, report["stray"])
    assert len(report["curves"]) == facts["curves"], name
    assert report["units"]["unit"] == facts["unit"] and report["units"]["scale"] == facts["scale"]
    assert report["curve_deviation"] <= report["curve_tolerance"]
    # the command line takes it too, and names the other parts
    args = [] if not facts["layers"] else sum((["--layer", n] for n in facts["layers"]), [])
    code, out, err = run(path, *args)
    assert code == 0 and json.loads(out) == parts[0]["shape"], err
    assert ("other part" in err) == (len(parts) > 1)


def run(path, *args):
    import subprocess
    p = subprocess.run([sys.executable, os.path.join(REPO, "clients", "python", "wrenchd_dxf.py"),
                        path] + list(args), capture_output=True, text=True, timeout=120)
    return p.returncode, p.stdout, p.stderr


def test_corpus_summary(corpus):
    """Every drawing read; the areas' worst relative difference from ezdxf's
    flattening (printed with -s)."""
    done = 0
    for name in NAMES:
        parts, _ = read(corpus, name)
        done += len(parts) == len(facts_of(corpus, name)["parts"])
    assert done == len(NAMES)
    print("\ncorpus: %d of %d drawings read; areas within %s of ezdxf's flattening" % (
        done, len(NAMES), ", ".join("%s %.1e" % kv for kv in sorted(AGREEMENT.items()))))


# ---- curves against ezdxf's own evaluation ------------------------------------------

def arc_points(loop, per=16):
    """Points along each segment of a loop [x, y(, b)] (this test's own
    arithmetic: the centre from the chord and the bulge)."""
    n = len(loop)
    for i in range(n):
        x0, y0 = loop[i][0], loop[i][1]
        b = loop[i][2] if len(loop[i]) > 2 else 0.0
        x1, y1 = loop[(i + 1) % n][0], loop[(i + 1) % n][1]
        for k in range(per):
            t = k / per
            if not b:
                yield (x0 + t * (x1 - x0), y0 + t * (y1 - y0))
                continue
            theta = 4 * math.atan(b)
            L = math.hypot(x1 - x0, y1 - y0)
            r = L / (2 * math.sin(abs(theta) / 2))
            # the centre: from the chord's midpoint along its left normal
            h = r * math.cos(theta / 2) * (1 if b > 0 else -1)
            mx, my = (x0 + x1) / 2, (y0 + y1) / 2
            cx, cy = mx - (y1 - y0) / L * h, my + (x1 - x0) / L * h
            a = math.atan2(y0 - cy, x0 - cx) + t * theta
            yield (cx + r * math.cos(a), cy + r * math.sin(a))


class Near:
    """A dense polyline with its segments in a grid of cells, to find the
    distance from a point near it quickly (this test's own)."""

    def __init__(self, pts, cell):
        self.pts, self.cell, self.grid = pts, cell, {}
        for k, (a, b) in enumerate(zip(pts, pts[1:])):
            for gx in range(math.floor(min(a[0], b[0]) / cell), math.floor(max(a[0], b[0]) / cell) + 1):
                for gy in range(math.floor(min(a[1], b[1]) / cell), math.floor(max(a[1], b[1]) / cell) + 1):
                    self.grid.setdefault((gx, gy), []).append(k)

    def distance(self, p):
        """The distance to the polyline when within a cell of it, else inf."""
        gx, gy = math.floor(p[0] / self.cell), math.floor(p[1] / self.cell)
        ks = {k for i in (-1, 0, 1) for j in (-1, 0, 1) for k in self.grid.get((gx + i, gy + j), ())}
        return min((point_to_polyline(p, self.pts[k:k + 2]) for k in ks), default=math.inf)


def point_to_polyline(p, pts):
    best = math.inf
    for a, b in zip(pts, pts[1:]):
        dx, dy = b[0] - a[0], b[1] - a[1]
        ll = dx * dx + dy * dy
        t = 0 if ll == 0 else max(0, min(1, ((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / ll))
        best = min(best, math.hypot(p[0] - a[0] - t * dx, p[1] - a[1] - t * dy))
    return best


@pytest.mark.parametrize("name", ["curves", "several_parts"])
@pytest.mark.parametrize("tolerance", [None, 1e-3])
def test_curves_against_ezdxf(corpus, name, tolerance):
    """Each SPLINE's and ELLIPSE's points as ezdxf evaluates them lie within
    the curve tolerance of the reader's arcs, and the arcs' points within it
    (and the flattening's sagitta) of ezdxf's curve."""
    path = os.path.join(corpus, name + ".dxf")
    parts, report = wrenchd_dxf.read_dxf(path, curve_tolerance=tolerance)
    tol = report["curve_tolerance"]
    if tolerance is not None:
        assert tol == tolerance
    doc = ezdxf.readfile(path)
    shapes_points = []
    for part in parts:
        for loop in part["shape"]["loops"]:
            shapes_points.append(list(arc_points(loop)))
    for e in doc.modelspace().query("SPLINE ELLIPSE"):
        tool = e.construction_tool()
        if e.dxftype() == "SPLINE":
            knots, p = tool.knots(), tool.degree
            u0, u1 = knots[p], knots[-p - 1]
            curve = [(v.x, v.y) for v in tool.points([u0 + (u1 - u0) * k / 400 for k in range(401)])]
        else:
            curve = [(v.x, v.y) for v in tool.vertices(tool.params(401))]
        dense = flatten(e, tol / 100)
        # ezdxf's points to the arcs: the nearest of the part's sampled
        # segments, the samples 1/16 of a segment apart, so measured to the
        # loops exactly below
        found = 0.0
        for p in curve[::8]:
            d = min(distance_to_loops(p, parts))
            assert d <= tol * (1 + 1e-9), (e.dxftype(), p, d, tol)
            found = max(found, d)
        # the arcs' points near this curve to ezdxf's flattening of it
        box = (min(q[0] for q in dense) - 2 * tol, min(q[1] for q in dense) - 2 * tol,
               max(q[0] for q in dense) + 2 * tol, max(q[1] for q in dense) + 2 * tol)
        # (points of the lines beyond an open curve's ends are nearest its
        # ends: not the curve's)
        closed = math.dist(dense[0], dense[-1]) <= tol
        coarse = dense[::max(1, len(dense) // 200)]
        coarse_index = Near(coarse, 50 * tol)
        near = [q for pts in shapes_points for q in pts
                if box[0] <= q[0] <= box[2] and box[1] <= q[1] <= box[3]
                and coarse_index.distance(q) <= 50 * tol]
        near = [q for q in near if closed or min(math.dist(q, dense[0]), math.dist(q, dense[-1])) > 50 * tol]
        assert near
        index = Near(dense, 4 * tol)
        worst = max(index.distance(q) for q in near)
        assert worst <= tol * 1.01 + tol / 100, (e.dxftype(), worst, tol)
        # what the reader reports it measured is what is found here, both
        # ways (within the flattening's tol / 100)
        reported = [c["deviation"] for c in report["curves"] if c["entity"].startswith(
            "%s (handle %s," % (e.dxftype(), e.dxf.handle))][0]
        assert max(found, worst) <= reported * 1.02 + tol / 100, (e.dxftype(), found, worst, reported)
        assert reported <= max(found, worst) * 1.5 + tol / 100, (e.dxftype(), found, worst, reported)


def distance_to_loops(p, parts):
    """The distance from p to each loop of the parts (this test's own: to
    lines, and to arcs by their circle where the angle is within the arc)."""
    for part in parts:
        for loop in part["shape"]["loops"]:
            best = math.inf
            n = len(loop)
            for i in range(n):
                x0, y0 = loop[i][0], loop[i][1]
                b = loop[i][2] if len(loop[i]) > 2 else 0.0
                x1, y1 = loop[(i + 1) % n][0], loop[(i + 1) % n][1]
                if not b:
                    best = min(best, point_to_polyline(p, [(x0, y0), (x1, y1)]))
                    continue
                theta = 4 * math.atan(b)
                L = math.hypot(x1 - x0, y1 - y0)
                r = L / (2 * math.sin(abs(theta) / 2))
                h = r * math.cos(theta / 2) * (1 if b > 0 else -1)
                mx, my = (x0 + x1) / 2, (y0 + y1) / 2
                cx, cy = mx - (y1 - y0) / L * h, my + (x1 - x0) / L * h
                a0 = math.atan2(y0 - cy, x0 - cx)
                ap = math.atan2(p[1] - cy, p[0] - cx)
                turn = ((ap - a0) * (1 if theta > 0 else -1)) % (2 * math.pi)
                if turn <= abs(theta):
                    best = min(best, abs(math.hypot(p[0] - cx, p[1] - cy) - r))
                else:
                    best = min(best, math.hypot(p[0] - x0, p[1] - y0), math.hypot(p[0] - x1, p[1] - y1))
            yield best


# ---- the drawing's unit in the fixture, and in wrenchctl's tables and pictures ----

WRENCHCTL = os.path.join(REPO, "build", "wrenchctl")


@pytest.mark.parametrize("with_units", [True, False])
def test_units_into_the_fixture_and_wrenchctl(corpus, tmp_path, with_units, client):
    """The inch plate's shape and its unit (fixture_units) make a fixture
    the daemon takes, units and all; wrenchctl's table and picture name the
    unit, and say nothing of units for the same fixture without them."""
    shape, report = wrenchd_dxf.shape_from_dxf(os.path.join(corpus, "inches.dxf"))
    fixture = {"name": "inch-plate", "body": {"mass": 0.2, "shape": shape},
               "friction": {"static": 0.3},
               "fixels": [{"at": [1, 0]}, {"at": [3, 0]}, {"at": [0, 1.25]}]}
    if with_units:
        fixture["units"] = wrenchd_dxf.fixture_units(report)
        assert fixture["units"] == {"length": "in", "force": "N"}
    stored = client.result("fixture.get", {"id": client.result("fixture.put", {"fixture": fixture})["id"]})
    assert stored.get("units") == fixture.get("units")
    path = tmp_path / "plate.json"
    path.write_text(json.dumps(fixture))
    svg = tmp_path / "plate.svg"
    import subprocess
    p = subprocess.run([WRENCHCTL, "--local", "push", str(path), "--set", "goal", "--svg", str(svg)],
                       capture_output=True, text=True, timeout=60)
    assert p.returncode in (0, 1) and "region" in p.stdout, p.stderr     # 1: no region
    line = "units: lengths in in, forces in N (the fixture's)"
    assert (p.stdout.splitlines()[0] == line) == with_units and (line in p.stdout) == with_units
    picture = svg.read_text()
    assert ('<text class="units"' in picture and ">lengths in in</text>" in picture) == with_units
    # the friction sweep's plot: its axis of lengths in inches
    p = subprocess.run([WRENCHCTL, "--local", "sweep", str(path), "--push", "both", "--range", "0:1",
                        "--svg", str(svg)], capture_output=True, text=True, timeout=60)
    assert p.returncode in (0, 1), p.stderr
    assert (p.stdout.splitlines()[0] == line) == with_units
    picture = svg.read_text()
    assert ("push region length (in)</text>" in picture) == with_units
    assert ("push region length</text>" in picture) != with_units


# ---- the README's walk-through --------------------------------------------------------

def readme_blocks(after):
    """The fenced blocks of README.md's walk-through section after the line
    holding `after`, in order."""
    with open(os.path.join(REPO, "README.md")) as fh:
        text = fh.read()
    text = text[text.index("### From a drawing to a fixture: a walk-through"):]
    text = text[text.index(after):]
    blocks, inside, lines = [], False, []
    for line in text.splitlines():
        if line.startswith("```"):
            if inside:
                blocks.append(lines)
                lines = []
            inside = not inside
        elif inside:
            lines.append(line)
    return blocks


def test_readme_walkthrough(tmp_path):
    """The README's walk-through, its commands as written (build/ and
    examples/ from the checkout): what it quotes of the reader's report and
    of the design is what they print, word for word, and the picture is
    docs/pictures/sheet-bracket-push-both.svg (make pictures)."""
    import shlex
    import subprocess
    blocks = readme_blocks("[`examples/sheet_dxf.py`]")
    commands = [b for b in blocks if b and b[0].startswith(("/usr/bin/python3", "build/"))]
    quoted = [b for b in blocks if b not in commands]
    outputs = []
    for block in commands:
        for line in block:
            words = shlex.split(line)
            out_file = None
            if ">" in words:
                out_file = words[words.index(">") + 1]
                words = words[:words.index(">")]
            words = [os.path.join(REPO, w) if w.startswith(("examples/", "clients/", "build/")) else w
                     for w in words]
            p = subprocess.run(words, cwd=str(tmp_path), capture_output=True, text=True, timeout=120)
            assert p.returncode == 0, (line, p.stderr)
            if out_file:
                (tmp_path / out_file).write_text(p.stdout)
            outputs.append((line, p.stdout, p.stderr))
    report = [o for o in outputs if "wrenchd_dxf.py sheet.dxf" in o[0]][0][2]
    assert quoted[0] == report.splitlines()
    design = [o for o in outputs if " design " in o[0]][0][1].splitlines()
    assert [line for line in quoted[1] if line != "..."] == design[:len(quoted[1]) - 1]
    # the design written as a fixture, and its push table as quoted: the
    # both region 15.6 mm of the left edge (loop 0), none in a hole (a point
    # finger pushes on the outer boundary only)
    push = [o for o in outputs if " push " in o[0]][0][1].splitlines()
    assert quoted[2] == push
    assert push[0] == "units: lengths in mm, forces in N (the fixture's)"
    assert push[2].split()[:2] == ["0", "66"] and push[2].split()[-1] == "15.648774"
    shape = json.loads((tmp_path / "bracket-shape.json").read_text())
    fixture = json.loads((tmp_path / "bracket.json").read_text())
    assert fixture["body"]["shape"] == shape and fixture["units"] == {"length": "mm", "force": "N"}
    designed = json.loads((tmp_path / "bracket-design.json").read_text())
    assert designed["body"] == fixture["body"] and designed["units"] == fixture["units"]
    assert len(designed["fixels"]) == 3
    with open(os.path.join(REPO, "docs", "pictures", "sheet-bracket-push-both.svg")) as fh:
        assert (tmp_path / "bracket-push-both.svg").read_text() == fh.read(), \
            "run 'make pictures' and commit docs/pictures"
