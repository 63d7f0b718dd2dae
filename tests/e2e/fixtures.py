"""Fixtures (docs/PROTOCOL.md wire form) used by the end-to-end tests."""

import copy
import math


def disc_corner(mu=0.5, kinetic=None, name="disc-corner", inertia=0.5, com=(0, 0)):
    """docs/MODEL.md section 7: a unit disc in a corner, fixel 1 at (-1, 0) with
    normal (1, 0), fixel 2 at (0, -1) with normal (0, 1)."""
    friction = {"static": mu}
    friction["kinetic"] = mu if kinetic is None else kinetic
    body = {"mass": 1.0, "com": list(com),
            "shape": {"type": "circle", "center": [0, 0], "radius": 1.0}}
    if inertia is not None:
        body["inertia"] = inertia
    return {
        "name": name,
        "body": body,
        "friction": friction,
        "fixels": [
            {"at": [-1, 0], "normal": [1, 0]},
            {"at": [0, -1], "normal": [0, 1]},
        ],
    }


def rectangle_321(mu=0.3, clockwise=False, name="plate-3-2-1", width=4.0, height=2.0):
    """A rectangular plate (com and inertia left out: uniform) against three
    fixels, two on its bottom edge and one on its left edge; normals left
    out (the shape's inward normals)."""
    verts = [[0, 0], [width, 0], [width, height], [0, height]]
    if clockwise:
        verts = verts[::-1]
    return {
        "name": name,
        "body": {"mass": 1.0, "shape": {"type": "polygon", "vertices": verts}},
        "friction": {"static": mu},
        "fixels": [
            {"at": [width / 4, 0]},
            {"at": [3 * width / 4, 0]},
            {"at": [0, height / 2]},
        ],
    }


def chamfered_plate(mu=0.05, name="chamfer"):
    """The 4 x 2 plate of rectangle_321 with the corner opposite the
    locators cut from (4, 1) to (3, 2) (docs/MODEL.md section 7's demo part)."""
    return {
        "name": name,
        "body": {"mass": 1.0, "shape": {"type": "polygon",
                                        "vertices": [[0, 0], [4, 0], [4, 1], [3, 2], [0, 2]]}},
        "friction": {"static": mu},
        "fixels": [{"at": [1, 0]}, {"at": [3, 0]}, {"at": [0, 1]}],
    }


def disc_one_fixel(mu=0.5, name="disc-one"):
    """A disc on a single fixel: not pinned (docs/MODEL.md section 4)."""
    return {
        "name": name,
        "body": {"mass": 1.0, "shape": {"type": "circle", "center": [0, 0], "radius": 1.0}},
        "friction": {"static": mu},
        "fixels": [{"at": [0, -1], "normal": [0, 1]}],
    }


def offset_disc(mu=0.4, name="offset-disc"):
    """A disc whose centre of mass is off its centre, with its own inertia,
    and per-fixel friction (kinetic below static on one fixel)."""
    return {
        "name": name,
        "body": {"mass": 2.0, "inertia": 0.8, "com": [0.2, 0.1],
                 "shape": {"type": "circle", "center": [0, 0], "radius": 1.0}},
        "fixels": [
            {"at": [-1, 0], "normal": [1, 0], "friction": {"static": mu}},
            {"at": [0, -1], "friction": {"static": mu, "kinetic": mu / 2}},
        ],
    }


def triangle(mu=0.25, name="triangle"):
    """A triangle with fixels on two of its edges, one normal given scaled
    (the daemon normalises it), the second fixel with its own friction
    (overriding the fixture's)."""
    return {
        "name": name,
        "body": {"mass": 3.0, "shape": {"type": "polygon",
                                        "vertices": [[0, 0], [3, 0], [0, 3]]}},
        "friction": {"static": mu, "kinetic": mu * 0.8},
        "fixels": [
            {"at": [1, 0], "normal": [0, 5]},
            {"at": [0, 2], "friction": {"static": 0.6}},
        ],
    }


