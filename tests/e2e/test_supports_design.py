"""On a base plate: the buttons' witness forces on the wire, and
fixture.design ranked by the least push on the plate (docs/PROTOCOL.md,
"Supports" and fixture.design; docs/MODEL.md section 11).

The witness is checked by physics computed here: Newton-Euler with the
fixels' and the supports' forces (M q = g + sum W c + sum (f_i, r_i x f_i)),
each sliding support's force against its own acceleration with magnitude
mu_k N_i, each sticking one within mu_s N_i, the normal forces a
distribution of the weight and the clamps. The design's ranking is
checked by brute force: every candidate put as a fixture and asked
push.force on the plate, one by one."""

import itertools
import json
import math
import os
import subprocess
import sys

import pytest

import model as M
import fixtures as FX
from conftest import REPO

from test_supports import BUTTONS, G, error_of, on_buttons, plate

PLATE_BUTTONS = [[1, 0.5], [3, 0.5], [2, 1.7]]


# ---- the witness's forces ------------------------------------------------------------------

def check_support_witness(fixture, g, witness, pressing):
    """The witness of a motion on supports against physics: returns the
    number of supports found sliding and sticking. `pressing` is the total
    normal force and its centre (weight and clamps, in the force unit)."""
    mdl = M.Model(fixture)
    s = fixture["supports"]
    fr = s["friction"]
    mu_s = fr if not isinstance(fr, dict) else fr["static"]
    mu_k = fr if not isinstance(fr, dict) else fr.get("kinetic", fr["static"])
    points = s["points"]
    q = witness["acceleration"]
    forces = witness["forces"]
    sf = witness["support_forces"]
    normals = witness["support_normals"]
    assert len(sf) == len(points) and len(normals) == len(points), witness
    # Newton-Euler: M q / k - sum W c - sum (f_i, r_i x f_i) = g.
    ne = list(mdl.newton_euler(q, forces))
    for p, f in zip(points, sf):
        w = mdl.force_wrench(f, p)
        ne = [a - b for a, b in zip(ne, w)]
    size = 1 + M.norm(g) + sum(abs(x) for f in sf for x in f) + sum(normals)
    assert all(abs(a - b) <= 1e-6 * size for a, b in zip(ne, g)), (ne, g, witness)
    # The distribution: non-negative, the total and the centre of pressure.
    total, centre = pressing
    assert all(n >= -1e-9 * total for n in normals), normals
    assert abs(sum(normals) - total) <= 1e-7 * total, (normals, total)
    for j in range(2):
        moment = sum(n * p[j] for n, p in zip(normals, points))
        assert abs(moment - total * centre[j]) <= 1e-7 * total * (1 + abs(centre[j])), normals
    # Each support: sliding against its acceleration with mu_k N_i, or
    # sticking within mu_s N_i. Its acceleration a_i = a + alpha z x r_i
    # (the part's acceleration in the fixture's length unit per s^2).
    sliding = sticking = 0
    speed = max(math.hypot(q[0], q[1]), abs(q[2]) * mdl.rho, 1e-300)
    for p, f, n in zip(points, sf, normals):
        r = (p[0] - mdl.com[0], p[1] - mdl.com[1])
        a = (q[0] - q[2] * r[1], q[1] + q[2] * r[0])
        if math.hypot(*a) > 1e-7 * speed:
            sliding += 1
            u = (a[0] / math.hypot(*a), a[1] / math.hypot(*a))
            expected = (-mu_k * n * u[0], -mu_k * n * u[1])
            assert math.hypot(f[0] - expected[0], f[1] - expected[1]) <= 1e-6 * (1 + mu_k * n), (
                "a sliding support's force %r is not -mu_k N a/|a| = %r" % (f, expected))
        else:
            sticking += 1
            assert math.hypot(*f) <= mu_s * n * (1 + 1e-7) + 1e-9, (f, n)
    return sliding, sticking


def classify_strong(client, fixture, wrenches):
    r = client.result("wrench.classify", {"fixture": fixture, "wrenches": wrenches,
                                          "sets": ["strong"]})
    return [x["strong"] for x in r["results"]]


