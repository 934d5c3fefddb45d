"""Speed against accuracy in one run: our solver's settings and the Python peers, on the same
linkages, against a 50-digit mpmath reference.

Run from the repository root (the peers are an optional extra: ``pip install -e '.[peers]'``):

    python -m benchmarks.bench_tradeoff             # a few minutes on 2 cores
    python -m benchmarks.bench_tradeoff --quick     # fewer repeats, noisier times
    python -m benchmarks.bench_tradeoff --no-write  # print only

It prints a markdown table and writes it into docs/BENCHMARKS.md between
``<!-- tradeoff:start -->`` and ``<!-- tradeoff:end -->``, with the Pareto front (time against
error, log-log) as a Plotly figure: docs/tradeoff.json (the figure), docs/tradeoff.html (the
figure drawn by the vendored Plotly, offline) and docs/tradeoff.svg (a static drawing of it for
the markdown). benchmarks/README.md says what each row means.
"""

from __future__ import annotations

import argparse
import importlib
import json
import math
import os
import subprocess
import sys
import time
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from dataclasses import dataclass
from datetime import UTC, datetime
from functools import cache
from importlib import metadata
from pathlib import Path
from typing import Any
from unittest import mock

ROOT = Path(__file__).resolve().parent.parent
if str(ROOT) not in sys.path:  # run as `python benchmarks/bench_tradeoff.py`
    sys.path.insert(0, str(ROOT))

import mpmath as mp  # noqa: E402
import numpy as np  # noqa: E402

from benchmarks.bench_kinematics import SEED_004, Budget, closed_form, repeated, table  # noqa: E402
from benchmarks.bench_newton import FULL_TURN, reference_error  # noqa: E402
from benchmarks.sections import write_section  # noqa: E402
from solver.analysis.sweeps import sweep  # noqa: E402
from solver.model.scene import LinkageScene, parse_linkage  # noqa: E402
from solver.position.topology import DriverStep, NewtonStep, Plan, build_plan  # noqa: E402
from solver.teaching.presets import build_preset  # noqa: E402

DOCS = ROOT / "docs"
ALL = ["position", "velocity", "acceleration"]
SAMPLE_COUNTS = (36, 72, 144, 360, 720, 1440, 3600)
PEER_COUNTS = (360, 3600)
TOLERANCES = (1e-15, 1e-13, 1e-10, 1e-8, 1e-6)
CHECKED = 360  # at most this many samples (and intervals) of a row are checked against mpmath
DRAWING_PX = 700.0  # the drawing's size on screen: the browser fits the mechanism in ~700 px
FLOOR = 1e-17  # errors below are drawn at this value on the log axis
FULL = Budget("full", 9, 0.05, 0, 0, 0, 0, (0, 0, 0))  # repeats of each row, seconds per repeat
QUICK = Budget("quick", 3, 0.02, 0, 0, 0, 0, (0, 0, 0))

Arrays = tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]  # angles, p, v, a (n, points, 2)


# -- the linkages and their 50-digit reference ------------------------------------------------


@dataclass(frozen=True)
class Case:
    """A linkage: its scene, its joints' positions in closed form at 50 digits as functions of
    the crank angle, the crank speed (constant: alpha = 0) and the drawing's size."""

    name: str
    doc: dict[str, Any]
    points: tuple[str, ...]
    position: Callable[[Any], list[tuple[Any, Any]]]  # crank angle (mpf) -> points' (x, y)
    omega: float
    start: float  # crank angle of the first sample, rad

    @property
    def scene(self) -> LinkageScene:
        return parse_linkage(self.doc)


def four_bar_position(theta: Any) -> list[tuple[Any, Any]]:
    """B on the crank circle; C = B + f e + g (k x e), e = D - B, on the open branch."""
    a, b, c, d = (mp.mpf(x) for x in ("0.15", "1.0", "0.55", "1.0"))
    bx, by = a * mp.cos(theta), a * mp.sin(theta)
    ex, ey = d - bx, -by
    e2 = ex * ex + ey * ey
    f = (e2 + b * b - c * c) / (2 * e2)
    g = mp.sqrt(b * b / e2 - f * f)
    return [(bx, by), (bx + f * ex - g * ey, by + f * ey + g * ex)]


