#!/usr/bin/env python3
"""A fixture from a DXF drawing: the part read by wrenchd_dxf (the largest,
or --part N), its mass from its area, a thickness and a density, its unit
the drawing's, and no fixels yet (wrenchctl design places them; or give
--fixel X,Y for each: moved onto the outline when within 1e-4 of it, as a
table's digits leave it).  The README's walk-through uses it.

    /usr/bin/python3 examples/dxf_fixture.py sheet.dxf bracket.json \\
        [--part N] [--thickness 3] [--density 2.7e-6] [--friction 0.3] [--fixel X,Y ...]

The density is in kg per cubic drawing unit (aluminium: 2.7e-6 kg/mm^3);
the report of the drawing goes to stderr."""

import argparse
import json
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "clients", "python"))
import wrenchd_arcs  # noqa: E402
import wrenchd_dxf  # noqa: E402


def on_outline(shape, point, within):
    """The point of the shape's boundary nearest `point` (a fixel typed with
    the digits a table prints), when within `within` of it."""
    best = None
    for loop in shape["loops"]:
        for k, v in enumerate(loop):
            w = loop[(k + 1) % len(loop)]
            seg = wrenchd_arcs.Segment(0, k, v[:2], w[:2], v[2] if len(v) > 2 else 0.0)
            _, q, d = seg.nearest(point)
            if best is None or d < best[1]:
                best = (q, d)
    if best[1] > within:
        raise ValueError("--fixel %g,%g is %g from the outline" % (point[0], point[1], best[1]))
    return [best[0][0], best[0][1]]


def main(argv=None):
    parser = argparse.ArgumentParser(prog="dxf_fixture.py", description=__doc__.split("\n\n")[0])
    parser.add_argument("dxf")
    parser.add_argument("fixture", help="the fixture file to write")
    parser.add_argument("--part", default="largest", help="N or largest (default)")
    parser.add_argument("--thickness", type=float, default=3.0, help="drawing units (default 3)")
    parser.add_argument("--density", type=float, default=2.7e-6,
                        help="kg per cubic drawing unit (default 2.7e-6: aluminium in mm)")
    parser.add_argument("--friction", type=float, default=0.3, help="static friction (default 0.3)")
    parser.add_argument("--fixel", action="append", default=[], metavar="X,Y")
    args = parser.parse_args(argv)
    try:
        parts, report = wrenchd_dxf.read_dxf(args.dxf)
        part = parts[wrenchd_dxf._part_number(args.part, len(parts)) - 1]
    except (wrenchd_dxf.DxfShapeError, OSError) as error:
        sys.stderr.write("dxf_fixture: %s: %s\n" % (args.dxf, error))
        return 1
    for other in parts:
        if other is not part:
            sys.stderr.write("dxf_fixture: not taken: part %d, area %.6g %s^2, x %.6g to %.6g, "
                             "y %.6g to %.6g\n" % (other["number"], other["area"], other["unit"],
                                                   other["extent"][0], other["extent"][2],
                                                   other["extent"][1], other["extent"][3]))
    fixture = {"name": "%s part %d" % (os.path.basename(args.dxf), part["number"]),
               "units": wrenchd_dxf.fixture_units(report),
               "body": {"mass": part["area"] * args.thickness * args.density, "shape": part["shape"]},
               "friction": {"static": args.friction},
               "fixels": []}
    for f in args.fixel:
        try:
            at = on_outline(part["shape"], [float(c) for c in f.split(",")], 1e-4)
        except ValueError as error:
            sys.stderr.write("dxf_fixture: %s\n" % error)
            return 1
        fixture["fixels"].append({"at": at})
    with open(args.fixture, "w") as fh:
        json.dump(fixture, fh, indent=1)
        fh.write("\n")
    sys.stderr.write("dxf_fixture: %s: part %d, area %.6g %s^2, mass %.4g kg, %d fixels\n" % (
        args.fixture, part["number"], part["area"], part["unit"], fixture["body"]["mass"],
        len(fixture["fixels"])))
    return 0


if __name__ == "__main__":
    sys.exit(main())
