"""The Wrench workbench's commands (GUI only; the work is wrench_freecad's).

    Wrench_Fixture       select a planar face of a part (or a closed sketch),
                         and optionally vertices or points on its edges: a
                         WrenchFixture there, its fixels shown as locators
    Wrench_AddFixels     select vertices or points on the part's edges: fixels
                         there (at a corner, the normal is the inward bisector)
    Wrench_ClearFixels   the fixture's fixels removed
    Wrench_Regions       the push regions of goal, strong and both, and the
                         best push; both is what to push with and let go
    Wrench_GravityDial   the tilts under which gravity alone seats and holds
                         the part, as a dial
    Wrench_Design        fixture.design: where to put the fixels, with
                         FreeCAD's progress indicator; the best design placed
    Wrench_LeastForce    with the fixture's Gravity or Loads: the least push
                         force along the outline as coloured pieces, and where
                         the smallest push suffices (an arrow); on rest
                         buttons, the least push that seats the part against
                         their friction, with the floating part's beside it
    Wrench_RestButtons   select vertices, holes' circular edges (their centre)
                         or points picked on the part: rest buttons there,
                         taken into the face's plane, their normal loads shown
    Wrench_DownClamps    the same picks: down clamps pressing the part onto its
                         buttons (DOWN_FORCE each at first)
    Wrench_ClearRestButtons  the fixture's rest buttons and down clamps removed

A command works on the WrenchFixture selected (or one of its objects), else
on the document's only one.  Messages and errors go to the report view.
"""

import FreeCAD
import FreeCADGui
import Part

import wrench_freecad as wf


def _say(text):
    FreeCAD.Console.PrintMessage("Wrench: %s\n" % text)


def _fail(text):
    FreeCAD.Console.PrintError("Wrench: %s\n" % text)


def _fixture_in_selection(doc):
    """The fixture the user means: one selected (or the fixture of a
    selected Wrench object), else the document's only one."""
    for s in FreeCADGui.Selection.getSelectionEx():
        obj = s.Object
        if wf._is(obj, "WrenchFixture"):
            return obj
        if wf._is(obj, "WrenchRegion") and obj.Regions is not None:
            return obj.Regions.Fixture
        if hasattr(obj, "Fixture") and wf._is(obj.Fixture, "WrenchFixture"):
            return obj.Fixture
    fixtures = [o for o in doc.Objects if wf._is(o, "WrenchFixture")]
    if len(fixtures) == 1:
        return fixtures[0]
    if not fixtures:
        _fail("no fixture in %s: select a planar face of the part (or a closed sketch) and run "
              "Fixture from face first" % doc.Label)
    else:
        _fail("%d fixtures in %s: select the one meant (or one of its objects)"
              % (len(fixtures), doc.Label))
    return None


def _picked_points():
    """Document points of the selected vertices and of the points picked on
    selected edges (moved onto the edge), with whether each is a vertex."""
    out = []
    for s in FreeCADGui.Selection.getSelectionEx():
        if wf._proxy_name(s.Object).startswith("Wrench"):
            continue
        picked = list(s.PickedPoints)
        for k, (name, sub) in enumerate(zip(s.SubElementNames, s.SubObjects)):
            if name.startswith("Vertex"):
                out.append((sub.Point, True))
            elif name.startswith("Edge") and k < len(picked):
                nearest = sub.distToShape(Part.Vertex(picked[k]))[1][0][0]
                out.append((nearest, False))
    return out


def _run(doc, what, action):
    """action() in one undo step; a wrench or outline error reported."""
    doc.openTransaction(what)
    try:
        result = action()
    except (wf.WrenchError, wf.OutlineError, ValueError) as error:
        doc.abortTransaction()
        _fail("%s: %s" % (what, error))
        return None
    doc.commitTransaction()
    return result


def _recompute(doc, objects):
    doc.recompute()
    failed = [o for o in objects if "Invalid" in o.State]
    for o in failed:
        _fail("%s: %s" % (o.Label, o.getStatusString()))
    return not failed


