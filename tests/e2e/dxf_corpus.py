#!/usr/bin/env python3
"""A corpus of DXF drawings that imitate how real laser-cut and CNC parts
are drawn, written with ezdxf: several parts in one file, entities drawn
twice or over each other, stray construction lines, splines and ellipses,
inches and unstated units, arcs faceted into lines, a plate of 72 holes,
symmetric parts, a washer drawn in its bore, block references.

    /usr/bin/python3 tests/e2e/dxf_corpus.py OUTDIR

writes OUTDIR/NAME.dxf and OUTDIR/NAME.json for each drawing.  The JSON is
what the drawing holds, as this script drew it (never as a reader reads
it): "parts", each {"outer": loop, "holes": [loop, ...]}, a loop being the
entities drawn for it in order around it (by handle, "H" or, inside a block
reference, "H#k" for the k-th entity it explodes into); "duplicates": the
segments drawn again over others; "stray": the open chains drawn beside
the parts; "curves": the SPLINEs and ELLIPSEs in the parts; "unit" and
"scale" (the fixture unit the drawing's numbers are in, and what they are
multiplied by to be in it); "layers": the layers to read (null: all).
tests/e2e/test_dxf_corpus.py reads each drawing with wrenchd_dxf and checks
it against these, computing areas and extents by ezdxf's own flattening.
"""

import json
import math
import os
import sys

import ezdxf
from ezdxf.math import closed_uniform_bspline


def _new(units=4, measurement=None):
    doc = ezdxf.new("R2010")
    doc.header["$INSUNITS"] = units
    if measurement is not None:
        doc.header["$MEASUREMENT"] = measurement
    return doc


def _h(e):
    return e.dxf.handle


def _rounded_rect(msp, x, y, w, h, r, layer="0"):
    """A closed LWPOLYLINE, corners of radius r (bulge tan(pi/8))."""
    q = math.tan(math.pi / 8)
    pts = [(x + r, y, 0), (x + w - r, y, q), (x + w, y + r, 0), (x + w, y + h - r, q),
           (x + w - r, y + h, 0), (x + r, y + h, q), (x, y + h - r, 0), (x, y + r, q)]
    return msp.add_lwpolyline(pts, format="xyb", close=True, dxfattribs={"layer": layer})


def _slot(msp, cx, cy, length, width, layer="0"):
    """A slot as LINEs and ARCs, in order around it."""
    r = width / 2.0
    a = {"layer": layer}
    x0, x1 = cx - length / 2.0, cx + length / 2.0
    return [msp.add_line((x0, cy - r), (x1, cy - r), dxfattribs=a),
            msp.add_arc((x1, cy), r, -90, 90, dxfattribs=a),
            msp.add_line((x1, cy + r), (x0, cy + r), dxfattribs=a),
            msp.add_arc((x0, cy), r, 90, 270, dxfattribs=a)]


def _cam_points(cx, cy, r, lobes, depth, n):
    return [(cx + (r + depth * math.cos(lobes * t)) * math.cos(t),
             cy + (r + depth * math.cos(lobes * t)) * math.sin(t))
            for t in (2 * math.pi * k / n for k in range(n))]


def several_parts():
    """A bracket with holes and a slot, a cam drawn as a closed SPLINE with
    a bore, a washer, a tab of LINEs: four parts in one file."""
    doc = _new()
    msp = doc.modelspace()
    bracket = _rounded_rect(msp, 0, 0, 120, 80, 8)
    h1 = msp.add_circle((15, 15), 3.2)
    h2 = msp.add_circle((105, 15), 3.2)
    slot = _slot(msp, 60, 55, 40, 8)
    cam = msp.add_spline(_cam_points(200, 40, 30, 3, 4, 48) + [_cam_points(200, 40, 30, 3, 4, 48)[0]])
    bore = msp.add_circle((200, 40), 6)
    washer = msp.add_circle((160, 120), 10)
    washer_hole = msp.add_circle((160, 120), 5.3)
    tab = [msp.add_line(p, q) for p, q in [((0, 110), (30, 110)), ((30, 110), (30, 125)),
                                           ((30, 125), (0, 125)), ((0, 125), (0, 110))]]
    msp.add_text("BRACKET 2 mm AL", dxfattribs={"insert": (10, -10)})
    return doc, {
        "parts": [{"outer": [_h(bracket)], "holes": [[_h(h1)], [_h(h2)], [_h(e) for e in slot]]},
                  {"outer": [_h(cam)], "holes": [[_h(bore)]]},
                  {"outer": [_h(washer)], "holes": [[_h(washer_hole)]]},
                  {"outer": [_h(e) for e in tab], "holes": []}],
        "curves": 1}


