"""wrenchctl force, push --force --case, push-force (--svg): the table and
JSON against the daemon's own answers for the same request sent by hand,
the case syntax, argument errors, and the picture (well-formed, one band
piece per sample, the least push drawn, a legend with the unit)."""

import json
import os
import subprocess
import xml.dom.minidom

import pytest

import fixtures as FX
from conftest import REPO

WRENCHCTL = os.path.join(REPO, "build", "wrenchctl")

BRACKET = {"name": "bracket-upright", "units": {"length": "mm", "force": "N"},
           "body": {"mass": 0.5, "shape": {"type": "polygon", "vertices": [
               [0, 0], [120, 0], [120, 40], [100, 60], [0, 60]]}},
           "friction": {"static": 0.1},
           "fixels": [{"at": [30, 0]}, {"at": [90, 0]}, {"at": [0, 30]}]}
CASES_ARGS = ["--case", "gravity=9810@270", "--case", "cut:gravity=9810@270;force=-20,0@60,60"]
CASES = [{"loads": [{"gravity": {"g": 9810, "direction_deg": 270}}]},
         {"name": "cut", "loads": [{"gravity": {"g": 9810, "direction_deg": 270}},
                                   {"force": [-20, 0], "at": [60, 60]}]}]


def run(*args, socket_path=None, cwd=None):
    env = dict(os.environ)
    if socket_path:
        env["WRENCHD_SOCKET"] = socket_path
    return subprocess.run([WRENCHCTL] + list(args), capture_output=True, text=True, env=env,
                          timeout=60, cwd=cwd)


def same(a, b):
    """Equal, numbers to 1e-14 relative (wrenchctl --json prints cJSON's 15
    digits where the daemon prints the shortest exact text)."""
    if isinstance(a, dict):
        return isinstance(b, dict) and set(a) == set(b) and all(same(a[k], b[k]) for k in a)
    if isinstance(a, list):
        return isinstance(b, list) and len(a) == len(b) and all(map(same, a, b))
    if isinstance(a, float) or isinstance(b, float):
        return abs(a - b) <= 1e-14 * max(abs(a), abs(b))
    return a == b


@pytest.fixture
def bracket(daemon, client):
    fid = client.result("fixture.put", {"fixture": BRACKET})["id"]
    return daemon, fid


def test_force_matches_force_range(bracket, client):
    daemon, fid = bracket
    r = run("force", fid, "--push", "110,50", *CASES_ARGS, "--json", socket_path=daemon.path)
    assert r.returncode == 0, r.stderr
    want = client.result("force.range", {"fixture": fid, "push": {"at": [110, 50]},
                                         "cases": CASES})
    assert same(json.loads(r.stdout), want)
    table = run("force", fid, "--push", "110,50", *CASES_ARGS, socket_path=daemon.path)
    assert table.returncode == 0, table.stderr
    assert "forces in (the fixture's unit)" in table.stdout
    lo, hi = want["all"]["both"]["intervals"][0]
    assert "all cases         both    %.9g" % lo in table.stdout, table.stdout
    assert "(%.6g, %.6g)" % (lo, hi) in table.stdout
    # A direction, a wrench, sets and a range pass through as written.
    r = run("force", fid, "--push", "110,50@-1,0", "--sets", "goal", "--range", "1:100",
            *CASES_ARGS, "--json", socket_path=daemon.path)
    want = client.result("force.range", {"fixture": fid, "push": {"at": [110, 50],
                                                                  "direction": [-1, 0]},
                                         "cases": CASES, "sets": ["goal"], "range": [1, 100]})
    assert same(json.loads(r.stdout), want)
    r = run("force", fid, "--wrench", "-1,-1,0", *CASES_ARGS, "--json", socket_path=daemon.path)
    assert same(json.loads(r.stdout), client.result(
        "force.range", {"fixture": fid, "wrench": [-1, -1, 0], "cases": CASES}))


