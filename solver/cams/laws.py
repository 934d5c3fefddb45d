"""The follower motion laws of cam design, in closed form over the normalised segment angle.

Each law maps x = (theta - theta_0) / beta in [0, 1] (the cam's turn through the segment as a
fraction of its duration beta) to the normalised lift y(x) in [0, 1] with y(0) = 0 and
y(1) = 1, and gives the derivatives y', y'', y''' with respect to x. A rise of lift h then
moves the follower s = h y, with ds/dtheta = h y' / beta, d2s/dtheta2 = h y'' / beta^2 and
d3s/dtheta3 = h y''' / beta^3 (Norton, Design of Machinery, ch. 8; Uicker, Pennock & Shigley,
Theory of Machines and Mechanisms, ch. 6). The peak factors C_v = max y', C_a = max |y''|
are the textbook's (Norton's table 8-3).

The modified trapezoid and modified sine are built, as Norton builds them, from pieces of
constant or sinusoidal acceleration; each piece is integrated in closed form and the pieces'
amplitude is fixed by y(1) = 1.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import Literal, NamedTuple, get_args

import numpy as np

Array = np.ndarray

LawName = Literal[
    "uniform",
    "harmonic",
    "cycloidal",
    "polynomial_345",
    "polynomial_4567",
    "modified_trapezoid",
    "modified_sine",
]
LAW_NAMES: tuple[LawName, ...] = get_args(LawName)

PI = math.pi


class NormalisedMotion(NamedTuple):
    """y(x) and its derivatives y', y'', y''' with respect to x = (theta - theta_0) / beta."""

    y: Array
    dy: Array
    d2y: Array
    d3y: Array


def uniform(x: Array) -> NormalisedMotion:
    """Constant velocity: y = x, y' = 1, y'' = y''' = 0 (infinite acceleration at the ends)."""
    return NormalisedMotion(x.copy(), np.ones_like(x), np.zeros_like(x), np.zeros_like(x))


def harmonic(x: Array) -> NormalisedMotion:
    """Simple harmonic: y = (1 - cos pi x) / 2, y' = (pi / 2) sin pi x,
    y'' = (pi^2 / 2) cos pi x, y''' = -(pi^3 / 2) sin pi x (C_v = pi/2, C_a = pi^2/2)."""
    c, s = np.cos(PI * x), np.sin(PI * x)
    return NormalisedMotion((1.0 - c) / 2.0, PI / 2.0 * s, PI**2 / 2.0 * c, -(PI**3) / 2.0 * s)


def cycloidal(x: Array) -> NormalisedMotion:
    """Cycloidal: y = x - sin(2 pi x) / (2 pi), y' = 1 - cos 2 pi x, y'' = 2 pi sin 2 pi x,
    y''' = 4 pi^2 cos 2 pi x (C_v = 2, C_a = 2 pi)."""
    c, s = np.cos(2.0 * PI * x), np.sin(2.0 * PI * x)
    return NormalisedMotion(x - s / (2.0 * PI), 1.0 - c, 2.0 * PI * s, 4.0 * PI**2 * c)


def polynomial_345(x: Array) -> NormalisedMotion:
    """3-4-5 polynomial: y = 10 x^3 - 15 x^4 + 6 x^5, y' = 30 x^2 - 60 x^3 + 30 x^4,
    y'' = 60 x - 180 x^2 + 120 x^3, y''' = 60 - 360 x + 360 x^2 (C_v = 1.875, C_a = 5.7735)."""
    return NormalisedMotion(
        x**3 * (10.0 + x * (-15.0 + 6.0 * x)),
        x**2 * (30.0 + x * (-60.0 + 30.0 * x)),
        x * (60.0 + x * (-180.0 + 120.0 * x)),
        60.0 + x * (-360.0 + 360.0 * x),
    )


def polynomial_4567(x: Array) -> NormalisedMotion:
    """4-5-6-7 polynomial: y = 35 x^4 - 84 x^5 + 70 x^6 - 20 x^7,
    y' = 140 x^3 - 420 x^4 + 420 x^5 - 140 x^6, y'' = 420 x^2 - 1680 x^3 + 2100 x^4 - 840 x^5,
    y''' = 840 x - 5040 x^2 + 8400 x^3 - 4200 x^4 (zero jerk at both ends)."""
    return NormalisedMotion(
        x**4 * (35.0 + x * (-84.0 + x * (70.0 - 20.0 * x))),
        x**3 * (140.0 + x * (-420.0 + x * (420.0 - 140.0 * x))),
        x**2 * (420.0 + x * (-1680.0 + x * (2100.0 - 840.0 * x))),
        x * (840.0 + x * (-5040.0 + x * (8400.0 - 4200.0 * x))),
    )


@dataclass(frozen=True)
class AccelerationPieces:
    """A normalised acceleration built from pieces y''(x) = A (p + q sin k u + r cos k u),
    u = x - x_0 on [x_0, x_1), each integrated in closed form from the previous piece's end:

        y'(x) = y'_0 + A (p u + q (1 - cos k u) / k + r sin(k u) / k)
        y(x) = y_0 + y'_0 u + A (p u^2 / 2 + q (u / k - sin(k u) / k^2) + r (1 - cos k u) / k^2)
        y'''(x) = A k (q cos k u - r sin k u)

    with y(0) = y'(0) = 0 and the amplitude A fixed by y(1) = 1."""

    starts: tuple[float, ...]
    p: tuple[float, ...]
    q: tuple[float, ...]
    r: tuple[float, ...]
    k: tuple[float, ...]

    def _unit(self, i: int, u: Array | float) -> tuple[Array, Array, Array, Array]:
        """Piece i's increments at unit amplitude: (y - y_0 - y'_0 u, y' - y'_0, y'', y''')."""
        p, q, r, k = self.p[i], self.q[i], self.r[i], self.k[i]
        ku = k * np.asarray(u, dtype=float)
        s, c = np.sin(ku), np.cos(ku)
        dy = p * u + q * (1.0 - c) / k + r * s / k
        y = p * u**2 / 2.0 + q * (u / k - s / k**2) + r * (1.0 - c) / k**2
        return y, dy, p + q * s + r * c, k * (q * c - r * s)

    def starting_values(self) -> tuple[float, list[float], list[float]]:
        """The amplitude A and each piece's y_0 and y'_0 (chained from y(0) = y'(0) = 0)."""
        y0, v0 = [0.0], [0.0]
        ends = (*self.starts[1:], 1.0)
        for i, end in enumerate(ends):
            u = end - self.starts[i]
            y, dy, _, _ = self._unit(i, u)
            y0.append(y0[-1] + v0[-1] * u + float(y))
            v0.append(v0[-1] + float(dy))
        amplitude = 1.0 / y0[-1]
        return amplitude, [amplitude * y for y in y0], [amplitude * v for v in v0]

    def __call__(self, x: Array) -> NormalisedMotion:
        amplitude, y0, v0 = self.starting_values()
        i = np.clip(np.searchsorted(self.starts, x, side="right") - 1, 0, len(self.starts) - 1)
        u = x - np.asarray(self.starts)[i]
        y, dy, d2y, d3y = (np.zeros_like(x) for _ in range(4))
        for piece in range(len(self.starts)):
            at = i == piece
            py, pdy, pd2y, pd3y = self._unit(piece, u[at])
            y[at] = y0[piece] + v0[piece] * u[at] + amplitude * py
            dy[at] = v0[piece] + amplitude * pdy
            d2y[at] = amplitude * pd2y
            d3y[at] = amplitude * pd3y
        return NormalisedMotion(y, dy, d2y, d3y)


# Norton's modified trapezoid: a quarter sine up over x < 1/8, constant to 3/8, a half cosine
# through zero to 5/8, constant to 7/8, a quarter cosine back to zero.
MODIFIED_TRAPEZOID = AccelerationPieces(
    starts=(0.0, 0.125, 0.375, 0.625, 0.875),
    p=(0.0, 1.0, 0.0, -1.0, 0.0),
    q=(1.0, 0.0, 0.0, 0.0, 0.0),
    r=(0.0, 0.0, 1.0, 0.0, -1.0),
    k=(4.0 * PI, 1.0, 4.0 * PI, 1.0, 4.0 * PI),
)
# Norton's modified sine: a quarter sine of period 1/2 up to x = 1/8, a half cosine of period
# 3/2 through zero to 7/8, a quarter cosine of period 1/2 back to zero.
MODIFIED_SINE = AccelerationPieces(
    starts=(0.0, 0.125, 0.875),
    p=(0.0, 0.0, 0.0),
    q=(1.0, 0.0, 0.0),
    r=(0.0, 1.0, -1.0),
    k=(4.0 * PI, 4.0 * PI / 3.0, 4.0 * PI),
)


def modified_trapezoid(x: Array) -> NormalisedMotion:
    """Modified trapezoid (Norton): y'' = A sin 4 pi x (x < 1/8), A (to 3/8),
    A cos 4 pi (x - 3/8) (to 5/8), -A (to 7/8), -A cos 4 pi (x - 7/8) (to 1), integrated
    piecewise in closed form with A = 4.8881 from y(1) = 1 (C_v = 2, C_a = 4.8881)."""
    return MODIFIED_TRAPEZOID(x)


def modified_sine(x: Array) -> NormalisedMotion:
    """Modified sine (Norton): y'' = A sin 4 pi x (x < 1/8), A cos (4 pi / 3)(x - 1/8)
    (to 7/8), -A cos 4 pi (x - 7/8) (to 1), integrated piecewise in closed form with
    A = 5.5280 from y(1) = 1 (C_v = 1.7596, C_a = 5.5280)."""
    return MODIFIED_SINE(x)


LAWS: dict[LawName, Callable[[Array], NormalisedMotion]] = {
    "uniform": uniform,
    "harmonic": harmonic,
    "cycloidal": cycloidal,
    "polynomial_345": polynomial_345,
    "polynomial_4567": polynomial_4567,
    "modified_trapezoid": modified_trapezoid,
    "modified_sine": modified_sine,
}
