"""Hostile clients and hostile configurations, second round: descriptors,
parse trees, hang-ups while reading is paused, empty allow lists, memory
running out while a line is parsed, fairness between users, the state
directory's lock and the socket file a daemon made.

Every test starts its own daemons and talks to them over Unix sockets only.
Thresholds are properties of the daemon (lines logged, CPU it spends, bytes
it holds) with wide margins, not of how loaded the machine is."""

import json
import math
import os
import struct
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
    """Connect, ask server.status, return the answer (raises on failure).
    The connect blocks (at most `timeout`, SO_SNDTIMEO) while the listen
    backlog is full, as a blocking client's does."""
    with socket.socket(socket.AF_UNIX, socket.SOCK_STREAM) as s:
        whole, part = int(timeout), int((timeout - int(timeout)) * 1e6)
        s.setsockopt(socket.SOL_SOCKET, socket.SO_SNDTIMEO, struct.pack("ll", whole, part))
        s.connect(path)
        s.settimeout(timeout)
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


# ---- descriptors ---------------------------------------------------------------------

# Run as nobody: hold up to COUNT connections to the daemon, each dripping a
# byte every 0.7 s (which restarted a refused connection's linger), opening
# new ones for those closed every 0.7 s, for SECONDS.
DRIPPER = r"""
import os, resource, select, socket, sys, time
path, count, seconds = sys.argv[1], int(sys.argv[2]), float(sys.argv[3])
os.setgroups([]); os.setgid(65534); os.setuid(65534)
soft, hard = resource.getrlimit(resource.RLIMIT_NOFILE)
resource.setrlimit(resource.RLIMIT_NOFILE, (min(hard, count + 64), hard))
socks, opened, end = [], 0, time.monotonic() + seconds
last_drip = 0.0
while time.monotonic() < end:
    while len(socks) < count and time.monotonic() - last_drip >= 0.7:
        s = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
        s.setblocking(False)
        try:
            s.connect(path)
        except (BlockingIOError, InterruptedError):
            pass
        except OSError:
            s.close()
            break
        socks.append(s)
        opened += 1
    if time.monotonic() - last_drip >= 0.7:
        last_drip = time.monotonic()
        alive = []
        for s in socks:
            try:
                s.send(b"x")
                alive.append(s)
            except OSError:
                s.close()
        socks = alive
    poller = select.poll()
    for s in socks:
        poller.register(s, select.POLLIN)
    byfd = {s.fileno(): s for s in socks}
    for fd, _ in poller.poll(50):
        s = byfd[fd]
        try:
            data = s.recv(4096)
        except OSError:
            data = b""
        if not data:
            socks.remove(s)
            s.close()
print(opened)
"""


