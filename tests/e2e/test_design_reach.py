"""fixture.design and push.regions on real outlines: sites by arc length,
push_on, pins.

Every expected number comes from geometry computed here or from the
daemon's other methods about fixtures this file builds (see
test_design.py's docstring for the brute force):

* sites by arc length: positions walked here along faceted arcs and mixed
  line/arc loops, on this file's own segment lengths and normals;
* push_on: push.regions without it, its regions on the loops not pushed on
  dropped here; the design against a brute force over every candidate with
  those regions;
* pins: where a pin of diameter D touches a wall and whether it fits,
  from the hole's own geometry here (a circle: D <= 2R; a rectangle: the
  pin's centre at least D / 2 from every wall), and a design with two
  fixels in one hole never ranked (counted as shared_hole).
"""

import math

import pytest

from conftest import FIGURES, SLOW
from test_design import (HOLED, Brute, LEN_TOL, check_best_push, check_candidate_identity,
                         check_ranking, check_shape_of_answer, design, loops_of,
                         loop_positions, results, spacing_sites)


def figure(key, n=1):
    FIGURES[key] = FIGURES.get(key, 0) + n


def faceted_circle(cx, cy, r, n, clockwise=False):
    step = -1 if clockwise else 1
    return [[cx + r * math.cos(step * 2 * math.pi * k / n),
             cy + r * math.sin(step * 2 * math.pi * k / n), 0] for k in range(n)]


def rounded_plate():
    """40 x 30, the corner at (40, 30) rounded with radius 10 as 12 facets
    from (40, 20) to (30, 30); a 24-facet hole of radius 4 about (12, 12);
    a hole of two half circles of radius 3 about (25, 10)."""
    outer = [[0, 0, 0], [40, 0, 0]]
    for k in range(13):
        a = (math.pi / 2) * k / 12
        outer.append([30 + 10 * math.cos(a), 20 + 10 * math.sin(a), 0])
    outer.append([0, 30, 0])
    hole = faceted_circle(12, 12, 4, 24)
    round_hole = [[22, 10, 1], [28, 10, 1]]
    return {"mass": 1.0, "shape": {"type": "outline", "loops": [outer, hole, round_hole]}}


ROUNDED = rounded_plate()


def daemon_sites(client, body, params, k=2):
    """{site index: (at, normal)} the daemon's designs show, and its site
    count."""
    # A thousand designs kept, each with its figures: about 10 s on the plain
    # daemon, three times that under ASan, beyond a call's usual timeout.
    req = client.request("fixture.design", dict(params, body=body, friction=0.2, fixels=k,
                                                objective="region", top=1000,
                                                collapse_symmetric=False))
    client.send(req)
    resp = client.read_json(timeout=120 * SLOW)
    assert "result" in resp, resp
    ans = resp["result"]
    seen = {}
    for d in ans["designs"]:
        for i, fx in zip(d["sites"], d["fixels"]):
            seen[i] = (tuple(fx["at"]), tuple(fx["normal"]))
    return ans, seen


def arc_walk(lp, s):
    """The point at distance s along a loop, walked here segment by segment
    with each segment's own point()."""
    for seg in lp.segments:
        if s <= seg.length + 1e-12:
            return seg.point(min(1.0, s / seg.length))
        s -= seg.length
    return lp.segments[-1].point(1.0)


