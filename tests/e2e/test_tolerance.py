"""A fixture's geometric tolerance over the wire, against what is derived
here: each outside's witness rebuilt here as a fixture of its own (its
contacts and normals given) and classified by the daemon, outside; its
contacts on the part's edges within the tolerance of nominal; inside
verdicts not contradicted by fixtures of the set sampled here; the
frictionless 3-2-1 plate's closed form |tau| < b (1 - T) - a T
(docs/MODEL.md section 10); robust regions and magnitudes within the
nominal ones; the id; and every refusal with its field."""

import copy
import math
import random

import pytest

# The 3-2-1 plate: a 4 x 2 rectangle, fixels 1 and 2 under it at x = 1 and
# x = 3, fixel 3 against its left side at y = 1.
PLATE = {
    "body": {"mass": 1.0, "shape": {"type": "polygon",
                                    "vertices": [[0, 0], [4, 0], [4, 2], [0, 2]]}},
    "friction": {"static": 0.3},
    "fixels": [{"at": [1, 0]}, {"at": [3, 0]}, {"at": [0, 1]}],
}
# Each fixel's edge: the way along it and its inward normal.
RUN = [(1, 0), (1, 0), (0, -1)]
NORMAL = [(0, 1), (0, 1), (1, 0)]


def with_tolerance(fixture, position, angle=None):
    f = copy.deepcopy(fixture)
    f["tolerance"] = {"position": position}
    if angle is not None:
        f["tolerance"]["angle"] = angle
    return f


def moved(fixture, s, tilt):
    """The fixture of the set with contact i moved s[i] along its edge and
    its normal tilted by tilt[i] radians, built here."""
    f = copy.deepcopy(fixture)
    f.pop("tolerance", None)
    for i, fixel in enumerate(f["fixels"]):
        x, y = PLATE["fixels"][i]["at"]
        fixel["at"] = [x + s[i] * RUN[i][0], y + s[i] * RUN[i][1]]
        c, sn = math.cos(tilt[i]), math.sin(tilt[i])
        n = NORMAL[i]
        fixel["normal"] = [c * n[0] - sn * n[1], sn * n[0] + c * n[1]]
    return f


def classify(client, fixture, wrenches, sets=("goal", "strong", "both")):
    return client.result("wrench.classify", {"fixture": fixture, "wrenches": wrenches,
                                             "sets": list(sets)})["results"]


def check_witness(client, fixture, wrench, set_name, answer, position, angle_deg):
    points, normals = answer["perturbation"], answer["perturbation_normals"]
    rebuilt = copy.deepcopy(fixture)
    rebuilt.pop("tolerance")
    for i, (p, n) in enumerate(zip(points, normals)):
        x, y = PLATE["fixels"][i]["at"]
        d = (p[0] - x, p[1] - y)
        # on the edge, within T of nominal
        assert abs(d[0] * NORMAL[i][0] + d[1] * NORMAL[i][1]) < 1e-12
        assert abs(d[0] * RUN[i][0] + d[1] * RUN[i][1]) <= position * (1 + 1e-12)
        tilt = math.atan2(NORMAL[i][0] * n[1] - NORMAL[i][1] * n[0],
                          NORMAL[i][0] * n[0] + NORMAL[i][1] * n[1])
        assert abs(tilt) <= math.radians(angle_deg) + 1e-12
        rebuilt["fixels"][i] = {"at": p, "normal": n}
    again = classify(client, rebuilt, [wrench], [set_name])[0][set_name]
    assert again["verdict"] == "outside", (answer, again)


