"""friction.sweep over the supports' mu_B for "push" (under a force) and
"gravity" (under an in-plane pull), and deadline_s for its wrenches
(docs/PROTOCOL.md, Supports and friction.sweep; docs/MODEL.md section 11,
"Against mu_B").

Closed forms derived here, on the disc in the corner (fixel friction 0.5)
on three buttons, W = m g = 9.81: every excluded goal cone holds the whole
torque axis (MODEL.md section 11), so the supports' friction grows each
cone in its force plane by the disc of radius mu_B W, and a force F u
seats iff it lies farther than mu_B W from the complement of the goal
wedge, whose edges are at 180 + atan(1/2) = 206.565 and
270 - atan(1/2) = 243.435 degrees.

* Push: the regular octagon circumscribing the unit disc (edges tangent
  to it at 0, 45, ... degrees; the same fixels, mass, inertia and centre,
  hence the same cones). Only the edge tangent at 45 degrees has its
  inward normal (225 degrees) inside the wedge, 45 - atan(1/2) =
  atan(1/3) from both edges, so a push F seats along that whole edge
  (length 2 tan(22.5 deg)) iff F sin(atan(1/3)) = F / sqrt(10) > mu_B W,
  and nowhere else: the region is that edge for mu_B < F / (W sqrt 10) and
  empty above.
* Tilt: a pull m a along phi seats iff m a sin(delta) > mu_B m g, delta
  its angle to the wedge's nearer edge: the arc (206.565 + d, 243.435 - d),
  sin d = mu_B g / a, of 2 (atan(1/3) - d) degrees, vanishing at
  mu_B = a sin(atan(1/3)) / g = a / (g sqrt 10).

Every answer is also checked against the point answers (push.regions,
gravity.sweep) of the fixture with that mu_B, at grid points and just
either side of the critical mu_B, and the chamfered plate's critical
mu_B against the largest of friction.sweep's own wrench limits (another
method: each seating wrench's mu* from wr_supports_friction_limit) over
points of its outline."""

import copy
import json
import math
import os
import subprocess
import time

from conftest import REPO, SLOW
import fixtures as FX

G = 9.81
BUTTONS = [[0, 0.2], [-0.17320508075688773, -0.1], [0.17320508075688773, -0.1]]
WEDGE_HALF = math.degrees(math.atan(1 / 3))  # 18.435: the wedge's half-width
EDGE = 2 * math.tan(math.pi / 8)             # an edge of the octagon


def on_buttons(fixture, mu, points=BUTTONS):
    f = copy.deepcopy(fixture)
    f["supports"] = {"points": points, "friction": mu, "g": G}
    return f


def octagon():
    """The disc in the corner with the octagon circumscribing it as its
    outline: vertices at sec(22.5 deg) and 22.5 + 45 k degrees."""
    f = FX.disc_corner(0.5)
    r = 1 / math.cos(math.pi / 8)
    f["body"]["shape"] = {"type": "polygon", "vertices": [
        [r * math.cos(math.pi / 8 + k * math.pi / 4), r * math.sin(math.pi / 8 + k * math.pi / 4)]
        for k in range(8)]}
    return f


def chamfered():
    with open(os.path.join(REPO, "examples", "plate-chamfered.json")) as fh:
        return json.load(fh)


CHAMFER_BUTTONS = [[1, 0.5], [3, 0.5], [1.5, 1.6]]


def sweep(c, params):
    """A sweep's result, waiting as long as a long one takes."""
    c.send(c.request("friction.sweep", params))
    answer = c.read_json(timeout=600 * SLOW)
    assert "result" in answer, answer
    return answer["result"]


def with_mu(fixture, mu):
    """The fixture on its supports, their friction mu."""
    f = copy.deepcopy(fixture)
    f["supports"]["friction"] = mu
    return f


def region_length(c, fixture, mu, push):
    """push.regions' total length for the fixture with that mu_B."""
    return c.result("push.regions", dict(push, fixture=with_mu(fixture, mu),
                                         set="goal"))["total_length"]


def arc_total(c, fixture, mu, pull):
    """gravity.sweep's arcs, in degrees in all, for the fixture with that mu_B."""
    arcs = c.result("gravity.sweep", {"fixture": with_mu(fixture, mu), "set": "goal",
                                      "in_plane_g": pull})["intervals_deg"]
    return sum(b - a for a, b in arcs)


