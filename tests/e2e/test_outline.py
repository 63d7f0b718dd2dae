"""The "outline" shape: loops of lines and arcs, holes, pins in
holes, mass properties, push regions by loop and segment, finger_radius.

Every expected number is derived here, independently of the daemon:

* equivalences: a circle written as two half-circle arcs answers what the
  circle fixture answers (put, classify, push.regions with degrees mapped to
  (segment, fraction), gravity.sweep); a polygon written as an outline of
  straight segments answers what the polygon answers (edge i = segment i);
* closed forms for the mass properties of an annulus, a rounded rectangle,
  a plate with a stadium slot and one with an off-centre hole (derived in
  the docstrings), and outline_model.py's Green's-theorem integrals;
* push regions checked point by point with wrench.classify (the default
  method, by margin, and "lp", by verdict), the push wrench
  w(p) = (nu, (p - x_c) x nu) computed from outline_model.py's geometry;
* the finger's clearance by elementary geometry: a disc of radius r
  touching a side of a 90 degree concave corner from outside the material
  meets the other side when closer than r to the corner, r cot(alpha / 2)
  for a corner of free-space angle alpha; nothing is lost on a convex part;
  a disc fits in a hole (or a concave arc) of radius R iff r <= R;
* ids pinned at their values before the outline existed (commit 0596807,
  computed by building that commit).
"""

import copy
import json
import math
import random
import re

import pytest

import fixtures as FX
import helpers as H
import model as M
import outline_model as O
from conftest import FIGURES, Harness, _require_binary

SETS = ("goal", "strong", "both")
CLASSIFY_TOL = 1e-9
SKIP = 1e-7          # of a segment's t range: probes this near an endpoint go either way
NEAR = 1e-6          # probes just inside / outside an endpoint
LP_SKIP = 1e-5       # the lp method decides strict rows by a slack above 1e-9


def count(key, n=1):
    FIGURES[key] = FIGURES.get(key, 0) + n


# One daemon for the whole module (these tests store nothing they read back
# from another test, and a daemon per test costs most of the time under
# ASan); its exit status and stderr are checked when the module ends.

@pytest.fixture(scope="module")
def shared_daemon():
    _require_binary()
    h = Harness()
    d = h.start()
    yield d
    h.cleanup()


@pytest.fixture
def client(shared_daemon):
    c = shared_daemon.client()
    yield c
    c.close()
    shared_daemon.clients.remove(c)


# ---- plumbing -------------------------------------------------------------------

def outline_fixture(loops, fixels, mu=0.3, mass=1.0, com=None, inertia=None, name=None):
    body = {"mass": mass, "shape": {"type": "outline", "loops": loops}}
    if com is not None:
        body["com"] = list(com)
    if inertia is not None:
        body["inertia"] = inertia
    f = {"body": body, "friction": {"static": mu}, "fixels": fixels}
    if name is not None:
        f["name"] = name
    return f


def as_outline(fixture, loops):
    f = copy.deepcopy(fixture)
    f["body"]["shape"] = {"type": "outline", "loops": loops}
    return f


def put(client, fixture):
    r = client.result("fixture.put", {"fixture": fixture})
    return r


def error_of(client, method, params, code=-32602):
    e = client.error(method, params)
    assert e["code"] == code, e
    assert isinstance(e.get("data"), dict) and set(e["data"]) == {"field", "reason"}, e
    assert isinstance(e["data"]["reason"], str) and e["data"]["reason"], e
    return e["data"]["field"], e["data"]["reason"]


def regions(client, fixture, which=None, finger_radius=None):
    params = {"fixture": fixture}
    if which is not None:
        params["set"] = which
    if finger_radius is not None:
        params["finger_radius"] = finger_radius
    return client.result("push.regions", params)


def as_intervals(res):
    """(loop, segment, t0, t1) of an answer; a polygon's or circle's edge e
    is (0, e)."""
    out = []
    for r in res["regions"]:
        if "loop" in r:
            out.append((r["loop"], r["segment"], r["t0"], r["t1"]))
        else:
            out.append((0, r["edge"], r["t0"], r["t1"]))
    return out


def same_intervals(a, b, tol):
    return len(a) == len(b) and all(
        x[0] == y[0] and x[1] == y[1] and abs(x[2] - y[2]) <= tol and abs(x[3] - y[3]) <= tol
        for x, y in zip(a, b))


def margins(client, fixture, wrenches, sets, method=None):
    """[{set: value}] for many wrenches, a few thousand per request."""
    out = []
    for i in range(0, len(wrenches), 4000):
        part = [list(w) for w in wrenches[i:i + 4000]]
        params = {"fixture": fixture, "wrenches": part, "sets": list(sets)}
        if method is not None:
            params["method"] = method
        res = client.result("wrench.classify", params)
        assert len(res["results"]) == len(part)
        out += res["results"]
        count("classified wrenches", len(part))
    return out


def rel_close(a, b, tol=1e-12):
    return abs(a - b) <= tol * max(1.0, abs(a), abs(b))


def check_outline_answer(ol, res):
    """The form of push.regions on an outline: every region's from / to /
    length recomputed from the geometry, ordered, disjoint; total_length the
    sum; fraction total over the perimeter of every loop."""
    assert set(res) == {"regions", "total_length", "fraction", "exact", "resolution"} | (
        set() if res["regions"] else {"why_empty"}), res
    size = max(1.0, math.sqrt(abs(ol.area)))
    out = []
    total = 0.0
    for r in res["regions"]:
        assert set(r) == {"loop", "segment", "from", "to", "t0", "t1", "length"}, r
        lp, sg, t0, t1 = r["loop"], r["segment"], r["t0"], r["t1"]
        assert isinstance(lp, int) and 0 <= lp < len(ol.loops), r
        assert isinstance(sg, int) and 0 <= sg < len(ol.loops[lp]), r
        assert 0 <= t0 < t1 <= 1, r
        s = ol.segment(lp, sg)
        assert H.vec_close(r["from"], s.point(t0), 1e-9 * size), (r, s.point(t0))
        assert H.vec_close(r["to"], s.point(t1), 1e-9 * size), (r, s.point(t1))
        length = s.length * (t1 - t0)
        assert H.close(r["length"], length, 1e-9 * size), (r, length)
        total += length
        out.append((lp, sg, t0, t1))
    assert out == sorted(out), ("regions not ordered by loop, segment, t0", out)
    for a, b in zip(out, out[1:]):
        if a[:2] == b[:2]:
            assert a[3] <= b[2], ("overlapping regions", a, b)
    assert H.close(res["total_length"], total, 1e-9 * size * (1 + len(out))), (res, total)
    assert H.close(res["fraction"], total / ol.perimeter(), 1e-9), (res, total / ol.perimeter())
    return out


def inside_of(iv, lp, sg, t):
    return any(a == lp and b == sg and t0 < t < t1 for a, b, t0, t1 in iv)


def near_end(iv, lp, sg, t, pad):
    return any(a == lp and b == sg and (abs(t - t0) <= pad or abs(t - t1) <= pad)
               for a, b, t0, t1 in iv)


def check_pointwise(client, fixture, ol, com, sets=SETS, per_segment=120, lp_every=0,
                    model_points=0, seed=0):
    """push.regions of `fixture` (an outline) against wrench.classify at
    dense points of every segment of every loop, just inside and just
    outside every endpoint, and at the endpoints inside a segment (margin 0).
    With `lp_every`, every lp_every-th point (away from endpoints) is also
    classified with method "lp", whose verdict must be "inside" exactly in
    the regions.  With `model_points`, that many points of each set are
    checked against model.py's margins too (the fixture made explicit with
    this module's normals, com and inertia).  Returns {set: intervals}."""
    rnd = random.Random(seed)
    found = {}
    jobs = []
    for which in sets:
        iv = check_outline_answer(ol, regions(client, fixture, which))
        found[which] = iv
        pts = []
        for lp, segs in enumerate(ol.loops):
            for sg in range(len(segs)):
                for j in range(per_segment):
                    pts.append((lp, sg, (j + rnd.uniform(0.05, 0.95)) / per_segment))
        ends = []
        for lp, sg, t0, t1 in iv:
            if t1 - t0 > 4 * NEAR:
                pts += [(lp, sg, t0 + NEAR), (lp, sg, t1 - NEAR)]
            pts.append((lp, sg, 0.5 * (t0 + t1)))
            for t in (t0 - NEAR, t1 + NEAR):
                if 0 < t < 1:
                    pts.append((lp, sg, t))
            for t in (t0, t1):
                if 0 < t < 1:
                    ends.append((lp, sg, t))
        pts = [(lp, sg, t, inside_of(iv, lp, sg, t)) for lp, sg, t in pts
               if not near_end(iv, lp, sg, t, SKIP)]
        jobs.append((which, iv, pts, ends))
    wrenches = []
    for which, iv, pts, ends in jobs:
        wrenches += [ol.push_wrench(com, lp, sg, t) for lp, sg, t, _ in pts]
        wrenches += [ol.push_wrench(com, lp, sg, t) for lp, sg, t in ends]
    answers = margins(client, fixture, wrenches, sets)
    at = 0
    lp_pts = []
    for which, iv, pts, ends in jobs:
        bad = []
        for (lp, sg, t, inside), a in zip(pts, answers[at:at + len(pts)]):
            m = a[which]["margin"]
            assert a[which]["inside"] is (a[which]["verdict"] == "inside"), a
            if inside and not m > CLASSIFY_TOL:
                bad.append(("in a region, margin %.3g" % m, lp, sg, t))
            if not inside and not m <= CLASSIFY_TOL:
                bad.append(("in no region, margin %.3g" % m, lp, sg, t))
        assert not bad, "set %s: regions %r disagree with classify at %d of %d points: %r" % (
            which, iv, len(bad), len(pts), bad[:10])
        at += len(pts)
        for (lp, sg, t), a in zip(ends, answers[at:at + len(ends)]):
            assert abs(a[which]["margin"]) < 1e-9, (
                "set %s: margin %.3g at the endpoint loop %d segment %d t %r of %r" % (
                    which, a[which]["margin"], lp, sg, t, iv))
        at += len(ends)
        count("outline push points", len(pts))
        count("outline push endpoints", len(ends))
        if lp_every:
            lp_pts += [(which, p) for p in pts[::lp_every]
                       if not near_end(iv, p[0], p[1], p[2], LP_SKIP)]
    if lp_pts:
        ws = [ol.push_wrench(com, lp, sg, t) for _, (lp, sg, t, _) in lp_pts]
        res = []
        for which in sets:
            idx = [i for i, (w, _) in enumerate(lp_pts) if w == which]
            got = margins(client, fixture, [ws[i] for i in idx], [which], method="lp")
            res += [(lp_pts[i], g[which]) for i, g in zip(idx, got)]
        bad = []
        for (which, (lp, sg, t, inside)), v in res:
            assert v["margin"] is None, v
            if inside != (v["verdict"] == "inside"):
                bad.append((which, lp, sg, t, inside, v["verdict"]))
        assert not bad, "lp verdicts disagree with the regions at %d of %d points: %r" % (
            len(bad), len(res), bad[:10])
        count("outline push points by lp", len(res))
    if model_points:
        explicit = explicit_fixture(fixture, ol, com)
        mdl = M.Model(explicit)
        cl = M.Classifier(mdl)
        at = 0
        for which, iv, pts, ends in jobs:
            ms = answers[at:at + len(pts)]
            at += len(pts) + len(ends)
            if which == "both":
                continue
            picks = rnd.sample(range(len(pts)), min(model_points, len(pts)))
            for i in picks:
                lp, sg, t, _ = pts[i]
                exp = cl.classify(ol.push_wrench(com, lp, sg, t), which).margin
                assert H.close(ms[i][which]["margin"], exp, H.MARGIN_TOL), (
                    which, lp, sg, t, ms[i][which]["margin"], exp)
                count("outline push points against the model")
    intersect = sorted((a, b, max(s0, u0), min(s1, u1))
                       for a, b, s0, s1 in found.get("goal", [])
                       for c, d, u0, u1 in found.get("strong", [])
                       if (a, b) == (c, d) and max(s0, u0) < min(s1, u1))
    if set(SETS) <= set(found):
        assert same_intervals(found["both"], intersect, 1e-9), ("both != goal and strong", found)
    return found


