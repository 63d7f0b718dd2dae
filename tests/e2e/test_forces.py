"""Forces and loads with magnitudes (docs/PROTOCOL.md, "force.range",
"Loads and cases", push.regions' "force" and "cases").

Nothing here echoes the daemon: closed forms derived below, every interval
end re-checked by wrench.classify just inside and just outside with both
methods (the explicit cones and the LPs), push.regions under a force against
force.range at 10,000 points, and one fixture written in three systems of
units giving the same answers converted."""

import json
import math
import os

import pytest

import fixtures as FX
from conftest import REPO
from helpers import run_client_program

G = 9.81
R2 = math.sqrt(2)


def error_of(client, method, params):
    e = client.error(method, params)
    assert e["code"] == -32602, e
    assert set(e["data"]) == {"field", "reason"}, e
    return e["data"]["field"], e["data"]["reason"]


def gravity(g=G, phi=270.0, name=None):
    load = {"gravity": {"g": g, "direction_deg": phi}}
    if name:
        load["name"] = name
    return load


def case(*loads, name=None):
    c = {"loads": list(loads)}
    if name:
        c["name"] = name
    return c


def force_range(client, fixture, cases, push=None, wrench=None, sets=None, rng=None):
    params = {"fixture": fixture, "cases": cases}
    if push is not None:
        params["push"] = push
    if wrench is not None:
        params["wrench"] = wrench
    if sets is not None:
        params["sets"] = sets
    if rng is not None:
        params["range"] = rng
    return client.result("force.range", params)


def plate_321(mu=0.0, units=None):
    f = FX.rectangle_321(mu)
    if units:
        f["units"] = units
    return f


# ---- closed forms ---------------------------------------------------------------------
#
# The disc in a corner (docs/MODEL.md section 7): G_goal = {f_x < 0, f_y < 0,
# |f_x| > mu |f_y|, |f_y| > mu |f_x|}, any torque.  Gravity along +x (phi = 0)
# and a push at boundary angle 45 degrees (the point (cos 45, sin 45), force
# -F (1, 1) / sqrt 2): f_x = m G - F / sqrt 2, f_y = -F / sqrt 2, seated
# exactly when F > sqrt 2 m G / (1 - mu) (f_x < 0 is implied; |f_y| >
# mu |f_x| holds then).
#
# The frictionless 3-2-1 plate (4 x 2, com (2, 1), fixels (1, 0), (3, 0),
# (0, 1)) under gravity straight down, pushed at (4, y) along -x: g = (-F,
# -m G, F (y - 1)).  Its goal cones (one s, the rest m or u) hold (-a, -b,
# tau), a, b > 0, exactly when tau <= -b (smm, smu: the part turns about
# (3, 1), alpha = (tau + b) / (I + m) <= 0) or tau >= b (msm, msu, about
# (1, 1)); the cones with s at fixel 3 need a_x >= 0, impossible as only
# fixel 3 pushes along x.  (The derivation in full: tests/unit/test_force.c.)
# So the push seats it exactly for 0 < F < m G / |y - 1|.


def test_disc_in_a_corner_closed_form(client):
    mu = 0.5
    f = FX.disc_corner(mu)
    r = force_range(client, f, [case({"wrench": [G, 0, 0]}, name="pull +x")],
                    push={"at": [1 / R2, 1 / R2]}, sets=["goal"])
    assert set(r) == {"cases", "all"}
    assert r["cases"][0]["name"] == "pull +x" and set(r["cases"][0]) == {"name", "goal"}
    goal = r["cases"][0]["goal"]
    least = R2 * G / (1 - mu)
    assert len(goal["intervals"]) == 1 and goal["intervals"][0][1] is None, goal
    assert abs(goal["intervals"][0][0] - least) < 1e-12 * least
    assert goal["least"] == goal["intervals"][0][0]
    assert r["all"]["goal"] == goal
    # Gravity the same way, as a gravity load: m = 1, phi = 0.
    r2 = force_range(client, f, [case(gravity(G, 0))], push={"at": [1 / R2, 1 / R2]},
                     sets=["goal"])
    assert abs(r2["all"]["goal"]["least"] - least) < 1e-12 * least
    assert r2["cases"][0]["name"] is None


def test_plate_321_under_gravity_closed_form(client):
    f = plate_321(0.0)
    for y in (1.5, 0.25, 1.9):
        r = force_range(client, f, [case(gravity())], push={"at": [4, y]}, sets=["goal"])
        goal = r["all"]["goal"]
        top = G / abs(y - 1)
        assert len(goal["intervals"]) == 1, goal
        assert goal["intervals"][0][0] == 0 and goal["least"] == 0
        assert abs(goal["intervals"][0][1] - top) < 1e-12 * top, (y, goal)
    r = force_range(client, f, [case(gravity())], push={"at": [4, 1]}, sets=["goal"])
    assert r["all"]["goal"]["intervals"] == [[0, None]]


def test_all_is_the_intersection_over_cases(client):
    f = plate_321(0.0)
    cases = [case(gravity(), name="y=%g" % y) for y in (1, 2, 3)]
    # The same gravity in every case, but a cutter force along the top edge
    # in two of them: the intersection is what every case allows.
    cases[1]["loads"].append({"force": [-5, 0], "at": [3, 2], "name": "cutter"})
    cases[2]["loads"].append({"force": [0, -20], "at": [3.5, 2]})
    r = force_range(client, f, cases, push={"at": [4, 1.5]})
    for s in ("goal", "strong", "both"):
        inter = None
        for c in r["cases"]:
            iv = [(a, math.inf if b is None else b) for a, b in c[s]["intervals"]]
            if inter is None:
                inter = iv
            else:
                inter = [(max(a, c2), min(b, d)) for a, b in inter for c2, d in iv
                         if max(a, c2) < min(b, d)]
        got = [(a, math.inf if b is None else b) for a, b in r["all"][s]["intervals"]]
        assert got == inter, (s, got, inter)


# ---- every end re-checked by wrench.classify, both methods ----------------------------


def classify(client, fixture, wrenches, sets, method):
    r = client.result("wrench.classify", {"fixture": fixture, "wrenches": wrenches,
                                          "sets": sets, "method": method})
    return r["results"]