def test_plate_witness_forces_against_a_cutting_force(client):
    """The 3-2-1 plate on three buttons (m = 2, mu_B = 0.2, a clamp D at the
    centre of mass) under a cutting force F_c along +x below the least
    clamp: the witness is the translation a_x = (F_c - mu_B W) / m
    (docs/MODEL.md section 11), every button sliding against +x with
    mu_B N_i, the N_i the weight's barycentric shares."""
    mu_b, cutting = 0.2, 30.0
    d = 0.9 * (cutting / mu_b - 2 * G)
    f = on_buttons(plate(), PLATE_BUTTONS, mu_b, down=[{"at": [2, 1], "force": d}])
    (v,) = classify_strong(client, f, [[cutting, 0, 0]])
    assert v["verdict"] == "outside", v
    w = v["witness"]
    total = 2 * G + d
    sliding, sticking = check_support_witness(f, [cutting, 0, 0], w, (total, (2, 1)))
    assert (sliding, sticking) == (3, 0)
    assert abs(w["acceleration"][0] - (cutting - mu_b * total) / 2) < 1e-6, w
    # The barycentric shares of (2, 1) in the buttons' triangle: 7/24,
    # 7/24 and 10/24 of W.
    for n, share in zip(w["support_normals"], (7 / 24, 7 / 24, 10 / 24)):
        assert abs(n - share * total) < 1e-7 * total, w["support_normals"]
    for sfi, n in zip(w["support_forces"], w["support_normals"]):
        assert abs(sfi[0] + mu_b * n) < 1e-7 * total and abs(sfi[1]) < 1e-7 * total, sfi


@pytest.mark.parametrize("buttons,friction", [
    (PLATE_BUTTONS, 0.2),
    (PLATE_BUTTONS, {"static": 0.3, "kinetic": 0.2}),
    # Four buttons: the normal forces are indeterminate; the witness's are
    # one admissible distribution.
    ([[0.5, 0.3], [3.5, 0.3], [3.5, 1.7], [0.5, 1.7]], {"static": 0.25, "kinetic": 0.15}),
])
def test_witness_forces_by_newton_euler(client, buttons, friction):
    """Loads that turn and push the plate off its locators: each witness
    holds Newton-Euler with the supports' forces, and each support slides
    against its own acceleration or sticks within its disc."""
    f = on_buttons(plate(), buttons, friction)
    wrenches = [[30, 0, 0], [0, 0, -40], [-5, 30, 10], [20, 20, -30], [0, 0, 25],
                [-25, 10, 0], [10, -3, 30]]
    answers = classify_strong(client, f, wrenches)
    moved = turned = 0
    for g, v in zip(wrenches, answers):
        if v["verdict"] != "outside":
            assert v["witness"] is None or v["verdict"] == "boundary", v
            continue
        moved += 1
        check_support_witness(f, g, v["witness"], (2 * G, (2, 1)))
        turned += abs(v["witness"]["acceleration"][2]) > 1e-6
    assert moved >= 4 and turned >= 2, (moved, turned, answers)


def test_witness_of_a_pivot_on_a_button(client):
    """The trapezoid (0,0) (4,0) (5,2) (0,2), m = 2, on buttons (0, 0.5),
    (3, 0.5), (2, 1.7), mu_B = 0.15, pulled by (0, s) at its corner (0, 0):
    above s* = 0.973422201 (docs/MODEL.md section 11) it turns about the
    second button, which sticks within its disc while the others slide."""
    f = {"name": "trapezoid", "body": {"mass": 2.0, "shape": {"type": "polygon", "vertices":
                                                               [[0, 0], [4, 0], [5, 2], [0, 2]]}},
         "friction": {"static": 0.3, "kinetic": 0.25},
         "fixels": [{"at": [1, 0]}, {"at": [3, 0]}, {"at": [0, 1]}]}
    f = on_buttons(f, [[0, 0.5], [3, 0.5], [2, 1.7]], 0.15)
    com = M.Model(f).com
    s = 0.973422201 * 1.001
    g = [0, s, (0 - com[0]) * s]
    (v,) = classify_strong(client, f, [g])
    assert v["verdict"] == "outside", v
    total = 2 * G
    sliding, sticking = check_support_witness(f, g, v["witness"], (total, com))
    assert (sliding, sticking) == (2, 1), v["witness"]


