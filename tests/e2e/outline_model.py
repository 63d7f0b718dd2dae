"""Independent geometry of the "outline" shape for the tests.

An outline is {"type": "outline", "loops": [loop, ...]}: the first loop is
the outer boundary, the others holes; a loop is a list of vertices [x, y] or
[x, y, bulge]; vertex j's bulge describes segment j, from vertex j to vertex
j + 1 (the last back to vertex 0), as in DXF's LWPOLYLINE: bulge = tan(theta
/ 4), theta the arc's included angle, positive counter-clockwise, 0 a line.

Nothing here comes from the daemon: arcs from the bulge by the chord and the
sagitta, mass properties by Green's theorem integrated along every segment
with Gauss-Legendre quadrature (exact for the line integrands, which are
polynomials, and converged to rounding for the arcs' trigonometric ones),
the inward normal from each loop's orientation (the material lies left of a
counter-clockwise outer loop and right of a counter-clockwise hole).
Only the standard library.
"""

import math


# ---- Gauss-Legendre nodes on [0, 1] -----------------------------------------

def _gauss_legendre(n):
    nodes, weights = [], []
    for i in range(1, n + 1):
        x = math.cos(math.pi * (i - 0.25) / (n + 0.5))
        for _ in range(100):
            p0, p1 = 1.0, x
            for k in range(2, n + 1):
                p0, p1 = p1, ((2 * k - 1) * x * p1 - (k - 1) * p0) / k
            dp = n * (x * p1 - p0) / (x * x - 1)
            dx = p1 / dp
            x -= dx
            if abs(dx) < 1e-16:
                break
        p0, p1 = 1.0, x
        for k in range(2, n + 1):
            p0, p1 = p1, ((2 * k - 1) * x * p1 - (k - 1) * p0) / k
        dp = n * (x * p1 - p0) / (x * x - 1)
        nodes.append(0.5 * (1 - x))
        weights.append(1.0 / ((1 - x * x) * dp * dp))
    return list(zip(nodes, weights))


GAUSS = _gauss_legendre(48)


# ---- segments ----------------------------------------------------------------

class Segment:
    """Segment j of a loop: a line or an arc from p0 to p1."""

    def __init__(self, p0, p1, bulge):
        self.p0 = (float(p0[0]), float(p0[1]))
        self.p1 = (float(p1[0]), float(p1[1]))
        self.bulge = float(bulge)
        dx, dy = self.p1[0] - self.p0[0], self.p1[1] - self.p0[1]
        chord = math.hypot(dx, dy)
        self.chord = chord
        if self.bulge == 0:
            self.arc = False
            self.length = chord
            return
        self.arc = True
        b = self.bulge
        self.theta = 4 * math.atan(b)                 # signed included angle
        self.radius = chord * (1 + b * b) / (4 * abs(b))
        # the centre: from the chord's midpoint along its left normal by
        # (chord / 2) (1 - b^2) / (2 b) (b = 1: the midpoint; b > 0 small:
        # far to the left, the arc bulging right of the chord)
        k = (1 - b * b) / (4 * b)
        mx, my = 0.5 * (self.p0[0] + self.p1[0]), 0.5 * (self.p0[1] + self.p1[1])
        self.center = (mx - k * dy, my + k * dx)
        self.a0 = math.atan2(self.p0[1] - self.center[1], self.p0[0] - self.center[0])
        self.length = self.radius * abs(self.theta)

    def point(self, t):
        if not self.arc:
            return (self.p0[0] + t * (self.p1[0] - self.p0[0]),
                    self.p0[1] + t * (self.p1[1] - self.p0[1]))
        if t == 0:
            return self.p0
        if t == 1:
            return self.p1
        a = self.a0 + t * self.theta
        return (self.center[0] + self.radius * math.cos(a),
                self.center[1] + self.radius * math.sin(a))

    def derivative(self, t):
        """d point / d t."""
        if not self.arc:
            return (self.p1[0] - self.p0[0], self.p1[1] - self.p0[1])
        a = self.a0 + t * self.theta
        return (-self.radius * self.theta * math.sin(a), self.radius * self.theta * math.cos(a))

    def direction(self, t):
        """Unit direction of travel at t."""
        d = self.derivative(t)
        n = math.hypot(d[0], d[1])
        return (d[0] / n, d[1] / n)

    def angle_of(self, t):
        """The boundary angle (radians) about the arc's centre at t."""
        return self.a0 + t * self.theta


