"""fixture.design: end-to-end tests written from the wire contract.

Every expected number here comes from the daemon's other methods, asked
about the candidate fixtures this file builds itself (fixture.put,
push.regions, wrench.classify, gravity.sweep, friction.sweep), or from
closed forms derived here (site positions and normals); never from
fixture.design's own answer.

Brute force.  Sites are computed here from the spacing rule, by arc length
(spacing_sites: each loop measured along its segments, cut at its corners
-- joints turning by more than 20 degrees -- into runs; a run of length L
gets floor((L - 2c) / h) + 1 sites h apart, centred, c clear of its ends; a
loop without corners floor(P / h) sites P / n apart from vertex 0; a circle
floor(2 pi R / h) at angles 2 pi k / n), numbered loop by loop, along each
loop.  Every combination of `fixels` of them, in lexicographic order, is
judged: two sites on one hole -> shared hole (a pin is one fixel); put
(fixture.put: refused -> degenerate, "pinned": false -> unpinned), then
push.regions goal, less the loops the finger may not push on (push_on,
filtered here by the regions' loops; empty -> no seating push),
push.regions both and gravity.sweep goal.  The margin objective's best push
is searched here by dense sampling of every both-region interval with
wrench.classify (set both, the frictionless push along the inward normal),
then a bracketing zoom around the best samples; that sampled maximum is a
lower bound of the true maximum, so the design's margin must be at least it
minus 1e-9, and, as the design's best push is a real point, classifying it
must give its margin back.

Rankings are compared allowing near ties: two candidates whose reference
scores lie within 1e-8 (margins: ours are sampled lower bounds, found here
to ~1e-10 of the design's) or 1e-9 (lengths, degrees: recomputed exactly)
of each other may come in either order; everything else must be exactly in
(score desc, candidate asc) order, and the daemon's own list must be in
that order on its own scores, exact ties by candidate number.

Readings of the contract where it is not explicit (see the report):
 * a best push may sit at an end of its both-region interval, even at a
   polygon vertex (t = 0 or 1), where the supremum of the margin over the
   open region lies: its point is checked against the closed interval;
 * the last notification's `best` is the best design's score (null when
   none), and `best` never decreases;
 * a request without an id (a notification) gets no design.progress
   notifications, as it gets no answer.
"""

import collections
import itertools
import json
import math
import time

import pytest

from conftest import FIGURES, SANITIZED, SLOW

TOL = 1e-9          # the contract's tolerance on the best margin
CLOSE = 1e-12       # a classify of the design's own best push
LEN_TOL = 1e-9      # lengths and degrees recomputed by other methods
TIE = 1e-8          # reference scores this close may swap in a ranking
MAX_BATCH = 1000


def figure(key, n=1):
    FIGURES[key] = FIGURES.get(key, 0) + n


# ---- geometry: the candidate sites, computed here ---------------------------------------

def _sub(a, b):
    return (a[0] - b[0], a[1] - b[1])


def _norm(v):
    return math.hypot(v[0], v[1])


def _unit(v):
    n = _norm(v)
    return (v[0] / n, v[1] / n)


def _left(v):
    return (-v[1], v[0])


class Segment:
    """A line from p0 to p1, or an arc from p0 to p1 of included angle theta
    (signed, counter-clockwise positive) about centre c with radius r."""

    def __init__(self, p0, p1, bulge=0.0):
        self.p0, self.p1 = tuple(map(float, p0)), tuple(map(float, p1))
        self.bulge = float(bulge)
        if self.bulge == 0.0:
            self.length = _norm(_sub(self.p1, self.p0))
            return
        v = _sub(self.p1, self.p0)
        k = (1.0 - self.bulge ** 2) / (4.0 * self.bulge)
        mid = ((self.p0[0] + self.p1[0]) / 2, (self.p0[1] + self.p1[1]) / 2)
        self.c = (mid[0] - v[1] * k, mid[1] + v[0] * k)
        self.theta = 4.0 * math.atan(self.bulge)
        self.r = _norm(_sub(self.p0, self.c))
        self.a0 = math.atan2(self.p0[1] - self.c[1], self.p0[0] - self.c[0])
        self.length = self.r * abs(self.theta)

    def point(self, u):
        """The point at fraction u of the segment (of its included angle)."""
        if self.bulge == 0.0:
            return (self.p0[0] + u * (self.p1[0] - self.p0[0]),
                    self.p0[1] + u * (self.p1[1] - self.p0[1]))
        a = self.a0 + u * self.theta
        return (self.c[0] + self.r * math.cos(a), self.c[1] + self.r * math.sin(a))

    def tangent(self, u):
        if self.bulge == 0.0:
            return _unit(_sub(self.p1, self.p0))
        a = self.a0 + u * self.theta
        s = 1.0 if self.theta > 0 else -1.0
        return (-s * math.sin(a), s * math.cos(a))

    def signed_area_part(self):
        """This segment's share of the loop's signed area (shoelace plus the
        circular segment between chord and arc)."""
        a = (self.p0[0] * self.p1[1] - self.p1[0] * self.p0[1]) / 2.0
        if self.bulge != 0.0:
            a += self.r ** 2 / 2.0 * (self.theta - math.sin(self.theta))
        return a


class Loop:
    def __init__(self, segments, hole):
        self.segments = segments
        area = sum(s.signed_area_part() for s in segments)
        # the material is left of the direction of travel on a
        # counter-clockwise outer loop, right of it on a counter-clockwise hole
        self.side = (1.0 if area > 0 else -1.0) * (-1.0 if hole else 1.0)

    def normal(self, seg, u):
        t = seg.tangent(u)
        n = _left(t)
        return (self.side * n[0], self.side * n[1])


def loops_of(shape):
    """The shape as loops of segments, in the daemon's edge/segment order."""
    if shape["type"] == "polygon":
        v = shape["vertices"]
        return [Loop([Segment(v[i], v[(i + 1) % len(v)]) for i in range(len(v))], False)]
    if shape["type"] == "outline":
        loops = []
        for li, lp in enumerate(shape["loops"]):
            segs = []
            for j, vert in enumerate(lp):
                nxt = lp[(j + 1) % len(lp)]
                segs.append(Segment(vert[:2], nxt[:2], vert[2] if len(vert) > 2 else 0.0))
            loops.append(Loop(segs, li > 0))
        return loops
    raise AssertionError("no loops for " + shape["type"])


CORNER_DEG = 20.0   # a joint turning by more than this is a corner


def turn_deg(n0, n1):
    """The angle between two unit normals, in degrees."""
    return math.degrees(math.atan2(abs(n0[0] * n1[1] - n0[1] * n1[0]),
                                   n0[0] * n1[0] + n0[1] * n1[1]))


def loop_positions(lp, h, c):
    """Distances along a loop (from vertex 0, in the direction written) of
    its sites: the rule of the docstring, on the loop's own lengths."""
    segs = lp.segments
    starts = [0.0]
    for seg in segs:
        starts.append(starts[-1] + seg.length)
    perimeter = starts[-1]
    corners = [starts[j] for j in range(len(segs))
               if turn_deg(lp.normal(segs[j - 1], 1.0), lp.normal(segs[j], 0.0)) > CORNER_DEG]
    if not corners:
        n = int(math.floor(perimeter / h + 1e-9))
        return [perimeter * k / n for k in range(n)], corners, starts
    out = []
    for i, c0 in enumerate(corners):
        c1 = corners[i + 1] if i + 1 < len(corners) else corners[0] + perimeter
        usable = c1 - c0 - 2 * c
        if usable < -1e-9 * h:
            continue
        usable = max(usable, 0.0)
        n = int(math.floor(usable / h + 1e-9)) + 1
        first = c0 + c + (usable - (n - 1) * h) / 2
        out += [(first + k * h) % perimeter for k in range(n)]
    return sorted(out), corners, starts


def loop_site(lp, starts, s):
    """(at, normal) at distance s along the loop; at a joint the vertex and
    the bisector of the two segments' normals."""
    segs = lp.segments
    j = 0
    while j + 1 < len(segs) and starts[j + 1] <= s:
        j += 1
    u = min(1.0, max(0.0, (s - starts[j]) / segs[j].length))
    if u < 1e-9 or u > 1 - 1e-9:
        after = j if u < 1e-9 else (j + 1) % len(segs)
        n0, n1 = lp.normal(segs[after - 1], 1.0), lp.normal(segs[after], 0.0)
        return segs[after].point(0.0), _unit((n0[0] + n1[0], n0[1] + n1[1]))
    return segs[j].point(u), lp.normal(segs[j], u)


def spacing_sites(shape, h, clearance=None, pin_diameter=0.0, pin_fits=None):
    """[(at, normal, loop)] by the spacing rule, in the contract's order.
    pin_fits(loop, at, normal) says whether a pin of pin_diameter fits at a
    hole's site (the caller's geometry); None: every one does."""
    if shape["type"] == "circle":
        cx, cy = shape["center"]
        r = shape["radius"]
        n = int(math.floor(2 * math.pi * r / h))
        out = []
        for k in range(n):
            a = 2 * math.pi * k / n
            out.append(((cx + r * math.cos(a), cy + r * math.sin(a)),
                        (-math.cos(a), -math.sin(a)), 0))
        return out
    c = h / 2 if clearance is None else clearance
    out = []
    for li, lp in enumerate(loops_of(shape)):
        positions, _, starts = loop_positions(lp, h, c)
        for s in positions:
            at, nrm = loop_site(lp, starts, s)
            if li > 0 and pin_fits is not None and not pin_fits(li, at, nrm):
                continue
            out.append((at, nrm, li))
    return out


def boundary_point(shape, where, t):
    """The point and inward normal where push.regions says `where`, `t`."""
    if shape["type"] == "circle":
        cx, cy = shape["center"]
        r = shape["radius"]
        a = math.radians(t)
        return (cx + r * math.cos(a), cy + r * math.sin(a)), (-math.cos(a), -math.sin(a))
    loops = loops_of(shape)
    if shape["type"] == "polygon":
        lp, seg = loops[0], loops[0].segments[where["edge"]]
    else:
        lp = loops[where["loop"]]
        seg = lp.segments[where["segment"]]
    return seg.point(t), lp.normal(seg, t)


