"""Time laws: the expressions in ``t`` that drive a crank angle or a moving point's arc length.

A scene may give a driver's motion as a string such as ``6*pi*t^2``. This module turns that
untrusted text into a sympy expression with its exact first and second derivatives, and into fast
numpy closures for value, rate and rate_dot. Nothing is ever evaluated as Python: a character-level
scanner rejects bad characters, names and shapes first (so hostile input costs microseconds), then
Python's ``ast`` parses the text and a strict whitelist walk builds the sympy objects directly.
Every rejection is an ``InvalidExpression`` pointing at the offending character of the original.
"""

from __future__ import annotations

import ast
import functools
import math
import re
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from typing import Any, NoReturn, overload

import numpy as np
import numpy.typing as npt
import sympy

from solver.errors import InvalidExpression, LimitExceeded
from solver.model.intervals import Range, RangeFn, enclosure, ranges

MAX_LENGTH = 500  # characters of the law text
MAX_DEPTH = 50  # nesting of parentheses and of the syntax tree
MAX_LITERAL = 1e12  # magnitude of a number written in the law
MAX_EXPONENT = 100  # magnitude of a constant exponent
MAX_CONSTANT_DIGITS = 100  # a t-free part or constant power may not exceed 1e100
# Functions and powers of t nested in one another (sin(exp(t)) is 2, t^t^t is 2): each level
# multiplies the size of the derivatives (chain rule); 51 levels of t^t^... took 53 s to
# differentiate, 6 levels of any kind at most about 1 s in a 500-character law.
MAX_COMPOSITION = 6

T = sympy.Symbol("t")
CONSTANTS: dict[str, sympy.Expr] = {"t": T, "pi": sympy.pi, "e": sympy.E}
FUNCTIONS: dict[str, Any] = {
    "sin": sympy.sin, "cos": sympy.cos, "tan": sympy.tan, "asin": sympy.asin,
    "acos": sympy.acos, "atan": sympy.atan, "sinh": sympy.sinh, "cosh": sympy.cosh,
    "tanh": sympy.tanh, "exp": sympy.exp, "log": sympy.log, "sqrt": sympy.sqrt,
}  # fmt: skip
_ALLOWED = "allowed: t, pi, e and the functions " + ", ".join(FUNCTIONS)
# The numpy ufunc for every sympy function that a law or its derivatives can contain.
_UFUNCS: dict[Any, Callable[[Any], Any]] = {
    sympy.sin: np.sin, sympy.cos: np.cos, sympy.tan: np.tan, sympy.asin: np.arcsin,
    sympy.acos: np.arccos, sympy.atan: np.arctan, sympy.sinh: np.sinh, sympy.cosh: np.cosh,
    sympy.tanh: np.tanh, sympy.exp: np.exp, sympy.log: np.log,
}  # fmt: skip

_TOKEN = re.compile(
    r"(?P<num>(?:[0-9]+\.?[0-9]*|\.[0-9]+)(?:[eE][+-]?[0-9]+)?)|(?P<name>[A-Za-z_][A-Za-z0-9_]*)"
    r"|(?P<op>\*\*|[-+*/^])|(?P<open>\()|(?P<close>\))|(?P<space>[ \t]+)",
    re.ASCII,
)
_CHAR_HINTS = {
    ",": "a function takes exactly one argument", "=": "a law is an expression, not an equation",
    "<": "comparisons are not allowed", ">": "comparisons are not allowed",
    "'": "text in quotes is not allowed", '"': "text in quotes is not allowed",
    "[": "use round parentheses ( )", "]": "use round parentheses ( )",
    ".": "a point may only appear inside a number such as 0.5", "\n": "write the law on one line",
}  # fmt: skip
_OPERAND_END = {"num", "name", "close", "str"}
_OPERAND_START = {"num", "name", "func", "open", "str"}

