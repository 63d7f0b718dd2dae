"""A part on a base plate: the fixture's "supports" (docs/PROTOCOL.md,
"Supports"; docs/MODEL.md section 11).

Closed forms derived here: the disc in the corner's least push force on
three buttons (the friction capacity mu_B W against the distance of the
push from the edge of the goal wedge), and the 3-2-1 plate's least down
clamp against a cutting force. Bad input refused naming the field; the
questions of directions alone refused saying what to give."""

import copy
import json
import math
import os

import pytest

import fixtures as FX
from conftest import REPO
from helpers import run_client_program

G = 9.81
R2 = math.sqrt(2)
BUTTONS = [[0, 0.2], [-0.17320508075688773, -0.1], [0.17320508075688773, -0.1]]


def on_buttons(fixture, points, mu, g=G, down=None):
    f = copy.deepcopy(fixture)
    f["supports"] = {"points": points, "friction": mu, "g": g}
    if down is not None:
        f["supports"]["down"] = down
    return f


def plate(mass=2.0):
    f = FX.rectangle_321(0.3)
    f["body"]["mass"] = mass
    return f


def error_of(client, method, params):
    e = client.error(method, params)
    assert e["code"] == -32602, e
    return e["data"]["field"], e["data"]["reason"]


def test_id_and_round_trip(client):
    floating = FX.disc_corner(0.5)
    a = client.result("fixture.put", {"fixture": floating})["id"]
    resting = on_buttons(floating, BUTTONS, 0.3)
    b = client.result("fixture.put", {"fixture": resting})["id"]
    assert a != b
    got = client.result("fixture.get", {"id": b})
    s = got["supports"]
    assert s["points"] == BUTTONS and s["g"] == G
    assert s["friction"] == {"static": 0.3, "kinetic": 0.3}
    assert "supports" not in client.result("fixture.get", {"id": a})
    # What get returns puts back to the same id.
    assert client.result("fixture.put", {"fixture": got})["id"] == b


@pytest.mark.parametrize("path,value,field,words", [
    ("points", BUTTONS[:2], "points", "at least 3"),
    ("points", BUTTONS[:2] + [[1.5, 0]], "points[2]", "outside the part"),
    ("friction", -0.1, "friction", "negative"),
    ("g", -1, "g", ">= 0"),
    ("down", [{"at": [3, 0], "force": 1}], "down[0].at", "outside the part"),
    ("down", [{"at": [0, 0], "force": -1}], "down[0].force", ">= 0"),
    # 10 m g at (0, -0.9): the centre of pressure at y = -9/11, 0.718182
    # below the buttons' edge y = -0.1.
    ("down", [{"at": [0, -0.9], "force": 10 * G}], "points", "0.718182"),
])
def test_bad_supports_name_the_field(client, path, value, field, words):
    f = on_buttons(FX.disc_corner(0.5), BUTTONS, 0.3)
    f["supports"][path] = value
    got, reason = error_of(client, "fixture.put", {"fixture": f})
    assert got == "params.fixture.supports." + field, (got, reason)
    assert words in reason, reason


def test_disc_least_push_force(client):
    """Every excluded cone of the disc in the corner (friction 0.5) holds
    the torque axis, so a push through the centre seats when its force is
    farther than mu_B W (the radius of the buttons' force discs' sum) from
    the complement of the goal wedge 206.565..243.435 degrees. A push at
    45 degrees on the rim pushes along 225 degrees, 18.435 degrees inside
    the wedge: F* = mu_B W / sin(18.435 deg) = mu_B W sqrt(10)."""
    mu_b = 0.3
    f = on_buttons(FX.disc_corner(0.5), BUTTONS, mu_b)
    r = client.result("force.range", {"fixture": f, "push": {"at": [1 / R2, 1 / R2]},
                                      "cases": [{"loads": [{"wrench": [0, 0, 0]}]}], "sets": ["goal"]})
    least = r["all"]["goal"]["least"]
    expected = mu_b * G * math.sqrt(10)
    assert abs(least - expected) < 1e-7 * expected, (least, expected)
    floating = client.result("force.range", {"fixture": FX.disc_corner(0.5),
                                             "push": {"at": [1 / R2, 1 / R2]},
                                             "cases": [{"loads": [{"wrench": [0, 0, 0]}]}], "sets": ["goal"]})
    assert floating["all"]["goal"]["least"] == 0


