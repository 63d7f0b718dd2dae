"""clients/python/wrenchd_dxf.py: the outline of a part from a DXF drawing.
The drawings are written here with ezdxf (and one by FreeCAD,
tests/e2e/data/); the expected loops, areas and centroids come from the
drawing's own numbers and closed forms, with an area and centroid routine of
this file's own (chord polygon plus circular segments), not from the tool."""

import ast
import json
import math
import os
import random
import subprocess
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

TOOL = os.path.join(REPO, "clients", "python", "wrenchd_dxf.py")
DATA = os.path.join(os.path.dirname(os.path.abspath(__file__)), "data")
Q = math.tan(math.pi / 8)               # the bulge of a quarter circle


# ---- this test's own geometry ------------------------------------------------

def loop_moments(loop):
    """Signed area and first moments (A, Sx, Sy) of a loop of [x, y(, b)]:
    Green's theorem on the chord polygon, plus each arc's circular segment
    (area r^2/2 (t - sin t), centroid 4 r sin^3(t/2) / (3 (t - sin t)) from
    the centre towards the arc's midpoint)."""
    a = sx = sy = 0.0
    n = len(loop)
    for i in range(n):
        x0, y0 = loop[i][0], loop[i][1]
        b = loop[i][2] if len(loop[i]) > 2 else 0.0
        x1, y1 = loop[(i + 1) % n][0], loop[(i + 1) % n][1]
        cross = x0 * y1 - x1 * y0
        a += cross / 2
        sx += (x0 + x1) * cross / 6
        sy += (y0 + y1) * cross / 6
        if b:
            L = math.hypot(x1 - x0, y1 - y0)
            t = 4 * math.atan(abs(b))                    # the arc's angle
            r = L / (2 * math.sin(t / 2))
            # unit vector from the chord towards the arc's midpoint: right of
            # the travel for a counter-clockwise arc (b > 0), left for b < 0
            ux, uy = math.copysign(1, b) * (y1 - y0) / L, -math.copysign(1, b) * (x1 - x0) / L
            mx, my = (x0 + x1) / 2 + ux * abs(b) * L / 2, (y0 + y1) / 2 + uy * abs(b) * L / 2
            cx, cy = mx - ux * r, my - uy * r           # the centre
            seg = r * r / 2 * (t - math.sin(t))
            d = 4 * r * math.sin(t / 2) ** 3 / (3 * (t - math.sin(t)))
            s = math.copysign(1, b)
            a += s * seg
            sx += s * seg * (cx + ux * d)
            sy += s * seg * (cy + uy * d)
    return a, sx, sy


def area_centroid(shape):
    """Net area and centroid of a shape: its first loop less the others,
    whichever way each runs."""
    A = SX = SY = 0.0
    for k, loop in enumerate(shape["loops"]):
        a, sx, sy = loop_moments(loop)
        s = math.copysign(1, a) * (1 if k == 0 else -1)
        A, SX, SY = A + s * a, SX + s * sx, SY + s * sy
    return A, SX / A, SY / A


def reverse(loop):
    """The loop run the other way (this test's own)."""
    n = len(loop)
    out = []
    for i in range(n):
        j = (-i) % n                      # vertices v0, v_{n-1}, ..., v1
        prev = loop[(j - 1) % n]          # the segment v_{j-1} -> v_j, reversed
        b = prev[2] if len(prev) > 2 else 0.0
        out.append([loop[j][0], loop[j][1]] + ([-b] if b else []))
    return out


def canonical(loop):
    """Counter-clockwise, from its least vertex: to compare loops up to
    orientation and the first vertex."""
    loop = [list(v) if len(v) > 2 and v[2] else [v[0], v[1]] for v in loop]
    if loop_moments(loop)[0] < 0:
        loop = reverse(loop)
    k = min(range(len(loop)), key=lambda i: (loop[i][0], loop[i][1]))
    return loop[k:] + loop[:k]


def same_loop(got, want, tol=0.0):
    g, w = canonical(got), canonical(want)
    assert len(g) == len(w), (got, want)
    for u, v in zip(g, w):
        assert len(u) == len(v), (got, want)
        for p, q in zip(u, v):
            assert abs(p - q) <= tol, (got, want)


def same_shape(got, want, tol=0.0):
    assert got["type"] == "outline"
    assert len(got["loops"]) == len(want["loops"])
    same_loop(got["loops"][0], want["loops"][0], tol)
    rest = [canonical(lp) for lp in got["loops"][1:]]
    for lp in want["loops"][1:]:
        c = canonical(lp)
        match = [r for r in rest if len(r) == len(c) and all(
            len(u) == len(v) and all(abs(p - q) <= tol for p, q in zip(u, v)) for u, v in zip(r, c))]
        assert match, ("hole not found", lp, got["loops"][1:])
        rest.remove(match[0])


