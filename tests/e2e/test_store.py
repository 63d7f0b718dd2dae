"""fixture.put / get / delete / list: content ids (idempotence), round trips,
persistence across SIGKILL, --load; the state directory (its lock, files
named by older ids, files whose name and content disagree), --max-fixtures."""

import copy
import glob
import hashlib
import json
import math
import os
import random
import re
import shutil
import subprocess
import time

import pytest

import fixtures as FX
from conftest import BINARY, REPO, SANITIZED, START_TIMEOUT

ID_RE = re.compile(r"^[0-9a-f]{32}$")


def reordered(obj):
    """The same JSON value with every object's keys in reverse order."""
    if isinstance(obj, dict):
        return {k: reordered(obj[k]) for k in reversed(list(obj))}
    if isinstance(obj, list):
        return [reordered(x) for x in obj]
    return obj


def put_text(client, fixture_text, id=1):
    client.send_line('{"jsonrpc":"2.0","method":"fixture.put","params":{"fixture":%s},"id":%d}'
                     % (fixture_text, id))
    r = client.read_json()
    assert r.get("id") == id and "result" in r, r
    return r["result"]


def numbers_equal(given, stored, path="fixture"):
    """Every member given is stored with the same value (numbers as
    doubles); the stored form may add members (defaults)."""
    if isinstance(given, dict):
        assert isinstance(stored, dict), (path, stored)
        for k, v in given.items():
            assert k in stored, "%s.%s missing from the stored fixture" % (path, k)
            numbers_equal(v, stored[k], path + "." + k)
    elif isinstance(given, list):
        assert isinstance(stored, list) and len(stored) == len(given), (path, stored)
        for i, (a, b) in enumerate(zip(given, stored)):
            numbers_equal(a, b, "%s[%d]" % (path, i))
    elif isinstance(given, (int, float)) and not isinstance(given, bool):
        assert isinstance(stored, (int, float)) and float(given) == float(stored), (path, stored)
    else:
        assert given == stored, (path, given, stored)


# ---- idempotence --------------------------------------------------------------

def test_put_twice_same_id(client):
    a = client.result("fixture.put", {"fixture": FX.disc_corner(0.5)})
    b = client.result("fixture.put", {"fixture": FX.disc_corner(0.5)})
    assert ID_RE.match(a["id"]) and a["id"] == b["id"], (a, b)
    assert len(client.result("fixture.list", {})["fixtures"]) == 1


@pytest.mark.parametrize("make", [lambda: FX.disc_corner(0.5), lambda: FX.rectangle_321(0.3),
                                  FX.offset_disc, FX.triangle])
def test_reordered_keys_same_id(client, make):
    f = make()
    a = client.result("fixture.put", {"fixture": f})["id"]
    g = reordered(f)
    assert json.dumps(g) != json.dumps(f)
    b = client.result("fixture.put", {"fixture": g})["id"]
    assert a == b


def test_number_spellings_same_id(client):
    """1, 1.0, 1e0 and 10E-1 are one number; 0.5, 5e-1, 0.50 another
    (PROTOCOL: numbers as the shortest text that reads back to the same
    double)."""
    template = ('{"name":"n","body":{"mass":%s,"inertia":%s,"com":[0,0],'
                '"shape":{"type":"circle","center":[0,0],"radius":%s}},'
                '"friction":{"static":%s,"kinetic":%s},'
                '"fixels":[{"at":[-1,0],"normal":[%s,0]},{"at":[0,-1],"normal":[0,1]}]}')
    spellings = [
        ("1", "0.5", "1", "0.5", "0.5", "1"),
        ("1.0", "5e-1", "1.0", "0.50", "5E-1", "1.0"),
        ("1e0", "0.5e0", "10E-1", "50e-2", "0.500", "1e+0"),
        ("1.000", "500e-3", "0.1e1", "0.5", "5.0e-1", "100e-2"),
    ]
    ids = {put_text(client, template % s, i)["id"] for i, s in enumerate(spellings)}
    assert len(ids) == 1, ids
    # and that is the id of the Python-encoded dict with floats
    assert client.result("fixture.put", {"fixture": FX.disc_corner(0.5)})["id"] in ids


