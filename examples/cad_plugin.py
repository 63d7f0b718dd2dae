#!/usr/bin/env python3
"""A CAD-plugin-style use of the wrenchd Python client.

Reads a part's outline (a polygon), its mass, where its locators (fixels)
touch it and the friction from a small JSON file (examples/outline.json by
default), computes each fixel's contact normal from the outline, builds the
fixture and stores it in wrenchd.  Then it asks, for pushes by a
frictionless finger at points of the outline, along the inward normal
there, whether each push seats the part from every contact state (goal) and
whether the part then holds still under it (strong), and prints each
verdict with its margin and what blocks it, in words.

    examples/cad_plugin.py [--socket PATH] [--outline FILE]
                           [--samples N | --push X,Y [--push X,Y ...]]

--socket defaults to $WRENCHD_SOCKET, else ./run/wrenchd.sock.  The pushes
are at N evenly spaced points of every edge (--samples, default 2: a
quarter and three quarters along), or at the points given with --push.

The outline file has the form of a fixture (docs/PROTOCOL.md) with a polygon
shape, so that it also loads as one (wrenchd --load):
    {"name": "...",
     "body": {"mass": 2.0, "shape": {"type": "polygon", "vertices": [[x, y], ...]}},
     "friction": {"static": 0.1, "kinetic": 0.08},
     "fixels": [{"at": [x, y]}, ...]}
Vertices in either orientation; a fixel's "normal" is computed here from the
edge it lies on (give one for a fixel at a vertex).

Exit status: 0 done, 1 wrenchd refused the fixture or a request, 2 wrenchd
cannot be reached or the outline file is invalid.  Standard library only.
"""

import argparse
import json
import math
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "clients", "python"))

import wrenchd  # noqa: E402  (after the path is set)


class OutlineError(Exception):
    pass


def signed_area(vertices):
    n = len(vertices)
    return 0.5 * sum(vertices[i][0] * vertices[(i + 1) % n][1]
                     - vertices[(i + 1) % n][0] * vertices[i][1] for i in range(n))


def locate(vertices, point):
    """The edge holding `point`: (edge index, fraction t along it).
    Raises OutlineError when the point is off the outline."""
    size = max(max(abs(c) for v in vertices for c in v), 1.0)
    best = None
    n = len(vertices)
    for i in range(n):
        (ax, ay), (bx, by) = vertices[i], vertices[(i + 1) % n]
        dx, dy = bx - ax, by - ay
        t = ((point[0] - ax) * dx + (point[1] - ay) * dy) / (dx * dx + dy * dy)
        t = max(0.0, min(1.0, t))
        dist = math.hypot(ax + t * dx - point[0], ay + t * dy - point[1])
        if best is None or dist < best[0]:
            best = (dist, i, t)
    dist, edge, t = best
    if dist > 1e-9 * size:
        raise OutlineError("(%g, %g) is not on the outline (%.3g away)" % (point[0], point[1], dist))
    return edge, t


def inward_normal(vertices, edge):
    """The unit normal of `edge` pointing into the part, for either orientation."""
    (ax, ay), (bx, by) = vertices[edge], vertices[(edge + 1) % len(vertices)]
    dx, dy = bx - ax, by - ay
    length = math.hypot(dx, dy)
    if signed_area(vertices) > 0:          # counter-clockwise: the interior is on the left
        return (-dy / length, dx / length)
    return (dy / length, -dx / length)


def normal_at(vertices, point):
    edge, t = locate(vertices, point)
    if t < 1e-9 or t > 1 - 1e-9:
        raise OutlineError("(%g, %g) is a vertex, where the outline has no normal"
                           % tuple(point))
    return edge, inward_normal(vertices, edge)


def load_outline(path):
    """(vertices, fixture): the file's fixture, with every fixel's normal."""
    with open(path) as f:
        spec = json.load(f)
    try:
        shape = spec["body"]["shape"]
        if shape.get("type") != "polygon":
            raise OutlineError("the outline must be a polygon")
        vertices = [(float(x), float(y)) for x, y in shape["vertices"]]
        if len(vertices) < 3 or abs(signed_area(vertices)) < 1e-12:
            raise OutlineError("the outline needs at least three vertices and an area")
        fixels = []
        for item in spec["fixels"]:
            fixel = dict(item)
            fixel["at"] = [float(c) for c in item["at"]]
            if "normal" in item:
                locate(vertices, fixel["at"])
            else:
                _, normal = normal_at(vertices, fixel["at"])
                fixel["normal"] = [normal[0], normal[1]]
            fixels.append(fixel)
        fixture = dict(spec)
        fixture.setdefault("name", os.path.splitext(os.path.basename(path))[0])
        fixture["fixels"] = fixels
    except (KeyError, TypeError, ValueError, AttributeError) as e:
        raise OutlineError("%s: %s" % (type(e).__name__, e))
    return vertices, fixture


