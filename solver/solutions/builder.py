"""Assembling one step: its values (with checks), its LaTeX lines and its plain text.

``StepBuilder`` keeps the numbers and their display together: a number enters a step once, by
``value`` (full precision, unit, source; a typed ``Ref`` back), and every place the step shows it
is formatted from that entry, so the LaTeX, the text and ``values`` always show the same digits.
Equations and sentences (``solver.solutions.equation``) are rendered when the step is built,
after its checks have settled the digits in one pass. A step that formats numbers while it is
written (``put`` and string keys, ``num``, ``txt``... called before ``build``) gets its digits
from a ``DigitPlan`` instead: its part of the solution is built a second time. ``present_solution``
writes a 2x2 linear system and its solution the way the seeds do: directly where one equation has
a single unknown, by Cramer's rule with the determinants written out otherwise.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from solver.solutions import latex as tex
from solver.solutions.digits import DigitPlan, needed_digits
from solver.solutions.equation import Equation, Operand, Piece, Ref, latex_of, text_of
from solver.solutions.format import Formatter, latex_unit
from solver.solutions.model import Check, Number, Relation, Step, Value

Source = tuple[str | int, ...]


def _number(value: float | Sequence[float] | np.ndarray) -> Number:
    if isinstance(value, np.ndarray):
        return float(value) if value.ndim == 0 else tuple(float(x) for x in value)
    if isinstance(value, int | float | np.floating):
        return float(value)
    return tuple(float(x) for x in value)


class StepBuilder:
    """Collects one step's values, checks, LaTeX lines and text sentences."""

    def __init__(
        self, fmt: Formatter, kind: str, title: str, plan: DigitPlan | None = None
    ) -> None:
        self.fmt = fmt
        self.kind = kind
        self.title = title
        self.plan = plan
        self.plan_key = plan.key(kind, title) if plan is not None else None
        self.digits = plan.digits(self.plan_key) if plan and self.plan_key else {}
        self.values: dict[str, Value] = {}
        self.checks: list[Check] = []
        self.lines: list[str | Equation | tuple[Piece, ...]] = []
        self.sentences: list[str | tuple[Piece, ...]] = []
        self.references: dict[str, float] = {}
        # True once a number was formatted before ``build``: the digits then come from ``plan``
        self.eager = False
        self.settled = False

    # --- values ---------------------------------------------------------------------------------

    def _shown(self, key: str | Ref) -> str:
        """The key of a value about to be formatted (noting a format before ``build``)."""
        if not self.settled:
            self.eager = True
        return key.key if isinstance(key, Ref) else key

    def fmt_of(self, key: str | Ref) -> Formatter:
        """The formatter of one value: more digits where the step's arithmetic needs them."""
        return self._digits_of(self._shown(key))

    def _digits_of(self, key: str) -> Formatter:
        digits = self.digits.get(key, self.fmt.digits)
        if digits <= self.fmt.digits:
            return self.fmt
        return self.fmt.with_digits(digits)

    def put(
        self,
        key: str,
        value: float | Sequence[float] | np.ndarray,
        unit: str,
        source: Source | None = None,
        reference: float = 0.0,
    ) -> str:
        """Register a value and return its key.

        ``reference`` is the size of the terms the value was computed from: a result smaller
        than rounding noise next to it (a dot product of two perpendicular vectors) shows as 0.
        """
        number = _number(value)
        if not all(math.isfinite(x) for x in (number if isinstance(number, tuple) else (number,))):
            raise ValueError(f"non-finite value {key} = {number}")
        self.references[key] = reference
        display = self._digits_of(key).display(number, unit, reference)
        self.values[key] = Value(number, unit, display, source)
        return key

    def value(
        self,
        key: str,
        value: float | Sequence[float] | np.ndarray,
        unit: str,
        source: Source | None = None,
        reference: float = 0.0,
    ) -> Ref:
        """Register a value (as ``put``) and return a typed reference to it."""
        return Ref(self.put(key, value, unit, source, reference))

    def scalar(self, key: str | Ref) -> float:
        value = self.values[key.key if isinstance(key, Ref) else key].value
        assert not isinstance(value, tuple), key
        return value

    def vector(self, key: str | Ref) -> tuple[float, ...]:
        value = self.values[key.key if isinstance(key, Ref) else key].value
        assert isinstance(value, tuple), key
        return value

    def num(self, key: str | Ref) -> str:
        """The scalar value as a LaTeX number."""
        fmt = self.fmt_of(key)
        key = self._shown(key)
        return fmt.latex(self.scalar(key), self.values[key].unit, self.references[key])

    def numu(self, key: str | Ref) -> str:
        """The scalar value as a LaTeX number with its unit."""
        key = self._shown(key)
        return self.num(key) + latex_unit(self.values[key].unit)

    def entries(self, key: str | Ref, dims: int = 3) -> list[str]:
        """The vector's components as LaTeX numbers (planar vectors get z = 0 when dims = 3)."""
        key = self._shown(key)
        vector = self.vector(key)
        clean = self.fmt.clean_vector(vector, self.values[key].unit)
        out = [self.fmt_of(key).latex(x) for x in clean]
        return out + ["0"] * (dims - len(out))

    def point(self, key: str | Ref) -> str:
        """A planar vector as coordinates '(x, y)' in LaTeX."""
        return "(" + ", ".join(self.entries(key, 2)) + ")"

    def col(self, key: str | Ref, dims: int = 3) -> str:
        return tex.column(self.entries(key, dims))

    def colu(self, key: str | Ref, dims: int = 3) -> str:
        key = self._shown(key)
        return self.col(key, dims) + latex_unit(self.values[key].unit)

    def txt(self, key: str | Ref) -> str:
        """The value as plain text with its unit."""
        return self.values[self._shown(key)].display

    def txtn(self, key: str | Ref) -> str:
        """The value as plain text without its unit."""
        key = self._shown(key)
        value = self.values[key]
        fmt = self.fmt_of(key)
        if isinstance(value.value, tuple):
            return fmt.text_vector(value.value)
        return fmt.text(value.value, value.unit, self.references[key])

    def is_zero(self, key: str | Ref) -> bool:
        """True when the value displays as zero (every component, for a vector)."""
        value = self.values[key.key if isinstance(key, Ref) else key]
        if isinstance(value.value, tuple):
            return all(x == 0.0 for x in self.fmt.clean_vector(value.value, value.unit)) or all(
                self.fmt.is_zero(x, value.unit) for x in value.value
            )
        return self.fmt.is_zero(
            value.value, value.unit, self.references[key.key if isinstance(key, Ref) else key]
        )

    # --- checks, lines, text --------------------------------------------------------------------

    def operand(self, name: str | Ref | Operand) -> Operand:
        """A check's operand: typed, or written 'key', '-key' or 'key[i]' (a value of the step)."""
        if isinstance(name, Ref):
            operand = name.operand
        elif isinstance(name, Operand):
            operand = name
        else:
            sign = -1.0 if name.startswith("-") else 1.0
            key = name.lstrip("-")
            index = None
            if key.endswith("]") and key.rsplit("[", 1)[0] in self.values:
                key, rest = key.rsplit("[", 1)
                index = int(rest[:-1])
            operand = Operand(Ref(key), sign, index)
        assert operand.ref.key in self.values, f"check of {self.kind}: unknown value {name}"
        return operand

    def check(
        self,
        relation: Relation,
        result: str | Ref | Operand,
        *operands: str | Ref | Operand,
        factor: float = 1.0,
    ) -> None:
        self.checks.append(
            Check(
                relation,
                self.operand(result),
                tuple(self.operand(o) for o in operands),
                factor,
            )
        )

    def line(self, *latex: Piece) -> None:
        """One LaTeX line (starting '&' where aligned): an equation (its lines, broken where it
        says), or pieces in a row (an equation among them inline)."""
        if len(latex) == 1 and isinstance(latex[0], str | Equation):
            self.lines.append(latex[0])
        else:
            self.lines.append(latex)

    def say(self, *text: Piece) -> None:
        """One sentence: words, values and equations (in their text form)."""
        self.sentences.append(text[0] if len(text) == 1 and isinstance(text[0], str) else text)

    def settle(self) -> None:
        """Settle the digits of a step written with references (one pass over its checks), or
        record what a step formatted while written needs in ``plan``."""
        found = needed_digits(self.values, self.references, self.checks, self.fmt)
        if self.eager:
            if self.plan is not None and self.plan_key is not None and self.plan.recording:
                self.plan.record(self.plan_key, found)
        else:
            self.digits = found
            for key in found:
                v = self.values[key]
                display = self._digits_of(key).display(v.value, v.unit, self.references[key])
                self.values[key] = Value(v.value, v.unit, display, v.source)
        self.settled = True

    def build(self) -> Step:
        if self.eager and (self.plan is None or not self.plan.recording):
            self.settled = True  # the digits are the plan's (or the solution's, without one)
        else:
            self.settle()
        lines: list[str] = []
        for line in self.lines:
            if isinstance(line, Equation):
                lines += line.lines(self)
            else:
                lines.append(line if isinstance(line, str) else latex_of(line, self))
        sentences = [s if isinstance(s, str) else text_of(s, self) for s in self.sentences]
        return Step(
            self.kind,
            self.title,
            tex.aligned(lines) if lines else "",
            " ".join(sentences),
            dict(self.values),
            tuple(self.checks),
        )


