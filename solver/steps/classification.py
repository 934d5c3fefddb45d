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

import numpy as np

from solver.steps import latex as tex
from solver.steps.builder import StepBuilder
from solver.steps.linkage import LinkageContext
from solver.steps.model import Step

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


def _cos_mu(b: StepBuilder, name: str, diagonal: str, coupler: str, rocker: str) -> str:
    """cos mu = (b^2 + c^2 - BD^2) / (2 b c) with its checks; returns the key of cos mu."""
    b2 = b.put(f"{coupler}^2", b.scalar(coupler) ** 2, "m^2")
    c2 = b.put(f"{rocker}^2", b.scalar(rocker) ** 2, "m^2")
    d2 = b.put(f"{diagonal}^2", b.scalar(diagonal) ** 2, "m^2")
    num = b.put(f"{name}: numerator", b.scalar(b2) + b.scalar(c2) - b.scalar(d2), "m^2")
    den = b.put(f"{name}: 2bc", 2 * b.scalar(coupler) * b.scalar(rocker), "m^2")
    cos = b.put(f"cos {name}", b.scalar(num) / b.scalar(den), "")
    b.check("product", b2, coupler, coupler)
    b.check("product", c2, rocker, rocker)
    b.check("product", d2, diagonal, diagonal)
    b.check("sum", num, b2, c2, f"-{d2}")
    b.check("product", den, coupler, rocker, factor=2.0)
    b.check("quotient", cos, num, den)
    return cos


def _angle(
    b: StepBuilder,
    name: str,
    cos: str,
    source: tuple[str | int, ...] | None = None,
    solver: float | None = None,
) -> str:
    """mu = arccos(cos mu) (the solver's number where it has one), checked through
    (cos mu, sin mu) = e^(i mu)."""
    value = math.acos(max(-1.0, min(1.0, b.scalar(cos)))) if solver is None else solver
    mu = b.put(name, value, "rad", source)
    one = b.put("1", 1.0, "")
    unit = b.put(f"e^(i {name})", (math.cos(value), math.sin(value)), "")
    b.check("phasor", unit, one, mu)
    b.check("sum", cos, f"{unit}[0]")
    return mu


