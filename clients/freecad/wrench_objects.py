"""wrench_objects -- the document objects of the Wrench workbench, and how
they ask wrenchd (wrench_freecad.py is the workbench's one import; the
geometry is wrench_outline.py's, the view wrench_view.py's).  FreeCAD and
Part only at module level, so that freecadcmd runs all of it.

The document objects
--------------------

    fixture = make_fixture(doc, (part, "Face6"), fixels=[...], friction=0.3)
    regions = make_regions(fixture, "both")
    doc.recompute()

A WrenchFixture links a face (or a sketch, or a shape of one planar face),
holds the fixels, the friction, the mass, the rest buttons under the part
(wrench_supports.py) and the daemon's socket, and puts the fixture in
wrenchd; WrenchRegions (one per set: goal, strong, both),
WrenchFixels, WrenchBestPush and WrenchGravityDial show what wrenchd answers
for it, and recompute when the part, the fixels or the friction change.
Each region of a WrenchRegions is a WrenchRegion object of its own, with its
Shape (the line or arc) and its numbers.  A WrenchRegions' PushOn is the
push_on it asks with (push_on_of: empty, the clients' default); PushOnLoops
and the report view say which loops that took.

What each set promises: a push in `goal` reaches every fixel from any
contact state, but the part may then slide along its fixels; one in
`strong` holds the seated part still but may not seat it.  What to push with
and let go is `both`.

    show_regions(doc, face, fixels, friction, set, client)   -> [WrenchRegion objects]
    design(fixture, client=None, progress=True)              -> wrenchd.DesignResult

Errors: OutlineError (a ValueError) for a face that has no outline (not
planar, an open wire); WrenchError for what wrenchd refuses or cannot be
asked, its message naming the fixel, the loop (and the FreeCAD edges) or
the property at fault; a busy daemon (no answer in time, too many
clients) is said to be busy, and for an unreachable one how to start one.
"""

import errno
import json
import math
import os
import re

import FreeCAD
import Part
from FreeCAD import Vector

# wrench_outline first: it puts wrenchd.py on the path.
from wrench_outline import (ON_OUTLINE, Outline, OutlineError, _angle, _fmt, _fmt_point,
                            _norm, _sub, outline)
from wrench_view import _attach_view, colour_least_force

import wrenchd  # noqa: E402  (its directory is on the path now)

SETS = ("goal", "strong", "both")

# The unit of every length the workbench reports: FreeCAD's own, whatever
# unit schema its preferences show; the fixtures it puts name it (with
# forces in N, and so the Mass in kg).
UNIT = "mm"
UNITS = {"length": UNIT, "force": "N"}

# What a push in each set promises, in the words of docs/PROTOCOL.md.
MEANING = {
    "goal": "goal: a push here reaches every fixel from any contact state, but the part "
            "may then slide along its fixels; to push and let go, use both",
    "strong": "strong: a push here holds the seated part still, but may not seat it; "
              "to push and let go, use both",
    "both": "both: a push here seats the part from any contact state and then holds it "
            "still: push here and let go",
}
# The same for gravity alone, pulling along a direction of the dial.
GRAVITY_MEANING = {
    "goal": "goal: gravity pulling this way seats the part from any contact state, but may "
            "then let it slide along its fixels; to tilt and let go, use both",
    "strong": "strong: gravity pulling this way holds the seated part still, but may not seat "
              "it; to tilt and let go, use both",
    "both": "both: gravity pulling this way seats the part from any contact state and then "
            "holds it still",
}
SHORT_MEANING = {
    "goal": "seats, may then slide: use both",
    "strong": "holds once seated: use both",
    "both": "push here and let go",
}


class WrenchError(RuntimeError):
    """wrenchd refused a request, or could not be reached; the message names
    what is wrong in FreeCAD's terms.  `field` and `reason` are wrenchd's
    (empty when it was not reached)."""

    def __init__(self, message, field="", reason=""):
        super().__init__(message)
        self.field = field
        self.reason = reason


# ---- talking to wrenchd ------------------------------------------------------------

_CLIENTS = {}


def socket_path(socket=""):
    """The socket a fixture uses: its own, else $WRENCHD_SOCKET, else
    ./run/wrenchd.sock (as an absolute path)."""
    return os.path.abspath(socket or wrenchd.default_socket_path())


def client_for(socket="", timeout=60.0):
    """One wrenchd.Client per socket path, shared by the objects using it."""
    path = socket_path(socket)
    client = _CLIENTS.get(path)
    if client is None:
        client = _CLIENTS[path] = wrenchd.Client(path, timeout=timeout)
    client.timeout = timeout
    return client


def _use_client(client):
    """Make `client` the one its socket path's objects use."""
    _CLIENTS[os.path.abspath(client.socket_path)] = client


def how_to_start(path):
    return ("Start one: `wrenchd --socket %s` (in a wrenchd checkout, `make run` serves "
            "./run/wrenchd.sock), or set the fixture's Socket property, or $WRENCHD_SOCKET "
            "before starting FreeCAD, to the socket of a running wrenchd." % path)


def _unreachable(error, path):
    return WrenchError("wrenchd is not reachable at %s (%s). %s" % (path, error, how_to_start(path)))


def _busy(error, path):
    """A daemon that is running but cannot take this request now: its
    workers on other work (no answer in time), too many clients, or its
    queue of connections full.  Starting another would not help."""
    return WrenchError("wrenchd at %s is busy (%s): it is running, but cannot answer now. Ask "
                       "again when its other work is done (a design or a sweep may take "
                       "minutes), or give the fixture's Socket property another daemon's "
                       "socket." % (path, str(error).replace("wrenchd at %s: " % path, "")))


def _is_busy(error):
    """Whether wrenchd's error says it is busy rather than gone: no answer in
    time (WrenchdTimeout), too many clients (LIMIT_EXCEEDED on the
    connection as a whole, no field), a full queue of connections
    (EAGAIN when connecting)."""
    if isinstance(error, wrenchd.WrenchdTimeout):
        return True
    if isinstance(error, wrenchd.WrenchdError):
        return error.code == wrenchd.LIMIT_EXCEEDED and not error.field and "clients" in error.reason
    return isinstance(error, wrenchd.WrenchdUnavailable) and os.strerror(errno.EAGAIN) in str(error)


_FIELD = re.compile(r"^params\.(?:fixture\.)?(.*)$")
_INDEXED = re.compile(r"^(fixels|sites)\[(\d+)\](.*)$")
_LOOP = re.compile(r"^body\.shape\.loops\[(\d+)\](?:\[(\d+)\])?(.*)$")


def _supports():
    """wrench_supports, which imports this module: asked for inside the
    fixture's functions, long after both are loaded."""
    import wrench_supports
    return wrench_supports


def _refusal(error, what, outline=None, fixels3d=(), properties=None, fixture_obj=None):
    """A WrenchError naming, in FreeCAD's terms, the field wrenchd refused;
    `properties` names the object's properties some fields come from
    ({"spacing": "DesignSpacing", ...}); `fixture_obj` the WrenchFixture
    whose rest buttons a field under supports names."""
    field = error.field or ""
    reason = error.reason or error.message
    rest = _FIELD.match(field)
    rest = rest.group(1) if rest else field
    subject = field or "the request"
    m = _INDEXED.match(rest)
    buttons = _supports().refusal_subject(fixture_obj, rest)
    if buttons is not None:
        subject = buttons
    elif properties and rest.split("[")[0].split(".")[0] in properties:
        subject = properties[rest.split("[")[0].split(".")[0]]
    elif m:
        i = int(m.group(2))
        if m.group(1) == "fixels":
            subject = "fixel %d" % (i + 1)
            if i < len(fixels3d):
                subject += " (FixelPoints[%d] = %s)" % (i, _fmt_point(fixels3d[i]))
        else:
            subject = "candidate site %d" % (i + 1)
        if m.group(3).startswith(".normal"):
            subject += "'s normal (FixelNormals[%d])" % i
        elif m.group(3).startswith(".friction"):
            subject += "'s friction"
    else:
        m = _LOOP.match(rest)
        if m and outline is not None and int(m.group(1)) < len(outline.segments):
            i = int(m.group(1))
            subject = "loop %d of the outline, %s" % (i, outline.loop_words(i))
            if m.group(2) is not None and int(m.group(2)) < len(outline.segments[i]):
                subject = "the start of %s" % outline.segment_words(i, int(m.group(2)))
            others = [int(k) for k in re.findall(r"loops\[(\d+)\]", reason)]
            for k in others:
                if k != i and k < len(outline.segments):
                    reason += "; loop %d is %s" % (k, outline.loop_words(k))
        elif rest.startswith("friction"):
            subject = "the friction (StaticFriction, KineticFriction)"
        elif rest.startswith("body.mass"):
            subject = "the Mass"
    return WrenchError("%s: wrenchd refused %s: %s [%s]" % (what, subject, reason, field),
                       field, reason)


def _ask(what, path, call, outline=None, fixels3d=(), properties=None, fixture_obj=None):
    """call(), with wrenchd's errors made WrenchErrors in FreeCAD's terms."""
    try:
        return call()
    except (wrenchd.WrenchdUnavailable, wrenchd.WrenchdError) as error:
        if _is_busy(error):
            raise _busy(error, path) from None
        if isinstance(error, wrenchd.WrenchdUnavailable):
            raise _unreachable(error, path) from None
        raise _refusal(error, what, outline, fixels3d, properties, fixture_obj) from None


def _report_error(obj, error):
    FreeCAD.Console.PrintError("Wrench: %s\n" % error)
    raise error


# ---- the objects ------------------------------------------------------------------

def _add(obj, kind, name, group, doc, value=None, mode=0):
    """Add a property unless the object has it (0 editable, 1 read-only,
    2 hidden)."""
    if name not in obj.PropertiesList:
        obj.addProperty(kind, name, group, doc)
        if value is not None:
            setattr(obj, name, value)
    obj.setEditorMode(name, mode)


def _proxy_name(obj):
    proxy = getattr(obj, "Proxy", None)
    return type(proxy).__name__ if proxy is not None else ""


def _is(obj, kind):
    return obj is not None and _proxy_name(obj) == kind


def _document_source(source):
    """(object, subelement or "") of a link value or an (object, name) pair."""
    if isinstance(source, (tuple, list)):
        obj = source[0]
        sub = source[1] if len(source) > 1 else ""
        if isinstance(sub, (list, tuple)):
            sub = sub[0] if sub else ""
        return obj, sub or ""
    return source, ""


