"""Framing (PROTOCOL.md): lines, batches, notifications, ids, pipelining,
and the limits --max-line, --max-depth, --max-wrenches, --max-clients,
--max-output."""

import json
import socket
import threading
import time

import pytest

import fixtures as FX
import helpers as H
from conftest import SLOW
import model as M


def check_response_shape(r):
    assert r.get("jsonrpc") == "2.0", r
    assert "id" in r, r
    if "error" in r:
        assert set(r) == {"jsonrpc", "id", "error"}, r
        e = r["error"]
        assert set(e) == {"code", "message", "data"}, e
        assert isinstance(e["code"], int) and isinstance(e["message"], str) and e["message"], e
        assert set(e["data"]) == {"field", "reason"}, e
        assert isinstance(e["data"]["field"], str), e
        assert isinstance(e["data"]["reason"], str) and e["data"]["reason"], e
    else:
        assert set(r) == {"jsonrpc", "id", "result"}, r


def req(method, params=None, id=None, notify=False):
    r = {"jsonrpc": "2.0", "method": method}
    if params is not None:
        r["params"] = params
    if not notify:
        r["id"] = id
    return r


# ---- batches and notifications ---------------------------------------------------

def test_batch_answers_in_order_without_notifications(client):
    batch = [
        req("fixture.put", {"fixture": FX.disc_corner(0.5)}, id=1),
        req("server.status", {}, notify=True),
        req("no.such.method", {}, id="two"),
        req("fixture.list", {}, id=None),
        req("fixture.put", {"fixture": {"body": 1}}, notify=True),
        req("wrench.classify", {"fixture": FX.disc_corner(0.5), "wrenches": [[-1, -1, 0]],
                                "sets": ["goal"]}, id=4.5),
    ]
    client.send(batch)
    line = client.read_line()
    answers = json.loads(line)
    assert isinstance(answers, list) and len(answers) == 4, answers
    for a in answers:
        check_response_shape(a)
    assert [a["id"] for a in answers] == [1, "two", None, 4.5]
    assert H.count_of(answers[0]["result"]["goal_cones"]) == 4, answers[0]
    assert answers[1]["error"]["code"] == -32601
    assert [x["id"] for x in answers[2]["result"]["fixtures"]] == [answers[0]["result"]["id"]]
    assert answers[3]["result"]["results"][0]["goal"]["verdict"] == "inside"
    client.expect_silence(0.2)


def test_batch_of_notifications_gets_no_answer(client):
    fid = client.result("fixture.put", {"fixture": FX.disc_corner(0.5)})["id"]
    client.send([req("fixture.delete", {"id": fid}, notify=True),
                 req("server.status", {}, notify=True)])
    client.send(req("fixture.list", {}, id=99))
    r = client.read_json()
    assert r["id"] == 99, r
    assert r["result"] == {"fixtures": [], "more": False}, r  # the notification's delete happened


def test_notifications_are_never_answered(client):
    client.send(req("fixture.put", {"fixture": FX.triangle()}, notify=True))
    client.send(req("no.such.method", {}, notify=True))
    client.send(req("fixture.put", {"fixture": {"body": "x"}}, notify=True))
    client.send(req("wrench.classify", {"fixture": "0" * 32, "wrenches": [[1, 2, 3]]},
                    notify=True))
    client.send(req("fixture.list", {}, id="after"))
    r = client.read_json()
    assert r["id"] == "after"
    assert [x["name"] for x in r["result"]["fixtures"]] == ["triangle"]
    client.expect_silence(0.2)


def test_batch_inside_pipeline(client):
    client.send_raw(json.dumps(req("server.status", {}, id=1)) + "\n" +
                    json.dumps([req("fixture.list", {}, id=2), req("fixture.list", {}, id=3)])
                    + "\n" + json.dumps(req("fixture.list", {}, id=4)) + "\n")
    a = client.read_json()
    b = client.read_json()
    c = client.read_json()
    assert a["id"] == 1
    assert [x["id"] for x in b] == [2, 3]
    assert c["id"] == 4


# ---- ids and lines -------------------------------------------------------------------

