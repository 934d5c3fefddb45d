"""RPR in the worked solutions: a slotted lever turning about a known pivot, its slot through a
known pin (the inverted slider-crank, the quick-return), the slotted-lever loop it closes, and
the pin in the lever's slot in the vector method.

From the pivot, the pin is s along the slot and c across it: (s + i c) e^(i beta) = w, w the
vector from the pivot to the pin. Squared and added, s^2 + c^2 = |w|^2, so s = +-sqrt(|w|^2 -
c^2), then beta = arg w - arg(s + i c).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import partial
from typing import TYPE_CHECKING

import numpy as np

from solver.position.topology import CircleSpec, LeverStep
from solver.solutions import latex as tex
from solver.solutions.builder import StepBuilder
from solver.solutions.equation import Boxed, Col, Num, Paren, Piece, Pt, Ref, ZCross
from solver.solutions.format import latex_unit
from solver.solutions.groups.base import SolutionGroup
from solver.solutions.groups.pose import point_value
from solver.solutions.linkage import (
    MOTION,
    VELOCITY,
    LinkageContext,
    a_vec,
    al_vec,
    omega_squared,
    omega_squared_line,
    origin,
    put_motion,
    r_vec,
    v_vec,
    w_vec,
)
from solver.solutions.model import Step
from solver.solutions.relative import Carrier, TransportTerms, check_transport, transport_terms
from solver.solutions.vector import (
    KnownAcceleration,
    Side,
    Term,
    VectorMethod,
    relative_line,
    side_column,
    side_text,
)

if TYPE_CHECKING:
    from solver.solutions.loop import Loop, LoopMethod
    from solver.solutions.mistakes import LinkageMistakes


@dataclass(frozen=True)
class LeverNotation:
    """How a lever's closed form is written: the keys of s, c and beta and their LaTeX symbols;
    w is the vector from the lever's pivot to the pin."""

    s: str
    c: str
    beta: str
    s_tex: str
    c_tex: str
    beta_tex: str


TURN_LATEX = {"": "", "2pi": r" + 2\pi", "-2pi": r" - 2\pi"}  # the whole turn of wrap_turn
TURN_TEXT = {"": "", "2pi": " + 2 pi", "-2pi": " - 2 pi"}


def wrap_turn(b: StepBuilder, value: float, target: float) -> tuple[str, float]:
    """The whole turns k (as an operand '2pi' or '-2pi', '' for none) with value + k 2 pi =
    target, and the corrected value: an angle found as a sum is written in (-pi, pi]."""
    k = round((target - value) / (2 * math.pi))
    if k == 0:
        return "", value
    b.put("2pi", 2 * math.pi, "rad")
    return ("2pi" if k > 0 else "-2pi"), value + math.copysign(2 * math.pi, k)


@dataclass(frozen=True)
class LeverClosedForm:
    """The values of a lever's closed form (``lever_values``) and the whole turn of beta."""

    c: Ref
    w2: Ref
    c2: Ref
    s: Ref
    epsilon: Ref
    theta_w: Ref
    beta: Ref
    turn: str


def lever_closed_form(b: StepBuilder, w: Ref, u_np: np.ndarray, n: LeverNotation) -> None:
    """(s + i c) e^(i beta) = w, w the vector from the lever's pivot to the pin: squared and
    added, s^2 + c^2 = |w|^2, so s = +-sqrt(|w|^2 - c^2); then beta = arg w - arg(s + i c).
    The offset c of the slot is a constant of the lever (from the pose); the sign of s is the
    drawn assembly (the pin ahead of the pivot along the slot, or behind)."""
    lever_lines(b, w, n, lever_values(b, w, u_np, n))