def test_robust_verdicts_against_sampling(client):
    T, A = 0.02, 1.0
    fixture = with_tolerance(PLATE, T, A)
    rng = random.Random(7)
    wrenches = []
    for _ in range(30):
        z = rng.uniform(-1, 1)
        phi = rng.uniform(0, 2 * math.pi)
        r = math.sqrt(1 - z * z)
        wrenches.append([r * math.cos(phi), r * math.sin(phi), z])
    # and some near the goal set's middle, which are inside
    wrenches += [[-0.5, -1, t] for t in (-0.4, 0, 0.3)]
    results = classify(client, fixture, wrenches)
    counts = {"inside": 0, "boundary": 0, "outside": 0}
    a = math.radians(A)
    for w, answers in zip(wrenches, results):
        for set_name, answer in answers.items():
            counts[answer["verdict"]] += 1
            if answer["verdict"] == "outside":
                check_witness(client, fixture, w, set_name, answer, T, A)
            elif answer["verdict"] == "inside":
                samples = [moved(PLATE, [rng.choice((-T, T, rng.uniform(-T, T)))
                                         for _ in range(3)],
                                 [rng.choice((-a, a, rng.uniform(-a, a))) for _ in range(3)])
                           for _ in range(12)]
                for sample in samples:
                    v = classify(client, sample, [w], [set_name])[0][set_name]
                    assert v["verdict"] == "inside", (w, set_name, sample, v)
    assert counts["inside"] >= 3 and counts["outside"] >= 10, counts


@pytest.mark.parametrize("tau", [0.3, 0.7, 0.95])
def test_closed_form(client, tau):
    """Frictionless: (-a, -b, tau) seats robustly for |tau| < b (1 - T) - a T."""
    T, a, b = 0.1, 0.5, 1.0
    frictionless = copy.deepcopy(PLATE)
    frictionless["friction"] = {"static": 0}
    fixture = with_tolerance(frictionless, T)
    for sign in (1, -1):
        w = [-a, -b, sign * tau]
        nominal = classify(client, frictionless, [w], ["goal"])[0]["goal"]
        assert nominal["verdict"] == "inside"
        robust = classify(client, fixture, [w], ["goal"])[0]["goal"]
        expect = "inside" if tau < b * (1 - T) - a * T else "outside"
        assert robust["verdict"] == expect, robust
        if expect == "outside":
            check_witness(client, fixture, w, "goal", robust, T, 0)


def test_regions_force_and_margin_shrink(client):
    fixture = with_tolerance(PLATE, 0.02, 0.5)
    arcs = client.result("gravity.sweep", {"fixture": PLATE, "set": "both"})["intervals_deg"]
    robust = client.result("gravity.sweep", {"fixture": fixture, "set": "both"})["intervals_deg"]
    assert robust, robust
    for lo, hi in robust:
        assert any(a <= lo and hi <= b for a, b in arcs)
    assert sum(h - l for l, h in robust) < sum(h - l for l, h in arcs)
    m0 = client.result("stability.margin", {"fixture": PLATE, "bias": [0, -1, 0.5]})
    m1 = client.result("stability.margin", {"fixture": fixture, "bias": [0, -1, 0.5]})
    assert "robust" not in m0 and m1["robust"] in ("inside", "boundary")
    assert m1["margin"] <= m0["margin"]


def test_id_and_refusals(client):
    plain = client.result("fixture.put", {"fixture": PLATE})["id"]
    tol = client.result("fixture.put", {"fixture": with_tolerance(PLATE, 0.02)})["id"]
    zero = client.result("fixture.put", {"fixture": with_tolerance(PLATE, 0.02, 0)})["id"]
    assert plain != tol and tol == zero
    assert client.result("fixture.get", {"id": tol})["tolerance"] == {"position": 0.02}
    for tolerance, field, words in [
            ({"position": -1}, "params.fixture.tolerance.position", ">= 0"),
            ({"position": 0.1, "angle": 90}, "params.fixture.tolerance.angle", "below 90"),
            ({"position": 1.5}, "params.fixture.tolerance.position", "0.5 more than fixel 1"),
            ({"angle": 1}, "params.fixture.tolerance.position", "required"),
            ({"position": 0.1, "spin": 1}, "params.fixture.tolerance.spin", "")]:
        f = copy.deepcopy(PLATE)
        f["tolerance"] = tolerance
        error = client.error("wrench.classify", {"fixture": f, "wrenches": [[0, -1, 0]]})
        assert error["code"] == -32602 and error["data"]["field"] == field, error
        assert words in error["data"]["reason"], error
    error = client.error("friction.sweep", {"fixture": with_tolerance(PLATE, 0.01),
                                            "push": {"set": "goal", "finger_friction": 0.2}})
    assert error["data"]["field"] == "params.push.finger_friction", error


