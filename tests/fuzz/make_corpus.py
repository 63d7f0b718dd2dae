#!/usr/bin/python3
"""Write the seed corpus of the libFuzzer targets: tests/fuzz/corpus/
{request,fixture,parse}/, one input per file.  Run from the top of the
repository after make (python3 tests/fuzz/make_corpus.py; fixture ids come from
build/wrenchd); it only adds: a seed already in the corpus (hand-written ones
are named hand-*) is never removed or replaced.

Seeds come from:
  - examples/*.json: each fixture, and requests of every method on it;
  - the README's example requests (and a session of them on one line each);
  - tests/e2e/test_malformed.py: every row of its malformed-input table
    (the raw line; its inline fixture, constraint string or wrench too),
    and the junk lines of test_garbage_bytes_do_not_hurt;
  - tests/e2e/fixtures.py: every fixture builder.
The over-long-line row (2 MiB) is left out: it is far past -max_len, and
tests/e2e/test_framing.py covers line limits."""

import glob
import hashlib
import json
import os
import random
import re
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
OUT = os.path.join(ROOT, "tests", "fuzz", "corpus")
sys.path.insert(0, os.path.join(ROOT, "tests", "e2e"))

try:
    import pytest  # noqa: F401  (test_malformed decorates with it)
except ImportError:  # only its decorators are needed: identity stand-ins
    import types
    _mark = types.SimpleNamespace(parametrize=lambda *a, **k: (lambda f: f))
    sys.modules["pytest"] = types.SimpleNamespace(mark=_mark, fixture=lambda *a, **k: (
        a[0] if a and callable(a[0]) else (lambda f: f)))

import fixtures as FX  # noqa: E402
import test_malformed as TM  # noqa: E402

MAX_LEN = 4096  # the targets' -max_len (tests/fuzz/run-fuzz)


# ---- fixture ids, as wrenchd computes them ---------------------------------------
#
# An id hashes the fixture's explicit form (docs/PROTOCOL.md), whose computed
# values (normals, com, inertia) only the library gives exactly: ask the
# built daemon (build/wrenchd, memory only) rather than redo them here.

_daemon = None


def fixture_id(f):
    global _daemon
    if _daemon is None:
        import atexit
        import socket
        import subprocess
        import tempfile
        import time
        folder = tempfile.mkdtemp(prefix="corpus")
        path = os.path.join(folder, "s")
        process = subprocess.Popen([os.path.join(ROOT, "build", "wrenchd"), "--socket", path,
                                    "--threads", "1", "--log-level", "error"])
        atexit.register(lambda: (process.terminate(), process.wait()))
        for _ in range(200):
            if os.path.exists(path):
                break
            time.sleep(0.05)
        connection = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
        connection.connect(path)
        _daemon = connection.makefile("rwb")
    _daemon.write((request("fixture.put", {"fixture": f}) + "\n").encode())
    _daemon.flush()
    return json.loads(_daemon.readline())["result"]["id"]


# ---- requests --------------------------------------------------------------------

def request(method, params=None, rid=1):
    r = {"jsonrpc": "2.0", "method": method}
    if params is not None:
        r["params"] = params
    if rid is not None:
        r["id"] = rid
    return json.dumps(r, separators=(",", ":"))


def kept_like(k):
    """Some constraint strings of k letters (valid ones and a few others)."""
    return ["s" * k, "m" * k, "u" * k, "n" * k, ("sm" * k)[:k], ("ms" * k)[:k],
            ("lrn" * k)[:k], ("au" * k)[:k]]


written = {"request": 0, "fixture": 0, "parse": 0}
names = set()


def emit(target, name, data):
    """Write a seed, never replacing one: a seed already there under this
    name with other bytes (a README line since changed, say) stays, and
    these bytes go beside it under the name and their hash."""
    if isinstance(data, str):
        data = data.encode()
    if len(data) > MAX_LEN:
        return
    name = re.sub(r"[^A-Za-z0-9_.-]", "_", name)
    path = os.path.join(OUT, target, name)
    assert path not in names, path
    names.add(path)
    if os.path.exists(path):
        with open(path, "rb") as f:
            if f.read() == data:
                return
        path += "-" + hashlib.sha1(data).hexdigest()[:8]
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "wb") as f:
        f.write(data)
    written[target] += 1


