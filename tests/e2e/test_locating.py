"""fixture.locating against numbers derived here, independently of the
daemon: the 3-2-1 plate's G^-1 worked by hand, the rotation t/L when one
locator moves by t, Monte Carlo over 100,000 perturbed fixtures (each pose
solved exactly, vectorised) against the covariance, the ellipses and the
linear worst case, the exact worst case against a pose solved here from
three distance equations written in the fixture's frame (the part moved,
not the locators moved back as the daemon does), the free motion of
fixtures that do not locate, and every refusal with its field."""

import json
import math
import os
import subprocess

import numpy as np
import pytest

from conftest import REPO

WRENCHCTL = os.path.join(REPO, "build", "wrenchctl")
CHI2 = -2 * math.log(0.0027)

# The 3-2-1 plate: a 4 x 2 rectangle, fixels 1 and 2 under it at x = 1 and
# x = 3, fixel 3 against its left side at y = 1; centre of mass (2, 1).
PLATE = {
    "body": {"mass": 2.0, "shape": {"type": "polygon",
                                    "vertices": [[0, 0], [4, 0], [4, 2], [0, 2]]}},
    "friction": {"static": 0.3},
    "fixels": [{"at": [1, 0]}, {"at": [3, 0]}, {"at": [0, 1]}],
}
# G's rows (n_i, (p_i - c) x n_i) by hand: fixel 1 (0, 1, -1), fixel 2
# (0, 1, 1), fixel 3 (1, 0, 0).  So e_3 = dx, e_1 = dy - dtheta,
# e_2 = dy + dtheta, and
#   dx = e_3,  dy = (e_1 + e_2) / 2,  dtheta = (e_2 - e_1) / 2:
PLATE_INVERSE = [[0, 0, 1], [0.5, 0.5, 0], [-0.5, 0.5, 0]]

with open(os.path.join(REPO, "examples", "bracket.json")) as f:
    BRACKET = json.load(f)


def locating(client, fixture, tolerance, features=None, **extra):
    params = {"fixture": fixture, "tolerance": tolerance}
    if features is not None:
        params["features"] = features
    params.update(extra)
    return client.result("fixture.locating", params)


def refusal(client, params, field):
    error = client.error("fixture.locating", params)
    assert error["code"] == -32602 and error["data"]["field"] == field, error
    return error["data"]["reason"]


# ---- the pose solved here ----------------------------------------------------------

def rot(theta):
    c, s = math.cos(theta), math.sin(theta)
    return np.array([[c, -s], [s, c]])


def moved(pose, com, x):
    """The part point x at pose (dx, dy, dtheta) about com."""
    return com + pose[:2] + rot(pose[2]) @ (np.asarray(x, float) - com)


def solve_pose(contacts, com, e, normals, points):
    """The pose putting each moved locator L_i = p_i + e_i n_i on the moved
    part: for a line through a (unit normal m), the moved line's distance
    to L_i; for a circle (centre C, radius r), |L_i - moved C| - r.  Newton
    with a central-difference Jacobian, from the nominal pose."""
    com = np.asarray(com, float)

    def residual(z):
        out = []
        for (kind, a, b), p, n, ei in zip(contacts, points, normals, e):
            L = np.asarray(p, float) + ei * np.asarray(n, float)
            if kind == "line":
                m = rot(z[2]) @ np.asarray(b, float)
                out.append(m @ (L - moved(z, com, a)))
            else:
                out.append(np.linalg.norm(L - moved(z, com, a)) - b)
        return np.array(out)

    return newton(residual)


def newton(residual):
    """The root of three equations near the nominal pose: Newton with a
    central-difference Jacobian, its residual checked."""
    z = np.zeros(3)
    for _ in range(50):
        f = residual(z)
        if np.max(np.abs(f)) < 1e-15:
            break
        jac = np.zeros((3, 3))
        for j in range(3):
            h = np.zeros(3)
            h[j] = 1e-7
            jac[:, j] = (residual(z + h) - residual(z - h)) / 2e-7
        z = z - np.linalg.solve(jac, f)
    assert np.max(np.abs(residual(z))) < 1e-13
    return z


def vertices(tolerance):
    k = len(tolerance)
    for v in range(1 << k):
        yield np.array([tolerance[i] if v >> i & 1 else -tolerance[i] for i in range(k)])


# ---- closed forms ------------------------------------------------------------------

