"""The relative-velocity (vector) method for planar linkages, in the form of seed 000.

The solver's plan gives the solving order, link by link. For each group the steps write the
equations a textbook writes:

- a driven link: v_B = v_A + omega x r_AB (and a_B = a_A + alpha x r_AB - omega^2 r_AB);
- a dyad point X on two loci: X seen from each side. Through a link L with a known point C,
  v_X = v_C + omega_L x r_CX (omega_L unknown); in a slot of a guide g,
  v_X = v_transport + v_rel with v_rel = s_dot u along the slot (s_dot unknown). "Geometric
  connection = relative connection" gives two component equations, solved for the two unknowns;
- a slotted lever turning about Q whose slot carries the known pin P:
  v_P = v_Q + omega_lever x r_QP + s_dot u, unknown omega_lever and s_dot;
- at every slot, the acceleration adds the Coriolis term 2 omega_guide x v_rel, computed with the
  guide's angular velocity and the relative velocity, or stated to be zero and why;
- a link known from two points: omega = (r x (v_S - v_F)) / |r|^2; every other point of a link by
  the rigid-body formulas; then the velocity and acceleration poles of every moving link.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from solver.kinematics.rigid import omega_cross, perp
from solver.position.constraints import ConstraintSystem, KnownPoses
from solver.position.topology import (
    CircleSpec,
    DriverStep,
    DyadStep,
    GuidedStep,
    LineSpec,
    NewtonStep,
    PlanStep,
    TwoPointStep,
)
from solver.solutions import latex as tex
from solver.solutions.builder import (
    StepBuilder,
    Unknown,
    linear_latex,
    linear_text,
    present_solution,
)
from solver.solutions.equation import (
    Boxed,
    Col,
    Frac,
    Num,
    Ref,
    ZCol,
    ZCross,
    joined,
)
from solver.solutions.format import Formatter, latex_unit
from solver.solutions.groups import solution_group
from solver.solutions.linkage import (
    ACCELERATION,
    MOTION,
    V0,
    VELOCITY,
    LinkageContext,
    SlotMotion,
    a_sym,
    a_vec,
    acceleration_pole_step,
    al_vec,
    fixed_points_step,
    omega_squared,
    origin,
    put_motion,
    r_vec,
    rigid_acceleration_step,
    rigid_velocity_step,
    v_vec,
    velocity_pole_step,
    w_sym,
    w_vec,
)
from solver.solutions.model import Step


@dataclass
class Term:
    """coefficient * unknown, the coefficient being k x r (a rotation) or u (a slot direction)."""

    unknown: Unknown
    kind: str  # "perp" (coefficient k x r) or "dir" (coefficient u)
    of: str  # the value key of r or u
    of_value: np.ndarray
    of_unit: str

    @property
    def coefficient(self) -> np.ndarray:
        return perp(self.of_value) if self.kind == "perp" else self.of_value


@dataclass
class Side:
    """One way of writing the motion of a point: known vector + terms in the unknowns."""

    known_key: str
    known: np.ndarray
    unit: str
    terms: list[Term] = field(default_factory=list)


def side_column(b: StepBuilder, side: Side) -> str:
    """The side as a column of linear expressions in its unknowns."""
    fmt = b.fmt
    entries = []
    for i in range(2):
        terms = [(float(t.coefficient[i]), t.unknown.latex) for t in side.terms]
        reference = max([abs(float(side.known[i]))] + [abs(c) for c, _ in terms])
        known = fmt.clean(float(side.known[i]), side.unit, float(np.hypot(*side.known)))
        entries.append(linear_latex(fmt, known, terms, reference))
    return tex.column([*entries, "0"])


def side_text(b: StepBuilder, side: Side) -> str:
    fmt = b.fmt
    entries = []
    for i in range(2):
        terms = [(float(t.coefficient[i]), t.unknown.text) for t in side.terms]
        reference = max([abs(float(side.known[i]))] + [abs(c) for c, _ in terms])
        known = fmt.clean(float(side.known[i]), side.unit, float(np.hypot(*side.known)))
        entries.append(linear_text(fmt, known, terms, reference))
    return "(" + ", ".join(entries) + ")"


def rotation_column(b: StepBuilder, r: np.ndarray, rate: str) -> str:
    """k x r times the unknown rate, (-r_y w, r_x w, 0), as a column in LaTeX."""
    size = float(np.hypot(*r))
    return tex.column(
        [
            linear_latex(b.fmt, None, [(-float(r[1]), rate)], size),
            linear_latex(b.fmt, None, [(float(r[0]), rate)], size),
            "0",
        ]
    )


def relative_line(
    b: StepBuilder, letter: str, sub: str, slide: str, s: Ref, u: Ref, rel: Ref
) -> None:
    """v_rel = s_dot u (a_rel = s_ddot u, ``letter`` 'a') along the slot, with the numbers."""
    b.check("product", rel, s, u)
    b.line(
        rf"&\vec{{{letter}}}_{{{sub},\mathrm{{rel}}}} = {slide}\,\vec{{u}} = ",
        Num(s),
        r" \cdot ",
        Col(u),
        " = ",
        Col(rel, unit=True),
    )


def _register_side(b: StepBuilder, side: Side) -> None:
    b.put(side.known_key, side.known, side.unit)
    for t in side.terms:
        b.put(t.of, t.of_value, t.of_unit)


@dataclass(frozen=True)
class KnownAcceleration:
    """a_C - omega_L^2 r_CX, the known part of a_X through link L (``value``, put as ``key``),
    and the keys of its terms a_C, omega_L^2, r_CX and -omega_L^2 r_CX."""

    key: str
    value: np.ndarray
    base: str
    omega2: str
    r: str
    normal: str


def circle_known_acceleration(
    b: StepBuilder, ctx: LinkageContext, spec: CircleSpec, point: str, r_np: np.ndarray
) -> KnownAcceleration:
    """a_C - omega_L^2 r_CX with its terms, each piece of arithmetic checked."""
    link, center = spec.link, spec.center
    omega = ctx.omega(link)
    base = put_motion(b, ctx, center, ACCELERATION)
    w = b.value(f"omega({link})", omega, "rad/s", ctx.link_source(link, "omega"))
    w2 = omega_squared(b, link, w)
    r = b.put(f"r({center},{point})", r_np, "m")
    n = b.put(f"normal({center},{point})", -(omega**2) * r_np, "m/s^2")
    value = ctx.acc(center) - omega**2 * r_np
    key = b.put(f"known({point} via {link})", value, "m/s^2")
    b.check("product", n, w2, r, factor=-1.0)
    b.check("sum", key, base, n)
    return KnownAcceleration(key, value, base, w2.key, r, n)


@dataclass(frozen=True)
class TwoPointRate:
    """The keys of omega = (r x (v_S - v_F))_z / |r|^2 between the points F and S (``first``,
    ``second``): d = v_S - v_F, (r x d)_z, |r|^2 and the rate."""

    first: str
    second: str
    diff: str
    cross: str
    r2: str
    value: str


def component_equation(
    b: StepBuilder,
    i: int,
    terms: list[tuple[Term, float]],
    sides: tuple[Side, Side],
    prefix: str,
) -> tuple[list[str], str]:
    """Component i of left = right with the unknowns to the left: sum_j c_ij x_j = b_i,
    c_ij = +-(k x r)_i or +-u_i, b_i = right_i - left_i, written with a positive lead.
    Returns the keys of the coefficients and of b_i."""
    left, right = sides
    raw = [sign * float(t.coefficient[i]) for t, sign in terms]
    largest = max(abs(c) for c in raw)
    leading = next((c for c in raw if not b.fmt.is_zero(c, "", largest)), 1.0)
    row_sign = -1.0 if leading < 0 else 1.0
    coefficients = []
    for j, (t, sign) in enumerate(terms):
        key = b.put(f"{prefix}c{i + 1}{j + 1}", row_sign * raw[j], t.of_unit)
        coefficients.append(key)
        if t.kind == "perp":  # k x r = (-r_y, r_x)
            factor = row_sign * sign * (-1.0 if i == 0 else 1.0)
            b.check("product", key, f"{t.of}[{1 - i}]", factor=factor)
        else:
            b.check("product", key, f"{t.of}[{i}]", factor=row_sign * sign)
    rhs = b.put(f"{prefix}b{i + 1}", row_sign * float(right.known[i] - left.known[i]), left.unit)
    sum_of = (f"{right.known_key}[{i}]", f"-{left.known_key}[{i}]")
    b.check("sum", rhs, *sum_of, factor=row_sign)
    return coefficients, rhs


def bmatrix(fmt: Formatter, rows: list[list[float]]) -> str:
    """A matrix in LaTeX; entries at rounding-noise level next to the largest are shown as 0."""
    largest = max((abs(x) for row in rows for x in row), default=0.0)
    body = r" \\ ".join(" & ".join(fmt.latex(x, reference=largest) for x in row) for row in rows)
    return r"\begin{bmatrix} " + body + r" \end{bmatrix}"


class VectorMethod:
    """Builds the steps of the relative-velocity method for one linkage."""

    def __init__(self, ctx: LinkageContext) -> None:
        self.ctx = ctx
        self.solved_omega: set[str] = set()
        self.solved_alpha: set[str] = set()

    # --- helpers --------------------------------------------------------------------------------

    def unknown_rate(self, link: str, order: int) -> Unknown:
        ctx = self.ctx
        if order == VELOCITY:
            return Unknown(
                f"omega({link})",
                w_sym(link),
                f"omega({link})",
                "rad/s",
                ctx.omega(link),
                ctx.link_source(link, "omega"),
                f"the angular velocity of link {link}",
            )
        return Unknown(
            f"alpha({link})",
            a_sym(link),
            f"alpha({link})",
            "rad/s^2",
            ctx.alpha(link),
            ctx.link_source(link, "alpha"),
            f"the angular acceleration of link {link}",
        )

    def unknown_slide(self, point: str, guide: str, order: int, two_slots: bool) -> Unknown:
        ctx = self.ctx
        sliding = ctx.slot(guide, point)
        u = sliding.direction
        sub = tex.name(point) + (r",\," + tex.name(guide) if two_slots else "")
        suffix = f"{point} in {guide}" if two_slots else point
        if order == VELOCITY:
            return Unknown(
                f"s_dot({point}/{guide})",
                rf"\dot{{s}}_{{{sub}}}",
                f"s-dot({suffix})",
                "m/s",
                float(np.dot(sliding.relative_velocity, u)),
                None,
                f"the signed sliding rate of {point} along the slot of {guide} (positive in the "
                "slot's direction u)",
            )
        assert sliding.relative_acceleration is not None
        return Unknown(
            f"s_ddot({point}/{guide})",
            rf"\ddot{{s}}_{{{sub}}}",
            f"s-double-dot({suffix})",
            "m/s^2",
            float(np.dot(sliding.relative_acceleration, u)),
            None,
            f"the relative acceleration of {point} along the slot of {guide}",
        )

    # --- the method -----------------------------------------------------------------------------

    def steps(self) -> list[Step]:
        ctx = self.ctx
        out: list[Step] = []
        for order in (VELOCITY, ACCELERATION):
            fixed = fixed_points_step(ctx, order)
            if fixed is not None:
                out.append(fixed)
            for step in ctx.analysis.plan.steps:
                out += self.plan_step(step, order)
        out += [velocity_pole_step(ctx, link) for link in ctx.scene.moving_links]
        out += [acceleration_pole_step(ctx, link) for link in ctx.scene.moving_links]
        return out

    def plan_step(self, step: PlanStep, order: int) -> list[Step]:
        group = solution_group(step)
        if group is not None:
            return group.vector_steps(self, step, order)
        if isinstance(step, DriverStep):
            return self.remaining(
                step.link,
                step.pivot,
                order,
                f"Link {step.link} is driven about the fixed pivot {step.pivot}.",
            )
        if isinstance(step, TwoPointStep):
            return self.two_points(step, order)
        if isinstance(step, GuidedStep):
            return self.guided(step, order)
        assert isinstance(step, NewtonStep)
        return self.newton(step, order)

    def remaining(self, link: str, base: str, order: int, reason: str = "") -> list[Step]:
        """The points of ``link`` not shown yet, from ``base`` by the rigid-body formula."""
        ctx = self.ctx
        shown = ctx.shown_velocity if order == VELOCITY else ctx.shown_acceleration
        out = []
        for p in ctx.scene.links[link].points:
            if p in shown or p == base:
                continue
            if order == VELOCITY:
                out.append(rigid_velocity_step(ctx, link, base, p, reason))
            else:
                out.append(rigid_acceleration_step(ctx, link, base, p, reason))
            reason = ""
        shown.add(base)
        return out

    # --- dyads ----------------------------------------------------------------------------------

    def circle_side(self, point: str, spec: CircleSpec, order: int) -> tuple[Step, Side]:
        """X through link L from its known point C: v_X = v_C + omega_L x r_CX (a_X = a_C +
        alpha_L x r_CX - omega_L^2 r_CX), the rate of L unknown."""
        self.ctx.use(spec.center, point)
        if order == VELOCITY:
            return self.circle_velocity_side(point, spec)
        return self.circle_acceleration_side(point, spec)

    def circle_velocity_side(self, point: str, spec: CircleSpec) -> tuple[Step, Side]:
        """v_X = v_C + omega_L x r_CX, omega_L unknown: a column linear in omega_L."""
        ctx, link, center = self.ctx, spec.link, spec.center
        r_np = ctx.pos(point) - ctx.pos(center)
        unknown = self.unknown_rate(link, VELOCITY)
        rkey = f"r({center},{point})"
        b = ctx.builder(
            "velocity.dyad.side",
            f"Velocity of {point} through link {link} ({unknown.text} unknown)",
        )
        vc = put_motion(b, ctx, center, VELOCITY)
        b.put(rkey, r_np, "m")
        side = Side(vc, ctx.vel(center), "m/s", [Term(unknown, "perp", rkey, r_np, "m")])
        base = origin(b, ctx, center, Ref(vc))
        b.line(
            rf"&{v_vec(point)} = {v_vec(center)} + {w_vec(link)} \times "
            rf"{r_vec(center, point)} = ",
            base,
            " + ",
            ZCross(unknown.symbol, Ref(rkey)),
        )
        b.line(
            rf"&\phantom{{{v_vec(point)}}} = ",
            base,
            f" + {rotation_column(b, r_np, unknown.latex)} = {side_column(b, side)}"
            f"{latex_unit('m/s')}",
        )
        b.say(
            f"{point} is a point of link {link}, which also carries {center}: v({point}) = "
            f"v({center}) + omega({link}) cross r({center},{point}) = ",
            Col(Ref(vc)),
            " + ",
            ZCross(unknown.symbol, Ref(rkey)),
            f" = {side_text(b, side)} m/s, with {unknown.text} unknown.",
        )
        return b.build(), side

    def circle_acceleration_side(self, point: str, spec: CircleSpec) -> tuple[Step, Side]:
        """a_X = a_C + alpha_L x r_CX - omega_L^2 r_CX, alpha_L unknown: the known part
        a_C - omega_L^2 r_CX plus a column linear in alpha_L."""
        ctx, link, center = self.ctx, spec.link, spec.center
        r_np = ctx.pos(point) - ctx.pos(center)
        unknown = self.unknown_rate(link, ACCELERATION)
        b = ctx.builder(
            "acceleration.dyad.side",
            f"Acceleration of {point} through link {link} ({unknown.text} unknown)",
        )
        known = circle_known_acceleration(b, ctx, spec, point, r_np)
        terms = [Term(unknown, "perp", known.r, r_np, "m")]
        side = Side(known.key, known.value, "m/s^2", terms)
        self.circle_acceleration_lines(b, point, spec, known, side)
        return b.build(), side

    def circle_acceleration_lines(
        self, b: StepBuilder, point: str, spec: CircleSpec, known: KnownAcceleration, side: Side
    ) -> None:
        """Write a_X = a_C + alpha_L x r_CX - omega_L^2 r_CX, expanded to a column linear in
        alpha_L."""
        link, center, k = spec.link, spec.center, side.terms[0]
        base = origin(b, self.ctx, center, Ref(known.base))
        r, w2, normal = Ref(known.r), Ref(known.omega2), Ref(known.normal)
        again = rf"&\phantom{{{a_vec(point)}}} = "
        b.line(
            rf"&{a_vec(point)} = {a_vec(center)} + {al_vec(link)} \times {r_vec(center, point)}"
            rf" - \omega_{{{tex.name(link)}}}^2\,{r_vec(center, point)}"
        )
        b.line(
            again,
            base,
            " + ",
            ZCross(k.unknown.symbol, r),
            " - ",
            Num(w2),
            r" \cdot ",
            Col(r),
        )
        b.line(
            again,
            base,
            f" + {rotation_column(b, k.of_value, k.unknown.latex)} + ",
            Col(normal),
            f" = {side_column(b, side)}{latex_unit('m/s^2')}",
        )
        b.say(
            f"Through link {link}: a({point}) = a({center}) + alpha({link}) cross "
            f"r({center},{point}) - omega({link}) squared r({center},{point}). The normal term -",
            Num(w2),
            " times ",
            Num(r),
            " = ",
            Col(normal),
            f" is known; {k.unknown.text} is unknown: a({point}) = {side_text(b, side)} m/s^2.",
        )

    def transport_step(self, point: str, guide: str, order: int) -> Step | None:
        """v_tr = v_G + omega x r_GX (a_tr = a_G + alpha x r_GX - omega^2 r_GX): the point of
        the moving guide under ``point``; None for a guide fixed in the ground."""
        ctx = self.ctx
        if guide == ctx.scene.ground:
            return None
        sliding = ctx.slot(guide, point)
        g = ctx.reference_point(guide)
        ctx.use(g, point)
        what = MOTION[order][0]
        b = ctx.builder(
            f"{what}.transport", f"Transport {what} of {point} (the point of {guide} under {point})"
        )
        tr = Ref(sliding.put(b, f"transport_{what}", point))
        r = b.value(f"r({g},{point})", ctx.pos(point) - ctx.pos(g), "m")
        w = b.value(f"omega({guide})", ctx.omega(guide), "rad/s", ctx.link_source(guide, "omega"))
        if order == VELOCITY:
            self.transport_velocity(b, (g, point), guide, tr, (r, w))
        else:
            self.transport_acceleration(b, (g, point), guide, tr, (r, w))
        return b.build()

    def transport_velocity(
        self, b: StepBuilder, pair: tuple[str, str], guide: str, tr: Ref, rw: tuple[Ref, Ref]
    ) -> None:
        """v_tr = v_G + omega x r_GX, with r and omega (``rw``) already put."""
        ctx, (g, point), (r, w) = self.ctx, pair, rw
        vg = Ref(put_motion(b, ctx, g, VELOCITY))
        wxr = b.value(
            f"omega x r({g},{point})", omega_cross(ctx.omega(guide), np.asarray(b.vector(r))), "m/s"
        )
        b.check("cross", wxr, w, r)
        b.check("sum", tr, vg, wxr)
        b.line(
            rf"&\vec{{v}}_{{{tex.name(point)},\mathrm{{tr}}}} = {v_vec(g)} + {w_vec(guide)} "
            rf"\times {r_vec(g, point)} = ",
            origin(b, ctx, g, vg),
            " + ",
            ZCross(w, r),
            " = ",
            Col(tr, unit=True),
        )
        b.say(
            f"The transport velocity of {point} is the velocity of the point of {guide} "
            f"that coincides with {point}: v({g}) + omega({guide}) cross r({g},{point}) = ",
            Col(vg),
            " + ",
            Col(wxr),
            " = ",
            Col(tr),
            ".",
        )

    def transport_acceleration(
        self, b: StepBuilder, pair: tuple[str, str], guide: str, tr: Ref, rw: tuple[Ref, Ref]
    ) -> None:
        """a_tr = a_G + alpha x r_GX - omega^2 r_GX, with r and omega (``rw``) already put."""
        ctx, (g, point), (r, w) = self.ctx, pair, rw
        r_np, omega, alpha = np.asarray(b.vector(r)), ctx.omega(guide), ctx.alpha(guide)
        ag = Ref(put_motion(b, ctx, g, ACCELERATION))
        al = b.value(f"alpha({guide})", alpha, "rad/s^2", ctx.link_source(guide, "alpha"))
        t = b.value(f"alpha x r({g},{point})", omega_cross(alpha, r_np), "m/s^2")
        n = b.value(f"normal({g},{point})", -(omega**2) * r_np, "m/s^2")
        w2 = omega_squared(b, guide, w)
        b.check("cross", t, al, r)
        b.check("product", n, w2, r, factor=-1.0)
        b.check("sum", tr, ag, t, n)
        sub, base = tex.name(point) + r",\mathrm{tr}", origin(b, ctx, g, ag)
        b.line(
            rf"&\vec{{a}}_{{{sub}}} = {a_vec(g)} + {al_vec(guide)} \times "
            rf"{r_vec(g, point)} - \omega_{{{tex.name(guide)}}}^2\,{r_vec(g, point)} = ",
            base,
            " + ",
            ZCross(al, r),
            " - ",
            Num(w2),
            r" \cdot ",
            Col(r),
        )
        b.line(
            rf"&\phantom{{\vec{{a}}_{{{sub}}}}} = ",
            base,
            " + ",
            Col(t),
            " + ",
            Col(n),
            " = ",
            Col(tr, unit=True),
        )
        b.say(
            f"The transport acceleration of {point} is the acceleration of the point of "
            f"{guide} under {point}: a({g}) + alpha({guide}) cross r({g},{point}) - "
            f"omega({guide}) squared r({g},{point}) = ",
            Col(ag),
            " + ",
            Col(t),
            " + ",
            Col(n),
            " = ",
            Col(tr),
            ".",
        )

    def coriolis_step(self, point: str, guide: str) -> Step:
        """a_Cor = 2 omega_guide x v_rel, or why it is zero."""
        ctx = self.ctx
        sliding = ctx.slot(guide, point)
        b = ctx.builder("acceleration.coriolis", f"Coriolis acceleration of {point}")
        cor = Ref(sliding.put(b, "coriolis_acceleration", point))
        w = b.value(
            f"omega({guide})", sliding.omega_guide, "rad/s", ctx.link_source(guide, "omega")
        )
        vrel = Ref(sliding.put(b, "relative_velocity", point))
        b.check("cross", cor, w, vrel, factor=2.0)
        formula = (
            rf"\vec{{a}}_{{{tex.name(point)},\mathrm{{Cor}}}} = 2\,{w_vec(guide)} \times "
            rf"\vec{{v}}_{{{tex.name(point)},\mathrm{{rel}}}}"
        )
        if guide == ctx.scene.ground:
            self.coriolis_in_ground(b, sliding, point, formula)
        elif b.is_zero(w) or b.is_zero(vrel):
            self.coriolis_zero_now(b, (point, guide), formula, w, vrel)
        else:
            self.coriolis_product(b, sliding, (point, guide), formula, (cor, w, vrel))
        return b.build()

    def coriolis_in_ground(
        self, b: StepBuilder, sliding: SlotMotion, point: str, formula: str
    ) -> None:
        """a_Cor = 2 . 0 x v_rel = 0 in a slot of the ground (the follower's rate not in it)."""
        ctx = self.ctx
        b.line(
            rf"&{formula} = 2 \cdot {V0} \times \vec{{v}}_{{{tex.name(point)},"
            rf"\mathrm{{rel}}}} = {tex.boxed_result(V0 + latex_unit('m/s^2'))}"
        )
        follower = sliding.joint.follower
        b.say(
            f"The Coriolis acceleration of {point} is zero: the slot is fixed in the ground, "
            "which does not rotate (omega of the guide = 0), so there is no transport "
            "rotation to turn the relative velocity."
        )
        if follower != ctx.scene.ground and not ctx.fmt.is_zero(ctx.omega(follower), "rad/s"):
            b.say(
                f"The angular velocity of link {follower} (omega({follower}) = "
                f"{ctx.fmt.text_value(ctx.omega(follower), 'rad/s')}) does not enter the "
                "Coriolis term: only the guide's rotation does."
            )

    def coriolis_zero_now(
        self, b: StepBuilder, pair: tuple[str, str], formula: str, w: Ref, vrel: Ref
    ) -> None:
        """a_Cor = 0 at this instant: the guide does not turn now, or the point does not slide."""
        point, guide = pair
        zero = tex.boxed_result(V0 + latex_unit("m/s^2"))
        if b.is_zero(w):
            b.line(rf"&{formula} = 2 \cdot ", ZCol(w), r" \times ", Col(vrel), f" = {zero}")
            b.say(
                f"The Coriolis acceleration of {point} is zero at this instant: the guide "
                f"{guide} does not rotate now (omega({guide}) = ",
                Num(w, unit=True),
                ").",
            )
            return
        b.line(rf"&{formula} = 2\,{w_vec(guide)} \times {V0} = {zero}")
        b.say(
            f"The Coriolis acceleration of {point} is zero at this instant: {point} does "
            f"not slide relative to {guide} now (v_rel = 0)."
        )

    def coriolis_product(
        self,
        b: StepBuilder,
        sliding: SlotMotion,
        pair: tuple[str, str],
        formula: str,
        keys: tuple[Ref, Ref, Ref],
    ) -> None:
        """a_Cor = 2 omega x v_rel, omega x v_rel written out (``keys``: a_Cor, omega, v_rel)."""
        (point, guide), (cor, w, vrel) = pair, keys
        half = b.value(
            f"omega x v_rel({point})",
            omega_cross(sliding.omega_guide, sliding.relative_velocity),
            "m/s^2",
        )
        b.check("cross", half, w, vrel)
        b.line(
            rf"&{formula} = 2 \cdot ",
            ZCross(w, vrel),
            r" = 2 \cdot ",
            Col(half),
            " = ",
            Boxed((Col(cor, unit=True),)),
        )
        b.say(
            f"Coriolis acceleration: a_Cor({point}) = 2 omega({guide}) cross v_rel({point})"
            " = 2 (0, 0, ",
            Num(w),
            ") cross ",
            Col(vrel),
            " = 2 times ",
            Col(half),
            " = ",
            Col(cor),
            f". It uses the guide's angular velocity and the relative velocity of {point} "
            "along the slot (not its absolute velocity).",
        )

    def line_side(
        self, point: str, spec: LineSpec, order: int, two_slots: bool
    ) -> tuple[list[Step], Side]:
        """X in the slot of a guide: v_X = v_tr + s' u (a_X = a_tr + s'' u + a_Cor), the
        sliding rate unknown; preceded by the transport (and Coriolis) steps."""
        guide = spec.guide
        transport = self.transport_step(point, guide, order)
        steps = [] if transport is None else [transport]
        if order == ACCELERATION:
            steps.append(self.coriolis_step(point, guide))
        unknown = self.unknown_slide(point, guide, order, two_slots)
        what = MOTION[order][0]
        b = self.ctx.builder(
            f"{what}.dyad.side",
            f"{what.capitalize()} of {point} in the slot of {guide} ({unknown.text} unknown)",
        )
        side, parts = self.slot_side(b, point, guide, order, unknown)
        if order == VELOCITY:
            self.slot_velocity_lines(b, point, guide, side, *parts)
        else:
            self.slot_acceleration_lines(b, point, guide, side, *parts)
        return [*steps, b.build()], side

    def slot_side(
        self, b: StepBuilder, point: str, guide: str, order: int, unknown: Unknown
    ) -> tuple[Side, list[str]]:
        """The known part of X's motion in the slot, v_tr (a_tr + a_Cor), and the term s' u
        (s'' u); returns the side and the keys of v_tr (a_tr and a_Cor)."""
        sliding = self.ctx.slot(guide, point)
        what, unit = MOTION[order]
        ukey = f"u({point}/{guide})"
        known_key, known = f"v_tr({point})", getattr(sliding, f"transport_{what}")
        if order == ACCELERATION:
            known_key, known = f"known({point} in {guide})", known + sliding.coriolis_acceleration
        side = Side(known_key, known, unit, [Term(unknown, "dir", ukey, sliding.direction, "")])
        tr = sliding.put(b, f"transport_{what}", point)
        b.put(ukey, sliding.direction, "")
        if order == ACCELERATION:
            cor = sliding.put(b, "coriolis_acceleration", point)
            b.put(known_key, known, unit)
            b.check("sum", known_key, tr, cor)
            return side, [tr, cor]
        return side, [tr]

    def slot_velocity_lines(
        self, b: StepBuilder, point: str, guide: str, side: Side, tr: str
    ) -> None:
        """Write v_X = v_tr + s' u (v_tr = 0 in a slot of the ground) as a column linear in s'."""
        unknown, ukey, sub = side.terms[0].unknown, side.terms[0].of, tex.name(point)
        fixed = guide == self.ctx.scene.ground
        b.line(
            rf"&{v_vec(point)} = \vec{{v}}_{{{sub},\mathrm{{tr}}}} + "
            rf"\vec{{v}}_{{{sub},\mathrm{{rel}}}}, \quad \vec{{v}}_{{{sub},\mathrm{{rel}}}}"
            rf" = {unknown.latex}\,\vec{{u}}, \quad \vec{{u}} = ",
            Col(Ref(ukey)),
        )
        b.line(
            rf"&\phantom{{{v_vec(point)}}} = ",
            V0 if fixed else Col(Ref(tr)),
            f" + {unknown.latex} ",
            Col(Ref(ukey)),
            f" = {side_column(b, side)}{latex_unit('m/s')}",
        )
        if fixed:
            b.say(
                f"{point} slides in a slot fixed in the ground: its transport velocity is "
                f"zero, so v({point}) = v_rel({point}) = {unknown.text} u, along the slot u = ",
                Num(Ref(ukey)),
                ".",
            )
        else:
            b.say(
                f"{point} slides in the slot of the moving link {guide}: v({point}) = "
                f"v_tr({point}) + v_rel({point}) = ",
                Col(Ref(tr)),
                f" + {unknown.text} times ",
                Num(Ref(ukey)),
                f" = {side_text(b, side)} m/s.",
            )

    def slot_acceleration_lines(
        self, b: StepBuilder, point: str, guide: str, side: Side, tr: str, cor: str
    ) -> None:
        """Write a_X = a_tr + s'' u + a_Cor (a_tr = a_Cor = 0 in a slot of the ground) as a
        column linear in s''."""
        unknown, ukey, sub = side.terms[0].unknown, side.terms[0].of, tex.name(point)
        fixed = guide == self.ctx.scene.ground
        b.line(
            rf"&{a_vec(point)} = \vec{{a}}_{{{sub},\mathrm{{tr}}}} + "
            rf"\vec{{a}}_{{{sub},\mathrm{{rel}}}} + \vec{{a}}_{{{sub},\mathrm{{Cor}}}}, \quad "
            rf"\vec{{a}}_{{{sub},\mathrm{{rel}}}} = {unknown.latex}\,\vec{{u}}"
        )
        b.line(
            rf"&\phantom{{{a_vec(point)}}} = ",
            V0 if fixed else Col(Ref(tr)),
            f" + {unknown.latex} ",
            Col(Ref(ukey)),
            " + ",
            V0 if b.is_zero(cor) else Col(Ref(cor)),
            f" = {side_column(b, side)}{latex_unit('m/s^2')}",
        )
        if fixed:
            b.say(
                f"The slot of {point} is fixed in the ground: the transport and Coriolis "
                f"accelerations are zero, so a({point}) = a_rel({point}) = {unknown.text} u."
            )
        else:
            b.say(
                f"In the slot of {guide}: a({point}) = a_tr({point}) + a_rel({point}) + "
                f"a_Cor({point}) = ",
                Col(Ref(tr)),
                f" + {unknown.text} times ",
                Num(Ref(ukey)),
                " + ",
                Col(Ref(cor)),
                f" = {side_text(b, side)} m/s^2.",
            )

    def equate(
        self, kind: str, title: str, left: Side, right: Side, sentence: str, prefix: str
    ) -> Step:
        """left = right, unknowns to the left: two component equations, solved."""
        b = self.ctx.builder(kind, title)
        _register_side(b, left)
        _register_side(b, right)
        b.line(rf"&{side_column(b, left)} = {side_column(b, right)}")
        b.say(sentence + f" {side_text(b, left)} = {side_text(b, right)}.")
        terms = [(t, 1.0) for t in left.terms] + [(t, -1.0) for t in right.terms]
        rows = [component_equation(b, i, terms, (left, right), prefix) for i in range(2)]
        coefficients = [row[0] for row in rows]
        rhs = [row[1] for row in rows]
        present_solution(b, [t.unknown for t, _ in terms], coefficients, rhs, prefix)
        return b.build()

    def dyad(self, step: DyadStep, order: int) -> list[Step]:
        point = step.point
        out: list[Step] = []
        sides: list[Side] = []
        lines = [s for s in step.loci if isinstance(s, LineSpec)]
        for spec in step.loci:
            if isinstance(spec, CircleSpec):
                side_step, side = self.circle_side(point, spec, order)
                out.append(side_step)
            else:
                more, side = self.line_side(point, spec, order, len(lines) == 2)
                out += more
            sides.append(side)
        what = "velocity" if order == VELOCITY else "acceleration"
        out.append(
            self.equate(
                f"{what}.dyad.solve",
                f"Components of the {what} of {point}: "
                + (
                    "geometric connection = relative connection"
                    if lines
                    else f"the two expressions of the {what} of {point} are equal"
                ),
                sides[0],
                sides[1],
                f"Both expressions give the {what} of the same point {point}; equating their x "
                "and y components gives two equations for the two unknowns:",
                f"{what[0]}:{point}:",
            )
        )
        out += self.dyad_results(step, order)
        return out

    def dyad_results(self, step: DyadStep, order: int) -> list[Step]:
        """The dyad point's velocity (acceleration) with the solved numbers, and slot parts."""
        ctx = self.ctx
        point = step.point
        out = []
        circle = next((s for s in step.loci if isinstance(s, CircleSpec)), None)
        for spec in step.loci:
            if isinstance(spec, CircleSpec):
                (self.solved_omega if order == VELOCITY else self.solved_alpha).add(spec.link)
        if circle is not None:
            if order == VELOCITY:
                out.append(rigid_velocity_step(ctx, circle.link, circle.center, point))
            else:
                out.append(rigid_acceleration_step(ctx, circle.link, circle.center, point))
        else:
            (ctx.shown_velocity if order == VELOCITY else ctx.shown_acceleration).add(point)
        for spec in step.loci:
            if isinstance(spec, LineSpec):
                out.append(self.relative_result(point, spec.guide, order))
        return out

    def relative_result(self, point: str, guide: str, order: int) -> Step:
        """v_rel = s_dot u (a_rel = s_ddot u) with the solved number, and the split of v (a):
        v = v_tr + v_rel, a = a_tr + a_rel + a_Cor."""
        ctx = self.ctx
        sliding = ctx.slot(guide, point)
        unknown = self.unknown_slide(point, guide, order, False)
        what, unit = MOTION[order]
        letter, sub = what[0], tex.name(point)
        b = ctx.builder(f"{what}.relative", f"Relative {what} of {point} in the slot of {guide}")
        s = b.value(unknown.key, unknown.value, unit)
        u = b.value(f"u({point}/{guide})", sliding.direction, "")
        rel = Ref(sliding.put(b, f"relative_{what}", point))
        parts = [Ref(sliding.put(b, f"transport_{what}", point)), rel]
        names = ["tr", "rel"]
        if order == ACCELERATION:
            parts.append(Ref(sliding.put(b, "coriolis_acceleration", point)))
            names.append("Cor")
        total = Ref(sliding.put(b, what, point))
        relative_line(b, letter, sub, unknown.latex, s, u, rel)
        b.check("sum", total, *parts)
        b.line(
            rf"&\vec{{{letter}}}_{{{sub}}} = "
            + " + ".join(rf"\vec{{{letter}}}_{{{sub},\mathrm{{{n}}}}}" for n in names)
            + " = ",
            *joined(" + ", [(Col(k),) for k in parts]),
            " = ",
            Boxed((Col(total, unit=True),)),
        )
        relative = (Num(s, unit=True), " times ", Num(u), " = ", Col(rel))
        if order == VELOCITY:
            b.say(
                f"Relative velocity of {point} along the slot of {guide}: v_rel = ",
                *relative,
                "; with the transport velocity ",
                Col(parts[0]),
                f", v({point}) = ",
                Col(total),
                ".",
            )
        else:
            b.say(
                f"Relative acceleration of {point} along the slot of {guide}: a_rel = ",
                *relative,
                f"; a({point}) = a_tr + a_rel + a_Cor = ",
                *joined(" + ", [(Col(k),) for k in parts]),
                " = ",
                Col(total),
                ".",
            )
        return b.build()

    # --- links known from two points, guided links, Newton groups -------------------------------

    def two_points(self, step: TwoPointStep, order: int) -> list[Step]:
        link, first, second = step.link, step.first, step.second
        solved = self.solved_omega if order == VELOCITY else self.solved_alpha
        out = []
        if link not in solved:
            out.append(self.rate_from_two_points(link, first, second, order))
            solved.add(link)
        out += self.remaining(link, first, order)
        return out

    def rate_from_two_points(self, link: str, first: str, second: str, order: int) -> Step:
        """omega = (r x (v_S - v_F)) / |r|^2  (alpha likewise: the normal term is along r)."""
        ctx = self.ctx
        ctx.use(first, second)
        rate = self.unknown_rate(link, order)
        b = ctx.builder(f"{MOTION[order][0]}.two_points", f"{rate.text} from two known points")
        values = self.two_point_values(b, (first, second), order, rate)
        self.two_point_lines(b, link, order, rate, values)
        return b.build()

    def two_point_values(
        self, b: StepBuilder, pair: tuple[str, str], order: int, rate: Unknown
    ) -> TwoPointRate:
        """v_F, v_S, r = S - F, d = v_S - v_F, (r x d)_z, |r|^2 and the rate, each checked."""
        ctx, (first, second) = self.ctx, pair
        r_np = ctx.pos(second) - ctx.pos(first)
        field_name, unit = MOTION[order]
        x1 = put_motion(b, ctx, first, order)
        x2 = put_motion(b, ctx, second, order)
        r = b.put(f"r({first},{second})", r_np, "m")
        dv = np.asarray(b.vector(x2)) - np.asarray(b.vector(x1))
        diff = b.put(f"d{field_name[0]}", dv, unit)
        dv = np.asarray(b.vector(diff))
        cross = b.put(
            "r x d",
            float(r_np[0] * dv[1] - r_np[1] * dv[0]),
            "",
            reference=float(np.hypot(*r_np) * np.hypot(*dv)),
        )
        r2 = b.put("|r|^2", float(np.dot(r_np, r_np)), "m^2")
        value = b.put(rate.key, rate.value, rate.unit, rate.source)
        b.check("sum", diff, x2, f"-{x1}")
        b.check("cross", cross, r, diff)
        b.check("dot", r2, r, r)
        b.check("quotient", value, cross, r2)
        return TwoPointRate(first, second, diff, cross, r2, value)

    def two_point_lines(
        self, b: StepBuilder, link: str, order: int, rate: Unknown, v: TwoPointRate
    ) -> None:
        """Write omega = (r x (v_S - v_F))_z / |r|^2 (alpha likewise) and its numbers."""
        first, second = v.first, v.second
        r = r_vec(first, second)
        if order == VELOCITY:
            b.line(
                rf"&{v_vec(second)} = {v_vec(first)} + {w_vec(link)} \times {r} \;\Rightarrow\; "
                rf"{rate.latex} = \frac{{({r} \times ({v_vec(second)} - {v_vec(first)}))_z}}"
                rf"{{|{r}|^2}}"
            )
        else:
            b.line(
                rf"&{a_vec(second)} = {a_vec(first)} + {al_vec(link)} \times {r} - \omega^2 {r}"
                rf" \;\Rightarrow\; {rate.latex} = \frac{{({r} \times ({a_vec(second)} - "
                rf"{a_vec(first)}))_z}}{{|{r}|^2}}"
            )
        cross, r2, value = Ref(v.cross), Ref(v.r2), Ref(v.value)
        b.line(f"&{rate.latex} = ", Frac(cross, r2), " = ", Boxed((Num(value, unit=True),)))
        sym = MOTION[order][0][0]
        b.say(
            f"Both {first} and {second} are known points of link {link}. Crossing "
            f"r({first},{second}) with {sym}({second}) - {sym}({first}) = ",
            Col(Ref(v.diff)),
            " "
            + ("" if order == VELOCITY else "(the normal term is along r and drops out) ")
            + "gives ",
            Num(cross),
            "; divided by |r|^2 = ",
            Num(r2, unit=True),
            f": {rate.text} = ",
            Num(value, unit=True),
            ".",
        )

    def guided(self, step: GuidedStep, order: int) -> list[Step]:
        ctx = self.ctx
        rate = self.unknown_rate(step.link, order)
        guide_rate = self.unknown_rate(step.guide, order)
        b = ctx.builder(
            "velocity.guided" if order == VELOCITY else "acceleration.guided",
            f"{rate.text}: link {step.link} cannot turn relative to {step.guide}",
        )
        value = b.value(rate.key, rate.value, rate.unit, rate.source)
        g = b.value(guide_rate.key, guide_rate.value, guide_rate.unit, guide_rate.source)
        b.check("sum", value, g)
        b.line(f"&{rate.latex} = {guide_rate.latex} = ", Boxed((Num(value, unit=True),)))
        b.say(
            f"Link {step.link} slides in a prismatic joint of {step.guide} and cannot turn "
            f"relative to it: {rate.text} = {guide_rate.text} = ",
            Num(value, unit=True),
            ".",
        )
        (self.solved_omega if order == VELOCITY else self.solved_alpha).add(step.link)
        return [b.build(), *self.remaining(step.link, step.point, order)]

    def newton_system(self, step: NewtonStep, order: int, b: StepBuilder) -> None:
        """The group's loop-closure equations differentiated once (twice): J qdot = b_v
        (J qddot = b_a), the unknowns being each link's first-point velocity (acceleration) and
        its omega (alpha), with the solver's own matrix, right-hand side and solution."""
        ctx = self.ctx
        system = ConstraintSystem(ctx.scene, step.links)
        poses = KnownPoses(ctx.analysis.motion.links, ctx.scene).at(0)
        _, J, rhs = system.equations(poses, order)
        dot = r"\dot" if order == VELOCITY else r"\ddot"
        rate = r"\omega" if order == VELOCITY else r"\alpha"
        unknowns, solution = [], []
        for link in step.links:
            first = tex.name(ctx.scene.links[link].points[0])
            pose = poses[link]
            motion = pose.v if order == VELOCITY else pose.a
            turn = pose.omega if order == VELOCITY else pose.alpha
            unknowns += [
                rf"{dot}{{x}}_{{{first}}}",
                rf"{dot}{{y}}_{{{first}}}",
                rf"{rate}_{{{tex.name(link)}}}",
            ]
            solution += [float(motion[0]), float(motion[1]), turn]
        column = tex.column(unknowns)
        b.line(
            f"{bmatrix(ctx.fmt, J.tolist())}{column} = {bmatrix(ctx.fmt, [[x] for x in rhs])}"
            rf"\quad\Rightarrow\quad {column} = {bmatrix(ctx.fmt, [[x] for x in solution])}"
        )

    def newton(self, step: NewtonStep, order: int) -> list[Step]:
        ctx = self.ctx
        what = "velocity" if order == VELOCITY else "acceleration"
        plural = "velocities" if order == VELOCITY else "accelerations"
        b = ctx.builder(f"{what}.newton", f"Links {', '.join(step.links)}: solved together")
        self.newton_system(step, order, b)
        for link in step.links:
            rate = self.unknown_rate(link, order)
            value = b.value(rate.key, rate.value, rate.unit, rate.source)
            b.line(f"&{rate.latex} = ", Num(value, unit=True))
        b.say(
            f"Links {', '.join(step.links)} form no two-joint group with a closed-form solution:"
            f" their {what} equations, linear in the unknown {plural} of their first points and"
            " their angular rates, are solved together (the matrix system above), which gives "
            + "; ".join(f"{k} = {v.display}" for k, v in b.values.items())
            + "."
        )
        out = [b.build()]
        shown = ctx.shown_velocity if order == VELOCITY else ctx.shown_acceleration
        todo = list(step.links)
        while todo:  # carry from points already shown where possible, link after link
            link = next(
                (k for k in todo if any(p in shown for p in ctx.scene.links[k].points)), todo[0]
            )
            todo.remove(link)
            points = ctx.scene.links[link].points
            base = next((p for p in points if p in shown), points[0])
            shown.add(base)
            out += self.remaining(link, base, order)
        return out


def vector_steps(ctx: LinkageContext) -> list[Step]:
    """The velocity, acceleration and pole steps of the vector method (data steps excluded)."""
    return VectorMethod(ctx).steps()
