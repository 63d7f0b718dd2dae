"""push.regions, gravity.sweep and stability.margin (docs/MODEL.md section 6).

Every expected number is derived here, not read back from the daemon:

* closed forms for docs/MODEL.md section 7's disc in a corner (the push region, the gravity
  arc, the finger-friction region, their lengths and fractions), derived in
  the docstrings below;
* elsewhere the push wrench w(p) = (nu, (p - x_c) x nu) is computed from the
  outline by model.py (point, inward normal from the orientation, torque
  about the centre of mass), and the daemon's regions are checked point by
  point with wrench.classify (many wrenches per request) and, where cheap,
  with model.py's independent margins: every endpoint inside an edge has
  margin 0, dense points inside a region have a positive margin, dense points
  outside every region do not;
* stability.margin against the scaling of a cone's distance: distances to
  cones are homogeneous of degree 1, so the unnormalised distance of the
  scaled bias h is |h| times the (normalised) margin classify gives.
"""

import math
import random

import pytest

import fixtures as FX
import helpers as H
import model as M
from conftest import FIGURES

SETS = ("goal", "strong", "both")
ENDPOINT_TOL = 1e-9      # |margin| at a region's endpoint
SKIP = 1e-7              # of the range: points this near an endpoint may go either way
NEAR = 1e-6              # of the range: probes just inside / outside an endpoint
CLASSIFY_TOL = 1e-9      # classify's default tolerance: "not inside" is margin <= this
PER_EDGE = 200           # dense points per polygon edge (or per circle)
CHUNK = 4000             # wrenches per classify request

def count(key, n=1):
    """Add to the figures conftest prints at the end of the run."""
    FIGURES[key] = FIGURES.get(key, 0) + n


# ---- plumbing -----------------------------------------------------------------

def classify(client, fixture, wrenches, sets=SETS):
    """Margins of many wrenches, a few thousand per request: a list (one per
    wrench) of {set: margin}."""
    out = []
    for i in range(0, len(wrenches), CHUNK):
        part = [list(w) for w in wrenches[i:i + CHUNK]]
        res = client.result("wrench.classify", {"fixture": fixture, "wrenches": part,
                                                "sets": list(sets)})
        assert len(res["results"]) == len(part)
        for r in res["results"]:
            for s in sets:
                assert r[s]["inside"] is (r[s]["verdict"] == "inside"), r
                assert (r[s]["verdict"] == "inside") == (r[s]["margin"] > CLASSIFY_TOL), r
            out.append({s: r[s]["margin"] for s in sets})
        count("classified wrenches", len(part))
    return out


def classify_full(client, fixture, wrenches, sets=("strong",)):
    res = client.result("wrench.classify", {"fixture": fixture, "sets": list(sets),
                                            "wrenches": [list(w) for w in wrenches]})
    count("classified wrenches", len(wrenches))
    return res["results"]


def regions(client, fixture, which=None, finger=None):
    params = {"fixture": fixture}
    if which is not None:
        params["set"] = which
    if finger is not None:
        params["finger_friction"] = finger
    return client.result("push.regions", params)


def sweep(client, fixture, which=None):
    params = {"fixture": fixture}
    if which is not None:
        params["set"] = which
    res = client.result("gravity.sweep", params)
    assert set(res) == {"intervals_deg"}, res
    return res["intervals_deg"]


def error_of(client, method, params, code=-32602):
    e = client.error(method, params)
    assert e["code"] == code, e
    assert isinstance(e.get("data"), dict) and set(e["data"]) == {"field", "reason"}, e
    assert isinstance(e["data"]["reason"], str) and e["data"]["reason"], e
    return e["data"]["field"]


def size_of(mdl):
    if mdl.shape["type"] == "circle":
        return float(mdl.shape["radius"])
    xs = [v[0] for v in mdl.vertices]
    ys = [v[1] for v in mdl.vertices]
    return max(max(xs) - min(xs), max(ys) - min(ys))


def check_region_answer(mdl, res, exact=True):
    """The shape of a push.regions answer, every region's from/to/length
    recomputed from the outline, the total and fraction; returns the regions
    as (edge, t0, t1)."""
    assert set(res) == {"regions", "total_length", "fraction", "exact", "resolution"} | (
        set() if res["regions"] else {"why_empty"}), res
    assert res["exact"] is exact, res
    if exact:
        assert res["resolution"] == 0, res
    else:
        assert isinstance(res["resolution"], (int, float)) and res["resolution"] > 0, res
    rng = M.edge_range(mdl)
    edges = M.edge_count(mdl)
    scale = size_of(mdl)
    out = []
    total = 0.0
    for r in res["regions"]:
        assert set(r) == {"edge", "from", "to", "t0", "t1", "length"}, r
        e, t0, t1 = r["edge"], r["t0"], r["t1"]
        assert isinstance(e, int) and 0 <= e < edges, r
        assert 0 <= t0 < t1 <= rng, r
        p0, _ = M.boundary_point(mdl, e, t0)
        p1, _ = M.boundary_point(mdl, e, t1)
        assert H.vec_close(r["from"], p0, 1e-9 * scale), (r, p0)
        assert H.vec_close(r["to"], p1, 1e-9 * scale), (r, p1)
        length = M.region_length(mdl, e, t0, t1)
        assert H.close(r["length"], length, 1e-9 * scale), (r, length)
        total += length
        out.append((e, t0, t1))
    assert out == sorted(out), ("regions not ordered by edge, then t0", out)
    for a, b in zip(out, out[1:]):
        if a[0] == b[0]:
            assert a[2] <= b[1], ("overlapping regions", a, b)
    assert H.close(res["total_length"], total, 1e-9 * scale * (1 + len(out))), (res, total)
    per = M.perimeter(mdl)
    assert H.close(res["fraction"], total / per, 1e-9), (res, total / per)
    assert 0.0 <= res["fraction"] <= 1.0 + 1e-12, res
    return out


def check_arcs(arcs):
    """gravity.sweep arcs: [a, b] with 0 <= a < b <= 360, ordered, disjoint."""
    for a in arcs:
        assert isinstance(a, list) and len(a) == 2, arcs
        assert 0 <= a[0] < a[1] <= 360, arcs
    assert arcs == sorted(arcs), arcs
    for a, b in zip(arcs, arcs[1:]):
        assert a[1] <= b[0], ("overlapping arcs", arcs)
    return [(0, a, b) for a, b in arcs]


def inside_of(intervals, edge, t):
    return any(e == edge and t0 < t < t1 for e, t0, t1 in intervals)


def near_end(intervals, edge, t, pad):
    return any(e == edge and (abs(t - t0) <= pad or abs(t - t1) <= pad)
               for e, t0, t1 in intervals)


