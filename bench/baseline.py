#!/usr/bin/python3
"""bench/baseline.py -- what a user without wrenchd would script, timed.

What it measures
    The cost of classifying wrenches for G_goal and G_strong (docs/MODEL.md
    sections 3 and 4) the way a user with Debian's python3-scipy and no wrenchd would:
    for every wrench and every excluded cone, build the membership LP of
    docs/MODEL.md section 2 (Newton-Euler in the scaled, normalised problem of
    section 5, the letter rows of the table, the slack t in [0, 1] for the
    strict rows) and solve it with scipy.optimize.linprog(method="highs").
    A wrench is outside a set as soon as one excluded cone contains it; the
    loop stops at that first cone (a user would), unless --all-cones.

    Only the classification loop is timed: LP build + solve per wrench per
    cone.  Reading the fixture, deriving its centre of mass, inertia and
    normals, generating the wrenches and asking wrenchd are outside the
    timer.

    The LPs are this script's own code, from docs/MODEL.md alone.  The *lists* of
    cones (plan.get's "cones" for G_goal, modes.get's "feasible" moving
    modes for G_strong) come from wrenchd: a user would script the LPs, but
    which strings to test is what wrenchd tells.

    It then asks wrenchd's wrench.classify (method "auto", sets goal and
    strong) for the same wrenches and counts agreement: wrenchd's verdict
    is inside / boundary / outside, the baseline's in / out; boundary
    verdicts are counted apart, every other one must agree.  For every
    wrench wrenchd puts outside, it also checks with its own LP that
    wrenchd's blocking cone does contain the wrench (outside the timer).

How to run it
    /usr/bin/python3 bench/baseline.py [FIXTURE.json] [-n 2000] [--seed 1]
        [--socket PATH] [--wrenchd-us-per-wrench X] [--all-cones] [--json]

    FIXTURE defaults to examples/plate-3-2-1.json.  Without --socket it
    starts build/wrenchd itself (building it with `make all` if missing) on
    a socket in a new temporary directory, with --log-level error, and stops
    it at the end.  With --wrenchd-us-per-wrench X (wrenchd's own figure,
    e.g. from build/wrenchclient-bench) it prints the speed-up baseline / X.
    --json prints one JSON object instead of the text, for a driver script.

    Exit status: 0 when every verdict not on a boundary agrees, 1 when some
    disagree, 2 on a bad command line or fixture, 3 when wrenchd cannot be
    started or reached.

Needs python3, python3-numpy and python3-scipy (Debian; `make deps`).
"""

import argparse
import json
import math
import os
import shutil
import subprocess
import sys
import tempfile
import time

import numpy as np
import scipy
from scipy.optimize import linprog

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "clients", "python"))
import wrenchd  # noqa: E402  (the stdlib client, imported by path)

# docs/MODEL.md section 2: a strict row holds iff the optimum slack t is above this,
# on the scaled, normalised problem (so the threshold is unit-free).
STRICT_EPS = 1e-9


class BadFixture(Exception):
    pass


# ---- the fixture, from docs/MODEL.md section 1 and docs/PROTOCOL.md --------------------

def cross(a, b):
    return a[0] * b[1] - a[1] * b[0]


def polygon_properties(vertices):
    """Signed area, centroid and polar second moment about the origin per
    unit area (uniform density), by the shoelace sums; either orientation."""
    area2 = cx = cy = j = 0.0
    count = len(vertices)
    for i in range(count):
        x0, y0 = vertices[i]
        x1, y1 = vertices[(i + 1) % count]
        w = x0 * y1 - x1 * y0
        area2 += w
        cx += (x0 + x1) * w
        cy += (y0 + y1) * w
        j += w * (x0 * x0 + x0 * x1 + x1 * x1 + y0 * y0 + y0 * y1 + y1 * y1)
    area = area2 / 2
    if area == 0:
        raise BadFixture("body.shape.vertices: zero area")
    centroid = (cx / (6 * area), cy / (6 * area))
    return area, centroid, (j / 12) / area


