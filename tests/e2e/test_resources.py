"""Resource control: whatever a client asks, and however it
behaves, its connection costs bounded memory and bounded work.

* Memory per connection is bounded: a large answer is produced in pieces as
  the client drains it (the work pauses while the connection is above a
  high-water mark), so a connection's unsent output, the answer being
  written included, stays under --max-output plus a small constant; a
  client that leaves output unread for longer than --idle-timeout is closed.
* Work for a client that is gone stops, and clients share the workers
  fairly: a closed connection's queued requests are cancelled and its
  running ones stop within a bounded amount of work; workers take work
  round-robin across connections in pieces of bounded cost.
* A request must arrive whole within --request-timeout of its first byte.

What the tests assume of the daemon beyond the issue's words:
* --max-output, --max-line, --max-wrenches, --threads, --idle-timeout as
  today; a new --request-timeout SECONDS (default 30), listed by --help and
  read from the configuration file as request-timeout.
* What a connection holds, the request being answered included, counts
  against the memory bound: 40 x --max-output + 64 MiB must cover 40 paused
  100,000-wrench requests (keep them as doubles, not as cJSON trees, and
  pause well below --max-output).
* A client closed for leaving its output unread is closed no earlier than
  --idle-timeout after its request; a steady slow reader is never closed.
* A request that does not arrive whole in time: the connection is closed,
  after at most one error line (-32600, id null).

Figures a run measures (peak resident memory, latencies, CPU after a
disconnect) are printed with -s and go into the assertion messages."""

import json
import math
import os
import random
import re
import socket
import statistics
import threading
import time

import pytest

import fixtures as FX
from conftest import SANITIZED, SLOW, WRAPPER, FIGURES

MIB = 1 << 20
KIB = 1 << 10

# ---- measuring the daemon -----------------------------------------------------

CLOCK_TICKS = os.sysconf("SC_CLK_TCK")


def resident_bytes(pid):
    with open("/proc/%d/status" % pid) as f:
        for line in f:
            if line.startswith("VmRSS:"):
                return int(line.split()[1]) * KIB
    return 0


def cpu_seconds(pid):
    """utime + stime of the whole process (every thread), in seconds."""
    with open("/proc/%d/stat" % pid) as f:
        fields = f.read().rsplit(")", 1)[1].split()
    # fields[0] is the state (field 3): utime and stime are fields 14 and 15
    return (int(fields[11]) + int(fields[12])) / CLOCK_TICKS


def thread_cpu(pid):
    """CPU seconds of each thread of a process, by thread id."""
    ticks = os.sysconf("SC_CLK_TCK")
    out = {}
    for tid in os.listdir("/proc/%d/task" % pid):
        try:
            with open("/proc/%d/task/%s/stat" % (pid, tid)) as f:
                fields = f.read().rsplit(")", 1)[1].split()
            out[tid] = (int(fields[11]) + int(fields[12])) / ticks
        except OSError:
            pass
    return out


def report(text):
    print("[resources] " + text)


def answers_of_one_worker(harness, requests, timeout):
    """Each request's answer line, in turn, from a daemon with one worker
    (what a daemon with more must answer byte for byte)."""
    one = harness.start("--threads", "1")
    try:
        s = raw_socket(one.path)
        reader = LineReader(s)
        answers = []
        for r in requests:
            s.sendall(r)
            answers.append(reader.line(timeout * SLOW))
        s.close()
        return answers
    finally:
        one.stop()


def busy_threads(pid, seconds, what):
    """Over `seconds`: the cores the process kept busy, and the CPU seconds
    of its threads, busiest first (reported)."""
    before, threads_before = cpu_seconds(pid), thread_cpu(pid)
    time.sleep(seconds)
    cores = (cpu_seconds(pid) - before) / seconds
    threads_after = thread_cpu(pid)
    used = sorted((threads_after[t] - threads_before.get(t, 0) for t in threads_after),
                  reverse=True)
    report("%s on two workers: %.2f cores busy; its busiest threads %s s"
           % (what, cores, ", ".join("%.2f" % u for u in used[:3])))
    return cores, used


# ---- raw connections ----------------------------------------------------------

def raw_socket(path, rcvbuf=None, timeout=None):
    s = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
    if rcvbuf:
        s.setsockopt(socket.SOL_SOCKET, socket.SO_RCVBUF, rcvbuf)
    s.settimeout(timeout or 30 * SLOW)
    s.connect(path)
    return s


def closed_by_peer(s, timeout):
    """Read (and drop) whatever is queued until EOF or a reset: True when the
    daemon has closed the connection, False when it stays open for
    `timeout` seconds without sending anything more."""
    deadline = time.monotonic() + timeout
    while True:
        left = deadline - time.monotonic()
        if left <= 0:
            return False
        s.settimeout(left)
        try:
            chunk = s.recv(1 << 20)
        except socket.timeout:
            return False
        except (ConnectionResetError, BrokenPipeError):
            return True
        if not chunk:
            return True