def locate(ol, p, tol=1e-9):
    """(loop, segment, t) of a boundary point p, 0 <= t <= 1 (a vertex is
    the end of the segment before it or the start of the next)."""
    for lp, segs in enumerate(ol.loops):
        for sg, s in enumerate(segs):
            if s.arc:
                d = math.hypot(p[0] - s.center[0], p[1] - s.center[1])
                if abs(d - s.radius) > tol * max(1, s.radius):
                    continue
                a = math.atan2(p[1] - s.center[1], p[0] - s.center[0])
                da = ((a - s.a0) * (1 if s.theta > 0 else -1)) % (2 * math.pi)
                if 2 * math.pi - da < 1e-12:
                    da = 0.0
                t = da / abs(s.theta)
                if t <= 1 + 1e-12:
                    return lp, sg, min(t, 1.0)
            else:
                dx, dy = s.p1[0] - s.p0[0], s.p1[1] - s.p0[1]
                L2 = dx * dx + dy * dy
                t = ((p[0] - s.p0[0]) * dx + (p[1] - s.p0[1]) * dy) / L2
                q = s.point(t)
                if -1e-12 <= t <= 1 + 1e-12 and \
                        math.hypot(q[0] - p[0], q[1] - p[1]) <= tol * math.sqrt(L2):
                    return lp, sg, min(max(t, 0.0), 1.0)
    raise AssertionError("%r is not on the outline" % (p,))


def explicit_fixture(fixture, ol, com):
    """The fixture with com, inertia and every normal written out from this
    module's geometry, and no shape (model.py then needs none)."""
    f = copy.deepcopy(fixture)
    body = f["body"]
    body.pop("shape")
    body["inertia"] = body.get("inertia", ol.inertia(body["mass"], com))
    body["com"] = list(com)
    for fx in f["fixels"]:
        if "normal" not in fx:
            lp, sg, t = locate(ol, fx["at"])
            fx["normal"] = list(ol.inward_normal(lp, sg, t))
    return f


# ---- 1. a circle written as two half-circle arcs ----------------------------------

CIRCLES = [
    dict(center=(0.0, 0.0), radius=1.0, phase=0.0, ccw=True, angles=[180, 270], mu=0.5),
    dict(center=(0.0, 0.0), radius=1.0, phase=0.0, ccw=False, angles=[180, 270], mu=0.5),
    dict(center=(1.5, -0.7), radius=2.3, phase=37.0, ccw=True, angles=[100, 215, 330], mu=0.2),
    dict(center=(1.5, -0.7), radius=2.3, phase=37.0, ccw=False, angles=[100, 215, 330], mu=0.2),
    dict(center=(-3.0, 2.0), radius=0.4, phase=200.0, ccw=False, angles=[20, 140], mu=0.3,
         com=(-2.9, 2.05), inertia=0.05, mass=2.0),
    dict(center=(0.0, 0.0), radius=1.0, phase=90.0, ccw=True, angles=[135, 225], mu=0.3),
    dict(center=(0.25, 0.5), radius=3.0, phase=-60.0, ccw=True, angles=[10, 80, 250], mu=0.1),
]


def circle_arcs(intervals_deg):
    """Open arcs (start, length) in degrees, start in [0, 360), pieces that
    meet merged (also across 360 = 0)."""
    arcs = sorted(((a % 360.0, b - a) for a, b in intervals_deg), key=lambda x: x[0])
    merged = []
    for s, L in arcs:
        if merged and abs(merged[-1][0] + merged[-1][1] - s) <= 1e-9:
            merged[-1] = (merged[-1][0], merged[-1][1] + L)
        else:
            merged.append((s, L))
    if len(merged) > 1 and abs(merged[-1][0] + merged[-1][1] - 360.0 - merged[0][0]) <= 1e-9:
        s, L = merged.pop()
        merged[0] = (s, L + merged[0][1])
    return merged


def outline_circle_degrees(iv, phase, ccw):
    """(segment, t) of the two-arc circle back to boundary angles: CCW
    segment s covers phase + 180 s + 180 t; CW, phase - 180 s - 180 t."""
    out = []
    for lp, sg, t0, t1 in iv:
        assert lp == 0 and sg in (0, 1), iv
        if ccw:
            out.append((phase + 180 * sg + 180 * t0, phase + 180 * sg + 180 * t1))
        else:
            out.append((phase - 180 * sg - 180 * t1, phase - 180 * sg - 180 * t0))
    return out


@pytest.mark.parametrize("case", range(len(CIRCLES)))
def test_circle_as_two_arcs(client, case):
    """A circle of radius R about c is the outline [[c + R u(phi), +-1],
    [c + R u(phi +- 180), +-1]] (bulge 1 = tan(180 / 4): half circles).  Its
    area pi R^2, centroid c, inertia m R^2 / 2 (when left out) are the
    circle's; each fixel's derived normal is radial, so the cones are the
    circle's to rounding: the same cone counts, margins, regions (degrees
    mapped to (segment, fraction of 180 degrees)), gravity arcs, total
    length and fraction."""
    k = CIRCLES[case]
    circ = FX.disc_at_angles(k["angles"], mu=k["mu"], radius=k["radius"], center=k["center"],
                             com=k.get("com"), inertia=k.get("inertia"),
                             mass=k.get("mass", 1.0))
    loop = O.circle_loop(k["center"], k["radius"], k["phase"], k["ccw"])
    outl = as_outline(circ, [loop])
    pc, po = put(client, circ), put(client, outl)
    for key in ("fixels", "goal_cones", "strong_cones", "pinned"):
        assert pc[key] == po[key], (key, pc, po)
    R = k["radius"]
    m = k.get("mass", 1.0)
    assert rel_close(po["area"], math.pi * R * R), po
    assert rel_close(pc["area"], math.pi * R * R), pc
    com = k.get("com", k["center"])
    assert H.vec_close(po["com"], com, 1e-12 * (R + abs(com[0]) + abs(com[1]))), po
    assert H.vec_close(pc["com"], com, 1e-12 * (R + abs(com[0]) + abs(com[1]))), pc
    inertia = k.get("inertia", m * R * R / 2)
    assert rel_close(po["inertia"], inertia), po
    assert rel_close(pc["inertia"], inertia), pc
    # the derived normals: towards the centre
    go = client.result("fixture.get", {"id": po["id"]})
    for fx in go["fixels"]:
        u = M.unit(M.sub(k["center"], fx["at"]))
        assert H.vec_close(fx["normal"], u, 1e-12), (fx, u)
    # classify: the same margins
    ws = H.random_wrenches(100 + case, 200, scale=(1.0, 1.0, R))
    a, b = margins(client, circ, ws, ("goal", "strong")), margins(client, outl, ws,
                                                                  ("goal", "strong"))
    for g, x, y in zip(ws, a, b):
        for s in ("goal", "strong"):
            assert abs(x[s]["margin"] - y[s]["margin"]) <= 1e-9, (g, s, x, y)
            if abs(x[s]["margin"]) > 1e-7:
                assert x[s]["verdict"] == y[s]["verdict"], (g, s, x, y)
                assert x[s]["blocking"] == y[s]["blocking"], (g, s, x, y)
    # regions and gravity
    ol = O.Outline(outl["body"]["shape"])
    for which in SETS:
        rc, ro = regions(client, circ, which), regions(client, outl, which)
        ivo = check_outline_answer(ol, ro)
        degc = circle_arcs([(t0, t1) for _, _, t0, t1 in as_intervals(rc)])
        dego = circle_arcs(outline_circle_degrees(ivo, k["phase"], k["ccw"]))
        assert len(degc) == len(dego), (which, degc, dego, rc, ro)
        for (s0, l0), (s1, l1) in zip(degc, dego):
            full = l0 >= 360 - 1e-9     # the whole circle: no start to compare
            assert (full or abs((s0 - s1 + 180) % 360 - 180) <= 1e-9) and \
                abs(l0 - l1) <= 1e-9, (which, degc, dego)
        assert abs(rc["total_length"] - ro["total_length"]) <= 1e-12 * R * 10, (rc, ro)
        assert abs(rc["fraction"] - ro["fraction"]) <= 1e-12 * 10, (rc, ro)
        gc = client.result("gravity.sweep", {"fixture": circ, "set": which})["intervals_deg"]
        go_ = client.result("gravity.sweep", {"fixture": outl, "set": which})["intervals_deg"]
        assert len(gc) == len(go_) and all(
            abs(x - y) <= 1e-9 for p, q in zip(gc, go_) for x, y in zip(p, q)), (which, gc, go_)
    check_pointwise(client, outl, ol, com, per_segment=90, seed=case)