def orientation_ok(shape):
    """The tool's convention: outer counter-clockwise, holes clockwise."""
    signs = [loop_moments(lp)[0] for lp in shape["loops"]]
    return signs[0] > 0 and all(s < 0 for s in signs[1:])


def all_floats(shape):
    return all(isinstance(c, float) for lp in shape["loops"] for v in lp for c in v)


# ---- writing drawings ------------------------------------------------------------

def new_doc(units=4):
    doc = ezdxf.new("R2010")
    doc.header["$INSUNITS"] = units
    return doc


def save(doc, tmp_path, name="part.dxf"):
    path = str(tmp_path / name)
    doc.saveas(path)
    return path


def run(path, *args):
    p = subprocess.run([sys.executable, TOOL, path] + list(args), capture_output=True,
                       text=True, timeout=60)
    return p.returncode, p.stdout, p.stderr


def refused(path, *words, **kw):
    with pytest.raises(wrenchd_dxf.DxfShapeError) as info:
        wrenchd_dxf.shape_from_dxf(path, **kw)
    message = str(info.value)
    for w in words:
        assert w in message, (w, message)
    return message


# ---- polylines -------------------------------------------------------------------

def test_rectangle_lwpolyline(tmp_path):
    doc = new_doc()
    doc.modelspace().add_lwpolyline([(0, 0), (40, 0), (40, 25), (0, 25)], format="xy", close=True)
    shape, report = wrenchd_dxf.shape_from_dxf(save(doc, tmp_path))
    assert shape == {"type": "outline", "loops": [[[0.0, 0.0], [40.0, 0.0], [40.0, 25.0], [0.0, 25.0]]]}
    assert all_floats(shape)
    A, cx, cy = area_centroid(shape)
    assert (A, cx, cy) == (1000.0, 20.0, 12.5)
    assert report["used"] == {"LWPOLYLINE": 1} and report["loops"] == 1 and report["holes"] == 0
    assert report["tolerance"] == pytest.approx(1e-6 * math.hypot(40, 25))


def test_closed_polyline_repeating_its_first_point_and_running_clockwise(tmp_path):
    doc = new_doc()
    doc.modelspace().add_lwpolyline([(0, 0), (0, 25), (40, 25), (40, 0), (0, 0)], format="xy", close=True)
    shape, report = wrenchd_dxf.shape_from_dxf(save(doc, tmp_path))
    assert report["zero_length_segments_dropped"] == 1
    # turned counter-clockwise, from the same first vertex
    assert shape["loops"] == [[[0.0, 0.0], [40.0, 0.0], [40.0, 25.0], [0.0, 25.0]]]


def rounded_rectangle(w, h, r):
    """A w x h rectangle from (0, 0), corners rounded with radius r, counter-clockwise."""
    return [[r, 0, 0], [w - r, 0, Q], [w, r, 0], [w, h - r, Q], [w - r, h, 0], [r, h, Q],
            [0, h - r, 0], [0, r, Q]]


@pytest.mark.parametrize("clockwise", [False, True])
def test_rounded_rectangle_with_bulges(tmp_path, clockwise):
    w, h, r = 60.0, 30.0, 5.0
    pts = rounded_rectangle(w, h, r)
    drawn = reverse(pts) if clockwise else pts
    doc = new_doc()
    doc.modelspace().add_lwpolyline([(v[0], v[1], v[2] if len(v) > 2 else 0) for v in drawn],
                                    format="xyb", close=True)
    shape, report = wrenchd_dxf.shape_from_dxf(save(doc, tmp_path))
    same_loop(shape["loops"][0], pts)
    assert orientation_ok(shape) and all_floats(shape)
    # the last vertex's bulge closes the loop: it is in the output
    assert sum(1 for v in shape["loops"][0] if len(v) == 3) == 4
    A, cx, cy = area_centroid(shape)
    assert A == pytest.approx(w * h - (4 - math.pi) * r * r, rel=1e-14)
    assert (cx, cy) == (pytest.approx(w / 2, rel=1e-13), pytest.approx(h / 2, rel=1e-13))


def test_d_profile_a_major_arc(tmp_path):
    """A circle of radius 10 cut flat at y = -6: a chord and an arc of more
    than half a circle, bulge exactly 2 (cot(asin(0.8) / 2))."""
    doc = new_doc()
    doc.modelspace().add_lwpolyline([(-8, -6, 0), (8, -6, 2)], format="xyb", close=True)
    shape, _ = wrenchd_dxf.shape_from_dxf(save(doc, tmp_path))
    assert shape["loops"] == [[[-8.0, -6.0], [8.0, -6.0, 2.0]]]
    A, cx, cy = area_centroid(shape)
    # integral of 2 sqrt(100 - y^2) dy and of y times it, from -6 to 10
    area = 50 * math.pi + 48 + 100 * math.asin(0.6)
    assert A == pytest.approx(area, rel=1e-14)
    assert cx == pytest.approx(0, abs=1e-13)
    assert cy == pytest.approx(2 / 3 * 512 / area, rel=1e-13)


