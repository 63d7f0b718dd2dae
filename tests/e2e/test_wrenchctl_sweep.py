"""wrenchctl --friction LO:HI (classify, push, gravity, margin) and wrenchctl
sweep (friction.sweep): answers against the daemon's own for the same
fixture sent by hand, argument errors, the tables, and the --svg plots
(well-formed, one shaded interval per interval of the answer, the critical
mu marked, a band per wrench and set).

The sweep tests that run against the daemon need its friction.sweep; those
against a tiny fake daemon (a Unix socket answering canned lines) reach the
table's and the plot's other cases (no critical mu, empty throughout,
sampled) without it."""

import copy
import json
import math
import os
import socket
import subprocess
import threading
import xml.dom.minidom

import pytest

import fixtures as FX
from conftest import REPO

WRENCHCTL = os.path.join(REPO, "build", "wrenchctl")
EXAMPLES = os.path.join(REPO, "examples")
DISC = os.path.join(EXAMPLES, "disc-corner.json")
PLATE = os.path.join(EXAMPLES, "plate-3-2-1.json")
DISC_ID = "e0d7a1a0bd6e8bf16fe5845da1960ed9"
ROBUST = "robust answers, each holds for every friction in the interval"


def run(*args, socket_path=None, cwd=None):
    env = dict(os.environ)
    if socket_path:
        env["WRENCHD_SOCKET"] = socket_path
    return subprocess.run([WRENCHCTL] + list(args), capture_output=True, text=True, env=env,
                          timeout=60, cwd=cwd)


@pytest.fixture
def ctl(daemon):
    def call(*args):
        return run(*args, socket_path=daemon.path, cwd=daemon.workdir)
    return call


def with_friction(fixture, low, high):
    """What --friction LO:HI sends: the interval at the top level, static
    and kinetic, no fixel's own friction."""
    f = copy.deepcopy(fixture)
    for fixel in f["fixels"]:
        fixel.pop("friction", None)
    f["friction"] = {"static": [low, high], "kinetic": [low, high]}
    return f


def close(a, b, tolerance=1e-12):
    """Equal, numbers to within `tolerance` (relative): the daemon's last bit
    may differ between two spellings of one fixture (each its own cache
    entry, computed by whichever worker took it)."""
    if isinstance(a, dict) and isinstance(b, dict):
        return a.keys() == b.keys() and all(close(a[k], b[k], tolerance) for k in a)
    if isinstance(a, list) and isinstance(b, list):
        return len(a) == len(b) and all(close(x, y, tolerance) for x, y in zip(a, b))
    if isinstance(a, (int, float)) and isinstance(b, (int, float)) and \
            not isinstance(a, bool) and not isinstance(b, bool):
        return abs(a - b) <= tolerance * max(1.0, abs(a), abs(b))
    return a == b


def without_witnesses(result):
    return [{name: dict(v, witness=None) for name, v in row.items()}
            for row in result["results"]]


def elements(path, tag, cls=None):
    document = xml.dom.minidom.parse(path)      # well-formed, or this raises
    return [e for e in document.getElementsByTagName(tag)
            if cls is None or e.getAttribute("class") == cls]


def texts(path):
    return [t.firstChild.data for t in elements(path, "text") if t.firstChild]


# ---- --friction -------------------------------------------------------------------

def plate_with_a_fixel_friction():
    """The 3-2-1 plate, one fixel with its own friction: --friction replaces
    it too."""
    f = FX.rectangle_321(0.3)
    f["fixels"][1]["friction"] = {"static": 0.9}
    return f


COMMANDS = [
    ["classify", "FIXTURE", "-1,-0.2,0.1", "0,-1,0.3", "-1,0@4,0.5", "--sets", "goal,strong,both"],
    ["push", "FIXTURE", "--set", "strong"],
    ["push", "FIXTURE", "--set", "both", "--finger-radius", "0.2"],
    ["gravity", "FIXTURE", "--set", "strong"],
    ["margin", "FIXTURE", "-1,-1,0"],
]


