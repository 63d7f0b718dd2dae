"""The fixture's optional units (docs/PROTOCOL.md, "Objects"): stored, part
of the id only when given, refused at their field when unknown.  Answers in
units are checked in test_forces.py, where magnitudes appear."""

import fixtures as FX


def error_of(client, method, params):
    e = client.error(method, params)
    assert e["code"] == -32602, e
    return e["data"]["field"], e["data"]["reason"]


def test_units_are_stored_and_change_the_id_only_when_given(client):
    plain = FX.disc_corner(0.5)
    # The disc's id before units existed (tests/e2e/test_outline.py OLD_IDS).
    assert client.result("fixture.put", {"fixture": plain})["id"] == \
        "e0d7a1a0bd6e8bf16fe5845da1960ed9"
    ids = set()
    for length, force in (("mm", "N"), ("m", "N"), ("in", "lbf"), ("m", "mN")):
        f = dict(plain, units={"force": force, "length": length})
        fid = client.result("fixture.put", {"fixture": f})["id"]
        assert fid not in ids and fid != "e0d7a1a0bd6e8bf16fe5845da1960ed9"
        ids.add(fid)
        got = client.result("fixture.get", {"id": fid})
        assert got["units"] == {"length": length, "force": force}, got
        # What fixture.get returns puts back to the same id.
        assert client.result("fixture.put", {"fixture": got})["id"] == fid
    got = client.result("fixture.get", {"id": "e0d7a1a0bd6e8bf16fe5845da1960ed9"})
    assert "units" not in got


def test_bad_units_are_refused_at_their_field(client):
    plain = FX.disc_corner(0.5)
    cases = [
        ({"length": "cm", "force": "N"}, "params.fixture.units.length", "cm"),
        ({"length": "mm", "force": "kgf"}, "params.fixture.units.force", "kgf"),
        ({"length": "mm"}, "params.fixture.units.force", "required"),
        ("mm", "params.fixture.units", "object"),
        ({"length": "mm", "force": "N", "mass": "g"}, "params.fixture.units.mass", ""),
    ]
    for units, field, word in cases:
        got = error_of(client, "fixture.put", {"fixture": dict(plain, units=units)})
        assert got[0] == field and word in got[1], (units, got)
    assert client.result("fixture.list", {})["fixtures"] == []
