#!/usr/bin/python3
"""bench/force.py -- magnitudes (force.range, push.force), timed beside a
scripted baseline.

What it measures
    1. force.range for one push and 100 load cases on the 3-2-1 plate
       (three fixels, examples/plate-3-2-1.json), all three sets: the
       round trip of one pre-encoded request line on a Unix socket, median
       of --repeats (and the least, a round trip no other process
       interrupted).  Target: under 1 ms.
    2. push.force on the bracket (examples/bracket-upright.json, an outline
       of 14 lines and arcs, five cutting cases): the round trip, median.
       Target: under 50 ms.
    3. The baseline a user without force.range would script: for each case,
       the least magnitude of `both` found by bisection on F (doubling from
       1 until the push is inside, then 50 halvings), each probe decided by
       scipy.optimize.linprog on every excluded cone (bench/baseline.py's
       LPs, from docs/MODEL.md alone; the cone lists from plan.get and
       modes.get).  Timed per case over --baseline-cases cases (the LPs
       are slow), beside wrenchd's time per case, and the least forces
       compared to 1e-5 (relative): linprog decides a membership to its
       feasibility tolerance, about 1e-7, which moves the bisection's end
       by about 1e-6 of the force.

    Only the requests and the bisection loop are timed; building the cases
    and starting the daemon are not.

How to run it
    /usr/bin/python3 bench/force.py [--repeats 50] [--baseline-cases 5] [--json]

    Starts build/wrenchd on a temporary socket (bench/baseline.py's
    Daemon).  Exit status 0 unless the baseline's least force disagrees
    with wrenchd's beyond 1e-5 (1), or wrenchd cannot be started (3).  Figures only: nothing fails because it is slow.

Needs python3-numpy and python3-scipy.
"""

import argparse
import json
import math
import os
import socket
import statistics
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import baseline as B  # noqa: E402  (its Model, LPs and Daemon)

ROOT = os.path.dirname(HERE)
G = 9.81


def cases_for_plate(n):
    """n cases: gravity down plus a cutter force at a point of the top edge,
    its size and direction varying along the path."""
    out = []
    for i in range(n):
        x = 0.2 + 3.6 * i / max(1, n - 1)
        fx = -2 + 4 * math.sin(i)
        out.append({"name": "c%d" % i,
                    "loads": [{"gravity": {"g": G, "direction_deg": 270}},
                              {"force": [fx, -3 - math.cos(i)], "at": [x, 2]}]})
    return out


def round_trips(path, line, repeats):
    """The median and the least seconds of sending `line` and reading its
    answer (the least: a round trip no other process interrupted, on a
    busy machine the cost itself)."""
    sock = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
    sock.connect(path)
    data = line.encode() + b"\n"
    times, answer = [], b""
    for _ in range(repeats):
        t = time.perf_counter()
        sock.sendall(data)
        buf = b""
        while not buf.endswith(b"\n"):
            buf += sock.recv(1 << 20)
        times.append(time.perf_counter() - t)
        answer = buf
    sock.close()
    result = json.loads(answer)
    if "result" not in result:
        raise SystemExit("wrenchd refused the request: %s" % result.get("error"))
    return statistics.median(times), min(times), result["result"]


def inside_both(model, h, goal, modes, failures, solve):
    """The baseline's verdict: outside every goal cone and every mode."""
    for s in goal:
        if B.contains(model, s, h, False, failures, solve):
            return False
    for s in modes:
        if B.contains(model, s, h, True, failures, solve):
            return False
    return True


def baseline_least(model, load, push, goal, modes):
    """The least F with load + F push inside both, by doubling then bisection;
    None when none is found below 1e6."""
    failures, solve = B.Failures(), [0.0]

    def good(F):
        w = [load[k] + F * push[k] for k in range(3)]
        if not any(w):
            return False
        return inside_both(model, model.scaled_unit(w), goal, modes, failures, solve)

    lo, hi = 0.0, 1.0
    if good(0.0):
        return 0.0
    while not good(hi):
        lo, hi = hi, 2 * hi
        if hi > 1e6:
            return None
    for _ in range(50):
        mid = (lo + hi) / 2
        if good(mid):
            hi = mid
        else:
            lo = mid
    return hi