def where_of(obj):
    return {k: obj[k] for k in ("edge", "loop", "segment") if k in obj}


def site_fixels(sites, combo):
    return [{"at": list(sites[i][0]), "normal": list(sites[i][1])} for i in combo]


# ---- talking to the daemon --------------------------------------------------------------

def batch(client, calls):
    """[(method, params)] -> [response], in batches of at most MAX_BATCH."""
    out = []
    for k in range(0, len(calls), MAX_BATCH):
        part = calls[k:k + MAX_BATCH]
        reqs = [client.request(m, p) for m, p in part]
        client.send(reqs)
        resp = client.read_json()
        assert isinstance(resp, list) and len(resp) == len(reqs), str(resp)[:500]
        for q, r in zip(reqs, resp):
            assert r.get("id") == q["id"], (q, r)
        out.extend(resp)
    return out


def results(client, calls):
    out = []
    for (m, p), r in zip(calls, batch(client, calls)):
        assert "result" in r, (m, json.dumps(p)[:300], r)
        out.append(r["result"])
    return out


def design(client, params):
    """The brute force here scores every candidate: symmetric duplicates are
    kept (test_design_symmetry.py tests their collapse)."""
    params = dict(params)
    params.setdefault("collapse_symmetric", False)
    return client.result("fixture.design", params)


def fixture_of(body, friction, fixels):
    if isinstance(friction, dict):
        fr = friction
    else:
        fr = {"static": friction}
    return {"body": body, "friction": fr, "fixels": fixels}


def longest_arc(intervals_deg):
    """The longest arc of tilts, arcs split at 0/360 joined."""
    arcs = [list(iv) for iv in intervals_deg]
    if len(arcs) >= 2 and abs(arcs[0][0]) <= 1e-12 and abs(arcs[-1][1] - 360.0) <= 1e-12:
        first = arcs.pop(0)
        arcs[-1][1] += first[1]
    return max((b - a for a, b in arcs), default=0.0)


# ---- the brute force --------------------------------------------------------------------

class Brute:
    """Every candidate of `sites` (a list of (at, normal)) worked out with the
    daemon's other methods."""

    N_SAMPLES = 64      # classify samples per both-region interval
    N_ZOOM = 16         # samples per bracket per zoom level
    ZOOM_LEVELS = 9
    KEEP = 3            # local maxima refined per candidate

    def __init__(self, client, body, friction, sites, k, finger_radius=0.0,
                 finger_friction=0.0, gravity=True, push_on=None):
        """sites: (at, normal) or (at, normal, loop); push_on: the loops the
        finger may push on (None: all), applied here to the regions."""
        self.client, self.body, self.friction, self.sites, self.k = (
            client, body, friction, sites, k)
        self.push_on = push_on
        self.finger = {}
        if finger_radius:
            self.finger["finger_radius"] = finger_radius
        if finger_friction:
            self.finger["finger_friction"] = finger_friction
        self.combos = list(itertools.combinations(range(len(sites)), k))
        self.fixtures = [fixture_of(body, friction, site_fixels(sites, c)) for c in self.combos]
        self.kind = {}
        self.ids = {}
        loops = [site[2] if len(site) > 2 else 0 for site in sites]
        for r, combo in enumerate(self.combos):
            holes = [loops[i] for i in combo if loops[i] > 0]
            if len(holes) != len(set(holes)):
                self.kind[r] = "shared_hole"
        puts = batch(client, [("fixture.put", {"fixture": f}) for r, f in enumerate(self.fixtures)
                              if r not in self.kind])
        for r, resp in zip([r for r in range(len(self.combos)) if r not in self.kind], puts):
            if "error" in resp:
                assert resp["error"]["code"] == -32602, resp
                self.kind[r] = "degenerate"
            elif resp["result"]["pinned"] is False:
                self.kind[r] = "unpinned"
            else:
                self.ids[r] = resp["result"]["id"]
        live = sorted(self.ids)
        goal = results(client, [("push.regions", dict(self.finger, fixture=self.ids[r], set="goal"))
                                for r in live])
        self.goal = {}
        goal = [self.reachable(g) for g in goal]
        for r, g in zip(live, goal):
            if g["regions"]:
                self.kind[r] = "scored"
                self.goal[r] = g
            else:
                self.kind[r] = "no_seating_push"
        self.scored = sorted(self.goal)
        both = results(client, [("push.regions", dict(self.finger, fixture=self.ids[r], set="both"))
                                for r in self.scored])
        self.both = dict(zip(self.scored, [self.reachable(b) for b in both]))
        self.gravity = {}
        if gravity:
            grav = results(client, [("gravity.sweep", {"fixture": self.ids[r], "set": "goal"})
                                    for r in self.scored])
            self.gravity = {r: longest_arc(g["intervals_deg"]) for r, g in zip(self.scored, grav)}
        self.region = {r: sum(x["length"] for x in self.both[r]["regions"]) for r in self.scored}
        self._margin = None
        figure("design candidates brute-forced", len(self.combos))

    def reachable(self, answer):
        """A push.regions answer less its regions on loops not in push_on."""
        if self.push_on is None:
            return answer
        kept = [g for g in answer["regions"] if g.get("loop", 0) in self.push_on]
        return dict(answer, regions=kept, total_length=sum(g["length"] for g in kept))

    def counts(self, shard=(0, 1)):
        rs = [r for r in range(len(self.combos)) if r % shard[1] == shard[0]]
        kinds = [self.kind[r] for r in rs]
        return {"candidates": len(self.combos), "examined": len(rs),
                "degenerate": kinds.count("degenerate"), "unpinned": kinds.count("unpinned"),
                "no_seating_push": kinds.count("no_seating_push"),
                "shared_hole": kinds.count("shared_hole"),
                "symmetric": 0}  # design() keeps symmetric duplicates

    # -- the best push margin, by sampling ------------------------------------------------
    def _classify(self, points_by_r):
        """{r: [(where, t), ...]} -> {r: [margin, ...]}"""
        rs = [r for r in points_by_r if points_by_r[r]]
        calls = []
        for r in rs:
            ws = []
            for where, t in points_by_r[r]:
                p, n = boundary_point(self.body["shape"], where, t)
                ws.append({"force": list(n), "at": list(p)})
            calls.append(("wrench.classify", {"fixture": self.ids[r], "wrenches": ws,
                                              "sets": ["both"]}))
        out = {}
        for r, res in zip(rs, results(self.client, calls)):
            out[r] = [x["both"]["margin"] for x in res["results"]]
            figure("design classify samples", len(out[r]))
        return out

    def margins(self):
        """{r: sampled best margin} (0 where the both region is empty), and
        {r: (where, t)} of that maximum."""
        if self._margin is not None:
            return self._margin
        n = self.N_SAMPLES
        pts, brackets = {}, {}
        for r in self.scored:
            pts[r] = []
            for reg in self.both[r]["regions"]:
                w, t0, t1 = where_of(reg), reg["t0"], reg["t1"]
                for j in range(1, n):
                    pts[r].append((w, t0 + (t1 - t0) * j / n, t0, t1, (t1 - t0) / n))
        got = self._classify({r: [(p[0], p[1]) for p in pts[r]] for r in self.scored})
        best = {r: (0.0, None) for r in self.scored}
        for r in got:
            ms = got[r]
            # local maxima of the samples, the best KEEP of them refined
            loc = [i for i in range(len(ms))
                   if (i == 0 or ms[i] >= ms[i - 1]) and (i == len(ms) - 1 or ms[i] >= ms[i + 1])]
            loc.sort(key=lambda i: -ms[i])
            brackets[r] = []
            for i in loc[:self.KEEP]:
                w, t, t0, t1, step = pts[r][i]
                brackets[r].append([w, max(t0, t - step), min(t1, t + step), t0, t1])
                if ms[i] > best[r][0]:
                    best[r] = (ms[i], (w, t))
        m = self.N_ZOOM
        for _ in range(self.ZOOM_LEVELS):
            zp = {}
            for r in brackets:
                zp[r] = []
                for b in brackets[r]:
                    w, a, c = b[0], b[1], b[2]
                    zp[r] += [(w, a + (c - a) * j / m) for j in range(1, m)]
            got = self._classify(zp)
            for r in got:
                ms = got[r]
                for bi, b in enumerate(brackets[r]):
                    seg = ms[bi * (m - 1):(bi + 1) * (m - 1)]
                    j = max(range(len(seg)), key=lambda x: seg[x])
                    a, c = b[1], b[2]
                    t = a + (c - a) * (j + 1) / m
                    step = (c - a) / m
                    b[1], b[2] = max(b[3], t - step), min(b[4], t + step)
                    if seg[j] > best[r][0]:
                        best[r] = (seg[j], (b[0], t))
        self._margin = ({r: best[r][0] for r in self.scored},
                        {r: best[r][1] for r in self.scored})
        return self._margin

    def scores(self, objective):
        if objective == "margin":
            return self.margins()[0]
        if objective == "region":
            return self.region
        return self.gravity


# ---- checks -----------------------------------------------------------------------------

DESIGN_KEYS = {"rank", "candidate", "sites", "fixels", "pins", "best_push", "goal_length",
               "both_length", "gravity_goal_deg", "critical_mu", "score", "copies"}


def check_shape_of_answer(ans, n_sites, objective, shard=(0, 1)):
    assert set(ans) == {"designs", "counts", "sites", "objective", "shard",
                        "why_no_seating_push"}, ans.keys()
    assert sum(r["candidates"] for r in ans["why_no_seating_push"]["reasons"]) == \
        ans["counts"]["no_seating_push"]
    assert ans["sites"] == n_sites, (ans["sites"], n_sites)
    assert ans["objective"] == objective, ans["objective"]
    assert ans["shard"] == list(shard), ans["shard"]
    for i, d in enumerate(ans["designs"]):
        assert set(d) == DESIGN_KEYS, d.keys()
        assert d["rank"] == i + 1, d
    # the answer's own order: score descending, ties by candidate ascending
    for a, b in zip(ans["designs"], ans["designs"][1:]):
        assert (a["score"] > b["score"]) or (a["score"] == b["score"]
                                             and a["candidate"] < b["candidate"]), (a, b)


