"""Newton-Raphson q <- q - J^-1 Phi(q) for groups with no closed form, every sample at once.

The equations Phi(q) = 0 and their Jacobian J are ``solver.position.constraints``; Newton-Raphson
polishes every sample of a sweep together with ``numpy.linalg.solve`` on the stacked Jacobians.
Which root each sample converges to is decided by the starting values, which come from following the
branch by continuation (``solver.position.continuation``).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from typing import TypeVar

import numpy as np

from solver.errors import InvalidScene
from solver.kinematics.rigid import Array
from solver.position.constraints import (
    ConstraintSystem,
    LinearForm,
    Rotations,
    States,
    solve_linear,
)

Jacobian = TypeVar("Jacobian")
NEWTON_TOLERANCE = 1e-13  # residual, relative to the scene size (the default)
TOLERANCE_BOUNDS = (1e-15, 1e-6)  # a user's choice of the Newton tolerance must lie in here
NEWTON_MAX_ITERATIONS = 50
# A sample whose residual is at most this (times the size) takes no polishing step: a step from
# there moves it by rounding only. (At 4 eps, taken sample by sample, the full-turning triad kept
# residuals of 2.4e-15 m and errors of 2e-15 m against 50 digits; at eps, 6e-16 m and 6e-16 m.)
ROUNDING = float(np.finfo(float).eps)


@dataclass(frozen=True)
class NewtonReport:
    """How Newton-Raphson went: the worst sample's iterations and residual; which converged."""

    links: tuple[str, ...]
    converged: Array
    iterations: int
    residual_norm: float
    tolerance: float
    message: str
    relative_tolerance: float = NEWTON_TOLERANCE


def newton_tolerance(value: float | None) -> float:
    """A user's Newton tolerance (relative to the scene size), checked against TOLERANCE_BOUNDS;
    None: the default NEWTON_TOLERANCE."""
    if value is None:
        return NEWTON_TOLERANCE
    low, high = TOLERANCE_BOUNDS
    if not (math.isfinite(value) and low <= value <= high):
        raise InvalidScene(
            f"tolerance: {value:g} is outside {low:g} .. {high:g} (the Newton-Raphson residual "
            f"relative to the scene size; default {NEWTON_TOLERANCE:g})"
        )
    return float(value)


def residual_tolerance(relative: float, system: ConstraintSystem) -> float:
    """The residual |Phi| (m) Newton-Raphson closes ``system`` to: ``relative`` x the scene size,
    but no less than sqrt(rows) eps X, X the drawing's largest coordinate. Each row of Phi is a
    difference of positions that far from the origin, each rounded to eps of it, so no pose
    closes the loop more closely (a 3 m triad drawn 1e4 m from the origin closes to 2e-12 m,
    not to 1e-13 of its size)."""
    scene = system.scene
    largest = max(abs(x) for point in scene.points.values() for x in point)
    return max(relative * scene.size, math.sqrt(system.rows) * ROUNDING * largest)


def newton_raphson(
    system: ConstraintSystem,
    known: Mapping[str, States],
    q: Array,
    tolerance: float,
    turns: Array | None = None,
    polish: bool = True,
    max_iterations: int = NEWTON_MAX_ITERATIONS,
) -> tuple[Array, Array, int, Array]:
    """Newton-Raphson q <- q - J^-1 Phi(q) on every sample at once, from the (M, n) ``q``.

    Samples below ``tolerance`` stop; the others go on until all have stopped or after
    ``max_iterations``. With ``polish`` one more step then takes a converged iterate to rounding
    (quadratic convergence), kept only where it lowers the residual (taken only where a sample
    is not already at ``ROUNDING``). Returns (q, residual norms
    (M,), iterations, the length of each sample's first step (rotations times the size)).
    """
    weights = np.tile([1.0, 1.0, system.scene.size], len(system.unknown))
    whole = system.residual(known, q.shape[0], turns)
    size = system.scene.size

    def equations(x: Array, index: Array) -> tuple[Array, Array]:
        full = np.array(q)  # the general evaluation takes every sample: the others as they were
        full[index] = x
        phi, J = whole(full)
        return phi[index], J[index]

    return iterate(
        equations, system.solve, q, weights, (tolerance, ROUNDING * size), polish, max_iterations
    )


