"""An independent, brute-force Python model of docs/MODEL.md sections 1-5.

Nothing here is taken from the daemon or from libwrench: every cone is built
from the definitions (Newton-Euler, the letter table of section 2, the plan
rule of section 3, the modes of section 4, the metric of section 5) with
plain 3-D geometry on small generator sets:

* Q_X (the accelerations a string allows) is turned from inequalities into
  generators by trying every cross product of two constraint rows;
* G_X = M Q_X - W C_X is the cone of M (Q_X generators) and the friction-cone
  edges -(W_n +- mu W_t);
* the distance of a unit wrench to a cone is a non-negative least-squares
  problem, solved by trying every subset of at most three generators
  (Caratheodory); the depth of a point in a full-dimensional cone is the
  distance to its nearest facet, and facets are the cross products of pairs
  of generators that support every generator.

Slow (pure Python) but exact enough (1e-12) for the small fixtures the tests
use.  Only the standard library.
"""

import itertools
import math

TOL = 1e-11


# ---- small vectors -------------------------------------------------------

def dot(a, b):
    return sum(x * y for x, y in zip(a, b))


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def cross2(a, b):
    return a[0] * b[1] - a[1] * b[0]


def norm(a):
    return math.sqrt(dot(a, a))


def unit(a):
    n = norm(a)
    return tuple(x / n for x in a)


def add(a, b):
    return tuple(x + y for x, y in zip(a, b))


def sub(a, b):
    return tuple(x - y for x, y in zip(a, b))


def mul(k, a):
    return tuple(k * x for x in a)


def solve(matrix, rhs):
    """Gaussian elimination with partial pivoting; None when singular."""
    n = len(matrix)
    a = [list(row) + [r] for row, r in zip(matrix, rhs)]
    scale = max((abs(x) for row in matrix for x in row), default=0.0) or 1.0
    for col in range(n):
        pivot = max(range(col, n), key=lambda r: abs(a[r][col]))
        if abs(a[pivot][col]) <= 1e-12 * scale:
            return None
        a[col], a[pivot] = a[pivot], a[col]
        for r in range(n):
            if r != col:
                f = a[r][col] / a[col][col]
                for c in range(col, n + 1):
                    a[r][c] -= f * a[col][c]
    return [a[i][n] / a[i][i] for i in range(n)]


def rank(vectors, tol=1e-9):
    vs = [unit(v) for v in vectors if norm(v) > tol]
    if not vs:
        return 0
    basis = [vs[0]]
    for v in vs[1:]:
        if len(basis) == 1 and norm(cross(basis[0], v)) > tol:
            basis.append(v)
        elif len(basis) == 2 and abs(dot(cross(basis[0], basis[1]), v)) > tol * norm(
                cross(basis[0], basis[1])):
            return 3
    return len(basis)


def nullspace(rows, tol=1e-9):
    """Orthonormal basis of {q : row . q = 0 for every row} in R^3."""
    rs = [unit(r) for r in rows if norm(r) > tol]
    if not rs:
        return [(1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0)]
    r0 = rs[0]
    second = None
    for r in rs[1:]:
        c = cross(r0, r)
        if norm(c) > tol:
            second = r
            break
    if second is None:
        # rank 1: the plane orthogonal to r0
        helper = (1.0, 0.0, 0.0) if abs(r0[0]) < 0.9 else (0.0, 1.0, 0.0)
        u = unit(cross(r0, helper))
        v = unit(cross(r0, u))
        return [u, v]
    d = unit(cross(r0, second))
    for r in rs:
        if abs(dot(r, d)) > tol:
            return []
    return [d]


def dedupe(vectors, tol=1e-9):
    out = []
    for v in vectors:
        if all(norm(sub(v, w)) > tol for w in out):
            out.append(v)
    return out


# ---- cones -----------------------------------------------------------------

