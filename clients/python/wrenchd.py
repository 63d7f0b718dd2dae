"""wrenchd.py -- a Python client of wrenchd (standard library only, Python >= 3.8).

wrenchd answers JSON-RPC 2.0 over a Unix socket (docs/PROTOCOL.md).  This
module gives one method per RPC, with dataclasses for the answers:

    import wrenchd

    with wrenchd.Client("run/wrenchd.sock", timeout=10) as client:
        put = client.put_fixture(fixture)                  # -> PutResult
        (r,) = client.classify(put.id, [(-1, -1, 0)])      # -> [{"goal": Verdict, ...}]
        if not r["goal"].inside:
            print(wrenchd.explain(r["goal"], "goal"))

Methods of Client (and of Batch, see below):

    put_fixture(fixture)                   -> PutResult   fixture.put
    get_fixture(fixture_id)                -> dict        fixture.get (the explicit form)
    delete_fixture(fixture_id, missing_ok=False) -> bool  fixture.delete
    list_fixtures(after=None, limit=None)  -> FixturePage [FixtureInfo]  fixture.list
                                              (a Client gathers every page
                                              unless after or limit is given)
    classify(fixture, wrenches, sets=("goal", "strong"), method="auto",
             tolerance=None)               -> [{set name: Verdict}]  wrench.classify
    cone(fixture, constraints)             -> Cone        cone.get
    plan(fixture)                          -> Plan        plan.get
    modes(fixture)                         -> Modes       modes.get
    push_regions(fixture, set="goal", finger_friction=0, finger_radius=0)
                                           -> PushRegions push.regions
    gravity_sweep(fixture, set="goal")     -> [[a, b]]    gravity.sweep (degrees)
    stability_margin(fixture, bias)        -> Disturbance stability.margin
    locating(fixture, tolerance, features=None, sigma_ratio=None)
                                           -> Locating    fixture.locating
    friction_sweep(fixture, range=(0, 2), kinetic_ratio=1.0, wrenches=None, sets=None,
                   push=None, gravity=None, force=None, cases=None, over=None)
                                           -> FrictionSweep  friction.sweep
    status()                               -> Status      server.status
    call(method, params=None, readonly=False) -> the raw "result" (any method)

A `fixture` argument is a fixture id (a string), a PutResult / FixtureInfo,
or a fixture dict (docs/PROTOCOL.md; sent inline, not stored).  A wrench is
(f_x, f_y, tau), tau about the centre of mass, or {"force": (f_x, f_y),
"at": (x, y)}.  Every method also takes `timeout=` (seconds, None: wait
forever) to override the client's timeout for that call.  Field names of the
dataclasses are those of PROTOCOL.md, and dataclasses.asdict() of a result
gives back its wire form.

Errors
    WrenchdError            the daemon answered with a JSON-RPC error: .code
                            (-32602, -32001, ...; constants below), .message,
                            .field (path into the request, e.g.
                            "params.fixture.body.mass"), .reason (a sentence).
    WrenchdUnavailable      (a ConnectionError) the daemon cannot be reached,
                            or the connection broke.  .maybe_executed tells
                            whether the request may have reached the daemon.
    WrenchdTimeout          (WrenchdUnavailable and TimeoutError) no answer
                            within the timeout.
    WrenchdProtocolError    (WrenchdUnavailable) the answer breaks the protocol.
    ValueError / TypeError  raised before anything is sent (a NaN, a wrong type).

Connections, reconnecting, retries
    A Client holds one connection, opened at the first call (or by
    connect()).  Before a request goes out on a connection that was used
    before, the client checks that the daemon has not closed it (it does when
    it stops or restarts); if it has, the request goes out on a new
    connection: a daemon restarted on the same socket is reconnected to
    transparently, whatever the method.  If the connection breaks *after* a
    request went out (no answer, or a reset), the request is sent again on a
    new connection, once, only when it is read-only (classify, get, list,
    cone, plan, modes, status; a batch only when all its requests are).
    fixture.put and fixture.delete then raise WrenchdUnavailable with
    maybe_executed=True: the daemon may or may not have done them.  A
    timeout is never retried (the daemon is alive but slow): the connection
    is closed (a late answer must not be read as the next one's) and
    WrenchdTimeout is raised.  A daemon that is not running gives
    WrenchdUnavailable at once; the next call tries again.

Batches
    with client.batch() as b:
        v = b.classify(fid, [(-1, -1, 0)])
        s = b.status()
    v.result()      # the value client.classify would return, or raises its error

    Each method of a Batch returns a Pending at once; the block's end sends
    every request as one JSON array line and reads the one answer line.  An
    error answer to one request raises only when that Pending's result() is
    read; a transport failure raises at the end of the block (and from every
    result()).  The daemon may run the requests of a batch in any order:
    do not classify in a batch a fixture you put in the same batch.  A batch
    with no request sends nothing; an exception inside the block sends
    nothing.  client.batch(timeout=...) bounds the whole exchange.

Threads
    Clients share nothing: several Client objects in one process are
    independent (no module-level state).  One Client may be used from
    several threads: a lock makes its calls take turns on its one connection
    (a Batch object itself belongs to one thread).  For calls that run in
    parallel, use one Client per thread: the daemon serves connections in
    parallel.
"""

from __future__ import annotations

import itertools
import json
import math
import os
import socket
import threading
import time
from dataclasses import MISSING, dataclass, fields
from dataclasses import field as dataclasses_field
from typing import Any, Callable, Dict, Iterable, List, Mapping, Optional, Sequence, Union

__all__ = [
    "Client", "Batch", "Pending",
    "WrenchdError", "WrenchdUnavailable", "WrenchdTimeout", "WrenchdProtocolError",
    "Verdict", "Witness", "Cone", "Plan", "PlanState", "Modes", "Status", "PutResult",
    "FixtureInfo", "FrictionSweep", "explain", "explain_goal", "explain_strong", "default_socket_path",
    "default_push_on", "loop_width", "explain_no_design", "explain_empty_regions", "with_tolerance",
    "PARSE_ERROR", "INVALID_REQUEST", "METHOD_NOT_FOUND", "INVALID_PARAMS", "INTERNAL_ERROR",
    "NO_SUCH_FIXTURE", "STORAGE_FAILURE", "LIMIT_EXCEEDED", "SOLVER_FAILURE",
]

__version__ = "0.1.0"

DEFAULT_TIMEOUT = 30.0
READ_ONLY_METHODS = frozenset(("wrench.classify", "fixture.get", "fixture.list", "cone.get",
                               "plan.get", "modes.get", "server.status", "friction.sweep"))

# JSON-RPC error codes (docs/PROTOCOL.md)
PARSE_ERROR = -32700
INVALID_REQUEST = -32600
METHOD_NOT_FOUND = -32601
INVALID_PARAMS = -32602
INTERNAL_ERROR = -32603
NO_SUCH_FIXTURE = -32001
STORAGE_FAILURE = -32002
LIMIT_EXCEEDED = -32003
SOLVER_FAILURE = -32004

_DEFAULT = object()     # "the client's timeout"


def on_supports(fixture: Mapping[str, Any], points: Sequence[Sequence[float]], friction: Any,
                g: float, down: Optional[Sequence[Mapping[str, Any]]] = None) -> Dict[str, Any]:
    """A copy of `fixture` lying on a base plate (docs/PROTOCOL.md,
    "Supports"): rest buttons at `points` with coefficient `friction` (a
    number, [lo, hi] or {"static", "kinetic"}), gravity `g` into the plate
    in the fixture's length / s^2, and down clamps [{"at": [x, y],
    "force": N}].  On supports wrench.classify and force.range answer with
    the buttons' friction; force_range(...)["all"]["goal"]["least"] is the
    least push force on the plate."""
    out = json.loads(json.dumps(fixture))
    supports: Dict[str, Any] = {"points": [list(p) for p in points], "friction": friction,
                                "g": g}
    if down:
        supports["down"] = [dict(d) for d in down]
    out["supports"] = supports
    return out


def default_socket_path() -> str:
    """$WRENCHD_SOCKET, else ./run/wrenchd.sock (the daemon's default)."""
    return os.environ.get("WRENCHD_SOCKET") or os.path.join(".", "run", "wrenchd.sock")


# ---- errors -------------------------------------------------------------------------

class WrenchdError(Exception):
    """A JSON-RPC error answer: code, message, field, reason (and data, method)."""

    def __init__(self, code: int, message: str, field: str = "", reason: str = "",
                 data: Any = None, method: Optional[str] = None):
        self.code = code
        self.message = message
        self.field = field
        self.reason = reason
        self.data = data
        self.method = method
        text = "%s (%s)" % (message, code)
        if field:
            text += " at %s" % field
        if reason:
            text += ": %s" % reason
        if method:
            text = "%s: %s" % (method, text)
        super().__init__(text)

    @classmethod
    def from_wire(cls, error: Any, method: Optional[str] = None) -> "WrenchdError":
        if not isinstance(error, dict) or not isinstance(error.get("code"), int):
            raise WrenchdProtocolError("an error answer without an integer code: %r"
                                       % (error,))
        data = error.get("data")
        field = reason = ""
        if isinstance(data, dict):
            field = data.get("field") or ""
            reason = data.get("reason") or ""
        return cls(error["code"], str(error.get("message", "")), field, reason, data, method)


class WrenchdUnavailable(ConnectionError):
    """The daemon cannot be reached, or the connection broke.  maybe_executed:
    the request may have reached the daemon (then it was not retried unless
    read-only)."""

    def __init__(self, message: str, socket_path: Optional[str] = None,
                 maybe_executed: bool = False):
        super().__init__(message)
        self.socket_path = socket_path
        self.maybe_executed = maybe_executed

    def __str__(self) -> str:
        return self.args[0] if self.args else ""


