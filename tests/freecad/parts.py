"""Parts built with FreeCAD's Part and Sketcher APIs, for the tests.

Each builder returns FreeCAD shapes or document objects; the tests hold
wrenchd's answers against FreeCAD's own geometry of them (area, centre of
mass, inertia, lengths, distances)."""

import math

import FreeCAD
import Part
import Sketcher
from FreeCAD import Vector as V


def vertical_edges(shape):
    return [i for i, e in enumerate(shape.Edges)
            if abs(e.Vertexes[0].Point.x - e.Vertexes[-1].Point.x) < 1e-9
            and abs(e.Vertexes[0].Point.y - e.Vertexes[-1].Point.y) < 1e-9
            and abs(e.Vertexes[0].Point.z - e.Vertexes[-1].Point.z) > 1e-9]


def face_at(shape, normal, offset):
    """The index of the planar face of `shape` with outward normal `normal`
    whose plane is at `offset` along it."""
    found = []
    for i, f in enumerate(shape.Faces):
        if f.findPlane() is None:
            continue
        n = f.normalAt(*f.Surface.parameter(f.CenterOfMass))
        if n.getAngle(normal) < 1e-9 and abs(f.CenterOfMass.dot(normal) - offset) < 1e-7:
            found.append(i)
    assert len(found) == 1, "%d faces along %s at %s" % (len(found), normal, offset)
    return found[0]


def filleted_plate(length=120.0, width=70.0, thickness=10.0, radius=8.0, hole=(30.0, 35.0),
                   hole_radius=6.0):
    """A plate with its four vertical edges filleted and a locating hole
    through it (a full circle)."""
    box = Part.makeBox(length, width, thickness)
    plate = box.makeFillet(radius, [box.Edges[i] for i in vertical_edges(box)])
    return plate.cut(Part.makeCylinder(hole_radius, thickness, V(hole[0], hole[1], 0)))


def parametric_plate(doc, length=120.0, width=60.0, thickness=10.0, radius=8.0,
                     hole=(30.0, 30.0), hole_radius=6.0):
    """The filleted plate with a locating hole as document features (Box,
    Fillet, Cylinder, Cut), to change and recompute.  Returns the Cut."""
    box = doc.addObject("Part::Box", "Box")
    box.Length, box.Width, box.Height = length, width, thickness
    doc.recompute()
    fillet = doc.addObject("Part::Fillet", "Fillet")
    fillet.Base = box
    fillet.Edges = [(i + 1, radius, radius) for i in vertical_edges(box.Shape)]
    cylinder = doc.addObject("Part::Cylinder", "Hole")
    cylinder.Radius, cylinder.Height = hole_radius, thickness
    cylinder.Placement = FreeCAD.Placement(V(hole[0], hole[1], 0), FreeCAD.Rotation())
    cut = doc.addObject("Part::Cut", "Plate")
    cut.Base, cut.Tool = fillet, cylinder
    doc.recompute()
    for o in (box, fillet, cylinder):
        o.Visibility = False
    return cut


def slot(x0, x1, y, half_width):
    """A stadium from (x0, y) to (x1, y), half_width wide each side."""
    r = half_width
    edges = [Part.LineSegment(V(x0, y - r, 0), V(x1, y - r, 0)).toShape(),
             Part.ArcOfCircle(Part.Circle(V(x1, y, 0), V(0, 0, 1), r), -math.pi / 2,
                              math.pi / 2).toShape(),
             Part.LineSegment(V(x1, y + r, 0), V(x0, y + r, 0)).toShape(),
             Part.ArcOfCircle(Part.Circle(V(x0, y, 0), V(0, 0, 1), r), math.pi / 2,
                              3 * math.pi / 2).toShape()]
    return Part.Face(Part.Wire(Part.__sortEdges__(edges)))


def bracket_face():
    """The bracket of examples/bracket.json in FreeCAD: 120 x 60, corners
    filleted r 8, a hole of radius 6 at (30, 30), a slot of half-width 5
    whose round ends are centred at (75, 30) and (95, 30)."""
    plate = Part.makeBox(120, 60, 1)
    plate = plate.makeFillet(8, [plate.Edges[i] for i in vertical_edges(plate)])
    top = plate.Faces[face_at(plate, V(0, 0, 1), 1)]
    face = top.cut(Part.Face(Part.Wire(Part.Circle(V(30, 30, 1), V(0, 0, 1), 6).toShape())))
    s = slot(75, 95, 30, 5)
    s.translate(V(0, 0, 1))
    return face.cut(s).Faces[0]


def l_bracket():
    """A slotted L bracket 6 thick: an L of 100 x 80 with an inner fillet,
    a slot and a hole, as a solid standing on z = 0."""
    pts = [V(0, 0, 0), V(100, 0, 0), V(100, 30, 0), V(40, 30, 0), V(40, 80, 0), V(0, 80, 0)]
    wire = Part.makePolygon(pts + [pts[0]])
    solid = Part.Face(wire).extrude(V(0, 0, 6))
    inner = [i for i, e in enumerate(solid.Edges)
             if i in vertical_edges(solid) and abs(e.Vertexes[0].Point.x - 40) < 1e-9
             and abs(e.Vertexes[0].Point.y - 30) < 1e-9]
    solid = solid.makeFillet(6, [solid.Edges[i] for i in inner])
    cutter = slot(60, 85, 15, 4).extrude(V(0, 0, 6))
    solid = solid.cut(cutter)
    return solid.cut(Part.makeCylinder(5, 6, V(20, 60, 0)))


