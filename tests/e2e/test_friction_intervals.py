"""Friction intervals (docs/PROTOCOL.md, "Friction intervals"): the field
forms and their refusals, ids of point friction unchanged, and robust
answers checked against the daemon's own answers for point-friction
fixtures sampled from the box (its physical corners and random points), and
against the witness's friction."""

import copy
import itertools
import math
import random

import pytest

import fixtures as FX
import helpers as H
import model as M
from conftest import FIGURES


def figure(key, n=1):
    FIGURES[key] = FIGURES.get(key, 0) + n


def put_error(client, fixture):
    e = client.error("fixture.put", {"fixture": fixture})
    assert e["code"] == -32602, e
    return e["data"]["field"], e["data"]["reason"]


# ---- the field forms --------------------------------------------------------------

@pytest.mark.parametrize("friction, field, words", [
    ({"static": [0.4, 0.2]}, "params.fixture.friction.static", "empty"),
    ({"static": [-0.1, 0.2]}, "params.fixture.friction.static[0]", "negative"),
    ({"static": [0.1, 2000]}, "params.fixture.friction.static[1]", "above 1000"),
    ({"static": [0.1]}, "params.fixture.friction.static", "interval"),
    ({"static": [0.1, 0.2, 0.3]}, "params.fixture.friction.static", "interval"),
    ({"static": [0.1, "0.2"]}, "params.fixture.friction.static[1]", "number"),
    ({"static": [0.2, 0.35], "kinetic": [0.3, 0.2]}, "params.fixture.friction.kinetic",
     "empty"),
    ({"static": [0.2, 0.35], "kinetic": [0.1, 0.4]}, "params.fixture.friction.kinetic[1]",
     "upper bound 0.4 exceeds"),
    ({"static": [0.2, 0.35], "kinetic": [0.25, 0.3]}, "params.fixture.friction.kinetic[0]",
     "lower bound 0.25 exceeds"),
    ({"static": [0.2, 0.35], "kinetic": 0.25}, "params.fixture.friction.kinetic",
     "lower bound 0.25 exceeds"),
    ({"static": 0.3, "kinetic": [0.1, 0.4]}, "params.fixture.friction.kinetic[1]",
     "exceeds"),
])
def test_invalid_intervals_are_named(client, friction, field, words):
    f = FX.disc_corner(0.5)
    f["friction"] = friction
    got_field, reason = put_error(client, f)
    assert got_field == field, (got_field, reason)
    assert words in reason, reason


def test_invalid_fixel_interval_is_named(client):
    f = FX.rectangle_321(0.3)
    f["friction"] = {"static": [0.2, 0.35], "kinetic": [0.15, 0.3]}
    f["fixels"][2]["friction"] = {"static": [0.1, 0.3], "kinetic": [0.05, 0.31]}
    field, reason = put_error(client, f)
    assert field == "params.fixture.fixels[2].friction.kinetic[1]", (field, reason)


def test_point_friction_keeps_its_id_and_form(client):
    """A scalar and the interval [a, a] are one fixture: one id, the explicit
    form with scalars; kinetic left out is static's whole interval."""
    plain = FX.disc_corner(0.5, kinetic=0.3)
    r = client.result("fixture.put", {"fixture": plain})
    pointed = copy.deepcopy(plain)
    pointed["friction"] = {"static": [0.5, 0.5], "kinetic": [0.3, 0.3]}
    assert client.result("fixture.put", {"fixture": pointed})["id"] == r["id"]
    form = client.result("fixture.get", {"id": r["id"]})
    for fx in form["fixels"]:
        assert fx["friction"] == {"static": 0.5, "kinetic": 0.3}, form

    wide = FX.disc_corner(0.5)
    wide["friction"] = {"static": [0.2, 0.35]}
    w = client.result("fixture.put", {"fixture": wide})
    spelled = copy.deepcopy(wide)
    spelled["friction"] = {"static": [0.2, 0.35], "kinetic": [0.2, 0.35]}
    assert client.result("fixture.put", {"fixture": spelled})["id"] == w["id"]
    form = client.result("fixture.get", {"id": w["id"]})
    for fx in form["fixels"]:
        assert fx["friction"] == {"static": [0.2, 0.35], "kinetic": [0.2, 0.35]}, form
    again = client.result("fixture.put", {"fixture": form})
    assert again["id"] == w["id"]
    # a different interval is a different fixture
    other = copy.deepcopy(wide)
    other["friction"] = {"static": [0.2, 0.35], "kinetic": [0.15, 0.3]}
    assert client.result("fixture.put", {"fixture": other})["id"] != w["id"]