def push_wrench(fixture_obj, at, direction):
    """(d, (at - com) x d) for the 4 x 2 plate or a disc at the origin."""
    com = fixture_obj["body"].get("com")
    if com is None:  # the plate's centroid
        xs = [v[0] for v in fixture_obj["body"]["shape"]["vertices"]]
        ys = [v[1] for v in fixture_obj["body"]["shape"]["vertices"]]
        com = [(min(xs) + max(xs)) / 2, (min(ys) + max(ys)) / 2]
    r = (at[0] - com[0], at[1] - com[1])
    return (direction[0], direction[1], r[0] * direction[1] - r[1] * direction[0])


PROBES = [
    # fixture, push point, inward normal, cases
    ("plate", [4, 1.5], [-1, 0], [[gravity()], [gravity(), {"force": [-3, -2], "at": [2, 2]}]]),
    ("plate", [2.5, 2], [0, -1], [[gravity(phi=200)], [{"wrench": [1, -4, 0.5]}]]),
    ("plate", [4, 0.4], [-1, 0], [[gravity(phi=240)], [gravity(phi=300)]]),
    ("disc", [math.cos(0.7), math.sin(0.7)], [-math.cos(0.7), -math.sin(0.7)],
     [[gravity(phi=0)], [gravity(phi=225)], [{"wrench": [2, 1, 3]}]]),
]


@pytest.mark.parametrize("probe", range(len(PROBES)))
def test_every_end_agrees_with_classify_both_methods(client, probe):
    kind, at, normal, case_loads = PROBES[probe]
    f = plate_321(0.2) if kind == "plate" else FX.disc_corner(0.3)
    fid = client.result("fixture.put", {"fixture": f})["id"]
    u = push_wrench(f, at, normal)
    r = force_range(client, fid, [case(*loads) for loads in case_loads], push={"at": at})
    # Each case's load as a wrench: the same case alone, pushed with F = 0,
    # is the load; the load's wrench is read from the case's definition.
    checked = lp_checked = 0
    for ci, loads in enumerate(case_loads):
        load = [0.0, 0.0, 0.0]
        for ld in loads:
            if "gravity" in ld:
                phi = math.radians(ld["gravity"]["direction_deg"])
                load[0] += ld["gravity"]["g"] * math.cos(phi)  # mass 1
                load[1] += ld["gravity"]["g"] * math.sin(phi)
            elif "wrench" in ld:
                load = [load[k] + ld["wrench"][k] for k in range(3)]
            else:
                w = push_wrench(f, ld["at"], ld["force"])
                load = [load[k] + w[k] for k in range(3)]
        for s in ("goal", "strong", "both"):
            iv = r["cases"][ci][s]["intervals"]
            probes = []  # (F, expected inside)
            for i, (a, b) in enumerate(iv):
                width = (b - a) if b is not None else math.inf
                step = 1e-6 * max(1.0, a)
                probes.append((a + min(step, width / 4), True))
                if a > 0:
                    probes.append((a - step, False))
                if b is not None:
                    step = 1e-6 * max(1.0, b)
                    probes.append((b - min(step, width / 4), True))
                    probes.append((b + step, False))
            if not probes:
                continue
            wrenches = [[load[k] + F * u[k] for k in range(3)] for F, _ in probes]
            cones = classify(client, fid, wrenches, [s], "auto")
            lp = classify(client, fid, wrenches, [s], "lp")
            for (F, want), c, l in zip(probes, cones, lp):
                got = c[s]["verdict"]
                assert (got == "inside") == want, (s, F, want, c[s])
                checked += 1
                # The methods agree where the margin is beyond 1e-6.
                if abs(c[s]["margin"]) > 1e-6:
                    assert (l[s]["verdict"] == "inside") == want, (s, F, l[s], c[s])
                    lp_checked += 1
    assert checked > 0


# ---- units: one fixture in three systems -------------------------------------------


def scaled_fixture(length_scale, units):
    """The 3-2-1 plate with lengths multiplied by length_scale (mass in kg)."""
    f = plate_321(0.2)
    f["body"]["shape"]["vertices"] = [[x * length_scale, y * length_scale]
                                      for x, y in f["body"]["shape"]["vertices"]]
    for fx in f["fixels"]:
        fx["at"] = [c * length_scale for c in fx["at"]]
    f["units"] = units
    return f


def test_units_give_the_same_answers_converted(client):
    # The plate 4 m x 2 m, mass 1 kg, in metres and newtons; in millimetres
    # (coordinates x1000, g in mm/s^2) and newtons; in inches and pounds-force.
    lbf = 4.4482216152605
    systems = [
        (1.0, {"length": "m", "force": "N"}, 1.0),
        (1000.0, {"length": "mm", "force": "N"}, 1.0),
        (1 / 0.0254, {"length": "in", "force": "lbf"}, 1 / lbf),
    ]
    answers = []
    for scale, units, per_newton in systems:
        f = scaled_fixture(scale, units)
        loads = [gravity(G * scale),
                 {"force": [-3 * per_newton, -2 * per_newton], "at": [2 * scale, 2 * scale]},
                 {"wrench": [0.5 * per_newton, -1 * per_newton, 0.7 * per_newton * scale]}]
        r = force_range(client, f, [case(*loads)], push={"at": [4 * scale, 1.5 * scale]},
                        rng=[0, 1000 * per_newton])
        answers.append((per_newton, r))
    base = answers[0][1]
    for per_newton, r in answers[1:]:
        for s in ("goal", "strong", "both"):
            want = base["all"][s]["intervals"]
            got = r["all"][s]["intervals"]
            assert len(got) == len(want), (s, got, want)
            for (a, b), (c, d) in zip(want, got):
                assert abs(c / per_newton - a) <= 1e-9 * max(1, a), (s, got, want)
                assert abs(d / per_newton - b) <= 1e-9 * max(1, b), (s, got, want)
    assert any(base["all"][s]["intervals"] for s in ("goal", "strong", "both"))


