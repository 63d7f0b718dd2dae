#!/usr/bin/python3
"""bench/design.py -- fixture.design's speed, beside the same design done as a
user would script it with the Python client.

    bench/design.py [--quick] [--json]

The part: a 12-segment outline (a 12 x 8 plate with a notch, two corners
filleted with arcs, two chamfered), mass 1, friction 0.25, candidate sites
every 0.5 along it (80 sites, 82,160 candidates): 3 fixels, objective
"margin", top 10.

  design   a fresh build/wrenchd --threads 1 (one core): the wall time of one
           fixture.design over every candidate, median of 3 runs (1 with
           --quick); candidates per second per core.  Then the same with
           --threads 2: the speed-up of one design on both cores.
  script   the same candidates, as a user would script it with the Python
           client: per candidate fixture.put, push.regions (set both) and,
           when the region is not empty, wrench.classify of a push at 32 points
           spread along the region (the margins, set both) to pick the best;
           on N candidates drawn at random from all of them (seed 1; 400, 100
           with --quick), per candidate.  Then fixture.delete, so that the
           store does not grow.

Prints one table, figure by figure, the baseline beside: candidates per
second, and the ratio.  Nothing here fails for being slow.  What is left out:
the daemon's start; the script's answers are not compared with the design's
(tests/e2e/test_design.py does that).
"""
import argparse
import json
import math
import os
import random
import shutil
import statistics
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "clients", "python"))
import wrenchd  # noqa: E402  (the stdlib client, imported by path)

FRICTION = 0.25
SPACING = 0.5
# A 12 x 8 plate, a 2 x 2 notch in its top edge, two corners filleted (bulge
# tan(22.5 deg): quarter circles) and two chamfered: 12 segments.
FILLET = 0.41421356237309503
BODY = {"mass": 1, "shape": {"type": "outline", "loops": [[
    [1, 0], [11, 0, FILLET], [12, 1], [12, 7], [11, 8], [7, 8], [7, 6], [5, 6], [5, 8],
    [1, 8, FILLET], [0, 7], [0, 1]]]}}


def start(directory, threads):
    socket = os.path.join(directory, "wrenchd-%d.sock" % threads)
    daemon = subprocess.Popen([os.path.join(ROOT, "build", "wrenchd"), "--socket", socket,
                               "--threads", str(threads), "--log-level", "error"], cwd=directory)
    for _ in range(200):
        if os.path.exists(socket):
            break
        time.sleep(0.02)
    return daemon, socket


def stop(daemon):
    daemon.terminate()
    daemon.wait(timeout=30)


def design_seconds(socket, repeats):
    times, answer = [], None
    with wrenchd.Client(socket, timeout=600) as client:
        for _ in range(repeats):
            t = time.perf_counter()
            answer = client.design(BODY, FRICTION, spacing=SPACING, top=10)
            times.append(time.perf_counter() - t)
    return statistics.median(times), answer


def scripted_seconds(socket, sites, count):
    """The candidates a user would loop over (combinations of 3 sites), a
    random `count` of them."""
    n = len(sites)
    every = [(i, j, k) for i in range(n) for j in range(i + 1, n) for k in range(j + 1, n)]
    combos = random.Random(1).sample(every, min(count, len(every)))
    best = None
    t = time.perf_counter()
    with wrenchd.Client(socket, timeout=600) as client:
        for combo in combos:
            fixture = {"body": BODY, "friction": {"static": FRICTION},
                       "fixels": [sites[c] for c in combo]}
            try:
                put = client.put_fixture(fixture)
            except wrenchd.WrenchdError:
                continue
            regions = client.push_regions(put.id, "both")
            wrenches = []
            for r in regions.regions:
                for s in range(32):
                    u = (s + 0.5) / 32
                    a, b = r.from_point, r.to_point
                    p = on_boundary(r.segment, [a[0] + u * (b[0] - a[0]),
                                                a[1] + u * (b[1] - a[1])])
                    wrenches.append({"force": inward(r.segment, p), "at": p})
            if wrenches:
                verdicts = client.classify(put.id, wrenches, sets="both")
                margin = max(v["both"].margin for v in verdicts)
                best = margin if best is None else max(best, margin)
            client.delete_fixture(put.id, missing_ok=True)
    return time.perf_counter() - t, len(combos)


# The fillets: segment 1 about (11, 1), segment 9 about (1, 7), radius 1.
ARCS = {1: (11, 1), 9: (1, 7)}


def on_boundary(segment, p):
    """A point between a region's ends, put back on its segment (an arc's
    chord is not on the arc)."""
    if segment not in ARCS:
        return p
    cx, cy = ARCS[segment]
    d = ((p[0] - cx) ** 2 + (p[1] - cy) ** 2) ** 0.5
    return [cx + (p[0] - cx) / d, cy + (p[1] - cy) / d]


def inward(segment, p):
    """The inward normal there: radial on a fillet, else the straight
    segment's (the outline runs counter-clockwise: material on the left)."""
    if segment in ARCS:
        cx, cy = ARCS[segment]
        return [cx - p[0], cy - p[1]]
    loop = BODY["shape"]["loops"][0]
    a, b = loop[segment], loop[(segment + 1) % len(loop)]
    dx, dy = b[0] - a[0], b[1] - a[1]
    length = (dx * dx + dy * dy) ** 0.5
    return [-dy / length, dx / length]


