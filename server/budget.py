"""The cost of a request, checked after parsing and before any work: ``limit_exceeded`` (413).

Scene sizes are bounded by the parsers (200 points, 100 links, ...) and a time law by
``solver.model.laws`` (500 characters, ``MAX_COMPOSITION`` levels), but their products are not. The
solver estimates them (``solver.estimate_work``: the response's size, the Newton-Raphson work,
an event search's oscillations; its cost model in ``solver.analysis.work_estimate``) and the server
compares the estimate with its limits:

- response size: at most ``MAX_SWEEP_VALUES`` values (about 20 MB of JSON; 200 points x 100,000
  samples x every quantity made 2.5 GB);
- Newton-Raphson work: at most the endpoint's default time limit (``TIME_LIMITS``) divided by
  ``SAFETY``, and no Newton-Raphson group larger than ``MAX_GROUP_LINKS`` links (the largest
  group the cost model was measured on; past it the cost grows far faster than the model: 64
  links took 50 s for 20 samples);
- an event search: at most ``MAX_OSCILLATIONS`` oscillations of the moving point's law;
- the whole request's estimated seconds (``WorkEstimate.seconds``: the Newton-Raphson and the
  closed-form work with the drivers' turn; ``exercise_work`` for exercises and exports;
  ``SOLUTION_COST`` and ``BALANCE_COST`` on top of an instant): at most the endpoint's time
  limit (its default, or the configured one where higher: ``time_limit``) divided by
  ``SAFETY``.

Every refusal states the product and the limit. Each check returns the request's estimated
seconds: the pool (``server.workers``) runs a request estimated past ``LANE_SECONDS`` in the
slow lane. The checks run in the server's own process before the request waits for a worker
(``server.workers.front_check``), so a refused request never queues.
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence
from contextvars import ContextVar
from typing import Any

import solver
from server.settings import TIME_LIMITS, Settings
from solver.analysis.work_estimate import WorkEstimate
from solver.cams import CamScene
from solver.errors import LimitExceeded
from solver.gears import GearTrainScene
from solver.kinematics.spatial import SpatialChain
from solver.model.scene import LinkageScene

MAX_SWEEP_VALUES = 500_000
MAX_OSCILLATIONS = 5_000
MAX_GROUP_LINKS = 32  # the largest group the cost model was measured on
SAFETY = 2.0  # refused past the time limit / SAFETY: an estimate off by 2x still ends in time
DEFAULT_LIMIT = 10.0  # s: the default time limit of an endpoint not in TIME_LIMITS
# The serving settings of the request being checked (set by server.workers): a time limit
# raised above its default raises the budget with it; one lowered below it does not lower it
# (the time limit then stops the work).
SETTINGS: ContextVar[Settings | None] = ContextVar("SETTINGS", default=None)


def time_limit(path: str) -> float:
    """``path``'s time limit for the budget: its default, or the configured one if higher."""
    default = TIME_LIMITS.get(path, DEFAULT_LIMIT)
    settings = SETTINGS.get()
    return default if settings is None else max(default, settings.time_limit_of(path))


def _response_size(estimate: WorkEstimate) -> None:
    """samples x entries x quantities values in a sweep's response, at most MAX_SWEEP_VALUES."""
    if estimate.values > MAX_SWEEP_VALUES:
        raise LimitExceeded(
            f"response size: {estimate.samples} samples x {estimate.entries} "
            f"{estimate.entries_what} x {estimate.quantities} quantities = "
            f"{estimate.values:,}, more than the limit of {MAX_SWEEP_VALUES:,}; ask for fewer "
            "samples or quantities"
        )


def _newton(estimate: WorkEstimate, what: str, path: str) -> None:
    """Refuse Newton-Raphson work estimated past ``path``'s default time limit / SAFETY."""
    work = estimate.newton
    if work is None:
        return
    if max(work.groups) > MAX_GROUP_LINKS:
        raise LimitExceeded(
            f"Newton-Raphson work: a group of {max(work.groups)} links solved together by "
            f"Newton-Raphson, more than the limit of {MAX_GROUP_LINKS} links"
        )
    seconds, allowed = work.seconds, time_limit(path) / SAFETY
    if seconds > allowed:
        per_group = work.squared_links / work.links
        raise LimitExceeded(
            f"Newton-Raphson work: {work.links} links solved by Newton-Raphson x ({work.samples} "
            f"samples {what} + {work.setup_samples} for tracing the path + {work.turn:.4g} rad "
            f"from the drawn pose x {work.samples_per_radian}) = {work.link_samples:,.0f} "
            f"link-samples x ({work.sample_cost * 1e6:g} us + {work.group_sample_cost * 1e6:g} "
            f"us x {per_group:g} links per group) = {seconds:.4g} s of estimated work, "
            f"more than the limit of {allowed:.4g} s ({path}'s time limit of "
            f"{time_limit(path):g} s / safety factor {SAFETY:g}); use fewer samples or a pose "
            "nearer the drawn one"
        )


