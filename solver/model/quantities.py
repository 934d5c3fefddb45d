"""Which quantities a request asks for, and the order of derivatives they need.

The kinematic quantities are ``QUANTITIES``; the dynamic ones (dynamics-v1) are computed only
when asked for; ``polygons`` (an extension, one instant of a linkage only: POST /analyze) the
velocity and acceleration polygons' segments as /solution gives them. ``required_order`` is 0
for positions, 1 for velocities, 2 for accelerations.
"""

from __future__ import annotations

from collections.abc import Iterable
from typing import Literal, get_args

from solver.errors import InvalidScene

# The names are declared here once; the server's schemas import the Literal types.
KinematicQuantity = Literal["position", "velocity", "acceleration", "poles", "components"]
DynamicQuantity = Literal["forces", "energy"]  # dynamics-v1: computed by solver.dynamics
Quantity = Literal[KinematicQuantity, DynamicQuantity]
InstantQuantity = Literal[Quantity, "polygons"]  # POST /analyze's: a sweep has no polygons
QUANTITIES: tuple[KinematicQuantity, ...] = get_args(KinematicQuantity)
DYNAMIC_QUANTITIES: tuple[DynamicQuantity, ...] = get_args(DynamicQuantity)
POLYGONS = "polygons"


def normalise_quantities(quantities: Iterable[str] | None, instant: bool = False) -> frozenset[str]:
    """The requested quantities; the default is every kinematic one (the dynamic ones, which
    dynamics-v1 adds, and ``polygons``, for one instant only (``instant``), only when asked
    for)."""
    if quantities is None:
        return frozenset(QUANTITIES)
    chosen = frozenset(quantities)
    allowed = (*QUANTITIES, *DYNAMIC_QUANTITIES, *((POLYGONS,) if instant else ()))
    unknown = sorted(chosen - set(allowed))
    if unknown:
        raise InvalidScene(f"quantities: unknown {unknown}; allowed: {', '.join(allowed)}")
    return chosen


def required_order(quantities: frozenset[str], moving_points: bool = False) -> int:
    """0 for positions, 1 to velocities, 2 to accelerations (poles, components, forces and
    energy need both; so do moving points, whose velocity and acceleration parts come together)."""
    if quantities & {"acceleration", "poles", "components", *DYNAMIC_QUANTITIES} or (
        moving_points and quantities - {"position"}
    ):
        return 2
    return 1 if "velocity" in quantities else 0
