#!/usr/bin/python3
"""bench/geometry.py -- geometry at interactive speed, side by side with a
baseline build of wrenchd, both daemons started by this script in one run.

    bench/geometry.py --wrenchd build/wrenchd --baseline build/baseline/src/build/wrenchd [--quick] [--json]

Each figure is the median over sequential requests on one connection, raw
JSON lines on the socket (no client library in the time):
  put4000-*    fixture.put of a 4,000-vertex outline (a star of lines, a
               star of arcs, 2,040 holes of two arcs in a plate) and a
               4,000-vertex polygon: the simplicity test dominates;
  inline/id    wrench.classify of one wrench on a 2,000-segment outline,
               the fixture inline (the same text each time) against by id;
and, counted by callgrind in process (build/bench/regions, build/bench/lattice):
  regions-*    push.regions' instructions per pair of an edge and a cone:
               lines, arcs, arcs by the reference;
  lattice-*    a lattice design's instructions per pose: lines, arcs, arcs
               by the theta scan.
"""
import argparse
import json
import math
import os
import shutil
import socket as socketlib
import statistics
import subprocess
import sys
import tempfile
import time


def start(binary, directory, name):
    path = os.path.join(directory, name + ".sock")
    daemon = subprocess.Popen([binary, "--socket", path, "--log-level", "error", "--threads", "2",
                               "--max-line", str(64 << 20)], cwd=directory)
    for _ in range(500):
        if os.path.exists(path):
            sock = socketlib.socket(socketlib.AF_UNIX, socketlib.SOCK_STREAM)
            try:
                sock.connect(path)
                return daemon, sock
            except ConnectionRefusedError:
                sock.close()  # bound, not listening yet
        time.sleep(0.02)
    daemon.kill()
    sys.exit("bench/geometry.py: %s did not start" % binary)


class Line:
    """One connection: send a request line, read its answer line (progress
    notifications skipped)."""

    def __init__(self, sock, pid):
        self.sock = sock
        self.pid = pid
        self.pending = b""

    def call(self, method, params):
        return self.send(encode(method, params))

    def send(self, text):
        self.sock.sendall(text)
        while True:
            while b"\n" not in self.pending:
                chunk = self.sock.recv(1 << 20)
                if not chunk:
                    raise RuntimeError("the daemon closed the connection")
                self.pending += chunk
            line, self.pending = self.pending.split(b"\n", 1)
            answer = json.loads(line)
            if "id" in answer:
                return answer


def cpu_seconds(pid):
    """CPU time of every thread of process pid so far (schedstat: ns)."""
    total = 0
    directory = "/proc/%d/task" % pid
    for task in os.listdir(directory):
        try:
            with open(os.path.join(directory, task, "schedstat")) as f:
                total += int(f.read().split()[0])
        except OSError:
            pass
    return total * 1e-9


def encode(method, params):
    request = {"jsonrpc": "2.0", "id": 1, "method": method, "params": params}
    return json.dumps(request, separators=(",", ":")).encode() + b"\n"


def timed(line, method, params, repeats):
    """The median wall seconds of `repeats` calls (the request written once,
    before the clock starts) and the daemon's CPU seconds per call (on a
    busy machine the steadier figure), and the last answer."""
    text = encode(method, params)
    times = []
    answer = line.send(text)  # once unmeasured: what a first call builds
    cpu = cpu_seconds(line.pid)
    for _ in range(repeats):
        start = time.perf_counter()
        answer = line.send(text)
        times.append(time.perf_counter() - start)
    cpu = (cpu_seconds(line.pid) - cpu) / repeats
    return (statistics.median(times), cpu), answer


def star(n, bulge, seed):
    """A star of n vertices at jittered angles, radii in [60, 100]."""
    state = seed
    loop = []
    for k in range(n):
        state = (state * 6364136223846793005 + 1442695040888963407) % (1 << 64)
        u = (state >> 11) / float(1 << 53)
        state = (state * 6364136223846793005 + 1442695040888963407) % (1 << 64)
        v = (state >> 11) / float(1 << 53)
        angle = 2 * math.pi * (k + 0.5 * u) / n
        r = 60 + 40 * v
        loop.append([r * math.cos(angle), r * math.sin(angle), bulge * (1 if k % 2 else -1)])
    return loop


def fixture_of(loops, fixels):
    return {"body": {"mass": 1, "shape": {"type": "outline", "loops": loops}},
            "friction": {"static": 0.3}, "fixels": [{"at": at} for at in fixels]}


def midpoint(loop, j):
    """The middle of segment j: of an arc of bulge k, its chord's middle
    moved k half chords to the right of the chord (positive bulge:
    counter-clockwise, the arc right of its chord)."""
    a, b = loop[j], loop[(j + 1) % len(loop)]
    k = a[2] if len(a) > 2 else 0
    dx, dy = b[0] - a[0], b[1] - a[1]
    return [(a[0] + b[0]) / 2 + k * dy / 2, (a[1] + b[1]) / 2 - k * dx / 2]


def holes_plate(columns, rows):
    """A plate 10 columns wide per hole with a two-arc hole of radius 2 in
    each cell."""
    width, height = 10 * columns, 10 * rows
    loops = [[[0, 0, 0], [width, 0, 0], [width, height, 0], [0, height, 0]]]
    for i in range(columns):
        for j in range(rows):
            cx, cy = 10 * i + 5, 10 * j + 5
            loops.append([[cx + 2, cy, 1], [cx - 2, cy, 1]])
    return loops, [[width / 3, 0], [width, height / 2], [0, height / 3]]