def cone_from_halfspaces(eqs, ineqs):
    """Generators of the closed cone {q : e.q = 0, r.q >= 0} in R^3.

    Returns (lineality basis, other generators).  Every extreme ray of the
    pointed part lies on the null space of two independent rows (constraint
    rows or lineality vectors), so cross products of pairs find them all."""
    rows = list(eqs) + list(ineqs)
    lin = nullspace(rows)
    if len(lin) == 3:
        return lin, []
    pool = [unit(r) for r in rows if norm(r) > 1e-12] + lin
    cands = []
    for a, b in itertools.combinations(pool, 2):
        c = cross(a, b)
        if norm(c) > 1e-9:
            c = unit(c)
            cands += [c, mul(-1, c)]
    keep = []
    for c in cands:
        if any(abs(dot(l, c)) > 1e-9 for l in lin):
            continue
        if any(abs(dot(e, c)) > 1e-9 * norm(e) for e in eqs):
            continue
        if any(dot(r, c) < -1e-9 * norm(r) for r in ineqs):
            continue
        keep.append(c)
    return lin, dedupe(keep)


class Cone:
    """A closed polyhedral cone in R^3 given by generators (any space)."""

    def __init__(self, generators):
        self.generators = dedupe([unit(g) for g in generators if norm(g) > 1e-14])
        self.dimension = rank(self.generators)
        self.facets = []
        if self.dimension == 3:
            facets = []
            for a, b in itertools.combinations(self.generators, 2):
                c = cross(a, b)
                if norm(c) <= 1e-9:
                    continue
                c = unit(c)
                for f in (c, mul(-1, c)):
                    if all(dot(f, g) <= 1e-10 for g in self.generators):
                        facets.append(f)
            self.facets = dedupe(facets)
        # equalities (orthonormal complement of the span), for dimension < 3
        if self.dimension == 0:
            self.equalities = [(1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0)]
        elif self.dimension == 1:
            self.equalities = nullspace([self.generators[0]])
        elif self.dimension == 2:
            span = None
            for a, b in itertools.combinations(self.generators, 2):
                if norm(cross(a, b)) > 1e-9:
                    span = unit(cross(a, b))
                    break
            self.equalities = [span]
        else:
            self.equalities = []

    @property
    def whole_space(self):
        return self.dimension == 3 and not self.facets

    def distance(self, x):
        """Euclidean distance from x to the cone (NNLS by subsets)."""
        if self.dimension == 3 and all(dot(f, x) <= 1e-13 for f in self.facets):
            return 0.0
        best = norm(x)  # the apex
        gens = self.generators
        for k in (1, 2, 3):
            for sub_ in itertools.combinations(gens, k):
                gram = [[dot(a, b) for b in sub_] for a in sub_]
                rhs = [dot(a, x) for a in sub_]
                coef = solve(gram, rhs)
                if coef is None or min(coef) < -1e-13:
                    continue
                p = (0.0, 0.0, 0.0)
                for c, g in zip(coef, sub_):
                    p = add(p, mul(c, g))
                best = min(best, norm(sub(x, p)))
        return best

    def depth(self, x):
        """Distance from a point x of the cone to the cone's complement."""
        if self.dimension < 3:
            return 0.0
        if not self.facets:
            return math.inf
        return max(0.0, min(-dot(f, x) for f in self.facets))

    def signed(self, x):
        d = self.distance(x)
        if d > 1e-12:
            return d
        return -self.depth(x)

    def contains(self, x, tol=1e-9):
        return self.distance(x) <= tol * max(1.0, norm(x))


# ---- the fixture ------------------------------------------------------------

def polygon_moments(vertices):
    """Signed area, centroid, polar second moment about the centroid (unit
    density)."""
    a = cx = cy = j = 0.0
    n = len(vertices)
    for i in range(n):
        x0, y0 = vertices[i]
        x1, y1 = vertices[(i + 1) % n]
        c = x0 * y1 - x1 * y0
        a += c
        cx += (x0 + x1) * c
        cy += (y0 + y1) * c
        j += c * (x0 * x0 + x0 * x1 + x1 * x1 + y0 * y0 + y0 * y1 + y1 * y1)
    a /= 2
    cx /= 6 * a
    cy /= 6 * a
    j /= 12
    area = abs(a)
    return a, (cx, cy), abs(j) - area * (cx * cx + cy * cy)


