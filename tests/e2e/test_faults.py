"""Faults: a crash in the middle of puts, a full or read-only state
directory, a GLPK failure, a batch over the limits.  Nothing acknowledged is
lost, and a fault is an error answer, never a crash."""

import json
import os
import signal
import socket
import threading
import time

import pytest

import fixtures as FX
from conftest import BINARY, REPO, SANITIZED, SLOW, Daemon

SHIM = os.path.join(REPO, "build", "tests", "libfail_storage.so")


def start_with_env(harness, env, *args, state_dir=None):
    d = Daemon(harness.dir, args, state_dir, None, env=env, tag="f%d" % len(harness.daemons))
    harness.daemons.append(d)
    return d.start()


def failing_storage_env(directory, errno_name):
    env = dict(os.environ, LD_PRELOAD=SHIM, FAIL_STORAGE_DIR=directory,
               FAIL_STORAGE_ERRNO=errno_name)
    # An ASan daemon wants its runtime first; the shim only wraps libc calls.
    env["ASAN_OPTIONS"] = env.get("ASAN_OPTIONS", "") + ":verify_asan_link_order=0"
    return env


def test_sigkill_in_the_middle_of_1000_puts(harness):
    """Put 1000 fixtures; SIGKILL the daemon part way; restart on the same
    state directory: every put that was acknowledged is there."""
    state = harness.path("state")
    d = harness.start(state_dir=state)
    c = d.client()
    acknowledged = []
    stop = threading.Event()

    def put_all():
        try:
            for i in range(1000):
                if stop.is_set():
                    return
                r = c.call("fixture.put", {"fixture": FX.disc_corner(0.001 * (i + 1),
                                                                       name="f%d" % i)})
                if "result" in r:
                    acknowledged.append(r["result"]["id"])
        except (OSError, EOFError, AssertionError, ValueError):
            pass  # the daemon died under us: that is the point

    thread = threading.Thread(target=put_all)
    thread.start()
    while len(acknowledged) < 300 and thread.is_alive():
        time.sleep(0.005)
    os.kill(d.pid, signal.SIGKILL)
    d.proc.wait()
    d.expected_status = -signal.SIGKILL
    stop.set()
    thread.join()
    assert 300 <= len(acknowledged) < 1000, len(acknowledged)
    again = harness.start(state_dir=state, socket_path=harness.path("again.sock"))
    c2 = again.client()
    stored = {f["id"] for f in c2.result("fixture.list")["fixtures"]}
    missing = [i for i in acknowledged if i not in stored]
    assert not missing, "%d acknowledged puts lost" % len(missing)
    # Whatever is on disk reads back whole: no torn files.
    for fid in list(stored)[:50]:
        assert c2.result("fixture.get", {"id": fid})["body"]["mass"] == 1


@pytest.mark.parametrize("errno_name,words", [("ENOSPC", "No space left on device"),
                                              ("EROFS", "Read-only file system")])
def test_full_or_read_only_state_directory(harness, errno_name, words):
    """The state directory refuses writes: a put fails with -32002 naming
    the cause and stores nothing; a delete fails and keeps the fixture;
    everything stored before is still served, and so are queries."""
    state = harness.path("state")
    first = harness.start(state_dir=state)
    stored_id = first.client().result("fixture.put", {"fixture": FX.disc_corner(0.5)})["id"]
    first.stop()
    d = start_with_env(harness, failing_storage_env(os.path.join(state, "fixtures"), errno_name),
                       state_dir=state)
    c = d.client()
    e = c.error("fixture.put", {"fixture": FX.rectangle_321(0.3)})
    assert e["code"] == -32002 and words in e["data"]["reason"], e
    e = c.error("fixture.delete", {"id": stored_id})
    assert e["code"] == -32002 and words in e["data"]["reason"], e
    assert [f["id"] for f in c.result("fixture.list")["fixtures"]] == [stored_id]
    answer = c.result("wrench.classify", {"fixture": stored_id, "wrenches": [[-1, -1, 0]]})
    assert answer["results"][0]["goal"]["verdict"] == "inside"
    inline = c.result("wrench.classify", {"fixture": FX.rectangle_321(0.3),
                                          "wrenches": [[0, -1, 0]]})
    assert inline["results"][0]["strong"]["verdict"] == "inside"
    assert not [n for n in os.listdir(os.path.join(state, "fixtures")) if n.endswith(".tmp")]


def test_glpk_failure_is_an_error_answer(harness):
    """GLPK failing fatally (the test hook WRENCHD_TEST_GLPK_FAILURE) gives
    that request -32004; the daemon does not abort, and the next request,
    on a rebuilt GLPK environment, is answered."""
    env = dict(os.environ, WRENCHD_TEST_GLPK_FAILURE="0")
    d = start_with_env(harness, env, "--threads", "1")
    c = d.client()
    params = {"fixture": FX.disc_corner(0.5), "wrenches": [[-1, -1, 0], [0, 1, 0]],
              "method": "lp"}
    e = c.error("wrench.classify", params)
    assert e["code"] == -32004 and "GLPK" in e["data"]["reason"], e
    again = c.result("wrench.classify", params)
    assert [r["goal"]["verdict"] for r in again["results"]] == ["inside", "outside"]
    assert d.running


def test_glpk_failure_first_in_a_batch(harness):
    """A batch whose first member fails in its first piece (GLPK, by the
    test hook) is still one JSON array: the error answer opens it, the
    next member follows after a comma.  The batch's "[" was once taken
    back with the failed member's text and not written again."""
    env = dict(os.environ, WRENCHD_TEST_GLPK_FAILURE="0")
    d = start_with_env(harness, env, "--threads", "1")
    c = d.client()
    params = {"fixture": FX.disc_corner(0.5), "wrenches": [[-1, -1, 0], [0, 1, 0]],
              "method": "lp"}
    c.send([{"jsonrpc": "2.0", "method": "wrench.classify", "params": params, "id": 1},
            {"jsonrpc": "2.0", "method": "server.status", "params": {}, "id": 2}])
    answers = c.read_json()
    assert isinstance(answers, list) and [a["id"] for a in answers] == [1, 2], answers
    assert answers[0]["error"]["code"] == -32004, answers[0]
    assert "result" in answers[1]
    assert d.running


def test_a_batch_over_the_limit(harness):
    """A batch larger than --max-batch gets one clear error, not work and
    memory in proportion to it; the limit itself is served."""
    d = harness.start("--max-batch", "10")
    c = d.client()
    request = {"jsonrpc": "2.0", "method": "server.status", "params": {}}
    c.send([dict(request, id=i) for i in range(11)])
    e = c.read_json()
    assert isinstance(e, dict) and e["error"]["code"] == -32600, e
    assert "--max-batch" in e["error"]["data"]["reason"]
    c.send([dict(request, id=i) for i in range(10)])
    assert [a["id"] for a in c.read_json()] == list(range(10))
    # The default limit refuses a million tiny requests in one line cheaply.
    d2 = harness.start("--max-line", str(8 << 20), socket_path=harness.path("two.sock"))
    c2 = d2.client()
    c2.send_line("[" + ",".join(["{}"] * 1000000) + "]")
    e = c2.read_json()
    assert e["error"]["code"] == -32600 and "1000000" in e["error"]["data"]["reason"], e
    assert "result" in c2.call("server.status")