def canonical(value):
    """PROTOCOL's canonical form: keys sorted, no spaces, numbers as the
    shortest text that reads back to the same double (1.0 is "1")."""
    if isinstance(value, dict):
        return "{" + ",".join(json.dumps(k) + ":" + canonical(value[k])
                              for k in sorted(value)) + "}"
    if isinstance(value, list):
        return "[" + ",".join(canonical(v) for v in value) + "]"
    if isinstance(value, bool) or value is None:
        return json.dumps(value)
    if isinstance(value, (int, float)):
        if float(value) == int(value) and abs(value) < 1e15:
            return str(int(value))
        text = repr(float(value))
        assert "e" not in text, "keep the test's numbers free of exponents"
        return text
    return json.dumps(value, ensure_ascii=False)


def text_id(fixture):
    """The first half of the SHA-256 of the canonical text of `fixture`
    without its name."""
    body = {k: v for k, v in fixture.items() if k != "name"}
    return hashlib.sha256(canonical(body).encode()).hexdigest()[:32]


def legacy_id(fixture):
    """The id before ids hashed the explicit form: that of the fixture as
    written (what older daemons named their files by)."""
    return text_id(fixture)


def explicit(fixture):
    """PROTOCOL's explicit form of a fixture that gives its body's com and
    inertia and every fixel's normal (unit): the fixture's friction copied
    into every fixel without its own, "kinetic" filled in with "static", no
    top-level friction.  Nothing here is computed, only moved."""
    f = copy.deepcopy(fixture)
    default = f.pop("friction", None)
    for fixel in f["fixels"]:
        friction = dict(fixel.get("friction", default))
        friction.setdefault("kinetic", friction["static"])
        fixel["friction"] = friction
    return f


def expected_id(fixture):
    return text_id(explicit(fixture))


def test_id_is_sha256_of_canonical_form(client):
    """PROTOCOL: the id is the first half of the SHA-256 of the canonical
    text of the explicit form (every field but name), computed here for
    fixtures that give com, inertia and normals (so that nothing has to be
    computed, only moved)."""
    full_rect = {
        "name": "full-rect",
        "body": {"mass": 2, "inertia": 1.25, "com": [2.5, 1],
                 "shape": {"type": "polygon", "vertices": [[0, 0], [4, 0], [4, 2], [0, 2]]}},
        "friction": {"static": 0.3, "kinetic": 0.25},
        "fixels": [{"at": [1, 0], "normal": [0, 1]},
                   {"at": [3, 0], "normal": [0, 1], "friction": {"static": 0.6, "kinetic": 0.5}},
                   {"at": [0, 1], "normal": [1, 0]}],
    }
    for f in (FX.disc_corner(0.5), FX.disc_corner(0.25, kinetic=0.125), FX.disc_corner(1.5),
              full_rect):
        r = client.result("fixture.put", {"fixture": f})
        assert r["id"] == expected_id(f), (f["name"], canonical(f))


def test_name_not_in_id_and_replaced(client):
    a = client.result("fixture.put", {"fixture": FX.disc_corner(0.5, name="first")})
    b = client.result("fixture.put", {"fixture": FX.disc_corner(0.5, name="second")})
    assert a["id"] == b["id"] and b["name"] == "second"
    listed = client.result("fixture.list", {})["fixtures"]
    assert [(x["id"], x["name"]) for x in listed] == [(a["id"], "second")]
    assert client.result("fixture.get", {"id": a["id"]})["name"] == "second"


def test_content_changes_id(client):
    base = client.result("fixture.put", {"fixture": FX.disc_corner(0.5)})["id"]
    others = [
        FX.disc_corner(0.51),
        FX.disc_corner(0.5, kinetic=0.4),
        FX.disc_corner(0.5, inertia=0.6),
        FX.variant(FX.disc_corner(0.5), ["body", "mass"], 2.0),
        FX.variant(FX.disc_corner(0.5), ["fixels", 1, "at"], [0.6, -0.8]),
    ]
    others[-1]["fixels"][1]["normal"] = [-0.6, 0.8]
    ids = {client.result("fixture.put", {"fixture": f})["id"] for f in others}
    assert base not in ids and len(ids) == len(others)


# ---- get / delete / list --------------------------------------------------------

