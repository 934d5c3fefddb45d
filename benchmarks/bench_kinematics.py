"""Speed of the kinematics solver and its HTTP API, against a vectorised numpy closed-form baseline.

Run from the repository root:

    python -m benchmarks.bench_kinematics            # full run (about a minute)
    python -m benchmarks.bench_kinematics --quick    # short run, noisier numbers
    python -m benchmarks.bench_kinematics --no-http  # in-process only

It prints one markdown report and writes it into docs/BENCHMARKS.md between the markers
``<!-- kinematics:start -->`` and ``<!-- kinematics:end -->`` (the rest of the file is kept).
benchmarks/README.md explains every row. Nothing here changes environment variables: the BLAS
library, its kernel and its thread count are reported as found.
"""

from __future__ import annotations

import argparse
import contextlib
import cProfile
import json
import math
import os
import platform
import pstats
import sys
import time
import tracemalloc
import warnings
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from datetime import UTC, datetime
from functools import partial
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parent.parent
if str(ROOT) not in sys.path:  # run as `python benchmarks/bench_kinematics.py`
    sys.path.insert(0, str(ROOT))

import numpy as np  # noqa: E402

from benchmarks.sections import markers, write_section  # noqa: E402
from server import budget as budget_check  # noqa: E402
from server.local import serve_locally  # noqa: E402
from solver.analysis.instant import LinkageAnalysis, analyze  # noqa: E402
from solver.analysis.sweeps import Sweep, sweep  # noqa: E402
from solver.errors import LimitExceeded  # noqa: E402
from solver.model.scene import LinkageScene, parse_linkage  # noqa: E402
from solver.position.assembly import DriverInput, assemble  # noqa: E402
from solver.position.drivers import driver_input  # noqa: E402
from solver.position.topology import build_plan  # noqa: E402
from solver.teaching.presets import PRESETS, build_preset  # noqa: E402

DOC = ROOT / "docs" / "BENCHMARKS.md"
START, END = markers("kinematics")
ALL = ("position", "velocity", "acceleration")
SIZES = (360, 3600, 36000)
TRADE_SIZES = (36, 360, 3600, 36000)
BLAS_ENV = (
    "OPENBLAS_CORETYPE",
    "OPENBLAS_L2_SIZE",
    "OPENBLAS_NUM_THREADS",
    "OMP_NUM_THREADS",
    "MKL_NUM_THREADS",
)
AGREEMENT = 1e-9  # relative: baseline and solver must give the same answers to compare speeds

# Targets of issue 2 (Speed), issue 4 (worked solutions) and issue 22 (one executor).
INSTANT_TARGET_S = 1e-3
# Issue 22: against the lean closed form (issue 8 asked 2x with the compiled clone; issue 2 had 3x
# a heavier one).
SWEEP_RATIO_TARGET = 2.5
# Issue 8: a 360-sample sweep under pylinkage's numba-compiled step_fast_with_kinematics, timed in
# the same run when the optional extra `peers` is installed, else 0.32 ms as the issue measured.
SWEEP_360_TARGET_S = 0.32e-3
HTTP_INSTANT_TARGET_S = 10e-3
SOLUTION_TARGET_S = 20e-3


@dataclass(frozen=True)
class Budget:
    """How much each measurement runs; the quick run trades stability for time."""

    name: str
    repeats: int  # timeit-style repeats of a sweep
    repeat_seconds: float  # each repeat loops the call for at least this long
    instant_calls: int  # one-instant latencies, four-bar
    preset_calls: int  # one-instant latencies, every preset
    solution_calls: int  # worked solutions, every preset (in-process and over HTTP)
    http_calls: int  # /analyze requests
    http_sweeps: tuple[int, int, int]  # /sweep requests for 360, 3600, 36000 samples


FULL = Budget("full", 25, 0.1, 2000, 300, 100, 1000, (100, 40, 8))
QUICK = Budget("quick", 7, 0.02, 300, 40, 10, 200, (20, 8, 3))


# -- the baseline: a closed-form four-bar in numpy ------------------------------------------


