"""The closed-form groups as the worked solutions write them (``solver.solutions.groups``): one
module per Assur group, asked by the methods instead of a dispatch on the step's type."""

from __future__ import annotations

import numpy as np

from solver.model.scene import parse_linkage
from solver.position import groups as position_groups
from solver.position.groups.rrr import chord
from solver.position.topology import DriverStep, DyadStep, build_plan
from solver.solutions.groups import groups, solution_group
from tests.solver.solutions.test_solve import _check_solution, example, solution_of


def test_every_group_of_the_position_layer_has_its_solution_module() -> None:
    assert set(groups()) == set(position_groups.GROUPS)
    assert all(kind == group.kind for kind, group in groups().items())


def test_a_plan_step_is_asked_for_its_group_by_kind() -> None:
    """The four-bar's plan: the driven link is no group; the RRR dyad is its module."""
    plan = build_plan(parse_linkage(example("S000-T1")))
    dyad = next(step for step in plan.steps if isinstance(step, DyadStep))
    assert solution_group(dyad) is groups()["RRR"]
    driver = next(step for step in plan.steps if isinstance(step, DriverStep))
    assert solution_group(driver) is None


def test_the_triangle_takes_the_chord_of_the_position_layer_and_its_arithmetic_recomputes() -> None:
    """cos gamma = a / r1 with a from ``rrr.chord`` (B = (0, 1), D = (2.5, 0), BC = 2,
    DC = sqrt(1.25)), and every check of the step recomputes from its shown numbers."""
    solution = solution_of(example("S000-T1"))
    step = next(s for s in solution.steps if s.kind == "position.triangle")
    cut = chord(np.array([[2.5, -1.0]]), 2.0, float(np.sqrt(1.25)))
    assert step.values["cos gamma"].value == float(cut.a[0]) / 2.0
    assert step.values["|BD|"].value == float(cut.d[0])
    _check_solution(solution)
