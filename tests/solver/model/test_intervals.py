"""Tests of solver.model.intervals: ranges of a time law and its derivatives over spans of time (the
natural interval extension that lets the event search resolve a fast law between samples).

Sources: ranges worked by hand from the functions' crests, troughs, poles and monotonicity
(exact to the rounding of the end values, 1e-15); and a property checked against the law
itself: every value of s' and s'' at 33 points of a span lies in the span's range (the law read
by sympy.sympify, differentiated by sympy and evaluated by lambdify: not through solver.model.laws).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
import sympy

from solver.errors import InvalidExpression
from solver.model.intervals import enclosure, ranges
from solver.model.laws import T, parse_time_law

E = math.e
INF = math.inf
CREST = 2e5 * math.pi  # a crest of cos 6e5 rad from 0 (its end values carry rounding 1e-10)


@pytest.mark.parametrize(
    ("expr", "span", "want"),
    [
        ("sin(t)", (1.0, 2.0), (math.sin(1.0), 1.0)),  # crest pi/2 inside
        ("sin(t)", (4.0, 5.0), (-1.0, math.sin(4.0))),  # trough 3 pi/2 inside
        ("sin(t)", (0.1, 0.2), (math.sin(0.1), math.sin(0.2))),  # rising, no extreme
        ("sin(t)", (2.0, 4.5), (math.sin(4.5), math.sin(2.0))),  # falling, no extreme
        ("sin(t)", (0.0, 7.0), (-1.0, 1.0)),  # more than a period
        ("cos(t)", (3.0, 4.0), (-1.0, math.cos(4.0))),  # trough pi inside
        ("cos(t)", (-0.5, 0.25), (math.cos(-0.5), 1.0)),  # crest 0 inside
        ("cos(t)", (0.5, 1.0), (math.cos(1.0), math.cos(0.5))),
        ("cos(t)", (CREST - 0.1, CREST + 0.2), (math.cos(CREST + 0.2), 1.0)),  # far from 0
        ("tan(t)", (1.0, 2.0), (-INF, INF)),  # pole pi/2 inside
        ("tan(t)", (2.0, 3.0), (math.tan(2.0), math.tan(3.0))),
        ("tan(t)", (-1.0, 1.0), (math.tan(-1.0), math.tan(1.0))),
        ("t^2", (-1.0, 2.0), (0.0, 4.0)),  # an even power is 0 where t is
        ("t^2", (-3.0, -2.0), (4.0, 9.0)),
        ("t^2", (0.5, 2.0), (0.25, 4.0)),  # 0 outside: the smaller end's square
        ("t^3", (-1.0, 2.0), (-1.0, 8.0)),
        ("t^(-1)", (1.0, 2.0), (0.5, 1.0)),
        ("t^(-1)", (-2.0, -1.0), (-1.0, -0.5)),
        ("t^(-1)", (-1.0, 0.0), (-INF, INF)),  # the pole at the upper end
        ("t^(-2)", (-2.0, -1.0), (0.25, 1.0)),
        ("t^(-2)", (-1.0, 2.0), (-INF, INF)),  # a pole inside
        ("t^(-3)", (0.0, 2.0), (-INF, INF)),  # a pole at an end
        ("sqrt(t)", (-1.0, 4.0), (0.0, 2.0)),  # clipped to the domain t >= 0
        ("t^(-0.5)", (1.0, 4.0), (0.5, 1.0)),
        ("2^t", (1.0, 3.0), (2.0, 8.0)),  # exp(t log 2)
        ("cosh(t)", (-1.0, 2.0), (1.0, math.cosh(2.0))),  # its minimum 1 at 0 inside
        ("cosh(t)", (-0.5, 0.25), (1.0, math.cosh(0.5))),
        ("cosh(t)", (-2.0, -1.0), (math.cosh(1.0), math.cosh(2.0))),
        ("cosh(t)", (1.0, 2.0), (math.cosh(1.0), math.cosh(2.0))),
        ("acos(t)", (-0.5, 0.5), (math.acos(0.5), math.acos(-0.5))),  # falling
        ("asin(t)", (0.5, 2.0), (math.asin(0.5), math.pi / 2)),  # clipped to [-1, 1]
        ("atan(t)", (-1.0, 1.0), (-math.pi / 4, math.pi / 4)),
        ("sinh(t)", (-1.0, 1.0), (math.sinh(-1.0), math.sinh(1.0))),
        ("tanh(t)", (0.0, 1.0), (0.0, math.tanh(1.0))),
        ("exp(t)", (0.0, 1.0), (1.0, E)),
        ("log(t)", (-1.0, E), (-INF, 1.0)),  # clipped to t >= 0
        ("3 - 2*t", (0.0, 1.0), (1.0, 3.0)),
        ("(t - 1)*(t + 2)", (0.0, 2.0), (-4.0, 4.0)),  # [-1, 1] x [2, 4], wider than [-2, 4]
        ("t*tan(t)", (0.0, 2.0), (-INF, INF)),  # 0 x the whole line: undefined (nan)
        ("tan(t) + log(t)", (-2.0, -1.0), (-INF, INF)),  # (-inf, inf) + (-inf, -inf): high nan
    ],
)
def test_range_over_a_span_worked_by_hand(
    expr: str, span: tuple[float, float], want: tuple[float, float]
) -> None:
    """The natural interval extension of one node (or a sum, a product) over [a, b]: the hand
    value named in each case; 1e-15 relative to max(1, |end|)."""
    a, b = (np.array([x]) for x in span)
    low, high = ranges(enclosure(sympy.sympify(expr, locals={"t": T})), a, b)
    for got, value, end in ((low[0], want[0], "low"), (high[0], want[1], "high")):
        if math.isinf(value):
            assert got == value, f"{expr} on {span}: {end} {got!r}, want {value!r}"
        else:
            assert abs(got - value) <= 1e-15 * max(1.0, abs(value)), f"{expr} on {span}: {end}"


LAWS = [
    "0.01*sin(1000*t) - t",
    "0.2*sin(40*t)",
    "0.01*sin(1000*t)*exp(-50*(t - 5)^2)",
    "t^2 - t",
    "tan(t)",
    "acos(t/10)",
    "asin(t/10) + atan(t)*tanh(t - 2)",
    "cosh(t - 3) - sinh(t)",
    "2^t - t^t",
    "sqrt(t) + t^(1/3)",
    "1/(t + 1) + 1/(t - 2.5)^3",
    "log(t + 1)*cos(3*t)^2",
    "(t - 1)^4 - 3*t^5 + t^(-2.5)",
]


@pytest.mark.parametrize("law", LAWS)
def test_ranges_hold_every_value_of_the_rate_and_its_derivative(law: str) -> None:
    """For 2000 random spans of t in (0.01, 9) s, 1e-4 to 3 s wide (seed 1): s'(t) and s''(t)
    (sympy's, by lambdify) at 33 evenly spread points of each span lie in the span's
    ``TimeLaw.rate_ranges``, to 1e-9 of max(1, |value|) (the ranges hold to the rounding of
    their ends). Where the law is undefined (a pole, outside a domain) the value is skipped; at
    least 60 % of the values are checked."""
    rng = np.random.default_rng(1)
    a = rng.uniform(0.01, 9.0, 2000)
    b = a + 10.0 ** rng.uniform(-4.0, 0.5, 2000)
    time_law = parse_time_law(law)
    rate_range, rate_dot_range = time_law.rate_ranges(a, b)
    expr = sympy.sympify(law, locals={"t": T})
    first, second = (sympy.lambdify(T, sympy.diff(expr, T, n), "numpy") for n in (1, 2))
    checked = 0
    for i in range(33):
        t = a + (b - a) * i / 32
        with np.errstate(all="ignore"):
            rate = np.broadcast_to(first(t), t.shape)
            rate_dot = np.broadcast_to(second(t), t.shape)
        for value, (low, high) in ((rate, rate_range), (rate_dot, rate_dot_range)):
            defined = np.isfinite(value)
            slack = 1e-9 * np.maximum(1.0, np.abs(value))
            outside = defined & ((value < low - slack) | (value > high + slack))
            assert not outside.any(), f"{law}: t = {t[outside][:3]} outside its span's range"
            checked += int(defined.sum())
    assert checked >= 0.6 * 2 * 33 * a.size


def test_a_node_outside_the_laws_grammar_is_refused() -> None:
    """|t| is not in the laws' grammar (the parser never builds it); were sympy to rewrite a law
    into it, bounding it must fail loudly (invalid_expression at character 0) rather than
    return a range that may miss values."""
    with pytest.raises(InvalidExpression, match=r"^cannot bound Abs\(t\) numerically$") as error:
        enclosure(sympy.Abs(T))
    assert error.value.position == 0