def test_force_argument_errors(bracket):
    daemon, fid = bracket
    for args, words in ((["--case", "gravity=9810@270"], "--push"),
                        (["--push", "110,50"], "--case"),
                        (["--push", "110", "--case", "gravity=1@270"], "--push wants"),
                        (["--push", "110,50", "--case", "gravity=1"], "not gravity"),
                        (["--push", "110,50", "--case", "spring=1,2"], "not gravity")):
        r = run("force", fid, *args, socket_path=daemon.path)
        assert r.returncode == 2 and words in r.stderr, (args, r.stderr)
    # The daemon's refusal, with its field.
    r = run("force", fid, "--push", "110,50", "--case", "gravity=-1@270", socket_path=daemon.path)
    assert r.returncode == 4 and "params.cases[0].loads[0].gravity.g" in r.stderr, r.stderr


def test_push_with_force_and_cases(bracket, client):
    daemon, fid = bracket
    r = run("push", fid, "--set", "both", "--force", "14.5", *CASES_ARGS, "--json",
            socket_path=daemon.path)
    assert r.returncode == 0, r.stderr
    assert same(json.loads(r.stdout), client.result(
        "push.regions", {"fixture": fid, "set": "both", "force": 14.5, "cases": CASES}))
    r = run("push", fid, *CASES_ARGS, socket_path=daemon.path)
    assert r.returncode == 2 and "--force" in r.stderr


def test_push_force_table_and_picture(bracket, client, tmp_path):
    daemon, fid = bracket
    svg = tmp_path / "force.svg"
    r = run("push-force", fid, *CASES_ARGS, "--svg", str(svg), socket_path=daemon.path)
    assert r.returncode == 0, r.stderr
    want = client.result("push.force", {"fixture": fid, "cases": CASES})
    assert "least push %.9g" % want["least"]["force"] in r.stdout, r.stdout
    doc = xml.dom.minidom.parse(str(svg))
    bands = [p for p in doc.getElementsByTagName("path") if p.getAttribute("class") == "force-band"]
    assert len(bands) == sum(len(s["t"]) for s in want["segments"])
    # Where no push works the band is grey and dashed; elsewhere coloured.
    grey = [p for p in bands if p.getAttribute("stroke") == "#cccccc"]
    none = sum(1 for s in want["segments"] for v in s["force"] if v is None)
    assert len(grey) == none and all(p.getAttribute("stroke-dasharray") for p in grey)
    arrows = [e for e in doc.getElementsByTagName("line") if e.getAttribute("class") == "least-push"]
    assert len(arrows) == 1
    text = " ".join(t.firstChild.data for t in doc.getElementsByTagName("text") if t.firstChild)
    assert " N " in text and "least push" in text, text
    r = run("push-force", fid, *CASES_ARGS, "--json", "--set", "goal", socket_path=daemon.path)
    assert same(json.loads(r.stdout), client.result("push.force", {"fixture": fid, "cases": CASES,
                                                                    "set": "goal"}))


def test_push_force_push_on_default_and_given(client):
    """push-force sends the clients' push_on: a point finger on the outer
    boundary only (the bracket's holes left out), --push-on all every loop;
    each against push.force asked by hand."""
    path = os.path.join(REPO, "examples", "bracket-upright.json")
    with open(path) as fh:
        fixture = json.load(fh)
    args = ["--case", "gravity=9810@180;force=30,-40@20,60"]
    cases = [{"loads": [{"gravity": {"g": 9810, "direction_deg": 180}},
                        {"force": [30, -40], "at": [20, 60]}]}]
    for extra, push_on in (([], "outer"), (["--push-on", "all"], None), (["--push-on", "0,1"],
                                                                        [0, 1])):
        r = run("--local", "push-force", path, *args, *extra, "--json")
        assert r.returncode in (0, 1), r.stderr
        params = {"fixture": fixture, "cases": cases}
        if push_on is not None:
            params["push_on"] = push_on
        assert same(json.loads(r.stdout), client.result("push.force", params)), extra
    r = run("--local", "push-force", path, *args, "--push-on", "inner")
    assert r.returncode == 2 and "--push-on" in r.stderr