def test_python_client(daemon):
    """wrenchd.with_tolerance and the witness on Verdict and Disturbance."""
    import os
    import sys
    from conftest import REPO
    sys.path.insert(0, os.path.join(REPO, "clients", "python"))
    import wrenchd
    fixture = wrenchd.with_tolerance(PLATE, 0.1, 1.0)
    assert fixture["tolerance"] == {"position": 0.1, "angle": 1.0}
    assert "tolerance" not in PLATE
    with wrenchd.Client(daemon.path, timeout=30) as c:
        v = c.classify(fixture, [[-0.5, -1, 0.95]], sets="goal")[0]["goal"]
        assert v.verdict == "outside" and len(v.perturbation) == 3
        assert len(v.perturbation_normals) == 3
        nominal = c.classify(PLATE, [[-0.5, -1, 0.95]], sets="goal")[0]["goal"]
        assert nominal.perturbation is None
        d = c.stability_margin(fixture, [0, -1, 0.5])
        assert d.robust in ("inside", "boundary", "outside")
        assert c.stability_margin(PLATE, [0, -1, 0.5]).robust is None


def test_lean_columns_are_robust(client):
    """A lean answer (fields) over a tolerance: the same verdicts and
    margins as the full answer's, which are robust."""
    fixture = with_tolerance(PLATE, 0.1)
    wrenches = [[-0.5, -1, t] for t in (-0.95, -0.3, 0, 0.3, 0.95)] + [[0, -1, 0.5]]
    full = classify(client, fixture, wrenches, ["goal", "strong"])
    lean = client.result("wrench.classify", {"fixture": fixture, "wrenches": wrenches,
                                             "sets": ["goal", "strong"],
                                             "fields": ["verdict", "margin"]})
    letters = {"inside": "i", "boundary": "b", "outside": "o"}
    for set_name in ("goal", "strong"):
        verdicts = "".join(p[set_name]["verdicts"] for p in lean["pieces"])
        margins = [m for p in lean["pieces"] for m in p[set_name]["margins"]]
        assert verdicts == "".join(letters[r[set_name]["verdict"]] for r in full)
        assert margins == [r[set_name]["margin"] for r in full]


def push_wrench(fixture, edge, t, force):
    """The physical wrench of a push of `force` along the inward normal at
    (edge, t) of the plate's polygon, about its centre (2, 1)."""
    vs = fixture["body"]["shape"]["vertices"]
    a, b = vs[edge], vs[(edge + 1) % len(vs)]
    p = (a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1]))
    length = math.hypot(b[0] - a[0], b[1] - a[1])
    n = (-(b[1] - a[1]) / length, (b[0] - a[0]) / length)  # counter-clockwise: left is in
    return (force * n[0], force * n[1], force * ((p[0] - 2) * n[1] - (p[1] - 1) * n[0]))


def test_push_force_robust_against_sampling(client):
    """push.force over a tolerance: each sample's F* does 'both' under the
    case on every fixture of the set sampled here (its corners and random
    points), is no less than the nominal F* there, and the least keeps the
    nominal search's point and lower bound."""
    T, A = 0.05, 0.5
    fixture = with_tolerance(PLATE, T, A)
    params = {"cases": [{"loads": [{"gravity": {"g": 9.81, "direction_deg": 270}}]}],
              "samples": 4}
    nominal = client.result("push.force", dict(params, fixture=PLATE))
    robust = client.result("push.force", dict(params, fixture=fixture))
    least = robust["least"]
    assert least["lower_bound"] == nominal["least"]["lower_bound"]
    assert least["force"] >= nominal["least"]["force"] and not least["converged"]
    # the least is the least of the samples' robust F* (or less, at the
    # nominal search's point)
    assert least["force"] <= min(f for seg in robust["segments"] for f in seg["force"]
                                 if f is not None)
    rng = random.Random(11)
    perturbations = [[(c >> i & 1) * 2 * T - T for i in range(3)] for c in range(8)]
    tilts = [[0, 0, 0]] * 8
    for _ in range(8):
        perturbations.append([rng.uniform(-T, T) for _ in range(3)])
        tilts.append([rng.uniform(-1, 1) * math.radians(A) for _ in range(3)])
    fixtures = [moved(PLATE, s, tilt) for s, tilt in zip(perturbations, tilts)]
    finite = 0
    push = push_wrench(PLATE, least["edge"], least["t"], least["force"])
    for g in fixtures:
        wrench = [push[0], push[1] - 9.81, push[2]]
        assert classify(client, g, [wrench], ["both"])[0]["both"]["verdict"] == "inside"
    for seg_n, seg_r in zip(nominal["segments"], robust["segments"]):
        assert seg_n["t"] == seg_r["t"]
        for t, fn, fr in zip(seg_r["t"], seg_n["force"], seg_r["force"]):
            if fr is None:
                continue
            finite += 1
            assert fn is not None and fr >= fn * (1 - 1e-12)
            push = push_wrench(PLATE, seg_r["edge"], t, fr)
            wrench = [push[0], push[1] - 9.81, push[2]]
            for g in fixtures:
                verdict = classify(client, g, [wrench], ["both"])[0]["both"]["verdict"]
                assert verdict == "inside", (seg_r["edge"], t, fr, g["fixels"])
    assert finite >= 3, robust