def slider_crank_position(theta: Any) -> list[tuple[Any, Any]]:
    """x_C = x_B + sqrt(l^2 - (e - y_B)^2): B on the crank circle, C on the guide y = e."""
    r, rod, e = mp.mpf("0.1"), mp.mpf("0.35"), mp.mpf("0.05")
    bx, by = r * mp.cos(theta), r * mp.sin(theta)
    return [(bx, by), (bx + mp.sqrt(rod * rod - (e - by) ** 2), e)]


FOUR_BAR = Case(
    "four-bar (seed 004, crank-rocker)",
    SEED_004.scene_document(30.0),
    ("B", "C"),
    four_bar_position,
    SEED_004.omega,
    math.radians(30.0),
)
SLIDER = Case(
    "offset slider-crank (preset)",
    build_preset("slider_crank", {"coupler_point_u": 0.0, "coupler_point_v": 0.0}),
    ("B", "C"),
    slider_crank_position,
    10.0,
    math.radians(60.0),
)
CASES = {"four_bar": FOUR_BAR, "slider": SLIDER}


@cache
def reference_at(case_key: str, theta: float) -> np.ndarray:
    """(3, points, 2): position, velocity, acceleration at crank angle ``theta`` (alpha = 0, so
    v = omega dp/dtheta and a = omega^2 d2p/dtheta2), derivatives by mpmath at 50 digits."""
    case = CASES[case_key]
    mp.mp.dps = 50
    out = np.empty((3, len(case.points), 2))
    t = mp.mpf(theta)
    for i in range(len(case.points)):
        for axis in (0, 1):

            def coordinate(x: Any, i: int = i, axis: int = axis) -> Any:
                return case.position(x)[i][axis]

            for order in (0, 1, 2):
                value = coordinate(t) if order == 0 else mp.diff(coordinate, t, order)
                out[order, i, axis] = float(value * mp.mpf(case.omega) ** order)
    return out


def reference(case_key: str, angles: np.ndarray) -> np.ndarray:
    """(3, n, points, 2) at the given crank angles."""
    return np.stack([reference_at(case_key, float(t)) for t in angles], axis=1)


# -- the methods: each gives angles, p, v, a at its samples -----------------------------------


def ours(scene: LinkageScene, n: int, quantities: list[str] | None = None) -> Arrays:
    """Our sweep of ``n`` samples (all quantities unless told)."""
    result = sweep(scene, n, quantities or ALL)
    points = [result.motion.points[name] for name in ("B", "C")]
    p = np.stack([q.p for q in points], axis=1)
    if quantities == ["position"]:
        return result.driver_angle, p, p, p  # derivatives not asked for
    v, a = (np.stack([getattr(q, k) for q in points], axis=1) for k in "va")
    return result.driver_angle, p, v, a


def newton_plan(scene: LinkageScene) -> Plan:
    """The same linkage with every moving link but the driven ones in one Newton group."""
    drivers = tuple(s for s in build_plan(scene).steps if isinstance(s, DriverStep))
    known = {s.link for s in drivers} | {scene.ground}
    return Plan((*drivers, NewtonStep(tuple(k for k in scene.links if k not in known))))


@contextmanager
def forced_newton() -> Iterator[None]:
    """Sweeps in this block solve the closed-form groups by Newton-Raphson instead."""
    with mock.patch.object(
        importlib.import_module("solver.analysis.sweeps"), "build_plan", newton_plan
    ):
        yield


def ours_newton(scene: LinkageScene, n: int) -> Arrays:
    with forced_newton():
        return ours(scene, n)


def finite_differences(angles: np.ndarray, p: np.ndarray, omega: float) -> Arrays:
    """Central differences of a cyclic position sweep: v = (p+ - p-) / 2 dt,
    a = (p+ - 2p + p-) / dt^2, dt = 2 pi / (n omega)."""
    dt = 2.0 * math.pi / (angles.size * omega)
    after, before = np.roll(p, -1, axis=0), np.roll(p, 1, axis=0)
    return angles, p, (after - before) / (2 * dt), (after - 2 * p + before) / dt**2


def ours_fd(scene: LinkageScene, n: int, omega: float) -> Arrays:
    angles, p, _, _ = ours(scene, n, ["position"])
    return finite_differences(angles, p, omega)