def check_candidate_identity(ans, brute, pin_diameter=0.0):
    """Each design's number, site list and fixels are those of our
    combination; its pins, those of its sites on holes."""
    for d in ans["designs"]:
        loops = [brute.sites[i][2] if len(brute.sites[i]) > 2 else 0 for i in d["sites"]]
        assert d["pins"] == [{"fixel": f, "hole": l, "diameter": pin_diameter}
                             for f, l in enumerate(loops) if l > 0], (d["pins"], loops)
        r = d["candidate"]
        assert isinstance(r, int) and 0 <= r < len(brute.combos), d
        assert d["sites"] == list(brute.combos[r]), (r, d["sites"], brute.combos[r])
        assert len(d["fixels"]) == brute.k, d
        for fx, i in zip(d["fixels"], brute.combos[r]):
            assert set(fx) == {"at", "normal"}, fx
            at, nrm = brute.sites[i][:2]
            assert max(abs(fx["at"][0] - at[0]), abs(fx["at"][1] - at[1])) <= 1e-9, (i, fx, at)
            assert max(abs(fx["normal"][0] - nrm[0]), abs(fx["normal"][1] - nrm[1])) <= 1e-9, (
                i, fx, nrm)


def check_ranking(designs, ref, top, tol, tie=TIE):
    """designs: the daemon's list; ref: {candidate: reference score} of every
    scored candidate.  Each score within tol of ours; the selection and the
    order those of (ref desc, candidate asc), up to swaps between candidates
    whose reference scores lie within `tie` of each other."""
    expected = sorted(ref, key=lambda r: (-ref[r], r))[:top]
    assert len(designs) == min(top, len(ref)), (len(designs), top, len(ref))
    got = [d["candidate"] for d in designs]
    for d in designs:
        r = d["candidate"]
        assert r in ref, ("a design that is not a scored candidate", r)
        assert abs(d["score"] - ref[r]) <= tol, (r, d["score"], ref[r])
    for i, (g, e) in enumerate(zip(got, expected)):
        if g != e:
            assert abs(ref[g] - ref[e]) <= tie, (
                "rank %d: candidate %d (reference score %r), expected %d (%r)"
                % (i + 1, g, ref[g], e, ref[e]), got, expected)
            figure("design near-tie swaps allowed")
    # nothing better left out
    if designs:
        floor = min(ref[r] for r in got)
        for r in ref:
            if r not in got:
                assert ref[r] <= floor + tie, ("candidate %d (score %r) left out" % (r, ref[r]),
                                               got)
    assert len(set(got)) == len(got), got


def check_best_push(client, brute, d, body, friction, objective="margin"):
    """The best push is a point of the both region whose classify gives its
    margin; it lies on the boundary where it says, pushing along the inward
    normal there; its margin is at least our sampled maximum less 1e-9."""
    r = d["candidate"]
    bp = d["best_push"]
    ms, _ = brute.margins()
    if not brute.both[r]["regions"]:
        assert bp is None, d
        assert d["score"] == 0, d
        return
    assert isinstance(bp, dict), d
    shape = body["shape"]
    keys = {"at", "direction", "margin", "t"} | (
        {"loop", "segment"} if shape["type"] == "outline" else {"edge"})
    assert set(bp) == keys, bp
    where, t = where_of(bp), bp["t"]
    p, n = boundary_point(shape, where, t)
    assert max(abs(bp["at"][0] - p[0]), abs(bp["at"][1] - p[1])) <= 1e-9, (bp, p)
    assert max(abs(bp["direction"][0] - n[0]), abs(bp["direction"][1] - n[1])) <= 1e-9, (bp, n)
    # inside (the closure of) a both region, which the finger (if any) allows
    inside = [reg for reg in brute.both[r]["regions"]
              if where_of(reg) == where and reg["t0"] - 1e-12 <= t <= reg["t1"] + 1e-12]
    assert inside, ("best push outside the both region", r, bp, brute.both[r]["regions"])
    # classify the reported push: its margin is the design's
    fx = fixture_of(body, friction, d["fixels"])
    got = client.result("wrench.classify", {
        "fixture": fx, "sets": ["both"],
        "wrenches": [{"force": bp["direction"], "at": bp["at"]}]})["results"][0]["both"]["margin"]
    assert abs(got - bp["margin"]) <= CLOSE, (r, got, bp["margin"])
    if objective == "margin":
        assert bp["margin"] == d["score"], d
    assert bp["margin"] >= ms[r] - TOL, ("best push below our sampled maximum", r, bp["margin"],
                                         ms[r])
    figure("design best pushes classified")


# ---- bodies -----------------------------------------------------------------------------

def load_example(name):
    import os
    here = os.path.dirname(os.path.abspath(__file__))
    with open(os.path.join(here, "..", "..", "examples", name)) as f:
        return json.load(f)


CHAMFER = {"mass": 2.0, "shape": {"type": "polygon",
                                  "vertices": [[0, 0], [4, 0], [4, 1], [3, 2], [0, 2]]}}
# a 12-sided plate: a stepped bottom, a chamfered corner and a slot on top
DODECAGON = {"mass": 1.5, "shape": {"type": "polygon", "vertices": [
    [0, 0], [3, 0], [4, 0.5], [6, 0.5], [6, 3], [5, 4], [3.5, 4], [3.5, 3], [2.5, 3], [2.5, 4],
    [0.5, 4], [0, 3]]}}
RECTANGLE = {"mass": 1.0, "shape": {"type": "polygon",
                                    "vertices": [[0, 0], [10, 0], [10, 4], [0, 4]]}}
# an outline with a quarter-circle arc (bulge tan(22.5 deg)), written clockwise
ARC_PLATE = {"mass": 1.0, "inertia": 7.5, "com": [3.9, 2.4], "shape": {"type": "outline", "loops": [
    [[0, 0], [0, 5], [8, 5], [8, 2, -0.41421356237309503], [6, 0]]]}}
DISC = {"mass": 1.0, "shape": {"type": "circle", "center": [1, 2], "radius": 1.0}}
# a square plate with a round hole of radius 2 about (5, 5), two half circles
# (counter-clockwise): pins in the hole, pushes from inside it
HOLED = {"mass": 1.0, "shape": {"type": "outline", "loops": [
    [[0, 0], [10, 0], [10, 10], [0, 10]], [[3, 5, 1], [7, 5, 1]]]}}

BRUTE_CASES = [
    # name, body, friction, spacing, fixels
    ("chamfer", CHAMFER, 0.1, 1.0, 3),
    ("dodecagon", DODECAGON, 0.05, 1.5, 3),
    ("rectangle", RECTANGLE, 0.1, 2.0, 3),
    ("arc-plate", ARC_PLATE, 0.2, 2.0, 3),
    ("disc", DISC, 0.3, 1.0, 2),
    ("holed", HOLED, 0.3, 2.5, 2),
]


# ---- 1. brute force: counts, ranking, scores and best pushes -------------------------------

def check_why(client, brute, base):
    """why_no_seating_push against wrench.classify: each candidate without a
    seating push, its fixture classified (set goal) for the push at the
    point the answer names (its inward normal there, computed here), counted
    by blocking string; a push inside G_goal counts as null.  The design is
    asked with our sites given, to the bit: a push at a point of symmetry
    (HOLED's (5, 0)) meets mirror-image candidates whose two cones tie to
    the last bit, and sites equal only to 1e-12 would break the tie
    either way."""
    sites = [{"at": list(s[0]), "normal": list(s[1])} for s in brute.sites]
    params = {k: v for k, v in base.items() if k != "spacing"}
    ans = design(client, dict(params, sites=sites, top=1))
    assert ans["counts"] == brute.counts(), (ans["counts"], brute.counts())
    why = ans["why_no_seating_push"]
    asked = why["asked_at"]
    where = {k: asked[k] for k in ("edge", "loop", "segment") if k in asked}
    p, n = boundary_point(brute.body["shape"], where, asked["t"])
    assert max(abs(p[0] - asked["at"][0]), abs(p[1] - asked["at"][1])) <= 1e-9, (p, asked)
    rs = [r for r in range(len(brute.combos)) if brute.kind[r] == "no_seating_push"]
    calls = [("wrench.classify", {"fixture": brute.ids[r], "sets": ["goal"],
                                  "wrenches": [{"force": list(n), "at": list(p)}]}) for r in rs]
    tally = collections.Counter()
    for res in results(brute.client, calls):
        v = res["results"][0]["goal"]
        tally[None if v["inside"] else v["blocking"]] += 1
    got = {r["blocking"]: r["candidates"] for r in why["reasons"]}
    assert got == dict(tally), (got, tally)
    figure("design why reasons recounted", len(rs))


def check_figures_against_brute(ans, brute):
    """goal_length, both_length and gravity_goal_deg of every design, against
    push.regions and gravity.sweep of our own candidate fixture."""
    for d in ans["designs"]:
        r = d["candidate"]
        assert abs(d["goal_length"] - brute.goal[r]["total_length"]) <= LEN_TOL, (r, d)
        assert abs(d["both_length"] - brute.both[r]["total_length"]) <= LEN_TOL, (r, d)
        if brute.gravity:
            assert abs(d["gravity_goal_deg"] - brute.gravity[r]) <= LEN_TOL, (r, d,
                                                                              brute.gravity[r])
        mu = d["critical_mu"]
        assert mu is None or (isinstance(mu, (int, float)) and 0 <= mu <= 2), d


@pytest.mark.parametrize("name, body, friction, spacing, k", BRUTE_CASES,
                         ids=[c[0] for c in BRUTE_CASES])
