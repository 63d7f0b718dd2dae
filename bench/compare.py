#!/usr/bin/python3
"""bench/compare.py -- the answers of this build against a baseline build,
request by request: what changed besides the speed.

    bench/compare.py --wrenchd build/wrenchd --baseline build/baseline/src/build/wrenchd [--random N]

Asks both daemons the same requests and compares the answers number by
number:
  push.regions (goal, strong, both) of the examples, the tests' fixtures
  (tests/e2e/fixtures.py) and N random outlines of lines and arcs (rounded
  polygons, some with a round hole) with 3 or 4 fixels: the regions must
  be the same, each end within 1e-12;
  fixture.put of the same: the same id (the simplicity test says yes to
  the same outlines, and no with the same error);
  fixture.design's lattice on parts with arcs: every baseline design must
  be among the new ones (the same holes and pose within 1e-7); the new
  ones it adds (poses the baseline's theta scan missed) are counted.
Prints one line per kind and every difference; the exit status is 1 when a
region or an id differs or a baseline design is missing.
"""
import argparse
import glob
import json
import math
import os
import random
import shutil
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "bench"))
sys.path.insert(0, os.path.join(ROOT, "tests", "e2e"))
import geometry  # noqa: E402  (start, Line)
import fixtures as FX  # noqa: E402


def rounded_polygon(rnd):
    n = rnd.randint(3, 8)
    angles = sorted(rnd.uniform(0, 2 * math.pi) for _ in range(n))
    loop = []
    for a in angles:
        r = rnd.uniform(2, 3)
        u = rnd.random()
        bulge = 0 if u < 0.2 else rnd.uniform(0.05, 0.6) if u < 0.8 else rnd.uniform(-0.2, 0)
        loop.append([r * math.cos(a), r * math.sin(a), bulge])
    loops = [loop]
    if rnd.random() < 0.5:
        loops.append([[0.4, 0.1, 1], [-0.2, 0.1, 1]])
    return loops


def arc_point(loop, j, t):
    """The point at fraction t of segment j (an arc by its bulge)."""
    a, b = loop[j], loop[(j + 1) % len(loop)]
    k = a[2] if len(a) > 2 else 0
    if k == 0:
        return [a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])]
    half = 2 * math.atan(abs(k))  # half the included angle
    chord = math.hypot(b[0] - a[0], b[1] - a[1])
    h = chord / 2
    e = [(b[0] - a[0]) / chord, (b[1] - a[1]) / chord]
    side = -1 if k > 0 else 1  # the bulge lies right of the chord when k > 0
    n = [-e[1] * side, e[0] * side]
    phi = half * (2 * t - 1)
    u = h * math.sin(phi) / math.sin(half)
    w = h * (math.cos(phi) - math.cos(half)) / math.sin(half)
    m = [(a[0] + b[0]) / 2, (a[1] + b[1]) / 2]
    return [m[0] + u * e[0] + w * n[0], m[1] + u * e[1] + w * n[1]]


def random_fixtures(count, seed=33):
    rnd = random.Random(seed)
    out = []
    while len(out) < count:
        loops = rounded_polygon(rnd)
        fixels = []
        for _ in range(rnd.choice((3, 4))):
            j = rnd.randrange(len(loops[0]))
            fixels.append({"at": arc_point(loops[0], j, rnd.uniform(0.1, 0.9))})
        out.append({"body": {"mass": 1, "shape": {"type": "outline", "loops": loops}},
                    "friction": {"static": round(rnd.uniform(0, 0.6), 3)}, "fixels": fixels})
    return out


def corpus(random_count):
    named = []
    for path in sorted(glob.glob(os.path.join(ROOT, "examples", "*.json"))):
        with open(path) as f:
            named.append((os.path.basename(path), json.load(f)))
    for name in ("disc_corner", "rectangle_321", "chamfered_plate", "offset_disc", "triangle",
                 "corner_fixel_plate", "square_form_closure"):
        named.append((name, getattr(FX, name)()))
    for i, f in enumerate(random_fixtures(random_count)):
        named.append(("random %d" % i, f))
    return named