# State expressions (forces and moments, see dynamics-v1) add to the time laws' language: the
# state of a link, comparisons, and/or/not, where(c, a, b), and quoted link names.
STATE_FUNCTIONS = ("angle", "omega", "alpha")
_STATE_NAMES = {"and": "op", "or": "op", "not": "not", "where": "func"}
_STATE_TOKEN = re.compile(
    r"(?P<num>(?:[0-9]+\.?[0-9]*|\.[0-9]+)(?:[eE][+-]?[0-9]+)?)|(?P<name>[A-Za-z_][A-Za-z0-9_]*)"
    r"|(?P<str>\"[^\"]*\"|'[^']*')|(?P<op>\*\*|<=|>=|[-+*/^<>,])|(?P<open>\()|(?P<close>\))"
    r"|(?P<space>[ \t]+)",
    re.ASCII,
)
_STATE_ALLOWED = (
    _ALLOWED + ', angle("L"), omega("L"), alpha("L"), where(c, a, b), comparisons '
    "< <= > >=, and, or, not"
)
_STATE_HINTS = {
    **_CHAR_HINTS,
    "=": "compare with < <= > >= (== and != are not allowed)",
    "!": "compare with < <= > >= (== and != are not allowed)",
}

_Fn = Callable[[Any], Any]  # float64 scalar or array in, the same out


def _error(text: str, pos: int, what: str, detail: str = "") -> InvalidExpression:
    """The error for ``text`` with message '<what> at character <pos><detail>'."""
    return InvalidExpression(f"{what} at character {pos}{detail}", pos, text)


def _too_large(literal: int | float) -> bool:
    """|literal| > MAX_LITERAL, compared exactly: an integer of 309 digits or more has no float
    (``math.isfinite`` would raise OverflowError), and a float literal past 1.8e308 is inf."""
    return abs(literal) > MAX_LITERAL


def _needs_parentheses(name: str) -> str:
    """Message detail for a function name that is not followed by '('."""
    return f": {name} needs its argument in parentheses, e.g. {name}(t)"


def _scan(text: str, state: bool = False) -> None:
    """Check characters, names, parentheses and juxtaposition before Python's parser runs.

    Python's own messages ("invalid decimal literal") would puzzle a student, and its parser
    should never see a character outside the expression language. ``state``: the language of
    force and moment expressions (``STATE_FUNCTIONS``, comparisons, and/or/not, where).
    """
    token, hints, allowed = (
        (_STATE_TOKEN, _STATE_HINTS, _STATE_ALLOWED) if state else (_TOKEN, _CHAR_HINTS, _ALLOWED)
    )
    opened: list[int] = []
    prev_kind, prev_text, pos = "", "", 0
    while pos < len(text):
        match = token.match(text, pos)
        if match is None:
            hint = hints.get(text[pos], allowed)
            raise _error(text, pos, f"{text[pos]!r} is not allowed", f"; {hint}")
        start, pos, kind, tok = pos, match.end(), str(match.lastgroup), match.group()
        if kind == "space":
            continue
        if kind == "name" and (tok in FUNCTIONS or (state and tok in STATE_FUNCTIONS)):
            kind = "func"
        elif kind == "name" and state and tok in _STATE_NAMES:
            kind = _STATE_NAMES[tok]
        elif kind == "name" and tok not in CONSTANTS:
            raise _error(text, start, f"unknown name {tok!r}", f"; {allowed}")
        if kind == "not" and prev_kind in _OPERAND_END:
            raise _error(text, start, "missing operator before 'not'")
        if prev_kind == "func" and kind != "open":
            raise _error(text, start, f"unexpected {tok!r}", _needs_parentheses(prev_text))
        if prev_kind == "num" and kind == "num":
            raise _error(text, start, f"missing operator between {prev_text} and {tok}")
        if prev_kind in _OPERAND_END and kind in _OPERAND_START:
            left = "(...)" if prev_kind == "close" else prev_text
            right = {"open": "(...)", "func": f"{tok}(...)"}.get(kind, tok)
            detail = f": implicit multiplication is not allowed: write {left}*{right}"
            raise _error(text, start, "missing '*'", detail)
        if kind == "open":
            opened.append(start)
            if len(opened) > MAX_DEPTH:
                raise _error(text, start, f"more than {MAX_DEPTH} nested parentheses")
        elif kind == "close":
            if prev_kind == "open":
                raise _error(text, start, "empty parentheses")
            if not opened:
                raise _error(text, start, "unbalanced parenthesis", ": this ')' has no '('")
            opened.pop()
        prev_kind, prev_text = kind, tok
    if prev_kind == "func":
        raise _error(text, len(text), "the law ends", _needs_parentheses(prev_text))
    if opened:
        raise _error(text, opened[-1], "unbalanced parenthesis", ": this '(' is never closed")


