"""friction.sweep's deadline_s: a sweep stopped by its deadline answers what
it has decided, "partial": true and the mu it reached ("stopped_at"), and
that is what the whole sweep answers below that mu (docs/PROTOCOL.md,
friction.sweep)."""
import math
import random
import time

from conftest import SLOW
import fixtures as FX


def octagon_8():
    """An elongated octagon with a fixel at the middle of each side: a push
    sweep of 8 fixels (tens of seconds of a core, minutes under ASan)."""
    corners = [[2 * math.cos(2 * math.pi * i / 8 + 0.3), math.sin(2 * math.pi * i / 8 + 0.3)]
               for i in range(8)]
    middles = [[(corners[i][0] + corners[(i + 1) % 8][0]) / 2,
                (corners[i][1] + corners[(i + 1) % 8][1]) / 2] for i in range(8)]
    return {"name": "octagon-8", "body": {"mass": 1, "shape": {"type": "polygon",
                                                              "vertices": corners}},
            "friction": {"static": 0.3}, "fixels": [{"at": m} for m in middles]}


DISC_8 = FX.disc_at_angles([180 + 11 * i for i in range(8)], mu=0.3)
# Twelve wrenches; one of them is strong from mu = 0.22 up.
_rnd = random.Random(3)
WRENCHES = [[_rnd.uniform(-1, 1), _rnd.uniform(-1, 1), _rnd.uniform(-0.3, 0.3)] for _ in range(12)]


def below(intervals, mu):
    """The intervals cut at mu: what a sweep stopped at mu must answer."""
    return [[lo, min(hi, mu)] for lo, hi in intervals if lo < mu]


def same_intervals(a, b):
    return len(a) == len(b) and all(abs(x[0] - y[0]) <= 1e-12 and abs(x[1] - y[1]) <= 1e-12
                                    for x, y in zip(a, b))


def test_a_k8_push_sweep_with_a_deadline_answers_in_time(harness):
    """The 8-fixel push sweep of G_strong (which decides every piece: it has
    no monotone shortcut), asked whole and then with deadline_s a quarter of
    its whole time: answered within the deadline and a scheduling margin,
    partial, intervals and curve below the point it reached.  Without
    deadline_s no answer is partial; a bad deadline_s is refused at the
    field."""
    d = harness.start("--threads", "1")
    c = d.client(timeout=120 * SLOW)
    params = {"fixture": octagon_8(), "range": [0, 1], "push": {"set": "strong"}}
    start = time.monotonic()
    c.result("friction.sweep", params)
    deadline = max((time.monotonic() - start) / 4, 1e-3)
    start = time.monotonic()
    r = c.result("friction.sweep", dict(params, deadline_s=deadline))
    took = time.monotonic() - start
    assert took < deadline + 8 * SLOW, took
    assert r["partial"] is True and 0 <= r["stopped_at"] < 1, r
    assert all(hi <= r["stopped_at"] for lo, hi in r["intervals"]), r
    assert all(mu <= r["stopped_at"] for mu, _ in r["curve"]), r
    assert r["critical"] is None
    whole = c.result("friction.sweep", {"fixture": DISC_8, "range": [0, 1],
                                        "push": {"set": "strong"}})
    assert "partial" not in whole and "stopped_at" not in whole
    for bad in (0, -1, "1", 2e9):
        e = c.error("friction.sweep", {"fixture": DISC_8, "push": {}, "deadline_s": bad})
        assert e["data"]["field"] == "params.deadline_s", (bad, e)


def stopped_runs(c, params, whole_seconds):
    """The sweep asked again with deadlines of a fifth to four fifths of its
    whole time: the partial answers (the machine decides where each stops)."""
    found = []
    for fraction in (0.2, 0.4, 0.6, 0.8):
        r = c.result("friction.sweep", dict(params, deadline_s=max(whole_seconds * fraction,
                                                                   1e-3)))
        if r.get("partial"):
            found.append(r)
    return found


def timed(c, params):
    start = time.monotonic()
    r = c.result("friction.sweep", params)
    return r, time.monotonic() - start