# ---- 2. a polygon written as an outline of straight segments ---------------------

def polygon_cases():
    out = [("rect-321", FX.rectangle_321(0.3)),
           ("rect-321-cw", FX.rectangle_321(0.3, clockwise=True)),
           ("chamfer", FX.chamfered_plate()),
           ("triangle", FX.triangle()),
           ("corner-fixel", FX.corner_fixel_plate()),
           ("plate-3-2-1.json", None)]
    for seed in range(4):
        rnd = random.Random(7000 + seed)
        out.append(("random-%d" % seed, FX.random_polygon(rnd, convex=seed % 2 == 0,
                                                         corner=True)))
    return out


POLYGONS = polygon_cases()


@pytest.mark.parametrize("case", [c for c, _ in POLYGONS])
def test_polygon_as_outline(client, case):
    """Vertices [x, y] (bulge absent) or [x, y, 0] are straight segments:
    the outline is the polygon, segment i its edge i.  Same cones, margins,
    area / com / inertia (against model.py's shoelace formulas too),
    regions (edge i -> loop 0 segment i, the same t to 1e-12), gravity; and
    [x, y] and [x, y, 0] are one fixture (one id)."""
    poly = dict(POLYGONS)[case]
    if poly is None:
        import os
        with open(os.path.join(os.path.dirname(__file__), "..", "..", "examples",
                               case)) as f:
            poly = json.load(f)
    verts = poly["body"]["shape"]["vertices"]
    outl = as_outline(poly, [verts])
    outl0 = as_outline(poly, [[[v[0], v[1], 0] for v in verts]])
    pp, po, po0 = put(client, poly), put(client, outl), put(client, outl0)
    assert po["id"] == po0["id"], (po, po0)
    for key in ("fixels", "goal_cones", "strong_cones", "pinned"):
        assert pp[key] == po[key], (key, pp, po)
    signed, centroid, polar = M.polygon_moments([tuple(map(float, v)) for v in verts])
    mdl = M.Model(poly)
    size = max(abs(x) for v in verts for x in v) + 1
    for r in (pp, po):
        assert rel_close(r["area"], abs(signed), 1e-12), (r, signed)
        assert H.vec_close(r["com"], mdl.com, 1e-12 * size), (r, mdl.com)
        assert rel_close(r["inertia"], mdl.inertia, 1e-12), (r, mdl.inertia)
    ws = H.random_wrenches(300, 200, scale=(1.0, 1.0, size))
    a, b = margins(client, poly, ws, SETS), margins(client, outl, ws, SETS)
    for g, x, y in zip(ws, a, b):
        for s in SETS:
            assert abs(x[s]["margin"] - y[s]["margin"]) <= 1e-12, (g, s, x, y)
    ol = O.Outline(outl["body"]["shape"])
    for which in SETS:
        rp, ro = regions(client, poly, which), regions(client, outl, which)
        ivo = check_outline_answer(ol, ro)
        ivp = as_intervals(rp)
        assert same_intervals(ivp, ivo, 1e-12), (which, ivp, ivo)
        assert abs(rp["total_length"] - ro["total_length"]) <= 1e-12 * size, (rp, ro)
        assert abs(rp["fraction"] - ro["fraction"]) <= 1e-12, (rp, ro)
        assert regions(client, outl0, which) == ro
        gp = client.result("gravity.sweep", {"fixture": poly, "set": which})
        assert client.result("gravity.sweep", {"fixture": outl, "set": which}) == gp or all(
            abs(x - y) <= 1e-12 for p, q in zip(
                gp["intervals_deg"],
                client.result("gravity.sweep", {"fixture": outl, "set": which})["intervals_deg"])
            for x, y in zip(p, q))


# ---- 3. mass properties against closed forms ---------------------------------------

def annulus_case(R, r, c, outer_ccw, hole_ccw, mass=2.0):
    """Area pi (R^2 - r^2); centroid c; polar moment about c of a ring is
    (pi/2)(R^4 - r^4), per unit area (R^2 + r^2) / 2: I = m (R^2 + r^2) / 2."""
    loops = [O.circle_loop(c, R, 30.0, outer_ccw), O.circle_loop(c, r, -75.0, hole_ccw)]
    fixels = [{"at": [c[0], c[1] - R]}, {"at": [c[0] - R, c[1]]}]
    f = outline_fixture(loops, fixels, mass=mass)
    return f, math.pi * (R * R - r * r), c, mass * (R * R + r * r) / 2


def rounded_rectangle_props(w, h, f):
    """A w x h rectangle about the origin with corner fillets of radius f.

    Area: the rectangle less, at each corner, an f x f square less a
    quarter disc: w h - 4 (f^2 - pi f^2 / 4) = w h - (4 - pi) f^2.

    Polar moment about the origin: the rectangle's w h (w^2 + h^2) / 12
    less four times (the corner square less its quarter disc).  With
    a = w/2 - f, c = h/2 - f the top right square [a, a+f] x [c, c+f] has
    J_sq = f ((a+f)^3 - a^3) / 3 + f ((c+f)^3 - c^3) / 3; the quarter disc
    centred (a, c) has, with u = x - a, v = y - c over it,
    int (u^2 + v^2) = pi f^4 / 8, int u = int v = f^3 / 3, so
    J_qd = pi f^4 / 8 + 2 a f^3 / 3 + 2 c f^3 / 3 + (a^2 + c^2) pi f^2 / 4.
    By symmetry the centroid is the origin and the four corners alike."""
    a, c = w / 2 - f, h / 2 - f
    area = w * h - (4 - math.pi) * f * f
    j_rect = w * h * (w * w + h * h) / 12
    j_sq = f * ((a + f) ** 3 - a ** 3) / 3 + f * ((c + f) ** 3 - c ** 3) / 3
    j_qd = math.pi * f ** 4 / 8 + 2 * a * f ** 3 / 3 + 2 * c * f ** 3 / 3 + \
        (a * a + c * c) * math.pi * f * f / 4
    return area, j_rect - 4 * (j_sq - j_qd)


def stadium_props(straight, rho):
    """A stadium (straight part L between half discs of radius rho) about
    its centre: area 2 rho L + pi rho^2; polar moment: the L x 2 rho
    rectangle's 2 rho L (L^2 + 4 rho^2) / 12, plus two half discs centred at
    (+-L/2, 0), each pi rho^4 / 4 about its own centre, its first moment
    along x (outward) 2 rho^3 / 3 and area pi rho^2 / 2:
    pi rho^4 / 4 + L (2 rho^3 / 3) + (L^2 / 4)(pi rho^2 / 2)."""
    L = straight
    area = 2 * rho * L + math.pi * rho * rho
    j = 2 * rho * L * (L * L + 4 * rho * rho) / 12 + \
        2 * (math.pi * rho ** 4 / 4 + L * 2 * rho ** 3 / 3 + L * L * math.pi * rho * rho / 8)
    return area, j


def plate_minus(W, Hh, holes):
    """A W x H plate centred at the origin less holes given as (area, centre,
    polar moment about their own centroid): area, centroid and polar moment
    about the centroid, by the parallel-axis theorem."""
    area = W * Hh
    sx = sy = 0.0
    j = W * Hh * (W * W + Hh * Hh) / 12
    for a, (x, y), jc in holes:
        area -= a
        sx -= a * x
        sy -= a * y
        j -= jc + a * (x * x + y * y)
    cx, cy = sx / area, sy / area
    return area, (cx, cy), j - area * (cx * cx + cy * cy)


def mass_cases():
    out = []
    for oc, hc in ((True, False), (True, True), (False, False), (False, True)):
        f, a, c, i = annulus_case(2.0, 0.75, (0.5, -1.0), oc, hc)
        out.append(("annulus-%d%d" % (oc, hc), f, a, c, i))
    f, a, c, i = annulus_case(1e3, 999.0, (-20.0, 3.0), True, False, mass=5.0)
    out.append(("thin-ring", f, a, c, i))
    for w, h, fl in ((6.0, 4.0, 1.0), (3.0, 2.0, 0.25), (2.0, 2.0, 0.999)):
        area, j = rounded_rectangle_props(w, h, fl)
        loop = O.rounded_rectangle(w, h, fl)
        fixels = [{"at": [0.0, -h / 2]}, {"at": [-w / 2, 0.0]}]
        for rev in (False, True):
            f = outline_fixture([O.reverse_loop(loop) if rev else loop], fixels, mass=3.0)
            out.append(("rounded-%g-%g-%g-%d" % (w, h, fl, rev), f, area, (0.0, 0.0),
                        3.0 * j / area))
    # a slotted plate: 8 x 5 less a stadium slot at (1.5, 0.75), straight 2, radius 0.6
    sa, sj = stadium_props(2.0, 0.6)
    area, com, j = plate_minus(8.0, 5.0, [(sa, (1.5, 0.75), sj)])
    for rev in (False, True):
        slot = O.stadium((1.5, 0.75), 2.0, 0.6)
        loops = [O.rectangle(-4, -2.5, 4, 2.5), O.reverse_loop(slot) if rev else slot]
        f = outline_fixture(loops, [{"at": [0.0, -2.5]}, {"at": [-4.0, 0.0]}], mass=1.5)
        out.append(("slotted-%d" % rev, f, area, com, 1.5 * j / area))
    # an off-centre hole: 6 x 4 less a disc of radius 0.8 at (1.7, -0.6)
    r = 0.8
    area, com, j = plate_minus(6.0, 4.0, [(math.pi * r * r, (1.7, -0.6), math.pi * r ** 4 / 2)])
    loops = [O.rectangle(-3, -2, 3, 2), O.circle_loop((1.7, -0.6), r, 45.0, True)]
    f = outline_fixture(loops, [{"at": [0.0, -2.0]}, {"at": [-3.0, 0.0]}], mass=2.5)
    out.append(("off-centre-hole", f, area, com, 2.5 * j / area))
    # two holes and the slot together
    area, com, j = plate_minus(8.0, 5.0, [(sa, (1.5, 0.75), sj),
                                          (math.pi * 0.5 ** 2, (-2.5, -1.0), math.pi * 0.5 ** 4 / 2),
                                          (math.pi * 0.3 ** 2, (-2.0, 1.5), math.pi * 0.3 ** 4 / 2)])
    loops = [O.rectangle(-4, -2.5, 4, 2.5), O.stadium((1.5, 0.75), 2.0, 0.6),
             O.circle_loop((-2.5, -1.0), 0.5, 10.0, False),
             O.circle_loop((-2.0, 1.5), 0.3, 170.0, True)]
    f = outline_fixture(loops, [{"at": [0.0, -2.5]}, {"at": [-4.0, 0.0]}], mass=1.0)
    out.append(("three-holes", f, area, com, j / area))
    return out