# --- linear expressions and 2x2 systems ------------------------------------------------------


def _term(number: str, symbol: str, first: bool, separator: str) -> str:
    """A term of a sum, c u with the number c as written: 'u', '- u', '+ 0.5 u'."""
    if number == "1":
        body = symbol
    elif number == "-1":
        body = "-" + symbol
    else:
        body = number + separator + symbol
    return tex.signed(body, first)


def term(fmt: Formatter, coefficient: float, symbol: str, first: bool, reference: float) -> str:
    """'+ 0.5\\,\\omega' (LaTeX); '' when the coefficient displays as 0."""
    if fmt.is_zero(coefficient, "", reference):
        return ""
    return _term(fmt.latex(coefficient), symbol, first, r"\,")


def term_text(
    fmt: Formatter, coefficient: float, symbol: str, first: bool, reference: float
) -> str:
    """'+ 0.5 omega' (plain text); '' when the coefficient displays as 0."""
    if fmt.is_zero(coefficient, "", reference):
        return ""
    return _term(fmt.text(coefficient), symbol, first, " ")


def _linear(
    fmt: Formatter,
    constant: float | None,
    terms: Sequence[tuple[float, str]],
    reference: float,
    latex: bool,
) -> str:
    """constant + c1 u1 + c2 u2, dropping zero parts (at least '0')."""
    number, write_term = (fmt.latex, term) if latex else (fmt.text, term_text)
    parts: list[str] = []
    if constant is not None and not fmt.is_zero(constant, "", reference):
        parts.append(number(constant))
    for coefficient, symbol in terms:
        piece = write_term(fmt, coefficient, symbol, not parts, reference)
        if piece:
            parts.append(piece)
    return " ".join(parts) if parts else "0"