class _Command:
    NAME = ""
    ICON = "Wrench"
    MENU = ""
    TIP = ""

    def GetResources(self):
        return {"Pixmap": wf.icon(self.ICON), "MenuText": self.MENU, "ToolTip": self.TIP}

    def IsActive(self):
        return FreeCAD.ActiveDocument is not None


class FixtureCommand(_Command):
    NAME = "Wrench_Fixture"
    ICON = "WrenchFixture"
    MENU = "Fixture from face"
    TIP = ("Select a planar face of a part (or a closed sketch), and optionally vertices or "
           "points on its edges for the fixels: the part's outline as wrenchd sees it, and its "
           "fixels as locators with their friction cones")

    def Activated(self):
        doc = FreeCAD.ActiveDocument
        source = None
        for s in FreeCADGui.Selection.getSelectionEx():
            faces = [n for n in s.SubElementNames if n.startswith("Face")]
            if faces:
                source = (s.Object, faces[0])
                break
            if not s.SubElementNames and (s.Object.TypeId.startswith("Sketcher::")
                                          or len(getattr(s.Object, "Shape", Part.Shape()).Faces) == 1):
                source = (s.Object, "")
                break
        if source is None:
            _fail("Fixture from face: select a planar face of a part, or a closed sketch")
            return
        picks = _picked_points()

        def make():
            fixture = wf.make_fixture(doc, source, label="Fixture of %s" % source[0].Label)
            wf.make_fixels(fixture)
            doc.recompute()
            if "Invalid" in fixture.State:
                raise wf.WrenchError(fixture.getStatusString())
            if picks:
                _add_fixels(fixture, picks)
            return fixture

        fixture = _run(doc, "Wrench fixture", make)
        if fixture is None:
            return
        _say("%s: the outline of %s%s, %d loop%s, %d segments, lengths in %s%s" % (
            fixture.Label, source[0].Label, " " + source[1] if source[1] else "", fixture.Loops,
            "" if fixture.Loops == 1 else "s", fixture.Segments, wf.UNIT,
            "; curves followed by arcs within %s %s (at most %s off): %s" % (
                wf._fmt(fixture.ToleranceUsed), wf.UNIT, wf._fmt(fixture.Deviation),
                "; ".join(fixture.Approximated)) if fixture.Approximated else ""))
        if fixture.OtherParts:
            _say("the largest part is taken; not read: %s" % "; ".join(fixture.OtherParts))
        if fixture.Ignored:
            _say("left out (open): %s" % "; ".join(fixture.Ignored))
        if not fixture.FixelPoints:
            _say("now place the fixels: select vertices or points on the part's edges and run Add "
                 "fixels, or run Design to have wrenchd place them")


def _add_fixels(fixture, picks):
    points, normals = list(fixture.FixelPoints), list(fixture.FixelNormals)
    normals += [FreeCAD.Vector()] * (len(points) - len(normals))
    for point, is_vertex in picks:
        p, n = wf.fixel_at(fixture, point, None if is_vertex else False)
        points.append(p)
        normals.append(n)
        _say("fixel %d at %s %s%s" % (len(points), wf._fmt_point(p), wf.UNIT,
                                   ", normal %s (the corner's inward bisector)" % wf._fmt_point(n)
                                   if n.Length > 0 else ""))
    fixture.FixelPoints, fixture.FixelNormals = points, normals
    _recompute(fixture.Document, [fixture])


class AddFixelsCommand(_Command):
    NAME = "Wrench_AddFixels"
    ICON = "WrenchAddFixels"
    MENU = "Add fixels"
    TIP = ("Select vertices or points on the part's edges: fixels there (at a corner, the contact "
           "normal is the inward bisector; change it in FixelNormals)")

    def Activated(self):
        doc = FreeCAD.ActiveDocument
        fixture = _fixture_in_selection(doc)
        if fixture is None:
            return
        picks = _picked_points()
        if not picks:
            _fail("Add fixels: select vertices or points on the part's edges")
            return
        _run(doc, "Wrench fixels", lambda: _add_fixels(fixture, picks))