@pytest.mark.parametrize("interval", [(0.2, 0.35), (0.3, 0.3)])
@pytest.mark.parametrize("stored", [False, True])
def test_friction_is_the_daemons_answer_for_the_interval_fixture(ctl, client, harness,
                                                                  interval, stored):
    """wrenchctl CMD FIXTURE --friction LO:HI --json is the daemon's answer
    for the fixture with that interval written in by hand, whether FIXTURE
    is a file or a stored fixture's id (fetched and sent inline)."""
    fixture = plate_with_a_fixel_friction()
    path = harness.path("plate.json")
    with open(path, "w") as f:
        json.dump(fixture, f)
    argument = client.result("fixture.put", {"fixture": fixture})["id"] if stored else path
    low, high = interval
    text = "%g:%g" % interval if low != high else "%g" % low
    # A stored fixture is sent in its explicit form (fixture.get's): its
    # derived com, inertia and normals written out, to the last bit.
    base = client.result("fixture.get", {"id": argument}) if stored else fixture
    by_hand = with_friction(base, low, high)
    methods = {"classify": "wrench.classify", "push": "push.regions",
               "gravity": "gravity.sweep", "margin": "stability.margin"}
    for command in COMMANDS:
        args = [argument if a == "FIXTURE" else a for a in command]
        r = ctl(*args, "--friction", text, "--json")
        assert r.returncode in (0, 1), (command, r.stderr)
        got = json.loads(r.stdout)
        params = {"fixture": by_hand}
        if command[0] == "classify":
            params.update(wrenches=[[-1, -0.2, 0.1], [0, -1, 0.3],
                                    {"force": [-1, 0], "at": [4, 0.5]}],
                          sets=["goal", "strong", "both"])
        elif command[0] == "push":
            params["set"] = command[3]
            if "--finger-radius" in command:
                params["finger_radius"] = 0.2
        elif command[0] == "gravity":
            params["set"] = "strong"
        else:
            params["bias"] = [-1, -1, 0]
        expected = client.result(methods[command[0]], params)
        if command[0] == "classify":
            # A witness is one of many, its last bits the solver's path.
            got, expected = without_witnesses(got), without_witnesses(expected)
        assert close(got, expected), (command, got, expected)
        # Not what the fixture's own friction gives.
        if interval == (0.2, 0.35) and "strong" in command:
            own = json.loads(ctl(*args, "--json").stdout)
            assert own != got, command


def test_friction_tables_say_they_are_robust(ctl):
    for command in (["classify", PLATE, "-1,-0.2,0.1"], ["push", PLATE, "--set", "strong"],
                    ["gravity", PLATE], ["margin", PLATE, "-1,-1,0"]):
        r = ctl(*command, "--friction", "0.2:0.35")
        assert r.returncode in (0, 1), r.stderr
        first = r.stdout.splitlines()[0]
        assert first.startswith("friction [0.2, 0.35] at every fixel, static and kinetic: ")
        assert ROBUST in first
        r = ctl(*command, "--friction=0.3")
        assert r.stdout.splitlines()[0] == \
            "friction 0.3 at every fixel, static and kinetic (--friction)"
        assert "friction" not in ctl(*command, "--friction", "0.3", "--json").stdout.split("\n")[0]


def test_friction_of_a_stored_fixture_under_local_and_unknown(ctl):
    r = ctl("--local", "push", DISC_ID, "--friction", "0.1:0.2")
    assert r.returncode == 2 and "--local needs a fixture file" in r.stderr
    r = ctl("push", DISC_ID, "--friction", "0.1:0.2")          # not stored
    assert r.returncode == 4 and "-32001" in r.stderr
    r = ctl("--local", "push", PLATE, "--friction", "0.2:0.35", "--set", "strong")
    assert r.returncode == 0 and ROBUST in r.stdout