def test_sweep_least_force(client, tmp_path):
    """sweep --least-force SET --case ...: friction.sweep's "force" as sent
    by hand, the table (the intervals, the samples with their points) and
    the plot (a curve broken where no push does it)."""
    path = os.path.join(REPO, "examples", "plate-chamfered.json")
    with open(path) as fh:
        fixture = json.load(fh)
    svg = tmp_path / "sweep.svg"
    r = run("--local", "sweep", path, "--least-force", "both", "--case", "gravity=9.81@270",
            "--range", "0:0.6", "--json", "--svg", str(svg))
    assert r.returncode in (0, 1), r.stderr
    got = json.loads(r.stdout)
    want = client.result("friction.sweep", {"fixture": fixture, "range": [0, 0.6],
                                            "force": {"set": "both"},
                                            "cases": [{"loads": [{"gravity": {
                                                "g": 9.81, "direction_deg": 270}}]}]})
    assert same(got, want)
    assert r.returncode == (0 if any(p[1] is not None for p in want["curve"]) else 1)
    doc = xml.dom.minidom.parse(str(svg))
    curves = [p for p in doc.getElementsByTagName("polyline") if p.getAttribute("class") == "curve"]
    runs, inside = 0, False
    for _, force in want["curve"]:
        runs += force is not None and not inside
        inside = force is not None
    assert len(curves) == runs
    text = " ".join(t.firstChild.data for t in doc.getElementsByTagName("text") if t.firstChild)
    assert "least push force" in text
    r = run("--local", "sweep", path, "--least-force", "both", "--case", "gravity=9.81@270",
            "--range", "0:0.6")
    assert r.returncode in (0, 1), r.stderr
    assert "the push alone has a region" in r.stdout and "least force" in r.stdout, r.stdout
    r = run("--local", "sweep", path, "--least-force", "both")
    assert r.returncode == 2 and "--case" in r.stderr
    r = run("--local", "sweep", path, "--push", "both", "--case", "gravity=9.81@270")
    assert r.returncode == 2 and "--case" in r.stderr


def test_design_objective_force(client):
    """design --objective force --case ...: fixture.design with the cases
    and the file's units as sent by hand; the table names each design's
    least push and the unit."""
    path = os.path.join(REPO, "examples", "bracket-upright.json")
    with open(path) as fh:
        fixture = json.load(fh)
    args = ["--objective", "force", "--case", "gravity=9810@180", "--top", "3"]
    r = run("--local", "design", path, *args, "--push-on", "all", "--json")
    assert r.returncode in (0, 1), r.stderr
    got = json.loads(r.stdout)
    sites = [{"at": f["at"]} for f in fixture["fixels"]]
    want = client.result("fixture.design", {
        "body": fixture["body"], "friction": fixture["friction"], "units": fixture["units"],
        "sites": sites, "objective": "force", "top": 3, "push_on": "all",
        "cases": [{"loads": [{"gravity": {"g": 9810, "direction_deg": 180}}]}]})
    assert [d["least_push"]["force"] for d in got["designs"]] == [
        d["least_push"]["force"] for d in want["designs"]]
    assert got["objective"] == "force"
    r = run("--local", "design", path, *args, "--push-on", "all")
    assert r.returncode in (0, 1), r.stderr
    assert "least push %.9g N" % want["designs"][0]["least_push"]["force"] in r.stdout, r.stdout
    assert "minus the least push force (N)" in r.stdout
    r = run("--local", "design", path, "--objective", "force")
    assert r.returncode == 2 and "--case" in r.stderr



def test_push_force_tolerance(daemon, client, tmp_path):
    """push-force --tolerance T,A sends the fixture inline with its
    tolerance: the same answer as push.force asked by hand with it (a
    small plate: every sample is a robust one)."""
    plate = FX.plate_321()
    path = tmp_path / "plate.json"
    path.write_text(json.dumps(plate))
    r = run("push-force", str(path), "--case", "gravity=9.81@270", "--json",
            "--tolerance", "0.05", socket_path=daemon.path)
    assert r.returncode == 0, r.stderr
    fixture = dict(plate, tolerance={"position": 0.05})
    cases = [{"loads": [{"gravity": {"g": 9.81, "direction_deg": 270}}]}]
    assert same(json.loads(r.stdout), client.result("push.force", {"fixture": fixture,
                                                                    "cases": cases}))