@pytest.mark.parametrize("make", [lambda: FX.disc_corner(0.5), lambda: FX.rectangle_321(0.3),
                                  FX.offset_disc, FX.triangle, FX.chamfered_plate])
def test_get_round_trip(client, make):
    f = make()
    fid = client.result("fixture.put", {"fixture": f})["id"]
    got = client.result("fixture.get", {"id": fid})
    assert got["name"] == f["name"]
    # What was given is stored: the friction in each fixel, normals of unit
    # length (these builders' normals normalise exactly).
    given = copy.deepcopy(f)
    for fixel in given["fixels"]:
        fixel.setdefault("friction", given.get("friction"))
        if "normal" in fixel:
            length = (fixel["normal"][0] ** 2 + fixel["normal"][1] ** 2) ** 0.5
            fixel["normal"] = [x / length for x in fixel["normal"]]
    given.pop("friction", None)
    numbers_equal(given, got)
    assert client.result("fixture.put", {"fixture": got})["id"] == fid
    # the stored form answers exactly like the original
    w = {"fixture": fid, "wrenches": [[-1, -1, 0.3], [0.2, -1, 0]], "sets": ["goal", "strong"]}
    w2 = dict(w, fixture=got)
    assert client.result("wrench.classify", w) == client.result("wrench.classify", w2)


def test_unicode_name_round_trip(client):
    f = FX.disc_corner(0.5, name="disque \u2014 coin \u2713 \"quoted\" \\ tab\t")
    fid = client.result("fixture.put", {"fixture": f})["id"]
    assert client.result("fixture.get", {"id": fid})["name"] == f["name"]
    assert client.result("fixture.list", {})["fixtures"][0]["name"] == f["name"]


def test_name_with_nul_refused(client):
    """A name holding U+0000 is refused whole (-32600, docs/PROTOCOL.md), not
    stored cut at the NUL; nothing is stored."""
    f = FX.disc_corner(0.5, name="a\u0000b")
    client.send({"jsonrpc": "2.0", "method": "fixture.put", "params": {"fixture": f}, "id": 1})
    r = client.read_json()
    assert r["error"]["code"] == -32600 and r["error"]["data"]["field"] == "", r
    assert r["id"] is None, r
    assert client.result("fixture.list", {})["fixtures"] == []


def test_delete(client):
    a = client.result("fixture.put", {"fixture": FX.disc_corner(0.5)})["id"]
    b = client.result("fixture.put", {"fixture": FX.rectangle_321(0.3)})["id"]
    assert client.result("fixture.delete", {"id": a}) == {"deleted": True}
    e = client.error("fixture.get", {"id": a})
    assert e["code"] == -32001 and e["data"]["field"] == "params.id", e
    e = client.error("fixture.delete", {"id": a})
    assert e["code"] == -32001 and e["data"]["field"] == "params.id", e
    e = client.error("wrench.classify", {"fixture": a, "wrenches": [[0, 0, 1]]})
    assert e["code"] == -32001 and e["data"]["field"] == "params.fixture", e
    assert [x["id"] for x in client.result("fixture.list", {})["fixtures"]] == [b]
    # putting it again brings it back under the same id
    assert client.result("fixture.put", {"fixture": FX.disc_corner(0.5)})["id"] == a


def test_list_sorted_with_counts(client):
    fs = FX.many(12)
    ids = {}
    for f in fs:
        ids[client.result("fixture.put", {"fixture": f})["id"]] = f
    listed = client.result("fixture.list", {})
    assert set(listed) == {"fixtures", "more"} and listed["more"] is False
    rows = listed["fixtures"]
    assert [r["id"] for r in rows] == sorted(ids), rows
    for r in rows:
        assert set(r) == {"id", "name", "fixels"}, r
        f = ids[r["id"]]
        assert r["name"] == f["name"]
        n = r["fixels"]
        assert (n if isinstance(n, int) else len(n)) == len(f["fixels"]), r
    assert client.result("fixture.list") == listed  # params left out