@dataclass(frozen=True)
class FourBar:
    """Crank AB about A = (0, 0), coupler BC, rocker DC about D = (ground, 0); the crank turns
    at omega (rad/s) with angular acceleration alpha."""

    ground: float
    crank: float
    coupler: float
    rocker: float
    omega: float
    alpha: float = 0.0

    def scene_document(self, crank_angle_deg: float = 30.0) -> dict[str, Any]:
        """The same linkage as a four_bar preset (open assembly, no coupler point)."""
        return build_preset(
            "four_bar",
            {
                "ground": self.ground,
                "crank": self.crank,
                "coupler": self.coupler,
                "rocker": self.rocker,
                "crank_angle_deg": crank_angle_deg,
                "assembly": 0,
                "coupler_point_u": 0.0,
                "coupler_point_v": 0.0,
                "omega": self.omega,
                "alpha": self.alpha,
            },
        )


SEED_004 = FourBar(ground=1.0, crank=0.15, coupler=1.0, rocker=0.55, omega=8 * math.pi)


def closed_form(fb: FourBar, theta2: np.ndarray) -> dict[str, np.ndarray]:
    """Positions, velocities and accelerations of B and C, omega and alpha of coupler (3) and
    rocker (4), for crank angles ``theta2``, as lean as numpy allows: one square root and a few
    products per sample, no inverse trigonometry but the links' final atan2.

    C = B + f e + g (k x e) on the open branch (left of B -> D), e = D - B, f = (|e|^2 + b^2 -
    c^2) / 2|e|^2, g = sqrt(b^2 / |e|^2 - f^2). With r3 = C - B, r4 = C - D and
    x = r3 x r4, the loop closure differentiated (omega3 k x r3 - omega4 k x r4 = -v_B) dotted
    with r4 and r3: omega3 = -v_B.r4 / x, omega4 = -v_B.r3 / x; then with
    R = -a_B + omega3^2 r3 - omega4^2 r4: alpha3 = R.r4 / x, alpha4 = R.r3 / x."""
    a, b, c, d = fb.crank, fb.coupler, fb.rocker, fb.ground
    w2, al2 = fb.omega, fb.alpha
    bx, by = a * np.cos(theta2), a * np.sin(theta2)
    ex, ey = d - bx, -by  # B -> D
    inv = 1.0 / (ex * ex + ey * ey)
    f = 0.5 + (b * b - c * c) * 0.5 * inv
    g = np.sqrt(b * b * inv - f * f)
    r3x, r3y = f * ex - g * ey, f * ey + g * ex  # B -> C
    cx, cy = bx + r3x, by + r3y
    r4x, r4y = cx - d, cy  # D -> C
    vbx, vby = -w2 * by, w2 * bx
    abx, aby = -al2 * by - w2 * w2 * bx, al2 * bx - w2 * w2 * by
    inv_x = 1.0 / (r3x * r4y - r3y * r4x)
    w3 = -(vbx * r4x + vby * r4y) * inv_x
    w4 = -(vbx * r3x + vby * r3y) * inv_x
    Rx = -abx + w3 * w3 * r3x - w4 * w4 * r4x
    Ry = -aby + w3 * w3 * r3y - w4 * w4 * r4y
    al3 = (Rx * r4x + Ry * r4y) * inv_x
    al4 = (Rx * r3x + Ry * r3y) * inv_x
    return {
        "B.p": np.stack((bx, by), axis=1),
        "B.v": np.stack((vbx, vby), axis=1),
        "B.a": np.stack((abx, aby), axis=1),
        "C.p": np.stack((cx, cy), axis=1),
        "C.v": np.stack((-w4 * r4y, w4 * r4x), axis=1),
        "C.a": np.stack((-al4 * r4y - w4 * w4 * r4x, al4 * r4x - w4 * w4 * r4y), axis=1),
        "coupler.angle": np.arctan2(r3y, r3x),
        "rocker.angle": np.arctan2(r4y, r4x),
        "coupler.omega": w3,
        "rocker.omega": w4,
        "coupler.alpha": al3,
        "rocker.alpha": al4,
    }


def baseline_sweep(
    fb: FourBar, samples: int, start: float = math.radians(30.0)
) -> dict[str, np.ndarray]:
    """The baseline's whole sweep: one revolution from ``start``, everything closed form."""
    return closed_form(fb, start + 2.0 * math.pi * np.arange(samples) / samples)


