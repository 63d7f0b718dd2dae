"""friction.sweep (sweeps over mu): answers checked against
closed forms and against the daemon's own point-friction answers.

The method sweeps one common coefficient mu over params.range: on every
fixel mu_s = mu and mu_k = kinetic_ratio * mu (default ratio 1); the
fixture's own friction is ignored.  Every reference value below is either a
closed form derived here or an answer of an existing method (wrench.classify,
push.regions, gravity.sweep) for the *point-friction* fixture at mu, i.e. the
fixture with "friction": {"static": mu, "kinetic": ratio * mu} and no
per-fixel friction.

Derivations.

1. The disc in the corner (docs/MODEL.md section 7.1, radius 1, centred at
   the origin, wall fixel at (-1, 0), floor fixel at (0, -1)).
   G_goal = {f_x < 0, f_y < 0, |f_y| > mu |f_x|, |f_x| > mu |f_y|}, any tau.
   * Goal push arc: a finger at boundary angle theta pushes with
     (-cos theta, -sin theta, 0), inside exactly when mu < tan theta < 1/mu:
     the arc (atan mu, 90 deg - atan mu), non-empty iff mu < 1.  Its length on
     the unit circle (push.regions reports lengths in the fixture's length
     units, radius times radians) is
         L(mu) = (90 - 2 atan(mu) [deg]) * pi / 180   for mu < 1,  0 for mu >= 1.
     So over range [0, 2] the region is non-empty on [0, 1) -- reported as
     the interval [0, 1] (ends compared to 1e-9, so open/closed does not
     matter) -- and the critical mu is exactly 1; mu = 1 is a breakpoint
     of the curve (where the length reaches 0 and stays there).
   * Over [0, 0.5] the region is non-empty at the top of the range:
     critical null.  Over [1.5, 2] it is empty throughout: critical = 1.5,
     the bottom of the range, and no intervals.
   * Goal gravity arc: gravity pulls along phi, w = (cos phi, sin phi, 0),
     which is G_goal's wedge: (180 + atan mu, 270 - atan mu) degrees; its
     length in DEGREES (the issue: "the same for the gravity arc, in
     degrees") is 90 - 2 atan(mu) [deg] for mu < 1, 0 beyond; critical 1.
   * Goal wrench intervals: a wrench (f_x, f_y, tau) with f_x < 0, f_y < 0 is
     inside exactly for mu < min(|f_y|/|f_x|, |f_x|/|f_y|); any other wrench
     never is.  Over [0, 2]: [[0, min(ratio, 2)]] or [].
   * Robust form of the same (docs/PROTOCOL.md, Friction intervals): with
     "static": [a, b] the goal arc is the arc at b.  G_goal's strings use only
     s, u and m, whose cones widen with mu, so G_goal shrinks as mu grows:
     every goal sweep (wrench, push, gravity) is one interval starting at the
     range's bottom, or none; and a wrench is robustly goal-inside on the box
     static [a, b] exactly when the sweep says it is inside at b.

2. General fixtures (rectangle_321, chamfered_plate, the disc): no closed
   form for G_strong, so
   * at 200 sampled mu in the range, a mu more than 1e-6 inside one of a
     wrench's intervals must be classified inside (tolerance 0: inside means
     margin > 0) at the point fixture; a mu more than 1e-6 away from every
     interval must not be;
   * each interval endpoint strictly inside the range is where classify's
     verdict changes: bracketing it by a small step on either side gives
     outside/inside in the right order, and bisection on classify's margin
     sign converges to the endpoint within 1e-9 (plus a rounding slack of
     1e-9);
   * push and gravity curves: at each curve point (mu, length), the length
     equals push.regions' total_length (gravity.sweep's total arc in degrees)
     for the point fixture at mu; at sampled mu the region is non-empty
     exactly inside the reported intervals.
   * robust: an interval box static [a, b] (kinetic [ratio a, ratio b]) for
     which classify says robustly inside must lie inside a sweep interval:
     the union over the box contains the union over its diagonal (common mu),
     so robust-inside implies inside at every common mu in [a, b].  Checked
     against a dense sample of the box's diagonal too.

3. The critical mu, by the issue's rule: the upper end of the last interval
   when that end lies below the top of the range; null when the region is
   non-empty at the top; the bottom of the range when empty throughout.
   Every push/gravity answer is checked against that rule applied to its own
   intervals (and to the closed forms where there are any).

Assumptions where the issue is ambiguous (see the report):
 * intervals are [lo, hi] with lo < hi, sorted, disjoint, inside the range;
   open or closed ends are not tested (1e-9 tolerance);
 * curve: [[mu, length], ...] strictly increasing in mu, from the range's
   bottom to its top, containing every interval endpoint, with no gap wider
   than a tenth of the range (enough for a plot); lengths compared to 1e-9
   (degrees for gravity) where exact;
 * the curve at a breakpoint is compared only where the closed form is
   continuous (the disc), otherwise curve points within 1e-6 of an interval
   end are not compared with the point answer;
 * errors are -32602 with data.field naming the field; for a range whose
   lower end is negative either params.range or params.range[0] is
   accepted; for both/none of "wrenches"/"push"/"gravity" the field is
   "params" or one of those names.
"""