@pytest.mark.parametrize("id", ["abc", "", 0, -5, 1.5, None, 12345678901, "\u00e9\u2713",
                                "quote\" backslash\\ newline\n"])
def test_id_echoed(client, id):
    client.send(req("fixture.list", {}, id=id))
    r = client.read_json()
    check_response_shape(r)
    assert r["id"] == id and type(r["id"]) is type(id), r


@pytest.mark.parametrize("id", ["9007199254740993", "123456789012345678901234567890", "-0",
                                "1.50", "1E+05", "0.5e-3", "-12"])
def test_numeric_id_echoed_as_written(client, id):
    """JSON-RPC echoes the id itself: the client's text, not a double's
    (9007199254740993 is not a double; a 30-digit id is not 1.23e+29)."""
    client.send_raw(('{"jsonrpc":"2.0","method":"fixture.list","id": %s}\n' % id).encode())
    line = client.read_line()
    assert line.endswith((',"id":%s}' % id).encode()), line
    check_response_shape(json.loads(line))


def test_numeric_ids_of_a_batch_echoed_as_written(client):
    client.send_raw(b'[{"jsonrpc":"2.0","method":"fixture.list","id":9007199254740993},'
                    b'{"id":1.50,"jsonrpc":"2.0","method":"no.such"},'
                    b'{"jsonrpc":"2.0","method":"fixture.list","params":{"id":1},'
                    b'"id":123456789012345678901234567890}]\n')
    line = client.read_line()
    ids = [b'"id":9007199254740993}', b'"id":1.50}', b'"id":123456789012345678901234567890}]']
    at = 0
    for id in ids:
        at = line.find(id, at)
        assert at > 0, (id, line)
    assert len(json.loads(line)) == 3


def test_id_with_nul_refused(client):
    """An id holding U+0000 cannot be echoed faithfully: the line is refused."""
    client.send(req("fixture.list", {}, id="a\u0000b"))
    r = client.read_json()
    assert r["error"]["code"] == -32600 and r["id"] is None, r


def test_crlf_and_whitespace(client):
    client.send_raw(b'{"jsonrpc":"2.0","method":"fixture.list","params":{},"id":1}\r\n')
    line = client.read_line()
    assert not line.endswith(b"\r")
    assert json.loads(line)["id"] == 1
    client.send_raw(b'  {"jsonrpc" : "2.0" ,\t"method":"fixture.list", "id":2}  \n')
    assert client.read_json()["id"] == 2


def test_request_split_across_writes(client):
    line = json.dumps(req("wrench.classify", {"fixture": FX.disc_corner(0.5),
                                               "wrenches": [[-1, -1, 0]]}, id=7)) + "\n"
    data = line.encode()
    for i in range(0, len(data), 9):
        client.send_raw(data[i:i + 9])
        time.sleep(0.002)
    r = client.read_json()
    assert r["id"] == 7 and r["result"]["results"][0]["goal"]["verdict"] == "inside"


def test_several_requests_in_one_write(client):
    lines = "".join(json.dumps(req("fixture.list", {}, id=i)) + "\n" for i in range(5))
    client.send_raw(lines)
    assert [client.read_json()["id"] for _ in range(5)] == list(range(5))


