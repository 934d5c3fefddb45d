"""What the endpoints answer for a cam: a revolution (/sweep), one cam angle (/analyze), the
extremes and the warnings a designer must act on.

Rates are per time at the scene's omega: v = (ds/dtheta) |omega|, a = (d2s/dtheta2) omega^2,
j = (d3s/dtheta3) |omega|^3 (m or rad). The warnings and the extremes are read on a fixed grid
of ``GRID`` cam angles (0.05 deg), so they do not depend on the samples asked for:

- a velocity or acceleration that jumps where two segments meet (infinite acceleration or
  jerk: the fundamental law of cam design asks for continuous acceleration);
- a pressure angle above ``PRESSURE_ANGLE_LIMIT_DEG`` (30 deg translating, 35 deg oscillating);
- undercutting: a roller's pitch curve curving tighter than the roller (0 < rho_pitch < r),
  or a flat face's cam surface with a negative radius of curvature (a cusp);

each with the smallest base radius that cures it, found by bisection on that grid.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Callable
from typing import Any

import numpy as np

from solver.analysis.sweeps import MAX_SAMPLES
from solver.cams.geometry import CamGeometry, cam_geometry
from solver.cams.laws import LAWS
from solver.cams.model import CamScene
from solver.errors import InvalidScene, LimitExceeded

JSON = dict[str, Any]
GRID = 7200  # cam angles (0.05 deg apart) for the extremes and the warnings
PROFILE_SAMPLES = 360  # the profile that /analyze carries
PRESSURE_ANGLE_LIMIT_DEG = {"translating": 30.0, "oscillating": 35.0}
JUMP_TOLERANCE = 1e-9  # relative to the largest magnitude over the revolution
CURE_STEPS = 60  # bisection steps for the base radius that cures a warning
CURE_GROWTH = 4096.0  # the largest base radius tried, as a multiple of the scene's


def _grid(samples: int) -> np.ndarray:
    return 2.0 * math.pi * np.arange(samples) / samples


def _rates(scene: CamScene, g: CamGeometry) -> tuple[np.ndarray, ...]:
    """s, v, a, j per time: s, s' |omega|, s'' omega^2, s''' |omega|^3."""
    w = abs(scene.omega)
    return g.lift.s, g.lift.ds * w, g.lift.d2s * w**2, g.lift.d3s * w**3


def _finite(values: np.ndarray) -> np.ndarray | list[float | None]:
    """An array as it is, or as a list with null where a radius of curvature is infinite (an
    inflection met exactly)."""
    if np.isfinite(values).all():
        return values
    return [float(v) if math.isfinite(v) else None for v in values]


def _fields(scene: CamScene, g: CamGeometry, at: Callable[[np.ndarray], Any]) -> JSON:
    s, v, a, j = _rates(scene, g)
    body: JSON = {
        "follower": {
            "displacement": at(s),
            "velocity": at(v),
            "acceleration": at(a),
            "jerk": at(j),
        },
        "pressure_angle": at(g.pressure_angle),
        "radius_of_curvature": at(g.radius),
    }
    if g.pitch_radius is not None:
        body["pitch_radius_of_curvature"] = at(g.pitch_radius)
    return body


def sweep_cam(scene: CamScene, samples: int = 360, warnings: list[str] | None = None) -> JSON:
    """One revolution at ``samples`` cam angles 2 pi k / samples (POST /sweep)."""
    if not 3 <= samples <= MAX_SAMPLES:
        raise LimitExceeded(f"samples: {samples} is outside 3..{MAX_SAMPLES}")
    g = cam_geometry(scene, _grid(samples))
    body: JSON = {"samples": samples, "cam_angle": g.theta}
    body.update(_fields(scene, g, _finite))
    body["profile"] = g.profile
    body["contact_point"] = g.contact
    body.update(_over_the_revolution(scene, g if samples == GRID else _revolution(scene), warnings))
    return body


def analyze_cam(scene: CamScene, angle_deg: float = 0.0, warnings: list[str] | None = None) -> JSON:
    """The mechanism at cam angle ``angle_deg`` (turned in the cam's direction of rotation,
    taken modulo 360), with the cam's profile at ``PROFILE_SAMPLES`` points (POST /analyze)."""
    if isinstance(angle_deg, bool) or not math.isfinite(angle_deg):
        raise InvalidScene(f"angle_deg: expected a finite number, got {angle_deg!r}")
    theta = math.radians(angle_deg % 360.0)
    g = cam_geometry(scene, np.array([theta]))

    def one(values: np.ndarray) -> float | None:
        value = float(values[0])
        return value if math.isfinite(value) else None

    index = int(g.lift.segment[0])
    body: JSON = {"cam_angle": theta, "cam_angle_deg": math.degrees(theta), "segment": index}
    body.update(_fields(scene, g, one))
    body["contact_point"] = [float(x) for x in g.contact[0]]
    body["profile"] = cam_geometry(scene, _grid(PROFILE_SAMPLES)).profile
    body.update(_over_the_revolution(scene, _revolution(scene), warnings))
    return body