def test_inline_fixture_cached_but_not_visible(harness):
    """An inline fixture's derived data is cached under its id, but it is not
    stored: fixture.get, a classify by id and fixture.list do not see it."""
    d = harness.start()
    c = d.client()
    f = FX.triangle()
    c.result("wrench.classify", {"fixture": f, "wrenches": [[0, 0, 1]]})
    assert c.result("server.status", {})["cached"] >= 1
    other = harness.start(socket_path=harness.path("o.sock")).client()
    fid = other.result("fixture.put", {"fixture": f})["id"]
    e = c.error("fixture.get", {"id": fid})
    assert e["code"] == -32001 and e["data"]["field"] == "params.id", e
    e = c.error("wrench.classify", {"fixture": fid, "wrenches": [[0, 0, 1]]})
    assert e["code"] == -32001 and e["data"]["field"] == "params.fixture", e
    e = c.error("fixture.delete", {"id": fid})
    assert e["code"] == -32001, e
    assert c.result("fixture.list", {}) == {"fixtures": [], "more": False}


def test_fixtures_shared_between_clients(daemon):
    a, b = daemon.client(), daemon.client()
    fid = a.result("fixture.put", {"fixture": FX.triangle()})["id"]
    assert b.result("fixture.get", {"id": fid})["name"] == "triangle"
    b.result("fixture.delete", {"id": fid})
    assert a.error("fixture.get", {"id": fid})["code"] == -32001


# ---- persistence ---------------------------------------------------------------

def test_persistence_after_sigkill(harness):
    """Put 50 fixtures with --state-dir, SIGKILL the daemon, restart it on the
    same directory: all 50 are there, with the same ids, names and content;
    a fixture deleted before the kill stays deleted."""
    state = harness.path("state")
    d = harness.start(state_dir=state)
    c = d.client()
    fs = FX.many(50)
    ids = [c.result("fixture.put", {"fixture": f})["id"] for f in fs]
    assert len(set(ids)) == 50
    extra = c.result("fixture.put", {"fixture": FX.disc_one_fixel()})["id"]
    assert c.result("fixture.delete", {"id": extra}) == {"deleted": True}
    stored = {i: c.result("fixture.get", {"id": i}) for i in ids}
    probe = {"wrenches": [[-1, -1, 0], [0.3, -1, 0.2]], "sets": ["goal", "strong"]}
    answers = {i: c.result("wrench.classify", dict(probe, fixture=i)) for i in ids[:6]}
    d.kill()

    d2 = harness.start(state_dir=state)
    c2 = d2.client()
    listed = c2.result("fixture.list", {})["fixtures"]
    assert sorted(x["id"] for x in listed) == sorted(ids)
    assert {x["id"]: x["name"] for x in listed} == {i: f["name"] for i, f in zip(ids, fs)}
    assert c2.result("server.status", {})["fixtures"] == 50
    for i, f in zip(ids, fs):
        got = c2.result("fixture.get", {"id": i})
        assert got == stored[i]
        assert c2.result("fixture.put", {"fixture": f})["id"] == i
    assert c2.error("fixture.get", {"id": extra})["code"] == -32001
    for i, a in answers.items():
        assert c2.result("wrench.classify", dict(probe, fixture=i)) == a
    # a clean stop keeps them too
    d2.stop()
    d3 = harness.start(state_dir=state)
    assert len(d3.client().result("fixture.list", {})["fixtures"]) == 50


def test_state_dir_created_and_rename_persisted(harness):
    """A state directory that does not exist yet is created; a new name for
    the same content survives a restart."""
    state = harness.path("new/state")
    d = harness.start(state_dir=state)
    c = d.client()
    fid = c.result("fixture.put", {"fixture": FX.disc_corner(0.5, name="a")})["id"]
    c.result("fixture.put", {"fixture": FX.disc_corner(0.5, name="b")})
    assert os.path.isdir(state)
    d.kill()
    d2 = harness.start(state_dir=state)
    c2 = d2.client()
    listed = c2.result("fixture.list", {})["fixtures"]
    assert [(x["id"], x["name"]) for x in listed] == [(fid, "b")]
    assert c2.result("fixture.get", {"id": fid})["name"] == "b"


