"""LaTeX building blocks of the worked solutions (only what KaTeX supports).

Names of points and links come from the user's scene, so they are never pasted into LaTeX as they
are: a short plain name (``B``, ``A0``, ``2``) is set as math, anything else inside ``\\text{}``
with every special character escaped. Vectors are written as the seeds write them: columns with
three components (z = 0 in the plane), and cross products as 3x3 determinants with the unit vectors
in the first row.
"""

from __future__ import annotations

import math
import re
from collections.abc import Sequence

import sympy

_PLAIN = re.compile(r"[A-Za-z][0-9]{0,2}|[0-9]{1,3}")
_TEXT_ESCAPES = {
    "\\": r"\textbackslash{}",
    "{": r"\{",
    "}": r"\}",
    "$": r"\$",
    "&": r"\&",
    "#": r"\#",
    "%": r"\%",
    "_": r"\_",
    "^": r"\textasciicircum{}",
    "~": r"\textasciitilde{}",
}
_UNIT_ROW = r"\mathbf{i} & \mathbf{j} & \mathbf{k}"


def escape_text(text: str) -> str:
    """``text`` safe inside ``\\text{...}`` (control characters dropped)."""
    out = []
    for ch in text:
        if ch in _TEXT_ESCAPES:
            out.append(_TEXT_ESCAPES[ch])
        elif ch.isprintable():
            out.append(ch)
    return "".join(out) or "?"


GREEK = frozenset(
    ("alpha", "beta", "gamma", "delta", "epsilon", "zeta", "eta", "theta", "iota", "kappa",
     "lambda", "mu", "nu", "xi", "pi", "rho", "sigma", "tau", "upsilon", "phi", "chi", "psi",
     "omega", "Gamma", "Delta", "Theta", "Lambda", "Xi", "Pi", "Sigma", "Upsilon", "Phi", "Psi",
     "Omega")
)  # fmt: skip
_GREEK_NAME = re.compile(r"([A-Za-z]+)([0-9]{0,2})")


def greek(raw: str) -> tuple[str, str] | None:
    """A name that is a Greek letter spelled out, with at most two digits after it ('Gamma',
    'omega1'): (the letter's name, the digits); None for any other name."""
    found = _GREEK_NAME.fullmatch(raw)
    if found is None or found.group(1) not in GREEK:
        return None
    return found.group(1), found.group(2)


def name(raw: str) -> str:
    """A point or link name as a LaTeX subscript body; a Greek letter spelled out (a point
    'Gamma', 'omega1') as its symbol, \\Gamma, \\omega1 (not 'Gamma' in text beside a
    \\Gamma_{13})."""
    if _PLAIN.fullmatch(raw):
        return raw
    letter = greek(raw)
    if letter is not None:
        return "\\" + letter[0] + "{}" + letter[1]  # {}: safe before a letter
    return r"\text{" + escape_text(raw) + "}"


def pair(first: str, second: str) -> str:
    """The subscript of a position vector from ``first`` to ``second``: AB, or A0\\,B."""
    a, b = name(first), name(second)
    if len(first) == 1 and len(second) == 1 and _PLAIN.fullmatch(first + second) is None:
        return a + b
    return a + r"\," + b


def vec(symbol: str, sub: str) -> str:
    """\\vec{symbol}_{sub} (``sub`` is already LaTeX)."""
    return rf"\vec{{{symbol}}}_{{{sub}}}"


def scalar(symbol: str, sub: str) -> str:
    return rf"{symbol}_{{{sub}}}"


def column(entries: Sequence[str]) -> str:
    """A column vector of LaTeX entries."""
    return r"\begin{pmatrix} " + r" \\ ".join(entries) + r" \end{pmatrix}"


def determinant3(row2: Sequence[str], row3: Sequence[str], units: str = _UNIT_ROW) -> str:
    """The cross product row2 x row3 as a determinant with the unit vectors in the first row."""
    return (
        r"\begin{vmatrix} "
        + units
        + r" \\ "
        + " & ".join(row2)
        + r" \\ "
        + " & ".join(row3)
        + r" \end{vmatrix}"
    )


def determinant2(rows: Sequence[Sequence[str]]) -> str:
    return r"\begin{vmatrix} " + r" \\ ".join(" & ".join(r) for r in rows) + r" \end{vmatrix}"


def aligned(lines: Sequence[str]) -> str:
    """Several equations, aligned at their first '&'."""
    if len(lines) == 1:
        return lines[0].replace("&", "", 1)
    return r"\begin{aligned} " + r" \\ ".join(lines) + r" \end{aligned}"


def paren(latex_number: str) -> str:
    """A number in parentheses when it is negative or has a power of ten (for products such as
    2 \\cdot (-1.5) and powers such as (1.5 \\cdot 10^{-7})^2)."""
    if latex_number.startswith("-") or "^" in latex_number:
        return f"({latex_number})"
    return latex_number


def signed(latex_number: str, first: bool = False) -> str:
    """A term of a sum: '+ 0.5', '- 0.5' (or '0.5', '-0.5' as the first term)."""
    if first:
        return latex_number
    if latex_number.startswith("-"):
        return "- " + latex_number[1:]
    return "+ " + latex_number


def boxed_result(latex: str) -> str:
    """A final result, doubly underlined as in the seeds."""
    return r"\underline{\underline{" + latex + "}}"


def exact_pi(expression: sympy.Expr) -> sympy.Expr:
    """The law with each decimal number that is a simple multiple of pi (p pi / q, |p|, q <=
    1000, equal to the float within 2 units in the last place) written so: 0.23561944901923448
    -> 3 pi / 40; other numbers stay as typed."""
    exact = {}
    for f in expression.atoms(sympy.Float):
        guess = sympy.nsimplify(f, [sympy.pi], tolerance=1e-15)
        ratio = sympy.nsimplify(guess / sympy.pi)
        if (
            guess.has(sympy.pi)
            and ratio.is_Rational
            and abs(ratio.p) <= 1000
            and ratio.q <= 1000
            and abs(float(guess) - float(f)) <= 4.0 * math.ulp(float(f))
        ):
            exact[f] = guess
    return expression.xreplace(exact)


def law_text(typed: str, expression: sympy.Expr) -> str:
    """A time law in plain text: as the user typed it, or its exact form where its decimals are
    simple multiples of pi (``exact_pi``), never 17 digits of pi."""
    exact = exact_pi(expression)
    if exact == expression:
        return typed
    return str(exact).replace("**", "^")


def law(expression: sympy.Expr, digits: int) -> str:
    """A time law (or a derivative) in LaTeX, exact multiples of pi as such (``exact_pi``),
    its other decimal numbers rounded to ``digits``."""
    expression = exact_pi(expression)
    rounded = {f: sympy.Float(f, digits) for f in expression.atoms(sympy.Float)}
    return str(sympy.latex(expression.xreplace(rounded)))
