"""stability.margin on a base plate (docs/PROTOCOL.md, `stability.margin`;
docs/MODEL.md section 11, "The disturbance margin"): the distance from
the bias to the wrenches that move the seated part, with its bracket.

Closed forms derived here by the power argument (tests/unit/lib/
test_support_margin.c writes them out in full): the disc in the corner
with frictionless walls on three buttons, pressed into the corner, moves
first by turning, at 0.2 sqrt(2) mu_B W; the 3-2-1 plate with frictionless
fixels, pressed down by P and cut along +x by F_c, moves first along +x,
at mu_B W - F_c (and past it is mu_B W - F_c < 0 deep)."""

import json
import math
import os
import subprocess

import pytest

import fixtures as FX
from conftest import REPO

from test_supports import BUTTONS, G, on_buttons

PLATE_BUTTONS = [[1, 0.5], [3, 0.5], [2, 1.7]]


def plate(scale=1.0):
    """The 3-2-1 plate, m = 2, frictionless fixels, lengths times scale."""
    f = FX.rectangle_321(0, width=4.0 * scale, height=2.0 * scale)
    f["body"]["mass"] = 2.0
    return f


def check_shape(r):
    assert set(r) == {"margin", "blocking", "worst_direction", "bracket", "converged"}, r
    lo, hi = r["bracket"]
    assert lo <= hi and r["margin"] == lo
    assert isinstance(r["blocking"], str) and len(r["worst_direction"]) == 3


def test_disc_turns_first(client):
    mu_b = 0.3
    f = on_buttons(FX.disc_corner(0), BUTTONS, mu_b)
    expected = 0.2 * math.sqrt(2) * mu_b * G
    for push in (1, 5):
        r = client.result("stability.margin", {"fixture": f, "bias": [-push, -push, 0]})
        check_shape(r)
        assert r["converged"], r
        lo, hi = r["bracket"]
        assert lo <= expected * (1 + 1e-9) and hi >= expected * (1 - 1e-9), r
        assert abs(r["margin"] - expected) < 1e-6 * expected, r
        # Along the torque axis: (0, 0, +-rho) has unit scaled length.
        wx, wy, wt = r["worst_direction"]
        assert abs(wx) < 1e-4 and abs(wy) < 1e-4 and abs(abs(wt) - math.sqrt(0.5)) < 1e-4, r


@pytest.mark.parametrize("cutting", [0, 3, 12])
def test_plate_against_a_cutting_force(client, cutting):
    mu_b, clamp, press = 0.2, 20.0, 20.0
    f = on_buttons(plate(), PLATE_BUTTONS, mu_b, down=[{"at": [2, 1], "force": clamp}])
    expected = mu_b * (2 * G + clamp) - cutting
    r = client.result("stability.margin", {"fixture": f, "bias": [cutting, -press, 0]})
    check_shape(r)
    assert r["converged"], r
    lo, hi = r["bracket"]
    assert lo <= expected + 1e-9 and hi >= expected - 1e-9, r
    assert abs(r["margin"] - expected) < 1e-6 * abs(expected), r
    wx, wy, wt = r["worst_direction"]
    assert abs(wx - math.copysign(1, expected)) < 1e-4 and abs(wy) < 1e-4 and abs(wt) < 1e-4, r


def test_pull_without_a_clamp_bracketed(client):
    """examples/plate-3-2-1-buttons.json (fixel friction 0.3, mu_B = 0.15,
    W = m g = 19.62) pulled along +x by F = 10 through the centre of mass:
    it slides off fixel 3. Every (F', 0, 0) with F' < mu_B W is held (a
    motion needs F' a_x >= mu_B W |a|, the power argument), so a change of
    F - mu_B W = 7.057 along -x holds it: the margin. Nothing presses the
    plate onto fixels 1 and 2, so the bias lies where sliding on them and
    lifting off meet, and the depth is not proved above 0: the bracket
    says so and is not converged."""
    with open(os.path.join(REPO, "examples", "plate-3-2-1-buttons.json")) as fh:
        f = json.load(fh)
    r = client.result("stability.margin", {"fixture": f, "bias": [10, 0, 0]})
    check_shape(r)
    expected = -(10 - 0.15 * 2 * G)
    assert abs(r["margin"] - expected) < 1e-6 * abs(expected), r
    assert r["bracket"][0] == r["margin"] and -1e-9 <= -r["bracket"][1] < abs(expected), r
    assert r["converged"] is False, r
    wx, wy, wt = r["worst_direction"]
    assert abs(wx + 1) < 1e-6 and abs(wy) < 1e-6 and abs(wt) < 1e-6, r