@pytest.mark.parametrize("h", [3.0, 5.0])
def test_sites_by_arc_length_faceted_and_mixed(client, h):
    """On ROUNDED: the 12-facet arc and its two straight neighbours are one
    run between the corners (40, 0) and (0, 30) (the facets turn 7.5
    degrees, the joints to the lines 3.75); the 24-facet hole (15 degrees
    a joint) and the two
    half circles have no corners: closed runs.  Our positions, walked along
    the loops, against the daemon's sites; and consecutive sites of a run
    h apart along the boundary."""
    shape = ROUNDED["shape"]
    mine = spacing_sites(shape, h)
    loops = loops_of(shape)
    # the faceted arc gets sites (by segment: floor(1.3 / h) = 0 on each facet)
    on_facets = [s for s in mine if s[2] == 0 and s[0][0] > 30.0 + 1e-9 and s[0][1] > 20 + 1e-9]
    assert len(on_facets) >= int(10 * math.pi / 2 / h) - 1, (len(on_facets), h)
    # spacing along each loop, from our own walk: a run's sites h apart, a
    # closed run's P / n apart
    for li, lp in enumerate(loops):
        positions, corners, starts = loop_positions(lp, h, h / 2)
        perimeter = starts[-1]
        ours = [s for s in mine if s[2] == li]
        assert len(ours) == len(positions)
        for (at, _, _), s in zip(ours, positions):
            p = arc_walk(lp, s)
            assert math.hypot(at[0] - p[0], at[1] - p[1]) <= 1e-9, (li, s, at, p)
        if li == 0:
            assert len(corners) == 3, corners       # (0, 0), (40, 0), (0, 30)
        else:
            assert corners == [], corners
            n = len(positions)
            assert n == int(perimeter / h + 1e-9)
            for a, b in zip(positions, positions[1:]):
                assert abs(b - a - perimeter / n) <= 1e-9
        for c in corners:
            for s in positions:
                gap = min(abs(s - c), perimeter - abs(s - c))
                assert gap >= h / 2 - 1e-9, (li, s, c)
    ans, seen = daemon_sites(client, ROUNDED, {"spacing": h})
    assert ans["sites"] == len(mine), (ans["sites"], len(mine))
    assert len(seen) >= len(mine) // 3, (len(seen), len(mine))
    for i, (at, nrm) in seen.items():
        a2, n2, _ = mine[i]
        assert max(abs(at[0] - a2[0]), abs(at[1] - a2[1])) <= 1e-9, (i, at, a2)
        assert max(abs(nrm[0] - n2[0]), abs(nrm[1] - n2[1])) <= 1e-9, (i, nrm, n2)
    figure("design sites by arc length checked", len(seen))


def test_faceted_circle_sites_at_the_facets_joints(client):
    """A 60-facet circle of radius 10 as the whole outline: each facet is
    1.05 long, so h = 2 gave no site by segment; by arc length floor(P / 2)
    = 31 sites, on the facets and at their joints, normals towards the
    centre within half a facet's turn (3 degrees)."""
    body = {"mass": 1.0, "shape": {"type": "outline", "loops": [faceted_circle(0, 0, 10, 60)]}}
    mine = spacing_sites(body["shape"], 2.0)
    assert len(mine) == 31
    ans, seen = daemon_sites(client, body, {"spacing": 2.0})
    assert ans["sites"] == 31
    assert seen, ans["counts"]
    for i, (at, nrm) in seen.items():
        assert max(abs(a - b) for a, b in zip(at + nrm, mine[i][0] + mine[i][1])) <= 1e-9
        centre = math.atan2(-at[1], -at[0])
        assert abs(math.remainder(math.atan2(nrm[1], nrm[0]) - centre, 2 * math.pi)) <= math.radians(3.0) + 1e-9


def test_corner_clearance(client):
    """A 10 x 4 rectangle, h = 2: clearance 3 leaves (10 - 6) / 2 + 1 = 3
    sites on a long side (3, 5, 7 from its start) and none on a short one."""
    body = {"mass": 1.0, "shape": {"type": "polygon",
                                   "vertices": [[0, 0], [10, 0], [10, 4], [0, 4]]}}
    mine = spacing_sites(body["shape"], 2.0, clearance=3.0)
    assert [s[0] for s in mine] == [(3, 0), (5, 0), (7, 0), (7, 4), (5, 4), (3, 4)]
    ans, seen = daemon_sites(client, body, {"spacing": 2.0, "corner_clearance": 3.0})
    assert ans["sites"] == 6
    for i, (at, _) in seen.items():
        assert at == mine[i][0]


# ---- push_on ------------------------------------------------------------------------------