@pytest.mark.parametrize("value, words", [
    ("0.4:0.2", "--friction 0.4:0.2: LO must be at most HI"),
    ("-0.1", "--friction -0.1: -0.1 is negative"),
    ("0.1:-1", "is negative"),
    ("0.1:2000", "2000 is above 1000"),
    ("x", "--friction wants LO:HI or MU, numbers, not 'x'"),
    ("kinetic", "--friction wants LO:HI or MU"),
    ("0.1:", "--friction wants LO:HI or MU"),
    (":0.2", "--friction wants LO:HI or MU"),
    ("0.1:0.2:0.3", "--friction wants LO:HI or MU"),
    ("nan", "--friction wants LO:HI or MU"),
    ("inf", "--friction wants LO:HI or MU"),
])
def test_bad_friction_is_a_usage_error_naming_it(value, words):
    r = run("--local", "classify", DISC, "1,1,1", "--friction", value)
    assert r.returncode == 2, r.stderr
    assert words in r.stderr, r.stderr


def test_friction_is_only_where_it_means_something():
    for command in (["cone", DISC, "ss"], ["plan", DISC], ["sweep", DISC, "--push", "goal"]):
        r = run("--local", *command, "--friction", "0.2")
        assert r.returncode == 2 and "no option '--friction'" in r.stderr, command


def test_help_and_man_page_know_friction_and_sweep():
    for command in ("classify", "push", "gravity", "margin"):
        r = run(command, "--help")
        assert "--friction LO:HI" in r.stdout and "robust" in r.stdout, command
    r = run("sweep", "--help")
    for option in ("--push SET", "--gravity SET", "--wrench FX,FY,TAU", "--range LO:HI",
                   "--kinetic-ratio R", "--svg FILE"):
        assert option in r.stdout, option
    assert "sweep" in run("--help").stdout
    with open(os.path.join(REPO, "clients", "wrenchctl", "wrenchctl.1")) as f:
        man = f.read()
    for words in ("\\-\\-friction", ".BI sweep", "\\-\\-kinetic\\-ratio", "\\-\\-range"):
        assert words in man, words


# ---- sweep against the daemon (needs friction.sweep) ----------------------------------

def curve_rows(stdout):
    """The table's (mu, length) rows."""
    rows = []
    for line in stdout.splitlines():
        parts = line.split()
        if len(parts) == 2:
            try:
                rows.append([float(parts[0]), float(parts[1])])
            except ValueError:
                pass
    return rows


def test_sweep_push_table_and_plot_of_the_disc(ctl, harness):
    """The disc in a corner: the goal push region is empty from mu = 1
    (docs/MODEL.md section 7.1), its length pi/2 - 2 atan mu before."""
    svg = harness.path("sweep.svg")
    r = ctl("sweep", DISC, "--push", "goal", "--svg", svg, "--table", "full")
    assert r.returncode == 0, r.stderr
    lines = r.stdout.splitlines()
    assert lines[0] == ("friction sweep of the push region, set goal: mu_s = mu, mu_k = 1 mu "
                        "at every fixel, mu from 0 to 2")
    assert lines[1] == "not empty for mu in [0, 1]"
    assert lines[2] == "critical mu 1: empty above it"
    assert lines[3].split() == ["mu", "length"]
    assert lines[-1].startswith("goal: reaches every fixel")
    answer = json.loads(ctl("sweep", DISC, "--push", "goal", "--json").stdout)
    rows = curve_rows(r.stdout)
    assert len(rows) == len(answer["curve"])
    for (mu, length), (mu2, length2) in zip(rows, answer["curve"]):
        assert mu == pytest.approx(mu2, abs=1e-6) and length == pytest.approx(length2, abs=1e-6)
        assert length == pytest.approx(max(0, math.pi / 2 - 2 * math.atan(mu)), abs=2e-6)
    assert len(elements(svg, "rect", "interval")) == len(answer["intervals"]) == 1
    (curve,) = elements(svg, "polyline", "curve")
    assert len(curve.getAttribute("points").split()) == len(answer["curve"])
    (line,) = elements(svg, "line", "critical")
    (label,) = elements(svg, "text", "critical")
    assert label.firstChild.data == "critical \u03bc = 1"
    # The critical line is half way along the mu axis (0 to 2).
    axis = elements(svg, "line", "axis")
    x0 = min(float(a.getAttribute("x1")) for a in axis)
    x1 = max(float(a.getAttribute("x2")) for a in axis)
    assert float(line.getAttribute("x1")) == pytest.approx((x0 + x1) / 2, abs=0.01)
    assert any(t.startswith("goal: reaches every fixel") for t in texts(svg))