def curved_face():
    """A face with a B-spline side, an ellipse hole and a full circle hole:
    what outline() must follow by arcs."""
    spline = Part.BSplineCurve()
    spline.interpolate([V(0, 0, 0), V(30, 10, 0), V(60, -6, 0), V(90, 0, 0)])
    outer = Part.Wire([spline.toShape(),
                       Part.LineSegment(V(90, 0, 0), V(90, 50, 0)).toShape(),
                       Part.LineSegment(V(90, 50, 0), V(0, 50, 0)).toShape(),
                       Part.LineSegment(V(0, 50, 0), V(0, 0, 0)).toShape()])
    face = Part.Face(outer)
    ellipse = Part.Ellipse(V(30, 28, 0), 12, 6)
    face = face.cut(Part.Face(Part.Wire(ellipse.toShape())))
    face = face.cut(Part.Face(Part.Wire(Part.Circle(V(70, 30, 0), V(0, 0, 1), 5).toShape())))
    return face.Faces[0]


def sketch_part(doc, length=80.0, width=40.0, radius=6.0, hole=(20.0, 20.0), hole_radius=4.0):
    """A closed sketch: a rectangle whose two right corners are rounded
    (tangent arcs) and a hole, fully constrained: constraint "Length" is the
    length, "HoleRadius" the hole's radius."""
    sk = doc.addObject("Sketcher::SketchObject", "Sketch")
    L, W, r = length, width, radius
    g = [Part.LineSegment(V(0, 0, 0), V(L - r, 0, 0)),                     # 0 bottom
         Part.ArcOfCircle(Part.Circle(V(L - r, r, 0), V(0, 0, 1), r), -math.pi / 2, 0),  # 1
         Part.LineSegment(V(L, r, 0), V(L, W - r, 0)),                     # 2 right
         Part.ArcOfCircle(Part.Circle(V(L - r, W - r, 0), V(0, 0, 1), r), 0, math.pi / 2),  # 3
         Part.LineSegment(V(L - r, W, 0), V(0, W, 0)),                     # 4 top
         Part.LineSegment(V(0, W, 0), V(0, 0, 0)),                         # 5 left
         Part.Circle(V(hole[0], hole[1], 0), V(0, 0, 1), hole_radius)]     # 6 hole
    sk.addGeometry(g, False)
    c = [Sketcher.Constraint("Tangent", 0, 2, 1, 1),                    # end to end, tangent
         Sketcher.Constraint("Tangent", 1, 2, 2, 1),
         Sketcher.Constraint("Tangent", 2, 2, 3, 1),
         Sketcher.Constraint("Tangent", 3, 2, 4, 1),
         Sketcher.Constraint("Coincident", 4, 2, 5, 1),
         Sketcher.Constraint("Coincident", 5, 2, 0, 1),
         Sketcher.Constraint("Horizontal", 0), Sketcher.Constraint("Horizontal", 4),
         Sketcher.Constraint("Vertical", 2), Sketcher.Constraint("Vertical", 5),
         Sketcher.Constraint("Equal", 1, 3),
         Sketcher.Constraint("Coincident", 0, 1, -1, 1),                   # at the origin
         Sketcher.Constraint("DistanceY", 5, 2, 5, 1, W),
         Sketcher.Constraint("Radius", 1, r),
         Sketcher.Constraint("DistanceX", -1, 1, 2, 1, L),
         Sketcher.Constraint("DistanceX", -1, 1, 6, 3, hole[0]),
         Sketcher.Constraint("DistanceY", -1, 1, 6, 3, hole[1]),
         Sketcher.Constraint("Radius", 6, hole_radius)]
    sk.addConstraint(c)
    sk.renameConstraint(len(c) - 4, "Length")
    sk.renameConstraint(len(c) - 1, "HoleRadius")
    doc.recompute()
    assert "Invalid" not in sk.State, sk.getStatusString()
    return sk


def sketch_face(sketch):
    """FreeCAD's own face of a sketch's wires (holes inside the outer one)."""
    return Part.makeFace(sketch.Shape.Wires, "Part::FaceMakerBullseye")


def sampled_area(face, points=20000):
    """The face's area from its wires alone: each wire as FreeCAD samples it
    (Wire.discretize, in order), by the shoelace formula; the outer wire's
    less the holes'.  A reference for faces bounded by B-splines, whose
    face.Area FreeCAD 0.20 integrates less precisely."""
    def shoelace(wire):
        pts = wire.discretize(Number=points)
        if pts[0].distanceToPoint(pts[-1]) < 1e-12:
            pts = pts[:-1]
        n = len(pts)
        return abs(0.5 * sum(pts[k].x * pts[(k + 1) % n].y - pts[(k + 1) % n].x * pts[k].y
                             for k in range(n)))
    outer = face.OuterWire
    return shoelace(outer) - sum(shoelace(w) for w in face.Wires if not w.isSame(outer))


def mass_properties(face, outline):
    """FreeCAD's area, centre of mass (in the outline's 2-D frame) and polar
    moment of inertia about it (per unit area: the moment about the face's
    normal through the centre of mass, divided by the area)."""
    n = outline.normal
    M = face.MatrixOfInertia
    polar = sum(n[i] * M.A[4 * i + j] * n[j] for i in range(3) for j in range(3))
    x, y, _ = outline.to_2d(face.CenterOfMass)
    return face.Area, (x, y), polar / face.Area