def spaced_sites():
    """Sites every SPACING along each segment, centred, as a user would
    place them (docs/PROTOCOL.md, "spacing"): the normals left to
    fixture.put."""
    loop = BODY["shape"]["loops"][0]
    sites = []
    for i, vertex in enumerate(loop):
        a, b = vertex[:2], loop[(i + 1) % len(loop)][:2]
        if i in ARCS:
            cx, cy = ARCS[i]
            start = math.atan2(a[1] - cy, a[0] - cx)
            sweep = math.pi / 2
            length = sweep
        else:
            length = math.hypot(b[0] - a[0], b[1] - a[1])
        steps = int(math.floor(length / SPACING + 1e-9))
        first = (length - (steps - 1) * SPACING) / 2
        for k in range(steps):
            u = (first + k * SPACING) / length
            if i in ARCS:
                angle = start + u * sweep
                sites.append({"at": [cx + math.cos(angle), cy + math.sin(angle)]})
            else:
                sites.append({"at": [a[0] + u * (b[0] - a[0]), a[1] + u * (b[1] - a[1])]})
    return sites


def machine_ceiling(repeats):
    """What two cores give two independent processes here: the same design
    in process (wrenchctl --local), alone and two at once; the speed-up of
    the pair (2 x alone / together), median of `repeats`.  One design on two
    workers can do no better."""
    body = tempfile.NamedTemporaryFile("w", suffix=".json", delete=False)
    json.dump({"body": BODY, "friction": {"static": FRICTION}}, body)
    body.close()
    argv = [os.path.join(ROOT, "build", "wrenchctl"), "--local", "design", body.name,
            "--spacing", str(SPACING), "--top", "10"]
    ratios = []
    try:
        for _ in range(repeats):
            t = time.perf_counter()
            subprocess.run(argv, check=True, stdout=subprocess.DEVNULL)
            alone = time.perf_counter() - t
            t = time.perf_counter()
            pair = [subprocess.Popen(argv, stdout=subprocess.DEVNULL) for _ in range(2)]
            for p in pair:
                p.wait()
            ratios.append(2 * alone / (time.perf_counter() - t))
    finally:
        os.unlink(body.name)
    return statistics.median(ratios)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--quick", action="store_true")
    parser.add_argument("--json", action="store_true")
    args = parser.parse_args(argv)
    directory = tempfile.mkdtemp(prefix="wrenchd-design-bench-")
    try:
        daemon, socket = start(directory, 1)
        try:
            seconds, answer = design_seconds(socket, 1 if args.quick else 3)
            count = 100 if args.quick else 400
            sites = spaced_sites()
            if len(sites) == answer.sites:
                script, scripted = scripted_seconds(socket, sites, count)
            else:
                script, scripted = float("nan"), 0
        finally:
            stop(daemon)
        daemon, socket2 = start(directory, 2)
        try:
            seconds2, answer2 = design_seconds(socket2, 1 if args.quick else 3)
        finally:
            stop(daemon)
    finally:
        shutil.rmtree(directory, ignore_errors=True)
    ceiling = machine_ceiling(1 if args.quick else 2)
    candidates = answer.counts["candidates"]
    per_core = candidates / seconds
    scripted_rate = scripted / script if scripted else float("nan")
    figures = {
        "design: candidates": candidates,
        "design: candidates/s, one core (median of runs)": round(per_core),
        "design: candidates/s, two cores": round(candidates / seconds2),
        "design: speed-up of one design on two cores": round(seconds / seconds2, 2),
        "two independent processes: speed-up on two cores": round(ceiling, 2),
        "scripted (put, push.regions, classify): candidates/s": round(scripted_rate, 1),
        "design over the script": round(per_core / scripted_rate, 1),
        "answers with 1 and 2 threads identical": json.dumps(answer.designs[0].__dict__,
                                                             sort_keys=True) ==
        json.dumps(answer2.designs[0].__dict__, sort_keys=True),
    }
    if args.json:
        print(json.dumps(figures))
        return 0
    print("fixture.design, 3 fixels, objective margin, a 12-segment outline, sites every %g: "
          "%d sites, %d candidates" % (SPACING, answer.sites, candidates))
    print("%-52s %14s %14s %10s" % ("", "design", "scripted", "ratio"))
    print("%-52s %14.0f %14.1f %9.1fx" % ("candidates per second, one core", per_core,
                                          scripted_rate, per_core / scripted_rate))
    print("%-52s %14.0f" % ("candidates per second, two cores", candidates / seconds2))
    print("%-52s %14.2f %14s %10s" % ("speed-up of one design on two cores", seconds / seconds2,
                                      "(machine)", "%.2f" % ceiling))
    print("  (machine: two independent in-process designs at once, 2 x alone / together: "
          "what two cores give here)")
    print("targets: at least 5,000 candidates/s per core; the script at least 10x slower")
    print("the same best design with 1 and 2 threads: %s"
          % figures["answers with 1 and 2 threads identical"])
    return 0


if __name__ == "__main__":
    sys.exit(main())