class WrenchdTimeout(WrenchdUnavailable, TimeoutError):
    """No answer within the timeout; the connection was closed."""


class WrenchdProtocolError(WrenchdUnavailable):
    """The daemon answered something the protocol does not allow; the
    connection was closed."""


# ---- results ------------------------------------------------------------------------

def _build(cls, obj: Any, what: str):
    if not isinstance(obj, dict):
        raise WrenchdProtocolError("%s: expected an object, got %r" % (what, obj))
    names = [f.name for f in fields(cls)]
    # A field with a default is one some answers leave out (a region's
    # "edge" on an outline, "area" of a body without a shape).
    missing = [f.name for f in fields(cls) if f.name not in obj
               and f.default is MISSING and f.default_factory is MISSING]
    if missing:
        raise WrenchdProtocolError("%s: the answer lacks %s" % (what, ", ".join(missing)))
    return cls(**{n: obj[n] for n in names if n in obj})  # members added later are ignored


@dataclass
class Witness:
    """A body acceleration [a_x, a_y, alpha], contact forces [[c_n, c_t], ...]
    (one per fixel) and the wrench [f_x, f_y, tau] they make."""
    acceleration: List[float]
    forces: List[List[float]]
    wrench: List[float]
    # Per fixel the friction coefficient its letter uses (None for s, a,
    # u): with friction intervals, a value in the interval at which the
    # motion is possible.  Left out by daemons before friction intervals.
    friction: Optional[List[Optional[float]]] = None
    # A fixture on supports: each support's friction force [f_x, f_y] on
    # the part and its normal force, in the fixture's force unit (None
    # without supports).
    support_forces: Optional[List[List[float]]] = None
    support_normals: Optional[List[float]] = None


@dataclass
class Verdict:
    """One wrench against one set (goal, strong or both)."""
    verdict: str                       # "inside" | "boundary" | "outside"
    inside: bool                       # verdict == "inside"
    margin: Optional[float]            # in [-1, 1]; None for method "lp"
    blocking: Optional[str]            # the excluded cone ("ms", "ll", "nn+"); None when inside
    states: List[str]                  # goal: contact states the blocking string comes from
    witness: Optional[Witness]         # None when inside
    # A fixture with a tolerance, outside: the contact points and normals
    # of a fixture of its set on which the wrench is outside (None else).
    perturbation: Optional[List[List[float]]] = None
    perturbation_normals: Optional[List[List[float]]] = None

    @classmethod
    def from_wire(cls, obj: Any) -> "Verdict":
        v = _build(cls, obj, "verdict")
        if v.witness is not None:
            v.witness = _build(Witness, v.witness, "witness")
        return v

    def explain(self, set_name: Optional[str] = None) -> str:
        """The verdict in words: see explain()."""
        return explain(self, set_name)


@dataclass
class PutResult:
    id: str
    name: str
    fixels: int
    goal_cones: int
    strong_cones: int
    pinned: bool
    # The mass properties in use, given or derived from the shape (area None
    # for a body without a shape).
    com: Optional[List[float]] = None
    inertia: Optional[float] = None
    area: Optional[float] = None


@dataclass
class FixtureInfo:
    id: str
    name: str
    fixels: int


@dataclass
class Cone:
    constraints: str
    empty: bool
    dimension: int                     # 0..3, -1 when empty
    halfspaces: List[List[float]]      # unit rows F: F g <= 0 on the closure
    equalities: List[List[float]]      # unit rows E: E g = 0
    generators: List[List[float]]
    strict: List[bool]                 # one per half-space: that face is open


@dataclass
class PlanState:
    state: str                         # "010": fixel 2 touched
    excluded: List[str]                # the transitions that must be impossible from it


@dataclass
class Plan:
    states: List[PlanState]
    cones: List[str]                   # the kept strings: the cones G_goal excludes


@dataclass
class Modes:
    feasible: List[str]                # moving modes; "n...n+" / "n...n-" when not pinned
    pinned: bool


@dataclass
class Status:
    version: str
    uptime_s: float
    fixtures: int
    cached: int
    cache_bytes: int
    cache_limit_bytes: int
    threads: int
    clients: int
    refused: int
    requests: int
    errors: int


@dataclass
class Region:
    """An open interval of the boundary: on a polygon, edge i runs from vertex
    i to vertex i+1 and t is the fraction along it; on a circle (edge 0) t is
    the boundary angle in degrees; on an outline (edge None) segment S of
    loop L runs from that loop's vertex S to the next and t is the fraction
    of its length."""
    t0: float
    t1: float
    length: float
    from_point: List[float]            # "from" on the wire
    to_point: List[float]              # "to"
    edge: Optional[int] = None         # polygon and circle
    loop: Optional[int] = None         # outline
    segment: Optional[int] = None      # outline


@dataclass
class PushRegions:
    regions: List[Region]
    total_length: float
    fraction: float                    # of the perimeter
    exact: bool                        # False: sampled (a finger with friction)
    resolution: float                  # the sampling step (t, or degrees); 0 when exact
    # An empty answer: why ({"reasons": [...]}, explain_empty_regions)
    why_empty: Optional[Dict[str, Any]] = None


@dataclass
class Disturbance:
    """stability.margin: how large a disturbance (scaled metric, force units)
    the seated part holds under a biasing wrench; all None when no contact
    mode moves the part at all."""
    margin: Optional[float]            # < 0: the bias itself moves the part
    blocking: Optional[str]            # the mode the worst disturbance starts
    worst_direction: Optional[List[float]]  # a wrench of unit scaled length
    # A fixture with a tolerance: the bias's verdict in G_strong over its
    # set ("inside", "boundary", "outside"; margin is then the worst), and
    # for outside the witness's contacts and normals.
    robust: Optional[str] = None
    perturbation: Optional[List[List[float]]] = None
    perturbation_normals: Optional[List[List[float]]] = None
    # A fixture on supports: [lo, hi] holding the exact margin (an end None
    # when nothing bounds it), and whether they met within 1e-6.
    bracket: Optional[List[Optional[float]]] = None
    converged: Optional[bool] = None


@dataclass
class Locating:
    """fixture.locating: where the part ends up when each locator is off
    along its normal within its tolerance.  Lengths in the fixture's unit,
    angles in radians.  When not `deterministic`, `free_motion` names the
    motion left free ({"twist": [vx, vy, w], "kind": "translation" |
    "rotation", "about": [x, y] | None}) and the rest is None."""
    deterministic: bool
    free_motion: Optional[Dict[str, Any]]
    sensitivity: Optional[List[List[float]]]  # G^-1: 3 rows (dx, dy, dtheta), one column per fixel
    condition: Optional[float]                # of the scaled locating matrix
    pose_error: Optional[Dict[str, List[float]]]  # {"linear", "exact"}: worst |dx|, |dy|, |dtheta|
    # Per feature: {"name", "at", "linear": {"vector", "length"}, "exact": {...},
    # "covariance": [[a, b], [b, d]], "ellipse": {"axes": [a1, a2], "angle_deg"}}
    features: Optional[List[Dict[str, Any]]]


@dataclass
class FrictionSweep:
    """friction.sweep: mu_s = mu and mu_k = kinetic_ratio * mu at every
    fixel, mu over a range.  For push or gravity: `intervals` of mu where
    the region is not empty, `critical` the mu above which it is empty
    (None when it is not empty at the top of the range; the bottom of the
    range when empty throughout), `curve` [[mu, size], ...] increasing in mu
    (the push region's total length, or the gravity arcs' total in
    degrees), and for push `exact` and `resolution`.  For force: `curve`
    [[mu, F], ...] the least push force (F None where no push does the job
    under every case), `at` its point per sample, `intervals` the mu where
    the push alone has a region (exact), `exact` False and `resolution` the
    grid's step.  For wrenches:
    `results`, one {set name: [[lo, hi], ...]} per wrench, the mu where it
    is inside; the other fields are then empty.  Over the supports' mu_B
    (over="supports"), push and gravity: one interval [low, critical], the
    curve's points each exact at its mu_B on a grid (`resolution` its step,
    `exact` False) and at `critical`, bisected to 1e-9."""
    intervals: List[List[float]] = dataclasses_field(default_factory=list)
    critical: Optional[float] = None
    curve: List[List[float]] = dataclasses_field(default_factory=list)
    exact: bool = True
    resolution: float = 0.0
    results: Optional[List[Dict[str, List[List[float]]]]] = None
    # force: the least push's point at each sample of `curve` ([x, y], None
    # where no push does it); `intervals` are then where the push alone has
    # a region.
    at: Optional[List[Optional[List[float]]]] = None