def test_witness_acceleration_in_the_fixture_length_unit(client):
    """A wrench pulling the bracket off its fixels (no contact force): its
    witness acceleration is f / m and tau / I in the fixture's units, 1 N on
    0.8 kg in mm/N being 1250 mm/s^2 (1 N = 1000 kg mm/s^2); the same
    fixture without units reads the numbers as kg mm/s^2 (1.25)."""
    import json
    with open(os.path.join(REPO, "examples", "bracket-upright.json")) as fh:
        f = json.load(fh)
    plain = dict(f)
    plain.pop("units")
    mass = f["body"]["mass"]
    answers = []
    for fixture, per_unit in ((f, 1000.0), (plain, 1.0)):
        r = client.result("wrench.classify", {"fixture": fixture, "wrenches": [[1, 2, 0.5]],
                                               "sets": ["goal"]})["results"][0]["goal"]
        w = r["witness"]
        assert all(c == [0, 0] for c in w["forces"]), w
        assert abs(w["acceleration"][0] - per_unit * 1 / mass) <= 1e-12 * per_unit / mass
        assert abs(w["acceleration"][1] - per_unit * 2 / mass) <= 1e-12 * per_unit / mass
        answers.append(w)
    assert abs(answers[0]["acceleration"][2] - 1000 * answers[1]["acceleration"][2]) <= \
        1e-9 * abs(answers[0]["acceleration"][2])
    assert answers[0]["wrench"] == answers[1]["wrench"]


# ---- bad input ------------------------------------------------------------------------


def test_bad_input_is_refused_at_its_field(client):
    f = plate_321(0.2)
    fid = client.result("fixture.put", {"fixture": f})["id"]
    ok_case = [case(gravity())]
    bad = [
        ({"cases": ok_case}, "params.push", "required"),
        ({"cases": ok_case, "push": {"at": [4, 1]}, "wrench": [1, 0, 0]}, "params.wrench", "not both"),
        ({"cases": [], "push": {"at": [4, 1]}}, "params.cases", "empty"),
        ({"cases": [{"loads": []}], "push": {"at": [4, 1]}}, "params.cases[0].loads", "empty"),
        ({"cases": [case(gravity(g=-9.81))], "push": {"at": [4, 1]}},
         "params.cases[0].loads[0].gravity.g", "negative"),
        ({"cases": [case({"force": [1, 0], "at": [400, 1]})], "push": {"at": [4, 1]}},
         "params.cases[0].loads[0].at", "beyond"),
        ({"cases": [case({"torque": 1})], "push": {"at": [4, 1]}},
         "params.cases[0].loads[0]", "gravity"),
        ({"cases": ok_case, "push": {"at": [4, 1]}, "range": [5, 1]}, "params.range",
         "upside down"),
        ({"cases": ok_case, "push": {"at": [4, 1]}, "range": [-1, 1]}, "params.range[0]",
         "negative"),
        ({"cases": ok_case, "push": {"at": [5, 1]}}, "params.push.at", "boundary"),
        ({"cases": ok_case, "push": {"at": [4, 0]}}, "params.push.at", ""),
        ({"cases": ok_case, "push": {"at": [4, 1], "direction": [0, 0]}},
         "params.push.direction", "non-zero"),
        ({"cases": ok_case, "wrench": [0, 0, 0]}, "params.wrench", "zero"),
        ({"cases": ok_case, "push": {"at": [4, 1]}, "sets": ["goal", "goal"]}, "params.sets[1]",
         "twice"),
        ({"cases": ok_case, "push": {"at": [4, 1]}, "sets": ["all"]}, "params.sets[0]", "goal"),
        ({"cases": [case(gravity())] * 1001, "push": {"at": [4, 1]}}, "params.cases", "1000"),
        ({"cases": [case(*([gravity()] * 101))], "push": {"at": [4, 1]}},
         "params.cases[0].loads", "100"),
        ({"cases": [{"loads": [gravity()], "extra": 1}], "push": {"at": [4, 1]}},
         "params.cases[0].extra", ""),
    ]
    for params, field, word in bad:
        params = dict(params, fixture=fid)
        got = error_of(client, "force.range", params)
        assert got[0] == field and word in got[1], (params, got)


def test_max_cases_is_the_daemons_limit(harness):
    """--max-cases N: N cases are taken, N + 1 refused at params.cases
    naming the limit and the option, by every method that takes cases."""
    d = harness.start("--max-cases", "3", socket_path=harness.path("cases.sock"))
    c = d.client()
    fid = c.result("fixture.put", {"fixture": plate_321(0.2)})["id"]
    three, four = [case(gravity())] * 3, [case(gravity())] * 4
    asks = [("force.range", {"fixture": fid, "push": {"at": [4, 1]}}),
            ("push.force", {"fixture": fid, "samples": 1}),
            ("push.regions", {"fixture": fid, "set": "both", "force": 5.0}),
            ("friction.sweep", {"fixture": fid, "force": {}, "range": [0, 0.2]}),
            ("fixture.design", {"body": plate_321(0.2)["body"], "friction": 0.2,
                                "sites": [{"at": [1, 0]}, {"at": [3, 0]}, {"at": [0, 1]}]})]
    for method, params in asks:
        assert c.result(method, dict(params, cases=three)) is not None, method
        e = c.error(method, dict(params, cases=four))
        assert e["data"]["field"] == "params.cases", (method, e)
        assert "at most 3 cases (the daemon's --max-cases), 4 given" in e["data"]["reason"], e


# ---- push.regions under a force, against force.range at 10,000 points ----------------

import outline_model as OM  # noqa: E402


def rounded_plate(mu=0.1):
    """A 4 x 2 plate with corners rounded to radius 0.5 (arcs), located by
    two fixels on its bottom edge and one on its left."""
    loop = OM.rounded_rectangle(4, 2, 0.5, center=(2, 1))
    return {"body": {"mass": 1.0, "shape": {"type": "outline", "loops": [loop]}},
            "friction": {"static": mu},
            "fixels": [{"at": [1, 0]}, {"at": [3, 0]}, {"at": [0, 1]}]}


