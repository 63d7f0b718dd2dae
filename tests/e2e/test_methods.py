"""Every method's answers, with numbers derived from docs/MODEL.md (sections 2-5,
7) and the seed's counts -- closed forms where it gives them, otherwise the
independent model in model.py."""

import json
import math
import os
import re

import pytest

import fixtures as FX
import helpers as H
import model as M
from conftest import REPO

ID_RE = re.compile(r"^[0-9a-f]{32}$")


def classifier_for(fixture):
    mdl = M.Model(fixture)
    return mdl, M.Classifier(mdl)


def classify(client, fixture, wrenches, **params):
    p = {"fixture": fixture, "wrenches": [list(w) if isinstance(w, tuple) else w
                                          for w in wrenches]}
    p.update(params)
    res = client.result("wrench.classify", p)
    assert set(res) == {"results"}, res
    assert len(res["results"]) == len(wrenches), res
    return res["results"]


# ---- fixture.put ---------------------------------------------------------------

def test_put_disc_corner_counts(client):
    """k = 2: k 2^(k-1) = 4 kept strings (seed eq. 6); figure 8: nine modes;
    rolling at both fixels pins the disc."""
    r = client.result("fixture.put", {"fixture": FX.disc_corner(0.5)})
    assert set(r) == {"id", "name", "fixels", "goal_cones", "strong_cones", "pinned",
                      "area", "com", "inertia"}, r
    assert ID_RE.match(r["id"]), r
    assert r["name"] == "disc-corner"
    # The unit disc's mass properties in use: pi, its centre, m r^2 / 2.
    assert H.close(r["area"], math.pi, 1e-15), r
    assert r["com"] == [0, 0], r
    assert H.close(r["inertia"], FX.disc_corner(0.5)["body"]["mass"] / 2, 1e-15), r
    assert H.count_of(r["fixels"]) == 2
    assert H.count_of(r["goal_cones"]) == 4
    assert H.count_of(r["strong_cones"]) == 9
    assert r["pinned"] is True


def test_put_rectangle_counts(client):
    """k = 3: twelve kept strings (seed section 4); the modes of the model."""
    f = FX.rectangle_321(0.3)
    _, cl = classifier_for(f)
    r = client.result("fixture.put", {"fixture": f})
    assert ID_RE.match(r["id"]), r
    assert H.count_of(r["fixels"]) == 3
    assert H.count_of(r["goal_cones"]) == 12
    assert H.count_of(r["strong_cones"]) == len(cl.modes) == 11
    assert r["pinned"] is True


def test_put_single_fixel_not_pinned(client):
    r = client.result("fixture.put", {"fixture": FX.disc_one_fixel()})
    assert H.count_of(r["goal_cones"]) == 1
    # s, l, r and the two pivots n+ and n-
    assert H.count_of(r["strong_cones"]) == 5
    assert r["pinned"] is False


# ---- wrench.classify: docs/MODEL.md section 7 closed forms ---------------------------------

@pytest.mark.parametrize("mu", [0.0, 0.25, 0.5, 0.9, 1.0, 1.5])
def test_disc_corner_goal_margin_closed_form(client, mu):
    """The margin of (-1, -1, 0) for G_goal is (1 - mu) / sqrt(2 (1 + mu^2)):
    the sine of the angle between (-1, -1) and the wedge's edge (-1, -mu)
    (inside for mu < 1; the same formula is minus the depth in G_sm for
    mu > 1; 0, a boundary, at mu = 1)."""
    f = FX.disc_corner(mu)
    expected = (1 - mu) / math.sqrt(2 * (1 + mu * mu))
    (r,) = classify(client, f, [[-1, -1, 0]], sets=["goal"])
    assert set(r) == {"goal"}
    v = r["goal"]
    assert v["margin"] == pytest.approx(expected, abs=1e-9)
    if mu < 1:
        assert v["verdict"] == "inside" and v["inside"] is True
        assert v["blocking"] is None and v["witness"] is None and v["states"] == []
    elif mu == 1:
        assert v["verdict"] == "boundary" and v["inside"] is False
        assert v["blocking"] in ("sm", "ms")
    else:
        assert v["verdict"] == "outside" and v["inside"] is False
        # (-1,-1) lies in both G_sm and G_ms, equally deep
        assert v["blocking"] in ("sm", "ms")
        assert sorted(v["states"]) == (["01", "11"] if v["blocking"] == "sm" else ["10", "11"])
    mdl, cl = classifier_for(f)
    H.check_value(mdl, cl, (-1, -1, 0), "goal", v)


