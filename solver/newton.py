"""Newton-Raphson q <- q - J^-1 Phi(q) for groups with no closed form, every sample at once.

The equations Phi(q) = 0 and their Jacobian J are ``solver.constraints``; Newton-Raphson polishes
every sample of a sweep together with ``numpy.linalg.solve`` on the stacked Jacobians. Which root
each sample converges to is decided by the starting values, which come from following the branch
by continuation (``solver.continuation``).
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass

import numpy as np

from solver.constraints import ConstraintSystem, States
from solver.errors import InvalidScene
from solver.rigid import Array

NEWTON_TOLERANCE = 1e-13  # residual, relative to the scene size (the default)
TOLERANCE_BOUNDS = (1e-15, 1e-6)  # a user's choice of the Newton tolerance must lie in here
NEWTON_MAX_ITERATIONS = 50


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
    (quadratic convergence), kept only where it lowers the residual. Returns (q, residual norms
    (M,), iterations, the length of each sample's first step (rotations times the size)).
    """
    iterations = 0
    weights = np.tile([1.0, 1.0, system.scene.size], len(system.unknown))
    first = np.zeros(q.shape[0])
    equations = system.residual(known, q.shape[0], turns)
    while True:
        phi, J = equations(q)
        residual = np.sqrt(np.einsum("mi,mi->m", phi, phi))
        done = residual <= tolerance
        if np.all(done | ~np.isfinite(residual)) or iterations >= max_iterations:
            break
        step = np.where(done[:, None], 0.0, system.solve(J, phi))
        if iterations == 0:
            first = np.sqrt(np.einsum("mi,mi->m", step * weights, step * weights))
        q = q - step
        iterations += 1
    if polish and np.any(done):
        trial = q - system.solve(J, phi)
        phi_next = equations(trial)[0]
        better = np.sqrt(np.einsum("mi,mi->m", phi_next, phi_next))
        take = done & (better < residual)
        q = np.where(take[:, None], trial, q)
        residual = np.where(take, better, residual)
    return q, residual, iterations, first
