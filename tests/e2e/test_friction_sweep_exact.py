"""friction.sweep's endpoints, checked by other means than the sweep's own
roots: against bisection.

For every fixture below, every sweep (push regions of goal, strong and both,
gravity arcs, with kinetic ratios 1 and 0.5) is compared with the existing
point-friction methods (push.regions, gravity.sweep) on the fixture with
"static": mu, "kinetic": ratio * mu:

* at 120 sampled mu, further than 1e-6 from every interval end, the region
  is non-empty exactly inside the reported intervals;
* at every curve point away from a jump, the length is the point answer's;
* every interval end strictly inside the range is found again by bisecting
  the point answer's emptiness from a bracket of +-1e-4: the side inside
  the interval is the non-empty one, and the two agree to 1e-9 (or, where
  the point answer has dropped a sliver narrower than 1e-9 of its range as
  rounding, the bisected end is that sliver's width early, under 1e-8).

The fixtures are the outlines with arcs and holes of examples/ (where
push regions on arcs are solved in the chord frame), and random polygons
with a locating corner (tests/e2e/fixtures.py), whose goal regions come
and go as mu grows.
"""

import copy
import json
import math
import os
import random

import pytest

import fixtures as FX
from conftest import FIGURES, REPO

RANGE = (0.0, 1.5)
AWAY = 1e-6
BRACKET = 1e-4
EPS = 1e-9


def figure(key, n=1):
    FIGURES[key] = FIGURES.get(key, 0) + n


def example(name):
    with open(os.path.join(REPO, "examples", name)) as f:
        return json.load(f)


def at_mu(fixture, mu, ratio):
    f = copy.deepcopy(fixture)
    for fixel in f["fixels"]:
        fixel.pop("friction", None)
    f["friction"] = {"static": mu, "kinetic": ratio * mu}
    return f


def point_length(client, fixture, what, which, mu, ratio):
    f = at_mu(fixture, mu, ratio)
    if what == "push":
        return client.result("push.regions", {"fixture": f, "set": which})["total_length"]
    arcs = client.result("gravity.sweep", {"fixture": f, "set": which})["intervals_deg"]
    return sum(b - a for a, b in arcs)


def inside(mu, intervals):
    """'in', 'out', or None within AWAY of an end."""
    for lo, hi in intervals:
        if abs(mu - lo) <= AWAY or abs(mu - hi) <= AWAY:
            return None
    return "in" if any(lo < mu < hi for lo, hi in intervals) else "out"


def random_corner_fixtures(count, seed):
    rnd = random.Random(seed)
    return [FX.random_polygon(rnd, rnd.random() < 0.5, corner=True, name="corner-%d" % i)
            for i in range(count)]


FIXTURES = {
    "bracket": lambda: example("bracket.json"),
    "notched-plate": lambda: example("notched-plate.json"),
    "outline": lambda: example("outline.json"),
    "chamfered": FX.chamfered_plate,
}
for _i, _f in enumerate(random_corner_fixtures(6, seed=17)):
    FIXTURES["corner-%d" % _i] = (lambda f=_f: f)

CASES = [(name, what, which, ratio)
         for name in FIXTURES
         for what in ("push", "gravity")
         for which in ("goal", "strong", "both")
         for ratio in (1.0, 0.5)
         if not (ratio == 0.5 and which == "goal")]  # goal does not use mu_k