def check_shape(r, low, high):
    """One interval [low, critical], a curve increasing in mu from low to
    high that never grows, and the critical point on it."""
    mus = [mu for mu, _ in r["curve"]]
    assert mus[0] == low and mus[-1] == high, mus
    assert all(a < b for a, b in zip(mus, mus[1:])), mus
    sizes = [size for _, size in r["curve"]]
    assert all(b <= a * (1 + 1e-9) + 1e-12 for a, b in zip(sizes, sizes[1:])), sizes
    assert r["exact"] is False and abs(r["resolution"] - (high - low) / 64) < 1e-15
    assert "partial" not in r and "stopped_at" not in r
    if r["critical"] is None:
        assert r["intervals"] == [[low, high]]
        return
    assert r["intervals"] == [[low, r["critical"]]], r["intervals"]
    assert r["critical"] in mus
    # Non-empty up to the critical point, empty beyond.
    for mu, size in r["curve"]:
        assert (size > 0) == (mu <= r["critical"]), (mu, size, r["critical"])


def test_push_sweep_on_the_octagon_closed_form(client):
    """The push region of F = 30 and F = 20 against mu_B: the edge tangent at
    45 degrees whole below F / (W sqrt 10), nothing above (module docstring);
    each curve point push.regions' total at that mu_B; push.regions
    non-empty just below the critical mu_B and empty just above."""
    f = on_buttons(octagon(), 0.3)
    for force in (30.0, 20.0):
        expected = force / (G * math.sqrt(10))
        r = sweep(client, {"fixture": f, "over": "supports",
                           "push": {"set": "goal", "force": force}})
        check_shape(r, 0, 2)
        assert abs(r["critical"] - expected) < 1e-8, (r["critical"], expected)
        for mu, length in r["curve"]:
            closed = EDGE if mu < expected else 0
            assert abs(length - closed) < 1e-12, (mu, length, closed)
        push = {"force": force}
        for mu, length in r["curve"][::9] + [[r["critical"], EDGE]]:
            assert abs(region_length(client, f, mu, push) - length) < 1e-12, mu
        crit = r["critical"]
        assert abs(region_length(client, f, crit * (1 - 1e-7), push) - EDGE) < 1e-12
        assert region_length(client, f, crit * (1 + 1e-7), push) == 0
    # A range above the critical: empty throughout, critical its bottom;
    # below it: non-empty at the top, critical null.
    above = sweep(client, {"fixture": f, "over": "supports",
                           "push": {"force": 30}, "range": [1, 1.5]})
    assert above["intervals"] == [] and above["critical"] == 1, above
    assert all(length == 0 for _, length in above["curve"]) and len(above["curve"]) == 65
    below = sweep(client, {"fixture": f, "over": "supports",
                           "push": {"force": 30}, "range": [0.2, 0.9]})
    check_shape(below, 0.2, 0.9)
    assert below["critical"] is None and len(below["curve"]) == 65


def test_push_sweep_on_the_chamfered_plate_agrees_with_point_answers(client):
    """The chamfered plate on three buttons under a push of 20 and a load
    (0, -3, 0): the region shrinks continuously with mu_B. Every ninth
    curve point and the critical one equal push.regions' total at that
    mu_B; push.regions is non-empty 1e-7 below the critical and empty 1e-7
    above. Another method: the push at a point of the outline plus the
    load is a wrench whose own mu* (friction.sweep's wrenches over the
    supports) is where that point stops seating; the largest over 41
    points an edge is at most the critical, and within the sampling of
    it."""
    plate = chamfered()
    load = [0, -3, 0]
    push = {"force": 20, "cases": [{"loads": [{"wrench": load}]}]}
    fixture = on_buttons(plate, 0.1, CHAMFER_BUTTONS)
    r = sweep(client, {"fixture": fixture, "over": "supports", "range": [0, 1],
                       "push": dict(push, set="goal")})
    check_shape(r, 0, 1)
    crit = r["critical"]
    assert 0.3 < crit < 0.7, crit
    sizes = [size for _, size in r["curve"]]
    assert sizes[0] > sizes[8] > sizes[16] > sizes[24] > 0, sizes
    for mu, length in r["curve"][::9] + [p for p in r["curve"] if p[0] == crit]:
        got = region_length(client, fixture, mu, push)
        assert abs(got - length) <= 1e-12 * max(1, length), (mu, got, length)
    assert region_length(client, fixture, crit - 1e-7, push) > 0
    assert region_length(client, fixture, crit + 1e-7, push) == 0

    # The second method. The plate's centre of mass is its polygon's
    # centroid (uniform); the push at p along the inward normal n is
    # (F n, (p - com) x F n), plus the load.
    vertices = plate["body"]["shape"]["vertices"]
    n = len(vertices)
    area = cx = cy = 0.0
    for i in range(n):
        (x0, y0), (x1, y1) = vertices[i], vertices[(i + 1) % n]
        cross = x0 * y1 - x1 * y0
        area += cross / 2
        cx += (x0 + x1) * cross
        cy += (y0 + y1) * cross
    com = (cx / (6 * area), cy / (6 * area))
    wrenches = []
    for i in range(n):
        (x0, y0), (x1, y1) = vertices[i], vertices[(i + 1) % n]
        length = math.hypot(x1 - x0, y1 - y0)
        nx, ny = -(y1 - y0) / length, (x1 - x0) / length  # counter-clockwise: inward
        for k in range(41):
            t = k / 40
            px, py = x0 + t * (x1 - x0), y0 + t * (y1 - y0)
            fx, fy = 20 * nx, 20 * ny
            torque = (px - com[0]) * fy - (py - com[1]) * fx
            wrenches.append([fx + load[0], fy + load[1], torque + load[2]])
    limits = sweep(client, {"fixture": fixture, "over": "supports", "range": [0, 1],
                            "wrenches": wrenches})["results"]
    ends = [x["goal"][0][1] for x in limits if x["goal"]]
    assert ends, limits
    assert max(ends) <= crit + 1e-8, (max(ends), crit)
    assert max(ends) >= crit - 0.02, (max(ends), crit)