@pytest.mark.parametrize("mu", [0.2, 0.5, 0.8])
def test_disc_corner_goal_wedge(client, mu):
    """G_goal = {f_x < 0, f_y < 0, |f_x| > mu |f_y|, |f_y| > mu |f_x|}, any
    tau: the open wedge of force directions (180 + atan mu, 270 - atan mu)
    degrees.  Directions every 5 degrees (off the wedge's edges), three
    torques each; margins against the model."""
    f = FX.disc_corner(mu)
    lo = 180 + math.degrees(math.atan(mu))
    hi = 270 - math.degrees(math.atan(mu))
    wrenches, expect = [], []
    for k in range(72):
        theta = 2.5 + 5 * k
        if min(abs(theta - lo), abs(theta - hi)) < 0.5:
            continue
        for tau in (0.0, 0.7, -3.0):
            wrenches.append((math.cos(math.radians(theta)), math.sin(math.radians(theta)), tau))
            expect.append(lo < theta < hi)
    results = classify(client, f, wrenches, sets=["goal"])
    mdl, cl = classifier_for(f)
    for g, inside, r in zip(wrenches, expect, results):
        v = r["goal"]
        assert v["verdict"] == ("inside" if inside else "outside"), (g, v)
        H.check_value(mdl, cl, g, "goal", v)


def test_readme_numbers_and_counterexample(client):
    """docs/MODEL.md section 4's counterexample, mu = 0.5: g = (-1, -1, -100) seats the
    disc (inside G_goal) but spins it, sliding at both fixels: outside
    G_strong, blocked by mode ll.  Margins: +-0.1 * 0.316228 (the force part
    of the normalised scaled wrench is 0.01 of it)."""
    f = FX.disc_corner(0.5)
    mdl, cl = classifier_for(f)
    wrenches = [(-1, -1, 0), (-1, -0.2, 0), (-1, -1, -100)]
    results = classify(client, f, wrenches, sets=["goal", "strong", "both"])
    expected = [
        (0.316228, "inside", None, 0.577350, "inside", None),
        (-0.263117, "outside", "ms", 0.160128, "inside", None),
        (0.0031621, "inside", None, -0.0031621, "outside", "ll"),
    ]
    for g, r, (gm, gv, gb, sm, sv, sb) in zip(wrenches, results, expected):
        assert set(r) == {"goal", "strong", "both"}, r
        assert r["goal"]["margin"] == pytest.approx(gm, abs=2e-6), (g, r)
        assert r["goal"]["verdict"] == gv and r["goal"]["blocking"] == gb, (g, r)
        assert r["strong"]["margin"] == pytest.approx(sm, abs=2e-6), (g, r)
        assert r["strong"]["verdict"] == sv and r["strong"]["blocking"] == sb, (g, r)
        assert r["both"]["margin"] == pytest.approx(min(gm, sm), abs=2e-6), (g, r)
        for s in ("goal", "strong", "both"):
            H.check_value(mdl, cl, g, s, r[s])
    # ms comes from states 10 (self) and 11 (fixel 2 breaks)
    assert sorted(results[1]["goal"]["states"]) == ["10", "11"]
    assert results[2]["both"]["verdict"] == "outside"
    assert results[2]["both"]["blocking"] == "ll"
    assert results[2]["strong"]["states"] == []


def test_zero_wrench(client):
    """docs/MODEL.md section 5: the zero wrench has margin 0, seats nothing (goal:
    outside) and, as no moving mode of the disc in a corner admits it
    (every mode needs c = 0 and then q = 0), is inside G_strong."""
    (r,) = classify(client, FX.disc_corner(0.5), [[0, 0, 0]], sets=["goal", "strong", "both"])
    assert r["goal"]["margin"] == 0 and r["goal"]["verdict"] == "outside", r
    assert r["goal"]["inside"] is False and r["goal"]["blocking"] in ("su", "us", "sm", "ms")
    assert r["strong"]["margin"] == 0 and r["strong"]["verdict"] == "inside", r
    assert r["strong"]["inside"] is True and r["strong"]["blocking"] is None
    assert r["both"]["margin"] == 0 and r["both"]["verdict"] == "outside", r


@pytest.mark.parametrize("k", [1e-300, 1e-160, 1e-100, 1e-6, 1e6, 1e100, 1e160, 1e300])
def test_scale_invariance(client, k):
    """Every G_X is a cone and the margin is taken on the normalised wrench
    (docs/MODEL.md section 5): k g has g's verdict and margin for any finite k > 0."""
    f = FX.disc_corner(0.5)
    base = [(1, 1, 0), (-1, -1, 0), (-1, -0.2, 0), (-1, -1, -100), (0.3, -1, 2)]
    ref = classify(client, f, base, sets=["goal", "strong"])
    scaled = classify(client, f, [[k * x for x in g] for g in base], sets=["goal", "strong"])
    for g, a, b in zip(base, ref, scaled):
        for s in ("goal", "strong"):
            assert b[s]["verdict"] == a[s]["verdict"], (k, g, s, a[s], b[s])
            assert b[s]["margin"] == pytest.approx(a[s]["margin"], abs=1e-9), (k, g, s, b[s])
            assert b[s]["blocking"] == a[s]["blocking"], (k, g, s, a[s], b[s])


