"""Concurrency: 16 clients x 500 classify requests, every answer checked;
clients putting and deleting their own fixtures while others classify."""

import json
import math
import threading

import fixtures as FX
import helpers as H
import model as M

CLIENTS = 16
REQUESTS = 500
WINDOW = 25
SETS = ("goal", "strong", "both")


def expectations(fixture, seed, n):
    cl = M.Classifier(M.Model(fixture))
    ws = H.random_wrenches(seed=seed, n=n, scale=(1, 1, 2))
    return ws, {g: {s: cl.classify(g, s) for s in SETS} for g in ws}


def check(v, e, where):
    assert abs(v["margin"] - e.margin) <= 1e-7, (where, v, e)
    if abs(e.margin) > 1e-7:
        assert v["verdict"] == e.verdict(), (where, v, e)
    if v["verdict"] == "inside":
        assert v["blocking"] is None, (where, v)
    elif e.margin < -1e-6:
        assert v["blocking"] in e.candidates, (where, v, e)


def run_threads(target, n):
    errors = []

    def wrap(i):
        try:
            target(i)
        except BaseException as exc:  # reported below
            errors.append("client %d: %r" % (i, exc))

    threads = [threading.Thread(target=wrap, args=(i,)) for i in range(n)]
    for t in threads:
        t.start()
    for t in threads:
        t.join(300)
    assert not any(t.is_alive() for t in threads), "a client thread hung"
    assert not errors, "\n".join(errors[:10])


def test_sixteen_clients_classify(daemon):
    """16 concurrent clients, 500 classify requests each (pipelined 25 at a
    time), on a stored disc-in-a-corner, a stored 3-2-1 plate and the plate
    inline: every answer in order, every margin and verdict right."""
    disc, plate = FX.disc_corner(0.5), FX.rectangle_321(0.3)
    disc_ws, disc_exp = expectations(disc, 21, 40)
    plate_ws, plate_exp = expectations(plate, 22, 40)
    setup = daemon.client()
    disc_id = setup.result("fixture.put", {"fixture": disc})["id"]
    plate_id = setup.result("fixture.put", {"fixture": plate})["id"]
    before = setup.result("server.status", {})
    counts = [0] * CLIENTS

    def client_main(i):
        c = daemon.client()
        for start in range(0, REQUESTS, WINDOW):
            batch = []
            for k in range(start, start + WINDOW):
                choice = (i + k) % 3
                if choice == 0:
                    ref, ws, exp = disc_id, disc_ws, disc_exp
                elif choice == 1:
                    ref, ws, exp = plate_id, plate_ws, plate_exp
                else:
                    ref, ws, exp = plate, plate_ws, plate_exp
                chosen = [ws[(i * 7 + k + j) % len(ws)] for j in range(1 + k % 3)]
                req = {"jsonrpc": "2.0", "method": "wrench.classify", "id": k + 1000 * i,
                       "params": {"fixture": ref, "wrenches": [list(g) for g in chosen],
                                  "sets": list(SETS)}}
                batch.append((req, chosen, exp))
            c.send_raw("".join(json.dumps(r) + "\n" for r, _, _ in batch))
            for req, chosen, exp in batch:
                a = c.read_json(timeout=60)
                assert a.get("id") == req["id"], ("out of order", a.get("id"), req["id"])
                assert "result" in a, a
                res = a["result"]["results"]
                assert len(res) == len(chosen)
                for g, r in zip(chosen, res):
                    for s in SETS:
                        check(r[s], exp[g][s], (i, req["id"], g, s))
                counts[i] += 1
        c.close()

    run_threads(client_main, CLIENTS)
    assert sum(counts) == CLIENTS * REQUESTS
    after = daemon.client().result("server.status", {})
    assert after["requests"] - before["requests"] >= CLIENTS * REQUESTS
    assert after["errors"] == before["errors"], (before, after)
    assert after["fixtures"] == 2


def test_puts_and_deletes_do_not_disturb_others(daemon):
    """Eight clients each put 20 fixtures of their own, classify against
    them and delete every other one, all at once: each sees its own, and
    the final list is exactly what was not deleted."""
    fixtures = FX.many(160)
    kept = {}
    lock = threading.Lock()

    def client_main(i):
        c = daemon.client()
        mine = fixtures[i * 20:(i + 1) * 20]
        ids = [c.result("fixture.put", {"fixture": f})["id"] for f in mine]
        for fid, f in zip(ids, mine):
            got = c.result("fixture.get", {"id": fid})
            assert got["name"] == f["name"]
            r = c.result("wrench.classify", {"fixture": fid, "wrenches": [[0, -1, 0.1]]})
            assert len(r["results"]) == 1
        for fid in ids[::2]:
            assert c.result("fixture.delete", {"id": fid}) == {"deleted": True}
        with lock:
            for fid, f in list(zip(ids, mine))[1::2]:
                kept[fid] = f["name"]
        c.close()

    run_threads(client_main, 8)
    listed = daemon.client().result("fixture.list", {})["fixtures"]
    assert {x["id"]: x["name"] for x in listed} == kept


