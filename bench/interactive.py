#!/usr/bin/python3
"""bench/interactive.py -- the bracket's recompute as the FreeCAD workbench
asks it, end to end through the socket, this build beside the baseline.

    bench/interactive.py [--json] [--repeats N] [--fixture PATH]

One recompute is what the workbench sends when a fixel moves
(clients/freecad/wrench_freecad.py): fixture.put of the fixture; for each
of the three region sets (goal, strong, both) push.regions and the
friction.sweep for its critical mu (push, that set, kinetic ratio from the
fixture's friction); and gravity.sweep of goal.  The fixture is sent
inline, as the workbench sends it, and each recompute moves the second
fixel along its edge by a few thousandths, so that nothing is
answered from a cache a real drag would miss.  Times each request and the
whole recompute with the Python client (its own time included) against
build/wrenchd and against the baseline's daemon (the Makefile's
BASELINE_REVISION), alternating, each first every other time; medians of N
(default 15).
"""
import json
import os
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "clients", "python"))
import wrenchd  # noqa: E402

NEW = os.path.join(ROOT, "build", "wrenchd")
BASE = os.path.join(ROOT, "build", "baseline", "src", "build", "wrenchd")


def start(binary, directory):
    socket = os.path.join(directory, "wrenchd.sock")
    daemon = subprocess.Popen([binary, "--socket", socket, "--log-level", "error"], cwd=directory)
    for _ in range(250):
        if os.path.exists(socket):
            return daemon, socket
        time.sleep(0.02)
    daemon.kill()
    sys.exit("bench/interactive.py: %s did not start" % binary)


def moved(fixture, step):
    """The fixture with its second fixel moved along its edge by `step`
    thousandths (the bracket's sits on the straight bottom edge)."""
    f = json.loads(json.dumps(fixture))
    f["fixels"][1]["at"][0] += 1e-3 * step
    return f


def recompute(client, fixture):
    times = {}
    friction = fixture.get("friction", {})
    mu_s = friction.get("static", 0)
    ratio = friction.get("kinetic", mu_s) / mu_s if mu_s > 0 else 1.0
    start = time.perf_counter()
    client.put_fixture(fixture)
    times["fixture.put"] = time.perf_counter() - start
    for which in ("goal", "strong", "both"):
        t = time.perf_counter()
        client.push_regions(fixture, which)
        times["push.regions " + which] = time.perf_counter() - t
        t = time.perf_counter()
        client.friction_sweep(fixture, push={"set": which}, kinetic_ratio=min(1.0, max(ratio, 1e-9)))
        times["friction.sweep " + which] = time.perf_counter() - t
    t = time.perf_counter()
    client.gravity_sweep(fixture, "goal")
    times["gravity.sweep goal"] = time.perf_counter() - t
    times["recompute"] = time.perf_counter() - start
    return times


def median(values):
    values = sorted(values)
    return values[len(values) // 2]


def main():
    args = sys.argv[1:]
    repeats = int(args[args.index("--repeats") + 1]) if "--repeats" in args else 15
    path = args[args.index("--fixture") + 1] if "--fixture" in args else \
        os.path.join(ROOT, "examples", "bracket.json")
    with open(path) as f:
        fixture = json.load(f)
    for b in (NEW, BASE):
        if not os.path.exists(b):
            sys.exit("bench/interactive.py: %s missing (make all build/baseline/src/build/wrenchd)" % b)
    with tempfile.TemporaryDirectory() as dn, tempfile.TemporaryDirectory() as db:
        dnew, snew = start(NEW, dn)
        dbase, sbase = start(BASE, db)
        try:
            cnew, cbase = wrenchd.Client(snew), wrenchd.Client(sbase)
            runs = {"new": [], "baseline": []}
            for i in range(repeats):
                f = moved(fixture, i % 7)
                # Which goes first alternates: neither always follows the
                # other's heaviest request.
                order = [("new", cnew), ("baseline", cbase)]
                for side, client in order if i % 2 == 0 else order[::-1]:
                    runs[side].append(recompute(client, f))
        finally:
            for d in (dnew, dbase):
                d.terminate()
                d.wait()
    keys = list(runs["new"][0])
    table = {k: {side: median([r[k] for r in runs[side]]) for side in runs} for k in keys}
    if "--json" in args:
        print(json.dumps({"fixture": os.path.basename(path), "repeats": repeats,
                          "median_s": table}))
        return
    print("%s, %d recomputes, medians (ms):" % (os.path.basename(path), repeats))
    for k in keys:
        print("  %-24s new %8.2f   baseline %8.2f" % (k, 1e3 * table[k]["new"],
                                                    1e3 * table[k]["baseline"]))


if __name__ == "__main__":
    main()
