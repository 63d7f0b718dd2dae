"""Geometry for checking wrenchctl's pictures of outlines, worked
out here from the wire's description of an outline, not from wrenchctl's
code: segments of loops of [x, y] or [x, y, bulge] vertices (the bulge
tan(theta / 4) of the arc's included angle theta, positive counter-
clockwise, as DXF's LWPOLYLINE), SVG path data as the SVG 1.1
specification reads it (its appendix F.6.5 turns an arc's endpoints and
flags into a centre and angles), and the fixture-to-page map fitted to
the drawing."""

import math
import re


# ---- the outline's own geometry ----------------------------------------------

class Segment:
    """Segment j of a loop: from vertex j to vertex j + 1 (the last back to
    vertex 0).  A straight one has bulge 0; an arc has its circle (centre,
    radius), the angle of its start about the centre and its signed
    included angle theta (> 0 counter-clockwise)."""

    def __init__(self, start, end, bulge):
        self.start = (float(start[0]), float(start[1]))
        self.end = (float(end[0]), float(end[1]))
        self.bulge = float(bulge)
        self.theta = 4 * math.atan(self.bulge)
        if self.bulge == 0:
            self.center = None
            self.radius = math.inf
            self.length = math.dist(self.start, self.end)
            return
        chord = math.dist(self.start, self.end)
        half = abs(self.theta) / 2
        self.radius = chord / (2 * math.sin(half))
        # The centre lies on the chord's perpendicular bisector, at
        # radius * cos(theta / 2) from the chord's midpoint: to the chord's
        # left for a counter-clockwise arc of less than a half circle.
        mx, my = (self.start[0] + self.end[0]) / 2, (self.start[1] + self.end[1]) / 2
        ux, uy = (self.end[0] - self.start[0]) / chord, (self.end[1] - self.start[1]) / chord
        left = (-uy, ux)
        offset = self.radius * math.cos(half) * (1 if self.theta > 0 else -1)
        self.center = (mx + offset * left[0], my + offset * left[1])
        self.start_angle = math.atan2(self.start[1] - self.center[1],
                                      self.start[0] - self.center[0])
        self.length = self.radius * abs(self.theta)

    def point(self, t):
        """The point at fraction t of the length (of an arc's angle)."""
        if self.bulge == 0:
            return (self.start[0] + t * (self.end[0] - self.start[0]),
                    self.start[1] + t * (self.end[1] - self.start[1]))
        a = self.start_angle + t * self.theta
        return (self.center[0] + self.radius * math.cos(a),
                self.center[1] + self.radius * math.sin(a))


def loops_of(shape):
    """The segments of every loop of an outline shape, as written."""
    loops = []
    for loop in shape["loops"]:
        n = len(loop)
        loops.append([Segment(loop[j][:2], loop[(j + 1) % n][:2],
                              loop[j][2] if len(loop[j]) > 2 else 0) for j in range(n)])
    return loops


def inside_loop(segments, p, samples=720):
    """Is p inside the loop?  Winding number of the loop's points, arcs
    sampled finely (points well inside or outside only)."""
    points = []
    for s in segments:
        n = 1 if s.bulge == 0 else samples
        points += [s.point(k / n) for k in range(n)]
    winding = 0.0
    for a, b in zip(points, points[1:] + points[:1]):
        da = math.atan2(a[1] - p[1], a[0] - p[0])
        db = math.atan2(b[1] - p[1], b[0] - p[0])
        d = db - da
        while d > math.pi:
            d -= 2 * math.pi
        while d < -math.pi:
            d += 2 * math.pi
        winding += d
    return abs(winding) > math.pi


def in_material(loops, p):
    return inside_loop(loops[0], p) and not any(inside_loop(h, p) for h in loops[1:])


# ---- SVG path data -----------------------------------------------------------

_TOKEN = re.compile(r"[MLAZmlaz]|-?\d+(?:\.\d*)?(?:[eE][-+]?\d+)?")


