"""Hostile clients and hostile configurations, second round: descriptors,
parse trees, hang-ups while reading is paused, empty allow lists, memory
running out while a line is parsed, fairness between users, the state
directory's lock and the socket file a daemon made.

Every test starts its own daemons and talks to them over Unix sockets only.
Thresholds are properties of the daemon (lines logged, CPU it spends, bytes
it holds) with wide margins, not of how loaded the machine is."""

import json
import os
import resource
import shutil
import socket
import subprocess
import sys
import threading
import time

import pytest

from conftest import SANITIZED, SLOW

DISC = {"name": "disc", "body": {"mass": 1, "inertia": 0.5, "com": [0, 0],
                                 "shape": {"type": "circle", "center": [0, 0], "radius": 1}},
        "friction": {"static": 0.5}, "fixels": [{"at": [-1, 0], "normal": [1, 0]},
                                                {"at": [0, -1], "normal": [0, 1]}]}

ROOT = os.geteuid() == 0
needs_root = pytest.mark.skipif(not ROOT, reason="needs root: connects as another user")


def status_line(i=1):
    return b'{"jsonrpc":"2.0","method":"server.status","id":%d}\n' % i


def ask_status(path, timeout):
    """Connect, ask server.status, return the answer (raises on failure)."""
    with socket.socket(socket.AF_UNIX, socket.SOCK_STREAM) as s:
        s.settimeout(timeout)
        s.connect(path)
        s.sendall(status_line())
        return json.loads(s.makefile("rb").readline())


def cpu_seconds(pid):
    """User and system CPU the process has used, from /proc."""
    with open("/proc/%d/stat" % pid) as f:
        fields = f.read().rsplit(")", 1)[1].split()
    return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")


def open_to_everyone(harness, daemon):
    """The directory's and the socket's modes are not what is tested here."""
    os.chmod(harness.dir, 0o755)
    os.chmod(daemon.path, 0o666)


# ---- allow lists ---------------------------------------------------------------------

@pytest.mark.parametrize("option,value", [
    ("--allow-uid", ""), ("--allow-uid", ","), ("--allow-uid", " , "),
    ("--allow-gid", ""), ("--allow-gid", ",,"),
])
def test_an_empty_allow_list_on_the_command_line_exits_2(harness, option, value):
    """An empty list is not "anyone": exit 2, naming the option."""
    r = harness.run(option, value, "--socket", harness.path("x.sock"))
    assert r.returncode == 2, r.stderr
    assert (option + " is an empty list") in r.stderr.decode(), r.stderr
    assert not os.path.exists(harness.path("x.sock"))


@pytest.mark.parametrize("line", ["allow-uid =\n", "allow-uid = ,\n", "allow-gid =   \n"])
def test_an_empty_allow_list_in_the_file_exits_2(harness, line):
    config = harness.path("empty.conf")
    with open(config, "w") as f:
        f.write("allow-uid = 0\n" + line)
    r = harness.run("--config", config, "--socket", harness.path("x.sock"))
    assert r.returncode == 2, r.stderr
    assert (":2: %s is an empty list" % line.split()[0]) in r.stderr.decode(), r.stderr


def test_any_among_names_exits_2(harness):
    r = harness.run("--allow-uid", "0,any", "--socket", harness.path("x.sock"))
    assert r.returncode == 2 and b"--allow-uid takes 'any' alone" in r.stderr, r.stderr


def test_the_effective_lists_are_logged_and_any_is_said_explicitly(harness):
    """The file admits uid 4242 only; "--allow-uid any" on the command line
    replaces that list with anyone, and the log says what is admitted."""
    config = harness.path("allow.conf")
    with open(config, "w") as f:
        f.write("allow-uid = 4242, 4343\nallow-gid = 77\n")
    d = harness.start("--config", config, "--log-level", "info",
                      socket_path=harness.path("a.sock"))
    assert "admitted: uids 4242, 4343; gids 77" in d.stderr()
    assert "error" in ask_status(d.path, 10 * SLOW) or os.getuid() in (4242, 4343)
    d2 = harness.start("--config", config, "--log-level", "info", "--allow-uid", "any",
                       socket_path=harness.path("b.sock"))
    assert "admitted: anyone who can open the socket ('any' given)" in d2.stderr()
    assert "result" in ask_status(d2.path, 10 * SLOW)
    d3 = harness.start("--log-level", "info", socket_path=harness.path("c.sock"))
    assert "admitted: anyone who can open the socket\n" in d3.stderr()


# ---- the state directory's lock and the socket file --------------------------------------

def test_deleting_the_lock_file_does_not_free_the_state_directory(harness):
    """The lock is on the directory itself: with DIR/lock deleted, a second
    daemon on the same directory still exits 1 naming it."""
    state = harness.path("state")
    first = harness.start(state_dir=state, socket_path=harness.path("one.sock"))
    os.unlink(os.path.join(state, "lock"))
    second = subprocess.run(
        [first.command()[0]] + first.command()[1:first.command().index("--socket")] +
        ["--socket", harness.path("two.sock"), "--state-dir", state],
        cwd=harness.dir, stdin=subprocess.DEVNULL, capture_output=True, timeout=20 * SLOW)
    assert second.returncode == 1, second.stderr
    assert ("the state directory %s is in use by another wrenchd" % state).encode() in second.stderr
    assert "result" in ask_status(first.path, 10 * SLOW)


def test_a_replaced_socket_file_is_left_to_its_maker(harness):
    """Daemon A's socket file is removed and daemon B binds the same path;
    when A stops it must not unlink B's socket."""
    path = harness.path("s.sock")
    a = harness.start(socket_path=path)
    os.unlink(path)
    b = harness.start(socket_path=path)
    a.stop()
    assert os.path.exists(path), "the first daemon removed the second one's socket"
    assert "result" in ask_status(path, 10 * SLOW)
    b.stop()
    assert not os.path.exists(path), "a daemon leaves its own socket file behind"
