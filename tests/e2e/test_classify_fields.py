"""wrench.classify with "fields": the lean answer by column
against the full answer by row for the same wrenches, every subset of the
fields, every set, both methods; the verdicts alone (computed without
margins, wr_classify_verdict) against the full path's on many wrenches,
counted, near boundaries too; answers cut into many pieces; refusals."""

import itertools
import json
import math
import os
import random
import sys

import pytest

from conftest import REPO, FIGURES

EXAMPLES = os.path.join(REPO, "examples")
FIELDS = ["verdict", "margin", "blocking", "states", "witness"]
COLUMNS = {"verdict": "verdicts", "margin": "margins", "blocking": "blocking",
           "states": "states", "witness": "witness"}
LETTER = {"inside": "i", "boundary": "b", "outside": "o"}


def example(name):
    with open(os.path.join(EXAMPLES, name + ".json")) as f:
        return json.load(f)


def wrenches(seed, count):
    rng = random.Random(seed)
    out = []
    for _ in range(count):
        w = [rng.gauss(0, 1) for _ in range(3)]
        scale = 10 ** rng.uniform(-2, 2)
        out.append([c * scale for c in w])
    out.append([0, 0, 0])
    return out


def joined(lean, sets, fields):
    """The lean answer's pieces, checked for their shape, joined into one
    set of columns per set: {"goal": {"verdicts": "...", ...}, ...}."""
    assert list(lean) == ["count", "pieces"]
    names = [COLUMNS[f] for f in FIELDS if f in fields]
    out = {name: {c: ("" if c == "verdicts" else []) for c in names} for name in sets}
    total = 0
    for piece in lean["pieces"]:
        assert list(piece) == ["count"] + sets
        assert piece["count"] >= 1
        total += piece["count"]
        for name in sets:
            assert list(piece[name]) == names
            for c in names:
                assert len(piece[name][c]) == piece["count"], (name, c)
                out[name][c] += piece[name][c]
    assert total == lean["count"]
    return out


def check_columns(rows, lean, sets, fields):
    assert lean["count"] == len(rows)
    columns_of = joined(lean, sets, fields)
    for name in sets:
        columns = columns_of[name]
        for field in fields:
            column = columns[COLUMNS[field]]
            assert len(column) == len(rows)
            for i, row in enumerate(rows):
                v = row[name]
                if field == "verdict":
                    assert column[i] == LETTER[v["verdict"]], (name, i)
                else:
                    assert column[i] == v[field], (name, i, field)


@pytest.mark.parametrize("name", ["plate-chamfered", "bracket", "disc-corner"])
def test_columns_equal_rows_for_every_subset(client, name):
    fixture = example(name)
    ws = wrenches(len(name), 40)
    sets = ["goal", "strong", "both"]
    rows = client.result("wrench.classify", {"fixture": fixture, "wrenches": ws,
                                             "sets": sets})["results"]
    subsets = 0
    for r in range(1, 6):
        for fields in itertools.combinations(FIELDS, r):
            lean = client.result("wrench.classify", {"fixture": fixture, "wrenches": ws,
                                                     "sets": sets,
                                                     "fields": list(reversed(fields))})
            check_columns(rows, lean, sets, fields)
            subsets += 1
    assert subsets == 31


def test_lp_columns_equal_lp_rows(client):
    fixture = example("plate-3-2-1")
    ws = wrenches(7, 30)
    rows = client.result("wrench.classify", {"fixture": fixture, "wrenches": ws,
                                             "method": "lp"})["results"]
    lean = client.result("wrench.classify", {"fixture": fixture, "wrenches": ws, "method": "lp",
                                             "fields": ["verdict", "margin", "blocking"]})
    check_columns(rows, lean, ["goal", "strong"], ["verdict", "margin", "blocking"])
    margins = joined(lean, ["goal", "strong"], ["verdict", "margin", "blocking"])["goal"]["margins"]
    assert len(margins) == len(ws) and all(m is None for m in margins)


def test_verdicts_alone_agree_with_the_full_path(client):
    """Every wrench of a large set, and wrenches a hair from the boundary
    (the full answer's witness wrench, the projection onto the blocking
    cone, moved a little), with the default tolerance and with 0."""
    compared = 0
    for name in ("plate-chamfered", "plate-3-2-1", "bracket", "notched-plate"):
        fixture = example(name)
        ws = wrenches(sum(map(ord, name)), 2000)
        rows = client.result("wrench.classify", {"fixture": fixture, "wrenches": ws,
                                                 "sets": ["goal", "strong", "both"]})["results"]
        # Near the boundary: projections onto the blocking cones, scaled
        # by 1 +- 1e-10 and nudged.
        near = []
        for row in rows[:400]:
            for s in ("goal", "strong"):
                w = row[s]["witness"]
                if w:
                    near.append([c * (1 + 1e-10) for c in w["wrench"]])
                    near.append([w["wrench"][0] + 1e-12, w["wrench"][1], w["wrench"][2]])
        for tolerance in (None, 0):
            batch = ws + near
            params = {"fixture": fixture, "wrenches": batch, "sets": ["goal", "strong", "both"]}
            if tolerance is not None:
                params["tolerance"] = tolerance
            full = client.result("wrench.classify", params)["results"]
            lean = client.result("wrench.classify", dict(params, fields=["verdict"]))
            columns = joined(lean, ["goal", "strong", "both"], ["verdict"])
            for s in ("goal", "strong", "both"):
                letters = columns[s]["verdicts"]
                assert letters == "".join(LETTER[r[s]["verdict"]] for r in full), (name, s)
                compared += len(letters)
    FIGURES["classify fields: verdicts alone compared with the full path"] = compared
    assert compared > 60000