def test_plate_least_clamp_against_cutting_force(client):
    """The 3-2-1 plate (m = 2, centre of mass (2, 1)) on buttons (1, 0.5),
    (3, 0.5), (2, 1.7), mu_B = 0.2, a down clamp D at the centre of mass.
    A cutting force F_c along +x through the centre of mass: any motion
    needs F_c a_x >= mu_B sum N_i |a_i| >= mu_B W |a_com| (power), so it is
    held while F_c < mu_B (m g + D): D* = F_c / mu_B - m g."""
    mu_b, cutting = 0.2, 30.0
    d_star = cutting / mu_b - 2 * G
    verdicts = []
    for factor in (0.999, 1.001):
        f = on_buttons(plate(), [[1, 0.5], [3, 0.5], [2, 1.7]], mu_b,
                       down=[{"at": [2, 1], "force": factor * d_star}])
        r = client.result("wrench.classify", {"fixture": f, "wrenches": [[cutting, 0, 0]],
                                              "sets": ["strong"]})
        verdicts.append(r["results"][0]["strong"]["verdict"])
    assert verdicts == ["outside", "inside"], verdicts


def test_zero_load_held(client):
    f = on_buttons(plate(), [[1, 0.5], [3, 0.5], [2, 1.7]], 0.2)
    r = client.result("wrench.classify", {"fixture": f, "wrenches": [[0, 0, 0]],
                                          "sets": ["strong"]})
    assert r["results"][0]["strong"]["verdict"] == "inside"


@pytest.mark.parametrize("method,params,field", [
    ("force.range", {"push": {"at": [1 / R2, 1 / R2]}, "cases": [{"loads": [{"wrench": [0, 0, 0]}]}]},
     "params.sets"),
    ("push.force", {"cases": [{"loads": [{"wrench": [0, 0, 0]}]}]}, "params.set"),
    ("gravity.sweep", {"set": "goal"}, "params.in_plane_g"),
])
def test_direction_questions_refused(client, method, params, field):
    f = on_buttons(FX.disc_corner(0.5), BUTTONS, 0.3)
    got, reason = error_of(client, method, dict(params, fixture=f))
    assert got == field, (got, reason)
    assert "supports" in reason, reason


def test_python_client_least_force_on_the_plate(daemon):
    """The Python client's on_supports and force_range: the disc's closed
    form again, through the client."""
    import os
    import sys
    from conftest import REPO
    sys.path.insert(0, os.path.join(REPO, "clients", "python"))
    import wrenchd
    with wrenchd.Client(daemon.path, timeout=60) as c:
        f = wrenchd.on_supports(FX.disc_corner(0.5), BUTTONS, 0.3, G)
        r = c.force_range(f, [[{"wrench": [0, 0, 0]}]], push={"at": [1 / R2, 1 / R2]},
                          sets=["goal"])
        expected = 0.3 * G * math.sqrt(10)
        assert abs(r["all"]["goal"]["least"] - expected) < 1e-7 * expected
        # The tilt on the plate: the disc's arc for a pull of 20 (see
        # test_tilt_of_the_disc_on_buttons for its closed form).
        d = math.degrees(math.asin(0.3 * G / 20))
        edge = math.degrees(math.atan(0.5))
        (lo, hi), = c.gravity_sweep(f, "goal", in_plane_g=20)
        assert abs(lo - (180 + edge + d)) < 1e-5 and abs(hi - (270 - edge - d)) < 1e-5
        whole = c.tilt_on_supports(f, 20)
        assert whole["intervals_deg"] == [[lo, hi]] and len(whole["undecided_deg"]) <= 2
        # Over the supports' mu_B: the force of 30 along 225 degrees seats
        # below 30 / (W sqrt 10) (test_friction_sweep_over_the_supports).
        swept = c.friction_sweep(f, over="supports", wrenches=[[-30 / R2, -30 / R2, 0]])
        (a, b), = swept.results[0]["goal"]
        assert a == 0 and abs(b - 30 / (G * math.sqrt(10))) < 1e-8


