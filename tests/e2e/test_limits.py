"""Limits that mean what they say: the default line length holds
the default number of wrenches however they are written; a classify's
tolerance is a band in [0, 1), and the lp method, which finds no margin,
takes none."""

import json
import math
import random

import fixtures as FX
import model as M


def test_max_wrenches_fits_in_max_line_by_default(harness):
    """100000 wrenches (the default --max-wrenches) in the longest ordinary
    spelling, {"force": [x, y], "at": [x, y]} with 17-digit numbers, fit in
    the default --max-line, and are answered; one more wrench is refused by
    --max-wrenches (-32003), not by the line length."""
    d = harness.start()
    c = d.client()
    fid = c.result("fixture.put", {"fixture": FX.disc_corner(0.5)})["id"]
    rnd = random.Random(14)

    def wrench():
        return {"force": [rnd.uniform(-1, 1), rnd.uniform(-1, 1)],
                "at": [rnd.uniform(-1, 1), rnd.uniform(-1, 1)]}

    wrenches = [wrench() for _ in range(100000)]
    request = {"jsonrpc": "2.0", "method": "wrench.classify", "id": 1,
               "params": {"fixture": fid, "wrenches": wrenches, "sets": ["goal"]}}
    line = json.dumps(request)
    assert len(line) > 10 * 1000 * 1000, len(line)  # the old default, 1 MiB, was far short
    c.send_line(line)
    answer = c.read_json(timeout=120)
    assert "result" in answer, str(answer)[:300]
    assert len(answer["result"]["results"]) == 100000
    # Spot-check against the independent model: its margins are the daemon's.
    model = M.Model(FX.disc_corner(0.5))
    classifier = M.Classifier(model)
    for i in range(0, 100000, 997):
        w = wrenches[i]
        lever = (w["at"][0] - model.com[0], w["at"][1] - model.com[1])
        g = (w["force"][0], w["force"][1], lever[0] * w["force"][1] - lever[1] * w["force"][0])
        expected = classifier.classify(g, "goal").margin
        got = answer["result"]["results"][i]["goal"]["margin"]
        assert abs(got - expected) < 1e-7, (i, got, expected)
    request["params"]["wrenches"].append(wrench())
    c.send_line(json.dumps(request))
    error = c.read_json(timeout=120)["error"]
    assert error["code"] == -32003 and error["data"]["field"] == "params.wrenches", error


def test_tolerance_is_a_band_in_0_1(daemon):
    c = daemon.client()
    fid = c.result("fixture.put", {"fixture": FX.disc_corner(0.5)})["id"]
    base = {"fixture": fid, "wrenches": [[-1, -1, 0], [1, 1, 0]]}
    for good in (0, 1e-9, 0.5, 0.999999):
        results = c.result("wrench.classify", dict(base, tolerance=good))["results"]
        assert len(results) == 2
    # A wrench with margin m is "boundary" exactly when |m| <= tolerance.
    plain = c.result("wrench.classify", base)["results"]
    for r in plain:
        m = r["goal"]["margin"]
        wide = c.result("wrench.classify", dict(base, tolerance=abs(m) + 1e-6))["results"]
        assert wide[plain.index(r)]["goal"]["verdict"] == "boundary", (m, wide)
    for bad in (1, 1.5, -1e-12, -1):
        e = c.error("wrench.classify", dict(base, tolerance=bad))
        assert e["code"] == -32602 and e["data"]["field"] == "params.tolerance", e
        assert "[0, 1)" in e["data"]["reason"], e


def test_lp_takes_no_tolerance(daemon):
    c = daemon.client()
    fid = c.result("fixture.put", {"fixture": FX.disc_corner(0.5)})["id"]
    base = {"fixture": fid, "wrenches": [[-1, -1, 0]], "method": "lp"}
    r = c.result("wrench.classify", base)["results"][0]["goal"]
    assert r["margin"] is None and r["verdict"] in ("inside", "outside")
    for tolerance in (0, 1e-9):
        e = c.error("wrench.classify", dict(base, tolerance=tolerance))
        assert e["code"] == -32602 and e["data"]["field"] == "params.tolerance", e
        assert "lp" in e["data"]["reason"], e


def test_fixels_must_spread_over_a_thousandth_of_the_gyration_radius(daemon):
    """Fuzz finding 8: fixels bunched far below the radius of gyration have
    torque rows equal but for spread / rho; a long bar held by three fixels
    at one end is refused at "fixels" below 1e-3 rho, taken above it, and
    fixels all at one point (exact) are kept."""
    c = daemon.client()
    length, width, mass = 1000.0, 2.0, 1.0
    # A uniform bar about its centroid: I = m (l^2 + w^2) / 12.
    rho = ((length ** 2 + width ** 2) / 12) ** 0.5

    def bar(fixels):
        return {"body": {"mass": mass, "shape": {"type": "polygon", "vertices": [
                    [0, 0], [length, 0], [length, width], [0, width]]}},
                "friction": {"static": 0.3}, "fixels": fixels}

    def spread(fixture):
        at = [f["at"] for f in fixture["fixels"]]
        return max(math.dist(p, q) for p in at for q in at)

    # The spread is the largest distance between two fixels: here 0.39 of
    # 1e-3 rho (the second fixel to the third), and 5.6 of it below.
    tight = bar([{"at": [0, 0.05]}, {"at": [0, 0.05 + 0.2 * 1e-3 * rho]},
                 {"at": [0.1 * 1e-3 * rho, 0]}])
    assert 0 < spread(tight) < 1e-3 * rho
    e = c.error("fixture.put", {"fixture": tight})
    assert e["code"] == -32602 and e["data"]["field"] == "params.fixture.fixels", e
    assert "radius of gyration" in e["data"]["reason"], e
    loose = bar([{"at": [0, 0.5]}, {"at": [0, 1.5]}, {"at": [2 * 1e-3 * rho, 0]}])
    assert spread(loose) > 1e-3 * rho
    assert c.result("fixture.put", {"fixture": loose})["fixels"] == 3
    # Two fixels at one point (a corner of the bar), normals given: exact, kept.
    corner = bar([{"at": [0, 0], "normal": [1, 0]}, {"at": [0, 0], "normal": [0, 1]}])
    assert c.result("fixture.put", {"fixture": corner})["fixels"] == 2
