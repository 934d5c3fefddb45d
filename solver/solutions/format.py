"""Numbers as a worked solution shows them: ``digits`` significant digits, SI units, no noise.

The data behind a step keep full precision; only the display is rounded. Rounding noise of the
solver (a component of 1e-17 m/s in a velocity of 1 m/s) is shown as 0: a value is noise when it
is smaller than ``NOISE`` times the scale of its unit in this solution (the largest velocity for
m/s, the largest angular velocity for rad/s, ...) or, inside a vector, times the vector's length.
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Mapping, Sequence

NOISE = 1e-11
# Fixed-point notation for magnitudes in [1e-4, 1e6); outside, a power of ten.
FIXED_LOW = -4
FIXED_HIGH = 6

LATEX_UNITS = {
    "m": r"\mathrm{m}",
    "m/s": r"\mathrm{m/s}",
    "m/s^2": r"\mathrm{m/s^{2}}",
    "rad": r"\mathrm{rad}",
    "rad/s": r"\mathrm{rad/s}",
    "rad/s^2": r"\mathrm{rad/s^{2}}",
    "s": r"\mathrm{s}",
    "deg": r"{}^{\circ}",
    "m^2": r"\mathrm{m^{2}}",
    "1/s": r"\mathrm{1/s}",
    "1/s^2": r"\mathrm{1/s^{2}}",
}


def _split(value: float, digits: int) -> tuple[str, int] | None:
    """(mantissa text, exponent) of ``value`` rounded to ``digits`` significant digits."""
    if value == 0.0 or not math.isfinite(value):
        return None
    mantissa, exponent = f"{value:.{digits - 1}e}".split("e")
    if "." in mantissa:
        mantissa = mantissa.rstrip("0").rstrip(".")
    return mantissa, int(exponent)


class Formatter:
    """Formats numbers for LaTeX and for plain text with a fixed number of significant digits."""

    def __init__(self, digits: int = 4, scales: Mapping[str, float] | None = None) -> None:
        if not 1 <= digits <= 15:
            raise ValueError(f"digits must be 1..15, got {digits}")
        self.digits = digits
        self.scales = dict(scales or {})
        # the same numbers are formatted again and again (a point's position in every step that
        # uses it, every value twice in a solution's two builds): each is worked out once
        self._numbers: dict[tuple[float, str, float, str], str] = {}
        self._others: dict[int, Formatter] = {}
        self._vectors: dict[tuple[tuple[float, ...], str], tuple[float, ...]] = {}
        self._split: dict[tuple[float, str, float], tuple[str, int] | None] = {}
        self._displays: dict[tuple[float | tuple[float, ...], str, float], str] = {}

    def with_digits(self, digits: int) -> Formatter:
        """The same formatter (scales) with ``digits`` significant digits, made once."""
        if digits == self.digits:
            return self
        found = self._others.get(digits)
        if found is None:
            found = self._others[digits] = Formatter(digits, self.scales)
        return found

    # --- cleaning -------------------------------------------------------------------------------

    def is_noise(self, value: float, unit: str, reference: float = 0.0) -> bool:
        """True when ``value`` is rounding noise next to the unit's scale or ``reference``."""
        scale = max(self.scales.get(unit, 0.0), abs(reference))
        return value == 0.0 or abs(value) <= NOISE * scale

    def clean(self, value: float, unit: str = "", reference: float = 0.0) -> float:
        return 0.0 if self.is_noise(value, unit, reference) else value

    def clean_vector(self, vector: Sequence[float], unit: str = "") -> tuple[float, ...]:
        key = (tuple(vector), unit)
        found = self._vectors.get(key)
        if found is None:
            length = math.sqrt(sum(x * x for x in vector))
            found = self._vectors[key] = tuple(self.clean(x, unit, length) for x in vector)
        return found

    # --- numbers --------------------------------------------------------------------------------

    def _parts(self, value: float, unit: str, reference: float) -> tuple[str, int] | None:
        key = (value, unit, reference)
        if key not in self._split:
            self._split[key] = _split(self.clean(value, unit, reference), self.digits)
        return self._split[key]

    def _number(self, value: float, unit: str, reference: float, power: str) -> str:
        """The rounded number, fixed-point or as ``power`` (mantissa {0}, exponent {1})."""
        key = (value, unit, reference, power)
        found = self._numbers.get(key)
        if found is None:
            found = self._numbers[key] = self._write(value, unit, reference, power)
        return found

    def _write(self, value: float, unit: str, reference: float, power: str) -> str:
        parts = self._parts(value, unit, reference)
        if parts is None:
            return "0"
        mantissa, exponent = parts
        if FIXED_LOW <= exponent < FIXED_HIGH:
            return self._fixed(mantissa, exponent)
        return power.format(mantissa, exponent)

    def text(self, value: float, unit: str = "", reference: float = 0.0) -> str:
        """Plain text: '-0.375', '12.31', '1.5 x 10^-7'."""
        return self._number(value, unit, reference, "{0} x 10^{1}")

    def latex(self, value: float, unit: str = "", reference: float = 0.0) -> str:
        """LaTeX: '-0.375', '1.5 \\cdot 10^{-7}'."""
        return self._number(value, unit, reference, r"{0} \cdot 10^{{{1}}}")

    def is_zero(self, value: float, unit: str = "", reference: float = 0.0) -> bool:
        """True when the value displays as 0 (noise, or smaller than the last digit shown)."""
        return self._parts(value, unit, reference) is None

    @staticmethod
    def _fixed(mantissa: str, exponent: int) -> str:
        negative = mantissa.startswith("-")
        digits = mantissa.lstrip("-").replace(".", "")
        point = 1 + exponent  # digits before the decimal point
        if point <= 0:
            body = "0." + "0" * (-point) + digits
        elif point >= len(digits):
            body = digits + "0" * (point - len(digits))
        else:
            body = digits[:point] + "." + digits[point:]
        return ("-" if negative else "") + body

    # --- with units -----------------------------------------------------------------------------

    def text_value(self, value: float, unit: str = "", reference: float = 0.0) -> str:
        number = self.text(value, unit, reference)
        if unit == "deg":
            return f"{number} deg"
        return f"{number} {unit}" if unit else number

    def text_vector(self, vector: Iterable[float], unit: str = "") -> str:
        values = tuple(vector)
        clean = self.clean_vector(values, unit)
        body = "(" + ", ".join(self.text(x) for x in clean) + ")"
        return f"{body} {unit}" if unit else body

    def display(self, value: float | tuple[float, ...], unit: str, reference: float = 0.0) -> str:
        """The ``Value.display`` string: plain text with the unit."""
        key = (value, unit, reference)
        found = self._displays.get(key)
        if found is None:
            if isinstance(value, tuple):
                found = self.text_vector(value, unit)
            else:
                found = self.text_value(value, unit, reference)
            self._displays[key] = found
        return found


def latex_unit(unit: str) -> str:
    """The unit typeset after a number (with a thin space), '' for a dimensionless value."""
    if not unit:
        return ""
    if unit == "deg":
        return LATEX_UNITS["deg"]
    return r"\," + LATEX_UNITS.get(unit, r"\mathrm{" + unit + "}")