def corner_fixel_plate(mu=0.2, name="corner-fixel"):
    """The 4 x 2 plate with a fixel on its bottom edge and one at the vertex
    (0, 0), whose normal must then be given (here along the diagonal)."""
    return {
        "name": name,
        "body": {"mass": 1.5, "shape": {"type": "polygon",
                                        "vertices": [[0, 0], [4, 0], [4, 2], [0, 2]]}},
        "friction": {"static": mu},
        "fixels": [
            {"at": [3, 0]},
            {"at": [0, 0], "normal": [1, 1]},
        ],
    }


def scaled_disc_corner(mu=0.5, length=1.0, mass=1.0):
    """disc_corner in other units: lengths times `length`, mass times
    `mass` (inertia times mass * length^2)."""
    L = length
    return {
        "name": "disc-corner-scaled",
        "body": {"mass": mass, "inertia": 0.5 * mass * L * L, "com": [0, 0],
                 "shape": {"type": "circle", "center": [0, 0], "radius": L}},
        "friction": {"static": mu},
        "fixels": [
            {"at": [-L, 0], "normal": [1, 0]},
            {"at": [0, -L], "normal": [0, 1]},
        ],
    }


def many(n=50):
    """n distinct valid fixtures (distinct content, so distinct ids)."""
    out = []
    for i in range(n):
        kind = i % 3
        if kind == 0:
            f = disc_corner(mu=0.05 + 0.01 * i, name="disc-%02d" % i)
        elif kind == 1:
            f = rectangle_321(mu=0.1 + 0.005 * i, name="plate-%02d" % i, width=3.0 + 0.1 * i)
        else:
            f = triangle(mu=0.2 + 0.003 * i, name="tri-%02d" % i)
        out.append(f)
    return out


def variant(fixture, path, value=None, delete=False):
    """A deep copy of `fixture` with the member at `path` (a list of keys and
    indices) set to `value`, or deleted."""
    f = copy.deepcopy(fixture)
    node = f
    for key in path[:-1]:
        node = node[key]
    if delete:
        del node[path[-1]]
    else:
        node[path[-1]] = value
    return f


# ---- for the push-region, gravity-sweep and margin tests (docs/MODEL.md section 6) -------------

def square_form_closure(name="square-form-closure"):
    """A 2 x 2 square held by four frictionless fixels, one per edge, each
    off its edge's midpoint so that their wrenches (1, 0, -0.5), (-1, 0,
    -0.5), (0, 1, 0.5), (0, -1, 0.5) sum to zero and span R^3: first-order
    form closure, so no moving mode is kinematically feasible."""
    return {
        "name": name,
        "body": {"mass": 1.0, "shape": {"type": "polygon",
                                        "vertices": [[-1, -1], [1, -1], [1, 1], [-1, 1]]}},
        "friction": {"static": 0.0},
        "fixels": [
            {"at": [-1, 0.5], "normal": [1, 0]},
            {"at": [1, -0.5], "normal": [-1, 0]},
            {"at": [0.5, -1], "normal": [0, 1]},
            {"at": [-0.5, 1], "normal": [0, -1]},
        ],
    }


def disc_at_angles(angles_deg, mu=0.5, radius=1.0, center=(0.0, 0.0), com=None,
                   inertia=None, mass=1.0, name="disc-angles"):
    """A disc with a fixel at each boundary angle (degrees); normals left out
    (towards the centre)."""
    cx, cy = center
    body = {"mass": mass, "shape": {"type": "circle", "center": [cx, cy], "radius": radius}}
    if com is not None:
        body["com"] = list(com)
    if inertia is not None:
        body["inertia"] = inertia
    fixels = []
    for a in angles_deg:
        r = math.radians(a)
        fixels.append({"at": [cx + radius * math.cos(r), cy + radius * math.sin(r)]})
    return {"name": name, "body": body, "friction": {"static": mu}, "fixels": fixels}


def _cross3(o, a, b):
    return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])