def test_load_files(harness):
    """--load FILE (repeatable) puts the fixtures in those files at start."""
    paths = []
    for i, f in enumerate([FX.disc_corner(0.5), FX.rectangle_321(0.3)]):
        p = harness.path("f%d.json" % i)
        with open(p, "w") as out:
            json.dump(f, out, indent=2)
        paths.append(p)
    d = harness.start("--load", paths[0], "--load", paths[1])
    c = d.client()
    listed = c.result("fixture.list", {})["fixtures"]
    assert sorted(x["name"] for x in listed) == ["disc-corner", "plate-3-2-1"]
    ids = sorted(x["id"] for x in listed)
    probe = harness.start(socket_path=harness.path("p.sock")).client()
    expected = sorted(probe.result("fixture.put", {"fixture": f})["id"]
                      for f in [FX.disc_corner(0.5), FX.rectangle_321(0.3)])
    assert ids == expected


def test_kill_during_puts_leaves_only_whole_fixtures(harness):
    """SIGKILL while puts stream in: after restart every listed fixture is
    complete (get works, classify works) and every put that was answered is
    there."""
    state = harness.path("state")
    d = harness.start(state_dir=state)
    c = d.client()
    fs = FX.many(30)
    for i, f in enumerate(fs):
        c.send(c.request("fixture.put", {"fixture": f}, id=i))
    answered = []
    for _ in range(15):
        r = c.read_json()
        answered.append(r["result"]["id"])
    d.kill()
    d2 = harness.start(state_dir=state)
    c2 = d2.client()
    listed = [x["id"] for x in c2.result("fixture.list", {})["fixtures"]]
    assert set(answered) <= set(listed)
    for i in listed:
        c2.result("fixture.get", {"id": i})
        c2.result("wrench.classify", {"fixture": i, "wrenches": [[0, -1, 0]]})


def test_load_invalid_file_exits_1(harness):
    """README: a --load file that is not a valid fixture stops the start."""
    bad = harness.path("bad.json")
    with open(bad, "w") as f:
        json.dump(FX.variant(FX.disc_corner(0.5), ["body", "mass"], -1), f)
    p = harness.run("--socket", harness.path("l.sock"), "--load", bad, timeout=20)
    assert p.returncode == 1, (p.returncode, p.stderr[-2000:])


def test_unreadable_state_file_skipped(harness):
    """README: at start every file of DIR/fixtures is loaded; one that does
    not read back is logged and skipped -- the others still load."""
    state = harness.path("state")
    d = harness.start(state_dir=state)
    c = d.client()
    ids = [c.result("fixture.put", {"fixture": f})["id"] for f in FX.many(4)]
    d.stop()
    folder = os.path.join(state, "fixtures")
    assert sorted(os.listdir(folder)) == sorted(i + ".json" for i in ids), os.listdir(folder)
    with open(os.path.join(folder, ids[0] + ".json"), "r+") as f:
        f.truncate(10)
    with open(os.path.join(folder, "0" * 32 + ".json"), "w") as f:
        f.write("{not json")
    d2 = harness.start(state_dir=state)
    listed = sorted(x["id"] for x in d2.client().result("fixture.list", {})["fixtures"])
    assert listed == sorted(ids[1:]), listed


def test_storage_failure_changes_nothing(harness):
    """When the state directory cannot be written, a put answers -32002 and
    nothing changes (the fixture is not held in memory either); a delete
    that cannot be written leaves the fixture in place."""
    state = harness.path("state")
    d = harness.start(state_dir=state)
    c = d.client()
    a = c.result("fixture.put", {"fixture": FX.disc_corner(0.5)})["id"]
    folder = os.path.join(state, "fixtures")
    assert os.path.isdir(folder)
    shutil.move(folder, folder + ".away")
    with open(folder, "w") as f:
        f.write("a file where the directory was\n")
    e = c.error("fixture.put", {"fixture": FX.triangle()})
    assert e["code"] == -32002, e
    assert [x["id"] for x in c.result("fixture.list", {})["fixtures"]] == [a]
    e = c.error("fixture.delete", {"id": a})
    assert e["code"] == -32002, e
    assert c.result("fixture.get", {"id": a})["name"] == "disc-corner"
    assert c.result("server.status", {})["fixtures"] == 1


# ---- ids of the explicit form ----------------------------------------------------