def load_wrench(model, case):
    w = [0.0, 0.0, 0.0]
    for ld in case["loads"]:
        if "gravity" in ld:
            phi = math.radians(ld["gravity"]["direction_deg"])
            w[0] += model.mass * ld["gravity"]["g"] * math.cos(phi)
            w[1] += model.mass * ld["gravity"]["g"] * math.sin(phi)
        else:
            f, at = ld["force"], ld["at"]
            r = (at[0] - model.com[0], at[1] - model.com[1])
            w[0] += f[0]
            w[1] += f[1]
            w[2] += r[0] * f[1] - r[1] * f[0]
    return w


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--repeats", type=int, default=50)
    ap.add_argument("--baseline-cases", type=int, default=5)
    ap.add_argument("--json", action="store_true")
    args = ap.parse_args(argv)
    with open(os.path.join(ROOT, "examples", "plate-3-2-1.json")) as fh:
        plate = json.load(fh)
    with open(os.path.join(ROOT, "examples", "bracket-upright.json")) as fh:
        bracket = json.load(fh)
    try:
        daemon = B.Daemon()
    except Exception as e:  # noqa: BLE001 (any failure to start is said and ends the run)
        print("bench/force.py: wrenchd did not start: %s" % e, file=sys.stderr)
        return 3
    status = 0
    try:
        client = B.wrenchd.Client(daemon.socket)
        pid = client.call("fixture.put", {"fixture": plate})["id"]
        bid = client.call("fixture.put", {"fixture": bracket})["id"]
        cases = cases_for_plate(100)
        push = {"at": [4, 1.5]}
        line = json.dumps({"jsonrpc": "2.0", "id": 1, "method": "force.range",
                           "params": {"fixture": pid, "push": push, "cases": cases}},
                          separators=(",", ":"))
        range_s, range_min_s, answer = round_trips(daemon.socket, line, args.repeats)
        cuts = [{"name": "x%d" % x, "loads": [{"gravity": {"g": 9810, "direction_deg": 180}},
                                              {"force": [30, -40], "at": [x, 60]}]}
                for x in (20, 40, 60, 80, 100)]
        line = json.dumps({"jsonrpc": "2.0", "id": 2, "method": "push.force",
                           "params": {"fixture": bid, "cases": cuts}}, separators=(",", ":"))
        push_force_s, push_force_min_s, pf = round_trips(daemon.socket, line,
                                                          max(5, args.repeats // 5))

        # The baseline, a few cases.
        model = B.Model(plate)
        goal = client.call("plan.get", {"fixture": pid})["cones"]
        modes = client.call("modes.get", {"fixture": pid})["feasible"]
        # The push's unit wrench: (d, r x d), d = (-1, 0) at (4, 1.5).
        unit = [-1.0, 0.0, 1.5 - model.com[1]]
        n = min(args.baseline_cases, len(cases))
        t = time.perf_counter()
        mine = [baseline_least(model, load_wrench(model, c), unit, goal, modes) for c in cases[:n]]
        baseline_per_case = (time.perf_counter() - t) / n
        agree = 0
        for c, got in zip(answer["cases"][:n], mine):
            least = c["both"]["least"]
            if (least is None) != (got is None):
                status = 1
            elif least is not None and abs(got - least) > 1e-5 * max(1, least):
                status = 1
            else:
                agree += 1
        figures = {
            "force_range_100_cases_ms": range_s * 1e3,
            "force_range_100_cases_least_ms": range_min_s * 1e3,
            "force_range_per_case_us": range_s * 1e6 / 100,
            "push_force_bracket_ms": push_force_s * 1e3,
            "push_force_bracket_least_ms": push_force_min_s * 1e3,
            "push_force_evaluations": pf["evaluations"],
            "baseline_per_case_ms": baseline_per_case * 1e3,
            "speedup_per_case": baseline_per_case / (range_s / 100),
            "baseline_cases_compared": n,
            "baseline_cases_agreeing": agree,
        }
        if args.json:
            print(json.dumps(figures))
        else:
            print("force.range, one push, 100 cases, 3 fixels: %.3f ms (target < 1 ms; "
                  "least %.3f), %.1f us a case" % (figures["force_range_100_cases_ms"],
                                                   figures["force_range_100_cases_least_ms"],
                                                   figures["force_range_per_case_us"]))
            print("push.force, bracket, 5 cases: %.2f ms (target < 50 ms; least %.2f), %d "
                  "evaluations" % (figures["push_force_bracket_ms"],
                                   figures["push_force_bracket_least_ms"], pf["evaluations"]))
            print("baseline (linprog per F, bisection): %.1f ms a case; wrenchd %.1f us a "
                  "case: %.0fx" % (figures["baseline_per_case_ms"],
                                   figures["force_range_per_case_us"],
                                   figures["speedup_per_case"]))
            print("least forces agreeing with the baseline: %d of %d" % (agree, n))
    finally:
        daemon.stop()
    return status


if __name__ == "__main__":
    sys.exit(main())