import copy
import math
import random

import pytest

import fixtures as FX
import helpers as H
import model as M
from conftest import FIGURES

EPS = 1e-9          # the issue's tolerance on endpoints
SLACK = 2e-9        # bisection result vs endpoint
AWAY = 1e-6         # samples this far from an end are decided
N_SAMPLES = 200


def figure(key, n=1):
    FIGURES[key] = FIGURES.get(key, 0) + n


# ---- helpers -----------------------------------------------------------------

def point_fixture(fixture, mu, ratio=1.0):
    """The fixture at the common coefficient mu: per-fixel friction removed,
    mu_s = mu, mu_k = ratio * mu."""
    f = copy.deepcopy(fixture)
    for fx in f["fixels"]:
        fx.pop("friction", None)
    f["friction"] = {"static": mu, "kinetic": ratio * mu}
    return f


def sweep(client, fixture, rng=(0.0, 2.0), **params):
    p = {"fixture": fixture, "range": list(rng)}
    p.update(params)
    return client.result("friction.sweep", p)


def classify_at(client, fixture, mu, wrenches, sets=("goal", "strong"), ratio=1.0):
    return client.result("wrench.classify", {
        "fixture": point_fixture(fixture, mu, ratio), "wrenches": [list(w) for w in wrenches],
        "sets": list(sets), "tolerance": 0})["results"]


def check_intervals(intervals, rng):
    assert isinstance(intervals, list), intervals
    last = None
    for iv in intervals:
        assert isinstance(iv, list) and len(iv) == 2, intervals
        lo, hi = iv
        assert all(isinstance(x, (int, float)) and not isinstance(x, bool) for x in iv), iv
        assert lo < hi, intervals
        assert rng[0] - EPS <= lo and hi <= rng[1] + EPS, (intervals, rng)
        if last is not None:
            # two intervals may meet at a single mu where the margin only touches 0
            assert lo >= last, ("intervals overlap or are out of order", intervals)
        last = hi


def expected_critical(intervals, rng):
    if not intervals:
        return rng[0]
    top = intervals[-1][1]
    if top >= rng[1] - EPS:
        return None
    return top


def check_critical(answer, rng):
    exp = expected_critical(answer["intervals"], rng)
    got = answer["critical"]
    if exp is None:
        assert got is None, answer
    else:
        assert isinstance(got, (int, float)) and abs(got - exp) <= EPS, (answer, exp)


def same_intervals(a, b, tol=EPS):
    return len(a) == len(b) and all(abs(x[0] - y[0]) <= tol and abs(x[1] - y[1]) <= tol
                                    for x, y in zip(a, b))


def where(mu, intervals):
    """'in' when mu is more than AWAY inside an interval, 'out' when more than
    AWAY from every interval, None near an end."""
    for lo, hi in intervals:
        if lo - AWAY <= mu <= hi + AWAY:
            return "in" if lo + AWAY < mu < hi - AWAY else None
    return "out"


def sample_mus(rng, n=N_SAMPLES, seed=0):
    rnd = random.Random(seed)
    lo, hi = rng
    pts = [lo + (hi - lo) * (i + 0.5) / n for i in range(n)]
    return [min(hi, max(lo, m + rnd.uniform(-0.2, 0.2) * (hi - lo) / n)) for m in pts]


