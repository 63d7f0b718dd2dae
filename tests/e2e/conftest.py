"""End-to-end test harness for wrenchd.

Every test starts its own daemon on a socket in a fresh short directory under
/tmp, waits until the socket accepts, and on teardown sends SIGTERM and
asserts exit status 0 and a stderr free of sanitizer / valgrind reports.

Environment:
  WRENCHD          the daemon binary (default: <repo>/build/wrenchd)
  WRENCHD_WRAPPER  a command prefix, e.g. "valgrind --error-exitcode=99
                   --leak-check=full"; timeouts are then multiplied by
                   WRENCHD_SLOW (default 20 with a wrapper, else 1)
"""

import json
import os
import re
import shlex
import shutil
import signal
import socket
import subprocess
import sys
import tempfile
import time

import pytest

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)

REPO = os.path.abspath(os.path.join(HERE, "..", ".."))
BINARY = os.environ.get("WRENCHD", os.path.join(REPO, "build", "wrenchd"))
WRAPPER = shlex.split(os.environ.get("WRENCHD_WRAPPER", ""))
SLOW = float(os.environ.get("WRENCHD_SLOW", "20" if WRAPPER else "1"))

# A sanitizer's allocator keeps freed memory (ASan's quarantine): resident
# memory is then no measure of what the daemon holds.
SANITIZED = "asan" in BINARY or "valgrind" in " ".join(WRAPPER)

# Without --config the daemon reads $(SYSCONFDIR)/wrenchd/wrenchd.conf when it
# exists: a test's daemon reads none unless the test gives its own (a later
# --config wins).
NO_CONFIG = ["--config", "/dev/null"]

START_TIMEOUT = 10.0 * SLOW
IO_TIMEOUT = 30.0 * SLOW
STOP_TIMEOUT = 20.0 * SLOW

# Reports a sanitizer or valgrind prints on stderr.
BAD_STDERR = [
    re.compile(p) for p in (
        r"ERROR: AddressSanitizer",
        r"ERROR: LeakSanitizer",
        r"WARNING: ThreadSanitizer",
        r"ERROR: ThreadSanitizer",
        r"UndefinedBehaviorSanitizer",
        r"runtime error:",
        r"ERROR SUMMARY: [1-9]",
        r"==\d+== (Invalid (read|write|free)|Conditional jump|Use of uninitialised|"
        r"Syscall param|Mismatched free|Source and destination overlap)",
        r"definitely lost: [1-9]",
        r"indirectly lost: [1-9]",
        r"Possible data race",
        r"Lock order",
    )
]


def sanitizer_reports(text):
    return [line for line in text.splitlines() if any(p.search(line) for p in BAD_STDERR)]


def short(obj, limit=600):
    text = json.dumps(obj) if not isinstance(obj, (str, bytes)) else repr(obj)
    return text if len(text) <= limit else text[:limit] + "...(%d chars)" % len(text)


class RpcError(Exception):
    pass