def _face_of_source(obj, sub):
    """(shape to outline, frame or None, shape naming the edges, owner
    label) of a linked object and subelement."""
    if obj is None:
        raise OutlineError("the fixture links no part: set its Source to a face (object, FaceN) "
                           "or a sketch")
    shape = obj.Shape
    if sub:
        if not sub.startswith("Face"):
            raise OutlineError("%s of %s is not a face: link a face (FaceN) or a sketch"
                               % (sub, obj.Label))
        try:
            face = shape.getElement(sub)
        except Exception:
            raise OutlineError("%s has no %s (it has %d faces): the part changed; link a face "
                               "again" % (obj.Label, sub, len(shape.Faces))) from None
        return face, None, shape, obj.Label
    if obj.TypeId.startswith("Sketcher::"):
        placement = obj.getGlobalPlacement()
        z = placement.Rotation.multVec(Vector(0, 0, 1))
        frame = None if abs(z.x) <= 1e-12 and abs(z.y) <= 1e-12 else placement
        return shape, frame, shape, obj.Label
    if len(shape.Faces) == 1:
        return shape.Faces[0], None, shape, obj.Label
    if not shape.Faces and shape.Wires:
        return shape, None, shape, obj.Label
    raise OutlineError("%s has %d faces: link one of them (object, FaceN)"
                       % (obj.Label, len(shape.Faces)))


def _friction_values(friction):
    """(static, kinetic) of a number, a (static, kinetic) pair or a dict
    {"static", "kinetic"?}."""
    try:
        if isinstance(friction, dict):
            static = float(friction["static"])
            return static, float(friction.get("kinetic", static))
        if isinstance(friction, (tuple, list)):
            static, kinetic = friction
            return float(static), float(kinetic)
        return float(friction), float(friction)
    except (KeyError, TypeError, ValueError):
        raise ValueError("friction: a number, a (static, kinetic) pair or {\"static\", "
                         "\"kinetic\"} of numbers, not %r" % (friction,)) from None


class _Proxy:
    """A document object's proxy: it sets up its properties when made and
    when its document is read again (setup adds only what is missing), and
    keeps no state of its own in the file (the properties are the state)."""

    def __init__(self, obj):
        obj.Proxy = self
        self.setup(obj)

    def onDocumentRestored(self, obj):
        self.setup(obj)
        _attach_view(obj)

    def __getstate__(self):
        return None

    def __setstate__(self, state):
        return None


class WrenchFixture(_Proxy):
    """The fixture: a part's face (or a sketch), the fixels, the friction and
    the mass; its Shape is the outline as wrenchd sees it (the curves
    approximated by arcs).  Its execute puts the fixture in wrenchd."""

    def setup(self, obj):
        _add(obj, "App::PropertyLinkSub", "Source", "Part",
             "The planar face (object, FaceN) or the closed sketch the fixture holds")
        _add(obj, "App::PropertyLength", "Tolerance", "Part",
             "How far arcs replacing a curve that is not a line or a circle may be from it "
             "(0: 1e-5 of the face's size)", 0.0)
        _add(obj, "App::PropertyVectorList", "FixelPoints", "Fixels",
             "Where the fixels touch the part, in the document's coordinates")
        _add(obj, "App::PropertyVectorList", "FixelNormals", "Fixels",
             "Each fixel's contact normal, pointing into the part; (0, 0, 0) or none: the "
             "outline's inward normal there (required at a corner)")
        _add(obj, "App::PropertyFloat", "StaticFriction", "Friction",
             "Coulomb friction between the part and every fixel, static", 0.3)
        _add(obj, "App::PropertyFloat", "KineticFriction", "Friction",
             "Kinetic friction, at most the static one", 0.3)
        _add(obj, "App::PropertyFloat", "Mass", "Friction",
             "The part's mass in kg (a uniform lamina: its centre of mass and inertia "
             "follow from the outline)", 1.0)
        _add(obj, "App::PropertyFloat", "Gravity", "Loads",
             "Gravity's acceleration in mm/s^2 (9810 on earth), pulling the part along "
             "GravityDirection; 0: none.  With Gravity or Loads the fixture is sent in mm and N, "
             "and the best push says how hard to push", 0.0)
        _add(obj, "App::PropertyFloat", "GravityDirection", "Loads",
             "Where gravity pulls, in degrees counter-clockwise from the outline's x axis "
             "(270: along -y)", 270.0)
        _add(obj, "App::PropertyStringList", "Loads", "Loads",
             "Load cases, one a line, each with gravity: NAME: FX,FY @ X,Y,Z -- a force in N along "
             "the document's X and Y at a point of the part (document mm); several forces of one "
             "case separated by ';'")
        _add(obj, "App::PropertyString", "Socket", "wrenchd",
             "wrenchd's socket; empty: $WRENCHD_SOCKET, else ./run/wrenchd.sock")
        _add(obj, "App::PropertyFloat", "Timeout", "wrenchd",
             "Seconds to wait for wrenchd's answer", 60.0)
        _add(obj, "App::PropertyInteger", "DesignFixels", "Design",
             "Design: how many fixels to place", 3)
        _add(obj, "App::PropertyLength", "DesignSpacing", "Design",
             "Design: candidate sites this far apart along each loop's length, across the joints "
             "of faceted curves, clear of corners by half of it (0: the perimeter / 40, to two "
             "digits); pushes on the outer boundary only (a point finger)",
             0.0)
        if "DesignObjective" not in obj.PropertiesList:
            obj.addProperty("App::PropertyEnumeration", "DesignObjective", "Design",
                            "Design: rank by the margin of the best push in both (margin), the "
                            "length of the both region (region), the gravity arc (gravity), the "
                            "least push force under Gravity and Loads (force), the worst "
                            "locating error with locators off by DesignTolerance (accuracy), or "
                            "list the designs no other beats on all three of margin, accuracy "
                            "and least force (pareto)")
            obj.DesignObjective = DESIGN_OBJECTIVES
            obj.DesignObjective = "margin"
        elif list(obj.getEnumerationsOfProperty("DesignObjective")) != DESIGN_OBJECTIVES:
            chosen = obj.DesignObjective  # a document of before: its choice kept
            obj.DesignObjective = DESIGN_OBJECTIVES
            obj.DesignObjective = chosen
        _add(obj, "App::PropertyLength", "DesignTolerance", "Design",
             "Design, objectives accuracy and pareto: how far each locator may be off along "
             "its normal; "
             "the worst error is the pose's (scaled), or the farthest DesignFeatures point's",
             0.02)
        _add(obj, "App::PropertyVectorList", "DesignFeatures", "Design",
             "Design, objectives accuracy and pareto: points of the part (document) whose worst "
             "displacement ranks the designs; empty: the pose's error")
        _add(obj, "App::PropertyInteger", "DesignTop", "Design", "Design: designs to list", 5)
        _add(obj, "App::PropertyStringList", "Designs", "Design",
             "The last design's ranking, best first (its fixels were placed)", mode=1)
        for kind, name, doc in (
                ("App::PropertyString", "FixtureId", "The fixture's id in wrenchd"),
                ("App::PropertyFloat", "Area", "The outline's area, as wrenchd computes it"),
                ("App::PropertyVector", "CenterOfMass", "The centre of mass wrenchd uses"),
                ("App::PropertyFloat", "Inertia", "The moment of inertia about it wrenchd uses"),
                ("App::PropertyBool", "Pinned", "Whether the fixels pin the part"),
                ("App::PropertyInteger", "Loops", "The outline's loops (1 + holes)"),
                ("App::PropertyInteger", "Segments", "The outline's lines and arcs"),
                ("App::PropertyFloat", "ToleranceUsed", "The tolerance the curves were followed to"),
                ("App::PropertyFloat", "Deviation",
                 "The largest distance measured between a curve and its arcs (0: all exact)"),
                ("App::PropertyStringList", "Approximated", "The edges replaced by arcs"),
                ("App::PropertyStringList", "OtherParts",
                 "Other parts in the sketch, not read (the largest part is)"),
                ("App::PropertyStringList", "Ignored",
                 "Open wires and loose edges left out of the sketch's outline"),
                ("App::PropertyStringList", "FixelsMoved",
                 "Fixels moved onto the outline (they were off it by less than the tolerance)"),
                ("App::PropertyPlacement", "Frame",
                 "The outline's 2-D frame: its (x, y) is Frame applied to (x, y, 0)")):
            _add(obj, kind, name, "Outline", doc, mode=1)
        _add(obj, "App::PropertyString", "FixtureJson", "Outline",
             "The fixture as sent to wrenchd (the outline's coordinates)", mode=2)
        _add(obj, "App::PropertyString", "EdgeTable", "Outline",
             "Per loop and segment, the FreeCAD edge it comes from", mode=2)
        _supports().setup_fixture(obj)

    def outline(self, obj):
        source, sub = _document_source(obj.Source)
        shape, frame, names, owner = _face_of_source(source, sub)
        return outline(shape, float(obj.Tolerance) or None, frame, names, owner)

    def fixels(self, obj, shape):
        """wrenchd's fixels from FixelPoints and FixelNormals, each moved onto
        the outline when it is off it by less than the tolerance."""
        normals = list(obj.FixelNormals)
        fixels, moved = [], []
        near = max(shape.tolerance, ON_OUTLINE * shape.size)
        for i, p in enumerate(obj.FixelPoints):
            x, y, off = shape.to_2d(p)
            if abs(off) > near:
                raise WrenchError("%s: fixel %d (FixelPoints[%d] = %s) is %s off the face's plane"
                                  % (obj.Label, i + 1, i, _fmt_point(p), _fmt(abs(off))),
                                  "fixels[%d].at" % i, "off the plane")
            segment, t, q, d = shape.nearest((x, y))
            at = [x, y]
            if 1e-9 * shape.size < d <= near:
                at = [q[0], q[1]]
                moved.append("fixel %d moved %s onto %s" % (i + 1, _fmt(d),
                                                           shape.segment_words(segment.loop,
                                                                               segment.index)))
            fixel = {"at": at}
            if i < len(normals) and normals[i].Length > 0:
                fixel["normal"] = list(shape.direction_2d(normals[i]))
            fixels.append(fixel)
        return fixels, moved

    def execute(self, obj):
        try:
            self._execute(obj)
        except (OutlineError, WrenchError) as error:
            obj.FixtureJson = ""
            _report_error(obj, WrenchError("%s: %s" % (obj.Label, error))
                          if isinstance(error, OutlineError) else error)

    def _execute(self, obj):
        if not obj.StaticFriction >= 0:
            raise WrenchError("%s: StaticFriction %s must be at least 0"
                              % (obj.Label, _fmt(obj.StaticFriction)), "friction.static", "negative")
        if obj.KineticFriction > obj.StaticFriction or obj.KineticFriction < 0:
            raise WrenchError("%s: KineticFriction %s must lie between 0 and StaticFriction %s"
                              % (obj.Label, _fmt(obj.KineticFriction), _fmt(obj.StaticFriction)),
                              "friction.kinetic", "above static")
        shape = self.outline(obj)
        obj.Shape = shape.shape_3d()
        obj.Frame = shape.frame
        obj.Loops = len(shape.segments)
        obj.Segments = sum(len(loop) for loop in shape.segments)
        obj.ToleranceUsed = shape.tolerance
        obj.Deviation = shape.deviation
        obj.Approximated = ["%s (%s): %d arcs, %s from it at most" % (
            a["edge"] or "an edge", a["kind"], a["arcs"], _fmt(a["deviation"]))
            for a in shape.approximated]
        obj.OtherParts = shape.other_parts
        obj.Ignored = shape.ignored
        obj.EdgeTable = json.dumps(shape.edge_table())
        fixels, moved = self.fixels(obj, shape)
        obj.FixelsMoved = moved
        fixture = {"name": obj.Label, "body": {"mass": obj.Mass, "shape": shape},
                   "friction": {"static": obj.StaticFriction, "kinetic": obj.KineticFriction},
                   "fixels": fixels, "units": dict(UNITS)}
        buttons = _supports()
        buttons.clear_loads(obj)
        supports = buttons.supports_member(obj, shape)
        if supports is not None:
            fixture["supports"] = supports
        if obj.Gravity != 0 or list(obj.Loads):
            load_cases(obj, shape)  # refused here, at the property, when malformed
        if not fixels:
            obj.FixtureId = ""
            obj.Pinned = False
            obj.FixtureJson = json.dumps(fixture)
            return
        path = socket_path(obj.Socket)
        client = client_for(obj.Socket, obj.Timeout)
        sent = dict(fixture, body={"mass": obj.Mass, "shape": buttons.wire_shape(fixture, shape)})
        try:
            put = _ask(obj.Label, path, lambda: client.put_fixture(sent), shape, obj.FixelPoints,
                       fixture_obj=obj)
        except WrenchError as error:
            if error.field.startswith("params.fixture.supports") or \
                    error.field.startswith("supports"):
                buttons.clear_loads(obj, str(error))
            raise
        obj.FixtureId = put.id
        obj.Area = float(put.area)
        obj.CenterOfMass = shape.to_3d(put.com)
        obj.Inertia = float(put.inertia)
        obj.Pinned = bool(put.pinned)
        obj.FixtureJson = json.dumps(fixture)
        if supports is not None:
            buttons.record_loads(obj, shape, put.com)


