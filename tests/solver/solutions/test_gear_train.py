"""The worked solution of a gear train (solver.solutions.gear_train, issue 25): the tabular
(Willis) method and the formula method, every number the solver's.

Sources: Shigley/Uicker, Theory of Machines and Mechanisms, ch. 13 (the planetary train with the
ring fixed, omega_arm / omega_sun = N_s / (N_s + N_r); the formula method e = (omega_L -
omega_A) / (omega_F - omega_A)); Rattan, Theory of Machines, ch. 10 (the tabular method, the
compound train value as the product of tooth ratios); the spur-gear differential, omega_carrier =
(omega_left + omega_right) / 2. Properties: every step's checks re-evaluate from its listed
values (``verify`` of test_solve), every value with a source is the /analyze number at that path,
every boxed number is a listed value, the LaTeX typesets in KaTeX.
"""

from __future__ import annotations

import json
from fractions import Fraction
from pathlib import Path
from typing import Any

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import solver
from solver.gears import parse_gear_train
from solver.solutions import Solution, Step, solve
from solver.teaching.gear_presets import GEAR_PRESETS, build_gear_preset
from tests.solver.solutions.test_solve import (
    Katex,
    at_path,
    katex,  # noqa: F401 (the fixture)
    unit_floors,
    verify,
)

EXAMPLE = json.loads(
    (
        Path(__file__).resolve().parents[3] / "server" / "examples" / "G001-planetary.json"
    ).read_text()
)


def solution_of(doc: dict[str, Any], digits: int = 4) -> Solution:
    return solve(parse_gear_train(doc), "vector", digits)


def scenes() -> list[tuple[str, dict[str, Any]]]:
    return [("G001-planetary", EXAMPLE)] + [(n, build_gear_preset(n, {})) for n in GEAR_PRESETS]


def check_solution(solution: Solution) -> None:
    """Checks re-evaluate; sources are the /analyze numbers; the last step is the summary."""
    body = solution.analysis
    floors = unit_floors(step.as_json() for step in solution.steps)
    for step in solution.steps:
        failures = verify(step.as_json(), floors)
        assert not failures, failures[:3]
        for key, v in step.values.items():
            if v.source is not None:
                assert np.array_equal(v.value, at_path(body, v.source)), (step.title, key)
    assert solution.steps[-1].kind == "summary"


def steps(solution: Solution, kind: str) -> list[Step]:
    return [s for s in solution.steps if s.kind == kind]


def value(step: Step, key: str) -> float:
    number = step.values[key].value
    assert isinstance(number, float)
    return number


@pytest.mark.parametrize("digits", [2, 4, 9])
@pytest.mark.parametrize(("name", "doc"), scenes())
def test_every_step_re_evaluates_with_the_solver_numbers(
    name: str, doc: dict[str, Any], digits: int
) -> None:
    solution = solution_of(doc, digits)
    assert solution.method == "tabular"
    check_solution(solution)


def test_planetary_ring_fixed_tabular_and_formula_give_shigley_closed_form() -> None:
    """Ring fixed: omega_arm / omega_sun = N_s / (N_s + N_r) = 20 / 100, both methods."""
    solution = solution_of(EXAMPLE)
    (table,) = steps(solution, "gears.tabular")
    (formula,) = steps(solution, "gears.formula")
    assert value(table, "y") == pytest.approx(100.0 * 20 / (20 + 80), rel=1e-12)
    assert value(table, "x") == pytest.approx(100.0 - 20.0, rel=1e-12)
    assert value(formula, "omega(arm)") == pytest.approx(20.0, rel=1e-12)
    assert value(formula, "r(sun,planet)") == pytest.approx(-20 / 30, rel=1e-15)
    assert value(formula, "e(sun,ring)") == pytest.approx(-20 / 80, rel=1e-15)
    # the three rows of the table, and the formula written out
    for row in ("arm locked, sun +x", "all with arm +y", r"\text{sum } \omega"):
        assert row in table.latex
    assert r"\frac{\omega_L - \omega_{arm}}{\omega_F - \omega_{arm}}" in formula.latex
    assert "counter-clockwise positive" in solution.steps[0].text
    assert solution.steps[0].figure.startswith("<svg")