@needs_root
@pytest.mark.skipif(shutil.which("prlimit") is None, reason="needs prlimit")
@pytest.mark.skipif(SANITIZED, reason="timing of connections under a sanitizer")
def test_denied_peers_cannot_exhaust_descriptors(harness):
    """1,300 connections from a denied uid, each dripping a byte every 0.7 s,
    against a daemon limited to 1,024 descriptors: the daemon never holds
    more than 200 descriptors, an allowed client (root) connects and is
    answered within 1 s on every one of 24 tries, and the log stays under
    100 lines."""
    d = harness.start("--allow-uid", "0")
    open_to_everyone(harness, d)
    subprocess.run(["prlimit", "--pid", str(d.pid), "--nofile=1024:1024"], check=True)
    attacker = subprocess.Popen([sys.executable, "-c", DRIPPER, d.path, "1300", "14"],
                                stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    try:
        time.sleep(3)  # the attack at full strength
        slow, descriptors = [], []
        for attempt in range(24):
            descriptors.append(len(os.listdir("/proc/%d/fd" % d.pid)))
            start = time.monotonic()
            try:
                answer = ask_status(d.path, 1.0)
                assert "result" in answer, answer
            except (OSError, ValueError) as e:
                slow.append("try %d: %r" % (attempt, e))
            else:
                took = time.monotonic() - start
                if took >= 1.0:
                    slow.append("try %d: %.2f s" % (attempt, took))
            time.sleep(0.3)
    finally:
        out, err = attacker.communicate(timeout=60)
    assert attacker.returncode == 0, err
    assert int(out) > 1300, "the attack opened only %s connections" % out
    assert not slow, "the allowed client was kept out: %s" % slow
    # Refused peers hold few descriptors (at most 64 linger), not the limit.
    assert max(descriptors) < 200, descriptors
    status = ask_status(d.path, 10 * SLOW)["result"]
    assert status["denied"] > 1300
    lines = d.stderr().count("\n")
    assert lines < 100, "%d log lines:\n%s" % (lines, d.stderr()[-2000:])


@pytest.mark.skipif(shutil.which("prlimit") is None, reason="needs prlimit")
def test_out_of_descriptors_accepting_pauses_and_logs_once(harness):
    """A daemon limited to 64 descriptors with 120 clients connected (the
    rest wait in the listen backlog): it neither spins on accept (under 0.5
    CPU-seconds in 3 s) nor floods the log (under 10 lines); once clients
    leave, a waiting one is answered."""
    d = harness.start("--max-clients", "1000")
    subprocess.run(["prlimit", "--pid", str(d.pid), "--nofile=64:64"], check=True)
    held = []
    for _ in range(120):
        s = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
        s.setblocking(False)
        try:
            s.connect(d.path)
        except BlockingIOError:
            s.close()
            break
        held.append(s)
    assert len(held) >= 100
    time.sleep(0.5)
    before = cpu_seconds(d.pid)
    time.sleep(3)
    spent = cpu_seconds(d.pid) - before
    assert spent < 0.5 * SLOW, "%.2f CPU-seconds while out of descriptors" % spent
    lines = d.stderr().count("\n")
    assert lines < 10, d.stderr()[-2000:]
    assert "Too many open files" in d.stderr()
    for s in held[:80]:
        s.close()
    # The last one waited in the backlog all along: it is accepted now.
    held[-1].setblocking(True)
    held[-1].settimeout(10 * SLOW)
    held[-1].sendall(status_line())
    assert "result" in json.loads(held[-1].makefile("rb").readline())
    for s in held[80:]:
        s.close()


# ---- hang-ups while reading is paused ------------------------------------------------

def long_request(kind, put_id):
    """A request that takes a core for a minute or more."""
    from test_resources import design_request, sweep_batch
    if kind == "design":
        return design_request(1, spacing=0.25)
    return sweep_batch(put_id, 1, count=4)


def many_lines(count=1100):
    return b"".join(status_line(100 + i) for i in range(count))


def two_long_lines():
    pad = b"x" * (9 << 20)
    return b"".join(b'{"jsonrpc":"2.0","method":"server.status","params":{"pad":"' + pad +
                    b'"},"id":%d}\n' % i for i in (7, 8))


@pytest.mark.parametrize("kind,then", [("design", "lines"), ("design", "long lines"),
                                       ("sweep", "lines"), ("sweep", "long lines")])
def test_a_hang_up_is_noticed_while_reading_is_paused(harness, kind, then):
    """A long design or friction.sweep, then 1,100 more lines (or two 9 MiB
    lines), so that reading pauses; then the client hangs up.  The work
    stops: under 0.1 CPU-seconds in the 2 s from 0.3 s after the hang-up."""
    from test_resources import eight_fixels
    d = harness.start("--threads", "2")
    setup = d.client()
    eight = setup.result("fixture.put", {"fixture": eight_fixels()})["id"]
    setup.close()
    s = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
    s.settimeout(30 * SLOW)
    s.connect(d.path)
    s.sendall(long_request(kind, eight))
    time.sleep(0.3)
    more = many_lines() if then == "lines" else two_long_lines()
    s.setblocking(False)
    sent = 0
    deadline = time.monotonic() + 10 * SLOW
    while sent < len(more) and time.monotonic() < deadline:
        try:
            sent += s.send(more[sent:sent + (1 << 20)])
        except BlockingIOError:
            time.sleep(0.01)
    assert sent > 0
    time.sleep(0.5)
    start = cpu_seconds(d.pid)
    assert start > 0.2, "the long request did not start"
    s.close()
    time.sleep(0.3)
    before = cpu_seconds(d.pid)
    time.sleep(2.0)
    used = cpu_seconds(d.pid) - before
    assert used < 0.1 * SLOW, "%.2f CPU-seconds after the hang-up" % used
    status = ask_status(d.path, 10 * SLOW)["result"]
    assert status["clients"] == 1, status


# ---- out of memory while parsing -------------------------------------------------------

def vm_size(pid):
    with open("/proc/%d/status" % pid) as f:
        for line in f:
            if line.startswith("VmSize:"):
                return int(line.split()[1]) << 10
    return 0


@pytest.mark.skipif(shutil.which("prlimit") is None, reason="needs prlimit")
@pytest.mark.skipif(SANITIZED, reason="a sanitizer's allocator reserves its own address space")
@pytest.mark.parametrize("id_text", [b'"big"', b"12345678901234567890", None])
def test_a_valid_line_out_of_memory_while_parsed_is_an_internal_error(harness, id_text):
    """With its address space capped (prlimit --as) 64 MiB above what it
    uses, the daemon is sent a valid line whose tree needs more (server.status
    with 1.5 million numbers in params, a 3 MB line): -32603, under the
    request's id as written (null when it has none), not -32700; the next
    request is answered.  One malloc arena (MALLOC_ARENA_MAX=1): glibc gives
    a thread its own arena when it first allocates, mapping 128 MiB of address
    space to align a 64 MiB heap, which under the cap would fail whichever
    read or parse came next (which one depends on timing), not the tree's."""
    d = harness.start("--threads", "1", env=dict(os.environ, MALLOC_ARENA_MAX="1"))
    c = d.client()
    c.result("server.status")
    limit = vm_size(d.pid) + (64 << 20)
    subprocess.run(["prlimit", "--pid", str(d.pid), "--as=%d:%d" % (limit, limit)], check=True)
    numbers = b",".join([b"0"] * 1500000)
    line = b'{"jsonrpc":"2.0","method":"server.status","params":[' + numbers + b"]"
    line += (b',"id":' + id_text if id_text else b"") + b"}"
    c.send_line(line)
    answer = c.read_json()
    assert answer["error"]["code"] == -32603, answer
    assert "out of memory" in answer["error"]["data"]["reason"]
    expected = json.loads(id_text) if id_text else None
    assert answer["id"] == expected, answer
    if id_text and id_text[0:1] != b'"':
        assert c.buf == b"" and json.dumps(answer["id"]).encode() == id_text
    assert "result" in c.call("server.status")


# ---- numerical edges -------------------------------------------------------------------

def disc_with_normal(normal):
    f = json.loads(json.dumps(DISC))
    f["fixels"][0]["normal"] = normal
    return f


@pytest.mark.parametrize("normal", [[1.3e308, 1.3e308], [1.7e308, 1.7e308], [5e-324, 5e-324],
                                    [1e-310, 1e-310], [3e-200, 3e-200], [1.2e308, 1.2e308]])
def test_a_normal_is_scaled_before_it_is_normalised(harness, normal):
    """Huge, tiny and subnormal normals along (1, 1) are accepted and stored
    unit, along (1, 1) to an ulp; the id follows the stored value: the
    stored fixture put again has the same id, and one whose stored normal
    is the same bits as (1, 1)'s has (1, 1)'s id."""
    d = harness.start()
    c = d.client()
    # The disc's fixel at (-1, 0) takes any normal into the disc.
    reference = c.result("fixture.put", {"fixture": disc_with_normal([1, 1])})
    reference_normal = c.result("fixture.get", {"id": reference["id"]})["fixels"][0]["normal"]
    answer = c.call("fixture.put", {"fixture": disc_with_normal(normal)})
    assert "result" in answer, answer
    stored = c.result("fixture.get", {"id": answer["result"]["id"]})
    n = stored["fixels"][0]["normal"]
    assert abs(n[0] - 2 ** -0.5) < 2e-16 and abs(n[1] - 2 ** -0.5) < 2e-16, n
    assert abs(math.hypot(*n) - 1) < 4e-16, n
    again = c.result("fixture.put", {"fixture": stored})
    assert again["id"] == answer["result"]["id"]
    assert (answer["result"]["id"] == reference["id"]) == (n == reference_normal), (n, reference_normal)


def test_a_witness_of_a_wrench_near_the_largest_double_is_finite(harness):
    """A wrench (1.7e308, 1.7e308, 1.7e308), outside the disc's cones: its
    witness is the witness of (1, 1, 1) times 1.7e308 (cones are cones),
    numbers, not nulls; by cones and by LP."""
    d = harness.start()
    c = d.client()
    for method in ("auto", "lp"):
        params = {"fixture": DISC, "sets": ["goal"], "method": method}
        big = c.result("wrench.classify", dict(params, wrenches=[[1.7e308] * 3]))["results"][0]["goal"]
        one = c.result("wrench.classify", dict(params, wrenches=[[1, 1, 1]]))["results"][0]["goal"]
        assert big["verdict"] == one["verdict"], (big, one)
        if "witness" not in one:
            continue

        def numbers(w):
            out = []
            for key in sorted(w):
                v = w[key]
                if isinstance(v, list):
                    out += [x for item in v for x in (item if isinstance(item, list) else [item])]
            return out
        wb, wo = numbers(big["witness"]), numbers(one["witness"])
        assert len(wb) == len(wo)
        finite = 0
        for x, y in zip(wb, wo):
            if y is None or abs(1.7e308 * y) > 1.797e308:
                assert x is None, (method, x, y)   # beyond a double, or none for (1, 1, 1)
            else:
                assert x is not None and abs(x - 1.7e308 * y) <= 1e-9 * 1.7e308 * max(1.0, abs(y)), (
                    method, x, y, big["witness"])
                finite += 1
        assert finite >= 4, big["witness"]


# ---- memory: parse trees of answers waiting on slow readers ---------------------------------

def memory_max_mib(*options):
    """systemd/memory-max's bound for these options (the formula's one place)."""
    config = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "systemd",
                          "memory-max")
    import tempfile
    with tempfile.NamedTemporaryFile("w", suffix=".conf", delete=False) as f:
        for name, value in zip(options[::2], options[1::2]):
            f.write("%s = %s\n" % (name.lstrip("-"), value))
        path = f.name
    try:
        from conftest import BINARY
        out = subprocess.run([config, BINARY, path], capture_output=True, text=True, check=True)
    finally:
        os.unlink(path)
    return int(out.stdout.strip().rstrip("M"))


