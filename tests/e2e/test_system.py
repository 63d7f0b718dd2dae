"""wrenchd as a system service: the systemd units, socket activation,
sd_notify, the configuration file, peer access control, make install."""

import json
import os
import re
import shutil
import signal
import socket
import subprocess
import sys
import tempfile
import time

import pytest

from conftest import BINARY, NO_CONFIG, REPO, WRAPPER, SLOW

WRENCHCTL = os.path.join(REPO, "build", "wrenchctl")
DISC = os.path.join(REPO, "examples", "disc-corner.json")
DISC_ID = "e0d7a1a0bd6e8bf16fe5845da1960ed9"


def request(sock_path, method, params=None, timeout=20):
    """One request on a new connection; the parsed answer."""
    with socket.socket(socket.AF_UNIX, socket.SOCK_STREAM) as s:
        s.settimeout(timeout * SLOW)
        s.connect(sock_path)
        s.sendall((json.dumps({"jsonrpc": "2.0", "method": method, "params": params or {},
                               "id": 1}) + "\n").encode())
        return json.loads(s.makefile("rb").readline())


def wait_for_socket(path, process, timeout=10):
    deadline = time.monotonic() + timeout * SLOW
    while time.monotonic() < deadline:
        if process.poll() is not None:
            raise AssertionError("exited with %s: %s" % (process.returncode,
                                                         process.stderr.read().decode()))
        if os.path.exists(path):
            try:
                with socket.socket(socket.AF_UNIX, socket.SOCK_STREAM) as s:
                    s.connect(path)
                    return
            except OSError:
                pass
        time.sleep(0.02)
    raise AssertionError("no socket at %s" % path)


def notify_socket(directory):
    listener = socket.socket(socket.AF_UNIX, socket.SOCK_DGRAM)
    path = os.path.join(directory, "notify.sock")
    listener.bind(path)
    listener.settimeout(10 * SLOW)
    return listener, path


def messages_until(listener, wanted):
    """Datagrams received until one holds `wanted`."""
    seen = []
    while not any(wanted in m for m in seen):
        seen.append(listener.recv(4096).decode())
    return seen


# ---- the units ------------------------------------------------------------------

@pytest.mark.skipif(shutil.which("systemd-analyze") is None, reason="no systemd-analyze")
def test_units_verify(harness):
    """systemd-analyze verify accepts the socket and the service (with
    ExecStart pointing at the built daemon, as make install would)."""
    memory_max = subprocess.run([os.path.join(REPO, "systemd", "memory-max"), BINARY],
                                capture_output=True, text=True, check=True).stdout.strip()
    for name in ("wrenchd.socket", "wrenchd.service"):
        with open(os.path.join(REPO, "systemd", name)) as f:
            text = (f.read().replace("@SBINDIR@", os.path.dirname(BINARY))
                    .replace("@CONFIG_FILE@", harness.path("wrenchd.conf"))
                    .replace("@MEMORY_MAX@", memory_max))
        with open(harness.path(name), "w") as f:
            f.write(text)
    r = subprocess.run(["systemd-analyze", "verify", "--man=no",
                        harness.path("wrenchd.socket"), harness.path("wrenchd.service")],
                       capture_output=True, text=True, timeout=60)
    assert r.returncode == 0, r.stderr
    with open(harness.path("wrenchd.service")) as f:
        service = f.read()
    for directive in ("Type=notify", "StateDirectory=wrenchd", "RuntimeDirectory=wrenchd",
                      "ProtectSystem=strict", "ProtectHome=yes", "PrivateTmp=yes",
                      "NoNewPrivileges=yes", "RestrictAddressFamilies=AF_UNIX",
                      "MemoryDenyWriteExecute=yes", "SystemCallFilter=@system-service",
                      "Restart=on-failure", "User=wrenchd", "MemoryMax=" + memory_max):
        assert directive in service, directive
    with open(harness.path("wrenchd.socket")) as f:
        unit = f.read()
    assert "SocketMode=0660" in unit and "SocketGroup=wrenchd" in unit