class _Builder:
    """Walks a Python AST under a strict whitelist and builds the sympy expression."""

    def __init__(self, text: str, origin: list[int]) -> None:
        self.text, self.origin = text, origin  # origin[i]: original index of rewritten char i
        self.values: dict[sympy.Expr, float] = {}  # validated value of every t-free part

    def position(self, node: ast.AST) -> int:
        """Original index of the first character of ``node``."""
        return self.origin[getattr(node, "col_offset", 0)]

    def fail(self, message: str, node: ast.AST) -> InvalidExpression:
        """An error located at the first character of ``node``."""
        return _error(self.text, self.position(node), message)

    def source(self, node: ast.AST) -> str:
        """The original text of ``node``, for messages."""
        end = self.origin[max(getattr(node, "end_col_offset", 1) - 1, 0)] + 1
        return self.text[self.position(node) : end]

    def checked(self, expr: sympy.Expr, node: ast.AST) -> sympy.Expr:
        """Return ``expr``; a t-free one must be a finite real of moderate size (it is recorded)."""
        if expr.free_symbols or expr in self.values:
            return expr
        approximation = expr.evalf(20)
        value = complex(approximation)  # zoo and nan become nan here
        if math.isnan(value.real) or math.isnan(value.imag):
            raise self.fail(f"{self.source(node)} is not defined", node)
        if math.isinf(value.real) or math.isinf(value.imag):
            raise self.fail(f"{self.source(node)} is too large", node)
        if abs(value.imag) > 1e-12 * max(1.0, abs(value.real)):
            raise self.fail(f"{self.source(node)} is not a real number", node)
        # Beyond 1e100 the exact integers sympy keeps grow costly; below 1e-308 a float is 0.
        if abs(value.real) > 10.0**MAX_CONSTANT_DIGITS or (value.real == 0) != (approximation == 0):
            raise self.fail(f"{self.source(node)} is too large or too close to zero", node)
        self.values[expr] = value.real
        return expr

    def build(self, node: ast.AST, depth: int) -> sympy.Expr:
        """Translate one whitelisted node (recursively) into sympy."""
        if depth > MAX_DEPTH:
            raise self.fail(f"the expression is nested too deeply (at most {MAX_DEPTH})", node)
        result: sympy.Expr
        if (
            isinstance(node, ast.Constant)
            and isinstance(node.value, int | float)
            and not isinstance(node.value, bool)
        ):
            if _too_large(node.value):
                raise self.fail(f"the number {self.source(node)} is larger than 1e12", node)
            is_int = isinstance(node.value, int)
            result = sympy.Integer(node.value) if is_int else sympy.Float(node.value)
        elif isinstance(node, ast.Name) and node.id in CONSTANTS:
            result = CONSTANTS[node.id]
        elif isinstance(node, ast.UnaryOp) and isinstance(node.op, ast.UAdd | ast.USub):
            operand = self.build(node.operand, depth + 1)
            result = -operand if isinstance(node.op, ast.USub) else operand
        elif isinstance(node, ast.BinOp):
            result = self.binop(node, depth)
        elif isinstance(node, ast.Call):
            result = self.call(node, depth)
        else:
            raise self.fail(f"{self.source(node)!r} is not allowed in a law; {_ALLOWED}", node)
        return self.checked(result, node)

    def binop(self, node: ast.BinOp, depth: int) -> sympy.Expr:
        """Arithmetic; powers and divisions are checked before sympy computes anything."""
        left = self.build(node.left, depth + 1)
        right = self.build(node.right, depth + 1)
        lv, rv = self.values.get(left), self.values.get(right)
        if isinstance(node.op, ast.Add):
            return self.checked(sympy.Add(left, right), node)
        if isinstance(node.op, ast.Sub):
            return self.checked(sympy.Add(left, -right), node)
        if isinstance(node.op, ast.Mult):
            return self.checked(sympy.Mul(left, right), node)
        if isinstance(node.op, ast.Div):
            if rv == 0:
                raise self.fail("division by zero", node.right)
            return self.checked(sympy.Mul(left, sympy.Pow(right, -1)), node)
        if isinstance(node.op, ast.Pow):
            # Guard the size of the result so that 9**9**9 is never computed.
            if rv is not None and abs(rv) > MAX_EXPONENT:
                msg = (
                    f"the exponent {self.source(node.right)} is too large (at most {MAX_EXPONENT})"
                )
                raise self.fail(msg, node.right)
            if lv is not None and lv <= 0 and rv is None:
                msg = "a power with t in its exponent needs a positive base"
                raise self.fail(msg, node.left)
            if lv == 0 and rv is not None and rv < 0:
                raise self.fail("division by zero: 0 to a negative power", node)
            if lv and rv is not None and abs(rv * math.log10(abs(lv))) > MAX_CONSTANT_DIGITS:
                raise self.fail(f"{self.source(node)} is too large or too close to zero", node)
            return self.checked(sympy.Pow(left, right), node)
        # Only '//' gets this far (the scanner refuses % @ & | ~ < >); point at it.
        after = self.text[self.origin[node.left.end_col_offset or 0] :]
        pos = len(self.text) - len(after.lstrip(" \t)"))
        message = f"the operator {self.text[pos : pos + 2]!r} is not allowed"
        raise _error(self.text, pos, message, "; use + - * / ^ (** also works for powers)")

    def call(self, node: ast.Call, depth: int) -> sympy.Expr:
        """One of the twelve functions, called by bare name with exactly one argument."""
        if not isinstance(node.func, ast.Name) or node.func.id not in FUNCTIONS:
            raise self.fail(f"only these functions can be called: {', '.join(FUNCTIONS)}", node)
        name = node.func.id
        if node.keywords or len(node.args) != 1 or isinstance(node.args[0], ast.Starred):
            raise self.fail(f"{name}() takes exactly one argument, e.g. {name}(t)", node)
        return self.checked(FUNCTIONS[name](self.build(node.args[0], depth + 1)), node)