def lean(n: int) -> Arrays:
    """bench_kinematics's lean numpy closed form of the four-bar."""
    angles = FOUR_BAR.start + 2.0 * math.pi * np.arange(n) / n
    cf = closed_form(SEED_004, angles)
    return angles, *(np.stack((cf[f"B.{q}"], cf[f"C.{q}"]), axis=1) for q in "pva")


def peers() -> dict[str, bool]:
    """Which peers are installed (the optional extra ``peers``)."""
    found = {}
    for name in ("pylinkage", "numba", "mechanism"):
        try:
            importlib.import_module(name)
            found[name] = True
        except ImportError:
            found[name] = False
    return found


class PyLinkage:
    """pylinkage's model of a case: ground pivots, a crank and one RRR or RRP dyad, stepped
    by ``step_fast_with_kinematics`` (numba-compiled unless NUMBA_DISABLE_JIT=1)."""

    def __init__(self, case_key: str, n: int) -> None:
        from pylinkage.actuators import Crank
        from pylinkage.components import Ground
        from pylinkage.dyads import RRPDyad, RRRDyad
        from pylinkage.simulation import Linkage

        case = CASES[case_key]
        self.n, self.start = n, case.start
        drawn = case.doc["points"]
        origin = Ground(0.0, 0.0, name="A")
        crank_length = math.hypot(*drawn["B"])
        crank = Crank(origin, crank_length, 2.0 * math.pi / n, case.start, name="crank")
        if case_key == "four_bar":
            pivot = Ground(*drawn["D"], name="D")
            out = RRRDyad(crank.output, pivot, 1.0, 0.55, *drawn["C"], name="C")
            grounds = [origin, pivot]
        else:
            e = drawn["C"][1]
            g1, g2 = Ground(0.0, e, name="G1"), Ground(1.0, e, name="G2")
            out = RRPDyad(crank.output, g1, g2, 0.35, *drawn["C"], name="C")
            grounds = [origin, g1, g2]
        self.linkage = Linkage([*grounds, crank, out])
        self.linkage.set_input_velocity(crank, omega=case.omega)
        self.columns = [len(grounds), len(grounds) + 1]  # B (crank), C

    def __call__(self) -> Arrays:
        p, v, a = self.linkage.step_fast_with_kinematics(iterations=self.n)
        # Each step turns the crank first: sample k is at start + (k + 1) step.
        angles = self.start + 2.0 * math.pi * np.arange(1, self.n + 1) / self.n
        return angles, p[:, self.columns], v[:, self.columns], a[:, self.columns]


class MechanismPkg:
    """The ``mechanism`` package: vector loops solved by scipy's fsolve at every sample."""

    def __init__(self, case_key: str, n: int) -> None:
        from mechanism import Mechanism, Vector, get_joints

        case = CASES[case_key]
        drawn = case.doc["points"]
        O, B, C, D = get_joints("O B C D")  # noqa: E741
        self.joints = (B, C)
        self.angles = case.start + 2.0 * math.pi * np.arange(n) / n
        theta0 = [math.atan2(drawn["C"][1] - drawn["B"][1], drawn["C"][0] - drawn["B"][0])]
        crank = Vector((O, B), r=math.hypot(*drawn["B"]))
        if case_key == "four_bar":
            rod = Vector((B, C), r=1.0)
            ground = Vector((O, D), r=1.0, theta=0.0, style="ground")
            rocker = Vector((D, C), r=0.55)
            theta0.append(math.atan2(drawn["C"][1], drawn["C"][0] - 1.0))

            def loop(x: Any, i: Any) -> Any:
                return crank(i) + rod(x[0]) - ground() - rocker(x[1])

            vectors = (crank, rod, ground, rocker)
        else:
            rod = Vector((B, C), r=0.35)
            offset = Vector((O, D), r=drawn["C"][1], theta=math.pi / 2, style="ground")
            slide = Vector((D, C), theta=0.0, style="dotted")
            theta0.append(drawn["C"][0])

            def loop(x: Any, i: Any) -> Any:
                return crank(i) + rod(x[0]) - offset() - slide(x[1])

            vectors = (crank, rod, offset, slide)
        self.mechanism = Mechanism(
            vectors=vectors, origin=O, loops=loop, pos=self.angles,
            vel=np.full(n, case.omega), acc=np.zeros(n),
            guess=(np.array(theta0), np.array([1.0, 1.0]), np.array([1.0, 1.0])),
        )  # fmt: skip

    def __call__(self) -> Arrays:
        self.mechanism.iterate()
        p, v, a = (
            np.stack([np.stack((getattr(j, f"x_{q}"), getattr(j, f"y_{q}")), 1)
                      for j in self.joints], axis=1)
            for q in ("positions", "velocities", "accelerations")
        )  # fmt: skip
        return self.angles, p, v, a