def segments(loop):
    out = []
    n = len(loop)
    for j in range(n):
        v = loop[j]
        w = loop[(j + 1) % n]
        out.append(Segment(v[:2], w[:2], v[2] if len(v) > 2 else 0.0))
    return out


# ---- integrals ------------------------------------------------------------------

def _loop_integrals(segs, origin):
    """Signed (area, Sx, Sy, J) of the region a loop encloses, counted
    positive when the loop is counter-clockwise, by Green's theorem with
    coordinates taken relative to `origin`:
    A = 1/2 oint (x dy - y dx), Sx = oint x^2/2 dy, Sy = -oint y^2/2 dx,
    J = oint (x^3 dy - y^3 dx) / 3."""
    a = sx = sy = j = 0.0
    ox, oy = origin
    for s in segs:
        for t, w in GAUSS:
            x, y = s.point(t)
            x -= ox
            y -= oy
            dx, dy = s.derivative(t)
            a += w * 0.5 * (x * dy - y * dx)
            sx += w * 0.5 * x * x * dy
            sy += w * -0.5 * y * y * dx
            j += w * (x ** 3 * dy - y ** 3 * dx) / 3.0
    return a, sx, sy, j


class Outline:
    def __init__(self, shape):
        assert shape["type"] == "outline"
        self.loops = [segments(loop) for loop in shape["loops"]]
        first = shape["loops"][0][0]
        self.origin = (float(first[0]), float(first[1]))
        self.signs = []
        total = [0.0, 0.0, 0.0, 0.0]
        for i, segs in enumerate(self.loops):
            ints = _loop_integrals(segs, self.origin)
            ccw = 1 if ints[0] > 0 else -1
            self.signs.append(ccw)
            # the outer loop adds its region, a hole takes its own away
            k = ccw if i == 0 else -ccw
            for q in range(4):
                total[q] += k * ints[q]
        self.area = total[0]
        cx = total[1] / self.area
        cy = total[2] / self.area
        self.centroid = (cx + self.origin[0], cy + self.origin[1])
        # polar second moment about the centroid, per unit area
        self.polar_per_area = total[3] / self.area - (cx * cx + cy * cy)

    def segment(self, loop, seg):
        return self.loops[loop][seg]

    def inertia(self, mass, com=None):
        """Uniform lamina of `mass`, about `com` (default the centroid)."""
        if com is None:
            com = self.centroid
        d2 = (com[0] - self.centroid[0]) ** 2 + (com[1] - self.centroid[1]) ** 2
        return mass * (self.polar_per_area + d2)

    def material_left(self, loop):
        """True when the material lies left of the direction of travel."""
        ccw = self.signs[loop] > 0
        return ccw if loop == 0 else not ccw

    def inward_normal(self, loop, seg, t):
        d = self.loops[loop][seg].direction(t)
        if self.material_left(loop):
            return (-d[1], d[0])
        return (d[1], -d[0])

    def perimeter(self):
        return sum(s.length for segs in self.loops for s in segs)

    def push_wrench(self, com, loop, seg, t):
        p = self.loops[loop][seg].point(t)
        nu = self.inward_normal(loop, seg, t)
        r = (p[0] - com[0], p[1] - com[1])
        return (nu[0], nu[1], r[0] * nu[1] - r[1] * nu[0])


# ---- building outlines ------------------------------------------------------------

BULGE_90 = math.tan(math.pi / 8)        # a quarter circle, counter-clockwise


def circle_loop(center, radius, phase_deg=0.0, ccw=True):
    """A circle as two half-circle arcs, starting at boundary angle
    `phase_deg`."""
    cx, cy = center
    out = []
    for k in range(2):
        a = math.radians(phase_deg + (180.0 * k if ccw else -180.0 * k))
        out.append([cx + radius * math.cos(a), cy + radius * math.sin(a), 1.0 if ccw else -1.0])
    return out