# ---- the disc in the corner (docs/MODEL.md section 7.1) ------------------------

@pytest.mark.parametrize("a, b", [(0.2, 0.5), (0.0, 0.3), (0.4, 0.45)])
def test_disc_corner_push_arc_is_the_arc_at_the_upper_bound(client, a, b):
    """G_goal's strings use static friction only: the robust push arc is the
    arc at the upper bound, (atan b, 90 deg - atan b), and the gravity arc
    likewise (180 deg + atan b, 270 deg - atan b)."""
    f = FX.disc_corner(0.5)
    f["friction"] = {"static": [a, b]}
    r = client.result("push.regions", {"fixture": f, "set": "goal"})
    assert len(r["regions"]) == 1, r
    reg = r["regions"][0]
    lo, hi = math.degrees(math.atan(b)), 90 - math.degrees(math.atan(b))
    assert abs(reg["t0"] - lo) < 1e-9 and abs(reg["t1"] - hi) < 1e-9, (reg, lo, hi)
    g = client.result("gravity.sweep", {"fixture": f, "set": "goal"})["intervals_deg"]
    assert len(g) == 1 and abs(g[0][0] - (180 + lo)) < 1e-9 and abs(g[0][1] - (180 + hi)) < 1e-9, g
    # the same as the point fixture at b
    point = FX.disc_corner(b)
    assert client.result("push.regions", {"fixture": point, "set": "goal"})["regions"] == \
        r["regions"]


# ---- robust answers against sampling the box -----------------------------------

def with_intervals(rnd, fixture):
    """The fixture with per-fixel intervals: static [s0, s1], kinetic [k0,
    k1] with k0 <= s0 and k1 <= s1 (sometimes above s0), sometimes a point,
    sometimes kinetic left out.  Returns (fixture, boxes), boxes[i] =
    (s0, s1, k0, k1)."""
    f = copy.deepcopy(fixture)
    f.pop("friction", None)
    boxes = []
    for fx in f["fixels"]:
        s0, s1 = sorted(round(rnd.uniform(0, 0.9), 3) for _ in range(2))
        if rnd.random() < 0.15:
            k0, k1 = s0, s1
            fx["friction"] = {"static": [s0, s1]}
        else:
            k0 = round(s0 * rnd.random(), 3)
            k1 = k0 if rnd.random() < 0.2 else round(k0 + (s1 - k0) * rnd.random(), 3)
            fx["friction"] = {"static": [s0, s1], "kinetic": [k0, k1]}
        boxes.append((s0, s1, k0, k1))
    return f, boxes


def at_friction(fixture, pairs):
    """The fixture with point friction (mu_s, mu_k) per fixel."""
    f = copy.deepcopy(fixture)
    for fx, (s, k) in zip(f["fixels"], pairs):
        fx["friction"] = {"static": s, "kinetic": k}
    return f


def samples(rnd, boxes, extra=6):
    """The box's corners with mu_k <= mu_s (every value of each interval is
    attained among them), then random points of that part of the box."""
    per_fixel = []
    for s0, s1, k0, k1 in boxes:
        per_fixel.append(sorted({(s, k) for s in (s0, s1) for k in (k0, k1) if k <= s}))
    out = [list(c) for c in itertools.product(*per_fixel)]
    for _ in range(extra):
        pt = []
        for s0, s1, k0, k1 in boxes:
            s = rnd.uniform(s0, s1)
            pt.append((s, min(rnd.uniform(k0, k1), s)))
        out.append(pt)
    return out