# ---- socket activation and sd_notify ---------------------------------------------

@pytest.mark.skipif(shutil.which("systemd-socket-activate") is None,
                    reason="no systemd-socket-activate")
def test_socket_activation_and_notify(harness):
    """systemd-socket-activate binds the socket and starts wrenchd on the
    first connection; wrenchd serves on the inherited socket, says READY=1,
    and at SIGTERM STOPPING=1 -- and leaves the socket file, systemd's, alone."""
    listener, notify_path = notify_socket(harness.dir)
    sock = harness.path("activated.sock")
    env = dict(os.environ, NOTIFY_SOCKET=notify_path)
    process = subprocess.Popen(["systemd-socket-activate", "-l", sock, "-E", "NOTIFY_SOCKET"] +
                               WRAPPER + [BINARY] + NO_CONFIG +
                               ["--log-level", "warn", "--socket", harness.path("ignored.sock")],
                               env=env, stderr=subprocess.PIPE)
    try:
        wait_for_socket(sock, process)
        with open(DISC) as f:
            put = request(sock, "fixture.put", {"fixture": json.load(f)})
        assert put["result"]["id"] == DISC_ID
        answer = request(sock, "wrench.classify", {"fixture": DISC_ID, "wrenches": [[-1, -1, 0]]})
        assert answer["result"]["results"][0]["goal"]["verdict"] == "inside"
        assert any("READY=1" in m for m in messages_until(listener, "READY=1"))
        assert not os.path.exists(harness.path("ignored.sock"))
    finally:
        process.send_signal(signal.SIGTERM)
        status = process.wait(timeout=20 * SLOW)
    assert status == 0, process.stderr.read().decode()
    assert any("STOPPING=1" in m for m in messages_until(listener, "STOPPING=1"))
    assert os.path.exists(sock)  # systemd's to remove
    listener.close()


def test_notify_without_activation(harness):
    """Started by hand with NOTIFY_SOCKET set: READY=1 once listening,
    STOPPING=1 at SIGTERM; the socket file it made is removed."""
    listener, notify_path = notify_socket(harness.dir)
    sock = harness.path("plain.sock")
    process = subprocess.Popen(WRAPPER + [BINARY] + NO_CONFIG + ["--log-level", "warn",
                                                                 "--socket", sock],
                               env=dict(os.environ, NOTIFY_SOCKET=notify_path),
                               stderr=subprocess.PIPE)
    ready = messages_until(listener, "READY=1")
    assert any("STATUS=" in m for m in ready)
    assert request(sock, "server.status")["result"]["fixtures"] == 0
    process.send_signal(signal.SIGTERM)
    assert process.wait(timeout=20 * SLOW) == 0
    assert messages_until(listener, "STOPPING=1")
    assert not os.path.exists(sock)
    listener.close()


# ---- the configuration file ----------------------------------------------------------

def test_configuration_file_and_overrides(harness):
    config = harness.path("wrenchd.conf")
    with open(config, "w") as f:
        f.write("# comment\n\nmax-wrenches = 5   # five\nlog-level=warn\nload = %s\n" % DISC)
    d = harness.start("--config", config)
    c = d.client()
    e = c.error("wrench.classify", {"fixture": DISC_ID, "wrenches": [[1, 0, 0]] * 6})
    assert e["code"] == -32003 and "5" in e["data"]["reason"]   # from the file
    assert c.result("fixture.list")["fixtures"][0]["id"] == DISC_ID   # load = ...
    d2 = harness.start("--config", config, "--max-wrenches", "10",
                       socket_path=harness.path("second.sock"))
    c2 = d2.client()
    assert len(c2.result("wrench.classify", {"fixture": DISC_ID,
                                             "wrenches": [[1, 0, 0]] * 6})["results"]) == 6