def check_curve(answer, rng):
    """The curve is sorted, spans the range, includes every interval end,
    is dense enough for a plot, has non-negative lengths, and is 0 exactly
    where no interval covers it (away from the ends)."""
    curve = answer["curve"]
    assert isinstance(curve, list) and len(curve) >= 2, answer
    mus = []
    for pt in curve:
        assert isinstance(pt, list) and len(pt) == 2, curve
        assert pt[1] >= -EPS, ("negative length", pt)
        mus.append(pt[0])
    assert all(a < b for a, b in zip(mus, mus[1:])), ("curve not increasing in mu", mus)
    assert abs(mus[0] - rng[0]) <= EPS and abs(mus[-1] - rng[1]) <= EPS, (mus[0], mus[-1], rng)
    width = rng[1] - rng[0]
    gaps = [b - a for a, b in zip(mus, mus[1:])]
    assert max(gaps) <= width / 10 + EPS, ("curve too sparse for a plot", max(gaps))
    for lo, hi in answer["intervals"]:
        for e in (lo, hi):
            assert any(abs(m - e) <= EPS for m in mus), ("breakpoint %r not on the curve" % e, mus)
    for mu, length in curve:
        w = where(mu, answer["intervals"])
        if w == "out":
            assert abs(length) <= EPS, ("length outside the intervals", mu, length, answer)
        elif w == "in":
            assert length > 0, ("no length inside an interval", mu, length, answer)
    return curve


def disc_goal_push_length(mu):
    return max(0.0, 90.0 - 2.0 * math.degrees(math.atan(mu))) * math.pi / 180.0


def disc_goal_arc_deg(mu):
    return max(0.0, 90.0 - 2.0 * math.degrees(math.atan(mu)))


def arc_total(intervals_deg):
    return sum(b - a for a, b in intervals_deg)


def inward_pushes(fixture, rnd, n):
    """Wrenches pushing into the fixels (so that some are inside G_goal)."""
    mdl = M.Model(point_fixture(fixture, 0.3))
    out = []
    for _ in range(n):
        w = [0.0, 0.0, 0.0]
        for fx in mdl.fixels:
            lam = rnd.uniform(0.1, 1.0)
            w = [w[i] - lam * fx.Wn[i] for i in range(3)]
        out.append([round(x + rnd.uniform(-0.2, 0.2), 6) for x in w])
    return out


def sweep_wrenches(fixture, seed, n_random=8, n_push=8):
    rnd = random.Random(seed)
    ws = [list(g) for g in H.random_wrenches(seed, n_random)]
    return ws + inward_pushes(fixture, rnd, n_push)


# ---- 1. the disc in the corner: closed forms ------------------------------------

def test_disc_corner_push_goal_closed_form(client):
    rng = (0.0, 2.0)
    ans = sweep(client, FX.disc_corner(0.5), rng, push={"set": "goal"})
    assert set(ans) == {"intervals", "critical", "curve", "exact", "resolution"}, ans
    assert ans["exact"] is True and ans["resolution"] == 0, ans
    check_intervals(ans["intervals"], rng)
    assert same_intervals(ans["intervals"], [[0.0, 1.0]]), ans["intervals"]
    assert ans["critical"] is not None and abs(ans["critical"] - 1.0) <= EPS, ans
    check_critical(ans, rng)
    curve = check_curve(ans, rng)
    assert any(abs(m - 1.0) <= EPS for m, _ in curve), curve
    for mu, length in curve:
        assert abs(length - disc_goal_push_length(mu)) <= EPS, (mu, length,
                                                                disc_goal_push_length(mu))
    figure("sweep curve points checked", len(curve))


def test_disc_corner_push_goal_default_set_and_ratio(client):
    """push {} (no set) is the goal set, as in push.regions; kinetic_ratio
    changes nothing for goal (its strings use only static friction)."""
    rng = (0.0, 2.0)
    base = sweep(client, FX.disc_corner(0.5), rng, push={"set": "goal"})
    plain = sweep(client, FX.disc_corner(0.5), rng, push={})
    half = sweep(client, FX.disc_corner(0.5), rng, push={"set": "goal"}, kinetic_ratio=0.5)
    for other in (plain, half):
        assert same_intervals(other["intervals"], base["intervals"]), (other, base)
        assert abs(other["critical"] - base["critical"]) <= EPS, (other, base)