def _parse_tree(text: str, state: bool = False) -> tuple[ast.Expression, list[int]]:
    """Scan ``text`` and parse it with Python's ``ast``; ``origin[i]`` is the original index of
    character i of the parsed source."""
    if len(text) > MAX_LENGTH:
        msg = f"the law is too long: {len(text)} characters, at most {MAX_LENGTH}"
        raise InvalidExpression(msg, MAX_LENGTH, text)
    if not text.strip():
        raise InvalidExpression("the law is empty; write an expression in t, e.g. 2*t", 0, text)
    _scan(text, state)
    # '^' means power, but Python reads it as xor with lower precedence than '*': rewrite it
    # to '**' and remember where every rewritten character came from. Leading blanks are
    # dropped because Python's parser calls them an indent.
    rewritten: list[str] = []
    origin: list[int] = []
    for index, char in enumerate(text):
        if char in " \t" and not rewritten:
            continue
        rewritten.append("**" if char == "^" else char)
        origin.extend([index] * len(rewritten[-1]))
    origin.append(len(text))
    source = "".join(rewritten)
    try:
        tree = ast.parse(source, mode="eval")
    except SyntaxError as exc:
        pos = origin[exc.offset - 1] if exc.offset and exc.offset <= len(source) else len(text)
        where = "the law ends too early" if pos >= len(text) else f"unexpected {text[pos]!r}"
        raise _error(text, pos, where) from None
    except (RecursionError, MemoryError, ValueError):
        raise InvalidExpression("the law is too complicated to read", 0, text) from None
    return tree, origin


