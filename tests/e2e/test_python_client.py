"""The Python client (clients/python/wrenchd.py) against a running wrenchd:
every call, its errors, batches, timeouts, reconnecting, independent
clients, and examples/cad_plugin.py.  Numbers come from docs/MODEL.md's closed
forms (sections 3, 4, 7) or from the independent model (model.py), never
from the daemon.  A few tests talk to a socket the test serves itself (a
listener that never answers, a scripted fake daemon), to make timeouts and
broken connections happen exactly where wanted."""

import ast
import dataclasses
import importlib.util
import json
import math
import os
import re
import socket
import subprocess
import sys
import threading
import time

import pytest

import fixtures as FX
import helpers as H
import model as M
from conftest import REPO, SLOW

sys.path.insert(0, os.path.join(REPO, "clients", "python"))
import wrenchd  # noqa: E402

ID_RE = re.compile(r"^[0-9a-f]{32}$")
PLUGIN = os.path.join(REPO, "examples", "cad_plugin.py")
OUTLINE = os.path.join(REPO, "examples", "outline.json")
TIMEOUT = 10.0 * SLOW
SHORT = 0.3          # the timeout of the timeout tests, seconds


@pytest.fixture
def pyclient(daemon):
    c = wrenchd.Client(daemon.path, timeout=TIMEOUT)
    yield c
    c.close()


def wire(v):
    """A Verdict back in its wire form (for helpers.check_value): the
    members a fixture with a tolerance adds are on the wire only there."""
    out = dataclasses.asdict(v)
    for key in ("perturbation", "perturbation_normals"):
        if out[key] is None:
            del out[key]
    return out


def elapsed(fn):
    start = time.monotonic()
    try:
        fn()
    except Exception as e:       # returned, for the caller to check
        return time.monotonic() - start, e
    return time.monotonic() - start, None


# ---- fixtures: put, get, list, delete ------------------------------------------

def test_put_get_list_delete(pyclient):
    c = pyclient
    put = c.put_fixture(FX.disc_corner(0.5))
    assert isinstance(put, wrenchd.PutResult)
    assert ID_RE.match(put.id) and put.name == "disc-corner"
    # k = 2: k 2^(k-1) = 4 kept strings; figure 8: nine modes; pinned
    assert (put.fixels, put.goal_cones, put.strong_cones, put.pinned) == (2, 4, 9, True)
    # same content, same id; a new name replaces the stored one
    again = c.put_fixture(FX.disc_corner(0.5, name="renamed"))
    assert again.id == put.id and again.name == "renamed"
    # the explicit form (the friction in each fixel) puts back to the same id
    stored = c.get_fixture(put.id)
    assert isinstance(stored, dict) and stored["name"] == "renamed"
    assert [x["friction"] for x in stored["fixels"]] == [{"static": 0.5, "kinetic": 0.5}] * 2
    assert c.put_fixture(stored).id == put.id
    plate = c.put_fixture(FX.rectangle_321(0.3))
    assert plate.goal_cones == 12          # k = 3: twelve kept strings (docs/MODEL.md section 3)
    listed = c.list_fixtures()
    assert all(isinstance(f, wrenchd.FixtureInfo) for f in listed)
    assert [(f.id, f.name, f.fixels) for f in listed] == sorted(
        [(put.id, "renamed", 2), (plate.id, "plate-3-2-1", 3)])
    assert c.delete_fixture(put.id) is True
    with pytest.raises(wrenchd.WrenchdError) as e:
        c.delete_fixture(put.id)
    assert (e.value.code, e.value.field) == (wrenchd.NO_SUCH_FIXTURE, "params.id")
    assert c.delete_fixture(put.id, missing_ok=True) is False
    assert [f.id for f in c.list_fixtures()] == [plate.id]
    # a PutResult stands for its id
    assert c.get_fixture(plate)["name"] == "plate-3-2-1"


# ---- wrench.classify ---------------------------------------------------------------

@pytest.mark.parametrize("mu", [0.25, 0.5, 0.9])
def test_classify_disc_corner_margin(pyclient, mu):
    """docs/MODEL.md section 7: the G_goal margin of (-1, -1, 0) is (1 - mu) / sqrt(2 (1 + mu^2))
    for mu < 1, whatever tau's units; a force at the centre of mass is the
    same wrench; inline and stored fixtures answer alike."""
    c = pyclient
    f = FX.disc_corner(mu)
    expected = (1 - mu) / math.sqrt(2 * (1 + mu * mu))
    fid = c.put_fixture(f).id
    by_id = c.classify(fid, [(-1, -1, 0), {"force": (-1, -1), "at": (0, 0)}], sets=("goal",))
    inline = c.classify(f, [[-1, -1, 0]], sets="goal")
    for r in by_id + inline:
        assert set(r) == {"goal"}
        v = r["goal"]
        assert isinstance(v, wrenchd.Verdict)
        assert v.margin == pytest.approx(expected, abs=1e-9)
        assert (v.verdict, v.inside, v.blocking, v.states, v.witness) == (
            "inside", True, None, [], None)


def test_classify_blocking_witness_and_words(pyclient):
    """mu = 0.5: (-1, -0.2, 0) is blocked by ms from states 10 and 11 (docs/MODEL.md section
    3); (-1, -1, -100) seats the disc but spins it: strong blocked by ll
    (docs/MODEL.md section 4's counterexample).  Every verdict, margin and witness checked
    against the independent model."""
    c = pyclient
    f = FX.disc_corner(0.5)
    mdl, cl = M.Model(f), M.Classifier(M.Model(f))
    wrenches = [(-1, -1, 0), (-1, -0.2, 0), (-1, -1, -100)]
    results = c.classify(f, wrenches, sets=("goal", "strong", "both"))
    assert len(results) == 3
    for g, r in zip(wrenches, results):
        assert set(r) == {"goal", "strong", "both"}
        for s in ("goal", "strong", "both"):
            H.check_value(mdl, cl, g, s, wire(r[s]))
    goal = results[1]["goal"]
    assert (goal.verdict, goal.blocking, sorted(goal.states)) == ("outside", "ms", ["10", "11"])
    assert isinstance(goal.witness, wrenchd.Witness)
    assert len(goal.witness.forces) == 2 and len(goal.witness.acceleration) == 3
    assert goal.witness.wrench == pytest.approx([-1, -0.2, 0], abs=1e-9)
    assert wrenchd.explain(goal, "goal") == (
        "from contact state 10 it can stay as it is: fixel 1 holds and fixel 2 is never "
        "reached; from contact state 11 fixel 2 may break away while fixel 1 holds")
    assert goal.explain() == wrenchd.explain(goal, "goal")     # states say it is a goal string
    spin = results[2]
    assert spin["goal"].inside and spin["goal"].explain("goal") == (
        "seats the part from every contact state")
    assert (spin["strong"].verdict, spin["strong"].blocking) == ("outside", "ll")
    assert spin["strong"].explain("strong") == (
        "it may start to move: fixel 1 slides left, fixel 2 slides left")
    assert spin["both"].blocking == "ll" and spin["both"].explain("both") == (
        "it may start to move: fixel 1 slides left, fixel 2 slides left")
    assert results[0]["strong"].explain("strong") == "once seated, it does not move"


