"""The cost of a request, checked after parsing and before any work: ``limit_exceeded`` (413).

Scene sizes are bounded by the parsers (200 points, 100 links, ...) and a time law by
``solver.model.laws`` (500 characters, ``MAX_COMPOSITION`` levels), but their products are not:

- response size: samples x (points + links + joints + moving points) x quantities (a spatial
  chain: points + bodies + joints), at most
  ``MAX_SWEEP_VALUES`` (about 20 MB of JSON; 200 points x 100,000 samples x every quantity
  made 2.5 GB);
- Newton-Raphson work: an estimate of the seconds of one core that the links solved by
  Newton-Raphson take, ``links x (samples + SETUP_SAMPLES + turn x SAMPLES_PER_RADIAN) x
  SAMPLE_COST`` (a sweep's samples, its path tracing and feasible-range search, and the radians
  the continuation walks from the drawn pose), at most the endpoint's default time limit divided
  by ``SAFETY``; and no Newton-Raphson group larger than ``MAX_GROUP_LINKS`` links (past it the
  cost grows far faster than the model: 64 links took 50 s for 20 samples). The constants are
  fitted to ``benchmarks/bench_budget.py`` (docs/SERVING.md quotes a run);
- an event search: t_max x the frequency of the moving point's law, at most
  ``MAX_OSCILLATIONS`` (the search resolves every turning point of s(t)).

Every refusal states the product and the limit.
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Sequence
from typing import Any

import numpy as np

import solver
from server.settings import TIME_LIMITS
from solver.errors import LimitExceeded
from solver.kinematics.spatial import SpatialChain
from solver.model.laws import parse_time_law
from solver.model.quantities import normalise_quantities
from solver.model.scene import MAX_TIME, LinkageScene
from solver.position.drivers import driver_inputs_over_time
from solver.position.topology import NewtonStep, build_plan

MAX_SWEEP_VALUES = 500_000
MAX_OSCILLATIONS = 5_000
EVENT_GRID = 4097  # samples of |M - P| in an event search off M's carrier (solver.analysis.events)
FREQUENCY_GRID = 1 << 18  # samples of s'(t) that estimate a law's frequency
# The Newton-Raphson cost model, fitted by benchmarks/bench_budget.py (best of 3, shared 2-core
# machine): the largest rate measured per link-sample (groups of up to 32 links, positions,
# velocities and accelerations), a sweep's fixed work in samples, and the continuation's cost per
# radian of driver turn in samples.
SAMPLE_COST = 70e-6  # s of one core per link-sample
SETUP_SAMPLES = 720  # fixed work: a revolution's path tracing and feasible-range search
SAMPLES_PER_RADIAN = 60  # walking the path from the drawn pose (instants, time sweeps, events)
MAX_GROUP_LINKS = 32  # the largest group measured
SAFETY = 2.0  # refused past the time limit / SAFETY: an estimate off by 2x still ends in time


def newton_groups(scene: LinkageScene) -> list[int]:
    """The size (links) of each group that ``scene`` solves by Newton-Raphson."""
    return [len(s.links) for s in build_plan(scene).steps if isinstance(s, NewtonStep)]


def newton_work(scene: LinkageScene, samples: int, turn: float) -> float:
    """Link-samples: links x (samples + SETUP_SAMPLES + turn x SAMPLES_PER_RADIAN)."""
    return sum(newton_groups(scene)) * (samples + SETUP_SAMPLES + SAMPLES_PER_RADIAN * turn)


def _response_size(samples: int, entries: int, what: str, quantities: int) -> None:
    """samples x entries x quantities values in a sweep's response, at most MAX_SWEEP_VALUES."""
    values = samples * entries * quantities
    if values > MAX_SWEEP_VALUES:
        raise LimitExceeded(
            f"response size: {samples} samples x {entries} {what} x {quantities} quantities = "
            f"{values:,}, more than the limit of {MAX_SWEEP_VALUES:,}; ask for fewer samples or "
            "quantities"
        )


