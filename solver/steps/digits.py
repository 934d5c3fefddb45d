"""Enough digits for the shown arithmetic to recompute: |f(shown operands) - shown result| <= 0.6
units in the last shown digit of the result.

A step shows its numbers with ``digits`` significant digits. Where a check's result, recomputed
from its operands as they are shown, would not round to the result as shown (-0.03125 / 0.0127
gives -2.461, the step says -2.462), the operands are shown with one more digit, and again, up to
``MAX_DIGITS``, until every check of the step recomputes (a fixed point: digits only grow).
``DigitPlan`` carries the digits found while a solution is built once to the second, final build
(steps are matched by kind, title and occurrence).
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence

import numpy as np

from solver.rigid import cross, perp
from solver.steps.format import Formatter
from solver.steps.model import Check, Value

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


def _cross(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """omega k x b (a scalar a), the planar a x b (a number), or the spatial a x b."""
    if a.size == 1 and b.size == 2:
        return float(a[0]) * perp(b)
    if a.size == 2 and b.size == 2:
        return np.array(float(cross(a, b)))
    return np.cross(a, b)


def evaluate(relation: str, ops: Sequence[np.ndarray], factor: float) -> tuple[np.ndarray, float]:
    """(the relation's value, the size of the terms it is made of) from operand arrays."""
    ops = [np.atleast_1d(np.asarray(o, dtype=float)) for o in ops]
    size = [float(np.linalg.norm(o)) for o in ops]
    if relation == "sum":
        value, scale = sum(ops[1:], ops[0]), sum(size)
    elif relation == "cross":
        value, scale = _cross(ops[0], ops[1]), size[0] * size[1]
    elif relation == "product":
        value, scale = math.prod(ops[1:], start=ops[0]), math.prod(size)
    elif relation == "quotient":
        value, scale = ops[0] / ops[1], size[0] / max(size[1], 1e-300)
    elif relation == "det2":
        value = ops[0] * ops[3] - ops[1] * ops[2]
        scale = size[0] * size[3] + size[1] * size[2]
    elif relation == "linear":
        value = sum((ops[k] * ops[k + 1] for k in range(2, len(ops), 2)), ops[0] * ops[1])
        scale = sum(size[k] * size[k + 1] for k in range(0, len(ops), 2))
    elif relation == "dot":
        value, scale = np.array(float(np.dot(ops[0], ops[1]))), size[0] * size[1]
    elif relation in ("phasor", "iphasor"):
        angle = float(ops[-1].reshape(-1)[0])
        unit = np.array([math.cos(angle), math.sin(angle)])
        value = math.prod(ops[1:-1], start=ops[0]) * (unit if relation == "phasor" else perp(unit))
        scale = math.prod(size[:-1])
    elif relation == "angle":
        value, scale = np.array(math.atan2(ops[0][1], ops[0][0])), math.pi
    elif relation == "norm":
        value, scale = np.array(float(np.linalg.norm(ops[0]))), size[0]
    else:
        raise ValueError(f"unknown relation {relation}")
    return factor * np.asarray(value, dtype=float), abs(factor) * scale


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
        self.cache: dict[tuple[str, int], np.ndarray] = {}

    def shown(self, key: str) -> np.ndarray:
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
        if isinstance(clean, tuple):
            found = np.array([rounded(x, d) for x in clean])
        else:
            found = np.array(rounded(clean, d))
        self.cache[(key, d)] = found
        return found

    def operand(self, name: str) -> tuple[str, np.ndarray]:
        """(value key, shown number) of an operand written 'name', '-name' or 'name[i]'."""
        sign = -1.0 if name.startswith("-") else 1.0
        key = name.lstrip("-")
        index = None
        if key.endswith("]") and key.rsplit("[", 1)[0] in self.values:
            key, rest = key.rsplit("[", 1)
            index = int(rest[:-1])
        value = self.shown(key)
        if index is not None:
            value = np.array(value.reshape(-1)[index])
        return key, sign * value

    def recomputes(self, check: Check) -> bool:
        """True when the check, evaluated with the shown operands, gives the shown result."""
        ops = [self.operand(o)[1] for o in check.operands]
        value, scale = evaluate(check.relation, ops, check.factor)
        result_key, result = self.operand(check.result)
        d = self.digits[result_key]
        diff = np.atleast_1d(value - result).astype(float)
        if check.relation == "angle":
            diff = (diff + math.pi) % (2 * math.pi) - math.pi
        result = np.atleast_1d(result)
        largest = float(np.max(np.abs(result))) if result.size else 0.0
        floor = _ulp(largest if largest > 0 else scale, d)
        for x, r in zip(diff, result, strict=True):
            tolerance = TOLERANCE_ULP * max(_ulp(float(r), d), floor) * (1 + 1e-9)
            if abs(x) > tolerance + 1e-12 * scale:
                return False
        return True


def needed_digits(
    values: Mapping[str, Value],
    references: Mapping[str, float],
    checks: Sequence[Check],
    fmt: Formatter,
) -> dict[str, int]:
    """The values that need more than ``fmt.digits`` digits for every check to recompute."""
    digits = dict.fromkeys(values, fmt.digits)
    shown = ShownValues(values, references, fmt, digits)
    for _ in range(MAX_DIGITS * max(1, len(values))):
        changed = False
        for check in checks:
            if check.relation in UNSHOWN or shown.recomputes(check):
                continue
            for name in check.operands:
                key = shown.operand(name)[0]
                if digits[key] < MAX_DIGITS:
                    digits[key] += 1
                    changed = True
        if not changed:
            break
    return {k: d for k, d in digits.items() if d > fmt.digits}


class DigitPlan:
    """Digits per value and step, found in a first build and used in the second."""

    def __init__(self) -> None:
        self.wanted: dict[tuple[str, str, int], dict[str, int]] = {}
        self.counts: dict[tuple[str, str], int] = {}
        self.recording = True

    def key(self, kind: str, title: str) -> tuple[str, str, int]:
        n = self.counts.get((kind, title), 0)
        self.counts[(kind, title)] = n + 1
        return kind, title, n

    def record(self, key: tuple[str, str, int], found: dict[str, int]) -> None:
        if self.recording and found:
            self.wanted[key] = found

    def digits(self, key: tuple[str, str, int]) -> dict[str, int]:
        return {} if self.recording else self.wanted.get(key, {})

    def replay(self) -> bool:
        """Switch to the final build; False when no step needs more digits (one build does)."""
        self.recording = False
        self.counts = {}
        return bool(self.wanted)
