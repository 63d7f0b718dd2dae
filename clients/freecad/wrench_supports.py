"""wrench_supports -- the rest buttons of the Wrench workbench: a part lying
on a base plate (wrench_freecad.py is the workbench's one import; the
fixture and its other objects are wrench_objects.py's).  FreeCAD and Part
only at module level, so that freecadcmd runs all of it.

A WrenchFixture's group "Rest buttons" holds them: SupportPoints (document
points, each taken into the face's plane: a button under the part, a
vertex or a hole's centre on either side of it, counts where it is in the
plane), their friction mu_B (SupportStaticFriction, SupportKineticFriction),
SupportGravity (into the plate, mm/s^2) and the down clamps (DownPoints,
DownForces in N).  With SupportPoints the fixture sent to wrenchd has the
member `supports` (docs/PROTOCOL.md, Supports), which is part of its id;
on a face bounded by straight lines alone its shape is sent as a polygon,
the shape on which wrenchd finds the least push on the plate.

    support_at(fixture, point)          -> the point in the face's plane
    add_supports(fixture, points)       -> the points added, recomputed
    normal_loads(points, com, mass, g, downs) -> the statics (below)
    make_supports(fixture)              -> a WrenchSupports

The normal loads are not in wrenchd's answers; they follow from statics
out of the plane alone (docs/MODEL.md section 11): sum N_i = W = m g + sum
D_k, sum N_i p_i = W c, N_i >= 0.  With three buttons the N_i are W times
the barycentric coordinates of the centre of pressure c; with more they
are not determined, and each lies in a range over the admissible
distributions, whose ends are reached at a vertex of that polytope: a
distribution on three buttons whose triangle holds c.  A centre of
pressure outside the buttons' polygon tips the part: wrenchd refuses the
fixture, and its reason is the fixture's error and the report's.

A WrenchSupports draws each button as a ring in the face's plane with its
normal load as an arrow leaving it along the face's normal (the force on
the part, where it acts; longest for the largest load, a range drawn at its
upper end), each down clamp as an arrow pressing onto the plane, both on
the side the face's normal points to, where a view onto the face sees them;
it lists the loads in Report and in the report view, and the view provider
writes them at the arrows' far ends in the 3-D view (LoadLabels).
"""

import itertools
import re

import FreeCAD
import Part

# wrench_objects imports this module only inside its functions (the
# fixture's proxy asks for the rest buttons long after both are loaded).
from wrench_objects import (OutlineError, WrenchError, _add, _attach_view, _Dependent,
                            _Fixture, _fmt, _fmt_point, _is, _report_error)


# A down clamp's force when it is picked, in N: a hand clamp's, to change in
# DownForces.
DOWN_FORCE = 100.0

# A kilogram under an acceleration in mm/s^2 weighs a thousandth of a newton:
# the fixture is sent in mm and N (wrench_objects.UNITS).
_NEWTONS_PER_KG_MM_S2 = 1e-3


# ---- the fixture's rest buttons ------------------------------------------------------

def setup_fixture(obj):
    """The fixture's properties for rest buttons (added when missing)."""
    _add(obj, "App::PropertyVectorList", "SupportPoints", "Rest buttons",
         "The rest buttons under the part, in the document's coordinates (each taken into the "
         "face's plane); none: the part floats in its plane")
    _add(obj, "App::PropertyFloat", "SupportStaticFriction", "Rest buttons",
         "The rest buttons' static friction mu_B", 0.15)
    _add(obj, "App::PropertyFloat", "SupportKineticFriction", "Rest buttons",
         "Their kinetic friction, at most the static one", 0.15)
    _add(obj, "App::PropertyFloat", "SupportGravity", "Rest buttons",
         "Gravity into the plate in mm/s^2 (9810 on earth); the part's weight is Mass times it",
         9810.0)
    _add(obj, "App::PropertyVectorList", "DownPoints", "Rest buttons",
         "Down clamps pressing the part onto its buttons: where (document; taken into the "
         "face's plane)")
    _add(obj, "App::PropertyFloatList", "DownForces", "Rest buttons",
         "Each down clamp's force in N, in DownPoints' order")
    for kind, name, doc in (
            ("App::PropertyFloat", "SupportWeight",
             "W: the weight and the down clamps pressing the part onto its buttons, N"),
            ("App::PropertyVector", "CentreOfPressure",
             "Where W acts: the centre of mass moved by the down clamps (document)"),
            ("App::PropertyFloatList", "NormalLoads",
             "Each button's normal load in N; with more than three, the middle of its range"),
            ("App::PropertyFloatList", "NormalLoadsMin",
             "Each button's least normal load over the admissible distributions, N"),
            ("App::PropertyFloatList", "NormalLoadsMax",
             "Each button's largest normal load over the admissible distributions, N"),
            ("App::PropertyStringList", "SupportsReport",
             "The buttons' loads, or wrenchd's reason for refusing them")):
        _add(obj, kind, name, "Rest buttons", doc, mode=1)


