"""wrenchctl and libwrenchclient against a running daemon.

Every subcommand, its exit status (0 all inside, 1 some not inside, 2 usage,
3 unreachable, 4 server error), --json, stdin batches, --local against the
daemon on the examples (identical JSON), and the C client's example and
bench programs.  Expected numbers: docs/MODEL.md section 7 (the disc in a corner)."""

import json
import math
import os
import shutil
import socket
import subprocess
import time

import pytest

from conftest import REPO

WRENCHCTL = os.path.join(REPO, "build", "wrenchctl")
EXAMPLES = os.path.join(REPO, "examples")
DISC = os.path.join(EXAMPLES, "disc-corner.json")
PLATE = os.path.join(EXAMPLES, "plate-3-2-1.json")
CHAMFERED = os.path.join(EXAMPLES, "plate-chamfered.json")
DISC_ID = "e0d7a1a0bd6e8bf16fe5845da1960ed9"


@pytest.fixture
def ctl(daemon):
    """Run wrenchctl against the test's daemon; returns the CompletedProcess."""
    def run(*args, stdin=None, socket_path=None, timeout=60):
        env = dict(os.environ, WRENCHD_SOCKET=socket_path or daemon.path)
        return subprocess.run([WRENCHCTL] + list(args), input=stdin, capture_output=True,
                              text=True, env=env, timeout=timeout, cwd=daemon.workdir)
    return run


def put_disc(ctl):
    r = ctl("put", DISC)
    assert r.returncode == 0, r.stderr
    assert r.stdout.split()[0] == DISC_ID
    return DISC_ID


def test_put_list_get_delete(ctl, client):
    fid = put_disc(ctl)
    assert "disc-corner" in ctl("list").stdout
    assert fid in ctl("list", "--json").stdout
    got = json.loads(ctl("get", fid).stdout)
    assert got == client.result("fixture.get", {"id": fid})
    r = ctl("delete", fid)
    assert r.returncode == 0 and "deleted" in r.stdout
    r = ctl("get", fid)
    assert r.returncode == 4
    assert "-32001" in r.stderr and "params.id" in r.stderr


def test_classify_table_and_exit_status(ctl):
    fid = put_disc(ctl)
    # docs/MODEL.md section 7, mu = 0.5: (-1,-1) seats the disc with margin (1-mu)/sqrt(2(1+mu^2)).
    r = ctl("classify", fid, "-1,-1,0", "--sets", "goal")
    assert r.returncode == 0, r.stderr
    margin = (1 - 0.5) / math.sqrt(2 * (1 + 0.25))
    assert "inside" in r.stdout and ("%+.6f" % margin) in r.stdout
    # (-1, -0.2): |f_y| < mu |f_x|, blocked by ms from states 10 and 11.
    r = ctl("classify", fid, "-1,-1,0", "-1,-0.2,0")
    assert r.returncode == 1
    assert "outside" in r.stdout and " ms " in r.stdout
    assert "from contact state 10 it can stay as it is" in r.stdout
    assert "from contact state 11 fixel 2 may break away while fixel 1 holds" in r.stdout
    # A force at a point: (-1,-1) at 45 degrees on the rim has no torque.
    r = ctl("classify", fid, "-1,-1@0.7071067811865476,0.7071067811865476", "--sets=goal")
    assert r.returncode == 0 and "(-1, -1) at (0.707107, 0.707107)" in r.stdout
    # docs/MODEL.md section 4's counterexample: seats, then spins, sliding at both fixels.
    r = ctl("classify", fid, "-1,-1,-100")
    assert r.returncode == 1
    assert "fixel 1 slides left, fixel 2 slides left" in r.stdout


def without_witnesses(result):
    """LP witnesses are not unique (a warm simplex may stop at another
    vertex); everything else in an answer is."""
    for r in result["results"]:
        for v in r.values():
            v.pop("witness")
    return result


def test_classify_json_is_the_daemons_result(ctl, client):
    fid = put_disc(ctl)
    for method in ("auto", "lp"):
        r = ctl("--json", "classify", fid, "-1,-1,0", "-1,-0.2,0", "--sets", "goal,both",
                "--method", method)
        assert r.returncode == 1
        direct = client.result("wrench.classify", {"fixture": fid,
                                                   "wrenches": [[-1, -1, 0], [-1, -0.2, 0]],
                                                   "sets": ["goal", "both"], "method": method})
        if method == "lp":
            assert without_witnesses(json.loads(r.stdout)) == without_witnesses(direct)
        else:
            assert json.loads(r.stdout) == direct


def test_classify_reads_a_batch_from_stdin(ctl):
    fid = put_disc(ctl)
    lines = "[-1, -1, 0]\n\n{\"force\": [-1, -0.2], \"at\": [-1, 0]}\n[-2, -2, 5]\n"
    r = ctl("classify", fid, "-", "--json", "--sets", "goal", stdin=lines)
    assert r.returncode == 1, r.stderr
    results = json.loads(r.stdout)["results"]
    assert [x["goal"]["verdict"] for x in results] == ["inside", "outside", "inside"]
    r = ctl("classify", fid, "-", stdin="[1, 2, 3]\nnot json\n")
    assert r.returncode == 2 and "stdin line 2" in r.stderr