def boundary_samples(fixture, n):
    """n points of the outline away from its vertices: (key, t, point,
    inward normal), key the region's edge (or (loop, segment))."""
    shape = fixture["body"]["shape"]
    out = []
    if shape["type"] == "circle":
        c, r = shape["center"], shape["radius"]
        for i in range(n):
            t = 360.0 * (i + 0.5) / n
            a = math.radians(t)
            out.append((0, t, (c[0] + r * math.cos(a), c[1] + r * math.sin(a)),
                        (-math.cos(a), -math.sin(a))))
        return out
    if shape["type"] == "polygon":
        segs = OM.segments([list(v) + [0] for v in shape["vertices"]])
        keys = list(range(len(segs)))
    else:
        segs = OM.segments(shape["loops"][0])
        keys = [(0, j) for j in range(len(segs))]
    per = n // len(segs)
    for key, s in zip(keys, segs):
        for i in range(per):
            t = (i + 0.5) / per
            d = s.direction(t)
            out.append((key, t, s.point(t), (-d[1], d[0])))  # counter-clockwise: left is in
    return out


def region_key(region):
    return (region["loop"], region["segment"]) if "loop" in region else region["edge"]


def batched(client, requests, size=500):
    """Answers of many requests, sent as JSON-RPC batches."""
    out = []
    for i in range(0, len(requests), size):
        chunk = [{"jsonrpc": "2.0", "id": i + k, "method": m, "params": p}
                 for k, (m, p) in enumerate(requests[i:i + size])]
        client.send(chunk)
        answers = sorted(client.read_json(), key=lambda a: a["id"])
        assert all("result" in a for a in answers), [a for a in answers if "result" not in a][:1]
        out.extend(a["result"] for a in answers)
    return out


REGION_CASES = [
    ("chamfered plate", lambda: FX.chamfered_plate(0.05), 12.0, "both",
     [[gravity()], [gravity(), {"force": [-4, -1], "at": [2, 2], "name": "cutter"}]]),
    ("disc in a corner", lambda: FX.disc_corner(0.3), 15.0, "goal",
     [[gravity(phi=200)], [gravity(phi=250), {"wrench": [1, 0, 2]}]]),
    ("rounded plate", lambda: rounded_plate(0.1), 20.0, "both",
     [[gravity()], [gravity(), {"force": [-3, 0], "at": [2, 2]}]]),
]


@pytest.mark.parametrize("which", range(len(REGION_CASES)))
def test_regions_under_a_force_agree_with_force_range(client, which):
    name, make, F, s, case_loads = REGION_CASES[which]
    f = make()
    fid = client.result("fixture.put", {"fixture": f})["id"]
    cases = [case(*loads) for loads in case_loads]
    regions = client.result("push.regions", {"fixture": fid, "set": s, "force": F,
                                             "cases": cases})
    assert regions["exact"] is True and regions["resolution"] == 0
    top = 360.0 if f["body"]["shape"]["type"] == "circle" else 1.0
    # Without loads the answer is today's (to rounding: another arithmetic
    # path): a force alone changes nothing.
    alone = client.result("push.regions", {"fixture": fid, "set": s, "force": F})["regions"]
    today = client.result("push.regions", {"fixture": fid, "set": s})["regions"]
    assert len(alone) == len(today), (alone, today)
    for a, b in zip(alone, today):
        assert region_key(a) == region_key(b)
        assert abs(a["t0"] - b["t0"]) < 1e-12 * top and abs(a["t1"] - b["t1"]) < 1e-12 * top
    samples = boundary_samples(f, 10000)
    assert len(samples) == 10000
    requests = [("force.range", {"fixture": fid, "cases": cases, "sets": [s],
                                 "push": {"at": list(p), "direction": list(nu)}})
                for _, _, p, nu in samples]
    answers = batched(client, requests)
    agree = inside = skipped = 0
    for (key, t, _, _), answer in zip(samples, answers):
        near = False
        in_region = False
        for reg in regions["regions"]:
            if region_key(reg) != key:
                continue
            in_region |= reg["t0"] < t < reg["t1"]
            near |= abs(t - reg["t0"]) < 1e-7 * top or abs(t - reg["t1"]) < 1e-7 * top
        in_range = False
        for a, b in answer["all"][s]["intervals"]:
            b = math.inf if b is None else b
            in_range |= a < F < b
            near |= abs(F - a) < 1e-7 * F or abs(F - b) < 1e-7 * F
        if near:
            skipped += 1
            continue
        assert in_region == in_range, (name, key, t, answer["all"][s], regions["regions"])
        agree += 1
        inside += in_region
    assert agree >= 9990 and inside > 50 and agree - inside > 50, (agree, inside, skipped)


def test_regions_under_a_force_refuse_bad_input(client):
    fid = client.result("fixture.put", {"fixture": FX.chamfered_plate(0.05)})["id"]
    bad = [
        ({"cases": [case(gravity())]}, "params.force", "required"),
        ({"force": 0}, "params.force", "positive"),
        ({"force": -2, "cases": [case(gravity())]}, "params.force", "positive"),
        ({"force": 5, "cases": []}, "params.cases", "empty"),
        ({"force": 5, "finger_friction": 0.2}, "params.finger_friction", "force"),
        ({"force": 5, "cases": [case(gravity(g=-1))]}, "params.cases[0].loads[0].gravity.g",
         "negative"),
    ]
    for params, field, word in bad:
        got = error_of(client, "push.regions", dict(params, fixture=fid))
        assert got[0] == field and word in got[1], (params, got)


# ---- push.force: the least force along the outline ------------------------------------


@pytest.mark.parametrize("which", range(len(REGION_CASES)))
def test_push_force_minimum_against_brute_force(client, which):
    name, make, _, s, case_loads = REGION_CASES[which]
    f = make()
    fid = client.result("fixture.put", {"fixture": f})["id"]
    cases = [case(*loads) for loads in case_loads]
    r = client.result("push.force", {"fixture": fid, "set": s, "cases": cases})
    assert set(r) == {"least", "segments", "samples", "evaluations"}
    # Brute force: force.range (the intersection of each case's intervals,
    # another path than the search's union of excluded intervals) at 4,000
    # points of the outline, each pushing along its own inward normal.
    samples = boundary_samples(f, 4000)
    answers = batched(client, [("force.range", {"fixture": fid, "cases": cases, "sets": [s],
                                                "push": {"at": list(p), "direction": list(nu)}})
                               for _, _, p, nu in samples])
    brute = min((a["all"][s]["least"] for a in answers if a["all"][s]["least"] is not None),
                default=None)
    least = r["least"]
    print(name, "least", least and least["force"], "brute", brute, "evaluations", r["evaluations"])
    # Each of these fixtures has a push that does the job.
    assert brute is not None
    assert least is not None and least["converged"], least
    assert least["force"] <= brute * (1 + 1e-9) + 1e-12, (least, brute)
    assert least["lower_bound"] <= brute + 1e-12, (least, brute)
    # F* where the search says it is least: force.range agrees.
    at_least = force_range(client, fid, cases, push={"at": least["at"],
                                                     "direction": least["direction"]},
                           sets=[s])
    assert abs(at_least["all"][s]["least"] - least["force"]) <= 1e-9 * least["force"] + 1e-12
    # The samples are F* at their points, exactly: three checked.
    seg = r["segments"][0]
    assert len(seg["t"]) == r["samples"] == 64


