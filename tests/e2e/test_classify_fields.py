"""wrench.classify with "fields" (issue 19): the lean answer by column
against the full answer by row for the same wrenches, every subset of the
fields, every set, both methods; the verdicts alone (computed without
margins, wr_classify_verdict) against the full path's on many wrenches,
counted, near boundaries too; answers cut into many pieces; refusals."""

import itertools
import json
import math
import os
import random

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


def check_columns(rows, lean, sets, fields):
    assert lean["count"] == len(rows)
    assert list(lean["sets"]) == sets
    for name in sets:
        columns = lean["sets"][name]
        assert list(columns) == [COLUMNS[f] for f in FIELDS if f in fields]
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
    assert all(m is None for m in lean["sets"]["goal"]["margins"])


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
            for s in ("goal", "strong", "both"):
                letters = lean["sets"][s]["verdicts"]
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
    assert [a["result"]["sets"]["goal"]["verdicts"] for a in answers] == ["io"] * 3


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