def load_cases(fixture_obj, outline_shape):
    """The fixture's load cases as wrenchd takes them (docs/PROTOCOL.md,
    "Loads and cases"): each line of Loads with gravity added, or gravity
    alone; [] with neither.  Forces along the document's X and Y are turned
    into the outline's plane, points taken into its coordinates."""
    gravity = []
    if fixture_obj.Gravity:
        if fixture_obj.Gravity < 0:
            raise WrenchError("%s: Gravity %s must not be negative (GravityDirection says where it "
                              "pulls)" % (fixture_obj.Label, _fmt(fixture_obj.Gravity)),
                              "cases[0].loads[0].gravity.g", "negative")
        gravity = [{"gravity": {"g": fixture_obj.Gravity,
                                "direction_deg": fixture_obj.GravityDirection}, "name": "gravity"}]
    cases = []
    for i, line in enumerate(fixture_obj.Loads):
        name, _, text = line.rpartition(":") if ":" in line else ("", "", line)
        loads = list(gravity)
        for part in [p for p in text.split(";") if p.strip()]:
            try:
                force_text, at_text = part.split("@")
                fx, fy = [float(v) for v in force_text.split(",")]
                x, y, z = [float(v) for v in at_text.split(",")]
            except ValueError:
                raise WrenchError("%s: Loads[%d] %r: a force is FX,FY @ X,Y,Z (N, document mm)"
                                  % (fixture_obj.Label, i, line), "Loads[%d]" % i, "malformed")
            f2 = outline_shape.direction_2d(Vector(fx, fy, 0)) if (fx or fy) else (0.0, 0.0)
            scale = math.hypot(fx, fy)
            norm = math.hypot(f2[0], f2[1])
            force = [f2[0] * scale / norm, f2[1] * scale / norm] if norm else [0.0, 0.0]
            ax, ay, _ = outline_shape.to_2d(Vector(x, y, z))
            loads.append({"force": force, "at": [ax, ay]})
        if not loads:
            raise WrenchError("%s: Loads[%d] %r has no force" % (fixture_obj.Label, i, line),
                              "Loads[%d]" % i, "empty")
        case = {"loads": loads}
        if name.strip():
            case["name"] = name.strip()
        cases.append(case)
    if not cases and gravity:
        cases = [{"name": "gravity", "loads": gravity}]
    return cases


# A load case of nothing: on rest buttons how hard to push is asked without
# loads too (the buttons' friction alone resists the push).
NO_LOAD = {"name": "none", "loads": [{"wrench": [0.0, 0.0, 0.0]}]}


def force_question(fixture):
    """(cases, set) that how hard to push is asked with, for a _Fixture:
    floating, its load cases (none: nothing to ask) and both; on rest
    buttons, its load cases or NO_LOAD, and goal (wrenchd answers how hard
    a push must be to seat the part against the buttons' friction; whether
    the seated part then holds is a question of its own there)."""
    cases = load_cases(fixture.obj, fixture.outline)
    if fixture.on_supports:
        return cases or [NO_LOAD], "goal"
    return cases, "both"


class _Fixture:
    """What a fixture's dependent objects read of it: the fixture dict, its
    outline (rebuilt from the dict and the frame), the client."""

    def __init__(self, fixture_obj, what):
        if fixture_obj is None or not _is(fixture_obj, "WrenchFixture"):
            raise WrenchError("%s: link a WrenchFixture (its Fixture property)" % what)
        if not fixture_obj.FixtureJson:
            raise WrenchError("%s: %s has no outline (see its error)" % (what, fixture_obj.Label))
        self.obj = fixture_obj
        self.fixture = json.loads(fixture_obj.FixtureJson)
        edges = json.loads(fixture_obj.EdgeTable) if fixture_obj.EdgeTable else None
        self.outline = Outline.from_shape(self.fixture["body"]["shape"], fixture_obj.Frame, edges,
                                          fixture_obj.ToleranceUsed, fixture_obj.Deviation)
        self.fixture["body"]["shape"] = _supports().wire_shape(self.fixture, self.outline)
        self.path = socket_path(fixture_obj.Socket)
        self.client = client_for(fixture_obj.Socket, fixture_obj.Timeout)
        self.what = what

    @property
    def has_fixels(self):
        return bool(self.fixture["fixels"])

    def ask(self, call):
        return _ask(self.what, self.path, call, self.outline, self.obj.FixelPoints,
                    fixture_obj=self.obj)

    @property
    def on_supports(self):
        return "supports" in self.fixture

    def friction(self):
        return self.fixture["friction"]


class _Dependent(_Proxy):
    """A proxy whose object links a WrenchFixture (its Fixture property)."""

    def setup(self, obj):
        _add(obj, "App::PropertyLink", "Fixture", "Fixture", "The WrenchFixture shown")

    def execute(self, obj):
        try:
            self._execute(obj)
        except (OutlineError, WrenchError) as error:
            self.failed(obj)
            _report_error(obj, error)

    def failed(self, obj):
        obj.Shape = Part.Shape()


def _set_enumeration(obj, name, values, value):
    setattr(obj, name, list(values))
    setattr(obj, name, value)


def _loop_count(body):
    shape = body.get("shape") or {}
    return len(shape.get("loops") or []) if shape.get("type") == "outline" else 1


def push_on_of(text, body, finger_radius):
    """The push_on a WrenchRegions' PushOn property asks for: "" the
    clients' default (wrenchd.default_push_on, docs/PROTOCOL.md push_on),
    "outer", "all", or loop numbers ("0, 2"); an OutlineError naming PushOn
    for anything else, or a loop the outline does not have."""
    text = (text or "").strip()
    if not text:
        return wrenchd.default_push_on(body, finger_radius)
    if text.lower() in ("outer", "all"):
        return text.lower()
    n = _loop_count(body)
    loops = []
    for word in text.replace(",", " ").replace(";", " ").split():
        try:
            loop = int(word)
        except ValueError:
            raise OutlineError("PushOn: %r is neither outer, all nor a list of loop numbers "
                               "(0 is the outer boundary)" % text) from None
        if not 0 <= loop < n:
            raise OutlineError("PushOn: loop %d is not one of the outline's loops (0 to %d)"
                               % (loop, n - 1))
        if loop not in loops:
            loops.append(loop)
    return sorted(loops)


def pushed_loops(push_on, body):
    """The loop numbers a push_on names (None and "all": every loop)."""
    if push_on == "outer":
        return [0]
    if push_on is None or push_on == "all":
        return list(range(_loop_count(body)))
    return list(push_on)


def describe_push_on(loops, body, finger_radius, chosen):
    """The report view's line on where the regions were looked for: which
    loops, which holes were left out and why (the clients' default)."""
    n = _loop_count(body)
    left = [i for i in range(1, n) if i not in loops]
    names = ", ".join("the outer boundary" if i == 0 else "hole %d" % i for i in loops)
    text = "pushes on %s" % names
    if left:
        text += "; not on hole%s %s" % ("s" if len(left) > 1 else "",
                                         ", ".join(str(i) for i in left))
        if chosen:
            text += " (PushOn)"
        elif finger_radius > 0:
            text += " (no wider than the finger, %s across)" % _fmt(2 * finger_radius)
        else:
            text += (" (a point finger has no size to compare with a hole's: set FingerRadius, "
                     "or PushOn to all)")
    return text