class _ClearCommand(_Command):
    """Empties the fixture's list properties CLEARS, in one undo step."""
    ICON = "WrenchClearFixels"
    CLEARS = ()
    UNDO = ""

    def Activated(self):
        doc = FreeCAD.ActiveDocument
        fixture = _fixture_in_selection(doc)
        if fixture is None:
            return

        def clear():
            for name in self.CLEARS:
                setattr(fixture, name, [])
            _recompute(doc, [fixture])
        _run(doc, self.UNDO, clear)


class ClearFixelsCommand(_ClearCommand):
    NAME = "Wrench_ClearFixels"
    MENU = "Clear fixels"
    TIP = "Remove the fixture's fixels"
    CLEARS = ("FixelPoints", "FixelNormals")
    UNDO = "Wrench fixels cleared"


def _dependents(fixture, kind):
    return [o for o in fixture.InList if wf._is(o, kind)]


def _views(fixture):
    """The fixture's regions of goal, strong and both (on rest buttons goal
    alone, the one wrenchd answers there), its fixels and its best push:
    those it lacks are made."""
    have = {o.Set for o in _dependents(fixture, "WrenchRegions")}
    sets = ("goal",) if list(fixture.SupportPoints) else wf.SETS
    made = [wf.make_regions(fixture, which) for which in sets if which not in have]
    if not _dependents(fixture, "WrenchFixels"):
        made.append(wf.make_fixels(fixture))
    if not _dependents(fixture, "WrenchBestPush"):
        made.append(wf.make_best_push(fixture))
    return made


class RegionsCommand(_Command):
    NAME = "Wrench_Regions"
    ICON = "WrenchRegions"
    MENU = "Push regions"
    TIP = ("Where a finger pushing along the outline's inward normal seats the part from any "
           "contact state (goal), holds it still once seated (strong), or both: push in both and "
           "let go. Also the best push, the one of both with the largest margin")

    def Activated(self):
        doc = FreeCAD.ActiveDocument
        fixture = _fixture_in_selection(doc)
        if fixture is None:
            return

        if _run(doc, "Wrench push regions", lambda: _views(fixture)) is None:
            return
        objects = _dependents(fixture, "WrenchRegions") + _dependents(fixture, "WrenchBestPush")
        if not _recompute(doc, [fixture] + objects):
            return
        if not fixture.FixelPoints:
            _say("%s has no fixels yet: add some (Add fixels) or run Design" % fixture.Label)
            return
        for regions in sorted(_dependents(fixture, "WrenchRegions"), key=lambda o: wf.SETS.index(o.Set)):
            _say("%s: %d region%s, %s %s long (%.2f %% of the outline)%s. %s" % (
                regions.Set, regions.Count, "" if regions.Count == 1 else "s",
                wf._fmt(regions.TotalLength), wf.UNIT, 100 * regions.Fraction,
                "" if regions.CriticalMu == -2 else
                ", none above mu %s" % wf._fmt(regions.CriticalMu) if regions.CriticalMu >= 0
                else ", not empty up to mu 2", regions.Meaning))
        for push in _dependents(fixture, "WrenchBestPush"):
            if push.Found and list(fixture.SupportPoints):
                _say("%s: %s at %s %s along %s; the least push on them anywhere is %s" % (
                    push.Label, push.Meaning, wf._fmt_point(push.At), wf.UNIT,
                    wf._fmt_point(push.Direction),
                    "%.4g N at %s" % (push.LeastForce, wf._fmt_point(push.LeastForceAt))
                    if push.LeastForce >= 0 else "none" if push.LeastForce == -1 else
                    "Least force's to find (on a face of straight lines alone)"))
            elif push.Found:
                _say("best push at %s %s along %s, margin %.4g: push there and let go (it is in "
                     "both)" % (wf._fmt_point(push.At), wf.UNIT, wf._fmt_point(push.Direction),
                                push.Margin))
                if fixture.Gravity or list(fixture.Loads):
                    _say("how hard: %s there under every load case; the least push anywhere is %s"
                         % ("%.4g N" % push.PushForce if push.PushForce >= 0 else "no force does it",
                            "%.4g N at %s" % (push.LeastForce, wf._fmt_point(push.LeastForceAt))
                            if push.LeastForce >= 0 else "none"))
            else:
                _say(push.Label)