def _to_sympy(text: str) -> sympy.Expr:
    """Validate ``text`` and build its sympy expression (no derivatives yet)."""
    tree, origin = _parse_tree(text)
    expr = _Builder(text, origin).build(tree.body, 0)
    if expr.has(sympy.zoo, sympy.nan, sympy.oo, sympy.I):
        raise InvalidExpression("the law is not a real, finite expression", 0, text)
    depth = composition_depth(expr)
    if depth > MAX_COMPOSITION:
        raise LimitExceeded(
            f"the law {text[:40]!r} nests {depth} functions or powers of t in one another, more "
            f"than the limit of {MAX_COMPOSITION} (its derivatives would take too long to form)"
        )
    return expr


def composition_depth(expr: sympy.Expr) -> int:
    """How many functions and powers of t are nested in one another in ``expr``.

    A sum or product adds no level; a function of t, or a power whose base or exponent holds t,
    adds one (``sin(t)``: 1, ``sin(t)^2``: 2, ``t^t^t``: 2, ``6*pi*t^2``: 1).
    """
    if T not in expr.free_symbols:
        return 0
    inner = max((composition_depth(a) for a in expr.args), default=0)
    return inner if isinstance(expr, sympy.Add | sympy.Mul) or expr == T else inner + 1


def _identity(t: Any) -> Any:
    """The closure for ``t`` itself."""
    return t


def _apply(ufunc: Callable[[Any], Any], inner: _Fn) -> _Fn:
    """The closure ``t -> ufunc(inner(t))``."""
    return lambda t: ufunc(inner(t))


def _compile(expr: sympy.Expr, table: dict[sympy.Expr, _Fn]) -> _Fn:
    """Turn a sympy tree into a tree of numpy closures; ``table`` records each non-constant node."""
    if not expr.free_symbols:
        value = complex(expr.evalf(20))
        if not math.isfinite(abs(value)) or abs(value.imag) > 1e-12 * max(1.0, abs(value.real)):
            raise InvalidExpression(f"{expr} in the law or its derivatives is not a real number", 0)
        constant = np.float64(value.real)
        return lambda t: constant
    fn: _Fn
    if expr == T:
        fn = _identity
    elif isinstance(expr, sympy.Add | sympy.Mul):
        # Fold the t-free factors or terms (6*pi in 6*pi*t**2) into one constant.
        constants = [a for a in expr.args if not a.free_symbols]
        parts = [_compile(a, table) for a in expr.args if a.free_symbols]
        if constants:
            parts.insert(0, _compile(expr.func(*constants), table))
        combine = np.add if isinstance(expr, sympy.Add) else np.multiply
        first, rest = parts[0], parts[1:]

        def fn(t: Any) -> Any:
            result = first(t)
            for part in rest:
                result = combine(result, part(t))
            return result
    elif isinstance(expr, sympy.Pow):
        base, exponent = _compile(expr.base, table), expr.exp
        if exponent == 2:
            fn = _apply(np.square, base)
        elif exponent == sympy.Rational(1, 2):
            fn = _apply(np.sqrt, base)
        elif exponent == -1:
            fn = _apply(np.reciprocal, base)
        else:
            power = _compile(exponent, table)
            fn = lambda t: np.power(base(t), power(t))  # noqa: E731
    elif expr.func in _UFUNCS and len(expr.args) == 1:
        fn = _apply(_UFUNCS[expr.func], _compile(expr.args[0], table))
    else:  # unreachable for the grammar above; kept so a sympy rewrite cannot slip through
        raise InvalidExpression(f"cannot evaluate {expr} numerically", 0)
    table[expr] = fn
    return fn