MASS = mass_cases()


@pytest.mark.parametrize("case", [c[0] for c in MASS])
def test_mass_properties_closed_forms(client, case):
    """fixture.put reports the uniform lamina's area, centroid and inertia
    about it (holes subtracted) to 1e-12 relative; fixture.get writes the
    same com and inertia; outline_model.py's integrals agree (so they may
    be trusted elsewhere)."""
    _, f, area, com, inertia = [c for c in MASS if c[0] == case][0]
    r = put(client, f)
    xs = [v[0] for v in f["body"]["shape"]["loops"][0]]
    ys = [v[1] for v in f["body"]["shape"]["loops"][0]]
    extent = math.hypot(max(xs) - min(xs), max(ys) - min(ys))
    assert set(r) >= {"id", "fixels", "goal_cones", "strong_cones", "pinned", "area", "com",
                      "inertia"}, r
    assert rel_close(r["area"], area), (r, area)
    # the com to 1e-12 of the part's extent (a thin ring's vertices, rounded
    # to doubles, fix its centroid no better than that)
    assert len(r["com"]) == 2 and H.vec_close(r["com"], com, 1e-12 * (
        extent + abs(com[0]) + abs(com[1]))), (r, com)
    assert rel_close(r["inertia"], inertia), (r, inertia)
    g = client.result("fixture.get", {"id": r["id"]})
    assert g["body"]["com"] == r["com"] and g["body"]["inertia"] == r["inertia"], (g, r)
    ol = O.Outline(f["body"]["shape"])
    assert rel_close(ol.area, area, 1e-11), (ol.area, area)
    assert H.vec_close(ol.centroid, com, 1e-11 * (extent + abs(com[0]) + abs(com[1]))), (
        ol.centroid, com)
    assert rel_close(ol.inertia(f["body"]["mass"]), inertia, 1e-11)


def test_mass_properties_given_com_and_inertia(client):
    """A com given elsewhere moves the uniform inertia by the parallel-axis
    theorem (I_c + m d^2); a given inertia is kept as written; the reported
    area is the shape's in every case."""
    r = 0.8
    area, com, j = plate_minus(6.0, 4.0, [(math.pi * r * r, (1.7, -0.6), math.pi * r ** 4 / 2)])
    loops = [O.rectangle(-3, -2, 3, 2), O.circle_loop((1.7, -0.6), r, 45.0, True)]
    fixels = [{"at": [0.0, -2.0]}, {"at": [-3.0, 0.0]}]
    m = 2.5
    given = (0.3, 0.4)
    d2 = (given[0] - com[0]) ** 2 + (given[1] - com[1]) ** 2
    a = put(client, outline_fixture(loops, fixels, mass=m, com=given))
    assert rel_close(a["area"], area) and a["com"] == list(given), a
    assert rel_close(a["inertia"], m * (j / area + d2)), (a, m * (j / area + d2))
    b = put(client, outline_fixture(loops, fixels, mass=m, inertia=7.25))
    assert b["inertia"] == 7.25 and rel_close(b["area"], area), b
    assert H.vec_close(b["com"], com, 1e-12 * 5), b
    c = put(client, outline_fixture(loops, fixels, mass=m, com=given, inertia=7.25))
    assert c["com"] == list(given) and c["inertia"] == 7.25, c


def test_put_reports_mass_properties_of_every_shape(client):
    """circle: pi R^2, its centre, m R^2 / 2; polygon: the shoelace area,
    centroid and polar moment (model.py); no shape: com and inertia as given
    and no area."""
    a = put(client, FX.disc_at_angles([200, 300], radius=1.5, center=(1.0, 2.0), mass=2.0))
    assert rel_close(a["area"], math.pi * 2.25) and a["com"] == [1.0, 2.0], a
    assert rel_close(a["inertia"], 2.0 * 2.25 / 2), a
    f = FX.rectangle_321(0.3)
    b = put(client, f)
    assert b["area"] == 8 and b["com"] == [2, 1], b
    assert rel_close(b["inertia"], 1.0 * (16 + 4) / 12), b
    c = put(client, FX.disc_corner(0.5))
    assert c["com"] == [0, 0] and c["inertia"] == 0.5 and rel_close(c["area"], math.pi), c
    shapeless = {"body": {"mass": 2.0, "inertia": 0.7, "com": [0.1, 0.2]},
                 "friction": {"static": 0.4},
                 "fixels": [{"at": [-1, 0], "normal": [1, 0]}, {"at": [0, -1], "normal": [0, 1]}]}
    d = put(client, shapeless)
    assert "area" not in d, d
    assert d["com"] == [0.1, 0.2] and d["inertia"] == 0.7, d


# ---- normals ------------------------------------------------------------------------

def test_derived_normals(client):
    """Left out, a fixel's normal points from it into the material: on a
    straight segment perpendicular to it, on an arc radial (towards the
    centre of a convex arc, away from it on a concave one), on a hole's
    boundary away from the hole's inside (for a pin in a round hole: from
    the hole's centre through the pin); at a vertex where the outline is
    smooth (a fillet meeting its side, the two arcs of a circle) it is
    defined; either orientation of every loop."""
    hole_c, hole_r = (1.5, 1.2), 0.6
    for rev_outer in (False, True):
        for rev_hole in (False, True):
            outer = [[0, 0], [5, 0, 0.3], [5, 3, -0.4], [0, 3]]
            hole = O.circle_loop(hole_c, hole_r, 0.0, True)
            sq_hole = O.rectangle(3.0, 1.0, 3.6, 1.6)
            loops = [O.reverse_loop(outer) if rev_outer else outer,
                     O.reverse_loop(hole) if rev_hole else hole,
                     O.reverse_loop(sq_hole) if rev_hole else sq_hole]
            ol = O.Outline({"type": "outline", "loops": loops})
            s1 = O.Segment((5, 0), (5, 3), 0.3)
            s2 = O.Segment((5, 3), (0, 3), -0.4)
            pts = [(2.0, 0.0),                                   # bottom line
                   s1.point(0.3),                                # convex arc
                   s2.point(0.6),                                # concave arc
                   (hole_c[0] + hole_r * math.cos(2.0), hole_c[1] + hole_r * math.sin(2.0)),
                   (hole_c[0] + hole_r, hole_c[1]),              # a vertex of the hole's arcs
                   (3.3, 1.0)]                                   # the square hole's bottom
            expect = [(0.0, 1.0),
                      M.unit(M.sub(s1.center, s1.point(0.3))),
                      M.unit(M.sub(s2.point(0.6), s2.center)),
                      (math.cos(2.0), math.sin(2.0)),
                      (1.0, 0.0),
                      (0.0, -1.0)]
            f = outline_fixture(loops, [{"at": list(p)} for p in pts])
            got = client.result("fixture.get", {"id": put(client, f)["id"]})
            for fx, e in zip(got["fixels"], expect):
                assert H.vec_close(fx["normal"], e, 1e-12), (rev_outer, rev_hole, fx, e)
                lp, sg, t = locate(ol, fx["at"]) if fx["at"] != [hole_c[0] + hole_r, hole_c[1]] \
                    else (1, 0, None)
                if t is not None:
                    assert H.vec_close(ol.inward_normal(lp, sg, t), e, 1e-12)
    # a fillet's ends are smooth: the side's normal
    loop = O.rounded_rectangle(4.0, 2.0, 0.5)
    f = outline_fixture([loop], [{"at": [2.0, -0.5]}, {"at": [1.5, 1.0]}, {"at": [0.0, -1.0]}])
    got = client.result("fixture.get", {"id": put(client, f)["id"]})
    for fx, e in zip(got["fixels"], [(-1.0, 0.0), (0.0, -1.0), (0.0, 1.0)]):
        assert H.vec_close(fx["normal"], e, 1e-12), (fx, e)


# ---- 4. push regions on arcs, point by point ----------------------------------------

