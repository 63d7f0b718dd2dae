"""Hostile clients: each one misbehaves while an ordinary client keeps being
served within its normal latency, and the daemon's memory stays bounded."""

import json
import os
import socket
import statistics
import threading
import time

import pytest

from conftest import SANITIZED, SLOW

DISC = {"name": "disc", "body": {"mass": 1, "inertia": 0.5, "com": [0, 0],
                                 "shape": {"type": "circle", "center": [0, 0], "radius": 1}},
        "friction": {"static": 0.5}, "fixels": [{"at": [-1, 0], "normal": [1, 0]},
                                                {"at": [0, -1], "normal": [0, 1]}]}


def classify_line(i):
    return (json.dumps({"jsonrpc": "2.0", "method": "wrench.classify",
                        "params": {"fixture": DISC, "wrenches": [[-1, -1, 0.01 * i]]},
                        "id": i}) + "\n").encode()


def latencies(path, count=30):
    """Round-trip times of ordinary requests on a fresh connection."""
    times = []
    with socket.socket(socket.AF_UNIX, socket.SOCK_STREAM) as s:
        s.settimeout(30 * SLOW)
        s.connect(path)
        f = s.makefile("rb")
        for i in range(count):
            start = time.monotonic()
            s.sendall(classify_line(i))
            answer = json.loads(f.readline())
            times.append(time.monotonic() - start)
            assert answer["id"] == i and "result" in answer, answer
    return times


def resident_kib(pid):
    with open("/proc/%d/status" % pid) as f:
        for line in f:
            if line.startswith("VmRSS:"):
                return int(line.split()[1])
    return 0


def served_normally(path, baseline):
    """The ordinary client's median latency stays near its baseline."""
    during = latencies(path)
    limit = 5 * statistics.median(baseline) + 0.05 * SLOW
    assert statistics.median(during) < limit, (statistics.median(during), limit)


# Under valgrind everything is ~20 times slower, the event loop included:
# the idle timeout grows with the rest.
IDLE = str(max(1, int(SLOW)))


def test_half_a_line_then_silence(harness):
    """A client sends half a request and waits: others are served as usual,
    and --idle-timeout closes the silent connection."""
    d = harness.start("--idle-timeout", IDLE)
    baseline = latencies(d.path)
    hostile = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
    hostile.connect(d.path)
    hostile.sendall(b'{"jsonrpc":"2.0","method":"server.st')
    served_normally(d.path, baseline)
    hostile.settimeout(10 * SLOW)
    start = time.monotonic()
    assert hostile.recv(100) == b""  # closed by the daemon
    assert time.monotonic() - start < 5 * SLOW + int(IDLE)
    hostile.close()


def test_idle_timeout_spares_a_client_waiting_for_its_answer(harness):
    """The timeout is for silence with nothing in flight: a connection
    waiting on a long request is not cut."""
    # (Two seconds at least: answers left unread for the idle timeout close
    # the connection too, and a loaded machine may stall this reader.)
    d = harness.start("--idle-timeout", str(max(2, int(SLOW))), "--threads", "1")
    c = d.client()
    # Many wrenches with the LP method: longer than the timeout under ASan or
    # valgrind, and at least a while otherwise; the answer must arrive.  Its
    # verdicts alone, so that reading it takes this reader little of the
    # timeout (the connection is idle again once the answer is sent).
    wrenches = [[-1, -1, 0.001 * i] for i in range(20000)]
    r = c.result("wrench.classify", {"fixture": DISC, "wrenches": wrenches, "method": "lp",
                                     "fields": ["verdict"]})
    assert r["count"] == 20000 and sum(p["count"] for p in r["pieces"]) == 20000
    time.sleep(0.2)
    assert c.result("server.status")["clients"] >= 1


def test_a_client_that_never_reads_is_dropped(harness):
    """It asks and asks and never reads: once its unsent answers pass
    --max-output its work pauses, and once they have lain unread for
    --idle-timeout it is dropped; everyone else is served as usual, and the
    daemon's memory does not grow with it."""
    d = harness.start("--max-output", "65536", "--idle-timeout", "3")
    baseline = latencies(d.path)
    rss_before = resident_kib(d.pid)
    hostile = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
    hostile.connect(d.path)
    hostile.settimeout(0.5)
    stop = threading.Event()

    def flood():
        i = 0
        while not stop.is_set():
            try:
                hostile.sendall(classify_line(i))
            except socket.timeout:
                continue  # the daemon stopped reading for now: it is backed up
            except OSError:
                return  # dropped
            i += 1

    thread = threading.Thread(target=flood)
    thread.start()
    try:
        served_normally(d.path, baseline)
        deadline = time.monotonic() + 30 * SLOW
        while "unread for --idle-timeout" not in d.stderr() and time.monotonic() < deadline:
            time.sleep(0.05)
        assert "unread for --idle-timeout" in d.stderr(), d.stderr()
    finally:
        stop.set()
        thread.join()
        hostile.close()
    growth = resident_kib(d.pid) - rss_before
    if not SANITIZED:  # the plain build measures memory; sanitized ones, errors
        assert growth < 64 * 1024, growth  # KiB


def test_connections_up_to_the_limit(harness):
    """Eight clients fill --max-clients 8: the ninth gets -32003 and is
    closed; the eight are served; when one leaves, a newcomer gets in."""
    d = harness.start("--max-clients", "8")
    time.sleep(0.2)  # the harness's readiness probe has gone
    held = [d.client() for _ in range(8)]
    for c in held:
        assert "result" in c.call("server.status")
    with socket.socket(socket.AF_UNIX, socket.SOCK_STREAM) as extra:
        extra.settimeout(10 * SLOW)
        extra.connect(d.path)
        f = extra.makefile("rb")
        refused = json.loads(f.readline())
        assert refused["error"]["code"] == -32003, refused
        assert f.readline() == b""
    for c in held:
        assert "result" in c.call("server.status")
    held.pop().close()
    deadline = time.monotonic() + 10 * SLOW
    while True:
        with socket.socket(socket.AF_UNIX, socket.SOCK_STREAM) as newcomer:
            newcomer.settimeout(10 * SLOW)
            newcomer.connect(d.path)
            newcomer.sendall(b'{"jsonrpc":"2.0","method":"server.status","id":1}\n')
            answer = json.loads(newcomer.makefile("rb").readline())
        if "result" in answer or time.monotonic() > deadline:
            break
        time.sleep(0.05)  # the closed one is still being counted
    assert "result" in answer, answer
    assert answer["result"]["refused"] >= 1


def test_a_100_mib_line(harness):
    """A 100 MiB line is answered -32600, skipped without being held in
    memory, and the same connection then answers normally; another client is
    served meanwhile."""
    d = harness.start()
    baseline = latencies(d.path)
    rss_before = resident_kib(d.pid)
    chunk = b"x" * (1 << 20)
    with socket.socket(socket.AF_UNIX, socket.SOCK_STREAM) as s:
        s.settimeout(60 * SLOW)
        s.connect(d.path)
        f = s.makefile("rb")
        peak = 0
        for i in range(100):
            s.sendall(chunk)
            if i % 10 == 0:
                peak = max(peak, resident_kib(d.pid))
                if i == 50:
                    served_normally(d.path, baseline)
        s.sendall(b"\n" + classify_line(7))
        first = json.loads(f.readline())
        assert first["error"]["code"] == -32600 and "longer than" in first["error"]["data"]["reason"]
        second = json.loads(f.readline())
        assert second["id"] == 7 and "result" in second
    if not SANITIZED:
        assert peak - rss_before < 32 * 1024, (peak, rss_before)  # KiB
