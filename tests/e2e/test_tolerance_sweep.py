"""friction.sweep "push", "gravity" and "force" over a fixture's tolerance,
against what is derived here: every robust interval of mu inside a nominal
one and the robust critical not above the nominal; at mu sampled in each
robust interval a point of push.regions' (gravity.sweep's) robust region at
that mu classified inside on fixtures of the set built here (contacts moved
along the outline within T, normals tilted within A, the friction that mu);
at mu not proved, the curve agreeing with push.regions there and no
sampled fixture seeing a region the nominal one lacks; with T = 1e-7 the
nominal intervals again, within the resolution; the robust least force no
less than the nominal least at its mu, push.force's over the tolerance at
that mu, its push inside by force.range over the tolerance and on sampled
fixtures; a deadline's partial answer; and the refusals at their fields."""

import copy
import json
import math
import random

import pytest

from test_tolerance import with_tolerance

# The chamfered 3-2-1 plate: [0, 4] x [0, 2] with the corner (4, 2) cut
# from (4, 1) to (3, 2); locators under it at x = 1 and 3, one on its left
# side at y = 0.5.
PLATE = {
    "body": {"mass": 2.0, "shape": {"type": "polygon",
                                    "vertices": [[0, 0], [4, 0], [4, 1], [3, 2], [0, 2]]}},
    "friction": {"static": 0.1},
    "fixels": [{"at": [1, 0]}, {"at": [3, 0]}, {"at": [0, 0.5]}],
}
RUN = [(1, 0), (1, 0), (0, -1)]
NORMAL = [(0, 1), (0, 1), (1, 0)]
T, A, RATIO = 0.02, 0.5, 0.8
G = 9.81


def at_mu(fixture, mu):
    f = copy.deepcopy(fixture)
    f["friction"] = {"static": mu, "kinetic": RATIO * mu}
    return f


def perturbed(mu, rng, k):
    """A fixture of the set at friction mu, built here: the corners of the
    set first, then random points."""
    f = at_mu(PLATE, mu)
    for i, fixel in enumerate(f["fixels"]):
        if k < 8:
            s = T if k >> i & 1 else -T
            tilt = math.radians(-A if k >> i & 1 else A)
        else:
            s = rng.uniform(-T, T)
            tilt = math.radians(rng.uniform(-A, A))
        x, y = PLATE["fixels"][i]["at"]
        fixel["at"] = [x + s * RUN[i][0], y + s * RUN[i][1]]
        c, sn = math.cos(tilt), math.sin(tilt)
        n = NORMAL[i]
        fixel["normal"] = [c * n[0] - sn * n[1], sn * n[0] + c * n[1]]
    return f


def push_wrench(edge, t, force, centre):
    """A push of `force` along the inward normal at (edge, t) of the
    counter-clockwise polygon, its torque about `centre`."""
    vs = PLATE["body"]["shape"]["vertices"]
    a, b = vs[edge], vs[(edge + 1) % len(vs)]
    p = (a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1]))
    length = math.hypot(b[0] - a[0], b[1] - a[1])
    n = (-(b[1] - a[1]) / length, (b[0] - a[0]) / length)
    return [force * n[0], force * n[1],
            force * ((p[0] - centre[0]) * n[1] - (p[1] - centre[1]) * n[0])]


def centre_of_mass():
    """The uniform pentagon's centroid, by the shoelace formula."""
    vs = PLATE["body"]["shape"]["vertices"]
    area = cx = cy = 0.0
    for (x0, y0), (x1, y1) in zip(vs, vs[1:] + vs[:1]):
        cross = x0 * y1 - x1 * y0
        area += cross / 2
        cx += (x0 + x1) * cross / 6
        cy += (y0 + y1) * cross / 6
    return (cx / area, cy / area)


def classify(client, fixtures, wrench, set_name):
    return [client.result("wrench.classify", {"fixture": g, "wrenches": [wrench],
                                              "sets": [set_name]})["results"][0][set_name]
            ["verdict"] for g in fixtures]


def within(inner, outer):
    return all(any(a <= lo and hi <= b for a, b in outer) for lo, hi in inner)


# Answers already had (each test has its own daemon; the answers are the
# same), so that one sweep asked by two tests is made once.
KNOWN = {}