def probes(intervals, edges, rng, per_edge, seed):
    """Points to classify on each edge: `per_edge` evenly spread ones (with
    a fixed jitter) and, for each interval, one just inside each end and
    one just outside it (when that is still on the edge).  Returns
    [(edge, t, expected_inside)], leaving out points within SKIP * rng of an
    endpoint."""
    rnd = random.Random(seed)
    pts = []
    for e in range(edges):
        for j in range(per_edge):
            pts.append((e, (j + rnd.uniform(0.05, 0.95)) / per_edge * rng))
    d = NEAR * rng
    for e, t0, t1 in intervals:
        if t1 - t0 > 4 * d:
            pts += [(e, t0 + d), (e, t1 - d)]
        pts.append((e, 0.5 * (t0 + t1)))
        for t in (t0 - d, t1 + d):
            if 0 < t < rng:
                pts.append((e, t))
    out = []
    for e, t in pts:
        if near_end(intervals, e, t, SKIP * rng):
            continue
        out.append((e, t, inside_of(intervals, e, t)))
    return out


def endpoints(intervals, rng, circle):
    """Endpoints strictly inside an edge: not a polygon's vertex (t = 0 or
    1), not the cut of a circle's interval at 0 = 360 degrees."""
    out = []
    have0 = any(t0 == 0 for _, t0, _ in intervals)
    have360 = any(t1 == rng for _, _, t1 in intervals)
    for e, t0, t1 in intervals:
        for t in (t0, t1):
            if circle:
                if (t == 0 and have360) or (t == rng and have0):
                    continue
                out.append((e, t % rng))
            elif 0 < t < rng:
                out.append((e, t))
    return out


def check_against_points(where, intervals, margins, pts):
    """margins[i] belongs to pts[i] = (edge, t, expected_inside)."""
    bad = []
    for (e, t, inside), m in zip(pts, margins):
        if inside and not m > 0:
            bad.append(("in a region, margin %.3g" % m, e, t))
        if not inside and not m <= CLASSIFY_TOL:
            bad.append(("in no region, margin %.3g" % m, e, t))
    assert not bad, "%s: regions %r disagree with classify at %d of %d points: %r" % (
        where, intervals, len(bad), len(pts), bad[:10])


def intersect(a, b):
    """The intersection of two lists of open intervals (edge, t0, t1)."""
    out = []
    for e, s0, s1 in a:
        for f, u0, u1 in b:
            if e == f and max(s0, u0) < min(s1, u1):
                out.append((e, max(s0, u0), min(s1, u1)))
    return sorted(out)


def same_intervals(a, b, tol=1e-9):
    return len(a) == len(b) and all(
        x[0] == y[0] and abs(x[1] - y[1]) <= tol and abs(x[2] - y[2]) <= tol
        for x, y in zip(a, b))


def check_both_is_the_intersection(found, rng):
    """margin(both) = min(margin(goal), margin(strong)) (docs/MODEL.md section 5), so the
    both region is the goal region intersected with the strong one."""
    if set(SETS) <= set(found):
        inter = intersect(found["goal"], found["strong"])
        assert same_intervals(found["both"], inter, 1e-9 * rng), (
            "both is not goal and strong", found)


def check_push_regions(client, fixture, sets=SETS, per_edge=PER_EDGE, model_every=0, seed=0):
    """push.regions of every set of `fixture` against classify at dense
    points and at the endpoints, and (every `model_every`-th point, and every
    endpoint) against model.py.  Returns {set: intervals}."""
    mdl = M.Model(fixture)
    cl = M.Classifier(mdl) if model_every else None
    circle = mdl.shape["type"] == "circle"
    rng = M.edge_range(mdl)
    edges = M.edge_count(mdl)
    found = {}
    batches = []
    for which in sets:
        res = regions(client, fixture, which)
        iv = check_region_answer(mdl, res)
        found[which] = iv
        pts = probes(iv, edges, rng, per_edge, seed)
        ends = endpoints(iv, rng, circle)
        batches.append((which, iv, pts, ends))
    # one classify request (or a few) for every set's points
    wrenches = []
    for which, iv, pts, ends in batches:
        wrenches += [M.push_wrench(mdl, e, t) for e, t, _ in pts]
        wrenches += [M.push_wrench(mdl, e, t) for e, t in ends]
    margins = classify(client, fixture, wrenches, sets)
    at = 0
    for which, iv, pts, ends in batches:
        where = "%s set=%s" % (fixture.get("name"), which)
        mp = [m[which] for m in margins[at:at + len(pts)]]
        at += len(pts)
        me = [m[which] for m in margins[at:at + len(ends)]]
        at += len(ends)
        check_against_points(where, iv, mp, pts)
        for (e, t), m in zip(ends, me):
            assert abs(m) < ENDPOINT_TOL, "%s: margin %.3g at endpoint edge %d t %r of %r" % (
                where, m, e, t, iv)
        count("push points", len(pts))
        count("push endpoints", len(ends))
        if cl is not None:
            for i, ((e, t, _), m) in enumerate(zip(pts, mp)):
                # 'both' is the smaller of the two, compared at the endpoints
                if i % model_every == 0 and which != "both":
                    exp = cl.classify(M.push_wrench(mdl, e, t), which).margin
                    assert H.close(m, exp, H.MARGIN_TOL), (where, e, t, m, exp)
                    count("push points against the model")
            for e, t in ends:
                exp = cl.classify(M.push_wrench(mdl, e, t), which).margin
                assert abs(exp) < H.MARGIN_TOL, ("model margin at an endpoint", where, e, t, exp)
                count("push endpoints against the model")
    check_both_is_the_intersection(found, rng)
    count("push fixtures")
    return found


# ---- 1. docs/MODEL.md section 7: the disc in a corner, closed forms ---------------

MUS = [0.1, 0.3, 0.5, 0.8, 0.95, 1.0, 1.2]