def test_units_millimetres_and_newtons(client):
    """The disc in millimetres and newtons (g = 9810 mm/s^2, a down clamp in
    N): the same least force in N as in metres, and a clamp of 1 N adds
    mu_B sqrt(10) N to it."""
    mu_b = 0.3
    f = FX.disc_corner_mm()
    mm = [[1000 * x, 1000 * y] for x, y in BUTTONS]
    for down, weight in ((None, G), ([{"at": [0, 0], "force": 1.0}], G + 1)):
        g = on_buttons(f, mm, mu_b, g=9810, down=down)
        r = client.result("force.range", {"fixture": g, "push": {"at": [1000 / R2, 1000 / R2]},
                                          "cases": [{"loads": [{"wrench": [0, 0, 0]}]}],
                                          "sets": ["goal"]})
        expected = mu_b * weight * math.sqrt(10)
        least = r["all"]["goal"]["least"]
        assert abs(least - expected) < 1e-7 * expected, (least, expected)
        # wrench.classify and the sweep over mu_B read wrenches in N too: a
        # force 1% above the least seats, 1% below does not, and it seats
        # for mu_B below 1.01 mu_B.
        verdicts = []
        for k in (0.99, 1.01):
            w = [-k * expected / R2, -k * expected / R2, 0]
            verdicts.append(client.result("wrench.classify", {
                "fixture": g, "wrenches": [w], "sets": ["goal"]})["results"][0]["goal"]["verdict"])
        assert verdicts == ["outside", "inside"], verdicts
        w = [-expected / R2, -expected / R2, 0]
        (_, end), = client.result("friction.sweep", {"fixture": g, "over": "supports",
                                                     "wrenches": [w]})["results"][0]["goal"]
        assert abs(end - mu_b) < 1e-8, end


def test_push_regions_under_a_force_agree_with_force_range(client):
    """The chamfered plate on three buttons: push.regions under a force of
    20 finds the part of the chamfer where a push that hard seats it; just
    inside its end force.range's least force at that point is below 20,
    just outside above. More force, a longer region, tending to the
    floating plate's."""
    with open(os.path.join(REPO, "examples", "plate-chamfered.json")) as fh:
        f = json.load(fh)
    f = on_buttons(f, [[1, 0.5], [3, 0.5], [1.5, 1.6]], 0.1)
    none = [{"loads": [{"wrench": [0, 0, 0]}]}]
    starts = []
    for force in (20, 60, 200):
        r = client.result("push.regions", {"fixture": f, "set": "goal", "force": force,
                                           "cases": none})
        assert len(r["regions"]) == 1, r
        region = r["regions"][0]
        assert region["edge"] == 2 and region["t1"] == 1, region
        starts.append(region["t0"])
    assert starts[0] > starts[1] > starts[2] > 0.525556, starts
    t = starts[0]
    for dt, below in ((1e-4, True), (-1e-4, False)):
        at = [4 - (t + dt), 1 + (t + dt)]  # edge 2 runs from (4, 1) to (3, 2)
        least = client.result("force.range", {"fixture": f, "push": {"at": at}, "cases": none,
                                               "sets": ["goal"]})["all"]["goal"]["least"]
        assert (least is not None and least < 20) == below, (dt, least)
    # On supports the other sets, a finger of some size and no force are refused.
    for extra, field in (({"set": "both", "force": 20, "cases": none}, "params.set"),
                         ({"set": "goal", "force": 20, "cases": none, "finger_radius": 0.1},
                          "params.finger_radius"),
                         ({"set": "goal"}, "params.force")):
        got, _ = error_of(client, "push.regions", dict(extra, fixture=f))
        assert got == field