def regions_differ(a, b):
    """The differences of two push.regions results, as text (none: [])."""
    if "result" not in a or "result" not in b:
        return [] if a.get("error", {}).get("code") == b.get("error", {}).get("code") else \
            ["errors %r / %r" % (a.get("error"), b.get("error"))]
    ra, rb = a["result"]["regions"], b["result"]["regions"]
    if len(ra) != len(rb):
        return ["%d regions against %d" % (len(ra), len(rb))]
    out = []
    for x, y in zip(ra, rb):
        for key in x:
            if isinstance(x[key], (int, float)) and abs(x[key] - y.get(key, math.inf)) > 1e-12:
                out.append("%s %r against %r" % (key, x[key], y.get(key)))
            elif not isinstance(x[key], (int, float)) and x[key] != y.get(key):
                out.append("%s %r against %r" % (key, x[key], y.get(key)))
    return out


LATTICE_PARTS = [
    ("rounded rectangle", {"mass": 1, "shape": {"type": "outline", "loops": [[
        [0.5, 0], [2.5, 0, math.tan(math.pi / 8)], [3, 0.5], [3, 1.5, math.tan(math.pi / 8)],
        [2.5, 2], [0.5, 2, math.tan(math.pi / 8)], [0, 1.5], [0, 0.5, math.tan(math.pi / 8)]]]}},
     {"pitch": 1, "peg_radius": 0.15, "extent": [4, 4]}),
    ("plate with hole and slot", {"mass": 1, "shape": {"type": "outline", "loops": [
        [[0, 0], [4, 0], [4, 2.5], [0, 2.5]], [[1.4, 1.2, 1], [0.8, 1.2, 1]],
        [[2.4, 1.0], [3.2, 1.0, 1], [3.2, 1.5], [2.4, 1.5, 1]]]}},
     {"pitch": 1, "peg_radius": 0.2, "extent": [5, 4]}),
]


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--wrenchd", required=True)
    parser.add_argument("--baseline", required=True)
    parser.add_argument("--random", type=int, default=200)
    args = parser.parse_args()
    directory = tempfile.mkdtemp(prefix="wrenchd-compare-")
    daemons = []
    bad = False
    try:
        lines = []
        for name, binary in (("new", args.wrenchd), ("baseline", args.baseline)):
            daemon, sock = geometry.start(os.path.abspath(binary), directory, name)
            daemons.append((daemon, sock))
            lines.append(geometry.Line(sock, daemon.pid))
        named = corpus(args.random)
        compared = differing = identical = 0
        ids_same = 0
        for name, fixture in named:
            put = [line.call("fixture.put", {"fixture": fixture}) for line in lines]
            if put[0].get("result", {}).get("id") != put[1].get("result", {}).get("id") or \
                    put[0].get("error", {}).get("reason") != put[1].get("error", {}).get("reason"):
                print("fixture.put %s: %r against %r" % (name, put[0], put[1]))
                bad = True
            else:
                ids_same += 1
            for s in ("goal", "strong", "both"):
                answers = [line.call("push.regions", {"fixture": fixture, "set": s})
                           for line in lines]
                diff = regions_differ(answers[0], answers[1])
                compared += 1
                identical += answers[0] == answers[1]
                if diff:
                    differing += 1
                    bad = True
                    print("push.regions %s %s: %s" % (name, s, "; ".join(diff[:5])))
        print("fixture.put: %d of %d fixtures with the same id or error" % (ids_same, len(named)))
        print("push.regions: %d of %d answers within 1e-12, %d identical (%d fixtures, three "
              "sets each)" % (compared - differing, compared, identical, len(named)))
        for name, body, lattice in LATTICE_PARTS:
            params = {"body": body, "friction": 0.3, "lattice": lattice, "top": 1000,
                      "objective": "region"}
            answers = [line.call("fixture.design", params)["result"] for line in lines]
            new, old = answers[0]["designs"], answers[1]["designs"]

            def same(a, b):
                return a["pegs"] == b["pegs"] and \
                    abs(math.remainder(a["pose"][2] - b["pose"][2], 360)) <= 1e-5 and \
                    math.hypot(a["pose"][0] - b["pose"][0], a["pose"][1] - b["pose"][1]) <= 1e-6
            missing = [d for d in old if not any(same(d, e) for e in new)]
            added = [d for d in new if not any(same(d, e) for e in old)]
            print("lattice %s: %d poses, the baseline %d; of the %d designs kept, %d new, %d of "
                  "the baseline's missing" % (name, answers[0]["poses"], answers[1]["poses"],
                                              len(new), len(added), len(missing)))
            bad = bad or bool(missing)
    finally:
        for daemon, sock in daemons:
            sock.close()
            daemon.terminate()
            daemon.wait(timeout=30)
        shutil.rmtree(directory, ignore_errors=True)
    sys.exit(1 if bad else 0)


if __name__ == "__main__":
    main()