def pure_pylinkage(case_key: str, n: int, repeats: int) -> dict[str, Any]:
    """pylinkage without numba, in a child process with NUMBA_DISABLE_JIT=1: time and answer."""
    env = dict(os.environ, NUMBA_DISABLE_JIT="1")
    command = [sys.executable, "-m", "benchmarks.bench_tradeoff", "--pure-pylinkage",
               case_key, str(n), str(repeats)]  # fmt: skip
    out = subprocess.run(command, env=env, cwd=ROOT, capture_output=True, text=True, check=True)
    return dict(json.loads(out.stdout))


def pure_pylinkage_child(case_key: str, n: int, repeats: int) -> None:
    budget = Budget("child", repeats, 0.05, 0, 0, 0, 0, (0, 0, 0))
    seconds = repeated([PyLinkage(case_key, n)], budget)[0].p50
    angles, p, v, a = PyLinkage(case_key, n)()
    print(json.dumps({"p50": seconds, "arrays": [x.tolist() for x in (angles, p, v, a)]}))


# -- errors ----------------------------------------------------------------------------------


@dataclass
class Row:
    linkage: str
    method: str
    setting: str
    p50: float  # seconds
    position: float  # relative to the drawing's size
    velocity: float | None  # relative to the largest speed
    acceleration: float | None
    animation: float | None = None  # linear interpolation between samples, relative to size
    estimate: float | None = None  # the browser's estimate of it (second differences / 8)

    @property
    def error(self) -> float:
        """The worst of its position, velocity and acceleration errors at its samples."""
        return max(e for e in (self.position, self.velocity, self.acceleration) if e is not None)