def linear_latex(
    fmt: Formatter, constant: float | None, terms: Sequence[tuple[float, str]], reference: float
) -> str:
    """constant + c1 u1 + c2 u2 in LaTeX, dropping zero parts (at least '0')."""
    return _linear(fmt, constant, terms, reference, latex=True)


def linear_text(
    fmt: Formatter, constant: float | None, terms: Sequence[tuple[float, str]], reference: float
) -> str:
    """constant + c1 u1 + c2 u2 in plain text, dropping zero parts (at least '0')."""
    return _linear(fmt, constant, terms, reference, latex=False)


@dataclass(frozen=True)
class Unknown:
    """An unknown of a linear system: its value key, symbols, unit and the solver's value."""

    key: str
    latex: str
    text: str
    unit: str
    value: float
    source: Source | None = None
    meaning: str = ""


def _sense(fmt: Formatter, unknown: Unknown) -> str:
    if unknown.unit in ("rad/s", "rad/s^2") and not fmt.is_zero(unknown.value, unknown.unit):
        return " (counter-clockwise)" if unknown.value > 0 else " (clockwise)"
    return ""


def present_solution(
    b: StepBuilder,
    unknowns: Sequence[Unknown],
    coefficients: Sequence[Sequence[str]],
    rhs: Sequence[str],
    prefix: str,
    cramer: bool = False,
) -> None:
    """Write and solve  c11 u1 + c12 u2 = b1,  c21 u1 + c22 u2 = b2  (values already registered).

    Registers the unknowns with the solver's values, the equations as ``linear`` checks, and the
    solution: directly where a row has one unknown, else (or always with ``cramer``) by Cramer's
    rule with the determinants written out (``det2``/``quotient`` checks).
    """
    for u in unknowns:
        b.put(u.key, u.value, u.unit, u.source)
    scales = [_equation(b, unknowns, coefficients[i], rhs[i], i) for i in range(len(unknowns))]
    if len(unknowns) == 1:
        b.check("quotient", unknowns[0].key, rhs[0], coefficients[0][0])
        _result(b, unknowns[0], _fraction(b, rhs[0], coefficients[0][0]))
        return
    single = [
        [j for j in range(2) if not b.fmt.is_zero(b.scalar(coefficients[i][j]), "", scales[i])]
        for i in range(2)
    ]
    if cramer:
        single = [[0, 1], [0, 1]]
    if all(len(single[i]) == 1 for i in range(2)) and single[0][0] != single[1][0]:
        for i in range(2):  # each equation has its own single unknown
            j = single[i][0]
            b.check("quotient", unknowns[j].key, rhs[i], coefficients[i][j])
            _result(b, unknowns[j], _fraction(b, rhs[i], coefficients[i][j]))
        return
    direct = next((i for i in range(2) if len(single[i]) == 1), None)
    if direct is not None:
        _substitution(b, unknowns, coefficients, rhs, prefix, (direct, single[direct][0]), scales)
        return
    determinants = _cramer_values(b, unknowns, coefficients, rhs, prefix)
    _write_cramer(b, unknowns, determinants)