def test_classify_stdin_reads_every_wrench_or_refuses(ctl):
    """Every value on a line is a wrench (none dropped after the first);
    anything else on a line, or no wrench at all, is a usage error."""
    fid = put_disc(ctl)
    r = ctl("classify", fid, "-", "--json", "--sets", "goal",
            stdin="[-1, -1, 0] [-1, -0.2, 0]\n\n  [-2, -2, 5]\t{\"force\": [0, -1], \"at\": [-1, 0]}\n")
    assert r.returncode == 1, r.stderr
    verdicts = [x["goal"]["verdict"] for x in json.loads(r.stdout)["results"]]
    assert verdicts == ["inside", "outside", "inside", "outside"], verdicts
    # Trailing garbage names its line (blank lines count).
    r = ctl("classify", fid, "-", stdin="[-1, -1, 0]\n\n[-1, -1, 0] trailing\n")
    assert r.returncode == 2 and "stdin line 3" in r.stderr and "trailing" in r.stderr, r.stderr
    assert r.stdout == ""
    for empty in ("", "\n  \n"):
        r = ctl("classify", fid, "-", stdin=empty)
        assert r.returncode == 2 and "no wrenches given" in r.stderr, r.stderr
        assert r.stdout == ""


def test_put_refuses_text_after_the_fixture(ctl, harness):
    bad = harness.path("trailing.json")
    with open(DISC) as f:
        text = f.read()
    with open(bad, "w") as f:
        f.write(text.rstrip() + "\n trailing\n")
    for args in (["put", bad], ["--local", "classify", bad, "-1,-1,0"]):
        r = ctl(*args)
        assert r.returncode == 2, (args, r.stderr)
        assert "text after the JSON value" in r.stderr and "trailing" in r.stderr, r.stderr
    with open(bad, "w") as f:
        f.write(text + "\n\n  \n")  # white space after it is fine
    assert ctl("put", bad).returncode == 0


@pytest.mark.skipif(not shutil.which("valgrind"), reason="needs valgrind")
def test_unknown_set_message_reads_no_freed_memory(ctl):
    """--sets gaol: the message names the set from memory still held
    (it printed a freed block)."""
    r = subprocess.run(["valgrind", "-q", "--error-exitcode=99", WRENCHCTL, "--local",
                        "classify", DISC, "1,1,1", "--sets", "goal,gaol"],
                       capture_output=True, text=True, timeout=120)
    assert r.returncode == 2, r.stderr
    assert "Invalid read" not in r.stderr, r.stderr
    assert "--sets: 'gaol' is not goal, strong or both" in r.stderr, r.stderr


@pytest.mark.parametrize("path", [DISC, PLATE, CHAMFERED])
def test_local_answers_as_the_daemon(ctl, path):
    wrenches = ["-1,-1,0", "0,-1,0.3", "-1,0@4,0.5", "-0.7071,-0.7071@3.25,1.75", "1,1,1"]
    commands = [["classify", path] + wrenches + ["--sets", "goal,strong,both"],
                ["classify", path] + wrenches + ["--method", "lp"],
                ["plan", path], ["modes", path]]
    with open(path) as f:
        k = len(json.load(f)["fixels"])
    commands += [["cone", path, letters * k] for letters in "smun"]
    for command in commands:
        daemon_answer = ctl("--json", *command)
        local_answer = ctl("--json", "--local", *command)
        assert daemon_answer.returncode == local_answer.returncode, command
        d, l = json.loads(daemon_answer.stdout), json.loads(local_answer.stdout)
        if "lp" in command:
            d, l = without_witnesses(d), without_witnesses(l)
        assert d == l, command


def test_cone_plan_modes_status_tables(ctl):
    fid = put_disc(ctl)
    r = ctl("cone", fid, "ss")
    # docs/MODEL.md section 7: G_ss of the disc is {f_x >= 0, f_y >= 0}.
    assert r.returncode == 0
    assert "G_ss: dimension 3, 2 half-spaces" in r.stdout
    assert "[-1.000000, +0.000000, +0.000000]" in r.stdout
    assert "[+0.000000, -1.000000, +0.000000]" in r.stdout
    r = ctl("plan", fid)
    assert "G_goal excludes 4 cones: su ms us sm" in r.stdout
    assert "11          ss ms sm" in r.stdout
    r = ctl("modes", fid)
    assert "9 feasible moving modes: ss sl sr sn ls rs ns ll rr" in r.stdout
    assert "pinned" in r.stdout
    r = ctl("status")
    assert r.returncode == 0 and "fixtures" in r.stdout and "uptime_s" in r.stdout
    assert json.loads(ctl("status", "--json").stdout)["fixtures"] == 1