def has_supports(obj):
    return "SupportPoints" in obj.PropertiesList and len(obj.SupportPoints) > 0


def _friction(obj):
    s, k = float(obj.SupportStaticFriction), float(obj.SupportKineticFriction)
    return s if s == k else {"static": s, "kinetic": k}


def supports_member(obj, shape):
    """The fixture's `supports` member in the outline's coordinates, or
    None without rest buttons."""
    if not has_supports(obj):
        return None
    points, forces = list(obj.DownPoints), list(obj.DownForces)
    if len(forces) != len(points):
        raise WrenchError(
            "%s: %d DownPoints but %d DownForces: give each down clamp its force in N"
            % (obj.Label, len(points), len(forces)), "supports.down", "one force a clamp")
    member = {"points": [list(shape.to_2d(p)[:2]) for p in obj.SupportPoints],
              "friction": _friction(obj), "g": float(obj.SupportGravity)}
    if points:
        member["down"] = [{"at": list(shape.to_2d(p)[:2]), "force": float(f)}
                          for p, f in zip(points, forces)]
    return member


def wire_shape(fixture, outline):
    """The body's shape to send: a polygon when the fixture is on supports
    and its outline one loop of straight lines (wrenchd finds the least
    push on the plate over a polygon's edges: edge i of the polygon is
    segment i of the loop), else the outline itself."""
    if "supports" not in fixture or len(outline.segments) != 1 or \
            any(s.is_arc for s in outline.segments[0]):
        return outline
    return {"type": "polygon", "vertices": [list(s.start) for s in outline.segments[0]]}


def floating(fixture):
    """The same fixture (the same shape) without its supports."""
    return {k: v for k, v in fixture.items() if k != "supports"}


# ---- refusals ---------------------------------------------------------------------

def refusal_subject(obj, rest):
    """The fixture's property wrenchd refused, for a field under `supports`
    (rest: the field without params.fixture.), or None."""
    if not rest.startswith("supports"):
        return None
    m = re.match(r"^supports\.(points|down)\[(\d+)\](?:\.(at|force))?", rest)
    if m:
        i = int(m.group(2))
        if m.group(1) == "points":
            pts = list(obj.SupportPoints) if obj is not None else []
            return "rest button %d%s" % (i + 1, " (SupportPoints[%d] = %s)" % (
                i, _fmt_point(pts[i])) if i < len(pts) else "")
        pts = list(obj.DownPoints) if obj is not None else []
        if m.group(3) == "force":
            return "down clamp %d's force (DownForces[%d])" % (i + 1, i)
        return "down clamp %d%s" % (i + 1, " (DownPoints[%d] = %s)" % (
            i, _fmt_point(pts[i])) if i < len(pts) else "")
    word = rest.split(".")[1].split("[")[0] if "." in rest else ""
    return {"points": "the rest buttons (SupportPoints)",
            "friction": "the rest buttons' friction (SupportStaticFriction, "
                        "SupportKineticFriction)",
            "g": "SupportGravity", "down": "the down clamps (DownPoints, DownForces)"}.get(
                word, "the rest buttons")


# ---- statics ----------------------------------------------------------------------

def _cross(o, a, b):
    return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])


def _barycentric(a, b, c, p):
    """p's barycentric coordinates in triangle abc (None when degenerate)."""
    area = _cross(a, b, c)
    scale = max(abs(v) for q in (a, b, c) for v in q) or 1.0
    if abs(area) <= 1e-12 * scale * scale:
        return None
    return (_cross(p, b, c) / area, _cross(a, p, c) / area, _cross(a, b, p) / area)