@dataclass(frozen=True)
class TimeLaw:
    """A parsed time law with its exact derivatives and compiled numeric evaluators."""

    text: str
    expression: sympy.Expr
    first_derivative: sympy.Expr
    second_derivative: sympy.Expr
    _functions: tuple[_Fn, _Fn, _Fn] = field(repr=False, compare=False)
    _nodes: dict[sympy.Expr, _Fn] = field(repr=False, compare=False)

    @overload
    def evaluate(self, t: float) -> tuple[float, float, float]: ...
    @overload
    def evaluate(
        self, t: npt.NDArray[np.float64]
    ) -> tuple[npt.NDArray[np.float64], npt.NDArray[np.float64], npt.NDArray[np.float64]]: ...
    def evaluate(self, t: Any) -> Any:
        """Value, rate and rate_dot at ``t`` (floats for a number, arrays shaped like an array).

        Raises ``InvalidExpression`` naming the time when any of them is undefined or infinite.
        """
        scalar = not isinstance(t, np.ndarray)
        x = np.float64(t) if scalar else np.asarray(t, dtype=np.float64)
        with np.errstate(all="ignore"):
            results = [fn(x) for fn in self._functions]
        if scalar:
            if all(math.isfinite(r) for r in results):
                return float(results[0]), float(results[1]), float(results[2])
        else:
            arrays = tuple(np.broadcast_to(r, x.shape).astype(np.float64) for r in results)
            if all(np.isfinite(a).all() for a in arrays):
                return arrays
        self._raise_undefined(x, results)

    def at(self, t: float, order: int) -> float:
        """The value (``order`` 0), the rate (1) or rate_dot (2) at one ``t``: the one asked for
        only, where ``evaluate`` computes all three (a root search asks for the value at each of
        its steps); ``InvalidExpression`` as from ``evaluate`` where it is undefined."""
        x = self._unchecked(t, order)
        if math.isfinite(x):
            return x
        return self.evaluate(t)[order]  # raises: the function asked for is undefined at t

    def value(self, t: float) -> float:
        """The law's value at one ``t`` without the checks of ``evaluate``: inf where it
        overflows (exp(100 t) past t = 7.1 s), nan where it is undefined (sqrt(t - 1) before
        t = 1); for a search that needs it only where finite (a root by Brent's method)."""
        return self._unchecked(t, 0)

    def _unchecked(self, t: float, order: int) -> float:
        """The function of ``order`` (0 the value, 1 the rate, 2 rate_dot) at one ``t``, inf or
        nan where it is not finite."""
        with np.errstate(all="ignore"):
            return float(self._functions[order](np.float64(t)))

    @functools.cached_property
    def _rate_enclosures(self) -> tuple[RangeFn, RangeFn]:
        return enclosure(self.first_derivative), enclosure(self.second_derivative)

    def rate_ranges(
        self, a: npt.NDArray[np.float64], b: npt.NDArray[np.float64]
    ) -> tuple[Range, Range]:
        """Ranges holding rate and rate_dot over each span [a_i, b_i]: the natural interval
        extension of the exact derivatives (``solver.model.intervals``), as (low, high) arrays."""
        rate, rate_dot = self._rate_enclosures
        return ranges(rate, a, b), ranges(rate_dot, a, b)

    def _raise_undefined(self, x: Any, results: list[Any]) -> NoReturn:
        """Find the first bad time and the innermost subexpression to blame, and raise."""
        bad = [~np.isfinite(np.broadcast_to(r, np.shape(x))) for r in results]
        order = next(i for i, b in enumerate(bad) if b.any())
        t0 = float(np.asarray(x).flat[int(np.argmax(bad[order]))])
        if not math.isfinite(t0):
            raise InvalidExpression(f"the time t = {t0} is not a finite number", 0, self.text)
        expr = culprit = (self.expression, self.first_derivative, self.second_derivative)[order]
        with np.errstate(all="ignore"):  # descend while some argument is itself non-finite
            while bad_args := [
                a
                for a in culprit.args
                if a in self._nodes and not np.isfinite(self._nodes[a](np.float64(t0)))
            ]:
                culprit = bad_args[0]
            infinite = np.isinf(self._nodes[culprit](np.float64(t0)))
        message = f"{sympy.sstr(culprit)} is not defined at t = {t0:.6g} s"
        if infinite:
            message += " (its value is infinite or too large)"
        if order:
            which = ("first", "second")[order - 1]
            message += f" (in the {which} derivative of {self.text}: {sympy.sstr(expr)})"
        raise InvalidExpression(message, 0, self.text)