@pytest.mark.parametrize("name, what, which, ratio", CASES)
def test_sweep_against_point_answers_and_bisection(client, name, what, which, ratio):
    fixture = FIXTURES[name]()
    params = {"fixture": fixture, "range": list(RANGE), what: {"set": which}}
    if ratio != 1.0:
        params["kinetic_ratio"] = ratio
    ans = client.result("friction.sweep", params)
    intervals = ans["intervals"]
    assert ans["exact"] is True
    for lo, hi in intervals:
        assert RANGE[0] <= lo < hi <= RANGE[1], intervals
    for (_, hi), (lo, _) in zip(intervals, intervals[1:]):
        assert hi < lo, intervals

    # Non-empty exactly inside the intervals, at sampled mu.
    for i in range(120):
        mu = RANGE[0] + (RANGE[1] - RANGE[0]) * (i + 0.37) / 120
        w = inside(mu, intervals)
        if w is None:
            continue
        length = point_length(client, fixture, what, which, mu, ratio)
        assert (length > 0) == (w == "in"), (name, what, which, mu, length, intervals)
        figure("sweep samples against point answers")

    # Curve points are the point answers.
    ends = [e for iv in intervals for e in iv]
    scale = 360.0 if what == "gravity" else 1.0
    for mu, length in ans["curve"]:
        if any(abs(mu - e) <= AWAY for e in ends):
            continue
        expected = point_length(client, fixture, what, which, mu, ratio)
        assert abs(length - expected) <= EPS * max(scale, expected), (name, mu, length, expected)
        figure("sweep curve points against point answers")

    # Each interior end, found again by bisection on the point answers.
    for lo, hi in intervals:
        for end, nonempty_below in ((lo, False), (hi, True)):
            if end <= RANGE[0] or end >= RANGE[1]:
                continue
            a, b = max(RANGE[0], end - BRACKET), min(RANGE[1], end + BRACKET)
            below = point_length(client, fixture, what, which, a, ratio) > 0
            above = point_length(client, fixture, what, which, b, ratio) > 0
            assert below == nonempty_below and above != nonempty_below, (name, end, a, b)
            for _ in range(44):
                mid = (a + b) / 2
                if (point_length(client, fixture, what, which, mid, ratio) > 0) == below:
                    a = mid
                else:
                    b = mid
            found = (a + b) / 2
            # The point answers drop a region narrower than 1e-9 of its
            # range (a sliver of rounding, docs/PROTOCOL.md), so near a
            # region's end they call it empty a little early: the bisected
            # end lies on the empty side, by at most that sliver over the
            # rate at which the region shrinks; exact ends agree to 1e-9.
            toward_empty = (end - found) if nonempty_below else (found - end)
            assert abs(found - end) <= EPS or 0 <= toward_empty <= 1e-8, \
                (name, what, which, end, a, b)
            figure("sweep ends bisected")

    # The critical mu by the rule.
    if not intervals:
        assert ans["critical"] == RANGE[0]
    elif intervals[-1][1] < RANGE[1]:
        assert ans["critical"] == intervals[-1][1]
    else:
        assert ans["critical"] is None


def test_some_cases_change_inside_the_range(client):
    """The cases above are not all trivial: some interval ends lie strictly
    inside the range (else the bisection above would test nothing)."""
    interior = 0
    for name, what, which, ratio in CASES:
        params = {"fixture": FIXTURES[name](), "range": list(RANGE), what: {"set": which},
                  "kinetic_ratio": ratio}
        ans = client.result("friction.sweep", params)
        interior += sum(1 for iv in ans["intervals"] for e in iv if RANGE[0] < e < RANGE[1])
    assert interior >= 10, interior


def test_disc_critical_is_exactly_one(client):
    """The disc in the corner: the goal arc empties at mu = 1 exactly (the
    closed form of docs/MODEL.md section 7.1), to the last digits."""
    ans = client.result("friction.sweep", {"fixture": FX.disc_corner(0.5), "range": [0, 3],
                                           "push": {"set": "goal"}})
    assert abs(ans["critical"] - 1.0) <= 1e-12, ans["critical"]
    for mu, length in ans["curve"]:
        expected = max(0.0, math.pi / 2 - 2 * math.atan(mu))
        assert abs(length - expected) <= 1e-12, (mu, length, expected)


@pytest.mark.parametrize("what", ["push", "gravity"])
def test_region_vanishing_at_the_top_has_its_critical_mu_there(client, what):
    """The disc's goal arc vanishes at mu = 1 exactly: over [0, 1] the region
    is empty at the top, so the critical mu is 1 (the rule: the last
    interval's end when the region is empty at the top), not null."""
    ans = client.result("friction.sweep", {"fixture": FX.disc_corner(0.5), "range": [0, 1],
                                           what: {"set": "goal"}})
    assert ans["intervals"] and abs(ans["intervals"][-1][1] - 1) <= 1e-12, ans["intervals"]
    assert ans["critical"] is not None and abs(ans["critical"] - 1) <= 1e-12, ans["critical"]
    assert ans["curve"][-1] == [1, 0], ans["curve"][-1]