class WrenchRegions:
    """The push regions of one set (goal, strong or both) on the fixture's
    outline: its Shape is every region's line or arc; each region is also a
    WrenchRegion object of its own (its children)."""

    def __init__(self, obj):
        obj.Proxy = self
        self.setup(obj)

    def setup(self, obj):
        _Dependent.setup(self, obj)
        if "Set" not in obj.PropertiesList:
            obj.addProperty("App::PropertyEnumeration", "Set", "Regions",
                            "goal: seats the part from any contact state, may then let it slide; "
                            "strong: holds it still once seated; both: seats it and then holds "
                            "it still (push here and let go)")
            _set_enumeration(obj, "Set", SETS, "both")
        _add(obj, "App::PropertyLength", "FingerRadius", "Regions",
             "The pushing finger's radius: points it cannot reach drop out (0: a point)", 0.0)
        _add(obj, "App::PropertyString", "PushOn", "Regions",
             "The loops the finger may push on: empty, the clients' default (the outer "
             "boundary and every hole wider than the finger; a point finger: the outer "
             "boundary only); outer; all; or loop numbers, 0 the outer boundary (0, 2)", "")
        _add(obj, "App::PropertyBool", "SweepFriction", "Regions",
             "Also find the critical friction above which the region is empty "
             "(friction.sweep over mu in [0, 2]: 0.01 to 0.2 s with 3 fixels, 27 s with 8; "
             "not on rest buttons)",
             True)
        _add(obj, "App::PropertyFloat", "PushForce", "Regions",
             "On rest buttons (set goal): the push's magnitude in N, the regions where a push "
             "that hard seats the part against their friction (Least force gives the least); "
             "0: none asked.  Not used when the part floats", 0.0)
        for kind, name, doc in (
                ("App::PropertyString", "Meaning", "What a push in this set promises"),
                ("App::PropertyInteger", "Count", "How many regions"),
                ("App::PropertyFloat", "TotalLength", "The regions' total length (push.regions)"),
                ("App::PropertyFloat", "Fraction", "Of the outline's perimeter"),
                ("App::PropertyFloat", "CriticalMu",
                 "The friction above which the region is empty, on every loop whatever "
                 "PushOn says: friction.sweep has no push_on (-1: not empty at 2; "
                 "-2: not computed)"),
                ("App::PropertyIntegerList", "PushOnLoops",
                 "The loops the regions were looked for on (PushOn resolved)"),
                ("App::PropertyIntegerList", "RegionLoops", "Each region's loop"),
                ("App::PropertyIntegerList", "RegionSegments", "Each region's segment"),
                ("App::PropertyStringList", "RegionEdges", "Each region's FreeCAD edge"),
                ("App::PropertyFloatList", "RegionT0", "Each region's start t on its segment"),
                ("App::PropertyFloatList", "RegionT1", "Each region's end t on its segment"),
                ("App::PropertyFloatList", "RegionLengths", "Each region's length"),
                ("App::PropertyVectorList", "RegionFrom", "Each region's start (document)"),
                ("App::PropertyVectorList", "RegionTo", "Each region's end (document)")):
            _add(obj, kind, name, "Answer", doc, mode=1)
        # How many WrenchRegion objects it has: set when they are made or
        # removed, after a recompute, so that the tree claims them again;
        # an output, so setting it does not touch the object.
        _add(obj, "App::PropertyInteger", "RegionObjects", "Answer",
             "How many WrenchRegion objects show the regions", mode=2)
        obj.setPropertyStatus("RegionObjects", "Output")

    onDocumentRestored = _Dependent.onDocumentRestored
    __getstate__ = _Dependent.__getstate__
    __setstate__ = _Dependent.__setstate__

    def execute(self, obj):
        try:
            self._execute(obj)
        except (OutlineError, WrenchError) as error:
            self.failed(obj)
            _report_error(obj, error)
        finally:
            _schedule_sync(obj)

    def failed(self, obj):
        obj.Shape = Part.Shape()
        for name in ("RegionLoops", "RegionSegments", "RegionEdges", "RegionT0", "RegionT1",
                     "RegionLengths", "RegionFrom", "RegionTo"):
            setattr(obj, name, [])
        obj.Count = 0
        obj.TotalLength = 0.0

    def _execute(self, obj):
        which = obj.Set
        obj.Meaning = MEANING[which]
        fixture = _Fixture(obj.Fixture, obj.Label)
        if not fixture.has_fixels:
            self.failed(obj)
            obj.Label = "Regions %s (no fixels yet)" % which
            return
        radius = float(obj.FingerRadius)
        push_on = push_on_of(obj.PushOn, fixture.fixture["body"], radius)
        force = {}
        if fixture.on_supports:
            if obj.PushForce <= 0:
                self.failed(obj)
                obj.Label = "Regions %s (on rest buttons: set PushForce, N)" % which
                return
            # how hard matters there: wrenchd answers goal only, and says so
            cases, _ = force_question(fixture)
            force = {"force": float(obj.PushForce), "cases": cases}
        answer = fixture.ask(lambda: fixture.client.push_regions(
            fixture.fixture, which, finger_radius=radius, push_on=push_on, **force))
        obj.PushOnLoops = pushed_loops(push_on, fixture.fixture["body"])
        FreeCAD.Console.PrintMessage("Wrench: regions %s %s\n" % (
            which, describe_push_on(obj.PushOnLoops, fixture.fixture["body"], radius,
                                    bool(obj.PushOn.strip()))))
        outline = fixture.outline
        edges, loops, segs, names, t0, t1, lengths, starts, ends = [], [], [], [], [], [], [], [], []
        for r in answer.regions:
            loop = r.loop if r.loop is not None else 0          # a polygon's edge: loop 0's
            index = r.segment if r.segment is not None else r.edge
            segment = outline.segments[loop][index]
            edges.append(outline.edge_3d(segment, r.t0, r.t1))
            loops.append(loop)
            segs.append(index)
            names.append(segment.edge)
            t0.append(r.t0)
            t1.append(r.t1)
            lengths.append(r.length)
            starts.append(outline.to_3d(r.from_point))
            ends.append(outline.to_3d(r.to_point))
        obj.Shape = Part.Compound(edges) if edges else Part.Shape()
        obj.RegionLoops, obj.RegionSegments, obj.RegionEdges = loops, segs, names
        obj.RegionT0, obj.RegionT1, obj.RegionLengths = t0, t1, lengths
        obj.RegionFrom, obj.RegionTo = starts, ends
        obj.Count = len(edges)
        obj.TotalLength = answer.total_length
        obj.Fraction = answer.fraction
        obj.CriticalMu = -2.0
        if obj.SweepFriction and not fixture.on_supports:
            friction = fixture.friction()
            ratio = friction["kinetic"] / friction["static"] if friction["static"] > 0 else 1.0
            push = {"set": which}
            if float(obj.FingerRadius) > 0:
                push["finger_radius"] = float(obj.FingerRadius)
            sweep = fixture.ask(lambda: fixture.client.friction_sweep(
                fixture.fixture, push=push, kinetic_ratio=min(1.0, max(ratio, 1e-9))))
            obj.CriticalMu = -1.0 if sweep.critical is None else float(sweep.critical)
        obj.Label = "Regions %s: %d, %s long (%s)" % (which, obj.Count, _fmt(obj.TotalLength),
                                                       SHORT_MEANING[which])
        if force:
            obj.Label = "Regions %s at %s N on the rest buttons: %d, %s long" % (
                which, _fmt(obj.PushForce), obj.Count, _fmt(obj.TotalLength))


class WrenchRegion:
    """One push region: its Shape is the line or arc, its properties the
    region's numbers (push.regions'), read from its WrenchRegions."""

    def __init__(self, obj):
        obj.Proxy = self
        self.setup(obj)

    def setup(self, obj):
        _add(obj, "App::PropertyLink", "Regions", "Region", "The WrenchRegions this is one of",
             mode=1)
        _add(obj, "App::PropertyInteger", "Index", "Region", "Which of its regions", mode=1)
        for kind, name, doc in (
                ("App::PropertyString", "Set", "goal, strong or both"),
                ("App::PropertyString", "Meaning", "What a push in this set promises"),
                ("App::PropertyInteger", "Loop", "The outline's loop (0: the outer boundary)"),
                ("App::PropertyInteger", "Segment", "The loop's segment"),
                ("App::PropertyString", "Edge", "The FreeCAD edge the segment lies on or follows"),
                ("App::PropertyFloat", "T0", "Where the region starts on the segment (fraction "
                                             "of its length, of an arc's angle)"),
                ("App::PropertyFloat", "T1", "Where it ends"),
                ("App::PropertyFloat", "Length", "Its length (push.regions)"),
                ("App::PropertyVector", "From", "Its start (document)"),
                ("App::PropertyVector", "To", "Its end (document)")):
            _add(obj, kind, name, "Region", doc, mode=1)

    onDocumentRestored = _Dependent.onDocumentRestored
    __getstate__ = _Dependent.__getstate__
    __setstate__ = _Dependent.__setstate__

    def execute(self, obj):
        parent = obj.Regions
        i = obj.Index
        if parent is None or i >= len(parent.RegionLengths):
            obj.Shape = Part.Shape()
            obj.Length = 0.0
            obj.Label = "%s region %d (gone)" % (parent.Set if parent else "", i + 1)
            return
        data = _Fixture(parent.Fixture, parent.Label)
        segment = data.outline.segments[parent.RegionLoops[i]][parent.RegionSegments[i]]
        obj.Shape = data.outline.edge_3d(segment, parent.RegionT0[i], parent.RegionT1[i])
        obj.Set = parent.Set
        obj.Meaning = MEANING[parent.Set]
        obj.Loop, obj.Segment = parent.RegionLoops[i], parent.RegionSegments[i]
        obj.Edge = parent.RegionEdges[i]
        obj.T0, obj.T1 = parent.RegionT0[i], parent.RegionT1[i]
        obj.Length = parent.RegionLengths[i]
        obj.From, obj.To = parent.RegionFrom[i], parent.RegionTo[i]
        obj.Label = "%s region %d: loop %d segment %d%s, %s long" % (
            obj.Set, i + 1, obj.Loop, obj.Segment, " (%s)" % obj.Edge if obj.Edge else "",
            _fmt(obj.Length))


def region_objects(regions):
    """The WrenchRegion objects of a WrenchRegions, in order."""
    children = [o for o in regions.InList if _is(o, "WrenchRegion") and o.Regions == regions]
    return sorted(children, key=lambda o: o.Index)


_PENDING = set()


def _schedule_sync(regions):
    if len(region_objects(regions)) != len(regions.RegionLengths) or \
            any(o.Index >= len(regions.RegionLengths) for o in region_objects(regions)):
        _PENDING.add((regions.Document.Name, regions.Name))


def sync_regions(regions):
    """Give a WrenchRegions one WrenchRegion per region (run after a
    recompute: objects are not added or removed during one)."""
    doc = regions.Document
    count = len(regions.RegionLengths)
    children = region_objects(regions)
    for child in children[count:]:
        doc.removeObject(child.Name)
    children = children[:count]
    for i in range(len(children), count):
        child = doc.addObject("Part::FeaturePython", "WrenchRegion")
        WrenchRegion(child)
        child.Regions = regions
        child.Index = i
        _attach_view(child)
        children.append(child)
    for child in children:
        if "Touched" in child.State or child.Shape.isNull():
            child.Proxy.execute(child)
            child.purgeTouched()
    if regions.RegionObjects != count:
        regions.RegionObjects = count
    return children


class _Observer:
    """After a document's recompute, the WrenchRegions whose number of
    regions changed get their WrenchRegion objects."""

    def slotRecomputedDocument(self, doc):
        for key in sorted(k for k in _PENDING if k[0] == doc.Name):
            _PENDING.discard(key)
            regions = doc.getObject(key[1])
            if regions is not None and _is(regions, "WrenchRegions"):
                sync_regions(regions)


