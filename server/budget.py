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
- an event search: at most ``MAX_OSCILLATIONS`` oscillations of the moving point's law.

Every refusal states the product and the limit.
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence
from typing import Any

import solver
from server.settings import TIME_LIMITS
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
    seconds, allowed = work.seconds, TIME_LIMITS[path] / SAFETY
    if seconds > allowed:
        raise LimitExceeded(
            f"Newton-Raphson work: {work.links} links solved by Newton-Raphson x ({work.samples} "
            f"samples {what} + {work.setup_samples} for tracing the path + {work.turn:.4g} rad "
            f"from the drawn pose x {work.samples_per_radian}) = {work.link_samples:,.0f} "
            f"link-samples x {work.sample_cost * 1e6:g} us = {seconds:.4g} s of estimated work, "
            f"more than the limit of {allowed:.4g} s ({path}'s time limit of "
            f"{TIME_LIMITS[path]:g} s / safety factor {SAFETY:g}); use fewer samples or a pose "
            "nearer the drawn one"
        )


def instant(scene: LinkageScene) -> None:
    """/analyze and /solution of a linkage: one sample, reached from the drawn pose."""
    _newton(solver.estimate_work(scene), "(one instant)", "/api/v1/analyze")


def sweep(
    scene: LinkageScene,
    samples: int,
    quantities: Iterable[str] | None,
    time_range: Sequence[float] | None = None,
) -> None:
    """/sweep: the response's size, the Newton work with the feasible-range search, and a time
    sweep's dense grid (the drivers' turn in steps of at most pi/8)."""
    estimate = solver.estimate_work(scene, samples, quantities, time_range=time_range)
    _response_size(estimate)
    what = "over the revolution" if time_range is None else "over the time range"
    _newton(estimate, what, "/api/v1/sweep")
    estimate.dense_samples()  # refuses a dense grid past the solver's MAX_DENSE_SAMPLES


def spatial_sweep(
    chain: SpatialChain | GearTrainScene, samples: int, quantities: Iterable[str] | None
) -> None:
    """/sweep of a spatial chain (bodies, points and joints) or a gear train (members' angles,
    planets' centres) over time: the response's size."""
    _response_size(solver.estimate_work(chain, samples, quantities))


def cam_sweep(scene: CamScene, samples: int) -> None:
    """/sweep of a cam: the response's size (its values per sample)."""
    _response_size(solver.estimate_work(scene, samples))


def event(scene: LinkageScene, moving_point: str, t_max: float) -> None:
    """/events: t_max x the law's frequency (and the Newton work of the distance search)."""
    estimate = solver.estimate_work(scene, event=(moving_point, t_max))
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


def read_instant(doc: dict[str, Any], strict: bool) -> solver.ReadScene:
    """A one-instant request's scene (/analyze, /solution), refused before any work if it
    costs too much; its warnings kept for the result."""
    read = solver.read_scene(doc, strict=strict)
    if isinstance(read.scene, LinkageScene):
        instant(read.scene)
    return read