def test_witness_forces_in_newtons(client):
    """The disc in millimetres and newtons on three buttons, pushed off its
    fixel along +x: the supports' forces and normals in N (the normals sum
    to m g = 9.81 N, not 9810 kg mm/s^2), Newton-Euler in N."""
    mu_b = 0.3
    f = FX.disc_corner_mm()
    f = on_buttons(f, [[1000 * x, 1000 * y] for x, y in BUTTONS], mu_b, g=9810)
    (v,) = classify_strong(client, f, [[10.0, 1.0, 0]])
    assert v["verdict"] == "outside", v
    w = v["witness"]
    check_support_witness(f, [10.0, 1.0, 0], w, (G, (0, 0)))
    assert abs(sum(w["support_normals"]) - G) < 1e-7
    assert set(w) >= {"support_forces", "support_normals"}


def test_no_support_members_without_supports(client):
    r = client.result("wrench.classify", {"fixture": plate(), "wrenches": [[30, 0, 0]],
                                          "sets": ["strong"]})
    w = r["results"][0]["strong"]["witness"]
    assert set(w) == {"acceleration", "forces", "wrench", "friction"}, w


def test_clients_show_the_witness_forces(daemon, client, tmp_path):
    """wrenchctl prints the supports' forces under a verdict; the Python
    client returns them."""
    mu_b, cutting = 0.2, 30.0
    f = on_buttons(plate(), PLATE_BUTTONS, mu_b)
    sys.path.insert(0, os.path.join(REPO, "clients", "python"))
    import wrenchd
    with wrenchd.Client(daemon.path, timeout=60) as c:
        (r,) = c.classify(f, [[cutting, 0, 0]], sets=["strong"])
        w = r["strong"].witness
        assert len(w.support_forces) == 3 and len(w.support_normals) == 3
        assert abs(sum(w.support_normals) - 2 * G) < 1e-7
        assert all(abs(sf[0] + mu_b * n) < 1e-7 for sf, n in zip(w.support_forces,
                                                                  w.support_normals))
    path = tmp_path / "plate-on-buttons.json"
    path.write_text(json.dumps(f))
    env = dict(os.environ, WRENCHD_SOCKET=daemon.path)
    run = subprocess.run([os.path.join(REPO, "build", "wrenchctl"), "classify", str(path),
                          "%g,0,0" % cutting, "--sets", "strong"],
                         capture_output=True, text=True, env=env, timeout=60)
    assert "the supports' friction" in run.stdout, run.stdout + run.stderr
    # Each button slides against +x with mu_B N_i: N = 7/24, 7/24, 10/24 of W.
    for share in (7 / 24, 7 / 24, 10 / 24):
        n = 2 * G * share
        assert "(%g, %g) of N = %g" % (-mu_b * n, 0, n) in run.stdout.replace("-0)", "0)"), \
            run.stdout


# ---- fixture.design on the plate -----------------------------------------------------------

CHAMFER = [[0, 0], [4, 0], [4, 1], [3, 2], [0, 2]]
CHAMFER_BUTTONS = [[1, 0.5], [3, 0.5], [1.5, 1.6]]
# Six sites on the chamfered plate (m = 2): two on the bottom, two on the
# left, one on the top, one on the right: C(6, 3) = 20 candidates, sites
# 0, 1, 2 the plate's own 3-2-1 fixels (examples/plate-chamfered.json).
SITES = [{"at": [1, 0], "normal": [0, 1]}, {"at": [3, 0], "normal": [0, 1]},
         {"at": [0, 0.5], "normal": [1, 0]}, {"at": [0, 1.5], "normal": [1, 0]},
         {"at": [1.5, 2], "normal": [0, -1]}, {"at": [4, 0.5], "normal": [-1, 0]}]
# Four of them whose four candidates all seat on the plate.
FOUR = [SITES[i] for i in (1, 3, 4, 5)]
NONE = [{"loads": [{"wrench": [0, 0, 0]}]}]
FRICTION = 0.1


def chamfer_body():
    return {"mass": 2.0, "shape": {"type": "polygon", "vertices": CHAMFER}}


def plate_supports(mu_b=0.2, g=G):
    return {"points": CHAMFER_BUTTONS, "friction": mu_b, "g": g}


