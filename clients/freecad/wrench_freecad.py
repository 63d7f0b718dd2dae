"""wrench_freecad -- wrenchd in FreeCAD: the outline of a planar face as
wrenchd's `shape`, and the document objects of the Wrench workbench.  The
workbench's one import (the commands' and the tests'); its parts live in

    wrench_outline.py   the outline: a face's lines and arcs, curves by arcs
    wrench_objects.py   the document objects, and how they ask wrenchd
    wrench_view.py      how they look: colours, widths, icons, view provider

and the arithmetic of a segment (bulges, arcs, biarcs) is the DXF reader's
too (clients/python/wrenchd_arcs.py).  Documents saved with the objects name
their classes here, so they are found here.

Nothing here needs the GUI: FreeCAD and Part only at module level (FreeCADGui
is imported inside the view providers and the commands), so that freecadcmd
runs all of it.

The outline
-----------

    shape = outline(face, tolerance=None)

is wrenchd's `{"type": "outline", "loops": [...]}` (docs/PROTOCOL.md) for a
planar face: its outer wire first, then its holes, each a loop of vertices
`[x, y]` or `[x, y, bulge]`.  Lines and circular arcs are exact (an arc of
more than half a turn, and a full circle, is written as equal arcs of at
most half a turn).  Every other curve -- B-spline, ellipse, Bezier, offset
curve ... -- is replaced by arcs that meet tangentially (biarcs), no farther
from it than `tolerance` (default: 1e-5 of the face's bounding-box
diagonal, 1 micrometre on a part 100 mm across); runs of them that are
straight, or on one circle, become one line or one arc.  The distance is
measured both ways, from points of the curve to the arcs and from points of
the arcs to the curve, and the largest found is `shape.deviation`.

The 2-D frame: a face in a plane z = const (its normal along +Z or -Z) is
written in the document's x and y.  A face in any other plane is written in
the plane's own frame: origin at the plane's Position, x along the plane's
first parameter direction (u), y = normal x (x), the normal being the
plane's axis.  A sketch out of the XY plane is written in its own
coordinates.  `shape.frame` is that frame as a Placement: the outline's
point (x, y) is `shape.frame.multVec(Vector(x, y, 0))` in the document.

`shape` is a dict (json.dumps writes it as wrenchd wants) that also knows
`frame`, `tolerance`, `deviation`, `size` (the bounding-box diagonal),
`segments` (per loop, one Segment per wrenchd segment: its geometry and the
FreeCAD edge it comes from) and `approximated` (the edges replaced by arcs).

The document objects
--------------------

    fixture = make_fixture(doc, (part, "Face6"), fixels=[...], friction=0.3)
    regions = make_regions(fixture, "both")
    doc.recompute()

A WrenchFixture links a face (or a sketch, or a shape of one planar face),
holds the fixels, the friction, the mass and the daemon's socket, and puts
the fixture in wrenchd; WrenchRegions (one per set: goal, strong, both),
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

# wrench_outline first: it puts wrenchd.py on the path.
from wrench_outline import (  # noqa: F401
    DEFAULT_RELATIVE_TOLERANCE, MAX_VERTICES, ON_OUTLINE, Outline, OutlineError, Segment,
    _fmt, _fmt_point, outline, wrenchd_arcs)
from wrench_view import (  # noqa: F401
    COLOURS, ICONS, LINE_WIDTHS, ViewProviderWrench, colour_least_force, icon,
    least_force_colours)
from wrench_objects import (  # noqa: F401
    DESIGN_OBJECTIVES, GRAVITY_MEANING, MEANING, SETS, SHORT_MEANING, UNIT, UNITS, WrenchBestPush, WrenchError,
    WrenchFixels, WrenchFixture, WrenchGravityDial, WrenchLeastForce, WrenchLocating,
    WrenchRegion, WrenchRegions, _Fixture, _is, _object_of_face, _proxy_name, client_for,
    describe_push_on, design, fixel_at, load_cases, locating_lines, make_best_push,
    make_fixels, make_fixture, make_gravity_dial, make_least_force, make_locating,
    make_regions, push_on_of, pushed_loops, region_objects, show_regions, socket_path,
    sync_regions, wrenchd)

__all__ = [
    "outline", "Outline", "Segment", "OutlineError", "WrenchError",
    "make_fixture", "make_regions", "make_fixels", "make_best_push", "make_gravity_dial",
    "show_regions", "region_objects", "design", "fixel_at", "client_for",
    "SETS", "MEANING", "COLOURS", "DEFAULT_RELATIVE_TOLERANCE",
]
