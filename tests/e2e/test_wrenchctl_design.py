"""wrenchctl design and design-merge, the Python client's design, and the
progress they show: the table against the daemon's own answer, --shard
lines merged against one run (sites and a lattice), refusals, the --svg
panels against the answer (a region path per region of each design's both
region as push.regions gives it, the best push arrow ending at the best
push, pegs on a lattice at distance r from their fixels), the progress bar
on a terminal (a pseudo-terminal), and the Python client's progress
callback."""

import json
import math
import os
import pty
import re
import select
import subprocess
import sys
import xml.dom.minidom

import pytest

from conftest import REPO

WRENCHCTL = os.path.join(REPO, "build", "wrenchctl")
EXAMPLES = os.path.join(REPO, "examples")
BRACKET = os.path.join(EXAMPLES, "bracket.json")
sys.path.insert(0, os.path.join(REPO, "clients", "python"))
import wrenchd  # noqa: E402

SQUARE = {"name": "square", "body": {"mass": 1, "shape": {
    "type": "polygon", "vertices": [[0, 0], [2.5, 0], [2.5, 2.5], [0, 2.5]]}},
    "friction": {"static": 0.3}}


def run(*args, socket_path=None, cwd=None, stdin=None):
    env = dict(os.environ)
    if socket_path:
        env["WRENCHD_SOCKET"] = socket_path
    return subprocess.run([WRENCHCTL] + list(args), capture_output=True, text=True, env=env,
                          timeout=120, cwd=cwd, input=stdin)


@pytest.fixture
def square_file(tmp_path):
    path = tmp_path / "square.json"
    path.write_text(json.dumps(SQUARE))
    return str(path)


def bracket():
    with open(BRACKET) as f:
        return json.load(f)


def close(a, b):
    if isinstance(a, dict):
        return isinstance(b, dict) and a.keys() == b.keys() and all(close(a[k], b[k]) for k in a)
    if isinstance(a, list):
        return isinstance(b, list) and len(a) == len(b) and all(map(close, a, b))
    if isinstance(a, float) or isinstance(b, float):
        return math.isclose(a, b, rel_tol=1e-14, abs_tol=1e-300)
    return a == b