def test_tiny_cache_under_load(harness):
    """--cache-mb 1 with an 8-fixel fixture (about a megabyte of cones) and
    twelve others classified round-robin by 8 clients at once: derived data
    is evicted and rebuilt all the time, yet every answer is right and the
    cache stays within its bound."""
    d = harness.start("--cache-mb", "1")
    fs = FX.many(12)
    big = FX.disc_corner(0.3, name="eight")
    big["fixels"] = [{"at": [math.cos(math.radians(200 + 15 * i)),
                             math.sin(math.radians(200 + 15 * i))]} for i in range(8)]
    exps = []
    for n, f in enumerate(fs):
        exps.append(expectations(f, 300 + n, 3))
    setup = d.client()
    ids = [setup.result("fixture.put", {"fixture": f})["id"] for f in fs]
    big_id = setup.result("fixture.put", {"fixture": big})["id"]
    big_answer = setup.result("wrench.classify", {"fixture": big_id, "wrenches": [[0, 1, 0]],
                                                  "sets": list(SETS)})

    def client_main(i):
        c = d.client()
        for round_ in range(6):
            for n in range(len(fs)):
                k = (n + i + round_) % len(fs)
                ws, exp = exps[k]
                ref = ids[k] if (i + round_) % 2 else fs[k]
                r = c.result("wrench.classify", {"fixture": ref, "wrenches": [list(g) for g in ws],
                                                 "sets": list(SETS)})
                for g, v in zip(ws, r["results"]):
                    for s in SETS:
                        check(v[s], exp[g][s], (i, k, g, s))
            again = c.result("wrench.classify", {"fixture": big_id, "wrenches": [[0, 1, 0]],
                                                 "sets": list(SETS)})
            assert again == big_answer
            st = c.result("server.status", {})
            assert st["cache_bytes"] <= st["cache_limit_bytes"] == 1048576, st
        c.close()

    run_threads(client_main, 8)


def test_same_fixture_put_concurrently_with_state_dir(harness):
    """Eight clients put the same content (under different names) at once,
    20 times each, with --state-dir: every put answers the same id, one
    fixture is held, and after SIGKILL and a restart it is there, complete,
    under one of the names."""
    state = harness.path("state")
    d = harness.start(state_dir=state)
    f = FX.rectangle_321(0.3)
    ids = set()
    names = set()
    lock = threading.Lock()

    def client_main(i):
        c = d.client()
        for k in range(20):
            g = dict(f, name="name-%d-%d \u2713" % (i, k))
            r = c.result("fixture.put", {"fixture": g})
            with lock:
                ids.add(r["id"])
                names.add(g["name"])
        c.close()

    run_threads(client_main, 8)
    assert len(ids) == 1, ids
    (fid,) = ids
    listed = d.client().result("fixture.list", {})["fixtures"]
    assert [x["id"] for x in listed] == [fid] and listed[0]["name"] in names
    d.kill()
    d2 = harness.start(state_dir=state)
    c = d2.client()
    listed = c.result("fixture.list", {})["fixtures"]
    assert [x["id"] for x in listed] == [fid], listed
    assert listed[0]["name"] in names
    got = c.result("fixture.get", {"id": fid})
    assert got["name"] == listed[0]["name"]
    assert c.result("fixture.put", {"fixture": got})["id"] == fid


def test_concurrent_renames_answer_with_their_own_name(daemon):
    """Two clients put the same fixture under different names, over and over:
    each put's answer carries the name that put stored, never the other's
    (a put once read the name after releasing the store's lock)."""
    import threading
    wrong = []

    def put_as(name):
        c = daemon.client()
        fixture = FX.disc_corner(0.5, name=name)
        for i in range(3000):
            c.send({"jsonrpc": "2.0", "method": "fixture.put", "params": {"fixture": fixture},
                    "id": i})
            if i % 50 == 49:  # pipeline 50 at a time
                for _ in range(50):
                    r = c.read_json()
                    if r["result"]["name"] != name:
                        wrong.append(r)

    threads = [threading.Thread(target=put_as, args=("name-%d" % k,)) for k in range(2)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert not wrong, "%d answers carried the other client's name" % len(wrong)
