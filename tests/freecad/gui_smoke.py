# The Wrench workbench in FreeCAD's GUI, as a designer uses it: run by
# test_gui.py (and make freecad-picture) under Xvfb,
#
#     WRENCHD_SOCKET=... WRENCH_GUI_OUT=DIR WRENCH_GUI_SCRIPT=this file \
#         xvfb-run freecad tests/freecad/gui_smoke.py -M clients/freecad
#
# (FreeCAD 0.20 takes -M only after the file.)
# A bracket (a plate with filleted corners, a locating hole and a slot) is
# made; the workbench activated; its top face selected; then the commands
# Fixture from face, Add fixels (on points picked on edges and a vertex),
# Clear fixels, Design, Push regions and Gravity dial run as from the
# toolbar (Design with friction 0.25 and candidate sites 10 apart, as the
# README designs this bracket with wrenchctl).  The 3-D view from the top is
# saved as DIR/view.png (1200 x 800) and the whole window as DIR/window.png;
# DIR/result.json says what was found (the objects, their states and
# figures, the tree, the report view's lines).
# FreeCAD then exits with status 0 (the test reads result.json).
import json
import os
import sys
import time
import traceback

import FreeCAD
import FreeCADGui as Gui

OUT = os.environ["WRENCH_GUI_OUT"]
# FreeCAD runs this file without __file__: its path comes in the environment.
HERE = os.path.dirname(os.path.abspath(os.environ.get("WRENCH_GUI_SCRIPT",
                                                      "tests/freecad/gui_smoke.py")))
result = {"errors": [], "report": []}


def settle():
    from PySide2 import QtWidgets
    for _ in range(5):
        QtWidgets.QApplication.processEvents()
        Gui.updateGui()


def fit(view):
    """Everything in view, closer than fitAll (which fits a sphere round it)."""
    view.fitAll()
    camera = view.getCameraNode()
    camera.height.setValue(camera.height.getValue() * 0.8)
    settle()


