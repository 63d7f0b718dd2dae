"""wrenchctl's pictures (--svg): well-formed XML, one region path per region
of the answer, and the part drawn (outline, fixels, friction cones, centre
of mass).  The README's pictures in docs/ are what wrenchctl draws now."""

import json
import os
import subprocess
import xml.dom.minidom

import pytest

from conftest import REPO

WRENCHCTL = os.path.join(REPO, "build", "wrenchctl")
EXAMPLES = os.path.join(REPO, "examples")


def run(*args):
    return subprocess.run([WRENCHCTL, "--local"] + list(args), capture_output=True, text=True,
                          timeout=60)


def elements(path, tag, cls=None):
    document = xml.dom.minidom.parse(path)
    return [e for e in document.getElementsByTagName(tag)
            if cls is None or e.getAttribute("class") == cls]


@pytest.mark.parametrize("name", ["disc-corner", "plate-3-2-1", "plate-chamfered", "outline"])
@pytest.mark.parametrize("set_name", ["goal", "strong", "both"])
def test_push_picture_has_one_path_per_region(harness, name, set_name):
    fixture = os.path.join(EXAMPLES, name + ".json")
    svg = harness.path("%s-%s.svg" % (name, set_name))
    answer = run("push", fixture, "--set", set_name, "--json", "--svg", svg)
    assert answer.returncode in (0, 1), answer.stderr
    regions = json.loads(answer.stdout)["regions"]
    assert answer.returncode == (0 if regions else 1)
    assert len(elements(svg, "path", "region")) == len(regions)
    with open(fixture) as f:
        fixels = len(json.load(f)["fixels"])
    assert len(elements(svg, "polygon", "fixel")) == fixels
    assert len(elements(svg, "polygon", "friction-cone")) == fixels
    assert len(elements(svg, "g", "com")) == 1
    assert len(elements(svg, "polygon", "outline") + elements(svg, "circle", "outline")) == 1


@pytest.mark.parametrize("name", ["disc-corner", "plate-chamfered"])
def test_gravity_dial_and_margin_pictures(harness, name):
    fixture = os.path.join(EXAMPLES, name + ".json")
    dial = harness.path("dial.svg")
    answer = run("gravity", fixture, "--set", "goal", "--json", "--svg", dial)
    arcs = json.loads(answer.stdout)["intervals_deg"]
    assert len(elements(dial, "path", "region")) == len(arcs)
    assert len(elements(dial, "circle", "dial")) == 1
    picture = harness.path("margin.svg")
    answer = run("margin", fixture, "-1,-1,0", "--svg", picture)
    assert answer.returncode in (0, 1), answer.stderr
    assert elements(picture, "line") or elements(picture, "path")
    assert not elements(picture, "path", "region")


def test_bad_svg_path_is_a_usage_error():
    r = run("push", os.path.join(EXAMPLES, "disc-corner.json"), "--svg", "/nonexistent/x.svg")
    assert r.returncode == 2 and "--svg" in r.stderr


@pytest.mark.parametrize("picture,command", [
    ("plate-3-2-1-push-strong.svg", ["push", "plate-3-2-1.json", "--set", "strong"]),
    ("plate-chamfered-push-both.svg", ["push", "plate-chamfered.json", "--set", "both"]),
    ("disc-corner-push-goal.svg", ["push", "disc-corner.json", "--set", "goal"]),
])
def test_readme_pictures_are_current(harness, picture, command):
    """docs/pictures/ holds what wrenchctl draws today (make pictures)."""
    fresh = harness.path(picture)
    command = command[:1] + [os.path.join(EXAMPLES, command[1])] + command[2:]
    assert run(*command, "--svg", fresh).returncode in (0, 1)
    with open(fresh) as a, open(os.path.join(REPO, "docs", "pictures", picture)) as b:
        assert a.read() == b.read(), "run 'make pictures' and commit docs/pictures"
