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
from typing import Any, NamedTuple

import numpy as np

from solver.analysis.sweeps import AngleExtremes
from solver.analysis.sweeps import sweep as linkage_sweep
from solver.analysis.work_estimate import estimate_work
from solver.kinematics.dead_centres import (
    SlottedLeverLimits,
    crank_turns_fully,
    slider_crank_dead_centres,
    slotted_lever_dead_centres,
)
from solver.kinematics.four_bar import FourBarLoop
from solver.kinematics.rigid import cross, rotate
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


def _degrees(b: StepBuilder, angle: Ref) -> Ref:
    """The angle in degrees, 180/pi times its radians (a ``product`` check)."""
    value = b.value(f"{angle.key} (deg)", math.degrees(b.scalar(angle)), "deg")
    b.check("product", value, angle, factor=180.0 / math.pi)
    return value


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
    _write_transmission(b, _transmission_values(ctx, b, loop, keys, src))
    if loop.grashof in ("Grashof crank-rocker", "Grashof double-crank"):
        near, far = _diagonal_range(b, keys)
        extremes = [
            _angle(b, label, _cos_mu(b, label, side, keys["coupler"], keys["rocker"]))
            for label, side in (("mu_min", near), ("mu_max", far))
        ]
        _write_cycle(b, (near, far), extremes)
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