def classify(client, fixture, wrenches, sets=("goal", "strong"), **params):
    p = {"fixture": fixture, "wrenches": wrenches, "sets": list(sets)}
    p.update(params)
    return client.result("wrench.classify", p)["results"]


def base_fixtures(rnd, n):
    out = []
    for i in range(n):
        if i % 3 == 2:
            out.append(FX.random_polygon(rnd, convex=True, corner=(i % 2 == 0)))
        else:
            out.append(FX.random_disc(rnd, corner=(i % 2 == 0)))
    return [f for f in out if len(f["fixels"]) <= 3]


@pytest.mark.parametrize("seed", [1, 2, 3])
def test_robust_answers_are_the_union_over_the_box(client, seed):
    rnd = random.Random(1700 + seed)
    for base in base_fixtures(rnd, 6):
        fixture, boxes = with_intervals(rnd, base)
        k = len(boxes)
        wrenches = [[rnd.uniform(-1, 1) for _ in range(3)] for _ in range(40)]
        # pushes into the fixels (against their normals), so that some
        # answers are inside
        mdl = M.Model(at_friction(fixture, [(b[1], b[3]) for b in boxes]))
        for _ in range(20):
            w = [0.0, 0.0, 0.0]
            for fx in mdl.fixels:
                lam = rnd.uniform(0.1, 1.0)
                w = [w[i] - lam * fx.Wn[i] for i in range(3)]
            wrenches.append([x + rnd.uniform(-0.05, 0.05) for x in w])
        robust = classify(client, fixture, wrenches)
        lp = classify(client, fixture, wrenches, method="lp")
        points = samples(rnd, boxes)
        figure("friction-interval samples", len(points))
        sampled = [classify(client, at_friction(fixture, pt), wrenches) for pt in points]
        # goal strings use only the static upper bounds
        top = classify(client, at_friction(fixture, [(b[1], b[2]) for b in boxes]), wrenches,
                       sets=("goal",))
        for j, g in enumerate(wrenches):
            for s in ("goal", "strong"):
                v = robust[j][s]
                least = min(answer[j][s]["margin"] for answer in sampled)
                assert v["margin"] <= least + 1e-9, (fixture, g, s, v, least)
                if v["verdict"] == "inside":
                    assert all(answer[j][s]["inside"] for answer in sampled), (fixture, g, s)
                    figure("friction-interval robust inside")
                if v["margin"] < least - 1e-6:
                    figure("friction-interval margins below every sample")
                if s == "goal":
                    assert abs(v["margin"] - top[j]["goal"]["margin"]) <= 1e-12, (
                        fixture, g, v, top[j])
                if abs(v["margin"]) > 1e-6:
                    assert lp[j][s]["inside"] == v["inside"], (fixture, g, s, v, lp[j][s])
                for answer in (v, lp[j][s]):
                    if answer["witness"] is None:
                        continue
                    check_robust_witness(client, fixture, boxes, g, s, answer)
                figure("friction-interval answers")