def test_brute_force(client, name, body, friction, spacing, k):
    sites = spacing_sites(body["shape"], spacing)
    brute = Brute(client, body, friction, sites, k)
    assert len(brute.scored) >= 10, ("the case should score enough candidates", name,
                                     brute.counts())
    base = {"body": body, "friction": friction, "spacing": spacing, "fixels": k}
    fr = {"static": friction}
    for objective, top in (("margin", 15), ("region", 6), ("gravity", 6)):
        ans = design(client, dict(base, objective=objective, top=top))
        check_shape_of_answer(ans, len(sites), objective)
        assert ans["counts"] == brute.counts(), (objective, ans["counts"], brute.counts())
        check_candidate_identity(ans, brute)
        ref = brute.scores(objective)
        if objective == "margin":
            # ours are lower bounds (sampled), the design's within 1e-9 of the
            # maximum: the design may be above ours by our sampling error only
            check_ranking(ans["designs"], ref, top, tol=1e-8, tie=1e-8)
        else:
            check_ranking(ans["designs"], ref, top, tol=LEN_TOL, tie=LEN_TOL)
        for d in ans["designs"]:
            check_best_push(client, brute, d, body, fr, objective)
        check_figures_against_brute(ans, brute)
        if objective == "margin":
            check_why(client, brute, base)
        figure("design rankings compared")


# ---- designer's own sites: degenerate and unpinned candidates ------------------------------

R2 = math.sqrt(0.5)
# On RECTANGLE (0..10 x 0..4): three sites at the corner (0, 0) with three
# normals (every candidate of only them is unpinned), a site given twice
# (candidates holding both are degenerate: same point, same normal), and
# ordinary sites, normals left out where the edge has one.
OWN_SITES = [
    ({"at": [0, 0], "normal": [1, 0]}, ((0, 0), (1, 0))),
    ({"at": [0, 0], "normal": [0, 1]}, ((0, 0), (0, 1))),
    ({"at": [0, 0], "normal": [R2, R2]}, ((0, 0), (R2, R2))),
    ({"at": [3, 0]}, ((3, 0), (0, 1))),
    ({"at": [3, 0]}, ((3, 0), (0, 1))),
    ({"at": [7.5, 0]}, ((7.5, 0), (0, 1))),
    ({"at": [10, 2]}, ((10, 2), (-1, 0))),
    ({"at": [6, 4]}, ((6, 4), (0, -1))),
    ({"at": [0, 2.5]}, ((0, 2.5), (1, 0))),
    # a normal not of unit length: the fixel's is divided by its length
    ({"at": [10, 4], "normal": [-3, -4]}, ((10, 4), (-0.6, -0.8))),
]


@pytest.mark.parametrize("k", [2, 3, 4])
def test_own_sites_degenerate_unpinned(client, k):
    sites = [s for _, s in OWN_SITES]
    brute = Brute(client, RECTANGLE, 0.1, sites, k, gravity=False)
    c = brute.counts()
    # the case must hold each kind of rejection
    assert c["degenerate"] >= 1 and c["no_seating_push"] >= 1, c
    assert c["unpinned"] >= (1 if k <= 3 else 0), c
    ans = design(client, {"body": RECTANGLE, "friction": 0.1, "fixels": k, "top": 1000,
                          "objective": "region", "sites": [w for w, _ in OWN_SITES]})
    check_shape_of_answer(ans, len(sites), "region")
    assert ans["counts"] == c, (ans["counts"], c)
    check_candidate_identity(ans, brute)
    check_ranking(ans["designs"], brute.region, 1000, tol=LEN_TOL, tie=LEN_TOL)
    check_figures_against_brute(ans, brute)
    # no degenerate nor unpinned candidate is ranked
    for d in ans["designs"]:
        assert brute.kind[d["candidate"]] == "scored", d


# ---- 2. a design's figures, by the other methods, for its own fixels -----------------------

def other_methods(client, body, friction, fixels, finger=None):
    finger = finger or {}
    fx = fixture_of(body, friction, fixels)
    goal, both, grav, sweep = results(client, [
        ("push.regions", dict(finger, fixture=fx, set="goal")),
        ("push.regions", dict(finger, fixture=fx, set="both")),
        ("gravity.sweep", {"fixture": fx, "set": "goal"}),
        ("friction.sweep", {"fixture": fx, "range": [0, 2], "kinetic_ratio": 1,
                            "push": dict(finger, set="goal")}),
    ])
    return goal, both, grav, sweep


def check_design_figures(client, body, friction, d, finger=None):
    goal, both, grav, sweep = other_methods(client, body, friction, d["fixels"], finger)
    assert abs(d["goal_length"] - goal["total_length"]) <= LEN_TOL, (d, goal)
    assert abs(d["both_length"] - both["total_length"]) <= LEN_TOL, (d, both)
    assert abs(d["gravity_goal_deg"] - longest_arc(grav["intervals_deg"])) <= LEN_TOL, (d, grav)
    if sweep["critical"] is None:
        assert d["critical_mu"] is None, (d, sweep)
    else:
        assert d["critical_mu"] is not None and abs(d["critical_mu"] - sweep["critical"]) <= 1e-9, (
            d["critical_mu"], sweep["critical"])
    figure("design figures recomputed")
    return goal, both


@pytest.mark.parametrize("name, body, friction, spacing, k, objective", [
    ("chamfer", CHAMFER, 0.1, 1.0, 3, "margin"),
    ("arc-plate", ARC_PLATE, 0.2, 2.0, 3, "gravity"),
    ("disc", DISC, 0.3, 1.0, 2, "region"),
])
def test_figures_by_other_methods(client, name, body, friction, spacing, k, objective):
    ans = design(client, {"body": body, "friction": friction, "spacing": spacing, "fixels": k,
                          "objective": objective, "top": 4})
    assert len(ans["designs"]) == 4, ans
    crit = 0
    for d in ans["designs"]:
        check_design_figures(client, body, {"static": friction}, d)
        crit += d["critical_mu"] is not None
    figure("design critical mu compared", crit)


def test_disc_closed_forms_and_critical_mu(client):
    """The disc held at two sites whose inward normals n1, n2 are D <= 180
    degrees apart (docs/MODEL.md 7.1 is D = 90, turned).  A push at the
    boundary goes through the centre along f; measure its angle a from -n1
    towards -n2.  It seats the disc from every contact state exactly when
    (i) it presses on both fixels, f . n_i < 0 (otherwise, touching fixel i
    alone, the disc leaves it along f and may pass the other point fixel by):
    D - 90 < a < 90; and (ii) touching one fixel it slides towards the other,
    i.e. f lies outside both friction cones: atan mu < a < D - atan mu.  The
    goal arc is (max(D - 90, atan mu), min(90, D - atan mu)), of length R
    times its width in radians, and it is non-empty exactly for
    mu < tan(D / 2): the critical mu is tan(D / 2), null above 2."""
    mu = 0.3
    angles = [180.0, 270.0, 310.0]
    sites = [{"at": [1 + math.cos(math.radians(a)), 2 + math.sin(math.radians(a))]}
             for a in angles]
    ans = design(client, {"body": DISC, "friction": mu, "fixels": 2, "sites": sites,
                          "objective": "region", "top": 10})
    assert ans["counts"] == {"candidates": 3, "examined": 3, "degenerate": 0, "unpinned": 0,
                             "no_seating_push": 0, "shared_hole": 0,
                             "symmetric": 0}, ans["counts"]
    by_sites = {tuple(d["sites"]): d for d in ans["designs"]}
    assert sorted(by_sites) == [(0, 1), (0, 2), (1, 2)], by_sites.keys()
    am = math.atan(mu)
    nulls = 0
    for (i, j), d in by_sites.items():
        delta = math.radians(angles[j] - angles[i])
        lo, hi = max(delta - math.pi / 2, am), min(math.pi / 2, delta - am)
        assert abs(d["goal_length"] - (hi - lo)) <= LEN_TOL, (i, j, d["goal_length"], hi - lo)
        crit = math.tan(delta / 2)
        if crit > 2:
            assert d["critical_mu"] is None, (i, j, d)
            nulls += 1
        else:
            assert d["critical_mu"] is not None and abs(d["critical_mu"] - crit) <= 1e-9, (
                i, j, d["critical_mu"], crit)
        check_design_figures(client, DISC, {"static": mu}, d)
    assert nulls == 1


# ---- 3. shards merged equal the whole run ----------------------------------------------------

def merged(answers, top):
    designs = [d for a in answers for d in a["designs"]]
    designs.sort(key=lambda d: (-d["score"], d["candidate"]))
    counts = {k: sum(a["counts"][k] for a in answers)
              for k in ("examined", "degenerate", "unpinned", "no_seating_push", "shared_hole",
                        "symmetric")}
    counts["candidates"] = answers[0]["counts"]["candidates"]
    return designs[:top], counts


def without_rank(designs):
    return [{k: v for k, v in d.items() if k != "rank"} for d in designs]


@pytest.mark.parametrize("objective, n, top", [("margin", 3, 5), ("region", 3, 4),
                                                ("gravity", 4, 3)])
def test_shards_merge_to_the_whole(client, objective, n, top):
    # the chamfered plate, 17 sites (6 + 1 + 2 + 5 + 3), 680 candidates
    base = {"body": CHAMFER, "friction": 0.1, "spacing": 0.6, "objective": objective,
            "top": top}
    whole = design(client, base)
    total = whole["counts"]["candidates"]
    assert total == math.comb(17, 3) == 680
    assert whole["counts"]["examined"] == total
    one = design(client, dict(base, shard=[0, 1]))
    assert one == whole
    parts = []
    for i in range(n):
        a = design(client, dict(base, shard=[i, n]))
        assert a["shard"] == [i, n], a["shard"]
        assert a["counts"]["candidates"] == total, a["counts"]
        assert a["counts"]["examined"] == len(range(i, total, n)), a["counts"]
        assert a["sites"] == whole["sites"] and a["objective"] == objective
        for d in a["designs"]:
            assert d["candidate"] % n == i, (i, n, d["candidate"])
        assert [d["rank"] for d in a["designs"]] == list(range(1, len(a["designs"]) + 1))
        parts.append(a)
    designs, counts = merged(parts, top)
    assert counts == whole["counts"], (counts, whole["counts"])
    assert len(whole["designs"]) == top
    # exactly: every figure bit for bit, candidates, sites, fixels, best pushes
    assert without_rank(designs) == without_rank(whole["designs"])
    figure("design shard runs merged", n)


# ---- 4. sites by spacing, in closed form -------------------------------------------------

