"""The cost of a request, estimated from the scene before any work (``estimate_work``).

Three products that grow past what a scene's own bounds (200 points, 100 links, a law of 500
characters) keep in check:

- the response's size: samples x entries (points + links + joints + moving points; a spatial
  chain's points + bodies + joints; a gear train's ``sweep_entries``) x quantities;
- the Newton-Raphson work: the links solved by Newton-Raphson x (samples + ``SETUP_SAMPLES`` +
  ``SAMPLES_PER_RADIAN`` x the radians the drivers turn from the drawn pose), in link-samples,
  at ``SAMPLE_COST`` + the group's links x ``GROUP_SAMPLE_COST`` seconds of one core each (a
  sweep's samples, its path tracing and feasible-range search, and the walk of the
  continuation from the drawn pose). Every constant is fitted to ``benchmarks/bench_budget.py``
  (docs/BENCHMARKS.md quotes a run);
- the closed-form work: the groups solved in closed form x (samples + ``SETUP_SAMPLES``) at
  ``CLOSED_FORM_COST``, and, where the continuation follows the path, the radians the drivers
  turn from the drawn pose x the dyads and levers at ``TURN_COST`` (a group passing its change
  points twice a turn, as a parallelogram does, is the costliest walk measured: every pass is
  screened for its branch);
- an event search: t_max x the frequency of the moving point's law (the search resolves every
  turning point of s(t)), the frequency from the sign changes of s' on ``FREQUENCY_GRID``
  samples; its distance search is a sweep of ``EVENT_SAMPLES`` over the drivers' turn up to
  t_max (both works above);
- the seconds of the whole request (``WorkEstimate.seconds``, with ``reckoning`` stating the
  products), and of the requests that solve no scene given to them: exercises and their exports
  (``exercise_work``: count x the type's measured cost, and an export's sheet), a worked
  solution's writing (``SOLUTION_COST`` on top of its instant), a balancing
  (``BALANCE_COST``) and a synthesis task (``SYNTHESIS_COST``).

The estimate only counts; the caller compares it with its limits (the server: ``server.budget``).
Its parts are computed when first read, so a caller that refuses on the response's size does not
pay for the Newton groups' plan.
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Sequence
from dataclasses import dataclass
from functools import cached_property
from typing import Protocol

import numpy as np

from solver.analysis.events import DISTANCE_GRID
from solver.analysis.sweeps import check_samples
from solver.kinematics.spatial import SpatialChain
from solver.model.laws import parse_time_law
from solver.model.quantities import normalise_quantities
from solver.model.scene import MAX_TIME, LinkageScene
from solver.position.assembly import dense_parts, follows_path
from solver.position.drivers import driver_inputs_over_time
from solver.position.topology import DriverStep, DyadStep, LeverStep, NewtonStep, build_plan

FREQUENCY_GRID = 1 << 18  # samples of s'(t) that estimate a law's frequency
EVENT_SAMPLES = DISTANCE_GRID + 1  # samples of |M - P| in an event search (solver.analysis.events)
# The cost model: seconds of one core (CPU time) per unit of each kind of work, fitted by
# benchmarks/bench_budget.py to 146 requests of every kind (non-negative least squares on the
# ratio estimate / measured; its run of 2026-11-29 and the residual spread are in
# docs/BENCHMARKS.md, "The cost model, fitted"). The fixed cost of a request through the app
# (about 6 ms: HTTP, validation, serialising) is fitted and not charged.
# Newton-Raphson: a group of n links costs n x (SAMPLE_COST + n x GROUP_SAMPLE_COST) per sample
# (its Jacobian grows with it: a 32-link group costs 40 times a 4-link one per sample), over the
# sweep's samples, a fixed work and the walk of the continuation per radian from the drawn pose.
SAMPLE_COST = 2.9e-6  # s per link-sample
GROUP_SAMPLE_COST = 0.32e-6  # s per link-sample and link of its group
SETUP_SAMPLES = 260  # fixed work: a revolution's path tracing and feasible-range search
SAMPLES_PER_RADIAN = 19  # walking the path from the drawn pose (instants, time sweeps, events)
# Closed form: per group and sample, a group's fixed work in samples, and per radian of driver
# turn and two-branch group walked (a parallelogram, S003-T1, passes a change point every half
# turn and has each pass screened for its branch: the costliest walk measured).
CLOSED_FORM_COST = 4.6e-6  # s per closed-form group and sample
CLOSED_FORM_SETUP_SAMPLES = 360  # a closed-form group's fixed work, in samples
TURN_COST = 1.9e-3  # s per radian of driver turn and two-branch group (dyad or lever)
VALUE_COST = (
    0.36e-6  # s per value of the response of a scene solved in closed form alone (cams, ...)
)
# Work that solves no scene of the request's: a worked solution's writing beyond its instant
# (the fit's; a linkage's by the vector or loop method measured 50 to 75 ms more, a cam's or a
# gear train's less), a balancing (the fit leaves it to the fixed cost; measured whole: 5 ms),
# a synthesis task, and an exported exercise's sheet on top of the exercise (HTML with MathML).
SOLUTION_COST = 0.005
BALANCE_COST = 0.005
SYNTHESIS_COST = 0.043
EXPORT_COST = 0.017  # s per exercise exported, on top of the exercise
# s per exercise of each type at its costliest difficulty, (alone, with its worked solution),
# generation and serialisation included (fitted to 4 and 12 exercises alone, 2 and 5 with their
# solutions, and an export of 3 with them, of each type). A type not listed costs the costliest.
EXERCISE_COSTS: dict[str, tuple[float, float]] = {
    "four_bar_velocity": (0.0028, 0.031),
    "four_bar_acceleration": (0.0032, 0.033),
    "four_bar_poles": (0.0025, 0.028),
    "slider_crank": (0.0019, 0.02),
    "inverted_slider_crank": (0.0039, 0.022),
    "quick_return": (0.0072, 0.039),
    "slider_extension": (0.004, 0.027),
    "moving_point": (0.004, 0.18),
    "spatial_arm": (0.0019, 0.014),
    "four_bar_torque": (0.009, 0.049),
    "flywheel": (0.011, 0.06),
    "holding_torque": (0.0067, 0.04),
    "slider_crank_friction": (0.0096, 0.049),
    "planetary_output": (0.00047, 0.0045),
    "differential_carrier": (0.00085, 0.0051),
    "cam_follower_motion": (0.014, 0.026),
    "cam_pressure_angle": (0.017, 0.031),
    "synthesis_function": (0.012, 0.021),
    "synthesis_fixed_pivots": (0.0094, 0.015),
    # its fit (0.068 s both) times 0.57, what screening a draft on its foreseen answers saved
    # (25 against 44 ms alone, 37 against 64 with solutions, 2026-11-30)
    "synthesis_two_positions": (0.039, 0.039),
}


class ChapterScene(Protocol):
    """A scene of another chapter (a cam, a gear train), solved in closed form: it states its
    response's values per sample, ``(count, what they are)``."""

    @property
    def response_entries(self) -> tuple[int, str]: ...


