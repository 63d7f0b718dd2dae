"""A lattice design's pieces are bounded whatever the part: a plate with
2,040 holes of two arcs (4,084 segments) on a fine lattice is years of work
in all, yet each piece (a hole pair with the segment of the first peg,
wr_lattice.h) is a few segments' worth.  Two such designs on the daemon's
two workers, and a third client's classify is answered within a second,
again and again; both designs send progress notifications of their poses
meanwhile, their counts of units going up."""

import time

import fixtures as FX


def holes_plate(columns, rows):
    """A plate 10 units a hole wide, a round hole (two half circles) of
    radius 2 in the middle of each cell."""
    width, height = 10 * columns, 10 * rows
    loops = [[[0, 0], [width, 0], [width, height], [0, height]]]
    for i in range(columns):
        for j in range(rows):
            cx, cy = 10 * i + 5, 10 * j + 5
            loops.append([[cx + 2, cy, 1], [cx - 2, cy, 1]])
    return {"mass": 1, "shape": {"type": "outline", "loops": loops}}


def test_classify_waits_under_a_second_behind_two_lattices(harness):
    d = harness.start("--threads", "2")
    body = holes_plate(60, 34)
    params = {"body": body, "friction": 0.3, "top": 3, "progress": True,
              "lattice": {"pitch": 7, "peg_radius": 0.5, "extent": [60, 40]}}
    designers = []
    for n in range(2):
        c = d.client()
        c.send({"jsonrpc": "2.0", "method": "fixture.design", "params": params, "id": 10 + n})
        designers.append(c)
    # Each design's first notification: the lattice's units are counted.
    first = []
    for c in designers:
        note = c.read_json(timeout=60)
        assert note.get("method") == "design.progress", note
        assert note["params"]["stage"] == "poses", note
        first.append(note["params"])
    assert all(p["total"] > 10 ** 9 for p in first), first  # far more work than a test waits for

    plate = FX.rectangle_321(0.3)
    other = d.client()
    waits = []
    for _ in range(8):
        start = time.monotonic()
        answer = other.result("wrench.classify", {"fixture": plate, "wrenches": [[0, 1, 0]]})
        waits.append(time.monotonic() - start)
        assert len(answer["results"]) == 1
        time.sleep(0.2)
    assert max(waits) < 1.0, waits

    # The designs are still running, and still say how far they are.
    for c, p in zip(designers, first):
        note = c.read_json(timeout=30)
        while note.get("method") == "design.progress" and note["params"]["done"] <= p["done"]:
            note = c.read_json(timeout=30)
        assert note.get("method") == "design.progress", note
        assert note["params"]["stage"] == "poses" and note["params"]["done"] > p["done"], note
    for c in designers:
        c.close()
    other.close()
