"""A step written once: lhs = side_1 = side_2 = ..., one definition rendered to LaTeX and to text.

An ``Equation`` is a chain of equal sides; a side is a sequence of pieces. A piece is a plain
string (the same in LaTeX and in text: ' + ', ' = '), a symbol written both ways (``Sym``:
``\\vec{v}_{B}`` and 'v(B)'), or a value of the step by reference (``Num``, ``Col``, ``Pt``: a
``Ref`` returned by ``StepBuilder.value``), shown as the step's settled digits give it. Nothing
is formatted until the step is built: the step's checks settle its digits first (one pass over
its values, ``solver.solutions.digits.needed_digits``), then every equation and sentence is
rendered with them. A sentence (``StepBuilder.say``) is pieces too; an equation inside it gives
its text form, so the LaTeX line and the words around it share one definition.

``Ref`` and ``Operand`` are the typed names of values that ``Check`` relations hold: ``-ref`` is
the value subtracted, ``ref[i]`` its component i.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import Protocol

from solver.solutions import latex as tex
from solver.solutions.format import Formatter, latex_unit


@dataclass(frozen=True)
class Operand:
    """A value of a step as a check uses it: ``sign`` times the value, or one of its components."""

    ref: Ref
    sign: float = 1.0
    component: int | None = None

    @property
    def name(self) -> str:
        """The operand as the /solution body writes it: 'key', '-key' or 'key[i]'."""
        index = "" if self.component is None else f"[{self.component}]"
        return ("-" if self.sign < 0 else "") + self.ref.key + index

    def __neg__(self) -> Operand:
        return Operand(self.ref, -self.sign, self.component)


@dataclass(frozen=True)
class Ref:
    """A value registered in a step (``StepBuilder.value``), named by its key in ``values``."""

    key: str

    @property
    def operand(self) -> Operand:
        return Operand(self)

    def __neg__(self) -> Operand:
        return Operand(self, -1.0)

    def __getitem__(self, component: int) -> Operand:
        return Operand(self, 1.0, component)


class Shows(Protocol):
    """What renders a value of a step once its digits are settled (``StepBuilder``)."""

    def num(self, key: str | Ref) -> str: ...
    def numu(self, key: str | Ref) -> str: ...
    def col(self, key: str | Ref, dims: int = 3) -> str: ...
    def colu(self, key: str | Ref, dims: int = 3) -> str: ...
    def point(self, key: str | Ref) -> str: ...
    def entries(self, key: str | Ref, dims: int = 3) -> list[str]: ...
    def txt(self, key: str | Ref) -> str: ...
    def txtn(self, key: str | Ref) -> str: ...
    def scalar(self, key: str | Ref) -> float: ...
    def fmt_of(self, key: str | Ref) -> Formatter: ...


class Token(Protocol):
    """A piece of an equation that is written differently in LaTeX and in text."""

    def latex(self, shows: Shows) -> str: ...
    def text(self, shows: Shows) -> str: ...


Piece = str | Token
Side = Piece | tuple[Piece, ...]


def latex_of(pieces: Sequence[Piece], shows: Shows) -> str:
    return "".join(p if isinstance(p, str) else p.latex(shows) for p in pieces)


def text_of(pieces: Sequence[Piece], shows: Shows) -> str:
    return "".join(p if isinstance(p, str) else p.text(shows) for p in pieces)


@dataclass(frozen=True)
class Sym:
    """A symbol (or any fixed words) written one way in LaTeX and another in text."""

    tex: str
    plain: str

    def latex(self, shows: Shows) -> str:
        return self.tex

    def text(self, shows: Shows) -> str:
        return self.plain


@dataclass(frozen=True)
class Alt:
    """Pieces that differ between the forms: ``tex`` in LaTeX, ``plain`` in text."""

    tex: tuple[Piece, ...]
    plain: tuple[Piece, ...]

    def latex(self, shows: Shows) -> str:
        return latex_of(self.tex, shows)

    def text(self, shows: Shows) -> str:
        return text_of(self.plain, shows)


def latex_only(*pieces: Piece) -> Alt:
    return Alt(pieces, ())


def text_only(*pieces: Piece) -> Alt:
    return Alt((), pieces)


@dataclass(frozen=True)
class Num:
    """A scalar value: '0.5' (with ``unit``: '0.5\\,\\mathrm{m}' and '0.5 m')."""

    ref: Ref
    unit: bool = False

    def latex(self, shows: Shows) -> str:
        return shows.numu(self.ref) if self.unit else shows.num(self.ref)

    def text(self, shows: Shows) -> str:
        return shows.txt(self.ref) if self.unit else shows.txtn(self.ref)


@dataclass(frozen=True)
class Frac:
    """The quotient of two scalar values: '\\frac{a}{b}' in LaTeX, 'a/b' in text, a negative
    denominator in parentheses ('0.32/(-0.18)', not '0.32/-0.18')."""

    numerator: Ref
    denominator: Ref

    def latex(self, shows: Shows) -> str:
        return rf"\frac{{{shows.num(self.numerator)}}}{{{shows.num(self.denominator)}}}"

    def text(self, shows: Shows) -> str:
        below = shows.txtn(self.denominator)
        return f"{shows.txtn(self.numerator)}/{f'({below})' if below.startswith('-') else below}"


@dataclass(frozen=True)
class Signed:
    """A scalar value as a term of a sum: '+ 0.5', '- 0.5'."""

    ref: Ref

    def latex(self, shows: Shows) -> str:
        return tex.signed(shows.num(self.ref))

    def text(self, shows: Shows) -> str:
        return tex.signed(shows.txtn(self.ref))


@dataclass(frozen=True)
class Col:
    """A vector value as a column of ``dims`` entries in LaTeX (the unit after it with ``unit``),
    '(x, y) m/s' in text."""

    ref: Ref
    unit: bool = False
    dims: int = 3

    def latex(self, shows: Shows) -> str:
        if self.unit:
            return shows.colu(self.ref, self.dims)
        return shows.col(self.ref, self.dims)

    def text(self, shows: Shows) -> str:
        return shows.txt(self.ref)


@dataclass(frozen=True)
class Pt:
    """A planar vector as coordinates: '(x, y)' in LaTeX (the unit after it with ``unit``),
    '(x, y) m' in text."""

    ref: Ref
    unit: str = ""

    def latex(self, shows: Shows) -> str:
        return shows.point(self.ref) + latex_unit(self.unit)

    def text(self, shows: Shows) -> str:
        return shows.txt(self.ref)


@dataclass(frozen=True)
class ZCol:
    """The z-component of a planar rotation as the column (0, 0, z) in LaTeX, '(0, 0, z)' in
    text."""

    z: Ref

    def latex(self, shows: Shows) -> str:
        return tex.column(["0", "0", shows.num(self.z)])

    def text(self, shows: Shows) -> str:
        return f"(0, 0, {shows.txtn(self.z)})"


@dataclass(frozen=True)
class Words:
    """Words (with values among them) set as \\text{...} in LaTeX, as they are in text."""

    pieces: tuple[Piece, ...]

    def latex(self, shows: Shows) -> str:
        return r"\text{" + tex.escape_text(text_of(self.pieces, shows)) + "}"

    def text(self, shows: Shows) -> str:
        return text_of(self.pieces, shows)


@dataclass(frozen=True)
class Boxed:
    """A final result, doubly underlined in LaTeX, as it is in text."""

    pieces: tuple[Piece, ...]

    def latex(self, shows: Shows) -> str:
        return tex.boxed_result(latex_of(self.pieces, shows))

    def text(self, shows: Shows) -> str:
        return text_of(self.pieces, shows)


@dataclass(frozen=True)
class ZCross:
    """(0, 0, z) x r of a planar z-component (a value or a symbol) and a vector (a value, or the
    symbols of its two components): the determinant with the unit vectors in its first row in LaTeX,
    '(0, 0, z) cross r' in text."""

    z: Ref | Sym
    r: Ref | tuple[str, str]

    def latex(self, shows: Shows) -> str:
        r = shows.entries(self.r) if isinstance(self.r, Ref) else [*self.r, "0"]
        z = shows.num(self.z) if isinstance(self.z, Ref) else self.z.tex
        return tex.determinant3(["0", "0", z], r)

    def text(self, shows: Shows) -> str:
        r = shows.txtn(self.r) if isinstance(self.r, Ref) else f"({self.r[0]}, {self.r[1]})"
        z = shows.txtn(self.z) if isinstance(self.z, Ref) else self.z.plain
        return f"(0, 0, {z}) cross {r}"


@dataclass(frozen=True)
class Cross:
    """r x F of a planar arm r (a value) and a force F (a value, or its two components written
    as pieces, 'F_{B,x}'): the determinant with the unit vectors in its first row in LaTeX,
    '(rx, ry) cross (Fx, Fy)' in text."""

    r: Ref
    f: Ref | tuple[tuple[Piece, ...], tuple[Piece, ...]]

    def _row(self, shows: Shows, latex: bool) -> list[str]:
        if isinstance(self.f, Ref):
            return shows.entries(self.f) if latex else [shows.txtn(self.f)]
        render = latex_of if latex else text_of
        return [render(e, shows) for e in self.f]

    def latex(self, shows: Shows) -> str:
        return tex.determinant3(shows.entries(self.r), [*self._row(shows, True)[:2], "0"])

    def text(self, shows: Shows) -> str:
        row = self._row(shows, False)
        f = row[0] if len(row) == 1 else f"({row[0]}, {row[1]})"
        return f"{shows.txtn(self.r)} cross {f}"


@dataclass(frozen=True)
class Component:
    """Component i of a vector value, as its column shows it (with ``factor``: in parentheses
    where negative, as a factor of a product)."""

    ref: Ref
    index: int
    factor: bool = False

    def latex(self, shows: Shows) -> str:
        entry = shows.entries(self.ref)[self.index]
        return tex.paren(entry) if self.factor else entry

    def text(self, shows: Shows) -> str:
        return self.latex(shows)


@dataclass(frozen=True)
class Sum:
    """Terms of a sum, each starting with its sign ('+ ', '- ' or a ``Signed`` value): '+ a - b'
    is written 'a - b', '- a + b' is '-a + b'; an empty term is left out; no terms is '0'."""

    terms: tuple[tuple[Piece, ...], ...]

    @staticmethod
    def _lead(written: str) -> str:
        if written.startswith("+ "):
            return written[2:]
        if written.startswith("- "):
            return "-" + written[2:]
        return written or "0"

    def latex(self, shows: Shows) -> str:
        return self._lead(" ".join(latex_of(t, shows) for t in self.terms if t))

    def text(self, shows: Shows) -> str:
        return self._lead(" ".join(text_of(t, shows) for t in self.terms if t))


@dataclass(frozen=True)
class ColumnOf:
    """A column of entries, each a row of pieces ('-2\\, r_y'): a column vector in LaTeX,
    '(a, b, c)' in text."""

    entries: tuple[tuple[Piece, ...], ...]

    def latex(self, shows: Shows) -> str:
        return tex.column([latex_of(e, shows) for e in self.entries])

    def text(self, shows: Shows) -> str:
        return "(" + ", ".join(text_of(e, shows) for e in self.entries) + ")"


@dataclass(frozen=True)
class Paren:
    """A scalar value as a factor: in parentheses where negative or with a power of ten
    ('2 \\cdot (-1.5)', '2 x (-1.5)')."""

    ref: Ref

    def latex(self, shows: Shows) -> str:
        return tex.paren(shows.num(self.ref))

    def text(self, shows: Shows) -> str:
        return tex.paren(shows.txtn(self.ref))


@dataclass(frozen=True)
class Det2:
    """A 2x2 determinant of scalar values written out: '\\begin{vmatrix} a & b \\\\ c & d
    \\end{vmatrix}' in LaTeX, '|a b; c d|' in text."""

    rows: tuple[tuple[Ref, Ref], tuple[Ref, Ref]]

    def latex(self, shows: Shows) -> str:
        return tex.determinant2([[shows.num(x) for x in row] for row in self.rows])

    def text(self, shows: Shows) -> str:
        return "|" + "; ".join(" ".join(shows.txtn(x) for x in row) for row in self.rows) + "|"


