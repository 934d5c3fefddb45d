"""Hypothesis strategies for random linkages beyond the presets: six-bars (Watt and Stephenson
chains), a block in a slotted lever (prismatic joint), and ``linkages(family)``, which draws any
preset, the block or a six-bar at a random omega and alpha, below a bound on the condition number.

A six-bar is drawn as a random four-bar from ``tests.strategies.assemblable_presets(["four_bar"])``
(links ground, crank, coupler, rocker) plus a dyad X-Q-Y: link ``dyad_in`` = [X, Q] and link
``dyad_out`` = [Q, Y], with X a new point of one four-bar link and Y a new point of another. The
two links that carry X and Y become ternary. When they are adjacent in the four-bar (they share a
joint) the chain is Watt's, otherwise Stephenson's (ground-coupler or crank-rocker).

The driver is the four-bar's crank, or, when X is on the ground, sometimes the dyad's grounded link
``dyad_in``. Driving ``dyad_in`` of a ground-coupler Stephenson chain leaves the four-bar with no
driven link: its moving links (crank, coupler, rocker, dyad_out) form one group that no dyad
closes, so the solver must use Newton-Raphson (the case the closed-form dyads cannot reach).

Every draw is posed consistently by construction (Q is the intersection of its two circles, never
near tangency: the dyad's triangle is kept away from flat) and is checked to assemble: the solver
analyses it at the drawn pose, and the condition number of its velocity equations is bounded
(``MAX_CONDITION``) so that property tests compare derivatives of a well-posed problem.
"""

from __future__ import annotations

import copy
import math
from dataclasses import dataclass
from typing import Any

from hypothesis import assume
from hypothesis import strategies as st

from solver.analysis.instant import analyze
from solver.errors import KinematicsError
from solver.model.scene import parse_linkage
from solver.teaching.presets import PRESETS, build_preset
from tests.strategies import assemblable_presets

# Bound on the reported condition number of an accepted draw (a well-posed instant).
MAX_CONDITION = 1e4
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


def stephenson_six_bar(
    points: dict[str, list[float]], driver: dict[str, Any], title: str | None = None
) -> dict[str, Any]:
    """The Stephenson six-bar ``six_bars(newton=True)`` draws, at given ``points`` (A, B, C, D,
    X, Q, Y): the four-bar A-B-C-D with the dyad X-Q-Y from the ground (X) to the coupler (Y),
    driven by ``driver`` (a scene driver, on ``dyad_in``)."""
    pairs = (
        ("A", ["ground", "crank"]),
        ("B", ["crank", "coupler"]),
        ("C", ["coupler", "rocker"]),
        ("D", ["rocker", "ground"]),
        ("X", ["ground", "dyad_in"]),
        ("Q", ["dyad_in", "dyad_out"]),
        ("Y", ["dyad_out", "coupler"]),
    )
    return {
        "kind": "linkage",
        **({"title": title} if title else {}),
        "points": points,
        "links": {
            "ground": {"points": ["A", "D", "X"], "ground": True},
            "crank": {"points": ["A", "B"]},
            "coupler": {"points": ["B", "C", "Y"]},
            "rocker": {"points": ["D", "C"]},
            "dyad_in": {"points": ["X", "Q"]},
            "dyad_out": {"points": ["Q", "Y"]},
        },
        "joints": [{"type": "revolute", "point": p, "links": links} for p, links in pairs],
        "drivers": [driver],
    }


@st.composite
def six_bars(
    draw: st.DrawFn, max_condition: float = MAX_CONDITION, newton: bool | None = None
) -> SixBar:
    """A random Watt or Stephenson six-bar that assembles at its drawn pose (see module doc), with
    the condition number of its velocity equations below ``max_condition``.

    ``newton=True`` draws only the Stephenson chains the solver must close by Newton-Raphson
    (ground-coupler, driven by ``dyad_in``), ``False`` only those closed by dyads, ``None`` both.
    """
    _, values = draw(assemblable_presets(["four_bar"]))
    doc = build_preset("four_bar", values)
    pts = {name: complex(x, y) for name, (x, y) in doc["points"].items()}
    size = max(abs(z - w) for z in pts.values() for w in pts.values())
    host, other = ("ground", "coupler") if newton else draw(st.sampled_from(ATTACHMENTS))
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
    if newton or (newton is None and host == "ground" and draw(st.booleans())):
        driver = "dyad_in"
        doc["drivers"] = [{**doc["drivers"][0], "link": "dyad_in"}]
    chain = "Watt" if frozenset((host, other)) in ADJACENT else "Stephenson"
    doc["title"] = f"{chain} six-bar ({host}-{other}, driver {driver})"
    assume(condition_number(doc) < max_condition)
    return SixBar(chain, (host, other), driver, doc)


def condition_number(doc: dict[str, Any]) -> float:
    """The reported condition number of the drawn pose's velocity equations (inf if singular)."""
    try:
        condition = analyze(parse_linkage(doc)).diagnostics.condition_number
    except KinematicsError:  # a singular draw: rare, and not what these strategies are for
        return math.inf
    return math.inf if condition is None else condition


def block_in_lever(doc: dict[str, Any]) -> dict[str, Any]:
    """An inverted slider-crank preset with its pin-in-slot at A replaced by a block.

    The block carries A only: a revolute joint to the crank and a prismatic joint in the lever's
    slot, so it turns with the lever (a prismatic joint and a one-point link, which no preset has).
    """
    doc = copy.deepcopy(doc)
    slider = next(j for j in doc["joints"] if j["type"] == "slider")
    guide, follower = slider["links"]
    doc["links"]["block"] = {"points": [slider["point"]]}
    doc["joints"].remove(slider)
    doc["joints"] += [
        {"type": "revolute", "point": slider["point"], "links": [follower, "block"]},
        {**slider, "type": "prismatic", "links": [guide, "block"]},
    ]
    doc["title"] = "inverted slider-crank with a block in the lever's slot"
    return doc


# seed004 is a four-bar with masses and a load: the four_bar family covers its kinematics.
FAMILIES = (*(name for name in PRESETS if name != "seed004"), "block_in_lever", "six_bar")


def _rate(largest: float) -> st.SearchStrategy[float]:
    """0, or a magnitude in [1e-3, largest] with either sign (no subnormal rates: their products
    underflow, which says nothing about the kinematics; extreme rates are tested on purpose)."""
    magnitude = st.floats(1e-3, largest)
    return st.just(0.0) | magnitude | magnitude.map(lambda x: -x)


@st.composite
def _with_rates(draw: st.DrawFn, docs: st.SearchStrategy[dict[str, Any]]) -> dict[str, Any]:
    doc = draw(docs)
    doc["drivers"][0] |= {"omega": draw(_rate(50.0)), "alpha": draw(_rate(100.0))}
    return doc


def linkages(
    family: str, max_condition: float = MAX_CONDITION, newton: bool | None = None
) -> st.SearchStrategy[dict[str, Any]]:
    """Scene documents of one family (a preset name, ``block_in_lever`` or ``six_bar``) whose
    drawn pose assembles with a velocity condition number below ``max_condition``, driven at a
    random omega and alpha. ``newton`` restricts the six-bars as in ``six_bars``."""
    if family == "six_bar":
        docs = six_bars(max_condition, newton).map(lambda s: s.doc)
    else:
        name = "inverted_slider_crank" if family == "block_in_lever" else family
        docs = assemblable_presets([name]).map(lambda nv: build_preset(*nv))
        if family == "block_in_lever":
            docs = docs.map(block_in_lever)
        docs = docs.filter(lambda doc: condition_number(doc) < max_condition)
    return _with_rates(docs)