if not getattr(FreeCAD, "_wrench_observer", None):
    FreeCAD._wrench_observer = _Observer()
    FreeCAD.addDocumentObserver(FreeCAD._wrench_observer)


class WrenchFixels(_Dependent):
    """The fixels as small locator pins, each touching the part from outside
    at its point, with its friction cone (two lines at atan(mu_s) from the
    normal, closed by an arc)."""

    def setup(self, obj):
        _Dependent.setup(self, obj)
        _add(obj, "App::PropertyLength", "PinRadius", "Fixels",
             "The locator pins' radius (0: 1.5 % of the part's size)", 0.0)
        _add(obj, "App::PropertyVectorList", "Normals", "Fixels",
             "Each fixel's contact normal as wrenchd uses it (document)", mode=1)

    def _execute(self, obj):
        fixture = _Fixture(obj.Fixture, obj.Label)
        outline = fixture.outline
        if not fixture.has_fixels:
            obj.Shape = Part.Shape()
            obj.Normals = []
            obj.Label = "Fixels (none yet)"
            return
        # The normals as wrenchd uses them: its explicit form of the fixture
        # (put again first: a daemon restarted without a state directory
        # has forgotten it; putting is idempotent).
        put = fixture.ask(lambda: fixture.client.put_fixture(fixture.fixture))
        explicit = fixture.ask(lambda: fixture.client.get_fixture(put.id))
        r = float(obj.PinRadius) or 0.015 * outline.size
        plane_normal = outline.normal
        parts, normals = [], []
        for fixel in explicit["fixels"]:
            p, n = fixel["at"], fixel["normal"]
            mu = fixel["friction"]["static"]
            mu = mu[1] if isinstance(mu, list) else mu
            centre = outline.to_3d((p[0] - r * n[0], p[1] - r * n[1]))
            pin = Part.makeCylinder(r, 2 * r, centre - plane_normal * r, plane_normal)
            parts.append(pin)
            half = math.atan(mu)
            apex = outline.to_3d(p)
            reach = 4 * r
            sides = []
            for s in (-1.0, 1.0):
                a = math.atan2(n[1], n[0]) + s * half
                sides.append(outline.to_3d((p[0] + reach * math.cos(a), p[1] + reach * math.sin(a))))
            mid = outline.to_3d((p[0] + reach * n[0], p[1] + reach * n[1]))
            parts.append(Part.LineSegment(apex, sides[0]).toShape())
            parts.append(Part.LineSegment(apex, sides[1]).toShape())
            parts.append(Part.Arc(sides[0], mid, sides[1]).toShape())
            normals.append(outline.direction_3d(n))
        obj.Shape = Part.Compound(parts)
        obj.Normals = normals
        obj.Label = "Fixels: %d, friction cones at mu %s" % (len(normals),
                                                            _fmt(fixture.friction()["static"]))


class WrenchLocating(_Dependent):
    """Locating accuracy (fixture.locating): with each locator off by up to
    Tolerance along its normal, each picked feature's 99.73 % error ellipse
    and its worst displacement, drawn on the part magnified, and the table
    in Report (and the report view)."""

    def setup(self, obj):
        _Dependent.setup(self, obj)
        _add(obj, "App::PropertyLength", "Tolerance", "Locating",
             "How far each locator may be off along its normal, +-", 0.02)
        _add(obj, "App::PropertyVectorList", "Features", "Locating",
             "Points of the part whose error is wanted (a hole to drill), in the document's "
             "coordinates")
        _add(obj, "App::PropertyStringList", "FeatureNames", "Locating",
             "The features' names, in order (missing: their numbers)")
        _add(obj, "App::PropertyFloat", "SigmaRatio", "Locating",
             "sigma = Tolerance / SigmaRatio for the ellipses (3: the tolerance is 3 sigma)", 3.0)
        _add(obj, "App::PropertyFloat", "Magnification", "Locating",
             "How many times the errors are drawn larger (0: an eighth of the part's size)", 0.0)
        _add(obj, "App::PropertyBool", "Deterministic", "Locating",
             "Whether the fixels determine the part's pose", mode=1)
        _add(obj, "App::PropertyStringList", "Report", "Locating",
             "The answer, as listed in the report view", mode=1)

    def _execute(self, obj):
        fixture = _Fixture(obj.Fixture, obj.Label)
        outline = fixture.outline
        unit = UNIT
        features = []
        names = list(obj.FeatureNames)
        for i, p in enumerate(obj.Features):
            x, y, off = outline.to_2d(p)
            if abs(off) > max(outline.tolerance, ON_OUTLINE * outline.size):
                raise WrenchError("%s: feature %d (Features[%d] = %s) is %s off the face's plane"
                                  % (obj.Label, i + 1, i, _fmt_point(p), _fmt(abs(off))),
                                  "features[%d].at" % i, "off the plane")
            feature = {"at": [x, y]}
            feature["name"] = names[i] if i < len(names) and names[i] else "feature %d" % (i + 1)
            features.append(feature)
        tolerance = float(obj.Tolerance)
        answer = fixture.ask(lambda: fixture.client.locating(
            fixture.fixture, tolerance, features, sigma_ratio=obj.SigmaRatio))
        lines = locating_lines(answer, tolerance, obj.SigmaRatio, unit)
        obj.Deterministic = bool(answer.deterministic)
        obj.Report = lines
        for line in lines:
            FreeCAD.Console.PrintMessage("Wrench: %s\n" % line)
        if not answer.deterministic:
            obj.Shape = Part.Shape()
            obj.Label = "Locating: not deterministic"
            return
        largest = max([f["exact"]["length"] for f in answer.features] +
                      [f["ellipse"]["axes"][0] for f in answer.features] + [0.0])
        scale = float(obj.Magnification) or (
            _nice_below(outline.size / 8 / largest) if largest > 0 else 1.0)
        parts = []
        for f in answer.features:
            parts.extend(_error_marks(outline, f, scale))
        obj.Shape = Part.Compound(parts) if parts else Part.Shape()
        obj.Label = "Locating +-%s %s: errors x%s" % (_fmt(tolerance), unit, _fmt(scale))


def _nice_below(x):
    """1, 2 or 5 times a power of ten, at most x > 0."""
    p = 10 ** math.floor(math.log10(x))
    return 5 * p if x >= 5 * p else 2 * p if x >= 2 * p else p


def _error_marks(outline, feature, scale):
    """A feature's 99.73 % ellipse and worst (exact) displacement, magnified
    `scale` times, in the outline's plane."""
    x, y = feature["at"]
    a, b = [scale * v for v in feature["ellipse"]["axes"]]
    phi = math.radians(feature["ellipse"]["angle_deg"])
    major = (math.cos(phi), math.sin(phi))
    minor = (-major[1], major[0])
    centre = outline.to_3d((x, y))
    marks = []
    if a > 0 and b > 1e-9 * a and a - b > 1e-9 * a:
        s1 = outline.to_3d((x + a * major[0], y + a * major[1]))
        s2 = outline.to_3d((x + b * minor[0], y + b * minor[1]))
        marks.append(Part.Ellipse(s1, s2, centre).toShape())
    elif a > 0 and b > 1e-9 * a:
        marks.append(Part.makeCircle(a, centre, outline.normal))
    elif a > 0:
        marks.append(Part.LineSegment(outline.to_3d((x - a * major[0], y - a * major[1])),
                                      outline.to_3d((x + a * major[0], y + a * major[1]))).toShape())
    u = feature["exact"]["vector"]
    if feature["exact"]["length"] > 0:
        marks.append(Part.LineSegment(centre, outline.to_3d((x + scale * u[0],
                                                             y + scale * u[1]))).toShape())
    return marks


def locating_lines(answer, tolerance, sigma_ratio, unit):
    """fixture.locating's answer as lines for the report view."""
    if not answer.deterministic:
        m = answer.free_motion
        motion = ("turn about (%s, %s)" % (_fmt(m["about"][0]), _fmt(m["about"][1]))
                  if m["kind"] == "rotation" else
                  "slide along (%s, %s)" % (_fmt(m["twist"][0]), _fmt(m["twist"][1])))
        return ["not deterministic: the fixels leave the part free to %s" % motion]
    lin, ex = answer.pose_error["linear"], answer.pose_error["exact"]
    lines = ["locators off by +-%s %s along their normals; condition number %s"
             % (_fmt(tolerance), unit, _fmt(answer.condition)),
             "pose error, worst: dx %s, dy %s %s, dtheta %s rad (linear %s, %s, %s)"
             % (_fmt(ex[0]), _fmt(ex[1]), unit, _fmt(ex[2]), _fmt(lin[0]), _fmt(lin[1]),
                _fmt(lin[2]))]
    for f in answer.features:
        axes = f["ellipse"]["axes"]
        lines.append("%s at (%s, %s): worst %s %s (linear %s); 99.73 %% ellipse (sigma = "
                     "tolerance / %s) %s by %s %s at %s deg"
                     % (f["name"], _fmt(f["at"][0]), _fmt(f["at"][1]), _fmt(f["exact"]["length"]),
                        unit, _fmt(f["linear"]["length"]), _fmt(sigma_ratio), _fmt(axes[0]),
                        _fmt(axes[1]), unit, _fmt(f["ellipse"]["angle_deg"])))
    return lines