class LineReader:
    """Lines from a raw socket, with a deadline per line."""

    def __init__(self, sock):
        self.sock = sock
        self.parts = []

    def line(self, timeout):
        deadline = time.monotonic() + timeout
        while True:
            if self.parts and b"\n" in self.parts[-1]:
                data = b"".join(self.parts)
                line, rest = data.split(b"\n", 1)
                self.parts = [rest] if rest else []
                return line
            left = deadline - time.monotonic()
            if left <= 0:
                raise socket.timeout("no line within %.1f s" % timeout)
            self.sock.settimeout(left)
            chunk = self.sock.recv(1 << 20)
            if not chunk:
                raise EOFError("connection closed by the daemon")
            self.parts.append(chunk)


def rpc_line(method, params, id):
    return (json.dumps({"jsonrpc": "2.0", "method": method, "params": params, "id": id},
                       separators=(",", ":")) + "\n").encode()


def timed_call(sock, reader, method, params, id, timeout):
    """One request on a raw socket: (seconds to its answer, the answer)."""
    start = time.monotonic()
    sock.sendall(rpc_line(method, params, id))
    answer = json.loads(reader.line(timeout))
    took = time.monotonic() - start
    assert answer.get("id") == id and "result" in answer, answer
    return took, answer


# ---- fixtures -----------------------------------------------------------------

def eight_fixels(mu=0.3):
    """A unit disc on 8 fixels (every 15 degrees from 200), friction 0.3:
    1024 goal cones; a classify of one wrench for goal, strong and both
    answers about 1 KB (blocking strings, states and witnesses)."""
    f = FX.disc_corner(mu, name="eight-fixels")
    f["fixels"] = [{"at": [math.cos(math.radians(200 + 15 * i)),
                           math.sin(math.radians(200 + 15 * i))]} for i in range(8)]
    return f


def large_outline(n=4000):
    """An ellipse-like polygon of n vertices (the limit is 4096) on four
    fixels: push.regions of the set strong with finger_friction samples
    2048 points per edge, about 2.5 s of one core per request here."""
    verts = [[round(2.0 * math.cos(2 * math.pi * i / n), 9),
              round(1.2 * math.sin(2 * math.pi * i / n), 9)] for i in range(n)]
    fixels = []
    for a in (200, 240, 280, 320):
        k = int(a / 360 * n)
        p, q = verts[k], verts[(k + 1) % n]
        fixels.append({"at": [(p[0] + q[0]) / 2, (p[1] + q[1]) / 2]})
    return {"name": "outline-%d" % n,
            "body": {"mass": 1.0, "shape": {"type": "polygon", "vertices": verts}},
            "friction": {"static": 0.3}, "fixels": fixels}


WRENCHES = 100000


def big_classify_prefix(fixture_id, count=WRENCHES, seed=14):
    """A wrench.classify line of `count` random wrenches for the three sets,
    without its id: prefix + b'%d}\\n' % id.  Small integers (the cones do
    not care about magnitudes) keep the line under 10 bytes a wrench (about
    0.95 MB), while the answer is about 970 bytes a wrench (97 MB): nearly
    all are outside both sets, with blocking strings, states and witnesses."""
    rnd = random.Random(seed)
    wrenches = []
    while len(wrenches) < count:
        w = [rnd.randint(-9, 9) for _ in range(3)]
        if any(w):
            wrenches.append(w)
    params = {"fixture": fixture_id, "wrenches": wrenches, "sets": ["goal", "strong", "both"]}
    return ('{"jsonrpc":"2.0","method":"wrench.classify","params":%s,"id":'
            % json.dumps(params, separators=(",", ":"))).encode()


class Observer(threading.Thread):
    """An ordinary client sending small requests one after another (a
    classify of one wrench by a stored fixture, then modes.get), one every
    `pace` seconds, recording each answer's latency."""

    def __init__(self, path, requests, pace=0.05, timeout=None):
        super().__init__(daemon=True)
        self.sock = raw_socket(path)
        self.reader = LineReader(self.sock)
        self.requests = requests
        self.pace = pace
        self.timeout = timeout or 30 * SLOW
        self.stop_event = threading.Event()
        self.latencies = []
        self.worst = (0.0, None)
        self.error = None
        self.pending = None     # (since, method) of the request awaiting its answer

    def run(self):
        i = 0
        try:
            while not self.stop_event.is_set():
                method, params = self.requests[i % len(self.requests)]
                self.pending = (time.monotonic(), method)
                took, _ = timed_call(self.sock, self.reader, method, params, i, self.timeout)
                self.pending = None
                self.latencies.append(took)
                if took > self.worst[0]:
                    self.worst = (took, method)
                i += 1
                self.stop_event.wait(self.pace)
        except BaseException as e:  # reported by the test
            self.error = e

    def finish(self):
        """Stop; a request still unanswered counts with its wait so far."""
        pending = self.pending
        if pending and time.monotonic() - pending[0] > self.worst[0]:
            self.worst = (time.monotonic() - pending[0], pending[1] + ", still unanswered")
        self.stop_event.set()
        self.join(5 * SLOW)
        if self.is_alive():       # stuck behind others' work: cut it short
            self.sock.shutdown(socket.SHUT_RDWR)
            self.join(self.timeout)
        self.sock.close()


# ---- 1. memory per connection is bounded ---------------------------------------