def lever_values(b: StepBuilder, w: Ref, u_np: np.ndarray, n: LeverNotation) -> LeverClosedForm:
    """Put the closed form's numbers, with a check for each piece of arithmetic."""
    w_np = np.asarray(b.vector(w))
    size = float(np.hypot(*w_np))  # c and arg(s + i c) at rounding level next to it are 0
    c = b.value(n.c, float(u_np[0] * w_np[1] - u_np[1] * w_np[0]), "m", reference=size)
    s_value = float(np.dot(w_np, u_np))
    w2 = b.value("|w|^2", float(np.dot(w_np, w_np)), "m^2")
    c2 = b.value(f"{n.c}^2", b.scalar(c) ** 2, "m^2", reference=size**2)
    s2 = b.value(f"{n.s}^2", s_value**2, "m^2", reference=b.scalar(w2))
    s = b.value(n.s, s_value, "m")
    sc = b.value(f"({n.s}, {n.c})", (s_value, b.scalar(c)), "m")
    eps = b.value("epsilon", math.atan2(b.scalar(c), s_value), "rad", reference=math.pi)
    theta_w = b.value("theta_w", math.atan2(w_np[1], w_np[0]), "rad")
    b.check("dot", w2, w, w)
    b.check("product", c2, c, c)
    b.check("sum", s2, w2, -c2)
    b.check("product", s2, s, s)
    b.check("sum", s, sc[0])
    b.check("sum", c, sc[1])
    b.check("angle", eps, sc)
    b.check("angle", theta_w, w)
    turn, beta_value = wrap_turn(b, b.scalar(theta_w) - b.scalar(eps), math.atan2(u_np[1], u_np[0]))
    beta = b.value(n.beta, beta_value, "rad")
    b.check("sum", beta, theta_w, -eps, *([turn] if turn else []))
    return LeverClosedForm(c, w2, c2, s, eps, theta_w, beta, turn)


def lever_lines(b: StepBuilder, w: Ref, n: LeverNotation, f: LeverClosedForm) -> None:
    """Write the closed form: Re and Im, the elimination, the numbers, the assembly taken."""
    ahead = b.scalar(f.s) >= 0
    pm = "+" if ahead else "-"
    b.line(
        rf"&\text{{Re: }} {n.s_tex}\cos{n.beta_tex} - {n.c_tex}\sin{n.beta_tex} = w_x, "
        rf"\quad \text{{Im: }} {n.s_tex}\sin{n.beta_tex} + {n.c_tex}\cos{n.beta_tex} = w_y"
    )
    b.line(
        rf"&{n.s_tex}^2 + {n.c_tex}^2 = |w|^2 \;\Rightarrow\; {n.s_tex} = \pm"
        rf"\sqrt{{|w|^2 - {n.c_tex}^2}}, \quad {n.beta_tex} = \arg w - "
        rf"\arg({n.s_tex} + i\,{n.c_tex})"
    )
    b.line(
        "&w = ",
        Pt(w, "m"),
        r", \quad |w|^2 = ",
        Num(f.w2, unit=True),
        rf", \quad {n.c_tex} = ",
        Num(f.c, unit=True),
    )
    b.line(
        rf"&{n.s_tex} = {pm}\sqrt{{",
        Num(f.w2),
        " - ",
        Num(f.c2),
        "} = ",
        Boxed((Num(f.s, unit=True),)),
    )
    b.line(
        r"&\arg w = ",
        Num(f.theta_w, unit=True),
        rf", \quad \arg({n.s_tex} + i\,{n.c_tex}) = ",
        Num(f.epsilon, unit=True),
        rf", \quad {n.beta_tex} = ",
        Num(f.theta_w),
        " - ",
        Paren(f.epsilon),
        f"{TURN_LATEX[f.turn]} = ",
        Boxed((Num(f.beta, unit=True),)),
    )
    where = "ahead of" if ahead else "behind"
    b.say(
        "Written as (s + i c) e^(i beta) = w, the real and imaginary parts are s cos "
        "beta - c sin beta = w_x and s sin beta + c cos beta = w_y. Squaring and adding "
        "eliminates beta: s^2 + c^2 = |w|^2, with the slot's offset c = ",
        Num(f.c, unit=True),
        " from the pivot (a constant of the lever) and |w|^2 = ",
        Num(f.w2, unit=True),
        ", so s = +-sqrt(|w|^2 - c^2). Two assemblies: the pin "
        f"{where} the pivot along the slot (sign {pm}) is the one drawn (the solver keeps the "
        "drawn branch): s = ",
        Num(f.s, unit=True),
        ". Then beta = arg w - arg(s + i c) = ",
        Num(f.theta_w, unit=True),
        " - ",
        Num(f.epsilon, unit=True),
        f"{TURN_TEXT[f.turn]} = ",
        Num(f.beta, unit=True),
        ", the angle of the slot.",
    )