class GravityDialCommand(_Command):
    NAME = "Wrench_GravityDial"
    ICON = "WrenchGravityDial"
    MENU = "Gravity dial"
    TIP = ("The tilts of the fixture under which gravity alone seats the part and holds it "
           "(set both), as arcs of a dial around the centre of mass: a direction on the dial is "
           "the way gravity pulls")

    def Activated(self):
        doc = FreeCAD.ActiveDocument
        fixture = _fixture_in_selection(doc)
        if fixture is None:
            return
        dial = _run(doc, "Wrench gravity dial", lambda: wf.make_gravity_dial(fixture, "both"))
        if dial is not None and _recompute(doc, [dial]):
            _say("%s: %s. A direction on the dial, from the centre of mass, is the way gravity "
                 "pulls in the outline's plane" % (dial.Label, dial.Meaning))


class DesignCommand(_Command):
    NAME = "Wrench_Design"
    ICON = "WrenchDesign"
    MENU = "Design"
    TIP = ("fixture.design: every choice of DesignFixels candidate sites DesignSpacing apart "
           "along the outline, ranked by DesignObjective (the margin of the best push in both, "
           "the both region's length, the gravity arc, the least push force under Gravity and "
           "Loads, or the worst locating error); the best design's fixels are placed")

    def Activated(self):
        doc = FreeCAD.ActiveDocument
        fixture = _fixture_in_selection(doc)
        if fixture is None:
            return
        doc.openTransaction("Wrench design")
        try:
            _views(fixture)
            wf.design(fixture, progress=True)
        except (wf.WrenchError, wf.OutlineError) as error:
            doc.abortTransaction()
            _fail(str(error))
            return
        except Exception as error:          # the user stopped the progress indicator
            doc.abortTransaction()
            _fail("design stopped: %s" % error)
            return
        doc.commitTransaction()


def _feature_points():
    """Points picked on the part, for locating features and rest buttons: a
    selected vertex, the centre of a selected circular edge (a hole), or the
    point picked on another edge or on a face."""
    out = []
    for s in FreeCADGui.Selection.getSelectionEx():
        if wf._proxy_name(s.Object).startswith("Wrench"):
            continue
        picked = list(s.PickedPoints)
        for k, (name, sub) in enumerate(zip(s.SubElementNames, s.SubObjects)):
            if name.startswith("Vertex"):
                out.append(sub.Point)
            elif name.startswith("Edge") and isinstance(getattr(sub, "Curve", None), Part.Circle):
                out.append(sub.Curve.Center)
            elif k < len(picked):
                out.append(picked[k])
    return out


class LocateCommand(_Command):
    NAME = "Wrench_Locate"
    ICON = "Wrench"
    MENU = "Locating accuracy"
    TIP = ("fixture.locating: with each locator off by up to Tolerance along its normal, where "
           "the selected features (vertices, holes' edges, picked points) end up: their 99.73 % "
           "error ellipses drawn magnified, the worst errors listed in the report view")

    def Activated(self):
        doc = FreeCAD.ActiveDocument
        fixture = _fixture_in_selection(doc)
        if fixture is None:
            return
        points = _feature_points()
        obj = _run(doc, "Wrench locating", lambda: wf.make_locating(fixture, 0.02, points))
        if obj is not None and _recompute(doc, [obj]):
            _say("%s: change its Tolerance, Features and SigmaRatio in the property view"
                 % obj.Label)


