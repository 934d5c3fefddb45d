"""Worked solution of a point M moving along a path fixed in a moving link (seed 003).

For each moving point, at the scene's instant t:

- the time law s(t) and its derivatives (exact, sympy), and M's place on the path;
- transport: the carrier's point coinciding with M, v_tr = v_A + omega x r_AM and
  a_tr = a_A + alpha x r_AM - omega^2 r_AM, with its tangential and normal parts;
- relative: v_rel = s' tau along the path tangent (no carrier rate in it),
  a_rel = s'' tau + (s'^2 / R) n, tangential and normal (towards the centre of the arc);
- Coriolis: a_cor = 2 omega_carrier x v_rel, or why it is zero (the carrier translates);
- v = v_tr + v_rel and a = a_tr + a_rel + a_cor;
- on an arc, the times at which M is opposite its start (s = pi R) and back at it (s = 2 pi R),
  only where the arc reaches there: a groove (``sweep_deg`` < 360) ends, and M leaves it there.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
import sympy
from scipy.optimize import brentq

from solver.kinematics.relative_motion import MovingPointMotion, path_radius
from solver.kinematics.rigid import normal_acceleration, omega_cross
from solver.model.laws import parse_time_law
from solver.model.scene import MovingPoint
from solver.solutions import latex as tex
from solver.solutions.builder import Source, StepBuilder
from solver.solutions.equation import (
    TIMES,
    Alt,
    Boxed,
    Col,
    Equation,
    Num,
    Paren,
    Piece,
    Pt,
    Ref,
    Sym,
    ZCross,
    latex_only,
)
from solver.solutions.format import latex_unit
from solver.solutions.linkage import (
    ACCELERATION,
    V0,
    VELOCITY,
    LinkageContext,
    a_vec,
    al_vec,
    omega_squared,
    omega_squared_line,
    origin,
    put_motion,
    r_vec,
    split_part,
    v_vec,
    w_vec,
)
from solver.solutions.model import Step

EVENT_HORIZON = 60.0  # s: the event search looks this far ahead (the /events default t_max)
EVENT_SAMPLES = 6001


@dataclass(frozen=True)
class Carrier:
    """A turning link that carries a moving point: its rates now and their paths in the
    response (``source('omega')``, ``source('alpha')``)."""

    link: str
    omega: float
    alpha: float
    source: Callable[[str], Source | None]


@dataclass(frozen=True)
class TransportTerms:
    """The keys of v_tr = v_A + omega x r_AM (a_tr = a_A + alpha x r_AM - omega^2 r_AM): A's
    motion (``base``), the carrier's rates, r_AM and the rotation's terms."""

    origin: str  # the carrier's point A
    base: str
    omega: str
    r: str
    rotation: str  # omega x r (velocity) or alpha x r (acceleration)
    alpha: str = ""
    normal: str = ""
    omega2: str = ""  # omega^2, the factor of the normal term


def transport_terms(
    b: StepBuilder,
    ctx: LinkageContext,
    carrier: Carrier,
    pair: tuple[str, str],
    r_np: np.ndarray,
    order: int,
    suffix: str = "",
) -> TransportTerms:
    """v_A, omega and omega x r_AM (a_A, omega, alpha, alpha x r_AM and -omega^2 r_AM) with
    r_AM = ``r_np``, A and M the ``pair``: the terms of the transport motion, put in ``b``."""
    a, m = pair
    base = put_motion(b, ctx, a, order)
    w = b.put(f"omega({carrier.link})", carrier.omega, "rad/s", carrier.source("omega"))
    if order == VELOCITY:
        r = b.put(f"r({a},{m})", r_np, "m")
        wxr = b.put(f"omega x r{suffix}", omega_cross(carrier.omega, r_np), "m/s")
        return TransportTerms(a, base, w, r, wxr)
    al = b.put(f"alpha({carrier.link})", carrier.alpha, "rad/s^2", carrier.source("alpha"))
    r = b.put(f"r({a},{m})", r_np, "m")
    t = b.put(f"alpha x r{suffix}", omega_cross(carrier.alpha, r_np), "m/s^2")
    n = b.put(f"normal{suffix}", normal_acceleration(carrier.omega, r_np), "m/s^2")
    w2 = omega_squared(b, carrier.link, Ref(w), write=False)
    return TransportTerms(a, base, w, r, t, al, n, w2.key)


def check_transport(b: StepBuilder, terms: TransportTerms, total: str | Ref) -> None:
    """total = v_A + omega x r (a_A + alpha x r - omega^2 r), each term checked."""
    if not terms.alpha:
        b.check("cross", terms.rotation, terms.omega, terms.r)
        b.check("sum", total, terms.base, terms.rotation)
        return
    b.check("cross", terms.rotation, terms.alpha, terms.r)
    b.check("product", terms.normal, terms.omega2, terms.r, factor=-1.0)
    b.check("sum", total, terms.base, terms.rotation, terms.normal)


@dataclass(frozen=True)
class LawValues:
    """t, s(t), s'(t) and s''(t)."""

    t: Ref
    s: Ref
    s_dot: Ref
    s_ddot: Ref


