"""fixture.design: symmetric duplicates collapsed (docs/PROTOCOL.md,
fixture.design, "collapse_symmetric").

Every check here is against designs the test groups itself: the same
request with "collapse_symmetric": false lists every scored design (top
large enough), and the test maps each design's fixels by each symmetry of
the part, which it writes down itself (rotations about, and mirrors
through, the part's centre, from the part's closed form), to find the
designs that are one design seen turned.  The collapsed answer must hold
one design per group, the group's lowest candidate, with `copies` the
group's size; its `symmetries` must be the test's own group.

Parts: a rectangle (D2: 2 rotations, 2 mirrors), a square plate with four
round holes (D4), a gear-like outline of 6 teeth (D6) and one whose teeth
lean (C6), an asymmetric bracket (the identity alone); and lattice
designs on a rounded rectangle (D2), collapsed the same way.
"""

import math

import pytest

FRICTION = 0.2
FILLET = math.tan(math.pi / 8)


def rotation(c, deg):
    a = math.radians(deg)

    def f(p, n):
        x, y = p[0] - c[0], p[1] - c[1]
        return ((c[0] + x * math.cos(a) - y * math.sin(a), c[1] + x * math.sin(a) + y * math.cos(a)),
                (n[0] * math.cos(a) - n[1] * math.sin(a), n[0] * math.sin(a) + n[1] * math.cos(a)))
    return ("rotation", deg % 360, f)


def mirror(c, deg):
    a = math.radians(deg)
    u = (math.cos(a), math.sin(a))

    def flip(v):
        along = v[0] * u[0] + v[1] * u[1]
        return (2 * along * u[0] - v[0], 2 * along * u[1] - v[1])

    def f(p, n):
        q = flip((p[0] - c[0], p[1] - c[1]))
        return (c[0] + q[0], c[1] + q[1]), flip(n)
    return ("reflection", deg % 180, f)


def dihedral(c, n, mirrors=True, first_mirror=0.0):
    group = [rotation(c, 360 * k / n) for k in range(n)]
    if mirrors:
        group += [mirror(c, first_mirror + 180 * k / n) for k in range(n)]
    return group


RECTANGLE = {"mass": 1, "shape": {"type": "polygon",
                                  "vertices": [[1, 1], [11, 1], [11, 5], [1, 5]]}}
RECTANGLE_GROUP = dihedral((6, 3), 2)


def circle(cx, cy, r, start_deg):
    a = math.radians(start_deg)
    return [[cx + r * math.cos(a), cy + r * math.sin(a), 1],
            [cx - r * math.cos(a), cy - r * math.sin(a), 1]]


# Round holes drawn from different points: what matters is their circles.
SQUARE = {"mass": 1, "shape": {"type": "outline", "loops": [
    [[2, 0], [18, 0, FILLET], [20, 2], [20, 18, FILLET], [18, 20], [2, 20, FILLET], [0, 18],
     [0, 2, FILLET]],
    circle(5, 5, 1.5, 0), circle(15, 5, 1.5, 90), circle(15, 15, 1.5, 30), circle(5, 15, 1.5, 200)]}}
SQUARE_GROUP = dihedral((10, 10), 4)


def gear(teeth, per_tooth, lean):
    n = teeth * per_tooth
    pts = []
    for i in range(n):
        t = 2 * math.pi * i / n
        r = 10 + 1.2 * max(-1, min(1, 1.6 * math.cos(teeth * t) + lean * math.sin(teeth * t)))
        pts.append([r * math.cos(t), r * math.sin(t)])
    return {"mass": 1, "shape": {"type": "outline", "loops": [pts]}}


BRACKET = {"mass": 1, "shape": {"type": "outline", "loops": [
    [[0, 0], [20, 0], [20, 4], [8, 4, -FILLET], [4, 8], [4, 20, 1], [0, 20]],
    circle(14, 2, 1, 0)]}}