def _equation(
    b: StepBuilder, unknowns: Sequence[Unknown], row: Sequence[str], rhs: str, i: int
) -> float:
    """Equation i + 1, c_i1 u1 + c_i2 u2 = b_i, written with its ``linear`` check; returns the
    size of its largest coefficient (what a coefficient displaying as 0 is measured against)."""
    n = len(unknowns)
    scale = max(abs(b.scalar(c)) for c in row)
    terms = [(b.scalar(row[j]), unknowns[j].latex) for j in range(n)]
    terms_text = [(b.scalar(row[j]), unknowns[j].text) for j in range(n)]
    fmt = max((b.fmt_of(c) for c in row), key=lambda f: f.digits)
    b.line("&" + linear_latex(fmt, None, terms, scale) + " = " + b.num(rhs))
    b.say(f"Equation {i + 1}: {linear_text(fmt, None, terms_text, scale)} = {b.txtn(rhs)}.")
    operands: list[str] = []
    for j in range(n):
        operands += [row[j], unknowns[j].key]
    b.check("linear", rhs, *operands)
    return scale


def _substitution(
    b: StepBuilder,
    unknowns: Sequence[Unknown],
    c: Sequence[Sequence[str]],
    rhs: Sequence[str],
    prefix: str,
    pivot: tuple[int, int],
    scales: Sequence[float],
) -> None:
    """Row d of ``pivot`` = (d, j) has the single unknown u = b_d / c_dj; the other row o then
    gives w = (b_o - c_oj u) / c_ow, the rest b_o - c_oj u written out."""
    direct, j = pivot
    other_row, other = 1 - direct, 1 - j
    u, w = unknowns[j], unknowns[other]
    b.check("quotient", u.key, rhs[direct], c[direct][j])
    b.say(f"Equation {direct + 1} has the single unknown {u.text}.")
    _result(b, u, _fraction(b, rhs[direct], c[direct][j]))
    c_key = c[other_row][other]
    c_other = b.scalar(c_key)
    if b.fmt.is_zero(c_other, "", scales[other_row]):
        b.say(f"{w.text} does not appear in the equations: it is not determined by them.")
        return
    known = b.scalar(c[other_row][j]) * u.value
    rest = b.put(
        f"{prefix}rest",
        b.scalar(rhs[other_row]) - known,
        "",
        reference=abs(b.scalar(rhs[other_row])) + abs(known),
    )
    b.check("quotient", w.key, rest, c_key)
    b.line(
        rf"&{term(b.fmt_of(c_key), c_other, w.latex, True, 0.0)} = {b.num(rhs[other_row])} - "
        rf"{tex.paren(b.num(c[other_row][j]))} \cdot {tex.paren(b.num(u.key))} = {b.num(rest)}"
    )
    b.say(
        f"Substituting into equation {other_row + 1}: "
        f"{term_text(b.fmt_of(c_key), c_other, w.text, True, 0.0)} = {b.txtn(rest)}."
    )
    _result(b, w, _fraction(b, rest, c_key))