def inward_normal(shape, at, size):
    """The shape's inward unit normal at a boundary point (docs/PROTOCOL.md:
    an error at a polygon vertex, where the fixture must give it)."""
    if shape["type"] == "circle":
        d = (shape["center"][0] - at[0], shape["center"][1] - at[1])
        length = math.hypot(*d)
        return (d[0] / length, d[1] / length)
    vertices = shape["vertices"]
    area, _, _ = polygon_properties(vertices)
    best = None
    for i in range(len(vertices)):
        a, b = vertices[i], vertices[(i + 1) % len(vertices)]
        d = (b[0] - a[0], b[1] - a[1])
        length2 = d[0] * d[0] + d[1] * d[1]
        s = ((at[0] - a[0]) * d[0] + (at[1] - a[1]) * d[1]) / length2
        s = min(1.0, max(0.0, s))
        dist = math.hypot(a[0] + s * d[0] - at[0], a[1] + s * d[1] - at[1])
        if best is None or dist < best[0]:
            best = (dist, i, s, d, math.sqrt(length2))
    dist, i, s, d, length = best
    if dist > 1e-9 * size:
        raise BadFixture("a fixel is not on the boundary")
    if min(s * length, (1 - s) * length) <= 1e-9 * size:
        raise BadFixture("a fixel at a polygon vertex needs its normal")
    # Inward is to the left of each edge of a counter-clockwise polygon.
    sign = 1.0 if area > 0 else -1.0
    return (-sign * d[1] / length, sign * d[0] / length)


class Model:
    """What the LPs need: m, I, x_c, rho, and per fixel the scaled rows
    N'_i = (n_i, (r_i x n_i)/rho), T'_i = (t_i, (r_i x t_i)/rho) and mu."""

    def __init__(self, fixture):
        body = fixture["body"]
        m = float(body["mass"])
        shape = body.get("shape")
        size = 1.0
        if shape is not None and shape["type"] == "polygon":
            area, centroid, j_origin = polygon_properties(shape["vertices"])
            xs = [v[0] for v in shape["vertices"]]
            ys = [v[1] for v in shape["vertices"]]
            size = math.hypot(max(xs) - min(xs), max(ys) - min(ys))
            # uniform body: I about the centroid by the parallel axes rule
            i_centroid = m * (j_origin - (centroid[0] ** 2 + centroid[1] ** 2))
        elif shape is not None:
            centroid = tuple(shape["center"])
            size = 2 * shape["radius"]
            i_centroid = m * shape["radius"] ** 2 / 2
        else:
            for field in ("com", "inertia"):
                if field not in body:
                    raise BadFixture("body.%s: required without a shape" % field)
        com = tuple(body["com"]) if "com" in body else centroid
        if "inertia" in body:
            inertia = float(body["inertia"])
        else:
            d2 = (com[0] - centroid[0]) ** 2 + (com[1] - centroid[1]) ** 2
            inertia = i_centroid + m * d2               # parallel axes (docs/PROTOCOL.md)
        self.mass, self.inertia, self.com = m, inertia, com
        self.rho = math.sqrt(inertia / m)          # radius of gyration (docs/MODEL.md section 5)
        glob = fixture.get("friction")
        n_rows, t_rows, mu_s, mu_k = [], [], [], []
        for fixel in fixture["fixels"]:
            at = fixel["at"]
            if "normal" in fixel:
                n = fixel["normal"]
                length = math.hypot(n[0], n[1])
                n = (n[0] / length, n[1] / length)
            else:
                if shape is None:
                    raise BadFixture("fixels[].normal: required without a shape")
                n = inward_normal(shape, at, size)
            t = (-n[1], n[0])                      # n turned +90 degrees
            r = (at[0] - com[0], at[1] - com[1])
            n_rows.append((n[0], n[1], cross(r, n) / self.rho))
            t_rows.append((t[0], t[1], cross(r, t) / self.rho))
            friction = fixel.get("friction", glob)
            if friction is None:
                raise BadFixture("friction: required, globally or on every fixel")
            mu_s.append(float(friction["static"]))
            mu_k.append(float(friction.get("kinetic", friction["static"])))
        self.k = len(n_rows)
        self.N = np.array(n_rows)
        self.T = np.array(t_rows)
        self.mu_s, self.mu_k = mu_s, mu_k

    def witness_residual(self, witness):
        """How far a witness of wrenchd's is from this script's Newton-Euler,
        M q = g + sum_i (W_in c_in + W_it c_it), in the scaled metric and
        relative to the largest term: a check on m, I, x_c and the normals
        derived here, independent of the LPs."""
        a = witness.acceleration
        lhs = np.array([self.mass * a[0], self.mass * a[1], self.inertia * a[2] / self.rho])
        g = witness.wrench
        rhs = np.array([g[0], g[1], g[2] / self.rho])
        scale = max(np.abs(lhs).max(), np.abs(rhs).max())
        for i, (cn, ct) in enumerate(witness.forces):
            rhs = rhs + cn * self.N[i] + ct * self.T[i]
            scale = max(scale, abs(cn), abs(ct))
        return float(np.abs(lhs - rhs).max() / scale) if scale > 0 else 0.0

    def scaled_unit(self, wrench):
        """docs/MODEL.md section 5: (f_x, f_y, tau/rho), normalised to length 1."""
        h = np.array([wrench[0], wrench[1], wrench[2] / self.rho])
        return h / np.linalg.norm(h)