def test_sweep_table_summarised_by_default(ctl):
    """Without --table full: the curve's points nearest 9 evenly spaced mu
    from the bottom of the range to the critical mu, those at the
    intervals' ends and the last, each a row of the full table, and a line
    saying how many of how many."""
    answer = json.loads(ctl("sweep", DISC, "--push", "goal", "--json").stdout)
    curve = answer["curve"]
    assert len(curve) > 18, len(curve)
    want = {len(curve) - 1}
    top = answer["critical"]
    for k in range(9):
        mu = top * k / 8
        want.add(min(range(len(curve)), key=lambda i: (abs(curve[i][0] - mu), i)))
    for lo, hi in answer["intervals"]:
        want |= {i for i, (mu, _) in enumerate(curve) if mu in (lo, hi)}
    r = ctl("sweep", DISC, "--push", "goal")
    rows = curve_rows(r.stdout)
    assert len(rows) == len(want), (rows, sorted(want))
    for (mu, length), i in zip(rows, sorted(want)):
        assert mu == pytest.approx(curve[i][0], abs=1e-6)
        assert length == pytest.approx(curve[i][1], abs=1e-6)
    assert "(%d of the curve's %d points; --table full for all" % (len(want), len(curve)) in r.stdout
    assert ctl("sweep", DISC, "--push", "goal", "--table", "most").returncode == 2


def test_sweep_gravity_and_options_reach_the_daemon(ctl):
    r = ctl("sweep", DISC, "--gravity", "both", "--range", "0.1:1.5", "--kinetic-ratio", "0.5",
            "--json")
    assert r.returncode in (0, 1), r.stderr
    answer = json.loads(r.stdout)
    assert answer["curve"][0][0] == pytest.approx(0.1) and \
        answer["curve"][-1][0] == pytest.approx(1.5)
    table = ctl("sweep", DISC, "--gravity", "both", "--range", "0.1:1.5", "--kinetic-ratio",
                "0.5")
    assert table.stdout.splitlines()[0].endswith("mu_k = 0.5 mu at every fixel, mu from 0.1 to 1.5")
    assert "arc (degrees)" in table.stdout
    assert table.stdout.splitlines()[-1].startswith("both: seats the part")


def test_sweep_wrenches_table_and_bands(ctl, harness):
    svg = harness.path("bands.svg")
    r = ctl("sweep", DISC, "--wrench", "-1,-1,0", "--wrench=-1,-0.2,0",
            "--svg", svg)
    assert r.returncode == 0, r.stderr
    answer = json.loads(ctl("sweep", DISC, "--wrench", "-1,-1,0", "--wrench", "-1,-0.2,0",
                            "--json").stdout)
    assert [sorted(row) for row in answer["results"]] == [["goal", "strong"]] * 2
    lines = r.stdout.splitlines()
    assert lines[1].split() == ["#", "wrench", "set", "inside", "for", "mu", "in"]
    assert lines[2].split()[:5] == ["1", "(-1,", "-1,", "0)", "goal"]
    assert lines[2].endswith("[0, 1]")
    assert lines[4].split()[:5] == ["2", "(-1,", "-0.2,", "0)", "goal"]
    assert lines[4].endswith("[0, 0.2]")
    assert len(elements(svg, "rect", "band")) == 4
    assert len(elements(svg, "rect", "inside")) == sum(
        len(intervals) for row in answer["results"] for intervals in row.values())
    r = ctl("sweep", DISC, "--wrench", "-1,-0.2,0", "--set", "goal", "--range", "0.5:2")
    assert r.returncode == 1 and r.stdout.splitlines()[2].endswith("none")