def test_partial_sweeps_agree_with_the_whole_below_where_they_stopped(harness):
    """Wrench, push and force sweeps stopped at a fifth .. four fifths of
    their whole time: each partial answer is the whole answer cut at
    stopped_at -- wrenches answered whole before the last, the last one's
    sets before its last, that set's intervals cut; a push sweep's intervals
    cut and its curve the whole curve's points up to stopped_at; a force
    sweep's curve the whole curve's first samples, its intervals cut."""
    d = harness.start("--threads", "1")
    c = d.client(timeout=300 * SLOW)
    reached_inside = 0

    wrenches = {"fixture": DISC_8, "range": [0, 1.5], "wrenches": WRENCHES,
                "sets": ["goal", "strong"]}
    whole, seconds = timed(c, wrenches)
    assert any(x["strong"] and x["strong"][0][0] > 0 for x in whole["results"]), whole
    for r in stopped_runs(c, wrenches, seconds):
        mu, results = r["stopped_at"], r["results"]
        assert 1 <= len(results) <= len(WRENCHES)
        assert results[:-1] == whole["results"][:len(results) - 1]
        last, full = results[-1], whole["results"][len(results) - 1]
        sets = list(last)
        assert sets == ["goal", "strong"][:len(sets)], last
        for s in sets[:-1]:
            assert last[s] == full[s]
        assert same_intervals(last[sets[-1]], below(full[sets[-1]], mu)), (mu, last, full)
        reached_inside += 0 < mu < 1.5

    push = {"fixture": DISC_8, "range": [0, 1], "push": {"set": "strong"}}
    whole, seconds = timed(c, push)
    for r in stopped_runs(c, push, seconds):
        mu = r["stopped_at"]
        assert same_intervals(r["intervals"], below(whole["intervals"], mu)), (mu, r, whole)
        assert r["curve"] == [p for p in whole["curve"] if p[0] <= mu][:len(r["curve"])]
        assert r["curve"] == whole["curve"][:len(r["curve"])]
        assert r["critical"] is None and r["exact"] is True
        reached_inside += 0 < mu < 1

    force = {"fixture": FX.chamfered_plate(), "range": [0.05, 1],
             "force": {"set": "both"}, "cases": [{"loads": [{"wrench": [0, -1, 0]}]}]}
    whole, seconds = timed(c, force)
    for r in stopped_runs(c, force, seconds):
        n = len(r["curve"])
        assert 1 <= n < len(whole["curve"])
        assert r["curve"] == whole["curve"][:n]
        assert r["stopped_at"] == r["curve"][-1][0]
        # The push alone's intervals, known over the whole range, cut at
        # stopped_at as every partial answer's are.
        mu = r["stopped_at"]
        assert same_intervals(r["intervals"], below(whole["intervals"], mu)), (mu, r, whole)
        reached_inside += 1
    # The deadlines fell inside the work, not only before its first decision.
    assert reached_inside >= 3, reached_inside


def ask(c, method, params):
    """The result, waiting as long as a whole long request takes."""
    c.send(c.request(method, params))
    answer = c.read_json(timeout=600 * SLOW)
    assert "result" in answer, answer
    return answer["result"]


def test_push_force_with_a_deadline_answers_the_samples_so_far(harness):
    """push.force of the 8-fixel octagon at 4096 samples a segment under ten
    cases takes minutes whole; with deadline_s 1 it answers within seconds,
    "partial" (its least null when its search had not ended, its segments
    the first ones sampled, the last cut short).  Each sample is exact, so
    those of a partial answer at 256 samples equal the whole answer's at
    the same points, and its least is the whole answer's."""
    d = harness.start("--threads", "1")
    c = d.client(timeout=600 * SLOW)
    cases = [{"loads": [{"wrench": [0.01 * i, -1, 0.001 * i]}]} for i in range(10)]
    # Stored first: its cones are made once, before the deadlines run.
    octagon = c.result("fixture.put", {"fixture": octagon_8()})["id"]
    start = time.monotonic()
    r = c.result("push.force", {"fixture": octagon, "cases": cases, "samples": 4096,
                                "deadline_s": 1})
    assert time.monotonic() - start < 1 + 8 * SLOW
    assert r["partial"] is True
    assert sum(len(s["t"]) for s in r["segments"]) < 8 * 4096

    params = {"fixture": octagon, "cases": cases, "samples": 256}
    # The search for the least takes about what one sample a segment does;
    # the deadlines fall inside the sampling that follows it.
    start = time.monotonic()
    ask(c, "push.force", dict(params, samples=1))
    search = time.monotonic() - start
    start = time.monotonic()
    whole = ask(c, "push.force", params)
    seconds = time.monotonic() - start
    assert "partial" not in whole
    sampled = 0
    for fraction in (0.3, 0.5, 0.7, 0.9):
        deadline = search + (seconds - search) * fraction
        r = ask(c, "push.force", dict(params, deadline_s=max(deadline, 1e-3)))
        if not r.get("partial"):
            continue
        if r["least"] != whole["least"]:
            # Stopped in the search for the least: nothing sampled yet.
            assert r["least"] is None and r["segments"] == [], r
            continue
        assert all(len(s["t"]) == 256 for s in r["segments"][:-1])
        for got, full in zip(r["segments"], whole["segments"]):
            n = len(got["t"])
            assert got["t"] == full["t"][:n] and got["force"] == full["force"][:n]
            sampled += n
    assert sampled > 0
    e = c.error("push.force", dict(params, deadline_s=0))
    assert e["data"]["field"] == "params.deadline_s", e