@dataclass(frozen=True)
class ArcValues:
    """M = C + R (cos psi, sin psi): the centre C, R, psi and r_CM."""

    center: Ref
    radius: Ref
    psi: Ref
    r: Ref


@dataclass(frozen=True)
class LineValues:
    """M = P_0 + s u: the start P_0, u and r_P0M."""

    start: Ref
    u: Ref
    r: Ref


@dataclass(frozen=True)
class TransportParts:
    """a_tr's tangential and normal parts (along and across v_tr), v_tr and the check
    a_tr^n . v_tr = 0."""

    tangential: Ref
    normal: Ref
    velocity: Ref
    dot: Ref


@dataclass(frozen=True)
class RelativeAcceleration:
    """a_rel = s'' tau + (s'^2 / R) n: s', s'', tau, n, 1/R and the two parts."""

    s_dot: Ref
    s_ddot: Ref
    tau: Ref
    n: Ref
    curvature: Ref
    tangential: Ref
    normal: Ref


BETWEEN = Sym(r", \quad ", ", ")  # between the equations of a row


class MovingPointSteps:
    def __init__(self, ctx: LinkageContext, mp: MovingPoint, motion: MovingPointMotion) -> None:
        self.ctx = ctx
        self.mp = mp
        self.m = motion
        self.name = mp.name
        self.n = tex.name(mp.name)
        self.carrier = mp.link

    def src(self, field: str) -> tuple[str, ...]:
        return ("moving_points", self.name, field)

    def put(self, b: StepBuilder, name: str) -> Ref:
        """One part of v = v_tr + v_rel or a = a_tr + a_rel + a_cor of M (``name`` a field of
        the motion, e.g. 'transport_velocity'), with its path in the response."""
        key, unit = split_part(name, self.name)
        return b.value(key, getattr(self.m, name), unit, self.src(name))

    def part(self, kind: str, order: str) -> str:
        """The symbol of a part of M's motion: '\\vec{v}_{M,\\mathrm{tr}}' (``kind`` 'v', ``order``
        'tr')."""
        return rf"\vec{{{kind}}}_{{{self.n},\mathrm{{{order}}}}}"

    @property
    def turn(self) -> float:
        """+1 for an arc run counter-clockwise, -1 clockwise."""
        return 1.0 if self.mp.path.direction == "ccw" else -1.0

    # --- the time law and the place on the path -------------------------------------------------

    def law_step(self) -> Step:
        """s = s(t), s' = ds/dt and s'' = d^2 s/dt^2 at the instant, then M on its path."""
        b = self.ctx.builder("relative.law", f"Moving point {self.name}: time law and position")
        law = self.law_values(b)
        self.write_law(b, law)
        m = b.value(f"pos({self.name})", self.m.position, "m", self.src("position"))
        if self.mp.path.type == "arc":
            self.write_arc(b, m, self.arc_values(b, m))
        else:
            self.write_line(b, law, m, self.line_values(b, law, m))
        return b.build()

    def law_values(self, b: StepBuilder) -> LawValues:
        """t, s(t), s'(t) and s''(t), the solver's numbers with their paths."""
        return LawValues(
            b.value("t", self.ctx.scene.time, "s"),
            b.value("s", float(self.m.s), "m", self.src("s")),
            b.value("s_dot", float(self.m.s_dot), "m/s", self.src("s_dot")),
            b.value("s_ddot", float(self.m.s_ddot), "m/s^2", self.src("s_ddot")),
        )

    def write_law(self, b: StepBuilder, v: LawValues) -> None:
        """s(t), s'(t), s''(t) as formulas, then their values at t."""
        law, digits = parse_time_law(self.mp.s_law), self.ctx.fmt.digits
        b.line(
            rf"&s(t) = {tex.law(law.expression, digits)}, \quad \dot{{s}}(t) = "
            rf"{tex.law(law.first_derivative, digits)}, \quad \ddot{{s}}(t) = "
            rf"{tex.law(law.second_derivative, digits)}"
        )
        now = (
            Equation.of("t", Num(v.t, unit=True)),
            Sym(r": \quad ", ": "),
            Equation.of("s", Num(v.s, unit=True)),
            BETWEEN,
            Equation.of(Sym(r"\dot{s}", "s-dot"), Num(v.s_dot, unit=True)),
            BETWEEN,
            Equation.of(Sym(r"\ddot{s}", "s-double-dot"), Num(v.s_ddot, unit=True)),
        )
        b.line("&", *now)
        b.say(
            f"{self.name} moves along a path fixed in link {self.carrier}; its arc length from "
            f"{self.mp.path.start} is s(t) = "
            f"{tex.law_text(self.mp.s_law, parse_time_law(self.mp.s_law).expression)} (m). At ",
            *now,
            ".",
        )

    def arc_values(self, b: StepBuilder, m: Ref) -> ArcValues:
        """M = C + R (cos psi, sin psi), psi = psi_0 + theta_carrier +- s / R (psi_0 the drawn
        start's angle about C, + counter-clockwise)."""
        ctx, route = self.ctx, self.mp.path
        assert route.center is not None
        center = ctx.pos(route.center)
        c = b.value(f"pos({route.center})", center, "m", ("points", route.center, "position"))
        radius = path_radius(self.ctx.scene, self.mp)
        r = b.value("R", radius, "m")
        start = ctx.scene.drawn(route.start) - ctx.scene.drawn(route.center)
        theta = float(ctx.analysis.motion.links[self.carrier].theta[0])
        psi = math.atan2(start[1], start[0]) + theta + self.turn * float(self.m.s) / radius
        angle = b.value("angle", psi, "rad")
        d = b.value(f"r({route.center},{self.name})", np.asarray(self.m.position) - center, "m")
        b.check("phasor", d, r, angle)
        b.check("sum", m, c, d)
        return ArcValues(c, r, angle, d)

    def write_arc(self, b: StepBuilder, m: Ref, v: ArcValues) -> None:
        """M = C + R (cos psi, sin psi) with the numbers."""
        route = self.mp.path
        assert route.center is not None
        sense = "counter-clockwise" if self.turn > 0 else "clockwise"
        radius = Equation.of("R", Num(v.radius, unit=True))
        angle = Equation.of(Sym(r"\psi", "psi"), Num(v.psi, unit=True))
        place = Equation.of(
            Sym(self.n, self.name),
            latex_only(Pt(v.center), " + ", Pt(v.r)),
            Boxed((Pt(m, "m"),)),
        )
        centre = tex.name(route.center)
        b.line(
            rf"&\text{{arc about }} {centre}, \; ",
            radius,
            rf", \; \text{{{sense} from }} {tex.name(route.start)}: \; {self.n} = "
            rf"{centre} + R\,(\cos\psi, \sin\psi), \; ",
            angle,
        )
        b.line(place)
        b.say(
            "The path is an arc of radius ",
            radius,
            f" about {route.center}, run {sense} from {route.start}; {self.name} is at the angle ",
            angle,
            " on it: ",
            place,
            ".",
        )

    def line_values(self, b: StepBuilder, law: LawValues, m: Ref) -> LineValues:
        """M = P_0 + s u, u the unit vector from the line's start P_0 towards its second point
        (the path's tangent)."""
        ctx, route = self.ctx, self.mp.path
        start = ctx.pos(route.start)
        s0 = b.value(f"pos({route.start})", start, "m", ("points", route.start, "position"))
        u = b.value("u", self.m.tangent, "")
        d = b.value(f"r({route.start},{self.name})", np.asarray(self.m.position) - start, "m")
        b.check("product", d, law.s, u)
        b.check("sum", m, s0, d)
        return LineValues(s0, u, d)

    def write_line(self, b: StepBuilder, law: LawValues, m: Ref, v: LineValues) -> None:
        """M = P_0 + s u with the numbers."""
        route = self.mp.path
        place = Equation.of(
            Sym(self.n, self.name),
            latex_only(rf"{tex.name(route.start)} + s\,\vec{{u}}"),
            latex_only(Pt(v.start), " + ", Num(law.s), r" \cdot ", Pt(v.u)),
            Boxed((Pt(m, "m"),)),
        )
        b.line(place)
        b.say(
            f"The path is the line from {route.start} towards {route.through} (direction ",
            Pt(v.u),
            "): ",
            place,
            ".",
        )

    # --- velocity -------------------------------------------------------------------------------

    def transport(self, b: StepBuilder, order: int) -> TransportTerms:
        """The terms of v_tr = v_A + omega x r_AM (a_tr = a_A + alpha x r_AM - omega^2 r_AM), A
        the carrier's reference point."""
        a = self.ctx.reference_point(self.carrier)
        carrier = Carrier(
            self.carrier,
            float(self.m.omega_carrier),
            float(self.m.alpha_carrier),
            lambda rate: self.src(f"{rate}_carrier"),
        )
        r_np = np.asarray(self.m.position) - self.ctx.pos(a)
        return transport_terms(b, self.ctx, carrier, (a, self.name), r_np, order)

    def velocity_steps(self) -> list[Step]:
        """v_tr, v_rel and v = v_tr + v_rel of M, one step each."""
        return [
            self.transport_velocity_step(),
            self.relative_velocity_step(),
            self.absolute_velocity_step(),
        ]

    def transport_velocity_step(self) -> Step:
        """v_tr = v_A + omega x r_AM: the velocity of the carrier's point under M."""
        ctx, carrier = self.ctx, self.carrier
        b = ctx.builder("relative.transport_velocity", f"Transport velocity of {self.name}")
        v = self.transport(b, VELOCITY)
        tr = self.put(b, "transport_velocity")
        check_transport(b, v, tr)
        a, w, r = v.origin, Ref(v.omega), Ref(v.r)
        transport = Equation.of(
            latex_only(self.part("v", "tr")),
            (
                Sym(v_vec(a), f"v({a})"),
                " + ",
                Sym(w_vec(carrier), f"omega({carrier})"),
                TIMES,
                Sym(r_vec(a, self.name), f"r({a},{self.name})"),
            ),
            (
                origin(b, ctx, a, Ref(v.base)),
                " + ",
                Alt((ZCross(w, r),), (Col(Ref(v.rotation)),)),
            ),
            Boxed((Col(tr, unit=True),)),
        )
        b.line(transport)
        if b.is_zero(w):
            b.say(
                f"{the_carrier(carrier)} translates at this instant (omega = 0): every point of "
                f"it, including the one under {self.name}, moves like {a}: v_tr = ",
                Col(tr),
                ".",
            )
        else:
            b.say(
                f"Transport velocity: the velocity of the point of {carrier} under {self.name}, ",
                transport,
                ".",
            )
        return b.build()

    def relative_velocity_step(self) -> Step:
        """v_rel = s' tau, tau the path's unit tangent (the carrier's rate does not enter)."""
        b = self.ctx.builder("relative.relative_velocity", f"Relative velocity of {self.name}")
        sd = b.value("s_dot", float(self.m.s_dot), "m/s", self.src("s_dot"))
        t = b.value("tau", self.m.tangent, "")
        rel = self.put(b, "relative_velocity")
        b.check("product", rel, sd, t)
        relative = Equation.of(
            Sym(self.part("v", "rel"), "v_rel"),
            Sym(r"\dot{s}\,\vec{\tau}", "s-dot tau"),
            latex_only(Num(sd), r" \cdot ", Col(t)),
            Boxed((Col(rel, unit=True),)),
        )
        b.line(relative)
        b.say(
            "Relative velocity: along the path's tangent tau = ",
            Col(t),
            " (the direction of increasing s), ",
            relative,
            f". It is the velocity an observer on {self.carrier} sees: the carrier's rate does "
            "not enter it.",
        )
        return b.build()

    def absolute_velocity_step(self) -> Step:
        """v = v_tr + v_rel."""
        b = self.ctx.builder("relative.velocity", f"Absolute velocity of {self.name}")
        tr = self.put(b, "transport_velocity")
        rel = self.put(b, "relative_velocity")
        v = self.put(b, "velocity")
        b.check("sum", v, tr, rel)
        total = Equation.of(
            Sym(v_vec(self.name), f"v({self.name})"),
            (Sym(self.part("v", "tr"), "v_tr"), " + ", Sym(self.part("v", "rel"), "v_rel")),
            (Col(tr), " + ", Col(rel)),
            Boxed((Col(v, unit=True),)),
        )
        b.line(total)
        b.say(total, ".")
        return b.build()

    # --- acceleration ---------------------------------------------------------------------------

    def acceleration_steps(self) -> list[Step]:
        """a_tr, a_rel, a_Cor and a = a_tr + a_rel + a_Cor of M, one step each."""
        return [
            self.transport_acceleration_step(),
            self.relative_acceleration_step(),
            self.coriolis_step(),
            self.absolute_acceleration_step(),
        ]

    def transport_acceleration_step(self) -> Step:
        """a_tr = a_A + alpha x r_AM - omega^2 r_AM, and its parts along and across v_tr."""
        b = self.ctx.builder(
            "relative.transport_acceleration", f"Transport acceleration of {self.name}"
        )
        terms = self.transport(b, ACCELERATION)
        tr = self.put(b, "transport_acceleration")
        check_transport(b, terms, tr)
        self.write_transport_acceleration(b, terms, tr, self.transport_parts(b, tr))
        return b.build()

    def transport_parts(self, b: StepBuilder, tr: Ref) -> TransportParts:
        """a_tr = a_tr^tau + a_tr^n, a_tr^n . v_tr = 0 (the normal part is across v_tr)."""
        tt = b.value(
            "a_tr tangential",
            self.m.transport_tangential,
            "m/s^2",
            self.src("transport_tangential"),
        )
        tn = b.value("a_tr normal", self.m.transport_normal, "m/s^2", self.src("transport_normal"))
        vtr = self.put(b, "transport_velocity")
        normal, velocity = self.m.transport_normal, self.m.transport_velocity
        d = b.value(
            "a_tr normal . v_tr",
            float(np.dot(normal, velocity)),
            "m^2/s^3",
            reference=float(np.hypot(*normal) * np.hypot(*velocity)),
        )
        b.check("sum", tr, tt, tn)
        b.check("dot", d, tn, vtr)
        return TransportParts(tt, tn, vtr, d)

    def write_transport_acceleration(
        self, b: StepBuilder, v: TransportTerms, tr: Ref, parts: TransportParts
    ) -> None:
        """a_tr = a_A + alpha x r - omega^2 r (or that the carrier translates), then its parts
        a_tr^tau and a_tr^n."""
        carrier, a = self.carrier, v.origin
        k, r = tex.name(carrier), Ref(v.r)
        base = origin(b, self.ctx, a, Ref(v.base))
        if not b.is_zero(v.omega):
            omega_squared_line(b, carrier, Ref(v.omega), Ref(v.omega2))
        transport = Equation.of(
            latex_only(self.part("a", "tr")),
            (
                Sym(a_vec(a), f"a({a})"),
                " + ",
                Sym(al_vec(carrier), f"alpha({carrier})"),
                TIMES,
                Sym(r"\vec{r}", "r"),
                Sym(rf" - \omega_{{{k}}}^2\,\vec{{r}}", f" - omega({carrier}) squared r"),
            ),
            latex_only(
                base,
                " + ",
                ZCross(Ref(v.alpha), r),
                " - ",
                Num(Ref(v.omega2)),
                r" \cdot ",
                Col(r),
            ),
            (base, " + ", Col(Ref(v.rotation)), " + ", Col(Ref(v.normal))),
            Boxed((Col(tr, unit=True),)),
            breaks=(3,),
            phantom=r"\vec{a}",
        )
        b.line(transport)
        along, across = (
            Equation.of(latex_only(rf"\vec{{a}}^{{{part}}}_{{{self.n},\mathrm{{tr}}}}"), Col(key))
            for part, key in ((r"\tau", parts.tangential), ("n", parts.normal))
        )
        b.line(
            "&",
            along,
            r", \quad ",
            across,
            r" \quad \text{(along and across } \vec{v}_{\mathrm{tr}}\text{)}",
        )
        if b.is_zero(v.omega) and b.is_zero(v.alpha):
            b.say(
                f"{the_carrier(carrier)} translates (omega = alpha = 0): all its points have "
                f"the acceleration of {a}, so a_tr = a({a}) = ",
                Col(tr),
                ".",
            )
        else:
            b.say("Transport acceleration: ", transport, ".")
        b.say(
            "Its tangential part (along v_tr) is ",
            along,
            " and its normal part (across it) ",
            across,
            ".",
        )

    def relative_acceleration_step(self) -> Step:
        """a_rel = s'' tau + (s'^2 / R) n, n towards the arc's centre (no normal part on a
        line)."""
        b = self.ctx.builder(
            "relative.relative_acceleration", f"Relative acceleration of {self.name}"
        )
        v = self.relative_acceleration_values(b)
        rel = self.put(b, "relative_acceleration")
        b.check("product", v.tangential, v.s_ddot, v.tau)
        b.check("product", v.normal, v.s_dot, v.s_dot, v.curvature, v.n)
        b.check("sum", rel, v.tangential, v.normal)
        self.write_relative_acceleration(b, v, rel)
        return b.build()

    def relative_acceleration_values(self, b: StepBuilder) -> RelativeAcceleration:
        """s', s'', tau, n, 1/R and the parts s'' tau and (s'^2 / R) n of a_rel."""
        curvature = float(self.m.curvature)
        return RelativeAcceleration(
            b.value("s_dot", float(self.m.s_dot), "m/s", self.src("s_dot")),
            b.value("s_ddot", float(self.m.s_ddot), "m/s^2", self.src("s_ddot")),
            b.value("tau", self.m.tangent, ""),
            b.value("n", self.m.normal, ""),
            b.value("1/R", curvature, "1/m" if curvature else ""),
            b.value(
                "a_rel tangential",
                self.m.relative_tangential,
                "m/s^2",
                self.src("relative_tangential"),
            ),
            b.value("a_rel normal", self.m.relative_normal, "m/s^2", self.src("relative_normal")),
        )

    def write_relative_acceleration(
        self, b: StepBuilder, v: RelativeAcceleration, rel: Ref
    ) -> None:
        """a_rel^tau = s'' tau, a_rel^n = (s'^2 / R) n (0 on a line) and their sum."""
        sub, curved = self.n, b.scalar(v.curvature) != 0.0
        tangential = Equation.of(
            latex_only(rf"\vec{{a}}^{{\tau}}_{{{sub},\mathrm{{rel}}}}"),
            Sym(r"\ddot{s}\,\vec{\tau}", "s-double-dot tau"),
            latex_only(Num(v.s_ddot), r" \cdot ", Col(v.tau)),
            Col(v.tangential),
        )
        normal_part = rf"\vec{{a}}^{{n}}_{{{sub},\mathrm{{rel}}}}"
        total = Equation.of(
            Sym(self.part("a", "rel"), "a_rel"),
            latex_only(Col(v.tangential), " + ", Col(v.normal)),
            Boxed((Col(rel, unit=True),)),
        )
        b.line(tangential)
        if curved:
            radius = self.ctx.fmt.latex(1 / b.scalar(v.curvature))
            centripetal = Equation.of(
                latex_only(normal_part),
                Sym(r"\frac{\dot{s}^2}{R}\,\vec{n}", "s-dot squared over R towards the centre"),
                latex_only(r"\frac{", Paren(v.s_dot), f"^2}}{{{radius}}} \\cdot ", Col(v.n)),
                Col(v.normal),
            )
            b.line(centripetal)
            normal: tuple[Piece, ...] = (", normal ", centripetal)
        else:
            normal = (", no normal part on a straight path",)
            b.line(rf"&{normal_part} = {V0} \quad \text{{(straight path)}}")
        b.line(total)
        b.say(
            "Relative acceleration: tangential ",
            tangential,
            " (along the direction of increasing s)",
            *normal,
            "; ",
            total,
            ".",
        )

    def coriolis_step(self) -> Step:
        """a_Cor = 2 omega_carrier x v_rel, or zero where the carrier translates."""
        carrier, omega = self.carrier, float(self.m.omega_carrier)
        b = self.ctx.builder("relative.coriolis", f"Coriolis acceleration of {self.name}")
        w = b.value(f"omega({carrier})", omega, "rad/s", self.src("omega_carrier"))
        vrel = self.put(b, "relative_velocity")
        cor = self.put(b, "coriolis_acceleration")
        b.check("cross", cor, w, vrel, factor=2.0)
        lhs = latex_only(self.part("a", "Cor"))
        formula = Sym(
            rf"2\,{w_vec(carrier)} \times {self.part('v', 'rel')}",
            f"2 omega({carrier}) cross v_rel",
        )
        if b.is_zero(w):
            b.line(
                Equation.of(
                    lhs,
                    formula,
                    (
                        Boxed((V0 + latex_unit("m/s^2"),)),
                        rf" \quad (\omega_{{{tex.name(carrier)}}} = 0)",
                    ),
                )
            )
            b.say(
                f"{the_carrier(carrier)} does not rotate (omega({carrier}) = ",
                Num(w, unit=True),
                "): it translates, so there is no Coriolis acceleration, even if the links that "
                "drive it turn.",
            )
            return b.build()
        half = b.value("omega x v_rel", omega_cross(omega, self.m.relative_velocity), "m/s^2")
        b.check("cross", half, w, vrel)
        coriolis = Equation.of(
            lhs,
            formula,
            ("2 ", Alt((r"\cdot ", ZCross(w, vrel)), ("(0, 0, ", Num(w), ") cross ", Col(vrel)))),
            latex_only(r"2 \cdot ", Col(half)),
            Boxed((Col(cor, unit=True),)),
        )
        b.line(coriolis)
        b.say("Coriolis acceleration: ", coriolis, ".")
        return b.build()

    def absolute_acceleration_step(self) -> Step:
        """a = a_tr + a_rel + a_Cor."""
        b = self.ctx.builder("relative.acceleration", f"Absolute acceleration of {self.name}")
        tr = self.put(b, "transport_acceleration")
        rel = self.put(b, "relative_acceleration")
        cor = self.put(b, "coriolis_acceleration")
        total = self.put(b, "acceleration")
        b.check("sum", total, tr, rel, cor)
        coriolis = Alt((V0,), (Col(cor),)) if b.is_zero(cor) else Col(cor)
        acceleration = Equation.of(
            Sym(a_vec(self.name), f"a({self.name})"),
            (
                Sym(self.part("a", "tr"), "a_tr"),
                " + ",
                Sym(self.part("a", "rel"), "a_rel"),
                " + ",
                Sym(self.part("a", "Cor"), "a_Cor"),
            ),
            (Col(tr), " + ", Col(rel), " + ", coriolis),
            Boxed((Col(total, unit=True),)),
        )
        b.line(acceleration)
        b.say(acceleration, ".")
        return b.build()

    # --- events ---------------------------------------------------------------------------------

    def event_step(self) -> Step | None:
        """s(t_e) = pi R (M opposite its start), s(t_e) = 2 pi R (M back at its start) and, on a
        groove of sweep theta < 2 pi, s(t_e) = theta R (M at the groove's end, where it leaves
        it), each for the first t_e > 0 (``first_time_at``): only the events within the path
        (``arc_events``). None on a line or if none is reached."""
        route = self.mp.path
        if route.type != "arc":
            return None
        law = parse_time_law(self.mp.s_law)
        in_math = sympy.lambdify(sympy.Symbol("t"), law.expression, "math")

        def s_of_t(t: float) -> float:  # where math raises (overflow), the law's inf or nan
            try:
                return float(in_math(t))
            except (OverflowError, ValueError, ZeroDivisionError):
                return law.value(t)

        radius = path_radius(self.ctx.scene, self.mp)
        events = arc_events(route.sweep_deg, route.start)
        title = (
            f"When {self.name} reaches the far end and its start"
            if route.sweep_deg >= 360.0
            else f"When {self.name} reaches the end of its groove"
        )
        b = self.ctx.builder("relative.event", title)
        r = b.value("R", radius, "m")
        pi = b.value("pi", math.pi, "")
        found = False
        for k, (turns, where) in enumerate(events, start=1):
            level = turns * math.pi * radius
            t_e = first_time_at(s_of_t, level)
            if t_e is None:
                continue
            lv = b.value(f"s_{k}", level, "m", reference=level)
            te = b.value(f"t_{k}", t_e, "s")
            b.check("product", lv, pi, r, factor=turns)
            self.write_event(b, turns, where, lv, te)
            found = True
        if found and route.sweep_deg < 360.0:
            b.say(
                f"Past its end (s = {route.sweep_deg / 180.0:g} pi R) {self.name} is off the "
                "groove: no later instant is an event of this path."
            )
        return b.build() if found else None

    def write_event(self, b: StepBuilder, turns: float, where: str, lv: Ref, te: Ref) -> None:
        """s(t) = k pi R solved for its first root t_k."""
        law = parse_time_law(self.mp.s_law)
        factor = "" if turns == 1.0 else f"{turns:g}"
        level = Equation.of("s(t)", latex_only(rf"{factor}\pi R"), Num(lv, unit=True))
        root = Equation.of(
            Sym(
                tex.law(law.expression, self.ctx.fmt.digits),
                tex.law_text(self.mp.s_law, law.expression),
            ),
            Num(lv),
        )
        time = Equation.of("t", Boxed((Num(te, unit=True),)))
        then = r" \;\Rightarrow\; "
        b.line("&", level, then, root, then, time)
        b.say(
            f"{self.name} is {where} when ",
            level,
            ": the first positive root of ",
            root,
            " is ",
            time,
            ".",
        )

    def steps(self) -> list[Step]:
        event = self.event_step()
        return [
            self.law_step(),
            *self.velocity_steps(),
            *self.acceleration_steps(),
            *([event] if event is not None else []),
        ]