def test_hundred_pipelined_in_order(client):
    """100 requests in one write, heavy (3000 wrenches) and light ones mixed,
    errors among them: the answers come back in request order, each right."""
    f = FX.disc_corner(0.5)
    mdl = M.Model(f)
    cl = M.Classifier(mdl)
    base = H.random_wrenches(seed=100, n=20, scale=(1, 1, 2))
    expect = {g: cl.classify(g, "goal") for g in base}
    fid = client.result("fixture.put", {"fixture": f})["id"]
    requests = []
    for i in range(100):
        kind = i % 5
        if kind == 0:
            n = 3000 if i % 10 == 0 else 1
            ws = [base[(i + j) % 20] for j in range(n)]
            requests.append((req("wrench.classify", {"fixture": fid, "wrenches": ws,
                                                      "sets": ["goal"]}, id=i), ws))
        elif kind == 1:
            requests.append((req("fixture.list", {}, id=i), None))
        elif kind == 2:
            requests.append((req("no.such", {}, id=i), None))
        elif kind == 3:
            ws = [base[i % 20]]
            requests.append((req("wrench.classify", {"fixture": f, "wrenches": ws,
                                                      "sets": ["goal"]}, id=i), ws))
        else:
            requests.append((req("modes.get", {"fixture": fid}, id=i), None))
    client.send_raw("".join(json.dumps(r) + "\n" for r, _ in requests))
    for r, ws in requests:
        a = client.read_json()
        check_response_shape(a)
        assert a["id"] == r["id"], "answer %r out of order (expected id %r)" % (a["id"], r["id"])
        m = r["method"]
        if m == "no.such":
            assert a["error"]["code"] == -32601
        elif m == "fixture.list":
            assert [x["id"] for x in a["result"]["fixtures"]] == [fid]
        elif m == "modes.get":
            assert len(a["result"]["feasible"]) == 9
        else:
            res = a["result"]["results"]
            assert len(res) == len(ws)
            for g, v in zip(ws, res):
                e = expect[g]
                assert abs(v["goal"]["margin"] - e.margin) < 1e-7, (g, v, e)


def test_large_request_and_answer(client):
    """20000 wrenches in one line (well under --max-wrenches 100000)."""
    f = FX.rectangle_321(0.3)
    cl = M.Classifier(M.Model(f))
    base = H.random_wrenches(seed=5, n=40, scale=(1, 1, 3))
    ws = [base[i % 40] for i in range(20000)]
    res = client.result("wrench.classify", {"fixture": f, "wrenches": ws, "sets": ["strong"]})
    assert len(res["results"]) == 20000
    for i in range(0, 20000, 397):
        assert abs(res["results"][i]["strong"]["margin"]
                   - cl.classify(ws[i], "strong").margin) < 1e-7


# ---- limits ----------------------------------------------------------------------------

def test_max_line(harness):
    d = harness.start("--max-line", "4096")
    c, other = d.client(), d.client()
    ok = json.dumps(req("wrench.classify", {"fixture": FX.disc_corner(0.5),
                                            "wrenches": [[-1, -1, 0]] * 150}, id=1))
    assert 2000 < len(ok) < 4000
    c.send_line(ok)
    assert len(c.read_json()["result"]["results"]) == 150
    long = json.dumps(req("wrench.classify", {"fixture": FX.disc_corner(0.5),
                                              "wrenches": [[-1, -1, 0]] * 400}, id=2))
    assert len(long) > 4096 + 1000
    # sent in pieces, the second after a pause
    c.send_raw(long[:3000])
    time.sleep(0.05)
    c.send_raw(long[3000:] + "\n")
    r = c.read_json()
    assert r["id"] is None and r["error"]["code"] == -32600, r
    assert r["error"]["data"]["field"] == "", r
    c.send_line(ok)
    r = c.read_json()
    assert r["id"] == 1 and len(r["result"]["results"]) == 150, r
    assert other.result("fixture.list", {}) == {"fixtures": [], "more": False}


def test_max_depth(harness):
    d = harness.start("--max-depth", "8")
    c = d.client()
    deep = "[" * 12 + "]" * 12
    c.send_line('{"jsonrpc":"2.0","method":"fixture.list","params":{"x":%s},"id":1}' % deep)
    r = c.read_json()
    assert r["error"]["code"] == -32600, r
    assert r["error"]["data"]["field"] == "", r
    res = c.result("wrench.classify", {"fixture": FX.rectangle_321(), "wrenches": [[0, -1, 0]]})
    assert len(res["results"]) == 1


def test_max_wrenches(harness):
    d = harness.start("--max-wrenches", "10")
    c = d.client()
    f = FX.disc_corner(0.5)
    assert len(c.result("wrench.classify", {"fixture": f, "wrenches": [[-1, -1, 0]] * 10})[
        "results"]) == 10
    e = c.error("wrench.classify", {"fixture": f, "wrenches": [[-1, -1, 0]] * 11})
    assert e["code"] == -32003 and e["data"]["field"] == "params.wrenches", e
    assert len(c.result("wrench.classify", {"fixture": f, "wrenches": [[0, 0, 1]]})[
        "results"]) == 1


