#!/usr/bin/env python3
"""make demo: start wrenchd, put the example fixtures, classify a few pushes
and say what each verdict means, stop wrenchd.  Standard library only."""
import json
import os
import shutil
import signal
import socket
import subprocess
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
RUN = os.path.join(ROOT, "run", "demo")
SOCKET = os.path.join(RUN, "wrenchd.sock")


class Client:
    def __init__(self, path):
        self.sock = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
        self.sock.connect(path)
        self.file = self.sock.makefile("rwb")
        self.next_id = 0

    def call(self, method, **params):
        self.next_id += 1
        request = {"jsonrpc": "2.0", "method": method, "params": params, "id": self.next_id}
        self.file.write(json.dumps(request).encode() + b"\n")
        self.file.flush()
        answer = json.loads(self.file.readline())
        if "error" in answer:
            error = answer["error"]
            raise RuntimeError("%s: %s (%s)" % (error["message"], error["data"]["reason"],
                                                error["data"]["field"]))
        return answer["result"]


def fixels_named(indices):
    names = ["fixel %d" % (i + 1) for i in indices]
    return names[0] if len(names) == 1 else ", ".join(names[:-1]) + " and " + names[-1]


def explain_goal(blocking, states):
    """Why a wrench does not seat the part: the transition it allows."""
    reasons = []
    for state in states:
        touched = [i for i, c in enumerate(state) if c == "1"]
        separating = [i for i in touched if blocking[i] == "s"]
        holding = [i for i in touched if blocking[i] == "m"]
        if not separating:
            apart = [i for i, c in enumerate(state) if c == "0"]
            reasons.append("from contact state %s it can stay as it is: %s %s and %s %s never "
                           "reached" % (state, fixels_named(holding),
                                        "holds" if len(holding) == 1 else "hold",
                                        fixels_named(apart), "is" if len(apart) == 1 else "are"))
        else:
            text = "from contact state %s %s may break away" % (state, fixels_named(separating))
            if holding:
                text += " while %s %s" % (fixels_named(holding),
                                          "holds" if len(holding) == 1 else "hold")
            reasons.append(text)
    return "; ".join(reasons)


MOTION = {"s": "separates", "l": "slides left", "r": "slides right", "n": "rolls"}


def explain_strong(blocking):
    if blocking[-1] in "+-":
        return "it may pivot %s about its contact point" % (
            "counter-clockwise" if blocking[-1] == "+" else "clockwise")
    return "it may start to move: " + ", ".join(
        "fixel %d %s" % (i + 1, MOTION[c]) for i, c in enumerate(blocking))


def show(client, fixture_id, label, wrench):
    result = client.call("wrench.classify", fixture=fixture_id, wrenches=[wrench],
                         sets=["goal", "strong"])["results"][0]
    goal, strong = result["goal"], result["strong"]
    print("  %s" % label)
    if goal["inside"]:
        print("    goal   %-8s margin %+.3f  seats the part from every contact state"
              % (goal["verdict"], goal["margin"]))
    else:
        print("    goal   %-8s margin %+.3f  blocked by %s: %s"
              % (goal["verdict"], goal["margin"], goal["blocking"],
                 explain_goal(goal["blocking"], goal["states"])))
    if strong["inside"]:
        print("    strong %-8s margin %+.3f  once seated, it does not move"
              % (strong["verdict"], strong["margin"]))
    else:
        print("    strong %-8s margin %+.3f  blocked by %s: %s"
              % (strong["verdict"], strong["margin"], strong["blocking"],
                 explain_strong(strong["blocking"])))


def main():
    daemon_path = os.path.join(ROOT, "build", "wrenchd")
    shutil.rmtree(RUN, ignore_errors=True)
    os.makedirs(RUN)
    log = open(os.path.join(RUN, "wrenchd.log"), "w")
    daemon = subprocess.Popen([daemon_path, "--socket", SOCKET, "--state-dir",
                               os.path.join(RUN, "state")], stderr=log)
    for _ in range(100):
        try:
            client = Client(SOCKET)
            break
        except OSError:
            time.sleep(0.05)
    else:
        sys.exit("wrenchd did not start; see %s" % log.name)
    print("wrenchd %s is listening on %s\n" % (client.call("server.status")["version"], SOCKET))

    ids = {}
    for name in ("disc-corner", "plate-3-2-1", "plate-chamfered"):
        with open(os.path.join(ROOT, "examples", name + ".json")) as f:
            fixture = json.load(f)
        put = client.call("fixture.put", fixture=fixture)
        ids[name] = put["id"]
        print("fixture.put examples/%s.json -> id %s: %d fixels, G_goal excludes %d cones, "
              "G_strong %d" % (name, put["id"], put["fixels"], put["goal_cones"],
                               put["strong_cones"]))

    print("\ndisc-corner: a disc in a corner, friction 0.5 (SPEC section 7)")
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

    daemon.send_signal(signal.SIGTERM)
    status = daemon.wait(timeout=10)
    print("\nwrenchd stopped (exit status %d); its log is %s" % (status, log.name))
    return status


if __name__ == "__main__":
    sys.exit(main())
