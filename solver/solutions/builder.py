"""Assembling one step: its values (with checks), its LaTeX lines and its plain text.

``StepBuilder`` keeps the numbers and their display together: a number enters a step once, by
``value`` (full precision, unit, source; a typed ``Ref`` back), and every place the step shows it
is formatted from that entry, so the LaTeX, the text and ``values`` always show the same digits.
Equations and sentences (``solver.solutions.equation``) are rendered when the step is built,
after its checks have settled the digits in one pass; a number formatted before that (while the
step is still written) is an error, since its digits would not be settled. ``present_solution``
writes a 2x2 linear system and its solution the way the seeds do (with references, its own pieces
``Linear``, ``Term`` and ``QuotientOf``): directly where one equation has a single unknown, by
Cramer's rule with the determinants written out otherwise.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from solver.kinematics.rigid import Column, cramer_numerators, determinant_2x2
from solver.solutions import latex as tex
from solver.solutions.digits import needed_digits
from solver.solutions.equation import (
    Boxed,
    Det2,
    Equation,
    Frac,
    Num,
    Operand,
    Paren,
    Piece,
    Ref,
    Shows,
    Sym,
    latex_of,
    text_of,
)
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
    """Collects one step's values, checks, LaTeX lines and text sentences.

    ``written=False``: the step's structure only (its kind, title, values with their sources,
    and checks), for a reader of that alone (the polygons' order, ``solutions.polygons``): no
    value's display, no digits settled, no LaTeX or text written.
    """

    def __init__(self, fmt: Formatter, kind: str, title: str, written: bool = True) -> None:
        self.fmt = fmt
        self.kind = kind
        self.title = title
        self.written = written
        self.digits: dict[str, int] = {}
        self.values: dict[str, Value] = {}
        self.checks: list[Check] = []
        self.lines: list[str | Equation | tuple[Piece, ...]] = []
        self.sentences: list[str | tuple[Piece, ...]] = []
        self.references: dict[str, float] = {}
        self.settled = False  # the digits are settled (``build``): numbers may be formatted

    # --- values ---------------------------------------------------------------------------------

    def _shown(self, key: str | Ref) -> str:
        """The key of a value about to be formatted (only once ``build`` settled the digits)."""
        if not self.settled:
            raise RuntimeError(
                f"step {self.title!r}: a number formatted before its digits are settled; "
                "write it with a reference (``Ref``) and let ``build`` format it"
            )
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
        display = self._digits_of(key).display(number, unit, reference) if self.written else ""
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
        """Settle the step's digits in one pass over its checks (``needed_digits``)."""
        self.digits = needed_digits(self.values, self.references, self.checks, self.fmt)
        for key in self.digits:
            v = self.values[key]
            display = self._digits_of(key).display(v.value, v.unit, self.references[key])
            self.values[key] = Value(v.value, v.unit, display, v.source)
        self.settled = True

    def build(self) -> Step:
        if not self.written:
            return Step(self.kind, self.title, "", "", dict(self.values), tuple(self.checks))
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
class Linear:
    """c1 u1 + c2 u2 of coefficient values and unknowns' symbols, written with the most digits any
    coefficient is shown with, dropping the terms whose coefficient displays as 0 against
    ``reference`` (at least '0')."""

    coefficients: tuple[Ref, ...]
    symbols: tuple[Sym, ...]
    reference: float

    def _terms(self, shows: Shows, latex: bool) -> str:
        fmt = max((shows.fmt_of(c) for c in self.coefficients), key=lambda f: f.digits)
        terms = [
            (shows.scalar(c), s.tex if latex else s.plain)
            for c, s in zip(self.coefficients, self.symbols, strict=True)
        ]
        return _linear(fmt, None, terms, self.reference, latex)

    def latex(self, shows: Shows) -> str:
        return self._terms(shows, latex=True)

    def text(self, shows: Shows) -> str:
        return self._terms(shows, latex=False)


@dataclass(frozen=True)
class Term:
    """c u as the first term of a sum: 'u', '-u', '0.5\\,u' ('0.5 u' in text)."""

    coefficient: Ref
    symbol: Sym

    def latex(self, shows: Shows) -> str:
        c = self.coefficient
        return term(shows.fmt_of(c), shows.scalar(c), self.symbol.tex, True, 0.0)

    def text(self, shows: Shows) -> str:
        c = self.coefficient
        return term_text(shows.fmt_of(c), shows.scalar(c), self.symbol.plain, True, 0.0)


@dataclass(frozen=True)
class QuotientOf:
    """' n/d =' between an unknown and its value: the fraction, or nothing where d is shown as
    1 (the value is then n itself). LaTeX only."""

    numerator: Ref
    denominator: Ref

    def latex(self, shows: Shows) -> str:
        if shows.num(self.denominator) == "1":
            return ""
        return " " + Frac(self.numerator, self.denominator).latex(shows) + " ="

    def text(self, shows: Shows) -> str:
        return ""


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

    @property
    def symbol(self) -> Sym:
        return Sym(self.latex, self.text)


def _sense(fmt: Formatter, unknown: Unknown) -> str:
    if unknown.unit in ("rad/s", "rad/s^2") and not fmt.is_zero(unknown.value, unknown.unit):
        return " (counter-clockwise)" if unknown.value > 0 else " (clockwise)"
    return ""


Key = str | Ref


def _ref(key: Key) -> Ref:
    return key if isinstance(key, Ref) else Ref(key)


def present_solution(
    b: StepBuilder,
    unknowns: Sequence[Unknown],
    coefficients: Sequence[Sequence[Key]],
    rhs: Sequence[Key],
    prefix: str,
    cramer: bool = False,
) -> None:
    """Write and solve  c11 u1 + c12 u2 = b1,  c21 u1 + c22 u2 = b2  (values already registered).

    Registers the unknowns with the solver's values, the equations as ``linear`` checks, and the
    solution: directly where a row has one unknown, else (or always with ``cramer``) by Cramer's
    rule with the determinants written out (``det2``/``quotient`` checks; their values from
    ``kinematics.rigid``, the solver's one 2x2 solve). Written with references: the digits
    settle when the step is built.
    """
    for u in unknowns:
        b.put(u.key, u.value, u.unit, u.source)
    c = [[_ref(k) for k in row] for row in coefficients]
    rs = [_ref(k) for k in rhs]
    scales = [_equation(b, unknowns, c[i], rs[i], i) for i in range(len(unknowns))]
    if len(unknowns) == 1:
        b.check("quotient", unknowns[0].key, rs[0], c[0][0])
        _result(b, unknowns[0], QuotientOf(rs[0], c[0][0]))
        return
    single = [
        [j for j in range(2) if not b.fmt.is_zero(b.scalar(c[i][j]), "", scales[i])]
        for i in range(2)
    ]
    if cramer:
        single = [[0, 1], [0, 1]]
    if all(len(single[i]) == 1 for i in range(2)) and single[0][0] != single[1][0]:
        for i in range(2):  # each equation has its own single unknown
            j = single[i][0]
            b.check("quotient", unknowns[j].key, rs[i], c[i][j])
            _result(b, unknowns[j], QuotientOf(rs[i], c[i][j]))
        return
    direct = next((i for i in range(2) if len(single[i]) == 1), None)
    if direct is not None:
        _substitution(b, unknowns, c, rs, prefix, (direct, single[direct][0]), scales)
        return
    _cramer(b, unknowns, c, rs, prefix)


def _equation(
    b: StepBuilder, unknowns: Sequence[Unknown], row: Sequence[Ref], rhs: Ref, i: int
) -> float:
    """Equation i + 1, c_i1 u1 + c_i2 u2 = b_i, written with its ``linear`` check; returns the
    size of its largest coefficient (what a coefficient displaying as 0 is measured against)."""
    scale = max(abs(b.scalar(c)) for c in row)
    left = Linear(tuple(row), tuple(u.symbol for u in unknowns), scale)
    b.line("&", left, " = ", Num(rhs))
    b.say(f"Equation {i + 1}: ", left, " = ", Num(rhs), ".")
    operands: list[Ref | str] = []
    for coefficient, u in zip(row, unknowns, strict=True):
        operands += [coefficient, u.key]
    b.check("linear", rhs, *operands)
    return scale


def _substitution(
    b: StepBuilder,
    unknowns: Sequence[Unknown],
    c: Sequence[Sequence[Ref]],
    rhs: Sequence[Ref],
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
    _result(b, u, QuotientOf(rhs[direct], c[direct][j]))
    c_w = c[other_row][other]
    if b.fmt.is_zero(b.scalar(c_w), "", scales[other_row]):
        b.say(f"{w.text} does not appear in the equations: it is not determined by them.")
        return
    known = b.scalar(c[other_row][j]) * u.value
    rest = b.value(
        f"{prefix}rest",
        b.scalar(rhs[other_row]) - known,
        "",
        reference=abs(b.scalar(rhs[other_row])) + abs(known),
    )
    b.check("quotient", w.key, rest, c_w)
    left = Term(c_w, w.symbol)
    b.line(
        "&",
        left,
        " = ",
        Num(rhs[other_row]),
        " - ",
        Paren(c[other_row][j]),
        r" \cdot ",
        Paren(Ref(u.key)),
        " = ",
        Num(rest),
    )
    b.say(f"Substituting into equation {other_row + 1}: ", left, " = ", Num(rest), ".")
    _result(b, w, QuotientOf(rest, c_w))


def _cramer(
    b: StepBuilder,
    unknowns: Sequence[Unknown],
    c: Sequence[Sequence[Ref]],
    rhs: Sequence[Ref],
    prefix: str,
) -> None:
    """Cramer's rule u_j = D_j / D, D = det c and D_j = det c with column j replaced by b (the
    solver's ``determinant_2x2`` and ``cramer_numerators``), each with its checks, written
    out: D, then D_j and u_j = D_j / D for each unknown."""
    rows = ((c[0][0], c[0][1]), (c[1][0], c[1][1]))
    values = [[b.scalar(x) for x in row] for row in rows]
    row1, row2 = (values[0][0], values[0][1]), (values[1][0], values[1][1])
    sides = (b.scalar(rhs[0]), b.scalar(rhs[1]))
    det = _det2(b, f"{prefix}D", rows, determinant_2x2(row1, row2))
    b.line("&D = ", Det2(rows), " = ", Num(det))
    b.say("By Cramer's rule, the determinant of the coefficients is D = ", Num(det), ".")
    for j, numerator in enumerate(cramer_numerators(row1, row2, sides)):
        column: Matrix2 = (
            ((rhs[0], c[0][1]), (rhs[1], c[1][1]))
            if j == 0
            else ((c[0][0], rhs[0]), (c[1][0], rhs[1]))
        )
        dj = _det2(b, f"{prefix}D{j + 1}", column, numerator)
        b.check("quotient", unknowns[j].key, dj, det)
        b.line(f"&D_{j + 1} = ", Det2(column), " = ", Num(dj))
        b.say(f"D{j + 1}, with column {j + 1} replaced by the right-hand sides, is ", Num(dj), ".")
        _result(b, unknowns[j], rf" \frac{{D_{j + 1}}}{{D}} = ", Frac(dj, det), " =")


Matrix2 = tuple[tuple[Ref, Ref], tuple[Ref, Ref]]


def _det2(b: StepBuilder, key: str, m: Matrix2, value: Column) -> Ref:
    """D = m11 m22 - m12 m21 (``value``) with its ``det2`` check; its reference is the size of
    the two products (a value or the size it was computed from, whichever is larger)."""

    def size(k: Ref) -> float:
        return max(abs(b.scalar(k)), b.references[k.key])

    (m11, m12), (m21, m22) = m
    reference = size(m11) * size(m22) + size(m12) * size(m21)
    det = b.value(key, float(value), "", reference=reference)
    b.check("det2", det, m11, m12, m21, m22)
    return det


def _result(b: StepBuilder, u: Unknown, *middle: Piece) -> None:
    """u = [middle] boxed value, and 'So u = value (sense): meaning.'"""
    value = Num(Ref(u.key), unit=True)
    b.line(f"&{u.latex} =", *middle, " ", Boxed((value,)))
    b.say(
        f"So {u.text} = ",
        value,
        _sense(b.fmt, u) + (f": {u.meaning}." if u.meaning else "."),
    )