# ---- one membership LP (docs/MODEL.md section 2) -------------------------------------
#
# Variables x = (q'_1..3, c_n1, c_t1, ..., c_nk, c_tk, t), where
# q' = m (a_x, a_y, rho alpha): with M = diag(m, m, I) and I = m rho^2, the
# Newton-Euler rows divided through in the scaled metric read
#     q' - sum_i (N'_i c_in + T'_i c_it) = h        (h: the unit scaled wrench)
# and the contact accelerations are a_in = N'_i . q' / m, a_it = T'_i . q' / m,
# so every sign row can be written on N'_i . q' and T'_i . q' directly.
# Rows never mix q' and c (docs/MODEL.md section 2).  Maximise t in [0, 1]: a string
# without strict rows leaves t free, so t* = 1 whenever it is feasible.

def build_lp(model, string, h, strict_s):
    """The LP of one constraint string for the unit scaled wrench h.
    strict_s: `s` is strictly separating (a_n > 0, modes of docs/MODEL.md section 4) rather
    than not approaching (a_n >= 0, the table).  A trailing + or - is a
    pivot (every contact rolling, alpha > 0 or < 0)."""
    pivot = 0
    if string.endswith("+"):
        pivot, string = 1, string[:-1]
    elif string.endswith("-"):
        pivot, string = -1, string[:-1]
    k = model.k
    nvar = 3 + 2 * k + 1
    it = nvar - 1
    a_eq = [np.concatenate(([1.0 if j == r else 0.0 for j in range(3)],
                            np.ravel(np.column_stack((-model.N[:, r], -model.T[:, r]))),
                            [0.0]))
            for r in range(3)]
    b_eq = list(h)
    a_ub, b_ub = [], []
    bounds = [(None, None)] * 3

    def row(q_coeffs=None, t_coeff=0.0, forces=None):
        x = np.zeros(nvar)
        if q_coeffs is not None:
            x[:3] = q_coeffs
        if forces:
            for j, v in forces:
                x[j] = v
        x[it] = t_coeff
        return x

    for i, letter in enumerate(string):
        n_q, t_q = model.N[i], model.T[i]
        cn, ct = 3 + 2 * i, 4 + 2 * i
        if letter in "sau":
            bounds = bounds + [(0, 0), (0, 0)]          # c = 0
            if letter == "s" and strict_s:
                a_ub.append(row(-n_q, 1.0)); b_ub.append(0.0)   # a_n >= t
            elif letter == "s":
                a_ub.append(row(-n_q)); b_ub.append(0.0)        # a_n >= 0
            elif letter == "a":
                a_ub.append(row(n_q, 1.0)); b_ub.append(0.0)    # a_n <= -t
            continue
        if letter not in "lrnm":
            raise ValueError("unknown letter %r in %r" % (letter, string))
        a_eq.append(row(n_q)); b_eq.append(0.0)                 # a_n = 0
        bounds = bounds + [(0, None), (None, None)]             # c_n >= 0
        if letter == "l":
            a_ub.append(row(-t_q, 1.0)); b_ub.append(0.0)       # a_t >= t
            a_eq.append(row(forces=[(ct, 1.0), (cn, model.mu_k[i])]))  # c_t = -mu_k c_n
            b_eq.append(0.0)
        elif letter == "r":
            a_ub.append(row(t_q, 1.0)); b_ub.append(0.0)        # a_t <= -t
            a_eq.append(row(forces=[(ct, 1.0), (cn, -model.mu_k[i])]))  # c_t = +mu_k c_n
            b_eq.append(0.0)
        else:
            if letter == "n":
                a_eq.append(row(t_q)); b_eq.append(0.0)         # a_t = 0
            mu = model.mu_s[i]                                  # |c_t| <= mu_s c_n
            a_ub.append(row(forces=[(ct, 1.0), (cn, -mu)])); b_ub.append(0.0)
            a_ub.append(row(forces=[(ct, -1.0), (cn, -mu)])); b_ub.append(0.0)
    if pivot:
        a_ub.append(row(np.array([0.0, 0.0, -pivot]), 1.0)); b_ub.append(0.0)  # pivot alpha >= t
    bounds = bounds + [(0, 1)]
    cost = np.zeros(nvar)
    cost[it] = -1.0                                             # maximise t
    return (cost, np.array(a_ub) if a_ub else None, np.array(b_ub) if b_ub else None,
            np.array(a_eq), np.array(b_eq), bounds)


