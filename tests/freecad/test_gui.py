"""The workbench in FreeCAD's GUI under Xvfb (gui_smoke.py): activated from
the checkout, its commands run on a bracket, a screenshot taken and read
back here: the right size, and the colours of the regions, the best push
and the locators in it."""

import json
import os
import shutil
import subprocess

import numpy
import pytest

import parts
import wrench_freecad as wf

HERE = os.path.dirname(os.path.abspath(__file__))
WORKBENCH = os.path.abspath(os.path.join(HERE, "..", "..", "clients", "freecad"))


USER_CFG = """<?xml version="1.0" encoding="UTF-8" standalone="no" ?>
<FCParameters>
  <FCParamGroup Name="Root">
    <FCParamGroup Name="BaseApp">
      <FCParamGroup Name="Preferences">
        <FCParamGroup Name="General">
          <FCText Name="AutoloadModule">WrenchWorkbench</FCText>
        </FCParamGroup>
      </FCParamGroup>
    </FCParamGroup>
  </FCParamGroup>
</FCParameters>
"""


def read_png(path):
    """(width, height, pixels: an array of rows of (r, g, b)) of a PNG, read
    by Qt."""
    from PySide2 import QtGui
    image = QtGui.QImage(str(path))
    assert not image.isNull(), "%s is not an image Qt reads" % path
    image = image.convertToFormat(QtGui.QImage.Format_RGB888)
    data = numpy.frombuffer(bytes(image.constBits())[:image.sizeInBytes()], dtype=numpy.uint8)
    rows = data.reshape(image.height(), image.bytesPerLine())[:, :image.width() * 3]
    return image.width(), image.height(), rows.reshape(image.height(), image.width(), 3)


def count_near(pixels, colour, within=60):
    """How many pixels lie within `within` (of 255 per channel) of colour."""
    target = numpy.array([round(255 * c) for c in colour], dtype=float)
    distance = numpy.sqrt(((pixels.astype(float) - target) ** 2).sum(axis=2))
    return int((distance <= within).sum())


