"""``present_solution``: the 2x2 system written and solved the way the seeds do, each branch
against numpy's solution of the same system (relative tolerance 1e-12) and its checks."""

from __future__ import annotations

import numpy as np
import pytest

from solver.solutions.builder import StepBuilder, Unknown, present_solution
from solver.solutions.digits import needed_digits
from solver.solutions.format import Formatter


def system(matrix: list[list[float]], rhs: list[float], cramer: bool = False) -> StepBuilder:
    """Register c_ij and b_i, solve with numpy for the unknowns' values, present the solution."""
    b = StepBuilder(Formatter(4), "test", "a 2x2 system")
    c = [[b.put(f"c{i + 1}{j + 1}", matrix[i][j], "") for j in range(2)] for i in range(2)]
    r = [b.put(f"b{i + 1}", rhs[i], "") for i in range(2)]
    try:
        u = np.linalg.solve(np.array(matrix), np.array(rhs))
    except np.linalg.LinAlgError:
        u = np.array([rhs[0] / matrix[0][0], 0.0])
    unknowns = [Unknown(f"u{j + 1}", f"u_{j + 1}", f"u{j + 1}", "", float(u[j])) for j in range(2)]
    present_solution(b, unknowns, c, r, "", cramer=cramer)
    return b


def test_cramer_determinants() -> None:
    """D = det c, D_j = det of c with column j replaced by b, u_j = D_j / D."""
    matrix, rhs = [[2.0, -1.0], [0.5, 3.0]], [1.0, 4.0]
    b = system(matrix, rhs, cramer=True)
    det = np.linalg.det(np.array(matrix))
    assert b.scalar("D") == pytest.approx(det, rel=1e-12)
    for j in range(2):
        replaced = np.array(matrix)
        replaced[:, j] = rhs
        d_j = b.scalar(f"D{j + 1}")
        assert d_j == pytest.approx(np.linalg.det(replaced), rel=1e-12)
        assert b.scalar(f"u{j + 1}") == pytest.approx(d_j / det, rel=1e-12)
    relations = [check.relation for check in b.checks]
    assert relations == ["linear", "linear", "det2", "det2", "quotient", "det2", "quotient"]
    assert "By Cramer's rule" in b.build().text


def test_substitution() -> None:
    """Row 1 has u1 alone: u1 = b1 / c11, then u2 = (b2 - c21 u1) / c22 from row 2."""
    matrix, rhs = [[2.0, 0.0], [0.5, 4.0]], [1.0, 3.0]
    b = system(matrix, rhs)
    assert b.scalar("rest") == pytest.approx(rhs[1] - matrix[1][0] * rhs[0] / matrix[0][0])
    text = b.build().text
    assert "Equation 1 has the single unknown u1" in text
    assert "Substituting into equation 2" in text
    assert [check.relation for check in b.checks][-2:] == ["quotient", "quotient"]


def test_unknown_not_in_the_equations() -> None:
    """A column of zeros: u2 is not determined, and the step says so."""
    b = system([[2.0, 0.0], [1.0, 0.0]], [1.0, 0.5])
    assert "u2 does not appear in the equations" in b.build().text
    assert "rest" not in b.values


def test_each_equation_its_own_unknown() -> None:
    """A diagonal system (rows swapped): each row gives its unknown directly."""
    b = system([[0.0, 3.0], [2.0, 0.0]], [6.0, 1.0])
    assert b.scalar("u1") == pytest.approx(0.5)
    assert b.scalar("u2") == pytest.approx(2.0)
    assert "D" not in b.values


def test_the_written_solution_settles_its_digits_in_one_pass() -> None:
    """Cramer's rule written with references: built once, the determinants and
    the unknowns show in the LaTeX and the text as their values do, every check recomputing
    from the digits shown."""
    b = system([[0.0126544, -1.0], [0.5, 3.0]], [-0.03125, 4.0], cramer=True)
    step = b.build()
    assert b.digits  # the premise: four digits do not recompute, some values show more
    assert needed_digits(step.values, b.references, step.checks, b.fmt) == b.digits
    for key in ("D", "D1", "D2", "u1", "u2"):
        assert step.values[key].display in step.text
        assert step.values[key].display in step.latex


def test_a_step_built_unwritten_has_the_written_steps_structure_and_no_words() -> None:
    """``written=False`` (what the polygons read): the same kind, title, values with their
    numbers, units and sources, and checks as the written step, and neither LaTeX, text nor
    displays (nothing formatted, no digits settled)."""

    def built(written: bool) -> StepBuilder:
        b = StepBuilder(Formatter(4), "test", "a 2x2 system", written)
        c = [[b.put(f"c{i}{j}", [[0.0126544, -1.0], [0.5, 3.0]][i][j], "", ("c", i, j))
              for j in range(2)] for i in range(2)]  # fmt: skip
        r = [b.put(f"b{i}", [-0.03125, 4.0][i], "m", ("b", i)) for i in range(2)]
        unknowns = [Unknown(f"u{j}", f"u_{j}", f"u{j}", "", [-2.3, 1.7][j]) for j in range(2)]
        present_solution(b, unknowns, c, r, "", cramer=True)
        return b

    written, structure = built(True).build(), built(False).build()
    assert (structure.kind, structure.title) == (written.kind, written.title)
    assert structure.checks == written.checks
    assert list(structure.values) == list(written.values)
    for key, value in structure.values.items():
        shown = written.values[key]
        assert (value.value, value.unit, value.source) == (shown.value, shown.unit, shown.source)
        assert value.display == "" and shown.display != ""
    assert (structure.latex, structure.text) == ("", "")
    assert written.latex and written.text
