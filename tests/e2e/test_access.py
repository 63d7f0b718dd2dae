"""Peer access control with many groups: a peer's supplementary
groups are read in full, however many, and never written past a buffer.

These tests run as root: they make a user and 300 groups of their own
(removed afterwards, also on failure) and connect as that user with chosen
supplementary groups (setpriv), to a daemon started with --allow-gid."""

import json
import os
import secrets
import shutil
import subprocess
import sys

import pytest

import conftest
from conftest import REPO, SLOW

pytestmark = [
    pytest.mark.skipif(os.geteuid() != 0,
                       reason="needs root: makes a user and groups, connects as that user"),
    pytest.mark.skipif(not all(shutil.which(tool) for tool in
                               ("useradd", "userdel", "groupadd", "groupdel", "usermod",
                                "setpriv")),
                       reason="needs useradd, userdel, groupadd, groupdel, usermod, setpriv"),
]

GROUP_COUNT = 300
# The ASan daemon: the write past the old stack array is only seen there.
ASAN_BINARY = os.path.join(REPO, "build", "asan", "wrenchd")


class People:
    """A user and GROUP_COUNT groups made for this module."""

    def __init__(self):
        self.tag = "wdt" + secrets.token_hex(3)   # short: names are at most 32 characters
        self.user = self.tag + "u"
        self.groups = []      # (name, gid), in the order made
        self.user_made = False

    def make(self):
        for i in range(1, GROUP_COUNT + 1):
            name = "%sg%d" % (self.tag, i)
            run(["groupadd", name])
            self.groups.append((name, gid_of(name)))
        run(["useradd", "--system", "--no-create-home", "--shell", "/usr/sbin/nologin",
             "--user-group", self.user])
        self.user_made = True
        run(["usermod", "--append", "--groups", ",".join(name for name, _ in self.groups),
             self.user])

    def remove(self):
        failures = []
        if self.user_made:
            failures += remove(["userdel", self.user])
        for name, _ in self.groups:
            failures += remove(["groupdel", name])
        return failures


def run(command):
    r = subprocess.run(command, capture_output=True, text=True, timeout=60)
    assert r.returncode == 0, "%s: %s" % (" ".join(command[:2]), r.stderr)


def remove(command):
    r = subprocess.run(command, capture_output=True, text=True, timeout=60)
    return [] if r.returncode == 0 else ["%s: %s" % (" ".join(command), r.stderr.strip())]


def gid_of(group):
    r = subprocess.run(["getent", "group", group], capture_output=True, text=True)
    return int(r.stdout.split(":")[2])


@pytest.fixture(scope="module")
def people():
    made = People()
    try:
        made.make()
        yield made
    finally:
        failures = made.remove()
        assert not failures, "could not remove the test's user and groups:\n" + "\n".join(failures)


def open_to_everyone(harness, daemon):
    """The directory's and the socket's modes are not what is tested here."""
    os.chmod(harness.dir, 0o755)
    os.chmod(daemon.path, 0o666)


def status_as(people, daemon, privileges):
    """server.status asked by a client that setpriv made `people.user` with
    `privileges` (setpriv's group options); the parsed answer."""
    script = ("import socket, sys\n"
              "s = socket.socket(socket.AF_UNIX); s.connect(sys.argv[1])\n"
              "s.sendall(b'{\"jsonrpc\":\"2.0\",\"method\":\"server.status\",\"id\":1}\\n')\n"
              "print(s.makefile('rb').readline().decode())\n")
    command = (["setpriv", "--reuid", people.user] + privileges +
               [sys.executable, "-c", script, daemon.path])
    r = subprocess.run(command, capture_output=True, text=True, timeout=30 * SLOW, cwd="/")
    assert r.returncode == 0, r.stderr
    return json.loads(r.stdout)


def refused_as_root(daemon):
    """Root (uid 0, gid 0, no listed group) gets the one -32005 line."""
    c = daemon.client()
    c.send(c.request("server.status"))
    return c.read_json()["error"]["code"] == -32005


def gid_list(groups):
    return ",".join(str(gid) for _, gid in groups)


def test_a_user_in_300_groups_is_admitted_through_the_300th(harness, people):
    """The user is in its own group and 300 more (initgroups, as a login
    would); only the 300th made is allowed, by name.  The old code read at
    most 255 groups and, told ERANGE, none: it turned the user away."""
    name, _ = people.groups[-1]
    d = harness.start("--allow-gid", name)
    open_to_everyone(harness, d)
    answer = status_as(people, d, ["--regid", people.user, "--init-groups"])
    assert "result" in answer, answer
    assert refused_as_root(d)


def test_a_user_in_none_of_the_allowed_groups_is_denied(harness, people):
    """In 299 groups, but not the allowed 300th: one -32005 naming the uid."""
    _, allowed_gid = people.groups[-1]
    d = harness.start("--allow-gid", str(allowed_gid))
    open_to_everyone(harness, d)
    answer = status_as(people, d, ["--regid", people.user,
                                   "--groups", gid_list(people.groups[:-1])])
    assert answer["error"]["code"] == -32005, answer
    uid = int(subprocess.run(["id", "-u", people.user], capture_output=True,
                             text=True).stdout)
    assert ("uid %d" % uid) in answer["error"]["data"]["reason"]
    assert refused_as_root(d)


def test_exactly_256_groups_under_asan(harness, people, monkeypatch):
    """Exactly 256 supplementary groups, against the ASan daemon: the old
    code had the kernel write 256 groups one entry into a 256-entry stack
    array (a stack-buffer-overflow report) and never looked at the last.
    Admitted through the group the kernel lists last (the highest gid)."""
    # Under make e2e-asan, WRENCHD is it; otherwise (plain, or valgrind's
    # run, whose wrapper is dropped here) the one make e2e builds.
    binary = conftest.BINARY if "asan" in conftest.BINARY else ASAN_BINARY
    assert os.access(binary, os.X_OK), "no %s: run make %s" % (binary, "build/asan/wrenchd")
    monkeypatch.setattr(conftest, "BINARY", binary)
    monkeypatch.setattr(conftest, "WRAPPER", [])   # never the ASan daemon under valgrind
    groups = people.groups[:256]
    last = max(gid for _, gid in groups)          # the kernel sorts the list
    d = harness.start("--allow-gid", str(last))
    open_to_everyone(harness, d)
    answer = status_as(people, d, ["--regid", people.user, "--groups", gid_list(groups)])
    assert "result" in answer, answer
    assert d.running(), d.stderr()
    d.stop()   # exit status 0 and no sanitizer report on stderr