@pytest.mark.parametrize("text,message", [
    ("no-such-option = 1\n", ":1: no such option"),
    ("\nthreads = lots\n", ":2: threads wants a whole number"),
    ("threads\n", ":1: wants 'option = value'"),
    ("allow-uid = no-such-user-anywhere\n", "no user named"),
])
def test_bad_configuration_exits_2(harness, text, message):
    config = harness.path("bad.conf")
    with open(config, "w") as f:
        f.write(text)
    r = harness.run("--config", config, "--socket", harness.path("x.sock"))
    assert r.returncode == 2, r.stderr
    assert message in r.stderr.decode(), r.stderr


def test_missing_configuration_file_exits_2(harness):
    r = harness.run("--config", harness.path("nowhere.conf"))
    assert r.returncode == 2 and b"nowhere.conf" in r.stderr


# ---- peer access control ---------------------------------------------------------------

def test_peer_outside_the_allow_list_is_refused(harness):
    """--allow-uid lists someone else: we get one JSON-RPC error (-32005)
    naming our uid, and the connection is closed."""
    d = harness.start("--allow-uid", str(os.getuid() + 4242))
    with socket.socket(socket.AF_UNIX, socket.SOCK_STREAM) as s:
        s.settimeout(10 * SLOW)
        s.connect(d.path)
        f = s.makefile("rb")
        answer = json.loads(f.readline())
        assert answer["error"]["code"] == -32005
        assert ("uid %d" % os.getuid()) in answer["error"]["data"]["reason"]
        assert f.readline() == b""  # closed


@pytest.mark.skipif(os.getuid() != 0, reason="needs root to connect as another user")
def test_allowed_and_denied_peers_are_counted(harness):
    """Root is allowed by --allow-uid 0, a child that became nobody is not,
    unless its supplementary group is in --allow-gid; server.status counts
    the refusals."""
    gid = 4343
    d = harness.start("--allow-uid", "0", "--allow-gid", str(gid))

    def as_nobody(groups):
        script = ("import os, socket, json\n"
                  "os.setgroups(%r); os.setgid(65534); os.setuid(65534)\n"
                  "s = socket.socket(socket.AF_UNIX); s.connect(%r)\n"
                  "s.sendall(b'{\"jsonrpc\":\"2.0\",\"method\":\"server.status\",\"id\":1}\\n')\n"
                  "print(s.makefile('rb').readline().decode())\n" % (groups, d.path))
        out = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True,
                             timeout=30 * SLOW)
        assert out.returncode == 0, out.stderr
        return json.loads(out.stdout)

    # The directory's and the socket's modes are not what is tested here.
    os.chmod(harness.dir, 0o755)
    os.chmod(d.path, 0o666)
    denied = as_nobody([])
    assert denied["error"]["code"] == -32005 and "uid 65534" in denied["error"]["data"]["reason"]
    allowed = as_nobody([gid])  # a supplementary group in --allow-gid
    assert "result" in allowed, allowed
    status = d.client().result("server.status")
    assert status["denied"] == 1


# ---- make install --------------------------------------------------------------------

PROGRAM = r"""
#include <stdio.h>
#include "wrench.h"
#include "wrenchclient.h"

int main(void)
{
    wr_fixel_spec fixels[2] = {{.at = {-1, 0}, .normal_given = 1, .normal = {1, 0}},
                               {.at = {0, -1}, .normal_given = 1, .normal = {0, 1}}};
    wr_fixture_spec spec = {.mass = 1, .shape = WR_SHAPE_CIRCLE, .radius = 1,
                            .friction = {.given = 1, .static_mu = 0.5},
                            .fixel_count = 2, .fixels = fixels};
    wr_fixture *f;
    wr_analysis *a;
    if (wr_fixture_new(&spec, &f, NULL) != WR_OK || wr_analysis_new(f, &a) != WR_OK)
        return 1;
    wr_answer answer;
    wr_classify(a, (double[3]){-1, -1, 0}, WR_SET_GOAL, WR_DEFAULT_TOLERANCE, &answer);
    printf("%d %.12f %s\n", answer.verdict, answer.margin, wrc_strerror(WRC_ETIMEOUT));
    wr_analysis_free(a);
    wr_fixture_free(f);
    return 0;
}
"""