def arc_fixtures():
    out = {}
    # a rounded plate with a round hole and a pin in it (pushing outward in
    # the hole is a region of the strong set)
    loops = [O.rounded_rectangle(6, 4, 1), O.circle_loop((-1, 0.5), 0.7, 0, False)]
    out["pin-in-hole"] = outline_fixture(
        loops, [{"at": [-1, -2]}, {"at": [1.5, -2]}, {"at": [-1.7, 0.5]}], mu=0.2)
    # convex and concave arcs
    out["concave-arc"] = outline_fixture(
        [[[0, 0], [4, 0, 0.3], [4, 3, -0.4], [0, 3]]],
        [{"at": [1, 0]}, {"at": [3, 0]}, {"at": [0, 1.5]}], mu=0.2)
    # the same, clockwise
    out["concave-arc-cw"] = outline_fixture(
        [O.reverse_loop([[0, 0], [4, 0, 0.3], [4, 3, -0.4], [0, 3]])],
        [{"at": [1, 0]}, {"at": [3, 0]}, {"at": [0, 1.5]}], mu=0.2)
    # located by two pins in a round hole and a slot, and one edge fixel
    loops = [O.rectangle(0, 0, 8, 4), O.circle_loop((2, 2), 0.5, 90),
             O.stadium((6, 2), 1, 0.5)]
    out["two-pins"] = outline_fixture(loops, [{"at": [1.5, 2]}, {"at": [5, 2]}, {"at": [4, 0]}],
                                      mu=0.15)
    # a part with a convex arc on its right and a concave one on its left
    # (bulge -0.2 from (0, 2) down to (0, 0)), com off the centroid; the
    # third fixel at the concave arc's middle
    left = O.Segment((0, 2), (0, 0), -0.2)
    out["lens"] = outline_fixture(
        [[[0, 0, 0], [3, 0, 0.5], [3, 2, 0], [0, 2, -0.2]]],
        [{"at": [1, 0]}, {"at": [2.2, 0]}, {"at": list(left.point(0.5))}],
        mu=0.1, com=(1.4, 1.1), inertia=1.2)
    # a lollipop: a stem under a head that is an arc of 4 atan 3 = 286
    # degrees (bulge 3), clockwise, with a hole in the head (bulge -2.5 arcs)
    head = O.Segment((0.5, 0), (-0.5, 0), 3.0)
    stem = [[-0.5, -3, 0], [0.5, -3, 0], [0.5, 0, 3.0], [-0.5, 0, 0]]
    hole = [[head.center[0] - 0.2, head.center[1], 1.0], [head.center[0] + 0.2, head.center[1], 1.0]]
    out["lollipop"] = outline_fixture(
        [O.reverse_loop(stem), hole],
        [{"at": [-0.5, -2.5]}, {"at": [0.5, -1.5]}, {"at": [0, -3]},
         {"at": [head.center[0], head.center[1] + head.radius]}], mu=0.3)
    return out


ARCS = arc_fixtures()


@pytest.mark.parametrize("name", sorted(ARCS))
def test_mass_properties_by_green(client, name):
    """Every part with arcs against outline_model.py's Green's-theorem
    integrals (checked against closed forms above), to 1e-12 relative."""
    f = ARCS[name]
    ol = O.Outline(f["body"]["shape"])
    r = put(client, f)
    assert rel_close(r["area"], ol.area, 1e-12), (r, ol.area)
    com = tuple(f["body"]["com"]) if "com" in f["body"] else ol.centroid
    assert H.vec_close(r["com"], com, 1e-12 * 10), (r, com)
    inertia = f["body"].get("inertia", ol.inertia(f["body"]["mass"], com))
    assert rel_close(r["inertia"], inertia, 1e-12), (r, inertia)


@pytest.mark.parametrize("name", sorted(ARCS))
def test_push_regions_on_arcs_pointwise(client, name):
    """Regions exact on lines and arcs of every loop: dense points of every
    segment classified by margin (positive exactly in the regions), the
    endpoints at margin 0, sparser points by method "lp" (inside exactly in
    the regions) and some by model.py; 'both' is goal and strong.  The push
    wrench at p is (nu, (p - x_c) x nu), nu the inward normal from
    outline_model.py."""
    f = ARCS[name]
    ol = O.Outline(f["body"]["shape"])
    r = put(client, f)
    com = tuple(f["body"]["com"]) if "com" in f["body"] else ol.centroid
    assert H.vec_close(r["com"], com, 1e-12 * 10), (r, com)
    found = check_pointwise(client, f, ol, com, per_segment=100, lp_every=9, model_points=12,
                            seed=len(name))
    arcs = {(lp, sg) for lp, segs in enumerate(ol.loops) for sg, s in enumerate(segs) if s.arc}
    on_arcs = [iv for s in SETS for iv in found[s] if (iv[0], iv[1]) in arcs]
    assert on_arcs, ("no region on any arc: the test does not bite", found)
    if name in ("pin-in-hole", "two-pins"):
        assert any(iv[0] >= 1 for iv in found["strong"]), (
            "a pin pushing outward in a hole: a region on a hole's boundary", found)