def test_old_style_polyline(tmp_path):
    """A regular hexagon as a 2-D POLYLINE (VERTEX entities), one side an
    arc; and a 3-D POLYLINE lying flat at z = 5."""
    R = 20.0
    hexagon = [(R * math.cos(k * math.pi / 3), R * math.sin(k * math.pi / 3)) for k in range(6)]
    doc = new_doc()
    msp = doc.modelspace()
    msp.add_polyline2d([(x, y, Q if k == 0 else 0) for k, (x, y) in enumerate(hexagon)],
                       format="xyb", close=True, dxfattribs={"layer": "HEX"})
    msp.add_polyline3d([(0, 0, 5), (10, 0, 5), (10, 10, 5)], close=True, dxfattribs={"layer": "TRI"})
    path = save(doc, tmp_path)
    shape, report = wrenchd_dxf.shape_from_dxf(path, layer="HEX")
    want = [[x, y] + ([Q] if k == 0 else []) for k, (x, y) in enumerate(hexagon)]
    same_loop(shape["loops"][0], want)
    assert report["used"] == {"POLYLINE": 1}
    # hexagon 3 sqrt(3)/2 R^2, plus the segment of a quarter circle on a side
    # of length R: its radius R / (2 sin(pi/4))
    r = R / math.sqrt(2)
    A, _, _ = area_centroid(shape)
    assert A == pytest.approx(3 * math.sqrt(3) / 2 * R * R + r * r / 2 * (math.pi / 2 - 1), rel=1e-13)
    shape, report = wrenchd_dxf.shape_from_dxf(path, layer="TRI")
    assert shape["loops"] == [[[0.0, 0.0], [10.0, 0.0], [10.0, 10.0]]] and report["z"] == [5.0, 5.0]


# ---- LINE and ARC chains, CIRCLEs ---------------------------------------------------

# The plate: 100 x 60, corner (100, 0) rounded with radius 10; a hole of
# diameter 12 at (25, 30); a slot from (55, 30) to (75, 30), width 10.
PLATE = {"type": "outline", "loops": [
    [[0, 0], [90, 0, Q], [100, 10], [100, 60], [0, 60]],
    [[19, 30, 1], [31, 30, 1]],
    [[55, 25], [75, 25, 1], [75, 35], [55, 35, 1]],
]}
PLATE_AREA = 100 * 60 - (1 - math.pi / 4) * 100 - math.pi * 36 - (20 * 10 + math.pi * 25)


def plate_centroid():
    """Closed form: the first moments of the rectangle, less the corner's
    (square less quarter disc), the hole's and the slot's."""
    corner_a = 100 - 25 * math.pi
    # the square (90..100, 0..10) has centroid (95, 5); the quarter disc
    # about (90, 10) of radius 10 has its centroid 40 / (3 pi) from it
    qx, qy = 90 + 40 / (3 * math.pi), 10 - 40 / (3 * math.pi)
    corner_sx = 100 * 95 - 25 * math.pi * qx
    corner_sy = 100 * 5 - 25 * math.pi * qy
    hole_a, slot_a = 36 * math.pi, 200 + 25 * math.pi
    sx = 6000 * 50 - corner_sx - hole_a * 25 - slot_a * 65
    sy = 6000 * 30 - corner_sy - hole_a * 30 - slot_a * 30
    return sx / PLATE_AREA, sy / PLATE_AREA


def add_plate(msp, gap=0.0, layer="0", seed=1):
    """The plate as LINEs, ARCs and a CIRCLE, in a shuffled order, some LINEs
    drawn backwards, one ARC mirrored (extrusion -Z), `gap` left at two
    joints."""
    a = {"layer": layer}
    m = {"layer": layer, "extrusion": (0, 0, -1)}
    ents = [
        lambda: msp.add_line((0, 0), (90 - gap, 0), dxfattribs=a),
        lambda: msp.add_arc((90, 10), 10, 270, 0, dxfattribs=a),
        lambda: msp.add_line((100, 60), (100, 10 + gap), dxfattribs=a),       # backwards
        lambda: msp.add_line((100, 60), (0, 60), dxfattribs=a),
        lambda: msp.add_line((0, 0), (0, 60), dxfattribs=a),                   # backwards
        lambda: msp.add_circle((25, 30), 6, dxfattribs=a),
        lambda: msp.add_line((55, 25), (75, 25), dxfattribs=a),
        lambda: msp.add_arc((75, 30), 5, -90, 90, dxfattribs=a),
        lambda: msp.add_line((75, 35), (55, 35), dxfattribs=a),
        # the left end, (55, 35) -> (55, 25) counter-clockwise about (55, 30),
        # drawn mirrored: in its OCS x is -x, the centre (-55, 30), and the
        # arc runs from -90 to 90 degrees
        lambda: msp.add_arc((-55, 30), 5, -90, 90, dxfattribs=m),
    ]
    random.Random(seed).shuffle(ents)
    for e in ents:
        e()