class WrenchBestPush(_Dependent):
    """The push of the both region with the largest margin, as an arrow:
    push there, along the arrow, and let go (fixture.design of this fixture's
    own fixels: its best push, maximised to 1e-9)."""

    def setup(self, obj):
        _Dependent.setup(self, obj)
        _add(obj, "App::PropertyLength", "ArrowLength", "Push",
             "The arrow's length (0: 15 % of the part's size)", 0.0)
        for kind, name, doc in (
                ("App::PropertyString", "Meaning", "What the push promises"),
                ("App::PropertyFloat", "Margin", "The push's margin in both (its distance to "
                                                  "every cone that would stop it seating or let "
                                                  "it move), in [-1, 1]; 0 when there is none"),
                ("App::PropertyBool", "Found", "Whether some push seats the part and holds it"),
                ("App::PropertyVector", "At", "Where to push (document)"),
                ("App::PropertyVector", "Direction", "Along what (the inward normal there)"),
                ("App::PropertyInteger", "Loop", "The outline's loop"),
                ("App::PropertyInteger", "Segment", "The loop's segment"),
                ("App::PropertyFloat", "T", "Where on the segment"),
                ("App::PropertyFloat", "GoalLength", "The goal region's total length"),
                ("App::PropertyFloat", "BothLength", "The both region's total length"),
                ("App::PropertyFloat", "GravityGoalDegrees",
                 "The longest arc of tilts under which gravity seats the part"),
                ("App::PropertyFloat", "CriticalMu",
                 "The friction above which no push seats the part (-1: none up to 2)"),
                ("App::PropertyFloat", "PushForce",
                 "With the fixture's Gravity or Loads: the least force in N of this push that "
                 "seats the part and holds it under every case (-1: none does; 0 without loads)"),
                ("App::PropertyFloat", "LeastForce",
                 "With loads: the least push force anywhere on the outline, in N (-1: none; "
                 "-2: not asked: on rest buttons, a face with arcs or holes)"),
                ("App::PropertyVector", "LeastForceAt", "Where that least push is (document)")):
            _add(obj, kind, name, "Answer", doc, mode=1)

    def _execute(self, obj):
        obj.Meaning = MEANING["both"]
        fixture = _Fixture(obj.Fixture, obj.Label)
        outline = fixture.outline
        obj.Found = False
        obj.Margin = 0.0
        if not fixture.has_fixels:
            obj.Shape = Part.Shape()
            obj.Label = "Best push (no fixels yet)"
            return
        fixels = fixture.fixture["fixels"]
        result = fixture.ask(lambda: fixture.client.design(
            fixture.fixture["body"], fixture.friction(), fixels=len(fixels), sites=fixels, top=1))
        design = result.designs[0] if result.designs else None
        if design is not None:
            obj.GoalLength, obj.BothLength = design.goal_length, design.both_length
            obj.GravityGoalDegrees = design.gravity_goal_deg
            obj.CriticalMu = -1.0 if design.critical_mu is None else design.critical_mu
        push = design.best_push if design is not None else None
        if push is None:
            obj.Shape = Part.Shape()
            counts = result.counts
            why = ("the fixels do not pin the part" if counts.get("unpinned") else
                   "the fixels are degenerate" if counts.get("degenerate") else
                   "no push seats the part from every contact state" if counts.get("no_seating_push")
                   else "the both region is empty")
            obj.Label = "Best push: none (%s)" % why
            return
        at, direction = push["at"], push["direction"]
        length = float(obj.ArrowLength) or 0.15 * outline.size
        tip = outline.to_3d(at)
        d3 = outline.direction_3d(direction)
        head = length * 0.3
        shaft_start = tip - d3 * length
        shaft = Part.makeCylinder(length * 0.04, length - head, shaft_start, d3)
        cone = Part.makeCone(length * 0.11, 0.0, head, tip - d3 * head, d3)
        obj.Shape = shaft.fuse(cone)
        obj.Found = True
        obj.Margin = push["margin"]
        obj.At, obj.Direction = tip, d3
        obj.Loop, obj.Segment, obj.T = push.get("loop", 0), push.get("segment", push.get("edge", 0)), \
            push["t"]
        obj.Label = "Best push (both): margin %.4g, push here and let go" % obj.Margin
        cases, which = force_question(fixture)
        obj.PushForce = obj.LeastForce = 0.0
        if cases:
            # How hard: this push's least force under every case, and the
            # least push anywhere (force.range, push.force; N).
            fid = fixture.obj.FixtureId
            here = fixture.ask(lambda: fixture.client.force_range(
                fid, cases, push={"at": at, "direction": direction}, sets=[which]))
            least = here["all"][which]["least"]
            obj.PushForce = -1.0 if least is None else least
            try:
                anywhere = fixture.ask(lambda: fixture.client.push_force(
                    fid, cases, set=which, samples=1))["least"]
                obj.LeastForce = -1.0 if anywhere is None else anywhere["force"]
            except WrenchError as error:
                # on rest buttons the least push anywhere is found on a
                # polygon only (Least force says why); this push's force stands
                if not (fixture.on_supports and error.field.endswith("body.shape")):
                    raise
                anywhere, obj.LeastForce = None, -2.0
            if anywhere is not None:
                obj.LeastForceAt = outline.to_3d(anywhere["at"])
            if fixture.on_supports:
                # The margin and the region are the floating part's (no
                # direction-only answer holds on the buttons); how hard is
                # the buttons' own.
                obj.Meaning = ("both for the part floating; on the rest buttons this push "
                               "seats it when at least PushForce hard (goal), and whether it "
                               "then holds is not asked")
                obj.Label = "Best push (both, floating): margin %.4g; on the rest buttons %s" % (
                    obj.Margin, "at least %.4g N to seat it" % least if least is not None
                    else "no force seats it")
            else:
                obj.Label = ("Best push (both): margin %.4g, %s" % (
                    obj.Margin, "at least %.4g N under every load case" % least
                    if least is not None else "no force does it under every load case"))


class WrenchLeastForce(_Dependent):
    """The least push force F*(p) along the outline under the fixture's
    load cases (push.force, set both): the outline cut into a piece per
    sample, each coloured from blue (the least) to red (the most), grey
    where no force does the job; and where the smallest push suffices,
    as an arrow (its last three edges).  On rest buttons the set is goal
    (wrenchd answers how hard to push to seat the part against the
    buttons' friction; whether the seated part is held is a question of
    its own), asked without loads too, and the same fixture floating is
    asked beside it (FloatingLeast)."""

    def setup(self, obj):
        _Dependent.setup(self, obj)
        _add(obj, "App::PropertyInteger", "Samples", "Force",
             "Samples of F* per segment of the outline", 32)
        _add(obj, "App::PropertyString", "PushOn", "Force",
             "Where the finger may push, as a regions object's PushOn: empty, the clients' "
             "default (a point finger on the outer boundary only); outer; all; or loop "
             "numbers (0, 2)", "")
        for kind, name, doc in (
                ("App::PropertyFloatList", "Forces",
                 "F* at each piece's sample, in N (-1: no force does the job there)"),
                ("App::PropertyFloat", "Least", "The least push force over the outline, N (-1: none)"),
                ("App::PropertyVector", "LeastAt", "Where it is (document)"),
                ("App::PropertyVector", "LeastDirection", "Along what (the inward normal there)"),
                ("App::PropertyString", "Set",
                 "What the force does: both (seats the part and holds it; floating) or goal "
                 "(seats it against the rest buttons' friction)"),
                ("App::PropertyFloat", "FloatingLeast",
                 "On rest buttons: the least push of the same set with the part floating, N "
                 "(-1: none; -2: not asked, the part floats)"),
                ("App::PropertyVector", "FloatingLeastAt", "Where it is (document)")):
            _add(obj, kind, name, "Answer", doc, mode=1)

    def _execute(self, obj):
        fixture = _Fixture(obj.Fixture, obj.Label)
        outline = fixture.outline
        cases, obj.Set = force_question(fixture)
        plate = fixture.on_supports
        obj.FloatingLeast = -2.0
        if not cases or not fixture.has_fixels:
            obj.Shape = Part.Shape()
            obj.Forces, obj.Least = [], -1.0
            obj.Label = "Least force (%s)" % ("set the fixture's Gravity or Loads" if not cases
                                              else "no fixels yet")
            return
        fid = fixture.obj.FixtureId
        samples = max(1, min(int(obj.Samples), 4096))
        try:
            push_on = push_on_of(obj.PushOn, fixture.fixture["body"], 0.0)
        except OutlineError as e:
            raise WrenchError("%s: %s" % (obj.Label, e))
        try:
            r = fixture.ask(lambda: fixture.client.push_force(fid, cases, set=obj.Set,
                                                              samples=samples,
                                                              push_on=push_on or "all"))
        except WrenchError as error:
            if plate and error.field.endswith("body.shape"):
                # what in the face keeps it from being a polygon
                outline = fixture.outline
                raise WrenchError("%s; %s has %s, so it is sent as an outline" % (
                    error, fixture.obj.Label, "holes" if len(outline.segments) > 1 else
                    "arcs (%s)" % ", ".join(s.edge or "an edge" for s in outline.segments[0]
                                           if s.is_arc)), error.field, error.reason) from None
            raise
        if plate:
            # The same part floating, for comparison: its least push alone.
            floating = fixture.ask(lambda: fixture.client.push_force(
                _supports().floating(fixture.fixture), cases, set=obj.Set, samples=1,
                push_on=push_on or "all"))["least"]
            obj.FloatingLeast = -1.0 if floating is None else floating["force"]
            if floating is not None:
                obj.FloatingLeastAt = outline.to_3d(floating["at"])
        pieces, forces = [], []
        for seg in r["segments"]:
            segment = outline.segments[seg.get("loop", 0)][seg.get("segment", seg.get("edge", 0))]
            ts = seg["t"]
            for j, (t, f) in enumerate(zip(ts, seg["force"])):
                t0 = 0.0 if j == 0 else (ts[j - 1] + t) / 2
                t1 = 1.0 if j + 1 == len(ts) else (t + ts[j + 1]) / 2
                pieces.append(outline.edge_3d(segment, t0, t1))
                forces.append(-1.0 if f is None else f)
        obj.Forces = forces
        least = r["least"]
        obj.Least = -1.0 if least is None else least["force"]
        if least is not None:
            obj.LeastAt = outline.to_3d(least["at"])
            obj.LeastDirection = outline.direction_3d(least["direction"])
            pieces += _push_arrow(outline, least["at"], least["direction"])
            obj.Label = "Least force%s: %.4g N at %s" % (
                " on the rest buttons" if plate else "", obj.Least, _fmt_point(obj.LeastAt))
            if plate:
                obj.Label += " (floating: %s)" % ("%.4g N" % obj.FloatingLeast
                                                  if obj.FloatingLeast >= 0 else "none")
        else:
            obj.Label = "Least force: no push does the job under every load case"
        obj.Shape = Part.Compound(pieces)
        colour_least_force(obj)


def _push_arrow(outline, at, direction):
    """Three edges: a shaft ending at the outline point `at`, along the
    unit `direction`, and its head."""
    length = 0.15 * outline.size
    tip = (at[0], at[1])
    back = (at[0] - length * direction[0], at[1] - length * direction[1])
    head = []
    for s in (-1.0, 1.0):
        c, d = math.cos(s * 0.4), math.sin(s * 0.4)
        u = (c * direction[0] - d * direction[1], d * direction[0] + c * direction[1])
        head.append(outline.to_3d((at[0] - 0.25 * length * u[0], at[1] - 0.25 * length * u[1])))
    return [Part.LineSegment(outline.to_3d(back), outline.to_3d(tip)).toShape()] + \
        [Part.LineSegment(h, outline.to_3d(tip)).toShape() for h in head]