def test_push_regions_push_on(client):
    """push.regions with push_on: exactly the regions without it on the loops
    named, on fixtures of HOLED with goal regions on both loops (the first
    ten of the spacing's 3-site candidates with one site in the hole)."""
    import itertools
    sites = spacing_sites(HOLED["shape"], 2.5)
    fixtures = []
    for combo in itertools.combinations(range(len(sites)), 3):
        if sum(1 for i in combo if sites[i][2] == 1) == 1:
            fixtures.append({"body": HOLED, "friction": {"static": 0.3},
                             "fixels": [{"at": list(sites[i][0])} for i in combo]})
    wholes = results(client, [("push.regions", {"fixture": f, "set": "goal"}) for f in fixtures])
    both = [(f, w) for f, w in zip(fixtures, wholes)
            if {r["loop"] for r in w["regions"]} == {0, 1}][:10]
    assert len(both) == 10, len(both)
    for fixture, whole in both:
        for push_on, keep in (("outer", {0}), ("all", {0, 1}), ([1], {1}), ([0, 1], {0, 1})):
            got = client.result("push.regions", {"fixture": fixture, "set": "goal",
                                                 "push_on": push_on})
            want = [r for r in whole["regions"] if r["loop"] in keep]
            assert got["regions"] == want, (push_on, got["regions"], want)
            assert abs(got["total_length"] - sum(r["length"] for r in want)) <= LEN_TOL
            figure("push_on regions compared")


@pytest.mark.parametrize("push_on, allowed", [("outer", {0}), ([1], {1}), ("all", None)])
def test_design_push_on_brute_force(client, push_on, allowed):
    """HOLED, sites every 2.5 (outer and hole), 2 fixels: counts, ranking
    and best pushes against the brute force whose regions keep only the
    loops pushed on; no best push on another loop."""
    sites = spacing_sites(HOLED["shape"], 2.5)
    brute = Brute(client, HOLED, 0.3, sites, 2, gravity=False, push_on=allowed)
    c = brute.counts()
    assert c["shared_hole"] >= 1, c
    fr = {"static": 0.3}
    for objective, top in (("margin", 8), ("region", 8)):
        ans = design(client, {"body": HOLED, "friction": 0.3, "spacing": 2.5, "fixels": 2,
                              "objective": objective, "top": top, "push_on": push_on})
        check_shape_of_answer(ans, len(sites), objective)
        assert ans["counts"] == c, (ans["counts"], c)
        check_candidate_identity(ans, brute)
        tol = 1e-8 if objective == "margin" else LEN_TOL
        check_ranking(ans["designs"], brute.scores(objective), top, tol=tol, tie=tol)
        for d in ans["designs"]:
            check_best_push(client, brute, d, HOLED, fr, objective)
            if allowed is not None and d["best_push"] is not None:
                assert d["best_push"]["loop"] in allowed, d["best_push"]
            # never two fixels in the hole
            assert sum(1 for i in d["sites"] if sites[i][2] > 0) <= 1, d
        figure("design push_on rankings compared")


def test_push_on_changes_the_designs(client):
    """On HOLED the brute force finds candidates whose only seating pushes
    are in the hole: with push_on "outer" they have none."""
    sites = spacing_sites(HOLED["shape"], 2.5)
    everywhere = Brute(client, HOLED, 0.3, sites, 2, gravity=False)
    outer = Brute(client, HOLED, 0.3, sites, 2, gravity=False, push_on={0})
    assert outer.counts()["no_seating_push"] > everywhere.counts()["no_seating_push"]


# ---- pins -----------------------------------------------------------------------------

# a 10 x 10 plate with a rectangular hole 2 x 6 (x 4..6, y 2..8), written
# counter-clockwise
SLOTTED = {"mass": 1.0, "shape": {"type": "outline", "loops": [
    [[0, 0], [10, 0], [10, 10], [0, 10]], [[4, 2], [6, 2], [6, 8], [4, 8]]]}}


