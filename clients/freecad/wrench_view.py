"""wrench_view -- how the Wrench workbench's objects look: colours, widths,
icons, the view provider (wrench_freecad.py is the workbench's one import;
the objects are wrench_objects.py's).  FreeCADGui is never imported: the
view provider is attached only when the GUI is up."""

import os

import FreeCAD


def _objects():
    """wrench_objects, which imports this module: asked for when a view
    provider runs, long after both are loaded."""
    import wrench_objects
    return wrench_objects

# Region colours (red, green, blue in [0, 1]) and widths in pixels.  both is
# goal and strong together, so only under both do regions of two sets lie
# on one another: both, what to push with, is drawn the widest and on top.
COLOURS = {"goal": (0.15, 0.40, 0.95), "strong": (1.00, 0.55, 0.00), "both": (0.00, 0.72, 0.20)}
LINE_WIDTHS = {"goal": 5.0, "strong": 5.0, "both": 10.0}
# The rest buttons, their loads' arrows and labels.
SUPPORT_COLOUR = (0.55, 0.25, 0.05)


def least_force_colours(forces):
    """Per piece: blue at the least F*, red at the most, grey where none."""
    finite = [f for f in forces if f >= 0]
    lo, hi = (min(finite), max(finite)) if finite else (0.0, 0.0)
    out = []
    for f in forces:
        if f < 0:
            out.append((0.8, 0.8, 0.8))
            continue
        x = (f - lo) / (hi - lo) if hi > lo else 0.0
        out.append((0.12 + x * (0.75 - 0.12), 0.31 + x * (0.22 - 0.31), 0.61 + x * (0.17 - 0.61)))
    return out


# The least push's arrow (a WrenchLeastForce's last edges), as the best push's.
ARROW_COLOUR = (0.85, 0.0, 0.55)


def colour_least_force(obj):
    """The pieces' colours, and the arrow's, when the GUI shows the object."""
    vobj = getattr(obj, "ViewObject", None)
    if FreeCAD.GuiUp and vobj is not None and hasattr(vobj, "LineColorArray"):
        vobj.LineWidth = 6.0
        colours = least_force_colours(list(obj.Forces))
        vobj.LineColorArray = colours + [ARROW_COLOUR] * (len(obj.Shape.Edges) - len(colours))


# ---- view providers ---------------------------------------------------------------

ICONS = os.path.join(os.path.dirname(os.path.realpath(__file__)), "Resources", "icons")


def icon(name):
    return os.path.join(ICONS, name + ".svg")


class ViewProviderWrench:
    """Colours and icons; the regions' objects as children of their set."""

    ICON = "Wrench"

    def __init__(self, vobj):
        vobj.Proxy = self
        self.style(vobj)

    def style(self, vobj):
        obj = vobj.Object
        kind = _objects()._proxy_name(obj)
        if kind in ("WrenchRegions", "WrenchRegion"):
            which = obj.Set if kind == "WrenchRegions" else \
                (obj.Regions.Set if obj.Regions is not None else "both")
            which = which if which in COLOURS else "both"
            vobj.LineColor = COLOURS[which]
            vobj.PointColor = COLOURS[which]
            vobj.LineWidth = LINE_WIDTHS[which]
            vobj.PointSize = 1.0
        elif kind == "WrenchGravityDial":
            vobj.LineColor = COLOURS[obj.Set if obj.Set in COLOURS else "both"]
            vobj.LineWidth = 4.0
            vobj.PointSize = 1.0
        elif kind == "WrenchFixture":
            vobj.LineColor = (0.1, 0.1, 0.1)
            vobj.LineWidth = 1.0
            vobj.PointSize = 1.0
        elif kind == "WrenchFixels":
            vobj.ShapeColor = (0.25, 0.25, 0.28)
            vobj.LineColor = (0.85, 0.1, 0.1)
            vobj.LineWidth = 2.0
            vobj.PointSize = 1.0
        elif kind == "WrenchBestPush":
            vobj.ShapeColor = ARROW_COLOUR
            vobj.LineColor = (0.5, 0.0, 0.3)
        elif kind == "WrenchSupports":
            vobj.ShapeColor = SUPPORT_COLOUR
            vobj.LineColor = SUPPORT_COLOUR
            vobj.LineWidth = 3.0
            vobj.PointSize = 1.0

    def attach(self, vobj):
        self.Object = vobj.Object
        self.labels = None

    def updateData(self, obj, prop):
        if prop == "Set" and getattr(obj, "ViewObject", None) is not None:
            self.style(obj.ViewObject)
        if prop in ("LoadLabels", "LabelPoints") and getattr(obj, "ViewObject", None) is not None:
            self.write_labels(obj.ViewObject)

    def write_labels(self, vobj):
        """A WrenchSupports' LoadLabels written in the 3-D view at its
        LabelPoints (a Coin text node each, under one separator)."""
        from pivy import coin
        obj = vobj.Object
        root = vobj.RootNode
        old = getattr(self, "labels", None)
        if old is not None and root.findChild(old) >= 0:
            root.removeChild(old)
        self.labels = coin.SoSeparator()
        self.labels.setName("WrenchLoadLabels")
        colour = coin.SoBaseColor()
        colour.rgb = SUPPORT_COLOUR
        self.labels.addChild(colour)
        for text, at in zip(obj.LoadLabels, obj.LabelPoints):
            node = coin.SoSeparator()
            move = coin.SoTranslation()
            move.translation = (at.x, at.y, at.z)
            label = coin.SoText2()
            label.string = text
            node.addChild(move)
            node.addChild(label)
            self.labels.addChild(node)
        root.addChild(self.labels)

    def claimChildren(self):
        obj = getattr(self, "Object", None)
        if obj is not None and _objects()._is(obj, "WrenchRegions"):
            return _objects().region_objects(obj)
        return []

    def onDelete(self, vobj, subelements):
        obj = vobj.Object
        if _objects()._is(obj, "WrenchRegions"):
            for child in _objects().region_objects(obj):
                obj.Document.removeObject(child.Name)
        return True

    def getIcon(self):
        obj = getattr(self, "Object", None)
        name = {"WrenchFixture": "WrenchFixture", "WrenchRegions": "WrenchRegions",
                "WrenchRegion": "WrenchRegions", "WrenchFixels": "WrenchFixels",
                "WrenchBestPush": "WrenchBestPush", "WrenchGravityDial": "WrenchGravityDial",
                "WrenchLeastForce": "WrenchRegions", "WrenchSupports": "WrenchFixels"}.get(
                    _objects()._proxy_name(obj) if obj is not None else "", "Wrench")
        return icon(name)

    def __getstate__(self):
        return None

    def __setstate__(self, state):
        return None


def _attach_view(obj):
    """A view provider for the object when the GUI is up and it has none."""
    if not FreeCAD.GuiUp:
        return
    vobj = getattr(obj, "ViewObject", None)
    if vobj is not None and not isinstance(getattr(vobj, "Proxy", None), ViewProviderWrench):
        ViewProviderWrench(vobj)