@pytest.mark.parametrize("mu", MUS)
def test_disc_corner_push_regions_closed_form(client, mu):
    """The disc (radius R, centre = com = origin): at boundary angle theta,
    p = R (cos, sin), nu = -(cos, sin), (p - x_c) x nu = 0, so
    w = (-cos theta, -sin theta, 0).  docs/MODEL.md section 7: G_goal = {f_x < 0, f_y < 0,
    |f_x| > mu |f_y|, |f_y| > mu |f_x|}, i.e. theta in (0, 90) with
    mu < tan theta < 1/mu: (atan mu, 90 - atan mu), empty for mu >= 1.
    Length (90 - 2 atan mu) degrees in radians times R, fraction that over
    2 pi R.

    G_strong: with tau = 0 and f in the open quadrant no motion exists
    (a_n1 = a_x, a_n2 = a_y; a_t1 = a_y - alpha, a_t2 = -a_x - alpha.  If
    fixel 1 separates, m a_x = f_x - c_t2 > 0 needs c_t2 < 0 while
    I alpha = -c_t2 > 0 contradicts both sticking (alpha = -a_x < 0) and
    sliding (l: alpha < -a_x < 0; r: c_t2 >= 0); fixel 2 likewise; both in
    contact leaves q = (0, 0, alpha) and both sliding the same way, whose
    friction torque opposes alpha).  Outside the closed quadrant a fixel is
    pulled off.  So the strong region is (0, 90) for every mu, and 'both'
    (G_goal and G_strong) is the goal region, which lies inside it."""
    f = FX.disc_corner(mu)
    mdl = M.Model(f)
    a = math.degrees(math.atan(mu))
    goal = check_region_answer(mdl, regions(client, f, "goal"))
    default = regions(client, f)
    assert default == regions(client, f, "goal"), "the default set is goal"
    strong = check_region_answer(mdl, regions(client, f, "strong"))
    both_res = regions(client, f, "both")
    both = check_region_answer(mdl, both_res)
    if mu < 1:
        assert len(goal) == 1, goal
        e, t0, t1 = goal[0]
        assert e == 0
        assert abs(t0 - a) < 1e-9 and abs(t1 - (90 - a)) < 1e-9, (goal, a, 90 - a)
        res = regions(client, f, "goal")
        length = math.radians(90 - 2 * a) * 1.0
        assert abs(res["regions"][0]["length"] - length) < 1e-9, res
        assert abs(res["total_length"] - length) < 1e-9, res
        assert abs(res["fraction"] - length / (2 * math.pi)) < 1e-9, res
        c, s = math.cos(math.radians(a)), math.sin(math.radians(a))
        assert H.vec_close(res["regions"][0]["from"], (c, s), 1e-9), res
        assert H.vec_close(res["regions"][0]["to"], (s, c), 1e-9), res
    else:
        assert goal == [], goal
        res = regions(client, f, "goal")
        assert res["total_length"] == 0 and res["fraction"] == 0, res
    assert len(strong) == 1 and strong[0][0] == 0, strong
    assert abs(strong[0][1] - 0) < 1e-9 and abs(strong[0][2] - 90) < 1e-9, strong
    assert both == goal, (both, goal)
    # and point by point, with the model
    check_push_regions(client, f, per_edge=360, model_every=9, seed=int(mu * 100))


@pytest.mark.parametrize("mu", MUS)
def test_disc_corner_gravity_closed_form(client, mu):
    """Gravity pulls along phi: w = m g0 (cos phi, sin phi, 0), torque 0 as
    for the push.  In G_goal (docs/MODEL.md section 7) iff phi is in the third quadrant with
    mu < tan(phi - 180) < 1/mu: (180 + atan mu, 270 - atan mu), empty for
    mu >= 1.  G_strong: the open quadrant (180, 270) (the argument of the
    push test); 'both' is the goal arc."""
    f = FX.disc_corner(mu)
    a = math.degrees(math.atan(mu))
    goal = sweep(client, f, "goal")
    assert sweep(client, f) == goal, "the default set is goal"
    strong = sweep(client, f, "strong")
    both = sweep(client, f, "both")
    check_arcs(goal), check_arcs(strong), check_arcs(both)
    if mu < 1:
        assert len(goal) == 1, goal
        assert abs(goal[0][0] - (180 + a)) < 1e-9 and abs(goal[0][1] - (270 - a)) < 1e-9, goal
    else:
        assert goal == [], goal
    assert len(strong) == 1, strong
    assert abs(strong[0][0] - 180) < 1e-9 and abs(strong[0][1] - 270) < 1e-9, strong
    assert both == goal, (both, goal)


@pytest.mark.parametrize("length", [0.01, 2.5, 40.0])
def test_disc_corner_in_other_units(client, length):
    """Angles do not depend on units; lengths scale with R: the region of
    the disc of radius L is (atan mu, 90 - atan mu) with length
    (90 - 2 atan mu) degrees times L, and the same fraction."""
    mu = 0.4
    a = math.degrees(math.atan(mu))
    f = FX.scaled_disc_corner(mu, length=length, mass=3.0)
    res = regions(client, f, "goal")
    check_region_answer(M.Model(f), res)
    (r,) = res["regions"]
    assert abs(r["t0"] - a) < 1e-9 and abs(r["t1"] - (90 - a)) < 1e-9, res
    assert H.close(r["length"], math.radians(90 - 2 * a) * length, 1e-9 * length), res
    assert H.close(res["fraction"], (90 - 2 * a) / 360, 1e-9), res
    arcs = sweep(client, f, "both")
    assert len(arcs) == 1 and abs(arcs[0][0] - (180 + a)) < 1e-9 and \
        abs(arcs[0][1] - (270 - a)) < 1e-9, arcs


def test_intervals_through_zero_are_split(client):
    """Turn the corner so that the arcs straddle 0 degrees.

    Push: fixels at 135 and 225 degrees (normals towards the centre) is docs/MODEL.md section
    7's corner turned by -45 degrees, so its goal region (atan mu,
    90 - atan mu) turns to (atan mu - 45, 45 - atan mu): [0, 45 - atan mu]
    and [315 + atan mu, 360].  Gravity: fixels at 315 and 45 degrees is the
    corner turned by +135 degrees, its goal arc (180 + atan mu,
    270 - atan mu) turns to (315 + atan mu, 45 - atan mu) through 0."""
    mu = 0.3
    a = math.degrees(math.atan(mu))
    f = FX.disc_at_angles([135, 225], mu=mu)
    res = regions(client, f, "goal")
    iv = check_region_answer(M.Model(f), res)
    assert len(iv) == 2, iv
    assert iv[0][1] == 0 and abs(iv[0][2] - (45 - a)) < 1e-9, iv
    assert abs(iv[1][1] - (315 + a)) < 1e-9 and iv[1][2] == 360, iv
    assert H.close(res["fraction"], (90 - 2 * a) / 360, 1e-9), res
    check_push_regions(client, f, seed=3)

    g = FX.disc_at_angles([315, 45], mu=mu)
    arcs = sweep(client, g, "goal")
    check_arcs(arcs)
    assert len(arcs) == 2, arcs
    assert arcs[0][0] == 0 and abs(arcs[0][1] - (45 - a)) < 1e-9, arcs
    assert abs(arcs[1][0] - (315 + a)) < 1e-9 and arcs[1][1] == 360, arcs
    # the push region of that one is the plain turned one: (135 + a, 225 - a)
    iv = check_region_answer(M.Model(g), regions(client, g, "goal"))
    assert len(iv) == 1 and abs(iv[0][1] - (135 + a)) < 1e-9 and \
        abs(iv[0][2] - (225 - a)) < 1e-9, iv


# ---- 2. random outlines, point by point ----------------------------------------------

