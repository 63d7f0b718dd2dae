#!/usr/bin/python3
"""bench/compare_sweeps.py -- friction.sweep answers of this build against
the baseline's, request by request.

    bench/compare_sweeps.py [--random N] [--seed S] [--quick]

Builds the requests: every example in examples/ with an outline or a
polygon, the fixtures the tests build (tests/e2e/fixtures.py), and N
(default 200) random fixtures (tests/e2e/fixtures.py's random polygons and
discs, some in a corner), each swept for push and gravity with goal,
strong and both, kinetic ratios 1 and 0.5, and a few wrenches.  Each
request is answered by build/bench/answer (this checkout) and
build/baseline/answer (the Makefile's BASELINE_REVISION), both in process.

Prints how many answers are byte for byte the same; for the others, the
differences: the same shape with every number within 1e-12 (relative to
its size, at least 1) is listed as such, any other difference as a
failure.  Exit status 1 when any answer differs by more.
"""
import glob
import json
import os
import random
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "tests", "e2e"))
import fixtures as FX  # noqa: E402

NEW = os.path.join(ROOT, "build", "bench", "answer")
BASE = os.path.join(ROOT, "build", "baseline", "answer")
CLOSE = 1e-12


def named_fixtures(count, seed):
    out = []
    for path in sorted(glob.glob(os.path.join(ROOT, "examples", "*.json"))):
        with open(path) as f:
            fixture = json.load(f)
        if isinstance(fixture, dict) and "fixels" in fixture:
            out.append((os.path.basename(path), fixture))
    for name in ("disc_corner", "rectangle_321", "chamfered_plate", "offset_disc", "triangle",
                 "corner_fixel_plate", "square_form_closure"):
        out.append((name, getattr(FX, name)()))
    out.append(("disc_corner-kinetic", FX.disc_corner(mu=0.5, kinetic=0.3)))
    rnd = random.Random(seed)
    for i in range(count):
        kind = rnd.random()
        if kind < 0.45:
            f = FX.random_polygon(rnd, rnd.random() < 0.5, corner=rnd.random() < 0.6)
        else:
            f = FX.random_disc(rnd, corner=rnd.random() < 0.6)
        out.append(("random-%d" % i, f))
    return out


def requests(fixtures, rnd):
    lines = []
    for name, f in fixtures:
        shaped = "shape" in f.get("body", {})
        for ratio in (1.0, 0.5):
            for which in ("goal", "strong", "both"):
                if ratio != 1.0 and which == "goal":
                    continue
                kinds = ["gravity"] + (["push"] if shaped else [])
                for what in kinds:
                    params = {"fixture": f, "range": [0, 2], "kinetic_ratio": ratio,
                              what: {"set": which}}
                    lines.append((name, params))
            wrenches = [[rnd.uniform(-1, 1), rnd.uniform(-1, 1), rnd.uniform(-1, 1)]
                        for _ in range(4)] + [[0, -1, 0]]
            lines.append((name, {"fixture": f, "range": [0, 2], "kinetic_ratio": ratio,
                                 "wrenches": wrenches}))
    return lines


def answers(binary, lines):
    text = "".join(json.dumps({"jsonrpc": "2.0", "id": i, "method": "friction.sweep",
                               "params": p}, separators=(",", ":")) + "\n"
                   for i, (_, p) in enumerate(lines))
    out = subprocess.run([binary], input=text, stdout=subprocess.PIPE, text=True,
                         check=True).stdout
    return out.splitlines()


def differences(a, b, path="", found=None):
    """Where two decoded answers differ: (path, a, b) for numbers, 'shape'
    for anything else."""
    if found is None:
        found = []
    if isinstance(a, bool) or isinstance(b, bool) or a is None or b is None or \
            isinstance(a, str) or isinstance(b, str):
        if a != b:
            found.append((path, a, b, "shape"))
    elif isinstance(a, (int, float)) and isinstance(b, (int, float)):
        if a != b:
            size = max(1.0, abs(a), abs(b))
            found.append((path, a, b, "close" if abs(a - b) <= CLOSE * size else "far"))
    elif isinstance(a, list) and isinstance(b, list):
        if len(a) != len(b):
            found.append((path, len(a), len(b), "shape"))
        else:
            for i, (x, y) in enumerate(zip(a, b)):
                differences(x, y, "%s[%d]" % (path, i), found)
    elif isinstance(a, dict) and isinstance(b, dict):
        if sorted(a) != sorted(b):
            found.append((path, sorted(a), sorted(b), "shape"))
        else:
            for k in a:
                differences(a[k], b[k], path + "." + k, found)
    else:
        found.append((path, type(a).__name__, type(b).__name__, "shape"))
    return found


def main():
    count, seed = 200, 33
    args = sys.argv[1:]
    if "--random" in args:
        count = int(args[args.index("--random") + 1])
    if "--seed" in args:
        seed = int(args[args.index("--seed") + 1])
    for b in (NEW, BASE):
        if not os.path.exists(b):
            sys.exit("compare_sweeps: %s missing (make build/bench/answer build/baseline/answer)" % b)
    rnd = random.Random(seed)
    lines = requests(named_fixtures(count, seed), rnd)
    new, base = answers(NEW, lines), answers(BASE, lines)
    assert len(new) == len(base) == len(lines)
    same = close = 0
    failed = []
    for (name, params), x, y in zip(lines, new, base):
        if x == y:
            same += 1
            continue
        found = differences(json.loads(x), json.loads(y))
        what = [k for k in ("push", "gravity", "wrenches") if k in params][0]
        label = "%s %s %s ratio %g" % (name, what, params.get(what, {}).get("set", "")
                                       if what != "wrenches" else "", params["kinetic_ratio"])
        if all(d[3] == "close" for d in found):
            close += 1
            worst = max(abs(d[1] - d[2]) for d in found)
            print("within 1e-12: %s: %d numbers, largest difference %.3g" % (label, len(found), worst))
        else:
            failed.append(label)
            for d in found[:5]:
                print("DIFFERS: %s: %s: %r against %r (%s)" % (label, d[0], d[1], d[2], d[3]))
    print("%d requests on %d fixtures: %d byte for byte the same, %d within 1e-12, %d differ" % (
        len(lines), len({n for n, _ in lines}), same, close, len(failed)))
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