def duplicates():
    """A plate of LINEs and ARCs, every LINE drawn twice (the copy
    backwards), an ARC twice, a LWPOLYLINE over two of the LINEs, a line
    again 1e-8 off, a hole's CIRCLE twice, and a side drawn as two LINEs
    that overlap each other by 20."""
    doc = _new()
    msp = doc.modelspace()
    lines = [((10, 0), (90, 0)), ((100, 10), (100, 60)), ((100, 60), (0, 60)), ((0, 60), (0, 10))]
    outer = []
    dup = 0
    ents = [msp.add_line(*lines[0]), msp.add_arc((90, 10), 10, 270, 0), msp.add_line(*lines[1]),
            None, msp.add_line(*lines[3]), msp.add_arc((10, 10), 10, 180, 270)]
    # the top side: (100, 60) -> (40, 60) and (60, 60) -> (0, 60), overlapping on 40..60
    top_a = msp.add_line((100, 60), (40, 60))
    top_b = msp.add_line((60, 60), (0, 60))
    ents[3] = top_a
    outer = [_h(ents[0]), _h(ents[1]), _h(ents[2]), _h(top_a), _h(top_b), _h(ents[4]), _h(ents[5])]
    dup += 1                                   # the overlap 40..60
    for (p, q) in (lines[0], lines[1], lines[3]):
        msp.add_line(q, p)                     # again, backwards
        dup += 1
    msp.add_arc((90, 10), 10, 270, 0)
    dup += 1
    msp.add_lwpolyline([(0, 10), (0, 60), (40, 60)], format="xy")   # over the left LINE and part of the top
    dup += 2
    msp.add_line((10, 1e-8), (90, 1e-8))       # near: 1e-8 off, under the tolerance (1.2e-4)
    dup += 1
    hole = msp.add_circle((30, 30), 6)
    msp.add_circle((30, 30), 6)
    dup += 2                                   # two half circles
    return doc, {"parts": [{"outer": outer, "holes": [[_h(hole)]]}], "duplicates": dup}


def stray():
    """A plate with two holes and, beside it, what drawings carry: a
    centreline through each hole, a construction line across the sheet, a
    sketch segment dangling from a corner, an open ARC."""
    doc = _new()
    msp = doc.modelspace()
    plate = msp.add_lwpolyline([(0, 0), (80, 0), (80, 50), (0, 50)], format="xy", close=True)
    h1 = msp.add_circle((20, 25), 5)
    h2 = msp.add_circle((60, 25), 8)
    for cx, r in ((20, 5), (60, 8)):
        msp.add_line((cx - r - 3, 25), (cx + r + 3, 25), dxfattribs={"linetype": "CENTER"})
        msp.add_line((cx, 25 - r - 3), (cx, 25 + r + 3), dxfattribs={"linetype": "CENTER"})
    msp.add_line((-20, -10), (120, -10))        # construction
    msp.add_line((80, 50), (95, 62))            # dangling from a corner
    msp.add_arc((40, 80), 10, 0, 120)           # open
    return doc, {"parts": [{"outer": [_h(plate)], "holes": [[_h(h1)], [_h(h2)]]}], "stray": 7}


def curves():
    """SPLINEs and ELLIPSEs: a part whose top is a SPLINE through fit points
    between LINEs, with an ELLIPSE hole and a slot of two elliptical arcs
    and LINEs; and a closed SPLINE of control points (a cam)."""
    doc = _new()
    msp = doc.modelspace()
    a = msp.add_line((0, 0), (60, 0))
    b = msp.add_line((60, 0), (60, 30))
    top = msp.add_spline(fit_points=[(60, 30), (45, 40), (30, 33), (15, 41), (0, 30)])
    c = msp.add_line((0, 30), (0, 0))
    hole = msp.add_ellipse((15, 15), major_axis=(6, 2, 0), ratio=0.5)
    # the slot: from (35, 10) to (50, 10) below, the right end an elliptical arc up to (50, 20)
    s1 = msp.add_line((35, 10), (50, 10))
    s2 = msp.add_ellipse((50, 15), major_axis=(0, 5, 0), ratio=0.6, start_param=math.pi, end_param=2 * math.pi)
    s3 = msp.add_line((50, 20), (35, 20))
    s4 = msp.add_ellipse((35, 15), major_axis=(0, 5, 0), ratio=0.6, start_param=0, end_param=math.pi)
    cam = msp.add_spline()
    cam.apply_construction_tool(closed_uniform_bspline(_cam_points(120, 20, 18, 5, 3, 40), order=4))
    return doc, {"parts": [{"outer": [_h(a), _h(b), _h(top), _h(c)],
                            "holes": [[_h(hole)], [_h(s1), _h(s2), _h(s3), _h(s4)]]},
                           {"outer": [_h(cam)], "holes": []}],
                 "curves": 5}