class Client:
    """A newline-delimited JSON-RPC 2.0 client over AF_UNIX."""

    def __init__(self, path, timeout=None):
        self.path = path
        self.sock = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
        self.sock.settimeout(timeout or IO_TIMEOUT)
        self.sock.connect(path)
        self.buf = b""
        self.next_id = 1

    # ---- raw ----
    def send_raw(self, data):
        if isinstance(data, str):
            data = data.encode()
        self.sock.sendall(data)

    def send_line(self, line):
        if isinstance(line, str):
            line = line.encode()
        self.send_raw(line + b"\n")

    def read_line(self, timeout=None):
        """The next line, without its newline.  Raises EOFError at EOF and
        socket.timeout when none arrives in time."""
        deadline = time.monotonic() + (timeout if timeout is not None else IO_TIMEOUT)
        while b"\n" not in self.buf:
            left = deadline - time.monotonic()
            if left <= 0:
                raise socket.timeout("no line within the timeout")
            self.sock.settimeout(left)
            try:
                chunk = self.sock.recv(1 << 16)
            finally:
                self.sock.settimeout(IO_TIMEOUT)
            if not chunk:
                raise EOFError("connection closed by the daemon (partial: %r)" % self.buf[:200])
            self.buf += chunk
        line, self.buf = self.buf.split(b"\n", 1)
        return line

    def read_json(self, timeout=None):
        line = self.read_line(timeout)
        try:
            return json.loads(line)
        except ValueError as e:
            raise AssertionError("daemon sent a line that is not JSON: %r (%s)" % (line[:300], e))

    def expect_silence(self, seconds=0.3):
        """Assert that no line arrives within `seconds`."""
        try:
            line = self.read_line(timeout=seconds)
        except socket.timeout:
            return
        raise AssertionError("expected no answer, got %r" % line[:300])

    def at_eof(self, timeout=5.0):
        """True when the daemon closed the connection (after any pending lines)."""
        deadline = time.monotonic() + timeout
        while time.monotonic() < deadline:
            self.sock.settimeout(max(0.01, deadline - time.monotonic()))
            try:
                chunk = self.sock.recv(1 << 16)
            except socket.timeout:
                return False
            except (ConnectionResetError, BrokenPipeError):
                return True
            finally:
                self.sock.settimeout(IO_TIMEOUT)
            if not chunk:
                return True
            self.buf += chunk
        return False

    # ---- JSON-RPC ----
    def request(self, method, params=None, id=None, **extra):
        """Build a request object (an id is allocated unless given)."""
        if id is None:
            id = self.next_id
            self.next_id += 1
        req = {"jsonrpc": "2.0", "method": method, "id": id}
        if params is not None:
            req["params"] = params
        req.update(extra)
        return req

    def send(self, obj):
        self.send_line(json.dumps(obj, separators=(",", ":")))

    def call(self, method, params=None, id=None):
        """Send one request and return the whole response object."""
        req = self.request(method, params, id)
        self.send(req)
        resp = self.read_json()
        assert resp.get("id") == req["id"], "answer to the wrong id: %s for %s" % (
            short(resp), short(req))
        assert resp.get("jsonrpc") == "2.0", resp
        return resp

    def result(self, method, params=None):
        resp = self.call(method, params)
        if "error" in resp:
            raise RpcError("%s failed: %s" % (method, json.dumps(resp["error"])))
        assert set(resp) == {"jsonrpc", "id", "result"}, resp
        return resp["result"]

    def error(self, method, params=None):
        resp = self.call(method, params)
        assert "error" in resp and "result" not in resp, "expected an error, got %r" % (resp,)
        return resp["error"]

    def close(self):
        try:
            self.sock.close()
        except OSError:
            pass