def spellings():
    """Pairs of fixtures that differ only in writing out a default."""
    plate = FX.rectangle_321(0.3)
    plate_explicit = copy.deepcopy(plate)
    plate_explicit["friction"]["kinetic"] = 0.3             # kinetic = static
    plate_explicit["body"]["com"] = [2, 1]                  # the centroid
    for fixel, normal in zip(plate_explicit["fixels"], [[0, 1], [0, 1], [1, 0]]):
        fixel["normal"] = normal                            # the edges' inward normals
    per_fixel = copy.deepcopy(plate)                        # the friction in every fixel
    for fixel in per_fixel["fixels"]:
        fixel["friction"] = {"static": 0.3}
    del per_fixel["friction"]
    disc = FX.disc_corner(0.5)
    disc_implicit = copy.deepcopy(disc)
    del disc_implicit["friction"]["kinetic"]
    for fixel in disc_implicit["fixels"]:
        del fixel["normal"]                                 # the circle's normals
    return [(plate, plate_explicit), (plate, per_fixel), (disc, disc_implicit),
            (FX.triangle(), FX.variant(FX.triangle(), ["fixels", 0, "normal"], [0, 1]))]


@pytest.mark.parametrize("pair", range(4))
def test_writing_out_a_default_keeps_the_id(client, pair):
    """A "kinetic" equal to "static", a com equal to the shape's, a
    normal equal to the derived one, the fixture's friction written in every
    fixel, a normal written at unit length: one fixture, one id."""
    a, b = spellings()[pair]
    assert canonical(a) != canonical(b)
    assert client.result("fixture.put", {"fixture": a})["id"] == \
        client.result("fixture.put", {"fixture": b})["id"]


def test_inertia_written_out_keeps_the_id(client):
    """The inertia the shape gives (the value fixture.get shows, a computed
    double) written out, and the com with it: the same id."""
    plate = FX.chamfered_plate()
    fid = client.result("fixture.put", {"fixture": plate})["id"]
    body = client.result("fixture.get", {"id": fid})["body"]
    written = copy.deepcopy(plate)
    written["body"]["inertia"] = body["inertia"]
    assert client.result("fixture.put", {"fixture": written})["id"] == fid
    written["body"]["inertia"] = body["inertia"] * 1.01  # another fixture
    assert client.result("fixture.put", {"fixture": written})["id"] != fid


def every_fixture():
    fs = [json.load(open(p)) for p in sorted(glob.glob(os.path.join(REPO, "examples", "*.json")))]
    assert len(fs) >= 4
    fs += [FX.disc_corner(), FX.disc_corner(0.25, kinetic=0.125), FX.rectangle_321(),
           FX.rectangle_321(clockwise=True), FX.chamfered_plate(), FX.disc_one_fixel(),
           FX.offset_disc(), FX.triangle(), FX.corner_fixel_plate(), FX.square_form_closure(),
           FX.scaled_disc_corner(length=1e-3, mass=1e3)] + FX.many(12)
    rnd = random.Random(14)
    for i in range(40):
        fs.append(FX.random_polygon(rnd, convex=i % 2 == 0, corner=i % 3 == 0))
        fs.append(FX.random_disc(rnd, corner=i % 2 == 0))
        fs.append(FX.moved(fs[-2], degrees=rnd.uniform(0, 360), shift=(rnd.uniform(-5, 5), 1.5)))
    return fs


def test_get_put_gives_the_id_back_and_the_id_is_its_hash(client):
    """For every example and every fixture of the tests: fixture.get is the
    explicit form (com, inertia, every fixel's normal and own friction, no
    top-level friction), putting it gives the same id, and the id is the
    SHA-256 of its canonical text without the name, computed here."""
    for f in every_fixture():
        fid = client.result("fixture.put", {"fixture": f})["id"]
        got = client.result("fixture.get", {"id": fid})
        # units: only a fixture that names them has them (docs/PROTOCOL.md,
        # "Units"), the same as it was given
        assert set(got) <= {"name", "body", "fixels", "units", "supports"}, got
        assert "friction" not in got, got
        assert got.get("units") == f.get("units"), (f.get("units"), got)
        # supports: only a fixture on a base plate has them
        assert ("supports" in got) == ("supports" in f), got
        assert {"mass", "inertia", "com"} <= set(got["body"]), got
        for fixel in got["fixels"]:
            assert set(fixel) == {"at", "normal", "friction"}, got
            assert set(fixel["friction"]) == {"static", "kinetic"}, got
        assert text_id(got) == fid, (f.get("name"), got)
        assert client.result("fixture.put", {"fixture": got})["id"] == fid, f.get("name")
        again = client.result("fixture.get", {"id": fid})
        assert canonical(again) == canonical(got)