def solver_values(result: Sweep) -> dict[str, np.ndarray]:
    """The solver's sweep (all quantities) in the baseline's keys."""
    m = result.motion
    out = {f"{point}.p": m.points[point].p for point in ("B", "C")}
    for point in ("B", "C"):
        out |= {
            f"{point}.v": computed(m.points[point].v),
            f"{point}.a": computed(m.points[point].a),
        }
    for link in ("coupler", "rocker"):
        out |= {
            f"{link}.omega": computed(m.links[link].omega),
            f"{link}.alpha": computed(m.links[link].alpha),
        }
    return out


def computed(value: np.ndarray | None) -> np.ndarray:
    """A quantity that was asked for (the solver gives None only for what was not)."""
    assert value is not None
    return value


def parse_and_analyze(doc: dict[str, Any]) -> LinkageAnalysis:
    """One instant from the document, as a request handler does it."""
    return analyze(parse_linkage(doc))


def max_rel_error(value: np.ndarray, reference: np.ndarray) -> float:
    """Largest difference over the cycle, relative to the largest magnitude of the reference."""
    return float(np.max(np.abs(value - reference)) / np.max(np.abs(reference)))


# -- timing helpers -------------------------------------------------------------------------


@dataclass(frozen=True)
class Stats:
    best: float
    p50: float
    p90: float
    p99: float
    count: int
    cpu: Stats | None = None  # the same calls in thread CPU time (``repeated``)

    @classmethod
    def of(cls, seconds: list[float] | np.ndarray, cpu: Stats | None = None) -> Stats:
        p50, p90, p99 = np.percentile(seconds, [50, 90, 99])
        return cls(float(np.min(seconds)), float(p50), float(p90), float(p99), len(seconds), cpu)


def repeated(
    fns: Sequence[Callable[[], object]], budget: Budget, repeats: int | None = None
) -> list[Stats]:
    """timeit-style: each repeat loops each of ``fns`` for at least ``budget.repeat_seconds``,
    one after the other (so that a change in the machine's load hits them alike); the statistics
    are over the repeats' seconds per call, wall clock, with the thread's CPU time alongside
    (``Stats.cpu``: what a loaded machine's other processes do not inflate)."""
    numbers = [_calibrate(fn, budget.repeat_seconds) for fn in fns]
    seconds: list[list[float]] = [[] for _ in fns]
    cpu: list[list[float]] = [[] for _ in fns]
    for _ in range(repeats or budget.repeats):
        for fn, number, out, out_cpu in zip(fns, numbers, seconds, cpu, strict=True):
            start = time.thread_time()
            out.append(_loop(fn, number) / number)
            out_cpu.append((time.thread_time() - start) / number)
    return [Stats.of(s, Stats.of(c)) for s, c in zip(seconds, cpu, strict=True)]


def _calibrate(fn: Callable[[], object], seconds: float) -> int:
    """How many calls last at least ``seconds`` (after a warm-up call)."""
    fn()
    number = 1
    while (elapsed := _loop(fn, number)) < seconds:
        number = max(number + 1, int(number * 1.2 * seconds / max(elapsed, 1e-9)))
    return number


def _loop(fn: Callable[[], object], number: int) -> float:
    start = time.perf_counter()
    for _ in range(number):
        fn()
    return time.perf_counter() - start


def latencies(fn: Callable[[], object], calls: int, warmup: int = 20) -> Stats:
    """Each call timed on its own (for p50 and p99 of single requests)."""
    for _ in range(min(warmup, calls)):
        fn()
    seconds = []
    for _ in range(calls):
        start = time.perf_counter()
        fn()
        seconds.append(time.perf_counter() - start)
    return Stats.of(seconds)


def peak_memory(fn: Callable[[], object]) -> int:
    """tracemalloc peak (bytes) of one call; numpy reports its buffers to tracemalloc."""
    tracemalloc.start()
    try:
        fn()
        return tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()


def page_faults(fn: Callable[[], object], calls: int = 20) -> float | None:
    """Minor page faults per call: memory handed back to the OS after one call and faulted in
    again by the next (glibc trims the heap when its free top exceeds a threshold)."""
    try:
        import resource
    except ImportError:  # not on this platform
        return None
    fn()
    before = resource.getrusage(resource.RUSAGE_SELF).ru_minflt
    for _ in range(calls):
        fn()
    return (resource.getrusage(resource.RUSAGE_SELF).ru_minflt - before) / calls


def ms(seconds: float | None) -> str:
    return "n/a" if seconds is None else f"{seconds * 1e3:.3g} ms"