def test_classify_method_lp_and_tolerance(pyclient):
    """method "lp": no margin, the same verdicts away from the boundary;
    a tolerance above the margin (0.316) makes the verdict boundary."""
    c = pyclient
    f = FX.rectangle_321(0.3)
    mdl, cl = M.Model(f), M.Classifier(M.Model(f))
    ws = H.away_from_boundary(cl, H.random_wrenches(seed=11, n=12, scale=(1, 1, 2)),
                              sets=("goal", "strong"))
    assert len(ws) >= 6
    auto = c.classify(f, ws)
    lp = c.classify(f, ws, method="lp")
    for g, a, b in zip(ws, auto, lp):
        for s in ("goal", "strong"):
            H.check_value(mdl, cl, g, s, wire(a[s]))
            H.check_value(mdl, cl, g, s, wire(b[s]), lp=True)
            assert b[s].margin is None and a[s].verdict == b[s].verdict
    (r,) = c.classify(FX.disc_corner(0.5), [(-1, -1, 0)], sets="goal", tolerance=0.5)
    assert r["goal"].verdict == "boundary" and r["goal"].margin == pytest.approx(0.316228, abs=1e-6)


def test_single_fixel_pivots_and_words(pyclient):
    """A disc on one fixel is not pinned (docs/MODEL.md section 4): its modes are s, l, r
    and the pivots n+ and n-; pulling it away is blocked by s from both
    contact states, and the words name the untouched state too."""
    c = pyclient
    f = FX.disc_one_fixel(0.5)
    modes = c.modes(f)
    assert isinstance(modes, wrenchd.Modes)
    expected, pinned = M.modes(M.Model(f))
    assert sorted(modes.feasible) == sorted(expected) == sorted(["s", "l", "r", "n+", "n-"])
    assert modes.pinned is False and pinned is False
    (r,) = c.classify(f, [(0, 1, 0)], sets="goal")
    v = r["goal"]
    assert (v.verdict, v.blocking, v.states) == ("outside", "s", ["0", "1"])
    assert v.explain("goal") == ("from contact state 0 it can stay as it is: fixel 1 is never "
                                 "reached; from contact state 1 fixel 1 may break away")


class _Recording(dict):
    """A dict that notes the keys looked up (as prefix + key)."""

    def __init__(self, table, used, prefix=""):
        super().__init__(table)
        self.used, self.prefix = used, prefix

    def __getitem__(self, key):
        self.used.add(self.prefix + key)
        return super().__getitem__(key)


def test_explain_speaks_like_wrenchctl(monkeypatch):
    """One table of words (clients/explain_words.txt, from which the build
    generates wrenchd._EXPLAIN_WORDS and wrenchctl's wc_explain.h), two
    compositions of the sentences: the Python client's explain() and
    wrenchctl's (C) say the same of every blocking string that 300 random
    wrenches meet on the 3-2-1 plate, on a single-fixel disc (whose goal string "s" comes from the no-contact
    state, and whose strong modes include the pivots) and on the disc in a
    corner, for the goal, strong
    and both sets, and of margin's blocking mode; and between them they use
    every entry of the table wrenchctl has."""
    import random
    import subprocess
    import tempfile
    used = set()
    monkeypatch.setattr(wrenchd, "_W", _Recording(wrenchd._EXPLAIN_WORDS, used))
    monkeypatch.setattr(wrenchd, "MOTION", _Recording(wrenchd.MOTION, used, "motion_"))
    rng = random.Random(7)
    wrenchctl = os.path.join(REPO, "build", "wrenchctl")
    seen = set()
    for fixture in (FX.rectangle_321(0.3), FX.disc_one_fixel(0.4), FX.disc_corner(0.5)):
        with tempfile.NamedTemporaryFile("w", suffix=".json", delete=False) as f:
            json.dump(fixture, f)
        try:
            wrenches = ["%.3f,%.3f,%.3f" % tuple(rng.uniform(-1, 1) for _ in range(3))
                        for _ in range(300)]
            command = [wrenchctl, "--local", "classify", f.name] + wrenches + [
                "--sets", "goal,strong,both"]
            table = subprocess.run(command, capture_output=True, text=True, timeout=60)
            as_json = subprocess.run(command + ["--json"], capture_output=True, text=True,
                                     timeout=60)
            margins = [subprocess.run([wrenchctl, "--local", "margin", f.name, w],
                                      capture_output=True, text=True, timeout=60)
                       for w in wrenches[:12]]
        finally:
            os.unlink(f.name)
        assert table.returncode in (0, 1), table.stderr
        results = json.loads(as_json.stdout)["results"]
        # Table rows: the "why" column follows the blocking string.
        rows = [line for line in table.stdout.splitlines()[1:] if line.strip()]
        expected = []
        for r in results:
            for name, v in r.items():
                expected.append((name, v))
        assert len(rows) == len(expected)
        for row, (name, v) in zip(rows, expected):
            if v["inside"]:
                continue
            why = wrenchd.explain(v, name)
            pattern = r"\s%s\s+%s$" % (re.escape(v["blocking"]), re.escape(why))
            assert re.search(pattern, row.rstrip()), (row, why)
            seen.add((name, v["blocking"], tuple(v["states"])))
        for margin in margins:
            assert margin.returncode in (0, 1), margin.stderr
            (line,) = [x for x in margin.stdout.splitlines() if x.startswith("blocking  ")]
            blocking, why = line[len("blocking  "):].split(": ", 1)
            assert why == wrenchd.explain_strong(blocking), line
    # Enough variety for the comparison to mean something, the state-0 case
    # included.
    assert len(seen) >= 12
    assert any(states == ("0", "1") for _, _, states in seen)
    assert any(blocking in ("n+", "n-") for _, blocking, _ in seen)
    # Every word wrenchctl has was compared but "are never reached" (two
    # fixels apart in a self transition: no plan keeps such a cone, see
    # test_explain_every_case_alike); the rest only the Python client says
    # (a verdict inside, a mode of letters no daemon sends).
    python_only = {"mode", "inside_goal", "inside_strong", "inside_both", "apart_many"}
    # An empty design's and an empty region's words: compared in
    # test_design_clients.py (test_empty_answers_explained_alike).
    python_only |= {k for k in wrenchd._EXPLAIN_WORDS
                    if k.startswith("no_design") or k == "empty_region"}
    assert used >= set(wrenchd._EXPLAIN_WORDS) - python_only, \
        set(wrenchd._EXPLAIN_WORDS) - python_only - used
    pivot = wrenchd.Verdict("boundary", False, 0.0, "nn+", [], None)
    assert pivot.explain("strong") == "it may pivot counter-clockwise about its contact point"
    pivot.blocking = "nn-"
    assert pivot.explain("strong") == "it may pivot clockwise about its contact point"