def _revolution(scene: CamScene) -> CamGeometry:
    """The cam's geometry on the grid of ``GRID`` cam angles, from which the extremes and the
    warnings are read."""
    return cam_geometry(scene, _grid(GRID))


def _over_the_revolution(scene: CamScene, g: CamGeometry, warnings: list[str] | None) -> JSON:
    """``diagnostics`` and ``warnings`` (the given ones, then the design's faults) from the
    geometry ``g`` on the grid of ``GRID`` cam angles (``_revolution``)."""
    return {
        "diagnostics": diagnostics(scene, g),
        "warnings": [*(warnings or []), *cam_warnings(scene, g)],
    }


def diagnostics(scene: CamScene, g: CamGeometry) -> JSON:
    """The extremes over the revolution (``g``: the geometry on the grid of ``GRID`` cam
    angles) and where they occur, and the circles."""
    named = _fields(scene, g, lambda values: values)
    named = {**named.pop("follower"), **named}
    extremes: JSON = {}
    for name, values in named.items():
        finite = np.where(np.isfinite(values), values, np.nan)
        low, high = int(np.nanargmin(finite)), int(np.nanargmax(finite))
        extremes[name] = {
            "min": float(finite[low]),
            "min_at_deg": math.degrees(g.theta[low]),
            "max": float(finite[high]),
            "max_at_deg": math.degrees(g.theta[high]),
        }
    return {
        "extremes": extremes,
        "base_radius": scene.base_radius,
        "prime_radius": scene.prime_radius,
        "lift_unit": "rad" if scene.follower.motion == "oscillating" else "m",
        "grid_samples": GRID,
    }


def _boundary_jumps(scene: CamScene, g: CamGeometry) -> list[str]:
    """Where two segments meet, a jump in ds/dtheta (infinite acceleration) or in d2s/dtheta2
    (infinite jerk), from each law's exact end values; a jump counts past ``JUMP_TOLERANCE``
    of the largest |v| or |a| over the revolution (``g``), rounding does not."""
    unit = "rad" if scene.follower.motion == "oscillating" else "m"
    ends: list[tuple[tuple[float, float], ...]] = []  # (ds, d2s) at each segment's start, end
    for seg in scene.segments:
        if seg.law is None:
            ends.append(((0.0, 0.0), (0.0, 0.0)))
            continue
        y = LAWS[seg.law](np.array([0.0, 1.0]))
        h = seg.lift if seg.type == "rise" else -seg.lift
        beta = seg.duration
        ends.append(
            tuple((float(h * y.dy[k] / beta), float(h * y.d2y[k] / beta**2)) for k in (0, 1))
        )
    w = abs(scene.omega)
    scale_v = float(np.abs(g.lift.ds).max()) * w
    scale_a = float(np.abs(g.lift.d2s).max()) * w**2
    found = []
    n = len(scene.segments)
    for i, seg in enumerate(scene.segments):
        after = scene.segments[(i + 1) % n]
        where = f"cam angle {math.degrees(seg.start + seg.duration) % 360.0:g} deg"
        pair = f"between {seg.describe(i)} and {after.describe((i + 1) % n)}"
        (v0, a0), (v1, a1) = ends[i][1], ends[(i + 1) % n][0]
        if abs(v1 - v0) * w > JUMP_TOLERANCE * scale_v:
            found.append(
                f"discontinuous velocity at {where} {pair}: v jumps from {v0 * w:.6g} to "
                f"{v1 * w:.6g} {unit}/s, an infinite acceleration (and jerk); use a law that "
                "starts and ends at rest, e.g. cycloidal or polynomial_345"
            )
        elif abs(a1 - a0) * w**2 > JUMP_TOLERANCE * scale_a:
            found.append(
                f"discontinuous acceleration at {where} {pair}: a jumps from {a0 * w**2:.6g} "
                f"to {a1 * w**2:.6g} {unit}/s^2, an infinite jerk (the fundamental law of cam "
                "design asks for continuous acceleration); use e.g. cycloidal, "
                "polynomial_345 or modified_sine"
            )
    return found