def measure(line, quick):
    out = {}
    repeats = 5 if quick else 15
    lines_star = star(4000, 0, 7)
    arcs_star = star(4000, 0.001, 7)
    for name, loop in (("put4000-lines", lines_star), ("put4000-arcs", arcs_star)):
        fixture = fixture_of([loop], [midpoint(loop, 0), midpoint(loop, 1333),
                                      midpoint(loop, 2666)])
        seconds, answer = timed(line, "fixture.put", {"fixture": fixture}, repeats)
        out[name] = ms(seconds, answer)
    loops, fixels = holes_plate(60, 34)
    seconds, answer = timed(line, "fixture.put", {"fixture": fixture_of(loops, fixels)}, repeats)
    out["put4000-holes"] = ms(seconds, answer)
    polygon = {"body": {"mass": 1, "shape": {"type": "polygon",
                                             "vertices": [v[:2] for v in lines_star]}},
               "friction": {"static": 0.3},
               "fixels": [{"at": midpoint(lines_star, j)} for j in (0, 1333, 2666)]}
    seconds, answer = timed(line, "fixture.put", {"fixture": polygon}, repeats)
    out["put4000-polygon"] = ms(seconds, answer)

    loop = star(2000, 0.001, 11)
    fixture = fixture_of([loop], [midpoint(loop, 0), midpoint(loop, 700), midpoint(loop, 1400)])
    put = line.call("fixture.put", {"fixture": fixture})
    wrench = {"wrenches": [[0.1, -1, 0.2]]}
    count = 50 if quick else 300
    seconds, answer = timed(line, "wrench.classify", dict(wrench, fixture=put["result"]["id"]),
                            count)
    out["classify-id"] = ms(seconds, answer)
    seconds, answer = timed(line, "wrench.classify", dict(wrench, fixture=fixture), count)
    out["classify-inline"] = ms(seconds, answer)
    return out


def ms(seconds, answer):
    """[wall ms, CPU ms] of an answered call; None for an error."""
    return [seconds[0] * 1e3, seconds[1] * 1e3] if "result" in answer else None


def instructions(argv):
    """The instructions a program runs, counted by callgrind (None without
    valgrind)."""
    if not shutil.which("valgrind"):
        return None
    with tempfile.TemporaryDirectory() as tmp:
        run = subprocess.run(["valgrind", "--tool=callgrind",
                              "--callgrind-out-file=" + os.path.join(tmp, "out")] + argv,
                             stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    for line in run.stderr.splitlines():
        if "Collected :" in line:
            return int(line.split(":")[-1])
    return None


def counted(build, quick):
    """Instructions per pair (push.regions) and per pose (lattice), each run
    less a run that only builds the parts: callgrind's counts, which a busy
    machine does not move."""
    out = {}
    regions = os.path.join(build, "bench", "regions")
    repeats = 20 if quick else 200
    base = instructions([regions, "--only", "lines", "--repeats", "0"])
    if base is None:
        return out
    pairs = json.loads(subprocess.run([regions, "--only", "lines", "--repeats", "0"],
                                      stdout=subprocess.PIPE, text=True).stdout)["pairs"]
    for mode in ("lines", "arcs", "reference"):
        total = instructions([regions, "--only", mode, "--repeats", str(repeats)])
        out["regions-" + mode] = (total - base) / repeats / pairs
    lattice = os.path.join(build, "bench", "lattice")
    base = instructions([lattice, "--only", "none"])
    for mode in ("lines", "arcs") + (() if quick else ("scan",)):
        poses = json.loads(subprocess.run([lattice, "--only", mode], stdout=subprocess.PIPE,
                                          text=True).stdout)["poses"]
        out["lattice-" + mode] = (instructions([lattice, "--only", mode]) - base) / poses
    return out


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--wrenchd", required=True)
    parser.add_argument("--baseline", required=True)
    parser.add_argument("--quick", action="store_true")
    parser.add_argument("--json", action="store_true")
    args = parser.parse_args()
    directory = tempfile.mkdtemp(prefix="wrenchd-geometry-")
    figures = {}
    try:
        for name, binary in (("new", args.wrenchd), ("baseline", args.baseline)):
            daemon, sock = start(os.path.abspath(binary), directory, name)
            try:
                figures[name] = measure(Line(sock, daemon.pid), args.quick)
            finally:
                sock.close()
                daemon.terminate()
                daemon.wait(timeout=30)
    finally:
        shutil.rmtree(directory, ignore_errors=True)
    figures["instructions"] = counted(os.path.dirname(os.path.abspath(args.wrenchd)), args.quick)
    if args.json:
        print(json.dumps(figures))
        return
    for key, value in figures["instructions"].items():
        print("%-18s %22.0f instructions per %s" % (key, value,
                                                   "pair" if "regions" in key else "pose"))
    print("%-18s %22s %22s" % ("ms: wall / CPU", "new", "baseline"))
    for key in figures["new"]:
        cells = ["%.2f / %.2f" % tuple(f[key]) if f[key] else "-"
                 for f in (figures["new"], figures["baseline"])]
        print("%-18s %22s %22s" % (key, cells[0], cells[1]))


if __name__ == "__main__":
    main()