def test_push_force_closed_forms(client):
    # The disc in a corner, gravity along +x: F*(theta) = m G / (cos - mu sin)
    # on the goal side, least as theta -> 0, approaching m G (derived in
    # tests/unit/test_force.c).
    r = client.result("push.force", {"fixture": FX.disc_corner(0.5), "set": "goal",
                                     "cases": [case(gravity(G, 0))]})
    assert G <= r["least"]["force"] < G * (1 + 1e-8), r["least"]
    assert r["least"]["lower_bound"] <= G * (1 + 1e-12)
    # The frictionless 3-2-1 plate under gravity: any push on the right edge
    # at a height y != 1 seats it for 0 < F < m G / |y - 1|: the least is 0
    # (approached: the answer is an infimum).
    r = client.result("push.force", {"fixture": plate_321(0.0), "set": "goal",
                                     "cases": [case(gravity())]})
    assert r["least"]["force"] == 0, r["least"]


def test_push_force_units_and_refusals(client):
    lbf = 4.4482216152605
    answers = []
    for scale, units, per_newton in ((1.0, {"length": "m", "force": "N"}, 1.0),
                                     (1 / 0.0254, {"length": "in", "force": "lbf"}, 1 / lbf)):
        f = scaled_fixture(scale, units)
        loads = [gravity(G * scale), {"force": [-3 * per_newton, -2 * per_newton],
                                      "at": [2 * scale, 2 * scale]}]
        r = client.result("push.force", {"fixture": f, "set": "strong", "cases": [case(*loads)]})
        answers.append((per_newton, r["least"]))
    (_, a), (k, b) = answers
    assert a is not None and abs(b["force"] / k - a["force"]) <= 1e-9 * a["force"], (a, b)
    fid = client.result("fixture.put", {"fixture": plate_321(0.2)})["id"]
    for params, field in (({}, "params.cases"), ({"cases": []}, "params.cases"),
                          ({"cases": [case(gravity())], "samples": 0}, "params.samples"),
                          ({"cases": [case(gravity())], "set": "all"}, "params.set"),
                          ({"cases": [case(gravity())], "finger_radius": -1},
                           "params.finger_radius")):
        got = error_of(client, "push.force", dict(params, fixture=fid))
        assert got[0] == field, (params, got)


# ---- fixture.design with objective "force", against a brute force -------------------


def test_design_objective_force_against_brute_force(client):
    import itertools
    body = {"mass": 1.0, "shape": {"type": "polygon",
                                   "vertices": [[0, 0], [4, 0], [4, 1], [3, 2], [0, 2]]}}
    sites = [{"at": [0.8, 0]}, {"at": [2, 0]}, {"at": [3.2, 0]}, {"at": [0, 0.6]},
             {"at": [0, 1.4]}, {"at": [1.5, 2]}]
    cases = [case(gravity()), case(gravity(), {"force": [-2, -1], "at": [1, 2]})]
    r = client.result("fixture.design", {"body": body, "friction": 0.05, "sites": sites,
                                         "objective": "force", "cases": cases, "top": 20})
    designs = r["designs"]
    # Brute force: every combination of three sites put as a fixture and
    # asked push.force (both, the same cases); those with a finite least.
    brute = {}
    for combo in itertools.combinations(range(len(sites)), 3):
        f = {"body": body, "friction": {"static": 0.05},
             "fixels": [dict(sites[i]) for i in combo]}
        try:
            fid = client.result("fixture.put", {"fixture": f})["id"]
        except Exception:
            continue  # degenerate: the design refuses it too
        if not client.result("fixture.put", {"fixture": f}).get("pinned", True):
            continue
        least = client.result("push.force", {"fixture": fid, "set": "both", "cases": cases,
                                             "samples": 1})["least"]
        if least is not None:
            brute[combo] = least["force"]
    assert brute, "no candidate has a push that works"
    ranked = sorted(brute.items(), key=lambda kv: (kv[1], kv[0]))
    assert len(designs) == min(20, len(ranked)), (len(designs), len(ranked))
    for d, (combo, force) in zip(designs, ranked):
        assert abs(d["least_push"]["force"] - force) <= 1e-9 * force, (d, combo, force)
        assert abs(-d["score"] - force) <= 1e-9 * force
    assert tuple(designs[0]["sites"]) == ranked[0][0]
    # The other objectives report the least push too when cases are given.
    m = client.result("fixture.design", {"body": body, "friction": 0.05, "sites": sites,
                                         "cases": cases, "top": 3})
    for d in m["designs"]:
        assert "least_push" in d
        combo = tuple(d["sites"])
        if d["least_push"] is not None:
            assert abs(d["least_push"]["force"] - brute[combo]) <= 1e-9 * brute[combo]
    e = client.error("fixture.design", {"body": body, "friction": 0.05, "sites": sites,
                                        "objective": "force"})
    assert e["data"]["field"] == "params.cases", e


