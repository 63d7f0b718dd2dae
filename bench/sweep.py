#!/usr/bin/python3
"""bench/sweep.py -- friction.sweep's cost, this build beside the baseline.

    bench/sweep.py [--json] [--quick] [--callgrind]

Answers each request in process (build/bench/answer, wp_answer_line: JSON
in and out, the inline fixture validated each time, no socket) with this
checkout's libraries and with the baseline's (build/baseline/answer, the
revision the Makefile's BASELINE_REVISION names), alternately, and prints
the median wall seconds of each and their ratio; the two answers must be
the same (bench/compare_sweeps.py says how they are compared).  The parts:

  part24-kK   a 24-edge polygon (an irregular ellipse) with K fixels on K
              different edges, K = 3, 6, 8; push sweeps for "goal" and
              "both", over [0, 2];
  gear1000    a 1,000-segment gear with 3 fixels, push "goal".

--callgrind adds each side's instruction count (valgrind's callgrind, one
run), the figure that does not move with the machine's load.
"""
import json
import math
import os
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
NEW = os.path.join(ROOT, "build", "bench", "answer")
BASE = os.path.join(ROOT, "build", "baseline", "answer")


def part24(k):
    """A 24-gon on an irregular ellipse, fixels at the middles of k edges
    spread around it, friction in the fixture (the sweep ignores it)."""
    n = 24
    verts = []
    for i in range(n):
        a = 2 * math.pi * i / n
        r = 1 + 0.08 * math.cos(3 * a) + 0.05 * math.sin(5 * a)
        verts.append([round(40 * r * math.cos(a), 6), round(25 * r * math.sin(a), 6)])
    # Edges for the fixels: a locating corner first (two fixels near edge
    # 0's end and edge 1), then spread.
    order = [0, 1, 7, 13, 18, 4, 10, 21][:k]
    fixels = []
    for j, e in enumerate(order):
        p, q = verts[e], verts[(e + 1) % n]
        t = 0.3 if j % 2 else 0.6
        fixels.append({"at": [p[0] + t * (q[0] - p[0]), p[1] + t * (q[1] - p[1])]})
    return {"name": "part24-k%d" % k, "body": {"mass": 1,
            "shape": {"type": "polygon", "vertices": verts}},
            "friction": {"static": 0.3}, "fixels": fixels}


def gear(segments, k=3):
    """A gear of `segments` straight segments (teeth of 10 segments), three
    fixels on tooth tips."""
    teeth = segments // 10
    verts = []
    for i in range(segments):
        a = 2 * math.pi * i / segments
        phase = i % 10
        r = 50 if phase < 5 else 46
        verts.append([round(r * math.cos(a), 6), round(r * math.sin(a), 6)])
    fixels = []
    for j in range(k):
        e = (j * segments // k) // 10 * 10 + 1
        p, q = verts[e], verts[e + 1]
        fixels.append({"at": [(p[0] + q[0]) / 2, (p[1] + q[1]) / 2]})
    del teeth
    return {"name": "gear%d" % segments, "body": {"mass": 1,
            "shape": {"type": "polygon", "vertices": verts}},
            "friction": {"static": 0.3}, "fixels": fixels}


def request(fixture, params):
    p = dict(params)
    p["fixture"] = fixture
    return json.dumps({"jsonrpc": "2.0", "id": 1, "method": "friction.sweep", "params": p},
                      separators=(",", ":"))


def cases(quick):
    out = []
    for k in (3, 6) if quick else (3, 6, 8):
        for which in ("goal", "both"):
            out.append(("part24 k=%d push %s" % (k, which), part24(k),
                        {"range": [0, 2], "push": {"set": which}}))
    out.append(("gear 1000 segments k=3 push goal", gear(1000),
                {"range": [0, 2], "push": {"set": "goal"}}))
    return out


def timed(binary, line, runs):
    out = subprocess.run([binary, "--time", "--runs", str(runs)], input=line + "\n",
                         stdout=subprocess.PIPE, text=True, check=True).stdout
    seconds, answer = out.split("\t", 1)
    return float(seconds), answer


def instructions(binary, line):
    with tempfile.TemporaryDirectory() as d:
        out = os.path.join(d, "cg.out")
        subprocess.run(["valgrind", "--tool=callgrind", "--callgrind-out-file=" + out, binary],
                       input=line + "\n", stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                       text=True, check=True)
        with open(out) as f:
            for row in f:
                if row.startswith("summary:") or row.startswith("totals:"):
                    return int(row.split()[1])
    return None


def main():
    as_json = "--json" in sys.argv
    quick = "--quick" in sys.argv
    grind = "--callgrind" in sys.argv
    for b in (NEW, BASE):
        if not os.path.exists(b):
            sys.exit("bench/sweep.py: %s missing (make build/bench/answer build/baseline/answer)" % b)
    rows = []
    for name, fixture, params in cases(quick):
        line = request(fixture, params)
        # Repeats alternate the two builds, so that a burst of load falls on both.
        new_t, base_t = [], []
        repeats = 3
        same = True
        for _ in range(repeats):
            t, a_new = timed(NEW, line, 1)
            new_t.append(t)
            slow = base_t and min(base_t) > 20 and len(base_t) >= 1
            if not slow:
                t, a_base = timed(BASE, line, 1)
                base_t.append(t)
                same = same and a_new == a_base
        row = {"case": name, "new_s": sorted(new_t)[len(new_t) // 2],
               "baseline_s": sorted(base_t)[len(base_t) // 2], "same_answer": same}
        row["speedup"] = row["baseline_s"] / row["new_s"]
        if grind:
            row["new_ir"] = instructions(NEW, line)
            row["baseline_ir"] = instructions(BASE, line)
        rows.append(row)
        if not as_json:
            print("%-36s new %8.4f s  baseline %8.3f s  x%7.1f  %s%s" % (
                name, row["new_s"], row["baseline_s"], row["speedup"],
                "same answer" if same else "ANSWERS DIFFER (bench/compare_sweeps.py)",
                "  Ir %.3g / %.3g" % (row["new_ir"], row["baseline_ir"]) if grind else ""),
                flush=True)
    if as_json:
        print(json.dumps({"sweeps": rows}))


if __name__ == "__main__":
    main()