def _is_convex(verts):
    n = len(verts)
    signs = {_cross3(verts[i], verts[(i + 1) % n], verts[(i + 2) % n]) > 0 for i in range(n)}
    return len(signs) == 1


def random_polygon(rnd, convex, corner=False, name="random-polygon"):
    """A random simple polygon (star-shaped about its first centre, so simple),
    convex (points on an ellipse) or not (at least one reflex vertex), in
    either orientation, with 3 or 4 fixels strictly inside edges (normals
    left out: the shape's inward normals), random friction, mass, and
    sometimes a given centre of mass and inertia.  With `corner`, the fixels
    sit on the two edges of one convex vertex (a locating corner, like the
    3-2-1 plate's) and friction is low, so that G_goal has push regions
    more often."""
    while True:
        n = rnd.randint(3, 6) if convex else rnd.randint(5, 8)
        angles = sorted(rnd.uniform(0, 2 * math.pi) for _ in range(n))
        gaps = [(angles[(i + 1) % n] - angles[i]) % (2 * math.pi) for i in range(n)]
        if min(gaps) < 0.25 or max(gaps) > 0.9 * math.pi:
            continue    # star-shaped about (cx, cy), hence simple, needs gaps < pi
        sx, sy = rnd.uniform(0.6, 2.5), rnd.uniform(0.6, 2.5)
        cx, cy = rnd.uniform(-3, 3), rnd.uniform(-3, 3)
        verts = []
        for a in angles:
            r = 1.0 if convex else rnd.uniform(0.35, 1.3)
            verts.append((round(cx + sx * r * math.cos(a), 6), round(cy + sy * r * math.sin(a), 6)))
        if _is_convex(verts) != convex:
            continue
        break
    if rnd.random() < 0.5:
        verts = verts[::-1]
    k = rnd.randint(3, 4)
    if corner:
        k = 3 if rnd.random() < 0.75 else 4
        # a vertex j whose interior angle is convex (the turn there has the
        # outline's orientation), fixels on edges j - 1 and j
        area2 = sum(verts[i][0] * verts[(i + 1) % n][1] - verts[(i + 1) % n][0] * verts[i][1]
                    for i in range(n))
        convex_at = [j for j in range(n)
                     if _cross3(verts[j - 1], verts[j], verts[(j + 1) % n]) * area2 > 0]
        j = rnd.choice(convex_at)
        edges = [(j - 1) % n, (j - 1) % n, j] + ([j] if k == 4 else [])
    else:
        edges = rnd.sample(range(n), min(k, n))
    while len(edges) < k:
        edges.append(rnd.randrange(n))
    fixels = []
    used = set()
    for e in edges:
        while True:
            t = round(rnd.uniform(0.1, 0.9), 3)
            if (e, t) not in used:
                used.add((e, t))
                break
        a, b = verts[e], verts[(e + 1) % n]
        fixels.append({"at": [a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])]})
    mu = round(rnd.uniform(0.0, 0.3 if corner else 0.9), 3)
    friction = {"static": mu}
    if rnd.random() < 0.3:
        friction["kinetic"] = round(mu * rnd.uniform(0.3, 1.0), 3)
    body = {"mass": round(rnd.uniform(0.5, 3.0), 3),
            "shape": {"type": "polygon", "vertices": [list(v) for v in verts]}}
    if rnd.random() < 0.3:
        body["com"] = [round(cx + rnd.uniform(-0.2, 0.2) * sx, 6),
                       round(cy + rnd.uniform(-0.2, 0.2) * sy, 6)]
        body["inertia"] = round(body["mass"] * rnd.uniform(0.2, 1.5) * sx * sy, 6)
    return {"name": name, "body": body, "friction": friction, "fixels": fixels}