def newton_rotations(
    form: LinearForm,
    rotations: Rotations,
    known: Array,
    q: Array,
    size: float,
    tolerance: float,
    polish: bool = True,
    max_iterations: int = NEWTON_MAX_ITERATIONS,
) -> tuple[Array, Array, int, Array]:
    """q <- q - J^-1 Phi(q) as ``newton_raphson``, on a group whose equations are linear in
    (q, cos, sin), J never formed: Phi = K_q q + K_c cos + K_s sin + k by matrix products
    (``known`` = k) and the step J^-1 Phi by ``Rotations.rates`` (an (M, U, U) solve in the
    rotations, then the translations; least squares in the rotations where a sample is
    singular)."""

    def equations(x: Array, index: Array) -> tuple[Array, tuple[Array, Array]]:
        theta = x[:, 2::3]
        cos, sin = np.cos(theta), np.sin(theta)
        phi = form.residual(x, known[index], cos, sin)
        return phi, (theta, rotations.jacobian(theta, cos, sin))

    def solve(J: tuple[Array, Array], phi: Array) -> Array:
        try:
            return rotations.rates(*J, phi)
        except np.linalg.LinAlgError:
            return rotations.rates(*J, phi, solve_linear)

    weights = np.tile([1.0, 1.0, size], q.shape[1] // 3)
    return iterate(
        equations, solve, q, weights, (tolerance, ROUNDING * size), polish, max_iterations
    )


def iterate(
    equations: Callable[[Array, Array], tuple[Array, Jacobian]],
    solve: Callable[[Jacobian, Array], Array],
    q: Array,
    weights: Array,
    tolerances: tuple[float, float],
    polish: bool,
    max_iterations: int,
) -> tuple[Array, Array, int, Array]:
    """q <- q - J^-1 Phi(q) with (Phi, J) = ``equations(q[index], index)`` for the samples
    ``index`` still iterating and J^-1 b = ``solve(J, b)``, as ``newton_raphson`` describes (a
    sample that has stopped is neither evaluated nor solved again); ``weights`` per coordinate
    for the first step's length; ``tolerances``: the residual that stops a sample, and the one
    below which it is not polished."""
    tolerance, rounding = tolerances
    q = np.array(q, dtype=float)
    residual = np.zeros(q.shape[0])
    first = np.zeros(q.shape[0])
    active = np.arange(q.shape[0])
    iterations = 0
    while active.size:
        phi, J = equations(q[active], active)
        residual[active] = norm = np.sqrt(np.einsum("mi,mi->m", phi, phi))
        going = (norm > tolerance) & np.isfinite(norm)
        if iterations >= max_iterations or not np.any(going):
            break
        if not np.all(going):
            phi, J = phi[going], _take(J, going)
            active = active[going]
        step = solve(J, phi)
        if iterations == 0:
            first[active] = np.sqrt(np.einsum("mi,mi->m", step * weights, step * weights))
        q[active] -= step
        iterations += 1
    unpolished = np.flatnonzero((residual <= tolerance) & (residual > rounding))
    if polish and unpolished.size:
        phi, J = equations(q[unpolished], unpolished)
        trial = q[unpolished] - solve(J, phi)
        phi_next = equations(trial, unpolished)[0]
        better = np.sqrt(np.einsum("mi,mi->m", phi_next, phi_next))
        take = better < residual[unpolished]
        q[unpolished[take]], residual[unpolished[take]] = trial[take], better[take]
    return q, residual, iterations, first


def _take(J: Jacobian, rows: Array) -> Jacobian:
    """The samples ``rows`` of a stacked Jacobian (an array, or a tuple of arrays)."""
    if isinstance(J, tuple):
        return tuple(part[rows] for part in J)  # type: ignore[return-value]
    return J[rows]  # type: ignore[index]