def mib(size: int) -> str:
    return f"{size / 2**20:.3g} MiB"


def table(headers: list[str], rows: list[list[str]]) -> str:
    lines = ["| " + " | ".join(headers) + " |", "|" + "---|" * len(headers)]
    return "\n".join(lines + ["| " + " | ".join(row) + " |" for row in rows])


def verdict(passed: bool | None) -> str:
    return "n/a" if passed is None else ("PASS" if passed else "MISS")


# -- measurements ---------------------------------------------------------------------------


@dataclass
class Results:
    sections: dict[str, str]  # markdown sections by title
    instant_p50: float | None = None
    sweep_ratio: float | None = None
    sweep_360_p50: float | None = None
    peer_360_p50: float | None = None  # pylinkage + numba, same run (None: not installed)
    sweep_3600_p50: float | None = None
    peer_3600_p50: float | None = None
    http_p50: float | None = None
    solution_p50: float | None = None


def measure_agreement(scene: LinkageScene) -> tuple[str, bool]:
    """Solver sweep versus baseline at the same samples: the answers must be the same."""
    result = sweep(scene, 3600, ALL)
    base = closed_form(SEED_004, result.driver_angle)
    ours = solver_values(result)
    units = {"p": "m", "v": "m/s", "a": "m/s^2", "omega": "rad/s", "alpha": "rad/s^2"}
    rows, worst = [], 0.0
    for key in (
        "C.p",
        "C.v",
        "C.a",
        "coupler.omega",
        "rocker.omega",
        "coupler.alpha",
        "rocker.alpha",
    ):
        unit = units[key.split(".")[1]]
        diff = float(np.max(np.abs(ours[key] - base[key])))
        scale = float(np.max(np.abs(base[key])))
        worst = max(worst, diff / scale)
        rows.append([key, f"{diff:.2e} {unit}", f"{scale:.4g} {unit}", f"{diff / scale:.1e}"])
    agree = worst < AGREEMENT and bool(result.feasible)
    header = (
        "Solver sweep versus baseline, seed-004 crank-rocker, 3600 samples, same crank "
        f"angles: {'the answers agree' if agree else 'THE ANSWERS DISAGREE'} "
        f"(worst relative difference {worst:.1e}, required < {AGREEMENT:.0e})."
    )
    return header + "\n\n" + table(
        ["quantity", "max abs difference", "max abs value", "relative"], rows
    ), agree


def pylinkage_step(n: int) -> Callable[[], object] | None:
    """pylinkage's numba-compiled ``step_fast_with_kinematics`` on the same four-bar
    (bench_tradeoff.PyLinkage), compiled; None without the optional extra ``peers``."""
    from benchmarks.bench_tradeoff import PyLinkage, peers  # it imports this module

    have = peers()
    if not (have["pylinkage"] and have["numba"]):
        return None
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        step = PyLinkage("four_bar", n)
        step()  # numba compiles on the first call
    return step


def cpu_of(stats: Stats) -> Stats:
    """The thread CPU time statistics of a ``repeated`` measurement."""
    assert stats.cpu is not None
    return stats.cpu


def measure_sweeps(scene: LinkageScene, budget: Budget, res: Results) -> str:
    """The sweep against the baseline and pylinkage + numba, alternating; the targets are
    checked on thread CPU time (the machine's other processes inflate wall clock time alike for
    all three, but not evenly), wall clock shown alongside."""
    rows = []
    for n in SIZES:
        peer = pylinkage_step(n) if n in (360, 3600) else None
        calls = [partial(baseline_sweep, SEED_004, n), partial(sweep, scene, n, ALL)]
        wall = repeated([*calls, *([peer] if peer else [])], budget)
        base, ours, *theirs = map(cpu_of, wall)
        ratio = ours.p50 / base.p50
        if n == 3600:
            res.sweep_ratio = ratio
            res.sweep_3600_p50 = ours.p50
            res.peer_3600_p50 = theirs[0].p50 if theirs else None
        if n == 360:
            res.sweep_360_p50 = ours.p50
            res.peer_360_p50 = theirs[0].p50 if theirs else None
        memory = [mib(peak_memory(call)) for call in calls]
        faults = ["n/a" if f is None else f"{f:.0f}" for f in map(page_faults, calls)]
        rows.append(
            [str(n), ms(base.p50), ms(ours.p50), ms(ours.p90), f"{ratio:.2f}x"]
            + [f"{ours.best / base.best:.2f}x"]
            + ([ms(theirs[0].p50), f"{ours.p50 / theirs[0].p50:.2f}x"] if theirs else ["-", "-"])
            + [" / ".join(ms(w.p50) for w in wall)]
            + [*memory, " / ".join(faults)]
        )
    headers = ["samples", "baseline p50", "solver p50", "solver p90", "solver / baseline (p50)"]
    headers += ["solver / baseline (best)", "pylinkage + numba p50", "solver / pylinkage (p50)"]
    headers += ["wall clock p50 (baseline / solver / pylinkage)"]
    headers += ["baseline peak mem", "solver peak mem", "page faults per call (baseline / solver)"]
    return (
        f"Seed-004 crank-rocker, one revolution, positions + velocities + accelerations, "
        f"in-process, scene parsed once; {budget.repeats} repeats, baseline, solver and "
        "pylinkage's numba-compiled `step_fast_with_kinematics` on the same four-bar (when the "
        "optional extra `peers` is installed) alternating. Times are thread CPU time (what the "
        "machine's other processes do not inflate) but for the wall clock column.\n\n"
        + table(headers, rows)
    )