def test_plate_inverse_by_hand(client):
    r = locating(client, PLATE, 0.01, [{"name": "corner", "at": [4, 2]}])
    assert r["deterministic"] is True and r["free_motion"] is None
    assert np.allclose(r["sensitivity"], PLATE_INVERSE, atol=1e-15)
    # The condition number of the scaled matrix, rho = sqrt(I / m) =
    # sqrt((4^2 + 2^2) / 12): its singular values by numpy.
    rho = math.sqrt(20 / 12)
    scaled = np.array([[0, 1, -1 / rho], [0, 1, 1 / rho], [1, 0, 0]])
    s = np.linalg.svd(scaled, compute_uv=False)
    assert r["condition"] == pytest.approx(s[0] / s[-1], rel=1e-12)
    # Linear worst over the box: sum of |G^-1_ji| t.
    assert r["pose_error"]["linear"] == pytest.approx([0.01, 0.01, 0.01], rel=1e-14)
    # The corner (4, 2) moves by (dx - dtheta * 1, dy + dtheta * 2):
    # (e3 - (e2 - e1)/2, (e1 + e2)/2 + (e2 - e1)) = (e3 + e1/2 - e2/2, -e1/2 + 3 e2/2),
    # worst at e = (-t, t, -t) or its negative: |(-2t, 2t)| = 2 sqrt(2) t.
    f = r["features"][0]
    assert f["linear"]["length"] == pytest.approx(2 * math.sqrt(2) * 0.01, rel=1e-14)
    sigma2 = (0.01 / 3) ** 2
    cov = np.array([[1 + 0.25 + 0.25, -0.25 - 0.75], [-0.25 - 0.75, 0.25 + 2.25]]) * sigma2
    assert np.allclose(f["covariance"], cov, rtol=1e-13, atol=0)


@pytest.mark.parametrize("t", [1e-3, 0.02, 0.1])
def test_rotation_t_over_l(client, t):
    """Fixel 1, the left one under the plate, moves by t, the others by
    nothing: the plate turns by t / L linearly, L = 2 between the bottom
    locators, and by atan(t / L) exactly (its bottom edge passes through
    (1, t) and (3, 0))."""
    r = locating(client, PLATE, [t, 0, 0])
    assert r["pose_error"]["linear"][2] == pytest.approx(t / 2, rel=1e-14)
    assert r["pose_error"]["exact"][2] == pytest.approx(math.atan(t / 2), rel=1e-12)
    assert r["pose_error"]["exact"][2] != pytest.approx(t / 2, rel=1e-6) or t < 2e-3


def test_disc_with_two_fixels(client):
    """The disc in the corner: G = I on (dx, dy), dtheta 0; exactly, the
    centre moves so that each moved locator is 1 from it."""
    with open(os.path.join(REPO, "examples", "disc-corner.json")) as f:
        disc = json.load(f)
    r = locating(client, disc, [0.05, 0.1], [{"at": [0, 1]}])
    assert np.allclose(r["sensitivity"], [[1, 0], [0, 1], [0, 0]], atol=1e-15)
    assert r["pose_error"]["linear"] == pytest.approx([0.05, 0.1, 0], abs=1e-15)
    worst = np.zeros(2)
    for e in vertices([0.05, 0.1]):
        # |(-1 + e1, 0) - d| = 1 and |(0, -1 + e2) - d| = 1, near d = e.
        d = np.array(e, float)
        for _ in range(50):
            a = np.array([-1 + e[0], 0.0]) - d
            b = np.array([0.0, -1 + e[1]]) - d
            f = np.array([np.linalg.norm(a) - 1, np.linalg.norm(b) - 1])
            jac = -np.array([a / np.linalg.norm(a), b / np.linalg.norm(b)])
            d = d - np.linalg.solve(jac, f)
        worst = np.maximum(worst, np.abs(d))
    assert r["pose_error"]["exact"][:2] == pytest.approx(list(worst), rel=1e-11)
    assert r["pose_error"]["exact"][2] == 0


# ---- statistics -----------------------------------------------------------------