def test_design_units_give_the_same_design_converted(client):
    """fixture.design's "units" as a fixture's: the same body in m/N, mm/N
    and in/lbf, its cases written in each, gives the same designs, each
    least push the same force converted (and its point scaled)."""
    lbf = 4.4482216152605
    vertices = [[0, 0], [4, 0], [4, 1], [3, 2], [0, 2]]
    sites = [[0.8, 0], [2, 0], [3.2, 0], [0, 0.6], [0, 1.4], [1.5, 2]]
    answers = []
    for scale, units, per_newton in ((1.0, {"length": "m", "force": "N"}, 1.0),
                                     (1000.0, {"length": "mm", "force": "N"}, 1.0),
                                     (1 / 0.0254, {"length": "in", "force": "lbf"}, 1 / lbf)):
        body = {"mass": 1.0, "shape": {"type": "polygon",
                                       "vertices": [[x * scale, y * scale] for x, y in vertices]}}
        cases = [case(gravity(G * scale)),
                 case(gravity(G * scale), {"force": [-2 * per_newton, -1 * per_newton],
                                           "at": [1 * scale, 2 * scale]})]
        r = client.result("fixture.design", {
            "body": body, "friction": 0.05, "units": units, "objective": "force",
            "cases": cases, "top": 6,
            "sites": [{"at": [x * scale, y * scale]} for x, y in sites]})
        answers.append((scale, per_newton, r["designs"]))
    _, _, base = answers[0]
    assert base and base[0]["least_push"] is not None
    for scale, per_newton, designs in answers[1:]:
        assert [d["sites"] for d in designs] == [d["sites"] for d in base]
        for d, b in zip(designs, base):
            want = b["least_push"]["force"]
            assert abs(d["least_push"]["force"] / per_newton - want) <= 1e-9 * want, (d, b)
            assert abs(-d["score"] / per_newton - want) <= 1e-9 * want, (d, b)
            for got, at in zip(d["least_push"]["at"], b["least_push"]["at"]):
                assert abs(got / scale - at) <= 1e-9 * 4, (d, b)
    # Without units the numbers are one consistent system: the m/N answer.
    plain = client.result("fixture.design", {
        "body": {"mass": 1.0, "shape": {"type": "polygon", "vertices": vertices}},
        "friction": 0.05, "objective": "force", "top": 6,
        "cases": [case(gravity()), case(gravity(), {"force": [-2, -1], "at": [1, 2]})],
        "sites": [{"at": s} for s in sites]})["designs"]
    assert [d["least_push"]["force"] for d in plain] == [d["least_push"]["force"] for d in base]
    e = client.error("fixture.design", {"body": {"mass": 1.0, "shape": {
        "type": "polygon", "vertices": vertices}}, "friction": 0.05,
        "units": {"length": "ft", "force": "N"}, "sites": [{"at": s} for s in sites]})
    assert e["data"]["field"] == "params.units.length", e


def test_push_force_samples_only_where_the_finger_pushes(client):
    """push.force's samples are null where the finger may not push (a loop
    push_on leaves out) or does not fit: the bracket's holes (12 and 10 mm
    wide, clients/python's loop_width) take no finger of radius 8, its
    outer boundary's straight edges away from the corners take any; and the
    samples that are given are F* there, push.force's with a point finger."""
    import json
    import sys
    sys.path.insert(0, os.path.join(REPO, "clients", "python"))
    import wrenchd
    with open(os.path.join(REPO, "examples", "bracket-upright.json")) as fh:
        f = json.load(fh)
    widths = [wrenchd.loop_width(loop) for loop in f["body"]["shape"]["loops"]]
    cut = [case(gravity(9810, 180), {"force": [30, -40], "at": [20, 60]})]
    point = client.result("push.force", {"fixture": f, "cases": cut, "samples": 16})
    big = client.result("push.force", {"fixture": f, "cases": cut, "samples": 16,
                                        "finger_radius": 8})
    outer = client.result("push.force", {"fixture": f, "cases": cut, "samples": 16,
                                          "push_on": "outer"})
    kept = 0
    for p, b, o in zip(point["segments"], big["segments"], outer["segments"]):
        if p["loop"] != 0:
            assert widths[p["loop"]] < 16
            assert all(v is None for v in b["force"]), b
            assert all(v is None for v in o["force"]), o
            continue
        assert o["force"] == p["force"]
        for v, w in zip(p["force"], b["force"]):
            assert w is None or w == v
            kept += w is not None
    assert kept > 0


# ---- the Python client ---------------------------------------------------------------


def test_python_client_functions(daemon, client):
    import sys
    sys.path.insert(0, os.path.join(REPO, "clients", "python"))
    import wrenchd
    f = plate_321(0.0)
    fid = client.result("fixture.put", {"fixture": f})["id"]
    with wrenchd.Client(daemon.path) as c:
        r = c.force_range(fid, [[gravity()]], push={"at": [4, 1.5]}, sets=["goal"])
        assert r == client.result("force.range", {"fixture": fid, "cases": [case(gravity())],
                                                  "push": {"at": [4, 1.5]}, "sets": ["goal"]})
        assert abs(r["all"]["goal"]["intervals"][0][1] - 2 * G) < 1e-12 * G
        p = c.push_force(fid, [{"name": "g", "loads": [gravity()]}], set="strong", samples=8)
        assert p == client.result("push.force", {"fixture": fid, "set": "strong", "samples": 8,
                                                 "cases": [case(gravity(), name="g")]})
        regions = c.push_regions(fid, "goal", force=5.0, cases=[[gravity()]])
        want = client.result("push.regions", {"fixture": fid, "set": "goal", "force": 5.0,
                                              "cases": [case(gravity())]})
        assert [[x.t0, x.t1] for x in regions.regions] == [[x["t0"], x["t1"]]
                                                           for x in want["regions"]]
        d = c.design(FX.chamfered_plate()["body"], 0.05, spacing=0.9, objective="force",
                     cases=[[gravity()]], top=2)
        assert d.designs and d.designs[0].least_push is not None
        with pytest.raises(ValueError):
            c.force_range(fid, [[gravity()]])
        # push_on: the clients' default on a part with holes is the outer
        # boundary for a point finger; given, as sent.
        with open(os.path.join(REPO, "examples", "bracket-upright.json")) as fh:
            import json
            upright = json.load(fh)
        cut = [case(gravity(9810, 180), {"force": [30, -40], "at": [20, 60]})]
        for push_on, sent in ((None, "outer"), ("all", "all"), ([0, 2], [0, 2])):
            got = c.push_force(upright, cut, push_on=push_on, samples=4)
            assert got == client.result("push.force", {"fixture": upright, "cases": cut,
                                                       "set": "both", "samples": 4,
                                                       "push_on": sent})
        s = c.friction_sweep(upright, range=(0, 0.4), force={"set": "both"}, cases=cut)
        want = client.result("friction.sweep", {"fixture": upright, "range": [0, 0.4],
                                                "kinetic_ratio": 1.0, "cases": cut,
                                                "force": {"set": "both", "push_on": "outer"}})
        assert s.curve == want["curve"] and s.at == want["at"]
        assert s.intervals == want["intervals"] and s.exact is False
        with pytest.raises(ValueError):
            c.friction_sweep(upright, force=True)
        d2 = c.design(upright["body"], 0.25, sites=[f["at"] for f in upright["fixels"]],
                      objective="force", cases=[[gravity(9810, 180)]], push_on="all",
                      units=upright["units"])
        d3 = client.result("fixture.design", {
            "body": upright["body"], "friction": 0.25, "units": upright["units"],
            "sites": [{"at": f["at"]} for f in upright["fixels"]], "objective": "force",
            "push_on": "all", "fixels": 3, "top": 10, "cases": [case(gravity(9810, 180))]})
        assert [d.least_push for d in d2.designs] == [d["least_push"] for d in d3["designs"]]