def test_supports_and_tolerance_not_together(client):
    f = on_buttons(FX.disc_corner(0.5), BUTTONS, 0.3)
    f["tolerance"] = {"position": 0.01}
    got, reason = error_of(client, "fixture.put", {"fixture": f})
    assert got == "params.fixture.supports" and "tolerance" in reason, (got, reason)


def test_push_force_on_the_plate_agrees_with_force_range(client):
    """The chamfered plate on three buttons: push.force's least push over
    the outline is force.range's least at the point it names (two
    methods), no point of force.range's dense sampling of the outline seats
    with less, and its certified lower bound is below both. Its segments'
    samples are force.range's least at their points. The floating plate's
    least is lower: the buttons' friction costs force."""
    with open(os.path.join(REPO, "examples", "plate-chamfered.json")) as fh:
        floating = json.load(fh)
    f = on_buttons(floating, [[1, 0.5], [3, 0.5], [1.5, 1.6]], 0.1)
    none = [{"loads": [{"wrench": [0, 0, 0]}]}]
    r = client.result("push.force", {"fixture": f, "set": "goal", "cases": none, "samples": 8})
    least = r["least"]
    assert least["converged"], least
    force, lower = least["force"], least["lower_bound"]
    assert lower <= force <= lower * (1 + 2e-6), least

    def least_at(at, direction):
        got = client.result("force.range", {"fixture": f, "push": {"at": at, "direction": direction},
                                             "cases": none,
                                             "sets": ["goal"]})["all"]["goal"]["least"]
        return math.inf if got is None else got

    assert abs(least_at(least["at"], least["direction"]) - force) <= 1e-6 * force, least
    vertices = floating["body"]["shape"]["vertices"]

    def point(e, t):
        a, b = vertices[e], vertices[(e + 1) % len(vertices)]
        length = math.hypot(b[0] - a[0], b[1] - a[1])
        inward = [-(b[1] - a[1]) / length, (b[0] - a[0]) / length]  # counter-clockwise
        return [a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])], inward

    sampled = math.inf
    for e in range(len(vertices)):
        for j in range(32):
            sampled = min(sampled, least_at(*point(e, (j + 0.5) / 32)))
    assert force <= sampled * (1 + 1e-6), (force, sampled)
    assert sampled <= force * 1.2, (force, sampled)
    segment = next(s for s in r["segments"] if s["edge"] == 2)
    for t, value in zip(segment["t"], segment["force"]):
        expected = least_at(*point(2, t))
        assert (value is None) == math.isinf(expected)
        assert value is None or abs(value - expected) <= 1e-9 * expected
    plain = client.result("push.force", {"fixture": floating, "set": "goal", "cases": none,
                                         "samples": 1})["least"]["force"]
    assert plain < force, (plain, force)
    # A finger of some size, another set, no outline of straight edges: refused.
    for extra, field in (({"set": "both"}, "params.set"),
                         ({"set": "goal", "finger_radius": 0.1}, "params.finger_radius")):
        got, reason = error_of(client, "push.force", dict(extra, fixture=f, cases=none))
        assert got == field and "supports" in reason, (got, reason)