@pytest.mark.parametrize("length,mass", [(1e-3, 1e-3), (1e3, 1e3), (1e6, 2.0), (0.01, 50.0)])
def test_units_do_not_matter(client, length, mass):
    """docs/MODEL.md section 5: the scaled metric does not depend on units.  The disc in a
    corner in other units (lengths x L, mass x m, inertia x m L^2), with
    forces x F and torques x F L: the same verdicts and margins."""
    F = mass * length  # any force unit will do
    base = [(-1, -1, 0), (-1, -0.2, 0), (-1, -1, -100), (0.3, -1, 2), (-0.2, -1, 0.4)]
    ref = classify(client, FX.disc_corner(0.5, kinetic=0.5), base, sets=["goal", "strong"])
    other = classify(client, FX.scaled_disc_corner(0.5, length, mass),
                     [[F * g[0], F * g[1], F * length * g[2]] for g in base],
                     sets=["goal", "strong"])
    for g, a, b in zip(base, ref, other):
        for s in ("goal", "strong"):
            assert b[s]["verdict"] == a[s]["verdict"], (g, s, a[s], b[s])
            assert b[s]["margin"] == pytest.approx(a[s]["margin"], abs=1e-9), (g, s, b[s])
            assert b[s]["blocking"] == a[s]["blocking"]


def test_eight_fixels(client):
    """The most fixels: k 2^(k-1) = 1024 kept strings.  Eight fixels on a
    disc's arc (200 to 305 degrees), normals radial: a contact's normal
    acceleration is n . a_c whatever alpha, so the moving modes are: all
    separating; one end fixel touching (l, r or n) with the rest separating
    (6); all sliding one way with a_c = 0 (2): nine, pinned."""
    f = FX.disc_corner(0.3)
    f["fixels"] = [{"at": [math.cos(math.radians(200 + 15 * i)),
                           math.sin(math.radians(200 + 15 * i))]} for i in range(8)]
    r = client.result("fixture.put", {"fixture": f})
    assert H.count_of(r["goal_cones"]) == 1024 and H.count_of(r["strong_cones"]) == 9, r
    m = client.result("modes.get", {"fixture": r["id"]})
    expected = ["s" * 8, "s" * 7 + "l", "s" * 7 + "r", "s" * 7 + "n", "l" + "s" * 7,
                "r" + "s" * 7, "n" + "s" * 7, "l" * 8, "r" * 8]
    assert sorted(m["feasible"]) == sorted(expected) and m["pinned"] is True, m
    p = client.result("plan.get", {"fixture": r["id"]})
    assert len(p["states"]) == 256 and len(p["cones"]) == 1024
    assert len(set(p["cones"])) == 1024
    res = classify(client, r["id"], [[0, 1, 0], [0.1, 1, 0.5], [0, -1, 0]], sets=["goal", "strong"])
    # pushing the disc straight up (+y) lifts it off every fixel
    assert res[0]["strong"]["verdict"] == "outside" and res[0]["strong"]["blocking"] == "s" * 8


def test_tolerance(client):
    """margin 0.316228 with tolerance 0.5 is a boundary answer: blocking names
    the nearest cone (sm or ms, equally near) and the witness makes g's
    projection onto it; tolerance 0 keeps it inside."""
    f = FX.disc_corner(0.5)
    mdl, cl = classifier_for(f)
    (r,) = classify(client, f, [[-1, -1, 0]], sets=["goal"], tolerance=0.5)
    v = r["goal"]
    assert v["verdict"] == "boundary" and v["inside"] is False, v
    assert v["margin"] == pytest.approx(0.316228, abs=2e-6)
    assert v["blocking"] in ("sm", "ms"), v
    H.check_value(mdl, cl, (-1, -1, 0), "goal", v, tol=0.5)
    (r,) = classify(client, f, [[-1, -1, 0]], sets=["goal"], tolerance=0)
    assert r["goal"]["verdict"] == "inside"
    # an outside wrench stays outside below its depth
    (r,) = classify(client, f, [[-1, -0.2, 0]], sets=["goal"], tolerance=0.2)
    assert r["goal"]["verdict"] == "outside"
    (r,) = classify(client, f, [[-1, -0.2, 0]], sets=["goal"], tolerance=0.3)
    assert r["goal"]["verdict"] == "boundary"


def test_default_and_chosen_sets(client):
    f = FX.disc_corner(0.5)
    (r,) = classify(client, f, [[-1, -1, 0]])
    assert set(r) == {"goal", "strong"}
    (r,) = classify(client, f, [[-1, -1, 0]], sets=["both"])
    assert set(r) == {"both"}
    (r,) = classify(client, f, [[-1, -1, 0]], sets=["strong", "both", "goal"])
    assert set(r) == {"goal", "strong", "both"}
    (r,) = classify(client, f, [[-1, -1, 0]], method="auto")
    assert set(r) == {"goal", "strong"}


# ---- wrench.classify against the model ---------------------------------------------