def kernel_call(scene: LinkageScene, samples: int) -> Callable[[], object]:
    """The plan executor alone, as a sweep of ``samples`` calls it on the seed-004 four-bar (one
    driver turning fully): ``assemble`` over one revolution and one sample more, back at the
    start, all orders, with continuation; the plan looked up, the driver's inputs made once."""
    plan = build_plan(scene)
    start, omega, alpha = driver_input(scene, scene.drivers[0], scene.time)
    turns = start + 2.0 * math.pi * np.arange(samples + 1) / samples
    inputs = [DriverInput(turns, np.full(turns.size, omega), np.full(turns.size, alpha))]
    return partial(assemble, scene, plan, inputs, 2, continuation=True)


def measure_overhead(doc: dict[str, Any], budget: Budget) -> str:
    """Where a sweep's time goes: parsing and the plan (paid once per request, not in the
    sweep rows above), the plan executor, and the rest of ``sweep`` (its driver inputs,
    feasibility checks, the closing sample cut off, the result), by difference."""
    parsed = parse_linkage(doc)
    build_plan(parsed)
    rows = []
    for n in (360, 3600):
        calls = [
            partial(parse_linkage, doc),
            lambda: build_plan(parse_linkage(doc)),
            partial(build_plan, parsed),
            kernel_call(parsed, n),
            partial(sweep, parsed, n, ALL),
        ]
        parse, parse_plan, lookup, kernel, whole = (
            s.best for s in map(cpu_of, repeated(calls, budget))
        )
        plan = parse_plan - parse
        rest = whole - kernel - lookup
        share = f"{kernel / whole:.0%}"
        rows.append([str(n), *map(ms, (parse, plan, lookup, kernel, rest, whole)), share])
    headers = ["samples", "parse the document", "build the plan (first sweep of a scene)"]
    headers += ["plan lookup (kept on the scene)", "plan executor (`assemble`)"]
    headers += ["rest of `sweep`", "whole sweep", "executor share"]
    return (
        "Seed-004 crank-rocker, all quantities, thread CPU time, the best repeat (the parts are "
        "differences: the best repeats of a loaded machine are the least disturbed). The sweep "
        "rows above parse "
        "the scene once and build its plan once (it is kept on the scene); a /sweep request "
        "parses and builds both again. The plan executor is `assemble` over the sweep's own "
        "samples (one more than asked, back at the start); the rest of `sweep` is the whole "
        "sweep less the executor and the lookup.\n\n" + table(headers, rows)
    )


def measure_instant(doc: dict[str, Any], budget: Budget, res: Results) -> str:
    scene = parse_linkage(doc)
    full = latencies(partial(parse_and_analyze, doc), budget.instant_calls)
    only = latencies(lambda: analyze(scene), budget.instant_calls)
    res.instant_p50 = full.p50
    rows = [
        ["seed-004 four-bar: parse + analyze", ms(full.p50), ms(full.p99), str(full.count)],
        ["seed-004 four-bar: analyze (pre-parsed)", ms(only.p50), ms(only.p99), str(only.count)],
    ]
    for name in PRESETS:
        preset = build_preset(name, {})
        s = latencies(partial(parse_and_analyze, preset), budget.preset_calls)
        rows.append(
            [f"preset {name} (defaults): parse + analyze", ms(s.p50), ms(s.p99), str(s.count)]
        )
    return (
        "One instant, everything (positions, velocities, accelerations, poles, components, "
        "instant centres), in-process.\n\n" + table(["call", "p50", "p99", "calls"], rows)
    )