def groups_of(designs, group, size):
    """The test's grouping: designs some symmetry maps onto each other."""
    eps = 1e-6 * size

    def image_matches(a, b, f):
        for fx in a["fixels"]:
            p, n = f(fx["at"], fx["normal"])
            if not any(math.hypot(p[0] - g["at"][0], p[1] - g["at"][1]) <= eps and
                       math.hypot(n[0] - g["normal"][0], n[1] - g["normal"][1]) <= 1e-6
                       for g in b["fixels"]):
                return False
        return True

    label = [None] * len(designs)
    count = 0
    for i, a in enumerate(designs):
        if label[i] is not None:
            continue
        label[i] = count
        for j in range(i + 1, len(designs)):
            if label[j] is None and any(image_matches(a, designs[j], f) for _, _, f in group):
                label[j] = count
                # the same fixture turned: the same score
                assert abs(designs[j]["score"] - a["score"]) <= 1e-7 * (1 + abs(a["score"]))
        count += 1
    return [[d for d, l in zip(designs, label) if l == k] for k in range(count)]


def check_symmetries(answer, group):
    got = sorted((s["kind"], round(s["angle_deg"], 6)) for s in answer["symmetries"])
    want = sorted((kind, round(angle, 6)) for kind, angle, _ in group)
    assert got == want, (got, want)
    assert answer["symmetries"][0] == {"kind": "rotation", "angle_deg": 0,
                                       "center": answer["symmetries"][0]["center"]}


def check_collapse(client, params, group, size):
    every = client.result("fixture.design", dict(params, top=1000, collapse_symmetric=False))
    assert len(every["designs"]) < 1000, "top must hold every scored design"
    assert "symmetries" not in every
    collapsed = client.result("fixture.design", dict(params, top=1000))
    check_symmetries(collapsed, group)
    groups = groups_of(every["designs"], group, size)
    assert len(collapsed["designs"]) == len(groups)
    by_candidate = {d["candidate"]: d for d in collapsed["designs"]}
    for g in groups:
        lowest = min(g, key=lambda d: d["candidate"])
        assert lowest["candidate"] in by_candidate, (lowest["candidate"], sorted(by_candidate))
        kept = by_candidate[lowest["candidate"]]
        assert kept["copies"] == len(g), (kept["copies"], len(g))
        assert kept["score"] == lowest["score"]
        assert kept["fixels"] == lowest["fixels"]
    c, e = collapsed["counts"], every["counts"]
    assert c["examined"] == e["examined"] and e["symmetric"] == 0
    scored = c["examined"] - c["degenerate"] - c["unpinned"] - c["no_seating_push"]
    assert scored + c["symmetric"] >= len(every["designs"])
    # top counts distinct designs
    top3 = client.result("fixture.design", dict(params, top=3))
    assert [d["candidate"] for d in top3["designs"]] == \
        [d["candidate"] for d in collapsed["designs"][:3]]
    return len(groups), len(every["designs"])


# The square's sites: its straight sides' middles and 4 either side of them
# (the holes' own sites would start where each hole was drawn).
SQUARE_SITES = [{"at": p} for x in (6, 10, 14)
                for p in ([x, 0], [20, x], [x, 20], [0, x])]


@pytest.mark.parametrize("name,params,group,size", [
    ("rectangle", {"body": RECTANGLE, "spacing": 2.0}, RECTANGLE_GROUP, math.hypot(10, 4)),
    ("square with holes", {"body": SQUARE, "sites": SQUARE_SITES}, SQUARE_GROUP,
     math.hypot(20, 20)),
])
def test_collapse_against_own_grouping(client, name, params, group, size):
    distinct, every = check_collapse(client, dict(params, friction=FRICTION, fixels=3),
                                     group, size)
    assert distinct < every, (name, distinct, every)