@pytest.mark.parametrize("seed", [1, 2, 3])
def test_plate_of_lines_arcs_and_a_circle(tmp_path, seed):
    doc = new_doc()
    add_plate(doc.modelspace(), seed=seed)
    shape, report = wrenchd_dxf.shape_from_dxf(save(doc, tmp_path))
    same_shape(shape, PLATE)
    assert orientation_ok(shape) and all_floats(shape)
    assert report["used"] == {"LINE": 6, "ARC": 3, "CIRCLE": 1}
    assert report["largest_gap"] == 0.0
    A, cx, cy = area_centroid(shape)
    wx, wy = plate_centroid()
    assert A == pytest.approx(PLATE_AREA, rel=1e-14)
    assert (cx, cy) == (pytest.approx(wx, rel=1e-13), pytest.approx(wy, rel=1e-13))


def test_gaps_below_the_tolerance_are_closed(tmp_path):
    doc = new_doc()
    add_plate(doc.modelspace(), gap=1e-7)
    path = save(doc, tmp_path)
    shape, report = wrenchd_dxf.shape_from_dxf(path)
    assert report["tolerance"] == pytest.approx(1e-6 * math.hypot(100, 60))
    assert report["largest_gap"] == pytest.approx(1e-7, rel=1e-6)
    # the joints keep the ARC's computed ends as drawn exactly, the LINE's
    # shortened one within 1e-7
    same_shape(shape, PLATE, tol=1e-7 * 1.01)
    code, out, err = run(path)
    assert code == 0 and json.loads(out) == shape
    assert "largest gap closed 1e-07" in err and "tolerance 0.000116619" in err


def test_a_line_shorter_than_the_tolerance_is_left_out(tmp_path):
    doc = new_doc()
    msp = doc.modelspace()
    msp.add_line((0, 0), (10, 0))
    msp.add_line((10, 0), (10, 1e-9))
    msp.add_line((10, 1e-9), (10, 10))
    msp.add_line((10, 10), (10, 10))
    msp.add_line((10, 10), (0, 0))
    shape, report = wrenchd_dxf.shape_from_dxf(save(doc, tmp_path))
    same_loop(shape["loops"][0], [[0, 0], [10, 0], [10, 10]], tol=1e-9)
    assert report["used"] == {"LINE": 3}
    assert report["ignored"] == {"shorter than the tolerance": {"LINE": 2}}


def test_a_gap_above_the_tolerance_is_an_open_chain(tmp_path):
    doc = new_doc()
    add_plate(doc.modelspace(), gap=0.01)
    path = save(doc, tmp_path)
    message = refused(path, "open chain", "meets nothing")
    # the two gaps, by the points where the LINEs stop short
    assert "(89.99, 0.0)" in message and "(100.0, 10.01)" in message
    assert "0.01 away" in message
    code, out, err = run(path)
    assert code == 1 and out == "" and "(89.99, 0.0)" in err
    # a tolerance above the gap closes it
    shape, report = wrenchd_dxf.shape_from_dxf(path, tolerance=0.02)
    assert report["tolerance_rule"] == "given" and report["largest_gap"] == pytest.approx(0.01)
    assert len(shape["loops"]) == 3


def test_a_dangling_line_is_stray_a_chord_is_a_branch(tmp_path):
    doc = new_doc()
    msp = doc.modelspace()
    for p, q in [((0, 0), (10, 0)), ((10, 0), (10, 10)), ((10, 10), (0, 0)), ((10, 0), (20, 0))]:
        msp.add_line(p, q)
    shape, report = wrenchd_dxf.shape_from_dxf(save(doc, tmp_path))
    same_loop(shape["loops"][0], [[0, 0], [10, 0], [10, 10]])
    assert len(report["stray"]) == 1 and report["stray"][0]["segments"] == 1
    assert report["stray"][0]["extent"] == [10.0, 0.0, 20.0, 0.0]
    # a line between two corners of a square: three ends at each
    doc = new_doc()
    msp = doc.modelspace()
    msp.add_lwpolyline([(0, 0), (10, 0), (10, 10), (0, 10)], format="xy", close=True)
    msp.add_line((0, 0), (10, 10))
    refused(save(doc, tmp_path), "3 ends meet at", "a branch", "LINE (handle")