def test_max_clients(harness):
    d = harness.start("--max-clients", "2")
    time.sleep(0.2)  # let the readiness probe's connection go
    a, b = d.client(), d.client()
    a.result("fixture.list", {})
    b.result("fixture.list", {})
    c = d.client()
    r = c.read_json(timeout=5)
    assert r["error"]["code"] == -32003 and r["id"] is None, r
    assert c.at_eof(5), "the client over --max-clients was not disconnected"
    a.result("fixture.list", {})
    b.close()
    deadline = time.monotonic() + 5
    while True:
        e = d.client()
        try:
            e.send(req("fixture.list", {}, id=1))
            r = e.read_json(timeout=5)
        except (EOFError, OSError):
            r = None
        if r is not None and "result" in r:
            break
        assert time.monotonic() < deadline, "no room for a new client after one left: %r" % r
        e.close()
        time.sleep(0.05)


def test_slow_reader_is_dropped(harness):
    """A client that sends but never reads gets no more work done once its
    unsent output passes --max-output, and is dropped once answers have lain
    unread for --idle-timeout; other clients are served all along."""
    d = harness.start("--max-output", "65536", "--idle-timeout", "2")
    slow, other = d.client(), d.client()
    f = FX.disc_corner(0.5)
    fid = other.result("fixture.put", {"fixture": f})["id"]
    line = json.dumps(req("wrench.classify", {"fixture": fid, "wrenches": [[-1, -0.2, 0]] * 20,
                                              "sets": ["goal"]}, id=1)) + "\n"
    # one answer is a few KB: well under the bound
    total = 600
    stop = threading.Event()

    def sender():
        try:
            for _ in range(total):
                if stop.is_set():
                    return
                slow.sock.sendall(line.encode())
        except OSError:
            pass

    t = threading.Thread(target=sender, daemon=True)
    t.start()
    t.join(10)
    time.sleep(0.5)
    assert other.result("fixture.list", {})["fixtures"][0]["id"] == fid
    # Unread for longer than --idle-timeout: what the kernel holds is all
    # it will get.
    time.sleep(2 + 1.5 * SLOW)
    other = d.client()  # the first one was idle for as long, and is closed too
    assert other.result("fixture.list", {})["fixtures"][0]["id"] == fid
    answers = 0
    dropped = False
    deadline = time.monotonic() + 20
    while time.monotonic() < deadline:
        try:
            slow.read_line(timeout=3)
            answers += 1
        except (EOFError, ConnectionResetError):
            dropped = True
            break
        except socket.timeout:
            break
    stop.set()
    assert dropped and answers < total, (
        "a client with %d unread answers (~%d KB) was not dropped" % (total, total * 5))
    assert other.result("fixture.list", {})["fixtures"][0]["id"] == fid
    assert d.client().result("fixture.list", {})["fixtures"][0]["id"] == fid


def test_half_close_still_answered(daemon):
    """A client that shuts down its sending side after its requests (as
    `nc -N` does) still gets every answer, then EOF."""
    s = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
    s.settimeout(10)
    s.connect(daemon.path)
    s.sendall(b"".join(json.dumps(req("modes.get", {"fixture": FX.disc_corner(0.5)}, id=i))
                       .encode() + b"\n" for i in range(3)))
    s.shutdown(socket.SHUT_WR)
    data = b""
    while True:
        chunk = s.recv(65536)
        if not chunk:
            break
        data += chunk
    s.close()
    lines = data.split(b"\n")
    assert lines[-1] == b"" and [json.loads(x)["id"] for x in lines[:-1]] == [0, 1, 2], data