MODEL_FIXTURES = {
    "disc-corner-0.5": lambda: FX.disc_corner(0.5),
    "disc-corner-0.3-kinetic-0.1": lambda: FX.disc_corner(0.3, kinetic=0.1),
    "rectangle-321": lambda: FX.rectangle_321(0.3),
    "rectangle-321-clockwise": lambda: FX.rectangle_321(0.3, clockwise=True),
    "offset-disc": FX.offset_disc,
    "triangle": FX.triangle,
    "chamfer": FX.chamfered_plate,
    "one-fixel": FX.disc_one_fixel,
    "corner-fixel": FX.corner_fixel_plate,
}


@pytest.mark.parametrize("name", sorted(MODEL_FIXTURES))
def test_classify_matches_model(client, name):
    """Random wrenches (fixed seed): every verdict, margin (1e-7), blocking
    string, contact states and witness against the model."""
    f = MODEL_FIXTURES[name]()
    mdl, cl = classifier_for(f)
    wrenches = H.random_wrenches(seed=sum(map(ord, name)), n=30, scale=(1, 1, 2))
    fid = client.result("fixture.put", {"fixture": f})["id"]
    results = classify(client, fid, wrenches, sets=["goal", "strong", "both"])
    for g, r in zip(wrenches, results):
        for s in ("goal", "strong", "both"):
            H.check_value(mdl, cl, g, s, r[s])


@pytest.mark.parametrize("name", ["disc-corner-0.5", "rectangle-321", "offset-disc", "triangle",
                                  "one-fixel"])
def test_lp_agrees_with_auto(client, name):
    """method lp: verdicts by GLPK, no margin; they agree with auto wherever
    the margin is farther than 1e-6 from 0 (docs/MODEL.md section 5)."""
    f = MODEL_FIXTURES[name]()
    mdl, cl = classifier_for(f)
    wrenches = H.random_wrenches(seed=7 + len(name), n=30, scale=(1, 1, 2))
    auto = classify(client, f, wrenches, sets=["goal", "strong", "both"])
    lp = classify(client, f, wrenches, sets=["goal", "strong", "both"], method="lp")
    compared = 0
    for g, a, b in zip(wrenches, auto, lp):
        for s in ("goal", "strong", "both"):
            assert b[s]["margin"] is None, b
            if abs(a[s]["margin"]) > 1e-6:
                assert b[s]["verdict"] == a[s]["verdict"], (g, s, a[s], b[s])
                compared += 1
            H.check_value(mdl, cl, g, s, b[s], lp=True)
    assert compared >= 60


def test_force_at_point(client):
    """{"force", "at"} is the wrench (f_x, f_y, (at - com) x force), com =
    (0.2, 0.1) here: same answers as the explicit triple."""
    f = FX.offset_disc()
    mdl, cl = classifier_for(f)
    points = [((-1, -0.5), (0.6, 0.8)), ((0.3, -2.0), (-0.6, 0.8)), ((-2, -1), (0.0, 1.0)),
              ((1.5, 0.2), (-1, 0)), ((-0.4, -0.4), (0.70710678, 0.70710678))]
    objects = [{"force": list(fo), "at": list(at)} for fo, at in points]
    triples = [(fo[0], fo[1], (at[0] - 0.2) * fo[1] - (at[1] - 0.1) * fo[0])
               for fo, at in points]
    a = classify(client, f, objects, sets=["goal", "strong"])
    b = classify(client, f, triples, sets=["goal", "strong"])
    for g, ra, rb in zip(triples, a, b):
        for s in ("goal", "strong"):
            assert ra[s]["margin"] == pytest.approx(rb[s]["margin"], abs=1e-12), (g, ra, rb)
            assert ra[s]["verdict"] == rb[s]["verdict"]
            H.check_value(mdl, cl, g, s, ra[s])


def test_inline_fixture_is_not_stored(client):
    f = FX.rectangle_321(0.2)
    before = client.result("fixture.list", {})
    status = client.result("server.status", {})
    results = classify(client, f, [[0, -1, 0]])
    assert len(results) == 1
    assert client.result("fixture.list", {}) == before
    assert client.result("server.status", {})["fixtures"] == status["fixtures"]
    fid = client.result("fixture.put", {"fixture": f})["id"]
    assert classify(client, fid, [[0, -1, 0]]) == results