def test_readme_how_hard_to_push(client):
    """The README's numbers (section "How hard to push"), as the daemon
    gives them today."""
    with open(os.path.join(REPO, "examples", "bracket-upright.json")) as fh:
        import json
        f = json.load(fh)
    cuts = [case(gravity(9810, 180), {"force": [30, -40], "at": [x, 60]}, name="x%d" % x)
            for x in (20, 40, 60, 80, 100)]
    alone = client.result("push.force", {"fixture": f, "cases": [case(gravity(9810, 180))]})
    assert "%.9g" % alone["least"]["force"] == "3.96122186"
    r = force_range(client, f, cuts, push={"at": [30, 60]}, sets=["strong", "both"])
    assert "%.9g" % r["all"]["strong"]["least"] == "23.4403564"
    assert "%.9g" % r["all"]["both"]["least"] == "199.844546"
    best = client.result("push.force", {"fixture": f, "cases": cuts})["least"]
    assert "%.8g" % best["force"] == "47.702833"
    finger = client.result("push.force", {"fixture": f, "cases": cuts, "finger_radius": 8})
    assert "%.9g" % finger["least"]["force"] == "168.925751"
    # A point finger on the outer boundary only (the clients' default push_on).
    outer = client.result("push.force", {"fixture": f, "cases": cuts, "push_on": "outer"})
    assert "%.9g" % outer["least"]["force"] == "168.925751"
    assert outer["least"]["loop"] == 0 and best["loop"] != 0


# ---- friction.sweep: the least force against mu ---------------------------------------


def test_friction_sweep_least_force_against_push_force(client):
    import copy
    f = FX.chamfered_plate(0.05)
    cases = [case(gravity()), case(gravity(), {"force": [-2, -1], "at": [1, 2]})]
    r = client.result("friction.sweep", {"fixture": f, "range": [0, 0.4], "kinetic_ratio": 0.8,
                                         "force": {"set": "both"}, "cases": cases})
    assert set(r) == {"curve", "at", "intervals", "exact", "resolution"} and r["exact"] is False
    curve = r["curve"]
    mus = [p[0] for p in curve]
    grid = [i * (0.4 / 127) for i in range(127)] + [0.4]
    ends = [e for iv in r["intervals"] for e in iv]
    # The grid and the push alone's interval ends, increasing.
    assert mus == sorted(set(grid) | set(ends)) and len(r["at"]) == len(curve)
    assert abs(r["resolution"] - 0.4 / 127) < 1e-15
    finite = [p for p in curve if p[1] is not None]
    assert finite and len(finite) < len(curve), "the push stops working as mu grows"
    # The intervals: where the push alone has a region, exactly (push.regions
    # with the fixture at mu, just inside and just outside every end), and
    # the least force is finite on them.
    assert r["intervals"] and r["intervals"][0][1] < 0.4, r
    for lo, hi in r["intervals"]:
        for mu, inside in ((lo + 1e-7, True), (hi - 1e-7, True), (lo - 1e-7, False),
                           (hi + 1e-7, False), ((lo + hi) / 2, True)):
            if not 0 <= mu <= 0.4 or (mu < 1e-7 and not inside) or (
                    mu > 0.4 - 1e-7 and not inside):
                continue
            g = copy.deepcopy(f)
            g["friction"] = {"static": mu, "kinetic": 0.8 * mu}
            regions = client.result("push.regions", {"fixture": g, "set": "both"})["regions"]
            assert bool(regions) == inside, (mu, lo, hi)
        assert all(p[1] is not None for p in curve if lo <= p[0] <= hi)
    # Each sample's point against force.range there: its least over all the
    # cases for the set is the sample's force.
    for (mu, least), at in list(zip(curve, r["at"]))[::9]:
        assert (least is None) == (at is None)
        if at is None:
            continue
        g = copy.deepcopy(f)
        g["friction"] = {"static": mu, "kinetic": 0.8 * mu}
        got = force_range(client, g, cases, push={"at": at}, sets=["both"])["all"]["both"]
        assert got["least"] is not None and abs(got["least"] - least) <= 1e-9 * least, (
            mu, least, got)
    # Each sample is push.force's least on the fixture at that mu.
    for mu, least in curve[::16] + [curve[-1]]:
        g = copy.deepcopy(f)
        g["friction"] = {"static": mu, "kinetic": 0.8 * mu}
        want = client.result("push.force", {"fixture": g, "set": "both", "cases": cases,
                                            "samples": 1})["least"]
        if want is None:
            assert least is None, (mu, least)
        else:
            assert least is not None and abs(least - want["force"]) <= 1e-12 * want["force"], (
                mu, least, want)
    for params, field in (({"force": {}}, "params.cases"),
                          ({"push": {"set": "both"}, "cases": cases}, "params.cases"),
                          ({"force": {"set": "all"}, "cases": cases}, "params.force.set"),
                          ({"force": {"finger_friction": 0.1}, "cases": cases},
                           "params.force.finger_friction")):
        got = error_of(client, "friction.sweep", dict(params, fixture=f))
        assert got[0] == field, (params, got)