EXPLAIN_DRIVER = r"""
#include "wc_print.h"
#include <stdio.h>
#include <string.h>
/* Lines "goal BLOCKING STATE..." or "strong BLOCKING": wrenchctl's words. */
int main(void)
{
    char line[4096], out[8192];
    while (fgets(line, sizeof line, stdin)) {
        char *set = strtok(line, " \n"), *blocking = strtok(NULL, " \n");
        if (strcmp(set, "strong") == 0) {
            wc_explain_strong(blocking, out, sizeof out);
        } else {
            cJSON *states = cJSON_CreateArray();
            for (char *s = strtok(NULL, " \n"); s; s = strtok(NULL, " \n"))
                cJSON_AddItemToArray(states, cJSON_CreateString(s));
            wc_explain_goal(blocking, states, out, sizeof out);
            cJSON_Delete(states);
        }
        puts(out);
    }
    return 0;
}
"""


def test_explain_every_case_alike(harness):
    """wrenchctl's explanations (its wc_print.o, driven directly) and the
    Python client's, over every goal string the plan can make for up to
    four fixels (from one, two and three of its contact states) and every
    strong mode of up to three fixels and the pivots: the same text."""
    import itertools
    import subprocess
    obj = os.path.join(REPO, "build", "clients", "wrenchctl", "wc_print.o")
    source, program = harness.path("explain.c"), harness.path("explain")
    with open(source, "w") as f:
        f.write(EXPLAIN_DRIVER)
    r = subprocess.run(["cc", "-std=c11", "-Wall", "-Werror", "-I" + os.path.join(REPO, "clients",
                        "wrenchctl"), source, obj, "-lcjson", "-o", program],
                       capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    cases = []
    for k in range(1, 5):
        origins = {}       # goal string -> the states it comes from (SPEC 5's plan)
        for bits in itertools.product("01", repeat=k):
            state = "".join(bits)
            touched = [i for i, c in enumerate(state) if c == "1"]
            for letters in itertools.product("sm", repeat=len(touched)):
                if touched and all(c == "m" for c in letters):
                    continue           # backward: all-m on S excluded
                string = ["u"] * k
                for i, c in zip(touched, letters):
                    string[i] = c
                origins.setdefault("".join(string), []).append(state)
            if len(touched) < k:       # self: all-m on S, s elsewhere
                origins.setdefault("".join("m" if c == "1" else "s" for c in state),
                                   []).append(state)
        for string, states in origins.items():
            for n in (1, 2, 3):
                for chosen in itertools.combinations(states, n):
                    cases.append(("goal", string, list(chosen)))
        if k <= 3:
            for mode in itertools.product("slrn", repeat=k):
                cases.append(("strong", "".join(mode), []))
        cases.append(("strong", "n" * k + "+", []))
        cases.append(("strong", "n" * k + "-", []))
    text = "".join("%s %s %s\n" % (s, b, " ".join(st)) for s, b, st in cases)
    ran = subprocess.run([program], input=text, capture_output=True, text=True, timeout=60)
    assert ran.returncode == 0, ran.stderr
    got = ran.stdout.splitlines()
    assert len(got) == len(cases)
    for line, (set_name, blocking, states) in zip(got, cases):
        expected = (wrenchd.explain_goal(blocking, states) if set_name == "goal"
                    else wrenchd.explain_strong(blocking))
        assert line == expected, (set_name, blocking, states)
    assert any("are never reached" in line for line in got)
    assert any("fixel 1, fixel 2 and fixel 3" in line for line in got)


def test_explain_words_are_wrenchctls():
    """wrenchctl's wc_explain.h and wrenchd._EXPLAIN_WORDS are generated
    from one data file: the generator run now writes the header the build
    used, and the Python table has its entries."""
    import subprocess
    import tempfile
    header = os.path.join(REPO, "build", "clients", "wrenchctl", "wc_explain.h")
    with tempfile.TemporaryDirectory() as d:
        out = os.path.join(d, "wc_explain.h")
        r = subprocess.run([sys.executable, os.path.join(REPO, "clients", "explain_gen.py"),
                            os.path.join(REPO, "clients", "explain_words.txt"), "--c", out],
                           capture_output=True, text=True, timeout=60)
        assert r.returncode == 0, r.stderr
        with open(out) as f, open(header) as g:
            generated = f.read()
            assert generated == g.read()
    for key, text in wrenchd._EXPLAIN_WORDS.items():
        assert '#define WC_EXPLAIN_%s "%s"\n' % (key.upper(), text) in generated


# ---- cone.get, plan.get, modes.get, server.status --------------------------------------

def test_cone_sm_disc_corner(pyclient):
    """G_sm of the disc, mu = 0.5, by hand: fixel 1 separating gives M Q =
    {f_x >= 0, f_y = 0, tau free}; fixel 2 keeping contact adds -(n +- mu t)
    = (+-0.5, -1) (tau free anyway).  So G_sm = {f_y <= 0, -2 f_x + f_y <=
    0}, closed, full-dimensional."""
    c = pyclient
    cone = c.cone(FX.disc_corner(0.5), "sm")
    assert isinstance(cone, wrenchd.Cone)
    assert (cone.constraints, cone.empty, cone.dimension, cone.equalities) == ("sm", False, 3, [])
    want = [(0.0, 1.0, 0.0), M.unit((-2.0, 1.0, 0.0))]
    assert len(cone.halfspaces) == 2 and cone.strict == [False, False]
    for row in cone.halfspaces:
        assert any(H.vec_close(row, w, 1e-9) for w in want), cone.halfspaces
    for g in cone.generators:
        assert all(M.dot(row, g) <= 1e-9 for row in cone.halfspaces), (g, cone)
    # tau is free: both signs of (0, 0, 1) generate
    assert any(H.vec_close(g, (0, 0, 1), 1e-9) for g in cone.generators)
    assert any(H.vec_close(g, (0, 0, -1), 1e-9) for g in cone.generators)


def test_plan_kept_strings(pyclient):
    """docs/MODEL.md section 3 (seed eq. 6): from 00 rule out ss, from 10 su and ms, from 01
    us and sm, from 11 ss, sm and ms; kept: su us sm ms."""
    c = pyclient
    plan = c.plan(FX.disc_corner(0.5))
    assert isinstance(plan, wrenchd.Plan)
    assert all(isinstance(s, wrenchd.PlanState) for s in plan.states)
    assert sorted(plan.cones) == sorted(["su", "us", "sm", "ms"])
    assert [(s.state, sorted(s.excluded)) for s in plan.states] == [
        ("00", ["ss"]), ("10", ["ms", "su"]), ("01", ["sm", "us"]), ("11", ["ms", "sm", "ss"])]
    states, kept, _ = M.plan(3)
    plan3 = c.plan(FX.rectangle_321(0.3))
    assert sorted(plan3.cones) == sorted(kept) and len(kept) == 12
    assert [(s.state, sorted(s.excluded)) for s in plan3.states] == [
        (st, sorted(ex)) for st, ex in states]


def test_modes_figure_8(pyclient):
    """The seed's figure 8: the disc's feasible modes are exactly ss sl sr
    sn ls rs ns ll rr, and it is pinned."""
    c = pyclient
    modes = c.modes(c.put_fixture(FX.disc_corner(0.5)).id)
    assert sorted(modes.feasible) == sorted("ss sl sr sn ls rs ns ll rr".split())
    assert modes.pinned is True


def test_status(pyclient):
    c = pyclient
    s1 = c.status()
    assert isinstance(s1, wrenchd.Status)
    assert isinstance(s1.version, str) and s1.version
    assert s1.fixtures == 0 and s1.clients >= 1 and s1.threads >= 1
    assert s1.cache_limit_bytes > 0 and s1.uptime_s >= 0
    c.put_fixture(FX.disc_corner(0.5))
    with pytest.raises(wrenchd.WrenchdError):
        c.get_fixture("0" * 32)
    s2 = c.status()
    assert s2.fixtures == 1
    assert s2.requests - s1.requests == 3      # put, get, this status
    assert s2.errors - s1.errors == 1


# ---- errors ------------------------------------------------------------------------

def test_errors_carry_code_and_field(pyclient):
    c = pyclient
    bad = FX.variant(FX.disc_corner(0.5), ["body", "mass"], -1)
    with pytest.raises(wrenchd.WrenchdError) as e:
        c.put_fixture(bad)
    err = e.value
    assert (err.code, err.field, err.message) == (-32602, "params.fixture.body.mass",
                                                  "Invalid params")
    assert err.reason and err.method == "fixture.put"
    assert "params.fixture.body.mass" in str(err) and "-32602" in str(err)
    assert not isinstance(err, ConnectionError)
    with pytest.raises(wrenchd.WrenchdError) as e:
        c.get_fixture("0" * 32)
    assert (e.value.code, e.value.field) == (-32001, "params.id")
    with pytest.raises(wrenchd.WrenchdError) as e:
        c.classify("0" * 32, [(1, 0, 0)])
    assert (e.value.code, e.value.field) == (-32001, "params.fixture")
    fid = c.put_fixture(FX.disc_corner(0.5)).id
    cases = [
        (lambda: c.classify(fid, [(1, 0, 0), (1, 2)]), -32602, "params.wrenches[1]"),
        (lambda: c.classify(fid, [(1, 0, 0)], sets=("goal", "gaol")), -32602, "params.sets[1]"),
        (lambda: c.classify(fid, [(1, 0, 0)], method="simplex"), -32602, "params.method"),
        (lambda: c.classify(fid, [(1, 0, 0)], tolerance=-1), -32602, "params.tolerance"),
        (lambda: c.cone(fid, "smu"), -32602, "params.constraints"),
        (lambda: c.get_fixture("xyz"), -32602, "params.id"),
        (lambda: c.call("push.regions", {"fixture": fid, "set": "goal", "x": 1}), -32602,
         "params.x"),
        (lambda: c.call("push.regionz", {"fixture": fid}), -32601, "method"),
    ]
    for fn, code, field in cases:
        with pytest.raises(wrenchd.WrenchdError) as e:
            fn()
        assert e.value.code == code, e.value
        if field is not None:
            assert e.value.field == field, e.value
    # refused before anything is sent: not finite, not a wrench
    before = c.status().requests
    with pytest.raises(ValueError):
        c.classify(fid, [(float("nan"), 0, 0)])
    with pytest.raises(TypeError):
        c.classify(fid, ["abc"])
    with pytest.raises(TypeError):
        c.get_fixture(42)
    assert c.status().requests == before + 1       # only that status
    # the raw call gives the raw result
    assert c.call("modes.get", {"fixture": fid}, readonly=True)["pinned"] is True


def test_too_many_clients_is_an_error(harness):
    """--max-clients 1: the second client gets the daemon's -32003 as a
    WrenchdError (its line has id null), not a vague connection error."""
    d = harness.start("--max-clients", "1")

    def until_admitted(client):
        # the daemon notices a client leaving (here the harness's readiness
        # probe, later `first`) a moment after it has gone
        deadline = time.monotonic() + TIMEOUT
        while True:
            try:
                return client.status()
            except wrenchd.WrenchdError as e:
                assert e.code == wrenchd.LIMIT_EXCEEDED and time.monotonic() < deadline, e
                time.sleep(0.02)

    with wrenchd.Client(d.path, timeout=TIMEOUT) as first, \
            wrenchd.Client(d.path, timeout=TIMEOUT) as second:
        refused = until_admitted(first).refused
        with pytest.raises(wrenchd.WrenchdError) as e:
            second.status()
        assert (e.value.code, e.value.field) == (wrenchd.LIMIT_EXCEEDED, "")
        assert first.status().refused == refused + 1
        first.close()
        assert until_admitted(second).clients == 1


# ---- batches ------------------------------------------------------------------------

def test_batch(pyclient):
    c = pyclient
    f = FX.disc_corner(0.5)
    fid = c.put_fixture(f).id
    with c.batch() as b:
        p_status = b.status()
        p_goal = b.classify(fid, [(-1, -1, 0), (-1, -0.2, 0)], sets="goal")
        p_missing = b.get_fixture("0" * 32)
        p_bad = b.classify(fid, [(1, 2)])
        p_list = b.list_fixtures()
        p_delete = b.delete_fixture("0" * 32, missing_ok=True)
        p_modes = b.modes(fid)
        assert len(b) == 7 and not p_status.done()
        with pytest.raises(RuntimeError):
            p_status.result()
    assert all(p.done() for p in (p_status, p_goal, p_missing, p_bad, p_list, p_delete))
    assert isinstance(p_status.result(), wrenchd.Status)
    goal = [r["goal"] for r in p_goal.result()]
    assert goal[0].margin == pytest.approx(0.5 / math.sqrt(2.5), abs=1e-9)
    assert (goal[1].verdict, goal[1].blocking) == ("outside", "ms")
    with pytest.raises(wrenchd.WrenchdError) as e:
        p_missing.result()
    assert e.value.code == -32001 and p_missing.exception() is not None
    with pytest.raises(wrenchd.WrenchdError) as e:
        p_bad.result()
    assert (e.value.code, e.value.field) == (-32602, "params.wrenches[0]")
    assert [x.id for x in p_list.result()] == [fid]
    assert p_delete.result() is False and p_delete.exception() is None
    assert sorted(p_modes.result().feasible) == sorted("ss sl sr sn ls rs ns ll rr".split())
    # seven requests went out, counted as seven (batch members count)
    before = c.status().requests
    with c.batch() as b:
        pass                         # an empty batch sends nothing
    with pytest.raises(KeyError):
        with c.batch() as b:
            never = b.status()
            raise KeyError("stop")   # the block raised: nothing sent
    with pytest.raises(RuntimeError):
        never.result()
    with pytest.raises(TypeError):
        c.batch().status(timeout=1)
    assert c.status().requests == before + 1
    with pytest.raises(RuntimeError):
        b.status()                   # that batch is over


def test_batch_refused_as_a_whole(harness):
    """A batch line over --max-line is answered with one error (id null):
    every request of the batch raises it; the client goes on."""
    d = harness.start("--max-line", "2000")
    with wrenchd.Client(d.path, timeout=TIMEOUT) as c:
        with c.batch() as b:
            big = b.classify(FX.disc_corner(0.5), [(1, 0, 0)] * 200)
            small = b.status()
        for p in (big, small):
            with pytest.raises(wrenchd.WrenchdError) as e:
                p.result()
            assert e.value.code == wrenchd.INVALID_REQUEST
        assert c.status().version


# ---- a socket the test serves -------------------------------------------------------

STATUS = {"version": "fake", "uptime_s": 1, "fixtures": 0, "cached": 0, "cache_bytes": 0,
          "cache_limit_bytes": 1, "threads": 1, "clients": 1, "refused": 0, "requests": 0,
          "errors": 0}


SWEEP_PUSH = {"intervals": [[0, 0.75]], "critical": 0.75, "curve": [[0, 2], [0.75, 0], [2, 0]],
              "exact": False, "resolution": 0.001}
SWEEP_WRENCHES = {"results": [{"goal": [[0, 0.2]], "strong": []}]}


class FakeDaemon:
    """Serves `path` itself.  The n-th connection follows script[n] ("drop":
    read one line and close without answering; "answer": answer every line;
    connections past the script answer).  Answers: server.status gives
    STATUS, fixture.put a PutResult, anything else {}; a batch's answers
    come back in reverse order.  Every line read is kept in `lines`."""

    def __init__(self, path, script=()):
        self.path = path
        self.script = list(script)
        self.lines = []
        self.connections = 0
        self.listener = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
        self.listener.bind(path)
        self.listener.listen(8)
        self.listener.settimeout(0.05)
        self.stopping = False
        self.threads = [threading.Thread(target=self._accept, daemon=True)]
        self.threads[0].start()

    def _accept(self):
        while not self.stopping:
            try:
                conn, _ = self.listener.accept()
            except socket.timeout:
                continue
            except OSError:
                return
            action = self.script[self.connections] if self.connections < len(self.script) \
                else "answer"
            self.connections += 1
            t = threading.Thread(target=self._serve, args=(conn, action), daemon=True)
            self.threads.append(t)
            t.start()

    @staticmethod
    def answer(request):
        result = {"server.status": STATUS,
                  "fixture.put": {"id": "1" * 32, "name": "x", "fixels": 1, "goal_cones": 1,
                                  "strong_cones": 1, "pinned": False},
                  "friction.sweep": SWEEP_WRENCHES if "wrenches" in request.get("params", {})
                  else SWEEP_PUSH}.get(request["method"], {})
        return {"jsonrpc": "2.0", "result": result, "id": request["id"]}

    def _serve(self, conn, action):
        buf = b""
        conn.settimeout(0.1)
        try:
            while not self.stopping:
                while b"\n" not in buf and not self.stopping:
                    try:
                        chunk = conn.recv(1 << 16)
                    except socket.timeout:
                        continue
                    if not chunk:
                        return
                    buf += chunk
                if self.stopping:
                    return
                line, buf = buf.split(b"\n", 1)
                self.lines.append(line)
                if action == "drop":
                    return
                request = json.loads(line)
                if isinstance(request, list):
                    out = [self.answer(r) for r in reversed(request)]
                else:
                    out = self.answer(request)
                conn.sendall(json.dumps(out).encode() + b"\n")
        finally:
            conn.close()

    def requests(self):
        return [json.loads(line) for line in self.lines]

    def close(self):
        self.stopping = True
        self.listener.close()
        for t in self.threads:
            t.join(2)


@pytest.fixture
def fake(harness):
    made = []

    def make(script=()):
        f = FakeDaemon(harness.path("fake%d.sock" % len(made)), script)
        made.append(f)
        return f
    yield make
    for f in made:
        f.close()


def test_batch_is_one_array_line(fake):
    """A batch goes out as one line holding a JSON array; answers are
    matched by id (the fake answers in reverse order)."""
    f = fake()
    with wrenchd.Client(f.path, timeout=TIMEOUT) as c:
        with c.batch() as b:
            put = b.put_fixture(FX.disc_corner(0.5))
            status = b.status()
        assert put.result().id == "1" * 32
        assert status.result().version == "fake"
    assert len(f.lines) == 1
    (batch,) = f.requests()
    assert isinstance(batch, list) and [r["method"] for r in batch] == [
        "fixture.put", "server.status"]
    assert len({r["id"] for r in batch}) == 2


def test_broken_connection_retries_only_read_only(fake):
    """The connection breaks after the request went out (the fake reads it
    and closes).  fixture.put and fixture.delete are not sent again: they
    raise WrenchdUnavailable, maybe_executed.  server.status (read-only) is
    sent again once on a new connection and answered; broken twice, it
    raises."""
    f = fake(["drop", "drop", "drop", "answer", "drop", "drop"])
    c = wrenchd.Client(f.path, timeout=TIMEOUT)
    with pytest.raises(wrenchd.WrenchdUnavailable) as e:
        c.put_fixture(FX.disc_corner(0.5))
    assert e.value.maybe_executed is True and not isinstance(e.value, wrenchd.WrenchdTimeout)
    assert [r["method"] for r in f.requests()] == ["fixture.put"]
    with pytest.raises(wrenchd.WrenchdUnavailable) as e:
        c.delete_fixture("1" * 32)
    assert e.value.maybe_executed is True
    assert [r["method"] for r in f.requests()] == ["fixture.put", "fixture.delete"]
    assert c.status().version == "fake"          # dropped once (3rd), answered (4th)
    assert [r["method"] for r in f.requests()] == [
        "fixture.put", "fixture.delete", "server.status", "server.status"]
    assert f.connections == 4
    c.close()
    with pytest.raises(wrenchd.WrenchdUnavailable) as e:
        c.list_fixtures()                        # 5th and 6th connections both drop
    assert f.connections == 6
    assert [r["method"] for r in f.requests()][-2:] == ["fixture.list", "fixture.list"]
    c.close()


def test_friction_sweep_request_shape(fake):
    """friction_sweep sends one friction.sweep with the range, the ratio and
    exactly one of wrenches (and sets), push and gravity; the answer is a
    FrictionSweep."""
    f = fake()
    fixture = FX.disc_corner(0.5)
    with wrenchd.Client(f.path, timeout=TIMEOUT) as c:
        r = c.friction_sweep("1" * 32, push="strong")
        assert (r.intervals, r.critical, r.curve) == ([[0, 0.75]], 0.75,
                                                       [[0, 2], [0.75, 0], [2, 0]])
        assert (r.exact, r.resolution, r.results) == (False, 0.001, None)
        c.friction_sweep(fixture, push={"set": "both", "finger_radius": 0.5}, range=(0.1, 1),
                         kinetic_ratio=0.5)
        c.friction_sweep(fixture, gravity=True)
        w = c.friction_sweep(fixture, wrenches=[(-1, -1, 0), {"force": [0, -1], "at": [1, 1]}],
                             sets="goal")
        assert w.results == [{"goal": [[0, 0.2]], "strong": []}] and w.intervals == []
        c.friction_sweep(fixture, wrenches=[(-1, -1, 0)])
    sent = [r["params"] for r in f.requests()]
    assert [r["method"] for r in f.requests()] == ["friction.sweep"] * 5
    assert sent[0] == {"fixture": "1" * 32, "range": [0, 2], "kinetic_ratio": 1.0,
                       "push": {"set": "strong"}}
    assert sent[1] == {"fixture": fixture, "range": [0.1, 1], "kinetic_ratio": 0.5,
                       "push": {"set": "both", "finger_radius": 0.5}}
    assert sent[2]["gravity"] == {} and "push" not in sent[2] and "wrenches" not in sent[2]
    assert sent[3]["wrenches"] == [[-1, -1, 0], {"force": [0, -1], "at": [1, 1]}]
    assert sent[3]["sets"] == ["goal"] and "push" not in sent[3]
    assert "sets" not in sent[4]


@pytest.mark.parametrize("kwargs, words", [
    ({}, "exactly one of wrenches, push, gravity and force"),
    ({"push": "goal", "gravity": "goal"}, "not push and gravity"),
    ({"wrenches": [(1, 0, 0)], "push": True}, "not wrenches and push"),
    ({"push": "goal", "sets": ["goal"]}, "sets go with wrenches"),
    ({"push": 3}, "push is a set name"),
])
def test_friction_sweep_refuses_before_sending(fake, kwargs, words):
    f = fake()
    with wrenchd.Client(f.path, timeout=TIMEOUT) as c:
        with pytest.raises((ValueError, TypeError)) as e:
            c.friction_sweep("1" * 32, **kwargs)
    assert words in str(e.value)
    assert f.lines == []


def test_friction_sweep_of_the_disc(pyclient):
    """The disc in a corner (docs/MODEL.md section 7.1): the goal push
    region is the arc (atan mu, 90 - atan mu) degrees of a unit circle, so
    its length is pi/2 - 2 atan mu, empty from mu = 1; the wrench (-1, -0.2,
    0) seats it while mu <= 0.2 (needs the daemon's friction.sweep)."""
    put = pyclient.put_fixture(FX.disc_corner(0.5))
    r = pyclient.friction_sweep(put, push="goal")
    assert r.critical == pytest.approx(1, abs=1e-9)
    assert len(r.intervals) == 1 and r.intervals[0] == pytest.approx([0, 1], abs=1e-9)
    assert r.curve[0][0] == 0 and r.curve[-1][0] == 2
    assert [mu for mu, _ in r.curve] == sorted(mu for mu, _ in r.curve)
    for mu, length in r.curve:
        assert length == pytest.approx(max(0.0, math.pi / 2 - 2 * math.atan(mu)), abs=1e-9)
    w = pyclient.friction_sweep(put.id, wrenches=[(-1, -0.2, 0)], sets=["goal"], range=(0, 1))
    (row,) = w.results
    assert list(row) == ["goal"] and len(row["goal"]) == 1
    assert row["goal"][0] == pytest.approx([0, 0.2], abs=1e-9)


def test_timeout_when_the_daemon_does_not_answer(harness):
    """A listening socket that never accepts nor answers: the call raises
    WrenchdTimeout (a TimeoutError and a ConnectionError) after about the
    timeout; per call, and per batch, a timeout overrides the client's."""
    path = harness.path("silent.sock")
    silent = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
    silent.bind(path)
    silent.listen(16)
    try:
        c = wrenchd.Client(path, timeout=SHORT)
        took, e = elapsed(c.status)
        assert isinstance(e, wrenchd.WrenchdTimeout), e
        assert isinstance(e, TimeoutError) and isinstance(e, ConnectionError)
        assert SHORT * 0.9 <= took <= SHORT + 1.0 * SLOW, took
        assert not c.connected                   # closed: no late answer can be misread
        slow = wrenchd.Client(path, timeout=60)
        took, e = elapsed(lambda: slow.put_fixture(FX.disc_corner(0.5), timeout=SHORT))
        assert isinstance(e, wrenchd.WrenchdTimeout) and e.maybe_executed is True
        assert SHORT * 0.9 <= took <= SHORT + 1.0 * SLOW, took

        def batch():
            with slow.batch(timeout=SHORT) as b:
                b.status()
        took, e = elapsed(batch)
        assert isinstance(e, wrenchd.WrenchdTimeout)
        assert SHORT * 0.9 <= took <= SHORT + 1.0 * SLOW, took
        c.close()
        slow.close()
    finally:
        silent.close()


def test_unreachable_daemon(harness):
    """No socket file, or a socket nobody listens on: WrenchdUnavailable at
    once, nothing sent."""
    missing = wrenchd.Client(harness.path("nothing-here.sock"), timeout=TIMEOUT)
    took, e = elapsed(missing.status)
    assert isinstance(e, wrenchd.WrenchdUnavailable) and isinstance(e, ConnectionError)
    assert not isinstance(e, wrenchd.WrenchdTimeout) and e.maybe_executed is False
    assert took < 1.0 * SLOW
    path = harness.path("dead.sock")
    dead = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
    dead.bind(path)
    dead.close()                                 # the file stays, no listener
    with pytest.raises(wrenchd.WrenchdUnavailable):
        wrenchd.Client(path, timeout=TIMEOUT).connect()


def test_late_answer_is_not_read_as_the_next(harness):
    """A call that times out on a busy daemon closes its connection: the
    next call gets its own answer, not the late one."""
    d = harness.start()
    f = FX.rectangle_321(0.3)
    with wrenchd.Client(d.path, timeout=TIMEOUT) as c:
        fid = c.put_fixture(f).id
        heavy = [(1, 0.5, 0.25)] * 2000        # about 0.15 s of work
        with pytest.raises(wrenchd.WrenchdTimeout):
            c.classify(fid, heavy, sets=("goal", "strong", "both"), method="lp", timeout=0.001)
        assert [x.id for x in c.list_fixtures()] == [fid]
        assert c.get_fixture(fid)["name"] == "plate-3-2-1"


# ---- reconnecting -----------------------------------------------------------------

@pytest.mark.parametrize("how", ["stop", "kill"])
def test_reconnects_after_the_daemon_restarts(harness, how):
    """The daemon restarts on the same socket (with its state directory):
    the next call, of any method, goes out on a new connection without an
    error; while it is down, calls raise WrenchdUnavailable."""
    d = harness.start(state_dir=harness.path("state"))
    c = wrenchd.Client(d.path, timeout=TIMEOUT)
    fid = c.put_fixture(FX.disc_corner(0.5)).id
    assert c.status().fixtures == 1
    getattr(d, how)()
    d.start()
    assert c.get_fixture(fid)["name"] == "disc-corner"      # read-only, transparent
    getattr(d, how)()
    d.start()
    plate = c.put_fixture(FX.rectangle_321(0.3))             # not read-only: transparent too
    assert sorted(x.id for x in c.list_fixtures()) == sorted([fid, plate.id])
    getattr(d, how)()
    with pytest.raises(wrenchd.WrenchdUnavailable):
        c.status()
    d.start()
    assert c.status().fixtures == 2
    c.close()


# ---- independent clients, threads ----------------------------------------------------

def test_clients_are_independent(harness, daemon):
    """Two clients: their own connections, timeouts and failures.  One
    timing out on a silent socket, or closed, leaves the other working;
    each goes on after the other's error."""
    a = wrenchd.Client(daemon.path, timeout=TIMEOUT)
    b = wrenchd.Client(daemon.path, timeout=TIMEOUT)
    fa = a.put_fixture(FX.disc_corner(0.5)).id
    fb = b.put_fixture(FX.disc_corner(0.25)).id
    assert a.status().clients == 2
    with pytest.raises(wrenchd.WrenchdError):
        a.get_fixture("0" * 32)
    assert b.plan(fb).cones and a.plan(fa).cones
    a.close()
    assert b.modes(fb).pinned is True
    assert a.status().clients == 2          # a reconnected on its own
    path = harness.path("silent.sock")
    silent = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
    silent.bind(path)
    silent.listen(4)
    try:
        stuck = wrenchd.Client(path, timeout=SHORT)
        with pytest.raises(wrenchd.WrenchdTimeout):
            stuck.status()
        assert a.get_fixture(fa)["fixels"][0]["friction"]["static"] == 0.5
        assert b.get_fixture(fb)["fixels"][0]["friction"]["static"] == 0.25
        stuck.close()
    finally:
        silent.close()
    a.close()
    b.close()


def test_threads(daemon):
    """Four threads with a client each, and four sharing one client (its
    lock makes them take turns): every answer is the expected one."""
    f = FX.rectangle_321(0.3)
    cl = M.Classifier(M.Model(f))
    ws = H.away_from_boundary(cl, H.random_wrenches(seed=5, n=10, scale=(1, 1, 2)))
    expect = [(cl.classify(g, "goal").verdict(), cl.classify(g, "strong").verdict()) for g in ws]
    shared = wrenchd.Client(daemon.path, timeout=TIMEOUT)
    fid = shared.put_fixture(f).id
    errors = []

    def work(client, own):
        try:
            for i in range(10):
                g = ws[i % len(ws)]
                (r,) = client.classify(fid, [g])
                assert (r["goal"].verdict, r["strong"].verdict) == expect[i % len(ws)]
                assert client.status().version
        except BaseException as e:            # reported below
            errors.append(e)
        finally:
            if own:
                client.close()

    threads = [threading.Thread(target=work, args=(wrenchd.Client(daemon.path, TIMEOUT), True))
               for _ in range(4)]
    threads += [threading.Thread(target=work, args=(shared, False)) for _ in range(4)]
    for t in threads:
        t.start()
    for t in threads:
        t.join(60)
    shared.close()
    assert not errors, errors


# ---- the example plugin ---------------------------------------------------------------

PUSH_RE = re.compile(r"^push (\d+) at \(([-\d.]+), ([-\d.]+)\) on edge (\d+), "
                     r"along the inward normal \(([-\d.]+), ([-\d.]+)\)$")
SET_RE = re.compile(r"^    (goal|strong) +(inside|boundary|outside) +margin ([+-]\d+\.\d+)  (.*)$")


def outline_fixture():
    with open(OUTLINE) as fh:
        return json.load(fh)


def edge_points(vertices, per_edge):
    out = []
    for i, a in enumerate(vertices):
        b = vertices[(i + 1) % len(vertices)]
        for j in range(per_edge):
            t = (j + 0.5) / per_edge
            out.append((a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])))
    return out