EXPECTED_FILES = ["sbin/wrenchd", "bin/wrenchctl", "lib/libwrench.a", "lib/libwrenchclient.a",
                  "include/wrench/wrench.h", "include/wrench/wr_status.h",
                  "include/wrench/wr_outline.h", "include/wrench/wr_finger.h",
                  "include/wrench/wr_fixture.h",
                  "include/wrench/wr_regions.h", "include/wrench/wrenchclient.h",
                  "lib/pkgconfig/wrench.pc", "lib/pkgconfig/wrenchclient.pc",
                  "lib/systemd/system/wrenchd.service", "lib/systemd/system/wrenchd.socket",
                  "lib/sysusers.d/wrenchd.conf", "share/man/man1/wrenchctl.1",
                  "share/man/man8/wrenchd.8", "share/wrenchd/examples/disc-corner.json"]


@pytest.mark.skipif(shutil.which("pkg-config") is None, reason="no pkg-config")
def test_make_install_and_pkg_config(harness):
    stage = harness.path("stage")
    prefix = "/usr/local"
    r = subprocess.run(["make", "-s", "-C", REPO, "install", "DESTDIR=" + stage,
                        "PREFIX=" + prefix], capture_output=True, text=True, timeout=600)
    assert r.returncode == 0, r.stdout + r.stderr
    root = stage + prefix
    for path in EXPECTED_FILES:
        assert os.path.isfile(os.path.join(root, path)), path
    # The configuration under the prefix too ($(PREFIX)/etc), none in /etc.
    assert os.path.isfile(os.path.join(root, "etc", "wrenchd", "wrenchd.conf"))
    assert not os.path.exists(os.path.join(stage, "etc"))
    python = [p for p in os.listdir(os.path.join(root, "lib")) if p.startswith("python")]
    assert python and os.path.isfile(os.path.join(root, "lib", python[0], "dist-packages",
                                                  "wrenchd.py"))
    with open(os.path.join(root, "lib/systemd/system/wrenchd.service")) as f:
        assert ("ExecStart=/usr/local/sbin/wrenchd --config /usr/local/etc/wrenchd/wrenchd.conf "
                in f.read())
    # pkg-config pointed at the staged tree compiles and runs a program.
    env = dict(os.environ, PKG_CONFIG_PATH=os.path.join(root, "lib", "pkgconfig"))
    flags = subprocess.run(["pkg-config", "--define-prefix", "--cflags", "--libs", "wrench",
                            "wrenchclient"], capture_output=True, text=True, env=env)
    assert flags.returncode == 0, flags.stderr
    assert root in flags.stdout
    source = harness.path("uses_wrench.c")
    with open(source, "w") as f:
        f.write(PROGRAM)
    program = harness.path("uses_wrench")
    compiled = subprocess.run(["cc", "-std=c11", "-Wall", "-Werror", source, "-o", program] +
                              flags.stdout.split(), capture_output=True, text=True)
    assert compiled.returncode == 0, compiled.stderr
    ran = subprocess.run([program], capture_output=True, text=True, timeout=30)
    # docs/MODEL.md section 7: inside, margin (1 - mu) / sqrt(2 (1 + mu^2)) at mu = 0.5.
    assert ran.stdout.split()[:2] == ["0", "%.12f" % (0.5 / (2 * 1.25) ** 0.5)]
    # The installed wrenchctl answers locally with the installed examples.
    local = subprocess.run([os.path.join(root, "bin", "wrenchctl"), "--local", "plan",
                            os.path.join(root, "share/wrenchd/examples/disc-corner.json")],
                           capture_output=True, text=True)
    assert "su ms us sm" in local.stdout
    # And make uninstall takes it all away.
    r = subprocess.run(["make", "-s", "-C", REPO, "uninstall", "DESTDIR=" + stage,
                        "PREFIX=" + prefix], capture_output=True, text=True, timeout=120)
    assert r.returncode == 0, r.stderr
    left = [os.path.join(d, f) for d, _, files in os.walk(stage) for f in files]
    assert left == [], left