def sites_read_back(ans):
    """{site index: (at, normal)} from the designs' fixels; one site, one place."""
    seen = {}
    for d in ans["designs"]:
        for i, fx in zip(d["sites"], d["fixels"]):
            got = (tuple(fx["at"]), tuple(fx["normal"]))
            assert seen.setdefault(i, got) == got, (i, seen[i], got)
    return seen


def assert_sites(seen, expected):
    assert sorted(seen) == list(range(len(expected))), ("every site should be in a design",
                                                        sorted(seen), len(expected))
    for i, (at, nrm) in enumerate(expected):
        got_at, got_n = seen[i]
        assert max(abs(got_at[0] - at[0]), abs(got_at[1] - at[1])) <= 1e-12, (i, got_at, at)
        assert max(abs(got_n[0] - nrm[0]), abs(got_n[1] - nrm[1])) <= 1e-12, (i, got_n, nrm)
    figure("design sites checked in closed form", len(expected))


@pytest.mark.parametrize("h, expected", [
    # 10 x 4, counter-clockwise: bottom (1,3,5,7,9), right (1,3 up), top
    # (from (10,4) leftwards), left (from (0,4) down)
    (2.0, [((x, 0), (0, 1)) for x in (1, 3, 5, 7, 9)] + [((10, y), (-1, 0)) for y in (1, 3)]
     + [((x, 4), (0, -1)) for x in (9, 7, 5, 3, 1)] + [((0, y), (1, 0)) for y in (3, 1)]),
    # h = 3: floor(10/3) = 3 at 2, 5, 8; floor(4/3) = 1 at 2
    (3.0, [((x, 0), (0, 1)) for x in (2, 5, 8)] + [((10, 2), (-1, 0))]
     + [((x, 4), (0, -1)) for x in (8, 5, 2)] + [((0, 2), (1, 0))]),
])
def test_spacing_rectangle_closed_form(client, h, expected):
    ans = design(client, {"body": RECTANGLE, "friction": 0.0, "spacing": h, "fixels": 2,
                          "objective": "region", "top": 1000})
    assert ans["sites"] == len(expected), (ans["sites"], len(expected))
    assert ans["counts"]["candidates"] == math.comb(len(expected), 2)
    assert_sites(sites_read_back(ans), expected)


def test_spacing_rectangle_clockwise_and_odd_spacing(client):
    """Written clockwise from (0, 4): edges (0,4)->(10,4)->(10,0)->(0,0)->(0,4);
    h = 4.5: the top and bottom (10) get floor(10/4.5) = 2 sites at 0.5 +
    2.25 +- ... i.e. (10 - 4.5) / 2 = 2.75 and 7.25 from each start; the
    sides (4) none."""
    body = {"mass": 1.0, "shape": {"type": "polygon",
                                   "vertices": [[0, 4], [10, 4], [10, 0], [0, 0]]}}
    expected = [((2.75, 4), (0, -1)), ((7.25, 4), (0, -1)),
                ((7.25, 0), (0, 1)), ((2.75, 0), (0, 1))]
    ans = design(client, {"body": body, "friction": 0.0, "spacing": 4.5, "fixels": 1,
                          "top": 10})
    assert ans["sites"] == 4, ans
    # one fixel is a pivot: every candidate is unpinned
    assert ans["counts"] == {"candidates": 4, "examined": 4, "degenerate": 0, "unpinned": 4,
                             "no_seating_push": 0, "shared_hole": 0,
                             "symmetric": 0}, ans["counts"]
    assert ans["designs"] == []
    ans = design(client, {"body": body, "friction": 0.0, "spacing": 4.5, "fixels": 3,
                          "objective": "region", "top": 10})
    assert ans["counts"]["candidates"] == 4
    seen = sites_read_back(ans)
    for i, (at, nrm) in enumerate(expected):
        if i in seen:
            assert max(abs(a - b) for a, b in zip(seen[i][0] + seen[i][1], at + nrm)) <= 1e-12


def test_spacing_circle_closed_form(client):
    """R = 2, h = 1: floor(4 pi) = 12 sites at 30 degree steps from +x."""
    body = {"mass": 1.0, "shape": {"type": "circle", "center": [0.5, -1], "radius": 2.0}}
    expected = []
    for k in range(12):
        a = 2 * math.pi * k / 12
        expected.append(((0.5 + 2 * math.cos(a), -1 + 2 * math.sin(a)),
                         (-math.cos(a), -math.sin(a))))
    ans = design(client, {"body": body, "friction": 0.1, "spacing": 1.0, "fixels": 2,
                          "objective": "gravity", "top": 1000})
    assert ans["sites"] == 12 and ans["counts"]["candidates"] == 66, ans["counts"]
    assert_sites(sites_read_back(ans), expected)
    # h just above 2 pi R / 7: 6 sites at 60 degree steps
    ans = design(client, {"body": body, "friction": 0.1, "spacing": 4 * math.pi / 7 + 1e-6,
                          "fixels": 2, "top": 1})
    assert ans["sites"] == 6, ans["sites"]


D_PLATE = {"mass": 1.0, "shape": {"type": "outline", "loops": [
    [[0, 0], [4, 0, 1], [4, 4], [0, 4]]]}}


def test_spacing_outline_arc_sites(client):
    """D_PLATE: counter-clockwise, a line (0,0)->(4,0), a half circle about
    (4, 2), R = 2, through (6, 2) (2 pi long), lines (4,4)->(0,4)->(0,0).
    The half circle meets both lines tangentially: one run from the corner
    (0, 0) to the corner (0, 4), 8 + 2 pi long; h = 2, c = 1: floor((6 +
    2 pi) / 2) + 1 = 7 sites from pi - 2 along it, 2 apart: (pi - 2, 0),
    (pi, 0); on the arc at angles -1, 0, 1 radian about (4, 2), radial
    normals towards the centre; (pi, 4), (pi - 2, 4).  The left side, 4
    long: 2 sites, at 1 and 3 from (0, 4)."""
    pi = math.pi
    expected = [((pi - 2, 0), (0, 1)), ((pi, 0), (0, 1))]
    for a in (-1.0, 0.0, 1.0):
        expected.append(((4 + 2 * math.cos(a), 2 + 2 * math.sin(a)),
                         (-math.cos(a), -math.sin(a))))
    expected += [((pi, 4), (0, -1)), ((pi - 2, 4), (0, -1)), ((0, 3), (1, 0)), ((0, 1), (1, 0))]
    ans = design(client, {"body": D_PLATE, "friction": 0.1, "spacing": 2.0, "fixels": 2,
                          "objective": "region", "top": 1000})
    assert ans["sites"] == 9, ans["sites"]
    assert_sites(sites_read_back(ans), expected)
    # and our geometry agrees (it is what the brute force builds on)
    mine = spacing_sites(D_PLATE["shape"], 2.0)
    assert len(mine) == len(expected)
    for (at, nrm), (a2, n2, loop) in zip(expected, mine):
        assert loop == 0 and max(abs(a - b) for a, b in zip(at + nrm, a2 + n2)) <= 1e-12


# ---- 5. progress notifications ------------------------------------------------------------

# a run of over a second: the chamfered plate, 74 sites, C(74, 3) = 64824
# candidates (45 sites, 14190 candidates under a sanitizer, 3-5 times slower)
LONG_SPACING = 0.25 if SANITIZED else 0.15
LONG_CANDIDATES = 14190 if SANITIZED else 64824


def call_with_progress(client, params, id):
    """Send fixture.design with progress; -> (notifications with arrival
    times, the response, elapsed seconds)."""
    req = {"jsonrpc": "2.0", "method": "fixture.design", "params": params, "id": id}
    t0 = time.monotonic()
    client.send(req)
    notes = []
    while True:
        msg = client.read_json()
        now = time.monotonic() - t0
        if "method" in msg:
            notes.append((now, msg))
            continue
        assert msg.get("id") == id, msg
        return notes, msg, now


def check_notifications(notes, resp, id, total):
    assert "result" in resp, resp
    assert len(notes) >= 2, notes
    last_done = -1
    last_best = None
    # The designs' figures come after the candidates (stage "figures").
    figures = [n for n in notes if n[1]["params"].get("stage") == "figures"]
    notes = [n for n in notes if n[1]["params"].get("stage") != "figures"]
    for _, n in figures:
        p = n["params"]
        assert set(p) == {"id", "stage", "done", "total", "best", "eta_s"}, p
        assert 0 <= p["done"] <= p["total"] == len(resp["result"]["designs"]), p
    for _, n in notes:
        assert set(n) == {"jsonrpc", "method", "params"}, n       # a notification: no id
        assert n["jsonrpc"] == "2.0" and n["method"] == "design.progress", n
        p = n["params"]
        # "stage": "candidates" (a lattice's "poses" come first; none here)
        assert set(p) == {"id", "stage", "done", "total", "best", "eta_s"}, p
        assert p["stage"] == "candidates", p
        # the seconds left: unknown before any is done, 0 at the end
        assert p["eta_s"] is None or p["eta_s"] >= 0, p
        if p["done"] == total:
            assert p["eta_s"] == 0, p
        assert p["id"] == id, (p, id)
        assert p["total"] == total, (p, total)
        assert isinstance(p["done"], int) and 0 <= p["done"] <= total, p
        assert p["done"] >= last_done, ("done went back", notes)
        last_done = p["done"]
        assert p["best"] is None or isinstance(p["best"], (int, float)), p
        if last_best is not None:
            assert p["best"] is not None and p["best"] >= last_best, ("best went back", notes)
        last_best = p["best"]
    assert notes[0][1]["params"]["done"] == 0, notes[0]
    assert notes[-1][1]["params"]["done"] == total, notes[-1]
    # one notification with done == total
    assert sum(1 for _, n in notes if n["params"]["done"] == total) == 1, notes
    designs = resp["result"]["designs"]
    if designs:
        assert notes[-1][1]["params"]["best"] == designs[0]["score"], (notes[-1], designs[0])
    else:
        assert notes[-1][1]["params"]["best"] is None, notes[-1]