def lever_step(ctx: LinkageContext, step: LeverStep) -> Step:
    """The lever's angle and the pin's distance along its slot, from the triangle pivot-pin."""
    q, p = step.pivot, step.pin
    b = ctx.builder("position.lever", f"Position of lever {step.link}: its slot through {p}")
    pq, pp = point_value(b, ctx, q), point_value(b, ctx, p)
    w = b.value(f"r({q},{p})", ctx.pos(p) - ctx.pos(q), "m")
    b.check("sum", w, pp, -pq)
    notation = LeverNotation("s", "c", "beta", "s", "c", r"\beta")
    b.line(
        rf"&w = {tex.name(p)} - {tex.name(q)} = (s + i\,c)\,e^{{i\beta}}, \quad s \text{{ along "
        rf"the slot, }} c \text{{ its offset from }} {tex.name(q)}"
    )
    b.say(
        f"Lever {step.link} turns about {q}; its slot passes through the pin {p}. From {q}, {p} "
        f"is s along the slot and c across it: w = {p} - {q} = ",
        Pt(w),
        ".",
    )
    lever_closed_form(b, w, ctx.slot(step.link, p).direction, notation)
    return b.build()


# --- the pin in the lever's slot in the vector method ---------------------------------------


def lever_vector_steps(v: VectorMethod, step: LeverStep, order: int) -> list[Step]:
    """The pin P (known) in the slot of a lever turning about Q: v_P = v_Q + omega x r_QP +
    s' u (a_P = a_Q + alpha x r_QP - omega^2 r_QP + s'' u + a_Cor), solved for the lever's
    rate and the sliding rate."""
    ctx = v.ctx
    lever, pivot, pin = step.link, step.pivot, step.pin
    ctx.use(pivot, pin)
    what = MOTION[order][0]
    out = [] if order == VELOCITY else [v.coriolis_step(pin, lever)]
    side_step, lever_side, known_side = lever_sides(v, step, order)
    out.append(side_step)
    out.append(
        v.equate(
            f"{what}.lever.solve",
            f"Components of the {what} of {pin}: geometric connection = relative connection",
            lever_side,
            known_side,
            f"The two expressions of the {what} of {pin} are equal; component by component:",
            f"{what[0]}:{pin}:",
        )
    )
    (v.solved_omega if order == VELOCITY else v.solved_alpha).add(lever)
    out.append(lever_parts(v, step, order))
    (ctx.shown_velocity if order == VELOCITY else ctx.shown_acceleration).add(pin)
    out += v.remaining(lever, pivot, order)
    return out


def lever_terms(v: VectorMethod, step: LeverStep, order: int) -> list[Term]:
    """omega k x r_QP and s' u (alpha k x r_QP and s'' u): the lever's unknown terms."""
    ctx, lever, pivot, pin = v.ctx, step.link, step.pivot, step.pin
    r_np = ctx.pos(pin) - ctx.pos(pivot)
    return [
        Term(v.unknown_rate(lever, order), "perp", f"r({pivot},{pin})", r_np, "m"),
        Term(
            v.unknown_slide(pin, lever, order, False),
            "dir",
            f"u({pin}/{lever})",
            ctx.slot(lever, pin).direction,
            "",
        ),
    ]


