"""The closed-form groups (solver.dyads): the length margin's rate is its derivative (central
differences), and a pin in two nearly parallel slots still meets while parallel slots do not.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
import pytest


def _moving(point: np.ndarray, t: np.ndarray, spin: float) -> Any:
    """A point turning about the origin at ``spin`` rad per unit t, from ``point`` at t = 0."""
    from solver.rigid import PointMotion

    c, s = np.cos(spin * t), np.sin(spin * t)
    p = np.stack((c * point[0] - s * point[1], s * point[0] + c * point[1]), axis=-1)
    return PointMotion(p, spin * np.stack((-p[:, 1], p[:, 0]), axis=-1))


@pytest.mark.parametrize("kind", ["circle-circle", "circle-line", "lever"])
def test_margin_rate_is_the_derivative_of_the_margin(kind: str) -> None:
    """dm/du of each group type against central differences of m (step 1e-6, to 1e-8), with
    every locus moving: centres on circles, the slot turning with its guide."""
    from solver import dyads

    t0 = np.linspace(0.1, 6.0, 7)
    step = 1e-6

    def margin_and_rate(t: np.ndarray) -> tuple[np.ndarray, np.ndarray | None]:
        first = _moving(np.array([0.4, 0.1]), t, 1.0)
        second = _moving(np.array([1.0, -0.2]), t, -0.7)
        if kind == "lever":
            return dyads.lever_margin(first, second, 0.3)
        circle = dyads.Circle(first, 0.9, "B", "coupler")
        if kind == "circle-circle":
            other: dyads.Locus = dyads.Circle(second, 0.5, "D", "rocker")
        else:
            direction = np.stack((np.cos(-0.7 * t), np.sin(-0.7 * t)), axis=-1)
            omega = np.full(t.size, -0.7)
            other = dyads.Line(second, direction, omega, np.zeros(t.size), "guide")
        cut = dyads.intersect(circle, other, "C")
        return cut.margin, cut.margin_rate

    _, rate = margin_and_rate(t0)
    ahead, _ = margin_and_rate(t0 + step)
    behind, _ = margin_and_rate(t0 - step)
    assert rate is not None
    np.testing.assert_allclose(rate, (ahead - behind) / (2.0 * step), atol=1e-8)


def test_pin_in_two_nearly_parallel_slots_still_meets() -> None:
    """Two slots 1e-6 rad apart meet, far away: slot 1 the x axis, slot 2 through (0, 1) at
    angle 1e-6, so X = (-1 / tan(1e-6), 0) (one solution: margin +inf); parallel slots do not."""
    from solver import dyads
    from solver.rigid import PointMotion

    def slot(through: list[float], angle: float) -> dyads.Line:
        direction = np.array([[math.cos(angle), math.sin(angle)]])
        return dyads.Line(PointMotion(np.array([through])), direction, None, None, "guide")

    cut = dyads.intersect(slot([0.0, 0.0], 0.0), slot([0.0, 1.0], 1e-6), "X")
    assert cut.margin[0] == math.inf
    np.testing.assert_allclose(cut.point(np.ones(1))[0], [-1.0 / math.tan(1e-6), 0.0], rtol=1e-9)
    parallel = dyads.intersect(slot([0.0, 0.0], 0.0), slot([0.0, 1.0], 0.0), "X")
    assert parallel.margin[0] == -math.inf and "parallel" in parallel.message