def test_progress_long_run(daemon):
    """A run of over a second: notifications before the answer, at most
    about four a second; meanwhile another client is answered at once."""
    client, other = daemon.client(), daemon.client()
    params = {"body": CHAMFER, "friction": 0.1, "spacing": LONG_SPACING, "top": 2,
              "progress": True}
    t0 = time.monotonic()
    client.send({"jsonrpc": "2.0", "method": "fixture.design", "params": params, "id": "long-1"})
    notes = []
    waited = None
    while True:
        msg = client.read_json()
        now = time.monotonic() - t0
        if "method" not in msg:
            resp, elapsed = msg, now
            break
        notes.append((now, msg))
        if waited is None:
            # the other client, while the run goes on
            t1 = time.monotonic()
            assert other.result("server.status", {})["clients"] >= 2
            assert other.result("fixture.design", {"body": CHAMFER, "friction": 0.1,
                                                   "spacing": 2.0})["counts"]["candidates"] == 4
            waited = time.monotonic() - t1
    assert resp["id"] == "long-1", resp
    assert waited < 0.5 * SLOW, ("another client waited during the run", waited)
    assert resp["result"]["counts"]["candidates"] == LONG_CANDIDATES, resp["result"]["counts"]
    assert elapsed > 1.0, ("the run should take over a second", elapsed)
    check_notifications(notes, resp, "long-1", LONG_CANDIDATES)
    # at most about four a second: the first, the last, and those between
    between = len(notes) - 2
    assert between <= 4.5 * elapsed + 1, (len(notes), elapsed, [t for t, _ in notes])
    # and some between, on a run this long (otherwise it is not progress)
    assert between >= 1, (len(notes), elapsed)
    # The end of a stage (done == total) is said at once, whenever it comes;
    # the rate holds for the notifications between the stages' ends.
    times = [t for t, m in notes[1:-1] if m["params"]["done"] != m["params"]["total"]]
    gaps = [b - a for a, b in zip(times, times[1:])]
    assert all(g >= 0.15 for g in gaps), ("notifications closer than a quarter second", gaps)
    figure("design progress notifications", len(notes))


def test_progress_eta(client):
    """eta_s, the seconds left of the stage at its rate so far, against the
    time the stage then took, measured here: within a factor of three once
    a fifth of it is done (a shared machine's rate varies), and the Python
    client's bar and wrenchctl's print it."""
    import io
    import os
    import sys
    sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..",
                                    "clients", "python"))
    import wrenchd
    params = {"body": CHAMFER, "friction": 0.1, "spacing": LONG_SPACING, "top": 2,
              "progress": True, "collapse_symmetric": False}
    notes, resp, elapsed = call_with_progress(client, params, "eta")
    search = [(t, n["params"]) for t, n in notes if n["params"]["stage"] == "candidates"]
    end = search[-1][0]                       # the notification at done == total
    assert search[-1][1]["done"] == search[-1][1]["total"] and search[-1][1]["eta_s"] == 0
    assert search[0][1]["eta_s"] is None      # nothing done yet: no rate
    checked = 0
    for t, p in search[1:-1]:
        assert p["eta_s"] is not None and p["eta_s"] >= 0, p
        if p["done"] >= p["total"] / 5:
            left = end - t
            assert left / 3 - 0.3 <= p["eta_s"] <= 3 * left + 0.3, (p, left)
            checked += 1
    assert checked >= 1, search
    bar = io.StringIO()
    for _, n in notes:
        wrenchd.progress_bar(bar)(n["params"])
    text = bar.getvalue()
    assert "left" in text and "100%" in text and "candidates" in text, text


def test_progress_shard_total_and_numeric_id(client):
    params = {"body": CHAMFER, "friction": 0.1, "spacing": 0.5, "top": 3, "progress": True,
              "shard": [1, 3]}
    notes, resp, _ = call_with_progress(client, params, 77)
    total = len(range(1, 1540, 3))
    assert resp["result"]["counts"]["examined"] == total
    check_notifications(notes, resp, 77, total)


def test_progress_without_designs(client):
    """best stays null when no candidate is scored (the 12-sided regular
    plate at mu 0.2, sites at its edges' middles: nothing seats)."""
    verts = [[math.cos(2 * math.pi * k / 12), math.sin(2 * math.pi * k / 12)] for k in range(12)]
    body = {"mass": 1.0, "shape": {"type": "polygon", "vertices": verts}}
    notes, resp, _ = call_with_progress(client, {"body": body, "friction": 0.2, "spacing": 0.4,
                                                 "progress": True, "collapse_symmetric": False},
                                        "none")
    assert resp["result"]["counts"]["no_seating_push"] == 220, resp["result"]["counts"]
    assert resp["result"]["designs"] == []
    check_notifications(notes, resp, "none", 220)
    assert all(n["params"]["best"] is None for _, n in notes)


def test_no_progress_when_false_or_absent(client):
    params = {"body": CHAMFER, "friction": 0.1, "spacing": 0.7, "top": 2}
    notes, with_progress, _ = call_with_progress(client, dict(params, progress=True), 5)
    assert len(notes) >= 2
    for extra in ({}, {"progress": False}):
        req = client.request("fixture.design", dict(params, **extra))
        client.send(req)
        msg = client.read_json()
        assert "method" not in msg and msg["id"] == req["id"] and "result" in msg, msg
        # progress changes nothing in the answer
        assert msg["result"] == with_progress["result"]
    client.expect_silence(0.2)


def test_no_progress_in_a_batch(client):
    params = {"body": CHAMFER, "friction": 0.1, "spacing": 0.7, "top": 2, "progress": True,
              "collapse_symmetric": False}
    reqs = [client.request("fixture.design", params), client.request("server.status", {}),
            client.request("fixture.design", dict(params, shard=[0, 2]))]
    client.send(reqs)
    msg = client.read_json()
    assert isinstance(msg, list) and len(msg) == 3, str(msg)[:300]
    assert [m["id"] for m in msg] == [r["id"] for r in reqs]
    assert all("result" in m for m in msg), str(msg)[:500]
    single = design(client, dict(params, progress=False))
    assert msg[0]["result"] == single
    client.expect_silence(0.2)


# ---- 6. refusals ------------------------------------------------------------------------

GOOD = {"body": CHAMFER, "friction": 0.1, "spacing": 1.0}


def without(d, key):
    return {k: v for k, v in d.items() if k != key}


ERRORS = [
    ("no body", without(GOOD, "body"), "params.body"),
    ("body without shape", dict(GOOD, body={"mass": 1.0, "inertia": 1.0, "com": [0, 0]}),
     "params.body.shape"),
    ("body without mass", dict(GOOD, body={"shape": CHAMFER["shape"]}), "params.body.mass"),
    ("body mass negative", dict(GOOD, body=dict(CHAMFER, mass=-1)), "params.body.mass"),
    ("no friction", without(GOOD, "friction"), "params.friction"),
    ("friction string", dict(GOOD, friction="low"), "params.friction"),
    ("friction negative", dict(GOOD, friction=-0.1), "params.friction"),
    ("friction interval empty", dict(GOOD, friction=[0.3, 0.1]), "params.friction"),
    ("friction interval bound", dict(GOOD, friction=[0.1, 2000]), "params.friction[1]"),
    ("friction kinetic above static", dict(GOOD, friction={"static": 0.1, "kinetic": 0.2}),
     "params.friction.kinetic"),
    ("friction unknown member", dict(GOOD, friction={"static": 0.1, "dynamic": 0.1}),
     "params.friction.dynamic"),
    ("fixels 0", dict(GOOD, fixels=0), "params.fixels"),
    ("fixels 9", dict(GOOD, fixels=9), "params.fixels"),
    ("fixels 2.5", dict(GOOD, fixels=2.5), "params.fixels"),
    ("fixels string", dict(GOOD, fixels="3"), "params.fixels"),
    ("top 0", dict(GOOD, top=0), "params.top"),
    ("top 1001", dict(GOOD, top=1001), "params.top"),
    ("top 1.5", dict(GOOD, top=1.5), "params.top"),
    ("objective x", dict(GOOD, objective="x"), "params.objective"),
    ("objective number", dict(GOOD, objective=1), "params.objective"),
    ("spacing 0", dict(GOOD, spacing=0), "params.spacing"),
    ("spacing -1", dict(GOOD, spacing=-1), "params.spacing"),
    ("spacing string", dict(GOOD, spacing="1"), "params.spacing"),
    ("spacing too fine", dict(GOOD, spacing=1e-4), "params.spacing"),
    ("sites not an array", dict(without(GOOD, "spacing"), sites={"at": [1, 0]}), "params.sites"),
    ("site off the boundary", dict(without(GOOD, "spacing"),
                                   sites=[{"at": [1, 0]}, {"at": [1, 1]}, {"at": [0, 1]}]),
     "params.sites[1].at"),
    ("site at a corner without normal", dict(without(GOOD, "spacing"),
                                             sites=[{"at": [1, 0]}, {"at": [2, 0]},
                                                    {"at": [4, 0]}]),
     "params.sites[2].normal"),
    ("site not an object", dict(without(GOOD, "spacing"), sites=[{"at": [1, 0]}, [2, 0]]),
     "params.sites[1]"),
    ("site without at", dict(without(GOOD, "spacing"), sites=[{"normal": [0, 1]}]),
     "params.sites[0].at"),
    ("site unknown member", dict(without(GOOD, "spacing"),
                                 sites=[{"at": [1, 0], "friction": 0.2}]),
     "params.sites[0].friction"),
    ("body self-intersecting", dict(GOOD, body={"mass": 1.0, "shape": {
        "type": "polygon", "vertices": [[0, 0], [2, 2], [2, 0], [0, 2]]}}),
     "params.body.shape.vertices"),
    ("site normal tangent", dict(without(GOOD, "spacing"),
                                 sites=[{"at": [1, 0], "normal": [1, 0]}, {"at": [2, 0]}]),
     "params.sites[0].normal"),
    # i must be below n: blamed on i; n below 1: on n
    ("shard [3, 3]", dict(GOOD, shard=[3, 3]), "params.shard[0]"),
    ("shard [0, 0]", dict(GOOD, shard=[0, 0]), "params.shard[1]"),
    ("shard [-1, 3]", dict(GOOD, shard=[-1, 3]), "params.shard[0]"),
    ("shard [0.5, 2]", dict(GOOD, shard=[0.5, 2]), "params.shard[0]"),
    ("shard not a pair", dict(GOOD, shard=[0]), "params.shard"),
    ("shard not an array", dict(GOOD, shard=0), "params.shard"),
    ("progress not boolean", dict(GOOD, progress=1), "params.progress"),
    ("finger_radius negative", dict(GOOD, finger_radius=-1), "params.finger_radius"),
    ("finger_friction negative", dict(GOOD, finger_friction=-0.5), "params.finger_friction"),
    ("sites and spacing", dict(GOOD, sites=[{"at": [1, 0]}]), "params"),
    ("none of sites, spacing, lattice", without(GOOD, "spacing"), "params"),
    ("lattice", dict(without(GOOD, "spacing"), lattice={"pitch": 10}),
     "params.lattice.peg_radius"),
    ("lattice and spacing", dict(GOOD, lattice={"pitch": 10}), "params"),
    ("unknown parameter", dict(GOOD, colour="red"), "params.colour"),
]

