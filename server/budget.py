"""The cost of a request, checked after parsing and before any work: ``limit_exceeded`` (413).

Scene sizes are bounded by the parsers (200 points, 100 links, ...) and a time law by
``solver.laws`` (500 characters, ``MAX_COMPOSITION`` levels), but their products are not:

- response size: samples x (points + links + joints + moving points) x quantities, at most
  ``MAX_SWEEP_VALUES`` (about 20 MB of JSON; 200 points x 100,000 samples x every quantity
  made 2.5 GB);
- Newton-Raphson work: links solved by Newton-Raphson x the samples at which they are solved
  (a sweep adds its feasible-range search, an instant its continuation steps from the drawn
  pose), at most ``MAX_NEWTON_WORK`` link-samples (about 5 s on one core; a 20-sample sweep of
  a linkage with 24 triads took 45 s);
- an event search: t_max x the frequency of the moving point's law, at most
  ``MAX_OSCILLATIONS`` (the search resolves every turning point of s(t)).

Every refusal states the product and the limit.
"""

from __future__ import annotations

from collections.abc import Iterable
from typing import Any

import numpy as np

import solver
from solver.drivers import driver_input
from solver.errors import LimitExceeded
from solver.laws import parse_time_law
from solver.quantities import normalise_quantities
from solver.scene import MAX_TIME, LinkageScene
from solver.sweeps import BISECTION_STEPS, PROBE_SAMPLES
from solver.topology import NewtonStep, build_plan

MAX_SWEEP_VALUES = 500_000
MAX_NEWTON_WORK = 25_000  # link-samples; measured about 0.2 to 0.3 ms each
MAX_OSCILLATIONS = 5_000
FEASIBLE_RANGE_SEARCH = 2 * PROBE_SAMPLES + 2 * BISECTION_STEPS  # samples, at most
EVENT_GRID = 4097  # samples of |M - P| in an event search off M's carrier (solver.events)
FREQUENCY_GRID = 1 << 18  # samples of s'(t) that estimate a law's frequency
# A Newton group reaches a pose by following its path from the drawn pose (solver.continuation):
# the work is estimated as one correction per this much driver turn (a cost model, not a rule).
TURN_PER_CORRECTION = np.radians(5.0)


def _newton_links(scene: LinkageScene) -> int:
    return sum(len(s.links) for s in build_plan(scene).steps if isinstance(s, NewtonStep))


def _newton(scene: LinkageScene, samples: int, what: str) -> None:
    links = _newton_links(scene)
    if links * samples > MAX_NEWTON_WORK:
        raise LimitExceeded(
            f"Newton-Raphson work: {links} links solved by Newton-Raphson x {samples} samples "
            f"({what}) = {links * samples:,} link-samples, more than the limit of "
            f"{MAX_NEWTON_WORK:,}; use fewer samples"
        )


def instant(scene: LinkageScene) -> None:
    """/analyze and /solution of a linkage: Newton groups x continuation steps to the pose."""
    if not _newton_links(scene):
        return
    turned = max((abs(driver_input(scene, d, scene.time)[0]) for d in scene.drivers), default=0.0)
    _newton(scene, 1 + int(turned / TURN_PER_CORRECTION), "continuation steps to the pose")


def sweep(
    scene: LinkageScene, samples: int, quantities: Iterable[str] | None, in_time: bool
) -> None:
    """/sweep: the response's size, and the Newton work with the feasible-range search."""
    wanted = normalise_quantities(["position"] if quantities is None else quantities)
    entries = len(scene.points) + len(scene.links) + len(scene.joints) + len(scene.moving_points)
    values = samples * entries * len(wanted)
    if values > MAX_SWEEP_VALUES:
        raise LimitExceeded(
            f"response size: {samples} samples x {entries} points, links, joints and moving "
            f"points x {len(wanted)} quantities = {values:,}, more than the limit of "
            f"{MAX_SWEEP_VALUES:,}; ask for fewer samples or quantities"
        )
    if in_time:
        _newton(scene, samples, "over the time range")
    else:
        _newton(scene, samples + FEASIBLE_RANGE_SEARCH, "with the feasible-range search")


def event(scene: LinkageScene, moving_point: str, t_max: float) -> None:
    """/events: t_max x the law's frequency (and the Newton work of the distance search)."""
    for law in [d.angle_law for d in scene.drivers] + [m.s_law for m in scene.moving_points]:
        if law is not None:
            parse_time_law(law)  # a bad law is reported as such, before any budget
    mp = next((m for m in scene.moving_points if m.name == moving_point), None)
    if mp is None or not 0.0 < t_max <= MAX_TIME:
        return  # the solver's own message
    _newton(scene, EVENT_GRID, "the distance search")
    grid = np.linspace(0.0, t_max, FREQUENCY_GRID + 1)
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
