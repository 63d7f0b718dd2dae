#!/usr/bin/env python3
"""Writes a DXF drawing as a CAD program exports a laser-cutting sheet: a
motor-mount bracket (its top edge a SPLINE, two M4 holes, an adjusting slot
of LINEs and ARCs, one corner's fillet drawn twice), a spacer washer and a
cable clip beside it, a centreline through each hole, and a title.  The
README's walk-through reads it with clients/python/wrenchd_dxf.py.

    /usr/bin/python3 examples/sheet_dxf.py sheet.dxf

Needs ezdxf (Debian: python3-ezdxf)."""

import sys

import ezdxf


def sheet():
    doc = ezdxf.new("R2010")
    doc.header["$INSUNITS"] = 4                    # mm
    doc.layers.add("CUT")
    doc.layers.add("CENTER")
    doc.layers.add("TEXT")
    msp = doc.modelspace()
    cut = {"layer": "CUT"}
    # the bracket: a 100 x 60 plate, the top a smooth SPLINE, fillets of 6 at the bottom
    msp.add_line((6, 0), (94, 0), dxfattribs=cut)
    msp.add_arc((94, 6), 6, 270, 0, dxfattribs=cut)
    msp.add_arc((94, 6), 6, 270, 0, dxfattribs=cut)          # drawn twice, as exports do
    msp.add_line((100, 6), (100, 50), dxfattribs=cut)
    msp.add_spline(fit_points=[(100, 50), (80, 62), (50, 56), (20, 62), (0, 50)], dxfattribs=cut)
    msp.add_line((0, 50), (0, 6), dxfattribs=cut)
    msp.add_arc((6, 6), 6, 180, 270, dxfattribs=cut)
    for x in (15, 85):
        msp.add_circle((x, 15), 2.2, dxfattribs=cut)          # M4 clearance
        msp.add_line((x - 5, 15), (x + 5, 15), dxfattribs={"layer": "CENTER"})
        msp.add_line((x, 10), (x, 20), dxfattribs={"layer": "CENTER"})
    # the adjusting slot, 30 long, 6 wide
    msp.add_line((35, 32), (65, 32), dxfattribs=cut)
    msp.add_arc((65, 35), 3, 270, 90, dxfattribs=cut)
    msp.add_line((65, 38), (35, 38), dxfattribs=cut)
    msp.add_arc((35, 35), 3, 90, 270, dxfattribs=cut)
    # a spacer washer and a cable clip
    msp.add_circle((130, 20), 12, dxfattribs=cut)
    msp.add_circle((130, 20), 4.3, dxfattribs=cut)
    msp.add_lwpolyline([(120, 45, 0), (150, 45, 1), (150, 55, 0), (120, 55, 1)],
                       format="xyb", close=True, dxfattribs=cut)
    msp.add_text("MOTOR MOUNT 3 mm AL 5754", dxfattribs={"layer": "TEXT", "insert": (0, -12),
                                                           "height": 4})
    return doc


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.stderr.write("usage: sheet_dxf.py OUT.dxf\n")
        sys.exit(2)
    sheet().saveas(sys.argv[1])