# ---- layers, units ----------------------------------------------------------------

def test_layers(tmp_path):
    doc = new_doc()
    msp = doc.modelspace()
    msp.add_lwpolyline([(200, 0), (210, 0), (210, 10)], format="xy", close=True, dxfattribs={"layer": "Part"})
    add_plate(msp, layer="PLATE")
    msp.add_text("PART 7", dxfattribs={"layer": "Part"})
    msp.add_spline([(0, 70), (5, 75), (10, 70)], dxfattribs={"layer": "Notes"})
    path = save(doc, tmp_path)
    shape, report = wrenchd_dxf.shape_from_dxf(path, layer="PLATE")
    same_shape(shape, PLATE)
    assert report["ignored"] == {"on another layer": {"LWPOLYLINE": 1, "TEXT": 1, "SPLINE": 1}}
    shape, report = wrenchd_dxf.shape_from_dxf(path, layer="part")           # any case
    assert shape["loops"] == [[[200.0, 0.0], [210.0, 0.0], [210.0, 10.0]]]
    assert report["ignored"]["annotation, not geometry"] == {"TEXT": 1}
    refused(path, "no entity on layer 'nope'", "'PLATE' (10)", layer="nope")
    code, out, err = run(path, "--layer", "PLATE")
    assert code == 0 and json.loads(out) == wrenchd_dxf.shape_from_dxf(path, layer="PLATE")[0]
    # --layer repeated: both layers, two parts, the plate the larger
    parts, report = wrenchd_dxf.read_dxf(path, layers=["PLATE", "part"])
    assert [p["area"] for p in parts] == [pytest.approx(PLATE_AREA, rel=1e-14), 50.0]
    assert report["ignored"]["on another layer"] == {"SPLINE": 1}
    code, out, err = run(path, "--layer", "PLATE", "--layer", "Part", "--part", "2")
    assert code == 0 and json.loads(out) == parts[1]["shape"]
    assert "part 2 of 2" in err and "part 1: area %.6g mm^2" % PLATE_AREA in err
    # every layer: the open SPLINE is stray, ignored and reported
    shape, report = wrenchd_dxf.shape_from_dxf(path)
    same_shape(shape, PLATE)
    assert [c["entities"][0].split(" ")[0] for c in report["stray"]] == ["SPLINE"]


@pytest.mark.parametrize("code,name,mm", [(4, "mm", 1.0), (1, "inch", 25.4), (0, "unitless", None),
                                          (6, "m", 1000.0)])
def test_units(tmp_path, code, name, mm):
    doc = new_doc(units=code)
    doc.modelspace().add_circle((0, 0), 1)
    path = save(doc, tmp_path)
    shape, report = wrenchd_dxf.shape_from_dxf(path)
    assert shape["loops"] == [[[-1.0, 0.0, 1.0], [1.0, 0.0, 1.0]]]
    assert report["units"]["code"] == code and report["units"]["name"] == name
    assert report["units"]["mm_per_unit"] == mm
    unit = {4: "mm", 1: "in", 0: "mm", 6: "m"}[code]
    assert report["units"]["unit"] == unit and report["units"]["scale"] == 1.0
    assert wrenchd_dxf.fixture_units(report) == {"length": unit, "force": "N"}
    c, out, err = run(path, *(["--report"] if code == 6 else []))
    assert c == 0 and json.loads(out) == shape
    if code == 6:
        assert json.loads(err)["units"] == report["units"]
    elif code:
        assert "unit: %s ($INSUNITS %d (%s))" % (unit, code, name) in err
    else:
        assert "unit: mm (not stated ($INSUNITS 0): taken as mm; give --units" in err


@pytest.mark.parametrize("measurement", [0, 1])
def test_measurement_is_not_the_unit(tmp_path, measurement):
    """$INSUNITS 0 with $MEASUREMENT 0 (imperial), as some exporters write
    drawings in mm: taken as mm, $MEASUREMENT reported only; --units in
    says otherwise, nothing scaled."""
    doc = new_doc(units=0)
    doc.header["$MEASUREMENT"] = measurement
    doc.modelspace().add_circle((0, 0), 1)
    path = save(doc, tmp_path)
    shape, report = wrenchd_dxf.shape_from_dxf(path)
    assert report["units"]["unit"] == "mm"
    assert report["units"]["measurement"] == ("metric" if measurement else "imperial")
    shape2, report = wrenchd_dxf.shape_from_dxf(path, units="in")
    assert shape2 == shape and report["units"]["unit"] == "in"
    assert report["units"]["rule"] == "given (--units)"
    code, out, err = run(path, "--units", "in")
    assert code == 0 and json.loads(out) == shape and "unit: in (given (--units))" in err
    code, out, err = run(path, "--units", "ft")
    assert code == 2 and "invalid choice" in err


