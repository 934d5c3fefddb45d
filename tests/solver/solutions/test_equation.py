"""A step written once: one equation gives the LaTeX line and the text, checks name values by
typed reference, and a step's digits are settled in one pass when it is built.

Sources: the rigid-body velocity v_B = v_A + omega x r_AB as the worked solutions write it
(tests/solver/solutions/test_solve.py pins it on the seeds), and the issue's example of shown
arithmetic that does not recompute (-0.03125 / 0.01265 = -2.470 while the step says -2.469).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from solver.solutions.builder import StepBuilder
from solver.solutions.digits import TOLERANCE_ULP, rounded
from solver.solutions.equation import (
    TIMES,
    Boxed,
    Col,
    Equation,
    Frac,
    Num,
    Ref,
    Sym,
    ZCross,
    latex_only,
)
from solver.solutions.format import Formatter

V_A = Sym(r"\vec{v}_{A}", "v(A)")


def rigid_velocity() -> tuple[StepBuilder, Equation]:
    """v_B = v_A + omega x r_AB with omega = 2 rad/s, r_AB = (0.5, 0) m, v_A = (1, 0) m/s."""
    b = StepBuilder(Formatter(4), "velocity.rigid", "Velocity of B")
    va = b.value("v(A)", (1.0, 0.0), "m/s")
    w = b.value("omega(2)", 2.0, "rad/s")
    r = b.value("r(A,B)", (0.5, 0.0), "m")
    wxr = b.value("omega x r(A,B)", (0.0, 1.0), "m/s")
    vb = b.value("v(B)", (1.0, 1.0), "m/s")
    b.check("cross", wxr, w, r)
    b.check("sum", vb, va, wxr)
    eq = Equation.of(
        Sym(r"\vec{v}_{B}", "v(B)"),
        (V_A, " + ", Sym(r"\vec{\omega}_{2}", "omega(2)"), TIMES, Sym(r"\vec{r}_{AB}", "r(A,B)")),
        (Col(va), " + ", ZCross(w, r)),
        (Col(va), " + ", Col(wxr)),
        Boxed((Col(vb, unit=True),)),
        breaks=(3,),
    )
    return b, eq


def test_one_equation_gives_the_latex_lines_and_the_text() -> None:
    b, eq = rigid_velocity()
    b.line(eq)
    b.say(eq, ".")
    step = b.build()
    column = r"\begin{pmatrix} %s \\ %s \\ 0 \end{pmatrix}"
    assert step.latex == (
        r"\begin{aligned} &\vec{v}_{B} = \vec{v}_{A} + \vec{\omega}_{2} \times \vec{r}_{AB} = "
        + column % (1, 0)
        + r" + \begin{vmatrix} \mathbf{i} & \mathbf{j} & \mathbf{k} \\ 0 & 0 & 2 \\ "
        r"0.5 & 0 & 0 \end{vmatrix} \\ &\phantom{\vec{v}_{B}} = "
        + column % (1, 0)
        + " + "
        + column % (0, 1)
        + r" = \underline{\underline{"
        + column % (1, 1)
        + r"\,\mathrm{m/s}}} \end{aligned}"
    )
    assert step.text == (
        "v(B) = v(A) + omega(2) cross r(A,B) = (1, 0) m/s + (0, 0, 2) cross (0.5, 0) = "
        "(1, 0) m/s + (0, 1) m/s = (1, 1) m/s."
    )


def test_a_single_line_equation_is_not_aligned() -> None:
    b = StepBuilder(Formatter(4), "x", "x")
    n = b.value("n", 3.0, "")
    d = b.value("d", 4.0, "")
    q = b.value("q", 0.75, "")
    b.check("quotient", q, n, d)
    eq = Equation.of("q", Frac(n, d), Num(q))
    b.line(eq)
    b.say("So ", eq, ".")
    step = b.build()
    assert step.latex == r"q = \frac{3}{4} = 0.75"
    assert step.text == "So q = 3/4 = 0.75."


def test_a_side_without_a_text_form_is_left_out_of_the_text() -> None:
    """v_rel = s-dot tau = 0.5 (1, 0) = (0.5, 0) m/s: the substitution is shown in LaTeX only
    (``latex_only``); the text goes from the formula to the result. A broken line starts with
    the ``phantom`` given (here the letter alone) instead of the first side."""
    b = StepBuilder(Formatter(4), "x", "x")
    sd = b.value("s_dot", 0.5, "m/s")
    tau = b.value("tau", (1.0, 0.0), "")
    rel = b.value("v_rel", (0.5, 0.0), "m/s")
    b.check("product", rel, sd, tau)
    eq = Equation.of(
        latex_only(r"\vec{v}_{\mathrm{rel}}"),
        Sym(r"\dot{s}\,\vec{\tau}", "s-dot tau"),
        latex_only(Num(sd), r" \cdot ", Col(tau, dims=2)),
        Boxed((Col(rel, unit=True, dims=2),)),
        breaks=(3,),
        phantom=r"\vec{v}",
    )
    b.line(eq)
    b.say(eq, ".")
    step = b.build()
    column = r"\begin{pmatrix} %s \\ %s \end{pmatrix}"
    assert step.latex == (
        r"\begin{aligned} &\vec{v}_{\mathrm{rel}} = \dot{s}\,\vec{\tau} = 0.5 \cdot "
        + column % (1, 0)
        + r" \\ &\phantom{\vec{v}} = \underline{\underline{"
        + column % (0.5, 0)
        + r"\,\mathrm{m/s}}} \end{aligned}"
    )
    assert step.text == "s-dot tau = (0.5, 0) m/s."


def test_checks_hold_typed_references_named_by_key_in_the_body() -> None:
    b = StepBuilder(Formatter(4), "x", "x")
    p = b.value("pos(B)", (1.0, 2.0), "m")
    o = b.value("pos(A)", (0.5, 0.5), "m")
    r = b.value("r(A,B)", (0.5, 1.5), "m")
    y = b.value("y", 1.5, "m")
    b.check("sum", r, p, -o)
    b.check("sum", y, r[1])
    first, second = b.build().checks
    assert first.operands[1] == -o and first.operands[1].ref == Ref("pos(A)")
    assert first.as_json() == {
        "relation": "sum",
        "result": "r(A,B)",
        "operands": ["pos(B)", "-pos(A)"],
        "factor": 1.0,
    }
    assert second.operands[0].component == 1
    assert second.as_json()["operands"] == ["r(A,B)[1]"]


def test_a_check_of_an_unknown_value_is_refused() -> None:
    b = StepBuilder(Formatter(4), "x", "x")
    y = b.value("y", 1.0, "m")
    with pytest.raises(AssertionError, match="unknown value"):
        b.check("sum", y, Ref("nowhere"))


def _shown(display: str) -> float:
    return float(display.split()[0])


def test_digits_are_settled_in_one_pass_so_the_shown_arithmetic_recomputes() -> None:
    """0.0126544 shown with four digits (0.01265) makes -0.03125/0.01265 = -2.470, not the
    -2.469 of the quotient: built once, without a digit plan, the step shows more digits."""
    numerator, denominator = -0.03125, 0.0126544
    quotient = numerator / denominator
    naive = rounded(rounded(numerator, 4) / rounded(denominator, 4), 4)
    assert naive != rounded(quotient, 4)  # the premise: four digits do not recompute
    b = StepBuilder(Formatter(4), "x", "x")
    n = b.value("n", numerator, "")
    d = b.value("d", denominator, "")
    q = b.value("q", quotient, "")
    b.check("quotient", q, n, d)
    eq = Equation.of("q", Frac(n, d), Num(q))
    b.line(eq)
    b.say(eq)
    step = b.build()
    shown = {k: _shown(v.display) for k, v in step.values.items()}
    assert len(step.values["d"].display) > len("0.01265")  # d needed more digits
    result = shown["n"] / shown["d"]
    last = 10.0 ** (math.floor(math.log10(abs(shown["q"]))) - 3)
    assert abs(result - shown["q"]) <= TOLERANCE_ULP * last
    # the LaTeX and the text show the settled digits, the same as the values
    text = step.text
    assert text == f"q = {step.values['n'].display}/{step.values['d'].display} = -2.469"
    assert step.latex == (
        rf"q = \frac{{{step.values['n'].display}}}{{{step.values['d'].display}}} = -2.469"
    )


def test_a_number_formatted_before_the_digits_are_settled_is_refused() -> None:
    """A step settles its digits once, when it is built: a number formatted while the step is
    still written would show digits that were never settled, so it is refused (with the step's
    title), and the same number written as a reference shows once built."""
    b = StepBuilder(Formatter(4), "x", "a step")
    n = b.value("n", float(np.pi), "")
    with pytest.raises(RuntimeError, match=r"'a step'.*before its digits are settled"):
        b.num(n)
    b.line("&", Num(n))
    assert b.build().latex.endswith("3.142")