def stride(n: int) -> int:
    return max(1, n // CHECKED)


def size_of(case_key: str) -> float:
    """The drawing's size: the larger side of the box of every point over the cycle."""
    angles = CASES[case_key].start + 2.0 * math.pi * np.arange(CHECKED) / CHECKED
    p = reference(case_key, angles)[0].reshape(-1, 2)
    fixed = np.array([xy for name, xy in CASES[case_key].doc["points"].items() if name in "AD"])
    box = np.vstack((p, fixed))
    return float(np.max(box.max(axis=0) - box.min(axis=0)))


def errors(case_key: str, arrays: Arrays) -> tuple[float, float, float]:
    """Position (of the size), velocity and acceleration (of their largest reference value)
    errors at every stride-th sample."""
    angles, p, v, a = (x[:: stride(arrays[0].size)] for x in arrays)
    ref = reference(case_key, angles)
    position = float(np.abs(p - ref[0]).max()) / size_of(case_key)
    velocity = float(np.abs(v - ref[1]).max() / np.abs(ref[1]).max())
    return position, velocity, float(np.abs(a - ref[2]).max() / np.abs(ref[2]).max())


def animation_error(case_key: str, angles: np.ndarray, p: np.ndarray) -> tuple[float, float]:
    """The browser's linear interpolation at the middle of every stride-th interval against the
    reference there, and the browser's estimate of it, max |p[k+1] - 2 p[k] + p[k-1]| / 8;
    both relative to the size."""
    k = np.arange(0, angles.size - 1, stride(angles.size))
    middle = 0.5 * (angles[k] + angles[k + 1])
    true = reference(case_key, middle)[0]
    worst = float(np.abs(0.5 * (p[k] + p[k + 1]) - true).max())
    second = p[2:] - 2 * p[1:-1] + p[:-2]
    estimate = float(np.hypot(second[..., 0], second[..., 1]).max()) / 8
    size = size_of(case_key)
    return worst / size, estimate / size


# -- the measurement ---------------------------------------------------------------------------


def timed(calls: dict[str, Callable[[], Arrays]], budget: Budget) -> dict[str, float]:
    """p50 seconds per call, the calls alternating repeat by repeat."""
    stats = repeated(list(calls.values()), budget)
    return {name: s.p50 for name, s in zip(calls, stats, strict=True)}


def measure_case(case_key: str, budget: Budget, have: dict[str, bool]) -> list[Row]:
    case = CASES[case_key]
    scene = case.scene
    rows: list[Row] = []
    for n in SAMPLE_COUNTS:
        calls: dict[str, Callable[[], Arrays]] = {"ours": lambda n=n: ours(scene, n)}
        if n in PEER_COUNTS:
            calls["ours, finite differences"] = lambda n=n: ours_fd(scene, n, case.omega)
            calls["ours, forced Newton"] = lambda n=n: ours_newton(scene, n)
            if case_key == "four_bar":
                calls["lean numpy closed form"] = lambda n=n: lean(n)
            if have["pylinkage"] and have["numba"]:
                calls["pylinkage + numba"] = PyLinkage(case_key, n)
        times = timed(calls, budget)
        for method, fn in calls.items():
            # pylinkage steps on from where its last call stopped: a fresh model for the answer
            arrays = PyLinkage(case_key, n)() if isinstance(fn, PyLinkage) else fn()
            position, velocity, acceleration = errors(case_key, arrays)
            row = Row(case.name, method, f"{n} samples", times[method], position, velocity,
                      acceleration)  # fmt: skip
            if method == "ours":
                row.animation, row.estimate = animation_error(case_key, arrays[0], arrays[1])
            rows.append(row)
        if n not in PEER_COUNTS:
            continue
        if have["pylinkage"]:
            child = pure_pylinkage(case_key, n, max(3, budget.repeats // 5))
            arrays = tuple(np.array(x) for x in child["arrays"])
            rows.append(Row(case.name, "pylinkage, no numba", f"{n} samples", child["p50"],
                            *errors(case_key, arrays)))  # type: ignore[arg-type]  # fmt: skip
        if have["mechanism"] and n == 360:
            model = MechanismPkg(case_key, n)
            p50 = timed({"m": model}, Budget("slow", 3, 0.0, 0, 0, 0, 0, (0, 0, 0)))["m"]
            rows.append(Row(case.name, "mechanism (fsolve)", f"{n} samples", p50,
                            *errors(case_key, model())))  # fmt: skip
    return rows


def measure_triad(budget: Budget) -> list[Row]:
    """The full-turning Stephenson III triad: the Newton tolerance, 360 samples."""
    scene = parse_linkage(FULL_TURN)
    calls = {t: (lambda t=t: sweep(scene, 360, ALL, tolerance=t)) for t in TOLERANCES}
    stats = repeated(list(calls.values()), budget, max(3, budget.repeats // 3))
    size = float(np.ptp(np.array(list(FULL_TURN["points"].values())), axis=0).max())
    rows = []
    for (tol, fn), s in zip(calls.items(), stats, strict=True):
        position = reference_error(fn(), FULL_TURN, 30) / size
        rows.append(Row("Stephenson III triad (Newton group)", "ours, Newton tolerance",
                        f"{tol:g}, 360 samples", s.p50, position, None, None))  # fmt: skip
    return rows


# -- the report and the figure -----------------------------------------------------------------


def sci(x: float | None) -> str:
    return "-" if x is None or math.isnan(x) else f"{x:.1e}"


def report_table(rows: list[Row]) -> str:
    body = [
        [r.linkage, r.method, r.setting, f"{r.p50 * 1e3:.3g}", sci(r.position), sci(r.velocity),
         sci(r.acceleration), sci(r.animation),
         "-" if r.animation is None else f"{r.animation * DRAWING_PX:.2g}",
         "-" if r.estimate is None or r.animation is None else f"{r.estimate / r.animation:.2f}"]
        for r in rows
    ]  # fmt: skip
    headers = ["linkage", "method", "setting", "p50 ms", "position error / size",
               "velocity error / max", "acceleration error / max",
               "animation error / size", f"animation error px at {DRAWING_PX:.0f} px",
               "estimate / true"]  # fmt: skip
    return table(headers, body)


def pareto(rows: list[Row]) -> list[Row]:
    """The rows no other row beats on both time and error, fastest first."""
    front: list[Row] = []
    for r in sorted(rows, key=lambda r: (r.p50, r.error)):
        if not front or r.error < front[-1].error:
            front.append(r)
    return front


def short(linkage: str) -> str:
    return linkage.split(" (")[0]


def figure(rows: list[Row]) -> dict[str, Any]:
    """The Plotly figure: every row by method, and the Pareto front, time against error."""
    traces: list[dict[str, Any]] = []
    for method in dict.fromkeys(r.method for r in rows):
        group = [r for r in rows if r.method == method]
        traces.append({
            "type": "scatter", "mode": "markers", "name": method,
            "x": [r.p50 * 1e3 for r in group], "y": [max(r.error, FLOOR) for r in group],
            "text": [f"{r.linkage}, {r.setting}" for r in group],
        })  # fmt: skip
    animated = [r for r in rows if r.animation is not None]
    traces.append({
        "type": "scatter", "mode": "markers", "name": "ours: the animation between samples",
        "marker": {"symbol": "x"},
        "x": [r.p50 * 1e3 for r in animated], "y": [r.animation for r in animated],
        "text": [f"{r.linkage}, {r.setting}" for r in animated],
    })  # fmt: skip
    for linkage in dict.fromkeys(r.linkage for r in rows):
        front = pareto([r for r in rows if r.linkage == linkage])
        traces.append({
            "type": "scatter", "mode": "lines", "name": f"Pareto front, {short(linkage)}",
            "line": {"dash": "dot"},
            "x": [r.p50 * 1e3 for r in front], "y": [max(r.error, FLOOR) for r in front],
        })  # fmt: skip
    layout = {
        "title": {"text": "Time against error, one run: the worst relative error of position, "
                  "velocity, acceleration at the samples (x: the animation between them)"},
        "xaxis": {"type": "log", "title": {"text": "p50 time per sweep (ms)"}},
        "yaxis": {"type": "log", "title": {"text": "relative error"}},
    }  # fmt: skip
    return {"data": traces, "layout": layout}


COLOURS = ("#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd", "#8c564b", "#e377c2",
           "#7f7f7f", "#bcbd22", "#17becf")  # fmt: skip


def svg(fig: dict[str, Any], width: int = 900, height: int = 560) -> str:
    """A static log-log drawing of the figure, for the markdown (no script)."""
    left, right, top, bottom = 70, 260, 30, 50
    xs = [x for t in fig["data"] for x in t["x"]]
    ys = [y for t in fig["data"] for y in t["y"]]
    x0, x1 = math.floor(math.log10(min(xs))), math.ceil(math.log10(max(xs)))
    y0, y1 = math.floor(math.log10(min(ys))), math.ceil(math.log10(max(ys)))

    def px(x: float, y: float) -> tuple[float, float]:
        u = (math.log10(x) - x0) / (x1 - x0)
        v = (math.log10(y) - y0) / (y1 - y0)
        return left + u * (width - left - right), height - bottom - v * (height - top - bottom)

    out = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{width}" height="{height}" '
           f'font-family="sans-serif" font-size="12"><rect width="100%" height="100%" '
           'fill="white"/>']  # fmt: skip
    for e in range(x0, x1 + 1):
        x, _ = px(10.0**e, 10.0**y0)
        out.append(f'<line x1="{x:.1f}" y1="{top}" x2="{x:.1f}" y2="{height - bottom}" '
                   f'stroke="#ddd"/><text x="{x:.1f}" y="{height - bottom + 16}" '
                   f'text-anchor="middle">1e{e}</text>')  # fmt: skip
    for e in range(y0, y1 + 1, 2):
        _, y = px(10.0**x0, 10.0**e)
        out.append(f'<line x1="{left}" y1="{y:.1f}" x2="{width - right}" y2="{y:.1f}" '
                   f'stroke="#ddd"/><text x="{left - 6}" y="{y + 4:.1f}" '
                   f'text-anchor="end">1e{e}</text>')  # fmt: skip
    middle = (top + height - bottom) / 2
    out.append(f'<text x="{(left + width - right) / 2}" y="{height - 12}" text-anchor="middle">'
               f'p50 time per sweep (ms)</text><text x="16" y="{middle}" '
               f'transform="rotate(-90 16 {middle})" text-anchor="middle">'
               'relative error</text>')  # fmt: skip
    for i, trace in enumerate(fig["data"]):
        colour = COLOURS[i % len(COLOURS)]
        points = [px(x, y) for x, y in zip(trace["x"], trace["y"], strict=True)]
        if trace["mode"] == "lines":
            path = " ".join(f"{x:.1f},{y:.1f}" for x, y in points)
            out.append(f'<polyline points="{path}" fill="none" stroke="{colour}" '
                       'stroke-width="1.5" stroke-dasharray="4 3"/>')  # fmt: skip
        else:
            out += [f'<circle cx="{x:.1f}" cy="{y:.1f}" r="4" fill="{colour}"/>' for x, y in points]
        ly = top + 10 + 18 * i
        lx = width - right + 16
        mark = (f'<line x1="{lx - 6}" y1="{ly - 4}" x2="{lx + 6}" y2="{ly - 4}" '
                f'stroke="{colour}" stroke-dasharray="4 3"/>' if trace["mode"] == "lines" else
                f'<circle cx="{lx}" cy="{ly - 4}" r="4" fill="{colour}"/>')  # fmt: skip
        out.append(f'{mark}<text x="{lx + 12}" y="{ly}">{trace["name"]}</text>')
    out.append("</svg>")
    return "\n".join(out) + "\n"


HTML = """<!doctype html>
<html lang="en"><head><meta charset="utf-8"><title>Speed against accuracy</title>
<script src="../static/vendor/plotly/plotly-basic.min.js"></script></head>
<body><div id="figure" style="width:100%;height:90vh"></div>
<script>
const figure = {figure};
Plotly.newPlot('figure', figure.data, figure.layout);
</script></body></html>
"""


def write(report: str, fig: dict[str, Any]) -> None:
    (DOCS / "tradeoff.json").write_text(json.dumps(fig, indent=1) + "\n")
    (DOCS / "tradeoff.html").write_text(HTML.replace("{figure}", json.dumps(fig)))
    (DOCS / "tradeoff.svg").write_text(svg(fig))
    write_section(DOCS / "BENCHMARKS.md", "tradeoff", "Speed against accuracy (issue 8)", report)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true")
    parser.add_argument("--no-write", action="store_true")
    parser.add_argument("--pure-pylinkage", nargs=3, help=argparse.SUPPRESS)
    args = parser.parse_args()
    if args.pure_pylinkage:
        key, n, repeats = args.pure_pylinkage
        pure_pylinkage_child(key, int(n), int(repeats))
        return
    budget = QUICK if args.quick else FULL
    load, began = os.getloadavg()[0], time.perf_counter()
    have = peers()
    rows = measure_case("four_bar", budget, have) + measure_case("slider", budget, have)
    rows += measure_triad(budget)
    missing = [name for name, found in have.items() if not found]
    fronts = [
        f"{short(linkage)}: "
        + "; ".join(
            f"{r.method} ({r.setting})" for r in pareto([r for r in rows if r.linkage == linkage])
        )
        for linkage in dict.fromkeys(r.linkage for r in rows)
    ]
    report = "\n".join([
        f"Measured {datetime.now(UTC):%Y-%m-%d %H:%M} UTC by `python -m benchmarks.bench_tradeoff"
        f"{' --quick' if args.quick else ''}` ({time.perf_counter() - began:.0f} s, one run; "
        f"1-minute load average before {load:.2f}, after {os.getloadavg()[0]:.2f} on "
        f"{os.cpu_count()} cores: a load above 0 means other processes competed, and the rows "
        "of one linkage and sample count alternate repeat by repeat, so their ratios hold "
        "better than the times).",
        "",
        "Peers: " + (", ".join(f"{n} {metadata.version(n)}" for n, f in
                               have.items() if f) or "none")
        + (f"; not installed, so skipped: {', '.join(missing)} (`pip install -e '.[peers]'`)"
           if missing else "") + ".",
        "",
        report_table(rows),
        "",
        "Pareto fronts (no other row of the linkage is both faster and more accurate): "
        + ". ".join(fronts) + ".",
        "",
        "![Time against error, log-log](tradeoff.svg)",
        "",
        "The same figure drawn by Plotly: [tradeoff.html](tradeoff.html) (offline, the vendored "
        "plotly-basic), its spec [tradeoff.json](tradeoff.json).",
    ])  # fmt: skip
    print(report)
    if not args.no_write:
        write(report, figure(rows))


if __name__ == "__main__":
    main()