def _write_transmission(b: StepBuilder, t: Transmission) -> None:
    """Write cos mu by the law of cosines and mu in rad and degrees."""
    bd_tex = f"{tex.name(t.joint_b)}{tex.name(t.joint_d)}"
    bd = f"{t.joint_b}{t.joint_d}"
    degrees = _degrees(b, t.mu)
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
        " = ",
        Num(degrees, unit=True),
    )
    b.say(
        f"Transmission angle now (between coupler and rocker): |{bd}| = ",
        Num(t.bd, unit=True),
        ", ",
        law_of_cosines,
        ", mu = ",
        Num(degrees, unit=True),
        ".",
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


def _write_cycle(b: StepBuilder, diagonal: tuple[Ref, Ref], extremes: list[Ref]) -> None:
    """Write mu's range over a turn of the crank and whether it stays within 40 to 140 deg."""
    near, far = diagonal
    lo, hi = (_degrees(b, k) for k in extremes)
    right = b.value("90 deg", 90.0, "deg")
    low, high = b.scalar(lo), b.scalar(hi)
    if abs(90.0 - low) >= abs(90.0 - high):
        worst = b.value("from 90 deg", abs(90.0 - low), "deg")
        b.check("sum", worst, *((right, -lo) if low <= 90.0 else (lo, -right)))
    else:
        worst = b.value("from 90 deg", abs(90.0 - high), "deg")
        b.check("sum", worst, *((hi, -right) if high >= 90.0 else (right, -hi)))
    b.line(
        r"&|BD| \in [",
        Num(near),
        ", ",
        Num(far),
        r"]\,\mathrm{m} \;\Rightarrow\; \mu_{\min} = ",
        Num(lo, unit=True),
        r", \; \mu_{\max} = ",
        Num(hi, unit=True),
    )
    verdict = (
        "within the usual 40 to 140 deg: the linkage transmits force well all round"
        if GOOD[0] <= low and high <= GOOD[1]
        else "outside the usual 40 to 140 deg at times: near there the rocker is driven "
        "poorly (a small turning moment for a large force along the coupler)"
    )
    b.say(
        "Over a full turn of the crank the diagonal runs from |g - a| = ",
        Num(near, unit=True),
        " (crank along the ground, towards D) to g + a = ",
        Num(far, unit=True),
        ", so mu runs from ",
        Num(lo, unit=True),
        " to ",
        Num(hi, unit=True),
        " (at most ",
        Num(worst, unit=True),
        f" from 90 deg), {verdict}.",
    )


def _crank_of(ctx: LinkageContext, link: str) -> str | None:
    """The ground pivot of ``link`` if it is a driven crank, else None."""
    return next((d.pivot for d in ctx.scene.drivers if d.link == link), None)


def _ground_pivot(ctx: LinkageContext, link: str) -> str | None:
    """The point at which ``link`` turns about the ground (a revolute joint with it), or None."""
    return next(
        (
            j.point
            for j in ctx.scene.joints
            if j.type == "revolute" and ctx.scene.ground in j.links and link in j.links
        ),
        None,
    )


def _partner(ctx: LinkageContext, link: str, point: str) -> str | None:
    """The other link of the revolute joint of ``link`` at ``point``, or None."""
    for j in ctx.scene.joints:
        if j.type == "revolute" and j.point == point and link in j.links:
            return j.links[1] if j.links[0] == link else j.links[0]
    return None


def slider_classification_steps(ctx: LinkageContext) -> list[Step]:
    """One step per slider mechanism driven by a crank: a slider-crank (the ram's rod pinned to
    the crank: ``slider_crank_dead_centres``) and a crank with a slotted lever, with or without a
    ram (inverted slider-crank, quick-return: ``slotted_lever_dead_centres``)."""
    scene, out = ctx.scene, []
    for joint in scene.joints:
        if joint.type != "slider" or joint.axis is None:
            continue
        guide, follower = joint.links
        if guide == scene.ground:
            for pin in scene.links[follower].points:
                crank = _partner(ctx, follower, pin)
                pivot = None if crank is None else _crank_of(ctx, crank)
                if crank is not None and pivot is not None:
                    out.append(_slider_crank_step(ctx, joint.point, joint.axis, pivot, pin))
                    break
        else:
            pivot, lever_pivot = _crank_of(ctx, follower), _ground_pivot(ctx, guide)
            if pivot is not None and lever_pivot is not None and lever_pivot != pivot:
                step = _slotted_lever_step(ctx, joint.point, joint.axis, pivot, guide, lever_pivot)
                out += [] if step is None else [step]
    return out


def _slider_crank_step(
    ctx: LinkageContext, slider: str, axis: tuple[float, float], pivot: str, pin: str
) -> Step:
    """r + |e| < l, the dead centres x = sqrt((l +- r)^2 - e^2), the stroke, the time ratio
    (180 + a) / (180 - a) and the transmission angle's extremes of a slider-crank."""
    a, b_, c = ctx.pos(pivot), ctx.pos(pin), ctx.pos(slider)
    u = np.asarray(axis, dtype=float)
    if float(u @ (c - a)) < 0.0:  # x along the guide towards the slider
        u = -u
    n = np.array([-u[1], u[0]])
    b = ctx.builder("classification", f"Classification of the slider-crank {pivot}{pin}{slider}")
    r = b.value(f"r = |{pivot}{pin}|", float(np.hypot(*(b_ - a))), "m")
    rod = b.value(f"l = |{pin}{slider}|", float(np.hypot(*(c - b_))), "m")
    e = b.value("e", float(n @ (c - a)), "m")
    reach = b.value("r + |e|", b.scalar(r) + abs(b.scalar(e)), "m")
    b.check("sum", reach, r, e if b.scalar(e) >= 0.0 else -e)
    turns = crank_turns_fully(b.scalar(r), b.scalar(rod), b.scalar(e))
    relation = "<" if turns else r"\ge"
    b.line(
        "&r + |e| = ",
        Num(r),
        " + ",
        Num(e),
        " = ",
        Num(reach, unit=True),
        rf" \; {relation} \; l = ",
        Num(rod, unit=True),
    )
    if not turns:
        b.say(
            "The crank turns fully only if r + |e| < l: here r + |e| = ",
            Num(reach, unit=True),
            " is not less than l = ",
            Num(rod, unit=True),
            ", so the crank rocks between two limit positions.",
        )
        return b.build()
    lim = slider_crank_dead_centres(b.scalar(r), b.scalar(rod), b.scalar(e))
    far = b.value("x_far", lim.x_far, "m")
    near = b.value("x_near", lim.x_near, "m")
    stroke = b.value("stroke", lim.stroke, "m")
    b.check("sum", stroke, far, -near)
    advance = b.value("a", abs(lim.advance), "rad")
    slow = b.value("slow stroke", lim.slow_stroke, "rad")
    fast = b.value("fast stroke", lim.fast_stroke, "rad")
    pi = b.value("pi", math.pi, "")
    b.check("sum", slow, pi, advance)
    b.check("sum", fast, pi, -advance)
    ratio = b.value("time ratio", lim.time_ratio, "")
    b.check("quotient", ratio, slow, fast)
    a_deg = _degrees(b, advance)
    mu_min = _degrees(b, b.value("mu_min", lim.mu_min, "rad"))
    mu_max = _degrees(b, b.value("mu_max", lim.mu_max, "rad"))
    b.line(
        r"&x_{\max} = \sqrt{(l + r)^2 - e^2} = ",
        Num(far, unit=True),
        r", \; x_{\min} = \sqrt{(l - r)^2 - e^2} = ",
        Num(near, unit=True),
    )
    b.line(r"&H = x_{\max} - x_{\min} = ", Num(stroke, unit=True))
    b.line(
        r"&a = \left|\arcsin\frac{e}{l - r} - \arcsin\frac{e}{l + r}\right| = ",
        Num(a_deg, unit=True),
        r" \;\Rightarrow\; K = \frac{180^\circ + a}{180^\circ - a} = ",
        Num(ratio),
    )
    b.line(
        r"&\mu_{\min} = \arccos\frac{r + |e|}{l} = ",
        Num(mu_min, unit=True),
        r", \; \mu_{\max} = \arccos\frac{\max(0, |e| - r)}{l} = ",
        Num(mu_max, unit=True),
    )
    b.say(
        "The crank turns fully, since r + |e| = ",
        Num(reach, unit=True),
        " < l = ",
        Num(rod, unit=True),
        ". The slider's limit positions are where crank and rod lie in one line: x_max = "
        "sqrt((l + r)^2 - e^2) = ",
        Num(far, unit=True),
        " (extended) and x_min = sqrt((l - r)^2 - e^2) = ",
        Num(near, unit=True),
        " (folded), so the stroke is H = ",
        Num(stroke, unit=True),
        ". Between them the crank turns 180 + a and 180 - a deg with a = ",
        Num(a_deg, unit=True),
        ", so the time ratio is K = (180 + a)/(180 - a) = ",
        Num(ratio),
        ". The transmission angle (between the rod and the normal to the guide) runs from ",
        Num(mu_min, unit=True),
        " (crank perpendicular to the guide, away from it) to ",
        Num(mu_max, unit=True),
        ".",
    )
    return b.build()


def _slotted_lever_step(
    ctx: LinkageContext,
    block: str,
    axis: tuple[float, float],
    pivot: str,
    lever: str,
    lever_pivot: str,
) -> Step | None:
    """r < d, the limit positions (crank perpendicular to the slot, cos theta = r / d), the
    lever's swing 2 asin(r / d) and the time ratio (180 + a) / (180 - a), a = 2 asin(r / d), of
    a crank with a slotted lever (inverted slider-crank; with a ram, the quick-return). None for
    a slot that misses the lever's pivot (its limit positions are not these)."""
    o, pin, c = ctx.pos(pivot), ctx.pos(block), ctx.pos(lever_pivot)
    u = np.asarray(axis, dtype=float)
    if abs(float(u[0] * (pin - c)[1] - u[1] * (pin - c)[0])) > 1e-9 * ctx.scene.size:
        return None
    b = ctx.builder(
        "classification",
        f"Classification of the crank {pivot}{block} and its slotted lever (link {lever})",
    )
    r = b.value(f"r = |{pivot}{block}|", float(np.hypot(*(pin - o))), "m")
    d = b.value(f"d = |{pivot}{lever_pivot}|", float(np.hypot(*(c - o))), "m")
    if b.scalar(r) >= b.scalar(d):
        b.line(r"&r = ", Num(r, unit=True), r" \; \ge \; d = ", Num(d, unit=True))
        b.say(
            "The crank is at least as long as the distance between the pivots (r = ",
            Num(r, unit=True),
            ", d = ",
            Num(d, unit=True),
            "): the lever turns round with the crank (a Whitworth drive), no limit positions.",
        )
        return b.build()
    lim = slotted_lever_dead_centres(b.scalar(r), b.scalar(d))
    swing = _degrees(b, b.value("swing", lim.swing, "rad"))
    slow = b.value("slow stroke", lim.slow_stroke, "rad")
    fast = b.value("fast stroke", lim.fast_stroke, "rad")
    slow_deg, fast_deg = _degrees(b, slow), _degrees(b, fast)
    half = _degrees(b, b.value("theta", lim.theta_1, "rad"))
    full = b.value("2 pi", 2.0 * math.pi, "")
    b.check("sum", slow, full, -fast)
    ratio = b.value("time ratio", lim.time_ratio, "")
    b.check("quotient", ratio, slow, fast)
    b.line(
        r"&r = ",
        Num(r, unit=True),
        r" < d = ",
        Num(d, unit=True),
        r" \;\Rightarrow\; \cos\theta = \frac{r}{d}, \; \theta = \pm ",
        Num(half, unit=True),
    )
    b.line(
        r"&\psi = 2\arcsin\frac{r}{d} = ",
        Num(swing, unit=True),
        r", \; K = \frac{360^\circ - 2\arccos(r/d)}{2\arccos(r/d)} = \frac{",
        Num(slow_deg, unit=True),
        "}{",
        Num(fast_deg, unit=True),
        r"} = \frac{180^\circ + a}{180^\circ - a} = ",
        Num(ratio),
    )
    sentences: list[Any] = [
        "The crank turns fully and the lever rocks, since r = ",
        Num(r, unit=True),
        " < d = ",
        Num(d, unit=True),
        ". The lever's limit positions are where the slot is tangent to the crank circle (crank "
        "perpendicular to the slot), at theta = +-",
        Num(half, unit=True),
        f" from {pivot}{lever_pivot}; the lever swings through 2 asin(r/d) = ",
        Num(swing, unit=True),
        ". The crank turns ",
        Num(slow_deg, unit=True),
        " over the slow stroke and ",
        Num(fast_deg, unit=True),
        " over the quick return, a time ratio K = (180 + a)/(180 - a) = ",
        Num(ratio),
        " with a = 2 asin(r/d) = ",
        Num(swing, unit=True),
        ".",
    ]
    ram = _ram_stroke(ctx, lever, block, (o, c), lim)
    if ram is not None:
        name, stroke = ram
        h = b.value("stroke", stroke, "m")
        b.line(rf"&H_{{{tex.name(name)}}} = ", Num(h, unit=True))
        sentences += [
            f" The ram {name} moves between the lever's limit positions: stroke H = ",
            Num(h, unit=True),
            ".",
        ]
    b.say(*sentences)
    return b.build()


def _ram_stroke(
    ctx: LinkageContext,
    lever: str,
    block: str,
    centres: tuple[np.ndarray, np.ndarray],
    lim: SlottedLeverLimits,
) -> tuple[str, float] | None:
    """The stroke of a ram on a fixed guide driven by the lever through a rod (the
    quick-return): the rod's end on the guide (on the drawn side) at the lever's two limit
    positions, crank pin O + r (cos, sin)(angle of OC + theta); None without a ram."""
    scene, (o, c) = ctx.scene, centres
    pin = ctx.pos(block)
    r = float(np.hypot(*(pin - o)))
    toward_c = math.atan2(*(c - o)[::-1])
    lever_now = math.atan2(*(pin - c)[::-1])
    for point in scene.links[lever].points:
        rod = _partner(ctx, lever, point)
        for j in scene.joints:
            if rod is None or j.type != "slider" or j.links != (scene.ground, rod):
                continue
            assert j.axis is not None
            g = np.asarray(j.axis, dtype=float)
            ram, end = ctx.pos(j.point), ctx.pos(point)
            length = float(np.hypot(*(ram - end)))
            side = math.copysign(1.0, float(g @ (ram - end)))
            xs = []
            for theta in (lim.theta_1, lim.theta_2):
                limit_pin = o + r * np.array(
                    [math.cos(toward_c + theta), math.sin(toward_c + theta)]
                )
                end_i = c + rotate(
                    end - c, np.asarray(math.atan2(*(limit_pin - c)[::-1]) - lever_now)
                )
                along = float(g @ (end_i - ram))
                off = float(cross(g, end_i - ram))
                if abs(off) > length:  # the rod cannot reach the guide there: no full turn
                    return None
                xs.append(along + side * math.sqrt(length**2 - off**2))
            return j.point, abs(xs[0] - xs[1])
    return None


DEG = "{}^{\\circ}"
ANGLE_SAMPLES = 360  # the revolution sampled each degree; the extremes are refined to rounding
# The most a worked solution spends on that revolution, estimated as the request budget does (a
# four-bar's is a few ms, within the spread of the solution's own writing, tens of ms).
EXTREMES_ALLOWANCE = 0.05  # s


def angle_extreme_steps(ctx: LinkageContext) -> list[Step]:
    """One step per four-bar loop whose crank is the (only) driver and turns fully: the least
    and greatest angle of the coupler and of the rocker over a turn of the crank, where
    omega = 0, and the crank angles there (``Sweep.angle_extremes``: the sweep's sampled extremes
    refined to rounding); none where that revolution would cost more than ``EXTREMES_ALLOWANCE``
    (estimated as the request budget does)."""
    scene = ctx.scene
    loops = [
        loop
        for loop in ctx.analysis.four_bar_loops
        if len(scene.drivers) == 1 and scene.drivers[0].link == loop.links[1]
    ]
    # The revolution within the worked solution's allowance (every four-bar; a large
    # mechanism's revolution would not be paid for).
    if not loops or estimate_work(scene, ANGLE_SAMPLES).seconds > EXTREMES_ALLOWANCE:
        return []
    sweep = linkage_sweep(scene, ANGLE_SAMPLES, ["position"])
    if not sweep.feasible:
        return []
    steps = []
    for loop in loops:
        found = [(link, sweep.angle_extremes(link)) for link in loop.links[2:]]
        rocking = [(link, e) for link, e in found if e is not None]
        if rocking:
            steps.append(_angle_extremes_step(ctx, loop, rocking))
    return steps


def _angle_extremes_step(
    ctx: LinkageContext, loop: FourBarLoop, rocking: list[tuple[str, AngleExtremes]]
) -> Step:
    """phi_min, phi_max of each rocking link and the crank angles theta there (d phi/d theta =
    0)."""
    crank = loop.links[1]
    names = " and ".join(_called(loop, link) for link, _ in rocking)
    b = ctx.builder("angle_extremes", f"Extremes of the angles of {names} over a turn of the crank")
    b.say(
        f"As {_called(loop, crank)} turns once from its drawn angle, each angle phi below (of the "
        "link's line from its first to its second point, counter-clockwise from +x) swings "
        "between a least and a greatest value, reached where the link stands still for an "
        "instant (omega = d phi/dt = 0). The revolution is sampled every degree and each "
        "sampled extreme refined where d phi/d theta = 0."
    )
    for link, e in rocking:
        low = b.value(f"phi_min ({link})", math.degrees(e.least), "deg")
        high = b.value(f"phi_max ({link})", math.degrees(e.greatest), "deg")
        at_low, at_high = (
            b.value(f"theta at phi_{end} ({link})", math.degrees(angle) % 360.0, "deg")
            for end, angle in zip(("min", "max"), e.driver_angles, strict=True)
        )
        sub = tex.name(link)
        b.line(
            rf"&\varphi_{{{sub},\min}} = ", Num(low), DEG, r"\;\text{at}\;\theta = ", Num(at_low),
            DEG, rf", \quad \varphi_{{{sub},\max}} = ", Num(high), DEG,
            r"\;\text{at}\;\theta = ", Num(at_high), DEG,
        )  # fmt: skip
        b.say(
            f"{_called(loop, link).capitalize()}: phi from ",
            Num(low, unit=True),
            " (crank at ",
            Num(at_low, unit=True),
            ") to ",
            Num(high, unit=True),
            " (crank at ",
            Num(at_high, unit=True),
            f"), a swing of {ctx.fmt.text(math.degrees(e.greatest - e.least))} deg.",
        )
    return b.build()


def _called(loop: FourBarLoop, link: str) -> str:
    """'the rocker' for a link named so, else 'the rocker BC'."""
    role = ROLES[loop.links.index(link)]
    return f"the {role}" if role == link else f"the {role} {link}"