# 6 MiB, not the default 16: the bound 40 x 6 MiB + 64 MiB = 304 MiB is
# passed within seconds when whole answers of ~97 MB are queued, yet it
# leaves a fixed daemon room for what a connection holds besides its output
# (the request line as read, about 1 MB, and the request being answered:
# 100,000 wrenches are 2.4 MB as doubles, but a 32 MB cJSON tree).
MAX_OUTPUT = 6 * MIB
SILENT_CLIENTS = 40
SMALL_CONSTANT = 64 * MIB
MEMORY_BOUND = SILENT_CLIENTS * MAX_OUTPUT + SMALL_CONSTANT    # 304 MiB


def big_request_daemon(harness, *extra):
    return harness.start("--max-output", str(MAX_OUTPUT), "--max-line", str(16 * MIB),
                         "--max-wrenches", str(WRENCHES), "--threads", "2", *extra)


def put_fixtures(d):
    setup = d.client()
    eight = setup.result("fixture.put", {"fixture": eight_fixels()})
    assert eight["goal_cones"] >= 1000, eight
    disc = setup.result("fixture.put", {"fixture": FX.disc_corner(0.5)})["id"]
    # derived data built before anything is measured
    setup.result("wrench.classify", {"fixture": eight["id"], "wrenches": [[0, 1, 0]],
                                     "sets": ["goal", "strong", "both"]})
    setup.result("modes.get", {"fixture": eight["id"]})
    setup.result("modes.get", {"fixture": disc})
    setup.close()
    return eight["id"], disc


@pytest.mark.skipif(bool(WRAPPER), reason="40 requests of 100,000 wrenches: too slow under valgrind")
def test_forty_clients_that_never_read_keep_memory_bounded(harness):
    """The scenario: 40 clients each send one wrench.classify of
    100,000 wrenches for goal, strong and both on an 8-fixel fixture (about
    100 MB of answer each) and never read.  Resident memory stays under
    40 x --max-output + 64 MiB (6 MiB here: 304 MiB) while the work
    proceeds, and a 41st client meanwhile gets its answers at its normal
    latency (the work of those who do not read pauses; the event loop and
    the workers stay free for others)."""
    d = big_request_daemon(harness)
    eight, disc = put_fixtures(d)
    small = [("wrench.classify", {"fixture": disc, "wrenches": [[-1, -0.2, 0]]}),
             ("modes.get", {"fixture": eight})]

    # the 41st client's latency with nothing else going on
    base = Observer(d.path, small, pace=0.0)
    base.start()
    while len(base.latencies) < 60 and base.is_alive():
        time.sleep(0.01)
    base.finish()
    assert base.error is None, base.error
    baseline_p50 = statistics.median(base.latencies)

    prefix = big_classify_prefix(eight)
    rss_start = resident_bytes(d.pid)
    cpu_start = cpu_seconds(d.pid)
    silent = []
    sent = threading.Event()
    send_errors = []

    def send_all():
        try:
            for i in range(SILENT_CLIENTS):
                s = raw_socket(d.path, rcvbuf=4096)
                silent.append(s)
                s.sendall(prefix + b"%d}\n" % (1000 + i))
        except BaseException as e:
            send_errors.append(e)
        finally:
            sent.set()

    observer = Observer(d.path, small)
    observer.start()
    sender = threading.Thread(target=send_all, daemon=True)
    t0 = time.monotonic()
    sender.start()
    samples = []          # (seconds since t0, rss bytes, cpu seconds)
    peak = (0, 0.0)
    over = None
    plateau = None
    try:
        while True:
            now = time.monotonic() - t0
            rss, cpu = resident_bytes(d.pid), cpu_seconds(d.pid) - cpu_start
            samples.append((now, rss, cpu))
            if rss > peak[0]:
                peak = (rss, now)
            if not SANITIZED and rss > MEMORY_BOUND:
                over = (rss, now)
                break      # do not let a daemon without the bound eat the machine
            # the work has paused everywhere: CPU time and memory stand still for 2 s
            back = [(r, c) for (t, r, c) in samples if t <= now - 2.0]
            if sent.is_set() and now >= 4.0 and back and cpu - back[-1][1] < 0.25 \
                    and (SANITIZED or rss - back[-1][0] < 8 * MIB):
                plateau = now
                break
            # or enough work to have passed the bound had it been kept: today's
            # daemon passes it after 4-5 s of CPU (on a loaded machine, that
            # is 15 s or more)
            if cpu > 12.0 or now > 45 * SLOW:
                break
            time.sleep(0.2)
    finally:
        if over:
            d.kill()
        observer.finish()
        sender.join(30 * SLOW)
        for s in silent:
            s.close()
    figures = ("peak RSS %.0f MiB at %.1f s (start %.0f MiB, bound %.0f MiB), %s, "
               "CPU %.1f s, 41st client: %d answers, p50 %.1f ms (unloaded %.1f ms), "
               "max %.0f ms (%s)"
               % (peak[0] / MIB, peak[1], rss_start / MIB, MEMORY_BOUND / MIB,
                  "work paused after %.1f s" % plateau if plateau else
                  "no plateau in %.1f s" % samples[-1][0], samples[-1][2],
                  len(observer.latencies),
                  1000 * statistics.median(observer.latencies) if observer.latencies else -1,
                  1000 * baseline_p50, 1000 * observer.worst[0], observer.worst[1]))
    report(figures)
    FIGURES["resources: peak RSS MiB, 40 silent clients"] = peak[0] // MIB
    try:
        check_memory_and_latency(over, send_errors, observer, baseline_p50, figures)
    except AssertionError:
        if d.running():
            d.kill()     # rather than wait for it to finish 40 big answers
        raise


