"""friction.sweep over the fixels' mu for a fixture on a base plate
(docs/PROTOCOL.md, friction.sweep; docs/MODEL.md section 11, "Against the
fixels' mu").

Closed forms derived here: the disc in the corner on three buttons seats a
push F along 225 degrees while F sin(45 deg - atan mu) > mu_B W, and the
3-2-1 plate under a load pulling it off its left fixel is held once its
lower fixels' sliding friction and the buttons' together outweigh the pull.
Every interval is checked against wrench.classify at many mu in and around
it, the force curve against push.force at the same mu."""

import copy
import json
import math
import os

import fixtures as FX
from conftest import REPO
from helpers import run_client_program

G = 9.81
R2 = math.sqrt(2)
BUTTONS = [[0, 0.2], [-0.17320508075688773, -0.1], [0.17320508075688773, -0.1]]
PLATE_BUTTONS = [[1, 0.5], [3, 0.5], [2, 1.7]]


def on_buttons(fixture, points, mu_b):
    f = copy.deepcopy(fixture)
    f["supports"] = {"points": points, "friction": mu_b, "g": G}
    return f


def with_friction(fixture, mu, ratio=1.0):
    f = copy.deepcopy(fixture)
    f["friction"] = {"static": mu, "kinetic": ratio * mu}
    return f


def plate():
    f = FX.rectangle_321(0.3)
    f["body"]["mass"] = 2.0
    return f


def verdict(client, fixture, wrench, set_name):
    r = client.result("wrench.classify", {"fixture": fixture, "wrenches": [wrench],
                                          "sets": [set_name]})
    return r["results"][0][set_name]["verdict"]


def cross_check(client, fixture, wrench, set_name, intervals, low, high, ratio=1.0, n=12):
    """wrench.classify with that friction on every fixel: inside across
    each interval, not 1e-6 beyond its ends, not across the gaps."""
    checked = 0
    for lo, hi in intervals:
        for k in range(n + 1):
            mu = lo + (hi - lo) * k / n
            assert verdict(client, with_friction(fixture, mu, ratio), wrench, set_name) == "inside", \
                (set_name, mu, intervals)
            checked += 1
        for mu in (lo - 1e-6, hi + 1e-6):
            if low < mu < high:
                assert verdict(client, with_friction(fixture, mu, ratio), wrench,
                               set_name) != "inside", (set_name, mu, intervals)
                checked += 1
    ends = [low] + [x for pair in intervals for x in pair] + [high]
    for start, end in zip(ends[::2], ends[1::2]):
        if end - start > (high - low) / 64:
            for k in range(1, n):
                mu = start + (end - start) * k / n
                assert verdict(client, with_friction(fixture, mu, ratio), wrench,
                               set_name) != "inside", (set_name, mu, intervals)
                checked += 1
    return checked


def test_disc_seating_end_closed_form(client):
    """The disc in the corner on three buttons (mu_B = 0.3, W = m g): every
    excluded goal cone holds the torque axis, so C + S is C grown in the
    force plane by the disc of radius mu_B W. The goal wedge of directions
    is (180 + atan mu, 270 - atan mu) degrees; a force F along 225 degrees
    is F sin(45 deg - atan mu) from its nearer edge, so it seats iff that
    exceeds mu_B W: below mu* = tan(45 deg - asin(mu_B W / F)), 0.5291249
    for F = 10. Held at every mu (pushed into the corner)."""
    mu_b, F = 0.3, 10.0
    f = on_buttons(FX.disc_corner(0.5), BUTTONS, mu_b)
    w = [-F / R2, -F / R2, 0]
    r = client.result("friction.sweep", {"fixture": f, "wrenches": [w],
                                         "sets": ["goal", "strong", "both"]})
    result = r["results"][0]
    expected = math.tan(math.pi / 4 - math.asin(mu_b * G / F))
    (lo, hi), = result["goal"]
    assert lo == 0 and abs(hi - expected) < 1e-8, (result, expected)
    assert result["strong"] == [[0, 2]], result
    assert result["both"] == result["goal"], result
    assert r["exact"] is False and r["resolution"] == 2 / 64
    checked = sum(cross_check(client, f, w, s, result[s], 0, 2, n=8)
                  for s in ("goal", "strong", "both"))
    assert checked > 30
    # Seating alone is exact: no "exact" member.
    goal = client.result("friction.sweep", {"fixture": f, "wrenches": [w], "sets": ["goal"]})
    assert goal == {"results": [{"goal": result["goal"]}]}, goal
    # Too weak to beat the buttons at any mu: F sin 45 deg <= mu_B W.
    weak = [-4 / R2, -4 / R2, 0]
    assert client.result("friction.sweep", {"fixture": f, "wrenches": [weak],
                                            "sets": ["goal"]})["results"][0]["goal"] == []