def solution_call(doc: dict[str, Any]) -> Callable[[], object]:
    """One worked solution in-process (issue 4): parse, solve (analysis included) and build
    the /solution response body as the route does (``as_dict(arrays=True)``), without HTTP."""
    import solver

    return lambda: solver.solve(doc, "vector", 4).as_dict(arrays=True)


def measure_solutions(budget: Budget, res: Results) -> str:
    rows, worst = [], 0.0
    for name in PRESETS:
        s = latencies(solution_call(build_preset(name, {})), budget.solution_calls, warmup=3)
        worst = max(worst, s.p50)
        rows.append(
            [f"preset {name} (defaults), method vector", ms(s.p50), ms(s.p99), str(s.count)]
        )
    res.solution_p50 = worst or None
    return (
        "Worked solution (issue 4), in-process: parse, solve and the /solution body.\n\n"
        + table(["scene", "p50", "p99", "calls"], rows)
    )


def measure_trade(scene: LinkageScene, budget: Budget) -> str:
    """What analytic derivatives buy: error of v_C and a_C against the closed form, for the
    solver's sweep and for finite differences of a position-only sweep."""
    rows = []
    for n in TRADE_SIZES:
        exact = sweep(scene, n, ALL)
        base = closed_form(SEED_004, exact.driver_angle)
        positions = sweep(scene, n, ["position"]).motion.points["C"].p
        dt = 2.0 * math.pi / n / abs(SEED_004.omega)  # uniform samples, constant crank speed
        ahead, behind = np.roll(positions, -1, axis=0), np.roll(positions, 1, axis=0)
        fd_v = (ahead - behind) / (2.0 * dt)
        fd_a = (ahead - 2.0 * positions + behind) / dt**2
        t_pos, t_all = repeated(
            [partial(sweep, scene, n, ["position"]), partial(sweep, scene, n, ALL)],
            budget,
            budget.repeats // 3,
        )
        ours = solver_values(exact)
        rows.append(
            [
                str(n),
                ms(t_pos.p50),
                f"{max_rel_error(fd_v, base['C.v']):.1e}",
                f"{max_rel_error(fd_a, base['C.a']):.1e}",
                ms(t_all.p50),
                f"{max_rel_error(ours['C.v'], base['C.v']):.1e}",
                f"{max_rel_error(ours['C.a'], base['C.a']):.1e}",
            ]
        )
    return (
        "Speed versus accuracy, seed-004 crank-rocker: maximum error over the cycle relative "
        "to the largest closed-form value. Finite differences: central differences of a "
        "position-only sweep (cyclic); analytic: the solver's own velocities and "
        "accelerations.\n\n"
        + table(
            [
                "samples",
                "position-only sweep p50",
                "FD v_C error",
                "FD a_C error",
                "full sweep p50",
                "analytic v_C error",
                "analytic a_C error",
            ],
            rows,
        )
    )


# -- over HTTP ------------------------------------------------------------------------------