def random_fixtures(seed, polygons, discs):
    rnd = random.Random(seed)
    out = []
    for i in range(polygons):
        f = FX.random_polygon(rnd, convex=(i % 2 == 0), corner=(i % 3 != 2),
                              name="poly-%d-%d" % (seed, i))
        out.append(f)
    for i in range(discs):
        out.append(FX.random_disc(rnd, corner=(i % 2 == 0), name="disc-%d-%d" % (seed, i)))
    return out


def test_random_polygons_regions_agree_with_classify(client):
    """24 random polygons (convex and not, both orientations, 3 or 4 fixels
    on edges with their normals left out, some with a given com and
    inertia): for each set, 200 points per edge, the points just inside and
    just outside every endpoint, and the endpoints themselves, classified
    with the push wrench computed here; one point in 50 (goal, strong) and every endpoint
    also against model.py."""
    fixtures = random_fixtures(14, polygons=24, discs=0)
    nonempty = {s: 0 for s in SETS}
    orient = set()
    for i, f in enumerate(fixtures):
        found = check_push_regions(client, f, model_every=50, seed=i)
        for s in SETS:
            nonempty[s] += bool(found[s])
        orient.add(M.Model(f).orientation)
    # the sample means something: some regions of every set, both orientations
    assert orient == {1, -1}
    assert nonempty["goal"] >= 3 and nonempty["strong"] >= 12 and nonempty["both"] >= 3, nonempty


def test_random_discs_regions_agree_with_classify(client):
    """16 random discs (centre anywhere, com off the centre for about half,
    2..4 fixels, some normals given unnormalised), as for the polygons
    (360 points around; one in 20 against the model)."""
    fixtures = random_fixtures(12, polygons=0, discs=16)
    nonempty = {s: 0 for s in SETS}
    off = 0
    for i, f in enumerate(fixtures):
        found = check_push_regions(client, f, per_edge=360, model_every=20, seed=100 + i)
        for s in SETS:
            nonempty[s] += bool(found[s])
        off += "com" in f["body"]
    assert off >= 4
    assert nonempty["goal"] >= 4 and nonempty["strong"] >= 8, nonempty


NAMED = {
    "triangle": FX.triangle,                    # a scaled normal, per-fixel friction
    "offset-disc": FX.offset_disc,              # com off the centre, kinetic < static
    "corner-fixel": FX.corner_fixel_plate,      # a fixel at a vertex, normal given
    "one-fixel": FX.disc_one_fixel,             # not pinned: pivot modes
    "form-closure": FX.square_form_closure,     # no moving mode at all
    "disc-corner-kinetic": lambda: FX.disc_corner(0.4, kinetic=0.1),
}


@pytest.mark.parametrize("name", sorted(NAMED))
def test_named_fixtures_regions_agree_with_classify(client, name):
    """The fixtures module's special cases, point by point, one point in 10
    against the model."""
    check_push_regions(client, NAMED[name](), model_every=10, seed=len(name))


def test_regions_of_a_stored_fixture_equal_inline(client):
    f = random_fixtures(13, polygons=1, discs=0)[0]
    fid = client.result("fixture.put", {"fixture": f})["id"]
    for s in SETS:
        assert regions(client, fid, s) == regions(client, f, s)
        assert sweep(client, fid, s) == sweep(client, f, s)


def whole_arcs(intervals, rng=360.0):
    """Circle intervals with the pieces cut at 0 = 360 joined again:
    [(start, length)]."""
    iv = [(t0, t1) for _, t0, t1 in intervals]
    tail = [a for a in iv if a[1] == rng and a[0] > 0]
    head = [a for a in iv if a[0] == 0 and a[1] < rng]
    out = []
    for a in iv:
        if a in tail and head:
            out.append((a[0], a[1] - a[0] + head[0][1]))
        elif not (a in head and tail):
            out.append((a[0], a[1] - a[0]))
    return out


def same_arcs(a, b, shift, tol=1e-9):
    """Arcs a turned by `shift` degrees are the arcs b."""
    if len(a) != len(b):
        return False
    if not a:
        return True
    if len(a) == 1 and a[0][1] == 360.0:
        return b[0][1] == 360.0     # the whole circle has no start
    turned = sorted(((s + shift) % 360.0, n) for s, n in a)
    b = sorted(b)
    # sorting after the turn can put an arc starting near 360 first or last
    for k in range(len(b)):
        rolled = turned[k:] + turned[:k]
        if all(abs(((x[0] - y[0] + 180) % 360) - 180) <= tol and abs(x[1] - y[1]) <= tol
               for x, y in zip(rolled, b)):
            return True
    return False


def test_regions_are_invariant_under_a_change_of_coordinates(client):
    """The physics does not see the frame: turning a fixture by beta,
    scaling it by k and shifting it keeps every polygon region's (edge, t0,
    t1) and fraction, multiplies lengths by k, and turns a circle's regions
    and every gravity arc by beta.  The disturbance margin is unchanged
    under a turn and a shift (a bias turns with its force, keeps its torque),
    and the worst direction turns."""
    rnd = random.Random(41)
    fixtures = random_fixtures(42, polygons=6, discs=6) + [FX.chamfered_plate(0.05),
                                                           FX.offset_disc()]
    for i, f in enumerate(fixtures):
        beta = round(rnd.uniform(-180, 180), 3)
        k = rnd.choice([0.05, 1.0, 20.0])
        shift = (round(rnd.uniform(-50, 50), 3), round(rnd.uniform(-50, 50), 3))
        g = FX.moved(f, beta, shift, k, name="moved")
        mf, mg = M.Model(f), M.Model(g)
        circle = mf.shape["type"] == "circle"
        for which in SETS:
            a, b = regions(client, f, which), regions(client, g, which)
            ia, ib = check_region_answer(mf, a), check_region_answer(mg, b)
            where = (f["name"], which, beta, k, shift, ia, ib)
            if circle:
                assert same_arcs(whole_arcs(ia), whole_arcs(ib), beta), where
            else:
                assert len(ia) == len(ib) and all(
                    x[0] == y[0] and abs(x[1] - y[1]) < 1e-9 and abs(x[2] - y[2]) < 1e-9
                    for x, y in zip(ia, ib)), where
            assert H.close(b["total_length"], k * a["total_length"], 1e-9 * k * size_of(mf)), where
            assert H.close(b["fraction"], a["fraction"], 1e-9), where
            sa = check_arcs(sweep(client, f, which))
            sb = check_arcs(sweep(client, g, which))
            assert same_arcs(whole_arcs(sa), whole_arcs(sb), beta), (
                "gravity", f["name"], which, beta, sa, sb)
            count("moved fixtures and sets")
        if k == 1.0:
            c, s = math.cos(math.radians(beta)), math.sin(math.radians(beta))
            for _ in range(3):
                bias = (rnd.uniform(-2, 2), rnd.uniform(-2, 2), rnd.uniform(-2, 2))
                turned = (c * bias[0] - s * bias[1], s * bias[0] + c * bias[1], bias[2])
                ra, rb = smargin(client, f, bias), smargin(client, g, turned)
                wd = ra["worst_direction"]
                assert H.close(ra["margin"], rb["margin"], 1e-9), (ra, rb)
                if abs(ra["margin"]) > 1e-6:
                    assert ra["blocking"] == rb["blocking"], (ra, rb)
                    assert H.vec_close(rb["worst_direction"], (c * wd[0] - s * wd[1],
                                                               s * wd[0] + c * wd[1], wd[2]),
                                       1e-7), (ra, rb)