def test_gravity_sweep_of_the_disc_closed_form(client):
    """The tilt arcs of the disc for a pull of 20 against mu_B: 2 (atan(1/3)
    - asin(mu_B g / a)) degrees, vanishing at a / (g sqrt 10) (module
    docstring); each curve point gravity.sweep's total at that mu_B;
    gravity.sweep non-empty 1e-6 below the critical and empty 1e-6 above."""
    disc = on_buttons(FX.disc_corner(0.5), 0.3)
    pull = 20.0
    expected = pull / (G * math.sqrt(10))
    r = sweep(client, {"fixture": disc, "over": "supports", "range": [0, 1],
                       "gravity": {"set": "goal", "in_plane_g": pull}})
    check_shape(r, 0, 1)
    # The arcs' ends are decided to 1e-6 degrees (arcs narrower stay
    # undecided and are not counted), which the arc's shrinking of about
    # 60 degrees per unit of mu_B turns into about 2e-8 of mu_B.
    assert abs(r["critical"] - expected) < 1e-7, (r["critical"], expected)
    for mu, degrees in r["curve"]:
        s = mu * G / pull
        closed = 2 * (WEDGE_HALF - math.degrees(math.asin(s))) if s < 1 / math.sqrt(10) else 0
        assert abs(degrees - max(closed, 0)) < 1e-5, (mu, degrees, closed)
    for mu, degrees in r["curve"][::9] + [p for p in r["curve"] if p[0] == r["critical"]]:
        assert abs(arc_total(client, disc, mu, pull) - degrees) < 1e-12, mu
    assert arc_total(client, disc, r["critical"] - 1e-6, pull) > 0
    assert arc_total(client, disc, r["critical"] + 1e-6, pull) == 0


def test_deadlines(harness):
    """deadline_s over the supports' mu_B. A tiny one: nothing decided, the
    bottom of the range as stopped_at (a push: no curve, no interval; the
    wrenches: the first under way, cut there). A generous one: the whole
    answer. One inside the work of a tilt sweep: the whole answer's grid
    points up to stopped_at, its interval cut there, no critical; and of
    a long wrench sweep: the wrenches answered as whole, the one under
    way empty."""
    d = harness.start("--threads", "1")
    c = d.client(timeout=600 * SLOW)
    f = on_buttons(octagon(), 0.3)
    push = {"fixture": f, "over": "supports", "push": {"force": 30}, "range": [0.1, 2]}
    whole = sweep(c, push)
    tiny = sweep(c, dict(push, deadline_s=1e-6))
    assert tiny == {"intervals": [], "critical": None, "curve": [], "exact": False,
                    "resolution": whole["resolution"], "partial": True, "stopped_at": 0.1}, tiny
    assert sweep(c, dict(push, deadline_s=600)) == whole

    plate = on_buttons(FX.rectangle_321(0.3), 0.2, [[1, 0.5], [3, 0.5], [2, 1.7]])
    wrenches = {"fixture": plate, "over": "supports", "range": [0.1, 2],
                "wrenches": [[-4.0 + 0.01 * k, -9.0, 2.0 - 0.002 * k] for k in range(300)]}
    start = time.monotonic()
    whole = sweep(c, wrenches)
    seconds = time.monotonic() - start
    assert "partial" not in whole and len(whole["results"]) == 300
    assert any(x["goal"] for x in whole["results"]), whole
    tiny = sweep(c, dict(wrenches, deadline_s=1e-6))
    assert tiny == {"results": [{"goal": []}], "partial": True, "stopped_at": 0.1}, tiny
    assert sweep(c, dict(wrenches, deadline_s=600)) == whole
    part = sweep(c, dict(wrenches, deadline_s=max(seconds / 2, 1e-3)))
    if part.get("partial"):
        results = part["results"]
        assert part["stopped_at"] == 0.1 and results[-1] == {"goal": []}, part
        assert results[:-1] == whole["results"][:len(results) - 1]

    disc = on_buttons(FX.disc_corner(0.5), 0.3)
    tilt = {"fixture": disc, "over": "supports", "range": [0, 1],
            "gravity": {"in_plane_g": 20}}
    start = time.monotonic()
    whole = sweep(c, tilt)
    seconds = time.monotonic() - start
    grid = [p for p in whole["curve"] if p[0] != whole["critical"]]
    stopped_inside = 0
    for fraction in (0.25, 0.5):
        r = sweep(c, dict(tilt, deadline_s=seconds * fraction))
        if not r.get("partial"):
            continue
        mu = r["stopped_at"]
        assert r["critical"] is None
        assert r["intervals"] == ([[0, mu]] if r["curve"] else []), r
        kept = [p for p in grid if p[0] <= mu]
        if mu in [p[0] for p in grid] or not r["curve"]:
            assert r["curve"] == kept, (mu, r["curve"])
        else:
            # Stopped while bisecting: the grid up to the bracket's lower
            # end, then that end, which the whole answer's bracket passed.
            assert r["curve"][:-1] == kept and r["curve"][-1][0] == mu, (mu, r["curve"])
            assert 0 < r["curve"][-1][1] and mu <= whole["critical"]
        stopped_inside += 0 < mu
    assert stopped_inside >= 1