Matrix2 = tuple[tuple[str, str], tuple[str, str]]


def _det2(b: StepBuilder, key: str, m: Matrix2) -> str:
    """D = m11 m22 - m12 m21 with its ``det2`` check; its reference is the size of the two
    products (a value or the size it was computed from, whichever is larger)."""

    def size(k: str) -> float:
        return max(abs(b.scalar(k)), b.references[k])

    (m11, m12), (m21, m22) = m
    value = b.scalar(m11) * b.scalar(m22) - b.scalar(m12) * b.scalar(m21)
    reference = size(m11) * size(m22) + size(m12) * size(m21)
    b.put(key, value, "", reference=reference)
    b.check("det2", key, m11, m12, m21, m22)
    return key


def _cramer_values(
    b: StepBuilder,
    unknowns: Sequence[Unknown],
    c: Sequence[Sequence[str]],
    rhs: Sequence[str],
    prefix: str,
) -> list[tuple[str, Matrix2]]:
    """Cramer's rule u_j = D_j / D, D = det c and D_j = det c with column j replaced by b:
    [(D, c), (D1, its matrix), (D2, its matrix)], each with its checks."""
    matrix: Matrix2 = ((c[0][0], c[0][1]), (c[1][0], c[1][1]))
    out = [(_det2(b, f"{prefix}D", matrix), matrix)]
    for j in range(2):
        column: Matrix2 = (
            ((rhs[0], c[0][1]), (rhs[1], c[1][1]))
            if j == 0
            else ((c[0][0], rhs[0]), (c[1][0], rhs[1]))
        )
        out.append((_det2(b, f"{prefix}D{j + 1}", column), column))
        b.check("quotient", unknowns[j].key, out[-1][0], out[0][0])
    return out


def _write_cramer(
    b: StepBuilder, unknowns: Sequence[Unknown], determinants: list[tuple[str, Matrix2]]
) -> None:
    """Write D, then D_j and u_j = D_j / D for each unknown (``_cramer_values``)."""

    def written(m: Matrix2) -> str:
        return tex.determinant2([[b.num(m[i][k]) for k in range(2)] for i in range(2)])

    (det, matrix), *columns = determinants
    b.line(rf"&D = {written(matrix)} = {b.num(det)}")
    b.say(f"By Cramer's rule, the determinant of the coefficients is D = {b.txtn(det)}.")
    for j, (dj, column) in enumerate(columns):
        b.line(rf"&D_{j + 1} = {written(column)} = {b.num(dj)}")
        b.say(f"D{j + 1}, with column {j + 1} replaced by the right-hand sides, is {b.txtn(dj)}.")
        _result(b, unknowns[j], rf"\frac{{D_{j + 1}}}{{D}} = \frac{{{b.num(dj)}}}{{{b.num(det)}}}")


def _fraction(b: StepBuilder, numerator: str, denominator: str) -> str:
    """The fraction n/d in LaTeX, or '' when d displays as 1 (the result is then n itself)."""
    if b.num(denominator) == "1":
        return ""
    return rf"\frac{{{b.num(numerator)}}}{{{b.num(denominator)}}}"


def _result(b: StepBuilder, u: Unknown, fraction: str) -> None:
    middle = f" {fraction} =" if fraction else ""
    b.line(rf"&{u.latex} ={middle} {tex.boxed_result(b.numu(u.key))}")
    b.say(
        f"So {u.text} = {b.txt(u.key)}{_sense(b.fmt, u)}"
        + (f": {u.meaning}." if u.meaning else ".")
    )