def _newton(scene: LinkageScene, samples: int, turn: float, what: str, path: str) -> None:
    """Refuse Newton-Raphson work estimated past ``path``'s default time limit / SAFETY."""
    groups = newton_groups(scene)
    if not groups:
        return
    if max(groups) > MAX_GROUP_LINKS:
        raise LimitExceeded(
            f"Newton-Raphson work: a group of {max(groups)} links solved together by "
            f"Newton-Raphson, more than the limit of {MAX_GROUP_LINKS} links"
        )
    work = newton_work(scene, samples, turn)
    seconds, allowed = work * SAMPLE_COST, TIME_LIMITS[path] / SAFETY
    if seconds > allowed:
        raise LimitExceeded(
            f"Newton-Raphson work: {sum(groups)} links solved by Newton-Raphson x ({samples} "
            f"samples {what} + {SETUP_SAMPLES} for tracing the path + {turn:.4g} rad from the "
            f"drawn pose x {SAMPLES_PER_RADIAN}) = {work:,.0f} link-samples x "
            f"{SAMPLE_COST * 1e6:g} us = {seconds:.4g} s of estimated work, more than the limit "
            f"of {allowed:.4g} s ({path}'s time limit of {TIME_LIMITS[path]:g} s / safety "
            f"factor {SAFETY:g}); use fewer samples or a pose nearer the drawn one"
        )


def driver_turn(scene: LinkageScene, times: np.ndarray) -> float:
    """Radians the drivers turn from the drawn pose to reach every one of ``times`` (both ways)."""
    turns = np.concatenate([d.theta for d in driver_inputs_over_time(scene, times)] + [[0.0]])
    return float(np.max(turns) - np.min(turns))


def instant(scene: LinkageScene) -> None:
    """/analyze and /solution of a linkage: one sample, reached from the drawn pose."""
    _newton(
        scene, 1, driver_turn(scene, np.array([scene.time])), "(one instant)", "/api/v1/analyze"
    )


def sweep(
    scene: LinkageScene,
    samples: int,
    quantities: Iterable[str] | None,
    time_range: Sequence[float] | None = None,
) -> None:
    """/sweep: the response's size, and the Newton work with the feasible-range search."""
    wanted = normalise_quantities(["position"] if quantities is None else quantities)
    entries = len(scene.points) + len(scene.links) + len(scene.joints) + len(scene.moving_points)
    _response_size(samples, entries, "points, links, joints and moving points", len(wanted))
    if time_range is not None:
        valid = len(time_range) == 2 and all(math.isfinite(t) for t in time_range)
        grid = (
            np.linspace(time_range[0], time_range[-1], min(samples, FREQUENCY_GRID))
            if valid
            else np.zeros(1)
        )
        _newton(scene, samples, driver_turn(scene, grid), "over the time range", "/api/v1/sweep")
    else:
        _newton(scene, samples, 0.0, "over the revolution", "/api/v1/sweep")


def spatial_sweep(chain: SpatialChain, samples: int, quantities: Iterable[str] | None) -> None:
    """/sweep of a spatial chain over time: the response's size (bodies, points and joints)."""
    wanted = normalise_quantities(["position"] if quantities is None else quantities)
    entries = len(chain.points) + 2 * len(chain.joints)  # a body and its joint per joint
    _response_size(samples, entries, "bodies, joints and points", len(wanted))


def event(scene: LinkageScene, moving_point: str, t_max: float) -> None:
    """/events: t_max x the law's frequency (and the Newton work of the distance search)."""
    for law in [d.angle_law for d in scene.drivers] + [m.s_law for m in scene.moving_points]:
        if law is not None:
            parse_time_law(law)  # a bad law is reported as such, before any budget
    mp = next((m for m in scene.moving_points if m.name == moving_point), None)
    if mp is None or not 0.0 < t_max <= MAX_TIME:
        return  # the solver's own message
    grid = np.linspace(0.0, t_max, FREQUENCY_GRID + 1)
    _newton(scene, EVENT_GRID, driver_turn(scene, grid), "of the distance search", "/api/v1/events")
    rate = parse_time_law(mp.s_law).evaluate(grid)[1]
    turns = int(np.count_nonzero(np.diff(np.sign(rate)) != 0))
    # s' changes sign twice a period; past a quarter of the grid the grid no longer resolves it.
    resolved = turns < FREQUENCY_GRID // 4
    frequency = turns / (2.0 * t_max)
    oscillations = t_max * frequency
    if not resolved or oscillations > MAX_OSCILLATIONS:
        at_least = "" if resolved else "at least "
        raise LimitExceeded(
            f"event search: t_max x the frequency of {mp.name}'s law = {t_max:g} s x "
            f"{at_least}{frequency:.6g} Hz = {at_least}{oscillations:,.0f} oscillations, more "
            f"than the limit of {MAX_OSCILLATIONS:,}; lower t_max"
        )


def read_instant(doc: dict[str, Any], strict: bool) -> solver.ReadScene:
    """A one-instant request's scene (/analyze, /solution), refused before any work if it
    costs too much; its warnings kept for the result."""
    read = solver.read_scene(doc, strict=strict)
    if isinstance(read.scene, LinkageScene):
        instant(read.scene)
    return read
