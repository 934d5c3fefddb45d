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
from typing import TYPE_CHECKING

import numpy as np

from solver.position.topology import CircleSpec, LeverStep
from solver.solutions import latex as tex
from solver.solutions.builder import StepBuilder
from solver.solutions.equation import Boxed, Num, Paren, Pt, Ref
from solver.solutions.groups.base import SolutionGroup
from solver.solutions.groups.pose import point_value
from solver.solutions.linkage import LinkageContext
from solver.solutions.model import Step

if TYPE_CHECKING:
    from solver.solutions.loop import Loop, LoopMethod
    from solver.solutions.mistakes import LinkageMistakes
    from solver.solutions.vector import VectorMethod


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


class RPR:
    """The slotted lever: its closed form; the slotted-lever loop; the pin in its slot."""

    kind = "RPR"
    loop_mistakes: tuple[str, ...] = ()

    def position_step(self, ctx: LinkageContext, step: LeverStep) -> Step:
        return lever_step(ctx, step)

    def vector_steps(self, method: VectorMethod, step: LeverStep, order: int) -> list[Step]:
        return method.lever(step, order)

    def loop(self, method: LoopMethod, step: LeverStep) -> Loop:
        return method.lever_loop(step)

    def circles(self, step: LeverStep) -> list[CircleSpec]:
        """None: the lever's rate comes from its slot, not from a circle."""
        return []

    def coriolis_mistakes(self, mistakes: LinkageMistakes, step: LeverStep) -> None:
        mistakes.lever_coriolis(step)


GROUP: SolutionGroup = RPR()