def rect_pin_fits(diameter):
    """Does a pin of `diameter` touching the slot's wall at `at` (normal into
    the material) fit: its centre at - D/2 normal at least D/2 from every
    wall of the slot (to 1e-9)?"""
    def fits(loop, at, normal):
        r = diameter / 2
        c = (at[0] - r * normal[0], at[1] - r * normal[1])
        return min(c[0] - 4, 6 - c[0], c[1] - 2, 8 - c[1]) >= r - 1e-9
    return fits


def test_spaced_pins_fit_and_never_share_a_hole(client):
    """pin_diameter 1.2, h = 1, clearance 0.3: on the slot's long walls the
    sites 0.5 from a corner are dropped (a pin of radius 0.6 there overlaps
    the end wall), the short walls (2 wide: sites 0.5 from each end) keep
    none.  The design against the brute force over those sites: pins listed
    with their diameter, never two fixels in the slot."""
    fits = rect_pin_fits(1.2)
    sites = spacing_sites(SLOTTED["shape"], 1.0, clearance=0.3, pin_diameter=1.2, pin_fits=fits)
    every = spacing_sites(SLOTTED["shape"], 1.0, clearance=0.3)
    holes = [s for s in sites if s[2] == 1]
    assert len([s for s in every if s[2] == 1]) == 2 * 6 + 2 * 2 and len(holes) == 2 * 4, holes
    brute = Brute(client, SLOTTED, 0.3, sites, 2, gravity=False)
    params = {"body": SLOTTED, "friction": 0.3, "spacing": 1.0, "corner_clearance": 0.3,
              "pin_diameter": 1.2, "fixels": 2, "objective": "region", "top": 30}
    ans = design(client, params)
    check_shape_of_answer(ans, len(sites), "region")
    assert ans["counts"] == brute.counts(), (ans["counts"], brute.counts())
    assert brute.counts()["shared_hole"] == 8 * 7 // 2
    check_candidate_identity(ans, brute, pin_diameter=1.2)
    check_ranking(ans["designs"], brute.region, 30, tol=LEN_TOL, tie=LEN_TOL)
    assert any(d["pins"] for d in ans["designs"]), "no design with a pin: the case shows none"
    figure("design pins compared", len(holes))


def test_pin_site_touches_the_wall(client):
    """A pin in HOLED's hole (radius 2 about (5, 5)), from its centre
    (5.5, 5.2): it moves to the nearest point of the wall, (5, 5) + 2 u with
    u along (0.5, 0.2); the contact's normal is u (into the material).  Its
    diameter may be up to the hole's 4."""
    u = (0.5 / math.hypot(0.5, 0.2), 0.2 / math.hypot(0.5, 0.2))
    contact = (5 + 2 * u[0], 5 + 2 * u[1])
    sites = [{"at": [5.5, 5.2], "pin": {"hole": 1, "diameter": 3.0}},
             {"at": [0, 3]}, {"at": [4, 0]}]
    ans = design(client, {"body": HOLED, "friction": 0.3, "sites": sites, "fixels": 3,
                          "objective": "region"})
    assert ans["counts"]["candidates"] == 1
    fx = {"body": HOLED, "friction": {"static": 0.3},
          "fixels": [{"at": list(contact)}, {"at": [0, 3]}, {"at": [4, 0]}]}
    goal = client.result("push.regions", {"fixture": fx, "set": "goal"})
    if ans["designs"]:
        d = ans["designs"][0]
        assert max(abs(a - b) for a, b in zip(d["fixels"][0]["at"], contact)) <= 1e-9, d
        assert max(abs(a - b) for a, b in zip(d["fixels"][0]["normal"], u)) <= 1e-9, d
        assert d["pins"] == [{"fixel": 0, "hole": 1, "diameter": 3.0}]
        assert abs(d["goal_length"] - goal["total_length"]) <= LEN_TOL
    else:
        assert not goal["regions"], goal
    # two pins in the one hole: never a design
    two = [{"at": [5.5, 5.2], "pin": {"hole": 1, "diameter": 1.0}},
           {"at": [4.5, 4.8], "pin": {"hole": 1, "diameter": 1.0}}, {"at": [0, 3]}]
    ans = design(client, {"body": HOLED, "friction": 0.3, "sites": two, "fixels": 2})
    assert ans["counts"]["shared_hole"] == 1 and all(
        sorted(d["sites"]) != [0, 1] for d in ans["designs"]), ans