@dataclass(frozen=True)
class NewtonWork:
    """The Newton-Raphson groups' work: each group of n links costs n x (``sample_cost`` + n x
    ``group_sample_cost``) per sample (a group's Jacobian grows with it), over (``samples`` +
    ``setup_samples`` + ``turn`` rad from the drawn pose x ``samples_per_radian``) samples."""

    groups: tuple[int, ...]
    samples: int
    turn: float
    setup_samples: int = SETUP_SAMPLES
    samples_per_radian: int = SAMPLES_PER_RADIAN
    sample_cost: float = SAMPLE_COST
    group_sample_cost: float = GROUP_SAMPLE_COST

    @property
    def links(self) -> int:
        """Links solved by Newton-Raphson."""
        return sum(self.groups)

    @property
    def squared_links(self) -> int:
        """The sum of each group's links squared."""
        return sum(n * n for n in self.groups)

    @property
    def per_link(self) -> float:
        """Samples per link: the sweep's, the path tracing's and the walk's."""
        return self.samples + self.setup_samples + self.samples_per_radian * self.turn

    @property
    def link_samples(self) -> float:
        return self.links * self.per_link

    @property
    def seconds(self) -> float:
        """Estimated seconds of one core."""
        rate = self.links * self.sample_cost + self.squared_links * self.group_sample_cost
        return self.per_link * rate

    @property
    def reckoning(self) -> str:
        """The products, with their numbers."""
        return (
            f"{self.links} links solved by Newton-Raphson x ({self.samples} samples + "
            f"{self.setup_samples} + {self.turn:,.6g} rad x {self.samples_per_radian}) x "
            f"({self.sample_cost * 1e6:g} us + {self.group_sample_cost * 1e6:g} us x "
            f"{self.squared_links / self.links:g} links per group)"
        )