@functools.lru_cache(maxsize=256)
def parse_time_law(text: str) -> TimeLaw:
    """Parse and check a time law, differentiate it exactly and compile it for numpy."""
    if not isinstance(text, str):
        raise InvalidExpression("a time law must be a string", 0, str(text))
    expression = _to_sympy(text)
    first = sympy.diff(expression, T)
    second = sympy.diff(first, T)
    nodes: dict[sympy.Expr, _Fn] = {}
    try:
        functions = (_compile(expression, nodes), _compile(first, nodes), _compile(second, nodes))
    except InvalidExpression as exc:  # _compile does not know the text
        raise InvalidExpression(exc.message, exc.position, text) from None
    return TimeLaw(text, expression, first, second, functions, nodes)


# ---------------------------------------------------------------------------------------------
# State expressions: magnitudes of forces and moments as functions of t and the links' state.

State = Mapping[str, tuple[npt.NDArray[np.float64], ...]]  # link -> (angle, omega, alpha) (N,)
_StateFn = Callable[[npt.NDArray[np.float64], State], Any]
_STATE_INDEX = {name: index for index, name in enumerate(STATE_FUNCTIONS)}
_COMPARE: dict[type, Callable[[Any, Any], Any]] = {
    ast.Lt: np.less, ast.LtE: np.less_equal, ast.Gt: np.greater, ast.GtE: np.greater_equal,
}  # fmt: skip
_ARITHMETIC: dict[type, Callable[[Any, Any], Any]] = {
    ast.Add: np.add, ast.Sub: np.subtract, ast.Mult: np.multiply, ast.Div: np.divide,
    ast.Pow: np.power,
}  # fmt: skip
_STATE_UFUNCS: dict[str, Callable[[Any], Any]] = {**{
    name: _UFUNCS[fn] for name, fn in FUNCTIONS.items() if fn in _UFUNCS
}, "sqrt": np.sqrt}  # fmt: skip


def _truth(value: Any) -> Any:
    return np.not_equal(value, 0.0)