def normal_loads(points, com, mass, g, downs=()):
    """The statics of the buttons `points` [(x, y)] under a part of `mass`
    kg at `com` with gravity `g` mm/s^2 into the plate and down clamps
    [((x, y), N)]: {"weight" W in N, "pressure" c, "min", "max" (each
    button's range over the admissible distributions; equal with three),
    "inside" (whether c lies in the buttons' polygon)}."""
    weight = mass * g * _NEWTONS_PER_KG_MM_S2
    moment = [weight * com[0], weight * com[1]]
    for at, force in downs:
        weight += force
        moment[0] += force * at[0]
        moment[1] += force * at[1]
    n = len(points)
    pressure = (moment[0] / weight, moment[1] / weight) if weight > 0 else tuple(com)
    if weight <= 0:
        return {"weight": 0.0, "pressure": pressure, "min": [0.0] * n, "max": [0.0] * n,
                "inside": True}
    low, high = [None] * n, [None] * n
    slack = 1e-9        # barycentric coordinates: a centre of pressure on an edge
    for i, j, k in itertools.combinations(range(n), 3):
        lam = _barycentric(points[i], points[j], points[k], pressure)
        if lam is None or min(lam) < -slack:
            continue
        row = [0.0] * n
        for index, l in zip((i, j, k), lam):
            row[index] = weight * max(l, 0.0)
        for m in range(n):
            low[m] = row[m] if low[m] is None else min(low[m], row[m])
            high[m] = row[m] if high[m] is None else max(high[m], row[m])
    if low[0] is None:
        return {"weight": weight, "pressure": pressure, "min": [], "max": [], "inside": False}
    return {"weight": weight, "pressure": pressure, "min": low, "max": high, "inside": True}


def _load_words(i, lo, hi, mu):
    if abs(hi - lo) <= 1e-9 * max(abs(hi), 1.0):
        return "rest button %d: N = %.6g N (its friction up to mu_B N = %.6g N)" % (
            i + 1, lo, mu * lo)
    return ("rest button %d: N between %.6g and %.6g N (its friction up to %.6g N; more than "
            "three buttons leave the loads undetermined: every distribution in range counts)"
            % (i + 1, lo, hi, mu * hi))


def record_loads(obj, shape, com2d):
    """The fixture's loads (NormalLoads, ...) and report lines, once wrenchd
    has taken its supports; com2d its centre of mass in the outline's
    coordinates."""
    member = supports_member(obj, shape)
    downs = [(d["at"], d["force"]) for d in member.get("down", [])]
    s = normal_loads(member["points"], com2d, float(obj.Mass), member["g"], downs)
    obj.SupportWeight = s["weight"]
    obj.CentreOfPressure = shape.to_3d(s["pressure"])
    obj.NormalLoadsMin, obj.NormalLoadsMax = s["min"], s["max"]
    obj.NormalLoads = [(lo + hi) / 2 for lo, hi in zip(s["min"], s["max"])]
    mu = float(obj.SupportStaticFriction)
    lines = ["%d rest buttons, mu_B %s; W = m g + down clamps = %.6g N at the centre of pressure "
             "%s" % (len(member["points"]), _fmt(mu), s["weight"],
                     _fmt_point(obj.CentreOfPressure))]
    for i, (lo, hi) in enumerate(zip(s["min"], s["max"])):
        lines.append("%s at %s" % (_load_words(i, lo, hi, mu),
                                   _fmt_point(shape.to_3d(member["points"][i]))))
    if not s["inside"]:
        lines.append("no distribution over the buttons balances W within rounding: the centre "
                     "of pressure is on their polygon's edge")
    obj.SupportsReport = lines
    for line in lines:
        FreeCAD.Console.PrintMessage("Wrench: %s\n" % line)


def clear_loads(obj, reason=""):
    """No loads: no buttons, or wrenchd refused them (`reason`, its words,
    which the fixture's WrenchSupports show too: FreeCAD does not recompute
    the objects of a fixture that failed)."""
    obj.SupportWeight = 0.0
    obj.NormalLoads = obj.NormalLoadsMin = obj.NormalLoadsMax = []
    obj.SupportsReport = ["refused: %s" % reason] if reason else []
    if reason:
        for view in supports_of(obj):
            view.Shape = Part.Shape()
            view.LoadLabels, view.LabelPoints = [], []
            view.Report = list(obj.SupportsReport)
            view.Label = "Rest buttons: refused (see the report)"


# ---- picking ----------------------------------------------------------------------

def support_at(fixture, point):
    """The document point of a rest button (or a down clamp) picked at
    `point`: taken into the fixture's face plane along its normal (a hole's
    centre on the other side of the part, a vertex below it).  The face's
    own outline: buttons are picked one at a time, and the fixture is
    refused until there are three."""
    shape = fixture.Proxy.outline(fixture)
    x, y, _ = shape.to_2d(point)
    return shape.to_3d((x, y))


def add_supports(fixture, points, down=None):
    """Rest buttons at the document points (taken into the face's plane),
    added to the fixture's; with `down` a force in N, down clamps there
    instead.  Recomputes the document; returns the points added."""
    added = [support_at(fixture, p) for p in points]
    if down is None:
        fixture.SupportPoints = list(fixture.SupportPoints) + added
    else:
        fixture.DownPoints = list(fixture.DownPoints) + added
        fixture.DownForces = list(fixture.DownForces) + [float(down)] * len(added)
    fixture.Document.recompute()
    return added