class WrenchGravityDial(_Dependent):
    """The tilts under which gravity alone does the set's job, as arcs of a
    dial around the centre of mass: a direction on the dial is the
    direction gravity pulls, in the outline's plane (gravity.sweep)."""

    def setup(self, obj):
        _Dependent.setup(self, obj)
        if "Set" not in obj.PropertiesList:
            obj.addProperty("App::PropertyEnumeration", "Set", "Dial",
                            "goal: gravity seats the part; strong: it holds it still once "
                            "seated; both: it seats it and then holds it still")
            _set_enumeration(obj, "Set", SETS, "both")
        _add(obj, "App::PropertyLength", "Radius", "Dial",
             "The dial's radius (0: just around the part)", 0.0)
        for kind, name, doc in (
                ("App::PropertyString", "Meaning", "What the set promises"),
                ("App::PropertyFloatList", "Arcs", "The arcs, [from, to, from, to, ...] in "
                                                   "degrees counter-clockwise from the outline's x"),
                ("App::PropertyFloat", "TotalDegrees", "Their total")):
            _add(obj, kind, name, "Answer", doc, mode=1)

    def _execute(self, obj):
        which = obj.Set
        obj.Meaning = GRAVITY_MEANING[which]
        fixture = _Fixture(obj.Fixture, obj.Label)
        if not fixture.has_fixels:
            obj.Shape = Part.Shape()
            obj.Arcs, obj.TotalDegrees = [], 0.0
            obj.Label = "Gravity %s (no fixels yet)" % which
            return
        if fixture.on_supports:
            arcs = self.on_buttons(obj, fixture)
        else:
            arcs = fixture.ask(lambda: fixture.client.gravity_sweep(fixture.fixture, which))
        outline = fixture.outline
        com = outline.to_2d(fixture.obj.CenterOfMass)
        radius = float(obj.Radius) or 1.15 * max(
            _norm(_sub(s.point(t), com[:2])) for s in outline.segments[0] for t in (0.0, 0.5))
        edges = []
        for a, b in arcs:
            circle = Part.Circle(outline.to_3d(com[:2]), outline.normal, radius)
            circle.XAxis = outline.direction_3d((1.0, 0.0))
            edges.append(Part.ArcOfCircle(circle, math.radians(a), math.radians(b)).toShape())
        for k in range(4):                     # ticks at 0, 90, 180 and 270 degrees
            a = k * math.pi / 2
            inner = (com[0] + 0.93 * radius * math.cos(a), com[1] + 0.93 * radius * math.sin(a))
            outer = (com[0] + 1.07 * radius * math.cos(a), com[1] + 1.07 * radius * math.sin(a))
            edges.append(Part.LineSegment(outline.to_3d(inner), outline.to_3d(outer)).toShape())
        obj.Shape = Part.Compound(edges)
        obj.Arcs = [x for arc in arcs for x in arc]
        obj.TotalDegrees = sum(b - a for a, b in arcs)
        obj.Label = "Gravity %s: %s degrees of tilt" % (which, _fmt(obj.TotalDegrees))
        if fixture.on_supports:
            obj.Label = "Gravity goal on the rest buttons, %s mm/s^2 in the plane: %s degrees" % (
                _fmt(fixture.obj.Gravity), _fmt(obj.TotalDegrees))

    @staticmethod
    def on_buttons(obj, fixture):
        """The tilts on rest buttons: whether the pull seats the part depends
        on its size, the fixture's Gravity (the part of gravity in the
        plate's plane), and only goal is answered there."""
        pull = float(fixture.obj.Gravity)
        if pull <= 0:
            raise WrenchError("%s: on rest buttons whether gravity seats the part depends on how "
                              "hard it pulls in the plate's plane: set %s's Gravity (g sin(tilt), "
                              "mm/s^2)" % (obj.Label, fixture.obj.Label), "in_plane_g", "required")
        obj.Meaning = ("goal on the rest buttons: gravity pulling this way with the fixture's "
                       "Gravity seats the part against their friction; whether it then holds "
                       "is not asked")
        return fixture.ask(lambda: fixture.client.tilt_on_supports(
            fixture.fixture, pull))["intervals_deg"]


# ---- making objects ---------------------------------------------------------------

def _fixel_vectors(outline_shape, fixels):
    """(points, normals) in the document of fixels given as document
    Vectors, (point, normal) pairs of Vectors, or wrenchd's dicts
    {"at": [x, y], "normal"?: [nx, ny]} in the outline's coordinates."""
    points, normals = [], []
    for i, f in enumerate(fixels):
        if isinstance(f, Vector):
            points.append(Vector(f))
            normals.append(Vector())
        elif isinstance(f, dict):
            if outline_shape is None:
                raise ValueError("fixels[%d]: a fixel in the outline's coordinates needs the outline"
                                 % i)
            points.append(outline_shape.to_3d(f["at"]))
            n = f.get("normal")
            normals.append(outline_shape.direction_3d(n) if n is not None else Vector())
        elif isinstance(f, (tuple, list)) and len(f) == 2 and isinstance(f[0], Vector):
            points.append(Vector(f[0]))
            normals.append(Vector(f[1]) if f[1] is not None else Vector())
        else:
            raise ValueError("fixels[%d]: a fixel is a Vector, a (point, normal) pair of Vectors "
                             "or {\"at\": [x, y], \"normal\": [nx, ny]}, not %r" % (i, f))
    return points, normals


def make_fixture(doc, source, fixels=(), friction=0.3, mass=1.0, socket="", tolerance=0.0,
                 label="WrenchFixture"):
    """A WrenchFixture on `source`: (object, "FaceN"), a sketch, or an object
    of one planar face.  fixels: see _fixel_vectors; friction: a number, a
    (static, kinetic) pair or {"static", "kinetic"}."""
    obj = doc.addObject("Part::FeaturePython", "WrenchFixture")
    WrenchFixture(obj)
    obj.Label = label
    source_obj, sub = _document_source(source)
    obj.Source = (source_obj, [sub] if sub else [])
    obj.Tolerance = tolerance
    obj.StaticFriction, obj.KineticFriction = _friction_values(friction)
    obj.Mass = mass
    obj.Socket = socket or ""
    if fixels:
        shape = None
        if any(isinstance(f, dict) for f in fixels):
            shape = obj.Proxy.outline(obj)
        obj.FixelPoints, obj.FixelNormals = _fixel_vectors(shape, fixels)
    _attach_view(obj)
    return obj


def _dependent(kind, fixture, label, **values):
    doc = fixture.Document
    obj = doc.addObject("Part::FeaturePython", kind)
    globals()[kind](obj)
    obj.Fixture = fixture
    for name, value in values.items():
        setattr(obj, name, value)
    obj.Label = label
    _attach_view(obj)
    return obj


def make_regions(fixture, set="both", push_on=""):
    """A WrenchRegions of `set` (goal, strong or both) for the fixture;
    push_on its PushOn: "" (the clients' default), "outer", "all" or a list
    of loop numbers."""
    if set not in SETS:
        raise ValueError("set: one of goal, strong, both, not %r" % (set,))
    if not isinstance(push_on, str):
        push_on = ", ".join(str(int(i)) for i in push_on)
    return _dependent("WrenchRegions", fixture, "Regions %s" % set, Set=set, PushOn=push_on)


def make_fixels(fixture):
    return _dependent("WrenchFixels", fixture, "Fixels")


def make_best_push(fixture):
    return _dependent("WrenchBestPush", fixture, "Best push (both)")


def make_locating(fixture, tolerance=0.02, features=(), names=()):
    """A WrenchLocating of the fixture: each locator off by +-tolerance, the
    document points `features` (named `names`)."""
    return _dependent("WrenchLocating", fixture, "Locating", Tolerance=tolerance,
                      Features=list(features), FeatureNames=list(names))


def make_least_force(fixture, samples=32, push_on=""):
    """A WrenchLeastForce of the fixture: F* at `samples` points of every
    segment, the finger pushing on `push_on` (as make_regions')."""
    if not isinstance(push_on, str):
        push_on = ", ".join(str(int(i)) for i in push_on)
    return _dependent("WrenchLeastForce", fixture, "Least force", Samples=samples,
                      PushOn=push_on)


def make_gravity_dial(fixture, set="both"):
    if set not in SETS:
        raise ValueError("set: one of goal, strong, both, not %r" % (set,))
    return _dependent("WrenchGravityDial", fixture, "Gravity %s" % set, Set=set)


def _object_of_face(doc, face):
    """(object, "FaceN") of the document object whose shape holds `face`, or
    a new Part::Feature holding it."""
    for obj in doc.Objects:
        shape = getattr(obj, "Shape", None)
        if shape is None or shape.isNull() or _proxy_name(obj).startswith("Wrench"):
            continue
        for i, f in enumerate(shape.Faces):
            if f.isSame(face) or f.isPartner(face):
                return obj, "Face%d" % (i + 1)
    # a face held before by a WrenchPart (a Part::Feature's shape is a copy)
    size = face.BoundBox.DiagonalLength
    for obj in doc.Objects:
        if obj.TypeId == "Part::Feature" and obj.Name.startswith("WrenchPart") \
                and len(obj.Shape.Faces) == 1:
            f = obj.Shape.Faces[0]
            if abs(f.Area - face.Area) <= 1e-12 * face.Area \
                    and f.CenterOfMass.distanceToPoint(face.CenterOfMass) <= 1e-12 * size \
                    and len(f.Edges) == len(face.Edges) \
                    and f.BoundBox.isInside(face.BoundBox.Center):
                return obj, ""
    part = doc.addObject("Part::Feature", "WrenchPart")
    part.Shape = face
    return part, ""


def _raise_failures(objects):
    for obj in objects:
        if "Invalid" in obj.State or "Error" in obj.State:
            raise WrenchError(obj.getStatusString())


def show_regions(doc, face, fixels, friction, set, client):
    """The push regions of `set` for the part's `face` held by `fixels`:
    creates a WrenchFixture and a WrenchRegions in `doc`, recomputes them,
    and returns the WrenchRegion objects, one per region, each with its
    Shape (the line or arc) and its numbers (Loop, Segment, T0, T1, From,
    To, Length, Edge, Set and Meaning).

    face: a Part.Face (of a document object, which the fixture then links,
    so that it follows the part; else a Part::Feature holding it is made),
    an (object, "FaceN") pair, a sketch, or an object of one planar face.
    fixels: document Vectors, (point, normal) pairs, or wrenchd's fixel
    dicts in the outline's coordinates.  friction: a number, (static,
    kinetic) or {"static", "kinetic"}.  client: a wrenchd.Client, its socket
    and timeout the fixture's (None: $WRENCHD_SOCKET or ./run/wrenchd.sock,
    60 s).  Raises WrenchError (what wrenchd refused, that it is busy, or
    how to start it) or OutlineError."""
    if set not in SETS:
        raise ValueError("set: one of goal, strong, both, not %r" % (set,))
    if isinstance(face, Part.Shape):
        source = _object_of_face(doc, face)
    else:
        source = face
    socket = ""
    if client is not None:
        _use_client(client)
        socket = client.socket_path
    fixture = make_fixture(doc, source, fixels, friction, socket=socket)
    if client is not None and client.timeout:
        fixture.Timeout = float(client.timeout)   # the client's, as given
    regions = make_regions(fixture, set)
    doc.recompute()
    _raise_failures([fixture, regions])
    return sync_regions(regions)


