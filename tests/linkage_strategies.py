"""Hypothesis strategies for random six-bar linkages (Watt and Stephenson chains).

A six-bar is drawn as a random four-bar from ``tests.strategies.assemblable_presets(["four_bar"])``
(links ground, crank, coupler, rocker) plus a dyad X-Q-Y: link ``dyad_in`` = [X, Q] and link
``dyad_out`` = [Q, Y], with X a new point of one four-bar link and Y a new point of another. The
two links that carry X and Y become ternary. When they are adjacent in the four-bar (they share a
joint) the chain is Watt's, otherwise Stephenson's (ground-coupler or crank-rocker).

The driver is the four-bar's crank, or, when X is on the ground, sometimes the dyad's grounded link
``dyad_in``. Driving ``dyad_in`` of a ground-coupler Stephenson chain leaves the four-bar with no
driven link: its four moving links form one loop of four unknown links, which no dyad closes, so
the solver must use Newton-Raphson (the case the closed-form dyads cannot reach).

Every draw is posed consistently by construction (Q is the intersection of its two circles, never
near tangency: the dyad's triangle is kept away from flat) and is checked to assemble: the solver
analyses it at the drawn pose, and the condition number of its velocity equations is bounded
(``MAX_CONDITION``) so that property tests compare derivatives of a well-posed problem.
"""

from __future__ import annotations

import cmath
from dataclasses import dataclass
from typing import Any

from hypothesis import assume
from hypothesis import strategies as st

from solver.analysis import analyze
from solver.errors import KinematicsError
from solver.presets import build_preset
from solver.scene import parse_linkage
from tests.strategies import assemblable_presets

# Bound on the reported condition number of an accepted draw (a well-posed instant).
MAX_CONDITION = 1e4
FOUR_BAR_LINKS = ("ground", "crank", "coupler", "rocker")
# Links of the four-bar that share a joint (A, B, C, D): a dyad between them makes a Watt chain.
ADJACENT = {
    frozenset(("ground", "crank")),
    frozenset(("crank", "coupler")),
    frozenset(("coupler", "rocker")),
    frozenset(("rocker", "ground")),
}
ATTACHMENTS = [
    ("ground", "crank"),
    ("ground", "coupler"),
    ("ground", "rocker"),
    ("crank", "coupler"),
    ("crank", "rocker"),
    ("coupler", "rocker"),
]


@dataclass(frozen=True)
class SixBar:
    """A drawn six-bar scene document and how it was built."""

    chain: str  # "Watt" or "Stephenson"
    attached: tuple[str, str]  # the four-bar links that carry X and Y
    driver: str  # "crank" or "dyad_in"
    doc: dict[str, Any]

    def __repr__(self) -> str:  # hypothesis prints this on failure: enough to rebuild the case
        return f"SixBar({self.chain}, {self.attached}, driver={self.driver}, doc={self.doc!r})"


def _point_near(draw: st.DrawFn, first: complex, second: complex) -> complex:
    """A point in the frame of the segment first -> second (u along, v across, in its lengths)."""
    u = draw(st.floats(-0.5, 1.5))
    v = draw(st.floats(-1.0, 1.0))
    return first + complex(u, v) * (second - first)


def _circle_circle(p: complex, r_p: float, q: complex, r_q: float, left: bool) -> complex:
    d = abs(q - p)
    a = (d * d + r_p * r_p - r_q * r_q) / (2 * d)
    h = (r_p * r_p - a * a) ** 0.5
    return p + complex(a, h if left else -h) * (q - p) / d


@st.composite
def six_bars(draw: st.DrawFn) -> SixBar:
    """A random Watt or Stephenson six-bar that assembles at its drawn pose (see module doc)."""
    _, values = draw(assemblable_presets(["four_bar"]))
    doc = build_preset("four_bar", values)
    pts = {name: complex(x, y) for name, (x, y) in doc["points"].items()}
    size = max(abs(z - w) for z in pts.values() for w in pts.values())
    host, other = draw(st.sampled_from(ATTACHMENTS))
    links = doc["links"]

    def new_point(link: str) -> complex:
        first, second = (pts[p] for p in links[link]["points"][:2])
        z = _point_near(draw, first, second)
        # clear of the link's own points: no zero-length or nearly coincident pair on one link
        assume(all(abs(z - pts[p]) > 0.05 * size for p in links[link]["points"]))
        return z

    X, Y = new_point(host), new_point(other)
    d = abs(Y - X)
    assume(d > 0.1 * size)
    l_in = d * draw(st.floats(0.4, 2.5))
    low, high = abs(d - l_in), d + l_in
    l_out = low + (high - low) * draw(st.floats(0.15, 0.85))  # triangle XQY never flat
    Q = _circle_circle(X, l_in, Y, l_out, draw(st.booleans()))

    doc["points"] |= {name: [z.real, z.imag] for name, z in (("X", X), ("Y", Y), ("Q", Q))}
    links[host]["points"].append("X")
    links[other]["points"].append("Y")
    links["dyad_in"] = {"points": ["X", "Q"]}
    links["dyad_out"] = {"points": ["Q", "Y"]}
    doc["joints"] += [
        {"type": "revolute", "point": "X", "links": [host, "dyad_in"]},
        {"type": "revolute", "point": "Q", "links": ["dyad_in", "dyad_out"]},
        {"type": "revolute", "point": "Y", "links": ["dyad_out", other]},
    ]
    driver = "crank"
    if host == "ground" and draw(st.booleans()):
        driver = "dyad_in"
        doc["drivers"] = [{**doc["drivers"][0], "link": "dyad_in"}]
    chain = "Watt" if frozenset((host, other)) in ADJACENT else "Stephenson"
    doc["title"] = f"{chain} six-bar ({host}-{other}, driver {driver})"
    try:
        condition = analyze(parse_linkage(doc)).diagnostics.condition_number
    except KinematicsError:  # a singular draw: rare, and not what these strategies are for
        condition = None
    assume(condition is not None and condition < MAX_CONDITION)
    assert cmath.isfinite(Q)
    return SixBar(chain, (host, other), driver, doc)