class Fixel:
    pass


class Model:
    """docs/MODEL.md sections 1-5 for one fixture dict (the wire form of docs/PROTOCOL.md)."""

    def __init__(self, fixture):
        body = fixture["body"]
        self.mass = float(body["mass"])
        shape = body.get("shape")
        centroid = None
        self.shape = shape
        if shape and shape["type"] == "circle":
            c = tuple(map(float, shape["center"]))
            r = float(shape["radius"])
            centroid = c
            area = math.pi * r * r
            polar = area * r * r / 2
        elif shape and shape["type"] == "polygon":
            verts = [tuple(map(float, v)) for v in shape["vertices"]]
            signed, centroid, polar = polygon_moments(verts)
            area = abs(signed)
            self.orientation = 1 if signed > 0 else -1
            self.vertices = verts
        self.com = tuple(map(float, body["com"])) if "com" in body else centroid
        if "inertia" in body:
            self.inertia = float(body["inertia"])
        else:
            d2 = (self.com[0] - centroid[0]) ** 2 + (self.com[1] - centroid[1]) ** 2
            self.inertia = self.mass * (polar / area + d2)
        self.rho = math.sqrt(self.inertia / self.mass)
        gf = fixture.get("friction")
        self.fixels = []
        for fx in fixture["fixels"]:
            f = Fixel()
            f.at = tuple(map(float, fx["at"]))
            if "normal" in fx:
                f.normal = unit(tuple(map(float, fx["normal"])))
            else:
                f.normal = self._inward_normal(f.at)
            f.tangent = (-f.normal[1], f.normal[0])
            fr = fx.get("friction", gf)
            f.mu_s = float(fr["static"])
            f.mu_k = float(fr.get("kinetic", fr["static"]))
            r = sub(f.at, self.com)
            f.Wn = (f.normal[0], f.normal[1], cross2(r, f.normal))
            f.Wt = (f.tangent[0], f.tangent[1], cross2(r, f.tangent))
            self.fixels.append(f)
        self.k = len(self.fixels)
        self._cones = {}
        # docs/PROTOCOL.md, units: forces in the fixture's force unit, the
        # acceleration in its length unit per s^2; M q is in kg length/s^2,
        # force_factor of them to one force unit (1 N = 1000 kg mm/s^2).
        units = fixture.get("units")
        self.force_factor = 1.0
        if units:
            metres = {"mm": 1e-3, "m": 1.0, "in": 0.0254}[units["length"]]
            newtons = {"N": 1.0, "mN": 1e-3, "lbf": 4.4482216152605}[units["force"]]
            self.force_factor = newtons / metres

    def _inward_normal(self, at):
        shape = self.shape
        if shape["type"] == "circle":
            return unit(sub(tuple(map(float, shape["center"])), at))
        best = None
        n = len(self.vertices)
        for i in range(n):
            a, b = self.vertices[i], self.vertices[(i + 1) % n]
            d = sub(b, a)
            t = max(0.0, min(1.0, dot(sub(at, a), d) / dot(d, d)))
            p = add(a, mul(t, d))
            dist = norm(sub(at, p))
            if best is None or dist < best[0]:
                best = (dist, d)
        d = unit(best[1])
        o = self.orientation
        return (-d[1] * o, d[0] * o)

    # ---- units ----
    def scale(self, g):
        """Physical wrench -> scaled (f_x, f_y, tau / rho)."""
        return (g[0], g[1], g[2] / self.rho)

    def unscale_row(self, f):
        """A scaled half-space row -> a unit row in physical units."""
        return unit((f[0], f[1], f[2] / self.rho))

    def unscale(self, h):
        return (h[0], h[1], h[2] * self.rho)

    def force_wrench(self, force, at):
        return (force[0], force[1], cross2(sub(at, self.com), force))

    def newton_euler(self, q, forces):
        """M q - sum_i (W_in c_in + W_it c_it), physical (M q converted to
        the fixture's force unit)."""
        k = self.force_factor
        w = (self.mass * q[0] / k, self.mass * q[1] / k, self.inertia * q[2] / k)
        for f, (cn, ct) in zip(self.fixels, forces):
            w = sub(w, add(mul(cn, f.Wn), mul(ct, f.Wt)))
        return w

    # ---- constraint strings ----
    def rows(self, letters, mode=False, pivot=0):
        """Acceleration rows of a string: (equalities, [(row, strict)]) with
        inequalities meaning row . q >= 0 (> 0 when strict)."""
        eqs, ineqs = [], []
        for f, x in zip(self.fixels, letters):
            if x == "s":
                ineqs.append((f.Wn, mode))
            elif x == "a":
                ineqs.append((mul(-1, f.Wn), True))
            elif x == "u":
                pass
            elif x == "l":
                eqs.append(f.Wn)
                ineqs.append((f.Wt, True))
            elif x == "r":
                eqs.append(f.Wn)
                ineqs.append((mul(-1, f.Wt), True))
            elif x in "nm":
                eqs.append(f.Wn)
                if x == "n":
                    eqs.append(f.Wt)
            else:
                raise ValueError(x)
        if pivot:
            ineqs.append(((0.0, 0.0, float(pivot)), True))
        return eqs, ineqs

    def force_generators(self, letters):
        """(physical wrench, fixel, c_n, c_t) for each friction-cone edge."""
        out = []
        for i, (f, x) in enumerate(zip(self.fixels, letters)):
            if x == "l":
                edges = [-f.mu_k]
            elif x == "r":
                edges = [f.mu_k]
            elif x in "nm":
                edges = [f.mu_s, -f.mu_s]
            else:
                edges = []
            for ct in edges:
                out.append((mul(-1, add(f.Wn, mul(ct, f.Wt))), i, 1.0, ct))
        return out

    def q_cone(self, letters, mode=False, pivot=0):
        eqs, ineqs = self.rows(letters, mode, pivot)
        lin, gens = cone_from_halfspaces(eqs, [r for r, _ in ineqs])
        strict = [r for r, s in ineqs if s]
        allg = lin + [mul(-1, l) for l in lin] + gens
        nonempty = True
        if strict:
            z = (0.0, 0.0, 0.0)
            for g in gens:
                z = add(z, g)
            nonempty = bool(gens) and all(dot(r, z) > 1e-9 * norm(r) for r in strict)
        return allg, nonempty, strict

    def cone(self, letters, mode=False, pivot=0):
        """Closure of G_X in the scaled space (a Cone), or None when empty."""
        key = (letters, mode, pivot)
        if key in self._cones:
            return self._cones[key]
        qg, nonempty, _ = self.q_cone(letters, mode, pivot)
        if not nonempty:
            self._cones[key] = None
            return None
        gens = [self.scale((self.mass * q[0], self.mass * q[1], self.inertia * q[2])) for q in qg]
        gens += [self.scale(g) for g, _, _, _ in self.force_generators(letters)]
        c = Cone(gens)
        self._cones[key] = c
        return c

    def physical_cone(self, letters, mode=False, pivot=0):
        """Closure of G_X in physical units (a Cone), or None when empty."""
        qg, nonempty, _ = self.q_cone(letters, mode, pivot)
        if not nonempty:
            return None
        gens = [(self.mass * q[0], self.mass * q[1], self.inertia * q[2]) for q in qg]
        gens += [g for g, _, _, _ in self.force_generators(letters)]
        return Cone(gens)

    def open_faces(self, letters):
        """For each facet of the closure (physical unit rows): True when the
        facet is open.  A facet is open iff the face of cl(Q_X) it comes from
        has some strict row vanishing on it (or is {0} while strict rows
        exist)."""
        qg, nonempty, strict = self.q_cone(letters)
        pc = self.physical_cone(letters)
        out = []
        for f in pc.facets:
            on = [q for q in qg
                  if abs(dot(f, (self.mass * q[0], self.mass * q[1], self.inertia * q[2]))) <= 1e-9]
            z = (0.0, 0.0, 0.0)
            for q in on:
                z = add(z, q)
            if not strict:
                out.append((f, False))
            elif not on:
                out.append((f, True))
            else:
                out.append((f, not all(dot(r, z) > 1e-9 for r in strict)))
        return out