# ---- 3. the 3-2-1 plate and the chamfered plate --------------------------------------

@pytest.mark.parametrize("mu", [0.0, 0.1, 0.3, 0.6, 1.0])
@pytest.mark.parametrize("clockwise", [False, True])
def test_rectangle_321_has_no_goal_region(client, mu, clockwise):
    """docs/MODEL.md section 7: a frictionless finger on an edge pushes along that edge's
    normal, toward the bottom locators or toward the left one, never toward
    both, so a self-transition (all-m on the touched fixels, s elsewhere)
    stays possible and no push seats the plate: no goal region for any
    friction, so no 'both' region either.  The strong and both regions agree
    with classify point by point."""
    f = FX.rectangle_321(mu, clockwise=clockwise)
    found = check_push_regions(client, f, seed=int(mu * 10) + clockwise)
    assert found["goal"] == [], found
    assert found["both"] == [], found


def test_chamfered_plate_goal_region_on_the_chamfer_only(client):
    """examples/plate-chamfered.json: the chamfer (edge 2, from (4, 1) to
    (3, 2)) pushes toward both locating edges; the goal region is non-empty
    and on that edge only.  Its endpoints are found again here by bisection
    on model.py's margin along the edge (w is affine in t there)."""
    import json
    import os
    from conftest import REPO
    with open(os.path.join(REPO, "examples", "plate-chamfered.json")) as fh:
        f = json.load(fh)
    found = check_push_regions(client, f, model_every=5, seed=5)
    goal = found["goal"]
    assert goal, "no goal region on the chamfered plate"
    assert all(e == 2 for e, _, _ in goal), goal
    mdl = M.Model(f)
    cl = M.Classifier(mdl)

    def margin(t):
        return cl.classify(M.push_wrench(mdl, 2, t), "goal").margin

    for _, t0, t1 in goal:
        mid = 0.5 * (t0 + t1)
        assert margin(mid) > 0
        for end in (t0, t1):
            if end in (0.0, 1.0):
                # a region that reaches the vertex: positive up to it
                assert margin(end + (1e-6 if end == 0 else -1e-6)) > 0
                continue
            a, b = mid, end + math.copysign(1e-3, end - mid)
            assert margin(b) <= 0, ("just past the endpoint the model says inside", end, b)
            for _ in range(60):
                c = 0.5 * (a + b)
                if margin(c) > 0:
                    a = c
                else:
                    b = c
            assert abs(a - end) < 1e-9, ("the model's endpoint", a, "daemon", end)
    # the same with the fixtures module's chamfered plate, at several frictions
    for mu in (0.0, 0.02, 0.05):
        g = FX.chamfered_plate(mu)
        found = check_push_regions(client, g, sets=("goal",), seed=int(mu * 100))
        assert found["goal"] and all(e == 2 for e, _, _ in found["goal"]), (mu, found)


# ---- 4. a finger with friction ---------------------------------------------------------

@pytest.mark.parametrize("mu,mu_f", [(0.5, 0.2), (0.1, 0.3), (0.3, 0.05), (0.2, 0.6),
                                     (0.5, 0.5), (0.0, 0.1)])
def test_disc_corner_finger_friction(client, mu, mu_f):
    """A finger with friction mu_f at angle theta can push with any force
    nu + s mu_f tangent, |s| <= 1: directions (theta + 180) +- atan mu_f.
    Their torque about the centre (R mu_f s) is free in docs/MODEL.md section 7's G_goal, and
    its force part is the open wedge of directions 180 + (atan mu,
    90 - atan mu), convex, so every force of the finger's cone is in G_goal
    iff both edges are: theta - atan mu_f > atan mu and theta + atan mu_f <
    90 - atan mu, i.e. (atan mu + atan mu_f, 90 - atan mu - atan mu_f), empty
    once atan mu + atan mu_f >= 45 degrees.  Sampled: exact false, a
    positive resolution, and the endpoints within it."""
    f = FX.disc_corner(mu)
    mdl = M.Model(f)
    res = regions(client, f, "goal", finger=mu_f)
    iv = check_region_answer(mdl, res, exact=False)
    step = res["resolution"]
    assert 0 < step <= 5, res
    a = math.degrees(math.atan(mu)) + math.degrees(math.atan(mu_f))
    if a < 45:
        assert len(iv) == 1, (iv, a)
        _, t0, t1 = iv[0]
        assert abs(t0 - a) <= step and abs(t1 - (90 - a)) <= step, (iv, a, step)
    else:
        assert iv == [], (iv, a)
    # mu_f = 0 is the frictionless, exact answer
    exact = regions(client, f, "goal", finger=0)
    assert exact == regions(client, f, "goal"), exact
    assert exact["exact"] is True and exact["resolution"] == 0


def test_finger_friction_point_by_point(client):
    """On random fixtures, with a finger of friction 0.15, for every set: a
    point in a region has every force of the finger's cone (33
    forces nu + s mu_f tangent, s in [-1, 1]) classify inside; a point
    farther than the resolution from every region has some force that does
    not (33, then 1025 forces before calling it a discrepancy)."""
    mu_f = 0.15
    fixtures = ([FX.disc_corner(0.3), FX.chamfered_plate(0.02), FX.offset_disc(), FX.triangle()]
                + random_fixtures(21, polygons=3, discs=3))
    svals = [-1 + 2 * i / 32 for i in range(33)]
    bad = []
    checked = 0
    for n, f in enumerate(fixtures):
        mdl = M.Model(f)
        rng = M.edge_range(mdl)
        for which in SETS:
            res = regions(client, f, which, finger=mu_f)
            iv = check_region_answer(mdl, res, exact=False)
            step = res["resolution"]
            # frictionless regions contain the finger's (mu_f = 0 is one force of the cone)
            plain = check_region_answer(mdl, regions(client, f, which))
            for e, t0, t1 in iv:
                assert inside_of(plain, e, 0.5 * (t0 + t1)), (which, iv, plain)
            rnd = random.Random(n)
            pts = []
            for e in range(M.edge_count(mdl)):
                for j in range(40):
                    t = (j + rnd.uniform(0.05, 0.95)) / 40 * rng
                    if near_end(iv, e, t, 2 * step):
                        continue
                    pts.append((e, t, inside_of(iv, e, t)))
            wrenches = [M.push_wrench(mdl, e, t, s * mu_f) for e, t, _ in pts for s in svals]
            margins = [m[which] for m in classify(client, f, wrenches, (which,))]
            for i, (e, t, inside) in enumerate(pts):
                ms = margins[i * len(svals):(i + 1) * len(svals)]
                all_in = all(m > 0 for m in ms)
                if inside and not all_in:
                    bad.append((f["name"], which, e, t, "in a region, min margin %.3g" % min(ms)))
                elif not inside and all_in:
                    fine = [-1 + 2 * k / 1024 for k in range(1025)]
                    more = classify(client, f, [M.push_wrench(mdl, e, t, s * mu_f)
                                                for s in fine], (which,))
                    if all(m[which] > 0 for m in more):
                        bad.append((f["name"], which, e, t, "in no region, every force inside"))
                checked += 1
    count("finger points", checked)
    assert not bad, "finger-friction regions disagree at %d of %d points: %r" % (
        len(bad), checked, bad[:10])