def sweep(client, fixture, what, body, **extra):
    params = {"fixture": fixture, what: body, "range": [0, 2], "kinetic_ratio": RATIO}
    params.update(extra)
    key = json.dumps(params, sort_keys=True)
    if "deadline_s" in params:
        return client.result("friction.sweep", params)
    if key not in KNOWN:
        KNOWN[key] = client.result("friction.sweep", params)
    return KNOWN[key]


def test_push_sweep_robust_against_sampling(client):
    fixture = with_tolerance(PLATE, T, A)
    nominal = sweep(client, PLATE, "push", {"set": "both"})
    robust = sweep(client, fixture, "push", {"set": "both"})
    assert robust["exact"] is False and robust["resolution"] == pytest.approx(2 / 32)
    assert robust["intervals"] and within(robust["intervals"], nominal["intervals"])
    assert robust["critical"] is not None and nominal["critical"] is not None
    assert robust["critical"] <= nominal["critical"]
    assert robust["critical"] == robust["intervals"][-1][1]
    centre = centre_of_mass()
    rng = random.Random(31)
    checked = 0
    for lo, hi in robust["intervals"]:
        for mu in (lo, hi, rng.uniform(lo, hi), rng.uniform(lo, hi)):
            regions = client.result("push.regions", {"fixture": at_mu(fixture, mu),
                                                     "set": "both"})["regions"]
            assert regions, mu  # proved non-empty there
            r = max(regions, key=lambda r: r["length"])
            wrench = push_wrench(r["edge"], 0.5 * (r["t0"] + r["t1"]), 1.0, centre)
            fixtures = [perturbed(mu, rng, k) for k in range(12)]
            assert classify(client, fixtures, wrench, "both") == ["inside"] * 12, (mu, r)
            checked += 1
    assert checked >= 4
    # At every point of the curve the robust length is push.regions' over
    # the tolerance at that mu.  Where not proved (above the critical,
    # inside the nominal interval) nothing is contradicted: the robust
    # region there is no longer than any sampled fixture's own region.
    for mu, length in robust["curve"][::3]:
        answer = client.result("push.regions", {"fixture": at_mu(fixture, mu), "set": "both"})
        assert length == pytest.approx(answer["total_length"], rel=1e-12, abs=1e-12), mu
    above = [mu for mu, _ in robust["curve"] if robust["critical"] < mu < nominal["critical"]]
    assert above
    for mu in above[:2]:
        robust_here = client.result("push.regions", {"fixture": at_mu(fixture, mu),
                                                     "set": "both"})["total_length"]
        for g in [perturbed(mu, rng, k) for k in range(8)]:
            own = client.result("push.regions", {"fixture": g, "set": "both"})["total_length"]
            assert robust_here <= own + 1e-12, (mu, g["fixels"])


def test_gravity_sweep_robust_against_sampling(client):
    fixture = with_tolerance(PLATE, T, A)
    nominal = sweep(client, PLATE, "gravity", {"set": "goal"})
    robust = sweep(client, fixture, "gravity", {"set": "goal"})
    assert robust["exact"] is False
    assert robust["intervals"] and within(robust["intervals"], nominal["intervals"])
    if nominal["critical"] is not None:
        assert robust["critical"] is not None and robust["critical"] <= nominal["critical"]
    rng = random.Random(32)
    for lo, hi in robust["intervals"]:
        for mu in (lo, hi, rng.uniform(lo, hi)):
            arcs = client.result("gravity.sweep", {"fixture": at_mu(fixture, mu),
                                                   "set": "goal"})["intervals_deg"]
            assert arcs, mu
            a, b = max(arcs, key=lambda arc: arc[1] - arc[0])
            phi = math.radians(0.5 * (a + b))
            wrench = [2 * G * math.cos(phi), 2 * G * math.sin(phi), 0]
            fixtures = [perturbed(mu, rng, k) for k in range(12)]
            assert classify(client, fixtures, wrench, "goal") == ["inside"] * 12, (mu, a, b)


