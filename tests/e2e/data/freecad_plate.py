# Makes freecad_plate.dxf with FreeCAD's own DXF writer (its C++ exporter,
# Import.writeDXFShape), so that tests/e2e/test_dxf.py reads a drawing ezdxf
# did not write.  Run with FreeCAD 0.20.2 (Debian 12: apt-get install
# freecad-python3), in this directory:
#
#     freecadcmd freecad_plate.py
#
# The part: a 60 x 40 plate, its corner at (60, 0) rounded with radius 5, a
# hole of diameter 8 at (15, 20) and a slot from (35, 15) to (45, 15) of
# width 6.  FreeCAD writes LINEs, ARCs and a CIRCLE on layer "none" and
# $INSUNITS 4 (mm).
import math
import os

import FreeCAD
import Import
import Part
from FreeCAD import Vector as V


def arc(c, r, a0, a1):
    circle = Part.Circle(V(c[0], c[1], 0), V(0, 0, 1), r)
    return Part.ArcOfCircle(circle, math.radians(a0), math.radians(a1)).toShape()


def seg(p, q):
    return Part.LineSegment(V(p[0], p[1], 0), V(q[0], q[1], 0)).toShape()


outer = Part.Wire(Part.__sortEdges__([
    seg((0, 0), (55, 0)), arc((55, 5), 5, -90, 0), seg((60, 5), (60, 40)),
    seg((60, 40), (0, 40)), seg((0, 40), (0, 0))]))
hole = Part.Wire([Part.Circle(V(15, 20, 0), V(0, 0, 1), 4).toShape()])
slot = Part.Wire(Part.__sortEdges__([
    seg((35, 12), (45, 12)), arc((45, 15), 3, -90, 90),
    seg((45, 18), (35, 18)), arc((35, 15), 3, 90, 270)]))
face = Part.Face(outer).cut(Part.Face(hole)).cut(Part.Face(slot)).Faces[0]
assert face.isValid()
print("FreeCAD %s: area %r" % (".".join(FreeCAD.Version()[:3]), face.Area))
# Its mass properties at unit density, which tests/e2e/test_dxf.py holds
# wrenchd's to: the centroid, and the polar moment about it (A33 of the
# matrix of inertia about the centre of mass).
c, m = face.CenterOfMass, face.MatrixOfInertia
print("centroid (%r, %r), polar moment %r" % (c.x, c.y, m.A33))
Import.writeDXFShape([face], os.path.join(os.getcwd(), "freecad_plate.dxf"))
