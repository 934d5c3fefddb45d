"""Two- and three-force members in the worked force analysis (methods ``statics`` and
``newton_euler``): a link in equilibrium under forces alone (no couple, no inertia) loaded at two
points carries two equal and opposite forces along the line through them; loaded at three, the
three lines of action meet at one point (or are parallel).

A pin's friction moment M_f shifts its force's line of action off the pin's centre, tangent to the
friction circle: the force F at X with the moment M on the link acts along the line through
p = X - M (k x F) / |F|^2, since (p - X) x F = M, at the distance |M| / |F| = mu r from X.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from solver.kinematics.rigid import cross, solve_2x2
from solver.solutions import latex as tex
from solver.solutions.builder import StepBuilder, Unknown, present_solution
from solver.solutions.equation import Boxed, Col, Num, Pt, Ref
from solver.solutions.linkage import LinkageContext
from solver.solutions.model import Step

FORCE = "N"


def force_symbol(name: str, axis: str = "", vector: bool = True) -> str:
    """A force's symbol: 'F_D' as \\vec F_{D} (with ``axis``: F_{D,x}; not ``vector``: F_{D}),
    another name as \\vec{name} (name_{x}; name)."""
    base, _, sub = name.partition("_")
    if sub and len(base) == 1:
        inner = tex.name(sub) + (f",{axis}" if axis else "")
        return rf"{base}_{{{inner}}}" if axis or not vector else rf"\vec {base}_{{{inner}}}"
    plain = tex.name(name)
    return rf"{plain}_{axis}" if axis else rf"\vec{{{plain}}}" if vector else plain


@dataclass(frozen=True)
class Acting:
    """One force on a link at this instant: its name (``F_B``, ``N_C``, a load's, ``W_rod``), the
    point it acts at (a pin's centre), the force on the link as solved, a pin's friction moment
    on the link (0 without), the joint's index (None for a load or a weight), and its line's
    direction where the problem gives it before solving (a load's or a weight's, a frictionless
    slot's normal; None), with ``whole`` for a force known in full (a load, a weight) and
    ``pin`` for a revolute joint's."""

    name: str
    at: np.ndarray
    force: np.ndarray
    moment: float = 0.0
    joint: int | None = None
    direction: np.ndarray | None = None
    whole: bool = False
    pin: bool = False

    @property
    def through(self) -> np.ndarray:
        """A point of the line of action: X - M (k x F) / |F|^2 (X itself without a moment)."""
        if self.moment == 0.0:
            return self.at
        F = self.force
        return self.at - self.moment * np.array([-F[1], F[0]]) / float(F @ F)


def is_two_force(acting: list[Acting]) -> bool:
    """Two pins and nothing else on the link, at distinct points."""
    return (
        len(acting) == 2
        and all(a.pin for a in acting)
        and float(np.hypot(*(acting[1].at - acting[0].at))) > 0.0
    )


def two_force_step(ctx: LinkageContext, link: str, acting: list[Acting]) -> Step:
    """F_P + F_Q = 0 and, without friction, F_Q = S e_PQ along the pins' line (S > 0: tension);
    with a friction moment at a pin the line is tangent to its friction circle, |d| = |M_f| / |F|
    = mu r off the pin's centre."""
    p, q = acting
    P, Q = p.name.split("_", 1)[1], q.name.split("_", 1)[1]
    b = ctx.builder("dynamics.two_force", f"{link}: a two-force member")
    r = b.value(f"r({P},{Q})", q.at - p.at, "m")
    size = float(np.hypot(*q.force))
    FP = b.value(f"F({P}) on {link}", p.force, FORCE)
    FQ = b.value(f"F({Q}) on {link}", q.force, FORCE)
    total = b.value(f"F({P}) + F({Q})", p.force + q.force, FORCE, reference=2 * size)
    b.check("sum", total, FP, FQ)
    sub_p, sub_q = tex.name(P), tex.name(Q)
    reason = (
        f"{link} is loaded only at its pins {P} and {Q}: no weight, no external force or moment"
    )
    if p.moment == 0.0 and q.moment == 0.0:
        length = b.value(f"|r({P},{Q})|", float(np.hypot(*(q.at - p.at))), "m")
        b.check("norm", length, r)
        e = b.value(f"e({P},{Q})", (q.at - p.at) / b.scalar(length), "")
        b.check("quotient", e, r, length)
        S = b.value(f"S({link})", float(q.force @ b.vector(e)), FORCE)
        b.check("product", FQ, S, e)
        moment = b.value(f"r({P},{Q}) x F({Q})", float(cross(q.at - p.at, q.force)), "N m",
                         reference=b.scalar(length) * size)  # fmt: skip
        b.check("cross", moment, r, FQ)
        b.line(
            rf"&\vec F_{{{sub_q}}} = -\vec F_{{{sub_p}}} = S\,\vec e_{{{sub_p}{sub_q}}},\quad "
            rf"\vec e_{{{sub_p}{sub_q}}} = \frac{{\vec r_{{{sub_p}{sub_q}}}}}"
            rf"{{|\vec r_{{{sub_p}{sub_q}}}|}} = ",
            Col(e, dims=2),
        )
        b.line(
            "&S = ",
            Boxed((Num(S, unit=True),)),
            rf",\quad \vec F_{{{sub_q}}} = ",
            Col(FQ, unit=True, dims=2),
            rf",\quad \vec F_{{{sub_p}}} + \vec F_{{{sub_q}}} = ",
            Col(total, dims=2),
        )
        sense = (
            "no force at this instant"
            if b.fmt.is_zero(b.scalar(S), FORCE)
            else "tension (it pulls on its pins)"
            if b.scalar(S) > 0
            else "compression (it pushes on its pins)"
        )
        b.say(
            reason + ", and no friction at those pins: a two-force member. Its moment equation "
            f"about {P} leaves r({P},{Q}) x F({Q}) = 0, so the force at {Q} lies along {P}{Q}, "
            f"and its force equation makes the force at {P} the opposite one: F({Q}) = "
            f"-F({P}) = S e({P},{Q}), the direction known and one unknown magnitude S instead "
            "of four components. Its three equations are used up by that; S enters the "
            "neighbours' equations. From the solution below: S = ",
            Num(S, unit=True),
            f", {sense}; F({Q}) = ",
            Col(FQ, unit=True),
            ".",
        )
        return b.build()
    b.line(rf"&\vec F_{{{sub_q}}} = -\vec F_{{{sub_p}}}:\quad ", Col(total, unit=True, dims=2),
           rf" = \vec F_{{{sub_p}}} + \vec F_{{{sub_q}}}")  # fmt: skip
    offsets = []
    for a, X in ((p, P), (q, Q)):
        if a.moment == 0.0:
            continue
        M = b.value(f"M_f({X}) on {link}", a.moment, "N m")
        magnitude = b.value(f"|F({X})|", float(np.hypot(*a.force)), FORCE)
        b.check("norm", magnitude, FP if a is p else FQ)
        d = b.value(f"d({X})", a.moment / b.scalar(magnitude), "m")
        b.check("quotient", d, M, magnitude)
        b.line(rf"&d_{{{tex.name(X)}}} = \frac{{M_{{f,{tex.name(X)}}}}}{{|\vec F|}} = ",
               Num(d, unit=True))  # fmt: skip
        offsets.append((X, d))
    b.say(
        reason + ": a two-force member, its two forces equal and opposite on one line, F("
        f"{Q}) = -F({P}) (their sum ",
        Col(total, unit=True),
        "). With friction at "
        + " and ".join(X for X, _ in offsets)
        + " that line does not pass through the pin centres: it is tangent to each friction "
        "circle (radius mu r), on the side that opposes the pin's relative rotation, at the "
        "distance |M_f| / |F| = mu r from the centre (",
        *[piece for X, d in offsets for piece in (f"d({X}) = ", Num(d, unit=True), "; ")],
        "signed, counter-clockwise moments positive).",
    )
    return b.build()


def _meet(p1: np.ndarray, u1: np.ndarray, p2: np.ndarray, u2: np.ndarray) -> np.ndarray | None:
    """The point where the lines p1 + t u1 and p2 + s u2 meet, t from t u1 - s u2 = p2 - p1
    (the solver's one 2x2 solve; None: parallel)."""
    if abs(float(cross(u1, u2))) <= 1e-12 * float(np.hypot(*u1) * np.hypot(*u2)):
        return None
    d = p2 - p1
    t, _ = solve_2x2((u1[0], -u2[0]), (u1[1], -u2[1]), (d[0], d[1]))
    return p1 + float(t) * u1


def three_force_step(ctx: LinkageContext, link: str, acting: list[Acting]) -> Step:
    """The three lines of action meet at one point K (or are parallel): (p_i - K) x F_i = 0 for
    each force as solved. Where two lines are known before solving (a load, a weight, a
    frictionless slot's normal, a two-force neighbour's line), K is their intersection, the third
    force's line runs through K, and the force triangle sum F = 0 gives the two unknown
    magnitudes."""
    b = ctx.builder("dynamics.three_force", f"{link}: a three-force member")
    names = ", ".join(a.name for a in acting)
    directions = {a.name: a.direction for a in acting if a.direction is not None}
    known = [a for a in acting if a.name in directions]
    answer = len(known) >= 2 and len(acting) - len(known) <= 1
    K = None
    if answer:
        first, second = known[0], known[1]
        K = _meet(first.through, directions[first.name], second.through, directions[second.name])
    from_known = K is not None  # else the two known lines are parallel
    if K is None:  # from the solution: the first two lines of the solved forces that meet
        K = next(
            (
                c
                for i, a in enumerate(acting)
                for other in acting[i + 1 :]
                if (c := _meet(a.through, a.force, other.through, other.force)) is not None
            ),
            None,
        )
    if K is None:
        b.say(
            f"{link} carries three forces and no couple ({names}): a three-force member. Their "
            "lines of action are parallel here (they meet at infinity), so the force triangle "
            "closes along one direction."
        )
        return b.build()
    point = b.value(f"K({link})", K, "m")
    b.line(rf"&K_{{{tex.name(link)}}} = ", Pt(point), r"\,\mathrm{m}")
    for a in acting:
        arm = b.value(f"r(K,{a.name})", a.through - K, "m")
        F = b.value(f"{a.name} on {link}", a.force, FORCE)
        size = float(np.hypot(*(a.through - K)) * np.hypot(*a.force))
        moment = b.value(
            f"r(K,{a.name}) x {a.name}", float(cross(a.through - K, a.force)), "N m",
            reference=size,
        )  # fmt: skip
        b.check("cross", moment, arm, F)
        scalar, symbol = force_symbol(a.name, vector=False), force_symbol(a.name)
        b.line(rf"&\vec r_{{K,{scalar}}} \times {symbol} = ", Col(arm, dims=2), r" \times ",
               Col(F, dims=2), " = ", Num(moment, unit=True))  # fmt: skip
    words = (
        f"{link} carries three forces and no couple ({names}): a three-force member. In "
        "equilibrium their lines of action meet at one point K (the moments about the meeting "
        "point of two of them leave the third no arm)"
    )
    lines = [a for a in acting if a.moment != 0.0]
    if lines:
        words += (
            "; with friction at "
            + ", ".join(a.name for a in lines)
            + " the pin's line is tangent to its friction circle, not through its centre"
        )
    if from_known:
        words += (
            f". The lines of {first.name} and {second.name} are known before solving, so K is "
            "where they meet"
        )
        rest = [a for a in acting if a.name not in directions]
        if rest and float(np.hypot(*(K - rest[0].through))) > 0.0:
            directions[rest[0].name] = K - rest[0].through
            words += f", and {rest[0].name} runs through K"
        unknowns = [a for a in acting if not a.whole]
        if len(unknowns) == 2 and all(a.name in directions for a in unknowns):
            b.say(words + "; the force triangle then gives the magnitudes.")
            _force_triangle(b, link, acting, unknowns, directions)
            b.say(
                "Each line runs through K as solved ((r_K x F) = 0 for every force above), "
                "so the equilibrium equations below give the same forces."
            )
            return b.build()
    b.say(
        words + ". Checked with the solved forces: each one's moment about K is zero, K = ",
        Col(point, unit=True),
        ".",
    )
    return b.build()


def _force_triangle(
    b: StepBuilder,
    link: str,
    acting: list[Acting],
    unknowns: list[Acting],
    directions: dict[str, np.ndarray],
) -> None:
    """sum F = 0 with the forces known in full moved right and the two others s_i u_i along
    their unit directions u_i: two equations for s_1, s_2 (the solver's values along u_i)."""
    units = {}
    for a in unknowns:
        u = directions[a.name] / float(np.hypot(*directions[a.name]))
        units[a.name] = b.value(f"u({a.name})", u, "")
    whole = [a for a in acting if a.whole]
    rhs = b.value("b(sum F)", -sum((a.force for a in whole), np.zeros(2)), FORCE)
    b.check("sum", rhs, *[-Ref(f"{a.name} on {link}") for a in whole])
    rows: list[list[Ref]] = []
    right: list[Ref] = []
    for k, axis in enumerate("xy"):
        row = []
        for a in unknowns:
            c = b.value(f"u_{axis}({a.name})", b.vector(units[a.name])[k], "")
            b.check("sum", c, units[a.name][k])
            row.append(c)
        rows.append(row)
        side = b.value(f"b_{axis}", b.vector(rhs)[k], FORCE)
        b.check("sum", side, rhs[k])
        right.append(side)
    present_solution(
        b,
        [
            Unknown(
                f"s({a.name})",
                rf"s_{{{force_symbol(a.name, vector=False)}}}",
                f"s({a.name})",
                FORCE,
                float(a.force @ b.vector(units[a.name])),
            )
            for a in unknowns
        ],
        rows,
        right,
        "sum F: ",
    )
