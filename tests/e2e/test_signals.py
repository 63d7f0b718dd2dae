"""Process life: SIGTERM / SIGINT with requests in flight, the socket file,
refusing a live socket, replacing a stale one, exit statuses."""

import json
import os
import signal
import socket
import stat
import subprocess
import time

import pytest

import fixtures as FX
import helpers as H
import model as M
from conftest import SLOW, STOP_TIMEOUT, WRAPPER


def heavy_request(id, fixture, wrenches, method="auto"):
    return json.dumps({"jsonrpc": "2.0", "method": "wrench.classify", "id": id,
                       "params": {"fixture": fixture, "wrenches": wrenches,
                                  "sets": ["goal", "strong", "both"], "method": method}})


@pytest.mark.parametrize("sig", [signal.SIGTERM, signal.SIGINT])
def test_stop_answers_requests_in_flight(harness, sig):
    """Eight clients each send a large classify request; the signal comes
    while they are being worked on.  Every one is answered in full, the
    daemon exits 0 and the socket file is gone."""
    d = harness.start("--threads", "2")
    f = FX.rectangle_321(0.3)
    cl = M.Classifier(M.Model(f))
    base = H.random_wrenches(seed=3, n=50, scale=(1, 1, 2))
    clients = [d.client() for _ in range(8)]
    fid = clients[0].result("fixture.put", {"fixture": f})["id"]
    sizes = []
    for i, c in enumerate(clients):
        # answers stay well under --max-output (16 MiB): about 290 bytes a
        # wrench and set with "auto", less with "lp"
        # (under a wrapper such as valgrind, which runs one thread at a
        # time, a tenth: the point there is memory, not timing)
        n = (5000 if i % 2 == 0 else 4000) // (10 if WRAPPER else 1)
        method = "auto" if i % 2 == 0 else "lp"
        ws = [base[(i + j) % 50] for j in range(n)]
        sizes.append((n, ws, method))
        c.send_line(heavy_request(i, fid if i % 3 else f, ws, method))
    # long enough for the daemon to have read every request (they are
    # received, hence in flight), short of their answers
    time.sleep(0.3 * SLOW)
    started = time.monotonic()
    d.send_signal(sig)
    for i, c in enumerate(clients):
        r = c.read_json(timeout=60)
        assert r["id"] == i and "result" in r, r
        n, ws, method = sizes[i]
        res = r["result"]["results"]
        assert len(res) == n
        for j in range(0, n, 53):
            e = cl.classify(ws[j], "strong")
            if method == "auto":
                assert abs(res[j]["strong"]["margin"] - e.margin) < 1e-7
            elif abs(e.margin) > 1e-6:
                assert res[j]["strong"]["verdict"] == e.verdict(0)
    status = d.wait()
    assert status == 0, "exit status %s after %s; stderr:\n%s" % (status, sig.name, d.stderr())
    d.checked = True
    d.stderr_file.close()
    d.assert_clean_stderr()
    assert not os.path.exists(d.path), "the socket file is still there"
    with pytest.raises(OSError):
        s = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
        try:
            s.connect(d.path)
        finally:
            s.close()
    assert time.monotonic() - started < STOP_TIMEOUT


def test_stop_with_idle_clients(harness):
    """Idle connected clients do not keep the daemon alive: it exits 0
    promptly and they see the connection close."""
    d = harness.start()
    clients = [d.client() for _ in range(5)]
    clients[0].result("fixture.list", {})
    d.send_signal(signal.SIGTERM)
    assert d.wait(timeout=10) == 0
    for c in clients:
        assert c.at_eof(5)
    d.checked = True
    d.stderr_file.close()
    d.assert_clean_stderr()
    assert not os.path.exists(d.path)


def test_refuses_a_live_socket(harness):
    d = harness.start()
    c = d.client()
    fid = c.result("fixture.put", {"fixture": FX.disc_corner(0.5)})["id"]
    p = harness.run("--socket", d.path, timeout=STOP_TIMEOUT)
    assert p.returncode == 1, (p.returncode, p.stderr[-2000:])
    # the first daemon is untouched and still answers on its socket
    assert os.path.exists(d.path)
    assert d.client().result("fixture.get", {"id": fid})["name"] == "disc-corner"
    assert c.result("fixture.list", {})["fixtures"][0]["id"] == fid


def test_replaces_a_stale_socket(harness):
    path = harness.path("stale.sock")
    s = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
    s.bind(path)
    s.close()  # the file stays, nobody listens
    assert stat.S_ISSOCK(os.stat(path).st_mode)
    d = harness.start(socket_path=path)
    assert d.client().result("fixture.list", {}) == {"fixtures": [], "more": False}


def test_socket_file_mode_and_parent(harness):
    path = harness.path("a/b/w.sock")
    d = harness.start(socket_path=path)
    st = os.stat(path)
    assert stat.S_ISSOCK(st.st_mode)
    assert stat.S_IMODE(st.st_mode) == 0o660, oct(st.st_mode)
    d.client().result("server.status", {})


def test_default_socket_path(harness):
    """Without --socket: ./run/wrenchd.sock, its directory created."""
    d = harness.start(socket_path="")
    assert d.path == harness.path("run/wrenchd.sock") and os.path.exists(d.path)
    assert d.client().result("fixture.list", {}) == {"fixtures": [], "more": False}


@pytest.mark.parametrize("args", [
    ["--bogus"],
    ["--threads", "many"],
    ["--threads"],
    ["--threads", "-2"],
    ["--log-level", "loud"],
    ["--max-line", "abc"],
    ["--cache-mb", "1x"],
    ["stray-argument"],
], ids=lambda a: " ".join(a))
def test_bad_command_line_exits_2(harness, args):
    try:
        p = harness.run("--socket", harness.path("x.sock"), *args, timeout=10)
    except subprocess.TimeoutExpired:
        pytest.fail("wrenchd %s started instead of exiting 2" % " ".join(args))
    assert p.returncode == 2, (args, p.returncode, p.stderr[-2000:])
    assert p.stderr.strip(), "no word on stderr about the bad command line"


def test_help_and_version(harness):
    p = harness.run("--help")
    assert p.returncode == 0, p
    assert b"--socket" in p.stdout + p.stderr and b"--state-dir" in p.stdout + p.stderr
    v = harness.run("--version")
    assert v.returncode == 0, v
    text = (v.stdout + v.stderr).decode().strip()
    assert text
    d = harness.start()
    version = d.client().result("server.status", {})["version"]
    assert version in text, (version, text)


def test_cannot_start_exits_1(harness):
    """A state directory that is a regular file, a socket whose parent
    cannot be created: exit 1."""
    plain = harness.path("plain")
    with open(plain, "w") as f:
        f.write("not a directory\n")
    p = harness.run("--socket", harness.path("y.sock"), "--state-dir", plain, timeout=10)
    assert p.returncode == 1, (p.returncode, p.stderr[-2000:])
    p = harness.run("--socket", os.path.join(plain, "sub", "z.sock"), timeout=10)
    assert p.returncode == 1, (p.returncode, p.stderr[-2000:])


def test_stop_with_a_partial_line_pending(harness):
    """A client in the middle of a line does not hold up the stop."""
    d = harness.start()
    c = d.client()
    c.send_raw('{"jsonrpc":"2.0","method":"fixture.list",')
    time.sleep(0.1)
    d.send_signal(signal.SIGTERM)
    assert d.wait(timeout=10) == 0
    d.checked = True
    d.stderr_file.close()
    d.assert_clean_stderr()
    assert not os.path.exists(d.path)
