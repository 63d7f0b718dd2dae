"""The Wrench workbench's tests: FreeCAD's Python (freecadcmd) with a real
wrenchd.

One daemon serves the session (fixtures are content-addressed, so tests
share it without meeting): build/wrenchd, or $WRENCHD, on a socket in a
fresh directory under /tmp, started with --config /dev/null; at the end it
gets SIGTERM and must exit with status 0.  Each test gets a new FreeCAD
document, closed afterwards.
"""

import os
import shutil
import signal
import socket
import subprocess
import sys
import tempfile
import time

import pytest

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.abspath(os.path.join(HERE, "..", ".."))
sys.path.insert(0, os.path.join(REPO, "clients", "freecad"))
sys.path.insert(0, HERE)

import FreeCAD  # noqa: E402

import wrench_freecad  # noqa: E402,F401  (first: it puts clients/python on the path)
import wrenchd  # noqa: E402

BINARY = os.environ.get("WRENCHD", os.path.join(REPO, "build", "wrenchd"))


class Daemon:
    def __init__(self, *options):
        if not (os.path.isfile(BINARY) and os.access(BINARY, os.X_OK)):
            pytest.fail("no daemon binary at %s (run make, or set WRENCHD)" % BINARY,
                        pytrace=False)
        self.dir = tempfile.mkdtemp(prefix="wfc", dir="/tmp")
        self.socket = os.path.join(self.dir, "wrenchd.sock")
        self.stderr = open(os.path.join(self.dir, "stderr"), "wb")
        self.proc = subprocess.Popen([BINARY, "--config", "/dev/null", "--log-level", "warn",
                                      "--socket", self.socket] + list(options), stdin=subprocess.DEVNULL,
                                     stdout=subprocess.DEVNULL, stderr=self.stderr, cwd=self.dir)
        deadline = time.monotonic() + 10
        while True:
            if self.proc.poll() is not None:
                pytest.fail("wrenchd exited with %s before accepting: %s"
                            % (self.proc.returncode, self.log()), pytrace=False)
            s = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
            try:
                s.connect(self.socket)
                break
            except OSError:
                if time.monotonic() > deadline:
                    pytest.fail("wrenchd did not accept on %s" % self.socket, pytrace=False)
                time.sleep(0.01)
            finally:
                s.close()

    def log(self):
        with open(os.path.join(self.dir, "stderr"), "rb") as f:
            return f.read().decode(errors="replace")[-4000:]

    def stop(self):
        self.proc.send_signal(signal.SIGTERM)
        try:
            status = self.proc.wait(20)
        except subprocess.TimeoutExpired:
            self.proc.kill()
            self.proc.wait()
            status = "killed after 20 s"
        self.stderr.close()
        log = self.log()
        shutil.rmtree(self.dir, ignore_errors=True)
        assert status == 0, "wrenchd exited with %s; stderr:\n%s" % (status, log)


@pytest.fixture(scope="session")
def daemon():
    d = Daemon()
    yield d
    d.stop()


@pytest.fixture
def client(daemon):
    c = wrenchd.Client(daemon.socket, timeout=60)
    yield c
    c.close()


@pytest.fixture
def doc(request):
    name = "t_" + "".join(ch if ch.isalnum() else "_" for ch in request.node.name)[:40]
    d = FreeCAD.newDocument(name)
    name = d.Name
    yield d
    if name in FreeCAD.listDocuments():      # a test may have closed it
        FreeCAD.closeDocument(name)