def requests_for(name, f):
    k = len(f["fixels"])
    fid = fixture_id(f)
    small = k <= 3
    lines = {
        "put": request("fixture.put", {"fixture": f}),
        "classify": request("wrench.classify", {"fixture": f, "wrenches": [
            [-1, -1, 0], [0, -9.81, 0], {"force": [0, 1], "at": [0, 0]}, [0, 0, 0]]}),
        "classify-both-tolerance": request("wrench.classify", {
            "fixture": f, "wrenches": [[-1, -0.2, 0]], "sets": ["both", "goal"],
            "tolerance": 0.01}),
        "classify-lp": request("wrench.classify", {
            "fixture": f, "wrenches": [[-1, -1, 0], [1, 1, 1]], "method": "lp",
            "sets": ["goal", "strong", "both"]}),
        "cone": request("cone.get", {"fixture": f, "constraints": ("sm" * k)[:k]}),
        "plan": request("plan.get", {"fixture": f}),
        "modes": request("modes.get", {"fixture": f}),
        "push-goal": request("push.regions", {"fixture": f, "set": "goal"}),
        "push-both": request("push.regions", {"fixture": f, "set": "both"}),
        "gravity-strong": request("gravity.sweep", {"fixture": f, "set": "strong"}),
        "margin": request("stability.margin", {"fixture": f, "bias": [0, -9.81, 0]}),
        "margin-force": request("stability.margin", {
            "fixture": f, "bias": {"force": [-1, -1], "at": [0.1, 0.2]}}),
    }
    at = f["fixels"][0]["at"]
    lines["locate"] = request("fixture.locating", {
        "fixture": f, "tolerance": 0.01, "features": [{"name": "hole", "at": at}, {"at": at}],
        "sigma_ratio": 3})
    lines["locate-each"] = request("fixture.locating", {
        "fixture": f, "tolerance": [0.01 * (i + 1) for i in range(k)]})
    # Forces, loads and cases, the fixture's units, the long requests'
    # deadline and the list's pages.
    cases = [{"name": "weight", "loads": [{"gravity": {"g": 9.81, "direction_deg": 270}}]},
             {"loads": [{"force": [0.5, -0.2], "at": at, "name": "cutter"},
                        {"wrench": [0, 0.1, 0.01]}]}]
    lines["force-range-push"] = request("force.range", {
        "fixture": f, "push": {"at": at, "direction": [0, 1]}, "cases": cases,
        "sets": ["goal", "both"], "range": [0, 100]})
    lines["force-range-wrench"] = request("force.range", {
        "fixture": f, "wrench": [-1, -1, 0], "cases": cases[:1]})
    lines["sweep-wrenches-deadline"] = request("friction.sweep", {
        "fixture": f, "wrenches": [[-1, -1, 0], [0, -9.81, 0]], "sets": ["goal", "strong"],
        "range": [0, 1], "kinetic_ratio": 0.8, "deadline_s": 0.5})
    if "shape" in f.get("body", {}):
        lines["push-force"] = request("push.force", {
            "fixture": f, "set": "both", "cases": cases, "finger_radius": 0.01, "samples": 8})
        lines["push-under-force"] = request("push.regions", {
            "fixture": f, "set": "goal", "force": 2, "cases": cases})
        lines["sweep-force"] = request("friction.sweep", {
            "fixture": f, "force": {"set": "both"}, "cases": cases[:1], "range": [0.1, 0.5],
            "deadline_s": 1})
        lines["sweep-push-deadline"] = request("friction.sweep", {
            "fixture": f, "push": {"set": "goal", "finger_radius": 0}, "deadline_s": 0.01})
    with_units = dict(f, units={"length": "mm", "force": "N"})
    lines["put-units"] = request("fixture.put", {"fixture": with_units})
    lines["classify-units"] = request("wrench.classify", {
        "fixture": dict(f, units={"length": "in", "force": "lbf"}),
        "wrenches": [{"force": [0, 1], "at": at}]})
    lines["list-page"] = request("fixture.list", {"after": fid, "limit": 2})
    if small:
        lines["push-friction"] = request("push.regions", {
            "fixture": f, "set": "strong", "finger_friction": 0.2})
    for what, line in lines.items():
        emit("request", "%s-%s" % (name, what), line)
    # A session: put, then everything by id, one request a line.
    session = [request("fixture.put", {"fixture": f}, 1),
               request("wrench.classify", {"fixture": fid, "wrenches": [[-1, -1, 0]]}, 2),
               request("cone.get", {"fixture": fid, "constraints": "m" * k}, 3),
               request("gravity.sweep", {"fixture": fid, "set": "both"}, 4),
               request("push.regions", {"fixture": fid}, 5),
               request("stability.margin", {"fixture": fid, "bias": [1, 0, 0]}, 6),
               request("fixture.get", {"id": fid}, 7),
               request("fixture.list", None, 8),
               request("fixture.delete", {"id": fid}, 9),
               request("fixture.get", {"id": fid}, 10)]
    emit("request", "%s-session" % name, "\n".join(session) + "\n")


