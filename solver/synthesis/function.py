"""Function generation: a four-bar whose rocker angle follows y = f(x) as the crank angle follows x.

x maps linearly onto the crank's angle theta_2 over the input range, y = f(x) onto the rocker's
angle theta_4 over the output range (both absolute, from the ground line A -> D). With the crank
a, coupler b, rocker c and ground d, the loop A B C D closes when Freudenstein's equation holds:

    K1 cos(theta_4) - K2 cos(theta_2) + K3 = cos(theta_2 - theta_4),
    K1 = d / a,  K2 = d / c,  K3 = (a^2 - b^2 + c^2 + d^2) / (2 a c),

linear in K1, K2, K3: three precision points (Chebyshev spacing over the x range by default)
give them, and a = d / K1, c = d / K2, b^2 = a^2 + c^2 + d^2 - 2 a c K3. A negative a (or c)
is a crank (rocker) pointing the other way: its link angle is theta_2 + 180 deg.

The function is read by the project's time-law parser (``solver.model.laws``, an ``ast``
whitelist to sympy, never ``eval``) with the variable x where a law has t.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass

import numpy as np

from solver.errors import InvalidExpression, InvalidScene
from solver.kinematics.rigid import Array
from solver.model.laws import TimeLaw, parse_time_law
from solver.synthesis.task import FunctionTask

_NAME = re.compile(r"[A-Za-z_][A-Za-z0-9_]*")
_T_WORD = re.compile(r"\bt\b")
_TOKEN = re.compile(r"[A-Za-z_][A-Za-z0-9_]*|.", re.DOTALL)
_SECONDS = re.compile(r"(x = \S+) s\b")


def chebyshev_spacing(low: float, high: float, n: int) -> tuple[float, ...]:
    """x_j = (low + high) / 2 - (high - low) / 2 cos((2 j - 1) pi / (2 n)), j = 1..n: the
    Chebyshev spacing of n precision points over [low, high], ascending."""
    middle, half = 0.5 * (low + high), 0.5 * (high - low)
    return tuple(middle - half * math.cos((2 * j - 1) * math.pi / (2 * n)) for j in range(1, n + 1))


def freudenstein_coefficients(
    crank_angles: Array, rocker_angles: Array
) -> tuple[float, float, float]:
    """K1, K2, K3 from K1 cos(theta_4) - K2 cos(theta_2) + K3 = cos(theta_2 - theta_4) at three
    precision points (``InvalidScene`` where the three equations are singular)."""
    matrix = np.column_stack(
        [np.cos(rocker_angles), -np.cos(crank_angles), np.ones_like(crank_angles)]
    )
    right = np.cos(crank_angles - rocker_angles)
    if np.linalg.cond(matrix) > 1e12:
        raise InvalidScene(
            "precision_points: Freudenstein's three equations are singular for these angles "
            "(the precision points give no four-bar); change the ranges"
        )
    k1, k2, k3 = np.linalg.solve(matrix, right)
    return float(k1), float(k2), float(k3)


def link_lengths(ground: float, k1: float, k2: float, k3: float) -> tuple[float, float, float]:
    """The signed crank a = d / K1, rocker c = d / K2 and the coupler b, b^2 = a^2 + c^2 + d^2 -
    2 a c K3 (``InvalidScene`` where no real coupler closes the loop)."""
    if abs(k1) < 1e-12 or abs(k2) < 1e-12:
        raise InvalidScene(
            f"Freudenstein's equation gives K1 = {k1:.6g}, K2 = {k2:.6g}: a crank or rocker of "
            "infinite length; change the ranges or the precision points"
        )
    a, c = ground / k1, ground / k2
    b_squared = a * a + c * c + ground * ground - 2.0 * a * c * k3
    if b_squared <= 1e-18 * ground * ground:
        raise InvalidScene(
            f"Freudenstein's equation gives K1 = {k1:.6g}, K2 = {k2:.6g}, K3 = {k3:.6g}, so "
            f"b^2 = a^2 + c^2 + d^2 - 2 a c K3 = {b_squared:.6g} m^2 <= 0: no coupler closes the "
            "loop; change the ranges or the precision points"
        )
    return a, math.sqrt(b_squared), c


def parse_function(text: str) -> TimeLaw:
    """The function f(x) read as a time law with x for t (``InvalidExpression`` pointing at the
    offending character, in x)."""
    for match in _NAME.finditer(text):
        if match.group() == "t":
            raise InvalidExpression(
                f"unknown name 't' at character {match.start()}; the function is written in x",
                match.start(),
                text,
            )
    law_text = "".join("t" if m.group() == "x" else m.group() for m in _TOKEN.finditer(text))
    try:
        return parse_time_law(law_text)
    except InvalidExpression as error:
        raise in_x(error, text) from None


def in_x(error: InvalidExpression, text: str) -> InvalidExpression:
    """The time-law parser's error about the function read with t for x, said in x (``sqrt(x -
    1.5) is not defined at x = 1``) about the text as written."""
    message = _SECONDS.sub(r"\1", _T_WORD.sub("x", error.message))
    return InvalidExpression(message, error.position, text)


class Scales:
    """The linear maps x -> theta_2 and y -> theta_4 of a function task."""

    def __init__(self, task: FunctionTask, law: TimeLaw) -> None:
        self.task, self.law = task, law
        x0, xf = task.x_range
        self.y0, self.yf = _value(law, x0, task.function), _value(law, xf, task.function)
        if self.y0 == self.yf:
            raise InvalidScene(
                f"function: f({x0:g}) = f({xf:g}) = {self.y0:.6g}: the output range cannot be "
                "mapped onto y (the function takes the same value at both ends of x_range)"
            )

    def crank(self, x: Array) -> Array:
        """theta_2 = theta_2s + (x - x0) / (xf - x0) (theta_2f - theta_2s)."""
        (x0, xf), (start, end) = self.task.x_range, self.task.input_range
        return start + (x - x0) / (xf - x0) * (end - start)

    def x_of(self, crank: Array) -> Array:
        """The inverse map theta_2 -> x."""
        (x0, xf), (start, end) = self.task.x_range, self.task.input_range
        return x0 + (crank - start) / (end - start) * (xf - x0)

    def rocker(self, y: Array) -> Array:
        """theta_4 = theta_4s + (y - y0) / (yf - y0) (theta_4f - theta_4s)."""
        start, end = self.task.output_range
        return start + (y - self.y0) / (self.yf - self.y0) * (end - start)

    def y_of(self, rocker: Array) -> Array:
        """The inverse map theta_4 -> y."""
        start, end = self.task.output_range
        return self.y0 + (rocker - start) / (end - start) * (self.yf - self.y0)

    def y(self, x: Array) -> Array:
        """f(x) (``InvalidExpression`` where it is undefined)."""
        try:
            value, _, _ = self.law.evaluate(np.asarray(x, dtype=float))
        except InvalidExpression as error:
            raise in_x(error, self.task.function) from None
        return value


def _value(law: TimeLaw, x: float, text: str) -> float:
    try:
        value, _, _ = law.evaluate(x)
    except InvalidExpression as error:
        raise in_x(error, text) from None
    return value


@dataclass(frozen=True)
class FunctionDesign:
    """A function task's design before any analysis: the precision points (x, y = f(x)), the
    crank's and the rocker's angles there (rad), Freudenstein's K1, K2, K3 and the signed crank
    a, coupler b and rocker c they give."""

    scales: Scales
    x: Array
    y: Array
    crank: Array
    rocker: Array
    k: tuple[float, float, float]
    a: float
    b: float
    c: float


def design_function(task: FunctionTask) -> FunctionDesign:
    """Freudenstein's equation at the task's precision points (given, or Chebyshev spacing over
    the x range) solved for K1, K2, K3, and the link lengths from them."""
    scales = Scales(task, parse_function(task.function))
    low, high = sorted(task.x_range)
    xs: Array = np.array(task.precision_x or chebyshev_spacing(low, high, 3))
    ys = scales.y(xs)
    theta2, theta4 = scales.crank(xs), scales.rocker(ys)
    k = freudenstein_coefficients(theta2, theta4)
    a, b, c = link_lengths(task.ground_length, *k)
    return FunctionDesign(scales, xs, ys, theta2, theta4, k, a, b, c)