TIMES = Sym(r" \times ", " cross ")


def _side(side: Side) -> tuple[Piece, ...]:
    return side if isinstance(side, tuple) else (side,)


@dataclass(frozen=True)
class Equation:
    """side_0 = side_1 = ...: one LaTeX line (aligned at its start), broken before the sides in
    ``breaks`` (the new line starts '\\phantom{side_0} = ', or '\\phantom{phantom} = '), and the
    same chain in text, without the sides that have no text form (``latex_only``)."""

    sides: tuple[tuple[Piece, ...], ...]
    breaks: tuple[int, ...] = ()
    phantom: str | None = None

    @staticmethod
    def of(*sides: Side, breaks: tuple[int, ...] = (), phantom: str | None = None) -> Equation:
        return Equation(tuple(_side(s) for s in sides), breaks, phantom)

    def lines(self, shows: Shows) -> list[str]:
        """The LaTeX lines, each starting with the alignment mark '&'."""
        first = latex_of(self.sides[0], shows)
        indent = first if self.phantom is None else self.phantom
        lines = ["&" + first]
        for i, side in enumerate(self.sides[1:], start=1):
            if i in self.breaks:
                lines.append(rf"&\phantom{{{indent}}}")
            lines[-1] += " = " + latex_of(side, shows)
        return lines

    def text(self, shows: Shows) -> str:
        sides = (text_of(side, shows) for side in self.sides)
        return " = ".join(side for side in sides if side)

    def latex(self, shows: Shows) -> str:
        """The chain on one line, without the alignment mark (inside other LaTeX)."""
        return " = ".join(latex_of(side, shows) for side in self.sides)


def joined(separator: Piece, groups: Sequence[Sequence[Piece]]) -> tuple[Piece, ...]:
    """The groups of pieces one after the other with ``separator`` between them ('; ')."""
    out: list[Piece] = []
    for i, group in enumerate(groups):
        if i:
            out.append(separator)
        out.extend(group)
    return tuple(out)