class _StateBuilder:
    """Walks a Python AST under the state whitelist and builds a numpy closure of (t, state)."""

    def __init__(self, text: str, origin: list[int]) -> None:
        self.text, self.origin = text, origin
        self.links: set[str] = set()

    def fail(self, message: str, node: ast.AST) -> InvalidExpression:
        return _error(self.text, self.origin[getattr(node, "col_offset", 0)], message)

    def build(self, node: ast.AST, depth: int) -> _StateFn:
        if depth > MAX_DEPTH:
            raise self.fail(f"the expression is nested too deeply (at most {MAX_DEPTH})", node)
        deeper = depth + 1
        if (
            isinstance(node, ast.Constant)
            and isinstance(node.value, int | float)
            and not isinstance(node.value, bool)
        ):
            if _too_large(node.value):
                raise self.fail("the number is larger than 1e12", node)
            constant = np.float64(node.value)
            return lambda t, s: constant
        if isinstance(node, ast.Name) and node.id in CONSTANTS:
            if node.id == "t":
                return lambda t, s: t
            value = np.float64(float(CONSTANTS[node.id]))
            return lambda t, s: value
        if isinstance(node, ast.UnaryOp) and isinstance(node.op, ast.UAdd | ast.USub | ast.Not):
            inner = self.build(node.operand, deeper)
            if isinstance(node.op, ast.USub):
                return lambda t, s: np.negative(inner(t, s))
            if isinstance(node.op, ast.Not):
                return lambda t, s: np.logical_not(_truth(inner(t, s)))
            return inner
        if isinstance(node, ast.BinOp) and type(node.op) in _ARITHMETIC:
            op = _ARITHMETIC[type(node.op)]
            left, right = self.build(node.left, deeper), self.build(node.right, deeper)
            return lambda t, s: op(left(t, s), right(t, s))
        if isinstance(node, ast.BoolOp):
            parts = [self.build(v, deeper) for v in node.values]
            combine = np.logical_and if isinstance(node.op, ast.And) else np.logical_or
            return lambda t, s: functools.reduce(combine, (_truth(p(t, s)) for p in parts))
        if isinstance(node, ast.Compare):
            if any(type(op) not in _COMPARE for op in node.ops):
                raise self.fail("only the comparisons < <= > >= are allowed", node)
            terms = [self.build(v, deeper) for v in (node.left, *node.comparators)]
            ops = [_COMPARE[type(op)] for op in node.ops]

            def compare(t: Any, s: State) -> Any:
                values = [term(t, s) for term in terms]
                pairs = (op(a, b) for op, a, b in zip(ops, values, values[1:], strict=False))
                return functools.reduce(np.logical_and, pairs)

            return compare
        if isinstance(node, ast.Call):
            return self.call(node, deeper)
        raise self.fail(f"this is not allowed in an expression; {_STATE_ALLOWED}", node)

    def call(self, node: ast.Call, depth: int) -> _StateFn:
        name = node.func.id if isinstance(node.func, ast.Name) else ""
        if node.keywords or any(isinstance(a, ast.Starred) for a in node.args):
            raise self.fail(f"{name}() takes plain arguments", node)
        if name == "where":
            if len(node.args) != 3:
                raise self.fail("where() takes three arguments: where(condition, a, b)", node)
            c, a, b = (self.build(arg, depth) for arg in node.args)
            return lambda t, s: np.where(_truth(c(t, s)), a(t, s), b(t, s))
        if name in _STATE_INDEX:
            argument = node.args[0] if len(node.args) == 1 else None
            if not (isinstance(argument, ast.Constant) and isinstance(argument.value, str)):
                raise self.fail(f'{name}() takes a link name in quotes, e.g. {name}("crank")', node)
            link, index = argument.value, _STATE_INDEX[name]
            self.links.add(link)
            return lambda t, s: s[link][index]
        if name in _STATE_UFUNCS:
            if len(node.args) != 1:
                raise self.fail(f"{name}() takes exactly one argument, e.g. {name}(t)", node)
            ufunc, inner = _STATE_UFUNCS[name], self.build(node.args[0], depth)
            return lambda t, s: ufunc(inner(t, s))
        raise self.fail(f"unknown function; {_STATE_ALLOWED}", node)


@dataclass(frozen=True)
class StateExpression:
    """A force or moment magnitude as an expression of ``t`` and the links' angle, omega, alpha.

    ``links`` names every link the expression reads (the scene checks that they exist).
    """

    text: str
    links: frozenset[str]
    _function: _StateFn = field(repr=False, compare=False)

    def evaluate(self, t: npt.NDArray[np.float64], state: State) -> npt.NDArray[np.float64]:
        """The value at every sample (comparisons count as 1 or 0); ``InvalidExpression`` where
        it is undefined or infinite."""
        with np.errstate(all="ignore"):
            value = np.broadcast_to(self._function(t, state), t.shape).astype(np.float64)
        bad = ~np.isfinite(value)
        if bad.any():
            k = int(np.argmax(bad))
            where = ", ".join(
                f'{STATE_FUNCTIONS[i]}("{link}") = {state[link][i][k]:.6g}'
                for link in sorted(self.links)
                for i in range(3)
            )
            raise InvalidExpression(
                f"{self.text} is not defined at t = {t[k]:.6g} s" + (f", {where}" if where else ""),
                0,
                self.text,
            )
        return value


@functools.lru_cache(maxsize=256)
def parse_state_expression(text: str) -> StateExpression:
    """Parse and check a force or moment expression (the time-law whitelist plus the state)."""
    if not isinstance(text, str):
        raise InvalidExpression("an expression must be a string", 0, str(text))
    tree, origin = _parse_tree(text, state=True)
    builder = _StateBuilder(text, origin)
    function = builder.build(tree.body, 0)
    return StateExpression(text, frozenset(builder.links), function)