def test_units_millimetres_and_newtons(client):
    """The same plate in millimetres (g = 9810 mm/s^2), the clamps and the
    bias in N, its torque in N mm: the same margin in N; in mN, 1000 times
    it."""
    mu_b, clamp = 0.2, 20.0
    f = plate(1000.0)
    f["units"] = {"length": "mm", "force": "N"}
    f = on_buttons(f, [[1000 * x, 1000 * y] for x, y in PLATE_BUTTONS], mu_b, g=9810,
                   down=[{"at": [2000, 1000], "force": clamp}])
    expected = mu_b * (2 * G + clamp) - 3
    r = client.result("stability.margin", {"fixture": f, "bias": [3, -20, 0]})
    check_shape(r)
    assert abs(r["margin"] - expected) < 1e-6 * expected, r
    # The same in mN: the answer in mN.
    f["units"]["force"] = "mN"
    f["supports"]["down"][0]["force"] = clamp * 1000
    r = client.result("stability.margin", {"fixture": f, "bias": [3000, -20000, 0]})
    assert abs(r["margin"] - expected * 1000) < 1e-6 * expected * 1000, r


def test_pinned_part_has_no_margin(client):
    """A plate held on all four sides by frictionless fixels, two under
    it, one on each other side: no moving mode (floating, the margin is
    null too), so nothing moves it."""
    f = plate()
    f["fixels"] += [{"at": [4, 1.5]}, {"at": [2, 2]}]
    floating = client.result("stability.margin", {"fixture": f, "bias": [1, 0, 0]})
    assert floating["margin"] is None, floating
    r = client.result("stability.margin", {"fixture": on_buttons(f, PLATE_BUTTONS, 0.2),
                                           "bias": [1, 0, 0]})
    assert r == {"margin": None, "blocking": None, "worst_direction": None,
                 "bracket": None}, r


@pytest.mark.parametrize("params,field", [
    ({}, "params.bias"),
    ({"bias": [1, 2]}, "params.bias"),
    ({"bias": "down"}, "params.bias"),
])
def test_bad_bias_names_the_field(client, params, field):
    f = on_buttons(FX.disc_corner(0.5), BUTTONS, 0.3)
    e = client.error("stability.margin", dict(params, fixture=f))
    assert e["code"] == -32602 and e["data"]["field"] == field, e


def test_python_client_and_wrenchctl(daemon, client, tmp_path):
    import sys
    sys.path.insert(0, os.path.join(REPO, "clients", "python"))
    import wrenchd
    mu_b = 0.2
    f = on_buttons(plate(), PLATE_BUTTONS, mu_b, down=[{"at": [2, 1], "force": 20.0}])
    expected = mu_b * (2 * G + 20) - 3
    with wrenchd.Client(daemon.path, timeout=60) as c:
        d = c.stability_margin(f, [3, -20, 0])
        assert abs(d.margin - expected) < 1e-6 * expected and d.converged
        assert d.bracket[0] == d.margin and d.bracket[1] >= d.margin
    # wrenchctl margin with --supports: the margin and its bracket.
    part, rest = tmp_path / "plate.json", tmp_path / "rest.json"
    part.write_text(json.dumps(plate()))
    rest.write_text(json.dumps(f["supports"]))
    out = subprocess.run([os.path.join(REPO, "build", "wrenchctl"), "margin", str(part),
                          "3,-20,0", "--supports", str(rest)], capture_output=True, text=True,
                         env=dict(os.environ, WRENCHD_SOCKET=daemon.path), timeout=120)
    assert out.returncode == 0, out.stderr
    lines = {line.split()[0]: line.split()[1:] for line in out.stdout.splitlines()}
    assert abs(float(lines["margin"][0]) - expected) < 1e-6 * expected, out.stdout
    assert abs(float(lines["bracket"][1]) - expected) < 1e-6 * expected, out.stdout
    assert "(converged)" in out.stdout, out.stdout