def test_monte_carlo_plate(client):
    """100,000 fixtures with locators perturbed by independent normal errors
    (sigma = t / 3), each pose solved exactly (vectorised Newton on the three
    line equations): the feature's sample covariance against the daemon's,
    the share inside its 99.73 % ellipse, and uniform errors in the box never
    beyond the linear worst case (and coming close to it)."""
    t = np.array([0.01, 0.02, 0.015])
    feature = np.array([3.5, 1.8])
    r = locating(client, PLATE, list(t), [{"at": list(feature)}])
    f = r["features"][0]
    rng = np.random.default_rng(31)
    n = 100_000
    com = np.array([2.0, 1.0])

    def poses(e):
        # Locators L_i = p_i + e_i n_i; lines of the part y = 0 (fixels 1, 2)
        # and x = 0 (fixel 3).  Moved: a point x goes to com + d + R (x - com);
        # L on the moved line y = 0 iff (R^T (L - com - d))_y + com_y = 0.
        z = np.zeros((len(e), 3))
        L = np.stack([np.stack([1 + 0 * e[:, 0], e[:, 0]], 1),
                      np.stack([3 + 0 * e[:, 1], e[:, 1]], 1),
                      np.stack([e[:, 2], 1 + 0 * e[:, 2]], 1)], 1)
        for _ in range(8):
            c, s = np.cos(z[:, 2]), np.sin(z[:, 2])
            y = L - com - z[:, None, :2]
            # back in the part's frame: R^T y
            qx = c[:, None] * y[..., 0] + s[:, None] * y[..., 1] + com[0]
            qy = -s[:, None] * y[..., 0] + c[:, None] * y[..., 1] + com[1]
            dqx = np.stack([-c[:, None] + 0 * qx, -s[:, None] + 0 * qx,
                            -s[:, None] * y[..., 0] + c[:, None] * y[..., 1]], -1)
            dqy = np.stack([s[:, None] + 0 * qy, -c[:, None] + 0 * qy,
                            -c[:, None] * y[..., 0] - s[:, None] * y[..., 1]], -1)
            res = np.stack([qy[:, 0], qy[:, 1], qx[:, 2]], 1)
            jac = np.stack([dqy[:, 0], dqy[:, 1], dqx[:, 2]], 1)
            z = z - np.linalg.solve(jac, res[..., None])[..., 0]
        return z

    def displacement(z):
        c, s = np.cos(z[:, 2]), np.sin(z[:, 2])
        w = feature - com
        return np.stack([z[:, 0] + c * w[0] - s * w[1] - w[0],
                         z[:, 1] + s * w[0] + c * w[1] - w[1]], 1)

    u = displacement(poses(rng.normal(0, t / 3, size=(n, 3))))
    sample = np.cov(u.T)
    cov = np.array(f["covariance"])
    assert np.allclose(sample, cov, rtol=0.02, atol=0.02 * np.max(np.abs(cov)))
    # The share inside the 99.73 % ellipse: u^T cov^-1 u <= chi2.
    inside = np.mean(np.einsum("ni,ij,nj->n", u, np.linalg.inv(cov), u) <= CHI2)
    assert abs(inside - 0.9973) < 0.001, inside
    # The ellipse's axes and angle are those of cov's eigenvectors.
    lam, vec = np.linalg.eigh(cov)
    assert f["ellipse"]["axes"] == pytest.approx(list(np.sqrt(CHI2 * lam[::-1])), rel=1e-12)
    major = vec[:, 1]
    angle = math.degrees(math.atan2(major[1], major[0]))
    angle = angle - 180 if angle > 90 else angle + 180 if angle <= -90 else angle
    assert f["ellipse"]["angle_deg"] == pytest.approx(angle, abs=1e-9)
    # Uniform errors in the box: no displacement beyond the linear worst
    # case (up to the exact model's second order), and the sample's largest
    # within 3 % of it.
    box = displacement(poses(rng.uniform(-t, t, size=(n, 3))))
    largest = np.max(np.hypot(box[:, 0], box[:, 1]))
    assert largest <= f["linear"]["length"] * (1 + 1e-3)
    assert largest >= 0.97 * f["linear"]["length"]
    linear = np.array(r["sensitivity"]) @ rng.uniform(-t, t, size=(n, 3)).T
    assert np.all(np.max(np.abs(linear), axis=1) <= np.array(r["pose_error"]["linear"]) * (1 + 1e-12))


# ---- exact poses ------------------------------------------------------------------

def bracket_contacts(com):
    """The bracket's fixels: a pin in the hole of radius 6 about (30, 30),
    the bottom edge y = 0, the left edge x = 0."""
    del com
    return [("circle", (30, 30), 6.0), ("line", (0, 0), (0, 1)), ("line", (0, 0), (1, 0))]


@pytest.mark.parametrize("tolerance", [0.02, [0.05, 0.01, 0.2], 0.5])
def test_exact_worst_case_bracket(client, tolerance):
    put = client.result("fixture.put", {"fixture": BRACKET})
    com = np.array(put["com"], float)
    hole, slot = [30.0, 30.0], [85.0, 30.0]
    r = locating(client, put["id"], tolerance, [{"name": "hole", "at": hole}, {"at": slot}])
    t = [tolerance] * 3 if not isinstance(tolerance, list) else tolerance
    points = [f["at"] for f in BRACKET["fixels"]]
    normals = [np.subtract(points[0], (30, 30)) / 6, (0, 1), (1, 0)]
    contacts = bracket_contacts(com)
    worst = np.zeros(3)
    features = [[0.0, None], [0.0, None]]
    for e in vertices(t):
        z = solve_pose(contacts, com, e, normals, points)
        worst = np.maximum(worst, np.abs(z))
        for i, x in enumerate((hole, slot)):
            u = moved(z, com, x) - np.asarray(x)
            if np.linalg.norm(u) > features[i][0]:
                features[i] = [np.linalg.norm(u), u]
    exact = r["pose_error"]["exact"]
    assert exact == pytest.approx(list(worst), rel=1e-9, abs=1e-14)
    for i in range(2):
        got = r["features"][i]["exact"]
        assert got["length"] == pytest.approx(features[i][0], rel=1e-9)
    # The exact pose differs from the linear one by more than the check's
    # tolerance: it is not the linear answer again.
    assert abs(exact[1] - r["pose_error"]["linear"][1]) > 1e-6 * exact[1]