@pytest.mark.parametrize("seed", [4, 5])
def test_robust_disturbance_margins_and_regions(client, seed):
    """stability.margin of a bias is at most that of every sampled point
    fixture; a push region point (its midpoint) of the robust fixture is in
    a region at every sample."""
    rnd = random.Random(1800 + seed)
    for base in base_fixtures(rnd, 6):
        fixture, boxes = with_intervals(rnd, base)
        mdl = M.Model(at_friction(fixture, [(b[1], b[3]) for b in boxes]))
        bias = [0.0, 0.0, 0.0]
        for fx in mdl.fixels:
            lam = rnd.uniform(0.1, 1.0)
            bias = [bias[i] - lam * fx.Wn[i] for i in range(3)]
        robust = client.result("stability.margin", {"fixture": fixture, "bias": bias})
        points = samples(rnd, boxes, extra=3)
        regions = client.result("push.regions", {"fixture": fixture, "set": "both"})["regions"]
        for pt in points:
            point = at_friction(fixture, pt)
            there = client.result("stability.margin", {"fixture": point, "bias": bias})
            if robust["margin"] is not None and there["margin"] is not None:
                assert robust["margin"] <= there["margin"] + 1e-9, (fixture, pt, robust, there)
                figure("friction-interval disturbance margins compared")
            sample_regions = client.result("push.regions", {"fixture": point, "set": "both"})
            for reg in regions:
                mid = (reg["t0"] + reg["t1"]) / 2
                assert any(r["edge"] == reg["edge"] and r["t0"] <= mid <= r["t1"]
                           for r in sample_regions["regions"]), (fixture, pt, reg)
                figure("friction-interval region midpoints checked")


def check_robust_witness(client, fixture, boxes, g, s, v):
    """The witness's friction lies in its intervals, is null for s, a, u and
    the static upper bound for n, m; at it (a point fixture) the witness
    satisfies its letters and makes its wrench, and an outside wrench is
    not inside there either."""
    name = v["blocking"]
    letters = name.rstrip("+-")
    friction = v["witness"]["friction"]
    pairs = []
    for x, mu, (s0, s1, k0, k1) in zip(letters, friction, boxes):
        if x in "sau":
            assert mu is None, (name, friction)
            pairs.append((s1, k0))
        elif x in "nm":
            assert mu == s1, (name, friction, boxes)
            pairs.append((s1, k0))
        else:
            assert k0 <= mu <= k1, (name, friction, boxes)
            pairs.append((s1, mu))
    point = at_friction(fixture, pairs)
    exact = v["verdict"] == "outside"
    H.check_witness(M.Model(point), g, name, v["witness"], exact=exact)
    if exact and v["margin"] is not None:
        there = classify(client, point, [g], sets=(s,))[0][s]
        assert there["margin"] <= 1e-7, (point, g, s, v, there)
        figure("friction-interval witnesses re-classified")


def test_sliding_uses_the_kinetic_interval(client):
    """The disc in the corner, static 0.4, kinetic [0.1, 0.4]: the wrench the
    wall's force (c_n, c_t) = (1, -0.25) makes on the resting disc is in the
    closure of the mode "ls" (sliding up the wall, leaving the floor) only
    at kinetic friction 0.25, inside the interval.  Robustly it is outside
    G_strong, blocked by "ls", whose witness names 0.25; at the point 0.25
    the wrench is only on the boundary, and the robust margin is the depth
    in the union, here that at 0.1."""
    f = FX.disc_corner(0.4)
    f["friction"] = {"static": 0.4, "kinetic": [0.1, 0.4]}
    mdl = M.Model(at_friction(f, [(0.4, 0.25), (0.4, 0.25)]))
    g = list(mdl.newton_euler([0, 0, 0], [[1.0, -0.25], [0.0, 0.0]]))
    robust = classify(client, f, [g], sets=("strong",))[0]["strong"]
    assert robust["verdict"] == "outside" and robust["blocking"] == "ls", robust
    friction = robust["witness"]["friction"]
    assert abs(friction[0] - 0.25) < 1e-9 and friction[1] is None, robust
    cn, ct = robust["witness"]["forces"][0]
    assert cn > 0 and abs(ct + 0.25 * cn) < 1e-9 * cn, robust
    margins = {}
    for kin in (0.1, 0.2, 0.25, 0.3, 0.4):
        point = at_friction(f, [(0.4, kin), (0.4, kin)])
        margins[kin] = classify(client, point, [g], sets=("strong",))[0]["strong"]["margin"]
    assert abs(margins[0.25]) < 1e-12, margins
    assert robust["margin"] < -0.1, robust
    assert abs(robust["margin"] - min(margins.values())) < 1e-12, (robust, margins)