class Failures:
    """LPs linprog could not decide (status other than optimal / infeasible)."""

    def __init__(self):
        self.items = []


def contains(model, string, h, strict_s, failures, timer):
    """True iff the wrench (unit scaled h) is in G_string."""
    lp = build_lp(model, string, h, strict_s)
    t0 = time.perf_counter()
    res = linprog(lp[0], A_ub=lp[1], b_ub=lp[2], A_eq=lp[3], b_eq=lp[4], bounds=lp[5],
                  method="highs")
    timer[0] += time.perf_counter() - t0
    if res.status == 2:                    # infeasible: not in the cone
        return False
    if res.status != 0:
        failures.items.append((string, res.status, res.message))
        return False
    return -res.fun > STRICT_EPS


def classify_all(model, wrenches, goal_cones, strong_modes, all_cones):
    """The timed loop.  Returns per wrench (goal blocking string or None,
    strong blocking string or None), LP counts and times."""
    failures = Failures()
    solve = [0.0]
    lps = {"goal": 0, "strong": 0}
    spent = {"goal": 0.0, "strong": 0.0}
    out = []
    wall0, cpu0 = time.perf_counter(), time.process_time()
    for w in wrenches:
        h = model.scaled_unit(w)
        row = []
        for name, cones, strict_s in (("goal", goal_cones, False),
                                      ("strong", strong_modes, True)):
            t0 = time.perf_counter()
            hit = None
            for s in cones:
                lps[name] += 1
                if contains(model, s, h, strict_s, failures, solve):
                    hit = hit or s
                    if not all_cones:
                        break
            spent[name] += time.perf_counter() - t0
            row.append(hit)
        out.append(tuple(row))
    wall = time.perf_counter() - wall0
    cpu = time.process_time() - cpu0
    return out, lps, spent, wall, cpu, solve[0], failures


# ---- wrenchd -------------------------------------------------------------------------