def run_plugin(args, env=None, cwd=None):
    return subprocess.run([sys.executable, PLUGIN] + args, capture_output=True, text=True,
                          timeout=60 * SLOW, env=env, cwd=cwd)


def check_plugin_output(stdout, points):
    """The plugin's report on pushes at `points`, against the independent
    model: the fixels' normals and each push's inward normal come from
    model.py (the outline file is a fixture whose normals are left out),
    not from the plugin.  Returns the (set, verdict) pairs seen."""
    f = outline_fixture()
    mdl = M.Model(f)
    cl = M.Classifier(mdl)
    lines = stdout.splitlines()
    assert "3 fixels, stored in wrenchd as" in lines[0], lines[0]
    assert ("is pinned; it may start to move in %d modes" % len(cl.modes)) in stdout
    pushes = [i for i, line in enumerate(lines) if line.startswith("push ")]
    assert len(pushes) == len(points)
    good, seen = [], set()
    for n, (i, point) in enumerate(zip(pushes, points), 1):
        nu = mdl._inward_normal(tuple(point))
        g = mdl.force_wrench(nu, point)
        m = PUSH_RE.match(lines[i])
        assert m, lines[i]
        assert int(m.group(1)) == n
        assert H.vec_close([float(m.group(2)), float(m.group(3))], point, 6e-4)
        assert H.vec_close([float(m.group(5)), float(m.group(6))], nu, 6e-4)
        exp = {}
        for line, s in zip(lines[i + 1:i + 3], ("goal", "strong")):
            m = SET_RE.match(line)
            assert m and m.group(1) == s, line
            e = exp[s] = cl.classify(g, s)
            assert abs(e.margin) > 1e-3, "the example must stay off the boundary"
            assert m.group(2) == e.verdict(), (line, e)
            assert abs(float(m.group(3)) - e.margin) <= 6e-4, (line, e)
            seen.add((s, m.group(2)))
            if e.verdict() == "inside":
                assert m.group(4) == ("seats the part from every contact state" if s == "goal"
                                      else "once seated, it does not move")
            else:
                blocked = re.match(r"blocked by (\S+): (.*)$", m.group(4))
                assert blocked and blocked.group(1) in e.candidates, (line, e)
                name = blocked.group(1)
                words = (wrenchd.explain_goal(name, cl.origins[name]) if s == "goal"
                         else wrenchd.explain_strong(name))
                assert sorted(blocked.group(2).split("; ")) == sorted(words.split("; "))
        if exp["goal"].verdict() == "inside" and exp["strong"].verdict() == "inside":
            good.append(str(n))
    assert lines[-1] == "pushes that seat the part and then hold it still: " + (
        ", ".join(good) or "none")
    return seen