def parse_path(d):
    """Absolute M, L, A and Z path data (what wrenchctl writes) as subpaths:
    each a list of commands ("M", p), ("L", p0, p), ("A", p0, rx, ry,
    rotation, large, sweep, p), ("Z", p0, start)."""
    tokens = _TOKEN.findall(d)
    assert "".join(tokens).replace(" ", "") == re.sub(r"[\s,]", "", d), \
        "unexpected path data: %r" % d
    subpaths, i, current, start = [], 0, None, None
    while i < len(tokens):
        c = tokens[i]
        i += 1
        if c == "M":
            current = start = (float(tokens[i]), float(tokens[i + 1]))
            i += 2
            subpaths.append([("M", current)])
        elif c == "L":
            p = (float(tokens[i]), float(tokens[i + 1]))
            i += 2
            subpaths[-1].append(("L", current, p))
            current = p
        elif c == "A":
            rx, ry, rot, large, sweep, x, y = tokens[i:i + 7]
            i += 7
            assert large in ("0", "1") and sweep in ("0", "1"), (large, sweep)
            p = (float(x), float(y))
            subpaths[-1].append(("A", current, float(rx), float(ry), float(rot),
                                 int(large), int(sweep), p))
            current = p
        elif c in "Zz":
            subpaths[-1].append(("Z", current, start))
            current = start
        else:
            raise AssertionError("command %r in %r" % (c, d))
    return subpaths


def svg_arc_center(p0, r, large, sweep, p1):
    """SVG 1.1 F.6.5 for a circle (rx = ry = r, no rotation): the centre,
    the start angle and the signed sweep (radians, in the page's frame,
    y down) of the arc from p0 to p1.  A radius too small is scaled up as
    SVG does (F.6.6)."""
    x1p, y1p = (p0[0] - p1[0]) / 2, (p0[1] - p1[1]) / 2
    lam = (x1p ** 2 + y1p ** 2) / r ** 2
    if lam > 1:
        r *= math.sqrt(lam)
    num = max(0.0, r ** 2 * r ** 2 - r ** 2 * y1p ** 2 - r ** 2 * x1p ** 2)
    coef = math.sqrt(num / (r ** 2 * y1p ** 2 + r ** 2 * x1p ** 2))
    if large == sweep:
        coef = -coef
    cxp, cyp = coef * y1p, -coef * x1p
    cx, cy = cxp + (p0[0] + p1[0]) / 2, cyp + (p0[1] + p1[1]) / 2
    a0 = math.atan2(p0[1] - cy, p0[0] - cx)
    a1 = math.atan2(p1[1] - cy, p1[0] - cx)
    d = a1 - a0
    if sweep and d < 0:
        d += 2 * math.pi
    if not sweep and d > 0:
        d -= 2 * math.pi
    return (cx, cy), a0, d


# ---- the fixture-to-page map -------------------------------------------------

class PageMap:
    """page = (s x + bx, -s y + by): a uniform scale with y flipped."""

    def __init__(self, s, bx, by):
        self.s, self.bx, self.by = s, bx, by

    def page(self, p):
        return (self.s * p[0] + self.bx, -self.s * p[1] + self.by)

    def fixture(self, q):
        return ((q[0] - self.bx) / self.s, (self.by - q[1]) / self.s)

    @staticmethod
    def fit(pairs):
        """Least squares over (fixture point, page point) pairs."""
        # Unknowns s, bx, by: rows (x, 1, 0) -> X and (-y, 0, 1) -> Y.
        rows = []
        for (x, y), (X, Y) in pairs:
            rows.append(((x, 1.0, 0.0), X))
            rows.append(((-y, 0.0, 1.0), Y))
        ata = [[sum(r[0][i] * r[0][j] for r in rows) for j in range(3)] for i in range(3)]
        atb = [sum(r[0][i] * r[1] for r in rows) for i in range(3)]
        s, bx, by = _solve3(ata, atb)
        return PageMap(s, bx, by)


def _solve3(a, b):
    m = [row[:] + [v] for row, v in zip(a, b)]
    for c in range(3):
        p = max(range(c, 3), key=lambda r: abs(m[r][c]))
        m[c], m[p] = m[p], m[c]
        for r in range(3):
            if r != c:
                f = m[r][c] / m[c][c]
                m[r] = [x - f * y for x, y in zip(m[r], m[c])]
    return [m[i][3] / m[i][i] for i in range(3)]