@dataclass
class Design:
    """One design of fixture.design: its `fixels` ([{"at", "normal"}]: put
    {"body", "friction", "fixels"} to ask anything else of it), the
    candidate sites chosen, the best push ({"at", "direction", "margin",
    ...}, None without a both region: push there and let go), the push
    regions' lengths, the longest goal arc of gravity tilts in degrees, the
    goal region's critical mu (None: not empty at mu = 2) and the score.
    On supports the figures of directions (best push, lengths, gravity,
    critical mu) are not made: None, and the score is minus the least
    push that seats the part on the plate (least_push, its "set" "goal")."""
    rank: int
    candidate: int
    fixels: List[Dict[str, List[float]]]
    score: float
    best_push: Optional[Dict[str, Any]] = None
    goal_length: Optional[float] = None
    both_length: Optional[float] = None
    gravity_goal_deg: Optional[float] = None
    critical_mu: Optional[float] = None
    sites: Optional[List[int]] = None          # the sites chosen (not on a lattice)
    pegs: Optional[List[List[int]]] = None     # a lattice: the pegs' holes
    # The fixels on holes: pins, [{"fixel", "hole", "diameter"}] (not on a lattice)
    pins: Optional[List[Dict[str, Any]]] = None
    pose: Optional[List[float]] = None         # a lattice: [x, y, theta in degrees]
    accuracy: Optional[float] = None           # objective accuracy: the worst locating error
    copies: int = 1                            # the candidates it stands for: its
                                               # images under the part's symmetries
    # With load cases: the least push doing both under every case ({"at",
    # "direction", "force", "lower_bound", ...}, None when none does).
    least_push: Optional[Dict[str, Any]] = None
    # Objective pareto: {"margin", "accuracy", "force" (None: no push does
    # both under the cases, or no cases)}, the figures of the front.
    pareto: Optional[Dict[str, Any]] = None


@dataclass
class DesignResult:
    """fixture.design: `designs` best first; `counts` {"candidates",
    "examined", "degenerate", "unpinned", "no_seating_push", "shared_hole",
    "symmetric"}; the number of `sites` (or, on a lattice, of `poses`), the
    `objective`, the `shard` [i, n], and the part's `symmetries` ([{"kind":
    "rotation" | "reflection", "angle_deg", "center"}], the identity first;
    None when collapse_symmetric=False)."""
    designs: List[Design]
    counts: Dict[str, int]
    sites: int = 0                     # candidate sites (0 on a lattice)
    poses: int = 0                     # a lattice: the poses found
    objective: str = "margin"
    shard: List[int] = dataclasses_field(default_factory=lambda: [0, 1])
    # Why candidates have no seating push: {"asked_at", "reasons": [{"blocking",
    # "states", "candidates"}]} (docs/PROTOCOL.md); see explain_no_design
    why_no_seating_push: Optional[Dict[str, Any]] = None
    symmetries: Optional[List[Dict[str, Any]]] = None


