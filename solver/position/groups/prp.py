"""PRP: a pin in two slots, each fixed in a known link (one solution)."""

from __future__ import annotations

import numpy as np

from solver.kinematics.rigid import cross, scale
from solver.position.groups.base import DyadGroup
from solver.position.groups.loci import Intersection, Line


def line_line(l1: Line, l2: Line, name: str) -> Intersection:
    """A pin in two slots: X = Q1 + t w1 with w2 x (X - Q2) = 0 (one solution: margin +inf)."""
    denominator = cross(l2.direction, l1.direction)
    parallel = np.abs(denominator) <= 1e-12
    t = cross(l2.direction, l2.through.p - l1.through.p) / np.where(parallel, 1.0, denominator)
    margin = np.where(parallel, -np.inf, np.inf)
    base = l1.through.p + scale(t, l1.direction)

    def message() -> str:
        return f"the two slots that carry {name} (in '{l1.guide}' and '{l2.guide}') are parallel"

    return Intersection(base, l1.direction, np.zeros_like(t), margin, (), message)


GROUP = DyadGroup("PRP", line_line, two_branch=False)