@pytest.mark.parametrize("code,factor,unit", [(5, 10.0, "mm"), (2, 12.0, "in"), (14, 100.0, "mm")])
def test_other_units_are_scaled_to_a_fixtures(tmp_path, code, factor, unit):
    """cm, feet, dm: written in mm or inches, the numbers scaled."""
    doc = new_doc(units=code)
    doc.modelspace().add_lwpolyline([(0, 0), (3, 0), (3, 2), (0, 2)], format="xy", close=True)
    parts, report = wrenchd_dxf.read_dxf(save(doc, tmp_path))
    assert report["units"]["unit"] == unit and report["units"]["scale"] == factor
    assert parts[0]["shape"]["loops"][0] == [[0.0, 0.0], [3 * factor, 0.0], [3 * factor, 2 * factor],
                                             [0.0, 2 * factor]]
    assert parts[0]["area"] == pytest.approx(6 * factor ** 2, rel=1e-15)


# ---- round trip ----------------------------------------------------------------------

ISSUE_SHAPE = {"type": "outline", "loops": [
    [[0, 0], [40, 0, 0.4142135623730951], [50, 10], [50, 30], [0, 30]],
    [[10, 10, 1], [16, 10, 1]]]}

ROUND_TRIP = {"type": "outline", "loops": [
    [[0.0, 0.0], [80.0, 0.0, 0.25], [80.0, 50.0, -0.125], [40.0, 55.5], [0.0, 50.0, 0.1]],
    [[10.0, 10.0, 1.0], [16.0, 10.0, 1.0]],
    [[30.0, 20.0], [45.0, 20.0, 1.0], [45.0, 30.0], [30.0, 30.0, -0.3]],
    [[60.125, 30.0], [70.0, 30.0, 2.0]],
]}


@pytest.mark.parametrize("mirrored", [False, True])
@pytest.mark.parametrize("want", [ISSUE_SHAPE, ROUND_TRIP], ids=["issue", "mixed"])
def test_round_trip(tmp_path, want, mirrored):
    """shape -> LWPOLYLINEs with bulges (or their mirror images with
    extrusion -Z) -> wrenchd_dxf -> the same shape, exactly."""
    doc = new_doc()
    msp = doc.modelspace()
    for loop in want["loops"]:
        pts = [(v[0], v[1], v[2] if len(v) > 2 else 0.0) for v in loop]
        attribs = {}
        if mirrored:
            pts = [(-x, y, -b) for x, y, b in pts]
            attribs = {"extrusion": (0, 0, -1)}
        msp.add_lwpolyline(pts, format="xyb", close=True, dxfattribs=attribs)
    path = save(doc, tmp_path)
    code, out, err = run(path)
    assert code == 0, err
    got = json.loads(out)
    same_shape(got, want)
    assert orientation_ok(got)
    assert area_centroid(got) == pytest.approx(area_centroid(want), rel=1e-14)


# ---- what is refused ------------------------------------------------------------------

def test_two_disjoint_parts(tmp_path):
    doc = new_doc()
    msp = doc.modelspace()
    msp.add_circle((30, 5), 4)
    msp.add_lwpolyline([(0, 0), (10, 0), (10, 10), (0, 10)], format="xy", close=True)
    path = save(doc, tmp_path)
    parts, report = wrenchd_dxf.read_dxf(path)
    assert [p["number"] for p in parts] == [1, 2]
    assert parts[0]["area"] == 100.0 and parts[1]["area"] == pytest.approx(16 * math.pi, rel=1e-15)
    assert parts[1]["extent"] == [26.0, 1.0, 34.0, 9.0]
    shape, report = wrenchd_dxf.shape_from_dxf(path)
    assert shape == parts[0]["shape"] and report["part"] == 1
    assert wrenchd_dxf.shape_from_dxf(path, part=2)[0] == parts[1]["shape"]
    refused(path, "--part 3: the drawing holds 2 parts", part=3)
    code, out, err = run(path)
    assert code == 0 and json.loads(out) == parts[0]["shape"]
    assert "1 other part" in err and "part 2: area 50.2655 mm^2, 0 holes, x 26 to 34, y 1 to 9" in err
    code, out, err = run(path, "--part", "all")
    assert code == 0 and json.loads(out) == [p["shape"] for p in parts]
    code, out, err = run(path, "--part", "two")
    assert code == 1 and "'two' is not a part" in err