def check_memory_and_latency(over, send_errors, observer, baseline_p50, figures):
    assert not send_errors, send_errors
    if not SANITIZED:
        assert over is None, (
            "resident memory passed 40 x max-output + 64 MiB = %d MiB: %.0f MiB after %.1f s; "
            "%s" % (MEMORY_BOUND // MIB, over[0] / MIB, over[1], figures))
    assert observer.error is None, "the 41st client: %r; %s" % (observer.error, figures)
    assert len(observer.latencies) >= 20, figures
    p50 = statistics.median(observer.latencies)
    # 5 x its unloaded median (well under 1 ms here), at least 50 ms: a
    # request queued behind one of the big ones waits seconds.
    assert p50 < max(5 * baseline_p50, 0.05) * SLOW, figures
    assert observer.worst[0] < 1.0 * SLOW, figures


IDLE_TIMEOUT = 3


@pytest.mark.skipif(bool(WRAPPER), reason="requests of 100,000 wrenches: too slow under valgrind")
def test_a_client_that_leaves_output_unread_is_closed_after_the_idle_timeout(harness):
    """With --idle-timeout 3, eight clients that send a 100,000-wrench
    classify and never read are closed once their output has stood unread
    for 3 s (not before: none is closed within 3 s of its request), the
    daemon's memory falls back near where it started, and each socket then
    reads to its end (EOF or a reset)."""
    d = big_request_daemon(harness, "--idle-timeout", str(IDLE_TIMEOUT))
    eight, _ = put_fixtures(d)
    watcher = d.client()
    assert watcher.result("server.status")["clients"] == 1
    prefix = big_classify_prefix(eight)
    rss_start = resident_bytes(d.pid)
    silent = []
    try:
        for i in range(8):
            s = raw_socket(d.path, rcvbuf=4096)
            silent.append(s)
            s.sendall(prefix + b"%d}\n" % i)
        sent = time.monotonic()
        # all eight accepted (connect() returns before the daemon accepts)
        deadline = sent + 5 * SLOW
        while watcher.result("server.status")["clients"] < 9:
            assert time.monotonic() < deadline, "the eight clients were not all accepted"
            time.sleep(0.02)
        deadline = sent + IDLE_TIMEOUT + 10 * SLOW
        clients, peak = None, 0
        while time.monotonic() < deadline:
            clients = watcher.result("server.status")["clients"]
            rss = resident_bytes(d.pid)
            peak = max(peak, rss)
            if clients == 1 or (not SANITIZED and rss > 1024 * MIB):
                break
            time.sleep(0.2)
        closed_after = time.monotonic() - sent
        report("silent clients: %s left after %.1f s, peak RSS %.0f MiB (start %.0f MiB)"
               % (clients - 1, closed_after, peak / MIB, rss_start / MIB))
        assert clients == 1, (
            "%d of the 8 clients that leave their output unread are still connected %.1f s "
            "after their requests (--idle-timeout %d); peak RSS %.0f MiB"
            % (clients - 1, closed_after, IDLE_TIMEOUT, peak / MIB))
        assert closed_after >= IDLE_TIMEOUT - 0.5, (
            "closed %.1f s after their requests: before --idle-timeout %d"
            % (closed_after, IDLE_TIMEOUT))
        for s in silent:
            assert closed_by_peer(s, 10 * SLOW), "a silent client's socket is still open"
        if not SANITIZED:
            deadline = time.monotonic() + 5 * SLOW
            while resident_bytes(d.pid) > rss_start + SMALL_CONSTANT \
                    and time.monotonic() < deadline:
                time.sleep(0.1)
            rss = resident_bytes(d.pid)
            report("RSS after the close %.0f MiB" % (rss / MIB))
            assert rss <= rss_start + SMALL_CONSTANT, (
                "RSS %.0f MiB after the silent clients were closed, %.0f MiB at the start"
                % (rss / MIB, rss_start / MIB))
    except BaseException:
        if d.running():
            d.kill()
        raise
    finally:
        for s in silent:
            s.close()


@pytest.mark.skipif(bool(WRAPPER), reason="15,000 wrenches and 15 MB: too slow under valgrind")
def test_a_slow_steady_reader_gets_an_answer_larger_than_max_output(harness):
    """The other side of the bound (today's daemon passes this): a client
    that reads slowly but steadily, 256 KiB every 20 ms, gets the whole of
    one answer of about 14.5 MB (15,000 wrenches, 2.3 x --max-output): it
    is neither dropped for it nor closed by --idle-timeout 3 before the
    answer's end."""
    d = big_request_daemon(harness, "--idle-timeout", str(IDLE_TIMEOUT))
    eight, _ = put_fixtures(d)
    count = 15000
    reader = raw_socket(d.path, rcvbuf=4096)
    reader.sendall(big_classify_prefix(eight, count, seed=7) + b"7}\n")
    parts = []
    start = time.monotonic()
    reader.settimeout(IDLE_TIMEOUT * 2 * SLOW)
    while not (parts and parts[-1].endswith(b"\n")):
        chunk = reader.recv(256 * KIB)
        assert chunk, "the slow reader was closed after %d bytes" % sum(map(len, parts))
        parts.append(chunk)
        time.sleep(0.02)
    data = b"".join(parts)
    report("slow reader: %d bytes in %.1f s" % (len(data), time.monotonic() - start))
    assert len(data) > 2 * MAX_OUTPUT
    answer = json.loads(data)
    assert answer["id"] == 7 and len(answer["result"]["results"]) == count, str(answer)[:300]
    assert all(set(r) == {"goal", "strong", "both"} for r in answer["result"]["results"])
    reader.close()


# ---- 2. work for a client that is gone stops; clients share the workers ----------

BATCH = 100


def push_batch(fixture_id, first_id):
    """One batch line of 100 push.regions (set strong, finger friction 0.2
    to 0.299: no two alike, nothing to share between them)."""
    batch = [{"jsonrpc": "2.0", "method": "push.regions",
              "params": {"fixture": fixture_id, "set": "strong",
                         "finger_friction": round(0.2 + 0.001 * i, 3)},
              "id": first_id + i} for i in range(BATCH)]
    return (json.dumps(batch, separators=(",", ":")) + "\n").encode()


def outline_daemon(harness):
    d = harness.start("--threads", "2")
    setup = d.client()
    outline = setup.result("fixture.put", {"fixture": large_outline()})
    disc = setup.result("fixture.put", {"fixture": FX.disc_corner(0.5)})["id"]
    # the cones, so that the batches start computing at once; and a cheap
    # push.regions (no finger friction: exact) to check the fixture
    r = setup.result("push.regions", {"fixture": outline["id"], "set": "strong"})
    assert r["regions"] and r["exact"], str(r)[:300]
    setup.result("modes.get", {"fixture": disc})
    setup.close()
    return d, outline["id"], disc


def cheap_requests(disc):
    """What the third client asks: modes.get of a stored fixture, and a
    classify of one wrench by an inline fixture (both worker requests)."""
    return [("modes.get", {"fixture": disc}),
            ("wrench.classify", {"fixture": FX.disc_corner(0.4, name="inline"),
                                 "wrenches": [[-1, -0.2, 0]]})]


def wait_for_cpu(pid, seconds, timeout):
    """Wait until the daemon has used `seconds` more CPU time: the work sent
    is really running."""
    start = cpu_seconds(pid)
    deadline = time.monotonic() + timeout
    while cpu_seconds(pid) - start < seconds:
        assert time.monotonic() < deadline, (
            "the daemon used only %.2f s of CPU in %.0f s: the batches are not running"
            % (cpu_seconds(pid) - start, timeout))
        time.sleep(0.05)


def test_work_of_clients_that_disconnect_stops(harness):
    """The scenario: two clients each send one batch of 100
    push.regions with finger_friction on a 4000-vertex outline (about 2.5 s
    of a core each, over 4 minutes of work per batch) and disconnect.  A
    third client's modes.get and classify are answered within 1 s, and
    from 1 s after the disconnects the daemon uses under 0.3 s of CPU in
    2 s: the running requests stopped within a bounded amount of work
    (between edges), the queued ones were cancelled."""
    d, outline, disc = outline_daemon(harness)
    try:
        gone = [raw_socket(d.path) for _ in range(2)]
        for n, s in enumerate(gone):
            s.sendall(push_batch(outline, 1000 * (n + 1)))
        wait_for_cpu(d.pid, 0.4, 10 * SLOW)   # both batches computing
        for s in gone:
            s.close()
        disconnected = time.monotonic()

        third = raw_socket(d.path)
        reader = LineReader(third)
        waits = []
        for i, (method, params) in enumerate(cheap_requests(disc) * 2):
            try:
                took, _ = timed_call(third, reader, method, params, i, 5 * SLOW)
            except socket.timeout:
                raise AssertionError("the third client's %s was not answered within %.0f s "
                                     "of the disconnects" % (method, 5 * SLOW)) from None
            waits.append((took, method))
        report("third client after the disconnects: %s"
               % ", ".join("%s %.0f ms" % (m, 1000 * t) for t, m in waits))
        assert max(waits)[0] < 1.0 * SLOW, waits

        grace_end = disconnected + 1.0 * SLOW
        while time.monotonic() < grace_end:
            time.sleep(0.05)
        before = cpu_seconds(d.pid)
        time.sleep(2.0)           # the window measured
        used = cpu_seconds(d.pid) - before
        report("CPU used 1-3 s after the disconnects: %.2f s" % used)
        FIGURES["resources: CPU ms after disconnect"] = int(1000 * used)
        assert used < 0.3 * SLOW, (
            "the daemon used %.2f s of CPU in the 2 s from 1 s after both clients left: "
            "their work goes on" % used)
    except BaseException:
        d.kill()   # the old daemon would compute for minutes
        raise


def test_a_backlog_does_not_delay_another_clients_cheap_request(harness):
    """Fairness, not cancellation: two clients stay connected, each with a
    batch of 100 slow push.regions queued (as many as --threads 2), and the
    workers stay busy with them; a third client's modes.get and classify
    are each answered within 1 s (workers take work round-robin across
    connections in pieces of bounded cost)."""
    d, outline, disc = outline_daemon(harness)
    try:
        busy = [raw_socket(d.path) for _ in range(2)]
        for n, s in enumerate(busy):
            s.sendall(push_batch(outline, 1000 * (n + 1)))
        wait_for_cpu(d.pid, 0.4, 10 * SLOW)

        third = raw_socket(d.path)
        reader = LineReader(third)
        waits = []
        cpu_before, start = cpu_seconds(d.pid), time.monotonic()
        for i, (method, params) in enumerate(cheap_requests(disc) * 4):
            try:
                took, _ = timed_call(third, reader, method, params, i, 5 * SLOW)
            except socket.timeout:
                raise AssertionError("the third client's %s was not answered within %.0f s "
                                     "behind the backlogs" % (method, 5 * SLOW)) from None
            waits.append((took, method))
            time.sleep(0.3)       # spread over a few seconds of the backlog
        busy_share = (cpu_seconds(d.pid) - cpu_before) / (time.monotonic() - start)
        report("third client behind two backlogs: %s; daemon CPU %.2f cores"
               % (", ".join("%s %.0f ms" % (m, 1000 * t) for t, m in waits), busy_share))
        FIGURES["resources: worst cheap wait ms behind a backlog"] = int(1000 * max(waits)[0])
        assert max(waits)[0] < 1.0 * SLOW, waits
        # the backlogs were worked on meanwhile (the test measured something;
        # on a machine shared with others, well under the 2 cores it could use)
        assert busy_share > 0.1, busy_share
        for s in busy:
            s.close()
    except BaseException:
        d.kill()
        raise


# ---- 3. a request must arrive whole within --request-timeout ---------------------

REQUEST_TIMEOUT = 2


def status_request(id):
    return rpc_line("server.status", {}, id)


def send_in_pieces(sock, pieces, spacing):
    """Send `pieces`, `spacing` seconds apart (the first at once)."""
    for n, piece in enumerate(pieces):
        if n:
            time.sleep(spacing)
        sock.sendall(piece)


def test_a_request_must_arrive_within_the_request_timeout(harness):
    """With --request-timeout 2 and --idle-timeout 60: a client that drips
    one byte of a request every 0.5 s is closed 2 s (plus slack) after its
    first byte, well before the idle timeout, with at most one -32600 error
    line first; a request sent in pieces over 1.5 s is answered; the timer
    is per request (two requests in a row, the second's first bytes in the
    same write as the first's newline, each arriving over 1.5 s, are both
    answered); connections that are merely quiet (after an answer, or
    since connecting) are left alone."""
    d = harness.start("--request-timeout", str(REQUEST_TIMEOUT), "--idle-timeout", "60")
    quiet_after_answer = d.client()
    assert "result" in quiet_after_answer.call("server.status")
    quiet_since_connect = d.client()
    quiet_since = time.monotonic()

    # the drip
    drip = raw_socket(d.path)
    request = status_request(1)
    first_byte = None
    received = b""
    closed_at = None
    limit = REQUEST_TIMEOUT + 2.0 * SLOW
    for i in range(len(request)):
        try:
            drip.sendall(request[i:i + 1])
        except (BrokenPipeError, ConnectionResetError):
            closed_at = time.monotonic()
            break
        if first_byte is None:
            first_byte = time.monotonic()
        pause_end = time.monotonic() + 0.5
        while closed_at is None and time.monotonic() < pause_end:
            drip.settimeout(max(0.01, pause_end - time.monotonic()))
            try:
                chunk = drip.recv(4096)
            except socket.timeout:
                break
            except ConnectionResetError:
                chunk = b""
            if not chunk:
                closed_at = time.monotonic()
            received += chunk
        if closed_at is not None or time.monotonic() - first_byte > limit:
            break
    drip.close()
    lasted = (closed_at or time.monotonic()) - first_byte
    report("drip: %s %.1f s after its first byte (%d bytes sent), received %r"
           % ("closed" if closed_at else "still open", lasted, i + 1, received[:200]))
    assert closed_at is not None, (
        "a client dripping one byte every 0.5 s is still connected %.1f s after its first "
        "byte (--request-timeout %d)" % (lasted, REQUEST_TIMEOUT))
    assert REQUEST_TIMEOUT - 0.2 <= lasted <= limit, lasted
    if received:
        lines = received.split(b"\n")
        assert len(lines) == 2 and lines[1] == b"", "at most one line before the close: %r" % received
        answer = json.loads(lines[0])
        assert answer.get("jsonrpc") == "2.0" and answer.get("id") is None, answer
        assert answer["error"]["code"] == -32600, answer

    # slow, but whole in time: 3 pieces over 1.5 s
    slow = raw_socket(d.path)
    reader = LineReader(slow)
    request = status_request(2)
    third = len(request) // 3
    send_in_pieces(slow, [request[:third], request[third:2 * third], request[2 * third:]], 0.75)
    answer = json.loads(reader.line(5 * SLOW))
    assert answer["id"] == 2 and "result" in answer, answer

    # two in a row: 3 s from the first byte of the first to the end of the
    # second, 1.5 s each
    one, two = status_request(3), status_request(4)
    half = len(one) // 2
    send_in_pieces(slow, [one[:half], one[half:-5], one[-5:] + two[:half], two[half:-5],
                          two[-5:]], 0.75)
    for id in (3, 4):
        answer = json.loads(reader.line(5 * SLOW))
        assert answer["id"] == id and "result" in answer, answer
    slow.close()

    # quiet connections are the idle timeout's business, not this one's
    assert time.monotonic() - quiet_since > REQUEST_TIMEOUT + 1
    assert "result" in quiet_after_answer.call("server.status")
    assert "result" in quiet_since_connect.call("server.status")


def test_help_and_config_know_the_request_timeout(harness):
    """--help lists --request-timeout with its default (30 s), and the
    configuration file takes request-timeout like every other option."""
    out = harness.run("--help")
    assert out.returncode == 0
    text = out.stdout.decode()
    m = re.search(r"^\s*--request-timeout\b.*?(?=^\s*--|\Z)", text, re.M | re.S)
    assert m, "--help does not list --request-timeout:\n" + text
    assert "30" in m.group(0), m.group(0)
    conf = harness.path("wrenchd.conf")
    with open(conf, "w") as f:
        f.write("request-timeout = 5\n")
    d = harness.start("--config", conf)
    assert "result" in d.client().call("server.status")


# ---- 4. friction.sweep is long work too ---------------------------------------------

def sweep_batch(fixture_id, first_id, count=6):
    """One batch line of friction.sweep push sweeps of the eight-fixel disc
    with a finger with friction (1024 goal cones; 256 steps of mu, at each
    push regions sampled all round: seconds each), no two alike."""
    batch = [{"jsonrpc": "2.0", "method": "friction.sweep",
              "params": {"fixture": fixture_id, "range": [0, 1.0 + 0.01 * i],
                         "push": {"set": "goal", "finger_friction": 0.1}},
              "id": first_id + i} for i in range(count)]
    return (json.dumps(batch, separators=(",", ":")) + "\n").encode()


def test_sweeps_share_the_workers_and_stop_with_their_clients(harness):
    """Two clients each send a batch of long friction.sweep requests: a
    third client's cheap requests are answered within 1 s while both run
    (a sweep is worked a piece at a time, wr_sweep.h's jobs); when the two
    disconnect, the daemon stops their work: under 0.3 s of CPU in the 2 s
    from 1 s after."""
    d = harness.start("--threads", "2")
    try:
        setup = d.client()
        eight = setup.result("fixture.put", {"fixture": eight_fixels()})["id"]
        disc = setup.result("fixture.put", {"fixture": FX.disc_corner(0.5)})["id"]
        setup.result("modes.get", {"fixture": disc})
        setup.close()
        busy = [raw_socket(d.path) for _ in range(2)]
        for n, s in enumerate(busy):
            s.sendall(sweep_batch(eight, 1000 * (n + 1)))
        wait_for_cpu(d.pid, 0.4, 10 * SLOW)

        third = raw_socket(d.path)
        reader = LineReader(third)
        waits = []
        for i, (method, params) in enumerate(cheap_requests(disc) * 3):
            took, _ = timed_call(third, reader, method, params, i, 5 * SLOW)
            waits.append((took, method))
            time.sleep(0.2)
        report("third client behind two sweep batches: %s"
               % ", ".join("%s %.0f ms" % (m, 1000 * t) for t, m in waits))
        FIGURES["resources: worst cheap wait ms behind sweeps"] = int(1000 * max(waits)[0])
        assert max(waits)[0] < 1.0 * SLOW, waits

        for s in busy:
            s.close()
        time.sleep(1.0 * SLOW)
        before = cpu_seconds(d.pid)
        time.sleep(2.0)
        used = cpu_seconds(d.pid) - before
        report("CPU used 1-3 s after the sweeping clients left: %.2f s" % used)
        assert used < 0.3 * SLOW, used
    except BaseException:
        d.kill()
        raise


def design_request(id, spacing=0.5):
    """A design on a 12-sided plate: spacing 0.5 gives about 82,000
    candidates, 0.25 about 680,000."""
    body = {"mass": 1, "shape": {"type": "polygon", "vertices": [
        [1, 0], [11, 0], [12, 1], [12, 7], [11, 8], [7, 8], [7, 6], [5, 6], [5, 8], [1, 8],
        [0, 7], [0, 1]]}}
    return rpc_line("fixture.design", {"body": body, "friction": 0.25, "spacing": spacing,
                                       "top": 3}, id)


def test_a_design_uses_every_worker_shares_them_and_stops_with_its_client(harness):
    """One design on a daemon with two workers keeps both busy (its pieces
    queue a helper for the other worker); a second client's cheap requests
    meanwhile wait at most one piece (under 1 s); the answer is the one a
    single worker gives, byte for byte; and when the client leaves, the
    work stops (under 0.3 s of CPU in the 2 s from 1 s after)."""
    smaller = design_request(1, spacing=1)
    alone, = answers_of_one_worker(harness, [smaller], 60)
    d = harness.start("--threads", "2")
    try:
        s = raw_socket(d.path)
        s.sendall(smaller)
        assert LineReader(s).line(60 * SLOW) == alone
        s.close()

        busy = raw_socket(d.path)
        busy.sendall(design_request(2, spacing=0.25))  # about a minute of one core
        time.sleep(0.5)
        cores, used = busy_threads(d.pid, 3.0, "one design")
        FIGURES["design: CPU percent with one design on 2 workers"] = int(100 * cores)
        # Both workers work on it: the second busiest thread used at least
        # half what the busiest did (on a quiet machine the two add up to
        # about 1.8 cores; a loaded one gives less to both, alike).
        assert used[1] >= 0.5 * used[0] > 0, used

        disc = FX.disc_corner(0.5)
        third = raw_socket(d.path)
        reader = LineReader(third)
        waits = []
        for i, (method, params) in enumerate(cheap_requests(disc) * 3):
            took, _ = timed_call(third, reader, method, params, 100 + i, 5 * SLOW)
            waits.append((took, method))
            time.sleep(0.1)
        FIGURES["resources: worst cheap wait ms behind a design"] = int(1000 * max(waits)[0])
        assert max(waits)[0] < 1.0 * SLOW, waits

        busy.close()
        time.sleep(1.0 * SLOW)
        before = cpu_seconds(d.pid)
        time.sleep(2.0)
        used = cpu_seconds(d.pid) - before
        report("CPU used 1-3 s after the designing client left: %.2f s" % used)
        assert used < 0.3 * SLOW, used
    except BaseException:
        d.kill()
        raise


def test_a_client_that_half_closes_then_hangs_up_is_noticed(harness):
    """A client sends a long design, shuts its sending side, then closes
    the socket: no event says the second part (the input ended before), so
    the daemon asks at every piece.  The work stops and the slot is freed
    within a second or two (found by a review helper: the slot was held
    until --max-clients ran out)."""
    d = harness.start("--threads", "2")
    try:
        status = d.client()
        for i in range(3):
            s = raw_socket(d.path)
            s.sendall(design_request(10 + i, spacing=0.25))
            s.shutdown(socket.SHUT_WR)
            time.sleep(0.3)
            s.close()
        deadline = time.monotonic() + 5 * SLOW
        while time.monotonic() < deadline:
            if status.result("server.status", {})["clients"] == 1:
                break
            time.sleep(0.1)
        assert status.result("server.status", {})["clients"] == 1
        time.sleep(0.5)
        before = cpu_seconds(d.pid)
        time.sleep(2.0)
        used = cpu_seconds(d.pid) - before
        report("CPU in the 2 s after three half-closed, then closed, designing clients: %.2f s"
               % used)
        assert used < 0.3 * SLOW, used
    except BaseException:
        d.kill()
        raise


def classify_request(id, count, fields=None, method=None, seed=1):
    rng = random.Random(seed)
    params = {"fixture": FX.rectangle_321(0.3),
              "wrenches": [[rng.uniform(-1, 1) for _ in range(3)] for _ in range(count)]}
    if fields:
        params["fields"] = fields
    if method:
        params["method"] = method
    return rpc_line("wrench.classify", params, id)


def test_a_batch_uses_every_worker_and_answers_the_same_bytes(harness):
    """One long wrench.classify on a daemon with two workers keeps both busy
    (its chunks are made by a helper on the other worker too) and answers
    byte for byte what one worker answers, lean and by rows; a second
    client's cheap requests meanwhile wait at most a piece."""
    requests = [classify_request(1, 30000, ["verdict", "margin", "states"]),
                classify_request(2, 150000 // 2, ["verdict"]),
                classify_request(3, 2000),
                # By LP only the verdicts: a witness is whichever vertex the
                # thread's warm simplex reaches first.
                classify_request(4, 300, ["verdict", "blocking"], "lp")]
    answers = answers_of_one_worker(harness, requests, 120)
    d = harness.start("--threads", "2")
    try:
        s = raw_socket(d.path)
        reader = LineReader(s)
        for r, alone in zip(requests, answers):
            s.sendall(r)
            assert reader.line(120 * SLOW) == alone
        s.close()

        # Busy: LP verdicts (tens of microseconds each), a dozen batches
        # pipelined on one connection, each split across both workers.
        busy = raw_socket(d.path)
        batches = 12
        for i in range(batches):
            busy.sendall(classify_request(100 + i, 20000, ["verdict"], "lp", seed=i))
        wait_for_cpu(d.pid, 0.3, 30 * SLOW)
        cores, used = busy_threads(d.pid, 1.5, "one classify batch")
        FIGURES["classify: CPU percent with one batch on 2 workers"] = int(100 * cores)
        # Both workers on it: the second busiest thread used at least half
        # what the busiest did (a connection's requests are answered one at
        # a time, so only the split can make the second work).
        assert used[1] >= 0.5 * used[0] > 0, used

        third = raw_socket(d.path)
        treader = LineReader(third)
        disc = FX.disc_corner(0.5)
        waits = []
        for i, (method, params) in enumerate(cheap_requests(disc) * 2):
            took, _ = timed_call(third, treader, method, params, 200 + i, 5 * SLOW)
            waits.append(took)
        FIGURES["resources: worst cheap wait ms behind a classify batch"] = int(1000 * max(waits))
        assert max(waits) < 1.0 * SLOW, waits

        busy_reader = LineReader(busy)
        for i in range(batches):
            answer = json.loads(busy_reader.line(120 * SLOW))
            assert answer["id"] == 100 + i and answer["result"]["count"] == 20000, answer
        busy.close()
        third.close()
    except BaseException:
        d.kill()
        raise