def test_wrenchctl_and_python_client(daemon):
    """wrenchctl sweep --over supports with --push goal --force F and with
    --gravity goal --in-plane-g A prints the critical mu_B of the closed
    forms; the Python client's friction_sweep answers the same."""
    import sys
    sys.path.insert(0, os.path.join(REPO, "clients", "python"))
    import wrenchd
    wrenchctl = os.path.join(REPO, "build", "wrenchctl")
    env = dict(os.environ, WRENCHD_SOCKET=daemon.path)
    rest = json.dumps({"points": BUTTONS, "friction": 0.3, "g": G})
    # A tilt sweep solves some 70 circles of tilts: longer than wrenchctl's
    # default wait on a loaded machine.
    wait = ["--timeout", str(600 * SLOW)]
    import tempfile
    with tempfile.TemporaryDirectory() as d:
        part = os.path.join(d, "oct.json")
        disc = os.path.join(d, "disc.json")
        with open(part, "w") as fh:
            json.dump(octagon(), fh)
        with open(disc, "w") as fh:
            json.dump(FX.disc_corner(0.5), fh)
        svg = os.path.join(d, "sweep.svg")
        out = subprocess.run([wrenchctl] + wait + ["sweep", part, "--over", "supports",
                                                   "--supports", rest, "--push", "goal",
                                                   "--force", "30", "--svg", svg],
                             capture_output=True, text=True, env=env, timeout=300 * SLOW)
        assert out.returncode == 0, out.stderr
        assert "critical mu %.6g" % (30 / (G * math.sqrt(10))) in out.stdout, out.stdout
        assert "the supports' mu_B from 0 to 2" in out.stdout, out.stdout
        with open(svg, encoding="utf-8") as fh:
            picture = fh.read()
        # The plot's axis is the supports' friction, not the fixels'.
        assert "\u03bc_B" in picture and "at every fixel" not in picture
        out = subprocess.run([wrenchctl, "--json"] + wait + ["sweep", disc, "--over", "supports",
                              "--supports", rest, "--gravity", "goal", "--in-plane-g", "20",
                              "--range", "0:1"],
                             capture_output=True, text=True, env=env, timeout=300 * SLOW)
        assert out.returncode == 0, out.stderr
        swept = json.loads(out.stdout)
        assert abs(swept["critical"] - 20 / (G * math.sqrt(10))) < 1e-7, swept
        for args, words in ((["--push", "goal"], "params.push.force"),
                            (["--gravity", "goal"], "params.gravity.in_plane_g"),
                            (["--gravity", "goal", "--force", "3"], "--force"),
                            (["--push", "goal", "--force", "3", "--in-plane-g", "2"],
                             "--in-plane-g"),
                            (["--push", "goal", "--force", "30", "--over", "plate"], "--over")):
            bad = subprocess.run([wrenchctl, "sweep", part, "--over", "supports", "--supports",
                                  rest] + args, capture_output=True, text=True, env=env,
                                 timeout=120 * SLOW)
            assert bad.returncode != 0 and words in bad.stderr, (args, bad.stderr)
    with wrenchd.Client(daemon.path, timeout=600 * SLOW) as c:
        f = on_buttons(octagon(), 0.3)
        r = c.friction_sweep(f, over="supports",
                             push={"force": 30, "cases": [[{"wrench": [0, 0, 0]}]]})
        assert abs(r.critical - 30 / (G * math.sqrt(10))) < 1e-8, r
        assert r.intervals == [[0, r.critical]] and r.exact is False