# ---- the plan (docs/MODEL.md section 3) -------------------------------------------------------

BELOW = {("s", "u"), ("a", "u"), ("l", "m"), ("r", "m"), ("n", "m")}


def letter_below(x, y):
    return x == y or (x, y) in BELOW


def string_below(x, y):
    return all(letter_below(a, b) for a, b in zip(x, y))


def state_text(state, k):
    return "".join("1" if state[i] else "0" for i in range(k))


def plan(k):
    """(states in order [(text, [excluded strings])], kept strings, origins)."""
    states = []
    for count in range(k + 1):
        for touched in itertools.combinations(range(k), count):
            S = set(touched)
            excluded = []
            # backward: every {s, m} assignment on S but all-m, u elsewhere
            for assign in itertools.product("sm", repeat=len(touched)):
                if all(a == "m" for a in assign):
                    continue
                s = ["u"] * k
                for i, a in zip(touched, assign):
                    s[i] = a
                excluded.append("".join(s))
            # self: all-m on S, s elsewhere (none when S is everything)
            if len(touched) < k:
                excluded.append("".join("m" if i in S else "s" for i in range(k)))
            states.append(("".join("1" if i in S else "0" for i in range(k)), excluded))
    everything = []
    for _, ex in states:
        for x in ex:
            if x not in everything:
                everything.append(x)
    kept = [x for x in everything
            if not any(y != x and string_below(x, y) for y in everything)]
    origins = {x: [st for st, ex in states if x in ex] for x in kept}
    return states, kept, origins