def test_a_long_batch_is_answered_request_by_request_as_before(harness):
    """A batch line over 64 KiB (read a request at a time) is answered as
    the same requests one by one: ids as written, errors in their places."""
    d = harness.start()
    c = d.client()
    requests = []
    for i in range(300):
        if i % 50 == 7:
            requests.append('{"jsonrpc":"2.0","method":"no.such","id":%d}' % i)
        elif i % 50 == 9:
            requests.append('{"jsonrpc":"2.0","method":"wrench.classify","params":{"fixture":%s,'
                            '"wrenches":[[1,2,3]]}}' % json.dumps(DISC))   # a notification
        else:
            requests.append('{"jsonrpc":"2.0","method":"wrench.classify","params":{"fixture":%s,'
                            '"wrenches":[[%d,-1,0.5],[0,1,0]]},"id":1%02d.50e0}'
                            % (json.dumps(DISC), i, i % 100))
    line = "[" + " , ".join(requests) + "]"
    assert len(line) > 65536
    c.send_line(line)
    whole = c.read_line()
    singles = []
    for r in requests:
        c.send_line(r)
        if '"id"' in r:
            singles.append(c.read_line())
    assert whole == b"[" + b",".join(singles) + b"]"
    assert b'"id":100.50e0' in whole and b'"id":7}' in whole