class Daemon:
    """build/wrenchd on a socket in a new temporary directory."""

    def __init__(self):
        binary = os.path.join(ROOT, "build", "wrenchd")
        if not os.access(binary, os.X_OK):
            subprocess.run(["make", "-C", ROOT, "all"], check=True,
                           stdout=sys.stderr, stderr=sys.stderr)
        self.dir = tempfile.mkdtemp(prefix="wrenchd-baseline.")
        self.socket = os.path.join(self.dir, "wrenchd.sock")
        self.proc = subprocess.Popen([binary, "--socket", self.socket, "--log-level", "error"],
                                     stdin=subprocess.DEVNULL)
        deadline = time.monotonic() + 10
        while True:
            try:
                wrenchd.Client(self.socket, timeout=2).status()
                return
            except wrenchd.WrenchdUnavailable:
                if self.proc.poll() is not None or time.monotonic() > deadline:
                    self.stop()
                    raise
                time.sleep(0.05)

    def stop(self):
        if self.proc.poll() is None:
            self.proc.terminate()          # SIGTERM to the one process we started
            try:
                self.proc.wait(10)
            except subprocess.TimeoutExpired:
                self.proc.kill()
                self.proc.wait()
        shutil.rmtree(self.dir, ignore_errors=True)


def shown_path(path):
    """A path inside the repository relative to its root, any other absolute."""
    full = os.path.abspath(path)
    inside = os.path.relpath(full, ROOT)
    return full if inside.startswith(os.pardir) else inside


def raw_classify_seconds(socket_path, fixture, wrenches, repeats=3):
    """wrenchd's own time for the same classify (sets goal and strong, method
    auto, fixture inline), as one request line on a plain socket: from
    writing the line to reading the last byte of the answer, best of
    `repeats`, not parsed (the Python client's decoding of 2000 verdicts
    costs far more than wrenchd's answer and is no part of wrenchd)."""
    import socket
    line = (json.dumps({"jsonrpc": "2.0", "id": 1, "method": "wrench.classify",
                        "params": {"fixture": fixture, "wrenches": wrenches,
                                   "sets": ["goal", "strong"], "method": "auto"}})
            + "\n").encode()
    best = None
    with socket.socket(socket.AF_UNIX, socket.SOCK_STREAM) as s:
        s.settimeout(600)
        s.connect(socket_path)
        for _ in range(repeats):
            t0 = time.perf_counter()
            s.sendall(line)
            tail = b""
            while not tail.endswith(b"\n"):
                chunk = s.recv(1 << 20)
                if not chunk:
                    raise wrenchd.WrenchdUnavailable("wrenchd closed the connection",
                                                     socket_path)
                tail = chunk
            elapsed = time.perf_counter() - t0
            best = elapsed if best is None else min(best, elapsed)
    return best


def random_wrenches(model, count, seed):
    """Directions uniform on the unit sphere of the scaled metric (docs/MODEL.md section 5),
    given to both sides as physical wrenches [f_x, f_y, tau]: the cones are
    cones, so only the direction matters, and the scaled metric makes the
    draw independent of units.  Python floats go over JSON exactly."""
    rng = np.random.default_rng(seed)
    h = rng.standard_normal((count, 3))
    h /= np.linalg.norm(h, axis=1)[:, None]
    return [[float(x), float(y), float(z * model.rho)] for x, y, z in h]


# ---- main ----------------------------------------------------------------------------