# ---- designing ---------------------------------------------------------------------

class _Progress:
    """design.progress notifications on FreeCAD's progress indicator (the
    status bar's in the GUI, the console's in freecadcmd): one run of the
    indicator per stage (a lattice's hole pairs, the candidates, the
    designs' figures), and the estimated time left (eta_s) beside it: on the
    status bar in the GUI, a console line at each tenth without it."""

    UNITS = {"poses": "hole pairs", "candidates": "candidates", "figures": "designs' figures"}

    def __init__(self, text):
        self.text = text
        self.indicator = None
        self.stage = None
        self.shown = 0
        # the status bar's bar in percent; the console's line in tenths
        self.steps = 100 if FreeCAD.GuiUp else 10

    def _eta(self, params):
        eta = params.get("eta_s")
        if eta is None or (params.get("done") or 0) >= (params.get("total") or 0):
            return ""
        return ", about %s left" % wrenchd._eta_text(eta)

    def __call__(self, params):
        total = params.get("total") or 0
        done = params.get("done") or 0
        stage = params.get("stage", "candidates")
        unit = self.UNITS.get(stage, stage)
        if self.indicator is None or stage != self.stage:
            self.stop()
            self.stage = stage
            self.shown = 0
            self.indicator = FreeCAD.Base.ProgressIndicator()
            self.indicator.start("%s: %d %s" % (self.text, total, unit), self.steps)
        step = int(self.steps * done / total) if total else self.steps
        eta = self._eta(params)
        if eta and FreeCAD.GuiUp:
            try:
                import FreeCADGui
                FreeCADGui.getMainWindow().statusBar().showMessage(
                    "%s: %d of %d %s%s" % (self.text, done, total, unit, eta))
            except Exception:                # no main window: the bar alone
                pass
        elif eta and step > self.shown:
            FreeCAD.Console.PrintMessage("%s: %d of %d %s%s\n" % (self.text, done, total, unit,
                                                                  eta))
        while self.shown < step:
            self.shown += 1
            self.indicator.next(True)      # raises when the user stops it

    def stop(self):
        if self.indicator is not None:
            self.indicator.stop()
            self.indicator = None


DESIGN_OBJECTIVES = ["margin", "region", "gravity", "force", "accuracy", "pareto"]


def design(fixture, client=None, progress=True, spacing=None, fixels=None, objective=None,
           top=None, place=True):
    """fixture.design on the fixture's face: `fixels` (default the fixture's
    DesignFixels) among candidate sites `spacing` apart (DesignSpacing; 0:
    the perimeter / 40), ranked by `objective` (DesignObjective), with
    FreeCAD's progress indicator (progress=True) or a callable.  With
    place=True the best design's fixels become the fixture's and the
    document is recomputed.  The ranking goes to the fixture's Designs and
    to the report view.  Returns the wrenchd.DesignResult."""
    doc = fixture.Document
    if not fixture.FixtureJson:
        fixture.recompute()
        if not fixture.FixtureJson:
            raise WrenchError(fixture.getStatusString() or "%s has no outline" % fixture.Label)
    data = json.loads(fixture.FixtureJson)
    edges = json.loads(fixture.EdgeTable) if fixture.EdgeTable else None
    shape = Outline.from_shape(data["body"]["shape"], fixture.Frame, edges)
    count = fixels or fixture.DesignFixels
    h = spacing or float(fixture.DesignSpacing) or float("%.2g" % (shape.perimeter() / 40.0))
    objective = objective or fixture.DesignObjective
    top = top or fixture.DesignTop
    path = socket_path(fixture.Socket)
    if client is None:
        client = client_for(fixture.Socket, fixture.Timeout)
    friction = {"static": fixture.StaticFriction, "kinetic": fixture.KineticFriction}
    body = {"mass": fixture.Mass, "shape": shape}
    # Gravity and Loads: every design reports its least push under them, and
    # objective force ranks by it (mm and N, as the fixture is sent).
    cases = load_cases(fixture, shape)
    if objective == "force" and not cases:
        raise WrenchError("%s: DesignObjective force ranks by the least push under the load "
                          "cases: set Gravity or Loads" % fixture.Label, "cases", "required")
    extra = {"cases": cases, "units": {"length": "mm", "force": "N"}} if cases else {}
    if objective in ("accuracy", "pareto"):
        extra["tolerance"] = float(fixture.DesignTolerance)
        extra["features"] = [shape.to_2d(p)[:2] for p in fixture.DesignFeatures]
    indicator = _Progress("Designing %s" % fixture.Label) if progress is True else None
    callback = indicator if indicator is not None else (progress or None)
    what = "%s: design" % fixture.Label
    try:
        result = _ask(what, path, lambda: client.design(
            body, friction, fixels=count, spacing=h, objective=objective, top=top,
            progress=callback, **extra), shape, properties={
                "fixels": "DesignFixels (%s)" % count, "spacing": "DesignSpacing (%s)" % _fmt(h),
                "objective": "DesignObjective (%s)" % objective, "top": "DesignTop (%s)" % top,
                "friction": "the friction (StaticFriction, KineticFriction)",
                "body": "the part (Mass, or its outline)", "cases": "Gravity and Loads",
                "tolerance": "DesignTolerance", "features": "DesignFeatures"})
    finally:
        if indicator is not None:
            indicator.stop()
    lines = _design_lines(count, shape, result, h)
    if list(fixture.SupportPoints):
        lines.insert(1, "the designs are the floating part's: its rest buttons are not among "
                        "what the design is asked with; Least force then says how hard to push "
                        "on them")
    fixture.Designs = lines
    for line in lines:
        FreeCAD.Console.PrintMessage("Wrench: %s\n" % line)
    if not result.designs:
        raise WrenchError("%s: no design: %s" % (what, lines[0]))
    if place:
        best = result.designs[0]
        points, normals = _fixel_vectors(shape, best.fixels)
        fixture.FixelPoints, fixture.FixelNormals = points, normals
        doc.recompute()
        for obj in [fixture] + [o for o in fixture.InList if _proxy_name(o).startswith("Wrench")]:
            if "Invalid" in obj.State:
                raise WrenchError(obj.getStatusString())
    return result


def _design_lines(count, shape, result, spacing):
    counts = result.counts
    head = ("%d fixels from %d sites %s %s apart, %d candidates (%d without a seating push, "
            "%d unpinned, %d degenerate), ranked by %s; lengths in %s" % (
                count, result.sites, _fmt(spacing), UNIT, counts.get("candidates", 0),
                counts.get("no_seating_push", 0), counts.get("unpinned", 0),
                counts.get("degenerate", 0),
                {"margin": "the margin of the best push in both",
                 "region": "the length of the both region",
                 "gravity": "the longest arc of tilts under which gravity seats the part",
                 "force": "the least push force (N) that seats and holds it under every load "
                          "case, smallest first",
                 "accuracy": "the worst locating error (%s) with every locator off by up to "
                             "DesignTolerance" % UNIT,
                 "pareto": "the Pareto front: the designs no other beats on margin, worst "
                           "locating error (%s, every locator off by up to DesignTolerance) and "
                           "least push force (N, under Gravity and Loads) together; score the "
                           "margin" % UNIT,
                 }.get(result.objective, result.objective), UNIT))
    lines = [head]
    for d in result.designs:
        at = " ".join(_fmt_point(shape.to_3d(f["at"])) for f in d.fixels)
        if d.best_push:
            push = "push at %s along %s, margin %.4g" % (
                _fmt_point(shape.to_3d(d.best_push["at"])),
                _fmt_point(shape.direction_3d(d.best_push["direction"])), d.best_push["margin"])
        else:
            push = "no push seats and holds it"
        lines.append("%d. score %.6g: fixels at %s; %s; goal %s, both %s long; gravity %s deg; "
                     "critical mu %s" % (d.rank, d.score, at, push, _fmt(d.goal_length),
                                         _fmt(d.both_length), _fmt(d.gravity_goal_deg),
                                         "none up to 2" if d.critical_mu is None
                                         else _fmt(d.critical_mu)))
        if d.least_push is not None:
            lines[-1] += "; least push %.6g N at %s" % (
                d.least_push["force"], _fmt_point(shape.to_3d(d.least_push["at"])))
        if d.accuracy is not None:
            lines[-1] += "; worst locating error %s %s" % (_fmt(d.accuracy), UNIT)
        pareto = getattr(d, "pareto", None)
        if pareto is not None:
            lines[-1] += "; pareto: margin %.4g, worst locating error %s %s, least push %s" % (
                pareto["margin"], _fmt(pareto["accuracy"]), UNIT,
                "none" if pareto["force"] is None else "%.6g N" % pareto["force"])
        if getattr(d, "copies", 1) > 1:
            lines[-1] += "; and %d more like it, turned or mirrored by the part's symmetries" % (
                d.copies - 1)
    if result.designs:
        lines.append("design 1's fixels placed. Push at its best push (the arrow) and let go: "
                     "it lies in both, which seats the part from any contact state and then "
                     "holds it still; a push in goal alone seats it but may leave it sliding "
                     "along its fixels.")
    return lines


# ---- picking fixels ----------------------------------------------------------------

def fixel_at(fixture, point, corner=None):
    """(point, normal) of a fixel at the document point: the point moved
    onto the fixture's outline; the normal (0, 0, 0) (the outline's own)
    except at a corner (a vertex where the outline turns: `corner` True, or
    None to find out), where it is the inward bisector."""
    if not fixture.FixtureJson:
        fixture.recompute()
    data = json.loads(fixture.FixtureJson)
    shape = Outline.from_shape(data["body"]["shape"], fixture.Frame)
    x, y, _ = shape.to_2d(point)
    segment, t, q, d = shape.nearest((x, y))
    at_vertex = t in (0.0, 1.0) or min(_norm(_sub(q, segment.start)), _norm(_sub(q, segment.end))) \
        <= 1e-9 * shape.size
    if corner is None:
        corner = False
        if at_vertex:
            index = segment.index if _norm(_sub(q, segment.start)) <= _norm(_sub(q, segment.end)) \
                else (segment.index + 1) % len(shape.segments[segment.loop])
            before = shape.segments[segment.loop][index - 1]
            after = shape.segments[segment.loop][index]
            corner = abs(_angle(before.tangent(1.0), after.tangent(0.0))) > 1e-9
    if corner:
        index = segment.index if _norm(_sub(q, segment.start)) <= _norm(_sub(q, segment.end)) \
            else (segment.index + 1) % len(shape.segments[segment.loop])
        vertex = shape.segments[segment.loop][index].start
        n = shape.corner_normal(segment.loop, index)
        return shape.to_3d(vertex), shape.direction_3d(n)
    return shape.to_3d(q), Vector()