def test_units_lengths_in_the_fixtures_unit(client):
    plate_mm = dict(PLATE, units={"length": "mm", "force": "N"})
    a = locating(client, PLATE, 0.02, [{"at": [4, 2]}])
    b = locating(client, plate_mm, 0.02, [{"at": [4, 2]}])
    assert a == b


# ---- fixtures that do not locate ---------------------------------------------------

def test_free_rotation(client):
    """Normals through one point (2, 1): the plate may turn about it."""
    fixture = dict(PLATE, fixels=[{"at": [2, 0]}, {"at": [0, 1]}, {"at": [2, 2]}])
    r = locating(client, fixture, 0.01, [{"at": [1, 1]}])
    assert r["deterministic"] is False
    m = r["free_motion"]
    assert m["kind"] == "rotation" and m["about"] == pytest.approx([2, 1], abs=1e-12)
    rho = math.sqrt(20 / 12)
    assert m["twist"] == pytest.approx([0, 0, 1 / rho], abs=1e-12)
    assert r["sensitivity"] is None and r["pose_error"] is None and r["features"] is None


def test_free_translation(client):
    fixture = dict(PLATE, fixels=[{"at": [1, 0]}, {"at": [2, 0]}, {"at": [3, 0]}])
    r = locating(client, fixture, 0.01)
    m = r["free_motion"]
    assert r["deterministic"] is False and m["kind"] == "translation" and m["about"] is None
    assert m["twist"] == pytest.approx([1, 0, 0], abs=1e-12)


# ---- refusals ------------------------------------------------------------------

@pytest.mark.parametrize("params, field, words", [
    ({"tolerance": -0.01}, "params.tolerance", "negative"),
    ({"tolerance": [0.01, -1, 0]}, "params.tolerance[1]", "negative"),
    ({"tolerance": [0.01, 0.01]}, "params.tolerance", "3 fixels"),
    ({"tolerance": "0.1"}, "params.tolerance", "number"),
    ({"tolerance": [0.01, "x", 0]}, "params.tolerance[1]", ""),
    ({"tolerance": 0.01, "sigma_ratio": 0}, "params.sigma_ratio", "above 0"),
    ({"tolerance": 0.01, "sigma_ratio": -3}, "params.sigma_ratio", "above 0"),
    ({"tolerance": 0.01, "features": [{"at": [104, 2]}]}, "params.features[0].at",
     "lies 100 outside"),
    ({"tolerance": 0.01, "features": [{"at": [2, 1]}, {"at": [1]}]}, "params.features[1].at", ""),
    ({"tolerance": 0.01, "features": [{"at": [2, 1], "size": 3}]}, "params.features[0].size", ""),
    ({"tolerance": 0.01, "features": {"at": [2, 1]}}, "params.features", "array"),
])
def test_bad_input(client, params, field, words):
    reason = refusal(client, dict(params, fixture=PLATE), field)
    assert words in reason, reason


def test_non_finite_tolerance(client):
    client.send_line('{"jsonrpc":"2.0","id":7,"method":"fixture.locating","params":'
                     '{"fixture":%s,"tolerance":1e999}}' % json.dumps(PLATE))
    resp = client.read_json()
    assert "error" in resp and resp["error"]["data"]["field"].startswith("params"), resp


@pytest.mark.parametrize("fixels, words", [
    ([{"at": [1, 0]}, {"at": [0, 1]}], "1 more is missing"),
    ([{"at": [1, 0]}], "2 more are missing"),
    ([{"at": [1, 0]}, {"at": [3, 0]}, {"at": [0, 1]}, {"at": [4, 1]}], "over-constrain"),
])
def test_out_of_scope(client, fixels, words):
    reason = refusal(client, {"fixture": dict(PLATE, fixels=fixels), "tolerance": 0.01},
                     "params.fixture.fixels")
    assert words in reason, reason


def test_two_fixels_name_the_motion_left(client):
    # Under the plate at x = 1 and against its left side at y = 1: normals
    # meet at (1, 1), about which it may still turn.
    reason = refusal(client, {"fixture": dict(PLATE, fixels=[{"at": [1, 0]}, {"at": [0, 1]}]),
                              "tolerance": 0.01}, "params.fixture.fixels")
    assert "turn about (1, 1)" in reason, reason


def test_tilted_normal_on_an_edge(client):
    fixture = dict(PLATE, fixels=[{"at": [1, 0], "normal": [0.1, 1]}, {"at": [3, 0]},
                                  {"at": [0, 1]}])
    reason = refusal(client, {"fixture": fixture, "tolerance": 0.01},
                     "params.fixture.fixels[0].normal")
    assert "degrees off" in reason