# ---- 5. gravity.sweep --------------------------------------------------------------------

def check_gravity(client, fixture, seed, model_every=0):
    mdl = M.Model(fixture)
    cl = M.Classifier(mdl) if model_every else None
    rnd = random.Random(seed)
    g0 = rnd.uniform(0.5, 20.0)
    found = {}
    wrenches = []
    batches = []
    for which in SETS:
        iv = check_arcs(sweep(client, fixture, which))
        found[which] = iv
        pts = probes(iv, 1, 360.0, 720, seed)
        ends = endpoints(iv, 360.0, True)
        batches.append((which, iv, pts, ends))
        wrenches += [M.gravity_wrench(mdl, t, g0) for _, t, _ in pts]
        wrenches += [M.gravity_wrench(mdl, t, g0) for _, t in ends]
    margins = classify(client, fixture, wrenches)
    at = 0
    for which, iv, pts, ends in batches:
        where = "gravity %s set=%s g0=%r" % (fixture.get("name"), which, g0)
        mp = [m[which] for m in margins[at:at + len(pts)]]
        at += len(pts)
        me = [m[which] for m in margins[at:at + len(ends)]]
        at += len(ends)
        check_against_points(where, iv, mp, pts)
        for (_, t), m in zip(ends, me):
            assert abs(m) < ENDPOINT_TOL, "%s: margin %.3g at arc end %r of %r" % (where, m, t, iv)
        count("gravity points", len(pts))
        count("gravity endpoints", len(ends))
        if cl is not None:
            for i, ((_, t, _), m) in enumerate(zip(pts, mp)):
                if i % model_every == 0:
                    exp = cl.classify(M.gravity_wrench(mdl, t, g0), which).margin
                    assert H.close(m, exp, H.MARGIN_TOL), (where, t, m, exp)
    check_both_is_the_intersection(found, 360.0)
    count("gravity fixtures")
    return found


def test_gravity_sweep_random_fixtures(client):
    """Random polygons and discs, the docs/MODEL.md section 7 disc and the plates: the arcs of
    each set against classify of m g0 (cos phi, sin phi, 0) (g0 random
    positive: cones do not care) at 720 points around plus the points just
    inside and outside each end; the ends have margin 0; one point in 23
    against model.py (every other fixture)."""
    fixtures = ([FX.disc_corner(0.3), FX.rectangle_321(0.2), FX.chamfered_plate(0.05),
                 FX.offset_disc(), FX.triangle(), FX.disc_one_fixel()]
                + random_fixtures(31, polygons=8, discs=8))
    nonempty = {s: 0 for s in SETS}
    split = 0
    for i, f in enumerate(fixtures):
        found = check_gravity(client, f, seed=i, model_every=23 if i % 2 == 0 else 0)
        for s in SETS:
            nonempty[s] += bool(found[s])
            split += any(a == 0 for _, a, _ in found[s]) and any(b == 360 for _, _, b in found[s])
    print("gravity: non-empty", nonempty, "split at 0:", split)
    assert nonempty["goal"] >= 3 and nonempty["strong"] >= 6, nonempty
    assert split >= 1, "no arc through 0 among the random fixtures: the split is untested here"


def test_gravity_sweep_needs_no_outline(client):
    """The gravity wrench needs the mass, not the outline: a fixture without
    a shape (com and inertia given) sweeps as the same fixture with one."""
    f = FX.disc_corner(0.3)
    g = FX.variant(f, ["body", "shape"], delete=True)
    for s in SETS:
        assert sweep(client, g, s) == sweep(client, f, s)


# ---- 6. stability.margin ------------------------------------------------------------------

def smargin(client, fixture, bias):
    res = client.result("stability.margin", {"fixture": fixture, "bias": list(bias)})
    assert set(res) == {"margin", "blocking", "worst_direction"}, res
    return res


def scaled_norm(mdl, w):
    return M.norm(mdl.scale(w))


def random_unit(rnd):
    while True:
        v = (rnd.gauss(0, 1), rnd.gauss(0, 1), rnd.gauss(0, 1))
        n = M.norm(v)
        if n > 1e-6:
            return M.mul(1 / n, v)