def the_carrier(link: str) -> str:
    """'The carrier' for a link named so, else 'The carrier <link>' (not 'The carrier
    carrier')."""
    return "The carrier" if link.lower() == "carrier" else f"The carrier {link}"


def arc_events(sweep_deg: float, start: str) -> list[tuple[float, str]]:
    """The events of a point on an arc of ``sweep_deg`` degrees from ``start``, as (s / (pi R),
    what happens there), only those within the arc: opposite the start (s = pi R) where the arc
    goes beyond it, back at the start (s = 2 pi R) on a whole circle, and the end of a groove
    (s = theta R, theta < 2 pi), where the point leaves the path."""
    if sweep_deg >= 360.0:
        return [
            (1.0, "opposite its start (half a turn, s = pi R)"),
            (2.0, f"back at {start} (a full turn, s = 2 pi R)"),
        ]
    end = sweep_deg / 180.0
    leaves = f"at the end of its groove ({sweep_deg:g} deg, s = {end:g} pi R) and leaves it"
    if sweep_deg == 180.0:
        leaves = (
            "at the end of its semicircular groove, opposite its start (s = pi R), and leaves it"
        )
    opposite = [(1.0, "opposite its start (half a turn, s = pi R)")] if end > 1.0 else []
    return [*opposite, (end, leaves)]


def first_time_at(s_of_t: Callable[[float], float], level: float) -> float | None:
    """The first t in [0, EVENT_HORIZON] with s(t) = level: a sign change of s(t) - level on
    EVENT_SAMPLES points, then Brent's method; None without one."""
    grid = np.linspace(0.0, EVENT_HORIZON, EVENT_SAMPLES)
    values = np.array([float(s_of_t(float(t))) for t in grid]) - level
    crossing = np.nonzero(np.sign(values[1:]) * np.sign(values[:-1]) <= 0)[0]
    if crossing.size == 0:
        return None
    k = int(crossing[0])
    root = brentq(lambda t: float(s_of_t(t)) - level, grid[k], grid[k + 1], xtol=1e-14, rtol=1e-15)
    return float(root)


def moving_point_steps(ctx: LinkageContext) -> list[Step]:
    """The composite-motion steps of every moving point of the scene (none without them)."""
    moving = getattr(ctx.analysis, "moving_points", {}) or {}
    out: list[Step] = []
    for mp in ctx.scene.moving_points:
        if mp.name in moving:
            out += MovingPointSteps(ctx, mp, moving[mp.name]).steps()
    return out