def test_no_shape(client):
    fixture = {"body": {"mass": 1, "inertia": 1, "com": [0, 0]}, "friction": {"static": 0.3},
               "fixels": [{"at": [1, 0], "normal": [-1, 0]}, {"at": [0, 1], "normal": [0, -1]},
                          {"at": [-1, 0], "normal": [1, 0]}]}
    refusal(client, {"fixture": fixture, "tolerance": 0.01}, "params.fixture.body.shape")


# ---- clients ---------------------------------------------------------------------

def test_python_client(daemon):
    import sys
    sys.path.insert(0, os.path.join(REPO, "clients", "python"))
    import wrenchd
    with wrenchd.Client(daemon.path) as c:
        r = c.locating(PLATE, 0.01, [("corner", (4, 2))], sigma_ratio=3)
    assert r.deterministic and np.allclose(r.sensitivity, PLATE_INVERSE, atol=1e-15)
    assert r.features[0]["name"] == "corner"


def test_wrenchctl_table_and_picture(tmp_path):
    fixture = dict(BRACKET, units={"length": "mm", "force": "N"})
    path = tmp_path / "bracket.json"
    path.write_text(json.dumps(fixture))
    svg = tmp_path / "b.svg"
    out = subprocess.run([WRENCHCTL, "--local", "locate", str(path), "--tolerance", "0.02",
                          "--feature", "hole=30,30", "--feature", "85,30", "--svg", str(svg)],
                         capture_output=True, text=True, check=True).stdout
    assert "units: lengths in mm" in out and "dx [mm]" in out and "dtheta [rad]" in out
    assert "hole" in out and "features [mm]" in out
    picture = svg.read_text()
    assert picture.count('class="error-ellipse"') == 2
    assert 'class="displaced"' in picture and "magnified" in picture
    bad = subprocess.run([WRENCHCTL, "--local", "locate", str(path), "--tolerance", "-1"],
                         capture_output=True, text=True)
    assert bad.returncode == 2 and "--tolerance" in bad.stderr


def test_readme_quotes_wrenchctl():
    """README.md's "Where the part ends up": the command's table as it
    prints today, word for word."""
    with open(os.path.join(REPO, "README.md")) as f:
        text = f.read()
    section = text.split("## Where the part ends up", 1)[1].split("\n## ", 1)[0]
    block = section.split("```\n", 2)[1]
    command, quoted = block.split("\n", 1)
    argv = command[2:].split()
    assert argv[0] == "build/wrenchctl"
    argv = [os.path.join(REPO, argv[0])] + argv[1:argv.index("--svg")]
    out = subprocess.run(argv, cwd=REPO, capture_output=True, text=True, check=True).stdout
    assert out == quoted
    assert "at most 0.0479 " in section and "0.0477 by the" in section and "0.86 mrad" in section
    hole = [line for line in out.splitlines() if line.strip().startswith("hole")][0].split()
    assert hole[3] == "0.0476815" and hole[6] == "0.047874"


def test_locator_passes_onto_the_next_segment(client):
    """Fixel 2 under the bracket 0.1 before its bottom edge ends in the
    rounded corner (an arc of radius 8 about (112, 8)): with +-0.5 the
    part slides along it far enough that the locator's foot passes onto
    the arc, which the solve here decides by itself (line first, then the
    arc if the foot lies beyond x = 112)."""
    fixture = dict(BRACKET, fixels=[BRACKET["fixels"][0], {"at": [111.9, 0]}, {"at": [0, 40]}])
    put = client.result("fixture.put", {"fixture": fixture})
    com = np.array(put["com"], float)
    t = [0.5, 0.5, 0.5]
    r = locating(client, put["id"], t)
    points = [f["at"] for f in fixture["fixels"]]
    normals = [np.subtract(points[0], (30, 30)) / 6, (0, 1), (1, 0)]
    worst = np.zeros(3)
    passed = 0
    for e in vertices(t):
        contacts = [("circle", (30, 30), 6.0), ("line", (0, 0), (0, 1)), ("line", (0, 0), (1, 0))]
        z = solve_pose(contacts, com, e, normals, points)
        # The locator's foot in the part's frame.
        L = np.asarray(points[1]) + e[1] * np.asarray(normals[1])
        foot = com + rot(-z[2]) @ (L - com - z[:2])
        if foot[0] > 112:
            passed += 1
            contacts[1] = ("circle", (112, 8), 8.0)
            z = solve_pose(contacts, com, e, normals, points)
        worst = np.maximum(worst, np.abs(z))
    assert passed > 0
    assert r["pose_error"]["exact"] == pytest.approx(list(worst), rel=1e-9, abs=1e-14)


