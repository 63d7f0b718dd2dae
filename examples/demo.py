#!/usr/bin/env python3
"""make demo: start wrenchd, put the example fixtures, classify a few pushes
and say what each verdict means, stop wrenchd.  Standard library only."""
import json
import os
import shutil
import signal
import subprocess
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "clients", "python"))
import wrenchd  # noqa: E402  (the Python client, standard library only)

RUN = os.path.join(ROOT, "run", "demo")
SOCKET = os.path.join(RUN, "wrenchd.sock")


def show(client, fixture_id, label, wrench):
    result = client.classify(fixture_id, [wrench], sets=["goal", "strong"])[0]
    print("  %s" % label)
    for name in ("goal", "strong"):
        v = result[name]
        if v.inside:
            meaning = ("seats the part from every contact state" if name == "goal"
                       else "once seated, it does not move")
        else:
            meaning = "blocked by %s: %s" % (v.blocking, v.explain(name))
        print("    %-6s %-8s margin %+.3f  %s" % (name, v.verdict, v.margin, meaning))


def main():
    daemon_path = os.path.join(ROOT, "build", "wrenchd")
    shutil.rmtree(RUN, ignore_errors=True)
    os.makedirs(RUN)
    log = open(os.path.join(RUN, "wrenchd.log"), "w")
    daemon = subprocess.Popen([daemon_path, "--socket", SOCKET, "--state-dir",
                               os.path.join(RUN, "state")], stderr=log)
    client = wrenchd.Client(SOCKET, timeout=30)
    for _ in range(100):
        try:
            client.connect()
            break
        except wrenchd.WrenchdUnavailable:
            time.sleep(0.05)
    else:
        sys.exit("wrenchd did not start; see %s" % log.name)
    print("wrenchd %s is listening on %s\n" % (client.status().version, SOCKET))

    ids = {}
    for name in ("disc-corner", "plate-3-2-1", "plate-chamfered", "bracket"):
        with open(os.path.join(ROOT, "examples", name + ".json")) as f:
            fixture = json.load(f)
        put = client.put_fixture(fixture)
        ids[name] = put.id
        print("fixture.put examples/%s.json -> id %s: %d fixels, G_goal excludes %d cones, "
              "G_strong %d" % (name, put.id, put.fixels, put.goal_cones, put.strong_cones))
    print("  bracket: an outline of lines and arcs with a hole and a slot; its mass properties "
          "in use: area %.6g, com (%.6g, %.6g), inertia %.6g"
          % (put.area, put.com[0], put.com[1], put.inertia))

    print("\ndisc-corner: a disc in a corner, friction 0.5 (docs/MODEL.md section 7.1)")
    show(client, ids["disc-corner"], "push toward the corner, g = (-1, -1, 0)", [-1, -1, 0])
    show(client, ids["disc-corner"], "push mostly to the left, g = (-1, -0.2, 0)", [-1, -0.2, 0])
    show(client, ids["disc-corner"], "the same push with a strong twist, g = (-1, -1, -100)",
         [-1, -1, -100])

    print("\nplate-3-2-1: a 4 x 2 plate on two bottom fixels and one left fixel, friction 0.3")
    show(client, ids["plate-3-2-1"], "push down on the top edge at (2, 2)",
         {"force": [0, -1], "at": [2, 2]})
    show(client, ids["plate-3-2-1"], "push left on the right edge at (4, 0.5)",
         {"force": [-1, 0], "at": [4, 0.5]})

    print("\nplate-chamfered: the same plate, its far corner cut off, friction 0.1")
    show(client, ids["plate-chamfered"], "push along the chamfer's normal at (3.25, 1.75)",
         {"force": [-0.7071067811865476, -0.7071067811865476], "at": [3.25, 1.75]})
    show(client, ids["plate-chamfered"], "the same push lower on the chamfer, at (3.75, 1.25)",
         {"force": [-0.7071067811865476, -0.7071067811865476], "at": [3.75, 1.25]})

    print("\nWhere to push, which tilt, how much disturbance (a goal push reaches every fixel "
          "but may leave\nthe part sliding on, a strong one holds it only once seated: push "
          "with both and let go):")
    for name, set_name in (("disc-corner", "goal"), ("plate-3-2-1", "goal"),
                           ("plate-3-2-1", "strong"), ("plate-chamfered", "both"),
                           ("bracket", "both")):
        regions = client.push_regions(ids[name], set_name)
        where = ", ".join(("edge %d" % r.edge if r.edge is not None
                           else "loop %d segment %d" % (r.loop, r.segment))
                          + " t in (%.4g, %.4g)" % (r.t0, r.t1)
                          for r in regions.regions) or "nowhere"
        print("  %-16s push.regions %-6s -> %s (%.1f%% of the outline)"
              % (name, set_name, where, 100 * regions.fraction))
    arcs = client.gravity_sweep(ids["disc-corner"], "goal")
    print("  %-16s gravity.sweep goal  -> tilts %s degrees"
          % ("disc-corner", ", ".join("(%.4g, %.4g)" % (a, b) for a, b in arcs)))
    held = client.stability_margin(ids["plate-chamfered"],
                                   {"force": [-0.7071067811865476, -0.7071067811865476],
                                    "at": [3.25, 1.75]})
    print("  %-16s stability.margin of the chamfer push -> %.4g, the worst disturbance "
          "starts %s" % ("plate-chamfered", held.margin, held.blocking))

    # Friction nobody knows exactly: the same question for every mu at once.
    sweep = client.friction_sweep(ids["plate-chamfered"], range=(0, 1), push="goal")
    print("\nfriction.sweep: how much friction can the chamfered plate take?")
    print("  %-16s push goal region, mu in [0, 1]: non-empty on %s; critical mu %.6f "
          "(above it no push seats the part)"
          % ("plate-chamfered", ", ".join("[%.6g, %.6g]" % (a, b) for a, b in sweep.intervals),
             sweep.critical))
    lengths = {round(mu, 6): length for mu, length in sweep.curve}
    print("  %-16s region length at mu = 0, 0.125, 0.25: %s" % (
        "", ", ".join("%.4f" % lengths[m] for m in (0.0, 0.125, 0.25) if m in lengths)))

    # Design the fixture: where the locators go and where the clamp pushes.
    with open(os.path.join(ROOT, "examples", "bracket.json")) as f:
        bracket = json.load(f)
    seen = []
    design = client.design(bracket["body"], bracket["friction"], spacing=10, top=3,
                           progress=seen.append)
    counts = design.counts
    print("\nfixture.design: 3 fixels among %d sites every 10 mm on the bracket's outline, "
          "hole and slot" % design.sites)
    print("  %d candidates (%d progress notifications): %d without a seating push, %d "
          "unpinned, %d degenerate; the best by the margin of their best push:"
          % (counts["candidates"], len(seen), counts["no_seating_push"], counts["unpinned"],
             counts["degenerate"]))
    for d in design.designs:
        push = d.best_push
        print("  #%d fixels %s; push at (%.2f, %.2f) along (%.3f, %.3f), margin %.4f; "
              "critical mu %s" % (d.rank, " ".join("(%g, %g)" % tuple(x["at"]) for x in d.fixels),
                                 push["at"][0], push["at"][1], push["direction"][0],
                                 push["direction"][1], push["margin"],
                                 "%.4f" % d.critical_mu if d.critical_mu is not None else "none"))
    print("  push there and let go: the best push is in the both region (goal seats, strong "
          "holds)")

    # Pictures, drawn by wrenchctl from the daemon's answers.
    out = os.path.join(ROOT, "out")
    os.makedirs(out, exist_ok=True)
    wrenchctl = [os.path.join(ROOT, "build", "wrenchctl"), "--socket", SOCKET]
    pictures = [
        ("disc-corner-push-goal.svg", ["push", ids["disc-corner"], "--set", "goal"]),
        ("disc-corner-gravity-goal.svg", ["gravity", ids["disc-corner"], "--set", "goal"]),
        ("plate-3-2-1-push-goal.svg", ["push", ids["plate-3-2-1"], "--set", "goal"]),
        ("plate-3-2-1-push-strong.svg", ["push", ids["plate-3-2-1"], "--set", "strong"]),
        ("plate-chamfered-push-both.svg", ["push", ids["plate-chamfered"], "--set", "both"]),
        ("plate-chamfered-gravity-both.svg", ["gravity", ids["plate-chamfered"], "--set", "both"]),
        ("plate-chamfered-margin.svg", ["margin", ids["plate-chamfered"],
                                        "-0.7071067811865476,-0.7071067811865476@3.25,1.75"]),
        ("bracket-push-both.svg", ["push", ids["bracket"], "--set", "both"]),
        ("bracket-gravity-both.svg", ["gravity", ids["bracket"], "--set", "both"]),
    ]
    pictures.append(("plate-chamfered-sweep-goal.svg",
                     ["sweep", ids["plate-chamfered"], "--push", "goal", "--range", "0:1"]))
    pictures.append(("bracket-designs.svg",
                     ["design", os.path.join(ROOT, "examples", "bracket.json"), "--spacing", "10",
                      "--top", "3"]))
    for filename, command in pictures:
        subprocess.run(wrenchctl + command + ["--svg", os.path.join(out, filename)],
                       stdout=subprocess.DEVNULL, check=False)
    print("\npictures: %s" % ", ".join("out/" + f for f, _ in pictures))

    client.close()
    daemon.send_signal(signal.SIGTERM)
    status = daemon.wait(timeout=10)
    print("\nwrenchd stopped (exit status %d); its log is %s" % (status, log.name))
    return status


if __name__ == "__main__":
    sys.exit(main())
