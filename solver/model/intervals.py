"""Ranges of a time law over spans of time: Moore's natural interval extension.

f([a, b]) = [low, high] contains f(t) for every t in [a, b]: each node of the law's sympy tree is
replaced by its interval counterpart. A sum adds the ends, a product takes the extremes of the
four products of ends, a monotonic function its values at the ends (clipped to its domain), sin
and cos reach +-1 where a crest or trough lies inside, cosh 1 where 0 does; across a pole (tan,
a negative power of a range holding 0) the range is the whole line, and so is an undefined one
(nan). The ends are not rounded outwards, so the ranges hold to the rounding of the end values.
Each occurrence of t varies independently, so a range over-estimates by an amount that shrinks
with the width b - a (first order); it never misses a value.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from functools import partial
from typing import Any

import numpy as np
import numpy.typing as npt
import sympy

from solver.errors import InvalidExpression

Range = tuple[Any, Any]  # (low, high): float64 arrays or numbers, elementwise
RangeFn = Callable[[Range], Range]


def _monotonic(
    x: Range, f: Callable[[Any], Any], domain: tuple[float, float], rising: bool
) -> Range:
    """A monotonic function: its values at the ends, clipped to its domain."""
    low, high = f(np.clip(x[0], *domain)), f(np.clip(x[1], *domain))
    return (low, high) if rising else (high, low)


def _contains(phase: float, period: float, x: Range) -> Any:
    """Whether phase + k period lies in [low, high] for some integer k."""
    low, high = x
    return phase + period * np.ceil((low - phase) / period) <= high


def _wave(x: Range, f: Callable[[Any], Any], crest: float) -> Range:
    """sin (crest pi/2) or cos (crest 0): the ends' values, or +-1 where a crest (crest + 2 pi k)
    or a trough (crest + pi + 2 pi k) lies inside."""
    a, b = f(x[0]), f(x[1])
    low = np.where(_contains(crest + math.pi, 2.0 * math.pi, x), -1.0, np.minimum(a, b))
    return low, np.where(_contains(crest, 2.0 * math.pi, x), 1.0, np.maximum(a, b))


def _tan(x: Range) -> Range:
    """tan rises between its poles pi/2 + k pi; across one it takes every value."""
    pole = _contains(math.pi / 2.0, math.pi, x)
    return np.where(pole, -np.inf, np.tan(x[0])), np.where(pole, np.inf, np.tan(x[1]))


def _cosh(x: Range) -> Range:
    """cosh falls to 1 at 0 and rises after it."""
    a, b = np.cosh(x[0]), np.cosh(x[1])
    low = np.where((x[0] <= 0.0) & (x[1] >= 0.0), 1.0, np.minimum(a, b))
    return low, np.maximum(a, b)


_WHOLE = (-math.inf, math.inf)
_FUNCTIONS: dict[Any, RangeFn] = {
    sympy.sin: partial(_wave, f=np.sin, crest=math.pi / 2.0),
    sympy.cos: partial(_wave, f=np.cos, crest=0.0),
    sympy.tan: _tan,
    sympy.asin: partial(_monotonic, f=np.arcsin, domain=(-1.0, 1.0), rising=True),
    sympy.acos: partial(_monotonic, f=np.arccos, domain=(-1.0, 1.0), rising=False),
    sympy.atan: partial(_monotonic, f=np.arctan, domain=_WHOLE, rising=True),
    sympy.sinh: partial(_monotonic, f=np.sinh, domain=_WHOLE, rising=True),
    sympy.cosh: _cosh,
    sympy.tanh: partial(_monotonic, f=np.tanh, domain=_WHOLE, rising=True),
    sympy.exp: partial(_monotonic, f=np.exp, domain=_WHOLE, rising=True),
    sympy.log: partial(_monotonic, f=np.log, domain=(0.0, math.inf), rising=True),
}


def _sum(x: Range, y: Range) -> Range:
    return x[0] + y[0], x[1] + y[1]


def _product(x: Range, y: Range) -> Range:
    """[a, b] [c, d] = [min, max] of ac, ad, bc, bd."""
    ends = np.stack(np.broadcast_arrays(x[0] * y[0], x[0] * y[1], x[1] * y[0], x[1] * y[1]))
    return ends.min(axis=0), ends.max(axis=0)


def _integer_power(x: Range, n: int) -> Range:
    """x^n: odd powers rise; even ones fall to 0 where the range holds 0; a negative power is
    the reciprocal of the positive one, whole across 0."""
    a, b = x[0] ** abs(n), x[1] ** abs(n)
    if abs(n) % 2:
        low, high = a, b
    else:
        low = np.where((x[0] <= 0.0) & (x[1] >= 0.0), 0.0, np.minimum(a, b))
        high = np.maximum(a, b)
    if n > 0:
        return low, high
    across = (low <= 0.0) & (high >= 0.0)
    return np.where(across, -np.inf, 1.0 / high), np.where(across, np.inf, 1.0 / low)


def _power(base: RangeFn, exponent: sympy.Expr) -> RangeFn:
    """base^p for a constant p (a real power is defined for base >= 0, where it is monotonic);
    base^e with t in the exponent as exp(e log base)."""
    if exponent.free_symbols:
        e, log, exp = enclosure(exponent), _FUNCTIONS[sympy.log], _FUNCTIONS[sympy.exp]
        return lambda x: exp(_product(e(x), log(base(x))))
    p = float(exponent)
    if p == round(p):
        return lambda x: _integer_power(base(x), round(p))
    return lambda x: _monotonic(base(x), lambda y: np.power(y, p), (0.0, math.inf), p > 0.0)


def enclosure(expr: sympy.Expr) -> RangeFn:
    """The natural interval extension of ``expr``, a sympy expression in one symbol t (a time
    law or one of its derivatives): a function from the ranges of t to ranges of ``expr``."""
    if not expr.free_symbols:
        value = np.float64(complex(expr.evalf(20)).real)
        return lambda x: (value, value)
    if expr.is_Symbol:
        return lambda x: x
    if isinstance(expr, sympy.Add | sympy.Mul):
        parts = [enclosure(a) for a in expr.args]
        combine = _sum if isinstance(expr, sympy.Add) else _product

        def fn(x: Range) -> Range:
            result = parts[0](x)
            for part in parts[1:]:
                result = combine(result, part(x))
            return result

        return fn
    if isinstance(expr, sympy.Pow):
        base = enclosure(expr.base)
        return _power(base, expr.exp)
    if expr.func in _FUNCTIONS and len(expr.args) == 1:
        outer, inner = _FUNCTIONS[expr.func], enclosure(expr.args[0])
        return lambda x: outer(inner(x))
    # unreachable for the laws' grammar (laws._compile refuses the same nodes)
    raise InvalidExpression(f"cannot bound {expr} numerically", 0)


def ranges(
    fn: RangeFn, a: npt.NDArray[np.float64], b: npt.NDArray[np.float64]
) -> tuple[npt.NDArray[np.float64], npt.NDArray[np.float64]]:
    """fn over each span [a_i, b_i], as arrays shaped like ``a``; an undefined range (nan) is
    the whole line."""
    with np.errstate(all="ignore"):
        low, high = (np.broadcast_to(r, a.shape).astype(np.float64) for r in fn((a, b)))
    undefined = np.isnan(low) | np.isnan(high)
    return np.where(undefined, -np.inf, low), np.where(undefined, np.inf, high)