@settings(max_examples=40, deadline=None)
@given(
    st.integers(12, 60),
    st.integers(12, 60),
    st.sampled_from([-200.0, -3.0, 7.0, 100.0, 1500.0]),
)
def test_planetary_ring_fixed_for_any_teeth(sun: int, planet: int, omega: float) -> None:
    doc = build_gear_preset(
        "planetary_ring_fixed", {"N_sun": sun, "N_planet": planet, "omega_sun": omega}
    )
    solution = solution_of(doc)
    check_solution(solution)
    ring = sun + 2 * planet
    (formula,) = steps(solution, "gears.formula")
    exact = float(Fraction(sun, sun + ring) * Fraction(omega))
    assert value(formula, "omega(arm)") == pytest.approx(exact, rel=1e-12)


def test_differential_carrier_is_the_mean_of_the_side_gears() -> None:
    doc = build_gear_preset("differential", {"omega_left": 40.0, "omega_right": -12.0})
    solution = solution_of(doc)
    check_solution(solution)
    (formula,) = steps(solution, "gears.formula")
    assert value(formula, "omega(carrier)") == pytest.approx((40.0 - 12.0) / 2, rel=1e-12)
    assert value(formula, "e(left,right)") == -1.0


def test_compound_train_value_is_the_product_of_tooth_ratios() -> None:
    """e = (N2/N3)(N4/N5) = (20/40)(16/44) = 2/11, both meshes external: positive."""
    solution = solution_of(build_gear_preset("compound_reverted", {}))
    (ordinary,) = steps(solution, "gears.ordinary")
    assert not steps(solution, "gears.tabular")
    assert value(ordinary, "e(gear2,gear5)") == pytest.approx(2 / 11, rel=1e-15)
    assert value(ordinary, "omega(gear5)") == pytest.approx(150 * 2 / 11, rel=1e-12)
    assert r"(-\frac{20}{40}) \cdot (-\frac{16}{44})" in ordinary.latex


def test_two_stage_train_solves_the_second_stage_from_the_keyed_arm() -> None:
    """e = 1/5 x 1/5 = 1/25: the first arm, keyed to the second sun, drives the second stage."""
    solution = solution_of(build_gear_preset("two_stage_planetary", {}))
    kinds = [s.kind for s in solution.steps]
    assert kinds.count("gears.tabular") == 2 and "gears.keyed" in kinds
    assert kinds.index("gears.keyed") < len(kinds) - 1 - kinds[::-1].index("gears.tabular")
    summary = solution.steps[-1]
    assert value(summary, "omega(arm2)") == pytest.approx(300 / 25, rel=1e-12)


def test_a_carrier_given_as_input_is_used_in_the_table() -> None:
    """The arm driven and the sun fixed (Shigley's reversed case): omega_ring = omega_arm (1 +
    N_s / N_r)."""
    doc = json.loads(json.dumps(EXAMPLE)) | {"inputs": {"arm": 20.0, "sun": 0.0}}
    solution = solution_of(doc)
    check_solution(solution)
    assert value(solution.steps[-1], "omega(ring)") == pytest.approx(20.0 * (1 + 20 / 80))


def test_api_and_http_body_carry_the_analyze_answer() -> None:
    body = solver.solve(EXAMPLE).as_dict()
    assert body["method"] == body["requested_method"] == "tabular"
    assert body["results"] == solver.analyze(EXAMPLE).as_dict()
    assert [s["kind"] for s in body["steps"]][:2] == ["gears.data", "gears.freedom"]


def test_latex_typesets(katex: Katex) -> None:  # noqa: F811 (the fixture)
    latex = [s.latex for _, doc in scenes() for s in solution_of(doc).steps if s.latex]
    assert not katex.failures(latex)