class LeastForceCommand(_Command):
    NAME = "Wrench_LeastForce"
    ICON = "WrenchRegions"
    MENU = "Least force"
    TIP = ("How hard to push: the least force of a push along the outline that seats the part "
           "and holds it under every load case (the fixture's Gravity and Loads), coloured from "
           "blue (least) to red, and where the smallest push suffices")

    def Activated(self):
        doc = FreeCAD.ActiveDocument
        fixture = _fixture_in_selection(doc)
        if fixture is None:
            return
        plate = bool(list(fixture.SupportPoints))
        if not plate and not fixture.Gravity and not list(fixture.Loads):
            _fail("%s has no Gravity, no Loads and no rest buttons: set them (its Loads group, "
                  "Rest buttons) first" % fixture.Label)
            return
        made = _dependents(fixture, "WrenchLeastForce")
        obj = made[0] if made else _run(doc, "Wrench least force",
                                        lambda: wf.make_least_force(fixture))
        if obj is None or not _recompute(doc, [fixture, obj]):
            return
        wf.colour_least_force(obj)
        if obj.Least >= 0 and plate:
            _say("least push on the rest buttons %.4g N at %s along %s: it seats the part "
                 "against their friction%s; the same part floating: %s" % (
                     obj.Least, wf._fmt_point(obj.LeastAt), wf._fmt_point(obj.LeastDirection),
                     " under every load case" if fixture.Gravity or list(fixture.Loads) else "",
                     "%.4g N at %s" % (obj.FloatingLeast, wf._fmt_point(obj.FloatingLeastAt))
                     if obj.FloatingLeast >= 0 else "no push seats it"))
        elif obj.Least >= 0:
            _say("least push %.4g N at %s along %s: it seats the part and holds it under every "
                 "load case" % (obj.Least, wf._fmt_point(obj.LeastAt),
                                wf._fmt_point(obj.LeastDirection)))
        else:
            _say(obj.Label)


class RestButtonsCommand(_Command):
    NAME = "Wrench_RestButtons"
    ICON = "WrenchFixels"
    MENU = "Rest buttons"
    TIP = ("Select vertices, holes' circular edges (their centre) or points on the part: rest "
           "buttons under it there, taken into the face's plane; their normal loads are shown "
           "(friction mu_B, gravity into the plate and down clamps in the fixture's Rest "
           "buttons group)")
    DOWN = None       # a down clamp's force: picks are down clamps, not buttons

    def Activated(self):
        doc = FreeCAD.ActiveDocument
        fixture = _fixture_in_selection(doc)
        if fixture is None:
            return
        points = _feature_points()
        if not points:
            _fail("%s: select vertices, circular edges or points on the part" % self.MENU)
            return

        def add():
            if not wf.supports_of(fixture):
                wf.make_supports(fixture)
            return wf.add_supports(fixture, points, down=self.DOWN)
        if _run(doc, "Wrench %s" % self.MENU.lower(), add) is None:
            return
        if _recompute(doc, [fixture] + wf.supports_of(fixture)):
            for line in fixture.SupportsReport:
                _say(line)


class DownClampsCommand(RestButtonsCommand):
    NAME = "Wrench_DownClamps"
    MENU = "Down clamps"
    TIP = ("Select vertices, circular edges (their centre) or points on the part: down clamps "
           "pressing it onto its rest buttons there, %s N each at first (the fixture's "
           "DownForces)" % wf._fmt(wf.DOWN_FORCE))
    DOWN = wf.DOWN_FORCE


class ClearRestButtonsCommand(_ClearCommand):
    NAME = "Wrench_ClearRestButtons"
    MENU = "Clear rest buttons"
    TIP = "Remove the fixture's rest buttons and down clamps: the part floats in its plane"
    CLEARS = ("SupportPoints", "DownPoints", "DownForces")
    UNDO = "Wrench rest buttons cleared"


COMMANDS = [FixtureCommand, AddFixelsCommand, ClearFixelsCommand, RegionsCommand,
            GravityDialCommand, DesignCommand, LeastForceCommand, LocateCommand,
            RestButtonsCommand, DownClampsCommand, ClearRestButtonsCommand]
for _command in COMMANDS:
    FreeCADGui.addCommand(_command.NAME, _command())

TOOLBAR = [c.NAME for c in COMMANDS]
MENU = TOOLBAR