def test_an_island_in_a_hole(tmp_path):
    """A washer drawn inside its bore: a part of its own."""
    doc = new_doc()
    msp = doc.modelspace()
    msp.add_lwpolyline([(0, 0), (50, 0), (50, 50), (0, 50)], format="xy", close=True)
    msp.add_circle((25, 25), 20)
    msp.add_circle((25, 25), 5)
    msp.add_circle((25, 25), 2)
    parts, report = wrenchd_dxf.read_dxf(save(doc, tmp_path))
    assert [p["holes"] for p in parts] == [1, 1]
    assert parts[0]["area"] == pytest.approx(2500 - 400 * math.pi, rel=1e-14)
    assert parts[1]["area"] == pytest.approx(21 * math.pi, rel=1e-14)


def test_crossing_loops(tmp_path):
    doc = new_doc()
    msp = doc.modelspace()
    msp.add_lwpolyline([(0, 0), (50, 0), (50, 50), (0, 50)], format="xy", close=True)
    msp.add_circle((50, 25), 5)
    refused(save(doc, tmp_path), "cross")


def test_a_hole_near_an_arc_is_inside(tmp_path):
    """A hole between a rounded corner's chord and its arc: inside the
    part, though outside the chord polygon."""
    doc = new_doc()
    msp = doc.modelspace()
    msp.add_lwpolyline([(v[0], v[1], v[2] if len(v) > 2 else 0) for v in rounded_rectangle(60, 30, 10)],
                       format="xyb", close=True)
    # the corner at (50, 0)..(60, 10) about (50, 10): its chord passes
    # (55, 5); the arc passes (50 + 10 cos 45, 10 - 10 sin 45) = (57.07, 2.93)
    msp.add_circle((56.3, 3.7), 0.5)
    shape, report = wrenchd_dxf.shape_from_dxf(save(doc, tmp_path))
    assert report["holes"] == 1 and shape["loops"][1] == [[55.8, 3.7, -1.0], [56.8, 3.7, -1.0]]


def test_no_closed_loop(tmp_path):
    doc = new_doc()
    doc.modelspace().add_text("nothing here")
    refused(save(doc, tmp_path), "no closed loop")
    code, out, err = run(save(doc, tmp_path))
    assert code == 1 and out == "" and "no closed loop" in err


def test_kinds_not_read_are_ignored_and_counted(tmp_path):
    doc = new_doc()
    msp = doc.modelspace()
    msp.add_lwpolyline([(0, 0), (10, 0), (10, 10), (0, 10)], format="xy", close=True)
    msp.add_3dface([(0, 0, 0), (1, 0, 0), (1, 1, 0)])
    msp.add_solid([(20, 0), (21, 0), (20, 1)])
    shape, report = wrenchd_dxf.shape_from_dxf(save(doc, tmp_path))
    assert len(shape["loops"]) == 1
    assert report["ignored"] == {"a kind of entity not read": {"3DFACE": 1, "SOLID": 1}}


def test_an_ellipse_hole_and_a_spline_side(tmp_path):
    """An ELLIPSE hole and a SPLINE closing a chain of LINEs: followed by
    tangent arcs within the curve tolerance, measured both ways; the areas
    against ezdxf's own flattening of the curves."""
    doc = new_doc()
    msp = doc.modelspace()
    msp.add_line((0, 0), (40, 0))
    msp.add_line((40, 0), (40, 30))
    msp.add_line((0, 30), (0, 0))
    spline = msp.add_spline(fit_points=[(40, 30), (30, 38), (20, 31), (10, 36), (0, 30)])
    msp.add_ellipse((20, 15), major_axis=(8, 3, 0), ratio=0.4)
    path = save(doc, tmp_path)
    shape, report = wrenchd_dxf.shape_from_dxf(path, curve_tolerance=1e-4)
    assert report["holes"] == 1 and len(report["curves"]) == 2
    assert 0 < report["curve_deviation"] <= 1e-4
    top = [(v.x, v.y) for v in spline.flattening(1e-7)]
    poly = [(0, 0), (40, 0)] + top
    want = abs(loop_moments([list(p) for p in poly])[0]) - math.pi * math.hypot(8, 3) ** 2 * 0.4
    got = area_centroid(shape)[0]
    # the arcs are within 1e-4 of a curve 60 long: the areas within 60e-4
    assert abs(got - want) <= 60e-4 + 1e-9, (got, want)
    assert wrenchd_dxf.read_dxf(path)[0][0]["area"] == pytest.approx(want, rel=1e-6)


