"""The closed-form groups as the worked solutions write them, one module per Assur group, in a
registry keyed like the position layer's (``solver.position.groups.GROUPS``).

RRR (``rrr``: the triangle, the four-bar loop), RRP (``rrp``: a circle and a guide, the
slider-crank loop), PRP (``prp``: a pin in two slots), RPR (``rpr``: the slotted lever). Each
follows the protocol ``base.SolutionGroup``; the position, vector and loop methods and the
typical mistakes ask ``solution_group(step)`` instead of dispatching on the step's type.
``groups()`` collects every module of this package that defines a ``GROUP``: adding a group is its
module here, beside its module in ``solver.position.groups`` and the place in ``topology`` that
recognises it.
"""

from __future__ import annotations

import functools
import importlib
import pkgutil

from solver.position.topology import DyadStep, LeverStep, PlanStep
from solver.solutions.groups.base import SolutionGroup


@functools.cache
def groups() -> dict[str, SolutionGroup]:
    """Every module of this package with a ``GROUP``, by the group's kind (collected on first
    use: a group's module may build on the methods that ask the registry)."""
    found: dict[str, SolutionGroup] = {}
    for module in pkgutil.iter_modules(__path__):
        group = getattr(importlib.import_module(f"{__name__}.{module.name}"), "GROUP", None)
        if group is not None:
            found[group.kind] = group
    return found


def solution_group(step: PlanStep) -> SolutionGroup | None:
    """The solution module of a plan step's closed-form group, by its ``kind`` (None: a driven
    link, a link known from its points, a Newton group)."""
    if isinstance(step, DyadStep | LeverStep):
        return groups()[step.kind]
    return None