def design(client, **extra):
    params = {"body": chamfer_body(), "friction": FRICTION, "sites": SITES, "fixels": 3,
              "objective": "force", "cases": NONE, "top": 20, "supports": plate_supports()}
    params.update(extra)
    return long_result(client, "fixture.design", params)


def long_result(client, method, params):
    """A call whose answer may take longer than the harness's read timeout
    (each candidate's least push on the plate is thousands of LPs)."""
    req = client.request(method, params)
    client.send(req)
    resp = client.read_json(timeout=900)
    assert resp.get("id") == req["id"] and "result" in resp, resp
    return resp["result"]


def brute_force(client, supports, cases=NONE):
    """Every candidate put as a fixture on the supports and asked push.force
    (set goal): {sites: least force or None}, and the unpinned ones."""
    least, unpinned = {}, set()
    for combo in itertools.combinations(range(len(SITES)), 3):
        fixture = {"name": "candidate", "body": chamfer_body(), "friction": {"static": FRICTION},
                   "fixels": [SITES[i] for i in combo], "supports": supports}
        put = client.call("fixture.put", {"fixture": fixture})
        if "error" in put:
            assert put["error"]["data"]["field"].startswith("params.fixture.fixels"), put
            continue  # degenerate
        if not put["result"]["pinned"]:
            unpinned.add(combo)
            continue
        r = client.result("push.force", {"fixture": put["result"]["id"],
                                          "set": "goal", "cases": cases, "samples": 1})
        least[combo] = r["least"]["force"] if r["least"] else None
    return least, unpinned


def test_design_on_the_plate_ranks_by_push_force_as_brute_force(client):
    """The design's ranking and figures are push.force's on the plate for
    every candidate, asked one by one: the same candidates scored, in the
    order of their least seating push, each score minus it."""
    supports = plate_supports()
    least, unpinned = brute_force(client, supports)
    scored = {c: f for c, f in least.items() if f is not None}
    assert len(scored) >= 5, least
    # The plate's own fixels: docs/MODEL.md's least push on three buttons,
    # mu_B = 0.2, checked there against 256-gon LPs: 10.6650.
    assert abs(scored[(0, 1, 2)] - 10.6650) < 1e-4, scored
    r = design(client)
    designs = r["designs"]
    got = {tuple(d["sites"]): d for d in designs}
    assert set(got) == set(scored), (sorted(got), sorted(scored))
    assert r["counts"]["unpinned"] == len(unpinned)
    assert r["counts"]["no_seating_push"] == sum(1 for f in least.values() if f is None)
    for combo, force in scored.items():
        d = got[combo]
        assert abs(-d["score"] - force) <= 1e-9 * force, (combo, d["score"], force)
        push = d["least_push"]
        assert push["set"] == "goal" and abs(push["force"] - force) <= 1e-9 * force
        assert push["lower_bound"] <= push["force"] * (1 + 1e-12)
        # The figures of directions are not made on the plate.
        assert not {"best_push", "goal_length", "both_length", "gravity_goal_deg",
                    "critical_mu"} & set(d), d
    order = sorted(scored, key=lambda c: (scored[c], c))
    ranked = [tuple(d["sites"]) for d in designs]
    # Ties within the solver's tolerance may order either way.
    for a, b in zip(ranked, ranked[1:]):
        assert scored[a] <= scored[b] * (1 + 1e-9), (a, b)
    assert abs(scored[ranked[0]] - scored[order[0]]) <= 1e-9 * scored[order[0]]
    assert "symmetries" not in r


def test_least_push_on_the_plate_scales_with_the_friction(client):
    """With no load S grows linearly with mu_B W and the excluded cones are
    cones, so F u avoids C + k S iff (F / k) u avoids C + S: every least
    push doubles with mu_B, and again with g (W = m g), and the ranking
    stays."""
    base = design(client, sites=FOUR)["designs"]
    doubled = design(client, sites=FOUR, supports=plate_supports(0.4))["designs"]
    heavy = design(client, sites=FOUR, supports=plate_supports(0.2, 2 * G))["designs"]
    assert len(base) == 4
    assert [d["sites"] for d in base] == [d["sites"] for d in doubled] == \
        [d["sites"] for d in heavy]
    for a, b, c in zip(base, doubled, heavy):
        fa = a["least_push"]["force"]
        assert abs(b["least_push"]["force"] - 2 * fa) <= 2e-6 * fa, (a, b)
        assert abs(c["least_push"]["force"] - 2 * fa) <= 2e-6 * fa, (a, c)