class Daemon:
    def __init__(self, workdir, args=(), state_dir=None, socket_path=None, env=None, tag="d"):
        self.workdir = workdir
        self.tag = tag
        # socket_path "": leave --socket out (the default ./run/wrenchd.sock)
        self.default_socket = socket_path == ""
        if self.default_socket:
            self.path = os.path.join(workdir, "run", "wrenchd.sock")
        else:
            self.path = socket_path or os.path.join(workdir, "s.sock")
        self.state_dir = state_dir
        self.args = list(args)
        self.env = env
        self.proc = None
        self.clients = []
        self.stderr_path = None
        self.generation = 0
        self.expected_status = 0
        self.checked = False

    def command(self):
        cmd = WRAPPER + [BINARY] + NO_CONFIG + ["--log-level", "warn"]
        if not self.default_socket:
            cmd += ["--socket", self.path]
        if self.state_dir:
            cmd += ["--state-dir", self.state_dir]
        return cmd + self.args

    def start(self, wait=True):
        self.generation += 1
        self.stderr_path = os.path.join(self.workdir, "%s.stderr.%d" % (self.tag, self.generation))
        self.stderr_file = open(self.stderr_path, "wb")
        self.proc = subprocess.Popen(self.command(), stdin=subprocess.DEVNULL,
                                     stdout=subprocess.DEVNULL, stderr=self.stderr_file,
                                     cwd=self.workdir, env=self.env)
        self.checked = False
        self.expected_status = 0
        if wait:
            self.wait_ready()
        return self

    def stderr(self):
        with open(self.stderr_path, "rb") as f:
            return f.read().decode(errors="replace")

    def wait_ready(self, timeout=START_TIMEOUT):
        deadline = time.monotonic() + timeout
        while True:
            if self.proc.poll() is not None:
                raise AssertionError("wrenchd exited with %s before accepting; stderr:\n%s"
                                     % (self.proc.returncode, self.stderr()[-4000:]))
            s = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
            try:
                s.connect(self.path)
                return
            except OSError:
                pass
            finally:
                s.close()
            if time.monotonic() > deadline:
                raise AssertionError("wrenchd did not accept on %s within %.0f s; stderr:\n%s"
                                     % (self.path, timeout, self.stderr()[-4000:]))
            time.sleep(0.01)

    def client(self, timeout=None):
        c = Client(self.path, timeout)
        self.clients.append(c)
        return c

    @property
    def pid(self):
        return self.proc.pid

    def running(self):
        return self.proc is not None and self.proc.poll() is None

    def send_signal(self, sig):
        self.proc.send_signal(sig)

    def wait(self, timeout=STOP_TIMEOUT):
        try:
            return self.proc.wait(timeout)
        except subprocess.TimeoutExpired:
            self.proc.kill()
            self.proc.wait()
            raise AssertionError("wrenchd did not exit within %.0f s" % timeout)

    def stop(self, sig=signal.SIGTERM):
        """Signal, wait, check status 0 and a clean stderr; returns the status."""
        for c in self.clients:
            c.close()
        self.clients = []
        self.send_signal(sig)
        status = self.wait()
        self.stderr_file.close()
        self.checked = True
        self.assert_clean_stderr()
        assert status == 0, "wrenchd exited with %s after %s; stderr:\n%s" % (
            status, signal.Signals(sig).name, self.stderr()[-4000:])
        return status

    def kill(self):
        """SIGKILL (no status check, but stderr is still checked)."""
        for c in self.clients:
            c.close()
        self.clients = []
        self.proc.kill()
        self.proc.wait()
        self.stderr_file.close()
        self.checked = True
        self.assert_clean_stderr()

    def assert_clean_stderr(self):
        bad = sanitizer_reports(self.stderr())
        assert not bad, "wrenchd reported errors on stderr:\n" + "\n".join(bad[:40])

    def teardown(self):
        if self.proc is None:
            return
        if self.running():
            self.stop()
        elif not self.checked:
            self.stderr_file.close()
            self.checked = True
            self.assert_clean_stderr()
            assert self.proc.returncode == self.expected_status, (
                "wrenchd exited with %s unexpectedly; stderr:\n%s"
                % (self.proc.returncode, self.stderr()[-4000:]))


class Harness:
    """Starts daemons for one test and cleans up after it."""

    def __init__(self):
        self.dir = tempfile.mkdtemp(prefix="wrd", dir="/tmp")
        self.daemons = []

    def path(self, name):
        return os.path.join(self.dir, name)

    def start(self, *args, state_dir=None, socket_path=None, wait=True, env=None):
        d = Daemon(self.dir, args, state_dir, socket_path, tag="d%d" % len(self.daemons))
        d.env = env
        self.daemons.append(d)
        return d.start(wait)

    def run(self, *args, timeout=None):
        """Run the binary to completion (for command-line checks)."""
        return subprocess.run(WRAPPER + [BINARY] + NO_CONFIG + list(args), cwd=self.dir,
                              stdin=subprocess.DEVNULL, capture_output=True,
                              timeout=timeout or STOP_TIMEOUT)

    def cleanup(self):
        errors = []
        for d in self.daemons:
            try:
                d.teardown()
            except AssertionError as e:
                errors.append(str(e))
        shutil.rmtree(self.dir, ignore_errors=True)
        if errors:
            pytest.fail("\n".join(errors), pytrace=False)


def _require_binary():
    if not (os.path.isfile(BINARY) and os.access(BINARY, os.X_OK)):
        pytest.fail("no daemon binary at %s (run make, or set WRENCHD)" % BINARY, pytrace=False)


@pytest.fixture
def harness():
    _require_binary()
    h = Harness()
    yield h
    h.cleanup()


@pytest.fixture
def daemon(harness):
    """A daemon with default options, memory only."""
    return harness.start()


@pytest.fixture
def client(daemon):
    return daemon.client()


# Figures tests report (how many points, endpoints ...), printed once at the
# end of the run, before pytest's closing line.
FIGURES = {}


def pytest_terminal_summary(terminalreporter):
    if FIGURES:
        terminalreporter.write_line("figures: " + ", ".join(
            "%s %d" % (k, v) for k, v in sorted(FIGURES.items())))