def random_disc(rnd, corner=False, name="random-disc"):
    """A random disc (centre, radius, mass) with 2..4 fixels at distinct
    boundary angles, its centre of mass off the centre about half the time
    (inertia then given), normals left out or given (unnormalised).  With
    `corner`: two fixels 50..150 degrees apart and low friction (a corner
    like docs/MODEL.md section 7's, rotated), so that G_goal has push regions more often."""
    radius = round(rnd.uniform(0.4, 2.5), 4)
    center = (round(rnd.uniform(-2, 2), 4), round(rnd.uniform(-2, 2), 4))
    k = 2 if corner else rnd.randint(2, 4)
    while True:
        if corner:
            a = round(rnd.uniform(0, 360), 3)
            angles = sorted([a, round((a + rnd.uniform(50, 150)) % 360, 3)])
        else:
            angles = sorted(round(rnd.uniform(0, 360), 3) for _ in range(k))
        gaps = [(angles[(i + 1) % k] - angles[i]) % 360 for i in range(k)]
        if min(gaps) > 15:
            break
    com = None
    inertia = None
    mass = round(rnd.uniform(0.5, 3.0), 3)
    if rnd.random() < 0.5:
        com = (center[0] + round(rnd.uniform(-0.4, 0.4) * radius, 4),
               center[1] + round(rnd.uniform(-0.4, 0.4) * radius, 4))
        inertia = round(mass * radius * radius * rnd.uniform(0.3, 0.7), 6)
    mu = round(rnd.uniform(0.0, 0.4 if corner else 0.9), 3)
    f = disc_at_angles(angles, mu=mu, radius=radius,
                       center=center, com=com, inertia=inertia, mass=mass, name=name)
    for fx in f["fixels"]:
        if rnd.random() < 0.3:
            s = rnd.uniform(0.5, 3.0)
            fx["normal"] = [s * (center[0] - fx["at"][0]), s * (center[1] - fx["at"][1])]
    return f


def moved(fixture, degrees=0.0, shift=(0.0, 0.0), scale=1.0, name=None):
    """`fixture` turned by `degrees` about the origin, then scaled by
    `scale` and shifted by `shift`: the same physics in other coordinates
    (a given inertia scales by scale^2, given normals turn, mass and
    friction stay)."""
    c, s = math.cos(math.radians(degrees)), math.sin(math.radians(degrees))

    def turn(v):
        return [c * v[0] - s * v[1], s * v[0] + c * v[1]]

    def place(p):
        q = turn(p)
        return [scale * q[0] + shift[0], scale * q[1] + shift[1]]

    f = copy.deepcopy(fixture)
    if name is not None:
        f["name"] = name
    body = f["body"]
    shape = body.get("shape")
    if shape and shape["type"] == "circle":
        shape["center"] = place(shape["center"])
        shape["radius"] = shape["radius"] * scale
    elif shape:
        shape["vertices"] = [place(v) for v in shape["vertices"]]
    if "com" in body:
        body["com"] = place(body["com"])
    if "inertia" in body:
        body["inertia"] = body["inertia"] * scale * scale
    for fx in f["fixels"]:
        fx["at"] = place(fx["at"])
        if "normal" in fx:
            fx["normal"] = turn(fx["normal"])
    return f


def plate_321(mu=0.3):
    """The 3-2-1 plate: a 4 x 2 rectangle, fixels 1 and 2 under it at x = 1
    and x = 3, fixel 3 against its left side at y = 1."""
    return {"body": {"mass": 1.0, "shape": {"type": "polygon",
                                            "vertices": [[0, 0], [4, 0], [4, 2], [0, 2]]}},
            "friction": {"static": mu},
            "fixels": [{"at": [1, 0]}, {"at": [3, 0]}, {"at": [0, 1]}]}


def disc_corner_mm():
    """disc_corner(0.5) in millimetres and newtons: radius 1000 mm, 1 kg,
    inertia 0.5e6 kg mm^2."""
    return {"name": "disc-mm", "units": {"length": "mm", "force": "N"},
            "body": {"mass": 1.0, "inertia": 0.5e6, "com": [0, 0],
                     "shape": {"type": "circle", "center": [0, 0], "radius": 1000.0}},
            "friction": {"static": 0.5},
            "fixels": [{"at": [-1000, 0], "normal": [1, 0]},
                       {"at": [0, -1000], "normal": [0, 1]}]}