def test_locator_at_a_corner(client):
    """A locator face against a corner of the chamfered plate (its top
    left corner (0, 2), normal (1, -0.5) normalised): the corner stays on
    the moved face, n . (moved corner - L) = 0."""
    n3 = np.array([1, -0.5]) / math.hypot(1, 0.5)
    fixture = {"body": {"mass": 2, "shape": {"type": "polygon", "vertices":
                                             [[0, 0], [4, 0], [4, 1], [3, 2], [0, 2]]}},
               "friction": {"static": 0.1},
               "fixels": [{"at": [1, 0]}, {"at": [3, 0]}, {"at": [0, 2], "normal": list(n3)}]}
    put = client.result("fixture.put", {"fixture": fixture})
    com = np.array(put["com"], float)
    t = [0.05, 0.02, 0.1]
    r = locating(client, put["id"], t)
    points = [f["at"] for f in fixture["fixels"]]
    normals = [(0, 1), (0, 1), n3]

    def solve(e):
        def residual(z):
            out = []
            for i in range(2):
                L = np.asarray(points[i], float) + e[i] * np.asarray(normals[i], float)
                m = rot(z[2]) @ np.array([0.0, 1.0])
                out.append(m @ (L - moved(z, com, (0, 0))))
            L = np.asarray(points[2], float) + e[2] * n3
            out.append(n3 @ (moved(z, com, (0, 2)) - L))
            return np.array(out)
        return newton(residual)

    worst = np.max([np.abs(solve(e)) for e in vertices(t)], axis=0)
    assert r["pose_error"]["exact"] == pytest.approx(list(worst), rel=1e-9, abs=1e-14)


# ---- design for accuracy -----------------------------------------------------------

CHAMFERED = {"mass": 2, "shape": {"type": "polygon",
                                  "vertices": [[0, 0], [4, 0], [4, 1], [3, 2], [0, 2]]}}
SITES = [[0.5, 0], [1.5, 0], [2.5, 0], [3.5, 0], [4, 0.5], [3.5, 1.5], [1.5, 2], [0, 1.5],
         [0, 0.5]]


@pytest.mark.parametrize("features", [[{"name": "hole", "at": [2.5, 1.2]}, {"at": [1, 1.8]}],
                                      None])
def test_design_accuracy_against_brute_force(client, features):
    """fixture.design with objective accuracy against every candidate judged
    here: put (refused: degenerate; not pinned: unpinned), push.regions of
    goal (empty: no seating push), then the worst error -- the features'
    largest exact length by fixture.locating, or without features the
    largest exact pose in the scaled metric, each corner's pose solved
    here -- ranked by it, ties by candidate number."""
    from itertools import combinations
    t = 0.01
    params = {"body": CHAMFERED, "friction": 0.1, "sites": [{"at": s} for s in SITES],
              "objective": "accuracy", "tolerance": t, "top": 6}
    if features:
        params["features"] = features
    answer = client.result("fixture.design", params)
    rho = math.sqrt(locate_rho_squared(client))
    judged, counts = [], {"degenerate": 0, "unpinned": 0, "no_seating_push": 0}
    for number, chosen in enumerate(combinations(range(len(SITES)), 3)):
        fixture = {"body": CHAMFERED, "friction": {"static": 0.1},
                   "fixels": [{"at": SITES[i]} for i in chosen]}
        put = client.call("fixture.put", {"fixture": fixture})
        if "error" in put:
            counts["degenerate"] += 1
            continue
        if not put["result"]["pinned"]:
            counts["unpinned"] += 1
            continue
        if not client.result("push.regions", {"fixture": fixture, "set": "goal"})["regions"]:
            counts["no_seating_push"] += 1
            continue
        if features:
            r = locating(client, fixture, t, features)
            worst = max(f["exact"]["length"] for f in r["features"])
        else:
            # The pose's worst in the scaled metric: each corner of the box
            # alone (a box of one point: tolerance 0 there), its exact pose.
            worst = 0
            for e in vertices([t, t, t]):
                worst = max(worst, corner_pose_scaled(client, fixture, e, rho))
        judged.append((-worst, number, [SITES[i] for i in chosen]))
    judged.sort(key=lambda j: (-j[0], j[1]))
    for key in counts:
        assert answer["counts"][key] == counts[key], (key, answer["counts"])
    designs = answer["designs"]
    assert len(designs) == 6
    for d, (score, number, fixels) in zip(designs, judged):
        assert d["candidate"] == number
        assert [f["at"] for f in d["fixels"]] == fixels
        assert d["score"] == pytest.approx(score, rel=1e-9, abs=1e-15)
        assert d["accuracy"] == pytest.approx(-score, rel=1e-9, abs=1e-15)