def test_tilt_of_the_disc_on_buttons(client):
    """The disc in the corner on three buttons, tilted: its in-plane pull
    m a seats iff it is farther than mu_B m g from the complement of the
    goal wedge (edges at 180 + atan(1/2) and 270 - atan(1/2) degrees), the
    torque absorbed by the axis every excluded cone holds: the arc is
    (180 + atan(1/2) + d, 270 - atan(1/2) - d), sin d = mu_B g / a. A pull
    too weak seats nowhere; the floating disc's arc is the whole wedge."""
    f = on_buttons(FX.disc_corner(0.5), BUTTONS, 0.3)
    edge = math.degrees(math.atan(0.5))
    for pull in (20.0, 60.0):
        r = client.result("gravity.sweep", {"fixture": f, "set": "goal", "in_plane_g": pull})
        d = math.degrees(math.asin(0.3 * G / pull))
        (lo, hi), = r["intervals_deg"]
        assert abs(lo - (180 + edge + d)) < 1e-5 and abs(hi - (270 - edge - d)) < 1e-5, r
        for a, b in r["undecided_deg"]:
            assert b - a <= 1e-5 and min(abs(a - lo), abs(b - hi)) < 1e-5, r
    weak = client.result("gravity.sweep", {"fixture": f, "set": "goal", "in_plane_g": 9.0})
    assert weak["intervals_deg"] == [], weak
    floating = client.result("gravity.sweep", {"fixture": FX.disc_corner(0.5), "set": "goal"})
    (lo, hi), = floating["intervals_deg"]
    assert abs(lo - (180 + edge)) < 1e-9 and abs(hi - (270 - edge)) < 1e-9
    for extra, field in (({"set": "both", "in_plane_g": 20}, "params.set"),
                         ({"set": "goal", "in_plane_g": -1}, "params.in_plane_g")):
        got, _ = error_of(client, "gravity.sweep", dict(extra, fixture=f))
        assert got == field
    # Floating: a pull is checked, then not used.
    for bad in (-1, 0, "x", [20]):
        got, _ = error_of(client, "gravity.sweep", {"fixture": FX.disc_corner(0.5), "set": "goal",
                                                     "in_plane_g": bad})
        assert got == "params.in_plane_g", bad
    same = client.result("gravity.sweep", {"fixture": FX.disc_corner(0.5), "set": "goal",
                                           "in_plane_g": 20})
    assert same == floating


def test_wrenchctl_supports_option(daemon, client):
    """wrenchctl --supports JSON|FILE sends the fixture with that member:
    push-force --set goal and gravity --in-plane-g answer as the daemon
    does for the fixture with the member written in."""
    import subprocess
    import tempfile
    wrenchctl = os.path.join(REPO, "build", "wrenchctl")
    env = dict(os.environ, WRENCHD_SOCKET=daemon.path)
    with open(os.path.join(REPO, "examples", "plate-chamfered.json")) as fh:
        floating = json.load(fh)
    supports = {"points": [[1, 0.5], [3, 0.5], [1.5, 1.6]], "friction": 0.1, "g": G}
    none = [{"loads": [{"wrench": [0, 0, 0]}]}]
    # Four samples a segment (--samples): the least is the branch and
    # bound's whatever their number, and the samples are the daemon's.
    expected = client.result("push.force", {"fixture": dict(floating, supports=supports),
                                            "set": "goal", "cases": none, "samples": 4})
    with tempfile.TemporaryDirectory() as d:
        part = os.path.join(d, "part.json")
        rest = os.path.join(d, "rest.json")
        with open(part, "w") as fh:
            json.dump(floating, fh)
        with open(rest, "w") as fh:
            json.dump(supports, fh)
        for given in (json.dumps(supports), rest):
            out = subprocess.run([wrenchctl, "--json", "push-force", part, "--set", "goal",
                                  "--case", "wrench=0,0,0", "--supports", given, "--samples", "4"],
                                 capture_output=True, text=True, env=env, timeout=300)
            assert out.returncode == 0, out.stderr
            answer = json.loads(out.stdout)
            got = answer["least"]
            assert abs(got["force"] - expected["least"]["force"]) <= 1e-12 * got["force"]
            assert answer["segments"] == expected["segments"]
            assert all(len(s["t"]) == 4 for s in answer["segments"]), answer["segments"]
        disc = os.path.join(d, "disc.json")
        with open(disc, "w") as fh:
            json.dump(FX.disc_corner(0.5), fh)
        rest = json.dumps({"points": BUTTONS, "friction": 0.3, "g": G})
        out = subprocess.run([wrenchctl, "gravity", disc, "--supports", rest, "--in-plane-g", "20"],
                             capture_output=True, text=True, env=env, timeout=120)
        assert out.returncode == 0, out.stderr
        assert "215.0268" in out.stdout and "234.9731" in out.stdout, out.stdout
        bad = subprocess.run([wrenchctl, "gravity", disc, "--supports", "[1]"],
                             capture_output=True, text=True, env=env, timeout=60)
        assert bad.returncode != 0 and "--supports" in bad.stderr, bad.stderr