def limit(path: str) -> float:
    """The seconds of estimated work allowed at ``path``: its time limit / SAFETY."""
    return time_limit(path) / SAFETY


def seconds(estimated: float, reckoning: str, path: str) -> float:
    """``estimated`` seconds, refused past ``limit(path)`` with the ``reckoning``."""
    if estimated > limit(path):
        raise LimitExceeded(
            f"estimated work: {reckoning}, more than the limit of {limit(path):.4g} s ({path}'s "
            f"time limit of {time_limit(path):g} s / safety factor "
            f"{SAFETY:g}); ask for less"
        )
    return estimated


def instant(scene: LinkageScene, path: str = "/api/v1/analyze", extra: float = 0.0) -> float:
    """/analyze and /solution of a linkage: one sample, reached from the drawn pose (``extra``
    seconds on top: a worked solution's writing)."""
    estimate = solver.estimate_work(scene)
    _newton(estimate, "(one instant)", "/api/v1/analyze")
    return _total(estimate, path, extra)


def _total(estimate: WorkEstimate, path: str, extra: float = 0.0) -> float:
    reckoning = estimate.reckoning
    if extra:
        reckoning = f"{reckoning} + {extra:g} s for writing the worked solution"
    return seconds(estimate.seconds + extra, reckoning, path)


def sweep(
    scene: LinkageScene,
    samples: int,
    quantities: Iterable[str] | None,
    time_range: Sequence[float] | None = None,
) -> float:
    """/sweep: the response's size, the Newton work with the feasible-range search, and a time
    sweep's dense grid (the drivers' turn in steps of at most pi/8), then the whole work."""
    estimate = solver.estimate_work(scene, samples, quantities, time_range=time_range)
    _response_size(estimate)
    what = "over the revolution" if time_range is None else "over the time range"
    _newton(estimate, what, "/api/v1/sweep")
    estimate.dense_samples()  # refuses a dense grid past the solver's MAX_DENSE_SAMPLES
    return _total(estimate, "/api/v1/sweep")


def spatial_sweep(
    chain: SpatialChain | GearTrainScene, samples: int, quantities: Iterable[str] | None
) -> float:
    """/sweep of a spatial chain (bodies, points and joints) or a gear train (members' angles,
    planets' centres) over time: the response's size."""
    estimate = solver.estimate_work(chain, samples, quantities)
    _response_size(estimate)
    return _total(estimate, "/api/v1/sweep")


def cam_sweep(scene: CamScene, samples: int) -> float:
    """/sweep of a cam: the response's size (its values per sample)."""
    estimate = solver.estimate_work(scene, samples)
    _response_size(estimate)
    return _total(estimate, "/api/v1/sweep")


def event(
    scene: LinkageScene, moving_point: str, t_max: float, reaches: str | None = None
) -> float:
    """/events: t_max x the law's frequency, the Newton work of the distance search, then the
    whole work (the distance search over the drivers' turn up to t_max)."""
    estimate = solver.estimate_work(scene, event=(moving_point, t_max), reaches=reaches)
    _newton(estimate, "of the distance search", "/api/v1/events")
    found = estimate.oscillations
    if found is not None and (not found.resolved or found.count > MAX_OSCILLATIONS):
        at_least = "" if found.resolved else "at least "
        raise LimitExceeded(
            f"event search: t_max x the frequency of {found.moving_point}'s law = "
            f"{found.t_max:g} s x {at_least}{found.frequency:.6g} Hz = "
            f"{at_least}{found.count:,.0f} oscillations, more than the limit of "
            f"{MAX_OSCILLATIONS:,}; lower t_max"
        )
    return _total(estimate, "/api/v1/events")


def exercises(kind: str, count: int, with_solutions: bool, path: str) -> float:
    """/exercises and /exercises/export: count x the type's cost (and an export's sheet)."""
    cost = solver.exercise_work(kind, count, with_solutions, path.endswith("/export"))
    return seconds(cost.seconds, cost.reckoning, path)


def read_instant(doc: dict[str, Any], strict: bool, path: str, extra: float = 0.0) -> float:
    """A one-instant request's scene (/analyze, /solution), refused before any work if it
    costs too much (``extra`` seconds on top of the instant); its estimated seconds."""
    read = solver.read_scene(doc, strict=strict)
    if isinstance(read.scene, LinkageScene):
        return instant(read.scene, path, extra)
    return extra