def test_many_pieces(daemon):
    """A long lean answer is cut into pieces between wrenches and columns:
    the same text as whole."""
    client = daemon.client()
    fixture = example("bracket")
    ws = wrenches(3, 6000)
    lean = client.result("wrench.classify", {"fixture": fixture, "wrenches": ws,
                                             "fields": ["verdict", "margin", "states"]})
    rows = client.result("wrench.classify", {"fixture": fixture, "wrenches": ws})["results"]
    check_columns(rows, lean, ["goal", "strong"], ["verdict", "margin", "states"])


def test_in_a_batch(client):
    fixture = example("disc-corner")
    batch = [{"jsonrpc": "2.0", "method": "wrench.classify", "id": i,
              "params": {"fixture": fixture, "wrenches": [[-1, -1, 0], [1, 0, 0]],
                         "fields": ["verdict"]}} for i in range(3)]
    client.send(batch)
    answers = json.loads(client.read_line(30))
    rows = client.result("wrench.classify", {"fixture": fixture,
                                             "wrenches": [[-1, -1, 0], [1, 0, 0]]})["results"]
    strong = "".join(LETTER[r["strong"]["verdict"]] for r in rows)
    # The goal letters by the closed form (docs/MODEL.md section 7.1).
    assert [a["result"] for a in answers] == [
        {"count": 2, "pieces": [{"count": 2, "goal": {"verdicts": "io"},
                                 "strong": {"verdicts": strong}}]}] * 3


@pytest.mark.parametrize("fields,field", [
    ([], "params.fields"),
    ("verdict", "params.fields"),
    (["verdict", "verdict"], "params.fields[1]"),
    (["margin", "speed"], "params.fields[1]"),
    ([1], "params.fields[0]"),
])
def test_refusals(client, fields, field):
    error = client.error("wrench.classify", {"fixture": example("disc-corner"),
                                             "wrenches": [[-1, -1, 0]], "fields": fields})
    assert error["code"] == -32602 and error["data"]["field"] == field, error


def cell_edge_wrenches(put, mass, rng, count):
    """Wrenches whose scaled direction (force, torque / rho) lies on an edge
    of the verdict map's cells (128 to a cube face's side), or a hair off."""
    rho = math.sqrt(put["inertia"] / mass)
    out = []
    for _ in range(count):
        axis = rng.randrange(3)
        h = [0.0, 0.0, 0.0]
        h[axis] = rng.choice((-1.0, 1.0))
        for k in (1, 2):
            u = -1 + 2 * rng.randrange(129) / 128
            if rng.random() < 0.3:
                u = math.nextafter(u, rng.choice((-2.0, 2.0)))
            h[(axis + k) % 3] = u
        size = 10 ** rng.uniform(-2, 2)
        out.append([h[0] * size, h[1] * size, h[2] * rho * size])
    return out


@pytest.mark.parametrize("name", ["plate-3-2-1", "bracket"])
def test_long_verdicts_by_the_map(client, name):
    """A batch of 100,000 verdicts or more is answered by the verdict map:
    every one of them the same as the margin path's (wr_classify_margin,
    which tests/unit/lib/test_verdict.c holds to the full answer bit for bit),
    random wrenches and wrenches on the map's cell edges, two tolerances;
    and a sample against the full rows."""
    fixture = example(name)
    put = client.result("fixture.put", {"fixture": fixture})
    rng = random.Random(name)
    ws = (wrenches(len(name) + 100, 40000) +
          cell_edge_wrenches(put, fixture["body"]["mass"], rng, 20000))
    compared = 0
    for tolerance in (None, 0.05):
        params = {"fixture": put["id"], "wrenches": ws}
        if tolerance is not None:
            params["tolerance"] = tolerance
        alone = joined(client.result("wrench.classify", dict(params, fields=["verdict"])),
                       ["goal", "strong"], ["verdict"])
        with_margins = joined(
            client.result("wrench.classify", dict(params, fields=["margin", "verdict"])),
            ["goal", "strong"], ["verdict", "margin"])
        for s in ("goal", "strong"):
            a, b = alone[s]["verdicts"], with_margins[s]["verdicts"]
            assert len(a) == len(ws)
            differ = [i for i in range(len(ws)) if a[i] != b[i]]
            assert not differ, (s, tolerance, [(ws[i], a[i], b[i]) for i in differ[:5]])
            compared += len(a)
        sample = list(range(0, len(ws), 37))
        rows = client.result("wrench.classify", dict(params, wrenches=[ws[i] for i in sample]))
        for j, i in enumerate(sample):
            for s in ("goal", "strong"):
                assert alone[s]["verdicts"][i] == LETTER[rows["results"][j][s]["verdict"]]
    FIGURES["classify fields: verdicts by the map compared"] = (
        FIGURES.get("classify fields: verdicts by the map compared", 0) + compared)


def test_python_client_columns(daemon):
    """Client.classify_columns joins the pieces: the same columns as the
    rows' values, over several pieces."""
    sys.path.insert(0, os.path.join(REPO, "clients", "python"))
    import wrenchd
    fixture = example("bracket")
    ws = wrenches(11, 3000)
    client = daemon.client()
    rows = client.result("wrench.classify", {"fixture": fixture, "wrenches": ws,
                                             "sets": ["both", "goal"]})["results"]
    with wrenchd.Client(daemon.path, timeout=60) as py:
        columns = py.classify_columns(fixture, ws, fields=["verdict", "margin", "blocking"],
                                      sets=["both", "goal"])
    assert list(columns) == ["both", "goal"]
    for s in ("both", "goal"):
        assert columns[s]["verdicts"] == "".join(LETTER[r[s]["verdict"]] for r in rows)
        assert columns[s]["margins"] == [r[s]["margin"] for r in rows]
        assert columns[s]["blocking"] == [r[s]["blocking"] for r in rows]