def main():
    examples = {}
    for path in sorted(glob.glob(os.path.join(ROOT, "examples", "*.json"))):
        name = "example-" + os.path.basename(path)[:-5]
        with open(path, "rb") as f:
            raw = f.read()
        examples[name] = json.loads(raw)
        emit("fixture", name, raw)

    # The README's requests, one file each, and all of them as a session.
    with open(os.path.join(ROOT, "README.md")) as f:
        readme = [l.strip() for l in f if l.startswith('{"jsonrpc"') and '"method"' in l]
    for i, line in enumerate(readme):
        emit("request", "readme-%02d" % i, line)
    emit("request", "readme-session", "\n".join(readme) + "\n")
    disc = examples["example-disc-corner"]
    assert fixture_id(disc) in "\n".join(readme), "fixture ids are not computed as wrenchd does"

    builders = {
        "disc-corner": FX.disc_corner(), "rectangle-321": FX.rectangle_321(),
        "rectangle-321-cw": FX.rectangle_321(clockwise=True), "chamfered": FX.chamfered_plate(),
        "disc-one": FX.disc_one_fixel(), "offset-disc": FX.offset_disc(),
        "triangle": FX.triangle(), "corner-fixel": FX.corner_fixel_plate(),
        "scaled-disc": FX.scaled_disc_corner(length=1000.0, mass=0.001),
        "square-form-closure": FX.square_form_closure(),
        "disc-8": FX.disc_at_angles([180 + 11 * i for i in range(8)], mu=0.3),
        "disc-5-offset": FX.disc_at_angles([190, 230, 260, 300, 350], com=[0.1, 0.2],
                                           inertia=0.4),
        "moved-plate": FX.moved(FX.rectangle_321(), degrees=30, shift=(5, -2), scale=0.01),
    }
    rnd = random.Random(1)
    for i in range(4):
        builders["random-polygon-%d" % i] = FX.random_polygon(rnd, convex=i % 2 == 0,
                                                              corner=i >= 2)
        builders["random-disc-%d" % i] = FX.random_disc(rnd, corner=i % 2 == 1)
    for name, f in builders.items():
        emit("fixture", "builder-" + name, json.dumps(f))
    # The fixture's units (every pair of a length and a force unit once).
    for i, (length, force) in enumerate([("mm", "N"), ("m", "mN"), ("in", "lbf")]):
        f = list(builders.values())[i]
        emit("fixture", "units-%s-%s" % (length, force),
             json.dumps(dict(f, units={"length": length, "force": force})))
    # Designs with the objectives of forces and accuracy, and a deadline.
    plate = {"mass": 1, "shape": {"type": "polygon", "vertices": [[0, 0], [4, 0], [4, 2], [0, 2]]}}
    design_cases = [{"loads": [{"gravity": {"g": 9.81, "direction_deg": 270}}]}]
    emit("request", "design-force", request("fixture.design", {
        "body": plate, "friction": 0.3, "spacing": 2, "top": 2, "objective": "force",
        "cases": design_cases, "deadline_s": 2}))
    emit("request", "design-pareto", request("fixture.design", {
        "body": plate, "friction": 0.3, "spacing": 2, "top": 3, "objective": "pareto",
        "tolerance": 0.01, "features": [{"at": [2, 1]}], "cases": design_cases,
        "deadline_s": 2}))
    emit("request", "design-accuracy-deadline", request("fixture.design", {
        "body": plate, "friction": 0.3, "spacing": 2, "top": 1, "objective": "accuracy",
        "tolerance": 0.01, "features": [{"name": "bore", "at": [2, 1]}], "deadline_s": 0.001}))
    # A part on a base plate (supports) and a fixture with a geometric
    # tolerance: the fixtures, and the analyses that answer differently on
    # them (docs/PROTOCOL.md, "Supports" and "Tolerance").
    on_plate = dict(FX.rectangle_321(name="plate-on-supports"), supports={
        "points": [[1, 0.5], [3, 0.5], [2, 1.7]], "friction": 0.2, "g": 9.81,
        "down": [{"at": [2, 1], "force": 100}]})
    on_plate_interval = dict(FX.rectangle_321(name="plate-on-buttons"), supports={
        "points": [[0.5, 0.5], [3.5, 0.5], [3.5, 1.5], [0.5, 1.5]],
        "friction": {"static": [0.15, 0.25], "kinetic": 0.1}, "g": 9810},
        units={"length": "mm", "force": "N"})
    toleranced = dict(FX.chamfered_plate(name="chamfer-toleranced"),
                      tolerance={"position": 0.01, "angle": 0.5})
    for name, f in (("supports", on_plate), ("supports-interval", on_plate_interval),
                    ("tolerance", toleranced)):
        emit("fixture", name, json.dumps(f))
        emit("request", name + "-put", request("fixture.put", {"fixture": f}))
        emit("request", name + "-classify", request("wrench.classify", {
            "fixture": f, "wrenches": [[0, -9.81, 0], [1, 0, 0.5]],
            "sets": ["goal", "strong", "both"]}))
        emit("request", name + "-force-range", request("force.range", {
            "fixture": f, "sets": ["goal"], "push": {"at": [4, 0.5]},
            "cases": [{"loads": [{"gravity": {"g": 9.81, "direction_deg": 270}}]}]}))
        emit("request", name + "-push-least", request("push.force", {
            "fixture": f, "set": "goal", "samples": 8,
            "cases": [{"loads": [{"wrench": [0, -1, 0]}]}]}))
        emit("request", name + "-push-force", request("push.regions", {
            "fixture": f, "set": "goal", "force": 50,
            "cases": [{"loads": [{"gravity": {"g": 9.81, "direction_deg": 270}}]}]}))
        emit("request", name + "-margin", request("stability.margin", {
            "fixture": f, "bias": [0, -9.81, 0]}))
        emit("request", name + "-gravity-tilt", request("gravity.sweep", {
            "fixture": f, "set": "goal", "in_plane_g": 2}))
        emit("request", name + "-sweep-over-supports", request("friction.sweep", {
            "fixture": f, "over": "supports", "range": [0, 1],
            "wrenches": [[0, -9.81, 0], [3, 0, 0]]}))
        emit("request", name + "-sweep-force-over-supports", request("friction.sweep", {
            "fixture": f, "over": "supports", "range": [0.1, 0.5], "force": {"set": "goal"},
            "cases": [{"loads": [{"wrench": [0, -1, 0]}]}], "deadline_s": 0.05}))
    for name, f in list(examples.items()) + [("builder-" + n, f) for n, f in builders.items()
                                             if n in ("offset-disc", "triangle", "disc-one",
                                                      "square-form-closure", "disc-8")]:
        requests_for(name, f)

    # The malformed-input table: raw lines, and the parts each target reads.
    for name, raw, code, field, rid in TM.ROWS:
        if name == "over-long-line":
            continue
        emit("request", "malformed-" + name, raw)
        text = raw.decode("latin-1") if isinstance(raw, bytes) else raw
        try:
            r = json.loads(text)
        except ValueError:
            continue
        params = r.get("params") if isinstance(r, dict) else None
        if not isinstance(params, dict):
            continue
        if isinstance(params.get("fixture"), dict):
            doc = json.dumps(params["fixture"], ensure_ascii=False)
            emit("fixture", "malformed-" + name,
                 doc.encode("latin-1") if isinstance(raw, bytes) else doc.encode())
        if isinstance(params.get("constraints"), str):
            k = len(params["fixture"]["fixels"]) if isinstance(params.get("fixture"), dict) else 2
            which = 1 if k == 3 else 0
            emit("parse", "malformed-" + name, bytes([which]) + params["constraints"].encode() +
                 b"\n[-1,-1,0]")
        if "wrenches" in params and isinstance(params["wrenches"], list):
            for i, w in enumerate(params["wrenches"]):
                emit("parse", "malformed-%s-%d" % (name, i),
                     b"\x00ms\n" + json.dumps(w).encode())
    for i, junk in enumerate([b"\x00\x01\x02", b"\xff\xfe\xfd{", b"\r", b"{" * 5000, b"]" * 100]):
        emit("request", "garbage-%d" % i, junk)

    # parse: each fixed fixture with constraint strings and wrenches.
    fixels = [2, 3, 3, 1]  # of the fixtures in tests/fuzz/fuzz_parse.c
    wrenches = ["[-1,-1,0]", "[-1,-0.2,0]", "[0,-9.81,0]", "[0,0,0]", "[1,2,3]",
                '{"force":[0,1],"at":[0,0]}', '{"force":[-1,-1],"at":[1,1]}',
                "[1e308,1e308,-1e308]", "[5e-324,0,0]", "[1,2]", '[1,2,"3"]',
                '{"force":[1,0]}', "[1e999,0,0]", "{}", "null"]
    for which, k in enumerate(fixels):
        for i, c in enumerate(kept_like(k) + ["", "x" * k, "S" * k, "s" * (k + 1), "n" * k + "+"]):
            w = wrenches[(i + which) % len(wrenches)]
            emit("parse", "fixture%d-constraint%02d" % (which, i),
                 bytes([which]) + c.encode() + b"\n" + w.encode())
        for i, w in enumerate(wrenches):
            emit("parse", "fixture%d-wrench%02d" % (which, i), bytes([which]) + b"\n" + w.encode())
    print("corpus: %d request, %d fixture, %d parse seeds added to %s" % (
        written["request"], written["fixture"], written["parse"], os.path.relpath(OUT, ROOT)))


if __name__ == "__main__":
    main()