def _eta_text(seconds: float) -> str:
    s = int(seconds + 0.5)
    if s < 60:
        return "%d s" % s
    if s < 3600:
        return "%d min %d s" % (s // 60, s % 60)
    return "%d h %d min" % (s // 3600, s % 3600 // 60)


def progress_bar(stream: Any = None, width: int = 30) -> Callable[[Dict[str, Any]], None]:
    """A progress callable for Client.design(progress=...): a bar redrawn in
    place on `stream` (default sys.stderr), as wrenchctl draws it: the stage
    (a lattice's hole pairs, the candidates, the designs' figures), done of
    total, the estimated time left of the stage (eta_s) and the best score
    so far; a new line when a stage is done."""
    import sys
    out = stream if stream is not None else sys.stderr
    units = {"poses": "hole pairs", "candidates": "candidates", "figures": "designs' figures"}

    def show(params: Dict[str, Any]) -> None:
        done, total = params.get("done") or 0, params.get("total") or 0
        if total <= 0:
            return
        filled = int(width * done / total)
        line = "\r[%s%s] %3.0f%% %d/%d %s" % ("#" * filled, "." * (width - filled),
                                              100.0 * done / total, done, total,
                                              units.get(params.get("stage"), "candidates"))
        if params.get("eta_s") is not None and done < total:
            line += ", about %s left" % _eta_text(params["eta_s"])
        if params.get("best") is not None:
            line += ", best %.6g" % params["best"]
        out.write(line + ("\n" if done >= total else " " * 10))
        out.flush()
    return show


_NO_DESIGN_REASONS = ("shared_hole", "degenerate", "unpinned", "no_seating_push")


def explain_no_design(result: Union["DesignResult", Mapping[str, Any]]) -> List[str]:
    """Why a design found nothing, as lines, wrenchctl's: each reason with
    its count ("1,001 of 1,001 candidates"), and for the candidates without
    a seating push why the push asked about does not seat them, in the
    words of explain_goal ("from contact state 1010 fixel 3 may break
    away")."""
    if not isinstance(result, DesignResult):
        result = _design_result(dict(result))
    counts = result.counts
    lines = [_W["no_design"] % "{:,}".format(counts.get("examined", 0))]
    for key in _NO_DESIGN_REASONS:
        if counts.get(key, 0) > 0:
            lines.append("  {:,} {}".format(counts[key], _W["no_design_" + key]))
    why = result.why_no_seating_push or {}
    asked, reasons = why.get("asked_at") or {}, why.get("reasons") or []
    if reasons and asked.get("at"):
        if "loop" in asked:
            place = ", loop %d segment %d" % (asked["loop"], asked["segment"])
        elif "edge" in asked:
            place = ", edge %d" % asked["edge"]
        else:
            place = ""
        lines.append("  " + _W["no_design_asked"] % ("(%.6g, %.6g)%s" % (
            asked["at"][0], asked["at"][1], place)))
        for r in reasons:
            words = (explain_goal(r["blocking"], r["states"]) if r.get("blocking") is not None
                     else _W["no_design_unreached"])
            lines.append("    {:,} of {:,}: {}".format(r["candidates"],
                                                       counts.get("no_seating_push", 0), words))
    return lines


def explain_empty_regions(answer: Mapping[str, Any]) -> List[str]:
    """Why push.regions found no region (its why_empty), as lines,
    wrenchctl's: each reason with the number of edges whose middle it
    blocks.  [] when there are regions.  `answer` is the raw result
    (Client.call) or a PushRegions."""
    why = getattr(answer, "why_empty", None)
    if why is None and isinstance(answer, Mapping):
        why = answer.get("why_empty")
    reasons = (why or {}).get("reasons") or []
    edges = sum(r["edges"] for r in reasons)
    if not edges:
        return []
    lines = [_W["empty_region"] % edges]
    for r in reasons:
        if r.get("blocking") is None:
            words = _W["no_design_unreached"]
        elif r.get("set") == "goal":
            words = explain_goal(r["blocking"], r["states"])
        else:
            words = explain_strong(r["blocking"])
        lines.append("  %d of %d: %s" % (r["edges"], edges, words))
    return lines


def _design_result(result: Any) -> DesignResult:
    if not isinstance(result, dict) or not isinstance(result.get("designs"), list):
        raise WrenchdProtocolError("fixture.design: the answer has no designs")
    designs = [_build(Design, d, "fixture.design") for d in result["designs"]]
    return _build(DesignResult, dict(result, designs=designs), "fixture.design")


def _friction_sweep_result(result: Any) -> FrictionSweep:
    if not isinstance(result, dict) or not (isinstance(result.get("results"), list)
                                            or isinstance(result.get("intervals"), list)
                                            or isinstance(result.get("curve"), list)):
        raise WrenchdProtocolError("friction.sweep: the answer has no results, intervals or "
                                   "curve")
    return _build(FrictionSweep, result, "friction.sweep")


def _sweep_part(value: Any, what: str) -> Dict[str, Any]:
    """push= or gravity= of friction_sweep: a set name, True (the defaults)
    or a dict of its members."""
    if value is True:
        return {}
    if isinstance(value, str):
        return {"set": value}
    if isinstance(value, Mapping):
        return dict(value)
    raise TypeError("%s is a set name, True or a dict, not %s" % (what, type(value).__name__))


def _push_result(result: Any) -> PushRegions:
    if not isinstance(result, dict) or not isinstance(result.get("regions"), list):
        raise WrenchdProtocolError("push.regions: the answer has no regions")
    regions = []
    for r in result["regions"]:
        if not isinstance(r, dict) or "from" not in r or "to" not in r:
            raise WrenchdProtocolError("push.regions: a region lacks from or to")
        w = dict(r, from_point=r["from"], to_point=r["to"])
        regions.append(_build(Region, w, "push.regions region"))
    rest = dict(result, regions=regions)
    return _build(PushRegions, rest, "push.regions")


def _sweep_result(result: Any) -> List[List[float]]:
    arcs = result.get("intervals_deg") if isinstance(result, dict) else None
    if not isinstance(arcs, list):
        raise WrenchdProtocolError("gravity.sweep: the answer has no intervals_deg")
    return arcs


def _classify_result(result: Any) -> List[Dict[str, Verdict]]:
    rows = result.get("results") if isinstance(result, dict) else None
    if not isinstance(rows, list):
        raise WrenchdProtocolError("wrench.classify: no results array in %r" % (result,))
    out = []
    for row in rows:
        if not isinstance(row, dict):
            raise WrenchdProtocolError("wrench.classify: a result is not an object: %r" % (row,))
        out.append({name: Verdict.from_wire(v) for name, v in row.items()})
    return out


_COLUMN_NAMES = ("verdicts", "margins", "blocking", "states", "witness")


def _columns_result(result: Any) -> Dict[str, Dict[str, Any]]:
    """A lean wrench.classify answer's pieces joined: {set: {column: all
    of it}}, "verdicts" a string of i/b/o, the others lists."""
    pieces = result.get("pieces") if isinstance(result, dict) else None
    count = result.get("count") if isinstance(result, dict) else None
    if not isinstance(pieces, list) or not isinstance(count, int):
        raise WrenchdProtocolError("wrench.classify: no count and pieces in %r" % (result,))
    out: Dict[str, Dict[str, Any]] = {}
    parts: Dict[str, Dict[str, list]] = {}
    total = 0
    for piece in pieces:
        if not isinstance(piece, dict) or not isinstance(piece.get("count"), int):
            raise WrenchdProtocolError("wrench.classify: a piece without a count: %r" % (piece,))
        total += piece["count"]
        for name, columns in piece.items():
            if name == "count":
                continue
            if not isinstance(columns, dict):
                raise WrenchdProtocolError("wrench.classify: set %s of a piece is %r"
                                           % (name, columns))
            for column, values in columns.items():
                if column not in _COLUMN_NAMES or len(values) != piece["count"]:
                    raise WrenchdProtocolError("wrench.classify: column %s of a piece is %r"
                                               % (column, values))
                parts.setdefault(name, {}).setdefault(column, []).append(values)
    if total != count:
        raise WrenchdProtocolError("wrench.classify: pieces of %d wrenches for %d"
                                   % (total, count))
    for name, columns in parts.items():
        out[name] = {}
        for column, lists in columns.items():
            if column == "verdicts":
                out[name][column] = "".join(lists)
            else:
                out[name][column] = [v for values in lists for v in values]
    return out


def _plan_result(result: Any) -> Plan:
    plan = _build(Plan, result, "plan.get")
    plan.states = [_build(PlanState, s, "plan.get state") for s in plan.states]
    return plan


class FixturePage(list):
    """A page of fixture.list: its FixtureInfo, and `more`: whether
    fixtures follow its last (ask again with after=page[-1].id)."""
    more = False


def _list_result(result: Any) -> "FixturePage":
    items = result.get("fixtures") if isinstance(result, dict) else None
    if not isinstance(items, list):
        raise WrenchdProtocolError("fixture.list: no fixtures array in %r" % (result,))
    page = FixturePage(_build(FixtureInfo, f, "fixture.list") for f in items)
    page.more = result.get("more") is True
    return page


def _object_result(result: Any) -> Dict[str, Any]:
    if not isinstance(result, dict):
        raise WrenchdProtocolError("fixture.get: not an object: %r" % (result,))
    return result


def _deleted_result(result: Any) -> bool:
    if not isinstance(result, dict) or not isinstance(result.get("deleted"), bool):
        raise WrenchdProtocolError("fixture.delete: no deleted flag in %r" % (result,))
    return result["deleted"]


def _missing_is_false(error: WrenchdError) -> bool:
    if error.code == NO_SUCH_FIXTURE:
        return False
    raise error


def _same(result: Any) -> Any:
    return result


# ---- explanations (the words of examples/demo.py) -----------------------------------

# Every word the clients explain a verdict with, this module and wrenchctl:
# the table below is written by the build from clients/explain_words.txt
# (clients/explain_gen.py), which also makes wrenchctl's wc_explain.h, so
# that both say the same.  Edit the data file, not the table.
# ---- BEGIN explain words: generated by clients/explain_gen.py from clients/explain_words.txt
_EXPLAIN_WORDS = {
    # a list of fixels: "fixel 1", "fixel 1 and fixel 2", "fixel 1, fixel 2 and fixel 3"
    "fixel": "fixel %d",
    "list_comma": ", ",
    "list_and": " and ",
    # a goal blocking string: the transition from each of its contact states
    "states_join": "; ",
    "stay": "from contact state %s it can stay as it is: ",
    "holds_one": "%s holds",
    "holds_many": "%s hold",
    "stay_and": " and ",
    "apart_one": "%s is never reached",
    "apart_many": "%s are never reached",
    "break_away": "from contact state %s %s may break away",
    "while_one": " while %s holds",
    "while_many": " while %s hold",
    # a strong blocking mode: a pivot, or the motion at each fixel
    "pivot": "it may pivot %s about its contact point",
    "pivot_plus": "counter-clockwise",
    "pivot_minus": "clockwise",
    "move": "it may start to move: ",
    "move_join": ", ",
    "move_fixel": "fixel %d %s",
    "motion_s": "separates",
    "motion_l": "slides left",
    "motion_r": "slides right",
    "motion_n": "rolls",
    "mode": "it may move in mode %s",
    # a verdict inside the set (explain() only: wrenchctl leaves it blank)
    "inside_goal": "seats the part from every contact state",
    "inside_strong": "once seated, it does not move",
    "inside_both": "seats the part from every contact state and, once seated, it does not move",
    # an empty design (explain_no_design); counts preformatted ("1,001")
    "no_design": "no design: no candidate has a push that seats the part.  Of %s candidates:",
    "no_design_shared_hole": "put two fixels in one hole (a pin is one fixel)",
    "no_design_degenerate": "are degenerate (fixels at one point with one normal, or too close)",
    "no_design_unpinned": "do not pin the part (it turns about a point with every contact kept)",
    "no_design_no_seating_push": "have no seating push",
    "no_design_asked": "why, for a push at %s, the middle of the longest segment pushed on:",
    "no_design_unreached": "that push seats the part, but the finger cannot push there",
    # an empty push region (explain_empty_regions)
    "empty_region": "no region: the push at the middle of each of the %d edges pushed on:",
}
# ---- END explain words
_W = _EXPLAIN_WORDS

MOTION = {letter: _W["motion_" + letter] for letter in "slrn"}


def _fixels_named(indices: Sequence[int]) -> str:
    names = [_W["fixel"] % (i + 1) for i in indices]
    if len(names) == 1:
        return names[0]
    return _W["list_comma"].join(names[:-1]) + _W["list_and"] + names[-1]


def _one_or_many(indices: Sequence[int], key: str) -> str:
    return _W[key + ("_one" if len(indices) == 1 else "_many")] % _fixels_named(indices)


def explain_goal(blocking: str, states: Sequence[str]) -> str:
    """Why a wrench does not seat the part: from each contact state, the
    transition the blocking string allows."""
    reasons = []
    for state in states:
        touched = [i for i, c in enumerate(state) if c == "1"]
        separating = [i for i in touched if i < len(blocking) and blocking[i] == "s"]
        holding = [i for i in touched if i < len(blocking) and blocking[i] == "m"]
        if not separating:
            apart = [i for i, c in enumerate(state) if c == "0"]
            parts = []
            if holding:
                parts.append(_one_or_many(holding, "holds"))
            if apart:
                parts.append(_one_or_many(apart, "apart"))
            reasons.append(_W["stay"] % state + _W["stay_and"].join(parts))
        else:
            text = _W["break_away"] % (state, _fixels_named(separating))
            if holding:
                text += _one_or_many(holding, "while")
            reasons.append(text)
    return _W["states_join"].join(reasons)


def explain_strong(blocking: str) -> str:
    """The motion a strong-set blocking mode allows."""
    if blocking[-1:] in ("+", "-"):
        return _W["pivot"] % _W["pivot_plus" if blocking[-1] == "+" else "pivot_minus"]
    if any(c not in MOTION for c in blocking):
        return _W["mode"] % blocking
    return _W["move"] + _W["move_join"].join(
        _W["move_fixel"] % (i + 1, MOTION[c]) for i, c in enumerate(blocking))


# ---- where the finger may push -------------------------------------------------------

WIDTH_STEPS = 180   # directions of a half turn at which a hole's width is measured


def loop_width(loop: Sequence[Sequence[float]]) -> float:
    """A loop's width (x, y, bulge rows as in an outline's shape): the least
    distance between two parallel lines holding it, over WIDTH_STEPS
    directions, arcs' bulges included (a circle's: its diameter).  The
    same measure as wrenchctl's (lib/wr_outline.h, wr_outline_loop_width)."""
    arcs, points = [], []
    for j, v in enumerate(loop):
        w = loop[(j + 1) % len(loop)]
        points.append((float(v[0]), float(v[1])))
        bulge = float(v[2]) if len(v) > 2 else 0.0
        if bulge:
            dx, dy = w[0] - v[0], w[1] - v[1]
            k = (1.0 - bulge * bulge) / (4.0 * bulge)
            c = ((v[0] + w[0]) / 2 - dy * k, (v[1] + w[1]) / 2 + dx * k)
            sweep = 4.0 * math.atan(bulge)
            start = math.atan2(v[1] - c[1], v[0] - c[0])
            arcs.append((c, math.hypot(v[0] - c[0], v[1] - c[1]),
                         start if sweep > 0 else start + sweep, abs(sweep)))

    def passes(frm, sweep, phi):
        return (phi - frm) % (2 * math.pi) <= sweep

    width = math.inf
    for k in range(WIDTH_STEPS):
        phi = math.pi * k / WIDTH_STEPS
        u = (math.cos(phi), math.sin(phi))
        along = [p[0] * u[0] + p[1] * u[1] for p in points]
        lo, hi = min(along), max(along)
        for c, r, frm, sweep in arcs:
            centre = c[0] * u[0] + c[1] * u[1]
            if passes(frm, sweep, phi):
                hi = max(hi, centre + r)
            if passes(frm, sweep, phi + math.pi):
                lo = min(lo, centre - r)
        width = min(width, hi - lo)
    return width


def default_push_on(body: Any, finger_radius: float = 0.0) -> Any:
    """The clients' push_on when none is given (docs/PROTOCOL.md, push_on):
    the outer boundary and every hole wider than the finger's diameter;
    a point finger (radius 0), whose size is not known, the outer boundary
    only -- never inside a screw hole.  None when the body has no holes
    (every loop is taken anyway), else "outer" or [0, holes...]."""
    shape = body.get("shape") if isinstance(body, Mapping) else None
    if not isinstance(shape, Mapping) or shape.get("type") != "outline":
        return None
    loops = shape.get("loops") or []
    if len(loops) < 2:
        return None
    wide = [i for i, loop in enumerate(loops) if i > 0 and finger_radius > 0
            and loop_width(loop) > 2 * finger_radius]
    return [0] + wide if wide else "outer"


def explain(verdict: Union[Verdict, Mapping[str, Any]], set_name: Optional[str] = None) -> str:
    """The verdict for one set in words, in the language of `make demo`:

    * inside, goal:   "seats the part from every contact state"
    * inside, strong: "once seated, it does not move"
    * otherwise, a goal blocking string: the transition from each of its
      contact states ("from contact state 10 it can stay as it is: fixel 1
      holds and fixel 2 is never reached; from contact state 11 fixel 2 may
      break away while fixel 1 holds");
    * a strong blocking mode: "it may start to move: fixel 1 slides left,
      fixel 2 slides left", or "it may pivot counter-clockwise about its
      contact point" for n...n+ (clockwise for n...n-).

    set_name is "goal", "strong" or "both"; for "both" (or None) a blocking
    string with contact states is a goal string, one without a mode.
    `verdict` may be a Verdict or its wire form (a dict)."""
    if not isinstance(verdict, Verdict):
        verdict = Verdict.from_wire(dict(verdict))
    if verdict.inside or not verdict.blocking:
        if set_name in ("goal", "strong"):
            return _W["inside_" + set_name]
        return _W["inside_both"]
    if set_name == "goal" or (set_name != "strong" and verdict.states):
        return explain_goal(verdict.blocking, verdict.states)
    return explain_strong(verdict.blocking)


# ---- encoding -----------------------------------------------------------------------

def _json_default(obj: Any) -> Any:
    tolist = getattr(obj, "tolist", None)        # numpy arrays and scalars
    if callable(tolist):
        return tolist()
    if isinstance(obj, (set, frozenset)):
        return sorted(obj)
    raise TypeError("cannot send a %s to wrenchd" % type(obj).__name__)


def _encode(obj: Any) -> bytes:
    try:
        text = json.dumps(obj, separators=(",", ":"), allow_nan=False, default=_json_default)
    except ValueError as e:
        raise ValueError("wrenchd takes finite numbers only (%s)" % e) from None
    return text.encode("utf-8") + b"\n"


def _fixture_ref(fixture: Any) -> Any:
    if isinstance(fixture, str):
        return fixture
    if isinstance(fixture, (PutResult, FixtureInfo)):
        return fixture.id
    if isinstance(fixture, Mapping):
        return dict(fixture)
    raise TypeError("a fixture is an id string, a PutResult or a fixture dict, not %s"
                    % type(fixture).__name__)


def with_tolerance(fixture: Mapping[str, Any], position: float,
                   angle: float = 0.0) -> Dict[str, Any]:
    """A copy of a fixture dict with the geometric tolerance {"position":
    position, "angle": angle} (docs/PROTOCOL.md, "Tolerance"): every
    analysis of it then answers for each fixture whose contacts lie within
    `position` along the outline and whose normals within `angle` degrees.
    A stored fixture: get_fixture() it first."""
    if not isinstance(fixture, Mapping):
        raise TypeError("with_tolerance takes a fixture dict (get_fixture() a stored one)")
    out = dict(fixture)
    out["tolerance"] = {"position": position}
    if angle:
        out["tolerance"]["angle"] = angle
    return out


def _fixture_id(fixture_id: Any) -> str:
    if isinstance(fixture_id, (PutResult, FixtureInfo)):
        return fixture_id.id
    if not isinstance(fixture_id, str):
        raise TypeError("a fixture id is a string (or a PutResult), not %s"
                        % type(fixture_id).__name__)
    return fixture_id


def _cases(cases: Iterable[Any]) -> List[Dict[str, Any]]:
    """Cases as the protocol takes them: a case given as a bare list of
    loads becomes {"loads": [...]}."""
    return [dict(c) if isinstance(c, Mapping) else {"loads": list(c)} for c in cases]


def _wrench(w: Any) -> Any:
    if isinstance(w, Mapping):
        return dict(w)
    if isinstance(w, (str, bytes)):
        raise TypeError("a wrench is (f_x, f_y, tau) or {'force': ..., 'at': ...}, not %r" % (w,))
    try:
        return list(w)
    except TypeError:
        return w          # the daemon names what is wrong with it


# ---- the methods, shared by Client and Batch -----------------------------------------

class _Methods:
    def _invoke(self, method: str, params: Optional[Dict[str, Any]], convert: Callable,
                readonly: bool, timeout: Any, on_error: Optional[Callable] = None,
                notify: Optional[Callable] = None):
        raise NotImplementedError

    def _stored_body(self, fixture_id: str) -> Any:
        """A stored fixture's body, asked now (for the default push_on)."""
        return self.call("fixture.get", {"id": fixture_id}, readonly=True).get("body")

    def put_fixture(self, fixture: Mapping[str, Any], *, timeout: Any = _DEFAULT):
        """fixture.put: store a fixture (idempotent: same content, same id)."""
        if not isinstance(fixture, Mapping):
            raise TypeError("put_fixture takes a fixture dict")
        return self._invoke("fixture.put", {"fixture": dict(fixture)},
                            lambda r: _build(PutResult, r, "fixture.put"), False, timeout)

    def get_fixture(self, fixture_id: str, *, timeout: Any = _DEFAULT):
        """fixture.get: the stored fixture in its explicit form, with its name."""
        return self._invoke("fixture.get", {"id": _fixture_id(fixture_id)}, _object_result,
                            True, timeout)

    def delete_fixture(self, fixture_id: str, *, missing_ok: bool = False,
                       timeout: Any = _DEFAULT):
        """fixture.delete: True when deleted.  An unknown id raises
        WrenchdError (-32001), or gives False with missing_ok=True."""
        return self._invoke("fixture.delete", {"id": _fixture_id(fixture_id)}, _deleted_result,
                            False, timeout, _missing_is_false if missing_ok else None)

    def list_fixtures(self, *, after: Optional[str] = None, limit: Optional[int] = None,
                      timeout: Any = _DEFAULT):
        """fixture.list, one page: a FixturePage of FixtureInfo sorted by
        id, those after the id `after`, at most `limit` (the daemon's
        default 1000); its `more` says whether others follow.  A Client
        asked without after or limit gathers every page."""
        params: Dict[str, Any] = {}
        if after is not None:
            params["after"] = _fixture_id(after)
        if limit is not None:
            params["limit"] = limit
        return self._invoke("fixture.list", params, _list_result, True, timeout)

    def classify(self, fixture: Any, wrenches: Iterable[Any],
                 sets: Union[str, Sequence[str]] = ("goal", "strong"), method: str = "auto",
                 tolerance: Optional[float] = None, *, timeout: Any = _DEFAULT):
        """wrench.classify: one {set name: Verdict} per wrench, in order."""
        params = {"fixture": _fixture_ref(fixture), "wrenches": [_wrench(w) for w in wrenches],
                  "sets": [sets] if isinstance(sets, str) else list(sets), "method": method}
        if tolerance is not None:
            params["tolerance"] = tolerance
        return self._invoke("wrench.classify", params, _classify_result, True, timeout)

    def classify_columns(self, fixture: Any, wrenches: Iterable[Any],
                         fields: Sequence[str] = ("verdict",),
                         sets: Union[str, Sequence[str]] = ("goal", "strong"),
                         method: str = "auto", tolerance: Optional[float] = None, *,
                         timeout: Any = _DEFAULT):
        """wrench.classify with "fields" (a lean answer, computed only as far
        as asked): {set: {column: values}}, the pieces joined; "verdicts"
        is a string with one letter per wrench (i inside, b boundary, o
        outside), "margins", "blocking", "states" and "witness" are lists
        as the full answer has them."""
        params = {"fixture": _fixture_ref(fixture), "wrenches": [_wrench(w) for w in wrenches],
                  "sets": [sets] if isinstance(sets, str) else list(sets), "method": method,
                  "fields": list(fields)}
        if tolerance is not None:
            params["tolerance"] = tolerance
        return self._invoke("wrench.classify", params, _columns_result, True, timeout)

    def cone(self, fixture: Any, constraints: str, *, timeout: Any = _DEFAULT):
        """cone.get: the explicit cone G_X of a constraint string ("smu")."""
        return self._invoke("cone.get", {"fixture": _fixture_ref(fixture),
                                         "constraints": constraints},
                            lambda r: _build(Cone, r, "cone.get"), True, timeout)

    def plan(self, fixture: Any, *, timeout: Any = _DEFAULT):
        """plan.get: every contact state with its excluded strings; the kept strings."""
        return self._invoke("plan.get", {"fixture": _fixture_ref(fixture)}, _plan_result,
                            True, timeout)

    def modes(self, fixture: Any, *, timeout: Any = _DEFAULT):
        """modes.get: the feasible moving contact modes, and whether the body is pinned."""
        return self._invoke("modes.get", {"fixture": _fixture_ref(fixture)},
                            lambda r: _build(Modes, r, "modes.get"), True, timeout)

    def _push_on(self, ref: Any, push_on: Any, finger_radius: float) -> Any:
        """push_on as given, or default_push_on of the fixture's body (a
        stored fixture's is fetched)."""
        if push_on is not None:
            return push_on
        body = ref.get("body") if isinstance(ref, Mapping) else self._stored_body(ref)
        return default_push_on(body, finger_radius)

    def push_regions(self, fixture: Any, set: str = "goal", finger_friction: float = 0.0, *,
                     finger_radius: float = 0.0, push_on: Any = None,
                     force: Optional[float] = None, cases: Optional[Iterable[Any]] = None,
                     timeout: Any = _DEFAULT):
        """push.regions: where a finger pushing along the inward normal gives
        a wrench in the set (PushRegions).  finger_friction > 0: every force
        of the finger's friction cone must be in it (sampled).  finger_radius
        > 0: only where a disc of that radius touching the boundary from
        outside overlaps no part of the workpiece.  push_on: "outer", "all"
        or a list of loops; None: default_push_on of the fixture's body (a
        stored fixture's is fetched).  force F (and cases, see force_range):
        where a push of magnitude F does the set's job under every case
        (exact, a frictionless finger)."""
        params: Dict[str, Any] = {"fixture": _fixture_ref(fixture), "set": set}
        if finger_friction:
            params["finger_friction"] = finger_friction
        if finger_radius:
            params["finger_radius"] = finger_radius
        push_on = self._push_on(params["fixture"], push_on, finger_radius)
        if push_on is not None:
            params["push_on"] = push_on
        if force is not None:
            params["force"] = force
        if cases is not None:
            params["cases"] = _cases(cases)
        return self._invoke("push.regions", params, _push_result, True, timeout)

    def force_range(self, fixture: Any, cases: Iterable[Any], *,
                    push: Optional[Mapping[str, Any]] = None, wrench: Any = None,
                    sets: Optional[Sequence[str]] = None,
                    range: Optional[Sequence[float]] = None, timeout: Any = _DEFAULT):
        """force.range: the magnitudes F of one push (push={"at": [x, y],
        "direction"?: [dx, dy]}, or a wrench direction) that do each set's
        job under each case and under all of them, as the daemon's answer
        {"cases": [...], "all": {...}} (S = {"intervals", "least"}, None for
        no upper end), in the fixture's force unit.  A case is {"name"?,
        "loads": [...]} or a list of loads; a load {"gravity": {"g",
        "direction_deg"}}, {"force", "at"} or {"wrench"}."""
        if (push is None) == (wrench is None):
            raise ValueError("force_range takes push or wrench, one of them")
        params: Dict[str, Any] = {"fixture": _fixture_ref(fixture), "cases": _cases(cases)}
        if push is not None:
            params["push"] = dict(push)
        else:
            params["wrench"] = list(wrench)
        if sets is not None:
            params["sets"] = list(sets)
        if range is not None:
            params["range"] = [range[0], range[1]]
        return self._invoke("force.range", params, _object_result, True, timeout)

    def push_force(self, fixture: Any, cases: Iterable[Any], *, set: str = "both",
                   finger_radius: float = 0.0, push_on: Any = None,
                   samples: Optional[int] = None, timeout: Any = _DEFAULT):
        """push.force: the least force F*(p) of a push along the inward
        normal that does the set's job under every case, sampled exactly
        along every segment, and its minimum over the outline ("least":
        {"at", "direction", "force", "lower_bound", ...} or None).
        push_on as push_regions' (None: default_push_on of the body)."""
        params: Dict[str, Any] = {"fixture": _fixture_ref(fixture), "cases": _cases(cases),
                                  "set": set}
        if finger_radius:
            params["finger_radius"] = finger_radius
        push_on = self._push_on(params["fixture"], push_on, finger_radius)
        if push_on is not None:
            params["push_on"] = push_on
        if samples is not None:
            params["samples"] = samples
        return self._invoke("push.force", params, _object_result, True, timeout)

    def gravity_sweep(self, fixture: Any, set: str = "goal", *,
                      in_plane_g: Optional[float] = None, timeout: Any = _DEFAULT):
        """gravity.sweep: the arcs [a, b] of tilt (degrees, the direction
        gravity pulls) under which gravity alone gives a wrench in the set.
        On supports (on_supports) give `in_plane_g`, the pull in the tilted
        plate's plane (g sin(tilt)): the arcs proved to seat the part
        against the supports' friction (set "goal"); tilt_on_supports also
        returns the undecided arcs."""
        params: Dict[str, Any] = {"fixture": _fixture_ref(fixture), "set": set}
        if in_plane_g is not None:
            params["in_plane_g"] = in_plane_g
        return self._invoke("gravity.sweep", params, _sweep_result, True, timeout)

    def tilt_on_supports(self, fixture: Any, in_plane_g: float, *, timeout: Any = _DEFAULT):
        """gravity.sweep on supports, whole: {"intervals_deg": arcs proved
        to seat, "undecided_deg": arcs of at most 1e-6 degrees proved
        neither way}."""
        params = {"fixture": _fixture_ref(fixture), "set": "goal", "in_plane_g": in_plane_g}
        return self._invoke("gravity.sweep", params, lambda r: r, True, timeout)

    def stability_margin(self, fixture: Any, bias: Any, *, timeout: Any = _DEFAULT):
        """stability.margin: the disturbance a biasing wrench tolerates
        (Disturbance)."""
        return self._invoke("stability.margin", {"fixture": _fixture_ref(fixture),
                                                 "bias": _wrench(bias)},
                            lambda r: _build(Disturbance, r, "stability.margin"), True, timeout)

    def locating(self, fixture: Any, tolerance: Union[float, Sequence[float]],
                 features: Optional[Iterable[Any]] = None, sigma_ratio: Optional[float] = None,
                 *, timeout: Any = _DEFAULT):
        """fixture.locating: locating accuracy (Locating).  `tolerance` is one
        number for every locator or one per fixel; a feature is (x, y), or
        {"name": ..., "at": (x, y)}, or a (name, (x, y)) pair."""
        params: Dict[str, Any] = {"fixture": _fixture_ref(fixture),
                                  "tolerance": tolerance if isinstance(tolerance, (int, float))
                                  else list(tolerance)}
        if features is not None:
            listed = []
            for f in features:
                if isinstance(f, Mapping):
                    listed.append(dict(f))
                elif len(f) == 2 and isinstance(f[0], str):
                    listed.append({"name": f[0], "at": list(f[1])})
                else:
                    listed.append({"at": list(f)})
            params["features"] = listed
        if sigma_ratio is not None:
            params["sigma_ratio"] = sigma_ratio
        return self._invoke("fixture.locating", params,
                            lambda r: _build(Locating, r, "fixture.locating"), True, timeout)

    def friction_sweep(self, fixture: Any, *, range: Sequence[float] = (0, 2),
                       kinetic_ratio: float = 1.0, wrenches: Optional[Iterable[Any]] = None,
                       sets: Optional[Union[str, Sequence[str]]] = None,
                       push: Any = None, gravity: Any = None, force: Any = None,
                       cases: Optional[Iterable[Any]] = None, over: Optional[str] = None,
                       timeout: Any = _DEFAULT):
        """friction.sweep: how the answers change with the friction, mu_s =
        mu and mu_k = kinetic_ratio * mu at every fixel (the fixture's own
        friction ignored), mu over `range` (FrictionSweep).  over="supports"
        sweeps the supports' mu_B of a fixture on a base plate instead
        (wrenches: where each seats, and with `sets` asking it where it is
        held, sampled as below; force: the least push on the plate; push:
        {"force": F, "cases"?, "push_on"?}, where a push that hard seats
        it; gravity: {"in_plane_g": A}, the tilts whose pull seats it; set
        goal for these).  Without it a fixture on a base plate
        sweeps its fixels' mu with the supports kept: the same questions,
        and wrenches with every set (strong and both sampled: `exact`
        False, every mu given proved held).  Exactly one of
        `wrenches` (with `sets`, default the daemon's: goal and strong),
        `push`, `gravity` and `force` (with `cases`, as force_range's: the
        least push force against mu); each of the last three is a set name,
        True (set goal; both for force) or a dict ({"set", "finger_friction",
        "finger_radius"} for push, {"set", "finger_radius", "push_on"} for
        force, whose push_on defaults to default_push_on of the body).  A
        fixture with a tolerance (with_tolerance) is answered robustly: the
        mu where the wrench, or the region, is proved for every fixture of
        its set, the curve the robust length (or least push) at each mu,
        `exact` False (a frictionless finger: finger_friction is refused)."""
        given = [name for name, value in (("wrenches", wrenches), ("push", push),
                                          ("gravity", gravity), ("force", force))
                 if value is not None]
        if len(given) != 1:
            raise ValueError("friction_sweep takes exactly one of wrenches, push, gravity and "
                             "force%s" % (", not " + " and ".join(given) if given else ""))
        if sets is not None and wrenches is None:
            raise ValueError("friction_sweep: sets go with wrenches")
        if (cases is None) != (force is None):
            raise ValueError("friction_sweep: cases go with force, and force needs them")
        params: Dict[str, Any] = {"fixture": _fixture_ref(fixture),
                                  "range": [float(x) for x in range],
                                  "kinetic_ratio": kinetic_ratio}
        if over is not None:
            params["over"] = over
        if wrenches is not None:
            params["wrenches"] = [_wrench(w) for w in wrenches]
            if sets is not None:
                params["sets"] = [sets] if isinstance(sets, str) else list(sets)
        elif push is not None:
            params["push"] = _sweep_part(push, "push")
            if "cases" in params["push"]:
                params["push"]["cases"] = _cases(params["push"]["cases"])
        elif force is not None:
            part = _sweep_part(force, "force")
            push_on = self._push_on(params["fixture"], part.get("push_on"),
                                    part.get("finger_radius", 0.0))
            if push_on is not None:
                part["push_on"] = push_on
            params["force"] = part
            params["cases"] = _cases(cases)
        else:
            params["gravity"] = _sweep_part(gravity, "gravity")
        return self._invoke("friction.sweep", params, _friction_sweep_result, True, timeout)

    def design(self, body: Mapping[str, Any], friction: Any, *, fixels: int = 3,
               sites: Optional[Iterable[Any]] = None, spacing: Optional[float] = None,
               lattice: Optional[Mapping[str, Any]] = None, objective: str = "margin",
               top: int = 10, finger_radius: float = 0.0, finger_friction: float = 0.0,
               push_on: Any = None, corner_clearance: Optional[float] = None,
               pin_diameter: Optional[float] = None, shard: Optional[Sequence[int]] = None,
               progress: Optional[Callable[[Dict[str, Any]], Any]] = None,
               tolerance: Optional[float] = None, features: Optional[Iterable[Any]] = None,
               cases: Optional[Iterable[Any]] = None, collapse_symmetric: bool = True,
               units: Optional[Mapping[str, str]] = None,
               fixel_tolerance: Optional[Mapping[str, float]] = None,
               supports: Optional[Mapping[str, Any]] = None, timeout: Any = _DEFAULT):
        """fixture.design: where to put `fixels` fixels among candidate
        sites (exactly one of `sites`, a list of {"at", "normal"?} or of
        [x, y]; `spacing`; `lattice`), ranked by `objective` (DesignResult).
        Objective "accuracy" takes `tolerance` and `features` (as locating);
        objective "pareto" takes them too, and `cases`: the designs no other
        beats on margin, accuracy and least force together, each with its
        `pareto` figures.
        `progress`, a callable, receives each design.progress notification's
        params ({"id", "stage", "done", "total", "best", "eta_s"}) as it
        arrives (progress_bar() draws them); the timeout is then the longest
        silence.  `shard` = (i, n): shard i of n.
        With `spacing`, `corner_clearance` (default spacing / 2) and
        `pin_diameter` (sites on holes are pins of that diameter).
        `push_on`: "outer", "all" or a list of loops; None: default_push_on
        (the outer boundary and the holes wider than the finger).  Designs
        that a symmetry of the part maps onto each other come once, with
        their `copies`; collapse_symmetric=False lists every one.
        Objective "force" ranks by the least push doing both under `cases`
        (as force_range's; with any objective each design then has its
        `least_push`); `units` ({"length", "force"}, as a fixture's) are
        those of the body, the cases and the forces answered.
        `fixel_tolerance` ({"position", "angle"?}, a fixture's tolerance):
        each design's both region and best push robust over it.
        `supports` ({"points", "friction", "g", "down"?}, a fixture's): the
        base plate under every candidate; objective "force" then ranks by
        the least push that seats the part on it (each design's least_push,
        set "goal"), "accuracy" as floating, the others are refused."""
        given = [name for name, value in (("sites", sites), ("spacing", spacing),
                                          ("lattice", lattice)) if value is not None]
        if len(given) != 1:
            raise ValueError("design takes exactly one of sites, spacing and lattice%s"
                             % (", not " + " and ".join(given) if given else ""))
        params: Dict[str, Any] = {"body": dict(body), "friction": friction, "fixels": fixels,
                                  "objective": objective, "top": top}
        if sites is not None:
            params["sites"] = [dict(x) if isinstance(x, Mapping) else {"at": list(x)}
                               for x in sites]
        elif spacing is not None:
            params["spacing"] = spacing
            if corner_clearance is not None:
                params["corner_clearance"] = corner_clearance
            if pin_diameter is not None:
                params["pin_diameter"] = pin_diameter
        else:
            params["lattice"] = dict(lattice)
        if finger_radius:
            params["finger_radius"] = finger_radius
        if finger_friction:
            params["finger_friction"] = finger_friction
        if push_on is None:
            push_on = default_push_on(body, finger_radius)
        if push_on is not None:
            params["push_on"] = push_on
        if shard is not None:
            params["shard"] = [int(shard[0]), int(shard[1])]
        if tolerance is not None:
            params["tolerance"] = tolerance
        if features is not None:
            params["features"] = [dict(f) if isinstance(f, Mapping) else {"at": list(f)}
                                  for f in features]
        if not collapse_symmetric:
            params["collapse_symmetric"] = False
        if progress is not None:
            params["progress"] = True
        if cases is not None:
            params["cases"] = _cases(cases)
        if units is not None:
            params["units"] = dict(units)
        if fixel_tolerance is not None:
            params["fixel_tolerance"] = dict(fixel_tolerance)
        if supports is not None:
            params["supports"] = dict(supports)
        return self._invoke("fixture.design", params, _design_result, True, timeout,
                            notify=progress)

    def status(self, *, timeout: Any = _DEFAULT):
        """server.status."""
        return self._invoke("server.status", {}, lambda r: _build(Status, r, "server.status"),
                            True, timeout)

    def call(self, method: str, params: Optional[Dict[str, Any]] = None, *,
             readonly: bool = False, timeout: Any = _DEFAULT):
        """Any method; returns its raw "result".  readonly=True allows one
        retry on a new connection when the connection breaks."""
        return self._invoke(method, params, _same, readonly, timeout)


# ---- the connection -----------------------------------------------------------------

# Notification lines (design.progress) begin so, as the daemon writes them.
_NOTIFICATION = b'{"jsonrpc":"2.0","method":'


class _Broken(Exception):
    """The connection broke; maybe_executed: some of the request went out."""

    def __init__(self, why: str, maybe_executed: bool):
        super().__init__(why)
        self.why = why
        self.maybe_executed = maybe_executed


_NOSIGNAL = getattr(socket, "MSG_NOSIGNAL", 0)


class Client(_Methods):
    """One connection to wrenchd at socket_path (default: $WRENCHD_SOCKET or
    ./run/wrenchd.sock).  timeout: seconds for each call (connecting,
    sending, answering); None waits forever.  See the module's docstring."""

    def list_fixtures(self, *, after: Optional[str] = None, limit: Optional[int] = None,
                      timeout: Any = _DEFAULT):
        page = _Methods.list_fixtures(self, after=after, limit=limit, timeout=timeout)
        if after is not None or limit is not None:
            return page
        every = FixturePage(page)
        while page.more and page:
            page = _Methods.list_fixtures(self, after=page[-1].id, timeout=timeout)
            every.extend(page)
        return every

    def __init__(self, socket_path: Optional[Union[str, "os.PathLike[str]"]] = None,
                 timeout: Optional[float] = DEFAULT_TIMEOUT):
        self.socket_path = os.fspath(socket_path) if socket_path is not None \
            else default_socket_path()
        self.timeout = timeout
        self._sock: Optional[socket.socket] = None
        self._buf = bytearray()
        self._scanned = 0
        self._lock = threading.Lock()
        self._ids = itertools.count(1)

    def __repr__(self) -> str:
        return "<wrenchd.Client %s%s>" % (self.socket_path,
                                          "" if self._sock else " (not connected)")

    def __enter__(self) -> "Client":
        return self

    def __exit__(self, *exc: Any) -> None:
        self.close()

    @property
    def connected(self) -> bool:
        return self._sock is not None

    def connect(self, timeout: Any = _DEFAULT) -> "Client":
        """Open the connection now (otherwise the first call does)."""
        deadline = self._deadline(timeout)
        with self._lock:
            if self._sock is None:
                self._connect(deadline)
        return self

    def close(self) -> None:
        """Close the connection; a later call opens a new one."""
        with self._lock:
            self._close()

    def batch(self, timeout: Any = _DEFAULT) -> "Batch":
        """A batch of requests sent as one line at the end of a with block."""
        return Batch(self, timeout)

    # ---- internals ----
    def _deadline(self, timeout: Any) -> Optional[float]:
        if timeout is _DEFAULT:
            timeout = self.timeout
        return None if timeout is None else time.monotonic() + float(timeout)

    def _left(self, deadline: Optional[float], doing: str, maybe_executed: bool) -> Optional[float]:
        if deadline is None:
            return None
        left = deadline - time.monotonic()
        if left <= 0:
            self._close()
            raise WrenchdTimeout("wrenchd at %s: timed out %s" % (self.socket_path, doing),
                                 self.socket_path, maybe_executed)
        return left

    def _close(self) -> None:
        if self._sock is not None:
            try:
                self._sock.close()
            except OSError:
                pass
        self._sock = None
        self._buf = bytearray()
        self._scanned = 0

    def _connect(self, deadline: Optional[float]) -> None:
        self._close()
        left = self._left(deadline, "connecting", False)
        sock = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
        try:
            sock.settimeout(left)
            sock.connect(self.socket_path)
        except socket.timeout:
            sock.close()
            raise WrenchdTimeout("wrenchd at %s: timed out connecting" % self.socket_path,
                                 self.socket_path, False) from None
        except OSError as e:
            sock.close()
            raise WrenchdUnavailable("cannot connect to wrenchd at %s: %s"
                                     % (self.socket_path, e.strerror or e),
                                     self.socket_path, False) from None
        except BaseException:
            sock.close()
            raise
        self._sock = sock

    def _stale(self) -> bool:
        """The daemon closed this connection (or sent something unasked)."""
        sock = self._sock
        previous = sock.gettimeout()
        try:
            sock.settimeout(0.0)
            sock.recv(1, socket.MSG_PEEK)
        except (BlockingIOError, InterruptedError):
            return False          # nothing to read: alive
        except OSError:
            return True
        finally:
            try:
                sock.settimeout(previous)
            except OSError:
                pass
        return True               # EOF, or an answer nobody asked for

    def _refusal(self) -> Optional[Dict[str, Any]]:
        """After the connection broke: an error line with id null that the
        daemon sent before closing it (too many clients), or None."""
        try:
            self._sock.settimeout(0.0)
            while True:
                chunk = self._sock.recv(1 << 16)
                if not chunk:
                    break
                self._buf += chunk
        except OSError:
            pass
        end = self._buf.find(b"\n")
        if end < 0:
            return None
        try:
            answer = json.loads(bytes(self._buf[:end]))
        except ValueError:
            return None
        if isinstance(answer, dict) and answer.get("id") is None \
                and isinstance(answer.get("error"), dict):
            return answer
        return None

    def _send(self, data: bytes, deadline: Optional[float]) -> None:
        view = memoryview(data)
        sent = 0
        while sent < len(data):
            self._sock.settimeout(self._left(deadline, "sending", sent > 0))
            try:
                sent += self._sock.send(view[sent:], _NOSIGNAL)
            except socket.timeout:
                self._close()
                raise WrenchdTimeout("wrenchd at %s: timed out sending (it does not read)"
                                     % self.socket_path, self.socket_path, sent > 0) from None
            except InterruptedError:
                continue
            except OSError as e:
                raise _Broken("sending: %s" % (e.strerror or e), sent > 0) from None

    def _notify(self, notify: Callable, line: bytes) -> None:
        try:
            params = json.loads(line).get("params")
        except ValueError:
            self._close()
            raise WrenchdProtocolError("wrenchd at %s: a notification that is not JSON: %.200r"
                                       % (self.socket_path, line)) from None
        try:
            notify(params)
        except BaseException:
            self._close()   # the answer is still to come: this connection is spent
            raise

    def _read_line(self, deadline: Optional[float]) -> bytes:
        while True:
            end = self._buf.find(b"\n", self._scanned)
            if end >= 0:
                line = bytes(self._buf[:end])
                del self._buf[:end + 1]
                self._scanned = 0
                return line
            self._scanned = len(self._buf)
            self._sock.settimeout(self._left(deadline, "waiting for the answer", True))
            try:
                chunk = self._sock.recv(1 << 18)
            except socket.timeout:
                self._close()
                raise WrenchdTimeout("wrenchd at %s: no answer within the timeout"
                                     % self.socket_path, self.socket_path, True) from None
            except InterruptedError:
                continue
            except OSError as e:
                raise _Broken("reading: %s" % (e.strerror or e), True) from None
            if not chunk:
                raise _Broken("the daemon closed the connection before answering", True)
            self._buf += chunk

    def _exchange(self, data: bytes, readonly: bool, timeout: Any, what: str,
                  notify: Optional[Callable] = None) -> Any:
        """Send one line and return the parsed answer line, reconnecting as
        the module's docstring says.  With `notify`, notifications before
        the answer (design.progress) go to it, their params; each renews
        the timeout."""
        deadline = self._deadline(timeout)
        with self._lock:
            for attempt in (1, 2):
                if self._sock is not None and self._stale():
                    self._close()
                if self._sock is None:
                    self._connect(deadline)
                try:
                    self._send(data, deadline)
                    line = self._read_line(deadline)
                    while notify is not None and line.startswith(_NOTIFICATION):
                        self._notify(notify, line)
                        deadline = self._deadline(timeout)
                        line = self._read_line(deadline)
                except _Broken as e:
                    refusal = self._refusal()
                    self._close()
                    if refusal is not None:
                        return refusal          # e.g. too many clients: a WrenchdError
                    if e.maybe_executed and not readonly:
                        raise WrenchdUnavailable(
                            "wrenchd at %s: %s; %s was not sent again: it changes state, and "
                            "may or may not have been done" % (self.socket_path, e.why, what),
                            self.socket_path, True) from None
                    if attempt == 2:
                        raise WrenchdUnavailable("wrenchd at %s: %s (on a new connection too)"
                                                 % (self.socket_path, e.why), self.socket_path,
                                                 e.maybe_executed) from None
                    continue
                try:
                    return json.loads(line)
                except ValueError:
                    self._close()
                    raise WrenchdProtocolError("wrenchd at %s answered a line that is not "
                                               "JSON: %r" % (self.socket_path, line[:200]),
                                               self.socket_path, True) from None
        raise AssertionError("unreachable")

    def _connection_error(self, answer: Any, method: str) -> None:
        """An answer that is not to our id: an error the daemon sends with
        id null (e.g. too many clients) or a protocol violation."""
        self.close()
        if isinstance(answer, dict) and answer.get("id") is None and "error" in answer:
            raise WrenchdError.from_wire(answer["error"], method)
        raise WrenchdProtocolError("wrenchd at %s: an answer that does not match the request: "
                                   "%.200r" % (self.socket_path, answer), self.socket_path, True)

    def _invoke(self, method, params, convert, readonly, timeout, on_error=None, notify=None):
        rid = next(self._ids)
        request = {"jsonrpc": "2.0", "method": method, "id": rid}
        if params is not None:
            request["params"] = params
        answer = self._exchange(_encode(request), readonly, timeout, method, notify)
        if not isinstance(answer, dict) or answer.get("id") != rid \
                or isinstance(answer.get("id"), bool):
            self._connection_error(answer, method)
        return _settle(answer, method, convert, on_error)


def _settle(answer: Dict[str, Any], method: str, convert: Callable,
            on_error: Optional[Callable]) -> Any:
    if "error" in answer:
        error = WrenchdError.from_wire(answer["error"], method)
        if on_error is not None:
            return on_error(error)
        raise error
    if "result" not in answer:
        raise WrenchdProtocolError("%s: an answer with neither result nor error: %.200r"
                                   % (method, answer))
    return convert(answer["result"])


# ---- batches ------------------------------------------------------------------------

class Pending:
    """The answer to one request of a Batch, known once the batch is sent."""

    def __init__(self, method: str, convert: Callable, on_error: Optional[Callable]):
        self.method = method
        self._convert = convert
        self._on_error = on_error
        self._answer: Optional[Dict[str, Any]] = None
        self._failure: Optional[BaseException] = None
        self._done = False

    def __repr__(self) -> str:
        return "<wrenchd.Pending %s%s>" % (self.method, " done" if self._done else "")

    def done(self) -> bool:
        """True once the batch was sent and answered (or failed)."""
        return self._done

    def result(self) -> Any:
        """What the Client method would have returned, or its exception."""
        if not self._done:
            raise RuntimeError("the batch has not been sent yet: read results after the "
                               "with block")
        if self._failure is not None:
            raise self._failure
        return _settle(self._answer, self.method, self._convert, self._on_error)

    def exception(self) -> Optional[BaseException]:
        """The exception result() would raise, or None."""
        try:
            self.result()
        except (WrenchdError, WrenchdUnavailable) as e:
            return e
        return None


class Batch(_Methods):
    """Requests collected in a with block and sent as one JSON array line.
    Its methods are those of Client, each returning a Pending."""

    def __init__(self, client: Client, timeout: Any = _DEFAULT):
        self.client = client
        self.timeout = timeout
        self._items: List[tuple] = []    # (id, method, encoded request, pending, readonly)
        self._sent = False

    def __len__(self) -> int:
        return len(self._items)

    def _stored_body(self, fixture_id: str) -> Any:
        # Asked on the client at once, not in the batch: the request being
        # built needs it.
        return self.client._stored_body(fixture_id)

    def __enter__(self) -> "Batch":
        return self

    def __exit__(self, exc_type: Any, exc: Any, tb: Any) -> None:
        if exc_type is None:
            self.send()
        else:
            self._fail(RuntimeError("the batch was not sent: its with block raised"))
            self._sent = True

    def _invoke(self, method, params, convert, readonly, timeout, on_error=None, notify=None):
        if notify is not None:
            raise ValueError("%s: progress needs a request of its own; a batch is answered "
                             "in one line" % method)
        if timeout is not _DEFAULT:
            raise TypeError("give the timeout to client.batch(timeout=...), not to one request")
        if self._sent:
            raise RuntimeError("this batch was sent already")
        request = {"jsonrpc": "2.0", "method": method, "id": next(self.client._ids)}
        if params is not None:
            request["params"] = params
        line = _encode(request)          # a NaN raises here, at its call
        pending = Pending(method, convert, on_error)
        self._items.append((request["id"], method, line[:-1], pending, readonly))
        return pending

    def _fail(self, failure: BaseException) -> None:
        for item in self._items:
            pending = item[3]
            pending._failure = failure
            pending._done = True

    def send(self) -> None:
        """Send the batch now (the with block's end does it).  Raises
        WrenchdUnavailable when the daemon cannot be reached or the
        connection breaks; errors of single requests wait in their Pending."""
        if self._sent:
            raise RuntimeError("this batch was sent already")
        self._sent = True
        if not self._items:
            return
        try:
            data = b"[" + b",".join(item[2] for item in self._items) + b"]\n"
            readonly = all(item[4] for item in self._items)
            answer = self.client._exchange(data, readonly, self.timeout, "the batch")
        except BaseException as e:
            self._fail(e)
            raise
        if isinstance(answer, dict) and answer.get("id") is None and "error" in answer:
            # the line was refused as a whole (too long, too many clients)
            error = WrenchdError.from_wire(answer["error"])
            for item in self._items:
                item[3]._answer = {"error": answer["error"]}
                item[3]._done = True
            if error.code == LIMIT_EXCEEDED and error.field == "":
                self.client.close()
            return
        if not isinstance(answer, list):
            self.client.close()
            failure = WrenchdProtocolError("wrenchd answered a batch with %.200r" % (answer,),
                                           self.client.socket_path, True)
            self._fail(failure)
            raise failure
        by_id = {}
        for item in answer:
            if isinstance(item, dict) and "id" in item and not isinstance(item["id"], bool):
                by_id[item["id"]] = item
        for rid, method, _, pending, _ in self._items:
            item = by_id.get(rid)
            if item is None:
                pending._failure = WrenchdProtocolError(
                    "%s: the batch's answer has no answer for id %s" % (method, rid),
                    self.client.socket_path, True)
            else:
                pending._answer = item
            pending._done = True