def inches():
    """A 4 x 2.5 inch plate ($INSUNITS 1), corners of 1/4 in, holes of
    0.257 in (an F drill)."""
    doc = _new(units=1)
    msp = doc.modelspace()
    plate = _rounded_rect(msp, 0, 0, 4, 2.5, 0.25)
    holes = [msp.add_circle((x, y), 0.257 / 2) for x, y in ((0.5, 0.5), (3.5, 0.5), (0.5, 2), (3.5, 2))]
    return doc, {"parts": [{"outer": [_h(plate)], "holes": [[_h(h)] for h in holes]}], "unit": "in"}


def unstated_mm():
    """A plate in mm whose header says $INSUNITS 0 and $MEASUREMENT 0
    (imperial), as some exporters write: taken as mm."""
    doc = _new(units=0, measurement=0)
    msp = doc.modelspace()
    plate = _rounded_rect(msp, 0, 0, 90, 40, 5)
    hole = msp.add_circle((45, 20), 11)
    return doc, {"parts": [{"outer": [_h(plate)], "holes": [[_h(hole)]]}], "unit": "mm"}


def centimetres():
    """A plate drawn in cm ($INSUNITS 5): written in mm, x 10."""
    doc = _new(units=5)
    msp = doc.modelspace()
    plate = msp.add_lwpolyline([(0, 0), (8, 0), (8, 5), (0, 5)], format="xy", close=True)
    hole = msp.add_circle((4, 2.5), 1)
    return doc, {"parts": [{"outer": [_h(plate)], "holes": [[_h(hole)]]}], "unit": "mm", "scale": 10.0}


def faceted():
    """Arcs as a mesh exporter writes them: the rounded corners of a plate as
    24 short LINEs each, a hole as a 180-gon LWPOLYLINE, another as an R12
    POLYLINE of 90 vertices."""
    doc = _new()
    msp = doc.modelspace()
    pts = []
    for (cx, cy), a0 in (((90, 10), -90), ((90, 50), 0), ((10, 50), 90), ((10, 10), 180)):
        for k in range(25):
            t = math.radians(a0 + 90 * k / 24)
            pts.append((cx + 10 * math.cos(t), cy + 10 * math.sin(t)))
    outer = [msp.add_line(pts[k], pts[(k + 1) % len(pts)]) for k in range(len(pts))]
    hole = msp.add_lwpolyline([(30 + 8 * math.cos(2 * math.pi * k / 180), 30 + 8 * math.sin(2 * math.pi * k / 180))
                               for k in range(180)], format="xy", close=True)
    poly = msp.add_polyline2d([(70 + 6 * math.cos(2 * math.pi * k / 90), 30 + 6 * math.sin(2 * math.pi * k / 90))
                               for k in range(90)], close=True)
    return doc, {"parts": [{"outer": [_h(e) for e in outer], "holes": [[_h(hole)], [_h(poly)]]}]}


def keyboard():
    """A keyboard plate: 72 switch cut-outs of 14 x 14 mm at a 19.05 mm
    pitch (6 rows of 12), 6 M2 screw holes, rounded corners."""
    doc = _new()
    msp = doc.modelspace()
    plate = _rounded_rect(msp, 0, 0, 12 * 19.05 + 10, 6 * 19.05 + 10, 3)
    holes = []
    for row in range(6):
        for col in range(12):
            x, y = 5 + col * 19.05 + 2.525, 5 + row * 19.05 + 2.525
            holes.append([_h(msp.add_lwpolyline([(x, y), (x + 14, y), (x + 14, y + 14), (x, y + 14)],
                                                format="xy", close=True))])
    for x in (2.5, 119.3, 236.1):
        for y in (2.5, 6 * 19.05 + 7.5):
            holes.append([_h(msp.add_circle((x, y), 1.1))])
    return doc, {"parts": [{"outer": [_h(plate)], "holes": holes}]}