def lever_sides(v: VectorMethod, step: LeverStep, order: int) -> tuple[Step, Side, Side]:
    """v_P = v_Q + omega x r_QP + s' u, omega and s' unknown (a_P = a_Q + alpha x r_QP -
    omega^2 r_QP + s'' u + a_Cor, alpha and s'' unknown); v_P (a_P) known from its crank.
    Returns the step, the lever's side and the pin's."""
    ctx, lever, pivot, pin = v.ctx, step.link, step.pivot, step.pin
    what, unit = MOTION[order]
    terms = lever_terms(v, step, order)
    rate, slide = (t.unknown for t in terms)
    b = ctx.builder(
        f"{what}.lever.side",
        f"{what.capitalize()} of {pin} in the slot of {lever} ({rate.text} and {slide.text} "
        "unknown)",
    )
    base = put_motion(b, ctx, pivot, order)
    known_pin = put_motion(b, ctx, pin, order)
    if order == VELOCITY:
        for t in terms:
            b.put(t.of, t.of_value, t.of_unit)
        lever_side = Side(base, ctx.vel(pivot), unit, terms)
        lever_velocity_lines(v, b, step, lever_side, known_pin)
        pin_motion = ctx.vel(pin)
    else:
        known, cor = lever_known_acceleration(v, b, step, base, terms)
        lever_side = Side(known.key, known.value, unit, terms)
        lever_acceleration_lines(v, b, step, lever_side, known, (known_pin, cor))
        pin_motion = ctx.acc(pin)
    return b.build(), lever_side, Side(known_pin, pin_motion, unit)


def braced(label: str, *pieces: Piece) -> tuple[Piece, ...]:
    """The pieces of one part of a sum under a brace naming it: \\underbrace{...}_{label} (a
    term of v_tr that reads as a term of v_tr, not of the whole sum)."""
    return (r"\underbrace{", *pieces, rf"}}_{{{label}}}")


def lever_velocity_lines(
    v: VectorMethod, b: StepBuilder, step: LeverStep, side: Side, vp: str
) -> None:
    """Write v_P = v_Q + omega x r_QP + s' u, expanded to a column linear in omega and s'."""
    lever, pivot, pin = step.link, step.pivot, step.pin
    (rate, rkey), (slide, ukey) = ((t.unknown, t.of) for t in side.terms)
    sub, base = tex.name(pin), origin(b, v.ctx, pivot, Ref(side.known_key))
    part = {name: rf"\vec{{v}}_{{{sub},\mathrm{{{name}}}}}" for name in ("tr", "rel")}
    again = rf"&\phantom{{{v_vec(pin)}}} = "
    b.line(rf"&{v_vec(pin)} = {part['tr']} + {part['rel']}, \quad \vec{{u}} = ", Col(Ref(ukey)))
    b.line(
        again,
        *braced(part["tr"], rf"{v_vec(pivot)} + {w_vec(lever)} \times {r_vec(pivot, pin)}"),
        " + ",
        *braced(part["rel"], rf"{slide.latex}\,\vec{{u}}"),
    )
    b.line(
        again,
        *braced(part["tr"], base, " + ", ZCross(rate.symbol, Ref(rkey))),
        " + ",
        *braced(part["rel"], f"{slide.latex} ", Col(Ref(ukey))),
    )
    b.line(f"{again}{side_column(b, side)}{latex_unit('m/s')}")
    b.say(
        f"Geometric connection: {pin} is the pin of its crank, so v({pin}) = ",
        Col(Ref(vp)),
        f" is known. Relative connection: {pin} slides in the slot of "
        f"{lever}, which turns about {pivot}: v({pin}) = v_tr + v_rel = v({pivot}) + "
        f"omega({lever}) cross r({pivot},{pin}) + {slide.text} u = "
        f"{side_text(b, side)} m/s, with {rate.text} and {slide.text} unknown.",
    )


