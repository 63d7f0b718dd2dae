"""Assertions shared by the end-to-end tests: answers of wrench.classify
checked against the independent model (model.py)."""

import math
import os
import random
import subprocess

import model as M

VERDICTS = ("inside", "boundary", "outside")
MARGIN_TOL = 1e-7


def close(a, b, tol):
    return abs(a - b) <= tol


def vec_close(a, b, tol):
    return len(a) == len(b) and all(abs(x - y) <= tol for x, y in zip(a, b))


def count_of(x):
    """A count given as an integer or as a list."""
    if isinstance(x, list):
        return len(x)
    assert isinstance(x, int) and not isinstance(x, bool), x
    return x


def check_witness(mdl, g, name, witness, exact):
    """The witness of a blocking string: its acceleration and forces satisfy
    the string's rows (closure), they make `witness.wrench` by Newton-Euler
    (computed here), and that wrench is g itself when `exact`."""
    assert isinstance(witness, dict), witness
    # The Python client's Witness has the supports' members, None without
    # supports (the wire leaves them out).
    keys = {k for k, v in witness.items() if not (k.startswith("support_") and v is None)}
    assert keys == {"acceleration", "forces", "wrench", "friction"}, witness
    q = witness["acceleration"]
    forces = witness["forces"]
    w = witness["wrench"]
    assert len(q) == 3 and len(w) == 3, witness
    assert len(forces) == mdl.k and all(len(c) == 2 for c in forces), witness
    ne = mdl.newton_euler(q, forces)
    scale = 1.0 + M.norm(g) + M.norm(q) + sum(abs(x) for c in forces for x in c)
    eps = 1e-6 * scale
    assert vec_close(ne, w, eps), (
        "witness wrench %r is not M q - sum(W c) = %r" % (w, ne))
    if exact:
        assert vec_close(w, g, 1e-6 * (1.0 + M.norm(g))), (
            "witness makes %r, not the classified wrench %r" % (w, g))
    # the rows of the string, closed
    pivot = 0
    letters = name
    if name.endswith("+") or name.endswith("-"):
        pivot = 1 if name.endswith("+") else -1
        letters = name[:-1]
    assert len(letters) == mdl.k, name
    # the coefficient each letter uses (point friction: the fixel's own)
    friction = witness["friction"]
    assert isinstance(friction, list) and len(friction) == mdl.k, witness
    for f, x, mu in zip(mdl.fixels, letters, friction):
        if x in "sau":
            assert mu is None, (name, friction)
        else:
            assert mu == (f.mu_k if x in "lr" else f.mu_s), (name, friction)
    for f, x, (cn, ct) in zip(mdl.fixels, letters, forces):
        an, at = M.dot(f.Wn, q), M.dot(f.Wt, q)
        if x in "sau":
            assert abs(cn) <= eps and abs(ct) <= eps, (name, forces)
            if x == "s":
                assert an >= -eps, (name, q, an)
            if x == "a":
                assert an <= eps, (name, q, an)
            continue
        assert abs(an) <= eps, ("a_n must vanish", name, q, an)
        assert cn >= -eps, (name, forces)
        if x == "l":
            assert at >= -eps and abs(ct + f.mu_k * cn) <= eps, (name, q, forces)
        elif x == "r":
            assert at <= eps and abs(ct - f.mu_k * cn) <= eps, (name, q, forces)
        else:
            if x == "n":
                assert abs(at) <= eps, (name, q, at)
            assert abs(ct) <= f.mu_s * cn + eps, (name, forces)
    if pivot:
        assert pivot * q[2] >= -eps, (name, q)


def check_value(mdl, classifier, g, which, value, tol=1e-9, lp=False):
    """Check one V of a classify answer against the model."""
    assert isinstance(value, dict), value
    assert set(value) == {"verdict", "inside", "margin", "blocking", "states", "witness"}, value
    verdict = value["verdict"]
    assert verdict in VERDICTS, value
    assert value["inside"] is (verdict == "inside"), value
    exp = classifier.classify(g, which)
    where = "g=%r set=%s model=%r daemon=%r" % (g, which, exp, value)
    if lp:
        assert value["margin"] is None, where
    else:
        assert isinstance(value["margin"], (int, float)), where
        assert -1.0 <= value["margin"] <= 1.0, where
        assert close(value["margin"], exp.margin, MARGIN_TOL), "margin: " + where
    # the verdict, away from the tolerance's edge (lp: away from 0)
    if lp:
        if abs(exp.margin) > 1e-6:
            assert verdict == exp.verdict(0.0), "lp verdict: " + where
    elif abs(abs(exp.margin) - tol) > MARGIN_TOL:
        assert verdict == exp.verdict(tol), "verdict: " + where
    if verdict == "inside":
        assert value["blocking"] is None and value["witness"] is None, where
        assert value["states"] == [], where
        return exp
    # not inside: a blocking string and a witness
    name = value["blocking"]
    assert isinstance(name, str), where
    goal_names = set(classifier.kept)
    strong_names = set(classifier.modes)
    allowed = goal_names if which == "goal" else strong_names if which == "strong" else (
        goal_names | strong_names)
    assert name in allowed, "blocking string not excluded by the set: " + where
    if not lp and exp.margin < -1e-6:
        assert name in exp.candidates, "blocking: " + where
    if name in goal_names and which != "strong":
        assert sorted(value["states"]) == sorted(classifier.origins[name]), "states: " + where
    else:
        assert value["states"] == [], "states: " + where
    # g is in the blocking cone when the verdict is outside
    cone = (mdl.cone(name) if name in goal_names and which != "strong"
            else M.mode_cone(mdl, name))
    if verdict == "outside":
        h = mdl.scale(g)
        assert cone.distance(M.mul(1 / M.norm(h), h)) <= 1e-6, (
            "g is not in the blocking cone: " + where)
    if value["witness"] is not None or verdict == "outside":
        check_witness(mdl, g, name, value["witness"], exact=(verdict == "outside"))
    return exp


def random_wrenches(seed, n, scale=(1.0, 1.0, 1.0)):
    rnd = random.Random(seed)
    out = []
    while len(out) < n:
        g = tuple(round(rnd.uniform(-s, s), 6) for s in scale)
        if M.norm(g) > 1e-3:
            out.append(g)
    return out


def away_from_boundary(classifier, wrenches, sets=("goal", "strong"), gap=1e-4):
    """The wrenches whose margins are all farther than `gap` from 0."""
    return [g for g in wrenches
            if all(abs(classifier.classify(g, s).margin) > gap for s in sets)]


def angle_deg(x, y):
    return math.degrees(math.atan2(y, x)) % 360.0


def run_client_program(tmp_path, name, source_text, *args, timeout=300):
    """A C program written against libwrenchclient (clients/c), compiled in
    tmp_path and run with args: its finished process (output as text)."""
    from conftest import REPO
    source, program = tmp_path / (name + ".c"), tmp_path / name
    source.write_text(source_text)
    subprocess.run(["cc", "-std=c11", "-I", os.path.join(REPO, "clients", "c"), str(source),
                    os.path.join(REPO, "build", "libwrenchclient.a"), "-lm", "-o", str(program)],
                   check=True)
    return subprocess.run([str(program)] + [str(a) for a in args], capture_output=True,
                          text=True, timeout=timeout)