def main():
    from PySide2 import QtCore, QtGui, QtWidgets
    sys.path.insert(0, HERE)
    import Part
    import parts
    from FreeCAD import Vector as V

    window = Gui.getMainWindow()
    window.resize(1500, 950)
    doc = FreeCAD.newDocument("Bracket")
    face = parts.bracket_face()
    solid = face.extrude(V(0, 0, -8))
    part = doc.addObject("Part::Feature", "Bracket")
    part.Shape = solid
    doc.recompute()
    top = parts.face_at(part.Shape, V(0, 0, 1), 1) + 1

    result["started_in"] = Gui.activeWorkbench().__class__.__name__
    Gui.activateWorkbench("WrenchWorkbench")
    result["workbench"] = Gui.activeWorkbench().__class__.__name__
    result["commands"] = [c for c in Gui.listCommands() if c.startswith("Wrench_")]
    Gui.Selection.clearSelection()
    Gui.Selection.addSelection(part, "Face%d" % top)
    Gui.runCommand("Wrench_Fixture")
    fixtures = [o for o in doc.Objects if o.Name.startswith("WrenchFixture")]
    result["fixtures"] = len(fixtures)
    fixture = fixtures[0]

    # Add fixels: points picked on two edges (a little off them, as a pick
    # on the screen is) and a vertex; then Clear fixels.
    def edge_at(p):
        return "Edge%d" % (1 + min(range(len(part.Shape.Edges)), key=lambda i: part.Shape.Edges[i]
                                   .distToShape(Part.Vertex(p))[0]))

    def vertex_at(p):
        return "Vertex%d" % (1 + min(range(len(part.Shape.Vertexes)),
                                     key=lambda i: part.Shape.Vertexes[i].Point.distanceToPoint(p)))

    Gui.Selection.clearSelection()
    for p in (V(50, 0.01, 1), V(-0.01, 40, 1)):
        Gui.Selection.addSelection(doc.Name, part.Name, edge_at(p), p.x, p.y, p.z)
    Gui.Selection.addSelection(doc.Name, part.Name, vertex_at(V(112, 0, 1)))
    Gui.Selection.addSelection(fixture)
    Gui.runCommand("Wrench_AddFixels")
    result["picked"] = [[p.x, p.y, p.z] for p in fixture.FixelPoints]
    result["picked_normals"] = [[n.x, n.y, n.z] for n in fixture.FixelNormals]
    result["picked_state"] = list(fixture.State)
    Gui.Selection.clearSelection()
    Gui.Selection.addSelection(fixture)
    Gui.runCommand("Wrench_ClearFixels")
    result["cleared"] = len(fixture.FixelPoints)

    Gui.Selection.clearSelection()
    Gui.Selection.addSelection(fixture)
    # as the README's wrenchctl design of this bracket (examples/bracket.json)
    fixture.StaticFriction = fixture.KineticFriction = 0.25
    fixture.DesignSpacing = 10
    Gui.runCommand("Wrench_Design")
    Gui.runCommand("Wrench_Regions")
    Gui.runCommand("Wrench_GravityDial")
    doc.recompute()
    result["objects"] = [{"name": o.Name, "label": o.Label, "state": list(o.State),
                          "type": type(getattr(o, "Proxy", None)).__name__,
                          "view": type(getattr(o.ViewObject, "Proxy", None)).__name__,
                          "visible": bool(o.ViewObject.Visibility)}
                         for o in doc.Objects]
    result["fixels"] = [[p.x, p.y, p.z] for p in fixture.FixelPoints]
    result["designs"] = list(fixture.Designs)
    for o in doc.Objects:
        if o.Name.startswith("WrenchRegions"):
            result.setdefault("regions", {})[o.Set] = {"count": o.Count, "total": o.TotalLength,
                                                       "colour": list(o.ViewObject.LineColor)[:3],
                                                       "width": o.ViewObject.LineWidth}
        if o.Name.startswith("WrenchBestPush"):
            result["best_push"] = {"found": o.Found, "margin": o.Margin,
                                   "colour": list(o.ViewObject.ShapeColor)[:3]}
    Gui.Selection.clearSelection()
    view = Gui.ActiveDocument.ActiveView
    view.viewTop()
    fit(view)
    view.saveImage(os.path.join(OUT, "view.png"), 1200, 800, "White")

    # The whole window: the start page closed, the tree (wide enough for the
    # labels) and the report view shown, no other panel; the 3-D view (an OpenGL widget, which a
    # window grab leaves blank) drawn in from saveImage.
    mdi = window.findChild(QtWidgets.QMdiArea)
    for sub in mdi.subWindowList():
        if sub.windowTitle().startswith("Start"):
            sub.close()
    combo = window.findChild(QtWidgets.QDockWidget, "Combo View")
    report_dock = window.findChild(QtWidgets.QDockWidget, "Report view")
    for dock in window.findChildren(QtWidgets.QDockWidget):
        dock.setVisible(dock in (combo, report_dock))
    window.addDockWidget(QtCore.Qt.LeftDockWidgetArea, combo)
    window.addDockWidget(QtCore.Qt.BottomDockWidgetArea, report_dock)
    for bottom in (QtCore.Qt.BottomLeftCorner, QtCore.Qt.BottomRightCorner):
        window.setCorner(bottom, QtCore.Qt.BottomDockWidgetArea)    # the report view's, full width
    window.resizeDocks([combo], [470], QtCore.Qt.Horizontal)
    window.resizeDocks([report_dock], [190], QtCore.Qt.Vertical)
    settle()
    viewer = mdi.activeSubWindow().widget()
    corner = viewer.mapTo(window, QtCore.QPoint(0, 0))
    fit(view)
    inset = os.path.join(OUT, "inset.png")
    view.saveImage(inset, viewer.width(), viewer.height(), "White")
    both = [o for o in doc.Objects if o.Name.startswith("WrenchRegions") and o.Set == "both"][0]
    Gui.Selection.addSelection(doc.Name, both.Name)
    settle()
    time.sleep(0.3)
    settle()
    picture = window.grab()
    painter = QtGui.QPainter(picture)
    painter.drawImage(corner, QtGui.QImage(inset))
    painter.end()
    picture.save(os.path.join(OUT, "window.png"))
    os.remove(inset)
    # the tree: each object's item and how many items it holds
    tree = [w for w in window.findChildren(QtWidgets.QTreeWidget) if w.topLevelItemCount()][0]
    document = tree.topLevelItem(0).child(0)
    result["tree"] = [[document.child(i).text(0), document.child(i).childCount()]
                      for i in range(document.childCount())]
    # the report view's text, as the designer reads it
    result["report"] = report_dock.widget().toPlainText().splitlines()

    # After the picture, two mistakes and what the report view says of them:
    # a fixel moved off the outline, and a socket where no wrenchd listens.
    report_dock.widget().clear()
    good = list(fixture.FixelPoints)
    # 0.5 into the part along its normal: 0.5 from the outline wherever the
    # design put it (a fillet's radius is 8)
    fixture.FixelPoints = [good[0] + fixture.FixelNormals[0] * 0.5] + good[1:]
    doc.recompute()
    settle()
    fixture.FixelPoints = good
    fixture.Socket = os.path.join(OUT, "nobody.sock")
    doc.recompute()
    settle()
    result["mistakes"] = report_dock.widget().toPlainText().splitlines()
    fixture.Socket = ""
    doc.recompute()
    result["after_mistakes"] = [o.Label for o in doc.Objects if "Invalid" in o.State]

    # Rest buttons picked on the part: a fillet's circular edge (its centre)
    # and a vertex on its underside (z = -7), a point picked on its top
    # face; their loads written beside them in the 3-D view.  (A hole's
    # centre is refused: a button there is not under the part.)
    def circle_edge_at(centre):
        return "Edge%d" % (1 + [i for i, e in enumerate(part.Shape.Edges)
                                if isinstance(e.Curve, Part.Circle)
                                and e.Curve.Center.distanceToPoint(centre) < 1e-9][0])

    Gui.Selection.clearSelection()
    Gui.Selection.addSelection(doc.Name, part.Name, circle_edge_at(V(8, 52, -7)))
    Gui.Selection.addSelection(doc.Name, part.Name, vertex_at(V(112, 0, -7)))
    Gui.Selection.addSelection(doc.Name, part.Name, "Face%d" % top, 90, 50, 1)
    Gui.Selection.addSelection(fixture)
    report_dock.widget().clear()
    Gui.runCommand("Wrench_RestButtons")
    settle()
    result["button_report"] = report_dock.widget().toPlainText().splitlines()
    buttons = [o for o in doc.Objects if o.Name.startswith("WrenchSupports")]
    result["buttons"] = [[p.x, p.y, p.z] for p in fixture.SupportPoints]
    result["button_loads"] = list(fixture.NormalLoads)
    result["button_state"] = [list(o.State) for o in buttons]
    result["button_labels"] = [list(o.LoadLabels) for o in buttons]
    from pivy import coin
    search = coin.SoSearchAction()
    search.setType(coin.SoText2.getClassTypeId())
    search.setInterest(coin.SoSearchAction.ALL)
    search.apply(buttons[0].ViewObject.RootNode)
    paths = search.getPaths()
    result["button_texts"] = [paths[i].getTail().string.getValues()[0]
                              for i in range(paths.getLength())]
    # a down clamp picked on the top face, pressing 100 N at first
    Gui.Selection.clearSelection()
    Gui.Selection.addSelection(doc.Name, part.Name, "Face%d" % top, 60, 30, 1)
    Gui.Selection.addSelection(fixture)
    Gui.runCommand("Wrench_DownClamps")
    settle()
    result["clamps"] = [[p.x, p.y, p.z] for p in fixture.DownPoints]
    result["clamp_forces"] = list(fixture.DownForces)
    result["clamp_loads"] = list(fixture.NormalLoads)
    result["clamp_labels"] = list(buttons[0].LoadLabels)
    search.apply(buttons[0].ViewObject.RootNode)
    paths = search.getPaths()
    result["clamp_texts"] = [paths[i].getTail().string.getValues()[0]
                             for i in range(paths.getLength())]
    # Push regions on the buttons: what the report view says of the best push
    report_dock.widget().clear()
    Gui.Selection.clearSelection()
    Gui.Selection.addSelection(fixture)
    Gui.runCommand("Wrench_Regions")
    settle()
    result["regions_on_buttons"] = report_dock.widget().toPlainText().splitlines()
    result["regions_on_buttons_labels"] = sorted(o.Label for o in doc.Objects
                                                 if o.Name.startswith("WrenchRegions"))
    # the buttons and the clamp from above at an angle, the regions hidden
    # (on the buttons they ask for a force)
    for o in doc.Objects:
        if o.Name.startswith(("WrenchRegion", "WrenchGravityDial", "WrenchBestPush")):
            o.ViewObject.Visibility = False
    Gui.Selection.clearSelection()
    view.viewIsometric()
    fit(view)
    view.saveImage(os.path.join(OUT, "buttons.png"), 1200, 800, "White")
    del Part


try:
    main()
except Exception:
    result["errors"].append(traceback.format_exc())
with open(os.path.join(OUT, "result.json"), "w") as f:
    json.dump(result, f, indent=1)
sys.stdout.flush()
os._exit(0)