def lever_known_acceleration(
    v: VectorMethod, b: StepBuilder, step: LeverStep, aq: str, terms: list[Term]
) -> tuple[KnownAcceleration, str]:
    """a_Q - omega^2 r_QP + a_Cor, the known part of a_P through the lever, with its terms
    (and r_QP and u) put and checked; returns it and the key of a_Cor."""
    ctx, lever, pivot, pin = v.ctx, step.link, step.pivot, step.pin
    sliding = ctx.slot(lever, pin)
    assert sliding.coriolis_acceleration is not None
    omega, r_np = ctx.omega(lever), terms[0].of_value
    w = b.value(f"omega({lever})", omega, "rad/s", ctx.link_source(lever, "omega"))
    w2 = omega_squared(b, lever, w)
    for t in terms:
        b.put(t.of, t.of_value, t.of_unit)
    n = b.put(f"normal({pivot},{pin})", -(omega**2) * r_np, "m/s^2")
    cor = sliding.put(b, "coriolis_acceleration", pin)
    value = ctx.acc(pivot) - omega**2 * r_np + sliding.coriolis_acceleration
    key = b.put(f"known({pin} in {lever})", value, "m/s^2")
    b.check("product", n, w2, terms[0].of, factor=-1.0)
    b.check("sum", key, aq, n, cor)
    return KnownAcceleration(key, value, aq, w2.key, terms[0].of, n), cor


def lever_acceleration_lines(
    v: VectorMethod,
    b: StepBuilder,
    step: LeverStep,
    side: Side,
    known: KnownAcceleration,
    pin_keys: tuple[str, str],
) -> None:
    """``pin_keys``: the keys of a_P and a_Cor."""
    lever, pivot, pin = step.link, step.pivot, step.pin
    (rate, rkey), (slide, ukey) = ((t.unknown, t.of) for t in side.terms)
    (ap, cor), sub = pin_keys, tex.name(pin)
    part = {name: rf"\vec{{a}}_{{{sub},\mathrm{{{name}}}}}" for name in ("tr", "rel", "Cor")}
    b.line(rf"&{a_vec(pin)} = {part['tr']} + {part['rel']} + {part['Cor']}")
    again = rf"&\phantom{{{a_vec(pin)}}} = "
    b.line(
        again,
        *braced(
            part["tr"],
            rf"{a_vec(pivot)} + {al_vec(lever)} \times {r_vec(pivot, pin)} - "
            rf"\omega_{{{tex.name(lever)}}}^2\,{r_vec(pivot, pin)}",
        ),
        " + ",
        *braced(part["rel"], rf"{slide.latex}\,\vec{{u}}"),
        " + ",
        *braced(part["Cor"], rf"2\,{w_vec(lever)} \times \vec{{v}}_{{{sub},\mathrm{{rel}}}}"),
    )
    b.line(
        again,
        *braced(
            part["tr"],
            origin(b, v.ctx, pivot, Ref(known.base)),
            " + ",
            ZCross(rate.symbol, Ref(rkey)),
            " - ",
            Num(Ref(known.omega2)),
            r" \cdot ",
            Col(Ref(rkey)),
        ),
        " + ",
        *braced(part["rel"], f"{slide.latex} ", Col(Ref(ukey))),
        " + ",
        *braced(part["Cor"], Col(Ref(cor))),
    )
    b.line(f"{again}{side_column(b, side)}{latex_unit('m/s^2')}")
    b.say(
        f"Geometric connection: a({pin}) = ",
        Col(Ref(ap)),
        f" is known from its crank. "
        f"Relative connection: a({pin}) = a_tr + a_rel + a_Cor, with the transport "
        f"term a({pivot}) + alpha({lever}) cross r({pivot},{pin}) - omega({lever}) "
        f"squared r({pivot},{pin}), the relative term {slide.text} u and the Coriolis "
        "term ",
        Col(Ref(cor)),
        f": a({pin}) = {side_text(b, side)} m/s^2.",
    )