def test_design_pareto_against_brute_force(client):
    """fixture.design with objective pareto against the front made here:
    every candidate's three figures asked of the other objectives (margin,
    accuracy, force, each listing every candidate it scores), the front the
    candidates no other beats on all three together, each listed with its
    figures."""
    t = 0.01
    cases = [{"loads": [{"gravity": {"g": 9.81, "direction_deg": 270}}]}]
    base = {"body": CHAMFERED, "friction": 0.1, "sites": [{"at": s} for s in SITES],
            "top": 84}
    figures = {}
    for objective, extra in (("margin", {}), ("accuracy", {"tolerance": t}),
                             ("force", {"cases": cases})):
        answer = client.result("fixture.design", dict(base, objective=objective, **extra))
        figures[objective] = {d["candidate"]: d for d in answer["designs"]}
    scored = set(figures["margin"]) & set(figures["accuracy"])
    three = {}
    for c in scored:
        force = figures["force"].get(c)
        three[c] = (figures["margin"][c]["score"], figures["accuracy"][c]["accuracy"],
                    -force["score"] if force else math.inf)

    def beats(a, b):
        return (a[0] >= b[0] and a[1] <= b[1] and a[2] <= b[2]) and a != b

    front = {c for c in three if not any(beats(three[o], three[c]) for o in three)}
    answer = client.result("fixture.design", dict(base, objective="pareto", tolerance=t,
                                                  cases=cases))
    assert answer["objective"] == "pareto"
    got = {d["candidate"]: d for d in answer["designs"]}
    assert set(got) == front and 1 < len(front) < len(three), (sorted(got), sorted(front))
    margins = [d["pareto"]["margin"] for d in answer["designs"]]
    assert margins == sorted(margins, reverse=True)
    for c, d in got.items():
        m, a, f = three[c]
        assert d["pareto"]["margin"] == pytest.approx(m, rel=1e-12, abs=1e-15)
        assert d["pareto"]["accuracy"] == pytest.approx(a, rel=1e-12, abs=1e-15)
        if math.isinf(f):
            assert d["pareto"]["force"] is None
        else:
            assert d["pareto"]["force"] == pytest.approx(f, rel=1e-9)
        assert d["score"] == d["pareto"]["margin"]


def locate_rho_squared(client):
    put = client.result("fixture.put", {"fixture": {"body": CHAMFERED,
                                                    "friction": {"static": 0.1},
                                                    "fixels": [{"at": [1, 0]}]}})
    return put["inertia"] / CHAMFERED["mass"]


def corner_pose_scaled(client, fixture, e, rho):
    """|(dx, dy, rho dtheta)| of the exact pose, solved here from the three
    line equations, when locator i is off by e_i (a corner of the box)."""
    put = client.result("fixture.put", {"fixture": fixture})
    com = np.array(put["com"], float)
    got = client.result("fixture.get", {"id": put["id"]})
    points = [f["at"] for f in got["fixels"]]
    normals = [f["normal"] for f in got["fixels"]]
    vertices_ = CHAMFERED["shape"]["vertices"]
    contacts = []
    for p, n in zip(points, normals):
        # the edge holding p: its start and its unit normal
        for a, b in zip(vertices_, vertices_[1:] + vertices_[:1]):
            d = np.subtract(b, a)
            if abs(np.cross(d, np.subtract(p, a))) < 1e-12 and \
                    -1e-12 <= np.dot(np.subtract(p, a), d) <= np.dot(d, d) + 1e-12:
                contacts.append(("line", a, np.array([-d[1], d[0]]) / np.linalg.norm(d)))
                break
    z = solve_pose(contacts, com, e, normals, points)
    return math.hypot(math.hypot(z[0], z[1]), rho * z[2])


@pytest.mark.parametrize("extra, field, words", [
    ({"objective": "accuracy"}, "params.tolerance", "required"),
    ({"objective": "accuracy", "tolerance": -1}, "params.tolerance", "negative"),
    ({"tolerance": 0.01}, "params.tolerance", "objective \"accuracy\""),
    ({"objective": "accuracy", "tolerance": 0.01, "fixels": 4}, "params.fixels", "must be 3"),
    ({"objective": "accuracy", "tolerance": 0.01, "features": [{"at": [40, 1]}]},
     "params.features[0].at", "lies 36 outside"),
    ({"objective": "accuracy", "tolerance": 0.01, "features": [{"at": [1, 1], "x": 1}]},
     "params.features[0].x", ""),
])
def test_design_accuracy_refusals(client, extra, field, words):
    params = dict({"body": CHAMFERED, "friction": 0.1, "sites": [{"at": s} for s in SITES]},
                  **extra)
    error = client.error("fixture.design", params)
    assert error["code"] == -32602 and error["data"]["field"] == field, error
    assert words in error["data"]["reason"], error


def test_design_accuracy_refuses_a_disc(client):
    body = {"mass": 1, "shape": {"type": "circle", "center": [0, 0], "radius": 1}}
    error = client.error("fixture.design", {"body": body, "friction": 0.1, "spacing": 0.5,
                                            "objective": "accuracy", "tolerance": 0.01})
    assert error["data"]["field"] == "params.objective" and "disc" in error["data"]["reason"]