def measure_http(doc: dict[str, Any], budget: Budget, res: Results) -> str:
    import httpx

    def poster(client: httpx.Client, path: str, body: dict[str, Any]) -> Callable[[], int]:
        payload = json.dumps(body).encode()

        def post() -> int:
            r = client.post(path, content=payload, headers={"content-type": "application/json"})
            if r.status_code != 200:
                raise RuntimeError(f"POST {path}: {r.status_code} {r.text[:300]}")
            return len(r.content)

        return post

    rows = []
    with serve_locally(timeout=60.0) as base, httpx.Client(base_url=base, timeout=60.0) as client:
        one = poster(client, "/api/v1/analyze", {"scene": doc})
        s = latencies(one, budget.http_calls, warmup=50)
        res.http_p50 = s.p50
        rows.append(
            ["/analyze one instant, everything", ms(s.p50), ms(s.p99), str(s.count), f"{one():,}"]
        )
        for n, count in zip(SIZES, budget.http_sweeps, strict=True):
            what = f"/sweep {n} samples, all quantities"
            try:
                budget_check.sweep(parse_linkage(doc), n, ALL)  # the server's own limits
            except LimitExceeded as refused:  # answered 413
                rows.append([what, f"refused (413): {str(refused).split(';')[0]}", "", "", ""])
                continue
            body = {"scene": doc, "samples": n, "quantities": list(ALL)}
            post = poster(client, "/api/v1/sweep", body)
            s = latencies(post, count, warmup=2)
            rows.append([what, ms(s.p50), ms(s.p99), str(s.count), f"{post():,}"])
        post = poster(client, "/api/v1/solution", {"scene": doc, "method": "vector"})
        s = latencies(post, budget.solution_calls, warmup=3)
        rows.append(
            ["/solution four-bar, method vector", ms(s.p50), ms(s.p99), str(s.count), f"{post():,}"]
        )
    versions = ", ".join(f"{m} {_version(m)}" for m in ("fastapi", "uvicorn", "httpx", "orjson"))
    return (
        "Over HTTP on loopback: uvicorn (1 worker, no access log) in a subprocess, one "
        f"httpx client with keep-alive, seed-004 four-bar ({versions}).\n\n"
        + table(["request", "p50", "p99", "requests", "response bytes"], rows)
    )


def _version(module: str) -> str:
    from importlib.metadata import PackageNotFoundError, version

    try:
        return version(module)
    except PackageNotFoundError:
        return "?"


# -- report ---------------------------------------------------------------------------------


def machine() -> str:
    model = platform.processor() or "unknown CPU"
    with contextlib.suppress(OSError):
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                model = line.split(":", 1)[1].strip()
                break
    return (
        f"{os.cpu_count()} cores, {model}; Python {platform.python_version()}; "
        f"numpy {np.__version__}; BLAS: {blas()}"
    )


def blas() -> str:
    env = ", ".join(f"{k}={os.environ[k]}" for k in BLAS_ENV if k in os.environ) or "none"
    try:
        from threadpoolctl import threadpool_info

        libs = (
            "; ".join(
                f"{i['internal_api']} {i.get('version')} ({Path(i['filepath']).parent.name}), "
                f"kernel {i.get('architecture')}, {i['num_threads']} threads"
                for i in threadpool_info()
            )
            or "none loaded"
        )
    except ImportError:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            config = np.show_config(mode="dicts")["Build Dependencies"]["blas"]
        libs = (
            f"{config.get('name')} {config.get('version')} (threads and kernel unknown: "
            "threadpoolctl is not installed)"
        )
    return f"{libs}; BLAS environment: {env}"


def targets(res: Results) -> str:
    def row(what: str, value: str, goal: str, passed: bool | None) -> list[str]:
        return [what, value, goal, verdict(passed)]

    def below(value: float | None, limit: float) -> bool | None:
        return None if value is None else value < limit

    ratio = res.sweep_ratio
    peer = res.peer_360_p50 or SWEEP_360_TARGET_S
    where_peer = "same run" if res.peer_360_p50 else "issue 8"
    solution = ms(res.solution_p50) if res.solution_p50 else "n/a"
    return table(
        ["target", "measured", "goal", "result"],
        [
            row(
                "one instant in-process, four-bar, parse + analyze (p50)",
                ms(res.instant_p50),
                "< 1 ms",
                below(res.instant_p50, INSTANT_TARGET_S),
            ),
            row(
                "3600-sample sweep, all quantities, in-process (CPU p50 / baseline CPU p50)",
                "n/a" if ratio is None else f"{ratio:.2f}x",
                f"<= {SWEEP_RATIO_TARGET:g}x",
                None if ratio is None else ratio <= SWEEP_RATIO_TARGET,
            ),
            row(
                "360-sample sweep, all quantities, in-process (CPU p50)",
                ms(res.sweep_360_p50),
                f"< {ms(peer)} (pylinkage + numba, {where_peer})",
                below(res.sweep_360_p50, peer),
            ),
            row(
                "3600-sample sweep, all quantities, in-process (CPU p50)",
                ms(res.sweep_3600_p50),
                f"< {ms(res.peer_3600_p50)} (pylinkage + numba, same run)"
                if res.peer_3600_p50
                else "< pylinkage + numba (not installed)",
                None if res.peer_3600_p50 is None else below(res.sweep_3600_p50, res.peer_3600_p50),
            ),
            row(
                "one instant over HTTP, /analyze (p50)",
                ms(res.http_p50) if res.http_p50 else "n/a (--no-http)",
                "< 10 ms",
                below(res.http_p50, HTTP_INSTANT_TARGET_S),
            ),
            row(
                "worked solution in-process, slowest preset (p50)",
                solution,
                "< 20 ms",
                below(res.solution_p50, SOLUTION_TARGET_S),
            ),
        ],
    )