def test_cad_plugin(daemon):
    """By default: two pushes on each edge, a quarter and three quarters
    along.  The example shows a seating push and both kinds of failure."""
    p = run_plugin(["--socket", daemon.path])
    assert p.returncode == 0, p.stderr
    points = edge_points(outline_fixture()["body"]["shape"]["vertices"], 2)
    seen = check_plugin_output(p.stdout, points)
    assert {("goal", "inside"), ("goal", "outside"), ("strong", "inside"),
            ("strong", "outside")} <= seen
    # the fixture it stored: the outline file's, with the normals the
    # model computes for the fixels
    mdl = M.Model(outline_fixture())
    with wrenchd.Client(daemon.path, timeout=TIMEOUT) as c:
        (info,) = c.list_fixtures()
        stored = c.get_fixture(info.id)
    assert info.name == stored["name"] == "chamfered-bracket"
    assert stored["body"]["shape"] == outline_fixture()["body"]["shape"]
    for fixel, want in zip(stored["fixels"], mdl.fixels):
        assert H.vec_close(fixel["at"], want.at, 1e-12)
        assert H.vec_close(fixel["normal"], want.normal, 1e-12)


def test_cad_plugin_points_and_socket_from_environment(daemon, harness):
    """--push X,Y picks the points; no --socket: $WRENCHD_SOCKET; a socket
    with no daemon: exit 2; a point off the outline: exit 2."""
    env = dict(os.environ, WRENCHD_SOCKET=daemon.path)
    points = [(4.5, 2.0), (2.5, 2.5), (5.0, 0.5)]
    p = run_plugin(["--push", "4.5,2", "--push", "2.5,2.5", "--push", "5,0.5"], env=env,
                   cwd=harness.dir)
    assert p.returncode == 0, p.stderr
    check_plugin_output(p.stdout, points)
    p = run_plugin(["--samples", "1", "--socket", daemon.path])
    assert p.returncode == 0, p.stderr
    check_plugin_output(p.stdout, edge_points(outline_fixture()["body"]["shape"]["vertices"], 1))
    p = run_plugin(["--socket", harness.path("none.sock")])
    assert p.returncode == 2 and "cannot use wrenchd" in p.stderr
    p = run_plugin(["--socket", daemon.path, "--push", "2,1"])
    assert p.returncode == 2 and "not on the outline" in p.stderr