def check_margin(client, fixture, mdl, cl, bias, rnd, disturbances=300):
    """One bias against classify, the model and random disturbances;
    returns 'inside' or 'outside' or None when too near the boundary."""
    (r0,) = classify_full(client, fixture, [bias])
    m_cl = r0["strong"]["margin"]
    if abs(m_cl) < 1e-4:
        return None
    res = smargin(client, fixture, bias)
    hn = scaled_norm(mdl, bias)
    margin, blocking, wd = res["margin"], res["blocking"], res["worst_direction"]
    where = "%s bias=%r answer=%r classify margin %r" % (fixture["name"], bias, res, m_cl)
    # (a) distances to cones are homogeneous: dist(h, C) = |h| dist(h/|h|, C)
    assert H.close(margin, hn * m_cl, 1e-9 * hn), where
    exp = cl.classify(bias, "strong")
    assert H.close(margin, hn * exp.margin, 1e-7 * hn), ("model", exp, where)
    assert blocking in cl.modes, where
    assert blocking in exp.candidates, ("blocking", exp, where)
    assert blocking == r0["strong"]["blocking"] or blocking in exp.candidates, where
    # (c) a physical wrench of unit scaled length
    assert isinstance(wd, list) and len(wd) == 3, where
    assert abs(scaled_norm(mdl, wd) - 1) < 1e-9, where
    cone = M.mode_cone(mdl, blocking)
    h = mdl.scale(bias)
    u = mdl.scale(wd)
    if margin > 0:
        # (b) along wd the distance to the union falls as (1 - s) margin:
        # bias + margin wd is on the nearest cone (margin 0, not inside),
        # 0.99 of it is inside with 0.01 margin left
        ss = (0.5, 0.99, 1.0, 1.01)
        pts = [M.add(bias, M.mul(s * margin, wd)) for s in ss]
        rs = classify_full(client, fixture, pts)
        dist = [scaled_norm(mdl, p) * r["strong"]["margin"] for p, r in zip(pts, rs)]
        tol = 1e-9 * (hn + margin)
        assert H.close(dist[0], 0.5 * margin, tol), ("half way", dist, where)
        assert H.close(dist[1], 0.01 * margin, tol), ("0.99", dist, where)
        assert rs[1]["strong"]["verdict"] == "inside", ("0.99", rs[1], where)
        assert abs(rs[2]["strong"]["margin"]) < 1e-9, ("on the cone", rs[2], where)
        assert rs[2]["strong"]["verdict"] != "inside", ("on the cone", rs[2], where)
        assert dist[3] <= 0.01 * margin + tol, ("1.01", dist, where)
        count("margin 1.01 leaves G_strong" if rs[3]["strong"]["verdict"] != "inside"
              else "margin 1.01 stays in G_strong (a thin cone or an edge)")
        # the model: the nearest point is on the blocking cone
        assert cone.distance(M.add(h, M.mul(margin, u))) < 1e-7 * (hn + margin), where
        assert H.close(cone.distance(h), margin, 1e-7 * hn), where
        # (d) no disturbance of scaled size 0.99 margin leaves G_strong
        ds = [M.add(bias, mdl.unscale(M.mul(0.99 * margin, random_unit(rnd))))
              for _ in range(disturbances)]
        rs = classify_full(client, fixture, ds)
        out = [(d, r["strong"]) for d, r in zip(ds, rs) if r["strong"]["verdict"] != "inside"]
        assert not out, ("a disturbance smaller than the margin", out[:3], where)
        count("disturbances", len(ds))
        count("biases inside G_strong")
        return "inside"
    # outside: margin = -|h| depth, blocking the deepest cone, wd the unit
    # outward normal of its nearest facet: bias + |margin| wd is on that
    # facet, half way the depth is halved, a bit beyond it is out of the cone
    depth = -margin
    assert H.close(cone.depth(M.mul(1 / hn, h)) * hn, depth, 1e-7 * hn), where
    assert any(H.vec_close(u, fct, 1e-7) and H.close(-M.dot(fct, h), depth, 1e-7 * hn)
               for fct in cone.facets), ("not the nearest facet's normal", cone.facets, where)
    half = M.add(h, M.mul(0.5 * depth, u))
    assert H.close(cone.depth(M.mul(1 / M.norm(half), half)) * M.norm(half), 0.5 * depth,
                   1e-7 * hn), where
    beyond = M.add(h, M.mul(1.01 * depth, u))
    assert cone.distance(beyond) > 0.005 * depth, where
    count("biases outside G_strong")
    return "outside"


def test_stability_margin_random(client):
    """Random biases on random fixtures (and docs/MODEL.md section 7's disc, the plates, the
    offset disc, a body on one fixel that is not pinned): (a) the margin is
    |scaled bias| times classify's strong margin (and model.py's), the
    blocking mode is the nearest / deepest one; (b) along worst_direction
    the distance shrinks linearly to 0 at the margin; (c) worst_direction
    has unit scaled length; (d) 300 random disturbances of scaled size 0.99
    margin per bias inside stay inside G_strong."""
    rnd = random.Random(61)
    fixtures = ([FX.disc_corner(0.5), FX.rectangle_321(0.3), FX.chamfered_plate(0.1),
                 FX.offset_disc(), FX.triangle(), FX.corner_fixel_plate(), FX.disc_one_fixel()]
                + random_fixtures(62, polygons=4, discs=3))
    kinds = {"inside": 0, "outside": 0}
    for f in fixtures:
        mdl = M.Model(f)
        cl = M.Classifier(mdl)
        got = {"inside": 0, "outside": 0}
        tries = 0
        while min(got.values()) < 2 and tries < 60:
            tries += 1
            bias = tuple(round(rnd.uniform(-3, 3), 4) for _ in range(3))
            if got["inside"] < 2 and rnd.random() < 0.5:
                # aim for G_strong: a push into the fixels, like a bias
                fx = rnd.choice(mdl.fixels)
                bias = tuple(round(x, 4) for x in M.add(
                    M.mul(-rnd.uniform(0.5, 3), fx.Wn),
                    M.mul(rnd.uniform(-0.5, 0.5), (rnd.gauss(0, 1), rnd.gauss(0, 1),
                                                   rnd.gauss(0, 1)))))
            kind = check_margin(client, f, mdl, cl, bias, rnd,
                                disturbances=300 if got["inside"] < 1 else 100)
            if kind:
                got[kind] += 1
        for k in kinds:
            kinds[k] += got[k]
    assert kinds["inside"] >= 12 and kinds["outside"] >= 12, kinds


def test_stability_margin_disc_corner_closed_form(client):
    """docs/MODEL.md section 7's disc (m = 1, I = 0.5, rho = sqrt(1/2)), mu = 0.5, bias
    (-1, -1, 0).  Mode sn (fixel 1 leaves, fixel 2 sticks): a_x > 0,
    a_y = 0, a_t2 = -a_x - alpha = 0, so M q = a (1, 0, -1/2); the friction
    edges of fixel 2 give -(W_2n +- mu W_2t) = (+-mu, -1, +-mu).  The facet
    spanned by the two friction edges lies in the plane tau = f_x, in the
    scaled metric {(1, 0, -rho) . h = 0}, whose distance from h = (-1, -1, 0)
    is 1 / sqrt(1 + rho^2) = sqrt(2/3); the foot of the perpendicular,
    (-1/3, -1, -1/3), is (1/6)(mu, -1, mu) + (5/6)(-mu, -1, -mu): inside the
    facet.  ns is the mirror image, as near.  The other modes are farther
    (ll, for one, needs tau <= -2 mu / (1 + mu^2) at this force: scaled
    distance 2 sqrt(2) mu / (1 + mu^2) = 1.13; the model checks them all).
    So margin = sqrt(2/3), blocking sn or ns, worst direction the facet's
    unit normal, scaled (1, 0, -rho) / sqrt(1 + rho^2), i.e. the physical
    wrench sqrt(2/3) (1, 0, -1/2) for sn (and sqrt(2/3) (0, 1, 1/2) for
    ns).  The bias given as a force at a point is the same bias."""
    f = FX.disc_corner(0.5)
    mdl = M.Model(f)
    cl = M.Classifier(mdl)
    res = smargin(client, f, (-1, -1, 0))
    k = 2 / math.sqrt(6)
    assert abs(res["margin"] - math.sqrt(2 / 3)) < 1e-12, res
    assert H.close(cl.classify((-1, -1, 0), "strong").margin * math.sqrt(2), math.sqrt(2 / 3),
                   1e-9)
    assert res["blocking"] in ("sn", "ns"), res
    expect = (k, 0, -k / 2) if res["blocking"] == "sn" else (0, k, k / 2)
    assert H.vec_close(res["worst_direction"], expect, 1e-12), (res, expect)
    check_margin(client, f, mdl, cl, (-1.0, -1.0, 0.0), random.Random(1))
    # the same bias as a force at the centre; a force at (0.5, 0) adds tau = 0.5 * -1
    same = client.result("stability.margin", {"fixture": f, "bias": {"force": [-1, -1],
                                                                      "at": [0, 0]}})
    assert same == res, (same, res)
    moved = client.result("stability.margin", {"fixture": f, "bias": {"force": [-1, -1],
                                                                       "at": [0.5, 0]}})
    assert moved == smargin(client, f, (-1, -1, -0.5)), moved
    # units: a bias twice as large has twice the margin, the same mode and direction
    twice = smargin(client, f, (-2, -2, 0))
    assert H.close(twice["margin"], 2 * res["margin"], 1e-12 * 2), (twice, res)
    assert twice["blocking"] == res["blocking"], (twice, res)
    assert H.vec_close(twice["worst_direction"], res["worst_direction"], 1e-12), (twice, res)


