"""Enough digits for the shown arithmetic to recompute: |f(shown operands) - shown result| <= 0.6
units in the last shown digit of the result.

A step shows its numbers with ``digits`` significant digits. Where a check's result, recomputed
from its operands as they are shown, would not round to the result as shown (-0.03125 / 0.0127
gives -2.461, the step says -2.462), the operands are shown with one more digit, and again, up to
``MAX_DIGITS``, until every check of the step recomputes (a fixed point: digits only grow). The
operands of one check are shown at one precision: a line reads 0.1205 * 1.582, never
0.347195^2 * 1.582 (a result may show fewer digits than the numbers it is computed from). A
step settles its digits in one pass over its values when it is built (``StepBuilder.build``).
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence

from solver.solutions.equation import Operand
from solver.solutions.format import Formatter
from solver.solutions.model import Check, Value

MAX_DIGITS = 15
TOLERANCE_ULP = 0.6  # half a unit in the last digit, and a little for ties
# relations that state an equation in the unknowns (c1 u1 + c2 u2 = b), not arithmetic on shown
# numbers: the solved unknowns are substituted, and checked, in the steps that follow
UNSHOWN = frozenset({"linear"})


def rounded(x: float, digits: int) -> float:
    """x rounded to ``digits`` significant digits (as the formatter writes it)."""
    return float(f"{x:.{digits - 1}e}") if x != 0.0 and math.isfinite(x) else 0.0


def _ulp(x: float, digits: int) -> float:
    """One unit in the last of ``digits`` significant digits of x (0 for x = 0)."""
    if x == 0.0:
        return 0.0
    return 10.0 ** (math.floor(math.log10(abs(x))) - digits + 1)


Shown = tuple[float, ...]  # a shown number: one component for a scalar, 2 or 3 for a vector


def _zip(a: Shown, b: Shown) -> zip[tuple[float, float]]:
    """Components of a and b side by side, a scalar repeated against a vector."""
    n = max(len(a), len(b))
    return zip(a * n if len(a) == 1 else a, b * n if len(b) == 1 else b, strict=True)


def _cross(a: Shown, b: Shown) -> Shown:
    if len(a) == 1 and len(b) == 2:
        return (a[0] * -b[1], a[0] * b[0])
    if len(a) == 2 and len(b) == 2:
        return (a[0] * b[1] - a[1] * b[0],)
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def _times(a: Shown, b: Shown) -> Shown:
    return tuple(x * y for x, y in _zip(a, b))


def _dot(a: Shown, b: Shown) -> float:
    total = 0.0
    for x, y in zip(a, b, strict=True):
        total += x * y
    return total


def evaluate(relation: str, ops: Sequence[Shown], factor: float) -> tuple[Shown, float]:
    """(the relation's value, the size of the terms it is made of) from the shown operands, in
    plain floats (a step's checks are a few hundred small sums and products)."""
    size = [math.sqrt(_dot(o, o)) for o in ops]
    if relation == "sum":
        value = ops[0]
        for o in ops[1:]:
            value = tuple(x + y for x, y in _zip(value, o))
        scale = sum(size)
    elif relation == "cross":
        value, scale = _cross(ops[0], ops[1]), size[0] * size[1]
    elif relation == "product":
        value = ops[0]
        for o in ops[1:]:
            value = _times(value, o)
        scale = math.prod(size)
    elif relation == "quotient":
        value = tuple(x / y for x, y in _zip(ops[0], ops[1]))
        scale = size[0] / max(size[1], 1e-300)
    elif relation == "det2":
        value = (ops[0][0] * ops[3][0] - ops[1][0] * ops[2][0],)
        scale = size[0] * size[3] + size[1] * size[2]
    elif relation == "linear":
        value = (sum(ops[k][0] * ops[k + 1][0] for k in range(0, len(ops), 2)),)
        scale = sum(size[k] * size[k + 1] for k in range(0, len(ops), 2))
    elif relation == "dot":
        value, scale = (_dot(ops[0], ops[1]),), size[0] * size[1]
    elif relation in ("phasor", "iphasor"):
        angle = ops[-1][0]
        c, s = math.cos(angle), math.sin(angle)
        magnitude = ops[0]
        for o in ops[1:-1]:
            magnitude = _times(magnitude, o)
        value = _times(magnitude, (c, s) if relation == "phasor" else (-s, c))
        scale = math.prod(size[:-1])
    elif relation == "angle":
        value, scale = (math.atan2(ops[0][1], ops[0][0]),), math.pi
    elif relation == "norm":
        value, scale = (size[0],), size[0]
    else:
        raise ValueError(f"unknown relation {relation}")
    return tuple(factor * x for x in value), abs(factor) * scale


class ShownValues:
    """The step's values as shown with per-value digits (noise cleaned as the display does)."""

    def __init__(
        self,
        values: Mapping[str, Value],
        references: Mapping[str, float],
        fmt: Formatter,
        digits: Mapping[str, int],
    ) -> None:
        self.values, self.references, self.fmt, self.digits = values, references, fmt, digits
        self.cleaned: dict[str, tuple[float, ...] | float] = {}
        self.cache: dict[tuple[str, int], Shown] = {}

    def shown(self, key: str) -> Shown:
        d = self.digits[key]
        found = self.cache.get((key, d))
        if found is not None:
            return found
        if key not in self.cleaned:
            v = self.values[key]
            self.cleaned[key] = (
                self.fmt.clean_vector(v.value, v.unit)
                if isinstance(v.value, tuple)
                else self.fmt.clean(v.value, v.unit, self.references[key])
            )
        clean = self.cleaned[key]
        found = tuple(rounded(x, d) for x in (clean if isinstance(clean, tuple) else (clean,)))
        self.cache[(key, d)] = found
        return found

    def operand(self, operand: Operand) -> Shown:
        """The shown number of an operand: the value, negated or one of its components."""
        value = self.shown(operand.ref.key)
        if operand.component is not None:
            value = (value[operand.component],)
        return value if operand.sign > 0 else tuple(-x for x in value)

    def recomputes(self, check: Check) -> bool:
        """True when the check, evaluated with the shown operands, gives the shown result: every
        component within 0.6 units in the last shown digit of the result's largest component (of
        the terms' size where the result is 0), and 1e-12 of that size."""
        operands = list(map(self.operand, check.operands))
        value, scale = evaluate(check.relation, operands, check.factor)
        result = self.operand(check.result)
        diff = [x - r for x, r in _zip(value, result)]
        if check.relation == "angle":
            diff = [(x + math.pi) % (2 * math.pi) - math.pi for x in diff]
        largest = max(map(abs, result))
        # (a component's own last digit is never finer than the largest's: one tolerance for all)
        unit = _ulp(largest if largest > 0 else scale, self.digits[check.result.ref.key])
        tolerance = TOLERANCE_ULP * unit * (1 + 1e-9)
        return max(map(abs, diff)) <= tolerance + 1e-12 * scale


def needed_digits(
    values: Mapping[str, Value],
    references: Mapping[str, float],
    checks: Sequence[Check],
    fmt: Formatter,
) -> dict[str, int]:
    """The values that need more than ``fmt.digits`` digits for every check to recompute, the
    operands of one check at one precision (0.1205 * 1.582, never 0.347195^2 * 1.582): where
    a check does not recompute, all its operands take one digit more than the most precise of
    them; where its operands differ, the others take the most precise one's digits."""
    digits = dict.fromkeys(values, fmt.digits)
    shown = ShownValues(values, references, fmt, digits)
    shown_checks = [c for c in checks if c.relation not in UNSHOWN]
    keys = [[o.ref.key for o in (c.result, *c.operands)] for c in shown_checks]
    passed: dict[int, list[int]] = {}  # a check that recomputed, with its values' digits then
    for _ in range(MAX_DIGITS * max(1, len(values))):
        changed = False
        for i, check in enumerate(shown_checks):
            now = [digits[k] for k in keys[i]]
            if passed.get(i) == now:
                continue  # the same shown numbers recompute again
            level = max(now[1:])
            if min(now[1:]) == level and shown.recomputes(check):
                passed[i] = now
                continue
            if min(now[1:]) == level or not shown.recomputes(check):
                level = min(level + 1, MAX_DIGITS)
            for key in keys[i][1:]:
                if digits[key] < level:
                    digits[key] = level
                    changed = True
        if not changed:
            break
    return {k: d for k, d in digits.items() if d > fmt.digits}