def test_sources_are_python38_stdlib():
    """clients/python/wrenchd.py and the plugin: Python 3.8 syntax, and
    only standard-library imports."""
    paths = [os.path.join(REPO, "clients", "python", "wrenchd.py"), PLUGIN]
    stdlib = getattr(sys, "stdlib_module_names", None)
    for path in paths:
        with open(path) as fh:
            tree = ast.parse(fh.read(), path, feature_version=(3, 8))
        for node in ast.walk(tree):
            names = []
            if isinstance(node, ast.Import):
                names = [a.name for a in node.names]
            elif isinstance(node, ast.ImportFrom) and node.level == 0:
                names = [node.module]
            for name in names:
                top = name.split(".")[0]
                if top in ("wrenchd", "__future__"):
                    continue
                if stdlib is not None:
                    assert top in stdlib, (path, name)


def test_regions_on_outlines_and_a_finger_with_a_size(pyclient):
    """Region names an outline's loop and segment (edge None), a polygon's
    edge (loop and segment None); finger_radius reaches the daemon: on the
    notched plate a finger of radius 4 keeps the notch floor's middle third
    only, (48, 52) of its 12 units from 44 to 56, and one of radius 7 none
    of it (half the notch's width is 6); PutResult reports the mass
    properties in use."""
    with open(os.path.join(REPO, "examples", "bracket.json")) as fh:
        bracket = json.load(fh)
    put = pyclient.put_fixture(bracket)
    # 120 x 60 less four fillets of 8 ((4 - pi) 64), a hole of radius 6 and a
    # slot 20 x 10 with round ends (20 * 10 + 25 pi).
    area = 120 * 60 - (4 - math.pi) * 64 - 36 * math.pi - (200 + 25 * math.pi)
    assert put.area == pytest.approx(area, rel=1e-13)
    assert put.com[1] == pytest.approx(30, rel=1e-13)
    regions = pyclient.push_regions(put, "both", push_on="all")
    assert regions.regions
    assert all(r.edge is None and r.loop is not None and r.segment is not None
               for r in regions.regions)
    assert {r.loop for r in regions.regions} == {0, 1, 2}
    with open(os.path.join(REPO, "examples", "notched-plate.json")) as fh:
        notched = json.load(fh)
    floor = {r.edge: r for r in pyclient.push_regions(notched, "strong", finger_radius=4).regions}
    assert floor[4].loop is None and floor[4].segment is None
    assert floor[4].from_point == pytest.approx([52, 15]) and floor[4].to_point == pytest.approx([48, 15])
    wide = pyclient.push_regions(notched, "strong", finger_radius=7).regions
    assert 4 not in [r.edge for r in wide]
    assert pyclient.put_fixture(FX.disc_corner(0.5)).area == pytest.approx(math.pi)