def test_cases_read_from_text_as_from_the_tree(client):
    """force.range reads a request's cases from its text, a batch member's
    from the tree: the same answer, byte for byte, for the common shape
    written every way JSON allows (white space, member order, exponents,
    names in UTF-8) and for every shape the text reader leaves to the tree
    (escapes, members twice or unknown, wrong types, refused loads)."""
    fid = client.result("fixture.put", {"fixture": plate_321(0.2)})["id"]
    push = '{"at":[4,1.5]}'
    texts = [
        '[{"name":"a","loads":[{"gravity":{"g":9.81,"direction_deg":270}},'
        '{"force":[-2.5e0,-3],"at":[1.25,2]}]}]',
        ' [ { "loads" : [ { "direction_deg" : 270 , "g" : 981E-2 } ] } ] '.replace(
            '{ "direction_deg"', '{ "gravity" : { "direction_deg"').replace('} ] }', '} } ] }'),
        '[{"loads":[{"at":[2,2],"force":[0.1,-1e-3],"name":"cutter"}],"name":"b\u00e9"}]',
        '[{"loads":[{"wrench":[1,-2,0.5]}]},{"name":"c","loads":[{"wrench":[-1,-2,-0.5]}]}]',
        '[{"name":"tab\\tbed","loads":[{"wrench":[1,-2,0.5]}]}]',
        '[{"na\\u006de":"x","loads":[{"wrench":[1,-2,0.5]}]}]',
        '[{"name":"x","name":"y","loads":[{"wrench":[1,-2,0.5]}]}]',
        '[{"name":1,"loads":[{"wrench":[1,-2,0.5]}]}]',
        '[{"loads":[{"wrench":[1,-2,0.5]}],"extra":0}]',
        '[{"loads":[{"wrench":[1,-2]}]}]',
        '[{"loads":[{"gravity":{"g":-9.81,"direction_deg":270}}]}]',
        '[{"loads":[{"gravity":{"g":9.81}}]}]',
        '[{"loads":[{"force":[1,0],"at":[400,1]}]}]',
        '[{"loads":[{"force":[1,0]}]}]',
        '[{"loads":[{"wrench":[1e308,0,0]},{"wrench":[1e308,0,0]}]}]',
        '[{"loads":[{"wrench":[1,0,0],"gravity":{"g":1,"direction_deg":0}}]}]',
        '[{"loads":[]}]',
        '[]',
        '{}',
        '[{"loads":[' + ','.join(['{"wrench":[0,-1,0]}'] * 101) + ']}]',
        '[' + ','.join(['{"loads":[{"wrench":[0,-1,0]}]}'] * 1001) + ']',
    ]
    for k, cases in enumerate(texts):
        one = '{"jsonrpc":"2.0","id":%d,"method":"force.range","params":{"fixture":"%s",' \
              '"push":%s,"cases":%s}}' % (k, fid, push, cases)
        client.send_line(one)
        alone = client.read_line()
        client.send_line("[" + one + "]")
        member = client.read_line()
        assert member == b"[" + alone + b"]", (cases[:200], alone[:300], member[:300])
        answer = json.loads(alone)
        if k < 4:
            assert "result" in answer, (cases, answer)
        else:
            assert "result" in answer or \
                answer["error"]["data"]["field"].startswith("params.cases"), (cases, answer)


C_FORCE_SWEEP = r'''
#include "wrenchclient.h"
#include <stdio.h>
int main(int argc, char **argv)
{
    wrc_client *c = wrc_connect(argv[1], 60000, 0, NULL);
    const wrc_load loads[] = {{.kind = WRC_LOAD_GRAVITY, .g = 9.81, .direction_deg = 270},
                              {.kind = WRC_LOAD_FORCE, .force = {-1, -2}, .at = {1, 2}}};
    wrc_force_sweep_request r = {.set = "both", .range = {0, 0.5}, .push_on = "all"};
    static double curve[400][2], at[400][2];
    wrc_force_curve s;
    if (!c || wrc_force_sweep(c, argv[2], loads, 2, &r, curve, at, 400, &s) != WRC_OK)
        return 1;
    for (int i = 0; i < s.sample_count; i++)
        printf("%.17g %.17g %.17g %.17g\n", curve[i][0], curve[i][1], at[i][0], at[i][1]);
    for (int i = 0; i < s.interval_count; i++)
        printf("interval %.17g %.17g\n", s.intervals[i][0], s.intervals[i][1]);
    wrc_close(c);
    return 0;
}
'''


def test_c_client_force_sweep_reads_what_the_daemon_answers(client, tmp_path):
    """wrc_force_sweep against the daemon: every sample's mu, least force
    and point, and the intervals, as the JSON answer holds them (nulls as
    NaN), printed to 17 digits and read back the same doubles."""
    fixture = json.load(open(os.path.join(REPO, "examples", "plate-3-2-1.json")))
    fixture = fixture.get("fixture", fixture)
    fid = client.result("fixture.put", {"fixture": fixture})["id"]
    run = run_client_program(tmp_path, "force_sweep", C_FORCE_SWEEP, client.path, fid)
    assert run.returncode == 0, run
    out = run.stdout.split("\n")
    want = client.result("friction.sweep", {
        "fixture": fid, "range": [0, 0.5], "force": {"set": "both", "push_on": "all"},
        "cases": [case(gravity(), {"force": [-1, -2], "at": [1, 2]})]})
    nan = float("nan")
    rows = [[float(x) for x in line.split()] for line in out if line and
            not line.startswith("interval")]
    intervals = [[float(x) for x in line.split()[1:]] for line in out
                 if line.startswith("interval")]
    assert len(rows) == len(want["curve"]) > 100
    for row, (mu, force), point in zip(rows, want["curve"], want["at"]):
        expect = [mu, nan if force is None else force] + (point or [nan, nan])
        assert all(a == b or (math.isnan(a) and math.isnan(b)) for a, b in zip(row, expect)), \
            (row, expect)
    assert any(not math.isnan(r[1]) for r in rows)
    assert intervals == want["intervals"]