def test_stability_margin_form_closure_is_null(client):
    """fixtures.square_form_closure: four frictionless fixels whose wrenches
    sum to zero and span R^3 (first-order form closure): no q != 0 keeps
    every a_n >= 0, so no mode is feasible (modes.get: none; the model
    agrees), G_strong is everything, and the margin is unbounded: nulls."""
    f = FX.square_form_closure()
    mdl = M.Model(f)
    modes, pinned = M.modes(mdl)
    assert modes == [] and pinned, modes
    assert client.result("modes.get", {"fixture": f})["feasible"] == []
    for bias in ([0, 0, 0], [1, 2, 3], [-5, 0.5, -0.1]):
        res = smargin(client, f, bias)
        assert res == {"margin": None, "blocking": None, "worst_direction": None}, res
    # every push and every tilt holds it (no excluded cone: margin 1)
    iv = check_region_answer(mdl, regions(client, f, "strong"))
    assert iv == [(e, 0.0, 1.0) for e in range(4)], iv
    assert sweep(client, f, "strong") == [[0, 360]]


def test_stability_margin_of_a_huge_bias(client):
    """Finite input, a margin past the largest double: |scaled bias| of
    (-1e308, -1e308, 1e308) overflows.  docs/MODEL.md section 6 and docs/PROTOCOL.md leave no room for a
    margin that is not a number when a moving mode exists (null means no
    moving mode at all, and then blocking and worst_direction are null
    too): the answer is either the margin, 1e308 times that of (-1, -1, 1)
    (distances to cones are homogeneous), or an invalid-params error naming
    the bias.  (A bias just inside the range, (1e308, 1e308, 0), is
    answered: depth 1/sqrt(2) of the unit wrench in G_ss's closure
    {f_x >= 0, f_y >= 0}, times |h| = sqrt(2) 1e308: -1e308.)"""
    f = FX.disc_corner(0.5)
    res = smargin(client, f, (1e308, 1e308, 0))
    assert H.close(res["margin"], -1e308, 1e295), res
    # homogeneity: margin(1e308 b) = 1e308 margin(b), b = (-1, -1, 1), whose
    # scaled length is 2 (rho = sqrt(1/2)): representable (about -2.1e307)
    small = smargin(client, f, (-1, -1, 1))
    expected = 1e308 * small["margin"]
    assert math.isfinite(expected) and expected < 0, small
    resp = client.call("stability.margin", {"fixture": f, "bias": [-1e308, -1e308, 1e308]})
    if "error" in resp:
        assert resp["error"]["code"] == -32602, resp
        assert resp["error"]["data"]["field"].startswith("params.bias"), resp
    else:
        res = resp["result"]
        assert isinstance(res["margin"], (int, float)), (
            "margin %r (expected %r) while blocking is %r: %r" % (
                res["margin"], expected, res["blocking"], res))
        assert H.close(res["margin"], expected, 1e-9 * abs(expected)), (res, expected)
        assert res["blocking"] == small["blocking"], (res, small)


def test_stability_margin_needs_no_outline(client):
    f = FX.disc_corner(0.5)
    g = FX.variant(f, ["body", "shape"], delete=True)
    for bias in ([-1, -1, 0], [1, -2, 0.3]):
        assert smargin(client, g, bias) == smargin(client, f, bias)


# ---- 7. errors ------------------------------------------------------------------------

def test_errors(client):
    f = FX.disc_corner(0.5)
    shapeless = FX.variant(f, ["body", "shape"], delete=True)
    assert error_of(client, "push.regions", {"fixture": shapeless}) == "params.fixture.body.shape"
    assert error_of(client, "push.regions", {"fixture": shapeless, "set": "strong"}) == \
        "params.fixture.body.shape"
    fid = client.result("fixture.put", {"fixture": shapeless})["id"]
    assert error_of(client, "push.regions", {"fixture": fid}).startswith("params.fixture")
    for method in ("push.regions", "gravity.sweep"):
        for bad in ("Goal", "", "all", 3, ["goal"], None):
            assert error_of(client, method, {"fixture": f, "set": bad}) == "params.set", (
                method, bad)
        assert error_of(client, method, {"fixture": f, "sets": ["goal"]}) == "params.sets"
        assert error_of(client, method, {"fixture": f, "colour": 1}) == "params.colour"
        assert error_of(client, method, {}) == "params.fixture"
        assert error_of(client, method, {"fixture": "0" * 32}, code=-32001) == "params.fixture"
    assert error_of(client, "push.regions", {"fixture": f, "finger_friction": -0.1}) == \
        "params.finger_friction"
    assert error_of(client, "push.regions", {"fixture": f, "finger_friction": "0.1"}) == \
        "params.finger_friction"
    assert error_of(client, "gravity.sweep", {"fixture": f, "finger_friction": 0.1}) == \
        "params.finger_friction"
    assert error_of(client, "stability.margin", {"fixture": f}) == "params.bias"
    for bad in ([1, 2], [1, 2, 3, 4], "x", 3, None, {"force": [1, 0]}, [1, "a", 0]):
        field = error_of(client, "stability.margin", {"fixture": f, "bias": bad})
        assert field == "params.bias" or field.startswith("params.bias[") or \
            field.startswith("params.bias."), (bad, field)
    assert error_of(client, "stability.margin", {"fixture": f, "bias": [1, "a", 0]}) == \
        "params.bias[1]"
    assert error_of(client, "stability.margin", {"fixture": f, "bias": [0, 0, 0],
                                                 "set": "strong"}) == "params.set"
    assert error_of(client, "stability.margin", {"bias": [0, 0, 0]}) == "params.fixture"
    # the daemon is still fine
    assert regions(client, f, "goal")["regions"]