def test_defaults_com_inertia_normals(client):
    """com left out is the centroid, inertia left out the uniform body's
    about com (parallel axes), normals left out the inward normals: the same
    margins as when they are given."""
    implicit = FX.rectangle_321(0.3)
    explicit = FX.rectangle_321(0.3)
    explicit["body"]["com"] = [2, 1]
    explicit["body"]["inertia"] = (16 + 4) / 12.0
    explicit["fixels"][0]["normal"] = [0, 1]
    explicit["fixels"][1]["normal"] = [0, 1]
    explicit["fixels"][2]["normal"] = [1, 0]
    shifted = FX.rectangle_321(0.3)
    shifted["body"]["com"] = [2.5, 0.75]
    shifted_explicit = FX.rectangle_321(0.3)
    shifted_explicit["body"]["com"] = [2.5, 0.75]
    shifted_explicit["body"]["inertia"] = 20 / 12.0 + 0.25 + 0.0625
    disc = FX.disc_corner(0.5, inertia=None)  # uniform disc: m r^2 / 2 = 0.5
    wrenches = H.random_wrenches(seed=11, n=12, scale=(1, 1, 2))
    a = classify(client, implicit, wrenches, sets=["goal", "strong"])
    b = classify(client, explicit, wrenches, sets=["goal", "strong"])
    c = classify(client, shifted, wrenches, sets=["goal", "strong"])
    d = classify(client, shifted_explicit, wrenches, sets=["goal", "strong"])
    e = classify(client, disc, wrenches, sets=["goal", "strong"])
    e2 = classify(client, FX.disc_corner(0.5), wrenches, sets=["goal", "strong"])
    for i in range(len(wrenches)):
        for s in ("goal", "strong"):
            assert a[i][s]["margin"] == pytest.approx(b[i][s]["margin"], abs=1e-9)
            assert c[i][s]["margin"] == pytest.approx(d[i][s]["margin"], abs=1e-9)
            assert e[i][s]["margin"] == pytest.approx(e2[i][s]["margin"], abs=1e-9)


# ---- cone.get -----------------------------------------------------------------------

CONE_KEYS = {"constraints", "empty", "dimension", "halfspaces", "equalities", "generators",
             "strict"}


def cone_get(client, fixture, letters):
    r = client.result("cone.get", {"fixture": fixture, "constraints": letters})
    assert set(r) == CONE_KEYS, r
    assert r["constraints"] == letters
    assert len(r["strict"]) == len(r["halfspaces"]), r
    for row in r["halfspaces"] + r["equalities"] + r["generators"]:
        assert len(row) == 3 and abs(M.norm(row) - 1) < 1e-9, ("not a unit row", row, r)
    if not r["empty"]:
        assert len(r["equalities"]) == 3 - r["dimension"], r
    return r


def same_rows(got, expected, tol=1e-9):
    got = [tuple(x) for x in got]
    assert len(got) == len(expected), (got, expected)
    for e in expected:
        assert any(H.vec_close(g, e, tol) for g in got), ("missing row", e, got)


def check_generators(r, expected_cone):
    """The generators given generate the expected closed cone (physical
    units): each lies in it, and each expected generator lies in theirs."""
    gens = [tuple(g) for g in r["generators"]]
    theirs = M.Cone(gens)
    for g in gens:
        assert expected_cone.contains(g, 1e-8), ("generator outside the cone", g, r)
        for row in r["halfspaces"]:
            assert M.dot(row, g) <= 1e-9, ("generator violates a half-space", g, row)
        for row in r["equalities"]:
            assert abs(M.dot(row, g)) <= 1e-9, ("generator violates an equality", g, row)
    for g in expected_cone.generators:
        assert theirs.contains(g, 1e-8), ("the generators miss part of the cone", g, r)
        for row in r["halfspaces"]:
            assert M.dot(row, g) <= 1e-9, ("the half-spaces cut the cone", g, row, r)


def test_cone_ss_disc(client):
    """G_ss for the disc in a corner is {f_x >= 0, f_y >= 0} (docs/MODEL.md section 7; seed
    eq. 4): rows (-1, 0, 0), (0, -1, 0); tau is a lineality direction."""
    f = FX.disc_corner(0.5)
    r = cone_get(client, f, "ss")
    assert r["empty"] is False and r["dimension"] == 3, r
    same_rows(r["halfspaces"], [(-1, 0, 0), (0, -1, 0)])
    assert r["strict"] == [False, False]
    assert r["equalities"] == []
    same_rows(r["generators"], [(0, 0, 1), (0, 0, -1), (1, 0, 0), (0, 1, 0)])
    assert [tuple(g) for g in r["generators"][:2]] in ([(0, 0, 1), (0, 0, -1)],
                                                      [(0, 0, -1), (0, 0, 1)]), r


@pytest.mark.parametrize("mu", [0.0, 0.5, 2.0])
def test_cone_sm_ms_su_us_disc(client, mu):
    """From g = M q - W c (docs/MODEL.md section 7): G_su = {f_x >= 0}, G_us = {f_y >= 0},
    G_sm = {f_y <= 0, f_x >= mu f_y}, G_ms = {f_x <= 0, f_y >= mu f_x}."""
    f = FX.disc_corner(mu)
    s = math.sqrt(1 + mu * mu)
    expected = {
        "su": [(-1, 0, 0)],
        "us": [(0, -1, 0)],
        "sm": [(0, 1, 0), (-1 / s, mu / s, 0)],
        "ms": [(1, 0, 0), (mu / s, -1 / s, 0)],
    }
    mdl = M.Model(f)
    for letters, rows in expected.items():
        r = cone_get(client, f, letters)
        assert r["dimension"] == 3 and r["empty"] is False, r
        same_rows(r["halfspaces"], rows)
        assert r["strict"] == [False] * len(rows)
        check_generators(r, mdl.physical_cone(letters))