def smallest_base_radius(scene: CamScene, cured: Callable[[CamGeometry], bool]) -> float | None:
    """The smallest base radius (to 4 significant digits, rounded up) whose cam passes ``cured``
    on the grid, by bisection from the scene's own; None if none up to ``CURE_GROWTH`` times
    it does (or the follower no longer reaches the cam)."""

    def passes(radius: float) -> bool | None:
        trial = dataclasses.replace(scene, base_radius=radius)
        try:
            g = _revolution(trial)
        except ValueError:  # the oscillating arm no longer reaches the prime circle
            return None
        with np.errstate(invalid="ignore"):
            return cured(g)

    low, high = scene.base_radius, scene.base_radius
    while True:
        high *= 2.0
        verdict = passes(high)
        if verdict is None or high > CURE_GROWTH * scene.base_radius:
            return None
        if verdict:
            break
        low = high
    for _ in range(CURE_STEPS):
        middle = 0.5 * (low + high)
        if passes(middle):
            high = middle
        else:
            low = middle
    digits = 3 - math.floor(math.log10(high))
    return math.ceil(high * 10**digits) / 10**digits


def _cure(radius: float | None, what: str) -> str:
    if radius is None:
        return f"no larger base radius {what}; change the laws or lengthen the segments"
    return f"a base radius of at least {radius:g} m {what}"


def tighter_than_roller(g: CamGeometry, roller_radius: float) -> np.ndarray:
    """Where a roller cannot follow: 0 < rho_pitch < r (the pitch curve convex and tighter than
    the roller; a concave pitch curve never undercuts)."""
    rho = g.pitch_radius if g.pitch_radius is not None else g.radius
    tight: np.ndarray = (rho > 0) & (rho < roller_radius)
    return tight


def cam_warnings(scene: CamScene, g: CamGeometry | None = None) -> list[str]:
    """The design's faults over the revolution (on the grid of ``GRID`` cam angles: ``g``, the
    geometry there, computed when not given): jumps where segments meet, too large a pressure
    angle, undercutting (see the module)."""
    if g is None:
        g = _revolution(scene)
    found = _boundary_jumps(scene, g)
    f = scene.follower
    if f.contact != "flat":
        limit = math.radians(PRESSURE_ANGLE_LIMIT_DEG[f.motion])
        worst = int(np.argmax(np.abs(g.pressure_angle)))
        if abs(g.pressure_angle[worst]) > limit:
            radius = smallest_base_radius(
                scene, lambda t: bool(np.abs(t.pressure_angle).max() <= limit)
            )
            found.append(
                f"pressure angle {math.degrees(g.pressure_angle[worst]):.4g} deg at cam angle "
                f"{math.degrees(g.theta[worst]):.4g} deg, above {math.degrees(limit):g} deg for "
                f"a {f.motion} follower; "
                + _cure(radius, f"brings it within {math.degrees(limit):g} deg")
            )
    if f.contact == "roller" and tighter_than_roller(g, f.roller_radius).any():
        r = f.roller_radius
        rho = g.pitch_radius if g.pitch_radius is not None else g.radius
        worst = int(np.argmin(np.where(tighter_than_roller(g, r), rho, np.inf)))
        radius = smallest_base_radius(scene, lambda t: not tighter_than_roller(t, r).any())
        found.append(
            f"undercutting: the pitch curve's radius of curvature is {rho[worst]:.4g} m at cam "
            f"angle {math.degrees(g.theta[worst]):.4g} deg, less than the roller radius {r:g} m "
            "(the cam surface would cross itself); " + _cure(radius, "cures it")
        )
    if f.contact == "flat" and (g.radius < 0).any():
        worst = int(np.argmin(g.radius))
        radius = smallest_base_radius(scene, lambda t: bool((t.radius >= 0).all()))
        found.append(
            f"undercutting: the cam surface's radius of curvature is {g.radius[worst]:.4g} m at "
            f"cam angle {math.degrees(g.theta[worst]):.4g} deg under a flat face (a cusp: the "
            f"face cannot follow the lift); " + _cure(radius, "cures it")
        )
    return found