def unit_settings(path):
    """The Key=value lines of a unit file, last one wins."""
    settings = {}
    with open(path) as f:
        for line in f:
            if "=" in line and not line.startswith("#"):
                key, value = line.rstrip("\n").split("=", 1)
                settings[key] = value
    return settings


def memory_max(binary, config_text=""):
    """MemoryMax= by the formula of systemd/memory-max, written again here:
    the defaults from the daemon's --help, the file's settings over them."""
    help_text = subprocess.run([binary, "--help"], capture_output=True, text=True,
                               check=True).stdout
    values, option = {}, None
    for line in help_text.splitlines():
        if line.startswith("  --"):
            option = line.split()[0][2:]
        found = re.search(r"\(default (\d+)\)", line)
        if found:
            values[option] = int(found.group(1))
    values["threads"] = os.sysconf("SC_NPROCESSORS_ONLN")   # "the number of cores"
    for line in config_text.splitlines():
        key, _, value = line.split("#")[0].partition("=")
        if value.strip():
            values[key.strip()] = int(value)
    mib = 1 << 20
    total = (values["cache-mb"] * mib
             + values["max-clients"] * (values["max-output"] + 3 * values["max-line"]
                                        + 256 * values["max-wrenches"] + mib / 4)
             + values["threads"] * (16 * 0.7 * mib + 64 * values["max-line"])
             + 64 * mib)
    return "%dM" % -(-total // mib)


def test_memory_max_matches_the_configured_limits(harness):
    """The installed unit's MemoryMax= is the formula's for the daemon's
    defaults (the shipped file sets nothing); with a file of the
    administrator's already in place, for its limits -- and the file is kept."""
    stage = harness.path("stage")

    def install():
        r = subprocess.run(["make", "-s", "-C", REPO, "install", "DESTDIR=" + stage,
                            "PREFIX=/usr/local"], capture_output=True, text=True, timeout=600)
        assert r.returncode == 0, r.stdout + r.stderr
        return unit_settings(os.path.join(stage, "usr/local/lib/systemd/system/wrenchd.service"))

    unit = install()
    assert unit["MemoryMax"] == memory_max(BINARY), unit.get("MemoryMax")
    config = os.path.join(stage, "usr/local/etc/wrenchd/wrenchd.conf")
    mine = "threads = 3\ncache-mb = 100   # less\nmax-clients = 10\nmax-output = 4096\n"
    with open(config, "w") as f:
        f.write(mine)
    unit = install()
    assert unit["MemoryMax"] == memory_max(BINARY, mine), unit.get("MemoryMax")
    # By hand: max-line's default is 16 MiB, max-wrenches' 100000.
    assert unit["MemoryMax"] == "%dM" % -(-(100 + 10 * (4096 / (1 << 20) + 3 * 16
                                                        + 256 * 100000 / (1 << 20) + 0.25)
                                            + 3 * (11.2 + 64 * 16) + 64) // 1)
    with open(config) as f:
        assert f.read() == mine


# Run in a mount namespace of its own (unshare -m): every mount read-only
# but the directories named in argv[1] (colon-separated), then exec argv[2:].
# A write anywhere else fails with EROFS.
READ_ONLY_BUT = r"""
import errno, os, re, subprocess, sys
writable = sys.argv[1].split(":")
for path in writable:
    subprocess.run(["mount", "--bind", path, path], check=True)
with open("/proc/self/mountinfo") as f:
    points = [re.sub(r"\\(\d{3})", lambda m: chr(int(m.group(1), 8)), line.split()[4])
              for line in f]
for point in points:
    if point not in writable and not point.startswith(("/proc", "/sys", "/dev")):
        subprocess.run(["mount", "-o", "remount,bind,ro", point], stderr=subprocess.DEVNULL)
for probe in ("/etc", os.path.dirname(writable[0])):
    try:
        os.close(os.open(os.path.join(probe, ".wrenchd-probe"), os.O_CREAT | os.O_WRONLY))
        sys.exit("%s is still writable: the test would prove nothing" % probe)
    except OSError as e:
        if e.errno != errno.EROFS:
            raise
os.execvp(sys.argv[2], sys.argv[2:])
"""


@pytest.fixture(scope="module")
def build_elsewhere():
    """A build directory of the install tests' own: a PREFIX other than the
    checkout's rebuilds the daemon (its configuration path), which must not
    change build/ under the other tests' feet."""
    directory = tempfile.mkdtemp(prefix="wrbuild", dir="/tmp")
    yield directory
    shutil.rmtree(directory, ignore_errors=True)


@pytest.mark.skipif(os.geteuid() != 0 or shutil.which("unshare") is None,
                    reason="needs root and unshare to make all but DESTDIR read-only")
@pytest.mark.parametrize("prefix,sysconfdir,destdir", [
    ("/tmp/inst", None, True),
    ("/usr", "/etc", True),
    ("inst", None, False),    # no DESTDIR: a PREFIX in the test's directory
])
def test_make_install_writes_only_under_destdir(harness, build_elsewhere, prefix, sysconfdir,
                                               destdir):
    """make install writes nothing outside DESTDIR$(PREFIX) (the rest of the
    system read-only): with a PREFIX of its own, with the usual PREFIX=/usr
    SYSCONFDIR=/etc, and without DESTDIR.  The unit and the installed daemon
    name the configuration file of that prefix; make uninstall takes it all
    away."""
    scratch = harness.path("scratch")
    os.makedirs(scratch)
    if destdir:
        stage = harness.path("stage")
        writable = stage
    else:
        stage, prefix = "", harness.path(prefix)
        writable = prefix
    os.makedirs(writable)
    make = (["make", "-s", "-C", REPO, "BUILD=" + build_elsewhere, "PREFIX=" + prefix] +
            (["DESTDIR=" + stage] if destdir else []) +
            (["SYSCONFDIR=" + sysconfdir] if sysconfdir else []))
    config = (sysconfdir or prefix + "/etc") + "/wrenchd/wrenchd.conf"
    env = dict(os.environ, TMPDIR=scratch)   # the compiler's temporary files
    r = subprocess.run(["unshare", "--mount", "--propagation", "private", sys.executable, "-c",
                        READ_ONLY_BUT, ":".join([writable, build_elsewhere, scratch])] +
                       make + ["-j2", "install"],
                       capture_output=True, text=True, timeout=900, env=env)
    assert r.returncode == 0, r.stdout[-3000:] + r.stderr[-3000:]
    files = {os.path.join(d, f)[len(stage):] for d, _, names in os.walk(writable)
             for f in names}
    assert config in files and prefix + "/sbin/wrenchd" in files, sorted(files)
    unit = unit_settings(stage + prefix + "/lib/systemd/system/wrenchd.service")
    assert unit["ExecStart"].split()[:3] == [prefix + "/sbin/wrenchd", "--config", config]
    installed = stage + prefix + "/sbin/wrenchd"
    help_text = subprocess.run([installed, "--help"], capture_output=True, text=True).stdout
    assert config in help_text, help_text[:600]
    assert unit["MemoryMax"] == memory_max(installed)
    with open(stage + config) as f:
        shipped = f.read()
    assert shipped.startswith("# " + config + " -- ")
    if not destdir:
        # Installed for real: without --config the daemon reads that file.
        with open(config, "w") as f:
            f.write("threads = lots\n")
        ran = subprocess.run([installed, "--socket", harness.path("never.sock")],
                             capture_output=True, text=True, timeout=30)
        assert ran.returncode == 2 and config + ":1: threads" in ran.stderr, ran.stderr
        with open(config, "w") as f:
            f.write(shipped)
    r = subprocess.run(make + ["uninstall"], capture_output=True, text=True, timeout=300)
    assert r.returncode == 0, r.stderr
    left = [os.path.join(d, f) for d, _, names in os.walk(writable) for f in names]
    assert left == [], left