def test_plate_holding_from_closed_form(client):
    """The 3-2-1 plate (m = 2) on buttons, mu_B = 0.2, W = 2 g, under (8,
    -10, 0) at its centre of mass: pressed onto its lower fixels by 10,
    pulled away from its left fixel by 8. The translation along +x is
    consistent while mu_k 10 + mu_B W < 8, so holding begins at mu_c =
    (8 - 0.2 W) / (10 ratio): 0.4076 at kinetic_ratio 1, 0.8152 at 0.5.
    It never seats (nothing pushes on the left fixel)."""
    f = on_buttons(plate(), PLATE_BUTTONS, 0.2)
    w = [8, -10, 0]
    for ratio in (1.0, 0.5):
        mu_c = (8 - 0.2 * 2 * G) / (10 * ratio)
        r = client.result("friction.sweep", {"fixture": f, "wrenches": [w],
                                             "kinetic_ratio": ratio,
                                             "sets": ["goal", "strong", "both"]})
        result = r["results"][0]
        (lo, hi), = result["strong"]
        assert abs(lo - mu_c) < 1e-7 and hi == 2, (ratio, result)
        assert result["goal"] == [] and result["both"] == []
        cross_check(client, f, w, "strong", result["strong"], 0, 2, ratio)


def test_plate_sets_against_classify(client):
    """Wrenches pushing the plate into its corner with torques either way:
    every set's intervals agree with wrench.classify in and around them,
    seating ends once from the bottom, and both lies within it."""
    f = on_buttons(plate(), PLATE_BUTTONS, 0.05)
    wrenches = [[-3, -10, 0.5], [-10, -10, -4], [2, -10, 3]]
    r = client.result("friction.sweep", {"fixture": f, "wrenches": wrenches,
                                         "sets": ["goal", "strong", "both"],
                                         "range": [0, 1.5], "kinetic_ratio": 0.8})
    assert len(r["results"]) == 3
    for w, result in zip(wrenches, r["results"]):
        for s in ("goal", "strong", "both"):
            cross_check(client, f, w, s, result[s], 0, 1.5, 0.8, n=6)
        assert len(result["goal"]) <= 1 and all(lo == 0 for lo, _ in result["goal"])
        for lo, hi in result["both"]:
            assert hi <= result["goal"][0][1]


def test_least_push_curve_against_push_force(client):
    """"force" over the fixels' mu on the plate: push.force's least push at
    17 coefficients; each sample equals push.force for the fixture with that
    friction, and the curve never falls (each excluded goal cone grown by
    the buttons' friction only grows with mu: docs/MODEL.md section 11)."""
    with open(os.path.join(REPO, "examples", "plate-chamfered.json")) as fh:
        floating = json.load(fh)
    buttons = [[1, 0.5], [3, 0.5], [1.5, 1.6]]
    none = [{"loads": [{"wrench": [0, 0, 0]}]}]
    f = on_buttons(floating, buttons, 0.1)
    # 17 least-push searches, each a branch and bound of LPs.
    client.send(client.request("friction.sweep", {"fixture": f, "force": {}, "cases": none,
                                                  "range": [0, 0.48]}))
    answer = client.read_json(timeout=600)
    assert "result" in answer, answer
    r = answer["result"]
    curve = r["curve"]
    assert len(curve) == 17 and len(r["at"]) == 17 and r["exact"] is False
    assert abs(r["resolution"] - 0.03) < 1e-15
    forces = [force for _, force in curve]
    finite = [x for x in forces if x is not None]
    assert all(b >= a * (1 - 1e-6) for a, b in zip(finite, finite[1:])), forces
    assert forces.index(None) == len(finite), forces  # null only at the top
    for mu, force in (curve[0], curve[6], curve[len(finite) - 1], curve[-1]):
        at_mu = client.result("push.force", {"fixture": with_friction(f, mu), "set": "goal",
                                             "cases": none, "samples": 1})
        got = at_mu["least"]["force"] if at_mu["least"] else None
        if force is None:
            assert got is None, (mu, at_mu)
        else:
            assert abs(got - force) <= 1e-9 * force, (mu, force, at_mu)


