"""Fixtures (SPEC section 8 wire form) used by the end-to-end tests."""

import copy


def disc_corner(mu=0.5, kinetic=None, name="disc-corner", inertia=0.5, com=(0, 0)):
    """SPEC section 7: a unit disc in a corner, fixel 1 at (-1, 0) with
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
    locators cut from (4, 1) to (3, 2) (SPEC section 7's demo part)."""
    return {
        "name": name,
        "body": {"mass": 1.0, "shape": {"type": "polygon",
                                        "vertices": [[0, 0], [4, 0], [4, 1], [3, 2], [0, 2]]}},
        "friction": {"static": mu},
        "fixels": [{"at": [1, 0]}, {"at": [3, 0]}, {"at": [0, 1]}],
    }


def disc_one_fixel(mu=0.5, name="disc-one"):
    """A disc on a single fixel: not pinned (SPEC section 4)."""
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