@pytest.mark.parametrize("rng, intervals, critical", [
    ((0.0, 0.5), [[0.0, 0.5]], None),
    ((1.5, 2.0), [], 1.5),
    ((0.25, 1.75), [[0.25, 1.0]], 1.0),
    ((0.0, 0.999), [[0.0, 0.999]], None),
])
def test_disc_corner_push_goal_critical_by_range(client, rng, intervals, critical):
    ans = sweep(client, FX.disc_corner(0.5), rng, push={"set": "goal"})
    check_intervals(ans["intervals"], rng)
    assert same_intervals(ans["intervals"], intervals), (ans["intervals"], intervals)
    if critical is None:
        assert ans["critical"] is None, ans
    else:
        assert ans["critical"] is not None and abs(ans["critical"] - critical) <= EPS, ans
    check_critical(ans, rng)
    curve = check_curve(ans, rng)
    for mu, length in curve:
        assert abs(length - disc_goal_push_length(mu)) <= EPS, (mu, length)


def test_disc_corner_gravity_goal_closed_form(client):
    rng = (0.0, 2.0)
    ans = sweep(client, FX.disc_corner(0.5), rng, gravity={"set": "goal"})
    assert set(ans) == {"intervals", "critical", "curve", "exact", "resolution"}, ans
    assert ans["exact"] is True and ans["resolution"] == 0, ans
    check_intervals(ans["intervals"], rng)
    assert same_intervals(ans["intervals"], [[0.0, 1.0]]), ans["intervals"]
    assert ans["critical"] is not None and abs(ans["critical"] - 1.0) <= EPS, ans
    curve = check_curve(ans, rng)
    for mu, length in curve:
        assert abs(length - disc_goal_arc_deg(mu)) <= EPS, ("gravity length in degrees",
                                                            mu, length, disc_goal_arc_deg(mu))


@pytest.mark.parametrize("what", ["push", "gravity"])
@pytest.mark.parametrize("which", ["goal", "strong", "both"])
def test_disc_corner_curves_against_point_answers(client, what, which):
    """Every curve point against push.regions / gravity.sweep for the point
    fixture at that mu; sampled mu non-empty exactly inside the intervals."""
    rng = (0.0, 2.0)
    f = FX.disc_corner(0.5)
    ans = sweep(client, f, rng, **{what: {"set": which}})
    check_intervals(ans["intervals"], rng)
    check_critical(ans, rng)
    curve = check_curve(ans, rng)

    def total(mu):
        p = point_fixture(f, mu)
        if what == "push":
            return client.result("push.regions", {"fixture": p, "set": which})["total_length"]
        return arc_total(client.result("gravity.sweep", {"fixture": p, "set": which})
                         ["intervals_deg"])

    for mu, length in curve:
        if where(mu, ans["intervals"]) is None and not (which == "goal"):
            continue  # a possible jump at a breakpoint
        assert abs(length - total(mu)) <= EPS, (what, which, mu, length, total(mu))
        figure("sweep curve points checked")
    for mu in sample_mus(rng, 40, seed=3):
        w = where(mu, ans["intervals"])
        if w is None:
            continue
        assert (total(mu) > 0) == (w == "in"), (what, which, mu, ans["intervals"])


# ---- 2. wrench sweeps -----------------------------------------------------------

def check_wrench_answer(ans, n, sets, rng):
    assert set(ans) == {"results"}, ans
    assert len(ans["results"]) == n, ans
    for r in ans["results"]:
        assert set(r) == set(sets), (r, sets)
        for s in sets:
            check_intervals(r[s], rng)


def test_disc_corner_goal_wrench_intervals_closed_form(client):
    rng = (0.0, 2.0)
    rnd = random.Random(17)
    ws = [[-1, -1, 0], [-1, -0.2, 0], [-1, -1, -100], [1, -1, 0], [-0.3, -2.0, 0.5]]
    ws += [[round(rnd.uniform(-1, 0.3), 6), round(rnd.uniform(-1, 0.3), 6),
            round(rnd.uniform(-1, 1), 6)] for _ in range(25)]
    ans = sweep(client, FX.disc_corner(0.5), rng, wrenches=ws, sets=["goal"])
    check_wrench_answer(ans, len(ws), ["goal"], rng)
    for g, r in zip(ws, ans["results"]):
        fx, fy = g[0], g[1]
        if fx < 0 and fy < 0:
            c = min(abs(fy) / abs(fx), abs(fx) / abs(fy))
            exp = [[0.0, min(c, 2.0)]]
        else:
            exp = []
        assert same_intervals(r["goal"], exp), (g, r["goal"], exp)
    # (-1, -1, 0): goal inside up to mu = 1 exactly
    assert same_intervals(ans["results"][0]["goal"], [[0.0, 1.0]]), ans["results"][0]