def main(argv=None):
    ap = argparse.ArgumentParser(description="Classify wrenches with scipy's linprog, "
                                 "as a user without wrenchd would, and compare with wrenchd.")
    ap.add_argument("fixture", nargs="?", default=os.path.join(ROOT, "examples",
                                                               "plate-3-2-1.json"))
    ap.add_argument("-n", "--wrenches", type=int, default=2000, help="how many (default 2000)")
    ap.add_argument("--seed", type=int, default=1, help="of the random wrenches (default 1)")
    ap.add_argument("--socket", help="a running wrenchd (default: start build/wrenchd)")
    ap.add_argument("--wrenchd-us-per-wrench", type=float, metavar="X",
                    help="wrenchd's figure, for the speed-up")
    ap.add_argument("--all-cones", action="store_true",
                    help="solve every cone's LP, not stopping at the first that holds the wrench")
    ap.add_argument("--json", action="store_true", help="print one JSON object")
    args = ap.parse_args(argv)
    if args.wrenches < 1:
        ap.error("--wrenches must be at least 1")
    try:
        with open(args.fixture) as f:
            fixture = json.load(f)
        model = Model(fixture)
    except (OSError, ValueError, KeyError, TypeError, BadFixture) as e:
        print("baseline: %s: %s" % (args.fixture, e), file=sys.stderr)
        return 2
    wrenches = random_wrenches(model, args.wrenches, args.seed)

    daemon = None
    try:
        if args.socket:
            socket_path = args.socket
        else:
            daemon = Daemon()
            socket_path = daemon.socket
        # The fixture goes inline: it is validated and cached, not stored, so a
        # running daemon given with --socket is left as it was.
        with wrenchd.Client(socket_path, timeout=600) as client:
            goal_cones = client.plan(fixture).cones
            modes = client.modes(fixture)
            verdicts = client.classify(fixture, wrenches, sets=("goal", "strong"),
                                       method="auto")
        wrenchd_wall = raw_classify_seconds(socket_path, fixture, wrenches)
    except (wrenchd.WrenchdUnavailable, subprocess.CalledProcessError, OSError) as e:
        print("baseline: wrenchd: %s" % e, file=sys.stderr)
        return 3
    except wrenchd.WrenchdError as e:
        print("baseline: wrenchd refused the fixture: %s" % e, file=sys.stderr)
        return 2
    finally:
        if daemon:
            daemon.stop()
    strong_modes = modes.feasible

    # ---- the timed loop ----
    ours, lps, spent, wall, cpu, solve, failures = classify_all(
        model, wrenches, goal_cones, strong_modes, args.all_cones)

    # ---- agreement (not timed) ----
    agree = {s: {"agree": 0, "boundary": 0, "disagree": 0} for s in ("goal", "strong")}
    blocking = {s: {"checked": 0, "confirmed": 0} for s in ("goal", "strong")}
    counts = {s: {"inside": 0, "outside": 0} for s in ("goal", "strong")}
    disagreements = []
    scratch, check_failures = [0.0], Failures()
    residual = 0.0
    for i, (w, row, theirs) in enumerate(zip(wrenches, ours, verdicts)):
        h = model.scaled_unit(w)
        for j, name in enumerate(("goal", "strong")):
            hit = row[j]
            counts[name]["outside" if hit else "inside"] += 1
            v = theirs[name]
            if v.verdict == "boundary":
                agree[name]["boundary"] += 1
                continue
            if (v.verdict == "inside") == (hit is None):
                agree[name]["agree"] += 1
            else:
                agree[name]["disagree"] += 1
                disagreements.append({"wrench": w, "index": i, "set": name,
                                      "wrenchd": v.verdict, "margin": v.margin,
                                      "wrenchd_blocking": v.blocking, "baseline_blocking": hit})
            if v.verdict == "outside" and v.blocking:
                # wrenchd's blocking cone must hold the wrench by our own LP too
                blocking[name]["checked"] += 1
                if contains(model, v.blocking, h, name == "strong", check_failures, scratch):
                    blocking[name]["confirmed"] += 1
            if v.witness is not None:
                residual = max(residual, model.witness_residual(v.witness))

    n = args.wrenches
    us = wall / n * 1e6
    lp_total = lps["goal"] + lps["strong"]
    figures = {
        "fixture": fixture.get("name", os.path.basename(args.fixture)),
        "file": shown_path(args.fixture),
        "fixels": model.k,
        "goal_cones": len(goal_cones),
        "strong_cones": len(strong_modes),
        "pinned": modes.pinned,
        "wrenches": n,
        "seed": args.seed,
        "stop_at_first_cone": not args.all_cones,
        "scipy": scipy.__version__,
        "numpy": np.__version__,
        "lps": {"goal": lps["goal"], "strong": lps["strong"], "total": lp_total,
                "without_stopping": n * (len(goal_cones) + len(strong_modes))},
        "lp_failures": len(failures.items),
        "seconds": wall,
        "cpu_seconds": cpu,
        "linprog_seconds": solve,
        "us_per_wrench": us,
        "us_per_wrench_cpu": cpu / n * 1e6,
        "us_per_wrench_goal": spent["goal"] / n * 1e6,
        "us_per_wrench_strong": spent["strong"] / n * 1e6,
        "us_per_lp": wall / lp_total * 1e6,
        "baseline_counts": counts,
        "agreement": agree,
        "blocking_confirmed": blocking,
        "disagreements": disagreements[:20],
        "witness_residual": residual,
        "wrenchd_classify_us_per_wrench_measured": wrenchd_wall / n * 1e6,
        "wrenchd_us_per_wrench": args.wrenchd_us_per_wrench,
        "speedup": (us / args.wrenchd_us_per_wrench) if args.wrenchd_us_per_wrench else None,
        "speedup_measured": us / (wrenchd_wall / n * 1e6),
    }
    ok = all(a["disagree"] == 0 for a in agree.values())
    if args.json:
        print(json.dumps(figures, sort_keys=True))
        return 0 if ok else 1

    p = figures
    print("baseline: %s (%s): fixels %d, %s; cones: goal %d (plan.get), strong %d (modes.get)"
          % (p["fixture"], p["file"], p["fixels"], "pinned" if p["pinned"] else "not pinned",
             p["goal_cones"], p["strong_cones"]))
    print("baseline: %d wrenches, seed %d, directions uniform in the scaled metric; "
          "scipy %s linprog(method=\"highs\"), numpy %s" % (n, args.seed, p["scipy"], p["numpy"]))
    print("baseline: LPs solved: goal %d, strong %d, total %d (%s)"
          % (lps["goal"], lps["strong"], lp_total,
             "--all-cones: every cone of every wrench" if args.all_cones else
             "each set stops at the first cone that holds the wrench, as a user would; "
             "every cone would be %d" % p["lps"]["without_stopping"]))
    print("baseline: classification loop %.2f s wall, %.2f s CPU, %.1f s of it in linprog"
          % (wall, cpu, solve))
    # Wall time is the figure; CPU time shows how much a shared machine took.
    print("baseline: %.0f us per wrench (goal %.0f + strong %.0f; CPU %.0f), %.0f us per LP"
          % (us, p["us_per_wrench_goal"], p["us_per_wrench_strong"], p["us_per_wrench_cpu"],
             p["us_per_lp"]))
    for name in ("goal", "strong"):
        a, c, b = agree[name], counts[name], blocking[name]
        print("baseline: %-6s baseline inside %d, outside %d; wrenchd agrees on %d, boundary %d, "
              "disagrees on %d; wrenchd's blocking cone holds the wrench by our LP: %d of %d"
              % (name, c["inside"], c["outside"], a["agree"], a["boundary"], a["disagree"],
                 b["confirmed"], b["checked"]))
    print("baseline: wrenchd's witnesses satisfy this script's Newton-Euler to %.1e "
          "(relative; checks its mass, inertia, centre of mass and normals)" % residual)
    if failures.items:
        print("baseline: %d LPs linprog did not decide (counted as not containing), first: %r"
              % (len(failures.items), failures.items[0]))
    for d in disagreements[:10]:
        print("baseline: DISAGREE wrench %d %r, %s: wrenchd %s (margin %r, blocking %r), "
              "baseline blocking %r" % (d["index"], d["wrench"], d["set"], d["wrenchd"],
                                        d["margin"], d["wrenchd_blocking"],
                                        d["baseline_blocking"]))
    print("baseline: wrenchd's wrench.classify of the same %d wrenches (goal and strong), one "
          "request line, round trip on a plain socket (best of 3, unparsed): %.1f us per wrench; "
          "%.0fx against that"
          % (n, p["wrenchd_classify_us_per_wrench_measured"], p["speedup_measured"]))
    if args.wrenchd_us_per_wrench:
        print("baseline: speed-up: %.0f us / %.3g us = %.0fx (target >= 500x)"
              % (us, args.wrenchd_us_per_wrench, p["speedup"]))
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