@pytest.mark.parametrize("site, field", [
    ({"at": [5.5, 5], "pin": {"hole": 0, "diameter": 1}}, "params.sites[0].pin.hole"),
    ({"at": [5.5, 5], "pin": {"hole": 2, "diameter": 1}}, "params.sites[0].pin.hole"),
    ({"at": [5.5, 5], "pin": {"hole": 1.5, "diameter": 1}}, "params.sites[0].pin.hole"),
    ({"at": [5.5, 5], "pin": {"hole": 1, "diameter": 4.5}}, "params.sites[0].pin.diameter"),
    ({"at": [5.5, 5], "pin": {"hole": 1, "diameter": -1}}, "params.sites[0].pin.diameter"),
    ({"at": [5.5, 5], "pin": {"hole": 1, "diameter": "x"}}, "params.sites[0].pin.diameter"),
    ({"at": [5.5, 5], "pin": {"hole": 1}}, "params.sites[0].pin.diameter"),
    ({"at": [5.5, 5], "pin": {"hole": 1, "diameter": 1, "x": 0}}, "params.sites[0].pin.x"),
    ({"at": [5.5, 5], "pin": [1, 1]}, "params.sites[0].pin"),
    ({"at": [1, 1], "pin": {"hole": 1, "diameter": 1}}, "params.sites[0].at"),
    ({"at": [5.5, 5], "normal": [1, 0], "pin": {"hole": 1, "diameter": 1}},
     "params.sites[0].normal"),
])
def test_pin_refusals(client, site, field):
    resp = client.call("fixture.design", {"body": HOLED, "friction": 0.3, "fixels": 1,
                                          "sites": [site]})
    assert resp.get("error", {}).get("code") == -32602, resp
    assert resp["error"]["data"]["field"] == field, resp["error"]


@pytest.mark.parametrize("method, extra, field", [
    ("fixture.design", {"push_on": "inner"}, "params.push_on"),
    ("fixture.design", {"push_on": []}, "params.push_on"),
    ("fixture.design", {"push_on": [0, 2]}, "params.push_on[1]"),
    ("fixture.design", {"push_on": [0, -1]}, "params.push_on[1]"),
    ("fixture.design", {"push_on": ["0"]}, "params.push_on[0]"),
    ("fixture.design", {"push_on": 1}, "params.push_on"),
    ("fixture.design", {"corner_clearance": 0}, "params.corner_clearance"),
    ("fixture.design", {"corner_clearance": "x"}, "params.corner_clearance"),
    ("fixture.design", {"pin_diameter": -1}, "params.pin_diameter"),
    ("push.regions", {"push_on": [3]}, "params.push_on[0]"),
    ("push.regions", {"push_on": "holes"}, "params.push_on"),
])
def test_push_on_refusals(client, method, extra, field):
    if method == "fixture.design":
        params = dict({"body": HOLED, "friction": 0.3, "spacing": 2.5}, **extra)
    else:
        params = dict({"fixture": {"body": HOLED, "friction": {"static": 0.3},
                                   "fixels": [{"at": [0, 3]}, {"at": [4, 0]}, {"at": [7, 5]}]},
                       "set": "goal"}, **extra)
    resp = client.call(method, params)
    assert resp.get("error", {}).get("code") == -32602, resp
    assert resp["error"]["data"]["field"] == field, resp["error"]


def test_spacing_only_members_without_spacing(client):
    resp = client.call("fixture.design", {"body": HOLED, "friction": 0.3, "corner_clearance": 1,
                                          "sites": [{"at": [0, 3]}]})
    assert resp["error"]["data"]["field"] == "params.corner_clearance", resp