def test_python_client_design_accuracy(daemon, client):
    import sys
    sys.path.insert(0, os.path.join(REPO, "clients", "python"))
    import wrenchd
    direct = client.result("fixture.design", {
        "body": CHAMFERED, "friction": 0.1, "sites": [{"at": s} for s in SITES],
        "objective": "accuracy", "tolerance": 0.01, "features": [{"at": [2.5, 1.2]}], "top": 2})
    with wrenchd.Client(daemon.path) as c:
        r = c.design(CHAMFERED, 0.1, sites=SITES, objective="accuracy", tolerance=0.01,
                     features=[(2.5, 1.2)], top=2)
    assert [d.accuracy for d in r.designs] == [d["accuracy"] for d in direct["designs"]]
    assert r.designs[0].accuracy == -r.designs[0].score > 0
    cases = [{"loads": [{"gravity": {"g": 9.81, "direction_deg": 270}}]}]
    direct = client.result("fixture.design", {
        "body": CHAMFERED, "friction": 0.1, "sites": [{"at": s} for s in SITES],
        "objective": "pareto", "tolerance": 0.01, "cases": cases, "top": 100})
    with wrenchd.Client(daemon.path) as c:
        r = c.design(CHAMFERED, 0.1, sites=SITES, objective="pareto", tolerance=0.01,
                     cases=cases, top=100)
    assert [d.pareto for d in r.designs] == [d["pareto"] for d in direct["designs"]]
    assert len(r.designs) > 1 and r.objective == "pareto"
    tolerance = {"position": 0.02, "angle": 0.5}
    direct = client.result("fixture.design", {
        "body": CHAMFERED, "friction": 0.1, "sites": [{"at": s} for s in SITES], "top": 2,
        "fixel_tolerance": tolerance})
    with wrenchd.Client(daemon.path) as c:
        r = c.design(CHAMFERED, 0.1, sites=SITES, top=2, fixel_tolerance=tolerance)
    assert [d.best_push for d in r.designs] == [d["best_push"] for d in direct["designs"]]


def test_design_fixel_tolerance_robust_figures(client):
    """fixture.design with fixel_tolerance: each design's both region lies
    inside its nominal one, and its best push is inside 'both' on every
    fixture of the set sampled here (the design's fixels moved along their
    edges and tilted) and robustly so (wrench.classify with the tolerance)."""
    import random
    T, A = 0.02, 0.5
    base = {"body": CHAMFERED, "friction": 0.3, "sites": [{"at": s} for s in SITES], "top": 3}
    nominal = client.result("fixture.design", base)["designs"]
    robust = client.result("fixture.design",
                           dict(base, fixel_tolerance={"position": T, "angle": A}))["designs"]
    assert [d["candidate"] for d in robust] == [d["candidate"] for d in nominal]
    rng = random.Random(3)
    checked = 0
    for dn, dr in zip(nominal, robust):
        assert dr["both_length"] <= dn["both_length"]
        if dr["best_push"] is None:
            continue
        push = dr["best_push"]
        assert push["margin"] <= dn["best_push"]["margin"] + 1e-12
        fixture = {"body": CHAMFERED, "friction": {"static": 0.3},
                   "fixels": [{"at": f["at"]} for f in dr["fixels"]]}
        put = client.result("fixture.put", {"fixture": fixture})
        got = client.result("fixture.get", {"id": put["id"]})
        normals = [f["normal"] for f in got["fixels"]]
        wrench = {"force": push["direction"], "at": push["at"]}
        tolerant = dict(fixture, tolerance={"position": T, "angle": A})
        verdict = client.result("wrench.classify", {"fixture": tolerant, "wrenches": [wrench],
                                                    "sets": ["both"]})["results"][0]["both"]
        assert verdict["verdict"] == "inside", verdict
        for _ in range(12):
            moved = []
            for f, n in zip(dr["fixels"], normals):
                s = rng.uniform(-T, T)
                a = math.radians(rng.uniform(-A, A))
                # along the edge: the tangent, the normal turned a quarter
                at = [f["at"][0] - s * n[1], f["at"][1] + s * n[0]]
                c, sn = math.cos(a), math.sin(a)
                moved.append({"at": at, "normal": [c * n[0] - sn * n[1], sn * n[0] + c * n[1]]})
            g = dict(fixture, fixels=moved)
            v = client.result("wrench.classify", {"fixture": g, "wrenches": [wrench],
                                                  "sets": ["both"]})["results"][0]["both"]
            assert v["verdict"] == "inside", (v, moved)
        checked += 1
    assert checked >= 1
    error = client.error("fixture.design", dict(base, fixel_tolerance={"position": -1}))
    assert error["data"]["field"] == "params.fixel_tolerance.position", error
    error = client.error("fixture.design", dict(base, fixel_tolerance={"position": 0.01},
                                                finger_friction=0.2))
    assert error["data"]["field"] == "params.finger_friction", error