def symmetric():
    """A flange with six-fold symmetry: a hexagon with rounded corners (a
    LWPOLYLINE with bulges), a bore, six bolt holes; and a plate symmetric
    about one axis, of LINEs and ARCs."""
    doc = _new()
    msp = doc.modelspace()
    R, r = 40.0, 6.0
    pts = []
    for k in range(6):
        t = math.radians(60 * k)
        # a corner rounded by r: the tangent points on either side of the corner
        cx, cy = (R - 2 * r / math.sqrt(3)) * math.cos(t), (R - 2 * r / math.sqrt(3)) * math.sin(t)
        for s, bulge in ((-1, math.tan(math.radians(60) / 4)), (1, 0.0)):
            a = t + s * math.radians(30)
            pts.append((cx + r * math.cos(a), cy + r * math.sin(a), bulge))
    flange = msp.add_lwpolyline(pts, format="xyb", close=True)
    bore = msp.add_circle((0, 0), 12)
    bolts = [msp.add_circle((27 * math.cos(math.radians(60 * k + 30)), 27 * math.sin(math.radians(60 * k + 30))), 3.3)
             for k in range(6)]
    lines = [msp.add_line((100, -20), (160, -20)), msp.add_arc((160, 0), 20, -90, 90),
             msp.add_line((160, 20), (100, 20)), msp.add_arc((100, 0), 20, 90, 270)]
    return doc, {"parts": [{"outer": [_h(flange)], "holes": [[_h(bore)]] + [[_h(b)] for b in bolts]},
                           {"outer": [_h(e) for e in lines], "holes": []}]}


def washer_in_bore():
    """A plate whose bore holds its washer, drawn in place; inside the
    washer's hole a disc (a third part)."""
    doc = _new()
    msp = doc.modelspace()
    plate = msp.add_lwpolyline([(0, 0), (70, 0), (70, 70), (0, 70)], format="xy", close=True)
    bore = msp.add_circle((35, 35), 20)
    washer = msp.add_circle((35, 35), 15)
    washer_hole = msp.add_circle((35, 35), 8)
    disc = msp.add_circle((35, 35), 4)
    return doc, {"parts": [{"outer": [_h(plate)], "holes": [[_h(bore)]]},
                           {"outer": [_h(washer)], "holes": [[_h(washer_hole)]]},
                           {"outer": [_h(disc)], "holes": []}]}


def blocks():
    """A part drawn once in a block and placed twice by INSERT, rotated and
    scaled; the parts on layer CUT, dimensions and a border on others."""
    doc = _new()
    block = doc.blocks.new("PLATE")
    block.add_lwpolyline([(0, 0), (30, 0), (30, 20), (0, 20)], format="xy", close=True)
    block.add_circle((10, 10), 4)
    msp = doc.modelspace()
    doc.layers.add("CUT")
    doc.layers.add("BORDER")
    i1 = msp.add_blockref("PLATE", (0, 0), dxfattribs={"layer": "CUT"})
    i2 = msp.add_blockref("PLATE", (100, 0), dxfattribs={"layer": "CUT", "rotation": 30,
                                                         "xscale": 1.5, "yscale": 1.5})
    msp.add_lwpolyline([(-50, -50), (250, -50), (250, 150), (-50, 150)], format="xy", close=True,
                       dxfattribs={"layer": "BORDER"})
    msp.add_text("SHEET 1", dxfattribs={"layer": "BORDER", "insert": (0, 140)})
    return doc, {"parts": [{"outer": [_h(i2) + "#0"], "holes": [[_h(i2) + "#1"]]},
                           {"outer": [_h(i1) + "#0"], "holes": [[_h(i1) + "#1"]]}],
                 "layers": ["CUT"]}


DRAWINGS = [several_parts, duplicates, stray, curves, inches, unstated_mm, centimetres, faceted,
            keyboard, symmetric, washer_in_bore, blocks]


def write(outdir):
    """Every drawing and its facts into outdir; returns the names."""
    os.makedirs(outdir, exist_ok=True)
    names = []
    for make in DRAWINGS:
        doc, facts = make()
        facts.setdefault("duplicates", 0)
        facts.setdefault("stray", 0)
        facts.setdefault("curves", 0)
        facts.setdefault("unit", "mm")
        facts.setdefault("scale", 1.0)
        facts.setdefault("layers", None)
        facts["what"] = make.__doc__.split("\n\n")[0].replace("\n", " ").replace("    ", " ")
        name = make.__name__
        doc.saveas(os.path.join(outdir, name + ".dxf"))
        with open(os.path.join(outdir, name + ".json"), "w") as fh:
            json.dump(facts, fh, indent=1)
        names.append(name)
    return names


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.stderr.write("usage: dxf_corpus.py OUTDIR\n")
        sys.exit(2)
    for name in write(sys.argv[1]):
        print(name)