def test_refusals_name_the_field(client):
    """Every refusal of the table: -32602 with data.field exactly the one
    named (all checked on one daemon, each mismatch reported)."""
    wrong = []
    for name, params, field in ERRORS:
        resp = client.call("fixture.design", params)
        e = resp.get("error")
        if (e is None or "result" in resp or e.get("code") != -32602
                or not isinstance(e.get("data"), dict)
                or not isinstance(e["data"].get("reason"), str)
                or e["data"].get("field") != field):
            wrong.append((name, field, str(resp)[:300]))
        figure("design refusals checked")
    assert not wrong, "\n".join("%s: expected -32602 at %s, got %s" % w for w in wrong)
    # the daemon is fine after them all
    assert design(client, GOOD)["counts"]["candidates"] == 165


def test_params_missing_or_not_an_object(client):
    for params in (None, [1, 2]):
        resp = client.call("fixture.design", params)
        assert resp["error"]["code"] == -32602, resp
        assert resp["error"]["data"]["field"] in ("params", "params.body"), resp


# ---- 7. determinism; friction intervals and objects --------------------------------------

def raw_answer(client, params, id):
    client.send({"jsonrpc": "2.0", "method": "fixture.design", "params": params, "id": id})
    return client.read_line()


def test_same_request_same_bytes(harness, daemon):
    params = {"body": ARC_PLATE, "friction": 0.2, "spacing": 1.5, "top": 3}
    a = daemon.client()
    first = raw_answer(a, params, 1)
    assert b'"result"' in first, first[:300]
    assert raw_answer(a, params, 1) == first
    assert raw_answer(daemon.client(), params, 1) == first
    other = harness.start(socket_path=harness.path("other.sock"))
    assert raw_answer(other.client(), params, 1) == first


def test_friction_interval_is_robust(client):
    """friction [0.05, 0.1]: every candidate fixture gets the static interval
    (kinetic the whole interval); scores, counts and best pushes are those of
    the robust answers of the fixtures put with that interval, and, G_goal's
    robust answers being those at the upper bound (docs/PROTOCOL.md,
    Friction intervals), the candidates without a seating push and every goal
    length are those at friction 0.1."""
    sites = spacing_sites(CHAMFER["shape"], 1.0)
    fr = [0.05, 0.1]
    brute = Brute(client, CHAMFER, fr, sites, 3)
    at_hi = Brute(client, CHAMFER, 0.1, sites, 3, gravity=False)
    assert ([brute.kind[r] == "no_seating_push" for r in range(len(brute.combos))]
            == [at_hi.kind[r] == "no_seating_push" for r in range(len(brute.combos))])
    for r in brute.scored:
        assert abs(brute.goal[r]["total_length"] - at_hi.goal[r]["total_length"]) <= LEN_TOL, r
    # the both region (strong) depends on the whole interval: from the brute
    # force with the interval itself
    for objective, top in (("margin", 10), ("region", 5), ("gravity", 5)):
        ans = design(client, {"body": CHAMFER, "friction": fr, "spacing": 1.0,
                              "objective": objective, "top": top})
        check_shape_of_answer(ans, len(sites), objective)
        assert ans["counts"] == brute.counts(), ans["counts"]
        check_candidate_identity(ans, brute)
        ref = brute.scores(objective)
        tol = 1e-8 if objective == "margin" else LEN_TOL
        check_ranking(ans["designs"], ref, top, tol=tol, tie=tol)
        for d in ans["designs"]:
            check_best_push(client, brute, d, CHAMFER, {"static": fr}, objective)
            assert abs(d["goal_length"] - at_hi.goal[d["candidate"]]["total_length"]) <= LEN_TOL
        check_figures_against_brute(ans, brute)
    # the design's fixels put with the interval, robust answers: its figures
    check_design_figures(client, CHAMFER, {"static": fr}, ans["designs"][0])


def test_friction_object_static_and_kinetic(client):
    """{"static": 0.1, "kinetic": 0.08} on every fixel, as a fixture's friction."""
    sites = spacing_sites(RECTANGLE["shape"], 2.0)
    fr = {"static": 0.1, "kinetic": 0.08}
    brute = Brute(client, RECTANGLE, fr, sites, 3, gravity=False)
    ans = design(client, {"body": RECTANGLE, "friction": fr, "spacing": 2.0,
                          "objective": "region", "top": 8})
    assert ans["counts"] == brute.counts()
    check_candidate_identity(ans, brute)
    check_ranking(ans["designs"], brute.region, 8, tol=LEN_TOL, tie=LEN_TOL)
    for d in ans["designs"]:
        check_best_push(client, brute, d, RECTANGLE, fr, "region")
    check_figures_against_brute(ans, brute)
    # a number, its interval [mu, mu] and {"static": mu} are one friction
    base = {"body": RECTANGLE, "spacing": 2.0, "objective": "margin", "top": 3}
    one = design(client, dict(base, friction=0.1))
    assert design(client, dict(base, friction=[0.1, 0.1])) == one
    assert design(client, dict(base, friction={"static": 0.1})) == one
    assert design(client, dict(base, friction={"static": 0.1, "kinetic": 0.1})) == one


# ---- 8. a finger of some size ---------------------------------------------------------------

NOTCHED = load_example("notched-plate.json")["body"]
# 100 x 40 with a slot 12 wide, 25 deep, open at the top (x 44..56, y 15..40)
NOTCHED_SITES = [
    ({"at": [5, 0]}, ((5, 0), (0, 1))),
    ({"at": [15, 0]}, ((15, 0), (0, 1))),
    ({"at": [85, 0]}, ((85, 0), (0, 1))),
    ({"at": [100, 25]}, ((100, 25), (-1, 0))),
    ({"at": [100, 35]}, ((100, 35), (-1, 0))),
    ({"at": [56, 32.5]}, ((56, 32.5), (1, 0))),       # in the slot, its right wall
    ({"at": [44, 22.5]}, ((44, 22.5), (-1, 0))),      # its left wall
    ({"at": [44, 32.5]}, ((44, 32.5), (-1, 0))),
    ({"at": [7, 40]}, ((7, 40), (0, -1))),
    ({"at": [0, 15]}, ((0, 15), (1, 0))),
    ({"at": [0, 5]}, ((0, 5), (1, 0))),
]


def test_finger_radius_brute_force(client):
    """Sites in and around the slot, a finger of radius 8 (the slot is 12
    wide: no such finger enters it): counts, rankings (region and margin)
    and best pushes against push.regions with the same finger."""
    sites = [s for _, s in NOTCHED_SITES]
    fr = {"static": 0.2}
    brute = Brute(client, NOTCHED, 0.2, sites, 3, finger_radius=8, gravity=False)
    bare = Brute(client, NOTCHED, 0.2, sites, 3, gravity=False)
    assert len(brute.scored) >= 10, brute.counts()
    # the finger matters here: without it the both regions of most candidates
    # are longer (pushes inside the slot), and the region ranking differs
    assert sum(1 for r in brute.scored if bare.region[r] > brute.region[r] + 1e-6) >= 5
    assert (sorted(brute.region, key=lambda r: (-brute.region[r], r))[:8]
            != sorted(bare.region, key=lambda r: (-bare.region[r], r))[:8])
    finger = {"finger_radius": 8}
    for objective, top in (("region", 10), ("margin", 10)):
        ans = design(client, {"body": NOTCHED, "friction": 0.2, "objective": objective,
                              "sites": [w for w, _ in NOTCHED_SITES], "finger_radius": 8,
                              "top": top})
        check_shape_of_answer(ans, len(sites), objective)
        assert ans["counts"] == brute.counts(), (ans["counts"], brute.counts())
        check_candidate_identity(ans, brute)
        tol = 1e-8 if objective == "margin" else LEN_TOL
        check_ranking(ans["designs"], brute.scores(objective), top, tol=tol, tie=tol)
        for d in ans["designs"]:
            # in the both region of this finger, classified to its margin
            check_best_push(client, brute, d, NOTCHED, fr, objective)
            bp = d["best_push"]
            # and not on the slot (its walls and floor, edges 3, 4, 5, their
            # ends included: a finger there overlaps the other wall)
            if bp is not None:
                assert bp["edge"] not in (3, 4, 5), bp
        check_figures_against_brute(ans, brute)
    for d in ans["designs"][:2]:
        check_design_figures(client, NOTCHED, fr, d, finger)