def test_cone_strict_face(client):
    """a (a_n < 0): G_au = {f_x < 0}, an open half-space: one row (1, 0, 0),
    strict.  G_sl has one open face, where fixel 2's sliding row a_t > 0 is
    tight (the model's face analysis)."""
    f = FX.disc_corner(0.5)
    r = cone_get(client, f, "au")
    assert r["dimension"] == 3 and r["empty"] is False
    same_rows(r["halfspaces"], [(1, 0, 0)])
    assert r["strict"] == [True]
    mdl = M.Model(f)
    for letters in ("sl", "ls", "sr", "ll", "rr", "aa"):
        r = cone_get(client, f, letters)
        faces = mdl.open_faces(letters)
        assert r["dimension"] == 3, r
        same_rows(r["halfspaces"], [row for row, _ in faces], 1e-8)
        for row, is_open in faces:
            i = [j for j, h in enumerate(r["halfspaces"]) if H.vec_close(h, row, 1e-8)][0]
            assert r["strict"][i] is is_open, (letters, row, is_open, r)
        check_generators(r, mdl.physical_cone(letters))
    assert sum(mdl.open_faces("sl")[i][1] for i in range(3)) == 1


def test_cone_empty(client):
    """lr on the disc in a corner: a_x = a_y = 0, then fixel 1 sliding left
    needs alpha < 0 and fixel 2 sliding right alpha > 0: no q at all."""
    for letters in ("lr", "rl"):
        r = cone_get(client, FX.disc_corner(0.5), letters)
        assert r["empty"] is True and r["dimension"] == -1, r


def test_cone_force_closure(client):
    """Fixels 90 degrees apart with mu = 1.5 (each friction cone, half-angle
    56 deg, holds the other fixel): force closure, G_nn is the whole wrench
    space (seed section 5): no half-space, no equality, a lineality basis
    with both signs."""
    f = FX.disc_corner(1.5)
    mdl = M.Model(f)
    assert mdl.physical_cone("nn").whole_space
    r = cone_get(client, f, "nn")
    assert r["empty"] is False and r["dimension"] == 3, r
    assert r["halfspaces"] == [] and r["strict"] == [] and r["equalities"] == [], r
    gens = [tuple(g) for g in r["generators"]]
    assert len(gens) == 6 and M.rank(gens) == 3, r
    for g in gens:
        assert any(H.vec_close(g, M.mul(-1, h), 1e-9) for h in gens), r
    # with mu = 0.5 the friction cones miss each other: not force closure
    r = cone_get(client, FX.disc_corner(0.5), "nn")
    assert r["dimension"] == 2 or r["halfspaces"], r
    check_generators(r, M.Model(FX.disc_corner(0.5)).physical_cone("nn"))


def test_cone_rectangle_against_model(client):
    """All twelve kept strings and a few others on the 3-2-1 plate: facets
    (full cones), dimension and the cone their generators span."""
    f = FX.rectangle_321(0.3)
    mdl = M.Model(f)
    _, kept, _ = M.plan(3)
    fid = client.result("fixture.put", {"fixture": f})["id"]
    for letters in kept + ["sss", "nnn", "mmm", "uuu", "mnu", "smn"]:
        r = cone_get(client, fid, letters)
        cone = mdl.physical_cone(letters)
        assert r["empty"] is False, r
        assert r["dimension"] == cone.dimension, (letters, r)
        if cone.dimension == 3:
            same_rows(r["halfspaces"], cone.facets, 1e-8)
        else:
            for row in r["equalities"]:
                for g in cone.generators:
                    assert abs(M.dot(row, g)) < 1e-9, (letters, row, r)
        check_generators(r, cone)
        assert r["strict"] == [False] * len(r["halfspaces"]), r


# ---- plan.get -----------------------------------------------------------------------

def check_plan(r, k):
    states, kept, _ = M.plan(k)
    assert set(r) == {"states", "cones"}, r
    assert [s["state"] for s in r["states"]] == [s for s, _ in states], r
    for got, (name, excluded) in zip(r["states"], states):
        assert set(got) == {"state", "excluded"}, got
        assert sorted(got["excluded"]) == sorted(excluded), (name, got)
        assert len(set(got["excluded"])) == len(got["excluded"]), got
    assert sorted(r["cones"]) == sorted(kept) and len(r["cones"]) == len(set(r["cones"]))
    assert len(r["cones"]) == k * 2 ** (k - 1)