def test_default_sets_are_goal_and_strong(client):
    rng = (0.0, 2.0)
    ws = [[-1, -1, 0], [-1, -0.2, 0]]
    ans = sweep(client, FX.disc_corner(0.5), rng, wrenches=ws)
    check_wrench_answer(ans, 2, ["goal", "strong"], rng)
    both = sweep(client, FX.disc_corner(0.5), rng, wrenches=ws, sets=["both"])
    check_wrench_answer(both, 2, ["both"], rng)


def sampled_check(client, fixture, ws, ans, sets, rng, ratio=1.0, seed=0):
    """Against classify at N_SAMPLES common mu."""
    decided = 0
    for mu in sample_mus(rng, N_SAMPLES, seed):
        res = classify_at(client, fixture, mu, ws, sets, ratio)
        for j, g in enumerate(ws):
            for s in sets:
                w = where(mu, ans["results"][j][s])
                if w is None:
                    continue
                v = res[j][s]
                assert v["inside"] == (w == "in"), (fixture["name"], g, s, mu, ratio,
                                                    ans["results"][j][s], v["margin"])
                decided += 1
    figure("sweep wrench samples decided", decided)
    return decided


def margin_at(client, fixture, mu, g, s, ratio):
    return classify_at(client, fixture, mu, [g], (s,), ratio)[0][s]["margin"]


def bisect_check(client, fixture, ws, ans, sets, rng, ratio=1.0, limit=30):
    """Interior endpoints are where classify's margin changes sign."""
    done = 0
    for j, g in enumerate(ws):
        for s in sets:
            ivs = ans["results"][j][s]
            ends = [(e, k) for iv in ivs for k, e in enumerate(iv)]
            all_ends = sorted(e for e, _ in ends)
            for e, k in ends:
                if e <= rng[0] + AWAY or e >= rng[1] - AWAY or done >= limit:
                    continue
                near = [abs(x - e) for x in all_ends if x != e]
                h = min([1e-4] + [d / 3 for d in near])
                a, b = e - h, e + h
                ma = margin_at(client, fixture, a, g, s, ratio)
                mb = margin_at(client, fixture, b, g, s, ratio)
                # a lower end: outside below, inside above; an upper end the reverse
                if k == 0:
                    assert ma <= 0 < mb, (fixture["name"], g, s, e, ma, mb)
                else:
                    assert mb <= 0 < ma, (fixture["name"], g, s, e, ma, mb)
                inside_low = ma > 0
                while b - a > 1e-10:
                    m = (a + b) / 2
                    if (margin_at(client, fixture, m, g, s, ratio) > 0) == inside_low:
                        a = m
                    else:
                        b = m
                assert abs((a + b) / 2 - e) <= SLACK, (fixture["name"], g, s, e, (a + b) / 2)
                done += 1
    figure("sweep endpoints bisected", done)
    return done


WRENCH_FIXTURES = {
    "disc_corner": lambda: FX.disc_corner(0.5),
    "rectangle_321": lambda: FX.rectangle_321(0.3),
    "chamfered_plate": lambda: FX.chamfered_plate(0.05),
}


@pytest.mark.parametrize("name", sorted(WRENCH_FIXTURES))
def test_wrench_intervals_agree_with_classify(client, name):
    fixture = WRENCH_FIXTURES[name]()
    rng = (0.0, 2.0)
    ws = sweep_wrenches(fixture, 100 + len(name))
    sets = ("goal", "strong")
    ans = sweep(client, fixture, rng, wrenches=ws, sets=list(sets))
    check_wrench_answer(ans, len(ws), sets, rng)
    assert sampled_check(client, fixture, ws, ans, sets, rng, seed=len(name)) > 0
    # G_goal shrinks as mu grows: at most one goal interval, from the bottom
    for r in ans["results"]:
        assert len(r["goal"]) <= 1, r
        if r["goal"]:
            assert abs(r["goal"][0][0] - rng[0]) <= EPS, r
    # some answers must have interior endpoints for the bisection to mean much
    assert bisect_check(client, fixture, ws, ans, sets, rng) > 0, ans