def test_finger_radius_spacing(client):
    """spacing 15 on the notched plate, finger radius 8: every best push lies
    in the both region push.regions gives for that finger, and is classified
    to its margin; goal lengths with the finger."""
    ans = design(client, {"body": NOTCHED, "friction": 0.1, "spacing": 15, "finger_radius": 8,
                          "top": 5})
    bare = design(client, {"body": NOTCHED, "friction": 0.1, "spacing": 15, "top": 5})
    fx_calls = []
    for d in ans["designs"] + bare["designs"]:
        fx = fixture_of(NOTCHED, 0.1, d["fixels"])
        fx_calls.append(("push.regions", {"fixture": fx, "set": "both", "finger_radius": 8}))
        fx_calls.append(("push.regions", {"fixture": fx, "set": "goal", "finger_radius": 8}))
    got = results(client, fx_calls)
    regions = {}
    for k, d in enumerate(ans["designs"] + bare["designs"]):
        regions[id(d)] = (got[2 * k], got[2 * k + 1])

    def in_finger_region(d):
        bp = d["best_push"]
        both = regions[id(d)][0]["regions"]
        return any(reg["edge"] == bp["edge"] and reg["t0"] - 1e-12 <= bp["t"] <= reg["t1"] + 1e-12
                   for reg in both)

    for d in ans["designs"]:
        assert d["best_push"] is not None, d
        assert in_finger_region(d), (d["best_push"], regions[id(d)][0])
        assert abs(d["goal_length"] - regions[id(d)][1]["total_length"]) <= LEN_TOL, d
        got = client.result("wrench.classify", {
            "fixture": fixture_of(NOTCHED, 0.1, d["fixels"]), "sets": ["both"],
            "wrenches": [{"force": d["best_push"]["direction"], "at": d["best_push"]["at"]}]})
        assert abs(got["results"][0]["both"]["margin"] - d["best_push"]["margin"]) <= CLOSE
    # without the finger some best push is where the finger cannot go: the
    # check above can fail
    assert any(d["best_push"] and not in_finger_region(d) for d in bare["designs"]), (
        [(d["best_push"]["edge"], d["best_push"]["t"]) for d in bare["designs"]])


# ---- ties and the top ---------------------------------------------------------------------

@pytest.mark.parametrize("body, friction, spacing, k", [
    # 84 designs, 34 of them with an empty both region (margin exactly 0)
    (RECTANGLE, 0.1, 2.0, 2),
    # a group of 12 designs with one margin, by symmetry
    (RECTANGLE, 0.1, 2.0, 3),
])
def test_top_cuts_through_ties(client, body, friction, spacing, k):
    """Cutting the ranking inside a group of equal scores keeps the lowest
    candidate numbers: the answer for top K is the first K designs of the
    whole ranking, whatever the prunings (which must not drop a candidate
    that ties the K-th)."""
    base = {"body": body, "friction": friction, "spacing": spacing, "fixels": k}
    full = design(client, dict(base, top=1000))["designs"]
    groups = {}
    for i, d in enumerate(full):
        groups.setdefault(d["score"], []).append(i)
    big = max(groups.values(), key=len)
    assert len(big) >= 4, ("no group of ties to cut", [len(g) for g in groups.values()])
    # the group is ranked by candidate number
    assert [full[i]["candidate"] for i in big] == sorted(full[i]["candidate"] for i in big)
    for cut in (big[0] + 1, big[len(big) // 2]):
        ans = design(client, dict(base, top=cut))
        assert ans["designs"] == full[:cut], ("top %d" % cut,
                                              [d["candidate"] for d in ans["designs"]],
                                              [d["candidate"] for d in full[:cut]])
    figure("design tie groups cut", 2)


# ---- finger friction ------------------------------------------------------------------------

def test_finger_friction_brute_force(client):
    """finger_friction 0.2 (sampled push regions, as push.regions samples
    them): the disc at six sites, two fixels."""
    sites = spacing_sites(DISC["shape"], 1.0)
    brute = Brute(client, DISC, 0.3, sites, 2, finger_friction=0.2, gravity=False)
    bare = Brute(client, DISC, 0.3, sites, 2, gravity=False)
    assert brute.region != bare.region          # the finger's friction matters here
    ans = design(client, {"body": DISC, "friction": 0.3, "spacing": 1.0, "fixels": 2,
                          "finger_friction": 0.2, "objective": "region", "top": 3})
    assert ans["counts"] == brute.counts(), (ans["counts"], brute.counts())
    check_candidate_identity(ans, brute)
    check_ranking(ans["designs"], brute.region, 3, tol=LEN_TOL, tie=LEN_TOL)
    check_figures_against_brute(ans, brute)
    d = ans["designs"][0]
    check_design_figures(client, DISC, {"static": 0.3}, d, {"finger_friction": 0.2})


# ---- progress: pipelining, notifications, refusals, empty shards ----------------------------

def test_progress_pipelined_ids_and_silences(client):
    """Two pipelined requests run one after the other: the first's
    notifications and answer, then the second's (an id null is an id).  A
    request without an id (a notification) gets neither notifications nor an
    answer; a refused request gets its error alone."""
    params = {"body": CHAMFER, "friction": 0.1, "spacing": 1.0, "progress": True, "top": 2}
    client.send({"jsonrpc": "2.0", "method": "fixture.design", "params": params})
    client.send({"jsonrpc": "2.0", "method": "fixture.design", "params": params, "id": "a"})
    client.send({"jsonrpc": "2.0", "method": "fixture.design", "params": params, "id": None})
    client.send({"jsonrpc": "2.0", "method": "fixture.design", "id": "e",
                 "params": dict(params, fixels=0)})
    lines = []
    while True:
        msg = client.read_json()
        lines.append(msg)
        if msg.get("id") == "e":
            break
    client.expect_silence(0.3)
    kinds = [("note", m["params"]["id"]) if "method" in m else ("answer", m["id"]) for m in lines]
    assert kinds == [("note", "a"), ("note", "a"), ("answer", "a"),
                     ("note", None), ("note", None), ("answer", None),
                     ("answer", "e")], kinds
    assert lines[2]["result"] == lines[5]["result"]
    assert lines[6]["error"]["code"] == -32602
    assert [m["params"]["done"] for m in lines[:2]] == [0, 165]


def test_empty_shard(client):
    """A shard past the last candidate examines none."""
    ans = design(client, {"body": CHAMFER, "friction": 0.1, "spacing": 2.0, "shard": [7, 10]})
    # 2 + 0 + 0 + 1 + 1 sites: C(4, 3) = 4 candidates, numbered 0..3
    assert ans["sites"] == 4
    assert ans["counts"] == {"candidates": 4, "examined": 0, "degenerate": 0, "unpinned": 0,
                             "no_seating_push": 0, "shared_hole": 0,
                             "symmetric": 0}, ans["counts"]
    assert ans["designs"] == [] and ans["shard"] == [7, 10]


# ---- counts beyond a double's integers -------------------------------------------------------

def test_huge_candidate_count_is_exact(daemon):
    """BUG (kept failing on purpose): C(376, 8) = 9192295203757875 candidates
    (the disc with 376 sites by spacing, 8 fixels) is accepted, but the
    first design.progress notification says "total": 9192295203757876 -- the
    count went through a double (above 2^53), so it is not this shard's
    candidate count.  With 692 sites the total is even written
    1.2522521717044803e+18 instead of 1252252171704480310.  Either the count
    is exact or the request should be refused (as it is from 2^64 up: "more
    candidates than can be counted").  The run is stopped by hanging up."""
    wrong = []
    for n in (376, 692):
        c = daemon.client()
        h = 2 * math.pi / (n + 0.5)        # floor(2 pi / h) = n sites on the unit disc
        c.send({"jsonrpc": "2.0", "method": "fixture.design", "id": 1, "params": {
            "body": DISC, "friction": 0.1, "spacing": h, "fixels": 8, "progress": True}})
        line = c.read_line()
        c.close()
        msg = json.loads(line)
        if "error" in msg:
            continue            # refusing is an honest answer too
        total = msg["params"]["total"]
        if not (isinstance(total, int) and total == math.comb(n, 8)):
            wrong.append("n = %d: %s, C(n, 8) = %d" % (n, line[:200].decode(), math.comb(n, 8)))
    # the daemon is fine, and the abandoned runs end (their clients gone)
    c = daemon.client()
    deadline = time.monotonic() + 10
    while c.result("server.status", {})["clients"] != 1:
        assert time.monotonic() < deadline, "the abandoned runs' clients stay"
        time.sleep(0.05)
    assert not wrong, "\n".join(wrong)


# ---- defaults; normals derived on an outline -------------------------------------------------

def test_defaults(client):
    """fixels 3, top 10, objective margin, no finger, no progress, shard [0, 1]."""
    plain = design(client, {"body": CHAMFER, "friction": 0.1, "spacing": 1.0})
    spelled = design(client, {"body": CHAMFER, "friction": 0.1, "spacing": 1.0, "fixels": 3,
                              "top": 10, "objective": "margin", "finger_radius": 0,
                              "finger_friction": 0, "progress": False, "shard": [0, 1]})
    assert plain == spelled
    assert plain["objective"] == "margin" and plain["shard"] == [0, 1]
    assert plain["counts"]["candidates"] == math.comb(plain["sites"], 3)
    assert len(plain["designs"]) == 10, len(plain["designs"])


def test_outline_site_normals(client):
    """On D_PLATE a line meets the half circle tangentially at (4, 0) and
    (4, 4): a site there needs no normal ((0, 1), (0, -1)); on the arc it is
    radial ((6, 2): (-1, 0)); at the corner (0, 0) it is required."""
    sites = [{"at": [4, 0]}, {"at": [4, 4]}, {"at": [6, 2]}, {"at": [0, 2]}, {"at": [2, 0]}]
    expected = {0: ((4, 0), (0, 1)), 1: ((4, 4), (0, -1)), 2: ((6, 2), (-1, 0)),
                3: ((0, 2), (1, 0)), 4: ((2, 0), (0, 1))}
    ans = design(client, {"body": D_PLATE, "friction": 0.1, "sites": sites, "fixels": 2,
                          "objective": "region", "top": 100})
    assert ans["sites"] == 5 and ans["counts"]["candidates"] == 10
    seen = sites_read_back(ans)
    assert sorted(seen) == [0, 1, 2, 3, 4], seen
    for i, (at, nrm) in expected.items():
        assert max(abs(a - b) for a, b in zip(seen[i][0] + seen[i][1], at + nrm)) <= 1e-12, (
            i, seen[i])
    e = client.error("fixture.design", {"body": D_PLATE, "friction": 0.1, "fixels": 1,
                                        "sites": [{"at": [2, 0]}, {"at": [0, 0]}]})
    assert e["code"] == -32602 and e["data"]["field"] == "params.sites[1].normal", e