def test_plan_two_fixels(client):
    """Seed eq. 6: G_goal excludes su, us, sm, ms; states 00: ss; 10: su, ms;
    01: us, sm; 11: ss, sm, ms."""
    r = client.result("plan.get", {"fixture": FX.disc_corner(0.5)})
    check_plan(r, 2)
    assert sorted(r["cones"]) == ["ms", "sm", "su", "us"]
    assert [(s["state"], sorted(s["excluded"])) for s in r["states"]] == [
        ("00", ["ss"]), ("10", ["ms", "su"]), ("01", ["sm", "us"]), ("11", ["ms", "sm", "ss"])]


def test_plan_three_fixels(client):
    """Seed section 4: eight states, twelve kept strings; 111 excludes every
    string over {s, m} but mmm (seven)."""
    r = client.result("plan.get", {"fixture": FX.rectangle_321()})
    check_plan(r, 3)
    last = r["states"][-1]
    assert last["state"] == "111" and len(last["excluded"]) == 7
    assert r["states"][0] == {"state": "000", "excluded": ["sss"]}
    assert sorted(r["states"][1]["excluded"]) == ["mss", "suu"]


def test_plan_one_and_four_fixels(client):
    r = client.result("plan.get", {"fixture": FX.disc_one_fixel()})
    check_plan(r, 1)
    assert r["cones"] == ["s"]
    four = FX.rectangle_321()
    four["fixels"].append({"at": [4, 1]})
    r = client.result("plan.get", {"fixture": four})
    check_plan(r, 4)


# ---- modes.get ----------------------------------------------------------------------

def test_modes_figure_8(client):
    """The seed's figure 8 (a disc against two fixels, not opposite): the
    feasible modes are exactly ss sl sr sn ls rs ns ll rr; pinned."""
    r = client.result("modes.get", {"fixture": FX.disc_corner(0.5)})
    assert set(r) == {"feasible", "pinned"}, r
    assert sorted(r["feasible"]) == sorted("ss sl sr sn ls rs ns ll rr".split()), r
    assert len(r["feasible"]) == 9 and r["pinned"] is True


def test_modes_rectangle(client):
    f = FX.rectangle_321(0.3)
    mdl, cl = classifier_for(f)
    r = client.result("modes.get", {"fixture": f})
    assert sorted(r["feasible"]) == sorted(cl.modes) and len(r["feasible"]) == len(cl.modes), r
    assert r["pinned"] is True


def test_modes_single_fixel_pivots(client):
    """One fixel does not pin the disc: s, l, r, and the pivots n+ and n-."""
    r = client.result("modes.get", {"fixture": FX.disc_one_fixel()})
    assert sorted(r["feasible"]) == sorted(["s", "l", "r", "n+", "n-"]), r
    assert r["pinned"] is False


# ---- docs/MODEL.md section 7: where to push ----------------------------------------------------

@pytest.mark.parametrize("mu", [0.0, 0.1, 0.3, 1.0])
def test_rectangle_no_goal_push(client, mu):
    """docs/MODEL.md section 7: a frictionless finger anywhere on the 3-2-1 plate's edges
    pushes toward the bottom or the left wall, never both: no push is inside
    G_goal, for any friction."""
    f = FX.rectangle_321(mu)
    mdl, cl = classifier_for(f)
    verts = f["body"]["shape"]["vertices"]
    wrenches = []
    for i in range(4):
        a, b = verts[i], verts[(i + 1) % 4]
        d = M.unit(M.sub(b, a))
        nu = (-d[1], d[0])  # counter-clockwise: the inward normal is on the left
        for j in range(1, 12):
            p = M.add(a, M.mul(j / 12, M.sub(b, a)))
            wrenches.append({"force": list(nu), "at": list(p)})
    results = classify(client, f, wrenches, sets=["goal"])
    for w, r in zip(wrenches, results):
        assert r["goal"]["verdict"] != "inside", (w, r)
        g = mdl.force_wrench(w["force"], w["at"])
        assert r["goal"]["margin"] == pytest.approx(cl.classify(g, "goal").margin, abs=1e-7)


def test_chamfer_push_seats(client):
    """docs/MODEL.md section 7: with a chamfer across the corner opposite the locators and
    little friction (0.05), pushing near its upper end seats the part; near
    its lower end it does not; with friction 0.3 nowhere on it."""
    for mu, inside in ((0.05, {7, 8, 9}), (0.3, set())):
        f = FX.chamfered_plate(mu)
        mdl, cl = classifier_for(f)
        nu = M.unit((-1, -1))
        wrenches = []
        for j in range(1, 10):
            p = M.add((4, 1), M.mul(j / 10, (-1, 1)))
            wrenches.append(mdl.force_wrench(nu, p))
        results = classify(client, f, wrenches, sets=["goal", "both"])
        got = {j + 1 for j, r in enumerate(results) if r["goal"]["verdict"] == "inside"}
        assert got == inside, (mu, results)
        for g, r in zip(wrenches, results):
            H.check_value(mdl, cl, g, "goal", r["goal"])
            H.check_value(mdl, cl, g, "both", r["both"])