def test_friction_sweep_over_the_supports(client):
    """friction.sweep "over": "supports": a force of 30 through the disc's
    centre along 225 degrees seats for mu_B below 30 / (W sqrt 10) (the
    disc's closed form); wrench.classify agrees at 0.999 and 1.001 times
    the end for a wrench of the 3-2-1 plate on buttons; holding against
    mu_B of the plate cut along +x begins at F_c / W. Sweeping the
    supports' mu_B of a floating part is refused at params.over."""
    f = on_buttons(FX.disc_corner(0.5), BUTTONS, 0.3)
    w = [-30 / R2, -30 / R2, 0]
    r = client.result("friction.sweep", {"fixture": f, "over": "supports", "wrenches": [w]})
    (lo, hi), = r["results"][0]["goal"]
    assert lo == 0 and abs(hi - 30 / (G * math.sqrt(10))) < 1e-8, r
    capped = client.result("friction.sweep", {"fixture": f, "over": "supports", "wrenches": [w],
                                              "range": [0.5, 0.8]})
    assert capped["results"][0]["goal"] == [[0.5, 0.8]], capped
    buttons = [[1, 0.5], [3, 0.5], [2, 1.7]]
    cut = [-4.0, -9.0, 2.0]
    g = on_buttons(plate(), buttons, 0.2)
    (_, end), = client.result("friction.sweep", {"fixture": g, "over": "supports",
                                                 "wrenches": [cut], "sets": ["goal"]})["results"][0]["goal"]
    verdicts = []
    for factor in (0.999, 1.001):
        h = on_buttons(plate(), buttons, end * factor)
        verdicts.append(client.result("wrench.classify", {"fixture": h, "wrenches": [cut],
                                                          "sets": ["goal"]})["results"][0]["goal"]["verdict"])
    assert verdicts == ["inside", "outside"], (end, verdicts)
    # Holding against mu_B: the plate cut by 3 along +x through its centre
    # of mass is held exactly from mu_B = F_c / W (MODEL.md's power
    # argument), on a grid, each interval proved; classify agrees either
    # side of the end.
    r = client.result("friction.sweep", {"fixture": g, "over": "supports", "range": [0, 1],
                                         "wrenches": [[3, 0, 0]], "sets": ["strong", "both"]})
    assert r["exact"] is False and r["resolution"] == 1 / 64, r
    (lo, hi), = r["results"][0]["strong"]
    assert abs(lo - 3 / (2 * G)) < 1e-7 and hi == 1 and r["results"][0]["both"] == [], r
    for factor, word in ((0.999, "outside"), (1.001, "inside")):
        h = on_buttons(plate(), buttons, lo * factor)
        got = client.result("wrench.classify", {"fixture": h, "wrenches": [[3, 0, 0]],
                                                "sets": ["strong"]})["results"][0]["strong"]
        assert got["verdict"] == word, (factor, got)
    for params, field in (({"fixture": FX.disc_corner(0.5), "over": "supports", "wrenches": [w]},
                           "params.over"),
                          # A tilt on the plate needs its pull.
                          ({"fixture": f, "over": "supports", "gravity": {}},
                           "params.gravity.in_plane_g")):
        got, _ = error_of(client, "friction.sweep", params)
        assert got == field, (params, got)