@dataclass(frozen=True)
class ClosedFormWork:
    """The closed-form groups' work: ``groups`` x (``samples`` + ``setup_samples``) x
    ``sample_cost``, plus ``branch_groups`` (dyads and levers, where the continuation follows
    the path) x ``turn`` rad from the drawn pose x ``turn_cost``."""

    groups: int
    branch_groups: int
    samples: int
    turn: float
    setup_samples: int = CLOSED_FORM_SETUP_SAMPLES
    sample_cost: float = CLOSED_FORM_COST
    turn_cost: float = TURN_COST

    @property
    def seconds(self) -> float:
        """Estimated seconds of one core."""
        sampled = self.groups * (self.samples + self.setup_samples) * self.sample_cost
        return sampled + self.branch_groups * self.turn * self.turn_cost

    @property
    def reckoning(self) -> str:
        """The products, with their numbers."""
        text = (
            f"{self.groups} closed-form groups x ({self.samples} samples + "
            f"{self.setup_samples} for tracing the path) x {self.sample_cost * 1e6:g} us"
        )
        if self.branch_groups and self.turn:
            text += (
                f" + {self.branch_groups} dyads or levers x {self.turn:,.6g} rad the drivers "
                f"turn from the drawn pose x {self.turn_cost * 1e3:g} ms"
            )
        return text


@dataclass(frozen=True)
class Cost:
    """Estimated ``seconds`` of one core, and the ``reckoning`` that gives them (its numbers)."""

    seconds: float
    reckoning: str


@dataclass(frozen=True)
class Oscillations:
    """An event search's span: ``t_max`` x the ``frequency`` (Hz) of ``moving_point``'s law;
    ``resolved`` false where the grid no longer resolves the law (the frequency is then a lower
    bound)."""

    moving_point: str
    t_max: float
    frequency: float
    resolved: bool

    @property
    def count(self) -> float:
        return self.t_max * self.frequency