def test_tiny_tolerance_is_nominal(client):
    """T = 1e-7: the nominal intervals again, each end within the
    resolution (in fact within the bisection's finest piece)."""
    nominal = sweep(client, PLATE, "push", {"set": "goal"})
    robust = sweep(client, with_tolerance(PLATE, 1e-7), "push", {"set": "goal"})
    assert len(robust["intervals"]) == len(nominal["intervals"]) >= 1
    for (a, b), (c, d) in zip(robust["intervals"], nominal["intervals"]):
        assert c <= a <= c + robust["resolution"] and d - robust["resolution"] <= b <= d
        assert d - b <= 2 * (d - c) / 1024
    assert abs(robust["critical"] - nominal["critical"]) <= robust["resolution"]


def test_force_sweep_robust(client):
    fixture = with_tolerance(PLATE, T, A)
    cases = [{"loads": [{"gravity": {"g": G, "direction_deg": 270}}]}]
    robust = sweep(client, fixture, "force", {"set": "both"}, cases=cases)
    push_alone = sweep(client, fixture, "push", {"set": "both"})
    assert robust["intervals"] == push_alone["intervals"]
    assert robust["exact"] is False and len(robust["at"]) == len(robust["curve"])
    centre = centre_of_mass()
    rng = random.Random(33)
    finite = [(mu, f, at) for (mu, f), at in zip(robust["curve"], robust["at"]) if f is not None]
    assert len(finite) >= 3, robust
    for mu, force, at in finite[:3]:
        nominal = client.result("push.force", {"fixture": at_mu(PLATE, mu), "cases": cases,
                                               "set": "both"})["least"]
        assert force >= nominal["force"] * (1 - 1e-12)
        # push.force over the tolerance at that mu, its samples as the
        # sweep's (4 an edge): the same least
        again = client.result("push.force", {"fixture": at_mu(fixture, mu), "cases": cases,
                                             "set": "both", "samples": 4})["least"]
        assert again["force"] == pytest.approx(force, rel=1e-12)
        assert again["at"] == pytest.approx(at, abs=1e-12)
        # force.range over the tolerance at that push (its direction given:
        # the least may sit at an edge's end): F inside "all" both
        good = client.result("force.range", {"fixture": at_mu(fixture, mu),
                                             "push": {"at": at, "direction": again["direction"]},
                                             "cases": cases,
                                             "sets": ["both"]})["all"]["both"]["intervals"]
        assert any(lo <= force * (1 + 1e-9) and (hi is None or force <= hi)
                   for lo, hi in good), (mu, force, good)
        edge, t = again["edge"], again["t"]
        push = push_wrench(edge, t, force * (1 + 1e-9), centre)
        wrench = [push[0], push[1] - 2 * G, push[2]]
        fixtures = [perturbed(mu, rng, k) for k in range(10)]
        assert classify(client, fixtures, wrench, "both") == ["inside"] * 10, (mu, force)


def test_deadline_partial(client):
    fixture = with_tolerance(PLATE, T, A)
    for what, body, extra in [
            ("push", {"set": "both"}, {}),
            ("gravity", {"set": "goal"}, {}),
            ("force", {"set": "both"},
             {"cases": [{"loads": [{"gravity": {"g": G, "direction_deg": 270}}]}]})]:
        cut = sweep(client, fixture, what, body, deadline_s=0.05, **extra)
        assert cut.get("partial") is True, (what, cut)
        assert 0 <= cut["stopped_at"] <= 2
        for lo, hi in cut["intervals"]:
            assert hi <= cut["stopped_at"]
        for point in cut["curve"]:
            assert point[0] <= cut["stopped_at"]
        if what != "force":
            assert cut["critical"] is None


def test_refusals(client):
    fixture = with_tolerance(PLATE, T, A)
    error = client.error("friction.sweep", {"fixture": fixture,
                                            "push": {"set": "goal", "finger_friction": 0.3}})
    assert error["code"] == -32602 and error["data"]["field"] == "params.push.finger_friction"
    assert "frictionless" in error["data"]["reason"]
    # push.regions refuses it the same way
    error = client.error("push.regions", {"fixture": fixture, "finger_friction": 0.3})
    assert error["data"]["field"] == "params.finger_friction"
    # a finger's radius is answered, as push.regions answers it
    answer = sweep(client, fixture, "push", {"set": "goal", "finger_radius": 0.05})
    nominal = sweep(client, PLATE, "push", {"set": "goal", "finger_radius": 0.05})
    assert answer["exact"] is False and within(answer["intervals"], nominal["intervals"])