@pytest.mark.skipif(SANITIZED, reason="resident memory under a sanitizer measures its allocator")
def test_the_memory_bound_holds_for_batches_whose_answers_wait(harness):
    """Twelve clients (--max-clients) each send a 4 MiB batch line -- a
    10,000-wrench classify, then server.status whose params is a huge array
    -- and never read.  Peak resident memory stays within systemd/memory-max's
    bound for the options (each waiting answer holds its text and one
    request's tree, not the whole batch's tree)."""
    options = ["--threads", "2", "--max-clients", "13", "--max-line", str(4 << 20),
               "--max-output", str(1 << 20), "--cache-mb", "16"]
    bound = memory_max_mib(*options)
    d = harness.start(*options)
    wrenches = ",".join("[%d,-1,0.5]" % (i % 97) for i in range(10000))
    classify = ('{"jsonrpc":"2.0","method":"wrench.classify","params":{"fixture":%s,"wrenches":[%s]},'
                '"id":1}' % (json.dumps(DISC), wrenches))
    room = (4 << 20) - len(classify) - 200
    status = '{"jsonrpc":"2.0","method":"server.status","params":[%s],"id":2}' % ",".join(
        ["0"] * (room // 2))
    line = ("[" + classify + "," + status + "]\n").encode()
    assert len(line) < 4 << 20
    clients, peak = [], 0
    try:
        for _ in range(12):
            s = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
            s.setsockopt(socket.SOL_SOCKET, socket.SO_RCVBUF, 4096)
            s.connect(d.path)
            s.sendall(line)
            clients.append(s)
            peak = max(peak, peak_rss_mib(d.pid))
        deadline = time.monotonic() + 20 * SLOW
        while time.monotonic() < deadline:
            peak = max(peak, peak_rss_mib(d.pid))
            if idle_cpu(d.pid):
                break
        peak = max(peak, peak_rss_mib(d.pid))
    finally:
        for s in clients:
            s.close()
    print("peak resident %d MiB, bound %d MiB" % (peak, bound))
    assert peak < bound, "peak resident %d MiB over the bound %d MiB" % (peak, bound)
    assert "result" in ask_status(d.path, 20 * SLOW)


def peak_rss_mib(pid):
    with open("/proc/%d/status" % pid) as f:
        for line in f:
            if line.startswith("VmHWM:"):
                return int(line.split()[1]) >> 10
    return 0


def idle_cpu(pid, seconds=1.0):
    """True when the process used under 5% of a core over `seconds`."""
    before = cpu_seconds(pid)
    time.sleep(seconds)
    return cpu_seconds(pid) - before < 0.05 * seconds


# ---- fairness by user ------------------------------------------------------------------

# Run as nobody: COUNT connections, each asking a long design, held open
# until killed.
DESIGNER = r"""
import os, socket, sys, time
path, count, line = sys.argv[1], int(sys.argv[2]), sys.argv[3].encode() + b"\n"
os.setgroups([]); os.setgid(65534); os.setuid(65534)
socks = []
for _ in range(count):
    s = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
    s.connect(path)
    s.sendall(line)
    socks.append(s)
print("ready", flush=True)
time.sleep(600)
"""


def put_latencies(path, count=20):
    """fixture.put round trips of root's own client, each a new fixture."""
    times = []
    with socket.socket(socket.AF_UNIX, socket.SOCK_STREAM) as s:
        s.settimeout(60 * SLOW)
        s.connect(path)
        f = s.makefile("rb")
        for i in range(count):
            fixture = dict(DISC, name="fair-%d-%f" % (i, time.monotonic()))
            line = json.dumps({"jsonrpc": "2.0", "method": "fixture.put",
                               "params": {"fixture": fixture}, "id": i}) + "\n"
            start = time.monotonic()
            s.sendall(line.encode())
            answer = json.loads(f.readline())
            times.append(time.monotonic() - start)
            assert "result" in answer, answer
            time.sleep(0.05)
    times.sort()
    return times[len(times) // 2]


def designs_by_nobody(d, count):
    from test_resources import design_request
    line = design_request(1, spacing=0.25).decode().strip()
    p = subprocess.Popen([sys.executable, "-c", DESIGNER, d.path, str(count), line],
                         stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    assert p.stdout.readline().strip() == "ready", p.stderr.read()
    time.sleep(0.5)
    return p


@needs_root
@pytest.mark.skipif(SANITIZED, reason="latency under a sanitizer")
def test_workers_are_shared_by_user_not_by_connection(harness):
    """One user (nobody) runs 2, 20, then 100 designs on as many
    connections; root's fixture.put p50 stays under 0.1 s with 100 as with
    2 (the workers take users in turn: when each connection had a turn, it
    was 238 ms behind 40)."""
    d = harness.start("--threads", "2")
    open_to_everyone(harness, d)
    figures = {}
    for count in (2, 20, 100):
        p = designs_by_nobody(d, count)
        try:
            figures[count] = put_latencies(d.path)
        finally:
            p.kill()
            p.wait()
        time.sleep(0.5)
    print("fixture.put p50 behind nobody's designs: %s" % ", ".join(
        "%d designs %.0f ms" % (n, 1000 * t) for n, t in sorted(figures.items())))
    assert figures[100] < 0.1 * SLOW, figures


@needs_root
def test_a_user_may_hold_at_most_max_clients_per_uid(harness):
    """--max-clients-per-uid 3: nobody's fourth connection is refused
    (-32003 naming the uid and the option); root has three of its own."""
    d = harness.start("--max-clients-per-uid", "3")
    open_to_everyone(harness, d)
    script = (
        "import os, socket, json, sys\n"
        "os.setgroups([]); os.setgid(65534); os.setuid(65534)\n"
        "held = []\n"
        "for i in range(4):\n"
        "    s = socket.socket(socket.AF_UNIX); s.connect(sys.argv[1]); held.append(s)\n"
        "    s.sendall(b'{\"jsonrpc\":\"2.0\",\"method\":\"server.status\",\"id\":1}\\n')\n"
        "    print(s.makefile('rb').readline().decode().strip(), flush=True)\n")
    out = subprocess.run([sys.executable, "-c", script, d.path], capture_output=True, text=True,
                         timeout=30 * SLOW)
    answers = [json.loads(line) for line in out.stdout.splitlines()]
    assert len(answers) == 4, out
    assert all("result" in a for a in answers[:3]), answers
    assert answers[3]["error"]["code"] == -32003
    assert "--max-clients-per-uid 3" in answers[3]["error"]["data"]["reason"]
    assert "uid 65534" in answers[3]["error"]["data"]["reason"]
    held = [d.client() for _ in range(3)]  # root's own three
    for c in held:
        assert "result" in c.call("server.status")
    fourth = d.client()
    fourth.send(fourth.request("server.status"))
    assert "uid 0 (--max-clients-per-uid 3)" in fourth.read_json()["error"]["data"]["reason"]


# ---- names and fixture.list ------------------------------------------------------------

def test_a_name_longer_than_1024_bytes_is_refused_at_its_field(harness):
    d = harness.start()
    c = d.client()
    assert "result" in c.call("fixture.put", {"fixture": dict(DISC, name="é" * 512)})
    e = c.error("fixture.put", {"fixture": dict(DISC, name="n" * 1025)})
    assert e["code"] == -32602 and e["data"]["field"] == "params.fixture.name", e
    assert "1025 bytes" in e["data"]["reason"] and "1024" in e["data"]["reason"]
    e = c.error("wrench.classify", {"fixture": dict(DISC, name="n" * (8 << 20)),
                                    "wrenches": [[1, 0, 0]]})
    assert e["data"]["field"] == "params.fixture.name", e


def put_many(c, count):
    """`count` distinct stored fixtures (pipelined puts); their ids."""
    lines = []
    for i in range(count):
        fixture = json.loads(json.dumps(DISC))
        fixture["name"] = "many-%d" % i
        fixture["body"]["mass"] = 1 + i / 1024.0   # a distinct id each
        lines.append(json.dumps({"jsonrpc": "2.0", "method": "fixture.put",
                                 "params": {"fixture": fixture}, "id": i}))
    c.send_raw(("\n".join(lines) + "\n").encode())
    return [c.read_json()["result"]["id"] for _ in range(count)]


def test_fixture_list_pages_by_after_and_limit(harness):
    """Pages of at most `limit` (default and most 1000) sorted by id, from
    after `after`; `more` says whether any follow.  Both clients gather
    every page: the Python client's list_fixtures and wrenchctl list."""
    d = harness.start()
    c = d.client()
    ids = sorted(put_many(c, 1005))
    first = c.result("fixture.list")
    assert [f["id"] for f in first["fixtures"]] == ids[:1000] and first["more"] is True
    second = c.result("fixture.list", {"after": ids[999]})
    assert [f["id"] for f in second["fixtures"]] == ids[1000:] and second["more"] is False
    page = c.result("fixture.list", {"after": ids[10], "limit": 3})
    assert [f["id"] for f in page["fixtures"]] == ids[11:14] and page["more"] is True
    assert c.result("fixture.list", {"after": ids[-1]}) == {"fixtures": [], "more": False}
    for bad, field in (({"limit": 0}, "params.limit"), ({"limit": 1001}, "params.limit"),
                       ({"limit": 2.5}, "params.limit"), ({"after": "x"}, "params.after"),
                       ({"after": 3}, "params.after"), ({"page": 1}, "params.page")):
        assert c.error("fixture.list", bad)["data"]["field"] == field, bad

    sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..",
                                    "clients", "python"))
    import wrenchd
    with wrenchd.Client(d.path) as client:
        assert [f.id for f in client.list_fixtures()] == ids
        page = client.list_fixtures(after=ids[0], limit=2)
        assert [f.id for f in page] == ids[1:3] and page.more
    from conftest import REPO
    out = subprocess.run([os.path.join(REPO, "build", "wrenchctl"), "--socket", d.path, "list"],
                         capture_output=True, text=True, timeout=60 * SLOW)
    assert out.returncode == 0, out.stderr
    assert "(1005 stored)" in out.stdout
    assert [line.split()[0] for line in out.stdout.splitlines()[1:-1]] == ids


def rss_kib(pid, field):
    with open("/proc/%d/status" % pid) as f:
        for line in f:
            if line.startswith(field + ":"):
                return int(line.split()[1])
    return 0


@pytest.mark.skipif(SANITIZED, reason="resident memory under a sanitizer measures its allocator")
def test_fixture_list_is_written_in_pieces_under_max_output(harness):
    """A page of 1000 fixtures whose 1024-byte names each escape to 6 KiB is
    about 6 MiB of text.  Ten clients ask for it and never read: each
    answer is written a piece at a time while the client's unsent output is
    under --max-output (256 KiB), so the daemon's resident memory grows by
    about a piece, the bound and the page's names a client (under 3 MiB),
    not the page's text (60 MiB if each answer were made whole).  A client
    that reads gets the same page as one reading the answer whole would."""
    d = harness.start("--max-output", str(256 << 10), "--max-clients", "16")
    c = d.client(timeout=60 * SLOW)
    lines = []
    for i in range(1000):
        fixture = json.loads(json.dumps(DISC))
        fixture["name"] = "\x01" * 1020 + "%04d" % i
        fixture["body"]["mass"] = 1 + i / 1024.0
        lines.append(json.dumps({"jsonrpc": "2.0", "method": "fixture.put",
                                 "params": {"fixture": fixture}, "id": i}))
    c.send_raw(("\n".join(lines) + "\n").encode())
    for _ in range(1000):
        assert "result" in c.read_json()
    whole = c.result("fixture.list")
    assert len(whole["fixtures"]) == 1000 and whole["more"] is False
    text = len(json.dumps(whole, separators=(",", ":")))
    assert text > 5 << 20, text
    # Peak resident memory from here (Linux: 5 to clear_refs resets VmHWM).
    with open("/proc/%d/clear_refs" % d.pid, "w") as f:
        f.write("5")
    before = rss_kib(d.pid, "VmRSS")
    request = b'{"jsonrpc":"2.0","method":"fixture.list","id":1}\n'
    clients = []
    try:
        for _ in range(10):
            s = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
            s.setsockopt(socket.SOL_SOCKET, socket.SO_RCVBUF, 4096)
            s.connect(d.path)
            s.sendall(request)
            clients.append(s)
        time.sleep(2 * SLOW)
        deadline = time.monotonic() + 20 * SLOW
        while time.monotonic() < deadline and not idle_cpu(d.pid):
            pass
        grown = (rss_kib(d.pid, "VmHWM") - before) >> 10
        print("resident memory grew by %d MiB for 10 unread pages of %d MiB" % (grown, text >> 20))
        assert grown < 30, grown
        # One of them reads: the whole page, the same as read at once.
        reader = clients.pop()
        reader.settimeout(60 * SLOW)
        got = b""
        while not got.endswith(b"\n"):
            chunk = reader.recv(1 << 16)
            assert chunk, "closed"
            got += chunk
        answer = json.loads(got)
        assert answer["result"] == whole and answer["id"] == 1
        reader.close()
    finally:
        for s in clients:
            s.close()
    assert "result" in ask_status(d.path, 20 * SLOW)


# ---- bounded work: --max-candidates and deadline_s ------------------------------------------

def design_params(spacing, **more):
    from test_resources import design_request
    params = json.loads(design_request(1, spacing=spacing))["params"]
    params.update(more)
    return params


def test_max_candidates_refuses_at_the_field_with_the_count(harness):
    """Eight fixels at spacing 0.1 (about 1e16 candidates) are refused by
    the default cap; --max-candidates 5000 refuses spacing 1 (about 10,000)
    naming the count, and takes half of it as a shard, and spacing 2."""
    d = harness.start()
    c = d.client()
    e = c.error("fixture.design", design_params(0.1, fixels=8))
    assert e["code"] == -32602 and e["data"]["field"] == "params.spacing", e
    assert "the limit is 100000000 (--max-candidates)" in e["data"]["reason"], e
    count = int(e["data"]["reason"].split("gives ")[1].split(" ")[0])
    assert count > 1e16
    d2 = harness.start("--max-candidates", "5000", socket_path=harness.path("b.sock"))
    c2 = d2.client()
    e = c2.error("fixture.design", design_params(1))
    assert e["data"]["field"] == "params.spacing", e
    count = int(e["data"]["reason"].split("gives ")[1].split(" ")[0])
    assert 5000 < count < 20000 and "(--max-candidates)" in e["data"]["reason"], e
    shard = c2.error("fixture.design", design_params(0.5, shard=[0, 2]))
    assert "candidates in this shard" in shard["data"]["reason"], shard
    assert "designs" in c2.result("fixture.design", design_params(1, shard=[0, 2]))
    assert "designs" in c2.result("fixture.design", design_params(2))


def test_a_design_with_a_deadline_answers_the_best_so_far_as_partial(harness):
    """A design of about 680,000 candidates (a minute of a core) with
    deadline_s 1 answers within 20 s: "partial": true, fewer examined than
    candidates, designs ranked from those; without the deadline a design is
    whole (no "partial")."""
    d = harness.start("--threads", "2")
    c = d.client(timeout=60 * SLOW)
    start = time.monotonic()
    result = c.result("fixture.design", design_params(0.25, deadline_s=1))
    took = time.monotonic() - start
    assert took < 20 * SLOW, took
    assert result["partial"] is True
    counts = result["counts"]
    assert 0 < counts["examined"] < counts["candidates"], counts
    # The best of those examined (how many of them seat the part depends on
    # how far the machine got): at most top, ranked.
    assert len(result["designs"]) <= 3
    assert [d["rank"] for d in result["designs"]] == list(range(1, len(result["designs"]) + 1))
    whole = c.result("fixture.design", design_params(2))
    assert "partial" not in whole
    assert whole["counts"]["examined"] == whole["counts"]["candidates"]
    for bad in (0, -1, "1", 2e9):
        e = c.error("fixture.design", design_params(2, deadline_s=bad))
        assert e["data"]["field"] == "params.deadline_s", (bad, e)