class WorkEstimate:
    """What a request costs (see the module): the response's ``values`` (``samples`` x
    ``entries`` x ``quantities``), the ``newton`` work (None where nothing is solved by
    Newton-Raphson) and an event search's ``oscillations`` (None but for an event)."""

    def __init__(
        self,
        scene: LinkageScene | SpatialChain | ChapterScene,
        samples: int,
        quantities: int,
        turn: float | None,
        event: tuple[str, float] | None = None,
        time_grid: np.ndarray | None = None,
        time_sweep: bool = False,
        walks: bool = True,
    ) -> None:
        self.scene = scene
        self._time_sweep = time_sweep
        self.samples = samples
        self.quantities = quantities
        self._turn = turn
        self._time_grid = time_grid
        self._event = event
        self._walks = walks
        if isinstance(scene, SpatialChain):
            self.entries = len(scene.points) + 2 * len(scene.joints)  # a body per joint
            self.entries_what = "bodies, joints and points"
        elif not isinstance(scene, LinkageScene):
            self.entries, self.entries_what = scene.response_entries
        else:
            self.entries = (
                len(scene.points) + len(scene.links) + len(scene.joints) + len(scene.moving_points)
            )
            self.entries_what = "points, links, joints and moving points"

    @property
    def values(self) -> int:
        """Values in the response: samples x entries x quantities."""
        return self.samples * self.entries * self.quantities

    @cached_property
    def newton(self) -> NewtonWork | None:
        scene = self.scene
        if not isinstance(scene, LinkageScene) or (self._turn is None and self._time_grid is None):
            return None
        # The turn first: a time law that cannot be evaluated is reported as such either way.
        turn = self._turn if self._time_grid is None else driver_turn(scene, self._time_grid)
        assert turn is not None
        groups = tuple(len(s.links) for s in build_plan(scene).steps if isinstance(s, NewtonStep))
        return NewtonWork(groups, self.samples, turn) if groups else None

    @cached_property
    def closed_form(self) -> ClosedFormWork | None:
        """The closed-form groups' work (None but for a linkage)."""
        scene = self.scene
        if not isinstance(scene, LinkageScene):
            return None
        plan = build_plan(scene)
        steps = [s for s in plan.steps if not isinstance(s, DriverStep | NewtonStep)]
        branches = sum(isinstance(s, DyadStep | LeverStep) for s in steps)
        turn = (
            self._turn
            if self._time_grid is None
            else driver_turn(scene, self._time_grid)
            if follows_path(plan) and self._walks
            else 0.0
        )
        return ClosedFormWork(len(steps), branches, self.samples, turn or 0.0)

    @property
    def seconds(self) -> float:
        """Estimated seconds of one core for the whole request (Newton-Raphson and closed
        form)."""
        if not isinstance(self.scene, LinkageScene):
            return self.values * VALUE_COST
        return sum(w.seconds for w in (self.newton, self.closed_form) if w is not None)

    @property
    def reckoning(self) -> str:
        """How ``seconds`` is reckoned, with the numbers."""
        parts = []
        if not isinstance(self.scene, LinkageScene):
            parts.append(f"{self.values:,} values x {VALUE_COST * 1e6:g} us")
        if self.newton is not None:
            parts.append(self.newton.reckoning)
        if self.closed_form is not None:
            parts.append(self.closed_form.reckoning)
        return " + ".join(parts) + f" = {self.seconds:,.4g} s"

    def dense_samples(self) -> int | None:
        """A time sweep's samples on the dense grid its continuation follows (``dense_parts``:
        the drivers' steps cut to MAX_DRIVER_STEP); None where it follows the given samples.
        Raises ``LimitExceeded`` past MAX_DENSE_SAMPLES, before any work."""
        scene = self.scene
        if not self._time_sweep or not isinstance(scene, LinkageScene):
            return None
        assert self._time_grid is not None
        if not follows_path(build_plan(scene)):
            return None
        parts = dense_parts(driver_inputs_over_time(scene, self._time_grid))
        return None if parts is None else int(parts.sum()) + 1

    @cached_property
    def oscillations(self) -> Oscillations | None:
        if self._event is None or not isinstance(self.scene, LinkageScene):
            return None
        name, t_max = self._event
        mp = next(m for m in self.scene.moving_points if m.name == name)
        grid = np.linspace(0.0, t_max, FREQUENCY_GRID + 1)
        rate = parse_time_law(mp.s_law).evaluate(grid)[1]
        turns = int(np.count_nonzero(np.diff(np.sign(rate)) != 0))
        # s' changes sign twice a period; past a quarter of the grid the grid no longer resolves it.
        return Oscillations(name, t_max, turns / (2.0 * t_max), turns < FREQUENCY_GRID // 4)


def exercise_work(kind: str, count: int, with_solutions: bool, export: bool = False) -> Cost:
    """``count`` x (the type's measured cost + ``EXPORT_COST`` for an export): ``count``
    exercises of type ``kind`` (``EXERCISE_COSTS``; the costliest for a type not listed), or an
    export of them (its sheet written on top)."""
    costliest = max(EXERCISE_COSTS.values(), key=lambda c: c[1])
    alone, solved = EXERCISE_COSTS.get(kind, costliest)
    each = (solved if with_solutions else alone) + (EXPORT_COST if export else 0.0)
    what = "with its worked solution" if with_solutions else "each"
    if export:
        what += " and its sheet"
    seconds = count * each
    return Cost(
        seconds, f"{count} exercises x {each * 1e3:g} ms {what} ({kind}) = {seconds:,.4g} s"
    )


def driver_turn(scene: LinkageScene, times: np.ndarray) -> float:
    """Radians the drivers turn from the drawn pose to reach every one of ``times`` (both ways)."""
    turns = np.concatenate([d.theta for d in driver_inputs_over_time(scene, times)] + [[0.0]])
    return float(np.max(turns) - np.min(turns))


def estimate_work(
    scene: LinkageScene | SpatialChain | ChapterScene,
    samples: int | None = None,
    quantities: Iterable[str] | None = None,
    *,
    time_range: Sequence[float] | None = None,
    event: tuple[str, float] | None = None,
    reaches: str | None = None,
) -> WorkEstimate:
    """The cost of a request on ``scene``, before any work: one instant (``samples`` None,
    reached from the drawn pose: /analyze, /solution), a revolution of ``samples`` (/sweep), the
    same over ``time_range`` (the drivers' turn over it counted), or an event search
    ``event`` = (moving point, t_max) (/events: its time laws are parsed first, and a moving
    point the scene does not have or a t_max outside 0 < t_max <= MAX_TIME is left to the
    search's own message: no work estimated; the linkage is walked over the drivers' turn up to
    t_max unless the target ``reaches`` is a point of the moving point's carrier, which is
    searched along its path). ``quantities`` as for a sweep (default
    position). A scene of another chapter (a cam, a gear train) counts its values per sample,
    whatever the quantities."""
    wanted = len(normalise_quantities(["position"] if quantities is None else quantities))
    if isinstance(scene, SpatialChain):
        return WorkEstimate(scene, samples or 1, wanted, None)
    if not isinstance(scene, LinkageScene):
        return WorkEstimate(scene, samples or 1, 1, None)
    if event is not None:
        for law in [d.angle_law for d in scene.drivers] + [m.s_law for m in scene.moving_points]:
            if law is not None:
                parse_time_law(law)  # a bad law is reported as such, before any estimate
        name, t_max = event
        if not any(m.name == name for m in scene.moving_points) or not 0.0 < t_max <= MAX_TIME:
            return WorkEstimate(scene, EVENT_SAMPLES, wanted, None)
        grid = np.linspace(0.0, t_max, FREQUENCY_GRID + 1)
        carrier = next(m.link for m in scene.moving_points if m.name == name)
        walks = reaches is None or reaches not in scene.links[carrier].points
        return WorkEstimate(scene, EVENT_SAMPLES, wanted, None, event, grid, walks=walks)
    if samples is None:
        return WorkEstimate(scene, 1, wanted, None, time_grid=np.array([scene.time]))
    check_samples(samples)  # a sweep's bounds first: the estimate below needs them
    if time_range is None:
        return WorkEstimate(scene, samples, wanted, 0.0)
    valid = len(time_range) == 2 and all(math.isfinite(t) for t in time_range)
    grid = (
        np.linspace(time_range[0], time_range[-1], min(samples, FREQUENCY_GRID))
        if valid
        else np.zeros(1)
    )
    return WorkEstimate(scene, samples, wanted, None, time_grid=grid, time_sweep=valid)