def test_design_on_the_plate_in_chunks_and_shards(client):
    """Two shards' designs are together the whole search's."""
    whole = design(client, sites=FOUR)["designs"]
    parts = []
    for i in range(2):
        parts += design(client, sites=FOUR, shard=[i, 2])["designs"]
    key = lambda d: (-d["score"], d["candidate"])
    assert [(d["candidate"], d["score"]) for d in sorted(parts, key=key)] == \
        [(d["candidate"], d["score"]) for d in whole]


def test_accuracy_on_the_plate_reports_the_least_push(client):
    """Objective accuracy does not depend on magnitudes: the same ranking as
    the floating part's; each design kept also reports its least push on
    the plate, push.force's."""
    params = {"objective": "accuracy", "tolerance": 0.01, "top": 5}
    floating = long_result(client, "fixture.design", dict(
        {"body": chamfer_body(), "friction": FRICTION, "sites": SITES, "fixels": 3,
         "cases": NONE}, **params))["designs"]
    on_plate = design(client, **params)["designs"]
    assert [(d["sites"], d["score"]) for d in on_plate] == \
        [(d["sites"], d["score"]) for d in floating]
    d = on_plate[0]
    fixture = {"name": "best", "body": chamfer_body(), "friction": {"static": FRICTION},
               "fixels": d["fixels"], "supports": plate_supports()}
    r = client.result("push.force", {"fixture": fixture, "set": "goal", "cases": NONE})
    if r["least"] is None:
        assert d["least_push"] is None
    else:
        assert abs(d["least_push"]["force"] - r["least"]["force"]) <= 1e-9 * r["least"]["force"]


@pytest.mark.parametrize("extra,field,words", [
    ({"objective": "margin"}, "params.objective", "force"),
    ({"objective": "region"}, "params.objective", "force"),
    ({"objective": "gravity"}, "params.objective", "force"),
    ({"objective": "pareto", "tolerance": 0.01}, "params.objective", "accuracy"),
    ({"finger_radius": 0.1}, "params.finger_radius", "point finger"),
    ({"finger_friction": 0.2}, "params.finger_friction", "point finger"),
    ({"fixel_tolerance": {"position": 0.01}}, "params.fixel_tolerance", "supports"),
    ({"supports": {"points": CHAMFER_BUTTONS[:2], "friction": 0.2, "g": G}},
     "params.supports.points", "at least 3"),
    ({"supports": {"points": CHAMFER_BUTTONS[:2] + [[5, 1]], "friction": 0.2, "g": G}},
     "params.supports.points[2]", "outside the part"),
    ({"supports": {"points": CHAMFER_BUTTONS, "friction": -0.2, "g": G}},
     "params.supports.friction", "negative"),
    ({"supports": {"points": CHAMFER_BUTTONS, "friction": 0.2, "g": -1}},
     "params.supports.g", ">= 0"),
    ({"supports": {"points": CHAMFER_BUTTONS, "friction": 0.2, "g": G,
                   "down": [{"at": [9, 0], "force": 1}]}},
     "params.supports.down[0].at", "outside the part"),
    ({"supports": {"points": CHAMFER_BUTTONS, "friction": 0.2, "g": G, "extra": 1}},
     "params.supports.extra", ""),
    ({"supports": [1, 2]}, "params.supports", ""),
])
def test_design_on_the_plate_refusals_name_the_field(client, extra, field, words):
    params = {"body": chamfer_body(), "friction": FRICTION, "sites": SITES, "fixels": 3,
              "objective": "force", "cases": NONE, "supports": plate_supports()}
    params.update(extra)
    got, reason = error_of(client, "fixture.design", params)
    assert got == field, (got, reason)
    assert words in reason, reason