def test_sub_range_is_the_restriction(client):
    """Sweeping [0.3, 1.2] gives the [0, 2] intervals cut to [0.3, 1.2]."""
    fixture = FX.rectangle_321(0.3)
    ws = sweep_wrenches(fixture, 7)
    full = sweep(client, fixture, (0.0, 2.0), wrenches=ws)
    part = sweep(client, fixture, (0.3, 1.2), wrenches=ws)
    check_wrench_answer(part, len(ws), ("goal", "strong"), (0.3, 1.2))
    for rf, rp in zip(full["results"], part["results"]):
        for s in ("goal", "strong"):
            cut = [[max(lo, 0.3), min(hi, 1.2)] for lo, hi in rf[s]
                   if min(hi, 1.2) - max(lo, 0.3) > 2 * EPS]
            assert same_intervals(rp[s], cut, 2 * EPS), (s, rf[s], rp[s], cut)


@pytest.mark.parametrize("name", ["disc_corner", "rectangle_321"])
def test_kinetic_ratio_changes_strong_as_classify_says(client, name):
    fixture = WRENCH_FIXTURES[name]()
    rng = (0.0, 2.0)
    ws = sweep_wrenches(fixture, 300 + len(name), n_random=12, n_push=4)
    if name == "disc_corner":
        # the wall's force (1, -0.25) on the resting disc: the boundary of
        # "ls" at mu_k = 0.25 (test_friction_intervals), scaled variants
        for cn, ct in ((1.0, -0.3), (1.0, -0.6), (1.0, -0.9)):
            ws.append([-cn, -ct, 0.0])
    one = sweep(client, fixture, rng, wrenches=ws)
    half = sweep(client, fixture, rng, wrenches=ws, kinetic_ratio=0.5)
    check_wrench_answer(half, len(ws), ("goal", "strong"), rng)
    sampled_check(client, fixture, ws, half, ("goal", "strong"), rng, ratio=0.5, seed=9)
    # goal uses static friction only: unchanged
    for r1, r2 in zip(one["results"], half["results"]):
        assert same_intervals(r1["goal"], r2["goal"]), (r1, r2)
    # the ratio must matter somewhere (checked on classify, then on the sweep)
    differ_classify = False
    for mu in sample_mus(rng, 40, seed=11):
        a = classify_at(client, fixture, mu, ws, ("strong",), 1.0)
        b = classify_at(client, fixture, mu, ws, ("strong",), 0.5)
        if any(x["strong"]["inside"] != y["strong"]["inside"] for x, y in zip(a, b)):
            differ_classify = True
            break
    if differ_classify:
        assert any(not same_intervals(r1["strong"], r2["strong"])
                   for r1, r2 in zip(one["results"], half["results"])), (one, half)
    bisect_check(client, fixture, ws, half, ("strong",), rng, ratio=0.5, limit=10)


def test_robust_classify_against_the_sweep(client):
    """A box static [a, b], kinetic [a, b]: robustly inside implies inside at
    every common mu of [a, b] (the box contains its diagonal): [a, b] lies
    in one sweep interval.  For goal the robust answer is the one at b, so
    robust goal inside <=> the sweep is inside at b."""
    rnd = random.Random(23)
    for fixture in (FX.disc_corner(0.5), FX.chamfered_plate(0.05), FX.rectangle_321(0.3)):
        rng = (0.0, 2.0)
        ws = sweep_wrenches(fixture, 31, n_random=6, n_push=10)
        ans = sweep(client, fixture, rng, wrenches=ws)
        for _ in range(6):
            a, b = sorted(round(rnd.uniform(0, 1.5), 4) for _ in range(2))
            if b - a < 1e-3:
                continue
            f = copy.deepcopy(fixture)
            for fx in f["fixels"]:
                fx.pop("friction", None)
            f["friction"] = {"static": [a, b]}
            robust = client.result("wrench.classify", {
                "fixture": f, "wrenches": ws, "sets": ["goal", "strong"],
                "tolerance": 0})["results"]
            # a dense sample of the diagonal of the box
            diag = [a + (b - a) * i / 24 for i in range(25)]
            sampled = [classify_at(client, fixture, mu, ws) for mu in diag]
            for j, g in enumerate(ws):
                for s in ("goal", "strong"):
                    ivs = ans["results"][j][s]
                    if robust[j][s]["inside"] and robust[j][s]["margin"] > 1e-7:
                        assert all(x[j][s]["inside"] for x in sampled), (g, s, a, b)
                        assert any(lo <= a + EPS and b - EPS <= hi for lo, hi in ivs), (
                            fixture["name"], g, s, a, b, ivs, robust[j][s])
                        figure("sweep robust insides compared")
                    if s == "goal":
                        w = where(b, ivs)
                        if w is not None:
                            assert robust[j][s]["inside"] == (w == "in"), (g, a, b, ivs)