def test_friction_sweep_of_the_least_push_over_the_supports(client):
    """friction.sweep "over": "supports" with "force": the least push on the
    plate at 17 coefficients mu_B; each sample is push.force's least for the
    fixture with that mu_B, mu_B = 0 is the floating plate's least seating
    push, and the curve never falls (the grown cones only grow with mu_B)."""
    with open(os.path.join(REPO, "examples", "plate-chamfered.json")) as fh:
        floating = json.load(fh)
    buttons = [[1, 0.5], [3, 0.5], [1.5, 1.6]]
    none = [{"loads": [{"wrench": [0, 0, 0]}]}]
    f = on_buttons(floating, buttons, 0.1)
    # 17 least-push searches on the plate, each a branch and bound of LPs:
    # longer than one call's usual timeout on a loaded machine or under ASan.
    request = client.request("friction.sweep", {"fixture": f, "over": "supports", "force": {},
                                                "cases": none, "range": [0, 0.16]})
    client.send(request)
    answer = client.read_json(timeout=600)
    assert "result" in answer, answer
    r = answer["result"]
    curve = r["curve"]
    assert len(curve) == 17 and len(r["at"]) == 17 and r["exact"] is False
    assert abs(r["resolution"] - 0.01) < 1e-15
    forces = [force for _, force in curve]
    assert all(b >= a * (1 - 1e-6) for a, b in zip(forces, forces[1:])), forces
    plain = client.result("push.force", {"fixture": floating, "set": "goal", "cases": none,
                                         "samples": 1})["least"]["force"]
    assert abs(forces[0] - plain) <= 1e-6 * plain, (forces[0], plain)
    for mu, force in (curve[5], curve[16]):
        at_mu = client.result("push.force", {"fixture": on_buttons(floating, buttons, mu),
                                             "set": "goal", "cases": none, "samples": 1})
        assert abs(at_mu["least"]["force"] - force) <= 1e-9 * force, (mu, force, at_mu)
    got, _ = error_of(client, "friction.sweep", {"fixture": f, "over": "supports", "cases": none,
                                                 "force": {"set": "both"}})
    assert got == "params.force.set"


C_ON_THE_PLATE = r'''
#include "wrenchclient.h"
#include <stdio.h>
int main(int argc, char **argv)
{
    (void)argc;
    wrc_client *c = wrc_connect(argv[1], 120000, 0, NULL);
    const wrc_load none[] = {{.kind = WRC_LOAD_FORCE, .force = {0, 0}, .at = {1, 1}}};
    wrc_least_push least;
    if (!c || wrc_push_force(c, argv[2], none, 1, "goal", 0, NULL, &least) != WRC_OK)
        return 1;
    printf("least %.17g %.17g %.17g %.17g\n", least.force, least.lower_bound, least.at[0],
           least.at[1]);
    wrc_force_sweep_request r = {.set = "goal", .range = {0, 0.08}, .over_supports = 1};
    static double curve[32][2], at[32][2];
    wrc_force_curve s;
    if (wrc_force_sweep(c, argv[2], none, 1, &r, curve, at, 32, &s) != WRC_OK)
        return 2;
    for (int i = 0; i < s.sample_count; i++)
        printf("%.17g %.17g\n", curve[i][0], curve[i][1]);
    wrc_close(c);
    return 0;
}
'''


def test_c_client_on_the_plate(client, tmp_path):
    """libwrenchclient with a stored fixture on supports: wrc_push_force
    (set goal) and wrc_force_sweep over the supports' mu_B read what the
    daemon answers, printed to 17 digits and read back the same doubles."""
    with open(os.path.join(REPO, "examples", "plate-chamfered.json")) as fh:
        floating = json.load(fh)
    f = on_buttons(floating, [[1, 0.5], [3, 0.5], [1.5, 1.6]], 0.1)
    fid = client.result("fixture.put", {"fixture": f})["id"]
    out = run_client_program(tmp_path, "plate", C_ON_THE_PLATE, client.path, fid)
    assert out.returncode == 0, out
    lines = out.stdout.split("\n")
    none = [{"loads": [{"force": [0, 0], "at": [1, 1]}]}]
    want = client.result("push.force", {"fixture": fid, "set": "goal", "cases": none,
                                        "samples": 1})["least"]
    got = [float(x) for x in lines[0].split()[1:]]
    assert got == [want["force"], want["lower_bound"]] + want["at"], (got, want)
    # 17 least-push searches: a longer wait than one call's usual.
    client.send(client.request("friction.sweep", {"fixture": fid, "over": "supports",
                                                  "range": [0, 0.08], "force": {"set": "goal"},
                                                  "cases": none}))
    sweep = client.read_json(timeout=600)["result"]
    rows = [[float(x) for x in line.split()] for line in lines[1:] if line]
    assert rows == [[mu, force] for mu, force in sweep["curve"]], (rows, sweep["curve"])
