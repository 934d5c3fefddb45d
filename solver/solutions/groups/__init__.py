"""The closed-form groups as the worked solutions write them, one module per Assur group, in a
registry keyed like the position layer's (``solver.position.groups.GROUPS``).

RRR (``rrr``: the triangle, the four-bar loop), RRP (``rrp``: a circle and a guide, the
slider-crank loop), PRP (``prp``: a pin in two slots), RPR (``rpr``: the slotted lever). Each
follows the protocol ``base.SolutionGroup``; the position, vector and loop methods and the
typical mistakes ask ``solution_group(step)`` instead of dispatching on the step's type.
Adding a group: its module here (and its entry in ``GROUPS``), beside its module in
``solver.position.groups`` and the place in ``topology`` that recognises it.
"""

from __future__ import annotations

from solver.position.topology import DyadStep, LeverStep, PlanStep
from solver.solutions.groups import prp, rpr, rrp, rrr
from solver.solutions.groups.base import SolutionGroup

GROUPS: dict[str, SolutionGroup] = {
    group.kind: group for group in (rrr.GROUP, rrp.GROUP, prp.GROUP, rpr.GROUP)
}


def solution_group(step: PlanStep) -> SolutionGroup | None:
    """The solution module of a plan step's closed-form group, by its ``kind`` (None: a driven
    link, a link known from its points, a Newton group)."""
    if isinstance(step, DyadStep | LeverStep):
        return GROUPS[step.kind]
    return None