# ---- 3. push sweeps on polygons, finger options ------------------------------------

def push_total(client, fixture, mu, which, **extra):
    p = {"fixture": point_fixture(fixture, mu), "set": which}
    p.update(extra)
    return client.result("push.regions", p)["total_length"]


@pytest.mark.parametrize("name, which, extra, tol", [
    ("chamfered_plate", "goal", {}, EPS),
    ("chamfered_plate", "strong", {}, EPS),
    ("rectangle_321", "strong", {}, EPS),
    ("chamfered_plate", "both", {"finger_radius": 0.3}, EPS),
    ("chamfered_plate", "goal", {"finger_friction": 0.1}, 1e-3),
])
def test_polygon_push_sweep_against_push_regions(client, name, which, extra, tol):
    fixture = WRENCH_FIXTURES[name]()
    rng = (0.0, 2.0)
    params = {"set": which}
    params.update(extra)
    ans = sweep(client, fixture, rng, push=params)
    check_intervals(ans["intervals"], rng)
    check_critical(ans, rng)
    curve = check_curve(ans, rng)
    for mu, length in curve:
        if where(mu, ans["intervals"]) is None and ans["intervals"]:
            # a possible jump at a breakpoint
            if any(abs(mu - e) <= AWAY for iv in ans["intervals"] for e in iv):
                continue
        exp = push_total(client, fixture, mu, which, **extra)
        assert abs(length - exp) <= tol, (name, which, extra, mu, length, exp)
    for mu in sample_mus(rng, 30, seed=5):
        w = where(mu, ans["intervals"])
        if w is None:
            continue
        exp = push_total(client, fixture, mu, which, **extra)
        assert (exp > 0) == (w == "in"), (name, which, mu, exp, ans["intervals"])
    if which == "goal":
        assert len(ans["intervals"]) <= 1, ans


def test_finger_radius_is_passed_through(client):
    """On the chamfered plate a finger of radius 0.3 is compared with
    push.regions at the same radius, curve point by curve point; where
    push.regions says the radius changes the length, the sweep must too."""
    fixture = FX.chamfered_plate(0.05)
    rng = (0.0, 1.0)
    plain = sweep(client, fixture, rng, push={"set": "strong"})
    fat = sweep(client, fixture, rng, push={"set": "strong", "finger_radius": 0.3})
    check_intervals(fat["intervals"], rng)
    check_curve(fat, rng)
    ends = [e for iv in fat["intervals"] + plain["intervals"] for e in iv]
    for mu, length in fat["curve"]:
        if any(abs(mu - e) <= AWAY for e in ends):
            continue
        exp = push_total(client, fixture, mu, "strong", finger_radius=0.3)
        assert abs(length - exp) <= EPS, (mu, length, exp)
        thin = push_total(client, fixture, mu, "strong")
        at = [l for m, l in plain["curve"] if abs(m - mu) <= EPS]
        if at and abs(thin - exp) > 1e-6:
            assert abs(at[0] - length) > 1e-6, (mu, at, length)


# ---- 4. the fixture's own friction is ignored ---------------------------------------

def test_own_friction_is_ignored(client):
    base = FX.rectangle_321(0.3)
    other = copy.deepcopy(base)
    other["friction"] = {"static": [0.1, 0.7], "kinetic": [0.05, 0.2]}
    other["fixels"][1]["friction"] = {"static": 0.9, "kinetic": 0.1}
    ws = sweep_wrenches(base, 41)
    for params in ({"wrenches": ws}, {"push": {"set": "both"}}, {"gravity": {"set": "strong"}}):
        a = sweep(client, base, (0.0, 2.0), **params)
        b = sweep(client, other, (0.0, 2.0), **params)
        assert a == b, params
    disc = FX.disc_corner(0.5)
    slick = FX.disc_corner(0.0)
    rough = FX.disc_corner(0.5)
    rough["friction"] = {"static": [0.2, 3.0]}
    for params in ({"push": {"set": "goal"}}, {"wrenches": [[-1, -1, 0], [-1, -0.2, 0.3]]}):
        a = sweep(client, disc, (0.0, 2.0), **params)
        assert sweep(client, slick, (0.0, 2.0), **params) == a
        assert sweep(client, rough, (0.0, 2.0), **params) == a