# ---- the state directory ---------------------------------------------------------

def test_second_daemon_on_the_same_state_dir_refused(harness):
    """A second daemon on the same --state-dir is refused (exit
    status 1) with a message naming the directory and the holder's pid; once
    the first has stopped, the directory can be used again."""
    state = harness.path("state")
    first = harness.start(state_dir=state)
    fid = first.client().result("fixture.put", {"fixture": FX.triangle()})["id"]
    p = harness.run("--socket", harness.path("second.sock"), "--state-dir", state,
                    timeout=START_TIMEOUT)
    err = p.stderr.decode(errors="replace")
    assert p.returncode == 1, (p.returncode, err[-2000:])
    assert state in err and "pid %d" % first.pid in err, err[-2000:]
    assert not os.path.exists(harness.path("second.sock"))
    assert [x["id"] for x in first.client().result("fixture.list")["fixtures"]] == [fid]
    first.stop()
    again = harness.start(state_dir=state)
    assert [x["id"] for x in again.client().result("fixture.list")["fixtures"]] == [fid]


def test_a_file_named_otherwise_is_refused_and_a_delete_sticks(harness):
    """A file whose name and content disagree is not loaded (a log
    line says why; the file is left in place), so deleting the fixture it
    holds leaves nothing on disk to come back at the next start."""
    state = harness.path("state")
    folder = os.path.join(state, "fixtures")
    d = harness.start(state_dir=state)
    fid = d.client().result("fixture.put", {"fixture": FX.triangle()})["id"]
    d.stop()
    stray = os.path.join(folder, "0123456789abcdef0123456789abcdef.json")
    os.rename(os.path.join(folder, fid + ".json"), stray)
    d2 = harness.start(state_dir=state)
    c2 = d2.client()
    assert c2.result("fixture.list")["fixtures"] == []
    assert stray in d2.stderr() and fid in d2.stderr(), d2.stderr()[-2000:]
    assert os.path.exists(stray)
    # put, delete, restart: gone for good
    assert c2.result("fixture.put", {"fixture": FX.triangle()})["id"] == fid
    assert c2.result("fixture.delete", {"id": fid}) == {"deleted": True}
    d2.stop()
    d3 = harness.start(state_dir=state)
    assert d3.client().result("fixture.list")["fixtures"] == []
    assert d3.client().error("fixture.get", {"id": fid})["code"] == -32001


def test_files_of_older_ids_are_re_keyed(harness):
    """Fixtures stored under the older ids (the hash of the text
    as written) keep loading, under their new id, re-keyed on disk with a
    log line; afterwards one file is left per fixture, and a delete
    sticks."""
    state = harness.path("state")
    folder = os.path.join(state, "fixtures")
    os.makedirs(folder)
    fs = [FX.triangle(), FX.rectangle_321(0.3), FX.disc_corner(0.5, name="disc")]
    for f in fs:
        with open(os.path.join(folder, legacy_id(f) + ".json"), "w") as out:
            out.write(canonical(f) + "\n")
    # another spelling of the disc, under its own older id: the same fixture
    other = FX.disc_corner(0.5, name="disc again")
    del other["friction"]["kinetic"]
    with open(os.path.join(folder, legacy_id(other) + ".json"), "w") as out:
        out.write(canonical(other) + "\n")
    probe = harness.start(socket_path=harness.path("probe.sock")).client()
    new = [probe.result("fixture.put", {"fixture": f})["id"] for f in fs]
    assert all(n != legacy_id(f) for n, f in zip(new, fs))

    d = harness.start("--log-level", "info", state_dir=state)  # re-keying logs at info
    c = d.client()
    listed = c.result("fixture.list")["fixtures"]
    assert sorted(x["id"] for x in listed) == sorted(new), listed
    assert {x["id"]: x["name"] for x in listed}[new[0]] == "triangle"
    assert sorted(os.listdir(folder)) == sorted(n + ".json" for n in new), os.listdir(folder)
    assert "re-keyed" in d.stderr() and legacy_id(fs[0]) in d.stderr(), d.stderr()[-3000:]
    for n in new:
        got = c.result("fixture.get", {"id": n})
        assert text_id(got) == n
    assert c.result("fixture.delete", {"id": new[2]}) == {"deleted": True}
    d.stop()
    d2 = harness.start(state_dir=state)
    listed = d2.client().result("fixture.list")["fixtures"]
    assert sorted(x["id"] for x in listed) == sorted(new[:2]), listed
    assert sorted(os.listdir(folder)) == sorted(n + ".json" for n in new[:2])