def test_the_workbench_in_freecad_gui(daemon, tmp_path):
    xvfb = shutil.which("xvfb-run")
    freecad = shutil.which("freecad")
    assert xvfb, "xvfb-run is missing: make deps-freecad installs xvfb"
    assert freecad, "the FreeCAD GUI (freecad) is missing: make deps-freecad"
    # A home of its own, whose FreeCAD starts in the Wrench workbench (not
    # on the start page, a web view)
    config = tmp_path / "home" / ".config" / "FreeCAD"
    config.mkdir(parents=True)
    (config / "user.cfg").write_text(USER_CFG)
    env = dict(os.environ, HOME=str(tmp_path / "home"), WRENCHD_SOCKET=daemon.socket,
               WRENCH_GUI_OUT=str(tmp_path), WRENCH_GUI_SCRIPT=os.path.join(HERE, "gui_smoke.py"),
               QTWEBENGINE_DISABLE_SANDBOX="1")
    # FreeCAD 0.20 takes -M (a module directory: the checkout's workbench)
    # after the file only.
    proc = subprocess.run([xvfb, "-a", "-s", "-screen 0 1600x1000x24", freecad,
                           os.path.join(HERE, "gui_smoke.py"), "-M", WORKBENCH],
                          env=env, stdin=subprocess.DEVNULL, capture_output=True, timeout=180)
    output = proc.stdout.decode(errors="replace") + proc.stderr.decode(errors="replace")
    assert proc.returncode == 0, output[-4000:]
    with open(tmp_path / "result.json") as f:
        result = json.load(f)
    assert result["errors"] == [], result["errors"][0] + output[-2000:]

    assert result["started_in"] == result["workbench"] == "WrenchWorkbench"
    assert set(result["commands"]) >= {"Wrench_Fixture", "Wrench_AddFixels", "Wrench_ClearFixels",
                                       "Wrench_Regions", "Wrench_GravityDial", "Wrench_Design",
                                       "Wrench_RestButtons", "Wrench_DownClamps",
                                       "Wrench_ClearRestButtons", "Wrench_LeastForce"}
    for o in result["objects"]:
        assert o["state"] == ["Up-to-date"], o
        if o["type"].startswith("Wrench"):
            assert o["view"] == "ViewProviderWrench", o
    assert result["fixtures"] == 1 and len(result["fixels"]) == 3
    # Add fixels put them on the edges picked (a pick is a little off), and
    # at the vertex where the bottom meets a fillet, no corner: no normal
    assert numpy.allclose(result["picked"], [[50, 0, 1], [0, 40, 1], [112, 0, 1]], rtol=0, atol=1e-9)
    assert result["picked_normals"] == [[0, 0, 0]] * 3
    assert result["picked_state"] == ["Up-to-date"] and result["cleared"] == 0
    regions = result["regions"]
    assert set(regions) == set(wf.SETS)
    for which, r in regions.items():
        assert r["colour"] == pytest.approx(wf.COLOURS[which], abs=1e-6)
        assert r["width"] == wf.LINE_WIDTHS[which]
    assert regions["both"]["count"] > 0 and result["best_push"]["found"]
    # each set's regions are its children in the tree
    tree = {label.split(":")[0]: children for label, children in result["tree"]}
    for which in wf.SETS:
        assert tree["Regions " + which] == regions[which]["count"]
    # the report view: the design ranked, what to push with said
    report = "\n".join(result["report"])
    # the README's bracket, designed as wrenchctl designs it there
    assert "Wrench: 3 fixels from 44 sites 10 mm apart, 13244 candidates" in report
    assert "ranked by the margin of the best push in both" in report
    assert "; lengths in mm" in report                     # the report names the unit
    assert "Wrench: 1. score 0.359737: fixels at (114.347, 0.352035, 1) (120, 8, 1) (27, 24.8038, 1)" \
        in report
    assert "it lies in both, which seats the part from any contact state and then holds it still" \
        in report
    assert "both: a push here seats the part from any contact state and then holds it still: " \
           "push here and let go" in report
    assert "to push and let go, use both" in report
    # where the regions were looked for: the bracket's hole and slot left out
    # by the clients' default for a point finger, and how to take them
    assert "Wrench: regions both pushes on the outer boundary; not on holes 1, 2 (a point " \
           "finger has no size to compare with a hole's: set FingerRadius, or PushOn to all)" \
        in report

    # mistakes, in the report view: the fixel named, and how to start wrenchd
    mistakes = "\n".join(result["mistakes"])
    assert "Wrench: Fixture of Bracket: wrenchd refused fixel 1 (FixelPoints[0] = " in mistakes
    assert "is not on the workpiece boundary: 0.5 away from it" in mistakes
    assert "wrenchd is not reachable at %s" % (tmp_path / "nobody.sock") in mistakes
    assert "Start one: `wrenchd --socket %s`" % (tmp_path / "nobody.sock") in mistakes
    assert result["after_mistakes"] == []

    # rest buttons picked: a fillet's centre and a vertex under the part, a
    # point on its face, all in the face's plane; their loads are the
    # barycentric ones of FreeCAD's centre of mass of the face (the default
    # Mass, 1 kg, under 9810 mm/s^2), written in the 3-D view
    want = [[8, 52, 1], [90, 50, 1], [112, 0, 1]]
    order = sorted(range(3), key=lambda i: result["buttons"][i])
    assert len(result["button_loads"]) == 3, result["button_report"][:2]
    assert numpy.allclose([result["buttons"][i] for i in order], want, rtol=0, atol=1e-9)
    com = parts.bracket_face().CenterOfMass
    loads = {tuple(want[k]): result["button_loads"][i] for k, i in enumerate(order)}
    (a, b, c) = [p[:2] for p in want]

    def area2(p, q, r):
        return (q[0] - p[0]) * (r[1] - p[1]) - (q[1] - p[1]) * (r[0] - p[0])
    whole, here = area2(a, b, c), (com.x, com.y)
    for p, lam in ((a, area2(here, b, c) / whole), (b, area2(a, here, c) / whole),
                   (c, area2(a, b, here) / whole)):
        assert loads[tuple(p) + (1,)] == pytest.approx(9.81 * lam, rel=1e-9)
    assert result["button_state"] == [["Up-to-date"]]
    # a down clamp at (60, 30): 100 N more, the loads still balancing it
    assert result["clamps"] == [[60, 30, 1]] and result["clamp_forces"] == [100.0]
    assert sum(result["clamp_loads"]) == pytest.approx(109.81, rel=1e-12)
    assert sum(n * p[0] for n, p in zip(result["clamp_loads"], result["buttons"])) == \
        pytest.approx(9.81 * com.x + 100 * 60, rel=1e-9)
    assert result["clamp_texts"] == result["clamp_labels"] and result["clamp_labels"][-1] == \
        "D1 100 N"
    assert result["button_texts"] == result["button_labels"][0] and \
        len(result["button_texts"]) == 3

    # Push regions on the buttons: the regions ask for a force, the best push
    # says it is the floating part's and how hard it must be on the buttons
    assert result["regions_on_buttons_labels"] == [
        "Regions %s (on rest buttons: set PushForce, N)" % s for s in ("both", "goal", "strong")]
    said = "\n".join(result["regions_on_buttons"])
    assert "Wrench: Best push (both, floating): margin " in said
    assert "; on the rest buttons at least " in said and " N to seat it: both for the part " \
        "floating" in said
    # (on the bracket's arcs and holes wrenchd finds no least push on buttons)
    assert "the least push on them anywhere is Least force's to find (on a face of straight " \
        "lines alone)" in said

    # the buttons' picture: their arrows drawn
    width, height, rows = read_png(tmp_path / "buttons.png")
    assert (width, height) == (1200, 800)
    assert count_near(rows, wf.SUPPORT_COLOUR, 40) > 500

    # the 3-D view from the top: its size, and what is drawn in it
    width, height, rows = read_png(tmp_path / "view.png")
    assert (width, height) == (1200, 800)
    colours = {tuple(p) for p in rows[::4, ::4].reshape(-1, 3)}
    assert len(colours) > 20, "a blank picture"
    assert count_near(rows, wf.COLOURS["both"]) > 50
    assert count_near(rows, wf.COLOURS["strong"]) > 500
    assert count_near(rows, (0.85, 0.0, 0.55)) > 200          # the best push's arrow
    assert count_near(rows, (0.25, 0.25, 0.28), 40) > 50      # the locator pins
    width, height, rows = read_png(tmp_path / "window.png")
    assert width >= 1200 and height >= 800
    assert count_near(rows, wf.COLOURS["both"]) > 50
    # make freecad-picture keeps it
    keep = os.environ.get("WRENCH_PICTURE")
    if keep:
        shutil.copyfile(tmp_path / "window.png", keep)
    keep = os.environ.get("WRENCH_PICTURE_BUTTONS")
    if keep:
        shutil.copyfile(tmp_path / "buttons.png", keep)