def classification_steps(ctx: LinkageContext) -> list[Step]:
    out = []
    for index, loop in enumerate(ctx.analysis.four_bar_loops):
        src = ("four_bar_loops", index)
        title = f"Classification of the four-bar {', '.join(loop.links)}"
        b = ctx.builder("classification", title)
        keys = {}
        for role, link, length in zip(ROLES, loop.links, loop.lengths, strict=True):
            keys[role] = b.put(f"{role} ({link})", length, "m", (*src, "lengths", role))
        ordered = sorted(ROLES, key=lambda r: loop.lengths[ROLES.index(r)])
        s, p, q, l_ = ordered
        sl = b.put("s + l", b.scalar(keys[s]) + b.scalar(keys[l_]), "m")
        pq = b.put("p + q", b.scalar(keys[p]) + b.scalar(keys[q]), "m")
        b.check("sum", sl, keys[s], keys[l_])
        b.check("sum", pq, keys[p], keys[q])
        relation = (
            "=" if loop.grashof == "change-point" else ("<" if b.scalar(sl) < b.scalar(pq) else ">")
        )
        b.line(
            rf"&s + l = {b.num(keys[s])} + {b.num(keys[l_])} = {b.numu(sl)} \; {relation} \; "
            rf"p + q = {b.num(keys[p])} + {b.num(keys[q])} = {b.numu(pq)}"
        )
        b.line(rf"&\Rightarrow \text{{{tex.escape_text(loop.grashof)}}}")
        b.say(
            f"Grashof's criterion: the shortest link ({s}, {b.txt(keys[s])}) plus the longest "
            f"({l_}, {b.txt(keys[l_])}) is {b.txt(sl)}; the other two ({p}, {q}) add up to "
            f"{b.txt(pq)}; s + l {relation} p + q: {loop.grashof}, {MEANING[loop.grashof]}."
        )
        crank, coupler, rocker = loop.links[1], loop.links[2], loop.links[3]
        pins = ctx.scene.links[coupler].points
        joint_b = next(p for p in pins if p in ctx.scene.links[crank].points)
        fixed = ctx.scene.links[ctx.scene.ground].points
        joint_d = next(p for p in ctx.scene.links[rocker].points if p in fixed)
        diagonal = float(np.hypot(*(ctx.pos(joint_d) - ctx.pos(joint_b))))
        bd = b.put(f"|{joint_b}{joint_d}|", diagonal, "m")
        cos_now = _cos_mu(b, "mu", bd, keys["coupler"], keys["rocker"])
        mu = _angle(b, "mu", cos_now, (*src, "transmission_angle"), loop.transmission_angle)
        b.line(
            rf"&\cos\mu = \frac{{b^2 + c^2 - |{tex.name(joint_b)}{tex.name(joint_d)}|^2}}{{2bc}} = "
            rf"{b.num(cos_now)} \;\Rightarrow\; \mu = {b.numu(mu)} = "
            rf"{ctx.fmt.latex(math.degrees(b.scalar(mu)))}{{}}^{{\circ}}"
        )
        b.say(
            f"Transmission angle now (between coupler and rocker): |{joint_b}{joint_d}| = "
            f"{b.txt(bd)}, cos mu = (b^2 + c^2 - |{joint_b}{joint_d}|^2)/(2 b c) = "
            f"{b.txtn(cos_now)}, mu = {ctx.fmt.text(math.degrees(b.scalar(mu)))} deg."
        )
        if loop.grashof in ("Grashof crank-rocker", "Grashof double-crank"):
            g, a = b.scalar(keys["ground"]), b.scalar(keys["crank"])
            near = b.put("g - a", abs(g - a), "m")
            far = b.put("g + a", g + a, "m")
            b.check("sum", far, keys["ground"], keys["crank"])
            if g >= a:
                b.check("sum", near, keys["ground"], f"-{keys['crank']}")
            else:
                b.check("sum", near, keys["crank"], f"-{keys['ground']}")
            extremes = []
            for label, side in (("mu_min", near), ("mu_max", far)):
                cos = _cos_mu(b, label, side, keys["coupler"], keys["rocker"])
                extremes.append(_angle(b, label, cos))
            lo, hi = (math.degrees(b.scalar(k)) for k in extremes)
            b.line(
                rf"&|BD| \in [{b.num(near)}, {b.num(far)}]\,\mathrm{{m}} \;\Rightarrow\; "
                rf"\mu_{{\min}} = {ctx.fmt.latex(lo)}{{}}^{{\circ}}, \; \mu_{{\max}} = "
                rf"{ctx.fmt.latex(hi)}{{}}^{{\circ}}"
            )
            worst = max(abs(90.0 - lo), abs(90.0 - hi))
            verdict = (
                "within the usual 40 to 140 deg: the linkage transmits force well all round"
                if GOOD[0] <= lo and hi <= GOOD[1]
                else "outside the usual 40 to 140 deg at times: near there the rocker is driven "
                "poorly (a small turning moment for a large force along the coupler)"
            )
            b.say(
                f"Over a full turn of the crank the diagonal runs from |g - a| = {b.txt(near)} "
                f"(crank along the ground, towards D) to g + a = {b.txt(far)}, so mu runs from "
                f"{ctx.fmt.text(lo)} to {ctx.fmt.text(hi)} deg (at most "
                f"{ctx.fmt.text(worst)} deg from 90 deg), {verdict}."
            )
        else:
            b.say(
                "The crank does not turn fully, so the transmission angle is only defined between "
                "the limit positions of the motion."
            )
        out.append(b.build())
    return out