def drawing_decimals(shape):
    """The drawing's precision (wrenchctl(1), push), computed here: the
    median of the decimals its coordinates have in their shortest exact
    form, at least those that show 1/10,000 of the shape's box diagonal, at
    most 6."""
    xs, ys, places = [], [], []
    for loop in shape["loops"]:
        for v in loop:
            xs.append(v[0])
            ys.append(v[1])
            for x in v[:2]:
                places.append(next(p for p in range(7)
                                   if p == 6 or float("%.*f" % (p, x)) == x))
    median = sorted(places)[len(places) // 2]
    size = math.hypot(max(xs) - min(xs), max(ys) - min(ys))
    return min(6, max(median, math.ceil(-math.log10(1e-4 * size))))


def trimmed(x, places):
    """x rounded to `places` decimals, trailing zeros dropped, as the tables
    print a coordinate."""
    text = "%.*f" % (places, x)
    if "." in text:
        text = text.rstrip("0").rstrip(".")
    return "0" if text == "-0" else text


def test_table_is_the_daemons_answer(daemon):
    b = bracket()
    # The bracket has holes and the finger is a point: the clients push on
    # the outer boundary only (docs/PROTOCOL.md, push_on).
    answer = daemon.client().result("fixture.design", {
        "body": b["body"], "friction": b["friction"], "spacing": 12, "top": 4,
        "push_on": "outer"})
    r = run("design", BRACKET, "--spacing", "12", "--top", "4", socket_path=daemon.path)
    assert r.returncode == 0, r.stderr
    lines = r.stdout.splitlines()
    assert lines[0].startswith("design: 3 fixels from %d sites, %d candidates"
                               % (answer["sites"], answer["counts"]["candidates"]))
    assert "%d without a seating push" % answer["counts"]["no_seating_push"] in lines[0]
    rows = [line for line in lines if line[:1].isdigit()]
    assert len(rows) == 4
    for row, d in zip(rows, answer["designs"]):
        cells = row.split()
        assert int(cells[0]) == d["rank"]
        assert float(cells[1]) == pytest.approx(d["score"], rel=1e-5)
        push = d["best_push"]
        places = drawing_decimals(b["body"]["shape"])
        assert places == 2
        assert "(%s, %s)" % (trimmed(push["at"][0], places), trimmed(push["at"][1], places)) in row
        assert push["loop"] == 0
    assert "let go" in r.stdout and "both" in r.stdout
    # --json: the daemon's answer itself (cJSON prints some numbers a last
    # digit short: to 1e-14).
    j = run("--json", "design", BRACKET, "--spacing", "12", "--top", "4", socket_path=daemon.path)
    assert close(json.loads(j.stdout), answer)


def test_local_equals_the_daemon(daemon):
    local = run("--local", "--json", "design", BRACKET, "--spacing", "12", "--top", "3")
    remote = run("--json", "design", BRACKET, "--spacing", "12", "--top", "3",
                 socket_path=daemon.path)
    assert local.returncode == remote.returncode == 0
    # Both printed by the same cJSON from the same text: equal exactly.
    assert json.loads(local.stdout) == json.loads(remote.stdout)


@pytest.mark.parametrize("shards", [1, 3, 5])
def test_shards_merged_equal_one_run(tmp_path, shards):
    whole = json.loads(run("--local", "--json", "design", BRACKET, "--spacing", "12", "--top",
                           "5").stdout)
    files = []
    for i in range(shards):
        r = run("--local", "design", BRACKET, "--spacing", "12", "--top", "5", "--shard",
                "%d/%d" % (i, shards))
        assert r.returncode == 0, r.stderr
        lines = [json.loads(line) for line in r.stdout.splitlines()]
        summary = lines[-1]
        assert summary["shard"] == [i, shards] and summary["top"] == 5
        assert all(d["candidate"] % shards == i for d in lines[:-1])
        path = tmp_path / ("shard-%d.jsonl" % i)
        path.write_text(r.stdout)
        files.append(str(path))
    merged = run("--json", "design-merge", *reversed(files))
    assert merged.returncode == 0, merged.stderr
    assert json.loads(merged.stdout) == whole
    # From standard input too, the table as design prints it.
    table = run("design-merge", "-", stdin="".join(open(f).read() for f in files))
    assert table.returncode == 0
    assert table.stdout == run("--local", "design", BRACKET, "--spacing", "12", "--top",
                               "5").stdout


def test_merge_names_missing_shards_and_refuses_mixtures(tmp_path, square_file):
    outputs = []
    for i in range(3):
        r = run("--local", "design", BRACKET, "--spacing", "12", "--top", "3", "--shard",
                "%d/3" % i)
        path = tmp_path / ("s%d" % i)
        path.write_text(r.stdout)
        outputs.append(str(path))
    partial = run("design-merge", outputs[0], outputs[2])
    assert partial.returncode == 0
    assert "2 of 3 shards given; missing: 1" in partial.stderr
    twice = run("design-merge", outputs[0], outputs[0])
    assert twice.returncode == 2 and "shard 0 of 3 given twice" in twice.stderr
    other = tmp_path / "other"
    other.write_text(run("--local", "design", BRACKET, "--spacing", "12", "--top", "3",
                         "--shard", "1/2").stdout)
    mixed = run("design-merge", outputs[0], str(other))
    assert mixed.returncode == 2 and "another design" in mixed.stderr
    junk = tmp_path / "junk"
    junk.write_text("not json\n")
    assert run("design-merge", str(junk)).returncode == 2
    assert run("design-merge", str(tmp_path / "none")).returncode == 2


def test_lattice_table_shards_and_merge(tmp_path, square_file):
    whole = run("--local", "--json", "design", square_file, "--lattice", "1,0.2,4x4", "--top", "3")
    assert whole.returncode == 0, whole.stderr
    answer = json.loads(whole.stdout)
    assert answer["poses"] == answer["counts"]["candidates"] > 0 and "sites" not in answer
    for d in answer["designs"]:
        assert d["pegs"][0] == [0, 0] and len(d["pose"]) == 3 and "sites" not in d
    table = run("--local", "design", square_file, "--lattice", "1,0.2,4x4", "--top", "3")
    assert "pegs in holes (0, 0)" in table.stdout and "poses of the part" in table.stdout
    files = []
    for i in range(2):
        path = tmp_path / ("l%d" % i)
        path.write_text(run("--local", "design", square_file, "--lattice", "1,0.2,4x4", "--top",
                            "3", "--shard", "%d/2" % i).stdout)
        files.append(str(path))
    assert json.loads(run("--json", "design-merge", *files).stdout) == answer


@pytest.mark.parametrize("args,message", [
    (["--spacing", "0"], "--spacing"),
    (["--spacing", "x"], "--spacing"),
    (["--fixels", "9"], "--fixels"),
    (["--top", "0"], "--top"),
    (["--objective", "best"], "--objective"),
    (["--shard", "3/3"], "--shard"),
    (["--shard", "1"], "--shard"),
    (["--lattice", "1,0.2"], "--lattice"),
    (["--spacing", "2", "--lattice", "1,0.2,4x4"], "not both"),
    ([], "no candidate sites"),
])
def test_usage_errors(square_file, args, message):
    r = run("--local", "design", square_file, *args)
    assert r.returncode == 2 and message in r.stderr, r.stderr


def test_shard_and_json_refused(square_file):
    r = run("--local", "--json", "design", square_file, "--spacing", "1", "--shard", "0/2")
    assert r.returncode == 2 and "JSON lines" in r.stderr


def test_daemon_errors_name_the_field(daemon, tmp_path):
    body_only = tmp_path / "circle.json"
    body_only.write_text(json.dumps({"body": {"mass": 1, "shape": {
        "type": "circle", "center": [0, 0], "radius": 1}}, "friction": {"static": 0.2}}))
    r = run("design", str(body_only), "--lattice", "1,0.1,3x3", socket_path=daemon.path)
    assert r.returncode == 4 and "params.body.shape" in r.stderr


def elements(path, tag, cls=None):
    document = xml.dom.minidom.parse(path)
    return [e for e in document.getElementsByTagName(tag)
            if cls is None or e.getAttribute("class") == cls]


def test_svg_panels_against_the_answer(daemon, tmp_path):
    """Each panel: as many region paths as push.regions (set both) gives
    that design's fixture, and the best-push arrow ends at the best push
    (in the panel's own frame: its end is the point nearest the region)."""
    picture = str(tmp_path / "designs.svg")
    r = run("design", BRACKET, "--spacing", "12", "--top", "4", "--svg", picture,
            socket_path=daemon.path)
    assert r.returncode == 0, r.stderr
    answer = json.loads(run("--json", "design", BRACKET, "--spacing", "12", "--top", "4",
                            socket_path=daemon.path).stdout)
    b = bracket()
    groups = elements(picture, "g", "design")
    assert len(groups) == len(answer["designs"]) == 4
    client = daemon.client()
    for group, d in zip(groups, answer["designs"]):
        fixture = {"body": b["body"], "friction": b["friction"], "fixels": d["fixels"]}
        regions = client.result("push.regions", {"fixture": fixture, "set": "both"})["regions"]
        paths = [p for p in group.getElementsByTagName("path")
                 if p.getAttribute("class") == "region"]
        assert len(paths) == len(regions)
        arrows = [line for line in group.getElementsByTagName("line")
                  if line.getAttribute("class") == "best-push"]
        assert len(arrows) == (1 if d["best_push"] else 0)
        fixels = [p for p in group.getElementsByTagName("polygon")
                  if p.getAttribute("class") == "fixel"]
        pins = [c for c in group.getElementsByTagName("circle")
                if "pin" in c.getAttribute("class")]
        assert len(fixels) + len(pins) == 3
        text = "".join(t.firstChild.data for t in group.getElementsByTagName("text")
                       if t.firstChild)
        assert "#%d" % d["rank"] in text


def test_svg_lattice_pegs_touch_their_fixels(square_file, tmp_path):
    """A peg of radius r is drawn at distance r from its fixel, on the side
    away from the part: the fixel's point minus r times its normal, in the
    panel's frame, whose scale is read off the pegs' own radius."""
    picture = str(tmp_path / "lattice.svg")
    r = run("--local", "design", square_file, "--lattice", "1,0.2,4x4", "--top", "2", "--svg",
            picture)
    assert r.returncode == 0, r.stderr
    pegs = elements(picture, "circle", "peg")
    assert len(pegs) == 6
    answer = json.loads(run("--local", "--json", "design", square_file, "--lattice",
                            "1,0.2,4x4", "--top", "2").stdout)
    groups = elements(picture, "g", "design")
    for group, d in zip(groups, answer["designs"]):
        circles = [c for c in group.getElementsByTagName("circle")
                   if c.getAttribute("class") == "peg"]
        scale = float(circles[0].getAttribute("r")) / 0.2
        centres = [(float(c.getAttribute("cx")), float(c.getAttribute("cy"))) for c in circles]
        # Page = ((x - x0) * scale, top + (y1 - y) * scale): differences of
        # centres are differences of part points, scaled, y flipped.
        parts = [(f["at"][0] - 0.2 * f["normal"][0], f["at"][1] - 0.2 * f["normal"][1])
                 for f in d["fixels"]]
        for i in range(3):
            for j in range(3):
                dx = (centres[i][0] - centres[j][0]) / scale
                dy = -(centres[i][1] - centres[j][1]) / scale
                assert dx == pytest.approx(parts[i][0] - parts[j][0], abs=0.02)
                assert dy == pytest.approx(parts[i][1] - parts[j][1], abs=0.02)


def test_progress_bar_on_a_terminal(daemon):
    """On a terminal (a pseudo-terminal here) the progress notifications
    draw a bar on stderr that ends at 100%; the table still comes whole."""
    pid, fd = pty.fork()
    if pid == 0:
        os.environ["WRENCHD_SOCKET"] = daemon.path
        os.execv(WRENCHCTL, [WRENCHCTL, "design", BRACKET, "--spacing", "8", "--top", "2"])
    out = b""
    while True:
        ready, _, _ = select.select([fd], [], [], 120)
        if not ready:
            break
        try:
            chunk = os.read(fd, 65536)
        except OSError:
            break
        if not chunk:
            break
        out += chunk
    _, status = os.waitpid(pid, 0)
    text = out.decode()
    assert os.WEXITSTATUS(status) == 0, text
    assert "[" in text and "100%" in text and "candidates" in text
    assert "rank  score" in text


def test_no_progress_bar_into_a_pipe(daemon):
    r = run("design", BRACKET, "--spacing", "12", "--top", "1", socket_path=daemon.path)
    assert r.returncode == 0 and "%" not in r.stderr


def test_python_client_design_and_progress(daemon):
    b = bracket()
    seen = []
    with wrenchd.Client(daemon.path, timeout=60) as client:
        result = client.design(b["body"], b["friction"], spacing=8, top=3, progress=seen.append)
        again = client.design(b["body"], b["friction"], spacing=8, top=3)
        raw = client.call("fixture.design", {"body": b["body"], "friction": b["friction"],
                                             "spacing": 8, "top": 3, "push_on": "outer"})
    assert [d.candidate for d in result.designs] == [d["candidate"] for d in raw["designs"]]
    assert result.counts == raw["counts"] and again.counts == raw["counts"]
    # the candidates, then perhaps the designs' figures
    stages = [p["stage"] for p in seen]
    assert stages == sorted(stages, key=["candidates", "figures"].index), stages
    seen = [p for p in seen if p["stage"] == "candidates"]
    assert seen and seen[0]["done"] == 0 and seen[-1]["done"] == seen[-1]["total"]
    assert seen[-1]["eta_s"] == 0
    assert [p["done"] for p in seen] == sorted(p["done"] for p in seen)
    assert result.designs[0].best_push["margin"] == result.designs[0].score
    with pytest.raises(ValueError):
        client.design(b["body"], b["friction"])
    with pytest.raises(ValueError):
        client.design(b["body"], b["friction"], spacing=8, sites=[[0, 0]])


def test_python_client_lattice_design(daemon):
    seen = []
    with wrenchd.Client(daemon.path, timeout=60) as client:
        result = client.design(SQUARE["body"], 0.3, top=2, progress=seen.append,
                               lattice={"pitch": 1, "peg_radius": 0.2, "extent": [4, 4]})
    assert result.poses == result.counts["candidates"] > 0 and result.sites == 0
    assert all(d.pegs[0] == [0, 0] and len(d.pose) == 3 and d.sites is None
               for d in result.designs)
    stages = [p["stage"] for p in seen]
    assert stages[0] == "poses" and "candidates" in stages
    assert stages == sorted(stages, key=["poses", "candidates", "figures"].index)


def test_python_client_progress_callback_that_raises_spends_the_connection(daemon):
    b = bracket()

    class Stop(Exception):
        pass

    def stop(params):
        raise Stop()

    with wrenchd.Client(daemon.path, timeout=60) as client:
        with pytest.raises(Stop):
            client.design(b["body"], b["friction"], spacing=8, top=1, progress=stop)
        # The next call works, on a new connection.
        assert client.status().version


def test_python_client_batch_refuses_progress(daemon):
    b = bracket()
    with wrenchd.Client(daemon.path, timeout=60) as client:
        batch = client.batch()
        with pytest.raises(ValueError):
            batch.design(b["body"], b["friction"], spacing=8, progress=print)


def test_symmetric_designs_collapsed_and_all(daemon, tmp_path):
    """The square's designs: by default each once, saying how many more it
    stands for; --symmetric all lists every one; the counts agree with the
    daemon's own answers, asked both ways."""
    path = tmp_path / "square.json"
    path.write_text(json.dumps(SQUARE))
    collapsed = run("design", str(path), "--spacing", "1", "--top", "1000",
                    socket_path=daemon.path)
    every = run("design", str(path), "--spacing", "1", "--top", "1000", "--symmetric", "all",
                socket_path=daemon.path)
    assert collapsed.returncode == every.returncode == 0, (collapsed.stderr, every.stderr)
    with wrenchd.Client(daemon.path, timeout=60) as client:
        one = client.design(SQUARE["body"], SQUARE["friction"], spacing=1, top=1000)
        all_ = client.design(SQUARE["body"], SQUARE["friction"], spacing=1, top=1000,
                             collapse_symmetric=False)
    assert len(one.symmetries) == 8 and all_.symmetries is None
    assert sum(d.copies for d in one.designs) == len(all_.designs) > len(one.designs)
    assert "the part has 8 symmetries" in collapsed.stdout
    rows = [l for l in collapsed.stdout.splitlines() if re.match(r"^\d+ ", l)]
    assert len(rows) == len(one.designs)
    more = [l for l in collapsed.stdout.splitlines() if "more: its images" in l]
    assert len(more) == sum(1 for d in one.designs if d.copies > 1)
    assert len([l for l in every.stdout.splitlines() if re.match(r"^\d+ ", l)]) == \
        len(all_.designs)
    bad = run("design", str(path), "--spacing", "1", "--symmetric", "some",
              socket_path=daemon.path)
    assert bad.returncode != 0 and "--symmetric" in bad.stderr


def test_pareto_shards_merged_equal_one_run(tmp_path):
    """design --objective pareto: each shard holds its own front, and
    design-merge keeps the designs no other shard's beats: the one run's
    front, with each design's three figures printed in the table."""
    args = ["design", BRACKET, "--spacing", "12", "--objective", "pareto", "--tolerance",
            "0.1", "--case", "gravity=9810@270", "--top", "1000"]
    whole = json.loads(run("--local", "--json", *args).stdout)
    assert len(whole["designs"]) > 1
    files = []
    for i in range(3):
        r = run("--local", *args, "--shard", "%d/3" % i)
        assert r.returncode == 0, r.stderr
        path = tmp_path / ("shard-%d.jsonl" % i)
        path.write_text(r.stdout)
        files.append(str(path))
    merged = json.loads(run("--json", "design-merge", *files).stdout)
    assert [d["candidate"] for d in merged["designs"]] == \
        [d["candidate"] for d in whole["designs"]]
    table = run("--local", *args).stdout
    assert table.count("pareto: margin") == len(whole["designs"]), table


def test_fixel_tolerance_sent(daemon, client):
    """design --fixel-tolerance T,A sends params.fixel_tolerance: the same
    designs, robust both lengths and best pushes, as asked by hand."""
    r = run("--json", "design", BRACKET, "--spacing", "12", "--top", "2", "--fixel-tolerance",
            "0.05,0.2", socket_path=daemon.path)
    assert r.returncode in (0, 1), r.stderr
    with open(BRACKET) as f:
        bracket = json.load(f)
    want = client.result("fixture.design", {
        "body": bracket["body"], "friction": bracket["friction"]["static"], "spacing": 12,
        "top": 2, "fixel_tolerance": {"position": 0.05, "angle": 0.2}})
    got = json.loads(r.stdout)
    assert [d["best_push"] for d in got["designs"]] == \
        [d["best_push"] for d in want["designs"]]
    assert [d["both_length"] for d in got["designs"]] == \
        [d["both_length"] for d in want["designs"]]