# ---- modes (docs/MODEL.md section 4) ------------------------------------------------------------

def strictly_feasible(model, letters, pivot=0):
    _, nonempty, _ = model.q_cone(letters, mode=True, pivot=pivot)
    return nonempty


def modes(model):
    """(feasible mode strings other than n...n, pinned)."""
    k = model.k
    out = []
    for letters in itertools.product("slrn", repeat=k):
        s = "".join(letters)
        if s == "n" * k:
            continue
        if strictly_feasible(model, s):
            out.append(s)
    eqs, _ = model.rows("n" * k)
    pinned = len(nullspace(eqs)) == 0
    if not pinned:
        out += ["n" * k + "+", "n" * k + "-"]
    return out, pinned


def mode_cone(model, name):
    if name.endswith("+"):
        return model.cone(name[:-1], mode=True, pivot=1)
    if name.endswith("-"):
        return model.cone(name[:-1], mode=True, pivot=-1)
    return model.cone(name, mode=True)


def mode_rows(model, name):
    if name.endswith("+"):
        return model.rows(name[:-1], True, 1)
    if name.endswith("-"):
        return model.rows(name[:-1], True, -1)
    return model.rows(name, True)


# ---- classification (docs/MODEL.md section 5) ---------------------------------------

class Answer:
    def __init__(self, margin, blocking, candidates, states):
        self.margin = margin
        self.blocking = blocking          # best cone name, or None
        self.candidates = candidates      # names within 1e-7 of the best
        self.states = states

    def verdict(self, tol=1e-9):
        if self.margin > tol:
            return "inside"
        if self.margin < -tol:
            return "outside"
        return "boundary"

    def __repr__(self):
        return "Answer(margin=%r, blocking=%r, candidates=%r)" % (
            self.margin, self.blocking, self.candidates)