def test_gears_dn_and_cn(client):
    straight = gear(6, 8, 0)
    sites = []
    pts = straight["shape"]["loops"][0]
    # a site at every third segment's middle (the daemon's normal)
    for i in range(0, len(pts), 3):
        a, b = pts[i], pts[(i + 1) % len(pts)]
        sites.append({"at": [(a[0] + b[0]) / 2, (a[1] + b[1]) / 2]})
    distinct, every = check_collapse(client, {"body": straight, "friction": 0.5,
                                              "sites": sites, "fixels": 3},
                                     dihedral((0, 0), 6), 24.0)
    assert distinct < every
    leaning = gear(6, 8, 0.9)
    ans = client.result("fixture.design", {"body": leaning, "friction": FRICTION, "spacing": 4.0,
                                           "top": 1})
    check_symmetries(ans, dihedral((0, 0), 6, mirrors=False))


def test_asymmetric_bracket_identity_only(client):
    params = {"body": BRACKET, "friction": FRICTION, "spacing": 8.0, "top": 1000}
    ans = client.result("fixture.design", params)
    assert [(s["kind"], s["angle_deg"]) for s in ans["symmetries"]] == [("rotation", 0)]
    every = client.result("fixture.design", dict(params, collapse_symmetric=False))
    assert [d["candidate"] for d in ans["designs"]] == [d["candidate"] for d in every["designs"]]
    assert all(d["copies"] == 1 for d in ans["designs"]) and ans["counts"]["symmetric"] == 0


def test_centre_of_mass_off_an_axis(client):
    """A centre of mass given on the long axis but off the short one: only
    the mirror in the long axis is a symmetry of the part."""
    body = dict(RECTANGLE, com=[8, 3], inertia=10)
    ans = client.result("fixture.design", {"body": body, "friction": FRICTION, "spacing": 2.0,
                                           "top": 1})
    check_symmetries(ans, [rotation((8, 3), 0), mirror((8, 3), 0)])


ROUNDED = {"mass": 1, "shape": {"type": "outline", "loops": [[
    [0.5, 0], [2.5, 0, FILLET], [3, 0.5], [3, 1.5, FILLET], [2.5, 2], [0.5, 2, FILLET],
    [0, 1.5], [0, 0.5, FILLET]]]}}


def test_lattice_designs_collapsed(client):
    params = {"body": ROUNDED, "friction": 0.3, "top": 1000,
              "lattice": {"pitch": 1, "peg_radius": 0.15, "extent": [4, 4]}}
    every = client.result("fixture.design", dict(params, collapse_symmetric=False))
    collapsed = client.result("fixture.design", params)
    check_symmetries(collapsed, dihedral((1.5, 1), 2))
    groups = groups_of(every["designs"], dihedral((1.5, 1), 2), math.hypot(3, 2))
    assert len(collapsed["designs"]) == len(groups) < len(every["designs"])
    by_candidate = {d["candidate"]: d for d in collapsed["designs"]}
    for g in groups:
        lowest = min(g, key=lambda d: d["candidate"])
        assert by_candidate[lowest["candidate"]]["copies"] == len(g)


def test_collapse_symmetric_refused(client):
    e = client.error("fixture.design", {"body": RECTANGLE, "friction": FRICTION, "spacing": 2.0,
                                        "collapse_symmetric": 1})
    assert e["code"] == -32602 and e["data"]["field"] == "params.collapse_symmetric", e


@pytest.mark.parametrize("features,group", [
    (None, RECTANGLE_GROUP),                                    # the pose's error: all of D2
    ([{"at": [1, 1]}, {"at": [11, 5]}], dihedral((6, 3), 2, mirrors=False)),  # the half turn
    ([{"at": [1, 1]}], dihedral((6, 3), 1, mirrors=False)),    # the identity alone
])
def test_accuracy_collapses_by_the_features(client, features, group):
    """Objective accuracy weighs its features by the worst: only the
    symmetries that map the set of features onto itself make copies, and
    the uncollapsed answer, grouped by the test's own group, has equal
    scores in each group (check_collapse)."""
    params = {"body": RECTANGLE, "spacing": 2.0, "friction": FRICTION, "fixels": 3,
              "objective": "accuracy", "tolerance": 0.01}
    if features is not None:
        params["features"] = features
    distinct, every = check_collapse(client, params, group, math.hypot(10, 4))
    assert distinct <= every
    if len(group) > 1:
        assert distinct < every