# ---- the view object ----------------------------------------------------------------

def _arrow(tip, direction, length, width):
    """A solid arrow ending at `tip`, pointing along unit `direction`."""
    head = min(0.35 * length, 3 * width)
    shaft = Part.makeCylinder(width / 2, length - head, tip - direction * length, direction)
    cone = Part.makeCone(width * 1.2, 0.0, head, tip - direction * head, direction)
    return shaft.fuse(cone)


class WrenchSupports(_Dependent):
    """The rest buttons of the fixture, with their normal loads: rings in
    the face's plane, the loads as arrows leaving it, the down clamps as
    arrows pressing onto it (see the module's docstring)."""

    def setup(self, obj):
        _Dependent.setup(self, obj)
        _add(obj, "App::PropertyLength", "ArrowLength", "Rest buttons",
                "The largest load's arrow (0: 15 % of the part's size)", 0.0)
        for kind, name, doc in (
                ("App::PropertyStringList", "LoadLabels",
                 "What the 3-D view writes beside each button and clamp"),
                ("App::PropertyVectorList", "LabelPoints", "Where (document)"),
                ("App::PropertyStringList", "Report", "The loads, as in the report view")):
            _add(obj, kind, name, "Rest buttons", doc, mode=1)

    def execute(self, obj):
        try:
            self._execute(obj)
        except (OutlineError, WrenchError) as error:
            obj.Shape = Part.Shape()
            fixture = obj.Fixture
            obj.Report = list(getattr(fixture, "SupportsReport", [])) or [str(error)]
            obj.LoadLabels, obj.LabelPoints = [], []
            _report_error(obj, error)

    def _execute(self, obj):
        fixture_obj = obj.Fixture
        if fixture_obj is not None and fixture_obj.SupportsReport \
                and fixture_obj.SupportsReport[0].startswith("refused: "):
            raise WrenchError("%s: %s" % (obj.Label, fixture_obj.SupportsReport[0]))
        fixture = _Fixture(fixture_obj, obj.Label)
        outline = fixture.outline
        if not has_supports(fixture_obj) or not fixture.has_fixels:
            obj.Shape = Part.Shape()
            obj.Report, obj.LoadLabels, obj.LabelPoints = [], [], []
            obj.Label = "Rest buttons (%s)" % ("none: the part floats" if not
                                               has_supports(fixture_obj) else "no fixels yet")
            return
        member = fixture.fixture["supports"]
        lo, hi = list(fixture_obj.NormalLoadsMin), list(fixture_obj.NormalLoadsMax)
        downs = member.get("down", [])
        largest = max(hi + [d["force"] for d in downs] + [0.0])
        length = float(obj.ArrowLength) or 0.15 * outline.size
        width = 0.012 * outline.size
        up = outline.normal
        parts, labels, where = [], [], []
        for i, p in enumerate(member["points"]):
            at = outline.to_3d(p)
            parts.append(Part.makeCircle(1.5 * width, at, up))
            reach = max(length * hi[i] / largest, 2 * width) if largest > 0 else 2 * width
            if hi[i] > 0:
                parts.append(_arrow(at + up * reach, up, reach, width))
            labels.append("N%d %s N" % (i + 1, "%.4g" % hi[i] if abs(hi[i] - lo[i]) <=
                                        1e-9 * max(hi[i], 1.0) else "%.4g..%.4g" % (lo[i], hi[i])))
            where.append(at + up * reach)
        for k, d in enumerate(downs):
            at = outline.to_3d(d["at"])
            reach = max(length * d["force"] / largest, 2 * width) if largest > 0 else 2 * width
            if d["force"] > 0:
                parts.append(_arrow(at, up * -1, reach, width))
            labels.append("D%d %.4g N" % (k + 1, d["force"]))
            where.append(at + up * reach)
        obj.Shape = Part.Compound(parts)
        obj.LoadLabels, obj.LabelPoints = labels, where
        obj.Report = list(fixture_obj.SupportsReport)
        obj.Label = "Rest buttons: %d, W %.4g N" % (len(member["points"]),
                                                    fixture_obj.SupportWeight)


def make_supports(fixture):
    """A WrenchSupports of the fixture (its rest buttons and their loads)."""
    doc = fixture.Document
    obj = doc.addObject("Part::FeaturePython", "WrenchSupports")
    WrenchSupports(obj)
    obj.Fixture = fixture
    obj.Label = "Rest buttons"
    _attach_view(obj)
    return obj


def supports_of(fixture):
    """The fixture's WrenchSupports objects."""
    return [o for o in fixture.InList if _is(o, "WrenchSupports")]
