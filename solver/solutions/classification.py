"""Classification of each four-bar loop (kind ``classification``): Grashof's criterion with the
numbers, and the transmission angle mu at this pose and over the cycle.

Grashof: with s the shortest and l the longest link, p and q the others, s + l <= p + q lets the
shortest link turn fully (a crank-rocker when it is the crank). The transmission angle mu between
coupler (length b) and rocker (length c) follows from the diagonal BD by the law of cosines,
cos mu = (b^2 + c^2 - BD^2) / (2 b c); when the crank (length a, ground g) turns fully, BD runs
from |g - a| to g + a, which gives mu's extremes over the cycle.
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np

from solver.kinematics.four_bar import FourBarLoop
from solver.solutions import latex as tex
from solver.solutions.builder import StepBuilder
from solver.solutions.equation import Equation, Num, Ref, Sym
from solver.solutions.linkage import LinkageContext
from solver.solutions.model import Step

ROLES = ("ground", "crank", "coupler", "rocker")
MEANING = {
    "Grashof crank-rocker": "the shortest link is the crank: it turns fully and the rocker "
    "rocks between two limit positions",
    "Grashof double-crank": "the shortest link is the ground: crank and rocker both turn fully",
    "Grashof double-rocker": "the shortest link is the coupler: it turns fully relative to the "
    "others, but crank and rocker only rock",
    "Grashof rocker-crank": "the shortest link is the rocker: it turns fully, the crank rocks",
    "non-Grashof triple-rocker": "no link turns fully: the crank rocks between limit positions",
    "change-point": "s + l = p + q: the links can fold flat (a change point)",
}
GOOD = (40.0, 140.0)  # deg: the usual limits of a transmission angle that transmits well


def _cos_mu(b: StepBuilder, name: str, diagonal: Ref, coupler: Ref, rocker: Ref) -> Ref:
    """cos mu = (b^2 + c^2 - BD^2) / (2 b c) with its checks; returns cos mu."""
    b2 = b.value(f"{coupler.key}^2", b.scalar(coupler) ** 2, "m^2")
    c2 = b.value(f"{rocker.key}^2", b.scalar(rocker) ** 2, "m^2")
    d2 = b.value(f"{diagonal.key}^2", b.scalar(diagonal) ** 2, "m^2")
    num = b.value(f"{name}: numerator", b.scalar(b2) + b.scalar(c2) - b.scalar(d2), "m^2")
    den = b.value(f"{name}: 2bc", 2 * b.scalar(coupler) * b.scalar(rocker), "m^2")
    cos = b.value(f"cos {name}", b.scalar(num) / b.scalar(den), "")
    b.check("product", b2, coupler, coupler)
    b.check("product", c2, rocker, rocker)
    b.check("product", d2, diagonal, diagonal)
    b.check("sum", num, b2, c2, -d2)
    b.check("product", den, coupler, rocker, factor=2.0)
    b.check("quotient", cos, num, den)
    return cos


def _angle(
    b: StepBuilder,
    name: str,
    cos: Ref,
    source: tuple[str | int, ...] | None = None,
    solver: float | None = None,
) -> Ref:
    """mu = arccos(cos mu) (the solver's number where it has one), checked through
    (cos mu, sin mu) = e^(i mu)."""
    value = math.acos(max(-1.0, min(1.0, b.scalar(cos)))) if solver is None else solver
    mu = b.value(name, value, "rad", source)
    one = b.value("1", 1.0, "")
    unit = b.value(f"e^(i {name})", (math.cos(value), math.sin(value)), "")
    b.check("phasor", unit, one, mu)
    b.check("sum", cos, unit[0])
    return mu


class Grashof(NamedTuple):
    """Grashof's criterion as put: the roles of the shortest s, the longest l and the others p, q,
    s + l and p + q, and how they compare ('<', '=' or '>')."""

    s: str
    p: str
    q: str
    l: str  # noqa: E741 (the textbook's letter)
    sl: Ref
    pq: Ref
    relation: str


class Transmission(NamedTuple):
    """The transmission angle now: the joints B (crank-coupler) and D (rocker-ground), the
    diagonal |BD|, cos mu and mu."""

    joint_b: str
    joint_d: str
    bd: Ref
    cos: Ref
    mu: Ref


def classification_steps(ctx: LinkageContext) -> list[Step]:
    """One step per four-bar loop: Grashof's criterion, the transmission angle now and, when the
    crank turns fully, over the cycle."""
    return [
        _classification_step(ctx, index, loop)
        for index, loop in enumerate(ctx.analysis.four_bar_loops)
    ]


def _classification_step(ctx: LinkageContext, index: int, loop: FourBarLoop) -> Step:
    """Grashof's criterion s + l <= p + q and the transmission angle of one four-bar loop."""
    src = ("four_bar_loops", index)
    b = ctx.builder("classification", f"Classification of the four-bar {', '.join(loop.links)}")
    keys = {}
    for role, link, length in zip(ROLES, loop.links, loop.lengths, strict=True):
        keys[role] = b.value(f"{role} ({link})", length, "m", (*src, "lengths", role))
    _write_grashof(b, loop, keys, _grashof_values(b, loop, keys))
    _write_transmission(ctx, b, _transmission_values(ctx, b, loop, keys, src))
    if loop.grashof in ("Grashof crank-rocker", "Grashof double-crank"):
        near, far = _diagonal_range(b, keys)
        extremes = [
            _angle(b, label, _cos_mu(b, label, side, keys["coupler"], keys["rocker"]))
            for label, side in (("mu_min", near), ("mu_max", far))
        ]
        _write_cycle(ctx, b, (near, far), extremes)
    else:
        b.say(
            "The crank does not turn fully, so the transmission angle is only defined between "
            "the limit positions of the motion."
        )
    return b.build()


def _grashof_values(b: StepBuilder, loop: FourBarLoop, keys: dict[str, Ref]) -> Grashof:
    """s + l and p + q from the lengths sorted, with their checks."""
    s, p, q, l_ = sorted(ROLES, key=lambda r: loop.lengths[ROLES.index(r)])
    sl = b.value("s + l", b.scalar(keys[s]) + b.scalar(keys[l_]), "m")
    pq = b.value("p + q", b.scalar(keys[p]) + b.scalar(keys[q]), "m")
    b.check("sum", sl, keys[s], keys[l_])
    b.check("sum", pq, keys[p], keys[q])
    relation = (
        "=" if loop.grashof == "change-point" else ("<" if b.scalar(sl) < b.scalar(pq) else ">")
    )
    return Grashof(s, p, q, l_, sl, pq, relation)


def _write_grashof(b: StepBuilder, loop: FourBarLoop, keys: dict[str, Ref], g: Grashof) -> None:
    """Write s + l against p + q and the class it gives."""
    sl = Equation.of("s + l", (Num(keys[g.s]), " + ", Num(keys[g.l])), Num(g.sl, unit=True))
    pq = Equation.of("p + q", (Num(keys[g.p]), " + ", Num(keys[g.q])), Num(g.pq, unit=True))
    b.line("&", sl, rf" \; {g.relation} \; ", pq)
    b.line(rf"&\Rightarrow \text{{{tex.escape_text(loop.grashof)}}}")
    b.say(
        f"Grashof's criterion: the shortest link ({g.s}, ",
        Num(keys[g.s], unit=True),
        f") plus the longest ({g.l}, ",
        Num(keys[g.l], unit=True),
        ") is ",
        Num(g.sl, unit=True),
        f"; the other two ({g.p}, {g.q}) add up to ",
        Num(g.pq, unit=True),
        f"; s + l {g.relation} p + q: {loop.grashof}, {MEANING[loop.grashof]}.",
    )


def _transmission_values(
    ctx: LinkageContext,
    b: StepBuilder,
    loop: FourBarLoop,
    keys: dict[str, Ref],
    src: tuple[str | int, ...],
) -> Transmission:
    """cos mu = (b^2 + c^2 - BD^2) / (2 b c) at this pose, mu the solver's value."""
    crank, coupler, rocker = loop.links[1], loop.links[2], loop.links[3]
    pins = ctx.scene.links[coupler].points
    joint_b = next(p for p in pins if p in ctx.scene.links[crank].points)
    fixed = ctx.scene.links[ctx.scene.ground].points
    joint_d = next(p for p in ctx.scene.links[rocker].points if p in fixed)
    diagonal = float(np.hypot(*(ctx.pos(joint_d) - ctx.pos(joint_b))))
    bd = b.value(f"|{joint_b}{joint_d}|", diagonal, "m")
    cos_now = _cos_mu(b, "mu", bd, keys["coupler"], keys["rocker"])
    mu = _angle(b, "mu", cos_now, (*src, "transmission_angle"), float(loop.transmission_angle))
    return Transmission(joint_b, joint_d, bd, cos_now, mu)


def _write_transmission(ctx: LinkageContext, b: StepBuilder, t: Transmission) -> None:
    """Write cos mu by the law of cosines and mu in rad and degrees."""
    bd_tex = f"{tex.name(t.joint_b)}{tex.name(t.joint_d)}"
    bd = f"{t.joint_b}{t.joint_d}"
    degrees = math.degrees(b.scalar(t.mu))
    law_of_cosines = Equation.of(
        Sym(r"\cos\mu", "cos mu"),
        Sym(rf"\frac{{b^2 + c^2 - |{bd_tex}|^2}}{{2bc}}", f"(b^2 + c^2 - |{bd}|^2)/(2 b c)"),
        Num(t.cos),
    )
    b.line(
        "&",
        law_of_cosines,
        r" \;\Rightarrow\; \mu = ",
        Num(t.mu, unit=True),
        rf" = {ctx.fmt.latex(degrees)}{{}}^{{\circ}}",
    )
    b.say(
        f"Transmission angle now (between coupler and rocker): |{bd}| = ",
        Num(t.bd, unit=True),
        ", ",
        law_of_cosines,
        f", mu = {ctx.fmt.text(degrees)} deg.",
    )


def _diagonal_range(b: StepBuilder, keys: dict[str, Ref]) -> tuple[Ref, Ref]:
    """|g - a| <= |BD| <= g + a while the crank (a) turns fully about the ground (g)."""
    g, a = b.scalar(keys["ground"]), b.scalar(keys["crank"])
    near = b.value("g - a", abs(g - a), "m")
    far = b.value("g + a", g + a, "m")
    b.check("sum", far, keys["ground"], keys["crank"])
    if g >= a:
        b.check("sum", near, keys["ground"], -keys["crank"])
    else:
        b.check("sum", near, keys["crank"], -keys["ground"])
    return near, far


def _write_cycle(
    ctx: LinkageContext, b: StepBuilder, diagonal: tuple[Ref, Ref], extremes: list[Ref]
) -> None:
    """Write mu's range over a turn of the crank and whether it stays within 40 to 140 deg."""
    near, far = diagonal
    lo, hi = (math.degrees(b.scalar(k)) for k in extremes)
    b.line(
        r"&|BD| \in [",
        Num(near),
        ", ",
        Num(far),
        rf"]\,\mathrm{{m}} \;\Rightarrow\; \mu_{{\min}} = {ctx.fmt.latex(lo)}{{}}^{{\circ}}, "
        rf"\; \mu_{{\max}} = {ctx.fmt.latex(hi)}{{}}^{{\circ}}",
    )
    worst = max(abs(90.0 - lo), abs(90.0 - hi))
    verdict = (
        "within the usual 40 to 140 deg: the linkage transmits force well all round"
        if GOOD[0] <= lo and hi <= GOOD[1]
        else "outside the usual 40 to 140 deg at times: near there the rocker is driven "
        "poorly (a small turning moment for a large force along the coupler)"
    )
    b.say(
        "Over a full turn of the crank the diagonal runs from |g - a| = ",
        Num(near, unit=True),
        " (crank along the ground, towards D) to g + a = ",
        Num(far, unit=True),
        f", so mu runs from {ctx.fmt.text(lo)} to {ctx.fmt.text(hi)} deg (at most "
        f"{ctx.fmt.text(worst)} deg from 90 deg), {verdict}.",
    )