def test_out_of_the_xy_plane(tmp_path):
    doc = new_doc()
    doc.modelspace().add_line((0, 0, 0), (10, 0, 5))
    refused(save(doc, tmp_path), "LINE", "not in a plane parallel to XY")
    doc = new_doc()
    doc.modelspace().add_circle((0, 0), 5, dxfattribs={"extrusion": (1, 0, 0)})
    refused(save(doc, tmp_path), "CIRCLE", "not parallel to the XY plane")


def test_not_a_dxf_file(tmp_path):
    path = tmp_path / "junk.dxf"
    path.write_text("this is not a drawing\n")
    code, out, err = run(str(path))
    assert code == 1 and out == "" and "junk.dxf" in err
    code, out, err = run(str(tmp_path / "missing.dxf"))
    assert code == 1 and out == ""


# ---- a drawing from another CAD program ------------------------------------------------

def test_freecad_drawing():
    """tests/e2e/data/freecad_plate.dxf, written by FreeCAD 0.20.2's DXF
    exporter (tests/e2e/data/freecad_plate.py): LINEs, ARCs (one ending at
    -1.0e-14 degrees) and a CIRCLE on layer "none", in mm."""
    path = os.path.join(DATA, "freecad_plate.dxf")
    shape, report = wrenchd_dxf.shape_from_dxf(path)
    want = {"type": "outline", "loops": [
        [[0, 0], [55, 0, Q], [60, 5], [60, 40], [0, 40]],
        [[11, 20, 1], [19, 20, 1]],
        [[35, 12], [45, 12, 1], [45, 18], [35, 18, 1]]]}
    same_shape(shape, want, tol=1e-12)
    assert report["units"]["name"] == "mm" and report["used"] == {"LINE": 6, "ARC": 3, "CIRCLE": 1}
    assert 0 < report["largest_gap"] < 1e-14
    A, cx, cy = area_centroid(shape)
    closed_form = 60 * 40 - (25 - 25 * math.pi / 4) - 16 * math.pi - (60 + 9 * math.pi)
    assert A == pytest.approx(closed_form, rel=1e-13)
    assert A == pytest.approx(2256.095137745191, rel=1e-12)      # FreeCAD's own face.Area


# FreeCAD 0.20.2's mass properties of that plate at unit density
# (data/freecad_plate.py prints them): area, centroid, polar moment about it.
FREECAD_AREA = 2256.095137745191
FREECAD_CENTROID = (29.874242633466682, 20.240539808092137)
FREECAD_POLAR = 1008815.3563047722


def test_freecad_drawing_through_wrenchd(client):
    """The DXF round trip into wrenchd: the shape wrenchd_dxf reads from
    FreeCAD's drawing, put as a fixture of unit density (mass = area), gets
    from fixture.put the area, centroid and moment of inertia FreeCAD
    computes for the same face, to 1e-13; and it round-trips through
    fixture.get to the same id."""
    shape, _ = wrenchd_dxf.shape_from_dxf(os.path.join(DATA, "freecad_plate.dxf"))
    fixture = {"body": {"mass": FREECAD_AREA, "shape": shape}, "friction": {"static": 0.3},
               "fixels": [{"at": [20, 0]}, {"at": [0, 20]}, {"at": [40, 40]}]}
    put = client.result("fixture.put", {"fixture": fixture})
    assert put["area"] == pytest.approx(FREECAD_AREA, rel=1e-13)
    assert put["com"][0] == pytest.approx(FREECAD_CENTROID[0], rel=1e-13)
    assert put["com"][1] == pytest.approx(FREECAD_CENTROID[1], rel=1e-13)
    assert put["inertia"] == pytest.approx(FREECAD_POLAR, rel=1e-13)
    again = client.result("fixture.put", {"fixture": client.result("fixture.get",
                                                                   {"id": put["id"]})})
    assert again["id"] == put["id"]


def test_imports():
    """wrenchd_dxf.py: Python 3.8 syntax, the standard library, ezdxf and
    wrenchd_arcs.py (standard library only: the FreeCAD workbench imports
    it); the client wrenchd.py does not import it (test_python_client.py
    checks the client is standard library only)."""
    for name, allowed in (("wrenchd_dxf.py", {"ezdxf", "wrenchd_arcs"}), ("wrenchd.py", set()),
                          ("wrenchd_arcs.py", set())):
        with open(os.path.join(REPO, "clients", "python", name)) as fh:
            tree = ast.parse(fh.read(), name, feature_version=(3, 8))
        names = {a.name.split(".")[0] for n in ast.walk(tree) if isinstance(n, ast.Import)
                 for a in n.names}
        names |= {n.module.split(".")[0] for n in ast.walk(tree)
                  if isinstance(n, ast.ImportFrom) and n.module and n.level == 0}
        assert names - allowed <= set(sys.stdlib_module_names), (name, names)
        assert ("ezdxf" in names) == (name == "wrenchd_dxf.py")