def test_tilt_arcs_closed_form(client):
    """"gravity" over the fixels' mu on the plate: the disc in the corner
    on three buttons (mu_B = 0.3) tilted so that its pull is m a, a = 20.
    As for a push, the pull seats iff m a sin(delta) > mu_B m g, delta its
    angle to the nearer edge of the goal wedge (180 + atan mu, 270 - atan
    mu): the arc is (180 + atan mu + delta*, 270 - atan mu - delta*) with
    sin delta* = mu_B g / a, 90 - 2 atan mu - 2 delta* degrees long, gone
    at mu_c = tan(45 deg - delta*) = 0.7409933. Arcs narrower than 1e-6
    degrees at its ends are undecided and not counted (docs/MODEL.md
    section 11), so each length is within 2e-6 degrees and mu_c within
    1e-7 (the arc shrinks by about 70 degrees per unit of mu there)."""
    f = on_buttons(FX.disc_corner(0.5), BUTTONS, 0.3)
    client.send(client.request("friction.sweep", {"fixture": f, "range": [0, 1],
                                                  "gravity": {"in_plane_g": 20}}))
    answer = client.read_json(timeout=600)
    assert "result" in answer, answer
    r = answer["result"]
    delta = math.degrees(math.asin(0.3 * G / 20))
    mu_c = math.tan(math.radians(45 - delta))
    (lo, hi), = r["intervals"]
    assert lo == 0 and abs(hi - mu_c) < 1e-7 and r["critical"] == hi, r
    assert r["exact"] is False and r["resolution"] == 1 / 64
    for mu, length in r["curve"]:
        expected = max(0.0, 90 - 2 * math.degrees(math.atan(mu)) - 2 * delta)
        assert abs(length - expected) < 2e-6 or (mu > mu_c - 1e-7 and length < 2e-6), \
            (mu, length, expected)


def test_push_regions_against_push_regions(client):
    """"push" with a force over the fixels' mu on the plate: each point of
    the curve is push.regions' total_length for the fixture with that
    friction under the same force; the region only shrinks as mu grows (the
    grown goal cones are nested), and at the critical mu it is still there
    while 1e-6 above it push.regions finds none."""
    with open(os.path.join(REPO, "examples", "plate-chamfered.json")) as fh:
        floating = json.load(fh)
    f = on_buttons(floating, [[1, 0.5], [3, 0.5], [1.5, 1.6]], 0.1)
    client.send(client.request("friction.sweep", {"fixture": f, "range": [0, 1],
                                                  "push": {"force": 20}}))
    answer = client.read_json(timeout=600)
    assert "result" in answer, answer
    r = answer["result"]
    (lo, critical), = r["intervals"]
    assert lo == 0 and r["critical"] == critical and 0 < critical < 1, r
    lengths = [length for _, length in r["curve"]]
    assert all(b <= a + 1e-9 for a, b in zip(lengths, lengths[1:])), lengths

    def regions(mu):
        return client.result("push.regions", {"fixture": with_friction(f, mu), "set": "goal",
                                              "force": 20})["total_length"]
    for mu, length in (r["curve"][0], r["curve"][10], r["curve"][-1]):
        assert abs(regions(mu) - length) <= 1e-9 * max(1, length), (mu, length)
    assert regions(critical) > 0 and regions(critical + 1e-6) == 0, critical


def test_deadline_partial(client):
    """Past deadline_s the sweep answers what it has decided: the wrench
    under way cut at stopped_at."""
    f = on_buttons(plate(), PLATE_BUTTONS, 0.2)
    r = client.result("friction.sweep", {"fixture": f, "wrenches": [[8, -10, 0]] * 4,
                                         "sets": ["strong"], "deadline_s": 1e-6})
    assert r["partial"] is True and 0 <= r["stopped_at"] <= 2, r
    assert 1 <= len(r["results"]) <= 4
    for lo, hi in r["results"][-1]["strong"]:
        assert hi <= r["stopped_at"] and lo > 0.4076 - 1e-7


def test_refusals_name_the_field(client):
    f = on_buttons(plate(), PLATE_BUTTONS, 0.2)
    none = [{"loads": [{"wrench": [0, 0, 0]}]}]
    for params, field in (({"push": {}}, "params.push.force"),
                          ({"gravity": {}}, "params.gravity.in_plane_g"),
                          ({"push": {"force": 20, "set": "both"}}, "params.push.set"),
                          ({"force": {"set": "both"}, "cases": none}, "params.force.set"),
                          ({"force": {"finger_radius": 0.1}, "cases": none},
                           "params.force.finger_radius")):
        params = dict(params, fixture=f)
        e = client.error("friction.sweep", params)
        assert e["code"] == -32602 and e["data"]["field"] == field, (params, e)


C_FIXELS_ON_THE_PLATE = r'''
#include "wrenchclient.h"
#include <stdio.h>
int main(int argc, char **argv)
{
    (void)argc;
    wrc_client *c = wrc_connect(argv[1], 300000, 0, NULL);
    const wrc_load none[] = {{.kind = WRC_LOAD_FORCE, .force = {0, 0}, .at = {1, 1}}};
    wrc_force_sweep_request r = {.set = "goal", .range = {0, 0.16}};
    static double curve[32][2], at[32][2];
    wrc_force_curve s;
    if (!c || wrc_force_sweep(c, argv[2], none, 1, &r, curve, at, 32, &s) != WRC_OK)
        return 2;
    printf("%d\n", s.interval_count);
    for (int i = 0; i < s.sample_count; i++)
        printf("%.17g %.17g\n", curve[i][0], curve[i][1]);
    wrc_close(c);
    return 0;
}
'''