# ---- --max-fixtures ------------------------------------------------------------

def test_max_fixtures(harness):
    """--max-fixtures caps the stored fixtures: a put of a new one
    past it answers -32003 (data.field "params.fixture", naming the option)
    and stores nothing; a put of a stored one (even renamed) still succeeds;
    after a delete there is room again."""
    state = harness.path("state")
    d = harness.start("--max-fixtures", "3", state_dir=state)
    c = d.client()
    fs = FX.many(4)
    ids = [c.result("fixture.put", {"fixture": f})["id"] for f in fs[:3]]
    e = c.error("fixture.put", {"fixture": fs[3]})
    assert e["code"] == -32003 and e["data"]["field"] == "params.fixture", e
    assert "--max-fixtures" in e["data"]["reason"], e
    assert sorted(x["id"] for x in c.result("fixture.list")["fixtures"]) == sorted(ids)
    assert len(os.listdir(os.path.join(state, "fixtures"))) == 3
    renamed = dict(fs[0], name="renamed")
    assert c.result("fixture.put", {"fixture": renamed})["id"] == ids[0]
    assert c.result("fixture.put", {"fixture": fs[1]})["id"] == ids[1]
    # inline fixtures are not stored, so not counted
    c.result("wrench.classify", {"fixture": fs[3], "wrenches": [[0, -1, 0]]})
    c.result("fixture.delete", {"id": ids[2]})
    c.result("fixture.put", {"fixture": fs[3]})
    assert c.result("server.status")["fixtures"] == 3


def test_max_fixtures_in_the_config_file(harness):
    conf = harness.path("wrenchd.conf")
    with open(conf, "w") as f:
        f.write("max-fixtures = 1\n")
    d = harness.start("--config", conf)
    c = d.client()
    c.result("fixture.put", {"fixture": FX.triangle()})
    assert c.error("fixture.put", {"fixture": FX.disc_corner()})["code"] == -32003


@pytest.mark.skipif(SANITIZED, reason="a sanitizer's allocator keeps freed memory")
def test_inline_fixtures_stay_within_the_cache_bound(harness):
    """Inline fixtures are cached, not stored: --cache-mb bounds them with
    their own text, so distinct large ones do not grow memory without
    bound."""
    from test_hostile import resident_kib
    d = harness.start("--cache-mb", "1", "--threads", "1")
    c = d.client()
    c.result("server.status")
    before = resident_kib(d.pid)
    # A disc as a 4000-gon: 170 KB of text each (names are at most 1 KiB).
    n = 4000
    vertices = [[math.cos(-math.pi / 2 + 2 * math.pi * k / n),
                 math.sin(-math.pi / 2 + 2 * math.pi * k / n)] for k in range(n)]
    for i in range(150):
        f = {"name": "%d" % i, "body": {"mass": 1 + i / 1024, "inertia": 0.5, "com": [0, 0],
                                        "shape": {"type": "polygon", "vertices": vertices}},
             "friction": {"static": 0.5}, "fixels": [{"at": vertices[0], "normal": [0, 1]}]}
        c.result("wrench.classify", {"fixture": f, "wrenches": [[0, -1, 0]]})
    status = c.result("server.status")
    assert status["cache_bytes"] <= status["cache_limit_bytes"], status
    growth = resident_kib(d.pid) - before
    assert growth < 14 * 1024, (growth, status)  # KiB; 150 x 170 KB held would be 25 MB
