"""wrench_freecad -- wrenchd in FreeCAD: the outline of a planar face as
wrenchd's `shape`, and the document objects of the Wrench workbench.  The
workbench's one import (the commands' and the tests'); its parts live in

    wrench_outline.py   the outline: a face's lines and arcs, curves by arcs
    wrench_objects.py   the document objects, and how they ask wrenchd
    wrench_view.py      how they look: colours, widths, icons, view provider
    wrench_supports.py  rest buttons under the part: their loads, their object

and the arithmetic of a segment (bulges, arcs, biarcs) is the DXF reader's
too (clients/python/wrenchd_arcs.py).  Documents saved with the objects name
their classes here, so they are found here.

Nothing here needs the GUI: FreeCAD and Part only at module level (FreeCADGui
is imported inside the view providers and the commands), so that freecadcmd
runs all of it.

What each part offers is said once, in its own module's docstring:
`outline(face, tolerance=None)` and the 2-D frame in wrench_outline.py;
`make_fixture`, `make_regions`, `show_regions`, `design`, what each set
promises (what to push with and let go is `both`) and the errors raised
(OutlineError, WrenchError) in wrench_objects.py.
"""

# wrench_outline first: it puts wrenchd.py on the path.
from wrench_outline import (  # noqa: F401
    DEFAULT_RELATIVE_TOLERANCE, MAX_VERTICES, ON_OUTLINE, Outline, OutlineError, Segment,
    _fmt, _fmt_point, outline, wrenchd_arcs)
from wrench_view import (  # noqa: F401
    ARROW_COLOUR, COLOURS, ICONS, LINE_WIDTHS, SUPPORT_COLOUR, ViewProviderWrench,
    colour_least_force, icon, least_force_colours)
from wrench_objects import (  # noqa: F401
    DESIGN_OBJECTIVES, GRAVITY_MEANING, MEANING, SETS, SHORT_MEANING, UNIT, UNITS, WrenchBestPush, WrenchError,
    WrenchFixels, WrenchFixture, WrenchGravityDial, WrenchLeastForce, WrenchLocating,
    WrenchRegion, WrenchRegions, _Fixture, _is, _object_of_face, _proxy_name, client_for,
    describe_push_on, design, fixel_at, load_cases, locating_lines, make_best_push,
    make_fixels, make_fixture, make_gravity_dial, make_least_force, make_locating,
    make_regions, push_on_of, pushed_loops, region_objects, show_regions, socket_path,
    sync_regions, wrenchd)
from wrench_supports import (  # noqa: F401
    DOWN_FORCE, WrenchSupports, add_supports, make_supports, normal_loads, support_at, supports_of)

__all__ = [
    "outline", "Outline", "Segment", "OutlineError", "WrenchError",
    "make_fixture", "make_regions", "make_fixels", "make_best_push", "make_gravity_dial",
    "make_supports", "add_supports", "support_at", "normal_loads",
    "show_regions", "region_objects", "design", "fixel_at", "client_for",
    "SETS", "MEANING", "COLOURS", "DEFAULT_RELATIVE_TOLERANCE",
]