def point(text):
    try:
        x, y = (float(c) for c in text.split(","))
    except ValueError:
        raise argparse.ArgumentTypeError("a point is X,Y, not %r" % text)
    return (x, y)


def sample_pushes(vertices, per_edge):
    n = len(vertices)
    out = []
    for i in range(n):
        (ax, ay), (bx, by) = vertices[i], vertices[(i + 1) % n]
        for j in range(per_edge):
            t = (j + 0.5) / per_edge
            out.append((ax + t * (bx - ax), ay + t * (by - ay)))
    return out


def number(x):
    """At most three decimals, no trailing zeros, no "-0"."""
    text = ("%.3f" % x).rstrip("0").rstrip(".")
    return "0" if text in ("-0", "") else text


def show(set_name, verdict):
    margin = "    n/a" if verdict.margin is None else "%+.3f" % verdict.margin
    if verdict.inside:
        text = wrenchd.explain(verdict, set_name)
    else:
        text = "blocked by %s: %s" % (verdict.blocking, wrenchd.explain(verdict, set_name))
    return "    %-6s %-8s margin %s  %s" % (set_name, verdict.verdict, margin, text)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--socket", default=wrenchd.default_socket_path(),
                        help="wrenchd's socket (default: $WRENCHD_SOCKET or ./run/wrenchd.sock)")
    parser.add_argument("--outline", default=os.path.join(HERE, "outline.json"),
                        help="the part's outline, fixels and friction (JSON)")
    parser.add_argument("--samples", type=int, default=2, metavar="N",
                        help="push at N evenly spaced points of every edge (default 2)")
    parser.add_argument("--push", type=point, action="append", metavar="X,Y",
                        help="push at this point of the outline instead (repeatable)")
    parser.add_argument("--timeout", type=float, default=10.0, help="seconds per request")
    args = parser.parse_args(argv)

    try:
        vertices, fixture = load_outline(args.outline)
    except (OSError, ValueError, OutlineError) as e:
        print("cad_plugin: %s: %s" % (args.outline, e), file=sys.stderr)
        return 2
    try:
        pushes = args.push or sample_pushes(vertices, max(args.samples, 1))
        located = [(p,) + normal_at(vertices, p) for p in pushes]
    except OutlineError as e:
        print("cad_plugin: push: %s" % e, file=sys.stderr)
        return 2

    client = wrenchd.Client(args.socket, timeout=args.timeout)
    try:
        put = client.put_fixture(fixture)
        print("%s: %d fixels, stored in wrenchd as %s (G_goal excludes %d cones, G_strong %d)"
              % (put.name, put.fixels, put.id, put.goal_cones, put.strong_cones))
        # one round trip for the classifications and the modes
        wrenches = [{"force": [n[0], n[1]], "at": [p[0], p[1]]} for p, _, n in located]
        with client.batch() as batch:
            answers = batch.classify(put.id, wrenches, sets=("goal", "strong"))
            modes = batch.modes(put.id)
        answers, modes = answers.result(), modes.result()
    except wrenchd.WrenchdUnavailable as e:
        print("cad_plugin: cannot use wrenchd: %s" % e, file=sys.stderr)
        return 2
    except wrenchd.WrenchdError as e:
        print("cad_plugin: wrenchd refused: %s" % e, file=sys.stderr)
        return 1
    finally:
        client.close()

    print("seated, the part %s; it may start to move in %d modes: %s\n"
          % ("is pinned" if modes.pinned else "is not pinned", len(modes.feasible),
             " ".join(modes.feasible)))
    good = []
    for index, ((p, edge, n), answer) in enumerate(zip(located, answers), 1):
        print("push %d at (%s, %s) on edge %d, along the inward normal (%s, %s)"
              % (index, number(p[0]), number(p[1]), edge, number(n[0]), number(n[1])))
        for set_name in ("goal", "strong"):
            print(show(set_name, answer[set_name]))
        if answer["goal"].inside and answer["strong"].inside:
            good.append(index)
    print("\npushes that seat the part and then hold it still: %s"
          % (", ".join(str(i) for i in good) if good else "none"))
    return 0


if __name__ == "__main__":
    sys.exit(main())