class Classifier:
    def __init__(self, model):
        self.model = model
        self.states, self.kept, self.origins = plan(model.k)
        self.modes, self.pinned = modes(model)
        self.goal = [(x, model.cone(x)) for x in self.kept]
        self.goal = [(x, c) for x, c in self.goal if c is not None]
        self.strong = [(x, mode_cone(model, x)) for x in self.modes]
        self.strong = [(x, c) for x, c in self.strong if c is not None]

    def _margin(self, cones, g):
        h = self.model.scale(g)
        n = norm(h)
        if n == 0:
            return None
        x = mul(1 / n, h)
        signed = [(name, c.signed(x)) for name, c in cones]
        if not signed:
            return 1.0, None, []
        if any(s < 0 for _, s in signed):
            deepest = min(s for _, s in signed)
            margin = max(-1.0, deepest)
            cands = [name for name, s in signed if s <= deepest + 1e-7]
            best = min(signed, key=lambda t: t[1])[0]
            return margin, best, cands
        nearest = min(s for _, s in signed)
        cands = [name for name, s in signed if s <= nearest + 1e-7]
        best = min(signed, key=lambda t: t[1])[0]
        return min(1.0, nearest), best, cands

    def classify(self, g, which):
        if which == "goal":
            m, b, c = self._margin(self.goal, g)
            st = sorted({s for x in c for s in self.origins.get(x, [])})
            return Answer(m, b, c, st)
        if which == "strong":
            m, b, c = self._margin(self.strong, g)
            return Answer(m, b, c, [])
        a, b = self.classify(g, "goal"), self.classify(g, "strong")
        if abs(a.margin - b.margin) <= 1e-7:
            return Answer(min(a.margin, b.margin), a.blocking, a.candidates + b.candidates, a.states)
        return a if a.margin < b.margin else b


# ---- the outline and the push wrench (docs/MODEL.md section 6) ---------------------------------
#
# Independent of the daemon: a polygon's edge i runs from vertex i to vertex
# i + 1, t the fraction along it; a circle is edge 0, t the boundary angle in
# degrees counter-clockwise from +x about the centre.  The inward normal of a
# polygon edge is its direction turned +90 degrees for a counter-clockwise
# outline (the interior is on the left), -90 degrees for a clockwise one.

def edge_count(model):
    return 1 if model.shape["type"] == "circle" else len(model.vertices)


def edge_range(model):
    """The range of the parameter t on an edge: 360 degrees or 1."""
    return 360.0 if model.shape["type"] == "circle" else 1.0


def boundary_point(model, edge, t):
    """(point, inward unit normal) at parameter t of edge `edge`."""
    if model.shape["type"] == "circle":
        c = tuple(map(float, model.shape["center"]))
        r = float(model.shape["radius"])
        a = math.radians(t)
        u = (math.cos(a), math.sin(a))
        return (c[0] + r * u[0], c[1] + r * u[1]), (-u[0], -u[1])
    n = len(model.vertices)
    a, b = model.vertices[edge], model.vertices[(edge + 1) % n]
    d = sub(b, a)
    p = (a[0] + t * d[0], a[1] + t * d[1])
    L = norm(d)
    o = model.orientation
    return p, (-d[1] * o / L, d[0] * o / L)


def edge_length(model, edge):
    if model.shape["type"] == "circle":
        return 2 * math.pi * float(model.shape["radius"])
    n = len(model.vertices)
    return norm(sub(model.vertices[(edge + 1) % n], model.vertices[edge]))


def perimeter(model):
    return sum(edge_length(model, e) for e in range(edge_count(model)))


def region_length(model, edge, t0, t1):
    """Boundary length between parameters t0 < t1 of one edge."""
    return edge_length(model, edge) * (t1 - t0) / edge_range(model)


def push_wrench(model, edge, t, finger=0.0):
    """The wrench of a unit normal push at (edge, t): (nu, (p - x_c) x nu);
    with `finger` != 0, of the force nu + finger * tangent instead (a friction
    cone edge of a finger with coefficient |finger|)."""
    p, nu = boundary_point(model, edge, t)
    f = (nu[0] - finger * nu[1], nu[1] + finger * nu[0])
    return model.force_wrench(f, p)


def gravity_wrench(model, phi_deg, g0=9.81):
    a = math.radians(phi_deg)
    return (model.mass * g0 * math.cos(a), model.mass * g0 * math.sin(a), 0.0)