def load() -> str:
    """1-minute load average: other processes on the machine compete with the benchmark."""
    with contextlib.suppress(OSError, AttributeError):
        return f"{os.getloadavg()[0]:.2f}"
    return "unknown"


def run(budget: Budget, http: bool) -> str:
    started, load_before = time.perf_counter(), load()
    doc = SEED_004.scene_document()
    scene = parse_linkage(doc)
    res = Results({})
    agreement, agree = measure_agreement(scene)
    res.sections["Sweeps in-process"] = measure_sweeps(scene, budget, res)
    res.sections["Where a sweep's time goes"] = measure_overhead(doc, budget)
    if not agree:
        res.sweep_ratio = None  # a ratio between different answers means nothing
    res.sections["One instant in-process"] = measure_instant(doc, budget, res)
    res.sections["Worked solutions in-process"] = measure_solutions(budget, res)
    res.sections["Speed versus accuracy"] = measure_trade(scene, budget)
    res.sections["Over HTTP"] = measure_http(doc, budget, res) if http else "Skipped (--no-http)."
    when = datetime.now(UTC).strftime("%Y-%m-%d %H:%M UTC")
    parts = [
        f"Measured {when} ({budget.name} run, {time.perf_counter() - started:.0f} s) by "
        "`python -m benchmarks.bench_kinematics`.\n\nMachine: " + machine() + ". Load "
        f"average (1 min) before the run {load_before}, after it {load()} (the machine has "
        f"{os.cpu_count()} cores: a load above 0 means other processes competed).",
        "### Targets\n\n" + targets(res),
        "### Agreement with the baseline\n\n" + agreement,
    ]
    parts += [f"### {title}\n\n{body}" for title, body in res.sections.items()]
    return "\n\n".join(parts)


TEMPLATE = f"""# Benchmarks

Measured, not asserted: these are benchmarks, not tests. Each section is written by its script;
run the script again to refresh it. How to run them and what each row means:
benchmarks/README.md.

## Kinematics: solver and API

{START}
{END}

## Front end

<!-- frontend:start -->
Placeholder for the front end's benchmark (benchmarks/frontend_fps.py): frames per second of the
animation and the plots.
<!-- frontend:end -->
"""


def write_doc(report: str) -> None:
    """Replace what stands between the kinematics markers; everything else is kept."""
    write_section(DOC, "kinematics", "Kinematics: solver and API", report, TEMPLATE)


def profile(budget: Budget) -> None:
    """cProfile of the in-process calls behind the targets: top functions by own time."""
    doc = SEED_004.scene_document()
    scene = parse_linkage(doc)
    calls: list[tuple[str, Callable[[], object], int]] = [
        ("sweep, 3600 samples, all quantities", lambda: sweep(scene, 3600, ALL), 200),
        ("parse + analyze, one instant", partial(parse_and_analyze, doc), budget.instant_calls),
    ]
    for title, fn, count in calls:
        profiler = cProfile.Profile()
        profiler.enable()
        for _ in range(count):
            fn()
        profiler.disable()
        print(f"\n## Profile: {title} x {count}, top by own time")
        pstats.Stats(profiler).sort_stats("tottime").print_stats(15)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--quick", action="store_true", help="short run (noisier numbers)")
    parser.add_argument("--no-http", action="store_true", help="skip the HTTP measurements")
    parser.add_argument("--no-write", action="store_true", help="print only; keep the doc as is")
    parser.add_argument(
        "--profile",
        action="store_true",
        help="also print cProfile hot spots of the in-process calls",
    )
    args = parser.parse_args()
    budget = QUICK if args.quick else FULL
    report = run(budget, http=not args.no_http)
    print(report)
    if not args.no_write:
        write_doc(report)
        print(f"\nwritten to {DOC.relative_to(ROOT)}")
    if args.profile:
        profile(budget)


if __name__ == "__main__":
    main()