def lever_parts(v: VectorMethod, step: LeverStep, order: int) -> Step:
    """v_tr = v_Q + omega x r_QP and v_rel = s' u at the pin (a_tr = a_Q + alpha x r_QP -
    omega^2 r_QP and a_rel = s'' u), with the solved numbers."""
    ctx, lever, pivot, pin = v.ctx, step.link, step.pivot, step.pin
    sliding = ctx.slot(lever, pin)
    what, unit = MOTION[order]
    b = ctx.builder(f"{what}.lever.parts", f"Transport and relative {what} of {pin}")
    carrier = Carrier(lever, ctx.omega(lever), ctx.alpha(lever), partial(ctx.link_source, lever))
    r_np = ctx.pos(pin) - ctx.pos(pivot)
    terms = transport_terms(b, ctx, carrier, (pivot, pin), r_np, order, f"({pivot},{pin})")
    tr = Ref(sliding.put(b, f"transport_{what}", pin))
    slide = v.unknown_slide(pin, lever, order, False)
    s = b.value(slide.key, slide.value, unit)
    u = b.value(f"u({pin}/{lever})", sliding.direction, "")
    rel = Ref(sliding.put(b, f"relative_{what}", pin))
    check_transport(b, terms, tr.key)
    transport = lever_transport(v, b, step, terms, tr, order)
    relative_line(b, what[0], tex.name(pin), slide.latex, s, u, rel)
    b.say(
        *transport,
        f"; the relative {what} along the slot is ",
        Num(s, unit=True),
        " times ",
        Num(u),
        " = ",
        Col(rel),
        ".",
    )
    return b.build()


def lever_transport(
    v: VectorMethod, b: StepBuilder, step: LeverStep, terms: TransportTerms, tr: Ref, order: int
) -> tuple[Piece, ...]:
    """Write v_tr = v_Q + omega x r_QP (a_tr = a_Q + alpha x r_QP - omega^2 r_QP); returns the
    sentence that says it."""
    lever, pivot, pin = step.link, step.pivot, step.pin
    what = MOTION[order][0]
    moving = not (v.ctx.is_fixed(pivot) and b.is_zero(terms.base))
    base: tuple[Piece, ...] = (Col(Ref(terms.base)), " + ") if moving else ()
    point_vec, rate_vec, rate, rate_name = (
        (v_vec, w_vec, terms.omega, "omega")
        if order == VELOCITY
        else (a_vec, al_vec, terms.alpha, "alpha")
    )
    start = f"{point_vec(pivot)} + " if moving else ""
    r = Ref(terms.r)
    formula = (
        rf"&\vec{{{what[0]}}}_{{{tex.name(pin)},\mathrm{{tr}}}} = {start}{rate_vec(lever)} "
        rf"\times {r_vec(pivot, pin)}"
    )
    numbers: tuple[Piece, ...] = (*base, ZCross(Ref(rate), r))
    parts: tuple[Piece, ...] = (Col(tr),)
    where = f" (the point of {lever} under the pin)"
    if order != VELOCITY:  # the normal term -omega^2 r_QP, and the two terms' columns
        formula += rf" - \omega_{{{tex.name(lever)}}}^2\,{r_vec(pivot, pin)}"
        t, n = Ref(terms.rotation), Ref(terms.normal)
        numbers += (" - ", Num(Ref(terms.omega2)), r" \cdot ", Col(r), " = ", *base, Col(t))
        numbers += (" + ", Col(n))
        parts = (Col(t), " + ", Col(n), " = ", Col(tr))
        where = ""
        if not b.is_zero(terms.omega):
            omega_squared_line(b, lever, Ref(terms.omega), Ref(terms.omega2))
    b.line(formula + " = ", *numbers, " = ", Col(tr, unit=True))
    return (
        f"With {rate_name}({lever}) = ",
        Num(Ref(rate), unit=True),
        f": the transport {what} of {pin}{where} is ",
        *parts,
    )


class RPR:
    """The slotted lever: its closed form; the slotted-lever loop; the pin in its slot."""

    kind = "RPR"
    loop_mistakes: tuple[str, ...] = ()

    def position_step(self, ctx: LinkageContext, step: LeverStep) -> Step:
        return lever_step(ctx, step)

    def vector_steps(self, method: VectorMethod, step: LeverStep, order: int) -> list[Step]:
        return lever_vector_steps(method, step, order)

    def loop(self, method: LoopMethod, step: LeverStep) -> Loop:
        return method.lever_loop(step)

    def circles(self, step: LeverStep) -> list[CircleSpec]:
        """None: the lever's rate comes from its slot, not from a circle."""
        return []

    def coriolis_mistakes(self, mistakes: LinkageMistakes, step: LeverStep) -> None:
        mistakes.lever_coriolis(step)


GROUP: SolutionGroup = RPR()