@pytest.mark.parametrize("args", [
    [],
    ["frobnicate"],
    ["classify"],
    ["classify", DISC],
    ["classify", DISC, "1,2"],
    ["classify", DISC, "1,2,x"],
    ["classify", DISC, "1,2,3", "--sets", "goal,nope"],
    ["classify", DISC, "1,2,3", "--method", "simplex"],
    ["classify", DISC, "1,2,3", "--tolerance", "-1"],
    ["classify", DISC, "1,2,3", "--bogus", "1"],
    ["classify", "no-such-file.json", "1,2,3"],
    ["cone", DISC],
    ["get"],
    ["put", DISC, "extra"],
    ["--timeout", "0", "status"],
    ["--local", "put", DISC],
    ["--local", "list"],
    ["--local", "status"],
    ["--local", "classify", DISC_ID, "1,2,3"],
])
def test_usage_errors_exit_2(ctl, args):
    r = ctl(*args)
    assert r.returncode == 2, (args, r.stdout, r.stderr)
    assert r.stderr or r.stdout


def test_server_errors_exit_4_naming_the_field(ctl, harness):
    bad = harness.path("bad.json")
    with open(DISC) as f:
        fixture = json.load(f)
    fixture["body"]["mass"] = -1
    with open(bad, "w") as f:
        json.dump(fixture, f)
    for args in (["put", bad], ["classify", bad, "1,2,3"], ["--local", "classify", bad, "1,2,3"]):
        r = ctl(*args)
        assert r.returncode == 4, (args, r.stderr)
        assert "params.fixture.body.mass" in r.stderr and "-32602" in r.stderr
    r = ctl("cone", DISC, "sx")
    assert r.returncode == 4 and "params.constraints" in r.stderr


def test_unreachable_exits_3(ctl, harness):
    r = ctl("status", socket_path=harness.path("nobody-here.sock"))
    assert r.returncode == 3 and "cannot connect" in r.stderr
    assert "no socket at %s: is wrenchd running?" % harness.path("nobody-here.sock") in r.stderr
    # A socket file nobody listens on: refused, a stale socket.
    stale = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
    stale.bind(harness.path("stale.sock"))
    stale.close()
    r = ctl("status", socket_path=harness.path("stale.sock"))
    assert r.returncode == 3, r.stderr
    assert "connection refused at %s: a stale socket" % harness.path("stale.sock") in r.stderr
    # A socket that accepts but never answers: the timeout.
    silent = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
    silent.bind(harness.path("silent.sock"))
    silent.listen(1)
    try:
        start = time.monotonic()
        r = ctl("--timeout", "0.5", "status", socket_path=harness.path("silent.sock"))
        assert r.returncode == 3 and "in time" in r.stderr
        assert time.monotonic() - start < 10
    finally:
        silent.close()


def test_permission_denied_is_named(daemon):
    """A socket the user may not open is "permission denied", not "is
    wrenchd running?".  Root opens anything: then wrenchctl runs as nobody."""
    path = os.path.join(daemon.workdir, "denied.sock")
    listener = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
    listener.bind(path)
    listener.listen(1)
    os.chmod(path, 0o600)
    prefix = []
    if os.geteuid() == 0:
        if not shutil.which("setpriv"):
            listener.close()
            pytest.skip("running as root without setpriv")
        prefix = ["setpriv", "--reuid=65534", "--regid=65534", "--clear-groups"]
        os.chmod(daemon.workdir, 0o755)
    try:
        r = subprocess.run(prefix + [WRENCHCTL, "--socket", path, "status"],
                           capture_output=True, text=True, timeout=60, cwd="/")
    finally:
        listener.close()
    assert r.returncode == 3, r.stderr
    assert "permission denied on %s" % path in r.stderr, r.stderr
    assert "running" not in r.stderr, r.stderr


def test_every_command_has_help(ctl):
    r = ctl("--help")
    assert r.returncode == 0 and "Exit status" in r.stdout
    for command in ["put", "get", "list", "delete", "classify", "cone", "plan", "modes",
                    "status", "help"]:
        r = ctl(command, "--help")
        assert r.returncode == 0 and r.stdout.startswith("Usage: wrenchctl"), command
        assert ctl("help", command).stdout == r.stdout
    assert ctl("--version").stdout.startswith("wrenchctl ")


def test_c_client_example_and_bench(daemon):
    example = subprocess.run([os.path.join(REPO, "build", "wrenchclient-example"), daemon.path,
                              DISC], capture_output=True, text=True, timeout=60)
    assert example.returncode == 0, example.stderr
    assert ("fixture %s" % DISC_ID) in example.stdout
    assert "(-1, -1, 0) goal   inside   margin +0.316228" in example.stdout
    assert "(-1, -0.2, 0) goal   outside  margin -0.263117 ms" in example.stdout
    assert "(-1, -1, -100) strong outside  margin -0.003162 ll" in example.stdout
    bench = subprocess.run([os.path.join(REPO, "build", "wrenchclient-bench"), daemon.path,
                            DISC_ID, "200"], capture_output=True, text=True, timeout=60)
    assert bench.returncode == 0, bench.stderr
    assert "200 calls" in bench.stdout and "p50" in bench.stdout