def test_c_client_sweeps_the_fixels_on_the_plate(client, tmp_path):
    """wrc_force_sweep over the fixels' mu of a fixture on supports reads
    the answer, which has no intervals of the push alone: the daemon's
    curve, to the last digit."""
    with open(os.path.join(REPO, "examples", "plate-chamfered.json")) as fh:
        floating = json.load(fh)
    f = on_buttons(floating, [[1, 0.5], [3, 0.5], [1.5, 1.6]], 0.1)
    fid = client.result("fixture.put", {"fixture": f})["id"]
    out = run_client_program(tmp_path, "fixels", C_FIXELS_ON_THE_PLATE, client.path, fid,
                             timeout=600)
    assert out.returncode == 0, out
    lines = [line for line in out.stdout.split("\n") if line]
    assert lines[0] == "0"
    none = [{"loads": [{"force": [0, 0], "at": [1, 1]}]}]
    client.send(client.request("friction.sweep", {"fixture": fid, "range": [0, 0.16],
                                                  "force": {"set": "goal"}, "cases": none}))
    sweep = client.read_json(timeout=600)["result"]
    assert "intervals" not in sweep
    rows = [[float(x) for x in line.split()] for line in lines[1:]]
    assert rows == [[mu, force] for mu, force in sweep["curve"]], (rows, sweep["curve"])


def test_wrenchctl_sweeps_the_fixels_on_the_plate(client):
    """wrenchctl sweep of a fixture on supports without --over: the fixels'
    mu, the push region under --force and the wrenches' sets as the daemon
    gives them."""
    import subprocess
    import tempfile
    wrenchctl = os.path.join(REPO, "build", "wrenchctl")
    env = dict(os.environ, WRENCHD_SOCKET=client.path)
    rest = json.dumps({"points": [[1, 0.5], [3, 0.5], [1.5, 1.6]], "friction": 0.1, "g": G})
    with tempfile.TemporaryDirectory() as d:
        part = os.path.join(d, "plate.json")
        with open(os.path.join(REPO, "examples", "plate-chamfered.json")) as fh:
            floating = json.load(fh)
        with open(part, "w") as fh:
            json.dump(floating, fh)
        out = subprocess.run([wrenchctl, "--json", "--timeout", "600", "sweep", part,
                              "--supports", rest, "--push", "goal", "--force", "20",
                              "--range", "0:1"],
                             capture_output=True, text=True, env=env, timeout=600)
        assert out.returncode == 0, out.stderr
        swept = json.loads(out.stdout)
        f = on_buttons(floating, [[1, 0.5], [3, 0.5], [1.5, 1.6]], 0.1)
        client.send(client.request("friction.sweep", {"fixture": f, "range": [0, 1],
                                                      "push": {"force": 20}}))
        want = client.read_json(timeout=600)["result"]
        # wrenchctl --json writes 15 significant digits.
        assert swept["intervals"] == want["intervals"] and swept["exact"] is False
        assert len(swept["curve"]) == len(want["curve"])
        for a, b in zip(swept["curve"], want["curve"]):
            assert a[0] == b[0] and abs(a[1] - b[1]) <= 1e-12, (a, b)
        out = subprocess.run([wrenchctl, "sweep", part, "--supports", rest,
                              "--wrench", "-4,-9,2"],
                             capture_output=True, text=True, env=env, timeout=600)
        assert out.returncode == 0, out.stderr
        assert "mu_s = mu, mu_k = 1 mu at every fixel" in out.stdout, out.stdout
        assert "strong and both sampled: grid step 0.03125" in out.stdout, out.stdout


def test_python_client_reads_the_sampled_sets(client):
    """The Python client's friction_sweep on the plate over the fixels' mu:
    the results, and exact False with the grid's step."""
    import sys
    sys.path.insert(0, os.path.join(REPO, "clients", "python"))
    import wrenchd
    f = on_buttons(plate(), PLATE_BUTTONS, 0.2)
    with wrenchd.Client(client.path, timeout=600) as c:
        swept = c.friction_sweep(f, wrenches=[[8, -10, 0]], sets=["goal", "strong"])
    (lo, hi), = swept.results[0]["strong"]
    assert swept.results[0]["goal"] == [] and abs(lo - 0.4076) < 1e-7 and hi == 2
    assert swept.exact is False and swept.resolution == 2 / 64