def test_design_on_a_circle_on_the_plate_refused(client):
    body = {"mass": 1.0, "shape": {"type": "circle", "center": [0, 0], "radius": 1.0}}
    got, reason = error_of(client, "fixture.design", {
        "body": body, "friction": 0.5, "spacing": 1.0, "fixels": 2, "objective": "force",
        "cases": NONE, "supports": {"points": BUTTONS, "friction": 0.3, "g": G}})
    assert got == "params.body.shape" and "polygon" in reason, (got, reason)


def test_clients_design_on_the_plate(daemon, client, tmp_path):
    """wrenchctl design --supports and the Python client's design(supports=)
    send the plate: the same designs and least pushes as the daemon's
    answer; the table says a seating push is ranked; the fixture emitted
    stands on the plate."""
    expected = design(client, sites=FOUR)["designs"]
    sys.path.insert(0, os.path.join(REPO, "clients", "python"))
    import wrenchd
    with wrenchd.Client(daemon.path, timeout=300) as c:
        got = c.design(chamfer_body(), FRICTION, sites=FOUR, objective="force", cases=NONE,
                       top=20, supports=plate_supports())
        assert [(d.sites, d.score) for d in got.designs] == \
            [(d["sites"], d["score"]) for d in expected]
        assert got.designs[0].best_push is None and got.designs[0].least_push["set"] == "goal"
    part = tmp_path / "part.json"
    part.write_text(json.dumps({"name": "chamfer", "body": chamfer_body(),
                                "friction": {"static": FRICTION},
                                "fixels": [{"at": s["at"], "normal": s["normal"]} for s in FOUR]}))
    emitted = tmp_path / "best.json"
    env = dict(os.environ, WRENCHD_SOCKET=daemon.path)
    run = subprocess.run([os.path.join(REPO, "build", "wrenchctl"), "design", str(part),
                          "--objective", "force", "--case", "wrench=0,0,0",
                          "--supports", json.dumps(plate_supports()),
                          "--emit-fixture", "1", str(emitted), "--svg", str(tmp_path / "d.svg")],
                         capture_output=True, text=True, env=env, timeout=300)
    assert run.returncode == 0, run.stdout + run.stderr
    assert "seats the part on its supports" in run.stdout, run.stdout
    for d in expected:
        assert "least push on the plate %.9g" % d["least_push"]["force"] in run.stdout, run.stdout
    # The picture draws each least push on the plate, not a both region.
    svg = (tmp_path / "d.svg").read_text()
    assert "seats the part on its supports" in svg and 'class="region"' not in svg, svg[:2000]
    assert "least push %.6g on the plate" % expected[0]["least_push"]["force"] in svg
    best = json.loads(emitted.read_text())
    assert best["supports"]["points"] == CHAMFER_BUTTONS
    r = client.result("push.force", {"fixture": best, "set": "goal", "cases": NONE,
                                     "samples": 1})
    assert abs(r["least"]["force"] - expected[0]["least_push"]["force"]) <= \
        1e-9 * r["least"]["force"]
    # Shards merged by design-merge print the same least pushes on the plate.
    lines = []
    for i in range(2):
        shard = subprocess.run([os.path.join(REPO, "build", "wrenchctl"), "design", str(part),
                                "--objective", "force", "--case", "wrench=0,0,0",
                                "--supports", json.dumps(plate_supports()),
                                "--shard", "%d/2" % i],
                               capture_output=True, text=True, env=env, timeout=300)
        assert shard.returncode == 0, shard.stderr
        lines.append(tmp_path / ("shard%d.jsonl" % i))
        lines[-1].write_text(shard.stdout)
    merged = subprocess.run([os.path.join(REPO, "build", "wrenchctl"), "design-merge"] +
                            [str(p) for p in lines], capture_output=True, text=True, timeout=60)
    assert "seats the part on its supports" in merged.stdout, merged.stdout + merged.stderr
    for d in expected:
        assert "least push on the plate %.9g" % d["least_push"]["force"] in merged.stdout
    bad = subprocess.run([os.path.join(REPO, "build", "wrenchctl"), "design", str(part),
                          "--objective", "force", "--case", "wrench=0,0,0", "--supports", "[1]"],
                         capture_output=True, text=True, env=env, timeout=60)
    assert bad.returncode != 0 and "--supports" in bad.stderr, bad.stderr