def test_pin_in_hole_region_closed_form(client):
    """The pin-in-hole part, strong set: a region on the hole (loop 1).  The
    finger in the hole pushes along nu = (p - c) / r (away from the hole's
    centre c), a force whose line passes through c: w = (nu, (c - x_c) x
    nu).  So the region on the hole is the set of directions nu for which
    the force through c is in G_strong; check it against classify of that
    force at the region's ends (margin 0) and its middle (positive)."""
    f = ARCS["pin-in-hole"]
    ol = O.Outline(f["body"]["shape"])
    com = ol.centroid
    res = regions(client, f, "strong")
    iv = [x for x in check_outline_answer(ol, res) if x[0] == 1]
    assert iv, res
    c = (-1.0, 0.5)
    ws = []
    for lp, sg, t0, t1 in iv:
        for t in (t0, 0.5 * (t0 + t1), t1):
            p = ol.segment(lp, sg).point(t)
            nu = M.unit(M.sub(p, c))
            ws.append((nu[0], nu[1], M.cross2(M.sub(c, com), nu)))
    got = margins(client, f, ws, ("strong",))
    for i, g in enumerate(got):
        m = g["strong"]["margin"]
        if i % 3 == 1:
            assert m > 1e-6, (iv, got)
        else:
            lp, sg, t0, t1 = iv[i // 3]
            t = t0 if i % 3 == 0 else t1
            if 0 < t < 1:
                assert abs(m) < 1e-9, (iv, i, m)


# ---- 5. field-precise errors ---------------------------------------------------------

SQ = [[0, 0], [4, 0], [4, 4], [0, 4]]
BASE_FIXELS = [{"at": [2, 0]}]
SHAPE = "params.fixture.body.shape"


def points_in(reason):
    return [(float(a), float(b)) for a, b in
            re.findall(r"\((-?[0-9.e+-]+), (-?[0-9.e+-]+)\)", reason)]


ROOT3 = math.sqrt(3.0)
ROOT23 = math.sqrt(2.3)

# (name, loops, field, [words in the reason], [possible meeting points])
LOOP_ERRORS = [
    # line-line: the bow tie's segments 1 ((4,0)-(0,4)) and 3 ((4,4)-(0,0)) cross at (2, 2)
    ("line-line", [[[0, 0], [4, 0], [0, 4], [4, 4]]], SHAPE + ".loops[0]",
     ["segment 1", "segment 3"], [(2, 2)]),
    # line-arc: the top of a 4 x 1 box dips as a half circle (bulge -1) of
    # radius 2 about (2, 1) to y = -1, crossing the bottom y = 0 where
    # (x - 2)^2 = 4 - 1: x = 2 -+ sqrt 3
    ("line-arc", [[[0, 0], [4, 0], [4, 1, -1], [0, 1]]], SHAPE + ".loops[0]",
     ["segment 0", "segment 2"], [(2 - ROOT3, 0), (2 + ROOT3, 0)]),
    # arc-arc: in a 6 x 4 box the bottom and the top bulge inward with
    # bulge -0.8: sagitta 0.8 * 6 / 2 = 2.4, radius 6 (1 + 0.64) / 3.2 =
    # 3.075, centres (3, 2.4 - 3.075) and (3, 1.6 + 3.075); they cross at
    # y = 2, x = 3 -+ sqrt(3.075^2 - 2.675^2) = 3 -+ sqrt 2.3
    ("arc-arc", [[[0, 0, -0.8], [6, 0], [6, 4, -0.8], [0, 4]]], SHAPE + ".loops[0]",
     ["segment 0", "segment 2"], [(3 - ROOT23, 2), (3 + ROOT23, 2)]),
    # a hole that crosses itself
    ("hole-self", [SQ, [[1, 1], [3, 1], [1, 3], [3, 3]]], SHAPE + ".loops[1]",
     ["segment 1", "segment 3"], [(2, 2)]),
    ("hole-outside", [SQ, [[10, 10], [11, 10], [11, 11]]], SHAPE + ".loops[1]", ["outside"], []),
    ("hole-around-outer", [SQ, [[-1, -1], [5, -1], [5, 5], [-1, 5]]], SHAPE + ".loops[1]", [],
     []),
    ("holes-overlap", [SQ, O.rectangle(1, 1, 2, 2), O.rectangle(1.5, 1.5, 2.5, 2.5)],
     SHAPE + ".loops[2]", ["loops[1]"], [(2, 1.5), (1.5, 2)]),
    ("hole-in-hole", [SQ, O.rectangle(1, 1, 3, 3), O.rectangle(1.5, 1.5, 2.5, 2.5)],
     SHAPE + ".loops[2]", ["loops[1]"], []),
    ("holes-touch", [SQ, O.rectangle(1, 1, 2, 2), O.rectangle(2, 2, 3, 3)],
     SHAPE + ".loops[2]", ["loops[1]"], [(2, 2)]),
    ("hole-touches-outer-vertex", [SQ, [[0, 2], [2, 1], [2, 3]]], SHAPE + ".loops[1]",
     ["loops[0]"], [(0, 2)]),
    ("hole-touches-outer-corner", [SQ, [[1, 1], [2, 1], [4, 4]]], SHAPE + ".loops[1]",
     ["loops[0]"], [(4, 4)]),
    # a round hole of radius 1 about (2, 1) is tangent to the bottom at (2, 0)
    ("hole-tangent-outer", [SQ, O.circle_loop((2, 1), 1, 0)], SHAPE + ".loops[1]",
     ["loops[0]"], [(2, 0)]),
    ("one-vertex", [[[1, 1]]], SHAPE + ".loops[0]", [], []),
    ("one-vertex-hole", [SQ, [[1, 1]]], SHAPE + ".loops[1]", [], []),
    ("two-vertex-lines", [[[0, 0], [4, 0]]], SHAPE + ".loops[0]", [], []),
    ("empty-loop", [[]], SHAPE + ".loops[0]", [], []),
    ("loops-object", {}, SHAPE + ".loops", [], []),
    ("loops-empty", [], SHAPE + ".loops", [], []),
    ("loops-string", "square", SHAPE + ".loops", [], []),
    ("loop-number", [5], SHAPE + ".loops[0]", [], []),
    ("loop-object", [SQ, {"a": 1}], SHAPE + ".loops[1]", [], []),
    ("vertex-4-numbers", [[[0, 0], [4, 0], [4, 4, 0, 1], [0, 4]]], SHAPE + ".loops[0][2]",
     [], []),
    ("vertex-1-number", [[[0, 0], [4, 0], [4], [0, 4]]], SHAPE + ".loops[0][2]", [], []),
    ("vertex-string", [[[0, 0], [4, 0], "4,4", [0, 4]]], SHAPE + ".loops[0][2]", [], []),
    ("vertex-object", [SQ, [[1, 1], {"x": 2, "y": 1}, [2, 2]]], SHAPE + ".loops[1][1]", [], []),
    ("coordinate-string", [[[0, 0], [4, 0], [4, "4"], [0, 4]]], SHAPE + ".loops[0][2][1]",
     [], []),
    ("coordinate-null", [[[0, 0], [None, 0], [4, 4], [0, 4]]], SHAPE + ".loops[0][1][0]",
     [], []),
    ("bulge-string", [[[0, 0], [4, 0], [4, 4, "0.5"], [0, 4]]], SHAPE + ".loops[0][2][2]",
     [], []),
    ("bulge-bool", [SQ, [[1, 1], [2, 1, True], [2, 2]]], SHAPE + ".loops[1][1][2]", [], []),
]


@pytest.mark.parametrize("case", [c[0] for c in LOOP_ERRORS])
def test_loop_errors_name_the_field(client, case):
    """-32602 with the exact path into the loops; a crossing names the two
    segments and where they meet (derived in the table's comments); the
    fixture is not stored."""
    _, loops, field, words, meets = [c for c in LOOP_ERRORS if c[0] == case][0]
    f = outline_fixture(loops, BASE_FIXELS)
    before = client.result("fixture.list", {})["fixtures"]
    got, reason = error_of(client, "fixture.put", {"fixture": f})
    assert got == field, (case, got, field, reason)
    for w in words:
        assert w in reason, (case, w, reason)
    if meets:
        pts = points_in(reason)
        assert any(H.vec_close(p, q, 1e-5) for p in pts for q in meets), (case, reason, meets)
    # the same through another method (an inline fixture)
    got2, _ = error_of(client, "push.regions", {"fixture": f})
    assert got2 == field, (case, got2)
    assert client.result("fixture.list", {})["fixtures"] == before


def test_shape_field_errors(client):
    """The outline's own fields: loops required, no other member."""
    base = outline_fixture([SQ], BASE_FIXELS)
    f = copy.deepcopy(base)
    del f["body"]["shape"]["loops"]
    assert error_of(client, "fixture.put", {"fixture": f})[0] == SHAPE + ".loops"
    for extra in ("vertices", "center", "radius", "holes"):
        f = copy.deepcopy(base)
        f["body"]["shape"][extra] = [1, 2]
        assert error_of(client, "fixture.put", {"fixture": f})[0] == SHAPE + "." + extra


# (name, loops, fixels, field, words, distance from the outline or None)
HOLE = O.circle_loop((2, 2), 1, 0, True)
FIXEL_ERRORS = [
    ("off-boundary", [SQ], [{"at": [2, 0]}, {"at": [2, 0.1]}], "params.fixture.fixels[1].at",
     [], 0.1),
    ("outside", [SQ], [{"at": [2, 0]}, {"at": [2, -0.1]}], "params.fixture.fixels[1].at",
     [], 0.1),
    ("far-outside", [SQ], [{"at": [2, 0]}, {"at": [7, 8]}], "params.fixture.fixels[1].at",
     [], 5.0),
    # in the hole's open inside, 0.5 from its edge
    ("in-the-hole", [SQ, HOLE], [{"at": [2, 0]}, {"at": [2.5, 2]}],
     "params.fixture.fixels[1].at", [], 0.5),
    ("corner-no-normal", [SQ], [{"at": [2, 0]}, {"at": [4, 0]}],
     "params.fixture.fixels[1].normal", [], None),
    ("hole-corner-no-normal", [SQ, O.rectangle(1, 1, 2, 2)],
     [{"at": [2, 0]}, {"at": [1, 2]}], "params.fixture.fixels[1].normal", [], None),
    # an arc meeting a line at an angle: (4, 0), where the bottom line meets
    # the right side's arc (bulge 0.3: the arc leaves at 2 atan 0.3 from its chord)
    ("arc-corner-no-normal", [[[0, 0], [4, 0, 0.3], [4, 3], [0, 3]]],
     [{"at": [2, 0]}, {"at": [4, 0]}], "params.fixture.fixels[1].normal", [], None),
    # a pin in a round hole of radius 1 about (2, 2) at (3, 2): the
    # material is at +x; (-1, 0) points into the hole
    ("pin-normal-out", [SQ, HOLE], [{"at": [2, 0]}, {"at": [3, 2], "normal": [-1, 0]}],
     "params.fixture.fixels[1].normal", [], None),
    ("pin-normal-tangent", [SQ, HOLE], [{"at": [2, 0]}, {"at": [3, 2], "normal": [0, 1]}],
     "params.fixture.fixels[1].normal", ["tangent"], None),
    ("outer-normal-out", [SQ, HOLE], [{"at": [2, 0], "normal": [0.2, -1]}],
     "params.fixture.fixels[0].normal", [], None),
    # on the square hole's bottom edge the material is below: (0, 1) points into the hole
    ("hole-edge-normal-out", [SQ, O.rectangle(1, 1, 2, 2)],
     [{"at": [2, 0]}, {"at": [1.5, 1], "normal": [0, 1]}], "params.fixture.fixels[1].normal",
     [], None),
]


@pytest.mark.parametrize("case", [c[0] for c in FIXEL_ERRORS])
def test_fixel_errors_name_the_field(client, case):
    """A fixel off every loop is refused at its `at`, the reason saying how
    far it is (as it does for polygons: 0.1 for (2, +-0.1) by the bottom
    edge, 5 for (7, 8) from the corner (4, 4), 0.5 for (2.5, 2) inside a hole
    of radius 1 about (2, 2)); at a corner a normal is required; a given
    normal must point into the material (on a hole: away from the hole's
    inside)."""
    _, loops, fixels, field, words, dist = [c for c in FIXEL_ERRORS if c[0] == case][0]
    got, reason = error_of(client, "fixture.put", {"fixture": outline_fixture(loops, fixels)})
    assert got == field, (case, got, field, reason)
    for w in words:
        assert w in reason, (case, w, reason)
    if dist is not None:
        said = re.findall(r"(-?[0-9.]+(?:e[+-]?[0-9]+)?) away", reason)
        assert said and abs(float(said[0]) - dist) <= 1e-5 * dist, (
            "the reason should say how far the fixel is: %g" % dist, reason)


def test_a_given_normal_at_a_corner_is_taken(client):
    """The corner's normal given (any direction strictly into the material)
    is accepted and kept, unit length."""
    f = outline_fixture([SQ, O.rectangle(1, 1, 2, 2)],
                        [{"at": [2, 0]}, {"at": [4, 0], "normal": [-1, 1]},
                         {"at": [1, 2], "normal": [-1, 1]}])
    g = client.result("fixture.get", {"id": put(client, f)["id"]})
    s = 1 / math.sqrt(2)
    assert H.vec_close(g["fixels"][1]["normal"], (-s, s), 1e-15), g
    assert H.vec_close(g["fixels"][2]["normal"], (-s, s), 1e-15), g


# ---- 6. ids ----------------------------------------------------------------------------

# fixture.put's ids at commit 0596807 (before the outline shape), computed by
# building that commit and putting these fixtures.
OLD_IDS = {
    "disc-corner.json": "e0d7a1a0bd6e8bf16fe5845da1960ed9",
    "outline.json": "1c3e7c0a5162fd124fa5fcaa646d94c6",
    "plate-3-2-1.json": "a5ce2de4d6cd2bd2e64b40f42ee7f028",
    "plate-chamfered.json": "795772a8c6f89d348c1b227f6a7b3a50",
    "disc_corner": "e0d7a1a0bd6e8bf16fe5845da1960ed9",
    "rectangle_321": "358f06a8af022e21815facd2d4d0ebf2",
    "rectangle_321_cw": "efdaa0e890493f8844d0818b3891ab7a",
    "chamfered_plate": "c9da5310274381792d69151dce6f3f91",
    "triangle": "007bf02320ce57a980434fd2e9c0871b",
    "corner_fixel_plate": "28c52bccdb9f915ca481fd371066fb0b",
    "offset_disc": "6913702eca1f33f2d06fcf49a7db00c0",
    "disc_one_fixel": "cf28101667485c019197b3f1ae39a9e8",
    "disc_at_angles": "2d7827b55b4869c96dab2965e27c5f65",
    "shapeless": "2df758b0268664b64519341783dec49d",
}


def old_fixtures():
    import glob
    import os
    out = {}
    here = os.path.dirname(os.path.abspath(__file__))
    for path in sorted(glob.glob(os.path.join(here, "..", "..", "examples", "*.json"))):
        with open(path) as f:
            fixture = json.load(f)
        # Examples written as outlines came with the shape: no old id.
        if fixture["body"].get("shape", {}).get("type") != "outline":
            out[os.path.basename(path)] = fixture
    out["disc_corner"] = FX.disc_corner(0.5)
    out["rectangle_321"] = FX.rectangle_321(0.3)
    out["rectangle_321_cw"] = FX.rectangle_321(0.3, clockwise=True)
    out["chamfered_plate"] = FX.chamfered_plate()
    out["triangle"] = FX.triangle()
    out["corner_fixel_plate"] = FX.corner_fixel_plate()
    out["offset_disc"] = FX.offset_disc()
    out["disc_one_fixel"] = FX.disc_one_fixel()
    out["disc_at_angles"] = FX.disc_at_angles([100, 200, 300], mu=0.3, radius=1.7,
                                              center=(0.5, -0.25))
    out["shapeless"] = {"body": {"mass": 2.0, "inertia": 0.7, "com": [0.1, 0.2]},
                        "friction": {"static": 0.4},
                        "fixels": [{"at": [-1, 0], "normal": [1, 0]},
                                   {"at": [0, -1], "normal": [0, 1]}]}
    return out


def test_ids_of_older_fixtures_unchanged(client):
    """The outline shape changes no other fixture's id: every example and a
    few circles, polygons and a shapeless fixture keep the id they had at
    commit 0596807; each example is in the table."""
    fx = old_fixtures()
    # Examples added with or after the outline shape have no older id.
    for new in ("notched-plate.json", "plate-3-2-1-buttons.json"):
        fx.pop(new, None)
    assert set(fx) == set(OLD_IDS), sorted(set(fx) ^ set(OLD_IDS))
    for name, f in fx.items():
        assert put(client, f)["id"] == OLD_IDS[name], name


def put_raw(client, text):
    client.send_line('{"jsonrpc":"2.0","method":"fixture.put","id":7,"params":{"fixture":%s}}'
                     % text)
    resp = client.read_json()
    assert "result" in resp, resp
    return resp["result"]["id"]


def test_outline_spellings_share_an_id(client):
    """[x, y], [x, y, 0], [x, y, -0], [x, y, 0.0e0], -0 for a zero
    coordinate, 1 / 1.0 / 1e0 for a bulge, key order: one fixture."""
    texts = [
        '{"body":{"mass":1,"shape":{"type":"outline","loops":[[[0,0],[4,0],[4,3],[0,3]],'
        '[[1,1,1],[2,1,1]]]}},"friction":{"static":0.3},"fixels":[{"at":[2,0]}]}',
        '{"body":{"mass":1,"shape":{"type":"outline","loops":[[[0,0,0],[4,0,0],[4,3,0],[0,3,0]],'
        '[[1,1,1.0],[2,1,1e0]]]}},"friction":{"static":0.3},"fixels":[{"at":[2,0]}]}',
        '{"body":{"mass":1,"shape":{"type":"outline","loops":[[[-0,-0,-0],[4,-0],[4,3,-0.0],'
        '[-0,3,0e0]],[[1,1,1],[2,1,1]]]}},"friction":{"static":0.3},"fixels":[{"at":[2,-0]}]}',
        '{"fixels":[{"at":[2.0,0.0]}],"friction":{"kinetic":0.3,"static":0.3},'
        '"body":{"shape":{"loops":[[[0.0,0.0],[4e0,0],[4,3],[0,3]],[[1,1,1],[2,1,1]]],'
        '"type":"outline"},"mass":1.0}}',
    ]
    ids = [put_raw(client, t) for t in texts]
    assert len(set(ids)) == 1, ids


def test_outline_round_trips_through_get(client):
    """fixture.get answers the explicit form: putting it again gives the
    same id, and it keeps the loops (vertex order, arcs' bulges, holes)."""
    cases = list(ARCS.values()) + [m[1] for m in MASS[:3]] + [
        outline_fixture([O.rounded_rectangle(3, 2, 0.5), O.reverse_loop(O.stadium((0, 0), 1, 0.3))],
                        [{"at": [0, -1]}, {"at": [-1.5, 0]}, {"at": [-0.5, -0.3]}], name="rr")]
    for f in cases:
        r = put(client, f)
        g = client.result("fixture.get", {"id": r["id"]})
        assert g["body"]["shape"]["type"] == "outline", g
        got = [[(v[0], v[1], v[2] if len(v) > 2 else 0) for v in lp]
               for lp in g["body"]["shape"]["loops"]]
        given = [[(float(v[0]), float(v[1]), float(v[2]) if len(v) > 2 else 0.0) for v in lp]
                 for lp in f["body"]["shape"]["loops"]]
        assert got == given, (got, given)
        assert put(client, g)["id"] == r["id"], g
        assert client.result("fixture.get", {"id": r["id"]}) == g


# ---- 7. finger_radius ------------------------------------------------------------------

def restrict(iv, allowed):
    """Intervals iv intersected with allowed[(loop, seg)] (a list of open
    (lo, hi); a segment not named is allowed whole)."""
    out = []
    for lp, sg, t0, t1 in iv:
        for lo, hi in allowed.get((lp, sg), [(0.0, 1.0)]):
            a, b = max(t0, lo), min(t1, hi)
            if a < b:
                out.append((lp, sg, a, b))
    return sorted(out)


def check_closed_form_by_brute_force(ol, allowed, r, per_segment=40):
    """The closed-form allowed parts against outline_model.finger_fits (a
    disc placed and tested for overlap directly) at sample points of every
    segment, away from the parts' ends."""
    bad = []
    for lp, segs in enumerate(ol.loops):
        for sg in range(len(segs)):
            parts = allowed.get((lp, sg), [(0.0, 1.0)])
            for j in range(per_segment):
                t = (j + 0.5) / per_segment
                if any(abs(t - e) < 1e-6 for part in parts for e in part):
                    continue
                want = any(lo < t < hi for lo, hi in parts)
                if O.finger_fits(ol, lp, sg, t, r) != want:
                    bad.append((lp, sg, t, want))
    assert not bad, ("the closed form disagrees with placing the disc", r, bad[:10])


def slot_plate(w, d=1.5, W=6.0, Hh=3.0, xs=3.0, polygon=False):
    """A W x H plate with a rectangular slot of width w and depth d cut
    down from its top at x = xs.  Segments: 0 bottom, 1 right, 2 top right,
    3 the slot's right wall (down), 4 the slot's bottom (right to left),
    5 the left wall (up), 6 top left, 7 left."""
    loop = [[0, 0], [W, 0], [W, Hh], [xs + w / 2, Hh], [xs + w / 2, Hh - d],
            [xs - w / 2, Hh - d], [xs - w / 2, Hh], [0, Hh]]
    fixels = [{"at": [1.5, 0]}, {"at": [4.5, 0]}, {"at": [0, 1.5]}]
    if polygon:
        return {"body": {"mass": 1, "shape": {"type": "polygon", "vertices": loop}},
                "friction": {"static": 0.2}, "fixels": fixels}
    return outline_fixture([loop], fixels, mu=0.2)


@pytest.mark.parametrize("polygon", [False, True], ids=["outline", "polygon"])
@pytest.mark.parametrize("r", [0.1, 0.3, 0.45, 0.6, 1.2])
def test_finger_in_a_slot(client, r, polygon):
    """Slot width w = 1, depth d = 1.5.  A disc of radius r touching the
    slot's bottom at p from above (centre p + (0, r)) overlaps a wall iff p
    is closer than r to it: the bottom keeps t in (r/w, 1 - r/w) when
    r < w/2 and nothing when r > w/2 (the disc is wider than the slot).  On
    a wall the centre is r into the slot: it overlaps the bottom within r of
    it (wall length d: t > 1 - r/d on the right wall, running down; t < r/d
    on the left, running up) and the other wall when r > w/2 (w - r < r).
    The plate's other sides lie on its convex hull: nothing lost there.
    So regions(r) = regions(0) restricted to those, for every set; and the
    strong set, whose radius-0 region on the slot's bottom is all of it,
    keeps exactly (r/w, 1 - r/w) there."""
    w, d = 1.0, 1.5
    f = slot_plate(w, d, polygon=polygon)
    if r < w / 2:
        allowed = {(0, 3): [(0.0, 1 - r / d)], (0, 4): [(r / w, 1 - r / w)],
                   (0, 5): [(r / d, 1.0)]}
    else:
        allowed = {(0, 3): [], (0, 4): [], (0, 5): []}
    check_closed_form_by_brute_force(O.Outline(slot_plate(w, d)["body"]["shape"]), allowed, r)
    for which in SETS:
        base = as_intervals(regions(client, f, which))
        assert as_intervals(regions(client, f, which, finger_radius=0)) == base
        res = regions(client, f, which, finger_radius=r)
        if not polygon:
            check_outline_answer(O.Outline(f["body"]["shape"]), res)
        else:
            assert all(set(x) == {"edge", "from", "to", "t0", "t1", "length"}
                       for x in res["regions"]), res
        got = as_intervals(res)
        want = restrict(base, allowed)
        assert same_intervals(got, want, 1e-10), (which, r, got, want, base)
        if which == "strong":
            assert (0, 4, 0, 1) in [(a, b, round(c, 12), round(e, 12)) for a, b, c, e in base], base
            bottom = [x for x in got if x[1] == 4]
            if r < w / 2:
                assert len(bottom) == 1 and abs(bottom[0][2] - r / w) <= 1e-12 and \
                    abs(bottom[0][3] - (1 - r / w)) <= 1e-12, got
            else:
                assert bottom == [], got


def notch_plate(alpha_deg, h=1.5):
    """An 8 x 3 plate with a V notch in its top at x = 4, depth h, free
    angle alpha at its bottom: half-width a = h tan(alpha / 2).  Segments:
    3 from (4 + a, 3) down to (4, 3 - h), 4 from there up to (4 - a, 3)."""
    a = h * math.tan(math.radians(alpha_deg) / 2)
    loop = [[0, 0], [8, 0], [8, 3], [4 + a, 3], [4, 3 - h], [4 - a, 3], [0, 3]]
    return outline_fixture([loop], [{"at": [2, 0]}, {"at": [6, 0]}, {"at": [0, 1.5]}], mu=0.1), \
        math.hypot(a, h)


@pytest.mark.parametrize("alpha", [60, 90, 120])
@pytest.mark.parametrize("r", [0.2, 0.5])
def test_finger_in_a_concave_corner(client, alpha, r):
    """A disc touching one side of a corner of free angle alpha from the
    free side meets the other side when its touching point is closer than
    r cot(alpha / 2) to the corner (the inscribed disc touches both sides
    there).  Both notch sides lose that length next to the notch's bottom
    (L = sqrt(a^2 + h^2) long: t > 1 - r cot / L on segment 3, t < r cot / L
    on segment 4); the notch's top corners are convex, nothing else is
    lost.  The goal and strong sets have regions on segment 4 from t = 0
    at radius 0, so the loss shows."""
    f, L = notch_plate(alpha)
    cut = r / math.tan(math.radians(alpha) / 2) / L
    assert cut < 1
    allowed = {(0, 3): [(0.0, 1 - cut)], (0, 4): [(cut, 1.0)]}
    check_closed_form_by_brute_force(O.Outline(f["body"]["shape"]), allowed, r)
    bites = False
    for which in SETS:
        base = as_intervals(regions(client, f, which))
        got = as_intervals(regions(client, f, which, finger_radius=r))
        want = restrict(base, allowed)
        assert same_intervals(got, want, 1e-10), (which, alpha, r, got, want, base)
        bites = bites or want != base
    assert bites, "the corner's loss is in no radius-0 region"


CONVEX = [("rect-321", FX.rectangle_321(0.3)), ("chamfer", FX.chamfered_plate()),
          ("disc", FX.disc_corner(0.5)),
          ("disc-angles", FX.disc_at_angles([100, 215, 330], mu=0.2, radius=2.3,
                                            center=(1.5, -0.7))),
          ("rounded", outline_fixture([O.rounded_rectangle(6, 4, 1)],
                                      [{"at": [-1, -2]}, {"at": [1.5, -2]}, {"at": [-3, 0]}],
                                      mu=0.1)),
          ("two-arcs", outline_fixture([O.circle_loop((0, 0), 1, 0, False)],
                                       [{"at": [-1, 0]}, {"at": [0, -1]}], mu=0.5))]


@pytest.mark.parametrize("r", [0.25, 3.0, 50.0])
@pytest.mark.parametrize("name", [c for c, _ in CONVEX])
def test_finger_on_a_convex_part_loses_nothing(client, name, r):
    """On a convex outline a disc touching it from outside lies in the
    half-plane beyond the tangent line there, which holds no material:
    every finger fits, the regions are those of radius 0."""
    f = dict(CONVEX)[name]
    if f["body"]["shape"]["type"] == "outline":
        check_closed_form_by_brute_force(O.Outline(f["body"]["shape"]), {}, r, per_segment=10)
    for which in SETS:
        base = regions(client, f, which)
        got = regions(client, f, which, finger_radius=r)
        assert same_intervals(as_intervals(got), as_intervals(base), 1e-12), (which, got, base)
        assert abs(got["total_length"] - base["total_length"]) <= 1e-12 * 10


@pytest.mark.parametrize("scale", [0.3 / 0.7, 1 - 1e-6, 1.0, 1 + 1e-6, 0.71 / 0.7, 2.0])
def test_finger_in_a_hole(client, scale):
    """A finger in a round hole of radius R = 0.7 touches the hole's edge
    from inside the hole; a disc of radius r internally tangent there lies
    in the hole iff r <= R.  So the hole's regions (the strong set has one)
    stay whole for r <= R and vanish for r > R; the outer loop, a rounded
    (convex) rectangle, loses nothing."""
    f = ARCS["pin-in-hole"]
    R = 0.7
    r = R * scale
    ol = O.Outline(f["body"]["shape"])
    check_closed_form_by_brute_force(
        ol, {} if r <= R else {(1, 0): [], (1, 1): []}, r, per_segment=10)
    base = as_intervals(regions(client, f, "strong"))
    assert any(x[0] == 1 for x in base), base
    got = as_intervals(regions(client, f, "strong", finger_radius=r))
    want = base if r <= R else [x for x in base if x[0] == 0]
    assert same_intervals(got, want, 1e-10), (r, got, want)


@pytest.mark.parametrize("scale", [0.5, 1 - 1e-6, 1 + 1e-6, 1.5])
def test_finger_on_a_concave_arc(client, scale):
    """The top of the concave-arc part is an arc from (4, 3) to (0, 3) with
    bulge -0.4, dipping into the material: radius rho = 4 (1 + 0.16) /
    (4 * 0.4) = 2.9, centre (2, 3 + 2.9 - 0.8).  The material lies outside
    that circle (below y = 3 it is the notch itself), so a disc of radius
    r <= rho internally tangent to the arc fits; one with r > rho holds the
    circle and crosses it on both sides of the touching point: nothing on
    the arc fits.  The other sides are on the convex hull."""
    f = ARCS["concave-arc"]
    rho = 2.9
    s = O.Segment((4, 3), (0, 3), -0.4)
    assert abs(s.radius - rho) < 1e-12 and H.vec_close(s.center, (2, 5.1), 1e-12)
    r = rho * scale
    check_closed_form_by_brute_force(O.Outline(f["body"]["shape"]),
                                     {} if r <= rho else {(0, 2): []}, r, per_segment=20)
    for which in ("strong", "goal"):
        base = as_intervals(regions(client, f, which))
        if which == "strong":
            assert any(x[1] == 2 for x in base), base
        got = as_intervals(regions(client, f, which, finger_radius=r))
        want = base if r <= rho else [x for x in base if x[1] != 2]
        assert same_intervals(got, want, 1e-10), (which, r, got, want)


@pytest.mark.parametrize("bad", [-1, -1e-300, "0.1", None, True, [0.1], {"r": 1}])
def test_finger_radius_invalid(client, bad):
    """finger_radius is a number >= 0: anything else is -32602 at
    params.finger_radius, for every shape."""
    for f in (FX.rectangle_321(0.3), FX.disc_corner(0.5), slot_plate(1.0)):
        field, _ = error_of(client, "push.regions", {"fixture": f, "finger_radius": bad})
        assert field == "params.finger_radius", (bad, field)


def test_finger_radius_zero_is_the_default(client):
    for f in (FX.rectangle_321(0.3), FX.disc_corner(0.5), slot_plate(1.0), ARCS["pin-in-hole"]):
        for which in SETS:
            assert regions(client, f, which, finger_radius=0) == regions(client, f, which)
            assert regions(client, f, which, finger_radius=0.0) == regions(client, f, which)


# ---- finger friction on outlines ------------------------------------------------------

def test_finger_friction_on_outlines(client):
    """With finger_friction the answer is sampled (exact false) but its
    endpoints are bisected to machine precision: the polygon and its
    outline agree (edge i = segment i), and the disc in a corner written as
    two arcs has its closed form: a finger with friction mu_f pushes along
    every direction within atan mu_f of the normal, so the goal region
    (atan mu, 90 - atan mu) degrees shrinks by atan mu_f at each end; on the
    counter-clockwise arcs from angle 0, t = degrees / 180."""
    p = FX.rectangle_321(0.3)
    o = as_outline(p, [p["body"]["shape"]["vertices"]])
    for which in SETS:
        rp = regions_ff(client, p, which, 0.1)
        ro = regions_ff(client, o, which, 0.1)
        assert rp["exact"] is False and ro["exact"] is False, (rp, ro)
        assert same_intervals(as_intervals(rp), as_intervals(ro), 1e-9), (which, rp, ro)
    mu, muf = 0.3, 0.1
    d = FX.disc_corner(mu)
    od = as_outline(d, [[[1, 0, 1], [-1, 0, 1]]])
    res = regions_ff(client, od, "goal", muf)
    check_outline_answer(O.Outline(od["body"]["shape"]), res)
    a = math.degrees(math.atan(mu) + math.atan(muf))
    got = as_intervals(res)
    assert len(got) == 1 and got[0][:2] == (0, 0), got
    assert abs(got[0][2] - a / 180) <= 1e-9 and abs(got[0][3] - (90 - a) / 180) <= 1e-9, (got, a)


def regions_ff(client, fixture, which, finger):
    return client.result("push.regions", {"fixture": fixture, "set": which,
                                          "finger_friction": finger})


@pytest.mark.parametrize("bulge", [1e-200, 1e-300, 1e-310, 5e-324])
def test_tiny_bulges(client, bulge):
    """A bulge of 1e-200 is an arc so flat that the rectangle it bends is
    the rectangle to every digit: area 8, com (2, 1), inertia
    m (16 + 4) / 12.  Smaller ones, down to the least subnormal, are the
    same (or, if refused like a subnormal radius, refused at that bulge's
    own field, not as an outline "too large")."""
    loop = [[0, 0, bulge], [4, 0], [4, 2], [0, 2]]
    f = outline_fixture([loop], [{"at": [0, 1]}, {"at": [4, 1]}, {"at": [2, 2]}])
    resp = client.call("fixture.put", {"fixture": f})
    if "error" in resp:
        e = resp["error"]
        assert e["code"] == -32602 and e["data"]["field"] == SHAPE + ".loops[0][0][2]", (
            bulge, e)
    else:
        r = resp["result"]
        assert rel_close(r["area"], 8.0) and H.vec_close(r["com"], (2, 1), 1e-12), r
        assert rel_close(r["inertia"], 20 / 12), r


@pytest.mark.parametrize("bulge", [1e-6, 1e-9, 1e-12, 1e-18])
def test_nearly_straight_arcs_give_their_chords_regions(client, bulge):
    """Found by fuzzing: an arc of bulge 1e-18 has its centre 1e19
    away, and regions worked out about it lost every digit of t (a whole
    region was missed).  Worked out in the chord frame, the 3-2-1 plate
    whose right and top sides bow out by bulge b has the polygon's regions
    within what the bow changes: the sagitta is b h, the normals turn by
    up to 4b, so each endpoint moves by O(b) of its side (1e-6 allowed
    at b = 1e-6, 1e-9 below)."""
    plate = FX.rectangle_321(0.3)
    straight = as_intervals(regions(client, plate, "strong"))
    assert straight, "the 3-2-1 plate has strong regions on its right and top sides"
    bowed = json.loads(json.dumps(plate))
    v = plate["body"]["shape"]["vertices"]
    bowed["body"]["shape"] = {"type": "outline", "loops": [
        [v[0], v[1] + [bulge], v[2] + [bulge], v[3]]]}
    arcs = as_intervals(regions(client, bowed, "strong"))
    tol = max(1e-9, 4 * bulge)
    assert len(arcs) == len(straight), (arcs, straight)
    for (l0, s0, a0, b0), (l1, s1, a1, b1) in zip(straight, arcs):
        assert (l0, s0) == (l1, s1)
        assert a1 == pytest.approx(a0, abs=tol) and b1 == pytest.approx(b0, abs=tol)