def test_friction_sweep_wrenches_robust_against_sampling(client):
    """friction.sweep "wrenches" over a tolerance: each robust interval of
    mu lies inside a nominal one, and at mu sampled in it (its ends
    included) the wrench is inside on every fixture of the set sampled
    here, with that friction (mu_s = mu, mu_k = 0.8 mu)."""
    T, A, ratio = 0.05, 0.5, 0.8
    fixture = with_tolerance(PLATE, T, A)
    wrenches = [[-0.5, -1, 0.3], [-0.3, -1, -0.5], [0.2, -1, 0.1]]
    params = {"wrenches": wrenches, "sets": ["goal", "strong"], "range": [0, 1.5],
              "kinetic_ratio": ratio}
    nominal = client.result("friction.sweep", dict(params, fixture=PLATE))["results"]
    robust = client.result("friction.sweep", dict(params, fixture=fixture))["results"]
    rng = random.Random(5)
    perturbations = [([(c >> i & 1) * 2 * T - T for i in range(3)], [0, 0, 0]) for c in range(8)]
    for _ in range(6):
        perturbations.append(([rng.uniform(-T, T) for _ in range(3)],
                              [rng.uniform(-1, 1) * math.radians(A) for _ in range(3)]))
    kept = 0
    for w, rn, rr in zip(wrenches, nominal, robust):
        for set_name in ("goal", "strong"):
            for lo, hi in rr[set_name]:
                assert any(a <= lo and hi <= b for a, b in rn[set_name]), (rr, rn)
                kept += hi - lo
                for mu in (lo, hi, rng.uniform(lo, hi)):
                    fixtures = []
                    for s, tilt in perturbations:
                        g = moved(PLATE, s, tilt)
                        g["friction"] = {"static": mu, "kinetic": ratio * mu}
                        fixtures.append(g)
                    for g in fixtures:
                        v = classify(client, g, [w], [set_name])[0][set_name]["verdict"]
                        assert v == "inside", (w, set_name, mu, g["fixels"])
    assert kept > 0.5, robust


def test_push_force_robust_deadline(client):
    """A deadline met while the robust samples are made: the answer is
    partial, its samples those made (in order, each robust as in a whole
    answer), its least the least of them or null."""
    fixture = with_tolerance(PLATE, 0.05, 0.5)
    params = {"fixture": fixture, "cases": [{"loads": [{"gravity": {"g": 9.81,
                                                                    "direction_deg": 270}}]}],
              "samples": 64, "deadline_s": 0.3}
    cut = client.result("push.force", params)
    assert cut.get("partial") is True, cut
    whole = client.result("push.force", dict(params, samples=4, deadline_s=1e9))
    assert "partial" not in whole
    made = [f for seg in cut["segments"] for f in seg["force"]]
    assert len(made) < 4 * 64
    finite = [f for f in made if f is not None]
    if cut["least"] is not None:
        assert finite and cut["least"]["force"] <= min(finite)