def test_clients_vanishing_mid_request(daemon):
    """Clients that send big requests and disconnect at once do not hurt the
    daemon (teardown checks exit status 0 and a clean stderr)."""
    f = FX.rectangle_321(0.3)
    line = json.dumps(req("wrench.classify", {"fixture": f, "wrenches": [[0.1, -1, 0.2]] * 3000,
                                              "method": "lp"}, id=1)) + "\n"
    for _ in range(12):
        s = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
        s.connect(daemon.path)
        s.sendall(line.encode() * 2)
        s.close()
    c = daemon.client()
    assert c.result("fixture.list", {}) == {"fixtures": [], "more": False}
    r = c.result("wrench.classify", {"fixture": f, "wrenches": [[0.1, -1, 0.2]]})
    assert len(r["results"]) == 1


def test_light_requests_in_a_long_pipeline(client):
    """Single-wrench classifies of a stored fixture are answered by the
    event loop itself, at most 32 per read, the rest by the workers
    (PERFORMANCE.md): 300 of them in one write, mixed with server.status
    and a request that is not JSON, come back in order, each right, and
    server.status counts every one."""
    f = FX.disc_corner(0.5)
    cl = M.Classifier(M.Model(f))
    fid = client.result("fixture.put", {"fixture": f})["id"]
    before = client.result("server.status", {})["requests"]
    ws = H.random_wrenches(seed=7, n=300, scale=(1, 1, 2))
    lines = []
    for i, w in enumerate(ws):
        if i % 50 == 49:
            lines.append("{not json")
        elif i % 50 == 25:
            lines.append(json.dumps(req("server.status", {}, id=i)))
        else:
            lines.append(json.dumps(req("wrench.classify", {"fixture": fid, "wrenches": [w],
                                                            "sets": ["goal"]}, id=i)))
    client.send_raw("".join(line + "\n" for line in lines))
    for i, w in enumerate(ws):
        a = client.read_json()
        if i % 50 == 49:
            assert a["id"] is None and a["error"]["code"] == -32700, a
            continue
        assert a["id"] == i, (i, a)
        if i % 50 == 25:
            assert a["result"]["requests"] >= before + i, a
            continue
        want = cl.classify(w, "goal").verdict(1e-7)
        got = a["result"]["results"][0]["goal"]
        if want != "boundary":
            assert got["verdict"] == want, (i, w, got, want)
    after = client.result("server.status", {})["requests"]
    assert after == before + 301, (before, after)


def test_default_max_wrenches(client):
    """--max-wrenches defaults to 100000."""
    f = FX.disc_corner(0.5)
    e = client.error("wrench.classify", {"fixture": f, "wrenches": [[0, 0, 1]] * 100001})
    assert e["code"] == -32003 and e["data"]["field"] == "params.wrenches", e


def test_pipelined_requests_run_in_order(harness):
    """PROTOCOL: pipelined requests run one after another, so a put followed
    at once by a query of its id works, and a delete is seen by the next
    request."""
    f = FX.rectangle_321(0.3)
    probe = harness.start(socket_path=harness.path("p.sock")).client()
    fid = probe.result("fixture.put", {"fixture": f})["id"]
    d = harness.start()
    c = d.client()
    seq = [
        req("fixture.put", {"fixture": f}, id=1),
        req("wrench.classify", {"fixture": fid, "wrenches": [[0, -1, 0]]}, id=2),
        req("fixture.get", {"id": fid}, id=3),
        req("fixture.delete", {"id": fid}, id=4),
        req("fixture.get", {"id": fid}, id=5),
        req("wrench.classify", {"fixture": fid, "wrenches": [[0, -1, 0]]}, id=6),
        req("fixture.put", {"fixture": f}, id=7),
        req("fixture.list", {}, id=8),
    ]
    for _ in range(5):
        c.send_raw("".join(json.dumps(r) + "\n" for r in seq))
        got = [c.read_json() for _ in seq]
        assert [g["id"] for g in got] == list(range(1, 9))
        assert got[0]["result"]["id"] == fid
        assert len(got[1]["result"]["results"]) == 1, got[1]
        assert got[2]["result"]["name"] == f["name"], got[2]
        assert got[3]["result"] == {"deleted": True}, got[3]
        assert got[4]["error"]["code"] == -32001, got[4]
        assert got[5]["error"]["code"] == -32001, got[5]
        assert got[6]["result"]["id"] == fid
        assert [x["id"] for x in got[7]["result"]["fixtures"]] == [fid]
