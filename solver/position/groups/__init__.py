"""The closed-form groups a linkage decomposes into, one module per Assur group, in a registry.

RRR (``rrr``: two circles), RRP (``rrp``: a circle and a slot), PRP (``prp``: a pin in two
slots) locate a joint point; RPR (``rpr``: a slotted lever) turns a link about a known pivot.
Each follows the protocol ``base.Group``; the assembler asks ``group_of(step)`` instead of
dispatching on the step's type. Adding a group: its module here (and its tests), its entry in
``GROUPS``, and the place in ``topology`` where the decomposition recognises it.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from solver.position.groups import prp, rpr, rrp, rrr
from solver.position.groups.base import Group
from solver.position.groups.loci import Circle, Intersection, Locus

if TYPE_CHECKING:
    from solver.position.topology import DyadStep, LeverStep

GROUPS: dict[str, Group] = {
    group.kind: group for group in (rrr.GROUP, rrp.GROUP, prp.GROUP, rpr.GROUP)
}


def group_of(step: DyadStep | LeverStep) -> Group:
    """The group type of a plan step, by its ``kind``."""
    return GROUPS[step.kind]


def intersect(first: Locus, second: Locus, name: str) -> Intersection:
    """Both candidate positions of the point ``name`` on the two loci (in either order), by the
    group their kinds make: two circles RRR, a circle and a line RRP, two lines PRP."""
    if not isinstance(first, Circle) and isinstance(second, Circle):
        first, second = second, first
    circles = isinstance(first, Circle) + isinstance(second, Circle)
    group = (prp.GROUP, rrp.GROUP, rrr.GROUP)[circles]
    return group.intersect(first, second, name)