# ---- server.status and unknown methods ------------------------------------------------------

def test_server_status(harness):
    d = harness.start("--threads", "3", "--cache-mb", "7")
    c = d.client()
    s = c.result("server.status", {})
    keys = {"version", "uptime_s", "fixtures", "cached", "cache_bytes", "cache_limit_bytes",
            "threads", "clients", "requests", "errors"}
    assert keys <= set(s), s  # (an undocumented extra member is tolerated)
    assert isinstance(s["version"], str) and s["version"]
    assert s["uptime_s"] >= 0
    assert s["fixtures"] == 0 and s["threads"] == 3
    assert s["cache_limit_bytes"] in (7 * 1048576, 7 * 1000000), s
    assert s["clients"] >= 1
    c.result("fixture.put", {"fixture": FX.disc_corner(0.5)})
    c.result("fixture.put", {"fixture": FX.rectangle_321(0.3)})
    c.result("fixture.put", {"fixture": FX.disc_corner(0.5, name="renamed")})
    c.error("no.such.method", {})
    c2 = d.client()
    t = c2.result("server.status", {})
    assert t["fixtures"] == 2, t
    assert t["cached"] >= 2 and t["cache_bytes"] > 0, t
    assert t["cache_bytes"] <= t["cache_limit_bytes"]
    assert t["clients"] >= 2, t
    assert t["requests"] >= s["requests"] + 5, (s, t)
    assert t["errors"] >= s["errors"] + 1, (s, t)
    assert t["uptime_s"] >= s["uptime_s"]
    # params may be left out when nothing is required
    c.send_line('{"jsonrpc":"2.0","method":"server.status","id":"x"}')
    r = c.read_json()
    assert r["id"] == "x" and "result" in r, r


@pytest.mark.parametrize("method", ["push.regions", "gravity.sweep", "stability.margin"])
def test_section_6_methods_served(client, method):
    """Once announced with -32601, now served: each answers the docs/MODEL.md section 7 disc."""
    params = {"fixture": FX.disc_corner(0.5), "set": "goal"}
    if method == "stability.margin":
        params = {"fixture": FX.disc_corner(0.5), "bias": [-1, -1, 0]}
    r = client.result(method, params)
    assert isinstance(r, dict) and r, r


def test_examples_loaded(harness):
    """The example fixtures load with --load; the chamfered plate's pushes
    of the README demo, against the model: at (3.25, 1.75) goal +0.188
    and strong +0.483; at (3.75, 1.25) goal -0.181 blocked by smu (from
    state 110)."""
    files = sorted(os.path.join(REPO, "examples", n) for n in os.listdir(
        os.path.join(REPO, "examples")) if n.endswith(".json"))
    args = []
    for p in files:
        args += ["--load", p]
    d = harness.start(*args)
    c = d.client()
    listed = c.result("fixture.list", {})["fixtures"]
    assert len(listed) == len(files)
    for p in files:
        with open(p) as fh:
            f = json.load(fh)
        fid = c.result("fixture.put", {"fixture": f})["id"]
        assert fid in [x["id"] for x in listed]
        if "supports" in f:
            continue  # the floating model does not apply: test_supports.py
        if f["body"].get("shape", {}).get("type") == "outline":
            # model.py knows no outlines; the explicit form gives what it
            # needs (com, inertia, every normal) without the shape, whose
            # mass properties test_outline.py checks against closed forms.
            f = c.result("fixture.get", {"id": fid})
            del f["body"]["shape"]
        mdl, cl = classifier_for(f)
        ws = H.random_wrenches(seed=len(p), n=10, scale=(1, 1, 2))
        for g, r in zip(ws, classify(c, fid, ws, sets=["goal", "strong", "both"])):
            for s in ("goal", "strong", "both"):
                H.check_value(mdl, cl, g, s, r[s])
        if f["name"] == "plate-chamfered":
            nu = M.unit((-1, -1))
            pushes = [{"force": list(nu), "at": [3.25, 1.75]},
                      {"force": list(nu), "at": [3.75, 1.25]}]
            hi, lo = classify(c, fid, pushes, sets=["goal", "strong"])
            assert hi["goal"]["verdict"] == "inside" and abs(hi["goal"]["margin"] - 0.188) < 5e-4
            assert hi["strong"]["verdict"] == "inside" and abs(
                hi["strong"]["margin"] - 0.483) < 5e-4
            assert lo["goal"]["verdict"] == "outside" and abs(lo["goal"]["margin"] + 0.181) < 5e-4
            assert lo["goal"]["blocking"] == "smu" and lo["goal"]["states"] == ["110"]
            for w, r in zip(pushes, (hi, lo)):
                g = mdl.force_wrench(w["force"], w["at"])
                H.check_value(mdl, cl, g, "goal", r["goal"])
                H.check_value(mdl, cl, g, "strong", r["strong"])