@pytest.mark.parametrize("args, words", [
    ([], "sweep wants --push SET, --gravity SET, --least-force SET or --wrench FX,FY,TAU"),
    (["--push", "goal", "--gravity", "goal"], "--push and --gravity: one of"),
    (["--wrench", "1,0,0", "--push", "goal"], "--wrench and --push: one of"),
    (["--push", "gaol"], "--push is goal, strong or both"),
    (["--push", "goal", "--set", "strong"], "--set is for --wrench"),
    (["--gravity", "goal", "--finger-radius", "1"], "--finger-radius is for --push and"),
    (["--least-force", "goal", "--finger-friction", "0.1", "--case", "gravity=9.81@270"],
     "--finger-friction is for --push"),
    (["--least-force", "goal"], "--least-force wants at least one --case"),
    (["--least-force", "goal", "--push", "goal"], "--least-force and --push: one of"),
    (["--gravity", "goal", "--case", "gravity=9.81@270"], "--case is for --least-force"),
    (["--gravity", "goal", "--push-on", "all"], "--push-on is for --least-force"),
    (["--wrench", "1,2"], "--wrench wants FX,FY,TAU"),
    (["--wrench", "1,0@2,2"], "--wrench wants FX,FY,TAU"),
    (["--push", "goal", "--range", "1:1"], "--range 1:1: LO must be below HI"),
    (["--push", "goal", "--range", "1"], "--range wants LO:HI"),
    (["--push", "goal", "--range", "-1:1"], "is negative"),
    (["--push", "goal", "--kinetic-ratio", "0"], "--kinetic-ratio wants a number above 0"),
    (["--push", "goal", "--kinetic-ratio", "1.5"], "--kinetic-ratio wants"),
])
def test_sweep_usage_errors(args, words):
    r = run("--local", "sweep", DISC, *args)
    assert r.returncode == 2, (args, r.stdout, r.stderr)
    assert words in r.stderr, r.stderr


# ---- sweep against a fake daemon: the other cases of the table and the plot ----------

class FakeDaemon:
    """Answers every request line on `path` with the canned result for its
    method, and keeps the requests."""

    def __init__(self, path, results):
        self.results = results
        self.requests = []
        self.listener = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
        self.listener.bind(path)
        self.listener.listen(4)
        self.thread = threading.Thread(target=self.serve, daemon=True)
        self.thread.start()

    def serve(self):
        while True:
            try:
                conn, _ = self.listener.accept()
            except OSError:
                return
            with conn:
                buffer = b""
                while True:
                    chunk = conn.recv(1 << 16)
                    if not chunk:
                        break
                    buffer += chunk
                    while b"\n" in buffer:
                        line, buffer = buffer.split(b"\n", 1)
                        request = json.loads(line)
                        self.requests.append(request)
                        answer = {"jsonrpc": "2.0", "result": self.results[request["method"]],
                                  "id": request["id"]}
                        conn.sendall(json.dumps(answer).encode() + b"\n")

    def close(self):
        self.listener.close()


@pytest.fixture
def fake(harness):
    made = []

    def make(results):
        made.append(FakeDaemon(harness.path("fake%d.sock" % len(made)), results))
        return made[-1]
    yield make
    for f in made:
        f.close()


STORED = {"name": "disc <&> corner", "body": {"mass": 1, "inertia": 0.5, "com": [0, 0],
          "shape": {"type": "circle", "center": [0, 0], "radius": 1}},
          "fixels": [{"at": [-1, 0], "normal": [1, 0], "friction": {"static": 0.5, "kinetic": 0.5}},
                     {"at": [0, -1], "normal": [0, 1], "friction": {"static": 0.5, "kinetic": 0.5}}]}