def test_stored_fixture_by_id(client):
    f = FX.disc_corner(0.7)
    fid = client.result("fixture.put", {"fixture": f})["id"]
    a = sweep(client, fid, (0.0, 2.0), push={"set": "goal"})
    b = sweep(client, f, (0.0, 2.0), push={"set": "goal"})
    assert a == b
    assert same_intervals(a["intervals"], [[0.0, 1.0]]), a


# ---- 5. refusals ---------------------------------------------------------------

def sweep_error(client, params):
    e = client.error("friction.sweep", params)
    assert e["code"] == -32602, e
    assert isinstance(e.get("data"), dict) and "field" in e["data"], e
    return e["data"]["field"]


DISC = FX.disc_corner(0.5)
GOOD_W = [[-1, -1, 0]]


@pytest.mark.parametrize("params, fields", [
    ({"range": [1.0, 0.5], "wrenches": GOOD_W}, {"params.range"}),
    ({"range": [0.5, 0.5], "wrenches": GOOD_W}, {"params.range"}),
    ({"range": [-0.1, 1.0], "wrenches": GOOD_W}, {"params.range", "params.range[0]"}),
    ({"range": [-1.0, -0.5], "push": {"set": "goal"}}, {"params.range", "params.range[0]"}),
    ({"range": [0.0], "wrenches": GOOD_W}, {"params.range"}),
    ({"range": [0.0, 1.0, 2.0], "wrenches": GOOD_W}, {"params.range"}),
    ({"range": [0.0, "1"], "wrenches": GOOD_W}, {"params.range[1]"}),
    ({"range": "0..2", "wrenches": GOOD_W}, {"params.range"}),
    ({"range": [0, 2], "wrenches": GOOD_W, "kinetic_ratio": 0}, {"params.kinetic_ratio"}),
    ({"range": [0, 2], "wrenches": GOOD_W, "kinetic_ratio": 1.5}, {"params.kinetic_ratio"}),
    ({"range": [0, 2], "wrenches": GOOD_W, "kinetic_ratio": -0.5}, {"params.kinetic_ratio"}),
    ({"range": [0, 2], "wrenches": GOOD_W, "kinetic_ratio": "half"}, {"params.kinetic_ratio"}),
    ({"range": [0, 2], "push": {"set": "goal"}, "wrenches": GOOD_W},
     {"params", "params.push", "params.wrenches"}),
    ({"range": [0, 2], "push": {"set": "goal"}, "gravity": {"set": "goal"}},
     {"params", "params.push", "params.gravity"}),
    ({"range": [0, 2]}, {"params", "params.wrenches", "params.push", "params.gravity"}),
    ({"range": [0, 2], "push": {"set": "sideways"}}, {"params.push.set"}),
    ({"range": [0, 2], "gravity": {"set": "sideways"}}, {"params.gravity.set"}),
    ({"range": [0, 2], "wrenches": GOOD_W, "sets": ["goal", "sideways"]}, {"params.sets[1]"}),
    ({"range": [0, 2], "wrenches": GOOD_W, "sets": []}, {"params.sets"}),
    ({"range": [0, 2], "wrenches": [[1, 2]]}, {"params.wrenches[0]"}),
    ({"range": [0, 2], "push": {"set": "goal", "finger_radius": -1}},
     {"params.push.finger_radius"}),
    ({"range": [0, 2], "push": {"set": "goal", "finger_friction": -0.1}},
     {"params.push.finger_friction"}),
    ({"range": [0, 2], "wrenches": GOOD_W, "colour": "red"}, {"params.colour"}),
])
def test_refusals_name_the_field(client, params, fields):
    p = {"fixture": DISC}
    p.update(params)
    field = sweep_error(client, p)
    assert field in fields, (field, fields, params)


def test_missing_fixture_is_refused(client):
    field = sweep_error(client, {"range": [0, 2], "wrenches": GOOD_W})
    assert field == "params.fixture", field
    e = client.error("friction.sweep", {"fixture": "0" * 64, "range": [0, 2],
                                        "wrenches": GOOD_W})
    assert e["code"] in (-32001, -32602), e


def test_daemon_still_answers_after_refusals(client):
    sweep_error(client, {"fixture": DISC, "range": [2, 1], "wrenches": GOOD_W})
    ans = sweep(client, DISC, (0.0, 2.0), wrenches=GOOD_W, sets=["goal"])
    assert same_intervals(ans["results"][0]["goal"], [[0.0, 1.0]]), ans