def reverse_loop(loop):
    """The same loop traversed the other way: segment j (v_j to v_j+1 with
    bulge b_j) becomes v_j+1 to v_j with bulge -b_j."""
    n = len(loop)
    out = []
    for j in range(n - 1, -1, -1):
        v = loop[(j + 1) % n]
        b = loop[j][2] if len(loop[j]) > 2 else 0.0
        out.append([v[0], v[1], -b])
    return out


def rounded_rectangle(w, h, f, center=(0.0, 0.0)):
    """A w x h rectangle whose corners are quarter circles of radius f,
    counter-clockwise, starting at the bottom of the right side."""
    cx, cy = center
    x, y = w / 2, h / 2
    b = BULGE_90
    pts = [[x, -y + f, 0], [x, y - f, b], [x - f, y, 0], [-x + f, y, b],
           [-x, y - f, 0], [-x, -y + f, b], [-x + f, -y, 0], [x - f, -y, b]]
    return [[cx + p[0], cy + p[1], p[2]] for p in pts]


def stadium(center, straight, radius):
    """A horizontal stadium: a straight part of length `straight` between
    two half circles of `radius`, counter-clockwise."""
    cx, cy = center
    L = straight / 2
    return [[cx - L, cy - radius, 0], [cx + L, cy - radius, 1], [cx + L, cy + radius, 0],
            [cx - L, cy + radius, 1]]


def rectangle(x0, y0, x1, y1):
    return [[x0, y0], [x1, y0], [x1, y1], [x0, y1]]


# ---- a round finger's clearance, by brute force ------------------------------------

def distance_to_segment(s, c):
    if s.arc:
        a = math.atan2(c[1] - s.center[1], c[0] - s.center[0])
        da = ((a - s.a0) * (1 if s.theta > 0 else -1)) % (2 * math.pi)
        if da <= abs(s.theta):
            return abs(math.hypot(c[0] - s.center[0], c[1] - s.center[1]) - s.radius)
        return min(math.hypot(c[0] - q[0], c[1] - q[1]) for q in (s.p0, s.p1))
    dx, dy = s.p1[0] - s.p0[0], s.p1[1] - s.p0[1]
    t = ((c[0] - s.p0[0]) * dx + (c[1] - s.p0[1]) * dy) / (dx * dx + dy * dy)
    t = min(1.0, max(0.0, t))
    q = s.point(t)
    return math.hypot(c[0] - q[0], c[1] - q[1])


def polyline(segs, per_arc=400):
    pts = []
    for s in segs:
        n = per_arc if s.arc else 1
        pts += [s.point(k / n) for k in range(n)]
    return pts


def in_material(ol, c):
    """Crossing parity over every loop (arcs as fine polylines): inside the
    outer loop and outside every hole."""
    inside = False
    if not hasattr(ol, "_polylines"):
        ol._polylines = [polyline(segs) for segs in ol.loops]
    for pts in ol._polylines:
        n = len(pts)
        for i in range(n):
            (x0, y0), (x1, y1) = pts[i], pts[(i + 1) % n]
            if (y0 > c[1]) != (y1 > c[1]):
                x = x0 + (c[1] - y0) * (x1 - x0) / (y1 - y0)
                if x > c[0]:
                    inside = not inside
    return inside


def finger_fits(ol, loop, seg, t, r):
    """The open disc of radius r touching the outline at (loop, seg, t) from
    outside the material (centre p - r nu) holds no material: its centre is
    in free space and at least r from every segment (touching allowed, to
    1e-9 relative)."""
    p = ol.segment(loop, seg).point(t)
    nu = ol.inward_normal(loop, seg, t)
    c = (p[0] - r * nu[0], p[1] - r * nu[1])
    d = min(distance_to_segment(s, c) for segs in ol.loops for s in segs)
    if d < r * (1 - 1e-9):
        return False
    return not in_material(ol, c)