@pytest.mark.parametrize("answer, lines, legend", [
    ({"intervals": [[0, 2]], "critical": None, "curve": [[0, 1], [2, 3]], "exact": False,
      "resolution": 0.0005},
     ["not empty for mu in [0, 2]",
      "critical mu: none, not empty at the top of the range (mu = 2)",
      "sampled: resolution 0.0005"],
     "no critical \u03bc"),
    ({"intervals": [], "critical": 0, "curve": [[0, 0], [2, 0]], "exact": True, "resolution": 0},
     ["not empty for mu in none", "critical mu 0: empty throughout the range"],
     "red: empty for every \u03bc from 0 to 2"),
    ({"intervals": [[0, 0.25], [0.5, 1]], "critical": 1,
      "curve": [[0, 2], [0.25, 0], [0.5, 0], [0.75, 1], [1, 0], [2, 0]], "exact": True,
      "resolution": 0},
     ["not empty for mu in [0, 0.25], [0.5, 1]", "critical mu 1: empty above it"],
     "red: the critical \u03bc = 1, above which it is empty"),
])
def test_sweep_table_and_plot_cases(fake, harness, answer, lines, legend):
    f = fake({"friction.sweep": answer, "fixture.get": STORED})
    svg = harness.path("case.svg")
    r = run("sweep", DISC_ID, "--push", "strong", "--finger-radius", "0.1", "--svg", svg,
            socket_path=harness.path("fake0.sock"))
    assert r.returncode == (0 if answer["intervals"] else 1), r.stderr
    out = r.stdout.splitlines()
    for line in lines:
        assert line in out, (line, out)
    assert out[-1].startswith("strong: holds the part once seated")
    assert f.requests[0]["params"] == {"fixture": DISC_ID,
                                       "push": {"set": "strong", "finger_radius": 0.1}}
    assert f.requests[1] == {"jsonrpc": "2.0", "method": "fixture.get",
                             "params": {"id": DISC_ID}, "id": 1}
    assert len(elements(svg, "rect", "interval")) == len(answer["intervals"])
    assert len(elements(svg, "line", "critical")) == (answer["critical"] is not None)
    words = texts(svg)
    assert legend in " ".join(words)
    assert any(w.startswith("disc <&> corner, set strong") for w in words)   # escaped, read back
    assert any(w.startswith("strong: holds the part once seated") for w in words)


def test_sweep_wrench_bands_with_one_set(fake, harness):
    f = fake({"friction.sweep": {"results": [{"both": [[0.5, 1]]}, {"both": []}]},
              "fixture.get": STORED})
    svg = harness.path("bands.svg")
    r = run("sweep", DISC_ID, "--wrench", "-1,-1,0", "--wrench", "0,-1,0.5", "--set", "both",
            "--kinetic-ratio", "0.75", "--svg", svg, socket_path=harness.path("fake0.sock"))
    assert r.returncode == 1, r.stderr
    assert f.requests[0]["params"] == {"fixture": DISC_ID, "kinetic_ratio": 0.75,
                                       "wrenches": [[-1, -1, 0], [0, -1, 0.5]], "sets": ["both"]}
    out = r.stdout.splitlines()
    assert out[0].startswith("friction sweep of wrenches: mu_s = mu, mu_k = 0.75 mu")
    assert out[2].endswith("both    [0.5, 1]") and out[3].endswith("both    none")
    assert out[-1].startswith("both: seats the part from any contact state")
    assert len(elements(svg, "rect", "band")) == 2
    assert len(elements(svg, "rect", "inside")) == 1
    assert any("\u03bc_k = 0.75 \u03bc" in t for t in texts(svg))


def test_sweep_wrench_tolerance(daemon, client, tmp_path):
    """sweep --wrench --tolerance T,A sends the fixture inline with its
    tolerance: the same intervals as friction.sweep asked by hand."""
    plate = FX.plate_321()
    path = tmp_path / "plate.json"
    path.write_text(json.dumps(plate))
    r = run("sweep", str(path), "--wrench", "-0.5,-1,0.3", "--set", "strong", "--json",
            "--tolerance", "0.05,0.5", socket_path=daemon.path)
    assert r.returncode in (0, 1), r.stderr
    fixture = dict(plate, tolerance={"position": 0.05, "angle": 0.5})
    want = client.result("friction.sweep", {"fixture": fixture, "wrenches": [[-0.5, -1, 0.3]],
                                            "sets": ["strong"]})
    assert close(json.loads(r.stdout), want), (r.stdout, want)
